/* stats.c - statistics of a campaign database (lv_campaign_stats): per phase end and final
 * value the sample mean, standard deviation (n - 1) and percentiles 1, 50, 99 (linear
 * interpolation between order statistics, Hyndman & Fan 1996 definition 7); 3-sigma ellipses
 * of ground points and orbit elements from the 2 x 2 sample covariance (principal axes:
 * eigenvectors, semi-axes 3 sqrt(lambda); e.g. Hoover, "Algorithms for Confidence Circles and
 * Ellipses", NOAA Technical Report NOS 107, 1984); end reasons and failures by cause; Pearson's
 * correlation of every dispersed input with every final value. Equations: docs/monte-carlo.md.
 */
#define _POSIX_C_SOURCE 200809L

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <sqlite3.h>

#include "campaign/sqlite_dl.h"
#include "campaign/mc_data.h"
#include "core/status.h"
#include "io/atomic.h"
#include "lvsim/lv_campaign.h"
#include "lvsim/lv_planet.h"
#include "post/json_print.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ---- reading the database ------------------------------------------------------------------ */

static char *dup_s(const char *s)
{
    const size_t n = strlen(s ? s : "") + 1;
    char *d = malloc(n);
    if (d)
        memcpy(d, s ? s : "", n);
    return d;
}

static int meta(sqlite3 *db, const char *key, char *out, size_t cap)
{
    sqlite3_stmt *s = NULL;
    int ok = 0;
    out[0] = '\0';
    if (sqlite3_prepare_v2(db, "SELECT value FROM campaign WHERE key = ?", -1, &s, NULL) ==
        SQLITE_OK) {
        sqlite3_bind_text(s, 1, key, -1, SQLITE_STATIC);
        if (sqlite3_step(s) == SQLITE_ROW) {
            snprintf(out, cap, "%s", (const char *)sqlite3_column_text(s, 0));
            ok = 1;
        }
    }
    sqlite3_finalize(s);
    return ok;
}

void lv_mc_data_free(lv_mc_data *d)
{
    if (d == NULL)
        return;
    for (size_t j = 0; j < d->n_in; j++) {
        free(d->in_name[j]);
        free(d->in_unit[j]);
    }
    free(d->in_name);
    free(d->in_unit);
    free(d->in);
    free(d->run_status);
    for (size_t k = 0; k < d->n_ph; k++) {
        lv_mc_phase *p = &d->ph[k];
        free(p->name);
        free(p->stages);
        for (size_t r = 0; r < p->n_rows; r++) {
            free(p->end[r]);
            free(p->error[r]);
        }
        free(p->end);
        free(p->error);
        free(p->state);
        free(p->row_of);
        free(p->run);
        for (size_t c = 0; c < p->n_cols; c++)
            free(p->col[c]);
        free(p->col);
        free(p->v);
    }
    free(d->ph);
    for (size_t i = 0; i < d->n_iip; i++) {
        lv_mc_iip *q = &d->iip[i];
        free(q->run);
        free(q->state);
        free(q->lat);
        free(q->lon);
        free(q->tof);
        free(q->range);
    }
    free(d->iip);
    free(d);
}

/* The IIP footprints (table iip, schema 3; none in an older database): one per phase and
 * `iip_at:` time, its runs in run order. */
static lv_status load_iip(sqlite3 *db, lv_mc_data *d, const char *db_path, lv_err *err)
{
    sqlite3_stmt *s = NULL, *q = NULL;
    if (sqlite3_prepare_v2(db, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND "
                           "name = 'iip'", -1, &s, NULL) != SQLITE_OK)
        goto sqlfail;
    const int have = sqlite3_step(s) == SQLITE_ROW;
    sqlite3_finalize(s);
    s = NULL;
    if (!have)
        return LV_OK;
    if (sqlite3_prepare_v2(db, "SELECT phase, t, count(*) FROM iip GROUP BY phase, t "
                           "ORDER BY phase, t", -1, &s, NULL) != SQLITE_OK ||
        sqlite3_prepare_v2(db, "SELECT run, state, lat, lon, tof, range FROM iip WHERE "
                           "phase = ? AND t = ? ORDER BY run", -1, &q, NULL) != SQLITE_OK)
        goto sqlfail;
    while (sqlite3_step(s) == SQLITE_ROW) {
        lv_mc_iip *ni = realloc(d->iip, (d->n_iip + 1) * sizeof *ni);
        if (ni == NULL)
            goto nomem;
        d->iip = ni;
        lv_mc_iip *f = &d->iip[d->n_iip++];
        memset(f, 0, sizeof *f);
        f->phase = sqlite3_column_int(s, 0);
        f->t = sqlite3_column_double(s, 1);
        const size_t cap = (size_t)sqlite3_column_int64(s, 2) + 1;
        const char *pn = f->phase >= 0 && (size_t)f->phase < d->n_ph ? d->ph[f->phase].name
                                                                     : "?";
        snprintf(f->label, sizeof f->label, "IIP at T%+.6g s (%.100s)", f->t, pn);
        f->run = malloc(cap * sizeof *f->run);
        f->state = malloc(cap);
        f->lat = malloc(cap * sizeof *f->lat);
        f->lon = malloc(cap * sizeof *f->lon);
        f->tof = malloc(cap * sizeof *f->tof);
        f->range = malloc(cap * sizeof *f->range);
        if (!f->run || !f->state || !f->lat || !f->lon || !f->tof || !f->range)
            goto nomem;
        sqlite3_reset(q);
        sqlite3_bind_int(q, 1, f->phase);
        sqlite3_bind_double(q, 2, f->t);
        while (sqlite3_step(q) == SQLITE_ROW && f->n < cap) {
            const sqlite3_int64 r = sqlite3_column_int64(q, 0);
            if (r < 0 || (size_t)r >= d->n_runs)
                continue;
            const char *stt = (const char *)sqlite3_column_text(q, 1);
            const size_t i = f->n++;
            f->run[i] = (size_t)r;
            f->state[i] = stt && strcmp(stt, "impact") == 0     ? 0
                          : stt && strcmp(stt, "in orbit") == 0 ? 1
                                                                : 2;
            double v4[4];
            for (int j = 0; j < 4; j++)
                v4[j] = f->state[i] == 0 && sqlite3_column_type(q, 2 + j) != SQLITE_NULL
                            ? sqlite3_column_double(q, 2 + j)
                            : NAN;
            f->lat[i] = v4[0];
            f->lon[i] = v4[1];
            f->tof[i] = v4[2];
            f->range[i] = v4[3];
            f->n_impact += f->state[i] == 0;
            f->n_orbit += f->state[i] == 1;
            f->n_not_flying += f->state[i] == 2;
        }
    }
    sqlite3_finalize(s);
    sqlite3_finalize(q);
    return LV_OK;
sqlfail:
    sqlite3_finalize(s);
    sqlite3_finalize(q);
    return lv_fail(err, LV_ERR_INPUT, "%s: %s", db_path, sqlite3_errmsg(db));
nomem:
    sqlite3_finalize(s);
    sqlite3_finalize(q);
    return lv_fail(err, LV_ERR_NOMEM, "out of memory");
}

