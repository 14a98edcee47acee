/* test_ends.c - a phase ends on any variable of its model or after a duration (issue 12):
 * `{mach: 1}`, `{fpa_deg: -45}`, `{output: v_down, value: 30}`, `{time: 5}` for dof3 and flat6;
 * the end is located on the crossing, named in the result, its value is a run parameter
 * ("<phase>.end.<variable>"); a wrong variable, a parameter, `_deg` on a non-angle or a time
 * with a direction is refused when the mission is loaded, with file, line and column. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mission_kit.h"
#include "lvsim/lv_mission.h"

static double final(const lv_run *r, size_t k, const char *name)
{
    double v = NAN;
    lv_err err;
    CHECK_OK(lv_run_final(r, k, name, &v, &err), &err);
    return v;
}

static const char *unit_of(const lv_mission *m, const char *name)
{
    size_t i = 0;
    int deg = 0;
    lv_err err;
    lv_param_info pi = {0};
    CHECK_OK(lv_mission_param_find(m, name, &i, &deg, &err), &err);
    lv_mission_param_info(m, i, &pi);
    return pi.unit != NULL ? pi.unit : "?";
}

/* flat6, uniform gravity g = 9.81 m/s^2, no thrust (a dry stage), dropped from rest at 1 km:
 * vz = -g t and z = 1000 - g t^2 / 2 in closed form. */
static void test_flat6_ends(void)
{
    write_file("ends_flat.yaml", "mission: {name: drop}\n"
                                 "parameters: {start_z: 1000, start_vel: 0}\n"
                                 "stages: [{name: s, dry_mass: 10, propellant_mass: 0}]\n"
                                 "phases:\n"
                                 "  - {name: A, model: flat6, stages: [s], stop_time: 100,\n"
                                 "     integrator: {tolerance: 1.0e-10},\n"
                                 "     end: [{vz: -20, direction: falling}, impact]}\n"
                                 "  - {name: B, model: flat6, stages: [s], from: A,\n"
                                 "     stop_time: 200, integrator: {tolerance: 1.0e-10}, end: [{time: 1.5}]}\n"
                                 "  - {name: C, model: flat6, stages: [s], from: B,\n"
                                 "     stop_time: 300, integrator: {tolerance: 1.0e-10},\n"
                                 "     end: [{output: speed, value: 40}]}\n");
    lv_mission *m = NULL;
    lv_run *r = NULL;
    lv_err err;
    CHECK_OK(lv_mission_load("ends_flat.yaml", &m, &err), &err);
    if (m == NULL)
        return;
    CHECK_OK(lv_run_create(m, &r, &err), &err);
    CHECK_OK(lv_run_execute(r, NULL, &err), &err);
    const double g = 9.81;
    /* A: vz = -20 m/s at t = 20 / g, the first of its ends (index 0) */
    const lv_phase_result *a = lv_run_result(r, 0);
    CHECK_CLOSE(a->t_end, 20.0 / g, 1e-7);
    CHECK_CLOSE(final(r, 0, "vz"), -20.0, 1e-7);
    CHECK(a->end_index == 0 && a->end_value == -20.0);
    CHECK(strcmp(a->report.stop_name, "vz") == 0);
    /* B: 1.5 s after its start, exactly (a time event) */
    const lv_phase_result *b = lv_run_result(r, 1);
    CHECK(b->t_end == a->t_end + 1.5);
    CHECK(b->end_index == 0 && strcmp(b->report.stop_name, "time") == 0);
    CHECK_CLOSE(final(r, 1, "vz"), -g * b->t_end, 1e-7);
    /* C: the speed output reaches 40 m/s */
    const lv_phase_result *c = lv_run_result(r, 2);
    CHECK_CLOSE(c->t_end, 40.0 / g, 1e-7);
    CHECK_CLOSE(final(r, 2, "z"), 1000.0 - 0.5 * g * c->t_end * c->t_end, 1e-4);

    /* the end values are run parameters with their model's unit */
    CHECK(strcmp(unit_of(m, "A.end.vz"), "m/s") == 0);
    CHECK(strcmp(unit_of(m, "B.end.time"), "s") == 0);
    CHECK_OK(lv_run_set(r, "A.end.vz", -30.0, &err), &err);
    CHECK_OK(lv_run_set(r, "B.end.time", 0.25, &err), &err);
    CHECK_OK(lv_run_execute(r, NULL, &err), &err);
    CHECK_CLOSE(lv_run_result(r, 0)->t_end, 30.0 / g, 1e-7);
    CHECK(lv_run_result(r, 1)->t_end == lv_run_result(r, 0)->t_end + 0.25);
    /* a duration must be > 0 */
    CHECK_FAILS(lv_run_set(r, "B.end.time", 0.0, &err), &err, LV_ERR_INPUT, "B.end.time");
    lv_run_free(r);
    lv_mission_free(m);
}

