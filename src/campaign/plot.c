/* plot.c - the campaign's report page (lv_campaign_plot): OUTDIR/index.html with the
 * campaign, its dispersions, per phase the end reasons, failures by cause, the ellipses and
 * the statistics of the main final values, and links to every file (stats.json, the CSVs,
 * footprint.kml, campaign.db). Read from the database and stats.json's inputs (stats.c). */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "campaign/mc_data.h"
#include "campaign/mc_plot.h"
#include "core/status.h"
#include "io/atomic.h"
#include "lvsim/lv_campaign.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* "5.15490&deg; N, 43.62727&deg; W" for a geodetic latitude and longitude [rad] (longitude
 * wrapped to [-180, 180] deg), into buf. */
static const char *latlon_html(double lat, double lon, char *buf, size_t cap)
{
    const double la = lat * 180.0 / M_PI, lo = remainder(lon, 2.0 * M_PI) * 180.0 / M_PI;
    snprintf(buf, cap, "%.5f&deg; %s, %.5f&deg; %s", fabs(la), la < 0.0 ? "S" : "N", fabs(lo),
             lo < 0.0 ? "W" : "E");
    return buf;
}

static void esc(FILE *f, const char *s)
{
    for (; *s; s++)
        switch (*s) {
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '&': fputs("&amp;", f); break;
        case '"': fputs("&quot;", f); break;
        default: fputc(*s, f);
        }
}

/* The final values shown on the page (all are in stats.csv). */
static const char *const shown[] = { "time", "h", "v_rel", "v_inertial", "fpa", "lat", "lon",
                                     "downrange", "m", "sma", "ecc", "inc", "apo_alt",
                                     "peri_alt", "x", "y", "z", "vz", NULL };

