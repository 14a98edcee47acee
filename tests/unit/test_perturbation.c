/* test_perturbation.c - dispersed profiles (lv_perturbation.h; docs/monte-carlo.md "Dispersed
 * profiles"): the realisation's samples rebuilt here from the generator by the documented
 * recurrence; its variance and its correlation at lag L over a long layer, and the variance
 * per altitude (sigma(h) piecewise linear) and the lag-L correlation over many runs, against
 * the Gauss-Markov process's closed forms; the perturbed atmosphere's state against the
 * documented formulas through the public lv_atmo_eval (us76 and exp); the perturbed wind;
 * a mission flown as a Monte Carlo run against the same draw, its nominal against the base;
 * the same run giving the same bits, another run another profile; bad specs refused; the cost
 * of a draw. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "check.h"
#include "core/random.h"
#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_dispersion.h"
#include "lvsim/lv_mission.h"
#include "lvsim/lv_perturbation.h"
#include "lvsim/lv_wind.h"

/* ---- the samples, rebuilt here ------------------------------------------------------------ *
 * lv_perturbation.h: x_0 = n_0, x_{k+1} = A x_k + sqrt(1 - A^2) n_{k+1}, A = exp(-1/20);
 * normals of samples 2j, 2j + 1: Phi^-1 of the two halves of the Philox call (run, stream + j);
 * sample k at h_from - L/20 + k L/20. */
static void rebuild(uint64_t seed, uint64_t run, uint64_t stream, size_t n, double *x)
{
    const double A = exp(-0.05), B = sqrt(1.0 - exp(-0.1));
    double u[2];
    for (size_t k = 0; k < n; k++) {
        if (k % 2 == 0)
            lv_rand_u01x2(seed, run, stream + k / 2, u);
        const double z = lv_disp_norm_inv(u[k % 2]);
        x[k] = k == 0 ? z : A * x[k - 1] + B * z;
    }
}

