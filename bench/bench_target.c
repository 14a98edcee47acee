/* bench_target.c - targeting and optimisation from the shipped start points (issue 13):
 *   kourou-leo-targeted    a guided two-stage ascent into a 200 km circular orbit at 5.2 deg
 *                          (damped Newton); the target: under 2 s wall and fewer than
 *                          200 phase simulations
 *   kourou-rtls-targeted   the same orbit and the booster back on the pad, two branches
 *   delta3-gto             Betts' Delta III to GTO: the final mass maximised (SLSQP), the time
 *                          to the optimum
 * Each problem is loaded once and solved `reps` times from its start (a fresh lv_target each
 * time): wall time and process CPU time of the solve (fastest of the repetitions; the machine
 * may be shared), iterations, executions of the run and phase simulations (the same every
 * time: the solve is deterministic), with the default 2 worker threads and with one. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "lvsim/lv_mission.h"
#include "lvsim/lv_target.h"

static double now(clockid_t clock)
{
    struct timespec ts;
    clock_gettime(clock, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int bench(const char *label, const char *file, int threads, int reps)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/examples/%s", LV_SOURCE_DIR, file);
    lv_mission *m = NULL;
    lv_err err;
    if (lv_mission_load(path, &m, &err) != LV_OK) {
        fprintf(stderr, "bench_target: %s\n", err.msg);
        return 1;
    }
    double wall = INFINITY, cpu = INFINITY;
    lv_target_result r = {0};
    for (int i = 0; i < reps; i++) {
        lv_target *t = NULL;
        const lv_target_result *res = NULL;
        lv_target_settings s;
        lv_target_settings_default(&s);
        s.threads = threads;
        if (lv_target_create(m, &t, &err) != LV_OK) {
            fprintf(stderr, "bench_target: %s\n", err.msg);
            lv_mission_free(m);
            return 1;
        }
        const double w0 = now(CLOCK_MONOTONIC), c0 = now(CLOCK_PROCESS_CPUTIME_ID);
        const lv_status st = lv_target_solve(t, &s, &res, &err);
        const double w1 = now(CLOCK_MONOTONIC), c1 = now(CLOCK_PROCESS_CPUTIME_ID);
        if (st != LV_OK || !res->converged) {
            fprintf(stderr, "bench_target: %s: %s\n", label, st != LV_OK ? err.msg : res->reason);
            lv_target_free(t);
            lv_mission_free(m);
            return 1;
        }
        wall = fmin(wall, w1 - w0);
        cpu = fmin(cpu, c1 - c0);
        r = *res;
        if (i == 0) {
            lv_target_cost_info ci;
            lv_target_cost_info_get(t, &ci);
            char what[96] = "constraints met";
            if (ci.present)
                snprintf(what, sizeof what, "%s = %.3f %s", ci.name, r.cost, ci.unit);
            printf("%-22s %2d %9.3f %9.3f %6zu %6zu %8zu  %-13s %s\n", label, threads, wall, cpu,
                   r.iterations, r.runs, r.phases, r.method, what);
        }
        lv_target_free(t);
    }
    if (reps > 1)
        printf("%-22s %2d %9.3f %9.3f   (fastest of %d)\n", label, threads, wall, cpu, reps);
    lv_mission_free(m);
    return 0;
}

int main(void)
{
    printf("# targeting from the shipped start points: wall and CPU s of the solve, iterations, "
           "runs, phase simulations\n");
    printf("%-22s %2s %9s %9s %6s %6s %8s  %-13s %s\n", "problem", "th", "wall [s]", "cpu [s]",
           "iter", "runs", "phases", "method", "result");
    int rc = 0;
    for (int th = 2; th >= 1; th--) {
        rc |= bench("kourou-leo-targeted", "kourou-leo-targeted/mission.yaml", th, 5);
        rc |= bench("kourou-rtls-targeted", "kourou-rtls-targeted/mission.yaml", th, 5);
        rc |= bench("delta3-gto", "delta3-gto/mission.yaml", th, 1);
    }
    return rc;
}
