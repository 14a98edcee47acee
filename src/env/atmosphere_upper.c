/* atmosphere_upper.c - U.S. Standard Atmosphere 1976 from 86 km to 1000 km.
 * Follows NOAA-S/T 76-1562 (1976), Part 1 Section 1.2 and Appendix B: kinetic temperature
 * in four segments, number densities of N2, O, O2, Ar, He and H from the molecular/eddy
 * diffusion equations, integrated once on a fine grid and kept as cubics of ln(N T) and
 * ln(rho T). */
#include "env/atmosphere.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"

/* Table 5: geometric heights and temperatures that define T(Z) above 86 km. */
#define Z8 91000.0      /* m */
#define Z9 110000.0     /* m */
#define Z10 120000.0    /* m */
#define Z11 500000.0    /* m, reference height of hydrogen */
#define Z12 1000000.0   /* m */
#define T7 186.8673     /* K */
#define T9 240.0        /* K */
#define T10 360.0       /* K */
#define TINF 1000.0     /* K */
#define LK9 0.012       /* K/m, gradient of the linear segment */
#define TC 263.1905     /* K, centre of the elliptical segment, eq. (27) */
#define ELL_A (-76.3232) /* K, eq. (27) */
#define ELL_a (-19942.9) /* m, eq. (27) */
#define LAMBDA 1.875e-5 /* 1/m, = LK9 / (TINF - T10), eq. (31) */

/* Heights where a branch of the species equations switches (m). */
#define Z_EDDY 95000.0  /* K(Z) starts to fall */
#define Z_MIX 100000.0  /* M switches from M0 to the background mean */
#define Z_O_FLUX 97000.0 /* second flux term of O ends */
#define Z_K0 115000.0   /* K = 0 above */
#define Z_H 150000.0    /* hydrogen is computed from here */

#define K7 120.0        /* m^2/s, eddy diffusion coefficient at 86 km */
#define PHI_H 7.2e11    /* 1/(m^2 s), vertical flux of H */
#define N_H11 8.0e10    /* 1/m^3, H at 500 km */

/* Molecular weights (Table 3, kg/kmol), number densities at 86 km (1/m^3, Section
 * 1.2.6; He as 7.5817e14, the value consistent with Table VIII), thermal-diffusion
 * factor alpha and the coefficients a (1/(m s)) and b of D = a (T/273.15)^b / N (Table 6). */
static const double MI[LV_US76_NSPECIES] = { 28.0134, 15.9994, 31.9988,
                                             39.948,  4.0026,  1.00797 };
static const double N7[LV_US76_NSPECIES] = { 1.129794e20, 8.6e16, 3.030898e19,
                                             1.351400e18, 7.5817e14, 0.0 };
static const double ALPHA[LV_US76_NSPECIES] = { 0.0, 0.0, 0.0, 0.0, -0.40, -0.25 };
static const double DIFF_A[LV_US76_NSPECIES] = { 0.0, 6.986e20, 4.863e20,
                                                 4.487e20, 1.700e21, 3.305e21 };
static const double DIFF_B[LV_US76_NSPECIES] = { 0.0, 0.750, 0.750, 0.870, 0.691, 0.500 };
/* Flux terms, eq. (37) (Table 7), converted from km to m: Q, W in 1/m^3, U in m. */
static const double FLUX_Q[LV_US76_NSPECIES] = { 0.0, -5.809644e-13, 1.366212e-13,
                                                 9.434079e-14, -2.457369e-13, 0.0 };
static const double FLUX_U[LV_US76_NSPECIES] = { 0.0, 56903.11, 86000.0, 86000.0, 86000.0, 0.0 };
static const double FLUX_W[LV_US76_NSPECIES] = { 0.0, 2.706240e-14, 8.333333e-14,
                                                 8.333333e-14, 6.666667e-13, 0.0 };
#define O_FLUX_q (-3.416248e-12) /* 1/m^3 */
#define O_FLUX_u 97000.0         /* m */
#define O_FLUX_w 5.008765e-13    /* 1/m^3 */