static void test_samples_rebuilt(void)
{
    const double sh[3] = { 0.0, 50000.0, 90000.0 }, sg[3] = { 0.01, 0.04, 0.1 };
    const lv_perturbation_spec sp = { 3, sh, sg, 6000.0, 0.0, 120000.0, 1 };
    const uint64_t stream = lv_disp_stream("profiles.environment.atmosphere.density");
    lv_perturbation *p = NULL;
    lv_err err;
    CHECK_OK(lv_perturbation_create(&sp, &stream, 7, 3, &p, &err), &err);
    double h0, dh;
    size_t n;
    lv_perturbation_grid(p, &h0, &dh, &n);
    CHECK_CLOSE(dh, 300.0, 1e-12);
    CHECK_CLOSE(h0, -300.0, 1e-9);
    CHECK(n == 404); /* 400 cells + one below, two above, one for the last cell's right end */
    double x[404];
    rebuild(7, 3, stream, n, x);
    /* at the samples inside the layer delta = sigma(h) x_k; sigma by hand, piecewise linear */
    const size_t ks[] = { 1, 2, 3, 101, 167, 301, 401 };
    for (size_t i = 0; i < sizeof ks / sizeof ks[0]; i++) {
        const double h = -300.0 + 300.0 * (double)ks[i];
        const double s = h <= 50000.0 ? 0.01 + 0.03 * h / 50000.0
                       : h <= 90000.0 ? 0.04 + 0.06 * (h - 50000.0) / 40000.0 : 0.1;
        CHECK_CLOSE(lv_perturbation_sigma(p, h), s, 1e-15);
        double d;
        lv_perturbation_eval(p, h, &d);
        CHECK_CLOSE(d, s * x[ks[i]], 1e-14);
    }
    /* held beyond the layer: x at h_from below it, at h_to above it (sigma still of h) */
    double d;
    lv_perturbation_eval(p, -2000.0, &d);
    CHECK_CLOSE(d, 0.01 * x[1], 1e-15);
    lv_perturbation_eval(p, 300000.0, &d);
    CHECK_CLOSE(d, 0.1 * x[401], 1e-15);
    lv_perturbation_eval(p, NAN, &d);
    CHECK(d == 0.0);

    /* the perturbed atmosphere through the public eval: rho' = rho (1 + delta), p kept,
     * T' = T / (1 + delta), a' = a / sqrt(1 + delta), mu by Sutherland (beta T^1.5/(T + S)) */
    const char *models[2] = { "us76", "exp" };
    for (int mi = 0; mi < 2; mi++) {
        lv_atmo *base = NULL, *pert = NULL;
        CHECK_OK(lv_atmo_create(models[mi], &base, &err), &err);
        CHECK_OK(lv_atmo_create_perturbed(base, p, &pert, &err), &err);
        for (size_t i = 0; i < sizeof ks / sizeof ks[0]; i++) {
            const double h = -300.0 + 300.0 * (double)ks[i];
            const double s = h <= 50000.0 ? 0.01 + 0.03 * h / 50000.0
                           : h <= 90000.0 ? 0.04 + 0.06 * (h - 50000.0) / 40000.0 : 0.1;
            const double f = 1.0 + s * x[ks[i]];
            lv_atmo_state a, b;
            CHECK_OK(lv_atmo_eval(base, h, &a, &err), &err);
            CHECK_OK(lv_atmo_eval(pert, h, &b, &err), &err);
            CHECK_REL(b.rho, a.rho * f, 1e-13);
            CHECK(b.p == a.p && b.M == a.M);
            CHECK_REL(b.T, a.T / f, 1e-13);
            CHECK_REL(b.p * b.M / (b.rho * 8314.32 * b.T), a.p * a.M / (a.rho * 8314.32 * a.T),
                      1e-12); /* the gas law holds as well as it held */
            CHECK_REL(b.a, a.a / sqrt(f), 1e-13);
            const double ma = 1.458e-6 * pow(a.T, 1.5) / (a.T + 110.4),
                         mb = 1.458e-6 * pow(b.T, 1.5) / (b.T + 110.4);
            CHECK_REL(b.mu, a.mu * mb / ma, 1e-12);
        }
        lv_atmo_state b;
        CHECK(lv_atmo_eval(pert, -6000.0, &b, &err) == LV_ERR_INPUT); /* the base's range */
        CHECK(strcmp(lv_atmo_model_of(pert)->name, "perturbed") == 0);
        lv_atmo_free(pert);
        lv_atmo_free(base);
    }
    lv_atmo *bad = NULL;
    lv_atmo *base = NULL;
    CHECK_OK(lv_atmo_create("us76", &base, &err), &err);
    CHECK(lv_atmo_create_perturbed(base, NULL, &bad, &err) == LV_ERR_INPUT && bad == NULL);
    lv_atmo_free(base);

    /* the same (seed, run): the same bits; another run: another profile */
    lv_perturbation *q = NULL, *r = NULL;
    CHECK_OK(lv_perturbation_create(&sp, &stream, 7, 3, &q, &err), &err);
    CHECK_OK(lv_perturbation_create(&sp, &stream, 7, 4, &r, &err), &err);
    int same = 1, differ = 0;
    for (double h = 0.0; h <= 120000.0; h += 123.4) {
        double a, b, c;
        lv_perturbation_eval(p, h, &a);
        lv_perturbation_eval(q, h, &b);
        lv_perturbation_eval(r, h, &c);
        same &= memcmp(&a, &b, sizeof a) == 0;
        differ += a != c;
    }
    CHECK(same);
    CHECK(differ > 900);
    lv_perturbation_free(q);
    lv_perturbation_free(r);
    lv_perturbation_free(p);
}

/* ---- statistics over a long layer --------------------------------------------------------- *
 * x is a stationary AR(1) with A = e^-0.05 at the samples: var 1, corr(k) = A^k, so at lag
 * L (k = 20) e^-1 = 0.3679. Over N = 2^20 samples the sample variance's standard error is
 * sqrt(2 (1 + A^2) / (1 - A^2) / N) = 0.0062 and the lag-20 correlation's about
 * sqrt((1 + A^2)/(1 - A^2) / N) = 0.0044 (Bartlett, for an AR(1)); bounds: 4 of them. Between
 * samples the Catmull-Rom midpoint's variance is sum w_i w_j A^|i-j|, w = (-1, 9, 9, -1)/16:
 * 0.98829 (by hand: 164/256 + 2 A 63/256 - 2 A^2 18/256 + 2 A^3/256). */
