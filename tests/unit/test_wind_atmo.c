/* test_wind_atmo.c - the "table" atmosphere and wind tables (lv_atmosphere.h, lv_wind.h):
 * a table written from US76 reproduces it on the grid and stays within a derived
 * interpolation bound between; file errors name the file, line and column; wind tables are
 * exact on the grid, linear between and clamped outside; in the 3-DoF model a uniform wind
 * on a body at rest relative to the ground gives drag q S CD, q = rho W^2 / 2, along the
 * wind. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_dof3.h"
#include "lvsim/lv_io.h"
#include "lvsim/lv_planet.h"
#include "lvsim/lv_sim.h"
#include "lvsim/lv_wind.h"

#define DEG (M_PI / 180.0)

/* US76 constants (document Table 2) for the reference values and bounds. */
#define RSTAR 8314.32
#define M0 28.9644
#define G0 9.80665
#define R0 6356766.0
#define GAMMA 1.40

#define DZ 1000.0  /* m, grid spacing of the US76 table */
#define NZ 101     /* 0 .. 100 km */

#define US76_CSV "wind_atmo_us76.csv"

static void write_text(const char *path, const char *text)
{
    FILE *fp = fopen(path, "w");
    CHECK(fp != NULL);
    if (fp == NULL)
        return;
    fputs(text, fp);
    fclose(fp);
}

/* MAT v4 (little-endian double, full matrix): header type 0, rows, cols, imagf 0, name
 * length with NUL; then the name and the values column by column. a[r * cols + c]. */
static void write_mat4(const char *path, const char *name, const double *a, int32_t rows,
                       int32_t cols)
{
    FILE *fp = fopen(path, "wb");
    CHECK(fp != NULL);
    if (fp == NULL)
        return;
    const int32_t hdr[5] = { 0, rows, cols, 0, (int32_t)strlen(name) + 1 };
    fwrite(hdr, sizeof hdr[0], 5, fp);
    fwrite(name, 1, strlen(name) + 1, fp);
    for (int32_t c = 0; c < cols; c++)
        for (int32_t r = 0; r < rows; r++)
            fwrite(&a[r * cols + c], sizeof(double), 1, fp);
    fclose(fp);
}

/* The US76 table: T, p, rho at 0, 1, .., 100 km, printed with 17 digits (exact). */
static void write_us76_csv(const lv_atmo *us, const char *path, int with_a_mu)
{
    FILE *fp = fopen(path, "w");
    CHECK(fp != NULL);
    if (fp == NULL)
        return;
    fprintf(fp, "# US76 every km, written by test_wind_atmo\n");
    if (with_a_mu) /* columns in another order: resolved by name */
        fprintf(fp, "h [m], rho [kg/m3], a [m/s], T [K], mu [Pa s], p [Pa]\n");
    else
        fprintf(fp, "h [m], T [K], p [Pa], rho [kg/m3]\n");
    for (int i = 0; i < NZ; i++) {
        lv_atmo_state s;
        lv_err err;
        const double z = i * DZ;
        CHECK_OK(lv_atmo_eval(us, z, &s, &err), &err);
        if (with_a_mu)
            fprintf(fp, "%.17g, %.17g, %.17g, %.17g, %.17g, %.17g\n", z, s.rho, s.a, s.T, s.mu,
                    s.p);
        else
            fprintf(fp, "%.17g, %.17g, %.17g, %.17g\n", z, s.T, s.p, s.rho);
    }
    fclose(fp);
}

/* ---- (1) the US76 table: grid points, interpolation, the bound ------------------------ */

/* Geometric altitude of a geopotential height H, inverse of US76 eq. (18). */
static double z_of_H(double H)
{
    return R0 * H / (R0 - H);
}

/* Bounds on the interpolation error below 86 km, derived from the US76 layer equations.
 * With H the geopotential height (dH/dz = (r0/(r0+z))^2 <= 1, |d2H/dz2| <= 2/r0), T_M
 * linear in H with gradient L in each layer and gMR = g0 M0 / R*:
 *   d ln p / dH = -gMR / T_M              (hydrostatic, eqs. 33a, b): continuous
 *   d2 ln p / dH2 = gMR L / T_M^2
 *   ln rho = ln p - ln T_M + const (eq. 42):  d ln rho / dH = -(gMR + L) / T_M,
 *   which jumps by -dL / T_M at a layer base; d2 ln rho / dH2 = L (gMR + L) / T_M^2.
 * So |f''(z)| <= |d2f/dH2| + |df/dH| 2/r0 and linear interpolation over an interval of
 * length D errs by at most D^2/8 max|f''|, plus |slope jump| D/4 for each kink inside.
 * The largest |L|/T_M^2 terms are in the first layer (L = -0.0065 K/m', T_M >= 216.65 K);
 * the smallest T_M below 86 km is 186.87 K. */
