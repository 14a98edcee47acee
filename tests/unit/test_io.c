/* test_io.c - result sinks: memory, CSV and dsres MAT v4 files, the failed-file
 * convention, error paths. Writes io_out/sine.mat and io_out/sine_fail.failed.mat,
 * which tests/python/check_dsres.py reads back (ctest test_io_dsres).
 *
 * The sample run (same recipe in check_dsres.py): t_k = k * 0.1, k = 0..10;
 * h = sin(t), der(h) = cos(t), m = 100 before and 60 after an event at t = 0.5
 * (that instant appears twice), C[1,2] = 0.5 t; four parameters.
 */
#define _POSIX_C_SOURCE 200809L /* mkdir, chmod, geteuid, setrlimit */

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <signal.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "io/sink.h"
#include "lvsim/lv_io.h"
#include "lvsim/lv_sim.h"

#define OUT "io_out"

static const lv_var sig[] = {
    {"time", "s", "", 0, 0},
    {"h", "m", "Altitude", 0, 1},
    {"der(h)", "m/s", "der(Altitude)", 0, 0},
    {"m", "kg", "Vehicle mass", 0, 0},
    {"C[1,2]", "", "Attitude matrix element, body to ECI", 0, 0},
};
static const lv_var_kind kinds[] = {LV_VAR_OUTPUT, LV_VAR_STATE, LV_VAR_DERIVATIVE,
                                    LV_VAR_STATE, LV_VAR_OUTPUT};
static const lv_var par[] = {
    {"mdot", "kg/s", "Mass flow", 12.5, 0},
    {"isp", "s", "Specific impulse", 300, 0},
    {"g0", "m/s2", "Standard gravity", 9.80665, 0},
    {"n_stages", "", "Stage count", 2, 0},
};
static const double par_val[] = {12.5, 300.0, 9.80665, 2.0};
enum { NSIG = 5, NPAR = 4, NROWS = 12 };

static lv_result_info sample_info(void)
{
    lv_result_info info = {"sample", "test result", NPAR, par, par_val, NSIG, sig, kinds};
    return info;
}

/* Row i of the sample run (i = 0..11; rows 5 and 6 are the event at t = 0.5). */
static void sample_row(int i, double *v)
{
    const int k = i <= 5 ? i : i - 1;
    const double t = k * 0.1;
    v[0] = t;
    v[1] = sin(t);
    v[2] = cos(t);
    v[3] = i <= 5 ? 100.0 : 60.0;
    v[4] = 0.5 * t;
}

/* open, `nrows` rows, close(failure); returns the first failing status. */
static lv_status run_sink(lv_sink *s, int nrows, const char *failure, lv_err *err)
{
    lv_result_info info = sample_info();
    lv_status st = s->vt->open(s->self, &info, err);
    for (int i = 0; i < nrows && st == LV_OK; i++) {
        double v[NSIG];
        sample_row(i, v);
        st = s->vt->row(s->self, v, err);
    }
    if (st == LV_OK)
        st = s->vt->close(s->self, failure, err);
    return st;
}

static int exists(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0;
}

static char *slurp(const char *path, size_t *len)
{
    FILE *fp = fopen(path, "rb");
    if (fp == NULL)
        return NULL;
    size_t cap = 4096, n = 0;
    char *buf = malloc(cap + 1);
    size_t got;
    while (buf != NULL && (got = fread(buf + n, 1, cap - n, fp)) > 0) {
        n += got;
        if (n == cap) {
            char *b = realloc(buf, 2 * cap + 1);
            if (b == NULL) {
                free(buf);
                buf = NULL;
            }
            buf = b;
            cap *= 2;
        }
    }
    fclose(fp);
    if (buf != NULL)
        buf[n] = '\0';
    if (len != NULL)
        *len = n;
    return buf;
}

static void write_text(const char *path, const char *text)
{
    FILE *fp = fopen(path, "w");
    if (fp != NULL) {
        fputs(text, fp);
        fclose(fp);
    }
}

