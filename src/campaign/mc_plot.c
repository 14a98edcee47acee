/* mc_plot.c - the campaign's figures (PLplot, pngcairo): per phase the final ground points
 * over the map with their 3-sigma ellipse, the histogram of a main final value, and the
 * orbit-element scatter (perigee against apogee altitude) with its ellipse. Each figure in its
 * own PLplot stream, ended before the next (PLplot keeps global state: one thread). */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <plplot.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "campaign/mc_data.h"
#include "campaign/mc_plot.h"
#include "core/status.h"
#include "io/atomic.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

typedef void (*mapform_fn)(PLINT n, PLFLT *x, PLFLT *y); /* plmap's transform */

typedef struct fig {
    const char *title, *xl, *yl;
    const double *x, *y; /* points (NaN skipped) */
    size_t n;
    const lv_mc_ell *e;  /* an ellipse in the same coordinates, or NULL */
    double ex0, ey0;     /* the ellipse's offset and scale into plot coordinates */
    double exs, eys;
    int map;             /* coastlines (lon, lat in degrees) */
    int hist;            /* histogram of x */
} fig;

static void range(const double *x, size_t n, double *lo, double *hi)
{
    *lo = INFINITY;
    *hi = -INFINITY;
    for (size_t i = 0; i < n; i++)
        if (isfinite(x[i])) {
            *lo = fmin(*lo, x[i]);
            *hi = fmax(*hi, x[i]);
        }
    if (!(*hi > *lo)) {
        const double c = isfinite(*lo) ? *lo : 0.0;
        *lo = c - 1.0;
        *hi = c + 1.0;
    }
    const double pad = 0.08 * (*hi - *lo);
    *lo -= pad;
    *hi += pad;
}

static lv_status render(const fig *f, const char *path, lv_err *err)
{
    lv_atomic out;
    lv_status st = lv_atomic_init(&out, path, err);
    if (st == LV_OK)
        st = lv_atomic_reserve(&out, err);
    if (st != LV_OK)
        return st;
    PLINT old = 0, strm = -1, code = 0;
    char msg[1024] = "";
    plgstrm(&old);
    plmkstrm(&strm);
    if (strm < 0) {
        lv_atomic_abort(&out);
        return lv_fail(err, LV_ERR_IO, "%s: PLplot has no free stream", path);
    }
    plsError(&code, msg);
    plsdev("pngcairo");
    plsfnam(out.tmp);
    plspage(0.0, 0.0, 900, 650, 0, 0);
    plscolbg(255, 255, 255);
    plscol0(1, 0, 0, 0);
    plscol0(2, 200, 30, 30);
    plscol0(3, 40, 90, 200);
    plscol0(4, 150, 150, 150);
    plinit();
    if (code == 0) {
        pladv(0);
        plvpor(0.12, 0.95, 0.12, 0.9);
        double xlo, xhi, ylo, yhi;
        range(f->x, f->n, &xlo, &xhi);
        if (f->hist) {
            const int nb = f->n > 400 ? 40 : 20;
            double *v = malloc((f->n + 1) * sizeof *v);
            PLINT m = 0;
            for (size_t i = 0; v && i < f->n; i++)
                if (isfinite(f->x[i]))
                    v[m++] = f->x[i];
            /* the tallest bin for the frame */
            double top = 1.0;
            int *cnt = calloc((size_t)nb, sizeof *cnt);
            for (PLINT i = 0; cnt && i < m; i++) {
                int b = (int)((v[i] - xlo) / (xhi - xlo) * nb);
                b = b < 0 ? 0 : b >= nb ? nb - 1 : b;
                cnt[b]++;
                top = fmax(top, cnt[b]);
            }
            plwind(xlo, xhi, 0.0, 1.1 * top);
            plcol0(4);
            plbox("g", 0.0, 0, "g", 0.0, 0);
            plcol0(3);
            if (v && m > 0)
                plhist(m, v, xlo, xhi, nb, PL_HIST_NOSCALING | PL_HIST_IGNORE_OUTLIERS);
            free(v);
            free(cnt);
        } else {
            range(f->y, f->n, &ylo, &yhi);
            if (f->e != NULL) { /* the frame holds the ellipse */
                const double r = 1.08 * fmax(f->e->a, 1e-300); /* and a margin */
                xlo = fmin(xlo, f->ex0 + (f->e->mx - r) * f->exs);
                xhi = fmax(xhi, f->ex0 + (f->e->mx + r) * f->exs);
                ylo = fmin(ylo, f->ey0 + (f->e->my - r) * f->eys);
                yhi = fmax(yhi, f->ey0 + (f->e->my + r) * f->eys);
            }
            plwind(xlo, xhi, ylo, yhi);
            plcol0(4);
            plbox("g", 0.0, 0, "g", 0.0, 0);
            if (f->map) {
                plmap((mapform_fn)NULL, "globe", xlo, xhi, ylo, yhi);
                code = 0; /* no shapefile: the grid only */
                msg[0] = '\0';
            }
            plcol0(3);
            for (size_t i = 0; i < f->n; i++)
                if (isfinite(f->x[i]) && isfinite(f->y[i]))
                    plpoin(1, (PLFLT *)&f->x[i], (PLFLT *)&f->y[i], 1);
            if (f->e != NULL && isfinite(f->e->a)) {
                double ex[97], ey[97];
                for (int i = 0; i <= 96; i++) {
                    const double ph = 2.0 * M_PI * i / 96.0;
                    const double u = f->e->a * cos(ph), w = f->e->b * sin(ph);
                    ex[i] = f->ex0 + (f->e->mx + u * cos(f->e->theta) - w * sin(f->e->theta)) *
                                         f->exs;
                    ey[i] = f->ey0 + (f->e->my + u * sin(f->e->theta) + w * cos(f->e->theta)) *
                                         f->eys;
                }
                plcol0(2);
                plwidth(2.0);
                plline(97, ex, ey);
                plwidth(1.0);
            }
        }
        plcol0(1);
        plbox("bcnst", 0.0, 0, "bcnstv", 0.0, 0);
        pllab(f->xl, f->yl, f->title);
    }
    plend1();
    plsstrm(old);
    struct stat sb;
    if (code != 0) {
        lv_atomic_abort(&out);
        return lv_fail(err, LV_ERR_IO, "%s: PLplot: %s", path, msg);
    }
    if (stat(out.tmp, &sb) != 0 || sb.st_size == 0) {
        lv_atomic_abort(&out);
        return lv_fail(err, LV_ERR_IO, "%s: PLplot wrote nothing (Debian: plplot-driver-cairo)",
                       path);
    }
    return lv_atomic_commit(&out, err);
}

