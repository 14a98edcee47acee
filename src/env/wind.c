/* wind.c - wind as a 1-axis table over geodetic altitude: north, east and optionally down
 * components in the local NED frame, m/s (lv_table.h); linear interpolation, clamped at the
 * ends of the table. An lv_wind_fn adapter lets the 3-DoF model use it directly. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/names.h"
#include "core/status.h"
#include "lvsim/lv_table.h"
#include "lvsim/lv_wind.h"

enum wind_col { W_NORTH, W_EAST, W_DOWN, W_N };
static const char *const COL_NAME[W_N] = { "north", "east", "down" };
static const char *const COL_ALIAS[W_N] = { "v_north", "v_east", "v_down" };
#define COL_ABSENT ((size_t)-1)

struct lv_wind {
    lv_table *tab; /* over h [m]: north, east[, down] in m/s; clamped */
    int has_down;
};

void lv_wind_free(lv_wind *w)
{
    if (w == NULL)
        return;
    lv_table_free(w->tab);
    free(w);
}

/* Output index of each component in `raw`: by name (or alias) for CSV, by position
 * (Modelica CombiTable1D columns) for MAT. Down may be absent. */
static lv_status resolve_columns(const lv_table *raw, const char *path, int mat, size_t *k,
                                 lv_err *err)
{
    const size_t n_out = lv_table_n_out(raw);
    if (mat) {
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
        const char *nm = lv_table_out_name(raw, j);
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
                           path, COL_NAME[c], lv_table_out_name(raw, k[c]), nm);
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

static lv_status check_units(const lv_table *raw, const char *path, const size_t *k,
                             lv_err *err)
{
    const char *u = lv_table_axis_unit(raw, 0);
    if (u[0] != '\0' && strcmp(u, "m") != 0)
        return lv_fail(err, LV_ERR_INPUT,
                       "%s: altitude column '%s' has unit '%s'; expected 'm'", path,
                       lv_table_axis_name(raw, 0), u);
    for (size_t c = 0; c < W_N; c++) {
        if (k[c] == COL_ABSENT)
            continue;
        u = lv_table_out_unit(raw, k[c]);
        if (u[0] != '\0' && strcmp(u, "m/s") != 0)
            return lv_fail(err, LV_ERR_INPUT, "%s: column '%s' has unit '%s'; expected 'm/s'",
                           path, lv_table_out_name(raw, k[c]), u);
    }
    return LV_OK;
}

lv_status lv_wind_create_table(const char *path, const char *var, lv_wind **out, lv_err *err)
{
    lv_table *raw = NULL;
    lv_wind *w = NULL;
    double *y = NULL, *row = NULL;
    lv_status st;

    if (out == NULL || path == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_wind_create_table: NULL argument");
    *out = NULL;
    const int mat = lv_table_path_is_mat(path);
    const lv_table_opts opts = { LV_INTERP_LINEAR, LV_EXTRAP_CLAMP };
    st = lv_table_load(path, var, &opts, &raw, err);
    if (st != LV_OK)
        return st;
    if (lv_table_n_dims(raw) != 1) {
        st = lv_fail(err, LV_ERR_INPUT,
                     "%s: a wind table has one axis (altitude), this one has %zu", path,
                     lv_table_n_dims(raw));
        goto fail;
    }
    size_t k[W_N];
    st = resolve_columns(raw, path, mat, k, err);
    if (st == LV_OK)
        st = check_units(raw, path, k, err);
    if (st != LV_OK)
        goto fail;

    /* A compact copy with the components in NED order, so that evaluation needs no
     * buffer for columns it does not use. */
    size_t n = 0;
    const double *h = lv_table_breakpoints(raw, 0, &n);
    const size_t n_raw = lv_table_n_out(raw);
    const size_t n_out = k[W_DOWN] != COL_ABSENT ? 3 : 2;
    st = LV_ERR_NOMEM;
    w = calloc(1, sizeof *w);
    y = malloc(n * n_out * sizeof *y);
    row = malloc(n_raw * sizeof *row);
    if (w == NULL || y == NULL || row == NULL) {
        lv_fail(err, st, "%s: out of memory", path);
        goto fail;
    }
    lv_table_cursor cur = LV_TABLE_CURSOR_INIT;
    for (size_t i = 0; i < n; i++) { /* exact at a breakpoint */
        st = lv_table_eval1(raw, &cur, h[i], row, err);
        if (st != LV_OK)
            goto fail;
        for (size_t c = 0; c < n_out; c++)
            y[i * n_out + c] = row[k[c]];
    }
    char axis_name[128];
    snprintf(axis_name, sizeof axis_name, "%s", lv_table_axis_name(raw, 0));
    static const char *const units[W_N] = { "m/s", "m/s", "m/s" };
    lv_table_spec spec = { 0 };
    spec.n_dims = 1;
    spec.n[0] = n;
    spec.x[0] = h;
    spec.n_out = n_out;
    spec.y = y;
    spec.interp = LV_INTERP_LINEAR;
    spec.extrap = LV_EXTRAP_CLAMP;
    spec.name = lv_table_name(raw);
    spec.axis_name[0] = axis_name;
    spec.axis_unit[0] = "m";
    spec.out_name = COL_NAME;
    spec.out_unit = units;
    st = lv_table_create(&spec, &w->tab, err);
    if (st != LV_OK)
        goto fail;
    w->has_down = n_out == 3;
    *out = w;
    w = NULL;
    st = LV_OK;
fail:
    lv_wind_free(w);
    free(row);
    free(y);
    lv_table_free(raw);
    return st;
}

void lv_wind_range(const lv_wind *w, double *h_lo, double *h_hi)
{
    size_t n = 0;
    const double *h = lv_table_breakpoints(w->tab, 0, &n);
    *h_lo = h[0];
    *h_hi = h[n - 1];
}

lv_status lv_wind_eval(const lv_wind *w, lv_table_cursor *cur, double h, double v_ned[3],
                       lv_err *err)
{
    double y[W_N] = { 0.0, 0.0, 0.0 };
    const lv_status st = lv_table_eval1(w->tab, cur, h, y, err); /* NaN is the only failure */
    if (st != LV_OK)
        return st;
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
    return lv_wind_eval(u->w, &u->cur, h, v_wind_ned, NULL) == LV_OK ? 0 : 1;
}
