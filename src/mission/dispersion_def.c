/* dispersion_def.c - the `dispersions:` section of a mission file: parameters perturbed by a
 * distribution (normal, truncated normal, uniform; absolute or a relative factor), correlation
 * groups, table dispersions (a scale factor or a bias on an engine table's or the wind's
 * outputs, registered here as parameters of their own) and the campaign's default seed. Every
 * bad value is "file:line:column: message". Format: docs/monte-carlo.md.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/names.h"
#include "core/status.h"
#include "core/units.h"
#include "mission/dispersion.h"

static char *dup_str(const char *s)
{
    const size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d != NULL)
        memcpy(d, s, n);
    return d;
}

void lv_disp_def_free(lv_disp_def *d)
{
    if (d == NULL)
        return;
    for (size_t j = 0; j < d->n; j++)
        free(d->p[j].name);
    free(d->p);
    for (size_t g = 0; g < d->n_groups; g++) {
        free(d->groups[g].member);
        free(d->groups[g].corr);
        free(d->groups[g].chol);
    }
    free(d->groups);
    free(d->xf);
    free(d);
}

static lv_src_loc loc_of(const lv_ynode *n) { return (lv_src_loc){n->line, n->col}; }

static lv_status get_bool(const lv_pctx *c, const lv_ynode *v, const char *what, const char *key,
                          int *out)
{
    if (v->kind == LV_YNODE_SCALAR && v->plain) {
        if (strcmp(v->text, "true") == 0 || strcmp(v->text, "yes") == 0) {
            *out = 1;
            return LV_OK;
        }
        if (strcmp(v->text, "false") == 0 || strcmp(v->text, "no") == 0) {
            *out = 0;
            return LV_OK;
        }
    }
    return lv_pk_fail(c, v, "%s: %s: true or false expected, found '%.40s'", what, key,
                      v->kind == LV_YNODE_SCALAR ? v->text : "a collection");
}

/* ---- table dispersions: "<engine>.table[.<output>].scale|bias", "environment.wind.scale",
 * "environment.wind.<north|east|down>.bias" ------------------------------------------------ */

