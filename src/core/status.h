/* status.h - internal helpers to fill an lv_err (not exported). */
#ifndef LV_CORE_STATUS_H
#define LV_CORE_STATUS_H

#include <stddef.h>

#include "lvsim/lv_status.h"

#if defined(__GNUC__)
#define LV_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define LV_PRINTF(a, b)
#endif

/* Numbers for messages, never 301 digits: a count exact below ten million, else "1.4e+11";
 * bytes as "12.3 MB", "512 B" (beyond exabytes "5.04e+35 B"). Return buf. */
char *lv_fmt_count(double n, char *buf, size_t cap);
char *lv_fmt_bytes(double bytes, char *buf, size_t cap);

/* Fill `err` (may be NULL) with `code` and a formatted message; returns `code`. */
lv_status lv_fail(lv_err *err, lv_status code, const char *fmt, ...) LV_PRINTF(3, 4);

/* Prefix an existing message: "prefix: old message". Returns err->code (or code). */
lv_status lv_fail_prefix(lv_err *err, lv_status code, const char *fmt, ...) LV_PRINTF(3, 4);

/* The system's text for errno value `e` ("Permission denied") in buf[cap], returned; the one
 * helper behind every system error message of the libraries. Thread-safe (strerror_r, built
 * as the XSI variant in status.c whatever feature macros the caller defines; "error E" only
 * for a value the system has no text for). */
#define LV_STRERROR_MAX 128
const char *lv_strerror(int e, char *buf, size_t cap);
/* The same into a buffer that lives until the end of the enclosing block, for a message
 * argument: lv_fail(err, LV_ERR_IO, "%s: %s", path, LV_STRERROR(errno)). */
#define LV_STRERROR(e) lv_strerror((e), (char[LV_STRERROR_MAX]){0}, LV_STRERROR_MAX)

#endif
