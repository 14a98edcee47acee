/* flight_model.h - what the flight models over the planet (the 3-DoF point, dof3.c, and the
 * 6-DoF rigid body, dof6.c) share besides the right-hand side's pieces (flight.h): the
 * checks of a configuration's mass, the domain (the geodetic altitude above a floor), the
 * start from geodetic values (the paper's userPar), the propellant book and the start checks
 * of an instance, and the callbacks of lv_model_def that read only those: the state events
 * (event 0 the burnout, then the named ends of flight_ends.h) and their handler, the domain's
 * quantity, the time events of the inputs table, engines and steering law, the last error.
 *
 * A model's object holds an lv_flight_core (one literal once the model is built); its
 * instance block begins with an lv_flight_rt that points to it (lv_flight_def_callbacks), so
 * that the callbacks below take the instance as it is. */
#ifndef LV_DYNAMICS_FLIGHT_MODEL_H
#define LV_DYNAMICS_FLIGHT_MODEL_H

#include <stddef.h>

#include "core/status.h"
#include "core/units.h"
#include "dynamics/flight.h"
#include "dynamics/flight_ends.h"
#include "dynamics/guidance.h"
#include "lvsim/lv_model.h"

/* The model's parts the shared callbacks read (borrowed from the model's object). */
typedef struct lv_flight_core {
    const lv_flight_world *world; /* planet, gravity, atmosphere, wind */
    lv_flight_ends *fe;           /* burnout (event 0) and the named ends */
    size_t i_r, i_v, i_m;         /* states: ECI position and velocity (3 each), mass */
    const lv_table *inputs;       /* the inputs' table over time, or NULL */
    lv_engine *eng;               /* [n_eng]; their engine-out modes change at time events */
    size_t n_eng;
    const lv_guid *guid;          /* the steering law whose time events count, or NULL */
    int stop_at_burnout;          /* 1: burnout ends the phase; 0: engines off, go on */
    /* the domain (lv_flight_domain_init): what each bound guards */
    const lv_guid *law;           /* the steering law, "inputs" included: its references */
    int rolls;                    /* 1: the attitude is a state (6-DoF): commanded about the
                                     wind, its roll needs the vertical plane through it */
    size_t n_dom;
    int dom[3];                   /* lv_flight_guard of each bound */
    double ground_h;              /* m: the highest `impact` end's level, or NAN */
    int sat_events;               /* 1: the throttle's saturation events follow the ends'
                                     (lv_flight_add_sat_events) */
} lv_flight_core;

/* The bounds of a flight model's domain: where its equations hold and where the attitude its
 * steering law commands is defined (lv_flight_domain_init). */
typedef enum lv_flight_guard {
    LV_FGUARD_H,        /* geodetic altitude above the floor */
    LV_FGUARD_SPEED,    /* air-relative speed while thrusting along the wind (LV_GREF_WIND) */
    LV_FGUARD_VERTICAL  /* horizontal air-relative speed while a force normal to the wind acts
                           (or a 6-DoF attitude is held about it) */
} lv_flight_guard;

/* m: within this height above an `impact` end's level the guards are off: a touchdown at zero
 * speed (the landing law's default) or vertical is the impact's to end, not a lost reference */
#define LV_FLIGHT_GROUND_ZONE 1.0
/* m/s^2: a normal force below this acceleration (1e-4 g0) flipping at the vertical is no
 * chatter the guard needs to stop (a trace of lift as a landing stage settles) */
#define LV_FLIGHT_NORMAL_MIN (1e-4 * LV_G0)

/* The first member of a flight model's instance block. */
typedef struct lv_flight_rt {
    const lv_flight_core *core; /* NULL in a block lv_simulate zeroed itself */
    int engines_on;             /* mode: 1 while propellant remains */
    int burned_out;             /* the propellant is gone */
    double m_burnout;           /* kg: the start mass minus the burning stage's propellant */
    double r0_unit[3];          /* ECEF unit vector of the start point (downrange) */
    lv_guid_rt guid;            /* the steering law's start frame, cursors, trigonometry */
    double thrust_last;         /* N: the thrust of the latest right-hand side (the guards);
                                   -1 before the first (then engines_on tells) */
    int normal_last;            /* 1: a force normal to the air-relative velocity acted there */
    char msg[LV_ERR_MSG_MAX];   /* why the last callback failed */
    char tev[LV_EVENT_NAME_MAX]; /* the name of the latest time event */
} lv_flight_rt;

/* ---- construction ------------------------------------------------------------------------ */

