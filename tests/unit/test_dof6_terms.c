/* test_dof6_terms.c - the switchable rigid-body terms of the 6-DoF model (lv_dof6_terms;
 * docs/models.md, "Rigid-body terms"): jet damping, the inertia-rate term -I' w and the frame
 * of the aerodynamic rate damping, each on and off, against closed forms derived here; the
 * mission keys `rigid_body: {terms: ...}` (parsed, refused at their place, carried to the
 * model) and the engine position they need. None of the references is the code's output. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_dof6.h"
#include "lvsim/lv_io.h"
#include "lvsim/lv_mission.h"
#include "lvsim/lv_planet.h"
#include "lvsim/lv_sim.h"
#include "mission/mission.h"

#define DEG (M_PI / 180.0)

static lv_status run(const lv_model_def *def, void *inst, double tf, double tol, size_t n_fin,
                     const char *const *fin, double *out, lv_err *err)
{
    lv_sim_settings s;
    lv_sim_settings_default(&s);
    s.result_file = NULL;
    s.start_time = 0.0;
    s.stop_time = tf;
    s.method = "dassl";
    s.tolerance = tol;
    s.number_of_intervals = 10;
    s.n_final = n_fin;
    s.final_names = fin;
    s.max_steps = 10000000;
    return lv_simulate(def, inst, &s, out, NULL, err);
}

static lv_gravity *pointmass(const lv_planet *pl)
{
    lv_err err;
    lv_gravity_config gc = {"pointmass", 0, -1, NULL};
    lv_gravity *g = NULL;
    CHECK_OK(lv_gravity_create(pl, &gc, &g, &err), &err);
    return g;
}

/* ---- (1) jet damping and inertia rate, all four combinations, closed form -------------- */
/* A body with an isotropic inertia i(t) E (full 100, empty 60 kg m^2), its CG at the origin,
 * one engine on the x axis at r_e = (-l, 0, 0), l = 0.5 m, thrusting along +x (no thrust
 * moment), in vacuum, spinning at w0 = (0.3, 0.2, -0.1) rad/s. w x (I w) = i w x w = 0, so
 * Euler's equation of a body of varying mass (Eke & Mao 2002, with a point nozzle exit;
 * Thomson ch. 8) reads
 *   i w' = -A i' w - B mdot r_e x (w x r_e) = -A i' w - B mdot l^2 (0, w_y, w_z)
 * with A, B the switches inertia_rate and jet_damping (1 on, 0 off). The mass flow is
 * constant, so i' = (60 - 100) mdot / 400 kg (the propellant) is constant and, with
 * x = i(t) / i(0) (di = i' dt),
 *   w_x(t) = w_x0 x^(-A),   w_y,z(t) = w_y,z0 x^(-(A + B mdot l^2 / i')).
 * With A = 1 and B = 0 the body's angular momentum i w is constant (nothing carries angular
 * momentum away: the check of the -I' w term by conservation); with A = 0 and B = 0 the rates
 * are constant. Checked after 8 s of the 11.8 s burn at 1e-11, to 1e-8 relative. */
