/* test_guidance.c - the 3-DoF model's steering and throttle laws against known answers
 * (issue 12, docs/guidance.md):
 *   (a) a constant-thrust-acceleration gravity turn against its closed-form solution;
 *   (b) a vacuum ascent with linear-tangent steering against the optimal-control solution of
 *       the same problem (Bryson & Ho);
 *   (c) max-q and g-limit throttle laws keep q and the axial load factor at their limits;
 *   (d) the landing-burn law lands at the speed the kinematics predict;
 *   (e) the heading law turns a glider onto the bearing of its target within its bank and
 *       load-factor limits;
 *   (f) one attitude commanded in the three frames gives one thrust direction where the
 *       frames coincide;
 *   (g) the heading law's limits on its angle of attack (lv_guid_heading_alpha): the
 *       load-factor soft saturation and the dynamic-pressure release, by their defining
 *       properties;
 * and bad input refused with file:line:column.
 *
 * "Flat world, uniform gravity" is a non-rotating sphere of radius R = 1e10 m with
 * GM = g0 R^2 and no atmosphere: over the few kilometres flown here the gravity's change
 * (2 h / R), the centrifugal term v^2 / R and the curvature x^2 / (2 R) are below 1e-6 of the
 * quantities compared (bounds given at each test). */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mission_kit.h"
#include "dynamics/guidance.h"
#include "lvsim/lv_mission.h"

#define G0 9.80665
#define DEG (M_PI / 180.0)

static double final(const lv_run *r, size_t k, const char *name)
{
    double v = NAN;
    lv_err err;
    CHECK_OK(lv_run_final(r, k, name, &v, &err), &err);
    return v;
}

/* Extremes of column `name` over phase k's rows. */
static void col_range(const lv_run *r, size_t k, const char *name, double *lo, double *hi)
{
    const lv_result *res = lv_run_rows(r, k);
    size_t c;
    *lo = INFINITY, *hi = -INFINITY;
    if (res == NULL || lv_result_column(res, name, &c, NULL) != LV_OK) {
        CHECK(0);
        return;
    }
    for (size_t i = 0; i < lv_result_rows(res); i++) {
        const double v = lv_result_value(res, i, c);
        *lo = v < *lo ? v : *lo;
        *hi = v > *hi ? v : *hi;
    }
}

/* The same over the rows where the engines burn (throttle_in is 0 with the engines off). */
static void col_range_on(const lv_run *r, size_t k, const char *name, double *lo, double *hi)
{
    const lv_result *res = lv_run_rows(r, k);
    size_t c, on;
    *lo = INFINITY, *hi = -INFINITY;
    if (res == NULL || lv_result_column(res, name, &c, NULL) != LV_OK ||
        lv_result_column(res, "engine_on", &on, NULL) != LV_OK) {
        CHECK(0);
        return;
    }
    for (size_t i = 0; i < lv_result_rows(res); i++) {
        if (lv_result_value(res, i, on) != 1.0)
            continue;
        const double v = lv_result_value(res, i, c);
        *lo = v < *lo ? v : *lo;
        *hi = v > *hi ? v : *hi;
    }
}

/* ---- (a) gravity turn ------------------------------------------------------------------- */

/* Thrust along the velocity at a constant thrust acceleration n g in uniform gravity g:
 * dv/dt = g (n - cos b), v db/dt = g sin b, b the angle from the vertical. With z = tan(b/2):
 * v = C z^(n-1) (1 + z^2) and t = (C / g) [z^(n-1) / (n-1) + z^(n+1) / (n+1)] + const
 * (Culler & Fried, "Universal gravity turn trajectories", J. Appl. Phys. 28 (1957) 672;
 * Wiesel, Spaceflight Dynamics, sec. 9.2). Both follow by substitution, checked here as
 * d(ln v)/db = (n - cos b) / sin b = (n-1)/(2z) + (n+1) z / 2. */
static double gt_v(double n, double v0, double b0, double b)
{
    const double z0 = tan(0.5 * b0), z = tan(0.5 * b);
    return v0 * pow(z / z0, n - 1.0) * (1.0 + z * z) / (1.0 + z0 * z0);
}

static double gt_t(double n, double v0, double b0, double b, double g)
{
    const double z0 = tan(0.5 * b0), z = tan(0.5 * b);
    const double C = v0 / (pow(z0, n - 1.0) * (1.0 + z0 * z0));
    const double F = pow(z, n - 1.0) / (n - 1.0) + pow(z, n + 1.0) / (n + 1.0);
    const double F0 = pow(z0, n - 1.0) / (n - 1.0) + pow(z0, n + 1.0) / (n + 1.0);
    return C / g * (F - F0);
}