static void test_long_layer(void)
{
    const size_t N = (size_t)1 << 20;
    const double L = 1000.0, sig = 2.5, dh = L / 20.0;
    const double sh[1] = { 0.0 }, sg[1] = { sig };
    const lv_perturbation_spec sp = { 1, sh, sg, L, 0.0, dh * (double)N, 2 };
    const uint64_t st[2] = { lv_disp_stream("a"), lv_disp_stream("b") };
    lv_perturbation *p = NULL;
    lv_err err;
    CHECK_OK(lv_perturbation_create(&sp, st, 11, 0, &p, &err), &err);
    double *v = malloc(2 * N * sizeof *v), *vm = malloc(N * sizeof *vm);
    CHECK(v != NULL && vm != NULL);
    if (v == NULL || vm == NULL)
        return;
    for (size_t k = 0; k < N; k++) {
        double d[2];
        lv_perturbation_eval(p, dh * (double)k, d); /* sample k + 1 */
        v[2 * k] = d[0] / sig;
        v[2 * k + 1] = d[1] / sig;
        lv_perturbation_eval(p, dh * ((double)k + 0.5), d);
        vm[k] = d[0] / sig;
    }
    for (int c = 0; c < 2; c++) {
        double m = 0.0, s2 = 0.0, r20 = 0.0;
        for (size_t k = 0; k < N; k++)
            m += v[2 * k + c];
        m /= (double)N;
        for (size_t k = 0; k < N; k++)
            s2 += (v[2 * k + c] - m) * (v[2 * k + c] - m);
        s2 /= (double)(N - 1);
        for (size_t k = 0; k + 20 < N; k++)
            r20 += (v[2 * k + c] - m) * (v[2 * (k + 20) + c] - m);
        r20 /= (double)(N - 20) * s2;
        printf("long layer, component %d: variance %.4f (1), corr at L %.4f (e^-1 = %.4f), "
               "mean %.4f\n", c, s2, r20, exp(-1.0), m);
        CHECK_CLOSE(s2, 1.0, 4.0 * 0.0062);
        CHECK_CLOSE(r20, exp(-1.0), 4.0 * 0.0044);
    }
    double cr = 0.0, mm = 0.0;
    for (size_t k = 0; k < N; k++) {
        cr += v[2 * k] * v[2 * k + 1];
        mm += vm[k] * vm[k];
    }
    cr /= (double)N;
    mm /= (double)N;
    const double A = exp(-0.05);
    const double mid = (164.0 + 2.0 * A * 63.0 - 2.0 * A * A * 18.0 + 2.0 * A * A * A) / 256.0;
    printf("long layer: north-east correlation %.4f (0); midpoint variance %.4f (%.5f)\n", cr,
           mm, mid);
    CHECK_CLOSE(mid, 0.98829, 1e-5);
    CHECK_CLOSE(cr, 0.0, 4.0 * 0.0044);
    CHECK_CLOSE(mm, mid, 4.0 * 0.0062);
    free(v);
    free(vm);
    lv_perturbation_free(p);
}

/* ---- statistics over many runs ------------------------------------------------------------ *
 * n = 4000 runs of sigma = [[0, 1], [20000, 3], [40000, 3], [60000, 0.5]] m/s (L = 2000 m):
 * the variance at h is sigma(h)^2 (by hand: 1, 2^2 at 10 km, 3^2, 1.75^2 at 50 km, 0.5^2 held
 * above), each within 4 standard errors sqrt(2/(n-1)) relative = 8.9 %; the correlation
 * between h and h + L is e^-1 (whatever sigma) within 4 (1 - rho^2)/sqrt(n) = 0.055; north and
 * east uncorrelated within 4/sqrt(n) = 0.063. */