static void test_closed_form(void)
{
    lv_err err;
    lv_planet pl = lv_planet_earth();
    pl.omega = 0.0;
    lv_gravity *g = pointmass(&pl);
    const double l = 0.5, thrust = 1e5, isp = 300.0, prop = 400.0, t_end = 8.0;
    const double mdot = thrust / (isp * LV_G0), idot = (60.0 - 100.0) * mdot / prop;
    const double x = (100.0 + idot * t_end) / 100.0;
    const double w0[3] = {0.3, 0.2, -0.1};
    for (int combo = 0; combo < 4; combo++) {
        const int A = combo & 1, B = (combo >> 1) & 1;
        lv_dof6_config cfg;
        lv_dof6_config_default(&cfg);
        cfg.planet = pl;
        cfg.gravity = g;
        cfg.m0 = 1000.0;
        cfg.propellant = prop;
        cfg.start_h = 2.0e6;
        cfg.start_vel = 7000.0;
        cfg.start_p = w0[0];
        cfg.start_q = w0[1];
        cfg.start_r = w0[2];
        for (int i = 0; i < 3; i++) {
            cfg.mass.inertia_full[i] = 100.0;
            cfg.mass.inertia_empty[i] = 60.0;
        }
        lv_engine_config ec;
        lv_engine_config_default(&ec);
        ec.thrust_vac = thrust;
        ec.isp_vac = isp;
        const lv_dof6_engine_geom eg = {{-l, 0.0, 0.0}, 0.0, 0.0};
        cfg.n_engines = 1;
        cfg.engines = &ec;
        cfg.engine_geom = &eg;
        cfg.terms.inertia_rate = A;
        cfg.terms.jet_damping = B;
        lv_dof6 *m = NULL;
        CHECK_OK(lv_dof6_create(&cfg, &m, &err), &err);
        if (m == NULL)
            continue;
        const char *fin[] = {"p", "q", "r", "I_xx", "mdot", "L_thrust", "M_thrust"};
        double out[7];
        CHECK_OK(run(lv_dof6_def(m), lv_dof6_inst(m), t_end, 1e-11, 7, fin, out, &err), &err);
        const double kx = -(double)A, kt = -(A + B * mdot * l * l / idot);
        const double ref[3] = {w0[0] * pow(x, kx), w0[1] * pow(x, kt), w0[2] * pow(x, kt)};
        printf("inertia_rate %s, jet_damping %s: p, q, r = %.9g, %.9g, %.9g (closed form %.9g, "
               "%.9g, %.9g)\n", A ? "on " : "off", B ? "on " : "off", out[0], out[1], out[2],
               ref[0], ref[1], ref[2]);
        for (int i = 0; i < 3; i++)
            CHECK_REL(out[i], ref[i], 1e-8);
        CHECK_REL(out[3], 100.0 * x, 1e-10);
        CHECK_REL(out[4], mdot, 1e-12);
        /* the thrust moment output carries the jet damping: -B mdot l^2 (0, q, r) */
        CHECK_CLOSE(out[5], 0.0, 1e-12);
        CHECK_CLOSE(out[6], -B * mdot * l * l * out[1], 1e-12 + 1e-10 * fabs(mdot * l * l * out[1]));
        lv_dof6_free(m);
    }
    lv_gravity_free(g);
}

/* ---- (1b) the jet damping's vector form, an engine off the axis ------------------------- */
/* An asymmetric body (100, 200, 300 kg m^2) spinning at w0 = (0.3, 0.2, -0.1) rad/s, its CG at
 * the origin, one engine at r_e = (-2, 0.3, -0.4) m thrusting T = 1 kN along +x in vacuum. The
 * thrust moment output is r_e x F + M_jet with F = (T, 0, 0):
 *   r_e x F = (0, r_z T, -r_y T),   M_jet = -mdot r_e x (w x r_e) = -mdot (|r_e|^2 w - (r_e.w) r_e)
 * (the vector triple product expanded: the model computes the cross products), evaluated with
 * the rates the same run reports at its end (1e-3 s); without jet damping r_e x F alone. Third
 * case: the nozzle exit given 0.7 m aft of the gimbal point, r_x = (-2.7, 0.3, -0.4) m: the
 * jet damping with r_x in place of r_e, the thrust moment still about r_e. */
