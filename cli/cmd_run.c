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

/* What `run` writes (--outputs): the phase files, the summary and bodies, the exports. */
enum {
    OUT_MAT = 1u, OUT_CSV = 2u, OUT_BODY = 4u, OUT_SUMMARY = 8u,
    OUT_CZML = 16u, OUT_KML = 32u, OUT_OEM = 64u,
    OUT_ALL = 127u
};
static const struct {
    const char *name;
    unsigned flag;
} out_names[] = {{"mat", OUT_MAT},         {"csv", OUT_CSV},   {"body", OUT_BODY},
                 {"summary", OUT_SUMMARY}, {"czml", OUT_CZML}, {"kml", OUT_KML},
                 {"oem", OUT_OEM}};

/* "mat,csv,summary" -> flags; "none" -> 0. Returns 0 and names the bad word in *bad. */
static int parse_outputs(const char *list, unsigned *out, char *bad, size_t cap)
{
    *out = 0;
    if (strcmp(list, "none") == 0)
        return 1;
    const char *p = list;
    while (1) {
        const char *comma = strchr(p, ',');
        const size_t len = comma ? (size_t)(comma - p) : strlen(p);
        unsigned f = 0;
        for (size_t i = 0; i < sizeof out_names / sizeof out_names[0]; i++)
            if (strlen(out_names[i].name) == len && strncmp(out_names[i].name, p, len) == 0)
                f = out_names[i].flag;
        if (f == 0) {
            snprintf(bad, cap, "%.*s", (int)len, p);
            return 0;
        }
        *out |= f;
        if (comma == NULL)
            return 1;
        p = comma + 1;
    }
}

static int run_run(const cli_cmd *self, int argc, char **argv)
{
    const char *path = NULL, *outdir = "lvsim-out";
    int json = 0, threads = 2, plots = 1;
    unsigned outputs = OUT_ALL;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "-o") == 0 || strcmp(a, "--threads") == 0 || strcmp(a, "--outputs") == 0) {
            const char *v = option_value(argc, argv, &i);
            if (v == NULL)
                return usage_error(self, "missing value for option", a);
            char bad[64];
            if (strcmp(a, "--outputs") == 0) {
                if (!parse_outputs(v, &outputs, bad, sizeof bad))
                    return usage_error(self, "--outputs: unknown output (mat, csv, body, "
                                             "summary, czml, kml, oem, none)", bad);
            } else if (a[1] == 'o') {
                outdir = v;
            } else if (!parse_int(v, &threads) || threads < 1) {
                return usage_error(self, "--threads needs a count >= 1, got", v);
            }
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
    /* The exports and the plots read the results folder: they need what they read. */
    const unsigned exports = outputs & (OUT_CZML | OUT_KML | OUT_OEM);
    if (exports && (outputs & (OUT_SUMMARY | OUT_BODY)) != (OUT_SUMMARY | OUT_BODY))
        return usage_error(self, "--outputs: czml, kml and oem read summary and body; add them",
                           NULL);
    if (json && !(outputs & OUT_SUMMARY))
        return usage_error(self, "--json prints summary.json: --outputs needs summary", NULL);
    const int can_plot = (outputs & (OUT_SUMMARY | OUT_BODY | OUT_CSV)) ==
                         (OUT_SUMMARY | OUT_BODY | OUT_CSV);
    plots = plots && can_plot;
    lv_mission *m;
    lv_err err;
    lv_status st = lv_mission_load(path, &m, &err);
    if (st != LV_OK)
        return print_err(NULL, &err, exit_code_for_input(st));
    if (!json) {
        if (outputs != 0)
            printf("mission '%s': %zu phases -> %s/\n", lv_mission_name(m),
                   lv_mission_phase_count(m), outdir);
        else
            printf("mission '%s': %zu phases (nothing written)\n", lv_mission_name(m),
                   lv_mission_phase_count(m));
        printf("%-3s %-12s %-10s %9s %9s  %-10s %7s %8s %4s %4s %9s  %s\n", "#", "phase", "from",
               "t0 [s]", "t1 [s]", "end", "steps", "rhs", "sev", "tev", "cpu [ms]", "status");
    }
    lv_run *run = NULL;
    lv_status run_st = lv_run_create(m, &run, &err);
    if (run_st != LV_OK) {
        lv_mission_free(m);
        return print_err("lvsim", &err, exit_code_for(run_st));
    }
    /* No output at all: a pure in-memory run (no folder, no file, no rows kept). Rows are
     * kept in memory only for the body files, which are merged from them. */
    const unsigned phase_files = outputs & (OUT_MAT | OUT_CSV);
    lv_run_options opt = {.outdir = outputs != 0 ? outdir : NULL, .threads = threads,
                          .on_phase = json ? NULL : print_phase_row,
                          .no_rows = !(outputs & OUT_BODY),
                          .result_formats = phase_files == 0 ? LV_RUN_NO_PHASE_FILES
                                            : (phase_files & OUT_MAT ? LV_RESULT_MAT : 0u) |
                                                  (phase_files & OUT_CSV ? LV_RESULT_CSV : 0u)};
    run_st = lv_run_execute(run, &opt, &err);
    lv_err serr;
    lv_status sum_st = LV_OK;
    const unsigned summary = (outputs & OUT_SUMMARY ? LV_SUMMARY_JSON : 0u) |
                             (outputs & OUT_BODY ? LV_SUMMARY_BODIES : 0u);
    if (summary != 0)
        sum_st = lv_run_write_summary_files(run, outdir, summary, &serr);
    /* post-processing reads the results folder, as `lvsim export` and `lvsim plot` do */
    if (sum_st == LV_OK && exports)
        sum_st = lv_export_run(outdir,
                               (outputs & OUT_CZML ? LV_EXPORT_CZML : 0u) |
                                   (outputs & OUT_KML ? LV_EXPORT_KML : 0u) |
                                   (outputs & OUT_OEM ? LV_EXPORT_OEM : 0u),
                               &serr);
    if (sum_st == LV_OK && plots)
        sum_st = lv_plot_run(outdir, &serr);
    if (sum_st != LV_OK)
        print_err("lvsim", &serr, 0);
    if (json) {
        print_file(outdir, "summary.json");
    } else if (outputs != 0) {
        static const char *const what[] = {"phase_<k>_<name>.mat", "phase_<k>_<name>.csv",
                                           "body_<stage>.csv", "summary.json", "mission.czml",
                                           "mission.kml", "<stage>.oem"};
        printf("results: %s/ (", outdir);
        const char *sep = "";
        for (unsigned i = 0; i < 7; i++)
            if (outputs & (1u << i)) {
                printf("%s%s", sep, what[i]);
                sep = ", ";
            }
        printf("%s)\n", plots ? ", plots/, index.html" : "");
    }
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
    "MISSION.yaml [-o OUTDIR] [--threads N] [--json] [--no-plots] [--outputs LIST]",
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
    "  --no-plots              skip plots/ and index.html\n"
    "  --outputs LIST          what to write, comma-separated: mat, csv (each phase's\n"
    "                          files), body (body_<stage>.csv), summary (summary.json),\n"
    "                          czml, kml, oem (the exports; they need body and summary);\n"
    "                          'none' writes nothing (a run in memory: the table only).\n"
    "                          Default: all of them. Plots are drawn only when csv, body\n"
    "                          and summary are written.\n",
    run_run,
};