static void test_runs(void)
{
    const size_t n = 4000;
    const double sh[4] = { 0.0, 20000.0, 40000.0, 60000.0 }, sg[4] = { 1.0, 3.0, 3.0, 0.5 };
    const lv_perturbation_spec sp = { 4, sh, sg, 2000.0, 0.0, 120000.0, 2 };
    const uint64_t st[2] = { lv_disp_stream("profiles.environment.wind.north"),
                             lv_disp_stream("profiles.environment.wind.east") };
    const double hs[6] = { 0.0, 10000.0, 30000.0, 50000.0, 70000.0, 150000.0 };
    const double sd[6] = { 1.0, 2.0, 3.0, 1.75, 0.5, 0.5 };
    double s2[6] = { 0 }, ne = 0.0, lag = 0.0, v0 = 0.0, vL = 0.0;
    lv_err err;
    const clock_t c0 = clock();
    for (size_t r = 0; r < n; r++) {
        lv_perturbation *p = NULL;
        CHECK_OK(lv_perturbation_create(&sp, st, 5, r, &p, &err), &err);
        if (p == NULL)
            return;
        double d[2], e[2];
        for (int i = 0; i < 6; i++) {
            lv_perturbation_eval(p, hs[i], d);
            s2[i] += d[0] * d[0];
            if (i == 2)
                ne += d[0] * d[1];
        }
        lv_perturbation_eval(p, 30000.0, d);
        lv_perturbation_eval(p, 32000.0, e);
        lag += d[1] * e[1];
        v0 += d[1] * d[1];
        vL += e[1] * e[1];
        lv_perturbation_free(p);
    }
    const double ms = 1e3 * (double)(clock() - c0) / CLOCKS_PER_SEC / (double)n;
    for (int i = 0; i < 6; i++) {
        const double var = s2[i] / (double)n; /* mean 0 known */
        printf("runs: h %6.0f m: sigma %.4f m/s (%.4f)\n", hs[i], sqrt(var), sd[i]);
        CHECK_REL(var, sd[i] * sd[i], 4.0 * sqrt(2.0 / (double)(n - 1)));
    }
    const double rho = lag / sqrt(v0 * vL), rne = ne / s2[2];
    printf("runs: corr(h, h + L) %.4f (e^-1 = %.4f), north-east %.4f (0); a draw (2 components, "
           "0-120 km at L/20 = 100 m: 2 x 1204 samples) %.3f ms\n", rho, exp(-1.0), rne, ms);
    CHECK_CLOSE(rho, exp(-1.0), 4.0 * (1.0 - exp(-2.0)) / sqrt((double)n));
    CHECK_CLOSE(rne, 0.0, 4.0 / sqrt((double)n));
}

/* ---- the perturbed wind -------------------------------------------------------------------- */

static void test_wind(void)
{
    const double sh[1] = { 0.0 }, sg[1] = { 4.0 };
    const lv_perturbation_spec sp = { 1, sh, sg, 2000.0, 0.0, 120000.0, 2 };
    const uint64_t st[2] = { 1, 2 };
    lv_perturbation *p = NULL;
    lv_wind *base = NULL, *w = NULL, *still = NULL, *aff = NULL;
    lv_err err;
    CHECK_OK(lv_perturbation_create(&sp, st, 3, 9, &p, &err), &err);
    CHECK_OK(lv_wind_create_const(5.0, -2.0, 0.5, &base, &err), &err);
    CHECK_OK(lv_wind_create_perturbed(base, p, &w, &err), &err);
    CHECK_OK(lv_wind_create_perturbed(NULL, p, &still, &err), &err);
    CHECK(!lv_wind_is_constant(w));
    for (double h = 0.0; h < 30000.0; h += 777.0) {
        double d[2], v[3], s[3];
        lv_perturbation_eval(p, h, d);
        CHECK_OK(lv_wind_eval_at(w, NULL, 10.0, h, v, &err), &err);
        CHECK_OK(lv_wind_eval_at(still, NULL, 10.0, h, s, &err), &err);
        CHECK_CLOSE(v[0], 5.0 + d[0], 1e-14);
        CHECK_CLOSE(v[1], -2.0 + d[1], 1e-14);
        CHECK(v[2] == 0.5 && s[2] == 0.0);
        CHECK(s[0] == d[0] && s[1] == d[1]);
    }
    double v[3];
    CHECK(lv_wind_eval_at(still, NULL, 0.0, NAN, v, &err) == LV_ERR_INPUT);
    CHECK(lv_wind_create_affine(w, 2.0, NULL, &aff, &err) == LV_ERR_INPUT && aff == NULL);
    /* a one-component perturbation is a density's, not a wind's */
    lv_perturbation *p1 = NULL;
    lv_wind *w1 = NULL;
    const lv_perturbation_spec s1 = { 1, sh, sg, 2000.0, 0.0, 120000.0, 1 };
    CHECK_OK(lv_perturbation_create(&s1, st, 3, 9, &p1, &err), &err);
    CHECK_FAILS(lv_wind_create_perturbed(base, p1, &w1, &err), &err, LV_ERR_INPUT, "2");
    lv_perturbation_free(p1);
    lv_wind_free(still);
    lv_wind_free(w);
    lv_wind_free(base);
    lv_perturbation_free(p);
}

