/* export_oem.c - <stage>.oem: CCSDS Orbit Ephemeris Message 2.0, KVN (CCSDS 502.0-B-2,
 * sections 5 and 7: header, META_START/META_STOP blocks, data lines "epoch x y z x_dot y_dot
 * z_dot" in km and km/s) for the orbital arcs of a body's flight (above 100 km, periapsis above
 * the surface), Earth-fixed. Epochs are
 * UTC with its leap seconds: CCSDS ASCII time code A (301.0-B-4, section 3.5) writes an instant
 * inside one as 23:59:60.ffffff. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/status.h"
#include "io/atomic.h"
#include "post/export_int.h"
#include "lvsim/lv_planet.h"
#include "lvsim/lvsim.h"

#define OEM_H_MIN 100e3  /* m: an orbital row is at or above this geodetic altitude */
#define EARTH_TOL_M 1e3  /* m: first row farther off the WGS-84 Earth: not an Earth mission */
#define ROW_TOL_M 1.0    /* m: r_eci and lat/lon/h of one row must agree to this */

/* KVN values are one line: control characters become spaces. */
/* A name in a KVN value: the ODM is ASCII text (CCSDS 502.0-B-2, 7.2: "all lines ... shall
 * consist of ASCII characters"): a control character is written as a blank, each non-ASCII
 * character (a UTF-8 sequence, or a stray byte) as one '_'. */
static void put_value(FILE *f, const char *s)
{
    int in_seq = 0; /* inside a non-ASCII sequence already written as '_' */
    for (; *s; s++) {
        const unsigned char ch = (unsigned char)*s;
        if (ch >= 0x80 && ch < 0xc0 && in_seq)
            continue; /* a continuation byte */
        in_seq = ch >= 0x80;
        fputc(ch < 0x20 || ch == 0x7f ? ' ' : ch >= 0x80 ? '_' : (int)ch, f);
    }
}

/* ECEF state of one row: position from its geodetic coordinates, velocity relative to the
 * rotating Earth from its ECI state (docs/frames.md F3); *mismatch: how far the row's ECI
 * position, rotated, lies from that position. */
static void ecef_state(const lv_planet *earth, const lv_ex_row *row, double r_ecef[3],
                       double v_ecef[3], double *mismatch)
{
    double r_rot[3];
    lv_frames_geodetic_to_ecef(earth, row->lat, row->lon, row->h, r_ecef);
    lv_frames_eci_to_ecef(earth, row->t, row->r_eci, row->v_eci, r_rot, v_ecef);
    const double dx = r_rot[0] - r_ecef[0], dy = r_rot[1] - r_ecef[1], dz = r_rot[2] - r_ecef[2];
    *mismatch = sqrt(dx * dx + dy * dy + dz * dz);
}

/* The rows an OEM is made of: body b's rows, all phases, one per written microsecond (at a
 * phase boundary the child's first row repeats the parent's last: skipped). next_row gives
 * the first such row after such a row i (i = SIZE_MAX: the first, row 0), b->n_rows at the
 * end. Nothing is stored: the file is written as the rows are read. */
static size_t next_row(const lv_ex_run *r, const lv_ex_body *b, size_t i)
{
    if (i == SIZE_MAX)
        return 0;
    const lv_tai last = lv_ex_ticks(r, b->rows[i].t);
    for (i++; i < b->n_rows; i++)
        if (lv_ex_ticks(r, b->rows[i].t) > last)
            return i;
    return b->n_rows;
}

/* The osculating periapsis radius [m] of a row's inertial state about a body of
 * gravitational parameter gm [m^3/s^2], for any conic: r_p = h^2 / (gm (1 + e)), with the
 * specific angular momentum h = |r x v| and e = sqrt(1 + 2 E h^2 / gm^2) from the vis-viva
 * energy E = v^2/2 - gm/r (Vallado, Fundamentals of Astrodynamics, 4th ed., eqs. 2-79, 2-80). */
static double periapsis_radius(const lv_ex_row *row, double gm)
{
    const double *r = row->r_eci, *v = row->v_eci;
    const double hx = r[1] * v[2] - r[2] * v[1], hy = r[2] * v[0] - r[0] * v[2],
                 hz = r[0] * v[1] - r[1] * v[0];
    const double h2 = hx * hx + hy * hy + hz * hz;
    const double rn = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    const double e_sp = 0.5 * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) - gm / rn;
    const double e2 = 1.0 + 2.0 * e_sp * h2 / (gm * gm);
    const double e = e2 > 0.0 ? sqrt(e2) : 0.0;
    return h2 / (gm * (1.0 + e));
}

/* A row of an orbital arc: at or above 100 km, on a conic whose periapsis lies above the
 * Earth's surface (outside the WGS-84 equatorial radius, which no point of the surface
 * exceeds): a suborbital arc above 100 km, which comes down again, is none. */
