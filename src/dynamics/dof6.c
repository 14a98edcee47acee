/* dof6.c - 6-DoF variable-mass rigid body over a rotating ellipsoidal planet: ECI position and
 * velocity of the centre of mass, attitude quaternion body -> ECI, body rates, mass. Built from
 * the pieces of flight.h (kinematics, air data, engines, aerodynamic coefficients, gravity).
 * Rigid-body equations: Stevens, Lewis & Johnson, Aircraft Control and Simulation, 3rd ed.,
 * sec. 1.7-1.8 (quaternion kinematics eq. 1.8-15, Euler's equations eq. 1.7-18); variable mass:
 * Thomson, Introduction to Space Dynamics (Dover, 1986), ch. 8; quaternion norm control:
 * Zipfel, Modeling and Simulation of Aerospace Vehicle Dynamics, 2nd ed., sec. 4.3; the
 * mass-variation moments (jet damping, inertia rate) as in F. O. Eke and T. C. Mao, "On the
 * dynamics of variable mass systems", Int. J. Mech. Eng. Educ. 30 (2002) 123-137, their
 * equation of attitude motion with a point nozzle exit and no internal flow.
 * Equations, the switchable terms and their defaults: docs/models.md, "6-DoF rigid body",
 * "Rigid-body terms". */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "core/table_unit.h"
#include "core/units.h"
#include "core/vec3.h"
#include "dynamics/flight.h"
#include "dynamics/flight_ends.h"
#include "dynamics/flight_model.h"
#include "dynamics/guidance.h"
#include "dynamics/orbit.h"
#include "lvsim/lv_dof6.h"
#include "vehicle/vehicle.h"

/* Gain of the quaternion norm correction K (1 - |q|^2) q [1/s] (Zipfel sec. 4.3): the unit
 * sphere attracts the quaternion at the rate 2 K, slower than any step an adaptive method
 * takes (K dt < 1 for dt < 1 s), so that it does not stiffen the equations. */
#define QUAT_NORM_GAIN 1.0
#define V_AIR_MIN 1e-6 /* m/s: below, alpha = beta = 0 (no aerodynamic force: q = 0) */

/* ---- variables ------------------------------------------------------------------- */

enum { P_LAT, P_LON, P_H, P_VEL, P_FPA, P_CHI, P_T0, P_PSI, P_THETA, P_PHI, P_RP, P_RQ, P_RR,
       P_GP, P_GY, P_THR, P_PROP, P_N };
enum { U_GP, U_GY, U_THR, U_N };

enum {
    O_H, O_LAT, O_LON, O_RADIUS, O_VN, O_VE, O_VD, O_VREL, O_VINR, O_FPA, O_CHI,
    O_MACH, O_Q, O_RHO, O_PAMB, O_THRUST, O_MDOT, O_ENGINE_ON, O_DRAG, O_LIFT, O_SIDE,
    O_NAX, O_NNORM, O_NLAT, O_THETA, O_PSI, O_PHI, O_ALPHA, O_BETA, O_BANK,
    O_LA, O_MA, O_NA, O_LT, O_MT, O_NT, O_CGX, O_CGY, O_CGZ, O_IXX, O_IYY, O_IZZ,
    O_QNORM, O_GP, O_GY, O_THR, O_PROP_LEFT, O_SMA, O_ECC, O_INC, O_APO, O_PERI,
    O_LAT_GC, O_FPA_I, O_CHI_I, O_ACC, O_ACC_SENSED, O_RAAN, O_ARGP, O_DOWNRANGE, O_THR_EFF,
    O_ENG_RUN,
    O_HEAT_SG, O_HEAT_FM, /* aerothermal heating */
    O_IIP_LAT, O_IIP_LON, O_IIP_TOF, O_IIP_RANGE, /* instantaneous impact point */
    O_WIND_N, O_WIND_E, O_WIND_D, /* the wind at the vehicle */
    O_N
};
/* outputs of a steering law (after O_N), then of a controller */
enum { O_THC = O_N, O_PSC, O_PHC, O_ER, O_EP, O_EY, O_GPC, O_GYC, O_NMAX };
/* controller states after the 16 of lv_x6: the actuators' gimbal angles, then (PID) the
 * integrals of the pitch and yaw errors */
enum { X_AP = LV_X6_N, X_AY, X_IP, X_IY, X_NMAX };

/* Error control as lv_dof3 (docs/integration.md) for position, velocity and mass; the
 * quaternion to tol (|q| ~ 1), the rates to tol (|w| + 0.01 rad/s). */
static const lv_var state_tpl[LV_X6_N] = {
    {"r_eci_x", "m", "Position of the centre of mass, ECI x", 0.0, 1e3},
    {"r_eci_y", "m", "Position of the centre of mass, ECI y", 0.0, 1e3},
    {"r_eci_z", "m", "Position of the centre of mass, ECI z", 0.0, 1e3},
    {"v_eci_x", "m/s", "Inertial velocity, ECI x", 0.0, 1.0},
    {"v_eci_y", "m/s", "Inertial velocity, ECI y", 0.0, 1.0},
    {"v_eci_z", "m/s", "Inertial velocity, ECI z", 0.0, 1.0},
    {"q_w", "1", "Attitude quaternion body -> ECI, scalar part", 1.0, 1.0},
    {"q_x", "1", "Attitude quaternion body -> ECI, x", 0.0, 1.0},
    {"q_y", "1", "Attitude quaternion body -> ECI, y", 0.0, 1.0},
    {"q_z", "1", "Attitude quaternion body -> ECI, z", 0.0, 1.0},
    {"p", "rad/s", "Roll rate: body rate relative to inertial space about body x", 0.0, 0.01},
    {"q", "rad/s", "Pitch rate: body rate relative to inertial space about body y", 0.0, 0.01},
    {"r", "rad/s", "Yaw rate: body rate relative to inertial space about body z", 0.0, 0.01},
    {"m", "kg", "Vehicle mass", 1000.0, 1e3},
    LV_FLIGHT_HEAT_LOAD_STATES
};

static const lv_var ctl_state_tpl[X_NMAX - LV_X6_N] = {
    {"act_pitch", "rad", "Pitch gimbal angle: the actuator's state (with a controller)", 0.0, 0.01},
    {"act_yaw", "rad", "Yaw gimbal angle: the actuator's state (with a controller)", 0.0, 0.01},
    {"int_pitch", "rad.s", "Integral of the pitch attitude error (with a PID controller)", 0.0, 0.01},
    {"int_yaw", "rad.s", "Integral of the yaw attitude error (with a PID controller)", 0.0, 0.01},
};

static const unsigned char abs_error[X_NMAX] = {1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
                                                0, 0, 0, 0, 0, 0};
/* The heat loads are quadratures: out of the error control (lv_model_def.quadrature). */
static const unsigned char quadrature[X_NMAX] = {
    [LV_X6_QSG] = 1, [LV_X6_QFM] = 1};

static const lv_var param_tpl[P_N] = {
    {"start_lat", "rad", "Initial geodetic latitude", 0, 0},
    {"start_lon", "rad", "Initial longitude", 0, 0},
    {"start_h", "m", "Initial geodetic altitude", 0, 0},
    {"start_vel", "m/s", "Initial speed relative to the rotating planet", 0, 0},
    {"start_fpa", "rad", "Initial flight-path angle of the relative velocity, up positive", 0, 0},
    {"start_chi", "rad", "Initial heading of the relative velocity, from north to east", 0, 0},
    {"start_time", "s", "Mission time at which the start_* values hold", 0, 0},
    {"start_psi", "rad", "Initial yaw attitude (3-2-1 Euler angles relative to NED)", 0, 0},
    {"start_theta", "rad", "Initial pitch attitude (3-2-1 Euler angles relative to NED)", 0, 0},
    {"start_phi", "rad", "Initial roll attitude (3-2-1 Euler angles relative to NED)", 0, 0},
    {"start_p", "rad/s", "Initial roll rate (relative to inertial space)", 0, 0},
    {"start_q", "rad/s", "Initial pitch rate (relative to inertial space)", 0, 0},
    {"start_r", "rad/s", "Initial yaw rate (relative to inertial space)", 0, 0},
    {"gimbal_pitch", "rad", "Pitch gimbal angle of every engine (constant input, without a controller)", 0, 0},
    {"gimbal_yaw", "rad", "Yaw gimbal angle of every engine (constant input, without a controller)", 0, 0},
    {"throttle", "1", "Throttle c_s (constant input)", 1, 0},
    {"propellant", "kg", "Propellant of the burning stage at the start: burnout when it is gone",
     0, 0},
};

static const lv_var output_vars[O_N] = {
    {"h", "m", "Geodetic altitude", 0, 0},
    {"lat", "rad", "Geodetic latitude", 0, 0},
    {"lon", "rad", "Longitude", 0, 0},
    {"radius", "m", "Distance from the planet's centre", 0, 0},
    {"v_north", "m/s", "Velocity relative to the planet, north (NED)", 0, 0},
    {"v_east", "m/s", "Velocity relative to the planet, east (NED)", 0, 0},
    {"v_down", "m/s", "Velocity relative to the planet, down (NED)", 0, 0},
    {"v_rel", "m/s", "Speed relative to the rotating planet", 0, 0},
    {"v_inertial", "m/s", "Inertial speed", 0, 0},
    {"fpa", "rad", "Flight-path angle of the relative velocity, up positive", 0, 0},
    {"heading", "rad", "Heading of the relative velocity, from north to east", 0, 0},
    {"mach", "1", "Mach number of the air-relative velocity", 0, 0},
    {"q_dyn", "Pa", "Dynamic pressure rho V_air^2 / 2", 0, 0},
    {"rho", "kg/m3", "Air density", 0, 0},
    {"p_amb", "Pa", "Ambient pressure", 0, 0},
    {"thrust", "N", "Net thrust of all engines (magnitude of the sum)", 0, 0},
    {"mdot", "kg/s", "Propellant mass flow of all engines (-dm/dt)", 0, 0},
    {"engine_on", "1", "1 while the engines burn", 0, 0},
    {"drag", "N", "Drag: aerodynamic force opposite the air-relative velocity", 0, 0},
    {"lift", "N", "Lift: aerodynamic force along wind -z", 0, 0},
    {"side_force", "N", "Aerodynamic force along wind +y", 0, 0},
    {"n_axial", "1", "Axial load factor: specific force along body x / g0", 0, 0},
    {"n_normal", "1", "Normal load factor: specific force along body -z / g0", 0, 0},
    {"n_lateral", "1", "Lateral load factor: specific force along body y / g0", 0, 0},
    {"theta", "rad", "Pitch attitude (3-2-1 Euler angles of the body relative to NED)", 0, 0},
    {"psi", "rad", "Yaw attitude (3-2-1 Euler angles relative to NED), [0, 2 pi)", 0, 0},
    {"phi", "rad", "Roll attitude (3-2-1 Euler angles relative to NED)", 0, 0},
    {"alpha", "rad", "Angle of attack: atan2(w, u) of the air-relative velocity in body axes", 0,
     0},
    {"beta", "rad", "Sideslip angle: asin(v / V) of the air-relative velocity in body axes", 0, 0},
    {"bank", "rad", "Bank angle of the wind axes about the air-relative velocity", 0, 0},
    {"L_aero", "N.m", "Aerodynamic rolling moment about the centre of mass, body x", 0, 0},
    {"M_aero", "N.m", "Aerodynamic pitching moment about the centre of mass, body y", 0, 0},
    {"N_aero", "N.m", "Aerodynamic yawing moment about the centre of mass, body z", 0, 0},
    {"L_thrust", "N.m", "Thrust moment about the centre of mass, body x", 0, 0},
    {"M_thrust", "N.m", "Thrust moment about the centre of mass, body y", 0, 0},
    {"N_thrust", "N.m", "Thrust moment about the centre of mass, body z", 0, 0},
    {"cg_x", "m", "Centre of mass, body x from the structural origin", 0, 0},
    {"cg_y", "m", "Centre of mass, body y from the structural origin", 0, 0},
    {"cg_z", "m", "Centre of mass, body z from the structural origin", 0, 0},
    {"I_xx", "kg.m2", "Moment of inertia about body x through the centre of mass", 0, 0},
    {"I_yy", "kg.m2", "Moment of inertia about body y through the centre of mass", 0, 0},
    {"I_zz", "kg.m2", "Moment of inertia about body z through the centre of mass", 0, 0},
    {"quat_norm", "1", "Norm of the attitude quaternion state (1 up to the drift control)", 0, 0},
    {"gimbal_pitch_in", "rad", "Pitch gimbal angle in effect", 0, 0},
    {"gimbal_yaw_in", "rad", "Yaw gimbal angle in effect", 0, 0},
    {"throttle_in", "1", "Throttle commanded: the constant, the inputs table's or the attitude "
     "table's (before engine limits; 0 with the engines off)", 0, 0},
    {"propellant_left", "kg", "Propellant left in the burning stage", 0, 0},
    {"sma", "m", "Osculating semi-major axis", 0, 0},
    {"ecc", "1", "Osculating eccentricity", 0, 0},
    {"inc", "rad", "Osculating inclination", 0, 0},
    {"apo_alt", "m", "Apoapsis radius minus the equatorial radius a", 0, 0},
    {"peri_alt", "m", "Periapsis radius minus the equatorial radius a", 0, 0},
    {"lat_gc", "rad", "Geocentric latitude", 0, 0},
    {"fpa_inertial", "rad", "Flight-path angle of the inertial velocity", 0, 0},
    {"heading_inertial", "rad", "Heading of the inertial velocity", 0, 0},
    {"accel", "m/s2", "Magnitude of the inertial acceleration of the CG (gravity included)", 0, 0},
    {"accel_sensed", "m/s2", "Magnitude of the specific force (thrust + aero) / m", 0, 0},
    {"raan", "rad", "Osculating right ascension of the ascending node (ECI)", 0, 0},
    {"argp", "rad", "Osculating argument of periapsis", 0, 0},
    {"downrange", "m", "Great-circle distance from the phase's start point on the sphere of radius a",
     0, 0},
    {"throttle_eff", "1", "Throttle each running engine gives: throttle_in clamped into one "
     "engine's [throttle_min, throttle_max]; 0 with the engines off", 0, 0},
    {"engines_running", "1", "Engines burning (a phase's `engines:` less its engine-outs; 0 off)",
     0, 0},
    LV_FLIGHT_SAFETY_OUTPUTS
    LV_FLIGHT_WIND_OUTPUTS
};

