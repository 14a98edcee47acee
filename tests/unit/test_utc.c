/* test_utc.c - UTC with leap seconds (src/core/utc.c over ERFA) against independent answers:
 * the IERS leap-second list (Bulletin C; TAI - UTC = 32 s from 1999-01-01, 35 s from
 * 2012-07-01, 36 s from 2015-07-01, 37 s from 2017-01-01; 27 leap seconds from 1972 to 2016),
 * USNO's tai-utc.dat for the drifting 1968-1971 offset, and Unix day numbers (POSIX time
 * counts 86400 s a day: 2017-01-01 is 1483228800 / 86400 = 17167 days after 1970-01-01). */
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "core/utc.h"

#define DAY 86400000000LL /* us */
#define S 1000000LL       /* us */

/* TAI microseconds since 1970-01-01T00:00:00 TAI of the UTC instant `day` days after
 * 1970-01-01 at second `sod` of that day, TAI - UTC = `dat` s. */
static lv_tai tai_of(long long day, long long sod_us, long long dat)
{
    return day * DAY + sod_us + dat * S;
}

static void check_format(lv_tai t, int no60, const char *want, int want_leap)
{
    char buf[48];
    int in_leap = -1;
    const int st = lv_utc_format(t, no60, "Z", buf, sizeof buf, &in_leap);
    CHECK(st == LV_UTC_OK);
    CHECK(strcmp(buf, want) == 0);
    CHECK(in_leap == want_leap);
    if (strcmp(buf, want) != 0)
        fprintf(stderr, "  wrote %s, expected %s\n", buf, want);
}

