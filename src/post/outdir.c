/* outdir.c - run-atomic results folders (lv_outdir.h): a lock beside OUTDIR, a staging
 * folder beside it that replaces it as a whole (renameat2 RENAME_EXCHANGE, Linux >= 3.15),
 * stale staging folders of killed runs removed, and manifest.json naming every file with
 * its SHA-256. The library never prints: what was cleaned is returned to the caller. */
#define _GNU_SOURCE /* renameat2, RENAME_EXCHANGE (glibc >= 2.28) */

#include <cjson/cJSON.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "core/status.h"
#include "io/atomic.h"
#include "lvsim/lv_outdir.h"
#include "lvsim/lvsim.h"

#define MANIFEST "manifest.json"
#define STAGING_TAG ".staging-"

struct lv_outdir {
    char final[PATH_MAX];   /* OUTDIR */
    char parent[PATH_MAX];  /* its folder ("." for a bare name) */
    char base[NAME_MAX + 1];
    char lock[PATH_MAX + NAME_MAX + 16];    /* parent/.base.lock */
    char staging[PATH_MAX + NAME_MAX + 32]; /* parent/.base.staging-XXXXXX; "" for open() */
    int lock_fd;            /* -1: not locked */
    int in_place;           /* open(): write into OUTDIR itself */
    int committed;
    char started[32];       /* ISO 8601 UTC */
    char *mission_file;     /* as given, absolute path, SHA-256, size */
    char *mission_abs;
    char mission_sha[65];
    unsigned long long mission_bytes;
    char **stale;           /* removed stale staging folders */
    size_t n_stale;
    lv_outdir_file *files;  /* after commit */
    size_t n_files;
};

static void iso_now(char *buf, size_t cap)
{
    time_t t = time(NULL);
    struct tm tm;
    if (gmtime_r(&t, &tm) == NULL || strftime(buf, cap, "%Y-%m-%dT%H:%M:%SZ", &tm) == 0)
        snprintf(buf, cap, "unknown");
}

/* ---- removing a folder tree, never following a link ----------------------------------- */

/* Removes everything inside the folder open as `fd` (which it closes), then nothing else. */
static int rm_contents(int fd)
{
    DIR *d = fdopendir(fd);
    if (d == NULL) {
        close(fd);
        return -1;
    }
    int rc = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        struct stat sb;
        if (fstatat(dirfd(d), e->d_name, &sb, AT_SYMLINK_NOFOLLOW) != 0) {
            rc = -1;
            continue;
        }
        if (S_ISDIR(sb.st_mode)) {
            int sub = openat(dirfd(d), e->d_name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
            if (sub < 0 || rm_contents(sub) != 0 || unlinkat(dirfd(d), e->d_name, AT_REMOVEDIR) != 0)
                rc = -1;
        } else if (unlinkat(dirfd(d), e->d_name, 0) != 0) {
            rc = -1;
        }
    }
    closedir(d);
    return rc;
}

static int rm_tree(const char *path)
{
    int fd = open(path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0)
        return errno == ENOENT ? 0 : -1;
    if (rm_contents(fd) != 0)
        return -1;
    return rmdir(path);
}

/* ---- names and checks ------------------------------------------------------------------ */

static lv_status mkdir_p(const char *dir, lv_err *err)
{
    char buf[PATH_MAX], text[128];
    const size_t n = strlen(dir);
    if (n == 0 || n >= sizeof buf)
        return lv_fail(err, LV_ERR_INPUT, "folder name '%.200s' is empty or too long", dir);
    memcpy(buf, dir, n + 1);
    for (size_t i = 1; i <= n; i++) {
        if (buf[i] != '/' && buf[i] != '\0')
            continue;
        const char ch = buf[i];
        buf[i] = '\0';
        struct stat sb;
        if (mkdir(buf, 0777) != 0 && errno != EEXIST)
            return lv_fail(err, LV_ERR_IO, "cannot create folder '%s': %s", buf,
                           lv_strerror(errno, text, sizeof text));
        if (stat(buf, &sb) != 0 || !S_ISDIR(sb.st_mode))
            return lv_fail(err, LV_ERR_INPUT, "'%s' is a file, not a folder", buf);
        buf[i] = ch;
    }
    return LV_OK;
}

