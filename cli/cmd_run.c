/* cmd_run.c - `lvsim run MISSION.yaml`: every phase of a mission through the run API
 * (lv_run_execute) into a private staging folder (lv_outdir.h), one table row per phase in
 * run order, then summary.json, the trajectory exports and the plots; the results folder
 * is replaced as a whole at the end, failed runs included (marked in manifest.json and
 * summary.json), so it never mixes two runs. Progress on stderr (progress.h).
 */
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "common.h"
#include "progress.h"

/* Why a phase ended, as summary.json's end.event or end.reason say it. */
static const char *end_word(const lv_phase_result *r)
{
    if (r->state != LV_PHASE_DONE &&
        !(r->state == LV_PHASE_CRASHED && r->report.reason == LV_STOP_EVENT))
        return "-"; /* a crash end's phase was flown: its end; a crash at its hand-off not */
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
               "-", "-", "-", "-", "-", "-", "-", lv_phase_state_name(r->state));
        return;
    }
    /* the method that ran; for "auto" with why ("dop853: not stiff") */
    printf("%-3zu %-*s %-*s %9.3f %9.3f  %-*s %7ld %8ld %4ld %4ld %9.2f  %-11s %s\n", k + 1, w,
           r->name, w, parent >= 0 ? lv_mission_phase_name(m, (size_t)parent) : "-", r->t_start,
           r->t_end, END_W, end_word(r), rep->stats.steps, rep->stats.rhs_evals,
           rep->stats.state_events, rep->stats.time_events, 1e3 * rep->stats.cpu_time, r->method,
           lv_phase_state_name(r->state));
}

/* A commanded throttle (a throttle law's, an inputs or attitude table's) that left the running
 * engines' range (the model's state events
 * `throttle_min` / `throttle_max`, direction -1 entering, +1 leaving: docs/guidance.md,
 * "Saturation"; from the start, where no crossing is logged: the first row's throttle_in
 * outside what the engines give, throttle_eff): one warning per kind on stderr, with the
 * first interval. */
static void warn_saturation(const lv_run *run, size_t k, const lv_phase_result *r)
{
    static const char *const ev[2] = {"throttle_min", "throttle_max"};
    /* the first row (the phase's start), when the model has the columns */
    const lv_result *rows = lv_run_rows(run, k);
    size_t c_in, c_eff, c_n;
    double in0 = NAN, eff0 = NAN;
    if (rows != NULL && lv_result_rows(rows) > 0 &&
        lv_result_column(rows, "throttle_in", &c_in, NULL) == LV_OK &&
        lv_result_column(rows, "throttle_eff", &c_eff, NULL) == LV_OK &&
        lv_result_column(rows, "engines_running", &c_n, NULL) == LV_OK &&
        lv_result_value(rows, 0, c_n) > 0.0) {
        in0 = lv_result_value(rows, 0, c_in);
        eff0 = lv_result_value(rows, 0, c_eff);
    }
    for (int j = 0; j < 2; j++) {
        const lv_sim_report *rep = &r->report;
        const int at_start = j == 0 ? in0 < eff0 - 1e-9 : in0 > eff0 + 1e-9;
        double t_in = at_start ? r->t_start : NAN, t_out = NAN;
        size_t n = at_start;
        for (size_t i = 0; i < rep->n_event_log; i++) {
            const lv_event_record *e = &rep->event_log[i];
            if (!e->is_state || strcmp(e->name, ev[j]) != 0)
                continue;
            if (e->direction < 0 && n++ == 0)
                t_in = e->t;
            else if (e->direction > 0 && !isnan(t_in) && isnan(t_out))
                t_out = e->t;
        }
        if (n == 0)
            continue;
        char until[48] = "";
        if (!isnan(t_out))
            snprintf(until, sizeof until, " to %.3f s", t_out);
        fprintf(stderr, "lvsim: warning: phase '%s': the commanded throttle asked for %s than the "
                "running engines' %s throttle from t = %.3f s%s%s%s: they gave n x T(%s) "
                "(events '%s' in summary.json; columns throttle_in, throttle_eff)\n", r->name,
                j == 0 ? "less" : "more", j == 0 ? "minimum" : "maximum", t_in,
                at_start ? " (the phase's start)" : "", until, n > 1 ? " and again later" : "",
                ev[j], ev[j]);
    }
}

