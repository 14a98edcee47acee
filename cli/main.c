/* main.c - the lvsim command line: arguments, messages and exit codes; no physics.
 *
 * Exit codes: 0 ok, 1 internal error, 2 bad input (arguments, files, names),
 * 3 simulation failure. See docs/cli.md.
 */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lvsim/lvsim.h"

enum { EXIT_OK = 0, EXIT_INTERNAL = 1, EXIT_INPUT = 2, EXIT_SIM = 3 };

static int exit_code_for(lv_status st)
{
    switch (st) {
    case LV_OK: return EXIT_OK;
    case LV_ERR_SOLVER: return EXIT_SIM;
    case LV_ERR_NOMEM: return EXIT_INTERNAL;
    default: return EXIT_INPUT;
    }
}

static int usage_error(const char *what, const char *arg)
{
    fprintf(stderr, "lvsim: %s%s%s%s\n(see 'lvsim help')\n", what, arg ? " '" : "",
            arg ? arg : "", arg ? "'" : "");
    return EXIT_INPUT;
}

/* Parses a whole argument as a finite double. */
static int parse_double(const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE || !isfinite(v))
        return 0;
    *out = v;
    return 1;
}

static int parse_int(const char *s, int *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end != '\0' || errno == ERANGE || v < 0 || v > 100000000)
        return 0;
    *out = (int)v;
    return 1;
}

static void print_help(FILE *f)
{
    fprintf(f,
            "lvsim %s - mission-dependent sequential simulation of launch vehicles\n"
            "\n"
            "usage:\n"
            "  lvsim models                      list the built-in models\n"
            "  lvsim vars MODEL                  list a model's variables (name, unit, start)\n"
            "  lvsim simulate MODEL [options]    one run, as Dymola's simulateExtendedModel\n"
            "      --start T  --stop T           start and stop time [s] (0, 1)\n"
            "      --intervals N | --interval DT output grid (500 intervals)\n"
            "      --method M                    dassl | cvode-adams | dopri5 | rk4 | euler\n"
            "      --tolerance TOL               relative tolerance (1e-4)\n"
            "      --fixed-step H                step of rk4/euler [s] (the output interval)\n"
            "      --max-steps N                 internal steps allowed in total (1e6)\n"
            "      --set NAME=VALUE              start value of a state or parameter (repeat)\n"
            "      --final NAME                  print this variable's final value (repeat)\n"
            "      -o PATH                       result file path without extension (dsres)\n"
            "      --format mat,csv              result formats (both)\n"
            "      --json                        print the report as JSON\n"
            "  lvsim run MISSION.yaml [-o OUTDIR] [--threads N] [--json] [--no-plots]\n"
            "                                    run every phase; results, exports, plots,\n"
            "                                    summary.json, index.html (OUTDIR: lvsim-out)\n"
            "  lvsim plot OUTDIR                 plots and index.html from a results folder\n"
            "  lvsim view OUTDIR [--port N] [--stage-only]\n"
            "                                    3-D globe view (CesiumJS, offline) on 127.0.0.1\n"
            "  lvsim check MISSION.yaml          validate only\n"
            "  lvsim export OUTDIR [--format czml,kml,oem]\n"
            "                                    trajectory exports from a results folder\n"
            "  lvsim compare MISSION.yaml [--method M] [--tolerance TOL] [--interval DT] [--json]\n"
            "                                    sequential vs end-to-end (the paper's Table 2)\n"
            "  lvsim atmosphere ALT_M... [--model us76|exp]\n"
            "                                    T, p, rho, a, mu at geometric altitudes\n"
            "  lvsim gravity LAT_DEG LON_DEG ALT_M [--model sh|sh:N|zonal|j2|pointmass]\n"
            "                [--planet earth|moon|mars] [--effective]\n"
            "                                    gravity vector in NED [m/s2] (default sh)\n"
            "  lvsim help | --help               this text\n"
            "  lvsim version\n"
            "\n"
            "exit codes: 0 ok, 2 bad input, 3 simulation failure\n"
            "data files (gravity coefficients, the viewer): $LVSIM_DATA, else share/lvsim\n"
            "next to the library, else the install prefix\n",
            LVSIM_VERSION);
}

static const lv_model_def *find_model(const char *name)
{
    const lv_model_def *m = lv_models_find(name);
    if (m == NULL) {
        fprintf(stderr, "lvsim: unknown model '%s'; built-in models:", name);
        for (const lv_model_def *const *all = lv_models_all(); *all; all++)
            fprintf(stderr, " %s", (*all)->name);
        fprintf(stderr, "\n");
    }
    return m;
}