static const lv_var steer_output_vars[O_NMAX - O_N] = {
    {"theta_cmd", "rad", "Commanded pitch attitude (3-2-1 Euler, local NED) (with a steering law)",
     0, 0},
    {"psi_cmd", "rad", "Commanded heading (yaw) attitude (with a steering law)", 0, 0},
    {"phi_cmd", "rad", "Commanded roll attitude (with a steering law)", 0, 0},
    {"err_roll", "rad", "Attitude error about body x: rotation vector from the actual to the "
     "commanded body axes (with a steering law)", 0, 0},
    {"err_pitch", "rad", "Attitude error about body y (rotation vector, body axes) (with a steering law)", 0, 0},
    {"err_yaw", "rad", "Attitude error about body z (rotation vector, body axes) (with a steering law)", 0, 0},
    {"gimbal_pitch_cmd", "rad", "Pitch gimbal command after the deflection limit (with a controller)",
     0, 0},
    {"gimbal_yaw_cmd", "rad", "Yaw gimbal command after the deflection limit (with a controller)", 0,
     0},
};

static const char *const input_names[U_N] = {"gimbal_pitch", "gimbal_yaw", "throttle"};


/* ---- model data -------------------------------------------------------------------- */


typedef struct dof6_inst {
    lv_flight_rt rt;      /* burnout book, start point, steering state, messages (first) */
    lv_dof6 *m;           /* NULL in a block lv_simulate zeroed itself */
    lv_table_cursor in_cur;
} dof6_inst;

typedef struct eng6 {
    lv_vec3 pos;             /* m, body, structural origin */
    lv_vec3 exit;            /* m, the nozzle exit (pos when not given) */
    double mis_pitch, mis_yaw; /* rad */
} eng6;

struct lv_dof6 {
    lv_model_def def;
    char name[64];
    lv_var states[X_NMAX];
    size_t n_states;             /* 16, + 2 actuator states (PD), + 2 integrals (PID) */
    lv_var outputs[O_NMAX];
    size_t n_outputs;            /* O_N, + 6 with a steering law, + 2 with a controller */
    double nose_radius, k_sg;    /* m, kg^0.5/m: the heat flux output's (lv_dof6_config) */
    lv_var params[P_N];
    unsigned char param_inactive[P_N]; /* lv_model_def.param_inactive: inputs given otherwise */
    lv_flight_ends fe;           /* burnout (event 0) and the named ends (flight_ends.h) */
    lv_flight_core core;         /* what the shared callbacks read (flight_model.h) */

    lv_flight_world world;
    lv_domain_def domain[3];     /* the altitude floor and the steering law's guards */
    double *grav_ws;
    double gm;

    lv_dof6_mass mp;             /* mass properties */
    size_t n_eng;
    lv_engine *eng;
    eng6 *geom;
    double *eng_buf;
    int has_aero, has_moments;
    lv_aero aero;                /* forces */
    lv_aero mom;                 /* moment coefficients in the slots of CA, CN, CY: Cl, Cm, Cn */
    double clp, cmq, cnr, b_ref, c_ref;
    lv_vec3 r_mrp;
    const lv_table *inputs;
    int in_k[U_N];               /* output index per input, -1: the parameter */
    double *in_buf;
    int const_throttle;
    int sat_watch;               /* the commanded throttle varies (a table's): the saturation */
    double c_min, c_max;         /* the throttle range every engine accepts */
    lv_event_def *events;        /* [1 + fe.n + 2]: the flight model's, lv_flight_sat_events */
    int stop_at_burnout;
    int steers;                  /* a steering law gives the commanded attitude */
    lv_guid guid;
    lv_dof6_controller ctl;      /* kind NONE: gimbal angles from the inputs */
    lv_dof6_terms terms;         /* the switchable rigid-body terms (lv_dof6.h) */

    dof6_inst inst;
};

/* ---- the rigid body: small pure functions ---------------------------------------------- */

/* Direction cosine matrix C_eci_body of the quaternion q = (w, x, y, z) divided by its norm
 * (Stevens & Lewis eq. 1.8-10 with the rotation body -> ECI): the attitude is exact whatever
 * the norm's drift. */
static lv_mat3 quat_to_dcm(const double *q)
{
    const double n2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
    const double s = 2.0 / n2;
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    lv_mat3 C = {{{1.0 - s * (y * y + z * z), s * (x * y - w * z), s * (x * z + w * y)},
                  {s * (x * y + w * z), 1.0 - s * (x * x + z * z), s * (y * z - w * x)},
                  {s * (x * z - w * y), s * (y * z + w * x), 1.0 - s * (x * x + y * y)}}};
    return C;
}

/* Unit quaternion of a rotation matrix C_a_b (Shepperd's method, J. Guidance Control 1 (1978)
 * 223-224: the largest of the four squared components first). */
static void quat_from_dcm(const lv_mat3 *C, double q[4])
{
    const double tr = C->m[0][0] + C->m[1][1] + C->m[2][2];
    const double c4[4] = {1.0 + tr, 1.0 + 2.0 * C->m[0][0] - tr, 1.0 + 2.0 * C->m[1][1] - tr,
                          1.0 + 2.0 * C->m[2][2] - tr};
    int k = 0;
    for (int i = 1; i < 4; i++)
        if (c4[i] > c4[k])
            k = i;
    const double d = 2.0 * sqrt(c4[k]); /* 4 |q_k| */
    const double a = C->m[2][1] - C->m[1][2], b = C->m[0][2] - C->m[2][0];
    const double c = C->m[1][0] - C->m[0][1], e = C->m[1][0] + C->m[0][1];
    const double f = C->m[0][2] + C->m[2][0], g = C->m[2][1] + C->m[1][2];
    switch (k) {
    case 0: q[0] = 0.25 * d; q[1] = a / d; q[2] = b / d; q[3] = c / d; break;
    case 1: q[0] = a / d; q[1] = 0.25 * d; q[2] = e / d; q[3] = f / d; break;
    case 2: q[0] = b / d; q[1] = e / d; q[2] = 0.25 * d; q[3] = g / d; break;
    default: q[0] = c / d; q[1] = f / d; q[2] = g / d; q[3] = 0.25 * d; break;
    }
    if (q[0] < 0.0)
        for (int i = 0; i < 4; i++)
            q[i] = -q[i];
}

/* Quaternion kinematics q' = 1/2 q (x) (0, w_body) (Stevens & Lewis eq. 1.8-15, body rates
 * relative to the frame q rotates into, here ECI) plus the norm correction
 * K (1 - |q|^2) q (Zipfel sec. 4.3.2), which leaves the direction of q (the attitude) alone. */
static void quat_rate(const double *q, lv_vec3 w, double *qd)
{
    const double lam = QUAT_NORM_GAIN * (1.0 - (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] +
                                                q[3] * q[3]));
    qd[0] = 0.5 * (-q[1] * w.x - q[2] * w.y - q[3] * w.z) + lam * q[0];
    qd[1] = 0.5 * (q[0] * w.x + q[2] * w.z - q[3] * w.y) + lam * q[1];
    qd[2] = 0.5 * (q[0] * w.y + q[3] * w.x - q[1] * w.z) + lam * q[2];
    qd[3] = 0.5 * (q[0] * w.z + q[1] * w.y - q[2] * w.x) + lam * q[3];
}

/* Symmetric tensor of the six elements (xx, yy, zz, xy, xz, yz). */
static lv_mat3 tensor(const double *e)
{
    lv_mat3 I = {{{e[0], e[3], e[4]}, {e[3], e[1], e[5]}, {e[4], e[5], e[2]}}};
    return I;
}

/* Mass properties at mass m: the fraction of the propellant used s = (m_full - m) /
 * (m_full - m_empty) in [0, 1], the inertia tensor I and centre of mass cg linear in s, and
 * dI/ds (zero once s is clamped). The ends belong to the range (to 1e-9 of the span, for the
 * rounding of m): at a full start and at the burnout event's instant the engines still burn,
 * and I' = dI/ds mdot / span there is the limit from inside, consistent with the mass flow of
 * the same row; the mode after the event (mdot = 0) makes it 0 on the event's second row. */
typedef struct mass_props {
    double s;
    lv_mat3 I, dI_ds;
    lv_vec3 cg;
} mass_props;

static mass_props mass_props_at(const lv_dof6_mass *mp, double m)
{
    mass_props r;
    const double span = mp->m_full - mp->m_empty;
    double s = span > 0.0 ? (mp->m_full - m) / span : 0.0;
    const int inside = span > 0.0 && s >= -1e-9 && s <= 1.0 + 1e-9;
    s = s < 0.0 ? 0.0 : s > 1.0 ? 1.0 : s;
    double e[6], de[6];
    for (int i = 0; i < 6; i++) {
        de[i] = inside ? mp->inertia_empty[i] - mp->inertia_full[i] : 0.0;
        e[i] = mp->inertia_full[i] + s * (mp->inertia_empty[i] - mp->inertia_full[i]);
    }
    r.s = s;
    r.I = tensor(e);
    r.dI_ds = tensor(de);
    r.cg = lv_v3(mp->cg_full[0] + s * (mp->cg_empty[0] - mp->cg_full[0]),
                 mp->cg_full[1] + s * (mp->cg_empty[1] - mp->cg_full[1]),
                 mp->cg_full[2] + s * (mp->cg_empty[2] - mp->cg_full[2]));
    return r;
}

/* x = A^-1 b for a symmetric positive definite 3x3 A, by the adjugate (Cramer's rule). */
static lv_vec3 solve3(const lv_mat3 *A, lv_vec3 b)
{
    const double (*a)[3] = A->m;
    const double c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1];
    const double c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2];
    const double c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
    const double c11 = a[0][0] * a[2][2] - a[0][2] * a[2][0];
    const double c12 = a[0][1] * a[2][0] - a[0][0] * a[2][1];
    const double c22 = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    const double det = a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02;
    /* symmetric: the adjugate is symmetric too */
    return lv_v3((c00 * b.x + c01 * b.y + c02 * b.z) / det,
                 (c01 * b.x + c11 * b.y + c12 * b.z) / det,
                 (c02 * b.x + c12 * b.y + c22 * b.z) / det);
}

