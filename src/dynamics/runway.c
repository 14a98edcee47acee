/* runway.c - the ground roll on a runway over the rotating planet (lv_runway.h): take-off
 * (rolling friction, rotation, lift-off) and landing roll-out (braking friction to a stop
 * speed). The along-runway equation is the classical ground-roll equation (Raymer, Aircraft
 * Design: A Conceptual Approach, 6th ed., sec. 17.8.1; Anderson, Aircraft Performance and
 * Design, sec. 6.7), written for the 3-DoF forces of flight.h resolved on the runway's axis
 * and normal. Equations: docs/models.md ("The runway model"). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "core/units.h"
#include "core/vec3.h"
#include "dynamics/flight.h"
#include "dynamics/flight_model.h"
#include "lvsim/lv_runway.h"
#include "vehicle/vehicle.h"

/* ---- variables ---------------------------------------------------------------------- */

enum {
    P_LAT, P_LON, P_H, P_HDG, P_MU, P_AG, P_VROT, P_AROT, P_RATE, P_VSTOP,
    P_S0, P_V0, P_T0, P_THR, P_PROP, P_LEN, P_N
};

enum {
    O_H, O_LAT, O_LON, O_VREL, O_FPA, O_CHI, O_MACH, O_Q, O_RHO, O_PAMB,
    O_THRUST, O_MDOT, O_DRAG, O_LIFT, O_NORMAL, O_FRICTION, O_ACCEL, O_NAX,
    O_ALPHA, O_THR, O_ENGINE_ON, O_ROTATING, O_PROP_LEFT, O_LIFT_MARGIN,
    O_RX, O_RY, O_RZ, O_VX, O_VY, O_VZ,
    O_IIP_LAT, O_IIP_LON, O_IIP_TOF, O_IIP_RANGE, /* the impact point: here, on the ground */
    O_N
};

/* Events: burnout, rotation, the mode's own end (liftoff or stop), at rest (a take-off that
 * slows to a standstill: an aborted take-off ends there), the runway's end (overrun: the
 * distance rises through the runway's length), then the configured speed ends. */
enum { E_BURNOUT, E_ROTATION, E_END, E_REST, E_OVERRUN, E_N0 };
_Static_assert(E_N0 == LV_RUNWAY_OWN_EVENTS, "lv_runway.h: LV_RUNWAY_OWN_EVENTS");

static const lv_var state_tpl[LV_XRW_N] = {
    {"distance", "m", "Distance along the runway from its threshold", 0.0, 1e3},
    {"speed", "m/s", "Ground speed along the runway (relative to the rotating planet)", 0.0,
     10.0},
    {"m", "kg", "Vehicle mass", 1000.0, 1e3},
};

static const lv_var param_tpl[P_N] = {
    {"runway_lat", "rad", "Geodetic latitude of the runway threshold", 0, 0},
    {"runway_lon", "rad", "Longitude of the runway threshold", 0, 0},
    {"runway_h", "m", "Geodetic elevation of the runway threshold", 0, 0},
    {"runway_heading", "rad", "Runway heading, from north to east", 0, 0},
    {"mu", "1", "Rolling (take-off) or braking (landing) friction coefficient", 0, 0},
    {"alpha_ground", "rad", "Angle of attack on all wheels", 0, 0},
    {"v_rot", "m/s", "Rotation speed (take-off)", 0, 0},
    {"alpha_rot", "rad", "Angle of attack after rotation (take-off)", 0, 0},
    {"rotation_rate", "rad/s", "Pitch rate of the rotation; 0: instant (take-off)", 0, 0},
    {"v_stop", "m/s", "The roll-out ends when the speed falls through it (landing)", 0, 0},
    {"start_distance", "m", "Start distance from the threshold", 0, 0},
    {"start_speed", "m/s", "Start ground speed along the runway", 0, 0},
    {"start_time", "s", "Mission time at which the start values hold", 0, 0},
    {"throttle", "1", "Throttle c_s (constant input, take-off)", 1, 0},
    {"propellant", "kg", "Propellant of the burning stage at the start: burnout when it is gone",
     0, 0},
    {"runway_length", "m", "Runway length from the threshold: the roll ends (overrun) where "
     "the distance rises through it; infinite: no end", 0, 0},
};