/* `guidance`: the gravity turn after its kick, or the prograde law: the same attitude */
static void test_gravity_turn(const char *guidance)
{
    /* m = 1100 kg, T = n m g0 with n = 2; Isp 1e9 s burns 2e-6 kg/s: T/m constant to 1e-7 */
    const double n = 2.0, v0 = 100.0, b0 = 10.0 * DEG, b1 = 45.0 * DEG;
    char yaml[2048];
    snprintf(yaml, sizeof yaml,
             "mission: {name: gravity-turn}\n" FLAT_WORLD
             "parameters: {start_h: 1000, start_vel: %.17g, start_fpa_deg: 80, start_chi_deg: 90}\n"
             "stages: [{name: s, dry_mass: 1000, propellant_mass: 100,\n"
             "          engines: [{thrust_vac: %.17g, isp_vac: 1.0e9}]}]\n"
             "phases:\n"
             "  - {name: turn, model: dof3, stages: [s], stop_time: 200,\n"
             "     guidance: %s,\n"
             "     integrator: {tolerance: 1.0e-10}, end: [{fpa_deg: 45}]}\n",
             v0, n * 1100.0 * G0, guidance);
    lv_mission *m;
    lv_run *r = run_text("gt.yaml", yaml, &m);
    if (r == NULL)
        return lv_mission_free(m);
    /* v(45 deg) = 550.47 m/s at t = 40.5 s. Flying ~10 km up and ~8 km across, the sphere
     * departs from the flat world by 2 h/R <= 2e-6 in g, and its horizon turns by x/R = 8e-7
     * rad, which moves the 45 deg point by dv/db x/R = 1000 m/s/rad x 8e-7 (1.5e-6 of v):
     * together below 1e-5 */
    const double v_ref = gt_v(n, v0, b0, b1), t_ref = gt_t(n, v0, b0, b1, G0);
    printf("%s to 45 deg: v %.6f m/s (closed form %.6f), t %.6f s (%.6f)\n", guidance,
           final(r, 0, "v_rel"), v_ref, lv_run_result(r, 0)->t_end, t_ref);
    CHECK_REL(final(r, 0, "v_rel"), v_ref, 1e-5);
    CHECK_REL(lv_run_result(r, 0)->t_end, t_ref, 1e-5);
    CHECK_CLOSE(final(r, 0, "alpha_in"), 0.0, 1e-12);
    lv_run_free(r);
    lv_mission_free(m);
}

/* ---- (b) linear tangent ------------------------------------------------------------------ */

/* Flat world, constant thrust acceleration a, uniform gravity g: the steering that reaches
 * altitude H with zero vertical speed at t_f with the most horizontal speed is the linear
 * tangent law tan theta = xi0 - c t (Bryson & Ho, Applied Optimal Control, sec. 2.7). Its
 * trajectory in closed form (xi = xi0 - c t, starting at rest):
 *   vx = (a/c) [asinh xi0 - asinh xi],  vy = (a/c) [sqrt(1+xi0^2) - sqrt(1+xi^2)] - g t,
 *   y  = (a/c) [sqrt(1+xi0^2) t - (G(xi0) - G(xi)) / c] - g t^2 / 2,
 * G(s) = (s sqrt(1+s^2) + asinh s) / 2 (integrals of sec theta and tan theta sec theta). */
static void lt_state(double a, double g, double xi0, double c, double t, double *y, double *vx,
                     double *vy)
{
    const double xi = xi0 - c * t;
    const double s0 = sqrt(1.0 + xi0 * xi0), s1 = sqrt(1.0 + xi * xi);
    const double G0v = 0.5 * (xi0 * s0 + asinh(xi0)), G1 = 0.5 * (xi * s1 + asinh(xi));
    *vx = a / c * (asinh(xi0) - asinh(xi));
    *vy = a / c * (s0 - s1) - g * t;
    *y = a / c * (s0 * t - (G0v - G1) / c) - 0.5 * g * t * t;
}

static void test_linear_tangent(void)
{
    const double a = 2.0 * G0, tf = 60.0, H = 10000.0;
    /* the optimal law's xi0 and c from y(tf) = H, vy(tf) = 0: Newton on the closed form */
    double xi0 = 2.0, c = 0.05;
    for (int it = 0; it < 50; it++) {
        double y, vx, vy, y1, vy1, y2, vy2;
        const double h1 = 1e-7 * xi0, h2 = 1e-7 * c;
        lt_state(a, G0, xi0, c, tf, &y, &vx, &vy);
        lt_state(a, G0, xi0 + h1, c, tf, &y1, &vx, &vy1);
        lt_state(a, G0, xi0, c + h2, tf, &y2, &vx, &vy2);
        const double J[2][2] = {{(y1 - y) / h1, (y2 - y) / h2}, {(vy1 - vy) / h1, (vy2 - vy) / h2}};
        const double f0 = y - H, f1 = vy, det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
        xi0 -= (J[1][1] * f0 - J[0][1] * f1) / det;
        c -= (J[0][0] * f1 - J[1][0] * f0) / det;
    }
    double y_ref, vx_ref, vy_ref;
    lt_state(a, G0, xi0, c, tf, &y_ref, &vx_ref, &vy_ref);
    CHECK_CLOSE(y_ref, H, 1e-6);
    CHECK_CLOSE(vy_ref, 0.0, 1e-9);
    char yaml[2048];
    snprintf(yaml, sizeof yaml,
             "mission: {name: linear-tangent}\n" FLAT_WORLD
             "parameters: {start_h: 1000, start_vel: 0}\n"
             "stages: [{name: s, dry_mass: 1000, propellant_mass: 100,\n"
             "          engines: [{thrust_vac: %.17g, isp_vac: 1.0e9}]}]\n"
             "phases:\n"
             "  - {name: climb, model: dof3, stages: [s], stop_time: 100,\n"
             "     guidance: {law: linear_tangent, a: %.17g, b: %.17g, heading_deg: 90},\n"
             "     integrator: {tolerance: 1.0e-10}, end: [{time: %.17g}]}\n",
             a * 1100.0, xi0, -c, tf);
    lv_mission *m;
    lv_run *r = run_text("lt.yaml", yaml, &m);
    if (r == NULL)
        return lv_mission_free(m);
    /* ~20 km downrange at ~600 m/s: centrifugal v^2/R = 4e-5 m/s^2, gravity change 2h/R = 2e-6
     * and curvature x^2/2R = 0.02 m leave the flat-world answer within 0.1 m and 5 mm/s */
    const double h = final(r, 0, "h") - 1000.0, ve = final(r, 0, "v_east");
    const double vu = -final(r, 0, "v_down");
    printf("linear tangent (xi0 %.6f, c %.6f 1/s): h %.4f m (%.4f), v_x %.5f m/s (%.5f), "
           "v_y %.6f m/s (0)\n", xi0, c, h, H, ve, vx_ref, vu);
    CHECK_CLOSE(h, H, 0.1);
    CHECK_CLOSE(ve, vx_ref, 5e-3);
    CHECK_CLOSE(vu, 0.0, 5e-3);
    lv_run_free(r);
    lv_mission_free(m);
}

