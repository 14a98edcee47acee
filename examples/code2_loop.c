/* code2_loop.c - the paper's Code 2 (sequentialScript) in C with liblvsim.
 *
 * For each phase of a chain, one lv_simulate() (Dymola's simulateExtendedModel): the first
 * phase starts from the mission's parameter set; every later phase starts from the previous
 * phase's final state. The hand-off - initialNames/initialValues = the parent's final states,
 * the mass of the stages the phase carries from the stage book, the phase's overrides - comes
 * from lv_run_prepare(), the same call the runner makes; lv_run_complete() hands the outcome
 * back so that the next phase can start from it.
 *
 *     build/examples/code2_loop examples/paper-test-case/mission.yaml P1 P2 P3
 */
#include <stdio.h>

#include "lvsim/lvsim.h"

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: %s MISSION.yaml PHASE...\n", argv[0]);
        return 2;
    }
    lv_mission *mission = NULL;
    lv_run *run = NULL;
    lv_err err;
    if (lv_mission_load(argv[1], &mission, &err) != LV_OK ||
        lv_run_create(mission, &run, &err) != LV_OK) {
        fprintf(stderr, "%s\n", err.msg);
        lv_mission_free(mission);
        return 2;
    }
    int rc = 0;
    for (int i = 2; i < argc && rc == 0; i++) {
        size_t k;
        lv_phase_call *call = NULL;
        if (lv_mission_phase_find(mission, argv[i], &k, &err) != LV_OK ||
            lv_run_prepare(run, k, &call, &err) != LV_OK) {
            fprintf(stderr, "%s\n", err.msg);
            rc = 2;
            break;
        }
        lv_sim_settings *s = lv_phase_call_settings(call);
        char result[64];
        snprintf(result, sizeof result, "phase_%d", i - 1); /* resultFile = "phase_" + String(i) */
        s->result_file = result;
        /* (ok, out) := simulateExtendedModel(..., initialNames, initialValues, finalNames) */
        lv_sim_report rep;
        lv_err sim_err;
        lv_status st = lv_simulate(lv_phase_call_model(call), lv_phase_call_inst(call), s,
                                   lv_phase_call_finals(call), &rep, &sim_err);
        const double t0 = s->start_time;
        lv_run_complete(run, call, st, &sim_err, &rep, &err);
        double t1, z, vz;
        if (st == LV_OK && lv_run_final(run, k, "time", &t1, &err) == LV_OK &&
            lv_run_final(run, k, "z", &z, &err) == LV_OK &&
            lv_run_final(run, k, "vz", &vz, &err) == LV_OK) {
            printf("%-4s ok  t = %9.3f .. %9.3f s  z = %12.3f m  vz = %9.3f m/s  -> %s.mat\n",
                   argv[i], t0, t1, z, vz, result);
        } else {
            fprintf(stderr, "%s: %s\n", argv[i], st != LV_OK ? sim_err.msg : err.msg);
            rc = 3;
        }
    }
    lv_run_free(run);
    lv_mission_free(mission);
    return rc;
}