static const lv_var output_vars[O_N] = {
    {"h", "m", "Geodetic altitude", 0, 0},
    {"lat", "rad", "Geodetic latitude", 0, 0},
    {"lon", "rad", "Longitude", 0, 0},
    {"v_rel", "m/s", "Speed relative to the rotating planet", 0, 0},
    {"fpa", "rad", "Flight-path angle of the relative velocity, up positive", 0, 0},
    {"heading", "rad", "Heading of the relative velocity, from north to east", 0, 0},
    {"mach", "1", "Mach number of the air-relative velocity", 0, 0},
    {"q_dyn", "Pa", "Dynamic pressure rho V_air^2 / 2", 0, 0},
    {"rho", "kg/m3", "Air density", 0, 0},
    {"p_amb", "Pa", "Ambient pressure", 0, 0},
    {"thrust", "N", "Net thrust of all engines", 0, 0},
    {"mdot", "kg/s", "Propellant mass flow of all engines (-dm/dt)", 0, 0},
    {"drag", "N", "Drag: aerodynamic force opposite the air-relative velocity", 0, 0},
    {"lift", "N", "Lift: aerodynamic force along wind -z", 0, 0},
    {"normal_force", "N", "Force of the runway on the wheels, along its normal (>= 0)", 0, 0},
    {"friction", "N", "Rolling or braking friction mu N, against the motion", 0, 0},
    {"accel", "m/s2", "Acceleration along the runway dV/dt", 0, 0},
    {"n_axial", "1", "Axial load factor: specific force (thrust + aero) along body x / g0", 0, 0},
    {"alpha_in", "rad", "Angle of attack in effect", 0, 0},
    {"throttle_in", "1", "Throttle in effect (0 with the engines off)", 0, 0},
    {"engine_on", "1", "1 while the engines burn", 0, 0},
    {"rotating", "1", "1 from the rotation on (take-off)", 0, 0},
    {"propellant_left", "kg", "Propellant left in the burning stage", 0, 0},
    {"lift_margin", "1", "(lift + thrust normal part) / weight normal part: 1 at lift-off", 0, 0},
    {"r_eci_x", "m", "Position, ECI x (the 3-DoF model's state)", 0, 0},
    {"r_eci_y", "m", "Position, ECI y", 0, 0},
    {"r_eci_z", "m", "Position, ECI z", 0, 0},
    {"v_eci_x", "m/s", "Inertial velocity, ECI x (the 3-DoF model's state)", 0, 0},
    {"v_eci_y", "m/s", "Inertial velocity, ECI y", 0, 0},
    {"v_eci_z", "m/s", "Inertial velocity, ECI z", 0, 0},
    {"iip_lat", "rad", "Instantaneous impact point, latitude: on the ground, the vehicle's own "
     "(as lat)", 0, 0},
    {"iip_lon", "rad", "Instantaneous impact point, longitude: the vehicle's own (as lon)", 0, 0},
    {"iip_tof", "s", "Time of flight to the impact point: 0 on the ground", 0, 0},
    {"iip_range", "m", "Distance to the impact point: 0 on the ground", 0, 0},
};

#define EVENT_NAME_MAX 48

/* ---- model data ---------------------------------------------------------------------- */

typedef struct rw_inst {
    lv_runway *m;          /* NULL in a block lv_simulate zeroed itself */
    int engines_on;        /* mode: 1 while propellant remains (take-off) */
    int burned_out;
    int rotating;          /* mode: the rotation has begun (take-off) */
    double t_rot;          /* s, when it began */
    double m_burnout;      /* kg */
    lv_vec3 r0, u, n;      /* threshold [m, ECEF], runway axis and normal (unit, ECEF) */
    lv_flight_trig_cache trig;
    char msg[LV_ERR_MSG_MAX];
} rw_inst;

struct lv_runway {
    lv_model_def def;
    char name[64];
    lv_runway_mode mode;
    lv_var states[LV_XRW_N];
    lv_var params[P_N];
    unsigned char param_inactive[P_N]; /* lv_model_def.param_inactive */
    size_t n_ends;
    lv_runway_end *ends;
    lv_event_def *events;
    char (*event_names)[EVENT_NAME_MAX];
    lv_flight_world world;
    double *grav_ws;
    size_t n_eng;
    lv_engine *eng;
    double *eng_buf;
    int has_aero;
    lv_aero aero;
    int stop_at_burnout;
    rw_inst inst;
};

/* Everything the right-hand side and the outputs derive from (t, x, p). */
typedef struct rw_point {
    lv_flight_kin kin;      /* 1. kinematics on the runway */
    lv_flight_air air;      /* 2. flight condition */
    lv_flight_controls ctl; /* 3. controls: alpha, beta = mu = 0, throttle */
    lv_flight_axes ax;      /* 4. axes, */
    double thrust, mdot;    /*    engines */
    double coef[3];
    lv_vec3 f_aero, f_sum;  /*    N, ECEF */
    lv_vec3 g_app;          /* 5. gravitation + the rotating frame's apparent acceleration */
    double normal_raw, normal, friction, dv_dt; /* the ground-roll equation */
} rw_point;

/* ---- the equations of motion ------------------------------------------------------------- */

/* The runway geometry at the threshold (lat, lon [rad], h [m], heading chi [rad]): its ECEF
 * position r0, the axis u = cos chi N + sin chi E and the normal n = -D (local up) of the
 * threshold's geodetic NED frame (docs/frames.md, F9). */
static void runway_frame(const lv_planet *pl, double lat, double lon, double h, double chi,
                         lv_vec3 *r0, lv_vec3 *u, lv_vec3 *n)
{
    double r[3], C[3][3];
    lv_frames_geodetic_to_ecef(pl, lat, lon, h, r);
    lv_frames_C_ned_ecef(lat, lon, C);
    *r0 = lv_v3(r[0], r[1], r[2]);
    const double c = cos(chi), s = sin(chi);
    *u = lv_v3(c * C[0][0] + s * C[1][0], c * C[0][1] + s * C[1][1], c * C[0][2] + s * C[1][2]);
    *n = lv_v3(-C[2][0], -C[2][1], -C[2][2]);
}