/* ---- (c) max-q and g-limit ----------------------------------------------------------------- */

static void test_throttle_limits(void)
{
    /* a 10 t vehicle at lift-off thrust/weight 3 through US76 (CD 0.3 on 1 m^2): unlimited,
     * q passes 60 kPa and the axial load 6 g */
#define LIMITS(throttle)                                                                   \
        "mission: {name: limits}\n"                                                       \
        "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}\n"     \
        "parameters: {start_lat_deg: 5.236, start_lon_deg: -52.775, start_h: 0, start_vel: 0}\n" \
        "stages: [{name: s, dry_mass: 3000, propellant_mass: 7000,\n"                      \
        "          engines: [{thrust_vac: 294200, isp_vac: 300, throttle_min: 0.1}]}]\n"    \
        "phases:\n"                                                                        \
        "  - {name: up, model: dof3, stages: [s], stop_time: 300, end: [burnout],\n"       \
        "     aero: {s_ref: 1, CD: 0.3},\n"                                                \
        "     guidance: {law: gravity_turn, rise_time: 5, kick_deg: 3, kick_time: 5, "      \
        "heading_deg: 90},\n"                                                               \
        "     throttle: " throttle "}\n"
    lv_mission *m;
    double lo, hi;
    lv_run *r = run_text("free.yaml", LIMITS("{value: 1}"), &m);
    if (r != NULL) {
        col_range(r, 0, "q_dyn", &lo, &hi);
        double nlo, nhi;
        col_range(r, 0, "n_axial", &nlo, &nhi);
        printf("no limits: max q %.0f Pa, max n_axial %.3f\n", hi, nhi);
        CHECK(hi > 40000.0 && nhi > 5.0);
    }
    lv_run_free(r);
    lv_mission_free(m);

    /* max q 25 kPa: q' <= k (q_max - q) makes q approach the limit without crossing it; what
     * remains is the integration's error (relative tolerance 1e-6) */
    r = run_text("maxq.yaml", LIMITS("{q_max: 25000, q_gain: 0.5}"), &m);
    if (r != NULL) {
        col_range(r, 0, "q_dyn", &lo, &hi);
        double tlo, thi;
        col_range_on(r, 0, "throttle_in", &tlo, &thi);
        printf("q_max 25 kPa: max q %.3f Pa, min throttle %.3f\n", hi, tlo);
        CHECK(hi <= 25000.0 * (1.0 + 1e-5));
        CHECK(hi >= 24500.0); /* the limit binds */
        CHECK(tlo < 0.8 && tlo >= 0.1);
    }
    lv_run_free(r);
    lv_mission_free(m);

    /* g-limit 4: algebraic, the axial load factor (thrust + axial aero force) / (m g0) */
    r = run_text("glim.yaml", LIMITS("{g_limit: 4}"), &m);
    if (r != NULL) {
        col_range(r, 0, "n_axial", &lo, &hi);
        printf("g_limit 4: max n_axial %.12f\n", hi);
        CHECK(hi <= 4.0 + 1e-9);
        CHECK(hi >= 4.0 - 1e-9);
    }
    lv_run_free(r);
    lv_mission_free(m);
#undef LIMITS
}

/* ---- (d) landing burn ------------------------------------------------------------------------ */

/* The landing law's touchdown (thr_landing.c): a constant deceleration a = (v0^2 - vt^2) /
 * (2 dh0) while the time to go on it, (v - vt) / a, is above tau = 0.001 s, i.e. until
 * t_s = (v0 - vt) / a - tau, where v = vt + a tau and dh = tau (2 vt + a tau) / 2; from there
 * dv/dt = -(v - vt) / tau, so v - vt = a tau e^-x after x tau more seconds, over the distance
 * vt tau x + a tau^2 (1 - e^-x): it touches down when that is dh, vt x + a tau (1 - e^-x) =
 * vt + a tau / 2 (Newton's method from x = 1; for vt = 0, x = ln 2). Returns the touchdown
 * time, *v_td the speed. */
static double landing_touchdown(double v0, double vt, double dh0, double *v_td)
{
    const double tau = 0.001, a = (v0 * v0 - vt * vt) / (2.0 * dh0), at = a * tau;
    double x = 1.0;
    for (int i = 0; i < 50; i++)
        x -= (vt * x + at * (1.0 - exp(-x)) - vt - at / 2.0) / (vt + at * exp(-x));
    *v_td = vt + at * exp(-x);
    return (v0 - vt) / a - tau + x * tau;
}