/* The histogram's variable: the first of these a phase has. */
static const char *const hist_vars[] = { "peri_alt", "downrange", "vz", "v_rel", "h", "time",
                                         NULL };

lv_status lv_mc_draw_figures(const lv_mc_data *d, const char *outdir, lv_mc_figs *figs,
                             lv_err *err)
{
    char dir[4200], path[4400];
    snprintf(dir, sizeof dir, "%s/plots", outdir);
    mkdir(dir, 0777);
    memset(figs, 0, sizeof *figs);
    const size_t N = d->n_runs;
    double *x = malloc((N + 1) * sizeof *x), *y = malloc((N + 1) * sizeof *y);
    double *lo = malloc((N + 1) * sizeof *lo), *la = malloc((N + 1) * sizeof *la);
    lv_status st = LV_OK;
    if (!x || !y || !lo || !la) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (size_t k = 0; k < d->n_ph && st == LV_OK; k++) {
        const lv_mc_phase *p = &d->ph[k];
        char title[256], xl[64], yl[64];
        double lat0, lon0;
        /* ground points over the map, with the ellipse (local metres -> degrees about lat0) */
        if (lv_mc_ground_points(d, p, x, y, &lat0, &lon0) >= 3 && figs->n < LV_MC_MAX_FIGS) {
            lv_mc_ell g;
            lv_mc_ellipse(x, y, p->n_rows, 3.0, &g);
            double a, e2;
            lv_mc_planet(d, &a, &e2);
            const double s = sin(lat0), w = sqrt(1.0 - e2 * s * s);
            const double M = a * (1.0 - e2) / (w * w * w), Nr = a / w;
            const size_t cl = lv_mc_col(p, "lat"), cn = lv_mc_col(p, "lon");
            for (size_t i = 0; i < p->n_rows; i++) {
                const int ok = p->state[i] == 1 && isfinite(x[i]);
                la[i] = ok ? p->v[i * p->n_cols + cl] * 180.0 / M_PI : NAN;
                lo[i] = ok ? (lon0 + remainder(p->v[i * p->n_cols + cn] - lon0, 2.0 * M_PI)) *
                                 180.0 / M_PI
                           : NAN;
            }
            snprintf(title, sizeof title, "%s%s%.60s%s: %s points and 3-sigma ellipse (%zu runs)",
                     p->name, p->stages[0] ? " (" : "", p->stages, p->stages[0] ? ")" : "",
                     lv_mc_is_impact(p) ? "impact" : "final ground", g.n);
            const fig f = { title, "longitude [deg]", "latitude [deg]", lo, la, p->n_rows, &g,
                            lon0 * 180.0 / M_PI, lat0 * 180.0 / M_PI,
                            180.0 / M_PI / (Nr * cos(lat0)), 180.0 / M_PI / M, 1, 0 };
            snprintf(figs->stem[figs->n], sizeof figs->stem[0], "mc_%.40s_ground", p->name);
            snprintf(figs->title[figs->n], sizeof figs->title[0], "%s", title);
            snprintf(path, sizeof path, "%s/%s.png", dir, figs->stem[figs->n]);
            if ((st = render(&f, path, err)) == LV_OK)
                figs->n++;
        }
        /* orbit scatter: perigee against apogee altitude, km */
        const size_t cpx = lv_mc_col(p, "peri_alt"), cpy = lv_mc_col(p, "apo_alt");
        if (st == LV_OK && cpx != (size_t)-1 && cpy != (size_t)-1 && !lv_mc_is_impact(p) &&
            figs->n < LV_MC_MAX_FIGS) {
            size_t m = 0;
            for (size_t i = 0; i < p->n_rows; i++) {
                x[i] = p->state[i] == 1 ? p->v[i * p->n_cols + cpx] / 1e3 : NAN;
                y[i] = p->state[i] == 1 ? p->v[i * p->n_cols + cpy] / 1e3 : NAN;
                m += isfinite(x[i]) && isfinite(y[i]);
            }
            if (m >= 3) {
                lv_mc_ell g;
                lv_mc_ellipse(x, y, p->n_rows, 3.0, &g);
                snprintf(title, sizeof title, "%s: orbit at the end, 3-sigma ellipse (%zu runs)",
                         p->name, g.n);
                const fig f = { title, "perigee altitude [km]", "apogee altitude [km]", x, y,
                                p->n_rows, &g, 0.0, 0.0, 1.0, 1.0, 0, 0 };
                snprintf(figs->stem[figs->n], sizeof figs->stem[0], "mc_%.40s_orbit", p->name);
                snprintf(figs->title[figs->n], sizeof figs->title[0], "%s", title);
                snprintf(path, sizeof path, "%s/%s.png", dir, figs->stem[figs->n]);
                if ((st = render(&f, path, err)) == LV_OK)
                    figs->n++;
            }
        }
        /* a histogram */
        for (size_t q = 0; st == LV_OK && hist_vars[q] != NULL && figs->n < LV_MC_MAX_FIGS;
             q++) {
            const size_t c = lv_mc_col(p, hist_vars[q]);
            if (c == (size_t)-1)
                continue;
            size_t m = 0;
            for (size_t i = 0; i < p->n_rows; i++) {
                x[i] = p->state[i] == 1 ? p->v[i * p->n_cols + c] : NAN;
                m += isfinite(x[i]);
            }
            if (m < 3)
                continue;
            lv_mc_stat s;
            lv_mc_summary(x, p->n_rows, &s);
            snprintf(title, sizeof title, "%s: %s at the end, mean %.6g, sd %.4g (%zu runs)",
                     p->name, hist_vars[q], s.mean, s.sd, s.n);
            snprintf(xl, sizeof xl, "%s", hist_vars[q]);
            snprintf(yl, sizeof yl, "runs");
            const fig f = { title, xl, yl, x, NULL, p->n_rows, NULL, 0, 0, 1, 1, 0, 1 };
            snprintf(figs->stem[figs->n], sizeof figs->stem[0], "mc_%.40s_hist_%s", p->name,
                     hist_vars[q]);
            snprintf(figs->title[figs->n], sizeof figs->title[0], "%s", title);
            snprintf(path, sizeof path, "%s/%s.png", dir, figs->stem[figs->n]);
            if ((st = render(&f, path, err)) == LV_OK)
                figs->n++;
            break;
        }
    }
    /* the IIP at given times: the impact points over the map with their ellipse */
    for (size_t q = 0; q < d->n_iip && st == LV_OK && figs->n < LV_MC_MAX_FIGS; q++) {
        const lv_mc_iip *f = &d->iip[q];
        double lat0, lon0;
        if (lv_mc_ground_xy(d, f->n, f->lat, f->lon, x, y, &lat0, &lon0) < 3)
            continue;
        lv_mc_ell g;
        lv_mc_ellipse(x, y, f->n, 3.0, &g);
        double a, e2;
        lv_mc_planet(d, &a, &e2);
        const double s = sin(lat0), w = sqrt(1.0 - e2 * s * s);
        const double M = a * (1.0 - e2) / (w * w * w), Nr = a / w;
        for (size_t i = 0; i < f->n; i++) {
            const int ok = isfinite(x[i]);
            la[i] = ok ? f->lat[i] * 180.0 / M_PI : NAN;
            lo[i] = ok ? (lon0 + remainder(f->lon[i] - lon0, 2.0 * M_PI)) * 180.0 / M_PI : NAN;
        }
        char title[256];
        snprintf(title, sizeof title, "%s: impact points and 3-sigma ellipse (%zu runs)",
                 f->label, g.n);
        const fig fg = { title, "longitude [deg]", "latitude [deg]", lo, la, f->n, &g,
                         lon0 * 180.0 / M_PI, lat0 * 180.0 / M_PI,
                         180.0 / M_PI / (Nr * cos(lat0)), 180.0 / M_PI / M, 1, 0 };
        snprintf(figs->stem[figs->n], sizeof figs->stem[0], "mc_iip_%zu_%.30s", q,
                 f->phase >= 0 && (size_t)f->phase < d->n_ph ? d->ph[f->phase].name : "");
        snprintf(figs->title[figs->n], sizeof figs->title[0], "%s", title);
        snprintf(path, sizeof path, "%s/%s.png", dir, figs->stem[figs->n]);
        if ((st = render(&fg, path, err)) == LV_OK)
            figs->n++;
    }
done:
    free(x);
    free(y);
    free(lo);
    free(la);
    return st;
}
