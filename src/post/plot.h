/* plot.h - internals of lv_plot_run(): the run's files as read back (summary.json, CSVs), the
 * figures (PLplot: the only code that includes plplot.h) and the HTML report. */
#ifndef LV_POST_PLOT_H
#define LV_POST_PLOT_H

#include <cjson/cJSON.h>
#include <stddef.h>

#include "lvsim/lv_status.h"

/* A CSV result file read back: header `name [unit]` (lvsim's layout), numbers row-major.
 * A field that is not a number (the body files' `phase` column) reads as NAN; lines that start
 * with '#' (a failed run's last line) and empty lines are skipped. */
typedef struct lv_csv {
    size_t n_cols, n_rows;
    char **names; /* without the unit */
    char **units; /* "" when the header has none */
    double *v;    /* v[row * n_cols + col] */
} lv_csv;

/* Errors: LV_ERR_IO (cannot open/read, with the path), LV_ERR_INPUT ("path:line: ..."). */
lv_status lv_plot_csv_read(const char *path, lv_csv **out, lv_err *err);
void lv_plot_csv_free(lv_csv *c);
/* Column index of `name`, or -1. */
long lv_plot_csv_col(const lv_csv *c, const char *name);

typedef struct lv_plot_phase {
    const char *name; /* borrowed from the summary's cJSON tree */
    double t0, t1;    /* s; NAN when the phase did not run */
    int done;         /* state "done" */
    lv_csv *csv;      /* its rows; NULL when the phase has no CSV file */
} lv_plot_phase;

typedef struct lv_plot_body {
    const char *name;
    size_t n;       /* phases it flies in, in time order */
    size_t *phase;  /* indices into lv_plot_data.phases */
    lv_csv *traj;   /* body_<name>.csv: lat, lon [rad] for the ground track */
} lv_plot_body;

typedef struct lv_plot_data {
    const char *outdir;
    cJSON *summary; /* owned */
    int flat;       /* world "flat" */
    size_t n_phases, n_bodies;
    lv_plot_phase *phases;
    lv_plot_body *bodies;
} lv_plot_data;

#define LV_PLOT_MAX_FIGS 16

/* What lv_plot_draw_figures() made and left out, for the report. */
typedef struct lv_plot_list {
    size_t n_made, n_skipped, n_notes;
    struct {
        char stem[48];   /* plots/<stem>.png, .svg */
        char title[256];
    } made[LV_PLOT_MAX_FIGS];
    struct {
        char what[64];
        char why[200];
    } skipped[LV_PLOT_MAX_FIGS];
    char notes[LV_PLOT_MAX_FIGS][200]; /* partial figures: a curve or the coastlines missing */
} lv_plot_list;

/* Draws every figure into `plotdir` (which exists). Not thread-safe: PLplot's global stream
 * table; each figure makes its own stream and ends it, the caller's stream is restored. */
lv_status lv_plot_draw_figures(const lv_plot_data *d, const char *plotdir, lv_plot_list *list,
                               lv_err *err);

/* Writes OUTDIR/index.html (temporary name, then renamed). */
lv_status lv_plot_html_write(const lv_plot_data *d, const lv_plot_list *list, lv_err *err);

#endif