static int cmd_models(void)
{
    for (const lv_model_def *const *all = lv_models_all(); *all; all++)
        printf("%-18s %s\n", (*all)->name, (*all)->description);
    return EXIT_OK;
}

static void print_vars(const char *kind, const lv_var *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        printf("%-10s %-16s %-8s %12g  %s\n", kind, v[i].name, v[i].unit[0] ? v[i].unit : "-",
               v[i].start, v[i].description);
}

static int cmd_vars(int argc, char **argv)
{
    if (argc != 1)
        return usage_error("vars takes one model name", NULL);
    const lv_model_def *m = find_model(argv[0]);
    if (m == NULL)
        return EXIT_INPUT;
    printf("# model %s: %s\n# %-8s %-16s %-8s %12s  %s\n", m->name, m->description, "kind",
           "name", "unit", "start", "description");
    print_vars("state", m->states, m->n_states);
    for (size_t i = 0; i < m->n_states; i++) {
        char der[128];
        snprintf(der, sizeof der, "der(%s)", m->states[i].name);
        printf("%-10s %-16s %-8s %12s  Time derivative of %s\n", "derivative", der, "-", "",
               m->states[i].name);
    }
    print_vars("parameter", m->params, m->n_params);
    print_vars("output", m->outputs, m->n_outputs);
    for (size_t i = 0; i < m->n_events; i++)
        printf("%-10s %-16s %-8s %12s  %s\n", "event", m->events[i].name,
               m->events[i].direction > 0 ? "rising" : m->events[i].direction < 0 ? "falling" : "both",
               "", m->events[i].description);
    return EXIT_OK;
}

static void json_string(const char *s)
{
    putchar('"');
    for (; *s; s++) {
        if (*s == '"' || *s == '\\')
            printf("\\%c", *s);
        else if ((unsigned char)*s < 0x20)
            printf("\\u%04x", *s);
        else
            putchar(*s);
    }
    putchar('"');
}

