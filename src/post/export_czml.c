/* export_czml.c - mission.czml for Cesium: a document packet with the clock, one track packet
 * per body and phase, event and phase-start markers. Packet and property names: the CZML Guide
 * and Packet reference (AnalyticalGraphicsInc/czml-writer wiki).
 * Written straight to the file as it goes (no document tree, nothing held per sample), laid
 * out byte for byte as cJSON_Print lays a document out (cJSON 1.7.15, print_object,
 * print_array, print_number, print_string_ptr): objects one item per line indented by tabs,
 * "key":<tab>value; arrays on one line, ", " between items; numbers as lv_ex_json_number says.
 * The file is the one the former cJSON writer gave (docs/exports.md, "CZML"). */
#define _POSIX_C_SOURCE 200809L

#include <locale.h>
#include <math.h>
#include <float.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "core/units.h"
#include "io/atomic.h"
#include "io/numparse.h"
#include "post/export_int.h"

#define RAD2DEG (180.0 / LV_PI) /* deg per rad */

/* ------------------------------------------------------- JSON as cJSON -- */

size_t lv_ex_json_number(double d, char decimal_point, char *buf)
{
    int n;
    if (isnan(d) || isinf(d)) {
        n = snprintf(buf, LV_EX_JSON_NUM_CAP, "null");
    } else {
        /* 15 significant digits unless they do not read back to d within cJSON's
         * compare_double (|a - b| <= max(|a|, |b|) DBL_EPSILON), then 17. (An integer comes
         * out as "%d" would write it; -0.0 as "-0", as Debian's cJSON 1.7.15 writes it.) */
        n = snprintf(buf, LV_EX_JSON_NUM_CAP, "%1.15g", d);
        char *end = NULL;
        const double test = lv_numparse_double(buf, &end); /* strtod's value, faster */
        const double m = fabs(test) > fabs(d) ? fabs(test) : fabs(d);
        if (end == buf || !(fabs(test - d) <= m * DBL_EPSILON))
            n = snprintf(buf, LV_EX_JSON_NUM_CAP, "%1.17g", d);
    }
    if (n < 0)
        n = 0;
    for (int i = 0; i < n; i++) /* cJSON writes the locale's decimal point as '.' */
        if (buf[i] == decimal_point)
            buf[i] = '.';
    return (size_t)n;
}

void lv_ex_json_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (const unsigned char *p = (const unsigned char *)(s ? s : ""); *p; p++) {
        switch (*p) {
        case '"': fputs("\\\"", f); break;
        case '\\': fputs("\\\\", f); break;
        case '\b': fputs("\\b", f); break;
        case '\f': fputs("\\f", f); break;
        case '\n': fputs("\\n", f); break;
        case '\r': fputs("\\r", f); break;
        case '\t': fputs("\\t", f); break;
        default:
            if (*p < 32)
                fprintf(f, "\\u%04x", *p);
            else
                fputc(*p, f); /* UTF-8 and everything else as it is */
        }
    }
    fputc('"', f);
}

/* A JSON document being written: the open containers (no document is deeper than 8). */
enum { JW_DEPTH = 8 };
typedef struct jw {
    FILE *f;
    char point;             /* the locale's decimal point (lv_ex_json_number) */
    int depth;              /* open containers */
    char kind[JW_DEPTH];    /* '{' or '[' */
    int items[JW_DEPTH];    /* items written in it so far */
} jw;

/* Before an item: its separator, and in an object its indentation and "key":<tab>. */
static void jw_item(jw *w, const char *key)
{
    if (w->depth == 0)
        return;
    const int d = w->depth - 1;
    if (w->kind[d] == '{') {
        if (w->items[d] > 0)
            fputs(",\n", w->f);
        for (int i = 0; i < w->depth; i++)
            fputc('\t', w->f);
        lv_ex_json_string(w->f, key);
        fputs(":\t", w->f);
    } else if (w->items[d] > 0) {
        fputs(", ", w->f);
    }
    w->items[d]++;
}

static void jw_open(jw *w, const char *key, char kind)
{
    jw_item(w, key);
    fputc(kind, w->f);
    if (kind == '{')
        fputc('\n', w->f);
    if (w->depth < JW_DEPTH) {
        w->kind[w->depth] = kind;
        w->items[w->depth] = 0;
    }
    w->depth++;
}

static void jw_close(jw *w)
{
    const int d = --w->depth;
    if (d >= JW_DEPTH)
        return;
    if (w->kind[d] == '{') {
        if (w->items[d] > 0)
            fputc('\n', w->f);
        for (int i = 0; i < d; i++)
            fputc('\t', w->f);
        fputc('}', w->f);
    } else {
        fputc(']', w->f);
    }
}