/* The ground roll (Raymer sec. 17.8.1: m dV/dt = T - D - mu (W - L), generalised): a mass m
 * held on a straight runway (axis u, normal n) by its wheels, under the force f (thrust +
 * aerodynamics, N) and the specific force g_app (gravitation + the rotating frame's
 * apparent acceleration, m/s^2), moving at speed V along u. The wheels give the normal force
 *     N_raw = -(f + m g_app) . n,   N = max(0, N_raw)
 * (what keeps the acceleration normal to the runway zero; N_raw <= 0: the vehicle lifts off)
 * and the friction mu N against the motion; at rest the friction holds the vehicle while
 * the drive along u is below mu N (static friction, taken equal to the rolling one). The
 * lateral force the tyres take (crosswind, the Coriolis force) does no work on the motion. */
static void ground_roll(lv_vec3 f, lv_vec3 g_app, lv_vec3 u, lv_vec3 n, double m, double mu,
                        double V, rw_point *pt)
{
    const double drive = lv_v3_dot(f, u) + m * lv_v3_dot(g_app, u);
    pt->normal_raw = -(lv_v3_dot(f, n) + m * lv_v3_dot(g_app, n));
    pt->normal = pt->normal_raw > 0.0 ? pt->normal_raw : 0.0;
    const double fmax = mu * pt->normal;
    if (V > 0.0)
        pt->friction = fmax;
    else if (V < 0.0)
        pt->friction = -fmax;
    else /* at rest: static friction up to mu N */
        pt->friction = drive > fmax ? fmax : drive < -fmax ? -fmax : drive;
    pt->dv_dt = (drive - pt->friction) / m;
}

/* Angle of attack in effect: alpha_ground; from the rotation on, raised at rotation_rate to
 * alpha_rot (instantly with rate 0). */
static double alpha_of(const rw_inst *s, double t, const double *p)
{
    if (!s->rotating)
        return p[P_AG];
    if (!(p[P_RATE] > 0.0))
        return p[P_AROT];
    const double a = p[P_AG] + p[P_RATE] * (t - s->t_rot);
    return a < p[P_AROT] ? a : p[P_AROT];
}

/* ECEF position and velocity relative to the planet at (s, V) on the runway. */
static void on_runway(const rw_inst *s, const double *x, lv_vec3 *r, lv_vec3 *v)
{
    *r = lv_v3_add(s->r0, lv_v3_scale(s->u, x[LV_XRW_S]));
    *v = lv_v3_scale(s->u, x[LV_XRW_V]);
}

/* Steps 1-5 of flight.h for a vehicle on the runway, then the ground roll. */
static int point_eval(lv_runway *m, rw_inst *s, double t, const double *x, const double *p,
                      int full, rw_point *pt, lv_err *err)
{
    const double mass = x[LV_XRW_M];
    if (!(mass > 0.0)) {
        if (err)
            lv_fail(err, LV_ERR_INPUT, "mass %g kg is not positive at t = %.9g s", mass, t);
        return 1;
    }
    const lv_flight_world *w = &m->world;
    lv_flight_kin *k = &pt->kin;
    const double th = w->planet.theta0 + w->planet.omega * t;
    k->c_th = cos(th);
    k->s_th = sin(th);
    on_runway(s, x, &k->r_ecef, &k->v_rel);
    lv_flight_geodetic(w, k, full, w->wind_latlon); /* a wind that reads lat, lon */
    int rc = lv_flight_air_eval(w, t, k, &pt->air, err);
    if (rc != 0)
        return rc;
    const double u0[LV_CTRL_N] = {alpha_of(s, t, p), 0.0, 0.0, p[P_THR]};
    if (lv_flight_controls_eval(u0, &(lv_flight_schedule){.table = NULL, .k = {-1, -1, -1, -1}}, NULL,
                                &s->trig, t, &pt->ctl, err) != 0)
        return 1;
    /* at rest in still air the wind axes take the runway's direction */
    lv_flight_axes_eval(k, &pt->air, &pt->ctl, 0.0, p[P_HDG], &pt->ax);
    if (lv_flight_thrust(m->eng, m->n_eng, s->engines_on, t, &pt->ctl, &pt->air, m->eng_buf,
                         &pt->thrust, &pt->mdot, err) != 0 ||
        lv_flight_aero(m->has_aero ? &m->aero : NULL, k, &pt->air, &pt->ctl, &pt->ax, pt->coef,
                       &pt->f_aero, err) != 0)
        return 1;
    pt->f_sum = lv_v3_add(lv_v3_scale(pt->ax.xb, pt->thrust), pt->f_aero);
    pt->g_app = lv_v3_add(lv_flight_gravity(w, m->grav_ws, k), lv_flight_frame_accel(w, k));
    ground_roll(pt->f_sum, pt->g_app, s->u, s->n, mass, p[P_MU], x[LV_XRW_V], pt);
    return 0;
}

/* ---- callbacks ---------------------------------------------------------------------------- */

static int fail_inst(rw_inst *s, const char *fmt, ...) LV_PRINTF(2, 3);
static int fail_inst(rw_inst *s, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(s->msg, sizeof s->msg, fmt, ap);
    va_end(ap);
    return -1;
}