static int cmd_simulate(int argc, char **argv)
{
    if (argc < 1)
        return usage_error("simulate needs a model name", NULL);
    const lv_model_def *m = find_model(argv[0]);
    if (m == NULL)
        return EXIT_INPUT;

    lv_sim_settings s;
    lv_sim_settings_default(&s);
    int json = 0;
    int rc = EXIT_OK;
    size_t cap = (size_t)argc;
    char **set_names = calloc(cap, sizeof *set_names);
    double *set_values = calloc(cap, sizeof *set_values);
    const char **final_names = calloc(cap, sizeof *final_names);
    double *finals = calloc(cap, sizeof *finals);
    if (!set_names || !set_values || !final_names || !finals) {
        fprintf(stderr, "lvsim: out of memory\n");
        rc = EXIT_INTERNAL;
        goto out;
    }
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
        int takes = 1;
        static const char *const with_value[] = {
            "--start", "--stop", "--interval", "--tolerance", "--fixed-step", "--intervals",
            "--method", "-o", "--format", "--set", "--final", "--max-steps", NULL};
        int known = 0;
        for (size_t k = 0; with_value[k] != NULL; k++)
            known |= strcmp(a, with_value[k]) == 0;
        if (strcmp(a, "--json") == 0) {
            json = 1;
            takes = 0;
        } else if (!known) {
            rc = usage_error("unknown option", a);
            goto out;
        } else if (val == NULL) {
            rc = usage_error("missing value for option", a);
            goto out;
        } else if (strcmp(a, "--start") == 0 || strcmp(a, "--stop") == 0 ||
                   strcmp(a, "--interval") == 0 || strcmp(a, "--tolerance") == 0 ||
                   strcmp(a, "--fixed-step") == 0) {
            double v;
            if (!parse_double(val, &v)) {
                fprintf(stderr, "lvsim: %s: '%s' is not a finite number\n", a, val);
                rc = EXIT_INPUT;
                goto out;
            }
            if (strcmp(a, "--start") == 0) s.start_time = v;
            else if (strcmp(a, "--stop") == 0) s.stop_time = v;
            else if (strcmp(a, "--interval") == 0) s.output_interval = v;
            else if (strcmp(a, "--tolerance") == 0) s.tolerance = v;
            else s.fixed_step = v;
        } else if (strcmp(a, "--intervals") == 0) {
            if (!parse_int(val, &s.number_of_intervals)) {
                fprintf(stderr, "lvsim: --intervals: '%s' is not a count\n", val);
                rc = EXIT_INPUT;
                goto out;
            }
        } else if (strcmp(a, "--max-steps") == 0) {
            int n;
            if (!parse_int(val, &n) || n == 0) {
                fprintf(stderr, "lvsim: --max-steps: '%s' is not a positive count\n", val);
                rc = EXIT_INPUT;
                goto out;
            }
            s.max_steps = n;
        } else if (strcmp(a, "--method") == 0) {
            s.method = val;
        } else if (strcmp(a, "-o") == 0) {
            s.result_file = val;
        } else if (strcmp(a, "--format") == 0) {
            s.result_formats = 0;
            if (strstr(val, "mat")) s.result_formats |= LV_RESULT_MAT;
            if (strstr(val, "csv")) s.result_formats |= LV_RESULT_CSV;
            if (strcmp(val, "none") == 0)
                s.result_file = NULL;
            else if (s.result_formats == 0) {
                fprintf(stderr, "lvsim: --format: '%s': use mat, csv, mat,csv or none\n", val);
                rc = EXIT_INPUT;
                goto out;
            }
        } else if (strcmp(a, "--set") == 0) {
            const char *eq = strchr(val, '=');
            double v;
            if (eq == NULL || eq == val || !parse_double(eq + 1, &v)) {
                fprintf(stderr, "lvsim: --set '%s': expected NAME=NUMBER\n", val);
                rc = EXIT_INPUT;
                goto out;
            }
            set_names[s.n_initial] = strndup(val, (size_t)(eq - val));
            set_values[s.n_initial++] = v;
        } else { /* --final */
            final_names[s.n_final++] = val;
        }
        i += takes;
    }
    s.initial_names = (const char *const *)set_names;
    s.initial_values = set_values;
    s.final_names = final_names;

    lv_sim_report rep;
    lv_err err;
    lv_status st = lv_simulate(m, NULL, &s, finals, &rep, &err);
    if (st != LV_OK)
        fprintf(stderr, "lvsim: %s\n", err.msg);
    if (json) {
        printf("{\"model\": ");
        json_string(m->name);
        printf(", \"ok\": %s, \"method\": ", st == LV_OK ? "true" : "false");
        json_string(s.method);
        printf(", \"tolerance\": %.17g, \"end_time\": %.17g, \"stop\": ", s.tolerance, rep.end_time);
        json_string(rep.stop_name);
        if (st != LV_OK) {
            printf(", \"error\": ");
            json_string(err.msg);
        }
        printf(",\n \"stats\": {\"states\": %zu, \"steps\": %ld, \"rhs_evals\": %ld, "
               "\"jac_evals\": %ld, \"state_events\": %ld, \"time_events\": %ld, "
               "\"restarts\": %ld, \"rows\": %ld, \"cpu_time\": %.6g},\n \"final\": {",
               rep.n_states, rep.stats.steps, rep.stats.rhs_evals, rep.stats.jac_evals,
               rep.stats.state_events, rep.stats.time_events, rep.stats.restarts,
               rep.stats.output_rows, rep.stats.cpu_time);
        for (size_t i = 0; st == LV_OK && i < s.n_final; i++) {
            printf("%s", i ? ", " : "");
            json_string(final_names[i]);
            printf(": %.17g", finals[i]);
        }
        printf("}}\n");
    } else {
        printf("model %s, method %s, tolerance %g: %s at t = %.9g s (%s)\n", m->name, s.method,
               s.tolerance, st == LV_OK ? "ok" : "FAILED", rep.end_time, rep.stop_name);
        printf("  states %zu, steps %ld, rhs evals %ld, jacobians %ld, state events %ld, "
               "time events %ld, cpu %.3f ms\n",
               rep.n_states, rep.stats.steps, rep.stats.rhs_evals, rep.stats.jac_evals,
               rep.stats.state_events, rep.stats.time_events, 1e3 * rep.stats.cpu_time);
        for (size_t i = 0; st == LV_OK && i < s.n_final; i++)
            printf("  %-16s = %.12g\n", final_names[i], finals[i]);
        if (s.result_file != NULL && rep.stats.output_rows > 0)
            printf("  result: %s%s%s%s\n", s.result_file, st == LV_OK ? "" : ".failed",
                   (s.result_formats & LV_RESULT_MAT) ? ".mat " : "",
                   (s.result_formats & LV_RESULT_CSV) ? ".csv" : "");
    }
    lv_sim_report_clear(&rep);
    rc = exit_code_for(st);
out:
    for (size_t i = 0; set_names && i < cap; i++)
        free(set_names[i]);
    free(set_names);
    free(set_values);
    free(final_names);
    free(finals);
    return rc;
}

/* ---- missions ------------------------------------------------------------------------ */

