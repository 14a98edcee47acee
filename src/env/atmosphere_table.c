/* atmosphere_table.c - the "table" model: any atmosphere as a 1-axis table over geometric
 * altitude, read from a CSV or MAT file (lv_table.h). T is interpolated linearly, p and rho
 * log-linearly (linear in ln p, ln rho: exact for an isothermal, exponential profile); a and
 * mu, when not tabulated, from T with the U.S. Standard Atmosphere 1976 eqs. (50), (51). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/names.h"
#include "core/status.h"
#include "env/atmosphere.h"
#include "lvsim/lv_table.h"

/* Columns of the file, in the order of a MAT matrix (after the altitude column). */
enum table_col { COL_T, COL_P, COL_RHO, COL_A, COL_MU, COL_N };
static const char *const COL_NAME[COL_N] = { "T", "p", "rho", "a", "mu" };
#define COL_REQUIRED 3 /* T, p, rho */
#define COL_ABSENT ((size_t)-1)

typedef struct table_par {
    lv_table *tab;      /* over h [m]: T, ln p, ln rho, then a and mu if tabulated */
    size_t k_a, k_mu;   /* output index in `tab`, or COL_ABSENT */
    double h_lo, h_hi;  /* m, first and last breakpoint */
    char src[128];      /* file name for messages */
} table_par;

static void table_par_free(void *par)
{
    table_par *p = par;
    if (p == NULL)
        return;
    lv_table_free(p->tab);
    free(p);
}

static lv_status table_par_create(void **out, lv_err *err)
{
    *out = NULL;
    return lv_fail(err, LV_ERR_INPUT,
                   "atmosphere model 'table' reads its data from a file: create it with "
                   "lv_atmo_create_table(path, var, ...)");
}

static lv_status table_par_set(void *par, const char *key, double value, lv_err *err)
{
    (void)value;
    const table_par *p = par;
    return lv_fail(err, LV_ERR_NOTFOUND,
                   "atmosphere model 'table' (%s) has no parameter '%s' (it has none; its "
                   "data come from the file)",
                   p->src, key);
}

/* Sutherland's law, eq. (51). */
static double viscosity(double T)
{
    return LV_US76_BETA * T * sqrt(T) / (T + LV_US76_S);
}

static lv_status table_eval(const void *par, double h, lv_atmo_state *out, lv_err *err)
{
    const table_par *p = par;
    if (!(h >= p->h_lo && h <= p->h_hi)) {
        if (isnan(h))
            return lv_fail(err, LV_ERR_INPUT,
                           "atmosphere model 'table' (%s): altitude is NaN; the table covers "
                           "%.9g m to %.9g m",
                           p->src, p->h_lo, p->h_hi);
        /* the excess in its own digits: an altitude a hair above the top would print as
         * the top itself with %.9g ("10000 m is outside ... to 10000 m") */
        return lv_fail(err, LV_ERR_INPUT,
                       "atmosphere model 'table' (%s): altitude %.17g m is %s the table's "
                       "range %.9g m to %.9g m (by %.3g m)",
                       p->src, h, h > p->h_hi ? "above" : "below", p->h_lo, p->h_hi,
                       h > p->h_hi ? h - p->h_hi : p->h_lo - h);
    }
    double y[COL_N];
    const lv_status st = lv_table_eval1(p->tab, NULL, h, y, err);
    if (st != LV_OK)
        return st;
    const double T = y[COL_T];
    out->T = T;
    out->p = exp(y[COL_P]);
    out->rho = exp(y[COL_RHO]);
    out->a = p->k_a != COL_ABSENT ? y[p->k_a]
                                  : sqrt(LV_US76_GAMMA * LV_US76_RSTAR * T / LV_US76_M0);
    out->mu = p->k_mu != COL_ABSENT ? y[p->k_mu] : viscosity(T);
    out->M = LV_US76_M0;
    return LV_OK;
}

const lv_atmo_model lv_atmo_table = {
    "table",
    "T, p, rho (and optionally a, mu) over altitude from a CSV or MAT file",
    table_par_create,
    table_par_free,
    table_par_set,
    table_eval,
};

/* ---- loading ---------------------------------------------------------------------------- */

/* Line number of data row `row` (0-based) of a 1-D CSV file: the (row + 2)-th line that is
 * neither blank nor a comment, as lv_table_load_csv counts them. 0 if not found. */
