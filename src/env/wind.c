/* wind.c - wind as a 1-axis table over geodetic altitude: north, east and optionally down
 * components in the local NED frame, m/s (lv_table.h), interpolated linearly (or as the
 * caller chooses) and clamped at the ends of the table unless told otherwise; or a constant
 * (one value, or a table of one row). An lv_wind_fn adapter lets the 3-DoF model use it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/names.h"
#include "core/status.h"
#include "io/table_load.h"
#include "lvsim/lv_table.h"
#include "lvsim/lv_wind.h"

enum wind_col { W_NORTH, W_EAST, W_DOWN, W_N };
static const char *const COL_NAME[W_N] = { "north", "east", "down" };
static const char *const COL_ALIAS[W_N] = { "v_north", "v_east", "v_down" };
#define COL_ABSENT ((size_t)-1)

struct lv_wind {
    lv_table *tab;   /* over h [m]: north, east[, down] in m/s; NULL: constant */
    int has_down;
    double c[W_N];   /* the constant wind, m/s (tab NULL) */
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
    static const lv_table_opts deflt = { LV_INTERP_LINEAR, LV_EXTRAP_CLAMP };
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

int lv_wind_is_constant(const lv_wind *w) { return w->tab == NULL; }

void lv_wind_range(const lv_wind *w, double *h_lo, double *h_hi)
{
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

lv_status lv_wind_eval(const lv_wind *w, lv_table_cursor *cur, double h, double v_ned[3],
                       lv_err *err)
{
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
    (void)t, (void)lat, (void)lon;
    lv_wind_user *u = user;
    if (lv_wind_eval(u->w, &u->cur, h, v_wind_ned, NULL) == LV_OK)
        return 0;
    return isnan(h) ? 1 : -1; /* outside the table under extrap: error: stop */
}

lv_status lv_wind_create_affine(const lv_wind *w, double scale, const double bias[3],
                                lv_wind **out, lv_err *err)
{
    if (w == NULL || out == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_wind_create_affine: NULL argument");
    *out = NULL;
    const double b[W_N] = { bias ? bias[0] : 0.0, bias ? bias[1] : 0.0, bias ? bias[2] : 0.0 };
    if (w->tab == NULL)
        return lv_wind_create_const(scale * w->c[W_NORTH] + b[0], scale * w->c[W_EAST] + b[1],
                                    scale * w->c[W_DOWN] + (w->has_down ? b[2] : 0.0), out, err);
    lv_wind *c = calloc(1, sizeof *c);
    if (c == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "wind: out of memory");
    const double s[W_N] = { scale, scale, scale };
    c->has_down = w->has_down;
    lv_status st = lv_table_create_affine(w->tab, s, b, &c->tab, err);
    if (st != LV_OK) {
        lv_wind_free(c);
        return lv_fail_prefix(err, st, "wind");
    }
    *out = c;
    return LV_OK;
}