/* What lv_mc_data_load and the statistics' work arrays hold for N runs of n_in inputs: per
 * run the inputs, a status byte and four doubles; per phase and run the row index, the
 * finals, state, run, end and error (two small strings); NAN when a table cannot be read. */
static double memory_needed(sqlite3 *db, double N, double n_in)
{
    double per_run = 8.0 * n_in + 1.0 + 32.0;
    sqlite3_stmt *s = NULL, *t = NULL;
    if (sqlite3_prepare_v2(db, "SELECT tbl FROM phases", -1, &s, NULL) != SQLITE_OK)
        return NAN;
    while (sqlite3_step(s) == SQLITE_ROW) {
        char sql[256];
        snprintf(sql, sizeof sql, "SELECT * FROM \"%s\"", (const char *)sqlite3_column_text(s, 0));
        if (sqlite3_prepare_v2(db, sql, -1, &t, NULL) != SQLITE_OK) {
            sqlite3_finalize(s);
            return NAN;
        }
        const int nc = sqlite3_column_count(t);
        sqlite3_finalize(t);
        per_run += 8.0 * (nc > 7 ? nc - 7 : 0) + 8.0 + 1.0 + 8.0 + 8.0 + 64.0;
    }
    sqlite3_finalize(s);
    return N * per_run;
}

