/* cmd_target.c - `lvsim target MISSION.yaml`: solves the mission's `targeting:` section
 * (lv_target.h): one block per iteration (variables, constraint residuals, cost, runs and phase
 * simulations), a progress line on a terminal, then the converged values or the best point
 * with the constraints that fail (exit 3); -o writes the converged mission and checks that
 * running it reproduces the targeted finals. Format and algorithms: docs/targeting.md.
 */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "common.h"

typedef struct target_ui {
    int quiet, tty;
    int progress_shown;
    double drawn; /* s: the progress line's last redraw (at most every 0.1 s) */
} target_ui;

static double wall_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void clear_progress(target_ui *ui)
{
    if (ui->progress_shown) {
        fputs("\r\033[K", stderr);
        fflush(stderr);
        ui->progress_shown = 0;
    }
}

/* " unit", or "" for a dimensionless value */
static const char *with_unit(const char *unit, char *buf, size_t cap)
{
    snprintf(buf, cap, "%s%s", LV_UNIT_ONE(unit) ? "" : " ", LV_UNIT_AFTER_NUMBER(unit));
    return buf;
}

static const char *kind_word(lv_con_kind k)
{
    return k == LV_CON_EQUAL ? "equal" : k == LV_CON_MIN ? "min" : "max";
}

/* x: name = value ... and f: name = value (residual) ..., wrapped at about 100 columns. */
static void print_values(const lv_target *t, const double *x, const double *f, const double *r,
                         double cost)
{
    int col = printf("      x:");
    for (size_t j = 0; j < lv_target_var_count(t); j++) {
        lv_target_var_info v;
        lv_target_var_info_get(t, j, &v);
        char item[160];
        const int n = snprintf(item, sizeof item, " %s = %.10g", v.name, x[j]);
        if (col + n > 100 && col > 8)
            col = printf("\n        ");
        col += printf("%s", item);
    }
    printf("\n");
    if (lv_target_con_count(t) > 0) {
        col = printf("      f:");
        for (size_t i = 0; i < lv_target_con_count(t); i++) {
            lv_target_con_info c;
            lv_target_con_info_get(t, i, &c);
            char item[200];
            const int n = isnan(f[i]) ? snprintf(item, sizeof item, " %s = -", c.name)
                                      : snprintf(item, sizeof item, " %s = %.10g (%+.3g)",
                                                 c.name, f[i], r[i]);
            if (col + n > 100 && col > 8)
                col = printf("\n        ");
            col += printf("%s", item);
        }
        printf("\n");
    }
    lv_target_cost_info ci;
    lv_target_cost_info_get(t, &ci);
    if (ci.present) {
        char u[32];
        printf("      cost: %s = %.10g%s\n", ci.name, cost, with_unit(ci.unit, u, sizeof u));
    }
}

static void on_iteration(const lv_target *t, const lv_target_iter *it, void *user)
{
    target_ui *ui = user;
    if (ui->quiet)
        return;
    clear_progress(ui);
    char worst[32], step[32], damp[32];
    snprintf(worst, sizeof worst, isfinite(it->worst) ? "%.3g" : "-", it->worst);
    snprintf(step, sizeof step, isnan(it->step) ? "-" : "%.3g", it->step);
    snprintf(damp, sizeof damp, isnan(it->damping) ? "-" : "%.2g", it->damping);
    printf("%4zu  %-7s %-9s %5zu %6zu %8.2f  %10s  %9s  %8s", it->iteration, it->solver,
           it->event, it->runs, it->phases, it->wall, worst, step, damp);
    if (!isnan(it->cost))
        printf("  cost %.10g", it->cost);
    printf("\n");
    print_values(t, it->x, it->finals, it->residual, it->cost);
    if (it->note != NULL)
        printf("      note: %s\n", it->note);
    fflush(stdout);
}

static int on_evaluation(const lv_target *t, const lv_target_eval *ev, void *user)
{
    (void)t;
    target_ui *ui = user;
    if (cli_stop_flag)
        return 1; /* Ctrl-C: the solve ends with the best point so far */
    const double now = wall_now();
    if (!ui->tty || now - ui->drawn < 0.1)
        return 0;
    ui->drawn = now;
    fprintf(stderr, "\r\033[K  %s%s%s - %zu runs, %zu phase simulations so far, %.1f s",
            ev->purpose, ev->var ? " of " : "", ev->var ? ev->var : "", ev->runs_total,
            ev->phases_total, ev->wall);
    fflush(stderr);
    ui->progress_shown = 1;
    return 0;
}

