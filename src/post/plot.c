/* plot.c - lv_plot_run(): reads a run's output directory back (post/results.h: summary.json, the
 * phase and body CSVs) and hands it to the figure and report writers. Post-processing only:
 * nothing here is used while simulating. */
#define _POSIX_C_SOURCE 200809L

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/status.h"
#include "lvsim/lv_plot.h"
#include "post/plot.h"

void lv_plot_data_free(lv_plot_data *d)
{
    for (size_t k = 0; d->phases != NULL && k < d->n_phases; k++) {
        lv_results_table_free(d->phases[k].csv);
        lv_results_table_free(d->phases[k].ref);
    }
    for (size_t b = 0; d->bodies != NULL && b < d->n_bodies; b++)
        lv_results_table_free(d->bodies[b].traj);
    free(d->phases);
    free(d->bodies);
}

lv_status lv_plot_data_load(lv_plot_data *d, lv_err *err)
{
    const lv_results *res = d->res;
    d->flat = res->flat;
    d->phases = calloc(res->n_phases + 1, sizeof *d->phases);
    d->bodies = calloc(res->n_bodies + 1, sizeof *d->bodies);
    if (d->phases == NULL || d->bodies == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    d->n_phases = res->n_phases;
    d->n_bodies = res->n_bodies;
    for (size_t k = 0; k < res->n_phases; k++) {
        const lv_results_phase *ph = &res->phases[k];
        lv_plot_phase *p = &d->phases[k];
        p->name = ph->name;
        p->done = ph->done;
        p->t0 = ph->t_start;
        p->t1 = ph->t_end;
        if (ph->ref.file != NULL && lv_results_exists(res, ph->ref.file)) {
            lv_status st = lv_results_load(res, ph->ref.file, NULL, &p->ref, err);
            if (st != LV_OK)
                return st;
        }
        if (ph->csv == NULL || (!p->done && !lv_results_exists(res, ph->csv)))
            continue;
        lv_status st = lv_results_load(res, ph->csv, NULL, &p->csv, err);
        if (st != LV_OK)
            return st;
        if (lv_results_table_col(p->csv, "time") != 0)
            return lv_fail(err, LV_ERR_INPUT, "%s:%zu: the first column is not 'time'",
                           p->csv->path, p->csv->header_line);
    }
    for (size_t i = 0; i < res->n_bodies; i++) {
        const lv_results_body *rb = &res->bodies[i];
        lv_plot_body *b = &d->bodies[i];
        b->name = rb->name;
        b->n = rb->n_phases;
        b->phase = rb->phases;
        if (rb->trajectory == NULL)
            continue;
        lv_status st = lv_results_load(res, rb->trajectory, NULL, &b->traj, err);
        if (st != LV_OK)
            return st;
    }
    return LV_OK;
}

static lv_status make_dir(const char *path, lv_err *err)
{
    if (mkdir(path, 0777) == 0 || errno == EEXIST) {
        struct stat sb;
        if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode))
            return LV_OK;
        return lv_fail(err, LV_ERR_IO, "cannot create directory '%s': a file of that name exists",
                       path);
    }
    return lv_fail(err, LV_ERR_IO, "cannot create directory '%s': %s", path, LV_STRERROR(errno));
}

lv_status lv_plot_run(const char *outdir, lv_err *err)
{
    if (outdir == NULL || outdir[0] == '\0')
        return lv_fail(err, LV_ERR_INPUT, "lv_plot_run: no output directory");
    if (strlen(outdir) > 4000)
        return lv_fail(err, LV_ERR_INPUT, "lv_plot_run: output directory name too long");
    lv_plot_data d = {.outdir = outdir, .v_max = NAN, .m_0 = NAN};
    lv_results *res = NULL;
    lv_plot_list *list = calloc(1, sizeof *list);
    if (list == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    char pdir[4100];
    snprintf(pdir, sizeof pdir, "%s/plots", outdir);
    lv_status st = lv_results_open(outdir, &res, err);
    d.res = res;
    if (st == LV_OK)
        st = lv_plot_data_load(&d, err);
    if (st == LV_OK) {
        lv_plot_fig10_refs(&d);
        lv_plot_find_sites(&d);
        st = make_dir(pdir, err);
    }
    if (st == LV_OK)
        st = lv_plot_fig10_write(&d, pdir, err);
    if (st == LV_OK)
        st = lv_plot_figures(&d, pdir, list, err);
    cJSON *keys = NULL;
    if (st == LV_OK)
        st = lv_plot_keys(&d, &keys, err);
    if (st == LV_OK)
        st = lv_plot_html_write(&d, list, keys, err);
    cJSON_Delete(keys);
    lv_plot_data_free(&d);
    lv_results_free(res);
    free(list);
    return st;
}
