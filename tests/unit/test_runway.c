/* test_runway.c - the runway model (lv_runway.h) through lv_simulate against closed forms of
 * the ground roll, and the `runway` phase type in missions: parse errors at their line and
 * column, the hand-off to dof3 (the climb-out starts where the roll ended) and from dof3
 * (touchdown, then the roll-out). Each reference is derived or cited next to its check.
 *
 * The closed-form cases fly on a non-rotating sphere 10^4 times the Earth's radius with
 * surface gravity g: a straight runway of a few km there rises s^2 / (2 R) < 1e-4 m and tilts
 * by s / R < 1e-7 rad, so gravity is uniform and normal to the runway to that level, as the
 * textbook ground roll assumes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mat_records.h"
#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_io.h"
#include "lvsim/lv_mission.h"
#include "lvsim/lv_planet.h"
#include "lvsim/lv_runway.h"
#include "lvsim/lv_sim.h"
#include "mission/mission.h"

#define DEG (M_PI / 180.0)

static const double G = 9.81, R_BIG = 6.4e10;

typedef struct world {
    lv_planet planet;
    lv_gravity *grav;
} world;

static void world_big(world *w)
{
    lv_err err;
    w->planet = (lv_planet){"bigsphere", R_BIG, 0.0, G * R_BIG * R_BIG, 0.0, 0.0, R_BIG,
                            0.0, 0.0, 0.0};
    lv_gravity_config gc = {"pointmass", 0, -1, NULL};
    w->grav = NULL;
    CHECK_OK(lv_gravity_create(&w->planet, &gc, &w->grav, &err), &err);
}

/* One run to the end: finals by name into out[]; rep may be NULL. */
static lv_status run(lv_runway *m, double tf, size_t n_fin, const char *const *fin, double *out,
                     lv_sim_report *rep, lv_err *err)
{
    lv_sim_settings s;
    lv_sim_settings_default(&s);
    s.result_file = NULL;
    s.start_time = 0.0;
    s.stop_time = tf;
    s.method = "dassl";
    s.tolerance = 1e-10;
    s.output_interval = 1.0;
    s.n_final = n_fin;
    s.final_names = fin;
    return lv_simulate(lv_runway_def(m), lv_runway_inst(m), &s, out, rep, err);
}

/* A constant engine with a negligible mass flow (Isp 10^12 s: the mass changes by 1e-8
 * relative over the roll), so that the closed forms for a constant mass hold. */
static lv_engine_config engine(double thrust)
{
    lv_engine_config e;
    lv_engine_config_default(&e);
    e.name = "main";
    e.thrust_vac = thrust;
    e.isp_vac = 1e12;
    return e;
}

/* ---- (1) constant thrust and rolling friction, no air ----------------------------------- */
/* m dV/dt = T - mu m g (Raymer, Aircraft Design, 6th ed., eq. 17.95 with D = L = 0):
 * V(t) = (T/m - mu g) t, s(t) = V^2 / (2 a); the speed end at V_e comes at t = V_e / a. */
static void test_friction_no_air(void)
{
    lv_err err;
    world w;
    world_big(&w);
    const double T = 2.0e5, m0 = 1.0e5, mu = 0.03, ve = 60.0;
    const lv_engine_config e = engine(T);
    const lv_runway_end end = {"v60", ve, LV_DIR_RISING};
    lv_runway_config cfg;
    lv_runway_config_default(&cfg);
    cfg.planet = w.planet;
    cfg.gravity = w.grav;
    cfg.m0 = m0;
    cfg.propellant = 1000.0;
    cfg.n_engines = 1;
    cfg.engines = &e;
    cfg.mu = mu;
    cfg.runway_lat = 30.0 * DEG;
    cfg.runway_heading = 70.0 * DEG;
    cfg.n_ends = 1;
    cfg.ends = &end;
    lv_runway *m = NULL;
    CHECK_OK(lv_runway_create(&cfg, &m, &err), &err);
    const char *fin[] = {"time", "distance", "speed", "normal_force", "friction", "h"};
    double out[6];
    lv_sim_report rep;
    memset(&rep, 0, sizeof rep);
    CHECK_OK(run(m, 100.0, 6, fin, out, &rep, &err), &err);
    const double a = T / m0 - mu * G;
    CHECK(rep.reason == LV_STOP_EVENT);
    CHECK_REL(out[0], ve / a, 1e-7);
    CHECK_REL(out[1], ve * ve / (2.0 * a), 1e-7);
    CHECK_REL(out[2], ve, 1e-9);
    CHECK_REL(out[3], m0 * G, 1e-7);         /* N = W without lift */
    CHECK_REL(out[4], mu * m0 * G, 1e-7);
    CHECK_CLOSE(out[5], 0.0, 1e-3);           /* the runway stays on the ground */
    lv_sim_report_clear(&rep);
    lv_runway_free(m);

    /* thrust below the friction limit: static friction holds the vehicle at rest */
    lv_engine_config weak = engine(0.5 * mu * m0 * G);
    cfg.engines = &weak;
    cfg.n_ends = 0;
    CHECK_OK(lv_runway_create(&cfg, &m, &err), &err);
    CHECK_OK(run(m, 10.0, 6, fin, out, NULL, &err), &err);
    CHECK_CLOSE(out[1], 0.0, 1e-9);
    CHECK_CLOSE(out[2], 0.0, 1e-9);
    CHECK_REL(out[4], 0.5 * mu * m0 * G, 1e-7); /* friction = the drive */
    lv_runway_free(m);
    lv_gravity_free(w.grav);
}

/* ---- (2) with drag and lift at constant coefficients -------------------------------------- */
/* m dV/dt = A - k V^2 with A = T - mu m g and k = rho S (CD - mu CL) / 2 (the lift unloads the
 * wheels): V(t) = sqrt(A/k) tanh(sqrt(A k) t / m) (a Riccati equation with constant
 * coefficients; e.g. Anderson, Aircraft Performance and Design, sec. 6.7). The distance to
 * reach V_f is Raymer's ground roll (6th ed., eq. 17.101):
 *   S_G = 1 / (2 g K_A) ln((K_T + K_A V_f^2) / (K_T + K_A V_i^2)),
 *   K_T = T/W - mu,  K_A = rho / (2 W/S) (mu CL - CD),
 * checked here from V_i = 0, independently of the time solution. */