/* Euler's equations of a body of varying mass (Thomson ch. 8; Eke & Mao 2002; docs/models.md):
 *   I w' = M - w x (I w) - I' w
 * with I' = dI/dt the change of the inertia tensor as propellant is used (the caller passes
 * a zero I' with the term `inertia_rate` off); the jet damping moment is part of M
 * (jet_damping). */
static lv_vec3 euler_rate(const lv_mat3 *I, const lv_mat3 *I_dot, lv_vec3 w, lv_vec3 M)
{
    const lv_vec3 Iw = lv_m3_mul_v3(I, w);
    const lv_vec3 rhs = lv_v3_sub(lv_v3_sub(M, lv_v3_cross(w, Iw)), lv_m3_mul_v3(I_dot, w));
    return solve3(I, rhs);
}

/* Unit thrust direction in body axes of an engine gimballed by dp (pitch) and dy (yaw) [rad]:
 * (cos dp cos dy, -sin dy, sin dp cos dy). + dp tilts the thrust toward +z_b: for an engine
 * aft of the CG a nose-up (+M) moment; + dy toward -y_b: a nose-right (+N) moment. */
static lv_vec3 thrust_dir(double dp, double dy)
{
    const double cy = cos(dy);
    return lv_v3(cos(dp) * cy, -sin(dy), sin(dp) * cy);
}

/* Jet damping: the exhaust leaves the nozzle exit at r_e from the CG with the body's rotation
 * velocity w x r_e, carrying angular momentum away at the rate mdot r_e x (w x r_e) (Thomson
 * ch. 8): the moment -mdot r_e x (w x r_e), mdot > 0 the flow out [kg/s]. */
static lv_vec3 jet_damping(double mdot, lv_vec3 r_e, lv_vec3 w)
{
    return lv_v3_scale(lv_v3_cross(r_e, lv_v3_cross(w, r_e)), -mdot);
}

/* Transfer of a moment about the reference point r_mrp to the centre of mass cg under the
 * force f (all body axes): M_cg = M_mrp + (r_mrp - cg) x f. */
static lv_vec3 moment_transfer(lv_vec3 M_mrp, lv_vec3 r_mrp, lv_vec3 cg, lv_vec3 f)
{
    return lv_v3_add(M_mrp, lv_v3_cross(lv_v3_sub(r_mrp, cg), f));
}

/* ---- attitude control: small pure functions ------------------------------------------------ */

/* Attitude error: the rotation vector e = theta n [rad, body axes] of the rotation R that
 * carries the actual body axes b_i onto the commanded ones c_i, R_ij = b_i . c_j (the
 * commanded axes in body components): cos theta = (tr R - 1) / 2, sin theta n = vex((R - R^T)
 * / 2) (the Euler axis and angle of a rotation matrix: Shuster, "A survey of attitude
 * representations", J. Astronaut. Sci. 41 (1993) 439-517); the rotation vector of the error
 * quaternion q_b^* q_c, twice its vector part for small angles. A positive component asks for a
 * positive rotation about that body axis. theta in [0, pi]. Near pi, where sin theta n
 * vanishes and its direction is round-off, the axis comes from the symmetric part instead:
 * (R + R^T)/2 = cos theta I + (1 - cos theta) n n^T, its largest diagonal's column
 * normalised (Markley & Crassidis, Fundamentals of Spacecraft Attitude Determination and
 * Control, 2014, sec. 2.9.3), signed along sin theta n; at theta = pi itself, where both
 * signs are the same rotation, the sign that makes the axis's largest component positive: one
 * answer, not one per step (a retrograde command from a prograde attitude chattered between
 * the two until the step size collapsed, issue 27). */
static lv_vec3 attitude_error(const lv_flight_axes *b, const lv_flight_axes *c)
{
    const lv_vec3 bx = b->xb, by = b->yb, bz = b->zb, cx = c->xb, cy = c->yb, cz = c->zb;
    const double r[3][3] = {{lv_v3_dot(bx, cx), lv_v3_dot(bx, cy), lv_v3_dot(bx, cz)},
                            {lv_v3_dot(by, cx), lv_v3_dot(by, cy), lv_v3_dot(by, cz)},
                            {lv_v3_dot(bz, cx), lv_v3_dot(bz, cy), lv_v3_dot(bz, cz)}};
    const double tr = r[0][0] + r[1][1] + r[2][2];
    const lv_vec3 sn = lv_v3(0.5 * (r[2][1] - r[1][2]), 0.5 * (r[0][2] - r[2][0]),
                             0.5 * (r[1][0] - r[0][1]));
    const double s = lv_v3_norm(sn), ct = 0.5 * (tr - 1.0);
    const double theta = atan2(s, ct);
    if (ct > -0.5) /* theta < 120 deg: sin theta n is well conditioned */
        return s > 0.0 ? lv_v3_scale(sn, theta / s) : lv_v3(0.0, 0.0, 0.0);
    int k = 0;
    for (int i = 1; i < 3; i++)
        if (r[i][i] > r[k][k])
            k = i;
    double n[3];
    for (int i = 0; i < 3; i++) /* column k of (R + R^T)/2 - cos theta I */
        n[i] = 0.5 * (r[i][k] + r[k][i]) - (i == k ? ct : 0.0);
    const double nn = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(nn > 0.0))
        return lv_v3(0.0, 0.0, 0.0);
    lv_vec3 axis = lv_v3(n[0] / nn, n[1] / nn, n[2] / nn);
    double d = lv_v3_dot(axis, sn);
    if (fabs(d) <= 1e-12) { /* theta = pi: either sign; the one with its largest part > 0 */
        const double m = fabs(axis.x) >= fabs(axis.y) && fabs(axis.x) >= fabs(axis.z) ? axis.x
                         : fabs(axis.y) >= fabs(axis.z)                              ? axis.y
                                                                                     : axis.z;
        d = m;
    }
    return lv_v3_scale(axis, d < 0.0 ? -theta : theta);
}

/* PD/PID gimbal command of one axis before the deflection limit [rad]:
 * kp e + ki i + kd (w_c - w), e the attitude error [rad], i its integral [rad s], w the body
 * rate [rad/s] about the axis (inertial, as a rate gyro measures it) and w_c the commanded
 * attitude's rate about it (command_rate): the damping acts on the rate error, so a command
 * that turns at a steady rate is tracked without the lag kd w_c / kp that damping on the body
 * rate alone leaves (docs/models.md, "Attitude control"). */
static double gimbal_command(double kp, double ki, double kd, double e, double i, double w,
                             double w_c)
{
    return kp * e + ki * i + kd * (w_c - w);
}

static double clamp_abs(double v, double lim) { return v > lim ? lim : v < -lim ? -lim : v; }

/* Rate-limited first-order actuator [rad/s]: delta' = rho tanh((delta_c - delta) / (tau rho)):
 * the first-order lag (delta_c - delta) / tau for small errors, the rate rho for large ones,
 * smoothly in between (no kink for the integrator to resolve). */
static double actuator_rate(double delta_c, double delta, double tau, double rho)
{
    return rho * tanh((delta_c - delta) / (tau * rho));
}

/* ---- the point: everything (t, x, p) gives ------------------------------------------------ */

typedef struct dof6_point {
    lv_flight_kin kin;
    lv_flight_air air;
    lv_mat3 C_eci_body;
    lv_flight_axes ax;         /* body axes (and the wind axes, at outputs), ECEF */
    lv_vec3 v_air_b;           /* m/s, body */
    double alpha, beta;        /* rad */
    mass_props mp;
    double u[U_N];             /* gimbal pitch, yaw [rad], throttle */
    lv_flight_axes cmd;        /* commanded body axes (steering law), ECEF */
    lv_vec3 w_cmd;             /* rad/s, the commanded attitude's angular velocity relative to
                                  inertial space, body axes (with a controller) */
    lv_vec3 err;               /* rad, attitude error, body axes (rotation vector) */
    double delta_c[2];         /* rad, controller's gimbal commands after the limit */
    double mdot;               /* kg/s */
    lv_vec3 f_thrust_b, m_thrust_b; /* N, N m (about the CG, jet damping included) */
    double coef[3];
    lv_vec3 f_aero_b, m_aero_b;
    lv_vec3 g_ecef, a_eci;
    lv_vec3 w_dot;             /* rad/s^2 */
} dof6_point;

static lv_vec3 body_to_ecef(const lv_flight_axes *ax, lv_vec3 v)
{
    return lv_v3_add(lv_v3_add(lv_v3_scale(ax->xb, v.x), lv_v3_scale(ax->yb, v.y)),
                     lv_v3_scale(ax->zb, v.z));
}

static int inputs_eval(lv_dof6 *m, dof6_inst *s, double t, const double *p, double *u,
                       lv_err *err)
{
    u[U_GP] = p[P_GP];
    u[U_GY] = p[P_GY];
    u[U_THR] = p[P_THR];
    if (m->inputs == NULL)
        return 0;
    if (lv_table_eval1(m->inputs, &s->in_cur, t, m->in_buf, err) != LV_OK) {
        if (err)
            lv_fail_prefix(err, LV_ERR_INPUT, "inputs");
        return 1;
    }
    for (int i = 0; i < U_N; i++)
        if (m->in_k[i] >= 0)
            u[i] = m->in_buf[m->in_k[i]];
    return 0;
}

/* The commanded attitude's angular velocity relative to inertial space, body axes [rad/s]:
 * the steering law evaluated again at t + h on the state carried there to first order
 * (r + v h, v + a h in ECI: the law may follow the velocity, as `frame: aero` does), the
 * rotation from the commanded axes at t to those at t + h (attitude_error, a rotation vector)
 * over h - relative to the rotating ECEF frame the axes are given in - plus the planet's
 * rotation. A forward difference of h = CMD_RATE_DT, backwards when a time breakpoint of the
 * law (an attitude table's, the end of a kick) lies within h ahead, so the difference never
 * spans the breakpoint the integrator stops at. Its error is O(h) of the command's angular
 * acceleration, and rounding ~1e-16 / (w h) relative: 1e-9 at w = 1e-3 rad/s. */
#define CMD_RATE_DT 1e-4 /* s */
static int command_rate(lv_dof6 *m, dof6_inst *s, double t, const double *x, const double *p,
                        const dof6_point *pt, lv_vec3 *w_cmd_b, lv_err *err)
{
    const lv_flight_world *w = &m->world;
    double h = CMD_RATE_DT;
    if (lv_guid_next_time_event(&m->guid, &s->rt.guid, t) - t < h)
        h = -h;
    const double r[3] = {x[LV_X6_RX] + h * x[LV_X6_VX], x[LV_X6_RY] + h * x[LV_X6_VY],
                         x[LV_X6_RZ] + h * x[LV_X6_VZ]};
    const double v[3] = {x[LV_X6_VX] + h * pt->a_eci.x, x[LV_X6_VY] + h * pt->a_eci.y,
                         x[LV_X6_VZ] + h * pt->a_eci.z};
    lv_flight_kin kh;
    lv_flight_air ah;
    lv_flight_controls cc;
    lv_flight_axes ch;
    lv_flight_kinematics(w, t + h, r, v, 0, &kh);
    if (lv_guid_reads_atmosphere(&m->guid)) {
        if (lv_flight_air_eval(w, t + h, &kh, &ah, err) != 0)
            return 1;
    } else { /* the air-relative velocity only: the wind at t + h, the atmosphere unread */
        ah = pt->air;
        ah.v_air = kh.v_rel;
        if (w->wind != NULL) {
            double w_ned[3] = {0.0, 0.0, 0.0};
            const int rc = w->wind(t + h, kh.h, kh.lat, kh.lon, w_ned, w->wind_user);
            if (rc != 0) {
                if (err)
                    lv_fail(err, LV_ERR_INPUT, "wind function returned %d at t = %.9g s", rc,
                            t + h);
                return rc;
            }
            ah.v_air = lv_v3_sub(kh.v_rel, lv_flight_from_ned(&kh, w_ned[0], w_ned[1], w_ned[2]));
        }
        ah.v_air_n = lv_v3_norm(ah.v_air);
    }
    if (lv_guid_attitude(&m->guid, &s->rt.guid, t + h, &kh, &ah, pt->u[U_THR], p[P_FPA], p[P_CHI],
                         0, &cc, &ch, err) != 0)
        return 1;
    lv_vec3 w_e = lv_v3_scale(body_to_ecef(&pt->cmd, attitude_error(&pt->cmd, &ch)), 1.0 / h);
    w_e.z += w->planet.omega; /* ECEF turns at omega about its z axis */
    *w_cmd_b = lv_v3(lv_v3_dot(w_e, pt->ax.xb), lv_v3_dot(w_e, pt->ax.yb),
                     lv_v3_dot(w_e, pt->ax.zb));
    return 0;
}

