/* test_flare.c - the steering law `flare` (src/dynamics/guid_flare.c) in a 3-DoF glide over the
 * rotating WGS-84 Earth with the US76 atmosphere:
 *   (a) from an entry on its path the height above the runway plane follows the exponential
 *       flare's closed form h(t) = (h0 + h_a) exp(-t / tau) - h_a, tau = h0 / (s0 - s_td),
 *       h_a = s_td tau (Blakelock, Automatic Control of Aircraft and Missiles, 2nd ed., sec.
 *       5.6), and crosses the plane at the commanded sink rate s_td;
 *   (b) with a time constant of its own (an entry off the path) the departure from the path
 *       decays as exp(-path_gain t): the sink rate at the plane is again s_td;
 *   (c) beside the centre line, the bank brings the vehicle back toward it;
 *   (d) an alpha range too small to hold the path: the law saturates at alpha_max (no
 *       failure), and the path is not held;
 *   (e) refusals: a dof6 phase, a throttle law, a start that does not sink faster than s_td,
 *       alpha_max below alpha_min, each with file:line:col and the reason (check = run).
 * The height above the plane is computed here from the phase's exact geodetic outputs (lat,
 * lon, h) through lv_frames_geodetic_to_ecef, independently of the law's own arithmetic. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "lvsim/lv_mission.h"
#include "lvsim/lv_planet.h"
#include "lvsim/lv_io.h"
#include "mission_kit.h"

#define DEG (M_PI / 180.0)
#define LAT0 (5.236 * DEG)
#define LON0 (-52.775 * DEG)
#define ELEV 10.0

/* A 20 t glider: CL = 3 alpha (alpha in rad; linear, so the table's interpolation is exact),
 * CD = 0.04 + 0.1 CL^2 at the table's points, S_ref 150 m^2 (wing loading 1.3 kPa). */
static const char *const aero_cl =
    "mach [1] \\ alpha [rad], -0.4, -0.2, 0.0, 0.2, 0.4, 0.6\n"
    "0, -1.2, -0.6, 0.0, 0.6, 1.2, 1.8\n"
    "2, -1.2, -0.6, 0.0, 0.6, 1.2, 1.8\n";
static const char *const aero_cd =
    "mach [1] \\ alpha [rad], -0.4, -0.2, 0.0, 0.2, 0.4, 0.6\n"
    "0, 0.184, 0.076, 0.04, 0.076, 0.184, 0.364\n"
    "2, 0.184, 0.076, 0.04, 0.076, 0.184, 0.364\n";

#define HEAD_MISSION                                                                       \
    "mission: {name: flare, epoch: 2026-03-01T12:00:00Z}\n"                                \
    "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}\n"
#define HEAD_STAGES                                                                        \
    "stages:\n"                                                                             \
    "  - {name: g, dry_mass: 20000, propellant_mass: 0}\n"                                  \
    "phases:\n"

/* A flare phase from h0 above the threshold (elevation 10 m), speed v, flight-path angle fpa,
 * heading 90 deg, `extra` guidance keys. */
static void mission(char *buf, size_t cap, double h0, double v, double fpa_deg, double lat_off,
                    const char *extra)
{
    snprintf(buf, cap,
             HEAD_MISSION
             "parameters: {start_lat_deg: %.12g, start_lon_deg: -52.775, start_h: %.12g,\n"
             "             start_vel: %.12g, start_fpa_deg: %.12g, start_chi_deg: 90}\n"
             HEAD_STAGES
             "  - {name: flare, model: dof3, stages: [g], start_time: 0, stop_time: 60,\n"
             "     end: [{altitude: 5, direction: falling}], throttle: off,\n"
             "     guidance: {law: flare, runway_lat_deg: 5.236, runway_lon_deg: -52.775,\n"
             "                runway_elevation: 10, runway_heading_deg: 90%s},\n"
             "     aero: {s_ref: 150, CL: flare_cl.csv, CD: flare_cd.csv},\n"
             "     integrator: {output_interval: 0.05}}\n",
             5.236 + lat_off, ELEV + h0, v, fpa_deg, extra);
}

