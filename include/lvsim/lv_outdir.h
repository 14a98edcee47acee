/* lv_outdir.h - results folders that are never half-written, mixed or shared, and that
 * lvsim replaces only where it can prove it wrote them.
 *
 *   lv_outdir *od;
 *   lv_outdir_begin("out", "mission.yaml", 0, &od, &err); lock, check, make the staging
 *                                                         folder .out.staging-XXXXXX beside out
 *   ... write everything into lv_outdir_path(od) ...      (lv_run_options.outdir, summary,
 *                                                         exports, plots)
 *   lv_outdir_commit(od, &rec, &err);                     manifest.json, then out replaced in
 *                                                         one rename; unlock
 *   lv_outdir_free(od);                                   (without commit: staging removed,
 *                                                         out untouched)
 *
 * Provably lvsim's. A folder is lvsim's when its manifest.json, written by lvsim, lists every
 * file in it (a subfolder with a manifest of its own - a Monte Carlo campaign's kept runs -
 * by that one). A file it does not list, a file whose size or SHA-256 differs from the
 * listed one (hashed only when it is newer than the manifest), a link, a pipe, and a folder
 * with none of the listed files under it are the user's. A folder holding any is refused
 * (LV_ERR_INPUT naming up to four of them) unless LV_OUTDIR_FORCE: then lvsim's files are
 * replaced and the user's are kept, carried into the new folder as hard links (their data,
 * owner and mode unchanged; a commit that would replace one, because the new results have a
 * file of its name, is refused and leaves OUTDIR as it was). A user's manifest.json is never
 * replaced, even with LV_OUTDIR_FORCE.
 *
 * Atomic. The lock is flock(2) on `.<name>.lock` beside OUTDIR (it says "lvsim <pid>"; a file
 * of that name that says anything else is not taken over; removed when done): a second
 * writer, in this process or another, is refused at once ("... is in use by lvsim process
 * N"), never made to wait or interleave. The staging folder `.<name>.staging-XXXXXX` lies
 * beside OUTDIR, on the same file system: the replacement is one renameat2 RENAME_EXCHANGE
 * (a reader sees the old complete folder or the new complete one, never a mix, never none),
 * and a run killed at any point leaves OUTDIR as it was plus a staging folder that the next
 * writer removes (and reports: lv_outdir_stale) - only when it is provably lvsim's (empty, or
 * marked by lvsim while it fills it or holding an lvsim manifest, and holding nothing but
 * hard links of OUTDIR's files and the names lvsim writes: docs/result-files.md). With
 * LV_OUTDIR_FORCE a user's file of a name the command writes (summary.json for a run,
 * stats.json for a campaign, ...) is refused when the folder is opened, not at the commit.
 *
 * Permissions. A new folder is created with mode 0777 less the umask, as any folder the user
 * makes; a folder replaced keeps its mode (and, where the system allows, its owner and group).
 *
 * Post-processing: part of liblvsim_post (cJSON for the manifest, Nettle for SHA-256).
 * Results: docs/result-files.md. Thread safety: one lv_outdir per thread; no global state.
 */
#ifndef LVSIM_LV_OUTDIR_H
#define LVSIM_LV_OUTDIR_H

#include <stddef.h>

#include "lvsim/lv_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct lv_outdir lv_outdir;

/* Flags of lv_outdir_begin and lv_outdir_open_live. */
enum {
    LV_OUTDIR_FORCE = 1u /* a folder holding files lvsim did not write is used anyway: those
                            files are kept, never replaced (the CLI's --force) */
};

/* Begins writing a new results folder OUTDIR for a run of `mission_file` (hashed now, the
 * file the run reads; NULL: none). OUTDIR may exist only as a folder that is empty or that
 * lvsim wrote (see above; with LV_OUTDIR_FORCE also one holding the user's files, which are
 * kept); "", "/", "." and ".." are refused. A symbolic link is followed: its target is
 * replaced. Missing parent folders are created. Writing goes into an empty staging folder.
 * Errors: LV_ERR_INPUT (the name, a file, a folder with files lvsim did not write, the folder
 * in use: each message names the path and what to do); LV_ERR_IO (a folder that cannot be
 * created or read, with the system's reason); LV_ERR_NOMEM. On failure *out is NULL and
 * nothing was changed. */
LV_API lv_status lv_outdir_begin(const char *outdir, const char *mission_file, unsigned flags,
                                 lv_outdir **out, lv_err *err);

