/* test_gravity.c - gravity models (docs/gravity.md).
 * References: Somigliana normal gravity of WGS-84 (NIMA TR8350.2, 3rd ed., 2000,
 * ch. 3: gamma_e = 9.7803253359, gamma_p = 9.8321849378 m/s^2); the normal
 * field's J2..J8 (Heiskanen & Moritz 1967, ch. 2); the identities
 * a = grad U and C(2,0) = -J2 / sqrt(5); EGM2008 (Pavlis et al. 2008) values. */
#define _POSIX_C_SOURCE 200809L /* setenv, unsetenv, mkdir */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "check.h"
#include "env/planet.h"
#include "lvsim/lv_planet.h"

#define PI 3.14159265358979323846

static double norm3(const double a[3]) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

static double rel_diff3(const double a[3], const double b[3])
{
    const double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return norm3(d) / norm3(b);
}

/* Test points: equator, mid latitudes, near and exactly at the poles, LEO to GEO. */
static const double points[][3] = {
    {6378137.0, 0.0, 0.0},       {0.0, 0.0, 6356752.3},    {0.0, 0.0, -6400e3},
    {4.1e6, -3.2e6, 3.9e6},      {-2.2e6, 1.1e6, -6.2e6},  {1e-3, -2e-3, 7000e3},
    {6.9e6, 1.0e6, 1.0},         {-3e7, 2.8e7, 1.2e6},     {5e-9, 0.0, -6.8e6},
};
#define N_POINTS (sizeof points / sizeof points[0])

static lv_gravity *make(const lv_planet *p, const char *spec)
{
    lv_gravity_config cfg;
    lv_gravity *g = NULL;
    lv_err err;
    CHECK_OK(lv_gravity_parse_spec(spec, &cfg, &err), &err);
    CHECK_OK(lv_gravity_create(p, &cfg, &g, &err), &err);
    return g;
}

static void test_pointmass(void)
{
    const lv_planet e = lv_planet_earth();
    lv_gravity *g = make(&e, "pointmass");
    CHECK(lv_gravity_ws_size(g) == 0);
    for (size_t i = 0; i < N_POINTS; i++) {
        double a[3], U;
        const double *r = points[i], rn = norm3(r);
        lv_gravity_eval(g, NULL, r, a, &U);
        for (int k = 0; k < 3; k++)
            CHECK_REL(a[k], -e.gm * r[k] / (rn * rn * rn), 1e-15);
        CHECK_REL(U, e.gm / rn, 1e-15);
    }
    lv_gravity_free(g);
}

/* The SH engine with only C00 = 1 and C(n,0) = -J_n / sqrt(2n+1) must reproduce
 * the closed-form zonal models. */
static void test_sh_vs_closed_form(void)
{
    const lv_planet e = lv_planet_earth();
    const char *specs[] = {"j2", "zonal"};
    const int degs[] = {2, 4};
    const double jn[5] = {0.0, 0.0, e.j2, e.j3, e.j4};
    for (int s = 0; s < 2; s++) {
        double cnm[15] = {0}, worst_a = 0.0, worst_u = 0.0;
        cnm[0] = 1.0;
        for (int n = 2; n <= degs[s]; n++)
            cnm[n * (n + 1) / 2] = -jn[n] / sqrt(2.0 * n + 1.0);
        lv_gravity *zon = make(&e, specs[s]), *sh = NULL;
        lv_err err;
        CHECK_OK(lv_gravity_create_sh(e.gm, e.r_ref, degs[s], 0, cnm, NULL, &sh, &err), &err);
        double *ws = malloc(lv_gravity_ws_size(sh) * sizeof *ws);
        for (size_t i = 0; i < N_POINTS; i++) {
            double a1[3], a2[3], u1, u2;
            lv_gravity_eval(zon, NULL, points[i], a1, &u1);
            lv_gravity_eval(sh, ws, points[i], a2, &u2);
            worst_a = fmax(worst_a, rel_diff3(a2, a1));
            worst_u = fmax(worst_u, fabs(u2 - u1) / u1);
        }
        printf("sh vs %s: worst relative difference accel %.3g, potential %.3g\n", specs[s],
               worst_a, worst_u);
        CHECK(worst_a < 1e-12);
        CHECK(worst_u < 1e-12);
        lv_gravity_info info;
        lv_gravity_info_get(sh, &info);
        CHECK_REL(info.jn[2], e.j2, 1e-15);
        lv_gravity_info_get(zon, &info);
        CHECK(info.jn[2] == e.j2 && info.gm == e.gm && info.r_ref == e.r_ref);
        free(ws);
        lv_gravity_free(sh);
        lv_gravity_free(zon);
    }
}


