/* dof3.c - 3-DoF variable-mass point over a rotating planet, integrated in ECI Cartesian
 * coordinates (the paper's sec. 2.2: dm = mdot, forces G + A + T). Rotating-frame
 * kinematics as in Stevens, Lewis & Johnson, Aircraft Control and Simulation, 3rd ed.,
 * sec. 1.6; wind/body axes as in sec. 2.3 there. Equations: docs/models.md. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/root.h"
#include "core/status.h"
#include "core/table_unit.h"
#include "core/units.h"
#include "core/vec3.h"
#include "dynamics/flight.h"
#include "dynamics/flight_ends.h"
#include "dynamics/flight_model.h"
#include "dynamics/guidance.h"
#include "dynamics/orbit.h"
#include "lvsim/lv_dof3.h"
#include "vehicle/vehicle.h"

/* ---- variables ------------------------------------------------------------------- */

enum {
    P_LAT, P_LON, P_H, P_VEL, P_FPA, P_CHI, P_T0, P_ALPHA, P_BETA, P_MU, P_THR, P_PROP,
    P_PH_EL, P_PH_RX, P_PH_VX = P_PH_RX + 3, P_N = P_PH_VX + 3
};
/* inputs: the controls lv_flight_controls knows, in the order of P_ALPHA.. */
enum { U_ALPHA = LV_CTRL_ALPHA, U_BETA = LV_CTRL_BETA, U_MU = LV_CTRL_MU,
       U_THR = LV_CTRL_THROTTLE, U_N = LV_CTRL_N };

enum {
    O_H, O_LAT, O_LON, O_LAT_GC, O_RADIUS, O_VN, O_VE, O_VD, O_VREL, O_VINR,
    O_FPA, O_CHI, O_FPA_I, O_CHI_I, O_MACH, O_Q, O_RHO, O_PAMB,
    O_NAX, O_NNORM, O_NLAT, O_ACC, O_ACC_SENSED,
    O_THRUST, O_DRAG, O_LIFT, O_SIDE, O_MDOT, O_ENGINE_ON,
    O_ALPHA, O_BETA, O_MU, O_THR, O_DOWNRANGE,
    O_SMA, O_ECC, O_INC, O_RAAN, O_ARGP, O_APO, O_PERI,
    O_THETA, O_PSI, O_PHI, O_PROP_LEFT, O_TGT_DIST, O_TGT_BEAR, O_TGT_OVER, O_THR_EFF,
    O_ENG_RUN,
    O_HEAT_SG, O_HEAT_FM, /* aerothermal heating */
    O_IIP_LAT, O_IIP_LON, O_IIP_TOF, O_IIP_RANGE, /* instantaneous impact point */
    O_WIND_N, O_WIND_E, O_WIND_D, /* the wind at the vehicle */
    O_N
};

/* Error control (docs/integration.md): the position is measured from the planet's centre, so
 * a relative tolerance on it would be |r| tol (6 m at 1e-6): its error is controlled absolutely,
 * to tol x 1 km (1 mm at the missions' default 1e-6); the velocity to tol (|v| + 1 m/s); the
 * mass to tol (m + m0). Chosen on the ball drop of tests/python/check_drop.py: with these, every
 * adaptive method at 1e-6 ends within 4 mm and 0.5 mm/s of the exact solution. */
static const lv_var state_tpl[LV_X3_N] = {
    {"r_eci_x", "m", "Position, ECI x", 0.0, 1e3},
    {"r_eci_y", "m", "Position, ECI y", 0.0, 1e3},
    {"r_eci_z", "m", "Position, ECI z", 0.0, 1e3},
    {"v_eci_x", "m/s", "Inertial velocity, ECI x", 0.0, 1.0},
    {"v_eci_y", "m/s", "Inertial velocity, ECI y", 0.0, 1.0},
    {"v_eci_z", "m/s", "Inertial velocity, ECI z", 0.0, 1.0},
    {"m", "kg", "Vehicle mass", 1000.0, 1e3},
    LV_FLIGHT_HEAT_LOAD_STATES
};

/* The position's error is controlled absolutely (lv_model_def.abs_error). */
static const unsigned char abs_error[LV_X3_N] = {1, 1, 1, 0, 0, 0, 0, 0, 0};
/* The heat loads are quadratures: out of the error control (lv_model_def.quadrature). */
static const unsigned char quadrature[LV_X3_N] = {0, 0, 0, 0, 0, 0, 0, 1, 1};

static const lv_var param_tpl[P_N] = {
    {"start_lat", "rad", "Initial geodetic latitude", 0, 0},
    {"start_lon", "rad", "Initial longitude", 0, 0},
    {"start_h", "m", "Initial geodetic altitude", 0, 0},
    {"start_vel", "m/s", "Initial speed relative to the rotating planet", 0, 0},
    {"start_fpa", "rad", "Initial flight-path angle of the relative velocity, up positive", 0, 0},
    {"start_chi", "rad", "Initial heading of the relative velocity, from north to east", 0, 0},
    {"start_time", "s", "Mission time at which the start_* values hold", 0, 0},
    {"alpha", "rad", "Angle of attack (constant input)", 0, 0},
    {"beta", "rad", "Sideslip angle (constant input)", 0, 0},
    {"mu", "rad", "Bank angle about the air-relative velocity (constant input)", 0, 0},
    {"throttle", "1", "Throttle c_s (constant input)", 1, 0},
    {"propellant", "kg", "Propellant of the burning stage at the start: burnout when it is gone",
     0, 0},
    /* A run that flies a piece of a phase (a multiple-shooting segment of an optimiser,
     * src/optimal/) starts from the piece's state, but what the phase keeps from its own start
     * is the phase's: the steering law's start (its time, its frozen inertial frame, a law's
     * start values) and the downrange origin. 0: the run is the phase (the others unread). */
    {"phase_elapsed", "s", "Time since the phase's start at the run's start, when the run "
     "flies a piece of the phase (0: the run starts the phase)", 0, 0},
    {"phase_start_r_eci_x", "m", "ECI position x at the phase's start (read when "
     "phase_elapsed > 0)", 0, 0},
    {"phase_start_r_eci_y", "m", "ECI position y at the phase's start", 0, 0},
    {"phase_start_r_eci_z", "m", "ECI position z at the phase's start", 0, 0},
    {"phase_start_v_eci_x", "m/s", "ECI velocity x at the phase's start", 0, 0},
    {"phase_start_v_eci_y", "m/s", "ECI velocity y at the phase's start", 0, 0},
    {"phase_start_v_eci_z", "m/s", "ECI velocity z at the phase's start", 0, 0},
};

