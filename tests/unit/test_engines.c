/* test_engines.c - engines by count (issue 27, item 3): a phase runs n of a stage's N identical
 * engines (`engines:`), the throttle laws respect the running engines' minimum throttle and
 * say where they saturate, an engine stops at a time within a phase (`engine_out:`), bad
 * values refused with file:line.
 *
 *   (a) thrust and mass flow of n of N engines against the closed forms
 *       T = n (c F_vac - p_amb A_exit) (Sutton & Biblarz, Rocket Propulsion Elements, 9th ed.,
 *       eq. 2-14) and mdot = n c F_vac / (Isp g0), the sea-level pressure of US76 (101325 Pa,
 *       U.S. Standard Atmosphere 1976, table I), the mass after a burn m0 - mdot t; the
 *       same on a runway's take-off roll;
 *   (b) a landing on 1 engine whose minimum throttle is above the throttle the law comes to
 *       need: until then the law holds a constant deceleration a, so the mass follows the
 *       rocket equation under constant thrust acceleration, m(t) = m0 exp(-(a + g) t / (Isp
 *       g0)), and the law's throttle c(t) = m(t) (a + g) / F_vac reaches T_min at
 *       t_s = Isp g0 / (a + g) ln(m0 (a + g) / (T_min F_vac)); there the throttle_min event is
 *       logged and from there the engine gives T_min F_vac while the law asks for less;
 *   (c) engine-out at t: the rows just before and just after the time event hold the thrust
 *       and mass flow of 3 and of 2 engines; the final mass m0 - 3 mdot1 t_out - 2 mdot1
 *       (t_f - t_out); the time as a run parameter (a dispersion's slot); the same in dof6;
 *   (d) bad values: file, line and field named.
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mission_kit.h"
#include "lvsim/lv_dispersion.h"
#include "lvsim/lv_io.h"
#include "lvsim/lv_mission.h"

#define G0 9.80665

static double final(const lv_run *r, size_t k, const char *name)
{
    double v = NAN;
    lv_err err;
    CHECK_OK(lv_run_final(r, k, name, &v, &err), &err);
    return v;
}

static size_t col(const lv_result *res, const char *name)
{
    size_t c = 0;
    lv_err err;
    CHECK_OK(lv_result_column(res, name, &c, &err), &err);
    return c;
}

/* ---- (a) n of N engines ---------------------------------------------------------------- */

static void test_count(void)
{
    /* 9 engines of 914 kN, Isp 311 s, A_exit 0.68 m^2; phase A runs 3 at throttle 0.7 from
     * the ground (US76), phase B all 9 (no `engines:`) at the same throttle */
    const char *yaml =
        "mission: {name: count}\n"
        "environment: {world: planet, planet: earth, atmosphere: us76}\n"
        "parameters: {start_lat_deg: 5, start_h: 0, start_vel: 0, start_fpa_deg: 90}\n"
        "stages: [{name: b, dry_mass: 300000, propellant_mass: 200000,\n"
        "          engines: [{name: e, count: 9, thrust_vac: 914000, isp_vac: 311,\n"
        "                     exit_area: 0.68, throttle_min: 0.4}]},\n"
        "         {name: b2, dry_mass: 300000, propellant_mass: 200000,\n"
        "          engines: [{name: e2, count: 9, thrust_vac: 914000, isp_vac: 311,\n"
        "                     exit_area: 0.68, throttle_min: 0.4}]}]\n"
        "phases:\n"
        "  - {name: A, model: dof3, stages: [b], start_time: 0, stop_time: 10, engines: 3,\n"
        "     throttle: {value: 0.7}, integrator: {tolerance: 1.0e-10}}\n"
        "  - {name: B, model: dof3, stages: [b2], start_time: 0, stop_time: 10,\n"
        "     throttle: {value: 0.7}, integrator: {tolerance: 1.0e-10}}\n";
    lv_mission *m;
    lv_run *r = run_text("engines_count.yaml", yaml, &m);
    if (r == NULL)
        return lv_mission_free(m);
    const double mdot1 = 914000.0 / (311.0 * G0); /* Isp definition */
    const int n[2] = {3, 9};
    for (size_t k = 0; k < 2; k++) {
        const lv_result *res = lv_run_rows(r, k);
        CHECK(res != NULL && lv_result_rows(res) > 2);
        if (res == NULL)
            continue;
        const double p = lv_result_value(res, 0, col(res, "p_amb"));
        CHECK_CLOSE(p, 101325.0, 1e-6); /* US76 sea level */
        const double thrust = lv_result_value(res, 0, col(res, "thrust"));
        const double mdot = lv_result_value(res, 0, col(res, "mdot"));
        printf("count: %d of 9: thrust %.3f N (%.3f), mdot %.6f kg/s (%.6f)\n", n[k], thrust,
               n[k] * (0.7 * 914000.0 - p * 0.68), mdot, n[k] * 0.7 * mdot1);
        CHECK_REL(thrust, n[k] * (0.7 * 914000.0 - p * 0.68), 1e-12);
        CHECK_REL(mdot, n[k] * 0.7 * mdot1, 1e-12);
        CHECK(lv_result_value(res, 0, col(res, "engines_running")) == n[k]);
        CHECK(lv_result_value(res, 0, col(res, "throttle_eff")) == 0.7);
        /* the mass after 10 s at a constant flow */
        CHECK_REL(final(r, k, "m"), 500000.0 - n[k] * 0.7 * mdot1 * 10.0, 1e-10);
    }
    lv_run_free(r);
    lv_mission_free(m);
}

