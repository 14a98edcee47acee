/* phase_kit.h - the build kit of the phase-model types (not exported): what every type's build
 * does alike, written once. A type's build is then its own model's configuration between
 * lv_kit_begin and lv_kit_done:
 *
 *     s = calloc(1, sizeof *s);                       s->kit: an lv_kit_model
 *     lv_kit_begin(bc, &s->kit, 1, sizeof(lv_dof3_end), 1, err);   env, engines, ends
 *     lv_kit_world(&s->kit, &cfg.planet, &cfg.gravity, &cfg.atmo, &cfg.wind, &cfg.wind_user);
 *     cfg.m0 = lv_kit_stack_mass(bc, 0);              kg, the phase's stages
 *     cfg.start_lat = lv_kit_param(bc, LV_KIT_START_LAT, 0.0);     mission parameters
 *     cfg.n_engines = lv_kit_engines(bc, bottom, s->kit.engines);  the bottom stage's
 *     cfg.n_ends = lv_kit_flight_ends(bc, &s->kit, &cfg.stop_at_burnout);
 *     lv_xxx_create(&cfg, &s->model, err);
 *     lv_kit_done(&s->kit, lv_xxx_def(s->model), lv_xxx_inst(s->model), s, out);
 *
 * and its free_self frees its model, then lv_kit_clear(&s->kit), then s. */
#ifndef LV_MISSION_PHASE_KIT_H
#define LV_MISSION_PHASE_KIT_H

#include <stddef.h>

#include "lvsim/lv_dof3.h"
#include "lvsim/lv_vehicle.h"
#include "lvsim/lv_wind.h"
#include "mission/aero_def.h"
#include "mission/phase_type.h"

/* ---- what a type over the planet declares --------------------------------------------- */

/* The columns of a body's merged trajectory over the planet (body_<stage>.csv) from a model
 * with the flight models' states and outputs (r_eci_*, v_eci_*, m; lat, lon, h, v_rel, mach,
 * q_dyn, iip_lat, iip_lon, iip_tof): what the exports read (time, lat, lon, h, the ECI state;
 * the impact point's trace) and more. */
#define LV_KIT_PLANET_TRAJ_N 16
extern const lv_traj_col lv_kit_planet_traj[LV_KIT_PLANET_TRAJ_N];

/* The mission parameters of a start over the planet, in this order (lv_kit_param's i), and
 * their ranges: the rows of a type's mission_params and mission_param_ranges. */
enum { LV_KIT_START_LAT, LV_KIT_START_LON, LV_KIT_START_H, LV_KIT_START_VEL, LV_KIT_START_FPA,
       LV_KIT_START_CHI, LV_KIT_START_N };
#define LV_KIT_START_PARAMS                                                                      \
    {"start_lat", "rad", "Initial geodetic latitude", 0, 0},                                     \
    {"start_lon", "rad", "Initial longitude", 0, 0},                                             \
    {"start_h", "m", "Initial geodetic altitude", 0, 0},                                         \
    {"start_vel", "m/s", "Initial speed relative to the rotating planet", 0, 0},                 \
    {"start_fpa", "rad", "Initial flight-path angle of the relative velocity, up positive", 0,   \
     0},                                                                                         \
    {"start_chi", "rad", "Initial heading of the relative velocity, from north to east", 0, 0}
/* lat in [-90, 90] deg, lon within a turn, h: the model's domain and the impact end decide,
 * vel >= 0, fpa in [-90, 90] deg, chi within a turn */
#define LV_KIT_START_RANGES                                                                      \
    LV_RANGE_LAT, LV_RANGE_TURN, {-HUGE_VAL, HUGE_VAL, 0, 0}, {0.0, HUGE_VAL, 0, 0},             \
        LV_RANGE_LAT, LV_RANGE_TURN

/* ---- values ------------------------------------------------------------------------------ */

/* The run's value of slot s; `fallback` where there is no slot (LV_NO_SLOT: a key the phase
 * does not have, an input that does not act). The one fallback rule of every build. */
double lv_kit_val(const lv_build_ctx *bc, lv_slot s, double fallback);

/* The run's value of mission parameter i of the phase's type (type->mission_params[i]),
 * resolved to its slot when the file was parsed (lv_phase_def.params); `fallback` when the
 * file's `parameters:` do not give it. */
double lv_kit_param(const lv_build_ctx *bc, size_t i, double fallback);

/* Parse time (parse_phase.c, once ph->type is known): ph->params[i] = the slot of the file's
 * `parameters:` entry named type->mission_params[i].name, or LV_NO_SLOT. Errors: LV_ERR_NOMEM. */
lv_status lv_kit_resolve_params(const lv_mission_def *d, lv_phase_def *ph, lv_err *err);

/* kg: the stages of the phase from its `first` (0: the bottom) up, each with its dry mass and
 * the propellant it has left at the phase's start (bc->prop). */
double lv_kit_stack_mass(const lv_build_ctx *bc, size_t first);

