/* test_atmosphere.c - atmosphere models against the U.S. Standard Atmosphere 1976 tables
 * (NOAA-S/T 76-1562): Table I (T, p, rho by geometric altitude; printed T to 5-6
 * significant digits, p to 5, rho to 5 below 86 km and 4 above), the defining values of
 * Table 4 at the layer bases, Table VIII (number densities, 4 digits). A value "matches to
 * its printed digits" when |model - printed| <= 0.5 unit of the last printed digit; the
 * few points where the model is further off carry their allowance and the reason. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "env/atmosphere.h"
#include "lvsim/lv_atmosphere.h"

#define R0 6356766.0 /* m, US76 effective Earth radius */

/* Geometric altitude of a geopotential height H (m'), inverse of eq. (18). */
static double z_of_H(double H)
{
    return R0 * H / (R0 - H);
}

/* One printed quantity: value, significant digits (0: not printed / not checked), and
 * the allowed difference in units of the last printed digit. */
typedef struct printed {
    double v;
    int digits;
    double ulps;
} printed;

typedef struct ref_row {
    double z;      /* m, geometric altitude */
    printed T, p, rho;
    const char *src;
} ref_row;

/* Worst |model/printed - 1| and worst units of the last digit per quantity, below and
 * above 86 km, for docs/atmosphere.md. */
static double worst_rel[2][3];
static double worst_units[2][3];

static double ulp_of(double v, int digits)
{
    return pow(10.0, floor(log10(fabs(v))) - digits + 1);
}

static void check_printed(double model, printed ref, int q, double z, const char *what,
                          const char *src)
{
    if (ref.digits == 0)
        return;
    const double ulp = ulp_of(ref.v, ref.digits);
    const double tol = (ref.ulps > 0.0 ? ref.ulps : 0.5) * ulp * (1.0 + 1e-9);
    const double rel = fabs(model / ref.v - 1.0), units = fabs(model - ref.v) / ulp;
    const int up = z >= 86000.0;
    worst_rel[up][q] = rel > worst_rel[up][q] ? rel : worst_rel[up][q];
    worst_units[up][q] = units > worst_units[up][q] ? units : worst_units[up][q];
    check_count_++;
    if (!(fabs(model - ref.v) <= tol)) {
        check_failures_++;
        fprintf(stderr, "%s at z = %.1f m: model %.8g, printed %.*g (%s), %.2f units off\n",
                what, z, model, ref.digits, ref.v, src, fabs(model - ref.v) / ulp);
    }
}

#define P(v, d) { (v), (d), 0.5 }
#define PX(v, d, u) { (v), (d), (u) }
#define NONE { 0.0, 0, 0.0 }

