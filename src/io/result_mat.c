/* result_mat.c - MAT v4 result sink in the Dymola/OpenModelica "dsres" layout
 * (Aclass "Atrajectory" 1.1 binTrans), written with libmatio.
 *
 * Follows OpenModelica's writer (SimulationRuntime/c/simulation/results/
 * simulation_result_mat4.cpp) and reader (util/read_matlab4.c): matrices in
 * the order Aclass, name, description, dataInfo, data_1, data_2; char matrices
 * of MAT4 type 51, dataInfo int32 (type 20), data double (type 0). The dataInfo
 * values follow a Dymola file (time 0 1 0 -1, signals 2 k 0 -1, parameters
 * 1 k 0 0). Layout and sources: docs/result-files.md.
 */
#define _POSIX_C_SOURCE 200809L /* stat() */

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <matio.h>

#include "core/status.h"
#include "io/sink.h"

typedef struct mat_sink {
    lv_sink_paths paths;
    lv_result_info info; /* shallow copy; names borrowed until close() */
    double *param_values; /* own copy of info.param_values */
    lv_rowbuf rows;      /* row-major [rows][n_signals]: data_2 in binTrans order */
    int state;           /* 0 created, 1 open, 2 closed */
} mat_sink;

static lv_status io_error(const char *path, const char *what, int e, lv_err *err)
{
    char why[128];
    return lv_fail(err, LV_ERR_IO, "%s: %s: %s", path, what, lv_sink_strerror(e, why, sizeof why));
}

static lv_status mat_open(void *self, const lv_result_info *info, lv_err *err)
{
    mat_sink *s = self;
    if (s->state != 0)
        return lv_fail(err, LV_ERR_INPUT, "%s: opened twice", s->paths.file.path);
    lv_status st = lv_sink_check_info(info, s->paths.file.path, err);
    if (st != LV_OK)
        return st;
    /* Rows are buffered and the file is written at close(); create the
     * temporary file now so that an unwritable directory fails before the run. */
    st = lv_atomic_reserve(&s->paths.file, err);
    if (st != LV_OK)
        return st;
    if (info->n_params > 0) {
        s->param_values = malloc(info->n_params * sizeof *s->param_values);
        if (s->param_values == NULL)
            return lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", s->paths.file.path);
        memcpy(s->param_values, info->param_values, info->n_params * sizeof *s->param_values);
    }
    s->info = *info;
    s->info.param_values = s->param_values;
    s->rows.width = info->n_signals;
    s->state = 1;
    return LV_OK;
}

static lv_status mat_row(void *self, const double *values, lv_err *err)
{
    mat_sink *s = self;
    if (s->state != 1)
        return lv_fail(err, LV_ERR_INPUT, "%s: row() %s", s->paths.file.path,
                       s->state == 0 ? "before open()" : "after close()");
    const size_t n = s->rows.rows;
    const double t_prev = n > 0 ? s->rows.v[(n - 1) * s->rows.width] : 0.0;
    lv_status st = lv_sink_check_row(s->paths.file.path, n, values[0], t_prev, err);
    if (st != LV_OK)
        return st;
    st = lv_rowbuf_push(&s->rows, values, err);
    if (st != LV_OK)
        return lv_fail_prefix(err, st, "%s", s->paths.file.path);
    return LV_OK;
}

/* One matrix through libmatio; adds its size on file to *bytes. MAT4 stores
 * the dimensions as int32 and the name with its NUL. */
