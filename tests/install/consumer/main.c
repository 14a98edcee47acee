/* main.c - the install test's consumer: built against an installed lvsim (find_package),
 * it runs a mission in memory and prints where the gravity coefficients were found and the
 * final altitude. Usage: consumer MISSION.yaml. Exit 0 ok, 1 failure. */
#include <stdio.h>

#include <lvsim/lvsim.h>

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s MISSION.yaml\n", argv[0]);
        return 1;
    }
    lv_err err;
    char gfc[4096];
    if (lv_gravity_default_file(gfc, sizeof gfc, &err) != LV_OK) {
        fprintf(stderr, "consumer: %s\n", err.msg);
        return 1;
    }
    printf("gravity file: %s\n", gfc);

    lv_mission *m = NULL;
    if (lv_mission_load(argv[1], &m, &err) != LV_OK) {
        fprintf(stderr, "consumer: %s\n", err.msg);
        return 1;
    }
    const lv_run_options opt = {0}; /* no output folder: nothing is written */
    const size_t n = lv_mission_phase_count(m);
    double h = 0.0;
    lv_run *run = NULL;
    lv_status st = lv_run_create(m, &run, &err);
    if (st == LV_OK)
        st = lv_run_execute(run, &opt, &err);
    if (st == LV_OK)
        st = lv_run_final(run, n - 1, "h", &h, &err);
    lv_run_free(run);
    if (st != LV_OK) {
        fprintf(stderr, "consumer: %s\n", err.msg);
        lv_mission_free(m);
        return 1;
    }
    printf("%s: %zu phases, final altitude %.1f km\n", lv_mission_name(m), n, h / 1e3);
    lv_mission_free(m);
    return 0;
}