static double bound_below_86km(double z0, double z1, int rho)
{
    static const double HB[] = { 11000.0, 20000.0, 32000.0, 47000.0, 51000.0, 71000.0 };
    static const double LB[] = { -0.0065, 0.0, 0.0010, 0.0028, 0.0, -0.0028, -0.0020 };
    static const double TMB[] = { 216.65, 216.65, 228.65, 270.65, 270.65, 214.65 };
    const double gMR = G0 * M0 / RSTAR, D = z1 - z0, Lmax = 0.0065;
    const double Tmin1 = 216.65, Tmin = 186.87;
    double f2 = rho ? Lmax * (gMR - Lmax) / (Tmin1 * Tmin1) + (gMR + Lmax) / Tmin * 2.0 / R0
                    : gMR * Lmax / (Tmin1 * Tmin1) + gMR / Tmin * 2.0 / R0;
    double b = D * D / 8.0 * f2;
    if (rho)
        for (int k = 0; k < 6; k++) {
            const double zk = z_of_H(HB[k]);
            if (zk > z0 && zk < z1)
                b += fabs(LB[k + 1] - LB[k]) / TMB[k] * D / 4.0;
        }
    return b;
}

/* Above 86 km the profile comes from the species integration; the bound uses the largest
 * second difference of ln f over the interval (step 50 m), doubled for safety. */
static double bound_above_86km(const lv_atmo *us, double z0, double z1, int rho)
{
    const double d = 50.0;
    double f2 = 0.0;
    for (double z = z0; z <= z1 + 1e-9; z += d) {
        lv_atmo_state a, b, c;
        lv_atmo_eval(us, z - d, &a, NULL);
        lv_atmo_eval(us, z, &b, NULL);
        lv_atmo_eval(us, z + d, &c, NULL);
        const double fa = rho ? log(a.rho) : log(a.p), fb = rho ? log(b.rho) : log(b.p);
        const double fc = rho ? log(c.rho) : log(c.p);
        const double s = fabs(fa - 2.0 * fb + fc) / (d * d);
        f2 = s > f2 ? s : f2;
    }
    return 2.0 * (z1 - z0) * (z1 - z0) / 8.0 * f2;
}

