/* test_mission_env.c - the environment a mission file defines (docs/mission-format.md,
 * "environment"), flown through whole missions (lv_mission_load, lv_run) and checked against
 * closed forms:
 *  - a planet by its constants: a dof3 coast over a non-rotating point-mass sphere is the
 *    two-body problem (apoapsis at half the Kepler period, the orbit closing after one);
 *  - a custom J2: the nodal regression rate of the first-order secular theory, and again after
 *    a run changes J2 (the gravity is then built from the run's value), and from a planet's
 *    own coefficient file;
 *  - the flat world in air: a fall from rest with quadratic drag at constant density against
 *    v(t) = v_t tanh(g t / v_t), and the steady drift in a constant wind and an updraft;
 *  - several aerodynamic tables per phase: CA over Mach from a CSV file, CN over Mach and
 *    alpha from a MAT struct with named axes, against Anderson's body-to-wind relations.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <matio.h>

#include "check.h"
#include "lvsim/lv_io.h"
#include "lvsim/lv_mission.h"

#define DEG (M_PI / 180.0)

static void write_text(const char *path, const char *text)
{
    FILE *fp = fopen(path, "w");
    CHECK(fp != NULL);
    if (fp == NULL)
        return;
    fputs(text, fp);
    fclose(fp);
}

static lv_mission *load(const char *path, const char *text)
{
    lv_err err;
    lv_mission *m = NULL;
    write_text(path, text);
    CHECK_OK(lv_mission_load(path, &m, &err), &err);
    return m;
}

static double final(const lv_run *r, size_t k, const char *name)
{
    lv_err err;
    double v = NAN;
    CHECK_OK(lv_run_final(r, k, name, &v, &err), &err);
    return v;
}

/* ---- (1) Kepler over a sphere given by its constants ------------------------------------ */
/* A sphere of radius R = 6371 km, GM = 3.986004418e14 m^3/s^2, not rotating, no zonal terms:
 * the default gravity of a planet given by its constants ("zonal") is then a point mass, and
 * without rotation the start velocity relative to the planet is the inertial one. From
 * r0 = R + 500 km with v0 = 1.1 sqrt(GM / r0) horizontal (periapsis), the vis-viva equation
 * and the conservation of angular momentum give (Vallado, 4th ed., eqs. 2-5, 2-22):
 *     a = 1 / (2 / r0 - v0^2 / GM),   T = 2 pi sqrt(a^3 / GM),
 *     r_apo = 2 a - r0,   v_apo = r0 v0 / r_apo,   apoapsis at t = T / 2.
 * P1 coasts to the apogee event (radial velocity falling through zero), P2 on to t = T, where
 * the orbit closes: the state is the start state again. Tolerances: dopri5 at 1e-11 controls
 * position to 1e-8 m per step (docs/integration.md); events are located to ~1e-9 s. */
