/* result_csv.c - CSV result sink: one header line "name [unit]", one line per row.
 *
 * Fields follow RFC 4180 (a field with a comma, quote or line break is quoted,
 * quotes doubled); values are printed as the shortest text that reads back to the
 * same double (io/numfmt.h: %.17g's layout, fewer digits). Rows are streamed to
 * "<path>.tmp": each row is formatted into a line buffer made at open() and written
 * with one fwrite() into a large stdio buffer; nothing is allocated per row. Parameters
 * are not in the CSV (they are in the .mat file). See docs/result-files.md.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "io/numfmt.h"
#include "io/sink.h"

#define CSV_STREAM_BUFFER (256u * 1024u) /* bytes of stdio buffer: few write(2) calls */

typedef struct csv_sink {
    lv_sink_paths paths; /* paths.file.fp: the stream, open between open() and close() */
    size_t n_signals;
    size_t rows;
    double t_prev;   /* s */
    int state;       /* 0 created, 1 open, 2 closed */
    char *line;      /* [n_signals * LV_NUMFMT_MAX + 1]: one row's text */
    char *stream_buf; /* [CSV_STREAM_BUFFER]: the stream's buffer, freed after it is closed */
} csv_sink;

static lv_status io_error(const csv_sink *s, const char *what, int e, lv_err *err)
{
    char why[128];
    return lv_fail(err, LV_ERR_IO, "%s: %s: %s", s->paths.file.tmp, what,
                   lv_strerror(e, why, sizeof why));
}

/* Writes `text` as one CSV field, quoted when it holds a comma, quote or line break. */
static int put_field(FILE *fp, const char *text)
{
    if (strpbrk(text, ",\"\r\n") == NULL)
        return fputs(text, fp) < 0 ? -1 : 0;
    if (fputc('"', fp) == EOF)
        return -1;
    for (const char *c = text; *c != '\0'; c++) {
        if (*c == '"' && fputc('"', fp) == EOF)
            return -1;
        if (fputc(*c, fp) == EOF)
            return -1;
    }
    return fputc('"', fp) == EOF ? -1 : 0;
}

static lv_status csv_open(void *self, const lv_result_info *info, lv_err *err)
{
    csv_sink *s = self;
    if (s->state != 0)
        return lv_fail(err, LV_ERR_INPUT, "%s: opened twice", s->paths.file.path);
    lv_status st = lv_sink_check_info(info, s->paths.file.path, err);
    if (st != LV_OK)
        return st;

    s->line = malloc(info->n_signals * LV_NUMFMT_MAX + 1);
    s->stream_buf = malloc(CSV_STREAM_BUFFER);
    if (s->line == NULL || s->stream_buf == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", s->paths.file.path);
    st = lv_atomic_open(&s->paths.file, NULL, err);
    if (st != LV_OK)
        return st;
    FILE *fp = s->paths.file.fp;
    setvbuf(fp, s->stream_buf, _IOFBF, CSV_STREAM_BUFFER);
    for (size_t i = 0; i < info->n_signals; i++) {
        const lv_var *v = &info->signals[i];
        /* "name [unit]": the unit part of lv_sink_describe() with the name as text */
        char *head = lv_sink_describe(v->name, i == 0 && (v->unit == NULL || v->unit[0] == '\0')
                                                   ? "s"
                                                   : v->unit);
        if (head == NULL) {
            st = lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", s->paths.file.path);
            goto fail;
        }
        errno = 0;
        const int bad = (i > 0 && fputc(',', fp) == EOF) || put_field(fp, head) != 0;
        free(head);
        if (bad) {
            st = io_error(s, "cannot write", errno, err);
            goto fail;
        }
    }
    errno = 0;
    if (fputc('\n', fp) == EOF) {
        st = io_error(s, "cannot write", errno, err);
        goto fail;
    }
    s->n_signals = info->n_signals;
    s->state = 1;
    return LV_OK;
fail:
    lv_atomic_abort(&s->paths.file);
    return st;
}

static lv_status csv_row(void *self, const double *values, lv_err *err)
{
    csv_sink *s = self;
    if (s->state != 1)
        return lv_fail(err, LV_ERR_INPUT, "%s: row() %s", s->paths.file.path,
                       s->state == 0 ? "before open()" : "after close()");
    lv_status st = lv_sink_check_row(s->paths.file.path, s->rows, values[0], s->t_prev, err);
    if (st != LV_OK)
        return st;
    char *p = s->line;
    for (size_t i = 0; i < s->n_signals; i++) {
        p += lv_numfmt_double(values[i], p);
        *p++ = ',';
    }
    p[-1] = '\n';
    const size_t len = (size_t)(p - s->line);
    errno = 0;
    if (fwrite(s->line, 1, len, s->paths.file.fp) != len)
        return io_error(s, "cannot write", errno, err);
    s->t_prev = values[0];
    s->rows++;
    return LV_OK;
}

static lv_status csv_close(void *self, const char *failure, lv_err *err)
{
    csv_sink *s = self;
    if (s->state != 1)
        return lv_fail(err, LV_ERR_INPUT, "%s: close() %s", s->paths.file.path,
                       s->state == 0 ? "before open()" : "twice");
    s->state = 2;
    errno = 0;
    if (failure != NULL) {
        /* A comment line, on one line whatever the reason's text. */
        FILE *fp = s->paths.file.fp;
        int bad = fputs("# run failed: ", fp) < 0;
        for (const char *c = failure; !bad && *c != '\0'; c++)
            bad = fputc(*c == '\n' || *c == '\r' ? ' ' : *c, fp) == EOF;
        if (!bad && failure[0] == '\0')
            bad = fputs("(no reason given)", fp) < 0;
        if (!bad)
            bad = fputc('\n', fp) == EOF;
        if (bad) {
            lv_status st = io_error(s, "cannot write", errno, err);
            lv_atomic_release(&s->paths.file); /* the .tmp file stays, with the rows written */
            return st;
        }
    }
    /* Flush, close, check, rename: a full disk shows here at the latest. */
    return lv_sink_paths_commit(&s->paths, failure, err);
}

/* Closes the stream of a sink destroyed while open; its .tmp file stays. */
static void csv_destroy(void *self)
{
    csv_sink *s = self;
    if (s == NULL)
        return;
    lv_sink_paths_free(&s->paths); /* closes the stream */
    free(s->stream_buf);
    free(s->line);
    free(s);
}

static const lv_sink_vtbl csv_vtbl = {"csv", csv_open, csv_row, csv_close, csv_destroy};

lv_status lv_sink_csv_create(const char *path, lv_sink *out, lv_err *err)
{
    if (out == NULL)
        return lv_fail(err, LV_ERR_INPUT, "csv result: NULL output argument");
    out->vt = NULL;
    out->self = NULL;
    csv_sink *s = calloc(1, sizeof *s);
    if (s == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", path != NULL ? path : "csv");
    lv_status st = lv_sink_paths_init(&s->paths, path, err);
    if (st != LV_OK) {
        free(s);
        return st;
    }
    out->vt = &csv_vtbl;
    out->self = s;
    return LV_OK;
}

/* docs/result-files.md */
const lv_result_format lv_result_format_csv = {
    "csv", ".csv", "CSV: a \"name [unit]\" header line, one line per output row",
    lv_sink_csv_create};