static void test_us76_table(const lv_atmo *us)
{
    lv_err err;
    lv_atmo *tab = NULL;
    write_us76_csv(us, US76_CSV, 0);
    CHECK_OK(lv_atmo_create_table(US76_CSV, NULL, &tab, &err), &err);
    if (tab == NULL)
        return;
    CHECK(lv_atmo_model_of(tab) == &lv_atmo_table);

    /* Grid points: T exactly (and mu up to 80 km); p and rho through exp(ln x), which rounds by at most
     * |ln x| eps + eps relative (|ln x| < 17 here): 1e-14. a from T with M0 equals US76's
     * eq. (50) with T_M = T below 80 km; above, T_M = T M0/M, so the table's a is
     * sqrt(gamma R* T / M0) (docs/atmosphere.md). */
    for (int i = 0; i < NZ; i++) {
        const double z = i * DZ;
        lv_atmo_state s, r;
        CHECK_OK(lv_atmo_eval(tab, z, &s, &err), &err);
        lv_atmo_eval(us, z, &r, NULL);
        CHECK(s.T == r.T);
        CHECK_REL(s.p, r.p, 1e-14);
        CHECK_REL(s.rho, r.rho, 1e-14);
        /* mu from Sutherland's law with the table's T; US76 below 86 km uses T_M (its
         * tables' convention: docs/atmosphere.md), equal to T up to 80 km */
        if (z <= 80e3)
            CHECK_REL(s.mu, r.mu, 1e-15);
        CHECK_REL(s.mu, 1.458e-6 * s.T * sqrt(s.T) / (s.T + 110.4), 1e-15);
        CHECK(s.M == M0);
        if (z <= 80e3)
            CHECK_REL(s.a, r.a, 1e-15);
        CHECK_REL(s.a, sqrt(GAMMA * RSTAR * s.T / M0), 1e-15);
    }

    /* Between grid points: T linear, ln p and ln rho linear (log-linear interpolation),
     * and the distance to US76 within the bounds above. */
    double worst[2] = { 0.0, 0.0 }, worst_ratio[2] = { 0.0, 0.0 };
    for (int i = 0; i + 1 < NZ; i++) {
        const double z0 = i * DZ, z1 = z0 + DZ;
        lv_atmo_state s0, s1;
        lv_atmo_eval(tab, z0, &s0, NULL);
        lv_atmo_eval(tab, z1, &s1, NULL);
        for (int q = 1; q < 4; q++) {
            const double t = q / 4.0, z = z0 + t * DZ;
            lv_atmo_state s, r;
            CHECK_OK(lv_atmo_eval(tab, z, &s, &err), &err);
            lv_atmo_eval(us, z, &r, NULL);
            CHECK_CLOSE(s.T, s0.T + t * (s1.T - s0.T), 1e-12);
            CHECK_CLOSE(log(s.p), log(s0.p) + t * (log(s1.p) - log(s0.p)), 1e-13);
            CHECK_CLOSE(log(s.rho), log(s0.rho) + t * (log(s1.rho) - log(s0.rho)), 1e-13);
            for (int k = 0; k < 2; k++) {
                const double e = fabs(log(k ? s.rho / r.rho : s.p / r.p));
                const double b = z1 <= 86e3 ? bound_below_86km(z0, z1, k)
                                            : bound_above_86km(us, z0, z1, k);
                check_count_++;
                if (!(e <= b)) {
                    check_failures_++;
                    fprintf(stderr, "%s at z = %.1f m: |ln(table/us76)| = %.3e > bound %.3e\n",
                            k ? "rho" : "p", z, e, b);
                }
                worst[k] = e > worst[k] ? e : worst[k];
                worst_ratio[k] = e / b > worst_ratio[k] ? e / b : worst_ratio[k];
            }
        }
    }
    printf("us76 table, 1 km grid: max |ln(table/us76)| p %.3e, rho %.3e between points "
           "(at most %.0f%%, %.0f%% of the bound)\n",
           worst[0], worst[1], 100.0 * worst_ratio[0], 100.0 * worst_ratio[1]);

    /* Outside the table: an error naming the altitude and the range, no extrapolation. */
    lv_atmo_state s;
    CHECK_FAILS(lv_atmo_eval(tab, 100001.0, &s, &err), &err, LV_ERR_INPUT, "100001 m");
    CHECK_FAILS(lv_atmo_eval(tab, -1.0, &s, &err), &err, LV_ERR_INPUT, "0 m to 100000 m");
    CHECK_FAILS(lv_atmo_eval(tab, NAN, &s, &err), &err, LV_ERR_INPUT, "NaN");
    CHECK(lv_atmo_eval(tab, INFINITY, &s, NULL) == LV_ERR_INPUT);
    CHECK_FAILS(lv_atmo_set(tab, "rho0", 1.0, &err), &err, LV_ERR_NOTFOUND, "'rho0'");
    lv_atmo_free(tab);

    /* a and mu from the file, columns in any order */
    write_us76_csv(us, US76_CSV, 1);
    CHECK_OK(lv_atmo_create_table(US76_CSV, NULL, &tab, &err), &err);
    if (tab == NULL)
        return;
    for (int i = 80; i < NZ; i += 5) {
        lv_atmo_state r, r1;
        lv_atmo_eval(us, i * DZ, &r, NULL);
        lv_atmo_eval(us, i * DZ + DZ, &r1, NULL);
        CHECK_OK(lv_atmo_eval(tab, i * DZ, &s, &err), &err);
        CHECK(s.a == r.a && s.mu == r.mu && s.T == r.T);
        CHECK_REL(s.p, r.p, 1e-14);
        if (i + 1 < NZ) { /* linear between */
            CHECK_OK(lv_atmo_eval(tab, i * DZ + 0.25 * DZ, &s, &err), &err);
            CHECK_CLOSE(s.a, r.a + 0.25 * (r1.a - r.a), 1e-12);
            CHECK_REL(s.mu, r.mu + 0.25 * (r1.mu - r.mu), 1e-14);
        }
    }
    lv_atmo_free(tab);
}

/* ---- (2) atmosphere file errors, MAT files ----------------------------------------------- */

