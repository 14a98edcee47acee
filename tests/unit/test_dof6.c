/* test_dof6.c - the 6-DoF rigid body (lv_dof6.h) through lv_simulate against known answers:
 * torque-free motion (conservation of inertial angular momentum and rotational kinetic
 * energy), the torque-free precession of an axisymmetric body, pure aerodynamic rate damping,
 * the quaternion norm, free fall equal to the 3-DoF model's, start attitude, thrust moment of a
 * gimballed engine and the mass properties, bad configurations. References are derived or
 * cited next to each check; none is the code's own output. */
#define _POSIX_C_SOURCE 200809L /* mkdir */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "check.h"
#include "mat_records.h"
#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_dof3.h"
#include "lvsim/lv_dof6.h"
#include "lvsim/lv_planet.h"
#include "lvsim/lv_io.h"
#include "lvsim/lv_mission.h"
#include "lvsim/lv_sim.h"
#include "lvsim/lv_summary.h"
#include "lvsim/lv_table.h"
#include "mission/mission.h"

#define DEG (M_PI / 180.0)

static lv_status run(const lv_model_def *def, void *inst, double t0, double tf,
                     const char *method, double tol, double step, size_t n_in,
                     const char *const *in, const double *iv, size_t n_fin,
                     const char *const *fin, double *out, lv_err *err)
{
    lv_sim_settings s;
    lv_sim_settings_default(&s);
    s.result_file = NULL;
    s.start_time = t0;
    s.stop_time = tf;
    s.method = method;
    s.tolerance = tol;
    s.fixed_step = step;
    s.number_of_intervals = 10;
    s.n_initial = n_in;
    s.initial_names = in;
    s.initial_values = iv;
    s.n_final = n_fin;
    s.final_names = fin;
    s.max_steps = 10000000;
    return lv_simulate(def, inst, &s, out, NULL, err);
}

/* C_eci_body of a unit quaternion (w, x, y, z) body -> ECI (Stevens & Lewis eq. 1.8-10),
 * written out here independently of the model. */
static void dcm(const double *q, double C[3][3])
{
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    C[0][0] = w * w + x * x - y * y - z * z;
    C[0][1] = 2.0 * (x * y - w * z);
    C[0][2] = 2.0 * (x * z + w * y);
    C[1][0] = 2.0 * (x * y + w * z);
    C[1][1] = w * w - x * x + y * y - z * z;
    C[1][2] = 2.0 * (y * z - w * x);
    C[2][0] = 2.0 * (x * z - w * y);
    C[2][1] = 2.0 * (y * z + w * x);
    C[2][2] = w * w - x * x - y * y + z * z;
}

/* Angular momentum in ECI H = C_eci_body I w and kinetic energy T = w.I w / 2 of a state
 * (quaternion normalised first). */
static void momentum(const double I[3][3], const double *q_in, const double *w, double H[3],
                     double *T)
{
    const double n = sqrt(q_in[0] * q_in[0] + q_in[1] * q_in[1] + q_in[2] * q_in[2] +
                          q_in[3] * q_in[3]);
    const double q[4] = {q_in[0] / n, q_in[1] / n, q_in[2] / n, q_in[3] / n};
    double C[3][3], Iw[3];
    dcm(q, C);
    for (int i = 0; i < 3; i++)
        Iw[i] = I[i][0] * w[0] + I[i][1] * w[1] + I[i][2] * w[2];
    for (int i = 0; i < 3; i++)
        H[i] = C[i][0] * Iw[0] + C[i][1] * Iw[1] + C[i][2] * Iw[2];
    *T = 0.5 * (w[0] * Iw[0] + w[1] * Iw[1] + w[2] * Iw[2]);
}

static lv_gravity *pointmass(const lv_planet *pl)
{
    lv_err err;
    lv_gravity_config gc = {"pointmass", 0, -1, NULL};
    lv_gravity *g = NULL;
    CHECK_OK(lv_gravity_create(pl, &gc, &g, &err), &err);
    return g;
}

/* A vehicle in free fall (an orbit) from 200 km, 7.5 km/s eastward relative to the Earth. */
static void free_fall_config(lv_dof6_config *cfg, const lv_gravity *g)
{
    lv_dof6_config_default(cfg);
    cfg->gravity = g;
    cfg->m0 = 500.0;
    cfg->start_lat = 28.5 * DEG;
    cfg->start_lon = -80.6 * DEG;
    cfg->start_h = 200e3;
    cfg->start_vel = 7500.0;
    cfg->start_fpa = 0.5 * DEG;
    cfg->start_chi = 90.0 * DEG;
}

static const char *const state_names[] = {"r_eci_x", "r_eci_y", "r_eci_z", "v_eci_x",
                                          "v_eci_y", "v_eci_z", "q_w",     "q_x",
                                          "q_y",     "q_z",     "p",       "q",
                                          "r",       "m",       "quat_norm"};

/* ---- (1) torque-free asymmetric body: H (inertial) and T conserved -------------------- */
/* Without external moment Euler's equations I w' = -w x I w conserve the angular momentum
 * in inertial axes, H = C_eci_body I w, and the kinetic energy of rotation T = w.I w / 2
 * (Goldstein, Classical Mechanics, 3rd ed., sec. 5.6). Gravity acts at the CG only (no
 * gravity gradient in the model), so free fall is torque-free. A full tensor with products of
 * inertia, rates near the intermediate axis (tumbling), 2000 s at 1e-10. */
static void test_torque_free(void)
{
    lv_err err;
    const lv_planet earth = lv_planet_earth();
    lv_gravity *g = pointmass(&earth);
    lv_dof6_config cfg;
    free_fall_config(&cfg, g);
    /* principal moments about 199, 300, 401 kg m^2: a real body's (I1 + I2 >= I3) */
    const double Ie[6] = {200.0, 300.0, 400.0, -10.0, 5.0, -8.0};
    memcpy(cfg.mass.inertia_full, Ie, sizeof Ie);
    memcpy(cfg.mass.inertia_empty, Ie, sizeof Ie);
    lv_dof6 *m = NULL;
    CHECK_OK(lv_dof6_create(&cfg, &m, &err), &err);
    if (m == NULL)
        return;
    const double qn = sqrt(0.9 * 0.9 + 0.1 * 0.1 + 0.3 * 0.3 + 0.2 * 0.2);
    const double q0[4] = {0.9 / qn, 0.1 / qn, -0.3 / qn, 0.2 / qn};
    const double w0[3] = {0.05, 0.4, 0.03}; /* mostly about y: the unstable axis */
    const char *in[] = {"q_w", "q_x", "q_y", "q_z", "p", "q", "r"};
    const double iv[] = {q0[0], q0[1], q0[2], q0[3], w0[0], w0[1], w0[2]};
    const double I[3][3] = {{200.0, -10.0, 5.0}, {-10.0, 300.0, -8.0}, {5.0, -8.0, 400.0}};
    /* Dormand-Prince 5(4) at 1e-10 keeps both within 1e-9 (measured 1.2e-11, 2.3e-11); the BDF
     * of "dassl" at 1e-10 drifts more, as BDF methods do on conservative oscillations
     * (measured 4.8e-7, 9.4e-7): within 5e-6. The quaternion norm within 1e-9 for both. */
    const char *method[] = {"dopri5", "dassl"};
    const double bound[] = {1e-9, 5e-6};
    for (int k = 0; k < 2; k++) {
        double out[15];
        CHECK_OK(run(lv_dof6_def(m), lv_dof6_inst(m), 0.0, 2000.0, method[k], 1e-10, 0.0, 7, in,
                     iv, 15, state_names, out, &err),
                 &err);
        double H0[3], T0, H1[3], T1;
        momentum(I, q0, w0, H0, &T0);
        momentum(I, out + 6, out + 10, H1, &T1);
        const double Hn = sqrt(H0[0] * H0[0] + H0[1] * H0[1] + H0[2] * H0[2]);
        const double dH =
            sqrt((H1[0] - H0[0]) * (H1[0] - H0[0]) + (H1[1] - H0[1]) * (H1[1] - H0[1]) +
                 (H1[2] - H0[2]) * (H1[2] - H0[2]));
        printf("torque-free, %s: |dH|/|H| = %.3g, dT/T = %.3g, |q| - 1 = %.3g\n", method[k],
               dH / Hn, (T1 - T0) / T0, out[14] - 1.0);
        CHECK(dH / Hn < bound[k]);
        CHECK_REL(T1, T0, bound[k]);
        /* (4) quaternion norm after 2000 s of tumbling (about 130 turns) */
        CHECK_CLOSE(out[14], 1.0, 1e-9);
        /* the rates did change: the body tumbles (not a trivial steady spin) */
        CHECK(fabs(out[10] - w0[0]) > 1e-3 || fabs(out[12] - w0[2]) > 1e-3);
    }
    lv_dof6_free(m);
    lv_gravity_free(g);
}

/* ---- (2) axisymmetric body: body-rate precession at lambda = (I3 - I1)/I1 r ------------- */
/* For I1 = I2, Euler's equations give r = const and p + i q = (p0 + i q0) exp(i lambda t),
 * lambda = (I3 - I1)/I1 r (Goldstein sec. 5.6, eq. 5.70): with q0 = 0,
 * p = p0 cos(lambda t), q = p0 sin(lambda t). I1 = 100, I3 = 180 (a flat body: I3 <= 2 I1 for
 * any axisymmetric one), r = 0.5 rad/s: lambda = 0.4 rad/s; checked at 4 times over 4 periods,
 * to 2e-8 rad/s (BDF at 1e-10: measured 1.1e-8 at 62.8 s). */
static void test_precession(void)
{
    lv_err err;
    const lv_planet earth = lv_planet_earth();
    lv_gravity *g = pointmass(&earth);
    lv_dof6_config cfg;
    free_fall_config(&cfg, g);
    const double Ie[6] = {100.0, 100.0, 180.0, 0.0, 0.0, 0.0};
    memcpy(cfg.mass.inertia_full, Ie, sizeof Ie);
    memcpy(cfg.mass.inertia_empty, Ie, sizeof Ie);
    cfg.start_p = 0.1;
    cfg.start_r = 0.5;
    lv_dof6 *m = NULL;
    CHECK_OK(lv_dof6_create(&cfg, &m, &err), &err);
    if (m == NULL)
        return;
    const double lambda = (180.0 - 100.0) / 100.0 * 0.5;
    const double tf[] = {1.0, 7.3, 31.0, 62.8};
    for (int k = 0; k < 4; k++) {
        double out[15];
        CHECK_OK(run(lv_dof6_def(m), lv_dof6_inst(m), 0.0, tf[k], "dassl", 1e-10, 0.0, 0, NULL,
                     NULL, 15, state_names, out, &err),
                 &err);
        CHECK_CLOSE(out[10], 0.1 * cos(lambda * tf[k]), 2e-8);
        CHECK_CLOSE(out[11], 0.1 * sin(lambda * tf[k]), 2e-8);
        CHECK_CLOSE(out[12], 0.5, 1e-12);
    }
    lv_dof6_free(m);
    lv_gravity_free(g);
}

/* ---- (3) pure rate damping: q = q0 exp(lambda t), and p, r likewise ---------------------------------- */
/* Only Cmq acts: Iyy q' = q_dyn S c Cmq q c / (2 V), so q = q0 exp(lambda t) with
 * lambda = q_dyn S c^2 Cmq / (2 V Iyy) (Etkin & Reid, Dynamics of Flight, 3rd ed., sec. 5.6:
 * the pitch damping term alone). Constant q_dyn and V: a non-rotating planet with negligible
 * gravity (gm = 1e-3 m^3/s^2), an exponential atmosphere of scale height 1e15 m (constant
 * density), no aerodynamic force (all force coefficients 0). rho0 = 1.225 kg/m^3, V = 200 m/s:
 * q_dyn = 24500 Pa; S = 10 m^2, c = 2 m, Cmq = -20 /rad, Iyy = 50000 kg m^2:
 * lambda = -0.98 1/s. */