/* The heat flux outputs' data (docs/models.md, "Aerothermal heating"): the nose radius [m] of
 * the phase's top stage (its `nose_radius`, else 1 m) and the Sutton-Graves constant
 * [kg^0.5/m] of the planet's air (its `sutton_graves_k`, else its preset's or base's: Mars
 * LV_SUTTON_GRAVES_MARS, any other LV_SUTTON_GRAVES_EARTH). */
void lv_kit_heating(const lv_build_ctx *bc, double *nose_radius, double *k_sutton_graves);

/* ---- the built model's common parts ------------------------------------------------------ */

/* One of the phase's ends as a state event of the model (lv_kit_ends). */
typedef struct lv_kit_end {
    const lv_end_def *def;
    double value; /* the run's value (SI); 0 for an end without a value */
} lv_kit_end;

/* State events a model may have after its ends that end nothing (dof3: the throttle law's
 * saturation, throttle_min and throttle_max). */
#define LV_KIT_MORE_EVENTS 2

typedef struct lv_kit_model {
    lv_phase_model pm;
    lv_phase_env env;         /* planet, gravity, atmosphere, wind of this run (borrowed by the
                                 model) */
    lv_wind_user wind;        /* the wind table and this simulation's cursor */
    lv_aero_config aero;      /* the phase's aerodynamic dataset, configured (lv_kit_aero) */
    lv_engine_config *engines; /* [lv_kit_engine_count(bottom) + 1] or NULL */
    void *ends;               /* [ph->n_ends + 1] of the model's end structure */
    lv_kit_end *end;          /* [ph->n_ends + 1] (lv_kit_ends) */
    int *event_end;           /* [n_own + ph->n_ends + LV_KIT_MORE_EVENTS]:
                                 lv_phase_model.event_end (-1 where an event ends nothing) */
    size_t n_own;             /* the model's own state events before the ends */
} lv_kit_model;

/* Starts phase bc->k's model: refuses a planet-world type on a world without gravity
 * ("model 'dof3' needs a planet world"), allocates the engine configurations of the bottom
 * stage (with_engines), the model's ends (end_size bytes each) and the event map (n_own: the
 * model's own events before the ends), and gets this run's environment. On an error k is
 * cleared. */
lv_status lv_kit_begin(const lv_build_ctx *bc, lv_kit_model *k, int with_engines,
                       size_t end_size, size_t n_own, lv_err *err);

/* The environment fields every planet model's configuration has. */
void lv_kit_world(lv_kit_model *k, lv_planet *planet, const lv_gravity **gravity,
                  const lv_atmo **atmo, lv_wind_fn *wind, void **wind_user);

/* The phase's aerodynamic dataset configured from the run's values; NULL when it has none. */
const lv_aero_config *lv_kit_aero(const lv_build_ctx *bc, const lv_aero_def *a,
                                  lv_kit_model *k);

/* Ends the build: *out = &k->pm for the model's def and instance; `self` is the type's
 * object its free_self gets. */
void lv_kit_done(lv_kit_model *k, const lv_model_def *def, void *inst, void *self,
                 lv_phase_model **out);

void lv_kit_clear(lv_kit_model *k); /* the environment and the arrays; accepts a zeroed one */

/* ---- engines ------------------------------------------------------------------------------ */

/* Engine configurations of stage st: `count` identical engines are `count` configurations. */
size_t lv_kit_engine_count(const lv_stage_def *st);

/* Fills out[lv_kit_engine_count(st)] with the stage's engines at the run's values (thrust, Isp,
 * mass flow, exit area, throttle limits; the run's table); returns their number. For the
 * phase's bottom stage only the engines its `engines:` runs (all without it), and the
 * engine-outs of its `engine_out:` (lv_engine_config.out_after) on the last of each kind. */
size_t lv_kit_engines(const lv_build_ctx *bc, const lv_stage_def *st, lv_engine_config *out);

/* Full throttle for a phase that writes none: 1 (rated thrust) held within what every engine
 * accepts: at most the lowest throttle_max, at least the highest throttle_min (an engine that
 * runs only above rated thrust). */
double lv_kit_full_throttle(const lv_engine_config *eng, size_t n);

/* ---- ends --------------------------------------------------------------------------------- */

/* The phase's ends as the model's state events: the model's own events 0..n_own-1 come first
 * (event_end -1), then one per end it is given, in the file's order: k->end[i] its definition
 * and run's value, k->event_end[n_own + i] its index in ph->ends. Variable and time ends are
 * stop conditions of the simulation (run.c), no event. Where the model's event 0 is its
 * burnout (burnout_event), a `burnout` end stands for event 0 and sets *stop_at_burnout
 * instead. Returns the number of ends in k->end. */
size_t lv_kit_ends(const lv_build_ctx *bc, lv_kit_model *k, int burnout_event,
                   int *stop_at_burnout);

/* lv_kit_ends for a flight model over the planet (flight_ends.h: event 0 its burnout, then the
 * named ends as lv_dof3_end, in k->ends). */
size_t lv_kit_flight_ends(const lv_build_ctx *bc, lv_kit_model *k, int *stop_at_burnout);

#endif