static void test_atmo_files(void)
{
    lv_err err;
    lv_atmo *a = NULL;
    const char *path = "wind_atmo_bad.csv";

    write_text(path, "h [m], T [K], p [Pa]\n0, 288.15, 101325\n1000, 281.65, 89876\n");
    CHECK_FAILS(lv_atmo_create_table(path, NULL, &a, &err), &err, LV_ERR_INPUT,
                "wind_atmo_bad.csv");
    CHECK_FAILS(lv_atmo_create_table(path, NULL, &a, &err), &err, LV_ERR_INPUT,
                "no output 'rho'");
    CHECK(a == NULL);

    write_text(path, "h [m], T [K], p [Pa], rh [kg/m3]\n0, 288.15, 101325, 1.225\n"
                     "1000, 281.65, 89876, 1.11\n");
    CHECK_FAILS(lv_atmo_create_table(path, NULL, &a, &err), &err, LV_ERR_INPUT,
                "did you mean 'rh'");

    /* negative p on line 6 (comments and blank lines count) */
    write_text(path, "# comment\nh [m], T [K], p [Pa], rho [kg/m3]\n\n0, 288.15, 101325, 1.225 "
                     "# sea level\n# another\n1000, 281.65, -5, 1.11\n");
    CHECK_FAILS(lv_atmo_create_table(path, NULL, &a, &err), &err, LV_ERR_INPUT,
                "wind_atmo_bad.csv:6: p = -5 at altitude 1000 m must be positive");
    write_text(path, "h [m], T [K], p [Pa], rho [kg/m3]\n0, 288.15, 101325, 0\n"
                     "1000, 281.65, 89876, 1.11");
    CHECK_FAILS(lv_atmo_create_table(path, NULL, &a, &err), &err, LV_ERR_INPUT,
                "wind_atmo_bad.csv:2: rho = 0");

    write_text(path, "h [m], T [K], p [Pa], rho [kg/m3]\n0, 288.15, 101325, 1.225\n"
                     "0, 281.65, 89876, 1.11\n");
    CHECK_FAILS(lv_atmo_create_table(path, NULL, &a, &err), &err, LV_ERR_INPUT,
                "wind_atmo_bad.csv:3:1: breakpoint 0 is not greater");
    write_text(path, "h [km], T [K], p [Pa], rho [kg/m3]\n0, 288.15, 101325, 1.225\n"
                     "1, 281.65, 89876, 1.11\n");
    CHECK_FAILS(lv_atmo_create_table(path, NULL, &a, &err), &err, LV_ERR_INPUT,
                "unit 'km'; expected 'm'");
    write_text(path, "h [m], T [K], p [Pa], rho [kg/m3], mu_ [Pa s]\n0, 288.15, 101325, 1.225, "
                     "1.8e-5\n1000, 281.65, 89876, 1.11, 1.7e-5\n");
    CHECK_FAILS(lv_atmo_create_table(path, NULL, &a, &err), &err, LV_ERR_INPUT,
                "unknown column 'mu_'; did you mean 'mu'");
    CHECK_FAILS(lv_atmo_create_table("wind_atmo_missing.csv", NULL, &a, &err), &err,
                LV_ERR_IO, "wind_atmo_missing.csv");
    CHECK_FAILS(lv_atmo_create_table(path, "atm", &a, &err), &err, LV_ERR_INPUT, "CSV");
    CHECK_FAILS(lv_atmo_create("table", &a, &err), &err, LV_ERR_INPUT, "lv_atmo_create_table");
    CHECK(lv_atmo_model_count() == 4 && lv_atmo_model_at(2) == &lv_atmo_table);
    remove(path);

    /* MAT (Modelica CombiTable1D layout): columns h, T, p, rho by position; a from T */
    const double m[3 * 4] = { 0.0, 250.0, 1.0e5, 1.0, 1000.0, 240.0, 8.0e4, 0.5,
                              3000.0, 200.0, 2.0e4, 0.25 };
    write_mat4("wind_atmo.mat", "atm", m, 3, 4);
    CHECK_OK(lv_atmo_create_table("wind_atmo.mat", "atm", &a, &err), &err);
    if (a != NULL) {
        lv_atmo_state s;
        CHECK_OK(lv_atmo_eval(a, 2000.0, &s, &err), &err); /* midway 1000 .. 3000 m */
        CHECK_CLOSE(s.T, 220.0, 1e-12);
        CHECK_REL(s.p, sqrt(8.0e4 * 2.0e4), 1e-14); /* geometric mean */
        CHECK_REL(s.rho, sqrt(0.5 * 0.25), 1e-14);
        CHECK_REL(s.a, sqrt(GAMMA * RSTAR * 220.0 / M0), 1e-15);
        CHECK_REL(s.mu, 1.458e-6 * 220.0 * sqrt(220.0) / (220.0 + 110.4), 1e-15);
        CHECK_FAILS(lv_atmo_eval(a, 3000.5, &s, &err), &err, LV_ERR_INPUT,
                    "0 m to 3000 m");
        lv_atmo_free(a);
    }
    const double mneg[2 * 4] = { 0.0, 250.0, 1.0e5, 1.0, 1000.0, 240.0, 8.0e4, -0.5 };
    write_mat4("wind_atmo.mat", "atm", mneg, 2, 4);
    CHECK_FAILS(lv_atmo_create_table("wind_atmo.mat", "atm", &a, &err), &err, LV_ERR_INPUT,
                "wind_atmo.mat: row 2: rho = -0.5");
    CHECK_FAILS(lv_atmo_create_table("wind_atmo.mat", "atn", &a, &err), &err, LV_ERR_NOTFOUND,
                "'atm'");
    CHECK_FAILS(lv_atmo_create_table("wind_atmo.mat", NULL, &a, &err), &err, LV_ERR_INPUT,
                "variable");
    remove("wind_atmo.mat");
}