static void test_pitch_damping(void)
{
    lv_err err;
    lv_planet pl = lv_planet_earth();
    pl.omega = 0.0;
    pl.gm = 1e-3;
    lv_gravity *g = pointmass(&pl);
    lv_atmo *atm = NULL;
    CHECK_OK(lv_atmo_create("exp", &atm, &err), &err);
    CHECK_OK(lv_atmo_set(atm, "H", 1e15, &err), &err);
    /* axis 0: roll (Clp, Ixx, b), 1: pitch (Cmq, Iyy, c), 2: yaw (Cnr, Izz, b). A rate about one
     * principal axis alone stays alone (the gyroscopic terms need two), so each decays as the
     * pitch rate above with its own derivative, inertia and length. */
    const double Iax[3] = {20000.0, 50000.0, 60000.0}, deriv[3] = {-8.0, -20.0, -15.0};
    const double len[3] = {3.0, 2.0, 3.0};
    const char *rate[3] = {"p", "q", "r"}, *mom[3] = {"L_aero", "M_aero", "N_aero"};
    for (int ax = 0; ax < 3; ax++) {
        lv_dof6_config cfg;
        lv_dof6_config_default(&cfg);
        cfg.planet = pl;
        cfg.gravity = g;
        cfg.atmo = atm;
        cfg.m0 = 1000.0;
        cfg.start_h = 1000.0;
        cfg.start_vel = 200.0;
        cfg.start_chi = 30.0 * DEG;
        cfg.start_psi = 30.0 * DEG; /* flying along body x: alpha = beta = 0 at the start */
        const double w0 = 0.2;
        if (ax == 0)
            cfg.start_p = w0;
        else if (ax == 1)
            cfg.start_q = w0;
        else
            cfg.start_r = w0;
        for (int i = 0; i < 3; i++)
            cfg.mass.inertia_full[i] = cfg.mass.inertia_empty[i] = Iax[i];
        lv_aero_config ac;
        lv_aero_config_default(&ac);
        ac.s_ref = 10.0;
        cfg.aero = &ac;
        lv_dof6_moments mo;
        memset(&mo, 0, sizeof mo);
        mo.clp = deriv[0];
        mo.cmq = deriv[1];
        mo.cnr = deriv[2];
        mo.b_ref = 3.0;
        mo.c_ref = 2.0;
        cfg.moments = &mo;
        lv_dof6 *m = NULL;
        CHECK_OK(lv_dof6_create(&cfg, &m, &err), &err);
        if (m == NULL)
            continue;
        const double qd = 0.5 * 1.225 * 200.0 * 200.0; /* 24500 Pa */
        const double lambda = qd * 10.0 * len[ax] * len[ax] * deriv[ax] / (2.0 * 200.0 * Iax[ax]);
        const double tf[] = {0.5, 2.0, 5.0};
        for (int k = 0; k < 3; k++) {
            const char *fin[] = {rate[ax], rate[(ax + 1) % 3], rate[(ax + 2) % 3], "q_dyn",
                                 mom[ax]};
            double out[5];
            CHECK_OK(run(lv_dof6_def(m), lv_dof6_inst(m), 0.0, tf[k], "dassl", 1e-10, 0.0, 0,
                         NULL, NULL, 5, fin, out, &err),
                     &err);
            /* relative 1e-7, or the rates' absolute tolerance 1e-10 x 0.01 rad/s (x 10) once the
             * rate has decayed to e^-11 of its start (roll at 5 s) */
            const double ref = w0 * exp(lambda * tf[k]);
            CHECK_CLOSE(out[0], ref, 1e-7 * ref + 1e-11);
            CHECK_CLOSE(out[1], 0.0, 1e-15);
            CHECK_CLOSE(out[2], 0.0, 1e-15);
            CHECK_REL(out[3], qd, 1e-9);
            /* the moment the output reports: q_dyn S l C_x w l / (2 V) */
            CHECK_REL(out[4], qd * 10.0 * len[ax] * deriv[ax] * out[0] * len[ax] / 400.0, 1e-9);
        }
        lv_dof6_free(m);
    }
    lv_atmo_free(atm);
    lv_gravity_free(g);
}

/* ---- moment reference point ahead of the CG: M_cg = (r_mrp - r_cg) x F ----------------- */
/* A constant normal-force coefficient CN = 0.5 (body axes) with Cm = 0 about a reference point
 * 5 m ahead of the CG: F = (0, 0, -q S CN), M_cg = (5, 0, 0) x F = (0, 5 q S CN, 0), a nose-up
 * (destabilising) moment, whatever the attitude; same air as above. Checked at the start. */
static void test_moment_transfer(void)
{
    lv_err err;
    lv_planet pl = lv_planet_earth();
    pl.omega = 0.0;
    pl.gm = 1e-3;
    lv_gravity *g = pointmass(&pl);
    lv_atmo *atm = NULL;
    CHECK_OK(lv_atmo_create("exp", &atm, &err), &err);
    CHECK_OK(lv_atmo_set(atm, "H", 1e15, &err), &err);
    lv_dof6_config cfg;
    lv_dof6_config_default(&cfg);
    cfg.planet = pl;
    cfg.gravity = g;
    cfg.atmo = atm;
    cfg.start_h = 1000.0;
    cfg.start_vel = 200.0;
    cfg.mass.cg_full[0] = cfg.mass.cg_empty[0] = -10.0;
    for (int i = 0; i < 3; i++)
        cfg.mass.inertia_full[i] = cfg.mass.inertia_empty[i] = 1e6;
    lv_aero_config ac;
    lv_aero_config_default(&ac);
    ac.axes = LV_AERO_BODY;
    ac.s_ref = 10.0;
    ac.coef[1].value = 0.5;
    cfg.aero = &ac;
    lv_dof6_moments mo;
    memset(&mo, 0, sizeof mo);
    mo.b_ref = mo.c_ref = 2.0;
    mo.r_mrp[0] = -5.0;
    cfg.moments = &mo;
    lv_dof6 *m = NULL;
    CHECK_OK(lv_dof6_create(&cfg, &m, &err), &err);
    if (m != NULL) {
        const char *fin[] = {"M_aero", "L_aero", "N_aero", "q_dyn", "n_normal"};
        double out[5];
        CHECK_OK(run(lv_dof6_def(m), lv_dof6_inst(m), 0.0, 1e-6, "dassl", 1e-10, 0.0, 0, NULL,
                     NULL, 5, fin, out, &err),
                 &err);
        CHECK_REL(out[0], 5.0 * out[3] * 10.0 * 0.5, 1e-12);
        CHECK_REL(out[3], 24500.0, 1e-6);
        CHECK_CLOSE(out[1], 0.0, 1e-9);
        CHECK_CLOSE(out[2], 0.0, 1e-9);
        CHECK_REL(out[4], out[3] * 10.0 * 0.5 / 1000.0 / LV_G0, 1e-12); /* F_N / (m g0) */
        lv_dof6_free(m);
    }
    lv_atmo_free(atm);
    lv_gravity_free(g);
}

/* ---- (4) quaternion norm under a fast spin at a loose tolerance ------------------------- */
/* 10 rad/s about a tilted axis for 200 s (320 turns) at the missions' default tolerance 1e-6:
 * the integrator's error (BDF damps the quaternion's oscillation) makes |q| drift; the
 * correction K (1 - |q|^2) q pulls it back at the rate 2 K = 2/s. Bounds at every output row:
 * BDF ("dassl") 1e-4 (measured 2.4e-5; without the correction, K = 0, 8.4e-3), dopri5 2e-6
 * (measured 5.0e-7; K = 0: 3.2e-4). A spherical inertia keeps w constant: the rates check
 * the attitude integration leaves the dynamics alone (1e-6 relative). */
static void test_quat_norm_spin(void)
{
    lv_err err;
    const lv_planet earth = lv_planet_earth();
    lv_gravity *g = pointmass(&earth);
    lv_dof6_config cfg;
    free_fall_config(&cfg, g);
    cfg.start_p = 10.0 * cos(30.0 * DEG);
    cfg.start_r = 10.0 * sin(30.0 * DEG);
    lv_dof6 *m = NULL;
    CHECK_OK(lv_dof6_create(&cfg, &m, &err), &err);
    if (m == NULL)
        return;
    const char *method[] = {"dassl", "dopri5"};
    for (int k = 0; k < 2; k++) {
        lv_sink sink;
        lv_result *res = NULL;
        lv_sim_settings s;
        lv_sim_settings_default(&s);
        s.result_file = NULL;
        s.stop_time = 200.0;
        s.method = method[k];
        s.tolerance = 1e-6;
        s.number_of_intervals = 400;
        s.max_steps = 10000000;
        const char *fin[] = {"p", "r"};
        double out[2];
        s.n_final = 2;
        s.final_names = fin;
        CHECK_OK(lv_sink_memory_create(&res, &sink, &err), &err);
        s.n_sinks = 1;
        s.sinks = &sink;
        CHECK_OK(lv_simulate(lv_dof6_def(m), lv_dof6_inst(m), &s, out, NULL, &err), &err);
        size_t col = 0;
        double worst = 0.0;
        if (res != NULL && lv_result_column(res, "quat_norm", &col, &err) == LV_OK)
            for (size_t i = 0; i < lv_result_rows(res); i++) {
                const double d = fabs(lv_result_value(res, i, col) - 1.0);
                worst = d > worst ? d : worst;
            }
        printf("fast spin, %s at 1e-6: max | |q| - 1 | = %.3g over %zu rows\n", method[k], worst,
               res != NULL ? lv_result_rows(res) : (size_t)0);
        CHECK(res != NULL && lv_result_rows(res) > 400);
        CHECK(worst < (k == 0 ? 1e-4 : 2e-6));
        CHECK_REL(out[0], 10.0 * cos(30.0 * DEG), 1e-6);
        CHECK_REL(out[1], 10.0 * sin(30.0 * DEG), 1e-6);
        lv_sink_destroy(&sink);
        lv_result_free(res);
    }
    lv_dof6_free(m);
    lv_gravity_free(g);
}

/* ---- (5) free fall over the rotating Earth = the 3-DoF model's translation ------------- */
/* Both models integrate r'' = g(r) in ECI with the same gravity function; with no force but
 * gravity the 6-DoF translation is the 3-DoF one. With the fixed-step RK4 (same steps) the
 * positions and velocities agree to the last bit; with the adaptive BDF at 1e-10 (other states,
 * other steps) to the tolerance (1 mm, 1 um/s after a 600 s arc). J2 gravity, a tumbling body. */
static void test_vs_dof3(void)
{
    lv_err err;
    const lv_planet earth = lv_planet_earth();
    lv_gravity_config gc = {"j2", 0, -1, NULL};
    lv_gravity *g = NULL;
    CHECK_OK(lv_gravity_create(&earth, &gc, &g, &err), &err);
    lv_dof6_config c6;
    free_fall_config(&c6, g);
    c6.start_p = 0.3;
    c6.start_q = -0.2;
    c6.start_r = 0.1;
    c6.mass.inertia_full[1] = c6.mass.inertia_empty[1] = 2.0;
    lv_dof3_config c3;
    lv_dof3_config_default(&c3);
    c3.gravity = g;
    c3.m0 = c6.m0;
    c3.start_lat = c6.start_lat;
    c3.start_lon = c6.start_lon;
    c3.start_h = c6.start_h;
    c3.start_vel = c6.start_vel;
    c3.start_fpa = c6.start_fpa;
    c3.start_chi = c6.start_chi;
    lv_dof6 *m6 = NULL;
    lv_dof3 *m3 = NULL;
    CHECK_OK(lv_dof6_create(&c6, &m6, &err), &err);
    CHECK_OK(lv_dof3_create(&c3, &m3, &err), &err);
    if (m6 == NULL || m3 == NULL)
        return;
    const char *fin[] = {"r_eci_x", "r_eci_y", "r_eci_z", "v_eci_x", "v_eci_y", "v_eci_z", "m"};
    double o6[7], o3[7];
    CHECK_OK(run(lv_dof6_def(m6), lv_dof6_inst(m6), 0.0, 600.0, "rk4", 1e-6, 0.5, 0, NULL, NULL,
                 7, fin, o6, &err),
             &err);
    CHECK_OK(run(lv_dof3_def(m3), lv_dof3_inst(m3), 0.0, 600.0, "rk4", 1e-6, 0.5, 0, NULL, NULL,
                 7, fin, o3, &err),
             &err);
    for (int i = 0; i < 7; i++)
        CHECK(o6[i] == o3[i]);
    /* the outputs both models have mean the same: equal at the same state */
    const char *same[] = {"h", "lat", "lon", "lat_gc", "radius", "v_north", "v_east", "v_down",
                          "v_rel", "v_inertial", "fpa", "heading", "fpa_inertial",
                          "heading_inertial", "accel", "accel_sensed", "sma", "ecc", "inc",
                          "raan", "argp", "apo_alt", "peri_alt", "downrange", "mach", "q_dyn",
                          "thrust", "mdot", "engine_on", "throttle_eff", "engines_running"};
    const size_t n_same = sizeof same / sizeof same[0];
    /* issue 27 (L7): dof6 has dof3's engine columns, with dof3's unit and description */
    const char *eng_cols[] = {"throttle_eff", "engines_running"};
    for (int j = 0; j < 2; j++) {
        const lv_model_def *d3 = lv_dof3_def(m3), *d6 = lv_dof6_def(m6);
        const lv_var *v3 = NULL, *v6 = NULL;
        for (size_t i = 0; i < d3->n_outputs; i++)
            if (strcmp(d3->outputs[i].name, eng_cols[j]) == 0)
                v3 = &d3->outputs[i];
        for (size_t i = 0; i < d6->n_outputs; i++)
            if (strcmp(d6->outputs[i].name, eng_cols[j]) == 0)
                v6 = &d6->outputs[i];
        CHECK(v3 != NULL && v6 != NULL);
        if (v3 != NULL && v6 != NULL) {
            CHECK(strcmp(v6->unit, "1") == 0 && strcmp(v3->unit, v6->unit) == 0);
            CHECK(strcmp(v3->description, v6->description) == 0);
        }
    }
    double s6[32], s3[32];
    /* at several states along the fall (the radius once differed by an ulp on some: the norm
     * of lv_vec3 against dof3's hypot) */
    const double t_end[] = {0.5, 1.0, 3.5, 17.0, 50.0, 123.5, 311.0, 600.0};
    for (size_t k = 0; k < sizeof t_end / sizeof t_end[0]; k++) {
        CHECK_OK(run(lv_dof6_def(m6), lv_dof6_inst(m6), 0.0, t_end[k], "rk4", 1e-6, 0.5, 0, NULL,
                     NULL, n_same, same, s6, &err),
                 &err);
        CHECK_OK(run(lv_dof3_def(m3), lv_dof3_inst(m3), 0.0, t_end[k], "rk4", 1e-6, 0.5, 0, NULL,
                     NULL, n_same, same, s3, &err),
                 &err);
        for (size_t i = 0; i < n_same; i++) {
            check_count_++;
            if (s6[i] != s3[i]) {
                check_failures_++;
                fprintf(stderr, "%s:%d: t = %g s, output '%s': dof6 %.17g, dof3 %.17g\n",
                        __FILE__, __LINE__, t_end[k], same[i], s6[i], s3[i]);
            }
        }
    }
    CHECK_OK(run(lv_dof6_def(m6), lv_dof6_inst(m6), 0.0, 600.0, "dassl", 1e-10, 0.0, 0, NULL,
                 NULL, 7, fin, o6, &err),
             &err);
    CHECK_OK(run(lv_dof3_def(m3), lv_dof3_inst(m3), 0.0, 600.0, "dassl", 1e-10, 0.0, 0, NULL,
                 NULL, 7, fin, o3, &err),
             &err);
    for (int i = 0; i < 3; i++) {
        CHECK_CLOSE(o6[i], o3[i], 1e-3);
        CHECK_CLOSE(o6[3 + i], o3[3 + i], 1e-6);
    }
    lv_dof6_free(m6);
    lv_dof3_free(m3);
    lv_gravity_free(g);
}

