/* mc_plot.h - the campaign's figures (mc_plot.c), listed for the report page (plot.c). */
#ifndef LV_CAMPAIGN_MC_PLOT_H
#define LV_CAMPAIGN_MC_PLOT_H

#include "campaign/mc_data.h"

#define LV_MC_MAX_FIGS 48

typedef struct lv_mc_figs {
    size_t n;
    char stem[LV_MC_MAX_FIGS][64];    /* plots/<stem>.png */
    char title[LV_MC_MAX_FIGS][256];
} lv_mc_figs;

/* Draws every figure into OUTDIR/plots (created). PLplot: one thread. In the figures' module
 * lvsim_plot.so with the run's figures (liblvsim_post loads it on first use:
 * src/post/plot_load.c), linked in the static library (plot_link.c). */
LV_API lv_status lv_mc_draw_figures(const lv_mc_data *d, const char *outdir, lv_mc_figs *figs,
                                    lv_err *err);
/* The same through the module: what the report calls. */
lv_status lv_mc_plot_figures(const lv_mc_data *d, const char *outdir, lv_mc_figs *figs,
                             lv_err *err);

#endif