/* ---- a mission: the Monte Carlo run flies the draw, lvsim run the nominal ----------------- */

static void test_mission(void)
{
    const char *src = getenv("LV_SOURCE_DIR");
    if (src == NULL)
        src = "..";
    FILE *f = fopen("dprof_mission.yaml", "w");
    CHECK(f != NULL);
    if (f == NULL)
        return;
    fprintf(f,
            "mission: {name: dprof}\n"
            "environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76,\n"
            "              wind: {profile: %s/tests/data/profiles/sounding.txt}}\n"
            "parameters: {start_lat_deg: 5.2, start_lon_deg: -52.8, start_h: 100, start_vel: 50,"
            " start_fpa_deg: 88, start_chi_deg: 90}\n"
            "stages:\n"
            "  - {name: s1, dry_mass: 15000, propellant_mass: 150000, engines: [{name: e, "
            "thrust_vac: 3.2e6, isp_vac: 300}]}\n"
            "phases:\n"
            "  - {name: P, model: dof3, stages: [s1], stop_time: 40, end: [impact], inputs: "
            "{alpha_deg: 0, throttle: 1},\n"
            "     aero: {s_ref: 10, axes: wind, table: %s/examples/dof3-branch/aero_ascent.csv}}\n"
            "dispersions:\n"
            "  profiles:\n"
            "    environment.wind: {sigma: 4, correlation_length: 2000}\n"
            "    environment.atmosphere.density: {sigma: [[0, 0.01], [50000, 0.04]], "
            "correlation_length: 6000, to: 100000}\n",
            src, src);
    fclose(f);
    lv_mission *m = NULL;
    lv_run *r = NULL;
    lv_err err;
    CHECK_OK(lv_mission_load("dprof_mission.yaml", &m, &err), &err);
    if (m == NULL)
        return;
    CHECK(lv_mission_disp_profile_count(m) == 2 && lv_mission_disp_count(m) == 0);
    CHECK_OK(lv_run_create(m, &r, &err), &err);
    lv_atmo *us76 = NULL;
    lv_wind *wp = NULL;
    char snd[4200];
    snprintf(snd, sizeof snd, "%s/tests/data/profiles/sounding.txt", src);
    const char *paths[1] = { snd };
    const double t0[1] = { 0.0 };
    CHECK_OK(lv_atmo_create("us76", &us76, &err), &err);
    CHECK_OK(lv_wind_create_profiles(paths, t0, 1, 10000.0, &wp, &err), &err);
    /* the nominal (no lv_run_disperse: what lvsim run flies): the base atmosphere and wind */
    double h, rho, wn, we, h_nom;
    lv_atmo_state a;
    double wb[3];
    CHECK_OK(lv_run_execute(r, NULL, &err), &err);
    CHECK_OK(lv_run_final(r, 0, "h", &h, &err), &err);
    CHECK_OK(lv_run_final(r, 0, "rho", &rho, &err), &err);
    CHECK_OK(lv_run_final(r, 0, "wind_north", &wn, &err), &err);
    CHECK_OK(lv_atmo_eval(us76, h, &a, &err), &err);
    CHECK_OK(lv_wind_eval_at(wp, NULL, 40.0, h, wb, &err), &err);
    CHECK_REL(rho, a.rho, 1e-12);
    CHECK_CLOSE(wn, wb[0], 1e-9);
    h_nom = h;
    /* runs 0 and 1 of seed 42: the draws of the documented streams, (42, i) */
    const double dsh[2] = { 0.0, 50000.0 }, dsg[2] = { 0.01, 0.04 }, wsh[1] = { 0.0 },
                 wsg[1] = { 4.0 };
    const lv_perturbation_spec dsp = { 2, dsh, dsg, 6000.0, 0.0, 100000.0, 1 };
    const lv_perturbation_spec wsp = { 1, wsh, wsg, 2000.0, 0.0, 120000.0, 2 };
    const uint64_t ds = lv_disp_stream("profiles.environment.atmosphere.density");
    const uint64_t ws[2] = { lv_disp_stream("profiles.environment.wind.north"),
                             lv_disp_stream("profiles.environment.wind.east") };
    double finals[2];
    for (uint64_t run = 0; run < 2; run++) {
        CHECK_OK(lv_run_disperse(r, 42, run, NULL, &err), &err);
        CHECK_OK(lv_run_execute(r, NULL, &err), &err);
        CHECK_OK(lv_run_final(r, 0, "h", &h, &err), &err);
        CHECK_OK(lv_run_final(r, 0, "rho", &rho, &err), &err);
        CHECK_OK(lv_run_final(r, 0, "wind_north", &wn, &err), &err);
        CHECK_OK(lv_run_final(r, 0, "wind_east", &we, &err), &err);
        lv_perturbation *pd = NULL, *pw = NULL;
        CHECK_OK(lv_perturbation_create(&dsp, &ds, 42, run, &pd, &err), &err);
        CHECK_OK(lv_perturbation_create(&wsp, ws, 42, run, &pw, &err), &err);
        double dd, dw[2];
        lv_perturbation_eval(pd, h, &dd);
        lv_perturbation_eval(pw, h, dw);
        CHECK_OK(lv_atmo_eval(us76, h, &a, &err), &err);
        CHECK_OK(lv_wind_eval_at(wp, NULL, 40.0, h, wb, &err), &err);
        printf("mission run %d: h %.2f m (nominal %.2f), rho %.6g = us76 %.6g x (1 + %.5f), "
               "wind %.3f, %.3f m/s = profile + (%.3f, %.3f)\n", (int)run, h, h_nom, rho, a.rho,
               dd, wn, we, dw[0], dw[1]);
        CHECK_REL(rho, a.rho * (1.0 + dd), 1e-12);
        CHECK_CLOSE(wn, wb[0] + dw[0], 1e-9);
        CHECK_CLOSE(we, wb[1] + dw[1], 1e-9);
        CHECK(fabs(h - h_nom) > 1.0);
        finals[run] = h;
        lv_perturbation_free(pd);
        lv_perturbation_free(pw);
    }
    CHECK(finals[0] != finals[1]);
    lv_wind_free(wp);
    lv_atmo_free(us76);
    lv_run_free(r);
    lv_mission_free(m);
}