/* ---- start attitude: the outputs psi, theta, phi give back the start values ------------ */
/* The quaternion is built from C_eci_body = C_eci_ecef C_ecef_ned C_ned_body; the outputs
 * read the 3-2-1 angles back from the body axes in NED. Over 1 us the local NED frame turns under
 * the inertially fixed body (no rates) by the orbital rate v / r ~ 1.1e-3 rad/s times 1 us,
 * 1.1e-9 rad: the tolerance 1e-8 rad. */
static void test_start_attitude(void)
{
    lv_err err;
    const lv_planet earth = lv_planet_earth();
    lv_gravity *g = pointmass(&earth);
    lv_dof6_config cfg;
    free_fall_config(&cfg, g);
    cfg.start_time = 50.0;
    cfg.start_psi = 250.0 * DEG;
    cfg.start_theta = 35.0 * DEG;
    cfg.start_phi = -20.0 * DEG;
    lv_dof6 *m = NULL;
    CHECK_OK(lv_dof6_create(&cfg, &m, &err), &err);
    if (m == NULL)
        return;
    const char *fin[] = {"psi", "theta", "phi", "quat_norm"};
    double out[4];
    CHECK_OK(run(lv_dof6_def(m), lv_dof6_inst(m), 50.0, 50.000001, "dassl", 1e-10, 0.0, 0, NULL,
                 NULL, 4, fin, out, &err),
             &err);
    CHECK_CLOSE(out[0], 250.0 * DEG, 1e-8);
    CHECK_CLOSE(out[1], 35.0 * DEG, 1e-8);
    CHECK_CLOSE(out[2], -20.0 * DEG, 1e-8);
    CHECK_CLOSE(out[3], 1.0, 1e-12);
    lv_dof6_free(m);
    lv_gravity_free(g);
}

/* ---- thrust moment of a gimballed engine, mass properties ----------------------------- */
/* One engine of 100 kN (vacuum, constant) at x = -10 m, the CG at x = -4 m (full) and
 * -6 m (empty), gimballed 2 deg in pitch: the thrust (cos d, 0, sin d) T at r_e = (x_e - x_cg,
 * 0, 0) gives M = r_e x F, M_y = -(x_e - x_cg) T sin d. Half the propellant used: cg_x = -5 m,
 * Ixx halfway. At the start (full): M_y = 6 m T sin 2 deg; the axial force T cos 2 deg. */
static void test_thrust_moment(void)
{
    lv_err err;
    const lv_planet earth = lv_planet_earth();
    lv_gravity *g = pointmass(&earth);
    lv_dof6_config cfg;
    free_fall_config(&cfg, g);
    cfg.m0 = 1000.0;
    cfg.propellant = 400.0;
    const double If[6] = {100.0, 2000.0, 2000.0, 0, 0, 0}, Iz[6] = {60.0, 1200.0, 1200.0, 0, 0, 0};
    memcpy(cfg.mass.inertia_full, If, sizeof If);
    memcpy(cfg.mass.inertia_empty, Iz, sizeof Iz);
    cfg.mass.cg_full[0] = -4.0;
    cfg.mass.cg_empty[0] = -6.0;
    lv_engine_config ec;
    lv_engine_config_default(&ec);
    ec.thrust_vac = 1e5;
    ec.isp_vac = 300.0;
    lv_dof6_engine_geom eg = {{-10.0, 0.0, 0.0}, 0.0, 0.0};
    cfg.n_engines = 1;
    cfg.engines = &ec;
    cfg.engine_geom = &eg;
    cfg.gimbal_pitch = 2.0 * DEG;
    cfg.start_p = 0.5;
    lv_dof6 *m = NULL;
    CHECK_OK(lv_dof6_create(&cfg, &m, &err), &err);
    if (m == NULL)
        return;
    const char *fin[] = {"M_thrust", "L_thrust", "N_thrust", "cg_x", "I_xx", "thrust", "m", "p"};
    double out[8];
    /* to half the propellant: t = 200 kg / (T / (Isp g0)) */
    const double t_half = 200.0 / (1e5 / (300.0 * LV_G0));
    CHECK_OK(run(lv_dof6_def(m), lv_dof6_inst(m), 0.0, t_half, "dassl", 1e-10, 0.0, 0, NULL,
                 NULL, 8, fin, out, &err),
             &err);
    CHECK_REL(out[6], 800.0, 1e-9);
    /* Roll with a varying Ixx: the exhaust of an engine on the x axis carries no angular
     * momentum about x (r_e x (w x r_e) has no x component), and Iyy = Izz removes the gyroscopic
     * term, so Ixx p is constant (Thomson ch. 8: d(I w)/dt = M - jet flux): p = p0 Ixx0 / Ixx =
     * 0.5 x 100 / 80 - the check of the mass-variation term I' w. */
    CHECK_REL(out[7], 0.5 * 100.0 / 80.0, 1e-8);
    CHECK_REL(out[3], -5.0, 1e-8);
    CHECK_REL(out[4], 80.0, 1e-8);
    CHECK_REL(out[5], 1e5, 1e-12);
    /* M_y = -(x_e - x_cg) T sin d = 5 m T sin d, plus the jet damping -mdot r_e x (w x r_e)
     * which is along y with the pitch rate q: -mdot (x_e - x_cg)^2 q; read q back to check */
    const char *fin2[] = {"q", "mdot", "M_thrust", "r"};
    double o2[4];
    CHECK_OK(run(lv_dof6_def(m), lv_dof6_inst(m), 0.0, t_half, "dassl", 1e-10, 0.0, 0, NULL,
                 NULL, 4, fin2, o2, &err),
             &err);
    CHECK_REL(o2[2], 5.0 * 1e5 * sin(2.0 * DEG) - o2[1] * 25.0 * o2[0], 1e-9);
    CHECK(o2[0] > 0.0); /* nose up */
    CHECK_CLOSE(out[1], 0.0, 1e-9);
    /* the roll couples q into r; N is the jet damping of r alone: -mdot (x_e - x_cg)^2 r */
    CHECK_REL(out[2], -o2[1] * 25.0 * o2[3], 1e-9);
    lv_dof6_free(m);
    lv_gravity_free(g);
}

/* ---- gimbal angles from a table over time ---------------------------------------------- */
/* gimbal_pitch ramps 0 -> 0.01 rad over [0, 1] s and holds, gimbal_yaw holds -0.02 rad: at
 * t = 0.5 s the angles in effect are 0.005 and -0.02 rad (linear interpolation), and the thrust
 * moment about y is (x_cg - x_e) T sin(dp) cos(dy) plus the jet damping of q (as above). */
static void test_gimbal_table(void)
{
    lv_err err;
    const lv_planet earth = lv_planet_earth();
    lv_gravity *g = pointmass(&earth);
    double tt[3] = {0.0, 1.0, 2.0}, y[6] = {0.0, -0.02, 0.01, -0.02, 0.01, -0.02};
    const char *outs[] = {"gimbal_pitch", "gimbal_yaw"};
    const char *units[] = {"rad", "rad"};
    lv_table_spec ts = {.n_dims = 1, .n = {3}, .x = {tt}, .n_out = 2, .y = y,
                        .interp = LV_INTERP_LINEAR, .extrap = LV_EXTRAP_CLAMP, .name = "gimbal",
                        .axis_name = {"time"}, .out_name = outs, .axis_unit = {"s"},
                        .out_unit = units};
    lv_table *tab = NULL;
    CHECK_OK(lv_table_create(&ts, &tab, &err), &err);
    lv_dof6_config cfg;
    free_fall_config(&cfg, g);
    cfg.m0 = 1000.0;
    cfg.propellant = 400.0;
    const double Ie[6] = {100.0, 2000.0, 2000.0, 0, 0, 0};
    memcpy(cfg.mass.inertia_full, Ie, sizeof Ie);
    memcpy(cfg.mass.inertia_empty, Ie, sizeof Ie);
    cfg.mass.cg_full[0] = cfg.mass.cg_empty[0] = -4.0;
    lv_engine_config ec;
    lv_engine_config_default(&ec);
    ec.thrust_vac = 1e5;
    ec.isp_vac = 300.0;
    lv_dof6_engine_geom eg = {{-10.0, 0.0, 0.0}, 0.0, 0.0};
    cfg.n_engines = 1;
    cfg.engines = &ec;
    cfg.engine_geom = &eg;
    cfg.inputs = tab;
    lv_dof6 *m = NULL;
    CHECK_OK(lv_dof6_create(&cfg, &m, &err), &err);
    if (m != NULL) {
        const char *fin[] = {"gimbal_pitch_in", "gimbal_yaw_in", "M_thrust", "q", "mdot"};
        double out[5];
        CHECK_OK(run(lv_dof6_def(m), lv_dof6_inst(m), 0.0, 0.5, "dassl", 1e-10, 0.0, 0, NULL,
                     NULL, 5, fin, out, &err),
                 &err);
        CHECK_CLOSE(out[0], 0.005, 1e-15);
        CHECK_CLOSE(out[1], -0.02, 1e-15);
        CHECK_REL(out[2], 6.0 * 1e5 * sin(0.005) * cos(-0.02) - out[4] * 36.0 * out[3], 1e-12);
        lv_dof6_free(m);
    }
    lv_table_free(tab);
    lv_gravity_free(g);
}

/* ---- bad configurations ---------------------------------------------------------------- */
static void test_bad_config(void)
{
    lv_err err;
    const lv_planet earth = lv_planet_earth();
    lv_gravity *g = pointmass(&earth);
    lv_dof6_config cfg;
    free_fall_config(&cfg, g);
    cfg.mass.inertia_full[0] = -1.0;
    lv_dof6 *m = NULL;
    CHECK(lv_dof6_create(&cfg, &m, &err) == LV_ERR_INPUT);
    CHECK(m == NULL);
    CHECK(strstr(err.msg, "positive definite") != NULL);
    free_fall_config(&cfg, g);
    cfg.mass.m_full = 100.0;
    cfg.mass.m_empty = 200.0;
    CHECK(lv_dof6_create(&cfg, &m, &err) == LV_ERR_INPUT);
    CHECK(strstr(err.msg, "m_empty") != NULL);
    free_fall_config(&cfg, g);
    lv_dof6_moments mo;
    memset(&mo, 0, sizeof mo);
    mo.b_ref = mo.c_ref = 1.0;
    cfg.moments = &mo; /* without a force set */
    CHECK(lv_dof6_create(&cfg, &m, &err) == LV_ERR_INPUT);
    CHECK(strstr(err.msg, "reference area") != NULL);
    lv_gravity_free(g);
}

