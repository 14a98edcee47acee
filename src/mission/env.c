/* env.c - the environment of a mission's phases: built once from the file's values when the
 * mission is loaded (planet and gravity, atmosphere, wind; shared read-only by every run), and
 * for one run from the run's values of the environment's slots (a planet given by its
 * constants, the exponential atmosphere's parameters, a constant wind). Format:
 * docs/mission-format.md ("environment"). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "mission/dispersion.h"
#include "mission/phase_type.h"

void lv_mission_env_clear(lv_mission_env *env)
{
    lv_gravity_free(env->gravity);
    lv_atmo_free(env->atmo);
    lv_wind_free(env->wind);
    memset(env, 0, sizeof *env);
}

static double slot_or(const double *vals, lv_slot s, double fallback)
{
    return s == LV_NO_SLOT ? fallback : vals[s];
}

/* The planet from the values `vals` of the slots (the file's or a run's). */
static lv_planet planet_of(const lv_env_def *e, const double *vals)
{
    const lv_planet_def *pd = &e->pdef;
    lv_planet p = pd->base;
    p.a = slot_or(vals, pd->radius, p.a);
    p.f = slot_or(vals, pd->flattening, p.f);
    p.gm = slot_or(vals, pd->gm, p.gm);
    p.omega = slot_or(vals, pd->rotation_rate, p.omega);
    p.r_ref = slot_or(vals, pd->r_ref, pd->has_base ? p.r_ref : p.a);
    if (pd->zonal_given) {
        double *j[3] = { &p.j2, &p.j3, &p.j4 };
        for (size_t k = 0; k < 3; k++)
            *j[k] = k < pd->n_zonal ? vals[pd->zonal[k]] : 0.0;
    }
    return p;
}

/* Gravity of planet p: the spec of the file; a planet's own zonal list and coefficient file. */
static lv_status gravity_of(const lv_env_def *e, const lv_planet *p, const double *vals,
                            lv_gravity **out, lv_err *err)
{
    lv_gravity_config gc;
    lv_status st = lv_gravity_parse_spec(e->gravity != NULL ? e->gravity : "j2", &gc, err);
    if (st != LV_OK)
        return st;
    const lv_planet_def *pd = &e->pdef;
    gc.coef_path = pd->coef_file;
    if (!pd->custom || pd->n_zonal == 0 || strcmp(gc.model, "sh") == 0)
        return lv_gravity_create(p, &gc, out, err);
    double zonal[LV_GRAVITY_ZONAL_MAX];
    for (size_t k = 0; k < pd->n_zonal; k++)
        zonal[k] = vals[pd->zonal[k]];
    return lv_gravity_create_zonal(p, gc.model, zonal, (int)pd->n_zonal, out, err);
}

/* The "exp" atmosphere with the parameters the file writes (the others: the model's). */
static lv_status atmo_exp(const lv_env_def *e, const double *vals, lv_atmo **out, lv_err *err)
{
    static const char *const keys[3] = { "rho0", "H", "T" };
    lv_status st = lv_atmo_create("exp", out, err);
    for (size_t k = 0; k < 3 && st == LV_OK; k++)
        if (e->atmo_par[k] != LV_NO_SLOT)
            st = lv_atmo_set(*out, keys[k], vals[e->atmo_par[k]], err);
    if (st != LV_OK) {
        lv_atmo_free(*out);
        *out = NULL;
    }
    return st;
}

static lv_status wind_const(const lv_env_def *e, const double *vals, lv_wind **out,
                            lv_err *err)
{
    return lv_wind_create_const(slot_or(vals, e->wind_ned[0], 0.0),
                                slot_or(vals, e->wind_ned[1], 0.0),
                                slot_or(vals, e->wind_ned[2], 0.0), out, err);
}