/* The closed-form zonal model with the caller's coefficients to degree 12 (J2..J8 of the
 * WGS-84 normal field, then odd and higher terms made up, as large as 1e-4) against the
 * SH engine with C(n,0) = -J_n / sqrt(2n+1): two independent evaluations of eq. G1's
 * gradient (Bonnet recursions vs the normalised Cunningham recursion, docs/gravity.md).
 * "j2" with the same list keeps J2 only; a bad list is refused. */
static void test_zonal_given(void)
{
    const lv_planet e = lv_planet_earth();
    enum { NZ = 11 }; /* J2 .. J12 */
    double zon[NZ], cnm[13 * 14 / 2] = {0};
    for (int n = 2; n <= 12; n++)
        zon[n - 2] = n % 2 == 0 && n <= 8 ? lv_planet_normal_j(&e, n) : 1e-4 / n;
    cnm[0] = 1.0;
    for (int n = 2; n <= 12; n++)
        cnm[n * (n + 1) / 2] = -zon[n - 2] / sqrt(2.0 * n + 1.0);
    lv_err err;
    lv_gravity *z = NULL, *j2 = NULL, *sh = NULL, *j2ref = NULL;
    CHECK_OK(lv_gravity_create_zonal(&e, "zonal", zon, NZ, &z, &err), &err);
    CHECK_OK(lv_gravity_create_zonal(&e, "j2", zon, NZ, &j2, &err), &err);
    CHECK_OK(lv_gravity_create_sh(e.gm, e.r_ref, 12, 0, cnm, NULL, &sh, &err), &err);
    lv_planet p = e;
    p.j2 = zon[0];
    j2ref = make(&p, "j2");
    if (z == NULL || j2 == NULL || sh == NULL || j2ref == NULL)
        return;
    double *ws = malloc(lv_gravity_ws_size(sh) * sizeof *ws);
    double worst_a = 0.0, worst_u = 0.0;
    for (size_t i = 0; i < N_POINTS; i++) {
        double a1[3], a2[3], a3[3], a4[3], u1, u2, u3, u4;
        lv_gravity_eval(z, NULL, points[i], a1, &u1);
        lv_gravity_eval(sh, ws, points[i], a2, &u2);
        worst_a = fmax(worst_a, rel_diff3(a2, a1));
        worst_u = fmax(worst_u, fabs(u2 - u1) / u1);
        lv_gravity_eval(j2, NULL, points[i], a3, &u3);
        lv_gravity_eval(j2ref, NULL, points[i], a4, &u4);
        CHECK(a3[0] == a4[0] && a3[1] == a4[1] && a3[2] == a4[2] && u3 == u4);
    }
    printf("zonal J2..J12 vs sh:12x0: worst relative difference accel %.3g, potential %.3g\n",
           worst_a, worst_u);
    CHECK(worst_a < 1e-12);
    CHECK(worst_u < 1e-12);
    lv_gravity_info info;
    lv_gravity_info_get(z, &info);
    CHECK(info.degree == 12 && info.jn[2] == zon[0] && info.jn[4] == zon[2]);
    free(ws);
    lv_gravity_free(z);
    lv_gravity_free(j2);
    lv_gravity_free(sh);
    lv_gravity_free(j2ref);
    CHECK_FAILS(lv_gravity_create_zonal(&e, "zonal", zon, 0, &z, &err), &err, LV_ERR_INPUT,
                "0 zonal coefficients");
    CHECK_FAILS(lv_gravity_create_zonal(&e, "zonal", zon, LV_GRAVITY_ZONAL_MAX, &z, &err),
                &err, LV_ERR_INPUT, "1 to 39 of them");
    zon[3] = 1.5;
    CHECK_FAILS(lv_gravity_create_zonal(&e, "zonal", zon, NZ, &z, &err), &err, LV_ERR_INPUT,
                "J5 = 1.5 must be finite and |J| < 1");
    CHECK_FAILS(lv_gravity_create_zonal(&e, "sh", zon, NZ, &z, &err), &err, LV_ERR_INPUT,
                "zonal coefficients go with");
    CHECK(z == NULL);
}

/* Somigliana: the normal gravity of the WGS-84 level ellipsoid on its surface,
 * gamma_e at the equator and gamma_p at the poles (TR8350.2 ch. 3), equals
 * the attraction of the normal field plus the centrifugal acceleration. The
 * field is built from J2..J8 (lv_planet_normal_j); J10 ~ 1e-12 contributes < 1e-11 m/s^2.
 * Tolerance 1e-9 m/s^2: the constants are published to 1e-10 m/s^2. */
