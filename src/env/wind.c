/* wind.c - wind as a 1-axis table over geodetic altitude: north, east and optionally down
 * components in the local NED frame, m/s (lv_table.h), interpolated linearly (or as the
 * caller chooses) and clamped at the ends of the table unless told otherwise; or a constant
 * (one value, or a table of one row); measured or forecast profiles over altitude and time; or
 * any of these plus a disturbance (gusts, turbulence: turbulence.c). An lv_wind_fn adapter
 * lets the flight models use it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/names.h"
#include "core/status.h"
#include "env/profile.h"
#include "io/table_load.h"
#include "lvsim/lv_table.h"
#include "lvsim/lv_wind.h"

enum wind_col { W_NORTH, W_EAST, W_DOWN, W_N };
static const char *const COL_NAME[W_N] = { "north", "east", "down" };
static const char *const COL_ALIAS[W_N] = { "v_north", "v_east", "v_down" };
#define COL_ABSENT ((size_t)-1)

struct lv_wind {
    lv_table *tab;   /* over h [m]: north, east[, down] in m/s; NULL: constant. Profiles:
                      * north and east of each profile in turn (2 n_prof outputs) */
    int has_down;
    double c[W_N];   /* the constant wind, m/s (tab NULL) */
    size_t n_prof;   /* 0: not a profile wind; else profiles at the times t_prof */
    double t_prof[LV_WIND_PROFILES_MAX]; /* s, mission time, strictly increasing */
    /* a disturbed wind (lv_wind_create_disturbed): base (NULL: still air) + dist; borrowed */
    const lv_wind_disturbance *dist;
    const lv_wind *base;
    /* a perturbed wind (lv_wind_create_perturbed): base (NULL: still air) + pert's north and
     * east; borrowed */
    const lv_perturbation *pert;
};

void lv_wind_free(lv_wind *w)
{
    if (w == NULL)
        return;
    lv_table_free(w->tab);
    free(w);
}

