/* plot.c - lv_plot_run(): reads a run's output directory back (summary.json, the phase and body
 * CSVs) and hands it to the figure and report writers. Post-processing only: nothing here is
 * used while simulating. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/status.h"
#include "lvsim/lv_plot.h"
#include "post/plot.h"

static void data_free(lv_plot_data *d)
{
    for (size_t k = 0; k < d->n_phases; k++)
        lv_plot_csv_free(d->phases[k].csv);
    for (size_t b = 0; b < d->n_bodies; b++) {
        free(d->bodies[b].phase);
        lv_plot_csv_free(d->bodies[b].traj);
    }
    free(d->phases);
    free(d->bodies);
    cJSON_Delete(d->summary);
}

static lv_status read_summary(const char *path, cJSON **out, lv_err *err)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return lv_fail(err, LV_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap + 1);
    while (buf != NULL) {
        n += fread(buf + n, 1, cap - n, f);
        if (n < cap)
            break;
        char *bigger = realloc(buf, 2 * cap + 1);
        if (bigger == NULL)
            free(buf);
        buf = bigger;
        cap *= 2;
    }
    fclose(f);
    if (buf == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory reading '%s'", path);
    buf[n] = '\0';
    const char *stop = NULL;
    *out = cJSON_ParseWithOpts(buf, &stop, 0);
    if (*out == NULL) {
        int line = 1;
        for (const char *p = buf; stop != NULL && p < stop && *p; p++)
            line += *p == '\n';
        free(buf);
        return lv_fail(err, LV_ERR_INPUT, "%s:%d: not valid JSON", path, line);
    }
    free(buf);
    return LV_OK;
}

static double num_or_nan(const cJSON *o, const char *key)
{
    const cJSON *j = cJSON_GetObjectItemCaseSensitive(o, key);
    return cJSON_IsNumber(j) ? j->valuedouble : NAN;
}

/* A file named in summary.json, relative to OUTDIR: a bare name, nothing that climbs out. */
static int safe_name(const char *s)
{
    return s != NULL && s[0] != '\0' && s[0] != '/' && strstr(s, "..") == NULL;
}