static const char *phase_state_name(lv_phase_state st)
{
    switch (st) {
    case LV_PHASE_DONE: return "ok";
    case LV_PHASE_FAILED: return "FAILED";
    case LV_PHASE_SKIPPED: return "skipped";
    default: return "pending";
    }
}

static void print_phase_row(const lv_run *run, size_t k, const lv_phase_result *r, void *user)
{
    (void)user;
    const lv_mission *m = lv_run_mission(run);
    int parent = lv_mission_phase_parent(m, k);
    const lv_sim_report *rep = &r->report;
    if (r->state == LV_PHASE_SKIPPED) {
        printf("%-3zu %-12s %-10s %s\n", k + 1, r->name, "skipped", r->error);
    } else {
        printf("%-3zu %-12s %-10s %9.3f %9.3f  %-10s %7ld %8ld %4ld %4ld %9.2f  %s\n", k + 1,
               r->name, parent >= 0 ? lv_mission_phase_name(m, (size_t)parent) : "-", r->t_start,
               r->t_end, r->state == LV_PHASE_DONE ? rep->stop_name : "-", rep->stats.steps,
               rep->stats.rhs_evals, rep->stats.state_events, rep->stats.time_events,
               1e3 * rep->stats.cpu_time, phase_state_name(r->state));
        if (r->state == LV_PHASE_FAILED)
            fprintf(stderr, "lvsim: %s\n", r->error);
    }
    fflush(stdout);
}

static int cmd_check(int argc, char **argv)
{
    if (argc != 1)
        return usage_error("check takes one mission file", NULL);
    lv_mission *m;
    lv_err err;
    lv_status st = lv_mission_load(argv[0], &m, &err);
    if (st != LV_OK) {
        fprintf(stderr, "%s\n", err.msg);
        return exit_code_for(st) == EXIT_SIM ? EXIT_INPUT : exit_code_for(st);
    }
    printf("%s: mission '%s' is valid: %zu phases\n", argv[0], lv_mission_name(m),
           lv_mission_phase_count(m));
    lv_mission_free(m);
    return EXIT_OK;
}

static int cmd_run(int argc, char **argv)
{
    const char *path = NULL, *outdir = "lvsim-out";
    int json = 0, threads = 2, plots = 1;
    for (int i = 0; i < argc; i++) {
        if (strcmp(argv[i], "-o") == 0 || strcmp(argv[i], "--threads") == 0) {
            if (i + 1 >= argc)
                return usage_error("missing value for option", argv[i]);
            if (argv[i][1] == 'o')
                outdir = argv[++i];
            else if (!parse_int(argv[++i], &threads) || threads < 1)
                return usage_error("--threads needs a count >= 1, got", argv[i]);
        } else if (strcmp(argv[i], "--json") == 0) {
            json = 1;
        } else if (strcmp(argv[i], "--no-plots") == 0) {
            plots = 0;
        } else if (argv[i][0] == '-' || path != NULL) {
            return usage_error("unexpected argument", argv[i]);
        } else {
            path = argv[i];
        }
    }
    if (path == NULL)
        return usage_error("run needs a mission file", NULL);
    lv_mission *m;
    lv_err err;
    lv_status st = lv_mission_load(path, &m, &err);
    if (st != LV_OK) {
        fprintf(stderr, "%s\n", err.msg);
        return exit_code_for(st) == EXIT_SIM ? EXIT_INPUT : exit_code_for(st);
    }
    if (!json) {
        printf("mission '%s': %zu phases -> %s/\n", lv_mission_name(m), lv_mission_phase_count(m),
               outdir);
        printf("%-3s %-12s %-10s %9s %9s  %-10s %7s %8s %4s %4s %9s  %s\n", "#", "phase", "from",
               "t0 [s]", "t1 [s]", "end", "steps", "rhs", "sev", "tev", "cpu [ms]", "status");
    }
    lv_run *run = NULL;
    lv_status run_st = lv_run_create(m, &run, &err);
    if (run_st != LV_OK) {
        fprintf(stderr, "lvsim: %s\n", err.msg);
        lv_mission_free(m);
        return exit_code_for(run_st);
    }
    lv_run_options opt = {.outdir = outdir, .threads = threads,
                          .on_phase = json ? NULL : print_phase_row};
    run_st = lv_run_execute(run, &opt, &err);
    lv_err serr;
    lv_status sum_st = lv_run_write_summary(run, outdir, &serr);
    /* post-processing reads the results folder, as `lvsim export` and `lvsim plot` do */
    if (sum_st == LV_OK)
        sum_st = lv_export_run(outdir, LV_EXPORT_ALL, &serr);
    if (sum_st == LV_OK && plots)
        sum_st = lv_plot_run(outdir, &serr);
    if (sum_st != LV_OK)
        fprintf(stderr, "lvsim: %s\n", serr.msg);
    if (json) {
        char path_json[4200];
        snprintf(path_json, sizeof path_json, "%s/summary.json", outdir);
        FILE *f = fopen(path_json, "r");
        int c;
        while (f != NULL && (c = fgetc(f)) != EOF)
            putchar(c);
        if (f != NULL)
            fclose(f);
    } else {
        printf("results: %s/ (phase_<k>_<name>.mat/.csv, body_<stage>.csv, summary.json, "
               "mission.czml, mission.kml, <stage>.oem%s)\n",
               outdir, plots ? ", plots/, index.html" : "");
    }
    if (run_st != LV_OK)
        fprintf(stderr, "lvsim: %s\n", err.msg);
    lv_run_free(run);
    lv_mission_free(m);
    if (run_st != LV_OK)
        return exit_code_for(run_st);
    return sum_st == LV_OK ? EXIT_OK : EXIT_INPUT;
}