double lv_us76_upper_T(double z, double *dT_dz)
{
    if (z < Z8) { /* isothermal segment, 86-91 km */
        *dT_dz = 0.0;
        return T7;
    }
    if (z < Z9) { /* elliptical, eq. (27) */
        const double x = (z - Z8) / ELL_a;
        const double s = sqrt(1.0 - x * x);
        *dT_dz = -ELL_A / ELL_a * x / s;
        return TC + ELL_A * s;
    }
    if (z < Z10) { /* linear, eq. (29) */
        *dT_dz = LK9;
        return T9 + LK9 * (z - Z9);
    }
    /* exponential, eq. (31), xi = (Z - Z10)(r0 + Z10)/(r0 + Z) */
    const double r = (LV_US76_R0 + Z10) / (LV_US76_R0 + z);
    const double e = (TINF - T10) * exp(-LAMBDA * (z - Z10) * r);
    *dT_dz = LAMBDA * r * r * e;
    return TINF - e;
}

/* The fine grid: z_j = 86 km + j h; all species at every point. */
typedef struct grid {
    size_t np;
    double h;
    size_t j_mix, j_h, j_11; /* indices of 100, 150 and 500 km */
    double *T, *dT, *g;
    double *n[LV_US76_NSPECIES];
    double *tau, *G;         /* hydrogen: eq. (40) integral and flux integral */
    double *buf;
} grid;

static double grid_z(const grid *gr, size_t j)
{
    return LV_US76_Z7 + (double)j * gr->h;
}

/* Branch selector: a discontinuity at a grid node is seen from below (side < 0) by the
 * panel ending there and from above (side > 0) by the panel starting there. */
static double side_z(double z, int side)
{
    return z + 1e-3 * (double)side;
}

/* Eddy-diffusion coefficient K(Z) (Section 1.2.6): K7 to 95 km, falling to 0 at 115 km. */
static double eddy_K(double z, double zb)
{
    if (zb < Z_EDDY)
        return K7;
    if (zb >= Z_K0)
        return 0.0;
    const double d = 4.0e8 - (z - Z_EDDY) * (z - Z_EDDY); /* 400 km^2 */
    return d > 0.0 ? K7 * exp(1.0 - 4.0e8 / d) : 0.0;
}

/* Integrand f_i + flux_i of eq. (36)-(37) for species s (N2..He) at grid point j, 1/m:
 *   n_i(Z) = n_i(86 km) (T7/T) exp(-int f_i dZ),
 *   f_i = g/(R* T) [D (M_i + alpha_i R* T'/g) + K M] / (D + K) + flux_i.
 * N2 is mixed below 100 km and in diffusive equilibrium above (no D, K). The background
 * N and M of D and of the eddy term are N2 for O and O2, and N2 + O + O2 for Ar and He. */
static double species_f(const grid *gr, int s, size_t j, int side)
{
    const double z = grid_z(gr, j), zb = side_z(z, side);
    const double T = gr->T[j], g = gr->g[j];
    const double gRT = g / (LV_US76_RSTAR * T);
    if (s == LV_US76_N2)
        return gRT * (zb < Z_MIX ? LV_US76_M0 : MI[LV_US76_N2]);

    const int last = (s == LV_US76_O || s == LV_US76_O2) ? LV_US76_N2 : LV_US76_O2;
    double nb = 0.0, nm = 0.0;
    for (int k = 0; k <= last; k++) {
        nb += gr->n[k][j];
        nm += gr->n[k][j] * MI[k];
    }
    const double M = zb < Z_MIX ? LV_US76_M0 : nm / nb;
    const double K = eddy_K(z, zb);
    const double D = DIFF_A[s] * pow(T / 273.15, DIFF_B[s]) / nb;
    const double thermal = ALPHA[s] * LV_US76_RSTAR * gr->dT[j] / g;
    double f = gRT * (D * (MI[s] + thermal) + K * M) / (D + K);

    /* Flux term, eq. (37). The document drops it above 150 km, where it is below 1e-9
     * of f; it is kept everywhere here so that the integrand has no jump. */
    const double u = z - FLUX_U[s];
    f += FLUX_Q[s] * u * u * exp(-FLUX_W[s] * u * u * u);
    if (s == LV_US76_O && zb < Z_O_FLUX) {
        const double v = O_FLUX_u - z;
        f += O_FLUX_q * v * v * exp(-O_FLUX_w * v * v * v);
    }
    return f;
}

