/* cmd_optimize.c - `lvsim optimize`: a mission's optimal_control section solved by direct
 * multiple shooting with IPOPT (lv_ocp.h); the optimal mission written and re-flown. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "common.h"
#include "lvsim/lv_mission.h"
#include "lvsim/lv_ocp.h"

typedef struct opt_ui {
    int quiet, tty;
    int header;
} opt_ui;

static int on_iteration(const lv_ocp_iteration *it, void *user)
{
    opt_ui *ui = user;
    if (ui->quiet)
        return 0;
    if (!ui->header) {
        printf("%5s  %16s  %9s  %9s  %7s  %8s  %9s  %8s\n", "iter", "cost", "inf_pr", "inf_du",
               "lg(mu)", "step", "segments", "wall [s]");
        ui->header = 1;
    }
    char cost[32] = "-"; /* a problem without a cost */
    if (!isnan(it->cost))
        snprintf(cost, sizeof cost, "%.9g", it->cost);
    printf("%5d%c %16s  %9.2e  %9.2e  %7.1f  %8.2e  %9ld  %8.2f\n", it->iteration,
           it->restoration ? 'r' : ' ', cost, it->inf_pr, it->inf_du, log10(it->mu), it->step,
           it->segments, it->wall);
    fflush(stdout);
    return 0;
}

/* The written mission flown by `lvsim run`'s runner: each optimised phase's drift from the
 * optimiser's trajectory (its reference). */
static int resimulate(const char *out, const lv_ocp *o)
{
    lv_mission *m = NULL;
    lv_run *r = NULL;
    lv_err err;
    lv_status st = lv_mission_load(out, &m, &err);
    if (st == LV_OK)
        st = lv_run_create(m, &r, &err);
    if (st == LV_OK)
        st = lv_run_execute(r, NULL, &err);
    if (st != LV_OK) {
        lv_run_free(r);
        lv_mission_free(m);
        return print_err("lvsim: the optimal mission re-flown", &err, EXIT_SIM);
    }
    printf("re-flown by 'lvsim run %s' (each phase's own integrator and tolerance), drift from "
           "the optimiser's trajectory:\n", out);
    printf("  %-20s %14s %14s %14s %14s\n", "phase", "position [m]", "(final)",
           "velocity [m/s]", "mass [kg]");
    for (size_t k = 0; k < lv_mission_phase_count(m); k++) {
        double t0, t1;
        if (lv_ocp_phase_times(o, k, &t0, &t1, NULL) != LV_OK)
            continue;
        lv_ref_drift dr;
        const lv_phase_result *pr = lv_run_result(r, k);
        if (lv_run_reference_drift(r, k, &dr, &err) != LV_OK) {
            printf("  %-20s %s\n", pr->name, err.msg);
            continue;
        }
        printf("  %-20s %14.4g %14.4g %14.4g %14.4g\n", pr->name, dr.pos_max, dr.pos_final,
               dr.vel_max, dr.mass_max);
    }
    lv_run_free(r);
    lv_mission_free(m);
    return EXIT_OK;
}