static int point_eval(lv_dof6 *m, dof6_inst *s, double t, const double *x, const double *p,
                      int full, dof6_point *pt, lv_err *err)
{
    const double mass = x[LV_X6_M];
    if (!(mass > 0.0)) {
        if (err)
            lv_fail(err, LV_ERR_INPUT, "mass %g kg is not positive at t = %.9g s", mass, t);
        return 1;
    }
    const lv_flight_world *w = &m->world;
    /* 1, 2: kinematics and flight condition */
    lv_flight_kinematics(w, t, x + LV_X6_RX, x + LV_X6_VX, full, &pt->kin);
    int rc = lv_flight_air_eval(w, t, &pt->kin, &pt->air, err);
    if (rc != 0)
        return rc;
    /* attitude: body axes in ECEF = R3(theta) C_eci_body columns */
    pt->C_eci_body = quat_to_dcm(x + LV_X6_QW);
    const lv_flight_kin *k = &pt->kin;
    lv_vec3 col[3];
    for (int j = 0; j < 3; j++) {
        const double cx = pt->C_eci_body.m[0][j], cy = pt->C_eci_body.m[1][j];
        col[j] = lv_v3(k->c_th * cx + k->s_th * cy, -k->s_th * cx + k->c_th * cy,
                       pt->C_eci_body.m[2][j]);
    }
    pt->ax.xb = col[0];
    pt->ax.yb = col[1];
    pt->ax.zb = col[2];
    /* aerodynamic angles of the attitude (Stevens & Lewis eq. 2.3-6) */
    pt->v_air_b = lv_v3(lv_v3_dot(pt->air.v_air, col[0]), lv_v3_dot(pt->air.v_air, col[1]),
                        lv_v3_dot(pt->air.v_air, col[2]));
    if (pt->air.v_air_n > V_AIR_MIN) {
        pt->alpha = atan2(pt->v_air_b.z, pt->v_air_b.x);
        const double sb = pt->v_air_b.y / pt->air.v_air_n;
        pt->beta = asin(sb > 1.0 ? 1.0 : sb < -1.0 ? -1.0 : sb);
    } else {
        pt->alpha = pt->beta = 0.0;
    }
    /* 3: inputs; the steering law's commanded attitude, the attitude error and the
     * controller's gimbal commands (the actuators' states are the gimbal angles in effect) */
    if (inputs_eval(m, s, t, p, pt->u, err) != 0)
        return 1;
    const lv_vec3 w_b = {x[LV_X6_P], x[LV_X6_Q], x[LV_X6_R]};
    if (m->steers) {
        lv_flight_controls cc;
        if (lv_guid_attitude(&m->guid, &s->rt.guid, t, k, &pt->air, pt->u[U_THR], p[P_FPA],
                             p[P_CHI], full, &cc, &pt->cmd, err) != 0)
            return 1;
        pt->u[U_THR] = cc.u[LV_CTRL_THROTTLE]; /* an attitude table's throttle */
        pt->err = attitude_error(&pt->ax, &pt->cmd);
        if (m->ctl.kind != LV_DOF6_CTL_NONE) { /* the gimbal angles in effect: the actuators */
            pt->u[U_GP] = x[X_AP];
            pt->u[U_GY] = x[X_AY];
        }
    }
    pt->mp = mass_props_at(&m->mp, mass);

    /* 4a: engines, each at its gimbal point */
    pt->mdot = 0.0;
    pt->f_thrust_b = pt->m_thrust_b = lv_v3(0.0, 0.0, 0.0);
    if (s->rt.engines_on) {
        for (size_t i = 0; i < m->n_eng; i++) {
            double f, md;
            if (lv_engine_eval(&m->eng[i], t, pt->u[U_THR], pt->air.p_amb, m->eng_buf, &f, &md,
                               err) != LV_OK)
                return 1;
            const eng6 *g = &m->geom[i];
            const lv_vec3 fi = lv_v3_scale(thrust_dir(pt->u[U_GP] + g->mis_pitch,
                                                      pt->u[U_GY] + g->mis_yaw), f);
            const lv_vec3 r_e = lv_v3_sub(g->pos, pt->mp.cg);
            pt->f_thrust_b = lv_v3_add(pt->f_thrust_b, fi);
            pt->m_thrust_b = lv_v3_add(pt->m_thrust_b, lv_v3_cross(r_e, fi));
            if (m->terms.jet_damping) /* the exhaust leaves at the nozzle exit */
                pt->m_thrust_b = lv_v3_add(pt->m_thrust_b,
                                           jet_damping(md, lv_v3_sub(g->exit, pt->mp.cg), w_b));
            pt->mdot += md;
        }
    }
    /* 4b: aerodynamic force and moment (only where there is air) */
    pt->coef[0] = pt->coef[1] = pt->coef[2] = 0.0;
    pt->f_aero_b = pt->m_aero_b = lv_v3(0.0, 0.0, 0.0);
    if (m->has_aero && pt->air.q > 0.0) {
        if (lv_aero_coefs(&m->aero, pt->air.mach, pt->alpha, pt->beta, k->h, pt->coef, err) !=
            LV_OK)
            return 1;
        const double ca = cos(pt->alpha), sa = sin(pt->alpha);
        const double cb = cos(pt->beta), sb = sin(pt->beta);
        const double qs = pt->air.q * m->aero.s_ref;
        if (m->aero.axes == LV_AERO_BODY) {
            pt->f_aero_b = lv_v3(-qs * pt->coef[0], qs * pt->coef[2], -qs * pt->coef[1]);
        } else { /* f_b = C_body_wind f_w, C_body_wind = R2(alpha) R3(-beta) */
            double fw[3];
            lv_aero_force_wind(&m->aero, pt->coef, qs, ca, sa, cb, sb, fw);
            pt->f_aero_b = lv_v3(ca * cb * fw[0] - ca * sb * fw[1] - sa * fw[2],
                                 sb * fw[0] + cb * fw[1],
                                 sa * cb * fw[0] - sa * sb * fw[1] + ca * fw[2]);
        }
        if (m->has_moments) {
            double cm[3];
            if (lv_aero_coefs(&m->mom, pt->air.mach, pt->alpha, pt->beta, k->h, cm, err) !=
                LV_OK)
                return 1;
            /* the rates the damping derivatives multiply (terms.rate_damping_frame): relative
             * to the atmosphere, w - C_body_eci (0, 0, omega), or to inertial space, w */
            const double om =
                m->terms.rate_damping_frame == LV_DOF6_DAMPING_AIR ? w->planet.omega : 0.0;
            const lv_vec3 w_r = lv_v3(w_b.x - om * pt->C_eci_body.m[2][0],
                                      w_b.y - om * pt->C_eci_body.m[2][1],
                                      w_b.z - om * pt->C_eci_body.m[2][2]);
            const double V = pt->air.v_air_n, S = m->aero.s_ref;
            const double bh = m->b_ref / (2.0 * V), ch = m->c_ref / (2.0 * V);
            const lv_vec3 m_mrp =
                lv_v3(pt->air.q * S * m->b_ref * (cm[0] + m->clp * w_r.x * bh),
                      pt->air.q * S * m->c_ref * (cm[1] + m->cmq * w_r.y * ch),
                      pt->air.q * S * m->b_ref * (cm[2] + m->cnr * w_r.z * bh));
            pt->m_aero_b = moment_transfer(m_mrp, m->r_mrp, pt->mp.cg, pt->f_aero_b);
        } /* else: no moment data, the force acts through the CG (lv_dof6_config.moments) */
    }
    /* 5: translation (as lv_dof3) and rotation */
    const lv_vec3 f_ecef = body_to_ecef(&pt->ax, lv_v3_add(pt->f_thrust_b, pt->f_aero_b));
    pt->a_eci = lv_flight_accel_eci(w, m->grav_ws, k, f_ecef, mass, &pt->g_ecef);
    const double span = m->mp.m_full - m->mp.m_empty;
    lv_mat3 I_dot = pt->mp.dI_ds; /* dI/dt = dI/ds ds/dt, ds/dt = mdot / span */
    const double ds_dt = span > 0.0 && m->terms.inertia_rate ? pt->mdot / span : 0.0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            I_dot.m[i][j] *= ds_dt;
    pt->w_dot = euler_rate(&pt->mp.I, &I_dot, w_b, lv_v3_add(pt->m_thrust_b, pt->m_aero_b));
    /* 6: the controller's gimbal commands (they drive the actuators, not this point's forces) */
    if (m->steers && m->ctl.kind != LV_DOF6_CTL_NONE) {
        const lv_dof6_controller *c = &m->ctl;
        const int pid = c->kind == LV_DOF6_CTL_PID;
        if (command_rate(m, s, t, x, p, pt, &pt->w_cmd, err) != 0)
            return 1;
        pt->delta_c[0] = clamp_abs(gimbal_command(c->kp[0], c->ki[0], c->kd[0], pt->err.y,
                                                  pid ? x[X_IP] : 0.0, w_b.y, pt->w_cmd.y),
                                   c->limit);
        pt->delta_c[1] = clamp_abs(gimbal_command(c->kp[1], c->ki[1], c->kd[1], pt->err.z,
                                                  pid ? x[X_IY] : 0.0, w_b.z, pt->w_cmd.z),
                                   c->limit);
    }
    return 0;
}

/* ---- callbacks ------------------------------------------------------------------------ */

static void note(dof6_inst *s, const lv_err *e) { snprintf(s->rt.msg, sizeof s->rt.msg, "%s", e->msg); }

static int dof6_rhs(double t, const double *x, const double *p, double *xdot, void *inst)
{
    dof6_inst *s = inst;
    dof6_point pt;
    int rc = point_eval(s->m, s, t, x, p, 0, &pt, NULL);
    if (rc != 0) {
        lv_err e = {LV_OK, ""};
        point_eval(s->m, s, t, x, p, 0, &pt, &e);
        note(s, &e);
        return rc;
    }
    const double va = lv_v3_norm(pt.v_air_b);
    lv_flight_note_forces(&s->rt, lv_v3_norm(pt.f_thrust_b), lv_v3_add(pt.f_thrust_b, pt.f_aero_b),
                          va > 0.0 ? lv_v3_scale(pt.v_air_b, 1.0 / va) : lv_v3(1.0, 0.0, 0.0),
                          x[LV_X6_M]);
    xdot[LV_X6_RX] = x[LV_X6_VX];
    xdot[LV_X6_RY] = x[LV_X6_VY];
    xdot[LV_X6_RZ] = x[LV_X6_VZ];
    xdot[LV_X6_VX] = pt.a_eci.x;
    xdot[LV_X6_VY] = pt.a_eci.y;
    xdot[LV_X6_VZ] = pt.a_eci.z;
    quat_rate(x + LV_X6_QW, lv_v3(x[LV_X6_P], x[LV_X6_Q], x[LV_X6_R]), xdot + LV_X6_QW);
    xdot[LV_X6_P] = pt.w_dot.x;
    xdot[LV_X6_Q] = pt.w_dot.y;
    xdot[LV_X6_R] = pt.w_dot.z;
    xdot[LV_X6_M] = -pt.mdot;
    xdot[LV_X6_QSG] = lv_flight_heat_flux_sg(s->m->k_sg, pt.air.rho, s->m->nose_radius,
                                             pt.air.v_air_n);
    xdot[LV_X6_QFM] = lv_flight_heat_flux_fm(pt.air.rho, pt.air.v_air_n);
    if (s->m->ctl.kind != LV_DOF6_CTL_NONE) {
        const lv_dof6_controller *c = &s->m->ctl;
        xdot[X_AP] = actuator_rate(pt.delta_c[0], x[X_AP], c->tau, c->rate_limit);
        xdot[X_AY] = actuator_rate(pt.delta_c[1], x[X_AY], c->tau, c->rate_limit);
        if (c->kind == LV_DOF6_CTL_PID) {
            xdot[X_IP] = pt.err.y;
            xdot[X_IY] = pt.err.z;
        }
    }
    return 0;
}

