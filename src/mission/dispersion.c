/* dispersion.c - the values a Monte Carlo run draws (lv_dispersion.h): Philox4x32-10 streams
 * (Salmon et al., SC'11; Random123) keyed by (seed, parameter-name hash, run index), the
 * inverse normal CDF of Wichura (Applied Statistics AS 241, 1988, PPND16), correlation groups
 * through their Cholesky factor; and the per-run copies of dispersed tables.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <Random123/philox.h>
#include <Random123/u01fixedpt.h>

#include "core/status.h"
#include "core/units.h"
#include "mission/dispersion.h"
#include "mission/mission_rt.h"

uint64_t lv_disp_stream(const char *name)
{
    uint64_t h = 14695981039346656037ULL; /* FNV-1a 64 offset basis */
    for (const unsigned char *p = (const unsigned char *)name; *p; p++) {
        h ^= *p;
        h *= 1099511628211ULL; /* FNV prime */
    }
    return h;
}

double lv_disp_uniform(uint64_t seed, uint64_t stream, uint64_t run)
{
    const philox4x32_key_t k = { { (uint32_t)seed, (uint32_t)(seed >> 32) } };
    const philox4x32_ctr_t c = { { (uint32_t)run, (uint32_t)(run >> 32), (uint32_t)stream,
                                   (uint32_t)(stream >> 32) } };
    const philox4x32_ctr_t r = philox4x32(c, k);
    return u01fixedpt_open_open_64_double(((uint64_t)r.v[0] << 32) | r.v[1]);
}

/* AS 241 PPND16: the normal deviate z with Phi(z) = p, 0 < p < 1, relative accuracy about
 * 1e-16. Coefficients from Wichura, Appl. Statist. 37(3), 477-484 (1988). */
static double poly(const double *c, int n, double x)
{
    double s = c[n - 1];
    for (int i = n - 2; i >= 0; i--)
        s = s * x + c[i];
    return s;
}

double lv_disp_norm_inv(double p)
{
    static const double a[8] = { 3.3871328727963666080e0, 1.3314166789178437745e+2,
                                 1.9715909503065514427e+3, 1.3731693765509461125e+4,
                                 4.5921953931549871457e+4, 6.7265770927008700853e+4,
                                 3.3430575583588128105e+4, 2.5090809287301226727e+3 };
    static const double b[8] = { 1.0, 4.2313330701600911252e+1, 6.8718700749205790830e+2,
                                 5.3941960214247511077e+3, 2.1213794301586595867e+4,
                                 3.9307895800092710610e+4, 2.8729085735721942674e+4,
                                 5.2264952788528545610e+3 };
    static const double c[8] = { 1.42343711074968357734e0, 4.63033784615654529590e0,
                                 5.76949722146069140550e0, 3.64784832476320460504e0,
                                 1.27045825245236838258e0, 2.41780725177450611770e-1,
                                 2.27238449892691845833e-2, 7.74545014278341407640e-4 };
    static const double d[8] = { 1.0, 2.05319162663775882187e0, 1.67638483018380384940e0,
                                 6.89767334985100004550e-1, 1.48103976427480074590e-1,
                                 1.51986665636164571966e-2, 5.47593808499534494600e-4,
                                 1.05075007164441684324e-9 };
    static const double e[8] = { 6.65790464350110377720e0, 5.46378491116411436990e0,
                                 1.78482653991729133580e0, 2.96560571828504891230e-1,
                                 2.65321895265761230930e-2, 1.24266094738807843860e-3,
                                 2.71155556874348757815e-5, 2.01033439929228813265e-7 };
    static const double f[8] = { 1.0, 5.99832206555887937690e-1, 1.36929880922735805310e-1,
                                 1.48753612908506148525e-2, 7.86869131145613259100e-4,
                                 1.84631831751005468180e-5, 1.42151175831644588870e-7,
                                 2.04426310338993978564e-15 };
    if (!(p > 0.0 && p < 1.0))
        return p == 0.0 ? -INFINITY : p == 1.0 ? INFINITY : NAN;
    const double q = p - 0.5;
    if (fabs(q) <= 0.425) {
        const double r = 0.180625 - q * q;
        return q * poly(a, 8, r) / poly(b, 8, r);
    }
    double r = sqrt(-log(q < 0.0 ? p : 1.0 - p));
    double z;
    if (r <= 5.0) {
        r -= 1.6;
        z = poly(c, 8, r) / poly(d, 8, r);
    } else {
        r -= 5.0;
        z = poly(e, 8, r) / poly(f, 8, r);
    }
    return q < 0.0 ? -z : z;
}

static double norm_cdf(double x) { return 0.5 * erfc(-x / sqrt(2.0)); }

