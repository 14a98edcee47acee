/* lv_runway.h - the ground roll of a winged vehicle on a runway over the rotating planet:
 * the take-off roll (thrust, drag, lift, rolling friction, rotation at a given speed, ending
 * at lift-off) and its mirror, the landing roll-out (engines off, braking friction, ending at
 * a stop speed).
 *
 * The runway is the straight line from its threshold (geodetic latitude, longitude,
 * elevation) along its heading in the local horizontal plane there, fixed to the rotating
 * planet. The vehicle is held on it by its wheels: the state is one-dimensional (distance
 * along the runway, ground speed along it, mass: 3 states), and everything else follows
 * from the constraint. The forces are those of the 3-DoF model (lv_dof3.h) evaluated at
 * the vehicle's ECEF position and velocity on the runway: the same planet, gravity,
 * atmosphere, wind, engines and aerodynamic data, so that one parameter set stays
 * consistent across a hand-off. The 3-DoF states (r_eci_*, v_eci_*) are outputs: a 3-DoF
 * phase that starts from a runway phase starts exactly where the roll ended.
 * Equations, frames, variables, events and sources: docs/models.md ("The runway model").
 *
 * Usage: fill an lv_runway_config (start from lv_runway_config_default), lv_runway_create(),
 * then lv_simulate(lv_runway_def(m), lv_runway_inst(m), &settings, ...). One lv_runway
 * serves one simulation at a time.
 */
#ifndef LVSIM_LV_RUNWAY_H
#define LVSIM_LV_RUNWAY_H

#include <stddef.h>

#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_model.h"
#include "lvsim/lv_planet.h"
#include "lvsim/lv_status.h"
#include "lvsim/lv_vehicle.h"

#ifdef __cplusplus
extern "C" {
#endif

/* State indices: "distance", "speed", "m". */
enum lv_xrw {
    LV_XRW_S, /* distance along the runway from its threshold, m */
    LV_XRW_V, /* ground speed along the runway (relative to the rotating planet), m/s */
    LV_XRW_M, /* mass, kg */
    LV_XRW_N  /* count */
};

typedef enum lv_runway_mode {
    LV_RUNWAY_TAKEOFF = 0, /* engines on; rotation at v_rot; ends at lift-off */
    LV_RUNWAY_LANDING = 1  /* engines off; braking friction; ends when the speed falls
                              through v_stop */
} lv_runway_mode;

/* The model's own state events, before the configured ends (lv_runway_config.ends, whose
 * events follow in order): burnout, rotation, lift-off or stop, at rest, overrun. */
#define LV_RUNWAY_OWN_EVENTS 5

/* A further end: the ground speed crosses `value` (m/s) in `direction`. */
typedef struct lv_runway_end {
    const char *name;  /* copied; NULL: "speed" */
    double value;      /* m/s, >= 0 */
    lv_dir direction;
} lv_runway_end;

typedef struct lv_runway_config {
    const char *name;          /* model name in reports; copied; NULL: "runway" */
    lv_planet planet;          /* copied (default lv_planet_earth()) */
    const lv_gravity *gravity; /* borrowed, required */
    const lv_atmo *atmo;       /* borrowed; NULL: vacuum (no aerodynamics) */
    lv_wind_fn wind;           /* NULL: no wind */
    void *wind_user;

    lv_runway_mode mode;
    double m0;                 /* kg, start mass (default of state "m"), > 0 */
    double propellant;         /* kg, propellant of the burning stage, 0 <= propellant < m0 */
    size_t n_engines;          /* take-off: the engines that burn; landing: ignored (off) */
    const lv_engine_config *engines; /* [n_engines], copied (tables borrowed) */
    const lv_aero_config *aero; /* copied (tables borrowed); NULL: no aerodynamic force */

    /* Defaults of the parameters of the same name. */
    double runway_lat, runway_lon; /* rad, geodetic position of the threshold */
    double runway_h;           /* m, geodetic elevation of the threshold */
    double runway_heading;     /* rad, from north to east */
    double runway_length;      /* m, > 0: the roll ends by the event "overrun" where the
                                  distance rises through it; INFINITY (default): no end */
    double mu;                 /* -, rolling (take-off) or braking (landing) friction
                                  coefficient, >= 0 */
    double alpha_ground;       /* rad, angle of attack on all wheels */
    double v_rot;              /* m/s, take-off: rotation starts when the speed rises
                                  through it (> 0) */
    double alpha_rot;          /* rad, take-off: angle of attack after rotation,
                                  >= alpha_ground */
    double rotation_rate;      /* rad/s, take-off: pitch rate of the rotation; 0: instant */
    double v_stop;             /* m/s, landing: the roll-out ends when the speed falls
                                  through it (> 0) */
    double start_distance;     /* m, from the threshold */
    double start_speed;        /* m/s, >= 0 */
    double start_time;         /* s, mission time at which the start values hold */
    double throttle;           /* -, take-off: constant throttle within every engine's limits */

    int stop_at_burnout;       /* 1: burnout ends the run; 0: engines off, continue */
    size_t n_ends;
    const lv_runway_end *ends; /* [n_ends], copied */
} lv_runway_config;

/* Earth, no gravity (must be set), no atmosphere, take-off, m0 = 1000 kg, no engines, no
 * aero, runway at (0, 0, 0 m) heading north, mu = 0.02, alpha_ground = alpha_rot = 0,
 * v_rot = 1e9 m/s (no rotation), rotation_rate 0, v_stop = 1 m/s, start at rest on the
 * threshold at t = 0, throttle 1, no ends, runway_length INFINITY (no end). */
LV_API void lv_runway_config_default(lv_runway_config *cfg);

typedef struct lv_runway lv_runway;

/* Checks `cfg` and builds the model; LV_ERR_INPUT names the field and value.
 * lv_runway_free() when done. */
LV_API lv_status lv_runway_create(const lv_runway_config *cfg, lv_runway **out, lv_err *err);
LV_API void lv_runway_free(lv_runway *m); /* accepts NULL */

LV_API const lv_model_def *lv_runway_def(const lv_runway *m);
LV_API void *lv_runway_inst(lv_runway *m);

/* A point and velocity relative to the planet (a 3-DoF vehicle at touchdown) in the runway's
 * axes: along the centre line from the threshold, up along the normal of the runway plane,
 * and to the right of the centre line. */
typedef struct lv_runway_pos {
    double distance;      /* m, along the runway from the threshold */
    double speed;         /* m/s, ground speed along it */
    double height;        /* m, above the runway plane */
    double sink_rate;     /* m/s, downward speed across the plane (positive: descending) */
    double lateral;       /* m, offset to the right of the centre line */
    double lateral_speed; /* m/s, speed to the right */
} lv_runway_pos;

/* The runway position of ECEF position r_ecef [m] and velocity relative to the planet
 * v_ecef [m/s]; the runway's geometry is the configuration's defaults. */
LV_API void lv_runway_project(const lv_runway *m, const double r_ecef[3], const double v_ecef[3],
                              lv_runway_pos *out);

#ifdef __cplusplus
}
#endif
#endif