/* Sets `what` on failure. */
lv_status lv_mc_data_load(const char *db_path, lv_mc_data **out, lv_err *err)
{
    *out = NULL;
    sqlite3 *db = NULL;
    sqlite3_stmt *s = NULL;
    lv_mc_data *d = calloc(1, sizeof *d);
    lv_status st = LV_ERR_NOMEM;
    if (d == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    if (sqlite3_open_v2(db_path, &db, SQLITE_OPEN_READONLY, NULL) != SQLITE_OK) {
        st = lv_fail(err, LV_ERR_IO, "%s: cannot open: %s", db_path,
                     db ? sqlite3_errmsg(db) : lv_sqlite_error() ? lv_sqlite_error() : "?");
        goto fail;
    }
    char v[4096];
    if (!meta(db, "schema", v, sizeof v)) {
        st = lv_fail(err, LV_ERR_INPUT, "%s is not an lvsim campaign database", db_path);
        goto fail;
    }
    meta(db, "mission", d->mission, sizeof d->mission);
    meta(db, "planet", d->planet, sizeof d->planet);
    meta(db, "seed", d->seed, sizeof d->seed);
    meta(db, "n_runs", v, sizeof v);
    d->n_runs = (size_t)strtoull(v, NULL, 10);
    /* inputs */
    if (sqlite3_prepare_v2(db, "SELECT name, unit FROM dispersions ORDER BY j", -1, &s, NULL) !=
        SQLITE_OK)
        goto sqlfail;
    while (sqlite3_step(s) == SQLITE_ROW) {
        char **nn = realloc(d->in_name, (d->n_in + 1) * sizeof *nn);
        if (nn == NULL)
            goto nomem;
        d->in_name = nn;
        char **nu = realloc(d->in_unit, (d->n_in + 1) * sizeof *nu);
        if (nu == NULL)
            goto nomem;
        d->in_unit = nu;
        d->in_name[d->n_in] = dup_s((const char *)sqlite3_column_text(s, 0));
        d->in_unit[d->n_in] = dup_s((const char *)sqlite3_column_text(s, 1));
        d->n_in++;
    }
    sqlite3_finalize(s);
    s = NULL;
    const size_t N = d->n_runs;
    /* every run's values are held at once: refused beyond the machine's memory */
    const double need = memory_needed(db, (double)N, (double)d->n_in);
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    const double have = pages > 0 && page > 0 ? (double)pages * (double)page : INFINITY;
    if (need > have) {
        char n[32], a[32], b[32];
        st = lv_fail(err, LV_ERR_INPUT, "%s: the statistics of its %s runs would need %s of "
                     "memory and this machine has %s: compute them for a smaller campaign",
                     db_path, lv_fmt_count((double)N, n, sizeof n),
                     lv_fmt_bytes(need, a, sizeof a), lv_fmt_bytes(have, b, sizeof b));
        goto fail;
    }
    d->in = malloc((N * d->n_in + 1) * sizeof *d->in);
    d->run_status = calloc(N + 1, 1);
    if (d->in == NULL || d->run_status == NULL)
        goto nomem;
    for (size_t i = 0; i < N * d->n_in; i++)
        d->in[i] = NAN;
    if (sqlite3_prepare_v2(db, "SELECT * FROM runs ORDER BY run", -1, &s, NULL) != SQLITE_OK)
        goto sqlfail;
    while (sqlite3_step(s) == SQLITE_ROW) {
        const sqlite3_int64 r = sqlite3_column_int64(s, 0);
        if (r < 0 || (size_t)r >= N)
            continue;
        const char *stt = (const char *)sqlite3_column_text(s, 1);
        /* "impact" (a phase that ended on the ground) and "crashed" (a touchdown beyond the
         * landing gear's limits): outcomes (store.c), runs done */
        d->run_status[r] = stt == NULL                    ? 0
                           : strcmp(stt, "ok") == 0 || strcmp(stt, "impact") == 0 ||
                                   strcmp(stt, "crashed") == 0 ? 1
                           : strcmp(stt, "failed") == 0     ? 2
                                                            : 3;
        d->n_stored++;
        d->n_input_fail += d->run_status[r] == 3;
        d->n_run_failed += d->run_status[r] == 2;
        d->n_run_impact += stt != NULL && strcmp(stt, "impact") == 0;
        d->n_run_crashed += stt != NULL && strcmp(stt, "crashed") == 0;
        for (size_t j = 0; j < d->n_in; j++)
            d->in[(size_t)r * d->n_in + j] = sqlite3_column_type(s, 3 + (int)j) == SQLITE_NULL
                                                 ? NAN
                                                 : sqlite3_column_double(s, 3 + (int)j);
    }
    sqlite3_finalize(s);
    s = NULL;
    /* phases */
    /* phases.stages since schema 3 */
    if (sqlite3_prepare_v2(db, "SELECT k, name, parent, tbl, stages FROM phases ORDER BY k", -1,
                           &s, NULL) != SQLITE_OK &&
        sqlite3_prepare_v2(db, "SELECT k, name, parent, tbl, '' FROM phases ORDER BY k", -1, &s,
                           NULL) != SQLITE_OK)
        goto sqlfail;
    while (sqlite3_step(s) == SQLITE_ROW) {
        lv_mc_phase *np = realloc(d->ph, (d->n_ph + 1) * sizeof *np);
        if (np == NULL)
            goto nomem;
        d->ph = np;
        lv_mc_phase *p = &d->ph[d->n_ph++];
        memset(p, 0, sizeof *p);
        p->name = dup_s((const char *)sqlite3_column_text(s, 1));
        p->stages = dup_s((const char *)sqlite3_column_text(s, 4));
        if (p->name == NULL || p->stages == NULL)
            goto nomem;
        p->parent = sqlite3_column_int(s, 2);
        snprintf(p->tbl, sizeof p->tbl, "%s", (const char *)sqlite3_column_text(s, 3));
    }
    sqlite3_finalize(s);
    s = NULL;
    for (size_t k = 0; k < d->n_ph; k++) {
        lv_mc_phase *p = &d->ph[k];
        char sql[256];
        snprintf(sql, sizeof sql, "SELECT * FROM \"%s\" ORDER BY run", p->tbl);
        if (sqlite3_prepare_v2(db, sql, -1, &s, NULL) != SQLITE_OK)
            goto sqlfail;
        const int nc = sqlite3_column_count(s);
        /* columns: run, state, end_reason, t_end, steps, rhs_evals, error, finals... */
        p->n_cols = nc > 7 ? (size_t)nc - 7 : 0;
        p->col = calloc(p->n_cols + 1, sizeof *p->col);
        p->row_of = malloc((N + 1) * sizeof *p->row_of);
        if (p->col == NULL || p->row_of == NULL)
            goto nomem;
        for (size_t r = 0; r < N; r++)
            p->row_of[r] = (size_t)-1;
        for (size_t c = 0; c < p->n_cols; c++)
            if ((p->col[c] = dup_s(sqlite3_column_name(s, 7 + (int)c))) == NULL)
                goto nomem;
        size_t cap = 0;
        while (sqlite3_step(s) == SQLITE_ROW) {
            const sqlite3_int64 r = sqlite3_column_int64(s, 0);
            if (r < 0 || (size_t)r >= N)
                continue;
            if (p->n_rows == cap) {
                cap = cap ? 2 * cap : 1024;
                double *nv = realloc(p->v, cap * (p->n_cols + 1) * sizeof *nv);
                char **ne = realloc(p->end, cap * sizeof *ne);
                if (ne)
                    p->end = ne;
                char **nr = realloc(p->error, cap * sizeof *nr);
                if (nr)
                    p->error = nr;
                unsigned char *ns = realloc(p->state, cap);
                if (ns)
                    p->state = ns;
                size_t *nrun = realloc(p->run, cap * sizeof *nrun);
                if (nrun)
                    p->run = nrun;
                if (nv == NULL || ne == NULL || nr == NULL || ns == NULL || nrun == NULL) {
                    if (nv)
                        p->v = nv;
                    goto nomem;
                }
                p->v = nv;
            }
            const size_t i = p->n_rows++;
            const char *stt = (const char *)sqlite3_column_text(s, 1);
            /* 1 done, 2 failed, 3 skipped, 4 impact, 5 crashed (docs/monte-carlo.md) */
            p->state[i] = stt && strcmp(stt, "done") == 0      ? 1
                          : stt && strcmp(stt, "failed") == 0  ? 2
                          : stt && strcmp(stt, "impact") == 0  ? 4
                          : stt && strcmp(stt, "crashed") == 0 ? 5
                                                               : 3;
            p->end[i] = dup_s((const char *)sqlite3_column_text(s, 2));
            p->error[i] = dup_s((const char *)sqlite3_column_text(s, 6));
            p->run[i] = (size_t)r;
            p->row_of[r] = i;
            for (size_t c = 0; c < p->n_cols; c++)
                p->v[i * p->n_cols + c] = sqlite3_column_type(s, 7 + (int)c) == SQLITE_NULL
                                              ? NAN
                                              : sqlite3_column_double(s, 7 + (int)c);
        }
        sqlite3_finalize(s);
        s = NULL;
    }
    if ((st = load_iip(db, d, db_path, err)) != LV_OK)
        goto fail;
    sqlite3_close(db);
    *out = d;
    return LV_OK;
sqlfail:
    st = lv_fail(err, LV_ERR_INPUT, "%s: %s", db_path, sqlite3_errmsg(db));
    goto fail;
nomem:
    st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
fail:
    sqlite3_finalize(s);
    sqlite3_close(db);
    lv_mc_data_free(d);
    return st;
}

/* ---- failures by cause ---------------------------------------------------------------------- */

const char *lv_mc_cause(const char *error)
{
    if (error == NULL || error[0] == '\0')
        return "unknown";
    if (strstr(error, "not run"))
        return "parent failed";
    if (strstr(error, "domain"))
        return "left the model's domain";
    if (strstr(error, "cancel"))
        return "cancelled";
    if (strstr(error, "row limit"))
        return "row limit";
    if (strstr(error, "must be") || strstr(error, "outside") || strstr(error, "invalid"))
        return "input out of range";
    if (strstr(error, "CVODE") || strstr(error, "ARKODE") || strstr(error, "integrat") ||
        strstr(error, "step") || strstr(error, "converge"))
        return "integrator";
    return "other";
}

/* ---- writing ---------------------------------------------------------------------------------- */

static lv_status write_text(const char *path, const char *text, lv_err *err)
{
    lv_atomic a;
    lv_status st = lv_atomic_open(&a, path, err);
    if (st != LV_OK)
        return st;
    fputs(text, a.fp);
    return lv_atomic_commit(&a, err);
}

static cJSON *num(double v) { return isfinite(v) ? cJSON_CreateNumber(v) : cJSON_CreateNull(); }

static void add_stat(cJSON *o, const lv_mc_stat *s)
{
    cJSON_AddNumberToObject(o, "n", (double)s->n);
    cJSON_AddItemToObject(o, "mean", num(s->mean));
    cJSON_AddItemToObject(o, "sd", num(s->sd));
    cJSON_AddItemToObject(o, "p1", num(s->p1));
    cJSON_AddItemToObject(o, "p50", num(s->p50));
    cJSON_AddItemToObject(o, "p99", num(s->p99));
    cJSON_AddItemToObject(o, "min", num(s->min));
    cJSON_AddItemToObject(o, "max", num(s->max));
}

typedef struct sbuf {
    char *p;
    size_t n, cap;
    int nomem;
} sbuf;

static void sb_printf(sbuf *b, const char *fmt, ...) LV_PRINTF(2, 3);
#include <stdarg.h>
static void sb_printf(sbuf *b, const char *fmt, ...)
{
    if (b->nomem)
        return;
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        const int w = vsnprintf(b->p ? b->p + b->n : NULL, b->p ? b->cap - b->n : 0, fmt, ap);
        va_end(ap);
        if (w < 0) {
            b->nomem = 1;
            return;
        }
        if (b->p && b->n + (size_t)w < b->cap) {
            b->n += (size_t)w;
            return;
        }
        size_t cap = b->cap ? b->cap : 65536;
        while (cap <= b->n + (size_t)w)
            cap *= 2;
        char *p = realloc(b->p, cap);
        if (p == NULL) {
            b->nomem = 1;
            return;
        }
        b->p = p;
        b->cap = cap;
    }
}

