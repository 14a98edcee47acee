/* cmd_run.c - `lvsim run MISSION.yaml`: every phase of a mission through the run API
 * (lv_run_execute) into a private staging folder (lv_outdir.h), one table row per phase in
 * run order, then summary.json, the trajectory exports and the plots; the results folder
 * is replaced as a whole at the end, failed runs included (marked in manifest.json and
 * summary.json), so it never mixes two runs. Progress on stderr (progress.h).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "common.h"
#include "progress.h"

/* One word per phase state: the spelling of summary.json, the report and the viewer. */
static const char *phase_state_name(lv_phase_state st)
{
    switch (st) {
    case LV_PHASE_DONE: return "done";
    case LV_PHASE_FAILED: return "failed";
    case LV_PHASE_SKIPPED: return "skipped";
    default: return "pending";
    }
}

/* Why a phase ended, as summary.json's end.event or end.reason say it. */
static const char *end_word(const lv_phase_result *r)
{
    if (r->state != LV_PHASE_DONE)
        return "-";
    switch (r->report.reason) {
    case LV_STOP_TIME: return "stop_time";
    case LV_STOP_EVENT: return r->report.stop_name;
    default: return "failed";
    }
}

typedef struct run_ui {
    cli_progress *prog;
    int table;          /* print the phase table (not --json) */
    size_t next;        /* the next phase to print, in run order */
    unsigned char *ended;
    int wname;          /* width of the phase-name columns: the longest name, >= 12 */
} run_ui;

/* Width of the end column: the longest end words of the examples ("target_overshoot"). */
#define END_W 16

static void print_row(const lv_run *run, size_t k, int w)
{
    const lv_mission *m = lv_run_mission(run);
    const lv_phase_result *r = lv_run_result(run, k);
    const int parent = lv_mission_phase_parent(m, k);
    const lv_sim_report *rep = &r->report;
    /* skipped, pending, or failed before its simulation started (no times): dashes */
    if (r->state == LV_PHASE_SKIPPED || r->state == LV_PHASE_PENDING || isnan(r->t_start)) {
        printf("%-3zu %-*s %-*s %9s %9s  %-*s %7s %8s %4s %4s %9s  %-11s %s\n", k + 1, w, r->name,
               w, parent >= 0 ? lv_mission_phase_name(m, (size_t)parent) : "-", "-", "-", END_W,
               "-", "-", "-", "-", "-", "-", "-", phase_state_name(r->state));
        return;
    }
    /* the method that ran; for "auto" with why ("dop853: not stiff") */
    printf("%-3zu %-*s %-*s %9.3f %9.3f  %-*s %7ld %8ld %4ld %4ld %9.2f  %-11s %s\n", k + 1, w,
           r->name, w, parent >= 0 ? lv_mission_phase_name(m, (size_t)parent) : "-", r->t_start,
           r->t_end, END_W, end_word(r), rep->stats.steps, rep->stats.rhs_evals,
           rep->stats.state_events, rep->stats.time_events, 1e3 * rep->stats.cpu_time, r->method,
           phase_state_name(r->state));
}

/* on_phase: a phase ended (under the run's lock). Rows are printed in run order: this one
 * and every later one that has already ended; a failure's reason at once on stderr. */
static void on_phase(const lv_run *run, size_t k, const lv_phase_result *r, void *user)
{
    run_ui *ui = user;
    const size_t n = lv_mission_phase_count(lv_run_mission(run));
    progress_print_begin(ui->prog);
    progress_phase_done(ui->prog, k);
    ui->ended[k] = 1;
    if (r->state == LV_PHASE_FAILED)
        fprintf(stderr, "lvsim: %s\n", r->error);
    while (ui->table && ui->next < n && ui->ended[ui->next])
        print_row(run, ui->next++, ui->wname);
    progress_print_end(ui->prog);
}

/* lv_run_options.progress: the run's user pointer is the run_ui (on_phase shares it). */
static int on_progress(const lv_run *run, size_t k, double t, void *user)
{
    const run_ui *ui = user;
    return progress_phase(run, k, t, ui->prog);
}

/* Copies DIR/summary.json to stdout (run --json). */
static void print_file(const char *dir, const char *name)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "r");
    if (f == NULL)
        return;
    int c;
    while ((c = fgetc(f)) != EOF)
        putchar(c);
    fclose(f);
}