static void test_drag_closed_form(void)
{
    lv_err err;
    world w;
    world_big(&w);
    lv_atmo *atmo = NULL;
    CHECK_OK(lv_atmo_create("exp", &atmo, &err), &err);
    const double rho = 1.2;
    CHECK_OK(lv_atmo_set(atmo, "rho0", rho, &err), &err);
    const double T = 3.0e5, m0 = 1.0e5, mu = 0.04, S = 200.0, CD = 0.08, CL = 0.25, vf = 80.0;
    const lv_engine_config e = engine(T);
    lv_aero_config aero;
    lv_aero_config_default(&aero);
    aero.s_ref = S;
    aero.coef[0].value = CD;
    aero.coef[1].value = CL;
    const lv_runway_end end = {"vf", vf, LV_DIR_RISING};
    lv_runway_config cfg;
    lv_runway_config_default(&cfg);
    cfg.planet = w.planet;
    cfg.gravity = w.grav;
    cfg.atmo = atmo;
    cfg.aero = &aero;
    cfg.m0 = m0;
    cfg.propellant = 1000.0;
    cfg.n_engines = 1;
    cfg.engines = &e;
    cfg.mu = mu;
    cfg.n_ends = 1;
    cfg.ends = &end;
    lv_runway *m = NULL;
    CHECK_OK(lv_runway_create(&cfg, &m, &err), &err);
    const char *fin[] = {"time", "distance", "speed", "normal_force", "lift", "drag"};
    double out[6];
    CHECK_OK(run(m, 200.0, 6, fin, out, NULL, &err), &err);
    const double A = T - mu * m0 * G, k = 0.5 * rho * S * (CD - mu * CL);
    const double t_ref = m0 / sqrt(A * k) * atanh(vf / sqrt(A / k)); /* V(t_ref) = vf */
    const double W = m0 * G, KT = T / W - mu, KA = rho / (2.0 * W / S) * (mu * CL - CD);
    const double sg = 1.0 / (2.0 * G * KA) * log((KT + KA * vf * vf) / KT);
    CHECK_REL(out[0], t_ref, 1e-7);
    CHECK_REL(out[1], sg, 1e-7);
    const double q = 0.5 * rho * vf * vf;
    CHECK_REL(out[4], q * S * CL, 1e-8); /* at the event located to the tolerance */
    CHECK_REL(out[5], q * S * CD, 1e-8);
    CHECK_REL(out[3], W - q * S * CL, 1e-7);
    lv_runway_free(m);
    lv_atmo_free(atmo);
    lv_gravity_free(w.grav);
}

/* ---- (3) lift-off speed from the wing loading ---------------------------------------------- */
/* With the angle of attack constant (no rotation: alpha_rot = alpha_ground = 0, so the thrust
 * has no normal part) and CL constant, the wheels unload when the lift equals the weight:
 * V_LO = sqrt(2 (W/S) / (rho CL)) (the stall-speed relation, Anderson, Introduction to
 * Flight, eq. 6.81, at the lift coefficient flown). The phase ends there by itself. */
static void test_liftoff_speed(void)
{
    lv_err err;
    world w;
    world_big(&w);
    lv_atmo *atmo = NULL;
    CHECK_OK(lv_atmo_create("exp", &atmo, &err), &err);
    const double rho = 1.1;
    CHECK_OK(lv_atmo_set(atmo, "rho0", rho, &err), &err);
    const double T = 4.0e5, m0 = 1.2e5, S = 400.0, CL = 0.6;
    const lv_engine_config e = engine(T);
    lv_aero_config aero;
    lv_aero_config_default(&aero);
    aero.s_ref = S;
    aero.coef[0].value = 0.05;
    aero.coef[1].value = CL;
    lv_runway_config cfg;
    lv_runway_config_default(&cfg);
    cfg.planet = w.planet;
    cfg.gravity = w.grav;
    cfg.atmo = atmo;
    cfg.aero = &aero;
    cfg.m0 = m0;
    cfg.propellant = 1000.0;
    cfg.n_engines = 1;
    cfg.engines = &e;
    cfg.mu = 0.02;
    lv_runway *m = NULL;
    CHECK_OK(lv_runway_create(&cfg, &m, &err), &err);
    const char *fin[] = {"speed", "normal_force", "lift_margin"};
    double out[3];
    lv_sim_report rep;
    memset(&rep, 0, sizeof rep);
    CHECK_OK(run(m, 300.0, 3, fin, out, &rep, &err), &err);
    CHECK(rep.reason == LV_STOP_EVENT && rep.stop_event == 2); /* liftoff */
    CHECK_REL(out[0], sqrt(2.0 * m0 * G / (rho * S * CL)), 1e-7);
    CHECK_CLOSE(out[1], 0.0, 1e-3 * m0 * G * 1e-6);
    CHECK_REL(out[2], 1.0, 1e-7);
    lv_sim_report_clear(&rep);
    lv_runway_free(m);

    /* rotation to alpha_rot at a finite rate: before v_rot alpha is alpha_ground; after,
     * alpha = alpha_ground + rate (t - t_rot) until alpha_rot. Without air the rotation
     * speed is reached at t_rot = v_rot / (T/m - mu g) (case 1), so at the end
     * (a speed end at 1.2 v_rot, reached before the rotation is complete) the angle is
     * rate (t_end - t_rot). */
    const lv_runway_end end = {"v_end", 36.0, LV_DIR_RISING};
    cfg.atmo = NULL;
    cfg.aero = NULL;
    cfg.v_rot = 30.0;
    cfg.alpha_ground = 0.0;
    cfg.alpha_rot = 20.0 * DEG;
    cfg.rotation_rate = 2.0 * DEG;
    cfg.n_ends = 1;
    cfg.ends = &end;
    CHECK_OK(lv_runway_create(&cfg, &m, &err), &err);
    const char *fin2[] = {"time", "alpha_in", "rotating"};
    memset(&rep, 0, sizeof rep);
    CHECK_OK(run(m, 300.0, 3, fin2, out, &rep, &err), &err);
    const double t_rot = 30.0 / (T / m0 - 0.02 * G);
    CHECK(out[2] == 1.0);
    CHECK(out[1] < 20.0 * DEG);
    CHECK_REL(out[1], 2.0 * DEG * (out[0] - t_rot), 1e-6);
    CHECK(rep.n_event_log >= 2); /* rotation, then the end */
    lv_sim_report_clear(&rep);
    lv_runway_free(m);
    lv_atmo_free(atmo);
    lv_gravity_free(w.grav);
}

/* ---- (4) landing roll-out: braking friction, engines off ----------------------------------- */
/* m dV/dt = -mu_b m g: V(t) = V0 - mu_b g t; the stop speed v_s comes at
 * t = (V0 - v_s) / (mu_b g) after (V0^2 - v_s^2) / (2 mu_b g) (uniform deceleration). */