static void test_jet_vector(void)
{
    lv_err err;
    lv_planet pl = lv_planet_earth();
    pl.omega = 0.0;
    lv_gravity *g = pointmass(&pl);
    const double T = 1e3, isp = 300.0, re[3] = {-2.0, 0.3, -0.4}, rx[3] = {-2.7, 0.3, -0.4};
    const double mdot = T / (isp * LV_G0);
    for (int cs = 0; cs < 3; cs++) {
        const int jd = cs > 0;
        const double *r = cs == 2 ? rx : re;
        lv_dof6_config cfg;
        lv_dof6_config_default(&cfg);
        cfg.planet = pl;
        cfg.gravity = g;
        cfg.m0 = 1000.0;
        cfg.propellant = 400.0;
        cfg.start_h = 2.0e6;
        cfg.start_vel = 7000.0;
        cfg.start_p = 0.3;
        cfg.start_q = 0.2;
        cfg.start_r = -0.1;
        for (int i = 0; i < 3; i++) {
            cfg.mass.inertia_full[i] = 100.0 * (i + 1);
            cfg.mass.inertia_empty[i] = 60.0 * (i + 1);
        }
        lv_engine_config ec;
        lv_engine_config_default(&ec);
        ec.thrust_vac = T;
        ec.isp_vac = isp;
        const lv_dof6_engine_geom eg = {{re[0], re[1], re[2]}, 0.0, 0.0};
        cfg.n_engines = 1;
        cfg.engines = &ec;
        cfg.engine_geom = &eg;
        cfg.engine_exit = cs == 2 ? rx : NULL;
        cfg.terms.jet_damping = jd;
        lv_dof6 *m = NULL;
        CHECK_OK(lv_dof6_create(&cfg, &m, &err), &err);
        if (m == NULL)
            continue;
        const char *fin[] = {"p", "q", "r", "L_thrust", "M_thrust", "N_thrust", "mdot", "cg_x"};
        double out[8];
        CHECK_OK(run(lv_dof6_def(m), lv_dof6_inst(m), 1e-3, 1e-11, 8, fin, out, &err), &err);
        const double w[3] = {out[0], out[1], out[2]};
        const double r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
        const double rw = r[0] * w[0] + r[1] * w[1] + r[2] * w[2];
        const double mt[3] = {0.0, re[2] * T, -re[1] * T};
        CHECK_REL(out[6], mdot, 1e-12);
        CHECK_CLOSE(out[7], 0.0, 0.0);
        for (int i = 0; i < 3; i++) {
            const double ref = mt[i] - jd * mdot * (r2 * w[i] - rw * r[i]);
            CHECK_CLOSE(out[3 + i], ref, 1e-12 * (fabs(mt[i]) + 1.0));
        }
        if (jd)
            printf("jet damping, engine off the axis%s: M_thrust - r_e x F = (%.9g, %.9g, %.9g) "
                   "N m (-mdot (|r|^2 w - (r.w) r) = (%.9g, %.9g, %.9g))\n",
                   cs == 2 ? ", exit aft" : "", out[3] - mt[0], out[4] - mt[1], out[5] - mt[2],
                   -mdot * (r2 * w[0] - rw * r[0]), -mdot * (r2 * w[1] - rw * r[1]),
                   -mdot * (r2 * w[2] - rw * r[2]));
        lv_dof6_free(m);
    }
    lv_gravity_free(g);
}

/* ---- (2) the frame of the rate damping: air or inertial ----------------------------------- */
/* A body at 45 deg N flying at 200 m/s relative to the rotating Earth (no wind) along its x axis
 * (psi = chi = 30 deg, theta = fpa = 0: alpha = beta = 0), through air of constant density
 * (exponential atmosphere with H = 1e15 m: rho = 1.225 kg/m^3, q = 24500 Pa), with damping
 * derivatives only (Cl = Cm = Cn = 0, no force coefficient). The Earth's rotation in the body
 * axes, from NED (Omega cos lat, 0, -Omega sin lat) turned by psi about down:
 *   w_E = Omega (cos psi cos lat, -sin psi cos lat, -sin lat).
 * Started at w0 = w_E + d, d = (0.01, 0.02, -0.01) rad/s, the moments at the start are
 *   air:      (q S b Clp b/(2V) d_x, q S c Cmq c/(2V) d_y, q S b Cnr b/(2V) d_z)
 *   inertial: the same with w0 in place of d,
 * so they differ by exactly the Earth's rotation term k w_E. Read 1e-6 s after the start (the
 * rates change by ~1e-7 of themselves). */