/* ---- missions: the dof6 phase type, parse errors, hand-offs -------------------------------- */

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

#define HEAD0                                                                               \
    "mission: {name: six}\n"                                                                \
    "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}\n"          \
    "parameters: {start_lat_deg: 5, start_lon_deg: -52, start_h: 0, start_vel: 1,\n"        \
    "             start_fpa_deg: 89, start_chi_deg: 90}\n"                                   \
    "stages:\n"
#define STAGE_RB                                                                            \
    "  - {name: s1, dry_mass: 20000, propellant_mass: 100000,\n"                            \
    "     engines: [{name: e, thrust_vac: 2.0e6, isp_vac: 300}],\n"                         \
    "     rigid_body: {inertia_full: {xx: 2.0e5, yy: 8.0e6, zz: 8.0e6},\n"                  \
    "                  inertia_empty: {xx: 5.0e4, yy: 2.0e6, zz: 2.0e6},\n"                 \
    "                  cg_full: {x: -15}, cg_empty: {x: -20}, engine_position: {x: -30}}}\n"
#define STAGE_PLAIN                                                                         \
    "  - {name: s1, dry_mass: 20000, propellant_mass: 100000,\n"                            \
    "     engines: [{name: e, thrust_vac: 2.0e6, isp_vac: 300}]}\n"

static void test_mission_errors(void)
{
    BAD(HEAD0 STAGE_PLAIN "phases:\n"
        "  - {name: P, model: dof6, stages: [s1], stop_time: 10}\n",
        "bad.yaml:9:5: phase 'P': model dof6 needs the rigid-body data of its bottom stage 's1'");
    BAD(HEAD0 "  - {name: s1, dry_mass: 1, propellant_mass: 1, rigid_body: {cg_full: {x: 1}}}\n"
        "phases:\n"
        "  - {name: P, model: dof6, stages: [s1], stop_time: 10}\n",
        "bad.yaml:6:61: stage 's1', rigid_body: 'inertia_full' is missing");
    BAD(HEAD0 "  - {name: s1, dry_mass: 1, propellant_mass: 1,\n"
        "     rigid_body: {inertia_full: {xx: 1, yy: 1, zz: 1, xq: 0}}}\n"
        "phases:\n"
        "  - {name: P, model: dof6, stages: [s1], stop_time: 10}\n",
        "bad.yaml:7:55: stage 's1', rigid_body, inertia_full: unknown key 'xq'");
    BAD(HEAD0 "  - {name: s1, dry_mass: 1, propellant_mass: 1,\n"
        "     rigid_body: {inertia_full: {xx: 1, yy: 1}}}\n"
        "phases:\n"
        "  - {name: P, model: dof6, stages: [s1], stop_time: 10}\n",
        "bad.yaml:7:33: stage 's1', rigid_body, inertia_full: 'zz' is missing");
    BAD(HEAD0 STAGE_RB "phases:\n"
        "  - {name: P, model: dof6, stages: [s1], stop_time: 10, attitude: {theta_deg: 95}}\n",
        "bad.yaml:12:79: phase 'P', attitude: theta_deg must be >= -90 and <= 90 deg, found 95");
    BAD(HEAD0 STAGE_RB "phases:\n"
        "  - {name: P, model: dof6, stages: [s1], stop_time: 10, moments: {Cmq: -1}}\n",
        "bad.yaml:12:57: phase 'P', moments: aerodynamic moments need the phase's `aero:`");
    BAD(HEAD0 STAGE_RB "phases:\n"
        "  - {name: P, model: dof6, stages: [s1], stop_time: 10, aero: {s_ref: 10},\n"
        "     moments: {Cmq: -1, b_ref: 4}}\n",
        "bad.yaml:13:15: phase 'P', moments: 'c_ref' is missing");
    BAD(HEAD0 STAGE_RB "phases:\n"
        "  - {name: P, model: dof6, stages: [s1], stop_time: 10, rates: {q_degs: 1}}\n",
        "bad.yaml:12:65: phase 'P', rates: unknown key 'q_degs'");
    BAD(HEAD0 STAGE_RB "phases:\n"
        "  - {name: A, model: dof3, stages: [s1], stop_time: 10}\n"
        "  - {name: P, model: dof6, stages: [s1], from: A, stop_time: 20,\n"
        "     attitude: {theta_deg: 80}}\n",
        "bad.yaml:14:6: phase 'P': 'attitude': a phase with `from` starts with its parent's");
    BAD("mission: {name: six}\n"
        "environment: {world: planet, planet: earth}\n"
        "parameters: {start_q_deg: 1}\n"
        "stages:\n" STAGE_RB "phases:\n"
        "  - {name: P, model: dof6, stages: [s1], stop_time: 10, rates: {q_deg: 2}}\n",
        "bad.yaml:11:57: phase 'P': 'rates': the mission's `parameters:` give start_q already");
}

static lv_run *run_text_to(const char *path, const char *yaml, const char *outdir,
                           lv_mission **mp);
static lv_run *run_text(const char *path, const char *yaml, lv_mission **mp)
{
    return run_text_to(path, yaml, NULL, mp);
}

/* As run_text, with the result files in outdir (NULL: none). */
static lv_run *run_text_to(const char *path, const char *yaml, const char *outdir,
                           lv_mission **mp)
{
    lv_err err;
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (f == NULL)
        return NULL;
    fputs(yaml, f);
    fclose(f);
    *mp = NULL;
    CHECK_OK(lv_mission_load(path, mp, &err), &err);
    if (*mp == NULL)
        return NULL;
    lv_run *r = NULL;
    CHECK_OK(lv_run_create(*mp, &r, &err), &err);
    lv_run_options opt = {.outdir = outdir, .threads = 2};
    if (r != NULL)
        CHECK_OK(lv_run_execute(r, outdir != NULL ? &opt : NULL, &err), &err);
    remove(path);
    return r;
}

/* The first row of phase k equals the final values of phase k - 1 in `names` (tolerance tol). */
static void check_continuous(lv_run *r, size_t k, const char *const *names, size_t n, double tol)
{
    lv_err err;
    const lv_result *rows = lv_run_rows(r, k);
    CHECK(rows != NULL && lv_result_rows(rows) > 0);
    for (size_t i = 0; rows != NULL && i < n; i++) {
        double fv;
        size_t col = 0;
        CHECK_OK(lv_run_final(r, k - 1, names[i], &fv, &err), &err);
        CHECK_OK(lv_result_column(rows, names[i], &col, &err), &err);
        if (tol == 0.0)
            CHECK(lv_result_value(rows, 0, col) == fv);
        else
            CHECK_CLOSE(lv_result_value(rows, 0, col), fv, tol);
    }
}

/* A root dof6 phase starts with the attitude and rates of `attitude:` and `rates:`; a dof3
 * ascent hands over to a dof6 coast (attitude from the dof3 final theta, psi, phi; rates 0),
 * which hands over to a dof3 coast: position, velocity and mass continuous to the bit. */
static void test_mission_handoffs(void)
{
    lv_mission *m = NULL;
    lv_err err;
    lv_run *r = run_text("test_dof6_root.yaml",
                         HEAD0 STAGE_RB "phases:\n"
                         "  - {name: P, model: dof6, stages: [s1], stop_time: 5,\n"
                         "     attitude: {psi_deg: 90, theta_deg: 88, phi_deg: 10},\n"
                         "     rates: {p_deg: 1, q_deg: -0.5, r: 0.01},\n"
                         "     inputs: {gimbal_pitch_deg: 0.5}}\n",
                         &m);
    if (r != NULL) {
        const lv_result *rows = lv_run_rows(r, 0);
        const char *nm[] = {"psi", "theta", "phi", "p", "q", "r", "gimbal_pitch_in"};
        const double want[] = {90.0 * DEG, 88.0 * DEG, 10.0 * DEG, 1.0 * DEG, -0.5 * DEG, 0.01,
                               0.5 * DEG};
        for (int i = 0; rows != NULL && i < 7; i++) {
            size_t col = 0;
            CHECK_OK(lv_result_column(rows, nm[i], &col, &err), &err);
            CHECK_CLOSE(lv_result_value(rows, 0, col), want[i], 1e-12);
        }
        double h;
        CHECK_OK(lv_run_final(r, 0, "h", &h, &err), &err);
        CHECK(h > 50.0); /* it flew up: about (T/m - g) t^2 / 2 = 86 m */
        lv_run_free(r);
    }
    lv_mission_free(m);

    /* the same start through the mission's parameter set, with the paper's Table 1 names */
    r = run_text("test_dof6_table1.yaml",
                 "mission: {name: six}\n"
                 "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}\n"
                 "parameters: {start_lat_deg: 5, start_lon_deg: -52, start_h: 0, start_vel: 1,\n"
                 "             start_fpa_deg: 89, start_chi_deg: 90, start_psi_deg: 90,\n"
                 "             start_theta_deg: 88, start_phi_deg: 10, start_p_deg: 1,\n"
                 "             start_q_deg: -0.5, start_r: 0.01}\n"
                 "stages:\n" STAGE_RB "phases:\n"
                 "  - {name: P, model: dof6, stages: [s1], stop_time: 5}\n",
                 &m);
    if (r != NULL) {
        const lv_result *rows = lv_run_rows(r, 0);
        const char *nm[] = {"psi", "theta", "phi", "p", "q", "r"};
        const double want[] = {90.0 * DEG, 88.0 * DEG, 10.0 * DEG, 1.0 * DEG, -0.5 * DEG, 0.01};
        for (int i = 0; rows != NULL && i < 6; i++) {
            size_t col = 0;
            CHECK_OK(lv_result_column(rows, nm[i], &col, &err), &err);
            CHECK_CLOSE(lv_result_value(rows, 0, col), want[i], 1e-12);
        }
        lv_run_free(r);
    }
    lv_mission_free(m);

    r = run_text_to("test_dof6_handoff.yaml",
                 HEAD0 STAGE_RB "phases:\n"
                 "  - {name: up, model: dof3, stages: [s1], stop_time: 40,\n"
                 "     guidance: {law: attitude, pitch_deg: 80, heading_deg: 90}}\n"
                 "  - {name: six, model: dof6, stages: [s1], from: up, stop_time: 60,\n"
                 "     aero: {s_ref: 10, CD: 0.3}, moments: {Cmq: -5, b_ref: 3.5, c_ref: 3.5}}\n"
                 "  - {name: three, model: dof3, stages: [s1], from: six, stop_time: 70}\n",
                 "dof6_handoff_out", &m);
    if (r != NULL) {
        const char *st[] = {"r_eci_x", "r_eci_y", "r_eci_z", "v_eci_x", "v_eci_y", "v_eci_z", "m"};
        check_continuous(r, 1, st, 7, 0.0);
        check_continuous(r, 2, st, 7, 0.0);
        /* the attitude the dof3 phase flew: 3-2-1 angles back from the quaternion to round-off */
        const char *att[] = {"theta", "psi", "phi"};
        check_continuous(r, 1, att, 3, 1e-12);
        const lv_result *rows = lv_run_rows(r, 1);
        const char *w[] = {"p", "q", "r"};
        for (int i = 0; rows != NULL && i < 3; i++) {
            size_t col = 0;
            CHECK_OK(lv_result_column(rows, w[i], &col, &err), &err);
            CHECK(lv_result_value(rows, 0, col) == 0.0);
        }
        double th;
        CHECK_OK(lv_run_final(r, 0, "theta", &th, &err), &err);
        CHECK_CLOSE(th, 80.0 * DEG, 1e-9); /* the attitude law's pitch */
        /* Issue 27 (M3): each child's .mat records its own start, its parent's final state:
         * the dof6 phase's start_* are the dof3 parent's last row's lat .. heading and its
         * attitude theta, psi, phi (the quaternion built from them, read back: to
         * round-off, as above), its rates 0 (the hand-off's rule); the dof3 child's are the
         * dof6 phase's last row. Not the mission's start (h = 0, v = 1 m/s). */
        const char *par[] = {"start_lat", "start_lon", "start_h", "start_vel", "start_fpa",
                             "start_chi", "start_theta", "start_psi", "start_phi"};
        const char *out[] = {"lat", "lon", "h", "v_rel", "fpa", "heading", "theta", "psi", "phi"};
        for (size_t k = 1; k <= 2; k++) {
            char mat[512];
            snprintf(mat, sizeof mat, "%s.mat", lv_run_result(r, k)->result_stem);
            for (int i = 0; i < (k == 1 ? 9 : 6); i++) {
                double rec = NAN, want = NAN;
                CHECK(mat_param(mat, par[i], &rec) == 0);
                CHECK_OK(lv_run_final(r, k - 1, out[i], &want, &err), &err);
                CHECK_CLOSE(rec, want, 1e-9 * fmax(1.0, fabs(want)));
            }
            double t0 = NAN, h0 = NAN;
            CHECK(mat_param(mat, "start_time", &t0) == 0 && t0 == lv_run_result(r, k - 1)->t_end);
            CHECK(mat_param(mat, "start_h", &h0) == 0 && h0 > 1000.0);
        }
        char mat6[512];
        snprintf(mat6, sizeof mat6, "%s.mat", lv_run_result(r, 1)->result_stem);
        for (int i = 0; i < 3; i++) {
            const char *rn[] = {"start_p", "start_q", "start_r"};
            double rate = NAN;
            CHECK(mat_param(mat6, rn[i], &rate) == 0 && rate == 0.0);
        }
        /* summary.json names each change of model in the phase's handoff */
        mkdir("dof6_out", 0755);
        CHECK_OK(lv_run_write_summary(r, "dof6_out", &err), &err);
        FILE *f = fopen("dof6_out/summary.json", "rb");
        CHECK(f != NULL);
        if (f != NULL) {
            static char text[1 << 20];
            const size_t nb = fread(text, 1, sizeof text - 1, f);
            text[nb] = '\0';
            fclose(f);
            CHECK(strstr(text, "\"transition\":\t\"dof3 -> dof6\"") != NULL);
            CHECK(strstr(text, "\"transition\":\t\"dof6 -> dof3\"") != NULL);
        }
        lv_run_free(r);
    }
    lv_mission_free(m);

    /* The aerodynamic angles carry over too: a dof3 phase flying alpha = 5 deg, beta = 2 deg,
     * bank mu = 10 deg (no wind) hands a body whose attitude gives the same alpha, beta and bank
     * in the dof6 phase's first row (the 3-DoF's body axes C_body_wind = R2(alpha) R3(-beta)
     * after the bank about the velocity, docs/models.md): a check of the attitude mapping, not
     * only of the Euler angles' round trip. */
    /* from an 80 deg path angle: from 89 deg, alpha 5 deg turns the velocity through the
     * vertical within 1.2 s, where the local-horizon angles are undefined and the 3-DoF force
     * direction flips back and forth (1e6 steps at tolerance 1e-9; issue 27's domain guards) */
    r = run_text("test_dof6_angles.yaml",
                 "mission: {name: six}\n"
                 "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}\n"
                 "parameters: {start_lat_deg: 5, start_lon_deg: -52, start_h: 0, start_vel: 1,\n"
                 "             start_fpa_deg: 80, start_chi_deg: 90}\n"
                 "stages:\n" STAGE_RB "phases:\n"
                 "  - {name: up, model: dof3, stages: [s1], stop_time: 30,\n"
                 "     inputs: {alpha_deg: 5, beta_deg: 2, mu_deg: 10},\n"
                 "     aero: {s_ref: 10, CD: 0.3, CL: 0.5}}\n"
                 "  - {name: six, model: dof6, stages: [s1], from: up, stop_time: 31,\n"
                 "     aero: {s_ref: 10, CD: 0.3, CL: 0.5}}\n",
                 &m);
    if (r != NULL) {
        const lv_result *rows = lv_run_rows(r, 1);
        const char *six[] = {"alpha", "beta", "bank"}, *three[] = {"alpha_in", "beta_in", "mu_in"};
        for (int i = 0; rows != NULL && i < 3; i++) {
            double fv;
            size_t col = 0;
            CHECK_OK(lv_run_final(r, 0, three[i], &fv, &err), &err);
            CHECK_OK(lv_result_column(rows, six[i], &col, &err), &err);
            CHECK_CLOSE(lv_result_value(rows, 0, col), fv, 1e-9);
        }
        lv_run_free(r);
    }
    lv_mission_free(m);
}


