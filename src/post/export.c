/* export.c - trajectory exports from a results folder: reads summary.json (cJSON) and the merged
 * body_<stage>.csv files back, then hands them to the CZML, KML and CCSDS OEM writers
 * (export_czml.c, export_kml.c, export_oem.c). Post-processing only: nothing is rerun.
 * Civil-date arithmetic: H. Hinnant, "chrono-Compatible Low-Level Date Algorithms". */
#define _POSIX_C_SOURCE 200809L

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "core/units.h"
#include "post/export_int.h"
#include "lvsim/lv_export.h"

#define PATH_CAP 4352

/* ------------------------------------------------------------------ time -- */

/* Days since 1970-01-01 of a proleptic Gregorian date. */
static long long days_from_civil(long long y, int m, int d)
{
    y -= m <= 2;
    const long long era = (y >= 0 ? y : y - 399) / 400;
    const long long yoe = y - era * 400;
    const long long doy = (153 * (m > 2 ? m - 3 : m + 9) + 2) / 5 + d - 1;
    const long long doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    return era * 146097 + doe - 719468;
}

static void civil_from_days(long long z, long long *y, int *m, int *d)
{
    z += 719468;
    const long long era = (z >= 0 ? z : z - 146096) / 146097;
    const long long doe = z - era * 146097;
    const long long yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
    const long long doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    const long long mp = (5 * doy + 2) / 153;
    *d = (int)(doy - (153 * mp + 2) / 5 + 1);
    *m = (int)(mp < 10 ? mp + 3 : mp - 9);
    *y = yoe + era * 400 + (*m <= 2);
}

/* "YYYY-MM-DDThh:mm:ss[.f...]Z" (the mission parser's rule) -> microseconds since 1970. */
static int parse_epoch(const char *s, long long *us)
{
    int y, mo, d, h, mi, n = 0;
    if (sscanf(s, "%4d-%2d-%2dT%2d:%2d:%n", &y, &mo, &d, &h, &mi, &n) != 5 || n == 0)
        return -1;
    char *end;
    const double sec = strtod(s + n, &end);
    if (end == s + n || strcmp(end, "Z") != 0 || mo < 1 || mo > 12 || d < 1 || d > 31 ||
        h < 0 || h > 23 || mi < 0 || mi > 59 || !(sec >= 0.0 && sec < 61.0))
        return -1;
    const long long whole = days_from_civil(y, mo, d) * 86400LL + h * 3600LL + mi * 60LL;
    *us = whole * 1000000LL + llround(sec * 1e6);
    return 0;
}

long long lv_ex_ticks(const lv_ex_run *r, double t)
{
    return r->epoch_us + llround(t * 1e6);
}

void lv_ex_iso(const lv_ex_run *r, double t, const char *suffix, char *buf, size_t cap)
{
    const long long us = lv_ex_ticks(r, t);
    long long s = us / 1000000LL, frac = us % 1000000LL;
    if (frac < 0) {
        frac += 1000000LL;
        s -= 1;
    }
    long long days = s / 86400LL, sod = s % 86400LL;
    if (sod < 0) {
        sod += 86400LL;
        days -= 1;
    }
    long long y;
    int mo, d;
    civil_from_days(days, &y, &mo, &d);
    const int h = (int)(sod / 3600), mi = (int)(sod / 60 % 60), sec = (int)(sod % 60);
    if (frac == 0)
        snprintf(buf, cap, "%04lld-%02d-%02dT%02d:%02d:%02d%s", y, mo, d, h, mi, sec, suffix);
    else
        snprintf(buf, cap, "%04lld-%02d-%02dT%02d:%02d:%02d.%06lld%s", y, mo, d, h, mi, sec, frac,
                 suffix);
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
    if (e->name == NULL)
        return "time event";
    if (strcmp(e->name, "burnout") == 0)
        return "MECO"; /* main engine cut-off: the burning stage's propellant is gone */
    if (strcmp(e->name, "impact") == 0)
        return "landing";
    return e->name;
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

static char *dup_str(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d != NULL)
        memcpy(d, s, n);
    return d;
}