static void test_landing_rollout(void)
{
    lv_err err;
    world w;
    world_big(&w);
    const double V0 = 85.0, mu = 0.35, vs = 2.0, s0 = 250.0;
    const lv_engine_config e = engine(1e6); /* ignored: the roll-out has its engines off */
    lv_runway_config cfg;
    lv_runway_config_default(&cfg);
    cfg.planet = w.planet;
    cfg.gravity = w.grav;
    cfg.mode = LV_RUNWAY_LANDING;
    cfg.m0 = 5.0e4;
    cfg.n_engines = 1;
    cfg.engines = &e;
    cfg.mu = mu;
    cfg.v_stop = vs;
    cfg.start_speed = V0;
    cfg.start_distance = s0;
    lv_runway *m = NULL;
    CHECK_OK(lv_runway_create(&cfg, &m, &err), &err);
    const char *fin[] = {"time", "distance", "speed", "thrust", "m"};
    double out[5];
    lv_sim_report rep;
    memset(&rep, 0, sizeof rep);
    CHECK_OK(run(m, 100.0, 5, fin, out, &rep, &err), &err);
    CHECK(rep.reason == LV_STOP_EVENT && rep.stop_event == 2); /* stop */
    CHECK_REL(out[0], (V0 - vs) / (mu * G), 1e-7);
    CHECK_REL(out[1], s0 + (V0 * V0 - vs * vs) / (2.0 * mu * G), 1e-7);
    CHECK_CLOSE(out[3], 0.0, 0.0);
    CHECK_CLOSE(out[4], 5.0e4, 0.0);
    lv_sim_report_clear(&rep);
    lv_runway_free(m);
    lv_gravity_free(w.grav);
}

/* ---- (5) on the rotating Earth: the threshold at rest ------------------------------------- */
/* At rest on the threshold, the ECI state the model hands to dof3 is the geodetic point
 * turned to ECEF (docs/frames.md F4) and ECI at t (F2, F3: v_eci = w x r), computed here with
 * the frame functions; the normal force is the weight in the rotating frame, m |g + w x (w x
 * r)| . up, between m g_pole and m g_equator of the WGS-84 normal gravity (9.78-9.83). */
static void test_rotating_threshold(void)
{
    lv_err err;
    const lv_planet earth = lv_planet_earth();
    lv_gravity_config gc = {"j2", 0, -1, NULL};
    lv_gravity *grav = NULL;
    CHECK_OK(lv_gravity_create(&earth, &gc, &grav, &err), &err);
    lv_runway_config cfg;
    lv_runway_config_default(&cfg);
    cfg.gravity = grav;
    cfg.m0 = 1000.0;
    cfg.runway_lat = 43.6 * DEG;
    cfg.runway_lon = 1.37 * DEG;
    cfg.runway_h = 150.0;
    cfg.runway_heading = 140.0 * DEG;
    cfg.start_time = 0.0;
    lv_runway *m = NULL;
    CHECK_OK(lv_runway_create(&cfg, &m, &err), &err);
    const char *fin[] = {"r_eci_x", "r_eci_y", "r_eci_z", "v_eci_x", "v_eci_y", "v_eci_z",
                         "normal_force", "h", "lat", "lon"};
    double out[10];
    lv_sim_settings s;
    lv_sim_settings_default(&s);
    s.result_file = NULL;
    s.start_time = 100.0;
    s.stop_time = 100.5;
    s.n_final = 10;
    s.final_names = fin;
    CHECK_OK(lv_simulate(lv_runway_def(m), lv_runway_inst(m), &s, out, NULL, &err), &err);
    double r_ecef[3], zero[3] = {0, 0, 0}, r_eci[3], v_eci[3];
    lv_frames_geodetic_to_ecef(&earth, cfg.runway_lat, cfg.runway_lon, 150.0, r_ecef);
    lv_frames_ecef_to_eci(&earth, 100.5, r_ecef, zero, r_eci, v_eci);
    for (int i = 0; i < 3; i++) {
        CHECK_CLOSE(out[i], r_eci[i], 1e-6);
        CHECK_CLOSE(out[3 + i], v_eci[i], 1e-9);
    }
    CHECK_CLOSE(out[7], 150.0, 1e-6);
    CHECK_CLOSE(out[8], cfg.runway_lat, 1e-12);
    CHECK(out[6] > 1000.0 * 9.78 && out[6] < 1000.0 * 9.835);
    lv_runway_free(m);
    lv_gravity_free(grav);
}

/* ---- (6) bad configurations ------------------------------------------------------------------ */
static void test_bad_config(void)
{
    lv_err err;
    world w;
    world_big(&w);
    lv_runway_config cfg;
    lv_runway *m = NULL;
#define BADCFG(field, value, needle)                                                       \
    do {                                                                                    \
        lv_runway_config_default(&cfg);                                                     \
        cfg.planet = w.planet;                                                              \
        cfg.gravity = w.grav;                                                               \
        cfg.field = value;                                                                  \
        CHECK_FAILS(lv_runway_create(&cfg, &m, &err), &err, LV_ERR_INPUT, needle);          \
        CHECK(m == NULL);                                                                   \
    } while (0)
    BADCFG(mu, -0.1, "mu = -0.1");
    BADCFG(v_rot, 0.0, "v_rot = 0");
    BADCFG(alpha_rot, -1.0 * DEG, "alpha_rot");
    BADCFG(rotation_rate, -1.0, "rotation_rate");
    BADCFG(m0, 0.0, "m0 = 0");
    BADCFG(start_speed, -1.0, "start_speed = -1");
    BADCFG(runway_lat, 2.0, "runway_lat = 2");
    BADCFG(gravity, NULL, "no gravity");
    lv_runway_config_default(&cfg);
    cfg.planet = w.planet;
    cfg.gravity = w.grav;
    cfg.mode = LV_RUNWAY_LANDING;
    cfg.v_stop = 0.0;
    CHECK_FAILS(lv_runway_create(&cfg, &m, &err), &err, LV_ERR_INPUT, "v_stop = 0");
    lv_gravity_free(w.grav);
#undef BADCFG
}

/* ---- (7) missions: parse errors, hand-offs ----------------------------------------------------- */

#define BAD(yaml, want) bad_((yaml), (want), __LINE__)
static void bad_(const char *yaml, const char *want, int line)
{
    lv_err err = {LV_OK, ""};
    lv_mission_def *m = NULL;
    lv_status st = lv_mission_def_parse(yaml, strlen(yaml), "bad.yaml", ".", &m, &err);
    check_count_++;
    if (st != LV_ERR_INPUT || m != NULL || strncmp(err.msg, want, strlen(want)) != 0) {
        check_failures_++;
        fprintf(stderr, "%s:%d: expected LV_ERR_INPUT \"%s...\",\n    got %d \"%s\"\n", __FILE__,
                line, want, (int)st, err.msg);
    }
    lv_mission_def_free(m);
}

#define HEAD                                                                                \
    "mission: {name: rw}\n"                                                                 \
    "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}\n"          \
    "stages:\n"                                                                             \
    "  - {name: ms, dry_mass: 50000, propellant_mass: 100000,\n"                            \
    "     engines: [{name: e, thrust_vac: 2.0e6, isp_vac: 350, exit_area: 1.5}]}\n"         \
    "phases:\n"