static void test_somigliana(void)
{
    const lv_planet e = lv_planet_earth();
    const double b = lv_planet_b(&e);
    double cnm[45] = {0};
    cnm[0] = 1.0;
    for (int n = 2; n <= 8; n += 2)
        cnm[n * (n + 1) / 2] = -lv_planet_normal_j(&e, n) / sqrt(2.0 * n + 1.0);
    lv_gravity *sh = NULL;
    lv_err err;
    CHECK_OK(lv_gravity_create_sh(e.gm, e.a, 8, 0, cnm, NULL, &sh, &err), &err);
    double *ws = malloc(lv_gravity_ws_size(sh) * sizeof *ws);
    const double r_eq[3] = {e.a, 0.0, 0.0}, r_pole[3] = {0.0, 0.0, b};
    double a[3], u_eq, u_pole;
    lv_gravity_eval(sh, ws, r_eq, a, &u_eq);
    const double gamma_e = -(a[0] + e.omega * e.omega * e.a);
    lv_gravity_eval(sh, ws, r_pole, a, &u_pole);
    const double gamma_p = -a[2];
    printf("normal gravity: equator %.10f (Somigliana 9.7803253359), pole %.10f (9.8321849378)\n",
           gamma_e, gamma_p);
    CHECK_CLOSE(gamma_e, 9.7803253359, 1e-9);
    CHECK_CLOSE(gamma_p, 9.8321849378, 1e-9);
    /* the ellipsoid is a level surface: U + centrifugal potential equal at both */
    CHECK_REL(u_eq + 0.5 * e.omega * e.omega * e.a * e.a, u_pole, 1e-12);
    free(ws);
    lv_gravity_free(sh);

    /* The EGM2008 field to degree 20 differs from the normal field by the gravity
     * disturbance, a few 1e-4 m/s^2 (< 1e-3) at these points. */
    lv_gravity *egm = make(&e, "sh");
    lv_gravity_local loc;
    CHECK_OK(lv_gravity_at_geodetic(egm, &e, 0.0, 0.3, 0.0, &loc, &err), &err);
    CHECK_CLOSE(loc.g_eff_ned[2], 9.7803253359, 1e-3);
    CHECK_CLOSE(hypot(loc.g_eff_ned[0], loc.g_eff_ned[1]), 0.0, 1e-3);
    CHECK_OK(lv_gravity_at_geodetic(egm, &e, PI / 2, 0.0, 0.0, &loc, &err), &err);
    CHECK_CLOSE(loc.g_eff_ned[2], 9.8321849378, 1e-3);
    CHECK(loc.g_ned[2] == loc.g_eff_ned[2]); /* no centrifugal term on the axis */
    CHECK_FAILS(lv_gravity_at_geodetic(egm, &e, 2.0, 0.0, 0.0, &loc, &err), &err, LV_ERR_INPUT,
                "out of range");
    lv_gravity_free(egm);
}

/* a = grad U by central differences (step 10 m: truncation ~1e-10 and rounding
 * ~1e-10 m/s^2, so 1e-8 m/s^2 is loose). */
static void test_gradient(void)
{
    const lv_planet e = lv_planet_earth();
    const char *specs[] = {"pointmass", "j2", "zonal", "sh:8", "sh:20x20", "sh:20x5", "sh:12x0"};
    for (size_t s = 0; s < sizeof specs / sizeof specs[0]; s++) {
        lv_gravity *g = make(&e, specs[s]);
        double *ws = malloc((lv_gravity_ws_size(g) + 1) * sizeof *ws), worst = 0.0;
        for (size_t i = 0; i < N_POINTS; i++) {
            double a[3], up, um;
            lv_gravity_eval(g, ws, points[i], a, NULL);
            for (int k = 0; k < 3; k++) {
                const double step = 10.0;
                double rp[3] = {points[i][0], points[i][1], points[i][2]};
                double rm[3] = {points[i][0], points[i][1], points[i][2]}, tmp[3];
                rp[k] += step;
                rm[k] -= step;
                lv_gravity_eval(g, ws, rp, tmp, &up);
                lv_gravity_eval(g, ws, rm, tmp, &um);
                worst = fmax(worst, fabs((up - um) / (2.0 * step) - a[k]));
            }
        }
        printf("grad U - a, %s: worst %.3g m/s^2\n", specs[s], worst);
        CHECK(worst < 1e-8);
        free(ws);
        lv_gravity_free(g);
    }
}

/* At the exact poles the SH acceleration is finite and is the limit of nearby
 * points (1e-9 rad off the axis is 6 mm away: |da| < 3e-6 s^-2 x 6 mm). */
