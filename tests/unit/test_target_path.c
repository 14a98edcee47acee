/* test_target_path.c - path constraints of the targeting section (docs/targeting.md, "Path
 * constraints"): `{path: PHASE.NAME, max: v, tolerance: t}` bounds the largest value of NAME over
 * the phase (`min`: the smallest), found on the phase's rows and refined by a parabola through
 * the extreme row and its neighbours (lv_targeting_path_extremum).
 *   (a) the extremum on samples of known functions: a parabola (exact), cos t on a 1 s grid
 *       (0.016 off where the rows' maximum is 0.079 off), a minimum, an
 *       extreme row at an event instant (two rows at one time: no refinement), NaN rows;
 *   (b) the closed form: a shell fired at 100 m/s over a flat, non-rotating world (a sphere of
 *       radius 1e10 m, g = 9.80665 m/s^2 at its surface; no air) reaches
 *           h_max = v^2 sin^2(gamma) / (2 g);
 *       the longest range with h_max <= 150 m is at sin^2(gamma*) = 2 g 150 / v^2:
 *       gamma* = 32.847277 deg (range v^2 sin(2 gamma) / g rises with gamma below 45 deg, so the
 *       path limit is active). SLSQP maximises downrange subject to the path constraint;
 *   (c) refusals with line:column: an unknown output, both min and max, equal, final and path
 *       together, the time, a path on a phase whose model lacks the output. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "lvsim/lv_mission.h"
#include "lvsim/lv_target.h"
#include "mission/targeting_def.h"
#include "mission_kit.h"

#define G0 9.80665

static void test_extremum(void)
{
    /* a parabola y = 5 - (t - 2.3)^2 on the grid 0, 1, .., 5: its vertex exactly */
    double t[8], y[8], tx = 0.0;
    for (int i = 0; i < 6; i++) {
        t[i] = i;
        y[i] = 5.0 - (i - 2.3) * (i - 2.3);
    }
    double v = lv_targeting_path_extremum(t, y, 6, 1, &tx);
    printf("parabola: max %.15g at t %.15g (exact 5 at 2.3)\n", v, tx);
    CHECK_CLOSE(v, 5.0, 1e-12);
    CHECK_CLOSE(tx, 2.3, 1e-12);
    /* the minimum of its negative */
    for (int i = 0; i < 6; i++)
        y[i] = -y[i];
    v = lv_targeting_path_extremum(t, y, 6, 0, &tx);
    CHECK_CLOSE(v, -5.0, 1e-12);
    /* cos(t - 0.4) on a 1 s grid: the rows' max is cos(0.4) = 0.921 (0.079 off); the
     * parabola's vertex value 0.9845 (0.016 off: cos is far from a parabola over +-1 rad) */
    for (int i = 0; i < 6; i++) {
        t[i] = i - 2.0;
        y[i] = cos(t[i] - 0.4);
    }
    v = lv_targeting_path_extremum(t, y, 6, 1, &tx);
    printf("cos: max %.9g at %.9g (exact 1 at 0.4; rows' max %.9g)\n", v, tx, cos(0.4));
    CHECK(fabs(v - 1.0) < 0.02 && v > cos(0.4));
    /* the extreme row at an event instant (two rows at t = 3): taken as it is */
    const double te[5] = {1, 2, 3, 3, 4}, ye[5] = {1, 2, 3, 0, -1};
    v = lv_targeting_path_extremum(te, ye, 5, 1, &tx);
    CHECK(v == 3.0 && tx == 3.0);
    /* NaN rows are skipped; none with a number: NAN */
    const double tn[3] = {0, 1, 2}, yn[3] = {NAN, 2, NAN}, yz[3] = {NAN, NAN, NAN};
    CHECK(lv_targeting_path_extremum(tn, yn, 3, 1, NULL) == 2.0);
    CHECK(isnan(lv_targeting_path_extremum(tn, yz, 3, 1, NULL)));
    /* the last row the extreme (an end): no neighbour beyond it, the row's value */
    const double tl[3] = {0, 1, 2}, yl[3] = {0, 1, 3};
    CHECK(lv_targeting_path_extremum(tl, yl, 3, 1, NULL) == 3.0);
}

#define SHOT(extra, targeting)                                                              \
    "mission: {name: shot}\n"                                                               \
    "environment:\n"                                                                        \
    "  world: planet\n"                                                                     \
    "  planet: {name: flatland, radius: 1.0e10, gm: 9.80665e20, rotation_rate: 0}\n"         \
    "  atmosphere: none\n"                                                                  \
    "parameters: {start_h: 0, start_vel: 100, start_fpa_deg: 20, start_chi_deg: 90}\n"      \
    "stages: [{name: ball, dry_mass: 1, propellant_mass: 0}]\n"                             \
    "phases:\n"                                                                             \
    "  - {name: flight, model: dof3, stages: [ball], stop_time: 100, end: [impact],\n"      \
    "     integrator: {tolerance: 1.0e-10, output_interval: 1}" extra "}\n"                  \
    "targeting:\n"                                                                          \
    "  variables: [{name: start_fpa_deg, min: 5, max: 85, scale: 1}]\n" targeting