static void test_kepler_sphere(void)
{
    const double R = 6371000.0, GM = 3.986004418e14, r0 = R + 500e3;
    const double v0 = 1.1 * sqrt(GM / r0);
    const double a = 1.0 / (2.0 / r0 - v0 * v0 / GM), T = 2.0 * M_PI * sqrt(a * a * a / GM);
    const double r_apo = 2.0 * a - r0, v_apo = r0 * v0 / r_apo;
    char text[2048];
    snprintf(text, sizeof text,
             "mission: {name: kepler}\n"
             "environment:\n"
             "  world: planet\n"
             "  planet: {name: sphere, radius: %.17g, gm: %.17g, rotation_rate: 0}\n"
             "parameters: {start_lat: 0, start_lon: 0, start_h: 500000, start_vel: %.17g,\n"
             "             start_fpa: 0, start_chi_deg: 90}\n"
             "stages: [{name: sat, dry_mass: 100, propellant_mass: 0}]\n"
             "phases:\n"
             "  - {name: P1, model: dof3, stages: [sat], stop_time: %.17g, end: [apogee],\n"
             "     integrator: {method: dopri5, tolerance: 1.0e-11, output_interval: 60}}\n"
             "  - {name: P2, model: dof3, stages: [sat], from: P1, stop_time: %.17g,\n"
             "     integrator: {method: dopri5, tolerance: 1.0e-11, output_interval: 60}}\n",
             R, GM, v0, 0.75 * T, T); /* P1 ends at its apogee, T / 2 */
    lv_mission *m = load("env_kepler.yaml", text);
    if (m == NULL)
        return;
    lv_err err;
    lv_run *r = NULL;
    CHECK_OK(lv_run_create(m, &r, &err), &err);
    const lv_run_options opt = {.threads = 1};
    CHECK_OK(lv_run_execute(r, &opt, &err), &err);
    lv_mission_info mi;
    lv_mission_get_info(m, &mi);
    CHECK(strcmp(mi.planet, "sphere") == 0);
    const double t_apo = final(r, 0, "time");
    CHECK(lv_run_result(r, 0)->end_index == 0); /* the apogee event ended P1 */
    CHECK_CLOSE(t_apo, T / 2.0, 1e-6);
    CHECK_CLOSE(final(r, 0, "radius"), r_apo, 1e-4);
    CHECK_CLOSE(final(r, 0, "v_inertial"), v_apo, 1e-7);
    CHECK_CLOSE(final(r, 0, "h"), r_apo - R, 1e-4); /* a sphere: altitude = radius - R */
    /* one period later the orbit closes: ECI (r0, 0, 0), (0, v0, 0) at longitude 0 */
    CHECK(final(r, 1, "time") == T);
    CHECK_CLOSE(final(r, 1, "r_eci_x"), r0, 1e-4);
    CHECK_CLOSE(final(r, 1, "r_eci_y"), 0.0, 1e-4);
    CHECK_CLOSE(final(r, 1, "r_eci_z"), 0.0, 1e-9);
    CHECK_CLOSE(final(r, 1, "v_eci_x"), 0.0, 1e-7);
    CHECK_CLOSE(final(r, 1, "v_eci_y"), v0, 1e-7);
    printf("kepler sphere: T/2 %.9f s vs %.9f s, r_apo %.6f m vs %.6f m, closure %.3e m\n",
           t_apo, T / 2.0, final(r, 0, "radius"), r_apo,
           hypot(final(r, 1, "r_eci_x") - r0, final(r, 1, "r_eci_y")));
    lv_run_free(r);
    lv_mission_free(m);
    remove("env_kepler.yaml");
}

/* ---- (2) nodal regression with a custom J2 -------------------------------------------- */
/* First-order secular rate (Vallado, 4th ed., eq. 9-41; Kaula 1966):
 *     dOmega/dt = -3/2 n J2 (R/p)^2 cos i.
 * The planet: R = 6378137 m, GM of the Earth, not rotating (so the start heading gives the
 * inertial inclination: cos i = sin chi cos lat, here i = 60 deg from chi = 30 deg at the
 * equator), J2 = 2e-3 (about twice the Earth's) and nothing else. A circular orbit at
 * 7000 km; the osculating RAAN is averaged over each of 12 orbits (200 samples each, which
 * removes the short-period terms to first order) and a line through the means gives the
 * rate. What remains is O(J2) relative (second-order terms, mean vs osculating elements):
 * tolerance 0.5 %, as for the Earth's J2 in test_dof3. A run then sets J2 = 1e-3: the rate
 * follows (the gravity is built from the run's value). */
static double raan_rate(const lv_result *res, double T, int n_orb, int per, double *n_mean,
                        double *p_mean, double *i_mean)
{
    lv_err err;
    size_t ct, cO, ca, ce, ci;
    CHECK_OK(lv_result_column(res, "time", &ct, &err), &err);
    CHECK_OK(lv_result_column(res, "raan", &cO, &err), &err);
    CHECK_OK(lv_result_column(res, "sma", &ca, &err), &err);
    CHECK_OK(lv_result_column(res, "ecc", &ce, &err), &err);
    CHECK_OK(lv_result_column(res, "inc", &ci, &err), &err);
    double tm[64] = {0}, Om[64] = {0}, am = 0, em = 0, im = 0, O_prev = 0, O_off = 0;
    int cnt[64] = {0};
    size_t used = 0;
    for (size_t row = 0; row < lv_result_rows(res); row++) {
        const double t = lv_result_value(res, row, ct);
        const int k = (int)floor(t / T + 1e-9);
        if (k >= n_orb || (row > 0 && t == lv_result_value(res, row - 1, ct)))
            continue;
        double O = lv_result_value(res, row, cO);
        if (row > 0 && O + O_off - O_prev > M_PI) O_off -= 2.0 * M_PI;
        if (row > 0 && O + O_off - O_prev < -M_PI) O_off += 2.0 * M_PI;
        O_prev = O + O_off;
        if ((int)(t / T * per + 0.5) % per == 0 && cnt[k] > 0)
            continue; /* the end point of an orbit belongs to the next one */
        tm[k] += t;
        Om[k] += O_prev;
        cnt[k]++;
        am += lv_result_value(res, row, ca);
        em += lv_result_value(res, row, ce);
        im += lv_result_value(res, row, ci);
        used++;
    }
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int k = 0; k < n_orb; k++) {
        CHECK(cnt[k] == per);
        const double x = tm[k] / cnt[k], y = Om[k] / cnt[k];
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
    }
    am /= (double)used;
    em /= (double)used;
    *i_mean = im / (double)used;
    *p_mean = am * (1.0 - em * em);
    *n_mean = am; /* the caller takes n from GM */
    return (n_orb * sxy - sx * sy) / (n_orb * sxx - sx * sx);
}

