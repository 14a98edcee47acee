/* export.c - trajectory exports from a results folder: reads summary.json and the merged
 * body_<stage>.csv files back (post/results.h), then hands them to the CZML, KML and CCSDS OEM
 * writers (export_czml.c, export_kml.c, export_oem.c), registered in the table below
 * (docs/architecture.md, "An export"). Post-processing only: nothing is rerun.
 * Times: the epoch on the TAI scale plus SI seconds, written back as UTC with its leap seconds
 * (core/utc.h, ERFA). */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "core/units.h"
#include "post/export_int.h"
#include "lvsim/lv_export.h"

/* ------------------------------------------------------------- the table -- */

/* One line per export (its writer and descriptor in export_<name>.c); flag 1u << position. */
const lv_ex_format *const lv_ex_formats[] = {
    &lv_ex_czml, /* LV_EXPORT_CZML */
    &lv_ex_kml,  /* LV_EXPORT_KML */
    &lv_ex_oem,  /* LV_EXPORT_OEM */
    NULL};

size_t lv_ex_format_count(void)
{
    size_t n = 0;
    while (lv_ex_formats[n] != NULL)
        n++;
    return n;
}

LV_API const char *lv_export_format_info(size_t i, const char **files, const char **description)
{
    if (i >= lv_ex_format_count())
        return NULL;
    if (files != NULL)
        *files = lv_ex_formats[i]->files;
    if (description != NULL)
        *description = lv_ex_formats[i]->description;
    return lv_ex_formats[i]->name;
}

/* ------------------------------------------------------------------ time -- */

lv_tai lv_ex_ticks(const lv_ex_run *r, double t)
{
    return lv_utc_add(r->epoch, t);
}

void lv_ex_iso(const lv_ex_run *r, double t, const char *suffix, char *buf, size_t cap)
{
    (void)lv_utc_format(lv_ex_ticks(r, t), 0, suffix, buf, cap, NULL);
}

int lv_ex_iso_no60(const lv_ex_run *r, double t, const char *suffix, char *buf, size_t cap)
{
    int in_leap = 0;
    (void)lv_utc_format(lv_ex_ticks(r, t), 1, suffix, buf, cap, &in_leap);
    return in_leap;
}

#define US_PER_S 1000000LL
#define CLOCK_SPAN (86399LL * US_PER_S) /* microseconds of a day written from the cache */

int lv_ex_clock_iso(const lv_ex_run *r, lv_ex_clock *c, double t, int no60, const char *suffix,
                    char *buf, size_t cap)
{
    const lv_tai tai = lv_ex_ticks(r, t);
    const size_t ns = strlen(suffix);
    if (c->ok && tai >= c->day0 && tai - c->day0 < CLOCK_SPAN && cap >= 28 + ns) {
        const long long in_day = tai - c->day0;
        const int s = (int)(in_day / US_PER_S), us = (int)(in_day % US_PER_S);
        const int f[3] = {s / 3600, s / 60 % 60, s % 60};
        char *p = buf;
        memcpy(p, c->date, 10);
        p += 10;
        *p++ = 'T';
        for (int k = 0; k < 3; k++) {
            if (k > 0)
                *p++ = ':';
            *p++ = (char)('0' + f[k] / 10);
            *p++ = (char)('0' + f[k] % 10);
        }
        if (us != 0) {
            *p++ = '.';
            for (int k = 5, v = us; k >= 0; k--, v /= 10)
                p[k] = (char)('0' + v % 10);
            p += 6;
        }
        memcpy(p, suffix, ns + 1);
        return 0;
    }
    int in_leap = 0;
    const int st = lv_utc_format(tai, no60, suffix, buf, cap, &in_leap);
    c->ok = 0;
    /* "YYYY-MM-DDThh:mm:ss[.ffffff]": read back its time of day */
    if (st == LV_UTC_BAD || in_leap || strlen(buf) < 19 + ns || buf[10] != 'T')
        return in_leap;
    const int hh = atoi(buf + 11), mm = atoi(buf + 14), ss = atoi(buf + 17);
    const int us = buf[19] == '.' ? atoi(buf + 20) : 0;
    const double dat = lv_utc_tai_minus_utc(tai);
    if (ss >= 60 || dat != floor(dat))
        return in_leap;
    c->day0 = tai - ((hh * 60LL + mm) * 60LL + ss) * US_PER_S - us;
    memcpy(c->date, buf, 10);
    c->date[10] = '\0';
    c->ok = 1;
    return in_leap;
}