static void test_failed_path(void)
{
    lv_err err = {0};
    char buf[64];
    CHECK_OK(lv_result_failed_path("dir/phase_3.mat", buf, sizeof buf, &err), &err);
    CHECK(strcmp(buf, "dir/phase_3.failed.mat") == 0);
    CHECK_OK(lv_result_failed_path("x.csv", buf, sizeof buf, &err), &err);
    CHECK(strcmp(buf, "x.failed.csv") == 0);
    CHECK_OK(lv_result_failed_path("run.v2/dsres", buf, sizeof buf, &err), &err);
    CHECK(strcmp(buf, "run.v2/dsres.failed") == 0);
    CHECK_OK(lv_result_failed_path("a/.hidden", buf, sizeof buf, &err), &err);
    CHECK(strcmp(buf, "a/.hidden.failed") == 0);
    CHECK_OK(lv_result_failed_path("a.tar.gz", buf, sizeof buf, &err), &err);
    CHECK(strcmp(buf, "a.tar.failed.gz") == 0);
    /* exactly fits: strlen("x.failed.csv") + 1 = 13 */
    CHECK_OK(lv_result_failed_path("x.csv", buf, 13, &err), &err);
    CHECK_FAILS(lv_result_failed_path("x.csv", buf, 12, &err), &err, LV_ERR_INPUT, "x.csv");
    CHECK_FAILS(lv_result_failed_path("", buf, sizeof buf, &err), &err, LV_ERR_INPUT, "empty");
}

static void test_memory(void)
{
    lv_err err = {0};
    lv_result *r = NULL;
    lv_sink s = {0};
    CHECK_OK(lv_sink_memory_create(&r, &s, &err), &err);
    CHECK(strcmp(s.vt->format, "memory") == 0);
    CHECK(lv_result_rows(r) == 0 && !lv_result_closed(r) && lv_result_failure(r) == NULL);
    CHECK(lv_result_name(r, 0) == NULL && lv_result_unit(r, 0) == NULL && lv_result_data(r) == NULL);
    CHECK_OK(run_sink(&s, NROWS, NULL, &err), &err);
    CHECK(lv_result_rows(r) == NROWS);
    CHECK(lv_result_signals(r) == NSIG);
    CHECK(lv_result_closed(r));
    CHECK(lv_result_failure(r) == NULL);
    size_t col = 99;
    CHECK_OK(lv_result_column(r, "der(h)", &col, &err), &err);
    CHECK(col == 2);
    CHECK_CLOSE(lv_result_value(r, 3, col), cos(0.3), 0.0);
    CHECK_OK(lv_result_column(r, "m", &col, &err), &err);
    CHECK(lv_result_value(r, 5, col) == 100.0 && lv_result_value(r, 6, col) == 60.0);
    CHECK(lv_result_value(r, 5, 0) == lv_result_value(r, 6, 0)); /* event row twice */
    CHECK(isnan(lv_result_value(r, NROWS, 0)));
    CHECK(isnan(lv_result_value(r, 0, NSIG)));
    /* names and units copied (the sample's lv_var array may go); every value in one block */
    for (size_t c = 0; c < NSIG; c++) {
        CHECK(lv_result_name(r, c) != NULL && strcmp(lv_result_name(r, c), sig[c].name) == 0);
        CHECK(lv_result_unit(r, c) != NULL && strcmp(lv_result_unit(r, c), sig[c].unit) == 0);
        CHECK(lv_result_name(r, c) != sig[c].name);
    }
    CHECK(strcmp(lv_result_unit(r, 4), "") == 0);
    CHECK(lv_result_name(r, NSIG) == NULL && lv_result_unit(r, NSIG) == NULL);
    const double *data = lv_result_data(r);
    CHECK(data != NULL);
    for (size_t i = 0; data != NULL && i < NROWS; i++)
        for (size_t c = 0; c < NSIG; c++)
            CHECK(data[i * NSIG + c] == lv_result_value(r, i, c));
    CHECK(lv_result_name(NULL, 0) == NULL && lv_result_data(NULL) == NULL);
    CHECK_FAILS(lv_result_column(r, "der(hh)", &col, &err), &err, LV_ERR_NOTFOUND, "der(h)");
    CHECK_FAILS(s.vt->close(s.self, NULL, &err), &err, LV_ERR_INPUT, "twice");
    double v[NSIG] = {0};
    CHECK_FAILS(s.vt->row(s.self, v, &err), &err, LV_ERR_INPUT, "after close");
    lv_sink_destroy(&s);
    CHECK(s.vt == NULL && s.self == NULL);
    lv_sink_destroy(&s); /* zeroed sink */
    lv_sink_destroy(NULL);
    lv_result_free(r);

    /* failure text is kept; rows up to the failure too */
    CHECK_OK(lv_sink_memory_create(&r, &s, &err), &err);
    CHECK_OK(run_sink(&s, 3, "solver failed at t = 0.2", &err), &err);
    CHECK(lv_result_rows(r) == 3);
    CHECK(lv_result_failure(r) != NULL && strcmp(lv_result_failure(r), "solver failed at t = 0.2") == 0);
    lv_sink_destroy(&s);
    lv_result_free(r);
    lv_result_free(NULL);
}

