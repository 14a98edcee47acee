/* atomic.c - write "<path>.tmp", then rename it to "<path>": the one place where lvsim's
 * writers finish a file (atomic.h). rename(2) replaces the target in one step on POSIX file
 * systems, so a reader sees the old complete file or the new complete one; the temporary file
 * is created exclusively, so it never replaces anything itself. The stream hashes (SHA-256,
 * FIPS 180-4, GNU Nettle) every byte it passes to the file, so that the results folder's
 * manifest need not read the file again (lv_atomic_digest). */
#define _GNU_SOURCE /* fopencookie (glibc); lstat, pread, O_CLOEXEC, fsetxattr */

#include "io/atomic.h"
#include "io/nettle_dl.h"

#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <nettle/sha2.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/xattr.h>
#include <unistd.h>

#include "core/status.h"

static lv_status io_fail(const lv_atomic *a, const char *what, int e, lv_err *err)
{
    char text[128];
    return lv_fail(err, LV_ERR_IO, "%s: %s: %s", a->tmp, what, lv_strerror(e, text, sizeof text));
}

/* tmp = path + ".tmp", or path + ".tmp.<pid>.<k>" when a file of that name exists already (a
 * user's, or one a killed writer left): lvsim's temporary file never replaces anything. */
static lv_status pick_tmp(lv_atomic *a, lv_err *err)
{
    const size_t n = strlen(a->path);
    struct stat sb;
    for (unsigned k = 0; k < 1000; k++) {
        int w;
        if (k == 0)
            w = snprintf(a->tmp, sizeof a->tmp, "%s.tmp", a->path);
        else
            w = snprintf(a->tmp, sizeof a->tmp, "%s.tmp.%ld.%u", a->path, (long)getpid(), k);
        if (w < 0 || (size_t)w >= sizeof a->tmp)
            return lv_fail(err, LV_ERR_INPUT, "%.200s...: file name of %zu bytes is too long",
                           a->path, n);
        if (lstat(a->tmp, &sb) != 0 && errno == ENOENT)
            return LV_OK;
    }
    return lv_fail(err, LV_ERR_IO, "%s: no free temporary name beside it", a->path);
}

lv_status lv_atomic_init(lv_atomic *a, const char *path, lv_err *err)
{
    a->path[0] = a->tmp[0] = '\0';
    a->fp = NULL;
    a->keep = 0;
    a->stream = NULL;
    a->sha256[0] = '\0';
    if (path == NULL || path[0] == '\0')
        return lv_fail(err, LV_ERR_INPUT, "output file: empty path");
    const size_t n = strlen(path);
    if (n + 32 >= sizeof a->path)
        return lv_fail(err, LV_ERR_INPUT, "%.200s...: file name of %zu bytes is too long", path,
                       n);
    memcpy(a->path, path, n + 1);
    return pick_tmp(a, err);
}

/* Creates tmp, which must not exist (O_EXCL: a name taken since pick_tmp is picked anew),
 * opened with `access` (O_WRONLY, or O_RDWR for a stream: its digest may read it back). */
static int create_tmp(lv_atomic *a, int access, lv_err *err)
{
    for (int attempt = 0; attempt < 3; attempt++) {
        errno = 0;
        const int fd = open(a->tmp, access | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0)
            return fd;
        if (errno != EEXIST || pick_tmp(a, err) != LV_OK)
            break;
    }
    io_fail(a, "cannot create", errno ? errno : EEXIST, err);
    return -1;
}

/* ---- the hashing stream --------------------------------------------------------------- */

enum { REHASH_BUF = 1 << 18 }; /* bytes read at a time when a file is hashed at commit */

struct lv_atomic_stream {
    int fd;
    int in_order;    /* 1 while every write continued the bytes hashed so far */
    int err;         /* errno of the first failed write; 0 */
    uint64_t hashed; /* bytes [0, hashed) of the file are in ctx, in order */
    uint64_t pos;    /* the descriptor's offset */
    struct sha256_ctx ctx;
};

/* fopencookie's write: the bytes go to the file and, when they continue the hashed ones (no
 * seek moved the offset elsewhere), into the digest. Returns the bytes written; fewer than n
 * is an error for stdio (the FILE's error flag), whose errno is kept in s->err. */
