/* phase_flat6.c - the phase-model type "flat6": the paper's test-case body (lv_flat.h), a
 * stack of stages as one 6-DoF point mass over a flat, non-rotating world with uniform
 * gravity; the bottom stage's engines burn (paper, section 4.1). With the environment's
 * atmosphere and wind, and its own key `aero` (drag only), a sounding rocket in air. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "lvsim/lv_flat.h"
#include "lvsim/lv_planet.h"
#include "lvsim/lv_units.h"
#include "mission/aero_def.h"
#include "mission/phase_kit.h"
#include "mission/phase_type.h"

/* The model's parameters that are the mission's shared parameter set (lv_flat.h). */
static const lv_var mission_params[] = {
    {"start_x", "m", "Initial position east", 0, 0},
    {"start_y", "m", "Initial position north", 0, 0},
    {"start_z", "m", "Initial altitude", 0, 0},
    {"start_vel", "m/s", "Initial speed", 0, 0},
    {"start_fpa", "rad", "Initial flight-path angle above the x-y plane", 0, 0},
    {"start_chi", "rad", "Initial heading, from north (+y) towards east (+x)", 0, 0},
    {"start_psi", "rad", "Initial heading angle (yaw)", 0, 0},
    {"start_theta", "rad", "Initial pitch angle", 0, 0},
    {"start_phi", "rad", "Initial bank angle", 0, 0},
    {"start_p", "rad/s", "Initial roll rate", 0, 0},
    {"start_q", "rad/s", "Initial pitch rate", 0, 0},
    {"start_r", "rad/s", "Initial yaw rate", 0, 0},
};

static const lv_range mission_param_ranges[] = {
    {-HUGE_VAL, HUGE_VAL, 0, 0}, {-HUGE_VAL, HUGE_VAL, 0, 0}, /* start_x, start_y */
    {-HUGE_VAL, HUGE_VAL, 0, 0}, /* start_z: the model's domain and the impact end decide */
    {0.0, HUGE_VAL, 0, 0},       /* start_vel >= 0 */
    LV_RANGE_LAT,                /* start_fpa in [-90, 90] deg */
    LV_RANGE_TURN, LV_RANGE_TURN, /* start_chi, start_psi in [-360, 360] deg */
    LV_RANGE_LAT,                 /* start_theta: a 3-2-1 pitch, [-90, 90] deg */
    LV_RANGE_TURN,                /* start_phi */
    LV_RANGE_RATE, LV_RANGE_RATE, LV_RANGE_RATE, /* p, q, r within 10 rev/s */
};

/* Merged trajectories: the states, the stage mass (written by the summary), and where the
 * point is over the Earth with the flat world's origin at the mission's site. */
static const lv_traj_col traj[] = {
    {"x", "m", "x"},           {"y", "m", "y"},           {"z", "m", "z"},
    {"vx", "m/s", "vx"},       {"vy", "m/s", "vy"},       {"vz", "m/s", "vz"},
    {"psi", "rad", "psi"},     {"theta", "rad", "theta"}, {"phi", "rad", "phi"},
    {"p", "rad/s", "p"},       {"q", "rad/s", "q"},       {"r", "rad/s", "r"},
    {"body_mass", "kg", "m"},  {"lat", "rad", NULL},      {"lon", "rad", NULL},
    {"h", "m", NULL},
};
enum { TC_X = 0, TC_Y = 1, TC_Z = 2, TC_LAT = 13, TC_LON = 14, TC_H = 15 };

/* The flat world's origin sits at the mission's site (WGS-84) with x east, y north, z up. */
static void flat6_traj_extra(const lv_mission_def *d, double *row)
{
    const lv_planet earth = lv_planet_earth();
    double r_site[3], C_ned_ecef[3][3], r_ecef[3];
    lv_frames_geodetic_to_ecef(&earth, d->env.site_lat, d->env.site_lon, 0.0, r_site);
    lv_frames_C_ned_ecef(d->env.site_lat, d->env.site_lon, C_ned_ecef);
    const double ned[3] = {row[TC_Y], row[TC_X], -row[TC_Z]};
    for (int a = 0; a < 3; a++)
        r_ecef[a] = r_site[a] + C_ned_ecef[0][a] * ned[0] + C_ned_ecef[1][a] * ned[1] +
                    C_ned_ecef[2][a] * ned[2];
    lv_frames_ecef_to_geodetic(&earth, r_ecef, &row[TC_LAT], &row[TC_LON], &row[TC_H]);
}

/* ---- the phase's own keys ------------------------------------------------------------ */

static const char *const keys[] = {"aero", NULL};

typedef struct flat6_cfg {
    lv_aero_def aero; /* drag only (aero_def.h) */
} flat6_cfg;

static void flat6_cfg_free(void *p)
{
    flat6_cfg *c = p;
    if (c == NULL)
        return;
    lv_aero_def_clear(&c->aero);
    free(c);
}

/* aero: {s_ref, axes, CD | CA, table}: the body's drag; it needs the atmosphere. */
static lv_status flat6_parse(const lv_pctx *c, const lv_ynode *n, lv_phase_def *ph)
{
    flat6_cfg *cfg = calloc(1, sizeof *cfg);
    if (cfg == NULL)
        return lv_pk_nomem(c);
    ph->type_cfg = cfg;
    const lv_ynode *v = lv_pk_get(n, "aero");
    lv_status st = lv_aero_def_parse(c, v, ph->name, 1, &cfg->aero);
    if (st == LV_OK && cfg->aero.present && c->m->env.atmosphere != NULL &&
        strcmp(c->m->env.atmosphere, "none") == 0)
        st = lv_pk_fail(c, lv_pk_key(n, "aero"), "phase '%s': aero: the flat world has no "
                        "atmosphere (environment: atmosphere: none, its default), so no drag; "
                        "give environment: atmosphere: us76, exp or {table: ..}", ph->name);
    return st;
}