static int check_params(dof6_inst *s, const double *p)
{
    if (lv_flight_check_start(&s->rt, p[P_LAT], p[P_VEL], p[P_PROP]) != 0)
        return -1;
    for (int i = P_PSI; i <= P_RR; i++)
        if (!isfinite(p[i]))
            return lv_flight_fail(&s->rt, "%s = %g is not finite", param_tpl[i].name, p[i]);
    for (int i = P_RP; i <= P_RR; i++)
        if (!(fabs(p[i]) <= LV_DOF6_RATE_MAX))
            return lv_flight_fail(&s->rt, "%s = %g rad/s is outside [-%g, %g] rad/s (10 rev/s)",
                                  param_tpl[i].name, p[i], LV_DOF6_RATE_MAX, LV_DOF6_RATE_MAX);
    return s->m->const_throttle ? lv_flight_check_throttle(&s->rt, p[P_THR]) : 0;
}

void lv_dof6_quat_from_euler(const lv_planet *pl, double t, double lat, double lon, double psi,
                             double theta, double phi, double q[4])
{
    lv_mat3 C_ecef_eci, C_ned_ecef, C_body_ned;
    lv_frames_C_ecef_eci(pl, t, C_ecef_eci.m);
    lv_frames_C_ned_ecef(lat, lon, C_ned_ecef.m);
    lv_frames_C_body_ned(psi, theta, phi, C_body_ned.m);
    /* C_body_eci = C_body_ned C_ned_ecef C_ecef_eci; its transpose is C_eci_body */
    const lv_mat3 A = lv_m3_mul(&C_body_ned, &C_ned_ecef);
    const lv_mat3 C_body_eci = lv_m3_mul(&A, &C_ecef_eci);
    const lv_mat3 C_eci_body = lv_m3_transpose(&C_body_eci);
    quat_from_dcm(&C_eci_body, q);
}

/* Position and velocity from the geodetic start values (as lv_dof3); the attitude from the
 * Euler angles relative to NED at the start point; the rates as given. */
static int dof6_start(const double *p, double *x, void *inst)
{
    dof6_inst *s = inst;
    if (s == NULL || s->m == NULL)
        return -1;
    s->rt.msg[0] = '\0';
    if (check_params(s, p) != 0)
        return -1;
    const lv_planet *pl = &s->m->world.planet;
    lv_flight_start_state(pl, p[P_LAT], p[P_LON], p[P_H], p[P_VEL], p[P_FPA], p[P_CHI], p[P_T0],
                          x + LV_X6_RX, x + LV_X6_VX);
    lv_dof6_quat_from_euler(pl, p[P_T0], p[P_LAT], p[P_LON], p[P_PSI], p[P_THETA], p[P_PHI],
                            x + LV_X6_QW);
    x[LV_X6_P] = p[P_RP];
    x[LV_X6_Q] = p[P_RQ];
    x[LV_X6_R] = p[P_RR];
    for (size_t i = LV_X6_N; i < s->m->n_states; i++)
        x[i] = 0.0; /* gimbal angles and integrals start at 0 */
    return 0;
}

/* The flight model's events, then the commanded throttle's saturation (lv_flight_sat_events,
 * as lv_dof3): constants (never crossed) for a constant throttle, with the engines off or none
 * running. */
static int dof6_event_g(double t, const double *x, const double *p, double *g, void *inst)
{
    dof6_inst *s = inst;
    lv_dof6 *m = s->m;
    const int rc = lv_flight_event_g(t, x, p, g, inst);
    double *gs = g + 1 + m->fe.n;
    if (!lv_flight_sat_begin(rc, m->sat_watch, &s->rt, m->eng, m->n_eng, gs))
        return rc;
    dof6_point pt;
    if (point_eval(m, s, t, x, p, 0, &pt, NULL) != 0)
        return 0; /* the right-hand side reports its own failure */
    lv_flight_sat_g(pt.u[U_THR], m->c_min, m->c_max, gs);
    return 0;
}

/* The start parameters of the state the run started from (lv_model_def.start_params): the
 * geodetic start as lv_dof3's, the attitude's Euler angles relative to NED and the rates as the
 * outputs theta, psi, phi and the states p, q, r give them. */
static int dof6_start_params(double t0, const double *x, double *p, void *inst)
{
    const dof6_inst *s = inst;
    if (s == NULL || s->m == NULL)
        return -1;
    const lv_flight_world *w = &s->m->world;
    lv_flight_start_geodetic(w, t0, x + LV_X6_RX, x + LV_X6_VX, p + P_LAT);
    p[P_T0] = t0;
    lv_flight_kin k;
    lv_flight_kinematics(w, t0, x + LV_X6_RX, x + LV_X6_VX, 1, &k);
    const lv_mat3 C = quat_to_dcm(x + LV_X6_QW);
    lv_vec3 col[3];
    for (int j = 0; j < 3; j++) /* body axes in ECEF, as point_eval */
        col[j] = lv_v3(k.c_th * C.m[0][j] + k.s_th * C.m[1][j],
                       -k.s_th * C.m[0][j] + k.c_th * C.m[1][j], C.m[2][j]);
    lv_flight_axes ax = {.xb = col[0], .yb = col[1], .zb = col[2]};
    lv_guid_euler_local(&k, &ax, &p[P_THETA], &p[P_PSI], &p[P_PHI]);
    p[P_RP] = x[LV_X6_P];
    p[P_RQ] = x[LV_X6_Q];
    p[P_RR] = x[LV_X6_R];
    return 0;
}

static int dof6_init(double t0, const double *x, const double *p, void *inst)
{
    dof6_inst *s = inst;
    if (s == NULL || s->m == NULL)
        return -1;
    s->rt.msg[0] = '\0';
    if (check_params(s, p) != 0)
        return -1;
    if (lv_flight_book(&s->rt, x[LV_X6_M], p[P_PROP], s->m->n_eng > 0) != 0)
        return -1;
    const double qn = sqrt(x[LV_X6_QW] * x[LV_X6_QW] + x[LV_X6_QX] * x[LV_X6_QX] +
                           x[LV_X6_QY] * x[LV_X6_QY] + x[LV_X6_QZ] * x[LV_X6_QZ]);
    if (!(fabs(qn - 1.0) < 1e-6))
        return lv_flight_fail(&s->rt, "start quaternion (%g, %g, %g, %g) has norm %.9g, not 1 (within "
                         "1e-6)", x[LV_X6_QW], x[LV_X6_QX], x[LV_X6_QY], x[LV_X6_QZ], qn);
    for (int i = LV_X6_P; i <= LV_X6_R; i++)
        if (!(fabs(x[i]) <= LV_DOF6_RATE_MAX))
            return lv_flight_fail(&s->rt, "start body rate %s = %g rad/s is outside [-%g, %g] rad/s (10 "
                             "rev/s)", state_tpl[i].name, x[i], LV_DOF6_RATE_MAX,
                             LV_DOF6_RATE_MAX);
    /* the actuators within the deflection limit; the integrals' share of the command, ki int,
     * too (0 on an axis with ki = 0, where the integral does not act): docs/models.md,
     * "Attitude control", start values */
    for (size_t i = LV_X6_N; i < s->m->n_states; i++) {
        const double ki = i >= X_IP ? s->m->ctl.ki[i - X_IP] : 1.0;
        const double share = i >= X_IP ? ki * x[i] : x[i];
        if (!isfinite(x[i]) || !(fabs(share) <= s->m->ctl.limit) || (ki == 0.0 && x[i] != 0.0))
            return lv_flight_fail(&s->rt, "start %s = %g %s: must be finite%s", ctl_state_tpl[i - LV_X6_N].name,
                             x[i], ctl_state_tpl[i - LV_X6_N].unit,
                             i <= X_AY ? " and within the controller's deflection limit"
                                       : ", |ki int| within the deflection limit (0 with ki = 0)");
    }
    lv_flight_kin kin;
    if (lv_flight_start(&s->rt, t0, x, &kin) != 0)
        return -1;
    if (s->m->steers &&
        lv_guid_start(&s->m->guid, &s->rt.guid, t0, &kin, s->rt.msg, sizeof s->rt.msg) != 0)
        return -1;
    return 0;
}