static void test_custom_j2(void)
{
    const double R = 6378137.0, GM = 3.986004418e14, r0 = 7.0e6, J2 = 2.0e-3;
    const double v0 = sqrt(GM / r0), T = 2.0 * M_PI * sqrt(r0 * r0 * r0 / GM);
    const int n_orb = 12, per = 200;
    char text[2048];
    snprintf(text, sizeof text,
             "mission: {name: j2}\n"
             "environment:\n"
             "  world: planet\n"
             "  planet: {name: oblate, radius: %.17g, gm: %.17g, rotation_rate: 0, zonal: [%g]}\n"
             "  gravity: j2\n"
             "parameters: {start_lat: 0, start_lon: 0, start_h: %.17g, start_vel: %.17g,\n"
             "             start_fpa: 0, start_chi_deg: 30}\n"
             "stages: [{name: sat, dry_mass: 100, propellant_mass: 0}]\n"
             "phases:\n"
             "  - {name: P1, model: dof3, stages: [sat], stop_time: %.17g,\n"
             "     integrator: {method: dopri5, tolerance: 1.0e-11, output_interval: %.17g}}\n",
             R, GM, J2, r0 - R, v0, n_orb * T, T / per);
    lv_mission *m = load("env_j2.yaml", text);
    if (m == NULL)
        return;
    lv_err err;
    lv_run *r = NULL;
    CHECK_OK(lv_run_create(m, &r, &err), &err);
    const lv_run_options opt = {.threads = 1};
    const double j2s[2] = {J2, 1.0e-3};
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1)
            CHECK_OK(lv_run_set(r, "environment.planet.J2", j2s[1], &err), &err);
        CHECK_OK(lv_run_execute(r, &opt, &err), &err);
        CHECK(lv_run_simulated(r) == 1);
        const lv_result *res = lv_run_rows(r, 0);
        CHECK(res != NULL);
        if (res == NULL)
            break;
        double am, pm, im;
        const double dO = raan_rate(res, T, n_orb, per, &am, &pm, &im);
        const double nm = sqrt(GM / (am * am * am));
        const double ref = -1.5 * nm * j2s[pass] * (R / pm) * (R / pm) * cos(im);
        CHECK_CLOSE(im, 60.0 * DEG, 1e-3);
        CHECK_REL(dO, ref, 5e-3);
        printf("custom J2 = %g: dOmega/dt %.6e rad/s vs %.6e (rel %.2e)\n", j2s[pass], dO, ref,
               fabs(dO / ref - 1.0));
    }
    lv_run_free(r);
    lv_mission_free(m);
    remove("env_j2.yaml");

    /* The same planet's field from an ICGEM coefficient file (gravity sh): C(2,0) only, fully
     * normalised, J2 = -sqrt(5) C(2,0) (docs/gravity.md); the file's GM and radius. Here
     * J2 = 1.5e-3; the rate follows the same formula. */
    const double J2f = 1.5e-3, c20 = -J2f / sqrt(5.0);
    snprintf(text, sizeof text,
             "product_type gravity_field\nmodelname test\nearth_gravity_constant %.17g\n"
             "radius %.17g\nmax_degree 2\nnorm fully_normalized\nend_of_head ====\n"
             "gfc 2 0 %.17e 0.0\ngfc 2 1 0.0 0.0\ngfc 2 2 0.0 0.0\n", GM, R, c20);
    write_text("env_j2.gfc", text);
    snprintf(text, sizeof text,
             "mission: {name: j2-file}\n"
             "environment:\n"
             "  world: planet\n"
             "  planet: {name: filed, radius: %.17g, gm: %.17g, rotation_rate: 0,\n"
             "           coefficients: env_j2.gfc}\n"
             "parameters: {start_lat: 0, start_lon: 0, start_h: %.17g, start_vel: %.17g,\n"
             "             start_fpa: 0, start_chi_deg: 30}\n"
             "stages: [{name: sat, dry_mass: 100, propellant_mass: 0}]\n"
             "phases:\n"
             "  - {name: P1, model: dof3, stages: [sat], stop_time: %.17g,\n"
             "     integrator: {method: dopri5, tolerance: 1.0e-11, output_interval: %.17g}}\n",
             R, GM, r0 - R, v0, n_orb * T, T / per);
    m = load("env_j2f.yaml", text);
    if (m != NULL) {
        CHECK_OK(lv_run_create(m, &r, &err), &err);
        CHECK_OK(lv_run_execute(r, &opt, &err), &err);
        const lv_result *res = lv_run_rows(r, 0);
        CHECK(res != NULL);
        if (res != NULL) {
            double am, pm, im;
            const double dO = raan_rate(res, T, n_orb, per, &am, &pm, &im);
            const double nm = sqrt(GM / (am * am * am));
            const double ref = -1.5 * nm * J2f * (R / pm) * (R / pm) * cos(im);
            CHECK_REL(dO, ref, 5e-3);
            printf("J2 = %g from a .gfc file: dOmega/dt %.6e rad/s vs %.6e (rel %.2e)\n", J2f,
                   dO, ref, fabs(dO / ref - 1.0));
        }
        lv_run_free(r);
        lv_mission_free(m);
    }
    remove("env_j2f.yaml");
    remove("env_j2.gfc");
}


