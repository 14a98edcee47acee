/* plot.h - internals of lv_plot_run(): the run's files as read back (post/results.h: summary.json,
 * the phase and body CSVs), the figures (PLplot: the only code that includes plplot.h) and the
 * HTML report. */
#ifndef LV_POST_PLOT_H
#define LV_POST_PLOT_H

#include <stddef.h>

#include "lvsim/lv_status.h"
#include "post/results.h"

typedef struct lv_plot_phase {
    const char *name;       /* borrowed from the results */
    double t0, t1;          /* s; NAN when the phase did not run */
    int done;               /* state "done" */
    lv_results_table *csv;  /* its rows (first column "time"); NULL when it has no CSV file */
} lv_plot_phase;

typedef struct lv_plot_body {
    const char *name;
    size_t n;                /* phases it flies in, in time order */
    const size_t *phase;     /* indices into lv_plot_data.phases (the results' list) */
    lv_results_table *traj;  /* body_<name>.csv: lat, lon [rad] for the ground track; or NULL */
} lv_plot_body;

typedef struct lv_plot_data {
    const lv_results *res;  /* summary.json as read back: mission, phases, events, files */
    const char *outdir;
    int flat;               /* world "flat" */
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
    /* plot_draw.c's own: which figures this process draws (two processes draw) */
    int draw_role;          /* all, the even ones or the odd ones (map figures: the even side) */
    size_t draw_index;      /* figures met so far, map figures not counted */
} lv_plot_list;

/* Draws every figure into `plotdir` (which exists). Not thread-safe: PLplot's global stream
 * table; each figure makes its own stream and ends it, the caller's stream is restored.
 * Defined in plot_draw.c, which is built into the module lvsim_plot.so (its only exported
 * symbol) and into the static liblvsim_post. */
LV_API lv_status lv_plot_draw_figures(const lv_plot_data *d, const char *plotdir,
                                      lv_plot_list *list, lv_err *err);

/* What lv_plot_run calls: lv_plot_draw_figures from the module, loaded on first use
 * (plot_load.c, shared library), or linked in (plot_link.c, static library). */
#define LV_PLOT_MODULE "lvsim_plot.so"
lv_status lv_plot_figures(const lv_plot_data *d, const char *plotdir, lv_plot_list *list,
                          lv_err *err);

struct cJSON;
/* Computes the key figures of every body and writes OUTDIR/key_figures.json; *out is the
 * document (cJSON_Delete it) for the report. */
lv_status lv_plot_keys(const lv_plot_data *d, struct cJSON **out, lv_err *err);

/* Writes OUTDIR/index.html (temporary name, then renamed); keys: lv_plot_keys' document or
 * NULL. */
lv_status lv_plot_html_write(const lv_plot_data *d, const lv_plot_list *list,
                             const struct cJSON *keys, lv_err *err);

#endif