static int orbital(const lv_planet *earth, const lv_ex_row *row)
{
    return row->h >= OEM_H_MIN && periapsis_radius(row, earth->gm) > earth->a;
}

/* A portion: rows from `first` while orbital; its last row in *end_row, the row after it (the
 * next portion's search start) returned, and its number of rows in *n. */
static size_t portion(const lv_ex_run *r, const lv_ex_body *b, size_t first, size_t *end_row,
                      size_t *n)
{
    const lv_planet earth = lv_planet_earth();
    size_t i = first, k = 0;
    *end_row = first;
    while (i < b->n_rows && orbital(&earth, &b->rows[i])) {
        *end_row = i;
        k++;
        i = next_row(r, b, i);
    }
    *n = k;
    return i;
}

static void put_segment(FILE *f, const lv_ex_run *r, const lv_ex_body *b, size_t first,
                        size_t end_row, size_t seg, size_t n_seg)
{
    const lv_planet earth = lv_planet_earth();
    char t_a[48], t_b[48];
    lv_ex_iso(r, b->rows[first].t, "", t_a, sizeof t_a);
    lv_ex_iso(r, b->rows[end_row].t, "", t_b, sizeof t_b);
    fprintf(f, "\nMETA_START\nCOMMENT orbital portion %zu of %zu (above 100 km, periapsis above "
               "the Earth's surface), mission time %.6f .. %.6f s\n", seg, n_seg,
            b->rows[first].t, b->rows[end_row].t);
    fputs("OBJECT_NAME = ", f);
    put_value(f, b->name);
    fputs("\nOBJECT_ID = ", f);
    put_value(f, r->mission);
    fputc('/', f);
    put_value(f, b->name);
    fprintf(f, "\nCENTER_NAME = EARTH\nREF_FRAME = ITRF2000\nTIME_SYSTEM = UTC\n"
               "START_TIME = %s\nSTOP_TIME = %s\nINTERPOLATION = HERMITE\n"
               "INTERPOLATION_DEGREE = 3\nMETA_STOP\n\n", t_a, t_b);
    lv_ex_clock clock = {0};
    for (size_t i = first; i <= end_row; i = next_row(r, b, i)) {
        double r_ecef[3], v_ecef[3], off;
        ecef_state(&earth, &b->rows[i], r_ecef, v_ecef, &off);
        lv_ex_clock_iso(r, &clock, b->rows[i].t, 0, "", t_a, sizeof t_a);
        fprintf(f, "%s %.6f %.6f %.6f %.9f %.9f %.9f\n", t_a, r_ecef[0] / 1e3, r_ecef[1] / 1e3,
                r_ecef[2] / 1e3, v_ecef[0] / 1e3, v_ecef[1] / 1e3, v_ecef[2] / 1e3);
    }
}

/* A body without an OEM now: the <body>.oem an earlier export of the same results wrote
 * (before this rule, or of data since rerun) would contradict this one; it is removed when
 * its first lines prove it lvsim's (as this writer begins every file), kept otherwise. */
static void drop_stale(const lv_ex_run *r, const lv_ex_body *b)
{
    char path[4400], head[128];
    snprintf(path, sizeof path, "%s/%s.oem", r->outdir, b->name);
    FILE *f = fopen(path, "r");
    if (f == NULL)
        return;
    const size_t n = fread(head, 1, sizeof head - 1, f);
    fclose(f);
    head[n] = '\0';
    static const char mine[] = "CCSDS_OEM_VERS = 2.0\nCOMMENT lvsim ";
    if (strncmp(head, mine, sizeof mine - 1) == 0 && remove(path) == 0)
        lv_ex_report(r, "oem", NULL, "%s: removed its earlier %s.oem", b->name, b->name);
}

/* Body b: its rows (next_row) checked, then its orbital portions of at least two rows
 * counted ("portion k of n"); OUTDIR/<body>.oem written when there is one, each row's state
 * computed again as it is written. */