static void test_mission_errors(void)
{
    BAD(HEAD "  - {name: P, model: runway, stages: [ms], stop_time: 60,\n"
             "     takeoff: {mu: 0.02, v_rot: 90, alpha_rot_deg: 8}}\n",
        "bad.yaml:7:5: phase 'P': a runway phase needs `runway:");
    BAD(HEAD "  - {name: P, model: runway, stages: [ms], stop_time: 60,\n"
             "     runway: {lat_deg: 43, lon_deg: 1, elevation: 150, heading_deg: 90}}\n",
        "bad.yaml:7:5: phase 'P': a runway phase needs `takeoff:");
    BAD(HEAD "  - {name: P, model: runway, stages: [ms], stop_time: 60,\n"
             "     runway: {lat_deg: 43, lon_deg: 1, elevation: 150},\n"
             "     takeoff: {mu: 0.02, v_rot: 90, alpha_rot_deg: 8}}\n",
        "bad.yaml:8:14: phase 'P', runway: 'heading_deg' is missing");
    BAD(HEAD "  - {name: P, model: runway, stages: [ms], stop_time: 60,\n"
             "     runway: {lat_deg: 43, lon_deg: 1, elevation: 150, heading_deg: 90},\n"
             "     takeoff: {mu: 0.02, v_rot: 90, alpha_rot_deg: 8},\n"
             "     landing: {mu: 0.3, v_stop: 1}}\n",
        "bad.yaml:10:6: phase 'P': `takeoff` and `landing` given both");
    BAD(HEAD "  - {name: P, model: runway, stages: [ms], stop_time: 60,\n"
             "     runway: {lat_deg: 43, lon_deg: 1, elevation: 150, heading_deg: 90},\n"
             "     takeoff: {mu: 0.02, v_rot: -5, alpha_rot_deg: 8}}\n",
        "bad.yaml:9:33: phase 'P', takeoff: v_rot must be > 0");
    BAD(HEAD "  - {name: P, model: runway, stages: [ms], stop_time: 60,\n"
             "     runway: {lat_deg: 43, lon_deg: 1, elevation: 150, heading_deg: 90},\n"
             "     takeoff: {mu: 0.02, v_rot: 90, alpha_rot_deg: 8, v_stop: 3}}\n",
        "bad.yaml:9:55: phase 'P', takeoff: unknown key 'v_stop'");
    BAD(HEAD "  - {name: P, model: runway, stages: [ms], stop_time: 60, end: [apogee],\n"
             "     runway: {lat_deg: 43, lon_deg: 1, elevation: 150, heading_deg: 90},\n"
             "     takeoff: {mu: 0.02, v_rot: 90, alpha_rot_deg: 8}}\n",
        "bad.yaml:7:65: phase 'P': end 'apogee': a runway phase rolls on the ground");
    BAD(HEAD "  - {name: P, model: runway, stages: [ms], stop_time: 60,\n"
             "     runway: {lat_deg: 43, lon_deg: 1, elevation: 150, heading_deg: 90},\n"
             "     takeoff: {mu: 0.02, v_rot: 90, alpha_rot_deg: 8}}\n"
             "  - {name: Q, model: runway, stages: [ms], from: P, stop_time: 90,\n"
             "     runway: {lat_deg: 43, lon_deg: 1, elevation: 150, heading_deg: 90},\n"
             "     landing: {mu: 0.3, v_stop: 1, start_speed: 50}}\n",
        "bad.yaml:12:36: phase 'Q', landing: 'start_speed': a phase with `from`");
    /* issue 27 (M4): a constant take-off throttle outside the engines' range [0, 1], at the
     * value */
    BAD(HEAD "  - {name: P, model: runway, stages: [ms], stop_time: 60,\n"
             "     runway: {lat_deg: 43, lon_deg: 1, elevation: 150, heading_deg: 90},\n"
             "     takeoff: {mu: 0.02, v_rot: 90, alpha_rot_deg: 8, throttle: 1.2}}\n",
        "bad.yaml:9:65: phase 'P': takeoff: throttle = 1.2 is outside the throttle range [0, 1] "
        "of engine 'e' (stage 'ms')");
}

/* A take-off roll, the climb-out (dof3) from it, and from a glide down to the runway's
 * elevation (dof3, impact at the elevation) a roll-out: every hand-off continuous. */