/* ---- attitude control (issue 15): the 6-DoF body under its controller flies the 3-DoF
 * trajectory of the same steering commands ------------------------------------------------ */

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (f != NULL) {
        fputs(text, f);
        fclose(f);
    }
}

/* Column `name` of a phase's rows at row i. */
static double at(const lv_result *res, size_t i, const char *name)
{
    size_t c = 0;
    lv_err err;
    if (res == NULL || lv_result_column(res, name, &c, &err) != LV_OK) {
        CHECK(res != NULL && 0);
        return NAN;
    }
    return lv_result_value(res, i, c);
}

static double fin(const lv_run *r, size_t k, const char *name)
{
    double v = NAN;
    lv_err err;
    CHECK_OK(lv_run_final(r, k, name, &v, &err), &err);
    return v;
}

/* The vehicle of the control tests: stage and pad of STAGE_RB; a pitch program (local frame,
 * heading east) held vertical for 8 s, then down to 25.8 deg at burnout (147.1 s), and
 * body-axis aerodynamics CA = 0.3, CN = 3 alpha (per rad, a table over alpha) on 10 m^2, with
 * the moment reference point (the centre of pressure) at x = -5 m: ahead of the centre of mass
 * (-15 m full, -20 m empty), so the body is statically unstable (Cm_alpha > 0). */
#define CTL_TABLES                                                                          \
    write_file("ctl_pitch.csv", "time [s], pitch [rad]\n0, 1.5707963\n8, 1.5707963\n"       \
                                "150, 0.45\n");                                             \
    write_file("ctl_cn.csv", "alpha [rad], CN [1]\n-0.6, -1.8\n0.6, 1.8\n")
#define CTL_PHASE(name, extra)                                                              \
    "  - name: " name "\n"                                                                  \
    "    model: dof6\n"                                                                     \
    "    stages: [s1]\n"                                                                    \
    "    stop_time: 200\n"                                                                  \
    "    attitude: {psi_deg: 90, theta_deg: 90}\n"                                          \
    "    guidance: {law: attitude, heading_deg: 90, table: ctl_pitch.csv}\n"                \
    "    aero: {s_ref: 10, axes: body, CA: 0.3, CN: ctl_cn.csv}\n" extra
#define CTL_PID                                                                             \
    "    controller: {pitch: {kp: 1.1, kd: 0.75, ki: 0.3}, yaw: {kp: 1.1, kd: 0.75, ki: 0.3},\n" \
    "                 limit_deg: 6, rate_limit_deg: 20, tau: 0.05}\n"                       \
    "    moments: {Cmq: -2, b_ref: 3.5, c_ref: 3.5, mrp_x: -5}\n"
#define HEAD_PAD                                                                            \
    "mission: {name: ctl}\n"                                                                \
    "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}\n"          \
    "parameters: {start_lat_deg: 5, start_lon_deg: -52, start_h: 0, start_vel: 0,\n"        \
    "             start_fpa_deg: 90, start_chi_deg: 90}\n"                                   \
    "stages:\n" STAGE_RB

/* The 6-DoF phase with the PID controller against the 3-DoF phase of the same steering law
 * and aerodynamic dataset (an alternative branch from the same pad). Where the two models'
 * translational equations differ (docs/models.md, "Attitude control"):
 *   - the thrust direction: 3-DoF along the commanded body x; 6-DoF along the actual body x
 *     turned by the gimbal: at most |eps| + |delta| apart, eps the attitude error's part
 *     normal to body x (err_pitch, err_yaw), delta the gimbal angles;
 *   - the normal force at the angle of attack the attitude error changes: q S CN_alpha |eps|.
 * The difference of the accelerations is therefore at most
 *   a_err(t) = (T/m) (|eps| + |delta|) + q S CN_alpha |eps| / m,
 * and the differences at burnout |dv| <= B_v = integral a_err dt, |dr| <= B_r = integral B_v
 * dt, |d fpa| <= B_v / v (to first order; the gravity gradient's 2 g / R |dr| t is 4 % of B_v
 * here, the drag's change with the speed and altitude differences less). The tolerances are
 * 1.25 B (the margin covers those second-order terms and the quadrature of a_err over the
 * output rows), with B integrated from the 6-DoF run's rows: a bound from the physics of the
 * two models, not a value of either run. The controller must hold the attitude "tightly":
 * |eps| < 0.5 deg everywhere. */
static void test_controller_vs_dof3(void)
{
    CTL_TABLES;
    lv_mission *m = NULL;
    lv_run *r = run_text("test_dof6_ctl.yaml",
                         HEAD_PAD "phases:\n" CTL_PHASE("six", "    end: [burnout]\n" CTL_PID)
                         "  - {name: three, model: dof3, stages: [s1], stop_time: 200,\n"
                         "     end: [burnout], alternative: true,\n"
                         "     guidance: {law: attitude, heading_deg: 90, table: ctl_pitch.csv},\n"
                         "     aero: {s_ref: 10, axes: body, CA: 0.3, CN: ctl_cn.csv}}\n",
                         &m);
    if (r == NULL) {
        lv_mission_free(m);
        return;
    }
    const lv_result *res = lv_run_rows(r, 0);
    const size_t n = res ? lv_result_rows(res) : 0;
    const double S = 10.0, CN_alpha = 3.0;
    double Bv = 0.0, Br = 0.0, a_prev = 0.0, eps_max = 0.0, delta_max = 0.0, q_max = 0.0;
    for (size_t i = 0; i < n; i++) {
        const double eps = hypot(at(res, i, "err_pitch"), at(res, i, "err_yaw"));
        const double delta = hypot(at(res, i, "gimbal_pitch_in"), at(res, i, "gimbal_yaw_in"));
        const double mass = at(res, i, "m"), q = at(res, i, "q_dyn");
        const double a =
            at(res, i, "thrust") / mass * (eps + delta) + q * S * CN_alpha * eps / mass;
        if (i > 0) {
            const double dt = at(res, i, "time") - at(res, i - 1, "time");
            Bv += 0.5 * (a + a_prev) * dt;
            Br += Bv * dt;
        }
        a_prev = a;
        eps_max = fmax(eps_max, eps);
        delta_max = fmax(delta_max, delta);
        q_max = fmax(q_max, q);
    }
    CHECK(n > 100);
    CHECK(eps_max < 0.5 * DEG);           /* held tightly */
    CHECK(delta_max > 0.05 * DEG);        /* ... by the gimbal: it did work */
    CHECK(delta_max < 6.0 * DEG + 1e-12); /* within its limit */
    CHECK(q_max > 20e3);                  /* through max-q */
    /* both burn out at the same time: the same engine, mass flow and propellant */
    CHECK_CLOSE(fin(r, 0, "time"), fin(r, 1, "time"), 1e-6);
    const double dv = sqrt(pow(fin(r, 0, "v_eci_x") - fin(r, 1, "v_eci_x"), 2) +
                           pow(fin(r, 0, "v_eci_y") - fin(r, 1, "v_eci_y"), 2) +
                           pow(fin(r, 0, "v_eci_z") - fin(r, 1, "v_eci_z"), 2));
    const double dr = sqrt(pow(fin(r, 0, "r_eci_x") - fin(r, 1, "r_eci_x"), 2) +
                           pow(fin(r, 0, "r_eci_y") - fin(r, 1, "r_eci_y"), 2) +
                           pow(fin(r, 0, "r_eci_z") - fin(r, 1, "r_eci_z"), 2));
    const double dh = fin(r, 0, "h") - fin(r, 1, "h");
    const double dspeed = fin(r, 0, "v_rel") - fin(r, 1, "v_rel");
    const double dfpa = fin(r, 0, "fpa") - fin(r, 1, "fpa");
    const double v_b = fin(r, 0, "v_rel");
    printf("6-DoF (PID) vs 3-DoF at burnout: |dv| = %.3g m/s (bound %.3g), |dr| = %.3g m (bound "
           "%.3g), dh = %.3g m, d speed = %.3g m/s, d fpa = %.3g deg (bound %.3g); max |eps| = "
           "%.3g deg, max |delta| = %.3g deg, max q = %.3g kPa\n",
           dv, 1.25 * Bv, dr, 1.25 * Br, dh, dspeed, dfpa / DEG, 1.25 * Bv / v_b / DEG,
           eps_max / DEG, delta_max / DEG, q_max * 1e-3);
    CHECK(dv <= 1.25 * Bv);
    CHECK(dr <= 1.25 * Br);
    CHECK(fabs(dh) <= 1.25 * Br);
    CHECK(fabs(dspeed) <= 1.25 * Bv);
    CHECK(fabs(dfpa) <= 1.25 * Bv / v_b);
    /* and the bound is not a vacuous one: under 1 % of the burnout speed */
    CHECK(Bv < 0.01 * fin(r, 0, "v_inertial"));
    /* PID: the actuators and the integrals are states */
    CHECK(!isnan(fin(r, 0, "int_pitch")) && !isnan(fin(r, 0, "act_pitch")));
    lv_run_free(r);
    lv_mission_free(m);
}