/* Height above the runway plane and its rate over the rows of phase 0 (the plane: through the
 * threshold, normal to the ellipsoid there). */
typedef struct rows {
    size_t n;
    double t[4096], h[4096], y[4096], hd[4096]; /* s, m, m, m/s */
} rows;

static void plane_rows(const lv_run *r, rows *out)
{
    lv_err err;
    const lv_result *res = lv_run_rows(r, 0);
    out->n = 0;
    CHECK(res != NULL);
    if (res == NULL)
        return;
    size_t ct, cla, clo, ch, cv[3];
    CHECK_OK(lv_result_column(res, "v_north", &cv[0], &err), &err);
    CHECK_OK(lv_result_column(res, "v_east", &cv[1], &err), &err);
    CHECK_OK(lv_result_column(res, "v_down", &cv[2], &err), &err);
    CHECK_OK(lv_result_column(res, "time", &ct, &err), &err);
    CHECK_OK(lv_result_column(res, "lat", &cla, &err), &err);
    CHECK_OK(lv_result_column(res, "lon", &clo, &err), &err);
    CHECK_OK(lv_result_column(res, "h", &ch, &err), &err);
    const lv_planet earth = lv_planet_earth();
    double r0[3];
    lv_frames_geodetic_to_ecef(&earth, LAT0, LON0, ELEV, r0);
    const double n[3] = {cos(LAT0) * cos(LON0), cos(LAT0) * sin(LON0), sin(LAT0)};
    const double w[3] = {-sin(LAT0) * cos(LON0), -sin(LAT0) * sin(LON0), cos(LAT0)}; /* north */
    for (size_t i = 0; i < lv_result_rows(res) && out->n < 4096; i++) {
        double rr[3];
        lv_frames_geodetic_to_ecef(&earth, lv_result_value(res, i, cla),
                                   lv_result_value(res, i, clo), lv_result_value(res, i, ch),
                                   rr);
        /* the velocity relative to the planet from its NED components at the vehicle */
        const double la = lv_result_value(res, i, cla), lo = lv_result_value(res, i, clo);
        const double N[3] = {-sin(la) * cos(lo), -sin(la) * sin(lo), cos(la)};
        const double E[3] = {-sin(lo), cos(lo), 0.0};
        const double D[3] = {-cos(la) * cos(lo), -cos(la) * sin(lo), -sin(la)};
        double hh = 0.0, yy = 0.0, hd = 0.0;
        for (int j = 0; j < 3; j++) {
            hh += (rr[j] - r0[j]) * n[j];
            yy -= (rr[j] - r0[j]) * w[j]; /* right of a runway heading east: south */
            hd += (lv_result_value(res, i, cv[0]) * N[j] + lv_result_value(res, i, cv[1]) * E[j] +
                   lv_result_value(res, i, cv[2]) * D[j]) * n[j];
        }
        out->hd[out->n] = hd;
        out->t[out->n] = lv_result_value(res, i, ct);
        out->h[out->n] = hh;
        out->y[out->n] = yy;
        out->n++;
    }
}

/* The sink rate where the rows cross the plane (interpolated linearly in h between the two
 * rows around it). */
static double sink_at_plane(const rows *p)
{
    for (size_t i = 1; i < p->n; i++)
        if (p->h[i - 1] > 0.0 && p->h[i] <= 0.0) {
            const double f = p->h[i - 1] / (p->h[i - 1] - p->h[i]);
            return -(p->hd[i - 1] + f * (p->hd[i] - p->hd[i - 1]));
        }
    return NAN;
}

static lv_run *run_flare(const char *yaml, lv_mission **m)
{
    return run_text("test_flare.yaml", yaml, m);
}

