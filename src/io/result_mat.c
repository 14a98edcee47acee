/* result_mat.c - MAT v4 result sink in the Dymola/OpenModelica "dsres" layout
 * (Aclass "Atrajectory" 1.1 binTrans), streamed to disk: constant memory for any number of
 * rows.
 *
 * Follows OpenModelica's writer (SimulationRuntime/c/simulation/results/
 * simulation_result_mat4.cpp) and reader (util/read_matlab4.c): matrices in
 * the order Aclass, name, description, dataInfo, data_1, data_2; char matrices
 * of MAT4 type 51, dataInfo int32 (type 20), data double (type 0). The dataInfo
 * values follow a Dymola file (time 0 1 0 -1, signals 2 k 0 -1, parameters
 * 1 k 0 0). Layout and sources: docs/result-files.md.
 *
 * Why the file can be streamed: binTrans stores data_2 as n_signals x N, column-major, so
 * each output row is one contiguous column, appended as it comes (Dymola writes its dsres
 * files this way). Only three numbers are unknown until the end: t0 and tf in data_1 and
 * N in data_2's header. open() writes the first five matrices and data_2's header with
 * placeholders, row() appends, close() patches the three numbers in place and appends
 * lvsim_failure for a failed run. MAT v4 is a plain sequence of (20-byte header, name,
 * data), written here directly: libmatio's MAT4 writer needs a matrix whole in memory.
 *
 * Its SHA-256 (the results folder's manifest, docs/result-files.md): the stream of io/atomic.c
 * hashes bytes as they are written, in file order, but the patch at close rewrites t0, tf and
 * N in the first few kB after every row has been hashed, and SHA-256 has no way to replace
 * bytes already hashed (each 64-byte block's chaining value depends on all bytes before it).
 * So the stream does not hash as it writes (lv_atomic_hash_at_commit: that digest would be
 * thrown away), and lv_atomic_commit (via
 * lv_sink_paths_commit) hashes the finished file once, before closing it, with pread() from
 * the still-open descriptor: the rows just written, from the page cache, in the closing thread
 * (a branch's or a campaign's phases close in parallel). That is one hashing pass over the
 * file, as before, moved from the manifest's commit into close(); keeping the header in
 * memory would spare reading back only those few kB. No layout with the three numbers at the
 * end exists in dsres (OpenModelica's reader wants N in data_2's header), and hashing the
 * rows before t0, tf and N are known is impossible for the same chaining reason.
 */
#define _POSIX_C_SOURCE 200809L /* fileno, fstat */

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/status.h"
#include "io/sink.h"

/* MAT v4 precision digit P of the type code MOPT (1000 M + 100 O + 10 P + T). */
enum { MAT4_DOUBLE = 0, MAT4_INT32 = 2, MAT4_UINT8 = 5 };

typedef struct mat_sink {
    lv_sink_paths paths;  /* paths.file.fp: the stream on the .tmp file, open()..close() */
    size_t n_signals;
    size_t n_params;
    size_t rows;
    double t0, t_last;    /* s: the first and the latest row's time */
    long pos_t0;          /* file offsets: data_1(1, 1), data_1(1, 2) = t0, tf; */
    long pos_tf;
    long pos_ncols;       /*   data_2's ncols (N) in its header */
    int broken;           /* a write failed: the file is incomplete */
    int state;            /* 0 created, 1 open, 2 closed */
    char *buf;            /* stdio buffer of the stream */
} mat_sink;

static lv_status io_error(const mat_sink *s, const char *what, int e, lv_err *err)
{
    char why[128];
    return lv_fail(err, LV_ERR_IO, "%s: %s: %s", s->paths.file.tmp, what,
                   lv_strerror(e != 0 ? e : EIO, why, sizeof why));
}

/* MOPT type code of precision p (T = 1 for text): M = 0 little-endian, 1 big-endian IEEE. */
static int32_t mat4_type(int p, int text)
{
    const uint16_t one = 1;
    unsigned char first;
    memcpy(&first, &one, 1);
    return (first == 1 ? 0 : 1000) + 10 * p + (text ? 1 : 0);
}

