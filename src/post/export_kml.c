/* export_kml.c - mission.kml (OGC KML 2.2 with the Google gx: extension, for Google Earth): one
 * Folder per body, a gx:Track per phase (when/gx:coord, altitudeMode absolute), a Style per
 * phase colour, Placemarks for phase starts and events, the instantaneous impact point's trace
 * per body (LineStrings on the ground). Text from the mission is escaped. Times
 * are xsd:dateTime, which has no second 60: an instant inside a leap second is written as
 * 23:59:59.999999 (docs/exports.md, "Times"). */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/status.h"
#include "core/units.h"
#include "io/atomic.h"
#include "post/export_int.h"

#define RAD2DEG (180.0 / LV_PI) /* deg per rad */

/* XML character data / attribute value: the five predefined entities; control characters
 * that XML 1.0 forbids become a space. */
static void put_text(FILE *f, const char *s)
{
    for (; *s; s++) {
        const unsigned char c = (unsigned char)*s;
        switch (c) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        case '\'': fputs("&apos;", f); break;
        default: fputc(c < 0x20 && c != '\t' && c != '\n' && c != '\r' ? ' ' : c, f);
        }
    }
}

static void put_style(FILE *f, const lv_ex_run *r, size_t p)
{
    int rgb[3];
    lv_ex_colour(r, p, rgb);
    char colour[16]; /* KML colours are aabbggrr */
    snprintf(colour, sizeof colour, "ff%02x%02x%02x", rgb[2], rgb[1], rgb[0]);
    fprintf(f,
            "  <Style id=\"phase-%d\">\n"
            "    <IconStyle><color>%s</color><scale>0.8</scale><Icon><href>"
            "http://maps.google.com/mapfiles/kml/shapes/placemark_circle.png</href></Icon>"
            "</IconStyle>\n"
            "    <LabelStyle><scale>0.8</scale></LabelStyle>\n"
            "    <LineStyle><color>%s</color><width>2</width></LineStyle>\n"
            "  </Style>\n",
            r->phases[p].index, colour, colour);
}

static void put_track(FILE *f, const lv_ex_run *r, const lv_ex_body *b, const lv_ex_track *k,
                      size_t *n_no60)
{
    const lv_ex_phase *ph = &r->phases[k->phase];
    char when[48], last[48];
    fputs("    <Placemark>\n      <name>", f);
    put_text(f, b->name);
    fputs(": ", f);
    put_text(f, ph->name);
    fprintf(f, "</name>\n      <styleUrl>#phase-%d</styleUrl>\n      <gx:Track>\n"
               "        <altitudeMode>absolute</altitudeMode>\n", ph->index);
    /* The schema wants every <when> before the first <gx:coord>. Rows whose written time is
     * the same (the same microsecond, or the same leap second: 23:59:59.999999) are written
     * once, the first of them. */
    for (int pass = 0; pass < 2; pass++) {
        lv_ex_clock clock = {0};
        last[0] = '\0';
        for (size_t i = 0; i < k->n; i++) {
            const lv_ex_row *row = &b->rows[k->first + i];
            const int leap = lv_ex_clock_iso(r, &clock, row->t, 1, "Z", when, sizeof when);
            if (strcmp(when, last) == 0)
                continue;
            memcpy(last, when, sizeof last);
            if (pass == 0) {
                *n_no60 += (size_t)leap;
                fprintf(f, "        <when>%s</when>\n", when);
            } else {
                fprintf(f, "        <gx:coord>%.10f %.10f %.4f</gx:coord>\n", row->lon * RAD2DEG,
                        row->lat * RAD2DEG, row->h);
            }
        }
    }
    fputs("      </gx:Track>\n    </Placemark>\n", f);
}

static void put_marker(FILE *f, const lv_ex_run *r, const lv_ex_body *b, const lv_ex_track *k,
                       double t, const char *text, size_t *n_no60)
{
    const lv_ex_phase *ph = &r->phases[k->phase];
    double lat, lon, h;
    char t_a[48], t_b[48];
    lv_ex_locate(b, k, t, &lat, &lon, &h);
    *n_no60 += (size_t)lv_ex_iso_no60(r, t, "Z", t_a, sizeof t_a);
    *n_no60 += (size_t)lv_ex_iso_no60(r, r->t1, "Z", t_b, sizeof t_b);
    fputs("    <Placemark>\n      <name>", f);
    put_text(f, text);
    fputs("</name>\n      <description>", f);
    put_text(f, ph->name);
    fprintf(f, ": t = %.6f s, h = %.3f km</description>\n", t, h / 1000.0);
    fprintf(f, "      <TimeSpan><begin>%s</begin><end>%s</end></TimeSpan>\n", t_a, t_b);
    fprintf(f, "      <styleUrl>#phase-%d</styleUrl>\n"
               "      <Point><altitudeMode>absolute</altitudeMode>"
               "<coordinates>%.10f,%.10f,%.4f</coordinates></Point>\n    </Placemark>\n",
            ph->index, lon * RAD2DEG, lat * RAD2DEG, h);
}

/* The finite runs of at least two rows of a body's instantaneous impact point (a NAN row, no
 * impact, ends a run): how many. */
static size_t iip_runs(const lv_ex_body *b)
{
    size_t n = 0, len = 0;
    for (size_t i = 0; b->has_iip && i <= b->n_rows; i++) {
        if (i < b->n_rows && isfinite(b->rows[i].iip_lat) && isfinite(b->rows[i].iip_lon)) {
            len++;
            continue;
        }
        n += len >= 2;
        len = 0;
    }
    return n;
}

/* The body's IIP trace: one Placemark, a LineString on the ground per finite run of rows
 * (docs/exports.md, "KML"). */