static void test_damping_frame(void)
{
    lv_err err;
    const lv_planet pl = lv_planet_earth();
    lv_gravity *g = pointmass(&pl);
    lv_atmo *atm = NULL;
    CHECK_OK(lv_atmo_create("exp", &atm, &err), &err);
    CHECK_OK(lv_atmo_set(atm, "H", 1e15, &err), &err);
    const double lat = 45.0 * DEG, psi = 30.0 * DEG, V = 200.0, S = 10.0, b = 3.0, c = 2.0;
    const double der[3] = {-8.0, -20.0, -15.0}, len[3] = {b, c, b};
    const double wE[3] = {pl.omega * cos(psi) * cos(lat), -pl.omega * sin(psi) * cos(lat),
                          -pl.omega * sin(lat)};
    const double d[3] = {0.01, 0.02, -0.01};
    double mom[2][3];
    for (int frame = 0; frame < 2; frame++) {
        lv_dof6_config cfg;
        lv_dof6_config_default(&cfg);
        cfg.gravity = g;
        cfg.atmo = atm;
        cfg.start_lat = lat;
        cfg.start_h = 1000.0;
        cfg.start_vel = V;
        cfg.start_chi = psi;
        cfg.start_psi = psi;
        cfg.start_p = wE[0] + d[0];
        cfg.start_q = wE[1] + d[1];
        cfg.start_r = wE[2] + d[2];
        for (int i = 0; i < 3; i++)
            cfg.mass.inertia_full[i] = cfg.mass.inertia_empty[i] = 1e6;
        lv_aero_config ac;
        lv_aero_config_default(&ac);
        ac.axes = LV_AERO_BODY;
        ac.s_ref = S;
        cfg.aero = &ac;
        lv_dof6_moments mo;
        memset(&mo, 0, sizeof mo);
        mo.clp = der[0];
        mo.cmq = der[1];
        mo.cnr = der[2];
        mo.b_ref = b;
        mo.c_ref = c;
        cfg.moments = &mo;
        cfg.terms.rate_damping_frame = frame ? LV_DOF6_DAMPING_INERTIAL : LV_DOF6_DAMPING_AIR;
        lv_dof6 *m = NULL;
        CHECK_OK(lv_dof6_create(&cfg, &m, &err), &err);
        if (m == NULL)
            continue;
        const char *fin[] = {"L_aero", "M_aero", "N_aero", "q_dyn", "v_rel", "alpha", "beta"};
        double out[7];
        CHECK_OK(run(lv_dof6_def(m), lv_dof6_inst(m), 1e-6, 1e-10, 7, fin, out, &err), &err);
        CHECK_REL(out[3], 0.5 * 1.225 * V * V, 1e-6);
        CHECK_CLOSE(out[5], 0.0, 1e-6);
        CHECK_CLOSE(out[6], 0.0, 1e-6);
        for (int i = 0; i < 3; i++) {
            const double k = out[3] * S * len[i] * der[i] * len[i] / (2.0 * out[4]);
            const double ref = k * (frame ? wE[i] + d[i] : d[i]);
            mom[frame][i] = out[i];
            CHECK_REL(out[i], ref, 1e-6);
        }
        lv_dof6_free(m);
    }
    /* the difference is the Earth's rotation term alone */
    for (int i = 0; i < 3; i++) {
        const double k = 0.5 * 1.225 * V * V * S * len[i] * der[i] * len[i] / (2.0 * V);
        printf("damping frame, axis %d: inertial - air = %.9g N m (k w_E = %.9g)\n", i,
               mom[1][i] - mom[0][i], k * wE[i]);
        CHECK_REL(mom[1][i] - mom[0][i], k * wE[i], 1e-5);
    }
    lv_atmo_free(atm);
    lv_gravity_free(g);
}

/* ---- (3) the C API's refusals --------------------------------------------------------------- */
static void test_config_errors(void)
{
    lv_err err;
    lv_planet pl = lv_planet_earth();
    lv_gravity *g = pointmass(&pl);
    lv_dof6_config cfg;
    lv_dof6_config_default(&cfg);
    CHECK(cfg.terms.jet_damping == 1 && cfg.terms.inertia_rate == 1 &&
          cfg.terms.rate_damping_frame == LV_DOF6_DAMPING_AIR);
    cfg.gravity = g;
    cfg.start_h = 2.0e6;
    cfg.start_vel = 7000.0;
    lv_engine_config ec;
    lv_engine_config_default(&ec);
    ec.thrust_vac = 1e5;
    ec.isp_vac = 300.0;
    cfg.propellant = 100.0;
    cfg.n_engines = 1;
    cfg.engines = &ec;
    lv_dof6 *m = NULL;
    /* engines without a position: no default */
    CHECK(lv_dof6_create(&cfg, &m, &err) == LV_ERR_INPUT && m == NULL);
    CHECK(strstr(err.msg, "without their position") != NULL);
    const lv_dof6_engine_geom eg = {{-1.0, 0.0, 0.0}, 0.0, 0.0};
    cfg.engine_geom = &eg;
    cfg.terms.jet_damping = 2;
    CHECK(lv_dof6_create(&cfg, &m, &err) == LV_ERR_INPUT && m == NULL);
    CHECK(strstr(err.msg, "jet_damping = 2") != NULL);
    cfg.terms.jet_damping = 1;
    cfg.terms.rate_damping_frame = (lv_dof6_damping_frame)3;
    CHECK(lv_dof6_create(&cfg, &m, &err) == LV_ERR_INPUT && m == NULL);
    cfg.terms.rate_damping_frame = LV_DOF6_DAMPING_INERTIAL;
    CHECK_OK(lv_dof6_create(&cfg, &m, &err), &err);
    lv_dof6_free(m);
    lv_gravity_free(g);
}

