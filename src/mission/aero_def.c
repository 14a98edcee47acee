/* aero_def.c - `aero:` of a phase: reference area, axes, and each coefficient a constant, a
 * table of its own, or an output of the dataset's table (aero_def.h). The aerodynamic model
 * itself: src/vehicle/aero.c (dof3), src/models/flat.c (flat6: drag only). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/names.h"
#include "core/status.h"
#include "mission/aero_def.h"

#include "core/table_unit.h"

static const char *const coef_names[2][3] = {{"CD", "CL", "CY"}, {"CA", "CN", "CY"}};
static const char *const axis_names[] = {"mach", "alpha", "beta", "altitude"};

void lv_aero_def_clear(lv_aero_def *a)
{
    if (a == NULL)
        return;
    for (int k = 0; k < 3; k++) {
        lv_table_free(a->tab[k]);
        free(a->out[k]);
        free(a->file[k]);
        free(a->var[k]);
    }
    lv_table_free(a->table);
    free(a->table_file);
    free(a->table_var);
    memset(a, 0, sizeof *a);
}

static char *dup_str(const char *s)
{
    const size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d != NULL)
        memcpy(d, s, n);
    return d;
}

/* The axes of an aerodynamic table name its inputs: mach, alpha, beta, altitude. */
static lv_status check_axes(const lv_pctx *c, const lv_ynode *at, const char *what,
                           const char *key, const lv_table *t)
{
    int used[4] = {0};
    for (size_t d = 0; d < lv_table_n_dims(t); d++) {
        const char *ax = lv_table_axis_name(t, d);
        size_t k = 0;
        while (k < 4 && strcmp(ax, axis_names[k]) != 0)
            k++;
        if (k == 4) {
            lv_suggest sg;
            char hint[128];
            lv_suggest_init(&sg, ax);
            for (size_t j = 0; j < 4; j++)
                lv_suggest_add(&sg, axis_names[j]);
            lv_suggest_text(&sg, hint, sizeof hint);
            return lv_pk_fail(c, at, "%s: %s: table '%s': axis %zu is named '%s'%s; the axes of "
                              "an aerodynamic table are mach, alpha [rad], beta [rad], "
                              "altitude [m] (CSV: the header; MAT: a struct's field names, "
                              "docs/tables.md)", what, key, lv_table_name(t), d + 1, ax, hint);
        }
        if (used[k]++)
            return lv_pk_fail(c, at, "%s: %s: table '%s': axis '%s' appears twice", what, key,
                              lv_table_name(t), ax);
        static const char *const axis_si[] = {"1", "rad", "rad", "m"};
        if (lv_table_expect_unit(t, 1, d, axis_si[k], NULL, c->err) != LV_OK)
            return lv_pk_fail(c, at, "%s: %s: %s", what, key, c->err->msg);
    }
    for (size_t o = 0; o < lv_table_n_out(t); o++) /* coefficients are dimensionless */
        if (lv_table_expect_unit(t, 0, o, "1", NULL, c->err) != LV_OK)
            return lv_pk_fail(c, at, "%s: %s: %s", what, key, c->err->msg);
    return LV_OK;
}

/* The outputs of t as "a, b, c" for messages. */
static void out_list(const lv_table *t, char *buf, size_t cap)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t k = 0; k < lv_table_n_out(t) && used < cap; k++) {
        const int w = snprintf(buf + used, cap - used, "%s%s", k ? ", " : "",
                               lv_table_out_name(t, k));
        used += w > 0 ? (size_t)w : 0;
    }
}

/* A coefficient's own table: the output named by `output`, else the one named as the
 * coefficient, else the table's only output. */
static lv_status coef_table(const lv_pctx *c, const lv_ynode *key, const lv_ynode *v,
                            const char *what, const char *cn, lv_aero_def *a, int k)
{
    const lv_ynode *on = NULL;
    lv_status st = lv_pk_table_out(c, key, v, what, LV_EXTRAP_CLAMP, &a->file[k], &a->var[k],
                                   &on, &a->tab[k]);
    if (st != LV_OK || (st = check_axes(c, key, what, cn, a->tab[k])) != LV_OK)
        return st;
    const lv_table *t = a->tab[k];
    size_t idx;
    const char *name = NULL;
    char list[256];
    if (on != NULL) {
        if (lv_table_out_index(t, on->text, &idx, NULL) != LV_OK) {
            out_list(t, list, sizeof list);
            return lv_pk_fail(c, on, "%s: %s: table '%s' has no output '%.60s' (its outputs: %s)",
                              what, cn, lv_table_name(t), on->text, list);
        }
        name = on->text;
    } else if (lv_table_out_index(t, cn, &idx, NULL) == LV_OK) {
        name = cn;
    } else if (lv_table_n_out(t) == 1) {
        name = lv_table_out_name(t, 0);
    } else {
        out_list(t, list, sizeof list);
        return lv_pk_fail(c, key, "%s: %s: table '%s' has several outputs (%s) and none is "
                          "named %s: say which with {file: .., output: name}", what, cn,
                          lv_table_name(t), list, cn);
    }
    return (a->out[k] = dup_str(name)) != NULL ? LV_OK : lv_pk_nomem(c);
}

/* A plain scalar that reads as a number (also .inf, nan: refused as numbers, with the number
 * rules' message) is a constant; anything else a table reference. */
