/* readfile.h - a whole file into memory, bounded (not exported): what lvsim reads whole (a
 * mission, a CSV table, a gravity coefficient file, a results folder's summary.json) is refused
 * beyond a size fixed per kind before anything is allocated, and must be a regular file (a
 * device or a FIFO could block the reader forever, a sparse file of gigabytes would be read
 * byte by byte: issue 22). The limits are documented in docs/mission-format.md and
 * docs/tables.md.
 */
#ifndef LV_IO_READFILE_H
#define LV_IO_READFILE_H

#include <stddef.h>

#include "core/status.h"

#define LV_MISSION_FILE_MAX ((size_t)16 << 20) /* 16 MiB: a mission file is written by hand */
#define LV_TABLE_FILE_MAX ((size_t)1 << 30)    /* 1 GiB: a table file (CSV or MAT) */
#define LV_GRAVITY_FILE_MAX ((size_t)1 << 30)  /* 1 GiB: EGM2008 to degree 2190 is ~0.3 GB */
#define LV_SUMMARY_FILE_MAX ((size_t)1 << 28)  /* 256 MiB: a results folder's summary.json */

/* Reads `path` whole into *out (malloc'ed, NUL-terminated; *len bytes without the NUL).
 * `kind` names the file in messages after "cannot open" ("the mission file"; NULL: nothing).
 * Errors: LV_ERR_IO "PATH: cannot open[ KIND]: <strerror>" or "PATH: cannot read: ...";
 * LV_ERR_INPUT "PATH: not a regular file" or "PATH: 3.2 GB; at most 1 GiB (KIND)" for a file
 * larger than `max` bytes (also one that grows past it while read); LV_ERR_NOMEM. */
lv_status lv_read_file(const char *path, size_t max, const char *kind, char **out, size_t *len,
                       lv_err *err);

/* The size limit's check alone, for files another library reads (MAT files through libmatio):
 * LV_OK, or LV_ERR_INPUT with the message of lv_read_file (a missing file is LV_OK: the
 * reader says so). */
lv_status lv_file_size_check(const char *path, size_t max, const char *kind, lv_err *err);

#endif