/* One matrix header (type, mrows, ncols, imagf, namlen) and the name with its NUL. */
static int put_header(FILE *fp, int32_t type, size_t rows, size_t cols, const char *name)
{
    const int32_t h[5] = {type, (int32_t)rows, (int32_t)cols, 0, (int32_t)(strlen(name) + 1)};
    return fwrite(h, sizeof h, 1, fp) == 1 && fwrite(name, strlen(name) + 1, 1, fp) == 1 ? 0
                                                                                          : -1;
}

static int put_matrix(FILE *fp, int32_t type, size_t rows, size_t cols, const char *name,
                      const void *data, size_t elem)
{
    if (put_header(fp, type, rows, cols, name) != 0)
        return -1;
    return rows * cols == 0 || fwrite(data, elem, rows * cols, fp) == rows * cols ? 0 : -1;
}

/* Column-major char matrix of `width` rows, one string per column ("binTrans"),
 * padded with NUL as OpenModelica does (numpy/scipy, MATLAB's deblank and the
 * OpenModelica reader all drop trailing NULs). */
static char *char_columns(const char *const *text, size_t n, size_t width)
{
    char *m = calloc(n * width > 0 ? n * width : 1, 1);
    if (m == NULL)
        return NULL;
    for (size_t j = 0; j < n; j++)
        memcpy(m + j * width, text[j], strlen(text[j]));
    return m;
}

/* Writes everything before data_2's values: Aclass, name, description, dataInfo, data_1
 * (t0 and tf NaN until close) and data_2's header (N = 0 until close). */
static lv_status write_head(mat_sink *s, const lv_result_info *in, lv_err *err)
{
    FILE *fp = s->paths.file.fp;
    const char *path = s->paths.file.path;
    const size_t ns = in->n_signals, np = in->n_params, nv = ns + np;
    if (nv > INT32_MAX - 2)
        return lv_fail(err, LV_ERR_INPUT, "%s: %zu variables are too many for MAT v4", path, nv);
    lv_status st = LV_OK;
    const char **names = calloc(nv, sizeof *names);
    char **descs = calloc(nv, sizeof *descs);
    int32_t *info = calloc(4 * nv, sizeof *info);
    double *data_1 = calloc(2 * (np + 1), sizeof *data_1);
    char *name_m = NULL, *desc_m = NULL;
    if (names == NULL || descs == NULL || info == NULL || data_1 == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", path);
        goto fail;
    }
    size_t name_w = 1, desc_w = 1;
    for (size_t i = 0; i < nv; i++) {
        const lv_var *v = i < ns ? &in->signals[i] : &in->params[i - ns];
        const char *d = v->description, *u = v->unit;
        if (i == 0) { /* time: OpenModelica's text when the model gives none */
            if (d == NULL || d[0] == '\0')
                d = "Simulation time";
            if (u == NULL || u[0] == '\0')
                u = "s";
        }
        names[i] = v->name;
        descs[i] = lv_sink_describe(d, u);
        if (descs[i] == NULL) {
            st = lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", path);
            goto fail;
        }
        if (strlen(names[i]) + 1 > name_w)
            name_w = strlen(names[i]) + 1;
        if (strlen(descs[i]) + 1 > desc_w)
            desc_w = strlen(descs[i]) + 1;
    }
    if (name_w > INT32_MAX || desc_w > INT32_MAX / 2) {
        st = lv_fail(err, LV_ERR_INPUT, "%s: a name or description is too long for MAT v4",
                     path);
        goto fail;
    }
    name_m = char_columns(names, nv, name_w);
    desc_m = char_columns((const char *const *)descs, nv, desc_w);
    if (name_m == NULL || desc_m == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", path);
        goto fail;
    }
    /* dataInfo(:, i) = [matrix; column (1-based, < 0: negated); interpolation
     * (0: linear); extrapolation (-1: undefined outside [t0, tf], 0: hold)].
     * Time is the abscissa of every data matrix: [0 1 0 -1]. */
    for (size_t i = 0; i < nv; i++) {
        int32_t *di = info + 4 * i;
        if (i == 0) {
            di[0] = 0; di[1] = 1; di[2] = 0; di[3] = -1;
        } else if (i < ns) {
            di[0] = 2; di[1] = (int32_t)(i + 1); di[2] = 0; di[3] = -1;
        } else {
            di[0] = 1; di[1] = (int32_t)(i - ns + 2); di[2] = 0; di[3] = 0;
        }
    }
    /* data_1 (binTrans: (1 + np) x 2, column-major): column 1 at t0, column 2 at tf; row 1
     * is time, then one row per parameter. t0, tf: NaN until close (and when no row came). */
    data_1[0] = data_1[np + 1] = NAN;
    for (size_t j = 0; j < np; j++)
        data_1[1 + j] = data_1[np + 2 + j] = in->param_values[j];

    /* Aclass: 4 x 11, column-major. */
    static const char *const aclass_rows[4] = {"Atrajectory", "1.1", "", "binTrans"};
    char aclass[4 * 11];
    memset(aclass, 0, sizeof aclass);
    for (size_t r = 0; r < 4; r++)
        for (size_t c = 0; aclass_rows[r][c] != '\0'; c++)
            aclass[c * 4 + r] = aclass_rows[r][c];

    const int32_t t_char = mat4_type(MAT4_UINT8, 1), t_int = mat4_type(MAT4_INT32, 0),
                  t_dbl = mat4_type(MAT4_DOUBLE, 0);
    errno = 0;
    int bad = put_matrix(fp, t_char, 4, 11, "Aclass", aclass, 1) != 0 ||
              put_matrix(fp, t_char, name_w, nv, "name", name_m, 1) != 0 ||
              put_matrix(fp, t_char, desc_w, nv, "description", desc_m, 1) != 0 ||
              put_matrix(fp, t_int, 4, nv, "dataInfo", info, sizeof(int32_t)) != 0 ||
              put_header(fp, t_dbl, np + 1, 2, "data_1") != 0;
    if (!bad) {
        s->pos_t0 = ftell(fp);
        s->pos_tf = s->pos_t0 + (long)((np + 1) * sizeof(double));
        bad = s->pos_t0 < 0 || fwrite(data_1, sizeof *data_1, 2 * (np + 1), fp) != 2 * (np + 1);
    }
    if (!bad) {
        s->pos_ncols = ftell(fp) + 2 * (long)sizeof(int32_t); /* type, mrows, ncols */
        bad = s->pos_ncols < 0 || put_header(fp, t_dbl, ns, 0, "data_2") != 0;
    }
    if (bad)
        st = io_error(s, "cannot write", errno, err);
fail:
    if (descs != NULL)
        for (size_t i = 0; i < nv; i++)
            free(descs[i]);
    free(descs);
    free(names);
    free(info);
    free(data_1);
    free(name_m);
    free(desc_m);
    return st;
}