static void print_problem(const lv_mission *m, const lv_target *t, const char *path, int quiet)
{
    lv_target_cost_info ci;
    lv_target_cost_info_get(t, &ci);
    printf("mission '%s' (%s): %zu variable(s), %zu constraint(s), %s\n", lv_mission_name(m),
           path, lv_target_var_count(t), lv_target_con_count(t),
           ci.present ? (ci.maximize ? "maximise" : "minimise") : "no cost");
    for (size_t j = 0; j < lv_target_var_count(t); j++) {
        lv_target_var_info v;
        lv_target_var_info_get(t, j, &v);
        char u[32];
        printf("  vary     %-32s [%g, %g]%s, start %.10g, scale %g, step %.3g\n", v.name, v.lo,
               v.hi, with_unit(v.unit, u, sizeof u), v.start, v.scale, v.step);
    }
    for (size_t i = 0; i < lv_target_con_count(t); i++) {
        lv_target_con_info c;
        lv_target_con_info_get(t, i, &c);
        char u[32];
        printf("  achieve  %-32s %s %.10g%s, tolerance %g\n", c.name, kind_word(c.kind),
               c.value, with_unit(c.unit, u, sizeof u), c.tol);
    }
    if (ci.present)
        printf("  %-8s %s [%s]\n", ci.maximize ? "maximise" : "minimise", ci.name, ci.unit);
    if (!quiet)
        printf("%4s  %-7s %-9s %5s %6s %8s  %10s  %9s  %8s\n", "it", "solver", "event", "runs",
               "phases", "wall [s]", "worst [tol]", "step", "lambda");
}

static void print_result(const lv_target *t, const lv_target_result *res)
{
    int met = 1;
    for (size_t i = 0; i < res->n_cons; i++)
        met &= res->met[i];
    printf("%s: %s\n", res->converged ? "converged" : met ? "NOT CONVERGED" : "NOT MET",
           res->reason);
    printf("  %s; %zu iterations, %zu runs, %zu phase simulations, %.3f s\n", res->method,
           res->iterations, res->runs, res->phases, res->wall);
    printf("%s:\n", res->converged ? "converged values" : "best point");
    for (size_t j = 0; j < res->n_vars; j++) {
        lv_target_var_info v;
        lv_target_var_info_get(t, j, &v);
        char u[32];
        printf("  %-32s = %.12g%s\n", v.name, res->x[j], with_unit(v.unit, u, sizeof u));
    }
    for (size_t i = 0; i < res->n_cons; i++) {
        lv_target_con_info c;
        lv_target_con_info_get(t, i, &c);
        char u[32];
        printf("  %-32s = %.12g%s  (%s %.10g +- %g: %s, %+.3g tol)\n", c.name, res->finals[i],
               with_unit(c.unit, u, sizeof u), kind_word(c.kind), c.value, c.tol,
               res->met[i] ? "met" : "FAILS", res->residual[i]);
    }
    lv_target_cost_info ci;
    lv_target_cost_info_get(t, &ci);
    char u[32];
    if (ci.present)
        printf("  %-32s = %.12g%s  (%s)\n", ci.name, res->cost, with_unit(ci.unit, u, sizeof u),
               ci.maximize ? "maximised" : "minimised");
    if (!res->converged) {
        size_t bad = 0;
        for (size_t i = 0; i < res->n_cons; i++)
            bad += !res->met[i];
        if (bad > 0) {
            printf("failing constraints:");
            for (size_t i = 0; i < res->n_cons; i++)
                if (!res->met[i]) {
                    lv_target_con_info c;
                    lv_target_con_info_get(t, i, &c);
                    printf(" %s", c.name);
                }
            printf("\n");
        }
    }
}

/* The phases that ended otherwise than the constraints assume (docs/targeting.md, "The end
 * each constraint assumes"): a converged point on another trajectory than the one targeted. */
static void print_end_mismatches(const lv_target_result *res)
{
    for (size_t i = 0; i < res->n_end_mismatch; i++) {
        const lv_target_end_mismatch *e = &res->end_mismatch[i];
        printf("warning: at the %s point phase '%s' ended by %s at t = %.10g s, not by %s, "
               "the end its constraints assume: %s\n", res->converged ? "converged" : "best",
               e->phase_name, e->actual, e->t_end, e->expected,
               res->converged ? "the constraints are met on another trajectory than the one "
                                "targeted (name the end on the constraint, `end:`, if this is "
                                "the one meant)"
                              : "the point is on another trajectory than the one targeted");
    }
}