lv_status lv_wind_create_const(double north, double east, double down, lv_wind **out,
                               lv_err *err)
{
    if (out == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_wind_create_const: NULL argument");
    *out = NULL;
    if (!isfinite(north) || !isfinite(east) || !isfinite(down))
        return lv_fail(err, LV_ERR_INPUT, "constant wind (%g, %g, %g) m/s (north, east, down) "
                       "must be finite", north, east, down);
    lv_wind *w = calloc(1, sizeof *w);
    if (w == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "wind: out of memory");
    w->c[W_NORTH] = north;
    w->c[W_EAST] = east;
    w->c[W_DOWN] = down;
    w->has_down = 1;
    *out = w;
    return LV_OK;
}

static const char *str_or_empty(const char *const *a, size_t k)
{
    return a != NULL && a[k] != NULL ? a[k] : "";
}

/* Output index of each component: by position (Modelica CombiTable1D columns col2, col3,
 * col4 of a MAT matrix), otherwise by name or alias. Down may be absent. */
static lv_status resolve_columns(const lv_table_spec *sp, const char *path, size_t *k,
                                 lv_err *err)
{
    const size_t n_out = sp->n_out;
    if (n_out >= 1 && strcmp(str_or_empty(sp->out_name, 0), "col2") == 0) {
        if (n_out < 2 || n_out > 3)
            return lv_fail(err, LV_ERR_INPUT,
                           "%s: wind table has %zu output columns; need 2 or 3 after the "
                           "altitude: north, east[, down] [m/s]",
                           path, n_out);
        for (size_t c = 0; c < W_N; c++)
            k[c] = c < n_out ? c : COL_ABSENT;
        return LV_OK;
    }
    for (size_t c = 0; c < W_N; c++)
        k[c] = COL_ABSENT;
    for (size_t j = 0; j < n_out; j++) {
        const char *nm = str_or_empty(sp->out_name, j);
        size_t c = 0;
        while (c < W_N && strcmp(nm, COL_NAME[c]) != 0 && strcmp(nm, COL_ALIAS[c]) != 0)
            c++;
        if (c == W_N) {
            lv_suggest sg;
            char hint[128];
            lv_suggest_init(&sg, nm);
            for (size_t i = 0; i < W_N; i++) {
                lv_suggest_add(&sg, COL_NAME[i]);
                lv_suggest_add(&sg, COL_ALIAS[i]);
            }
            lv_suggest_text(&sg, hint, sizeof hint);
            return lv_fail(err, LV_ERR_INPUT,
                           "%s: wind table: unknown column '%s'%s (columns: north, east, down "
                           "or v_north, v_east, v_down)",
                           path, nm, hint);
        }
        if (k[c] != COL_ABSENT)
            return lv_fail(err, LV_ERR_INPUT, "%s: wind table: two columns for '%s' ('%s', '%s')",
                           path, COL_NAME[c], str_or_empty(sp->out_name, k[c]), nm);
        k[c] = j;
    }
    for (size_t c = 0; c < 2; c++)
        if (k[c] == COL_ABSENT)
            return lv_fail(err, LV_ERR_INPUT,
                           "%s: wind table has no column '%s' (or '%s'); the header must be "
                           "\"h [m], north [m/s], east [m/s][, down [m/s]]\"",
                           path, COL_NAME[c], COL_ALIAS[c]);
    return LV_OK;
}

static lv_status check_units(const lv_table_spec *sp, const char *path, const size_t *k,
                             lv_err *err)
{
    const char *u = sp->axis_unit[0] != NULL ? sp->axis_unit[0] : "";
    if (u[0] != '\0' && strcmp(u, "m") != 0)
        return lv_fail(err, LV_ERR_INPUT,
                       "%s: altitude column '%s' has unit '%s'; expected 'm'", path,
                       sp->axis_name[0] != NULL ? sp->axis_name[0] : "", u);
    for (size_t c = 0; c < W_N; c++) {
        if (k[c] == COL_ABSENT)
            continue;
        u = str_or_empty(sp->out_unit, k[c]);
        if (u[0] != '\0' && strcmp(u, "m/s") != 0)
            return lv_fail(err, LV_ERR_INPUT, "%s: column '%s' has unit '%s'; expected 'm/s'",
                           path, str_or_empty(sp->out_name, k[c]), u);
    }
    return LV_OK;
}

typedef struct wind_load {
    const char *path;
    const lv_table_opts *opts;
    lv_wind *w;
} wind_load;

/* The loaded file: a compact table with the components in NED order (so that evaluation
 * needs no buffer for columns it does not use), or a constant for a single row. */
static lv_status wind_from_spec(const lv_table_spec *sp, void *user, lv_err *err)
{
    wind_load *wl = user;
    const char *path = wl->path;
    if (sp->n_dims != 1)
        return lv_fail(err, LV_ERR_INPUT,
                       "%s: a wind table has one axis (altitude), this one has %zu", path,
                       sp->n_dims);
    size_t k[W_N];
    lv_status st = resolve_columns(sp, path, k, err);
    if (st == LV_OK)
        st = check_units(sp, path, k, err);
    if (st != LV_OK)
        return st;
    const size_t n = sp->n[0], n_raw = sp->n_out;
    const size_t n_out = k[W_DOWN] != COL_ABSENT ? 3 : 2;
    if (n == 0)
        return lv_fail(err, LV_ERR_INPUT, "%s: wind table has no rows", path);
    lv_wind *w = calloc(1, sizeof *w);
    double *y = malloc(n * n_out * sizeof *y);
    if (w == NULL || y == NULL) {
        free(w);
        free(y);
        return lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", path);
    }
    for (size_t i = 0; i < n; i++)
        for (size_t c = 0; c < n_out; c++)
            y[i * n_out + c] = sp->y[i * n_raw + k[c]];
    w->has_down = n_out == 3;
    if (n == 1) { /* one row: the same wind at every altitude */
        for (size_t c = 0; c < n_out; c++) {
            w->c[c] = y[c];
            if (!isfinite(y[c]))
                st = lv_fail(err, LV_ERR_INPUT, "%s: wind value %g is not finite", path, y[c]);
        }
    } else {
        static const char *const units[W_N] = { "m/s", "m/s", "m/s" };
        lv_table_spec spec = { 0 };
        spec.n_dims = 1;
        spec.n[0] = n;
        spec.x[0] = sp->x[0];
        spec.n_out = n_out;
        spec.y = y;
        spec.interp = wl->opts->interp;
        spec.extrap = wl->opts->extrap;
        spec.name = sp->name;
        spec.axis_name[0] = sp->axis_name[0];
        spec.axis_unit[0] = "m";
        spec.out_name = COL_NAME;
        spec.out_unit = units;
        st = lv_table_create(&spec, &w->tab, err);
        if (st != LV_OK)
            lv_fail_prefix(err, st, "%s", path);
    }
    free(y);
    if (st != LV_OK) {
        lv_wind_free(w);
        return st;
    }
    wl->w = w;
    return LV_OK;
}

lv_status lv_wind_create_table_opts(const char *path, const char *var,
                                    const lv_table_opts *opts, lv_wind **out, lv_err *err)
{
    if (out == NULL || path == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_wind_create_table: NULL argument");
    *out = NULL;
    static const lv_table_opts deflt = { LV_INTERP_LINEAR, LV_EXTRAP_CLAMP, 0 };
    wind_load wl = { path, opts != NULL ? opts : &deflt, NULL };
    const lv_status st = lv_table_load_spec(path, var, wl.opts, wind_from_spec, &wl, err);
    if (st != LV_OK) {
        lv_wind_free(wl.w);
        return st;
    }
    *out = wl.w;
    return LV_OK;
}

lv_status lv_wind_create_table(const char *path, const char *var, lv_wind **out, lv_err *err)
{
    return lv_wind_create_table_opts(path, var, NULL, out, err);
}

int lv_wind_is_constant(const lv_wind *w)
{
    return w->dist == NULL && w->pert == NULL && w->tab == NULL;
}

void lv_wind_range(const lv_wind *w, double *h_lo, double *h_hi)
{
    if ((w->dist != NULL || w->pert != NULL) && w->base != NULL) {
        lv_wind_range(w->base, h_lo, h_hi);
        return;
    }
    if (w->tab == NULL) {
        *h_lo = -INFINITY;
        *h_hi = INFINITY;
        return;
    }
    size_t n = 0;
    const double *h = lv_table_breakpoints(w->tab, 0, &n);
    *h_lo = h[0];
    *h_hi = h[n - 1];
}

/* Profiles: each profile's north and east at h (one table row lookup), then linearly in time
 * between the two profiles around t; before the first and after the last, that profile. */
static lv_status profiles_eval(const lv_wind *w, lv_table_cursor *cur, double t, double h,
                               double v_ned[3], lv_err *err)
{
    if (isnan(t))
        return lv_fail(err, LV_ERR_INPUT, "wind: time is NaN");
    double y[2 * LV_WIND_PROFILES_MAX];
    const lv_status st = lv_table_eval1(w->tab, cur, h, y, err); /* NaN h */
    if (st != LV_OK)
        return err != NULL ? lv_fail_prefix(err, st, "wind") : st;
    const size_t n = w->n_prof;
    size_t k = 0;
    double f = 0.0; /* weight of profile k + 1 */
    if (t >= w->t_prof[n - 1]) {
        k = n - 1;
    } else if (t > w->t_prof[0]) {
        while (k + 2 < n && t >= w->t_prof[k + 1])
            k++;
        f = (t - w->t_prof[k]) / (w->t_prof[k + 1] - w->t_prof[k]);
    }
    const size_t k1 = f > 0.0 ? k + 1 : k;
    v_ned[0] = (1.0 - f) * y[2 * k] + f * y[2 * k1];
    v_ned[1] = (1.0 - f) * y[2 * k + 1] + f * y[2 * k1 + 1];
    v_ned[2] = 0.0;
    return LV_OK;
}

lv_status lv_wind_eval(const lv_wind *w, lv_table_cursor *cur, double h, double v_ned[3],
                       lv_err *err)
{
    return lv_wind_eval_at(w, cur, 0.0, h, v_ned, err);
}

lv_status lv_wind_eval_at(const lv_wind *w, lv_table_cursor *cur, double t, double h,
                          double v_ned[3], lv_err *err)
{
    if (w->dist != NULL || w->pert != NULL) {
        double d[3] = { 0.0, 0.0, 0.0 };
        if (w->base != NULL) {
            const lv_status st = lv_wind_eval_at(w->base, cur, t, h, v_ned, err);
            if (st != LV_OK)
                return st;
        } else if (isnan(h)) {
            return lv_fail(err, LV_ERR_INPUT, "wind: altitude is NaN");
        } else {
            v_ned[0] = v_ned[1] = v_ned[2] = 0.0;
        }
        if (w->dist != NULL)
            lv_wind_disturbance_eval(w->dist, h, d);
        else
            lv_perturbation_eval(w->pert, h, d); /* north, east */
        for (int c = 0; c < 3; c++)
            v_ned[c] += d[c];
        return LV_OK;
    }
    if (w->n_prof > 0)
        return profiles_eval(w, cur, t, h, v_ned, err);
    if (w->tab == NULL) {
        if (isnan(h))
            return lv_fail(err, LV_ERR_INPUT, "wind: altitude is NaN");
        v_ned[0] = w->c[W_NORTH];
        v_ned[1] = w->c[W_EAST];
        v_ned[2] = w->c[W_DOWN];
        return LV_OK;
    }
    double y[W_N] = { 0.0, 0.0, 0.0 };
    const lv_status st = lv_table_eval1(w->tab, cur, h, y, err); /* NaN; outside: ERROR */
    if (st != LV_OK)
        return err != NULL ? lv_fail_prefix(err, st, "wind") : st;
    v_ned[0] = y[W_NORTH];
    v_ned[1] = y[W_EAST];
    v_ned[2] = w->has_down ? y[W_DOWN] : 0.0;
    return LV_OK;
}

int lv_wind_fn_table(double t, double h, double lat, double lon, double v_wind_ned[3],
                     void *user)
{
    (void)lat, (void)lon;
    lv_wind_user *u = user;
    if (lv_wind_eval_at(u->w, &u->cur, t, h, v_wind_ned, NULL) == LV_OK)
        return 0;
    return isnan(h) || isnan(t) ? 1 : -1; /* outside the table under extrap: error: stop */
}

lv_status lv_wind_create_affine(const lv_wind *w, double scale, const double bias[3],
                                lv_wind **out, lv_err *err)
{
    if (w == NULL || out == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_wind_create_affine: NULL argument");
    *out = NULL;
    if (w->dist != NULL || w->pert != NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_wind_create_affine: a disturbed or perturbed "
                       "wind: disperse its base, then disturb the copy");
    const double b[W_N] = { bias ? bias[0] : 0.0, bias ? bias[1] : 0.0, bias ? bias[2] : 0.0 };
    if (w->tab == NULL)
        return lv_wind_create_const(scale * w->c[W_NORTH] + b[0], scale * w->c[W_EAST] + b[1],
                                    scale * w->c[W_DOWN] + (w->has_down ? b[2] : 0.0), out, err);
    lv_wind *c = calloc(1, sizeof *c);
    if (c == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "wind: out of memory");
    double s[2 * LV_WIND_PROFILES_MAX], bb[2 * LV_WIND_PROFILES_MAX];
    const size_t n_out = w->n_prof > 0 ? 2 * w->n_prof : w->has_down ? 3 : 2;
    for (size_t j = 0; j < n_out; j++) { /* profiles: north, east of each in turn */
        s[j] = scale;
        bb[j] = w->n_prof > 0 ? b[j % 2] : b[j];
    }
    c->has_down = w->has_down;
    c->n_prof = w->n_prof;
    memcpy(c->t_prof, w->t_prof, sizeof c->t_prof);
    lv_status st = lv_table_create_affine(w->tab, s, bb, &c->tab, err);
    if (st != LV_OK) {
        lv_wind_free(c);
        return lv_fail_prefix(err, st, "wind");
    }
    *out = c;
    return LV_OK;
}

/* ---- profile winds ------------------------------------------------------------------------ */

/* The wind of profile pr at altitude x: its levels linearly, the lowest level's wind below
 * them, tapering linearly to zero over [top, top + blend], zero above. */
static void profile_at(const lv_profile *pr, double blend, double x, double *vn, double *ve)
{
    const size_t n = pr->n_w;
    const double *z = pr->z_w;
    if (x <= z[0]) {
        *vn = pr->north[0];
        *ve = pr->east[0];
    } else if (x <= z[n - 1]) {
        size_t i = 0;
        while (i + 2 < n && x > z[i + 1])
            i++;
        const double f = (x - z[i]) / (z[i + 1] - z[i]);
        *vn = (1.0 - f) * pr->north[i] + f * pr->north[i + 1];
        *ve = (1.0 - f) * pr->east[i] + f * pr->east[i + 1];
    } else if (x < z[n - 1] + blend) {
        const double f = 1.0 - (x - z[n - 1]) / blend;
        *vn = f * pr->north[n - 1];
        *ve = f * pr->east[n - 1];
    } else {
        *vn = *ve = 0.0;
    }
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

lv_status lv_wind_create_profiles(const char *const *paths, const double *t, size_t n,
                                  double blend, lv_wind **out, lv_err *err)
{
    if (out == NULL || paths == NULL || t == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_wind_create_profiles: NULL argument");
    *out = NULL;
    if (n < 1 || n > LV_WIND_PROFILES_MAX)
        return lv_fail(err, LV_ERR_INPUT, "wind: %zu profiles; 1 to %d", n,
                       LV_WIND_PROFILES_MAX);
    if (!(blend > 0.0 && blend <= 1e6))
        return lv_fail(err, LV_ERR_INPUT, "wind: blend band %.9g m must be in (0, 1e6] m", blend);
    for (size_t k = 0; k < n; k++)
        if (!isfinite(t[k]) || (k > 0 && !(t[k] > t[k - 1])))
            return lv_fail(err, LV_ERR_INPUT, "wind: profile %zu ('%s') at t = %.9g s: the "
                           "profiles' times must be finite and increasing", k + 1, paths[k],
                           t[k]);
    lv_profile pr[LV_WIND_PROFILES_MAX];
    memset(pr, 0, sizeof pr);
    lv_wind *w = NULL;
    double *x = NULL, *y = NULL;
    size_t nx = 0;
    lv_status st = LV_OK;
    for (size_t k = 0; k < n && st == LV_OK; k++) {
        st = lv_profile_load(paths[k], &pr[k], err);
        if (st == LV_OK && pr[k].n_w == 0)
            st = lv_fail(err, LV_ERR_INPUT, "%s: the profile has no wind (speed and direction, or "
                         "north and east, at two levels at least)", paths[k]);
        nx += pr[k].n_w + 1;
    }
    if (st != LV_OK)
        goto done;
    /* One altitude grid for all profiles: every level of every profile and each top + blend.
     * Each profile's wind is piecewise linear with breakpoints among these, so linear
     * interpolation on the common grid reproduces it exactly. */
    x = malloc(nx * sizeof *x);
    y = malloc(nx * 2 * n * sizeof *y);
    w = calloc(1, sizeof *w);
    if (x == NULL || y == NULL || w == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "wind: out of memory");
        goto done;
    }
    size_t m = 0;
    for (size_t k = 0; k < n; k++) {
        memcpy(x + m, pr[k].z_w, pr[k].n_w * sizeof *x);
        m += pr[k].n_w;
        x[m++] = pr[k].z_w[pr[k].n_w - 1] + blend;
    }
    qsort(x, m, sizeof *x, cmp_double);
    size_t u = 0;
    for (size_t i = 0; i < m; i++)
        if (u == 0 || x[i] > x[u - 1])
            x[u++] = x[i];
    for (size_t i = 0; i < u; i++)
        for (size_t k = 0; k < n; k++)
            profile_at(&pr[k], blend, x[i], &y[(i * n + k) * 2], &y[(i * n + k) * 2 + 1]);
    char names[2 * LV_WIND_PROFILES_MAX][16];
    const char *np[2 * LV_WIND_PROFILES_MAX], *up[2 * LV_WIND_PROFILES_MAX];
    for (size_t j = 0; j < 2 * n; j++) {
        snprintf(names[j], sizeof names[j], "%s_%zu", j % 2 ? "east" : "north", j / 2 + 1);
        np[j] = names[j];
        up[j] = "m/s";
    }
    lv_table_spec spec = { 0 };
    spec.n_dims = 1;
    spec.n[0] = u;
    spec.x[0] = x;
    spec.n_out = 2 * n;
    spec.y = y;
    spec.interp = LV_INTERP_LINEAR;
    spec.extrap = LV_EXTRAP_CLAMP; /* below: the lowest levels' winds; above: zero */
    spec.name = "wind_profile";
    spec.axis_name[0] = "h";
    spec.axis_unit[0] = "m";
    spec.out_name = np;
    spec.out_unit = up;
    st = lv_table_create(&spec, &w->tab, err);
    if (st != LV_OK) {
        lv_fail_prefix(err, st, "%s", paths[0]);
        goto done;
    }
    w->n_prof = n;
    memcpy(w->t_prof, t, n * sizeof *t);
    *out = w;
    w = NULL;
done:
    for (size_t k = 0; k < n; k++)
        lv_profile_clear(&pr[k]);
    free(x);
    free(y);
    lv_wind_free(w);
    return st;
}

size_t lv_wind_profile_count(const lv_wind *w)
{
    if (w->dist != NULL || w->pert != NULL)
        return w->base != NULL ? lv_wind_profile_count(w->base) : 0;
    return w->n_prof;
}

lv_status lv_wind_create_disturbed(const lv_wind *base, const lv_wind_disturbance *d,
                                   lv_wind **out, lv_err *err)
{
    if (d == NULL || out == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_wind_create_disturbed: NULL argument");
    *out = NULL;
    lv_wind *w = calloc(1, sizeof *w);
    if (w == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "wind: out of memory");
    w->base = base;
    w->dist = d;
    w->has_down = 1;
    *out = w;
    return LV_OK;
}

lv_status lv_wind_create_perturbed(const lv_wind *base, const lv_perturbation *p, lv_wind **out,
                                   lv_err *err)
{
    if (p == NULL || out == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_wind_create_perturbed: NULL argument");
    *out = NULL;
    if (lv_perturbation_comp(p) != 2)
        return lv_fail(err, LV_ERR_INPUT, "lv_wind_create_perturbed: the perturbation has %zu "
                       "component(s); a wind's has 2 (north, east)", lv_perturbation_comp(p));
    lv_wind *w = calloc(1, sizeof *w);
    if (w == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "wind: out of memory");
    w->base = base;
    w->pert = p;
    w->has_down = 1;
    *out = w;
    return LV_OK;
}