static void test_mission_handoffs(void)
{
    /* the glide touches down at ~150 m/s sinking at ~38 m/s (a crash): the roll-out's
     * mechanics are the subject here, so the stage's gear takes it (the limits:
     * test_gear_limits) */
    const char *yaml =
        "mission: {name: rw}\n"
        "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}\n"
        "stages:\n"
        "  - {name: ms, dry_mass: 50000, propellant_mass: 100000,\n"
        "     landing_gear: {sink_rate_max: 50, lateral_speed_max: 20, ground_speed_max: 300,\n"
        "                    bank_max_deg: 90, pitch_min_deg: -90, pitch_max_deg: 90},\n"
        "     engines: [{name: e, thrust_vac: 2.0e6, isp_vac: 350, exit_area: 1.5}]}\n"
        "phases:\n"
        "  - {name: roll, model: runway, stages: [ms], start_time: 0, stop_time: 60,\n"
        "     runway: {lat_deg: 43.6, lon_deg: 1.37, elevation: 150, heading_deg: 140},\n"
        "     takeoff: {mu: 0.02, v_rot: 90, alpha_rot_deg: 10, rotation_rate_deg: 3},\n"
        "     aero: {s_ref: 300, CD: 0.05, CL: 0.5}}\n"
        "  - {name: climb, model: dof3, stages: [ms], from: roll, stop_time: 90,\n"
        "     end: [{altitude: 200, direction: rising}],\n"
        "     guidance: {law: attitude, pitch_deg: 8, heading_deg: 140},\n"
        "     aero: {s_ref: 300, CD: 0.05, CL: 0.5}}\n"
        "  - {name: down, model: dof3, stages: [ms], from: climb, stop_time: 300,\n"
        "     end: [{altitude: 150, direction: falling}], throttle: off,\n"
        "     inputs: {alpha_deg: 2}, aero: {s_ref: 300, CD: 0.05, CL: 0.1}}\n"
        "  - {name: rollout, model: runway, stages: [ms], from: down, stop_time: 500,\n"
        "     runway: {lat_deg: 43.6, lon_deg: 1.37, elevation: 150, heading_deg: 140},\n"
        "     landing: {mu: 0.3, v_stop: 2}}\n";
    const char *path = "test_runway_handoff.yaml";
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (f == NULL)
        return;
    fputs(yaml, f);
    fclose(f);
    lv_err err;
    lv_mission *m = NULL;
    CHECK_OK(lv_mission_load(path, &m, &err), &err);
    if (m == NULL)
        return;
    lv_run *r = NULL;
    CHECK_OK(lv_run_create(m, &r, &err), &err);
    lv_run_options opt = {.outdir = "rw_handoff_out", .threads = 2};
    CHECK_OK(lv_run_execute(r, &opt, &err), &err);
    const char *st[] = {"r_eci_x", "r_eci_y", "r_eci_z", "v_eci_x", "v_eci_y", "v_eci_z", "m"};
    /* roll -> climb: the climb's first row is the roll's last, exactly */
    const lv_result *climb = lv_run_rows(r, 1);
    CHECK(climb != NULL && lv_result_rows(climb) > 0);
    for (int i = 0; climb != NULL && i < 7; i++) {
        double fv;
        size_t col = 0;
        CHECK_OK(lv_run_final(r, 0, st[i], &fv, &err), &err);
        CHECK_OK(lv_result_column(climb, st[i], &col, &err), &err);
        CHECK_CLOSE(lv_result_value(climb, 0, col), fv, 0.0);
    }
    const lv_phase_result *p0 = lv_run_result(r, 0);
    CHECK(p0->report.reason == LV_STOP_EVENT); /* liftoff, not the time limit */
    /* down -> rollout: the roll-out starts at the touchdown's ground speed along the runway */
    double v_td, fpa_td, hd_td, t_end;
    CHECK_OK(lv_run_final(r, 2, "v_rel", &v_td, &err), &err);
    CHECK_OK(lv_run_final(r, 2, "fpa", &fpa_td, &err), &err);
    CHECK_OK(lv_run_final(r, 2, "heading", &hd_td, &err), &err);
    const lv_result *ro = lv_run_rows(r, 3);
    size_t cv = 0;
    CHECK(ro != NULL);
    CHECK_OK(lv_result_column(ro, "speed", &cv, &err), &err);
    const double v0 = lv_result_value(ro, 0, cv);
    /* the horizontal speed along the runway: v cos(fpa) cos(heading - runway heading), to the
     * runway plane's tilt over the distance flown (~1e-3 rad) */
    CHECK_REL(v0, v_td * cos(fpa_td) * cos(hd_td - 140.0 * DEG), 2e-3);
    /* what the touchdown absorbed, recorded in the roll-out's result: the sink rate is the
     * parent's descent rate -v sin(fpa) and the lateral speed v cos(fpa) sin(heading - 140
     * deg), both to the plane's tilt (~1e-3 rad of v ~ 1e-1 m/s); the height above the plane
     * is the parent's final altitude (150 m, the runway's elevation) minus the plane's drop
     * d^2 / (2 R) below the ellipsoid over the distance d flown (< 5 m for d < 8 km) */
    const lv_phase_result *p3 = lv_run_result(r, 3);
    CHECK(p3->n_absorbed == 8); /* and distance, ground_speed, pitch, bank */
    double ab[4] = {NAN, NAN, NAN, NAN};
    const char *abn[4] = {"height", "sink_rate", "lateral", "lateral_speed"};
    for (size_t i = 0; i < p3->n_absorbed; i++)
        for (int j = 0; j < 4; j++)
            if (strcmp(p3->absorbed_names[i], abn[j]) == 0)
                ab[j] = p3->absorbed_values[i];
    CHECK(fabs(ab[0]) < 5.0);
    CHECK(-v_td * sin(fpa_td) > 1.0); /* it descends */
    CHECK_CLOSE(ab[1], -v_td * sin(fpa_td), 0.15);
    CHECK(fabs(ab[2]) < 60.0);
    CHECK_CLOSE(ab[3], v_td * cos(fpa_td) * sin(hd_td - 140.0 * DEG), 0.15);
    CHECK(lv_run_result(r, 1)->n_absorbed == 0); /* a lift-off absorbs nothing */
    CHECK_OK(lv_run_final(r, 3, "speed", &t_end, &err), &err);
    CHECK_CLOSE(t_end, 2.0, 1e-6);
    CHECK(lv_run_result(r, 3)->report.reason == LV_STOP_EVENT);
    /* Issue 27 (M3): each child's .mat records its own start. The climb (dof3 from the roll)
     * starts from the roll's final state: its start_* are the roll's last row's h, lat, lon,
     * v_rel, fpa, heading (the same geodetic of the same ECI state, to round-off), not the
     * mission's parameters (it has none of start_h ...: 0); the roll-out (runway from the
     * glide) starts at the touchdown's projection: start_distance, start_speed are its first
     * row's states, start_time the glide's end. */
    {
        char mat[512];
        snprintf(mat, sizeof mat, "%s.mat", lv_run_result(r, 1)->result_stem);
        const char *par[] = {"start_lat", "start_lon", "start_h", "start_vel", "start_fpa",
                             "start_chi"};
        const char *out[] = {"lat", "lon", "h", "v_rel", "fpa", "heading"};
        for (int i = 0; i < 6; i++) {
            double rec = NAN, want = NAN;
            CHECK(mat_param(mat, par[i], &rec) == 0);
            CHECK_OK(lv_run_final(r, 0, out[i], &want, &err), &err);
            CHECK_CLOSE(rec, want, 1e-9 * fmax(1.0, fabs(want)));
        }
        double h0 = NAN;
        CHECK(mat_param(mat, "start_h", &h0) == 0 && h0 > 140.0); /* the runway's 150 m */
        snprintf(mat, sizeof mat, "%s.mat", lv_run_result(r, 3)->result_stem);
        const char *rs[] = {"distance", "speed"}, *rp[] = {"start_distance", "start_speed"};
        for (int i = 0; ro != NULL && i < 2; i++) {
            double rec = NAN;
            size_t col = 0;
            CHECK(mat_param(mat, rp[i], &rec) == 0);
            CHECK_OK(lv_result_column(ro, rs[i], &col, &err), &err);
            CHECK(rec == lv_result_value(ro, 0, col));
        }
        double s0 = NAN, t0 = NAN;
        CHECK(mat_param(mat, "start_speed", &s0) == 0 && s0 > 10.0); /* not the default 0 */
        CHECK(mat_param(mat, "start_time", &t0) == 0 && t0 == lv_run_result(r, 2)->t_end);
    }
    lv_run_free(r);
    lv_mission_free(m);
    remove(path);
}

/* Writes yaml to path and loads it: the mission, or NULL with err. */
static lv_mission *load_text(const char *path, const char *yaml, lv_err *err)
{
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (f == NULL)
        return NULL;
    fputs(yaml, f);
    fclose(f);
    lv_mission *m = NULL;
    if (lv_mission_load(path, &m, err) != LV_OK)
        return NULL;
    return m;
}

#define ROLL_RUNWAY "     runway: {lat_deg: 43.6, lon_deg: 1.37, elevation: 150, heading_deg: 140},\n"

/* The roll's edges: a vehicle that never lifts off hands nothing to a flight phase; one that
 * is flying at the start is not held on the runway; an aborted take-off (burnout before
 * lift-off) ends at rest; a take-off roll does not start from a flight phase. */
