/* plot_load.c - lv_plot_figures() in the shared liblvsim_post: the figures are drawn by the
 * module lvsim_plot.so (plot_draw.c: PLplot, its cairo drivers, libpng), which is loaded with
 * dlopen() the first time a figure is drawn, from the folder "lvsim" next to this library
 * (build/lib/lvsim/, <prefix>/lib/lvsim/). A program that draws nothing (lvsim check, run
 * --no-plots, export) never loads PLplot, cairo, pango and their dependencies. The module
 * stays loaded (PLplot and its drivers are not made to be unloaded); a second dlopen() of it
 * is only a reference count. */
#define _GNU_SOURCE /* dladdr */

#include <dlfcn.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "campaign/mc_plot.h"
#include "core/status.h"
#include "post/plot.h"

static const char anchor = 0; /* an address inside liblvsim_post */

/* The module's function `name` (a data pointer: dlsym's), or NULL with err. */
static void *module_sym(const char *name, lv_err *err)
{
    Dl_info info;
    char lib[PATH_MAX], path[PATH_MAX + 64];
    if (dladdr(&anchor, &info) == 0 || info.dli_fname == NULL ||
        realpath(info.dli_fname, lib) == NULL) {
        lv_fail(err, LV_ERR_IO, "plots: cannot tell where liblvsim_post is, so not where its "
                                "plotting module %s is", LV_PLOT_MODULE);
        return NULL;
    }
    char *slash = strrchr(lib, '/');
    if (slash != NULL)
        *slash = '\0';
    snprintf(path, sizeof path, "%s/lvsim/%s", lib, LV_PLOT_MODULE);
    void *h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (h == NULL) {
        lv_fail(err, LV_ERR_IO, "plots: cannot load the plotting module: %s", dlerror());
        return NULL;
    }
    void *sym = dlsym(h, name);
    if (sym == NULL)
        lv_fail(err, LV_ERR_IO, "plots: %s has no %s", path, name);
    return sym;
}

typedef lv_status (*draw_fn)(const lv_plot_data *, const char *, lv_plot_list *, lv_err *);
typedef lv_status (*mc_draw_fn)(const lv_mc_data *, const char *, lv_mc_figs *, lv_err *);

lv_status lv_plot_figures(const lv_plot_data *d, const char *plotdir, lv_plot_list *list,
                          lv_err *err)
{
    void *sym = module_sym("lv_plot_draw_figures", err);
    if (sym == NULL)
        return err ? err->code : LV_ERR_IO;
    draw_fn fn;
    memcpy(&fn, &sym, sizeof fn); /* POSIX: a data pointer from dlsym names the function */
    return fn(d, plotdir, list, err);
}

lv_status lv_mc_plot_figures(const lv_mc_data *d, const char *outdir, lv_mc_figs *figs,
                             lv_err *err)
{
    void *sym = module_sym("lv_mc_draw_figures", err);
    if (sym == NULL)
        return err ? err->code : LV_ERR_IO;
    mc_draw_fn fn;
    memcpy(&fn, &sym, sizeof fn);
    return fn(d, outdir, figs, err);
}