/* ---- (4) the mission keys ------------------------------------------------------------------ */
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
    "mission: {name: terms}\n"                                                              \
    "environment: {world: planet, planet: earth, gravity: pointmass, atmosphere: none}\n"   \
    "parameters: {start_lat: 0, start_lon: 0, start_h: 2.0e6, start_vel: 7000,\n"          \
    "             start_fpa: 0, start_chi: 0}\n"                                            \
    "stages:\n"                                                                             \
    "  - name: s1\n"                                                                        \
    "    dry_mass: 600\n"                                                                   \
    "    propellant_mass: 400\n"                                                            \
    "    engines: [{name: e, thrust_vac: 1.0e5, isp_vac: 300}]\n"
#define PHASE                                                                               \
    "phases:\n"                                                                             \
    "  - {name: P, model: dof6, stages: [s1], stop_time: 8,\n"                               \
    "     rates: {p: 0.3, q: 0.2, r: -0.1}, integrator: {tolerance: 1e-11}}\n"

static void test_mission_keys(void)
{
    /* the engine position is required where the stage has engines */
    BAD(HEAD "    rigid_body: {inertia_full: {xx: 100, yy: 100, zz: 100}}\n" PHASE,
        "bad.yaml:10:17: stage 's1', rigid_body: 'engine_position' is missing: the stage has "
        "engines");
    BAD(HEAD "    rigid_body: {inertia_full: {xx: 100, yy: 100, zz: 100},\n"
        "                 engine_position: {y: 0}}\n" PHASE,
        "bad.yaml:11:35: stage 's1', rigid_body: 'engine_position.x' is missing: the stage has "
        "engines, and their thrust moment and jet damping act at");
    BAD(HEAD "    rigid_body: {inertia_full: {xx: 100, yy: 100, zz: 100},\n"
        "                 terms: {jet_damping: off}}\n" PHASE,
        "bad.yaml:10:17: stage 's1', rigid_body: 'engine_position' is missing: the stage has "
        "engines, and their thrust moment acts at");
    BAD(HEAD "    rigid_body: {inertia_full: {xx: 100, yy: 100, zz: 100},\n"
        "                 engine_position: {x: -0.5}, terms: {jet_damping: no}}\n" PHASE,
        "bad.yaml:11:67: stage 's1', rigid_body, terms: jet_damping");
    BAD(HEAD "    rigid_body: {inertia_full: {xx: 100, yy: 100, zz: 100},\n"
        "                 engine_position: {x: -0.5}, terms: {jet_dampin: off}}\n" PHASE,
        "bad.yaml:11:54: stage 's1', rigid_body, terms: unknown key 'jet_dampin'");
    BAD(HEAD "    rigid_body: {inertia_full: {xx: 100, yy: 100, zz: 100},\n"
        "                 engine_position: {x: -0.5}, terms: {rate_damping_frame: body}}\n" PHASE,
        "bad.yaml:11:74: stage 's1', rigid_body, terms: rate_damping_frame");
    BAD(HEAD "    rigid_body: {inertia_full: {xx: 100, yy: 100, zz: 100},\n"
        "                 engine_position: {x: -0.5}, terms: off}\n" PHASE,
        "bad.yaml:11:53: stage 's1', rigid_body, terms: a mapping");
    BAD(HEAD "    rigid_body: {inertia_full: {xx: 100, yy: 100, zz: 100},\n"
        "                 engine_position: {x: -0.5}, nozzle_exit: {x: -1}}\n" PHASE,
        "bad.yaml:11:59: stage 's1', rigid_body, nozzle_exit: 'y' is missing");
    /* positions far outside any vehicle (1e300 failed `run` at the first step, not `check`) */
    BAD(HEAD "    rigid_body: {inertia_full: {xx: 100, yy: 100, zz: 100},\n"
        "                 engine_position: {x: -1e300}}\n" PHASE,
        "bad.yaml:11:39: stage 's1', rigid_body, engine_position: x must be >= -1000 and <= 1000 m, "
        "found -1e+300");
    BAD(HEAD "    rigid_body: {inertia_full: {xx: 100, yy: 100, zz: 100},\n"
        "                 engine_position: {x: -0.5}, nozzle_exit: {x: -1e5, y: 0, z: 0}}\n" PHASE,
        "bad.yaml:11:63: stage 's1', rigid_body, nozzle_exit: x must be >= -1000 and <= 1000 m, "
        "found -100000");
    /* a stage without engines needs no position */
    {
        static const char ok[] =
            "mission: {name: terms}\n"
            "environment: {world: planet, planet: earth, gravity: pointmass}\n"
            "parameters: {start_lat: 0, start_lon: 0, start_h: 2.0e6, start_vel: 7000,\n"
            "             start_fpa: 0, start_chi: 0}\n"
            "stages: [{name: s1, dry_mass: 600, propellant_mass: 0,\n"
            "          rigid_body: {inertia_full: {xx: 100, yy: 100, zz: 100}}}]\n"
            "phases: [{name: P, model: dof6, stages: [s1], stop_time: 8}]\n";
        lv_err err;
        lv_mission_def *m = NULL;
        CHECK_OK(lv_mission_def_parse(ok, strlen(ok), "ok.yaml", ".", &m, &err), &err);
        lv_mission_def_free(m);
    }
    /* the keys carried to the model: the closed form of test (1) through a mission file, the
     * body of (1) (1000 kg, 400 of them propellant), each combination of the two switches */
    static const char *const onoff[2] = {"off", "on"};
    const double mdot = 1e5 / (300.0 * LV_G0), idot = -40.0 * mdot / 400.0;
    const double x = (100.0 + idot * 8.0) / 100.0;
    /* combo 4: both on, with the nozzle exit at x = -1 m (l = 1 m for the jet damping) */
    for (int combo = 0; combo < 5; combo++) {
        const int A = combo == 4 ? 1 : combo & 1, B = combo == 4 ? 1 : (combo >> 1) & 1;
        const double l2 = combo == 4 ? 1.0 : 0.25;
        char yaml[2048];
        snprintf(yaml, sizeof yaml,
                 HEAD "    rigid_body: {inertia_full: {xx: 100, yy: 100, zz: 100},\n"
                 "                 inertia_empty: {xx: 60, yy: 60, zz: 60},\n"
                 "                 engine_position: {x: -0.5},%s\n"
                 "                 terms: {inertia_rate: %s, jet_damping: %s,\n"
                 "                         rate_damping_frame: inertial}}\n" PHASE,
                 combo == 4 ? " nozzle_exit: {x: -1, y: 0, z: 0}," : "", onoff[A], onoff[B]);
        FILE *f = fopen("test_dof6_terms.yaml", "w");
        CHECK(f != NULL);
        if (f == NULL)
            return;
        fputs(yaml, f);
        fclose(f);
        lv_err err;
        lv_mission *m = NULL;
        lv_run *r = NULL;
        CHECK_OK(lv_mission_load("test_dof6_terms.yaml", &m, &err), &err);
        if (m != NULL)
            CHECK_OK(lv_run_create(m, &r, &err), &err);
        if (r != NULL) {
            CHECK_OK(lv_run_execute(r, NULL, &err), &err);
            double p = NAN, q = NAN;
            CHECK_OK(lv_run_final(r, 0, "p", &p, &err), &err);
            CHECK_OK(lv_run_final(r, 0, "q", &q, &err), &err);
            CHECK_REL(p, 0.3 * pow(x, -(double)A), 1e-8);
            CHECK_REL(q, 0.2 * pow(x, -(A + B * mdot * l2 / idot)), 1e-8);
        }
        lv_run_free(r);
        lv_mission_free(m);
        remove("test_dof6_terms.yaml");
    }
}

int main(void)
{
    test_closed_form();
    test_jet_vector();
    test_damping_frame();
    test_config_errors();
    test_mission_keys();
    return check_report("test_dof6_terms");
}
