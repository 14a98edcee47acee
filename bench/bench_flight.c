/* bench_flight.c - the cost of one flight in-process, as a study (Monte Carlo, targeting, an
 * optimiser's inner loop) pays it: create the 3-DoF model, simulate a vertical flight to
 * apogee (about 200 s, 400 rows at a 0.5 s grid) into an in-memory result, free everything.
 * The environment (WGS-84 Earth, J2 gravity, US76) is created once, as a loaded mission
 * shares it. Issue 11's target: <= 100 us per flight with the same steps, issue 24's: <= 80 us
 * with the default method; RocketPy needs about 14 ms in-process for such a flight (the issue's
 * figure; not measured here). bench/instr_flight.py counts the instructions of one flight with
 * callgrind (bench_flight METHOD 1 1 rows|norows) and splits them (steps against the rhs, rows,
 * events, dense output, set-up).
 *
 * Printed, per integration method (CPU time of this thread, best of several rounds of many
 * flights so a busy machine distorts less):
 *   flight     create + lv_simulate + free, per flight
 *   sim        the part inside lv_sim_advance (steps, events, rows into memory)
 *   outside    flight - sim: model set-up, lv_sim_create/finish, sinks, freeing
 *   steps/rhs  the run's statistics (unchanged by any of this: the same steps)
 *   x dassl    flight time against dassl's (the default method until issue 24)
 *   dh_apo     |apogee height - the reference's|: dop853 at tolerance 1e-12
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_dof3.h"
#include "lvsim/lv_io.h"
#include "lvsim/lv_planet.h"
#include "lvsim/lv_sim.h"
#include "lvsim/lv_vehicle.h"

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct flight_env {
    const lv_gravity *grav;
    const lv_atmo *atmo;
} flight_env;

typedef struct flight_out {
    double t_apogee, h_apogee; /* s, m */
    long steps, rhs, rows;
    double t_sim; /* s CPU inside lv_sim_advance */
} flight_out;

/* One whole flight: model, simulation into memory, free. */
static int fly(const flight_env *env, const char *method, double tol, int rows, flight_out *fo,
               lv_err *err)
{
    lv_engine_config eng;
    lv_engine_config_default(&eng);
    eng.thrust_vac = 60e3; /* N */
    eng.isp_vac = 240.0;   /* s */
    eng.exit_area = 0.05;  /* m^2 */
    lv_aero_config aero;
    lv_aero_config_default(&aero);
    aero.s_ref = 0.2; /* m^2 */
    aero.coef[0].value = 0.35;
    lv_dof3_config cfg;
    lv_dof3_config_default(&cfg);
    cfg.gravity = env->grav;
    cfg.atmo = env->atmo;
    cfg.m0 = 1500.0;
    cfg.propellant = 900.0; /* kg: burnout at 600 kg */
    cfg.n_engines = 1;
    cfg.engines = &eng;
    cfg.aero = &aero;
    cfg.start_lat = 0.5;
    cfg.start_lon = -1.3;
    cfg.start_h = 10.0;
    cfg.start_vel = 1.0;
    cfg.start_fpa = 0.5 * 3.14159265358979323846; /* vertical */
    const lv_dof3_end ends[] = {{"apogee", LV_DOF3_END_APOGEE, 0.0, LV_DIR_BOTH, 1}};
    cfg.n_ends = 1;
    cfg.ends = ends;

    lv_dof3 *m = NULL;
    lv_result *res = NULL;
    lv_sink sink = {0};
    lv_sim *sim = NULL;
    lv_sim_report rep = {0};
    const char *fin[] = {"time", "h"};
    double finals[2];
    lv_status st = lv_dof3_create(&cfg, &m, err);
    if (st == LV_OK)
        st = lv_sink_memory_create(&res, &sink, err);
    lv_sim_settings s;
    lv_sim_settings_default(&s);
    s.stop_time = 400.0;
    s.output_interval = 0.5;
    s.method = method;
    s.tolerance = tol;
    s.result_file = NULL;
    s.n_sinks = rows ? 1 : 0; /* without: the integrator's own cost (rows counted, not made) */
    s.sinks = &sink;
    s.n_final = 2;
    s.final_names = fin;
    if (st == LV_OK)
        st = lv_sim_create(lv_dof3_def(m), lv_dof3_inst(m), &s, &sim, err);
    if (st == LV_OK) {
        double t0 = cpu_now();
        st = lv_sim_advance(sim, s.stop_time, err);
        fo->t_sim = cpu_now() - t0;
    }
    if (sim != NULL) {
        lv_status fst = lv_sim_finish(sim, finals, &rep, err);
        if (st == LV_OK)
            st = fst;
    }
    if (st == LV_OK) {
        fo->t_apogee = finals[0];
        fo->h_apogee = finals[1];
        fo->steps = rep.stats.steps;
        fo->rhs = rep.stats.rhs_evals;
        fo->rows = rows ? (long)lv_result_rows(res) : rep.stats.output_rows;
    }
    lv_sim_report_clear(&rep);
    lv_sim_free(sim);
    lv_sink_destroy(&sink);
    lv_result_free(res);
    lv_dof3_free(m);
    return st == LV_OK ? 0 : 1;
}