static int optimize_run(const cli_cmd *self, int argc, char **argv)
{
    const char *path = NULL, *out = NULL;
    int force = 0;
    opt_ui ui = {0, isatty(1), 0};
    lv_ocp_settings set = {0};
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "-o") == 0 || strcmp(a, "--max-iter") == 0 ||
            strcmp(a, "--threads") == 0 || strcmp(a, "--print-level") == 0) {
            const char *v = option_value(argc, argv, &i);
            if (v == NULL)
                return usage_error(self, "missing value for option", a);
            if (a[1] == 'o') {
                if (out != NULL)
                    return usage_error(self, "-o given twice", v);
                out = v;
                continue;
            }
            const int mi = strcmp(a, "--max-iter") == 0, pl = strcmp(a, "--print-level") == 0;
            const int rc = parse_int_option(self, a, v, pl ? 0.0 : 1.0,
                                            mi ? 100000.0 : pl ? 12.0 : 15.0,
                                            mi ? &set.max_iterations
                                               : pl ? &set.print_level : &set.threads);
            if (rc != EXIT_OK)
                return rc;
        } else if (strcmp(a, "-q") == 0 || strcmp(a, "--quiet") == 0) {
            ui.quiet = 1;
        } else if (strcmp(a, "--force") == 0) {
            force = 1;
        } else if (is_option(a)) {
            return usage_error(self, "unknown option", a);
        } else if (path != NULL) {
            return usage_error(self, "unexpected argument", a);
        } else {
            path = a;
        }
    }
    if (path == NULL)
        return usage_error(self, "optimize needs a mission file", NULL);
    int code;
    if (out != NULL && (code = check_out_file(self, out, "OPTIMAL.yaml")) != EXIT_OK)
        return code;
    lv_mission *m;
    const int lcode = load_mission(path, &m); /* as `lvsim check` and `run` load it */
    if (lcode != EXIT_OK)
        return lcode;
    lv_err err;
    lv_status st;
    lv_ocp *o = NULL;
    if ((st = lv_ocp_create(path, &o, &err)) != LV_OK) {
        lv_mission_free(m);
        return print_err("lvsim", &err, exit_code_for_input(st));
    }
    /* every file -o would write, before the solve: never an input, never a user's file */
    if (out != NULL &&
        (st = lv_ocp_check_write(o, out, force ? LV_OUTPUT_REPLACE : 0u, &err)) != LV_OK) {
        lv_ocp_free(o);
        lv_mission_free(m);
        return print_err("lvsim optimize", &err, EXIT_INPUT);
    }
    lv_ocp_result res;
    cli_catch_stop();
    set.on_iteration = on_iteration;
    set.user = &ui;
    set.stop = &cli_stop_flag;
    if (!ui.quiet) {
        printf("optimal control of %s: direct multiple shooting, IPOPT (limited-memory "
               "Hessian)\n", path);
        fflush(stdout);
    }
    st = lv_ocp_solve(o, &set, &res, &err);
    if (st != LV_OK && st != LV_ERR_CANCELLED) {
        code = print_err("lvsim", &err, exit_code_for(st));
        lv_ocp_free(o);
        lv_mission_free(m);
        return code;
    }
    static const char *const outcome[] = {"OPTIMAL", "INFEASIBLE", "NOT CONVERGED", "STOPPED"};
    printf("%s (IPOPT: %s) after %d iterations, %.2f s wall, %.2f s CPU\n",
           outcome[res.outcome], res.ipopt_text, res.iterations, res.wall, res.cpu);
    printf("  NLP: %zu variables, %zu constraints, %zu Jacobian entries in %zu column groups; "
           "%ld segment simulations, %ld evaluations (Jacobians %.2f s, points %.2f s)\n",
           res.n_vars, res.n_cons, res.nnz_jac, res.n_groups, res.segments, res.evaluations,
           res.wall_jac, res.wall_eval);
    if (res.iterations > 0 && res.segments > 0)
        printf("  per iteration: %.1f ms wall (Jacobian %.1f, points %.1f, IPOPT and the rest "
               "%.1f); %.1f us CPU per segment simulation\n", 1e3 * res.wall / res.iterations,
               1e3 * res.wall_jac / res.iterations, 1e3 * res.wall_eval / res.iterations,
               1e3 * (res.wall - res.wall_jac - res.wall_eval) / res.iterations,
               1e6 * res.cpu / (double)res.segments);
    if (!isnan(res.cost))
        printf("  cost: %.12g (start %.12g)\n", res.cost, res.cost_start);
    printf("  largest violation: %.3g (of each row's scale or tolerance)\n", res.max_violation);
    if (res.last_failure[0] != '\0' && res.outcome != LV_OCP_OPTIMAL)
        printf("  the last point that did not fly: %s\n", res.last_failure);
    for (size_t i = 0; i < res.n_violated && i < 12; i++) {
        char text[512];
        double v;
        if (lv_ocp_violation(o, i, text, sizeof text, &v, &err) == LV_OK)
            printf("  VIOLATED  %s\n", text);
    }
    if (res.n_violated > 12)
        printf("  ... and %zu more violated rows\n", res.n_violated - 12);
    if (res.outcome == LV_OCP_INFEASIBLE && res.n_violated == 0 && isfinite(res.max_violation))
        printf("  the point returned meets every row: IPOPT stopped on trial points that did "
               "not fly (below), not on the constraints\n");
    code = res.outcome == LV_OCP_OPTIMAL ? EXIT_OK
           : res.outcome == LV_OCP_STOPPED ? EXIT_STOPPED
                                           : EXIT_SIM;
    if (out != NULL && res.outcome == LV_OCP_OPTIMAL) {
        st = lv_ocp_write(o, out, force ? LV_OUTPUT_REPLACE : 0u, &err);
        if (st != LV_OK) {
            code = print_err("lvsim", &err, exit_code_for(st));
        } else {
            printf("wrote %s (and its controls and reference tables beside it)\n", out);
            fflush(stdout);
            code = resimulate(out, o);
        }
    } else if (out != NULL) {
        printf("%s not written: no optimum\n", out);
    }
    fflush(stdout);
    lv_ocp_free(o);
    lv_mission_free(m);
    return code;
}

