/* sink.c - what all result sinks share: lv_sink_destroy(), the failed-file
 * name, the temporary-file protocol (write "<path>.tmp", rename when closed: io/atomic.c),
 * checks of the result description and rows. See docs/result-files.md.
 */

#include "io/sink.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/names.h"
#include "core/status.h"

void lv_sink_destroy(lv_sink *sink)
{
    if (sink == NULL)
        return;
    if (sink->vt != NULL && sink->vt->destroy != NULL)
        sink->vt->destroy(sink->self);
    sink->vt = NULL;
    sink->self = NULL;
}

lv_status lv_result_failed_path(const char *path, char *buf, size_t cap, lv_err *err)
{
    static const char tag[] = ".failed";
    if (path == NULL || path[0] == '\0')
        return lv_fail(err, LV_ERR_INPUT, "result file: empty path");

    /* The extension is the last '.' of the last path component, unless that
     * dot starts the component (".hidden" has no extension). */
    const char *base = path;
    for (const char *c = path; *c != '\0'; c++)
        if (*c == '/' || *c == '\\')
            base = c + 1;
    const char *dot = strrchr(base, '.');
    if (dot == base)
        dot = NULL;
    const size_t len = strlen(path);
    const size_t stem_len = dot != NULL ? (size_t)(dot - path) : len;

    const size_t need = len + sizeof tag; /* + terminating NUL */
    if (buf == NULL || need > cap)
        return lv_fail(err, LV_ERR_INPUT, "%s: failed-result name needs %zu bytes, %zu given",
                       path, need, cap);
    memcpy(buf, path, stem_len);
    memcpy(buf + stem_len, tag, sizeof tag - 1);
    memcpy(buf + stem_len + sizeof tag - 1, path + stem_len, len - stem_len + 1);
    return LV_OK;
}

lv_status lv_sink_paths_init(lv_sink_paths *p, const char *path, lv_err *err)
{
    memset(p, 0, sizeof *p);
    if (path == NULL || path[0] == '\0')
        return lv_fail(err, LV_ERR_INPUT, "result file: empty path");
    lv_status st = lv_atomic_init(&p->file, path, err);
    if (st != LV_OK)
        return st;
    p->file.keep = 1; /* a failed commit leaves the rows written so far */
    const size_t failed_cap = strlen(path) + sizeof ".failed";
    p->failed_path = malloc(failed_cap);
    if (p->failed_path == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", path);
    st = lv_result_failed_path(path, p->failed_path, failed_cap, err);
    if (st != LV_OK)
        lv_sink_paths_free(p);
    return st;
}

void lv_sink_paths_free(lv_sink_paths *p)
{
    if (p == NULL)
        return;
    lv_atomic_release(&p->file);
    free(p->failed_path);
    p->failed_path = NULL;
}

lv_status lv_sink_paths_commit(lv_sink_paths *p, const char *failure, lv_err *err)
{
    return lv_atomic_commit_as(&p->file, failure == NULL ? p->file.path : p->failed_path, err);
}

lv_status lv_sink_check_info(const lv_result_info *info, const char *path, lv_err *err)
{
    if (info == NULL)
        return lv_fail(err, LV_ERR_INPUT, "%s: open() without result information", path);
    if (info->n_signals == 0 || info->signals == NULL)
        return lv_fail(err, LV_ERR_INPUT, "%s: a result needs at least the signal 'time'", path);
    if (info->n_params > 0 && (info->params == NULL || info->param_values == NULL))
        return lv_fail(err, LV_ERR_INPUT, "%s: %zu parameters without names or values", path,
                       info->n_params);
    if (info->signals[0].name == NULL || strcmp(info->signals[0].name, "time") != 0)
        return lv_fail(err, LV_ERR_INPUT, "%s: signal 0 is '%s', expected 'time'", path,
                       info->signals[0].name != NULL ? info->signals[0].name : "(null)");
    if (info->n_signals > SIZE_MAX / 16 || info->n_params > SIZE_MAX / 16)
        return lv_fail(err, LV_ERR_INPUT, "%s: too many variables", path);

    const size_t n = info->n_signals + info->n_params;
    const char **names = malloc(n * sizeof *names);
    if (names == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", path);
    lv_status st = LV_OK;
    for (size_t i = 0; i < n; i++) {
        const int is_sig = i < info->n_signals;
        const size_t k = is_sig ? i : i - info->n_signals;
        const char *name = is_sig ? info->signals[k].name : info->params[k].name;
        if (name == NULL || name[0] == '\0') {
            st = lv_fail(err, LV_ERR_INPUT, "%s: %s %zu has no name", path,
                         is_sig ? "signal" : "parameter", k);
            goto fail;
        }
        names[i] = name;
    }
    const size_t dup = lv_names_duplicate(names, n); /* hashed: O(n) */
    if (dup < n)
        st = lv_fail(err, LV_ERR_INPUT, "%s: variable name '%s' appears twice", path, names[dup]);
fail:
    free(names);
    return st;
}

lv_status lv_sink_check_row(const char *path, size_t row, double t, double t_prev, lv_err *err)
{
    if (!isfinite(t))
        return lv_fail(err, LV_ERR_INPUT, "%s: row %zu: time is %g", path, row, t);
    if (row > 0 && t < t_prev)
        return lv_fail(err, LV_ERR_INPUT, "%s: row %zu: time %.17g before previous row's %.17g",
                       path, row, t, t_prev);
    return LV_OK;
}

char *lv_sink_describe(const char *description, const char *unit)
{
    const char *d = description != NULL ? description : "";
    /* dimensionless: "1", shown "[1]" (lv_units.h), also for a model that wrote "" */
    const char *u = unit != NULL && unit[0] != '\0' ? unit : "1";
    const size_t dl = strlen(d), ul = strlen(u);
    char *s = malloc(dl + ul + 4); /* ' ' '[' ']' NUL */
    if (s == NULL)
        return NULL;
    if (ul == 0)
        memcpy(s, d, dl + 1);
    else if (dl == 0)
        snprintf(s, ul + 3, "[%s]", u);
    else
        snprintf(s, dl + ul + 4, "%s [%s]", d, u);
    return s;
}

lv_status lv_rowbuf_push(lv_rowbuf *b, const double *row, lv_err *err)
{
    if (b->rows == b->cap_rows) {
        const size_t cap = b->cap_rows < 64 ? 64 : b->cap_rows * 2;
        if (b->width == 0 || cap > SIZE_MAX / sizeof(double) / b->width)
            return lv_fail(err, LV_ERR_NOMEM, "result buffer: %zu rows of %zu values", cap,
                           b->width);
        double *v = realloc(b->v, cap * b->width * sizeof(double));
        if (v == NULL)
            return lv_fail(err, LV_ERR_NOMEM, "result buffer: out of memory at row %zu",
                           b->rows);
        b->v = v;
        b->cap_rows = cap;
    }
    memcpy(b->v + b->rows * b->width, row, b->width * sizeof(double));
    b->rows++;
    return LV_OK;
}

void lv_rowbuf_free(lv_rowbuf *b)
{
    if (b == NULL)
        return;
    free(b->v);
    b->v = NULL;
    b->rows = b->cap_rows = 0;
}