static int has_prefix(const char *s, const char *p) { return strncmp(s, p, strlen(p)) == 0; }
static int has_suffix(const char *s, const char *x)
{
    const size_t n = strlen(s), m = strlen(x);
    return n >= m && strcmp(s + n - m, x) == 0;
}

/* "results: OUTDIR/ ..." from the manifest's list: exactly the files written. */
static void print_results(const lv_outdir *od)
{
    const size_t n = lv_outdir_file_count(od);
    const lv_outdir_file *f = lv_outdir_files(od);
    size_t n_phase = 0, n_failed = 0, n_body = 0, n_plots = 0, n_viewer = 0;
    unsigned long long total = 0;
    for (size_t i = 0; i < n; i++) {
        total += f[i].bytes;
        if (has_prefix(f[i].name, "phase_"))
            n_phase++, n_failed += strstr(f[i].name, ".failed.") != NULL;
        else if (has_prefix(f[i].name, "body_") && has_suffix(f[i].name, ".csv"))
            n_body++;
        else if (has_prefix(f[i].name, "plots/"))
            n_plots++;
        else if (has_prefix(f[i].name, "viewer/"))
            n_viewer++;
    }
    char size[32];
    human_bytes((double)total + 0.0, size, sizeof size);
    printf("results: %s/ (%zu files, %s; manifest.json lists each with its SHA-256):\n ",
           lv_outdir_final(od), n + 1, size);
    printf(" manifest.json");
    for (size_t i = 0; i < n; i++)
        if (!has_prefix(f[i].name, "phase_") && !has_prefix(f[i].name, "body_") &&
            strchr(f[i].name, '/') == NULL)
            printf(", %s", f[i].name);
    if (n_phase > 0)
        printf(", %zu phase files (phase_<k>_<name>.mat, .csv%s)", n_phase,
               n_failed ? "; *.failed.* for failed phases" : "");
    if (n_body > 0)
        printf(", %zu body trajectories (body_<stage>.csv)", n_body);
    if (n_plots > 0)
        printf(", plots/ (%zu files)", n_plots);
    if (n_viewer > 0)
        printf(", viewer/ (%zu files)", n_viewer);
    printf("\n");
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
    int json = 0, threads = 2, plots = 1, quiet = 0, force = 0;
    double max_rows = CLI_DEFAULT_MAX_ROWS;
    unsigned outputs = OUT_ALL;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "-o") == 0 || strcmp(a, "--threads") == 0 ||
            strcmp(a, "--max-rows") == 0 || strcmp(a, "--outputs") == 0) {
            const char *v = option_value(argc, argv, &i);
            if (v == NULL)
                return usage_error(self, "missing value for option", a);
            char bad[64];
            if (strcmp(a, "--outputs") == 0) {
                if (!parse_outputs(v, &outputs, bad, sizeof bad))
                    return usage_error(self, "--outputs: unknown output (mat, csv, body, "
                                             "summary, czml, kml, oem, none)", bad);
            } else if (a[1] == 'o') {
                if (v[0] == '\0')
                    return usage_error(self, "-o needs a folder name; got an empty one", NULL);
                outdir = v;
            } else if (a[2] == 't') {
                /* lv_run_execute uses at most 16: more would be replaced silently */
                if (!parse_int(v, &threads) || threads < 1 || threads > 16)
                    return usage_error(self, "--threads needs a count from 1 to 16 (the most "
                                             "a run uses), got", v);
            } else if (!parse_count(v, &max_rows)) {
                return usage_error(self, "--max-rows needs a whole number >= 1, got", v);
            }
        } else if (strcmp(a, "--json") == 0) {
            json = 1;
        } else if (strcmp(a, "--no-plots") == 0) {
            plots = 0;
        } else if (strcmp(a, "--force") == 0) {
            force = 1;
        } else if (strcmp(a, "--quiet") == 0 || strcmp(a, "-q") == 0) {
            quiet = 1;
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
    cli_catch_stop(); /* from here on Ctrl-C cancels: OUTDIR is left as it was */
    lv_mission *m;
    int code = load_mission(path, &m);
    if (code != EXIT_OK)
        return code;
    if ((code = check_output_bound(m, max_rows, 0.0, 0)) != EXIT_OK) {
        lv_mission_free(m);
        return code;
    }
    const size_t n = lv_mission_phase_count(m);
    lv_err err;
    lv_outdir *od = NULL; /* none with --outputs none: nothing is written, not even OUTDIR */
    lv_status st = outputs != 0
                       ? lv_outdir_begin(outdir, path, force ? LV_OUTDIR_FORCE : 0u, &od, &err)
                       : LV_OK;
    if (st != LV_OK) {
        lv_mission_free(m);
        return print_err("lvsim", &err, st == LV_ERR_NOMEM ? EXIT_INTERNAL : EXIT_INPUT);
    }
    for (size_t i = 0; od != NULL && i < lv_outdir_stale_count(od); i++)
        fprintf(stderr, "lvsim: removed '%s', the unfinished folder of an interrupted run\n",
                lv_outdir_stale(od, i));
    const char *stage = od != NULL ? lv_outdir_path(od) : NULL;
    run_ui ui = {progress_new(n, quiet), !json, 0, calloc(n + 1, 1), 12};
    for (size_t k = 0; k < n; k++) {
        const int len = (int)strlen(lv_mission_phase_name(m, k));
        ui.wname = len > ui.wname ? len : ui.wname;
    }
    lv_run *run = NULL;
    if (ui.ended == NULL || (st = lv_run_create(m, &run, &err)) != LV_OK) {
        if (ui.ended == NULL)
            fprintf(stderr, "lvsim: out of memory\n");
        else
            print_err("lvsim", &err, 0);
        progress_free(ui.prog);
        free(ui.ended);
        lv_outdir_free(od);
        lv_mission_free(m);
        return ui.ended == NULL ? EXIT_INTERNAL : exit_code_for(st);
    }
    if (!json) {
        if (od != NULL)
            printf("mission '%s': %zu phases -> %s/\n", lv_mission_name(m), n,
                   lv_outdir_final(od));
        else
            printf("mission '%s': %zu phases (nothing written)\n", lv_mission_name(m), n);
        printf("%-3s %-*s %-*s %9s %9s  %-*s %7s %8s %4s %4s %9s  %-11s %s\n", "#", ui.wname,
               "phase", ui.wname, "from", "t0 [s]", "t1 [s]", END_W, "end", "steps", "rhs", "sev",
               "tev", "cpu [ms]", "method", "status");
        fflush(stdout);
    }
    /* rows are kept in memory only for the body files, which are merged from them */
    const unsigned phase_files = outputs & (OUT_MAT | OUT_CSV);
    lv_run_options opt = {.outdir = stage, .threads = threads, .on_phase = on_phase,
                          .user = &ui, .progress = on_progress,
                          .no_rows = !(outputs & OUT_BODY), .max_rows = max_rows,
                          .result_formats = phase_files == 0 ? LV_RUN_NO_PHASE_FILES
                                            : (phase_files & OUT_MAT ? LV_RESULT_MAT : 0u) |
                                                  (phase_files & OUT_CSV ? LV_RESULT_CSV : 0u)};
    lv_status run_st = lv_run_execute(run, &opt, &err);
    /* the rows on_phase could not print yet: phases never run (skipped, pending) and those
     * after them */
    progress_print_begin(ui.prog);
    while (ui.table && ui.next < n)
        print_row(run, ui.next++, ui.wname);
    progress_print_end(ui.prog);
    /* what never ran (skipped by a failed ancestor) is printed by on_phase too; nothing left.
     * Interrupted (Ctrl-C, SIGTERM): the phases that ended are kept, with summary.json, in a
     * folder marked failed; no exports or plots (a second signal ends the process at once and
     * leaves OUTDIR as it was) */
    int interrupted = progress_interrupted();
    if (od == NULL && interrupted) {
        lv_run_free(run);
        progress_free(ui.prog);
        free(ui.ended);
        lv_mission_free(m);
        return 130;
    }
    if (od == NULL) { /* --outputs none: the table was all */
        if (run_st != LV_OK) {
            print_err("lvsim", &err, 0);
            code = exit_code_for(run_st);
        }
        lv_run_free(run);
        progress_free(ui.prog);
        free(ui.ended);
        lv_mission_free(m);
        return code;
    }
    /* post-processing reads the staging folder, as `lvsim export` and `lvsim plot` do */
    const char *notes[8];
    size_t n_notes = 0;
    char note_buf[5][LV_ERR_MSG_MAX + 32];
    if (interrupted) {
        snprintf(note_buf[n_notes], sizeof note_buf[0],
                 "interrupted (SIGINT or SIGTERM): the phases that ended are complete, the "
                 "others failed or not run; no exports or plots");
        notes[n_notes] = note_buf[n_notes];
        n_notes++;
    }
    if (run_st != LV_OK) {
        snprintf(note_buf[n_notes], sizeof note_buf[0], "run: %s", err.msg);
        notes[n_notes] = note_buf[n_notes];
        n_notes++;
    }
    /* each step on its own: an export that cannot be made (no phase done) does not keep the
     * report of a failed run from being written; the first failure decides the exit code */
    lv_err serr, e;
    lv_status post_st = LV_OK, st1;
    lv_export_report xr = {0};
    char post_msg[3][LV_ERR_MSG_MAX];
    size_t n_post = 0;
    const unsigned summary = (outputs & OUT_SUMMARY ? LV_SUMMARY_JSON : 0u) |
                             (outputs & OUT_BODY ? LV_SUMMARY_BODIES : 0u);
    st1 = LV_OK;
    if (summary != 0) {
        progress_step_begin(ui.prog, "summary.json and body trajectories");
        st1 = lv_run_write_summary_files(run, stage, summary, &e);
        progress_step_end(ui.prog);
    }
    if (st1 != LV_OK) {
        post_st = st1;
        snprintf(post_msg[n_post++], sizeof post_msg[0], "%.480s", e.msg);
    } else {
        st1 = LV_OK;
        if (exports && !progress_interrupted()) {
            progress_step_begin(ui.prog, "exports (CZML, KML, OEM)");
            st1 = lv_export_run_report(stage,
                                       (outputs & OUT_CZML ? LV_EXPORT_CZML : 0u) |
                                           (outputs & OUT_KML ? LV_EXPORT_KML : 0u) |
                                           (outputs & OUT_OEM ? LV_EXPORT_OEM : 0u),
                                       &xr, &e);
            progress_step_end(ui.prog);
        }
        if (st1 != LV_OK) {
            post_st = post_st != LV_OK ? post_st : st1;
            snprintf(post_msg[n_post++], sizeof post_msg[0], "exports: %.480s", e.msg);
        }
        if (plots && !progress_interrupted()) {
            progress_step_begin(ui.prog, "plots and index.html");
            st1 = lv_plot_run(stage, &e);
            progress_step_end(ui.prog);
            if (st1 != LV_OK) {
                post_st = post_st != LV_OK ? post_st : st1;
                snprintf(post_msg[n_post++], sizeof post_msg[0], "plots: %.480s", e.msg);
            }
        }
    }
    /* messages name files in the staging folder: name them where they will be */
    for (size_t i = 0; i < n_post; i++) {
        restage(post_msg[i], sizeof post_msg[0], stage, lv_outdir_final(od));
        if (n_notes < sizeof note_buf / sizeof note_buf[0]) {
            snprintf(note_buf[n_notes], sizeof note_buf[0], "post-processing: %.500s", post_msg[i]);
            notes[n_notes] = note_buf[n_notes];
            n_notes++;
        }
    }
    /* a signal during the post-processing: the simulation is complete (summary.json says how
     * it ended, and so does the manifest's status); the note says what may be missing */
    const int post_interrupted = !interrupted && progress_interrupted();
    if (post_interrupted && n_notes < sizeof note_buf / sizeof note_buf[0]) {
        snprintf(note_buf[n_notes], sizeof note_buf[0],
                 "interrupted (SIGINT or SIGTERM) during the post-processing: exports, plots or "
                 "the report may be missing");
        notes[n_notes] = note_buf[n_notes];
        n_notes++;
    }
    serr.code = post_st;
    snprintf(serr.msg, sizeof serr.msg, "%s", n_post > 0 ? post_msg[0] : "");
    {
        const lv_outdir_record rec = {"run",
                                      run_st == LV_OK && post_st == LV_OK && !interrupted ? "ok"
                                                                                         : "failed",
                                      lv_mission_name(m), n_notes, notes};
        progress_step_begin(ui.prog, "manifest.json");
        lv_err cerr;
        lv_status cst = lv_outdir_commit(od, &rec, &cerr);
        progress_step_end(ui.prog);
        if (json && cst == LV_OK)
            print_file(lv_outdir_final(od), "summary.json");
        for (size_t i = 0; i < n_post; i++)
            fprintf(stderr, "lvsim: %s\n", post_msg[i]);
        for (size_t i = 0; i < xr.n && !json; i++)
            if (xr.items[i].file[0] == '\0')
                printf("export %s: %s\n", xr.items[i].format, xr.items[i].note);
        if (cst != LV_OK) {
            print_err("lvsim", &cerr, 0);
            code = cst == LV_ERR_NOMEM ? EXIT_INTERNAL : EXIT_INPUT;
        } else if (!json) {
            print_results(od);
        }
        if (cst == LV_OK)
            print_kept(od);
        if (interrupted || post_interrupted) {
            if (cst != LV_OK)
                fprintf(stderr, "lvsim: interrupted: '%s' was left as it was\n",
                        lv_outdir_final(od));
            else if (interrupted)
                fprintf(stderr, "lvsim: interrupted: '%s' holds the phases that ended, marked "
                        "failed\n", lv_outdir_final(od));
            else
                fprintf(stderr, "lvsim: interrupted: '%s' holds the complete simulation; "
                        "exports, plots or the report may be missing (lvsim export, lvsim plot "
                        "make them)\n", lv_outdir_final(od));
            code = 130;
        } else if (run_st != LV_OK) {
            print_err("lvsim", &err, 0);
            code = exit_code_for(run_st);
        } else if (code == EXIT_OK && post_st != LV_OK) {
            code = post_st == LV_ERR_NOMEM ? EXIT_INTERNAL : EXIT_INPUT;
        }
    }
    lv_export_report_clear(&xr);
    lv_run_free(run);
    progress_free(ui.prog);
    free(ui.ended);
    lv_outdir_free(od);
    lv_mission_free(m);
    return code;
}