static int cmd_compare(int argc, char **argv)
{
    const char *path = NULL, *method = NULL;
    double tol = 0.0, dt = 1.0;
    int json = 0;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--json") == 0) {
            json = 1;
        } else if (strcmp(a, "--method") == 0 || strcmp(a, "--tolerance") == 0 ||
                   strcmp(a, "--interval") == 0) {
            if (i + 1 >= argc)
                return usage_error("missing value for option", a);
            const char *v = argv[++i];
            if (a[2] == 'm')
                method = v;
            else if (!parse_double(v, a[2] == 't' ? &tol : &dt))
                return usage_error("not a finite number:", v);
        } else if (a[0] == '-' || path != NULL) {
            return usage_error("unexpected argument", a);
        } else {
            path = a;
        }
    }
    if (path == NULL)
        return usage_error("compare needs a mission file", NULL);
    if (!(dt > 0.0))
        return usage_error("--interval must be > 0", NULL);
    lv_compare_report rep;
    lv_err err;
    lv_mission *m = NULL;
    lv_status st = lv_mission_load(path, &m, &err);
    if (st == LV_OK)
        st = lv_mission_compare(m, method, tol, dt, &rep, &err);
    lv_mission_free(m);
    if (st != LV_OK) {
        fprintf(stderr, "%s\n", err.msg);
        return exit_code_for(st);
    }
    const lv_compare_side *sd[2] = {&rep.e2e, &rep.seq};
    if (json) {
        printf("{\"mission\": ");
        json_string(path);
        printf(", \"output_interval\": %.17g", dt);
        const char *nm[2] = {"end_to_end", "sequential"};
        for (int i = 0; i < 2; i++)
            printf(",\n \"%s\": {\"method\": \"%s\", \"tolerance\": %.17g, \"states\": %zu, "
                   "\"state_events\": %ld, \"time_events\": %ld, \"steps\": %ld, "
                   "\"rhs_evals\": %ld, \"jac_evals\": %ld, \"cpu_time\": %.9g}",
                   nm[i], sd[i]->method, sd[i]->tolerance, sd[i]->n_states, sd[i]->state_events,
                   sd[i]->time_events, sd[i]->steps, sd[i]->rhs_evals, sd[i]->jac_evals,
                   sd[i]->cpu_time);
        printf(",\n \"bodies\": [");
        for (size_t b = 0; b < rep.n_bodies; b++)
            printf("%s\n  {\"name\": \"%s\", \"common_times\": %zu, \"max_dpos\": %.9g, "
                   "\"max_dvel\": %.9g, \"max_dmass\": %.9g}",
                   b ? "," : "", rep.bodies[b].name, rep.bodies[b].n_common,
                   rep.bodies[b].max_dpos, rep.bodies[b].max_dvel, rep.bodies[b].max_dmass);
        printf("]}\n");
        return EXIT_OK;
    }
    printf("%s: end-to-end versus sequential (the paper's Table 2)\n\n", path);
    printf("%-28s %14s %14s\n", "", "end-to-end", "sequential");
    printf("%-28s %14s %14s\n", "integration method", rep.e2e.method, rep.seq.method);
    printf("%-28s %14g %14g\n", "integration tolerance", rep.e2e.tolerance, rep.seq.tolerance);
    printf("%-28s %14zu %14zu\n", "number of states", rep.e2e.n_states, rep.seq.n_states);
    printf("%-28s %14ld %14ld\n", "state events (total)", rep.e2e.state_events,
           rep.seq.state_events);
    printf("%-28s %14ld %14ld\n", "time events (total)", rep.e2e.time_events,
           rep.seq.time_events);
    printf("%-28s %14ld %14ld\n", "steps", rep.e2e.steps, rep.seq.steps);
    printf("%-28s %14ld %14ld\n", "RHS evaluations", rep.e2e.rhs_evals, rep.seq.rhs_evals);
    printf("%-28s %14ld %14ld\n", "Jacobian evaluations", rep.e2e.jac_evals, rep.seq.jac_evals);
    printf("%-28s %14.3f %14.3f\n", "CPU time [ms]", 1e3 * rep.e2e.cpu_time,
           1e3 * rep.seq.cpu_time);
    printf("\nlargest difference at %g s output times common to both:\n", dt);
    printf("%-12s %8s %14s %14s %14s\n", "body", "times", "position [m]", "velocity [m/s]",
           "mass [kg]");
    for (size_t b = 0; b < rep.n_bodies; b++)
        printf("%-12s %8zu %14.3e %14.3e %14.3e\n", rep.bodies[b].name, rep.bodies[b].n_common,
               rep.bodies[b].max_dpos, rep.bodies[b].max_dvel, rep.bodies[b].max_dmass);
    return EXIT_OK;
}