static void test_poles(void)
{
    const lv_planet e = lv_planet_earth();
    lv_gravity *g = make(&e, "sh:20");
    double *ws = malloc(lv_gravity_ws_size(g) * sizeof *ws);
    const double rads[] = {6356752.3, 6.6e6, 4.2e7};
    for (size_t i = 0; i < 3; i++) {
        for (int sgn = -1; sgn <= 1; sgn += 2) {
            const double pole[3] = {0.0, 0.0, sgn * rads[i]};
            double a0[3], u0;
            lv_gravity_eval(g, ws, pole, a0, &u0);
            CHECK(isfinite(a0[0]) && isfinite(a0[1]) && isfinite(a0[2]) && isfinite(u0));
            for (int j = 0; j < 8; j++) {
                const double lon = 2.0 * PI * j / 8.0, d = 1e-9;
                double r[3], a[3], u;
                lv_frames_geocentric_to_ecef(sgn * (PI / 2 - d), lon, rads[i], r);
                lv_gravity_eval(g, ws, r, a, &u);
                for (int k = 0; k < 3; k++)
                    CHECK_CLOSE(a[k], a0[k], 3e-6 * rads[i] * d + 1e-14);
                CHECK_CLOSE(u, u0, norm3(a0) * rads[i] * d); /* |grad U| x distance */
            }
        }
    }
    free(ws);
    lv_gravity_free(g);
}

/* Independent evaluation of the potential in spherical coordinates with the
 * standard fully normalised Legendre recursion (Holmes & Featherstone 2002,
 * eqs. 11-13), from the same file, to check the Cartesian recursion and its
 * normalisation. */
static double potential_spherical(const lv_planet *e, const double r[3], int nmax)
{
    (void)e;
    /* coefficients from the shipped file, found like the library finds it */
    char file[4096];
    lv_err err;
    const lv_status st = lv_gravity_default_file(file, sizeof file, &err);
    CHECK(st == LV_OK);
    FILE *fp = st == LV_OK ? fopen(file, "r") : NULL;
    CHECK(fp != NULL);
    static double C[21][21], S[21][21];
    double gm = 0.0, R = 0.0;
    char line[512];
    memset(C, 0, sizeof C);
    memset(S, 0, sizeof S);
    while (fp != NULL && fgets(line, sizeof line, fp) != NULL) {
        int n, m;
        double c, s;
        if (sscanf(line, "earth_gravity_constant %lf", &gm) == 1) continue;
        if (sscanf(line, "radius %lf", &R) == 1) continue;
        if (sscanf(line, "gfc %d %d %lf %lf", &n, &m, &c, &s) == 4 && n <= 20) {
            C[n][m] = c;
            S[n][m] = s;
        }
    }
    if (fp != NULL) fclose(fp);
    const double rn = norm3(r), t = r[2] / rn, u = sqrt(1.0 - t * t);
    const double lon = atan2(r[1], r[0]);
    double P[22][22] = {{0}};
    P[0][0] = 1.0;
    for (int m = 1; m <= nmax; m++)
        P[m][m] = u * sqrt((m == 1 ? 3.0 : (2.0 * m + 1.0) / (2.0 * m))) * P[m - 1][m - 1];
    for (int m = 0; m <= nmax; m++)
        for (int n = m + 1; n <= nmax; n++) {
            const double an = sqrt((2.0 * n - 1) * (2.0 * n + 1) / ((n - m) * (double)(n + m)));
            const double bn = n >= m + 2 ? sqrt((2.0 * n + 1) * (n + m - 1.0) * (n - m - 1.0) /
                                                ((2.0 * n - 3) * (n + m) * (double)(n - m)))
                                         : 0.0;
            P[n][m] = an * t * P[n - 1][m] - (n >= m + 2 ? bn * P[n - 2][m] : 0.0);
        }
    double sum = 0.0;
    for (int n = nmax; n >= 0; n--) {
        double sn = 0.0;
        for (int m = 0; m <= n; m++)
            sn += P[n][m] * (C[n][m] * cos(m * lon) + S[n][m] * sin(m * lon));
        sum += pow(R / rn, n) * sn;
    }
    return gm / rn * sum;
}