/* A take-off roll on 2 of 4 engines (runway model): its thrust and mass flow at the start, at
 * rest on the runway at 150 m (US76 pressure there, the phase's own output p_amb). */
static void test_count_runway(void)
{
    const char *yaml =
        "mission: {name: rw}\n"
        "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}\n"
        "stages:\n"
        "  - {name: ms, dry_mass: 50000, propellant_mass: 100000,\n"
        "     engines: [{name: e, count: 4, thrust_vac: 5.0e5, isp_vac: 350, exit_area: 0.4}]}\n"
        "phases:\n"
        "  - {name: P, model: runway, stages: [ms], stop_time: 20, engines: 2,\n"
        "     runway: {lat_deg: 43, lon_deg: 1, elevation: 150, heading_deg: 90},\n"
        "     takeoff: {mu: 0.02, v_rot: 90, alpha_rot_deg: 8}}\n";
    lv_mission *m;
    lv_run *r = run_text("engines_runway.yaml", yaml, &m);
    if (r == NULL)
        return lv_mission_free(m);
    const lv_result *res = lv_run_rows(r, 0);
    if (res != NULL && lv_result_rows(res) > 0) {
        size_t cp = 0;
        lv_err err;
        const int has_p = lv_result_column(res, "p_amb", &cp, &err) == LV_OK;
        const double p = has_p ? lv_result_value(res, 0, cp) : NAN;
        const double thrust = lv_result_value(res, 0, col(res, "thrust"));
        printf("runway: 2 of 4: thrust %.3f N (%.3f at p = %.3f Pa)\n", thrust,
               2.0 * (5.0e5 - p * 0.4), p);
        CHECK(has_p);
        CHECK_REL(thrust, 2.0 * (5.0e5 - p * 0.4), 1e-12);
        CHECK_REL(lv_result_value(res, 0, col(res, "mdot")), 2.0 * 5.0e5 / (350.0 * G0), 1e-12);
    }
    lv_run_free(r);
    lv_mission_free(m);
}

/* ---- (b) a landing on one engine that cannot throttle low enough ------------------------- */

