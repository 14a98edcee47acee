/* flight.h - the pieces a flight model's right-hand side is composed of, in the order it
 * uses them (docs/models.md, "The right-hand side"):
 *
 *   1. kinematics          lv_flight_kinematics  ECI state -> ECEF position, velocity relative
 *                                                to the rotating planet, geodetic altitude, NED
 *   2. flight condition    lv_flight_air         atmosphere (rho, p, a), wind, air-relative
 *                                                velocity, Mach number, dynamic pressure
 *   3. controls            lv_flight_controls    angle of attack, sideslip, bank, throttle in
 *                                                effect (constants, tables; guidance laws)
 *   4. vehicle forces      lv_flight_axes        wind and body axes from the controls
 *                          lv_flight_thrust      engines (thrust along body x, mass flow)
 *                          lv_flight_aero        aerodynamic force from coefficient tables
 *   5. equations of motion lv_flight_accel_eci   a = g(r) + F/m, rotated to ECI
 *
 * The 3-DoF model (dof3.c) is these five steps and nothing else; a 6-DoF model and guidance
 * laws use the same pieces. Everything here is a pure function of its arguments (table
 * cursors excepted), allocates nothing and looks nothing up by name: it runs in the hot path.
 * Frames (docs/frames.md): ECI and ECEF share the z axis, ECEF = R3(theta0 + omega t) ECI;
 * NED at the vehicle's geodetic position; wind axes x_w along the air-relative velocity;
 * body axes from the wind axes by alpha and beta. Rotating-frame kinematics: Stevens, Lewis
 * & Johnson, Aircraft Control and Simulation, 3rd ed., sec. 1.6; wind/body axes sec. 2.3.
 */
#ifndef LV_DYNAMICS_FLIGHT_H
#define LV_DYNAMICS_FLIGHT_H

#include <stddef.h>

#include "core/vec3.h"
#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_planet.h"
#include "lvsim/lv_status.h"
#include "lvsim/lv_table.h"
#include "lvsim/lv_vehicle.h"
#include "vehicle/vehicle.h"

/* What the environment gives a flight model (borrowed pointers; read-only in the hot path
 * except the wind function's own `wind_user`). */
typedef struct lv_flight_world {
    lv_planet planet;                /* ellipsoid and rotation */
    double e2;                       /* first eccentricity squared */
    double b;                        /* m, polar radius */
    const lv_gravity *grav;          /* evaluated at ECEF positions */
    const lv_atmo_model *atmo_model; /* NULL: vacuum */
    const void *atmo_par;
    lv_wind_fn wind;                 /* NULL: no wind */
    void *wind_user;
    int wind_latlon; /* the wind function reads lat, lon: every function but lvsim's table
                        wind (lv_wind_fn_table, over time and altitude), whose two atan2 per
                        evaluation were 9 % of a Monte Carlo mission's instructions */
} lv_flight_world;

/* Fills the derived fields (e2, b) of `w` from w->planet. */
void lv_flight_world_init(lv_flight_world *w);

/* The environment of a model over the planet (dof3, dof6, runway): checks the planet, requires
 * a gravity model, takes the atmosphere (NULL: vacuum) and wind; *grav_ws gets the gravity
 * model's workspace (malloc'ed, the caller frees it) and *gm its GM [m^3/s^2] (NULL: not
 * wanted). LV_ERR_INPUT with the model's name for a bad planet or no gravity, LV_ERR_NOMEM. */
lv_status lv_flight_world_setup(lv_flight_world *w, const char *model, const lv_planet *planet,
                                const lv_gravity *gravity, const lv_atmo *atmo, lv_wind_fn wind,
                                void *wind_user, double **grav_ws, double *gm, lv_err *err);

/* 1. Kinematics at time t of the ECI position r [m] and velocity v [m/s]. */
typedef struct lv_flight_kin {
    double c_th, s_th;        /* cos, sin of the ECI -> ECEF angle theta0 + omega t */
    lv_vec3 r_ecef;           /* m */
    lv_vec3 v_rel;            /* m/s, velocity relative to the planet, ECEF axes */
    double lat, lon, h;       /* rad, rad, m: geodetic (lat, lon NAN unless computed) */
    lv_vec3 n_ax, e_ax, d_ax; /* NED axes, ECEF components */
} lv_flight_kin;

/* ECEF position and relative velocity only: r_ecef = R3(theta) r_eci,
 * v_rel = R3(theta) (v_eci - w x r_eci). */
void lv_flight_to_ecef(const lv_flight_world *w, double t, const double r_eci[3],
                       const double v_eci[3], lv_flight_kin *k);