static lv_status table_xf(const lv_pctx *c, const lv_ynode *key, lv_disp_def *dd, lv_slot *out,
                          int *found)
{
    lv_mission_def *m = c->m;
    const char *name = key->text;
    const size_t n = strlen(name);
    *found = 0;
    int bias;
    size_t cut;
    if (n > 6 && strcmp(name + n - 6, ".scale") == 0)
        bias = 0, cut = n - 6;
    else if (n > 5 && strcmp(name + n - 5, ".bias") == 0)
        bias = 1, cut = n - 5;
    else
        return LV_OK;
    char prefix[LV_NAME_MAX * 2 + 32];
    if (cut >= sizeof prefix)
        return LV_OK;
    memcpy(prefix, name, cut);
    prefix[cut] = '\0';
    lv_table_xf xf = { NULL, 0, (size_t)-1, bias, LV_NO_SLOT };
    const char *unit = "";
    lv_range range = LV_RANGE_ANY;
    lv_slot_owner owner = LV_OWN_ENV;
    size_t owner_index = 0;
    static const char *const wind_out[3] = { "north", "east", "down" };
    if (strncmp(prefix, "environment.wind", 16) == 0 &&
        (prefix[16] == '\0' || prefix[16] == '.')) {
        if (m->env.wind_file == NULL && m->env.n_wind_prof == 0)
            return lv_pk_fail(c, key, "dispersions: '%s': the mission has no wind table%s", name,
                              m->env.wind_const ? " (a constant wind: disperse "
                              "environment.wind.north, .east, .down themselves)" : "");
        xf.wind = 1;
        if (prefix[16] == '.') {
            for (size_t k = 0; k < 3; k++)
                if (strcmp(prefix + 17, wind_out[k]) == 0)
                    xf.out = k;
            if (xf.out == (size_t)-1 || !bias)
                return lv_pk_fail(c, key, "dispersions: '%s': the wind takes "
                                  "environment.wind.scale (every component) and "
                                  "environment.wind.north.bias, .east.bias, .down.bias", name);
            unit = "m/s";
        } else if (bias) {
            return lv_pk_fail(c, key, "dispersions: '%s': a wind bias names its component: "
                              "environment.wind.north.bias, .east.bias or .down.bias", name);
        }
    } else {
        /* an engine's table: "<engine>.table" or "<engine>.table.<output>" */
        const char *t = strstr(prefix, ".table");
        while (t != NULL && t[6] != '\0' && t[6] != '.')
            t = strstr(t + 1, ".table");
        if (t == NULL)
            return LV_OK;
        const size_t ne = (size_t)(t - prefix);
        const lv_engine_def *eng = NULL;
        for (size_t s = 0; s < m->n_stages && eng == NULL; s++)
            for (size_t e = 0; e < m->stages[s].n_engines; e++)
                if (strlen(m->stages[s].engines[e].name) == ne &&
                    strncmp(m->stages[s].engines[e].name, prefix, ne) == 0) {
                    eng = &m->stages[s].engines[e];
                    owner = LV_OWN_STAGE;
                    owner_index = s;
                    break;
                }
        if (eng == NULL)
            return LV_OK;
        if (eng->table == NULL)
            return lv_pk_fail(c, key, "dispersions: '%s': engine '%s' has no table (a constant "
                              "engine: disperse its thrust_vac, isp_vac or mdot)", name,
                              eng->name);
        xf.table = eng->table;
        if (t[6] == '.') {
            lv_err e2;
            if (lv_table_out_index(eng->table, t + 7, &xf.out, &e2) != LV_OK)
                return lv_pk_fail(c, key, "dispersions: '%s': %s", name, e2.msg);
            unit = bias ? lv_table_out_unit(eng->table, xf.out) : "";
        } else if (bias) {
            return lv_pk_fail(c, key, "dispersions: '%s': a bias names the output it adds to "
                              "(%s.table.%s.bias)", name, eng->name,
                              lv_table_out_name(eng->table, 0));
        }
        if (!bias)
            range = LV_RANGE_NONNEG; /* thrust and mass flow stay >= 0 */
    }
    const lv_slot old = lv_mission_def_slot(m, name);
    if (old != LV_NO_SLOT) { /* named twice in the section cannot happen: keys are unique */
        *out = old;
        *found = 1;
        return LV_OK;
    }
    lv_status st = lv_mission_def_add_slot(m, name, unit, bias ? 0.0 : 1.0, range, owner,
                                           owner_index, loc_of(key), &xf.slot, c->err);
    if (st != LV_OK)
        return st;
    lv_table_xf *grown = realloc(dd->xf, (dd->n_xf + 1) * sizeof *grown);
    if (grown == NULL)
        return lv_pk_nomem(c);
    dd->xf = grown;
    dd->xf[dd->n_xf++] = xf;
    *out = xf.slot;
    *found = 1;
    return LV_OK;
}

