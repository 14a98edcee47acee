/* bench_sinks.c - what writing a result costs per row: the CSV sink, the MAT sink and both, for
 * rows of 57 columns (a 3-DoF phase: time, 7 states, 7 derivatives, 42 outputs) of values like
 * a run's (17 significant digits, a few integers and zeros), 10^3 to 10^5 rows; CPU time of
 * this thread per row and per row per 50 columns, the time to close (write) included.
 * Issue 11's target: <= 1 us of CPU per row per 50 columns for CSV + MAT together. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

#include "lvsim/lv_io.h"

#define NCOL 57

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Writes n rows to the sinks (1: CSV, 2: MAT, 3: both); returns CPU seconds, or -1. */
static double write_rows(unsigned which, long n, const char *dir)
{
    static lv_var sig[NCOL];
    static lv_var_kind kinds[NCOL];
    static char names[NCOL][16];
    for (int i = 0; i < NCOL; i++) {
        snprintf(names[i], sizeof names[i], i == 0 ? "time" : "x%d", i);
        sig[i] = (lv_var){names[i], i == 0 ? "s" : "m", "a signal", 0.0, 1.0};
        kinds[i] = i == 0 ? LV_VAR_OUTPUT : LV_VAR_STATE;
    }
    lv_result_info info = {"bench", "", 0, NULL, NULL, NCOL, sig, kinds};
    lv_sink s[2] = {{0}, {0}};
    size_t ns = 0;
    char path[512];
    lv_err err;
    /* 1024 distinct rows made beforehand: only the writing is timed */
    static double rows[1024][NCOL];
    for (int r = 0; r < 1024; r++)
        for (int i = 1; i < NCOL; i++)
            rows[r][i] = i % 9 == 0 ? (double)(i % 2) : sin(1e-3 * (double)r + i) * pow(10.0, i % 8);
    const double t0 = cpu_now();
    if (which & 1u) {
        snprintf(path, sizeof path, "%s/bench.csv", dir);
        if (lv_sink_csv_create(path, &s[ns++], &err) != LV_OK)
            goto fail;
    }
    if (which & 2u) {
        snprintf(path, sizeof path, "%s/bench.mat", dir);
        if (lv_sink_mat_create(path, &s[ns++], &err) != LV_OK)
            goto fail;
    }
    for (size_t k = 0; k < ns; k++)
        if (s[k].vt->open(s[k].self, &info, &err) != LV_OK)
            goto fail;
    for (long r = 0; r < n; r++) {
        double *row = rows[r & 1023];
        row[0] = 0.01 * (double)r;
        for (size_t k = 0; k < ns; k++)
            if (s[k].vt->row(s[k].self, row, &err) != LV_OK)
                goto fail;
    }
    for (size_t k = 0; k < ns; k++)
        if (s[k].vt->close(s[k].self, NULL, &err) != LV_OK)
            goto fail;
    const double t = cpu_now() - t0;
    for (size_t k = 0; k < ns; k++)
        lv_sink_destroy(&s[k]);
    return t;
fail:
    fprintf(stderr, "bench_sinks: %s\n", err.msg);
    for (size_t k = 0; k < ns; k++)
        lv_sink_destroy(&s[k]);
    return -1.0;
}

int main(void)
{
    char dir[] = "/tmp/lvsim-bench-sinks-XXXXXX";
    if (mkdtemp(dir) == NULL) {
        perror("mkdtemp");
        return 1;
    }
    printf("# result sinks, %d columns: CPU per row (best of 3), close included\n", NCOL);
    printf("%-10s %8s %12s %18s\n", "sinks", "rows", "us/row", "us/row/50 cols");
    const char *label[] = {"", "csv", "mat", "csv+mat"};
    int rc = 0;
    for (unsigned which = 1; which <= 3 && rc == 0; which++)
        for (long n = 1000; n <= 100000 && rc == 0; n *= 10) {
            double best = INFINITY;
            for (int k = 0; k < 3; k++) {
                const double t = write_rows(which, n, dir);
                if (t < 0) {
                    rc = 1;
                    break;
                }
                best = fmin(best, t);
            }
            printf("%-10s %8ld %12.3f %18.3f\n", label[which], n, 1e6 * best / (double)n,
                   1e6 * best / (double)n * 50.0 / NCOL);
        }
    char p[600];
    snprintf(p, sizeof p, "%s/bench.csv", dir);
    remove(p);
    snprintf(p, sizeof p, "%s/bench.mat", dir);
    remove(p);
    rmdir(dir);
    printf("# target (issue 11): csv+mat <= 1 us per row per 50 columns\n");
    return rc;
}
