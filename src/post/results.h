/* results.h - internal: the one reader of a results folder, used by the exports, the figures
 * and the report (liblvsim_post; not exported). OUTDIR/summary.json (docs/result-files.md,
 * written by lv_run_write_summary) becomes plain structures; the CSV files it names (the
 * per-phase results and the merged body trajectories) load as tables addressed by column name.
 * Post-processing only: nothing here reruns anything. */
#ifndef LV_POST_RESULTS_H
#define LV_POST_RESULTS_H

#include <stddef.h>

#include "lvsim/lv_status.h"

struct cJSON;

/* Room for the registered result formats (lv_io.h; test_results.c checks it suffices). */
#define LV_RESULTS_MAX_FORMATS 8

/* Strings are borrowed from the parsed summary and live as long as their lv_results. A value
 * the summary does not give reads as NULL (strings) or NAN (numbers). */

typedef struct lv_results_event {
    double t;         /* s, mission time; NAN when missing */
    const char *name; /* a state event's name ("burnout", "impact"), a time event's source
                       * ("stage 'stage3' thrust table breakpoint t = 481 s"); NULL: none */
    const char *kind; /* "state" or "time"; NULL when missing */
    double direction; /* zero crossing: +1 rising, -1 falling; NAN when missing */
    const char *label; /* the user's name of the event (`name: MECO`); NULL: none */
} lv_results_event;

typedef struct lv_results_phase {
    const char *name;
    int index;              /* 1-based run order, as in summary.json; 0 when missing */
    const char *from;       /* the parent phase's name; NULL: seeded from the parameters */
    int parent;             /* position of `from` in lv_results.phases; -1 */
    const char *state;      /* "done", "failed", "skipped", "pending"; NULL when missing */
    int done;               /* state "done", or "crashed" by a crash end (end.event: a roll
                             * off the runway): its times, events and rows are complete */
    const char *error;      /* why it failed or was skipped; NULL */
    const char *model;      /* model type ("dof3", "flat6"); NULL when missing */
    double t_start, t_end;  /* s; NAN when missing */
    const char *end_reason; /* end.reason, why it stopped: "event", "stop_time", "failed";
                             * NULL: the summary has no 'end' (a phase that did not run) */
    const char *end_event;  /* end.event: the end condition that fired; NULL */
    const char *end_label;  /* end.label: the user's name of that end ("MECO"); NULL */
    double end_value;       /* end.value: that condition's value, or the stop time (s); NAN */
    lv_results_event *events; /* in summary order */
    size_t n_events;
    const char **stages;    /* stages it carries: fewer than its parent's = a separation */
    size_t n_stages;
    const char *files[LV_RESULTS_MAX_FORMATS]; /* files.<name> per result format i
                             * (lv_result_format_info(i)): names in OUTDIR; NULL when missing */
    const char *csv;        /* files.csv (its files[i]): the table the plots read; NULL */
    double steps, rhs_evals, state_events, time_events; /* stats: counts; NAN when missing */
    double cpu_time;        /* stats.cpu_time, s; NAN when missing */
    struct {                /* its `reference` block (the drift from an optimiser's trajectory) */
        int present;        /* the phase has one */
        double rows;        /* rows compared; NAN when not computed */
        double pos_max, pos_max_t, pos_final; /* m, s, m; NAN when missing */
        double vel_max, vel_final;            /* m/s */
        double mass_max, mass_final;          /* kg */
        const char *file;   /* reference.file: "reference_<k>_<phase>.csv" in OUTDIR; NULL */
    } ref;
} lv_results_phase;

typedef struct lv_results_body {
    const char *name;
    size_t *phases;         /* the phases it flies in (positions in lv_results.phases), in
                             * summary order */
    size_t n_phases;
    const char *trajectory; /* its merged trajectory, a name in OUTDIR ("body_<stage>.csv");
                             * NULL when missing */
} lv_results_body;

