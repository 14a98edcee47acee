/* cmd_simulate.c - `lvsim simulate MODEL [options]`: one lv_simulate() of a built-in model,
 * the settings of Dymola's simulateExtendedModel; the report as text or JSON (cJSON).
 */
#define _POSIX_C_SOURCE 200809L

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"
#include "common.h"

/* The report as one JSON object: model, ok, method, tolerance, end_time, stop, [error],
 * stats {...}, final {name: value} (empty unless ok). */
static cJSON *report_json(const lv_model_def *m, const lv_sim_settings *s, lv_status st,
                          const lv_err *err, const lv_sim_report *rep, const double *finals)
{
    cJSON *doc = cJSON_CreateObject();
    if (doc == NULL)
        return NULL;
    cJSON_AddStringToObject(doc, "model", m->name);
    cJSON_AddBoolToObject(doc, "ok", st == LV_OK);
    cJSON_AddStringToObject(doc, "method", s->method);
    cJSON_AddNumberToObject(doc, "tolerance", s->tolerance);
    cJSON_AddNumberToObject(doc, "end_time", rep->end_time);
    cJSON_AddStringToObject(doc, "stop", rep->stop_name);
    if (st != LV_OK)
        cJSON_AddStringToObject(doc, "error", err->msg);
    cJSON *stats = cJSON_AddObjectToObject(doc, "stats");
    cJSON_AddNumberToObject(stats, "states", (double)rep->n_states);
    cJSON_AddNumberToObject(stats, "steps", (double)rep->stats.steps);
    cJSON_AddNumberToObject(stats, "rhs_evals", (double)rep->stats.rhs_evals);
    cJSON_AddNumberToObject(stats, "rhs_evals_steps", (double)rep->stats.rhs_evals_steps);
    cJSON_AddNumberToObject(stats, "rhs_evals_output", (double)rep->stats.rhs_evals_output);
    cJSON_AddNumberToObject(stats, "row_evals", (double)rep->stats.row_evals);
    cJSON_AddNumberToObject(stats, "jac_evals", (double)rep->stats.jac_evals);
    cJSON_AddNumberToObject(stats, "state_events", (double)rep->stats.state_events);
    cJSON_AddNumberToObject(stats, "time_events", (double)rep->stats.time_events);
    cJSON_AddNumberToObject(stats, "restarts", (double)rep->stats.restarts);
    cJSON_AddNumberToObject(stats, "rows", (double)rep->stats.output_rows);
    cJSON_AddNumberToObject(stats, "cpu_time", rep->stats.cpu_time);
    cJSON *fin = cJSON_AddObjectToObject(doc, "final");
    for (size_t i = 0; st == LV_OK && i < s->n_final; i++)
        cJSON_AddNumberToObject(fin, s->final_names[i], finals[i]);
    return doc;
}

static void print_report(const lv_model_def *m, const lv_sim_settings *s, lv_status st,
                         const lv_sim_report *rep, const double *finals)
{
    printf("model %s, method %s, tolerance %g: %s at t = %.9g s (%s)\n", m->name, s->method,
           s->tolerance, st == LV_OK ? "ok" : "FAILED", rep->end_time, rep->stop_name);
    printf("  states %zu, steps %ld, rhs evals %ld, jacobians %ld, state events %ld, "
           "time events %ld, cpu %.3f ms\n",
           rep->n_states, rep->stats.steps, rep->stats.rhs_evals, rep->stats.jac_evals,
           rep->stats.state_events, rep->stats.time_events, 1e3 * rep->stats.cpu_time);
    for (size_t i = 0; st == LV_OK && i < s->n_final; i++)
        printf("  %-16s = %.12g\n", s->final_names[i], finals[i]);
    /* exactly the files written: each format asked for, under its failed name if it failed */
    const unsigned fm = s->result_file != NULL && rep->stats.output_rows > 0 ? s->result_formats : 0;
    const char *fail = st == LV_OK ? "" : ".failed", *ext;
    for (size_t i = 0, n = 0; lv_result_format_info(i, &ext, NULL) != NULL; i++)
        if (fm & (1u << i))
            printf("%s%s%s%s", n++ ? ", " : "  result: ", s->result_file, fail, ext);
    if (fm != 0)
        printf("\n");
}