/* The parameter a dispersion names: a slot, "NAME_deg" for an angle, or a table dispersion. */
static lv_status resolve(const lv_pctx *c, const lv_ynode *key, lv_disp_def *dd, lv_slot *slot,
                         int *deg)
{
    const lv_mission_def *m = c->m;
    const char *name = key->text;
    *deg = 0;
    if ((*slot = lv_mission_def_slot(m, name)) != LV_NO_SLOT)
        return LV_OK;
    const size_t n = strlen(name);
    if (n > 4 && strcmp(name + n - 4, "_deg") == 0) {
        char base[256];
        if (n - 4 < sizeof base) {
            memcpy(base, name, n - 4);
            base[n - 4] = '\0';
            const lv_slot s = lv_mission_def_slot(m, base);
            if (s != LV_NO_SLOT && (strcmp(m->slots[s].unit, "rad") == 0 ||
                                    strcmp(m->slots[s].unit, "rad/s") == 0)) {
                *slot = s;
                *deg = 1;
                return LV_OK;
            }
        }
    }
    int found = 0;
    lv_status st = table_xf(c, key, dd, slot, &found);
    if (st != LV_OK || found)
        return st;
    if (strcmp(name, "environment.wind") == 0 ||
        strcmp(name, "environment.atmosphere.density") == 0)
        return lv_pk_fail(c, key, "dispersions: '%s' is a profile, not a parameter: write it "
                          "under dispersions: profiles: with {sigma, correlation_length} "
                          "(docs/monte-carlo.md, \"Dispersed profiles\")", name);
    lv_suggest sg;
    char hint[200];
    lv_suggest_init(&sg, name);
    for (size_t s = 0; s < m->n_slots; s++)
        lv_suggest_add(&sg, m->slots[s].name);
    lv_suggest_text(&sg, hint, sizeof hint);
    /* a landing gear's limits are parameters only where the stage writes `landing_gear:` */
    const char *lg = strstr(name, ".landing_gear.");
    if (lg != NULL && hint[0] == '\0')
        return lv_pk_fail(c, key, "dispersions: no parameter '%.80s': stage '%.*s' writes no "
                          "`landing_gear:` (its limits are the defaults, not parameters: write "
                          "`landing_gear: {}` to vary them)", name, (int)(lg - name), name);
    return lv_pk_fail(c, key, "dispersions: no parameter '%.80s'%s (lvsim params lists them; "
                      "tables: <engine>.table.<output>.scale or .bias, environment.wind.scale)",
                      name, hint);
}

static const char *const dist_names[] = { "normal", "truncated_normal", "uniform", NULL };

