/* test_checks.c - a run is right or says why (issue 9): leaving a model's domain ends the phase
 * at the located crossing with the reason, whatever the method; a start state outside the
 * domain and a non-positive mass are refused when the mission is loaded; one propellant book
 * for every model (burnout when the stage's propellant is gone, a payload set by the user is
 * not burnt); phases run and are numbered in file order among those ready. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mission_kit.h"
#include "lvsim/lv_mission.h"

#define G0 9.80665

static size_t phase(const lv_mission *m, const char *name)
{
    size_t k = 0;
    lv_err err;
    CHECK_OK(lv_mission_phase_find(m, name, &k, &err), &err);
    return k;
}

/* The last row of phase k's rows: column `name`. */
static double last(const lv_run *r, size_t k, const char *name)
{
    const lv_result *res = lv_run_rows(r, k);
    size_t c;
    if (res == NULL || lv_result_rows(res) == 0 || lv_result_column(res, name, &c, NULL) != LV_OK)
        return NAN;
    return lv_result_value(res, lv_result_rows(res) - 1, c);
}

/* ---- item 2: the model's domain ------------------------------------------------------------ */

/* A ball dropped from 1 km with nothing to stop it: over a planet without atmosphere it falls
 * 20 km below the ellipsoid, where the dof3 model's domain ends; with US76 at its floor, -5 km.
 * Every method ends the phase there, failed, with the reason, after few steps (no "too much
 * work"). With an `impact` end the phase ends on the ground, done. */
static void test_domain(void)
{
    static const char *const methods[] = {"dassl", "cvode-adams", "dopri5", "rk4", "euler"};
    for (int atmo = 0; atmo < 2; atmo++) {
        for (int k = 0; k < 5; k++) {
            char yaml[2048];
            snprintf(yaml, sizeof yaml,
                     "mission: {name: drop}\n"
                     "environment: {world: planet, gravity: j2, atmosphere: %s}\n"
                     "parameters: {start_lat_deg: 45, start_h: 1000}\n"
                     "stages: [{name: ball, dry_mass: 10, propellant_mass: 0}]\n"
                     "phases:\n"
                     "  - {name: fall, model: dof3, stages: [ball], stop_time: 1000,\n"
                     "     integrator: {method: %s, fixed_step: 0.05}}\n",
                     atmo ? "us76" : "none", methods[k]);
            write_file("domain.yaml", yaml);
            lv_mission *m = NULL;
            lv_run *r = NULL;
            lv_err err;
            CHECK_OK(lv_mission_load("domain.yaml", &m, &err), &err);
            if (m == NULL)
                continue;
            CHECK_OK(lv_run_create(m, &r, &err), &err);
            CHECK(lv_run_execute(r, NULL, &err) == LV_ERR_SOLVER);
            const lv_phase_result *res = lv_run_result(r, 0);
            const double floor_h = atmo ? -5000.0 : -20000.0;
            char want[160];
            snprintf(want, sizeof want, "left the model's domain: h fell to its lower bound %g m",
                     floor_h);
            CHECK(res->state == LV_PHASE_FAILED && strstr(res->error, want) != NULL);
            CHECK(strstr(res->error, "under the ground") != NULL);
            /* the failed rows end at the crossing (Euler: on its straight-line interpolant) */
            CHECK_CLOSE(last(r, 0, "h"), floor_h, 1e-3);
            CHECK(res->report.stats.steps < 20000);
            lv_run_free(r);
            lv_mission_free(m);
        }
    }
    /* the same with an impact end: done, on the ground */
    write_file("impact.yaml", "mission: {name: drop}\n"
                              "environment: {world: planet, gravity: j2, atmosphere: none}\n"
                              "parameters: {start_lat_deg: 45, start_h: 1000}\n"
                              "stages: [{name: ball, dry_mass: 10, propellant_mass: 0}]\n"
                              "phases:\n"
                              "  - {name: fall, model: dof3, stages: [ball], stop_time: 1000,\n"
                              "     end: [impact]}\n");
    lv_mission *m = NULL;
    lv_run *r = NULL;
    lv_err err;
    CHECK_OK(lv_mission_load("impact.yaml", &m, &err), &err);
    if (m != NULL) {
        CHECK_OK(lv_run_create(m, &r, &err), &err);
        CHECK_OK(lv_run_execute(r, NULL, &err), &err);
        double h;
        CHECK_OK(lv_run_final(r, 0, "h", &h, &err), &err);
        CHECK_CLOSE(h, 0.0, 1e-6);
        lv_run_free(r);
        lv_mission_free(m);
    }
    /* the flat world: its ground is z = 0, its domain ends 5 km below */
    write_file("flatfall.yaml", "mission: {name: fall}\n"
                                "parameters: {start_z: 100}\n"
                                "stages: [{name: s, dry_mass: 10, propellant_mass: 0}]\n"
                                "phases:\n  - {name: fall, model: flat6, stages: [s], "
                                "stop_time: 1000, integrator: {tolerance: 1.0e-12}}\n");
    CHECK_OK(lv_mission_load("flatfall.yaml", &m, &err), &err);
    if (m != NULL) {
        CHECK_OK(lv_run_create(m, &r, &err), &err);
        CHECK(lv_run_execute(r, NULL, &err) == LV_ERR_SOLVER);
        /* free fall from 100 m to -5000 m: t = sqrt(2 * 5100 / 9.81) */
        CHECK_CLOSE(lv_run_result(r, 0)->t_end, sqrt(2.0 * 5100.0 / 9.81), 1e-6);
        CHECK(strstr(lv_run_result(r, 0)->error, "z fell to its lower bound -5000 m") != NULL);
        lv_run_free(r);
        lv_mission_free(m);
    }
}