/* The start mass m0 > 0 [kg] and the burning stage's propellant 0 <= propellant < m0 [kg];
 * LV_ERR_INPUT naming the model ("dof3: start mass m0 = -1 kg (must be > 0)") otherwise. */
lv_status lv_flight_check_mass(const char *model, double m0, double propellant, lv_err *err);
/* The heat flux outputs' nose radius (> 0, m) and Sutton-Graves constant (>= 0, kg^0.5/m),
 * both finite (lv_dof3_config). */
lv_status lv_flight_check_heating(const char *model, double nose_radius, double k_sg, lv_err *err);

/* The states both planet flight models put after the mass (lv_var entries): the heat loads,
 * the time integrals of the heat flux outputs below, J/m^2. Quadratures (their derivatives
 * lv_flight_heat_flux_sg, _fm; lv_model_def.quadrature): out of the error control, so they
 * never shrink a step; nominal 1 MJ/m^2 scales only the SUNDIALS methods' (negligible)
 * weight. A child phase starts from its parent's final heat loads (handed over by name, as the
 * mass): the loads accumulate over the body's flight; a root phase starts from 0. */
#define LV_FLIGHT_HEAT_LOAD_STATES                                                              \
    {"heat_load", "J/m2", "Stagnation-point heat load: the time integral of heat_flux", 0.0,    \
     1e6},                                                                                      \
    {"heat_load_fm", "J/m2", "Free-molecular heat load: the time integral of heat_flux_fm",    \
     0.0, 1e6}

/* The outputs both planet flight models end their tables with, in this order (lv_var
 * entries; their values: lv_flight_heat_flux_sg, lv_flight_heat_flux_fm of flight.h and
 * lv_flight_iip below): the heating and the instantaneous impact point. */
#define LV_FLIGHT_SAFETY_OUTPUTS                                                                \
    {"heat_flux", "W/m2", "Stagnation-point convective heat flux k sqrt(rho / r_n) V_air^3 "     \
     "(Sutton-Graves)", 0, 0},                                                                  \
    {"heat_flux_fm", "W/m2", "Free-molecular heat flux rho V_air^3 / 2", 0, 0},                \
    {"iip_lat", "rad", "Instantaneous impact point: geodetic latitude where the drag-free "     \
     "path meets the ellipsoid (NaN: no impact)", 0, 0},                                        \
    {"iip_lon", "rad", "Instantaneous impact point: longitude at the time of impact (NaN: no "  \
     "impact)", 0, 0},                                                                          \
    {"iip_tof", "s", "Instantaneous impact point: time of flight to it (NaN: no impact)", 0,   \
     0},                                                                                        \
    {"iip_range", "m", "Instantaneous impact point: great-circle distance from the point "     \
     "below the vehicle on the sphere of radius a (NaN: no impact)", 0, 0},

/* The wind outputs both planet flight models end their tables with (after the safety
 * outputs): lv_flight_air's w_ned. */
#define LV_FLIGHT_WIND_OUTPUTS                                                                  \
    {"wind_north", "m/s", "Wind at the vehicle (gusts and turbulence included): north", 0, 0}, \
    {"wind_east", "m/s", "Wind at the vehicle (gusts and turbulence included): east", 0, 0},   \
    {"wind_down", "m/s", "Wind at the vehicle (gusts and turbulence included): down", 0, 0},

/* The instantaneous impact point outputs of the ECI state (r_eci [m], v_eci [m/s]) at time t
 * [s] (dynamics/iip.h, lv_iip_propagate under the world's gravity model, workspace grav_ws, GM
 * gm): y[0] iip_lat, y[1] iip_lon [rad, geodetic], y[2] iip_tof [s], y[3] iip_range [m, great
 * circle on the sphere of radius a from the vehicle's ECEF direction r_ecef]; all four NAN
 * when the drag-free path does not meet the ellipsoid (docs/models.md). */
void lv_flight_iip(const lv_flight_world *w, double *grav_ws, double gm, double t,
                   const double r_eci[3], const double v_eci[3], const double r_ecef[3],
                   double y[4]);
/* The four IIP outputs y[0..3] when need (the model's outputs_some mask, NULL: all) asks for
 * one of them at need[i0..i0+3] (lv_flight_iip), else NaN: the propagation is the costliest
 * output of dof3 and dof6. */
void lv_flight_iip_if(const unsigned char *need, size_t i0, const lv_flight_world *w,
                      double *grav_ws, double gm, double t, const double r_eci[3],
                      const double v_eci[3], const double r_ecef[3], double y[4]);