static void test_table_values(const lv_atmo *atm)
{
    static const char *const T1 = "U.S. Standard Atmosphere 1976, Table I";
    static const char *const T4 = "U.S. Standard Atmosphere 1976, Table 4 (layer bases)";
    const ref_row rows[] = {
        /* Table I, geometric altitude, -5 km to 80 km. */
        { -5000.0, P(320.676, 6), P(1.7776e5, 5), P(1.9311, 5), T1 },
        { 0.0, P(288.150, 6), P(1.01325e5, 6), P(1.2250, 5), T1 },
        { 1000.0, P(281.651, 6), P(8.9876e4, 5), P(1.1117, 5), T1 },
        { 10000.0, P(223.252, 6), P(2.6500e4, 5), P(4.1351e-1, 5), T1 },
        { 20000.0, P(216.650, 6), P(5.5293e3, 5), P(8.8910e-2, 5), T1 },
        { 30000.0, P(226.509, 6), P(1.1970e3, 5), P(1.8410e-2, 5), T1 },
        { 40000.0, P(250.350, 6), P(2.8714e2, 5), P(3.9957e-3, 5), T1 },
        { 50000.0, P(270.650, 6), P(7.9779e1, 5), P(1.0269e-3, 5), T1 },
        { 60000.0, P(247.021, 6), P(2.1959e1, 5), P(3.0968e-4, 5), T1 },
        { 70000.0, P(219.585, 6), P(5.2209, 5), P(8.2829e-5, 5), T1 },
        { 80000.0, P(198.639, 6), NONE, P(1.8458e-5, 5), T1 },
        /* Layer bases: geopotential 11, 20, 32, 47, 51, 71 and 84.852 km' (Z = 86 km).
         * The base pressures are printed truncated, not rounded (model 5474.889 Pa is
         * printed 5474.8): allowed 1 unit. */
        { z_of_H(11000.0), P(216.650, 6), P(2.2632e4, 5), P(3.6392e-1, 5), T4 },
        { z_of_H(20000.0), P(216.650, 6), PX(5.4748e3, 5, 1.0), P(8.8035e-2, 5), T4 },
        { z_of_H(32000.0), P(228.650, 6), PX(8.6801e2, 5, 1.0), P(1.3225e-2, 5), T4 },
        { z_of_H(47000.0), P(270.650, 6), PX(1.1090e2, 5, 1.0), P(1.4275e-3, 5), T4 },
        { z_of_H(51000.0), P(270.650, 6), PX(6.6938e1, 5, 1.0), P(8.6160e-4, 5), T4 },
        { z_of_H(71000.0), P(214.650, 6), P(3.9564, 5), P(6.4211e-5, 5), T4 },
        { z_of_H(84852.0), P(186.87, 5), P(3.7338e-1, 5), P(6.958e-6, 4), T4 },
        /* Table I rows listed by geopotential height (0.2, 17.9, 49.4, 61.5, 79.5, 84 km'),
         * as transcribed in the ussa1976 package's tests; two pressures there look
         * truncated (model 81.9199 and 16.4568 Pa): allowed 1 unit. */
        { z_of_H(200.0), P(286.850, 6), P(9.8945e4, 5), P(1.2017, 5), T1 },
        { z_of_H(17900.0), P(216.650, 6), P(7.6241e3, 5), P(1.2259e-1, 5), T1 },
        { z_of_H(49400.0), P(270.650, 6), PX(8.1919e1, 5, 1.0), P(1.0544e-3, 5), T1 },
        { z_of_H(61500.0), P(241.250, 6), PX(1.6456e1, 5, 1.0), P(2.3764e-4, 5), T1 },
        { z_of_H(79500.0), NONE, P(9.6649e-1, 5), P(1.7035e-5, 5), T1 },
        { z_of_H(84000.0), NONE, P(4.3598e-1, 5), P(8.0510e-6, 5), T1 },
        /* Table I above 86 km (rho printed to 4 digits). */
        { 86000.0, P(186.87, 5), P(3.7338e-1, 5), P(6.958e-6, 4), T1 },
        { 90000.0, P(186.87, 5), P(1.8359e-1, 5), P(3.416e-6, 4), T1 },
        { 91000.0, P(186.87, 5), P(1.5381e-1, 5), P(2.860e-6, 4), T1 },
        { 100000.0, P(195.08, 5), P(3.2011e-2, 5), P(5.604e-7, 4), T1 },
        /* p: model 7.10393e-3, 4e-5 below the printed value (3 units). */
        { 110000.0, P(240.00, 5), PX(7.1042e-3, 5, 3.0), P(9.708e-8, 4), T1 },
        { 120000.0, P(360.00, 5), P(2.5382e-3, 5), P(2.222e-8, 4), T1 },
        { 130000.0, P(469.27, 5), NONE, NONE, T1 },
        { 150000.0, P(634.39, 5), P(4.5422e-4, 5), P(2.076e-9, 4), T1 },
        /* p: model 8.47349e-5, 9e-5 below the printed value (8 units). */
        { 200000.0, P(854.56, 5), PX(8.4743e-5, 5, 8.5), P(2.541e-10, 4), T1 },
        /* p: model 8.77034e-6 (0.7 units). */
        { 300000.0, P(976.01, 5), PX(8.7704e-6, 5, 1.0), P(1.916e-11, 4), T1 },
        /* p: model 3.02354e-7 (0.6 units). */
        { 500000.0, P(999.24, 5), PX(3.0236e-7, 5, 1.0), P(5.215e-13, 4), T1 },
        /* p: model 3.19067e-8 (1.3 units); rho 3.06948e-14 (0.5 units). */
        { 700000.0, NONE, PX(3.1908e-8, 5, 1.5), PX(3.070e-14, 4, 0.6), T1 },
        /* p: model 7.51342e-9, 5e-5 below (3.8 units); the printed value follows from
         * Table VIII's He 4.850e11 and H 4.967e10, our H is 4.9661e10. */
        { 1000000.0, P(1000.0, 5), PX(7.5138e-9, 5, 4.0), P(3.561e-15, 4), T1 },
    };
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        lv_atmo_state s;
        lv_err err;
        CHECK_OK(lv_atmo_eval(atm, rows[i].z, &s, &err), &err);
        check_printed(s.T, rows[i].T, 0, rows[i].z, "T", rows[i].src);
        check_printed(s.p, rows[i].p, 1, rows[i].z, "p", rows[i].src);
        check_printed(s.rho, rows[i].rho, 2, rows[i].z, "rho", rows[i].src);
    }
    for (int up = 0; up < 2; up++)
        printf("%s 86 km, max |model/printed - 1| (units of the last digit): T %.2e (%.2f), "
               "p %.2e (%.2f), rho %.2e (%.2f)\n",
               up ? "above" : "below", worst_rel[up][0], worst_units[up][0], worst_rel[up][1],
               worst_units[up][1], worst_rel[up][2], worst_units[up][2]);
}