/* Splits OUTDIR into parent and base after dropping trailing slashes; follows a link. */
static lv_status set_names(lv_outdir *od, const char *outdir, lv_err *err)
{
    if (outdir == NULL || outdir[0] == '\0')
        return lv_fail(err, LV_ERR_INPUT, "the results folder's name is empty: name a folder");
    size_t n = strlen(outdir);
    if (n >= sizeof od->final)
        return lv_fail(err, LV_ERR_INPUT, "results folder name of %zu bytes is too long", n);
    char path[PATH_MAX];
    memcpy(path, outdir, n + 1);
    while (n > 1 && path[n - 1] == '/')
        path[--n] = '\0';
    struct stat sb;
    if (lstat(path, &sb) == 0 && S_ISLNK(sb.st_mode)) {
        char real[PATH_MAX];
        if (realpath(path, real) == NULL) {
            char text[128];
            return lv_fail(err, LV_ERR_INPUT, "results folder '%s' is a link that leads nowhere: %s",
                           outdir, lv_strerror(errno, text, sizeof text));
        }
        snprintf(path, sizeof path, "%s", real);
        n = strlen(path);
    }
    const char *slash = strrchr(path, '/');
    const char *base = slash != NULL ? slash + 1 : path;
    if (strcmp(path, "/") == 0 || strcmp(base, ".") == 0 || strcmp(base, "..") == 0 ||
        base[0] == '\0')
        return lv_fail(err, LV_ERR_INPUT,
                       "'%s' cannot be a results folder (it would be replaced as a whole): name "
                       "a folder of its own, e.g. '%s/lvsim-out'",
                       outdir, path);
    if (strlen(base) > NAME_MAX - 20)
        return lv_fail(err, LV_ERR_INPUT, "results folder name '%s' is too long", base);
    snprintf(od->final, sizeof od->final, "%s", path);
    snprintf(od->base, sizeof od->base, "%s", base);
    if (slash == NULL)
        snprintf(od->parent, sizeof od->parent, ".");
    else if (slash == path)
        snprintf(od->parent, sizeof od->parent, "/");
    else
        snprintf(od->parent, sizeof od->parent, "%.*s", (int)(slash - path), path);
    snprintf(od->lock, sizeof od->lock, "%s/.%s.lock", od->parent, od->base);
    return LV_OK;
}

static int has_file(const char *dir, const char *name)
{
    char p[PATH_MAX + 32];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    struct stat sb;
    return stat(p, &sb) == 0 && S_ISREG(sb.st_mode);
}

static int dir_is_empty(const char *dir)
{
    DIR *d = opendir(dir);
    if (d == NULL)
        return 0;
    int empty = 1;
    struct dirent *e;
    while (empty && (e = readdir(d)) != NULL)
        empty = strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0;
    closedir(d);
    return empty;
}

/* ---- the lock ------------------------------------------------------------------------ */

/* flock on parent/.base.lock, refusing when held. The file is unlinked by its holder when
 * done; a lock taken on a file that was unlinked meanwhile is retaken on the new one. */
static lv_status take_lock(lv_outdir *od, lv_err *err)
{
    char text[128];
    for (int attempt = 0; attempt < 20; attempt++) {
        int fd = open(od->lock, O_RDWR | O_CREAT | O_CLOEXEC, 0666);
        if (fd < 0)
            return lv_fail(err, errno == EACCES || errno == EROFS ? LV_ERR_INPUT : LV_ERR_IO,
                           "cannot write in '%s' (the lock file %s): %s", od->parent, od->lock,
                           lv_strerror(errno, text, sizeof text));
        if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
            const int e = errno;
            char pid[32] = "";
            ssize_t got = pread(fd, pid, sizeof pid - 1, 0);
            close(fd);
            if (e != EWOULDBLOCK)
                return lv_fail(err, LV_ERR_IO, "%s: cannot lock: %s", od->lock,
                               lv_strerror(e, text, sizeof text));
            pid[got > 0 ? got : 0] = '\0';
            pid[strcspn(pid, "\n")] = '\0';
            return lv_fail(err, LV_ERR_INPUT,
                           "results folder '%s' is in use by another lvsim (process %s, lock "
                           "%s): wait until it ends, or write elsewhere",
                           od->final, pid[0] ? pid : "?", od->lock);
        }
        struct stat a, b;
        if (fstat(fd, &a) == 0 && stat(od->lock, &b) == 0 && a.st_dev == b.st_dev &&
            a.st_ino == b.st_ino) {
            char pid[32];
            const int len = snprintf(pid, sizeof pid, "%ld\n", (long)getpid());
            if (ftruncate(fd, 0) != 0 || pwrite(fd, pid, (size_t)len, 0) != len) {
                /* the pid is only for the message of a refused writer */
            }
            od->lock_fd = fd;
            return LV_OK;
        }
        close(fd); /* its holder removed it as we took it: take the new one */
    }
    return lv_fail(err, LV_ERR_IO, "%s: cannot lock: the lock file keeps changing", od->lock);
}

