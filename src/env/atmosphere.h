/* atmosphere.h - internals of the atmosphere models (not exported).
 * U.S. Standard Atmosphere 1976 (NOAA-S/T 76-1562, NASA-TM-X-74335): constants of its
 * Tables 2-6 and the precomputed upper-atmosphere table (86 km to 1000 km). */
#ifndef LV_ENV_ATMOSPHERE_H
#define LV_ENV_ATMOSPHERE_H

#include <stddef.h>

#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_units.h"

/* Category I constants, Table 2 of the 1976 document (kmol-based, as printed). */
#define LV_US76_RSTAR 8314.32     /* N m / (kmol K), gas constant */
#define LV_US76_M0 28.9644        /* kg/kmol, sea-level mean molecular weight */
#define LV_US76_G0 LV_G0          /* m/s^2: the standard gravity (lv_units.h) */
#define LV_US76_R0 6356766.0      /* m, effective Earth radius for H(Z), eq. (18) */
#define LV_US76_NA 6.022169e26    /* 1/kmol, Avogadro constant */
#define LV_US76_K 1.380622e-23    /* N m / K, Boltzmann constant */
#define LV_US76_GAMMA 1.40        /* ratio of specific heats, eq. (50) */
#define LV_US76_BETA 1.458e-6     /* kg / (s m K^0.5), Sutherland, eq. (51) */
#define LV_US76_S 110.4           /* K, Sutherland's constant, eq. (51) */

#define LV_US76_Z7 86000.0        /* m, lower edge of the upper atmosphere */
#define LV_US76_NSPECIES 6        /* N2, O, O2, Ar, He, H */

enum lv_us76_species { LV_US76_N2, LV_US76_O, LV_US76_O2, LV_US76_AR, LV_US76_HE, LV_US76_H };

/* Kinetic temperature above 86 km (eqs. 25-31 of the document's Section 1.2.5, the four
 * segments of Table 5) and its gradient dT/dZ in K/m. Z in m, 86 km <= Z <= 1000 km. */
double lv_us76_upper_T(double z, double *dT_dz);

/* Upper-atmosphere table: per interval of `dz` metres a cubic in t = (z - z_k)/dz for
 * ln(N T) (N: total number density, 1/m^3; T in K) and ln(rho T) (rho in kg/m^3).
 * Built once, read-only after. */
typedef struct lv_us76_upper {
    double z0;        /* m, 86 km */
    double dz;        /* m, interval length */
    size_t n;         /* number of intervals */
    const double *c;  /* [n][8]: ln(N T) coefficients c0..c3, then ln(rho T) c0..c3 */
    double *own;      /* the block c points to when built here (freed by release), or NULL */
} lv_us76_upper;

/* Integrates the species equations on a grid of `h` metres (Simpson's rule) and fits
 * Hermite cubics on intervals of `node_dz` metres (a multiple of 2 h dividing 1000 m).
 * The default model uses h = 50 m and node_dz = 500 m (interpolation error < 5e-7): that
 * table is computed at build time (lv_us76_upper_1976), not at run time. */
#define LV_US76_UPPER_H 50.0       /* m, integration step of the default table */
#define LV_US76_UPPER_NODE_DZ 500.0 /* m, its node spacing */
lv_status lv_us76_upper_build(lv_us76_upper *up, double h, double node_dz, lv_err *err);
void lv_us76_upper_release(lv_us76_upper *up);

/* The default table (h = LV_US76_UPPER_H, node_dz = LV_US76_UPPER_NODE_DZ), computed by
 * lv_us76_upper_build at build time and compiled in (us76_upper_table.c, written by
 * src/env/atmosphere_us76_gen.c): every process shares it and nobody computes it at run time.
 * Bit for bit what lv_us76_upper_build gives on the build machine (test_atmosphere checks). */
extern const lv_us76_upper lv_us76_upper_1976;

/* ln(N T) and ln(rho T) at z (86 km <= z <= 1000 km). No allocation. */
void lv_us76_upper_lookup(const lv_us76_upper *up, double z, double *ln_NT, double *ln_rhoT);

/* Number densities n[i][species] (1/m^3) at grid-aligned altitudes z[i] (multiples of
 * 2 h above 86 km), integrated with step h. For tests and documentation. */
lv_status lv_us76_number_densities(const double *z, size_t count, double h,
                                   double (*n)[LV_US76_NSPECIES], lv_err *err);

#endif
