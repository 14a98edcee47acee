/* atomic.h - internal: a file written under a temporary name, "<path>.tmp", and renamed to its
 * final name when complete, so that no reader ever finds half a file under the final name.
 * Every lvsim writer goes through it: the result sinks (docs/result-files.md), summary.json and
 * the body trajectories, the exports (docs/exports.md), the figures and the report
 * (docs/visualization.md). Not exported. */
#ifndef LV_IO_ATOMIC_H
#define LV_IO_ATOMIC_H

#include <stdio.h>

#include "lvsim/lv_status.h"

#define LV_ATOMIC_PATH_MAX 4096 /* bytes with the NUL: Linux's PATH_MAX */

/* One file being written; lives where the caller puts it (no allocation). A zeroed struct is
 * a valid "nothing" for lv_atomic_abort() and lv_atomic_release(). */
typedef struct lv_atomic {
    char path[LV_ATOMIC_PATH_MAX];    /* the final name, as given */
    char tmp[LV_ATOMIC_PATH_MAX + 40]; /* path + ".tmp" (or ".tmp.<pid>.<k>"): what is written */
    FILE *fp;  /* stream on tmp after lv_atomic_open(); NULL when a library writes tmp by name */
    int keep;  /* set by the caller: a failed commit leaves tmp in place (the result sinks keep
                * the rows written so far); 0: a failed commit removes it */
} lv_atomic;

/* Fills the names only, opens nothing: for writers that take a file name (libmatio, PLplot).
 * tmp is "<path>.tmp", or "<path>.tmp.<pid>.<k>" when a file of that name exists (never
 * replaced). Errors: LV_ERR_INPUT (empty or too long a path). */
lv_status lv_atomic_init(lv_atomic *a, const char *path, lv_err *err);

/* lv_atomic_init (path NULL: the names an earlier lv_atomic_init gave), then creates tmp for
 * writing, exclusively (O_EXCL: an existing file is never truncated; in a hard-linked replica
 * of a results folder that would change the original): a->fp. Errors: LV_ERR_INPUT as above; LV_ERR_IO "<tmp>: cannot create: <reason>".
 * On failure nothing is left open. */
lv_status lv_atomic_open(lv_atomic *a, const char *path, lv_err *err);

/* Creates tmp empty and closes it (after lv_atomic_init): an unwritable folder fails here,
 * before a library that writes tmp by name gets to it. Errors: LV_ERR_IO as lv_atomic_open. */
lv_status lv_atomic_reserve(lv_atomic *a, lv_err *err);

/* Completes the file: flushes and closes a->fp when open, checks that every write reached the
 * file, renames tmp to a->path (lv_atomic_commit) or to `target` (lv_atomic_commit_as: the
 * sinks' failed name), replacing a file of that name. a->fp is NULL afterwards; the names stay.
 * On failure tmp is removed unless a->keep. Errors: LV_ERR_IO naming tmp and the system's
 * reason: "<tmp>: cannot write: ...", "<tmp>: cannot close: ...",
 * "<tmp>: cannot rename to '<target>': ...". */
lv_status lv_atomic_commit(lv_atomic *a, lv_err *err);
lv_status lv_atomic_commit_as(lv_atomic *a, const char *target, lv_err *err);

/* Gives up: closes a->fp when open and removes tmp (whatever a->keep says). */
void lv_atomic_abort(lv_atomic *a);

/* Closes a->fp when open and leaves tmp as it is (a sink destroyed without close()). */
void lv_atomic_release(lv_atomic *a);

#endif
