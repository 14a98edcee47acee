/* utc.c - UTC instants with their leap seconds, through ERFA (the IAU SOFA algorithms and its
 * table of TAI - UTC: eraDtf2d, eraUtctai, eraTaiutc, eraD2dtf, eraDat). Instants are whole
 * TAI microseconds, so mission time adds exactly and every written time is rounded once; the
 * ERFA two-part Julian dates in between carry ~1e-11 s. Contract: core/utc.h. */
#include "core/utc.h"

#include <erfa.h>
#include <erfaextra.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#define DAY_US 86400000000LL  /* microseconds per TAI day */
#define JD_1970 2440587.5     /* Julian date of 1970-01-01T00:00:00 */
#define T_MAX 1e11            /* s: |t| held below this (3000 years) */

/* The fields of "YYYY-MM-DDThh:mm:ss[.f...]Z", strictly; 0, or -1 when it is not that. */
static int fields(const char *s, int v[6], double *frac)
{
    static const char tmpl[] = "dddd-dd-ddTdd:dd:dd";
    for (size_t i = 0; i < sizeof tmpl - 1; i++) {
        const char ch = s[i];
        if (tmpl[i] == 'd' ? !(ch >= '0' && ch <= '9') : ch != tmpl[i])
            return -1;
    }
    static const int at[6] = {0, 5, 8, 11, 14, 17}, len[6] = {4, 2, 2, 2, 2, 2};
    for (int k = 0; k < 6; k++) {
        v[k] = 0;
        for (int i = 0; i < len[k]; i++)
            v[k] = 10 * v[k] + (s[at[k] + i] - '0');
    }
    const char *p = s + sizeof tmpl - 1;
    *frac = 0.0;
    if (*p == '.') { /* digits past the 15th are below a femtosecond: read, not counted */
        const char *q = ++p;
        long long num = 0, den = 1;
        for (; *p >= '0' && *p <= '9'; p++)
            if (p - q < 15) {
                num = 10 * num + (*p - '0');
                den *= 10;
            }
        if (p == q)
            return -1;
        *frac = (double)num / (double)den;
    }
    return p[0] == 'Z' && p[1] == '\0' ? 0 : -1;
}

/* TAI two-part Julian date (big part first) as whole microseconds. */
static lv_tai from_jd(double tai1, double tai2)
{
    const double days = floor(tai1 - JD_1970); /* tai1 is a day's 0h: exact */
    const double rest = (tai1 - JD_1970 - days) + tai2;
    return (lv_tai)days * DAY_US + llround(rest * (double)DAY_US);
}

static void to_jd(lv_tai t, double *tai1, double *tai2)
{
    lv_tai days = t / DAY_US, rem = t % DAY_US;
    if (rem < 0) {
        rem += DAY_US;
        days -= 1;
    }
    *tai1 = JD_1970 + (double)days;
    *tai2 = (double)rem / (double)DAY_US;
}

/* UTC of t as a quasi Julian date (ERFA's convention: a day of 86401 s in a leap second). */
static int to_utc(lv_tai t, double *u1, double *u2)
{
    double a1, a2;
    to_jd(t, &a1, &a2);
    return eraTaiutc(a1, a2, u1, u2);
}

/* The TAI instant of a UTC calendar time (validated by eraDtf2d); ERFA's status. */
static int from_utc(int y, int mo, int d, int h, int mi, double sec, lv_tai *out)
{
    double d1, d2, t1, t2;
    const int js = eraDtf2d("UTC", y, mo, d, h, mi, sec, &d1, &d2);
    if (js < 0 || (js & 2))
        return js;
    const int ju = eraUtctai(d1, d2, &t1, &t2);
    if (ju < 0)
        return -1;
    *out = from_jd(t1, t2);
    return js;
}

int lv_utc_parse(const char *s, lv_tai *out)
{
    int v[6];
    double frac;
    if (s == NULL || fields(s, v, &frac) != 0 || v[5] > 60)
        return LV_UTC_BAD;
    lv_tai t = 0;
    const int js = from_utc(v[0], v[1], v[2], v[3], v[4], v[5] + frac, &t);
    if (js < 0)
        return LV_UTC_BAD;
    if (js & 2) /* past the day's last second: a :60 of a day without a leap second */
        return v[5] == 60 ? LV_UTC_NO_LEAP : LV_UTC_BAD;
    *out = t;
    return js & 1 ? LV_UTC_DUBIOUS : LV_UTC_OK;
}

lv_tai lv_utc_add(lv_tai epoch, double t)
{
    const double c = t > T_MAX ? T_MAX : t < -T_MAX ? -T_MAX : t;
    return epoch + llround((isnan(c) ? 0.0 : c) * 1e6);
}