static void release_lock(lv_outdir *od)
{
    if (od->lock_fd < 0)
        return;
    unlink(od->lock); /* while holding it: a writer that opened it retakes a new one */
    close(od->lock_fd);
    od->lock_fd = -1;
}

/* With the lock held, every parent/.base.staging-* is a killed run's: remove it. */
static lv_status clean_stale(lv_outdir *od, lv_err *err)
{
    DIR *d = opendir(od->parent);
    if (d == NULL)
        return LV_OK;
    char prefix[NAME_MAX + 32];
    snprintf(prefix, sizeof prefix, ".%s" STAGING_TAG, od->base);
    const size_t np = strlen(prefix);
    lv_status st = LV_OK;
    struct dirent *e;
    while (st == LV_OK && (e = readdir(d)) != NULL) {
        if (strncmp(e->d_name, prefix, np) != 0 || strlen(e->d_name) != np + 6)
            continue;
        char path[PATH_MAX + NAME_MAX + 2];
        snprintf(path, sizeof path, "%s/%s", od->parent, e->d_name);
        if (rm_tree(path) != 0) {
            char text[128];
            st = lv_fail(err, LV_ERR_IO, "cannot remove the stale staging folder '%s': %s",
                         path, lv_strerror(errno, text, sizeof text));
            break;
        }
        char **grown = realloc(od->stale, (od->n_stale + 1) * sizeof *grown);
        char *name = strdup(e->d_name);
        if (grown == NULL || name == NULL) {
            free(name);
            if (grown != NULL)
                od->stale = grown;
            st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
            break;
        }
        od->stale = grown;
        od->stale[od->n_stale++] = name;
    }
    closedir(d);
    return st;
}

static lv_outdir *outdir_new(void)
{
    lv_outdir *od = calloc(1, sizeof *od);
    if (od != NULL)
        od->lock_fd = -1;
    return od;
}