static void csv_field(sbuf *b, const char *s)
{
    sb_printf(b, "\"");
    for (const char *q = s; *q; q++)
        sb_printf(b, *q == '"' ? "\"\"" : "%c", *q);
    sb_printf(b, "\"");
}

static void kml_ellipse(sbuf *k, const lv_mc_data *d, const char *name, double lat0, double lon0,
                        const lv_mc_ell *e)
{
    sb_printf(k, "<Placemark><name>%s: 3-sigma ellipse</name><styleUrl>#ell</styleUrl>"
              "<LineString><tessellate>1</tessellate><coordinates>\n", name);
    for (int i = 0; i <= 72; i++) {
        const double ph = 2.0 * M_PI * i / 72.0;
        const double u = e->a * cos(ph), w = e->b * sin(ph);
        const double ex = e->mx + u * cos(e->theta) - w * sin(e->theta);
        const double ny = e->my + u * sin(e->theta) + w * cos(e->theta);
        double la, lo;
        lv_mc_ground_inv(d, lat0, lon0, ex, ny, &la, &lo);
        sb_printf(k, "%.8f,%.8f,0\n", remainder(lo, 2.0 * M_PI) * 180.0 / M_PI,
                  la * 180.0 / M_PI);
    }
    sb_printf(k, "</coordinates></LineString></Placemark>\n");
}