/* Geodetic altitude and NED axes at k->r_ecef. exact = 0 (right-hand side, events): one step
 * of Bowring's iteration from the parametric latitude (Bowring, "Transformation from spatial
 * to geographical coordinates", Survey Review 23 (1976) 323-327) without trigonometric calls:
 * against the exact lv_frames_ecef_to_geodetic, h is within 2.5e-9 m and the latitude within
 * 1.3e-9 rad from -5 km to 1250 km on the Earth, within 1.5e-8 m and 8.4e-9 rad up to
 * geostationary altitude; lat and lon are computed only when `angles`. exact = 1 (outputs):
 * lv_frames_ecef_to_geodetic itself, lat and lon always. */
void lv_flight_geodetic(const lv_flight_world *w, lv_flight_kin *k, int exact, int angles);

/* Both: lv_flight_to_ecef, then lv_flight_geodetic (angles when the world has a wind). */
void lv_flight_kinematics(const lv_flight_world *w, double t, const double r_eci[3],
                          const double v_eci[3], int exact, lv_flight_kin *k);

/* ECEF vector from NED components at the vehicle. */
lv_vec3 lv_flight_from_ned(const lv_flight_kin *k, double n, double e, double d);

/* 2. Flight condition. */
typedef struct lv_flight_air {
    double rho, p_amb, a_sound; /* kg/m^3, Pa, m/s (vacuum: 0, 0, 1) */
    double w_ned[3];            /* m/s, the wind (gusts, turbulence included): north, east, down */
    lv_vec3 v_air;              /* m/s, air-relative velocity, ECEF axes */
    double v_air_n;             /* m/s, its magnitude */
    double mach;                /* - */
    double q;                   /* Pa, dynamic pressure rho V^2 / 2 */
} lv_flight_air;

/* Aerothermal heating at the flight condition (docs/models.md, "Aerothermal heating"), W/m^2:
 * the stagnation point's convective heat flux of a sphere of nose radius r_n [m] by Sutton &
 * Graves (NASA TR R-376, 1971; the form q = k sqrt(rho / r_n) V^3 of Tauber, NASA TP-2914,
 * 1989, eq. 1, k in kg^0.5/m), and the free-molecular flux rho V^3 / 2 a surface normal to the
 * flow takes at full accommodation (the fairing-jettison criterion of launch vehicles' user's
 * manuals). V: the air-relative speed. */
static inline double lv_flight_heat_flux_sg(double k, double rho, double r_n, double v)
{
    return k * sqrt(rho / r_n) * v * v * v;
}
static inline double lv_flight_heat_flux_fm(double rho, double v) { return 0.5 * rho * v * v * v; }

/* Atmosphere at the geodetic altitude (above the model's top: vacuum with the top layer's
 * speed of sound; below its floor: the floor's values - the model's domain ends there), the
 * wind at the vehicle, Mach and q. Returns 0; 1 (state not acceptable: a NaN altitude, the
 * atmosphere model failed); or the wind function's nonzero code.
 * `err` (NULL in the hot path) receives the reason. */
int lv_flight_air_eval(const lv_flight_world *w, double t, const lv_flight_kin *k,
                       lv_flight_air *a, lv_err *err);

/* 3. Controls in effect. */
enum { LV_CTRL_ALPHA, LV_CTRL_BETA, LV_CTRL_MU, LV_CTRL_THROTTLE, LV_CTRL_N };

typedef struct lv_flight_controls {
    double u[LV_CTRL_N];    /* alpha, beta, mu [rad], throttle [1] */
    double cs[3][2];        /* cos, sin of alpha, beta, mu */
} lv_flight_controls;

/* A control history: a 1-axis table over time whose outputs replace the constants. */
typedef struct lv_flight_schedule {
    const lv_table *table;  /* NULL: constants only */
    int k[LV_CTRL_N];       /* output index for each control, -1: the constant */
    double *buf;            /* [n_out] scratch */
    int over;               /* lv_dof3_over: what the axis holds (the caller computes it) */
    double duration;        /* s: tau's, or NAN: stop_time - the start */
    double stop_time;       /* s */
} lv_flight_schedule;

/* The trigonometry of the angles is cached per instance: they change only with a table. */
typedef struct lv_flight_trig_cache {
    double ang[3];          /* angles of the cached values (NAN: none) */
    double cs[3][2];
} lv_flight_trig_cache;

/* u = the constants u0[LV_CTRL_N], replaced by the schedule's columns at time t; the cosines
 * and sines from the cache. Returns 0, or 1 when the table cannot be evaluated (err). */
int lv_flight_controls_eval(const double *u0, const lv_flight_schedule *sch,
                            lv_table_cursor *cur, lv_flight_trig_cache *cache, double t,
                            lv_flight_controls *c, lv_err *err);