static void test_landing_min(void)
{
    /* stage: 20 t dry, 10 t propellant, 2 engines of 600 kN (Isp 300 s, T_min 0.85), 1 runs;
     * 2 km up falling at 181 m/s: the law asks a = (181^2 - 2^2) / 4000 = 8.1893 m/s^2,
     * throttle 0.900 at the start, falling as the mass does: the minimum 0.85 (510 kN, above
     * the 294 kN weight: no hover) is reached at 9.3 s, long before touchdown */
    const char *yaml =
        "mission: {name: landing-min}\n" FLAT_WORLD
        "parameters: {start_h: 2000, start_vel: 181, start_fpa_deg: -90}\n"
        "stages: [{name: s, dry_mass: 20000, propellant_mass: 10000,\n"
        "          engines: [{name: m1, count: 2, thrust_vac: 600000, isp_vac: 300,\n"
        "                     throttle_min: 0.85}]}]\n"
        "phases:\n"
        "  - {name: land, model: dof3, stages: [s], stop_time: 40, engines: 1,\n"
        "     end: [impact, {speed: 1, direction: falling}],\n"
        "     integrator: {tolerance: 1.0e-10, output_interval: 0.05},\n"
        "     guidance: {law: retrograde}, throttle: {landing: {altitude: 0, speed: 2}}}\n";
    lv_mission *m;
    lv_run *r = run_text("engines_landing.yaml", yaml, &m);
    if (r == NULL)
        return lv_mission_free(m);
    const double a = (181.0 * 181.0 - 4.0) / 4000.0, F = 600000.0, m0 = 30000.0;
    /* g at 2 km above the flat world's surface differs from g0 by 4e-7: in the tolerance */
    const double ts = 300.0 * G0 / (a + G0) * log(m0 * (a + G0) / (0.85 * F));
    const lv_phase_result *pr = lv_run_result(r, 0);
    double t_ev = NAN;
    int dir = 0;
    for (size_t i = 0; i < pr->report.n_event_log; i++) {
        const lv_event_record *e = &pr->report.event_log[i];
        if (e->is_state && e->index >= 0 && (size_t)e->index < pr->n_event_names &&
            strcmp(pr->event_names[e->index], "throttle_min") == 0 && isnan(t_ev)) {
            t_ev = e->t;
            dir = e->direction;
        }
    }
    printf("landing-min: throttle_min event at %.6f s (closed form %.6f s), direction %d; "
           "ended by %s at %.3f s\n", t_ev, ts, dir, pr->report.stop_name, pr->t_end);
    CHECK_CLOSE(t_ev, ts, 1e-4);
    CHECK(dir == -1);
    /* from there the engine gives T_min F_vac while the law asks for less */
    const lv_result *res = lv_run_rows(r, 0);
    int n_sat = 0, bad = 0;
    const size_t c_t = res ? col(res, "time") : 0, c_in = res ? col(res, "throttle_in") : 0;
    const size_t c_eff = res ? col(res, "throttle_eff") : 0, c_f = res ? col(res, "thrust") : 0;
    const size_t c_n = res ? col(res, "engines_running") : 0;
    for (size_t i = 0; res != NULL && i < lv_result_rows(res); i++) {
        const double t = lv_result_value(res, i, c_t);
        if (!(t > ts + 1e-3) || t > ts + 2.0)
            continue;
        n_sat++;
        bad += !(lv_result_value(res, i, c_in) < 0.85);
        bad += lv_result_value(res, i, c_eff) != 0.85;
        bad += fabs(lv_result_value(res, i, c_f) - 0.85 * F) > 1e-6;
        bad += lv_result_value(res, i, c_n) != 1.0;
    }
    CHECK(n_sat > 10 && bad == 0);
    /* the minimum thrust is above the weight: the stage cannot hover nor come down at 2 m/s;
     * it stops short of the ground (the speed end, not the impact) */
    CHECK(pr->end_index == 1);
    printf("landing-min: stopped at h = %.3f m\n", final(r, 0, "h"));
    CHECK(final(r, 0, "h") > 1.0);
    lv_run_free(r);
    lv_mission_free(m);
}

/* ---- (c) engine-out at a time within the phase ----------------------------------------- */

