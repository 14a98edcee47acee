/* lv_dof6.h - 6-DoF variable-mass rigid body over a rotating ellipsoidal planet (the paper's
 * sec. 2.3 and Table 1: start values psi, theta, phi, p, q, r).
 *
 * States (14): ECI position of the centre of mass and inertial velocity (as lv_dof3.h), the
 * attitude quaternion body -> ECI (scalar first), the body rates p, q, r relative to inertial
 * space in body axes, and the mass. Forces: gravity, thrust of several engines along their
 * gimballed and misaligned axes, acting at their gimbal points, aerodynamics from the
 * coefficient tables of lv_vehicle.h at the angle of attack and sideslip of the attitude.
 * Moments: thrust about the centre of mass, the aerodynamic moment coefficients Cl, Cm, Cn
 * (constants or tables) and damping derivatives Clp, Cmq, Cnr about a moment reference point
 * transferred to the moving centre of mass, the jet damping of the exhaust. Inertia tensor and
 * centre of mass are linear in the propellant used between full and empty values. Euler's
 * equations with the mass-variation terms: docs/models.md, "6-DoF rigid body".
 *
 * Body axes: x forward along the vehicle's axis, z down in the vehicle's plane of symmetry
 * (for a launcher: its "pitch plane"), y completing the right-handed frame. Positions on the
 * vehicle (centre of mass, moment reference point, engines) are body-axis components [m]
 * from one structural origin of the user's choice (e.g. the nose).
 *
 * Usage as lv_dof3.h: fill an lv_dof6_config (lv_dof6_config_default), lv_dof6_create(),
 * lv_simulate(lv_dof6_def(m), lv_dof6_inst(m), ...). One lv_dof6 serves one simulation at a
 * time.
 */
#ifndef LVSIM_LV_DOF6_H
#define LVSIM_LV_DOF6_H

#include <stddef.h>

#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_dof3.h"
#include "lvsim/lv_guidance.h"
#include "lvsim/lv_model.h"
#include "lvsim/lv_planet.h"
#include "lvsim/lv_status.h"
#include "lvsim/lv_table.h"
#include "lvsim/lv_vehicle.h"