static void test_csv(void)
{
    lv_err err = {0};
    lv_sink s = {0};
    const char *path = OUT "/sine.csv";
    remove(path);
    CHECK_OK(lv_sink_csv_create(path, &s, &err), &err);
    CHECK(strcmp(s.vt->format, "csv") == 0);
    CHECK_OK(run_sink(&s, NROWS, NULL, &err), &err);
    lv_sink_destroy(&s);
    CHECK(exists(path));
    CHECK(!exists(OUT "/sine.csv.tmp"));
    CHECK(!exists(OUT "/sine.failed.csv"));

    char *text = slurp(path, NULL);
    CHECK(text != NULL);
    if (text == NULL)
        return;
    /* "C[1,2]" has no unit: dimensionless, "[1]" (lv_units.h) */
    const char *header = "time [s],h [m],der(h) [m/s],m [kg],\"C[1,2] [1]\"\n";
    CHECK(strncmp(text, header, strlen(header)) == 0);
    /* values read back exactly (%.17g round-trips) */
    const char *p = strchr(text, '\n') + 1;
    int rows = 0;
    while (*p != '\0' && rows < NROWS + 1) {
        double want[NSIG];
        sample_row(rows, want);
        for (int i = 0; i < NSIG; i++) {
            char *end;
            const double got = strtod(p, &end);
            CHECK(got == want[i]);
            CHECK(*end == (i + 1 < NSIG ? ',' : '\n'));
            p = *end != '\0' ? end + 1 : end;
        }
        rows++;
    }
    CHECK(rows == NROWS);
    CHECK(*p == '\0');
    free(text);

    /* failed run: rows kept, a final comment line, the failed name; an older
     * successful file under the final name is left alone */
    const char *keep = OUT "/keep.csv";
    write_text(keep, "old result\n");
    remove(OUT "/keep.failed.csv");
    CHECK_OK(lv_sink_csv_create(keep, &s, &err), &err);
    CHECK_OK(run_sink(&s, 4, "CVODE error at t = 0.3:\nrepeated test failures", &err), &err);
    lv_sink_destroy(&s);
    text = slurp(keep, NULL);
    CHECK(text != NULL && strcmp(text, "old result\n") == 0);
    free(text);
    CHECK(!exists(OUT "/keep.csv.tmp"));
    text = slurp(OUT "/keep.failed.csv", NULL);
    CHECK(text != NULL);
    if (text != NULL) {
        const char *tail = "# run failed: CVODE error at t = 0.3: repeated test failures\n";
        const size_t n = strlen(text), nt = strlen(tail);
        CHECK(n > nt && strcmp(text + n - nt, tail) == 0);
        int lines = 0;
        for (const char *c = text; *c != '\0'; c++)
            lines += *c == '\n';
        CHECK(lines == 1 + 4 + 1);
        free(text);
    }
}

/* Reads the MAT v4 headers of `path`: type codes, names, sizes, in order.
 * Independent of libmatio. Returns the number of matrices (-1: corrupt). */
typedef struct mat4_hdr {
    int32_t type, mrows, ncols, imagf;
    char name[32];
    long data_pos;
} mat4_hdr;

