/* outdir.c - results folders that lvsim replaces only where it can prove it wrote them
 * (lv_outdir.h). A folder is lvsim's when its manifest.json, written by lvsim, lists every
 * file in it with its size and SHA-256 (a nested results folder by its own manifest); a file
 * that is not listed, or that changed since, is the user's. Every writer works in a staging
 * folder beside OUTDIR - empty for a new run, a hard-linked replica for a command that adds
 * files - and the commit carries the user's files into it as hard links, checks that no
 * user's file was replaced, writes the manifest and exchanges the two folders in one
 * renameat2(RENAME_EXCHANGE) (Linux >= 3.15). A lock beside OUTDIR refuses a second writer;
 * stale staging folders of killed runs are removed when they are provably lvsim's. The
 * library never prints: what was cleaned and kept is returned to the caller. */
#define _GNU_SOURCE /* renameat2, RENAME_EXCHANGE (glibc >= 2.28), getrandom */

#include <cjson/cJSON.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <fnmatch.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "core/status.h"
#include "io/atomic.h"
#include "io/readfile.h"
#include "lvsim/lv_outdir.h"
#include "lvsim/lvsim.h"
#include "post/export_int.h"
#include "post/json_print.h"

#define MANIFEST "manifest.json"
#define STAGING_TAG ".staging-"
#define MARKER ".lvsim-staging" /* inside a staging folder while lvsim fills it */
#define LOCK_MAGIC "lvsim "     /* a lock file's first bytes: "lvsim <pid>\n" */
#define MAX_DEPTH 64            /* folder nesting a survey follows */
#define NAMES_IN_MESSAGE 4

static const char *why(int e, char *buf, size_t cap) { return lv_strerror(e, buf, cap); }

static void iso_now(char *buf, size_t cap)
{
    time_t t = time(NULL);
    struct tm tm;
    if (gmtime_r(&t, &tm) == NULL || strftime(buf, cap, "%Y-%m-%dT%H:%M:%SZ", &tm) == 0)
        snprintf(buf, cap, "unknown");
}

static lv_status nomem(lv_err *err) { return lv_fail(err, LV_ERR_NOMEM, "out of memory"); }

/* `s` for a message: control characters (a name holding an escape sequence) as '?',
 * truncated to cap. */
static void printable(const char *s, char *out, size_t cap)
{
    size_t n = 0;
    for (; s[n] != '\0' && n + 1 < cap; n++)
        out[n] = (unsigned char)s[n] < 0x20 || s[n] == 0x7f ? '?' : s[n];
    out[n] = '\0';
}

/* "a/b", or the one that is not empty. Returns 0, or -1 when it does not fit. */
static int join(char *buf, size_t cap, const char *a, const char *b)
{
    const int n = a[0] && b[0] ? snprintf(buf, cap, "%s/%s", a, b)
                               : snprintf(buf, cap, "%s", a[0] ? a : b);
    return n >= 0 && (size_t)n < cap ? 0 : -1;
}

/* ---- the manifest of a folder ------------------------------------------------------------- */

typedef struct man_file {
    const char *name; /* relative to the manifest's folder */
    double bytes;
    const char *sha;
    const char *stamp; /* "inode:ctime" when the manifest was written (file_stamp), or NULL */
} man_file;

/* A file's identity and last status change, "st_ino:st_ctim" (seconds.nanoseconds): written
 * into the manifest beside each digest and compared by the next command, which trusts an
 * unchanged stamp without reading the file. Any write, truncate, utime (a modification time set
 * back after an edit), chmod or rename of the file moves its ctime, which no call can set; a
 * copy is another inode. Renaming the folder that holds it changes neither. */
static void file_stamp(const struct stat *sb, char *buf, size_t cap)
{
    snprintf(buf, cap, "%llu:%lld.%09ld", (unsigned long long)sb->st_ino,
             (long long)sb->st_ctim.tv_sec, (long)sb->st_ctim.tv_nsec);
}

typedef struct manifest {
    cJSON *root;           /* NULL: no manifest, or one lvsim did not write */
    man_file *files;       /* sorted by name */
    size_t n_files;
    cJSON *live;           /* "live": names lvsim owns whatever they hold (a campaign database) */
    struct timespec mtime; /* the manifest's own modification time */
} manifest;

static int by_man_name(const void *a, const void *b)
{
    return strcmp(((const man_file *)a)->name, ((const man_file *)b)->name);
}

static void man_free(manifest *m)
{
    cJSON_Delete(m->root);
    free(m->files);
    memset(m, 0, sizeof *m);
}

static char *read_all(const char *path, size_t limit)
{
    FILE *fp = fopen(path, "rb");
    if (fp == NULL)
        return NULL;
    char *buf = NULL;
    size_t n = 0, cap = 0, got;
    char chunk[8192];
    while ((got = fread(chunk, 1, sizeof chunk, fp)) > 0) {
        if (n + got + 1 > cap) {
            cap = 2 * (n + got + 1);
            char *g = n + got > limit ? NULL : realloc(buf, cap);
            if (g == NULL) {
                free(buf);
                fclose(fp);
                return NULL;
            }
            buf = g;
        }
        memcpy(buf + n, chunk, got);
        n += got;
    }
    fclose(fp);
    if (buf != NULL)
        buf[n] = '\0';
    return buf;
}

/* 64 lowercase hex digits: a SHA-256 as lvsim writes it. */
static int is_sha256_hex(const char *s)
{
    size_t n = 0;
    for (; s[n] != '\0'; n++)
        if (!((s[n] >= '0' && s[n] <= '9') || (s[n] >= 'a' && s[n] <= 'f')))
            return 0;
    return n == 64;
}

/* Loads DIR/manifest.json when lvsim wrote it: a JSON object with "lvsim" (the version that
 * wrote it) and "files", each {name, bytes, sha256}. Returns 1 (m filled), 0 (none or not
 * lvsim's: m zeroed), -1 (out of memory). */
static int man_load(const char *dir, manifest *m)
{
    memset(m, 0, sizeof *m);
    char path[PATH_MAX + 32];
    struct stat sb;
    if (join(path, sizeof path, dir, MANIFEST) != 0 || lstat(path, &sb) != 0 ||
        !S_ISREG(sb.st_mode))
        return 0;
    char *text = read_all(path, (size_t)1 << 30);
    if (text == NULL)
        return 0;
    cJSON *root = cJSON_Parse(text);
    free(text);
    const cJSON *files = cJSON_GetObjectItemCaseSensitive(root, "files");
    const cJSON *ver = cJSON_GetObjectItemCaseSensitive(root, "lvsim");
    if (!cJSON_IsObject(root) || !cJSON_IsString(ver) || ver->valuestring[0] == '\0' ||
        !cJSON_IsString(cJSON_GetObjectItemCaseSensitive(root, "command")) ||
        !cJSON_IsString(cJSON_GetObjectItemCaseSensitive(root, "status")) ||
        !cJSON_IsArray(files)) {
        cJSON_Delete(root);
        return 0;
    }
    const int n = cJSON_GetArraySize(files);
    m->files = calloc((size_t)n + 1, sizeof *m->files);
    if (m->files == NULL) {
        cJSON_Delete(root);
        return -1;
    }
    const cJSON *f;
    cJSON_ArrayForEach(f, files)
    {
        const cJSON *name = cJSON_GetObjectItemCaseSensitive(f, "name");
        const cJSON *bytes = cJSON_GetObjectItemCaseSensitive(f, "bytes");
        const cJSON *sha = cJSON_GetObjectItemCaseSensitive(f, "sha256");
        const cJSON *stamp = cJSON_GetObjectItemCaseSensitive(f, "stamp");
        if (!cJSON_IsString(name) || !cJSON_IsNumber(bytes) || !cJSON_IsString(sha) ||
            !is_sha256_hex(sha->valuestring) || !(bytes->valuedouble >= 0.0))
            continue; /* an entry lvsim would not write proves nothing */
        m->files[m->n_files].name = name->valuestring;
        m->files[m->n_files].bytes = bytes->valuedouble;
        m->files[m->n_files].sha = sha->valuestring;
        m->files[m->n_files].stamp = cJSON_IsString(stamp) ? stamp->valuestring : NULL;
        m->n_files++;
    }
    if (m->n_files > 1)
        qsort(m->files, m->n_files, sizeof *m->files, by_man_name);
    cJSON *live = cJSON_GetObjectItemCaseSensitive(root, "live");
    m->live = cJSON_IsArray(live) ? live : NULL;
    m->root = root;
    m->mtime = sb.st_mtim;
    return 1;
}

static const man_file *man_find(const manifest *m, const char *name)
{
    const man_file key = {name, 0.0, NULL, NULL};
    return m->n_files ? bsearch(&key, m->files, m->n_files, sizeof key, by_man_name) : NULL;
}

static int man_is_live(const manifest *m, const char *name)
{
    const cJSON *e;
    cJSON_ArrayForEach(e, m->live)
    {
        if (cJSON_IsString(e) && strcmp(e->valuestring, name) == 0)
            return 1;
    }
    return 0;
}

/* ---- a survey of a folder: what is lvsim's and what is not --------------------------------- */

enum { E_FILE, E_DIR, E_LINK, E_FIFO, E_OTHER };
enum { OWNED, FOREIGN, JUNK }; /* JUNK: lvsim's leftovers (stale locks and staging folders) */

