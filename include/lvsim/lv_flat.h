/* lv_flat.h - the paper's test-case world: rocket stages as 6-DoF point masses over a flat,
 * non-rotating world with uniform gravity g along -z; thrust along +z (paper, section 4.1);
 * optionally air (lv_flat6): an atmosphere over the altitude z, a wind, and drag.
 *
 * Frame: x east, y north, z up (ENU), origin at the launch point. Attitude: 3-2-1 Euler
 * angles psi, theta, phi of the body relative to the local NED axes (north = +y, east = +x,
 * down = -z); body rates p, q, r [rad/s]. A point mass carries no torques, so the rates are
 * constant and the angles follow the Euler kinematics. Thirteen states per body:
 *     x y z [m], vx vy vz [m/s], psi theta phi [rad], p q r [rad/s], m [kg]
 *
 * Two models over the same body physics:
 *   - lv_flat6:    ONE body carrying a stack of stages (the sequential approach). Only the
 *                  bottom stage burns; its propellant running out is a state event.
 *   - lv_flat_e2e: ALL stages as separate bodies from liftoff to the end (the end-to-end
 *                  approach): connected bodies move together (an ideal joint: the stack's
 *                  acceleration is applied to each member), separations are time events,
 *                  each stage's burnout is a state event, a body that reaches the ground
 *                  stops there (impact event).
 * Thrust and mass flow: constant, or from a table over mission time (two of its outputs);
 * its breakpoints are time events while the engine burns.
 *
 * Air (lv_flat6 only; docs/models.md): with an atmosphere, the air data at the altitude z
 * (rho, p, speed of sound), the air-relative velocity v_air = v - v_wind (the wind's NED
 * components at z, as east = x, north = y, up = -down), Mach and q = rho |v_air|^2 / 2; with
 * an aerodynamic set, the drag q S_ref CD along -v_air. The body has no angle of attack (its
 * attitude does not steer it: thrust stays along +z), so CD is its drag coefficient at zero
 * angle of attack (in body axes: CA) and it has no lift or side force.
 */
#ifndef LVSIM_LV_FLAT_H
#define LVSIM_LV_FLAT_H

#include <stddef.h>

#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_model.h"
#include "lvsim/lv_status.h"
#include "lvsim/lv_table.h"
#include "lvsim/lv_vehicle.h"
#include "lvsim/lv_wind.h"

#ifdef __cplusplus
extern "C" {
#endif

enum lv_flat_x {
    LV_FLAT_X, LV_FLAT_Y, LV_FLAT_Z, LV_FLAT_VX, LV_FLAT_VY, LV_FLAT_VZ,
    LV_FLAT_PSI, LV_FLAT_THETA, LV_FLAT_PHI, LV_FLAT_P, LV_FLAT_Q, LV_FLAT_R, LV_FLAT_M,
    LV_FLAT_N
};

typedef struct lv_flat_engine {
    const lv_table *table; /* borrowed: thrust [N] and mass flow [kg/s] over time; or NULL */
    size_t thrust_out;     /* table output holding the thrust */
    size_t mdot_out;       /* table output holding the mass flow */
    double thrust;         /* N, when table == NULL */
    double mdot;           /* kg/s, when table == NULL */
    int count;             /* identical engines, >= 1 */
} lv_flat_engine;

typedef struct lv_flat_stage {
    const char *name;       /* copied */
    double dry_mass;        /* kg, >= 0 */
    double prop_mass;       /* kg, >= 0: propellant remaining at the start of the run */
    size_t n_engines;
    const lv_flat_engine *engines; /* copied */
} lv_flat_stage;

/* Events that may end a lv_flat6 run (besides its stop time). */
typedef enum lv_flat_end_kind {
    LV_FLAT_END_BURNOUT = 0, /* the bottom stage's propellant is gone (after the cut-off) */
    LV_FLAT_END_ALTITUDE,    /* z crosses value */
    LV_FLAT_END_SPEED,       /* |v| crosses value */
    LV_FLAT_END_APOGEE,      /* vz falls through zero */
    LV_FLAT_END_IMPACT       /* z falls through value */
} lv_flat_end_kind;

typedef struct lv_flat_end {
    lv_flat_end_kind kind;
    double value;
    lv_dir direction; /* ALTITUDE, SPEED; the others have a fixed direction */
} lv_flat_end;

typedef struct lv_flat6_config {
    const char *name;  /* model name in messages and results (copied); NULL: "flat6" */
    double g;          /* m/s^2, > 0 */
    size_t n_stages;   /* >= 1, bottom first */
    const lv_flat_stage *stages;
    size_t n_ends;
    const lv_flat_end *ends;
    /* the air (optional; see above): */
    const lv_atmo *atmo;         /* borrowed; NULL: none (vacuum) */
    const lv_wind *wind;         /* borrowed; NULL: still air. Needs an atmosphere */
    const lv_aero_config *aero;  /* copied, its tables borrowed; NULL: no aerodynamic force.
                                  * Drag only: coef[0] is CD (LV_AERO_WIND) or CA (LV_AERO_BODY),
                                  * a constant or a table over "mach" and "altitude" (axes
                                  * "alpha", "beta" are read at 0); coef[1], coef[2] must be the
                                  * constant 0. Needs an atmosphere */
} lv_flat6_config;

typedef struct lv_flat6 lv_flat6;

/* Builds the model: 13 states named as lv_flat_x ("x", "vz", "m", ...), the parameters
 * start_x, start_y, start_z [m], start_vel [m/s], start_fpa, start_chi [rad] (elevation
 * above the x-y plane; heading from north (+y) towards east (+x)), start_psi, start_theta,
 * start_phi [rad], start_p, start_q, start_r [rad/s], g [m/s^2]; m starts at the sum of the
 * stages' masses. Events: "burnout" (always: the engines stop), then the ends in order,
 * named "burnout", "altitude", "speed", "apogee", "impact". Outputs: thrust, mdot, speed,
 * accel, burning, propellant; with air also mach, q_dyn, rho, p_amb, v_air, drag. */
LV_API lv_status lv_flat6_create(const lv_flat6_config *cfg, lv_flat6 **out, lv_err *err);
LV_API void lv_flat6_free(lv_flat6 *m);
LV_API const lv_model_def *lv_flat6_def(const lv_flat6 *m);
LV_API void *lv_flat6_inst(lv_flat6 *m);

typedef struct lv_flat_e2e_config {
    const char *name;     /* NULL: "flat_e2e" */
    double g;             /* m/s^2, > 0 */
    size_t n_bodies;      /* >= 1: the stages, bottom first, stacked at liftoff */
    const lv_flat_stage *bodies;
    const double *t_sep;  /* [n_bodies - 1]: time body k separates from body k+1 (s) */
} lv_flat_e2e_config;

typedef struct lv_flat_e2e lv_flat_e2e;

/* 13 states per body, named "<stage>.x" ... "<stage>.m"; the same start parameters as
 * lv_flat6 (all bodies start together), g, and t_sep1 .. t_sep<n-1> [s]. Events per body:
 * "<stage>.burnout" and "<stage>.impact". Outputs per body: "<stage>.thrust" [N]. */
LV_API lv_status lv_flat_e2e_create(const lv_flat_e2e_config *cfg, lv_flat_e2e **out, lv_err *err);
LV_API void lv_flat_e2e_free(lv_flat_e2e *m);
LV_API const lv_model_def *lv_flat_e2e_def(const lv_flat_e2e *m);
LV_API void *lv_flat_e2e_inst(lv_flat_e2e *m);

#ifdef __cplusplus
}
#endif
#endif