static int target_run(const cli_cmd *self, int argc, char **argv)
{
    static const char *const methods[] = {"auto", "newton", "slsqp", "cobyla", NULL};
    static const char *const diffs[] = {"auto", "forward", "central", NULL};
    const char *path = NULL, *out = NULL;
    int force = 0, strict = 0;
    lv_target_settings set;
    lv_target_settings_default(&set);
    double max_rows = CLI_DEFAULT_MAX_ROWS;
    target_ui ui = {0, isatty(2), 0, 0.0};
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "-o") == 0 || strcmp(a, "--method") == 0 ||
            strcmp(a, "--differences") == 0 || strcmp(a, "--max-iter") == 0 ||
            strcmp(a, "--threads") == 0 || strcmp(a, "--restarts") == 0 ||
            strcmp(a, "--max-rows") == 0) {
            const char *v = option_value(argc, argv, &i);
            if (v == NULL)
                return usage_error(self, "missing value for option", a);
            if (strcmp(a, "-o") == 0) {
                if (out != NULL)
                    return usage_error(self, "-o given twice", v);
                out = v;
            } else if (strcmp(a, "--method") == 0 || strcmp(a, "--differences") == 0) {
                const char *const *list = a[2] == 'm' ? methods : diffs;
                int k = 0;
                while (list[k] != NULL && strcmp(list[k], v) != 0)
                    k++;
                if (list[k] == NULL)
                    return usage_error(self, a[2] == 'm' ? "--method: auto, newton, slsqp or "
                                                           "cobyla expected, got"
                                                         : "--differences: auto, forward or "
                                                           "central expected, got",
                                       v);
                if (a[2] == 'm')
                    set.method = (lv_target_method)k;
                else
                    set.differences = (lv_target_diff)k;
            } else if (strcmp(a, "--max-rows") == 0) {
                if (!parse_count(v, &max_rows))
                    return usage_error(self, "--max-rows needs a whole number from 1 to 1e15, got", v);
            } else {
                /* counts as the file's keys take them: an integer, also written 1e3 */
                const int r = strcmp(a, "--restarts") == 0, mi = strcmp(a, "--max-iter") == 0;
                const int rc = parse_int_option(self, a, v, r ? 0.0 : 1.0,
                                                r ? 100.0 : mi ? 100000.0 : 1024.0,
                                                r ? &set.restarts
                                                  : mi ? &set.max_iterations : &set.threads);
                if (rc != EXIT_OK)
                    return rc;
            }
        } else if (strcmp(a, "-q") == 0 || strcmp(a, "--quiet") == 0) {
            ui.quiet = 1;
        } else if (strcmp(a, "--force") == 0) {
            force = 1;
        } else if (strcmp(a, "--strict") == 0) {
            strict = 1;
        } else if (is_option(a)) {
            return usage_error(self, "unknown option", a);
        } else if (path != NULL) {
            return usage_error(self, "unexpected argument", a);
        } else {
            path = a;
        }
    }
    if (path == NULL)
        return usage_error(self, "target needs a mission file", NULL);
    int ocode;
    if (out != NULL && (ocode = check_out_file(self, out, "CONVERGED.yaml")) != EXIT_OK)
        return ocode; /* before the solve, not after it */
    if (ui.quiet)
        ui.tty = 0;
    lv_mission *m;
    lv_err err;
    lv_status st;
    const int lcode = load_mission(path, &m); /* as `lvsim check` and `run` load it */
    if (lcode != EXIT_OK)
        return lcode;
    /* before the solve: never an input; an existing file only with --force */
    if (out != NULL && (st = lv_output_check(out, m, force ? LV_OUTPUT_REPLACE : 0u, &err)) != LV_OK) {
        lv_mission_free(m);
        return print_err("lvsim target", &err, EXIT_INPUT);
    }
    /* the start point's rows, as `lvsim check` estimates them; a trial point's are held to
     * the same limit as it runs (a point refused or stopped by it fails) */
    const int bcode = check_output_bound(m, max_rows, 0.0, 0);
    if (bcode != EXIT_OK) {
        lv_mission_free(m);
        return bcode;
    }
    lv_target *t = NULL;
    if ((st = lv_target_create(m, &t, &err)) != LV_OK) {
        lv_mission_free(m);
        return print_err("lvsim", &err, exit_code_for_input(st));
    }
    lv_target_cost_info ci0;
    lv_target_cost_info_get(t, &ci0);
    if (set.method == LV_TARGET_NEWTON && ci0.present) {
        lv_target_free(t);
        lv_mission_free(m);
        return usage_error(self, "--method newton meets constraints and optimises no cost; the "
                           "mission has a cost: use auto, slsqp or cobyla", NULL);
    }
    cli_catch_stop(); /* Ctrl-C, SIGTERM: the best point so far, nothing written */
    set.on_iteration = on_iteration;
    set.on_evaluation = on_evaluation;
    set.user = &ui;
    set.stop = &cli_stop_flag;
    set.max_rows = max_rows;
    print_problem(m, t, path, ui.quiet);
    fflush(stdout);
    const lv_target_result *res = NULL;
    st = lv_target_solve(t, &set, &res, &err);
    clear_progress(&ui);
    int code = EXIT_OK;
    if (st == LV_ERR_CANCELLED) { /* before the start point was evaluated: no point */
        fprintf(stderr, "lvsim: interrupted before the start point was evaluated%s\n",
                out != NULL ? "; nothing written" : "");
        code = 130;
    } else if (st != LV_OK) {
        code = print_err("lvsim", &err, exit_code_for(st));
    } else {
        print_result(t, res);
        print_end_mismatches(res);
        if (!res->converged)
            code = EXIT_SIM;
        const int strict_fail = strict && res->converged && res->n_end_mismatch > 0;
        if (strict_fail) {
            fprintf(stderr, "lvsim: --strict: converged onto a point where %zu phase(s) ended "
                    "otherwise than the constraints assume (above)%s\n", res->n_end_mismatch,
                    out != NULL ? "; nothing written" : "");
            code = EXIT_SIM;
        }
        if (res->cancelled) {
            fprintf(stderr, "lvsim: interrupted: the best point so far above%s\n",
                    out != NULL ? "; nothing written" : "");
            code = 130;
        } else if (out != NULL && res->converged && !strict_fail) {
            double worst = NAN;
            st = lv_target_write(t, res->x, out, &worst, &err);
            if (st != LV_OK)
                code = print_err("lvsim", &err, exit_code_for(st));
            else
                printf("wrote %s: 'lvsim run %s' reproduces the targeted finals (largest "
                       "difference %.2g of a tolerance)\n", out, out, worst);
        } else if (out != NULL && !strict_fail) {
            printf("%s not written: the target was not met\n", out);
        }
    }
    fflush(stdout);
    lv_target_free(t);
    lv_mission_free(m);
    return code;
}