static int read_mat4_headers(const char *path, mat4_hdr *h, int max)
{
    FILE *fp = fopen(path, "rb");
    if (fp == NULL)
        return -1;
    int n = 0;
    int32_t w[5];
    while (n < max && fread(w, sizeof w, 1, fp) == 1) {
        h[n].type = w[0];
        h[n].mrows = w[1];
        h[n].ncols = w[2];
        h[n].imagf = w[3];
        if (w[4] < 1 || w[4] > (int32_t)sizeof h[n].name ||
            fread(h[n].name, (size_t)w[4], 1, fp) != 1 || h[n].name[w[4] - 1] != '\0') {
            n = -1;
            break;
        }
        h[n].data_pos = ftell(fp);
        const int p = (w[0] / 10) % 10;
        const long elem = p == 0 ? 8 : p == 1 || p == 2 ? 4 : p == 5 ? 1 : 2;
        if (fseek(fp, elem * w[1] * w[2], SEEK_CUR) != 0) {
            n = -1;
            break;
        }
        n++;
    }
    fclose(fp);
    return n;
}

static void test_mat(void)
{
    lv_err err = {0};
    lv_sink s = {0};
    const char *path = OUT "/sine.mat";
    remove(path);
    CHECK_OK(lv_sink_mat_create(path, &s, &err), &err);
    CHECK(strcmp(s.vt->format, "mat") == 0);
    CHECK_OK(run_sink(&s, NROWS, NULL, &err), &err);
    lv_sink_destroy(&s);
    CHECK(exists(path) && !exists(OUT "/sine.mat.tmp") && !exists(OUT "/sine.failed.mat"));

    /* the types and order Dymola/OpenModelica write and OpenModelica's reader demands */
    mat4_hdr h[8];
    static const char *const want_name[6] = {"Aclass", "name", "description",
                                             "dataInfo", "data_1", "data_2"};
    static const int32_t want_type[6] = {51, 51, 51, 20, 0, 0};
    const int n = read_mat4_headers(path, h, 8);
    CHECK(n == 6);
    for (int i = 0; i < 6 && i < n; i++) {
        CHECK(strcmp(h[i].name, want_name[i]) == 0);
        CHECK(h[i].type == want_type[i]);
        CHECK(h[i].imagf == 0);
    }
    if (n == 6) {
        CHECK(h[0].mrows == 4 && h[0].ncols == 11);
        CHECK(h[1].mrows == (int32_t)sizeof "n_stages" && h[1].ncols == NSIG + NPAR);
        CHECK(h[3].mrows == 4 && h[3].ncols == NSIG + NPAR);
        CHECK(h[4].mrows == NPAR + 1 && h[4].ncols == 2);
        CHECK(h[5].mrows == NSIG && h[5].ncols == NROWS);
        /* data_2 is the rows in order: spot-check the event rows */
        FILE *fp = fopen(path, "rb");
        double d[2 * NSIG];
        CHECK(fp != NULL && fseek(fp, h[5].data_pos + 5 * NSIG * 8, SEEK_SET) == 0 &&
              fread(d, sizeof d, 1, fp) == 1);
        if (fp != NULL)
            fclose(fp);
        CHECK(d[0] == 0.5 && d[NSIG] == 0.5 && d[3] == 100.0 && d[NSIG + 3] == 60.0);
    }

    /* failed run: the failed name, a 7th matrix with the reason, final name absent */
    const char *fpath = OUT "/sine_fail.mat";
    remove(fpath);
    remove(OUT "/sine_fail.failed.mat");
    CHECK_OK(lv_sink_mat_create(fpath, &s, &err), &err);
    CHECK_OK(run_sink(&s, 4, "CVODE error -3 at t = 0.3: repeated error test failures", &err),
             &err);
    lv_sink_destroy(&s);
    CHECK(!exists(fpath) && !exists(OUT "/sine_fail.mat.tmp"));
    const int nf = read_mat4_headers(OUT "/sine_fail.failed.mat", h, 8);
    CHECK(nf == 7);
    if (nf == 7) {
        CHECK(strcmp(h[6].name, "lvsim_failure") == 0 && h[6].type == 51);
        CHECK(h[5].ncols == 4);
        CHECK(h[6].mrows == 1 &&
              h[6].ncols == (int32_t)strlen("CVODE error -3 at t = 0.3: repeated error test failures"));
    }

    /* a failure before the first row still gives a readable file */
    const char *epath = OUT "/empty.mat";
    remove(OUT "/empty.failed.mat");
    CHECK_OK(lv_sink_mat_create(epath, &s, &err), &err);
    CHECK_OK(run_sink(&s, 0, "", &err), &err);
    lv_sink_destroy(&s);
    const int ne = read_mat4_headers(OUT "/empty.failed.mat", h, 8);
    CHECK(ne == 7);
    if (ne == 7)
        CHECK(h[5].mrows == NSIG && h[5].ncols == 0);
}