static lv_status put_matrix(mat_t *mat, const char *path, const char *name,
                            enum matio_classes cls, enum matio_types type, size_t rows,
                            size_t cols, void *data, size_t elem_size, size_t *bytes, lv_err *err)
{
    if (rows > INT32_MAX || cols > INT32_MAX || (cols > 0 && rows > INT32_MAX / cols))
        return lv_fail(err, LV_ERR_INPUT, "%s: matrix '%s' of %zu x %zu is too large for MAT v4",
                       path, name, rows, cols);
    double dummy = 0.0; /* an empty matrix still needs a data pointer */
    size_t dims[2] = {rows, cols};
    matvar_t *v = Mat_VarCreate(name, cls, type, 2, dims, data != NULL ? data : &dummy,
                                MAT_F_DONT_COPY_DATA);
    if (v == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "%s: matio cannot create matrix '%s'", path, name);
    errno = 0;
    const int rc = Mat_VarWrite(mat, v, MAT_COMPRESSION_NONE);
    const int e = errno;
    Mat_VarFree(v); /* MAT_F_DONT_COPY_DATA: frees the header, not `data` */
    if (rc != 0) {
        char why[128];
        return lv_fail(err, LV_ERR_IO, "%s: cannot write matrix '%s' (matio error %d): %s", path,
                       name, rc, e != 0 ? lv_sink_strerror(e, why, sizeof why) : "unknown");
    }
    *bytes += 5 * 4 + strlen(name) + 1 + rows * cols * elem_size;
    return LV_OK;
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

/* Builds the dsres matrices and writes them to the temporary file. */
static lv_status write_dsres(const mat_sink *s, const char *failure, lv_err *err)
{
    const lv_result_info *in = &s->info;
    const char *path = s->paths.file.tmp; /* libmatio writes the temporary file by name */
    const size_t ns = in->n_signals, np = in->n_params, nv = ns + np;
    const size_t nrows = s->rows.rows;
    if (nv > INT32_MAX - 2)
        return lv_fail(err, LV_ERR_INPUT, "%s: %zu variables are too many for MAT v4", path, nv);
    lv_status st = LV_OK;
    mat_t *mat = NULL;
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
    /* data_1 (binTrans: (1 + np) x 2, column-major): column 1 at t0, column 2
     * at tf; row 1 is time, then one row per parameter. No rows: NaN times. */
    data_1[0] = nrows > 0 ? s->rows.v[0] : NAN;
    data_1[np + 1] = nrows > 0 ? s->rows.v[(nrows - 1) * ns] : NAN;
    for (size_t j = 0; j < np; j++)
        data_1[1 + j] = data_1[np + 2 + j] = in->param_values[j];

    /* Aclass: 4 x 11, column-major. */
    static const char *const aclass_rows[4] = {"Atrajectory", "1.1", "", "binTrans"};
    char aclass[4 * 11];
    memset(aclass, 0, sizeof aclass);
    for (size_t r = 0; r < 4; r++)
        for (size_t c = 0; aclass_rows[r][c] != '\0'; c++)
            aclass[c * 4 + r] = aclass_rows[r][c];

    errno = 0;
    mat = Mat_CreateVer(path, NULL, MAT_FT_MAT4);
    if (mat == NULL) {
        st = io_error(path, "cannot create", errno, err);
        goto fail;
    }
    /* libmatio's MAT4 writer derives the type code from the data type, +1 for
     * MAT_C_CHAR: char/uint8 gives 51, int32 gives 20, double gives 0 -- the
     * types Dymola and OpenModelica write and OpenModelica's reader demands. */
    size_t bytes = 0;
    st = put_matrix(mat, path, "Aclass", MAT_C_CHAR, MAT_T_UINT8, 4, 11, aclass, 1, &bytes, err);
    if (st == LV_OK)
        st = put_matrix(mat, path, "name", MAT_C_CHAR, MAT_T_UINT8, name_w, nv, name_m, 1,
                        &bytes, err);
    if (st == LV_OK)
        st = put_matrix(mat, path, "description", MAT_C_CHAR, MAT_T_UINT8, desc_w, nv, desc_m,
                        1, &bytes, err);
    if (st == LV_OK)
        st = put_matrix(mat, path, "dataInfo", MAT_C_INT32, MAT_T_INT32, 4, nv, info,
                        sizeof(int32_t), &bytes, err);
    if (st == LV_OK)
        st = put_matrix(mat, path, "data_1", MAT_C_DOUBLE, MAT_T_DOUBLE, np + 1, 2, data_1,
                        sizeof(double), &bytes, err);
    if (st == LV_OK)
        st = put_matrix(mat, path, "data_2", MAT_C_DOUBLE, MAT_T_DOUBLE, ns, nrows, s->rows.v,
                        sizeof(double), &bytes, err);
    if (st == LV_OK && failure != NULL) {
        /* After data_2: dsres readers (OpenModelica's reads exactly six
         * matrices, DyMat and dymload pick theirs by name) ignore it. */
        const char *text = failure[0] != '\0' ? failure : "(no reason given)";
        st = put_matrix(mat, path, "lvsim_failure", MAT_C_CHAR, MAT_T_UINT8, 1, strlen(text),
                        (void *)text, 1, &bytes, err);
    }
    errno = 0;
    const int rc = Mat_Close(mat);
    const int e_close = errno;
    mat = NULL;
    if (st != LV_OK)
        goto fail;
    if (rc != 0) {
        st = io_error(path, "cannot close", e_close, err);
        goto fail;
    }
    /* libmatio does not check its fwrite() calls: compare the size on disk. */
    struct stat sb;
    if (stat(path, &sb) != 0) {
        st = io_error(path, "cannot stat", errno, err);
        goto fail;
    }
    if ((uintmax_t)sb.st_size != (uintmax_t)bytes) {
        st = lv_fail(err, LV_ERR_IO, "%s: short write: %jd of %zu bytes (disk full?)", path,
                     (intmax_t)sb.st_size, bytes);
        goto fail;
    }
fail: /* and success: mat is NULL then */
    if (mat != NULL)
        Mat_Close(mat);
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

static lv_status mat_close(void *self, const char *failure, lv_err *err)
{
    mat_sink *s = self;
    if (s->state != 1)
        return lv_fail(err, LV_ERR_INPUT, "%s: close() %s", s->paths.file.path,
                       s->state == 0 ? "before open()" : "twice");
    s->state = 2;
    lv_status st = write_dsres(s, failure, err);
    if (st == LV_OK)
        st = lv_sink_paths_commit(&s->paths, failure, err);
    else
        lv_atomic_abort(&s->paths.file); /* incomplete; the rows are lost with it */
    lv_rowbuf_free(&s->rows);
    free(s->param_values);
    s->param_values = NULL;
    memset(&s->info, 0, sizeof s->info);
    return st;
}

static void mat_destroy(void *self)
{
    mat_sink *s = self;
    if (s == NULL)
        return;
    lv_rowbuf_free(&s->rows);
    free(s->param_values);
    lv_sink_paths_free(&s->paths);
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
