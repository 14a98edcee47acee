/* turbulence.c - wind disturbances over altitude (lv_wind.h, docs/wind.md "Gusts and
 * turbulence"): discrete 1-cosine gusts (MIL-F-8785C sec. 3.7.4) and a realisation of Dryden
 * continuous turbulence (MIL-F-8785C sec. 3.7.2), frozen over altitude.
 *
 * The realisation. The Dryden spectra are those of linear filters driven by white noise; a
 * sampled path of such a process is drawn exactly (not by integrating the filter with a
 * numerical method) from its state-space form x' = A x + B w by
 *     x_{k+1} = Phi x_k + G n_k,  Phi = exp(A Delta),  G G^T = Q = P - Phi P Phi^T,
 * with P the stationary covariance (A P + P A^T + B B^T = 0) and n_k independent standard
 * normals (the discrete-time equivalent of a continuous Gauss-Markov process: e.g. Gelb,
 * *Applied Optimal Estimation*, MIT Press 1974, sec. 4.2; P - Phi P Phi^T is Q_d of a
 * stationary process). The first state is drawn from P itself, so the path is stationary from
 * its first sample. In the scaled coordinate s = h / L:
 *   - longitudinal (the vertical component; Phi_long = sigma^2 (2L/pi)/(1 + (L Omega)^2)):
 *     x' = -x + w, P = 1/2: x_{k+1} = e^{-D} x_k + sqrt((1 - e^{-2D})/2) n_k, y = sqrt(2) x;
 *   - lateral (north, east; Phi_lat = sigma^2 (L/pi)(1 + 3 (L Omega)^2)/(1 + (L Omega)^2)^2,
 *     the filter (1 + sqrt(3) L s)/(1 + L s)^2): x1' = -x1 + x2, x2' = -x2 + w,
 *     y = (1 - sqrt(3)) x1 + sqrt(3) x2, P = [[1/4, 1/4], [1/4, 1/2]], var(y) = 1,
 *     Phi = e^{-D} [[1, D], [0, 1]];
 * both then scaled by sigma. D = Delta / L = 1/20: the samples resolve wavelengths down to
 * L / 10, well past the scales a launch vehicle's rigid-body and control modes respond to. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/random.h"
#include "core/status.h"
#include "lvsim/lv_dispersion.h"
#include "lvsim/lv_units.h"
#include "lvsim/lv_wind.h"

#define SAMPLES_PER_L 20
#define SAMPLES_MAX ((size_t)1 << 22)

struct lv_wind_disturbance {
    size_t n_gusts;
    lv_gust_1cos gust[LV_GUSTS_MAX];
    int turbulent;
    lv_dryden_spec spec;
    double h0, dh, inv_dh;  /* m: altitude of sample 0 (h_from - dh), spacing; 1/dh */
    double fade;            /* m: the fade length at each end of the layer */
    size_t n;               /* samples per component (sample k at h0 + k dh) */
    double *s;              /* [n][3] north, east, down: the realisation, m/s */
    double *m2;             /* [n][3] the interpolating cubic spline's second differences */
};

void lv_wind_disturbance_free(lv_wind_disturbance *d)
{
    if (d == NULL)
        return;
    free(d->s);
    free(d->m2);
    free(d);
}

/* The realisation, sample by sample: five normals per sample (two per lateral component, one
 * for the vertical), from three generator calls. */
static void realise(lv_wind_disturbance *d, uint64_t seed, uint64_t run)
{
    const double D = 1.0 / SAMPLES_PER_L, E = exp(-D);
    /* longitudinal: AR(1) with the stationary variance 1/2 */
    const double g_long = sqrt(0.5 * (1.0 - E * E));
    /* lateral: Q = P - Phi P Phi^T with P = [[1/4, 1/4], [1/4, 1/2]] and its Cholesky factor */
    const double p11 = 0.25, p12 = 0.25, p22 = 0.5, E2 = E * E;
    const double q11 = p11 - E2 * (p11 + 2.0 * D * p12 + D * D * p22);
    const double q12 = p12 - E2 * (p12 + D * p22);
    const double q22 = p22 * (1.0 - E2);
    const double l11 = sqrt(q11), l21 = q12 / l11, l22 = sqrt(q22 - l21 * l21);
    const double c1 = 1.0 - sqrt(3.0), c2 = sqrt(3.0);
    const double sig[3] = { d->spec.sigma_h, d->spec.sigma_h, d->spec.sigma_v };
    const uint64_t stream = lv_disp_stream("environment.turbulence");
    double x1[2], x2[2], xv, z[6];
    for (size_t k = 0; k < d->n; k++) {
        for (int j = 0; j < 3; j++) /* counter (run, stream + 3k + j) */
            lv_rand_normal2(seed, run, stream + 3 * (uint64_t)k + (uint64_t)j, z + 2 * j);
        if (k == 0) { /* from the stationary distribution: x ~ N(0, P) */
            for (int c = 0; c < 2; c++) {
                x1[c] = 0.5 * z[2 * c];                                     /* sqrt(p11) */
                x2[c] = 0.5 * z[2 * c] + 0.5 * z[2 * c + 1];                /* chol(P) */
            }
            xv = sqrt(0.5) * z[4];
        } else {
            for (int c = 0; c < 2; c++) {
                const double a = E * (x1[c] + D * x2[c]), b = E * x2[c];
                x1[c] = a + l11 * z[2 * c];
                x2[c] = b + l21 * z[2 * c] + l22 * z[2 * c + 1];
            }
            xv = E * xv + g_long * z[4];
        }
        double *s = d->s + 3 * k;
        for (int c = 0; c < 2; c++)
            s[c] = sig[c] * (c1 * x1[c] + c2 * x2[c]);
        s[2] = sig[2] * sqrt(2.0) * xv;
    }
}

