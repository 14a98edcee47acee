/* cmd_run.c - `lvsim run MISSION.yaml`: every phase of a mission through the run API
 * (lv_run_execute), one table row per phase as it finishes, then summary.json, the
 * trajectory exports and the plots of the results folder (liblvsim_post).
 */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "common.h"

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

/* Copies OUTDIR/summary.json to stdout (run --json). */
static void print_file(const char *outdir, const char *name)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/%s", outdir, name);
    FILE *f = fopen(path, "r");
    if (f == NULL)
        return;
    int c;
    while ((c = fgetc(f)) != EOF)
        putchar(c);
    fclose(f);
}

static int run_run(const cli_cmd *self, int argc, char **argv)
{
    const char *path = NULL, *outdir = "lvsim-out";
    int json = 0, threads = 2, plots = 1;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "-o") == 0 || strcmp(a, "--threads") == 0) {
            const char *v = option_value(argc, argv, &i);
            if (v == NULL)
                return usage_error(self, "missing value for option", a);
            if (a[1] == 'o')
                outdir = v;
            else if (!parse_int(v, &threads) || threads < 1)
                return usage_error(self, "--threads needs a count >= 1, got", v);
        } else if (strcmp(a, "--json") == 0) {
            json = 1;
        } else if (strcmp(a, "--no-plots") == 0) {
            plots = 0;
        } else if (is_option(a)) {
            return usage_error(self, "unknown option", a);
        } else if (path != NULL) {
            return usage_error(self, "unexpected argument", a);
        } else {
            path = a;
        }
    }
    if (path == NULL)
        return usage_error(self, "run needs a mission file", NULL);
    lv_mission *m;
    lv_err err;
    lv_status st = lv_mission_load(path, &m, &err);
    if (st != LV_OK)
        return print_err(NULL, &err, exit_code_for_input(st));
    if (!json) {
        printf("mission '%s': %zu phases -> %s/\n", lv_mission_name(m), lv_mission_phase_count(m),
               outdir);
        printf("%-3s %-12s %-10s %9s %9s  %-10s %7s %8s %4s %4s %9s  %s\n", "#", "phase", "from",
               "t0 [s]", "t1 [s]", "end", "steps", "rhs", "sev", "tev", "cpu [ms]", "status");
    }
    lv_run *run = NULL;
    lv_status run_st = lv_run_create(m, &run, &err);
    if (run_st != LV_OK) {
        lv_mission_free(m);
        return print_err("lvsim", &err, exit_code_for(run_st));
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
        print_err("lvsim", &serr, 0);
    if (json)
        print_file(outdir, "summary.json");
    else
        printf("results: %s/ (phase_<k>_<name>.mat/.csv, body_<stage>.csv, summary.json, "
               "mission.czml, mission.kml, <stage>.oem%s)\n",
               outdir, plots ? ", plots/, index.html" : "");
    if (run_st != LV_OK)
        print_err("lvsim", &err, 0);
    lv_run_free(run);
    lv_mission_free(m);
    if (run_st != LV_OK)
        return exit_code_for(run_st);
    return sum_st == LV_OK ? EXIT_OK : EXIT_INPUT;
}

const cli_cmd cli_cmd_run = {
    "run",
    "run every phase of a mission; results, exports, plots, report",
    "MISSION.yaml [-o OUTDIR] [--threads N] [--json] [--no-plots]",
    "Validates the mission (as 'lvsim check'), runs every phase in dependency order,\n"
    "independent branches in parallel, and prints one line per phase as it finishes.\n"
    "Writes OUTDIR/phase_<k>_<name>.mat/.csv, body_<stage>.csv, summary.json, the exports\n"
    "(mission.czml, mission.kml, <stage>.oem), plots/ and index.html. A failing phase stops\n"
    "only its descendants; the exit code is then 3.\n"
    "\n"
    "options:\n"
    "  -o OUTDIR               results folder, created if missing (default lvsim-out)\n"
    "  --threads N             worker threads for independent branches, >= 1 (default 2)\n"
    "  --json                  print summary.json instead of the table\n"
    "  --no-plots              skip plots/ and index.html\n",
    run_run,
};