/* Opens an existing results folder of lvsim to add or replace files (lvsim export, plot,
 * view): the same lock; lv_outdir_path is a staging folder that starts as a hard-linked
 * replica of OUTDIR (writers replace files there by rename, as every lvsim writer does);
 * lv_outdir_commit checks that none of the user's files was replaced, adds a history entry
 * to the manifest and exchanges the folders. Errors: LV_ERR_INPUT (missing, not a folder,
 * not lvsim's, in use); LV_ERR_IO; LV_ERR_NOMEM. */
LV_API lv_status lv_outdir_open(const char *outdir, lv_outdir **out, lv_err *err);

/* Opens a folder that lvsim fills in place for a long time (a Monte Carlo campaign's
 * database, written as it runs): OUTDIR is created when missing; it must be empty, lvsim's,
 * or (LV_OUTDIR_FORCE) hold only files that are not among `live`; its manifest is written at
 * once with status "incomplete" and `live` (a NULL-terminated list of names relative to
 * OUTDIR: files, or folders of nested results folders) recorded as lvsim's whatever they
 * come to hold. lv_outdir_path is OUTDIR itself until lv_outdir_stage. mission_file as for
 * lv_outdir_begin. Errors as lv_outdir_open; a user's file named in `live` is refused. */
LV_API lv_status lv_outdir_open_live(const char *outdir, const char *mission_file, unsigned flags,
                                     const char *const *live, lv_outdir **out, lv_err *err);

/* After lv_outdir_open_live: from now on writes go to a staging replica of OUTDIR, committed
 * as for lv_outdir_open (the figures and statistics written after a campaign). Errors:
 * LV_ERR_INPUT (not a live folder, staged twice), LV_ERR_IO, LV_ERR_NOMEM. */
LV_API lv_status lv_outdir_stage(lv_outdir *od, lv_err *err);

/* Where to write now: the staging folder (begin) or OUTDIR (open). */
LV_API const char *lv_outdir_path(const lv_outdir *od);
/* OUTDIR as it will be named (trailing slashes removed; a link's target). */
LV_API const char *lv_outdir_final(const lv_outdir *od);

/* The stale staging folders of killed runs that begin/open removed (their names beside
 * OUTDIR), for the caller to report. */
LV_API size_t lv_outdir_stale_count(const lv_outdir *od);
LV_API const char *lv_outdir_stale(const lv_outdir *od, size_t i);

/* After a commit with LV_OUTDIR_FORCE: the files lvsim did not write that it kept (paths
 * relative to OUTDIR), for the caller to report. */
LV_API size_t lv_outdir_kept_count(const lv_outdir *od);
LV_API const char *lv_outdir_kept(const lv_outdir *od, size_t i);

/* What the manifest records besides the files. Strings are copied. */
typedef struct lv_outdir_record {
    const char *command;      /* what wrote the folder: "run", "export", "plot", "view" */
    const char *status;       /* "ok" or "failed" (a run with failed phases is kept, marked) */
    const char *mission_name; /* NULL: not known */
    size_t n_notes;           /* errors and warnings worth keeping with the results */
    const char *const *notes;
} lv_outdir_record;

/* Writes the manifest.json (lvsim version, command, status, mission file with its SHA-256
 * and size, start and end time, notes, the history of the commands that changed the folder,
 * and every file lvsim wrote with its size and SHA-256; not the user's files), carries the
 * user's files into the staging folder, then replaces OUTDIR by it as a whole and removes
 * the old one; for a live folder not staged, writes its manifest in place. Unlocks in every
 * case. Errors: LV_ERR_INPUT (a user's file would be replaced: named), LV_ERR_IO naming the
 * path (OUTDIR is then as it was before); LV_ERR_NOMEM. */
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
/* For a live folder whose command was refused before it wrote anything (a campaign whose
 * database does not match its options): the manifest that lv_outdir_open_live wrote is
 * replaced by the one the folder had (none: removed; a folder the open made is removed when
 * empty), then as lv_outdir_free. Other folders: lv_outdir_free. Accepts NULL. */
LV_API void lv_outdir_discard(lv_outdir *od);

/* SHA-256 (FIPS 180-4) of a file as 64 lowercase hex digits and a NUL, and its size.
 * Errors: LV_ERR_IO "path: cannot read: reason". */
LV_API lv_status lv_sha256_file(const char *path, char hex[65], unsigned long long *bytes,
                                lv_err *err);

#ifdef __cplusplus
}
#endif
#endif