/* Rate feed-forward: a PD controller tracking a command that turns at a steady rate. In
 * vacuum, a pitch program in the inertial frame from 90 to 30 deg over 100 s turns the
 * commanded axes at w_c = 0.6 deg/s relative to inertial space. With damping on the body rate
 * alone, -kd q, the steady state of kp e - kd w_c = delta_trim has the lag e = kd w_c / kp
 * (0.48 deg at kp 1.5, kd 1.2 s: the classical ramp error of a type-1 loop); with damping on
 * the rate error, kd (w_c - q), only the trim moments are left: the jet damping
 * mdot r_e^2 w_c needs delta = mdot r_e^2 w_c / (T l_e), i.e. e = r_e w_c / (Isp g0 kp) with
 * r_e = l_e (15-10 m here): under 4e-5 rad = 0.002 deg, and the inertia's decrease
 * (-I' w_c) about as much. The test asks for 2 % of the ramp lag from 30 s on (after the
 * start transient: the body starts at rest). */
static void test_controller_rate_feedforward(void)
{
    write_file("ff_pitch.csv", "time [s], pitch [rad]\n0, 1.5707963267948966\n"
                               "100, 0.5235987755982988\n");
    lv_mission *m = NULL;
    lv_run *r = run_text(
        "test_dof6_ff.yaml",
        "mission: {name: ff}\n"
        "environment: {world: planet, planet: earth, gravity: j2, atmosphere: none}\n"
        "parameters: {start_lat_deg: 5, start_lon_deg: -52, start_h: 0, start_vel: 0,\n"
        "             start_fpa_deg: 90, start_chi_deg: 90}\n"
        "stages:\n" STAGE_RB "phases:\n"
        "  - name: P\n"
        "    model: dof6\n"
        "    stages: [s1]\n"
        "    stop_time: 100\n"
        "    attitude: {psi_deg: 90, theta_deg: 90}\n"
        "    guidance: {law: attitude, frame: inertial, heading_deg: 90, table: ff_pitch.csv}\n"
        "    controller: {pitch: {kp: 1.5, kd: 1.2}, yaw: {kp: 1.5, kd: 1.2}, limit_deg: 6,\n"
        "                 rate_limit_deg: 20, tau: 0.05}\n"
        "    integrator: {tolerance: 1.0e-9, output_interval: 1}\n",
        &m);
    if (r == NULL) {
        lv_mission_free(m);
        return;
    }
    const lv_result *res = lv_run_rows(r, 0);
    const size_t n = res ? lv_result_rows(res) : 0;
    const double w_c = (90.0 - 30.0) / 100.0 * DEG, lag = 1.2 * w_c / 1.5;
    double e_max = 0.0, q_err = 0.0;
    for (size_t i = 0; i < n; i++)
        if (at(res, i, "time") >= 30.0) {
            e_max = fmax(e_max, fabs(at(res, i, "err_pitch")));
            q_err = fmax(q_err, fabs(at(res, i, "q") + w_c)); /* nose down: q = -w_c */
        }
    printf("rate feed-forward: max |pitch error| from 30 s %.3g deg (ramp lag without it %.3g "
           "deg), max |q + w_c| %.3g deg/s\n", e_max / DEG, lag / DEG, q_err / DEG);
    CHECK(n > 90);
    CHECK(e_max < 0.02 * lag);
    CHECK(q_err < 0.01 * w_c);
    lv_run_free(r);
    lv_mission_free(m);
    remove("ff_pitch.csv");
}

/* Without the controller (gimbal fixed at 0) the statically unstable body diverges in angle
 * of attack: with the centre of pressure l = 10 m ahead of the centre of mass the aerodynamic
 * moment q S CN_alpha l alpha grows alpha at the rate sqrt(q S CN_alpha l / I_yy) (0.55 /s at
 * q = 8 kPa: I_yy alpha'' = M_alpha alpha with M_alpha > 0 has the real root
 * sqrt(M_alpha / I_yy), damping and the path's turn aside), so |alpha| reaches 20 deg within seconds of the dynamic pressure's rise
 * (its end event stops the phase, long before burnout); the same body with the centre of
 * pressure 5-10 m aft of the centre of mass (mrp_x = -25) weathervanes: |alpha| stays below
 * 1 deg wherever q > 1 kPa, to burnout. The controlled run of test_controller_vs_dof3 flies
 * the unstable body to burnout. */
static void test_unstable_diverges(void)
{
    CTL_TABLES;
    for (int stable = 0; stable < 2; stable++) {
        char text[4096];
        snprintf(text, sizeof text, "%s", HEAD_PAD "phases:\n" CTL_PHASE("six",
                 "    end: [burnout, {alpha_deg: 20, direction: both},\n"
                 "          {alpha_deg: -20, direction: both}]\n"
                 "    moments: {Cmq: -2, b_ref: 3.5, c_ref: 3.5, mrp_x: MRP}\n"));
        char *mrp = strstr(text, "MRP");
        memcpy(mrp, stable ? "-25" : " -5", 3);
        lv_mission *m = NULL;
        lv_run *r = run_text("test_dof6_unstable.yaml", text, &m);
        if (r == NULL) {
            lv_mission_free(m);
            continue;
        }
        const lv_result *res = lv_run_rows(r, 0);
        double a_max = 0.0;
        for (size_t i = 0; res != NULL && i < lv_result_rows(res); i++)
            if (at(res, i, "q_dyn") > 1e3)
                a_max = fmax(a_max, fabs(at(res, i, "alpha")));
        const double t_end = fin(r, 0, "time");
        printf("uncontrolled, %s: max |alpha| = %.3g deg (q > 1 kPa), end at %.4g s\n",
               stable ? "stable" : "unstable", a_max / DEG, t_end);
        if (stable) {
            CHECK(a_max < 1.0 * DEG);
            CHECK(t_end > 140.0); /* burnout at 147.1 s */
        } else {
            CHECK(fabs(fabs(fin(r, 0, "alpha")) - 20.0 * DEG) < 1e-6);
            CHECK(t_end < 60.0);
        }
        lv_run_free(r);
        lv_mission_free(m);
    }
}

/* 3-DoF -> 6-DoF with the rates from the trajectory's curvature: the child's first body rates
 * are the angular velocity of the parent's velocity relative to the planet, u = v_eci - W x
 * r_eci. Reference: that direction's rotation from the parent's own rows (0.01 s apart), by
 * the second-order backward difference of u/|u| at its last three rows, w = u_hat x
 * d(u_hat)/dt, in body axes through the child's first attitude; zero rates under the default
 * rule. summary.json names the rule. rule 2: the same with the child's quaternion set (a
 * quarter turn about ECI x, far from the parent's attitude): the inertial angular velocity is
 * the trajectory's whatever the attitude, so the rates are its projection on the attitude set
 * (the breaker's finding: they were projected on the parent's attitude), and C_eci_body (p, q,
 * r) is the same vector in both runs. */
static void test_rates_curvature(void)
{
    double w_eci_run[3][3] = {{0}}, w_body_run1[3] = {0};
    for (int rule = 0; rule < 3; rule++) {
        char text[4096];
        snprintf(text, sizeof text,
                 HEAD0 STAGE_RB "phases:\n"
                 "  - {name: up, model: dof3, stages: [s1], stop_time: 40,\n"
                 "     guidance: {law: gravity_turn, rise_time: 5, kick_deg: 5, kick_time: 5,\n"
                 "                heading_deg: 90},\n"
                 "     integrator: {output_interval: 0.01, tolerance: 1e-10}}\n"
                 "  - {name: six, model: dof6, stages: [s1], from: up, stop_time: 41%s%s}\n",
                 rule ? ", transition: {rates: curvature}" : "",
                 rule == 2 ? ",\n     set: {q_w: 0.7071067811865476, q_x: 0.7071067811865476, "
                             "q_y: 0, q_z: 0}"
                           : "");
        lv_mission *m = NULL;
        lv_run *r = run_text("test_dof6_rates.yaml", text, &m);
        if (r == NULL) {
            lv_mission_free(m);
            return;
        }
        const lv_result *up = lv_run_rows(r, 0), *six = lv_run_rows(r, 1);
        const size_t n = up ? lv_result_rows(up) : 0;
        double w_ref[3] = {0.0, 0.0, 0.0};
        if (rule && n > 3) {
            const double W = 7.292115e-5; /* rad/s, the Earth's rotation (WGS 84) */
            double uh[3][3], h = 0.0;
            for (int j = 0; j < 3; j++) {
                const size_t i = n - 3 + (size_t)j;
                const double rx = at(up, i, "r_eci_x"), ry = at(up, i, "r_eci_y");
                const double u[3] = {at(up, i, "v_eci_x") + W * ry,
                                     at(up, i, "v_eci_y") - W * rx, at(up, i, "v_eci_z")};
                const double un = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
                for (int c = 0; c < 3; c++)
                    uh[j][c] = u[c] / un;
                if (j == 2)
                    h = at(up, i, "time") - at(up, i - 1, "time");
            }
            double d[3], w_eci[3];
            for (int c = 0; c < 3; c++) /* (3 f_n - 4 f_n-1 + f_n-2) / (2 h) */
                d[c] = (3.0 * uh[2][c] - 4.0 * uh[1][c] + uh[0][c]) / (2.0 * h);
            w_eci[0] = uh[2][1] * d[2] - uh[2][2] * d[1];
            w_eci[1] = uh[2][2] * d[0] - uh[2][0] * d[2];
            w_eci[2] = uh[2][0] * d[1] - uh[2][1] * d[0];
            double q[4], C[3][3];
            const char *qn[4] = {"q_w", "q_x", "q_y", "q_z"};
            for (int c = 0; c < 4; c++)
                q[c] = at(six, 0, qn[c]);
            dcm(q, C); /* C_eci_body */
            for (int c = 0; c < 3; c++)
                w_ref[c] = C[0][c] * w_eci[0] + C[1][c] * w_eci[1] + C[2][c] * w_eci[2];
            printf("curvature rates: p, q, r = %.6g, %.6g, %.6g rad/s (finite difference %.6g, "
                   "%.6g, %.6g; h = %g s)\n", at(six, 0, "p"), at(six, 0, "q"), at(six, 0, "r"),
                   w_ref[0], w_ref[1], w_ref[2], h);
            /* the trajectory turns: not a trivial zero */
            CHECK(sqrt(w_ref[0] * w_ref[0] + w_ref[1] * w_ref[1] + w_ref[2] * w_ref[2]) > 1e-3);
        }
        const char *wn[3] = {"p", "q", "r"};
        for (int c = 0; c < 3; c++) /* difference error O(h^2 w''), h = 0.01 s */
            CHECK_CLOSE(at(six, 0, wn[c]), w_ref[c], rule ? 2e-6 : 0.0);
        if (rule == 2) /* the attitude set is the one the child starts with */
            CHECK_CLOSE(at(six, 0, "q_x"), 0.7071067811865476, 1e-15);
        if (six != NULL) { /* the start rates as an inertial vector, C_eci_body (p, q, r) */
            double q[4], C[3][3];
            const char *qn[4] = {"q_w", "q_x", "q_y", "q_z"};
            for (int c = 0; c < 4; c++)
                q[c] = at(six, 0, qn[c]);
            dcm(q, C);
            for (int c = 0; c < 3; c++)
                w_eci_run[rule][c] = C[c][0] * at(six, 0, "p") + C[c][1] * at(six, 0, "q") +
                                     C[c][2] * at(six, 0, "r");
            for (int c = 0; rule == 1 && c < 3; c++)
                w_body_run1[c] = at(six, 0, wn[c]);
        }
        if (rule == 2) {
            /* same parent, same rule: the same inertial vector (to rounding), though the body
             * rates differ (the attitudes are far apart) */
            for (int c = 0; c < 3; c++)
                CHECK_CLOSE(w_eci_run[2][c], w_eci_run[1][c], 1e-15);
            double dw = 0.0;
            for (int c = 0; c < 3; c++)
                dw += fabs(at(six, 0, wn[c]) - w_body_run1[c]);
            CHECK(dw > 1e-3);
        }
        mkdir("dof6_rates_out", 0755);
        lv_err err;
        CHECK_OK(lv_run_write_summary(r, "dof6_rates_out", &err), &err);
        FILE *f = fopen("dof6_rates_out/summary.json", "rb");
        CHECK(f != NULL);
        if (f != NULL) {
            static char js[1 << 20];
            const size_t nb = fread(js, 1, sizeof js - 1, f);
            js[nb] = '\0';
            fclose(f);
            CHECK(strstr(js, rule ? "\"rule\":\t\"rates: curvature\""
                                  : "\"rule\":\t\"rates: zero\"") != NULL);
        }
        lv_run_free(r);
        lv_mission_free(m);
    }
}

/* A mission that lv_mission_load (what `lvsim check` and `lvsim run` do) refuses with `want`
 * in the message. */