static const lv_var output_vars[O_N] = {
    {"h", "m", "Geodetic altitude", 0, 0},
    {"lat", "rad", "Geodetic latitude", 0, 0},
    {"lon", "rad", "Longitude (eq. 1)", 0, 0},
    {"lat_gc", "rad", "Geocentric latitude (eq. 1)", 0, 0},
    {"radius", "m", "Distance from the planet's centre (eq. 1)", 0, 0},
    {"v_north", "m/s", "Velocity relative to the planet, north (NED; eq. 1)", 0, 0},
    {"v_east", "m/s", "Velocity relative to the planet, east (NED; eq. 1)", 0, 0},
    {"v_down", "m/s", "Velocity relative to the planet, down (NED; eq. 1)", 0, 0},
    {"v_rel", "m/s", "Speed relative to the rotating planet", 0, 0},
    {"v_inertial", "m/s", "Inertial speed", 0, 0},
    {"fpa", "rad", "Flight-path angle of the relative velocity, up positive", 0, 0},
    {"heading", "rad", "Heading of the relative velocity, from north to east", 0, 0},
    {"fpa_inertial", "rad", "Flight-path angle of the inertial velocity", 0, 0},
    {"heading_inertial", "rad", "Heading of the inertial velocity", 0, 0},
    {"mach", "1", "Mach number of the air-relative velocity", 0, 0},
    {"q_dyn", "Pa", "Dynamic pressure rho V_air^2 / 2", 0, 0},
    {"rho", "kg/m3", "Air density", 0, 0},
    {"p_amb", "Pa", "Ambient pressure", 0, 0},
    {"n_axial", "1", "Axial load factor: specific force along body x / g0", 0, 0},
    {"n_normal", "1", "Normal load factor: specific force along body -z / g0", 0, 0},
    {"n_lateral", "1", "Lateral load factor: specific force along body y / g0", 0, 0},
    {"accel", "m/s2", "Magnitude of the inertial acceleration (gravity included)", 0, 0},
    {"accel_sensed", "m/s2", "Magnitude of the specific force (thrust + aero) / m", 0, 0},
    {"thrust", "N", "Net thrust of all engines", 0, 0},
    {"drag", "N", "Drag: aerodynamic force opposite the air-relative velocity", 0, 0},
    {"lift", "N", "Lift: aerodynamic force along wind -z", 0, 0},
    {"side_force", "N", "Aerodynamic force along wind +y", 0, 0},
    {"mdot", "kg/s", "Propellant mass flow of all engines (-dm/dt)", 0, 0},
    {"engine_on", "1", "1 while the engines burn", 0, 0},
    {"alpha_in", "rad", "Angle of attack in effect (input, table, or the attitude's)", 0, 0},
    {"beta_in", "rad", "Sideslip angle in effect", 0, 0},
    {"mu_in", "rad", "Bank angle in effect (about the air-relative velocity)", 0, 0},
    {"throttle_in", "1", "Throttle in effect: commanded, or the throttle law's (before engine "
     "limits)", 0, 0},
    {"downrange", "m", "Great-circle distance from the phase's start point on the sphere of radius a", 0,
     0},
    {"sma", "m", "Osculating semi-major axis", 0, 0},
    {"ecc", "1", "Osculating eccentricity", 0, 0},
    {"inc", "rad", "Osculating inclination", 0, 0},
    {"raan", "rad", "Osculating right ascension of the ascending node (ECI)", 0, 0},
    {"argp", "rad", "Osculating argument of periapsis", 0, 0},
    {"apo_alt", "m", "Apoapsis radius minus the equatorial radius a", 0, 0},
    {"peri_alt", "m", "Periapsis radius minus the equatorial radius a", 0, 0},
    {"theta", "rad", "Pitch attitude of body x above the local horizon (3-2-1 Euler, NED)", 0, 0},
    {"psi", "rad", "Heading (yaw) attitude of body x, from north to east", 0, 0},
    {"phi", "rad", "Roll attitude about body x", 0, 0},
    {"propellant_left", "kg", "Propellant left in the burning stage", 0, 0},
    {"target_distance", "m", "Great-circle distance to the target (sphere of radius a; default "
     "target: the launch site)", 0, 0},
    {"target_bearing", "rad", "Bearing of the target, from north to east", 0, 0},
    {"target_overshoot", "m", "Vacuum ballistic range toward the target over flat ground minus "
     "its distance (> 0: beyond it)", 0, 0},
    {"throttle_eff", "1", "Throttle each running engine gives: throttle_in clamped into one "
     "engine's [throttle_min, throttle_max]; 0 with the engines off", 0, 0},
    {"engines_running", "1", "Engines burning (a phase's `engines:` less its engine-outs; 0 off)",
     0, 0},
    LV_FLIGHT_SAFETY_OUTPUTS
    LV_FLIGHT_WIND_OUTPUTS
};

/* The commanded throttle's saturation: two state events after the flight model's (burnout,
 * the named ends), lv_flight_sat_events (flight_model.h), watched where the throttle varies. */
enum { SAT_MIN = LV_FLIGHT_SAT_MIN, SAT_MAX = LV_FLIGHT_SAT_MAX, SAT_N = LV_FLIGHT_SAT_N };

static const char *const input_names[U_N] = {"alpha", "beta", "mu", "throttle"};


/* ---- model data -------------------------------------------------------------------- */


typedef struct dof3_inst {
    lv_flight_rt rt;      /* burnout book, start point, steering state, messages (first) */
    lv_dof3 *m;           /* NULL in a block lv_simulate zeroed itself */
    lv_table_cursor in_cur;
    lv_flight_trig_cache trig; /* cosines and sines of alpha, beta, mu */
} dof3_inst;

struct lv_dof3 {
    lv_model_def def;
    char name[64];
    lv_var states[LV_X3_N];
    lv_var params[P_N];
    unsigned char param_inactive[P_N]; /* lv_model_def.param_inactive: inputs given otherwise */
    lv_flight_ends fe;           /* burnout (event 0) and the named ends (flight_ends.h) */
    lv_flight_core core;         /* what the shared callbacks read (flight_model.h) */

    lv_flight_world world;       /* planet, gravity, atmosphere, wind */
    lv_domain_def domain[3];     /* the altitude floor and the steering law's guards */
    double *grav_ws;
    double gm;                   /* m^3/s^2, of the gravity model (osculating elements) */

    size_t n_eng;
    lv_engine *eng;
    double *eng_buf;             /* scratch for engine tables */
    int has_aero;
    lv_aero aero;
    lv_flight_schedule inputs;   /* control history (table NULL: constants only) */
    int const_throttle;          /* the parameter "throttle" drives the engines (no table, on) */
    int steers;                  /* a steering law other than the inputs (lv_guidance.h) */
    lv_guid guid;
    int throttles;               /* a throttle law with an effect (limits, landing) */
    int sat_watch;               /* the commanded throttle varies (a law, a table): sat_events */
    lv_thr thr;
    double c_min, c_max;         /* the throttle range every engine accepts */
    double p_ae;                 /* m^2: the engines' exit areas */
    double nose_radius, k_sg;    /* m, kg^0.5/m: the heat flux output's (lv_dof3_config) */
    int stop_at_burnout;
    lv_event_def *events;        /* [1 + fe.n + SAT_N]: the flight model's, then sat_events */