lv_status lv_outdir_begin(const char *outdir, const char *mission_file, lv_outdir **out,
                          lv_err *err)
{
    *out = NULL;
    lv_outdir *od = outdir_new();
    if (od == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    iso_now(od->started, sizeof od->started);
    char text[128];
    struct stat sb;
    lv_status st = set_names(od, outdir, err);
    if (st != LV_OK)
        goto fail;
    if (stat(od->final, &sb) == 0) {
        if (!S_ISDIR(sb.st_mode)) {
            st = lv_fail(err, LV_ERR_INPUT,
                         "'%s' is a file, not a folder: name a folder for the results",
                         od->final);
            goto fail;
        }
        if (!has_file(od->final, MANIFEST) && !has_file(od->final, "summary.json") &&
            !dir_is_empty(od->final)) {
            st = lv_fail(err, LV_ERR_INPUT,
                         "'%s' holds files lvsim did not write (no manifest.json or "
                         "summary.json): a results folder is replaced as a whole, so it is "
                         "left alone; name a new folder, an empty one or an earlier results "
                         "folder",
                         od->final);
            goto fail;
        }
    }
    if (mission_file != NULL) {
        char abs[PATH_MAX];
        od->mission_file = strdup(mission_file);
        od->mission_abs = strdup(realpath(mission_file, abs) != NULL ? abs : mission_file);
        if (od->mission_file == NULL || od->mission_abs == NULL) {
            st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
            goto fail;
        }
        if ((st = lv_sha256_file(mission_file, od->mission_sha, &od->mission_bytes, err)) != LV_OK)
            goto fail;
    }
    if ((st = mkdir_p(od->parent, err)) != LV_OK)
        goto fail;
    if ((st = take_lock(od, err)) != LV_OK)
        goto fail;
    if ((st = clean_stale(od, err)) != LV_OK)
        goto fail;
    snprintf(od->staging, sizeof od->staging, "%s/.%s" STAGING_TAG "XXXXXX", od->parent, od->base);
    if (mkdtemp(od->staging) == NULL) {
        const int e = errno;
        st = lv_fail(err, e == EACCES || e == EROFS ? LV_ERR_INPUT : LV_ERR_IO,
                     "cannot write in '%s' (for the results folder '%s'): %s", od->parent,
                     od->final, lv_strerror(e, text, sizeof text));
        od->staging[0] = '\0';
        goto fail;
    }
    *out = od;
    return LV_OK;
fail:
    lv_outdir_free(od);
    return st;
}

lv_status lv_outdir_open(const char *outdir, lv_outdir **out, lv_err *err)
{
    *out = NULL;
    lv_outdir *od = outdir_new();
    if (od == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    iso_now(od->started, sizeof od->started);
    od->in_place = 1;
    struct stat sb;
    lv_status st = set_names(od, outdir, err);
    if (st == LV_OK && (stat(od->final, &sb) != 0 || !S_ISDIR(sb.st_mode)))
        st = lv_fail(err, LV_ERR_INPUT, "'%s' is not a results folder (%s)", od->final,
                     errno == ENOENT ? "no such folder" : "not a folder");
    if (st == LV_OK)
        st = take_lock(od, err);
    if (st == LV_OK)
        st = clean_stale(od, err);
    if (st != LV_OK) {
        lv_outdir_free(od);
        return st;
    }
    *out = od;
    return LV_OK;
}

const char *lv_outdir_path(const lv_outdir *od) { return od->in_place ? od->final : od->staging; }
const char *lv_outdir_final(const lv_outdir *od) { return od->final; }
size_t lv_outdir_stale_count(const lv_outdir *od) { return od->n_stale; }
const char *lv_outdir_stale(const lv_outdir *od, size_t i)
{
    return i < od->n_stale ? od->stale[i] : NULL;
}
size_t lv_outdir_file_count(const lv_outdir *od) { return od->n_files; }
const lv_outdir_file *lv_outdir_files(const lv_outdir *od) { return od->files; }

/* ---- the manifest ---------------------------------------------------------------------- */

typedef struct file_list {
    char **names;
    size_t n, cap;
} file_list;

static int list_add(file_list *l, const char *name)
{
    if (l->n == l->cap) {
        const size_t cap = l->cap ? 2 * l->cap : 64;
        char **g = realloc(l->names, cap * sizeof *g);
        if (g == NULL)
            return -1;
        l->names = g;
        l->cap = cap;
    }
    if ((l->names[l->n] = strdup(name)) == NULL)
        return -1;
    l->n++;
    return 0;
}

/* Every regular file under root/rel (rel "" at the top), as paths relative to root; the
 * manifest itself and temporary files left out. Returns 0, or -1 (errno) */
static int walk(const char *root, const char *rel, file_list *l)
{
    char dir[PATH_MAX * 2];
    snprintf(dir, sizeof dir, "%s%s%s", root, rel[0] ? "/" : "", rel);
    DIR *d = opendir(dir);
    if (d == NULL)
        return -1;
    int rc = 0;
    struct dirent *e;
    while (rc == 0 && (e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        char sub[PATH_MAX];
        if ((size_t)snprintf(sub, sizeof sub, "%s%s%s", rel, rel[0] ? "/" : "", e->d_name) >=
            sizeof sub)
            continue;
        if (rel[0] == '\0' && (strcmp(e->d_name, MANIFEST) == 0 ||
                               strcmp(e->d_name, MANIFEST ".tmp") == 0))
            continue;
        struct stat sb;
        if (fstatat(dirfd(d), e->d_name, &sb, AT_SYMLINK_NOFOLLOW) != 0)
            continue;
        if (S_ISDIR(sb.st_mode))
            rc = walk(root, sub, l);
        else if (S_ISREG(sb.st_mode))
            rc = list_add(l, sub);
    }
    closedir(d);
    return rc;
}

static int by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static lv_status write_manifest(lv_outdir *od, const lv_outdir_record *rec, lv_err *err)
{
    const char *dir = lv_outdir_path(od);
    char path[PATH_MAX + 32], text[128], finished[32];
    iso_now(finished, sizeof finished);
    file_list l = {0};
    lv_status st = LV_OK;
    cJSON *root = NULL;
    char *json = NULL;
    if (walk(dir, "", &l) != 0) {
        st = lv_fail(err, errno == ENOMEM ? LV_ERR_NOMEM : LV_ERR_IO,
                     "cannot list the files of '%s': %s", dir, lv_strerror(errno, text, sizeof text));
        goto fail;
    }
    qsort(l.names, l.n, sizeof *l.names, by_name);
    /* open(): the existing manifest is kept and updated */
    snprintf(path, sizeof path, "%s/%s", dir, MANIFEST);
    if (od->in_place) {
        FILE *fp = fopen(path, "rb");
        if (fp != NULL) {
            char *buf = NULL;
            size_t cap = 0, n = 0, got;
            char chunk[8192];
            while ((got = fread(chunk, 1, sizeof chunk, fp)) > 0) {
                if (n + got + 1 > cap) {
                    cap = 2 * (n + got + 1);
                    char *g = realloc(buf, cap);
                    if (g == NULL)
                        break;
                    buf = g;
                }
                memcpy(buf + n, chunk, got);
                n += got;
            }
            fclose(fp);
            if (buf != NULL) {
                buf[n] = '\0';
                root = cJSON_Parse(buf);
                free(buf);
            }
            if (root != NULL && !cJSON_IsObject(root)) {
                cJSON_Delete(root);
                root = NULL;
            }
        }
    }
    if (root == NULL) {
        root = cJSON_CreateObject();
        if (root == NULL) {
            st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
            goto fail;
        }
        cJSON_AddStringToObject(root, "lvsim", LVSIM_VERSION);
        cJSON_AddStringToObject(root, "command", rec && rec->command ? rec->command : "run");
        cJSON_AddStringToObject(root, "status", rec && rec->status ? rec->status : "ok");
        if (od->mission_file != NULL) {
            cJSON *m = cJSON_AddObjectToObject(root, "mission");
            if (rec && rec->mission_name)
                cJSON_AddStringToObject(m, "name", rec->mission_name);
            cJSON_AddStringToObject(m, "file", od->mission_file);
            cJSON_AddStringToObject(m, "path", od->mission_abs);
            cJSON_AddStringToObject(m, "sha256", od->mission_sha);
            cJSON_AddNumberToObject(m, "bytes", (double)od->mission_bytes);
        } else {
            cJSON_AddNullToObject(root, "mission");
        }
        cJSON_AddStringToObject(root, "started", od->started);
        cJSON_AddStringToObject(root, "finished", finished);
        cJSON *notes = cJSON_AddArrayToObject(root, "notes");
        for (size_t i = 0; rec && i < rec->n_notes; i++)
            cJSON_AddItemToArray(notes, cJSON_CreateString(rec->notes[i]));
        cJSON_AddArrayToObject(root, "history");
    } else {
        cJSON *h = cJSON_GetObjectItemCaseSensitive(root, "history");
        if (!cJSON_IsArray(h)) {
            cJSON_DeleteItemFromObjectCaseSensitive(root, "history");
            h = cJSON_AddArrayToObject(root, "history");
        }
        cJSON *e = cJSON_CreateObject();
        cJSON_AddStringToObject(e, "command", rec && rec->command ? rec->command : "?");
        cJSON_AddStringToObject(e, "status", rec && rec->status ? rec->status : "ok");
        cJSON_AddStringToObject(e, "time", finished);
        cJSON_AddStringToObject(e, "lvsim", LVSIM_VERSION);
        cJSON *notes = cJSON_AddArrayToObject(e, "notes");
        for (size_t i = 0; rec && i < rec->n_notes; i++)
            cJSON_AddItemToArray(notes, cJSON_CreateString(rec->notes[i]));
        cJSON_AddItemToArray(h, e);
        cJSON_DeleteItemFromObjectCaseSensitive(root, "files");
    }
    cJSON *files = cJSON_AddArrayToObject(root, "files");
    od->files = calloc(l.n + 1, sizeof *od->files);
    if (files == NULL || od->files == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto fail;
    }
    for (size_t i = 0; i < l.n; i++) {
        char fpath[PATH_MAX * 2], hex[65];
        unsigned long long bytes = 0;
        snprintf(fpath, sizeof fpath, "%s/%s", dir, l.names[i]);
        if ((st = lv_sha256_file(fpath, hex, &bytes, err)) != LV_OK)
            goto fail;
        cJSON *f = cJSON_CreateObject();
        cJSON_AddStringToObject(f, "name", l.names[i]);
        cJSON_AddNumberToObject(f, "bytes", (double)bytes);
        cJSON_AddStringToObject(f, "sha256", hex);
        cJSON_AddItemToArray(files, f);
        od->files[i].name = l.names[i]; /* moves */
        od->files[i].bytes = bytes;
        l.names[i] = NULL;
        od->n_files = i + 1;
    }
    json = cJSON_Print(root);
    if (json == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto fail;
    }
    lv_atomic a;
    if ((st = lv_atomic_open(&a, path, err)) == LV_OK) {
        fputs(json, a.fp);
        fputc('\n', a.fp);
        st = lv_atomic_commit(&a, err);
    }
fail:
    for (size_t i = 0; i < l.n; i++)
        free(l.names[i]); /* those not moved */
    free(l.names);
    cJSON_free(json);
    cJSON_Delete(root);
    return st;
}

lv_status lv_outdir_commit(lv_outdir *od, const lv_outdir_record *rec, lv_err *err)
{
    if (od == NULL || od->committed)
        return lv_fail(err, LV_ERR_INPUT, "lv_outdir_commit: no folder, or committed twice");
    lv_status st = write_manifest(od, rec, err);
    if (st == LV_OK && !od->in_place) {
        char text[128];
        struct stat sb;
        int rc;
        if (lstat(od->final, &sb) == 0) {
            /* one step: OUTDIR gets the new folder, the staging name the old one */
            rc = renameat2(AT_FDCWD, od->staging, AT_FDCWD, od->final, RENAME_EXCHANGE);
            if (rc != 0 && (errno == EINVAL || errno == ENOSYS || errno == ENOTSUP)) {
                /* a file system without RENAME_EXCHANGE: two renames, a moment without
                 * OUTDIR, never a mixed one */
                char old[sizeof od->staging];
                snprintf(old, sizeof old, "%s/.%s" STAGING_TAG "XXXXXX", od->parent, od->base);
                if (mkdtemp(old) != NULL && rmdir(old) == 0 && rename(od->final, old) == 0) {
                    rc = rename(od->staging, od->final);
                    if (rc != 0)
                        rename(old, od->final);
                    else
                        snprintf(od->staging, sizeof od->staging, "%s", old);
                }
            }
        } else {
            rc = rename(od->staging, od->final);
            if (rc == 0)
                od->staging[0] = '\0';
        }
        if (rc != 0)
            st = lv_fail(err, LV_ERR_IO, "cannot replace '%s' by '%s': %s", od->final,
                         od->staging, lv_strerror(errno, text, sizeof text));
        else if (od->staging[0] != '\0')
            rm_tree(od->staging); /* the old results; a failure leaves a stale folder that the
                                     next writer removes */
        if (rc == 0)
            od->staging[0] = '\0';
    }
    od->committed = st == LV_OK;
    release_lock(od);
    return st;
}

void lv_outdir_free(lv_outdir *od)
{
    if (od == NULL)
        return;
    if (!od->in_place && od->staging[0] != '\0')
        rm_tree(od->staging);
    release_lock(od);
    for (size_t i = 0; i < od->n_stale; i++)
        free(od->stale[i]);
    free(od->stale);
    for (size_t i = 0; i < od->n_files; i++)
        free((char *)od->files[i].name);
    free(od->files);
    free(od->mission_file);
    free(od->mission_abs);
    free(od);
}
