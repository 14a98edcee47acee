/* data.c - run-time lookup of lvsim's data files (lvsim/lv_data.h): a caller's folder,
 * $LVSIM_DATA, the share/lvsim folder next to the library that holds this code (found
 * with dladdr1), and the install prefix's datadir, LV_INSTALL_DATADIR (set by CMake). */
#define _GNU_SOURCE /* dladdr1() and RTLD_DL_LINKMAP: which loaded object holds this code */
#include "core/data.h"

#include <dlfcn.h>
#include <limits.h>
#include <link.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/status.h"

static const char anchor = 0; /* an address inside the object that holds lvsim */

/* Appends dir = a + b unless it does not fit or is already listed. */
static void add_dir(lv_data_dirs *d, const char *origin, const char *a, const char *b)
{
    if (d->n >= LV_DATA_MAX_DIRS)
        return;
    char *dst = d->dir[d->n];
    const int len = snprintf(dst, LV_DATA_PATH_MAX, "%s%s", a, b);
    if (len < 0 || len >= LV_DATA_PATH_MAX)
        return;
    for (size_t k = 0; k < d->n; k++)
        if (strcmp(d->dir[k], dst) == 0)
            return;
    d->origin[d->n++] = origin;
}

/* Writes the folder holding the absolute path p ("/a/b" -> "/a", "/a" -> "/") to out. */
static void parent_dir(const char *p, char *out, size_t size)
{
    const char *slash = strrchr(p, '/');
    size_t n = slash == NULL ? 0 : (size_t)(slash - p);
    snprintf(out, size, "%.*s", n > 0 ? (int)n : 1, n > 0 ? p : "/");
}

/* Adds <prefix>/share/lvsim. */
static void add_share(lv_data_dirs *d, const char *origin, const char *prefix)
{
    add_dir(d, origin, strcmp(prefix, "/") == 0 ? "" : prefix, "/share/lvsim");
}

/* The shared library that holds this code or, when lvsim is linked statically, the
 * program; symbolic links and ".." resolved. *program tells which. 0: unknown. */
static int object_file(char *buf, int *program)
{
    Dl_info info;
    struct link_map *map = NULL;
    if (dladdr1(&anchor, &info, (void **)&map, RTLD_DL_LINKMAP) == 0 || map == NULL)
        return 0;
    /* the main program's link map has an empty name (dli_fname would be its argv[0]) */
    *program = map->l_name == NULL || map->l_name[0] == '\0';
    const char *file = *program ? "/proc/self/exe" : info.dli_fname;
    return file != NULL && realpath(file, buf) != NULL && buf[0] == '/';
}

void lv_data_dirs_get(const char *dir, lv_data_dirs *out)
{
    memset(out, 0, sizeof *out);
    if (dir != NULL && dir[0] != '\0')
        add_dir(out, "argument", dir, "");
    const char *env = getenv(LV_DATA_ENV);
    out->env_set = env != NULL && env[0] != '\0';
    if (out->env_set)
        add_dir(out, LV_DATA_ENV, env, "");

    char file[PATH_MAX], libdir[PATH_MAX], up[PATH_MAX], up2[PATH_MAX];
    int program = 0;
    if (object_file(file, &program)) {
        const char *origin = program ? "next to the program" : "next to the library";
        parent_dir(file, libdir, sizeof libdir);
        parent_dir(libdir, up, sizeof up);
        add_share(out, origin, up); /* <prefix>/lib/liblvsim.so, <build>/lib/liblvsim.so */
        const char *slash = strrchr(up, '/');
        if (slash != NULL && strncmp(slash + 1, "lib", 3) == 0) {
            parent_dir(up, up2, sizeof up2); /* multiarch: <prefix>/lib/<triplet>/ */
            add_share(out, origin, up2);
        }
    }
#ifdef LV_INSTALL_DATADIR
    add_dir(out, "install prefix", LV_INSTALL_DATADIR, "");
#endif
}

lv_status lv_data_find(const char *dir, const char *name, char *path, size_t size, lv_err *err)
{
    if (name == NULL || name[0] == '\0' || name[0] == '/')
        return lv_fail(err, LV_ERR_INPUT, "data file '%s': need a name relative to the data "
                       "folder, like gravity/egm2008_n20.gfc", name != NULL ? name : "(null)");
    if (path == NULL || size == 0)
        return lv_fail(err, LV_ERR_INPUT, "data file '%s': no room for its path", name);
    lv_data_dirs *d = malloc(sizeof *d); /* 20 kB: not on a worker thread's stack */
    if (d == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "data file '%s': out of memory", name);
    lv_data_dirs_get(dir, d);

    lv_status st = LV_OK;
    char cand[LV_DATA_PATH_MAX + 64];
    for (size_t k = 0; k < d->n; k++) {
        struct stat sb;
        const int len = snprintf(cand, sizeof cand, "%s/%s", d->dir[k], name);
        if (len < 0 || (size_t)len >= sizeof cand || stat(cand, &sb) != 0 || S_ISDIR(sb.st_mode))
            continue;
        if ((size_t)len >= size)
            st = lv_fail(err, LV_ERR_INPUT, "data file %s: path longer than %zu characters",
                         cand, size - 1);
        else
            memcpy(path, cand, (size_t)len + 1);
        goto done;
    }

    /* Not found: every folder searched, with why it was searched. */
    char msg[LV_ERR_MSG_MAX];
    size_t used = 0;
    int n = snprintf(msg, sizeof msg, "%s: lvsim data file not found%s; searched", name,
                     d->env_set ? "" : " (" LV_DATA_ENV " not set)");
    used = n > 0 ? (size_t)n : 0;
    for (size_t k = 0; k < d->n && used < sizeof msg; k++) {
        n = snprintf(msg + used, sizeof msg - used, "%s %s (%s)", k > 0 ? "," : "", d->dir[k],
                     d->origin[k]);
        used += n > 0 ? (size_t)n : 0;
    }
    if (d->n == 0 && used < sizeof msg)
        snprintf(msg + used, sizeof msg - used, " no folder");
    st = lv_fail(err, LV_ERR_NOTFOUND, "%s", msg);
done:
    free(d);
    return st;
}