/* -o PATH names files PATH.mat and PATH.csv: PATH must be a file name that can take them
 * (not empty, not ending in '/', not an existing device, pipe or socket such as /dev/null). */
static int check_result_stem(const char *path)
{
    const size_t n = strlen(path);
    const char *base = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    const char *dot = strrchr(base, '.');
    struct stat sb;
    if (strcmp(base, ".") == 0 || strcmp(base, "..") == 0 ||
        (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode))) {
        fprintf(stderr, "lvsim: -o '%s' is a folder: give a file path without extension in it "
                "(e.g. '%s%sdsres': PATH.mat and PATH.csv are written)\n", path, path,
                n > 0 && path[n - 1] == '/' ? "" : "/");
        return EXIT_INPUT;
    }
    if (dot != NULL && (strcmp(dot, ".mat") == 0 || strcmp(dot, ".csv") == 0)) {
        fprintf(stderr, "lvsim: -o '%s': give the path without its extension ('%.*s'): "
                "PATH.mat and PATH.csv are written\n", path, (int)(dot - path), path);
        return EXIT_INPUT;
    }
    if (n == 0 || path[n - 1] == '/') {
        fprintf(stderr, "lvsim: -o '%s': give a file path without extension (PATH.mat and "
                "PATH.csv are written), or --format none to write nothing\n", path);
        return EXIT_INPUT;
    }
    if (stat(path, &sb) == 0 && !S_ISREG(sb.st_mode) && !S_ISDIR(sb.st_mode)) {
        fprintf(stderr, "lvsim: -o '%s' is a device, pipe or socket: PATH.mat and PATH.csv would "
                "be written next to it; use --format none to write nothing\n", path);
        return EXIT_INPUT;
    }
    return EXIT_OK;
}

/* The output grid's rows, before anything runs: refused beyond max_rows when only the stop time
 * ends the run (the model has no events); a model with events is held to max_rows as it runs. */
static int check_grid_rows(const lv_model_def *m, const lv_sim_settings *s, double max_rows)
{
    const double span = s->stop_time - s->start_time;
    double rows;
    if (s->output_interval > 0.0)
        rows = ceil(span / s->output_interval - 1e-9) + 1.0;
    else
        rows = (s->number_of_intervals > 0 ? s->number_of_intervals : 500) + 1.0;
    if (!(span > 0.0) || m->n_events > 0 || !(rows > max_rows))
        return EXIT_OK;
    char r[32], l[32];
    snprintf(r, sizeof r, rows < 1e7 ? "%.0f" : "%.3g", rows);
    snprintf(l, sizeof l, max_rows < 1e7 ? "%.0f" : "%.3g", max_rows);
    fprintf(stderr, "lvsim: model '%s' would write %s rows (%.6g s%s) - more than the limit of "
            "%s rows, and nothing but --stop ends it; give a larger --interval, fewer "
            "--intervals or an earlier --stop, or raise the limit with --max-rows\n", m->name, r,
            span, s->output_interval > 0.0 ? " at the --interval" : "", l);
    return EXIT_INPUT;
}