static void test_shot(void)
{
    const double v = 100.0, hmax = 150.0;
    const double gamma = asin(sqrt(2.0 * G0 * hmax) / v);
    const char *yaml = SHOT("", "  constraints: [{path: flight.h, max: 150, tolerance: 0.01}]\n"
                                "  cost: {maximize: flight.downrange, scale: 10}\n");
    write_file("target_path_shot.yaml", yaml);
    lv_mission *m = NULL;
    lv_target *t = NULL;
    lv_err err;
    CHECK_OK(lv_mission_load("target_path_shot.yaml", &m, &err), &err);
    if (m != NULL)
        CHECK_OK(lv_target_create(m, &t, &err), &err);
    if (t != NULL) {
        lv_target_settings s;
        lv_target_settings_default(&s);
        const lv_target_result *res = NULL;
        CHECK_OK(lv_target_solve(t, &s, &res, &err), &err);
        if (res != NULL) {
            const double g = res->x[0] * M_PI / 180.0, s2 = sin(g);
            const double h_closed = v * v * s2 * s2 / (2.0 * G0);
            printf("shot: %s; gamma %.6f deg (closed form %.6f), path max h %.6f m (closed form "
                   "at that gamma %.6f), downrange %.4f m (closed form at gamma* %.4f)\n",
                   res->reason, res->x[0], gamma * 180.0 / M_PI, res->finals[0], h_closed,
                   res->cost, v * v * sin(2.0 * gamma) / G0);
            CHECK(res->converged);
            CHECK_CLOSE(res->x[0], gamma * 180.0 / M_PI, 2e-3);
            CHECK(res->finals[0] <= hmax + 0.01);
            /* the rows' parabola on a parabola in t: the closed form's apex, but for the 1e10 m
             * sphere (gravity falling by 2 h / R = 3e-8 at the apex): measured 1.3e-5 m */
            CHECK_CLOSE(res->finals[0], h_closed, 5e-5);
        }
    }
    lv_target_free(t);
    lv_mission_free(m);
}

static void test_refusals(void)
{
    static const struct {
        const char *targeting, *want;
    } bad[] = {
        {"  constraints: [{path: flight.hh, max: 150, tolerance: 0.01}]\n",
         ":13:24: targeting: path constraint: 'flight.hh': phase 'flight' (model dof3) has no "
         "final value 'hh'"},
        {"  constraints: [{path: flight.h, min: 1, max: 150, tolerance: 0.01}]\n",
         ":13:42: targeting: path constraint on 'flight.h': give one of equal, min and max"},
        {"  constraints: [{path: flight.h, equal: 150, tolerance: 0.01}]\n",
         ":13:34: targeting: path constraint on 'flight.h': a path constraint bounds the "
         "largest"},
        {"  constraints: [{path: flight.h, tolerance: 0.01}]\n",
         ":13:17: targeting: path constraint on 'flight.h': give one of min and max"},
        {"  constraints: [{final: flight.h, path: flight.h, max: 1, tolerance: 0.01}]\n",
         ":13:35: targeting: constraint #1: give one of final and path"},
        {"  constraints: [{path: flight.time, max: 150, tolerance: 0.01}]\n",
         ":13:24: targeting: path constraint on 'flight.time': the time only grows"},
        {"  constraints: [{path: flight.heat_flux_fm, max: 1000, tolerance: 1, end: impakt}]\n",
         ":13:75: targeting: constraint on 'flight.heat_flux_fm': end 'impakt'"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char yaml[4096];
        snprintf(yaml, sizeof yaml, SHOT("", "%s"), bad[i].targeting);
        write_file("target_path_bad.yaml", yaml);
        lv_mission *m = NULL;
        lv_err err;
        const lv_status st = lv_mission_load("target_path_bad.yaml", &m, &err);
        printf("refused: %s\n", st != LV_OK ? err.msg : "(loaded)");
        CHECK(st == LV_ERR_INPUT);
        CHECK(st != LV_OK && strstr(err.msg, "target_path_bad.yaml") != NULL &&
              strstr(err.msg, bad[i].want) != NULL);
        lv_mission_free(m);
    }
    /* the flat world's flat6 model has no heat flux: a path on it names the phase's model */
    const char *flat =
        "mission: {name: flat}\n"
        "environment: {world: flat, g: 9.81}\n"
        "stages: [{name: ball, dry_mass: 1, propellant_mass: 0}]\n"
        "phases:\n"
        "  - {name: up, model: flat6, stages: [ball], stop_time: 10, set: {vz: 100}}\n"
        "targeting:\n"
        "  variables: [{name: up.stop_time, min: 1, max: 20}]\n"
        "  constraints: [{path: up.heat_flux, max: 1, tolerance: 0.1}]\n";
    write_file("target_path_flat.yaml", flat);
    lv_mission *m = NULL;
    lv_err err;
    const lv_status st = lv_mission_load("target_path_flat.yaml", &m, &err);
    printf("refused: %s\n", st != LV_OK ? err.msg : "(loaded)");
    CHECK(st == LV_ERR_INPUT && strstr(err.msg, "target_path_flat.yaml:8:") != NULL &&
          strstr(err.msg, "(model flat6) has no final value 'heat_flux'") != NULL);
    lv_mission_free(m);
}

int main(void)
{
    test_extremum();
    test_shot();
    test_refusals();
    return check_report("test_target_path");
}