/* A 6-DoF phase whose pointing error (the controller's pitch and yaw attitude errors, columns
 * err_pitch, err_yaw: the rotation vector to the commanded attitude; roll, which the gimbal
 * does not control, left out) grew past 90 deg after it had been within:
 * the vehicle no longer followed its command, which the phase's model does not forbid (a
 * tumbling body is a state like any other) but a reader of its results must know. From the
 * written rows; an error above 90 deg from the start (a commanded flip being flown) counts
 * only once it came within. */
static void warn_attitude(const lv_run *run, size_t k, const lv_phase_result *r)
{
    const lv_result *rows = lv_run_rows(run, k);
    size_t c[3], c_t;
    static const char *const name[3] = {"err_roll", "err_pitch", "err_yaw"};
    if (rows == NULL || lv_result_column(rows, "time", &c_t, NULL) != LV_OK)
        return;
    for (int j = 0; j < 3; j++)
        if (lv_result_column(rows, name[j], &c[j], NULL) != LV_OK)
            return;
    const double lim = 0.5 * LV_PI;
    int within = 0;
    double t_lost = NAN, e_max = 0.0, t_max = NAN;
    for (size_t i = 0; i < lv_result_rows(rows); i++) {
        /* pitch and yaw: the pointing; roll is not controlled (one gimbal point) */
        const double e = hypot(lv_result_value(rows, i, c[1]), lv_result_value(rows, i, c[2]));
        if (!(e > lim)) {
            within = 1;
            continue;
        }
        if (!within)
            continue;
        if (isnan(t_lost))
            t_lost = lv_result_value(rows, i, c_t);
        if (e > e_max) {
            e_max = e;
            t_max = lv_result_value(rows, i, c_t);
        }
    }
    if (isnan(t_lost))
        return;
    fprintf(stderr, "lvsim: warning: phase '%s': the pointing error passed 90 deg at t = %.3f s "
            "(largest %.0f deg at t = %.3f s): the vehicle did not follow its commanded attitude; "
            "a command that turns faster than the controller follows does that (one about the "
            "air-relative velocity at low speed turns at about g/v) (columns err_pitch, "
            "err_yaw)\n", r->name, t_lost, e_max / LV_DEG, t_max);
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
    if (r->state == LV_PHASE_FAILED || r->state == LV_PHASE_CRASHED)
        fprintf(stderr, "lvsim: %s\n", r->error);
    warn_saturation(run, k, r);
    warn_attitude(run, k, r);
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
    if (n_phase > 0) { /* "phase_<k>_<name>.mat, .csv": the result formats' extensions */
        printf(", %zu phase files (phase_<k>_<name>", n_phase);
        const char *ext;
        for (size_t i = 0; lv_result_format_info(i, &ext, NULL) != NULL; i++)
            printf("%s%s", i ? ", " : "", ext);
        printf("%s)", n_failed ? "; *.failed.* for failed phases" : "");
    }
    if (n_body > 0)
        printf(", %zu body trajectories (body_<stage>.csv)", n_body);
    if (n_plots > 0)
        printf(", plots/ (%zu files)", n_plots);
    if (n_viewer > 0)
        printf(", viewer/ (%zu files)", n_viewer);
    printf("\n");
}

/* What `run` writes (--outputs): its words are the result formats (each phase's files, from
 * lv_result_format_info), "body", "summary" and the exports (lv_export_format_info), in this
 * order; word i is bit i of run_args.outputs. The result formats come first, so their bits
 * are the library's LV_RESULT_* flags. */
typedef struct run_outputs {
    name_list words;
    size_t n_results;    /* words [0, n_results): the result formats */
    unsigned body, summary;
    size_t first_export; /* words [first_export, words.n): the exports */
    unsigned results, exports; /* the masks of both ranges */
    unsigned csv;        /* the bit of "csv" (the plots read it); 0 if not registered */
} run_outputs;

static void outputs_init(run_outputs *o)
{
    memset(o, 0, sizeof *o);
    name_list_add_results(&o->words);
    o->n_results = o->words.n;
    o->results = (1u << o->n_results) - 1u;
    o->body = name_list_add(&o->words, "body");
    o->summary = name_list_add(&o->words, "summary");
    o->first_export = o->words.n;
    name_list_add_exports(&o->words);
    o->exports = ((1u << o->words.n) - 1u) & ~((1u << o->first_export) - 1u);
    for (size_t i = 0; i < o->n_results; i++)
        if (strcmp(o->words.names[i], "csv") == 0)
            o->csv = 1u << i;
}