/* The natural cubic spline through the samples (unit spacing in the index): second
 * differences M with M[k-1] + 4 M[k] + M[k+1] = 6 (s[k+1] - 2 s[k] + s[k-1]), M = 0 at both
 * ends, by the Thomas algorithm (de Boor, *A practical guide to splines*, ch. IV). C2 between
 * the samples: an integrator meets no jump of the wind's second derivative at every sample (a
 * C1 Catmull-Rom cubic took 20-30 % more steps: 1059 against 842 in kourou-leo's ascent). */
static void spline(lv_wind_disturbance *d)
{
    /* the constant tridiagonal's eliminated super-diagonal c_k = 1 / (4 - c_{k-1}), c_0 = 0:
     * it reaches its limit 2 - sqrt(3) to the last bit well before k = 64 */
    double cp[64];
    cp[0] = 0.0;
    for (int k = 1; k < 64; k++)
        cp[k] = 1.0 / (4.0 - cp[k - 1]);
    const size_t n = d->n;
    double *m = d->m2;
    const double *s = d->s;
    for (int c = 0; c < 3; c++) {
        m[c] = m[3 * (n - 1) + c] = 0.0;
        for (size_t k = 1; k + 1 < n; k++) { /* forward: m holds d_k */
            const double r = 6.0 * (s[3 * (k + 1) + c] - 2.0 * s[3 * k + c] + s[3 * (k - 1) + c]);
            m[3 * k + c] = (r - m[3 * (k - 1) + c]) * (k < 64 ? cp[k] : cp[63]);
        }
        for (size_t k = n - 2; k >= 1; k--) /* back: M_k = d_k - c_k M_{k+1} */
            m[3 * k + c] -= (k < 64 ? cp[k] : cp[63]) * m[3 * (k + 1) + c];
    }
}

