/* plot_csv.c - reads lvsim's CSV result files back (docs/result-files.md): a header of
 * `name [unit]` fields, then one row of numbers per output instant. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "post/plot.h"

void lv_plot_csv_free(lv_csv *c)
{
    if (c == NULL)
        return;
    for (size_t i = 0; i < c->n_cols; i++) {
        free(c->names[i]);
        free(c->units[i]);
    }
    free(c->names);
    free(c->units);
    free(c->v);
    free(c);
}

long lv_plot_csv_col(const lv_csv *c, const char *name)
{
    for (size_t i = 0; c != NULL && i < c->n_cols; i++)
        if (strcmp(c->names[i], name) == 0)
            return (long)i;
    return -1;
}

static char *read_all(const char *path, size_t *len, lv_err *err)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        lv_fail(err, LV_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
        return NULL;
    }
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap + 1);
    while (buf != NULL) {
        n += fread(buf + n, 1, cap - n, f);
        if (n < cap)
            break;
        char *bigger = realloc(buf, 2 * cap + 1);
        if (bigger == NULL) {
            free(buf);
            buf = NULL;
            break;
        }
        buf = bigger;
        cap *= 2;
    }
    int bad = ferror(f);
    fclose(f);
    if (buf == NULL) {
        lv_fail(err, LV_ERR_NOMEM, "out of memory reading '%s'", path);
        return NULL;
    }
    if (bad) {
        free(buf);
        lv_fail(err, LV_ERR_IO, "cannot read '%s'", path);
        return NULL;
    }
    buf[n] = '\0';
    *len = n;
    return buf;
}

static char *dup_range(const char *a, const char *b)
{
    while (a < b && (*a == ' ' || *a == '\t'))
        a++;
    while (b > a && (b[-1] == ' ' || b[-1] == '\t' || b[-1] == '\r'))
        b--;
    char *s = malloc((size_t)(b - a) + 1);
    if (s != NULL) {
        memcpy(s, a, (size_t)(b - a));
        s[b - a] = '\0';
    }
    return s;
}

/* One header field "name [unit]" into its name and unit. */
static int parse_header_field(const char *a, const char *b, char **name, char **unit)
{
    const char *open = NULL;
    for (const char *p = a; p < b; p++)
        if (*p == '[')
            open = p;
    const char *close = open ? memchr(open, ']', (size_t)(b - open)) : NULL;
    if (open != NULL && close != NULL) {
        *name = dup_range(a, open);
        *unit = dup_range(open + 1, close);
    } else {
        *name = dup_range(a, b);
        *unit = dup_range(b, b);
    }
    return *name != NULL && *unit != NULL;
}

static size_t count_fields(const char *line, const char *end)
{
    size_t n = 1;
    for (const char *p = line; p < end; p++)
        n += *p == ',';
    return n;
}

lv_status lv_plot_csv_read(const char *path, lv_csv **out, lv_err *err)
{
    *out = NULL;
    size_t len = 0;
    char *text = read_all(path, &len, err);
    if (text == NULL)
        return err ? err->code : LV_ERR_IO;
    lv_status st = LV_OK;
    lv_csv *c = calloc(1, sizeof *c);
    if (c == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto fail;
    }
    char *line = text, *end = strchr(line, '\n');
    if (end == NULL)
        end = text + len;
    if (end == line) {
        st = lv_fail(err, LV_ERR_INPUT, "%s:1: no header line", path);
        goto fail;
    }
    size_t nc = count_fields(line, end);
    c->names = calloc(nc, sizeof *c->names);
    c->units = calloc(nc, sizeof *c->units);
    if (c->names == NULL || c->units == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto fail;
    }
    for (const char *a = line; c->n_cols < nc;) {
        const char *b = memchr(a, ',', (size_t)(end - a));
        b = b ? b : end;
        size_t i = c->n_cols++;
        if (!parse_header_field(a, b, &c->names[i], &c->units[i])) {
            st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
            goto fail;
        }
        a = b + 1;
    }
    /* Rows: at most one per remaining line. */
    size_t max_rows = 0;
    for (const char *p = end; p < text + len; p++)
        max_rows += *p == '\n';
    c->v = malloc((max_rows + 1) * nc * sizeof *c->v);
    if (c->v == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto fail;
    }
    int lineno = 1;
    for (line = *end ? end + 1 : end; line < text + len; line = *end ? end + 1 : end) {
        lineno++;
        end = strchr(line, '\n');
        if (end == NULL)
            end = text + len;
        if (line == end || line[0] == '#' || (line[0] == '\r' && end == line + 1))
            continue;
        size_t nf = count_fields(line, end);
        if (nf != nc) {
            st = lv_fail(err, LV_ERR_INPUT, "%s:%d: %zu fields, the header has %zu", path,
                         lineno, nf, nc);
            goto fail;
        }
        double *row = c->v + c->n_rows * nc;
        const char *a = line;
        for (size_t i = 0; i < nc; i++) {
            char *stop = NULL;
            errno = 0;
            double x = strtod(a, &stop);
            const char *b = memchr(a, ',', (size_t)(end - a));
            b = b ? b : end;
            /* A number must fill its field (trailing blanks allowed); else it is text. */
            const char *q = stop;
            while (q != NULL && q < b && (*q == ' ' || *q == '\r'))
                q++;
            row[i] = (stop != a && q == b) ? x : NAN;
            a = b + 1;
        }
        c->n_rows++;
    }
    free(text);
    *out = c;
    return LV_OK;
fail:
    free(text);
    lv_plot_csv_free(c);
    return st;
}
