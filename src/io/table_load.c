/* table_load.c - lookup tables from CSV files and MATLAB/Octave MAT files (libmatio).
 *
 * Conventions (docs/tables.md): CSV 1-D with a "name [unit]" header; CSV 2-D grid and MAT
 * matrices in the Modelica CombiTable2D / CombiTable1D layouts (Modelica Standard Library,
 * Modelica.Blocks.Tables); MAT N-D as an n1 x .. x nN array with vectors var_x1 .. var_xN.
 */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <matio.h>

#include "core/names.h"
#include "core/status.h"
#include "lvsim/lv_table.h"

/* ---- small helpers -------------------------------------------------------------------- */

typedef struct dvec {
    double *v;
    size_t n, cap;
} dvec;

static int dvec_push(dvec *a, double x)
{
    if (a->n == a->cap) {
        const size_t cap = a->cap ? 2 * a->cap : 64;
        double *v = realloc(a->v, cap * sizeof *v);
        if (v == NULL)
            return -1;
        a->v = v;
        a->cap = cap;
    }
    a->v[a->n++] = x;
    return 0;
}

static const lv_table_opts *opts_or_default(const lv_table_opts *opts)
{
    static const lv_table_opts deflt = { LV_INTERP_LINEAR, LV_EXTRAP_ERROR }; /* const */
    return opts != NULL ? opts : &deflt;
}

/* "dir/thrust.csv" -> "thrust" into buf. */
static void file_stem(const char *path, char *buf, size_t cap)
{
    const char *base = strrchr(path, '/');
    base = base != NULL ? base + 1 : path;
    size_t len = strlen(base);
    const char *dot = strrchr(base, '.');
    if (dot != NULL && dot != base)
        len = (size_t)(dot - base);
    if (len >= cap)
        len = cap - 1;
    memcpy(buf, base, len);
    buf[len] = '\0';
}

/* ---- CSV ------------------------------------------------------------------------------ */

#define CSV_MAX_FIELDS 1024
#define CSV_TEXT_MAX 128

typedef struct csv_field {
    const char *s; /* trimmed text, not terminated */
    size_t len;
    size_t col; /* 1-based column of the text (or of the field's place when empty) */
} csv_field;

typedef struct csv_ctx {
    const char *path;
    size_t line;
} csv_ctx;

static int is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r';
}

/* Splits [s, end) at commas into f[]; returns the field count, or CSV_MAX_FIELDS + 1. */
static size_t split_fields(const char *line, const char *end, csv_field *f)
{
    size_t nf = 0;
    const char *p = line;
    for (;;) {
        const char *q = p;
        while (q < end && *q != ',')
            q++;
        const char *a = p, *b = q;
        while (a < b && is_blank(*a))
            a++;
        while (b > a && is_blank(b[-1]))
            b--;
        if (nf == CSV_MAX_FIELDS)
            return CSV_MAX_FIELDS + 1;
        f[nf].s = a;
        f[nf].len = (size_t)(b - a);
        f[nf].col = (size_t)(a - line) + 1;
        nf++;
        if (q == end)
            return nf;
        p = q + 1;
    }
}

/* A finite number filling the whole field. */
static int parse_number(const csv_field *f, double *v)
{
    char buf[64];
    if (f->len == 0 || f->len >= sizeof buf)
        return -1;
    memcpy(buf, f->s, f->len);
    buf[f->len] = '\0';
    char *endp = NULL;
    errno = 0;
    const double d = strtod(buf, &endp);
    if (endp != buf + f->len || !isfinite(d) || errno == ERANGE)
        return -1;
    *v = d;
    return 0;
}

static lv_status csv_fail_field(const csv_ctx *c, const csv_field *f, const char *what,
                                lv_err *err)
{
    const int len = f->len > 40 ? 40 : (int)f->len;
    return lv_fail(err, LV_ERR_INPUT, "%s:%zu:%zu: %s, found '%.*s'", c->path, c->line, f->col,
                   what, len, f->s);
}

