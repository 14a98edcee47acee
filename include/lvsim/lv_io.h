/* lv_io.h - result sinks: the one open/row/close interface every result writer shares.
 *
 * lv_simulate() streams rows to sinks and never knows the format. A row holds
 * every time-varying signal of the run: signals[0] is "time", then the states,
 * their derivatives and the outputs. Parameters are constant and passed once
 * at open().
 *
 * Files are written under a temporary name ("<path>.tmp") and renamed when
 * complete. A run that fails still closes its sinks with the failure text: the
 * rows up to the failure are kept, in a complete file whose name marks it
 * failed: "<stem>.failed.<ext>" (e.g. phase_3.failed.mat), never under the
 * final name. See docs/result-files.md.
 */
#ifndef LVSIM_LV_IO_H
#define LVSIM_LV_IO_H

#include <stddef.h>

#include "lvsim/lv_model.h"
#include "lvsim/lv_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What a sink learns at open(). All pointers are borrowed for the sink's open..close. */
typedef struct lv_result_info {
    const char *model_name;
    const char *model_description;
    size_t n_params;
    const lv_var *params;        /* name, unit, description of each parameter */
    const double *param_values;  /* [n_params] values used in the run */
    size_t n_signals;
    const lv_var *signals;       /* [n_signals]; signals[0] is time */
    const lv_var_kind *signal_kinds; /* [n_signals]; kind of signals[1..] (time: LV_VAR_OUTPUT) */
} lv_result_info;

typedef struct lv_sink_vtbl {
    const char *format; /* "mat", "csv", "memory" */
    lv_status (*open)(void *self, const lv_result_info *info, lv_err *err);
    /* values[n_signals], values[0] = time. Rows come in non-decreasing time;
     * an event instant appears twice (before and after the event). */
    lv_status (*row)(void *self, const double *values, lv_err *err);
    /* failure == NULL: the run completed. Otherwise a one-line reason; keep the
     * rows and mark the result failed. */
    lv_status (*close)(void *self, const char *failure, lv_err *err);
    void (*destroy)(void *self);
} lv_sink_vtbl;

typedef struct lv_sink {
    const lv_sink_vtbl *vt;
    void *self;
} lv_sink;

/* Releases the sink's memory; closes nothing (a sink never opened or already
 * closed). Accepts a zeroed sink. */
LV_API void lv_sink_destroy(lv_sink *sink);

/* Dymola/OpenModelica "dsres" MAT v4 file at `path` (should end in .mat). */
LV_API lv_status lv_sink_mat_create(const char *path, lv_sink *out, lv_err *err);

/* CSV with a "name [unit]" header at `path` (should end in .csv). */
LV_API lv_status lv_sink_csv_create(const char *path, lv_sink *out, lv_err *err);

/* The result-file formats a run writes per phase, by position i = 0, 1, ... (its flag in
 * lv_sim_settings.result_formats and lv_run_options.result_formats is 1u << i: LV_RESULT_MAT
 * is "mat", LV_RESULT_CSV "csv"): its name ("mat": the word of `--format`, `--outputs` and of
 * summary.json's "files"), and, when the pointers are not NULL, its extension (".mat") and a
 * one-line description. NULL when i is past the last format. Strings are static. */
LV_API const char *lv_result_format_info(size_t i, const char **ext, const char **description);

/* In-memory result (for post-processing and tests). */
typedef struct lv_result lv_result;
LV_API lv_status lv_sink_memory_create(lv_result **result, lv_sink *out, lv_err *err);
LV_API void lv_result_free(lv_result *r);
LV_API size_t lv_result_rows(const lv_result *r);
LV_API size_t lv_result_signals(const lv_result *r);
/* Column index of a signal by name ("time", "h", "der(h)", ...) or LV_ERR_NOTFOUND. */
LV_API lv_status lv_result_column(const lv_result *r, const char *name, size_t *col, lv_err *err);
LV_API double lv_result_value(const lv_result *r, size_t row, size_t col);
/* Signal col's name ("time", "h", "der(h)") and unit (SI, "1" dimensionless), owned by the
 * result; NULL when col >= lv_result_signals() (or the result was never opened). */
LV_API const char *lv_result_name(const lv_result *r, size_t col);
LV_API const char *lv_result_unit(const lv_result *r, size_t col);
/* Every value, row-major: [lv_result_rows() * lv_result_signals()], value (row, col) at
 * row * signals + col; NULL when there is no row. Owned by the result and valid until its
 * next row or lv_result_free() (for copying out in one go, as the Python package does). */
LV_API const double *lv_result_data(const lv_result *r);
/* NULL until closed; then NULL when complete or the failure text. */
LV_API const char *lv_result_failure(const lv_result *r);
LV_API int lv_result_closed(const lv_result *r);

/* The name a failed result is kept under: "dir/stem.ext" -> "dir/stem.failed.ext".
 * Writes at most `cap` bytes; returns LV_ERR_INPUT when it does not fit. */
LV_API lv_status lv_result_failed_path(const char *path, char *buf, size_t cap, lv_err *err);

#ifdef __cplusplus
}
#endif
#endif