static int rw_rhs(double t, const double *x, const double *p, double *xdot, void *inst)
{
    rw_inst *s = inst;
    rw_point pt;
    int rc = point_eval(s->m, s, t, x, p, 0, &pt, NULL);
    if (rc != 0) {
        lv_err e = {LV_OK, ""};
        point_eval(s->m, s, t, x, p, 0, &pt, &e);
        snprintf(s->msg, sizeof s->msg, "%s", e.msg);
        return rc;
    }
    xdot[LV_XRW_S] = x[LV_XRW_V];
    xdot[LV_XRW_V] = pt.dv_dt;
    xdot[LV_XRW_M] = -pt.mdot;
    return 0;
}

/* The parameters a run can change by name. */
static int check_params(rw_inst *s, const double *p)
{
    const lv_runway *m = s->m;
    for (int i = 0; i < P_N; i++)
        if (!isfinite(p[i]) && !((i == P_VROT || i == P_LEN) && p[i] > 0.0))
            return fail_inst(s, "%s = %g %s is not finite", param_tpl[i].name, p[i],
                             param_tpl[i].unit);
    if (!(fabs(p[P_LAT]) <= 0.5 * LV_PI))
        return fail_inst(s, "runway_lat = %g rad is outside [-pi/2, pi/2]", p[P_LAT]);
    if (!(p[P_MU] >= 0.0))
        return fail_inst(s, "mu = %g is negative", p[P_MU]);
    if (!(p[P_V0] >= 0.0))
        return fail_inst(s, "start_speed = %g m/s is negative", p[P_V0]);
    if (!(p[P_PROP] >= 0.0))
        return fail_inst(s, "propellant = %g kg is negative", p[P_PROP]);
    if (!(p[P_LEN] > 0.0))
        return fail_inst(s, "runway_length = %g m must be > 0", p[P_LEN]);
    if (m->mode == LV_RUNWAY_TAKEOFF) {
        if (!(p[P_VROT] > 0.0))
            return fail_inst(s, "v_rot = %g m/s must be > 0", p[P_VROT]);
        if (!(p[P_AROT] >= p[P_AG]))
            return fail_inst(s, "alpha_rot = %g rad is below alpha_ground = %g rad: the rotation "
                             "raises the nose", p[P_AROT], p[P_AG]);
        if (!(p[P_RATE] >= 0.0))
            return fail_inst(s, "rotation_rate = %g rad/s is negative", p[P_RATE]);
        for (size_t i = 0; i < m->n_eng; i++)
            if (!(p[P_THR] >= m->eng[i].thr_min && p[P_THR] <= m->eng[i].thr_max))
                return fail_inst(s, "throttle = %g is outside the limits [%g, %g] of engine '%s'",
                                 p[P_THR], m->eng[i].thr_min, m->eng[i].thr_max, m->eng[i].name);
    } else if (!(p[P_VSTOP] > 0.0)) {
        return fail_inst(s, "v_stop = %g m/s must be > 0: the roll-out ends when the speed falls "
                         "through it", p[P_VSTOP]);
    }
    return 0;
}

static int rw_start(const double *p, double *x, void *inst)
{
    rw_inst *s = inst;
    if (s == NULL || s->m == NULL)
        return -1; /* not an lv_runway instance */
    s->msg[0] = '\0';
    if (check_params(s, p) != 0)
        return -1;
    x[LV_XRW_S] = p[P_S0];
    x[LV_XRW_V] = p[P_V0];
    return 0; /* the mass keeps the start value of state "m" */
}

/* The start parameters of the state the run started from (lv_model_def.start_params): the
 * distance and speed a hand-off gave (a roll-out projected from a dof3 touchdown). */
static int rw_start_params(double t0, const double *x, double *p, void *inst)
{
    (void)inst;
    p[P_S0] = x[LV_XRW_S];
    p[P_V0] = x[LV_XRW_V];
    p[P_T0] = t0;
    return 0;
}

static int rw_init(double t0, const double *x, const double *p, void *inst)
{
    rw_inst *s = inst;
    if (s == NULL || s->m == NULL)
        return -1;
    s->msg[0] = '\0';
    if (check_params(s, p) != 0)
        return -1;
    if (!(x[LV_XRW_M] > 0.0))
        return fail_inst(s, "start mass m = %g kg is not positive", x[LV_XRW_M]);
    if (!(x[LV_XRW_V] >= 0.0))
        return fail_inst(s, "start speed %g m/s is negative: the runway model rolls forwards",
                         x[LV_XRW_V]);
    if (!(p[P_PROP] < x[LV_XRW_M]))
        return fail_inst(s, "the propellant %g kg is not less than the start mass %g kg",
                         p[P_PROP], x[LV_XRW_M]);
    runway_frame(&s->m->world.planet, p[P_LAT], p[P_LON], p[P_H], p[P_HDG], &s->r0, &s->u,
                 &s->n);
    s->m_burnout = x[LV_XRW_M] - p[P_PROP];
    s->burned_out = 0;
    s->engines_on = s->m->mode == LV_RUNWAY_TAKEOFF && s->m->n_eng > 0 && p[P_PROP] > 0.0;
    /* a take-off that starts at or above the rotation speed starts rotated (at t0) */
    s->rotating = s->m->mode == LV_RUNWAY_TAKEOFF && x[LV_XRW_V] >= p[P_VROT];
    s->t_rot = t0;
    for (int k = 0; k < 3; k++)
        s->trig.ang[k] = NAN;
    if (s->m->mode == LV_RUNWAY_LANDING && !(x[LV_XRW_V] > p[P_VSTOP]))
        return fail_inst(s, "the roll-out starts at %g m/s, not above v_stop = %g m/s: it has "
                         "nothing to do", x[LV_XRW_V], p[P_VSTOP]);
    if (s->m->mode == LV_RUNWAY_TAKEOFF) { /* the runway cannot pull the vehicle down */
        rw_point pt;
        lv_err e = {LV_OK, ""};
        if (point_eval(s->m, s, t0, x, p, 0, &pt, &e) != 0)
            return fail_inst(s, "at the start: %s", e.msg);
        if (!(pt.normal_raw > 0.0))
            return fail_inst(s, "the vehicle is already flying at the start (t = %.9g s, %g m/s): "
                             "lift and thrust carry its weight on the runway (normal force %g "
                             "N); start a flight phase instead", t0, x[LV_XRW_V],
                             pt.normal_raw);
    }
    return 0;
}

