/* export_czml.c - mission.czml for Cesium: a document packet with the clock, one track packet
 * per body and phase, event and phase-start markers. Built with cJSON only. Packet and property
 * names: the CZML Guide and Packet reference (AnalyticalGraphicsInc/czml-writer wiki). */
#define _POSIX_C_SOURCE 200809L

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "core/units.h"
#include "io/atomic.h"
#include "post/export_int.h"

#define RAD2DEG (180.0 / LV_PI) /* deg per rad */

static cJSON *rgba(int r, int g, int b, int a)
{
    cJSON *o = cJSON_CreateObject();
    const double v[4] = {r, g, b, a};
    cJSON_AddItemToObject(o, "rgba", cJSON_CreateDoubleArray(v, 4));
    return o;
}

static void add_interval(cJSON *o, const char *key, const lv_ex_run *r, double ta, double tb)
{
    char a[48], b[48], iv[100];
    lv_ex_iso(r, ta, "Z", a, sizeof a);
    lv_ex_iso(r, tb, "Z", b, sizeof b);
    snprintf(iv, sizeof iv, "%s/%s", a, b);
    cJSON_AddStringToObject(o, key, iv);
}

static cJSON *point(const int rgb[3])
{
    cJSON *p = cJSON_CreateObject();
    cJSON_AddNumberToObject(p, "pixelSize", 8);
    cJSON_AddItemToObject(p, "color", rgba(rgb[0], rgb[1], rgb[2], 255));
    cJSON_AddItemToObject(p, "outlineColor", rgba(0, 0, 0, 255));
    cJSON_AddNumberToObject(p, "outlineWidth", 1);
    return p;
}

static cJSON *label(const char *text, const int rgb[3])
{
    cJSON *l = cJSON_CreateObject();
    cJSON_AddStringToObject(l, "text", text);
    cJSON_AddStringToObject(l, "font", "13px sans-serif");
    cJSON_AddStringToObject(l, "style", "FILL_AND_OUTLINE");
    cJSON_AddItemToObject(l, "fillColor", rgba(rgb[0], rgb[1], rgb[2], 255));
    cJSON_AddItemToObject(l, "outlineColor", rgba(0, 0, 0, 255));
    cJSON_AddNumberToObject(l, "outlineWidth", 2);
    cJSON_AddStringToObject(l, "horizontalOrigin", "LEFT");
    cJSON *off = cJSON_AddObjectToObject(l, "pixelOffset");
    const double px[2] = {10, 0};
    cJSON_AddItemToObject(off, "cartesian2", cJSON_CreateDoubleArray(px, 2));
    return l;
}

static cJSON *document_packet(const lv_ex_run *r)
{
    char now[48];
    cJSON *d = cJSON_CreateObject();
    cJSON_AddStringToObject(d, "id", "document");
    cJSON_AddStringToObject(d, "name", r->mission);
    cJSON_AddStringToObject(d, "version", "1.0");
    cJSON *clock = cJSON_AddObjectToObject(d, "clock");
    add_interval(clock, "interval", r, r->t0, r->t1);
    lv_ex_iso(r, r->t0, "Z", now, sizeof now);
    cJSON_AddStringToObject(clock, "currentTime", now);
    /* About a minute of wall time for the whole mission, at least real time. */
    cJSON_AddNumberToObject(clock, "multiplier", fmax(1.0, ceil((r->t1 - r->t0) / 60.0)));
    cJSON_AddStringToObject(clock, "range", "LOOP_STOP");
    cJSON_AddStringToObject(clock, "step", "SYSTEM_CLOCK_MULTIPLIER");
    return d;
}

/* Body b in phase k->phase: samples [t - t_epoch, lon, lat, h], linear between them. */
static cJSON *track_packet(const lv_ex_run *r, size_t bi, const lv_ex_track *k, int last)
{
    const lv_ex_body *b = &r->bodies[bi];
    const lv_ex_phase *ph = &r->phases[k->phase];
    char buf[512], epoch[48];
    int rgb[3];
    lv_ex_colour(r, k->phase, rgb);
    cJSON *p = cJSON_CreateObject();
    snprintf(buf, sizeof buf, "track/%s/%s", b->name, ph->name);
    cJSON_AddStringToObject(p, "id", buf);
    snprintf(buf, sizeof buf, "%s, phase %s", b->name, ph->name);
    cJSON_AddStringToObject(p, "name", buf);
    snprintf(buf, sizeof buf, "Body %s in phase %s (%d), t = %.3f .. %.3f s after the "
             "mission epoch.", b->name, ph->name, ph->index, ph->t_start,
             ph->t_end);
    cJSON_AddStringToObject(p, "description", buf);
    /* The whole mission: a finished track stays drawn (a track available only during its own
     * phase disappears when the clock leaves that phase). */
    add_interval(p, "availability", r, r->t0, r->t1);

    cJSON *pos = cJSON_AddObjectToObject(p, "position");
    lv_ex_iso(r, 0.0, "Z", epoch, sizeof epoch);
    cJSON_AddStringToObject(pos, "epoch", epoch);
    cJSON_AddStringToObject(pos, "interpolationAlgorithm", "LAGRANGE");
    cJSON_AddNumberToObject(pos, "interpolationDegree", 1);
    cJSON_AddStringToObject(pos, "forwardExtrapolationType", "HOLD");
    cJSON_AddStringToObject(pos, "backwardExtrapolationType", "NONE");
    cJSON *s = cJSON_AddArrayToObject(pos, "cartographicDegrees");
    for (size_t i = 0; i < k->n; i++) {
        const lv_ex_row *row = &b->rows[k->first + i];
        cJSON_AddItemToArray(s, cJSON_CreateNumber(row->t));
        cJSON_AddItemToArray(s, cJSON_CreateNumber(row->lon * RAD2DEG));
        cJSON_AddItemToArray(s, cJSON_CreateNumber(row->lat * RAD2DEG));
        cJSON_AddItemToArray(s, cJSON_CreateNumber(row->h));
    }

    cJSON *path = cJSON_AddObjectToObject(p, "path");
    cJSON *mat = cJSON_AddObjectToObject(path, "material");
    cJSON *solid = cJSON_AddObjectToObject(mat, "solidColor");
    cJSON_AddItemToObject(solid, "color", rgba(rgb[0], rgb[1], rgb[2], 255));
    cJSON_AddNumberToObject(path, "width", 2);
    cJSON_AddNumberToObject(path, "leadTime", 0);
    cJSON_AddNumberToObject(path, "trailTime", r->t1 - r->t0 + 1.0); /* everything flown */
    cJSON_AddNumberToObject(path, "resolution", 1);
    if (last) { /* the body itself rides on the track of its last phase */
        cJSON_AddItemToObject(p, "point", point(rgb));
        cJSON_AddItemToObject(p, "label", label(b->name, rgb));
    }
    return p;
}