/* The outputs; need (NULL: all) as lv_model_def.outputs_some: the IIP only when asked for. */
static int dof6_outputs_some(double t, const double *x, const double *p, double *y,
                             const unsigned char *need, void *inst)
{
    dof6_inst *s = inst;
    lv_dof6 *m = s->m;
    dof6_point pt;
    lv_err e = {LV_OK, ""};
    int rc = point_eval(m, s, t, x, p, 1, &pt, &e);
    if (rc != 0) {
        note(s, &e);
        return rc;
    }
    const lv_flight_kin *k = &pt.kin;
    const double mass = x[LV_X6_M];
    const lv_vec3 v_eci = {x[LV_X6_VX], x[LV_X6_VY], x[LV_X6_VZ]};
    y[O_H] = k->h;
    y[O_LAT] = k->lat;
    y[O_LON] = k->lon;
    const double r[3] = {k->r_ecef.x, k->r_ecef.y, k->r_ecef.z};
    /* as lv_dof3 (hypot, not the norm of lv_vec3): the same bits at the same state */
    lv_frames_ecef_to_geocentric(r, &y[O_LAT_GC], NULL, &y[O_RADIUS]);
    y[O_VN] = lv_v3_dot(k->v_rel, k->n_ax);
    y[O_VE] = lv_v3_dot(k->v_rel, k->e_ax);
    y[O_VD] = lv_v3_dot(k->v_rel, k->d_ax);
    y[O_VREL] = lv_v3_norm(k->v_rel);
    y[O_VINR] = lv_v3_norm(v_eci);
    const double ned[3] = {y[O_VN], y[O_VE], y[O_VD]};
    lv_frames_fpa_from_ned(ned, NULL, &y[O_FPA], &y[O_CHI]);
    y[O_MACH] = pt.air.mach;
    y[O_Q] = pt.air.q;
    y[O_RHO] = pt.air.rho;
    y[O_PAMB] = pt.air.p_amb;
    y[O_THRUST] = lv_v3_norm(pt.f_thrust_b);
    y[O_MDOT] = pt.mdot;
    y[O_ENGINE_ON] = s->rt.engines_on;
    /* aerodynamic force in wind axes: x_w, y_w, z_w in body components (eq. 2.3-6) */
    const double ca = cos(pt.alpha), sa = sin(pt.alpha), cb = cos(pt.beta), sb = sin(pt.beta);
    const lv_vec3 xw_b = {ca * cb, sb, sa * cb}, yw_b = {-ca * sb, cb, -sa * sb},
                  zw_b = {-sa, 0.0, ca};
    y[O_DRAG] = -lv_v3_dot(pt.f_aero_b, xw_b);
    y[O_LIFT] = -lv_v3_dot(pt.f_aero_b, zw_b);
    y[O_SIDE] = lv_v3_dot(pt.f_aero_b, yw_b);
    const lv_vec3 f_spec = lv_v3_scale(lv_v3_add(pt.f_thrust_b, pt.f_aero_b), 1.0 / mass);
    y[O_NAX] = f_spec.x / LV_G0;
    y[O_NNORM] = -f_spec.z / LV_G0;
    y[O_NLAT] = f_spec.y / LV_G0;
    lv_guid_euler_local(k, &pt.ax, &y[O_THETA], &y[O_PSI], &y[O_PHI]);
    y[O_ALPHA] = pt.alpha;
    y[O_BETA] = pt.beta;
    /* bank: y_w against the horizontal y0 = z0 x x_w, z0 the down axis normal to x_w
     * (the wind frame of flight.h with mu = 0) */
    y[O_BANK] = 0.0;
    if (pt.air.v_air_n > V_AIR_MIN) {
        const lv_vec3 xw = body_to_ecef(&pt.ax, xw_b), yw = body_to_ecef(&pt.ax, yw_b);
        const lv_vec3 z0 = lv_flight_down_normal(k, xw, pt.air.v_air_n, 0, p[P_CHI]);
        const lv_vec3 y0 = lv_v3_cross(z0, xw);
        y[O_BANK] = atan2(lv_v3_dot(yw, z0), lv_v3_dot(yw, y0));
    }
    y[O_LA] = pt.m_aero_b.x;
    y[O_MA] = pt.m_aero_b.y;
    y[O_NA] = pt.m_aero_b.z;
    y[O_LT] = pt.m_thrust_b.x;
    y[O_MT] = pt.m_thrust_b.y;
    y[O_NT] = pt.m_thrust_b.z;
    y[O_CGX] = pt.mp.cg.x;
    y[O_CGY] = pt.mp.cg.y;
    y[O_CGZ] = pt.mp.cg.z;
    y[O_IXX] = pt.mp.I.m[0][0];
    y[O_IYY] = pt.mp.I.m[1][1];
    y[O_IZZ] = pt.mp.I.m[2][2];
    y[O_QNORM] = sqrt(x[LV_X6_QW] * x[LV_X6_QW] + x[LV_X6_QX] * x[LV_X6_QX] +
                      x[LV_X6_QY] * x[LV_X6_QY] + x[LV_X6_QZ] * x[LV_X6_QZ]);
    y[O_GP] = pt.u[U_GP];
    y[O_GY] = pt.u[U_GY];
    y[O_THR] = s->rt.engines_on ? pt.u[U_THR] : 0.0;
    size_t running = 0;
    for (size_t i = 0; s->rt.engines_on && i < m->n_eng; i++)
        running += !m->eng[i].out;
    y[O_ENG_RUN] = (double)running;
    y[O_HEAT_SG] = lv_flight_heat_flux_sg(m->k_sg, pt.air.rho, m->nose_radius, pt.air.v_air_n);
    y[O_HEAT_FM] = lv_flight_heat_flux_fm(pt.air.rho, pt.air.v_air_n);
    for (int c = 0; c < 3; c++)
        y[O_WIND_N + c] = pt.air.w_ned[c];
    y[O_THR_EFF] = 0.0;
    for (size_t i = 0; i < m->n_eng && running > 0; i++)
        if (!m->eng[i].out) { /* as lv_dof3: the first running engine's clamp */
            y[O_THR_EFF] = lv_engine_throttle(&m->eng[i], pt.u[U_THR]);
            break;
        }
    y[O_PROP_LEFT] = s->rt.burned_out || mass < s->rt.m_burnout ? 0.0 : mass - s->rt.m_burnout;
    lv_orbit_elem el;
    const double rv[3] = {x[LV_X6_RX], x[LV_X6_RY], x[LV_X6_RZ]};
    const double vv[3] = {v_eci.x, v_eci.y, v_eci.z};
    lv_orbit_elements(m->gm, rv, vv, &el);
    y[O_SMA] = el.a;
    y[O_ECC] = el.e;
    y[O_INC] = el.i;
    y[O_APO] = el.r_apo - m->world.planet.a;
    y[O_PERI] = el.r_peri - m->world.planet.a;
    y[O_RAAN] = el.raan;
    y[O_ARGP] = el.argp;
    const double r_ecef[3] = {k->r_ecef.x, k->r_ecef.y, k->r_ecef.z};
    lv_flight_iip_if(need, O_IIP_LAT, &m->world, m->grav_ws, m->gm, t, rv, vv, r_ecef,
                     &y[O_IIP_LAT]);

    /* inertial velocity in ECEF axes (no w x r): the inertial angles, as lv_dof3 */
    const lv_vec3 v_i = {k->c_th * v_eci.x + k->s_th * v_eci.y,
                         -k->s_th * v_eci.x + k->c_th * v_eci.y, v_eci.z};
    const double ned_i[3] = {lv_v3_dot(v_i, k->n_ax), lv_v3_dot(v_i, k->e_ax),
                             lv_v3_dot(v_i, k->d_ax)};
    lv_frames_fpa_from_ned(ned_i, NULL, &y[O_FPA_I], &y[O_CHI_I]);
    y[O_ACC] = lv_v3_norm(pt.a_eci);
    y[O_ACC_SENSED] = lv_v3_norm(f_spec);
    const lv_vec3 u0 = {s->rt.r0_unit[0], s->rt.r0_unit[1], s->rt.r0_unit[2]};
    const lv_vec3 u1 = lv_v3_scale(k->r_ecef, 1.0 / lv_v3_norm(k->r_ecef)); /* as lv_dof3 */
    y[O_DOWNRANGE] =
        m->world.planet.a * atan2(lv_v3_norm(lv_v3_cross(u0, u1)), lv_v3_dot(u0, u1));
    if (m->steers) {
        lv_guid_euler_local(k, &pt.cmd, &y[O_THC], &y[O_PSC], &y[O_PHC]);
        y[O_ER] = pt.err.x;
        y[O_EP] = pt.err.y;
        y[O_EY] = pt.err.z;
    }
    if (m->ctl.kind != LV_DOF6_CTL_NONE) {
        y[O_GPC] = pt.delta_c[0];
        y[O_GYC] = pt.delta_c[1];
    }
    return 0;
}

static int dof6_outputs(double t, const double *x, const double *p, double *y, void *inst)
{
    return dof6_outputs_some(t, x, p, y, NULL, inst);
}

void lv_dof6_rates_from_trajectory(lv_dof6 *m, double t, const double *x, const double f_eci[3],
                                   double w_body[3])
{
    const lv_flight_world *w = &m->world;
    lv_flight_kin kin;
    lv_flight_to_ecef(w, t, x + LV_X6_RX, x + LV_X6_VX, &kin);
    const lv_vec3 g_ecef = lv_flight_gravity(w, m->grav_ws, &kin);
    /* a = g + f, ECI (g rotated back: R3(theta)^T) */
    const lv_vec3 a = lv_v3(kin.c_th * g_ecef.x - kin.s_th * g_ecef.y + f_eci[0],
                            kin.s_th * g_ecef.x + kin.c_th * g_ecef.y + f_eci[1],
                            g_ecef.z + f_eci[2]);
    const lv_vec3 Wv = lv_v3(0.0, 0.0, w->planet.omega);
    const lv_vec3 r = lv_v3(x[LV_X6_RX], x[LV_X6_RY], x[LV_X6_RZ]);
    const lv_vec3 v = lv_v3(x[LV_X6_VX], x[LV_X6_VY], x[LV_X6_VZ]);
    const lv_vec3 u = lv_v3_sub(v, lv_v3_cross(Wv, r));    /* v_rel, ECI axes */
    const lv_vec3 du = lv_v3_sub(a, lv_v3_cross(Wv, v));   /* its inertial rate of change */
    const double u2 = lv_v3_dot(u, u);
    w_body[0] = w_body[1] = w_body[2] = 0.0;
    if (!(u2 > 1.0))
        return;
    const lv_vec3 w_eci = lv_v3_scale(lv_v3_cross(u, du), 1.0 / u2);
    const lv_mat3 C = quat_to_dcm(x + LV_X6_QW); /* C_eci_body: its transpose to body */
    w_body[0] = C.m[0][0] * w_eci.x + C.m[1][0] * w_eci.y + C.m[2][0] * w_eci.z;
    w_body[1] = C.m[0][1] * w_eci.x + C.m[1][1] * w_eci.y + C.m[2][1] * w_eci.z;
    w_body[2] = C.m[0][2] * w_eci.x + C.m[1][2] * w_eci.y + C.m[2][2] * w_eci.z;
}

/* ---- construction ---------------------------------------------------------------------- */

void lv_dof6_config_default(lv_dof6_config *cfg)
{
    memset(cfg, 0, sizeof *cfg);
    cfg->planet = lv_planet_earth();
    cfg->m0 = 1000.0;
    cfg->throttle = 1.0;
    cfg->nose_radius = 1.0;
    cfg->k_sutton_graves = LV_SUTTON_GRAVES_EARTH;
    for (int i = 0; i < 3; i++)
        cfg->mass.inertia_full[i] = cfg->mass.inertia_empty[i] = 1.0;
    cfg->terms = (lv_dof6_terms){1, 1, LV_DOF6_DAMPING_AIR};
    lv_steering_init(&cfg->steering, "inputs", NULL); /* target: the start point */
}

/* The steering law and the attitude controller (lv_dof6.h; docs/models.md, "Attitude
 * control"). */
static lv_status setup_control(lv_dof6 *m, const lv_dof6_config *cfg, lv_err *err)
{
    lv_steering st = cfg->steering;
    if (isnan(st.target_lat) || isnan(st.target_lon)) {
        st.target_lat = cfg->start_lat;
        st.target_lon = cfg->start_lon;
    }
    m->steers = lv_guid_cfg_steers(&st);
    const lv_dof6_controller *c = &cfg->controller;
    if ((unsigned)c->kind > LV_DOF6_CTL_PID)
        return lv_fail(err, LV_ERR_INPUT, "dof6: controller: unknown kind %d", (int)c->kind);
    if (c->kind != LV_DOF6_CTL_NONE && !m->steers)
        return lv_fail(err, LV_ERR_INPUT, "dof6: the attitude controller needs a steering law: "
                       "the attitude it holds (the steering law is 'inputs')");
    if (m->steers && st.law->dof3_only != NULL)
        return lv_fail(err, LV_ERR_INPUT, "dof6: guidance '%s' is for 3-DoF phases: %s",
                       lv_steering_law(&st), st.law->dof3_only);
    if (m->steers) {
        const lv_law_key *k3 = lv_guid_dof3_key(&st);
        if (k3 != NULL)
            return lv_fail(err, LV_ERR_INPUT, "dof6: guidance '%s': %s %s: give none",
                           lv_steering_law(&st), k3->name, st.law->dof3_why);
        lv_status rc = lv_guid_init(&m->guid, &st, &cfg->planet, cfg->aero != NULL, err);
        if (rc != LV_OK)
            return lv_fail_prefix(err, rc, "dof6");
        m->guid.need_alpha = m->guid.need_beta = 0; /* the commanded attitude's angles: unused */
    }
    m->ctl = *c;
    if (c->kind == LV_DOF6_CTL_NONE)
        return LV_OK;
    static const char *const ax[2] = {"pitch", "yaw"};
    for (int i = 0; i < 2; i++)
        if (!(c->kp[i] > 0.0 && c->kp[i] <= 100.0) || !(c->kd[i] >= 0.0 && c->kd[i] <= 100.0) ||
            !(c->ki[i] >= 0.0 && c->ki[i] <= 100.0))
            return lv_fail(err, LV_ERR_INPUT, "dof6: controller, %s: kp = %g rad/rad must be in "
                           "(0, 100], kd = %g s and ki = %g 1/s in [0, 100]", ax[i], c->kp[i],
                           c->kd[i], c->ki[i]);
    if (!(c->limit > 0.0 && c->limit <= 0.5 * LV_PI) || !(c->rate_limit > 0.0) ||
        !isfinite(c->rate_limit) || !(c->tau > 0.0) || !isfinite(c->tau))
        return lv_fail(err, LV_ERR_INPUT, "dof6: controller: limit = %g rad must be in (0, pi/2], "
                       "rate_limit = %g rad/s and tau = %g s > 0", c->limit, c->rate_limit,
                       c->tau);
    if (m->inputs != NULL && (m->in_k[U_GP] >= 0 || m->in_k[U_GY] >= 0))
        return lv_fail(err, LV_ERR_INPUT, "dof6: the controller gives the gimbal angles: the "
                       "input table '%s' must not", lv_table_name(m->inputs));
    /* the controller's signs hold for a gimbal point aft of the centre of mass */
    for (size_t i = 0; i < m->n_eng; i++)
        if (!(m->geom[i].pos.x < m->mp.cg_full[0] && m->geom[i].pos.x < m->mp.cg_empty[0]))
            return lv_fail(err, LV_ERR_INPUT, "dof6: controller: engine '%s' at x = %g m is not "
                           "aft of the centre of mass (x = %g m full, %g m empty): the gimbal "
                           "commands' signs assume it is", m->eng[i].name, m->geom[i].pos.x,
                           m->mp.cg_full[0], m->mp.cg_empty[0]);
    return LV_OK;
}