static void test_mission_edges(void)
{
    lv_err err;
    /* thrust 2 MN on 150 t, no lift: it never lifts off; the roll ends at its time limit */
    lv_mission *m = load_text("rw_edges.yaml",
        HEAD "  - {name: roll, model: runway, stages: [ms], stop_time: 20,\n" ROLL_RUNWAY
             "     takeoff: {mu: 0.02, v_rot: 90, alpha_rot_deg: 0}}\n"
             "  - {name: climb, model: dof3, stages: [ms], from: roll, stop_time: 90}\n", &err);
    CHECK(m != NULL);
    if (m != NULL) {
        lv_run *r = NULL;
        CHECK_OK(lv_run_create(m, &r, &err), &err);
        CHECK(lv_run_execute(r, NULL, &err) != LV_OK);
        CHECK(lv_run_result(r, 0)->state == LV_PHASE_DONE);
        CHECK(lv_run_result(r, 1)->state == LV_PHASE_FAILED &&
              strstr(lv_run_result(r, 1)->error, "the parent roll did not lift off") != NULL);
        lv_run_free(r);
        lv_mission_free(m);
    }
    /* a roll-out's written end keeps its user name (the runway model's own events come first:
     * the end's index maps past all of them): at 50 m/s, braking 0.3, no air, the speed falls
     * through 30 m/s after (50 - 30) / (0.3 g) = 6.8 s */
    m = load_text("rw_edges.yaml",
        HEAD "  - {name: roll, model: runway, stages: [ms], stop_time: 60,\n" ROLL_RUNWAY
             "     landing: {mu: 0.3, v_stop: 1, start_speed: 50},\n"
             "     end: [{speed: 30, direction: falling, name: slow}]}\n", &err);
    CHECK(m != NULL);
    if (m != NULL) {
        lv_run *r = NULL;
        CHECK_OK(lv_run_create(m, &r, &err), &err);
        CHECK_OK(lv_run_execute(r, NULL, &err), &err);
        const lv_phase_result *pr = lv_run_result(r, 0);
        CHECK(pr->state == LV_PHASE_DONE && strcmp(pr->report.stop_name, "speed") == 0);
        CHECK(pr->end_index == 0 && pr->end_label != NULL && strcmp(pr->end_label, "slow") == 0);
        CHECK_CLOSE(pr->t_end, 20.0 / (0.3 * 9.80), 0.05);
        lv_run_free(r);
        lv_mission_free(m);
    }
    /* a root roll at 150 m/s with CL 2 on 300 m^2: lift (q S CL ~ 1.6e7 N) far above the
     * weight (1.5e6 N): refused when the mission is loaded, as `lvsim check` does */
    m = load_text("rw_edges.yaml",
        HEAD "  - {name: roll, model: runway, stages: [ms], stop_time: 20,\n" ROLL_RUNWAY
             "     takeoff: {mu: 0.02, v_rot: 90, alpha_rot_deg: 8, start_speed: 150},\n"
             "     aero: {s_ref: 300, CD: 0.05, CL: 2}}\n", &err);
    CHECK(m == NULL && strstr(err.msg, "the vehicle is already flying at the start") != NULL);
    lv_mission_free(m);
    /* 2 t of propellant at 2 MN and Isp 350 s (mdot 583 kg/s): burnout after 3.4 s, then the
     * friction and drag stop it: the roll ends at rest, "at_rest", before its time limit */
    m = load_text("rw_edges.yaml",
        "mission: {name: rw}\n"
        "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}\n"
        "stages:\n"
        "  - {name: ms, dry_mass: 50000, propellant_mass: 2000,\n"
        "     engines: [{name: e, thrust_vac: 2.0e6, isp_vac: 350, exit_area: 1.5}]}\n"
        "phases:\n"
        "  - {name: roll, model: runway, stages: [ms], stop_time: 600,\n" ROLL_RUNWAY
        "     takeoff: {mu: 0.05, v_rot: 90, alpha_rot_deg: 0}}\n", &err);
    CHECK(m != NULL);
    if (m != NULL) {
        lv_run *r = NULL;
        CHECK_OK(lv_run_create(m, &r, &err), &err);
        CHECK_OK(lv_run_execute(r, NULL, &err), &err);
        const lv_phase_result *p = lv_run_result(r, 0);
        CHECK(p->report.reason == LV_STOP_EVENT && p->t_end < 600.0);
        CHECK(p->report.stop_event >= 0 && (size_t)p->report.stop_event < p->n_event_names &&
              strcmp(p->event_names[p->report.stop_event], "at_rest") == 0);
        double v = NAN;
        CHECK_OK(lv_run_final(r, 0, "speed", &v, &err), &err);
        CHECK_CLOSE(v, 0.0, 1e-6);
        lv_run_free(r);
        lv_mission_free(m);
    }
    /* a take-off roll from a flight phase */
    m = load_text("rw_edges.yaml",
        HEAD "  - {name: fly, model: dof3, stages: [ms], stop_time: 1, throttle: off}\n"
             "  - {name: roll, model: runway, stages: [ms], from: fly, stop_time: 20,\n" ROLL_RUNWAY
             "     takeoff: {mu: 0.02, v_rot: 90, alpha_rot_deg: 8}}\n", &err);
    CHECK(m != NULL);
    if (m != NULL) {
        lv_run *r = NULL;
        CHECK_OK(lv_run_create(m, &r, &err), &err);
        CHECK(lv_run_execute(r, NULL, &err) != LV_OK);
        CHECK(strstr(lv_run_result(r, 1)->error, "a take-off roll starts on the runway") != NULL);
        lv_run_free(r);
        lv_mission_free(m);
    }
    remove("rw_edges.yaml");
}

/* ---- (6) the landing gear's limits at touchdown ------------------------------------------- */

/* A glide that starts 1 cm above the runway's threshold (elevation 150 m, heading 140 deg) at
 * speed v [m/s], flight-path angle fpa and heading 140 + dchi [deg], alpha and bank mu [deg]
 * (inputs; no aerodynamics: no force from them, only the attitude), touches down at once
 * (end at the elevation) and hands over to a roll-out. `gear`: the stage's landing_gear
 * mapping or "". Over 1 cm the speeds change by g t ~ 0.1 m/s at most (t = 0.01 m / sink). */
static const char *g_runway = NULL; /* the roll-out's `runway:`; NULL: the threshold below */