/* ---- (3) the flat world in air: a fall with quadratic drag ----------------------------- */
/* A 10 kg ball (CD 0.47, S 0.03 m^2) falls from rest at z0 = 5 km in uniform gravity
 * g = 9.81 m/s^2 through air of constant density rho: the exponential atmosphere with
 * rho0 = 1.2 kg/m^3 and a scale height of 1e15 m (rho changes by 5e-12 relative over 5 km).
 * With the drag q S CD along -v and downward speed v, m dv/dt = m g - rho S CD v^2 / 2, so
 * (e.g. Taylor, Classical Mechanics, 2005, sec. 2.4):
 *     v_t = sqrt(2 m g / (rho CD S)),  v(t) = v_t tanh(g t / v_t),
 *     z0 - z(t) = (v_t^2 / g) ln cosh(g t / v_t),  drag = m g (v / v_t)^2.
 * Mach = v / a with a = sqrt(gamma R* T / M0) at the exponential model's T = 288.15 K
 * (US76 constants, docs/atmosphere.md). A run then sets rho0 = 0.6: v_t grows by sqrt(2). */
static const double BALL_M = 10.0, BALL_CD = 0.47, BALL_S = 0.03, G = 9.81, Z0 = 5000.0;

static void fall_closed_form(double rho, double t, double *v, double *d)
{
    const double vt = sqrt(2.0 * BALL_M * G / (rho * BALL_CD * BALL_S));
    *v = vt * tanh(G * t / vt);
    *d = vt * vt / G * log(cosh(G * t / vt));
}

