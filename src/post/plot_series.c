/* plot_series.c - the data behind two figures, computed from a results folder once, before
 * anything is drawn (liblvsim_post; the drawing module only draws them):
 *  - the paper's Figure 10: one speed reference v_max (the largest speed of any body in any
 *    phase) and one mass reference m_0 (the mission's initial mass) for every body, so that
 *    the bodies' curves coincide where they fly together and the mass steps at a separation
 *    show each stage's share of the launch mass; written as plots/fig10_normalised.csv;
 *  - the sites of the ground tracks: the runways of the runway phases and the launch site.
 * docs/visualization.md. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "io/atomic.h"
#include "io/numfmt.h"
#include "lvsim/lv_units.h"
#include "post/plot.h"

static long first_col(const lv_results_table *t, const char *a, const char *b)
{
    long k = lv_results_table_col(t, a);
    return k >= 0 || b == NULL ? k : lv_results_table_col(t, b);
}

static double cell(const lv_results_table *t, size_t r, long c)
{
    return c >= 0 ? t->v[r * t->n_cols + (size_t)c] : NAN;
}

void lv_plot_fig10_refs(lv_plot_data *d)
{
    double v_max = -1.0, m_0 = -1.0;
    for (size_t b = 0; b < d->n_bodies; b++) {
        const lv_plot_body *body = &d->bodies[b];
        int have_m0 = 0;
        for (size_t i = 0; i < body->n; i++) {
            const lv_results_table *t = d->phases[body->phase[i]].csv;
            if (t == NULL)
                continue;
            const long kv = first_col(t, "v_rel", "speed"), km = first_col(t, "m", NULL);
            for (size_t r = 0; r < t->n_rows; r++) {
                const double v = fabs(cell(t, r, kv)), m = cell(t, r, km);
                if (isfinite(v))
                    v_max = fmax(v_max, v);
                if (!have_m0 && isfinite(m)) { /* the body's first mass */
                    m_0 = fmax(m_0, m);
                    have_m0 = 1;
                }
            }
        }
    }
    d->v_max = v_max > 0.0 ? v_max : NAN;
    d->m_0 = m_0 > 0.0 ? m_0 : NAN;
}

/* A CSV field: quoted when it holds a comma, a quote or a line break (RFC 4180). */
static void put_field(FILE *f, const char *s)
{
    if (strpbrk(s, ",\"\r\n") == NULL) {
        fputs(s, f);
        return;
    }
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"')
            fputc('"', f);
        fputc(*s, f);
    }
    fputc('"', f);
}

lv_status lv_plot_fig10_write(const lv_plot_data *d, const char *plotdir, lv_err *err)
{
    if (!(isfinite(d->v_max) && isfinite(d->m_0)))
        return LV_OK;
    char path[4200], a[LV_NUMFMT_MAX], b[LV_NUMFMT_MAX];
    snprintf(path, sizeof path, "%s/fig10_normalised.csv", plotdir);
    lv_atomic out;
    lv_status st = lv_atomic_open(&out, path, err);
    if (st != LV_OK)
        return st;
    FILE *f = out.fp;
    lv_numfmt_double(d->v_max, a);
    lv_numfmt_double(d->m_0, b);
    fprintf(f, "# the paper's Figure 10: v_norm = speed / v_max, m_norm = m / m_0; v_max = %s m/s, "
               "m_0 = %s kg\n", a, b);
    fputs("time [s],body,phase,v_norm,m_norm\n", f);
    for (size_t ib = 0; ib < d->n_bodies; ib++) {
        const lv_plot_body *body = &d->bodies[ib];
        for (size_t i = 0; i < body->n; i++) {
            const lv_plot_phase *ph = &d->phases[body->phase[i]];
            const lv_results_table *t = ph->csv;
            if (t == NULL)
                continue;
            const long kv = first_col(t, "v_rel", "speed"), km = first_col(t, "m", NULL);
            if (kv < 0 && km < 0)
                continue;
            for (size_t r = 0; r < t->n_rows; r++) {
                char num[LV_NUMFMT_MAX];
                lv_numfmt_double(cell(t, r, 0), num);
                fputs(num, f);
                fputc(',', f);
                put_field(f, body->name);
                fputc(',', f);
                put_field(f, ph->name);
                lv_numfmt_double(fabs(cell(t, r, kv)) / d->v_max, num);
                fprintf(f, ",%s", num);
                lv_numfmt_double(cell(t, r, km) / d->m_0, num);
                fprintf(f, ",%s\n", num);
            }
        }
    }
    return lv_atomic_commit(&out, err);
}

/* The runway of a phase that rolls on one (its rows have the distance along the runway and
 * the runway's normal force on the wheels: the runway model's state and output) from its
 * rows, or 0. Along the runway, latitude and longitude are linear in the distance from the
 * threshold to well below a metre over a few km: the threshold is where the line through the
 * first row and the farthest row meets distance 0. */
