/* table_load.c - lookup tables from CSV files and MATLAB/Octave MAT files (libmatio).
 *
 * Conventions (docs/tables.md): CSV 1-D with a "name [unit]" header; CSV 2-D grid and MAT
 * matrices in the Modelica CombiTable2D / CombiTable1D layouts (Modelica Standard Library,
 * Modelica.Blocks.Tables); MAT N-D as an n1 x .. x nN array with vectors var_x1 .. var_xN,
 * or as a struct whose fields are the named axes and outputs. MAT v7.3 variables that
 * libmatio cannot classify (written by other HDF5 writers) are read with the HDF5 C API.
 */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <hdf5.h>
#include <matio.h>

#include "core/names.h"
#include "core/status.h"
#include "io/numparse.h"
#include "io/hdf5_dl.h"
#include "io/readfile.h"
#include "io/table_load.h"
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
    static const lv_table_opts deflt = { LV_INTERP_LINEAR, LV_EXTRAP_ERROR, 0 }; /* const */
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
    int repeats_last; /* lv_table_opts.repeats_last */
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
    return lv_numparse_field(f->s, f->len, v); /* strtod's rules, fast_float's speed */
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
            if (j == 0 && c->repeats_last && x0->n > 0 && v == x0->v[x0->n - 1])
                y->n -= ncol - 1; /* the row replaces the previous one: its values go */
            else if (j == 0)
                st = push_breakpoint(c, &f[j], x0, v, err);
            else if (dvec_push(y, v) != 0)
                st = lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", c->path);
            if (st != LV_OK)
                return st;
        }
    }
}