/* One entry of `parameters:`: NAME: {dist, mean, sigma, min, max, half_width, relative}. */
static lv_status parse_param(const lv_pctx *c, const lv_ynode *key, const lv_ynode *v,
                             lv_disp_def *dd, lv_disp_param *p)
{
    static const char *const keys[] = { "dist", "mean", "sigma", "min", "max", "half_width",
                                        "relative", NULL };
    const lv_mission_def *m = c->m;
    char what[LV_WHAT_MAX];
    snprintf(what, sizeof what, "dispersions: '%.100s'", key->text);
    lv_status st;
    const lv_ynode *dv;
    size_t kind;
    if ((st = resolve(c, key, dd, &p->slot, &p->deg)) != LV_OK ||
        (st = lv_pk_check_map(c, v, what, keys)) != LV_OK ||
        (st = lv_pk_need(c, v, what, "dist", &dv)) != LV_OK ||
        (st = lv_pk_enum(c, dv, what, "dist", dist_names, &kind)) != LV_OK)
        return st;
    const char *by = NULL;
    if (lv_mission_def_slot_overridden(m, p->slot, &by))
        return lv_pk_fail(c, key, "%s has no effect: phase '%s' starts from its reference "
                          "(start: reference), whose first row replaces it (disperse the "
                          "reference, or start: parent)", what, by);
    if ((p->name = dup_str(key->text)) == NULL)
        return lv_pk_nomem(c);
    p->dist = (lv_disp_dist)kind;
    p->loc = loc_of(key);
    p->stream = lv_disp_stream(p->name);
    p->group = -1;
    const lv_slot_def *sd = &m->slots[p->slot];
    p->nominal = p->deg ? sd->value / LV_DEG : sd->value;
    const lv_ynode *rv = lv_pk_get(v, "relative");
    if (rv != NULL && (st = get_bool(c, rv, what, "relative", &p->relative)) != LV_OK)
        return st;
    double num[5];
    int has[5];
    static const char *const nk[5] = { "mean", "sigma", "min", "max", "half_width" };
    for (int i = 0; i < 5; i++) {
        const lv_ynode *x = lv_pk_get(v, nk[i]);
        has[i] = x != NULL;
        if (has[i] && (st = lv_pk_num(c, x, what, nk[i], &num[i])) != LV_OK)
            return st;
    }
    const double centre = p->relative ? 1.0 : p->nominal;
    /* keys the distribution does not take */
    static const int takes[3][5] = { { 1, 1, 0, 0, 0 }, { 1, 1, 1, 1, 0 }, { 0, 0, 1, 1, 1 } };
    for (int i = 0; i < 5; i++)
        if (has[i] && !takes[kind][i])
            return lv_pk_fail(c, lv_pk_key(v, nk[i]), "%s: dist %s takes no '%s' (it takes %s)",
                              what, dist_names[kind], nk[i],
                              kind == 0 ? "mean, sigma" : kind == 1 ? "mean, sigma, min, max"
                                                                  : "min and max, or half_width");
    p->mean = has[0] ? num[0] : centre;
    p->lo = -INFINITY;
    p->hi = INFINITY;
    if (kind != LV_DIST_UNIFORM) {
        const lv_ynode *sv;
        if ((st = lv_pk_need(c, v, what, "sigma", &sv)) != LV_OK)
            return st;
        p->sigma = num[1];
        if (!(p->sigma >= 0.0) || (kind == LV_DIST_TRUNCATED_NORMAL && !(p->sigma > 0.0)))
            return lv_pk_fail(c, sv, "%s: sigma must be %s, found %g", what,
                              kind == LV_DIST_NORMAL ? ">= 0" : "> 0", p->sigma);
    }
    if (kind == LV_DIST_TRUNCATED_NORMAL) {
        if (!has[2] && !has[3])
            return lv_pk_fail(c, v, "%s: a truncated normal needs min, max or both", what);
        if (has[2])
            p->lo = num[2];
        if (has[3])
            p->hi = num[3];
    } else if (kind == LV_DIST_UNIFORM) {
        if (has[4] && (has[2] || has[3]))
            return lv_pk_fail(c, lv_pk_key(v, "half_width"), "%s: give min and max, or "
                              "half_width (about the file's value), not both", what);
        if (has[4]) {
            if (!(num[4] > 0.0))
                return lv_pk_fail(c, lv_pk_get(v, "half_width"), "%s: half_width must be > 0, "
                                  "found %g", what, num[4]);
            p->lo = centre - num[4];
            p->hi = centre + num[4];
        } else {
            if (!has[2] || !has[3])
                return lv_pk_fail(c, v, "%s: a uniform distribution needs min and max (or "
                                  "half_width)", what);
            p->lo = num[2];
            p->hi = num[3];
        }
    }
    if ((kind != LV_DIST_NORMAL) && !(p->lo < p->hi))
        return lv_pk_fail(c, lv_pk_get(v, has[3] ? "max" : "half_width"),
                          "%s: max %g must be greater than min %g", what, p->hi, p->lo);
    if (kind == LV_DIST_TRUNCATED_NORMAL && !(p->mean > p->lo - 8.0 * p->sigma &&
                                              p->mean < p->hi + 8.0 * p->sigma))
        return lv_pk_fail(c, v, "%s: [min, max] = [%g, %g] lies more than 8 sigma from the mean "
                          "%g: almost no probability to sample", what, p->lo, p->hi, p->mean);
    /* the bounds a draw can reach must be allowed values of the parameter */
    const double scale = p->deg ? LV_DEG : 1.0;
    const double f = p->relative ? p->nominal : 1.0;
    for (int b = 0; b < 2; b++) {
        const double x = b == 0 ? p->lo : p->hi;
        if (!isfinite(x))
            continue;
        const double si = x * f * scale;
        if (!lv_range_holds(sd->range, si)) {
            char rule[64];
            lv_range_text(sd->range, rule, sizeof rule);
            return lv_pk_fail(c, lv_pk_get(v, has[4] ? "half_width" : b == 0 ? "min" : "max"),
                              "%s: the %s %g %s gives %s = %g %s, outside its range %s", what,
                              b == 0 ? "lower bound" : "upper bound", x,
                              p->relative ? "(a factor)" : p->deg ? "deg" : sd->unit, sd->name,
                              si, sd->unit, rule);
        }
    }
    return LV_OK;
}

/* Cholesky factor of the n x n matrix a (row-major): L lower with a = L L^T; 0 when a is not
 * positive definite. */
static int cholesky(const double *a, size_t n, double *l)
{
    memset(l, 0, n * n * sizeof *l);
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j <= i; j++) {
            double s = a[i * n + j];
            for (size_t k = 0; k < j; k++)
                s -= l[i * n + k] * l[j * n + k];
            if (i == j) {
                if (!(s > 1e-12))
                    return 0;
                l[i * n + i] = sqrt(s);
            } else {
                l[i * n + j] = s / l[j * n + j];
            }
        }
    return 1;
}

