/* aero.c - aerodynamic forces from coefficient tables over Mach, alpha, beta and altitude:
 * F = q S_ref C in wind axes (CD, CL, CY) or body axes (CA, CN, CY); axes and angles as in
 * Stevens, Lewis & Johnson, Aircraft Control and Simulation, 3rd ed., sec. 2.3. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "core/table_unit.h"
#include "vehicle/vehicle.h"

static const char *const coef_names[2][3] = {{"CD", "CL", "CY"}, {"CA", "CN", "CY"}};
static const char *const input_names[LV_AERO_IN_N] = {"mach", "alpha", "beta", "altitude"};

void lv_aero_config_default(lv_aero_config *c)
{
    memset(c, 0, sizeof *c);
    c->axes = LV_AERO_WIND;
    c->s_ref = 1.0;
}

void lv_aero_clear(lv_aero *a)
{
    if (a == NULL)
        return;
    for (size_t i = 0; i < a->n_tab; i++) {
        free(a->tab[i].y);
        a->tab[i].y = NULL;
    }
    a->n_tab = 0;
}

/* Adds `tab` to the distinct tables of `a` (or finds it there); *slot its index. */
static lv_status add_table(lv_aero *a, const lv_table *tab, const char *coef, int *slot,
                           lv_err *err)
{
    for (size_t i = 0; i < a->n_tab; i++) {
        if (a->tab[i].table == tab) {
            *slot = (int)i;
            return LV_OK;
        }
    }
    lv_aero_tab *t = &a->tab[a->n_tab];
    memset(t, 0, sizeof *t);
    t->table = tab;
    t->n_dims = lv_table_n_dims(tab);
    int used[LV_AERO_IN_N] = {0};
    for (size_t d = 0; d < t->n_dims; d++) {
        const char *ax = lv_table_axis_name(tab, d);
        int in = -1;
        for (int k = 0; k < LV_AERO_IN_N; k++)
            if (strcmp(ax, input_names[k]) == 0)
                in = k;
        if (in < 0)
            return lv_fail(err, LV_ERR_INPUT,
                           "aerodynamics %s: table '%s': axis %zu is named '%s'; an aerodynamic "
                           "table axis must be named 'mach', 'alpha', 'beta' or 'altitude'",
                           coef, lv_table_name(tab), d, ax);
        if (used[in]++)
            return lv_fail(err, LV_ERR_INPUT, "aerodynamics %s: table '%s': axis '%s' appears twice",
                           coef, lv_table_name(tab), ax);
        static const char *const axis_si[LV_AERO_IN_N] = {"1", "rad", "rad", "m"};
        char what[64];
        snprintf(what, sizeof what, "aerodynamics %s", coef);
        lv_status ust = lv_table_expect_unit(tab, 1, d, axis_si[in], what, err);
        if (ust != LV_OK)
            return ust;
        t->input[d] = in;
    }
    t->y = malloc(lv_table_n_out(tab) * sizeof *t->y);
    if (t->y == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    *slot = (int)a->n_tab++;
    return LV_OK;
}

lv_status lv_aero_init(lv_aero *a, const lv_aero_config *c, lv_err *err)
{
    memset(a, 0, sizeof *a);
    lv_status st = LV_OK;
    if (c->axes != LV_AERO_WIND && c->axes != LV_AERO_BODY)
        return lv_fail(err, LV_ERR_INPUT, "aerodynamics: axes = %d (LV_AERO_WIND or LV_AERO_BODY)",
                       (int)c->axes);
    if (!isfinite(c->s_ref) || !(c->s_ref > 0.0))
        return lv_fail(err, LV_ERR_INPUT, "aerodynamics: s_ref = %g m^2 (must be > 0)", c->s_ref);
    a->axes = c->axes;
    a->s_ref = c->s_ref;
    for (int i = 0; i < 3; i++) {
        const lv_aero_coef *k = &c->coef[i];
        const char *cn = coef_names[c->axes][i];
        a->coef_tab[i] = -1;
        if (k->table == NULL) {
            if (!isfinite(k->value)) {
                st = lv_fail(err, LV_ERR_INPUT, "aerodynamics %s: constant value %g", cn,
                             k->value);
                goto fail;
            }
            a->coef_value[i] = k->value;
            continue;
        }
        if ((st = add_table(a, k->table, cn, &a->coef_tab[i], err)) != LV_OK)
            goto fail;
        const char *out = k->output;
        if (out == NULL && lv_table_n_out(k->table) == 1) {
            a->coef_k[i] = 0;
            continue;
        }
        if (out == NULL)
            out = cn;
        if ((st = lv_table_out_index(k->table, out, &a->coef_k[i], err)) != LV_OK) {
            lv_fail_prefix(err, st, "aerodynamics %s: table '%s'", cn, lv_table_name(k->table));
            goto fail;
        }
    }
    return LV_OK;
fail:
    lv_aero_clear(a);
    return st;
}

lv_status lv_aero_coefs(lv_aero *a, double mach, double alpha, double beta, double h,
                        double coef[3], lv_err *err)
{
    const double in[LV_AERO_IN_N] = {mach, alpha, beta, h};
    for (size_t i = 0; i < a->n_tab; i++) {
        lv_aero_tab *t = &a->tab[i];
        double x[LV_TABLE_MAX_DIMS];
        for (size_t d = 0; d < t->n_dims; d++)
            x[d] = in[t->input[d]];
        lv_status st = lv_table_eval(t->table, &t->cur, x, t->y, err);
        if (st != LV_OK)
            return err ? lv_fail_prefix(err, st, "aerodynamics") : st;
    }
    for (int i = 0; i < 3; i++)
        coef[i] = a->coef_tab[i] < 0 ? a->coef_value[i] : a->tab[a->coef_tab[i]].y[a->coef_k[i]];
    return LV_OK;
}

void lv_aero_force_wind(const lv_aero *a, const double coef[3], double qs, double ca, double sa,
                        double cb, double sb, double f_w[3])
{
    if (a->axes == LV_AERO_WIND) {
        f_w[0] = -qs * coef[0]; /* drag */
        f_w[1] = qs * coef[2];  /* side force */
        f_w[2] = -qs * coef[1]; /* lift */
        return;
    }
    const double fb[3] = {-qs * coef[0], qs * coef[2], -qs * coef[1]};
    /* f_w = C_body_wind^T f_b with rows of C_body_wind = R2(alpha) R3(-beta):
     *   x_b = ( ca cb, -ca sb, -sa ),  y_b = ( sb, cb, 0 ),  z_b = ( sa cb, -sa sb, ca ) */
    f_w[0] = ca * cb * fb[0] + sb * fb[1] + sa * cb * fb[2];
    f_w[1] = -ca * sb * fb[0] + cb * fb[1] - sa * sb * fb[2];
    f_w[2] = -sa * fb[0] + ca * fb[2];
}