    dof3_inst inst;
};

/* Everything the right-hand side and the outputs derive from (t, x, p): the pieces of
 * flight.h, in the order they are computed. */
typedef struct dof3_point {
    lv_flight_kin kin;           /* 1. kinematics */
    lv_flight_air air;           /* 2. flight condition */
    lv_flight_controls ctl;      /* 3. controls */
    lv_flight_axes ax;           /* 4. wind and body axes, */
    double thrust, mdot;         /*    engines: N, kg/s */
    double coef[3];              /*    aerodynamic coefficients */
    lv_vec3 f_aero, f_sum;       /*    N, ECEF */
    lv_vec3 g_ecef;              /* 5. gravity, m/s^2, ECEF */
    lv_vec3 a_eci;               /*    acceleration, m/s^2 */
} dof3_point;

static const double *r_of(const double *x) { return x + LV_X3_RX; }
static const double *v_of(const double *x) { return x + LV_X3_VX; }

/* ---- the point model ----------------------------------------------------------------- */

/* The acceleration a law commands (guidance.h, lv_guid_accel_cmd): f(alpha) = dir . a(alpha)
 * - accel, with a = (T x_b + F_aero) / m + g + a_frame, the thrust's magnitude and the
 * bank fixed (they do not depend on alpha). */
typedef struct alpha_solve {
    lv_dof3 *m;
    dof3_point *pt;
    const double *p;
    lv_err *err;
    double thrust, inv_m, base; /* N, 1/kg, dir . (g + a_frame) - accel */
    lv_vec3 dir;
} alpha_solve;

static int accel_residual(double alpha, double *f, void *user)
{
    alpha_solve *as = user;
    dof3_point *pt = as->pt;
    pt->ctl.u[LV_CTRL_ALPHA] = alpha;
    pt->ctl.cs[LV_CTRL_ALPHA][0] = cos(alpha);
    pt->ctl.cs[LV_CTRL_ALPHA][1] = sin(alpha);
    lv_flight_axes_eval(&pt->kin, &pt->air, &pt->ctl, as->p[P_FPA], as->p[P_CHI], &pt->ax);
    if (lv_flight_aero(as->m->has_aero ? &as->m->aero : NULL, &pt->kin, &pt->air, &pt->ctl,
                       &pt->ax, pt->coef, &pt->f_aero, as->err) != 0)
        return -1;
    const lv_vec3 f_sum = lv_v3_add(lv_v3_scale(pt->ax.xb, as->thrust), pt->f_aero);
    *f = as->inv_m * lv_v3_dot(f_sum, as->dir) + as->base;
    return 0;
}

/* The angle of attack of a law that commands an acceleration (g->commands_accel): the root of
 * accel_residual in [alpha_lo, alpha_hi] by Brent's method (core/root.h) to 1e-13 rad, or the
 * end of the range whose residual is the smaller in magnitude when the range holds none (the
 * flare asks for more lift than alpha_hi gives: saturated). Leaves pt's controls, axes and
 * aerodynamic force at that alpha. Returns 0, or 1 when a table fails (err). */
static int solve_alpha(lv_dof3 *m, dof3_inst *s, double t, double mass, const double *p,
                       dof3_point *pt, lv_err *err)
{
    lv_guid_accel_cmd cmd;
    lv_guid_accel_command(&m->guid, &s->rt.guid, t, &pt->kin, &cmd);
    alpha_solve as = {m, pt, p, err, 0.0, 1.0 / mass, 0.0, cmd.dir};
    double mdot;
    if (lv_flight_thrust(m->eng, m->n_eng, s->rt.engines_on, t, &pt->ctl, &pt->air, m->eng_buf,
                         &as.thrust, &mdot, err) != 0)
        return 1;
    const lv_vec3 g_app = lv_v3_add(lv_flight_gravity(&m->world, m->grav_ws, &pt->kin),
                                    lv_flight_frame_accel(&m->world, &pt->kin));
    as.base = lv_v3_dot(g_app, cmd.dir) - cmd.accel;
    double f_lo, f_hi, alpha;
    if (accel_residual(cmd.alpha_lo, &f_lo, &as) != 0 ||
        accel_residual(cmd.alpha_hi, &f_hi, &as) != 0)
        return 1;
    const int rc = lv_root_brent(accel_residual, &as, cmd.alpha_lo, cmd.alpha_hi, f_lo, f_hi,
                                 1e-13, 60, &alpha);
    if (rc < 0)
        return 1;
    if (rc == 1) /* no root in the range: the nearer end */
        alpha = fabs(f_lo) < fabs(f_hi) ? cmd.alpha_lo : cmd.alpha_hi;
    if (pt->ctl.u[LV_CTRL_ALPHA] != alpha) { /* the last evaluation was elsewhere */
        double f;
        if (accel_residual(alpha, &f, &as) != 0)
            return 1;
    }
    return 0;
}

/* The value the inputs table is evaluated at (lv_dof3_config.inputs_over): mission time, the
 * normalised phase time tau = (t - t0) / D, or a variable of the state (geodetic altitude,
 * speed relative to the planet, mass, specific energy v_rel^2 / 2 + g0 h). */
static double schedule_x(const lv_flight_schedule *sch, double t, const double *x,
                         const double *p, const lv_flight_kin *k)
{
    switch (sch->over) {
    case LV_DOF3_OVER_TAU: {
        const double d = isnan(sch->duration) ? sch->stop_time - p[P_T0] : sch->duration;
        return (t - p[P_T0]) / d;
    }
    case LV_DOF3_OVER_ALTITUDE: return k->h;
    case LV_DOF3_OVER_SPEED: return lv_v3_norm(k->v_rel);
    case LV_DOF3_OVER_MASS: return x[LV_X3_M];
    case LV_DOF3_OVER_ENERGY: {
        const double v = lv_v3_norm(k->v_rel);
        return 0.5 * v * v + LV_G0 * k->h;
    }
    default: return t;
    }
}

/* Steps 3 to 5 with a steering law and a throttle law (guidance.h): the law's attitude and
 * the aerodynamic angles that result; the aerodynamic force (with the heading law's
 * load-factor limit); gravity; the throttle law from the forces without thrust; thrust. */