/* --------------------------------------------------------------- helpers -- */

const lv_ex_track *lv_ex_track_of(const lv_ex_body *b, size_t p)
{
    for (size_t i = 0; i < b->n_tracks; i++)
        if (b->tracks[i].phase == p)
            return &b->tracks[i];
    return NULL;
}

void lv_ex_locate(const lv_ex_body *b, const lv_ex_track *k, double t, double *lat, double *lon,
                  double *h)
{
    const lv_ex_row *row = b->rows + k->first;
    size_t i = 0;
    while (i + 1 < k->n && row[i + 1].t <= t)
        i++;
    if (i + 1 >= k->n || t <= row[i].t) { /* at or outside an end, or on a row */
        *lat = row[i].lat;
        *lon = row[i].lon;
        *h = row[i].h;
        return;
    }
    const double w = (t - row[i].t) / (row[i + 1].t - row[i].t);
    double dlon = row[i + 1].lon - row[i].lon; /* across the antimeridian: the short way */
    if (dlon > LV_PI)
        dlon -= 2.0 * LV_PI;
    else if (dlon < -LV_PI)
        dlon += 2.0 * LV_PI;
    *lat = row[i].lat + w * (row[i + 1].lat - row[i].lat);
    *lon = remainder(row[i].lon + w * dlon, 2.0 * LV_PI);
    *h = row[i].h + w * (row[i + 1].h - row[i].h);
}

void lv_ex_colour(const lv_ex_run *r, size_t p, int rgb[3])
{
    /* Distinct on a dark globe and in Google Earth; repeats after eight phases. */
    static const int palette[8][3] = {{255, 165, 0},   {0, 200, 255},   {120, 230, 60},
                                      {255, 70, 70},   {190, 120, 255}, {255, 240, 80},
                                      {255, 120, 200}, {170, 170, 170}};
    const int i = (r->phases[p].index - 1) % 8;
    const int k = i < 0 ? 0 : i;
    rgb[0] = palette[k][0];
    rgb[1] = palette[k][1];
    rgb[2] = palette[k][2];
}

const char *lv_ex_event_label(const lv_ex_event *e)
{
    /* the user's name of it ("MECO", `name:`), else the event's own name, as summary.json,
     * the report and the CLI give it: "burnout", "impact" (a ground contact, whatever its
     * speed: never "landing"), a time event's source */
    return e->label != NULL ? e->label : e->name != NULL ? e->name : "time event";
}

void lv_ex_marker_label(const lv_ex_run *r, size_t p, size_t k, char *buf, size_t cap)
{
    const lv_ex_phase *ph = &r->phases[p];
    if (k > 0) {
        snprintf(buf, cap, "%s", lv_ex_event_label(&ph->events[k - 1]));
        return;
    }
    const int sep = ph->parent >= 0 && ph->n_stages < r->phases[ph->parent].n_stages;
    if (sep)
        snprintf(buf, cap, "separation (%s)", ph->name);
    else
        snprintf(buf, cap, "%s start", ph->name);
}

static void run_free(lv_ex_run *r)
{
    free(r->phase_body);
    for (size_t i = 0; r->bodies != NULL && i < r->n_bodies; i++) {
        free(r->bodies[i].path);
        free(r->bodies[i].rows);
        free(r->bodies[i].tracks);
    }
    free(r->bodies);
}

/* -------------------------------------------------------------- summary -- */

/* What the exports need of the summary beyond what the reader checks: the mission's name,
 * epoch and world; every phase's index and state; times and event times of the done phases
 * (at least one); a trajectory file for every body. */