lv_status lv_mission_env_make(const lv_mission_def *d, lv_mission_env *env, lv_err *err)
{
    const lv_env_def *e = &d->env;
    double *vals = malloc((d->n_slots > 0 ? d->n_slots : 1) * sizeof *vals);
    if (vals == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    for (size_t i = 0; i < d->n_slots; i++)
        vals[i] = d->slots[i].value;
    const lv_src_loc *loc = &e->loc;
    lv_status st = LV_OK;
    memset(env, 0, sizeof *env);
    if (e->world == LV_WORLD_PLANET) {
        if (e->pdef.custom) {
            loc = &e->pdef.loc;
            env->planet = planet_of(e, vals);
            st = lv_planet_check(&env->planet, err);
        } else {
            st = lv_planet_by_name(e->planet != NULL ? e->planet : "earth", &env->planet, err);
        }
        if (st == LV_OK) {
            loc = &e->gravity_loc;
            st = gravity_of(e, &env->planet, vals, &env->gravity, err);
        }
    }
    const char *atm = e->atmosphere;
    if (st == LV_OK && atm != NULL && strcmp(atm, "none") != 0) {
        loc = &e->atmo_loc;
        if (strcmp(atm, "table") == 0)
            st = lv_atmo_create_table(e->atmo_file, e->atmo_var, &env->atmo, err);
        else if (strcmp(atm, "profile") == 0)
            st = lv_atmo_create_profile(e->atmo_file, e->atmo_blend, &env->atmo, err);
        else if (strcmp(atm, "exp") == 0)
            st = atmo_exp(e, vals, &env->atmo, err);
        else
            st = lv_atmo_create(atm, &env->atmo, err);
    }
    if (st == LV_OK && (e->wind_file != NULL || e->wind_const || e->n_wind_prof > 0)) {
        loc = &e->wind_loc;
        const lv_table_opts wo = { e->wind_interp, e->wind_extrap, 0 };
        st = e->n_wind_prof > 0 ? lv_wind_create_profiles((const char *const *)e->wind_prof_file,
                                                          e->wind_prof_t, e->n_wind_prof,
                                                          e->wind_blend, &env->wind, err)
           : e->wind_const ? wind_const(e, vals, &env->wind, err)
                           : lv_wind_create_table_opts(e->wind_file, e->wind_var, &wo, &env->wind,
                                                       err);
    }
    free(vals);
    if (st != LV_OK) {
        lv_mission_env_clear(env);
        return lv_fail_prefix(err, st == LV_ERR_NOMEM ? st : LV_ERR_INPUT,
                              "%s:%d:%d: environment", d->path, loc->line, loc->column);
    }
    return LV_OK;
}

/* 1 if the run's value of any of the slots differs from the file's. */
static int changed(const lv_build_ctx *bc, const lv_slot *s, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (s[k] != LV_NO_SLOT && bc->vals[s[k]] != bc->def->slots[s[k]].value)
            return 1;
    return 0;
}

void lv_phase_env_clear(lv_phase_env *pe)
{
    lv_gravity_free(pe->own_gravity);
    lv_atmo_free(pe->own_perturbed_atmo);
    lv_atmo_free(pe->own_atmo);
    lv_wind_free(pe->own_disturbed);
    lv_wind_free(pe->own_perturbed);
    lv_wind_free(pe->own_wind);
    memset(pe, 0, sizeof *pe);
}

lv_status lv_phase_env_get(const lv_build_ctx *bc, lv_phase_env *pe, lv_err *err)
{
    const lv_env_def *e = &bc->def->env;
    const lv_mission_env *env = bc->env;
    lv_status st = LV_OK;
    memset(pe, 0, sizeof *pe);
    pe->planet = env->planet;
    pe->gravity = env->gravity;
    pe->atmo = env->atmo;
    pe->wind = env->wind;
    const lv_planet_def *pd = &e->pdef;
    const lv_slot ps[] = { pd->radius, pd->flattening, pd->gm, pd->rotation_rate, pd->r_ref };
    if (e->world == LV_WORLD_PLANET && pd->custom &&
        (changed(bc, ps, 5) || changed(bc, pd->zonal, pd->n_zonal))) {
        pe->planet = planet_of(e, bc->vals);
        st = lv_planet_check(&pe->planet, err);
        /* "sh" takes GM, radius and coefficients from its file: the same model */
        if (st == LV_OK && e->gravity != NULL && strncmp(e->gravity, "sh", 2) != 0 &&
            (st = gravity_of(e, &pe->planet, bc->vals, &pe->own_gravity, err)) == LV_OK)
            pe->gravity = pe->own_gravity;
    }
    if (st == LV_OK && e->atmosphere != NULL && strcmp(e->atmosphere, "exp") == 0 &&
        changed(bc, e->atmo_par, 3) &&
        (st = atmo_exp(e, bc->vals, &pe->own_atmo, err)) == LV_OK)
        pe->atmo = pe->own_atmo;
    if (st == LV_OK && e->wind_const && changed(bc, e->wind_ned, 3) &&
        (st = wind_const(e, bc->vals, &pe->own_wind, err)) == LV_OK)
        pe->wind = pe->own_wind;
    if (st == LV_OK && lv_run_tables_wind(bc->tables) != NULL) /* a dispersed wind table */
        pe->wind = lv_run_tables_wind(bc->tables);
    /* a campaign run's dispersed profiles (docs/monte-carlo.md, "Dispersed profiles") */
    const lv_perturbation *pd_rho = lv_run_tables_profile(bc->tables, LV_PROF_DENSITY);
    if (st == LV_OK && pd_rho != NULL && pe->atmo != NULL &&
        (st = lv_atmo_create_perturbed(pe->atmo, pd_rho, &pe->own_perturbed_atmo, err)) == LV_OK)
        pe->atmo = pe->own_perturbed_atmo;
    const lv_perturbation *pd_wind = lv_run_tables_profile(bc->tables, LV_PROF_WIND);
    if (st == LV_OK && pd_wind != NULL &&
        (st = lv_wind_create_perturbed(pe->wind, pd_wind, &pe->own_perturbed, err)) == LV_OK)
        pe->wind = pe->own_perturbed;
    const lv_wind_disturbance *dist = lv_run_tables_disturbance(bc->tables);
    if (st == LV_OK && dist != NULL &&
        (st = lv_wind_create_disturbed(pe->wind, dist, &pe->own_disturbed, err)) == LV_OK)
        pe->wind = pe->own_disturbed; /* plus the run's gusts and turbulence */
    if (st != LV_OK) {
        lv_phase_env_clear(pe);
        return lv_fail_prefix(err, st, "environment");
    }
    return LV_OK;
}

const lv_table *lv_build_table(const lv_build_ctx *bc, const lv_table *t)
{
    return lv_run_tables_get(bc->tables, t);
}