/* The command line of `run`. */
typedef struct run_args {
    const char *path, *outdir;
    int json, threads, plots, quiet, force;
    double max_rows;
    unsigned outputs; /* bits of run_outputs.words */
} run_args;

/* Everything one `lvsim run` holds; run_close frees it. */
typedef struct run_job {
    run_args a;
    run_outputs o;
    lv_mission *m;
    lv_outdir *od;     /* NULL with --outputs none: nothing is written, not even OUTDIR */
    const char *stage; /* od's staging folder, where the run and post-processing write */
    lv_run *run;
    run_ui ui;
    lv_err err;        /* why the run failed */
    lv_status run_st;
    int interrupted;   /* Ctrl-C or SIGTERM during the run */
    const char *notes[8]; /* the manifest's notes */
    size_t n_notes;
    char note_buf[5][LV_ERR_MSG_MAX + 32];
    lv_status post_st; /* the first post-processing failure */
    char post_msg[3][LV_ERR_MSG_MAX];
    size_t n_post;
    lv_export_report xr;
} run_job;

/* Reads the options into j->a. Returns EXIT_OK or a usage error's exit code. */
static int parse_args(const cli_cmd *self, int argc, char **argv, run_job *j)
{
    run_args *a = &j->a;
    *a = (run_args){NULL, "lvsim-out", 0, 2, 1, 0, 0, CLI_DEFAULT_MAX_ROWS,
                    (1u << j->o.words.n) - 1u};
    for (int i = 0; i < argc; i++) {
        const char *arg = argv[i];
        if (strcmp(arg, "-o") == 0 || strcmp(arg, "--threads") == 0 ||
            strcmp(arg, "--max-rows") == 0 || strcmp(arg, "--outputs") == 0) {
            const char *v = option_value(argc, argv, &i);
            if (v == NULL)
                return usage_error(self, "missing value for option", arg);
            if (strcmp(arg, "--outputs") == 0) {
                if (!parse_name_list(self, arg, "output", &j->o.words, 1, v, &a->outputs))
                    return EXIT_INPUT;
            } else if (arg[1] == 'o') {
                if (v[0] == '\0')
                    return usage_error(self, "-o needs a folder name; got an empty one", NULL);
                a->outdir = v;
            } else if (arg[2] == 't') {
                /* lv_run_execute uses at most 16: more would be replaced silently */
                if (!parse_int(v, &a->threads) || a->threads < 1 || a->threads > 16)
                    return usage_error(self, "--threads needs a count from 1 to 16 (the most "
                                             "a run uses), got", v);
            } else if (!parse_count(v, &a->max_rows)) {
                return usage_error(self, "--max-rows needs a whole number from 1 to 1e15, got", v);
            }
        } else if (strcmp(arg, "--json") == 0) {
            a->json = 1;
        } else if (strcmp(arg, "--no-plots") == 0) {
            a->plots = 0;
        } else if (strcmp(arg, "--force") == 0) {
            a->force = 1;
        } else if (strcmp(arg, "--quiet") == 0 || strcmp(arg, "-q") == 0) {
            a->quiet = 1;
        } else if (is_option(arg)) {
            return usage_error(self, "unknown option", arg);
        } else if (a->path != NULL) {
            return usage_error(self, "unexpected argument", arg);
        } else {
            a->path = arg;
        }
    }
    if (a->path == NULL)
        return usage_error(self, "run needs a mission file", NULL);
    return EXIT_OK;
}

/* The exports and the plots read the results folder: they need what they read. Turns the
 * plots off when their inputs are not written. Returns EXIT_OK or a usage error's code. */