typedef struct od_entry {
    char *name; /* relative to the surveyed folder: "plots/altitude.png" */
    int kind, owner;
    const char *reason; /* FOREIGN: why */
    struct stat sb;
    char sha[65]; /* OWNED files: the manifest's SHA-256 ("" when live) */
} od_entry;

typedef struct od_list {
    od_entry *e;
    size_t n, cap;
} od_list;

static void list_free(od_list *l)
{
    for (size_t i = 0; i < l->n; i++)
        free(l->e[i].name);
    free(l->e);
    memset(l, 0, sizeof *l);
}

static od_entry *list_add(od_list *l, const char *name, const struct stat *sb)
{
    if (l->n == l->cap) {
        const size_t cap = l->cap ? 2 * l->cap : 64;
        od_entry *g = realloc(l->e, cap * sizeof *g);
        if (g == NULL)
            return NULL;
        l->e = g;
        l->cap = cap;
    }
    od_entry *e = &l->e[l->n];
    memset(e, 0, sizeof *e);
    if ((e->name = strdup(name)) == NULL)
        return NULL;
    e->sb = *sb;
    e->kind = S_ISREG(sb->st_mode)    ? E_FILE
              : S_ISDIR(sb->st_mode)  ? E_DIR
              : S_ISLNK(sb->st_mode)  ? E_LINK
              : S_ISFIFO(sb->st_mode) ? E_FIFO
                                      : E_OTHER;
    l->n++;
    return e;
}

static int is_staging_name(const char *name)
{
    const char *tag = strstr(name, STAGING_TAG);
    return name[0] == '.' && tag != NULL && strlen(tag) == sizeof STAGING_TAG - 1 + 6;
}

/* The names lvsim writes at the top of a run's results folder (lvsim run, lv_outdir_begin)
 * and of a campaign's (lvsim mc, lv_outdir_open_live); the folders whose contents are all its
 * own (plots, the staged viewer, a campaign's kept runs). fnmatch(3) patterns. */
static const char *const run_names[] = {"summary.json", "index.html", "key_figures.json",
                                        "body_*.csv", NULL};
static const char *const mc_names[] = {"stats.json", "stats.csv", "ellipses.csv", "outcomes.csv",
                                       "sensitivity.csv", "footprint.kml", "index.html",
                                       "campaign.db", "campaign.db-journal", NULL};
static const char *const own_folders[] = {"plots", "viewer", "runs", NULL};

static int matches(const char *const *patterns, const char *name)
{
    for (size_t i = 0; patterns[i] != NULL; i++)
        if (fnmatch(patterns[i], name, 0) == 0)
            return 1;
    return 0;
}

/* A name a run writes: run_names, a phase's result file "phase_*<ext>" of a registered result
 * format (lv_io.h), or an export's files (export_int.h). */
static int is_run_name(const char *name)
{
    if (matches(run_names, name))
        return 1;
    const char *ext;
    for (size_t i = 0; lv_result_format_info(i, &ext, NULL) != NULL; i++) {
        const size_t n = strlen(name), m = strlen(ext);
        if (strncmp(name, "phase_", 6) == 0 && n >= 6 + m && strcmp(name + n - m, ext) == 0)
            return 1;
    }
    for (size_t i = 0; lv_ex_formats[i] != NULL; i++)
        if (fnmatch(lv_ex_formats[i]->pattern, name, 0) == 0)
            return 1;
    return 0;
}

/* 1 when every file under `path` (depth levels at most) is lvsim's to remove: a hard link of
 * another file (the replica of a results folder: its data stays in OUTDIR), a name lvsim
 * writes (or one of its temporary files), or anything in one of lvsim's own folders. */
static int all_removable(const char *path, int depth, int in_own)
{
    DIR *d = opendir(path);
    if (d == NULL || depth > MAX_DEPTH) {
        if (d != NULL)
            closedir(d);
        return 0;
    }
    int ok = 1;
    struct dirent *e;
    while (ok && (e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        char full[PATH_MAX];
        struct stat sb;
        if (snprintf(full, sizeof full, "%s/%s", path, e->d_name) >= (int)sizeof full ||
            lstat(full, &sb) != 0) {
            ok = 0;
            break;
        }
        if (S_ISDIR(sb.st_mode))
            ok = all_removable(full, depth + 1,
                               in_own || (depth == 0 && matches(own_folders, e->d_name)));
        else
            ok = in_own || sb.st_nlink > 1 || strcmp(e->d_name, MARKER) == 0 ||
                 strcmp(e->d_name, MANIFEST) == 0 || is_run_name(e->d_name) ||
                 matches(mc_names, e->d_name) || fnmatch("*.tmp*", e->d_name, 0) == 0;
    }
    closedir(d);
    return ok;
}

/* A staging folder lvsim may remove: empty, marked as being filled by lvsim, or holding an
 * lvsim manifest (a folder replaced by an exchange, whose removal was cut short) - and in
 * the last two cases holding nothing but what lvsim writes there (all_removable: a user's
 * file put into a folder that looks like lvsim's is never removed with it). */
static int staging_is_lvsims(const char *path)
{
    DIR *d = opendir(path);
    if (d == NULL)
        return 0;
    int empty = 1, marked = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        empty = 0;
        marked |= strcmp(e->d_name, MARKER) == 0;
    }
    closedir(d);
    if (empty)
        return 1;
    if (!marked) {
        manifest m;
        const int lv = man_load(path, &m) == 1;
        man_free(&m);
        if (!lv)
            return 0;
    }
    return all_removable(path, 0, 0);
}

/* A lock file lvsim left: ".NAME.lock" holding exactly "lvsim <pid>\n" (what take_lock
 * writes; empty too when `empty_ok`: the moment between its creation and the write). */
static int lock_is_lvsims(const char *path, const char *name, const struct stat *sb,
                          int empty_ok)
{
    const size_t n = strlen(name);
    if (name[0] != '.' || n < 6 || strcmp(name + n - 5, ".lock") != 0 || !S_ISREG(sb->st_mode))
        return 0;
    if (sb->st_size == 0)
        return empty_ok;
    if (sb->st_size > 40)
        return 0;
    char buf[48] = "";
    FILE *fp = fopen(path, "rb");
    if (fp == NULL)
        return 0;
    const size_t got = fread(buf, 1, sizeof buf - 1, fp);
    fclose(fp);
    buf[got] = '\0';
    const size_t lm = sizeof LOCK_MAGIC - 1;
    if (got < lm + 2 || memcmp(buf, LOCK_MAGIC, lm) != 0 || buf[got - 1] != '\n')
        return 0;
    for (size_t i = lm; i + 1 < got; i++)
        if (buf[i] < '0' || buf[i] > '9')
            return 0;
    return 1;
}

typedef struct survey_ctx {
    const char *root; /* the folder surveyed */
    dev_t dev;        /* its device: every entry must be on it */
    od_list *l;
    int hashed;       /* files hashed because they were newer than their manifest */
    char *bad;        /* the entry a failure is about (relative), or NULL */
} survey_ctx;