static ssize_t stream_write(void *cookie, const char *data, size_t n)
{
    lv_atomic_stream *s = cookie;
    size_t done = 0;
    while (done < n) {
        const ssize_t w = write(s->fd, data + done, n - done);
        if (w > 0) {
            done += (size_t)w;
        } else if (w < 0 && errno == EINTR) {
            continue;
        } else {
            if (w == 0)
                errno = EIO;
            if (s->err == 0)
                s->err = errno;
            break;
        }
    }
    if (s->in_order && s->pos == s->hashed) {
        sha256_update(&s->ctx, done, (const uint8_t *)data);
        s->hashed += done;
    } else {
        s->in_order = 0; /* rewritten or with a hole: hashed again at commit */
    }
    s->pos += done;
    return (ssize_t)done;
}

/* fopencookie's seek (fseek, ftell, rewind): moves the descriptor; the digest is given up only
 * by a write at another offset than the end of the hashed bytes (stream_write), so an ftell()
 * or a seek back to the end costs nothing. */
static int stream_seek(void *cookie, off64_t *offset, int whence)
{
    lv_atomic_stream *s = cookie;
    const off_t r = lseek(s->fd, (off_t)*offset, whence);
    if (r < 0)
        return -1;
    *offset = (off64_t)r;
    s->pos = (uint64_t)r;
    return 0;
}

static int stream_close(void *cookie)
{
    lv_atomic_stream *s = cookie;
    const int rc = close(s->fd);
    s->fd = -1;
    return rc;
}