/* The engines of a configuration: *eng = [n] initialised from engines[n] (lv_engine_init),
 * *n_eng the number initialised (also after an error, for the caller's free), *eng_buf
 * scratch for their tables; nothing when n = 0. LV_ERR_INPUT naming the model ("dof3:
 * n_engines = 2 but engines is NULL") or the engine, LV_ERR_NOMEM. */
lv_status lv_flight_engines_init(const char *model, const lv_engine_config *engines, size_t n,
                                 lv_engine **eng, size_t *n_eng, double **eng_buf, lv_err *err);

/* The domain of a model over the planet, into dom[3] and core->dom, core->n_dom (core->law
 * and core->rolls set): the geodetic altitude "h" above the atmosphere's floor (US76: -5 km),
 * or 20 km below the ellipsoid without an atmosphere (deeper than the lowest ground of the
 * Earth, Moon and Mars); then the guards of the references the steering law's attitude rests
 * on at some time of the phase (lv_guid_refs; each holds from above, LV_DOMAIN_OFF where it
 * does not apply):
 *   v_air >= LV_FLIGHT_V_GUARD while the attitude follows the wind and the engines thrust
 *     (the wind axes have no direction at zero air-relative speed: the thrust would flip);
 *   v_air_h >= LV_FLIGHT_V_GUARD, the horizontal part of the air-relative velocity, while the
 *     attitude follows the wind and a force normal to it acts (lift, thrust at an angle of
 *     attack) or a 6-DoF attitude is commanded about it: its bank's reference, the vertical
 *     plane through it, is undefined in vertical flight. For a 6-DoF this guard holds from
 *     the start too: a phase that starts at rest or vertical with its attitude commanded
 *     about the wind (and its engines on) is refused at once.
 * Within LV_FLIGHT_GROUND_ZONE above an `impact` end's level, not rising, the guards are off
 * (a landing; a launch from the ground keeps them).
 * Without the guards such a phase chatters about the undefined reference until the step
 * limit (issue 27): the force that flips drives the state back to where it flips. A law that
 * steers by the bearing to a target (boostback, heading) is not guarded over the target: the
 * vehicle flies through that point, its heading command jumps once, and the flight goes on;
 * one that circles back onto it again and again is stopped by the step-size collapse check
 * (integrator.h). */
void lv_flight_domain_init(lv_domain_def dom[3], lv_flight_core *core, int has_atmo);

/* The shared callbacks into def (with the events of core->fe: 1 + fe->n) and the domain
 * (core->n_dom quantities); rt (the model's instance template) reads core. */
void lv_flight_def_callbacks(lv_model_def *def, const lv_flight_core *core, lv_flight_rt *rt,
                             const lv_domain_def *domain);

/* An inputs table over time: one axis named "time" (or "t") in s. `model` prefixes the
 * messages. LV_ERR_INPUT otherwise. */
lv_status lv_flight_check_inputs_table(const char *model, const lv_table *tab, lv_err *err);

/* ---- an instance ------------------------------------------------------------------------ */

/* Records the reason in rt->msg; returns -1 (a callback's failure). */
int lv_flight_fail(lv_flight_rt *rt, const char *fmt, ...) LV_PRINTF(2, 3);

/* The start checks every flight model makes of its parameters: start_lat in [-pi/2, pi/2],
 * start_vel >= 0, propellant >= 0 [rad, m/s, kg]; 0, or -1 with the reason in rt->msg. */
int lv_flight_check_start(lv_flight_rt *rt, double lat, double vel, double prop);

/* A constant throttle c within every engine's limits; 0, or -1 with the reason. */
int lv_flight_check_throttle(lv_flight_rt *rt, double c);

/* The commanded throttle's saturation, two state events a flight model adds after its others
 * (dof3, dof6): the throttle a law, the inputs table or the attitude table commands leaves the
 * running engines' range [c_min, c_max] (direction -1) or comes back (+1). Logged, never an
 * end: a landing that asks for less than n T_min (or a schedule for more than n T_max) shows
 * where the engines could not follow (docs/guidance.md, "Saturation"); the model restarts the
 * integrator there (the clamp is a kink of the thrust). A constant throttle outside the range
 * is refused instead; where the throttle cannot vary the model keeps g constant (1). */
enum { LV_FLIGHT_SAT_MIN, LV_FLIGHT_SAT_MAX, LV_FLIGHT_SAT_N };
extern const lv_event_def lv_flight_sat_events[LV_FLIGHT_SAT_N];