static int point_eval_guided(lv_dof3 *m, dof3_inst *s, double t, const double *x,
                             const double *p, int full, dof3_point *pt, lv_err *err)
{
    const lv_flight_world *w = &m->world;
    const double mass = x[LV_X3_M];
    lv_aero *aero = m->has_aero ? &m->aero : NULL;
    if (m->steers) {
        if (lv_guid_attitude(&m->guid, &s->rt.guid, t, &pt->kin, &pt->air, p[P_THR], p[P_FPA],
                             p[P_CHI], full, &pt->ctl, &pt->ax, err) != 0)
            return 1;
    } else {
        if (lv_flight_controls_eval(p + P_ALPHA, &m->inputs, &s->in_cur, &s->trig,
                                    schedule_x(&m->inputs, t, x, p, &pt->kin), &pt->ctl,
                                    err) != 0)
            return 1;
        lv_flight_axes_eval(&pt->kin, &pt->air, &pt->ctl, p[P_FPA], p[P_CHI], &pt->ax);
    }
    if (m->guid.commands_accel) {
        if (solve_alpha(m, s, t, mass, p, pt, err) != 0)
            return 1;
    } else if (lv_flight_aero(aero, &pt->kin, &pt->air, &pt->ctl, &pt->ax, pt->coef,
                              &pt->f_aero, err) != 0)
        return 1;
    if (m->guid.limits_alpha) {
        const double alpha = pt->ctl.u[LV_CTRL_ALPHA];
        const double lim = lv_guid_alpha_limited(&m->guid, alpha,
                                                 -lv_v3_dot(pt->f_aero, pt->ax.zw), mass,
                                                 pt->air.q);
        if (lim != alpha) { /* the lift at the limited angle of attack */
            pt->ctl.u[LV_CTRL_ALPHA] = lim;
            pt->ctl.cs[LV_CTRL_ALPHA][0] = cos(lim);
            pt->ctl.cs[LV_CTRL_ALPHA][1] = sin(lim);
            lv_flight_axes_eval(&pt->kin, &pt->air, &pt->ctl, p[P_FPA], p[P_CHI], &pt->ax);
            if (lv_flight_aero(aero, &pt->kin, &pt->air, &pt->ctl, &pt->ax, pt->coef,
                               &pt->f_aero, err) != 0)
                return 1;
        }
    }
    pt->g_ecef = lv_flight_gravity(w, m->grav_ws, &pt->kin);
    if (m->throttles && s->rt.engines_on) {
        double t_full, md_full;
        lv_flight_controls at_full = pt->ctl;
        at_full.u[LV_CTRL_THROTTLE] = 1.0;
        if (lv_flight_thrust(m->eng, m->n_eng, 1, t, &at_full, &pt->air, m->eng_buf, &t_full,
                             &md_full, err) != 0)
            return 1;
        const lv_vec3 a_nt = lv_v3_add(lv_v3_add(pt->g_ecef, lv_v3_scale(pt->f_aero, 1.0 / mass)),
                                       lv_flight_frame_accel(w, &pt->kin));
        const lv_thr_in in = {
            .mass = mass,
            .t_full = t_full,
            .p_ae = pt->air.p_amb * m->p_ae,
            .c_min = m->c_min,
            .c_max = m->c_max,
            .xb = pt->ax.xb,
            .f_aero = pt->f_aero,
            .a_nothrust = a_nt,
            .up = lv_v3_scale(pt->kin.d_ax, -1.0),
            .h = pt->kin.h,
            .v_down = lv_v3_dot(pt->kin.v_rel, pt->kin.d_ax),
            .h_dot = -lv_v3_dot(pt->kin.v_rel, pt->kin.d_ax),
            .drho_dh = m->thr.reads_drho ? lv_flight_drho_dh(w, pt->kin.h, pt->air.rho) : 0.0,
        };
        pt->ctl.u[LV_CTRL_THROTTLE] =
            lv_guid_throttle(&m->thr, pt->ctl.u[LV_CTRL_THROTTLE], &in, &pt->air);
    }
    if (lv_flight_thrust(m->eng, m->n_eng, s->rt.engines_on, t, &pt->ctl, &pt->air, m->eng_buf,
                         &pt->thrust, &pt->mdot, err) != 0)
        return 1;
    pt->f_sum = lv_v3_add(lv_v3_scale(pt->ax.xb, pt->thrust), pt->f_aero);
    pt->a_eci = lv_flight_accel_eci_g(&pt->kin, pt->g_ecef, pt->f_sum, mass);
    return 0;
}

/* Fills *pt from (t, x, p): kinematics, flight condition, controls, forces, equations of
 * motion. `full` (outputs): the exact geodetic conversion. Returns 0, > 0 (state not
 * acceptable) or < 0 (stop); err (may be NULL, as in the hot path) receives the reason. */
static int point_eval(lv_dof3 *m, dof3_inst *s, double t, const double *x, const double *p,
                      int full, dof3_point *pt, lv_err *err)
{
    const double mass = x[LV_X3_M];
    if (!(mass > 0.0)) {
        if (err)
            lv_fail(err, LV_ERR_INPUT, "mass %g kg is not positive at t = %.9g s", mass, t);
        return 1;
    }
    const lv_flight_world *w = &m->world;
    lv_flight_kinematics(w, t, r_of(x), v_of(x), full, &pt->kin);
    int rc = lv_flight_air_eval(w, t, &pt->kin, &pt->air, err);
    if (rc != 0)
        return rc;
    if (m->steers || m->throttles)
        return point_eval_guided(m, s, t, x, p, full, pt, err);
    if (lv_flight_controls_eval(p + P_ALPHA, &m->inputs, &s->in_cur, &s->trig,
                                schedule_x(&m->inputs, t, x, p, &pt->kin), &pt->ctl, err) != 0)
        return 1;
    lv_flight_axes_eval(&pt->kin, &pt->air, &pt->ctl, p[P_FPA], p[P_CHI], &pt->ax);
    if (lv_flight_thrust(m->eng, m->n_eng, s->rt.engines_on, t, &pt->ctl, &pt->air, m->eng_buf,
                         &pt->thrust, &pt->mdot, err) != 0 ||
        lv_flight_aero(m->has_aero ? &m->aero : NULL, &pt->kin, &pt->air, &pt->ctl, &pt->ax,
                       pt->coef, &pt->f_aero, err) != 0)
        return 1;
    pt->f_sum = lv_v3_add(lv_v3_scale(pt->ax.xb, pt->thrust), pt->f_aero);
    pt->a_eci = lv_flight_accel_eci(w, m->grav_ws, &pt->kin, pt->f_sum, mass, &pt->g_ecef);
    return 0;
}

/* ---- callbacks ------------------------------------------------------------------------ */

static void note(dof3_inst *s, const lv_err *e)
{
    snprintf(s->rt.msg, sizeof s->rt.msg, "%s", e->msg);
}