/* Runs argv[0] with argv and waits; returns its exit status, or -1. */
static int run_program(char *const *args)
{
    pid_t pid = fork();
    if (pid < 0)
        return -1;
    if (pid == 0) {
        execv(args[0], args);
        _exit(127);
    }
    int status;
    if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status))
        return -1;
    return WEXITSTATUS(status);
}

static int file_exists(const char *dir, const char *name)
{
    char path[4200];
    struct stat sb;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return stat(path, &sb) == 0;
}

/* lvsim view OUTDIR [--port N] [--stage-only]: the results folder becomes a static site
 * (OUTDIR/viewer/ with the CesiumJS page and its assets, ~14 MB) served on 127.0.0.1. */
static int cmd_view(int argc, char **argv)
{
    const char *dir = NULL;
    int port = 8765, stage_only = 0;
    for (int i = 0; i < argc; i++) {
        if (strcmp(argv[i], "--port") == 0) {
            if (i + 1 >= argc || !parse_int(argv[i + 1], &port) || port < 1 || port > 65535)
                return usage_error("--port needs a number from 1 to 65535", NULL);
            i++;
        } else if (strcmp(argv[i], "--stage-only") == 0) {
            stage_only = 1;
        } else if (argv[i][0] == '-' || dir != NULL) {
            return usage_error("unexpected argument", argv[i]);
        } else {
            dir = argv[i];
        }
    }
    if (dir == NULL)
        return usage_error("view needs a results folder (lvsim run -o OUTDIR)", NULL);
    if (!file_exists(dir, "summary.json")) {
        fprintf(stderr, "lvsim view: %s/summary.json not found: run a mission first "
                        "(lvsim run MISSION.yaml -o %s)\n", dir, dir);
        return EXIT_INPUT;
    }
    lv_err err;
    if (!file_exists(dir, "mission.czml") && lv_export_run(dir, LV_EXPORT_CZML, &err) != LV_OK) {
        fprintf(stderr, "lvsim view: %s\n", err.msg);
        return EXIT_INPUT;
    }
    if (!file_exists(dir, "viewer/VERSION")) {
        /* the installed (or build tree's) share/lvsim/viewer; stage.sh copies from its folder */
        char script[4200];
        if (lv_data_find(NULL, "viewer/stage.sh", script, sizeof script, &err) != LV_OK) {
            fprintf(stderr, "lvsim view: %s\n", err.msg);
            return EXIT_INTERNAL;
        }
        char *args[] = {script, (char *)dir, NULL}; /* executable, with its own #! */
        if (run_program(args) != 0) {
            fprintf(stderr, "lvsim view: staging the viewer with %s failed\n", script);
            return EXIT_INTERNAL;
        }
    }
    if (stage_only) {
        printf("viewer staged in %s/viewer/ (open with: lvsim view %s)\n", dir, dir);
        return EXIT_OK;
    }
    char port_s[16];
    snprintf(port_s, sizeof port_s, "%d", port);
    printf("lvsim view: http://127.0.0.1:%d/viewer/  (serving %s; Ctrl-C to stop)\n", port, dir);
    fflush(stdout);
    char *args[] = {"/usr/bin/python3", "-m", "http.server", "--bind", "127.0.0.1", port_s,
                    "--directory", (char *)dir, NULL};
    execv(args[0], args);
    fprintf(stderr, "lvsim view: cannot start %s: %s\n", args[0], strerror(errno));
    return EXIT_INTERNAL;
}