static lv_status mat_open(void *self, const lv_result_info *info, lv_err *err)
{
    mat_sink *s = self;
    if (s->state != 0)
        return lv_fail(err, LV_ERR_INPUT, "%s: opened twice", s->paths.file.path);
    lv_status st = lv_sink_check_info(info, s->paths.file.path, err);
    if (st != LV_OK)
        return st;
    /* the .tmp file now: an unwritable directory fails before the run */
    st = lv_atomic_open(&s->paths.file, NULL, err);
    if (st != LV_OK)
        return st;
    lv_atomic_hash_at_commit(&s->paths.file); /* close() patches the head: see the top */
    enum { BUF = 1 << 16 };
    s->buf = malloc(BUF);
    if (s->buf != NULL)
        setvbuf(s->paths.file.fp, s->buf, _IOFBF, BUF);
    s->n_signals = info->n_signals;
    s->n_params = info->n_params;
    st = write_head(s, info, err);
    if (st != LV_OK) {
        lv_atomic_abort(&s->paths.file);
        return st;
    }
    s->state = 1;
    return LV_OK;
}

static lv_status mat_row(void *self, const double *values, lv_err *err)
{
    mat_sink *s = self;
    if (s->state != 1)
        return lv_fail(err, LV_ERR_INPUT, "%s: row() %s", s->paths.file.path,
                       s->state == 0 ? "before open()" : "after close()");
    lv_status st = lv_sink_check_row(s->paths.file.path, s->rows, values[0], s->t_last, err);
    if (st != LV_OK)
        return st;
    if (s->broken)
        return lv_fail(err, LV_ERR_IO, "%s: an earlier write failed", s->paths.file.tmp);
    if (s->rows >= INT32_MAX)
        return lv_fail(err, LV_ERR_INPUT, "%s: more than %d rows do not fit a MAT v4 matrix",
                       s->paths.file.path, INT32_MAX);
    errno = 0;
    if (fwrite(values, sizeof *values, s->n_signals, s->paths.file.fp) != s->n_signals) {
        s->broken = 1;
        return io_error(s, "cannot write", errno, err);
    }
    if (s->rows == 0)
        s->t0 = values[0];
    s->t_last = values[0];
    s->rows++;
    return LV_OK;
}