/* Peak resident memory of this process, kB (VmHWM of /proc/self/status), or -1. */
static long peak_rss_kb(void)
{
    FILE *fp = fopen("/proc/self/status", "r");
    char line[256];
    long kb = -1;
    while (fp != NULL && fgets(line, sizeof line, fp) != NULL)
        if (strncmp(line, "VmHWM:", 6) == 0)
            kb = strtol(line + 6, NULL, 10);
    if (fp != NULL)
        fclose(fp);
    return kb;
}

/* The MAT sink streams: 10^6 rows (40 MB of data_2) raise the peak memory by less than
 * 4 MB (buffering every row, as the sink once did, takes 40 to 80 MB), and the file holds
 * every row with t0, tf and N patched in at close. */
static void test_mat_streams(void)
{
    lv_err err = {0};
    lv_sink s = {0};
    const char *path = OUT "/stream.mat";
    enum { N = 1000000 };
    CHECK_OK(lv_sink_mat_create(path, &s, &err), &err);
    lv_result_info info = sample_info();
    CHECK_OK(s.vt->open(s.self, &info, &err), &err);
    const long before = peak_rss_kb();
    double v[NSIG];
    lv_status st = LV_OK;
    for (int i = 0; i < N && st == LV_OK; i++) {
        sample_row(0, v);
        v[0] = 0.001 * i;
        v[1] = i;
        st = s.vt->row(s.self, v, &err);
    }
    CHECK_OK(st, &err);
    CHECK_OK(s.vt->close(s.self, NULL, &err), &err);
    const long after = peak_rss_kb();
    lv_sink_destroy(&s);
    CHECK(before > 0 && after > 0 && after - before < 4096);
    if (!(after - before < 4096))
        fprintf(stderr, "test_mat_streams: peak memory grew by %ld kB\n", after - before);
    mat4_hdr h[8];
    CHECK(read_mat4_headers(path, h, 8) == 6);
    CHECK(h[5].mrows == NSIG && h[5].ncols == N);
    FILE *fp = fopen(path, "rb");
    double d1[2 * (NPAR + 1)], last[NSIG];
    CHECK(fp != NULL && fseek(fp, h[4].data_pos, SEEK_SET) == 0 &&
          fread(d1, sizeof d1, 1, fp) == 1 &&
          fseek(fp, h[5].data_pos + (long)(N - 1) * NSIG * 8, SEEK_SET) == 0 &&
          fread(last, sizeof last, 1, fp) == 1);
    if (fp != NULL)
        fclose(fp);
    CHECK(d1[0] == 0.0 && d1[NPAR + 1] == 0.001 * (N - 1)); /* t0, tf */
    CHECK(last[0] == 0.001 * (N - 1) && last[1] == N - 1);
    remove(path);
}

