/* sink.h - helpers shared by the result sinks (not exported).
 *
 * Checks of lv_result_info, the temporary/final/failed file names, the final
 * rename, and the "description [unit]" text of a variable (Dymola's way of
 * carrying units in dsres descriptions). See docs/result-files.md.
 */
#ifndef LV_IO_SINK_H
#define LV_IO_SINK_H

#include <stddef.h>

#include "lvsim/lv_io.h"

/* The three names of one result file. Strings are owned (malloc). */
typedef struct lv_sink_paths {
    char *final_path;  /* "dir/stem.ext" as given */
    char *tmp_path;    /* "dir/stem.ext.tmp": written while the run goes on */
    char *failed_path; /* "dir/stem.failed.ext": kept when the run failed */
} lv_sink_paths;

/* Fills `p` from `path` (non-empty). On failure `p` holds nothing to free. */
lv_status lv_sink_paths_init(lv_sink_paths *p, const char *path, lv_err *err);
void lv_sink_paths_free(lv_sink_paths *p);

/* Renames the complete temporary file to the final name (failure == NULL) or
 * to the failed name. Overwrites a file of the target name; never touches the
 * other name. LV_ERR_IO names both paths and the system's reason. */
lv_status lv_sink_paths_commit(const lv_sink_paths *p, const char *failure, lv_err *err);

/* Checks what every sink relies on: at least one signal, signals[0] named
 * "time", every name non-empty, names of signals and parameters unique, and
 * arrays present when their count is non-zero. `path` names the sink in
 * messages. */
lv_status lv_sink_check_info(const lv_result_info *info, const char *path, lv_err *err);

/* Checks one row against the previous time: finite, non-decreasing time.
 * `row` is the 0-based index of this row (for the message). */
lv_status lv_sink_check_row(const char *path, size_t row, double t, double t_prev, lv_err *err);

/* "description [unit]", "description" (dimensionless), "[unit]" (no
 * description) or "" into a new malloc'd string; NULL when out of memory. */
char *lv_sink_describe(const char *description, const char *unit);

/* The system's text for errno value `e` (thread-safe). */
const char *lv_sink_strerror(int e, char *buf, size_t cap);

/* Growable array of doubles, one row of `width` values at a time. */
typedef struct lv_rowbuf {
    double *v;
    size_t width, rows, cap_rows;
} lv_rowbuf;

lv_status lv_rowbuf_push(lv_rowbuf *b, const double *row, lv_err *err);
void lv_rowbuf_free(lv_rowbuf *b);

#endif
