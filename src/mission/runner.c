/* runner.c - runs a mission's phase tree: builds each phase's model, hands the parent's final
 * state over (states by name, stage-mass bookkeeping, `set:` overrides), calls lv_simulate(),
 * and keeps results for children, summaries and merged per-body trajectories. Independent
 * branches run in parallel threads; a failing phase stops only its descendants. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/names.h"
#include "core/status.h"
#include "lvsim/lv_dof3.h"
#include "lvsim/lv_vehicle.h"
#include "lvsim/lv_flat.h"
#include "lvsim/lv_wind.h"
#include "lvsim/lv_io.h"
#include "lvsim/lv_mission.h"
#include "mission/mission.h"
#include "mission/runner.h"


/* ---- phase models ------------------------------------------------------------------------- */

/* A phase's model: flat6 (flat world) or dof3 (planet world), with the configuration
 * arrays it was built from. */
struct lv_phase_model {
    lv_flat6 *flat;
    lv_dof3 *dof3;
    lv_aero_config aero;
    lv_wind_user wind;  /* the wind table and this simulation's cursor */
    lv_flat_stage *stages;
    lv_flat_engine *engines;
    lv_flat_end *ends;
    lv_engine_config *engines3;
    lv_dof3_end *ends3;
};

void lv_phase_model_free(lv_phase_model *pm)
{
    if (pm == NULL)
        return;
    lv_flat6_free(pm->flat);
    lv_dof3_free(pm->dof3);
    free(pm->stages);
    free(pm->engines);
    free(pm->ends);
    free(pm->engines3);
    free(pm->ends3);
    free(pm);
}

const lv_model_def *lv_phase_model_def(const lv_phase_model *pm)
{
    return pm->flat ? lv_flat6_def(pm->flat) : lv_dof3_def(pm->dof3);
}
void *lv_phase_model_inst(lv_phase_model *pm)
{
    return pm->flat ? lv_flat6_inst(pm->flat) : lv_dof3_inst(pm->dof3);
}

/* Flat-world stage configuration of mission stage `si` with `prop` kg of propellant left;
 * engines are written to `eng` (caller-sized). */
static void flat_stage_from_def(const lv_stage_def *sd, double prop, lv_flat_engine *eng,
                                lv_flat_stage *out)
{
    for (size_t e = 0; e < sd->n_engines; e++) {
        const lv_engine_def *ed = &sd->engines[e];
        double mdot = ed->mdot;
        if (ed->table == NULL && !(mdot > 0.0) && ed->isp_vac > 0.0)
            mdot = ed->thrust_vac / (ed->isp_vac * LV_G0);
        eng[e] = (lv_flat_engine){ed->table, ed->thrust_out, ed->mdot_out, ed->thrust_vac, mdot,
                                  ed->count};
    }
    *out = (lv_flat_stage){sd->name, sd->dry_mass, prop, sd->n_engines, eng};
}

static const lv_flat_end_kind flat_end_of[] = {
    [LV_END_BURNOUT] = LV_FLAT_END_BURNOUT, [LV_END_ALTITUDE] = LV_FLAT_END_ALTITUDE,
    [LV_END_SPEED] = LV_FLAT_END_SPEED,     [LV_END_APOGEE] = LV_FLAT_END_APOGEE,
    [LV_END_IMPACT] = LV_FLAT_END_IMPACT};

static const lv_dof3_end_kind dof3_end_of[] = {
    [LV_END_ALTITUDE] = LV_DOF3_END_ALTITUDE, [LV_END_SPEED] = LV_DOF3_END_SPEED_REL,
    [LV_END_APOGEE] = LV_DOF3_END_APOGEE, [LV_END_IMPACT] = LV_DOF3_END_IMPACT};