static int check_outputs(const cli_cmd *self, run_job *j)
{
    const run_outputs *o = &j->o;
    const unsigned out = j->a.outputs, needs = o->summary | o->body;
    if ((out & o->exports) && (out & needs) != needs) {
        char names[256], what[320];
        name_list_join(&o->words, o->first_export, o->words.n - o->first_export, names,
                       sizeof names);
        snprintf(what, sizeof what, "--outputs: %s read summary and body; add them", names);
        return usage_error(self, what, NULL);
    }
    if (j->a.json && !(out & o->summary))
        return usage_error(self, "--json prints summary.json: --outputs needs summary", NULL);
    const unsigned plot_needs = needs | o->csv;
    j->a.plots = j->a.plots && o->csv != 0 && (out & plot_needs) == plot_needs;
    return EXIT_OK;
}

/* Loads the mission, checks its output bound, begins OUTDIR's staging folder (not with
 * --outputs none) and creates the run and its progress. Returns EXIT_OK or the exit code,
 * the error printed. */
static int run_open(run_job *j)
{
    int code = load_mission(j->a.path, &j->m);
    if (code != EXIT_OK)
        return code;
    if ((code = check_output_bound(j->m, j->a.max_rows, 0.0, 0)) != EXIT_OK)
        return code;
    const size_t n = lv_mission_phase_count(j->m);
    lv_err err;
    lv_status st = LV_OK;
    if (j->a.outputs != 0)
        st = lv_outdir_begin(j->a.outdir, j->a.path, j->a.force ? LV_OUTDIR_FORCE : 0u, &j->od,
                             &err);
    if (st != LV_OK)
        return print_err("lvsim", &err, st == LV_ERR_NOMEM ? EXIT_INTERNAL : EXIT_INPUT);
    for (size_t i = 0; j->od != NULL && i < lv_outdir_stale_count(j->od); i++)
        fprintf(stderr, "lvsim: removed '%s', the unfinished folder of an interrupted run\n",
                lv_outdir_stale(j->od, i));
    j->stage = j->od != NULL ? lv_outdir_path(j->od) : NULL;
    j->ui = (run_ui){progress_new(n, j->a.quiet), !j->a.json, 0, calloc(n + 1, 1), 12};
    for (size_t k = 0; k < n; k++) {
        const int len = (int)strlen(lv_mission_phase_name(j->m, k));
        j->ui.wname = len > j->ui.wname ? len : j->ui.wname;
    }
    if (j->ui.ended == NULL) {
        fprintf(stderr, "lvsim: out of memory\n");
        return EXIT_INTERNAL;
    }
    if ((st = lv_run_create(j->m, &j->run, &err)) != LV_OK) {
        print_err("lvsim", &err, 0);
        return exit_code_for(st);
    }
    return EXIT_OK;
}

static void run_close(run_job *j)
{
    lv_export_report_clear(&j->xr);
    lv_run_free(j->run);
    progress_free(j->ui.prog);
    free(j->ui.ended);
    lv_outdir_free(j->od);
    lv_mission_free(j->m);
}

/* "mission 'NAME': N phases -> OUTDIR/" and the table's header (not with --json). */
static void print_header(const run_job *j)
{
    if (j->a.json)
        return;
    const size_t n = lv_mission_phase_count(j->m);
    const int w = j->ui.wname;
    if (j->od != NULL)
        printf("mission '%s': %zu phases -> %s/\n", lv_mission_name(j->m), n,
               lv_outdir_final(j->od));
    else
        printf("mission '%s': %zu phases (nothing written)\n", lv_mission_name(j->m), n);
    printf("%-3s %-*s %-*s %9s %9s  %-*s %7s %8s %4s %4s %9s  %-11s %s\n", "#", w, "phase", w,
           "from", "t0 [s]", "t1 [s]", END_W, "end", "steps", "rhs", "sev", "tev", "cpu [ms]",
           "method", "status");
    fflush(stdout);
}

/* One line of the console timeline: an event of one or more bodies (the same label, phase
 * and row: the same instant of the same flight). */
typedef struct tl_line {
    const lv_timeline_row *w;
    size_t first_body, pos; /* where it was met first: ties in time keep flight order */
    char bodies[200];
    size_t n_bodies;
} tl_line;

static int tl_line_cmp(const void *a, const void *b)
{
    const tl_line *x = a, *y = b;
    if (x->w->t != y->w->t)
        return x->w->t < y->w->t ? -1 : 1;
    if (x->first_body != y->first_body)
        return x->first_body < y->first_body ? -1 : 1;
    return x->pos < y->pos ? -1 : x->pos > y->pos;
}

