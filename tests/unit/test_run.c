/* test_run.c - one mission, many runs (lv_run): parameters set by name, only the phases whose
 * inputs changed run again (with their descendants), and a mission shared by threads gives,
 * run for run, bit for bit what fresh loads give. The mission: the paper's test case
 * (examples/paper-test-case), whose phase tree is
 *        P1 (stages 1+2+3) --+-- P2 (stages 2+3) --+-- P3 (stage 3)
 *                            |                     +-- P5 (stage 2)
 *                            +-- P4 (stage 1)                                            */
#define _POSIX_C_SOURCE 200809L

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "lvsim/lv_mission.h"

static char path_buf[4096];
static const char *mission_path(void)
{
    const char *root = getenv("LV_SOURCE_DIR");
    snprintf(path_buf, sizeof path_buf, "%s/examples/paper-test-case/mission.yaml",
             root ? root : "..");
    return path_buf;
}

static size_t phase(const lv_mission *m, const char *name)
{
    size_t k = 0;
    lv_err err;
    CHECK_OK(lv_mission_phase_find(m, name, &k, &err), &err);
    return k;
}

/* ---- (b) only what a parameter affects runs again ------------------------------------- */

static void test_dirty_phases(void)
{
    lv_mission *m;
    lv_run *r;
    lv_err err;
    CHECK_OK(lv_mission_load(mission_path(), &m, &err), &err);
    if (m == NULL)
        return;
    CHECK_OK(lv_run_create(m, &r, &err), &err);
    const lv_run_options opt = {.threads = 2, .no_rows = 1};
    CHECK_OK(lv_run_execute(r, &opt, &err), &err);
    CHECK(lv_run_simulated(r) == 5);
    CHECK_OK(lv_run_execute(r, &opt, &err), &err); /* nothing changed */
    CHECK(lv_run_simulated(r) == 0);

    /* (name, value, phases that run again): a branch's own number runs that branch only; a
     * stage's number the phases that carry it and their descendants. */
    static const struct {
        const char *name;
        double value;
        size_t n;
    } cases[] = {
        {"P4.end.impact", 10.0, 1},            /* P4: the booster's ground level */
        {"P5.integrator.tolerance", 1e-8, 1},   /* P5 alone */
        {"P2.stop_time", 281.0, 3},             /* P2 and its children P3, P5 */
        {"stage3.propellant_mass", 2600.0, 5},  /* P1 carries stage 3: everything */
        {"stage1.dry_mass", 3100.0, 5},         /* P1 and P4 carry stage 1: everything */
        {"start_z", 1.0, 5},                    /* the parameter set: the root and the rest */
        {"P3.stop_time", 600.0, 0},             /* the value it has: nothing */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        CHECK_OK(lv_run_set(r, cases[i].name, cases[i].value, &err), &err);
        CHECK_OK(lv_run_execute(r, &opt, &err), &err);
        if (lv_run_simulated(r) != cases[i].n)
            fprintf(stderr, "%s: %zu phases ran again, expected %zu\n", cases[i].name,
                    lv_run_simulated(r), cases[i].n);
        CHECK(lv_run_simulated(r) == cases[i].n);
    }
    /* the run's results are those of a fresh run with the same values */
    lv_run *fresh;
    CHECK_OK(lv_run_create(m, &fresh, &err), &err);
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        CHECK_OK(lv_run_set(fresh, cases[i].name, cases[i].value, &err), &err);
    CHECK_OK(lv_run_execute(fresh, &opt, &err), &err);
    for (size_t k = 0; k < lv_mission_phase_count(m); k++) {
        const lv_phase_result *a = lv_run_result(r, k), *b = lv_run_result(fresh, k);
        CHECK(a->state == LV_PHASE_DONE && b->state == LV_PHASE_DONE);
        CHECK(a->n_final == b->n_final &&
              memcmp(a->final_values, b->final_values, a->n_final * sizeof(double)) == 0);
    }
    /* the P4 end value shows in its result: impact at 10 m */
    double z;
    CHECK_OK(lv_run_final(r, phase(m, "P4"), "z", &z, &err), &err);
    CHECK_CLOSE(z, 10.0, 1e-6);
    CHECK(lv_run_result(r, phase(m, "P4"))->end_value == 10.0);
    lv_run_free(fresh);

    /* names and values that are refused, with the reason */
    CHECK(lv_run_set(r, "stage1.propelant_mass", 1.0, &err) == LV_ERR_NOTFOUND);
    CHECK(strstr(err.msg, "did you mean 'stage1.propellant_mass'") != NULL);
    CHECK(lv_run_set(r, "stage1.dry_mass", -5.0, &err) == LV_ERR_INPUT);
    CHECK(strstr(err.msg, "stage1.dry_mass = -5 kg: must be >= 0 kg") != NULL);
    CHECK(lv_run_set(r, "P1.integrator.tolerance", 0.0, &err) == LV_ERR_INPUT);
    CHECK(lv_run_set(r, "start_z", NAN, &err) == LV_ERR_INPUT);
    /* an angle in degrees: start_fpa_deg 45 is start_fpa pi/4 */
    CHECK_OK(lv_run_set(r, "start_fpa_deg", 45.0, &err), &err);
    double fpa, fpa_deg;
    CHECK_OK(lv_run_get(r, "start_fpa", &fpa, &err), &err);
    CHECK_OK(lv_run_get(r, "start_fpa_deg", &fpa_deg, &err), &err);
    CHECK_CLOSE(fpa, M_PI / 4.0, 1e-15);
    CHECK_CLOSE(fpa_deg, 45.0, 1e-12);
    CHECK(lv_run_set(r, "stage1.dry_mass_deg", 1.0, &err) == LV_ERR_NOTFOUND); /* not an angle */
    /* back to the file's values: everything that changed runs again */
    lv_run_reset(r);
    CHECK_OK(lv_run_get(r, "stage1.dry_mass", &z, &err), &err);
    CHECK(z == 3000.0);

    /* a child cannot be prepared before its parent has run in this run */
    lv_run *r2;
    lv_phase_call *call = NULL;
    CHECK_OK(lv_run_create(m, &r2, &err), &err);
    CHECK(lv_run_prepare(r2, phase(m, "P2"), &call, &err) == LV_ERR_INPUT && call == NULL);
    CHECK(strstr(err.msg, "needs its parent 'P1'") != NULL);
    lv_run_free(r2);
    lv_run_free(r);
    lv_mission_free(m);
}