/* 4. Vehicle forces. */
typedef struct lv_flight_axes {
    lv_vec3 xw, yw, zw; /* wind axes, ECEF components */
    lv_vec3 xb, yb, zb; /* body axes, ECEF components */
} lv_flight_axes;

/* m/s: below this air-relative speed the wind axes hold the start direction, and below this
 * horizontal air-relative speed (straight up or down) the start heading's vertical plane; the
 * flight models' speed guards (flight_model.h) use the same floor. */
#define LV_FLIGHT_V_GUARD 0.01

/* The downward unit normal z0 to the unit vector xw [ECEF] in the vertical plane through it
 * (the wind axes' z_w at mu = 0). The plane is undefined straight up or down; there it is the
 * start heading chi0's [rad from north]: when xw is the start direction itself (from_start)
 * within 1e-9 rad of the vertical, else when the horizontal part of the air-relative velocity,
 * v_air_n |xw x d| [m/s], is below LV_FLIGHT_V_GUARD. So a vertical start banks in the plane
 * the user gave, not in the plane of a Coriolis drift of nanometres per second. */
lv_vec3 lv_flight_down_normal(const lv_flight_kin *k, lv_vec3 xw, double v_air_n, int from_start,
                              double chi0);

/* Wind axes: x_w along the air-relative velocity; z_w in the vertical plane through it,
 * downwards, for mu = 0 (C_wind_ned = R1(mu) R2(gamma_a) R3(chi_a)); then the bank mu about
 * x_w. Below LV_FLIGHT_V_GUARD of air-relative speed x_w takes the start direction (fpa0,
 * chi0) [rad] in NED (a phase that starts at rest holds it until the air moves past it);
 * straight up or down, the plane is lv_flight_down_normal's. Body axes:
 * C_body_wind = R2(alpha) R3(-beta). */
void lv_flight_axes_eval(const lv_flight_kin *k, const lv_flight_air *a,
                         const lv_flight_controls *c, double fpa0, double chi0,
                         lv_flight_axes *ax);

/* Thrust [N] along body x and mass flow [kg/s] of the engines that burn (engines_on),
 * at throttle c->u[LV_CTRL_THROTTLE] and ambient pressure a->p_amb. Returns 0, or 1 when an
 * engine table cannot be evaluated (err). `buf` holds the largest engine table's outputs. */
int lv_flight_thrust(lv_engine *eng, size_t n_eng, int engines_on, double t,
                     const lv_flight_controls *c, const lv_flight_air *a, double *buf,
                     double *thrust, double *mdot, lv_err *err);

/* Aerodynamic force [N, ECEF] F = q S_ref C from the coefficients at (Mach, alpha, beta, h),
 * zero without air (q = 0) or without an aerodynamic set (aero NULL); coef[3] receives the
 * coefficients. Returns 0, or 1 when a table cannot be evaluated (err). */
int lv_flight_aero(lv_aero *aero, const lv_flight_kin *k, const lv_flight_air *a,
                   const lv_flight_controls *c, const lv_flight_axes *ax, double coef[3],
                   lv_vec3 *f_aero, lv_err *err);

/* 5. Translational equations of motion of a point of mass m [kg] under the force f [N, ECEF]:
 * a_ecef = g(r_ecef) + f/m (gravitation only: the rotation is handled by integrating in ECI),
 * returned rotated to ECI. `ws` is the gravity model's workspace; g_ecef receives g. */
lv_vec3 lv_flight_accel_eci(const lv_flight_world *w, double *ws, const lv_flight_kin *k,
                            lv_vec3 f, double m, lv_vec3 *g_ecef);
/* The same in two steps: gravity g(r_ecef) [m/s^2, ECEF], then a = g + f/m rotated to ECI. */
lv_vec3 lv_flight_gravity(const lv_flight_world *w, double *ws, const lv_flight_kin *k);
lv_vec3 lv_flight_accel_eci_g(const lv_flight_kin *k, lv_vec3 g_ecef, lv_vec3 f, double m);

/* The rotating frame's apparent acceleration [m/s^2, ECEF]: -2 w x v_rel - w x (w x r)
 * (Stevens & Lewis eq. 1.6-8): what an acceleration relative to the planet adds to the
 * inertial one. */
lv_vec3 lv_flight_frame_accel(const lv_flight_world *w, const lv_flight_kin *k);

/* d rho / dh [kg/m^4] of the world's atmosphere at geodetic altitude h where the density is
 * rho, by a forward difference over 1 cm (relative truncation error 1 cm / (2 H) ~ 1e-6 for a
 * scale height H of 7 km, rounding ~ 1e-10; one atmosphere evaluation); 0 without atmosphere
 * or outside its range. */
double lv_flight_drho_dh(const lv_flight_world *w, double h, double rho);

#endif
