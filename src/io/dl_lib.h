/* dl_lib.h - internal: a shared library loaded the first time one of its functions is called.
 *
 * Linking a library costs every process its loading and relocation, whether or not it calls
 * it: libzip (with OpenSSL's libcrypto) alone is about 3 million instructions, a quarter of
 * `lvsim --version` (issue 24: measured with callgrind). The libraries that only some commands
 * need (libmatio: MAT files; libzip: `lvsim fmu`; SQLite: `lvsim mc`; NLopt: `lvsim target`
 * with an optimiser) are therefore not linked: a file `<lib>_dl.c` defines the functions
 * lvsim calls, with the library's own signatures (its header is included), and forwards them
 * to the library, opened with dlopen() once per process (pthread_once) at the first call. A
 * process that never calls one never loads the library.
 *
 * Use, in one .c file per library (the names below are static to it):
 *
 *     #define ZIP_FUNCS(X, V)                                    \
 *         X(int, zip_close, (zip_t *a), (a), -1)                 \
 *         V(zip_discard, (zip_t *a), (a))
 *     LV_DL_LIBRARY(LV_ZIP_SONAME, ZIP_FUNCS)
 *     const char *lv_zip_error(void) { return dl_error(); }
 *
 * X(return type, name, parameters, arguments, value returned when the library cannot be
 * loaded) for a function with a result, V(name, parameters, arguments) for a void one (a
 * no-op then). dl_error() loads the library if no function has yet and says why it could not
 * be loaded, or returns NULL: a caller checks it before its first call to give the user the
 * reason instead of the library's own failure. The entry points are written once, in the
 * pthread_once routine, and read-only after: thread-safe. Adding a function: one line.
 * Not exported: the forwarders take the visibility of the library that compiles them. */
#ifndef LV_IO_DL_LIB_H
#define LV_IO_DL_LIB_H

#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>

#define LV_DL_FIELD(ret, name, params, args, fail) ret(*name) params;
#define LV_DL_FIELD_V(name, params, args) void(*name) params;
/* POSIX: the pointer dlsym returns names the function; memcpy avoids the object-to-function
 * pointer conversion ISO C leaves undefined */
#define LV_DL_RESOLVE(ret, name, params, args, fail)                                          \
    {                                                                                          \
        void *sym = dlsym(h, #name);                                                           \
        ok &= sym != NULL;                                                                     \
        if (sym == NULL && missing[0] == '\0')                                                 \
            snprintf(missing, sizeof missing, "%s", #name);                                    \
        memcpy(&dl_fn.name, &sym, sizeof sym);                                                 \
    }
#define LV_DL_RESOLVE_V(name, params, args) LV_DL_RESOLVE(void, name, params, args, )
#define LV_DL_FORWARD(ret, name, params, args, fail)                                          \
    ret name params                                                                            \
    {                                                                                          \
        pthread_once(&dl_once, dl_load);                                                       \
        return dl_loaded ? dl_fn.name args : fail;                                             \
    }
#define LV_DL_FORWARD_V(name, params, args)                                                   \
    void name params                                                                           \
    {                                                                                          \
        pthread_once(&dl_once, dl_load);                                                       \
        if (dl_loaded)                                                                         \
            dl_fn.name args;                                                                   \
    }

#define LV_DL_LIBRARY(soname, FUNCS)                                                          \
    static struct {                                                                            \
        FUNCS(LV_DL_FIELD, LV_DL_FIELD_V)                                                      \
    } dl_fn;                                                                                   \
    static pthread_once_t dl_once = PTHREAD_ONCE_INIT;                                         \
    static int dl_loaded;    /* written once, in dl_load() */                                  \
    static char dl_why[320]; /* written once, in dl_load(): why it could not be loaded */      \
    static void dl_load(void)                                                                  \
    {                                                                                          \
        void *h = dlopen(soname, RTLD_NOW | RTLD_LOCAL);                                       \
        if (h == NULL) {                                                                       \
            snprintf(dl_why, sizeof dl_why, "%s", dlerror());                                  \
            return;                                                                            \
        }                                                                                      \
        int ok = 1;                                                                            \
        char missing[64] = "";                                                                 \
        FUNCS(LV_DL_RESOLVE, LV_DL_RESOLVE_V)                                                  \
        if (!ok)                                                                               \
            snprintf(dl_why, sizeof dl_why, "%s lacks %s, a function lvsim needs", soname,     \
                     missing);                                                                 \
        dl_loaded = ok;                                                                        \
    }                                                                                          \
    static const char *dl_error(void)                                                          \
    {                                                                                          \
        pthread_once(&dl_once, dl_load);                                                       \
        return dl_loaded ? NULL : dl_why;                                                      \
    }                                                                                          \
    FUNCS(LV_DL_FORWARD, LV_DL_FORWARD_V)

#endif