const cli_cmd cli_cmd_run = {
    "run",
    "run every phase of a mission; results, exports, plots, report",
    "MISSION.yaml [-o OUTDIR] [--force] [--threads N] [--max-rows N] [--outputs LIST]\n"
    "            [--json] [--no-plots] [--quiet]",
    "Validates the mission (as 'lvsim check'), refuses a phase that only its stop time ends\n"
    "and that would write more than --max-rows rows (a phase with an end event that reaches\n"
    "the limit fails there as it runs), runs every phase in dependency order, independent\n"
    "branches in parallel, and prints the phase table in run order. Writes OUTDIR/phase_<k>_<name>.mat\n"
    "and .csv, body_<stage>.csv, summary.json, the exports (mission.czml, mission.kml,\n"
    "<stage>.oem), plots/, index.html and manifest.json (every file with its SHA-256);\n"
    "--outputs chooses fewer. Everything is written into a staging folder beside OUTDIR\n"
    "that replaces OUTDIR as a whole when the run ends, also when phases failed (then\n"
    "marked 'failed'): OUTDIR never mixes two runs. lvsim replaces only what it provably\n"
    "wrote: an OUTDIR holding files that its manifest.json does not list (or that changed\n"
    "since) is refused (exit 2) unless --force. A second run into an OUTDIR in use is\n"
    "refused (exit 2). Ctrl-C or SIGTERM stops the run: OUTDIR then holds the phases that\n"
    "ended and summary.json, marked 'failed' (exit 130; a second Ctrl-C leaves OUTDIR as it\n"
    "was). A failing phase stops only its descendants; the exit code is then 3. Progress\n"
    "goes to stderr.\n"
    "\n"
    "options:\n"
    "  -o OUTDIR               results folder (default lvsim-out): new, empty, or an\n"
    "                          earlier one of lvsim\n"
    "  --force                 OUTDIR may hold files lvsim did not write: they are kept\n"
    "                          (never replaced; a run whose results have a file of the\n"
    "                          same name is refused), lvsim's own files are replaced\n"
    "  --threads N             worker threads for independent branches, 1 to 16 (default 2)\n"
    "  --max-rows N            output rows one phase may write (default 1e6)\n"
    "  --json                  print summary.json instead of the table\n"
    "  --no-plots              skip plots/ and index.html\n"
    "  --outputs LIST          what to write, comma-separated: mat, csv (each phase's\n"
    "                          files), body (body_<stage>.csv), summary (summary.json),\n"
    "                          czml, kml, oem (the exports; they need body and summary);\n"
    "                          'none' writes nothing, not even OUTDIR (a run in memory:\n"
    "                          the table only). Default: all of them. Plots are drawn only\n"
    "                          when csv, body and summary are written.\n"
    "  --quiet, -q             no progress lines\n",
    run_run,
};
