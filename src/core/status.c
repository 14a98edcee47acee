/* status.c - status strings, error-record formatting and the system's error texts. */
#define _POSIX_C_SOURCE 200809L /* strerror_r: the XSI variant (int); never _GNU_SOURCE here */

#include "core/status.h"

#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

const char *lv_status_str(lv_status st)
{
#define LV_STATUS_CASE_(name, value, text) \
    case name:                             \
        return text;
    switch (st) {
        LV_STATUS_LIST(LV_STATUS_CASE_)
    }
#undef LV_STATUS_CASE_
    return "unknown status";
}

const char *lv_status_name(lv_status st)
{
#define LV_STATUS_CASE_(name, value, text) \
    case name:                             \
        return #name;
    switch (st) {
        LV_STATUS_LIST(LV_STATUS_CASE_)
    }
#undef LV_STATUS_CASE_
    return NULL;
}

/* ---- numbers in messages: never 301 digits ---- */

char *lv_fmt_count(double n, char *buf, size_t cap)
{
    if (n < 1e7 && n > -1e7)
        snprintf(buf, cap, "%.0f", n);
    else
        snprintf(buf, cap, "%.3g", n);
    return buf;
}

char *lv_fmt_bytes(double b, char *buf, size_t cap)
{
    static const char *const unit[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
    size_t u = 0;
    double x = b;
    while (x >= 1000.0 && u + 1 < sizeof unit / sizeof unit[0]) {
        x /= 1000.0;
        u++;
    }
    if (u == 0)
        snprintf(buf, cap, "%.0f B", b);
    else if (x >= 1000.0) /* beyond exabytes: the bytes in exponent form */
        snprintf(buf, cap, "%.3g B", b);
    else
        snprintf(buf, cap, "%.3g %s", x, unit[u]);
    return buf;
}

lv_status lv_fail(lv_err *err, lv_status code, const char *fmt, ...)
{
    if (err == NULL)
        return code;
    err->code = code;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
    return code;
}

lv_status lv_fail_prefix(lv_err *err, lv_status code, const char *fmt, ...)
{
    if (err == NULL)
        return code;
    char old[LV_ERR_MSG_MAX];
    memcpy(old, err->msg, sizeof old);
    old[sizeof old - 1] = '\0';
    char prefix[LV_ERR_MSG_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(prefix, sizeof prefix, fmt, ap);
    va_end(ap);
    err->code = code;
    size_t n = strlen(prefix);
    if (n > sizeof err->msg - 3)
        n = sizeof err->msg - 3;
    memcpy(err->msg, prefix, n);
    memcpy(err->msg + n, ": ", 2);
    size_t room = sizeof err->msg - n - 2;
    size_t m = strlen(old);
    if (m >= room)
        m = room - 1;
    memcpy(err->msg + n + 2, old, m);
    err->msg[n + 2 + m] = '\0';
    return code;
}

const char *lv_strerror(int e, char *buf, size_t cap)
{
    if (buf == NULL || cap == 0)
        return "";
    /* XSI: 0 or an error number. Held in an int so that the GNU variant (char *, what a file
     * with _GNU_SOURCE gets, whose result is never 0) cannot compile here. */
    const int rc = strerror_r(e, buf, cap);
    if (rc != 0 || buf[0] == '\0')
        snprintf(buf, cap, "error %d", e);
    return buf;
}