static lv_run *touchdown(const char *gear, double v, double fpa, double dchi, double alpha,
                         double mu, lv_mission **m)
{
    const char *runway = g_runway != NULL
                             ? g_runway
                             : "{lat_deg: 43.6, lon_deg: 1.37, elevation: 150, heading_deg: 140}";
    char yaml[2048];
    snprintf(yaml, sizeof yaml,
             "mission: {name: gear}\n"
             "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}\n"
             "parameters: {start_lat_deg: 43.6, start_lon_deg: 1.37, start_h: 150.01,\n"
             "             start_vel: %g, start_fpa_deg: %g, start_chi_deg: %g}\n"
             "stages:\n"
             "  - {name: ms, dry_mass: 50000, propellant_mass: 0%s%s}\n"
             "phases:\n"
             "  - {name: down, model: dof3, stages: [ms], start_time: 0, stop_time: 30,\n"
             "     end: [{altitude: 150, direction: falling}], throttle: off,\n"
             "     inputs: {alpha_deg: %g, mu_deg: %g}}\n"
             "  - {name: rollout, model: runway, stages: [ms], from: down, stop_time: 300,\n"
             "     runway: %s,\n"
             "     landing: {mu: 0.3, v_stop: 2}}\n",
             v, fpa, 140.0 + dchi, gear[0] ? ", landing_gear: " : "", gear, alpha, mu, runway);
    lv_err err;
    lv_run *r = NULL;
    *m = NULL;
    FILE *f = fopen("test_gear.yaml", "w");
    CHECK(f != NULL);
    if (f == NULL)
        return NULL;
    fputs(yaml, f);
    fclose(f);
    CHECK_OK(lv_mission_load("test_gear.yaml", m, &err), &err);
    if (*m == NULL)
        return NULL;
    CHECK_OK(lv_run_create(*m, &r, &err), &err);
    if (r != NULL)
        CHECK_OK(lv_run_execute(r, NULL, &err), &err); /* a crash is no failure of the run */
    return r;
}

/* The roll-out's state and, for a crash, that its error names `want`. */
static void expect_touchdown(const char *gear, double v, double fpa, double dchi, double alpha,
                             double mu, lv_phase_state want_state, const char *want)
{
    lv_mission *m;
    lv_run *r = touchdown(gear, v, fpa, dchi, alpha, mu, &m);
    CHECK(r != NULL);
    if (r == NULL)
        return;
    const lv_phase_result *ro = lv_run_result(r, 1);
    CHECK(lv_run_result(r, 0)->state == LV_PHASE_DONE);
    CHECK(ro->state == want_state);
    if (want != NULL && strstr(ro->error, want) == NULL) {
        fprintf(stderr, "expected '%s' in: %s\n", want, ro->error);
        CHECK(0);
    }
    if (want_state == LV_PHASE_CRASHED) {
        CHECK(strstr(ro->error, "phase 'rollout': crashed at touchdown: ") == ro->error);
        CHECK(strstr(ro->error, " at t = ") != NULL);
        CHECK(ro->n_absorbed == 8); /* what the touchdown was, recorded */
        CHECK(strcmp(lv_phase_state_name(ro->state), "crashed") == 0);
    }
    lv_run_free(r);
    lv_mission_free(m);
}