/* A fixed marker: id, label, where body b of phase p was at t, visible from t to the end. */
static cJSON *marker_packet(const lv_ex_run *r, size_t p, size_t j, double t, const char *text)
{
    const lv_ex_phase *ph = &r->phases[p];
    const lv_ex_body *b = &r->bodies[r->phase_body[p]];
    const lv_ex_track *k = lv_ex_track_of(b, p);
    double lat, lon, h;
    lv_ex_locate(b, k, t, &lat, &lon, &h);
    char buf[512];
    int rgb[3];
    lv_ex_colour(r, p, rgb);
    cJSON *o = cJSON_CreateObject();
    snprintf(buf, sizeof buf, "event/%s/%zu", ph->name, j);
    cJSON_AddStringToObject(o, "id", buf);
    snprintf(buf, sizeof buf, "%s (%s)", text, ph->name);
    cJSON_AddStringToObject(o, "name", buf);
    snprintf(buf, sizeof buf, "%s in phase %s at t = %.6f s, h = %.3f km",
             text, ph->name, t, h / 1000.0);
    cJSON_AddStringToObject(o, "description", buf);
    add_interval(o, "availability", r, t, r->t1);
    cJSON *pos = cJSON_AddObjectToObject(o, "position");
    const double c[3] = {lon * RAD2DEG, lat * RAD2DEG, h};
    cJSON_AddItemToObject(pos, "cartographicDegrees", cJSON_CreateDoubleArray(c, 3));
    cJSON_AddItemToObject(o, "point", point(rgb));
    cJSON_AddItemToObject(o, "label", label(text, rgb));
    return o;
}

static lv_status write_czml(const lv_ex_run *r, lv_err *err)
{
    char path[LV_EX_PATH_CAP];
    snprintf(path, sizeof path, "%s/mission.czml", r->outdir);
    cJSON *doc = cJSON_CreateArray();
    if (doc == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    cJSON_AddItemToArray(doc, document_packet(r));
    for (size_t bi = 0; bi < r->n_bodies; bi++) {
        const lv_ex_body *b = &r->bodies[bi];
        for (size_t i = 0; i < b->n_tracks; i++)
            cJSON_AddItemToArray(doc, track_packet(r, bi, &b->tracks[i], i + 1 == b->n_tracks));
    }
    /* Markers per done phase: 0 its start ("P2 start"), 1..n its events in summary order. */
    for (size_t p = 0; p < r->n_phases; p++) {
        const lv_ex_phase *ph = &r->phases[p];
        if (!ph->done || r->phase_body[p] < 0)
            continue;
        char text[300];
        lv_ex_marker_label(r, p, 0, text, sizeof text);
        cJSON_AddItemToArray(doc, marker_packet(r, p, 0, ph->t_start, text));
        for (size_t j = 0; j < ph->n_events; j++) {
            lv_ex_marker_label(r, p, j + 1, text, sizeof text);
            cJSON_AddItemToArray(doc, marker_packet(r, p, j + 1, ph->events[j].t, text));
        }
    }
    char *text = cJSON_Print(doc);
    cJSON_Delete(doc);
    if (text == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    lv_atomic out;
    lv_status st = lv_atomic_open(&out, path, err);
    if (st == LV_OK) {
        fputs(text, out.fp);
        fputc('\n', out.fp);
        st = lv_atomic_commit(&out, err);
    }
    cJSON_free(text);
    if (st == LV_OK)
        lv_ex_report(r, "czml", path, NULL);
    return st;
}

const lv_ex_format lv_ex_czml = {
    "czml", "mission.czml", "mission.czml",
    "CZML for CesiumJS: every body's track, phase colours, event markers", write_czml};
