/* export_czml.c - mission.czml for Cesium: a document packet with the clock, one track packet
 * per body and phase, the instantaneous impact point's trace per body (polylines), event and
 * phase-start markers. Packet and property names: the CZML Guide
 * and Packet reference (AnalyticalGraphicsInc/czml-writer wiki).
 * Written straight to the file as it goes (no document tree, nothing held per sample), laid
 * out byte for byte as cJSON_Print lays a document out (cJSON 1.7.15, print_object,
 * print_array, print_number, print_string_ptr): objects one item per line indented by tabs,
 * "key":<tab>value; arrays on one line, ", " between items; numbers as lv_ex_json_number says:
 * exact, as lv_json_print writes the other JSON files (post/json_print.h), where cJSON_Print
 * itself would write 15 digits that read back to another double (docs/exports.md, "CZML"). */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "core/status.h"
#include "core/units.h"
#include "io/atomic.h"
#include "io/numfmt.h"
#include "lvsim/lv_planet.h"
#include "post/export_int.h"

#define RAD2DEG (180.0 / LV_PI) /* deg per rad */

/* ------------------------------------------------------- JSON as cJSON -- */

size_t lv_ex_json_number(double d, char *buf)
{
    if (!isfinite(d)) {
        memcpy(buf, "null", 5);
        return 4;
    }
    return lv_numfmt_double(d, buf); /* shortest round-trip digits, '.' whatever the locale */
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

/* A CZML `description` is HTML (Cesium's info box renders it): the text with &, <, >, " and '
 * escaped, so that a user's event or stage name shows as written (a name with "</script>"). */
static void jw_description(jw *w, const char *text)
{
    char buf[2048];
    size_t n = 0;
    for (const char *c = text; *c != '\0' && n + 7 < sizeof buf; c++) {
        const char *e = *c == '&' ? "&amp;" : *c == '<' ? "&lt;" : *c == '>' ? "&gt;"
                        : *c == '"' ? "&quot;" : *c == '\'' ? "&#39;" : NULL;
        if (e != NULL) {
            memcpy(buf + n, e, strlen(e));
            n += strlen(e);
        } else {
            buf[n++] = *c;
        }
    }
    buf[n] = '\0';
    jw_str(w, "description", buf);
}

static void jw_num(jw *w, const char *key, double v)
{
    char buf[LV_EX_JSON_NUM_CAP];
    jw_item(w, key);
    fwrite(buf, 1, lv_ex_json_number(v, buf), w->f);
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
    jw_description(w, buf);
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

/* Body bi's instantaneous impact point trace: a polyline on the ground per finite run of at
 * least two rows (a NAN row, no impact, ends one), id "iip/<body>/<run>", drawn all mission
 * long (docs/exports.md, "CZML"). */
static void iip_packets(jw *w, const lv_ex_run *r, size_t bi)
{
    const lv_ex_body *b = &r->bodies[bi];
    size_t start = 0, len = 0, run = 0;
    char buf[512];
    for (size_t i = 0; b->has_iip && i <= b->n_rows; i++) {
        if (i < b->n_rows && isfinite(b->rows[i].iip_lat) && isfinite(b->rows[i].iip_lon)) {
            if (len++ == 0)
                start = i;
            continue;
        }
        if (len >= 2) {
            jw_open(w, NULL, '{');
            snprintf(buf, sizeof buf, "iip/%s/%zu", b->name, run++);
            jw_str(w, "id", buf);
            snprintf(buf, sizeof buf, "%s: IIP trace", b->name);
            jw_str(w, "name", buf);
            snprintf(buf, sizeof buf, "Instantaneous impact point of body %s (drag-free, "
                     "thrust off) from t = %.3f to %.3f s after the mission epoch.", b->name,
                     b->rows[start].t, b->rows[start + len - 1].t);
            jw_description(w, buf);
            interval(w, "availability", r, r->t0, r->t1);
            jw_open(w, "polyline", '{');
            jw_open(w, "positions", '{');
            jw_open(w, "cartographicDegrees", '[');
            for (size_t j = start; j < start + len; j++) {
                jw_num(w, NULL, b->rows[j].iip_lon * RAD2DEG);
                jw_num(w, NULL, b->rows[j].iip_lat * RAD2DEG);
                jw_num(w, NULL, 0);
            }
            jw_close(w);
            jw_close(w);
            jw_open(w, "material", '{');
            jw_open(w, "solidColor", '{');
            rgba(w, "color", 224, 32, 32, 255);
            jw_close(w);
            jw_close(w);
            jw_num(w, "width", 1.5);
            jw_str(w, "arcType", "GEODESIC");
            jw_close(w);
            jw_close(w);
        }
        len = 0;
    }
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
    jw_description(w, buf);
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

/* ------------------------------------------------------- vehicle models -- */

/* A stage without `geometry`: a cylinder DEFAULT_LD times as long as wide whose volume at
 * DEFAULT_RHO holds its full mass (dry + propellant at its first phase): a shape that scales
 * with the stage, not the vehicle's (docs/exports.md, "Vehicle models"). */
#define DEFAULT_LD 8.0    /* length / diameter */
#define DEFAULT_RHO 300.0 /* kg/m^3, bulk density of a launcher stage, roughly */
#define MODEL_MIN_PX 48   /* minimumPixelSize: the model is drawn at least this tall */
#define MODEL_MAX_SCALE 5000 /* maximumScale: at most 5000 times its size */

static double json_num(const cJSON *o, const char *key)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

/* Stage `stage`'s shape: summary.json phases[].geometry.<stage> (the mission's `geometry:`),
 * else the default from its mass (phases[].propellant.<stage>). */
static lv_ex_shape stage_shape(const lv_ex_run *r, const char *stage)
{
    const cJSON *phases = cJSON_GetObjectItemCaseSensitive(r->res->json, "phases");
    const cJSON *p;
    double mass = 0.0;
    cJSON_ArrayForEach(p, phases) {
        const cJSON *g = cJSON_GetObjectItemCaseSensitive(
            cJSON_GetObjectItemCaseSensitive(p, "geometry"), stage);
        const double len = json_num(g, "length"), dia = json_num(g, "diameter");
        if (len > 0.0 && dia > 0.0) {
            const double span = json_num(g, "span");
            return (lv_ex_shape){len, dia, span > 0.0 ? span : 0.0};
        }
        const cJSON *b = cJSON_GetObjectItemCaseSensitive(
            cJSON_GetObjectItemCaseSensitive(p, "propellant"), stage);
        const double m = json_num(b, "dry_mass") + json_num(b, "start");
        if (m > mass)
            mass = m;
    }
    if (!(mass >= 1.0))
        mass = 1.0;
    const double d = cbrt(4.0 * mass / (LV_PI * DEFAULT_LD * DEFAULT_RHO));
    return (lv_ex_shape){DEFAULT_LD * d, d, 0.0};
}

/* The unit quaternion [x, y, z, w] of the rotation whose matrix has columns c[0], c[1], c[2]
 * (Shepperd's method: the largest of 4w^2, 4x^2, 4y^2, 4z^2 first). */
static void mat_to_quat(const double c[3][3], double q[4])
{
    /* m[i][j]: row i, column j */
    const double m00 = c[0][0], m11 = c[1][1], m22 = c[2][2];
    const double tr = m00 + m11 + m22;
#define M(i, j) c[j][i]
    if (tr >= m00 && tr >= m11 && tr >= m22) {
        const double w4 = 2.0 * sqrt(1.0 + tr);
        q[3] = 0.25 * w4;
        q[0] = (M(2, 1) - M(1, 2)) / w4;
        q[1] = (M(0, 2) - M(2, 0)) / w4;
        q[2] = (M(1, 0) - M(0, 1)) / w4;
    } else if (m00 >= m11 && m00 >= m22) {
        const double x4 = 2.0 * sqrt(1.0 + m00 - m11 - m22);
        q[0] = 0.25 * x4;
        q[3] = (M(2, 1) - M(1, 2)) / x4;
        q[1] = (M(0, 1) + M(1, 0)) / x4;
        q[2] = (M(0, 2) + M(2, 0)) / x4;
    } else if (m11 >= m22) {
        const double y4 = 2.0 * sqrt(1.0 - m00 + m11 - m22);
        q[1] = 0.25 * y4;
        q[3] = (M(0, 2) - M(2, 0)) / y4;
        q[0] = (M(0, 1) + M(1, 0)) / y4;
        q[2] = (M(1, 2) + M(2, 1)) / y4;
    } else {
        const double z4 = 2.0 * sqrt(1.0 - m00 - m11 + m22);
        q[2] = 0.25 * z4;
        q[3] = (M(1, 0) - M(0, 1)) / z4;
        q[0] = (M(0, 2) + M(2, 0)) / z4;
        q[1] = (M(1, 2) + M(2, 1)) / z4;
    }
#undef M
    const double nq = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (int i = 0; i < 4; i++)
        q[i] /= nq;
}

/* Body axes (ECEF) from 3-2-1 Euler angles relative to the geodetic NED frame at lat, lon
 * (docs/frames.md; the outputs theta, psi, phi of dof3, dof6, flat6). */
static void euler_axes(double th, double ps, double ph, double lat, double lon, double ax[3][3])
{
    const double ct = cos(th), st = sin(th), cp = cos(ps), sp = sin(ps), cf = cos(ph),
                 sf = sin(ph);
    /* body axes in NED components: the columns of C_ned_body = R3(-psi) R2(-theta) R1(-phi) */
    const double b[3][3] = {{ct * cp, ct * sp, -st},
                            {sf * st * cp - cf * sp, sf * st * sp + cf * cp, sf * ct},
                            {cf * st * cp + sf * sp, cf * st * sp - sf * cp, cf * ct}};
    const double sl = sin(lat), cl = cos(lat), so = sin(lon), co = cos(lon);
    const double n[3] = {-sl * co, -sl * so, cl}, e[3] = {-so, co, 0.0},
                 d[3] = {-cl * co, -cl * so, -sl};
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++)
            ax[i][k] = b[i][0] * n[k] + b[i][1] * e[k] + b[i][2] * d[k];
}

typedef struct att_row {
    double t;
    double q[4]; /* x, y, z, w: the model's axes -> ECEF (CZML unitQuaternion) */
} att_row;

/* The attitude of phase p at its result rows, as CZML orientation quaternions: the model's
 * +x = body x (nose), +y = -body y, +z = -body z (docs/exports.md, "Vehicle models").
 *   q_w, q_x, q_y, q_z (dof6: body -> ECI): the body axes turned to ECEF by C_ecef_eci(t);
 *   else theta, psi, phi (dof3: the attitude alpha, beta, mu give about the air-relative
 *   velocity; flat6): relative to NED at the row's lat, lon (its own columns, else the body
 *   track's);
 *   else heading (runway): pitch alpha_in + fpa along the heading, no roll.
 * *n = 0 (and no error) when the phase has none of these or no CSV. Rows at one instant (an
 * event): the last. */
static lv_status phase_attitude(const lv_ex_run *r, size_t p, att_row **out, size_t *n,
                                lv_err *err)
{
    *out = NULL;
    *n = 0;
    const lv_ex_phase *ph = &r->phases[p];
    if (ph->csv == NULL || !lv_results_exists(r->res, ph->csv) || r->phase_body[p] < 0)
        return LV_OK;
    lv_results_table *tb = NULL;
    lv_status st = lv_results_load(r->res, ph->csv, NULL, &tb, err);
    if (st != LV_OK)
        return st;
    enum { T, QW, QX, QY, QZ, TH, PS, PH, LAT, LON, HD, AL, FPA, NC };
    static const char *const names[NC] = {"time", "q_w",   "q_x", "q_y", "q_z",
                                          "theta", "psi",  "phi", "lat", "lon",
                                          "heading", "alpha_in", "fpa"};
    long c[NC];
    for (int i = 0; i < NC; i++)
        c[i] = lv_results_table_col(tb, names[i]);
    const int quat = !r->flat && c[QW] >= 0 && c[QX] >= 0 && c[QY] >= 0 && c[QZ] >= 0;
    const int euler = c[TH] >= 0 && c[PS] >= 0 && c[PH] >= 0;
    const int runway = c[HD] >= 0;
    if (c[T] < 0 || tb->n_rows == 0 || !(quat || euler || runway)) {
        lv_results_table_free(tb);
        return LV_OK;
    }
    lv_planet planet = lv_planet_earth();
    if (r->planet != NULL && lv_planet_by_name(r->planet, &planet, NULL) != LV_OK)
        planet = lv_planet_earth();
    const lv_ex_body *b = &r->bodies[r->phase_body[p]];
    const lv_ex_track *k = lv_ex_track_of(b, p);
    att_row *a = malloc(tb->n_rows * sizeof *a);
    if (a == NULL) {
        lv_results_table_free(tb);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    size_t m = 0;
    for (size_t i = 0; i < tb->n_rows; i++) {
        const double *v = tb->v + i * tb->n_cols;
        const double t = v[c[T]];
        double ax[3][3]; /* body x, y, z in ECEF */
        if (quat) {
            const double w = v[c[QW]], x = v[c[QX]], y = v[c[QY]], z = v[c[QZ]];
            const double s = 1.0 / (w * w + x * x + y * y + z * z);
            /* columns of R(q), body -> ECI (Hamilton, active) */
            const double e[3][3] = {
                {1.0 - 2.0 * s * (y * y + z * z), 2.0 * s * (x * y + w * z),
                 2.0 * s * (x * z - w * y)},
                {2.0 * s * (x * y - w * z), 1.0 - 2.0 * s * (x * x + z * z),
                 2.0 * s * (y * z + w * x)},
                {2.0 * s * (x * z + w * y), 2.0 * s * (y * z - w * x),
                 1.0 - 2.0 * s * (x * x + y * y)}};
            double C[3][3];
            lv_frames_C_ecef_eci(&planet, t, C);
            for (int col = 0; col < 3; col++)
                for (int row = 0; row < 3; row++)
                    ax[col][row] = C[row][0] * e[col][0] + C[row][1] * e[col][1] +
                                   C[row][2] * e[col][2];
        } else {
            double lat, lon, h;
            if (c[LAT] >= 0 && c[LON] >= 0) {
                lat = v[c[LAT]];
                lon = v[c[LON]];
            } else if (k != NULL) {
                lv_ex_locate(b, k, t, &lat, &lon, &h);
            } else {
                continue;
            }
            if (euler) {
                euler_axes(v[c[TH]], v[c[PS]], v[c[PH]], lat, lon, ax);
            } else {
                const double pitch = (c[AL] >= 0 ? v[c[AL]] : 0.0) + (c[FPA] >= 0 ? v[c[FPA]] : 0.0);
                euler_axes(pitch, v[c[HD]], 0.0, lat, lon, ax);
            }
        }
        int finite = isfinite(t);
        for (int col = 0; col < 3; col++)
            for (int row = 0; row < 3; row++)
                finite &= isfinite(ax[col][row]) ? 1 : 0;
        if (!finite)
            continue;
        /* the model's axes: +x = body x, +y = -body y, +z = -body z */
        const double mc[3][3] = {{ax[0][0], ax[0][1], ax[0][2]},
                                 {-ax[1][0], -ax[1][1], -ax[1][2]},
                                 {-ax[2][0], -ax[2][1], -ax[2][2]}};
        att_row row;
        row.t = t;
        mat_to_quat(mc, row.q);
        if (m > 0 && !(t > a[m - 1].t)) {
            if (t < a[m - 1].t)
                continue; /* not in time order: left out */
            m--;          /* the same instant: the later row */
        }
        /* q and -q are one rotation: keep neighbours on one side, so that the samples
         * interpolate the short way */
        const att_row *prev = m > 0 ? &a[m - 1] : NULL;
        if (prev != NULL && prev->q[0] * row.q[0] + prev->q[1] * row.q[1] +
                                    prev->q[2] * row.q[2] + prev->q[3] * row.q[3] < 0.0)
            for (int i2 = 0; i2 < 4; i2++)
                row.q[i2] = -row.q[i2];
        a[m++] = row;
    }
    lv_results_table_free(tb);
    if (m == 0) {
        free(a);
        a = NULL;
    }
    *out = a;
    *n = m;
    return LV_OK;
}

/* Is stage s among phase q's stages? */
static int carries(const lv_ex_phase *q, const char *s)
{
    for (size_t i = 0; i < q->n_stages; i++)
        if (strcmp(q->stages[i], s) == 0)
            return 1;
    return 0;
}

/* "model/<phase>": the stack of phase p's stages with its attitude, from the phase start to
 * its end (a phase no other phase continues: to the mission's end); "model/<phase>/spent":
 * the stages of p that no child phase carries on, held where and as p left them. */
static lv_status model_packets(jw *w, const lv_ex_run *r, size_t p, lv_err *err)
{
    const lv_ex_phase *ph = &r->phases[p];
    if (!ph->done || r->phase_body[p] < 0 || ph->n_stages == 0)
        return LV_OK;
    att_row *a = NULL;
    size_t na = 0;
    lv_status st = phase_attitude(r, p, &a, &na, err);
    if (st != LV_OK)
        return st;
    if (na == 0) {
        lv_ex_report(r, "czml", NULL, "phase '%s': no attitude in its results (no vehicle "
                     "model)", ph->name);
        return LV_OK;
    }
    const char **spent = malloc(ph->n_stages * sizeof *spent);
    lv_ex_shape *sh = malloc(ph->n_stages * sizeof *sh);
    if (spent == NULL || sh == NULL) {
        free(spent);
        free(sh);
        free(a);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    int children = 0;
    size_t n_spent = 0;
    for (size_t q = 0; q < r->n_phases; q++)
        if (r->phases[q].parent == (int)p && r->phases[q].done)
            children = 1;
    for (size_t i = 0; i < ph->n_stages && children; i++) {
        int on = 0;
        for (size_t q = 0; q < r->n_phases && !on; q++)
            on = r->phases[q].parent == (int)p && r->phases[q].done &&
                 carries(&r->phases[q], ph->stages[i]);
        if (!on)
            spent[n_spent++] = ph->stages[i];
    }
    const lv_ex_body *b = &r->bodies[r->phase_body[p]];
    int rgb[3];
    lv_ex_colour(r, p, rgb);
    char id[400], ref[600], epoch[48];
    lv_ex_iso(r, 0.0, "Z", epoch, sizeof epoch);
    for (int part = 0; part < 1 + (n_spent > 0) && st == LV_OK; part++) {
        const char *const *list = part == 0 ? ph->stages : spent;
        const size_t nl = part == 0 ? ph->n_stages : n_spent;
        char names[600] = "";
        size_t used = 0;
        for (size_t i = 0; i < nl; i++) {
            sh[i] = stage_shape(r, list[i]);
            const int k = snprintf(names + used, sizeof names - used, "%s%s", i ? " + " : "",
                                   list[i]);
            if (k > 0 && used + (size_t)k < sizeof names)
                used += (size_t)k;
        }
        unsigned char *glb = NULL;
        size_t glb_len = 0;
        st = lv_ex_glb_stack(sh, nl, rgb, &glb, &glb_len, err);
        if (st != LV_OK)
            break;
        char *b64 = lv_ex_base64(glb, glb_len);
        free(glb);
        const size_t uri_cap = b64 != NULL ? strlen(b64) + 64 : 0;
        char *uri = b64 != NULL ? malloc(uri_cap) : NULL;
        if (uri == NULL) {
            free(b64);
            st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
            break;
        }
        snprintf(uri, uri_cap, "data:model/gltf-binary;base64,%s", b64);
        free(b64);
        jw_open(w, NULL, '{');
        snprintf(id, sizeof id, part == 0 ? "model/%s" : "model/%s/spent", ph->name);
        jw_str(w, "id", id);
        char text[800];
        snprintf(text, sizeof text, part == 0 ? "%s (phase %s)" : "%s (spent after phase %s)",
                 names, ph->name);
        jw_str(w, "name", text);
        double total = 0.0;
        for (size_t i = 0; i < nl; i++)
            total += sh[i].length;
        snprintf(text, sizeof text, "%s in phase %s: a shape %.1f m long from the stages' "
                 "geometry, turned by the body's attitude (model x = body x, the nose).",
                 names, ph->name, total);
        jw_description(w, text);
        if (part == 0)
            interval(w, "availability", r, ph->t_start, children ? ph->t_end : r->t1);
        else
            interval(w, "availability", r, ph->t_end, r->t1);
        jw_open(w, "position", '{');
        snprintf(ref, sizeof ref, "track/%s/%s#position", b->name, ph->name);
        jw_str(w, "reference", ref);
        jw_close(w);
        jw_open(w, "orientation", '{');
        if (part == 0) {
            jw_str(w, "epoch", epoch);
            jw_str(w, "interpolationAlgorithm", "LINEAR");
            jw_num(w, "interpolationDegree", 1);
            jw_str(w, "forwardExtrapolationType", "HOLD");
            jw_str(w, "backwardExtrapolationType", "HOLD");
            jw_open(w, "unitQuaternion", '[');
            for (size_t i = 0; i < na; i++) {
                jw_num(w, NULL, a[i].t);
                for (int c = 0; c < 4; c++)
                    jw_num(w, NULL, a[i].q[c]);
            }
            jw_close(w);
        } else {
            snprintf(ref, sizeof ref, "model/%s#orientation", ph->name);
            jw_str(w, "reference", ref);
        }
        jw_close(w);
        jw_open(w, "model", '{');
        jw_str(w, "gltf", uri);
        jw_num(w, "minimumPixelSize", MODEL_MIN_PX);
        jw_num(w, "maximumScale", MODEL_MAX_SCALE);
        jw_str(w, "shadows", "DISABLED");
        jw_close(w);
        jw_close(w);
        free(uri);
    }
    free(spent);
    free(sh);
    free(a);
    return st;
}

static lv_status write_czml(const lv_ex_run *r, lv_err *err)
{
    char path[LV_EX_PATH_CAP];
    snprintf(path, sizeof path, "%s/mission.czml", r->outdir);
    lv_atomic out;
    lv_status st = lv_atomic_open(&out, path, err);
    if (st != LV_OK)
        return st;
    jw w;
    memset(&w, 0, sizeof w);
    w.f = out.fp;
    jw_open(&w, NULL, '[');
    document_packet(&w, r);
    for (size_t bi = 0; bi < r->n_bodies; bi++) {
        const lv_ex_body *b = &r->bodies[bi];
        for (size_t i = 0; i < b->n_tracks; i++)
            track_packet(&w, r, bi, &b->tracks[i], i + 1 == b->n_tracks);
    }
    for (size_t bi = 0; bi < r->n_bodies; bi++)
        iip_packets(&w, r, bi);
    /* A vehicle model per done phase with an attitude in its results */
    for (size_t p = 0; p < r->n_phases && st == LV_OK; p++)
        st = model_packets(&w, r, p, err);
    if (st != LV_OK) {
        lv_atomic_abort(&out);
        return st;
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
    "CZML for CesiumJS: every body's track, phase colours, event markers, vehicle models with "
    "their attitude, the IIP trace", write_czml};