/* ---- (a) one mission, two threads, 1000 runs = 1000 fresh loads ------------------------- */

#define N_RUNS 1000
#define N_PHASES 5
#define N_FINAL 32 /* time, 13 states, 6 outputs of flat6: 20; room to spare */

/* Run i's overrides: three numbers that move every phase. */
static void overrides(int i, const char **names, double *values)
{
    names[0] = "stage1.propellant_mass";
    values[0] = 27000.0 - 7.0 * (i % 50);
    names[1] = "P2.stop_time";
    values[1] = 275.0 + 0.25 * (i % 40);
    names[2] = "stage3.dry_mass";
    values[2] = 300.0 + (double)(i % 13);
}

static double results_threads[N_RUNS][N_PHASES][N_FINAL];
static double results_fresh[N_RUNS][N_PHASES][N_FINAL];

/* Runs i's overrides on run r and copies every phase's final values into out. */
static int run_and_copy(lv_run *r, int i, double out[N_PHASES][N_FINAL])
{
    const char *names[3];
    double values[3];
    lv_err err;
    overrides(i, names, values);
    for (int j = 0; j < 3; j++)
        if (lv_run_set(r, names[j], values[j], &err) != LV_OK)
            return -1;
    /* a coarse output grid and no rows in memory: final values are what is compared */
    const lv_run_options opt = {.threads = 1, .no_rows = 1, .output_interval = 20.0};
    if (lv_run_execute(r, &opt, &err) != LV_OK)
        return -1;
    for (size_t k = 0; k < N_PHASES; k++) {
        const lv_phase_result *res = lv_run_result(r, k);
        if (res->n_final > N_FINAL)
            return -1;
        memcpy(out[k], res->final_values, res->n_final * sizeof(double));
    }
    return 0;
}

typedef struct thread_arg {
    const lv_mission *m;
    int first, step, failed;
} thread_arg;

static void *thread_main(void *p)
{
    thread_arg *a = p;
    lv_run *r;
    lv_err err;
    if (lv_run_create(a->m, &r, &err) != LV_OK) {
        a->failed = 1;
        return NULL;
    }
    for (int i = a->first; i < N_RUNS; i += a->step)
        a->failed |= run_and_copy(r, i, results_threads[i]) != 0;
    lv_run_free(r);
    return NULL;
}