const cli_cmd cli_cmd_target = {
    "target",
    "solve a mission's targeting section: meet constraints, optimise a cost",
    "MISSION.yaml [-o CONVERGED.yaml [--force]] [--strict] [--method M] [--differences D] "
    "[--max-iter N] [--restarts N] [--threads N] [--max-rows N] [-q]",
    "Varies the run parameters listed under the mission's `targeting:` section within their\n"
    "bounds until the phases' final values meet the constraints (damped Newton /\n"
    "Levenberg-Marquardt with finite-difference sensitivities) and, with a cost, optimises\n"
    "it (NLopt's SLSQP, COBYLA as the fallback). Each evaluation re-simulates only the\n"
    "phases the changed variables reach. Prints the problem, one block per iteration\n"
    "(solver, event, runs and phase simulations, the worst residual in tolerances, the step,\n"
    "the variables, the constraints' finals with their residuals, the cost) and a progress\n"
    "line on a terminal; then the converged values, or the best point and the constraints\n"
    "that fail (NOT MET, exit 3; NOT CONVERGED when they are met but the optimiser did not\n"
    "reach its stopping test, exit 3). Each phase a constraint reads is assumed to end by\n"
    "its first end written (or the constraint's `end:`); a phase of the result that ended\n"
    "otherwise (burnout before the orbit's end) is a warning, an error with --strict.\n"
    "Before it starts, the start point's output rows are\n"
    "estimated as 'lvsim check' does (a phase only its stop time ends refused beyond\n"
    "--max-rows, exit 2); a trial point whose phase reaches the limit fails. Ctrl-C or\n"
    "SIGTERM stops it within a second, inside a long evaluation too, with the best point so\n"
    "far (exit 130, nothing written). docs/targeting.md.\n"
    "\n"
    "options:\n"
    "  -o CONVERGED.yaml       write the mission with the converged values (comments and\n"
    "                          layout kept; paths to the files it reads rewritten from the\n"
    "                          new file's folder), then run it and check that it reproduces\n"
    "                          the targeted finals; its folder must exist; never the\n"
    "                          mission or one of its data files; an existing file is\n"
    "                          refused unless --force\n"
    "  --force                 -o may replace an existing file (never an input)\n"
    "  --strict                a converged point where a constrained phase ended otherwise\n"
    "                          than its constraints assume is an error (exit 3, nothing\n"
    "                          written), not a warning\n"
    "  --method M              auto, newton, slsqp or cobyla (default: the file's, else auto)\n"
    "  --differences D         auto, forward or central (default: the file's, else auto)\n"
    "  --max-iter N            iterations, 1 to 100000 (default: the file's, else 50 for newton,\n"
    "                          50 + 25 per variable for each optimiser)\n"
    "  --restarts N            run SLSQP again from its best point up to N (<= 100) times while it\n"
    "                          gains (default: the file's, else 0)\n"
    "  --threads N             worker threads: sensitivities in parallel, each on a run of\n"
    "                          its own; independent branches of one evaluation (default 2)\n"
    "  --max-rows N            output rows a phase of an evaluation may compute (default 1e6)\n"
    "  -q, --quiet             no iterations, no progress line: the result only\n",
    target_run,
};