int main(int argc, char **argv)
{
    lv_err err;
    const lv_planet earth = lv_planet_earth();
    lv_gravity_config gc = {"j2", 0, -1, NULL};
    lv_gravity *grav = NULL;
    lv_atmo *atmo = NULL;
    if (lv_gravity_create(&earth, &gc, &grav, &err) != LV_OK ||
        lv_atmo_create("us76", &atmo, &err) != LV_OK) {
        fprintf(stderr, "bench_flight: %s\n", err.msg);
        return 1;
    }
    const flight_env env = {grav, atmo};
    /* bench_flight [METHOD [FLIGHTS [ROUNDS [rows|norows]]]]: one method only; with the fourth
     * argument only that half and no reference flight (for a profiler: bench/instr_flight.py) */
    const char *methods[] = {"dassl", "dopri5", "cvode-adams", "dp5", "dop853", "auto"};
    size_t n_methods = sizeof methods / sizeof methods[0];
    if (argc > 1) {
        methods[0] = argv[1];
        n_methods = 1;
    }
    int flights = argc > 2 ? atoi(argv[2]) : 200;
    const int rounds = argc > 3 ? atoi(argv[3]) : 5;
    int rows_first = 1, rows_last = 0;
    if (argc > 4) {
        rows_first = rows_last = strcmp(argv[4], "rows") == 0 ? 1 : 0;
        if (!rows_first && strcmp(argv[4], "norows") != 0)
            flights = 0; /* refused below */
    }
    if (flights < 1 || rounds < 1) {
        fprintf(stderr, "usage: bench_flight [METHOD [FLIGHTS [ROUNDS [rows|norows]]]]\n");
        return 2;
    }
    printf("# one flight in-process: lv_dof3_create + lv_simulate (vertical, to apogee, 0.5 s "
           "grid, memory sink) + free;\n# CPU us per flight, best of %d rounds of %d flights\n",
           rounds, flights);
    flight_out ref = {.h_apogee = NAN};
    if (argc <= 4 && fly(&env, "dop853", 1e-12, 1, &ref, &err) != 0) {
        fprintf(stderr, "bench_flight: reference: %s\n", err.msg);
        return 1;
    }
    printf("%-12s %10s %10s %10s %8s %7s %7s %6s %9s %8s %9s\n", "method", "flight", "sim",
           "outside", "outside%", "steps", "rhs", "rows", "apogee_t", "x dassl", "dh_apo[m]");
    int rc = 0;
    for (int rows = rows_first; rows >= rows_last && rc == 0; rows--) {
        double best_dassl = NAN;
        if (!rows)
            printf("# the same flights without a sink: rows counted, not evaluated (integration "
                   "only)\n");
        for (size_t k = 0; k < n_methods; k++) {
            double best = INFINITY, best_sim = INFINITY;
            flight_out fo = {0};
            for (int r = 0; r < rounds && rc == 0; r++) {
                double sim = 0.0;
                double t0 = cpu_now();
                for (int i = 0; i < flights; i++) {
                    if (fly(&env, methods[k], 1e-6, rows, &fo, &err) != 0) {
                        fprintf(stderr, "bench_flight: %s: %s\n", methods[k], err.msg);
                        rc = 1;
                        break;
                    }
                    sim += fo.t_sim;
                }
                double t = (cpu_now() - t0) / flights;
                if (t < best) {
                    best = t;
                    best_sim = sim / flights;
                }
            }
            if (rc != 0)
                break;
            if (strcmp(methods[k], "dassl") == 0)
                best_dassl = best;
            printf("%-12s %10.1f %10.1f %10.1f %7.0f%% %7ld %7ld %6ld %9.2f %8.2f %9.2e\n",
                   methods[k], 1e6 * best, 1e6 * best_sim, 1e6 * (best - best_sim),
                   100.0 * (best - best_sim) / best, fo.steps, fo.rhs, fo.rows, fo.t_apogee,
                   best / best_dassl, fabs(fo.h_apogee - ref.h_apogee));
        }
    }
    printf("# tolerance 1e-6 for all; target (issue 24): flight <= 80 us with the default "
           "method\n");
    lv_atmo_free(atmo);
    lv_gravity_free(grav);
    return rc;
}
