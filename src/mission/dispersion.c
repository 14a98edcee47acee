/* dispersion.c - the values a Monte Carlo run draws (lv_dispersion.h): Philox4x32-10 streams
 * (Salmon et al., SC'11; Random123) keyed by (seed, parameter-name hash, run index), the
 * inverse normal CDF of Wichura (Applied Statistics AS 241, 1988, PPND16), correlation groups
 * through their Cholesky factor; and the per-run copies of dispersed tables.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "core/units.h"
#include "mission/dispersion.h"
#include "mission/mission_rt.h"

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

int lv_mission_turbulent(const lv_mission *m)
{
    return m->def->env.turbulent;
}

size_t lv_mission_disp_profile_count(const lv_mission *m)
{
    return disp_of(m) ? disp_of(m)->n_prof : 0;
}

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
    /* gusts and turbulence: the values and realisation they were made with */
    lv_wind_disturbance *dist;
    double dist_vals[5 * LV_GUSTS_MAX + 5];
    uint64_t dist_seed, dist_run;
    /* dispersed profiles: the realisations, indexed by lv_prof_target, and the (seed, run)
     * they were drawn for; NULL: none (a nominal run) */
    lv_perturbation *prof[2];
    uint64_t prof_seed, prof_run;
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
    lv_wind_disturbance_free(rt->dist);
    lv_perturbation_free(rt->prof[0]);
    lv_perturbation_free(rt->prof[1]);
    free(rt->e);
    free(rt);
}

