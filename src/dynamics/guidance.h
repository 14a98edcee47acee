/* guidance.h - the steering and throttle laws of lv_guidance.h in the right-hand side (not
 * exported). Step 3 of flight.h ("controls") for a model that steers: the law gives the body
 * axes and the aerodynamic angles that result (lv_guid_attitude), and, once the forces
 * without thrust are known, the throttle (lv_guid_throttle). Pure functions of their
 * arguments except the table cursors and the trigonometry cache in lv_guid_rt; nothing is
 * allocated or looked up by name. Equations: docs/guidance.md.
 */
#ifndef LV_DYNAMICS_GUIDANCE_H
#define LV_DYNAMICS_GUIDANCE_H

#include "core/vec3.h"
#include "dynamics/flight.h"
#include "lvsim/lv_guidance.h"
#include "lvsim/lv_status.h"

/* What a table's axis is read against. */
typedef enum { LV_GAXIS_TIME, LV_GAXIS_ALTITUDE, LV_GAXIS_SPEED, LV_GAXIS_MACH } lv_gaxis;

/* A steering law resolved for the hot path (one per model; read-only while flying). */
typedef struct lv_guid {
    lv_steering s;
    lv_gaxis axis;        /* ATTITUDE table's axis */
    int k[4];             /* ATTITUDE table's output for each angle and the throttle, -1: none */
    size_t n_out;         /* outputs of the larger table (scratch size) */
    double cs_heading[2]; /* cos, sin of s.heading */
    double cs_pitch[2];   /* BOOSTBACK: cos, sin of s.pitch */
    lv_vec3 target;       /* unit vector of the target point, ECEF (geocentric direction) */
    lv_vec3 target_r;     /* m, the target point on the ellipsoid, ECEF */
    int need_alpha, need_beta; /* the aerodynamic tables read alpha, beta (else the right-hand
                                  side skips them: outputs only) */
} lv_guid;

/* Per simulation instance: the phase's start, the frozen inertial frame, cursors, scratch. */
typedef struct lv_guid_rt {
    double t0;              /* s, the phase's start */
    lv_vec3 f0[3];          /* N0, E0, D0 at the phase's start, ECI components */
    lv_table_cursor cur;    /* ATTITUDE table */
    lv_table_cursor alpha_cur; /* HEADING alpha table */
    double buf[16];         /* table outputs (tables with more outputs are refused) */
    double ang[3], cs[3][2]; /* trigonometry of the last attitude angles */
} lv_guid_rt;

/* Resolves `s` (checked: ranges, table axes and outputs, frames; a HEADING law needs an
 * aerodynamic dataset: has_aero) into g. `planet` places the target. LV_ERR_INPUT names
 * the field and value. */
lv_status lv_guid_init(lv_guid *g, const lv_steering *s, const lv_planet *planet, int has_aero,
                       lv_err *err);

/* A table law's table: an ATTITUDE table over time, altitude, speed or Mach with at least
 * one of the frame's angle outputs or "throttle"; a HEADING alpha table over Mach with output
 * "alpha"; at most 16 outputs. With g, records the axis and output indices. */
lv_status lv_guid_table_check(const lv_table *t, lv_steer_law law, lv_att_frame frame,
                             lv_guid *g, lv_err *err);

/* 1 when the law's attitude reads the atmosphere (Mach: an attitude table over Mach, the
 * heading law's alpha over Mach), 0 when it needs only the kinematics and the air-relative
 * velocity. */
int lv_guid_reads_atmosphere(const lv_guid *g);

/* At the phase's start (time t0, kinematics k): freezes the inertial frame, resets the
 * cursors. */
void lv_guid_start(const lv_guid *g, lv_guid_rt *rt, double t0, const lv_flight_kin *k);

/* The next breakpoint of the law after t (gravity turn: end of the rise and of the kick;
 * an attitude table over time: its breakpoints), or INFINITY. */
double lv_guid_next_time_event(const lv_guid *g, const lv_guid_rt *rt, double t);

/* What the law's time event at t is ("end of the vertical rise", "end of the kick", "attitude
 * table breakpoint"), or NULL when the law has none at t. */
const char *lv_guid_time_event_label(const lv_guid *g, const lv_guid_rt *rt, double t);

/* The time events of a flight model over the planet (dof3, dof6): the breakpoints on the first
 * axis (time) of its inputs table and of its engines' tables, and its steering law's events
 * (g NULL: no law). The next one after t, or INFINITY. */
double lv_flight_next_time_event(const lv_table *inputs, const lv_engine *eng, size_t n_eng,
                                 const lv_guid *g, const lv_guid_rt *rt, double t);

/* What those events at t are, written into buf[cap] ("inputs table 'x' breakpoint; end of
 * the kick t = 14 s"); "" when none. Returns buf. */