static void test_engine_out(void)
{
    /* 3 engines of 100 kN (Isp 300 s) lifting a 40 t stack in the flat world, no air; the
     * phase starts at mission time 10 s and one engine stops 2.5 s later */
    const char *yaml =
        "mission: {name: out}\n" FLAT_WORLD
        "parameters: {start_h: 0, start_vel: 0, start_fpa_deg: 90}\n"
        "stages: [{name: s, dry_mass: 20000, propellant_mass: 20000,\n"
        "          engines: [{name: k, count: 3, thrust_vac: 100000, isp_vac: 300}]}]\n"
        "phases:\n"
        "  - {name: P, model: dof3, stages: [s], start_time: 10, stop_time: 20,\n"
        "     engine_out: {time: 2.5, count: 1}, integrator: {tolerance: 1.0e-10}}\n"
        "dispersions:\n"
        "  parameters: {P.engine_out.time: {dist: uniform, min: 1, max: 9}}\n";
    lv_mission *m;
    lv_run *r = run_text("engines_out.yaml", yaml, &m);
    if (r == NULL)
        return lv_mission_free(m);
    const double mdot1 = 100000.0 / (300.0 * G0);
    const lv_result *res = lv_run_rows(r, 0);
    size_t at = 0, n_at = 0;
    for (size_t i = 0; res != NULL && i < lv_result_rows(res); i++)
        if (lv_result_value(res, i, col(res, "time")) == 12.5 && n_at++ == 0)
            at = i;
    CHECK(n_at == 2); /* the rows just before and just after the event, at exactly 12.5 s */
    if (n_at == 2) {
        CHECK(lv_result_value(res, at, col(res, "thrust")) == 300000.0);
        CHECK(lv_result_value(res, at + 1, col(res, "thrust")) == 200000.0);
        CHECK_REL(lv_result_value(res, at, col(res, "mdot")), 3.0 * mdot1, 1e-14);
        CHECK_REL(lv_result_value(res, at + 1, col(res, "mdot")), 2.0 * mdot1, 1e-14);
        CHECK(lv_result_value(res, at + 1, col(res, "engines_running")) == 2.0);
    }
    const lv_phase_result *pr = lv_run_result(r, 0);
    int named = 0;
    for (size_t i = 0; i < pr->report.n_event_log; i++)
        named |= !pr->report.event_log[i].is_state && pr->report.event_log[i].t == 12.5 &&
                 strstr(pr->report.event_log[i].name, "engine-out 1 x 'k'") != NULL;
    CHECK(named);
    CHECK_REL(final(r, 0, "m"), 40000.0 - 3.0 * mdot1 * 2.5 - 2.0 * mdot1 * 7.5, 1e-10);
    /* the time is a run parameter (targeting, dispersions) */
    lv_err err;
    CHECK_OK(lv_run_set(r, "P.engine_out.time", 6.0, &err), &err);
    CHECK_OK(lv_run_execute(r, NULL, &err), &err);
    printf("engine-out: final mass %.6f kg (%.6f) with the engine-out at 6 s\n",
           final(r, 0, "m"), 40000.0 - 3.0 * mdot1 * 6.0 - 2.0 * mdot1 * 4.0);
    CHECK_REL(final(r, 0, "m"), 40000.0 - 3.0 * mdot1 * 6.0 - 2.0 * mdot1 * 4.0, 1e-10);
    /* a Monte Carlo draw of the engine-out time: uniform in [1, 9] s */
    for (uint64_t run = 0; run < 3; run++) {
        double v = NAN;
        CHECK_OK(lv_run_disperse(r, 7, run, &v, &err), &err);
        CHECK_OK(lv_run_execute(r, NULL, &err), &err);
        CHECK(v >= 1.0 && v <= 9.0);
        CHECK_REL(final(r, 0, "m"), 40000.0 - 3.0 * mdot1 * v - 2.0 * mdot1 * (10.0 - v), 1e-10);
    }
    /* a time a run sets beyond the phase's end (a dispersion's tail): a run without the
     * failure, all three engines to the end (docs/monte-carlo.md), not an error */
    CHECK_OK(lv_run_set(r, "P.engine_out.time", 15.0, &err), &err);
    CHECK_OK(lv_run_execute(r, NULL, &err), &err);
    CHECK(lv_run_result(r, 0)->state == LV_PHASE_DONE);
    CHECK_REL(final(r, 0, "m"), 40000.0 - 3.0 * mdot1 * 10.0, 1e-10);
    lv_run_free(r);
    lv_mission_free(m);
}

/* The same in the 6-DoF model: 4 engines of 500 kN at the gimbal point on the body axis, the
 * rigid body held vertical (no aerodynamics, no torque), two engines out 1.5 s after the start. */
static void test_engine_out_dof6(void)
{
    const char *yaml =
        "mission: {name: out6}\n" FLAT_WORLD
        "parameters: {start_h: 0, start_vel: 0, start_fpa_deg: 90}\n"
        "stages:\n"
        "  - {name: s1, dry_mass: 20000, propellant_mass: 100000,\n"
        "     engines: [{name: e, count: 4, thrust_vac: 5.0e5, isp_vac: 300}],\n"
        "     rigid_body: {inertia_full: {xx: 2.0e5, yy: 8.0e6, zz: 8.0e6},\n"
        "                  cg_full: {x: -15}, engine_position: {x: -30}}}\n"
        "phases:\n"
        "  - {name: P, model: dof6, stages: [s1], stop_time: 4, attitude: {theta_deg: 90},\n"
        "     engine_out: {time: 1.5, count: 2}, integrator: {tolerance: 1.0e-10}}\n";
    lv_mission *m;
    lv_run *r = run_text("engines_out6.yaml", yaml, &m);
    if (r == NULL)
        return lv_mission_free(m);
    const double mdot1 = 5.0e5 / (300.0 * G0);
    const lv_result *res = lv_run_rows(r, 0);
    size_t at = 0, n_at = 0;
    for (size_t i = 0; res != NULL && i < lv_result_rows(res); i++)
        if (lv_result_value(res, i, col(res, "time")) == 1.5 && n_at++ == 0)
            at = i;
    CHECK(n_at == 2);
    if (n_at == 2) {
        CHECK(lv_result_value(res, at, col(res, "thrust")) == 2.0e6);
        CHECK(lv_result_value(res, at + 1, col(res, "thrust")) == 1.0e6);
    }
    printf("engine-out dof6: final mass %.6f kg (%.6f)\n", final(r, 0, "m"),
           120000.0 - 4.0 * mdot1 * 1.5 - 2.0 * mdot1 * 2.5);
    CHECK_REL(final(r, 0, "m"), 120000.0 - 4.0 * mdot1 * 1.5 - 2.0 * mdot1 * 2.5, 1e-10);
    lv_run_free(r);
    lv_mission_free(m);
}