/* Integrand of the hydrogen flux integral (Section 1.2.6, with tau of eq. 40):
 *   (T/T11)^(1+alpha) exp(tau(Z)) / D_H, zero at and above 500 km. */
static double hydrogen_h(const grid *gr, size_t j, int side)
{
    const double zb = side_z(grid_z(gr, j), side);
    if (zb >= Z11 || zb < Z_H)
        return 0.0;
    const double T = gr->T[j];
    double nb = 0.0;
    for (int k = LV_US76_N2; k <= LV_US76_HE; k++)
        nb += gr->n[k][j];
    const double D = DIFF_A[LV_US76_H] * pow(T / 273.15, DIFF_B[LV_US76_H]) / nb;
    const double T11 = gr->T[gr->j_11];
    return pow(T / T11, 1.0 + ALPHA[LV_US76_H]) * exp(gr->tau[j] - gr->tau[gr->j_11]) / D;
}

/* Cumulative integral of one panel [j, j+2] by Simpson's rule, with the fourth-order
 * partial rule h (5 f0 + 8 f1 - f2) / 12 for the midpoint. */
static void panel(double F0, double f0, double f1, double f2, double h, double *F1, double *F2)
{
    *F1 = F0 + h * (5.0 * f0 + 8.0 * f1 - f2) / 12.0;
    *F2 = F0 + h * (f0 + 4.0 * f1 + f2) / 3.0;
}

static void grid_free(grid *gr)
{
    free(gr->buf);
    memset(gr, 0, sizeof *gr);
}

static lv_status grid_check(double h, size_t *np, lv_err *err)
{
    /* 100, 150 and 500 km must be panel ends: 2h must divide 2000 m. */
    const double panels = 2000.0 / (2.0 * h);
    if (!(h > 0.0) || panels != floor(panels) || panels < 1.0)
        return lv_fail(err, LV_ERR_INPUT,
                       "us76 upper atmosphere: integration step %g m must divide 1000 m",
                       h);
    *np = (size_t)lround((Z12 - LV_US76_Z7) / h) + 1;
    return LV_OK;
}