/* dof3 over a planet without atmosphere: a ball thrown level at 300 m/s from 5 km; its
 * relative flight-path angle falls through -45 deg; with {v_down: 30} a second ball ends
 * when its downward speed reaches 30 m/s (an output), with {mach: 1} a third in US76 air. */
static void test_dof3_ends(void)
{
    write_file("ends_dof3.yaml",
               "mission: {name: throw}\n"
               "environment: {world: planet, gravity: j2, atmosphere: us76}\n"
               "parameters: {start_lat_deg: 45, start_h: 5000, start_vel: 300, start_fpa_deg: 0}\n"
               "stages: [{name: ball, dry_mass: 10, propellant_mass: 0}]\n"
               "phases:\n"
               "  - {name: A, model: dof3, stages: [ball], stop_time: 200,\n"
               "     integrator: {tolerance: 1.0e-9}, end: [{fpa_deg: -45}, impact]}\n"
               "  - {name: B, model: dof3, stages: [ball], stop_time: 200,\n"
               "     alternative: true, end: [{output: v_down, value: 30, direction: rising}]}\n"
               "  - {name: C, model: dof3, stages: [ball], stop_time: 200,\n"
               "     alternative: true, end: [{mach: 1}, impact]}\n");
    lv_mission *m = NULL;
    lv_run *r = NULL;
    lv_err err;
    CHECK_OK(lv_mission_load("ends_dof3.yaml", &m, &err), &err);
    if (m == NULL)
        return;
    CHECK_OK(lv_run_create(m, &r, &err), &err);
    CHECK_OK(lv_run_execute(r, NULL, &err), &err);
    CHECK_CLOSE(final(r, 0, "fpa"), -M_PI / 4.0, 1e-9);
    CHECK(lv_run_result(r, 0)->end_index == 0);
    CHECK_CLOSE(lv_run_result(r, 0)->end_value, -M_PI / 4.0, 1e-15);
    CHECK_CLOSE(final(r, 1, "v_down"), 30.0, 1e-6);
    CHECK_CLOSE(final(r, 2, "mach"), 1.0, 1e-6);
    CHECK(lv_run_result(r, 2)->end_index == 0);
    /* the ends' names are the phase's event names after the model's own */
    const lv_phase_result *c = lv_run_result(r, 2);
    CHECK(c->n_event_names >= 1 && strcmp(c->event_names[c->n_event_names - 1], "mach") == 0);
    CHECK(strcmp(unit_of(m, "A.end.fpa"), "rad") == 0);
    lv_run_free(r);
    lv_mission_free(m);
}

/* Two ends of the same kind in one phase (a window: leave through the top or the bottom)
 * load for both models; the second is named "<kind>_2" in the events and as a parameter.
 * dof3: thrown up at 100 m/s, fpa 80 deg from 1 km in vacuum, apex below 1000 + 100^2/(2 g)
 * = 1510 m, so the 500 m end (the second) ends the phase. flat6: dropped from 1 km, the
 * 900 m end (the first) comes first. */
