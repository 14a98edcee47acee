/* code2_loop.c - the paper's Code 2 (sequentialScript) in C with liblvsim.
 *
 * For each phase of a chain, one lv_simulate() (Dymola's simulateExtendedModel): the first
 * phase starts from the mission's parameter set; every later phase gets the previous phase's
 * final state through initialNames/initialValues = stateNames/out, and returns its own final
 * state in out. As in the paper, the mass is not handed over: each phase model starts with
 * the mass of the stages it carries.
 *
 *     build/examples/code2_loop examples/paper-test-case/mission.yaml P1 P2 P3
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "lvsim/lvsim.h"

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: %s MISSION.yaml PHASE...\n", argv[0]);
        return 2;
    }
    /* stateNames: position, velocity, attitude and rates; not the mass */
    static const char *const state_names[] = {"x", "y", "z", "vx", "vy", "vz", "psi",
                                              "theta", "phi", "p", "q", "r"};
    enum { N_STATES = sizeof state_names / sizeof state_names[0] };
    double out[N_STATES + 1];
    const char *final_names[N_STATES + 1];
    memcpy(final_names, state_names, sizeof state_names);
    final_names[N_STATES] = "time";

    lv_mission *mission;
    lv_err err;
    if (lv_mission_load(argv[1], &mission, &err) != LV_OK) {
        fprintf(stderr, "%s\n", err.msg);
        return 2;
    }
    int rc = 0;
    double t_end = 0.0;
    for (int i = 2; i < argc && rc == 0; i++) {
        size_t k;
        lv_phase_model *pm = NULL;
        if (lv_mission_phase_find(mission, argv[i], &k, &err) != LV_OK ||
            lv_mission_phase_model(mission, k, NULL, &pm, &err) != LV_OK) {
            fprintf(stderr, "%s\n", err.msg);
            rc = 2;
            break;
        }
        /* The model of phase i with its stages full: along P1 -> P2 -> P3 each phase's
         * stages have not burnt yet when it starts (the start values of the redeclared
         * model in Code 2). lv_mission_run() does this bookkeeping for any tree. */
        lv_sim_settings s;
        lv_mission_phase_settings(mission, k, &s);
        if (isnan(s.start_time))
            s.start_time = t_end; /* phaseTimes[i,1]: the previous phase's end */
        char result[64];
        snprintf(result, sizeof result, "phase_%d", i - 1); /* resultFile = "phase_" + String(i) */
        s.result_file = result;
        s.n_initial = i == 2 ? 0 : N_STATES; /* initialNames = if i == 1 then {} else stateNames */
        s.initial_names = state_names;
        s.initial_values = out;              /* initialValues = if i == 1 then {} else out */
        s.n_final = N_STATES + 1;            /* finalNames = stateNames */
        s.final_names = final_names;
        lv_sim_report rep;
        lv_status st = lv_simulate(lv_phase_model_def(pm), lv_phase_model_inst(pm), &s, out, &rep,
                                   &err);
        if (st == LV_OK) {
            t_end = out[N_STATES];
            printf("%-4s ok  t = %9.3f .. %9.3f s  z = %12.3f m  vz = %9.3f m/s  -> %s.mat\n",
                   argv[i], s.start_time, t_end, out[2], out[5], result);
        } else {
            fprintf(stderr, "%s: %s\n", argv[i], err.msg);
            rc = 3;
        }
        lv_sim_report_clear(&rep);
        lv_phase_model_free(pm);
    }
    lv_mission_free(mission);
    return rc;
}