/* The samples a layer needs (0 without turbulence), or the reason it cannot be drawn. */
static lv_status check_spec(const lv_dryden_spec *turb, const lv_gust_1cos *gusts,
                            size_t n_gusts, size_t *n_samples, lv_err *err)
{
    if (n_gusts > 0 && gusts == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_wind_disturbance: NULL gusts");
    if (n_gusts > LV_GUSTS_MAX)
        return lv_fail(err, LV_ERR_INPUT, "wind: %zu gusts; at most %d", n_gusts, LV_GUSTS_MAX);
    for (size_t i = 0; i < n_gusts; i++) {
        const lv_gust_1cos *g = &gusts[i];
        if (!isfinite(g->altitude) || !(g->half_width > 0.0 && g->half_width <= 1e6))
            return lv_fail(err, LV_ERR_INPUT, "wind: gust %zu: altitude %.9g m must be finite "
                           "and half_width %.9g m in (0, 1e6]", i + 1, g->altitude, g->half_width);
        for (int c = 0; c < 3; c++)
            if (!(fabs(g->v_max[c]) <= 500.0))
                return lv_fail(err, LV_ERR_INPUT, "wind: gust %zu: peak %s %.9g m/s must be "
                               "within [-500, 500] m/s", i + 1,
                               c == 0 ? "north" : c == 1 ? "east" : "down", g->v_max[c]);
    }
    size_t n = 0;
    if (turb != NULL) {
        const lv_dryden_spec *t = turb;
        if (!(t->sigma_h >= 0.0 && t->sigma_h <= 100.0) || !(t->sigma_v >= 0.0 && t->sigma_v <= 100.0))
            return lv_fail(err, LV_ERR_INPUT, "wind: turbulence: sigma %.9g m/s (horizontal), "
                           "%.9g m/s (vertical) must be in [0, 100] m/s", t->sigma_h, t->sigma_v);
        if (!(t->length >= 1.0 && t->length <= 1e5))
            return lv_fail(err, LV_ERR_INPUT, "wind: turbulence: length %.9g m must be in "
                           "[1, 1e5] m", t->length);
        if (!isfinite(t->h_from) || !isfinite(t->h_to) || !(t->h_to > t->h_from))
            return lv_fail(err, LV_ERR_INPUT, "wind: turbulence: the layer [%.9g, %.9g] m must "
                           "be finite with from < to", t->h_from, t->h_to);
        const double cells = (t->h_to - t->h_from) / (t->length / SAMPLES_PER_L);
        if (!(cells + 4.0 <= (double)SAMPLES_MAX))
            return lv_fail(err, LV_ERR_INPUT, "wind: turbulence: the layer [%.9g, %.9g] m is "
                           "%.9g scale lengths deep; at most %zu (2^22 samples at L/%d)",
                           t->h_from, t->h_to, (t->h_to - t->h_from) / t->length,
                           (SAMPLES_MAX - 4) / SAMPLES_PER_L, SAMPLES_PER_L);
        n = (size_t)ceil(cells) + 4; /* one sample below h_from, two above h_to */
    }
    *n_samples = n;
    return LV_OK;
}

lv_status lv_wind_disturbance_check(const lv_dryden_spec *turb, const lv_gust_1cos *gusts,
                                    size_t n_gusts, lv_err *err)
{
    size_t n;
    return check_spec(turb, gusts, n_gusts, &n, err);
}

lv_status lv_wind_disturbance_create(const lv_dryden_spec *turb, const lv_gust_1cos *gusts,
                                     size_t n_gusts, uint64_t seed, uint64_t run,
                                     lv_wind_disturbance **out, lv_err *err)
{
    if (out == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_wind_disturbance_create: NULL argument");
    *out = NULL;
    size_t n = 0;
    const lv_status st = check_spec(turb, gusts, n_gusts, &n, err);
    if (st != LV_OK)
        return st;
    lv_wind_disturbance *d = calloc(1, sizeof *d);
    if (d == NULL || (n > 0 && ((d->s = malloc(3 * n * sizeof *d->s)) == NULL ||
                                (d->m2 = malloc(3 * n * sizeof *d->m2)) == NULL))) {
        lv_wind_disturbance_free(d);
        return lv_fail(err, LV_ERR_NOMEM, "wind: turbulence: out of memory");
    }
    d->n_gusts = n_gusts;
    if (n_gusts > 0)
        memcpy(d->gust, gusts, n_gusts * sizeof *gusts);
    if (turb != NULL) {
        d->turbulent = 1;
        d->spec = *turb;
        d->dh = turb->length / SAMPLES_PER_L;
        d->inv_dh = 1.0 / d->dh;
        d->h0 = turb->h_from - d->dh;
        d->n = n;
        const double depth = turb->h_to - turb->h_from;
        d->fade = turb->length < 0.5 * depth ? turb->length : 0.5 * depth;
        realise(d, seed, run);
        spline(d);
    }
    *out = d;
    return LV_OK;
}

/* (1 - cos(pi x))/2 for x in [0, 1]: 0 to 1 with zero slope at both ends. */
static double ramp(double x) { return 0.5 - 0.5 * cos(LV_PI * x); }

void lv_wind_disturbance_eval(const lv_wind_disturbance *d, double h, double v_ned[3])
{
    v_ned[0] = v_ned[1] = v_ned[2] = 0.0;
    if (isnan(h))
        return;
    for (size_t i = 0; i < d->n_gusts; i++) {
        const lv_gust_1cos *g = &d->gust[i];
        const double x = (h - g->altitude) / g->half_width;
        if (fabs(x) < 1.0) {
            const double f = 0.5 * (1.0 + cos(LV_PI * x));
            for (int c = 0; c < 3; c++)
                v_ned[c] += f * g->v_max[c];
        }
    }
    if (!d->turbulent || !(h > d->spec.h_from && h < d->spec.h_to))
        return;
    const double u = (h - d->h0) * d->inv_dh; /* >= 1: sample 0 is one spacing below h_from */
    size_t i = (size_t)u;
    if (i > d->n - 3)
        i = d->n - 3;
    const double t = u - (double)i;
    double w = 1.0; /* the fade at the layer's ends */
    if (h < d->spec.h_from + d->fade)
        w = ramp((h - d->spec.h_from) / d->fade);
    else if (h > d->spec.h_to - d->fade)
        w = ramp((d->spec.h_to - h) / d->fade);
    const double *s = d->s + 3 * i, *m = d->m2 + 3 * i;
    const double u1 = 1.0 - t;
    /* the cubic spline on [i, i+1]: linear part plus the second differences' cubic terms */
    const double a = (u1 * u1 * u1 - u1) / 6.0, b = (t * t * t - t) / 6.0;
    for (int k = 0; k < 3; k++)
        v_ned[k] += w * (u1 * s[k] + t * s[3 + k] + a * m[k] + b * m[3 + k]);
}

void lv_wind_disturbance_grid(const lv_wind_disturbance *d, double *h0, double *spacing)
{
    *h0 = d->turbulent ? d->h0 : 0.0;
    *spacing = d->turbulent ? d->dh : 0.0;
}
