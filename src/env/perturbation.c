/* perturbation.c - perturbation profiles over altitude (lv_perturbation.h; docs/monte-carlo.md
 * "Dispersed profiles"): a unit Ornstein-Uhlenbeck process over altitude per component, sampled
 * exactly at L/20 from the campaign generator (core/random.c), Catmull-Rom between samples,
 * times a piecewise-linear sigma(h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/random.h"
#include "core/status.h"
#include "lvsim/lv_dispersion.h"
#include "lvsim/lv_perturbation.h"

#define SAMPLES_PER_L 20
#define SAMPLES_MAX ((size_t)1 << 22)

struct lv_perturbation {
    size_t n_comp;
    size_t n_sigma;
    double sigma_h[LV_PERTURBATION_SIGMA_MAX], sigma[LV_PERTURBATION_SIGMA_MAX];
    double h_from, h_to;   /* m: the layer; x is held beyond it */
    double h0, dh, inv_dh; /* m: sample 0's altitude (h_from - dh), spacing; 1/dh */
    size_t n;              /* samples per component */
    double *x;             /* [n][n_comp] the unit process */
};

void lv_perturbation_free(lv_perturbation *p)
{
    if (p == NULL)
        return;
    free(p->x);
    free(p);
}

/* Component c's n samples: x_0 = n_0, x_{k+1} = A x_k + sqrt(1 - A^2) n_{k+1}; the normals of
 * samples 2j and 2j + 1 from the call with counter (run, stream + j). */
static void realise(lv_perturbation *p, size_t c, uint64_t stream, uint64_t seed, uint64_t run)
{
    const double A = exp(-1.0 / SAMPLES_PER_L), B = sqrt(1.0 - A * A);
    double z[2], x = 0.0;
    for (size_t k = 0; k < p->n; k++) {
        if (k % 2 == 0)
            lv_rand_normal2(seed, run, stream + k / 2, z);
        x = k == 0 ? z[0] : A * x + B * z[k % 2];
        p->x[k * p->n_comp + c] = x;
    }
}