static void test_flat_drag(void)
{
    char text[2048];
    snprintf(text, sizeof text,
             "mission: {name: drop}\n"
             "environment:\n"
             "  world: flat\n"
             "  g: %g\n"
             "  atmosphere: {model: exp, rho0: 1.2, scale_height: 1.0e15}\n"
             "parameters: {start_z: %g, start_vel: 0}\n"
             "stages: [{name: ball, dry_mass: %g, propellant_mass: 0}]\n"
             "phases:\n"
             "  - name: fall\n"
             "    model: flat6\n"
             "    stages: [ball]\n"
             "    stop_time: 30\n"
             "    end: [impact]\n"
             "    aero: {s_ref: %g, CD: %g}\n"
             "    integrator: {method: dopri5, tolerance: 1.0e-10, output_interval: 1}\n",
             G, Z0, BALL_M, BALL_S, BALL_CD);
    lv_mission *m = load("env_drop.yaml", text);
    if (m == NULL)
        return;
    lv_err err;
    lv_run *r = NULL;
    CHECK_OK(lv_run_create(m, &r, &err), &err);
    const lv_run_options opt = {.threads = 1};
    const double rhos[2] = {1.2, 0.6};
    const double a_sound = sqrt(1.4 * 8314.32 / 28.9644 * 288.15); /* m/s, eq. 50 */
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1)
            CHECK_OK(lv_run_set(r, "environment.atmosphere.rho0", rhos[1], &err), &err);
        CHECK_OK(lv_run_execute(r, &opt, &err), &err);
        const lv_result *res = lv_run_rows(r, 0);
        CHECK(res != NULL);
        if (res == NULL)
            break;
        size_t ct, cz, cvz, cvx, cd, cm, cq, crho;
        CHECK_OK(lv_result_column(res, "time", &ct, &err), &err);
        CHECK_OK(lv_result_column(res, "z", &cz, &err), &err);
        CHECK_OK(lv_result_column(res, "vz", &cvz, &err), &err);
        CHECK_OK(lv_result_column(res, "vx", &cvx, &err), &err);
        CHECK_OK(lv_result_column(res, "drag", &cd, &err), &err);
        CHECK_OK(lv_result_column(res, "mach", &cm, &err), &err);
        CHECK_OK(lv_result_column(res, "q_dyn", &cq, &err), &err);
        CHECK_OK(lv_result_column(res, "rho", &crho, &err), &err);
        double worst_v = 0.0, worst_z = 0.0;
        const double vt = sqrt(2.0 * BALL_M * G / (rhos[pass] * BALL_CD * BALL_S));
        for (size_t row = 0; row < lv_result_rows(res); row++) {
            const double t = lv_result_value(res, row, ct);
            double v, d;
            fall_closed_form(rhos[pass], t, &v, &d);
            worst_v = fmax(worst_v, fabs(-lv_result_value(res, row, cvz) - v));
            worst_z = fmax(worst_z, fabs(lv_result_value(res, row, cz) - (Z0 - d)));
            CHECK(lv_result_value(res, row, cvx) == 0.0); /* no wind: straight down */
            CHECK_REL(lv_result_value(res, row, crho), rhos[pass], 1e-11);
            if (t > 0.0) {
                CHECK_REL(lv_result_value(res, row, cd), BALL_M * G * (v / vt) * (v / vt), 1e-7);
                CHECK_REL(lv_result_value(res, row, cm), v / a_sound, 1e-7);
                CHECK_REL(lv_result_value(res, row, cq), 0.5 * rhos[pass] * v * v, 1e-7);
            }
        }
        CHECK(lv_run_result(r, 0)->t_end == 30.0); /* no impact: z stays above 0 */
        CHECK(worst_v < 1e-6);
        CHECK(worst_z < 1e-5);
        printf("flat drop, rho %.1f: v_t %.6f m/s, v(30) %.9f vs %.9f, worst |dv| %.2e m/s, "
               "|dz| %.2e m\n", rhos[pass], vt, -final(r, 0, "vz"), vt * tanh(G * 30.0 / vt),
               worst_v, worst_z);
    }
    lv_run_free(r);
    lv_mission_free(m);
    remove("env_drop.yaml");
}

/* The same ball in a constant wind, with CD from a table of its own over Mach (constant: two
 * rows of 0.47) and the density from a table atmosphere (two rows of 1.2 kg/m^3, T = 288.15 K,
 * p = rho R* T / M0: constant between them). Drag acts along -(v - v_wind): near the steady
 * state a horizontal difference u from the wind decays as du/dt = -(g / v_t) u (time constant
 * v_t / g = 11 s; the vertical one is half of it), after which the body falls at v_t relative
 * to the air. After 300 s (27 time constants, e^-27 ~ 2e-12) the closed-form steady state
 * holds: vx = W_east, vy = W_north, vz = -v_t - W_down (an updraft, down < 0, slows the fall
 * by its speed). The wind's sign is the check: east = 6 is air moving towards +x, which
 * carries the ball there. */