static int rw_g(double t, const double *x, const double *p, double *g, void *inst)
{
    rw_inst *s = inst;
    const lv_runway *m = s->m;
    g[E_BURNOUT] = s->engines_on ? x[LV_XRW_M] - s->m_burnout : 1.0;
    g[E_ROTATION] = m->mode == LV_RUNWAY_TAKEOFF && !s->rotating ? x[LV_XRW_V] - p[P_VROT] : 1.0;
    if (m->mode == LV_RUNWAY_TAKEOFF) {
        rw_point pt;
        if (point_eval(s->m, s, t, x, p, 0, &pt, NULL) != 0)
            return 1;
        g[E_END] = pt.normal_raw; /* lift-off: the wheels carry nothing */
    } else {
        g[E_END] = x[LV_XRW_V] - p[P_VSTOP];
    }
    /* the speed falling to 0 while rolling: at rest, where the friction's sign flips (the
     * ground-roll equation switches to static friction: the phase ends there) */
    g[E_REST] = m->mode == LV_RUNWAY_TAKEOFF ? x[LV_XRW_V] : 1.0;
    g[E_OVERRUN] = isfinite(p[P_LEN]) ? x[LV_XRW_S] - p[P_LEN] : -1.0;
    for (size_t i = 0; i < m->n_ends; i++)
        g[E_N0 + i] = x[LV_XRW_V] - m->ends[i].value;
    return 0;
}

static lv_event_action rw_on_event(double t, double *x, const double *p, const int *fired,
                                   void *inst)
{
    (void)x;
    rw_inst *s = inst;
    const lv_runway *m = s->m;
    lv_event_action act = LV_EVENT_CONTINUE;
    if (fired[E_BURNOUT]) {
        s->engines_on = 0;
        s->burned_out = 1;
        act = m->stop_at_burnout ? LV_EVENT_STOP : LV_EVENT_RESTART;
    }
    if (fired[E_ROTATION] && !s->rotating) {
        s->rotating = 1;
        s->t_rot = t;
        if (act != LV_EVENT_STOP)
            act = LV_EVENT_RESTART;
        /* an instant rotation that lifts the vehicle at once: lift-off here */
        rw_point pt;
        if (!(p[P_RATE] > 0.0) && point_eval(s->m, s, t, x, p, 0, &pt, NULL) == 0 &&
            pt.normal_raw <= 0.0)
            act = LV_EVENT_STOP;
    }
    if (fired[E_END] || fired[E_REST] || fired[E_OVERRUN])
        act = LV_EVENT_STOP;
    for (size_t i = 0; i < m->n_ends; i++)
        if (fired[E_N0 + i])
            act = LV_EVENT_STOP;
    return act;
}

/* The end of a rotation at a finite rate: a kink of alpha(t), a time event. */
static double rw_next_time_event(double t, const double *p, void *inst)
{
    const rw_inst *s = inst;
    double tn = INFINITY;
    if (s->rotating && p[P_RATE] > 0.0) {
        const double te = s->t_rot + (p[P_AROT] - p[P_AG]) / p[P_RATE];
        if (te > t)
            tn = te;
    }
    for (size_t i = 0; i < s->m->n_eng; i++)
        if (s->m->eng[i].table != NULL) {
            const double tb = lv_table_next_breakpoint(s->m->eng[i].table, 0, t);
            if (tb < tn)
                tn = tb;
        }
    return tn;
}

static const char *rw_time_event_name(double t, const double *p, void *inst)
{
    const rw_inst *s = inst;
    if (s->rotating && p[P_RATE] > 0.0 && t == s->t_rot + (p[P_AROT] - p[P_AG]) / p[P_RATE])
        return "rotation complete (alpha_rot reached)";
    return "engine table breakpoint";
}