static void test_threads_vs_fresh(void)
{
    lv_mission *m;
    lv_err err;
    CHECK_OK(lv_mission_load(mission_path(), &m, &err), &err);
    if (m == NULL)
        return;
    CHECK(lv_mission_phase_count(m) == N_PHASES);
    memset(results_threads, 0, sizeof results_threads);
    thread_arg args[2] = {{m, 0, 2, 0}, {m, 1, 2, 0}};
    pthread_t t[2];
    for (int j = 0; j < 2; j++)
        CHECK(pthread_create(&t[j], NULL, thread_main, &args[j]) == 0);
    for (int j = 0; j < 2; j++)
        pthread_join(t[j], NULL);
    CHECK(!args[0].failed && !args[1].failed);
    lv_mission_free(m);

    int same = 0;
    for (int i = 0; i < N_RUNS; i++) {
        lv_mission *fm;
        lv_run *r;
        memset(results_fresh[i], 0, sizeof results_fresh[i]);
        if (lv_mission_load(mission_path(), &fm, &err) != LV_OK ||
            lv_run_create(fm, &r, &err) != LV_OK) {
            CHECK_OK(LV_ERR_INPUT, &err);
            return;
        }
        CHECK(run_and_copy(r, i, results_fresh[i]) == 0);
        same += memcmp(results_threads[i], results_fresh[i], sizeof results_fresh[i]) == 0;
        lv_run_free(r);
        lv_mission_free(fm);
    }
    printf("%d of %d runs from one mission in two threads equal fresh loads bit for bit\n",
           same, N_RUNS);
    CHECK(same == N_RUNS);
    /* and the overrides did change the results: run 0 and run 1 differ */
    CHECK(memcmp(results_fresh[0], results_fresh[1], sizeof results_fresh[0]) != 0);
}

/* ---- lv_run_invalidate and lv_run_stale: results out of date, and forced to run again ---- */

static void test_invalidate_stale(void)
{
    lv_mission *m;
    lv_run *r;
    lv_err err;
    CHECK_OK(lv_mission_load(mission_path(), &m, &err), &err);
    if (m == NULL)
        return;
    CHECK_OK(lv_run_create(m, &r, &err), &err);
    const size_t p1 = phase(m, "P1"), p2 = phase(m, "P2"), p3 = phase(m, "P3"),
                 p4 = phase(m, "P4"), p5 = phase(m, "P5");
    CHECK(lv_run_stale(r, p1) && lv_run_stale(r, p3)); /* never run */
    const lv_run_options opt = {.threads = 2, .no_rows = 1};
    CHECK_OK(lv_run_execute(r, &opt, &err), &err);
    for (size_t k = 0; k < 5; k++)
        CHECK(!lv_run_stale(r, k));
    CHECK(!lv_run_stale(r, 99));
    /* a parameter of P2: P2 and its descendants are out of date, the others are not */
    CHECK_OK(lv_run_set(r, "P2.stop_time", 281.0, &err), &err);
    CHECK(!lv_run_stale(r, p1) && lv_run_stale(r, p2) && lv_run_stale(r, p3) &&
          lv_run_stale(r, p5) && !lv_run_stale(r, p4));
    CHECK(lv_run_result(r, p3)->state == LV_PHASE_DONE); /* still readable */
    CHECK_OK(lv_run_execute(r, &opt, &err), &err);
    CHECK(lv_run_simulated(r) == 3);
    CHECK(!lv_run_stale(r, p3));
    /* one phase invalidated: it and its descendants run again */
    CHECK_OK(lv_run_invalidate(r, p2, &err), &err);
    CHECK(lv_run_stale(r, p5) && !lv_run_stale(r, p4));
    CHECK_OK(lv_run_execute(r, &opt, &err), &err);
    CHECK(lv_run_simulated(r) == 3);
    /* every phase */
    CHECK_OK(lv_run_invalidate(r, LV_RUN_ALL_PHASES, &err), &err);
    CHECK(lv_run_stale(r, p1) && lv_run_stale(r, p4));
    CHECK_OK(lv_run_execute(r, &opt, &err), &err);
    CHECK(lv_run_simulated(r) == 5);
    /* a stop flag set: nothing starts, the run is cancelled; cleared: everything runs */
    CHECK_OK(lv_run_invalidate(r, LV_RUN_ALL_PHASES, &err), &err);
    volatile int stop = 1;
    const lv_run_options sopt = {.threads = 2, .no_rows = 1, .stop = &stop};
    CHECK(lv_run_execute(r, &sopt, &err) == LV_ERR_CANCELLED);
    CHECK(lv_run_result(r, p1)->state == LV_PHASE_FAILED &&
          strstr(lv_run_result(r, p1)->error, "stopped") != NULL &&
          lv_run_result(r, p3)->state == LV_PHASE_SKIPPED);
    stop = 0;
    CHECK_OK(lv_run_execute(r, &sopt, &err), &err);
    CHECK(lv_run_simulated(r) == 5);
    CHECK(lv_run_invalidate(r, 5, &err) == LV_ERR_INPUT);
    CHECK(strstr(err.msg, "out of range") != NULL);
    lv_run_free(r);
    lv_mission_free(m);
}