/* "thrust [N]" -> name "thrust", unit "N". */
static lv_status parse_label(const csv_ctx *c, const csv_field *f, char *name, char *unit,
                             lv_err *err)
{
    const char *s = f->s, *e = f->s + f->len;
    const char *lb = memchr(s, '[', f->len);
    const char *ne = lb != NULL ? lb : e;
    while (ne > s && is_blank(ne[-1]))
        ne--;
    unit[0] = '\0';
    if (lb != NULL) {
        const char *rb = memchr(lb, ']', (size_t)(e - lb));
        if (rb == NULL || rb + 1 != e)
            return lv_fail(err, LV_ERR_INPUT, "%s:%zu:%zu: unit of '%.*s' must be one "
                           "'[unit]' at the end", c->path, c->line, f->col + (size_t)(lb - s),
                           (int)(f->len > 40 ? 40 : f->len), s);
        const size_t ul = (size_t)(rb - lb - 1);
        if (ul >= CSV_TEXT_MAX)
            return lv_fail(err, LV_ERR_INPUT, "%s:%zu:%zu: unit too long", c->path, c->line,
                           f->col);
        memcpy(unit, lb + 1, ul);
        unit[ul] = '\0';
    }
    const size_t nl = (size_t)(ne - s);
    if (nl == 0 || nl >= CSV_TEXT_MAX)
        return lv_fail(err, LV_ERR_INPUT, "%s:%zu:%zu: %s column name in the header", c->path,
                       c->line, f->col, nl == 0 ? "empty" : "too long a");
    memcpy(name, s, nl);
    name[nl] = '\0';
    return LV_OK;
}