static int rw_outputs(double t, const double *x, const double *p, double *y, void *inst)
{
    rw_inst *s = inst;
    lv_runway *m = s->m;
    rw_point pt;
    lv_err e = {LV_OK, ""};
    int rc = point_eval(m, s, t, x, p, 1, &pt, &e);
    if (rc != 0) {
        snprintf(s->msg, sizeof s->msg, "%s", e.msg);
        return rc;
    }
    const lv_flight_kin *k = &pt.kin;
    const double mass = x[LV_XRW_M];
    y[O_H] = k->h;
    y[O_LAT] = k->lat;
    y[O_LON] = k->lon;
    y[O_VREL] = lv_v3_norm(k->v_rel);
    const double ned[3] = {lv_v3_dot(k->v_rel, k->n_ax), lv_v3_dot(k->v_rel, k->e_ax),
                           lv_v3_dot(k->v_rel, k->d_ax)};
    if (y[O_VREL] > 0.0) {
        lv_frames_fpa_from_ned(ned, NULL, &y[O_FPA], &y[O_CHI]);
    } else {
        y[O_FPA] = 0.0;
        y[O_CHI] = p[P_HDG];
    }
    y[O_MACH] = pt.air.mach;
    y[O_Q] = pt.air.q;
    y[O_RHO] = pt.air.rho;
    y[O_PAMB] = pt.air.p_amb;
    y[O_THRUST] = pt.thrust;
    y[O_MDOT] = pt.mdot;
    y[O_DRAG] = -lv_v3_dot(pt.f_aero, pt.ax.xw);
    y[O_LIFT] = -lv_v3_dot(pt.f_aero, pt.ax.zw);
    y[O_NORMAL] = pt.normal;
    y[O_FRICTION] = pt.friction;
    y[O_ACCEL] = pt.dv_dt;
    y[O_NAX] = lv_v3_dot(pt.f_sum, pt.ax.xb) / (mass * LV_G0);
    y[O_ALPHA] = pt.ctl.u[LV_CTRL_ALPHA];
    y[O_THR] = s->engines_on ? pt.ctl.u[LV_CTRL_THROTTLE] : 0.0;
    y[O_ENGINE_ON] = s->engines_on;
    y[O_ROTATING] = s->rotating;
    y[O_PROP_LEFT] = s->burned_out || mass < s->m_burnout ? 0.0 : mass - s->m_burnout;
    const double w_n = -mass * lv_v3_dot(pt.g_app, s->n); /* the weight's normal part */
    y[O_LIFT_MARGIN] = w_n > 0.0 ? lv_v3_dot(pt.f_sum, s->n) / w_n : 0.0;
    double r[3] = {k->r_ecef.x, k->r_ecef.y, k->r_ecef.z};
    double v[3] = {k->v_rel.x, k->v_rel.y, k->v_rel.z}, r_eci[3], v_eci[3];
    lv_frames_ecef_to_eci(&m->world.planet, t, r, v, r_eci, v_eci);
    for (int i = 0; i < 3; i++) {
        y[O_RX + i] = r_eci[i];
        y[O_VX + i] = v_eci[i];
    }
    /* held on the runway: it is where it would come down (the flight models' iip_* outputs,
     * docs/models.md, "Instantaneous impact point"; here so a body's trajectory has them
     * across a take-off or a landing) */
    y[O_IIP_LAT] = k->lat;
    y[O_IIP_LON] = k->lon;
    y[O_IIP_TOF] = 0.0;
    y[O_IIP_RANGE] = 0.0;
    return 0;
}

static const char *rw_last_error(const void *inst)
{
    const rw_inst *s = inst;
    return s != NULL && s->msg[0] != '\0' ? s->msg : NULL;
}

/* ---- construction --------------------------------------------------------------------------- */

void lv_runway_config_default(lv_runway_config *cfg)
{
    memset(cfg, 0, sizeof *cfg);
    cfg->planet = lv_planet_earth();
    cfg->m0 = 1000.0;
    cfg->mu = 0.02;
    cfg->v_rot = 1e9;
    cfg->v_stop = 1.0;
    cfg->throttle = 1.0;
    cfg->runway_length = INFINITY;
}

static lv_status bad(lv_err *err, const char *what, double v, const char *unit, const char *rule)
{
    return lv_fail(err, LV_ERR_INPUT, "runway: %s = %g %s (%s)", what, v, unit, rule);
}

static lv_status check_config(const lv_runway_config *c, lv_err *err)
{
    if (c->mode != LV_RUNWAY_TAKEOFF && c->mode != LV_RUNWAY_LANDING)
        return lv_fail(err, LV_ERR_INPUT, "runway: unknown mode %d", (int)c->mode);
    if (!isfinite(c->m0) || !(c->m0 > 0.0))
        return bad(err, "m0", c->m0, "kg", "must be > 0");
    if (!isfinite(c->propellant) || c->propellant < 0.0 || !(c->propellant < c->m0))
        return bad(err, "propellant", c->propellant, "kg", "must be >= 0 and less than m0");
    if (!(fabs(c->runway_lat) <= 0.5 * LV_PI))
        return bad(err, "runway_lat", c->runway_lat, "rad", "must be in [-pi/2, pi/2]");
    const struct { const char *n; double v; const char *u; } fin[] = {
        {"runway_lon", c->runway_lon, "rad"}, {"runway_h", c->runway_h, "m"},
        {"runway_heading", c->runway_heading, "rad"}, {"alpha_ground", c->alpha_ground, "rad"},
        {"alpha_rot", c->alpha_rot, "rad"}, {"start_distance", c->start_distance, "m"},
        {"start_time", c->start_time, "s"}, {"throttle", c->throttle, ""}};
    for (size_t i = 0; i < sizeof fin / sizeof fin[0]; i++)
        if (!isfinite(fin[i].v))
            return bad(err, fin[i].n, fin[i].v, fin[i].u, "must be finite");
    if (!isfinite(c->mu) || c->mu < 0.0)
        return bad(err, "mu", c->mu, "", "must be >= 0");
    if (!isfinite(c->start_speed) || c->start_speed < 0.0)
        return bad(err, "start_speed", c->start_speed, "m/s", "must be >= 0");
    if (c->mode == LV_RUNWAY_TAKEOFF) {
        if (!(c->v_rot > 0.0))
            return bad(err, "v_rot", c->v_rot, "m/s", "must be > 0");
        if (!(c->alpha_rot >= c->alpha_ground))
            return bad(err, "alpha_rot", c->alpha_rot, "rad",
                       "must be >= alpha_ground: the rotation raises the nose");
        if (!isfinite(c->rotation_rate) || c->rotation_rate < 0.0)
            return bad(err, "rotation_rate", c->rotation_rate, "rad/s", "must be >= 0 (0: instant)");
    } else if (!isfinite(c->v_stop) || !(c->v_stop > 0.0)) {
        return bad(err, "v_stop", c->v_stop, "m/s", "must be > 0");
    }
    if (!(c->runway_length > 0.0))
        return bad(err, "runway_length", c->runway_length, "m", "must be > 0 (INFINITY: no end)");
    return LV_OK;
}

