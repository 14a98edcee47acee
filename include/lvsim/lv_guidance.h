/* lv_guidance.h - steering and throttle laws of the 3-DoF model (lv_dof3.h).
 *
 * A steering law gives the vehicle's attitude (its body axes: thrust acts along body x) at
 * every instant; a throttle law the throttle c_s. Equations, frames and the source of each
 * law: docs/guidance.md. All angles in radians, times in seconds, SI throughout.
 *
 * Attitude frames:
 *   LV_FRAME_AERO      angle of attack alpha, sideslip beta and bank mu about the
 *                      air-relative velocity (the paper's inputs; Stevens & Lewis sec. 2.3).
 *   LV_FRAME_LOCAL     pitch theta, heading (yaw) psi and roll phi of the body axes relative
 *                      to the local NED frame at the vehicle: C_body_ned = R1(phi) R2(theta)
 *                      R3(psi) (3-2-1 Euler angles; theta = 90 deg points body x straight up).
 *   LV_FRAME_INERTIAL  the same angles relative to the NED frame at the phase's start,
 *                      frozen in inertial space (exo-atmospheric steering).
 * Whatever the frame, lift and drag act on the air-relative velocity; the angles of attack,
 * sideslip and bank that result, and the attitude relative to local NED, are outputs.
 */
#ifndef LVSIM_LV_GUIDANCE_H
#define LVSIM_LV_GUIDANCE_H

#include "lvsim/lv_table.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum lv_att_frame {
    LV_FRAME_AERO = 0,
    LV_FRAME_LOCAL = 1,
    LV_FRAME_INERTIAL = 2
} lv_att_frame;

typedef enum lv_steer_law {
    /* The model's parameters alpha, beta, mu (aerodynamic frame), or the `inputs` control
     * table over time that replaces them (lv_dof3_config.inputs): the paper's inputs. */
    LV_STEER_INPUTS = 0,
    /* Constant angles in `frame` (angle[0..2]: alpha, beta, mu or theta, psi, phi), or from
     * `table` over time, altitude, speed or Mach (axis named "time"/"t" [s, mission time],
     * "altitude"/"h" [m], "speed"/"v_rel" [m/s], "mach"), outputs named "alpha", "beta",
     * "mu" (aero) or "pitch", "heading", "roll" (local, inertial) in rad, and "throttle";
     * an angle the table does not give keeps its constant. */
    LV_STEER_ATTITUDE = 1,
    /* Vertical rise for rise_time, a pitch-over of `kick` at a constant rate over
     * kick_time in the plane of `heading` (local frame), then zero angle of attack, sideslip
     * and bank (thrust along the air-relative velocity): the gravity turn. Times from the
     * phase's start; both breakpoints are time events. */
    LV_STEER_GRAVITY_TURN = 2,
    /* Bilinear tangent: tan theta = (a + b tau) / (c + d tau), tau = t - phase start, in
     * `frame` (local or inertial), heading `heading`, roll 0. Linear tangent: c = 1, d = 0. */
    LV_STEER_TANGENT = 3,
    /* Bank to turn toward the target: mu = clamp(gain (bearing - chi_air), +-bank_max),
     * alpha = `alpha` or from `alpha_table` over Mach (output "alpha"), beta 0; with
     * n_max > 0, alpha is scaled down smoothly so that the lift load factor L / (m g0)
     * stays below n_max; with q_max > 0 that limit yields as the dynamic pressure rises to
     * q_max. Needs an aerodynamic dataset. */
    LV_STEER_HEADING = 4,
    /* Body x against the air-relative velocity (alpha = 180 deg, beta = mu = 0): entry and
     * landing burns. */
    LV_STEER_RETROGRADE = 5,
    /* Body x toward the target over the local horizon: heading = the bearing to the target,
     * pitch `pitch` above the horizon (local frame). */
    LV_STEER_BOOSTBACK = 6
} lv_steer_law;

typedef struct lv_steering {
    lv_steer_law law;
    lv_att_frame frame;     /* ATTITUDE (any), TANGENT (local or inertial) */
    double angle[3];        /* rad, ATTITUDE: alpha, beta, mu | pitch, heading, roll */
    const lv_table *table;  /* ATTITUDE: optional, borrowed (see above) */
    double rise_time;       /* s, GRAVITY_TURN, >= 0 */
    double kick;            /* rad, GRAVITY_TURN: pitch-over angle, in [0, pi/2] */
    double kick_time;       /* s, GRAVITY_TURN, >= 0 (0 with kick 0: straight to alpha 0) */
    double heading;         /* rad, GRAVITY_TURN and TANGENT: heading (yaw) of the plane */
    double a, b, c, d;      /* TANGENT: -, 1/s, -, 1/s; c + d tau must stay > 0 */
    double target_lat;      /* rad, geodetic: HEADING, BOOSTBACK and the target outputs */
    double target_lon;      /* rad */
    double bank_max;        /* rad, HEADING, in (0, pi/2] */
    double gain;            /* HEADING: bank per heading error (rad/rad), > 0 */
    double n_max;           /* HEADING: lift load-factor limit [g0], a soft saturation
                               (docs/guidance.md); 0: none */
    double q_max;           /* Pa, HEADING with n_max: above q_max / 2 the load-factor limit
                               yields, at q_max the schedule's alpha is back; 0: none */
    double alpha;           /* rad, HEADING: angle of attack when no alpha_table */
    const lv_table *alpha_table; /* HEADING: optional, 1 axis "mach", output "alpha" [rad] */
    double pitch;           /* rad, BOOSTBACK: pitch above the local horizon */
} lv_steering;

/* Throttle laws act on the throttle of the steering (the parameter "throttle" or the
 * table's): c_s = min(c_nominal, c_g, c_q) clamped into each engine's limits, or the
 * landing law's value; c_g keeps the axial load factor (thrust + axial aerodynamic
 * force) / (m g0) at g_limit; c_q makes the dynamic pressure obey dq/dt <= q_gain (q_max -
 * q), so that q approaches q_max without crossing it (docs/guidance.md). */
typedef enum lv_throttle_law {
    LV_THROTTLE_NOMINAL = 0, /* the nominal throttle with the limits below */
    LV_THROTTLE_LANDING = 1, /* a constant deceleration to land_speed at land_altitude:
                                a_up = (v_down^2 - land_speed^2) / (2 (h - land_altitude)) */
    LV_THROTTLE_OFF = 2      /* engines off: a coast, no propellant burnt */
} lv_throttle_law;

typedef struct lv_throttle_cfg {
    lv_throttle_law law;
    double g_limit;       /* axial load factor limit [g0]; 0: none */
    double q_max;         /* Pa; 0: none */
    double q_gain;        /* 1/s, > 0 with q_max (default 1) */
    double land_altitude; /* m, geodetic, LANDING */
    double land_speed;    /* m/s, >= 0, LANDING: touchdown speed */
} lv_throttle_cfg;

#ifdef __cplusplus
}
#endif
#endif