static void jw_str(jw *w, const char *key, const char *s)
{
    jw_item(w, key);
    lv_ex_json_string(w->f, s);
}

static void jw_num(jw *w, const char *key, double v)
{
    char buf[LV_EX_JSON_NUM_CAP];
    jw_item(w, key);
    fwrite(buf, 1, lv_ex_json_number(v, w->point, buf), w->f);
}

/* ----------------------------------------------------------------- CZML -- */

static void rgba(jw *w, const char *key, int r, int g, int b, int a)
{
    jw_open(w, key, '{');
    jw_open(w, "rgba", '[');
    jw_num(w, NULL, r);
    jw_num(w, NULL, g);
    jw_num(w, NULL, b);
    jw_num(w, NULL, a);
    jw_close(w);
    jw_close(w);
}

static void interval(jw *w, const char *key, const lv_ex_run *r, double ta, double tb)
{
    char a[48], b[48], iv[100];
    lv_ex_iso(r, ta, "Z", a, sizeof a);
    lv_ex_iso(r, tb, "Z", b, sizeof b);
    snprintf(iv, sizeof iv, "%s/%s", a, b);
    jw_str(w, key, iv);
}

static void point(jw *w, const int rgb[3])
{
    jw_open(w, "point", '{');
    jw_num(w, "pixelSize", 8);
    rgba(w, "color", rgb[0], rgb[1], rgb[2], 255);
    rgba(w, "outlineColor", 0, 0, 0, 255);
    jw_num(w, "outlineWidth", 1);
    jw_close(w);
}

static void label(jw *w, const char *text, const int rgb[3])
{
    jw_open(w, "label", '{');
    jw_str(w, "text", text);
    jw_str(w, "font", "13px sans-serif");
    jw_str(w, "style", "FILL_AND_OUTLINE");
    rgba(w, "fillColor", rgb[0], rgb[1], rgb[2], 255);
    rgba(w, "outlineColor", 0, 0, 0, 255);
    jw_num(w, "outlineWidth", 2);
    jw_str(w, "horizontalOrigin", "LEFT");
    jw_open(w, "pixelOffset", '{');
    jw_open(w, "cartesian2", '[');
    jw_num(w, NULL, 10);
    jw_num(w, NULL, 0);
    jw_close(w);
    jw_close(w);
    jw_close(w);
}

static void document_packet(jw *w, const lv_ex_run *r)
{
    char now[48];
    jw_open(w, NULL, '{');
    jw_str(w, "id", "document");
    jw_str(w, "name", r->mission);
    jw_str(w, "version", "1.0");
    jw_open(w, "clock", '{');
    interval(w, "interval", r, r->t0, r->t1);
    lv_ex_iso(r, r->t0, "Z", now, sizeof now);
    jw_str(w, "currentTime", now);
    /* About a minute of wall time for the whole mission, at least real time. */
    jw_num(w, "multiplier", fmax(1.0, ceil((r->t1 - r->t0) / 60.0)));
    jw_str(w, "range", "LOOP_STOP");
    jw_str(w, "step", "SYSTEM_CLOCK_MULTIPLIER");
    jw_close(w);
    jw_close(w);
}

/* Body b in phase k->phase: samples [t - t_epoch, lon, lat, h], linear between them. */
static void track_packet(jw *w, const lv_ex_run *r, size_t bi, const lv_ex_track *k, int last)
{
    const lv_ex_body *b = &r->bodies[bi];
    const lv_ex_phase *ph = &r->phases[k->phase];
    char buf[512], epoch[48];
    int rgb[3];
    lv_ex_colour(r, k->phase, rgb);
    jw_open(w, NULL, '{');
    snprintf(buf, sizeof buf, "track/%s/%s", b->name, ph->name);
    jw_str(w, "id", buf);
    snprintf(buf, sizeof buf, "%s, phase %s", b->name, ph->name);
    jw_str(w, "name", buf);
    snprintf(buf, sizeof buf, "Body %s in phase %s (%d), t = %.3f .. %.3f s after the "
             "mission epoch.", b->name, ph->name, ph->index, ph->t_start,
             ph->t_end);
    jw_str(w, "description", buf);
    /* The whole mission: a finished track stays drawn (a track available only during its own
     * phase disappears when the clock leaves that phase). */
    interval(w, "availability", r, r->t0, r->t1);

    jw_open(w, "position", '{');
    lv_ex_iso(r, 0.0, "Z", epoch, sizeof epoch);
    jw_str(w, "epoch", epoch);
    jw_str(w, "interpolationAlgorithm", "LAGRANGE");
    jw_num(w, "interpolationDegree", 1);
    jw_str(w, "forwardExtrapolationType", "HOLD");
    jw_str(w, "backwardExtrapolationType", "NONE");
    jw_open(w, "cartographicDegrees", '[');
    for (size_t i = 0; i < k->n; i++) {
        const lv_ex_row *row = &b->rows[k->first + i];
        jw_num(w, NULL, row->t);
        jw_num(w, NULL, row->lon * RAD2DEG);
        jw_num(w, NULL, row->lat * RAD2DEG);
        jw_num(w, NULL, row->h);
    }
    jw_close(w);
    jw_close(w);

    jw_open(w, "path", '{');
    jw_open(w, "material", '{');
    jw_open(w, "solidColor", '{');
    rgba(w, "color", rgb[0], rgb[1], rgb[2], 255);
    jw_close(w);
    jw_close(w);
    jw_num(w, "width", 2);
    jw_num(w, "leadTime", 0);
    jw_num(w, "trailTime", r->t1 - r->t0 + 1.0); /* everything flown */
    jw_num(w, "resolution", 1);
    jw_close(w);
    if (last) { /* the body itself rides on the track of its last phase */
        point(w, rgb);
        label(w, b->name, rgb);
    }
    jw_close(w);
}