static void put_iip(FILE *f, const lv_ex_body *b)
{
    fputs("    <Placemark>\n      <name>", f);
    put_text(f, b->name);
    fputs(": IIP trace</name>\n      <description>instantaneous impact point (drag-free, "
          "thrust off) over the body's rows; gaps: no impact</description>\n"
          "      <styleUrl>#iip</styleUrl>\n      <MultiGeometry>\n", f);
    size_t start = 0, len = 0;
    for (size_t i = 0; i <= b->n_rows; i++) {
        if (i < b->n_rows && isfinite(b->rows[i].iip_lat) && isfinite(b->rows[i].iip_lon)) {
            if (len++ == 0)
                start = i;
            continue;
        }
        if (len >= 2) {
            fputs("        <LineString><tessellate>1</tessellate><altitudeMode>clampToGround"
                  "</altitudeMode><coordinates>\n", f);
            for (size_t j = start; j < start + len; j++)
                fprintf(f, "          %.10f,%.10f,0\n", b->rows[j].iip_lon * RAD2DEG,
                        b->rows[j].iip_lat * RAD2DEG);
            fputs("        </coordinates></LineString>\n", f);
        }
        len = 0;
    }
    fputs("      </MultiGeometry>\n    </Placemark>\n", f);
}

/* *n_no60: how many written instants fell inside a leap second (written 23:59:59.999999). */
static lv_status write_file(const lv_ex_run *r, const char *path, size_t *n_no60, lv_err *err)
{
    char epoch[48];
    *n_no60 = 0;
    lv_atomic out;
    lv_status st = lv_atomic_open(&out, path, err);
    if (st != LV_OK)
        return st;
    FILE *f = out.fp;
    lv_ex_iso(r, 0.0, "Z", epoch, sizeof epoch);
    fputs("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
          "<kml xmlns=\"http://www.opengis.net/kml/2.2\" "
          "xmlns:gx=\"http://www.google.com/kml/ext/2.2\">\n<Document>\n  <name>", f);
    put_text(f, r->mission);
    fprintf(f, "</name>\n  <open>1</open>\n  <description>lvsim trajectories, mission epoch %s "
               "(UTC); one folder per body, one track per phase", epoch);
    /* the leap seconds of the span, whose instants xsd:dateTime cannot hold, and the table */
    lv_tai leaps[4];
    const size_t n_leap = lv_utc_leaps(lv_ex_ticks(r, r->t0), lv_ex_ticks(r, r->t1), leaps, 4);
    for (size_t i = 0; i < n_leap && i < 4; i++) {
        char w[48];
        (void)lv_utc_format(leaps[i], 0, "Z", w, sizeof w, NULL);
        fprintf(f, "; leap second %s: its instants are written as 23:59:59.999999Z", w);
    }
    if (r->time_note[0] != '\0') {
        fputs("; ", f);
        put_text(f, r->time_note);
    }
    fputs("</description>\n", f);
    for (size_t p = 0; p < r->n_phases; p++)
        if (r->phases[p].done)
            put_style(f, r, p);
    size_t n_iip = 0;
    for (size_t bi = 0; bi < r->n_bodies; bi++)
        n_iip += iip_runs(&r->bodies[bi]);
    if (n_iip > 0) /* the IIP traces: thin, red */
        fputs("  <Style id=\"iip\">\n"
              "    <LineStyle><color>ff2020e0</color><width>1.5</width></LineStyle>\n"
              "  </Style>\n", f);
    for (size_t bi = 0; bi < r->n_bodies; bi++) {
        const lv_ex_body *b = &r->bodies[bi];
        fputs("  <Folder>\n    <name>", f);
        put_text(f, b->name);
        fputs("</name>\n", f);
        for (size_t i = 0; i < b->n_tracks; i++)
            put_track(f, r, b, &b->tracks[i], n_no60);
        if (iip_runs(b) > 0)
            put_iip(f, b);
        /* The markers of this body's phases: start, then the events (as in the CZML). */
        for (size_t i = 0; i < b->n_tracks; i++) {
            const lv_ex_track *k = &b->tracks[i];
            const lv_ex_phase *ph = &r->phases[k->phase];
            char text[300];
            lv_ex_marker_label(r, k->phase, 0, text, sizeof text);
            put_marker(f, r, b, k, ph->t_start, text, n_no60);
            for (size_t j = 0; j < ph->n_events; j++) {
                lv_ex_marker_label(r, k->phase, j + 1, text, sizeof text);
                put_marker(f, r, b, k, ph->events[j].t, text, n_no60);
            }
        }
        fputs("  </Folder>\n", f);
    }
    fputs("</Document>\n</kml>\n", f);
    return lv_atomic_commit(&out, err);
}

static lv_status write_kml(const lv_ex_run *r, lv_err *err)
{
    char path[LV_EX_PATH_CAP];
    size_t n_no60 = 0;
    snprintf(path, sizeof path, "%s/mission.kml", r->outdir);
    lv_status st = write_file(r, path, &n_no60, err);
    if (st == LV_OK && n_no60 > 0)
        lv_ex_report(r, "kml", path, "%zu time%s inside a leap second written as "
                     "23:59:59.999999 (KML's xsd:dateTime has no second 60)", n_no60,
                     n_no60 == 1 ? "" : "s");
    else if (st == LV_OK)
        lv_ex_report(r, "kml", path, NULL);
    return st;
}

const lv_ex_format lv_ex_kml = {
    "kml", "mission.kml", "mission.kml",
    "KML 2.2 for Google Earth: a folder per body, a track per phase, event markers, the IIP "
    "trace", write_kml};