static void test_sh_file(void)
{
    const lv_planet e = lv_planet_earth();
    lv_gravity *g = make(&e, "sh");
    lv_gravity_info info;
    lv_gravity_info_get(g, &info);
    CHECK(info.kind == LV_GRAVITY_SH && info.degree == 20 && info.order == 20);
    /* zero-initialised config: the whole shipped file */
    lv_gravity_config zero;
    lv_gravity *gz = NULL;
    lv_err err;
    memset(&zero, 0, sizeof zero);
    zero.model = "sh";
    CHECK_OK(lv_gravity_create(&e, &zero, &gz, &err), &err);
    lv_gravity_info_get(gz, &info);
    CHECK(info.degree == 20 && info.order == 20);
    lv_gravity_free(gz);
    zero.order = LV_GRAVITY_ORDER_ZONAL;
    CHECK_OK(lv_gravity_create(&e, &zero, &gz, &err), &err);
    lv_gravity_info_get(gz, &info);
    CHECK(info.degree == 20 && info.order == 0);
    lv_gravity_free(gz);
    lv_gravity_info_get(g, &info);
    CHECK_CLOSE(info.gm, 3.986004415e14, 0.0);
    CHECK_CLOSE(info.r_ref, 6378136.3, 0.0);
    CHECK_REL(info.jn[2], 0.484165143790815e-3 * sqrt(5.0), 1e-15);
    CHECK_REL(info.jn[2], e.j2, 1e-15);
    double *ws = malloc(lv_gravity_ws_size(g) * sizeof *ws);
    double worst = 0.0;
    for (size_t i = 0; i < N_POINTS; i++) {
        double a[3], U;
        lv_gravity_eval(g, ws, points[i], a, &U);
        worst = fmax(worst, fabs(U - potential_spherical(&e, points[i], 20)) / U);
    }
    printf("sh:20 potential vs spherical Legendre sum: worst relative %.3g\n", worst);
    CHECK(worst < 1e-14);
    /* truncation: degree 8 differs from 20 by < 1e-4 relative at the surface */
    lv_gravity *g8 = make(&e, "sh:8x8");
    double a20[3], a8[3];
    lv_gravity_eval(g, ws, points[3], a20, NULL);
    lv_gravity_eval(g8, ws, points[3], a8, NULL);
    CHECK(rel_diff3(a8, a20) < 1e-4 && rel_diff3(a8, a20) > 0.0);
    free(ws);
    lv_gravity_free(g8);
    lv_gravity_free(g);
}

/* ---- errors: registry names and bad coefficient files ---- */

static void write_file(const char *path, const char *body)
{
    FILE *fp = fopen(path, "w");
    fputs("modelname test\nearth_gravity_constant 3.986004415e14\nradius 6378136.3\n"
          "max_degree 3\nnorm fully_normalized\nend_of_head ====\n",
          fp);
    fputs(body, fp);
    fclose(fp);
}

static void expect_file_error(const char *body, int degree, const char *needle)
{
    const char *path = "test_gravity_bad.gfc";
    const lv_planet e = lv_planet_earth();
    lv_gravity_config cfg = {"sh", degree, 0, path};
    lv_gravity *g = (lv_gravity *)&cfg; /* must be reset to NULL on failure */
    lv_err err;
    write_file(path, body);
    CHECK_FAILS(lv_gravity_create(&e, &cfg, &g, &err), &err, LV_ERR_INPUT, needle);
    CHECK(g == NULL);
    remove(path);
}