/* ---- (b') a throttle schedule the engines cannot follow (issue 27, M4) --------------------- */

/* The first state event `name` of phase 0 at or after t_from: its time and direction (NAN, 0:
 * none). */
static double event_at(const lv_run *r, const char *name, double t_from, int *dir)
{
    const lv_phase_result *pr = lv_run_result(r, 0);
    for (size_t i = 0; i < pr->report.n_event_log; i++) {
        const lv_event_record *e = &pr->report.event_log[i];
        if (e->is_state && e->index >= 0 && (size_t)e->index < pr->n_event_names &&
            strcmp(pr->event_names[e->index], name) == 0 && e->t >= t_from) {
            *dir = e->direction;
            return e->t;
        }
    }
    *dir = 0;
    return NAN;
}

/* An inputs table's throttle, linear between (0 s, 1), (5 s, 0.2), (10 s, 0.2), (15 s, 1),
 * (20 s, 1.4), on one engine of range [0.4, 1]: c(t) = 1 - 0.16 t falls through 0.4 at
 * t = 0.6 / 0.16 = 3.75 s and c(t) = 0.2 + 0.16 (t - 10) comes back at 11.25 s; above 1 from
 * 15 s on. The events sit 1e-9 beyond the limits (docs/guidance.md, "Saturation"): at 3.75 +
 * 1e-9 / 0.16 s, 11.25 - 1e-9 / 0.16 s and 15 + 1e-9 / 0.08 s. Between them the engine gives
 * T_min = 0.4 F_vac in vacuum while the table asks for less; the same in dof3 and dof6. */
static void test_table_saturation(void)
{
    write_file("engines_thr.csv", "time [s],throttle [1]\n0,1\n5,0.2\n10,0.2\n15,1\n20,1.4\n");
    const char *yaml[2] = {
        "mission: {name: sat-table}\n" FLAT_WORLD
        "parameters: {start_h: 1000, start_vel: 0, start_fpa_deg: 90}\n"
        "stages: [{name: s, dry_mass: 20000, propellant_mass: 10000,\n"
        "          engines: [{name: e, thrust_vac: 600000, isp_vac: 300, throttle_min: 0.4}]}]\n"
        "phases:\n"
        "  - {name: P, model: dof3, stages: [s], stop_time: 20, inputs: {table: engines_thr.csv},\n"
        "     integrator: {tolerance: 1.0e-10, output_interval: 0.05}}\n",
        "mission: {name: sat-table6}\n" FLAT_WORLD
        "parameters: {start_h: 1000, start_vel: 0, start_fpa_deg: 90}\n"
        "stages: [{name: s, dry_mass: 20000, propellant_mass: 10000,\n"
        "          engines: [{name: e, thrust_vac: 600000, isp_vac: 300, throttle_min: 0.4}],\n"
        "          rigid_body: {inertia_full: {xx: 2.0e5, yy: 8.0e6, zz: 8.0e6},\n"
        "                       cg_full: {x: -15}, engine_position: {x: -30}}}]\n"
        "phases:\n"
        "  - {name: P, model: dof6, stages: [s], stop_time: 20, inputs: {table: engines_thr.csv},\n"
        "     attitude: {theta_deg: 90}, integrator: {tolerance: 1.0e-10, output_interval: 0.05}}\n"};
    const double t_want[3] = {3.75 + 1e-9 / 0.16, 11.25 - 1e-9 / 0.16, 15.0 + 1e-9 / 0.08};
    for (int six = 0; six < 2; six++) {
        lv_mission *m;
        lv_run *r = run_text("engines_sat.yaml", yaml[six], &m);
        if (r == NULL) {
            lv_mission_free(m);
            continue;
        }
        int d0, d1, d2;
        const double t0 = event_at(r, "throttle_min", 0.0, &d0);
        const double t1 = event_at(r, "throttle_min", t0 + 1e-3, &d1);
        const double t2 = event_at(r, "throttle_max", 0.0, &d2);
        printf("table saturation (%s): throttle_min at %.9f s (%d), back at %.9f s (%d), "
               "throttle_max at %.9f s (%d)\n", six ? "dof6" : "dof3", t0, d0, t1, d1, t2, d2);
        CHECK_CLOSE(t0, t_want[0], 1e-7);
        CHECK(d0 == -1);
        CHECK_CLOSE(t1, t_want[1], 1e-7);
        CHECK(d1 == 1);
        CHECK_CLOSE(t2, t_want[2], 1e-7);
        CHECK(d2 == -1);
        /* within: the table's throttle in throttle_in, the engine's minimum (maximum) given */
        const lv_result *res = lv_run_rows(r, 0);
        int n_lo = 0, n_hi = 0, bad = 0;
        const size_t c_t = res ? col(res, "time") : 0, c_in = res ? col(res, "throttle_in") : 0;
        const size_t c_eff = res ? col(res, "throttle_eff") : 0, c_f = res ? col(res, "thrust") : 0;
        for (size_t i = 0; res != NULL && i < lv_result_rows(res); i++) {
            const double t = lv_result_value(res, i, c_t), in = lv_result_value(res, i, c_in);
            const double want_in = t <= 5.0 ? 1.0 - 0.16 * t : t <= 10.0 ? 0.2
                                   : t <= 15.0 ? 0.2 + 0.16 * (t - 10.0) : 1.0 + 0.08 * (t - 15.0);
            bad += fabs(in - want_in) > 1e-12;
            if (t > 3.76 && t < 11.24) {
                n_lo++;
                bad += lv_result_value(res, i, c_eff) != 0.4;
                bad += fabs(lv_result_value(res, i, c_f) - 0.4 * 600000.0) > 1e-6;
            } else if (t > 15.01) {
                n_hi++;
                bad += lv_result_value(res, i, c_eff) != 1.0;
                bad += fabs(lv_result_value(res, i, c_f) - 600000.0) > 1e-6;
            }
        }
        CHECK(n_lo > 100 && n_hi > 50 && bad == 0);
        lv_run_free(r);
        lv_mission_free(m);
    }
    remove("engines_sat.yaml");
    remove("engines_thr.csv");
}