/* Speed of sound and viscosity: U.S. Standard Atmosphere 1976, Table III (sea level
 * 340.294 m/s, 1.7894e-5 N s/m^2; the 11-20 km isothermal layer 295.07 m/s, 1.4216e-5). */
static void test_sound_viscosity(const lv_atmo *atm)
{
    lv_atmo_state s;
    lv_err err;
    CHECK_OK(lv_atmo_eval(atm, 0.0, &s, &err), &err);
    CHECK_CLOSE(s.a, 340.294, 0.0005);
    CHECK_CLOSE(s.mu, 1.7894e-5, 0.00005e-5);
    CHECK_CLOSE(s.M, 28.9644, 1e-12);
    CHECK_OK(lv_atmo_eval(atm, 15000.0, &s, &err), &err);
    CHECK_CLOSE(s.a, 295.07, 0.005);
    CHECK_CLOSE(s.mu, 1.4216e-5, 0.00005e-5);
    /* 85 km, where the kinetic T (188.836 K) and T_M (188.898 K) differ: Table I prints
     * 1.2647e-5 N s/m^2, eq. (51) evaluated with T_M (with T it would be 1.26436e-5). */
    CHECK_OK(lv_atmo_eval(atm, 85000.0, &s, &err), &err);
    CHECK_CLOSE(s.mu, 1.2647e-5, 0.00005e-5);
    /* Above 86 km: eq. (50) with T_M = T M0 / M and eq. (51) with T (docs/atmosphere.md). */
    CHECK_OK(lv_atmo_eval(atm, 300000.0, &s, &err), &err);
    CHECK_REL(s.a, sqrt(1.4 * 8314.32 * s.T / s.M), 1e-12);
    CHECK_REL(s.mu, 1.458e-6 * pow(s.T, 1.5) / (s.T + 110.4), 1e-12);
    CHECK(s.a > 0.0 && isfinite(s.a) && s.mu > 0.0 && isfinite(s.mu));
}

/* Number densities: U.S. Standard Atmosphere 1976, Table VIII, pp. 210-215 (4 digits), as
 * listed by the ussa1976 package's tests. Species N2, O, O2, Ar, He, H. That list gives
 * O at 300 km as 5.443e14, off the smooth profile that matches its 200 and 400 km values
 * to 4 digits; it is read here as a transposition of 5.433e14 (model 5.4331e14). */