static lv_status grid_integrate(grid *gr, double h, lv_err *err)
{
    memset(gr, 0, sizeof *gr);
    size_t np = 0;
    lv_status st = grid_check(h, &np, err);
    if (st != LV_OK)
        return st;
    const size_t narr = 3 + LV_US76_NSPECIES + 2;
    gr->buf = malloc(narr * np * sizeof *gr->buf);
    if (gr->buf == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "us76 upper atmosphere: out of memory (%zu points)",
                       np);
    gr->np = np;
    gr->h = h;
    gr->T = gr->buf;
    gr->dT = gr->buf + np;
    gr->g = gr->buf + 2 * np;
    for (int s = 0; s < LV_US76_NSPECIES; s++)
        gr->n[s] = gr->buf + (size_t)(3 + s) * np;
    gr->tau = gr->buf + (3 + LV_US76_NSPECIES) * np;
    gr->G = gr->buf + (4 + LV_US76_NSPECIES) * np;
    gr->j_mix = (size_t)lround((Z_MIX - LV_US76_Z7) / h);
    gr->j_h = (size_t)lround((Z_H - LV_US76_Z7) / h);
    gr->j_11 = (size_t)lround((Z11 - LV_US76_Z7) / h);

    for (size_t j = 0; j < np; j++) {
        const double z = grid_z(gr, j);
        const double q = LV_US76_R0 / (LV_US76_R0 + z);
        gr->T[j] = lv_us76_upper_T(z, &gr->dT[j]);
        gr->g[j] = LV_US76_G0 * q * q; /* inverse-square gravity */
    }

    /* N2, O, O2, Ar, He in this order: each needs the ones before it at the same Z. */
    for (int s = LV_US76_N2; s <= LV_US76_HE; s++) {
        double *n = gr->n[s];
        double F = 0.0;
        n[0] = N7[s];
        for (size_t j = 0; j + 2 < np; j += 2) {
            double F1, F2;
            panel(F, species_f(gr, s, j, +1), species_f(gr, s, j + 1, 0),
                  species_f(gr, s, j + 2, -1), h, &F1, &F2);
            n[j + 1] = N7[s] * T7 / gr->T[j + 1] * exp(-F1);
            n[j + 2] = N7[s] * T7 / gr->T[j + 2] * exp(-F2);
            F = F2;
        }
    }

    /* Hydrogen (tau: eq. 40): tau(Z) = int_{500 km}^{Z} g M_H / (R* T) dZ;
     * n_H = [n_H(500) + phi int_Z^{500} h dZ] (T11/T)^(1+alpha) exp(-tau). */
    const size_t jh = gr->j_h, j11 = gr->j_11;
    double *nH = gr->n[LV_US76_H];
    for (size_t j = 0; j < jh; j++) {
        nH[j] = 0.0;
        gr->tau[j] = gr->G[j] = 0.0;
    }
    gr->tau[jh] = 0.0;
    for (size_t j = jh; j + 2 < np; j += 2) {
        double f[3];
        for (size_t i = 0; i < 3; i++)
            f[i] = gr->g[j + i] * MI[LV_US76_H] / (LV_US76_RSTAR * gr->T[j + i]);
        panel(gr->tau[j], f[0], f[1], f[2], h, &gr->tau[j + 1], &gr->tau[j + 2]);
    }
    gr->G[jh] = 0.0;
    for (size_t j = jh; j + 2 < np; j += 2)
        panel(gr->G[j], hydrogen_h(gr, j, +1), hydrogen_h(gr, j + 1, 0),
              hydrogen_h(gr, j + 2, -1), h, &gr->G[j + 1], &gr->G[j + 2]);
    const double T11 = gr->T[j11], e_H = 1.0 + ALPHA[LV_US76_H];
    for (size_t j = jh; j < np; j++)
        nH[j] = (N_H11 + PHI_H * (gr->G[j11] - gr->G[j])) * pow(T11 / gr->T[j], e_H) *
                exp(-(gr->tau[j] - gr->tau[j11]));
    return LV_OK;
}

/* ln(N T), ln(rho T) and their derivatives at grid point j, seen from `side`. */
static void node_values(const grid *gr, size_t j, int side, double *lnN, double *dlnN,
                        double *lnrho, double *dlnrho)
{
    const double T = gr->T[j], dlnT = gr->dT[j] / T;
    double N = 0.0, dN = 0.0, R = 0.0, dR = 0.0;
    for (int s = LV_US76_N2; s <= LV_US76_H; s++) {
        double n = gr->n[s][j], dln;
        if (s == LV_US76_H) {
            if (j < gr->j_h || (j == gr->j_h && side < 0))
                continue; /* no hydrogen below 150 km */
            const double S = N_H11 + PHI_H * (gr->G[gr->j_11] - gr->G[j]);
            dln = -PHI_H * hydrogen_h(gr, j, side) / S - (1.0 + ALPHA[s]) * dlnT -
                  gr->g[j] * MI[s] / (LV_US76_RSTAR * T);
        } else {
            dln = -dlnT - species_f(gr, s, j, side);
        }
        N += n;
        dN += n * dln;
        R += n * MI[s];
        dR += n * MI[s] * dln;
    }
    /* Tabulated with the factor T, which carries the fast variation of T near 110 km:
     * ln(N T) and ln(rho T) are integrals of smooth functions and interpolate well. */
    *lnN = log(N * T);
    *dlnN = dN / N + dlnT;
    *lnrho = log(R / LV_US76_NA * T);
    *dlnrho = dR / R + dlnT;
}