static lv_status check_summary(lv_ex_run *r, const lv_results *res, lv_err *err)
{
    const char *path = res->summary_path;
    if (res->mission == NULL || res->epoch == NULL || res->world == NULL)
        return lv_fail(err, LV_ERR_INPUT, "%s: not an lvsim summary: 'mission', 'epoch', "
                       "'world', 'phases' or 'bodies' missing", path);
    const int js = lv_utc_parse(res->epoch, &r->epoch);
    if (js == LV_UTC_NO_LEAP)
        return lv_fail(err, LV_ERR_INPUT, "%s: epoch '%.40s': no leap second at that time (a "
                       "second 60 exists only as 23:59:60 of a day that ended with one)", path,
                       res->epoch);
    if (js < 0)
        return lv_fail(err, LV_ERR_INPUT, "%s: epoch '%.40s': ISO 8601 UTC time like "
                       "2026-03-01T12:00:00Z expected", path, res->epoch);
    if (res->n_phases == 0)
        return lv_fail(err, LV_ERR_INPUT, "%s: no phases", path);
    r->t0 = INFINITY;
    r->t1 = -INFINITY;
    for (size_t i = 0; i < res->n_phases; i++) {
        const lv_ex_phase *p = &res->phases[i];
        if (p->index < 1 || p->state == NULL)
            return lv_fail(err, LV_ERR_INPUT, "%s: phases[%zu]: 'name', 'index' or 'state' "
                           "missing", path, i);
        if (!p->done)
            continue;
        if (!isfinite(p->t_start) || !isfinite(p->t_end) || p->t_end < p->t_start)
            return lv_fail(err, LV_ERR_INPUT, "%s: phase '%s': 't_start'/'t_end' missing or "
                           "wrong", path, p->name);
        for (size_t j = 0; j < p->n_events; j++)
            if (!isfinite(p->events[j].t))
                return lv_fail(err, LV_ERR_INPUT, "%s: phase '%s': events[%zu]: 't' missing",
                               path, p->name, j);
        r->t0 = fmin(r->t0, p->t_start);
        r->t1 = fmax(r->t1, p->t_end);
    }
    if (!(r->t0 <= r->t1))
        return lv_fail(err, LV_ERR_INPUT, "%s: no phase is done: nothing to export", path);
    char a[48], b[48];
    if (lv_utc_format(lv_ex_ticks(r, r->t0), 0, "Z", a, sizeof a, NULL) == LV_UTC_BAD ||
        lv_utc_format(lv_ex_ticks(r, r->t1), 0, "Z", b, sizeof b, NULL) == LV_UTC_BAD ||
        fabs(r->t0) > 1e10 || fabs(r->t1) > 1e10)
        return lv_fail(err, LV_ERR_INPUT, "%s: phase times %.17g .. %.17g s after the epoch "
                       "'%s' leave the years 0000-9999 that UTC text can be written in", path,
                       r->t0, r->t1, res->epoch);
    lv_utc_note(lv_ex_ticks(r, r->t0), lv_ex_ticks(r, r->t1), r->time_note,
                sizeof r->time_note);
    for (size_t i = 0; i < res->n_bodies; i++)
        if (res->bodies[i].trajectory == NULL)
            return lv_fail(err, LV_ERR_INPUT, "%s: bodies[%zu]: 'name' or 'trajectory' (a file "
                           "name in the folder) missing", path, i);
    return LV_OK;
}

/* ------------------------------------------------------------- body CSV -- */

enum { C_TIME, C_PHASE, C_LAT, C_LON, C_H, C_RX, C_RY, C_RZ, C_VX, C_VY, C_VZ, C_ILAT, C_ILON,
       C_N };
static const char *const col_names[C_N + 1] = {"time", "phase", "lat", "lon", "h", "r_eci_x",
                                               "r_eci_y", "r_eci_z", "v_eci_x", "v_eci_y",
                                               "v_eci_z", "iip_lat", "iip_lon", NULL};
static const char *const text_cols[] = {"phase", NULL};
/* Every column but `phase` must be a finite number where present; iip_lat, iip_lon may be NaN
 * (no impact: docs/models.md). */
static const char *const finite_cols[] = {"time", "lat", "lon", "h", "r_eci_x", "r_eci_y",
                                          "r_eci_z", "v_eci_x", "v_eci_y", "v_eci_z", NULL};

/* Body b's trajectory as rows and per-phase tracks: rows in CSV order, one block per phase (a
 * done phase of the summary), time not going back; of rows at the same instant (an event)
 * only the last. */