typedef struct lv_results {
    char *outdir;           /* as given */
    char *summary_path;     /* "OUTDIR/summary.json", for messages */
    const char *mission, *file, *epoch, *world, *planet, *lvsim; /* top level; NULL missing */
    int flat;               /* world "flat" */
    lv_results_phase *phases;
    size_t n_phases;
    lv_results_body *bodies;
    size_t n_bodies;
    struct cJSON *json;     /* the parsed summary: owns the strings above */
} lv_results;

/* Reads OUTDIR/summary.json. Checks what every reader relies on: arrays 'phases' and
 * 'bodies', a name for every phase and body, a body's phases name phases of the summary, an
 * index (when given) in 1 .. 10^6, and every file name (files.csv, files.mat, trajectory) is a
 * bare name inside OUTDIR: not empty, no '/', not "." or "..". What a reader needs beyond that
 * (an epoch for the exports, say) it checks itself.
 * Errors: LV_ERR_IO "OUTDIR/summary.json: cannot read: <reason>"; LV_ERR_INPUT
 * "OUTDIR/summary.json:<line>: malformed JSON" or naming the phase or body and field;
 * LV_ERR_NOMEM. *out is NULL on failure. */
lv_status lv_results_open(const char *outdir, lv_results **out, lv_err *err);
void lv_results_free(lv_results *r);

/* Position of the phase called `name`, or -1. */
int lv_results_phase_find(const lv_results *r, const char *name);

/* File `file` (a name from the summary) exists in OUTDIR. */
int lv_results_exists(const lv_results *r, const char *file);

/* A CSV result file as read back: a header of "name [unit]" fields, then one row per line;
 * RFC 4180 quoting ("a, ""b""" is one field); empty lines and lines that start with '#' (a
 * failed run's last line) are skipped. */
typedef struct lv_results_column {
    char *name;  /* the header field without its " [unit]" */
    char *unit;  /* "" when the field has none */
    char **text; /* a text column (lv_results_csv_spec.text): each row's field (runs of equal
                  * fields share one string); NULL: a number column */
} lv_results_column;

typedef struct lv_results_table {
    char *path;              /* OUTDIR/<file>, for messages */
    size_t n_cols, n_rows;
    lv_results_column *cols;
    double *v;               /* v[row * n_cols + col]; NAN in a text column, and for a field
                              * that is not a number (unless the column must be finite) */
    size_t *line;            /* line[row]: its line in the file, 1-based */
    size_t header_line;      /* line of the header */
    size_t n_lines;          /* lines in the file */
} lv_results_table;

/* How to read a CSV file; NULL: no text columns, no finite columns. */
typedef struct lv_results_csv_spec {
    const char *const *text;   /* NULL-terminated names of text columns (the body files'
                                * `phase`); NULL: none */
    const char *const *finite; /* NULL-terminated names of columns that, where the header has
                                * them, must hold a finite number in every row; NULL: none */
} lv_results_csv_spec;

/* Loads OUTDIR/<file> (a name from the summary, checked by lv_results_open).
 * Errors: LV_ERR_IO "OUTDIR/<file>: cannot read: <reason>"; LV_ERR_INPUT "OUTDIR/<file>:<line>:
 * ..." for no header, an unterminated quote, a row whose field count is not the header's, or
 * a field of a finite column that is not a finite number; LV_ERR_NOMEM. *out is NULL on
 * failure. */
lv_status lv_results_load(const lv_results *r, const char *file, const lv_results_csv_spec *spec,
                          lv_results_table **out, lv_err *err);
void lv_results_table_free(lv_results_table *t);

/* Position of the column called `name` (the first of that name), or -1. t may be NULL. */
long lv_results_table_col(const lv_results_table *t, const char *name);

/* The field of a text column; NULL for a number column. */
const char *lv_results_table_text(const lv_results_table *t, size_t row, size_t col);

#endif