/* ---- (d) the row limit: refused up front, or held as the phase runs --------------------- */

/* No run of digits longer than a count written exactly below ten million: "1e+30", never
 * 1000000000000000019884624838656. */
static int readable(const char *msg)
{
    int run = 0;
    for (const char *c = msg; *c; c++) {
        run = *c >= '0' && *c <= '9' ? run + 1 : 0;
        if (run > 8)
            return 0;
    }
    return 1;
}

static void test_row_limit(void)
{
    lv_mission *m;
    lv_run *r;
    lv_err err;
    CHECK_OK(lv_mission_load(mission_path(), &m, &err), &err);
    if (m == NULL)
        return;
    CHECK_OK(lv_run_create(m, &r, &err), &err);
    const size_t p1 = phase(m, "P1"), p2 = phase(m, "P2"), p4 = phase(m, "P4");
    /* P1: 0 .. 140 s, a row every 0.5 s: 140 / 0.5 + 1 = 281 rows, only its stop time ends
     * it. P4 (the booster's fall, end: [impact], a row every 2 s) starts after P1, at 0 s at
     * the earliest before P1 ran: 1500 / 2 + 1 = 751 rows by its stop time, not a bound. */
    lv_output_estimate e;
    CHECK_OK(lv_run_estimate_output(r, p1, 0.0, &e, &err), &err);
    CHECK(e.rows == 281.0 && e.bounded == 1);
    CHECK_CLOSE(e.duration, 140.0, 0.0);
    CHECK_OK(lv_run_estimate_output(r, p4, 0.0, &e, &err), &err);
    CHECK(e.rows == 751.0 && e.bounded == 0);
    /* P1 refused above its 281 rows before anything runs */
    lv_run_options opt = {.threads = 1, .no_rows = 1, .max_rows = 280.0};
    CHECK(lv_run_check_output(r, &opt, &err) == LV_ERR_INPUT);
    CHECK(strstr(err.msg, "phase 1 'P1' would write up to 281 rows (140 s of mission time, a "
                          "row every 0.5 s;") != NULL);
    CHECK(strstr(err.msg, "more than the limit of 280 rows per phase") != NULL);
    /* and its children, at least from P1's stop time: P2 140 .. 280 s, P3 280 .. 600 s */
    CHECK(strstr(err.msg, "phases 2 'P2' (281 rows), 3 'P3' (641 rows) are over it too") !=
          NULL);
    CHECK(strstr(err.msg, "raise the limit to 641 rows") != NULL);
    CHECK(lv_run_execute(r, &opt, &err) == LV_ERR_INPUT);
    CHECK(lv_run_result(r, p1)->state == LV_PHASE_PENDING); /* nothing ran */
    /* P2 at a row every 0.25 s: it starts when P1 ends, at 140 s at the latest (P1's stop
     * time: only it ends P1), and stops at 280 s: at least 140 / 0.25 + 1 = 561 rows, known
     * before P1 runs (counted from 0 s, its earliest start, it would be 1121 rows: the count
     * issue 22's breaker saw refuse runs that fit, in the wrong direction) */
    CHECK_OK(lv_run_set(r, "P2.integrator.output_interval", 0.25, &err), &err);
    CHECK_OK(lv_run_estimate_output(r, p2, 0.0, &e, &err), &err);
    CHECK(e.rows == 1121.0 && e.bounded == 0);
    opt.max_rows = 700.0;
    CHECK_OK(lv_run_check_output(r, &opt, &err), &err); /* P3 has 641 rows at 0.5 s */
    opt.max_rows = 300.0;
    CHECK(lv_run_check_output(r, &opt, &err) == LV_ERR_INPUT);
    CHECK(strstr(err.msg, "phase 2 'P2' would write at least 561 rows (from its parent's stop "
                          "time to its own, a row every 0.25 s;") != NULL);
    CHECK(strstr(err.msg, "phase 3 'P3' (641 rows) is over it too") != NULL);
    CHECK(strstr(err.msg, "raise the limit to 641 rows") != NULL);
    /* a limit of 561 lets it run, P2 wanted alone: 561 rows, as counted (its child P3 would
     * write 641 rows, 280 .. 600 s at 0.5 s) */
    opt.max_rows = 561.0;
    unsigned char want2[N_PHASES] = {0};
    want2[p2] = 1;
    opt.want = want2;
    CHECK_OK(lv_run_execute(r, &opt, &err), &err);
    CHECK(lv_run_result(r, p2)->state == LV_PHASE_DONE);
    CHECK(lv_run_result(r, p2)->report.stats.output_rows >= 561); /* + its events' rows */
    CHECK_OK(lv_run_estimate_output(r, p2, 0.0, &e, &err), &err); /* now from P1's end */
    CHECK(e.rows == 561.0 && e.bounded == 1);
    opt.want = NULL;
    lv_run_free(r); /* a fresh run: nothing ran */
    CHECK_OK(lv_run_create(m, &r, &err), &err);
    opt.max_rows = 300.0;
    /* wanted P4 only: P1 (281) is within the limit, P4 is not refused for its stop time */
    unsigned char want[N_PHASES] = {0};
    want[p4] = 1;
    opt.want = want;
    CHECK_OK(lv_run_check_output(r, &opt, &err), &err);
    /* ... but held as it runs: every phase at a row every 0.5 s (P1 still 281 rows), P4 stops
     * when it would write row 301, at t = 140 + 300 * 0.5 = 290 s, before its impact (594.6 s:
     * `lvsim run` of the example) */
    opt.output_interval = 0.5;
    CHECK(lv_run_execute(r, &opt, &err) == LV_ERR_SOLVER);
    const lv_phase_result *res = lv_run_result(r, p4);
    CHECK(lv_run_result(r, p1)->state == LV_PHASE_DONE);
    CHECK(res->state == LV_PHASE_FAILED);
    CHECK(strstr(res->error, "phase 'P4': stopped at t = 290 s by the row limit: 300 output "
                             "rows") != NULL);
    printf("row limit as it runs: %s\n", res->error);
    /* without the limit it reaches its impact: a limit of exactly its rows lets it */
    opt.max_rows = 0.0;
    CHECK_OK(lv_run_execute(r, &opt, &err), &err);
    const double t0 = res->t_start, t1 = res->t_end;
    CHECK(res->end_index == 0); /* the impact */
    const double rows = floor((t1 - t0) / 0.5) + 1.0; /* grid rows t0 + 0.5 k <= t1 */
    lv_run_invalidate(r, p4, &err);
    opt.max_rows = rows;
    CHECK_OK(lv_run_execute(r, &opt, &err), &err);
    CHECK(res->state == LV_PHASE_DONE && res->t_end == t1);
    lv_run_invalidate(r, p4, &err);
    opt.max_rows = rows - 1.0;
    CHECK(lv_run_execute(r, &opt, &err) == LV_ERR_SOLVER);
    CHECK(res->state == LV_PHASE_FAILED);
    lv_run_free(r);
    lv_mission_free(m);

    /* a generous stop time: refused with a readable count when only it ends the phase; a
     * `time` end bounds the phase as exactly (100 s: 101 rows); burnout does not, and is
     * accepted */
    char dir[] = "/tmp/lv_rows_XXXXXX", path[64];
    CHECK(mkdtemp(dir) != NULL);
    snprintf(path, sizeof path, "%s/m.yaml", dir);
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (f == NULL)
        return;
    fputs("mission: {name: rows}\n"
          "environment: {world: flat, g: 9.81}\n"
          "parameters: {start_theta_deg: 90}\n"
          "stages:\n"
          "  - {name: s1, dry_mass: 1000, propellant_mass: 4000,\n"
          "     engines: [{name: e1, thrust_vac: 100000, isp_vac: 300}]}\n"
          "  - {name: s2, dry_mass: 1000, propellant_mass: 4000,\n"
          "     engines: [{name: e2, thrust_vac: 100000, isp_vac: 300}]}\n"
          "  - {name: s3, dry_mass: 1000, propellant_mass: 4000,\n"
          "     engines: [{name: e3, thrust_vac: 100000, isp_vac: 300}]}\n"
          "  - {name: s4, dry_mass: 1000, propellant_mass: 4000,\n"
          "     engines: [{name: e4, thrust_vac: 100000, isp_vac: 300}]}\n"
          "phases:\n"
          "  - {name: timed, model: flat6, stages: [s1], stop_time: 1e30, end: [{time: 100}],\n"
          "     integrator: {output_interval: 1.0}}\n"
          "  - {name: burn, model: flat6, stages: [s2], stop_time: 1e30, end: [burnout],\n"
          "     integrator: {output_interval: 1.0}}\n"
          "  - {name: open, model: flat6, stages: [s3], stop_time: 1e30,\n"
          "     integrator: {output_interval: 1.0}}\n"
          "  - {name: burn2, model: flat6, stages: [s4], stop_time: 300, end: [burnout],\n"
          "     integrator: {output_interval: 1.0}}\n"
          "  - {name: after, model: flat6, stages: [s4], from: burn2, stop_time: 400,\n"
          "     integrator: {output_interval: 0.5}}\n",
          f);
    fclose(f);
    CHECK_OK(lv_mission_load(path, &m, &err), &err);
    if (m != NULL) {
        CHECK_OK(lv_run_create(m, &r, &err), &err);
        CHECK_OK(lv_run_estimate_output(r, 0, 0.0, &e, &err), &err);
        CHECK(e.rows == 101.0 && e.bounded == 1 && e.duration == 100.0);
        CHECK_OK(lv_run_estimate_output(r, 1, 0.0, &e, &err), &err);
        CHECK(e.rows == 1e30 + 1.0 && e.bounded == 0);
        unsigned char w2[5] = {1, 1, 0, 0, 0};
        lv_run_options o2 = {.threads = 1, .no_rows = 1, .max_rows = 1e6, .want = w2};
        CHECK_OK(lv_run_check_output(r, &o2, &err), &err);
        /* the burn ends at burnout, t = m_p Isp g0 / F = 4000 * 300 * 9.80665 / 1e5 s */
        CHECK_OK(lv_run_execute(r, &o2, &err), &err);
        CHECK_CLOSE(lv_run_result(r, 1)->t_end, 4000.0 * 300.0 * 9.80665 / 1e5, 1e-6);
        CHECK_CLOSE(lv_run_result(r, 0)->t_end, 100.0, 0.0);
        o2.want = NULL;
        CHECK(lv_run_check_output(r, &o2, &err) == LV_ERR_INPUT);
        CHECK(strstr(err.msg, "phase 3 'open' would write up to 1e+30 rows (1e+30 s of mission "
                              "time") != NULL);
        CHECK(readable(err.msg));
        CHECK(strstr(err.msg, "raise the limit") == NULL); /* beyond any sensible limit */
        printf("refused: %s\n", err.msg);
        /* `after` starts when burn2 ends (burnout at 117.7 s, not its stop time 300 s): at
         * least (400 - 300) / 0.5 + 1 = 201 rows before burn2 runs, its true count known only
         * then: (400 - 117.68) / 0.5 -> 565 intervals, 566 rows. Under a limit of 400, burn2
         * (118 rows) runs, and `after` is refused as it would start, unsimulated; burn2's
         * results stay. */
        lv_run_free(r);
        CHECK_OK(lv_run_create(m, &r, &err), &err);
        unsigned char w3[5] = {0, 0, 0, 0, 1};
        lv_run_options o3 = {.threads = 1, .no_rows = 1, .max_rows = 400.0, .want = w3};
        CHECK_OK(lv_run_check_output(r, &o3, &err), &err);
        CHECK(lv_run_execute(r, &o3, &err) == LV_ERR_SOLVER);
        CHECK(lv_run_result(r, 3)->state == LV_PHASE_DONE);
        CHECK(lv_run_result(r, 4)->state == LV_PHASE_FAILED);
        CHECK(lv_run_result(r, 4)->report.stats.steps == 0);
        CHECK(strstr(lv_run_result(r, 4)->error, "phase 5 'after' would write up to 566 rows") !=
              NULL);
        CHECK(strstr(lv_run_result(r, 4)->error, "phase 'after': phase 5") == NULL);
        o3.max_rows = 200.0; /* below its fewest rows: refused before anything runs */
        CHECK(lv_run_check_output(r, &o3, &err) == LV_ERR_INPUT);
        o3.max_rows = 566.0;
        CHECK_OK(lv_run_execute(r, &o3, &err), &err);
        CHECK(lv_run_result(r, 4)->state == LV_PHASE_DONE);
        lv_run_free(r);
        lv_mission_free(m);
    }
    remove(path);
    rmdir(dir);
}

int main(void)
{
    test_dirty_phases();
    test_threads_vs_fresh();
    test_invalidate_stale();
    test_row_limit();
    return check_report("test_run");
}