const cli_cmd cli_cmd_optimize = {
    "optimize",
    "solve a mission's optimal_control section: control histories by multiple shooting",
    "MISSION.yaml [-o OPTIMAL.yaml [--force]] [--max-iter N] [--threads N] [--print-level N] "
    "[-q]",
    "Optimises the control histories (dof3: alpha, beta, mu, throttle, or an attitude\n"
    "law's pitch, heading, roll; piecewise linear between equally spaced nodes) and the\n"
    "free durations of the phases listed under the\n"
    "mission's `optimal_control:` section, subject to its constraints on finals and its path\n"
    "constraints (held at every segment start and the end), optimising its cost: direct\n"
    "multiple shooting over the phase tree with each phase's own model and integrator, the\n"
    "runner's hand-offs as links, a sparse finite-difference Jacobian, and IPOPT with a\n"
    "limited-memory Hessian. The start point is the mission flown as written (each control\n"
    "from the section's `start:`, the phase's own input, or its attitude law's table or\n"
    "constant). Prints one line per iteration, then OPTIMAL (exit 0) or INFEASIBLE / NOT\n"
    "CONVERGED with the violated constraints (exit 3). With -o, writes the optimal mission -\n"
    "each optimised phase flying its control nodes as a table over mission time (its inputs\n"
    "table, or its attitude law's) to its optimal stop_time, with the optimiser's\n"
    "trajectory as its reference - re-flies it as `lvsim run` does and prints the drift. Ctrl-C stops it (exit 130, nothing written). docs/optimal-control.md.\n"
    "\n"
    "options:\n"
    "  -o OPTIMAL.yaml         write the optimal mission, and OPTIMAL_<phase>_controls.csv and\n"
    "                          OPTIMAL_<phase>_reference.csv beside it; never an input; an\n"
    "                          existing file lvsim optimize did not write is refused unless\n"
    "                          --force\n"
    "  --force                 -o may replace existing files (never an input)\n"
    "  --max-iter N            IPOPT iterations, 1 to 100000 (default: the file's, else 500)\n"
    "  --threads N             worker threads for the Jacobian's column groups, 1 to 15\n"
    "                          (default 2)\n"
    "  --print-level N         IPOPT's own output, 0 to 12 (default 0)\n"
    "  -q, --quiet             no iteration lines: the result only\n",
    optimize_run,
};
