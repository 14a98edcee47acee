/* lv_dof3.h - 3-DoF variable-mass point over a rotating planet (the paper's sec. 2.2-2.3).
 *
 * States are ECI Cartesian position and velocity plus mass (7 states, singularity-free);
 * the paper's eq. (1) variables (geocentric latitude, longitude, radius and north/east/
 * down velocity relative to the rotating planet) are outputs. Inputs: angle of attack
 * alpha, sideslip beta, bank mu, throttle c_s - constant parameters or a time table.
 * Forces: gravity (lv_planet.h), thrust of several engines and aerodynamics from
 * coefficient tables (lv_vehicle.h), with an optional wind. Equations, frames, variable
 * names and units: docs/models.md.
 *
 * Usage: fill an lv_dof3_config (start from lv_dof3_config_default), lv_dof3_create(),
 * then lv_simulate(lv_dof3_def(m), lv_dof3_inst(m), &settings, ...). The model
 * definition is built per configuration (its events are the configured end
 * conditions); `inst` must be lv_dof3_inst(m) - lv_simulate's own zeroed block makes
 * start() fail. One lv_dof3 serves one simulation at a time; create one per thread.
 */
#ifndef LVSIM_LV_DOF3_H
#define LVSIM_LV_DOF3_H

#include <stddef.h>

#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_guidance.h"
#include "lvsim/lv_model.h"
#include "lvsim/lv_planet.h"
#include "lvsim/lv_status.h"
#include "lvsim/lv_table.h"
#include "lvsim/lv_vehicle.h"