static void test_closed_form(void)
{
    char yaml[2048];
    const double h0 = 30.0, v = 70.0, fpa = -4.0, s_td = 0.6;
    mission(yaml, sizeof yaml, h0, v, fpa, 0.0, "");
    lv_mission *m;
    lv_run *r = run_flare(yaml, &m);
    CHECK(r != NULL);
    if (r == NULL)
        return;
    rows p;
    plane_rows(r, &p);
    CHECK(p.n > 100);
    /* the start: the threshold's own vertical, so the plane height is the altitude above it */
    CHECK_CLOSE(p.h[0], h0, 1e-6);
    const double s0 = -v * sin(fpa * DEG), tau = h0 / (s0 - s_td), h_a = s_td * tau;
    double worst = 0.0;
    for (size_t i = 0; i < p.n && p.h[i] > 0.0; i++) {
        const double want = (h0 + h_a) * exp(-p.t[i] / tau) - h_a;
        if (fabs(p.h[i] - want) > worst)
            worst = fabs(p.h[i] - want);
    }
    printf("flare from %.0f m at %.3g m/s sink: tau %.4f s, largest departure from the closed "
           "form %.3g m\n", h0, s0, tau, worst);
    CHECK(worst < 1e-6);
    /* the plane is crossed at the commanded sink rate (interpolated between rows 0.05 s
     * apart: the slope changes by (s_td / tau) 0.05 s ~ 0.4 % between them, linearly to
     * 1e-5 relative) */
    CHECK_REL(sink_at_plane(&p), s_td, 1e-4);
    lv_run_free(r);
    lv_mission_free(m);
}

/* The column `name` of phase 0's rows at row i. */
static double col_at(const lv_run *r, const char *name, size_t i)
{
    lv_err err;
    const lv_result *res = lv_run_rows(r, 0);
    size_t c;
    if (res == NULL || lv_result_column(res, name, &c, &err) != LV_OK)
        return NAN;
    return lv_result_value(res, i, c);
}

/* (b) tau 10 s with an entry sinking at 4.88 m/s: e(0) = h'0 + (h0 + h_a) / tau = -4.88 + 36 /
 * 10 = -1.28 m/s, then e(t) = e(0) exp(-t) (path_gain 1/s). */
static void test_off_path(void)
{
    char yaml[2048];
    const double h0 = 30.0, v = 70.0, fpa = -4.0, s_td = 0.6, tau = 10.0, h_a = s_td * tau;
    mission(yaml, sizeof yaml, h0, v, fpa, 0.0, ", tau: 10");
    lv_mission *m;
    lv_run *r = run_flare(yaml, &m);
    CHECK(r != NULL);
    if (r == NULL)
        return;
    rows p;
    plane_rows(r, &p);
    const double e0 = v * sin(fpa * DEG) + (h0 + h_a) / tau;
    int checked = 0;
    for (size_t i = 1; i + 1 < p.n; i++) {
        const double t = p.t[i];
        if (fabs(t - 1.0) > 1e-9 && fabs(t - 2.0) > 1e-9 && fabs(t - 4.0) > 1e-9)
            continue;
        CHECK_CLOSE(p.hd[i] + (p.h[i] + h_a) / tau, e0 * exp(-t), 1e-7);
        checked++;
    }
    CHECK(checked == 3);
    /* on the path long before the plane: it is crossed at the commanded sink rate */
    CHECK_REL(sink_at_plane(&p), s_td, 5e-3);
    lv_run_free(r);
    lv_mission_free(m);
}

/* (c) 55 m right of the centre line (south of a runway heading east): the bank turns the
 * vehicle back, and the height still follows the closed form (the solved alpha holds the
 * vertical acceleration whatever the bank). */
