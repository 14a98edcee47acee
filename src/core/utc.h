/* utc.h - UTC instants with their leap seconds (internal, not exported): ISO 8601 UTC text to
 * TAI and back, TAI - UTC, the leap seconds inside a span, a note when the leap-second table
 * cannot vouch for a date. Through ERFA (Debian's liberfa: the IAU SOFA algorithms eraDtf2d,
 * eraUtctai, eraTaiutc, eraD2dtf and eraDat with its table). liblvsim (the mission epoch) and
 * liblvsim_post (every written instant) each carry a copy. docs/exports.md, "Times". */
#ifndef LV_CORE_UTC_H
#define LV_CORE_UTC_H

#include <stddef.h>

/* An instant on the TAI scale: whole microseconds since 1970-01-01T00:00:00 TAI. Mission time
 * t (SI seconds since the epoch) is added to the epoch's as lv_utc_add(epoch, t). */
typedef long long lv_tai;

enum {
    LV_UTC_OK = 0,
    LV_UTC_DUBIOUS = 1,  /* valid, but outside what ERFA's table vouches for: before 1960 (no
                          * UTC yet) or past its "dubious year" (leap seconds announced after
                          * ERFA's release are unknown to it); lv_utc_note says so */
    LV_UTC_BAD = -1,     /* not "YYYY-MM-DDThh:mm:ss[.f...]Z", or no such date or time */
    LV_UTC_NO_LEAP = -2  /* a second 60 where no leap second was: only 23:59:60 of a day that
                          * ended with one exists */
};

/* s, "YYYY-MM-DDThh:mm:ss[.f...]Z" (the mission parser's form; seconds 60 in a leap second),
 * as TAI, rounded to the microsecond. Returns LV_UTC_OK, LV_UTC_DUBIOUS (*out set),
 * LV_UTC_BAD or LV_UTC_NO_LEAP (*out untouched). */
int lv_utc_parse(const char *s, lv_tai *out);

/* epoch + t seconds (SI), the microsecond nearest; t beyond +-1e11 s (3000 years) is held
 * there (no instant lvsim writes is that far). */
lv_tai lv_utc_add(lv_tai epoch, double t);

/* UTC of `t` as "YYYY-MM-DDThh:mm:ss[.ffffff]" + suffix ("Z" or ""), the fraction only when
 * not zero; an instant inside a leap second is 23:59:60.ffffff. With no60 set, such an
 * instant is written 23:59:59.999999 instead (for formats without a second 60) and *in_leap
 * (may be NULL) is set to 1, else 0. buf: at least 48 bytes. Returns LV_UTC_OK,
 * LV_UTC_DUBIOUS or LV_UTC_BAD (a year outside 0000..9999: buf gets "invalid"). */
int lv_utc_format(lv_tai t, int no60, const char *suffix, char *buf, size_t cap, int *in_leap);

/* TAI - UTC at `t`, s (37 from 2017-01-01; a fraction between 1961 and 1972; 0 before). */
double lv_utc_tai_minus_utc(lv_tai t);

/* The leap seconds that start in [a, b]: their number, and the instants of their starts
 * (23:59:60.0 UTC) in starts[0 .. min(number, cap)) (starts may be NULL when cap is 0). */
size_t lv_utc_leaps(lv_tai a, lv_tai b, lv_tai *starts, size_t cap);

/* When some instant of [a, b] lies outside what ERFA's table vouches for (LV_UTC_DUBIOUS),
 * one sentence saying so and how far the written UTC can be off; returns 1. Else buf = ""
 * and 0. 256 bytes hold both sentences (before 1960, after the table). */
int lv_utc_note(lv_tai a, lv_tai b, char *buf, size_t cap);

/* The version of the ERFA whose table is used: "2.0.0". */
const char *lv_utc_erfa_version(void);

#endif