/* Appends the two to def's events (after lv_flight_def_callbacks): a new array of them all,
 * which def->events points to and the caller frees; core->sat_events set, so that
 * lv_flight_on_event restarts the integrator where one fires. NULL when out of memory. */
lv_event_def *lv_flight_add_sat_events(lv_model_def *def, lv_flight_core *core);

/* Starts the two functions g[0], g[1] of a model's event function, after its other events
 * (their status rc): both constant 1, and returns 1 when they are to be computed from the
 * commanded throttle (rc 0, the throttle watched, the engines on, one of eng[n] running), 0
 * when they stay so. */
int lv_flight_sat_begin(int rc, int watch, const lv_flight_rt *rt, const lv_engine *eng, size_t n,
                        double *g);

/* g[0], g[1] of the two at commanded throttle c: below c_min (above c_max) by more than 1e-9,
 * so that a throttle held at the limit exactly (a schedule at throttle_min) is not saturated. */
void lv_flight_sat_g(double c, double c_min, double c_max, double *g);

/* ECI position r[3] [m] and velocity v[3] [m/s] at mission time t0 [s] of a vehicle at
 * geodetic lat, lon [rad], h [m] moving at `vel` [m/s] relative to the rotating planet with
 * flight-path angle fpa and heading chi [rad] (NED). */
void lv_flight_start_state(const lv_planet *pl, double lat, double lon, double h, double vel,
                           double fpa, double chi, double t0, double *r, double *v);

/* Its inverse, for the result files' records of a start set by a hand-off
 * (lv_model_def.start_params): g[6] = lat, lon [rad], h [m], vel [m/s], fpa, chi [rad] of the
 * ECI state r, v at t0, computed as the models' outputs h, lat, lon, v_rel, fpa, heading are
 * (exact geodetic), so the records equal the start row's outputs bit for bit. */
void lv_flight_start_geodetic(const lv_flight_world *w, double t0, const double *r,
                              const double *v, double g[6]);

/* The propellant book at the start: a positive mass m above the propellant `prop` [kg];
 * burnout when the propellant is gone, whatever else the mass carries; the engines on when
 * `engines` and prop > 0. 0, or -1 with the reason in rt->msg. */
int lv_flight_book(lv_flight_rt *rt, double m, double prop, int engines);

/* The downrange's origin (rt->r0_unit) at the ECI position r_eci at mission time t, and kin
 * its kinematics with the geodetic position. 0, or -1 with "<what> is the planet's centre"
 * in rt->msg. */
int lv_flight_origin(lv_flight_rt *rt, double t, const double r_eci[3], const double v_eci[3],
                     const char *what, lv_flight_kin *kin);

/* The instance's start at t0 from state x: a position away from the planet's centre (kin:
 * its kinematics with the geodetic position), the start point for the downrange, the named
 * ends' start (lv_flight_ends_start), every engine running with its engine-out instant
 * (lv_engine_start). 0, or -1 with the reason in rt->msg. */
int lv_flight_start(lv_flight_rt *rt, double t0, const double *x, lv_flight_kin *kin);

/* ---- the callbacks (lv_model_def; inst: an instance block beginning with lv_flight_rt) ---- */

int lv_flight_event_g(double t, const double *x, const double *p, double *g, void *inst);
lv_event_action lv_flight_on_event(double t, double *x, const double *p, const int *fired,
                                   void *inst);
int lv_flight_domain_q(double t, const double *x, const double *p, double *q, void *inst);
/* The guards' record of a right-hand side: its thrust [N] and total force f [N, any axes]
 * against the unit wind axis xw (same axes) on the mass [kg], for the domain's relevance
 * (lv_flight_domain_init): a normal force counts above LV_FLIGHT_NORMAL_MIN. */
void lv_flight_note_forces(lv_flight_rt *rt, double thrust, lv_vec3 f, lv_vec3 xw, double mass);
/* The state in words for failure messages (lv_model_def.describe): altitude, air-relative
 * speed and flight-path angle, heading, mass. */
void lv_flight_describe(double t, const double *x, const double *p, char *buf, size_t cap,
                        void *inst);
double lv_flight_next_time_event_cb(double t, const double *p, void *inst);
/* At a time event: the engines whose engine-out instant it is stop; a restart. */
lv_event_action lv_flight_on_time_event_cb(double t, double *x, const double *p, void *inst);
const char *lv_flight_time_event_name_cb(double t, const double *p, void *inst);
const char *lv_flight_last_error_cb(const void *inst);

#endif