/* lvsim plot OUTDIR */
static int cmd_plot(int argc, char **argv)
{
    if (argc != 1 || argv[0][0] == '-')
        return usage_error("plot takes one results folder (lvsim run -o OUTDIR)", NULL);
    lv_err err;
    lv_status st = lv_plot_run(argv[0], &err);
    if (st != LV_OK) {
        fprintf(stderr, "lvsim plot: %s\n", err.msg);
        return st == LV_ERR_NOMEM ? EXIT_INTERNAL : EXIT_INPUT;
    }
    printf("plots in %s/plots/, report %s/index.html\n", argv[0], argv[0]);
    return EXIT_OK;
}

/* lvsim export OUTDIR [--format czml,kml,oem] */
static int cmd_export(int argc, char **argv)
{
    const char *dir = NULL;
    unsigned formats = 0;
    for (int i = 0; i < argc; i++) {
        if (strcmp(argv[i], "--format") == 0) {
            if (i + 1 >= argc)
                return usage_error("missing value for option", "--format");
            const char *f = argv[++i];
            if (strstr(f, "czml")) formats |= LV_EXPORT_CZML;
            if (strstr(f, "kml")) formats |= LV_EXPORT_KML;
            if (strstr(f, "oem")) formats |= LV_EXPORT_OEM;
            if (formats == 0)
                return usage_error("--format takes czml, kml, oem (comma-separated), got", f);
        } else if (argv[i][0] == '-' || dir != NULL) {
            return usage_error("unexpected argument", argv[i]);
        } else {
            dir = argv[i];
        }
    }
    if (dir == NULL)
        return usage_error("export needs a results folder (lvsim run -o OUTDIR)", NULL);
    lv_err err;
    lv_status st = lv_export_run(dir, formats ? formats : LV_EXPORT_ALL, &err);
    if (st != LV_OK) {
        fprintf(stderr, "lvsim export: %s\n", err.msg);
        return st == LV_ERR_NOMEM ? EXIT_INTERNAL : EXIT_INPUT;
    }
    printf("exports written to %s/ (mission.czml, mission.kml, <stage>.oem for orbital "
           "portions)\n", dir);
    return EXIT_OK;
}

/* lvsim atmosphere ALT_M... [--model NAME]: one line per altitude. */
static int cmd_atmosphere(int argc, char **argv)
{
    const char *model = "us76";
    double *alt = calloc((size_t)argc + 1, sizeof *alt);
    lv_atmo_state *out = calloc((size_t)argc + 1, sizeof *out);
    size_t n = 0;
    int rc = EXIT_OK;
    if (alt == NULL || out == NULL) {
        rc = EXIT_INTERNAL;
        goto done;
    }
    for (int i = 0; i < argc; i++) {
        if (strcmp(argv[i], "--model") == 0) {
            if (i + 1 >= argc) {
                rc = usage_error("missing value for option", "--model");
                goto done;
            }
            model = argv[++i];
        } else if (!parse_double(argv[i], &alt[n++])) {
            fprintf(stderr, "lvsim atmosphere: '%s' is not an altitude in m\n", argv[i]);
            rc = EXIT_INPUT;
            goto done;
        }
    }
    if (n == 0) {
        rc = usage_error("atmosphere needs at least one altitude in m", NULL);
        goto done;
    }
    lv_err err;
    lv_status st = lv_atmo_eval_by_name(model, alt, n, out, &err);
    if (st != LV_OK) {
        fprintf(stderr, "lvsim atmosphere: %s\n", err.msg);
        rc = exit_code_for(st) == EXIT_SIM ? EXIT_INPUT : exit_code_for(st);
        goto done;
    }
    printf("# %s: altitude [m]  T [K]  p [Pa]  rho [kg/m3]  a [m/s]  mu [Pa s]\n", model);
    for (size_t i = 0; i < n; i++)
        printf("%.9g %.9g %.9g %.9g %.9g %.9g\n", alt[i], out[i].T, out[i].p, out[i].rho,
               out[i].a, out[i].mu);
done:
    free(alt);
    free(out);
    return rc;
}