/* A footprint on the ground: the points lat[i], lon[i] (rad; non-finite: left out) of the
 * runs run[i], i < n. With 3 points or more: its 3-sigma ellipse as a row of ellipses.csv
 * (kind `csv_kind`), an object of `els` (stats.json, "kind": `json_kind`), and a folder of
 * footprint.kml (the ellipse, at most 5000 points). east, north: [n] work arrays. */
static void ground_footprint(const lv_mc_data *d, const char *name, const char *json_kind,
                             const char *csv_kind, const char *kml_what, size_t n,
                             const double *lat, const double *lon, const size_t *run,
                             double *east, double *north, sbuf *ell, sbuf *kml, cJSON *els)
{
    double lat0, lon0;
    if (lv_mc_ground_xy(d, n, lat, lon, east, north, &lat0, &lon0) < 3)
        return;
    lv_mc_ell g;
    lv_mc_ellipse(east, north, n, 3.0, &g);
    double clat, clon;
    lv_mc_ground_inv(d, lat0, lon0, g.mx, g.my, &clat, &clon);
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "kind", json_kind);
    cJSON_AddStringToObject(o, "frame", "local east (x), north (y) about the mean, m");
    cJSON_AddNumberToObject(o, "n", (double)g.n);
    cJSON_AddItemToObject(o, "centre_lat_deg", num(clat * 180.0 / M_PI));
    cJSON_AddItemToObject(o, "centre_lon_deg", num(remainder(clon, 2.0 * M_PI) * 180.0 / M_PI));
    cJSON_AddItemToObject(o, "sd_east_m", num(g.sx));
    cJSON_AddItemToObject(o, "sd_north_m", num(g.sy));
    cJSON_AddItemToObject(o, "rho", num(g.rho));
    cJSON_AddItemToObject(o, "semi_major_m", num(g.a));
    cJSON_AddItemToObject(o, "semi_minor_m", num(g.b));
    /* azimuth of the major axis: clockwise from north */
    cJSON_AddItemToObject(o, "azimuth_deg",
                          num(fmod(90.0 - g.theta * 180.0 / M_PI + 360.0, 180.0)));
    double la1, lo1, la2, lo2;
    lv_mc_ground_inv(d, lat0, lon0, g.mx, g.my + g.a, &la1, &lo1);
    lv_mc_ground_inv(d, lat0, lon0, g.mx + g.a, g.my, &la2, &lo2);
    cJSON_AddItemToObject(o, "semi_major_dlat_deg", num((la1 - clat) * 180.0 / M_PI));
    cJSON_AddItemToObject(o, "semi_major_dlon_deg", num((lo2 - clon) * 180.0 / M_PI));
    cJSON_AddItemToArray(els, o);
    sb_printf(ell, "\"%s\",%s,east_m,north_m,%zu,%.10g,%.10g,%.10g,%.10g,%.6g,%.10g,"
              "%.10g,%.6g,%.10g,%.10g\n", name, csv_kind, g.n, g.mx, g.my, g.sx, g.sy, g.rho,
              g.a, g.b, fmod(90.0 - g.theta * 180.0 / M_PI + 360.0, 180.0),
              clat * 180.0 / M_PI, remainder(clon, 2.0 * M_PI) * 180.0 / M_PI);
    sb_printf(kml, "<Folder><name>%s (%s, %zu runs)</name>\n", name, kml_what, g.n);
    kml_ellipse(kml, d, name, lat0, lon0, &g);
    size_t shown = 0;
    for (size_t i = 0; i < n && shown < 5000; i++)
        if (isfinite(east[i])) {
            sb_printf(kml, "<Placemark><name>run %zu</name><styleUrl>#pt</styleUrl>"
                      "<Point><coordinates>%.8f,%.8f,0</coordinates></Point>"
                      "</Placemark>\n", run[i], remainder(lon[i], 2.0 * M_PI) * 180.0 / M_PI,
                      lat[i] * 180.0 / M_PI);
            shown++;
        }
    sb_printf(kml, "</Folder>\n");
}