static int looks_numeric(const lv_ynode *v)
{
    if (v->kind != LV_YNODE_SCALAR || !v->plain || lv_yaml_is_null(v) || v->len == 0)
        return 0;
    const char *s = v->text;
    if (*s == '+' || *s == '-')
        s++;
    if (strcmp(s, ".inf") == 0 || strcmp(s, ".Inf") == 0 || strcmp(s, ".INF") == 0 ||
        strcmp(s, ".nan") == 0 || strcmp(s, ".NaN") == 0 || strcmp(s, ".NAN") == 0)
        return 1;
    char *end = NULL;
    (void)strtod(v->text, &end);
    return end != v->text && *end == '\0';
}

lv_status lv_aero_def_parse(const lv_pctx *c, const lv_ynode *n, const char *phase,
                            int drag_only, lv_aero_def *a)
{
    static const char *const akeys[] = {"s_ref", "axes", "table", "CD", "CL", "CY", "CA", "CN",
                                        NULL};
    static const char *const axes[] = {"wind", "body", NULL};
    char what[LV_WHAT_MAX], slot[LV_NAME_MAX + 32];
    const lv_ynode *v;
    lv_status st;
    size_t i = 0;
    memset(a, 0, sizeof *a);
    for (int k = 0; k < 3; k++)
        a->coef[k] = LV_NO_SLOT;
    a->s_ref = LV_NO_SLOT;
    snprintf(what, sizeof what, "phase '%s', aero", phase);
    if (n == NULL || lv_yaml_is_null(n))
        return LV_OK;
    if ((st = lv_pk_check_map(c, n, what, akeys)) != LV_OK)
        return st;
    a->present = 1;
    snprintf(slot, sizeof slot, "%s.aero.s_ref", phase);
    if ((st = lv_pk_need(c, n, what, "s_ref", &v)) != LV_OK ||
        (st = lv_pk_slot(c, v, what, "s_ref", slot, "m2", LV_RANGE_POS, 0, &a->s_ref)) != LV_OK)
        return st;
    if ((v = lv_pk_get(n, "axes")) != NULL &&
        (st = lv_pk_enum(c, v, what, "axes", axes, &i)) != LV_OK)
        return st;
    a->body_axes = i == 1;
    const char *const other[2][2] = {{"CA", "CN"}, {"CD", "CL"}};
    for (int k = 0; k < 2; k++)
        if (lv_pk_get(n, other[i][k]) != NULL)
            return lv_pk_fail(c, lv_pk_key(n, other[i][k]), "%s: '%s' belongs to axes: %s", what,
                              other[i][k], i == 0 ? "body" : "wind");
    const char *const *names = coef_names[i];
    for (int k = drag_only ? 1 : 3; k < 3; k++)
        if (lv_pk_get(n, names[k]) != NULL)
            return lv_pk_fail(c, lv_pk_key(n, names[k]), "%s: '%s': the flat world's body "
                              "flies at zero angle of attack and has no lift or side force; "
                              "it takes %s only", what, names[k], names[0]);
    int own = 0;
    for (int k = 0; k < 3; k++) {
        if ((v = lv_pk_get(n, names[k])) == NULL)
            continue;
        own++;
        if (looks_numeric(v)) {
            snprintf(slot, sizeof slot, "%s.aero.%s", phase, names[k]);
            st = lv_pk_slot(c, v, what, names[k], slot, "", LV_RANGE_ANY, 0, &a->coef[k]);
        } else {
            st = coef_table(c, lv_pk_key(n, names[k]), v, what, names[k], a, k);
        }
        if (st != LV_OK)
            return st;
    }
    if ((v = lv_pk_get(n, "table")) != NULL) {
        const lv_ynode *key = lv_pk_key(n, "table");
        if ((st = lv_pk_table(c, key, v, what, LV_EXTRAP_CLAMP, &a->table_file, &a->table_var,
                              &a->table)) != LV_OK ||
            (st = check_axes(c, key, what, "table", a->table)) != LV_OK)
            return st;
        int used = 0;
        size_t idx;
        for (int k = 0; k < (drag_only ? 1 : 3); k++) {
            if (lv_pk_get(n, names[k]) != NULL ||
                lv_table_out_index(a->table, names[k], &idx, NULL) != LV_OK)
                continue;
            if ((a->out[k] = dup_str(names[k])) == NULL)
                return lv_pk_nomem(c);
            used++;
        }
        if (used == 0) {
            char list[256], want[64] = "";
            size_t w = 0;
            for (int k = 0; k < (drag_only ? 1 : 3) && w < sizeof want; k++)
                if (lv_pk_get(n, names[k]) == NULL) {
                    const int r = snprintf(want + w, sizeof want - w, "%s%s", w ? ", " : "",
                                           names[k]);
                    w += r > 0 ? (size_t)r : 0;
                }
            out_list(a->table, list, sizeof list);
            return lv_pk_fail(c, key, "%s: table '%s' gives none of %s (its outputs: %s): name "
                              "its outputs as the coefficients, or give a table per "
                              "coefficient (%s: file)", what, lv_table_name(a->table),
                              w ? want : "the coefficients (each is given on its own)", list,
                              names[0]);
        }
    }
    return LV_OK;
}

void lv_aero_def_config(const lv_aero_def *a, const double *vals, lv_aero_config *out)
{
    lv_aero_config_default(out);
    out->axes = a->body_axes ? LV_AERO_BODY : LV_AERO_WIND;
    out->s_ref = vals[a->s_ref];
    for (int k = 0; k < 3; k++) {
        if (a->coef[k] != LV_NO_SLOT)
            out->coef[k] = (lv_aero_coef){NULL, NULL, vals[a->coef[k]]};
        else if (a->tab[k] != NULL)
            out->coef[k] = (lv_aero_coef){a->tab[k], a->out[k], 0.0};
        else if (a->out[k] != NULL)
            out->coef[k] = (lv_aero_coef){a->table, a->out[k], 0.0};
    }
}