/* A fixed marker: id, label, where body b of phase p was at t, visible from t to the end. */
static void marker_packet(jw *w, const lv_ex_run *r, size_t p, size_t j, double t,
                          const char *text)
{
    const lv_ex_phase *ph = &r->phases[p];
    const lv_ex_body *b = &r->bodies[r->phase_body[p]];
    const lv_ex_track *k = lv_ex_track_of(b, p);
    double lat, lon, h;
    lv_ex_locate(b, k, t, &lat, &lon, &h);
    char buf[512];
    int rgb[3];
    lv_ex_colour(r, p, rgb);
    jw_open(w, NULL, '{');
    snprintf(buf, sizeof buf, "event/%s/%zu", ph->name, j);
    jw_str(w, "id", buf);
    snprintf(buf, sizeof buf, "%s (%s)", text, ph->name);
    jw_str(w, "name", buf);
    snprintf(buf, sizeof buf, "%s in phase %s at t = %.6f s, h = %.3f km",
             text, ph->name, t, h / 1000.0);
    jw_str(w, "description", buf);
    interval(w, "availability", r, t, r->t1);
    jw_open(w, "position", '{');
    jw_open(w, "cartographicDegrees", '[');
    jw_num(w, NULL, lon * RAD2DEG);
    jw_num(w, NULL, lat * RAD2DEG);
    jw_num(w, NULL, h);
    jw_close(w);
    jw_close(w);
    point(w, rgb);
    label(w, text, rgb);
    jw_close(w);
}

static lv_status write_czml(const lv_ex_run *r, lv_err *err)
{
    char path[LV_EX_PATH_CAP];
    snprintf(path, sizeof path, "%s/mission.czml", r->outdir);
    lv_atomic out;
    lv_status st = lv_atomic_open(&out, path, err);
    if (st != LV_OK)
        return st;
    const struct lconv *lc = localeconv();
    jw w;
    memset(&w, 0, sizeof w);
    w.f = out.fp;
    w.point = lc != NULL && lc->decimal_point != NULL && lc->decimal_point[0] != '\0'
                  ? lc->decimal_point[0] : '.';
    jw_open(&w, NULL, '[');
    document_packet(&w, r);
    for (size_t bi = 0; bi < r->n_bodies; bi++) {
        const lv_ex_body *b = &r->bodies[bi];
        for (size_t i = 0; i < b->n_tracks; i++)
            track_packet(&w, r, bi, &b->tracks[i], i + 1 == b->n_tracks);
    }
    /* Markers per done phase: 0 its start ("P2 start"), 1..n its events in summary order. */
    for (size_t p = 0; p < r->n_phases; p++) {
        const lv_ex_phase *ph = &r->phases[p];
        if (!ph->done || r->phase_body[p] < 0)
            continue;
        char text[300];
        lv_ex_marker_label(r, p, 0, text, sizeof text);
        marker_packet(&w, r, p, 0, ph->t_start, text);
        for (size_t j = 0; j < ph->n_events; j++) {
            lv_ex_marker_label(r, p, j + 1, text, sizeof text);
            marker_packet(&w, r, p, j + 1, ph->events[j].t, text);
        }
    }
    jw_close(&w);
    fputc('\n', w.f);
    st = lv_atomic_commit(&out, err); /* checks that every write reached the file */
    if (st == LV_OK)
        lv_ex_report(r, "czml", path, NULL);
    return st;
}

const lv_ex_format lv_ex_czml = {
    "czml", "mission.czml", "mission.czml",
    "CZML for CesiumJS: every body's track, phase colours, event markers", write_czml};