static void test_flat_wind(void)
{
    write_text("env_cd.csv", "mach [1], CD [1]\n0, 0.47\n2, 0.47\n");
    const double rho = 1.2, T = 288.15, p = rho * 8314.32 / 28.9644 * T;
    char text[2048];
    snprintf(text, sizeof text, "h [m], T [K], p [Pa], rho [kg/m3]\n-5000, %.17g, %.17g, %.17g\n"
             "1.0e5, %.17g, %.17g, %.17g\n", T, p, rho, T, p, rho);
    write_text("env_air.csv", text);
    snprintf(text, sizeof text,
             "mission: {name: drift}\n"
             "environment:\n"
             "  world: flat\n"
             "  g: %g\n"
             "  atmosphere: {table: env_air.csv}\n"
             "  wind: {north: -2, east: 6, down: -3}\n"
             "parameters: {start_z: 50000, start_vel: 0}\n"
             "stages: [{name: ball, dry_mass: %g, propellant_mass: 0}]\n"
             "phases:\n"
             "  - name: fall\n"
             "    model: flat6\n"
             "    stages: [ball]\n"
             "    stop_time: 300\n"
             "    aero: {s_ref: %g, CD: env_cd.csv}\n"
             "    integrator: {method: dopri5, tolerance: 1.0e-10, output_interval: 10}\n",
             G, BALL_M, BALL_S);
    lv_mission *m = load("env_drift.yaml", text);
    if (m == NULL)
        return;
    lv_err err;
    lv_run *r = NULL;
    CHECK_OK(lv_run_create(m, &r, &err), &err);
    const lv_run_options opt = {.threads = 1};
    CHECK_OK(lv_run_execute(r, &opt, &err), &err);
    const double vt = sqrt(2.0 * BALL_M * G / (rho * BALL_CD * BALL_S));
    CHECK_CLOSE(final(r, 0, "vx"), 6.0, 1e-6);
    CHECK_CLOSE(final(r, 0, "vy"), -2.0, 1e-6);
    CHECK_CLOSE(final(r, 0, "vz"), -vt + 3.0, 1e-6);
    CHECK_CLOSE(final(r, 0, "v_air"), vt, 1e-6);
    CHECK_CLOSE(final(r, 0, "drag"), BALL_M * G, 1e-6); /* steady: drag carries the weight */
    printf("flat drift: v = (%.9f, %.9f, %.9f) m/s vs (6, -2, %.9f)\n", final(r, 0, "vx"),
           final(r, 0, "vy"), final(r, 0, "vz"), -vt + 3.0);
    /* the wind is a slot of the environment: a run without it falls straight down */
    CHECK_OK(lv_run_set(r, "environment.wind.east", 0.0, &err), &err);
    CHECK_OK(lv_run_set(r, "environment.wind.north", 0.0, &err), &err);
    CHECK_OK(lv_run_execute(r, &opt, &err), &err);
    CHECK(final(r, 0, "vx") == 0.0 && final(r, 0, "vy") == 0.0);
    CHECK_CLOSE(final(r, 0, "vz"), -vt + 3.0, 1e-6);
    lv_run_free(r);
    lv_mission_free(m);
    remove("env_drift.yaml");
    remove("env_cd.csv");
    remove("env_air.csv");

    /* a wind table with extrap: error ends the phase where the body leaves it, with the
     * reason: a ball thrown up at 300 m/s passes the table's top (1000 m) after ~3.5 s */
    write_text("env_w.csv", "h [m], north [m/s], east [m/s]\n0, 0, 5\n1000, 0, 10\n");
    m = load("env_wx.yaml", "mission: {name: wx}\n"
                            "environment: {atmosphere: us76,\n"
                            "              wind: {file: env_w.csv, extrap: error}}\n"
                            "parameters: {start_z: 100, start_vel: 300, start_fpa_deg: 80}\n"
                            "stages: [{name: s, dry_mass: 100, propellant_mass: 0}]\n"
                            "phases: [{name: up, model: flat6, stages: [s], stop_time: 60,\n"
                            "          aero: {s_ref: 0.1, CD: 0.3}}]\n");
    if (m != NULL) {
        CHECK_OK(lv_run_create(m, &r, &err), &err);
        CHECK(lv_run_execute(r, &opt, &err) == LV_ERR_SOLVER);
        const lv_phase_result *pr = lv_run_result(r, 0);
        /* the time the model left the table is in the message; the phase's end time is the
         * last accepted state before it (with auto's dop853 the step that would have crossed
         * 1000 m started at ~1.1 s; with dassl's small steps, at ~3.5 s) */
        CHECK(pr->state == LV_PHASE_FAILED && pr->t_end < 4.0);
        CHECK(strstr(pr->error, "right-hand side returned -1 at t = 3.") != NULL);
        CHECK(strstr(pr->error, "wind: table 'env_w': axis 0 'h' [m] = ") != NULL);
        CHECK(strstr(pr->error, "is outside [0, 1000] (extrapolation: error)") != NULL);
        lv_run_free(r);
        lv_mission_free(m);
    }
    remove("env_wx.yaml");
    remove("env_w.csv");
}