#define LOAD_BAD(yaml, want) load_bad_((yaml), (want), __LINE__)
static void load_bad_(const char *yaml, const char *want, int line)
{
    write_file("bad.yaml", yaml);
    lv_err err = {LV_OK, ""};
    lv_mission *m = NULL;
    lv_status st = lv_mission_load("bad.yaml", &m, &err);
    check_count_++;
    if (st != LV_ERR_INPUT || m != NULL || strstr(err.msg, want) == NULL) {
        check_failures_++;
        fprintf(stderr, "%s:%d: expected LV_ERR_INPUT \"...%s...\",\n    got %d \"%s\"\n",
                __FILE__, line, want, (int)st, err.msg);
    }
    lv_mission_free(m);
    remove("bad.yaml");
}

/* The controller's keys and the leftovers of a breaker's run, each refused at its place. */
static void test_control_errors(void)
{
    BAD(HEAD0 STAGE_RB "phases:\n"
        "  - {name: P, model: dof6, stages: [s1], stop_time: 10,\n"
        "     controller: {pitch: {kp: 1}, yaw: {kp: 1}, limit_deg: 5, rate_limit_deg: 20}}\n",
        "bad.yaml:13:6: phase 'P', controller: the controller holds the attitude a steering law "
        "commands");
    BAD(HEAD0 STAGE_RB "phases:\n"
        "  - {name: P, model: dof6, stages: [s1], stop_time: 10,\n"
        "     guidance: {law: attitude, pitch_deg: 80, heading_deg: 90},\n"
        "     controller: {pitch: {kp: 0}, yaw: {kp: 1}, limit_deg: 5, rate_limit_deg: 20}}\n",
        "bad.yaml:14:31: phase 'P', controller.pitch: kp must be > 0");
    BAD(HEAD0 STAGE_RB "phases:\n"
        "  - {name: P, model: dof6, stages: [s1], stop_time: 10,\n"
        "     guidance: {law: attitude, pitch_deg: 80, heading_deg: 90},\n"
        "     controller: {pitch: {kp: 1}, yaw: {kp: 1}, limit_deg: 0, rate_limit_deg: 20}}\n",
        "bad.yaml:14:60: phase 'P', controller: limit_deg must be > 0");
    BAD(HEAD0 STAGE_RB "phases:\n"
        "  - {name: P, model: dof6, stages: [s1], stop_time: 10,\n"
        "     guidance: {law: attitude, pitch_deg: 80, heading_deg: 90},\n"
        "     controller: {pitch: {kp: 1, kd: -1}, yaw: {kp: 1}, limit_deg: 5,\n"
        "                  rate_limit_deg: 20}}\n",
        "bad.yaml:14:38: phase 'P', controller.pitch: kd must be >= 0");
    BAD(HEAD0 STAGE_RB "phases:\n"
        "  - {name: P, model: dof6, stages: [s1], stop_time: 10,\n"
        "     guidance: {law: attitude, pitch_deg: 80, heading_deg: 90},\n"
        "     controller: {pitch: {kp: 1}, yaw: {kp: 1}, limit_deg: 5}}\n",
        "bad.yaml:14:18: phase 'P', controller: 'rate_limit_deg' is missing");
    BAD(HEAD0 STAGE_RB "phases:\n"
        "  - {name: P, model: dof6, stages: [s1], stop_time: 10,\n"
        "     guidance: {law: attitude, pitch_deg: 80, heading_deg: 90},\n"
        "     controller: {pitch: {kp: 1}, yaw: {kp: 1}, limit_deg: 5, rate_limit_deg: 20},\n"
        "     inputs: {gimbal_pitch_deg: 1}}\n",
        "bad.yaml:15:15: phase 'P', inputs: 'gimbal_pitch_deg': the controller gives the gimbal "
        "angles");
    BAD(HEAD0 STAGE_RB "phases:\n"
        "  - {name: P, model: dof6, stages: [s1], stop_time: 10, transition: {rates: zero}}\n",
        "bad.yaml:12:57: phase 'P', transition: a transition is a hand-off rule");
    BAD(HEAD0 STAGE_RB "phases:\n"
        "  - {name: A, model: dof3, stages: [s1], stop_time: 10}\n"
        "  - {name: P, model: dof6, stages: [s1], from: A, stop_time: 20,\n"
        "     transition: {rates: bent}}\n",
        "bad.yaml:14:26: phase 'P', transition: rates: unknown value 'bent'");
    /* huge start rates: 10 rev/s at most */
    BAD(HEAD0 STAGE_RB "phases:\n"
        "  - {name: P, model: dof6, stages: [s1], stop_time: 10, rates: {p_deg: 1e5}}\n",
        "bad.yaml:12:72: phase 'P', rates: p_deg must be >= -3600 and <= 3600");
    LOAD_BAD(HEAD0 STAGE_RB "phases:\n"
             "  - {name: P, model: dof6, stages: [s1], stop_time: 10, set: {q: 100}}\n",
             "start body rate q = 100 rad/s is outside");
    /* a child's quaternion is set by its four components, a unit quaternion */
    BAD(HEAD0 STAGE_RB "phases:\n"
        "  - {name: A, model: dof3, stages: [s1], stop_time: 10}\n"
        "  - {name: P, model: dof6, stages: [s1], from: A, stop_time: 20, set: {q_w: 1}}\n",
        "bad.yaml:13:72: phase 'P': set: the attitude quaternion is set by its four components "
        "q_w, q_x, q_y, q_z together (missing: q_x, q_y, q_z)");
    BAD(HEAD0 STAGE_RB "phases:\n"
        "  - {name: A, model: dof3, stages: [s1], stop_time: 10}\n"
        "  - {name: P, model: dof6, stages: [s1], from: A, stop_time: 20,\n"
        "     set: {q_w: 1, q_x: 0.1, q_y: 0, q_z: 0}}\n",
        "bad.yaml:14:12: phase 'P': set: the quaternion (q_w, q_x, q_y, q_z) has norm 1.00498756");
    /* ... which then works, at run time too (not only at check) */
    lv_mission *m = NULL;
    lv_run *r = run_text("test_dof6_setq.yaml",
                         HEAD0 STAGE_RB "phases:\n"
                         "  - {name: A, model: dof3, stages: [s1], stop_time: 10}\n"
                         "  - {name: P, model: dof6, stages: [s1], from: A, stop_time: 12,\n"
                         "     set: {q_w: 0.6, q_x: 0.8, q_y: 0, q_z: 0}}\n",
                         &m);
    if (r != NULL) {
        CHECK(lv_run_result(r, 1)->state == LV_PHASE_DONE);
        CHECK_CLOSE(at(lv_run_rows(r, 1), 0, "q_x"), 0.8, 1e-15);
        lv_run_free(r);
    }
    lv_mission_free(m);
    /* `set:` of the rates and the controller's states in a child, refused where the file
     * writes them, as the model refuses them when the child starts (so `lvsim check` and
     * `lvsim run` accept the same files). The controller: PID on pitch (ki 0.5 /s), ki = 0 on
     * yaw, limit 5 deg = 0.0872665 rad: an integral start within +-0.0872665 / 0.5 = 0.174533
     * rad s */
#define CHILD_CTL(ctl, set)                                                                 \
    HEAD0 STAGE_RB "phases:\n"                                                              \
    "  - {name: A, model: dof3, stages: [s1], stop_time: 10}\n"                             \
    "  - {name: P, model: dof6, stages: [s1], from: A, stop_time: 12,\n"                    \
    "     guidance: {law: attitude, pitch_deg: 80, heading_deg: 90},\n"                     \
    "     " ctl ",\n"                                                                       \
    "     set: {" set "}}\n"
#define PID_5 "controller: {pitch: {kp: 1, ki: 0.5}, yaw: {kp: 1}, limit_deg: 5, rate_limit_deg: 20}"
#define PD_5 "controller: {pitch: {kp: 1}, yaw: {kp: 1}, limit_deg: 5, rate_limit_deg: 20}"
    BAD(CHILD_CTL(PID_5, "q: 100"),
        "bad.yaml:16:12: phase 'P': set: start body rate q = 100 rad/s is outside [-62.8319, "
        "62.8319] rad/s (10 rev/s)");
    BAD(CHILD_CTL(PID_5, "act_pitch: 3"),
        "bad.yaml:16:12: phase 'P': set: start act_pitch = 3 rad (171.887 deg) is outside the "
        "controller's deflection limit +-5 deg");
    BAD(CHILD_CTL(PID_5, "act_yaw_deg: -5.01"), "bad.yaml:16:12: phase 'P': set: start act_yaw");
    BAD(CHILD_CTL(PID_5, "int_pitch: 1e6"),
        "bad.yaml:16:12: phase 'P': set: start int_pitch = 1e+06 rad s is outside +-0.174533 "
        "rad s");
    BAD(CHILD_CTL(PID_5, "int_pitch: 0.18"), /* 0.5 x 0.18 = 0.09 rad = 5.16 deg > 5 deg */
        "bad.yaml:16:12: phase 'P': set: start int_pitch = 0.18 rad s is outside +-0.174533");
    BAD(CHILD_CTL(PID_5, "int_yaw: 0.01"),
        "bad.yaml:16:12: phase 'P': set: start int_yaw = 0.01 rad s on an axis with ki = 0");
    BAD(CHILD_CTL(PD_5, "int_pitch: 0"),
        "bad.yaml:16:12: phase 'P': set: 'int_pitch' is a state of the PID controller: the "
        "phase has a PD controller (no `ki`)");
    BAD(CHILD_CTL("inputs: {throttle: 1}", "act_pitch: 0"),
        "bad.yaml:16:12: phase 'P': set: 'act_pitch' is a state of the attitude controller: the "
        "phase has no `controller:`");
    /* ... and within the ranges, the child runs from them (what check accepts, run accepts) */
    r = run_text("test_dof6_setctl.yaml",
                 CHILD_CTL(PID_5, "act_pitch_deg: 4.99, act_yaw: -0.087, int_pitch: 0.17, "
                                  "q: 62.8"),
                 &m);
    if (r != NULL) {
        CHECK(lv_run_result(r, 1)->state == LV_PHASE_DONE);
        CHECK_CLOSE(at(lv_run_rows(r, 1), 0, "act_pitch"), 4.99 * M_PI / 180.0, 1e-15);
        CHECK_CLOSE(at(lv_run_rows(r, 1), 0, "int_pitch"), 0.17, 0.0);
        lv_run_free(r);
    }
    lv_mission_free(m);
    m = NULL;
    /* a transition is the rule of a change of model: refused from a dof6 parent */
    BAD(HEAD0 STAGE_RB "phases:\n"
        "  - {name: A, model: dof6, stages: [s1], stop_time: 10}\n"
        "  - {name: P, model: dof6, stages: [s1], from: A, stop_time: 20,\n"
        "     transition: {rates: curvature}}\n",
        "bad.yaml:14:6: phase 'P', transition: applies to a change of model (from a dof3 "
        "parent); the parent 'A' is dof6: its rates are copied");
    /* an unknown controller key is named (with a suggestion) before what is missing */
    BAD(HEAD0 STAGE_RB "phases:\n"
        "  - {name: P, model: dof6, stages: [s1], stop_time: 10,\n"
        "     guidance: {law: attitude, pitch_deg: 80, heading_deg: 90},\n"
        "     controller: {pitch: {kp_deg: 1.5}, yaw: {kp: 1}, limit_deg: 5, rate_limit_deg: 20}}\n",
        "bad.yaml:14:27: phase 'P', controller.pitch: unknown key 'kp_deg'; did you mean 'kp'");
    BAD(HEAD0 STAGE_RB "phases:\n"
        "  - {name: P, model: dof6, stages: [s1], stop_time: 10,\n"
        "     guidance: {law: attitude, pitch_deg: 80, heading_deg: 90},\n"
        "     controller: {pitch: {kp: 1}, yaw: {kp: 1}, limit_deg: 5, rate_limt_deg: 20}}\n",
        "bad.yaml:14:63: phase 'P', controller: unknown key 'rate_limt_deg'; did you mean "
        "'rate_limit_deg'");
    /* start values in `parameters:` that only a child would read */
    LOAD_BAD("mission: {name: six}\n"
             "environment: {world: planet, planet: earth}\n"
             "parameters: {start_lat: 0, start_lon: 0, start_h: 0, start_vel: 1,\n"
             "             start_fpa_deg: 89, start_chi: 0, start_q_deg: 2}\n"
             "stages:\n" STAGE_RB "phases:\n"
             "  - {name: A, model: dof3, stages: [s1], stop_time: 10}\n"
             "  - {name: P, model: dof6, stages: [s1], from: A, stop_time: 20}\n",
             "bad.yaml:4:60: parameter 'start_q' would start only phase 'P' (model dof6), which "
             "starts from its parent 'A'");
    /* the principal moments of a real body: I1 + I2 >= I3 */
    LOAD_BAD(HEAD0 "  - {name: s1, dry_mass: 20000, propellant_mass: 100000,\n"
             "     engines: [{name: e, thrust_vac: 2.0e6, isp_vac: 300}],\n"
             "     rigid_body: {inertia_full: {xx: 2.0e5, yy: 8.0e6, zz: 8.0e6},\n"
             "                  inertia_empty: {xx: 1.0e5, yy: 1.0e5, zz: 3.0e5},\n"
             "                  engine_position: {x: -30}}}\n"
             "phases:\n"
             "  - {name: P, model: dof6, stages: [s1], stop_time: 10}\n",
             "bad.yaml:12:5: phase 'P': dof6: the inertia tensor (empty) has the principal "
             "moments 100000, 100000, 300000 kg m^2: the two smaller add up to less than the "
             "largest");
    /* the default root attitude is what `lvsim vars dof6` lists: psi = theta = phi = 0 */
    lv_err err;
    lv_phase_sample *sm = NULL;
    CHECK_OK(lv_phase_types_sample("dof6", &sm, &err), &err);
    if (sm != NULL) {
        const lv_model_def *md = lv_phase_types_sample_model(sm);
        int seen = 0;
        for (size_t i = 0; i < md->n_params; i++)
            if (strcmp(md->params[i].name, "start_psi") == 0 ||
                strcmp(md->params[i].name, "start_theta") == 0 ||
                strcmp(md->params[i].name, "start_phi") == 0) {
                CHECK(md->params[i].start == 0.0);
                seen++;
            }
        CHECK(seen == 3);
        /* `lvsim vars dof6` lists the controller's states and outputs (the sample has a
         * steering law and a PID controller), the names `set:` and `end:` take */
        static const char *const ctl_vars[] = {"act_pitch", "act_yaw", "int_pitch", "int_yaw",
                                               "err_roll", "err_pitch", "err_yaw", "theta_cmd",
                                               "psi_cmd", "phi_cmd", "gimbal_pitch_cmd",
                                               "gimbal_yaw_cmd"};
        for (size_t i = 0; i < sizeof ctl_vars / sizeof ctl_vars[0]; i++) {
            lv_var_kind kind;
            size_t idx;
            CHECK(lv_model_find(md, ctl_vars[i], &kind, &idx, NULL) == LV_OK);
            CHECK(kind == (i < 4 ? LV_VAR_STATE : LV_VAR_OUTPUT));
        }
        lv_phase_types_sample_free(sm);
    }
    r = run_text("test_dof6_default.yaml",
                 HEAD0 STAGE_RB "phases:\n"
                 "  - {name: P, model: dof6, stages: [s1], stop_time: 1}\n", &m);
    if (r != NULL) {
        const lv_result *rows = lv_run_rows(r, 0);
        CHECK_CLOSE(at(rows, 0, "theta"), 0.0, 1e-12);
        CHECK_CLOSE(at(rows, 0, "phi"), 0.0, 1e-12);
        const double psi = at(rows, 0, "psi");
        CHECK(fabs(psi) < 1e-12 || fabs(psi - 2.0 * M_PI) < 1e-12);
        lv_run_free(r);
    }
    lv_mission_free(m);
}