/* Quantile u of parameter p's marginal (in its written unit, before a relative factor). */
static double quantile(const lv_disp_param *p, double u)
{
    switch (p->dist) {
    case LV_DIST_NORMAL:
        return p->mean + p->sigma * lv_disp_norm_inv(u);
    case LV_DIST_UNIFORM:
        return p->lo + (p->hi - p->lo) * u;
    case LV_DIST_TRUNCATED_NORMAL: {
        const double a = (p->lo - p->mean) / p->sigma, b = (p->hi - p->mean) / p->sigma;
        double x;
        if (a > 0.0) { /* the upper tail: work with Q(x) = Phi(-x), which keeps its digits */
            const double qa = norm_cdf(-a), qb = norm_cdf(-b);
            x = -lv_disp_norm_inv(qa - u * (qa - qb));
        } else {
            const double pa = norm_cdf(a), pb = norm_cdf(b);
            x = lv_disp_norm_inv(pa + u * (pb - pa));
        }
        x = x < a ? a : x > b ? b : x;
        return p->mean + p->sigma * x;
    }
    }
    return NAN;
}

static const lv_disp_def *disp_of(const lv_mission *m) { return m->def->disp; }

size_t lv_mission_disp_count(const lv_mission *m)
{
    return disp_of(m) ? disp_of(m)->n : 0;
}

void lv_mission_disp_info(const lv_mission *m, size_t j, lv_disp_info *out)
{
    static const char *const dn[] = { "normal", "truncated_normal", "uniform" };
    memset(out, 0, sizeof *out);
    const lv_disp_def *dd = disp_of(m);
    if (dd == NULL || j >= dd->n)
        return;
    const lv_disp_param *p = &dd->p[j];
    const lv_slot_def *sd = &m->def->slots[p->slot];
    *out = (lv_disp_info){ p->name, p->deg ? (strcmp(sd->unit, "rad") == 0 ? "deg" : "deg/s")
                                           : sd->unit,
                           dn[p->dist], p->dist, p->relative, p->nominal, p->mean, p->sigma,
                           p->lo, p->hi, p->slot, p->group, p->stream, p->loc.line,
                           p->loc.column };
}

double lv_mission_disp_correlation(const lv_mission *m, size_t a, size_t b)
{
    const lv_disp_def *dd = disp_of(m);
    if (dd == NULL || a >= dd->n || b >= dd->n)
        return NAN;
    if (a == b)
        return 1.0;
    const lv_disp_param *pa = &dd->p[a], *pb = &dd->p[b];
    if (pa->group < 0 || pa->group != pb->group)
        return 0.0;
    const lv_disp_group *g = &dd->groups[pa->group];
    return g->corr[pa->gpos * g->n + pb->gpos];
}

int lv_mission_disp_seed(const lv_mission *m, uint64_t *seed)
{
    const lv_disp_def *dd = disp_of(m);
    if (dd == NULL || !dd->has_seed)
        return 0;
    *seed = dd->seed;
    return 1;
}

void lv_mission_disp_draw(const lv_mission *m, uint64_t seed, uint64_t run, double *values)
{
    const lv_disp_def *dd = disp_of(m);
    if (dd == NULL)
        return;
    for (size_t j = 0; j < dd->n; j++) {
        const lv_disp_param *p = &dd->p[j];
        if (p->group < 0)
            values[j] = quantile(p, lv_disp_uniform(seed, p->stream, run));
    }
    for (size_t g = 0; g < dd->n_groups; g++) {
        const lv_disp_group *gr = &dd->groups[g];
        double z[64], x;
        const size_t n = gr->n < 64 ? gr->n : 64;
        for (size_t i = 0; i < n; i++)
            z[i] = lv_disp_norm_inv(lv_disp_uniform(seed, dd->p[gr->member[i]].stream, run));
        for (size_t i = 0; i < n; i++) {
            x = 0.0;
            for (size_t k = 0; k <= i; k++)
                x += gr->chol[i * gr->n + k] * z[k];
            const lv_disp_param *p = &dd->p[gr->member[i]];
            if (p->dist == LV_DIST_NORMAL) {
                values[gr->member[i]] = p->mean + p->sigma * x;
            } else {
                /* Gaussian copula: the member's own quantile of Phi(x), kept inside (0, 1) */
                double u = norm_cdf(x);
                u = u < 1e-300 ? 1e-300 : u >= 1.0 ? 1.0 - 0x1p-53 : u;
                values[gr->member[i]] = quantile(p, u);
            }
        }
    }
    for (size_t j = 0; j < dd->n; j++)
        if (dd->p[j].relative)
            values[j] *= dd->p[j].nominal;
}

/* ---- per-run table copies ------------------------------------------------------------------ */

