/* hdf5_dl.c - the HDF5 library, loaded the first time lvsim reads a MAT v7.3 variable that
 * libmatio cannot classify (table_load.c), as libmatio itself is (matio_dl.c): HDF5 brings
 * some forty libraries whose loading costs about 5 ms in every process that links them, and
 * only such a file needs it. The HDF5 functions table_load.c calls are defined here with
 * HDF5's own signatures (hdf5.h) and forward to the library, opened with dlopen() once per
 * process (pthread_once); its predefined types (H5T_NATIVE_DOUBLE, H5T_C_S1: global variables
 * the library sets in H5open()) are read through lv_h5_native_double() and lv_h5_c_s1().
 * When the library cannot be loaded every call fails as HDF5 reports failure (a negative
 * value, NULL) and lv_hdf5_error() says why. Adding an HDF5 function: one line in
 * HDF5_FUNCS. Not exported. */
#define _GNU_SOURCE

#include <dlfcn.h>
#include <hdf5.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>

#include "io/hdf5_dl.h"

#ifndef LV_HDF5_SONAME
#define LV_HDF5_SONAME "libhdf5_serial.so.103" /* set by cmake/lv_deps.cmake */
#endif

/* X(return type, name, parameters, arguments, value on failure) */
#define HDF5_FUNCS(X)                                                                          \
    X(herr_t, H5open, (void), (), -1)                                                          \
    X(herr_t, H5check_version, (unsigned a, unsigned b, unsigned c), (a, b, c), -1)            \
    X(hid_t, H5Dopen2, (hid_t a, const char *b, hid_t c), (a, b, c), -1)                       \
    X(hid_t, H5Fopen, (const char *a, unsigned b, hid_t c), (a, b, c), -1)                     \
    X(herr_t, H5Fclose, (hid_t a), (a), -1)                                                    \
    X(herr_t, H5Eget_auto2, (hid_t a, H5E_auto2_t * b, void **c), (a, b, c), -1)               \
    X(herr_t, H5Eset_auto2, (hid_t a, H5E_auto2_t b, void *c), (a, b, c), -1)                  \
    X(htri_t, H5Lexists, (hid_t a, const char *b, hid_t c), (a, b, c), -1)                     \
    X(herr_t, H5Literate,                                                                      \
      (hid_t a, H5_index_t b, H5_iter_order_t c, hsize_t * d, H5L_iterate_t e, void *f),       \
      (a, b, c, d, e, f), -1)                                                                  \
    X(hid_t, H5Oopen, (hid_t a, const char *b, hid_t c), (a, b, c), -1)                        \
    X(herr_t, H5Oclose, (hid_t a), (a), -1)                                                    \
    X(herr_t, H5Oget_info_by_name, (hid_t a, const char *b, H5O_info_t *c, hid_t d),           \
      (a, b, c, d), -1)                                                                        \
    X(htri_t, H5Aexists, (hid_t a, const char *b), (a, b), -1)                                 \
    X(hid_t, H5Aopen, (hid_t a, const char *b, hid_t c), (a, b, c), -1)                        \
    X(herr_t, H5Aread, (hid_t a, hid_t b, void *c), (a, b, c), -1)                             \
    X(hid_t, H5Aget_type, (hid_t a), (a), -1)                                                  \
    X(hid_t, H5Aget_space, (hid_t a), (a), -1)                                                 \
    X(herr_t, H5Aclose, (hid_t a), (a), -1)                                                    \
    X(hid_t, H5Dget_type, (hid_t a), (a), -1)                                                  \
    X(hid_t, H5Dget_space, (hid_t a), (a), -1)                                                 \
    X(herr_t, H5Dread, (hid_t a, hid_t b, hid_t c, hid_t d, hid_t e, void *f),                 \
      (a, b, c, d, e, f), -1)                                                                  \
    X(herr_t, H5Dclose, (hid_t a), (a), -1)                                                    \
    X(herr_t, H5Sclose, (hid_t a), (a), -1)                                                    \
    X(int, H5Sget_simple_extent_ndims, (hid_t a), (a), -1)                                     \
    X(int, H5Sget_simple_extent_dims, (hid_t a, hsize_t b[], hsize_t c[]), (a, b, c), -1)      \
    X(hssize_t, H5Sget_simple_extent_npoints, (hid_t a), (a), -1)                              \
    X(hid_t, H5Tcopy, (hid_t a), (a), -1)                                                      \
    X(herr_t, H5Tclose, (hid_t a), (a), -1)                                                    \
    X(H5T_class_t, H5Tget_class, (hid_t a), (a), H5T_NO_CLASS)                                 \
    X(size_t, H5Tget_size, (hid_t a), (a), 0)                                                  \
    X(herr_t, H5Tset_size, (hid_t a, size_t b), (a, b), -1)                                    \
    X(htri_t, H5Tis_variable_str, (hid_t a), (a), -1)                                          \
    X(herr_t, H5free_memory, (void *a), (a), -1)

#define FIELD(ret, name, params, args, fail) ret(*name) params;
static struct {
    HDF5_FUNCS(FIELD)
    const hid_t *native_double, *c_s1; /* the library's H5T_NATIVE_DOUBLE_g, H5T_C_S1_g */
} fn;
static pthread_once_t once = PTHREAD_ONCE_INIT;
static int loaded;    /* written once, in load() */
static char why[256]; /* written once, in load() */

static void load(void)
{
    void *h = dlopen(LV_HDF5_SONAME, RTLD_NOW | RTLD_LOCAL);
    if (h == NULL) {
        snprintf(why, sizeof why, "%s", dlerror());
        return;
    }
    int ok = 1;
#define RESOLVE(ret, name, params, args, fail)                                               \
    {                                                                                         \
        void *sym = dlsym(h, #name);                                                          \
        ok &= sym != NULL;                                                                    \
        memcpy(&fn.name, &sym, sizeof sym); /* POSIX: dlsym's pointer names the function */ \
    }
    HDF5_FUNCS(RESOLVE)
    /* the variables where the library writes them: a program that also links HDF5 and uses
     * its types has copies of them (copy relocations) that the global scope finds first */
    fn.native_double = dlsym(RTLD_DEFAULT, "H5T_NATIVE_DOUBLE_g");
    if (fn.native_double == NULL)
        fn.native_double = dlsym(h, "H5T_NATIVE_DOUBLE_g");
    fn.c_s1 = dlsym(RTLD_DEFAULT, "H5T_C_S1_g");
    if (fn.c_s1 == NULL)
        fn.c_s1 = dlsym(h, "H5T_C_S1_g");
    ok &= fn.native_double != NULL && fn.c_s1 != NULL;
    if (ok && fn.H5open() < 0) /* sets the predefined types */
        ok = 0;
    if (!ok)
        snprintf(why, sizeof why, "%s lacks a function lvsim needs, or did not start",
                 LV_HDF5_SONAME);
    loaded = ok;
}

#define FORWARD(ret, name, params, args, fail)                                                \
    ret name params                                                                           \
    {                                                                                         \
        pthread_once(&once, load);                                                            \
        return loaded ? fn.name args : fail;                                                  \
    }
HDF5_FUNCS(FORWARD)

hid_t lv_h5_native_double(void)
{
    pthread_once(&once, load);
    return loaded ? *fn.native_double : -1;
}

hid_t lv_h5_c_s1(void)
{
    pthread_once(&once, load);
    return loaded ? *fn.c_s1 : -1;
}

const char *lv_hdf5_error(void)
{
    pthread_once(&once, load);
    return loaded ? NULL : why;
}
