/* test_mission_env.c - the environment a mission file defines (docs/mission-format.md,
 * "environment"), flown through whole missions (lv_mission_load, lv_run) and checked against
 * closed forms:
 *  - a planet by its constants: a dof3 coast over a non-rotating point-mass sphere is the
 *    two-body problem (apoapsis at half the Kepler period, the orbit closing after one);
 *  - a custom J2: the nodal regression rate of the first-order secular theory, and again after
 *    a run changes J2 (the gravity is then built from the run's value).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
             R, GM, v0, T, T);
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
}

int main(void)
{
    test_kepler_sphere();
    test_custom_j2();
    return check_report("test_mission_env");
}