static int by_cstr(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Surveys root/rel against manifest m, whose folder is root/mrel (names in m are relative to
 * it). Returns 1 when anything under rel is FOREIGN, 0 when not, -1 out of memory or a
 * folder that cannot be read (errno). */
static int survey(survey_ctx *c, const char *rel, const manifest *m, size_t mrel_len, int depth)
{
    char dir[PATH_MAX];
    if (join(dir, sizeof dir, c->root, rel) != 0) {
        errno = ENAMETOOLONG;
        return -1;
    }
    DIR *d = opendir(dir);
    if (d == NULL) {
        const int e = errno;
        if (c->bad == NULL)
            c->bad = strdup(rel);
        errno = e;
        return -1;
    }
    char **names = NULL;
    size_t n = 0, cap = 0;
    struct dirent *de;
    int rc = 0;
    while ((de = readdir(d)) != NULL) {
        if (strcmp(de->d_name, ".") == 0 || strcmp(de->d_name, "..") == 0)
            continue;
        if (n == cap) {
            cap = cap ? 2 * cap : 32;
            char **g = realloc(names, cap * sizeof *g);
            if (g == NULL) {
                rc = -1;
                break;
            }
            names = g;
        }
        if ((names[n] = strdup(de->d_name)) == NULL) {
            rc = -1;
            break;
        }
        n++;
    }
    closedir(d);
    if (rc == 0 && n > 1)
        qsort(names, n, sizeof *names, by_cstr);
    int any_foreign = 0;
    for (size_t i = 0; rc >= 0 && i < n; i++) {
        char r[PATH_MAX], full[PATH_MAX];
        struct stat sb;
        if (join(r, sizeof r, rel, names[i]) != 0 || join(full, sizeof full, c->root, r) != 0) {
            /* a name lvsim cannot hold: never taken for "not there" */
            c->bad = strdup(names[i]);
            errno = ENAMETOOLONG;
            rc = -1;
            break;
        }
        if (lstat(full, &sb) != 0) {
            const int e = errno;
            if (e == ENOENT)
                continue; /* gone meanwhile */
            c->bad = strdup(r);
            errno = e;
            rc = -1; /* a folder that cannot be searched: its files are not seen */
            break;
        }
        if (sb.st_dev != c->dev) {
            c->bad = strdup(r);
            errno = EXDEV;
            rc = -1; /* a mount point: its files could not be kept by a link */
            break;
        }
        const char *mname = r + mrel_len + (mrel_len ? 1 : 0); /* relative to m's folder */
        od_entry *e = list_add(c->l, r, &sb);
        if (e == NULL) {
            rc = -1;
            break;
        }
        const size_t idx = c->l->n - 1;
        e->owner = OWNED;
        if (m->root != NULL && strcmp(mname, MANIFEST) == 0 && S_ISREG(sb.st_mode)) {
            /* the manifest itself: lvsim's (the top one is rewritten by every commit) */
        } else if (S_ISDIR(sb.st_mode)) {
            if (is_staging_name(names[i]) && staging_is_lvsims(full)) {
                e->owner = JUNK;
                continue;
            }
            if (depth >= MAX_DEPTH) { /* never carry a folder whose contents were not seen */
                errno = ELOOP;
                rc = -1;
                break;
            }
            manifest sub;
            const int has_sub = man_load(full, &sub);
            if (has_sub < 0) {
                rc = -1;
                break;
            }
            const size_t before = c->l->n;
            const int f = has_sub ? survey(c, r, &sub, strlen(r), depth + 1)
                                  : survey(c, r, m, mrel_len, depth + 1);
            if (has_sub)
                man_free(&sub);
            if (f < 0) {
                rc = -1;
                break;
            }
            e = &c->l->e[idx]; /* the list may have moved */
            int foreign = f;
            if (!foreign && c->l->n == before && !has_sub) {
                /* an empty folder: lvsim's only when the manifest lists something under it */
                char prefix[PATH_MAX];
                snprintf(prefix, sizeof prefix, "%s/", mname);
                const size_t lp = strlen(prefix);
                int under = 0;
                for (size_t k = 0; !under && k < m->n_files; k++)
                    under = strncmp(m->files[k].name, prefix, lp) == 0;
                foreign = !under && !man_is_live(m, mname);
            }
            if (foreign) {
                e->owner = FOREIGN;
                e->reason = "not written by lvsim";
            }
        } else if (S_ISREG(sb.st_mode)) {
            const man_file *mf = m->root != NULL ? man_find(m, mname) : NULL;
            if (m->root != NULL && man_is_live(m, mname)) {
                /* lvsim's whatever it holds (a campaign database, growing) */
            } else if (mf != NULL && mf->bytes == (double)sb.st_size) {
                /* its stamp unchanged: the file the manifest vouched for, not read; a manifest
                 * written before stamps vouches for a file not newer than itself (an edit with
                 * its mtime set back went unseen there) */
                char now[64];
                file_stamp(&sb, now, sizeof now);
                const int newer = mf->stamp != NULL
                                      ? strcmp(mf->stamp, now) != 0
                                      : sb.st_mtim.tv_sec > m->mtime.tv_sec ||
                                            (sb.st_mtim.tv_sec == m->mtime.tv_sec &&
                                             sb.st_mtim.tv_nsec > m->mtime.tv_nsec);
                char hex[65];
                if (newer) {
                    lv_err ignored;
                    c->hashed++;
                    if (lv_sha256_file(full, hex, NULL, &ignored) != LV_OK ||
                        strcmp(hex, mf->sha) != 0) {
                        e->owner = FOREIGN;
                        e->reason = "changed since lvsim wrote it";
                    }
                }
                if (e->owner == OWNED)
                    snprintf(e->sha, sizeof e->sha, "%s", mf->sha);
            } else if (lock_is_lvsims(full, names[i], &sb, 0) ||
                       (strcmp(names[i], MARKER) == 0 && sb.st_size == 0)) {
                e->owner = JUNK; /* a stale lock; the marker of an exchange cut short */
            } else {
                e->owner = FOREIGN;
                e->reason = mf != NULL ? "changed since lvsim wrote it" : "not written by lvsim";
            }
        } else {
            e->owner = FOREIGN; /* lvsim writes no links, pipes or devices */
            e->reason = "not written by lvsim";
        }
        any_foreign |= c->l->e[idx].owner == FOREIGN;
    }
    for (size_t i = 0; i < n; i++)
        free(names[i]);
    free(names);
    return rc < 0 ? -1 : any_foreign;
}

/* Surveys DIR (which exists); *is_lvsim: it has an lvsim manifest. */
static lv_status survey_dir(const char *dir, od_list *l, int *is_lvsim, lv_err *err)
{
    manifest m;
    struct stat rs;
    if (stat(dir, &rs) != 0) {
        char text[128];
        return lv_fail(err, LV_ERR_IO, "cannot read the folder '%s': %s", dir,
                       why(errno, text, sizeof text));
    }
    const int lv = man_load(dir, &m);
    if (lv < 0)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    survey_ctx c = {dir, rs.st_dev, l, 0, NULL};
    const int rc = survey(&c, "", &m, 0, 0);
    man_free(&m);
    *is_lvsim = lv == 1;
    if (rc < 0) {
        char text[128], name[256];
        const int e = errno;
        printable(c.bad != NULL ? c.bad : "", name, sizeof name);
        free(c.bad);
        list_free(l);
        if (e == ENOMEM)
            return nomem(err);
        if (e == EXDEV)
            return lv_fail(err, LV_ERR_INPUT,
                           "'%s/%s' is on another file system (a mount point): lvsim keeps the "
                           "files of a results folder by hard links and replaces it with one "
                           "rename, which a mount point cannot take; move it out, or write "
                           "elsewhere", dir, name);
        return lv_fail(err, e == EACCES || e == ENAMETOOLONG || e == ELOOP ? LV_ERR_INPUT : LV_ERR_IO,
                       "cannot read the folder '%s'%s%s%s: %s: lvsim replaces nothing it cannot "
                       "see", dir, name[0] ? " (at '" : "", name, name[0] ? "')" : "",
                       why(e, text, sizeof text));
    }
    return LV_OK;
}

/* "a, b/, c and 3 more" of the FOREIGN entries that are not under a FOREIGN folder. */
static void foreign_names(const od_list *l, char *buf, size_t cap, size_t *count)
{
    size_t shown = 0, total = 0, len = 0;
    const char *top = NULL; /* the last FOREIGN folder named: its contents go with it */
    buf[0] = '\0';
    for (size_t i = 0; i < l->n; i++) {
        const od_entry *e = &l->e[i];
        if (e->owner != FOREIGN)
            continue;
        if (top != NULL && strncmp(e->name, top, strlen(top)) == 0 && e->name[strlen(top)] == '/')
            continue;
        top = e->kind == E_DIR ? e->name : top;
        total++;
        if (shown < NAMES_IN_MESSAGE && len + 1 < cap) {
            char pname[256];
            printable(e->name, pname, sizeof pname);
            const int w = snprintf(buf + len, cap - len, "%s%s%s%s%s", shown ? ", " : "", pname,
                                   e->kind == E_DIR ? "/" : "",
                                   strcmp(e->reason, "not written by lvsim") ? ": " : "",
                                   strcmp(e->reason, "not written by lvsim") ? e->reason : "");
            len += w > 0 ? (size_t)w : 0;
            shown++;
        }
    }
    if (total > shown && len + 1 < cap)
        snprintf(buf + len, cap - len, " and %zu more", total - shown);
    if (len >= cap)
        buf[cap - 1] = '\0';
    *count = total;
}

/* ---- removing a folder tree, never following a link ----------------------------------- */

/* Removes everything inside the folder open as `fd` (which it closes) but the entry named
 * `keep` (NULL: none). */
static int rm_contents(int fd, const char *keep)
{
    DIR *d = fdopendir(fd);
    if (d == NULL) {
        close(fd);
        return -1;
    }
    int rc = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0 ||
            (keep != NULL && strcmp(e->d_name, keep) == 0))
            continue;
        struct stat sb;
        if (fstatat(dirfd(d), e->d_name, &sb, AT_SYMLINK_NOFOLLOW) != 0) {
            if (errno != ENOENT) /* gone already: what removing it wanted */
                rc = -1;
            continue;
        }
        if (S_ISDIR(sb.st_mode)) {
            /* a read-only folder (carried with its mode) must be writable to be emptied */
            if (fchmodat(dirfd(d), e->d_name, 0700, 0) != 0) {
            }
            int sub = openat(dirfd(d), e->d_name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
            if (sub < 0 ? errno != ENOENT
                        : rm_contents(sub, NULL) != 0 ||
                              (unlinkat(dirfd(d), e->d_name, AT_REMOVEDIR) != 0 && errno != ENOENT))
                rc = -1;
        } else if (unlinkat(dirfd(d), e->d_name, 0) != 0 && errno != ENOENT) {
            rc = -1;
        }
    }
    closedir(d);
    return rc;
}

/* Removes a staging folder (or a folder replaced by one), its marker last: a kill halfway
 * leaves a folder that is still provably lvsim's, which the next writer removes. */
static int rm_tree(const char *path)
{
    struct stat sb;
    if (lstat(path, &sb) == 0 && S_ISDIR(sb.st_mode) && chmod(path, 0700) != 0) {
    }
    int fd = open(path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0)
        return errno == ENOENT ? 0 : -1;
    if (rm_contents(fd, MARKER) != 0)
        return -1;
    char marker[PATH_MAX + 32];
    if (join(marker, sizeof marker, path, MARKER) == 0)
        unlink(marker);
    return rmdir(path);
}

