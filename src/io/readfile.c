/* readfile.c - a whole file into memory, bounded (readfile.h). */
#define _POSIX_C_SOURCE 200809L /* fstat, fileno */

#include "io/readfile.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>

static lv_status too_large(const char *path, double size, size_t max, const char *kind,
                           lv_err *err)
{
    char have[32], most[32];
    lv_fmt_bytes(size, have, sizeof have);
    lv_fmt_bytes((double)max, most, sizeof most);
    return lv_fail(err, LV_ERR_INPUT, "%s: %s%s; at most %s are read%s%s%s", path,
                   size > (double)max ? "" : "more than ", have, most, kind ? " (" : "",
                   kind ? kind : "", kind ? ")" : "");
}

static lv_status check_stat(const char *path, const struct stat *sb, size_t max,
                            const char *kind, lv_err *err)
{
    if (!S_ISREG(sb->st_mode))
        return lv_fail(err, LV_ERR_INPUT, "%s: not a regular file", path);
    if ((double)sb->st_size > (double)max)
        return too_large(path, (double)sb->st_size, max, kind, err);
    return LV_OK;
}

lv_status lv_file_size_check(const char *path, size_t max, const char *kind, lv_err *err)
{
    struct stat sb;
    if (stat(path, &sb) != 0)
        return LV_OK;
    return check_stat(path, &sb, max, kind, err);
}

lv_status lv_read_file(const char *path, size_t max, const char *kind, char **out, size_t *len,
                       lv_err *err)
{
    *out = NULL;
    *len = 0;
    FILE *fp = fopen(path, "rb");
    if (fp == NULL)
        return lv_fail(err, LV_ERR_IO, "%s: cannot open%s%s: %s", path, kind ? " " : "",
                       kind ? kind : "", LV_STRERROR(errno));
    struct stat sb;
    lv_status st = LV_OK;
    if (fstat(fileno(fp), &sb) != 0) {
        st = lv_fail(err, LV_ERR_IO, "%s: cannot read: %s", path, LV_STRERROR(errno));
        fclose(fp);
        return st;
    }
    if ((st = check_stat(path, &sb, max, kind, err)) != LV_OK) {
        fclose(fp);
        return st;
    }
    /* the size it has now, and more if it grows while read, never beyond max */
    size_t cap = (size_t)sb.st_size + 1, n = 0;
    char *buf = malloc(cap + 1);
    for (;;) {
        if (buf == NULL) {
            st = lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", path);
            break;
        }
        const size_t got = fread(buf + n, 1, cap - n, fp);
        n += got;
        if (n > max) {
            st = too_large(path, (double)n, max, kind, err);
            break;
        }
        if (n < cap) {
            if (ferror(fp))
                st = lv_fail(err, LV_ERR_IO, "%s: cannot read: %s", path,
                             LV_STRERROR(errno ? errno : EIO));
            break;
        }
        cap = cap * 2 < max + 1 ? cap * 2 : max + 1;
        char *grown = realloc(buf, cap + 1);
        if (grown == NULL)
            free(buf);
        buf = grown;
    }
    fclose(fp);
    if (st != LV_OK) {
        free(buf);
        return st;
    }
    buf[n] = '\0';
    *out = buf;
    *len = n;
    return LV_OK;
}
