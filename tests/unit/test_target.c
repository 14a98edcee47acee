/* test_target.c - targeting and optimisation over a mission's phase tree (issue 13,
 * docs/targeting.md) against known answers:
 *   (a) the launch angle of a drag-free shot that hits a given range over flat ground
 *       (closed form R = v^2 sin(2 gamma) / g);
 *   (b) two variables (speed and angle) for a range and a flight time, from a poor start;
 *   (c) a trial point where the vehicle leaves its model's domain is a rejected step (Newton)
 *       or a penalised point (SLSQP);
 *   (d) a range beyond the maximum: reported as not met, the failing constraint named;
 *   (e) the maximum range (45 deg) by SLSQP, and COBYLA;
 *   (f) the converged mission file: values replaced in place, comments kept, and running it
 *       reproduces the finals; a re-target from it is met at the start;
 *   (g) a branch the constraints do not read is never simulated, and a variable of a child
 *       phase re-simulates only that phase;
 *   (h) the same problem built through the C API;
 *   (i) a converged point where the constrained phase ended by another end than the one its
 *       constraints assume (burnout before the altitude end of a vertical hop) is reported;
 * and bad `targeting:` sections refused with file:line:column.
 *
 * The flat world is a non-rotating sphere of radius R = 1e10 m with GM = g0 R^2 and no
 * atmosphere (as test_guidance.c). Over ranges x <= 1.1 km and heights h <= 260 m its ground
 * drops by x^2 / (2 R) <= 6e-5 m and its gravity changes by 2 h / R <= 5.2e-8, which moves a
 * range by < 1e-4 m: below every tolerance used here (bounds stated at each test). */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "check.h"
#include "mission_kit.h"
#include "lvsim/lv_mission.h"
#include "lvsim/lv_target.h"

#define G0 9.80665
#define DEG (M_PI / 180.0)

static char *read_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return NULL;
    char *s = calloc(1, 1 << 16);
    if (s != NULL)
        s[fread(s, 1, (1 << 16) - 1, f)] = '\0';
    fclose(f);
    return s;
}

/* A ball shot at start_vel and start_fpa_deg to its impact; `targeting` follows. */
static void shot_yaml(char *buf, size_t cap, double v, double fpa_deg, const char *targeting)
{
    snprintf(buf, cap,
             "# a drag-free shot over flat ground\n"
             "mission: {name: shot}\n" FLAT_WORLD
             "parameters: {start_h: 0, start_vel: %.17g, start_fpa_deg: %.17g, "
             "start_chi_deg: 90}  # the gun\n"
             "stages: [{name: ball, dry_mass: 1, propellant_mass: 0}]\n"
             "phases:\n"
             "  - {name: flight, model: dof3, stages: [ball], stop_time: 100, end: [impact],\n"
             "     integrator: {tolerance: 1.0e-10}}\n"
             "%s",
             v, fpa_deg, targeting);
}

/* How many times `what` occurs in s. */
static int count_of(const char *s, const char *what)
{
    int n = 0;
    for (const char *p = strstr(s, what); p != NULL; p = strstr(p + 1, what))
        n++;
    return n;
}

typedef struct counts {
    int iterations, rejected, domain, accepted;
    size_t max_phases;
} counts;

static void count_iter(const lv_target *t, const lv_target_iter *it, void *user)
{
    (void)t;
    counts *c = user;
    c->iterations++;
    c->rejected += strcmp(it->event, "rejected") == 0;
    c->accepted += strcmp(it->event, "accepted") == 0;
    c->domain += it->note != NULL && strstr(it->note, "left the model's domain") != NULL;
    if (it->phases > c->max_phases)
        c->max_phases = it->phases;
}

/* Loads `yaml` (written to path), solves its targeting section: the result, or NULL. */
static const lv_target_result *solve_text(const char *path, const char *yaml, lv_mission **m,
                                          lv_target **t, counts *c)
{
    lv_err err;
    const lv_target_result *res = NULL;
    write_file(path, yaml);
    *m = NULL;
    *t = NULL;
    CHECK_OK(lv_mission_load(path, m, &err), &err);
    if (*m == NULL)
        return NULL;
    CHECK_OK(lv_target_create(*m, t, &err), &err);
    if (*t == NULL)
        return NULL;
    lv_target_settings s;
    lv_target_settings_default(&s);
    s.on_iteration = count_iter;
    s.user = c;
    CHECK_OK(lv_target_solve(*t, &s, &res, &err), &err);
    return res;
}

/* ---- (a) the launch angle for a range ---------------------------------------------------- */

static void test_launch_angle(void)
{
    const double v = 100.0, range = 800.0, tol = 1e-3;
    const double gamma = 0.5 * asin(range * G0 / (v * v)); /* the lower of the two angles */
    char yaml[4096];
    shot_yaml(yaml, sizeof yaml, v, 20.0,
              "targeting:\n"
              "  variables:\n"
              "    - {name: start_fpa_deg, min: 5, max: 44, scale: 1}\n"
              "  constraints:\n"
              "    - {final: flight.downrange, equal: 800, tolerance: 0.001}\n");
    lv_mission *m;
    lv_target *t;
    counts c = {0};
    const lv_target_result *res = solve_text("target_angle.yaml", yaml, &m, &t, &c);
    if (res != NULL) {
        /* dR/dgamma = 2 v^2 cos(2 gamma) / g = 1274 m/rad; the tolerance and the sphere's
         * < 1e-4 m put gamma within (1e-3 + 1e-4) / 1274 rad = 8.6e-7 rad of the closed form */
        printf("launch angle for %.0f m: %.9f deg (closed form %.9f), %zu iterations, %zu runs, "
               "%zu phase simulations\n", range, res->x[0], gamma / DEG, res->iterations,
               res->runs, res->phases);
        CHECK(res->converged);
        CHECK(res->met[0]);
        CHECK_CLOSE(res->finals[0], range, tol);
        CHECK_CLOSE(res->x[0] * DEG, gamma, 8.6e-7);
        CHECK(res->iterations <= 8);
        CHECK(c.rejected == 0);
        CHECK(strcmp(res->method, "newton") == 0);
    }
    lv_target_free(t);
    lv_mission_free(m);
}

