/* zip_dl.c - libzip, loaded the first time `lvsim fmu` writes an archive (io/dl_lib.h).
 *
 * Only the FMU exporter (export.c) writes a zip archive, yet linking libzip (and OpenSSL's
 * libcrypto, which Debian's libzip needs) costs every lvsim process about 3 million
 * instructions of loading and relocation (callgrind, `lvsim --version`: 12.0 M before, issue
 * 24). The zip functions export.c calls are defined here with libzip's own signatures and
 * forward to the library; lv_zip_error() says why it could not be loaded. Adding a function:
 * one line in ZIP_FUNCS. */
#define _GNU_SOURCE
#define ZIP_EXTERN /* these definitions are liblvsim_post's own, hidden: not exported */

#include <zip.h>

#include "fmi/zip_dl.h"
#include "io/dl_lib.h"

#ifndef LV_ZIP_SONAME
#define LV_ZIP_SONAME "libzip.so.4" /* set by cmake/lv_deps.cmake from the library found */
#endif

#define ZIP_FUNCS(X, V)                                                                       \
    X(zip_t *, zip_open, (const char *a, int b, int *c), (a, b, c), NULL)                     \
    X(int, zip_close, (zip_t * a), (a), -1)                                                   \
    V(zip_discard, (zip_t * a), (a))                                                          \
    X(const char *, zip_strerror, (zip_t * a), (a), "libzip is not loaded")                   \
    V(zip_error_init_with_code, (zip_error_t * a, int b), (a, b))                             \
    X(const char *, zip_error_strerror, (zip_error_t * a), (a), "libzip is not loaded")       \
    V(zip_error_fini, (zip_error_t * a), (a))                                                 \
    X(zip_int64_t, zip_file_add, (zip_t * a, const char *b, zip_source_t *c, zip_flags_t d),  \
      (a, b, c, d), -1)                                                                       \
    X(int, zip_file_set_external_attributes,                                                  \
      (zip_t * a, zip_uint64_t b, zip_flags_t c, zip_uint8_t d, zip_uint32_t e),              \
      (a, b, c, d, e), -1)                                                                    \
    X(zip_source_t *, zip_source_buffer, (zip_t * a, const void *b, zip_uint64_t c, int d),   \
      (a, b, c, d), NULL)                                                                     \
    X(zip_source_t *, zip_source_file, (zip_t * a, const char *b, zip_uint64_t c,             \
                                        zip_int64_t d),                                       \
      (a, b, c, d), NULL)                                                                     \
    V(zip_source_free, (zip_source_t * a), (a))

LV_DL_LIBRARY(LV_ZIP_SONAME, ZIP_FUNCS)

const char *lv_zip_error(void) { return dl_error(); }