static void run_free(lv_ex_run *r)
{
    free(r->mission);
    free(r->planet);
    for (size_t i = 0; i < r->n_phases; i++) {
        free(r->phases[i].name);
        for (size_t j = 0; j < r->phases[i].n_events; j++)
            free(r->phases[i].events[j].name);
        free(r->phases[i].events);
    }
    free(r->phases);
    for (size_t i = 0; i < r->n_bodies; i++) {
        free(r->bodies[i].name);
        free(r->bodies[i].path);
        free(r->bodies[i].rows);
        free(r->bodies[i].tracks);
    }
    free(r->bodies);
}

/* Whole file into a NUL-terminated buffer. */
static lv_status slurp(const char *path, char **out, lv_err *err)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return lv_fail(err, LV_ERR_IO, "%s: cannot read: %s", path, strerror(errno));
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap);
    while (buf != NULL) {
        n += fread(buf + n, 1, cap - n - 1, f);
        if (n < cap - 1)
            break;
        char *nb = realloc(buf, cap * 2);
        if (nb == NULL) {
            free(buf);
            buf = NULL;
            break;
        }
        buf = nb;
        cap *= 2;
    }
    const int bad = ferror(f);
    fclose(f);
    if (buf == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", path);
    if (bad) {
        free(buf);
        return lv_fail(err, LV_ERR_IO, "%s: read error", path);
    }
    buf[n] = '\0';
    *out = buf;
    return LV_OK;
}

/* -------------------------------------------------------------- summary -- */

static const char *json_str(const cJSON *o, const char *key)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    return cJSON_IsString(v) ? v->valuestring : NULL;
}

static int json_num(const cJSON *o, const char *key, double *x)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble))
        return -1;
    *x = v->valuedouble;
    return 0;
}

static int phase_find(const lv_ex_run *r, const char *name)
{
    for (size_t i = 0; i < r->n_phases; i++)
        if (strcmp(r->phases[i].name, name) == 0)
            return (int)i;
    return -1;
}