/* The same shot with the optimisers and no cost: they minimise the residuals' merit and meet
 * the constraint (a NaN objective once stalled SLSQP in an endless loop). The met constraint
 * puts gamma within tolerance / (dR/dgamma) = 0.1 / 1274 rad of the closed form. */
static void test_launch_angle_optimisers(void)
{
    const double v = 100.0, range = 800.0;
    const double gamma = 0.5 * asin(range * G0 / (v * v));
    static const char *const methods[] = {"slsqp", "cobyla"};
    for (int k = 0; k < 2; k++) {
        char tg[512], yaml[4096];
        snprintf(tg, sizeof tg,
                 "targeting:\n"
                 "  method: %s\n"
                 "  variables:\n"
                 "    - {name: start_fpa_deg, min: 5, max: 44, scale: 1}\n"
                 "  constraints:\n"
                 "    - {final: flight.downrange, equal: 800, tolerance: 0.1}\n",
                 methods[k]);
        shot_yaml(yaml, sizeof yaml, v, 20.0, tg);
        lv_mission *m;
        lv_target *t;
        counts c = {0};
        const lv_target_result *res = solve_text("target_angle_opt.yaml", yaml, &m, &t, &c);
        if (res != NULL) {
            printf("launch angle, %s without a cost: %.6f deg (closed form %.6f), %zu runs\n",
                   methods[k], res->x[0], gamma / DEG, res->runs);
            CHECK(res->converged && res->met[0]);
            CHECK_CLOSE(res->x[0] * DEG, gamma, 0.11 / 1274.0);
            CHECK(strcmp(res->method, methods[k]) == 0);
            CHECK(res->runs < 200);
        }
        lv_target_free(t);
        lv_mission_free(m);
    }
}

/* ---- (b) two variables from a poor start ------------------------------------------------- */

static void test_two_variables(void)
{
    /* range X and flight time T: v cos(gamma) = X / T, v sin(gamma) = g T / 2 */
    const double X = 1000.0, T = 10.0, vx = X / T, vy = 0.5 * G0 * T;
    char yaml[4096];
    shot_yaml(yaml, sizeof yaml, 30.0, 70.0,
              "targeting:\n"
              "  variables:\n"
              "    - {name: start_vel, min: 1, max: 1000, scale: 10}\n"
              "    - {name: start_fpa_deg, min: 1, max: 89, scale: 5}\n"
              "  constraints:\n"
              "    - {final: flight.downrange, equal: 1000, tolerance: 0.001}\n"
              "    - {final: flight.time, equal: 10, tolerance: 1.0e-5}\n");
    lv_mission *m;
    lv_target *t;
    counts c = {0};
    const lv_target_result *res = solve_text("target_two.yaml", yaml, &m, &t, &c);
    if (res != NULL) {
        /* the start (30 m/s at 70 deg) flies 59 m in 5.8 s: residuals of 1e6 tolerances.
         * Converged within the tolerances: v to (0.001 m / (dX/dv = 2 X / v = 18 s)) plus the
         * time's 1e-5 s x (dv/dT ~ 5 m/s^2), gamma likewise: 1e-4 m/s and 1e-5 rad */
        const double v = hypot(vx, vy), gamma = atan2(vy, vx);
        printf("two variables from (30 m/s, 70 deg): %.6f m/s (%.6f), %.6f deg (%.6f) in %zu "
               "iterations\n", res->x[0], v, res->x[1], gamma / DEG, res->iterations);
        CHECK(res->converged);
        CHECK_CLOSE(res->x[0], v, 1e-4);
        CHECK_CLOSE(res->x[1] * DEG, gamma, 1e-5);
        CHECK(res->iterations <= 25);
    }
    lv_target_free(t);
    lv_mission_free(m);
}

/* ---- (c) a failing trial point is a rejected step ------------------------------------------- */

static void test_rejected_step(void)
{
    /* h(70 s) = v sin(gamma) T - g T^2 / 2 = 0 at v = 400 m/s: sin(gamma) = g T / (2 v). From
     * 85 deg the Newton step lands near -6 deg, where the ball is 20 km under the ground at
     * 60 s: the phase fails (the model's domain), the step is rejected and a shorter one taken.
     * Over the 14 km flown the sphere's ground drops 0.01 m and its gravity weakens by up to
     * 1.4e-6 (h <= 7 km): h(70 s) moves by < 0.05 m, gamma by < 0.05 / 251 m/deg = 2e-4 deg */
    const double v = 400.0, T = 70.0;
    char yaml[4096];
    snprintf(yaml, sizeof yaml,
             "mission: {name: shot-fail}\n" FLAT_WORLD
             "parameters: {start_h: 0, start_vel: %.17g, start_fpa_deg: 85, start_chi_deg: 90}\n"
             "stages: [{name: ball, dry_mass: 1, propellant_mass: 0}]\n"
             "phases:\n"
             "  - {name: flight, model: dof3, stages: [ball], stop_time: %.17g,\n"
             "     integrator: {tolerance: 1.0e-10}}\n"
             "targeting:\n"
             "  variables: [{name: start_fpa_deg, min: -10, max: 89, scale: 30}]\n"
             "  constraints: [{final: flight.h, equal: 0, tolerance: 0.01}]\n",
             v, T);
    lv_mission *m;
    lv_target *t;
    counts c = {0};
    const lv_target_result *res = solve_text("target_fail.yaml", yaml, &m, &t, &c);
    if (res != NULL) {
        const double gamma = asin(G0 * T / (2.0 * v));
        printf("rejected steps: %d (%d outside the domain), converged at %.6f deg (%.6f)\n",
               c.rejected, c.domain, res->x[0], gamma / DEG);
        CHECK(res->converged);
        CHECK(c.domain >= 1);
        CHECK_CLOSE(res->x[0], gamma / DEG, 2e-4);
    }
    lv_target_free(t);
    lv_mission_free(m);
}

/* The same ball, the horizontal range at 70 s maximised by SLSQP with the ball above the
 * ground (h >= 0): the optimum is the h = 0 boundary, gamma = asin(g T / 2 v) again. SLSQP's
 * first step lands 20 km under the ground: the penalty makes its line search step back. */
