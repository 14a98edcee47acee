/* lv_perturbation.h - a perturbation profile over altitude: a random field delta(h) that
 * disperses a wind or an atmosphere coherently over altitude for Monte Carlo (docs/
 * monte-carlo.md, "Dispersed profiles"; the wind and atmosphere wrappers: lv_wind.h
 * lv_wind_create_perturbed, lv_atmosphere.h lv_atmo_create_perturbed).
 *
 * delta_c(h) = sigma(h) x_c(h) for each component c (1 or 2: the density's relative
 * perturbation; the wind's north and east), with
 *   - sigma(h) piecewise linear in h between given points (held beyond the first and last),
 *   - x_c a stationary Gauss-Markov (Ornstein-Uhlenbeck) process over altitude with unit
 *     variance and correlation E[x(h) x(h + dh)] = exp(-|dh| / L), L the correlation length,
 *     the components independent (each its own stream).
 * This is the form of Earth-GRAM's perturbation model along a path, a first-order Markov
 * (autoregressive) update new = A old + sqrt(1 - A^2) N(0, 1), A = exp(-displacement / L)
 * (Justus & Leslie, NASA/TM-2008-215581, The NASA MSFC Earth Global Reference Atmospheric
 * Model - 2007 Version, the perturbation model of its technical description), kept to the
 * vertical displacement only and with a sigma profile of the user's (no climatology, no
 * large-scale wave model, no cross-correlation between density, temperature and pressure).
 *
 * The realisation. x is sampled at spacing L/20 over [h_from - L/20, h_to + 2 L/20] exactly
 * (not by integrating an equation): x_0 = n_0, x_{k+1} = A x_k + sqrt(1 - A^2) n_{k+1},
 * A = exp(-1/20), n_k independent standard normals (the exact discretisation of the OU process:
 * Gillespie, Phys. Rev. E 54, 2084 (1996), eq. 1.9 without drift; x_0 from the stationary law,
 * so the path is stationary from its first sample). The normals come from lvsim's generator
 * (lv_dispersion.h; Philox4x32-10): sample pair j of component c is the call with counter
 * (run, stream[c] + j), both halves of its output. Between samples a Catmull-Rom cubic (C1, as
 * the turbulence: lv_wind.h); below h_from x is held at its value at h_from, above h_to at its
 * value at h_to. The interpolation lowers the variance between samples by at most 1.2 % (the
 * midpoint: w = (-1, 9, 9, -1)/16, var = sum w_i w_j A^|i-j| = 0.988); at the samples it is 1.
 *
 * Threads: immutable once created; eval allocates nothing. */
#ifndef LVSIM_LV_PERTURBATION_H
#define LVSIM_LV_PERTURBATION_H

#include <stddef.h>
#include <stdint.h>

#include "lvsim/lv_status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LV_PERTURBATION_COMP_MAX 2
#define LV_PERTURBATION_SIGMA_MAX 64 /* points of the sigma profile */

typedef struct lv_perturbation_spec {
    size_t n_sigma;        /* 1 .. LV_PERTURBATION_SIGMA_MAX points (h_k, sigma_k) */
    const double *sigma_h; /* m, strictly increasing */
    const double *sigma;   /* >= 0, finite: in the perturbed quantity's unit */
    double length;         /* m, L: 1 <= L <= 1e6 */
    double h_from, h_to;   /* m, the layer sampled: finite, h_from < h_to, at most 2^22 samples */
    size_t n_comp;         /* 1 or 2 */
} lv_perturbation_spec;

typedef struct lv_perturbation lv_perturbation; /* opaque, immutable once created */

/* A realisation of `spec` for (seed, run), component c from the stream stream[c] (e.g.
 * lv_disp_stream("profiles.environment.wind.north")). LV_ERR_INPUT naming the value for a
 * spec out of its domain. lv_perturbation_free(*out) when done. */
LV_API lv_status lv_perturbation_create(const lv_perturbation_spec *spec, const uint64_t *stream,
                                        uint64_t seed, uint64_t run, lv_perturbation **out,
                                        lv_err *err);
LV_API void lv_perturbation_free(lv_perturbation *p); /* accepts NULL */
/* delta[0 .. n_comp-1] at altitude h [m] (0 for a NaN h). No allocation. */
LV_API void lv_perturbation_eval(const lv_perturbation *p, double h, double *delta);
/* sigma(h) of the profile (piecewise linear, held beyond its ends). */
LV_API double lv_perturbation_sigma(const lv_perturbation *p, double h);
LV_API size_t lv_perturbation_comp(const lv_perturbation *p);
/* The samples: altitude of sample 0 [m], spacing [m], count; x_c(h0 + k spacing) is sample k
 * exactly (delta there = sigma(h) x). For statistical checks. */
LV_API void lv_perturbation_grid(const lv_perturbation *p, double *h0, double *spacing,
                                 size_t *n);

#ifdef __cplusplus
}
#endif
#endif