static lv_status read_phase(lv_ex_run *r, const char *path, const cJSON *pj, size_t i,
                            lv_err *err)
{
    lv_ex_phase *p = &r->phases[i];
    const char *name = json_str(pj, "name"), *state = json_str(pj, "state");
    double index;
    p->parent = -1;
    p->body = -1;
    if (name == NULL || state == NULL || json_num(pj, "index", &index) != 0)
        return lv_fail(err, LV_ERR_INPUT, "%s: phases[%zu]: 'name', 'index' or 'state' missing",
                       path, i);
    if ((p->name = dup_str(name)) == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    if (!(index >= 1.0 && index <= 1e6))
        return lv_fail(err, LV_ERR_INPUT, "%s: phase '%s': index %g out of range", path, name,
                       index);
    p->index = (int)index;
    p->done = strcmp(state, "done") == 0;
    if (!p->done)
        return LV_OK;
    if (json_num(pj, "t_start", &p->t_start) != 0 || json_num(pj, "t_end", &p->t_end) != 0 ||
        p->t_end < p->t_start)
        return lv_fail(err, LV_ERR_INPUT, "%s: phase '%s': 't_start'/'t_end' missing or wrong",
                       path, name);
    const cJSON *ev = cJSON_GetObjectItemCaseSensitive(pj, "events");
    const int n = cJSON_IsArray(ev) ? cJSON_GetArraySize(ev) : 0;
    if (n > 0 && (p->events = calloc((size_t)n, sizeof *p->events)) == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    for (int j = 0; j < n; j++) {
        const cJSON *e = cJSON_GetArrayItem(ev, j);
        lv_ex_event *x = &p->events[p->n_events++];
        if (json_num(e, "t", &x->t) != 0)
            return lv_fail(err, LV_ERR_INPUT, "%s: phase '%s': events[%d]: 't' missing", path,
                           name, j);
        const char *en = json_str(e, "name");
        if (en != NULL && (x->name = dup_str(en)) == NULL)
            return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    return LV_OK;
}

static lv_status read_summary(lv_ex_run *r, lv_err *err)
{
    char path[PATH_CAP];
    snprintf(path, sizeof path, "%s/summary.json", r->outdir);
    char *text = NULL;
    lv_status st = slurp(path, &text, err);
    if (st != LV_OK)
        return st;
    const char *end = NULL;
    cJSON *root = cJSON_ParseWithOpts(text, &end, 0);
    if (root == NULL) {
        int line = 1;
        for (const char *c = text; end != NULL && c < end && *c; c++)
            line += *c == '\n';
        free(text);
        return lv_fail(err, LV_ERR_INPUT, "%s:%d: malformed JSON", path, line);
    }
    free(text);
    const char *mission = json_str(root, "mission"), *epoch = json_str(root, "epoch");
    const char *world = json_str(root, "world"), *planet = json_str(root, "planet");
    const cJSON *phases = cJSON_GetObjectItemCaseSensitive(root, "phases");
    const cJSON *bodies = cJSON_GetObjectItemCaseSensitive(root, "bodies");
    if (mission == NULL || epoch == NULL || world == NULL || !cJSON_IsArray(phases) ||
        !cJSON_IsArray(bodies)) {
        st = lv_fail(err, LV_ERR_INPUT,
                     "%s: not an lvsim summary: 'mission', 'epoch', 'world', 'phases' or "
                     "'bodies' missing", path);
        goto fail;
    }
    if (parse_epoch(epoch, &r->epoch_us) != 0) {
        st = lv_fail(err, LV_ERR_INPUT, "%s: epoch '%.40s': ISO 8601 UTC time like "
                     "2026-03-01T12:00:00Z expected", path, epoch);
        goto fail;
    }
    r->flat = strcmp(world, "flat") == 0;
    if ((r->mission = dup_str(mission)) == NULL ||
        (planet != NULL && (r->planet = dup_str(planet)) == NULL))
        goto nomem;

    const size_t np = (size_t)cJSON_GetArraySize(phases);
    if (np == 0 || (r->phases = calloc(np, sizeof *r->phases)) == NULL) {
        st = np == 0 ? lv_fail(err, LV_ERR_INPUT, "%s: no phases", path) : LV_ERR_NOMEM;
        if (st == LV_ERR_NOMEM)
            goto nomem;
        goto fail;
    }
    for (size_t i = 0; i < np; i++) {
        r->n_phases = i + 1;
        if ((st = read_phase(r, path, cJSON_GetArrayItem(phases, (int)i), i, err)) != LV_OK)
            goto fail;
    }
    r->t0 = INFINITY;
    r->t1 = -INFINITY;
    for (size_t i = 0; i < np; i++) {
        const cJSON *pj = cJSON_GetArrayItem(phases, (int)i);
        const char *from = json_str(pj, "from");
        r->phases[i].parent = from != NULL ? phase_find(r, from) : -1;
        r->phases[i].n_stages = (size_t)cJSON_GetArraySize(cJSON_GetObjectItem(pj, "stages"));
        if (r->phases[i].done) {
            r->t0 = fmin(r->t0, r->phases[i].t_start);
            r->t1 = fmax(r->t1, r->phases[i].t_end);
        }
    }
    if (!(r->t0 <= r->t1)) {
        st = lv_fail(err, LV_ERR_INPUT, "%s: no phase is done: nothing to export", path);
        goto fail;
    }

    const size_t nb = (size_t)cJSON_GetArraySize(bodies);
    if (nb > 0 && (r->bodies = calloc(nb, sizeof *r->bodies)) == NULL)
        goto nomem;
    for (size_t i = 0; i < nb; i++) {
        const cJSON *bj = cJSON_GetArrayItem(bodies, (int)i);
        const char *name = json_str(bj, "name"), *file = json_str(bj, "trajectory");
        lv_ex_body *b = &r->bodies[r->n_bodies++];
        if (name == NULL || file == NULL || strchr(file, '/') != NULL) {
            st = lv_fail(err, LV_ERR_INPUT, "%s: bodies[%zu]: 'name' or 'trajectory' (a file "
                         "name in the folder) missing", path, i);
            goto fail;
        }
        char bp[PATH_CAP];
        snprintf(bp, sizeof bp, "%s/%s", r->outdir, file);
        if ((b->name = dup_str(name)) == NULL || (b->path = dup_str(bp)) == NULL)
            goto nomem;
        /* A body flying in a phase gives that phase's event positions. */
        const cJSON *pl = cJSON_GetObjectItemCaseSensitive(bj, "phases");
        for (int j = 0; cJSON_IsArray(pl) && j < cJSON_GetArraySize(pl); j++) {
            const cJSON *pn = cJSON_GetArrayItem(pl, j);
            const int k = cJSON_IsString(pn) ? phase_find(r, pn->valuestring) : -1;
            if (k < 0) {
                st = lv_fail(err, LV_ERR_INPUT, "%s: body '%s': phases[%d] is not a phase",
                             path, name, j);
                goto fail;
            }
            if (r->phases[k].body < 0)
                r->phases[k].body = (int)i;
        }
    }
    cJSON_Delete(root);
    return LV_OK;
nomem:
    st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
fail:
    cJSON_Delete(root);
    return st;
}

/* ------------------------------------------------------------- body CSV -- */

/* Splits one CSV line in place (RFC 4180 quoting). Returns the field count, -1 on an
 * unterminated quote, or max + 1 when there are more than max fields. */
static int split_csv(char *s, char **fields, int max)
{
    int n = 0;
    for (;;) {
        if (n == max)
            return max + 1;
        char *out = s;
        fields[n++] = s;
        if (*s == '"') {
            char *in = s + 1;
            for (;;) {
                if (*in == '\0')
                    return -1;
                if (*in == '"' && in[1] == '"') {
                    *out++ = '"';
                    in += 2;
                } else if (*in == '"') {
                    in++;
                    break;
                } else {
                    *out++ = *in++;
                }
            }
            if (*in != ',' && *in != '\0')
                return -1;
            const char c = *in;
            *out = '\0';
            if (c == '\0')
                return n;
            s = in + 1;
        } else {
            while (*s != ',' && *s != '\0')
                s++;
            if (*s == '\0')
                return n;
            *s++ = '\0';
        }
    }
}

enum { C_TIME, C_PHASE, C_LAT, C_LON, C_H, C_RX, C_RY, C_RZ, C_VX, C_VY, C_VZ, C_N };
static const char *const col_names[C_N] = {"time", "phase", "lat", "lon", "h", "r_eci_x",
                                           "r_eci_y", "r_eci_z", "v_eci_x", "v_eci_y",
                                           "v_eci_z"};

/* Column name without its " [unit]". */
static int col_is(const char *field, const char *name)
{
    const size_t n = strlen(name);
    return strncmp(field, name, n) == 0 && (field[n] == '\0' || field[n] == ' ');
}

static int parse_num(const char *s, double *x)
{
    char *end;
    errno = 0;
    *x = strtod(s, &end);
    return end != s && *end == '\0' && isfinite(*x) ? 0 : -1;
}

#define MAX_COLS 64

static lv_status read_body(lv_ex_run *r, lv_ex_body *b, lv_err *err)
{
    FILE *f = fopen(b->path, "r");
    if (f == NULL)
        return lv_fail(err, LV_ERR_IO, "%s: cannot read: %s", b->path, strerror(errno));
    char *line = NULL, *fields[MAX_COLS + 1];
    size_t cap = 0, lineno = 0, rows_cap = 0, tracks_cap = 0;
    int col[C_N], n_cols = 0, cur = -1; /* cur: phase of the current track */
    lv_status st = LV_OK;
    for (int c = 0; c < C_N; c++)
        col[c] = -1;
    while (getline(&line, &cap, f) >= 0) {
        lineno++;
        size_t len = strlen(line);
        while (len > 0 && (line[len - 1] == '\n' || line[len - 1] == '\r'))
            line[--len] = '\0';
        if (len == 0 || line[0] == '#')
            continue;
        const int n = split_csv(line, fields, MAX_COLS);
        if (n < 0 || n > MAX_COLS) {
            st = lv_fail(err, LV_ERR_INPUT, "%s:%zu: %s", b->path, lineno,
                         n < 0 ? "unterminated quote" : "too many columns");
            goto fail;
        }
        if (n_cols == 0) { /* the header */
            n_cols = n;
            for (int i = 0; i < n; i++)
                for (int c = 0; c < C_N; c++)
                    if (col[c] < 0 && col_is(fields[i], col_names[c]))
                        col[c] = i;
            for (int c = 0; c <= C_H; c++)
                if (col[c] < 0) {
                    st = lv_fail(err, LV_ERR_INPUT, "%s:%zu: no column '%s' in the header",
                                 b->path, lineno, col_names[c]);
                    goto fail;
                }
            b->has_eci = 1;
            for (int c = C_RX; c < C_N; c++)
                b->has_eci &= col[c] >= 0;
            continue;
        }
        if (n != n_cols) {
            st = lv_fail(err, LV_ERR_INPUT, "%s:%zu: %d fields, the header has %d", b->path,
                         lineno, n, n_cols);
            goto fail;
        }
        lv_ex_row row;
        memset(&row, 0, sizeof row);
        row.line = lineno;
        double *dst[C_N] = {&row.t,        NULL,         &row.lat,     &row.lon,
                            &row.h,        &row.r_eci[0], &row.r_eci[1], &row.r_eci[2],
                            &row.v_eci[0], &row.v_eci[1], &row.v_eci[2]};
        for (int c = 0; c < C_N; c++) {
            if (dst[c] == NULL || col[c] < 0)
                continue;
            if (parse_num(fields[col[c]], dst[c]) != 0) {
                st = lv_fail(err, LV_ERR_INPUT, "%s:%zu: column '%s': '%.40s' is not a finite "
                             "number", b->path, lineno, col_names[c], fields[col[c]]);
                goto fail;
            }
        }
        const int k = phase_find(r, fields[col[C_PHASE]]);
        if (k < 0 || !r->phases[k].done) {
            st = lv_fail(err, LV_ERR_INPUT, "%s:%zu: phase '%.60s' is not a done phase of "
                         "summary.json", b->path, lineno, fields[col[C_PHASE]]);
            goto fail;
        }
        if (k != cur) { /* a new track */
            if (lv_ex_track_of(b, (size_t)k) != NULL) {
                st = lv_fail(err, LV_ERR_INPUT, "%s:%zu: phase '%s' appears twice, not in one "
                             "block", b->path, lineno, r->phases[k].name);
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
                             "%.17g)", b->path, lineno, row.t, t_prev);
                goto fail;
            }
            if (row.t == t_prev) { /* an event instant: keep the row after it */
                b->rows[b->n_rows - 1] = row;
                continue;
            }
        }
        if (b->n_rows == rows_cap) {
            rows_cap = rows_cap ? 2 * rows_cap : 1024;
            lv_ex_row *nr = realloc(b->rows, rows_cap * sizeof *nr);
            if (nr == NULL)
                goto nomem;
            b->rows = nr;
        }
        b->rows[b->n_rows++] = row;
        tr->n++;
    }
    if (ferror(f)) {
        st = lv_fail(err, LV_ERR_IO, "%s: read error", b->path);
        goto fail;
    }
    if (n_cols == 0 || b->n_rows == 0) {
        st = lv_fail(err, LV_ERR_INPUT, "%s:%zu: no %s", b->path, lineno,
                     n_cols == 0 ? "header" : "rows");
        goto fail;
    }
    free(line);
    fclose(f);
    return LV_OK;
nomem:
    st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
fail:
    free(line);
    fclose(f);
    return st;
}

/* ------------------------------------------------------------------- run -- */

LV_API lv_status lv_export_run(const char *outdir, unsigned formats, lv_err *err)
{
    if (outdir == NULL || (formats & ~(unsigned)LV_EXPORT_ALL) != 0)
        return lv_fail(err, LV_ERR_INPUT, "lv_export_run: %s",
                       outdir == NULL ? "no folder" : "unknown format flag");
    lv_ex_run r;
    memset(&r, 0, sizeof r);
    r.outdir = outdir;
    lv_status st = read_summary(&r, err);
    for (size_t i = 0; i < r.n_bodies && st == LV_OK; i++)
        st = read_body(&r, &r.bodies[i], err);
    /* Every done phase a body lists must have rows in its CSV. */
    for (size_t i = 0; i < r.n_phases && st == LV_OK; i++) {
        const int b = r.phases[i].body;
        if (r.phases[i].done && b >= 0 && lv_ex_track_of(&r.bodies[b], i) == NULL)
            st = lv_fail(err, LV_ERR_INPUT, "%s: no rows of phase '%s'", r.bodies[b].path,
                         r.phases[i].name);
    }
    char path[PATH_CAP];
    if (st == LV_OK && (formats & LV_EXPORT_CZML)) {
        snprintf(path, sizeof path, "%s/mission.czml", outdir);
        st = lv_ex_write_czml(&r, path, err);
    }
    if (st == LV_OK && (formats & LV_EXPORT_KML)) {
        snprintf(path, sizeof path, "%s/mission.kml", outdir);
        st = lv_ex_write_kml(&r, path, err);
    }
    if (st == LV_OK && (formats & LV_EXPORT_OEM) && !r.flat)
        st = lv_ex_write_oem(&r, err);
    run_free(&r);
    return st;
}