#ifdef __cplusplus
extern "C" {
#endif

/* State indices: "r_eci_x" .. "v_eci_z" as lv_x3, "q_w", "q_x", "q_y", "q_z" (quaternion
 * body -> ECI, scalar first: v_eci = q v_body q*), "p", "q", "r" (body rates relative to
 * inertial space, body axes, rad/s), "m". */
enum lv_x6 {
    LV_X6_RX, LV_X6_RY, LV_X6_RZ,         /* position of the CG, ECI, m */
    LV_X6_VX, LV_X6_VY, LV_X6_VZ,         /* inertial velocity, ECI, m/s */
    LV_X6_QW, LV_X6_QX, LV_X6_QY, LV_X6_QZ, /* attitude quaternion body -> ECI, - */
    LV_X6_P, LV_X6_Q, LV_X6_R,            /* body rates, rad/s */
    LV_X6_M,                              /* mass, kg */
    LV_X6_QSG, LV_X6_QFM,                 /* heat loads, J/m^2: the time integrals of
                                             heat_flux and heat_flux_fm (quadratures) */
    LV_X6_N                               /* count */
};

/* Mass properties at the full and empty ends of the burning stage: the inertia tensor about
 * the centre of mass (body axes) and the centre of mass's position, each linear in the
 * propellant used, s = (m_full - m) / (m_full - m_empty) clamped to [0, 1]. */
typedef struct lv_dof6_mass {
    double m_full, m_empty;   /* kg, m_full > m_empty > 0 (or equal: constant properties) */
    double inertia_full[6];   /* kg m^2: tensor elements Ixx, Iyy, Izz, Ixy, Ixz, Iyz (the
                                 off-diagonal elements as they stand in the tensor, i.e.
                                 Ixy = -integral of x y dm); positive definite */
    double inertia_empty[6];  /* kg m^2, the same at m_empty */
    double cg_full[3];        /* m, body axes from the structural origin */
    double cg_empty[3];
} lv_dof6_mass;

/* Where one engine is and how its thrust is directed (body axes, structural origin). */
typedef struct lv_dof6_engine_geom {
    double pos[3];            /* m, gimbal point (the thrust's point of action) */
    double mis_pitch;         /* rad, misalignment added to the pitch gimbal angle */
    double mis_yaw;           /* rad, misalignment added to the yaw gimbal angle */
} lv_dof6_engine_geom;

/* Aerodynamic moments about the moment reference point r_mrp, body axes:
 *   L = q S b (Cl + Clp p' b / (2V)),  M = q S c (Cm + Cmq q' c / (2V)),
 *   N = q S b (Cn + Cnr r' b / (2V))
 * with p', q', r' the body rates relative to the atmosphere (inertial rates minus the planet's
 * rotation; the inertial rates with terms.rate_damping_frame LV_DOF6_DAMPING_INERTIAL) and V
 * the air-relative speed; S is the force set's s_ref. Cl, Cm, Cn are constants
 * or outputs of tables over "mach", "alpha", "beta", "altitude" (output names default to "Cl",
 * "Cm", "Cn" when a table has several). */
typedef struct lv_dof6_moments {
    lv_aero_coef cl, cm, cn;  /* -, rolling, pitching, yawing moment coefficients */
    double clp, cmq, cnr;     /* 1/rad, damping derivatives (< 0 damps) */
    double b_ref;             /* m, reference span (roll, yaw), > 0 */
    double c_ref;             /* m, reference chord (pitch), > 0 */
    double r_mrp[3];          /* m, moment reference point, body axes from the structural
                                 origin */
} lv_dof6_moments;

/* Attitude controller (docs/models.md, "Attitude control"): the attitude error e (body axes,
 * rad) is the rotation vector of the rotation from the actual body axes to the commanded ones
 * (those of the steering law, lv_guid_attitude), e = theta n with cos theta = (tr R - 1) / 2,
 * sin theta n = vex((R - R^T) / 2), R_ij = b_i . c_j (Euler axis and angle: Shuster, "A
 * survey of attitude representations", J. Astronaut. Sci. 41 (1993) 439-517). Pitch (body y) and yaw
 * (body z) are controlled by the gimbal of every engine (aft of the centre of mass):
 *   delta_c,pitch = kp_pitch e_y + ki_pitch integral(e_y) - kd_pitch q
 *   delta_c,yaw   = kp_yaw   e_z + ki_yaw   integral(e_z) - kd_yaw   r
 * clamped to +-limit; each gimbal angle is a state of a rate-limited first-order actuator
 *   delta' = rate_limit tanh((delta_c - delta) / (tau rate_limit)).
 * Roll (body x) is not controlled: engines that share one gimbal point have no roll authority;
 * the roll error is an output. kind PID adds the two integrals as states. */
typedef enum lv_dof6_ctl_kind {
    LV_DOF6_CTL_NONE = 0,
    LV_DOF6_CTL_PD = 1,
    LV_DOF6_CTL_PID = 2
} lv_dof6_ctl_kind;

typedef struct lv_dof6_controller {
    lv_dof6_ctl_kind kind;
    double kp[2];             /* rad of deflection per rad of error (pitch, yaw), > 0 */
    double kd[2];             /* rad per rad/s of body rate = s, >= 0 */
    double ki[2];             /* rad per rad s of integrated error = 1/s, >= 0 (PID) */
    double limit;             /* rad, deflection limit, in (0, pi/2] */
    double rate_limit;        /* rad/s, gimbal rate limit, > 0 */
    double tau;               /* s, actuator time constant, > 0 */
} lv_dof6_controller;

/* Start body rates of a 3-DoF -> 6-DoF hand-off (docs/models.md, "Level-of-detail
 * transitions"). */
typedef enum lv_dof6_rates_rule {
    LV_DOF6_RATES_ZERO = 0,     /* p = q = r = 0 */
    LV_DOF6_RATES_CURVATURE = 1 /* the angular velocity of the velocity relative to the planet */
} lv_dof6_rates_rule;

/* The rigid-body terms that published models and check cases treat differently, each
 * switchable (docs/models.md, "Rigid-body terms"). lv_dof6_config_default sets the defaults:
 * jet damping on, the inertia-rate term on, rate damping against the air.
 *   jet_damping         M_jd = -sum_e mdot_e r_e x (w x r_e), r_e = engine position - CG
 *                       (Thomson ch. 8; Zipfel sec. 9.2): 1 on, 0 off
 *   inertia_rate        -I' w in Euler's equation, I' = dI/dt as propellant is used
 *                       (Thomson ch. 8; Eke & Mao 2000): 1 on, 0 off
 *   rate_damping_frame  the body rates the damping derivatives Clp, Cmq, Cnr multiply: the
 *                       rates relative to the air that turns with the planet
 *                       (w - C_body_eci (0, 0, omega)), or relative to inertial space (w) */
typedef enum lv_dof6_damping_frame {
    LV_DOF6_DAMPING_AIR = 0,
    LV_DOF6_DAMPING_INERTIAL = 1
} lv_dof6_damping_frame;

typedef struct lv_dof6_terms {
    int jet_damping;                    /* 1 (default): on */
    int inertia_rate;                   /* 1 (default): on */
    lv_dof6_damping_frame rate_damping_frame; /* LV_DOF6_DAMPING_AIR (default) */
} lv_dof6_terms;

typedef struct lv_dof6_config {
    const char *name;          /* model name in reports; copied; NULL: "dof6" */
    lv_planet planet;          /* copied */
    const lv_gravity *gravity; /* borrowed, required */
    const lv_atmo *atmo;       /* borrowed; NULL: vacuum */
    lv_wind_fn wind;           /* NULL: no wind */
    void *wind_user;

    double m0;                 /* kg, start mass (default of state "m"), > 0 */
    double propellant;         /* kg, propellant of the burning stage at the start, < m0 */
    lv_dof6_mass mass;         /* mass properties (m_full 0: m0 and m0 - propellant) */
    size_t n_engines;
    const lv_engine_config *engines;      /* [n_engines], copied (tables borrowed) */
    const lv_dof6_engine_geom *engine_geom; /* [n_engines], copied; required with engines:
                                             the thrust moment and the jet damping act at
                                             their positions (no default position) */
    const double *engine_exit;            /* [3 n_engines] m, copied: each engine's nozzle
                                             exit centre, where the jet damping's exhaust
                                             leaves; NULL: at its position (engine_geom) */
    const lv_aero_config *aero;           /* copied; NULL: no aerodynamic force or moment */
    double nose_radius;        /* m, > 0: the nose radius of the stagnation-point heat flux
                                  (output heat_flux; default 1) */
    double k_sutton_graves;    /* kg^0.5/m, >= 0: Sutton-Graves constant of the atmosphere's gas
                                  (default LV_SUTTON_GRAVES_EARTH: air) */
    const lv_dof6_moments *moments;       /* copied; NULL: no aerodynamic moment (the force
                                             acts through the CG) */

    /* Default values of the parameters of the same name. Position and velocity as lv_dof3;
     * attitude: 3-2-1 Euler angles of the body relative to the local NED frame at the start
     * point and time; rates: body rates relative to inertial space. */
    double start_lat, start_lon, start_h, start_vel, start_fpa, start_chi, start_time;
    double start_psi, start_theta, start_phi; /* rad */
    double start_p, start_q, start_r;         /* rad/s */
    double gimbal_pitch, gimbal_yaw;          /* rad, constant inputs for every engine:
                                                 + pitch: thrust toward +z_b (nose-up moment
                                                 for an engine aft of the CG); + yaw: thrust
                                                 toward -y_b (nose-right moment) */
    double throttle;                          /* -, constant input */

    /* Optional input history: a 1-axis table over "time" [s] with outputs "gimbal_pitch",
     * "gimbal_yaw" [rad], "throttle" [-] that replace the parameters of the same name.
     * Borrowed. */
    const lv_table *inputs;

    /* Steering law (lv_guidance.h: lv_steering_init, lv_steering_set): "inputs" (default):
     * none. Otherwise the commanded attitude, its Euler angles and the attitude error are
     * outputs; with a controller the gimbal angles come from it (the inputs' gimbal angles are
     * then unused). target_lat/lon NAN: the start point. Keys that act in 3-DoF models only
     * (LV_KEY_DOF3: the heading law's n_max and q_max, a load-factor limit) are refused away
     * from their defaults. */
    lv_steering steering;
    lv_dof6_controller controller; /* kind NONE: gimbal angles from the inputs */

    int stop_at_burnout;
    size_t n_ends;
    const lv_dof3_end *ends;   /* [n_ends], copied: the end kinds of lv_dof3.h */

    lv_dof6_terms terms;       /* the switchable rigid-body terms (above) */
} lv_dof6_config;

/* Earth, no gravity (must be set), vacuum, m0 = 1000 kg, propellant 0, mass properties of a
 * unit sphere's inertia (1 kg m^2 about every axis) with the CG at the origin, no engines, no
 * aero, every start value and input 0 except throttle 1 and the quaternion of psi = theta =
 * phi = 0; no steering law, no controller; the rigid-body terms' defaults (lv_dof6_terms). */
LV_API void lv_dof6_config_default(lv_dof6_config *cfg);

typedef struct lv_dof6 lv_dof6;

/* Checks `cfg` and builds the model. LV_ERR_INPUT names the offending field and value (an
 * inertia tensor that is not positive definite, m_empty above m_full, a table without the
 * axis or output it needs, ...). lv_dof6_free() when done. */
LV_API lv_status lv_dof6_create(const lv_dof6_config *cfg, lv_dof6 **out, lv_err *err);
LV_API void lv_dof6_free(lv_dof6 *m); /* accepts NULL */

LV_API const lv_model_def *lv_dof6_def(const lv_dof6 *m);
LV_API void *lv_dof6_inst(lv_dof6 *m);
LV_API const char *lv_dof6_last_error(const lv_dof6 *m);

/* Quaternion body -> ECI [4] (scalar first) of the 3-2-1 Euler angles psi, theta, phi [rad] of
 * the body relative to the NED frame at geodetic latitude lat, longitude lon [rad], at time
 * t [s] on planet `pl`: C_eci_body = C_eci_ecef(t) C_ecef_ned(lat, lon) C_ned_body(psi, theta,
 * phi). For the hand-offs between phases and tests. */
LV_API void lv_dof6_quat_from_euler(const lv_planet *pl, double t, double lat, double lon,
                                    double psi, double theta, double phi, double q[4]);

/* Largest body rate a start value or the state may have [rad/s]: 10 revolutions per second
 * (a spin-stabilised stage spins at 1-2 rev/s). */
#define LV_DOF6_RATE_MAX (20.0 * 3.14159265358979323846)

/* The "curvature" rule of the 3-DoF -> 6-DoF hand-off: the body rates [rad/s, body axes]
 * of a body whose x axis follows the velocity relative to the planet, at time t [s], with the
 * 14 states x (position, velocity, attitude quaternion; rates and mass unused) and the
 * specific force f_eci [m/s^2, ECI] (thrust and aerodynamic force over mass) of the parent:
 *   u = v - W x r,  du/dt = a - W x v,  a = g(r) + f,  w = u x du/dt / |u|^2
 * (W the planet's rotation; the angular velocity in inertial space of the direction of u,
 * perpendicular to it: no roll about the velocity), w_body = C_body_eci w. Below |u| = 1 m/s
 * the direction is undefined: zero rates. Evaluates the model's gravity (not thread-safe on
 * one model). */
LV_API void lv_dof6_rates_from_trajectory(lv_dof6 *m, double t, const double *x,
                                          const double f_eci[3], double w_body[3]);

#ifdef __cplusplus
}
#endif
#endif
