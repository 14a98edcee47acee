/* atomic.c - write "<path>.tmp", then rename it to "<path>": the one place where lvsim's
 * writers finish a file (atomic.h). rename(2) replaces the target in one step on POSIX file
 * systems, so a reader sees the old complete file or the new complete one; the temporary file
 * is created exclusively, so it never replaces anything itself. */
#define _POSIX_C_SOURCE 200809L /* lstat, fdopen, O_CLOEXEC */

#include "io/atomic.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
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
    if (path == NULL || path[0] == '\0')
        return lv_fail(err, LV_ERR_INPUT, "output file: empty path");
    const size_t n = strlen(path);
    if (n + 32 >= sizeof a->path)
        return lv_fail(err, LV_ERR_INPUT, "%.200s...: file name of %zu bytes is too long", path,
                       n);
    memcpy(a->path, path, n + 1);
    return pick_tmp(a, err);
}

/* Creates tmp, which must not exist (O_EXCL: a name taken since pick_tmp is picked anew). */
static int create_tmp(lv_atomic *a, lv_err *err)
{
    for (int attempt = 0; attempt < 3; attempt++) {
        errno = 0;
        const int fd = open(a->tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0)
            return fd;
        if (errno != EEXIST || pick_tmp(a, err) != LV_OK)
            break;
    }
    io_fail(a, "cannot create", errno ? errno : EEXIST, err);
    return -1;
}

lv_status lv_atomic_open(lv_atomic *a, const char *path, lv_err *err)
{
    if (path != NULL) {
        lv_status st = lv_atomic_init(a, path, err);
        if (st != LV_OK)
            return st;
    }
    const int fd = create_tmp(a, err);
    if (fd < 0)
        return LV_ERR_IO;
    a->fp = fdopen(fd, "w");
    if (a->fp == NULL) {
        const int e = errno;
        close(fd);
        remove(a->tmp);
        return io_fail(a, "cannot create", e, err);
    }
    return LV_OK;
}

lv_status lv_atomic_reserve(lv_atomic *a, lv_err *err)
{
    const int fd = create_tmp(a, err);
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
    if (a->fp != NULL) {
        /* fclose() flushes: a full disk shows here at the latest. */
        errno = 0;
        const int e_write = fflush(a->fp) != 0 || ferror(a->fp) ? (errno != 0 ? errno : EIO) : 0;
        errno = 0;
        const int closed = fclose(a->fp);
        const int e_close = errno != 0 ? errno : EIO;
        a->fp = NULL;
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
    if (st != LV_OK && !a->keep)
        remove(a->tmp);
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
    if (a != NULL && a->fp != NULL) {
        fclose(a->fp);
        a->fp = NULL;
    }
}