/* ---- (d) bad values ---------------------------------------------------------------------- */

/* A mission whose phase P carries `extra` (line 8 of the file) must fail naming `want`. */
static void load_fails(const char *extra, const char *want)
{
    char yaml[2048];
    snprintf(yaml, sizeof yaml,
             "mission: {name: t}\n"
             "environment: {world: planet}\n"
             "stages:\n"
             "  - {name: s, dry_mass: 10, propellant_mass: 5, engines: [{name: a, count: 3,\n"
             "     thrust_vac: 1000, isp_vac: 300}, {name: v, count: 2, "
             "thrust_vac: 10, mdot: 1}]}\n"
             "  - {name: one, dry_mass: 10, propellant_mass: 5, engines: [{name: o, count: 3,\n"
             "     thrust_vac: 1000, isp_vac: 300}]}\n"
             "  - {name: dry, dry_mass: 10, propellant_mass: 0}\n"
             "phases:\n"
             "  - {name: P, model: dof3, stop_time: 10,\n"
             "     %s}\n",
             extra);
    write_file("bad_engines.yaml", yaml);
    lv_mission *m = NULL;
    lv_err err;
    lv_status st = lv_mission_load("bad_engines.yaml", &m, &err);
    CHECK(st != LV_OK && m == NULL);
    /* the file and the phase's line (11) */
    if (st != LV_OK && (strstr(err.msg, want) == NULL ||
                        strstr(err.msg, "bad_engines.yaml:11:") == NULL)) {
        fprintf(stderr, "  [%s]\n  got:  %s\n  want: %s\n", extra, err.msg, want);
        CHECK(0);
    }
    lv_mission_free(m);
}

static void test_refused(void)
{
    load_fails("stages: [one], engines: 4",
               "phase 'P': engines: 4 engines cannot run: stage 'one' has 3 of engine 'o'");
    load_fails("stages: [one], engines: -1", "engines: an integer >= 0 expected, found -1");
    load_fails("stages: [one], engines: 1.5", "engines: an integer >= 0 expected, found 1.5");
    load_fails("stages: [one], engines: three", "engines");
    load_fails("stages: [dry], engines: 1",
               "phase 'P': engines: stage 'dry' (the phase's bottom stage, whose engines burn) "
               "has no engines");
    load_fails("stages: [s], engines: 2", "stage 's' has 2 kinds of engines");
    load_fails("stages: [s], engines: {a: 2}", "how many of 'v' run is not given");
    load_fails("stages: [s], engines: {a: 2, w: 1}", "stage 's' has no engine 'w'");
    load_fails("stages: [s], engines: {a: 2, v: 3}",
               "engines.v: 3 engines cannot run: stage 's' has 2 of engine 'v'");
    load_fails("stages: [one], engines: 1, engine_out: {time: 3, count: 2}",
               "engine_out: 2 engines of 'o' stop, but only 1 runs in this phase");
    load_fails("stages: [one], engine_out: [{time: 3, count: 2}, {time: 4, count: 2}]",
               "engine_out: 4 engines of 'o' stop, but only 3 run in this phase");
    load_fails("stages: [one], engine_out: {time: 0}", "time");
    load_fails("stages: [one], engine_out: {count: 1}", "missing required key 'time'");
    load_fails("stages: [s], engine_out: {time: 2}", "'engine' is missing");
    load_fails("stages: [s], engine_out: {time: 2, engine: x}", "stage 's' has no engine 'x'");
    load_fails("stages: [one], engine_out: {time: 2, when: 3}", "when");
    /* issue 27 (M4): a constant throttle the engines cannot give, refused at the value (line
     * 11, column 6 + the text before it); a kind that does not run does not limit it */
    load_fails("stages: [one], inputs: {throttle: 1.5}",
               "bad_engines.yaml:11:40: phase 'P': inputs: throttle = 1.5 is outside the "
               "throttle range [0, 1] of engine 'o' (stage 'one')");
    load_fails("stages: [one], throttle: {value: 1.5}",
               "bad_engines.yaml:11:39: phase 'P': throttle: value = 1.5 is outside");
    load_fails("stages: [s], engines: {a: 1, v: 0}, inputs: {throttle: 1.01}",
               "bad_engines.yaml:11:61: phase 'P': inputs: throttle = 1.01 is outside the "
               "throttle range [0, 1] of engine 'a'");
}