static void test_errors(void)
{
    lv_gravity_config cfg;
    lv_err err;
    CHECK_OK(lv_gravity_parse_spec("sh:8x4", &cfg, &err), &err);
    CHECK(strcmp(cfg.model, "sh") == 0 && cfg.degree == 8 && cfg.order == 4);
    CHECK_OK(lv_gravity_parse_spec("zonal", &cfg, &err), &err);
    CHECK(cfg.degree == 0 && cfg.order == 0 && cfg.coef_path == NULL);
    CHECK_OK(lv_gravity_parse_spec("sh:6x0", &cfg, &err), &err);
    CHECK(cfg.degree == 6 && cfg.order == LV_GRAVITY_ORDER_ZONAL);
    CHECK_FAILS(lv_gravity_parse_spec("zonl", &cfg, &err), &err, LV_ERR_NOTFOUND,
                "did you mean 'zonal'");
    CHECK_FAILS(lv_gravity_parse_spec("point_mass", &cfg, &err), &err, LV_ERR_NOTFOUND,
                "'pointmass'");
    CHECK_FAILS(lv_gravity_parse_spec("sh:0", &cfg, &err), &err, LV_ERR_INPUT, "degree");
    CHECK_FAILS(lv_gravity_parse_spec("sh:4x5", &cfg, &err), &err, LV_ERR_INPUT, "order");
    CHECK_FAILS(lv_gravity_parse_spec("sh:4y", &cfg, &err), &err, LV_ERR_INPUT, "sh:NxM");
    CHECK_FAILS(lv_gravity_parse_spec("j2:3", &cfg, &err), &err, LV_ERR_INPUT, "no degree");

    const lv_planet e = lv_planet_earth();
    lv_gravity *g = NULL;
    lv_gravity_config big = {"sh", 30, 0, NULL};
    CHECK_FAILS(lv_gravity_create(&e, &big, &g, &err), &err, LV_ERR_INPUT,
                "requested degree 30");
    lv_gravity_config nofile = {"sh", 0, 0, "no/such/file.gfc"};
    CHECK_FAILS(lv_gravity_create(&e, &nofile, &g, &err), &err, LV_ERR_IO, "no/such/file.gfc");

    const char *good = "gfc 0 0 1.0 0.0\n"
                       "gfc 2 0 -0.484165143790815e-03 0.0 1e-11 0\n"
                       "gfc 2 1 -0.206615509074176e-09 0.138441389137979e-08\n"
                       "gfc 2 2 0.243938357328313D-05 -0.140027370385934D-05\n"
                       "gfc 3 0 0.957161207093473e-06 0.0\n"
                       "gfc 3 1 0.203046201047864e-05 0.248200415856872e-06\n"
                       "gfc 3 2 0.904787894809528e-06 -0.619005475177618e-06\n"
                       "gfc 3 3 0.721321757121568e-06 0.141434926192941e-05\n";
    write_file("test_gravity_good.gfc", good);
    lv_gravity_config ok = {"sh", 0, 0, "test_gravity_good.gfc"};
    CHECK_OK(lv_gravity_create(&e, &ok, &g, &err), &err);
    lv_gravity_free(g);
    ok.degree = 2; /* truncation of a longer file is fine */
    CHECK_OK(lv_gravity_create(&e, &ok, &g, &err), &err);
    lv_gravity_free(g);
    remove("test_gravity_good.gfc");

    /* header lines are 6, so the first data line is line 7 */
    expect_file_error("gfc 2 3 1.0 0.0\n", 0, "test_gravity_bad.gfc:7: degree/order (2, 3)");
    expect_file_error("gfc 2 0 1e-3 0.0\ngfc -2 0 1.0 0.0\n", 0, ":8: degree/order (-2, 0)");
    expect_file_error("gfc 4 0 1.0 0.0\n", 0, ":7: degree/order (4, 0) invalid");
    expect_file_error("gfc 2 0 nan 0.0\n", 0, ":7: coefficient (2, 0): bad value 'nan'");
    expect_file_error("gfc 2 0 1e-3 inf\n", 0, ":7: coefficient (2, 0)");
    expect_file_error("gfc 2 0 1e-3 0.0\ngfc 2 0 1e-3 0.0\n", 0, ":8: coefficient (2, 0) given twice");
    expect_file_error("gfc 2 0 1e-3\n", 0, ":7: expected 'gfc n m C S'");
    expect_file_error("gfc 2 x 1e-3 0\n", 0, ":7: degree/order '2 x' not integers");
    expect_file_error("gfct 2 0 1e-3 0 0 0 20000101\n", 0, ":7: key 'gfct' not supported");
    expect_file_error("gfc 2 0 1e-3 0\ngfc 2 2 1e-6 0\n", 2, ":8: end of file: coefficient (2, 1) missing");
    expect_file_error("gfc 2 0 1e-3 0\n", 4, "requested degree 4");

    /* a max_degree the file cannot begin to hold (fuzz_tables: 70920, the arrays 260 GB)
     * is refused at its line before anything is allocated */
    FILE *fp = fopen("test_gravity_bad.gfc", "w");
    fputs("earth_gravity_constant 3.986004415e14\nradius 6378136.3\nmax_degree 70920\n"
          "end_of_head\ngfc 2 0 -0.484165143790815e-03 0.0\n", fp);
    fclose(fp);
    lv_gravity_config huge = {"sh", 0, 0, "test_gravity_bad.gfc"};
    CHECK_FAILS(lv_gravity_create(&e, &huge, &g, &err), &err, LV_ERR_INPUT,
                "test_gravity_bad.gfc:3: max_degree 70920: degree 70920, order 70920 needs "
                "2514929578 'gfc' lines; the 35 bytes after end_of_head cannot hold them");
    huge.degree = 4; /* a degree it could hold: the line-by-line checks */
    CHECK_FAILS(lv_gravity_create(&e, &huge, &g, &err), &err, LV_ERR_INPUT,
                "test_gravity_bad.gfc:5: end of file: coefficient (2, 1) missing");

    fp = fopen("test_gravity_bad.gfc", "w");
    fputs("radius 6378136.3\nmax_degree 2\nend_of_head\n", fp);
    fclose(fp);
    lv_gravity_config hdr = {"sh", 0, 0, "test_gravity_bad.gfc"};
    CHECK_FAILS(lv_gravity_create(&e, &hdr, &g, &err), &err, LV_ERR_INPUT,
                "test_gravity_bad.gfc:3: header lacks earth_gravity_constant");
    fp = fopen("test_gravity_bad.gfc", "w");
    fputs("earth_gravity_constant 3.986004415e14\nradius 6378136.3\nmax_degree 2\n"
          "norm unnormalized\nend_of_head\n", fp);
    fclose(fp);
    CHECK_FAILS(lv_gravity_create(&e, &hdr, &g, &err), &err, LV_ERR_INPUT,
                "test_gravity_bad.gfc:4: norm 'unnormalized' not supported");
    fp = fopen("test_gravity_bad.gfc", "w");
    fputs("2 0 -0.484165371736E-03 0.0\n", fp);
    fclose(fp);
    CHECK_FAILS(lv_gravity_create(&e, &hdr, &g, &err), &err, LV_ERR_INPUT, "no end_of_head");
    remove("test_gravity_bad.gfc");

    lv_gravity_config unk = {"egm", 0, 0, NULL};
    CHECK_FAILS(lv_gravity_create(&e, &unk, &g, &err), &err, LV_ERR_NOTFOUND, "unknown gravity model 'egm'");
    lv_planet bad = e;
    bad.gm = -1.0;
    lv_gravity_config j2 = {"j2", 0, 0, NULL};
    CHECK_FAILS(lv_gravity_create(&bad, &j2, &g, &err), &err, LV_ERR_INPUT, "gm = -1");
    const double c[3] = {1.0, 0.0, NAN};
    CHECK_FAILS(lv_gravity_create_sh(e.gm, e.a, 1, 1, c, NULL, &g, &err), &err, LV_ERR_INPUT,
                "(1, 1) not finite");
    lv_gravity_free(NULL);
}