static int dof3_rhs(double t, const double *x, const double *p, double *xdot, void *inst)
{
    dof3_inst *s = inst;
    dof3_point pt;
    int rc = point_eval(s->m, s, t, x, p, 0, &pt, NULL);
    if (rc != 0) { /* failure path only: evaluate again to keep the reason */
        lv_err e = {LV_OK, ""};
        point_eval(s->m, s, t, x, p, 0, &pt, &e);
        note(s, &e);
        return rc;
    }
    lv_flight_note_forces(&s->rt, pt.thrust, pt.f_sum, pt.ax.xw, x[LV_X3_M]);
    xdot[LV_X3_RX] = x[LV_X3_VX];
    xdot[LV_X3_RY] = x[LV_X3_VY];
    xdot[LV_X3_RZ] = x[LV_X3_VZ];
    xdot[LV_X3_VX] = pt.a_eci.x;
    xdot[LV_X3_VY] = pt.a_eci.y;
    xdot[LV_X3_VZ] = pt.a_eci.z;
    xdot[LV_X3_M] = -pt.mdot; /* the paper's dm = mdot, mdot < 0 while burning */
    xdot[LV_X3_QSG] = lv_flight_heat_flux_sg(s->m->k_sg, pt.air.rho, s->m->nose_radius,
                                             pt.air.v_air_n);
    xdot[LV_X3_QFM] = lv_flight_heat_flux_fm(pt.air.rho, pt.air.v_air_n);
    return 0;
}

/* Checks the parameters a run can change by name. */
static int check_params(dof3_inst *s, const double *p)
{
    if (lv_flight_check_start(&s->rt, p[P_LAT], p[P_VEL], p[P_PROP]) != 0)
        return -1;
    if (!(p[P_PH_EL] >= 0.0) || !isfinite(p[P_PH_EL]))
        return lv_flight_fail(&s->rt, "phase_elapsed = %g s: the time since the phase's start "
                              "must be finite and >= 0", p[P_PH_EL]);
    return s->m->const_throttle ? lv_flight_check_throttle(&s->rt, p[P_THR]) : 0;
}

/* The flight model's events, then the commanded throttle's saturation (sat_events):
 * constants (never crossed) for a constant throttle, with the engines off or none running. */
static int dof3_event_g(double t, const double *x, const double *p, double *g, void *inst)
{
    dof3_inst *s = inst;
    lv_dof3 *m = s->m;
    const int rc = lv_flight_event_g(t, x, p, g, inst);
    double *gs = g + 1 + m->fe.n;
    if (!lv_flight_sat_begin(rc, m->sat_watch, &s->rt, m->eng, m->n_eng, gs))
        return rc;
    dof3_point pt;
    if (point_eval(m, s, t, x, p, 0, &pt, NULL) != 0)
        return 0; /* the right-hand side reports its own failure */
    const double c = pt.ctl.u[U_THR];
    lv_flight_sat_g(c, m->c_min, m->c_max, gs);
    return 0;
}

/* Position and velocity from the geodetic start values (the paper's userPar). */
static int dof3_start(const double *p, double *x, void *inst)
{
    dof3_inst *s = inst;
    if (s == NULL || s->m == NULL)
        return -1; /* not an lv_dof3 instance */
    s->rt.msg[0] = '\0';
    if (check_params(s, p) != 0)
        return -1;
    lv_flight_start_state(&s->m->world.planet, p[P_LAT], p[P_LON], p[P_H], p[P_VEL], p[P_FPA],
                          p[P_CHI], p[P_T0], x + LV_X3_RX, x + LV_X3_VX);
    return 0; /* the mass keeps the start value of state "m" */
}

/* The start parameters of the state the run started from (lv_model_def.start_params). */
static int dof3_start_params(double t0, const double *x, double *p, void *inst)
{
    const dof3_inst *s = inst;
    if (s == NULL || s->m == NULL)
        return -1;
    lv_flight_start_geodetic(&s->m->world, t0, x + LV_X3_RX, x + LV_X3_VX, p + P_LAT);
    p[P_T0] = t0;
    return 0;
}

static int dof3_init(double t0, const double *x, const double *p, void *inst)
{
    dof3_inst *s = inst;
    if (s == NULL || s->m == NULL)
        return -1;
    s->rt.msg[0] = '\0';
    if (check_params(s, p) != 0)
        return -1;
    for (int k = 0; k < 3; k++)
        s->trig.ang[k] = NAN;
    /* the propellant book: burnout when the burning stage's propellant is gone, whatever else
     * the start mass carries (a payload set by the user is not burnt) */
    if (lv_flight_book(&s->rt, x[LV_X3_M], p[P_PROP], s->m->n_eng > 0 && !s->m->thr.engines_off))
        return -1;
    lv_flight_kin kin;
    if (lv_flight_start(&s->rt, t0, x, &kin) != 0)
        return -1;
    double tg = t0;
    if (p[P_PH_EL] > 0.0) { /* a piece of the phase: the phase's start (param_tpl) */
        tg = t0 - p[P_PH_EL];
        if (lv_flight_origin(&s->rt, tg, p + P_PH_RX, p + P_PH_VX, "phase_start_r_eci",
                             &kin) != 0)
            return -1;
    }
    if (lv_guid_start(&s->m->guid, &s->rt.guid, tg, &kin, s->rt.msg, sizeof s->rt.msg) != 0)
        return -1;
    return 0;
}

/* Flight-path angle and heading of an ECEF vector in the local NED frame. */
static void fpa_chi(const lv_flight_kin *k, lv_vec3 v, double *gamma, double *chi)
{
    const double ned[3] = {lv_v3_dot(v, k->n_ax), lv_v3_dot(v, k->e_ax), lv_v3_dot(v, k->d_ax)};
    lv_frames_fpa_from_ned(ned, NULL, gamma, chi);
}