/* ---- (4) several aerodynamic tables per phase ---------------------------------------------- */
/* Body axes, one table per coefficient:
 *   CA over Mach from a CSV file:          CA(M) = 0.2 + 0.1 M       (rows M = 0, 1, 3)
 *   CN over Mach and alpha from a MAT v5/v7.3 struct {mach, alpha, CN, CM}, output chosen by
 *   name (`output: CN`):                   CN(M, a) = 2 a + 0.05 M   (M = 0, 1, 3; a = 0, 0.1)
 *   CY the constant 0.
 * Both functions are (bi)linear, so linear interpolation gives them exactly. At the first
 * row of a dof3 phase (h = 10 km over the Earth, 500 m/s horizontal relative to the ground,
 * alpha = 4 deg, no wind) the model's own Mach number and q give the expected forces through
 * the body-to-wind relations (Anderson, Fundamentals of Aerodynamics, 5th ed., eqs. 1.1-1.2):
 *   CD = CA cos a + CN sin a,  CL = CN cos a - CA sin a,
 *   drag = q S CD,  lift = q S CL,  side force 0.
 * The examples/dof3-branch tables (one table for the set, outputs named as the coefficients)
 * are flown by test_runner. */
static void mat_struct_cn(const char *file, enum mat_ft ver)
{
    double mach[3] = {0.0, 1.0, 3.0}, alpha[2] = {0.0, 0.1}, cn[6], cm[6];
    for (size_t j = 0; j < 2; j++)
        for (size_t i = 0; i < 3; i++) {
            cn[i + 3 * j] = 2.0 * alpha[j] + 0.05 * mach[i];
            cm[i + 3 * j] = -0.5 * alpha[j];
        }
    const char *fields[] = {"mach", "alpha", "CN", "CM"};
    size_t dm[2] = {1, 3}, da[2] = {1, 2}, dg[2] = {3, 2}, one[2] = {1, 1};
    double *data[4] = {mach, alpha, cn, cm};
    size_t *dims[4] = {dm, da, dg, dg};
    mat_t *mat = Mat_CreateVer(file, NULL, ver);
    CHECK(mat != NULL);
    if (mat == NULL)
        return;
    matvar_t *sv = Mat_VarCreateStruct("aero", 2, one, fields, 4);
    for (size_t i = 0; i < 4; i++)
        Mat_VarSetStructFieldByIndex(
            sv, i, 0, Mat_VarCreate(NULL, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims[i], data[i], 0));
    CHECK(Mat_VarWrite(mat, sv, MAT_COMPRESSION_NONE) == 0);
    Mat_VarFree(sv);
    Mat_Close(mat);
}