static void test_landing(void)
{
    /* 2 km up, falling at 150 m/s; the law holds a = (v^2 - v_td^2) / (2 dh) constant, so
     * the kinematics predict a = (150^2 - 2^2) / 4000 = 5.624 m/s^2 and touchdown at 2 m/s
     * after (150 - 2) / a = 26.316 s, but for the last millisecond (landing_touchdown: 2.00207 m/s
     * at 26.31579 s); thrust needed m (a + g) = 463 kN of 600 kN: unsaturated */
    const char *yaml =
        "mission: {name: landing}\n" FLAT_WORLD
        "parameters: {start_h: 2000, start_vel: 150, start_fpa_deg: -90}\n"
        "stages: [{name: s, dry_mass: 20000, propellant_mass: 10000,\n"
        "          engines: [{thrust_vac: 600000, isp_vac: 300, throttle_min: 0.2}]}]\n"
        "phases:\n"
        "  - {name: land, model: dof3, stages: [s], stop_time: 100, end: [impact],\n"
        "     integrator: {tolerance: 1.0e-9},\n"
        "     guidance: {law: retrograde}, throttle: {landing: {altitude: 0, speed: 2}}}\n";
    lv_mission *m;
    lv_run *r = run_text("land.yaml", yaml, &m);
    if (r == NULL)
        return lv_mission_free(m);
    double v_td;
    const double t_td = landing_touchdown(150.0, 2.0, 2000.0, &v_td);
    printf("landing: touchdown %.6f m/s (%.6f), at %.6f s (%.6f)\n", final(r, 0, "v_rel"), v_td,
           lv_run_result(r, 0)->t_end, t_td);
    CHECK_CLOSE(final(r, 0, "v_rel"), v_td, 1e-4);
    CHECK_CLOSE(lv_run_result(r, 0)->t_end, t_td, 1e-4);
    CHECK(fabs(v_td - 2.0) < 0.003); /* the last millisecond: 0.1 % of the touchdown speed */
    double lo, hi;
    col_range_on(r, 0, "throttle_in", &lo, &hi);
    CHECK(lo > 0.2 && hi < 1.0); /* never saturated: the prediction holds */
    CHECK_CLOSE(final(r, 0, "alpha_in"), M_PI, 1e-12);
    lv_run_free(r);
    lv_mission_free(m);
}

/* Issue 27 (L2): no saturation event at the touchdown unless the engines truly saturate. The
 * law was 0/0 there, (v^2 - vt^2) / (2 dh) with v -> vt and dh -> 0: the integrator's errors
 * became spikes of the throttle in the last microseconds (a throttle_max event just before the
 * impact, and -1/+1 at it), and its jump to 0 at dh = 0 logged a saturated landing's "back
 * within range" at the impact. Each case, run before the fix: (150 m/s, 0.5 m/s, 900 kN, tol
 * 1e-6) gave throttle_max -1 2 us before the impact; (181, 5, 600 kN, 1e-9) -1 and +1 at
 * it; (220, 2, 600 kN) needs m (a + g) = 30 t (12.1 + 9.8) m/s^2 = 657 kN > 600 kN from the
 * start (no crossing) and gave +1 at the impact. Now: none at all, the saturated one still at
 * throttle_max on its last row (throttle_in > 1); and a landing at speed 0 (before: never
 * reached) touches down as landing_touchdown predicts (x = ln 2: v = a tau / 2), on a
 * non-rotating sphere of the Earth's radius (the flat world's 1e10 m radius leaves a position
 * resolution of 2e-6 m, too coarse for the last millimetres). */
static void test_landing_events(void)
{
    const struct {
        double v0, vt, thrust, tol;
        int saturated;
    } cases[] = {{150.0, 0.5, 900000.0, 1e-6, 0}, {181.0, 5.0, 600000.0, 1e-9, 0},
                 {220.0, 2.0, 600000.0, 1e-6, 1}, {150.0, 0.0, 600000.0, 1e-9, 0}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char yaml[1400];
        snprintf(yaml, sizeof yaml,
                 "mission: {name: landing-events}\n%s"
                 "parameters: {start_h: 2000, start_vel: %g, start_fpa_deg: -90}\n"
                 "stages: [{name: s, dry_mass: 20000, propellant_mass: 10000,\n"
                 "          engines: [{thrust_vac: %g, isp_vac: 300}]}]\n"
                 "phases:\n"
                 "  - {name: land, model: dof3, stages: [s], stop_time: 60, end: [impact],\n"
                 "     integrator: {tolerance: %g},\n"
                 "     guidance: {law: retrograde}, throttle: {landing: {altitude: 0, speed: %g}}}\n",
                 cases[i].vt > 0.0 ? FLAT_WORLD
                                   : "environment:\n  world: planet\n  planet: {name: round, "
                                     "radius: 6.4e6, gm: 4.0168e14, rotation_rate: 0}\n"
                                     "  atmosphere: none\n",
                 cases[i].v0, cases[i].thrust, cases[i].tol, cases[i].vt);
        lv_mission *m;
        lv_run *r = run_text("land_events.yaml", yaml, &m);
        if (r == NULL) {
            lv_mission_free(m);
            continue;
        }
        const lv_phase_result *pr = lv_run_result(r, 0);
        int n_sat = 0;
        for (size_t e = 0; e < pr->report.n_event_log; e++) {
            const lv_event_record *ev = &pr->report.event_log[e];
            if (ev->is_state && ev->index >= 0 && (size_t)ev->index < pr->n_event_names &&
                strncmp(pr->event_names[ev->index], "throttle_m", 10) == 0) {
                n_sat++;
                fprintf(stderr, "  case %zu: %s %+d at %.9f s (impact %.9f s)\n", i,
                        pr->event_names[ev->index], ev->direction, ev->t, pr->t_end);
            }
        }
        CHECK(n_sat == 0);
        CHECK(pr->report.reason == LV_STOP_EVENT); /* the impact */
        const lv_result *res = lv_run_rows(r, 0);
        size_t c_in = 0;
        lv_err err;
        CHECK(res != NULL && lv_result_rows(res) > 1);
        if (res != NULL && lv_result_column(res, "throttle_in", &c_in, &err) == LV_OK) {
            const double last = lv_result_value(res, lv_result_rows(res) - 1, c_in);
            CHECK(cases[i].saturated ? last > 1.0 : last > 0.0 && last < 1.0);
        }
        if (cases[i].vt == 0.0) {
            double v_td;
            const double t_td = landing_touchdown(cases[i].v0, 0.0, 2000.0, &v_td);
            printf("landing at speed 0: touchdown %.6f m/s (%.6f) at %.6f s (%.6f)\n",
                   final(r, 0, "v_rel"), v_td, pr->t_end, t_td);
            CHECK_CLOSE(v_td, 150.0 * 150.0 / 4000.0 * 0.001 / 2.0, 1e-12); /* a tau / 2 */
            CHECK_CLOSE(final(r, 0, "v_rel"), v_td, 1e-4);
            CHECK_CLOSE(pr->t_end, t_td, 1e-4);
        }
        lv_run_free(r);
        lv_mission_free(m);
    }
    remove("land_events.yaml");
}

