/* bench_mission.c - the paper's Table 2 as a benchmark: the test case
 * (examples/paper-test-case) run sequentially (five 13-state phase models) and as one
 * 39-state end-to-end model, per integration method, at the paper's tolerance 1e-7.
 * Prints states, events, steps, RHS and Jacobian evaluations, CPU time of both, and the
 * ratios sequential / end-to-end (fastest of the repetitions). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "lvsim/lv_mission.h"

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : LV_SOURCE_DIR "/examples/paper-test-case/mission.yaml";
    const char *methods[] = {"dassl", "cvode-adams", "dopri5"};
    const int reps = 15;
    printf("# %s, tolerance 1e-7, output interval 1 s, fastest of %d runs\n", path, reps);
    printf("%-12s %6s %6s %5s %5s %5s %5s %7s %7s %7s %7s %5s %5s %9s %9s %7s %7s\n", "method",
           "n_e2e", "n_seq", "sev_e", "sev_s", "tev_e", "tev_s", "stp_e", "stp_s", "rhs_e",
           "rhs_s", "jac_e", "jac_s", "cpu_e[ms]", "cpu_s[ms]", "cpu s/e", "rhs s/e");
    lv_mission *m = NULL;
    lv_err lerr;
    if (lv_mission_load(path, &m, &lerr) != LV_OK) {
        fprintf(stderr, "bench_mission: %s\n", lerr.msg);
        return 1;
    }
    for (size_t i = 0; i < sizeof methods / sizeof methods[0]; i++) {
        lv_compare_report best, rep;
        double cpu_e = INFINITY, cpu_s = INFINITY;
        for (int r = 0; r < reps; r++) {
            lv_err err;
            if (lv_mission_compare(m, methods[i], 1e-7, 1.0, 0.0, &rep, &err) != LV_OK) {
                fprintf(stderr, "bench_mission: %s\n", err.msg);
                lv_mission_free(m);
                return 1;
            }
            cpu_e = fmin(cpu_e, rep.e2e.cpu_time);
            cpu_s = fmin(cpu_s, rep.seq.cpu_time);
            best = rep;
        }
        printf("%-12s %6zu %6zu %5ld %5ld %5ld %5ld %7ld %7ld %7ld %7ld %5ld %5ld %9.3f %9.3f %7.3f "
               "%7.3f\n",
               methods[i], best.e2e.n_states, best.seq.n_states, best.e2e.state_events,
               best.seq.state_events, best.e2e.time_events, best.seq.time_events, best.e2e.steps,
               best.seq.steps, best.e2e.rhs_evals, best.seq.rhs_evals, best.e2e.jac_evals,
               best.seq.jac_evals, 1e3 * cpu_e, 1e3 * cpu_s, cpu_s / cpu_e,
               (double)best.seq.rhs_evals / (double)best.e2e.rhs_evals);
    }
    printf("# goal (paper): sequential cheaper; with dassl at 1e-7, cpu s/e <= 0.5\n");
    lv_mission_free(m);
    return 0;
}