/* "sh" without a file reads gravity/egm2008_n20.gfc, looked up at run time: $LVSIM_DATA
 * comes before the build tree's copy (lvsim/lv_data.h). */
static void test_default_file(void)
{
    const lv_planet e = lv_planet_earth();
    lv_gravity_config cfg;
    lv_gravity *g = NULL;
    lv_gravity_info info;
    lv_err err;
    char path[4096];

    unsetenv("LVSIM_DATA");
    CHECK_OK(lv_gravity_default_file(path, sizeof path, &err), &err);
    const size_t n = strlen(path), tail = strlen("/share/lvsim/" LV_GRAVITY_DEFAULT_FILE);
    CHECK(n > tail && strcmp(path + n - tail, "/share/lvsim/" LV_GRAVITY_DEFAULT_FILE) == 0);
    CHECK_OK(lv_gravity_parse_spec("sh", &cfg, &err), &err);
    CHECK_OK(lv_gravity_create(&e, &cfg, &g, &err), &err);
    lv_gravity_info_get(g, &info);
    CHECK(info.degree == 20 && info.gm == 3.986004415e14);
    lv_gravity_free(g);

    /* a planted file of degree 3 with another GM wins */
    mkdir("test_gravity_data", 0755);
    mkdir("test_gravity_data/gravity", 0755);
    FILE *fp = fopen("test_gravity_data/" LV_GRAVITY_DEFAULT_FILE, "w");
    CHECK(fp != NULL);
    if (fp == NULL)
        return;
    fputs("earth_gravity_constant 4.0e14\nradius 6378136.3\nmax_degree 3\n"
          "norm fully_normalized\nend_of_head ====\ngfc 0 0 1.0 0.0\n", fp);
    for (int k = 1; k <= 3; k++)
        for (int m = 0; m <= k; m++)
            fprintf(fp, "gfc %d %d 0.0 0.0\n", k, m);
    fclose(fp);
    setenv("LVSIM_DATA", "test_gravity_data", 1);
    CHECK_OK(lv_gravity_default_file(path, sizeof path, &err), &err);
    CHECK(strcmp(path, "test_gravity_data/" LV_GRAVITY_DEFAULT_FILE) == 0);
    CHECK_OK(lv_gravity_parse_spec("sh:2", &cfg, &err), &err);
    CHECK_OK(lv_gravity_create(&e, &cfg, &g, &err), &err);
    lv_gravity_info_get(g, &info);
    CHECK(info.degree == 2 && info.gm == 4.0e14);
    lv_gravity_free(g);
    /* errors name the file found */
    CHECK_OK(lv_gravity_parse_spec("sh:4", &cfg, &err), &err);
    CHECK_FAILS(lv_gravity_create(&e, &cfg, &g, &err), &err, LV_ERR_INPUT,
                "test_gravity_data/gravity/egm2008_n20.gfc: requested degree 4");
    unsetenv("LVSIM_DATA");
    remove("test_gravity_data/" LV_GRAVITY_DEFAULT_FILE);
}

