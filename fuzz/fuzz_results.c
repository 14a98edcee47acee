/* fuzz_results.c - libFuzzer target: a results folder as `lvsim export` and `lvsim plot` read
 * it from a user (src/post/results.c: summary.json with cJSON, the CSV files it names), then
 * what those commands compute from it before anything is drawn: the exports (CZML, KML, OEM:
 * lv_export_run), the Figure-10 data, the launch sites, the key figures and the HTML report
 * (plot.c's reading, plot_series.c, plot_keys.c, plot_html.c; the figures themselves are
 * PLplot's, in the module lvsim_plot.so, not here). Any input must give LV_OK or an error with
 * a terminated message, never a crash, a leak or a hang.
 *
 * Input: summary.json, a NUL byte, then a CSV file written under every name the summary gives
 * (each phase's files.csv, each body's trajectory), in a private temporary folder emptied
 * before every input. Seeds: fuzz/corpus/results (fuzz/make_seeds.sh). `make fuzz`. */
#define _POSIX_C_SOURCE 200809L

#include <dirent.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cjson/cJSON.h>

#include "fuzz_util.h"
#include "lvsim/lv_export.h"
#include "post/plot.h"
#include "post/results.h"

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static char dir[4200]; /* the private folder */

/* Everything in `d` removed (files, and plots/ one level down). */
static void empty(const char *d)
{
    DIR *dp = opendir(d);
    if (dp == NULL)
        return;
    struct dirent *e;
    char p[4200];
    while ((e = readdir(dp)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        snprintf(p, sizeof p, "%s/%s", d, e->d_name);
        struct stat sb;
        if (lstat(p, &sb) == 0 && S_ISDIR(sb.st_mode)) {
            empty(p);
            rmdir(p);
        } else {
            unlink(p);
        }
    }
    closedir(dp);
}

static void cleanup(void)
{
    empty(dir);
    rmdir(dir);
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    lv_fuzz_tempdir(dir, sizeof dir, "results");
    atexit(cleanup);
    return 0;
}

static void write_file(const char *name, const uint8_t *data, size_t size)
{
    char p[4200];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    FILE *fp = fopen(p, "wb");
    if (fp == NULL) /* a name the file system refuses (too long): the reader says so later */
        return;
    if (fwrite(data, 1, size, fp) != size)
        abort();
    fclose(fp);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const uint8_t *nul = memchr(data, '\0', size);
    const size_t n_sum = nul != NULL ? (size_t)(nul - data) : size;
    const uint8_t *csv = nul != NULL ? nul + 1 : data + size;
    const size_t n_csv = size - n_sum - (nul != NULL);
    empty(dir);
    write_file("summary.json", data, n_sum);
    lv_err err;
    lv_results *res = NULL;
    lv_status st = lv_results_open(dir, &res, &err);
    lv_fuzz_check_status(st, &err);
    if ((st == LV_OK) != (res != NULL))
        __builtin_trap();
    if (res == NULL) {
        empty(dir);
        return 0;
    }
    /* the CSV under every name the summary gives (checked bare names: inside the folder) */
    for (size_t k = 0; k < res->n_phases; k++)
        if (res->phases[k].csv != NULL)
            write_file(res->phases[k].csv, csv, n_csv);
    for (size_t i = 0; i < res->n_bodies; i++)
        if (res->bodies[i].trajectory != NULL)
            write_file(res->bodies[i].trajectory, csv, n_csv);
    /* a body file as the exports read it: the phase column as text, time finite */
    static const char *const text[] = {"phase", NULL}, *const finite[] = {"time", NULL};
    const lv_results_csv_spec spec = {text, finite};
    for (size_t i = 0; i < res->n_bodies; i++) {
        lv_results_table *t = NULL;
        st = lv_results_load(res, res->bodies[i].trajectory, &spec, &t, &err);
        lv_fuzz_check_status(st, &err);
        if (t != NULL) {
            for (size_t r = 0; r < t->n_rows && r < 4; r++)
                for (size_t c = 0; c < t->n_cols; c++)
                    (void)lv_results_table_text(t, r, c);
            (void)lv_results_table_col(t, "lat");
        }
        lv_results_table_free(t);
    }
    /* lvsim plot up to the figures: Figure 10's data, the sites, the key figures, the report */
    lv_plot_data d = {.res = res, .outdir = dir, .v_max = NAN, .m_0 = NAN};
    st = lv_plot_data_load(&d, &err);
    lv_fuzz_check_status(st, &err);
    if (st == LV_OK) {
        lv_plot_fig10_refs(&d);
        lv_plot_find_sites(&d);
        char pdir[4300];
        snprintf(pdir, sizeof pdir, "%s/plots", dir);
        if (mkdir(pdir, 0777) != 0)
            abort();
        st = lv_plot_fig10_write(&d, pdir, &err);
        lv_fuzz_check_status(st, &err);
        cJSON *keys = NULL;
        st = lv_plot_keys(&d, &keys, &err);
        lv_fuzz_check_status(st, &err);
        lv_plot_list list; /* nothing drawn */
        memset(&list, 0, sizeof list);
        if (st == LV_OK)
            lv_fuzz_check_status(lv_plot_html_write(&d, &list, keys, &err), &err);
        cJSON_Delete(keys);
    }
    lv_plot_data_free(&d);
    lv_results_free(res);
    /* lvsim export: reads the folder again, itself */
    lv_fuzz_check_status(lv_export_run(dir, LV_EXPORT_ALL, &err), &err);
    empty(dir); /* nothing left behind should the process end without atexit (a crash) */
    return 0;
}