int main(void)
{
    lv_tai t = 0;
    const long long d2017 = 17167, d2015_07 = 16617; /* 1435708800 / 86400 */

    /* Parsing: TAI = UTC + TAI - UTC, the leap second counted. */
    CHECK(lv_utc_parse("2017-01-01T00:00:00Z", &t) == LV_UTC_OK);
    CHECK(t == tai_of(d2017, 0, 37));
    CHECK(lv_utc_parse("2016-12-31T23:59:60Z", &t) == LV_UTC_OK);
    CHECK(t == tai_of(d2017, 0, 36)); /* 1 s before 2017-01-01T00:00:00Z */
    CHECK(lv_utc_parse("2016-12-31T23:59:59Z", &t) == LV_UTC_OK);
    CHECK(t == tai_of(d2017 - 1, 86399 * S, 36));
    CHECK(lv_utc_parse("2015-06-30T23:59:60.5Z", &t) == LV_UTC_OK);
    CHECK(t == tai_of(d2015_07, 0, 35) + S / 2);
    CHECK(lv_utc_parse("2000-01-01T12:00:00Z", &t) == LV_UTC_OK);
    CHECK(t == 946728000LL * S + 32 * S);
    CHECK(lv_utc_parse("2026-03-01T12:00:00.1234567Z", &t) == LV_UTC_OK); /* nearest us */
    CHECK(lv_utc_parse("2026-03-01T12:00:00Z", &t) == LV_UTC_OK);
    lv_tai t7;
    CHECK(lv_utc_parse("2026-03-01T12:00:00.1234567Z", &t7) == LV_UTC_OK && t7 - t == 123457);

    /* A second 60 only where a leap second was; malformed text. */
    CHECK(lv_utc_parse("2016-12-30T23:59:60Z", &t) == LV_UTC_NO_LEAP);
    CHECK(lv_utc_parse("2016-12-31T23:58:60Z", &t) == LV_UTC_NO_LEAP);
    CHECK(lv_utc_parse("2017-06-30T23:59:60Z", &t) == LV_UTC_NO_LEAP);
    CHECK(lv_utc_parse("2016-12-31T23:59:61Z", &t) == LV_UTC_BAD);
    CHECK(lv_utc_parse("2026-02-30T12:00:00Z", &t) == LV_UTC_BAD);
    CHECK(lv_utc_parse("2026-03-01T24:00:00Z", &t) == LV_UTC_BAD);
    CHECK(lv_utc_parse("2026-03-01T12:00:00", &t) == LV_UTC_BAD);
    CHECK(lv_utc_parse("2026-03-01T12:00:00+01:00", &t) == LV_UTC_BAD);
    CHECK(lv_utc_parse("2026-03-01T12:00:00.Z", &t) == LV_UTC_BAD);
    CHECK(lv_utc_parse(NULL, &t) == LV_UTC_BAD);

    /* Writing: mission seconds are SI seconds, so 2 s after 23:59:59 is 00:00:00, not 00:00:01;
     * inside the leap second :60, or 23:59:59.999999 for a format without it. */
    lv_tai e;
    CHECK(lv_utc_parse("2016-12-31T23:59:59Z", &e) == LV_UTC_OK);
    check_format(lv_utc_add(e, 1.0), 0, "2016-12-31T23:59:60Z", 0);
    check_format(lv_utc_add(e, 1.25), 0, "2016-12-31T23:59:60.250000Z", 0);
    check_format(lv_utc_add(e, 1.999999), 0, "2016-12-31T23:59:60.999999Z", 0);
    check_format(lv_utc_add(e, 2.0), 0, "2017-01-01T00:00:00Z", 0);
    check_format(lv_utc_add(e, 1.25), 1, "2016-12-31T23:59:59.999999Z", 1);
    check_format(lv_utc_add(e, 0.5), 1, "2016-12-31T23:59:59.500000Z", 0);
    check_format(lv_utc_add(e, 2.0 + 86400.0 * 181), 0, "2017-07-01T00:00:00Z", 0);
    check_format(lv_utc_add(e, -86400.0 * 549), 0, "2015-07-01T23:59:59Z", 0);
    /* a day back from there crosses 2015-06-30's leap second: 86400 s reach only its :60 */
    check_format(lv_utc_add(e, -86400.0 * 549 - 86399.0), 0, "2015-07-01T00:00:00Z", 0);
    check_format(lv_utc_add(e, -86400.0 * 549 - 86400.0), 0, "2015-06-30T23:59:60Z", 0);
    check_format(lv_utc_add(e, -86400.0 * 549 - 86401.0), 0, "2015-06-30T23:59:59Z", 0);
    /* every 0.1 s across the leap second reads back to itself */
    int round_trip = 1;
    for (int i = -100; i <= 100; i++) {
        char buf[48];
        lv_tai a = lv_utc_add(e, 1.0 + 0.1 * i), b = 0;
        lv_utc_format(a, 0, "Z", buf, sizeof buf, NULL);
        round_trip &= lv_utc_parse(buf, &b) == LV_UTC_OK && a == b;
    }
    CHECK(round_trip);

    /* TAI - UTC (the 1970 value: tai-utc.dat, 4.2131700 s + (MJD - 39126) x 0.002592 s at
     * MJD 40587 = 8.000082 s). */
    CHECK(lv_utc_parse("2016-06-01T00:00:00Z", &t) == LV_UTC_OK);
    CHECK_CLOSE(lv_utc_tai_minus_utc(t), 36.0, 0.0);
    CHECK(lv_utc_parse("2017-06-01T00:00:00Z", &t) == LV_UTC_OK);
    CHECK_CLOSE(lv_utc_tai_minus_utc(t), 37.0, 0.0);
    CHECK(lv_utc_parse("1970-01-01T00:00:00Z", &t) == LV_UTC_OK);
    CHECK_CLOSE(lv_utc_tai_minus_utc(t), 8.000082, 1e-9);
    CHECK_CLOSE((double)t / 1e6, 8.000082, 1e-6);

    /* The leap seconds inside a span: 2015-06-30 and 2016-12-31 in 2015..mid-2017; 27 from
     * 1972 to 2017-01-01; none in a span that misses them. */
    lv_tai a, b, starts[4], l1, l2;
    CHECK(lv_utc_parse("2015-01-01T00:00:00Z", &a) == LV_UTC_OK);
    CHECK(lv_utc_parse("2017-06-01T00:00:00Z", &b) == LV_UTC_OK);
    CHECK(lv_utc_parse("2015-06-30T23:59:60Z", &l1) == LV_UTC_OK);
    CHECK(lv_utc_parse("2016-12-31T23:59:60Z", &l2) == LV_UTC_OK);
    CHECK(lv_utc_leaps(a, b, starts, 4) == 2);
    CHECK(starts[0] == l1 && starts[1] == l2);
    CHECK(lv_utc_leaps(l2, l2, starts, 4) == 1 && starts[0] == l2);
    CHECK(lv_utc_leaps(l2 + 1, b, starts, 4) == 0);
    CHECK(lv_utc_parse("1960-01-01T00:00:00Z", &a) == LV_UTC_OK);
    CHECK(lv_utc_parse("2017-01-01T00:00:00Z", &b) == LV_UTC_OK);
    CHECK(lv_utc_leaps(a, b, NULL, 0) == 27);

    /* The table's limits: a note far in the future and before 1960; none in 2016-2017. */
    char note[256];
    CHECK(lv_utc_note(l1, l2, note, sizeof note) == 0 && note[0] == '\0');
    CHECK(lv_utc_parse("2200-01-01T00:00:00Z", &a) == LV_UTC_DUBIOUS);
    CHECK(lv_utc_note(l2, a, note, sizeof note) == 1);
    CHECK(strstr(note, "leap-second table") != NULL && strlen(note) < 256);
    CHECK(strstr(note, "2016-12-31T23:59:60Z") != NULL); /* its last leap second */
    CHECK(lv_utc_parse("1950-01-01T00:00:00Z", &a) == LV_UTC_DUBIOUS);
    CHECK(lv_utc_note(a, l1, note, sizeof note) == 1 && strstr(note, "1960") != NULL);
    CHECK(lv_utc_parse("2200-01-01T00:00:00Z", &b) == LV_UTC_DUBIOUS);
    CHECK(lv_utc_note(a, b, note, sizeof note) == 1 && strstr(note, "1960") != NULL &&
          strstr(note, "leap-second table") != NULL && strlen(note) < sizeof note - 1);
    char buf[48];
    CHECK(lv_utc_format(a, 0, "Z", buf, sizeof buf, NULL) == LV_UTC_DUBIOUS);
    CHECK(strcmp(buf, "1950-01-01T00:00:00Z") == 0);

    return check_report("test_utc");
}