static void test_rejected_point(void)
{
    const double v = 400.0, T = 70.0;
    char yaml[4096];
    snprintf(yaml, sizeof yaml,
             "mission: {name: shot-fail-opt}\n" FLAT_WORLD
             "parameters: {start_h: 0, start_vel: %.17g, start_fpa_deg: 85, start_chi_deg: 90}\n"
             "stages: [{name: ball, dry_mass: 1, propellant_mass: 0}]\n"
             "phases:\n"
             "  - {name: flight, model: dof3, stages: [ball], stop_time: %.17g,\n"
             "     integrator: {tolerance: 1.0e-10}}\n"
             "targeting:\n"
             "  method: slsqp\n"
             "  variables: [{name: start_fpa_deg, min: -10, max: 89, scale: 30}]\n"
             "  constraints: [{final: flight.h, min: 0, tolerance: 0.01}]\n"
             "  cost: {maximize: flight.downrange}\n",
             v, T);
    lv_mission *m;
    lv_target *t;
    counts c = {0};
    const lv_target_result *res = solve_text("target_fail_opt.yaml", yaml, &m, &t, &c);
    if (res != NULL) {
        const double gamma = asin(G0 * T / (2.0 * v));
        printf("SLSQP through a failing point: %d outside the domain, %.6f deg (%.6f), range "
               "%.3f m\n", c.domain, res->x[0], gamma / DEG, res->cost);
        CHECK(res->converged);
        CHECK(c.domain >= 1);
        CHECK_CLOSE(res->x[0], gamma / DEG, 2e-4); /* the sphere's 0.05 m: test_rejected_step */
    }
    lv_target_free(t);
    lv_mission_free(m);
}

/* ---- (d) no solution ------------------------------------------------------------------------ */

static void test_no_solution(void)
{
    /* 100 m/s carries at most v^2 / g = 1019.7 m (at 45 deg): 2000 m cannot be met. The best
     * point is the maximum range, where the residual's gradient vanishes */
    char yaml[4096];
    shot_yaml(yaml, sizeof yaml, 100.0, 20.0,
              "targeting:\n"
              "  variables: [{name: start_fpa_deg, min: 5, max: 60, scale: 1}]\n"
              "  constraints: [{final: flight.downrange, equal: 2000, tolerance: 1}]\n");
    lv_mission *m;
    lv_target *t;
    counts c = {0};
    const lv_target_result *res = solve_text("target_nosol.yaml", yaml, &m, &t, &c);
    if (res != NULL) {
        printf("no solution: %s; best %.6f deg, %.6f m (max %.6f m)\n", res->reason, res->x[0],
               res->finals[0], 1e4 / G0);
        CHECK(!res->converged);
        CHECK(!res->met[0]);
        CHECK_CLOSE(res->residual[0], (1e4 / G0 - 2000.0), 1e-3);
        CHECK_CLOSE(res->x[0], 45.0, 0.01);
        CHECK(strlen(res->reason) > 0);
        CHECK(res->iterations <= 50);
    }
    lv_target_free(t);
    lv_mission_free(m);
}

/* ---- (e) the maximum range --------------------------------------------------------------------- */

static void test_max_range(void)
{
    /* R(gamma) = v^2 sin(2 gamma) / g is flat at 45 deg: R(45 + e) = R_max - 2 R_max e^2
     * (e in rad). The optimiser stops when the cost changes by < ftol of its scale (1e-7 x
     * 655 m): e < sqrt(6.6e-5 / 2040) rad = 0.01 deg */
    static const char *const methods[] = {"slsqp", "cobyla"};
    for (int k = 0; k < 2; k++) {
        char yaml[4096], tg[512];
        snprintf(tg, sizeof tg,
                 "targeting:\n"
                 "  method: %s\n"
                 "  variables: [{name: start_fpa_deg, min: 10, max: 80, scale: 10}]\n"
                 "  cost: {maximize: flight.downrange}\n",
                 methods[k]);
        shot_yaml(yaml, sizeof yaml, 100.0, 20.0, tg);
        lv_mission *m;
        lv_target *t;
        counts c = {0};
        const lv_target_result *res = solve_text("target_max.yaml", yaml, &m, &t, &c);
        if (res != NULL) {
            printf("maximum range by %s: %.6f deg, %.6f m (max %.6f m) in %zu iterations, %zu "
                   "runs\n", methods[k], res->x[0], res->cost, 1e4 / G0, res->iterations,
                   res->runs);
            CHECK(res->converged);
            CHECK_CLOSE(res->x[0], 45.0, 0.01);
            CHECK_CLOSE(res->cost, 1e4 / G0, 1e-3);
            CHECK(strcmp(res->method, methods[k]) == 0);
        }
        lv_target_free(t);
        lv_mission_free(m);
    }
}

/* ---- (f) the converged mission file ---------------------------------------------------------- */