static lv_status csv_load(const char *path, const lv_table_opts *opts, lv_table_spec_fn fn,
                          void *user, lv_err *err)
{
    char *text = NULL;
    size_t len = 0, nf = 0;
    csv_field *f = NULL;
    dvec x0 = { 0 }, x1 = { 0 }, y = { 0 };
    char (*names)[CSV_TEXT_MAX] = NULL, (*units)[CSV_TEXT_MAX] = NULL;
    const char **np = NULL, **up = NULL;
    csv_ctx c = { path, 0, 0 };
    char stem[CSV_TEXT_MAX];
    lv_status st;

    opts = opts_or_default(opts);
    c.repeats_last = opts->repeats_last;
    file_stem(path, stem, sizeof stem);
    st = lv_read_file(path, LV_TABLE_FILE_MAX, "a table file", &text, &len, err);
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
    st = fn(&spec, user, err);

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

/* ---- MAT (libmatio; HDF5 directly for v7.3 files from other writers) ------------------ */

#define MAT_RANK_MAX 8

/* A real numeric array as doubles, column-major as MATLAB stores it. */
typedef struct mat_arr {
    size_t rank;                /* >= 2, as MATLAB counts (a vector is 1 x n or n x 1) */
    size_t dims[MAT_RANK_MAX];
    size_t n;                   /* number of elements */
    double *v;
} mat_arr;

/* An open MAT file; for v7.3 also, when needed, the same file through the HDF5 C API. */
typedef struct mat_src {
    const char *path;
    mat_t *mat;
    int v73;
    hid_t h5; /* -1 until the fallback needs it */
} mat_src;

static void mat_arr_free(mat_arr *a)
{
    free(a->v);
    a->v = NULL;
}

static const char *class_name(enum matio_classes c)
{
    static const char *const names[] = { "empty", "cell", "struct", "object", "char",
                                         "sparse", "double", "single", "int8", "uint8",
                                         "int16", "uint16", "int32", "uint32", "int64",
                                         "uint64", "function", "opaque" };
    return (size_t)c < sizeof names / sizeof names[0] ? names[c] : "unknown";
}

static int class_numeric(enum matio_classes c)
{
    return c == MAT_C_DOUBLE || c == MAT_C_SINGLE || (c >= MAT_C_INT8 && c <= MAT_C_UINT64);
}

/* Nearest names to a missing variable, keeping copies of the names (a file listing frees
 * each name before the next). */
typedef struct name_pool {
    lv_suggest sg;
    char pool[LV_SUGGEST_MAX + 1][64];
} name_pool;

static void pool_add(name_pool *p, const char *name)
{
    lv_suggest_add(&p->sg, name);
    for (size_t j = 0; j < p->sg.n; j++) {
        if (p->sg.best[j] != name)
            continue;
        for (size_t b = 0; b <= LV_SUGGEST_MAX; b++) { /* a buffer nobody uses */
            size_t used = 0;
            for (size_t q = 0; q < p->sg.n; q++)
                used |= p->sg.best[q] == p->pool[b];
            if (!used) {
                snprintf(p->pool[b], sizeof p->pool[b], "%s", name);
                p->sg.best[j] = p->pool[b];
                break;
            }
        }
    }
}

/* Missing variable: LV_ERR_NOTFOUND with the nearest names in the file. */
static lv_status mat_missing(mat_t *mat, const char *path, const char *var, lv_err *err)
{
    name_pool p;
    char hint[160];
    lv_suggest_init(&p.sg, var);
    Mat_Rewind(mat);
    matvar_t *info;
    while ((info = Mat_VarReadNextInfo(mat)) != NULL) {
        if (info->name != NULL)
            pool_add(&p, info->name);
        Mat_VarFree(info);
    }
    lv_suggest_text(&p.sg, hint, sizeof hint);
    return lv_fail(err, LV_ERR_NOTFOUND, "%s: no variable '%s'%s", path, var, hint);
}

/* ---- the HDF5 fallback ----
 * libmatio 1.5 reads a v7.3 variable's class from its MATLAB_class attribute by converting it
 * to a null-terminated string of the attribute's own size: an attribute written null-padded
 * without a terminator (h5py, hdf5storage: "double" in 6 bytes) loses its last character, the
 * class becomes unknown and no data are read. Such a variable is read here with the HDF5 C
 * API: a dataset of integers or floating-point numbers whose MATLAB_class (any padding, fixed
 * or variable length; or none at all) is a numeric class. Complex (compound), logical,
 * char, cell, struct groups and references are not read. libmatio also stops listing a
 * file's variables at the first object it cannot classify, so a v7.3 variable libmatio does
 * not find is looked up with HDF5 too. */

/* The MATLAB_class attribute of `obj` into cls (""; no attribute: "-"). 0, or -1 if it is
 * not a single string. */
static int h5_class(hid_t obj, char *cls, size_t cap)
{
    snprintf(cls, cap, "-");
    if (H5Aexists(obj, "MATLAB_class") <= 0)
        return 0;
    int rc = -1;
    hid_t a = H5Aopen(obj, "MATLAB_class", H5P_DEFAULT);
    hid_t t = a >= 0 ? H5Aget_type(a) : -1;
    hid_t sp = a >= 0 ? H5Aget_space(a) : -1;
    if (t >= 0 && sp >= 0 && H5Tget_class(t) == H5T_STRING &&
        H5Sget_simple_extent_npoints(sp) == 1) {
        if (H5Tis_variable_str(t) > 0) {
            char *s = NULL;
            hid_t mt = H5Tcopy(lv_h5_c_s1());
            if (mt >= 0 && H5Tset_size(mt, H5T_VARIABLE) >= 0 && H5Aread(a, mt, &s) >= 0 &&
                s != NULL) {
                snprintf(cls, cap, "%s", s);
                rc = 0;
            }
            if (s != NULL)
                H5free_memory(s);
            if (mt >= 0)
                H5Tclose(mt);
        } else {
            const size_t n = H5Tget_size(t);
            char *buf = n > 0 && n < 4096 ? calloc(n + 1, 1) : NULL;
            hid_t mt = buf != NULL ? H5Tcopy(t) : -1; /* the file's own size and padding */
            if (mt >= 0 && H5Aread(a, mt, buf) >= 0) {
                const char *z = memchr(buf, '\0', n);
                size_t k = z != NULL ? (size_t)(z - buf) : n;
                while (k > 0 && buf[k - 1] == ' ') /* space-padded */
                    k--;
                snprintf(cls, cap, "%.*s", (int)k, buf);
                rc = 0;
            }
            if (mt >= 0)
                H5Tclose(mt);
            free(buf);
        }
    }
    if (sp >= 0)
        H5Sclose(sp);
    if (t >= 0)
        H5Tclose(t);
    if (a >= 0)
        H5Aclose(a);
    return rc;
}

static lv_status h5_read_dataset(mat_src *s, const char *obj, const char *shown, mat_arr *out,
                                 lv_err *err)
{
    static const char *const numeric[] = { "double", "single", "int8", "uint8", "int16",
                                           "uint16", "int32", "uint32", "int64", "uint64" };
    lv_status st = LV_OK;
    hid_t ds = -1, ty = -1, sp = -1;
    char cls[64];
    if (s->h5 < 0 && (s->h5 = H5Fopen(s->path, H5F_ACC_RDONLY, H5P_DEFAULT)) < 0)
        return lv_fail(err, LV_ERR_IO, "%s: cannot open as an HDF5 (MAT v7.3) file", s->path);
    H5O_info_t info;
    if (H5Oget_info_by_name(s->h5, obj, &info, H5P_DEFAULT) < 0)
        return lv_fail(err, LV_ERR_INPUT, "%s: variable '%s': not found by HDF5", s->path,
                       shown);
    if (info.type != H5O_TYPE_DATASET) {
        hid_t o = H5Oopen(s->h5, obj, H5P_DEFAULT);
        if (o >= 0) {
            (void)h5_class(o, cls, sizeof cls);
            H5Oclose(o);
        }
        return lv_fail(err, LV_ERR_INPUT,
                       "%s: variable '%s' is an HDF5 group (MATLAB_class '%s') that libmatio "
                       "does not read; a table from a non-MATLAB HDF5 writer must be a numeric "
                       "dataset (a struct works as MATLAB, Octave or libmatio write it)",
                       s->path, shown, cls);
    }
    if ((ds = H5Dopen2(s->h5, obj, H5P_DEFAULT)) < 0) {
        st = lv_fail(err, LV_ERR_IO, "%s: variable '%s': cannot open the dataset", s->path,
                     shown);
        goto done;
    }
    if (h5_class(ds, cls, sizeof cls) != 0) {
        st = lv_fail(err, LV_ERR_INPUT, "%s: variable '%s': its MATLAB_class attribute is not "
                     "a single string", s->path, shown);
        goto done;
    }
    int known = strcmp(cls, "-") == 0; /* no class: a plain HDF5 dataset */
    for (size_t i = 0; i < sizeof numeric / sizeof numeric[0] && !known; i++)
        known = strcmp(cls, numeric[i]) == 0;
    if (!known) {
        st = lv_fail(err, LV_ERR_INPUT, "%s: variable '%s' has MATLAB_class '%.40s'; a table "
                     "needs a numeric class (double, single, int8 .. uint64)",
                     s->path, shown, cls);
        goto done;
    }
    ty = H5Dget_type(ds);
    const H5T_class_t tc = ty >= 0 ? H5Tget_class(ty) : H5T_NO_CLASS;
    if (tc != H5T_FLOAT && tc != H5T_INTEGER) {
        st = lv_fail(err, LV_ERR_INPUT, "%s: variable '%s': HDF5 datatype class %d is not "
                     "integer or floating point (complex numbers are a compound type, not "
                     "supported)", s->path, shown, (int)tc);
        goto done;
    }
    sp = H5Dget_space(ds);
    const int rank = sp >= 0 ? H5Sget_simple_extent_ndims(sp) : -1;
    hsize_t hd[MAT_RANK_MAX];
    if (rank < 0 || rank > MAT_RANK_MAX || H5Sget_simple_extent_dims(sp, hd, NULL) < 0) {
        st = lv_fail(err, LV_ERR_INPUT, "%s: variable '%s': dataspace of rank %d (1 to %d "
                     "supported)", s->path, shown, rank, MAT_RANK_MAX);
        goto done;
    }
    /* HDF5 lists the dimensions slowest first: MATLAB's order reversed. A 1-D dataset is a
     * column vector. */
    memset(out, 0, sizeof *out);
    out->rank = rank < 2 ? 2 : (size_t)rank;
    out->n = 1;
    for (int r = 0; r < rank; r++) {
        out->dims[r] = (size_t)hd[rank - 1 - r];
        out->n *= out->dims[r];
    }
    for (size_t r = (size_t)rank; r < out->rank; r++)
        out->dims[r] = 1;
    if (H5Aexists(ds, "MATLAB_empty") > 0) {
        out->n = 0; /* MATLAB's [] : the dataset holds the dimensions instead */
        out->dims[0] = out->dims[1] = 0;
    }
    out->v = malloc((out->n > 0 ? out->n : 1) * sizeof *out->v);
    if (out->v == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", s->path);
        goto done;
    }
    if (out->n > 0 && H5Dread(ds, lv_h5_native_double(), H5S_ALL, H5S_ALL, H5P_DEFAULT, out->v) < 0) {
        mat_arr_free(out);
        st = lv_fail(err, LV_ERR_IO, "%s: variable '%s': HDF5 read failed", s->path, shown);
    }
done:
    if (sp >= 0)
        H5Sclose(sp);
    if (ty >= 0)
        H5Tclose(ty);
    if (ds >= 0)
        H5Dclose(ds);
    return st;
}

/* 1 if the v7.3 file has an object at the top level named `name`. */
static int h5_exists(mat_src *s, const char *name)
{
    if (s->h5 < 0 && (s->h5 = H5Fopen(s->path, H5F_ACC_RDONLY, H5P_DEFAULT)) < 0)
        return 0;
    return name[0] != '\0' && strchr(name, '/') == NULL && H5Lexists(s->h5, name, H5P_DEFAULT) > 0;
}

static herr_t h5_suggest_one(hid_t g, const char *name, const H5L_info_t *info, void *user)
{
    (void)g;
    (void)info;
    pool_add(user, name);
    return 0;
}

/* Missing variable in a v7.3 file: the nearest names among the file's top-level objects
 * (libmatio's own listing stops at objects it cannot classify). */
static lv_status h5_missing(mat_src *s, const char *var, lv_err *err)
{
    name_pool p;
    char hint[160];
    lv_suggest_init(&p.sg, var);
    if (s->h5 >= 0) {
        hsize_t idx = 0;
        H5Literate(s->h5, H5_INDEX_NAME, H5_ITER_INC, &idx, h5_suggest_one, &p);
    }
    lv_suggest_text(&p.sg, hint, sizeof hint);
    return lv_fail(err, LV_ERR_NOTFOUND, "%s: no variable '%s'%s", s->path, var, hint);
}

/* ---- libmatio ---- */

/* The numbers of `mv` (variable or struct field `shown`; its HDF5 path `h5path` for the
 * fallback) as doubles. */
static lv_status mat_numbers(mat_src *s, const matvar_t *mv, const char *h5path,
                             const char *shown, mat_arr *out, lv_err *err)
{
    memset(out, 0, sizeof *out);
    if (mv->class_type == MAT_C_EMPTY && s->v73 && h5path != NULL)
        return h5_read_dataset(s, h5path, shown, out, err);
    if (!class_numeric(mv->class_type) || mv->isComplex)
        return lv_fail(err, LV_ERR_INPUT, "%s: variable '%s' is %s%s, not a real numeric "
                       "array (complex, sparse, cell, struct, char are not tables)", s->path,
                       shown, mv->isComplex ? "complex " : "", class_name(mv->class_type));
    if (mv->rank < 1 || mv->rank > MAT_RANK_MAX)
        return lv_fail(err, LV_ERR_INPUT, "%s: variable '%s' has rank %d (at most %d)",
                       s->path, shown, mv->rank, MAT_RANK_MAX);
    out->rank = mv->rank < 2 ? 2 : (size_t)mv->rank;
    out->n = 1;
    for (size_t r = 0; r < out->rank; r++) {
        out->dims[r] = r < (size_t)mv->rank ? mv->dims[r] : 1;
        out->n *= out->dims[r];
    }
    if (out->n > 0 && mv->data == NULL)
        return lv_fail(err, LV_ERR_IO, "%s: variable '%s': no data read", s->path, shown);
    double *v = malloc((out->n > 0 ? out->n : 1) * sizeof *v);
    if (v == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", s->path);
    for (size_t i = 0; i < out->n; i++) {
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
                           s->path, shown, (int)mv->data_type);
        }
    }
    out->v = v;
    return LV_OK;
}