/* The bodies' timelines (lv_run_timeline: lift-off, max-q, each phase's end by its name,
 * burnouts, separations) after the phase table, compact: one line per event, with the bodies
 * it concerns ("all": every body with a timeline). Only when the run kept its rows;
 * summary.json and the report give each body's own. */
static void print_timelines(const lv_run *run)
{
    const lv_mission *m = lv_run_mission(run);
    const size_t ns = lv_mission_stage_count(m);
    lv_timeline **tl = calloc(ns + 1, sizeof *tl);
    size_t n_rows = 0, n_tl = 0;
    for (size_t s = 0; tl != NULL && s < ns; s++) {
        lv_err err;
        if (lv_run_timeline(run, s, &tl[s], &err) != LV_OK)
            tl[s] = NULL;
        n_rows += tl[s] != NULL ? tl[s]->n : 0;
        n_tl += tl[s] != NULL && tl[s]->n > 0;
    }
    tl_line *lines = tl != NULL && n_rows > 0 ? calloc(n_rows, sizeof *lines) : NULL;
    size_t n = 0;
    for (size_t s = 0; lines != NULL && s < ns; s++)
        for (size_t i = 0; tl[s] != NULL && i < tl[s]->n; i++) {
            const lv_timeline_row *w = &tl[s]->rows[i];
            size_t j = 0;
            while (j < n && !(lines[j].w->t == w->t && lines[j].w->row == w->row &&
                              strcmp(lines[j].w->phase, w->phase) == 0 &&
                              strcmp(lines[j].w->label, w->label) == 0))
                j++;
            tl_line *l = &lines[j];
            if (j == n)
                *l = (tl_line){w, s, i, "", 0}, n++;
            const size_t used = strlen(l->bodies);
            snprintf(l->bodies + used, sizeof l->bodies - used, "%s%s", used ? ", " : "",
                     tl[s]->body);
            l->n_bodies++;
        }
    if (n > 0) {
        qsort(lines, n, sizeof *lines, tl_line_cmp);
        printf("timeline: %-26s %10s %9s %8s %6s %8s  %-12s %s\n", "event", "t [s]", "h [km]",
               "v [m/s]", "Mach", "q [kPa]", "phase", "bodies");
        for (size_t i = 0; i < n; i++) {
            const lv_timeline_row *w = lines[i].w;
            char mach[16] = "-", q[16] = "-";
            if (isfinite(w->mach))
                snprintf(mach, sizeof mach, "%.2f", w->mach);
            if (isfinite(w->q))
                snprintf(q, sizeof q, "%.3f", w->q / 1e3);
            const double h = fabs(w->h) < 0.5 ? 0.0 : w->h / 1e3; /* no "-0.000" */
            fputs("  ", stdout);
            print_padded(w->label, 34, 63); /* a name has at most 63 */
            printf(" %10.3f %9.3f %8.1f %6s %8s  ", w->t, h, w->speed, mach, q);
            print_padded(w->phase, 12, SIZE_MAX);
            printf(" %s\n", lines[i].n_bodies == n_tl ? "all" : lines[i].bodies);
        }
    }
    free(lines);
    for (size_t s = 0; tl != NULL && s < ns; s++)
        lv_timeline_free(tl[s]);
    free(tl);
}

/* Each phase's drift from its `reference:` (an optimiser's trajectory; lv_run_reference_drift)
 * after the phase table: largest and final position, velocity and mass differences, the time
 * of the largest. Only when the run kept its rows. */