static void test_round_trip(void)
{
    char yaml[4096];
    shot_yaml(yaml, sizeof yaml, 100.0, 20.0,
              "targeting:   # hit 800 m\n"
              "  variables:\n"
              "    - {name: start_fpa_deg, min: 5, max: 44, start: 30, scale: 1}  # low shot\n"
              "  constraints:\n"
              "    - {final: flight.downrange, equal: 800, tolerance: 0.001}\n");
    lv_mission *m;
    lv_target *t;
    counts c = {0};
    lv_err err;
    const lv_target_result *res = solve_text("target_rt.yaml", yaml, &m, &t, &c);
    if (res != NULL && res->converged) {
        double worst = NAN;
        CHECK_OK(lv_target_write(t, res->x, "target_rt_conv.yaml", &worst, &err), &err);
        CHECK(worst <= 1e-3);
        char *out = read_file("target_rt_conv.yaml");
        CHECK(out != NULL);
        if (out != NULL) {
            /* only the two values changed: the parameter and the targeting start */
            char num[64], line[256];
            snprintf(num, sizeof num, "%.17g", res->x[0]);
            CHECK(strtod(num, NULL) == res->x[0]);
            CHECK(strstr(out, "# a drag-free shot over flat ground\n") != NULL);
            CHECK(strstr(out, "start_chi_deg: 90}  # the gun\n") != NULL);
            CHECK(strstr(out, "targeting:   # hit 800 m\n") != NULL);
            const char *p = strstr(out, "start_fpa_deg: ");
            CHECK(p != NULL && strtod(p + 15, NULL) == res->x[0]);
            p = strstr(out, "min: 5, max: 44, start: ");
            CHECK(p != NULL && strtod(p + 24, NULL) == res->x[0]);
            snprintf(line, sizeof line, ", scale: 1}  # low shot\n");
            CHECK(strstr(out, line) != NULL);
            /* a header first: where it comes from, how the constrained phase ended (its one
             * end, impact, at the flight time 2 v sin(gamma) / g = 9.018 s of the closed
             * form); the file after it */
            CHECK(strncmp(out, "# lvsim target: written from target_rt.yaml ", 44) == 0);
            p = strstr(out, "# lvsim target: ended as the constraints assume: flight by impact "
                            "at t = ");
            CHECK(p != NULL && fabs(strtod(p + 72, NULL) - 2.0 * 100.0 * sin(res->x[0] * DEG) /
                                                               G0) < 1e-6);
            const char *body = strstr(out, "# a drag-free shot over flat ground\n");
            CHECK(body != NULL && strlen(body) - strlen(yaml) < 40);
            CHECK(count_of(out, "# lvsim target:") == 2);
            free(out);
        }
        /* the converged file, run on its own, reproduces the final; re-targeted, it is met at
         * the start without a single step */
        lv_mission *m2 = NULL;
        lv_target *t2 = NULL;
        counts c2 = {0};
        const lv_target_result *r2 = NULL;
        CHECK_OK(lv_mission_load("target_rt_conv.yaml", &m2, &err), &err);
        if (m2 != NULL) {
            lv_run *run = NULL;
            CHECK_OK(lv_run_create(m2, &run, &err), &err);
            CHECK_OK(lv_run_execute(run, NULL, &err), &err);
            double range = NAN;
            CHECK_OK(lv_run_final(run, 0, "downrange", &range, &err), &err);
            CHECK(range == res->finals[0]);
            lv_run_free(run);
            CHECK_OK(lv_target_create(m2, &t2, &err), &err);
            lv_target_settings s;
            lv_target_settings_default(&s);
            s.on_iteration = count_iter;
            s.user = &c2;
            if (t2 != NULL)
                CHECK_OK(lv_target_solve(t2, &s, &r2, &err), &err);
            CHECK(r2 != NULL && r2->converged && r2->iterations == 0 && r2->x[0] == res->x[0]);
            /* written again: its header replaces the one it had */
            if (r2 != NULL && r2->converged)
                CHECK_OK(lv_target_write(t2, r2->x, "target_rt_conv2.yaml", NULL, &err), &err);
            char *out2 = read_file("target_rt_conv2.yaml");
            CHECK(out2 != NULL && count_of(out2, "# lvsim target:") == 2 &&
                  strstr(out2, "written from target_rt_conv.yaml ") != NULL);
            free(out2);
        }
        lv_target_free(t2);
        lv_mission_free(m2);
    } else {
        CHECK(0);
    }
    lv_target_free(t);
    lv_mission_free(m);
}

/* Written into another folder, the files the mission reads by relative paths keep working:
 * a rocket with a thrust table in data/, targeted for its burnout altitude (its dry mass is
 * the variable), its converged mission written one folder over. */
static void test_moved_file(void)
{
    mkdir("target_src", 0777);
    mkdir("target_src/data", 0777);
    mkdir("target_out", 0777);
    write_file("target_src/data/thrust.csv", "t [s], thrust [N], mdot [kg/s]\n"
                                             "0, 30000, 10\n100, 30000, 10\n");
    write_file("target_src/m.yaml",
               "mission: {name: moved}\n" FLAT_WORLD
               "parameters: {start_h: 0, start_vel: 0}\n"
               "stages: [{name: s, dry_mass: 500, propellant_mass: 500,\n"
               "          engines: [{table: data/thrust.csv}]}]\n"
               "phases:\n"
               "  - {name: up, model: dof3, stages: [s], stop_time: 100, end: [burnout],\n"
               "     guidance: {law: attitude, pitch_deg: 90},\n"
               "     integrator: {tolerance: 1.0e-9}}\n"
               "targeting:\n"
               "  variables: [{name: stages.s.dry_mass, min: 100, max: 900, scale: 10}]\n"
               "  constraints: [{final: up.h, equal: 20000, tolerance: 0.1}]\n");
    lv_mission *m = NULL;
    lv_err err;
    /* `stages.s.dry_mass` is no parameter: the check says so (the parameter is s.dry_mass) */
    CHECK_FAILS(lv_mission_load("target_src/m.yaml", &m, &err), &err, LV_ERR_INPUT,
                "did you mean 's.dry_mass'");
    char *text = read_file("target_src/m.yaml");
    if (text != NULL) {
        char *p = strstr(text, "stages.s.dry_mass");
        if (p != NULL)
            memmove(p, p + 7, strlen(p + 7) + 1);
        write_file("target_src/m.yaml", text);
        free(text);
    }
    lv_target *t = NULL;
    const lv_target_result *res = NULL;
    CHECK_OK(lv_mission_load("target_src/m.yaml", &m, &err), &err);
    if (m != NULL)
        CHECK_OK(lv_target_create(m, &t, &err), &err);
    if (t != NULL)
        CHECK_OK(lv_target_solve(t, NULL, &res, &err), &err);
    if (res != NULL && res->converged) {
        double worst = NAN;
        CHECK_OK(lv_target_write(t, res->x, "target_out/conv.yaml", &worst, &err), &err);
        char *out = read_file("target_out/conv.yaml");
        CHECK(out != NULL && strstr(out, "{table: ../target_src/data/thrust.csv}") != NULL);
        free(out);
        printf("moved converged file: dry mass %.6f kg, written with its table's path relative "
               "to its folder (worst difference %.2g tol)\n", res->x[0], worst);
    } else {
        CHECK(0);
    }
    lv_target_free(t);
    lv_mission_free(m);
}

/* ---- (g) the phase tree: only what a variable reaches ----------------------------------------- */