/* - {parameters: [a, b, ...], matrix: [[1, r], [r, 1]]}  or  {parameters: [a, b], rho: r} */
static lv_status parse_group(const lv_pctx *c, const lv_ynode *n, size_t gi, lv_disp_def *dd)
{
    static const char *const keys[] = { "parameters", "matrix", "rho", NULL };
    char what[LV_WHAT_MAX];
    snprintf(what, sizeof what, "dispersions: correlations #%zu", gi + 1);
    lv_disp_group *g = &dd->groups[gi];
    g->loc = loc_of(n);
    const lv_ynode *pv;
    lv_status st;
    if ((st = lv_pk_check_map(c, n, what, keys)) != LV_OK ||
        (st = lv_pk_need(c, n, what, "parameters", &pv)) != LV_OK)
        return st;
    if (pv->kind != LV_YNODE_SEQ || pv->n < 2)
        return lv_pk_fail(c, pv, "%s: parameters: a list of at least two dispersed parameters "
                          "expected", what);
    const size_t k = pv->n;
    g->n = k;
    g->member = calloc(k, sizeof *g->member);
    g->corr = calloc(k * k, sizeof *g->corr);
    g->chol = calloc(k * k, sizeof *g->chol);
    if (g->member == NULL || g->corr == NULL || g->chol == NULL)
        return lv_pk_nomem(c);
    for (size_t i = 0; i < k; i++) {
        const lv_ynode *it = pv->kids[i];
        const char *nm;
        if ((st = lv_pk_text(c, it, what, "parameters", &nm)) != LV_OK)
            return st;
        size_t j = 0;
        while (j < dd->n && strcmp(dd->p[j].name, nm) != 0)
            j++;
        if (j == dd->n)
            return lv_pk_fail(c, it, "%s: '%.80s' is not dispersed (name it under "
                              "dispersions: parameters: first, exactly as written there)", what,
                              nm);
        if (dd->p[j].group >= 0)
            return lv_pk_fail(c, it, "%s: '%.80s' is already in correlation group #%d (one "
                              "group per parameter: merge the groups)", what, nm,
                              dd->p[j].group + 1);
        dd->p[j].group = (int)gi;
        dd->p[j].gpos = i;
        g->member[i] = j;
    }
    const lv_ynode *mv = lv_pk_get(n, "matrix"), *rv = lv_pk_get(n, "rho");
    if ((mv == NULL) == (rv == NULL))
        return lv_pk_fail(c, n, "%s: give either 'matrix' (k x k) or, for a pair, 'rho'", what);
    if (rv != NULL) {
        double r;
        if (k != 2)
            return lv_pk_fail(c, rv, "%s: rho is for a pair; %zu parameters need a matrix", what,
                              k);
        if ((st = lv_pk_num(c, rv, what, "rho", &r)) != LV_OK)
            return st;
        if (!(r > -1.0 && r < 1.0))
            return lv_pk_fail(c, rv, "%s: rho must lie in (-1, 1), found %g", what, r);
        g->corr[0] = g->corr[3] = 1.0;
        g->corr[1] = g->corr[2] = r;
    } else {
        if (mv->kind != LV_YNODE_SEQ || mv->n != k)
            return lv_pk_fail(c, mv, "%s: matrix: %zu rows expected (one per parameter)", what,
                              k);
        for (size_t i = 0; i < k; i++) {
            const lv_ynode *row = mv->kids[i];
            if (row->kind != LV_YNODE_SEQ || row->n != k)
                return lv_pk_fail(c, row, "%s: matrix row %zu: %zu numbers expected", what,
                                  i + 1, k);
            for (size_t j = 0; j < k; j++)
                if ((st = lv_pk_num(c, row->kids[j], what, "matrix", &g->corr[i * k + j])) !=
                    LV_OK)
                    return st;
        }
        for (size_t i = 0; i < k; i++)
            for (size_t j = 0; j < k; j++) {
                const lv_ynode *at = mv->kids[i]->kids[j];
                const double a = g->corr[i * k + j];
                if (i == j && a != 1.0)
                    return lv_pk_fail(c, at, "%s: matrix: the diagonal must be 1, found %g", what,
                                      a);
                if (i != j && !(a >= -1.0 && a <= 1.0))
                    return lv_pk_fail(c, at, "%s: matrix: a correlation lies in [-1, 1], found "
                                      "%g", what, a);
                if (fabs(a - g->corr[j * k + i]) > 1e-12)
                    return lv_pk_fail(c, at, "%s: matrix: not symmetric (row %zu column %zu is "
                                      "%g, row %zu column %zu is %g)", what, i + 1, j + 1, a,
                                      j + 1, i + 1, g->corr[j * k + i]);
            }
    }
    if (!cholesky(g->corr, k, g->chol))
        return lv_pk_fail(c, mv != NULL ? mv : rv, "%s: the correlation matrix is not positive "
                          "definite (no joint distribution has these correlations)", what);
    return LV_OK;
}