int lv_utc_format(lv_tai t, int no60, const char *suffix, char *buf, size_t cap, int *in_leap)
{
    double u1, u2;
    int y, mo, d, hmsf[4];
    if (in_leap != NULL)
        *in_leap = 0;
    const int ju = to_utc(t, &u1, &u2);
    const int jd = ju < 0 ? -1 : eraD2dtf("UTC", 6, u1, u2, &y, &mo, &d, hmsf);
    if (jd < 0 || y < 0 || y > 9999) {
        snprintf(buf, cap, "invalid%s", suffix);
        return LV_UTC_BAD;
    }
    if (hmsf[2] == 60 && no60) { /* the last microsecond before the leap second */
        hmsf[2] = 59;
        hmsf[3] = 999999;
        if (in_leap != NULL)
            *in_leap = 1;
    }
    if (hmsf[3] == 0)
        snprintf(buf, cap, "%04d-%02d-%02dT%02d:%02d:%02d%s", y, mo, d, hmsf[0], hmsf[1],
                 hmsf[2], suffix);
    else
        snprintf(buf, cap, "%04d-%02d-%02dT%02d:%02d:%02d.%06d%s", y, mo, d, hmsf[0], hmsf[1],
                 hmsf[2], hmsf[3], suffix);
    return ju == 1 || jd == 1 ? LV_UTC_DUBIOUS : LV_UTC_OK;
}

/* UTC calendar date of t and the fraction of its day; ERFA's status. */
static int utc_date(lv_tai t, int *y, int *mo, int *d, double *fd)
{
    double u1, u2;
    const int ju = to_utc(t, &u1, &u2);
    if (ju < 0 || eraJd2cal(u1, u2, y, mo, d, fd) != 0)
        return -1;
    return ju;
}

double lv_utc_tai_minus_utc(lv_tai t)
{
    int y, mo, d;
    double fd, dat = 0.0;
    if (utc_date(t, &y, &mo, &d, &fd) >= 0)
        (void)eraDat(y, mo, d, fd, &dat);
    return dat;
}

/* Days in month mo of year y (Gregorian), from ERFA's calendar. */
static int month_days(int y, int mo)
{
    double a0, a1, b0, b1;
    const int ny = mo == 12 ? y + 1 : y, nm = mo == 12 ? 1 : mo + 1;
    if (eraCal2jd(y, mo, 1, &a0, &a1) != 0 || eraCal2jd(ny, nm, 1, &b0, &b1) != 0)
        return 0;
    return (int)lround((b0 - a0) + (b1 - a1));
}

/* 1 when month mo of year y ends with a (positive) leap second, its start in *start. Leap
 * seconds come at the end of a month (ITU-R TF.460-6); the steps of 1961-1971 (0.05-0.1 s)
 * are not leap seconds. */
static int month_leap(int y, int mo, lv_tai *start)
{
    const int last = month_days(y, mo);
    double dat1, dat2;
    if (last == 0 || eraDat(y, mo, last, 0.0, &dat1) < 0 ||
        eraDat(mo == 12 ? y + 1 : y, mo == 12 ? 1 : mo + 1, 1, 0.0, &dat2) < 0 ||
        !(dat2 - dat1 > 0.5))
        return 0;
    return from_utc(y, mo, last, 23, 59, 60.0, start) >= 0;
}

size_t lv_utc_leaps(lv_tai a, lv_tai b, lv_tai *starts, size_t cap)
{
    int ya, ma, yb, mb, d;
    double fd;
    if (b < a || utc_date(a, &ya, &ma, &d, &fd) < 0 || utc_date(b, &yb, &mb, &d, &fd) < 0)
        return 0;
    if (ya < 1972) { /* no leap second before 1972-06-30 */
        ya = 1972;
        ma = 1;
    }
    size_t n = 0;
    for (int y = ya, mo = ma; y < yb || (y == yb && mo <= mb);) {
        lv_tai s;
        if (month_leap(y, mo, &s) && s >= a && s <= b) {
            if (n < cap)
                starts[n] = s;
            n++;
        }
        if (++mo > 12) {
            mo = 1;
            y++;
        }
    }
    return n;
}

int lv_utc_note(lv_tai a, lv_tai b, char *buf, size_t cap)
{
    char w[48];
    buf[0] = '\0';
    int ya, yb, mo, d;
    double fd;
    const int ja = utc_date(a, &ya, &mo, &d, &fd), jb = utc_date(b, &yb, &mo, &d, &fd);
    const int early = (ja == 1 && ya < 1960) || (jb == 1 && yb < 1960);
    const int late = (ja == 1 && ya >= 1960) || (jb == 1 && yb >= 1960);
    if (!early && !late)
        return 0;
    size_t n = 0;
    if (early)
        n += (size_t)snprintf(buf, cap, "UTC began in 1960: earlier times are TAI (ERFA: "
                              "TAI - UTC = 0)");
    if (late && n < cap) {
        /* the first year ERFA calls dubious, and its table's last leap second before it */
        int yd = 1972;
        double dat;
        while (yd < 9999 && eraDat(yd, 1, 1, 0.0, &dat) != 1)
            yd++;
        lv_tai last = 0;
        int found = 0;
        for (int y = yd - 1; y >= 1972 && !found; y--)
            for (int m = 12; m >= 1 && !found; m--)
                found = month_leap(y, m, &last);
        if (found)
            lv_utc_format(last, 0, "Z", w, sizeof w, NULL);
        else
            snprintf(w, sizeof w, "none");
        snprintf(buf + n, cap - n, "%sUTC from %d on is past ERFA %s's leap-second table "
                 "(last: %s): a leap second announced since is not counted and makes these "
                 "times 1 s late", n > 0 ? "; " : "", yd, eraVersion(), w);
    }
    return 1;
}

const char *lv_utc_erfa_version(void)
{
    return eraVersion();
}
