/* matio_dl.c - libmatio, loaded the first time lvsim reads or writes a MAT file.
 *
 * Debian's libmatio is built with HDF5, which brings libcurl, GnuTLS, Kerberos, LDAP and some
 * forty other libraries whose loading and constructors cost about 5 ms in every process that
 * links them: most of what `lvsim check` or a run that writes no .mat file cost. liblvsim
 * therefore does not link libmatio: the MAT functions lvsim calls (result_mat.c, table_load.c)
 * are defined here, with matio's own signatures (matio.h), and forward to the library, which
 * is opened with dlopen() the first time one of them is called (io/dl_lib.h). When the
 * library cannot be loaded each call fails as matio itself reports failure (NULL, -1), and
 * lv_matio_error() says why. Adding a matio function lvsim uses: one line in MATIO_FUNCS. */
#define _GNU_SOURCE

#include <matio.h>

#include "io/dl_lib.h"
#include "io/matio_dl.h"

#ifndef LV_MATIO_SONAME
#define LV_MATIO_SONAME "libmatio.so.11" /* set by cmake/lv_deps.cmake from the library found */
#endif

/* X(return type, name, parameters, arguments, value on failure); V(name, ...) for void */
#define MATIO_FUNCS(X, V)                                                                     \
    X(mat_t *, Mat_CreateVer, (const char *a, const char *b, enum mat_ft c), (a, b, c), NULL) \
    X(int, Mat_Close, (mat_t *a), (a), -1)                                                    \
    X(mat_t *, Mat_Open, (const char *a, int b), (a, b), NULL)                                \
    X(int, Mat_Rewind, (mat_t *a), (a), -1)                                                   \
    X(matvar_t *, Mat_VarCreate,                                                              \
      (const char *a, enum matio_classes b, enum matio_types c, int d, size_t *e, void *f,   \
       int g),                                                                                \
      (a, b, c, d, e, f, g), NULL)                                                            \
    X(matvar_t *, Mat_VarRead, (mat_t *a, const char *b), (a, b), NULL)                       \
    X(matvar_t *, Mat_VarReadNextInfo, (mat_t *a), (a), NULL)                                 \
    X(int, Mat_VarWrite, (mat_t *a, matvar_t *b, enum matio_compression c), (a, b, c), -1)   \
    X(enum mat_ft, Mat_GetVersion, (mat_t *a), (a), MAT_FT_UNDEFINED)                         \
    X(unsigned, Mat_VarGetNumberOfFields, (matvar_t *a), (a), 0)                              \
    X(char *const *, Mat_VarGetStructFieldnames, (const matvar_t *a), (a), NULL)              \
    X(matvar_t *, Mat_VarGetStructFieldByIndex, (matvar_t *a, size_t b, size_t c), (a, b, c), \
      NULL)                                                                                   \
    V(Mat_VarFree, (matvar_t * a), (a))

LV_DL_LIBRARY(LV_MATIO_SONAME, MATIO_FUNCS)

const char *lv_matio_error(void) { return dl_error(); }