static void test_number_densities(void)
{
    static const double z[] = { 90e3, 100e3, 110e3, 120e3, 150e3, 200e3, 300e3,
                                400e3, 500e3, 600e3, 700e3, 800e3, 900e3, 1000e3 };
    static const double tab[][LV_US76_NSPECIES] = {
        { 5.547e19, 2.443e17, 1.479e19, 6.574e17, 3.976e14, 0.0 },
        { 9.210e18, 4.298e17, 2.151e18, 9.501e16, 1.133e14, 0.0 },
        { 1.641e18, 2.303e17, 2.621e17, 1.046e16, 5.821e13, 0.0 },
        { 3.726e17, 9.275e16, 4.395e16, 1.366e15, 3.888e13, 0.0 },
        { 3.124e16, 1.780e16, 2.750e15, 5.000e13, 2.106e13, 3.767e11 },
        { 2.925e15, 4.050e15, 1.918e14, 1.938e12, 1.310e13, 1.630e11 },
        { 9.593e13, 5.433e14, 3.942e12, 1.568e10, 7.566e12, 1.049e11 },
        { 4.669e12, 9.584e13, 1.252e11, 2.124e8, 4.868e12, 8.960e10 },
        { 2.592e11, 1.836e13, 4.607e9, 3.445e6, 3.215e12, 8.000e10 },
        { 1.575e10, 3.707e12, 1.880e8, 6.351e4, 2.154e12, 7.231e10 },
        { 1.038e9, 7.840e11, 8.410e6, 1.313e3, 1.461e12, 6.556e10 },
        { 7.377e7, 1.732e11, 4.105e5, 3.027e1, 1.001e12, 5.961e10 },
        { 5.641e6, 3.989e10, 2.177e4, 7.741e-1, 6.933e11, 5.434e10 },
        { 4.626e5, 9.562e9, 1.251e3, 2.188e-2, 4.850e11, 4.967e10 },
    };
    enum { NZ = sizeof z / sizeof z[0] };
    double n[NZ][LV_US76_NSPECIES];
    lv_err err;
    CHECK_OK(lv_us76_number_densities(z, NZ, 50.0, n, &err), &err);
    double worst = 0.0, max_units = 0.0;
    for (size_t i = 0; i < NZ; i++)
        for (int s = 0; s < LV_US76_NSPECIES; s++) {
            if (tab[i][s] == 0.0) {
                CHECK(n[i][s] == 0.0); /* no hydrogen below 150 km */
                continue;
            }
            const double units = fabs(n[i][s] - tab[i][s]) / ulp_of(tab[i][s], 4);
            const double rel = fabs(n[i][s] / tab[i][s] - 1.0);
            if (rel > worst)
                worst = rel;
            if (units > max_units)
                max_units = units;
            /* Printed to 4 digits: within 1 unit (the document's own integration differs
             * slightly: 8 of 74 values are 0.50-0.70 units off), except H above 500 km,
             * which the model puts up to 1.8e-4 low (4.9661e10 for 4.967e10 at 1000 km). */
            const double allowed = (s == LV_US76_H && z[i] > 500e3) ? 1.5 : 1.0;
            check_count_++;
            if (!(units <= allowed)) {
                check_failures_++;
                fprintf(stderr, "n[%d] at %.0f km: %.5g, Table VIII %.4g (%.2f units)\n", s,
                        z[i] / 1e3, n[i][s], tab[i][s], units);
            }
        }
    printf("number densities vs Table VIII: max rel %.2e, max %.2f units of the 4th digit\n",
           worst, max_units);
    /* Values at 86 km are the document's boundary values. */
    const double z86 = 86000.0;
    double n86[1][LV_US76_NSPECIES];
    CHECK_OK(lv_us76_number_densities(&z86, 1, 50.0, n86, &err), &err);
    CHECK(n86[0][LV_US76_N2] == 1.129794e20 && n86[0][LV_US76_O] == 8.6e16);
}