/* ---- bad specs ------------------------------------------------------------------------------ */

static void test_bad(void)
{
    const double h2[2] = { 0.0, 1000.0 }, hb[2] = { 1000.0, 1000.0 }, s2[2] = { 1.0, 2.0 },
                 sn[2] = { 1.0, -2.0 };
    const uint64_t st[2] = { 1, 2 };
    lv_perturbation *p = NULL;
    lv_err err;
    const lv_perturbation_spec ok = { 2, h2, s2, 1000.0, 0.0, 1e4, 1 };
    lv_perturbation_spec s = ok;
    s.sigma_h = hb;
    CHECK_FAILS(lv_perturbation_create(&s, st, 1, 0, &p, &err), &err, LV_ERR_INPUT,
                "not above the previous");
    s = ok;
    s.sigma = sn;
    CHECK_FAILS(lv_perturbation_create(&s, st, 1, 0, &p, &err), &err, LV_ERR_INPUT, ">= 0");
    s = ok;
    s.length = 0.0;
    CHECK_FAILS(lv_perturbation_create(&s, st, 1, 0, &p, &err), &err, LV_ERR_INPUT,
                "correlation length");
    s = ok;
    s.h_to = -5.0;
    CHECK_FAILS(lv_perturbation_create(&s, st, 1, 0, &p, &err), &err, LV_ERR_INPUT, "from < to");
    s = ok;
    s.h_to = 1e9;
    CHECK_FAILS(lv_perturbation_create(&s, st, 1, 0, &p, &err), &err, LV_ERR_INPUT,
                "correlation lengths deep");
    s = ok;
    s.n_comp = 3;
    CHECK_FAILS(lv_perturbation_create(&s, st, 1, 0, &p, &err), &err, LV_ERR_INPUT, "components");
    CHECK(p == NULL);
}

int main(void)
{
    test_samples_rebuilt();
    test_long_layer();
    test_runs();
    test_wind();
    test_mission();
    test_bad();
    return check_report("test_perturbation");
}