static void test_lateral(void)
{
    char yaml[2048];
    const double h0 = 30.0, v = 70.0, fpa = -4.0, s_td = 0.6;
    mission(yaml, sizeof yaml, h0, v, fpa, -0.0005, "");
    lv_mission *m;
    lv_run *r = run_flare(yaml, &m);
    CHECK(r != NULL);
    if (r == NULL)
        return;
    rows p;
    plane_rows(r, &p);
    CHECK(p.n > 100);
    /* 55 m south of the threshold the plane is 55^2 / (2 R) = 2.4e-4 m closer than the
     * altitude: the path starts from the height the law sees */
    CHECK_CLOSE(p.h[0], h0, 3e-4);
    const double h1 = p.h[0];
    const double s0 = -v * sin(fpa * DEG), tau = h1 / (s0 - s_td), h_a = s_td * tau;
    double worst = 0.0, bank_min = 0.0;
    for (size_t i = 0; i < p.n && p.h[i] > 0.0; i++) {
        const double want = (h1 + h_a) * exp(-p.t[i] / tau) - h_a;
        worst = fmax(worst, fabs(p.h[i] - want));
        bank_min = fmin(bank_min, col_at(r, "mu_in", i));
    }
    printf("55 m off the centre line: closed form within %.3g m, bank down to %.3g deg, "
           "%.3g m off at the end\n", worst, bank_min / DEG, p.y[p.n - 1]);
    CHECK(worst < 1e-6);
    CHECK(p.y[0] > 54.0 && p.y[0] < 56.0);    /* 0.0005 deg of latitude: 55.3 m */
    CHECK(bank_min < -1.0 * DEG);              /* it banks left, toward the line ... */
    CHECK(bank_min >= -10.0 * DEG - 1e-12);    /* ... within bank_max */
    CHECK(fabs(p.y[p.n - 1]) < 0.5 * p.y[0]);  /* and closes on it */
    lv_run_free(r);
    lv_mission_free(m);
}

/* (d) alpha_max 3 deg (CL 0.16, a third of the lift the glide needs): alpha stays at the
 * bound, the phase flies on (done), and the plane is met far faster than s_td. */
static void test_saturated(void)
{
    char yaml[2048];
    mission(yaml, sizeof yaml, 30.0, 70.0, -4.0, 0.0, ", alpha_max_deg: 3");
    lv_mission *m;
    lv_run *r = run_flare(yaml, &m);
    CHECK(r != NULL);
    if (r == NULL)
        return;
    CHECK(lv_run_result(r, 0)->state == LV_PHASE_DONE);
    rows p;
    plane_rows(r, &p);
    CHECK_CLOSE(col_at(r, "alpha_in", 1), 3.0 * DEG, 1e-12);
    CHECK(sink_at_plane(&p) > 3.0);
    lv_run_free(r);
    lv_mission_free(m);
}

/* (e) what is refused: at load with the file's position (lvsim check = run). */
static void expect_load_error(const char *yaml, const char *want)
{
    lv_err err = {LV_OK, ""};
    lv_mission *m = NULL;
    write_file("test_flare_bad.yaml", yaml);
    const lv_status st = lv_mission_load("test_flare_bad.yaml", &m, &err);
    CHECK(st == LV_ERR_INPUT);
    if (strstr(err.msg, want) == NULL) {
        fprintf(stderr, "expected '%s' in: %s\n", want, err.msg);
        CHECK(0);
    }
    lv_mission_free(m);
}

static void test_refused(void)
{
    char yaml[2048];
    mission(yaml, sizeof yaml, 30.0, 70.0, -4.0, 0.0, ", alpha_min_deg: 5, alpha_max_deg: 4");
    expect_load_error(yaml, "test_flare_bad.yaml:11:");
    expect_load_error(yaml, "alpha_max 4 deg must be above alpha_min 5 deg");
    /* a start that climbs: no path tangent to it (root phase: refused at load) */
    mission(yaml, sizeof yaml, 30.0, 70.0, 1.0, 0.0, "");
    expect_load_error(yaml, "sinking faster than sink_rate 0.6 m/s (or give tau)");
    /* a throttle law would change the forces the angle of attack is solved from */
    mission(yaml, sizeof yaml, 30.0, 70.0, -4.0, 0.0, "");
    char *off = strstr(yaml, "throttle: off");
    CHECK(off != NULL);
    if (off != NULL) {
        char with[2200];
        snprintf(with, sizeof with, "%.*sthrottle: {value: 1, g_limit: 2}%s", (int)(off - yaml),
                 yaml, off + strlen("throttle: off"));
        expect_load_error(with, "solves the angle of attack from the forces");
    }
}

int main(void)
{
    write_file("flare_cl.csv", aero_cl);
    write_file("flare_cd.csv", aero_cd);
    test_closed_form();
    test_off_path();
    test_lateral();
    test_saturated();
    test_refused();
    return check_report("test_flare");
}