static lv_status write_body(const lv_ex_run *r, const lv_ex_body *b, lv_err *err)
{
    const lv_planet earth = lv_planet_earth();
    double h_max = -INFINITY, rp_max = -INFINITY;
    for (size_t i = next_row(r, b, SIZE_MAX); i < b->n_rows;
         i = next_row(r, b, i)) {
        const lv_ex_row *row = &b->rows[i];
        double r_ecef[3], v_ecef[3], off;
        ecef_state(&earth, row, r_ecef, v_ecef, &off);
        if (i == 0 && !(off <= EARTH_TOL_M)) { /* another planet: no OEM */
            lv_ex_report(r, "oem", NULL, "%s: not written: its positions do not lie on the "
                         "WGS-84 Earth (OEM files are Earth-fixed)", b->name);
            return LV_OK;
        }
        if (!(off <= ROW_TOL_M))
            return lv_fail(err, LV_ERR_INPUT, "%s:%zu: r_eci and lat/lon/h disagree by %.3g m",
                           b->path, row->line, off);
        h_max = fmax(h_max, row->h);
        rp_max = fmax(rp_max, periapsis_radius(row, earth.gm));
    }
    size_t n_seg = 0;
    for (size_t i = next_row(r, b, SIZE_MAX); i < b->n_rows;) {
        size_t end_row, n;
        const size_t j = portion(r, b, i, &end_row, &n);
        n_seg += n >= 2;
        i = n > 0 ? j : next_row(r, b, i);
    }
    if (n_seg == 0) {
        drop_stale(r, b);
        if (!(h_max >= OEM_H_MIN))
            lv_ex_report(r, "oem", NULL, "%s: not written: never above 100 km (highest %.1f "
                         "km)", b->name, fabs(h_max) < 50.0 ? 0.0 : h_max / 1e3); /* no -0.0 */
        else
            lv_ex_report(r, "oem", NULL, "%s: not written: no orbital arc (suborbital: its "
                         "highest periapsis %.1f km below the equatorial surface; highest "
                         "altitude %.1f km)", b->name, (earth.a - rp_max) / 1e3, h_max / 1e3);
        return LV_OK;
    }

    char path[4400], created[32];
    snprintf(path, sizeof path, "%s/%s.oem", r->outdir, b->name);
    lv_atomic out;
    lv_status st = lv_atomic_open(&out, path, err);
    if (st != LV_OK)
        return st;
    FILE *f = out.fp;
    const time_t now = time(NULL);
    struct tm tm;
    gmtime_r(&now, &tm);
    strftime(created, sizeof created, "%Y-%m-%dT%H:%M:%S", &tm);
    fprintf(f, "CCSDS_OEM_VERS = 2.0\n"
               "COMMENT lvsim %s trajectory export, mission ", LVSIM_VERSION);
    put_value(f, r->mission);
    fprintf(f, "\nCOMMENT Earth-fixed WGS-84 positions and velocities relative to the rotating "
               "Earth; no polar motion\n");
    /* the leap seconds inside the file's span (epochs count them), the table's limits */
    const lv_tai a = lv_ex_ticks(r, b->rows[0].t), z = lv_ex_ticks(r, b->rows[b->n_rows - 1].t);
    lv_tai leaps[4];
    const size_t n_leap = lv_utc_leaps(a, z, leaps, 4);
    for (size_t i = 0; i < n_leap && i < 4; i++) {
        char w[48];
        (void)lv_utc_format(leaps[i], 0, "", w, sizeof w, NULL);
        fprintf(f, "COMMENT leap second %s inside the span: TAI - UTC %.0f s before, %.0f s "
                   "after\n", w, lv_utc_tai_minus_utc(leaps[i] - 1000000),
                lv_utc_tai_minus_utc(leaps[i] + 1000000));
    }
    if (r->time_note[0] != '\0') {
        fputs("COMMENT ", f);
        put_value(f, r->time_note);
        fputc('\n', f);
    }
    fprintf(f, "CREATION_DATE = %s\nORIGINATOR = LVSIM\n", created);
    size_t seg = 0;
    for (size_t i = next_row(r, b, SIZE_MAX); i < b->n_rows;) {
        size_t end_row, n;
        const size_t j = portion(r, b, i, &end_row, &n);
        if (n >= 2)
            put_segment(f, r, b, i, end_row, ++seg, n_seg);
        i = n > 0 ? j : next_row(r, b, i);
    }
    st = lv_atomic_commit(&out, err); /* checks that every write reached the file */
    if (st == LV_OK)
        lv_ex_report(r, "oem", path, "%zu orbital portion%s", n_seg, n_seg == 1 ? "" : "s");
    return st;
}

static lv_status write_oem(const lv_ex_run *r, lv_err *err)
{
    if (r->flat) {
        lv_ex_report(r, "oem", NULL, "not written: a flat-world mission has no orbit to "
                     "describe (OEM files are for Earth orbits)");
        return LV_OK;
    }
    if (r->planet != NULL && strcmp(r->planet, "earth") != 0) {
        lv_ex_report(r, "oem", NULL, "not written: the mission flies around %s; OEM files "
                     "are written for Earth orbits only", r->planet);
        return LV_OK;
    }
    lv_status st = LV_OK;
    for (size_t i = 0; i < r->n_bodies && st == LV_OK; i++) {
        const lv_ex_body *b = &r->bodies[i];
        if (!b->has_eci)
            return lv_fail(err, LV_ERR_INPUT, "%s: no r_eci_x .. v_eci_z columns for the OEM "
                           "export of a planet-world mission", b->path);
        st = write_body(r, b, err);
    }
    return st;
}

const lv_ex_format lv_ex_oem = {
    "oem", "<stage>.oem", "*.oem",
    "CCSDS OEM 2.0 (KVN): each body's orbital arcs (above 100 km, periapsis above the surface), Earth only", write_oem};