static lv_status load_phases(lv_plot_data *d, const char *spath, lv_err *err)
{
    const cJSON *phases = cJSON_GetObjectItemCaseSensitive(d->summary, "phases");
    if (!cJSON_IsArray(phases))
        return lv_fail(err, LV_ERR_INPUT, "%s: no 'phases' array", spath);
    d->n_phases = (size_t)cJSON_GetArraySize(phases);
    d->phases = calloc(d->n_phases + 1, sizeof *d->phases);
    if (d->phases == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    char path[4300];
    size_t k = 0;
    const cJSON *ph;
    cJSON_ArrayForEach(ph, phases)
    {
        lv_plot_phase *p = &d->phases[k++];
        const cJSON *name = cJSON_GetObjectItemCaseSensitive(ph, "name");
        const cJSON *state = cJSON_GetObjectItemCaseSensitive(ph, "state");
        if (!cJSON_IsString(name))
            return lv_fail(err, LV_ERR_INPUT, "%s: phase %zu has no name", spath, k);
        p->name = name->valuestring;
        p->done = cJSON_IsString(state) && strcmp(state->valuestring, "done") == 0;
        p->t0 = num_or_nan(ph, "t_start");
        p->t1 = num_or_nan(ph, "t_end");
        const cJSON *files = cJSON_GetObjectItemCaseSensitive(ph, "files");
        const cJSON *csv = cJSON_GetObjectItemCaseSensitive(files, "csv");
        if (!cJSON_IsString(csv))
            continue;
        if (!safe_name(csv->valuestring))
            return lv_fail(err, LV_ERR_INPUT, "%s: phase '%s': bad file name '%s'", spath,
                           p->name, csv->valuestring);
        snprintf(path, sizeof path, "%s/%s", d->outdir, csv->valuestring);
        struct stat sb;
        if (!p->done && stat(path, &sb) != 0)
            continue; /* a failed phase may have left no rows */
        lv_status st = lv_plot_csv_read(path, &p->csv, err);
        if (st != LV_OK)
            return st;
        if (lv_plot_csv_col(p->csv, "time") != 0)
            return lv_fail(err, LV_ERR_INPUT, "%s:1: the first column is not 'time'", path);
    }
    return LV_OK;
}

static lv_status load_bodies(lv_plot_data *d, const char *spath, lv_err *err)
{
    const cJSON *bodies = cJSON_GetObjectItemCaseSensitive(d->summary, "bodies");
    if (!cJSON_IsArray(bodies))
        return lv_fail(err, LV_ERR_INPUT, "%s: no 'bodies' array", spath);
    d->n_bodies = (size_t)cJSON_GetArraySize(bodies);
    d->bodies = calloc(d->n_bodies + 1, sizeof *d->bodies);
    if (d->bodies == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    char path[4300];
    size_t i = 0;
    const cJSON *bj;
    cJSON_ArrayForEach(bj, bodies)
    {
        lv_plot_body *b = &d->bodies[i++];
        const cJSON *name = cJSON_GetObjectItemCaseSensitive(bj, "name");
        const cJSON *pl = cJSON_GetObjectItemCaseSensitive(bj, "phases");
        const cJSON *traj = cJSON_GetObjectItemCaseSensitive(bj, "trajectory");
        if (!cJSON_IsString(name) || !cJSON_IsArray(pl))
            return lv_fail(err, LV_ERR_INPUT, "%s: body %zu has no name or no phases", spath, i);
        b->name = name->valuestring;
        b->phase = calloc((size_t)cJSON_GetArraySize(pl) + 1, sizeof *b->phase);
        if (b->phase == NULL)
            return lv_fail(err, LV_ERR_NOMEM, "out of memory");
        const cJSON *pn;
        cJSON_ArrayForEach(pn, pl)
        {
            size_t k = 0;
            while (k < d->n_phases &&
                   !(cJSON_IsString(pn) && strcmp(d->phases[k].name, pn->valuestring) == 0))
                k++;
            if (k == d->n_phases)
                return lv_fail(err, LV_ERR_INPUT, "%s: body '%s': unknown phase '%s'", spath,
                               b->name, cJSON_IsString(pn) ? pn->valuestring : "?");
            b->phase[b->n++] = k;
        }
        if (!cJSON_IsString(traj))
            continue;
        if (!safe_name(traj->valuestring))
            return lv_fail(err, LV_ERR_INPUT, "%s: body '%s': bad file name '%s'", spath,
                           b->name, traj->valuestring);
        snprintf(path, sizeof path, "%s/%s", d->outdir, traj->valuestring);
        lv_status st = lv_plot_csv_read(path, &b->traj, err);
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
    return lv_fail(err, LV_ERR_IO, "cannot create directory '%s': %s", path, strerror(errno));
}

lv_status lv_plot_run(const char *outdir, lv_err *err)
{
    if (outdir == NULL || outdir[0] == '\0')
        return lv_fail(err, LV_ERR_INPUT, "lv_plot_run: no output directory");
    if (strlen(outdir) > 4000)
        return lv_fail(err, LV_ERR_INPUT, "lv_plot_run: output directory name too long");
    lv_plot_data d = {.outdir = outdir};
    lv_plot_list *list = calloc(1, sizeof *list);
    if (list == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    char spath[4100], pdir[4100];
    snprintf(spath, sizeof spath, "%s/summary.json", outdir);
    snprintf(pdir, sizeof pdir, "%s/plots", outdir);
    lv_status st = read_summary(spath, &d.summary, err);
    if (st == LV_OK) {
        const cJSON *world = cJSON_GetObjectItemCaseSensitive(d.summary, "world");
        d.flat = cJSON_IsString(world) && strcmp(world->valuestring, "flat") == 0;
        st = load_phases(&d, spath, err);
    }
    if (st == LV_OK)
        st = load_bodies(&d, spath, err);
    if (st == LV_OK)
        st = make_dir(pdir, err);
    if (st == LV_OK)
        st = lv_plot_draw_figures(&d, pdir, list, err);
    if (st == LV_OK)
        st = lv_plot_html_write(&d, list, err);
    data_free(&d);
    free(list);
    return st;
}