/* ---- (e) heading law -------------------------------------------------------------------------- */

static void test_heading(void)
{
    /* a 1 t glider at 30 km and 1200 m/s heading north; the target on the equator 5 deg east
     * (bearing ~90 deg). CL = 2 alpha: at alpha 10 deg the lift would be 3.4 g, above n_max 1.5 */
    const char *yaml =
        "mission: {name: glide}\n"
        "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}\n"
        "parameters: {start_lat_deg: 0, start_lon_deg: 0, start_h: 30000, start_vel: 1200,\n"
        "             start_fpa_deg: 0, start_chi_deg: 0}\n"
        "stages: [{name: g, dry_mass: 1000, propellant_mass: 0}]\n"
        "phases:\n"
        "  - name: glide\n"
        "    model: dof3\n"
        "    stages: [g]\n"
        "    stop_time: 200\n"
        "    end: [impact]\n"
        "    aero: {s_ref: 2, table: data/glider_aero.csv}\n"
        "    guidance: {law: heading, target_lat_deg: 0, target_lon_deg: 5, alpha_deg: 10,\n"
        "               bank_max_deg: 60, gain: 2, n_max: 1.5}\n";
    char path[512];
    snprintf(path, sizeof path, "%s/heading.yaml", LV_MISSION_DIR);
    lv_mission *m;
    lv_run *r = run_text(path, yaml, &m);
    remove(path);
    if (r == NULL)
        return lv_mission_free(m);
    const double err_deg = (final(r, 0, "heading") - final(r, 0, "target_bearing")) / DEG;
    printf("heading law: final heading %.4f deg, bearing %.4f deg (error %.2e deg) at %.1f s\n",
           final(r, 0, "heading") / DEG, final(r, 0, "target_bearing") / DEG, err_deg,
           lv_run_result(r, 0)->t_end);
    CHECK(fabs(err_deg) < 0.5);
    double lo, hi;
    col_range(r, 0, "mu_in", &lo, &hi);
    CHECK(lo >= -60.0 * DEG - 1e-12 && hi <= 60.0 * DEG + 1e-12);
    CHECK(hi > 59.9 * DEG); /* it banked to the limit to turn right (east) */
    /* the lift load factor L / (m g0) at most n_max: alpha scaled down smoothly where the lift
     * is proportional to alpha (3.4 g unlimited: 3.4 / (1 + (3.4/1.5)^8)^(1/8) = 1.4993 g) */
    col_range(r, 0, "lift", &lo, &hi);
    printf("heading law: max lift load factor %.9f (n_max 1.5)\n", hi / (1000.0 * G0));
    CHECK(hi / (1000.0 * G0) <= 1.5 + 1e-9 && hi / (1000.0 * G0) > 1.49);
    /* q_max as a run parameter: at the start q = rho V^2 / 2 = 13 kPa (US 1976 at 30 km,
     * rho = 0.01841 kg/m^3); with q_max 10 kPa the limit is released there and the lift
     * load factor exceeds n_max, as the law says it may */
    lv_err err;
    double q0 = NAN;
    CHECK_OK(lv_run_get(r, "glide.guidance.q_max", &q0, &err), &err);
    CHECK(q0 == 0.0);
    CHECK_OK(lv_run_set(r, "glide.guidance.q_max", 10000.0, &err), &err);
    CHECK_OK(lv_run_execute(r, NULL, &err), &err);
    col_range(r, 0, "lift", &lo, &hi);
    printf("heading law, q_max 10 kPa: max lift load factor %.3f\n", hi / (1000.0 * G0));
    CHECK(hi / (1000.0 * G0) > 2.0);
    lv_run_free(r);
    lv_mission_free(m);
}

/* ---- (g) the heading law's limits ---------------------------------------------------------------- */

/* For a lift coefficient proportional to alpha the lift load factor at the limited angle is
 * n a_n / alpha. The soft saturation n / (1 + (n/n_max)^8)^(1/8) is a p-norm-type limiter
 * (p = 8): below n_max for every n, increasing in n, tending to n_max, and within 0.1 % of n
 * below n_max / 2 ((1 + 2^-8)^(1/8) - 1 = 4.9e-4). The release is the cubic smoothstep
 * 3 t^2 - 2 t^3 (0 and 1 with zero slope at t = 0 and 1; 1/2 at t = 1/2). */