static size_t csv_data_line(const char *path, size_t row)
{
    FILE *fp = fopen(path, "rb");
    if (fp == NULL)
        return 0;
    size_t line = 1, seen = 0, found = 0;
    int content = 0, comment = 0, c;
    while (found == 0 && (c = getc(fp)) != EOF) {
        if (c == '\n') {
            if (content && seen++ == row + 1)
                found = line;
            line++;
            content = comment = 0;
        } else if (c == '#') {
            comment = 1;
        } else if (!comment && c != ' ' && c != '\t' && c != '\r') {
            content = 1;
        }
    }
    if (found == 0 && content && seen == row + 1) /* last line without a newline */
        found = line;
    fclose(fp);
    return found;
}

/* A unit given in the file must be the SI unit the model expects (no conversion). */
static int unit_ok(const char *unit, const char *const *accepted)
{
    if (unit[0] == '\0')
        return 1;
    for (size_t i = 0; accepted[i] != NULL; i++)
        if (strcmp(unit, accepted[i]) == 0)
            return 1;
    return 0;
}

static const char *const UNIT_M[] = { "m", NULL };
static const char *const UNIT_K[] = { "K", NULL };
static const char *const UNIT_PA[] = { "Pa", NULL };
static const char *const UNIT_RHO[] = { "kg/m3", "kg/m^3", NULL };
static const char *const UNIT_A[] = { "m/s", NULL };
static const char *const UNIT_MU[] = { "Pa s", "Pa*s", "Pa.s", "kg/(m s)", NULL };
static const char *const *const COL_UNITS[COL_N] = { UNIT_K, UNIT_PA, UNIT_RHO, UNIT_A,
                                                     UNIT_MU };

/* Output index of each column in `raw` (COL_ABSENT when an optional one is missing): by
 * name for CSV, by position (Modelica CombiTable1D columns) for MAT. */
static lv_status resolve_columns(const lv_table *raw, const char *path, int mat, size_t *k,
                                 lv_err *err)
{
    const size_t n_out = lv_table_n_out(raw);
    if (mat) {
        if (n_out < COL_REQUIRED || n_out > COL_N)
            return lv_fail(err, LV_ERR_INPUT,
                           "%s: atmosphere table has %zu output columns; need 3 to 5 after the "
                           "altitude: T [K], p [Pa], rho [kg/m3][, a [m/s][, mu [Pa s]]]",
                           path, n_out);
        for (size_t c = 0; c < COL_N; c++)
            k[c] = c < n_out ? c : COL_ABSENT;
        return LV_OK;
    }
    for (size_t c = 0; c < COL_N; c++) {
        lv_status st = lv_table_out_index(raw, COL_NAME[c], &k[c], err);
        if (st == LV_OK)
            continue;
        k[c] = COL_ABSENT;
        if (c < COL_REQUIRED)
            return lv_fail_prefix(err, LV_ERR_INPUT,
                                  "%s: atmosphere table needs columns T [K], p [Pa], "
                                  "rho [kg/m3] (optional: a [m/s], mu [Pa s])",
                                  path);
    }
    for (size_t j = 0; j < n_out; j++) { /* a misspelt optional column must not vanish */
        int known = 0;
        for (size_t c = 0; c < COL_N && !known; c++)
            known = k[c] == j;
        if (known)
            continue;
        lv_suggest sg;
        char hint[128];
        lv_suggest_init(&sg, lv_table_out_name(raw, j));
        for (size_t c = 0; c < COL_N; c++)
            lv_suggest_add(&sg, COL_NAME[c]);
        lv_suggest_text(&sg, hint, sizeof hint);
        return lv_fail(err, LV_ERR_INPUT,
                       "%s: atmosphere table: unknown column '%s'%s (columns: T, p, rho, a, mu)",
                       path, lv_table_out_name(raw, j), hint);
    }
    return LV_OK;
}

static lv_status check_units(const lv_table *raw, const char *path, const size_t *k,
                             lv_err *err)
{
    const char *u = lv_table_axis_unit(raw, 0);
    if (!unit_ok(u, UNIT_M))
        return lv_fail(err, LV_ERR_INPUT,
                       "%s: altitude column '%s' has unit '%s'; expected 'm' (geometric "
                       "altitude in metres)",
                       path, lv_table_axis_name(raw, 0), u);
    for (size_t c = 0; c < COL_N; c++) {
        if (k[c] == COL_ABSENT)
            continue;
        u = lv_table_out_unit(raw, k[c]);
        if (!unit_ok(u, COL_UNITS[c]))
            return lv_fail(err, LV_ERR_INPUT, "%s: column '%s' has unit '%s'; expected '%s'",
                           path, COL_NAME[c], u, COL_UNITS[c][0]);
    }
    return LV_OK;
}