static int runway_site(const lv_plot_phase *ph, lv_plot_site *s)
{
    const lv_results_table *t = ph->csv;
    if (t == NULL || t->n_rows == 0)
        return 0;
    const long kd = first_col(t, "distance", NULL), klat = first_col(t, "lat", NULL),
               klon = first_col(t, "lon", NULL), khdg = first_col(t, "heading", NULL);
    if (kd < 0 || klat < 0 || klon < 0 || khdg < 0 || first_col(t, "normal_force", NULL) < 0)
        return 0;
    size_t far = 0;
    for (size_t r = 1; r < t->n_rows; r++)
        if (cell(t, r, kd) > cell(t, far, kd))
            far = r;
    const double d0 = cell(t, 0, kd), d1 = cell(t, far, kd);
    const double lat0 = cell(t, 0, klat), lon0 = cell(t, 0, klon);
    double hdg = cell(t, 0, khdg);
    if (!(isfinite(d0) && isfinite(d1) && isfinite(lat0) && isfinite(lon0) && isfinite(hdg)))
        return 0;
    memset(s, 0, sizeof *s);
    s->lat1 = cell(t, far, klat);
    s->lon1 = cell(t, far, klon);
    if (d1 > d0 + 1.0) { /* m: rolled on it */
        const double k = d0 / (d1 - d0);
        s->lat = lat0 - k * (s->lat1 - lat0);
        s->lon = lon0 - k * (s->lon1 - lon0);
        s->length = d1;
    } else if (fabs(d0) < 1.0) { /* never moved, on the threshold */
        s->lat = s->lat1 = lat0;
        s->lon = s->lon1 = lon0;
    } else {
        return 0;
    }
    hdg = fmod(hdg, 2.0 * LV_PI);
    if (hdg < 0.0)
        hdg += 2.0 * LV_PI;
    s->heading = hdg;
    long des = lround(hdg / LV_DEG / 10.0) % 36; /* the runway's designator: heading / 10 deg */
    snprintf(s->label, sizeof s->label, "runway %02ld (%.60s)", des == 0 ? 36 : des, ph->name);
    return 1;
}

void lv_plot_find_sites(lv_plot_data *d)
{
    d->n_sites = 0;
    if (d->flat)
        return;
    for (size_t k = 0; k < d->n_phases && d->n_sites < LV_PLOT_MAX_SITES; k++) {
        lv_plot_site s;
        if (!runway_site(&d->phases[k], &s))
            continue;
        int same = 0; /* one runway, one site: the same threshold and heading */
        for (size_t j = 0; j < d->n_sites && !same; j++) {
            lv_plot_site *o = &d->sites[j];
            same = fabs(o->lat - s.lat) < 1e-6 && fabs(o->lon - s.lon) < 1e-6 &&
                   fabs(remainder(o->heading - s.heading, 2.0 * LV_PI)) < LV_DEG;
            if (same && s.length > o->length) {
                o->length = s.length;
                o->lat1 = s.lat1;
                o->lon1 = s.lon1;
            }
        }
        if (!same)
            d->sites[d->n_sites++] = s;
    }
    /* the launch site: the first row of the earliest phase that has a position */
    double t_first = INFINITY, lat = NAN, lon = NAN;
    for (size_t k = 0; k < d->n_phases; k++) {
        const lv_results_table *t = d->phases[k].csv;
        if (t == NULL || t->n_rows == 0)
            continue;
        const long klat = first_col(t, "lat", NULL), klon = first_col(t, "lon", NULL);
        const double t0 = cell(t, 0, 0);
        if (klat >= 0 && klon >= 0 && t0 < t_first && isfinite(cell(t, 0, klat)) &&
            isfinite(cell(t, 0, klon))) {
            t_first = t0;
            lat = cell(t, 0, klat);
            lon = cell(t, 0, klon);
        }
    }
    if (!isfinite(lat) || d->n_sites >= LV_PLOT_MAX_SITES)
        return;
    for (size_t j = 0; j < d->n_sites; j++) /* 0.01 deg: about 1 km on the Earth */
        if (fabs(d->sites[j].lat - lat) < 0.01 * LV_DEG &&
            fabs(remainder(d->sites[j].lon - lon, 2.0 * LV_PI)) * cos(lat) < 0.01 * LV_DEG)
            return;
    lv_plot_site *s = &d->sites[d->n_sites++];
    memset(s, 0, sizeof *s);
    snprintf(s->label, sizeof s->label, "launch site");
    s->lat = s->lat1 = lat;
    s->lon = s->lon1 = lon;
    s->heading = NAN;
}
