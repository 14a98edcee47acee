/* phase_kit.c - the build kit of the phase-model types (phase_kit.h): slot values, mission
 * parameters, the stack's mass, the environment, engines and ends of a built phase model. */
#include "mission/phase_kit.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"

const lv_traj_col lv_kit_planet_traj[LV_KIT_PLANET_TRAJ_N] = {
    {"r_eci_x", "m", "r_eci_x"}, {"r_eci_y", "m", "r_eci_y"}, {"r_eci_z", "m", "r_eci_z"},
    {"v_eci_x", "m/s", "v_eci_x"}, {"v_eci_y", "m/s", "v_eci_y"}, {"v_eci_z", "m/s", "v_eci_z"},
    {"body_mass", "kg", "m"},    {"lat", "rad", "lat"},       {"lon", "rad", "lon"},
    {"h", "m", "h"},             {"v_rel", "m/s", "v_rel"},   {"mach", "1", "mach"},
    {"q_dyn", "Pa", "q_dyn"},
    {"iip_lat", "rad", "iip_lat"}, {"iip_lon", "rad", "iip_lon"}, {"iip_tof", "s", "iip_tof"},
};

double lv_kit_val(const lv_build_ctx *bc, lv_slot s, double fallback)
{
    return s == LV_NO_SLOT ? fallback : bc->vals[s];
}

double lv_kit_param(const lv_build_ctx *bc, size_t i, double fallback)
{
    const lv_phase_def *ph = &bc->def->phases[bc->k];
    return ph->params != NULL && i < ph->type->n_mission_params
               ? lv_kit_val(bc, ph->params[i], fallback)
               : fallback;
}

