/* status.h - internal helpers to fill an lv_err (not exported). */
#ifndef LV_CORE_STATUS_H
#define LV_CORE_STATUS_H

#include "lvsim/lv_status.h"

#if defined(__GNUC__)
#define LV_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define LV_PRINTF(a, b)
#endif

/* Fill `err` (may be NULL) with `code` and a formatted message; returns `code`. */
lv_status lv_fail(lv_err *err, lv_status code, const char *fmt, ...) LV_PRINTF(3, 4);

/* Prefix an existing message: "prefix: old message". Returns err->code (or code). */
lv_status lv_fail_prefix(lv_err *err, lv_status code, const char *fmt, ...) LV_PRINTF(3, 4);

/* The system's text for errno value e ("Permission denied"), written into buf (strerror_r in
 * its XSI form: no buffer shared between threads, and the same in files that define
 * _GNU_SOURCE); returns buf. */
const char *lv_strerror(int e, char *buf, size_t cap);

#endif