static void test_errors(void)
{
    lv_err err = {0};
    lv_sink s = {0};
    lv_result_info info = sample_info();

    /* unwritable location: LV_ERR_IO at open(), naming the file */
    CHECK_OK(lv_sink_mat_create("no_such_dir_lvsim/x.mat", &s, &err), &err);
    CHECK_FAILS(s.vt->open(s.self, &info, &err), &err, LV_ERR_IO, "no_such_dir_lvsim/x.mat");
    CHECK(strstr(err.msg, "No such file or directory") != NULL);
    CHECK_FAILS(s.vt->close(s.self, NULL, &err), &err, LV_ERR_INPUT, "before open");
    lv_sink_destroy(&s);
    CHECK_OK(lv_sink_csv_create("no_such_dir_lvsim/x.csv", &s, &err), &err);
    CHECK_FAILS(s.vt->open(s.self, &info, &err), &err, LV_ERR_IO, "no_such_dir_lvsim/x.csv");
    lv_sink_destroy(&s);

    /* a directory without write permission (root writes anyway: skip) */
    if (geteuid() != 0) {
        const char *ro = OUT "/readonly";
        mkdir(ro, 0700);
        chmod(ro, 0500);
        CHECK_OK(lv_sink_mat_create(OUT "/readonly/r.mat", &s, &err), &err);
        CHECK_FAILS(s.vt->open(s.self, &info, &err), &err, LV_ERR_IO, "readonly/r.mat.tmp");
        CHECK(strstr(err.msg, "Permission denied") != NULL);
        lv_sink_destroy(&s);
        chmod(ro, 0700);
    }

    CHECK_FAILS(lv_sink_mat_create("", &s, &err), &err, LV_ERR_INPUT, "empty path");
    CHECK(s.vt == NULL);
    CHECK_FAILS(lv_sink_csv_create(NULL, &s, &err), &err, LV_ERR_INPUT, "empty path");

    /* rows out of order, rows before open, bad descriptions */
    CHECK_OK(lv_sink_csv_create(OUT "/bad.csv", &s, &err), &err);
    double v[NSIG] = {1.0, 0, 0, 0, 0};
    CHECK_FAILS(s.vt->row(s.self, v, &err), &err, LV_ERR_INPUT, "before open");
    CHECK_OK(s.vt->open(s.self, &info, &err), &err);
    CHECK_FAILS(s.vt->open(s.self, &info, &err), &err, LV_ERR_INPUT, "twice");
    CHECK_OK(s.vt->row(s.self, v, &err), &err);
    v[0] = 0.5;
    CHECK_FAILS(s.vt->row(s.self, v, &err), &err, LV_ERR_INPUT, "row 1: time 0.5");
    v[0] = NAN;
    CHECK_FAILS(s.vt->row(s.self, v, &err), &err, LV_ERR_INPUT, "time is nan");
    CHECK_OK(s.vt->close(s.self, "stopped by the test", &err), &err);
    lv_sink_destroy(&s);
    CHECK(exists(OUT "/bad.failed.csv"));

    lv_var dup[NSIG];
    memcpy(dup, sig, sizeof dup);
    dup[3].name = "h";
    lv_result_info bad = info;
    bad.signals = dup;
    CHECK_OK(lv_sink_mat_create(OUT "/dup.mat", &s, &err), &err);
    CHECK_FAILS(s.vt->open(s.self, &bad, &err), &err, LV_ERR_INPUT, "'h' appears twice");
    dup[3].name = "m";
    dup[0].name = "t";
    CHECK_FAILS(s.vt->open(s.self, &bad, &err), &err, LV_ERR_INPUT, "expected 'time'");
    bad.signals = sig;
    lv_var pdup[NPAR];
    memcpy(pdup, par, sizeof pdup);
    pdup[0].name = "m"; /* a parameter named like a signal */
    bad.params = pdup;
    CHECK_FAILS(s.vt->open(s.self, &bad, &err), &err, LV_ERR_INPUT, "'m' appears twice");
    lv_sink_destroy(&s); /* never opened: nothing on disk */
    CHECK(!exists(OUT "/dup.mat.tmp"));

    lv_result *r = NULL;
    CHECK_OK(lv_sink_memory_create(&r, &s, &err), &err);
    bad.params = par;
    bad.n_signals = 0;
    CHECK_FAILS(s.vt->open(s.self, &bad, &err), &err, LV_ERR_INPUT, "at least");
    lv_sink_destroy(&s);
    lv_result_free(r);
}

/* A full disk, simulated with a file-size limit (writes beyond it fail with
 * EFBIG): libmatio does not report it, the size check after closing does. */