/* The Hermite table reproduces the fine-grid integration between its nodes. */
static void test_table_interpolation(const lv_atmo *atm)
{
    enum { NQ = 2000 };
    static const double MI[LV_US76_NSPECIES] = { 28.0134, 15.9994, 31.9988,
                                                 39.948,  4.0026,  1.00797 };
    double *z = malloc(NQ * sizeof *z);
    double(*n)[LV_US76_NSPECIES] = malloc(NQ * sizeof *n);
    CHECK(z != NULL && n != NULL);
    if (z == NULL || n == NULL) {
        free(z);
        free(n);
        return;
    }
    for (size_t i = 0; i < NQ; i++) /* 86.1 km to 285.9 km, every 100 m, off the nodes */
        z[i] = 86100.0 + 100.0 * (double)i;
    lv_err err;
    CHECK_OK(lv_us76_number_densities(z, NQ, 50.0, n, &err), &err);
    double worst_p = 0.0, worst_rho = 0.0;
    for (size_t i = 0; i < NQ; i++) {
        double N = 0.0, R = 0.0;
        for (int s = 0; s < LV_US76_NSPECIES; s++) {
            N += n[i][s];
            R += n[i][s] * MI[s];
        }
        lv_atmo_state st;
        CHECK_OK(lv_atmo_eval(atm, z[i], &st, &err), &err);
        const double ep = fabs(st.p / (N * 1.380622e-23 * st.T) - 1.0);
        const double er = fabs(st.rho / (R / 6.022169e26) - 1.0);
        worst_p = ep > worst_p ? ep : worst_p;
        worst_rho = er > worst_rho ? er : worst_rho;
    }
    CHECK(worst_p < 1e-6);
    CHECK(worst_rho < 1e-6);
    printf("table interpolation vs direct integration: p %.2e, rho %.2e\n", worst_p,
           worst_rho);
    free(z);
    free(n);
}

/* Continuity at the layer boundaries: values just below and just above agree. */
static void test_continuity(const lv_atmo *atm)
{
    const double zb[] = { z_of_H(11000.0), z_of_H(20000.0), z_of_H(32000.0),
                          z_of_H(47000.0), z_of_H(51000.0), z_of_H(71000.0),
                          80000.0,         91000.0,         95000.0,
                          97000.0,         100000.0,        115000.0,
                          120000.0,        500000.0 };
    lv_err err;
    for (size_t i = 0; i < sizeof zb / sizeof zb[0]; i++) {
        lv_atmo_state lo, hi;
        const double dz = 1e-6 * (1.0 + zb[i] / 1e5);
        CHECK_OK(lv_atmo_eval(atm, zb[i] - dz, &lo, &err), &err);
        CHECK_OK(lv_atmo_eval(atm, zb[i] + dz, &hi, &err), &err);
        CHECK_REL(lo.T, hi.T, 1e-9);
        CHECK_REL(lo.p, hi.p, 1e-9);
        CHECK_REL(lo.rho, hi.rho, 1e-9);
        CHECK_REL(lo.a, hi.a, 1e-9);
        CHECK_REL(lo.mu, hi.mu, 1e-9);
    }
    /* 110 km: the elliptical segment, eq. (27), with the published Tc, A and a ends at
     * 239.99973 K, not T9 = 240 K; T, rho, a and mu jump by about 1e-6. */
    lv_atmo_state lo, hi;
    CHECK_OK(lv_atmo_eval(atm, 110000.0 - 1e-6, &lo, &err), &err);
    CHECK_OK(lv_atmo_eval(atm, 110000.0, &hi, &err), &err);
    CHECK_CLOSE(lo.T, hi.T, 3e-4);
    CHECK_REL(lo.p, hi.p, 1e-9);
    CHECK_REL(lo.rho, hi.rho, 2e-6);
    /* 86 km: the lower (geopotential) and upper (species) formulations meet with the
     * small mismatch of the document itself (both print 3.7338e-1 Pa, 6.958e-6 kg/m^3). */
    CHECK_OK(lv_atmo_eval(atm, 86000.0 - 1e-6, &lo, &err), &err);
    CHECK_OK(lv_atmo_eval(atm, 86000.0, &hi, &err), &err);
    CHECK_REL(lo.T, hi.T, 1e-6);
    CHECK_REL(lo.p, hi.p, 2e-5);
    CHECK_REL(lo.rho, hi.rho, 2e-5);
    CHECK_REL(lo.a, hi.a, 1e-5);
    CHECK_REL(lo.M, hi.M, 1e-5);
    printf("jump at 86 km: T %.1e, p %.1e, rho %.1e, M %.1e\n", fabs(hi.T / lo.T - 1.0),
           fabs(hi.p / lo.p - 1.0), fabs(hi.rho / lo.rho - 1.0), fabs(hi.M / lo.M - 1.0));
    /* 150 km: hydrogen starts (Table VIII has none below); N jumps by n_H / N = 7e-6. */
    CHECK_OK(lv_atmo_eval(atm, 150000.0 - 1e-6, &lo, &err), &err);
    CHECK_OK(lv_atmo_eval(atm, 150000.0, &hi, &err), &err);
    CHECK_REL(lo.p, hi.p, 1e-5);
    CHECK_REL(lo.rho, hi.rho, 1e-6);

    /* Pressure and density fall monotonically over the whole range. */
    lv_atmo_state prev;
    CHECK_OK(lv_atmo_eval(atm, LV_ATMO_ALT_MIN, &prev, &err), &err);
    int mono = 1;
    for (double z = LV_ATMO_ALT_MIN + 50.0; z <= LV_ATMO_ALT_MAX; z += 50.0) {
        lv_atmo_state s;
        if (lv_atmo_eval(atm, z, &s, &err) != LV_OK || !(s.p < prev.p) || !(s.rho < prev.rho))
            mono = 0;
        prev = s;
    }
    CHECK(mono);
}