/* Every YAML example of docs/mission-format.md about dof6 (the indented blocks of "Rigid-body
 * data" and "6-DoF phases") loads as `lvsim check` loads it: a phase block as a phase of a
 * mission with the stages it names (and the dof3 parent `liftoff` a block with `from:` names),
 * a rigid_body block as the data of the bottom stage of a dof6 phase. A breaker found the
 * example `aero: {s_ref: 10, CA: 0.3, CN: 0.1}` refused ("'CA' belongs to axes: body"). */
static char *slurp_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return NULL;
    char *buf = NULL;
    if (fseek(f, 0, SEEK_END) == 0) {
        const long n = ftell(f);
        rewind(f);
        buf = n >= 0 ? malloc((size_t)n + 1) : NULL;
        if (buf != NULL)
            buf[fread(buf, 1, (size_t)n, f)] = '\0';
    }
    fclose(f);
    return buf;
}

static void test_doc_examples(void)
{
    const char *root = getenv("LV_SOURCE_DIR");
    char path[4096];
    static const char *const tables[] = {"ca_mach.csv", "cn_alpha.csv"};
    for (int i = 0; i < 2; i++) { /* the tables the examples name, from the example */
        snprintf(path, sizeof path, "%s/examples/two-stage-6dof/%s", root ? root : "..",
                 tables[i]);
        char *t = slurp_file(path);
        CHECK(t != NULL);
        if (t != NULL)
            write_file(tables[i], t);
        free(t);
    }
    snprintf(path, sizeof path, "%s/docs/mission-format.md", root ? root : "..");
    char *doc = slurp_file(path);
    CHECK(doc != NULL);
    if (doc == NULL)
        return;
    static const char *const sections[] = {"### Rigid-body data", "#### 6-DoF phases"};
    int n_blocks = 0;
    for (int sct = 0; sct < 2; sct++) {
        const char *a = strstr(doc, sections[sct]);
        CHECK(a != NULL);
        if (a == NULL)
            continue;
        const char *end = strstr(a + strlen(sections[sct]), "\n#");
        if (end == NULL)
            end = a + strlen(a);
        for (const char *b = a; b < end;) { /* the indented blocks after a blank line */
            const char *blk = strstr(b, "\n\n    ");
            if (blk == NULL || blk >= end)
                break;
            blk += 2;
            const char *e = blk;
            while (e < end && strncmp(e, "    ", 4) == 0) {
                const char *nl = strchr(e, '\n');
                e = nl ? nl + 1 : e + strlen(e);
            }
            const int len = (int)(e - blk);
            static char yaml[16384];
            const int rigid = strncmp(blk, "    rigid_body:", 15) == 0;
            snprintf(yaml, sizeof yaml,
                     "mission: {name: doc}\n"
                     "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}\n"
                     "parameters: {start_lat_deg: 5, start_lon_deg: -52, start_h: 0, "
                     "start_vel: 1,\n"
                     "             start_fpa_deg: 89, start_chi_deg: 90}\n"
                     "stages:\n"
                     "  - name: %s\n"
                     "    dry_mass: 20000\n"
                     "    propellant_mass: 100000\n"
                     "    engines: [{name: e, thrust_vac: 2.0e6, isp_vac: 300}]\n"
                     "%.*s%s"
                     "  - {name: upper, dry_mass: 4000, propellant_mass: 10000}\n"
                     "  - {name: payload, dry_mass: 1000, propellant_mass: 0}\n"
                     "  - name: s1\n"
                     "    dry_mass: 20000\n"
                     "    propellant_mass: 100000\n"
                     "    engines: [{name: e1, thrust_vac: 2.0e6, isp_vac: 300}]\n"
                     "    rigid_body: {inertia_full: {xx: 2.0e5, yy: 8.0e6, zz: 8.0e6},\n"
                     "                 cg_full: {x: -15}, engine_position: {x: -30}}\n"
                     "  - {name: s2, dry_mass: 4000, propellant_mass: 10000}\n"
                     "phases:\n"
                     "    - {name: liftoff, model: dof3, stages: [booster, upper, payload],\n"
                     "       stop_time: 14}\n"
                     "%.*s%s",
                     "booster", rigid ? len : 0, blk,
                     rigid ? ""
                           : "    rigid_body: {inertia_full: {xx: 2.0e5, yy: 8.0e6, zz: 8.0e6},\n"
                             "                 cg_full: {x: -15}, engine_position: {x: -30}}\n",
                     rigid ? 0 : len, blk,
                     rigid ? "    - {name: six, model: dof6, stages: [booster], from: liftoff,\n"
                             "       stop_time: 20}\n"
                           : "");
            lv_err err = {LV_OK, ""};
            lv_mission *m = NULL;
            write_file("doc_example.yaml", yaml);
            const lv_status st = lv_mission_load("doc_example.yaml", &m, &err);
            check_count_++;
            if (st != LV_OK) {
                check_failures_++;
                fprintf(stderr, "%s:%d: docs/mission-format.md example at \"%.40s\" refused: %s\n",
                        __FILE__, __LINE__, blk + 4, err.msg);
            }
            lv_mission_free(m);
            remove("doc_example.yaml");
            n_blocks++;
            b = e;
        }
    }
    CHECK(n_blocks >= 3); /* rigid_body, ascent6, boost */
    printf("docs/mission-format.md: %d dof6 examples load\n", n_blocks);
    free(doc);
}

/* The burnout event's two rows (the instant written twice, docs/result-files.md), each in the
 * mode of its side. A body pitching at q = 1 deg/s in vacuum (2000 km up), its engine on the
 * axis: no thrust or aerodynamic moment, only the mass-variation terms of Euler's equation
 * (docs/models.md), I_yy q' = -mdot l^2 q - I'_yy q with l the engine's distance from the CG
 * (jet damping) and I'_yy = (I_empty - I_full)_yy mdot / propellant_mass. Before the event the
 * engine burns: mdot = T / (Isp g0) and both terms act (the breaker found I' = 0 on that row
 * while mdot flowed: q' = -mdot l^2 q / I_yy alone, about 6 times smaller and of the other
 * sign here); after it mdot = 0 and q' = 0 (omega x I omega = 0 for a rate about a principal
 * axis). */
static void test_burnout_rows(void)
{
    lv_mission *m = NULL;
    lv_run *r = run_text("test_dof6_burnout.yaml",
                         "mission: {name: bo}\n"
                         "environment: {world: planet, planet: earth, gravity: j2}\n"
                         "parameters: {start_lat: 0, start_lon: 0, start_h: 2.0e6, "
                         "start_vel: 7000, start_fpa: 0, start_chi: 0}\n"
                         "stages:\n"
                         "  - {name: s1, dry_mass: 20000, propellant_mass: 10000,\n"
                         "     engines: [{name: e, thrust_vac: 2.0e6, isp_vac: 300}],\n"
                         "     rigid_body: {inertia_full: {xx: 2.0e5, yy: 8.0e6, zz: 8.0e6},\n"
                         "                  inertia_empty: {xx: 5.0e4, yy: 2.0e6, zz: 2.0e6},\n"
                         "                  cg_full: {x: -15}, cg_empty: {x: -20},\n"
                         "                  engine_position: {x: -30}}}\n"
                         "phases:\n"
                         "  - {name: P, model: dof6, stages: [s1], stop_time: 30, end: [burnout],\n"
                         "     rates: {q_deg: 1}, integrator: {tolerance: 1e-10}}\n",
                         &m);
    if (r != NULL) {
        const lv_result *rows = lv_run_rows(r, 0);
        const size_t n = rows ? lv_result_rows(rows) : 0;
        CHECK(n > 3);
        if (n > 3) {
            const size_t b = n - 2, a = n - 1; /* before, after */
            CHECK(at(rows, b, "time") == at(rows, a, "time"));
            const double mdot = 2.0e6 / (300.0 * 9.80665);
            CHECK_CLOSE(at(rows, b, "mdot"), mdot, 1e-9 * mdot);
            const double l = -30.0 - at(rows, b, "cg_x"), q = at(rows, b, "q");
            const double idot = (2.0e6 - 8.0e6) * mdot / 10000.0;
            const double qd = -(mdot * l * l + idot) * q / at(rows, b, "I_yy");
            printf("burnout rows: der(q) = %.9g (expected %.9g; jet damping alone %.9g), then "
                   "%.3g; mdot %.6g then %.3g kg/s\n", at(rows, b, "der(q)"), qd,
                   -mdot * l * l * q / at(rows, b, "I_yy"), at(rows, a, "der(q)"),
                   at(rows, b, "mdot"), at(rows, a, "mdot"));
            CHECK_CLOSE(at(rows, b, "der(q)"), qd, 1e-9 * fabs(qd));
            CHECK(at(rows, a, "mdot") == 0.0 && at(rows, a, "der(m)") == 0.0);
            CHECK_CLOSE(at(rows, a, "der(q)"), 0.0, 1e-15);
            /* the row before continues the burn: its der(q) on the trend of the rows before */
            CHECK_CLOSE(at(rows, b, "der(q)"), at(rows, b - 1, "der(q)"),
                        0.05 * fabs(at(rows, b - 1, "der(q)")));
        }
        lv_run_free(r);
    }
    lv_mission_free(m);
}

int main(void)
{
    test_torque_free();
    test_precession();
    test_quat_norm_spin();
    test_pitch_damping();
    test_moment_transfer();
    test_vs_dof3();
    test_start_attitude();
    test_thrust_moment();
    test_gimbal_table();
    test_bad_config();
    test_mission_errors();
    test_mission_handoffs();
    test_controller_vs_dof3();
    test_controller_rate_feedforward();
    test_unstable_diverges();
    test_rates_curvature();
    test_control_errors();
    test_doc_examples();
    test_burnout_rows();
    return check_report("test_dof6");
}