/* The outputs; need (NULL: all) as lv_model_def.outputs_some: the IIP only when asked for. */
static int dof3_outputs_some(double t, const double *x, const double *p, double *y,
                             const unsigned char *need, void *inst)
{
    dof3_inst *s = inst;
    lv_dof3 *m = s->m;
    dof3_point pt;
    lv_err e = {LV_OK, ""};
    int rc = point_eval(m, s, t, x, p, 1, &pt, &e);
    if (rc != 0) {
        note(s, &e);
        return rc;
    }
    const lv_flight_kin *k = &pt.kin;
    const lv_flight_air *air = &pt.air;
    const lv_flight_axes *ax = &pt.ax;
    const double mass = x[LV_X3_M];
    const lv_vec3 v_eci = {x[LV_X3_VX], x[LV_X3_VY], x[LV_X3_VZ]};
    const lv_vec3 r_eci = {x[LV_X3_RX], x[LV_X3_RY], x[LV_X3_RZ]};
    /* inertial velocity in ECEF axes (no w x r): for the inertial angles */
    const lv_vec3 v_i_ecef = {k->c_th * v_eci.x + k->s_th * v_eci.y,
                              -k->s_th * v_eci.x + k->c_th * v_eci.y, v_eci.z};
    const lv_vec3 f_spec = lv_v3_scale(pt.f_sum, 1.0 / mass);

    y[O_H] = k->h;
    y[O_LAT] = k->lat;
    y[O_LON] = k->lon;
    const double r[3] = {k->r_ecef.x, k->r_ecef.y, k->r_ecef.z};
    lv_frames_ecef_to_geocentric(r, &y[O_LAT_GC], NULL, &y[O_RADIUS]);
    y[O_VN] = lv_v3_dot(k->v_rel, k->n_ax);
    y[O_VE] = lv_v3_dot(k->v_rel, k->e_ax);
    y[O_VD] = lv_v3_dot(k->v_rel, k->d_ax);
    y[O_VREL] = lv_v3_norm(k->v_rel);
    y[O_VINR] = lv_v3_norm(v_eci);
    fpa_chi(k, k->v_rel, &y[O_FPA], &y[O_CHI]);
    fpa_chi(k, v_i_ecef, &y[O_FPA_I], &y[O_CHI_I]);
    y[O_MACH] = air->mach;
    y[O_Q] = air->q;
    y[O_RHO] = air->rho;
    y[O_PAMB] = air->p_amb;
    y[O_NAX] = lv_v3_dot(f_spec, ax->xb) / LV_G0;
    y[O_NNORM] = -lv_v3_dot(f_spec, ax->zb) / LV_G0;
    y[O_NLAT] = lv_v3_dot(f_spec, ax->yb) / LV_G0;
    y[O_ACC] = lv_v3_norm(pt.a_eci);
    y[O_ACC_SENSED] = lv_v3_norm(f_spec);
    y[O_THRUST] = pt.thrust;
    y[O_DRAG] = -lv_v3_dot(pt.f_aero, ax->xw);
    y[O_LIFT] = -lv_v3_dot(pt.f_aero, ax->zw);
    y[O_SIDE] = lv_v3_dot(pt.f_aero, ax->yw);
    y[O_MDOT] = pt.mdot;
    y[O_ENGINE_ON] = s->rt.engines_on;
    size_t running = 0;
    for (size_t i = 0; s->rt.engines_on && i < m->n_eng; i++)
        running += !m->eng[i].out;
    y[O_ENG_RUN] = (double)running;
    y[O_HEAT_SG] = lv_flight_heat_flux_sg(m->k_sg, air->rho, m->nose_radius, air->v_air_n);
    y[O_HEAT_FM] = lv_flight_heat_flux_fm(air->rho, air->v_air_n);
    for (int c = 0; c < 3; c++)
        y[O_WIND_N + c] = air->w_ned[c];
    y[O_THR_EFF] = 0.0;
    for (size_t i = 0; i < m->n_eng && running > 0; i++)
        if (!m->eng[i].out) { /* identical limits: dof3 refuses ranges that do not overlap */
            y[O_THR_EFF] = lv_engine_throttle(&m->eng[i], pt.ctl.u[U_THR]);
            break;
        }
    for (int i = 0; i < U_N; i++)
        y[O_ALPHA + i] = pt.ctl.u[i];
    if (!s->rt.engines_on) /* engines off (burnt out, a coast): no throttle */
        y[O_THR] = 0.0;
    const lv_vec3 u0 = {s->rt.r0_unit[0], s->rt.r0_unit[1], s->rt.r0_unit[2]};
    const double rn = lv_v3_norm(k->r_ecef);
    const lv_vec3 u1 = lv_v3_scale(k->r_ecef, 1.0 / rn);
    y[O_DOWNRANGE] =
        m->world.planet.a * atan2(lv_v3_norm(lv_v3_cross(u0, u1)), lv_v3_dot(u0, u1));

    lv_orbit_elem el;
    const double rv[3] = {r_eci.x, r_eci.y, r_eci.z}, vv[3] = {v_eci.x, v_eci.y, v_eci.z};
    lv_orbit_elements(m->gm, rv, vv, &el);
    y[O_SMA] = el.a;
    y[O_ECC] = el.e;
    y[O_INC] = el.i;
    y[O_RAAN] = el.raan;
    y[O_ARGP] = el.argp;
    y[O_APO] = el.r_apo - m->world.planet.a;
    y[O_PERI] = el.r_peri - m->world.planet.a;
    lv_flight_iip_if(need, O_IIP_LAT, &m->world, m->grav_ws, m->gm, t, rv, vv, r, &y[O_IIP_LAT]);
    lv_guid_euler_local(k, ax, &y[O_THETA], &y[O_PSI], &y[O_PHI]);
    y[O_PROP_LEFT] = s->rt.burned_out || mass < s->rt.m_burnout ? 0.0 : mass - s->rt.m_burnout;
    lv_guid_target(&m->guid, k, m->world.planet.a, lv_v3_dot(pt.g_ecef, k->d_ax),
                   &y[O_TGT_DIST], &y[O_TGT_BEAR], &y[O_TGT_OVER]);
    return 0;
}

static int dof3_outputs(double t, const double *x, const double *p, double *y, void *inst)
{
    return dof3_outputs_some(t, x, p, y, NULL, inst);
}

/* ---- construction ---------------------------------------------------------------------- */

void lv_dof3_config_default(lv_dof3_config *cfg)
{
    memset(cfg, 0, sizeof *cfg);
    cfg->planet = lv_planet_earth();
    cfg->m0 = 1000.0;
    cfg->throttle = 1.0;
    cfg->nose_radius = 1.0;
    cfg->k_sutton_graves = LV_SUTTON_GRAVES_EARTH;
    cfg->inputs_duration = NAN;
    cfg->inputs_stop_time = NAN;
    lv_steering_init(&cfg->steering, "inputs", NULL); /* target: the start point */
    lv_throttle_init(&cfg->throttle_law, "nominal", NULL);
}

/* The steering and throttle laws (lv_guidance.h) for engines m->eng. */
static lv_status setup_guidance(lv_dof3 *m, const lv_dof3_config *cfg, lv_err *err)
{
    lv_steering st = cfg->steering;
    if (isnan(st.target_lat) || isnan(st.target_lon)) {
        st.target_lat = cfg->start_lat;
        st.target_lon = cfg->start_lon;
    }
    lv_status rc = lv_guid_init(&m->guid, &st, &cfg->planet, cfg->aero != NULL, err);
    if (rc != LV_OK)
        return lv_fail_prefix(err, rc, "dof3");
    m->steers = lv_guid_steers(&m->guid);
    /* the angles of attack and sideslip an attitude gives are computed in the right-hand side
     * only when an aerodynamic table reads them */
    m->guid.need_alpha = m->guid.need_beta = 0;
    for (size_t i = 0; m->has_aero && i < m->aero.n_tab; i++)
        for (size_t d = 0; d < m->aero.tab[i].n_dims; d++) {
            m->guid.need_alpha |= m->aero.tab[i].input[d] == LV_AERO_IN_ALPHA;
            m->guid.need_beta |= m->aero.tab[i].input[d] == LV_AERO_IN_BETA;
        }
    if ((rc = lv_thr_init(&m->thr, &cfg->throttle_law, err)) != LV_OK)
        return lv_fail_prefix(err, rc, "dof3");
    m->throttles = m->thr.active;
    if (m->guid.commands_accel && m->throttles)
        return lv_fail(err, LV_ERR_INPUT, "dof3: guidance '%s' solves the angle of attack from "
                       "the forces at the phase's throttle, and the throttle law '%s' (a throttle "
                       "with limits such as g_limit or q_max) would change the throttle from "
                       "those forces: give a constant throttle {value: c} without limits or "
                       "`throttle: off`", m->guid.law->name, m->thr.law->name);
    m->c_min = 0.0;
    m->c_max = HUGE_VAL;
    for (size_t i = 0; i < m->n_eng; i++) {
        if (m->eng[i].thr_min > m->c_min)
            m->c_min = m->eng[i].thr_min;
        if (m->eng[i].thr_max < m->c_max)
            m->c_max = m->eng[i].thr_max;
        m->p_ae += m->eng[i].exit_area;
    }
    if (m->n_eng == 0)
        m->c_max = 1.0;
    if (m->throttles && m->c_min > m->c_max)
        return lv_fail(err, LV_ERR_INPUT, "dof3: the engines' throttle ranges have nothing in "
                       "common (largest minimum %g, smallest maximum %g): a throttle law sets one "
                       "throttle for all", m->c_min, m->c_max);
    return LV_OK;
}