/* The entries: one per distinct table (and one for the wind), in the order of the xforms. */
static lv_status rt_make(const lv_disp_def *dd, lv_run_tables **out, lv_err *err)
{
    lv_run_tables *rt = calloc(1, sizeof *rt);
    const size_t n_xf = dd != NULL ? dd->n_xf : 0;
    if (rt == NULL || (rt->e = calloc(n_xf + 1, sizeof *rt->e)) == NULL) {
        free(rt);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    for (size_t i = 0; i < n_xf; i++) {
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

/* The values the run's gusts and turbulence are made from, in a fixed order (NAN: not used):
 * each gust's altitude, half width, north, east, down; turbulence sigma, sigma_vertical,
 * length, from, to. */
static size_t dist_values(const lv_env_def *e, const double *vals, double *out)
{
    size_t n = 0;
    for (size_t k = 0; k < e->n_gusts; k++)
        for (size_t i = 0; i < 5; i++)
            out[n++] = vals[e->gust[k][i]];
    for (size_t i = 0; i < 5; i++)
        out[n++] = e->turbulent ? vals[e->turb[i]] : NAN;
    return n;
}

/* The gusts and turbulence spec of the values v (dist_values' order). */
static void dist_spec(const lv_env_def *e, const double *v, lv_gust_1cos *g, lv_dryden_spec *ts)
{
    for (size_t k = 0; k < e->n_gusts; k++)
        g[k] = (lv_gust_1cos){ v[5 * k], v[5 * k + 1], { v[5 * k + 2], v[5 * k + 3], v[5 * k + 4] } };
    const double *t = v + 5 * e->n_gusts;
    *ts = (lv_dryden_spec){ t[0], t[1], t[2], t[3], t[4] };
}

lv_status lv_run_disturbance_check(const lv_mission_def *d, const double *vals, lv_err *err)
{
    const lv_env_def *e = &d->env;
    if (e->n_gusts == 0 && !e->turbulent)
        return LV_OK;
    double v[5 * LV_GUSTS_MAX + 5];
    dist_values(e, vals, v);
    lv_gust_1cos g[LV_GUSTS_MAX];
    lv_dryden_spec ts;
    dist_spec(e, v, g, &ts);
    return lv_wind_disturbance_check(e->turbulent ? &ts : NULL, g, e->n_gusts, err);
}

static lv_status dist_update(const lv_mission_def *d, const double *vals, uint64_t seed,
                             uint64_t run, lv_run_tables *rt, lv_err *err)
{
    const lv_env_def *e = &d->env;
    double v[5 * LV_GUSTS_MAX + 5];
    const size_t n = dist_values(e, vals, v);
    if (rt->dist != NULL && memcmp(v, rt->dist_vals, n * sizeof *v) == 0 &&
        (!e->turbulent || (seed == rt->dist_seed && run == rt->dist_run)))
        return LV_OK; /* this run's already */
    lv_wind_disturbance_free(rt->dist);
    rt->dist = NULL;
    lv_gust_1cos g[LV_GUSTS_MAX];
    lv_dryden_spec ts;
    dist_spec(e, v, g, &ts);
    lv_status st = lv_wind_disturbance_create(e->turbulent ? &ts : NULL, g, e->n_gusts, seed, run,
                                              &rt->dist, err);
    if (st != LV_OK)
        return lv_fail_prefix(err, st, "environment");
    memcpy(rt->dist_vals, v, n * sizeof *v);
    rt->dist_seed = seed;
    rt->dist_run = run;
    return LV_OK;
}

/* The run's dispersed profiles: drawn for (seed, run) when `on`, none otherwise. */
static lv_status prof_update(const lv_disp_def *dd, uint64_t seed, uint64_t run, int on,
                             lv_run_tables *rt, lv_err *err)
{
    const int have = rt->prof[0] != NULL || rt->prof[1] != NULL;
    if (have == on && (!on || (seed == rt->prof_seed && run == rt->prof_run)))
        return LV_OK; /* this run's already */
    for (size_t k = 0; k < 2; k++) {
        lv_perturbation_free(rt->prof[k]);
        rt->prof[k] = NULL;
    }
    if (!on)
        return LV_OK;
    for (size_t i = 0; i < dd->n_prof; i++) {
        const lv_disp_profile *pr = &dd->prof[i];
        const lv_perturbation_spec sp = { pr->n_sigma, pr->sigma_h, pr->sigma, pr->length,
                                          pr->h_from, pr->h_to,
                                          pr->target == LV_PROF_WIND ? 2u : 1u };
        const lv_status st = lv_perturbation_create(&sp, pr->stream, seed, run,
                                                    &rt->prof[pr->target], err);
        if (st != LV_OK) {
            for (size_t k = 0; k < 2; k++) {
                lv_perturbation_free(rt->prof[k]);
                rt->prof[k] = NULL;
            }
            return lv_fail_prefix(err, st, "dispersions: profiles: '%s'", pr->name);
        }
    }
    rt->prof_seed = seed;
    rt->prof_run = run;
    return LV_OK;
}

lv_status lv_run_tables_update(const lv_mission_def *d, const lv_wind *wind, const double *vals,
                               uint64_t seed, uint64_t run, int profiles, lv_run_tables **prt,
                               lv_err *err)
{
    const lv_disp_def *dd = d->disp;
    const int disturbed = d->env.n_gusts > 0 || d->env.turbulent;
    const int prof = dd != NULL && dd->n_prof > 0;
    if ((dd == NULL || dd->n_xf == 0) && !disturbed && !prof)
        return LV_OK;
    lv_status st;
    if (*prt == NULL && (st = rt_make(dd, prt, err)) != LV_OK)
        return st;
    if (disturbed && (st = dist_update(d, vals, seed, run, *prt, err)) != LV_OK)
        return st;
    if (prof && (st = prof_update(dd, seed, run, profiles, *prt, err)) != LV_OK)
        return st;
    if (dd == NULL)
        return LV_OK;
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

const lv_perturbation *lv_run_tables_profile(const lv_run_tables *rt, lv_prof_target target)
{
    return rt != NULL ? rt->prof[target] : NULL;
}

const lv_wind_disturbance *lv_run_tables_disturbance(const lv_run_tables *rt)
{
    return rt != NULL ? rt->dist : NULL;
}

const lv_wind *lv_run_tables_wind(const lv_run_tables *rt)
{
    for (size_t j = 0; rt != NULL && j < rt->n; j++)
        if (rt->e[j].base == NULL)
            return rt->e[j].wind;
    return NULL;
}