/* 3-DoF over the planet: the stages are one mass point; the bottom stage's engines burn. */
static lv_status build_dof3(const lv_mission_def *d, const lv_runner_env *env, size_t k,
                            const double *prop_all, lv_phase_model *pm, lv_err *err)
{
    const lv_phase_def *ph = &d->phases[k];
    const lv_stage_def *bottom = &d->stages[ph->stages[0]];
    pm->engines3 = calloc(bottom->n_engines + 1, sizeof *pm->engines3);
    pm->ends3 = calloc(ph->n_ends + 1, sizeof *pm->ends3);
    if (!pm->engines3 || !pm->ends3)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    lv_dof3_config cfg;
    lv_dof3_config_default(&cfg);
    cfg.name = ph->name;
    cfg.planet = env->planet;
    cfg.gravity = env->gravity;
    cfg.atmo = env->atmo;
    if (env->wind != NULL) {
        pm->wind = (lv_wind_user)LV_WIND_USER_INIT(env->wind);
        cfg.wind = lv_wind_fn_table;
        cfg.wind_user = &pm->wind;
    }
    double m0 = 0.0;
    for (size_t i = 0; i < ph->n_stages; i++) {
        const size_t si = ph->stages[i];
        m0 += d->stages[si].dry_mass + (prop_all ? prop_all[si] : d->stages[si].propellant_mass);
    }
    const double prop0 = prop_all ? prop_all[ph->stages[0]] : bottom->propellant_mass;
    cfg.m0 = m0;
    cfg.m_burnout = m0 - prop0;
    size_t n_all = 0;
    for (size_t e = 0; e < bottom->n_engines; e++)
        n_all += (size_t)(bottom->engines[e].count > 0 ? bottom->engines[e].count : 1);
    free(pm->engines3);
    pm->engines3 = calloc(n_all + 1, sizeof *pm->engines3);
    if (pm->engines3 == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    size_t ne = 0; /* `count` identical engines are `count` engine configurations */
    for (size_t e = 0; prop0 > 0.0 && e < bottom->n_engines; e++) {
        const lv_engine_def *ed = &bottom->engines[e];
        for (int c = 0; c < (ed->count > 0 ? ed->count : 1); c++) {
            lv_engine_config *ec = &pm->engines3[ne++];
            lv_engine_config_default(ec);
            ec->name = ed->name;
            ec->thrust_vac = ed->thrust_vac;
            ec->isp_vac = ed->isp_vac;
            ec->mdot = ed->mdot;
            ec->exit_area = ed->exit_area;
            ec->table = ed->table;
        }
    }
    cfg.n_engines = ne;
    cfg.engines = pm->engines3;
    cfg.start_lat = lv_mission_def_param(d, "start_lat", 0.0);
    cfg.start_lon = lv_mission_def_param(d, "start_lon", 0.0);
    cfg.start_h = lv_mission_def_param(d, "start_h", 0.0);
    cfg.start_vel = lv_mission_def_param(d, "start_vel", 0.0);
    cfg.start_fpa = lv_mission_def_param(d, "start_fpa", 0.0);
    cfg.start_chi = lv_mission_def_param(d, "start_chi", 0.0);
    size_t n_ends = 0;
    for (size_t j = 0; j < ph->n_ends; j++) {
        const lv_end_def *e = &ph->ends[j];
        if (e->kind == LV_END_BURNOUT) {
            cfg.stop_at_burnout = 1;
            continue;
        }
        pm->ends3[n_ends++] = (lv_dof3_end){NULL, dof3_end_of[e->kind], e->value, e->direction, 1};
    }
    cfg.n_ends = n_ends;
    cfg.ends = pm->ends3;
    /* inputs: constants from the phase (else the model's defaults), or a control history */
    if (!isnan(ph->alpha))
        cfg.alpha = ph->alpha;
    if (!isnan(ph->beta))
        cfg.beta = ph->beta;
    if (!isnan(ph->mu))
        cfg.mu = ph->mu;
    if (!isnan(ph->throttle))
        cfg.throttle = ph->throttle;
    cfg.inputs = ph->inputs;
    /* the phase's aerodynamic dataset: a coefficient is a constant, else the table's output
     * of its name, else 0 */
    if (ph->has_aero) {
        static const char *const names[2][3] = {{"CD", "CL", "CY"}, {"CA", "CN", "CY"}};
        lv_aero_config_default(&pm->aero);
        pm->aero.axes = ph->aero_body_axes ? LV_AERO_BODY : LV_AERO_WIND;
        pm->aero.s_ref = ph->aero_s_ref;
        for (int c = 0; c < 3; c++) {
            const char *nm = names[ph->aero_body_axes][c];
            size_t idx;
            if (!isnan(ph->aero_coef[c]))
                pm->aero.coef[c] = (lv_aero_coef){NULL, NULL, ph->aero_coef[c]};
            else if (ph->aero_table && lv_table_out_index(ph->aero_table, nm, &idx, NULL) == LV_OK)
                pm->aero.coef[c] = (lv_aero_coef){ph->aero_table, nm, 0.0};
        }
        cfg.aero = &pm->aero;
    }
    return lv_dof3_create(&cfg, &pm->dof3, err);
}

/* Flat world: the stages carried, each with its engines; the bottom stage burns. */
static lv_status build_flat6(const lv_mission_def *d, size_t k, const double *prop_all,
                             lv_phase_model *pm, lv_err *err)
{
    const lv_phase_def *ph = &d->phases[k];
    size_t n_eng = 0;
    for (size_t i = 0; i < ph->n_stages; i++)
        n_eng += d->stages[ph->stages[i]].n_engines;
    pm->stages = calloc(ph->n_stages, sizeof *pm->stages);
    pm->engines = calloc(n_eng + 1, sizeof *pm->engines);
    pm->ends = calloc(ph->n_ends + 1, sizeof *pm->ends);
    if (!pm->stages || !pm->engines || !pm->ends)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    size_t e0 = 0;
    for (size_t i = 0; i < ph->n_stages; i++) {
        const size_t si = ph->stages[i];
        const lv_stage_def *sd = &d->stages[si];
        flat_stage_from_def(sd, prop_all ? prop_all[si] : sd->propellant_mass, pm->engines + e0,
                            &pm->stages[i]);
        e0 += sd->n_engines;
    }
    for (size_t j = 0; j < ph->n_ends; j++)
        pm->ends[j] = (lv_flat_end){flat_end_of[ph->ends[j].kind], ph->ends[j].value,
                                    ph->ends[j].direction};
    lv_flat6_config cfg = {ph->name, d->env.g, ph->n_stages, pm->stages, ph->n_ends, pm->ends};
    return lv_flat6_create(&cfg, &pm->flat, err);
}

lv_status lv_runner_build_model(const lv_mission_def *d, const lv_runner_env *env, size_t k,
                                const double *prop_all, lv_phase_model **out, lv_err *err)
{
    const lv_phase_def *ph = &d->phases[k];
    *out = NULL;
    lv_phase_model *pm = calloc(1, sizeof *pm);
    if (pm == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    lv_status st;
    if (strcmp(ph->model, "flat6") == 0)
        st = build_flat6(d, k, prop_all, pm, err);
    else if (strcmp(ph->model, "dof3") == 0 && env != NULL && env->gravity != NULL)
        st = build_dof3(d, env, k, prop_all, pm, err);
    else
        st = lv_fail(err, LV_ERR_INPUT, "model '%s' needs a %s world", ph->model,
                     strcmp(ph->model, "dof3") == 0 ? "planet" : "flat");
    if (st != LV_OK) {
        lv_phase_model_free(pm);
        return lv_fail_prefix(err, st, "%s:%d:%d: phase '%s'", d->path, ph->loc.line,
                              ph->loc.column, ph->name);
    }
    *out = pm;
    return LV_OK;
}

/* ---- the mission object ---------------------------------------------------------------- */

typedef struct phase_rt {
    lv_phase_result res;
    int claimed;
    char *stem;
    char **fnames;
    double *fvalues;
    size_t nf;
    char **evnames; /* [n_event_names] */
    double *prop_end;    /* [n_stages of the mission]: propellant left after this phase */
    double m_start;      /* kg, the phase's initial mass (after overrides) */
    double mass_handoff; /* kg, the mass the stage bookkeeping gave (NAN for roots) */
    size_t n_copied;     /* states copied from the parent */
    lv_result *rows;     /* in-memory rows, for merged trajectories and comparisons */
} phase_rt;

struct lv_mission {
    lv_mission_def *def;
    lv_runner_env env;
    phase_rt *ph;
    pthread_mutex_t lock;
    pthread_cond_t cv;
    int running;
};

const lv_mission_def *lv_runner_def(const lv_mission *m) { return m->def; }
const lv_runner_env *lv_runner_environment(const lv_mission *m) { return &m->env; }
const lv_result *lv_runner_rows(const lv_mission *m, size_t k) { return m->ph[k].rows; }

static void phase_rt_clear(phase_rt *p)
{
    lv_sim_report_clear(&p->res.report);
    free(p->stem);
    for (size_t i = 0; i < p->nf; i++)
        free(p->fnames[i]);
    free(p->fnames);
    free(p->fvalues);
    for (size_t i = 0; i < p->res.n_event_names; i++)
        free(p->evnames[i]);
    free(p->evnames);
    free(p->prop_end);
    lv_result_free(p->rows);
    memset(p, 0, sizeof *p);
}

void lv_mission_free(lv_mission *m)
{
    if (m == NULL)
        return;
    for (size_t k = 0; m->def && k < m->def->n_phases; k++)
        phase_rt_clear(&m->ph[k]);
    free(m->ph);
    lv_gravity_free(m->env.gravity);
    lv_atmo_free(m->env.atmo);
    lv_wind_free(m->env.wind);
    lv_mission_def_free(m->def);
    pthread_mutex_destroy(&m->lock);
    pthread_cond_destroy(&m->cv);
    free(m);
}

/* Every phase's initial state must be buildable before anything runs: the model can be made,
 * and every `set:` name and every shared parameter is a variable of the phase's model. */
static lv_status check_phases(const lv_mission_def *d, const lv_runner_env *env, lv_err *err)
{
    int *param_used = calloc(d->n_params + 1, sizeof *param_used);
    if (param_used == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    lv_status st = LV_OK;
    for (size_t k = 0; k < d->n_phases && st == LV_OK; k++) {
        const lv_phase_def *ph = &d->phases[k];
        lv_phase_model *pm;
        if ((st = lv_runner_build_model(d, env, k, NULL, &pm, err)) != LV_OK)
            break;
        const lv_model_def *md = lv_phase_model_def(pm);
        for (size_t i = 0; i < ph->n_set && st == LV_OK; i++) {
            lv_var_kind kind;
            size_t idx;
            st = lv_model_find(md, ph->set_names[i], &kind, &idx, err);
            if (st == LV_OK && kind != LV_VAR_STATE && kind != LV_VAR_PARAMETER)
                st = lv_fail(err, LV_ERR_INPUT, "'%s' is not a state or parameter",
                             ph->set_names[i]);
            if (st != LV_OK) {
                lv_src_loc loc = ph->set_locs ? ph->set_locs[i] : ph->loc;
                st = lv_fail_prefix(err, LV_ERR_INPUT, "%s:%d:%d: phase '%s': set", d->path,
                                    loc.line, loc.column, ph->name);
            }
        }
        for (size_t j = 0; j < d->n_params; j++) {
            lv_var_kind kind;
            size_t idx;
            if (lv_model_find(md, d->param_names[j], &kind, &idx, NULL) == LV_OK &&
                kind == LV_VAR_PARAMETER)
                param_used[j] = 1;
        }
        lv_phase_model_free(pm);
    }
    for (size_t j = 0; j < d->n_params && st == LV_OK; j++)
        if (!param_used[j])
            st = lv_fail(err, LV_ERR_INPUT,
                         "%s: parameter '%s' is not used by any phase's model (flat6 knows "
                         "start_x/y/z, start_vel, start_fpa, start_chi, start_psi/theta/phi, "
                         "start_p/q/r; dof3 knows start_lat, start_lon, start_h, start_vel, "
                         "start_fpa, start_chi)",
                         d->path, d->param_names[j]);
    free(param_used);
    return st;
}

/* Planet, gravity and atmosphere of a planet world, shared read-only by all phases. */
static lv_status make_env(const lv_mission_def *d, lv_runner_env *env, lv_err *err)
{
    if (d->env.world != LV_WORLD_PLANET)
        return LV_OK;
    const lv_src_loc *loc = &d->env.loc;
    lv_gravity_config gc;
    lv_status st = lv_planet_by_name(d->env.planet ? d->env.planet : "earth", &env->planet, err);
    if (st == LV_OK)
        st = lv_gravity_parse_spec(d->env.gravity ? d->env.gravity : "j2", &gc, err);
    if (st == LV_OK)
        st = lv_gravity_create(&env->planet, &gc, &env->gravity, err);
    const char *atm = d->env.atmosphere;
    if (st == LV_OK && atm != NULL && strcmp(atm, "table") == 0)
        st = lv_atmo_create_table(d->env.atmo_file, d->env.atmo_var, &env->atmo, err);
    else if (st == LV_OK && atm != NULL && strcmp(atm, "none") != 0)
        st = lv_atmo_create(atm, &env->atmo, err);
    if (st == LV_OK && d->env.wind_file != NULL) {
        loc = &d->env.wind_loc;
        st = lv_wind_create_table(d->env.wind_file, d->env.wind_var, &env->wind, err);
    }
    if (st != LV_OK)
        return lv_fail_prefix(err, LV_ERR_INPUT, "%s:%d:%d: environment", d->path, loc->line,
                              loc->column);
    return LV_OK;
}

lv_status lv_mission_load(const char *path, lv_mission **out, lv_err *err)
{
    *out = NULL;
    lv_mission_def *d = NULL;
    lv_status st = lv_mission_def_load(path, &d, err);
    if (st != LV_OK)
        return st;
    lv_mission *m = calloc(1, sizeof *m);
    if (m == NULL || (m->ph = calloc(d->n_phases, sizeof *m->ph)) == NULL) {
        free(m);
        lv_mission_def_free(d);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    m->def = d;
    if ((st = make_env(d, &m->env, err)) != LV_OK || (st = check_phases(d, &m->env, err)) != LV_OK) {
        free(m->ph);
        lv_gravity_free(m->env.gravity);
        lv_atmo_free(m->env.atmo);
        lv_wind_free(m->env.wind);
        lv_mission_def_free(d);
        free(m);
        return st;
    }
    pthread_mutex_init(&m->lock, NULL);
    pthread_cond_init(&m->cv, NULL);
    for (size_t k = 0; k < d->n_phases; k++) {
        m->ph[k].res.name = d->phases[k].name;
        m->ph[k].res.t_start = m->ph[k].res.t_end = NAN;
    }
    *out = m;
    return LV_OK;
}

const char *lv_mission_name(const lv_mission *m) { return m->def->name; }
size_t lv_mission_phase_count(const lv_mission *m) { return m->def->n_phases; }
const char *lv_mission_phase_name(const lv_mission *m, size_t k)
{
    return k < m->def->n_phases ? m->def->phases[k].name : NULL;
}
int lv_mission_phase_parent(const lv_mission *m, size_t k)
{
    return k < m->def->n_phases ? m->def->phases[k].parent : -1;
}

lv_status lv_mission_phase_find(const lv_mission *m, const char *name, size_t *k, lv_err *err)
{
    lv_suggest sg;
    lv_suggest_init(&sg, name);
    for (size_t i = 0; i < m->def->n_phases; i++) {
        if (strcmp(m->def->phases[i].name, name) == 0) {
            *k = i;
            return LV_OK;
        }
        lv_suggest_add(&sg, m->def->phases[i].name);
    }
    char hint[160];
    lv_suggest_text(&sg, hint, sizeof hint);
    return lv_fail(err, LV_ERR_NOTFOUND, "mission '%s' has no phase '%s'%s", m->def->name, name,
                   hint);
}

const lv_phase_result *lv_mission_result(const lv_mission *m, size_t k)
{
    return k < m->def->n_phases ? &m->ph[k].res : NULL;
}

lv_status lv_mission_final(const lv_mission *m, size_t k, const char *name, double *value,
                           lv_err *err)
{
    if (k >= m->def->n_phases)
        return lv_fail(err, LV_ERR_INPUT, "phase index %zu out of range", k);
    const phase_rt *p = &m->ph[k];
    if (p->res.state != LV_PHASE_DONE)
        return lv_fail(err, LV_ERR_INPUT, "phase '%s' has not run successfully",
                       p->res.name);
    lv_suggest sg;
    lv_suggest_init(&sg, name);
    for (size_t i = 0; i < p->nf; i++) {
        if (strcmp(p->fnames[i], name) == 0) {
            *value = p->fvalues[i];
            return LV_OK;
        }
        lv_suggest_add(&sg, p->fnames[i]);
    }
    char hint[160];
    lv_suggest_text(&sg, hint, sizeof hint);
    return lv_fail(err, LV_ERR_NOTFOUND, "phase '%s' has no final value '%s'%s", p->res.name,
                   name, hint);
}

lv_status lv_mission_phase_model(const lv_mission *m, size_t k, const double *prop,
                                 lv_phase_model **out, lv_err *err)
{
    const lv_mission_def *d = m->def;
    if (k >= d->n_phases)
        return lv_fail(err, LV_ERR_INPUT, "phase index %zu out of range", k);
    double *all = calloc(d->n_stages + 1, sizeof *all);
    if (all == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    for (size_t s = 0; s < d->n_stages; s++)
        all[s] = d->stages[s].propellant_mass;
    for (size_t i = 0; prop != NULL && i < d->phases[k].n_stages; i++)
        all[d->phases[k].stages[i]] = prop[i];
    lv_status st = lv_runner_build_model(d, &m->env, k, all, out, err);
    free(all);
    return st;
}

void lv_mission_phase_settings(const lv_mission *m, size_t k, lv_sim_settings *s)
{
    const lv_phase_def *ph = &m->def->phases[k];
    lv_sim_settings_default(s);
    s->start_time = ph->t_start;
    s->stop_time = ph->t_stop;
    s->method = ph->method ? ph->method : "dassl";
    s->tolerance = ph->tolerance;
    s->number_of_intervals = ph->intervals;
    s->output_interval = ph->output_interval;
    s->fixed_step = ph->fixed_step;
    s->result_file = NULL;
}

/* ---- one phase ------------------------------------------------------------------------- */

static int mkdir_p(const char *dir)
{
    char buf[4096];
    size_t n = strlen(dir);
    if (n == 0 || n >= sizeof buf)
        return -1;
    memcpy(buf, dir, n + 1);
    for (size_t i = 1; i <= n; i++) {
        if (buf[i] == '/' || buf[i] == '\0') {
            char c = buf[i];
            buf[i] = '\0';
            if (mkdir(buf, 0777) != 0 && errno != EEXIST)
                return -1;
            buf[i] = c;
        }
    }
    return 0;
}

/* Build the start values: mission parameters (root) or the parent's final states, the mass
 * of the carried stages from the bookkeeping, the phase's overrides. Names/values are
 * written to caller arrays of at least n_params + n_states + n_set + 1 entries. */
static size_t handoff(lv_mission *m, size_t k, const lv_model_def *md, const double *prop,
                      double t0, const char **names, double *values)
{
    const lv_mission_def *d = m->def;
    const lv_phase_def *ph = &d->phases[k];
    phase_rt *p = &m->ph[k];
    size_t n = 0;
    lv_var_kind kind;
    size_t idx;
    if (lv_model_find(md, "g", &kind, &idx, NULL) == LV_OK) {
        names[n] = "g";
        values[n++] = d->env.g;
    }
    p->n_copied = 0;
    p->mass_handoff = NAN;
    if (ph->parent < 0) {
        for (size_t j = 0; j < d->n_params; j++) {
            if (lv_model_find(md, d->param_names[j], &kind, &idx, NULL) == LV_OK) {
                names[n] = d->param_names[j];
                values[n++] = d->param_values[j];
            }
        }
    } else {
        const phase_rt *par = &m->ph[ph->parent];
        double mass = 0.0;
        for (size_t i = 0; i < ph->n_stages; i++)
            mass += d->stages[ph->stages[i]].dry_mass + prop[ph->stages[i]];
        for (size_t i = 0; i < md->n_states; i++) {
            const char *sn = md->states[i].name;
            if (strcmp(sn, "m") == 0) {
                names[n] = sn;
                values[n++] = mass;
                p->mass_handoff = mass;
                continue;
            }
            for (size_t j = 0; j < par->nf; j++)
                if (strcmp(par->fnames[j], sn) == 0) {
                    names[n] = sn;
                    values[n++] = par->fvalues[j];
                    p->n_copied++;
                    break;
                }
        }
    }
    if (lv_model_find(md, "start_time", &kind, &idx, NULL) == LV_OK) {
        names[n] = "start_time"; /* the ECI <-> ECEF angle at the phase's start */
        values[n++] = t0;
    }
    for (size_t i = 0; i < ph->n_set; i++) {
        names[n] = ph->set_names[i];
        values[n++] = ph->set_values[i];
    }
    return n;
}

/* Names of the final values (time, states, outputs) and of the model's events, kept with
 * the result: the model itself is gone when the summary is written. */
static lv_status keep_names(phase_rt *p, const lv_model_def *md, lv_err *err)
{
    p->evnames = calloc(md->n_events + 1, sizeof *p->evnames);
    if (p->evnames == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    for (size_t i = 0; i < md->n_events; i++) {
        if ((p->evnames[i] = strdup(md->events[i].name)) == NULL)
            return lv_fail(err, LV_ERR_NOMEM, "out of memory");
        p->res.n_event_names = i + 1;
    }
    p->res.event_names = (const char *const *)p->evnames;
    size_t nf = 1 + md->n_states + md->n_outputs;
    p->fnames = calloc(nf, sizeof *p->fnames);
    p->fvalues = calloc(nf, sizeof *p->fvalues);
    if (!p->fnames || !p->fvalues)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    p->fnames[0] = strdup("time");
    for (size_t i = 0; i < md->n_states; i++)
        p->fnames[1 + i] = strdup(md->states[i].name);
    for (size_t i = 0; i < md->n_outputs; i++)
        p->fnames[1 + md->n_states + i] = strdup(md->outputs[i].name);
    p->nf = nf;
    for (size_t i = 0; i < nf; i++)
        if (p->fnames[i] == NULL)
            return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    p->res.n_final = nf;
    p->res.final_names = (const char *const *)p->fnames;
    p->res.final_values = p->fvalues;
    return LV_OK;
}

/* Runs phase k; the parent (if any) is done. Called without the lock held. */
static lv_status run_one(lv_mission *m, size_t k, const lv_run_options *opt, lv_err *err)
{
    const lv_mission_def *d = m->def;
    const lv_phase_def *ph = &d->phases[k];
    phase_rt *p = &m->ph[k];
    const phase_rt *par = ph->parent >= 0 ? &m->ph[ph->parent] : NULL;
    lv_status st;
    lv_phase_model *pm = NULL;
    const char **names = NULL;
    double *values = NULL;
    lv_sink mem = {0};

    p->prop_end = calloc(d->n_stages + 1, sizeof *p->prop_end);
    if (p->prop_end == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    for (size_t s = 0; s < d->n_stages; s++)
        p->prop_end[s] = par ? par->prop_end[s] : d->stages[s].propellant_mass;

    if ((st = lv_runner_build_model(d, &m->env, k, p->prop_end, &pm, err)) != LV_OK)
        goto done;
    const lv_model_def *md = lv_phase_model_def(pm);
    size_t cap = d->n_params + md->n_states + ph->n_set + 3;
    names = calloc(cap, sizeof *names);
    values = calloc(cap, sizeof *values);
    if (!names || !values) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto done;
    }
    lv_sim_settings s;
    lv_mission_phase_settings(m, k, &s);
    if (isnan(s.start_time))
        s.start_time = par ? par->res.t_end : 0.0;
    if (opt && opt->output_interval > 0.0) {
        s.output_interval = opt->output_interval;
        s.number_of_intervals = 0;
    }
    s.n_initial = handoff(m, k, md, p->prop_end, s.start_time, names, values);
    s.initial_names = names;
    s.initial_values = values;
    if (opt && opt->outdir) {
        char stem[4096];
        snprintf(stem, sizeof stem, "%s/phase_%zu_%s", opt->outdir, k + 1, ph->name);
        p->stem = strdup(stem);
        if (p->stem == NULL) {
            st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
            goto done;
        }
        s.result_file = p->stem;
        p->res.result_stem = p->stem;
    }
    if ((st = keep_names(p, md, err)) != LV_OK)
        goto done;
    if ((st = lv_sink_memory_create(&p->rows, &mem, err)) != LV_OK)
        goto done;
    s.n_sinks = 1;
    s.sinks = &mem;
    s.n_final = p->nf;
    s.final_names = (const char *const *)p->fnames;
    p->res.t_start = s.start_time;
    if (s.stop_time <= s.start_time) {
        st = lv_fail(err, LV_ERR_INPUT,
                     "%s:%d:%d: phase '%s': stop_time %g s is not after its start %g s (the "
                     "parent '%s' ended then)",
                     d->path, ph->loc.line, ph->loc.column, ph->name, s.stop_time, s.start_time,
                     par ? par->res.name : "-");
        goto done;
    }
    st = lv_simulate(md, lv_phase_model_inst(pm), &s, p->fvalues, &p->res.report, err);
    p->res.t_end = p->res.report.end_time;
    if (st == LV_OK) {
        /* stage bookkeeping: what the phase burned came out of its bottom stage */
        double m0 = NAN, m1 = NAN;
        for (size_t i = 0; i < s.n_initial; i++)
            if (strcmp(names[i], "m") == 0)
                m0 = values[i];
        for (size_t i = 0; i < p->nf; i++)
            if (strcmp(p->fnames[i], "m") == 0)
                m1 = p->fvalues[i];
        for (size_t i = 0; isnan(m0) && i < md->n_states; i++)
            if (strcmp(md->states[i].name, "m") == 0)
                m0 = md->states[i].start;
        p->m_start = m0;
        size_t bottom = ph->stages[0];
        double burned = m0 - m1;
        if (burned > 0.0)
            p->prop_end[bottom] = fmax(0.0, p->prop_end[bottom] - burned);
    }
done:
    if (st != LV_OK)
        lv_fail_prefix(err, st, "phase '%s'", ph->name);
    lv_sink_destroy(&mem);
    lv_phase_model_free(pm);
    free(names);
    free(values);
    return st;
}

/* ---- scheduling -------------------------------------------------------------------------- */

typedef struct worker_ctx {
    lv_mission *m;
    const lv_run_options *opt;
    int any_failed;
} worker_ctx;

/* With the lock held: the next phase that can run, marking skipped ones on the way; -1 when
 * none is ready now. */
static long next_ready(lv_mission *m, int *pending)
{
    *pending = 0;
    for (size_t k = 0; k < m->def->n_phases; k++) {
        phase_rt *p = &m->ph[k];
        if (p->res.state != LV_PHASE_PENDING || p->claimed)
            continue;
        int par = m->def->phases[k].parent;
        lv_phase_state ps = par < 0 ? LV_PHASE_DONE : m->ph[par].res.state;
        if (ps == LV_PHASE_FAILED || ps == LV_PHASE_SKIPPED) {
            p->res.state = LV_PHASE_SKIPPED;
            snprintf(p->res.error, sizeof p->res.error, "phase '%s' not run: its parent '%s' %s",
                     p->res.name, m->def->phases[par].name,
                     ps == LV_PHASE_FAILED ? "failed" : "was not run");
            k = (size_t)-1; /* a new skip may unblock nothing but can skip more: rescan */
            continue;
        }
        if (ps == LV_PHASE_DONE)
            return (long)k;
        *pending = 1;
    }
    return -1;
}

static void *worker(void *arg)
{
    worker_ctx *w = arg;
    lv_mission *m = w->m;
    pthread_mutex_lock(&m->lock);
    for (;;) {
        int pending;
        long k = next_ready(m, &pending);
        if (k < 0) {
            if (!pending)
                break; /* nothing left that this worker could ever run */
            pthread_cond_wait(&m->cv, &m->lock); /* a running parent will wake us */
            continue;
        }
        m->ph[k].claimed = 1;
        m->running++;
        pthread_mutex_unlock(&m->lock);
        lv_err err;
        lv_status st = run_one(m, (size_t)k, w->opt, &err);
        pthread_mutex_lock(&m->lock);
        m->running--;
        phase_rt *p = &m->ph[k];
        if (st == LV_OK) {
            p->res.state = LV_PHASE_DONE;
        } else {
            p->res.state = LV_PHASE_FAILED;
            snprintf(p->res.error, sizeof p->res.error, "%s", err.msg);
            w->any_failed = 1;
        }
        if (w->opt && w->opt->on_phase)
            w->opt->on_phase(m, (size_t)k, &p->res, w->opt->user);
        pthread_cond_broadcast(&m->cv);
    }
    pthread_cond_broadcast(&m->cv);
    pthread_mutex_unlock(&m->lock);
    return NULL;
}

lv_status lv_mission_run(lv_mission *m, const lv_run_options *opt, lv_err *err)
{
    if (opt && opt->outdir && mkdir_p(opt->outdir) != 0)
        return lv_fail(err, LV_ERR_IO, "cannot create output directory '%s': %s", opt->outdir,
                       strerror(errno));
    int threads = opt && opt->threads > 0 ? opt->threads : 2;
    if (threads > 16)
        threads = 16;
    worker_ctx w = {m, opt, 0};
    pthread_t tid[16];
    int started = 0;
    for (int i = 1; i < threads; i++)
        if (pthread_create(&tid[started], NULL, worker, &w) == 0)
            started++;
    worker(&w);
    for (int i = 0; i < started; i++)
        pthread_join(tid[i], NULL);
    size_t failed = 0, skipped = 0;
    for (size_t k = 0; k < m->def->n_phases; k++) {
        failed += m->ph[k].res.state == LV_PHASE_FAILED;
        skipped += m->ph[k].res.state == LV_PHASE_SKIPPED;
    }
    if (failed > 0)
        return lv_fail(err, LV_ERR_SOLVER, "mission '%s': %zu phase(s) failed, %zu not run",
                       m->def->name, failed, skipped);
    return LV_OK;
}

lv_status lv_mission_run_phase(lv_mission *m, size_t k, const lv_run_options *opt, lv_err *err)
{
    if (k >= m->def->n_phases)
        return lv_fail(err, LV_ERR_INPUT, "phase index %zu out of range", k);
    int par = m->def->phases[k].parent;
    if (par >= 0 && m->ph[par].res.state != LV_PHASE_DONE)
        return lv_fail(err, LV_ERR_INPUT, "phase '%s' needs its parent '%s' to have run",
                       m->def->phases[k].name, m->def->phases[par].name);
    if (opt && opt->outdir && mkdir_p(opt->outdir) != 0)
        return lv_fail(err, LV_ERR_IO, "cannot create output directory '%s': %s", opt->outdir,
                       strerror(errno));
    phase_rt *p = &m->ph[k];
    const char *name = p->res.name;
    phase_rt_clear(p);
    p->res.name = name;
    p->claimed = 1;
    lv_status st = run_one(m, k, opt, err);
    p->res.state = st == LV_OK ? LV_PHASE_DONE : LV_PHASE_FAILED;
    if (st != LV_OK)
        snprintf(p->res.error, sizeof p->res.error, "%s", err ? err->msg : "failed");
    if (opt && opt->on_phase)
        opt->on_phase(m, k, &p->res, opt->user);
    return st;
}

/* ---- views for the summary and the comparison ---------------------------------------------- */

double lv_runner_mass_start(const lv_mission *m, size_t k) { return m->ph[k].m_start; }
double lv_runner_mass_handoff(const lv_mission *m, size_t k) { return m->ph[k].mass_handoff; }
size_t lv_runner_n_copied(const lv_mission *m, size_t k) { return m->ph[k].n_copied; }
const double *lv_runner_prop_end(const lv_mission *m, size_t k) { return m->ph[k].prop_end; }