lv_status lv_perturbation_create(const lv_perturbation_spec *s, const uint64_t *stream,
                                 uint64_t seed, uint64_t run, lv_perturbation **out, lv_err *err)
{
    if (s == NULL || stream == NULL || out == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_perturbation_create: NULL argument");
    *out = NULL;
    if (s->n_comp < 1 || s->n_comp > LV_PERTURBATION_COMP_MAX)
        return lv_fail(err, LV_ERR_INPUT, "perturbation: %zu components; 1 or 2", s->n_comp);
    if (s->n_sigma < 1 || s->n_sigma > LV_PERTURBATION_SIGMA_MAX || s->sigma_h == NULL ||
        s->sigma == NULL)
        return lv_fail(err, LV_ERR_INPUT, "perturbation: sigma: %zu points; 1 to %d", s->n_sigma,
                       LV_PERTURBATION_SIGMA_MAX);
    for (size_t k = 0; k < s->n_sigma; k++) {
        if (!isfinite(s->sigma_h[k]) || !(s->sigma[k] >= 0.0) || !isfinite(s->sigma[k]))
            return lv_fail(err, LV_ERR_INPUT, "perturbation: sigma point %zu (%.9g m, %.9g): the "
                           "altitude must be finite and sigma finite and >= 0", k + 1,
                           s->sigma_h[k], s->sigma[k]);
        if (k > 0 && !(s->sigma_h[k] > s->sigma_h[k - 1]))
            return lv_fail(err, LV_ERR_INPUT, "perturbation: sigma point %zu: altitude %.9g m "
                           "not above the previous %.9g m", k + 1, s->sigma_h[k],
                           s->sigma_h[k - 1]);
    }
    if (!(s->length >= 1.0 && s->length <= 1e6))
        return lv_fail(err, LV_ERR_INPUT, "perturbation: correlation length %.9g m must be in "
                       "[1, 1e6] m", s->length);
    if (!isfinite(s->h_from) || !isfinite(s->h_to) || !(s->h_to > s->h_from))
        return lv_fail(err, LV_ERR_INPUT, "perturbation: the layer [%.9g, %.9g] m must be "
                       "finite with from < to", s->h_from, s->h_to);
    const double cells = (s->h_to - s->h_from) / (s->length / SAMPLES_PER_L);
    if (!(cells + 4.0 <= (double)SAMPLES_MAX))
        return lv_fail(err, LV_ERR_INPUT, "perturbation: the layer [%.9g, %.9g] m is %.3g "
                       "correlation lengths deep; at most %.3g (%zu samples at L/%d)", s->h_from,
                       s->h_to, (s->h_to - s->h_from) / s->length,
                       (double)(SAMPLES_MAX - 4) / SAMPLES_PER_L, SAMPLES_MAX, SAMPLES_PER_L);
    lv_perturbation *p = calloc(1, sizeof *p);
    const size_t n = (size_t)ceil(cells) + 4; /* one sample below h_from, two above h_to */
    if (p == NULL || (p->x = malloc(n * s->n_comp * sizeof *p->x)) == NULL) {
        lv_perturbation_free(p);
        return lv_fail(err, LV_ERR_NOMEM, "perturbation: out of memory");
    }
    p->n_comp = s->n_comp;
    p->n_sigma = s->n_sigma;
    memcpy(p->sigma_h, s->sigma_h, s->n_sigma * sizeof *p->sigma_h);
    memcpy(p->sigma, s->sigma, s->n_sigma * sizeof *p->sigma);
    p->h_from = s->h_from;
    p->h_to = s->h_to;
    p->dh = s->length / SAMPLES_PER_L;
    p->inv_dh = 1.0 / p->dh;
    p->h0 = s->h_from - p->dh;
    p->n = n;
    for (size_t c = 0; c < s->n_comp; c++)
        realise(p, c, stream[c], seed, run);
    *out = p;
    return LV_OK;
}

double lv_perturbation_sigma(const lv_perturbation *p, double h)
{
    const size_t n = p->n_sigma;
    if (n == 1 || h <= p->sigma_h[0])
        return p->sigma[0];
    if (h >= p->sigma_h[n - 1])
        return p->sigma[n - 1];
    size_t k = 1;
    while (h > p->sigma_h[k])
        k++;
    const double f = (h - p->sigma_h[k - 1]) / (p->sigma_h[k] - p->sigma_h[k - 1]);
    return p->sigma[k - 1] + f * (p->sigma[k] - p->sigma[k - 1]);
}

size_t lv_perturbation_comp(const lv_perturbation *p)
{
    return p->n_comp;
}

void lv_perturbation_eval(const lv_perturbation *p, double h, double *delta)
{
    for (size_t c = 0; c < p->n_comp; c++)
        delta[c] = 0.0;
    if (isnan(h))
        return;
    const double hc = h < p->h_from ? p->h_from : h > p->h_to ? p->h_to : h;
    const double u = (hc - p->h0) * p->inv_dh; /* >= 1: sample 0 is one spacing below h_from */
    size_t i = (size_t)u;
    if (i > p->n - 3)
        i = p->n - 3;
    const double t = u - (double)i, t2 = t * t, t3 = t2 * t;
    /* Catmull-Rom weights of samples i-1, i, i+1, i+2 */
    const double w[4] = { -0.5 * t3 + t2 - 0.5 * t, 1.5 * t3 - 2.5 * t2 + 1.0,
                          -1.5 * t3 + 2.0 * t2 + 0.5 * t, 0.5 * t3 - 0.5 * t2 };
    const double sig = lv_perturbation_sigma(p, h);
    const size_t nc = p->n_comp;
    const double *x = p->x + (i - 1) * nc;
    for (size_t c = 0; c < nc; c++)
        delta[c] = sig * (w[0] * x[c] + w[1] * x[nc + c] + w[2] * x[2 * nc + c] +
                          w[3] * x[3 * nc + c]);
}

void lv_perturbation_grid(const lv_perturbation *p, double *h0, double *spacing, size_t *n)
{
    *h0 = p->h0;
    *spacing = p->dh;
    *n = p->n;
}