/* Issue 27 (M5, L5): an engine-out that would never happen and an unbounded throttle range,
 * refused where the file writes them (`path`:line:column); the same start known only at run
 * time fails the phase when it starts. */
static void load_fails_at(const char *yaml, const char *want)
{
    write_file("bad_engines2.yaml", yaml);
    lv_mission *m = NULL;
    lv_err err;
    CHECK_FAILS(lv_mission_load("bad_engines2.yaml", &m, &err), &err, LV_ERR_INPUT, want);
    lv_mission_free(m);
}

#define TWO_STAGES                                                                         \
    "stages: [{name: s1, dry_mass: 20000, propellant_mass: 1000,\n"                         \
    "          engines: [{name: k, count: 3, thrust_vac: 100000, isp_vac: 300}]},\n"        \
    "         {name: s2, dry_mass: 5000, propellant_mass: 1000,\n"                          \
    "          engines: [{name: u, count: 2, thrust_vac: 20000, isp_vac: 300}]}]\n"

static void test_never(void)
{
    const char *head = "mission: {name: never}\n" FLAT_WORLD
                       "parameters: {start_h: 0, start_vel: 0, start_fpa_deg: 90}\n" TWO_STAGES
                       "phases:\n";
    char yaml[2048];
    /* a root phase from 0 s to 20 s: an engine-out at 20 s or later never happens (line 12,
     * the time's column) */
    snprintf(yaml, sizeof yaml, "%s  - {name: A, model: dof3, stages: [s1, s2], stop_time: 20,\n"
             "     engine_out: {time: 20}}\n", head);
    load_fails_at(yaml, "bad_engines2.yaml:13:25: phase 'A', engine_out: time 20 s after the "
                        "phase's start (at t = 0 s) is at or after its stop_time 20 s");
    /* from start_time 5 s: 15 s after it is the stop_time */
    snprintf(yaml, sizeof yaml, "%s  - {name: A, model: dof3, stages: [s1, s2], start_time: 5,\n"
             "     stop_time: 20, engine_out: {time: 15}}\n", head);
    load_fails_at(yaml, "phase 'A', engine_out: time 15 s after the phase's start (at t = 5 s)");
    /* a child of a parent without end events starts at the parent's stop_time 10 s */
    snprintf(yaml, sizeof yaml, "%s  - {name: A, model: dof3, stages: [s1, s2], stop_time: 10}\n"
             "  - {name: B, model: dof3, stages: [s1, s2], from: A, stop_time: 30,\n"
             "     engine_out: {time: 20.5}}\n", head);
    load_fails_at(yaml, "phase 'B', engine_out: time 20.5 s after the phase's start (at t = 10 s)");
    /* a child of a parent that ends at burnout starts after the parent's start, 0 s */
    snprintf(yaml, sizeof yaml, "%s  - {name: A, model: dof3, stages: [s1, s2], stop_time: 20,\n"
             "     end: [burnout]}\n"
             "  - {name: B, model: dof3, stages: [s2], from: A, stop_time: 30,\n"
             "     engine_out: {time: 31}}\n", head);
    load_fails_at(yaml, "phase 'B', engine_out: time 31 s after the phase's start (after t = 0 s)");
    /* ... and at run time where the start is known: A burns s1's 1000 kg at 3 x 100 kN / (300
     * g0) kg/s, burnout at 1000 300 g0 / 3e5 = g0 s = 9.80665 s; B's engine-out 25 s later
     * would be at 34.8 s, after its stop_time 30 s: B fails naming the place; 15 s flies */
    snprintf(yaml, sizeof yaml, "%s  - {name: A, model: dof3, stages: [s1, s2], stop_time: 20,\n"
             "     end: [burnout]}\n"
             "  - {name: B, model: dof3, stages: [s2], from: A, stop_time: 30,\n"
             "     engine_out: {time: 25}}\n", head);
    lv_mission *m = NULL;
    lv_run *r = NULL;
    lv_err err;
    write_file("engines_never.yaml", yaml);
    CHECK_OK(lv_mission_load("engines_never.yaml", &m, &err), &err);
    if (m != NULL)
        CHECK_OK(lv_run_create(m, &r, &err), &err);
    if (r != NULL) {
        CHECK(lv_run_execute(r, NULL, &err) != LV_OK); /* a phase failed */
        const lv_phase_result *b = lv_run_result(r, 1);
        CHECK(lv_run_result(r, 0)->state == LV_PHASE_DONE);
        CHECK_CLOSE(lv_run_result(r, 0)->t_end, G0, 1e-6);
        CHECK(b->state == LV_PHASE_FAILED);
        CHECK(strstr(b->error, "engines_never.yaml:15:25: phase 'B', engine_out: time 25 s after "
                               "the phase's start (at t = 9.80665") != NULL);
        if (strstr(b->error, "engines_never.yaml:15:25") == NULL)
            fprintf(stderr, "  got: %s\n", b->error);
        CHECK_OK(lv_run_set(r, "B.engine_out.time", 15.0, &err), &err);
        CHECK_OK(lv_run_execute(r, NULL, &err), &err);
        CHECK(lv_run_result(r, 1)->state == LV_PHASE_DONE);
        lv_run_free(r);
    }
    lv_mission_free(m);
    remove("engines_never.yaml");
    /* throttle_max: finite, at most 2 (twice the rated thrust: lv_vehicle.h) */
#define THR(keys)                                                                          \
    snprintf(yaml, sizeof yaml, "mission: {name: t}\n" FLAT_WORLD                          \
             "stages: [{name: s, dry_mass: 10, propellant_mass: 5,\n"                       \
             "          engines: [{name: e, thrust_vac: 1000, isp_vac: 300, %s}]}]\n"       \
             "phases:\n  - {name: A, model: dof3, stages: [s], stop_time: 10}\n", keys)
    THR("throttle_max: 1e9");
    load_fails_at(yaml, "bad_engines2.yaml:7:77: stage 's', engine 'e': throttle_max must be > 0 "
                        "and <= 2, found 1e+09");
    THR("throttle_max: .inf");
    load_fails_at(yaml, "bad_engines2.yaml:7:77: stage 's', engine 'e': throttle_max: non-finite");
    THR("throttle_min: 2.5, throttle_max: 2");
    load_fails_at(yaml, "throttle_min must be >= 0 and <= 2, found 2.5");
    THR("throttle_min: 0.9, throttle_max: 0.5");
    load_fails_at(yaml, "throttle_min 0.9 is above throttle_max 0.5");
#undef THR
    remove("bad_engines2.yaml");
}

