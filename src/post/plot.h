/* plot.h - internals of lv_plot_run(): the run's files as read back (post/results.h: summary.json,
 * the phase and body CSVs), the figures (PLplot: the only code that includes plplot.h) and the
 * HTML report. */
#ifndef LV_POST_PLOT_H
#define LV_POST_PLOT_H

#include <stddef.h>
#include <string.h>

#include "lvsim/lv_status.h"
#include "post/results.h"

typedef struct lv_plot_phase {
    const char *name;       /* borrowed from the results */
    double t0, t1;          /* s; NAN when the phase did not run */
    int done;               /* state "done" */
    lv_results_table *csv;  /* its rows (first column "time"); NULL when it has no CSV file */
    lv_results_table *ref;  /* its rows compared with its reference (reference_<k>_<name>.csv:
                               time, h, h_ref, v_rel, v_ref, m, m_ref, d_*); or NULL */
} lv_plot_phase;

typedef struct lv_plot_body {
    const char *name;
    size_t n;                /* phases it flies in, in time order */
    const size_t *phase;     /* indices into lv_plot_data.phases (the results' list) */
    lv_results_table *traj;  /* body_<name>.csv: lat, lon [rad] for the ground track; or NULL */
} lv_plot_body;

/* A place the ground-track figures mark: a runway (the part of it a runway phase rolled on)
 * or, when no runway is there, the launch site (the mission's first position). */
typedef struct lv_plot_site {
    char label[96];         /* "runway 09 (liftoff)", "launch site" */
    double lat, lon;        /* rad: the runway's threshold, or the launch site */
    double lat1, lon1;      /* rad: the farthest point along the runway rolled on; = lat, lon
                             * for a launch site */
    double heading;         /* rad from north to east: the runway's heading; NAN: a point */
    double length;          /* m: threshold to (lat1, lon1) along the runway; 0: a point */
} lv_plot_site;

#define LV_PLOT_MAX_SITES 8

typedef struct lv_plot_data {
    const lv_results *res;  /* summary.json as read back: mission, phases, events, files */
    const char *outdir;
    int flat;               /* world "flat" */
    size_t n_phases, n_bodies;
    lv_plot_phase *phases;
    lv_plot_body *bodies;
    /* the paper's Figure 10 (lv_plot_fig10_refs): every body's speed over v_max and mass over
     * m_0; NAN when no phase file has a speed (or the mass) */
    double v_max;           /* m/s: the largest speed ('v_rel' or 'speed') of any body, any phase */
    double m_0;             /* kg: the mission's initial mass, the largest first mass of a body */
    lv_plot_site sites[LV_PLOT_MAX_SITES]; /* lv_plot_find_sites; none on a flat world */
    size_t n_sites;
} lv_plot_data;

#define LV_PLOT_MAX_FIGS 32

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

/* Whether body `b` is the vehicle that flies in phase `k`: the phase's bottom
 * stage, the first of its `stages` in summary.json, is that body. The vehicle-attitude figures
 * (attitude, angle_of_attack, body_rates, gimbal, attitude_error) draw a body's curve over
 * these phases only: the stages a phase carries ride on its bottom stage's attitude, so one
 * curve per phase (docs/visualization.md). */
static inline int lv_plot_is_vehicle(const lv_plot_data *d, size_t b, size_t k)
{
    if (d->res == NULL || b >= d->n_bodies || k >= d->n_phases || k >= d->res->n_phases)
        return 0;
    const lv_results_phase *ph = &d->res->phases[k];
    return ph->n_stages > 0 && ph->stages[0] != NULL && d->bodies[b].name != NULL &&
           strcmp(ph->stages[0], d->bodies[b].name) == 0;
}

/* The phase CSVs (a failed phase may have left none) and the body trajectories of d->res
 * into d (plot.c); lv_plot_data_free releases what it loaded (also after a failure). */
lv_status lv_plot_data_load(lv_plot_data *d, lv_err *err);
void lv_plot_data_free(lv_plot_data *d);

/* Sets d->v_max and d->m_0 from the bodies' phase files (plot_series.c). */
void lv_plot_fig10_refs(lv_plot_data *d);

/* Writes OUTDIR/plots/fig10_normalised.csv, the data of the Figure-10 plot: a comment line
 * with v_max [m/s] and m_0 [kg], the header "time [s],body,phase,v_norm,m_norm", then every
 * body's rows across its phases in time order (v_norm = speed / v_max, m_norm = m / m_0;
 * dimensionless; an event instant twice). Nothing when v_max or m_0 is NAN. Through a
 * temporary file. Errors: LV_ERR_IO, LV_ERR_NOMEM. */
lv_status lv_plot_fig10_write(const lv_plot_data *d, const char *plotdir, lv_err *err);

/* Fills d->sites (plot_series.c): every runway phase's runway (a phase whose file has
 * 'distance', 'normal_force', 'lat', 'lon', 'heading': one that rolls on a runway; the
 * threshold found by extrapolating its rows' positions back to distance 0), then the launch
 * site (the first row of the earliest phase with 'lat' and 'lon') unless a runway's threshold
 * is within 0.01 deg (about 1 km on the Earth) of it.
 * Nothing on a flat world. */
void lv_plot_find_sites(lv_plot_data *d);

struct cJSON;
/* Computes the key figures of every body and writes OUTDIR/key_figures.json; *out is the
 * document (cJSON_Delete it) for the report. */
lv_status lv_plot_keys(const lv_plot_data *d, struct cJSON **out, lv_err *err);

/* Writes OUTDIR/index.html (temporary name, then renamed); keys: lv_plot_keys' document or
 * NULL. */
lv_status lv_plot_html_write(const lv_plot_data *d, const lv_plot_list *list,
                             const struct cJSON *keys, lv_err *err);

#endif