static void test_branches(void)
{
    /* P1 climbs for 2 s; P2 (from P1) falls to the impact height P2.end.impact; P3 (from P1) is
     * a branch no constraint reads. Target: P2 ends at t = 9 s. The impact height reaches P2
     * only: every run after the start simulates P2 alone, P3 never */
    char yaml[4096];
    snprintf(yaml, sizeof yaml,
             "mission: {name: branches}\n" FLAT_WORLD
             "parameters: {start_h: 0, start_vel: 50, start_fpa_deg: 60, start_chi_deg: 90}\n"
             "stages: [{name: a, dry_mass: 1, propellant_mass: 0},\n"
             "         {name: b, dry_mass: 1, propellant_mass: 0}]\n"
             "phases:\n"
             "  - {name: P1, model: dof3, stages: [a, b], stop_time: 2,\n"
             "     integrator: {tolerance: 1.0e-10}}\n"
             "  - {name: P2, model: dof3, stages: [a], from: P1, stop_time: 100,\n"
             "     end: [{impact: 10}], integrator: {tolerance: 1.0e-10}}\n"
             "  - {name: P3, model: dof3, stages: [b], from: P1, stop_time: 100,\n"
             "     end: [impact]}\n"
             "targeting:\n"
             "  variables: [{name: P2.end.impact, min: -50, max: 100, scale: 10}]\n"
             "  constraints: [{final: P2.time, equal: 9, tolerance: 1.0e-6}]\n");
    lv_mission *m;
    lv_target *t;
    counts c = {0};
    const lv_target_result *res = solve_text("target_branch.yaml", yaml, &m, &t, &c);
    if (res != NULL) {
        /* h(9 s) from the start: vz = 50 sin 60 deg = 43.30 m/s */
        const double vz = 50.0 * sin(60.0 * DEG), h9 = vz * 9.0 - 0.5 * G0 * 81.0;
        printf("branches: impact height %.6f m (%.6f), %zu runs, %zu phase simulations\n",
               res->x[0], h9, res->runs, res->phases);
        CHECK(res->converged);
        /* the position is integrated in ECI, |r| = 1e10 m: a relative tolerance of 1e-10
         * allows ~1 m per step, and through the hand-off at 2 s the impact comes ~1e-5 s
         * (5e-4 m) earlier than the closed form */
        CHECK_CLOSE(res->x[0], h9, 2e-3);
        CHECK(res->phases == 2 + (res->runs - 1) - 1); /* start: P1, P2; then P2 per run but
                                                          the last (unchanged) run: none */
        lv_run *run = lv_target_run(t);
        size_t k3;
        lv_err err;
        CHECK_OK(lv_mission_phase_find(m, "P3", &k3, &err), &err);
        CHECK(lv_run_result(run, k3)->state == LV_PHASE_PENDING);
        /* a full execute now runs the branch left out */
        CHECK_OK(lv_run_execute(run, NULL, &err), &err);
        CHECK(lv_run_simulated(run) == 1);
        CHECK(lv_run_result(run, k3)->state == LV_PHASE_DONE);
    }
    lv_target_free(t);
    lv_mission_free(m);
}

/* ---- (h) the C API ------------------------------------------------------------------------------- */

static void test_api(void)
{
    char yaml[4096];
    shot_yaml(yaml, sizeof yaml, 100.0, 20.0, "");
    write_file("target_api.yaml", yaml);
    lv_mission *m = NULL;
    lv_target *t = NULL;
    lv_err err;
    CHECK_OK(lv_mission_load("target_api.yaml", &m, &err), &err);
    if (m == NULL)
        return;
    CHECK_FAILS(lv_target_create(m, &t, &err), &err, LV_ERR_INPUT, "no `targeting:` section");
    CHECK_OK(lv_target_create_empty(m, &t, &err), &err);
    CHECK_FAILS(lv_target_add_var(t, "start_fpa_dg", 5, 44, NAN, 1, NAN, &err), &err,
                LV_ERR_INPUT, "did you mean 'start_fpa'");
    CHECK_FAILS(lv_target_add_var(t, "start_vel", -5, 44, NAN, 1, NAN, &err), &err, LV_ERR_INPUT,
                "min -5 m/s is outside the parameter's allowed values (>= 0)");
    CHECK_OK(lv_target_add_var(t, "start_fpa_deg", 5, 44, NAN, 1, NAN, &err), &err);
    CHECK_FAILS(lv_target_add_var(t, "start_fpa", 0.1, 0.7, NAN, 0.1, NAN, &err), &err,
                LV_ERR_INPUT, "already the variable 'start_fpa_deg'");
    CHECK_FAILS(lv_target_add_con(t, "flight.downrang", LV_CON_EQUAL, 800, 1e-3, &err), &err,
                LV_ERR_INPUT, "did you mean 'downrange'");
    CHECK_FAILS(lv_target_add_con(t, "flight.h_deg", LV_CON_EQUAL, 800, 1e-3, &err), &err,
                LV_ERR_INPUT, "'h' is not an angle");
    CHECK_OK(lv_target_add_con(t, "flight.downrange", LV_CON_EQUAL, 800, 1e-3, &err), &err);
    CHECK_OK(lv_target_add_con(t, "flight.fpa_deg", LV_CON_MIN, -60, 0.1, &err), &err);
    const lv_target_result *res = NULL;
    CHECK_OK(lv_target_solve(t, NULL, &res, &err), &err);
    if (res != NULL) {
        CHECK(res->converged && res->met[1]);
        CHECK_CLOSE(res->x[0] * DEG, 0.5 * asin(800.0 * G0 / 1e4), 8.6e-7);
        CHECK_CLOSE(res->finals[1], -res->x[0], 1e-4); /* lands at the launch angle */
    }
    lv_target_var_info vi;
    lv_target_var_info_get(t, 0, &vi);
    CHECK(strcmp(vi.unit, "deg") == 0 && vi.deg == 1 && vi.start == 20.0);
    lv_target_con_info ci;
    lv_target_con_info_get(t, 1, &ci);
    CHECK(strcmp(ci.unit, "deg") == 0 && ci.kind == LV_CON_MIN);
    lv_target_free(t);
    lv_mission_free(m);
}

/* ---- bad input ----------------------------------------------------------------------------------- */