lv_status lv_atomic_open(lv_atomic *a, const char *path, lv_err *err)
{
    if (path != NULL) {
        lv_status st = lv_atomic_init(a, path, err);
        if (st != LV_OK)
            return st;
    }
    a->stream = NULL;
    a->sha256[0] = '\0';
    lv_atomic_stream *s = malloc(sizeof *s);
    if (s == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", a->path);
    const int fd = create_tmp(a, O_RDWR, err);
    if (fd < 0) {
        free(s);
        return LV_ERR_IO;
    }
    s->fd = fd;
    s->in_order = 1;
    s->err = 0;
    s->hashed = s->pos = 0;
    sha256_init(&s->ctx);
    const cookie_io_functions_t io = {NULL, stream_write, stream_seek, stream_close};
    a->fp = fopencookie(s, "w", io);
    if (a->fp == NULL) {
        const int e = errno;
        close(fd);
        remove(a->tmp);
        free(s);
        return io_fail(a, "cannot create", e, err);
    }
    a->stream = s; /* stdio's own buffer (BUFSIZ), or the caller's setvbuf() */
    return LV_OK;
}

void lv_atomic_hash_at_commit(lv_atomic *a)
{
    if (a != NULL && a->stream != NULL)
        a->stream->in_order = 0;
}

static void to_hex(const uint8_t *d, size_t n, char *hex)
{
    static const char digits[] = "0123456789abcdef";
    for (size_t i = 0; i < n; i++) {
        hex[2 * i] = digits[d[i] >> 4];
        hex[2 * i + 1] = digits[d[i] & 15];
    }
    hex[2 * n] = '\0';
}

/* After the last write (fflush'ed), before the close: a->sha256 and the record on the file.
 * A stream written in one pass has its digest already; otherwise the file is hashed from the
 * descriptor, still open: what was just written, from the page cache. Anything unexpected (a
 * failing fstat, malloc or pread) leaves no digest: the manifest then reads the file itself. */
static void finish_digest(lv_atomic *a)
{
    lv_atomic_stream *s = a->stream;
    struct stat sb;
    if (lv_nettle_error() != NULL) /* Nettle could not be loaded: no digest (io/nettle_dl.c) */
        return;
    if (fstat(s->fd, &sb) != 0 || !S_ISREG(sb.st_mode) || sb.st_size < 0)
        return;
    const uint64_t size = (uint64_t)sb.st_size;
    if (!s->in_order || s->hashed != size) {
        uint8_t *buf = malloc(REHASH_BUF);
        if (buf == NULL)
            return;
        sha256_init(&s->ctx);
        uint64_t at = 0;
        while (at < size) {
            const size_t want = size - at < REHASH_BUF ? (size_t)(size - at) : REHASH_BUF;
            const ssize_t got = pread(s->fd, buf, want, (off_t)at);
            if (got < 0 && errno == EINTR)
                continue;
            if (got <= 0)
                break;
            sha256_update(&s->ctx, (size_t)got, buf);
            at += (uint64_t)got;
        }
        free(buf);
        if (at != size)
            return;
    }
    uint8_t d[SHA256_DIGEST_SIZE];
    sha256_digest(&s->ctx, sizeof d, d);
    to_hex(d, sizeof d, a->sha256);
    char rec[200];
    const int n = snprintf(rec, sizeof rec, "%s %" PRIu64 " %" PRIu64 " %" PRIu64 " %lld.%09ld",
                           a->sha256, size, (uint64_t)sb.st_dev, (uint64_t)sb.st_ino,
                           (long long)sb.st_mtim.tv_sec, (long)sb.st_mtim.tv_nsec);
    if (n > 0 && (size_t)n < sizeof rec) {
        /* No user extended attributes there (ENOTSUP): no record; the manifest hashes it. */
        (void)fsetxattr(s->fd, LV_ATOMIC_XATTR, rec, (size_t)n, 0);
    }
}

int lv_atomic_digest(const char *path, const struct stat *sb, char hex[65])
{
    char rec[200], h[65];
    const ssize_t n = lgetxattr(path, LV_ATOMIC_XATTR, rec, sizeof rec - 1);
    if (n <= 0)
        return 0;
    rec[n] = '\0';
    unsigned long long size, dev, ino;
    long long sec;
    long nsec;
    int end = -1;
    if (sscanf(rec, "%64[0-9a-f] %llu %llu %llu %lld.%ld%n", h, &size, &dev, &ino, &sec, &nsec,
               &end) != 6 ||
        end != (int)n || strlen(h) != 64)
        return 0;
    if (!S_ISREG(sb->st_mode) || size != (unsigned long long)sb->st_size ||
        dev != (unsigned long long)sb->st_dev || ino != (unsigned long long)sb->st_ino ||
        sec != (long long)sb->st_mtim.tv_sec || nsec != (long)sb->st_mtim.tv_nsec)
        return 0;
    memcpy(hex, h, 65);
    return 1;
}

/* fclose(a->fp) and the stream's state freed; returns fclose's result. */
static int close_stream(lv_atomic *a)
{
    const int rc = fclose(a->fp);
    a->fp = NULL;
    free(a->stream);
    a->stream = NULL;
    return rc;
}

lv_status lv_atomic_reserve(lv_atomic *a, lv_err *err)
{
    const int fd = create_tmp(a, O_WRONLY, err);
    if (fd < 0)
        return LV_ERR_IO;
    if (close(fd) != 0) {
        const int e = errno;
        remove(a->tmp);
        return io_fail(a, "cannot close", e, err);
    }
    return LV_OK;
}

lv_status lv_atomic_commit_as(lv_atomic *a, const char *target, lv_err *err)
{
    lv_status st = LV_OK;
    a->sha256[0] = '\0';
    if (a->fp != NULL) {
        /* A full disk shows here at the latest. */
        errno = 0;
        int e_write = fflush(a->fp) != 0 || ferror(a->fp) ? (errno != 0 ? errno : EIO) : 0;
        if (e_write != 0 && a->stream != NULL && a->stream->err != 0)
            e_write = a->stream->err; /* the first failed write's reason */
        if (e_write == 0 && a->stream != NULL)
            finish_digest(a);
        errno = 0;
        const int closed = close_stream(a);
        const int e_close = errno != 0 ? errno : EIO;
        if (e_write != 0)
            st = io_fail(a, "cannot write", e_write, err);
        else if (closed != 0)
            st = io_fail(a, "cannot close", e_close, err);
    }
    if (st == LV_OK && rename(a->tmp, target) != 0) {
        char text[128];
        const int e = errno;
        st = lv_fail(err, LV_ERR_IO, "%s: cannot rename to '%s': %s", a->tmp, target,
                     lv_strerror(e, text, sizeof text));
    }
    if (st != LV_OK) {
        a->sha256[0] = '\0';
        if (!a->keep)
            remove(a->tmp);
    }
    return st;
}

lv_status lv_atomic_commit(lv_atomic *a, lv_err *err)
{
    return lv_atomic_commit_as(a, a->path, err);
}

void lv_atomic_abort(lv_atomic *a)
{
    if (a == NULL)
        return;
    lv_atomic_release(a);
    if (a->tmp[0] != '\0')
        remove(a->tmp);
}

void lv_atomic_release(lv_atomic *a)
{
    if (a != NULL && a->fp != NULL)
        close_stream(a);
}