/* ---- (3) wind tables ---------------------------------------------------------------------- */

static void test_wind(void)
{
    lv_err err;
    lv_wind *w = NULL;
    const char *path = "wind_atmo_wind.csv";
    write_text(path, "h [m], north [m/s], east [m/s], down [m/s]\n"
                     "0,    1,  2,  0.5\n"
                     "1000, 3, -4,  0\n"
                     "5000, 11, 6, -1\n");
    CHECK_OK(lv_wind_create_table(path, NULL, &w, &err), &err);
    if (w == NULL)
        return;
    double h_lo, h_hi, v[3];
    lv_wind_range(w, &h_lo, &h_hi);
    CHECK(h_lo == 0.0 && h_hi == 5000.0);
    lv_table_cursor cur = LV_TABLE_CURSOR_INIT;
    static const double H[] = { 0.0, 1000.0, 5000.0 };
    static const double V[3][3] = { { 1, 2, 0.5 }, { 3, -4, 0 }, { 11, 6, -1 } };
    for (int i = 0; i < 3; i++) { /* exact on the grid */
        CHECK_OK(lv_wind_eval(w, &cur, H[i], v, &err), &err);
        CHECK(v[0] == V[i][0] && v[1] == V[i][1] && v[2] == V[i][2]);
    }
    for (int i = 0; i < 2; i++) /* linear between */
        for (int q = 1; q < 8; q++) {
            const double t = q / 8.0, h = H[i] + t * (H[i + 1] - H[i]);
            CHECK_OK(lv_wind_eval(w, &cur, h, v, &err), &err);
            for (int k = 0; k < 3; k++)
                CHECK_CLOSE(v[k], V[i][k] + t * (V[i + 1][k] - V[i][k]), 1e-14);
        }
    /* clamped: above the top the top row holds, below the bottom the bottom row */
    CHECK_OK(lv_wind_eval(w, &cur, 8.0e4, v, &err), &err);
    CHECK(v[0] == 11.0 && v[1] == 6.0 && v[2] == -1.0);
    CHECK_OK(lv_wind_eval(w, NULL, -200.0, v, &err), &err);
    CHECK(v[0] == 1.0 && v[1] == 2.0 && v[2] == 0.5);
    CHECK_FAILS(lv_wind_eval(w, &cur, NAN, v, &err), &err, LV_ERR_INPUT, "NaN");

    /* the lv_wind_fn adapter, as the 3-DoF model calls it */
    lv_wind_user wu = LV_WIND_USER_INIT(w);
    double vf[3];
    CHECK(lv_wind_fn_table(0.0, 3000.0, 0.1, 0.2, vf, &wu) == 0);
    CHECK_CLOSE(vf[0], 7.0, 1e-14);
    CHECK_CLOSE(vf[1], 1.0, 1e-14);
    CHECK_CLOSE(vf[2], -0.5, 1e-14);
    CHECK(wu.cur.i[0] == 1);
    CHECK(lv_wind_fn_table(0.0, NAN, 0.1, 0.2, vf, &wu) > 0);
    lv_wind_free(w);
    w = NULL;

    /* no down column (names with the v_ prefix, any order): down is 0 */
    write_text(path, "alt [m], v_east [m/s], v_north [m/s]\n0, 5, -1\n2000, 15, 3\n");
    CHECK_OK(lv_wind_create_table(path, NULL, &w, &err), &err);
    if (w != NULL) {
        CHECK_OK(lv_wind_eval(w, NULL, 500.0, v, &err), &err);
        CHECK_CLOSE(v[0], 0.0, 1e-14);
        CHECK_CLOSE(v[1], 7.5, 1e-14);
        CHECK(v[2] == 0.0);
        lv_wind_free(w);
        w = NULL;
    }

    write_text(path, "h [m], north [m/s]\n0, 1\n1000, 2\n");
    CHECK_FAILS(lv_wind_create_table(path, NULL, &w, &err), &err, LV_ERR_INPUT,
                "no column 'east'");
    write_text(path, "h [m], north [m/s], east [m/s], dwn [m/s]\n0, 1, 2, 3\n1000, 2, 3, 4\n");
    CHECK_FAILS(lv_wind_create_table(path, NULL, &w, &err), &err, LV_ERR_INPUT,
                "unknown column 'dwn'; did you mean 'down'");
    write_text(path, "h [m], north [kt], east [m/s]\n0, 1, 2\n1000, 2, 3\n");
    CHECK_FAILS(lv_wind_create_table(path, NULL, &w, &err), &err, LV_ERR_INPUT, "'kt'");
    write_text(path, "h [m], north [m/s], east [m/s]\n0, 1, 2\n1000, 2, 3\n900, 2, 3\n");
    CHECK_FAILS(lv_wind_create_table(path, NULL, &w, &err), &err, LV_ERR_INPUT,
                "wind_atmo_wind.csv:4:1");
    CHECK(w == NULL);
    remove(path);

    /* MAT: h, north, east by position */
    const double m[2 * 3] = { 0.0, 4.0, -2.0, 1000.0, 8.0, 2.0 };
    write_mat4("wind_atmo_wind.mat", "wind", m, 2, 3);
    CHECK_OK(lv_wind_create_table("wind_atmo_wind.mat", "wind", &w, &err), &err);
    if (w != NULL) {
        CHECK_OK(lv_wind_eval(w, NULL, 250.0, v, &err), &err);
        CHECK_CLOSE(v[0], 5.0, 1e-14);
        CHECK_CLOSE(v[1], -1.0, 1e-14);
        CHECK(v[2] == 0.0);
        lv_wind_free(w);
    }
    remove("wind_atmo_wind.mat");
}