static void load_fails(const char *targeting, const char *want)
{
    char yaml[4096];
    shot_yaml(yaml, sizeof yaml, 100.0, 20.0, targeting);
    write_file("target_bad.yaml", yaml);
    lv_mission *m = NULL;
    lv_err err;
    lv_status st = lv_mission_load("target_bad.yaml", &m, &err);
    CHECK(st == LV_ERR_INPUT && m == NULL);
    if (st != LV_OK && strstr(err.msg, want) == NULL) {
        fprintf(stderr, "  [%s]\n  got:  %s\n  want: %s\n", targeting, err.msg, want);
        CHECK(0);
    }
    lv_mission_free(m);
}

static void test_refused(void)
{
    /* the section starts at line 12, its first variable at line 14 */
#define V(x) "targeting:\n  variables:\n    - " x "\n"
#define C(x) "  constraints:\n    - " x "\n"
    const char *ok_var = "{name: start_fpa_deg, min: 5, max: 44}";
    const char *ok_con = "{final: flight.downrange, equal: 800, tolerance: 0.01}";
    char buf[1024];
    load_fails("targeting: {variables: []}\n", "target_bad.yaml:12:24: targeting: 'variables' "
               "needs at least one variable");
    snprintf(buf, sizeof buf, V("%s"), ok_var);
    load_fails(buf, "target_bad.yaml:13:3: targeting: nothing to achieve");
    snprintf(buf, sizeof buf, V("%s") C("%s") "  methd: newton\n", ok_var, ok_con);
    load_fails(buf, "target_bad.yaml:17:3: targeting: unknown key 'methd'; did you mean "
                    "'method'?");
    snprintf(buf, sizeof buf, V("{name: start_fpa_dg, min: 5, max: 44}") C("%s"), ok_con);
    load_fails(buf, "target_bad.yaml:14:14: targeting: variable 'start_fpa_dg': mission 'shot' "
                    "has no parameter 'start_fpa_dg'; did you mean 'start_fpa'");
    snprintf(buf, sizeof buf, V("{name: start_fpa_deg, min: 5}") C("%s"), ok_con);
    load_fails(buf, "target_bad.yaml:14:7: targeting: variable 'start_fpa_deg': missing required "
                    "key 'max'");
    snprintf(buf, sizeof buf, V("{name: start_fpa_deg, min: 50, max: 44}") C("%s"), ok_con);
    load_fails(buf, "targeting: variable 'start_fpa_deg': max 44 must be greater than min 50");
    snprintf(buf, sizeof buf, V("{name: start_fpa_deg, min: 30, max: 44}") C("%s"), ok_con);
    load_fails(buf, "target_bad.yaml:14:14: targeting: variable 'start_fpa_deg': the start (the "
                    "mission file's value) 20 deg is outside [30, 44]: give a start");
    snprintf(buf, sizeof buf, V("{name: start_fpa_deg, min: 5, max: 44, start: 50}") C("%s"),
             ok_con);
    load_fails(buf, "target_bad.yaml:14:53: targeting: variable 'start_fpa_deg': the start 50 "
                    "deg is outside [5, 44]");
    snprintf(buf, sizeof buf, V("{name: start_vel, min: -1, max: 44}") C("%s"), ok_con);
    load_fails(buf, "min -1 m/s is outside the parameter's allowed values (>= 0)");
    snprintf(buf, sizeof buf, V("{name: flight.integrator.fixed_step, min: 0, max: 1}") C("%s"),
             ok_con);
    load_fails(buf, "target_bad.yaml:14:14: targeting: variable 'flight.integrator.fixed_step': "
                    "the mission file does not write this parameter");
    snprintf(buf, sizeof buf, V("%s") "    - {name: start_fpa, min: 0.1, max: 0.7}\n" C("%s"),
             ok_var, ok_con);
    load_fails(buf, "target_bad.yaml:15:14: targeting: variable 'start_fpa': the parameter is "
                    "already a variable (line 14)");
    snprintf(buf, sizeof buf, V("{name: start_fpa_deg, min: 5, max: 44, scale: 0}") C("%s"),
             ok_con);
    load_fails(buf, "scale 0 is outside [0.0039, 39], 0.0001 to 1 times max - min");
    snprintf(buf, sizeof buf, V("%s") C("{final: flihgt.downrange, equal: 800, tolerance: 1}"),
             ok_var);
    load_fails(buf, "target_bad.yaml:16:15: targeting: constraint: 'flihgt.downrange': mission "
                    "'shot' has no phase 'flihgt'; did you mean 'flight'?");
    snprintf(buf, sizeof buf, V("%s") C("{final: flight.range, equal: 800, tolerance: 1}"),
             ok_var);
    load_fails(buf, "target_bad.yaml:16:15: targeting: constraint: 'flight.range': phase "
                    "'flight' (model dof3) has no final value 'range'");
    snprintf(buf, sizeof buf, V("%s") C("{final: downrange, equal: 800, tolerance: 1}"), ok_var);
    load_fails(buf, "'downrange': a final value is PHASE.NAME");
    snprintf(buf, sizeof buf, V("%s") C("{final: flight.m_deg, equal: 800, tolerance: 1}"),
             ok_var);
    load_fails(buf, "'m' is not an angle (its unit is 'kg')");
    snprintf(buf, sizeof buf, V("%s") C("{final: flight.downrange, equal: 800}"), ok_var);
    load_fails(buf, "target_bad.yaml:16:7: targeting: constraint on 'flight.downrange': missing "
                    "required key 'tolerance'");
    snprintf(buf, sizeof buf, V("%s") C("{final: flight.downrange, equal: 800, tolerance: 0}"),
             ok_var);
    load_fails(buf, "tolerance must be > 0, found 0");
    snprintf(buf, sizeof buf, V("%s") C("{final: flight.h, min: 0, max: 800, tolerance: 1}"),
             ok_var);
    load_fails(buf, "target_bad.yaml:16:33: targeting: constraint on 'flight.h': give one of "
                    "equal, min and max");
    snprintf(buf, sizeof buf, V("%s") C("%s") "  cost: {maximize: flight.m, minimize: flight.m}\n",
             ok_var, ok_con);
    load_fails(buf, "targeting: cost: give one of maximize and minimize");
    snprintf(buf, sizeof buf, V("%s") C("%s") "  cost: {maximize: flight.mass}\n", ok_var, ok_con);
    load_fails(buf, "target_bad.yaml:17:20: targeting: cost: 'flight.mass': phase 'flight' "
                    "(model dof3) has no final value 'mass'");
    snprintf(buf, sizeof buf, V("%s") C("%s") "  method: newton\n  cost: {maximize: flight.m}\n",
             ok_var, ok_con);
    load_fails(buf, "target_bad.yaml:17:11: targeting: method newton meets constraints and "
                    "optimises no cost");
    snprintf(buf, sizeof buf, V("%s") C("%s") "  method: simplex\n", ok_var, ok_con);
    load_fails(buf, "targeting: method: unknown value 'simplex'");
    snprintf(buf, sizeof buf, V("%s") C("%s") "  max_iterations: 2.5\n", ok_var, ok_con);
    load_fails(buf, "max_iterations: an integer from 1 to 100000 expected");
    load_fails("targeting:\n", "target_bad.yaml:12:11: targeting: the section is empty");
    snprintf(buf, sizeof buf, V("{name: start_fpa_deg, min: 5, max: 44, step: 20}") C("%s"),
             ok_con);
    load_fails(buf, "step 20 must be less than half the range max - min = 39");
    snprintf(buf, sizeof buf, V("%s") C("{final: flight.downrange, equal: 1e308, tolerance: "
                                        "1e-300}"), ok_var);
    load_fails(buf, "tolerance 1e-300 is too small for the value 1e+308");
    snprintf(buf, sizeof buf, V("%s") C("{final: flight.downrange, equal: 800, tolerance: "
                                        "1e-13}"), ok_var);
    load_fails(buf, "tolerance 1e-13 is too small for the value 800");
    snprintf(buf, sizeof buf, V("%s") C("%s") "    - %s\n", ok_var, ok_con, ok_con);
    load_fails(buf, "target_bad.yaml:17:15: targeting: constraint on 'flight.downrange': the "
                    "final is already constrained the same way (line 16)");
    /* the end a constraint assumes: one of the phase's ends (impact), stop_time or any */
    snprintf(buf, sizeof buf, V("%s") C("{final: flight.downrange, equal: 800, tolerance: 1, "
                                        "end: impakt}"), ok_var);
    load_fails(buf, "target_bad.yaml:16:64: targeting: constraint on 'flight.downrange': end "
                    "'impakt': phase 'flight' has no such end; did you mean 'impact'? (its ends: "
                    "impact, stop_time; or any)");
    snprintf(buf, sizeof buf, V("%s") C("{final: flight.downrange, equal: 800, tolerance: 1, "
                                        "end: impact}") "    - {final: flight.h, max: 9, "
                                        "tolerance: 1, end: stop_time}\n", ok_var);
    load_fails(buf, "target_bad.yaml:17:52: targeting: constraint on 'flight.h': end "
                    "'stop_time', but line 16 assumes phase 'flight' ends by 'impact': a phase "
                    "ends one way");
    snprintf(buf, sizeof buf, V("%s") C("%s") "  cost: {maximize: flight.m, end: burnout}\n",
             ok_var, ok_con);
    load_fails(buf, "target_bad.yaml:17:35: targeting: cost on 'flight.m': end 'burnout': phase "
                    "'flight' has no such end");
#undef V
#undef C
}