typedef struct rt_entry {
    const lv_table *base;  /* NULL: the wind */
    size_t n_out;
    double *scale, *bias;  /* [n_out] the values the copy was made with */
    lv_table *copy;        /* NULL: identity (the base is used) */
    lv_wind *wind;
} rt_entry;

struct lv_run_tables {
    size_t n;
    rt_entry *e;
};

void lv_run_tables_free(lv_run_tables *rt)
{
    if (rt == NULL)
        return;
    for (size_t i = 0; i < rt->n; i++) {
        free(rt->e[i].scale);
        free(rt->e[i].bias);
        lv_table_free(rt->e[i].copy);
        lv_wind_free(rt->e[i].wind);
    }
    free(rt->e);
    free(rt);
}

/* The entries: one per distinct table (and one for the wind), in the order of the xforms. */
static lv_status rt_make(const lv_disp_def *dd, lv_run_tables **out, lv_err *err)
{
    lv_run_tables *rt = calloc(1, sizeof *rt);
    if (rt == NULL || (rt->e = calloc(dd->n_xf + 1, sizeof *rt->e)) == NULL) {
        free(rt);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    for (size_t i = 0; i < dd->n_xf; i++) {
        const lv_table_xf *x = &dd->xf[i];
        size_t j = 0;
        while (j < rt->n && !(rt->e[j].base == x->table && (x->table != NULL || x->wind)))
            j++;
        if (j < rt->n)
            continue;
        rt_entry *e = &rt->e[rt->n++];
        e->base = x->table;
        e->n_out = x->wind ? 3 : lv_table_n_out(x->table);
        e->scale = malloc(e->n_out * sizeof *e->scale);
        e->bias = malloc(e->n_out * sizeof *e->bias);
        if (e->scale == NULL || e->bias == NULL) {
            lv_run_tables_free(rt);
            return lv_fail(err, LV_ERR_NOMEM, "out of memory");
        }
        for (size_t k = 0; k < e->n_out; k++)
            e->scale[k] = 1.0, e->bias[k] = 0.0;
    }
    *out = rt;
    return LV_OK;
}

lv_status lv_run_tables_update(const lv_mission_def *d, const lv_wind *wind, const double *vals,
                               lv_run_tables **prt, lv_err *err)
{
    const lv_disp_def *dd = d->disp;
    if (dd == NULL || dd->n_xf == 0)
        return LV_OK;
    lv_status st;
    if (*prt == NULL && (st = rt_make(dd, prt, err)) != LV_OK)
        return st;
    lv_run_tables *rt = *prt;
    double s[64], b[64];
    for (size_t j = 0; j < rt->n; j++) {
        rt_entry *e = &rt->e[j];
        const size_t no = e->n_out < 64 ? e->n_out : 64;
        for (size_t k = 0; k < no; k++)
            s[k] = 1.0, b[k] = 0.0;
        int identity = 1;
        for (size_t i = 0; i < dd->n_xf; i++) {
            const lv_table_xf *x = &dd->xf[i];
            if (x->table != e->base || (e->base == NULL && !x->wind))
                continue;
            const double v = vals[x->slot];
            for (size_t k = 0; k < no; k++)
                if (x->out == (size_t)-1 || x->out == k) {
                    if (x->bias)
                        b[k] += v;
                    else
                        s[k] *= v;
                }
            identity &= x->bias ? v == 0.0 : v == 1.0;
        }
        if (memcmp(s, e->scale, no * sizeof *s) == 0 && memcmp(b, e->bias, no * sizeof *b) == 0)
            continue; /* the copy (or the base) is this run's already */
        lv_table_free(e->copy);
        lv_wind_free(e->wind);
        e->copy = NULL;
        e->wind = NULL;
        memcpy(e->scale, s, no * sizeof *s);
        memcpy(e->bias, b, no * sizeof *b);
        if (identity)
            continue;
        if (e->base != NULL)
            st = lv_table_create_affine(e->base, s, b, &e->copy, err);
        else
            st = wind != NULL ? lv_wind_create_affine(wind, s[0], b, &e->wind, err) : LV_OK;
        if (st != LV_OK) {
            for (size_t k = 0; k < no; k++) /* made again at the next update */
                e->scale[k] = NAN;
            return st;
        }
    }
    return LV_OK;
}

const lv_table *lv_run_tables_get(const lv_run_tables *rt, const lv_table *t)
{
    for (size_t j = 0; rt != NULL && t != NULL && j < rt->n; j++)
        if (rt->e[j].base == t)
            return rt->e[j].copy != NULL ? rt->e[j].copy : t;
    return t;
}

const lv_wind *lv_run_tables_wind(const lv_run_tables *rt)
{
    for (size_t j = 0; rt != NULL && j < rt->n; j++)
        if (rt->e[j].base == NULL)
            return rt->e[j].wind;
    return NULL;
}
