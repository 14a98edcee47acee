/* mc_geom.c - the campaign's statistics that need no database: columns, summaries,
 * percentiles, 3-sigma ellipses, ground points in a local tangent plane (mc_data.h). Compiled
 * into liblvsim_post and, as hidden copies, into the figures' module lvsim_plot.so, whose
 * campaign figures (mc_plot.c) use them. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "campaign/mc_data.h"
#include "lvsim/lv_planet.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

size_t lv_mc_col(const lv_mc_phase *p, const char *name)
{
    for (size_t c = 0; c < p->n_cols; c++)
        if (strcmp(p->col[c], name) == 0)
            return c;
    return (size_t)-1;
}

/* ---- statistics ----------------------------------------------------------------------------- */

static int cmp_d(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Percentile q (0..100) of sorted x[n]: definition 7 of Hyndman & Fan (numpy's default). */
static double pct(const double *x, size_t n, double q)
{
    if (n == 0)
        return NAN;
    const double h = (double)(n - 1) * q / 100.0;
    const size_t lo = (size_t)floor(h);
    const size_t hi = lo + 1 < n ? lo + 1 : lo;
    return x[lo] + (h - (double)lo) * (x[hi] - x[lo]);
}

void lv_mc_summary(const double *x, size_t n, lv_mc_stat *s)
{
    memset(s, 0, sizeof *s);
    double *y = malloc((n + 1) * sizeof *y);
    size_t m = 0;
    for (size_t i = 0; y && i < n; i++)
        if (isfinite(x[i]))
            y[m++] = x[i];
    s->n = m;
    s->mean = s->sd = s->p1 = s->p50 = s->p99 = s->min = s->max = NAN;
    if (y == NULL || m == 0) {
        free(y);
        return;
    }
    double sum = 0.0;
    for (size_t i = 0; i < m; i++)
        sum += y[i];
    s->mean = sum / (double)m;
    double ss = 0.0;
    for (size_t i = 0; i < m; i++)
        ss += (y[i] - s->mean) * (y[i] - s->mean);
    s->sd = m > 1 ? sqrt(ss / (double)(m - 1)) : 0.0;
    qsort(y, m, sizeof *y, cmp_d);
    s->p1 = pct(y, m, 1.0);
    s->p50 = pct(y, m, 50.0);
    s->p99 = pct(y, m, 99.0);
    s->min = y[0];
    s->max = y[m - 1];
    free(y);
}

double lv_mc_pearson(const double *x, const double *y, size_t n, size_t *used)
{
    double sx = 0, sy = 0;
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (isfinite(x[i]) && isfinite(y[i])) {
            sx += x[i];
            sy += y[i];
            m++;
        }
    if (used)
        *used = m;
    if (m < 3)
        return NAN;
    const double mx = sx / (double)m, my = sy / (double)m;
    double sxx = 0, syy = 0, sxy = 0;
    for (size_t i = 0; i < n; i++)
        if (isfinite(x[i]) && isfinite(y[i])) {
            sxx += (x[i] - mx) * (x[i] - mx);
            syy += (y[i] - my) * (y[i] - my);
            sxy += (x[i] - mx) * (y[i] - my);
        }
    return sxx > 0 && syy > 0 ? sxy / sqrt(sxx * syy) : NAN;
}

/* The 3-sigma ellipse of (x, y) from the sample covariance: principal axes by the
 * eigen-decomposition of [[sxx, sxy], [sxy, syy]]. */
void lv_mc_ellipse(const double *x, const double *y, size_t n, double k, lv_mc_ell *e)
{
    memset(e, 0, sizeof *e);
    double sx = 0, sy = 0;
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (isfinite(x[i]) && isfinite(y[i])) {
            sx += x[i];
            sy += y[i];
            m++;
        }
    e->n = m;
    if (m < 3) {
        e->mx = e->my = NAN;
        return;
    }
    e->mx = sx / (double)m;
    e->my = sy / (double)m;
    double cxx = 0, cyy = 0, cxy = 0;
    for (size_t i = 0; i < n; i++)
        if (isfinite(x[i]) && isfinite(y[i])) {
            cxx += (x[i] - e->mx) * (x[i] - e->mx);
            cyy += (y[i] - e->my) * (y[i] - e->my);
            cxy += (x[i] - e->mx) * (y[i] - e->my);
        }
    cxx /= (double)(m - 1);
    cyy /= (double)(m - 1);
    cxy /= (double)(m - 1);
    const double tr = 0.5 * (cxx + cyy), d = sqrt(0.25 * (cxx - cyy) * (cxx - cyy) + cxy * cxy);
    const double l1 = tr + d, l2 = fmax(tr - d, 0.0);
    e->sx = sqrt(cxx);
    e->sy = sqrt(cyy);
    e->rho = e->sx > 0 && e->sy > 0 ? cxy / (e->sx * e->sy) : 0.0;
    e->a = k * sqrt(l1);
    e->b = k * sqrt(l2);
    e->theta = 0.5 * atan2(2.0 * cxy, cxx - cyy); /* major axis from the x axis, rad */
    e->k = k;
}

/* ---- ground coordinates ---------------------------------------------------------------------- */

void lv_mc_planet(const lv_mc_data *d, double *a, double *e2)
{
    lv_planet p = lv_planet_earth();
    if (d->planet[0] != '\0')
        lv_planet_by_name(d->planet, &p, NULL);
    *a = p.a;
    *e2 = lv_planet_e2(&p);
}

/* Local north/east metres of (lat, lon) about (lat0, lon0): the meridian and prime-vertical
 * radii of curvature at lat0 (a tangent plane: good to ~1e-3 relative over 100 km). */
void lv_mc_ground(const lv_mc_data *d, double lat0, double lon0, double lat, double lon,
                  double *east, double *north)
{
    double a, e2;
    lv_mc_planet(d, &a, &e2);
    const double s = sin(lat0), w = sqrt(1.0 - e2 * s * s);
    const double M = a * (1.0 - e2) / (w * w * w), Nr = a / w;
    double dl = lon - lon0;
    dl = remainder(dl, 2.0 * M_PI);
    *north = (lat - lat0) * M;
    *east = dl * Nr * cos(lat0);
}

void lv_mc_ground_inv(const lv_mc_data *d, double lat0, double lon0, double east, double north,
                      double *lat, double *lon)
{
    double a, e2;
    lv_mc_planet(d, &a, &e2);
    const double s = sin(lat0), w = sqrt(1.0 - e2 * s * s);
    const double M = a * (1.0 - e2) / (w * w * w), Nr = a / w;
    *lat = lat0 + north / M;
    *lon = lon0 + east / (Nr * cos(lat0));
}

/* The phases whose final ground points are a footprint: a planet phase (lat, lon) ending on
 * the ground (end impact or altitude reached falling); the others' points are reported too,
 * as "final ground point". */
int lv_mc_is_impact(const lv_mc_phase *p)
{
    size_t n_imp = 0, n_done = 0;
    for (size_t i = 0; i < p->n_rows; i++)
        if (p->state[i] == 1) {
            n_done++;
            n_imp += strstr(p->end[i], "impact") != NULL || strstr(p->end[i], "landing") != NULL;
        }
    return n_done > 0 && 2 * n_imp >= n_done;
}

size_t lv_mc_ground_xy(const lv_mc_data *d, size_t n, const double *lat, const double *lon,
                       double *east, double *north, double *lat0, double *lon0)
{
    /* the mean point, longitudes unwrapped about the first point */
    double sl = 0, sn = 0, ref = NAN;
    size_t m = 0;
    *lat0 = *lon0 = NAN;
    for (size_t i = 0; i < n; i++) {
        const double la = lat[i], lo = lon[i];
        if (!isfinite(la) || !isfinite(lo))
            continue;
        if (isnan(ref))
            ref = lo;
        sl += la;
        sn += ref + remainder(lo - ref, 2.0 * M_PI);
        m++;
    }
    if (m == 0) {
        for (size_t i = 0; i < n; i++)
            east[i] = north[i] = NAN;
        return 0;
    }
    *lat0 = sl / (double)m;
    *lon0 = sn / (double)m;
    for (size_t i = 0; i < n; i++) {
        const double la = lat[i], lo = lon[i];
        if (!isfinite(la) || !isfinite(lo))
            east[i] = north[i] = NAN;
        else
            lv_mc_ground(d, *lat0, *lon0, la, lo, &east[i], &north[i]);
    }
    return m;
}

/* Every run's ground point (E, N metres about the mean; lat, lon) of phase p; returns the
 * count of done runs with finite points. x/y: [n_rows] (NaN where not done). */
size_t lv_mc_ground_points(const lv_mc_data *d, const lv_mc_phase *p, double *east,
                           double *north, double *lat0, double *lon0)
{
    const size_t cl = lv_mc_col(p, "lat"), cn = lv_mc_col(p, "lon");
    *lat0 = *lon0 = NAN;
    if (cl == (size_t)-1 || cn == (size_t)-1)
        return 0;
    for (size_t i = 0; i < p->n_rows; i++) { /* the done runs' points, in place */
        east[i] = p->state[i] == 1 ? p->v[i * p->n_cols + cl] : NAN;
        north[i] = p->state[i] == 1 ? p->v[i * p->n_cols + cn] : NAN;
    }
    return lv_mc_ground_xy(d, p->n_rows, east, north, east, north, lat0, lon0);
}

/* The orbit-element pairs whose ellipses are reported. */
const char *const lv_mc_orbit_pairs[][2] = {
    { "peri_alt", "apo_alt" }, { "sma", "ecc" }, { "inc", "raan" }, { NULL, NULL } };