/* ---- the folder object ----------------------------------------------------------------- */

enum { MODE_BEGIN, MODE_OPEN, MODE_LIVE };

struct lv_outdir {
    char final[PATH_MAX];   /* OUTDIR */
    char parent[PATH_MAX];  /* its folder ("." for a bare name) */
    char base[NAME_MAX + 1];
    char lock[PATH_MAX + NAME_MAX + 16];    /* parent/.base.lock */
    char staging[PATH_MAX + NAME_MAX + 32]; /* parent/.base.staging-XXXXXX; "" when none */
    int lock_fd;            /* -1: not locked */
    int mode;               /* MODE_*: what lv_outdir_path names before and after staging */
    unsigned flags;
    int committed;
    char started[32];       /* ISO 8601 UTC */
    char *mission_file;     /* as given, absolute path, SHA-256, size; NULL: none */
    char *mission_abs;
    char mission_sha[65];
    unsigned long long mission_bytes;
    char **live;            /* names lvsim owns whatever they hold (MODE_LIVE) */
    size_t n_live;
    char **stale;           /* removed stale staging folders */
    size_t n_stale;
    char **kept;            /* files lvsim did not write, carried into the new folder */
    size_t n_kept;
    char **dir_rel;         /* folders carried into the staging folder, in the order made */
    mode_t *dir_mode;       /* and the modes they get just before the exchange */
    size_t n_dirs;
    lv_outdir_file *files;  /* after commit */
    size_t n_files;
    char *prev_manifest;    /* MODE_LIVE: the manifest before the open wrote its own, and */
    size_t prev_len;        /* its length (lv_outdir_discard); NULL: there was none */
    int made;               /* MODE_LIVE: OUTDIR was made by the open */
};


static int strv_add(char ***v, size_t *n, const char *s)
{
    char **g = realloc(*v, (*n + 1) * sizeof *g);
    if (g == NULL)
        return -1;
    *v = g;
    if ((g[*n] = strdup(s)) == NULL)
        return -1;
    (*n)++;
    return 0;
}

static void strv_free(char **v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        free(v[i]);
    free(v);
}

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
        if (mkdir(buf, 0777) != 0 && errno != EEXIST) /* the umask decides the mode */
            return lv_fail(err, errno == EACCES || errno == EROFS ? LV_ERR_INPUT : LV_ERR_IO,
                           "cannot create folder '%s': %s", buf, why(errno, text, sizeof text));
        if (stat(buf, &sb) != 0)
            return lv_fail(err, LV_ERR_INPUT, "cannot use folder '%s': %s", buf,
                           why(errno, text, sizeof text));
        if (!S_ISDIR(sb.st_mode))
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
    for (size_t i = 0; i < n; i++) /* every message and the manifest print it on one line */
        if ((unsigned char)outdir[i] < 0x20 || outdir[i] == 0x7f)
            return lv_fail(err, LV_ERR_INPUT, "the results folder's name holds a control "
                           "character (byte %zu is 0x%02x): name another folder", i + 1,
                           (unsigned)(unsigned char)outdir[i]);
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
                           outdir, why(errno, text, sizeof text));
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
                       outdir, strcmp(path, "/") == 0 ? "" : path);
    if (strlen(base) > NAME_MAX - 20)
        return lv_fail(err, LV_ERR_INPUT, "results folder name '%s' is too long", base);
    /* its staging folder's files (phase_<k>_<name>.failed.mat.tmp..., plots/, viewer/...)
     * must fit PATH_MAX too: refused now, not as a phase failing at its first row */
    enum { ROOM = 300 };
    if (n > PATH_MAX - ROOM)
        return lv_fail(err, LV_ERR_INPUT,
                       "results folder path of %zu bytes is too long: lvsim needs room for the "
                       "names of its files under it (at most %d bytes)", n, PATH_MAX - ROOM);
    snprintf(od->final, sizeof od->final, "%s", path);
    snprintf(od->base, sizeof od->base, "%.*s", (int)(sizeof od->base - 1), base); /* fits */
    if (slash == NULL)
        snprintf(od->parent, sizeof od->parent, ".");
    else if (slash == path)
        snprintf(od->parent, sizeof od->parent, "/");
    else
        snprintf(od->parent, sizeof od->parent, "%.*s", (int)(slash - path), path);
    snprintf(od->lock, sizeof od->lock, "%s/.%s.lock", od->parent, od->base);
    return LV_OK;
}

/* ---- the lock ------------------------------------------------------------------------ */

/* flock on parent/.base.lock, refusing when held. The file says "lvsim <pid>"; one that says
 * anything else is not lvsim's and is left alone. It is unlinked by its holder when done; a
 * lock taken on a file that was unlinked meanwhile is retaken on the new one. */
static lv_status take_lock(lv_outdir *od, lv_err *err)
{
    char text[128];
    for (int attempt = 0; attempt < 20; attempt++) {
        int fd = open(od->lock, O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0666);
        if (fd < 0)
            return lv_fail(err, errno == EACCES || errno == EROFS || errno == ELOOP ? LV_ERR_INPUT
                                                                                    : LV_ERR_IO,
                           "cannot write in '%s' (the lock file %s): %s", od->parent, od->lock,
                           why(errno, text, sizeof text));
        struct stat ls;
        if (fstat(fd, &ls) != 0 || !S_ISREG(ls.st_mode) ||
            !lock_is_lvsims(od->lock, strrchr(od->lock, '/') + 1, &ls, 1)) {
            close(fd);
            return lv_fail(err, LV_ERR_INPUT,
                           "'%s' beside the results folder is not lvsim's lock file: it is left "
                           "alone; move it away or write elsewhere", od->lock);
        }
        if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
            const int e = errno;
            char pid[40] = "";
            ssize_t got = pread(fd, pid, sizeof pid - 1, 0);
            close(fd);
            if (e != EWOULDBLOCK)
                return lv_fail(err, LV_ERR_IO, "%s: cannot lock: %s", od->lock,
                               why(e, text, sizeof text));
            pid[got > 0 ? got : 0] = '\0';
            pid[strcspn(pid, "\n")] = '\0';
            const char *num = strncmp(pid, LOCK_MAGIC, sizeof LOCK_MAGIC - 1) == 0
                                  ? pid + sizeof LOCK_MAGIC - 1
                                  : pid;
            return lv_fail(err, LV_ERR_INPUT,
                           "results folder '%s' is in use by another lvsim (process %s, lock "
                           "%s): wait until it ends, or write elsewhere",
                           od->final, num[0] ? num : "?", od->lock);
        }
        struct stat a, b;
        if (fstat(fd, &a) == 0 && stat(od->lock, &b) == 0 && a.st_dev == b.st_dev &&
            a.st_ino == b.st_ino) {
            char pid[40];
            const int len = snprintf(pid, sizeof pid, LOCK_MAGIC "%ld\n", (long)getpid());
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

/* With the lock held, every parent/.base.staging-XXXXXX that is provably lvsim's is a killed
 * run's: remove it. One that is not is left alone. */
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
        struct stat sb;
        if (lstat(path, &sb) != 0 || !S_ISDIR(sb.st_mode) || !staging_is_lvsims(path))
            continue;
        if (rm_tree(path) != 0) {
            char text[128];
            st = lv_fail(err, LV_ERR_IO, "cannot remove the stale staging folder '%s': %s",
                         path, why(errno, text, sizeof text));
            break;
        }
        if (strv_add(&od->stale, &od->n_stale, e->d_name) != 0)
            st = nomem(err);
    }
    closedir(d);
    return st;
}

/* ---- staging ----------------------------------------------------------------------------- */

/* Creates parent/.base.staging-XXXXXX with mkdir(0777) (so the umask decides its mode, as for
 * any folder the user creates; mkdtemp would make it 0700) and its marker. When it replaces an
 * existing folder it takes that folder's group and set-group-ID bit at once, so that what is
 * written into it gets the group a shared folder gives (the exact mode comes at the exchange). */