/* lvsim gravity LAT_DEG LON_DEG ALT_M [--model SPEC] [--planet NAME] [--effective] */
static int cmd_gravity(int argc, char **argv)
{
    const char *spec = "sh", *planet_name = "earth";
    int effective = 0;
    double v[3];
    int npos = 0;
    for (int i = 0; i < argc; i++) {
        if (strcmp(argv[i], "--model") == 0 || strcmp(argv[i], "--planet") == 0) {
            if (i + 1 >= argc)
                return usage_error("missing value for option", argv[i]);
            if (argv[i][2] == 'm')
                spec = argv[++i];
            else
                planet_name = argv[++i];
        } else if (strcmp(argv[i], "--effective") == 0) {
            effective = 1;
        } else if (npos < 3 && parse_double(argv[i], &v[npos])) {
            npos++;
        } else {
            fprintf(stderr, "lvsim gravity: unexpected argument '%s' (expected LAT_DEG LON_DEG "
                            "ALT_M as numbers)\n", argv[i]);
            return EXIT_INPUT;
        }
    }
    if (npos != 3)
        return usage_error("gravity needs LAT_DEG LON_DEG ALT_M", NULL);
    const double lat_deg = v[0], lon_deg = v[1], alt_m = v[2];
    if (fabs(lat_deg) > 90.0 || fabs(lon_deg) > 360.0) {
        fprintf(stderr, "lvsim gravity: latitude %g deg must be within [-90, 90] and longitude "
                        "%g deg within [-360, 360]\n", lat_deg, lon_deg);
        return EXIT_INPUT;
    }
    lv_err err;
    lv_planet planet;
    lv_gravity_config cfg;
    lv_gravity *g = NULL;
    lv_gravity_local loc;
    lv_status st = lv_planet_by_name(planet_name, &planet, &err);
    if (st == LV_OK && !(alt_m > -0.5 * planet.a)) {
        fprintf(stderr, "lvsim gravity: altitude %g m is below half the planet's radius\n", alt_m);
        return EXIT_INPUT;
    }
    if (st == LV_OK)
        st = lv_gravity_parse_spec(spec, &cfg, &err);
    if (st == LV_OK)
        st = lv_gravity_create(&planet, &cfg, &g, &err);
    const double deg = LV_DEG; /* user interface: degrees */
    if (st == LV_OK)
        st = lv_gravity_at_geodetic(g, &planet, lat_deg * deg, lon_deg * deg, alt_m, &loc, &err);
    lv_gravity_free(g);
    if (st != LV_OK) {
        fprintf(stderr, "lvsim gravity: %s\n", err.msg);
        return st == LV_ERR_NOMEM ? EXIT_INTERNAL : EXIT_INPUT;
    }
    const double *gv = effective ? loc.g_eff_ned : loc.g_ned;
    printf("# %s, model %s, planet %s, lat %g deg, lon %g deg, alt %g m\n",
           effective ? "gravity (gravitation + centrifugal)" : "gravitation",
           spec, planet.name, lat_deg, lon_deg, alt_m);
    printf("# g_north [m/s2]  g_east [m/s2]  g_down [m/s2]  |g| [m/s2]\n");
    printf("%.10g %.10g %.10g %.10g\n", gv[0], gv[1], gv[2],
           sqrt(gv[0] * gv[0] + gv[1] * gv[1] + gv[2] * gv[2]));
    return EXIT_OK;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        print_help(stderr);
        return EXIT_INPUT;
    }
    const char *cmd = argv[1];
    if (strcmp(cmd, "help") == 0 || strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0) {
        print_help(stdout);
        return EXIT_OK;
    }
    if (strcmp(cmd, "version") == 0 || strcmp(cmd, "--version") == 0) {
        printf("lvsim %s\n", LVSIM_VERSION);
        return EXIT_OK;
    }
    if (strcmp(cmd, "models") == 0)
        return cmd_models();
    if (strcmp(cmd, "vars") == 0)
        return cmd_vars(argc - 2, argv + 2);
    if (strcmp(cmd, "simulate") == 0)
        return cmd_simulate(argc - 2, argv + 2);
    if (strcmp(cmd, "run") == 0)
        return cmd_run(argc - 2, argv + 2);
    if (strcmp(cmd, "check") == 0)
        return cmd_check(argc - 2, argv + 2);
    if (strcmp(cmd, "compare") == 0)
        return cmd_compare(argc - 2, argv + 2);
    if (strcmp(cmd, "export") == 0)
        return cmd_export(argc - 2, argv + 2);
    if (strcmp(cmd, "plot") == 0)
        return cmd_plot(argc - 2, argv + 2);
    if (strcmp(cmd, "view") == 0)
        return cmd_view(argc - 2, argv + 2);
    if (strcmp(cmd, "atmosphere") == 0)
        return cmd_atmosphere(argc - 2, argv + 2);
    if (strcmp(cmd, "gravity") == 0)
        return cmd_gravity(argc - 2, argv + 2);
    return usage_error("unknown command", cmd);
}