/* ---- (i) converged onto another end -------------------------------------------------------- */

/* A rocket rising vertically over the flat ground of flat6 (uniform g = 9.81 m/s^2, no air)
 * whose burn is meant to end at 2 km (`end: [{altitude: 2000}, burnout]`), its propellant the
 * variable, its final time the constraint. In vacuum under uniform gravity the rocket equation
 * integrates in closed form (Tsiolkovsky; e.g. Sutton & Biblarz, Rocket Propulsion Elements,
 * 9th ed., sec. 4.3): with c = Isp g0, mdot = F / c, m(t) = m0 - mdot t,
 *     h(t) = c [t - (m / mdot) ln(m0 / m)] - g t^2 / 2.
 * Burnout (t_b = m_p / mdot) comes before 2 km for m_p < 246.08 kg (h(t_b) = 2000 m, bisection
 * of the closed form: t_b = 7.24 s); above, the altitude end fires, later than 7.24 s (15.6 s at
 * 3000 kg). A final time of 5 s is therefore met only by a burnout at 5 s: m_p = 5 mdot =
 * 169.9527 kg, a point on another trajectory than the one the end assumes. */
#define HOP_F 100000.0
#define HOP_ISP 300.0

static void hop_yaml(char *buf, size_t cap, const char *con)
{
    snprintf(buf, cap,
             "# a vertical hop: the burn is meant to end at 2 km\n"
             "mission: {name: hop}\n"
             "stages:\n"
             "  - {name: s, dry_mass: 1000, propellant_mass: 2000,\n"
             "     engines: [{name: e, thrust_vac: %g, isp_vac: %g}]}\n"
             "phases:\n"
             "  - {name: burn, model: flat6, stages: [s], stop_time: 100,\n"
             "     end: [{altitude: 2000, direction: rising}, burnout],\n"
             "     integrator: {tolerance: 1.0e-10}}\n"
             "targeting:\n"
             "  variables: [{name: s.propellant_mass, min: 10, max: 3000, scale: 100}]\n"
             "  constraints:\n"
             "    - %s\n",
             HOP_F, HOP_ISP, con);
}

typedef struct end_notes {
    int iterations, start_clean, burnout_noted;
} end_notes;

static void note_ends(const lv_target *t, const lv_target_iter *it, void *user)
{
    (void)t;
    end_notes *e = user;
    if (it->iteration == 0)
        e->start_clean = it->note == NULL; /* 2000 kg: the altitude end, as assumed */
    e->burnout_noted += it->note != NULL &&
                        strstr(it->note, "phase 'burn' ended by burnout at t = ") != NULL &&
                        strstr(it->note, "s, not by altitude") != NULL;
    e->iterations++;
}