static int simulate_run(const cli_cmd *self, int argc, char **argv)
{
    if (argc < 1 || is_option(argv[0]))
        return usage_error(self, "simulate needs a model name first", NULL);
    const lv_model_def *m = find_model(argv[0]);
    if (m == NULL)
        return EXIT_INPUT;

    lv_sim_settings s;
    lv_sim_settings_default(&s);
    int json = 0, force = 0;
    int rc = EXIT_OK;
    double max_rows = CLI_DEFAULT_MAX_ROWS;
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
        static const char *const with_value[] = {
            "--start", "--stop", "--interval", "--tolerance", "--fixed-step", "--intervals",
            "--method", "-o", "--format", "--set", "--final", "--max-steps", "--max-rows",
            NULL};
        int known = 0;
        for (size_t k = 0; with_value[k] != NULL; k++)
            known |= strcmp(a, with_value[k]) == 0;
        if (strcmp(a, "--json") == 0) {
            json = 1;
            continue;
        }
        if (strcmp(a, "--force") == 0) {
            force = 1;
            continue;
        }
        if (!known) {
            rc = usage_error(self, is_option(a) ? "unknown option" : "unexpected argument", a);
            goto out;
        }
        const char *val = option_value(argc, argv, &i);
        if (val == NULL) {
            rc = usage_error(self, "missing value for option", a);
            goto out;
        }
        if (strcmp(a, "--start") == 0 || strcmp(a, "--stop") == 0 ||
            strcmp(a, "--interval") == 0 || strcmp(a, "--tolerance") == 0 ||
            strcmp(a, "--fixed-step") == 0) {
            double v;
            if (!parse_double(val, &v)) {
                fprintf(stderr, "lvsim: %s: '%s' is not a finite number\n", a, val);
                rc = EXIT_INPUT;
                goto out;
            }
            /* held to the ranges lv_simulate takes (a mission phase's integrator keys) */
            if (strcmp(a, "--tolerance") == 0 && !parse_tolerance_option(self, a, val, &v)) {
                rc = EXIT_INPUT;
                goto out;
            }
            if ((strcmp(a, "--interval") == 0 || strcmp(a, "--fixed-step") == 0) && v < 0.0) {
                fprintf(stderr, "lvsim: %s: '%s' s must be >= 0 (0: %s)\n", a, val,
                        a[2] == 'i' ? "the --intervals grid" : "the output interval");
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
        } else if (strcmp(a, "--max-rows") == 0) {
            if (!parse_count(val, &max_rows)) {
                rc = usage_error(self, "--max-rows needs a whole number from 1 to 1e15, got", val);
                goto out;
            }
        } else if (strcmp(a, "--max-steps") == 0) {
            int n;
            double c; /* 100000 or 1e5, as --max-rows */
            if (!parse_int(val, &n) && parse_count(val, &c) && c <= INT_MAX)
                n = (int)c;
            else if (!parse_int(val, &n))
                n = 0;
            if (n <= 0) {
                fprintf(stderr, "lvsim: --max-steps: '%s' is not a whole count from 1 to %d\n",
                        val, INT_MAX);
                rc = EXIT_INPUT;
                goto out;
            }
            s.max_steps = n;
        } else if (strcmp(a, "--method") == 0) {
            if (!parse_method_option(self, a, val)) {
                rc = EXIT_INPUT;
                goto out;
            }
            s.method = val;
        } else if (strcmp(a, "-o") == 0) {
            if ((rc = check_result_stem(val)) != EXIT_OK)
                goto out;
            s.result_file = val;
        } else if (strcmp(a, "--format") == 0) {
            name_list formats = {{0}, 0};
            name_list_add_results(&formats);
            if (!parse_name_list(self, a, "format", &formats, 1, val, &s.result_formats)) {
                rc = EXIT_INPUT;
                goto out;
            }
            if (s.result_formats == 0) /* none */
                s.result_file = NULL; /* and result_formats 0: -o after it writes nothing */
        } else if (strcmp(a, "--set") == 0) {
            const char *eq = strchr(val, '=');
            double v;
            if (eq == NULL || eq == val || !parse_double(eq + 1, &v)) {
                fprintf(stderr, "lvsim: --set '%s': expected NAME=NUMBER\n", val);
                rc = EXIT_INPUT;
                goto out;
            }
            set_names[s.n_initial] = strndup(val, (size_t)(eq - val));
            if (set_names[s.n_initial] == NULL) {
                fprintf(stderr, "lvsim: out of memory\n");
                rc = EXIT_INTERNAL;
                goto out;
            }
            set_values[s.n_initial++] = v;
        } else { /* --final */
            final_names[s.n_final++] = val;
        }
    }
    /* the result files it may write (a failed run's under .failed): none replaces a file
     * lvsim cannot prove it wrote, unless --force (lv_output_check) */
    if (s.result_file != NULL) {
        size_t n = 0; /* the final names of every format, then the failed ones */
        while (lv_result_format_info(n, NULL, NULL) != NULL)
            n++;
        for (size_t k = 0; k < 2 * n; k++) {
            const char *ext;
            lv_result_format_info(k % n, &ext, NULL);
            if (!(s.result_formats & (1u << (k % n))))
                continue;
            char name[4200];
            lv_err cerr;
            snprintf(name, sizeof name, "%s%s%s", s.result_file, k < n ? "" : ".failed", ext);
            if (lv_output_check(name, NULL, force ? LV_OUTPUT_REPLACE : 0u, &cerr) != LV_OK) {
                rc = print_err("lvsim", &cerr, EXIT_INPUT);
                goto out;
            }
        }
    }
    s.initial_names = (const char *const *)set_names;
    s.initial_values = set_values;
    s.final_names = final_names;
    /* bounded: the output grid's rows before anything runs when nothing but the stop time
     * ends the run (a model without events), and as it runs otherwise (lv_sim_settings) */
    s.max_rows = max_rows;
    if ((rc = check_grid_rows(m, &s, max_rows)) != EXIT_OK)
        goto out;
    s.stop = &cli_stop_flag; /* Ctrl-C, SIGTERM: cancelled within a step, files marked failed */
    cli_catch_stop();

    lv_sim_report rep;
    lv_err err;
    lv_status st = lv_simulate(m, NULL, &s, finals, &rep, &err);
    if (st != LV_OK) {
        /* the settings' names are Dymola's (initialNames[k]): the option that gave them */
        char opt[32];
        int k = -1;
        if (sscanf(err.msg, "initialNames[%d]:", &k) == 1 && k >= 0 && (size_t)k < s.n_initial) {
            snprintf(opt, sizeof opt, "initialNames[%d]", k);
            restage(err.msg, sizeof err.msg, opt, "--set");
        }
        fprintf(stderr, "lvsim: %s\n", err.msg);
    }
    if (exit_code_for(st) == EXIT_INPUT && rep.stats.output_rows == 0 && !json) { /* refused */
        lv_sim_report_clear(&rep);
        rc = EXIT_INPUT;
        goto out;
    }
    if (json)
        rc = print_json(report_json(m, &s, st, &err, &rep, finals));
    else
        print_report(m, &s, st, &rep, finals);
    lv_sim_report_clear(&rep);
    if (rc == EXIT_OK)
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

const cli_cmd cli_cmd_simulate = {
    "simulate",
    "one run of a built-in model (Dymola's simulateExtendedModel)",
    "MODEL [options]",
    "Simulates a built-in model (see 'lvsim models', 'lvsim vars MODEL') once with\n"
    "lv_simulate and prints the report: method, tolerance, end time and why it ended,\n"
    "statistics, and the final values asked for; result files unless --format none.\n"
    "\n"
    "options:\n"
    "  --start T, --stop T     start and stop time [s] (default 0, 1)\n"
    "  --intervals N           output grid: number of intervals (default 500)\n"
    "  --interval DT           output grid: interval [s]; wins over --intervals (default 0)\n"
    "  --method M              dassl | cvode-adams | dopri5 | rk4 | euler | dp5 | dop853 |\n"
    "                          auto (default dassl)\n"
    "  --tolerance TOL         relative tolerance, 1e-14 to 0.1 (default 1e-4)\n"
    "  --fixed-step H          step of rk4 and euler [s] (default: the output interval)\n"
    "  --max-steps N           internal steps allowed in total (default 1e6)\n"
    "  --max-rows N            output rows allowed (default 1e6): a model without events is\n"
    "                          refused beyond it before it runs, one with events stopped there\n"
    "  --set NAME=VALUE        start value of a state or parameter, SI (repeatable)\n"
    "  --final NAME            print this variable's final value, or 'time' (repeatable)\n"
    "  -o PATH                 result file path without extension (default dsres); an\n"
    "                          existing PATH.mat or .csv is refused unless --force\n"
    "  --force                 replace existing result files\n"
    "  --format F              result formats, comma-separated (lvsim formats: mat, csv),\n"
    "                          or none (default: all)\n"
    "  --json                  print the report as one JSON object\n"
    "\n"
    "A run the integrator cannot finish exits 3; its partial results are kept as\n"
    "PATH.failed.mat/.csv. Ctrl-C or SIGTERM stops the run there too (exit 130).\n",
    simulate_run,
};