static lv_status setup_inputs(lv_dof6 *m, const lv_table *tab, lv_err *err)
{
    for (int k = 0; k < U_N; k++)
        m->in_k[k] = -1;
    if (tab == NULL)
        return LV_OK;
    lv_status st = lv_flight_check_inputs_table("dof6", tab, err);
    if (st != LV_OK)
        return st;
    int any = 0;
    for (int k = 0; k < U_N; k++) {
        size_t idx;
        if (lv_table_out_index(tab, input_names[k], &idx, NULL) == LV_OK) {
            if ((st = lv_table_expect_unit(tab, 0, idx, k < U_THR ? "rad" : "1", "dof6: inputs",
                                           err)) != LV_OK)
                return st;
            m->in_k[k] = (int)idx;
            any = 1;
        }
    }
    if (!any)
        return lv_fail(err, LV_ERR_INPUT,
                       "dof6: input table '%s' has none of the outputs 'gimbal_pitch', "
                       "'gimbal_yaw', 'throttle' (its first output is '%s')",
                       lv_table_name(tab), lv_table_out_name(tab, 0));
    for (size_t o = 0; o < lv_table_n_out(tab); o++) { /* a column nobody reads is a typo */
        int known = 0;
        for (int k = 0; k < U_N; k++)
            known |= m->in_k[k] == (int)o;
        if (!known)
            return lv_fail(err, LV_ERR_INPUT, "dof6: input table '%s': column '%s' is not an "
                           "input (gimbal_pitch, gimbal_yaw, throttle)", lv_table_name(tab),
                           lv_table_out_name(tab, o));
    }
    /* the gimbal angles at the breakpoints within +-90 deg, the range the constants are held to
     * (linear and PCHIP interpolation do not overshoot them; the ends are clamped); a throttle
     * outside the engines' limits is clamped and logged (lv_flight_sat_events) */
    size_t nb = 0;
    const double *tb = lv_table_breakpoints(tab, 0, &nb);
    double *row = malloc((lv_table_n_out(tab) + 1) * sizeof *row);
    if (row == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    lv_table_cursor cur = {0};
    for (size_t i = 0; i < nb && st == LV_OK; i++) {
        if ((st = lv_table_eval1(tab, &cur, tb[i], row, err)) != LV_OK)
            break;
        for (int k = 0; k < U_N && st == LV_OK; k++) {
            if (m->in_k[k] < 0)
                continue;
            const double v = row[m->in_k[k]];
            if (k < U_THR && !(fabs(v) <= 0.5 * LV_PI))
                st = lv_fail(err, LV_ERR_INPUT, "dof6: input table '%s': %s = %g rad at time "
                             "%g s is outside [-pi/2, pi/2]", lv_table_name(tab),
                             input_names[k], v, tb[i]);
        }
    }
    free(row);
    if (st != LV_OK)
        return st;
    m->in_buf = malloc(lv_table_n_out(tab) * sizeof *m->in_buf);
    if (m->in_buf == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    m->inputs = tab;
    return LV_OK;
}

static lv_status setup_ends(lv_dof6 *m, const lv_dof6_config *cfg, lv_err *err)
{
    return lv_flight_ends_init(&m->fe, "dof6", cfg->ends, cfg->n_ends, err);
}

/* Eigenvalues l[0] <= l[1] <= l[2] of the symmetric tensor of elements e[6] (the principal
 * moments): the closed form of O. K. Smith, "Eigenvalues of a symmetric 3 x 3 matrix", Commun.
 * ACM 4 (1961) 168. */
static void principal_moments(const double *e, double l[3])
{
    const double p1 = e[3] * e[3] + e[4] * e[4] + e[5] * e[5];
    const double q = (e[0] + e[1] + e[2]) / 3.0;
    const double d0 = e[0] - q, d1 = e[1] - q, d2 = e[2] - q;
    const double p2 = d0 * d0 + d1 * d1 + d2 * d2 + 2.0 * p1;
    if (!(p2 > 0.0)) { /* a multiple of the identity */
        l[0] = l[1] = l[2] = q;
        return;
    }
    const double pp = sqrt(p2 / 6.0);
    /* det((I - q E) / pp) / 2 */
    const double b00 = d0 / pp, b11 = d1 / pp, b22 = d2 / pp;
    const double b01 = e[3] / pp, b02 = e[4] / pp, b12 = e[5] / pp;
    double rr = 0.5 * (b00 * (b11 * b22 - b12 * b12) - b01 * (b01 * b22 - b12 * b02) +
                       b02 * (b01 * b12 - b11 * b02));
    rr = rr < -1.0 ? -1.0 : rr > 1.0 ? 1.0 : rr;
    const double phi = acos(rr) / 3.0;
    l[2] = q + 2.0 * pp * cos(phi);
    l[0] = q + 2.0 * pp * cos(phi + 2.0 * LV_PI / 3.0);
    l[1] = 3.0 * q - l[0] - l[2];
}

/* 1 if the principal moments of the tensor of elements e[6] satisfy the triangle inequality
 * I1 + I2 >= I3 of a real body (the second moment of mass J = tr(I)/2 E - I is positive
 * semidefinite), within 1e-9 of the largest; the moments in l[3]. */
static int physical_inertia(const double *e, double l[3])
{
    principal_moments(e, l);
    return l[0] + l[1] >= l[2] * (1.0 - 1e-9);
}

/* 1 if the symmetric tensor of elements e[6] is positive definite (Sylvester's criterion). */
static int positive_definite(const double *e)
{
    const lv_mat3 I = tensor(e);
    const double d1 = I.m[0][0], d2 = I.m[0][0] * I.m[1][1] - I.m[0][1] * I.m[1][0];
    const double d3 = I.m[0][0] * (I.m[1][1] * I.m[2][2] - I.m[1][2] * I.m[2][1]) -
                      I.m[0][1] * (I.m[1][0] * I.m[2][2] - I.m[1][2] * I.m[2][0]) +
                      I.m[0][2] * (I.m[1][0] * I.m[2][1] - I.m[1][1] * I.m[2][0]);
    return d1 > 0.0 && d2 > 0.0 && d3 > 0.0;
}

static lv_status setup_mass(lv_dof6 *m, const lv_dof6_config *cfg, lv_err *err)
{
    m->mp = cfg->mass;
    if (m->mp.m_full == 0.0) {
        m->mp.m_full = cfg->m0;
        m->mp.m_empty = cfg->m0 - cfg->propellant;
    }
    const lv_dof6_mass *mp = &m->mp;
    if (!isfinite(mp->m_full) || !isfinite(mp->m_empty) || !(mp->m_empty > 0.0) ||
        mp->m_empty > mp->m_full)
        return lv_fail(err, LV_ERR_INPUT, "dof6: mass properties: m_full = %g kg and m_empty = "
                       "%g kg must satisfy m_full >= m_empty > 0", mp->m_full, mp->m_empty);
    const char *const nm[6] = {"Ixx", "Iyy", "Izz", "Ixy", "Ixz", "Iyz"};
    for (int i = 0; i < 6; i++)
        if (!isfinite(mp->inertia_full[i]) || !isfinite(mp->inertia_empty[i]))
            return lv_fail(err, LV_ERR_INPUT, "dof6: inertia %s = %g (full), %g (empty) kg m^2 "
                           "must be finite", nm[i], mp->inertia_full[i], mp->inertia_empty[i]);
    for (int i = 0; i < 3; i++)
        if (!isfinite(mp->cg_full[i]) || !isfinite(mp->cg_empty[i]))
            return lv_fail(err, LV_ERR_INPUT, "dof6: centre of mass component %d = %g (full), "
                           "%g (empty) m must be finite", i, mp->cg_full[i], mp->cg_empty[i]);
    /* a convex combination of positive definite tensors is positive definite: both ends */
    if (!positive_definite(mp->inertia_full) || !positive_definite(mp->inertia_empty))
        return lv_fail(err, LV_ERR_INPUT, "dof6: the inertia tensor (Ixx %g, Iyy %g, Izz %g, Ixy "
                       "%g, Ixz %g, Iyz %g kg m^2 full; Ixx %g, Iyy %g, Izz %g empty) is not "
                       "positive definite at both ends", mp->inertia_full[0],
                       mp->inertia_full[1], mp->inertia_full[2], mp->inertia_full[3],
                       mp->inertia_full[4], mp->inertia_full[5], mp->inertia_empty[0],
                       mp->inertia_empty[1], mp->inertia_empty[2]);
    /* J = tr(I)/2 E - I is linear in I: positive semidefinite at both ends, it is in between */
    for (int end = 0; end < 2; end++) {
        double l[3];
        if (!physical_inertia(end == 0 ? mp->inertia_full : mp->inertia_empty, l))
            return lv_fail(err, LV_ERR_INPUT, "dof6: the inertia tensor (%s) has the principal "
                           "moments %g, %g, %g kg m^2: the two smaller add up to less than the "
                           "largest (I1 + I2 >= I3 holds for every real body)",
                           end == 0 ? "full" : "empty", l[0], l[1], l[2]);
    }
    return LV_OK;
}

static lv_status setup_aero(lv_dof6 *m, const lv_dof6_config *cfg, lv_err *err)
{
    lv_status st;
    if (cfg->aero != NULL) {
        if ((st = lv_aero_init(&m->aero, cfg->aero, err)) != LV_OK)
            return lv_fail_prefix(err, st, "dof6");
        m->has_aero = 1;
    }
    const lv_dof6_moments *mo = cfg->moments;
    if (mo == NULL)
        return LV_OK;
    if (cfg->aero == NULL)
        return lv_fail(err, LV_ERR_INPUT, "dof6: aerodynamic moments need the force set (its "
                       "reference area): aero is NULL");
    if (!(mo->b_ref > 0.0) || !(mo->c_ref > 0.0) || !isfinite(mo->b_ref) || !isfinite(mo->c_ref))
        return lv_fail(err, LV_ERR_INPUT, "dof6: moments: b_ref = %g m and c_ref = %g m must be "
                       "> 0", mo->b_ref, mo->c_ref);
    if (!isfinite(mo->clp) || !isfinite(mo->cmq) || !isfinite(mo->cnr))
        return lv_fail(err, LV_ERR_INPUT, "dof6: moments: Clp = %g, Cmq = %g, Cnr = %g 1/rad "
                       "must be finite", mo->clp, mo->cmq, mo->cnr);
    for (int i = 0; i < 3; i++)
        if (!isfinite(mo->r_mrp[i]))
            return lv_fail(err, LV_ERR_INPUT, "dof6: moments: reference point component %d = %g m",
                           i, mo->r_mrp[i]);
    /* Cl, Cm, Cn through the coefficient machinery of lv_aero, in the slots of CA, CN, CY */
    lv_aero_config mc;
    lv_aero_config_default(&mc);
    mc.axes = LV_AERO_BODY;
    mc.s_ref = cfg->aero->s_ref;
    const lv_aero_coef *src[3] = {&mo->cl, &mo->cm, &mo->cn};
    static const char *const names[3] = {"Cl", "Cm", "Cn"};
    for (int i = 0; i < 3; i++) {
        mc.coef[i] = *src[i];
        if (mc.coef[i].table != NULL && mc.coef[i].output == NULL &&
            lv_table_n_out(mc.coef[i].table) > 1)
            mc.coef[i].output = names[i];
    }
    if ((st = lv_aero_init(&m->mom, &mc, err)) != LV_OK)
        return lv_fail_prefix(err, st, "dof6: moment coefficients (Cl, Cm, Cn in the slots of CA, "
                              "CN, CY)");
    m->has_moments = 1;
    m->clp = mo->clp;
    m->cmq = mo->cmq;
    m->cnr = mo->cnr;
    m->b_ref = mo->b_ref;
    m->c_ref = mo->c_ref;
    m->r_mrp = lv_v3(mo->r_mrp[0], mo->r_mrp[1], mo->r_mrp[2]);
    return LV_OK;
}

/* The engines (flight_model.h) and each one's position and misalignment on the body. */
static lv_status setup_engines(lv_dof6 *m, const lv_dof6_config *cfg, lv_err *err)
{
    lv_status st = lv_flight_engines_init("dof6", cfg->engines, cfg->n_engines, &m->eng,
                                          &m->n_eng, &m->eng_buf, err);
    if (st != LV_OK || m->n_eng == 0)
        return st;
    if (cfg->engine_geom == NULL) /* no default position: the moments depend on it */
        return lv_fail(err, LV_ERR_INPUT, "dof6: %zu engine(s) without their position "
                       "(engine_geom NULL): the thrust moment%s act%s at it", m->n_eng,
                       cfg->terms.jet_damping ? " and the jet damping" : "",
                       cfg->terms.jet_damping ? "" : "s");
    if ((m->geom = calloc(m->n_eng, sizeof *m->geom)) == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    for (size_t i = 0; i < m->n_eng; i++) {
        const lv_dof6_engine_geom *g = &cfg->engine_geom[i];
        const double *ex = cfg->engine_exit != NULL ? cfg->engine_exit + 3 * i : g->pos;
        if (!isfinite(g->pos[0]) || !isfinite(g->pos[1]) || !isfinite(g->pos[2]) ||
            !isfinite(g->mis_pitch) || !isfinite(g->mis_yaw) || !isfinite(ex[0]) ||
            !isfinite(ex[1]) || !isfinite(ex[2]))
            return lv_fail(err, LV_ERR_INPUT, "dof6: engine '%s': position (%g, %g, %g) m, "
                           "nozzle exit (%g, %g, %g) m and misalignment (%g, %g) rad must be "
                           "finite", m->eng[i].name, g->pos[0], g->pos[1], g->pos[2], ex[0],
                           ex[1], ex[2], g->mis_pitch, g->mis_yaw);
        m->geom[i] = (eng6){lv_v3(g->pos[0], g->pos[1], g->pos[2]), lv_v3(ex[0], ex[1], ex[2]),
                            g->mis_pitch, g->mis_yaw};
    }
    return LV_OK;
}

lv_status lv_dof6_create(const lv_dof6_config *cfg, lv_dof6 **out, lv_err *err)
{
    *out = NULL;
    lv_status st;
    lv_dof6 *m = calloc(1, sizeof *m);
    if (m == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    snprintf(m->name, sizeof m->name, "%s", cfg->name != NULL ? cfg->name : "dof6");
    if ((st = lv_flight_check_mass("dof6", cfg->m0, cfg->propellant, err)) != LV_OK ||
        (st = lv_flight_check_heating("dof6", cfg->nose_radius, cfg->k_sutton_graves, err)) !=
            LV_OK)
        goto fail;
    m->nose_radius = cfg->nose_radius;
    m->k_sg = cfg->k_sutton_graves;
    const double fin[] = {cfg->start_lon, cfg->start_h, cfg->start_fpa, cfg->start_chi,
                          cfg->start_time, cfg->start_psi, cfg->start_theta, cfg->start_phi,
                          cfg->start_p, cfg->start_q, cfg->start_r, cfg->gimbal_pitch,
                          cfg->gimbal_yaw, cfg->throttle};
    static const char *const fin_names[] = {"start_lon", "start_h", "start_fpa", "start_chi",
                                            "start_time", "start_psi", "start_theta",
                                            "start_phi", "start_p", "start_q", "start_r",
                                            "gimbal_pitch", "gimbal_yaw", "throttle"};
    for (size_t i = 0; i < sizeof fin / sizeof fin[0]; i++)
        if (!isfinite(fin[i])) {
            st = lv_fail(err, LV_ERR_INPUT, "dof6: %s = %g (must be finite)", fin_names[i],
                         fin[i]);
            goto fail;
        }
    if (!(fabs(cfg->start_lat) <= 0.5 * LV_PI) || !(cfg->start_vel >= 0.0) ||
        !isfinite(cfg->start_vel)) {
        st = lv_fail(err, LV_ERR_INPUT, "dof6: start_lat = %g rad (must be in [-pi/2, pi/2]), "
                     "start_vel = %g m/s (must be >= 0)", cfg->start_lat, cfg->start_vel);
        goto fail;
    }
    if ((st = lv_flight_world_setup(&m->world, "dof6", &cfg->planet, cfg->gravity, cfg->atmo,
                                    cfg->wind, cfg->wind_user, &m->grav_ws, &m->gm, err)) != LV_OK)
        goto fail;

    if ((st = setup_mass(m, cfg, err)) != LV_OK || (st = setup_engines(m, cfg, err)) != LV_OK ||
        (st = setup_aero(m, cfg, err)) != LV_OK || (st = setup_inputs(m, cfg->inputs, err)) != LV_OK)
        goto fail;
    m->const_throttle = m->in_k[U_THR] < 0;
    if (m->const_throttle)
        for (size_t i = 0; i < m->n_eng; i++)
            if (!(cfg->throttle >= m->eng[i].thr_min && cfg->throttle <= m->eng[i].thr_max)) {
                st = lv_fail(err, LV_ERR_INPUT,
                             "dof6: throttle = %g is outside the limits [%g, %g] of engine '%s'",
                             cfg->throttle, m->eng[i].thr_min, m->eng[i].thr_max,
                             m->eng[i].name);
                goto fail;
            }
    m->stop_at_burnout = cfg->stop_at_burnout != 0;
    if ((cfg->terms.jet_damping != 0 && cfg->terms.jet_damping != 1) ||
        (cfg->terms.inertia_rate != 0 && cfg->terms.inertia_rate != 1) ||
        (cfg->terms.rate_damping_frame != LV_DOF6_DAMPING_AIR &&
         cfg->terms.rate_damping_frame != LV_DOF6_DAMPING_INERTIAL)) {
        st = lv_fail(err, LV_ERR_INPUT, "dof6: terms: jet_damping = %d, inertia_rate = %d (0 or "
                     "1), rate_damping_frame = %d (0 air, 1 inertial)", cfg->terms.jet_damping,
                     cfg->terms.inertia_rate, (int)cfg->terms.rate_damping_frame);
        goto fail;
    }
    m->terms = cfg->terms;
    if ((st = setup_ends(m, cfg, err)) != LV_OK || (st = setup_control(m, cfg, err)) != LV_OK)
        goto fail;
    /* the range one throttle can give every engine, and whether the throttle varies (the
     * inputs table's, the attitude table's): its saturation is then logged */
    m->c_min = 0.0;
    m->c_max = m->n_eng > 0 ? HUGE_VAL : 1.0;
    for (size_t i = 0; i < m->n_eng; i++) {
        m->c_min = fmax(m->c_min, m->eng[i].thr_min);
        m->c_max = fmin(m->c_max, m->eng[i].thr_max);
    }
    m->sat_watch = m->n_eng > 0 && (m->in_k[U_THR] >= 0 ||
                                    (m->steers && lv_guid_gives_throttle(&cfg->steering)));

    memcpy(m->states, state_tpl, sizeof state_tpl);
    m->states[LV_X6_M].start = cfg->m0;
    m->states[LV_X6_M].nominal = cfg->m0;
    m->n_states = LV_X6_N + (m->ctl.kind == LV_DOF6_CTL_PID   ? 4
                             : m->ctl.kind == LV_DOF6_CTL_PD ? 2
                                                              : 0);
    memcpy(m->states + LV_X6_N, ctl_state_tpl, (m->n_states - LV_X6_N) * sizeof *m->states);
    memcpy(m->outputs, output_vars, sizeof output_vars);
    m->n_outputs = m->ctl.kind != LV_DOF6_CTL_NONE ? O_NMAX : m->steers ? O_GPC : O_N;
    memcpy(m->outputs + O_N, steer_output_vars, (m->n_outputs - O_N) * sizeof *m->outputs);
    memcpy(m->params, param_tpl, sizeof m->params);
    const double pv[P_N] = {cfg->start_lat,   cfg->start_lon,   cfg->start_h,
                            cfg->start_vel,   cfg->start_fpa,   cfg->start_chi,
                            cfg->start_time,  cfg->start_psi,   cfg->start_theta,
                            cfg->start_phi,   cfg->start_p,     cfg->start_q,
                            cfg->start_r,     cfg->gimbal_pitch, cfg->gimbal_yaw,
                            cfg->throttle,    cfg->propellant};
    for (int i = 0; i < P_N; i++)
        m->params[i].start = pv[i];
    /* the constant inputs that do not act, left out of the result files' parameter records:
     * the gimbal angles a controller or the inputs table gives, a throttle the table gives or
     * that no engine burns with (the values in effect: gimbal_*_in, throttle_in) */
    const int ctl = m->steers && m->ctl.kind != LV_DOF6_CTL_NONE;
    m->param_inactive[P_GP] = ctl || m->in_k[U_GP] >= 0;
    m->param_inactive[P_GY] = ctl || m->in_k[U_GY] >= 0;
    m->param_inactive[P_THR] = !m->const_throttle || m->n_eng == 0 ||
                               (m->steers && lv_guid_gives_throttle(&cfg->steering));

    m->def = (lv_model_def){
        .name = m->name,
        .description = "6-DoF variable-mass rigid body over a rotating planet, ECI states and "
                       "attitude quaternion",
        .n_states = m->n_states,
        .n_params = P_N,
        .n_outputs = m->n_outputs,
        .states = m->states,
        .params = m->params,
        .outputs = m->outputs,
        .inst_size = sizeof(dof6_inst),
        .start = dof6_start,
        .init = dof6_init,
        .rhs = dof6_rhs,
        .outputs_fn = dof6_outputs,
        .outputs_some = dof6_outputs_some,
        .abs_error = abs_error,
        /* an attitude controller drives first-order actuator lags (tau: 0.05 s in the
         * examples): stiff for an explicit method, so "auto" integrates with BDF (measured on
         * two-stage-6dof's boost at 1e-8: dop853 2476 steps, 33989 rhs; BDF 1740, 3379) */
        .stiff = m->ctl.kind != LV_DOF6_CTL_NONE,
        .param_inactive = m->param_inactive,
        .start_params = dof6_start_params,
        .quadrature = quadrature,
    };
    m->core = (lv_flight_core){.world = &m->world, .fe = &m->fe, .i_r = LV_X6_RX,
                               .i_v = LV_X6_VX, .i_m = LV_X6_M, .inputs = m->inputs,
                               .eng = m->eng, .n_eng = m->n_eng,
                               .guid = m->steers ? &m->guid : NULL,
                               .stop_at_burnout = m->stop_at_burnout};
    m->core.law = m->steers ? &m->guid : NULL; /* without: the inputs are the gimbal's */
    m->core.rolls = 1;
    lv_flight_domain_init(m->domain, &m->core, cfg->atmo != NULL);
    lv_flight_def_callbacks(&m->def, &m->core, &m->inst.rt, m->domain);
    if ((m->events = lv_flight_add_sat_events(&m->def, &m->core)) == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto fail;
    }
    m->def.event_g = dof6_event_g;
    m->inst.m = m;
    if ((st = lv_model_validate(&m->def, err)) != LV_OK)
        goto fail;
    *out = m;
    return LV_OK;
fail:
    lv_dof6_free(m);
    return st;
}

void lv_dof6_free(lv_dof6 *m)
{
    if (m == NULL)
        return;
    lv_aero_clear(&m->aero);
    lv_aero_clear(&m->mom);
    free(m->eng);
    free(m->geom);
    free(m->eng_buf);
    free(m->in_buf);
    free(m->grav_ws);
    lv_flight_ends_clear(&m->fe);
    free(m->events);
    free(m);
}

const lv_model_def *lv_dof6_def(const lv_dof6 *m) { return &m->def; }

void *lv_dof6_inst(lv_dof6 *m) { return &m->inst; }

const char *lv_dof6_last_error(const lv_dof6 *m) { return m->inst.rt.msg; }