lv_status lv_atmo_table_load(const char *path, const char *var, void **par, lv_err *err)
{
    lv_table *raw = NULL;
    table_par *p = NULL;
    double *y = NULL, *row = NULL;
    lv_status st;

    if (par == NULL || path == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_atmo_table_load: NULL argument");
    *par = NULL;
    const int mat = lv_table_path_is_mat(path);
    st = lv_table_load(path, var, NULL, &raw, err);
    if (st != LV_OK)
        return st;
    if (lv_table_n_dims(raw) != 1) {
        st = lv_fail(err, LV_ERR_INPUT,
                     "%s: an atmosphere table has one axis (altitude), this one has %zu", path,
                     lv_table_n_dims(raw));
        goto fail;
    }

    size_t k[COL_N];
    st = resolve_columns(raw, path, mat, k, err);
    if (st == LV_OK)
        st = check_units(raw, path, k, err);
    if (st != LV_OK)
        goto fail;

    size_t n = 0;
    const double *h = lv_table_breakpoints(raw, 0, &n);
    const size_t n_raw = lv_table_n_out(raw);
    size_t n_out = COL_REQUIRED;
    const char *names[COL_N] = { "T", "ln_p", "ln_rho", NULL, NULL };
    const char *units[COL_N] = { "K", "ln Pa", "ln kg/m3", NULL, NULL };
    size_t k_new[COL_N] = { COL_T, COL_P, COL_RHO, COL_ABSENT, COL_ABSENT };
    for (size_t c = COL_REQUIRED; c < COL_N; c++)
        if (k[c] != COL_ABSENT) {
            names[n_out] = COL_NAME[c];
            units[n_out] = COL_UNITS[c][0];
            k_new[c] = n_out++;
        }

    st = LV_ERR_NOMEM;
    p = calloc(1, sizeof *p);
    y = malloc(n * n_out * sizeof *y);
    row = malloc(n_raw * sizeof *row);
    if (p == NULL || y == NULL || row == NULL) {
        lv_fail(err, st, "%s: out of memory", path);
        goto fail;
    }
    /* Grid values: evaluating at a breakpoint returns the stored value exactly. */
    lv_table_cursor cur = LV_TABLE_CURSOR_INIT;
    for (size_t i = 0; i < n; i++) {
        st = lv_table_eval1(raw, &cur, h[i], row, err);
        if (st != LV_OK)
            goto fail;
        for (size_t c = 0; c < COL_N; c++) {
            if (k[c] == COL_ABSENT)
                continue;
            const double v = row[k[c]];
            if (!(v > 0.0)) {
                const size_t line = mat ? 0 : csv_data_line(path, i);
                if (line > 0)
                    st = lv_fail(err, LV_ERR_INPUT,
                                 "%s:%zu: %s = %.17g at altitude %.9g m must be positive", path,
                                 line, COL_NAME[c], v, h[i]);
                else
                    st = lv_fail(err, LV_ERR_INPUT,
                                 "%s: row %zu: %s = %.17g at altitude %.9g m must be positive",
                                 path, i + 1, COL_NAME[c], v, h[i]);
                goto fail;
            }
            y[i * n_out + k_new[c]] = c == COL_P || c == COL_RHO ? log(v) : v;
        }
    }

    char axis_name[128];
    snprintf(axis_name, sizeof axis_name, "%s", lv_table_axis_name(raw, 0));
    lv_table_spec spec = { 0 };
    spec.n_dims = 1;
    spec.n[0] = n;
    spec.x[0] = h;
    spec.n_out = n_out;
    spec.y = y;
    spec.interp = LV_INTERP_LINEAR;
    spec.extrap = LV_EXTRAP_ERROR;
    spec.name = lv_table_name(raw);
    spec.axis_name[0] = axis_name;
    spec.axis_unit[0] = "m";
    spec.out_name = names;
    spec.out_unit = units;
    st = lv_table_create(&spec, &p->tab, err);
    if (st != LV_OK)
        goto fail;
    p->k_a = k_new[COL_A];
    p->k_mu = k_new[COL_MU];
    p->h_lo = h[0];
    p->h_hi = h[n - 1];
    snprintf(p->src, sizeof p->src, "%s", path);
    *par = p;
    p = NULL;
    st = LV_OK;
fail:
    table_par_free(p);
    free(row);
    free(y);
    lv_table_free(raw);
    return st;
}