static void test_heading_limits(void)
{
    const double a = 0.5, n_max = 2.5, q_max = 4000.0;
    /* no limit: the schedule */
    CHECK(lv_guid_heading_alpha(a, 10.0, 0.0, 0.0, 0.0) == a);
    CHECK(lv_guid_heading_alpha(a, 0.0, n_max, 0.0, 0.0) == a);
    double prev = 0.0;
    int below = 1, rising = 1;
    for (int i = 1; i <= 4000; i++) {
        const double n = 0.01 * i; /* 0.01 .. 40 g */
        const double ne = n * lv_guid_heading_alpha(a, n, n_max, 0.0, 0.0) / a;
        below &= ne < n_max;
        rising &= ne > prev;
        prev = ne;
        if (n <= 0.5 * n_max)
            CHECK(ne >= n * (1.0 - 5e-4) && ne <= n);
    }
    CHECK(below && rising);
    /* at n = n_max: 2^(-1/8) of it; far above: n_max to 1e-12 */
    CHECK_CLOSE(n_max * lv_guid_heading_alpha(a, n_max, n_max, 0.0, 0.0) / a,
                n_max * pow(2.0, -0.125), 1e-15);
    CHECK_CLOSE(1e6 * lv_guid_heading_alpha(a, 1e6, n_max, 0.0, 0.0) / a, n_max, 1e-12);
    /* the release: limited at q <= q_max / 2, the schedule at q >= q_max, the mean at 3/4 */
    const double an = lv_guid_heading_alpha(a, 6.0, n_max, 0.0, 0.0);
    CHECK(an < 0.5 * a);
    CHECK_CLOSE(lv_guid_heading_alpha(a, 6.0, n_max, 0.5 * q_max, q_max), an, 1e-15);
    CHECK_CLOSE(lv_guid_heading_alpha(a, 6.0, n_max, 0.75 * q_max, q_max), 0.5 * (an + a),
                1e-15);
    CHECK_CLOSE(lv_guid_heading_alpha(a, 6.0, n_max, q_max, q_max), a, 1e-15);
    CHECK_CLOSE(lv_guid_heading_alpha(a, 6.0, n_max, 5.0 * q_max, q_max), a, 1e-15);
    /* continuous: no step at either end of the release */
    CHECK_CLOSE(lv_guid_heading_alpha(a, 6.0, n_max, 0.5 * q_max * (1.0 + 1e-9), q_max), an,
                1e-12);
    CHECK_CLOSE(lv_guid_heading_alpha(a, 6.0, n_max, q_max * (1.0 - 1e-9), q_max), a, 1e-12);
}

/* ---- (f) frames ---------------------------------------------------------------------------------- */

/* At a phase's start the inertial frame is the local one, and with the velocity at flight-path
 * angle 50 deg in the vertical plane of heading 90 deg an angle of attack of 10 deg (bank 0)
 * puts body x at pitch 60 deg: the same thrust, hence the same acceleration in the first row. */
static void test_frames(void)
{
    const char *yaml =
        "mission: {name: frames}\n"
        "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}\n"
        "parameters: {start_lat_deg: 30, start_lon_deg: 10, start_h: 5000, start_vel: 200,\n"
        "             start_fpa_deg: 50, start_chi_deg: 90}\n"
        "stages: [{name: s, dry_mass: 1000, propellant_mass: 500,\n"
        "          engines: [{thrust_vac: 30000, isp_vac: 300}]}]\n"
        "phases:\n"
        "  - {name: local, model: dof3, stages: [s], stop_time: 1,\n"
        "     guidance: {law: attitude, frame: local, pitch_deg: 60, heading_deg: 90}}\n"
        "  - {name: inertial, model: dof3, stages: [s], stop_time: 1, alternative: true,\n"
        "     guidance: {law: attitude, frame: inertial, pitch_deg: 60, heading_deg: 90}}\n"
        "  - {name: aero, model: dof3, stages: [s], stop_time: 1, alternative: true,\n"
        "     guidance: {law: attitude, frame: aero, alpha_deg: 10}}\n"
        "  - {name: inputs, model: dof3, stages: [s], stop_time: 1, alternative: true,\n"
        "     inputs: {alpha_deg: 10}}\n";
    lv_mission *m;
    lv_run *r = run_text("frames.yaml", yaml, &m);
    if (r == NULL)
        return lv_mission_free(m);
    static const char *const cols[] = {"der(v_eci_x)", "der(v_eci_y)", "der(v_eci_z)", "theta",
                                       "psi", "alpha_in", "beta_in", "mu_in"};
    double ref[8];
    for (size_t k = 0; k < 4; k++) {
        const lv_result *res = lv_run_rows(r, k);
        for (int j = 0; j < 8; j++) {
            size_t c;
            CHECK(res != NULL && lv_result_column(res, cols[j], &c, NULL) == LV_OK);
            if (res == NULL)
                continue;
            const double v = lv_result_value(res, 0, c);
            if (k == 0)
                ref[j] = v;
            else if (fabs(v - ref[j]) > 1e-9 * (1.0 + fabs(ref[j]))) {
                fprintf(stderr, "  phase %zu %s = %.17g, local frame %.17g\n", k, cols[j], v,
                        ref[j]);
                CHECK(0);
            }
        }
    }
    CHECK_CLOSE(ref[3], 60.0 * DEG, 1e-12);
    CHECK_CLOSE(ref[4], 90.0 * DEG, 1e-12);
    CHECK_CLOSE(ref[5], 10.0 * DEG, 1e-12);
    CHECK_CLOSE(ref[6], 0.0, 1e-12);
    CHECK_CLOSE(ref[7], 0.0, 1e-12);
    lv_run_free(r);
    lv_mission_free(m);
}

/* ---- bad input ------------------------------------------------------------------------------------ */

static void load_fails(const char *phase_extra, const char *want)
{
    char yaml[2048];
    snprintf(yaml, sizeof yaml,
             "mission: {name: t}\n"
             "environment: {world: planet}\n"
             "stages: [{name: s, dry_mass: 10, propellant_mass: 5,\n"
             "          engines: [{thrust_vac: 1000, isp_vac: 300}]}]\n"
             "phases:\n"
             "  - {name: P, model: dof3, stages: [s], stop_time: 10,\n"
             "     %s}\n",
             phase_extra);
    char path[512];
    snprintf(path, sizeof path, "%s/bad_guidance.yaml", LV_MISSION_DIR);
    write_file(path, yaml);
    lv_mission *m = NULL;
    lv_err err;
    lv_status st = lv_mission_load(path, &m, &err);
    remove(path);
    CHECK(st != LV_OK && m == NULL);
    if (st != LV_OK && strstr(err.msg, want) == NULL) {
        fprintf(stderr, "  [%s]\n  got:  %s\n  want: %s\n", phase_extra, err.msg, want);
        CHECK(0);
    }
    lv_mission_free(m);
}