/* Constant winds and the ends of a table (docs/wind.md): a wind of one value or a table of
 * one row is that value at every altitude; a table's extrapolation is the caller's: clamp
 * (the default), linear (the end interval's line continued), error (an evaluation error
 * naming the altitude and the range). */
static void test_wind_forms(void)
{
    lv_err err;
    lv_wind *w = NULL;
    double v[3], lo, hi;
    CHECK_OK(lv_wind_create_const(5.0, -3.0, 0.25, &w, &err), &err);
    if (w != NULL) {
        CHECK(lv_wind_is_constant(w));
        lv_wind_range(w, &lo, &hi);
        CHECK(lo == -INFINITY && hi == INFINITY);
        const double hs[] = { -4000.0, 0.0, 12345.6, 9.0e5 };
        for (int i = 0; i < 4; i++) {
            CHECK_OK(lv_wind_eval(w, NULL, hs[i], v, &err), &err);
            CHECK(v[0] == 5.0 && v[1] == -3.0 && v[2] == 0.25);
        }
        CHECK_FAILS(lv_wind_eval(w, NULL, NAN, v, &err), &err, LV_ERR_INPUT, "NaN");
        lv_wind_free(w);
        w = NULL;
    }
    CHECK_FAILS(lv_wind_create_const(1.0, NAN, 0.0, &w, &err), &err, LV_ERR_INPUT,
                "must be finite");

    const char *path = "wind_atmo_forms.csv";
    write_text(path, "# a constant wind as a table of one row\nh [m], north [m/s], east [m/s]\n"
                     "100, 2, 7\n");
    CHECK_OK(lv_wind_create_table(path, NULL, &w, &err), &err);
    if (w != NULL) {
        CHECK(lv_wind_is_constant(w));
        CHECK_OK(lv_wind_eval(w, NULL, 0.0, v, &err), &err);
        CHECK(v[0] == 2.0 && v[1] == 7.0 && v[2] == 0.0);
        CHECK_OK(lv_wind_eval(w, NULL, 5.0e4, v, &err), &err);
        CHECK(v[0] == 2.0 && v[1] == 7.0 && v[2] == 0.0);
        lv_wind_free(w);
        w = NULL;
    }
    write_text(path, "h [m], north [m/s], east [m/s]\n");
    CHECK_FAILS(lv_wind_create_table(path, NULL, &w, &err), &err, LV_ERR_INPUT, "no rows");

    write_text(path, "h [m], north [m/s], east [m/s]\n0, 1, 10\n1000, 3, 20\n");
    const lv_table_opts lin = { LV_INTERP_LINEAR, LV_EXTRAP_LINEAR, 0 };
    CHECK_OK(lv_wind_create_table_opts(path, NULL, &lin, &w, &err), &err);
    if (w != NULL) { /* the line through (0, 1) and (1000, 3): north = 1 + h / 500 */
        CHECK(!lv_wind_is_constant(w));
        CHECK_OK(lv_wind_eval(w, NULL, 2000.0, v, &err), &err);
        CHECK_CLOSE(v[0], 5.0, 1e-14);
        CHECK_CLOSE(v[1], 30.0, 1e-13);
        CHECK_OK(lv_wind_eval(w, NULL, -500.0, v, &err), &err);
        CHECK_CLOSE(v[0], 0.0, 1e-14);
        CHECK_CLOSE(v[1], 5.0, 1e-14);
        lv_wind_free(w);
        w = NULL;
    }
    const lv_table_opts strict = { LV_INTERP_LINEAR, LV_EXTRAP_ERROR, 0 };
    CHECK_OK(lv_wind_create_table_opts(path, NULL, &strict, &w, &err), &err);
    if (w != NULL) {
        CHECK_OK(lv_wind_eval(w, NULL, 1000.0, v, &err), &err); /* the ends are inside */
        CHECK(v[0] == 3.0 && v[1] == 20.0);
        CHECK_FAILS(lv_wind_eval(w, NULL, 1000.5, v, &err), &err, LV_ERR_INPUT,
                    "wind: table 'wind_atmo_forms': axis 0 'h' [m] = 1000.5 is outside [0, 1000]");
        lv_wind_user wu = LV_WIND_USER_INIT(w);
        CHECK(lv_wind_fn_table(0.0, -1.0, 0.0, 0.0, v, &wu) == -1); /* left the data: stop */
        CHECK(lv_wind_fn_table(0.0, NAN, 0.0, 0.0, v, &wu) == 1);   /* retry a smaller step */
        lv_wind_free(w);
        w = NULL;
    }
    remove(path);
}