/* ---- item 3: refused when loaded ----------------------------------------------------------- */

static void load_fails(const char *yaml, const char *want)
{
    write_file("bad.yaml", yaml);
    lv_mission *m = NULL;
    lv_err err = {LV_OK, ""};
    lv_status st = lv_mission_load("bad.yaml", &m, &err);
    check_count_++;
    if (st != LV_ERR_INPUT || m != NULL || strstr(err.msg, want) == NULL) {
        check_failures_++;
        fprintf(stderr, "%s:%d: expected LV_ERR_INPUT with \"%s\", got %d \"%s\"\n", __FILE__,
                __LINE__, want, (int)st, err.msg);
    }
    lv_mission_free(m);
}

static void test_start_checks(void)
{
    /* a start altitude below the model's domain (US76's floor), and a NaN-free but absurd one */
    load_fails("mission: {name: t}\n"
               "environment: {world: planet}\n"
               "parameters: {start_h: -6000}\n"
               "stages: [{name: s, dry_mass: 10, propellant_mass: 0}]\n"
               "phases:\n  - {name: P, model: dof3, stages: [s], stop_time: 10}\n",
               "bad.yaml:6:5: phase 'P': the start state at t = 0 s is outside the "
               "model's domain: h = -6000 m is below its lower bound -5000 m");
    /* a mass set to zero or below, in a root and in a child */
    load_fails("mission: {name: t}\n"
               "stages: [{name: s, dry_mass: 10, propellant_mass: 0}]\n"
               "phases:\n  - {name: P, model: flat6, stages: [s], stop_time: 10, set: {m: -5}}\n",
               "bad.yaml:4:63: phase 'P': set: m = -5 kg: a mass must be > 0");
    load_fails("mission: {name: t}\n"
               "stages: [{name: s, dry_mass: 10, propellant_mass: 0}]\n"
               "phases:\n  - {name: P, model: flat6, stages: [s], stop_time: 10}\n"
               "  - {name: C, model: flat6, stages: [s], from: P, stop_time: 20, set: {m: 0}}\n",
               "bad.yaml:5:72: phase 'C': set: m = 0 kg: a mass must be > 0");
    load_fails("mission: {name: t}\n"
               "stages: [{name: s, dry_mass: 10, propellant_mass: 0}]\n"
               "phases:\n  - {name: P, model: flat6, stages: [s], stop_time: 10, set: {m: 7}}\n",
               "bad.yaml:4:63: phase 'P': set: m = 7 kg is less than the dry mass 10 kg");
    /* check and run accept the same files: a good file loads */
    write_file("good.yaml", "mission: {name: t}\n"
                            "stages: [{name: s, dry_mass: 10, propellant_mass: 0}]\n"
                            "phases:\n  - {name: P, model: flat6, stages: [s], stop_time: 1}\n");
    lv_mission *m = NULL;
    lv_err err;
    CHECK_OK(lv_mission_load("good.yaml", &m, &err), &err);
    lv_mission_free(m);
}

/* ---- item 4: one propellant book ----------------------------------------------------------- */

/* A stage of 1000 kg dry and 2000 kg propellant, engine 1e5 N at Isp 300 s: burnout when the
 * 2000 kg are gone, t_b = 2000 / (1e5 / (300 g0)) = 58.8399 s, in both models, also when the
 * phase's mass is set 1500 kg higher (payload: it stays on board, burnout at m = 2500 kg); set
 * 500 kg lower (2500 kg: a mid-burn start) the stage holds 1500 kg, burnout at 1500 / mdot =
 * 44.1299 s at the dry mass 1000 kg. */