static void test_refused(void)
{
    load_fails("guidance: {law: gravity_trun}",
               "bad_guidance.yaml:7:22: phase 'P', guidance: law: unknown value 'gravity_trun'; "
               "did you mean 'gravity_turn'?");
    load_fails("guidance: {law: gravity_turn, kick_deg: 3, heading_deg: 90}",
               "bad_guidance.yaml:7:16: phase 'P', guidance 'gravity_turn': 'kick_time' is "
               "required");
    load_fails("guidance: {law: gravity_turn, kick_deg: 3, kick_time: 0, heading_deg: 90}",
               "guidance 'gravity_turn': a kick needs kick_time > 0 s");
    load_fails("guidance: {law: linear_tangent, a: 1, heading_deg: 90}",
               "guidance 'linear_tangent': 'b' is required");
    load_fails("guidance: {law: bilinear_tangent, a: 1, b: 0, c: 1, heading_deg: 90}",
               "guidance 'bilinear_tangent': 'd' is required");
    load_fails("guidance: {law: heading, alpha_deg: 5}",
               "bad_guidance.yaml:7:22: phase 'P', guidance 'heading': the heading law banks the "
               "lift vector: the phase needs an aerodynamic dataset (aero:)");
    load_fails("aero: {s_ref: 2, table: data/glider_aero.csv},\n"
               "     guidance: {law: heading, alpha_deg: 5, q_max: 3000}",
               "bad_guidance.yaml:8:52: phase 'P', guidance 'heading': q_max releases the "
               "load-factor limit as q rises: it needs n_max > 0");
    load_fails("aero: {s_ref: 2, table: data/glider_aero.csv},\n"
               "     guidance: {law: heading, alpha_deg: 5, n_max: 2.5, q_max: -1}",
               "bad_guidance.yaml:8:64: phase 'P', guidance 'heading': q_max must be >= 0 Pa, found -1");
    load_fails("guidance: {law: attitude, frame: local, alpha_deg: 3}",
               "'alpha_deg' is an angle of the aero frame; frame local takes pitch, heading, roll");
    load_fails("guidance: {law: attitude, table: data/glider_aero.csv}",
               "bad_guidance.yaml:7:39: phase 'P', guidance 'attitude': table 'glider_aero' must "
               "have one axis named time, altitude, speed or mach");
    load_fails("guidance: {law: attitude, frame: aero, table: data/pitch_program.csv}",
               "table 'pitch_program' has none of the outputs alpha, beta, mu, throttle");
    load_fails("guidance: {law: retrograde, pitch_deg: 3}",
               "guidance 'retrograde': unknown key 'pitch_deg'");
    load_fails("guidance: {law: attitude, pitch_deg: 80}, inputs: {alpha_deg: 2}",
               "inputs: 'alpha_deg' and `guidance:` both steer the vehicle");
    load_fails("throttle: {g_limit: -1}", "g_limit must be > 0");
    load_fails("throttle: {q_gain: 2}", "q_gain applies to q_max");
    load_fails("throttle: {landing: {altitude: 0}, g_limit: 3}",
               "the landing law sets the throttle itself: 'g_limit' does not go with it");
    load_fails("throttle: full", "'off' or a mapping");
    load_fails("throttle: {value: 0.5}, inputs: {throttle: 0.5}",
               "inputs: throttle is also given as throttle.value");
}

/* A pitch program from a table over time in the local frame, and the laws' coefficients as
 * run parameters: a run that changes the kick changes the flight, not the file. */
static void test_table_and_slots(void)
{
    const char *yaml =
        "mission: {name: program}\n"
        "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}\n"
        "parameters: {start_lat_deg: 5.236, start_lon_deg: -52.775, start_h: 0, start_vel: 0}\n"
        "stages: [{name: s, dry_mass: 3000, propellant_mass: 7000,\n"
        "          engines: [{thrust_vac: 294200, isp_vac: 300}]}]\n"
        "phases:\n"
        "  - {name: A, model: dof3, stages: [s], stop_time: 60,\n"
        "     guidance: {law: attitude, table: data/pitch_program.csv}}\n"
        "  - {name: B, model: dof3, stages: [s], stop_time: 60, alternative: true,\n"
        "     guidance: {law: gravity_turn, rise_time: 10, kick_deg: 5, kick_time: 10,\n"
        "                heading_deg: 90}}\n";
    char path[512];
    snprintf(path, sizeof path, "%s/program.yaml", LV_MISSION_DIR);
    lv_mission *m;
    lv_run *r = run_text(path, yaml, &m);
    remove(path);
    if (r == NULL)
        return lv_mission_free(m);
    /* at t = 60 s the table's pitch is 0.9 rad (local frame), the heading 90 deg */
    CHECK_CLOSE(final(r, 0, "theta"), 0.9, 1e-9);
    CHECK_CLOSE(final(r, 0, "psi"), 0.5 * M_PI, 1e-9);
    /* the table's breakpoints are time events */
    CHECK(lv_run_result(r, 0)->report.stats.time_events >= 3);
    /* the kick as a run parameter */
    const double h5 = final(r, 1, "h"), x5 = final(r, 1, "downrange");
    lv_err err;
    CHECK_OK(lv_run_set(r, "B.guidance.kick_deg", 8.0, &err), &err);
    CHECK_OK(lv_run_execute(r, NULL, &err), &err);
    CHECK(lv_run_simulated(r) == 1);
    printf("kick 5 deg: h(60 s) %.1f m, downrange %.1f m; kick 8 deg: %.1f m, %.1f m\n", h5, x5,
           final(r, 1, "h"), final(r, 1, "downrange"));
    CHECK(final(r, 1, "h") < h5 - 10.0 && final(r, 1, "downrange") > x5 + 1000.0);
    lv_run_free(r);
    lv_mission_free(m);
}

