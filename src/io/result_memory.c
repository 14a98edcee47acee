/* result_memory.c - the in-memory result sink and the lv_result accessors.
 *
 * Keeps every row (time and all signals) and a copy of the signal names and units, so
 * that the result outlives the model and the sink. Parameters are not kept:
 * the caller already holds them.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/names.h"
#include "core/status.h"
#include "io/sink.h"

struct lv_result {
    size_t n_signals;
    char **names;   /* [n_signals], owned copies (one block with their text and units) */
    char **units;   /* [n_signals], in the same block */
    lv_rowbuf rows; /* row-major, rows.width == n_signals */
    int opened;
    int closed;
    char *failure; /* owned copy of the failure text, NULL when complete */
};

static lv_status mem_open(void *self, const lv_result_info *info, lv_err *err)
{
    lv_result *r = self;
    if (r->opened)
        return lv_fail(err, LV_ERR_INPUT, "memory result: opened twice");
    lv_status st = lv_sink_check_info(info, "memory result", err);
    if (st != LV_OK)
        return st;
    /* the names' and units' pointers and their text in one block (one allocation per
     * result); a NULL unit is kept as "" */
    size_t text = 0;
    for (size_t i = 0; i < info->n_signals; i++) {
        const char *unit = info->signals[i].unit;
        text += strlen(info->signals[i].name) + 1 + (unit ? strlen(unit) : 0) + 1;
    }
    r->names = malloc(2 * info->n_signals * sizeof *r->names + text);
    if (r->names == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "memory result: out of memory");
    r->units = r->names + info->n_signals;
    char *dst = (char *)(r->units + info->n_signals);
    for (size_t i = 0; i < info->n_signals; i++) {
        const size_t n = strlen(info->signals[i].name) + 1;
        memcpy(dst, info->signals[i].name, n);
        r->names[i] = dst;
        dst += n;
        const char *unit = info->signals[i].unit ? info->signals[i].unit : "";
        const size_t nu = strlen(unit) + 1;
        memcpy(dst, unit, nu);
        r->units[i] = dst;
        dst += nu;
    }
    r->n_signals = info->n_signals;
    r->rows.width = info->n_signals;
    r->opened = 1;
    return LV_OK;
}

static lv_status mem_row(void *self, const double *values, lv_err *err)
{
    lv_result *r = self;
    if (!r->opened || r->closed)
        return lv_fail(err, LV_ERR_INPUT, "memory result: row() %s",
                       r->closed ? "after close()" : "before open()");
    const size_t n = r->rows.rows;
    const double t_prev = n > 0 ? r->rows.v[(n - 1) * r->n_signals] : 0.0;
    lv_status st = lv_sink_check_row("memory result", n, values[0], t_prev, err);
    if (st != LV_OK)
        return st;
    return lv_rowbuf_push(&r->rows, values, err);
}

static lv_status mem_close(void *self, const char *failure, lv_err *err)
{
    lv_result *r = self;
    if (!r->opened || r->closed)
        return lv_fail(err, LV_ERR_INPUT, "memory result: close() %s",
                       r->closed ? "twice" : "before open()");
    r->closed = 1;
    if (failure != NULL) {
        const size_t n = strlen(failure) + 1;
        r->failure = malloc(n);
        if (r->failure == NULL)
            return lv_fail(err, LV_ERR_NOMEM, "memory result: out of memory");
        memcpy(r->failure, failure, n);
    }
    return LV_OK;
}

/* The sink borrows the result: destroying the sink leaves it to lv_result_free(). */
static void mem_destroy(void *self)
{
    (void)self;
}

static const lv_sink_vtbl mem_vtbl = {"memory", mem_open, mem_row, mem_close, mem_destroy};

lv_status lv_sink_memory_create(lv_result **result, lv_sink *out, lv_err *err)
{
    if (result == NULL || out == NULL)
        return lv_fail(err, LV_ERR_INPUT, "memory result: NULL output argument");
    *result = NULL;
    out->vt = NULL;
    out->self = NULL;
    lv_result *r = calloc(1, sizeof *r);
    if (r == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "memory result: out of memory");
    *result = r;
    out->vt = &mem_vtbl;
    out->self = r;
    return LV_OK;
}

void lv_result_free(lv_result *r)
{
    if (r == NULL)
        return;
    free(r->names); /* with the names' text */
    lv_rowbuf_free(&r->rows);
    free(r->failure);
    free(r);
}

size_t lv_result_rows(const lv_result *r)
{
    return r != NULL ? r->rows.rows : 0;
}

size_t lv_result_signals(const lv_result *r)
{
    return r != NULL ? r->n_signals : 0;
}

lv_status lv_result_column(const lv_result *r, const char *name, size_t *col, lv_err *err)
{
    if (r == NULL || name == NULL || col == NULL)
        return lv_fail(err, LV_ERR_INPUT, "memory result: NULL argument");
    for (size_t i = 0; i < r->n_signals; i++)
        if (strcmp(r->names[i], name) == 0) {
            *col = i;
            return LV_OK;
        }
    lv_suggest sg;
    lv_suggest_init(&sg, name);
    for (size_t i = 0; i < r->n_signals; i++)
        lv_suggest_add(&sg, r->names[i]);
    char hint[256];
    lv_suggest_text(&sg, hint, sizeof hint);
    return lv_fail(err, LV_ERR_NOTFOUND, "memory result: no signal '%s'%s", name, hint);
}

double lv_result_value(const lv_result *r, size_t row, size_t col)
{
    if (r == NULL || row >= r->rows.rows || col >= r->n_signals)
        return NAN;
    return r->rows.v[row * r->n_signals + col];
}

const char *lv_result_name(const lv_result *r, size_t col)
{
    return r != NULL && r->names != NULL && col < r->n_signals ? r->names[col] : NULL;
}

const char *lv_result_unit(const lv_result *r, size_t col)
{
    return r != NULL && r->names != NULL && col < r->n_signals ? r->units[col] : NULL;
}

const double *lv_result_data(const lv_result *r)
{
    return r != NULL && r->rows.rows > 0 ? r->rows.v : NULL;
}

const char *lv_result_failure(const lv_result *r)
{
    return r != NULL && r->closed ? r->failure : NULL;
}

int lv_result_closed(const lv_result *r)
{
    return r != NULL && r->closed;
}