static lv_status read_body(lv_ex_run *r, const lv_results *res, size_t bi, lv_err *err)
{
    lv_ex_body *b = &r->bodies[bi];
    const lv_results_csv_spec spec = {text_cols, finite_cols};
    lv_results_table *t = NULL;
    lv_status st = lv_results_load(res, res->bodies[bi].trajectory, &spec, &t, err);
    if (st != LV_OK)
        return st;
    b->name = res->bodies[bi].name;
    if ((b->path = malloc(strlen(t->path) + 1)) == NULL)
        goto nomem;
    memcpy(b->path, t->path, strlen(t->path) + 1);
    long col[C_N];
    for (int c = 0; c < C_N; c++)
        col[c] = lv_results_table_col(t, col_names[c]);
    for (int c = 0; c <= C_H; c++)
        if (col[c] < 0) {
            st = lv_fail(err, LV_ERR_INPUT, "%s:%zu: no column '%s' in the header", t->path,
                         t->header_line, col_names[c]);
            goto fail;
        }
    b->has_eci = 1;
    for (int c = C_RX; c <= C_VZ; c++)
        b->has_eci &= col[c] >= 0;
    b->has_iip = col[C_ILAT] >= 0 && col[C_ILON] >= 0;
    if (t->n_rows == 0) {
        st = lv_fail(err, LV_ERR_INPUT, "%s:%zu: no rows", t->path, t->n_lines);
        goto fail;
    }
    if ((b->rows = malloc(t->n_rows * sizeof *b->rows)) == NULL)
        goto nomem;
    size_t tracks_cap = 0;
    int cur = -1; /* phase of the current track */
    for (size_t i = 0; i < t->n_rows; i++) {
        const double *v = t->v + i * t->n_cols;
        const size_t line = t->line[i];
        lv_ex_row row;
        memset(&row, 0, sizeof row);
        row.line = line;
        row.iip_lat = row.iip_lon = NAN;
        double *dst[C_N] = {&row.t,        NULL,          &row.lat,      &row.lon,
                            &row.h,        &row.r_eci[0], &row.r_eci[1], &row.r_eci[2],
                            &row.v_eci[0], &row.v_eci[1], &row.v_eci[2], &row.iip_lat,
                            &row.iip_lon};
        for (int c = 0; c < C_N; c++)
            if (dst[c] != NULL && col[c] >= 0)
                *dst[c] = v[col[c]];
        const char *phase = lv_results_table_text(t, i, (size_t)col[C_PHASE]);
        const int k = lv_results_phase_find(res, phase);
        if (k < 0 || !r->phases[k].done) {
            st = lv_fail(err, LV_ERR_INPUT, "%s:%zu: phase '%.60s' is not a done phase of "
                         "summary.json", t->path, line, phase);
            goto fail;
        }
        if (k != cur) { /* a new track */
            if (lv_ex_track_of(b, (size_t)k) != NULL) {
                st = lv_fail(err, LV_ERR_INPUT, "%s:%zu: phase '%s' appears twice, not in one "
                             "block", t->path, line, r->phases[k].name);
                goto fail;
            }
            if (b->n_tracks == tracks_cap) {
                tracks_cap = tracks_cap ? 2 * tracks_cap : 8;
                lv_ex_track *nt = realloc(b->tracks, tracks_cap * sizeof *nt);
                if (nt == NULL)
                    goto nomem;
                b->tracks = nt;
            }
            b->tracks[b->n_tracks++] = (lv_ex_track){(size_t)k, b->n_rows, 0};
            cur = k;
        }
        lv_ex_track *tr = &b->tracks[b->n_tracks - 1];
        if (tr->n > 0) {
            const double t_prev = b->rows[b->n_rows - 1].t;
            if (row.t < t_prev) {
                st = lv_fail(err, LV_ERR_INPUT, "%s:%zu: time %.17g goes back (previous row "
                             "%.17g)", t->path, line, row.t, t_prev);
                goto fail;
            }
            if (row.t == t_prev) { /* an event instant: keep the row after it */
                b->rows[b->n_rows - 1] = row;
                continue;
            }
        }
        b->rows[b->n_rows++] = row;
        tr->n++;
    }
    lv_results_table_free(t);
    return LV_OK;
nomem:
    st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
fail:
    lv_results_table_free(t);
    return st;
}