lv_status lv_campaign_plot(const char *db_path, const char *outdir, lv_err *err)
{
    lv_mc_data *d = NULL;
    lv_status st = lv_mc_data_load(db_path, &d, err);
    if (st != LV_OK)
        return st;
    char path[4200];
    lv_mc_figs figs;
    if ((st = lv_mc_plot_figures(d, outdir, &figs, err)) != LV_OK) {
        lv_mc_data_free(d);
        return st;
    }
    snprintf(path, sizeof path, "%s/index.html", outdir);
    lv_atomic a;
    if ((st = lv_atomic_open(&a, path, err)) != LV_OK) {
        lv_mc_data_free(d);
        return st;
    }
    FILE *f = a.fp;
    const size_t N = d->n_runs;
    double *x = malloc((N + 1) * sizeof *x), *y = malloc((N + 1) * sizeof *y);
    if (x == NULL || y == NULL) {
        free(x);
        free(y);
        lv_atomic_abort(&a);
        lv_mc_data_free(d);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    fputs("<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>", f);
    esc(f, d->mission);
    fputs(": Monte Carlo campaign</title><style>body{font-family:sans-serif;margin:2em}"
          "table{border-collapse:collapse;margin:0.5em 0 1.5em}td,th{border:1px solid #bbb;"
          "padding:2px 8px;text-align:right}th{background:#eee}td:first-child{text-align:left}"
          "</style></head><body>\n<h1>", f);
    esc(f, d->mission);
    fprintf(f, ": Monte Carlo campaign</h1>\n<p>%zu of %zu runs stored, seed %s; %zu with an "
            "input outside its range, %zu with a failed phase, %zu with a phase that fell to "
            "the ground, %zu crashed (a touchdown off the runway or beyond the landing gear's limits, or a roll off the runway's end). Files: <a href=\"stats.json\">stats.json</a>, "
            "<a href=\"stats.csv\">stats.csv</a>, <a href=\"ellipses.csv\">ellipses.csv</a>, "
            "<a href=\"outcomes.csv\">outcomes.csv</a>, <a href=\"sensitivity.csv\">"
            "sensitivity.csv</a>, <a href=\"footprint.kml\">footprint.kml</a> (Google Earth), "
            "<a href=\"campaign.db\">campaign.db</a> (SQLite).</p>\n", d->n_stored, N, d->seed,
            d->n_input_fail, d->n_run_failed, d->n_run_impact, d->n_run_crashed);
    fputs("<h2>Dispersed inputs (as drawn)</h2>\n<table><tr><th>parameter</th><th>unit</th>"
          "<th>n</th><th>mean</th><th>sd</th><th>p1</th><th>p50</th><th>p99</th></tr>\n", f);
    for (size_t j = 0; j < d->n_in; j++) {
        for (size_t r = 0; r < N; r++)
            x[r] = d->run_status[r] ? d->in[r * d->n_in + j] : NAN;
        lv_mc_stat s;
        lv_mc_summary(x, N, &s);
        fputs("<tr><td>", f);
        esc(f, d->in_name[j]);
        fputs("</td><td>", f);
        esc(f, d->in_unit[j]);
        fprintf(f, "</td><td>%zu</td><td>%.6g</td><td>%.4g</td><td>%.6g</td><td>%.6g</td>"
                "<td>%.6g</td></tr>\n", s.n, s.mean, s.sd, s.p1, s.p50, s.p99);
    }
    fputs("</table>\n", f);
    for (size_t k = 0; k < d->n_ph; k++) {
        const lv_mc_phase *p = &d->ph[k];
        size_t nd = 0, nf = 0, ns = 0, ni = 0, nc = 0;
        for (size_t i = 0; i < p->n_rows; i++)
            nd += p->state[i] == 1, nf += p->state[i] == 2, ns += p->state[i] == 3,
                ni += p->state[i] == 4, nc += p->state[i] == 5;
        fputs("<h2>Phase ", f);
        esc(f, p->name);
        fputs("</h2>\n<p>", f);
        if (p->stages[0] != '\0') { /* the bodies: a jettisoned part's fall names its part */
            fputs("Carries ", f);
            esc(f, p->stages);
            fputs(". ", f);
        }
        fprintf(f, "%zu runs: %zu done, %zu fell to the ground (an impact end not "
                "the first written), %zu crashed (a touchdown beyond the landing gear's "
                "limits), %zu failed (%.3g %%), %zu not run.", p->n_rows, nd, ni, nc, nf,
                p->n_rows ? 100.0 * (double)nf / (double)p->n_rows : 0.0, ns);
        /* end reasons and causes, counted in order of first appearance */
        const char *seen[32];
        size_t cnt[32], n_seen = 0;
        for (size_t i = 0; i < p->n_rows; i++) {
            const char *key = p->state[i] == 1   ? p->end[i]
                              : p->state[i] == 4 ? "impact (not the end meant)"
                              : p->state[i] == 5 ? "crashed"
                                                 : lv_mc_cause(p->error[i]);
            size_t q = 0;
            while (q < n_seen && strcmp(seen[q], key) != 0)
                q++;
            if (q == n_seen && n_seen < 32) {
                seen[n_seen] = key;
                cnt[n_seen++] = 0;
            }
            if (q < n_seen)
                cnt[q]++;
        }
        fputs(" Ends and failures:", f);
        for (size_t q = 0; q < n_seen; q++) {
            fprintf(f, "%s ", q ? "," : "");
            esc(f, seen[q]);
            fprintf(f, " %zu", cnt[q]);
        }
        fputs(".</p>\n", f);
        double lat0, lon0;
        if (lv_mc_ground_points(d, p, x, y, &lat0, &lon0) >= 3) {
            lv_mc_ell g;
            lv_mc_ellipse(x, y, p->n_rows, 3.0, &g);
            char ll[64];
            fprintf(f, "<p>%s 3-sigma ellipse (%zu points) about %s: "
                    "semi-axes %.4g m and %.4g m, major axis at azimuth %.1f&deg;; sd east "
                    "%.4g m, north %.4g m, correlation %.3f.</p>\n",
                    lv_mc_is_impact(p) ? "Impact" : "Final ground point", g.n,
                    latlon_html(lat0, lon0, ll, sizeof ll), g.a, g.b,
                    fmod(90.0 - g.theta * 180.0 / M_PI + 360.0, 180.0), g.sx, g.sy, g.rho);
        }
        fputs("<table><tr><th>final value</th><th>n</th><th>mean</th><th>sd</th><th>p1</th>"
              "<th>p50</th><th>p99</th></tr>\n", f);
        for (size_t q = 0; shown[q] != NULL; q++) {
            const size_t c = lv_mc_col(p, shown[q]);
            if (c == (size_t)-1)
                continue;
            for (size_t i = 0; i < p->n_rows; i++)
                x[i] = p->state[i] == 1 ? p->v[i * p->n_cols + c] : NAN;
            lv_mc_stat s;
            lv_mc_summary(x, p->n_rows, &s);
            fprintf(f, "<tr><td>%s</td><td>%zu</td><td>%.8g</td><td>%.4g</td><td>%.8g</td>"
                    "<td>%.8g</td><td>%.8g</td></tr>\n", shown[q], s.n, s.mean, s.sd, s.p1,
                    s.p50, s.p99);
        }
        fputs("</table>\n", f);
    }
    if (d->n_iip > 0)
        fputs("<h2>Instantaneous impact point at given times</h2>\n<p>Per phase and "
              "<code>iip_at:</code> time, where the vehicle would fall if its thrust stopped "
              "then (drag-free, docs/models.md): the runs flying with an impact point, in orbit "
              "(no impact), not flying at that time; the impact points' 3-sigma ellipse.</p>\n"
              "<table><tr><th>footprint</th><th>runs</th><th>impact point</th><th>in orbit"
              "</th><th>not flying</th><th>centre</th><th>semi-axes [m]</th><th>azimuth"
              "</th><th>time of flight [s]</th></tr>\n", f);
    for (size_t q = 0; q < d->n_iip; q++) {
        const lv_mc_iip *fp = &d->iip[q];
        fputs("<tr><td>", f);
        esc(f, fp->label);
        fprintf(f, "</td><td>%zu</td><td>%zu</td><td>%zu</td><td>%zu</td>", fp->n, fp->n_impact,
                fp->n_orbit, fp->n_not_flying);
        double lat0, lon0;
        if (lv_mc_ground_xy(d, fp->n, fp->lat, fp->lon, x, y, &lat0, &lon0) >= 3) {
            lv_mc_ell g;
            lv_mc_ellipse(x, y, fp->n, 3.0, &g);
            lv_mc_stat s;
            lv_mc_summary(fp->tof, fp->n, &s);
            char ll[64];
            fprintf(f, "<td>%s</td><td>%.4g, %.4g</td><td>%.1f&deg;</td>"
                    "<td>%.6g &plusmn; %.3g</td>", latlon_html(lat0, lon0, ll, sizeof ll), g.a, g.b,
                    fmod(90.0 - g.theta * 180.0 / M_PI + 360.0, 180.0), s.mean, s.sd);
        } else {
            fputs("<td>-</td><td>-</td><td>-</td><td>-</td>", f);
        }
        fputs("</tr>\n", f);
    }
    if (d->n_iip > 0)
        fputs("</table>\n", f);
    if (figs.n > 0)
        fputs("<h2>Figures</h2>\n", f);
    for (size_t i = 0; i < figs.n; i++) {
        fprintf(f, "<figure><img src=\"plots/%s.png\" width=\"900\" alt=\"", figs.stem[i]);
        esc(f, figs.title[i]);
        fputs("\"><figcaption>", f);
        esc(f, figs.title[i]);
        fputs("</figcaption></figure>\n", f);
    }
    fputs("<p>Statistics: sample mean and standard deviation (n - 1), percentiles by linear "
          "interpolation (Hyndman &amp; Fan definition 7), ellipses of the 2 x 2 sample "
          "covariance with semi-axes 3 sqrt(eigenvalue); docs/monte-carlo.md.</p>\n"
          "</body></html>\n", f);
    free(x);
    free(y);
    lv_mc_data_free(d);
    return lv_atomic_commit(&a, err);
}
