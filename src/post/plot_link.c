/* plot_link.c - lv_plot_figures() in the static liblvsim_post (the tests): the figures are
 * linked in and drawn directly; the shared library loads them instead (plot_load.c). */
#include "campaign/mc_plot.h"
#include "post/plot.h"

lv_status lv_plot_figures(const lv_plot_data *d, const char *plotdir, lv_plot_list *list,
                          lv_err *err)
{
    return lv_plot_draw_figures(d, plotdir, list, err);
}

lv_status lv_mc_plot_figures(const lv_mc_data *d, const char *outdir, lv_mc_figs *figs,
                             lv_err *err)
{
    return lv_mc_draw_figures(d, outdir, figs, err);
}
