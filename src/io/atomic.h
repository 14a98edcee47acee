/* atomic.h - internal: a file written under a temporary name, "<path>.tmp", and renamed to its
 * final name when complete, so that no reader ever finds half a file under the final name.
 * Every lvsim writer goes through it: the result sinks (docs/result-files.md), summary.json and
 * the body trajectories, the exports (docs/exports.md), the figures and the report
 * (docs/visualization.md). Each stream's SHA-256 is computed as it is written and handed to
 * the results folder's manifest (lv_atomic_commit, lv_atomic_digest; docs/result-files.md).
 * Not exported. */
#ifndef LV_IO_ATOMIC_H
#define LV_IO_ATOMIC_H

#include <stdio.h>
#include <sys/stat.h>

#include "lvsim/lv_status.h"

#define LV_ATOMIC_PATH_MAX 4096 /* bytes with the NUL: Linux's PATH_MAX */

/* The stream of lv_atomic_open(): the file's SHA-256 kept as its bytes go out (atomic.c). */
typedef struct lv_atomic_stream lv_atomic_stream;

/* One file being written; lives where the caller puts it. A zeroed struct is a valid
 * "nothing" for lv_atomic_abort() and lv_atomic_release(). lv_atomic_open() allocates the
 * stream's state (a->stream), which commit, abort and release free: the struct may be copied
 * only before lv_atomic_open() or after one of those. */
typedef struct lv_atomic {
    char path[LV_ATOMIC_PATH_MAX];    /* the final name, as given */
    char tmp[LV_ATOMIC_PATH_MAX + 40]; /* path + ".tmp" (or ".tmp.<pid>.<k>"): what is written */
    FILE *fp;  /* stream on tmp after lv_atomic_open(); NULL when a library writes tmp by name.
                * Write, seek and tell it as any FILE; it has no file descriptor (fileno() is
                * -1): a glibc fopencookie() stream whose writes hash the bytes they pass on */
    int keep;  /* set by the caller: a failed commit leaves tmp in place (the result sinks keep
                * the rows written so far); 0: a failed commit removes it */
    lv_atomic_stream *stream; /* fp's state; NULL when fp is */
    char sha256[65]; /* after a successful commit of a stream: the file's SHA-256 (FIPS 180-4),
                      * lowercase hex; "" otherwise (a file a library wrote by name) */
} lv_atomic;

/* The extended attribute that carries a committed stream's digest to the results folder's
 * manifest (lv_atomic_digest). Its value, text: "<sha256 hex> <bytes> <st_dev> <st_ino>
 * <mtime s>.<mtime ns, 9 digits>", the identity of the file as it was closed. */
#define LV_ATOMIC_XATTR "user.lvsim.sha256"

/* Fills the names only, opens nothing: for writers that take a file name (libmatio, PLplot).
 * tmp is "<path>.tmp", or "<path>.tmp.<pid>.<k>" when a file of that name exists (never
 * replaced). Errors: LV_ERR_INPUT (empty or too long a path). */
lv_status lv_atomic_init(lv_atomic *a, const char *path, lv_err *err);

/* lv_atomic_init (path NULL: the names an earlier lv_atomic_init gave), then creates tmp for
 * writing, exclusively (O_EXCL: an existing file is never truncated; in a hard-linked replica
 * of a results folder that would change the original): a->fp, a stream (stdio's buffer of
 * BUFSIZ bytes; the caller may setvbuf() a larger one before writing) that hashes what it
 * writes (commit). Errors:
 * LV_ERR_INPUT as above; LV_ERR_NOMEM; LV_ERR_IO "<tmp>: cannot create: <reason>".
 * On failure nothing is left open. */
lv_status lv_atomic_open(lv_atomic *a, const char *path, lv_err *err);

/* For a writer that will seek back and rewrite what it wrote (the MAT sink patches its header
 * at close): the stream stops hashing as it writes, since that digest would be thrown away,
 * and lv_atomic_commit hashes the finished file once from the open descriptor. Without this
 * call such a file is hashed twice (the same digest). After lv_atomic_open. */
void lv_atomic_hash_at_commit(lv_atomic *a);

/* Creates tmp empty and closes it (after lv_atomic_init): an unwritable folder fails here,
 * before a library that writes tmp by name gets to it. Errors: LV_ERR_IO as lv_atomic_open. */
lv_status lv_atomic_reserve(lv_atomic *a, lv_err *err);

/* Completes the file: flushes a->fp when open, checks that every write reached the file,
 * finishes the digest (below), closes the stream, and renames tmp to a->path
 * (lv_atomic_commit) or to `target` (lv_atomic_commit_as: the sinks' failed name), replacing a
 * file of that name. a->fp and a->stream are NULL afterwards; the names stay.
 *
 * The digest: every byte the stream passes to the file is hashed on its way (SHA-256, GNU
 * Nettle), so a file written front to back in one pass is never read back. A writer that
 * seeks and rewrites (the MAT sink patches t0, tf and N in its header at close) breaks that
 * order: its file is then hashed here, before the close, with pread() from the still-open
 * descriptor: the bytes just written, from the page cache. The digest goes into a->sha256 and,
 * with the file's identity after the last write (st_dev, st_ino, size, mtime), into the
 * extended attribute LV_ATOMIC_XATTR of tmp (the name it is renamed from), where the manifest
 * finds it without reading the file; a file system without user extended attributes (tmpfs
 * before Linux 6.6, some NFS) simply has no record, and the manifest hashes that file itself.
 * A file a library wrote by name (fp NULL) gets no digest and no record.
 *
 * On failure tmp is removed unless a->keep. Errors: LV_ERR_IO naming tmp and the system's
 * reason: "<tmp>: cannot write: ...", "<tmp>: cannot close: ...",
 * "<tmp>: cannot rename to '<target>': ...". */
lv_status lv_atomic_commit(lv_atomic *a, lv_err *err);
lv_status lv_atomic_commit_as(lv_atomic *a, const char *target, lv_err *err);

/* Gives up: closes a->fp when open and removes tmp (whatever a->keep says). */
void lv_atomic_abort(lv_atomic *a);

/* Closes a->fp when open and leaves tmp as it is (a sink destroyed without close()); no
 * digest is recorded for it. */
void lv_atomic_release(lv_atomic *a);

/* The digest lv_atomic_commit recorded for the file at `path`, when the record's identity is
 * `sb`'s, the caller's lstat() of path now: the same st_dev, st_ino, size and modification
 * time to the nanosecond. Then the file holds what lvsim wrote through the stream (a later
 * write changes the size or the mtime; a copy elsewhere is another inode) and `hex` (65 bytes)
 * is its SHA-256. Returns 1 with hex filled, 0 when there is no such record (none, another
 * identity, no extended attributes there). Reads no file data. */
int lv_atomic_digest(const char *path, const struct stat *sb, char hex[65]);

#endif