static void test_propellant_book(void)
{
    const double mdot = 1e5 / (300.0 * G0), tb = 2000.0 / mdot;
    for (int planet = 0; planet < 2; planet++) {
        for (int payload = 0; payload < 3; payload++) { /* 2: mid-burn */
            const double prop = payload == 2 ? 1500.0 : 2000.0;
            char yaml[2048];
            snprintf(yaml, sizeof yaml,
                     "mission: {name: book}\n%s"
                     "stages: [{name: s, dry_mass: 1000, propellant_mass: 2000,\n"
                     "          engines: [{thrust_vac: 1.0e5, isp_vac: 300}]}]\n"
                     "phases:\n"
                     "  - {name: burn, model: %s, stages: [s], stop_time: 200, end: [burnout],\n"
                     "     integrator: {method: dopri5, tolerance: 1.0e-10}%s}\n",
                     planet ? "environment: {world: planet, atmosphere: none}\n"
                              "parameters: {start_h: 100000, start_vel: 7000, start_fpa: 0}\n"
                            : "parameters: {start_fpa_deg: 90}\n",
                     planet ? "dof3" : "flat6",
                     payload == 1 ? ", set: {m: 4500}" : payload == 2 ? ", set: {m: 2500}" : "");
            write_file("book.yaml", yaml);
            lv_mission *m = NULL;
            lv_run *r = NULL;
            lv_err err;
            CHECK_OK(lv_mission_load("book.yaml", &m, &err), &err);
            if (m == NULL)
                continue;
            CHECK_OK(lv_run_create(m, &r, &err), &err);
            CHECK_OK(lv_run_execute(r, NULL, &err), &err);
            const lv_phase_result *res = lv_run_result(r, 0);
            double t, mass;
            CHECK_OK(lv_run_final(r, 0, "time", &t, &err), &err);
            CHECK_OK(lv_run_final(r, 0, "m", &mass, &err), &err);
            CHECK_CLOSE(t, tb * prop / 2000.0, 1e-8);
            CHECK_CLOSE(mass, payload == 1 ? 2500.0 : 1000.0, 1e-8);
            CHECK_CLOSE(res->payload, payload == 1 ? 1500.0 : 0.0, 1e-9);
            CHECK(res->propellant_start[0] == prop);
            CHECK_CLOSE(res->propellant_end[0], 0.0, 1e-8);
            printf("book %s%s: burnout at %.9f s (%.9f), m = %.6f kg\n", planet ? "dof3" : "flat6",
                   payload == 1 ? " + 1500 kg payload" : payload == 2 ? " from 2500 kg" : "", t,
                   tb * prop / 2000.0, mass);
            lv_run_free(r);
            lv_mission_free(m);
        }
    }
}

/* ---- item 6: run order ------------------------------------------------------------------------- */

static void record_order(const lv_run *r, size_t k, const lv_phase_result *res, void *user)
{
    (void)r;
    (void)res;
    size_t *log = user;
    log[1 + log[0]++] = k;
}

/* File order C2 (from R2), R1, R2, C1 (from R1): the roots first in file order, then among the
 * phases ready, file order: R1, R2, C2, C1; one worker runs them in that order. */
static void test_run_order(void)
{
    write_file("order.yaml",
               "mission: {name: order}\n"
               "stages: [{name: a, dry_mass: 1, propellant_mass: 0},\n"
               "         {name: b, dry_mass: 1, propellant_mass: 0}]\n"
               "phases:\n"
               "  - {name: C2, model: flat6, stages: [b], from: R2, stop_time: 2}\n"
               "  - {name: R1, model: flat6, stages: [a], stop_time: 1}\n"
               "  - {name: R2, model: flat6, stages: [b], stop_time: 1}\n"
               "  - {name: C1, model: flat6, stages: [a], from: R1, stop_time: 2}\n");
    lv_mission *m = NULL;
    lv_run *r = NULL;
    lv_err err;
    CHECK_OK(lv_mission_load("order.yaml", &m, &err), &err);
    if (m == NULL)
        return;
    static const char *const want[] = {"R1", "R2", "C2", "C1"};
    for (size_t k = 0; k < 4; k++)
        CHECK(strcmp(lv_mission_phase_name(m, k), want[k]) == 0);
    lv_phase_info pi;
    lv_mission_phase_info(m, phase(m, "C2"), &pi);
    CHECK(pi.file_index == 0);
    size_t log[8] = {0};
    const lv_run_options opt = {.threads = 1, .on_phase = record_order, .user = log};
    CHECK_OK(lv_run_create(m, &r, &err), &err);
    CHECK_OK(lv_run_execute(r, &opt, &err), &err);
    CHECK(log[0] == 4);
    for (size_t i = 0; i < 4; i++)
        CHECK(log[1 + i] == i);
    lv_run_free(r);
    lv_mission_free(m);
}

int main(void)
{
    test_domain();
    test_start_checks();
    test_propellant_book();
    test_run_order();
    return check_report("test_checks");
}