static void test_disk_full(void)
{
    lv_err err = {0};
    lv_sink s = {0};
    struct rlimit old;
    if (getrlimit(RLIMIT_FSIZE, &old) != 0)
        return;
    void (*old_handler)(int) = signal(SIGXFSZ, SIG_IGN);
    struct rlimit small = old;
    small.rlim_cur = 2000; /* bytes: the header and a few rows */

    remove(OUT "/full.mat");
    CHECK_OK(lv_sink_mat_create(OUT "/full.mat", &s, &err), &err);
    lv_result_info info = sample_info();
    CHECK_OK(s.vt->open(s.self, &info, &err), &err);
    double v[NSIG];
    for (int i = 0; i < 200; i++) {
        sample_row(0, v);
        v[0] = i;
        CHECK_OK(s.vt->row(s.self, v, &err), &err);
    }
    setrlimit(RLIMIT_FSIZE, &small);
    CHECK_FAILS(s.vt->close(s.self, NULL, &err), &err, LV_ERR_IO, OUT "/full.mat.tmp");
    setrlimit(RLIMIT_FSIZE, &old);
    lv_sink_destroy(&s);
    CHECK(!exists(OUT "/full.mat") && !exists(OUT "/full.mat.tmp"));

    remove(OUT "/full.csv");
    CHECK_OK(lv_sink_csv_create(OUT "/full.csv", &s, &err), &err);
    CHECK_OK(s.vt->open(s.self, &info, &err), &err);
    setrlimit(RLIMIT_FSIZE, &small);
    lv_status st = LV_OK;
    for (int i = 0; i < 200 && st == LV_OK; i++) {
        sample_row(0, v);
        v[0] = i;
        st = s.vt->row(s.self, v, &err);
    }
    if (st == LV_OK)
        st = s.vt->close(s.self, NULL, &err);
    setrlimit(RLIMIT_FSIZE, &old);
    CHECK(st == LV_ERR_IO && strstr(err.msg, OUT "/full.csv.tmp") != NULL &&
          strstr(err.msg, "too large") != NULL);
    lv_sink_destroy(&s);
    CHECK(!exists(OUT "/full.csv"));
    remove(OUT "/full.csv.tmp");
    signal(SIGXFSZ, old_handler);
}

/* The contract of every registered result format (io/result_formats.c): a name of at most 7
 * lowercase letters or digits and an extension ".xyz", both unique; flag 1u << position (the
 * public LV_RESULT_* constants agree); lv_result_format_info says the same; its sink, made
 * through the descriptor, writes "<stem><ext>" for a complete run and "<stem>.failed<ext>"
 * for a failed one - the names summary.json gives (post/summary.c) and `lvsim simulate`
 * checks before it writes. */
static void test_registry(void)
{
    const size_t n = lv_result_format_count();
    CHECK(n >= 2 && n < 32 && lv_result_format_mask() == (1u << n) - 1u);
    CHECK(strcmp(lv_result_formats[0]->name, "mat") == 0 && LV_RESULT_MAT == 1u << 0);
    CHECK(strcmp(lv_result_formats[1]->name, "csv") == 0 && LV_RESULT_CSV == 1u << 1);
    CHECK(lv_result_format_info(n, NULL, NULL) == NULL);
    for (size_t i = 0; i < n; i++) {
        const lv_result_format *f = lv_result_formats[i];
        const char *ext = NULL, *desc = NULL;
        CHECK(lv_result_format_info(i, &ext, &desc) == f->name && ext == f->ext &&
              desc == f->description);
        const size_t len = strlen(f->name);
        CHECK(len >= 1 && len <= 7 &&
              strspn(f->name, "abcdefghijklmnopqrstuvwxyz0123456789") == len);
        CHECK(f->ext[0] == '.' && strlen(f->ext) >= 2 && strchr(f->ext, '/') == NULL);
        CHECK(f->description != NULL && f->description[0] != '\0' && f->create != NULL);
        for (size_t j = 0; j < i; j++)
            CHECK(strcmp(f->name, lv_result_formats[j]->name) != 0 &&
                  strcmp(f->ext, lv_result_formats[j]->ext) != 0);
        for (int failed = 0; failed <= 1; failed++) {
            char path[256], want[256];
            snprintf(path, sizeof path, OUT "/registry_%d%s", failed, f->ext);
            snprintf(want, sizeof want, OUT "/registry_%d%s%s", failed, failed ? ".failed" : "",
                     f->ext);
            remove(want);
            lv_sink s = {0};
            lv_err err;
            CHECK_OK(f->create(path, &s, &err), &err);
            if (s.vt == NULL)
                continue;
            CHECK_OK(run_sink(&s, 11, failed ? "stopped" : NULL, &err), &err);
            lv_sink_destroy(&s);
            if (!exists(want))
                fprintf(stderr, "format '%s': no file %s\n", f->name, want);
            CHECK(exists(want));
        }
    }
}

int main(void)
{
    if (mkdir(OUT, 0755) != 0 && errno != EEXIST) {
        perror(OUT);
        return 1;
    }
    test_failed_path();
    test_memory();
    test_csv();
    test_mat();
    test_mat_streams();
    test_errors();
    test_disk_full();
    test_registry();
    return check_report("test_io");
}
