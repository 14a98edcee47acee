/* lv_outdir.h - results folders that are never half-written, mixed or shared: a run writes
 * into a private staging folder and replaces the results folder as a whole when it ends,
 * under a lock that refuses a second writer; a manifest names every file with its SHA-256.
 *
 *   lv_outdir *od;
 *   lv_outdir_begin("out", "mission.yaml", &od, &err);   lock, clean stale staging folders,
 *                                                         make .out.staging-XXXXXX beside out
 *   ... write everything into lv_outdir_path(od) ...      (lv_run_options.outdir, summary,
 *                                                         exports, plots)
 *   lv_outdir_commit(od, &rec, &err);                     manifest.json, then out replaced in
 *                                                         one rename; unlock
 *   lv_outdir_free(od);                                   (without commit: staging removed,
 *                                                         out untouched)
 *
 * The lock is flock(2) on OUTDIR's lock file `.<name>.lock` beside it (removed when done):
 * a second writer of the same folder, in this process or another, is refused at once
 * (LV_ERR_INPUT, "... is in use by lvsim process N"), never made to wait or interleave. The
 * staging folder `.<name>.staging-XXXXXX` lies beside OUTDIR, so on the same file system:
 * the replacement is one rename(2) (renameat2 RENAME_EXCHANGE when OUTDIR exists: a reader
 * sees the old complete folder or the new complete one, never a mix, never none), and a run
 * killed at any point leaves OUTDIR as it was plus a staging folder that the next writer of
 * OUTDIR removes (and reports: lv_outdir_stale). Results: docs/result-files.md.
 *
 * Post-processing: part of liblvsim_post (cJSON for the manifest, Nettle for SHA-256).
 * Thread safety: one lv_outdir per thread; the library keeps no global state.
 */
#ifndef LVSIM_LV_OUTDIR_H
#define LVSIM_LV_OUTDIR_H

#include <stddef.h>

#include "lvsim/lv_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct lv_outdir lv_outdir;

/* Begins writing a new results folder OUTDIR for a run of `mission_file` (hashed now, the
 * file the run reads; NULL: none). OUTDIR may exist only as a folder that is empty or that
 * lvsim wrote (it has manifest.json or summary.json): any other folder is refused rather
 * than replaced, and so are a file, "", "/", "." and "..". A symbolic link is followed: its
 * target is replaced. Missing parent folders are created.
 * Errors: LV_ERR_INPUT (the name, a file, a foreign folder, the folder in use: each message
 * names the path and what to do); LV_ERR_IO (a folder that cannot be created, the system's
 * reason); LV_ERR_NOMEM. On failure *out is NULL and nothing was changed. */
LV_API lv_status lv_outdir_begin(const char *outdir, const char *mission_file, lv_outdir **out,
                                 lv_err *err);

/* Opens an existing results folder to add or replace files in place (lvsim export, plot,
 * view): the same lock; lv_outdir_path is OUTDIR itself; lv_outdir_commit updates its
 * manifest. Errors: LV_ERR_INPUT (not a folder, in use); LV_ERR_IO; LV_ERR_NOMEM. */
LV_API lv_status lv_outdir_open(const char *outdir, lv_outdir **out, lv_err *err);

/* Where to write now: the staging folder (begin) or OUTDIR (open). */
LV_API const char *lv_outdir_path(const lv_outdir *od);
/* OUTDIR as it will be named (trailing slashes removed; a link's target). */
LV_API const char *lv_outdir_final(const lv_outdir *od);

/* The stale staging folders of killed runs that begin/open removed (their names beside
 * OUTDIR), for the caller to report. */
LV_API size_t lv_outdir_stale_count(const lv_outdir *od);
LV_API const char *lv_outdir_stale(const lv_outdir *od, size_t i);

/* What the manifest records besides the files. Strings are copied. */
typedef struct lv_outdir_record {
    const char *command;      /* what wrote the folder: "run", "export", "plot", "view" */
    const char *status;       /* "ok" or "failed" (a run with failed phases is kept, marked) */
    const char *mission_name; /* NULL: not known */
    size_t n_notes;           /* errors and warnings worth keeping with the results */
    const char *const *notes;
} lv_outdir_record;

/* Writes OUTDIR's manifest.json (lvsim version, command, status, mission file with its
 * SHA-256 and size, start and end time, and every file with its size and SHA-256; open:
 * the files again, and the command added to its history), then, after begin, replaces
 * OUTDIR by the staging folder as a whole and removes the old one. Unlocks in every case.
 * Errors: LV_ERR_IO naming the path (OUTDIR is then as it was before begin); LV_ERR_NOMEM. */
LV_API lv_status lv_outdir_commit(lv_outdir *od, const lv_outdir_record *rec, lv_err *err);

/* The files the manifest lists (after a successful commit), in name order: paths relative
 * to OUTDIR ("plots/altitude.png"), sizes in bytes. */
typedef struct lv_outdir_file {
    const char *name;
    unsigned long long bytes;
} lv_outdir_file;
LV_API size_t lv_outdir_file_count(const lv_outdir *od);
LV_API const lv_outdir_file *lv_outdir_files(const lv_outdir *od);

/* Releases the folder: when not committed, the staging folder is removed and OUTDIR is left
 * as it was; the lock is released. Accepts NULL. */
LV_API void lv_outdir_free(lv_outdir *od);

/* SHA-256 (FIPS 180-4) of a file as 64 lowercase hex digits and a NUL, and its size.
 * Errors: LV_ERR_IO "path: cannot read: reason". */
LV_API lv_status lv_sha256_file(const char *path, char hex[65], unsigned long long *bytes,
                                lv_err *err);

#ifdef __cplusplus
}
#endif
#endif