static lv_status check_finite(const char *what, double v, const char *unit, lv_err *err)
{
    if (!isfinite(v))
        return lv_fail(err, LV_ERR_INPUT, "dof3: %s = %g %s (must be finite)", what, v, unit);
    return LV_OK;
}

static lv_status setup_inputs(lv_dof3 *m, const lv_dof3_config *cfg, lv_err *err)
{
    const lv_table *tab = cfg->inputs;
    for (int k = 0; k < U_N; k++)
        m->inputs.k[k] = -1;
    m->inputs.over = LV_DOF3_OVER_TIME;
    if (tab == NULL)
        return LV_OK;
    int any = 0;
    lv_status st;
    static const char *const over_axis[] = {"time", "tau", "altitude", "speed", "mass",
                                            "energy"};
    static const char *const over_unit[] = {"s", "1", "m", "m/s", "kg", "J/kg"};
    const int over = cfg->inputs_over;
    if (over < LV_DOF3_OVER_TIME || over > LV_DOF3_OVER_ENERGY)
        return lv_fail(err, LV_ERR_INPUT, "dof3: inputs_over = %d is not an lv_dof3_over", over);
    if (over == LV_DOF3_OVER_TIME)
        st = lv_flight_check_inputs_table("dof3", tab, err);
    else if (lv_table_n_dims(tab) != 1 || strcmp(lv_table_axis_name(tab, 0), over_axis[over]) != 0)
        st = lv_fail(err, LV_ERR_INPUT, "dof3: input table '%s' must have exactly one axis "
                     "named '%s' (has %zu, the first named '%s')", lv_table_name(tab),
                     over_axis[over], lv_table_n_dims(tab), lv_table_axis_name(tab, 0));
    else
        st = lv_table_expect_unit(tab, 1, 0, over_unit[over], "dof3: inputs", err);
    if (st != LV_OK)
        return st;
    if (over == LV_DOF3_OVER_TAU && !(cfg->inputs_duration > 0.0) &&
        !(isnan(cfg->inputs_duration) && isfinite(cfg->inputs_stop_time)))
        return lv_fail(err, LV_ERR_INPUT, "dof3: inputs over tau: inputs_duration = %g s must "
                       "be > 0 (or NAN with a finite inputs_stop_time)", cfg->inputs_duration);
    m->inputs.over = over;
    m->inputs.duration = cfg->inputs_duration;
    m->inputs.stop_time = cfg->inputs_stop_time;
    for (int k = 0; k < U_N; k++) {
        size_t idx;
        if (lv_table_out_index(tab, input_names[k], &idx, NULL) == LV_OK) {
            if ((st = lv_table_expect_unit(tab, 0, idx, k < 3 ? "rad" : "1", "dof3: inputs",
                                           err)) != LV_OK)
                return st;
            m->inputs.k[k] = (int)idx;
            any = 1;
        }
    }
    if (!any)
        return lv_fail(err, LV_ERR_INPUT,
                       "dof3: input table '%s' has none of the outputs 'alpha', 'beta', 'mu', "
                       "'throttle' (its first output is '%s')",
                       lv_table_name(tab), lv_table_out_name(tab, 0));
    m->inputs.buf = malloc(lv_table_n_out(tab) * sizeof *m->inputs.buf);
    if (m->inputs.buf == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    m->inputs.table = tab;
    return LV_OK;
}

static lv_status setup_ends(lv_dof3 *m, const lv_dof3_config *cfg, lv_err *err)
{
    return lv_flight_ends_init(&m->fe, "dof3", cfg->ends, cfg->n_ends, err);
}

lv_status lv_dof3_create(const lv_dof3_config *cfg, lv_dof3 **out, lv_err *err)
{
    *out = NULL;
    lv_status st;
    lv_dof3 *m = calloc(1, sizeof *m);
    if (m == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    snprintf(m->name, sizeof m->name, "%s", cfg->name != NULL ? cfg->name : "dof3");

    /* masses and start values */
    if ((st = lv_flight_check_mass("dof3", cfg->m0, cfg->propellant, err)) != LV_OK ||
        (st = lv_flight_check_heating("dof3", cfg->nose_radius, cfg->k_sutton_graves, err)) !=
            LV_OK ||
        (st = check_finite("start_lon", cfg->start_lon, "rad", err)) != LV_OK ||
        (st = check_finite("start_h", cfg->start_h, "m", err)) != LV_OK ||
        (st = check_finite("start_fpa", cfg->start_fpa, "rad", err)) != LV_OK ||
        (st = check_finite("start_chi", cfg->start_chi, "rad", err)) != LV_OK ||
        (st = check_finite("start_time", cfg->start_time, "s", err)) != LV_OK ||
        (st = check_finite("alpha", cfg->alpha, "rad", err)) != LV_OK ||
        (st = check_finite("beta", cfg->beta, "rad", err)) != LV_OK ||
        (st = check_finite("mu", cfg->mu, "rad", err)) != LV_OK)
        goto fail;
    if (!(fabs(cfg->start_lat) <= 0.5 * LV_PI)) {
        st = lv_fail(err, LV_ERR_INPUT, "dof3: start_lat = %g rad (must be in [-pi/2, pi/2])",
                     cfg->start_lat);
        goto fail;
    }
    if (!isfinite(cfg->start_vel) || cfg->start_vel < 0.0) {
        st = lv_fail(err, LV_ERR_INPUT, "dof3: start_vel = %g m/s (must be >= 0)",
                     cfg->start_vel);
        goto fail;
    }
    m->nose_radius = cfg->nose_radius;
    m->k_sg = cfg->k_sutton_graves;

    /* environment */
    if ((st = lv_flight_world_setup(&m->world, "dof3", &cfg->planet, cfg->gravity, cfg->atmo,
                                    cfg->wind, cfg->wind_user, &m->grav_ws, &m->gm, err)) != LV_OK)
        goto fail;

    /* vehicle */
    if ((st = lv_flight_engines_init("dof3", cfg->engines, cfg->n_engines, &m->eng, &m->n_eng,
                                     &m->eng_buf, err)) != LV_OK)
        goto fail;
    if (cfg->aero != NULL) {
        if ((st = lv_aero_init(&m->aero, cfg->aero, err)) != LV_OK) {
            lv_fail_prefix(err, st, "dof3");
            goto fail;
        }
        m->has_aero = 1;
    }
    if ((st = setup_inputs(m, cfg, err)) != LV_OK)
        goto fail;
    /* one throttle drives every engine: their ranges must overlap */
    for (size_t i = 0; i < m->n_eng; i++)
        for (size_t j = 0; j < i; j++)
            if (m->eng[i].thr_min > m->eng[j].thr_max || m->eng[j].thr_min > m->eng[i].thr_max) {
                st = lv_fail(err, LV_ERR_INPUT, "dof3: the throttle ranges of engines '%s' [%g, "
                             "%g] and '%s' [%g, %g] do not overlap: one throttle c_s drives "
                             "every engine of the stage", m->eng[j].name, m->eng[j].thr_min,
                             m->eng[j].thr_max, m->eng[i].name, m->eng[i].thr_min,
                             m->eng[i].thr_max);
                goto fail;
            }
    /* a constant throttle (not a table's, not with the engines off) within the limits */
    m->const_throttle = m->inputs.k[U_THR] < 0 && !lv_thr_engines_off(&cfg->throttle_law) &&
                        !lv_guid_gives_throttle(&cfg->steering);
    if (m->const_throttle) {
        for (size_t i = 0; i < m->n_eng; i++) {
            if (!(cfg->throttle >= m->eng[i].thr_min && cfg->throttle <= m->eng[i].thr_max)) {
                st = lv_fail(err, LV_ERR_INPUT,
                             "dof3: throttle = %g is outside the limits [%g, %g] of engine '%s'",
                             cfg->throttle, m->eng[i].thr_min, m->eng[i].thr_max,
                             m->eng[i].name);
                goto fail;
            }
        }
    }
    if (!isfinite(cfg->throttle)) {
        st = lv_fail(err, LV_ERR_INPUT, "dof3: throttle = %g (must be finite)", cfg->throttle);
        goto fail;
    }
    m->stop_at_burnout = cfg->stop_at_burnout != 0;
    if ((st = setup_ends(m, cfg, err)) != LV_OK || (st = setup_guidance(m, cfg, err)) != LV_OK)
        goto fail;
    /* a throttle that varies: a law's, the inputs table's, the attitude table's */
    m->sat_watch = m->throttles || m->inputs.k[U_THR] >= 0 ||
                   (m->steers && lv_guid_gives_throttle(&cfg->steering));

    /* variables with this configuration's defaults */
    memcpy(m->states, state_tpl, sizeof m->states);
    m->states[LV_X3_M].start = cfg->m0;
    m->states[LV_X3_M].nominal = cfg->m0;
    memcpy(m->params, param_tpl, sizeof m->params);
    const double pv[P_N] = {cfg->start_lat, cfg->start_lon, cfg->start_h, cfg->start_vel,
                            cfg->start_fpa, cfg->start_chi, cfg->start_time, cfg->alpha,
                            cfg->beta,      cfg->mu,        cfg->throttle, cfg->propellant,
                            0.0,            0.0,            0.0,           0.0,
                            0.0,            0.0,            0.0};
    for (int i = 0; i < P_N; i++)
        m->params[i].start = pv[i];
    for (int i = P_PH_EL; i < P_N; i++) /* an optimiser's, not the run's: not recorded */
        m->param_inactive[i] = 1;
    /* the constant inputs that do not act, left out of the result files' parameter records:
     * an angle a steering law or the inputs table gives, a throttle that a table, a steering
     * law's table or an active throttle law gives, or that no engine burns with (the values in
     * effect are the outputs alpha_in .. throttle_in) */
    for (int k = 0; k < 3; k++)
        m->param_inactive[P_ALPHA + k] = m->steers || m->inputs.k[k] >= 0;
    m->param_inactive[P_THR] = !m->const_throttle || m->throttles || m->n_eng == 0;

    m->def = (lv_model_def){
        .name = m->name,
        .description = "3-DoF variable-mass point over a rotating planet, ECI states",
        .n_states = LV_X3_N,
        .n_params = P_N,
        .n_outputs = O_N,
        .states = m->states,
        .params = m->params,
        .outputs = output_vars,
        .inst_size = sizeof(dof3_inst),
        .start = dof3_start,
        .init = dof3_init,
        .rhs = dof3_rhs,
        .outputs_fn = dof3_outputs,
        .outputs_some = dof3_outputs_some,
        .abs_error = abs_error,
        .param_inactive = m->param_inactive,
        .start_params = dof3_start_params,
        .quadrature = quadrature,
    };
    m->core = (lv_flight_core){.world = &m->world, .fe = &m->fe, .i_r = LV_X3_RX,
                               .i_v = LV_X3_VX, .i_m = LV_X3_M,
                               /* only a time table's breakpoints are time events */
                               .inputs = m->inputs.over == LV_DOF3_OVER_TIME ? m->inputs.table
                                                                             : NULL,
                               .eng = m->eng, .n_eng = m->n_eng,
                               .guid = m->steers ? &m->guid : NULL,
                               .stop_at_burnout = m->stop_at_burnout};
    m->core.law = &m->guid;
    lv_flight_domain_init(m->domain, &m->core, cfg->atmo != NULL);
    lv_flight_def_callbacks(&m->def, &m->core, &m->inst.rt, m->domain);
    if ((m->events = lv_flight_add_sat_events(&m->def, &m->core)) == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto fail;
    }
    m->def.event_g = dof3_event_g;
    m->inst.m = m;
    for (int k = 0; k < 3; k++)
        m->inst.trig.ang[k] = NAN;
    if ((st = lv_model_validate(&m->def, err)) != LV_OK)
        goto fail;
    *out = m;
    return LV_OK;
fail:
    lv_dof3_free(m);
    return st;
}

void lv_dof3_free(lv_dof3 *m)
{
    if (m == NULL)
        return;
    lv_aero_clear(&m->aero);
    free(m->eng);
    free(m->eng_buf);
    free(m->inputs.buf);
    free(m->grav_ws);
    lv_flight_ends_clear(&m->fe);
    free(m->events);
    free(m);
}

const lv_model_def *lv_dof3_def(const lv_dof3 *m) { return &m->def; }

void *lv_dof3_inst(lv_dof3 *m) { return &m->inst; }

const char *lv_dof3_last_error(const lv_dof3 *m) { return m->inst.rt.msg; }