/* Top-level variable `name` as numbers; *found 0 (and LV_OK) when the file has none. */
static lv_status mat_read_numbers(mat_src *s, const char *name, mat_arr *out, int *found,
                                  lv_err *err)
{
    memset(out, 0, sizeof *out);
    matvar_t *mv = Mat_VarRead(s->mat, name);
    char h5path[128];
    snprintf(h5path, sizeof h5path, "/%s", name);
    *found = mv != NULL || (s->v73 && h5_exists(s, name));
    if (mv == NULL)
        return *found ? h5_read_dataset(s, h5path, name, out, err) : LV_OK;
    const lv_status st = mat_numbers(s, mv, h5path, name, out, err);
    Mat_VarFree(mv);
    return st;
}

/* Non-singleton dimensions of `a` (MATLAB drops trailing singletons); *len the element
 * count. A vector has at most one. */
static size_t big_dims(const mat_arr *a)
{
    size_t big = 0;
    for (size_t r = 0; r < a->rank; r++)
        big += a->dims[r] > 1;
    return big;
}

static void dims_text(const mat_arr *a, char *buf, size_t cap)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t r = 0; r < a->rank && used < cap; r++) {
        const int w = snprintf(buf + used, cap - used, "%s%zu", r ? " x " : "", a->dims[r]);
        used += w > 0 ? (size_t)w : 0;
    }
}