static void hermite(double y0, double d0, double y1, double d1, double dz, double *c)
{
    const double m0 = d0 * dz, m1 = d1 * dz;
    c[0] = y0;
    c[1] = m0;
    c[2] = 3.0 * (y1 - y0) - 2.0 * m0 - m1;
    c[3] = 2.0 * (y0 - y1) + m0 + m1;
}

lv_status lv_us76_upper_build(lv_us76_upper *up, double h, double node_dz, lv_err *err)
{
    memset(up, 0, sizeof *up);
    const double stride_d = node_dz / h;
    if (!(node_dz > 0.0) || 2000.0 / node_dz != floor(2000.0 / node_dz) ||
        stride_d != floor(stride_d) || stride_d < 1.0)
        return lv_fail(err, LV_ERR_INPUT,
                       "us76 upper atmosphere: node spacing %g m must divide 2000 m and be "
                       "a multiple of the step %g m",
                       node_dz, h);
    grid gr;
    lv_status st = grid_integrate(&gr, h, err);
    if (st != LV_OK)
        return st;
    const size_t stride = (size_t)stride_d;
    const size_t n = (gr.np - 1) / stride;
    double *c = malloc(n * 8 * sizeof *c);
    if (c == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "us76 upper atmosphere: out of memory (%zu nodes)", n);
        goto fail;
    }
    up->z0 = LV_US76_Z7;
    up->dz = node_dz;
    up->n = n;
    up->c = up->own = c;
    for (size_t k = 0; k < n; k++) {
        double a[4], b[4];
        node_values(&gr, k * stride, +1, &a[0], &a[1], &a[2], &a[3]);
        node_values(&gr, (k + 1) * stride, -1, &b[0], &b[1], &b[2], &b[3]);
        hermite(a[0], a[1], b[0], b[1], node_dz, c + 8 * k);
        hermite(a[2], a[3], b[2], b[3], node_dz, c + 8 * k + 4);
    }
fail:
    grid_free(&gr);
    return st;
}

void lv_us76_upper_release(lv_us76_upper *up)
{
    if (up == NULL)
        return;
    free(up->own);
    memset(up, 0, sizeof *up);
}

void lv_us76_upper_lookup(const lv_us76_upper *up, double z, double *ln_NT, double *ln_rhoT)
{
    const double u = (z - up->z0) / up->dz;
    size_t k = u > 0.0 ? (size_t)u : 0;
    if (k >= up->n)
        k = up->n - 1;
    const double t = u - (double)k;
    const double *c = up->c + 8 * k;
    *ln_NT = c[0] + t * (c[1] + t * (c[2] + t * c[3]));
    *ln_rhoT = c[4] + t * (c[5] + t * (c[6] + t * c[7]));
}

lv_status lv_us76_number_densities(const double *z, size_t count, double h,
                                   double (*n)[LV_US76_NSPECIES], lv_err *err)
{
    grid gr;
    lv_status st = grid_integrate(&gr, h, err);
    if (st != LV_OK)
        return st;
    for (size_t i = 0; i < count; i++) {
        const double u = (z[i] - LV_US76_Z7) / h;
        if (!(u >= 0.0) || u > (double)(gr.np - 1) || u != floor(u)) {
            st = lv_fail(err, LV_ERR_INPUT,
                         "us76 number densities: altitude %g m is not on the %g m grid "
                         "from 86 km to 1000 km",
                         z[i], h);
            goto fail;
        }
        const size_t j = (size_t)u;
        for (int s = 0; s < LV_US76_NSPECIES; s++)
            n[i][s] = gr.n[s][j];
    }
fail:
    grid_free(&gr);
    return st;
}