#ifdef __cplusplus
extern "C" {
#endif

/* State indices: "r_eci_x" .. "v_eci_z", "m", "heat_load", "heat_load_fm". */
enum lv_x3 {
    LV_X3_RX, LV_X3_RY, LV_X3_RZ, /* position, ECI, m   */
    LV_X3_VX, LV_X3_VY, LV_X3_VZ, /* velocity, ECI, m/s */
    LV_X3_M,                      /* mass, kg           */
    LV_X3_QSG, LV_X3_QFM,         /* heat loads, J/m^2: the time integrals of the heat flux
                                     outputs heat_flux and heat_flux_fm (quadratures, out of
                                     the error control: lv_model_def.quadrature) */
    LV_X3_N                       /* count */
};

/* End conditions (state events) besides burnout. */
typedef enum lv_dof3_end_kind {
    LV_DOF3_END_ALTITUDE = 1,     /* geodetic altitude crosses `value` [m] (`direction`) */
    LV_DOF3_END_SPEED_REL = 2,    /* speed relative to the rotating planet crosses `value` [m/s] */
    LV_DOF3_END_SPEED_INERTIAL = 3, /* inertial speed crosses `value` [m/s] */
    LV_DOF3_END_APOGEE = 4,       /* radial velocity falls through 0 (`value`, `direction`
                                     ignored) */
    LV_DOF3_END_IMPACT = 5        /* geodetic altitude falls through `value` [m] (0: the
                                     ellipsoid; `direction` ignored) */
} lv_dof3_end_kind;

typedef struct lv_dof3_end {
    const char *name;     /* event name in reports ("meco", "impact"); copied; NULL: the kind's
                             name ("altitude", "speed_rel", "speed_inertial", "apogee", "impact") */
    lv_dof3_end_kind kind;
    double value;         /* m or m/s, see the kind */
    lv_dir direction;     /* altitude and speed crossings */
    int stop;             /* 1: end the run (a phase end); 0: log the event and continue */
} lv_dof3_end;

/* What a dof3 inputs table is over (lv_dof3_config.inputs_over). */
typedef enum lv_dof3_over {
    LV_DOF3_OVER_TIME = 0, LV_DOF3_OVER_TAU, LV_DOF3_OVER_ALTITUDE, LV_DOF3_OVER_SPEED,
    LV_DOF3_OVER_MASS, LV_DOF3_OVER_ENERGY
} lv_dof3_over;

typedef struct lv_dof3_config {
    const char *name;          /* model name in reports; copied; NULL: "dof3" */
    lv_planet planet;          /* copied: ellipsoid, rotation (default lv_planet_earth()) */
    const lv_gravity *gravity; /* borrowed, required; evaluated at ECEF positions */
    const lv_atmo *atmo;       /* borrowed; NULL: vacuum (no aerodynamics, p_amb = 0) */
    lv_wind_fn wind;           /* NULL: no wind */
    void *wind_user;           /* passed to `wind` */

    double m0;                 /* kg, start mass (default of state "m"), > 0 */
    double propellant;         /* kg, propellant of the burning stage at the start (default of
                                  parameter "propellant"), 0 <= propellant < m0: burnout when it
                                  is gone, whatever else the start mass carries */
    size_t n_engines;          /* 0: unpowered */
    const lv_engine_config *engines; /* [n_engines], copied (their tables borrowed) */
    const lv_aero_config *aero; /* copied (tables borrowed); NULL: no aerodynamic force */
    double nose_radius;        /* m, > 0: the nose radius of the stagnation-point heat flux
                                  (output heat_flux; default 1) */
    double k_sutton_graves;    /* kg^0.5/m, >= 0: Sutton-Graves constant of the atmosphere's gas
                                  (default LV_SUTTON_GRAVES_EARTH: air) */

    /* Default values of the parameters of the same name (the paper's userPar). */
    double start_lat, start_lon; /* rad, geodetic */
    double start_h;              /* m, geodetic altitude */
    double start_vel;            /* m/s, speed relative to the rotating planet, >= 0 */
    double start_fpa, start_chi; /* rad, flight-path angle (up +) and heading (from north to
                                    east) of the relative velocity */
    double start_time;           /* s, mission time at which the start_* values hold (sets
                                    the ECI <-> ECEF angle); should equal the run's start */
    double alpha, beta, mu;      /* rad, constant inputs */
    double throttle;             /* -, constant input c_s, within every engine's limits */

    /* Optional control history: a 1-axis table over "time" (or "t") [s] whose outputs
     * named "alpha", "beta", "mu" [rad], "throttle" [-] replace the parameters of the
     * same name (others stay parameters). Throttle values are clamped into each engine's
     * limits. Its breakpoints are time events. Borrowed. */
    const lv_table *inputs;
    /* The variable the inputs table's axis holds (lv_dof3_over; default LV_DOF3_OVER_TIME):
     * mission time t [s]; tau = (t - start) / inputs_duration, the phase time normalised to
     * [0, 1] (start: the run's start time; inputs_duration NAN: inputs_stop_time - start);
     * or the state's geodetic altitude [m], speed relative to the rotating planet [m/s],
     * mass [kg] or specific energy v_rel^2 / 2 + LV_G0 h [J/kg]. The axis is then named
     * "tau", "altitude", "speed", "mass" or "energy" (no unit check beyond SI). Only a time
     * table's breakpoints are time events (the others' kinks are left to the step control). */
    int inputs_over;
    double inputs_duration;      /* s, > 0, or NAN (LV_DOF3_OVER_TAU only) */
    double inputs_stop_time;     /* s, mission time: tau's end when inputs_duration is NAN */

    /* Steering and throttle laws (lv_guidance.h: lv_steering_init, lv_steering_set,
     * lv_throttle_init, lv_throttle_set). Steering "inputs" (default): the inputs above. Any
     * other law replaces alpha, beta, mu and the inputs table's angles. steering.target_lat/lon
     * NAN (default): the start point (start_lat/lon). Throttle "nominal" (default): the
     * throttle above (the law's key "value" is a mission file's; here `throttle` gives it).
     * Tables borrowed. */
    lv_steering steering;
    lv_throttle_cfg throttle_law;

    int stop_at_burnout;       /* 1: burnout ends the run; 0: engines off, continue */
    size_t n_ends;
    const lv_dof3_end *ends;   /* [n_ends], copied */
} lv_dof3_config;

/* Earth (lv_planet_earth), no gravity (must be set), no atmosphere, m0 = 1000 kg,
 * propellant 0, no engines, no aero, all start values and inputs 0 except throttle 1,
 * stop_at_burnout 0, no ends; steering: "inputs" (target: the start point), throttle law:
 * "nominal" without limits. */
LV_API void lv_dof3_config_default(lv_dof3_config *cfg);

typedef struct lv_dof3 lv_dof3;

/* Checks `cfg` and builds the model. LV_ERR_INPUT names the offending field and value
 * (negative mass, throttle outside an engine's limits, a table without the axis or
 * output it needs, ...). lv_dof3_free() when done. */
LV_API lv_status lv_dof3_create(const lv_dof3_config *cfg, lv_dof3 **out, lv_err *err);
LV_API void lv_dof3_free(lv_dof3 *m); /* accepts NULL */

/* The model definition to pass to lv_simulate (owned by m). */
LV_API const lv_model_def *lv_dof3_def(const lv_dof3 *m);
/* The instance to pass to lv_simulate with it (owned by m). */
LV_API void *lv_dof3_inst(lv_dof3 *m);

/* Why the last callback failed (atmosphere or table out of range, wind, bad start
 * parameters), "" if none; valid until the next run. */
LV_API const char *lv_dof3_last_error(const lv_dof3 *m);

#ifdef __cplusplus
}
#endif
#endif