static void test_gear_limits(void)
{
    const lv_phase_state D = LV_PHASE_DONE, C = LV_PHASE_CRASHED;
    /* inside every default limit: 80 m/s, sink 80 sin 1 deg = 1.40 m/s, on the centre line,
     * pitch = fpa + alpha = 4 deg, wings level */
    expect_touchdown("", 80, -1, 0, 5, 0, D, NULL);
    /* beyond each default limit, one at a time (docs/models.md): sink 80 sin 3 deg = 4.19 >
     * 3.05 m/s (10 ft/s; 4.21 after the 1 cm fall); lateral 80 cos 1 sin 2 deg = 2.79 > 2
     * m/s; ground speed 120 cos 0.5 deg = 119.995 > 115.7 m/s (225 kt); bank 12 > 10 deg;
     * pitch -1 + 17 = 16 > 15 deg and -1 - 1 = -2 < 0 deg (the nose wheel first; -2.05
     * after the fall's steepening) */
    expect_touchdown("", 80, -3, 0, 5, 0, C, "sink rate 4.2");
    expect_touchdown("", 80, -3, 0, 5, 0, C, "> 3.05 m/s (landing gear of stage 'ms': the "
                                             "default limits)");
    expect_touchdown("", 80, -1, 2, 5, 0, C, "lateral speed 2.7");
    expect_touchdown("", 80, -1, -2, 5, 0, C, "lateral speed -2.7");
    expect_touchdown("", 120, -0.5, 0, 5, 0, C, "ground speed 120 m/s > 115.7 m/s");
    expect_touchdown("", 80, -1, 0, 0, 12, C, "bank 12 deg beyond +-10 deg");
    expect_touchdown("", 80, -1, 0, 17, 0, C, "pitch 16 deg outside [0, 15] deg");
    expect_touchdown("", 80, -1, 0, -1, 0, C, "pitch -2.0");
    expect_touchdown("", 80, -1, 0, -1, 0, C, "deg outside [0, 15] deg");
    /* two at once, both named: sink 120 sin 3 deg = 6.28 m/s, ground speed 120 cos 3 deg =
     * 119.8 m/s */
    expect_touchdown("", 120, -3, 0, 5, 0, C, "sink rate 6.3 m/s > 3.05 m/s; ground speed "
                                              "119.8 m/s > 115.7 m/s");
    /* a stage's own gear: its limits, the others default */
    expect_touchdown("{sink_rate_max: 5}", 80, -3, 0, 5, 0, D, NULL);
    expect_touchdown("{sink_rate_max: 4}", 80, -3, 0, 5, 0, C,
                     "> 4 m/s (landing gear of stage 'ms')");
    expect_touchdown("{bank_max_deg: 15, pitch_max_deg: 20}", 80, -1, 0, 17, 12, D, NULL);
    /* on the runway or off it (the touchdown at 43.6 N, 1.37 E, heading 140 deg): a threshold
     * 100 m further along the heading is an undershoot; one 100 m back with a length of 50 m
     * a touchdown past the end; a centre line 30 m to the left (the threshold moved 30 m
     * towards 50 deg: the vehicle 30 m right of it) an excursion beyond the 45 m runway's
     * half-width, not beyond a 100 m one's. Offsets on WGS-84 at 43.6 deg: 1 deg of latitude
     * 111.104 km (the meridian radius), of longitude 80.743 km (100 m at 140 deg: -0.000690
     * deg lat, +0.000797 deg lon, 100.08 m along the heading as rounded; 30 m at 50 deg:
     * +0.000174, +0.000285, 30.1 m). The glide covers 80 m/s x 0.007 s = 0.56 m to its
     * touchdown: 100.08 - 0.56 = 99.52 m before the threshold. */
    g_runway = "{lat_deg: 43.59931, lon_deg: 1.370797, elevation: 150, heading_deg: 140}";
    expect_touchdown("", 80, -1, 0, 5, 0, C, "m before the runway's threshold (undershoot)");
    expect_touchdown("", 80, -1, 0, 5, 0, C, "crashed at touchdown: 99.5");
    g_runway = "{lat_deg: 43.60069, lon_deg: 1.369203, elevation: 150, heading_deg: 140, "
               "length: 50}";
    expect_touchdown("", 80, -1, 0, 5, 0, C, "m past the runway's end (length 50 m)");
    g_runway = "{lat_deg: 43.600174, lon_deg: 1.370285, elevation: 150, heading_deg: 140}";
    expect_touchdown("", 80, -1, 0, 5, 0, C, "30.1 m right of the centre line, beyond the half-width "
                                             "22.5 m (runway excursion)");
    g_runway = "{lat_deg: 43.600174, lon_deg: 1.370285, elevation: 150, heading_deg: 140, "
               "width: 100}";
    expect_touchdown("", 80, -1, 0, 5, 0, D, NULL);
    /* two at once: off the runway and beyond the gear */
    g_runway = "{lat_deg: 43.59931, lon_deg: 1.370797, elevation: 150, heading_deg: 140}";
    expect_touchdown("", 80, -3, 0, 5, 0, C, "m before the runway's threshold (undershoot); sink rate 4.2");
    /* a roll-out longer than the runway ends where the runway does (its end "overrun", a
     * crash: flown to there, then crashed, its finals kept): from
     * 80 m/s with braking friction 0.3 and no air the roll takes v^2 / (2 mu g) = 1.09 km;
     * over 100 m the speed falls to sqrt(80^2 - 2 x 0.3 x 9.80 x 100) = 76.3 m/s */
    g_runway = "{lat_deg: 43.6, lon_deg: 1.37, elevation: 150, heading_deg: 140, length: 100}";
    {
        lv_mission *m;
        lv_run *r = touchdown("", 80, -1, 0, 5, 0, &m);
        CHECK(r != NULL);
        if (r != NULL) {
            const lv_phase_result *ro = lv_run_result(r, 1);
            CHECK(ro->state == LV_PHASE_CRASHED);
            CHECK(strcmp(ro->report.stop_name, "overrun") == 0);
            CHECK(strstr(ro->error, "phase 'rollout': crashed at t = ") == ro->error &&
                  strstr(ro->error, ": overrun: ") != NULL);
            double s_end = NAN, v_end = NAN;
            for (size_t i = 0; i < ro->n_final; i++) {
                if (strcmp(ro->final_names[i], "distance") == 0)
                    s_end = ro->final_values[i];
                if (strcmp(ro->final_names[i], "speed") == 0)
                    v_end = ro->final_values[i];
            }
            CHECK_CLOSE(s_end, 100.0, 1e-6);
            CHECK_CLOSE(v_end, 76.3, 0.3); /* 1.40 m/s of sink and 1 deg less: within 0.3 */
            lv_run_free(r);
        }
        lv_mission_free(m);
    }
    g_runway = NULL;
    /* the limits are run parameters: a run may set them */
    {
        lv_mission *m;
        lv_run *r = touchdown("{sink_rate_max: 5}", 80, -3, 0, 5, 0, &m);
        lv_err err;
        CHECK(r != NULL);
        if (r != NULL) {
            CHECK_OK(lv_run_set(r, "ms.landing_gear.sink_rate_max", 4.0, &err), &err);
            CHECK_OK(lv_run_execute(r, NULL, &err), &err);
            CHECK(lv_run_result(r, 1)->state == LV_PHASE_CRASHED);
            lv_run_free(r);
        }
        lv_mission_free(m);
    }
    /* bad gear values and keys: file:line:col */
#define GEAR_HEAD(gear)                                                                    \
    "mission: {name: rw}\n"                                                                 \
    "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}\n"          \
    "stages:\n"                                                                             \
    "  - {name: ms, dry_mass: 1000, propellant_mass: 0, landing_gear: " gear "}\n"          \
    "phases:\n"                                                                             \
    "  - {name: P, model: runway, stages: [ms], stop_time: 60,\n"                           \
    "     runway: {lat_deg: 43, lon_deg: 1, elevation: 150, heading_deg: 90},\n"            \
    "     landing: {mu: 0.3, v_stop: 1, start_speed: 50}}\n"
    /* a dispersion of a limit the stage does not write: the defaults are no parameters */
    BAD("mission: {name: rw}\n"
        "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}\n"
        "stages:\n"
        "  - {name: ms, dry_mass: 1000, propellant_mass: 0}\n"
        "phases:\n"
        "  - {name: P, model: runway, stages: [ms], stop_time: 60,\n"
        "     runway: {lat_deg: 43, lon_deg: 1, elevation: 150, heading_deg: 90},\n"
        "     landing: {mu: 0.3, v_stop: 1, start_speed: 50}}\n"
        "dispersions:\n"
        "  seed: 1\n"
        "  parameters: {ms.landing_gear.sink_rate_max: {dist: normal, sigma: 0.3}}\n",
        "bad.yaml:11:16: dispersions: no parameter 'ms.landing_gear.sink_rate_max': stage 'ms' "
        "writes no `landing_gear:`");
    /* a start before the threshold is off the runway */
    BAD(HEAD "  - {name: P, model: runway, stages: [ms], stop_time: 60,\n" ROLL_RUNWAY
             "     takeoff: {mu: 0.02, v_rot: 90, alpha_rot_deg: 8, start_distance: -100}}\n",
        "bad.yaml:9:71: phase 'P', takeoff: start_distance must be >= 0 m, found -100");
    /* runway length and width out of range */
    BAD("mission: {name: rw}\n"
        "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}\n"
        "stages:\n"
        "  - {name: ms, dry_mass: 1000, propellant_mass: 0}\n"
        "phases:\n"
        "  - {name: P, model: runway, stages: [ms], stop_time: 60,\n"
        "     runway: {lat_deg: 43, lon_deg: 1, elevation: 150, heading_deg: 90, length: 5},\n"
        "     landing: {mu: 0.3, v_stop: 1, start_speed: 50}}\n",
        "bad.yaml:7:81: phase 'P', runway: length must be >= 10");
    BAD(GEAR_HEAD("{sink_rate_max: 0}"),
        "bad.yaml:4:82: stage 'ms', landing_gear: sink_rate_max must be > 0 m/s, found 0");
    BAD(GEAR_HEAD("{sink_rate: 3}"), "bad.yaml:4:67: stage 'ms', landing_gear: unknown key "
                                     "'sink_rate'; did you mean 'sink_rate_max'");
    BAD(GEAR_HEAD("{bank_max_deg: 95}"), "bad.yaml:4:81: stage 'ms', landing_gear: "
                                         "bank_max_deg must be > 0 and <= 90 deg, found 95");
    BAD(GEAR_HEAD("{bank_max: 0.1, bank_max_deg: 5}"),
        "bad.yaml:4:82: stage 'ms', landing_gear: 'bank_max' and 'bank_max_deg' given both");
    BAD(GEAR_HEAD("{pitch_min_deg: 10, pitch_max_deg: 5}"),
        "bad.yaml:4:66: stage 'ms', landing_gear: pitch_max 5 deg must be above pitch_min 10 "
        "deg");
    BAD(GEAR_HEAD("3"), "bad.yaml:4:66: stage 'ms', landing_gear: a mapping such as "
                        "{sink_rate_max: 3} expected");
#undef GEAR_HEAD
}

int main(void)
{
    test_friction_no_air();
    test_drag_closed_form();
    test_liftoff_speed();
    test_landing_rollout();
    test_rotating_threshold();
    test_mission_edges();
    test_gear_limits();
    test_bad_config();
    test_mission_errors();
    test_mission_handoffs();
    return check_report("test_runway");
}
