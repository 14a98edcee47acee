/* export_oem.c - <stage>.oem: CCSDS Orbit Ephemeris Message 2.0, KVN (CCSDS 502.0-B-2,
 * sections 5 and 7: header, META_START/META_STOP blocks, data lines "epoch x y z x_dot y_dot
 * z_dot" in km and km/s) for the parts of a body's flight above 100 km, Earth-fixed. Epochs are
 * UTC with its leap seconds: CCSDS ASCII time code A (301.0-B-4, section 3.5) writes an instant
 * inside one as 23:59:60.ffffff. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/status.h"
#include "io/atomic.h"
#include "post/export_int.h"
#include "lvsim/lv_planet.h"
#include "lvsim/lvsim.h"

#define OEM_H_MIN 100e3  /* m: a row is "orbital" at or above this geodetic altitude */
#define EARTH_TOL_M 1e3  /* m: first row farther off the WGS-84 Earth: not an Earth mission */
#define ROW_TOL_M 1.0    /* m: r_eci and lat/lon/h of one row must agree to this */

/* KVN values are one line: control characters become spaces. */
static void put_value(FILE *f, const char *s)
{
    for (; *s; s++)
        fputc((unsigned char)*s < 0x20 ? ' ' : *s, f);
}

typedef struct oem_pt {
    const lv_ex_row *row;
    double r_ecef[3], v_ecef[3]; /* m, m/s */
} oem_pt;

/* ECEF position from the row's geodetic coordinates; velocity relative to the rotating Earth
 * from the ECI state (docs/frames.md F3); the two positions checked against each other. */
static void ecef_state(const lv_planet *earth, const lv_ex_row *row, oem_pt *pt,
                       double *mismatch)
{
    double r_rot[3];
    lv_frames_geodetic_to_ecef(earth, row->lat, row->lon, row->h, pt->r_ecef);
    lv_frames_eci_to_ecef(earth, row->t, row->r_eci, row->v_eci, r_rot, pt->v_ecef);
    const double dx = r_rot[0] - pt->r_ecef[0], dy = r_rot[1] - pt->r_ecef[1],
                 dz = r_rot[2] - pt->r_ecef[2];
    *mismatch = sqrt(dx * dx + dy * dy + dz * dz);
}

static void put_segment(FILE *f, const lv_ex_run *r, const lv_ex_body *b, const oem_pt *pts,
                        size_t n, size_t seg, size_t n_seg)
{
    char t_a[48], t_b[48];
    lv_ex_iso(r, pts[0].row->t, "", t_a, sizeof t_a);
    lv_ex_iso(r, pts[n - 1].row->t, "", t_b, sizeof t_b);
    fprintf(f, "\nMETA_START\nCOMMENT portion %zu of %zu above 100 km, mission time %.6f .. "
               "%.6f s\n", seg, n_seg, pts[0].row->t, pts[n - 1].row->t);
    fputs("OBJECT_NAME = ", f);
    put_value(f, b->name);
    fputs("\nOBJECT_ID = ", f);
    put_value(f, r->mission);
    fputc('/', f);
    put_value(f, b->name);
    fprintf(f, "\nCENTER_NAME = EARTH\nREF_FRAME = ITRF2000\nTIME_SYSTEM = UTC\n"
               "START_TIME = %s\nSTOP_TIME = %s\nINTERPOLATION = HERMITE\n"
               "INTERPOLATION_DEGREE = 3\nMETA_STOP\n\n", t_a, t_b);
    for (size_t i = 0; i < n; i++) {
        lv_ex_iso(r, pts[i].row->t, "", t_a, sizeof t_a);
        fprintf(f, "%s %.6f %.6f %.6f %.9f %.9f %.9f\n", t_a, pts[i].r_ecef[0] / 1e3,
                pts[i].r_ecef[1] / 1e3, pts[i].r_ecef[2] / 1e3, pts[i].v_ecef[0] / 1e3,
                pts[i].v_ecef[1] / 1e3, pts[i].v_ecef[2] / 1e3);
    }
}

/* Body b: the rows (all phases, one per written microsecond) and their segments above
 * 100 km of at least two rows. Writes OUTDIR/<body>.oem when there is one. */
static lv_status write_body(const lv_ex_run *r, const lv_ex_body *b, oem_pt *pts, lv_err *err)
{
    const lv_planet earth = lv_planet_earth();
    size_t n = 0;
    long long last = 0;
    for (size_t i = 0; i < b->n_rows; i++) {
        const lv_ex_row *row = &b->rows[i];
        const long long tick = lv_ex_ticks(r, row->t);
        if (n > 0 && tick <= last) /* a phase boundary: the child's first row is the same */
            continue;
        double off;
        ecef_state(&earth, row, &pts[n], &off);
        if (n == 0 && !(off <= EARTH_TOL_M)) { /* another planet: no OEM */
            lv_ex_report(r, "oem", NULL, "%s: not written: its positions do not lie on the "
                         "WGS-84 Earth (OEM files are Earth-fixed)", b->name);
            return LV_OK;
        }
        if (!(off <= ROW_TOL_M))
            return lv_fail(err, LV_ERR_INPUT, "%s:%zu: r_eci and lat/lon/h disagree by %.3g m",
                           b->path, row->line, off);
        pts[n++].row = row;
        last = tick;
    }
    size_t n_seg = 0;
    for (size_t i = 0; i < n;) { /* count the segments first: "portion k of n" */
        size_t j = i;
        while (j < n && pts[j].row->h >= OEM_H_MIN)
            j++;
        n_seg += j - i >= 2;
        i = j > i ? j : i + 1;
    }
    if (n_seg == 0) {
        double h_max = -INFINITY;
        for (size_t i = 0; i < n; i++)
            h_max = fmax(h_max, pts[i].row->h);
        lv_ex_report(r, "oem", NULL, "%s: not written: never above 100 km (highest %.1f km)",
                     b->name, fabs(h_max) < 50.0 ? 0.0 : h_max / 1e3); /* no "-0.0" */
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
    for (size_t i = 0; i < n;) {
        size_t j = i;
        while (j < n && pts[j].row->h >= OEM_H_MIN)
            j++;
        if (j - i >= 2)
            put_segment(f, r, b, pts + i, j - i, ++seg, n_seg);
        i = j > i ? j : i + 1;
    }
    st = lv_atomic_commit(&out, err);
    if (st == LV_OK)
        lv_ex_report(r, "oem", path, "%zu portion%s above 100 km", n_seg, n_seg == 1 ? "" : "s");
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
        oem_pt *pts = malloc(b->n_rows * sizeof *pts);
        if (pts == NULL)
            return lv_fail(err, LV_ERR_NOMEM, "out of memory");
        st = write_body(r, b, pts, err);
        free(pts);
    }
    return st;
}

const lv_ex_format lv_ex_oem = {
    "oem", "<stage>.oem", "*.oem",
    "CCSDS OEM 2.0 (KVN): each body's orbital portions above 100 km, Earth only", write_oem};