static lv_status setup_events(lv_runway *m, const lv_runway_config *cfg, lv_err *err)
{
    const size_t n = cfg->n_ends;
    if (n > 0 && cfg->ends == NULL)
        return lv_fail(err, LV_ERR_INPUT, "runway: n_ends = %zu but ends is NULL", n);
    m->events = calloc(E_N0 + n, sizeof *m->events);
    m->event_names = calloc(E_N0 + n, sizeof *m->event_names);
    m->ends = calloc(n + 1, sizeof *m->ends);
    if (!m->events || !m->event_names || !m->ends)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    const int to = m->mode == LV_RUNWAY_TAKEOFF;
    snprintf(m->event_names[E_BURNOUT], EVENT_NAME_MAX, "burnout");
    snprintf(m->event_names[E_ROTATION], EVENT_NAME_MAX, "rotation");
    snprintf(m->event_names[E_END], EVENT_NAME_MAX, "%s", to ? "liftoff" : "stop");
    m->events[E_BURNOUT] = (lv_event_def){m->event_names[E_BURNOUT],
                                          "Propellant exhausted", LV_DIR_FALLING, 0};
    m->events[E_ROTATION] = (lv_event_def){m->event_names[E_ROTATION],
                                           "Speed rises through v_rot: the nose rises",
                                           LV_DIR_RISING, 0};
    m->events[E_END] =
        (lv_event_def){m->event_names[E_END],
                       to ? "Lift-off: the runway's normal force falls through zero"
                          : "The speed falls through v_stop: roll-out complete",
                       LV_DIR_FALLING, 1};
    snprintf(m->event_names[E_REST], EVENT_NAME_MAX, "at_rest");
    m->events[E_REST] = (lv_event_def){m->event_names[E_REST],
                                       "Take-off: the speed falls to 0 (an aborted take-off "
                                       "stops on the runway)", LV_DIR_FALLING, 0};
    snprintf(m->event_names[E_OVERRUN], EVENT_NAME_MAX, "overrun");
    m->events[E_OVERRUN] = (lv_event_def){m->event_names[E_OVERRUN],
                                          "The distance rises through the runway's length: "
                                          "the vehicle runs off its end", LV_DIR_RISING, 1};
    for (size_t i = 0; i < n; i++) {
        const lv_runway_end *e = &cfg->ends[i];
        const char *nm = e->name != NULL ? e->name : "speed";
        if (nm[0] == '\0' || strlen(nm) >= EVENT_NAME_MAX)
            return lv_fail(err, LV_ERR_INPUT, "runway: ends[%zu]: name '%s' is empty or longer "
                           "than %d characters", i, nm, EVENT_NAME_MAX - 1);
        for (size_t j = 0; j < E_N0 + i; j++)
            if (strcmp(m->event_names[j], nm) == 0)
                return lv_fail(err, LV_ERR_INPUT, "runway: ends[%zu]: event name '%s' is used "
                               "twice", i, nm);
        if (!isfinite(e->value) || e->value < 0.0)
            return lv_fail(err, LV_ERR_INPUT, "runway: end '%s': speed %g m/s must be >= 0", nm,
                           e->value);
        if (e->direction < LV_DIR_FALLING || e->direction > LV_DIR_RISING)
            return lv_fail(err, LV_ERR_INPUT, "runway: end '%s': direction %d", nm,
                           (int)e->direction);
        snprintf(m->event_names[E_N0 + i], EVENT_NAME_MAX, "%s", nm);
        m->ends[i] = *e;
        m->ends[i].name = m->event_names[E_N0 + i];
        m->events[E_N0 + i] = (lv_event_def){m->event_names[E_N0 + i],
                                             "Ground speed crosses the configured value",
                                             e->direction, 1};
    }
    m->n_ends = n;
    return LV_OK;
}