static void test_other_end(void)
{
    const double mdot = HOP_F / (HOP_ISP * G0), mp = 5.0 * mdot; /* 169.9527 kg */
    char yaml[2048];
    lv_err err;
    /* (1) the default: the first end written, altitude; converged by burnout: reported */
    hop_yaml(yaml, sizeof yaml, "{final: burn.time, equal: 5, tolerance: 0.001}");
    write_file("target_hop.yaml", yaml);
    lv_mission *m = NULL;
    lv_target *t = NULL;
    const lv_target_result *res = NULL;
    end_notes en = {0};
    CHECK_OK(lv_mission_load("target_hop.yaml", &m, &err), &err);
    if (m != NULL)
        CHECK_OK(lv_target_create(m, &t, &err), &err);
    if (t != NULL) {
        lv_target_settings s;
        lv_target_settings_default(&s);
        s.on_iteration = note_ends;
        s.user = &en;
        CHECK_OK(lv_target_solve(t, &s, &res, &err), &err);
    }
    if (res != NULL) {
        printf("hop: %s, m_p = %.6f kg (closed form %.6f), %zu end mismatch(es)%s%s\n",
               res->converged ? "converged" : "NOT MET", res->x[0], mp, res->n_end_mismatch,
               res->n_end_mismatch ? ": " : "",
               res->n_end_mismatch ? res->end_mismatch[0].actual : "");
        CHECK(res->converged);
        /* dt/dm_p = 1 / mdot = 0.0294 s/kg: the 1 ms tolerance is 0.034 kg */
        CHECK_CLOSE(res->x[0], mp, 0.001 * mdot);
        CHECK(res->n_end_mismatch == 1);
        if (res->n_end_mismatch == 1) {
            const lv_target_end_mismatch *e = &res->end_mismatch[0];
            CHECK(e->phase == 0 && strcmp(e->phase_name, "burn") == 0);
            CHECK(strcmp(e->expected, "altitude") == 0 && strcmp(e->actual, "burnout") == 0);
            CHECK_CLOSE(e->t_end, 5.0, 0.001);
        }
        CHECK(en.start_clean && en.burnout_noted >= 1);
        /* the converged file's header says so */
        CHECK_OK(lv_target_write(t, res->x, "target_hop_conv.yaml", NULL, &err), &err);
        char *out = read_file("target_hop_conv.yaml");
        CHECK(out != NULL && strstr(out, "# lvsim target: WARNING: phase 'burn' ended by burnout "
                                         "at t = 4.99") != NULL &&
              strstr(out, "s, not by altitude, the end its constraints assume") != NULL);
        free(out);
    }
    lv_target_free(t);
    lv_mission_free(m);

    /* (2) the constraint names burnout: the same point, nothing to report */
    hop_yaml(yaml, sizeof yaml, "{final: burn.time, equal: 5, tolerance: 0.001, end: burnout}");
    counts c = {0};
    res = solve_text("target_hop2.yaml", yaml, &m, &t, &c);
    CHECK(res != NULL && res->converged && res->n_end_mismatch == 0);
    if (res != NULL && res->converged) {
        CHECK_CLOSE(res->x[0], mp, 0.001 * mdot);
        CHECK_OK(lv_target_write(t, res->x, "target_hop2_conv.yaml", NULL, &err), &err);
        char *out = read_file("target_hop2_conv.yaml");
        CHECK(out != NULL && strstr(out, "WARNING") == NULL &&
              strstr(out, "# lvsim target: ended as the constraints assume: burn by burnout at "
                          "t = 4.99") != NULL);
        free(out);
    }
    lv_target_free(t);
    lv_mission_free(m);

    /* (3) not met (a final time of 30 s: at most 15.6 s by the altitude end within the bounds,
     * 7.24 s by burnout), with the constraint naming burnout: the best point (3000 kg) ends by
     * altitude, and that is said too */
    hop_yaml(yaml, sizeof yaml, "{final: burn.time, equal: 30, tolerance: 0.001, end: burnout}");
    res = solve_text("target_hop3.yaml", yaml, &m, &t, &c);
    CHECK(res != NULL && !res->converged && res->n_end_mismatch == 1);
    if (res != NULL && res->n_end_mismatch == 1) {
        CHECK(strcmp(res->end_mismatch[0].expected, "burnout") == 0 &&
              strcmp(res->end_mismatch[0].actual, "altitude") == 0);
        CHECK(res->x[0] == 3000.0);
    }
    lv_target_free(t);
    lv_mission_free(m);

    /* (4) the C API: the default, then lv_target_set_end; bad names refused */
    m = NULL;
    t = NULL;
    CHECK_OK(lv_mission_load("target_hop.yaml", &m, &err), &err);
    if (m != NULL)
        CHECK_OK(lv_target_create_empty(m, &t, &err), &err);
    if (t != NULL) {
        CHECK_OK(lv_target_add_var(t, "s.propellant_mass", 10, 3000, NAN, 100, NAN, &err), &err);
        CHECK_OK(lv_target_add_con(t, "burn.time", LV_CON_EQUAL, 5, 0.001, &err), &err);
        CHECK_OK(lv_target_solve(t, NULL, &res, &err), &err);
        CHECK(res != NULL && res->converged && res->n_end_mismatch == 1);
        CHECK_FAILS(lv_target_set_end(t, "burn", "burnot", &err), &err, LV_ERR_INPUT,
                    "end 'burnot': phase 'burn' has no such end; did you mean 'burnout'? (its "
                    "ends: altitude, burnout, stop_time; or any)");
        CHECK_FAILS(lv_target_set_end(t, "brun", "burnout", &err), &err, LV_ERR_INPUT,
                    "did you mean 'burn'");
        CHECK_OK(lv_target_set_end(t, "burn", "any", &err), &err);
        CHECK_OK(lv_target_solve(t, NULL, &res, &err), &err);
        CHECK(res != NULL && res->converged && res->n_end_mismatch == 0);
        CHECK_OK(lv_target_set_end(t, "burn", "stop_time", &err), &err);
        CHECK_OK(lv_target_solve(t, NULL, &res, &err), &err);
        CHECK(res != NULL && res->converged && res->n_end_mismatch == 1 &&
              strcmp(res->end_mismatch[0].expected, "stop_time") == 0);
    }
    lv_target_free(t);
    lv_mission_free(m);
}

int main(void)
{
    test_launch_angle();
    test_launch_angle_optimisers();
    test_two_variables();
    test_rejected_step();
    test_rejected_point();
    test_no_solution();
    test_max_range();
    test_round_trip();
    test_moved_file();
    test_branches();
    test_api();
    test_refused();
    test_other_end();
    return check_report("test_target");
}