/* ---- (4) the 3-DoF model with a table wind ---------------------------------------------- */
/* A body at rest relative to the ground in a uniform east wind W: the air-relative
 * velocity is v_rel - v_wind = -W east, so q = rho W^2 / 2 and the drag q S CD pushes the
 * body east. Without wind it is zero. At t0 the force follows from the derivatives:
 * f = m (a_eci - g_eci), rotated to NED (the check of test_dof3's aerodynamic test). A
 * wind ignored gives f = 0, one added with the wrong sign f pointing west. */
static void test_dof3_wind(const lv_atmo *us)
{
    lv_err err;
    const lv_planet earth = lv_planet_earth();
    lv_gravity_config gc = { "pointmass", 0, -1, NULL };
    lv_gravity *grav = NULL;
    lv_atmo *atmo = NULL;
    lv_wind *wind = NULL;
    const double W = 40.0, S = 2.0, CD = 0.5, h0 = 3000.0, mass = 1000.0;
    CHECK_OK(lv_gravity_create(&earth, &gc, &grav, &err), &err);
    write_us76_csv(us, US76_CSV, 0);
    CHECK_OK(lv_atmo_create_table(US76_CSV, NULL, &atmo, &err), &err);
    write_text("wind_atmo_const.csv", "h [m], north [m/s], east [m/s]\n"
                                      "-5000, 0, 40\n0, 0, 40\n100000, 0, 40\n");
    CHECK_OK(lv_wind_create_table("wind_atmo_const.csv", NULL, &wind, &err), &err);
    remove("wind_atmo_const.csv");
    if (grav == NULL || atmo == NULL || wind == NULL)
        goto done;

    lv_aero_config aero;
    lv_aero_config_default(&aero);
    aero.s_ref = S;
    aero.coef[0].value = CD;
    lv_wind_user wu = LV_WIND_USER_INIT(wind);
    lv_dof3_config cfg;
    lv_dof3_config_default(&cfg);
    cfg.gravity = grav;
    cfg.atmo = atmo;
    cfg.aero = &aero;
    cfg.m0 = mass;
    cfg.start_lat = 30.0 * DEG;
    cfg.start_lon = 10.0 * DEG;
    cfg.start_h = h0;
    cfg.start_vel = 0.0;

    lv_atmo_state as;
    CHECK_OK(lv_atmo_eval(atmo, h0, &as, &err), &err); /* a grid point: US76 */
    for (int with = 0; with < 2; with++) {
        cfg.wind = with ? lv_wind_fn_table : NULL;
        cfg.wind_user = with ? &wu : NULL;
        lv_dof3 *m = NULL;
        CHECK_OK(lv_dof3_create(&cfg, &m, &err), &err);
        if (m == NULL)
            break;
        lv_result *res = NULL;
        lv_sink mem;
        CHECK_OK(lv_sink_memory_create(&res, &mem, &err), &err);
        lv_sim_settings s;
        lv_sim_settings_default(&s);
        s.result_file = NULL;
        s.start_time = 0.0;
        s.stop_time = 0.2;
        s.method = "dopri5";
        s.tolerance = 1e-10;
        s.output_interval = 0.1;
        s.n_sinks = 1;
        s.sinks = &mem;
        CHECK_OK(lv_simulate(lv_dof3_def(m), lv_dof3_inst(m), &s, NULL, NULL, &err), &err);
        static const char *const names[] = { "time", "r_eci_x", "r_eci_y", "r_eci_z",
                                             "der(v_eci_x)", "der(v_eci_y)", "der(v_eci_z)",
                                             "m", "drag", "q_dyn", "h", "lat", "lon" };
        double o[13];
        for (size_t k = 0; k < 13; k++) {
            size_t col = 0;
            CHECK_OK(lv_result_column(res, names[k], &col, &err), &err);
            o[k] = lv_result_rows(res) > 0 ? lv_result_value(res, 0, col) : NAN;
        }
        CHECK(o[0] == 0.0);
        CHECK_CLOSE(o[10], h0, 1e-6);
        const double q = with ? 0.5 * as.rho * W * W : 0.0, D = q * S * CD;
        CHECK_REL(o[9], q, 1e-12);
        CHECK_REL(o[8], D, 1e-12);

        const double th = lv_frames_theta(&earth, o[0]), c = cos(th), sn = sin(th);
        const double r_eci[3] = { o[1], o[2], o[3] }, a_eci[3] = { o[4], o[5], o[6] };
        const double r_ecef[3] = { c * r_eci[0] + sn * r_eci[1], -sn * r_eci[0] + c * r_eci[1],
                                   r_eci[2] };
        const double a_ecef[3] = { c * a_eci[0] + sn * a_eci[1], -sn * a_eci[0] + c * a_eci[1],
                                   a_eci[2] };
        double g_ecef[3], C[3][3], f_ned[3];
        lv_gravity_eval(grav, NULL, r_ecef, g_ecef, NULL);
        lv_frames_C_ned_ecef(o[11], o[12], C);
        for (int i = 0; i < 3; i++)
            f_ned[i] = o[7] * (C[i][0] * (a_ecef[0] - g_ecef[0]) +
                               C[i][1] * (a_ecef[1] - g_ecef[1]) +
                               C[i][2] * (a_ecef[2] - g_ecef[2]));
        /* 1e-9 m/s^2 of rounding in a - g (|g| ~ 10) times the mass */
        CHECK_CLOSE(f_ned[0], 0.0, 1e-9 * mass);
        CHECK_CLOSE(f_ned[1], D, 1e-9 * mass); /* east: pushed by the wind */
        CHECK_CLOSE(f_ned[2], 0.0, 1e-9 * mass);
        printf("dof3 %s: drag %.6f N (q S CD = %.6f N), f_ned = (%.2e, %.6f, %.2e) N\n",
               with ? "east wind 40 m/s" : "no wind         ", o[8], D, f_ned[0], f_ned[1],
               f_ned[2]);
        lv_sink_destroy(&mem);
        lv_result_free(res);
        lv_dof3_free(m);
    }
done:
    lv_wind_free(wind);
    lv_atmo_free(atmo);
    lv_gravity_free(grav);
}

int main(void)
{
    lv_err err;
    lv_atmo *us = NULL;
    CHECK_OK(lv_atmo_create("us76", &us, &err), &err);
    if (us == NULL)
        return check_report("test_wind_atmo");
    test_us76_table(us);
    test_atmo_files();
    test_wind();
    test_wind_forms();
    test_dof3_wind(us);
    remove(US76_CSV);
    lv_atmo_free(us);
    return check_report("test_wind_atmo");
}