/* ---- dispersed profiles: `profiles:` NAME: {sigma, correlation_length, from, to} ----------- */

#define PROF_FROM 0.0        /* m, the default layer sampled */
#define PROF_TO 120000.0
#define PROF_SAMPLES_MAX (((size_t)1 << 22) - 4) /* lv_perturbation.h's limit: L/20 samples */

/* sigma: a number (at every altitude) or a list of [h, sigma] pairs, h strictly increasing;
 * every sigma in [0, cap]. */
static lv_status prof_sigma(const lv_pctx *c, const lv_ynode *v, const char *what, double cap,
                            const char *unit, lv_disp_profile *pr)
{
    lv_status st;
    if (v->kind == LV_YNODE_SCALAR) {
        pr->n_sigma = 1;
        pr->sigma_h[0] = 0.0;
        if ((st = lv_pk_num(c, v, what, "sigma", &pr->sigma[0])) != LV_OK)
            return st;
        if (!(pr->sigma[0] >= 0.0 && pr->sigma[0] <= cap))
            return lv_pk_fail(c, v, "%s: sigma must be in [0, %g]%s, found %g", what, cap, unit,
                              pr->sigma[0]);
        return LV_OK;
    }
    if (v->kind != LV_YNODE_SEQ || v->n < 1 || v->n > LV_PERTURBATION_SIGMA_MAX)
        return lv_pk_fail(c, v, "%s: sigma: a number, or a list of 1 to %d pairs [altitude m, "
                          "sigma] expected", what, LV_PERTURBATION_SIGMA_MAX);
    pr->n_sigma = v->n;
    for (size_t k = 0; k < v->n; k++) {
        const lv_ynode *row = v->kids[k];
        if (row->kind != LV_YNODE_SEQ || row->n != 2)
            return lv_pk_fail(c, row, "%s: sigma point %zu: a pair [altitude m, sigma] expected",
                              what, k + 1);
        if ((st = lv_pk_num(c, row->kids[0], what, "sigma", &pr->sigma_h[k])) != LV_OK ||
            (st = lv_pk_num(c, row->kids[1], what, "sigma", &pr->sigma[k])) != LV_OK)
            return st;
        if (!isfinite(pr->sigma_h[k]))
            return lv_pk_fail(c, row->kids[0], "%s: sigma point %zu: the altitude must be "
                              "finite", what, k + 1);
        if (k > 0 && !(pr->sigma_h[k] > pr->sigma_h[k - 1]))
            return lv_pk_fail(c, row->kids[0], "%s: sigma point %zu: altitude %g m is not above "
                              "the previous point's %g m (altitudes must increase)", what, k + 1,
                              pr->sigma_h[k], pr->sigma_h[k - 1]);
        if (!(pr->sigma[k] >= 0.0 && pr->sigma[k] <= cap))
            return lv_pk_fail(c, row->kids[1], "%s: sigma point %zu: sigma must be in [0, %g]%s, "
                              "found %g", what, k + 1, cap, unit, pr->sigma[k]);
    }
    return LV_OK;
}

