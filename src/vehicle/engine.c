/* engine.c - rocket engines: vacuum thrust with Isp or mass flow, nozzle-exit pressure
 * loss F = c F_vac - p_amb A_exit (Sutton & Biblarz, Rocket Propulsion Elements, 9th ed.,
 * eq. 2-14), throttle limits, thrust and mass flow from time tables. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/status.h"
#include "core/table_unit.h"
#include "vehicle/vehicle.h"

void lv_engine_config_default(lv_engine_config *c)
{
    memset(c, 0, sizeof *c);
    c->throttle_min = 0.0;
    c->throttle_max = 1.0;
}

static int is_time_axis(const char *name)
{
    return strcmp(name, "time") == 0 || strcmp(name, "t") == 0;
}

lv_status lv_engine_init(lv_engine *e, const lv_engine_config *c, size_t index, lv_err *err)
{
    memset(e, 0, sizeof *e);
    if (c->name != NULL && c->name[0] != '\0')
        snprintf(e->name, sizeof e->name, "%s", c->name);
    else
        snprintf(e->name, sizeof e->name, "engine%zu", index);
    const char *n = e->name;

    if (!isfinite(c->throttle_min) || !isfinite(c->throttle_max) || c->throttle_min < 0.0 ||
        !(c->throttle_max > 0.0) || c->throttle_max < c->throttle_min ||
        c->throttle_max > LV_THROTTLE_MAX)
        return lv_fail(err, LV_ERR_INPUT,
                       "engine '%s': throttle limits [%g, %g] invalid (need 0 <= min <= max, "
                       "0 < max <= %g: a throttle scales the rated thrust thrust_vac, at most "
                       "twice)",
                       n, c->throttle_min, c->throttle_max, LV_THROTTLE_MAX);
    if (!isfinite(c->exit_area) || c->exit_area < 0.0)
        return lv_fail(err, LV_ERR_INPUT, "engine '%s': exit_area = %g m^2 (must be >= 0)", n,
                       c->exit_area);
    if (!isfinite(c->isp_vac) || c->isp_vac < 0.0)
        return lv_fail(err, LV_ERR_INPUT, "engine '%s': isp_vac = %g s (must be >= 0)", n,
                       c->isp_vac);
    if (!isfinite(c->mdot) || c->mdot < 0.0)
        return lv_fail(err, LV_ERR_INPUT, "engine '%s': mdot = %g kg/s (must be >= 0)", n,
                       c->mdot);
    if (isnan(c->out_after) || c->out_after < 0.0)
        return lv_fail(err, LV_ERR_INPUT, "engine '%s': out_after = %g s (must be > 0, or 0: "
                       "never out)", n, c->out_after);
    e->out_after = c->out_after > 0.0 ? c->out_after : INFINITY;
    e->t_out = INFINITY;
    e->exit_area = c->exit_area;
    e->thr_min = c->throttle_min;
    e->thr_max = c->throttle_max;
    e->k_mdot = (size_t)-1;
    if (c->isp_vac > 0.0)
        e->mdot_per_thrust = 1.0 / (c->isp_vac * LV_G0);

    if (c->table == NULL) {
        if (!isfinite(c->thrust_vac) || !(c->thrust_vac > 0.0))
            return lv_fail(err, LV_ERR_INPUT, "engine '%s': thrust_vac = %g N (must be > 0)", n,
                           c->thrust_vac);
        if (c->mdot > 0.0)
            e->mdot_full = c->mdot;
        else if (c->isp_vac > 0.0)
            e->mdot_full = c->thrust_vac / (c->isp_vac * LV_G0); /* Isp definition */
        else
            return lv_fail(err, LV_ERR_INPUT,
                           "engine '%s': give isp_vac (s) or mdot (kg/s); both are 0", n);
        e->thrust_vac = c->thrust_vac;
        return LV_OK;
    }

    const lv_table *tab = c->table;
    e->table = tab;
    e->n_out = lv_table_n_out(tab);
    if (lv_table_n_dims(tab) != 1 || !is_time_axis(lv_table_axis_name(tab, 0)))
        return lv_fail(err, LV_ERR_INPUT,
                       "engine '%s': table '%s' must have exactly one axis named 'time' "
                       "(has %zu, the first named '%s')",
                       n, lv_table_name(tab), lv_table_n_dims(tab), lv_table_axis_name(tab, 0));
    lv_status st = lv_table_out_index(tab, "thrust", &e->k_thrust, err);
    if (st != LV_OK)
        return lv_fail_prefix(err, st, "engine '%s': table '%s' needs an output 'thrust' [N]", n,
                              lv_table_name(tab));
    char what[LV_ENGINE_NAME_MAX + 16];
    snprintf(what, sizeof what, "engine '%s'", n);
    if ((st = lv_table_expect_unit(tab, 1, 0, "s", what, err)) != LV_OK ||
        (st = lv_table_expect_unit(tab, 0, e->k_thrust, "N", what, err)) != LV_OK)
        return st;
    size_t k;
    if (lv_table_out_index(tab, "mdot", &k, NULL) == LV_OK) {
        if ((st = lv_table_expect_unit(tab, 0, k, "kg/s", what, err)) != LV_OK)
            return st;
        e->k_mdot = k;
    }
    else if (!(c->isp_vac > 0.0))
        return lv_fail(err, LV_ERR_INPUT,
                       "engine '%s': table '%s' has no output 'mdot' and isp_vac is 0: give one", n,
                       lv_table_name(tab));
    return LV_OK;
}

void lv_engine_start(lv_engine *e, double t0)
{
    e->t_out = t0 + e->out_after;
    e->out = 0;
}

int lv_engine_out_event(lv_engine *e, double t)
{
    if (e->out || !(e->t_out <= t))
        return 0;
    e->out = 1;
    return 1;
}

double lv_engine_throttle(const lv_engine *e, double throttle)
{
    return throttle < e->thr_min ? e->thr_min : throttle > e->thr_max ? e->thr_max : throttle;
}

lv_status lv_engine_eval(lv_engine *e, double t, double throttle, double p_amb, double *buf,
                         double *thrust, double *mdot, lv_err *err)
{
    if (e->out) { /* an engine-out: this engine gives nothing from its instant on */
        *thrust = *mdot = 0.0;
        return LV_OK;
    }
    const double c = lv_engine_throttle(e, throttle);
    double f_vac = e->thrust_vac, md = e->mdot_full;
    if (e->table != NULL) {
        lv_status st = lv_table_eval1(e->table, &e->cur, t, buf, err);
        if (st != LV_OK)
            return err ? lv_fail_prefix(err, st, "engine '%s'", e->name) : st;
        f_vac = buf[e->k_thrust];
        md = e->k_mdot != (size_t)-1 ? buf[e->k_mdot] : f_vac * e->mdot_per_thrust;
    }
    /* Net thrust: the exit-plane pressure term of the thrust equation; a nozzle cannot
     * pull backwards, so heavy over-expansion floors at 0 (continuous, a kink only). */
    const double f = c * f_vac - p_amb * e->exit_area;
    *thrust = f > 0.0 ? f : 0.0;
    *mdot = c * md;
    return LV_OK;
}