/* MATLAB's column-major V(i1, .., iN, k) (N axes of n[d] points, no outputs) into ours:
 * row-major, last axis fastest, the no outputs of a point adjacent. */
static void to_row_major(const double *vals, size_t nd, const size_t *n, size_t no, double *y)
{
    size_t np = 1;
    for (size_t d = 0; d < nd; d++)
        np *= n[d];
    for (size_t p = 0; p < np; p++) {
        size_t rest = p, lin = 0, scale = 1;
        size_t idx[LV_TABLE_MAX_DIMS];
        for (size_t d = nd; d-- > 0;) {
            idx[d] = rest % n[d];
            rest /= n[d];
        }
        for (size_t d = 0; d < nd; d++) {
            lin += idx[d] * scale;
            scale *= n[d];
        }
        for (size_t k = 0; k < no; k++)
            y[p * no + k] = vals[lin + np * k];
    }
}

/* Modelica CombiTable1D: `var` is m x (1 + n_out), the first column the breakpoints, the
 * outputs named col2, col3, .. (Modelica's column numbers). One row is passed on as read. */
static lv_status mat_combi(mat_src *s, const char *var, const mat_arr *a,
                           const lv_table_opts *opts, lv_table_spec_fn fn, void *user,
                           lv_err *err)
{
    if (a->rank != 2 || a->dims[1] < 2)
        return lv_fail(err, LV_ERR_INPUT,
                       "%s: variable '%s' (%zu-D, %zu columns) is neither an m x (1 + n_out) "
                       "matrix (first column: breakpoints), a struct of named axes and outputs, "
                       "nor an N-D array with vectors '%s_x1', '%s_x2', ..",
                       s->path, var, a->rank, a->dims[1], var, var);
    const size_t m = a->dims[0], no = a->dims[1] - 1;
    if (m == 0) /* no values: the column count alone, however large, would size the names */
        return lv_fail(err, LV_ERR_INPUT, "%s: variable '%s' is 0 x %zu: a table needs rows "
                       "(breakpoints)", s->path, var, a->dims[1]);
    double *y = malloc((m * no > 0 ? m * no : 1) * sizeof *y);
    char (*cn)[24] = calloc(no, sizeof *cn);
    const char **cp = calloc(no, sizeof *cp);
    lv_status st;
    if (y == NULL || cn == NULL || cp == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", s->path);
        goto done;
    }
    for (size_t r = 0; r < m; r++)
        for (size_t k = 0; k < no; k++)
            y[r * no + k] = a->v[r + m * (k + 1)]; /* column-major */
    for (size_t k = 0; k < no; k++) { /* Modelica numbers the columns from 1 */
        snprintf(cn[k], sizeof cn[k], "col%zu", k + 2);
        cp[k] = cn[k];
    }
    lv_table_spec spec = { 0 };
    spec.interp = opts->interp;
    spec.extrap = opts->extrap;
    spec.name = var;
    spec.n_dims = 1;
    spec.n[0] = m;
    spec.x[0] = a->v; /* the first column */
    spec.axis_name[0] = "col1";
    spec.n_out = no;
    spec.out_name = cp;
    spec.y = y;
    st = fn(&spec, user, err);
done:
    free(y);
    free(cn);
    free(cp);
    return st;
}