static lv_status parse_profile(const lv_pctx *c, const lv_ynode *key, const lv_ynode *v,
                               lv_disp_profile *pr)
{
    static const char *const keys[] = { "sigma", "correlation_length", "from", "to", NULL };
    static const char *const targets[] = { "environment.wind", "environment.atmosphere.density" };
    const lv_env_def *e = &c->m->env;
    char what[LV_WHAT_MAX];
    snprintf(what, sizeof what, "dispersions: profiles: '%.80s'", key->text);
    size_t t = 0;
    while (t < 2 && strcmp(key->text, targets[t]) != 0)
        t++;
    if (t == 2) {
        lv_suggest sg;
        char hint[200];
        lv_suggest_init(&sg, key->text);
        for (size_t k = 0; k < 2; k++)
            lv_suggest_add(&sg, targets[k]);
        lv_suggest_text(&sg, hint, sizeof hint);
        return lv_pk_fail(c, key, "dispersions: profiles: no profile '%.80s'%s (profiles: "
                          "environment.wind, environment.atmosphere.density)", key->text, hint);
    }
    const int no_air = e->atmosphere == NULL || strcmp(e->atmosphere, "none") == 0;
    if (no_air)
        return lv_pk_fail(c, key, "%s: the mission has no atmosphere (atmosphere: none): "
                          "nothing to perturb", what);
    pr->target = t == 0 ? LV_PROF_WIND : LV_PROF_DENSITY;
    pr->name = targets[t];
    pr->loc = loc_of(key);
    const lv_ynode *sv, *lv;
    lv_status st;
    if ((st = lv_pk_check_map(c, v, what, keys)) != LV_OK ||
        (st = lv_pk_need(c, v, what, "sigma", &sv)) != LV_OK ||
        (st = lv_pk_need(c, v, what, "correlation_length", &lv)) != LV_OK)
        return st;
    /* density: 1 + delta reaches the floor 0.05 at -0.95: 3.8 sigma at the largest sigma */
    if ((st = t == 0 ? prof_sigma(c, sv, what, 100.0, " m/s", pr)
                     : prof_sigma(c, sv, what, 0.25, " (relative)", pr)) != LV_OK)
        return st;
    if ((st = lv_pk_num(c, lv, what, "correlation_length", &pr->length)) != LV_OK)
        return st;
    if (!(pr->length >= 1.0 && pr->length <= 1e6))
        return lv_pk_fail(c, lv, "%s: correlation_length must be in [1, 1e6] m, found %g", what,
                          pr->length);
    pr->h_from = PROF_FROM;
    pr->h_to = PROF_TO;
    const lv_ynode *fv = lv_pk_get(v, "from"), *tv = lv_pk_get(v, "to");
    if ((fv != NULL && (st = lv_pk_num(c, fv, what, "from", &pr->h_from)) != LV_OK) ||
        (tv != NULL && (st = lv_pk_num(c, tv, what, "to", &pr->h_to)) != LV_OK))
        return st;
    if (!isfinite(pr->h_from) || !isfinite(pr->h_to) || !(pr->h_to > pr->h_from))
        return lv_pk_fail(c, tv != NULL ? tv : fv != NULL ? fv : key, "%s: 'to' (%g m) must be "
                          "above 'from' (%g m), both finite", what, pr->h_to, pr->h_from);
    const double cells = (pr->h_to - pr->h_from) / (pr->length / 20.0);
    if (!(cells <= (double)PROF_SAMPLES_MAX))
        return lv_pk_fail(c, lv, "%s: [from, to] = [%g, %g] m is %.3g correlation lengths deep; "
                          "at most %.3g (samples at L/20): a longer correlation_length or a "
                          "thinner layer", what, pr->h_from, pr->h_to,
                          (pr->h_to - pr->h_from) / pr->length,
                          (double)PROF_SAMPLES_MAX / 20.0);
    char sname[96];
    for (size_t k = 0; k < (t == 0 ? 2u : 1u); k++) {
        snprintf(sname, sizeof sname, "profiles.%s%s", pr->name,
                 t == 0 ? (k == 0 ? ".north" : ".east") : "");
        pr->stream[k] = lv_disp_stream(sname);
    }
    return LV_OK;
}