static void test_errors(const lv_atmo *atm)
{
    lv_atmo_state s;
    lv_err err;
    CHECK_FAILS(lv_atmo_eval(atm, -5000.5, &s, &err), &err, LV_ERR_INPUT, "-5000.5 m");
    CHECK_FAILS(lv_atmo_eval(atm, -5000.5, &s, &err), &err, LV_ERR_INPUT,
                "-5000 m to 1000000 m");
    CHECK_FAILS(lv_atmo_eval(atm, 1000001.0, &s, &err), &err, LV_ERR_INPUT, "1000001 m");
    CHECK_FAILS(lv_atmo_eval(atm, NAN, &s, &err), &err, LV_ERR_INPUT, "NaN");
    CHECK_FAILS(lv_atmo_eval(atm, INFINITY, &s, &err), &err, LV_ERR_INPUT, "'us76'");
    CHECK(lv_atmo_eval(atm, NAN, &s, NULL) == LV_ERR_INPUT); /* err may be NULL */
    CHECK_OK(lv_atmo_eval(atm, LV_ATMO_ALT_MIN, &s, &err), &err);
    CHECK_OK(lv_atmo_eval(atm, LV_ATMO_ALT_MAX, &s, &err), &err);

    lv_atmo *bad = NULL;
    CHECK_FAILS(lv_atmo_create("us67", &bad, &err), &err, LV_ERR_NOTFOUND, "'us76'");
    CHECK(bad == NULL);
    CHECK_FAILS(lv_atmo_create("expo", &bad, &err), &err, LV_ERR_NOTFOUND,
                "did you mean 'exp'");
    const lv_atmo_model *m = NULL;
    CHECK_OK(lv_atmo_model_find("exp", &m, &err), &err);
    CHECK(m == &lv_atmo_exp);
    CHECK(lv_atmo_model_count() == 4);
    CHECK(lv_atmo_model_at(0) == &lv_atmo_us76 && lv_atmo_model_at(4) == NULL);
    CHECK_FAILS(lv_atmo_set((lv_atmo *)atm, "rho0", 1.0, &err), &err, LV_ERR_NOTFOUND,
                "'rho0'");

    /* The CLI entry point: stops at the first bad altitude, names it. */
    const double alts[] = { 0.0, 2e6 };
    lv_atmo_state out[2];
    CHECK_OK(lv_atmo_eval_by_name("us76", alts, 1, out, &err), &err);
    CHECK_CLOSE(out[0].p, 101325.0, 1e-9);
    CHECK_FAILS(lv_atmo_eval_by_name("us76", alts, 2, out, &err), &err, LV_ERR_INPUT,
                "2000000 m");
    CHECK_FAILS(lv_atmo_eval_by_name("US76", alts, 1, out, &err), &err, LV_ERR_NOTFOUND,
                "unknown atmosphere model 'US76'");
}

