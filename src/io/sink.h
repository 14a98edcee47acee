/* sink.h - helpers shared by the result sinks (not exported).
 *
 * Checks of lv_result_info, the final/failed file names and the final rename
 * (through io/atomic.h), and the "description [unit]" text of a variable (Dymola's way of
 * carrying units in dsres descriptions). See docs/result-files.md.
 */
#ifndef LV_IO_SINK_H
#define LV_IO_SINK_H

#include <stddef.h>

#include "io/atomic.h"
#include "lvsim/lv_io.h"

/* The names of one result file: the final one and its temporary "<path>.tmp" (io/atomic.h:
 * file.path, file.tmp, and for a streamed sink file.fp), and the failed one. The sinks keep
 * their .tmp file when a commit fails (file.keep, docs/result-files.md). */
typedef struct lv_sink_paths {
    lv_atomic file;    /* file.path "dir/stem.ext" as given; file.tmp "dir/stem.ext.tmp" */
    char *failed_path; /* "dir/stem.failed.ext": kept when the run failed (owned, malloc) */
} lv_sink_paths;

/* Fills `p` from `path` (non-empty). On failure `p` holds nothing to free. */
lv_status lv_sink_paths_init(lv_sink_paths *p, const char *path, lv_err *err);
void lv_sink_paths_free(lv_sink_paths *p);

/* Completes the temporary file (lv_atomic_commit_as: closes file.fp when open, checks the
 * writes) and renames it to the final name (failure == NULL) or to the failed name. Overwrites
 * a file of the target name; never touches the other name. LV_ERR_IO names the temporary
 * file, the target and the system's reason; the temporary file then stays. */
lv_status lv_sink_paths_commit(lv_sink_paths *p, const char *failure, lv_err *err);

/* Checks what every sink relies on: at least one signal, signals[0] named
 * "time", every name non-empty, names of signals and parameters unique, and
 * arrays present when their count is non-zero. `path` names the sink in
 * messages. */
lv_status lv_sink_check_info(const lv_result_info *info, const char *path, lv_err *err);

/* Checks one row against the previous time: finite, non-decreasing time.
 * `row` is the 0-based index of this row (for the message). */
lv_status lv_sink_check_row(const char *path, size_t row, double t, double t_prev, lv_err *err);

/* "description [unit]", or "[unit]" (no description), into a new malloc'd string; a
 * dimensionless unit ("1", or "" / NULL) is "[1]" (lv_units.h); NULL when out of memory. */
char *lv_sink_describe(const char *description, const char *unit);

/* A result-file format a run writes per phase (lv_sim_settings.result_formats): one file
 * src/io/result_<name>.c defines its sink and this descriptor, one line in the table of
 * io/result_formats.c registers it. Its flag is 1u << (its position in the table): the order of
 * the table is the public flags' (LV_RESULT_MAT, LV_RESULT_CSV; lv_sim.h). */
typedef struct lv_result_format {
    const char *name;        /* "mat": the word of --format/--outputs and of summary.json's
                                "files"; at most 7 characters */
    const char *ext;         /* ".mat": the file is "<stem><ext>", "<stem>.failed<ext>" */
    const char *description; /* one line, for `lvsim formats`, the docs and Python */
    lv_status (*create)(const char *path, lv_sink *out, lv_err *err); /* the sink at `path` */
} lv_result_format;

extern const lv_result_format lv_result_format_mat; /* io/result_mat.c */
extern const lv_result_format lv_result_format_csv; /* io/result_csv.c */

/* The registered formats, NULL-terminated (io/result_formats.c). */
extern const lv_result_format *const lv_result_formats[];

/* Number of registered formats and the OR of their flags. */
size_t lv_result_format_count(void);
unsigned lv_result_format_mask(void);

/* Growable array of doubles, one row of `width` values at a time. */
typedef struct lv_rowbuf {
    double *v;
    size_t width, rows, cap_rows;
} lv_rowbuf;

lv_status lv_rowbuf_push(lv_rowbuf *b, const double *row, lv_err *err);
void lv_rowbuf_free(lv_rowbuf *b);

#endif