lv_status lv_disp_def_parse(const lv_pctx *c, const lv_ynode *n)
{
    static const char *const keys[] = { "seed", "parameters", "correlations", "profiles",
                                        NULL };
    const char *what = "dispersions";
    lv_status st;
    if (n == NULL || lv_yaml_is_null(n))
        return LV_OK;
    if ((st = lv_pk_check_map(c, n, what, keys)) != LV_OK)
        return st;
    lv_disp_def *dd = calloc(1, sizeof *dd);
    if (dd == NULL)
        return lv_pk_nomem(c);
    c->m->disp = dd;
    const lv_ynode *v = lv_pk_get(n, "seed");
    if (v != NULL) {
        if ((st = lv_pk_seed(c, v, "dispersions", &dd->seed)) != LV_OK)
            return st;
        dd->has_seed = 1;
    }
    const lv_ynode *fv = lv_pk_get(n, "profiles");
    if (fv != NULL) {
        if ((st = lv_pk_check_map(c, fv, "dispersions: profiles", NULL)) != LV_OK)
            return st;
        if (fv->n == 0)
            return lv_pk_fail(c, fv, "dispersions: profiles: at least one profile expected");
        for (size_t i = 0; i + 1 < fv->n; i += 2) {
            lv_disp_profile *pr = &dd->prof[dd->n_prof];
            if ((st = parse_profile(c, fv->kids[i], fv->kids[i + 1], pr)) != LV_OK)
                return st;
            dd->n_prof++; /* keys are unique: at most one of each */
        }
    }
    const lv_ynode *pv;
    if (fv != NULL && lv_pk_get(n, "parameters") == NULL) { /* profiles alone */
        const lv_ynode *cv = lv_pk_get(n, "correlations");
        if (cv != NULL && !lv_yaml_is_null(cv))
            return lv_pk_fail(c, lv_pk_key(n, "correlations"), "dispersions: correlations "
                              "group dispersed parameters, and there is no 'parameters:'");
        return LV_OK;
    }
    if ((st = lv_pk_need(c, n, what, "parameters", &pv)) != LV_OK ||
        (st = lv_pk_check_map(c, pv, "dispersions: parameters", NULL)) != LV_OK)
        return st;
    if (pv->n == 0)
        return lv_pk_fail(c, pv, "dispersions: parameters: at least one parameter expected");
    if ((dd->p = calloc(pv->n / 2, sizeof *dd->p)) == NULL)
        return lv_pk_nomem(c);
    for (size_t i = 0; i + 1 < pv->n; i += 2) {
        lv_disp_param *p = &dd->p[dd->n];
        if ((st = parse_param(c, pv->kids[i], pv->kids[i + 1], dd, p)) != LV_OK) {
            free(p->name);
            memset(p, 0, sizeof *p);
            return st;
        }
        for (size_t j = 0; j < dd->n; j++)
            if (dd->p[j].slot == p->slot)
                return lv_pk_fail(c, pv->kids[i], "dispersions: '%s' and '%s' (line %d) are the "
                                  "same parameter", p->name, dd->p[j].name, dd->p[j].loc.line);
            else if (dd->p[j].stream == p->stream)
                return lv_pk_fail(c, pv->kids[i], "dispersions: '%s' and '%s' share a stream "
                                  "(a 64-bit hash collision): rename one", p->name,
                                  dd->p[j].name);
        dd->n++;
    }
    const lv_ynode *cv = lv_pk_get(n, "correlations");
    if (cv != NULL && !lv_yaml_is_null(cv)) {
        if (cv->kind != LV_YNODE_SEQ)
            return lv_pk_fail(c, cv, "dispersions: correlations: a list of groups expected");
        if ((dd->groups = calloc(cv->n + 1, sizeof *dd->groups)) == NULL)
            return lv_pk_nomem(c);
        for (size_t g = 0; g < cv->n; g++) {
            dd->n_groups = g + 1;
            if ((st = parse_group(c, cv->kids[g], g, dd)) != LV_OK)
                return st;
        }
    }
    return LV_OK;
}