lv_status lv_runway_create(const lv_runway_config *cfg, lv_runway **out, lv_err *err)
{
    *out = NULL;
    lv_status st = check_config(cfg, err);
    if (st != LV_OK)
        return st;
    lv_runway *m = calloc(1, sizeof *m);
    if (m == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    snprintf(m->name, sizeof m->name, "%s", cfg->name != NULL ? cfg->name : "runway");
    m->mode = cfg->mode;
    if ((st = lv_flight_world_setup(&m->world, "runway", &cfg->planet, cfg->gravity, cfg->atmo,
                                    cfg->wind, cfg->wind_user, &m->grav_ws, NULL, err)) != LV_OK)
        goto fail;
    /* a landing roll-out's engines are off */
    if ((st = lv_flight_engines_init("runway", cfg->engines,
                                     cfg->mode == LV_RUNWAY_TAKEOFF ? cfg->n_engines : 0, &m->eng,
                                     &m->n_eng, &m->eng_buf, err)) != LV_OK)
        goto fail;
    for (size_t i = 0; i < m->n_eng; i++)
        if (!(cfg->throttle >= m->eng[i].thr_min && cfg->throttle <= m->eng[i].thr_max)) {
            st = lv_fail(err, LV_ERR_INPUT, "runway: throttle = %g is outside the limits [%g, "
                         "%g] of engine '%s'", cfg->throttle, m->eng[i].thr_min,
                         m->eng[i].thr_max, m->eng[i].name);
            goto fail;
        }
    if (cfg->aero != NULL) {
        if ((st = lv_aero_init(&m->aero, cfg->aero, err)) != LV_OK) {
            lv_fail_prefix(err, st, "runway");
            goto fail;
        }
        m->has_aero = 1;
    }
    m->stop_at_burnout = cfg->stop_at_burnout != 0;
    if ((st = setup_events(m, cfg, err)) != LV_OK)
        goto fail;

    memcpy(m->states, state_tpl, sizeof m->states);
    m->states[LV_XRW_M].start = cfg->m0;
    m->states[LV_XRW_M].nominal = cfg->m0;
    memcpy(m->params, param_tpl, sizeof m->params);
    const double pv[P_N] = {cfg->runway_lat, cfg->runway_lon, cfg->runway_h,
                            cfg->runway_heading, cfg->mu, cfg->alpha_ground, cfg->v_rot,
                            cfg->alpha_rot, cfg->rotation_rate, cfg->v_stop,
                            cfg->start_distance, cfg->start_speed, cfg->start_time,
                            cfg->throttle, cfg->propellant, cfg->runway_length};
    for (int i = 0; i < P_N; i++)
        m->params[i].start = pv[i];
    /* no engine (a landing roll-out's are off): the throttle does not act and is not recorded
     * as a constant (throttle_in: 0) */
    m->param_inactive[P_THR] = m->n_eng == 0;
    m->def = (lv_model_def){
        .name = m->name,
        .description = cfg->mode == LV_RUNWAY_TAKEOFF
                           ? "Take-off roll on a runway over a rotating planet"
                           : "Landing roll-out on a runway over a rotating planet",
        .n_states = LV_XRW_N,
        .n_params = P_N,
        .n_outputs = O_N,
        .n_events = E_N0 + m->n_ends,
        .states = m->states,
        .params = m->params,
        .outputs = output_vars,
        .events = m->events,
        .inst_size = sizeof(rw_inst),
        .start = rw_start,
        .init = rw_init,
        .rhs = rw_rhs,
        .event_g = rw_g,
        .on_event = rw_on_event,
        .next_time_event = rw_next_time_event,
        .outputs_fn = rw_outputs,
        .last_error = rw_last_error,
        .time_event_name = rw_time_event_name,
        .param_inactive = m->param_inactive,
        .start_params = rw_start_params,
    };
    m->inst.m = m;
    runway_frame(&m->world.planet, cfg->runway_lat, cfg->runway_lon, cfg->runway_h,
                 cfg->runway_heading, &m->inst.r0, &m->inst.u, &m->inst.n);
    if ((st = lv_model_validate(&m->def, err)) != LV_OK)
        goto fail;
    *out = m;
    return LV_OK;
fail:
    lv_runway_free(m);
    return st;
}

void lv_runway_free(lv_runway *m)
{
    if (m == NULL)
        return;
    lv_aero_clear(&m->aero);
    free(m->eng);
    free(m->eng_buf);
    free(m->grav_ws);
    free(m->events);
    free(m->event_names);
    free(m->ends);
    free(m);
}

const lv_model_def *lv_runway_def(const lv_runway *m) { return &m->def; }

void *lv_runway_inst(lv_runway *m) { return &m->inst; }

void lv_runway_project(const lv_runway *m, const double r_ecef[3], const double v_ecef[3],
                       lv_runway_pos *out)
{
    const rw_inst *s = &m->inst;
    const lv_vec3 d = lv_v3_sub(lv_v3(r_ecef[0], r_ecef[1], r_ecef[2]), s->r0);
    const lv_vec3 v = lv_v3(v_ecef[0], v_ecef[1], v_ecef[2]);
    const lv_vec3 right = lv_v3_cross(s->u, s->n); /* forward x up = right */
    out->distance = lv_v3_dot(d, s->u);
    out->speed = lv_v3_dot(v, s->u);
    out->height = lv_v3_dot(d, s->n);
    out->sink_rate = -lv_v3_dot(v, s->n);
    out->lateral = lv_v3_dot(d, right);
    out->lateral_speed = lv_v3_dot(v, right);
}