static void print_reference_drift(const lv_run *run)
{
    const lv_mission *m = lv_run_mission(run);
    int head = 0;
    for (size_t k = 0; k < lv_mission_phase_count(m); k++) {
        lv_ref_drift d;
        if (!lv_mission_phase_has_reference(m, k) ||
            lv_run_reference_drift(run, k, &d, NULL) != LV_OK)
            continue;
        if (!head++)
            printf("reference: %-12s %6s %11s %10s %11s %10s %10s %10s %9s %9s\n", "phase", "rows",
                   "pos max [m]", "at t [s]", "final [m]", "vel [m/s]", "at t [s]",
                   "final", "m [kg]", "final");
        fputs("  ", stdout);
        print_padded(lv_mission_phase_name(m, k), 21, SIZE_MAX);
        if (d.n_rows == 0) {
            printf(" %6s  (no result row within the reference's range)\n", "0");
            continue;
        }
        printf(" %6zu %11.4g %10.3f %11.4g %10.4g %10.3f %10.4g %9.4g %9.4g\n", d.n_rows,
               d.pos_max, d.pos_max_t, d.pos_final, d.vel_max, d.vel_max_t, d.vel_final,
               d.mass_max, d.mass_final);
        /* where the phase and the reference end apart, say so: a tau reference laid over a
         * span the phase did not fly, or a final drift short of one of the two ends */
        if (d.over_tau && d.phase_end < 1.0 - 1e-6)
            printf("  note: '%s' ended at tau = %.4g, before its stop_time: its tau reference "
                   "was laid over the span to stop_time, not over the phase flown\n",
                   lv_mission_phase_name(m, k), d.phase_end);
        else if (!d.over_tau && fabs(d.ref_end - d.phase_end) >
                                    1e-6 * fmax(1.0, fabs(d.ref_end - d.t_first)))
            printf("  note: '%s' ended at t = %.9g s, its reference at t = %.9g s: the final "
                   "drift is at t = %.9g s\n", lv_mission_phase_name(m, k), d.phase_end,
                   d.ref_end, d.t_final);
    }
}

/* Runs every phase into the staging folder, printing the table as phases end; then the rows
 * on_phase could not print yet: phases never run (skipped, pending) and those after them. */
static void run_phases(run_job *j)
{
    /* rows are kept in memory only for the body files, which are merged from them, and
     * summary.json's timelines (lv_run_timeline), which read them */
    const unsigned phase_files = j->a.outputs & j->o.results; /* = LV_RESULT_* flags */
    lv_run_options opt = {.outdir = j->stage, .threads = j->a.threads, .on_phase = on_phase,
                          .user = &j->ui, .progress = on_progress,
                          .no_rows = !(j->a.outputs & (j->o.body | j->o.summary)), .max_rows = j->a.max_rows,
                          .result_formats = phase_files == 0 ? LV_RUN_NO_PHASE_FILES
                                                             : phase_files};
    j->run_st = lv_run_execute(j->run, &opt, &j->err);
    progress_print_begin(j->ui.prog);
    while (j->ui.table && j->ui.next < lv_mission_phase_count(j->m))
        print_row(j->run, j->ui.next++, j->ui.wname);
    if (j->ui.table && !progress_interrupted()) {
        print_timelines(j->run);
        print_reference_drift(j->run);
    }
    progress_print_end(j->ui.prog);
    /* Interrupted (Ctrl-C, SIGTERM): the phases that ended are kept, with summary.json, in a
     * folder marked failed; no exports or plots (a second signal ends the process at once and
     * leaves OUTDIR as it was) */
    j->interrupted = progress_interrupted();
}

/* A note of the manifest (at most 5). */
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static void add_note(run_job *j, const char *fmt, ...)
{
    if (j->n_notes >= sizeof j->note_buf / sizeof j->note_buf[0])
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(j->note_buf[j->n_notes], sizeof j->note_buf[0], fmt, ap);
    va_end(ap);
    j->notes[j->n_notes] = j->note_buf[j->n_notes];
    j->n_notes++;
}

/* A failed post-processing step: the first failure decides the exit code. */
static void post_failed(run_job *j, lv_status st, const char *step, const lv_err *e)
{
    j->post_st = j->post_st != LV_OK ? j->post_st : st;
    snprintf(j->post_msg[j->n_post++], sizeof j->post_msg[0], "%s%.960s", step, e->msg);
}

/* summary.json and the body trajectories; then, if they were written, the exports and the
 * plots, each step on its own: an export that cannot be made (no phase done) does not keep
 * the report of a failed run from being written. Post-processing reads the staging folder,
 * as `lvsim export` and `lvsim plot` do. */