const char *lv_flight_time_event_label(const lv_table *inputs, const lv_engine *eng,
                                       size_t n_eng, const lv_guid *g, const lv_guid_rt *rt,
                                       double t, char *buf, size_t cap);

/* Attitude at time t: fills ax (wind and body axes, ECEF) and c->u[alpha, beta, mu] with
 * their cosines and sines (the angles that result for an attitude frame; 0 below 1e-6 m/s
 * of air-relative speed, where the wind axes are the body axes), and c->u[throttle] from
 * `throttle` or the law's table; the bank mu that results from an attitude only when `full`
 * (outputs: the force does not need it; NAN otherwise). (fpa0, chi0): the direction the aerodynamic frame takes
 * without air-relative speed (lv_flight_axes_eval). Returns 0, or 1 when a table cannot be
 * evaluated (err, may be NULL). */
int lv_guid_attitude(const lv_guid *g, lv_guid_rt *rt, double t, const lv_flight_kin *k,
                     const lv_flight_air *a, double throttle, double fpa0, double chi0, int full,
                     lv_flight_controls *c, lv_flight_axes *ax, lv_err *err);

/* HEADING with n_max > 0: the law's angle of attack `alpha` [rad] given the lift L [N] it
 * gives, the mass [kg] and the dynamic pressure q [Pa]: lv_guid_heading_alpha with the lift
 * load factor n = |L| / (m g0) and the law's n_max, q_max. Other laws, n_max 0: alpha. */
double lv_guid_alpha_limited(const lv_guid *g, double alpha, double lift, double mass, double q);

/* The heading law's limits on its scheduled angle of attack `alpha` [rad] (pure; equations
 * in docs/guidance.md, "heading"). n: the lift load factor L / (m g0) at `alpha`; n_max > 0.
 * Load-factor limit, a soft saturation: a_n = alpha / (1 + (n / n_max)^8)^(1/8); for a lift
 * coefficient proportional to alpha the lift load factor becomes n / (1 + (n/n_max)^8)^(1/8),
 * below n_max for every n, within 0.1 % of n below n_max / 2 and tending to n_max as n grows
 * (a smooth function of the state: no switch for the integrator to resolve). Dynamic-pressure
 * release, q_max > 0: alpha_cmd = a_n + s (alpha - a_n), s = 3 t^2 - 2 t^3, t = clamp(2 q /
 * q_max - 1, 0, 1): at q >= q_max the schedule's alpha (the drag and lift of the high angle
 * of attack stop a dive instead of the limit lowering alpha and letting q grow), at q <=
 * q_max / 2 the limited one. q_max 0: a_n. n <= 0 or n_max <= 0: alpha. */
double lv_guid_heading_alpha(double alpha, double n, double n_max, double q, double q_max);

/* The forces a throttle law needs, thrust excluded. T(c) = c (t_full + p_ae) - p_ae is the
 * engines' net thrust at throttle c [N]. */
typedef struct lv_thr_in {
    double mass;        /* kg */
    double t_full;      /* N, net thrust at full throttle (c = 1) */
    double p_ae;        /* N, ambient pressure x the engines' exit areas */
    double c_min, c_max; /* the throttle range every engine accepts */
    lv_vec3 xb;         /* body x, ECEF */
    lv_vec3 f_aero;     /* N, ECEF */
    lv_vec3 a_nothrust; /* m/s^2, ECEF: acceleration relative to the rotating planet without
                           thrust: g + f_aero/m - 2 w x v_rel - w x (w x r) */
    lv_vec3 up;         /* local vertical (-d), ECEF */
    double h;           /* m, geodetic altitude */
    double v_down;      /* m/s, downward speed relative to the planet */
    double h_dot;       /* m/s */
    double drho_dh;     /* kg/m^4 (q_max only) */
} lv_thr_in;

/* The throttle of law `t` given the nominal throttle `c_nom`, before the engines' clamp into
 * [c_min, c_max]: outside it the law asks for more (or less) than the engines can give and
 * its limit does not hold there. */
double lv_guid_throttle(const lv_throttle_cfg *t, double c_nom, const lv_thr_in *in,
                        const lv_flight_air *a);

/* Target outputs: great-circle distance [m] on the sphere of radius `radius` and initial
 * bearing [rad, from north to east] from the vehicle to the target, and the overshoot [m]
 * of a vacuum ballistic flight over flat ground in uniform gravity `g` from here along that
 * bearing: (horizontal velocity toward the target) x (time to fall to h = 0) - distance. */
void lv_guid_target(const lv_guid *g, const lv_flight_kin *k, double radius, double g_up,
                    double *distance, double *bearing, double *overshoot);

/* Attitude relative to local NED (3-2-1 Euler angles) of body axes ax. */
void lv_guid_euler_local(const lv_flight_kin *k, const lv_flight_axes *ax, double *theta,
                         double *psi, double *phi);

#endif