lv_status lv_campaign_stats(const char *db_path, const char *outdir, lv_err *err)
{
    lv_mc_data *d = NULL;
    lv_status st = lv_mc_data_load(db_path, &d, err);
    if (st != LV_OK)
        return st;
    const size_t N = d->n_runs;
    cJSON *root = cJSON_CreateObject();
    sbuf csv = { 0 }, ell = { 0 }, out = { 0 }, sen = { 0 }, kml = { 0 };
    double *e = malloc((N + 1) * sizeof *e), *nn = malloc((N + 1) * sizeof *nn);
    double *x = malloc((N + 1) * sizeof *x), *y = malloc((N + 1) * sizeof *y);
    if (root == NULL || e == NULL || nn == NULL || x == NULL || y == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto done;
    }
    cJSON *camp = cJSON_AddObjectToObject(root, "campaign");
    cJSON_AddStringToObject(camp, "mission", d->mission);
    cJSON_AddStringToObject(camp, "seed", d->seed);
    cJSON_AddNumberToObject(camp, "n_runs", (double)N);
    cJSON_AddNumberToObject(camp, "stored", (double)d->n_stored);
    cJSON_AddNumberToObject(camp, "input_out_of_range", (double)d->n_input_fail);
    /* runs by their outcome (runs.status): a phase failed; fell to the ground; crashed */
    cJSON_AddNumberToObject(camp, "failed", (double)d->n_run_failed);
    cJSON_AddNumberToObject(camp, "impact", (double)d->n_run_impact);
    cJSON_AddNumberToObject(camp, "crashed", (double)d->n_run_crashed);
    sb_printf(&csv, "phase,variable,n,mean,sd,p1,p50,p99,min,max\n");
    sb_printf(&ell, "phase,kind,x,y,n,mean_x,mean_y,sd_x,sd_y,rho,semi_major,semi_minor,"
              "angle_deg,centre_lat_deg,centre_lon_deg\n");
    sb_printf(&out, "phase,outcome,cause,count,fraction\n");
    sb_printf(&sen, "phase,output,input,r,n\n");
    sb_printf(&kml, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
              "<kml xmlns=\"http://www.opengis.net/kml/2.2\"><Document><name>%s: Monte Carlo "
              "footprint</name>\n<Style id=\"ell\"><LineStyle><color>ff0000ff</color><width>2"
              "</width></LineStyle></Style>\n<Style id=\"pt\"><IconStyle><scale>0.4</scale>"
              "<Icon><href>http://maps.google.com/mapfiles/kml/shapes/shaded_dot.png</href>"
              "</Icon></IconStyle></Style>\n", d->mission);
    /* the inputs as drawn */
    cJSON *ins = cJSON_AddArrayToObject(root, "inputs");
    for (size_t j = 0; j < d->n_in; j++) {
        for (size_t r = 0; r < N; r++)
            x[r] = d->run_status[r] ? d->in[r * d->n_in + j] : NAN;
        lv_mc_stat s;
        lv_mc_summary(x, N, &s);
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "name", d->in_name[j]);
        cJSON_AddStringToObject(o, "unit", d->in_unit[j]);
        add_stat(o, &s);
        cJSON_AddItemToArray(ins, o);
        sb_printf(&csv, "inputs,");
        csv_field(&csv, d->in_name[j]);
        sb_printf(&csv, ",%zu,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", s.n, s.mean, s.sd,
                  s.p1, s.p50, s.p99, s.min, s.max);
    }
    cJSON *phs = cJSON_AddArrayToObject(root, "phases");
    for (size_t k = 0; k < d->n_ph; k++) {
        const lv_mc_phase *p = &d->ph[k];
        cJSON *po = cJSON_CreateObject();
        cJSON_AddItemToArray(phs, po);
        cJSON_AddStringToObject(po, "name", p->name);
        cJSON_AddStringToObject(po, "stages", p->stages);
        cJSON_AddStringToObject(po, "from", p->parent >= 0 && (size_t)p->parent < d->n_ph
                                                ? d->ph[p->parent].name : "");
        size_t nd = 0, nf = 0, nsk = 0, nim = 0, ncr = 0;
        for (size_t i = 0; i < p->n_rows; i++)
            nd += p->state[i] == 1, nf += p->state[i] == 2, nsk += p->state[i] == 3,
                nim += p->state[i] == 4, ncr += p->state[i] == 5;
        cJSON_AddNumberToObject(po, "runs", (double)p->n_rows);
        cJSON_AddNumberToObject(po, "done", (double)nd);
        cJSON_AddNumberToObject(po, "impact", (double)nim);
        cJSON_AddNumberToObject(po, "crashed", (double)ncr);
        cJSON_AddNumberToObject(po, "failed", (double)nf);
        cJSON_AddNumberToObject(po, "skipped", (double)nsk);
        cJSON_AddItemToObject(po, "failure_rate",
                              num(p->n_rows ? (double)nf / (double)p->n_rows : NAN));
        /* end reasons and failure causes */
        cJSON *ends = cJSON_AddObjectToObject(po, "ends");
        cJSON *causes = cJSON_AddObjectToObject(po, "failures");
        for (size_t i = 0; i < p->n_rows; i++) {
            if (p->state[i] == 4 || p->state[i] == 5) /* an impact, a crash: counted above,
                                                         neither an end meant nor a failure */
                continue;
            const char *key = p->state[i] == 1 ? p->end[i] : lv_mc_cause(p->error[i]);
            cJSON *tgt = p->state[i] == 1 ? ends : causes;
            cJSON *it = cJSON_GetObjectItemCaseSensitive(tgt, key);
            if (it)
                cJSON_SetNumberValue(it, it->valuedouble + 1);
            else
                cJSON_AddNumberToObject(tgt, key, 1);
        }
        if (nim > 0)
            sb_printf(&out, "\"%s\",impact,\"impact\",%zu,%.6g\n", p->name, nim,
                      (double)nim / (double)p->n_rows);
        if (ncr > 0)
            sb_printf(&out, "\"%s\",crashed,\"crashed\",%zu,%.6g\n", p->name, ncr,
                      (double)ncr / (double)p->n_rows);
        for (int t = 0; t < 2; t++) {
            cJSON *it;
            cJSON *grp = t == 0 ? ends : causes;
            cJSON_ArrayForEach(it, grp) {
                sb_printf(&out, "\"%s\",%s,\"%s\",%.0f,%.6g\n", p->name, t == 0 ? "end" : "failed",
                          it->string, it->valuedouble,
                          p->n_rows ? it->valuedouble / (double)p->n_rows : 0.0);
            }
        }
        /* every final value */
        cJSON *fin = cJSON_AddObjectToObject(po, "finals");
        for (size_t c = 0; c < p->n_cols; c++) {
            for (size_t i = 0; i < p->n_rows; i++)
                x[i] = p->state[i] == 1 ? p->v[i * p->n_cols + c] : NAN;
            lv_mc_stat s;
            lv_mc_summary(x, p->n_rows, &s);
            cJSON *o = cJSON_CreateObject();
            add_stat(o, &s);
            cJSON_AddItemToObject(fin, p->col[c], o);
            sb_printf(&csv, "\"%s\",", p->name);
            csv_field(&csv, p->col[c]);
            sb_printf(&csv, ",%zu,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", s.n, s.mean,
                      s.sd, s.p1, s.p50, s.p99, s.min, s.max);
        }
        /* ellipses: the ground point, then orbit elements */
        cJSON *els = cJSON_AddArrayToObject(po, "ellipses");
        const size_t cl = lv_mc_col(p, "lat"), cn = lv_mc_col(p, "lon");
        if (cl != (size_t)-1 && cn != (size_t)-1) {
            for (size_t i = 0; i < p->n_rows; i++) {
                x[i] = p->state[i] == 1 ? p->v[i * p->n_cols + cl] : NAN;
                y[i] = p->state[i] == 1 ? p->v[i * p->n_cols + cn] : NAN;
            }
            const int impact = lv_mc_is_impact(p);
            char what[1200];
            snprintf(what, sizeof what, "%s of %.1100s",
                     impact ? "impact points" : "final ground points",
                     p->stages[0] ? p->stages : "its bodies");
            ground_footprint(d, p->name, impact ? "impact" : "ground point",
                             impact ? "impact" : "ground", what, p->n_rows, x, y, p->run, e, nn,
                             &ell, &kml, els);
        }
        for (size_t q = 0; lv_mc_orbit_pairs[q][0] != NULL; q++) {
            const size_t cx = lv_mc_col(p, lv_mc_orbit_pairs[q][0]);
            const size_t cy = lv_mc_col(p, lv_mc_orbit_pairs[q][1]);
            if (cx == (size_t)-1 || cy == (size_t)-1 || lv_mc_is_impact(p))
                continue;
            for (size_t i = 0; i < p->n_rows; i++) {
                x[i] = p->state[i] == 1 ? p->v[i * p->n_cols + cx] : NAN;
                y[i] = p->state[i] == 1 ? p->v[i * p->n_cols + cy] : NAN;
            }
            lv_mc_ell g;
            lv_mc_ellipse(x, y, p->n_rows, 3.0, &g);
            if (g.n < 3)
                continue;
            cJSON *o = cJSON_CreateObject();
            cJSON_AddStringToObject(o, "kind", "orbit");
            cJSON_AddStringToObject(o, "x", lv_mc_orbit_pairs[q][0]);
            cJSON_AddStringToObject(o, "y", lv_mc_orbit_pairs[q][1]);
            cJSON_AddNumberToObject(o, "n", (double)g.n);
            cJSON_AddItemToObject(o, "mean_x", num(g.mx));
            cJSON_AddItemToObject(o, "mean_y", num(g.my));
            cJSON_AddItemToObject(o, "sd_x", num(g.sx));
            cJSON_AddItemToObject(o, "sd_y", num(g.sy));
            cJSON_AddItemToObject(o, "rho", num(g.rho));
            cJSON_AddItemToObject(o, "semi_major", num(g.a));
            cJSON_AddItemToObject(o, "semi_minor", num(g.b));
            cJSON_AddItemToObject(o, "angle_deg", num(g.theta * 180.0 / M_PI));
            cJSON_AddItemToArray(els, o);
            sb_printf(&ell, "\"%s\",orbit,%s,%s,%zu,%.10g,%.10g,%.10g,%.10g,%.6g,%.10g,%.10g,"
                      "%.6g,,\n", p->name, lv_mc_orbit_pairs[q][0], lv_mc_orbit_pairs[q][1], g.n,
                      g.mx, g.my, g.sx, g.sy, g.rho, g.a, g.b, g.theta * 180.0 / M_PI);
        }
        /* sensitivity: every input against every final value */
        cJSON *so = cJSON_AddObjectToObject(po, "sensitivity");
        for (size_t c = 0; c < p->n_cols; c++) {
            cJSON *oc = cJSON_AddObjectToObject(so, p->col[c]);
            for (size_t j = 0; j < d->n_in; j++) {
                for (size_t i = 0; i < p->n_rows; i++) {
                    x[i] = p->state[i] == 1 ? d->in[p->run[i] * d->n_in + j] : NAN;
                    y[i] = p->state[i] == 1 ? p->v[i * p->n_cols + c] : NAN;
                }
                size_t used;
                const double r = lv_mc_pearson(x, y, p->n_rows, &used);
                cJSON_AddItemToObject(oc, d->in_name[j], num(r));
                sb_printf(&sen, "\"%s\",", p->name);
                csv_field(&sen, p->col[c]);
                sb_printf(&sen, ",");
                csv_field(&sen, d->in_name[j]);
                sb_printf(&sen, ",%.6g,%zu\n", r, used);
            }
        }
    }
    /* the IIP at given times: per phase and `iip_at:` time, the runs by state, the impact
     * points' ellipse, the time of flight and range */
    cJSON *iips = cJSON_AddArrayToObject(root, "iip");
    for (size_t q = 0; q < d->n_iip; q++) {
        const lv_mc_iip *f = &d->iip[q];
        cJSON *io = cJSON_CreateObject();
        cJSON_AddItemToArray(iips, io);
        cJSON_AddStringToObject(io, "name", f->label);
        cJSON_AddStringToObject(io, "phase", f->phase >= 0 && (size_t)f->phase < d->n_ph
                                                 ? d->ph[f->phase].name : "");
        cJSON_AddNumberToObject(io, "t", f->t);
        cJSON_AddNumberToObject(io, "runs", (double)f->n);
        cJSON_AddNumberToObject(io, "impact", (double)f->n_impact);
        cJSON_AddNumberToObject(io, "in_orbit", (double)f->n_orbit);
        cJSON_AddNumberToObject(io, "not_flying", (double)f->n_not_flying);
        static const char *const st_name[] = { "impact", "in orbit", "not flying" };
        const size_t cnt[3] = { f->n_impact, f->n_orbit, f->n_not_flying };
        for (int j = 0; j < 3; j++)
            if (cnt[j] > 0)
                sb_printf(&out, "\"%s\",iip,\"%s\",%zu,%.6g\n", f->label, st_name[j], cnt[j],
                          f->n ? (double)cnt[j] / (double)f->n : 0.0);
        cJSON *fin = cJSON_AddObjectToObject(io, "values");
        const double *vals[4] = { f->lat, f->lon, f->tof, f->range };
        static const char *const vnames[4] = { "iip_lat", "iip_lon", "iip_tof", "iip_range" };
        for (int j = 0; j < 4; j++) {
            lv_mc_stat s;
            lv_mc_summary(vals[j], f->n, &s);
            cJSON *o = cJSON_CreateObject();
            add_stat(o, &s);
            cJSON_AddItemToObject(fin, vnames[j], o);
            sb_printf(&csv, "\"%s\",%s,%zu,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n",
                      f->label, vnames[j], s.n, s.mean, s.sd, s.p1, s.p50, s.p99, s.min, s.max);
        }
        ground_footprint(d, f->label, "iip", "iip", "instantaneous impact points", f->n, f->lat,
                         f->lon, f->run, e, nn, &ell, &kml,
                         cJSON_AddArrayToObject(io, "ellipses"));
    }
    sb_printf(&kml, "</Document></kml>\n");
    if (csv.nomem || ell.nomem || out.nomem || sen.nomem || kml.nomem) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto done;
    }
    char path[4200];
    char *json = lv_json_print(root);
    if (json == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto done;
    }
    snprintf(path, sizeof path, "%s/stats.json", outdir);
    st = write_text(path, json, err);
    cJSON_free(json);
    static const char *const names[] = { "stats.csv", "ellipses.csv", "outcomes.csv",
                                         "sensitivity.csv", "footprint.kml" };
    const sbuf *bufs[] = { &csv, &ell, &out, &sen, &kml };
    for (int i = 0; i < 5 && st == LV_OK; i++) {
        snprintf(path, sizeof path, "%s/%s", outdir, names[i]);
        st = write_text(path, bufs[i]->p ? bufs[i]->p : "", err);
    }
done:
    cJSON_Delete(root);
    free(csv.p);
    free(ell.p);
    free(out.p);
    free(sen.p);
    free(kml.p);
    free(e);
    free(nn);
    free(x);
    free(y);
    lv_mc_data_free(d);
    return st;
}