lv_status lv_kit_resolve_params(const lv_mission_def *d, lv_phase_def *ph, lv_err *err)
{
    const lv_phase_type *t = ph->type;
    if (t->n_mission_params == 0)
        return LV_OK;
    if ((ph->params = malloc(t->n_mission_params * sizeof *ph->params)) == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    for (size_t i = 0; i < t->n_mission_params; i++) {
        ph->params[i] = LV_NO_SLOT;
        for (size_t j = 0; j < d->n_params; j++)
            if (strcmp(d->param_names[j], t->mission_params[i].name) == 0)
                ph->params[i] = d->param_values[j];
    }
    return LV_OK;
}

double lv_kit_stack_mass(const lv_build_ctx *bc, size_t first)
{
    const lv_mission_def *d = bc->def;
    const lv_phase_def *ph = &d->phases[bc->k];
    double m = 0.0;
    for (size_t i = first; i < ph->n_stages; i++) {
        const size_t si = ph->stages[i];
        m += lv_kit_val(bc, d->stages[si].dry_mass, 0.0) + bc->prop[si];
    }
    return m;
}

void lv_kit_heating(const lv_build_ctx *bc, double *nose_radius, double *k_sutton_graves)
{
    const lv_mission_def *d = bc->def;
    const lv_phase_def *ph = &d->phases[bc->k];
    const lv_planet_def *pd = &d->env.pdef;
    *nose_radius = lv_kit_val(bc, d->stages[ph->stages[ph->n_stages - 1]].nose_radius, 1.0);
    /* (a planet by its constants has its base's constant from the parser) */
    *k_sutton_graves = !isnan(pd->sutton_graves_k) ? pd->sutton_graves_k
                       : !pd->custom && d->env.planet != NULL && strcmp(d->env.planet, "mars") == 0
                           ? LV_SUTTON_GRAVES_MARS
                           : LV_SUTTON_GRAVES_EARTH;
}

lv_status lv_kit_begin(const lv_build_ctx *bc, lv_kit_model *k, int with_engines,
                       size_t end_size, size_t n_own, lv_err *err)
{
    const lv_phase_def *ph = &bc->def->phases[bc->k];
    memset(k, 0, sizeof *k);
    if (ph->type->world == LV_WORLD_PLANET && (bc->env == NULL || bc->env->gravity == NULL))
        return lv_fail(err, LV_ERR_INPUT, "model '%s' needs a planet world", ph->type->name);
    const size_t n_eng = with_engines ? lv_kit_engine_count(&bc->def->stages[ph->stages[0]]) : 0;
    k->n_own = n_own;
    if ((with_engines && (k->engines = calloc(n_eng + 1, sizeof *k->engines)) == NULL) ||
        (k->ends = calloc(ph->n_ends + 1, end_size)) == NULL ||
        (k->end = calloc(ph->n_ends + 1, sizeof *k->end)) == NULL ||
        (k->event_end = calloc(ph->n_ends + n_own + LV_KIT_MORE_EVENTS,
                               sizeof *k->event_end)) == NULL) {
        lv_kit_clear(k);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    for (size_t i = 0; i < ph->n_ends + n_own + LV_KIT_MORE_EVENTS; i++)
        k->event_end[i] = -1; /* a model's event that ends nothing (dof3's throttle_min) */
    lv_status st = lv_phase_env_get(bc, &k->env, err);
    if (st != LV_OK) {
        lv_kit_clear(k);
        return st;
    }
    if (k->env.wind != NULL)
        k->wind = (lv_wind_user)LV_WIND_USER_INIT(k->env.wind);
    return LV_OK;
}

void lv_kit_world(lv_kit_model *k, lv_planet *planet, const lv_gravity **gravity,
                  const lv_atmo **atmo, lv_wind_fn *wind, void **wind_user)
{
    *planet = k->env.planet;
    *gravity = k->env.gravity;
    *atmo = k->env.atmo;
    if (k->env.wind != NULL) {
        *wind = lv_wind_fn_table;
        *wind_user = &k->wind;
    }
}

const lv_aero_config *lv_kit_aero(const lv_build_ctx *bc, const lv_aero_def *a,
                                  lv_kit_model *k)
{
    if (a == NULL || !a->present)
        return NULL;
    lv_aero_def_config(a, bc->vals, &k->aero);
    return &k->aero;
}

void lv_kit_done(lv_kit_model *k, const lv_model_def *def, void *inst, void *self,
                 lv_phase_model **out)
{
    k->pm.def = def;
    k->pm.inst = inst;
    k->pm.event_end = k->event_end;
    k->pm.self = self;
    *out = &k->pm;
}

void lv_kit_clear(lv_kit_model *k)
{
    lv_phase_env_clear(&k->env);
    free(k->engines);
    free(k->ends);
    free(k->end);
    free(k->event_end);
    memset(k, 0, sizeof *k);
}

size_t lv_kit_engine_count(const lv_stage_def *st)
{
    size_t n = 0;
    for (size_t e = 0; e < st->n_engines; e++)
        n += (size_t)(st->engines[e].count > 0 ? st->engines[e].count : 1);
    return n;
}

double lv_kit_full_throttle(const lv_engine_config *eng, size_t n)
{
    double c = 1.0;
    for (size_t e = 0; e < n; e++)
        if (eng[e].throttle_max < c)
            c = eng[e].throttle_max;
    for (size_t e = 0; e < n; e++)
        if (eng[e].throttle_min > c)
            c = eng[e].throttle_min;
    return c;
}

size_t lv_kit_engines(const lv_build_ctx *bc, const lv_stage_def *st, lv_engine_config *out)
{
    /* the phase's bottom stage runs `engines:` of each kind (all without it); the last of a
     * kind's running engines are the ones its `engine_out:` entries stop, in their order */
    const lv_phase_def *ph = &bc->def->phases[bc->k];
    const int bottom = st == &bc->def->stages[ph->stages[0]];
    size_t n = 0;
    for (size_t e = 0; e < st->n_engines; e++) {
        const lv_engine_def *ed = &st->engines[e];
        const int count = ed->count > 0 ? ed->count : 1;
        const int run = bottom && ph->engines_run != NULL ? ph->engines_run[e] : count;
        const size_t first = n;
        for (int c = 0; c < run; c++) {
            lv_engine_config *ec = &out[n++];
            lv_engine_config_default(ec);
            ec->name = ed->name;
            ec->thrust_vac = lv_kit_val(bc, ed->thrust_vac, 0.0);
            ec->isp_vac = lv_kit_val(bc, ed->isp_vac, 0.0);
            ec->mdot = lv_kit_val(bc, ed->mdot, 0.0);
            ec->exit_area = lv_kit_val(bc, ed->exit_area, 0.0);
            ec->throttle_min = lv_kit_val(bc, ed->throttle_min, 0.0);
            ec->throttle_max = lv_kit_val(bc, ed->throttle_max, 1.0);
            ec->table = lv_build_table(bc, ed->table);
        }
        size_t last = n; /* engines [first, last) not yet given an engine-out */
        for (size_t j = 0; bottom && j < ph->n_engine_out; j++) {
            const lv_engine_out_def *o = &ph->engine_out[j];
            for (int c = 0; o->engine == e && c < o->count && last > first; c++)
                out[--last].out_after = lv_kit_val(bc, o->time, 0.0);
        }
    }
    return n;
}

size_t lv_kit_ends(const lv_build_ctx *bc, lv_kit_model *k, int burnout_event,
                   int *stop_at_burnout)
{
    const lv_phase_def *ph = &bc->def->phases[bc->k];
    size_t n = 0;
    for (size_t i = 0; i < k->n_own; i++)
        k->event_end[i] = -1;
    for (size_t j = 0; j < ph->n_ends; j++) {
        const lv_end_def *e = &ph->ends[j];
        if (e->kind == LV_END_VAR || e->kind == LV_END_TIME)
            continue; /* a stop condition of the simulation (run.c) */
        if (burnout_event && e->kind == LV_END_BURNOUT) {
            *stop_at_burnout = 1;
            k->event_end[0] = (int)j;
            continue;
        }
        k->event_end[k->n_own + n] = (int)j;
        k->end[n++] = (lv_kit_end){e, lv_kit_val(bc, e->value, 0.0)};
    }
    return n;
}

size_t lv_kit_flight_ends(const lv_build_ctx *bc, lv_kit_model *k, int *stop_at_burnout)
{
    static const lv_dof3_end_kind end_of[] = {
        [LV_END_ALTITUDE] = LV_DOF3_END_ALTITUDE, [LV_END_SPEED] = LV_DOF3_END_SPEED_REL,
        [LV_END_APOGEE] = LV_DOF3_END_APOGEE, [LV_END_IMPACT] = LV_DOF3_END_IMPACT};
    const size_t n = lv_kit_ends(bc, k, 1, stop_at_burnout);
    lv_dof3_end *ends = k->ends;
    for (size_t i = 0; i < n; i++) {
        const lv_end_def *e = k->end[i].def;
        ends[i] = (lv_dof3_end){e->name, end_of[e->kind], k->end[i].value, e->direction, 1};
    }
    return n;
}