static lv_status read_file(const char *path, char **text, size_t *len, lv_err *err)
{
    FILE *fp = fopen(path, "rb");
    char *buf = NULL;
    size_t n = 0, cap = 0;
    if (fp == NULL)
        return lv_fail(err, LV_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    for (;;) {
        if (cap - n < 4096) {
            cap = cap ? 2 * cap : 65536;
            char *b = realloc(buf, cap + 1);
            if (b == NULL) {
                free(buf);
                fclose(fp);
                return lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", path);
            }
            buf = b;
        }
        const size_t got = fread(buf + n, 1, cap - n, fp);
        n += got;
        if (got == 0)
            break;
    }
    const int bad = ferror(fp);
    fclose(fp);
    if (bad) {
        free(buf);
        return lv_fail(err, LV_ERR_IO, "%s: read error", path);
    }
    buf[n] = '\0';
    *text = buf;
    *len = n;
    return LV_OK;
}

/* Next non-blank, non-comment line: fields in f, count in *nf (0 at end of file). */
static lv_status next_line(csv_ctx *c, const char **pos, const char *end, csv_field *f,
                           size_t *nf, lv_err *err)
{
    while (*pos < end) {
        const char *line = *pos;
        const char *eol = memchr(line, '\n', (size_t)(end - line));
        if (eol == NULL)
            eol = end;
        *pos = eol < end ? eol + 1 : end;
        c->line++;
        const char *hash = memchr(line, '#', (size_t)(eol - line));
        const char *stop = hash != NULL ? hash : eol;
        const char *q = line;
        while (q < stop && is_blank(*q))
            q++;
        if (q == stop)
            continue;
        *nf = split_fields(line, stop, f);
        if (*nf > CSV_MAX_FIELDS)
            return lv_fail(err, LV_ERR_INPUT, "%s:%zu: more than %d columns", c->path, c->line,
                           CSV_MAX_FIELDS);
        return LV_OK;
    }
    *nf = 0;
    return LV_OK;
}

static lv_status push_breakpoint(const csv_ctx *c, const csv_field *f, dvec *x, double v,
                                 lv_err *err)
{
    if (x->n > 0 && !(v > x->v[x->n - 1]))
        return lv_fail(err, LV_ERR_INPUT,
                       "%s:%zu:%zu: breakpoint %.17g is not greater than the previous one "
                       "(%.17g); breakpoints must be strictly increasing",
                       c->path, c->line, f->col, v, x->v[x->n - 1]);
    return dvec_push(x, v) == 0 ? LV_OK : lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", c->path);
}

/* The data rows of both CSV layouts: each row a breakpoint of axis 0, then ncol - 1 values
 * (appended to y), until the end of the file. `ref` names what fixed ncol in messages. */
static lv_status read_rows(csv_ctx *c, const char **pos, const char *end, csv_field *f,
                           size_t ncol, const char *ref, dvec *x0, dvec *y, lv_err *err)
{
    for (;;) {
        size_t nf = 0;
        lv_status st = next_line(c, pos, end, f, &nf, err);
        if (st != LV_OK || nf == 0)
            return st;
        if (nf != ncol) {
            const csv_field *at = nf > ncol ? &f[ncol] : &f[nf - 1];
            return lv_fail(err, LV_ERR_INPUT, "%s:%zu:%zu: %zu columns, %s has %zu", c->path,
                           c->line, nf > ncol ? at->col : at->col + at->len, nf, ref, ncol);
        }
        for (size_t j = 0; j < ncol; j++) {
            double v;
            if (parse_number(&f[j], &v) != 0)
                return csv_fail_field(c, &f[j], "expected a finite number", err);
            if (j == 0)
                st = push_breakpoint(c, &f[j], x0, v, err);
            else if (dvec_push(y, v) != 0)
                st = lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", c->path);
            if (st != LV_OK)
                return st;
        }
    }
}

lv_status lv_table_load_csv(const char *path, const lv_table_opts *opts, lv_table **out,
                            lv_err *err)
{
    char *text = NULL;
    size_t len = 0, nf = 0;
    csv_field *f = NULL;
    dvec x0 = { 0 }, x1 = { 0 }, y = { 0 };
    char (*names)[CSV_TEXT_MAX] = NULL, (*units)[CSV_TEXT_MAX] = NULL;
    const char **np = NULL, **up = NULL;
    csv_ctx c = { path, 0 };
    char stem[CSV_TEXT_MAX];
    lv_status st;

    if (out == NULL || path == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_table_load_csv: NULL argument");
    *out = NULL;
    opts = opts_or_default(opts);
    file_stem(path, stem, sizeof stem);
    st = read_file(path, &text, &len, err);
    if (st != LV_OK)
        return st;
    st = LV_ERR_NOMEM;
    f = malloc(CSV_MAX_FIELDS * sizeof *f);
    if (f == NULL) {
        lv_fail(err, st, "%s: out of memory", path);
        goto fail;
    }
    const char *pos = text, *end = text + len;
    st = next_line(&c, &pos, end, f, &nf, err);
    if (st != LV_OK)
        goto fail;
    if (nf == 0) {
        st = lv_fail(err, LV_ERR_INPUT, "%s: no header line (only blank or comment lines)", path);
        goto fail;
    }
    if (nf < 2) {
        st = lv_fail(err, LV_ERR_INPUT, "%s:%zu: header has one column; need a breakpoint "
                     "column and at least one output", path, c.line);
        goto fail;
    }

    /* Grid format when every header field after the first is a number. */
    int grid = 1;
    for (size_t j = 1; j < nf && grid; j++) {
        double v;
        grid = parse_number(&f[j], &v) == 0;
    }
    const size_t ncol = nf;
    names = calloc(ncol, sizeof *names);
    units = calloc(ncol, sizeof *units);
    np = calloc(ncol, sizeof *np);
    up = calloc(ncol, sizeof *up);
    if (names == NULL || units == NULL || np == NULL || up == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", path);
        goto fail;
    }
    lv_table_spec spec = { 0 };
    spec.interp = opts->interp;
    spec.extrap = opts->extrap;
    spec.name = stem;

    if (!grid) {
        for (size_t j = 0; j < ncol; j++) {
            st = parse_label(&c, &f[j], names[j], units[j], err);
            if (st != LV_OK)
                goto fail;
            np[j] = names[j];
            up[j] = units[j];
        }
        st = read_rows(&c, &pos, end, f, ncol, "the header", &x0, &y, err);
        if (st != LV_OK)
            goto fail;
        spec.n_dims = 1;
        spec.n[0] = x0.n;
        spec.x[0] = x0.v;
        spec.axis_name[0] = names[0];
        spec.axis_unit[0] = units[0];
        spec.n_out = ncol - 1;
        spec.out_name = np + 1;
        spec.out_unit = up + 1;
    } else {
        double corner;
        if (ncol < 3) {
            st = lv_fail(err, LV_ERR_INPUT, "%s:%zu: first line is all numbers, so a 2-D grid, "
                         "which needs at least 2 column breakpoints; a 1-D table needs a header "
                         "'name [unit], name [unit], ..'", path, c.line);
            goto fail;
        }
        /* Label "mach [1] \ alpha [rad]" (optional): axis names and units. A number there
         * is ignored, as table[1,1] of Modelica's CombiTable2D. */
        if (f[0].len > 0 && parse_number(&f[0], &corner) != 0) {
            const char *bs = memchr(f[0].s, '\\', f[0].len);
            if (bs == NULL) {
                st = lv_fail(err, LV_ERR_INPUT, "%s:%zu:%zu: grid label must read "
                             "'row axis [unit] \\ column axis [unit]' (or be empty)",
                             path, c.line, f[0].col);
                goto fail;
            }
            csv_field a = { f[0].s, (size_t)(bs - f[0].s), f[0].col };
            csv_field b = { bs + 1, (size_t)(f[0].s + f[0].len - bs - 1),
                            f[0].col + a.len + 1 };
            while (a.len > 0 && is_blank(a.s[a.len - 1]))
                a.len--;
            while (b.len > 0 && is_blank(*b.s)) {
                b.s++;
                b.len--;
                b.col++;
            }
            st = parse_label(&c, &a, names[0], units[0], err);
            if (st == LV_OK)
                st = parse_label(&c, &b, names[1], units[1], err);
            if (st != LV_OK)
                goto fail;
        }
        for (size_t j = 1; j < ncol; j++) {
            double v = 0.0;
            (void)parse_number(&f[j], &v); /* checked above */
            st = push_breakpoint(&c, &f[j], &x1, v, err);
            if (st != LV_OK)
                goto fail;
        }
        st = read_rows(&c, &pos, end, f, ncol, "the first row", &x0, &y, err);
        if (st != LV_OK)
            goto fail;
        spec.n_dims = 2;
        spec.n[0] = x0.n;
        spec.x[0] = x0.v;
        spec.n[1] = x1.n;
        spec.x[1] = x1.v;
        for (size_t d = 0; d < 2; d++) {
            spec.axis_name[d] = names[d];
            spec.axis_unit[d] = units[d];
        }
        spec.n_out = 1;
        np[0] = stem;
        spec.out_name = np;
    }
    spec.y = y.v;
    st = lv_table_create(&spec, out, err);
    if (st != LV_OK)
        lv_fail_prefix(err, st, "%s", path);

fail:
    free(text);
    free(f);
    free(x0.v);
    free(x1.v);
    free(y.v);
    free(names);
    free(units);
    free(np);
    free(up);
    return st;
}

/* ---- MAT (libmatio) -------------------------------------------------------------------- */

/* The numbers of a real, dense, numeric variable as doubles (column-major, as stored). */
static lv_status mat_numbers(const char *path, const matvar_t *mv, double **out, size_t *count,
                             lv_err *err)
{
    size_t n = 1;
    const int numeric = mv->class_type == MAT_C_DOUBLE || mv->class_type == MAT_C_SINGLE
                        || (mv->class_type >= MAT_C_INT8 && mv->class_type <= MAT_C_UINT64);
    if (!numeric || mv->isComplex)
        return lv_fail(err, LV_ERR_INPUT, "%s: variable '%s' is not a real numeric array "
                       "(complex, sparse, cell, struct, char are not tables)",
                       path, mv->name != NULL ? mv->name : "?");
    for (int r = 0; r < mv->rank; r++)
        n *= mv->dims[r];
    if (n > 0 && mv->data == NULL)
        return lv_fail(err, LV_ERR_IO, "%s: variable '%s': no data read", path, mv->name);
    double *v = malloc((n > 0 ? n : 1) * sizeof *v);
    if (v == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", path);
    for (size_t i = 0; i < n; i++) {
        switch (mv->data_type) {
        case MAT_T_DOUBLE: v[i] = ((const double *)mv->data)[i]; break;
        case MAT_T_SINGLE: v[i] = ((const float *)mv->data)[i]; break;
        case MAT_T_INT8: v[i] = ((const int8_t *)mv->data)[i]; break;
        case MAT_T_UINT8: v[i] = ((const uint8_t *)mv->data)[i]; break;
        case MAT_T_INT16: v[i] = ((const int16_t *)mv->data)[i]; break;
        case MAT_T_UINT16: v[i] = ((const uint16_t *)mv->data)[i]; break;
        case MAT_T_INT32: v[i] = ((const int32_t *)mv->data)[i]; break;
        case MAT_T_UINT32: v[i] = ((const uint32_t *)mv->data)[i]; break;
        case MAT_T_INT64: v[i] = (double)((const int64_t *)mv->data)[i]; break;
        case MAT_T_UINT64: v[i] = (double)((const uint64_t *)mv->data)[i]; break;
        default:
            free(v);
            return lv_fail(err, LV_ERR_INPUT, "%s: variable '%s': unsupported data type %d",
                           path, mv->name, (int)mv->data_type);
        }
    }
    *out = v;
    *count = n;
    return LV_OK;
}

/* Missing variable: LV_ERR_NOTFOUND with the nearest names in the file. */
static lv_status mat_missing(mat_t *mat, const char *path, const char *var, lv_err *err)
{
    lv_suggest sg;
    char hint[160];
    char pool[LV_SUGGEST_MAX + 1][64]; /* copies of the kept names; info is freed */
    lv_suggest_init(&sg, var);
    Mat_Rewind(mat);
    matvar_t *info;
    while ((info = Mat_VarReadNextInfo(mat)) != NULL) {
        if (info->name != NULL) {
            lv_suggest_add(&sg, info->name);
            for (size_t j = 0; j < sg.n; j++) {
                if (sg.best[j] != info->name)
                    continue;
                for (size_t b = 0; b <= LV_SUGGEST_MAX; b++) { /* a buffer nobody uses */
                    size_t used = 0;
                    for (size_t q = 0; q < sg.n; q++)
                        used |= sg.best[q] == pool[b];
                    if (!used) {
                        snprintf(pool[b], sizeof pool[b], "%s", info->name);
                        sg.best[j] = pool[b];
                        break;
                    }
                }
            }
        }
        Mat_VarFree(info);
    }
    lv_suggest_text(&sg, hint, sizeof hint);
    return lv_fail(err, LV_ERR_NOTFOUND, "%s: no variable '%s'%s", path, var, hint);
}

static int is_vector(const matvar_t *mv, size_t *len)
{
    size_t n = 1, big = 0;
    for (int r = 0; r < mv->rank; r++) {
        n *= mv->dims[r];
        if (mv->dims[r] > 1)
            big++;
    }
    *len = n;
    return big <= 1;
}

lv_status lv_table_load_mat(const char *path, const char *var, const lv_table_opts *opts,
                            lv_table **out, lv_err *err)
{
    mat_t *mat = NULL;
    matvar_t *mv = NULL;
    double *vals = NULL, *y = NULL;
    double *bx[LV_TABLE_MAX_DIMS] = { NULL };
    char axis[LV_TABLE_MAX_DIMS][CSV_TEXT_MAX];
    char outname[CSV_TEXT_MAX];
    const char *outp[1] = { outname };
    size_t count = 0;
    lv_status st;

    if (out == NULL || path == NULL || var == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_table_load_mat: NULL argument");
    *out = NULL;
    opts = opts_or_default(opts);
    if (strlen(var) > 60)
        return lv_fail(err, LV_ERR_INPUT, "%s: variable name '%.60s...' too long", path, var);
    mat = Mat_Open(path, MAT_ACC_RDONLY);
    if (mat == NULL)
        return lv_fail(err, LV_ERR_IO, "%s: cannot open as a MAT file (v4, v5, v7, v7.3)", path);
    mv = Mat_VarRead(mat, var);
    if (mv == NULL) {
        st = mat_missing(mat, path, var, err);
        goto fail;
    }
    st = mat_numbers(path, mv, &vals, &count, err);
    if (st != LV_OK)
        goto fail;

    lv_table_spec spec = { 0 };
    spec.interp = opts->interp;
    spec.extrap = opts->extrap;
    spec.name = var;

    /* Breakpoint vectors var_x1 .. var_xN select the gridded layout. */
    size_t nd = 0;
    for (; nd < LV_TABLE_MAX_DIMS; nd++) {
        snprintf(axis[nd], sizeof axis[nd], "%s_x%zu", var, nd + 1);
        matvar_t *xv = Mat_VarRead(mat, axis[nd]);
        if (xv == NULL)
            break;
        size_t nx = 0, len = 0;
        st = mat_numbers(path, xv, &bx[nd], &nx, err);
        const int vec = is_vector(xv, &len);
        Mat_VarFree(xv);
        if (st != LV_OK)
            goto fail;
        if (!vec) {
            st = lv_fail(err, LV_ERR_INPUT, "%s: breakpoints '%s' must be a vector", path,
                         axis[nd]);
            goto fail;
        }
        spec.n[nd] = nx;
        spec.x[nd] = bx[nd];
        spec.axis_name[nd] = axis[nd];
    }

    if (nd == 0) { /* CombiTable1D: [x, y1, y2, ..] */
        if (mv->rank != 2 || mv->dims[1] < 2) {
            st = lv_fail(err, LV_ERR_INPUT,
                         "%s: variable '%s' (%d-D, %zu columns) is neither an m x (1 + n_out) "
                         "matrix (first column: breakpoints) nor an N-D array with vectors "
                         "'%s_x1', '%s_x2', ..",
                         path, var, mv->rank, mv->rank >= 2 ? mv->dims[1] : (size_t)1, var, var);
            goto fail;
        }
        const size_t m = mv->dims[0], no = mv->dims[1] - 1;
        y = malloc(m * no * sizeof *y);
        char (*cn)[24] = calloc(no, sizeof *cn);
        const char **cp = calloc(no, sizeof *cp);
        if (y == NULL || cn == NULL || cp == NULL) {
            free(cn);
            free(cp);
            st = lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", path);
            goto fail;
        }
        for (size_t r = 0; r < m; r++)
            for (size_t k = 0; k < no; k++)
                y[r * no + k] = vals[r + m * (k + 1)]; /* column-major */
        for (size_t k = 0; k < no; k++) { /* Modelica numbers the columns from 1 */
            snprintf(cn[k], sizeof cn[k], "col%zu", k + 2);
            cp[k] = cn[k];
        }
        spec.n_dims = 1;
        spec.n[0] = m;
        spec.x[0] = vals; /* the first column */
        spec.axis_name[0] = "col1";
        spec.n_out = no;
        spec.out_name = cp;
        spec.y = y;
        st = lv_table_create(&spec, out, err);
        free(cn);
        free(cp);
    } else { /* gridded: V(i1, .., iN[, k]) column-major */
        size_t dims[8] = { 0 }, rank = 0, np = 1;
        for (int r = 0; r < mv->rank && r < 8; r++)
            dims[rank++] = mv->dims[r];
        while (rank > 0 && dims[rank - 1] == 1) /* MATLAB drops trailing singletons too */
            rank--;
        if (nd == 1 && rank == 2 && dims[0] == 1) { /* a row vector */
            dims[0] = dims[1];
            rank = 1;
        }
        for (size_t d = 0; d < nd; d++)
            np *= spec.n[d];
        int ok = (rank == nd || rank == nd + 1) && mv->rank <= 8;
        for (size_t d = 0; d < nd && ok; d++)
            ok = dims[d] == spec.n[d];
        if (!ok) {
            char got[96] = "", want[96] = "";
            size_t lg = 0, lw = 0;
            for (int r = 0; r < mv->rank && lg < sizeof got; r++) {
                const int w = snprintf(got + lg, sizeof got - lg, "%s%zu", r ? " x " : "",
                                       mv->dims[r]);
                lg += w > 0 ? (size_t)w : 0;
            }
            for (size_t d = 0; d < nd && lw < sizeof want; d++) {
                const int w = snprintf(want + lw, sizeof want - lw, "%s%zu", d ? " x " : "",
                                       spec.n[d]);
                lw += w > 0 ? (size_t)w : 0;
            }
            st = lv_fail(err, LV_ERR_INPUT, "%s: variable '%s' is %s; its breakpoint vectors "
                         "'%s_x1' .. '%s_x%zu' need %s (x n_out)", path, var, got, var, var, nd,
                         want);
            goto fail;
        }
        const size_t no = rank == nd + 1 ? dims[nd] : 1;
        y = malloc(np * no * sizeof *y);
        if (y == NULL) {
            st = lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", path);
            goto fail;
        }
        /* Ours: row-major, last axis fastest, outputs innermost. MATLAB: first axis fastest. */
        for (size_t p = 0; p < np; p++) {
            size_t rest = p, lin = 0, scale = 1;
            size_t idx[LV_TABLE_MAX_DIMS];
            for (size_t d = nd; d-- > 0;) {
                idx[d] = rest % spec.n[d];
                rest /= spec.n[d];
            }
            for (size_t d = 0; d < nd; d++) {
                lin += idx[d] * scale;
                scale *= spec.n[d];
            }
            for (size_t k = 0; k < no; k++)
                y[p * no + k] = vals[lin + np * k];
        }
        snprintf(outname, sizeof outname, "%s", var);
        spec.n_dims = nd;
        spec.n_out = no;
        spec.out_name = no == 1 ? outp : NULL;
        spec.y = y;
        st = lv_table_create(&spec, out, err);
    }
    if (st != LV_OK)
        lv_fail_prefix(err, st, "%s: variable '%s'", path, var);

fail:
    for (size_t d = 0; d < LV_TABLE_MAX_DIMS; d++)
        free(bx[d]);
    free(vals);
    free(y);
    Mat_VarFree(mv);
    Mat_Close(mat);
    return st;
}

int lv_table_path_is_mat(const char *path)
{
    const size_t n = strlen(path);
    return n >= 4 && (strcmp(path + n - 4, ".mat") == 0 || strcmp(path + n - 4, ".MAT") == 0);
}

lv_status lv_table_load(const char *path, const char *var, const lv_table_opts *opts,
                        lv_table **out, lv_err *err)
{
    const int mat = lv_table_path_is_mat(path);
    if (mat && var == NULL)
        return lv_fail(err, LV_ERR_INPUT, "%s: a MAT file needs the name of its variable",
                       path);
    if (!mat && var != NULL)
        return lv_fail(err, LV_ERR_INPUT,
                       "%s: variable '%s' given, but the file is read as CSV (not '.mat')",
                       path, var);
    return mat ? lv_table_load_mat(path, var, opts, out, err)
               : lv_table_load_csv(path, opts, out, err);
}