/* ---- the model ---------------------------------------------------------------------------- */

static const lv_flat_end_kind flat_end_of[] = {
    [LV_END_BURNOUT] = LV_FLAT_END_BURNOUT, [LV_END_ALTITUDE] = LV_FLAT_END_ALTITUDE,
    [LV_END_SPEED] = LV_FLAT_END_SPEED,     [LV_END_APOGEE] = LV_FLAT_END_APOGEE,
    [LV_END_IMPACT] = LV_FLAT_END_IMPACT};

/* What one built model owns. */
typedef struct flat6_self {
    lv_kit_model kit; /* atmosphere and wind of this run, ends (phase_kit.h) */
    lv_flat6 *model;
    lv_flat_stage *stages;
    lv_flat_engine *engines;
} flat6_self;

static void flat6_free_self(void *p)
{
    flat6_self *s = p;
    if (s == NULL)
        return;
    lv_flat6_free(s->model);
    lv_kit_clear(&s->kit);
    free(s->stages);
    free(s->engines);
    free(s);
}

/* The stages carried, each with its engines; the bottom stage burns. */
static lv_status flat6_build(const lv_build_ctx *bc, lv_phase_model **out, lv_err *err)
{
    const lv_mission_def *d = bc->def;
    const lv_phase_def *ph = &d->phases[bc->k];
    *out = NULL;
    flat6_self *s = calloc(1, sizeof *s);
    if (s == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    /* event 0: the bottom stage's burnout stops the engines; a `burnout` end is an end */
    lv_status st = lv_kit_begin(bc, &s->kit, 0, sizeof(lv_flat_end), 1, err);
    if (st != LV_OK) {
        free(s);
        return st;
    }
    size_t n_eng = 0;
    for (size_t i = 0; i < ph->n_stages; i++)
        n_eng += d->stages[ph->stages[i]].n_engines;
    if ((s->stages = calloc(ph->n_stages, sizeof *s->stages)) == NULL ||
        (s->engines = calloc(n_eng + 1, sizeof *s->engines)) == NULL) {
        flat6_free_self(s);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    size_t e0 = 0;
    for (size_t i = 0; i < ph->n_stages; i++) {
        const size_t si = ph->stages[i];
        const lv_stage_def *sd = &d->stages[si];
        for (size_t e = 0; e < sd->n_engines; e++) {
            const lv_engine_def *ed = &sd->engines[e];
            double thrust = lv_kit_val(bc, ed->thrust_vac, 0.0);
            double mdot = lv_kit_val(bc, ed->mdot, 0.0);
            if (ed->table == NULL && !(mdot > 0.0) && ed->isp_vac != LV_NO_SLOT)
                mdot = thrust / (lv_kit_val(bc, ed->isp_vac, 0.0) * LV_G0);
            s->engines[e0 + e] = (lv_flat_engine){lv_build_table(bc, ed->table), ed->thrust_out,
                                                  ed->mdot_out, thrust, mdot, ed->count};
        }
        s->stages[i] = (lv_flat_stage){sd->name, lv_kit_val(bc, sd->dry_mass, 0.0),
                                       bc->prop[si], sd->n_engines, s->engines + e0};
        e0 += sd->n_engines;
    }
    const size_t n_ends = lv_kit_ends(bc, &s->kit, 0, NULL);
    /* a `burnout` end fires with the model's own burnout event 0 (the same root, m - m_burnout):
     * when the simulation names event 0 as the one that stopped it, the phase ended by that end
     * (lv_phase_result.end_index; it read -1, "stop_time", before) */
    for (size_t j = 0; j < ph->n_ends; j++)
        if (ph->ends[j].kind == LV_END_BURNOUT)
            s->kit.event_end[0] = (int)j;
    lv_flat_end *ends = s->kit.ends;
    for (size_t i = 0; i < n_ends; i++)
        ends[i] = (lv_flat_end){flat_end_of[s->kit.end[i].def->kind], s->kit.end[i].value,
                                s->kit.end[i].def->direction};
    const flat6_cfg *pc = ph->type_cfg;
    lv_flat6_config cfg = {.name = ph->name,
                           .g = lv_kit_val(bc, d->env.g, 0.0),
                           .n_stages = ph->n_stages,
                           .stages = s->stages,
                           .n_ends = n_ends,
                           .ends = ends,
                           .atmo = s->kit.env.atmo,
                           .wind = s->kit.env.wind,
                           .aero = pc != NULL ? lv_kit_aero(bc, &pc->aero, &s->kit) : NULL};
    st = lv_flat6_create(&cfg, &s->model, err);
    if (st != LV_OK) {
        flat6_free_self(s);
        return st;
    }
    lv_kit_done(&s->kit, lv_flat6_def(s->model), lv_flat6_inst(s->model), s, out);
    return LV_OK;
}

const lv_phase_type lv_phase_type_flat6 = {
    .name = "flat6",
    .description = "point mass with the paper's 13 states (attitude kinematics at constant rates, no moments) carrying a stack of stages over a flat world (the paper's "
                   "test case; thrust along +z; drag along -v_air in the environment's air)",
    .world = LV_WORLD_FLAT,
    .keys = keys,
    .n_mission_params = sizeof mission_params / sizeof mission_params[0],
    .mission_params = mission_params,
    .mission_param_ranges = mission_param_ranges,
    .mass_state = "m",
    .parse = flat6_parse,
    .cfg_free = flat6_cfg_free,
    .build = flat6_build,
    .free_self = flat6_free_self,
    .n_traj = sizeof traj / sizeof traj[0],
    .traj = traj,
    .traj_extra = flat6_traj_extra,
};