/* A throttle nobody wrote is full throttle held within the engines' range: an engine that runs
 * only between 1.5 and 2 times its rated thrust flies at 1.5 F (it was refused: "throttle = 1
 * is outside the limits [1.5, 2]", a value the file never wrote), one limited to 0.5 at 0.5 F. */
static void test_default_throttle(void)
{
    static const char *const range[2] = {"throttle_min: 1.5, throttle_max: 2", "throttle_max: 0.5"};
    static const double want[2] = {1.5, 0.5};
    for (int k = 0; k < 2; k++) {
        char yaml[1024];
        snprintf(yaml, sizeof yaml,
                 "mission: {name: thr}\n" FLAT_WORLD
                 "parameters: {start_h: 0, start_vel: 0, start_fpa_deg: 90}\n"
                 "stages: [{name: s, dry_mass: 20000, propellant_mass: 20000,\n"
                 "          engines: [{thrust_vac: 1.0e6, isp_vac: 300, %s}]}]\n"
                 "phases:\n"
                 "  - {name: P, model: dof3, stages: [s], stop_time: 1}\n", range[k]);
        lv_mission *m;
        lv_run *r = run_text("engines_default.yaml", yaml, &m);
        if (r == NULL) {
            lv_mission_free(m);
            continue;
        }
        CHECK(final(r, 0, "thrust") == want[k] * 1.0e6);
        lv_run_free(r);
        lv_mission_free(m);
    }
}

int main(void)
{
    test_default_throttle();
    test_count();
    test_count_runway();
    test_landing_min();
    test_engine_out();
    test_engine_out_dof6();
    test_table_saturation();
    test_refused();
    test_never();
    return check_report("test_engines");
}