static void test_aero_tables(void)
{
    write_text("env_ca.csv", "mach [1], CA [1]\n0, 0.2\n1, 0.3\n3, 0.5\n");
    const struct {
        const char *file;
        enum mat_ft ver;
    } fmt[] = {{"env_cn5.mat", MAT_FT_MAT5}, {"env_cn73.mat", MAT_FT_MAT73}};
    for (size_t f = 0; f < 2; f++) {
        mat_struct_cn(fmt[f].file, fmt[f].ver);
        char text[2048];
        snprintf(text, sizeof text,
                 "mission: {name: aero}\n"
                 "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}\n"
                 "parameters: {start_lat_deg: 10, start_lon_deg: 20, start_h: 10000,\n"
                 "             start_vel: 500, start_fpa: 0, start_chi_deg: 90}\n"
                 "stages: [{name: v, dry_mass: 1000, propellant_mass: 0}]\n"
                 "phases:\n"
                 "  - name: glide\n"
                 "    model: dof3\n"
                 "    stages: [v]\n"
                 "    stop_time: 1\n"
                 "    inputs: {alpha_deg: 4}\n"
                 "    aero:\n"
                 "      s_ref: 2\n"
                 "      axes: body\n"
                 "      CA: env_ca.csv\n"
                 "      CN: {file: %s, var: aero, output: CN}\n"
                 "      CY: 0\n"
                 "    integrator: {output_interval: 0.5}\n",
                 fmt[f].file);
        lv_mission *m = load("env_aero.yaml", text);
        if (m == NULL)
            continue;
        lv_err err;
        lv_run *r = NULL;
        CHECK_OK(lv_run_create(m, &r, &err), &err);
        const lv_run_options opt = {.threads = 1};
        CHECK_OK(lv_run_execute(r, &opt, &err), &err);
        const lv_result *res = lv_run_rows(r, 0);
        CHECK(res != NULL);
        if (res != NULL) {
            size_t cm, cq, cd, cl, cy;
            CHECK_OK(lv_result_column(res, "mach", &cm, &err), &err);
            CHECK_OK(lv_result_column(res, "q_dyn", &cq, &err), &err);
            CHECK_OK(lv_result_column(res, "drag", &cd, &err), &err);
            CHECK_OK(lv_result_column(res, "lift", &cl, &err), &err);
            CHECK_OK(lv_result_column(res, "side_force", &cy, &err), &err);
            const double M = lv_result_value(res, 0, cm), q = lv_result_value(res, 0, cq);
            const double a = 4.0 * DEG, CA = 0.2 + 0.1 * M, CN = 2.0 * a + 0.05 * M;
            CHECK(M > 1.5 && M < 1.8); /* 500 m/s at 10 km (a = 299.5 m/s) */
            CHECK_REL(lv_result_value(res, 0, cd), q * 2.0 * (CA * cos(a) + CN * sin(a)), 1e-12);
            CHECK_REL(lv_result_value(res, 0, cl), q * 2.0 * (CN * cos(a) - CA * sin(a)), 1e-12);
            CHECK(fabs(lv_result_value(res, 0, cy)) < 1e-9 * q);
            printf("aero tables (%s): M %.6f, drag %.3f N = q S (CA cos a + CN sin a) = %.3f N\n",
                   fmt[f].file, M, lv_result_value(res, 0, cd),
                   q * 2.0 * (CA * cos(a) + CN * sin(a)));
        }
        lv_run_free(r);
        lv_mission_free(m);
        remove(fmt[f].file);
    }
    remove("env_aero.yaml");
    remove("env_ca.csv");
}


/* ---- (5) examples/sounding-rocket ------------------------------------------------------- */
/* The example flies: burnout when the 200 kg of propellant are gone at the constant mass
 * flow F / (Isp g0) = 15000 / (230 * 9.80665) kg/s (Sutton & Biblarz, eq. 2-5), apogee where
 * vz = 0, impact at z = 0; the east wind carries it east (vx > 0 although it starts with no
 * horizontal velocity), and drag = q S CD with CD from the table at the final Mach number. */
static void test_sounding_rocket_example(void)
{
    char path[1024];
    const char *root = getenv("LV_SOURCE_DIR");
    snprintf(path, sizeof path, "%s/examples/sounding-rocket/mission.yaml", root ? root : "..");
    lv_err err;
    lv_mission *m = NULL;
    CHECK_OK(lv_mission_load(path, &m, &err), &err);
    if (m == NULL)
        return;
    lv_run *r = NULL;
    CHECK_OK(lv_run_create(m, &r, &err), &err);
    const lv_run_options opt = {.threads = 1};
    CHECK_OK(lv_run_execute(r, &opt, &err), &err);
    CHECK_CLOSE(final(r, 0, "time"), 200.0 / (15000.0 / (230.0 * 9.80665)), 1e-6);
    CHECK_CLOSE(final(r, 1, "vz"), 0.0, 1e-6);
    CHECK_CLOSE(final(r, 2, "z"), 0.0, 1e-4);
    CHECK(final(r, 2, "vx") > 0.0 && final(r, 2, "x") > 0.0);
    const double mach = final(r, 2, "mach"); /* between the rows Mach 2 and 4 of cd_mach.csv */
    CHECK(mach > 2.0 && mach < 4.0);
    const double cd = 0.45 + (0.32 - 0.45) * (mach - 2.0) / 2.0;
    CHECK_REL(final(r, 2, "drag"), final(r, 2, "q_dyn") * 0.0314 * cd, 1e-12);
    lv_run_free(r);
    lv_mission_free(m);
}

int main(void)
{
    test_kepler_sphere();
    test_custom_j2();
    test_flat_drag();
    test_flat_wind();
    test_aero_tables();
    test_sounding_rocket_example();
    return check_report("test_mission_env");
}