static void post_process(run_job *j)
{
    const unsigned out = j->a.outputs;
    const unsigned summary = (out & j->o.summary ? LV_SUMMARY_JSON : 0u) |
                             (out & j->o.body ? LV_SUMMARY_BODIES : 0u);
    lv_err e;
    lv_status st = LV_OK;
    if (summary != 0) {
        progress_step_begin(j->ui.prog, "summary.json and body trajectories");
        st = lv_run_write_summary_files(j->run, j->stage, summary, &e);
        progress_step_end(j->ui.prog);
    }
    if (st != LV_OK) {
        post_failed(j, st, "", &e);
        return;
    }
    const unsigned exports = (out & j->o.exports) >> j->o.first_export; /* LV_EXPORT_* */
    if (exports && !progress_interrupted()) {
        char step[160] = "exports ("; /* "exports (CZML, KML, OEM)" */
        const size_t n = j->o.words.n - j->o.first_export;
        size_t used = strlen(step);
        for (size_t i = 0; i < n && used < sizeof step; i++)
            used += (size_t)snprintf(step + used, sizeof step - used, "%s%s", i ? ", " : "",
                                     j->o.words.names[j->o.first_export + i]);
        for (char *c = step + strlen("exports ("); *c != '\0'; c++)
            *c = (char)toupper((unsigned char)*c);
        if (used + 1 < sizeof step)
            strcat(step, ")");
        progress_step_begin(j->ui.prog, step);
        st = lv_export_run_report(j->stage, exports, &j->xr, &e);
        progress_step_end(j->ui.prog);
        if (st != LV_OK)
            post_failed(j, st, "exports: ", &e);
    }
    if (j->a.plots && !progress_interrupted()) {
        progress_step_begin(j->ui.prog, "plots and index.html");
        st = lv_plot_run(j->stage, &e);
        progress_step_end(j->ui.prog);
        if (st != LV_OK)
            post_failed(j, st, "plots: ", &e);
    }
}

/* Writes manifest.json and replaces OUTDIR with the staging folder; prints what was written
 * and why it failed. Returns the exit code. */
static int commit(run_job *j)
{
    /* messages name files in the staging folder: name them where they will be */
    for (size_t i = 0; i < j->n_post; i++) {
        restage(j->post_msg[i], sizeof j->post_msg[0], j->stage, lv_outdir_final(j->od));
        add_note(j, "post-processing: %.1000s", j->post_msg[i]);
    }
    /* a signal during the post-processing: the simulation is complete (summary.json says how
     * it ended, and so does the manifest's status); the note says what may be missing */
    const int post_interrupted = !j->interrupted && progress_interrupted();
    if (post_interrupted)
        add_note(j, "interrupted (SIGINT or SIGTERM) during the post-processing: exports, "
                    "plots or the report may be missing");
    const int ok = j->run_st == LV_OK && j->post_st == LV_OK && !j->interrupted;
    const lv_outdir_record rec = {"run", ok ? "ok" : "failed", lv_mission_name(j->m),
                                  j->n_notes, j->notes};
    progress_step_begin(j->ui.prog, "manifest.json");
    lv_err cerr;
    lv_status cst = lv_outdir_commit(j->od, &rec, &cerr);
    progress_step_end(j->ui.prog);
    if (j->a.json && cst == LV_OK)
        print_file(lv_outdir_final(j->od), "summary.json");
    for (size_t i = 0; i < j->n_post; i++)
        fprintf(stderr, "lvsim: %s\n", j->post_msg[i]);
    for (size_t i = 0; i < j->xr.n && !j->a.json; i++)
        if (j->xr.items[i].file[0] == '\0')
            printf("export %s: %s\n", j->xr.items[i].format, j->xr.items[i].note);
    int code = EXIT_OK;
    if (cst != LV_OK) {
        print_err("lvsim", &cerr, 0);
        code = cst == LV_ERR_NOMEM ? EXIT_INTERNAL : EXIT_INPUT;
    } else if (!j->a.json) {
        print_results(j->od);
    }
    if (cst == LV_OK)
        print_kept(j->od);
    if (j->interrupted || post_interrupted) {
        if (cst != LV_OK)
            fprintf(stderr, "lvsim: interrupted: '%s' was left as it was\n",
                    lv_outdir_final(j->od));
        else if (j->interrupted)
            fprintf(stderr, "lvsim: interrupted: '%s' holds the phases that ended, marked "
                    "failed\n", lv_outdir_final(j->od));
        else
            fprintf(stderr, "lvsim: interrupted: '%s' holds the complete simulation; "
                    "exports, plots or the report may be missing (lvsim export, lvsim plot "
                    "make them)\n", lv_outdir_final(j->od));
        return 130;
    }
    if (j->run_st != LV_OK) {
        print_err("lvsim", &j->err, 0);
        return exit_code_for(j->run_st);
    }
    if (code == EXIT_OK && j->post_st != LV_OK)
        return j->post_st == LV_ERR_NOMEM ? EXIT_INTERNAL : EXIT_INPUT;
    return code;
}