/* The separation impulse of a hand-off: dv along the parent's final body x, plus NED parts. */
static void test_separation(void)
{
    const char *yaml =
        "mission: {name: sep}\n"
        "environment: {world: planet, planet: earth, gravity: j2, atmosphere: none}\n"
        "parameters: {start_lat_deg: 20, start_lon_deg: 30, start_h: 150000, start_vel: 3000,\n"
        "             start_fpa_deg: 10, start_chi_deg: 70}\n"
        "stages: [{name: a, dry_mass: 1000, propellant_mass: 0},\n"
        "         {name: b, dry_mass: 500, propellant_mass: 0}]\n"
        "phases:\n"
        "  - {name: P, model: dof3, stages: [a, b], stop_time: 10,\n"
        "     guidance: {law: attitude, pitch_deg: 30, heading_deg: 90}}\n"
        "  - {name: up, model: dof3, stages: [b], from: P, stop_time: 20,\n"
        "     separation: {dv: 5, dv_down: 1}}\n"
        "  - {name: down, model: dof3, stages: [a], from: P, stop_time: 20,\n"
        "     separation: {dv: -2}}\n";
    lv_mission *m;
    lv_run *r = run_text("sep.yaml", yaml, &m);
    if (r == NULL)
        return lv_mission_free(m);
    static const char *const v[3] = {"v_north", "v_east", "v_down"};
    /* body x at pitch 30 deg, heading 90 deg: NED (0, cos 30, -sin 30) */
    const double up[3] = {0.0, 5.0 * cos(30.0 * DEG), -5.0 * sin(30.0 * DEG) + 1.0};
    const double down[3] = {0.0, -2.0 * cos(30.0 * DEG), 2.0 * sin(30.0 * DEG)};
    for (int i = 0; i < 3; i++) {
        size_t c;
        const lv_result *ru = lv_run_rows(r, 1), *rd = lv_run_rows(r, 2);
        CHECK(ru != NULL && rd != NULL && lv_result_column(ru, v[i], &c, NULL) == LV_OK);
        if (ru == NULL || rd == NULL)
            break;
        CHECK_CLOSE(lv_result_value(ru, 0, c) - final(r, 0, v[i]), up[i], 1e-9);
        CHECK_CLOSE(lv_result_value(rd, 0, c) - final(r, 0, v[i]), down[i], 1e-9);
    }
    lv_run_free(r);
    lv_mission_free(m);
    load_fails("separation: {dv: 3}", "bad_guidance.yaml:7:6: phase 'P', separation: a "
               "separation is a hand-off rule: only a phase with `from` has one");
}

/* The target outputs where the geodetic and geocentric verticals differ most (45 deg): the
 * bearing of a point 0.1 deg of longitude east is the great circle's initial bearing
 * atan2(sin dl cos p2, cos p1 sin p2 - sin p1 cos p2 cos dl) = 89.9646 deg (spherical formula;
 * the ellipsoid changes it by less than 1e-3 deg at 8 km), the distance a dl cos(phi) within
 * the ellipsoid's 0.5 %. */
static void test_target_outputs(void)
{
    const char *yaml =
        "mission: {name: bearing}\n"
        "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}\n"
        "parameters: {start_lat_deg: 45, start_lon_deg: 0, start_h: 1000, start_vel: 0}\n"
        "stages: [{name: s, dry_mass: 100, propellant_mass: 0}]\n"
        "phases:\n"
        "  - {name: P, model: dof3, stages: [s], stop_time: 1,\n"
        "     guidance: {law: boostback, target_lat_deg: 45, target_lon_deg: 0.1}}\n";
    lv_mission *m;
    lv_run *r = run_text("bearing.yaml", yaml, &m);
    if (r == NULL)
        return lv_mission_free(m);
    const lv_result *res = lv_run_rows(r, 0);
    size_t cb, cd, cp;
    CHECK(res != NULL && lv_result_column(res, "target_bearing", &cb, NULL) == LV_OK &&
          lv_result_column(res, "target_distance", &cd, NULL) == LV_OK &&
          lv_result_column(res, "psi", &cp, NULL) == LV_OK);
    if (res != NULL) {
        const double p = 45.0 * DEG, dl = 0.1 * DEG;
        const double b_ref = atan2(sin(dl) * cos(p), cos(p) * sin(p) - sin(p) * cos(p) * cos(dl));
        const double b = lv_result_value(res, 0, cb);
        printf("target bearing at 45 deg: %.6f deg (sphere %.6f), distance %.1f m\n", b / DEG,
               b_ref / DEG, lv_result_value(res, 0, cd));
        CHECK_CLOSE(b, b_ref, 1e-3 * DEG);
        CHECK_REL(lv_result_value(res, 0, cd), 6378137.0 * dl * cos(p), 5e-3);
        CHECK_CLOSE(lv_result_value(res, 0, cp), b, 1e-12); /* the boost-back's heading */
    }
    lv_run_free(r);
    lv_mission_free(m);
}

int main(void)
{
    test_gravity_turn("{law: gravity_turn, kick_deg: 0, kick_time: 0, heading_deg: 90}");
    test_gravity_turn("{law: prograde}");
    test_linear_tangent();
    test_throttle_limits();
    test_landing();
    test_landing_events();
    test_heading();
    test_heading_limits();
    test_frames();
    test_refused();
    test_table_and_slots();
    test_separation();
    test_target_outputs();
    return check_report("test_guidance");
}