static void test_exponential(void)
{
    lv_atmo *atm = NULL;
    lv_err err;
    lv_atmo_state s;
    CHECK_OK(lv_atmo_create("exp", &atm, &err), &err);
    if (atm == NULL)
        return;
    CHECK_OK(lv_atmo_eval(atm, 0.0, &s, &err), &err);
    CHECK_CLOSE(s.rho, 1.225, 1e-15);
    CHECK_CLOSE(s.p, 101325.0, 0.1); /* ideal gas with the rounded 1.225 kg/m^3 */
    CHECK_CLOSE(s.a, 340.294, 0.0005);
    CHECK_CLOSE(s.mu, 1.7894e-5, 0.00005e-5);
    CHECK_OK(lv_atmo_eval(atm, 7200.0, &s, &err), &err);
    CHECK_REL(s.rho, 1.225 / exp(1.0), 1e-14);

    CHECK_OK(lv_atmo_set(atm, "rho0", 2.0, &err), &err);
    CHECK_OK(lv_atmo_set(atm, "H", 8000.0, &err), &err);
    CHECK_OK(lv_atmo_set(atm, "T", 250.0, &err), &err);
    CHECK_OK(lv_atmo_eval(atm, 16000.0, &s, &err), &err);
    CHECK_REL(s.rho, 2.0 * exp(-2.0), 1e-14);
    CHECK_REL(s.p, s.rho * 8314.32 * 250.0 / 28.9644, 1e-14);
    CHECK(s.T == 250.0 && s.M == 28.9644);
    const lv_atmo_exp_par *par = lv_atmo_par(atm);
    CHECK(par->rho0 == 2.0 && par->H == 8000.0 && par->T == 250.0);

    CHECK_FAILS(lv_atmo_set(atm, "rho", 1.0, &err), &err, LV_ERR_NOTFOUND,
                "did you mean 'rho0'");
    CHECK_FAILS(lv_atmo_set(atm, "H", -1.0, &err), &err, LV_ERR_INPUT, "'H' = -1");
    CHECK_FAILS(lv_atmo_set(atm, "T", NAN, &err), &err, LV_ERR_INPUT, "'T'");
    CHECK_FAILS(lv_atmo_eval(atm, -6000.0, &s, &err), &err, LV_ERR_INPUT, "'exp'");
    CHECK_FAILS(lv_atmo_eval(atm, NAN, &s, &err), &err, LV_ERR_INPUT, "NaN");
    lv_atmo_free(atm);
    lv_atmo_free(NULL);
}

/* The upper-atmosphere table compiled into the library (generated at build time) is bit for
 * bit what lv_us76_upper_build computes now, with the same step and node spacing. */
static void test_generated_table(void)
{
    lv_us76_upper up;
    lv_err err;
    CHECK_OK(lv_us76_upper_build(&up, LV_US76_UPPER_H, LV_US76_UPPER_NODE_DZ, &err), &err);
    const lv_us76_upper *g = &lv_us76_upper_1976;
    CHECK(up.n == g->n && up.z0 == g->z0 && up.dz == g->dz && g->own == NULL);
    size_t differ = 0;
    for (size_t i = 0; up.n == g->n && i < 8 * up.n; i++)
        differ += memcmp(&up.c[i], &g->c[i], sizeof(double)) != 0;
    CHECK(differ == 0);
    lv_us76_upper_release(&up);
    CHECK(up.c == NULL && up.own == NULL);
}

int main(void)
{
    lv_atmo *atm = NULL;
    lv_err err;
    CHECK_OK(lv_atmo_create("us76", &atm, &err), &err);
    if (atm == NULL)
        return check_report("test_atmosphere");
    CHECK(lv_atmo_model_of(atm) == &lv_atmo_us76);
    test_table_values(atm);
    test_sound_viscosity(atm);
    test_number_densities();
    test_table_interpolation(atm);
    test_continuity(atm);
    test_errors(atm);
    test_exponential();
    test_generated_table();
    lv_atmo_free(atm);
    return check_report("test_atmosphere");
}