/* --outputs none: the table was all; the exit code of the run. */
static int finish_in_memory(run_job *j)
{
    if (j->interrupted)
        return 130;
    if (j->run_st != LV_OK) {
        print_err("lvsim", &j->err, 0);
        return exit_code_for(j->run_st);
    }
    return EXIT_OK;
}

/* 1 when a phase crashed (a touchdown beyond the landing gear's limits). */
static int any_crashed(const lv_run *run)
{
    const size_t n = lv_mission_phase_count(lv_run_mission(run));
    for (size_t k = 0; k < n; k++)
        if (lv_run_result(run, k)->state == LV_PHASE_CRASHED)
            return 1;
    return 0;
}

static int run_run(const cli_cmd *self, int argc, char **argv)
{
    run_job *j = calloc(1, sizeof *j);
    if (j == NULL) {
        fprintf(stderr, "lvsim: out of memory\n");
        return EXIT_INTERNAL;
    }
    outputs_init(&j->o);
    int code = parse_args(self, argc, argv, j);
    if (code == EXIT_OK)
        code = check_outputs(self, j);
    if (code == EXIT_OK) {
        cli_catch_stop(); /* from here on Ctrl-C cancels: OUTDIR is left as it was */
        code = run_open(j);
    }
    if (code == EXIT_OK) {
        print_header(j);
        run_phases(j);
        if (j->od == NULL) {
            code = finish_in_memory(j);
        } else {
            if (j->interrupted)
                add_note(j, "interrupted (SIGINT or SIGTERM): the phases that ended are "
                            "complete, the others failed or not run; no exports or plots");
            if (j->run_st != LV_OK)
                add_note(j, "run: %s", j->err.msg);
            post_process(j);
            code = commit(j);
        }
        if (code == EXIT_OK && any_crashed(j->run))
            code = EXIT_CRASHED; /* complete results; a body's touchdown was a crash */
    }
    run_close(j);
    free(j);
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
    "branches in parallel, and prints the phase table in run order, then the bodies'\n"
    "timeline (lift-off, max-q, each phase's end by its name - MECO - or condition,\n"
    "separations; with t, h, speed, Mach, q) and each phase's drift from its reference.\n"
    "Writes OUTDIR/phase_<k>_<name>.mat and .csv, body_<stage>.csv, summary.json, the\n"
    "exports (mission.czml, mission.kml, <stage>.oem), plots/, index.html and\n"
    "manifest.json (every file with its SHA-256);\n"
    "--outputs chooses fewer. Everything is written into a staging folder beside OUTDIR\n"
    "that replaces OUTDIR as a whole when the run ends, also when phases failed (then\n"
    "marked 'failed'): OUTDIR never mixes two runs. lvsim replaces only what it provably\n"
    "wrote: an OUTDIR holding files that its manifest.json does not list (or that changed\n"
    "since) is refused (exit 2) unless --force. A second run into an OUTDIR in use is\n"
    "refused (exit 2). Ctrl-C or SIGTERM stops the run: OUTDIR then holds the phases that\n"
    "ended and summary.json, marked 'failed' (exit 130; a second Ctrl-C leaves OUTDIR as it\n"
    "was). A failing phase stops only its descendants; the exit code is then 3. A touchdown\n"
    "beyond the landing gear's limits marks its roll-out 'crashed' (not flown; exit 4 when\n"
    "nothing failed). Progress\n"
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
    "  --outputs LIST          what to write, comma-separated: the result formats mat,\n"
    "                          csv (each phase's files), body (body_<stage>.csv), summary\n"
    "                          (summary.json), the exports czml, kml, oem (they need body\n"
    "                          and summary; 'lvsim formats' lists both kinds);\n"
    "                          'none' writes nothing, not even OUTDIR (a run in memory:\n"
    "                          the table only). Default: all of them. Plots are drawn only\n"
    "                          when csv, body and summary are written.\n"
    "  --quiet, -q             no progress lines\n",
    run_run,
};