static lv_status make_staging(lv_outdir *od, lv_err *err)
{
    static const char digits[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
    char text[128];
    for (int attempt = 0; attempt < 100; attempt++) {
        unsigned char r[6];
        if (getrandom(r, sizeof r, 0) != (ssize_t)sizeof r)
            for (size_t i = 0; i < sizeof r; i++)
                r[i] = (unsigned char)(rand() ^ (int)getpid() ^ attempt);
        char suffix[7];
        for (size_t i = 0; i < 6; i++)
            suffix[i] = digits[r[i] % (sizeof digits - 1)];
        suffix[6] = '\0';
        snprintf(od->staging, sizeof od->staging, "%s/.%s" STAGING_TAG "%s", od->parent, od->base,
                 suffix);
        if (mkdir(od->staging, 0777) == 0) {
            char marker[sizeof od->staging + 32];
            snprintf(marker, sizeof marker, "%s/" MARKER, od->staging);
            const int fd = open(marker, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
            if (fd >= 0)
                close(fd);
            struct stat sb, ss;
            if (stat(od->final, &sb) == 0 && S_ISDIR(sb.st_mode) && stat(od->staging, &ss) == 0) {
                if (ss.st_gid != sb.st_gid && chown(od->staging, (uid_t)-1, sb.st_gid) != 0) {
                    /* not a member of that group: the caller's */
                }
                if (sb.st_mode & S_ISGID)
                    chmod(od->staging, (ss.st_mode & 07777) | S_ISGID);
            }
            return LV_OK;
        }
        if (errno != EEXIST) {
            const int e = errno;
            od->staging[0] = '\0';
            return lv_fail(err, e == EACCES || e == EROFS ? LV_ERR_INPUT : LV_ERR_IO,
                           "cannot write in '%s' (for the results folder '%s'): %s", od->parent,
                           od->final, why(e, text, sizeof text));
        }
    }
    od->staging[0] = '\0';
    return lv_fail(err, LV_ERR_IO, "cannot create a staging folder in '%s'", od->parent);
}

/* Gives the staging folder the mode (and, where allowed, the owner) of the folder it replaces,
 * and the folders carried into it theirs (deepest first: a read-only folder is filled before
 * it becomes read-only). */
static void apply_modes(const lv_outdir *od)
{
    for (size_t i = od->n_dirs; i-- > 0;) {
        char dst[sizeof od->staging + PATH_MAX];
        if (join(dst, sizeof dst, od->staging, od->dir_rel[i]) == 0)
            chmod(dst, od->dir_mode[i]);
    }
    struct stat sb;
    if (stat(od->final, &sb) != 0 || !S_ISDIR(sb.st_mode))
        return;
    if (chown(od->staging, sb.st_uid, sb.st_gid) != 0) {
        /* not allowed (another owner): the group alone, else the caller's */
        if (chown(od->staging, (uid_t)-1, sb.st_gid) != 0) {
        }
    }
    chmod(od->staging, sb.st_mode & 07777);
}

/* Puts entry e of `from` at the same name in `to`: a folder made (owner kept where allowed; its
 * mode recorded for apply_modes), anything else as a hard link of itself (linkat without
 * following: a file, a link, a pipe or a socket stays the very same inode, with its data,
 * owner and mode). Returns 0, or -1 with errno. */
static int carry(lv_outdir *od, const char *from, const char *to, const od_entry *e)
{
    char src[PATH_MAX], dst[PATH_MAX + NAME_MAX + 32];
    if (join(src, sizeof src, from, e->name) != 0 || join(dst, sizeof dst, to, e->name) != 0) {
        errno = ENAMETOOLONG;
        return -1;
    }
    if (e->kind != E_DIR)
        return linkat(AT_FDCWD, src, AT_FDCWD, dst, 0);
    struct stat sb;
    const int made = mkdir(dst, 0700) == 0;
    if (!made && (errno != EEXIST || lstat(dst, &sb) != 0 || !S_ISDIR(sb.st_mode)))
        return -1;
    if (!made)
        return 0; /* a writer made it: its mode stays */
    if (chown(dst, e->sb.st_uid, e->sb.st_gid) != 0) {
    }
    char **g = realloc(od->dir_rel, (od->n_dirs + 1) * sizeof *g);
    mode_t *gm = g != NULL ? realloc(od->dir_mode, (od->n_dirs + 1) * sizeof *gm) : NULL;
    if (g != NULL)
        od->dir_rel = g;
    if (gm == NULL || (g[od->n_dirs] = strdup(e->name)) == NULL) {
        errno = ENOMEM;
        return -1;
    }
    od->dir_mode = gm;
    od->dir_mode[od->n_dirs++] = e->sb.st_mode & 07777;
    return 0;
}

static lv_status carry_fail(const lv_outdir *od, const od_entry *e, lv_err *err)
{
    char text[128], name[256];
    const int en = errno;
    printable(e->name, name, sizeof name);
    return lv_fail(err, en == ENOMEM ? LV_ERR_NOMEM : LV_ERR_IO,
                   "cannot keep '%s/%s' in the new results folder (%s%s): nothing was replaced",
                   od->final, name,
                   en == EXDEV ? "it lies on another file system: " : "", why(en, text, sizeof text));
}

/* A hard-linked replica of OUTDIR in the staging folder: every entry but lvsim's leftovers. */
static lv_status replicate(lv_outdir *od, lv_err *err)
{
    od_list l = {0};
    int lv = 0;
    lv_status st = survey_dir(od->final, &l, &lv, err);
    for (size_t i = 0; st == LV_OK && i < l.n; i++) {
        const od_entry *e = &l.e[i];
        if (e->owner == JUNK)
            continue;
        if (carry(od, od->final, od->staging, e) != 0)
            st = carry_fail(od, e, err);
    }
    list_free(&l);
    return st;
}

/* ---- begin / open ----------------------------------------------------------------------- */

static lv_outdir *outdir_new(int mode, unsigned flags)
{
    lv_outdir *od = calloc(1, sizeof *od);
    if (od != NULL) {
        od->lock_fd = -1;
        od->mode = mode;
        od->flags = flags;
        iso_now(od->started, sizeof od->started);
    }
    return od;
}

static lv_status set_mission(lv_outdir *od, const char *mission_file, lv_err *err)
{
    if (mission_file == NULL)
        return LV_OK;
    char abs[PATH_MAX];
    od->mission_file = strdup(mission_file);
    od->mission_abs = strdup(realpath(mission_file, abs) != NULL ? abs : mission_file);
    if (od->mission_file == NULL || od->mission_abs == NULL)
        return nomem(err);
    return lv_sha256_file(mission_file, od->mission_sha, &od->mission_bytes, err);
}

/* OUTDIR's state before writing: *exists; refuses a file, a folder with files lvsim did not
 * write (unless LV_OUTDIR_FORCE), and names lvsim must write that belong to the user. */
/* 1 when `name` is in the list as a file lvsim did not write */
static int foreign_named(const od_list *l, const char *name)
{
    for (size_t i = 0; i < l->n; i++)
        if (l->e[i].owner == FOREIGN && strcmp(l->e[i].name, name) == 0)
            return 1;
    return 0;
}

static lv_status check_existing(lv_outdir *od, int need_lvsim, int *exists, lv_err *err)
{
    struct stat sb;
    *exists = 0;
    if (stat(od->final, &sb) != 0)
        return LV_OK;
    if (!S_ISDIR(sb.st_mode))
        return lv_fail(err, LV_ERR_INPUT,
                       "'%s' is a file, not a folder: name a folder for the results", od->final);
    *exists = 1;
    /* a mount point cannot be exchanged with a folder beside it (EBUSY, EXDEV) */
    struct stat ps;
    if (stat(od->parent, &ps) == 0 && ps.st_dev != sb.st_dev)
        return lv_fail(err, LV_ERR_INPUT,
                       "'%s' is a mount point: lvsim replaces a results folder as a whole with "
                       "one rename beside it, which a mount point cannot take; use a folder "
                       "inside it (e.g. '%s/results')", od->final, od->final);
    /* the current folder (or one holding it) would leave the shell in a deleted folder */
    char cwd[PATH_MAX], real[PATH_MAX];
    if (getcwd(cwd, sizeof cwd) != NULL && realpath(od->final, real) != NULL) {
        const size_t lr = strlen(real);
        if (strncmp(cwd, real, lr) == 0 && (cwd[lr] == '\0' || cwd[lr] == '/' || lr == 1))
            return lv_fail(err, LV_ERR_INPUT,
                           "'%s' is the current folder or holds it: a results folder is "
                           "replaced as a whole, which would leave this shell in a deleted "
                           "folder; run lvsim from outside it", od->final);
    }
    od_list l = {0};
    int lv = 0;
    lv_status st = survey_dir(od->final, &l, &lv, err);
    if (st != LV_OK)
        return st;
    /* a campaign's folder and a run's are not each other's */
    manifest top;
    if (lv && man_load(od->final, &top) == 1) {
        const char *cmd = cJSON_GetObjectItemCaseSensitive(top.root, "command")->valuestring;
        if (od->mode == MODE_LIVE && strcmp(cmd, "mc") != 0)
            st = lv_fail(err, LV_ERR_INPUT,
                         "'%s' is the results folder of 'lvsim %s', not a Monte Carlo "
                         "campaign's: a campaign would mix into it; choose another folder",
                         od->final, cmd);
        else if (od->mode == MODE_BEGIN && strcmp(cmd, "mc") == 0)
            st = lv_fail(err, LV_ERR_INPUT,
                         "'%s' is a Monte Carlo campaign's folder (lvsim mc): a run would "
                         "replace its database; choose another folder", od->final);
        man_free(&top);
        if (st != LV_OK) {
            list_free(&l);
            return st;
        }
    }
    size_t n_foreign = 0, n_any = 0;
    char names[600];
    foreign_names(&l, names, sizeof names, &n_foreign);
    for (size_t i = 0; i < l.n; i++)
        n_any += l.e[i].owner != JUNK;
    /* a run replaces the folder: any file of the user's refuses it (unless force); adding to
     * a folder (open, live) needs lvsim's folder, in which the user's files are kept */
    if (need_lvsim && !lv && n_any > 0 && od->mode == MODE_OPEN)
        st = lv_fail(err, LV_ERR_INPUT,
                     "'%s' is not a results folder of lvsim (it has no manifest.json written "
                     "by lvsim): lvsim adds files only to a folder it wrote",
                     od->final);
    else if (n_foreign > 0 && (od->mode == MODE_BEGIN || (od->mode == MODE_LIVE && !lv)) &&
             !(od->flags & LV_OUTDIR_FORCE))
        st = lv_fail(err, LV_ERR_INPUT,
                     "'%s' holds %zu file%s lvsim did not write (%s): lvsim replaces only what "
                     "its manifest.json lists, so the folder is left alone; name a new or empty "
                     "folder, an earlier results folder%s",
                     od->final, n_foreign, n_foreign == 1 ? "" : "s", names,
                     foreign_named(&l, MANIFEST) ? "" /* --force would refuse it too */
                                                 : ", or add --force to replace lvsim's files "
                                                   "and keep these");
    /* export, plot, view read lvsim's files: one changed since lvsim wrote it would make
     * figures or exports that the manifest then vouches for */
    for (size_t i = 0; st == LV_OK && od->mode == MODE_OPEN && i < l.n; i++)
        if (l.e[i].owner == FOREIGN && strcmp(l.e[i].reason, "not written by lvsim") != 0)
            st = lv_fail(err, LV_ERR_INPUT,
                         "'%s/%s' changed since lvsim wrote it (its size or SHA-256 differs "
                         "from manifest.json), and what lvsim adds to the folder is made from "
                         "its files: put lvsim's file back, or run the mission again",
                         od->final, l.e[i].name);
    for (size_t i = 0; st == LV_OK && i < l.n; i++) {
        const od_entry *e = &l.e[i];
        int reserved = strcmp(e->name, MANIFEST) == 0;
        for (size_t k = 0; k < od->n_live; k++)
            reserved |= strcmp(e->name, od->live[k]) == 0;
        /* a name the command writes: with force the user's files are kept, and this one it
         * would have to replace - refused now, not after the whole run */
        if (strchr(e->name, '/') == NULL && od->mode != MODE_OPEN)
            reserved |= od->mode == MODE_LIVE ? matches(mc_names, e->name) : is_run_name(e->name);
        if (e->owner == FOREIGN && reserved)
            st = lv_fail(err, LV_ERR_INPUT,
                         "'%s/%s' is %s and lvsim must write a file of that name: it is left "
                         "alone (also with --force); move it away or write elsewhere",
                         od->final, e->name,
                         strcmp(e->reason, "not written by lvsim") == 0 ? "not lvsim's"
                                                                         : "lvsim's file changed "
                                                                           "since it wrote it");
    }
    list_free(&l);
    return st;
}

static lv_status common_start(lv_outdir *od, const char *outdir, const char *mission_file,
                              lv_err *err)
{
    lv_status st = set_names(od, outdir, err);
    if (st == LV_OK)
        st = set_mission(od, mission_file, err);
    return st;
}

lv_status lv_outdir_begin(const char *outdir, const char *mission_file, unsigned flags,
                          lv_outdir **out, lv_err *err)
{
    *out = NULL;
    lv_outdir *od = outdir_new(MODE_BEGIN, flags);
    if (od == NULL)
        return nomem(err);
    int exists = 0;
    struct stat sb;
    lv_status st = common_start(od, outdir, mission_file, err);
    if (st == LV_OK && stat(od->final, &sb) == 0 && !S_ISDIR(sb.st_mode))
        st = lv_fail(err, LV_ERR_INPUT,
                     "'%s' is a file, not a folder: name a folder for the results", od->final);
    /* the folder is surveyed under the lock (a writer's exchange is not seen halfway), and
     * again at the commit */
    if (st == LV_OK)
        st = mkdir_p(od->parent, err);
    if (st == LV_OK)
        st = take_lock(od, err);
    if (st == LV_OK)
        st = check_existing(od, 0, &exists, err);
    if (st == LV_OK)
        st = clean_stale(od, err);
    if (st == LV_OK)
        st = make_staging(od, err);
    if (st != LV_OK) {
        lv_outdir_free(od);
        return st;
    }
    *out = od;
    return LV_OK;
}

static lv_status write_manifest(lv_outdir *od, const char *dir, const lv_outdir_record *rec,
                                const od_list *old, lv_err *err);

static lv_status open_folder(const char *outdir, const char *mission_file, unsigned flags,
                             const char *const *live, int mode, lv_outdir **out, lv_err *err)
{
    *out = NULL;
    lv_outdir *od = outdir_new(mode, flags);
    if (od == NULL)
        return nomem(err);
    lv_status st = common_start(od, outdir, mission_file, err);
    for (size_t i = 0; st == LV_OK && live != NULL && live[i] != NULL; i++)
        if (strv_add(&od->live, &od->n_live, live[i]) != 0)
            st = nomem(err);
    int exists = 0;
    struct stat sb;
    if (st == LV_OK && (stat(od->final, &sb) != 0 || !S_ISDIR(sb.st_mode)) &&
        od->mode != MODE_LIVE)
        st = lv_fail(err, LV_ERR_INPUT, "'%s' is not a results folder (%s)", od->final,
                     errno == ENOENT ? "no such folder" : "not a folder");
    if (st == LV_OK && od->mode == MODE_LIVE)
        st = mkdir_p(od->parent, err);
    if (st == LV_OK)
        st = take_lock(od, err);
    if (st == LV_OK)
        st = check_existing(od, 1, &exists, err);
    if (st == LV_OK)
        st = clean_stale(od, err);
    if (st == LV_OK && od->mode == MODE_LIVE) {
        /* write in OUTDIR itself: its manifest now claims the live names (a campaign killed
         * at any point is still lvsim's folder) */
        if (!exists && mkdir(od->final, 0777) != 0 && errno != EEXIST) {
            char text[128];
            st = lv_fail(err, LV_ERR_IO, "cannot create folder '%s': %s", od->final,
                         why(errno, text, sizeof text));
        }
        od->made = !exists;
        char mpath[PATH_MAX + 32];
        snprintf(mpath, sizeof mpath, "%s/%s", od->final, MANIFEST);
        if (st == LV_OK && exists && access(mpath, F_OK) == 0) /* put back by a discard */
            st = lv_read_file(mpath, LV_SUMMARY_FILE_MAX, NULL, &od->prev_manifest,
                              &od->prev_len, err);
        od_list l = {0};
        int lv = 0;
        if (st == LV_OK)
            st = survey_dir(od->final, &l, &lv, err);
        const lv_outdir_record rec = {"mc", "incomplete", NULL, 0, NULL};
        if (st == LV_OK)
            st = write_manifest(od, od->final, &rec, &l, err);
        list_free(&l);
    } else if (st == LV_OK) {
        st = make_staging(od, err);
        if (st == LV_OK)
            st = replicate(od, err);
    }
    if (st != LV_OK) {
        lv_outdir_free(od);
        return st;
    }
    *out = od;
    return LV_OK;
}

lv_status lv_outdir_open(const char *outdir, lv_outdir **out, lv_err *err)
{
    return open_folder(outdir, NULL, 0, NULL, MODE_OPEN, out, err);
}

lv_status lv_outdir_open_live(const char *outdir, const char *mission_file, unsigned flags,
                              const char *const *live, lv_outdir **out, lv_err *err)
{
    if (live == NULL) {
        *out = NULL;
        return lv_fail(err, LV_ERR_INPUT, "lv_outdir_open_live: no live names");
    }
    return open_folder(outdir, mission_file, flags, live, MODE_LIVE, out, err);
}

lv_status lv_outdir_stage(lv_outdir *od, lv_err *err)
{
    if (od == NULL || od->mode != MODE_LIVE || od->staging[0] != '\0' || od->committed)
        return lv_fail(err, LV_ERR_INPUT, "lv_outdir_stage: not a live folder, or staged twice");
    lv_status st = make_staging(od, err);
    if (st == LV_OK)
        st = replicate(od, err);
    return st;
}

const char *lv_outdir_path(const lv_outdir *od)
{
    return od->staging[0] != '\0' ? od->staging : od->final;
}
const char *lv_outdir_final(const lv_outdir *od) { return od->final; }
size_t lv_outdir_stale_count(const lv_outdir *od) { return od->n_stale; }
const char *lv_outdir_stale(const lv_outdir *od, size_t i)
{
    return i < od->n_stale ? od->stale[i] : NULL;
}
size_t lv_outdir_kept_count(const lv_outdir *od) { return od->n_kept; }
const char *lv_outdir_kept(const lv_outdir *od, size_t i)
{
    return i < od->n_kept ? od->kept[i] : NULL;
}
size_t lv_outdir_file_count(const lv_outdir *od) { return od->n_files; }
const lv_outdir_file *lv_outdir_files(const lv_outdir *od) { return od->files; }

/* ---- the manifest ---------------------------------------------------------------------- */

typedef struct file_list {
    char **names;
    size_t n, cap;
} file_list;

static int flist_add(file_list *l, const char *name)
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

/* The files of a survey of OUTDIR by device and inode: which file of a staging folder is
 * one of OUTDIR's (a hard link carried there). */
typedef struct inode_index {
    const od_entry **e;
    size_t n;
} inode_index;

static int cmp_inode(const struct stat *a, const struct stat *b)
{
    if (a->st_dev != b->st_dev)
        return a->st_dev < b->st_dev ? -1 : 1;
    return a->st_ino < b->st_ino ? -1 : a->st_ino > b->st_ino;
}

static int by_inode(const void *a, const void *b)
{
    return cmp_inode(&(*(const od_entry *const *)a)->sb, &(*(const od_entry *const *)b)->sb);
}

static int index_build(const od_list *l, inode_index *ix)
{
    ix->n = 0;
    ix->e = malloc((l->n + 1) * sizeof *ix->e);
    if (ix->e == NULL)
        return -1;
    for (size_t i = 0; i < l->n; i++)
        if (l->e[i].kind != E_DIR || l->e[i].owner == JUNK)
            ix->e[ix->n++] = &l->e[i];
    if (ix->n > 1)
        qsort(ix->e, ix->n, sizeof *ix->e, by_inode);
    return 0;
}

/* The entry of the survey that is this very file (same device and inode), or NULL. */
static const od_entry *same_file(const inode_index *ix, const struct stat *sb)
{
    size_t lo = 0, hi = ix->n;
    while (lo < hi) {
        const size_t mid = lo + (hi - lo) / 2;
        const int c = cmp_inode(&ix->e[mid]->sb, sb);
        if (c == 0)
            return ix->e[mid];
        if (c < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    return NULL;
}

/* Every regular file under root/rel that lvsim wrote: the manifest, the marker, temporary
 * files and the user's files (those of `old` that are FOREIGN) left out. Returns 0, or -1
 * (errno). */
static int walk(const char *root, const char *rel, const inode_index *old, file_list *l)
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
        if (rel[0] == '\0' && (strcmp(e->d_name, MANIFEST) == 0 || strcmp(e->d_name, MARKER) == 0))
            continue;
        struct stat sb;
        if (fstatat(dirfd(d), e->d_name, &sb, AT_SYMLINK_NOFOLLOW) != 0)
            continue;
        if (S_ISDIR(sb.st_mode)) {
            rc = walk(root, sub, old, l);
        } else if (S_ISREG(sb.st_mode)) {
            const od_entry *o = same_file(old, &sb);
            if (o == NULL || o->owner != FOREIGN)
                rc = flist_add(l, sub);
        }
    }
    closedir(d);
    return rc;
}

/* DIR/manifest.json: lvsim's identification, the command, status, mission, times, notes,
 * the history of commands that changed the folder (from OUTDIR's manifest), the live names
 * and every file lvsim wrote with its size and SHA-256. A file's SHA-256 is read, in this
 * order, from: `old`, for a file that is still the same one OUTDIR's manifest vouched for;
 * the record lv_atomic_commit left on a file written through its stream, hashed as its bytes
 * went out (lv_atomic_digest: the same inode, size and mtime as when it was closed); else the
 * file itself (lv_sha256_file: files libraries wrote by name - PLplot's SVGs, a campaign's
 * SQLite database -, a file changed since, a file system without extended attributes). */
static lv_status write_manifest(lv_outdir *od, const char *dir, const lv_outdir_record *rec,
                                const od_list *old, lv_err *err)
{
    char path[PATH_MAX + 32], text[128], finished[32];
    iso_now(finished, sizeof finished);
    file_list l = {0};
    lv_status st = LV_OK;
    cJSON *root = NULL;
    char *json = NULL;
    manifest prev;
    memset(&prev, 0, sizeof prev);
    inode_index ix = {NULL, 0};
    const od_list none = {0};
    if (index_build(old != NULL ? old : &none, &ix) != 0) {
        st = nomem(err);
        goto fail;
    }
    if (walk(dir, "", &ix, &l) != 0) {
        st = lv_fail(err, errno == ENOMEM ? LV_ERR_NOMEM : LV_ERR_IO,
                     "cannot list the files of '%s': %s", dir, why(errno, text, sizeof text));
        goto fail;
    }
    if (l.n > 1)
        qsort(l.names, l.n, sizeof *l.names, by_cstr);
    snprintf(path, sizeof path, "%s/%s", dir, MANIFEST);
    /* adding to a folder (open, live): its manifest is kept and its history extended */
    if (od->mode != MODE_BEGIN && man_load(od->final, &prev) == 1) {
        root = prev.root;
        prev.root = NULL;
    }
    if (root == NULL) {
        root = cJSON_CreateObject();
        if (root == NULL) {
            st = nomem(err);
            goto fail;
        }
        cJSON_AddStringToObject(root, "lvsim", LVSIM_VERSION);
        cJSON_AddStringToObject(root, "command", rec && rec->command ? rec->command : "run");
        cJSON_AddStringToObject(root, "status", rec && rec->status ? rec->status : "ok");
        cJSON_AddNullToObject(root, "mission");
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
        if (od->mode == MODE_LIVE) { /* the campaign's own status, not a history entry's */
            cJSON_ReplaceItemInObjectCaseSensitive(
                root, "status", cJSON_CreateString(rec && rec->status ? rec->status : "ok"));
            cJSON_ReplaceItemInObjectCaseSensitive(root, "finished", cJSON_CreateString(finished));
        }
    }
    if (od->mission_file != NULL) {
        cJSON *m = cJSON_CreateObject();
        if (rec && rec->mission_name)
            cJSON_AddStringToObject(m, "name", rec->mission_name);
        cJSON_AddStringToObject(m, "file", od->mission_file);
        cJSON_AddStringToObject(m, "path", od->mission_abs);
        cJSON_AddStringToObject(m, "sha256", od->mission_sha);
        cJSON_AddNumberToObject(m, "bytes", (double)od->mission_bytes);
        cJSON_ReplaceItemInObjectCaseSensitive(root, "mission", m);
    }
    if (od->n_live > 0) {
        cJSON *live = cJSON_GetObjectItemCaseSensitive(root, "live");
        if (!cJSON_IsArray(live)) {
            cJSON_DeleteItemFromObjectCaseSensitive(root, "live");
            live = cJSON_AddArrayToObject(root, "live");
        }
        for (size_t i = 0; i < od->n_live; i++) {
            int have = 0;
            const cJSON *x;
            cJSON_ArrayForEach(x, live) have |= cJSON_IsString(x) && !strcmp(x->valuestring, od->live[i]);
            if (!have)
                cJSON_AddItemToArray(live, cJSON_CreateString(od->live[i]));
        }
    }
    cJSON *files = cJSON_AddArrayToObject(root, "files");
    for (size_t i = 0; i < od->n_files; i++)
        free((char *)od->files[i].name);
    free(od->files);
    od->files = calloc(l.n + 1, sizeof *od->files);
    od->n_files = 0;
    if (files == NULL || od->files == NULL) {
        st = nomem(err);
        goto fail;
    }
    for (size_t i = 0; i < l.n; i++) {
        char fpath[PATH_MAX * 2], hex[65];
        unsigned long long bytes = 0;
        struct stat sb;
        snprintf(fpath, sizeof fpath, "%s/%s", dir, l.names[i]);
        const int have_sb = lstat(fpath, &sb) == 0;
        const od_entry *o = have_sb ? same_file(&ix, &sb) : NULL;
        if (o != NULL && o->sha[0] != '\0' && o->sb.st_size == sb.st_size &&
            o->sb.st_mtim.tv_sec == sb.st_mtim.tv_sec && o->sb.st_mtim.tv_nsec == sb.st_mtim.tv_nsec) {
            snprintf(hex, sizeof hex, "%s", o->sha); /* the same file the manifest vouched for */
            bytes = (unsigned long long)sb.st_size;
        } else if (have_sb && lv_atomic_digest(fpath, &sb, hex)) {
            /* written through lv_atomic's stream, hashed as it went out, unchanged since
             * (the same inode, size and mtime): not read again */
            bytes = (unsigned long long)sb.st_size;
        } else if ((st = lv_sha256_file(fpath, hex, &bytes, err)) != LV_OK) {
            goto fail;
        }
        cJSON *f = cJSON_CreateObject();
        cJSON_AddStringToObject(f, "name", l.names[i]);
        cJSON_AddNumberToObject(f, "bytes", (double)bytes);
        cJSON_AddStringToObject(f, "sha256", hex);
        char stamp[64]; /* the file as stat'ed above: reading it to hash moves no ctime */
        if (have_sb && (unsigned long long)sb.st_size == bytes) {
            file_stamp(&sb, stamp, sizeof stamp);
            cJSON_AddStringToObject(f, "stamp", stamp);
        }
        cJSON_AddItemToArray(files, f);
        od->files[i].name = l.names[i]; /* moves */
        od->files[i].bytes = bytes;
        l.names[i] = NULL;
        od->n_files = i + 1;
    }
    json = lv_json_print(root);
    if (json == NULL) {
        st = nomem(err);
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
    man_free(&prev);
    free(ix.e);
    return st;
}

/* ---- commit -------------------------------------------------------------------------------- */

/* Brings the user's files into the staging folder and refuses the commit where lvsim would
 * replace one: every FOREIGN entry of OUTDIR (surveyed now, under the lock) must be in the
 * staging folder as itself (the same inode; a folder as a folder) or is carried there now.
 * OWNED entries are not carried: lvsim replaced them, or removed them in a replica. */
static lv_status carry_foreign(lv_outdir *od, const od_list *l, lv_err *err)
{
    for (size_t i = 0; i < l->n; i++) {
        const od_entry *e = &l->e[i];
        if (e->owner != FOREIGN)
            continue;
        char sp[sizeof od->staging + PATH_MAX], name[256];
        struct stat sb;
        printable(e->name, name, sizeof name);
        if (join(sp, sizeof sp, od->staging, e->name) != 0)
            return lv_fail(err, LV_ERR_INPUT, "'%s/%s': name too long", od->final, name);
        if (lstat(sp, &sb) == 0) {
            const int same = e->kind == E_DIR ? S_ISDIR(sb.st_mode)
                                              : sb.st_dev == e->sb.st_dev &&
                                                    sb.st_ino == e->sb.st_ino;
            if (!same)
                return lv_fail(err, LV_ERR_INPUT,
                               "'%s/%s' is %s, and the new results have a file of that name: "
                               "nothing was replaced; move it away or write elsewhere",
                               od->final, name,
                               strcmp(e->reason, "not written by lvsim") == 0
                                   ? "not lvsim's"
                                   : "lvsim's file changed since it wrote it");
        } else if (carry(od, od->final, od->staging, e) != 0) {
            return carry_fail(od, e, err);
        }
        if (e->kind != E_DIR && strv_add(&od->kept, &od->n_kept, e->name) != 0)
            return nomem(err);
    }
    return LV_OK;
}

/* The old folder after the exchange, emptied without losing anything: every entry the last
 * survey saw (`known`, by inode: lvsim's replaced files, the user's now linked into OUTDIR,
 * lvsim's leftovers) is unlinked; anything else - a file the user saved into OUTDIR between
 * that survey and the exchange - is moved into the new OUTDIR at its name (or NAME.kept-N
 * when the new folder has that name) and counted as kept. Returns 0, or -1 when something
 * could not be moved (then the old folder, holding it, is left with its marker removed:
 * never taken for a stale staging folder). */
static int empty_old(lv_outdir *od, const char *old, const char *rel, const inode_index *known)
{
    char dir[sizeof od->staging + PATH_MAX];
    if (join(dir, sizeof dir, old, rel) != 0)
        return -1;
    if (rel[0] != '\0' && chmod(dir, 0700) != 0) {
        /* a read-only folder must be writable to be emptied; fails below if it is not ours */
    }
    DIR *d = opendir(dir);
    if (d == NULL)
        return -1;
    int rc = 0;
    struct dirent *de;
    while ((de = readdir(d)) != NULL) {
        if (strcmp(de->d_name, ".") == 0 || strcmp(de->d_name, "..") == 0 ||
            (rel[0] == '\0' && strcmp(de->d_name, MARKER) == 0))
            continue;
        char r[PATH_MAX], full[sizeof dir + NAME_MAX + 2];
        struct stat sb;
        if (join(r, sizeof r, rel, de->d_name) != 0 || join(full, sizeof full, old, r) != 0 ||
            lstat(full, &sb) != 0) {
            rc = -1;
            continue;
        }
        if (S_ISDIR(sb.st_mode)) {
            const od_entry *k = same_file(known, &sb);
            if (k != NULL && k->owner == JUNK) { /* a stale staging folder: lvsim's whole */
                if (rm_tree(full) != 0)
                    rc = -1;
            } else if (empty_old(od, old, r, known) != 0 || rmdir(full) != 0) {
                rc = -1;
            }
            continue;
        }
        if (same_file(known, &sb) != NULL) {
            if (unlink(full) != 0)
                rc = -1;
            continue;
        }
        /* a late arrival: into the new folder */
        char dst[PATH_MAX + 32], parent[PATH_MAX + 32];
        int moved = 0;
        for (int k = 0; k < 100 && !moved; k++) {
            const int w = k == 0 ? snprintf(dst, sizeof dst, "%s/%s", od->final, r)
                                 : snprintf(dst, sizeof dst, "%s/%s.kept-%d", od->final, r, k);
            if (w < 0 || (size_t)w >= sizeof dst)
                break;
            snprintf(parent, sizeof parent, "%s", dst);
            char *sl = strrchr(parent, '/');
            if (sl != NULL) {
                *sl = '\0';
                lv_err ignored;
                mkdir_p(parent, &ignored);
            }
            struct stat ds;
            if (lstat(dst, &ds) == 0)
                continue;
            moved = rename(full, dst) == 0;
            if (!moved)
                break;
            strv_add(&od->kept, &od->n_kept, dst + strlen(od->final) + 1);
        }
        if (!moved)
            rc = -1;
    }
    closedir(d);
    return rc;
}

/* One step: OUTDIR gets the staging folder, the staging name the old folder, which is then
 * emptied (empty_old). The old folder is marked first, so that a kill in between leaves a
 * staging folder the next writer may remove. */
static lv_status exchange(lv_outdir *od, const inode_index *known, lv_err *err)
{
    char text[128], marker[sizeof od->staging + 32], old_marker[PATH_MAX + 32];
    struct stat sb;
    int rc;
    snprintf(marker, sizeof marker, "%s/" MARKER, od->staging);
    unlink(marker);
    apply_modes(od); /* now: a read-only folder's mode would have kept lvsim from writing */
    if (lstat(od->final, &sb) == 0) {
        int marked = 0;
        if (join(old_marker, sizeof old_marker, od->final, MARKER) == 0) {
            const int fd = open(old_marker, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
            if (fd >= 0) {
                close(fd);
                marked = 1;
            }
        }
        rc = renameat2(AT_FDCWD, od->staging, AT_FDCWD, od->final, RENAME_EXCHANGE);
        if (rc != 0 && (errno == EINVAL || errno == ENOSYS || errno == ENOTSUP)) {
            /* a file system without RENAME_EXCHANGE: two renames, a moment without OUTDIR,
             * never a mixed one */
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
        if (rc != 0) {
            const int e = errno;
            if (marked)
                unlink(old_marker);
            return lv_fail(err, LV_ERR_IO, "cannot replace '%s': %s", od->final,
                           why(e, text, sizeof text));
        }
        if (chmod(od->staging, 0700) != 0) {
        }
        if (empty_old(od, od->staging, "", known) == 0) {
            char m[sizeof od->staging + 32];
            snprintf(m, sizeof m, "%s/" MARKER, od->staging);
            unlink(m);
            rmdir(od->staging);
        } else {
            /* what could not be moved stays there: unmarked, so never removed as stale */
            char m[sizeof od->staging + 32];
            snprintf(m, sizeof m, "%s/" MARKER, od->staging);
            unlink(m);
        }
    } else if (rename(od->staging, od->final) != 0) {
        return lv_fail(err, LV_ERR_IO, "cannot create '%s': %s", od->final,
                       why(errno, text, sizeof text));
    }
    od->staging[0] = '\0';
    return LV_OK;
}

lv_status lv_outdir_commit(lv_outdir *od, const lv_outdir_record *rec, lv_err *err)
{
    if (od == NULL || od->committed)
        return lv_fail(err, LV_ERR_INPUT, "lv_outdir_commit: no folder, or committed twice");
    od_list l = {0};
    int lv = 0;
    struct stat sb;
    lv_status st = LV_OK;
    if (od->mode == MODE_LIVE && od->staging[0] == '\0') {
        /* nothing staged: the manifest of the folder as it is */
        if ((st = survey_dir(od->final, &l, &lv, err)) == LV_OK)
            st = write_manifest(od, od->final, rec, &l, err);
    } else {
        const int exists = stat(od->final, &sb) == 0 && S_ISDIR(sb.st_mode);
        /* the manifest first (its hashing takes time), then a fresh survey, the user's files
         * carried and the exchange at once after it; what arrives later still is kept by
         * empty_old */
        if (exists)
            st = survey_dir(od->final, &l, &lv, err);
        if (st == LV_OK)
            st = write_manifest(od, od->staging, rec, &l, err);
        list_free(&l);
        if (st == LV_OK && exists)
            st = survey_dir(od->final, &l, &lv, err);
        if (st == LV_OK)
            st = carry_foreign(od, &l, err);
        inode_index known = {NULL, 0};
        if (st == LV_OK && index_build(&l, &known) != 0)
            st = nomem(err);
        if (st == LV_OK)
            st = exchange(od, &known, err);
        free(known.e);
    }
    list_free(&l);
    od->committed = st == LV_OK;
    release_lock(od);
    return st;
}

void lv_outdir_discard(lv_outdir *od)
{
    if (od != NULL && od->mode == MODE_LIVE && od->staging[0] == '\0' && !od->committed) {
        char mpath[PATH_MAX + 32];
        snprintf(mpath, sizeof mpath, "%s/%s", od->final, MANIFEST);
        lv_atomic a;
        if (od->prev_manifest == NULL)
            remove(mpath);
        else if (lv_atomic_open(&a, mpath, NULL) == LV_OK) {
            fwrite(od->prev_manifest, 1, od->prev_len, a.fp);
            lv_atomic_commit(&a, NULL); /* on failure: the open's own manifest stays */
        }
        if (od->made)
            rmdir(od->final); /* only when empty: anything else stays */
    }
    lv_outdir_free(od);
}

void lv_outdir_free(lv_outdir *od)
{
    if (od == NULL)
        return;
    free(od->prev_manifest);
    if (od->staging[0] != '\0')
        rm_tree(od->staging); /* hard links only: the user's files stay in OUTDIR */
    release_lock(od);
    strv_free(od->stale, od->n_stale);
    strv_free(od->kept, od->n_kept);
    strv_free(od->live, od->n_live);
    strv_free(od->dir_rel, od->n_dirs);
    free(od->dir_mode);
    for (size_t i = 0; i < od->n_files; i++)
        free((char *)od->files[i].name);
    free(od->files);
    free(od->mission_file);
    free(od->mission_abs);
    free(od);
}