static void test_two_ends_of_a_kind(void)
{
    static const char *const yaml[2] = {
        "mission: {name: t}\n"
        "environment: {world: planet}\n"
        "parameters: {start_h: 1000, start_vel: 100, start_fpa_deg: 80}\n"
        "stages: [{name: s, dry_mass: 10, propellant_mass: 0}]\n"
        "phases:\n"
        "  - {name: P, model: dof3, stages: [s], stop_time: 100,\n"
        "     end: [{altitude: 2000}, {altitude: 500}]}\n",
        "mission: {name: t}\n"
        "parameters: {start_z: 1000, start_vel: 0}\n"
        "stages: [{name: s, dry_mass: 10, propellant_mass: 0}]\n"
        "phases:\n"
        "  - {name: P, model: flat6, stages: [s], stop_time: 100,\n"
        "     end: [{z: 900}, {z: 500}]}\n"};
    static const int want_end[2] = {1, 0};
    static const char *const want_name[2] = {"altitude_2", "z"};
    static const char *const second[2] = {"P.end.altitude_2", "P.end.z_2"};
    for (int k = 0; k < 2; k++) {
        write_file("two_ends.yaml", yaml[k]);
        lv_mission *m = NULL;
        lv_run *r = NULL;
        lv_err err;
        CHECK_OK(lv_mission_load("two_ends.yaml", &m, &err), &err);
        if (m == NULL)
            continue;
        CHECK_OK(lv_run_create(m, &r, &err), &err);
        CHECK_OK(lv_run_execute(r, NULL, &err), &err);
        const lv_phase_result *p = lv_run_result(r, 0);
        CHECK(p->end_index == want_end[k]);
        int found = 0;
        for (size_t i = 0; i < p->n_event_names; i++)
            found += strcmp(p->event_names[i], want_name[k]) == 0;
        if (found != 1)
            for (size_t i = 0; i < p->n_event_names; i++)
                fprintf(stderr, "  %d event %zu: %s\n", k, i, p->event_names[i]);
        CHECK(found == 1);
        size_t idx = 0;
        int deg = 0;
        CHECK_OK(lv_mission_param_find(m, second[k], &idx, &deg, &err), &err);
        lv_run_free(r);
        lv_mission_free(m);
    }
}

static void load_fails(const char *end, const char *want)
{
    char yaml[1024];
    snprintf(yaml, sizeof yaml,
             "mission: {name: t}\n"
             "stages: [{name: s, dry_mass: 10, propellant_mass: 0}]\n"
             "phases:\n"
             "  - {name: P, model: flat6, stages: [s], stop_time: 10,\n"
             "     end: [%s]}\n",
             end);
    write_file("bad_end.yaml", yaml);
    lv_mission *m = NULL;
    lv_err err;
    lv_status st = lv_mission_load("bad_end.yaml", &m, &err);
    CHECK(st != LV_OK && m == NULL);
    if (st != LV_OK && strstr(err.msg, want) == NULL) {
        fprintf(stderr, "  end [%s]\n  got:  %s\n  want: %s\n", end, err.msg, want);
        CHECK(0);
    }
    lv_mission_free(m);
}

static void test_refused(void)
{
    load_fails("{vzz: 3}", "bad_end.yaml:5:12: phase 'P': end: the flat6 model has no variable 'vzz'");
    load_fails("{vzz: 3}", "did you mean");
    load_fails("{g: 3}", "'g' is a parameter of the model");
    load_fails("{z_deg: 3}", "'z' is not an angle (its unit is 'm')");
    load_fails("{time: 0}", "bad_end.yaml:5:19: phase 'P', end event #1: time must be >= 1e-09 s");
    load_fails("{time: 2, direction: rising}", "a time end has no direction");
    load_fails("{vz: 1, z: 3}", "one event per entry");
    load_fails("{output: vz}", "'value'");
    load_fails("{output: 3, value: 1}", "no variable '3'");
    load_fails("{vz: fast}", "number");
}

int main(void)
{
    test_flat6_ends();
    test_dof3_ends();
    test_two_ends_of_a_kind();
    test_refused();
    return check_report("test_ends");
}