/* N-D gridded: `var` is n1 x .. x nN (x n_out) with breakpoint vectors var_x1 .. var_xN. */
static lv_status mat_grid(mat_src *s, const char *var, const mat_arr *a, size_t nd,
                          mat_arr *bx, const lv_table_opts *opts, lv_table_spec_fn fn,
                          void *user, lv_err *err)
{
    char axis[LV_TABLE_MAX_DIMS][CSV_TEXT_MAX];
    lv_table_spec spec = { 0 };
    size_t dims[MAT_RANK_MAX] = { 0 }, rank = 0, np = 1;
    for (size_t r = 0; r < a->rank; r++)
        dims[rank++] = a->dims[r];
    while (rank > 0 && dims[rank - 1] == 1) /* MATLAB drops trailing singletons too */
        rank--;
    if (nd == 1 && rank == 2 && dims[0] == 1) { /* a row vector */
        dims[0] = dims[1];
        rank = 1;
    }
    for (size_t d = 0; d < nd; d++) {
        snprintf(axis[d], sizeof axis[d], "%s_x%zu", var, d + 1);
        spec.n[d] = bx[d].n;
        spec.x[d] = bx[d].v;
        spec.axis_name[d] = axis[d];
        np *= spec.n[d];
    }
    int ok = rank == nd || rank == nd + 1;
    for (size_t d = 0; d < nd && ok; d++)
        ok = dims[d] == spec.n[d];
    if (!ok) {
        char got[96], want[96] = "";
        size_t lw = 0;
        dims_text(a, got, sizeof got);
        for (size_t d = 0; d < nd && lw < sizeof want; d++) {
            const int w = snprintf(want + lw, sizeof want - lw, "%s%zu", d ? " x " : "",
                                   spec.n[d]);
            lw += w > 0 ? (size_t)w : 0;
        }
        return lv_fail(err, LV_ERR_INPUT, "%s: variable '%s' is %s; its breakpoint vectors "
                       "'%s_x1' .. '%s_x%zu' need %s (x n_out)", s->path, var, got, var, var,
                       nd, want);
    }
    const size_t no = rank == nd + 1 ? dims[nd] : 1;
    double *y = malloc((np * no > 0 ? np * no : 1) * sizeof *y);
    if (y == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", s->path);
    to_row_major(a->v, nd, spec.n, no, y);
    const char *outp[1] = { var };
    spec.interp = opts->interp;
    spec.extrap = opts->extrap;
    spec.name = var;
    spec.n_dims = nd;
    spec.n_out = no;
    spec.out_name = no == 1 ? outp : NULL;
    spec.y = y;
    const lv_status st = fn(&spec, user, err);
    free(y);
    return st;
}

/* A 1 x 1 struct whose fields are the axes and the outputs, named (docs/tables.md):
 *  - N-D (N >= 2): the output fields are arrays n1 x .. x nN; every vector field is an axis,
 *    in field order, axis d of length n_d;
 *  - 1-D (every field a vector): the first field is the axis, the others are outputs. */
static lv_status mat_struct(mat_src *s, const char *var, matvar_t *mv,
                            const lv_table_opts *opts, lv_table_spec_fn fn, void *user,
                            lv_err *err)
{
    size_t count = 1;
    for (int r = 0; r < mv->rank; r++)
        count *= mv->dims[r];
    const unsigned nf = Mat_VarGetNumberOfFields(mv);
    char *const *names = Mat_VarGetStructFieldnames(mv);
    if (count != 1)
        return lv_fail(err, LV_ERR_INPUT, "%s: variable '%s' is a struct array of %zu "
                       "elements; a table is one struct (1 x 1)", s->path, var, count);
    if (nf < 2 || names == NULL)
        return lv_fail(err, LV_ERR_INPUT, "%s: struct '%s' has %u field%s; a table needs an "
                       "axis and at least one output", s->path, var, nf, nf == 1 ? "" : "s");
    mat_arr *f = calloc(nf, sizeof *f);
    size_t *ax = calloc(nf, sizeof *ax), *ou = calloc(nf, sizeof *ou);
    double *y = NULL;
    const char **on = calloc(nf, sizeof *on);
    lv_status st = LV_OK;
    size_t nax = 0, nout = 0, ngrid = 0;
    if (f == NULL || ax == NULL || ou == NULL || on == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", s->path);
        goto done;
    }
    for (unsigned i = 0; i < nf && st == LV_OK; i++) {
        char shown[CSV_TEXT_MAX + 72], h5path[CSV_TEXT_MAX + 72];
        snprintf(shown, sizeof shown, "%s.%s", var, names[i]);
        snprintf(h5path, sizeof h5path, "/%s/%s", var, names[i]);
        matvar_t *fv = Mat_VarGetStructFieldByIndex(mv, i, 0);
        if (fv == NULL)
            st = lv_fail(err, LV_ERR_INPUT, "%s: struct field '%s' is empty", s->path, shown);
        else
            st = mat_numbers(s, fv, h5path, shown, &f[i], err);
        if (st == LV_OK && f[i].n == 0)
            st = lv_fail(err, LV_ERR_INPUT, "%s: struct field '%s' is empty", s->path, shown);
        if (st == LV_OK && strlen(names[i]) >= CSV_TEXT_MAX)
            st = lv_fail(err, LV_ERR_INPUT, "%s: struct field name '%.40s...' too long",
                         s->path, names[i]);
        ngrid += big_dims(&f[i]) > 1;
    }
    if (st != LV_OK)
        goto done;
    if (ngrid == 0) { /* 1-D: the first field is the axis */
        ax[nax++] = 0;
        for (unsigned i = 1; i < nf; i++)
            ou[nout++] = i;
    } else {
        for (unsigned i = 0; i < nf; i++) {
            if (big_dims(&f[i]) > 1)
                ou[nout++] = i;
            else
                ax[nax++] = i;
        }
    }
    if (nax > LV_TABLE_MAX_DIMS) {
        st = lv_fail(err, LV_ERR_INPUT, "%s: struct '%s' has %zu axis vectors; at most %d "
                     "axes", s->path, var, nax, LV_TABLE_MAX_DIMS);
        goto done;
    }
    lv_table_spec spec = { 0 };
    size_t np = 1;
    for (size_t d = 0; d < nax; d++) {
        const mat_arr *a = &f[ax[d]];
        if (a->n < 2 && ngrid > 0) {
            st = lv_fail(err, LV_ERR_INPUT, "%s: struct '%s': field '%s' holds one number; "
                         "a table struct holds axis vectors and output arrays only", s->path,
                         var, names[ax[d]]);
            goto done;
        }
        spec.n[d] = a->n;
        spec.x[d] = a->v;
        spec.axis_name[d] = names[ax[d]];
        np *= a->n;
    }
    for (size_t k = 0; k < nout; k++) { /* each output exactly n1 x .. x nN */
        const mat_arr *o = &f[ou[k]];
        size_t dims[MAT_RANK_MAX], rank = 0;
        for (size_t r = 0; r < o->rank; r++)
            dims[rank++] = o->dims[r];
        while (rank > 1 && dims[rank - 1] == 1)
            rank--;
        if (nax == 1 && rank == 2 && dims[0] == 1) { /* a row vector */
            dims[0] = dims[1];
            rank = 1;
        }
        int ok = rank == nax;
        for (size_t d = 0; d < nax && ok; d++)
            ok = dims[d] == spec.n[d];
        if (!ok) {
            char got[96], want[96] = "";
            size_t lw = 0;
            dims_text(o, got, sizeof got);
            for (size_t d = 0; d < nax && lw < sizeof want; d++) {
                const int w = snprintf(want + lw, sizeof want - lw, "%s%s (%zu)",
                                       d ? " x " : "", names[ax[d]], spec.n[d]);
                lw += w > 0 ? (size_t)w : 0;
            }
            st = lv_fail(err, LV_ERR_INPUT, "%s: struct '%s': output '%s' is %s; the axis "
                         "fields, in field order, need %s", s->path, var, names[ou[k]], got,
                         want);
            goto done;
        }
        on[k] = names[ou[k]];
    }
    y = malloc((np * nout > 0 ? np * nout : 1) * sizeof *y);
    double *one = malloc((np > 0 ? np : 1) * sizeof *one);
    if (y == NULL || one == NULL) {
        free(one);
        st = lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", s->path);
        goto done;
    }
    for (size_t k = 0; k < nout; k++) { /* each output on its own, then interleaved */
        to_row_major(f[ou[k]].v, nax, spec.n, 1, one);
        for (size_t p = 0; p < np; p++)
            y[p * nout + k] = one[p];
    }
    free(one);
    spec.interp = opts->interp;
    spec.extrap = opts->extrap;
    spec.name = var;
    spec.n_dims = nax;
    spec.n_out = nout;
    spec.out_name = on;
    spec.y = y;
    st = fn(&spec, user, err);
done:
    for (unsigned i = 0; f != NULL && i < nf; i++)
        mat_arr_free(&f[i]);
    free(f);
    free(ax);
    free(ou);
    free(on);
    free(y);
    return st;
}

/* What libmatio allocates comes from the file's own headers, read before the data they
 * announce: a file of a few hundred bytes could claim gigabytes (found by fuzz/fuzz_tables.c:
 * a v4 name of 1.75 GB, a v5 dimensions element of 1.2 GB that became a 2.4 GB array). So the
 * headers are walked first, and the file is refused when one claims more than the file holds
 * (MAT-File Format, The MathWorks, R2023a: "Level 4 MAT-files" and "Level 5 MAT-file
 * format"). Every allocation libmatio then makes is a few times the file's size. */
typedef struct mat_walk {
    FILE *fp;
    const char *path;
    int big;      /* big-endian */
    long end;     /* the file's size */
    lv_err *err;
} mat_walk;

static uint32_t get_u32(const unsigned char *b, int big)
{
    return big ? (uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 | (uint32_t)b[2] << 8 | b[3]
               : (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 |
                     (uint32_t)b[3] << 24;
}

/* A v4 file: a run of variables, each five int32 (type MOPT, rows, columns, imaginary flag,
 * name length), the name and the data. A partial header at the end is where libmatio stops
 * reading, and is left to it. */
static lv_status mat_v4_check(mat_walk *w)
{
    static const unsigned elsize[6] = {8, 4, 4, 2, 2, 1}; /* by P: double .. uint8 */
    unsigned char h[20];
    long off = 0;
    while (w->end - off >= 20 && fseek(w->fp, off, SEEK_SET) == 0 &&
           fread(h, 1, 20, w->fp) == 20) {
        const int big = get_u32(h, 0) > 4052u; /* M = 1: big-endian */
        uint32_t v[5];
        for (int i = 0; i < 5; i++)
            v[i] = get_u32(h + 4 * i, big);
        const uint32_t t = v[0];
        const uint64_t left = (uint64_t)(w->end - off - 20);
        if (t > 4052u || t / 100 % 10 != 0 || t / 10 % 10 > 5 || t % 10 > 2 || v[3] > 1 ||
            v[4] < 1 || v[1] > INT32_MAX || v[2] > INT32_MAX || v[4] > INT32_MAX)
            return lv_fail(w->err, LV_ERR_INPUT, "%s: not a MAT file: no v5 header, and bytes "
                           "%ld.. are not a MAT v4 variable header (type %u, %u x %u, imaginary "
                           "%u, name of %u bytes)", w->path, off, (unsigned)t, (unsigned)v[1],
                           (unsigned)v[2], (unsigned)v[3], (unsigned)v[4]);
        const uint64_t per = elsize[t / 10 % 10] * (v[3] ? 2u : 1u); /* bytes per value */
        if (v[4] > left || (v[1] > 0 && v[2] > (left - v[4]) / per / v[1]))
            return lv_fail(w->err, LV_ERR_INPUT, "%s: truncated MAT v4 file: the variable at "
                           "byte %ld (%u x %u of %u-byte values, a name of %u bytes) is longer "
                           "than the %llu bytes after its header", w->path, off, (unsigned)v[1],
                           (unsigned)v[2], (unsigned)per, (unsigned)v[4],
                           (unsigned long long)left);
        off += 20 + (long)v[4] + (long)((uint64_t)v[1] * v[2] * per);
    }
    return LV_OK;
}

/* The data elements of a v5 file in [off, end): each tag (type, size; or the small format:
 * size in the upper 16 bits, data in the next 4 bytes) within its container; a matrix's
 * elements in turn, and its dimensions' product within the matrix's size, each value taking a
 * byte at least (a sparse matrix: its nzmax). Compressed elements (v7) are checked for their
 * size only. */
static lv_status mat_v5_elements(mat_walk *w, long off, long end, int depth, const char *in)
{
    unsigned char tag[8];
    int k = 0; /* position in a matrix: flags, dimensions, name, the rest */
    uint32_t cls = 0, nzmax = 0, fnlen = 0;
    uint64_t cells = 0;
    while (end - off >= 8) {
        if (fseek(w->fp, off, SEEK_SET) != 0 || fread(tag, 1, 8, w->fp) != 8)
            return LV_OK; /* libmatio reports the short read */
        uint32_t type = get_u32(tag, w->big), n = get_u32(tag + 4, w->big);
        long size = 8 + (long)n + (long)((8u - n % 8u) % 8u); /* padded to 8 bytes */
        if (type >> 16 != 0) { /* small data element */
            n = type >> 16;
            type &= 0xffffu;
            size = 8;
            if (n > 4)
                return lv_fail(w->err, LV_ERR_INPUT, "%s: malformed MAT file: the small "
                               "element at byte %ld (%s) claims %u bytes (4 at most)", w->path,
                               off, in, (unsigned)n);
        } else if ((uint64_t)n > (uint64_t)(end - off - 8)) {
            return lv_fail(w->err, LV_ERR_INPUT, "%s: malformed MAT file: the element at byte %ld "
                           "(%s) claims %u bytes, %ld are left", w->path, off, in, (unsigned)n,
                           end - off - 8);
        }
        if (type == 15u) /* miCOMPRESSED: not padded */
            size = 8 + (long)n;
        if (depth > 0 && k == 0 && n >= 8 && size > 8) { /* array flags: class, nzmax */
            unsigned char f[8];
            if (fread(f, 1, 8, w->fp) == 8) {
                cls = get_u32(f, w->big) & 0xffu;
                nzmax = get_u32(f + 4, w->big);
            }
        } else if (depth > 0 && k == 1 && type == 5u && size > 8) { /* dimensions, miINT32 */
            cells = 1;
            for (uint32_t i = 0; i + 4 <= n; i += 4) { /* the product, saturated */
                unsigned char d[4];
                if (fread(d, 1, 4, w->fp) != 4)
                    break;
                const uint32_t di = get_u32(d, w->big);
                cells = di != 0 && cells > UINT64_MAX / di ? UINT64_MAX : cells * di;
            }
            /* a cell or struct holds a matrix element (8 bytes at least) per value */
            const uint64_t need = cls == 5u ? nzmax : cls == 1u || cls == 2u ? 8 * cells : cells;
            if (cells > (uint64_t)(end - off) || need > (uint64_t)(end - off))
                return lv_fail(w->err, LV_ERR_INPUT, "%s: malformed MAT file: the array at byte "
                               "%ld (%s) claims %llu values, more than its %ld bytes hold",
                               w->path, off, in, (unsigned long long)cells, end - off);
        } else if (depth > 0 && (cls == 2u || cls == 3u) && k == (cls == 2u ? 3 : 4)) {
            unsigned char d[4]; /* struct: field name length, small or not */
            fnlen = n != 4 ? 0 : size == 8 ? get_u32(tag + 4, w->big)
                               : fread(d, 1, 4, w->fp) == 4 ? get_u32(d, w->big) : 0;
        } else if (depth > 0 && (cls == 2u || cls == 3u) && k == (cls == 2u ? 4 : 5) &&
                   fnlen > 0 && cells * (n / fnlen) > (uint64_t)(end - off) / 8) {
            return lv_fail(w->err, LV_ERR_INPUT, "%s: malformed MAT file: the struct at byte %ld "
                           "(%s) claims %llu values of %u fields, more than its %ld bytes hold",
                           w->path, off, in, (unsigned long long)cells, (unsigned)(n / fnlen),
                           end - off);
        }
        if (type == 14u && depth < 8) { /* miMATRIX: its elements */
            char what[96];
            snprintf(what, sizeof what, "a matrix at byte %ld", off);
            lv_status st = mat_v5_elements(w, off + 8, off + 8 + (long)n, depth + 1, what);
            if (st != LV_OK)
                return st;
        }
        off += size;
        k++;
    }
    return LV_OK;
}

static lv_status mat_check(const char *path, lv_err *err)
{
    mat_walk w = {fopen(path, "rb"), path, 0, 0, err};
    if (w.fp == NULL)
        return LV_OK; /* Mat_Open says it cannot open it */
    unsigned char h[128];
    lv_status st = LV_OK;
    if (fseek(w.fp, 0, SEEK_END) == 0 && (w.end = ftell(w.fp)) >= 0) {
        const int v5 = w.end >= 128 && fseek(w.fp, 0, SEEK_SET) == 0 &&
                       fread(h, 1, 128, w.fp) == 128 &&
                       ((h[126] == 'I' && h[127] == 'M') || (h[126] == 'M' && h[127] == 'I'));
        w.big = v5 && h[126] == 'M';
        const uint32_t version = v5 ? (w.big ? (uint32_t)h[124] << 8 | h[125]
                                             : (uint32_t)h[125] << 8 | h[124]) : 0;
        if (!v5)
            st = mat_v4_check(&w);
        else if (version == 0x0100) /* v5, v7 */
            st = mat_v5_elements(&w, 128, w.end, 0, "the file");
        else if (version != 0x0200) /* v7.3 (HDF5) aside, no other version exists; libmatio
                                       reads such a file as v4, whose headers are not checked
                                       against the v5 ones (fuzz: a 1.9 GB v4 name) */
            st = lv_fail(err, LV_ERR_INPUT, "%s: not a MAT file: a v5 header with version "
                         "0x%04x (MATLAB writes 0x0100, and 0x0200 for v7.3)", path,
                         (unsigned)version);
    }
    fclose(w.fp);
    return st;
}

static lv_status mat_load_quiet(const char *path, const char *var, const lv_table_opts *opts,
                                lv_table_spec_fn fn, void *user, lv_err *err)
{
    mat_src s = { path, NULL, 0, -1 };
    matvar_t *mv = NULL;
    mat_arr a = { 0 }, bx[LV_TABLE_MAX_DIMS];
    lv_status st;
    memset(bx, 0, sizeof bx);

    opts = opts_or_default(opts);
    if (strlen(var) > 60)
        return lv_fail(err, LV_ERR_INPUT, "%s: variable name '%.60s...' too long", path, var);
    if ((st = lv_file_size_check(path, LV_TABLE_FILE_MAX, "a table file", err)) != LV_OK ||
        (st = mat_check(path, err)) != LV_OK)
        return st;
    s.mat = Mat_Open(path, MAT_ACC_RDONLY);
    if (s.mat == NULL)
        return lv_fail(err, LV_ERR_IO, "%s: cannot open as a MAT file (v4, v5, v7, v7.3)", path);
    s.v73 = Mat_GetVersion(s.mat) == MAT_FT_MAT73;
    mv = Mat_VarRead(s.mat, var);
    if (mv != NULL && mv->class_type == MAT_C_STRUCT) {
        st = mat_struct(&s, var, mv, opts, fn, user, err);
        goto done;
    }
    int present = 0;
    if (mv != NULL) {
        char h5path[80];
        snprintf(h5path, sizeof h5path, "/%s", var);
        st = mat_numbers(&s, mv, h5path, var, &a, err);
    } else {
        st = mat_read_numbers(&s, var, &a, &present, err); /* v7.3: libmatio may miss it */
    }
    if (st == LV_OK && mv == NULL && !present)
        st = s.v73 ? h5_missing(&s, var, err) : mat_missing(s.mat, path, var, err);
    if (st != LV_OK)
        goto done;

    /* Breakpoint vectors var_x1 .. var_xN select the gridded layout. */
    size_t nd = 0;
    for (; nd < LV_TABLE_MAX_DIMS; nd++) {
        char name[80];
        int found = 0;
        snprintf(name, sizeof name, "%s_x%zu", var, nd + 1);
        if ((st = mat_read_numbers(&s, name, &bx[nd], &found, err)) != LV_OK)
            goto done;
        if (!found)
            break;
        if (big_dims(&bx[nd]) > 1) {
            st = lv_fail(err, LV_ERR_INPUT, "%s: breakpoints '%s' must be a vector", path, name);
            goto done;
        }
    }
    st = nd == 0 ? mat_combi(&s, var, &a, opts, fn, user, err)
                 : mat_grid(&s, var, &a, nd, bx, opts, fn, user, err);
done:
    for (size_t d = 0; d < LV_TABLE_MAX_DIMS; d++)
        mat_arr_free(&bx[d]);
    mat_arr_free(&a);
    Mat_VarFree(mv);
    Mat_Close(s.mat);
    if (s.h5 >= 0)
        H5Fclose(s.h5);
    return st;
}

/* HDF5 prints its error stack unless told not to, also for errors libmatio provokes while
 * it reads a v7.3 file: switched off for the calling thread (HDF5 keeps this per thread) for
 * the whole load, then restored. The library never prints. */
static lv_status mat_load(const char *path, const char *var, const lv_table_opts *opts,
                          lv_table_spec_fn fn, void *user, lv_err *err)
{
    H5E_auto2_t efunc = NULL;
    void *edata = NULL;
    H5Eget_auto2(H5E_DEFAULT, &efunc, &edata);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    const lv_status st = mat_load_quiet(path, var, opts, fn, user, err);
    H5Eset_auto2(H5E_DEFAULT, efunc, edata);
    return st;
}

/* ---- entry points ------------------------------------------------------------------------- */

/* lv_table_create with the file's name (and variable) before a failure's message. */
typedef struct make_ctx {
    const char *path, *var;
    lv_table **out;
} make_ctx;

static lv_status make_table(const lv_table_spec *spec, void *user, lv_err *err)
{
    const make_ctx *m = user;
    const lv_status st = lv_table_create(spec, m->out, err);
    if (st != LV_OK && m->var != NULL)
        lv_fail_prefix(err, st, "%s: variable '%s'", m->path, m->var);
    else if (st != LV_OK)
        lv_fail_prefix(err, st, "%s", m->path);
    return st;
}

lv_status lv_table_load_csv(const char *path, const lv_table_opts *opts, lv_table **out,
                            lv_err *err)
{
    if (out == NULL || path == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_table_load_csv: NULL argument");
    *out = NULL;
    make_ctx m = { path, NULL, out };
    return csv_load(path, opts, make_table, &m, err);
}

lv_status lv_table_load_mat(const char *path, const char *var, const lv_table_opts *opts,
                            lv_table **out, lv_err *err)
{
    if (out == NULL || path == NULL || var == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_table_load_mat: NULL argument");
    *out = NULL;
    make_ctx m = { path, var, out };
    return mat_load(path, var, opts, make_table, &m, err);
}

int lv_table_path_is_mat(const char *path)
{
    const size_t n = strlen(path);
    return n >= 4 && (strcmp(path + n - 4, ".mat") == 0 || strcmp(path + n - 4, ".MAT") == 0);
}

/* The file kind from its name, and `var` only with MAT files. */
static lv_status check_kind(const char *path, const char *var, int *mat, lv_err *err)
{
    *mat = lv_table_path_is_mat(path);
    if (*mat && var == NULL)
        return lv_fail(err, LV_ERR_INPUT, "%s: a MAT file needs the name of its variable",
                       path);
    if (!*mat && var != NULL)
        return lv_fail(err, LV_ERR_INPUT,
                       "%s: variable '%s' given, but the file is read as CSV (not '.mat')",
                       path, var);
    return LV_OK;
}

lv_status lv_table_load(const char *path, const char *var, const lv_table_opts *opts,
                        lv_table **out, lv_err *err)
{
    int mat = 0;
    const lv_status st = check_kind(path, var, &mat, err);
    if (st != LV_OK)
        return st;
    return mat ? lv_table_load_mat(path, var, opts, out, err)
               : lv_table_load_csv(path, opts, out, err);
}

lv_status lv_table_load_spec(const char *path, const char *var, const lv_table_opts *opts,
                             lv_table_spec_fn fn, void *user, lv_err *err)
{
    int mat = 0;
    const lv_status st = check_kind(path, var, &mat, err);
    if (st != LV_OK)
        return st;
    return mat ? mat_load(path, var, opts, fn, user, err) : csv_load(path, opts, fn, user, err);
}