/* Appends lvsim_failure (failed runs) and patches t0, tf and N. */
static lv_status finish(mat_sink *s, const char *failure, lv_err *err)
{
    FILE *fp = s->paths.file.fp;
    const double t0 = s->rows > 0 ? s->t0 : NAN, tf = s->rows > 0 ? s->t_last : NAN;
    const int32_t n = (int32_t)s->rows;
    errno = 0;
    int bad = 0;
    if (failure != NULL) {
        /* After data_2: dsres readers (OpenModelica's reads exactly six matrices, DyMat and
         * dymload pick theirs by name) ignore it. One line. */
        const char *text = failure[0] != '\0' ? failure : "(no reason given)";
        const size_t len = strlen(text) < 4000 ? strlen(text) : 4000;
        char line[4001];
        for (size_t i = 0; i < len; i++)
            line[i] = text[i] == '\n' || text[i] == '\r' ? ' ' : text[i];
        bad = put_matrix(fp, mat4_type(MAT4_UINT8, 1), 1, len, "lvsim_failure", line, 1) != 0;
    }
    bad = bad || fseek(fp, s->pos_t0, SEEK_SET) != 0 || fwrite(&t0, sizeof t0, 1, fp) != 1 ||
          fseek(fp, s->pos_tf, SEEK_SET) != 0 || fwrite(&tf, sizeof tf, 1, fp) != 1 ||
          fseek(fp, s->pos_ncols, SEEK_SET) != 0 || fwrite(&n, sizeof n, 1, fp) != 1 ||
          fflush(fp) != 0 || ferror(fp);
    if (bad)
        return io_error(s, "cannot write", errno, err);
    return LV_OK;
}

static lv_status mat_close(void *self, const char *failure, lv_err *err)
{
    mat_sink *s = self;
    if (s->state != 1)
        return lv_fail(err, LV_ERR_INPUT, "%s: close() %s", s->paths.file.path,
                       s->state == 0 ? "before open()" : "twice");
    s->state = 2;
    lv_status st = s->broken ? lv_fail(err, LV_ERR_IO, "%s: incomplete: a write failed",
                                       s->paths.file.tmp)
                             : finish(s, failure, err);
    if (st == LV_OK)
        st = lv_sink_paths_commit(&s->paths, failure, err); /* closes, checks, renames */
    else
        lv_atomic_abort(&s->paths.file); /* incomplete; the rows are lost with it */
    free(s->buf);
    s->buf = NULL;
    return st;
}

static void mat_destroy(void *self)
{
    mat_sink *s = self;
    if (s == NULL)
        return;
    lv_sink_paths_free(&s->paths); /* closes a stream left open; its .tmp file stays */
    free(s->buf);
    free(s);
}

static const lv_sink_vtbl mat_vtbl = {"mat", mat_open, mat_row, mat_close, mat_destroy};

lv_status lv_sink_mat_create(const char *path, lv_sink *out, lv_err *err)
{
    if (out == NULL)
        return lv_fail(err, LV_ERR_INPUT, "mat result: NULL output argument");
    out->vt = NULL;
    out->self = NULL;
    mat_sink *s = calloc(1, sizeof *s);
    if (s == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", path != NULL ? path : "mat");
    lv_status st = lv_sink_paths_init(&s->paths, path, err);
    if (st != LV_OK) {
        free(s);
        return st;
    }
    out->vt = &mat_vtbl;
    out->self = s;
    return LV_OK;
}

/* docs/result-files.md */
const lv_result_format lv_result_format_mat = {
    "mat", ".mat", "MAT v4, Dymola/OpenModelica dsres layout: every signal and the parameters",
    lv_sink_mat_create};