/* ------------------------------------------------------------------- run -- */

void lv_ex_report(const lv_ex_run *r, const char *format, const char *file, const char *fmt, ...)
{
    lv_export_report *rep = r->rep;
    if (rep == NULL)
        return;
    lv_export_item *g = realloc(rep->items, (rep->n + 1) * sizeof *g);
    if (g == NULL)
        return; /* the report is informative: the files are what counts */
    rep->items = g;
    lv_export_item *it = &g[rep->n++];
    memset(it, 0, sizeof *it);
    snprintf(it->format, sizeof it->format, "%s", format);
    if (file != NULL) {
        const char *base = strrchr(file, '/');
        snprintf(it->file, sizeof it->file, "%s", base ? base + 1 : file);
    }
    if (fmt != NULL) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(it->note, sizeof it->note, fmt, ap);
        va_end(ap);
    }
}

void lv_export_report_clear(lv_export_report *rep)
{
    if (rep == NULL)
        return;
    free(rep->items);
    rep->items = NULL;
    rep->n = 0;
}

LV_API lv_status lv_export_run(const char *outdir, unsigned formats, lv_err *err)
{
    return lv_export_run_report(outdir, formats, NULL, err);
}

LV_API lv_status lv_export_run_report(const char *outdir, unsigned formats, lv_export_report *rep,
                                      lv_err *err)
{
    if (rep != NULL)
        memset(rep, 0, sizeof *rep);
    const unsigned known = (1u << lv_ex_format_count()) - 1u;
    if (formats == LV_EXPORT_ALL)
        formats = known;
    if (outdir == NULL || (formats & ~known) != 0)
        return lv_fail(err, LV_ERR_INPUT, "lv_export_run: %s",
                       outdir == NULL ? "no folder" : "unknown format flag");
    lv_results *res = NULL;
    lv_status st = lv_results_open(outdir, &res, err);
    if (st != LV_OK)
        return st;
    lv_ex_run r;
    memset(&r, 0, sizeof r);
    r.outdir = outdir;
    r.rep = rep;
    r.mission = res->mission;
    r.flat = res->flat;
    r.planet = res->planet;
    r.phases = res->phases;
    r.n_phases = res->n_phases;
    r.res = res;
    st = check_summary(&r, res, err);
    if (st == LV_OK) {
        r.phase_body = malloc((res->n_phases + 1) * sizeof *r.phase_body);
        r.bodies = calloc(res->n_bodies + 1, sizeof *r.bodies);
        if (r.phase_body == NULL || r.bodies == NULL)
            st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    if (st == LV_OK) {
        /* A body flying in a phase gives that phase's event positions: the first one listed. */
        for (size_t i = 0; i < res->n_phases; i++)
            r.phase_body[i] = -1;
        for (size_t i = 0; i < res->n_bodies; i++)
            for (size_t j = 0; j < res->bodies[i].n_phases; j++)
                if (r.phase_body[res->bodies[i].phases[j]] < 0)
                    r.phase_body[res->bodies[i].phases[j]] = (int)i;
    }
    for (size_t i = 0; i < res->n_bodies && st == LV_OK; i++) {
        r.n_bodies = i + 1;
        st = read_body(&r, res, i, err);
    }
    /* Every done phase a body lists must have rows in its CSV. */
    for (size_t i = 0; i < r.n_phases && st == LV_OK; i++) {
        const int b = r.phase_body[i];
        if (r.phases[i].done && b >= 0 && lv_ex_track_of(&r.bodies[b], i) == NULL)
            st = lv_fail(err, LV_ERR_INPUT, "%s: no rows of phase '%s'", r.bodies[b].path,
                         r.phases[i].name);
    }
    for (size_t i = 0; lv_ex_formats[i] != NULL && st == LV_OK; i++)
        if (formats & (1u << i))
            st = lv_ex_formats[i]->write(&r, err);
    if (st == LV_OK && r.time_note[0] != '\0') /* the times written may be off: said once */
        lv_ex_report(&r, "utc", NULL, "%s", r.time_note);
    run_free(&r);
    lv_results_free(res);
    return st;
}