/* The internal ECI adapter rotates into ECEF and back (docs/frames.md eq. F2). */
static void test_eci_adapter(void)
{
    lv_planet e = lv_planet_earth();
    e.theta0 = 1.1;
    lv_gravity *g = make(&e, "sh:20");
    double *ws = malloc(lv_gravity_ws_size(g) * sizeof *ws);
    const lv_vec3 r_eci = lv_v3(3.1e6, -4.4e6, 3.3e6);
    const double t = 5000.0;
    const lv_vec3 a_eci = lv_gravity_accel_eci_v(g, &e, t, ws, r_eci);
    const double r[3] = {r_eci.x, r_eci.y, r_eci.z};
    double r_ecef[3], a_ecef[3], a_back[3];
    lv_frames_eci_to_ecef(&e, t, r, NULL, r_ecef, NULL);
    lv_gravity_eval(g, ws, r_ecef, a_ecef, NULL);
    lv_frames_ecef_to_eci(&e, t, a_ecef, NULL, a_back, NULL);
    CHECK_CLOSE(a_eci.x, a_back[0], 1e-15);
    CHECK_CLOSE(a_eci.y, a_back[1], 1e-15);
    CHECK_CLOSE(a_eci.z, a_back[2], 1e-15);
    /* the tesseral field is not axisymmetric: the rotation matters */
    const lv_vec3 a0 = lv_gravity_accel_ecef_v(g, ws, r_eci);
    CHECK(fabs(a0.x - a_eci.x) > 1e-7);
    free(ws);
    lv_gravity_free(g);
}

/* A coefficient file is parsed once per process and its result used again while the file
 * holds the same bytes (gravity_sh.c): the same file twice gives the same model; a file
 * rewritten with other coefficients of the same length (same size, maybe the same mtime) is
 * read anew. */
static void test_file_cache(void)
{
    const lv_planet e = lv_planet_earth();
    lv_gravity_config cfg = {"sh", 2, 0, "test_gravity_cache.gfc"};
    lv_gravity *g1 = NULL, *g2 = NULL, *g3 = NULL;
    lv_err err;
    write_file(cfg.coef_path, "gfc 2 0 -0.484165143790815e-03 0.0\ngfc 2 1 0.0 0.0\n"
                              "gfc 2 2 0.243938357328313e-05 -0.140027370385934e-05\n");
    CHECK_OK(lv_gravity_create(&e, &cfg, &g1, &err), &err);
    CHECK_OK(lv_gravity_create(&e, &cfg, &g2, &err), &err); /* from the cache */
    write_file(cfg.coef_path, "gfc 2 0 -0.484165143790815e-03 0.0\ngfc 2 1 0.0 0.0\n"
                              "gfc 2 2 0.143938357328313e-05 -0.140027370385934e-05\n");
    CHECK_OK(lv_gravity_create(&e, &cfg, &g3, &err), &err); /* changed bytes: parsed again */
    const double r[3] = {4.0e6, 3.0e6, 3.5e6};
    double a1[3], a2[3], a3[3], ws[64];
    CHECK(lv_gravity_ws_size(g1) <= 64);
    lv_gravity_eval(g1, ws, r, a1, NULL);
    lv_gravity_eval(g2, ws, r, a2, NULL);
    lv_gravity_eval(g3, ws, r, a3, NULL);
    CHECK(memcmp(a1, a2, sizeof a1) == 0);
    CHECK(memcmp(a1, a3, sizeof a1) != 0);
    lv_gravity_free(g1);
    lv_gravity_free(g2);
    lv_gravity_free(g3);
    /* an error is not cached: a bad file fails every time, a repaired one then reads */
    write_file(cfg.coef_path, "gfc 2 0 nan 0.0\n");
    CHECK_FAILS(lv_gravity_create(&e, &cfg, &g1, &err), &err, LV_ERR_INPUT, "bad value 'nan'");
    CHECK_FAILS(lv_gravity_create(&e, &cfg, &g1, &err), &err, LV_ERR_INPUT, "bad value 'nan'");
    remove(cfg.coef_path);
    CHECK_FAILS(lv_gravity_create(&e, &cfg, &g1, &err), &err, LV_ERR_IO, "cannot open");
}

int main(void)
{
    test_file_cache();
    test_eci_adapter();
    test_pointmass();
    test_sh_vs_closed_form();
    test_zonal_given();
    test_somigliana();
    test_gradient();
    test_poles();
    test_sh_file();
    test_errors();
    test_default_file();
    return check_report("test_gravity");
}
