/* test_turbulence.c - wind disturbances (lv_wind.h, docs/wind.md "Gusts and turbulence"):
 * the 1-cosine gust against its closed form, and the response of a first-order lag flown
 * through it against the lag's closed-form solution; the Dryden realisation's variance,
 * autocorrelation and spectra against MIL-F-8785C's (fitted over a long seeded run); the same
 * (seed, run) giving the same bits and another run another realisation; bad values refused. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "lvsim/lv_model.h"
#include "lvsim/lv_sim.h"
#include "lvsim/lv_units.h"
#include "lvsim/lv_vehicle.h"
#include "lvsim/lv_wind.h"

/* ---- the gust's shape --------------------------------------------------------------------- */

static void test_gust_shape(void)
{
    const lv_gust_1cos g = { 11000.0, 200.0, { 3.0, -8.0, 1.0 } };
    lv_wind_disturbance *d = NULL;
    lv_err err;
    CHECK_OK(lv_wind_disturbance_create(NULL, &g, 1, 1, 0, &d, &err), &err);
    double v[3];
    lv_wind_disturbance_eval(d, 11000.0, v); /* the peak */
    CHECK_CLOSE(v[0], 3.0, 1e-15);
    CHECK_CLOSE(v[1], -8.0, 1e-15);
    CHECK_CLOSE(v[2], 1.0, 1e-15);
    lv_wind_disturbance_eval(d, 10900.0, v); /* half way up: (1 + cos(pi/2))/2 = 1/2 */
    CHECK_CLOSE(v[1], -4.0, 1e-14);
    lv_wind_disturbance_eval(d, 11150.0, v); /* (1 + cos(3 pi/4))/2 = (2 - sqrt 2)/4 */
    CHECK_CLOSE(v[1], -8.0 * (2.0 - sqrt(2.0)) / 4.0, 1e-14);
    lv_wind_disturbance_eval(d, 10800.0, v); /* the edges and beyond: still air */
    CHECK(v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0);
    lv_wind_disturbance_eval(d, 11201.0, v);
    CHECK(v[1] == 0.0);
    lv_wind_disturbance_eval(d, NAN, v);
    CHECK(v[1] == 0.0);

    /* on a base wind: the sum */
    lv_wind *base = NULL, *w = NULL;
    CHECK_OK(lv_wind_create_const(1.0, 2.0, 0.0, &base, &err), &err);
    CHECK_OK(lv_wind_create_disturbed(base, d, &w, &err), &err);
    CHECK(!lv_wind_is_constant(w));
    CHECK_OK(lv_wind_eval_at(w, NULL, 0.0, 10900.0, v, &err), &err);
    CHECK_CLOSE(v[0], 1.0 + 1.5, 1e-14);
    CHECK_CLOSE(v[1], 2.0 - 4.0, 1e-14);
    CHECK(lv_wind_eval_at(w, NULL, 0.0, NAN, v, &err) != LV_OK);
    lv_wind *aff = NULL;
    CHECK(lv_wind_create_affine(w, 2.0, NULL, &aff, &err) == LV_ERR_INPUT && aff == NULL);
    lv_wind_free(w);
    lv_wind_free(base);
    lv_wind_disturbance_free(d);
}

/* ---- a first-order lag through the gust: closed form ------------------------------------- *
 * A body rising at constant speed V (h = h_start + V t) whose horizontal speed follows the
 * wind with time constant tau: v' = (w_north(h) - v) / tau, v(0) = 0. The gust spans
 * [h_c - d, h_c + d], i.e. t in [t_s, t_s + 2T] with T = d / V; in s = t - t_s,
 * w = (V_m/2)(1 - cos(omega s)), omega = pi / T, and the solution is
 *   v(s) = V_m/2 - B (cos(omega s) + omega tau sin(omega s)) - (V_m/2) k e^{-s/tau},
 *   B = (V_m/2) / (1 + omega^2 tau^2), k = omega^2 tau^2 / (1 + omega^2 tau^2),
 * (particular solution of the forced linear ODE plus the homogeneous one fixed by v(0) = 0),
 * and after the gust v(s) = v(2T) e^{-(s - 2T)/tau}. */
enum { LAG_V, LAG_NX };
enum { P_TAU, P_VRISE, P_H0, LAG_NP };
static const lv_var lag_states[] = { { "v", "m/s", "horizontal speed", 0.0, 1.0 } };
static const lv_var lag_params[] = { { "tau", "s", "time constant", 2.0, 0 },
                                     { "v_rise", "m/s", "rise speed", 300.0, 0 },
                                     { "h_start", "m", "altitude at t = 0", 0.0, 0 } };
typedef struct lag_inst {
    lv_wind_user wu;
} lag_inst;
static lag_inst g_lag;

static int lag_rhs(double t, const double *x, const double *p, double *xdot, void *inst)
{
    lag_inst *li = inst;
    double w[3];
    const int rc = lv_wind_fn_table(t, p[P_H0] + p[P_VRISE] * t, 0.0, 0.0, w, &li->wu);
    if (rc != 0)
        return rc;
    xdot[LAG_V] = (w[0] - x[LAG_V]) / p[P_TAU];
    return 0;
}

static const lv_model_def lag_model = {
    .name = "lag", .description = "first-order lag behind the wind",
    .n_states = LAG_NX, .n_params = LAG_NP, .states = lag_states, .params = lag_params,
    .rhs = lag_rhs,
};

static double lag_exact(double s, double Vm, double T, double tau)
{
    const double om = LV_PI / T, ot2 = om * om * tau * tau;
    const double B = 0.5 * Vm / (1.0 + ot2), k = ot2 / (1.0 + ot2);
    const double se = s < 2.0 * T ? s : 2.0 * T;
    const double v = 0.5 * Vm - B * (cos(om * se) + om * tau * sin(om * se)) -
                     0.5 * Vm * k * exp(-se / tau);
    return s <= 2.0 * T ? v : v * exp(-(s - 2.0 * T) / tau);
}

static void test_gust_response(void)
{
    const double Vm = 9.0, d = 150.0, hc = 2000.0, V = 300.0, tau = 2.0, h0 = 1000.0;
    const double ts = (hc - d - h0) / V, T = d / V; /* gust from t = 3.1667 s for 1 s */
    const lv_gust_1cos g = { hc, d, { Vm, 0.0, 0.0 } };
    lv_wind_disturbance *dist = NULL;
    lv_wind *w = NULL;
    lv_err err;
    CHECK_OK(lv_wind_disturbance_create(NULL, &g, 1, 1, 0, &dist, &err), &err);
    CHECK_OK(lv_wind_create_disturbed(NULL, dist, &w, &err), &err);
    const double s_at[] = { 0.25 * T, T, 1.5 * T, 2.0 * T, 2.0 * T + 3.0 * tau };
    for (int tol = 0; tol < 2; tol++)
        for (size_t i = 0; i < sizeof s_at / sizeof s_at[0]; i++) {
            lv_sim_settings s;
            lv_sim_settings_default(&s);
            s.result_file = NULL;
            if (tol == 1)
                s.tolerance = 1e-9;
            /* Before the gust this model's right-hand side is exactly zero, so any step-size
             * control lets its steps grow until one passes over the whole gust without sampling
             * it (docs/wind.md: a flight phase's own dynamics keep its steps short; a model this
             * still needs a step limit below the gust's crossing time) */
            s.max_step_size = 0.25 * T;
            s.stop_time = ts + s_at[i];
            const char *in[] = { "tau", "v_rise", "h_start" };
            const double iv[] = { tau, V, h0 };
            const char *fin[] = { "v" };
            double out[1] = { NAN };
            s.n_initial = 3;
            s.initial_names = in;
            s.initial_values = iv;
            s.n_final = 1;
            s.final_names = fin;
            g_lag.wu = (lv_wind_user)LV_WIND_USER_INIT(w);
            lv_sim_report rep;
            CHECK_OK(lv_simulate(&lag_model, &g_lag, &s, out, &rep, &err), &err);
            const double ref = lag_exact(s_at[i], Vm, T, tau);
            /* the default settings within 1e-4 of the peak gust; tolerance 1e-9 within 5e-8
             * (the gust's second derivative jumps at its edges, which no step lands on) */
            CHECK_CLOSE(out[0], ref, tol == 0 ? 1e-4 * Vm : 5e-8 * Vm);
            lv_sim_report_clear(&rep);
        }
    lv_wind_free(w);
    lv_wind_disturbance_free(dist);
}

/* ---- Dryden: the realisation's statistics ------------------------------------------------- */

/* In-place radix-2 FFT (n a power of 2), forward: X_j = sum_k x_k e^{-2 pi i jk/n}. Written
 * here so that the spectral check depends on nothing of the code under test. */
static void fft(double *re, double *im, size_t n)
{
    for (size_t i = 1, j = 0; i < n; i++) {
        size_t bit = n >> 1;
        for (; j & bit; bit >>= 1)
            j ^= bit;
        j ^= bit;
        if (i < j) {
            double t = re[i]; re[i] = re[j]; re[j] = t;
            t = im[i]; im[i] = im[j]; im[j] = t;
        }
    }
    for (size_t len = 2; len <= n; len <<= 1) {
        const double a = -2.0 * LV_PI / (double)len;
        for (size_t i = 0; i < n; i += len)
            for (size_t k = 0; k < len / 2; k++) {
                const double c = cos(a * (double)k), s = sin(a * (double)k);
                const size_t p = i + k, q = i + k + len / 2;
                const double xr = re[q] * c - im[q] * s, xi = re[q] * s + im[q] * c;
                re[q] = re[p] - xr;
                im[q] = im[p] - xi;
                re[p] += xr;
                im[p] += xi;
            }
    }
}

/* MIL-F-8785C's one-sided Dryden spectra [m^2/s^2 / (rad/m)], and the spectrum of their
 * samples at spacing dh: the continuous one folded over the sampling frequency 2 pi / dh
 * (aliasing; Papoulis, *Probability, random variables and stochastic processes*, sec. 11-5),
 * summed over 400 images (the tail beyond is below 1e-4 of the terms kept). */
static double phi_dryden(int lateral, double sigma, double L, double om)
{
    const double x2 = L * L * om * om;
    return lateral ? sigma * sigma * L / LV_PI * (1.0 + 3.0 * x2) / ((1.0 + x2) * (1.0 + x2))
                   : sigma * sigma * 2.0 * L / LV_PI / (1.0 + x2);
}

static double phi_sampled(int lateral, double sigma, double L, double dh, double om)
{
    const double oms = 2.0 * LV_PI / dh;
    double s = phi_dryden(lateral, sigma, L, om);
    for (int m = 1; m <= 400; m++)
        s += phi_dryden(lateral, sigma, L, om + m * oms) + phi_dryden(lateral, sigma, L, om - m * oms);
    return s;
}

static void test_dryden_statistics(void)
{
    const double L = 100.0, sig_h = 2.0, sig_v = 1.5;
    const size_t M = 1024, K = 1024, N = M * K; /* 2^20 samples: Welch over K segments */
    const lv_dryden_spec spec = { sig_h, sig_v, L, 0.0, (double)(N + 100) * L / 20.0 };
    lv_wind_disturbance *d = NULL;
    lv_err err;
    CHECK_OK(lv_wind_disturbance_create(&spec, NULL, 0, 20261203, 7, &d, &err), &err);
    double h0 = 0.0, dh = 0.0;
    lv_wind_disturbance_grid(d, &h0, &dh);
    CHECK_CLOSE(dh, L / 20.0, 1e-15);
    double *x = malloc(3 * N * sizeof *x);
    CHECK(x != NULL);
    if (x == NULL)
        return;
    const size_t k0 = 40; /* beyond the fade-in of one L (20 samples) */
    for (size_t k = 0; k < N; k++) {
        double v[3];
        lv_wind_disturbance_eval(d, h0 + (double)(k0 + k) * dh, v);
        for (int c = 0; c < 3; c++)
            x[c * N + k] = v[c];
    }
    /* variance and autocorrelation at lags L and 2L: R_long(r) = s^2 e^{-r/L},
     * R_lat(r) = s^2 e^{-r/L} (1 - r / (2L)) (MIL-F-8785C's correlation functions, the Fourier
     * pairs of the spectra). Sampling error of a 2^20 sample estimate with correlation length
     * 20 samples: about 1 % of s^2; bounds 4 %. */
    for (int c = 0; c < 3; c++) {
        const double sg = c < 2 ? sig_h : sig_v;
        const double *y = x + c * N;
        double m = 0.0;
        for (size_t k = 0; k < N; k++)
            m += y[k];
        m /= (double)N;
        double r[3] = { 0, 0, 0 };
        const size_t lag[3] = { 0, 20, 40 };
        for (int j = 0; j < 3; j++) {
            for (size_t k = 0; k + lag[j] < N; k++)
                r[j] += (y[k] - m) * (y[k + lag[j]] - m);
            r[j] /= (double)(N - lag[j]);
        }
        printf("component %d: mean %.4f, var %.4f (sigma^2 %.4f), r(L)/r(0) %.4f, r(2L)/r(0) %.4f\n",
               c, m, r[0], sg * sg, r[1] / r[0], r[2] / r[0]);
        CHECK(fabs(m) < 0.05 * sg);
        CHECK_CLOSE(r[0], sg * sg, 0.04 * sg * sg);
        const double e1 = c < 2 ? exp(-1.0) * 0.5 : exp(-1.0);
        const double e2 = c < 2 ? 0.0 : exp(-2.0);
        CHECK_CLOSE(r[1] / r[0], e1, 0.03);
        CHECK_CLOSE(r[2] / r[0], e2, 0.03);
    }
    /* spectra: Welch's estimate, Hann window, K segments of M samples,
     * Phi_hat(om_j) = 2 dh / (2 pi) |sum w_n x_n e^{-i om_j n dh}|^2 / sum w_n^2, om_j = 2 pi j / (M dh);
     * averaged over bands of bins (L om from 0.25 to 25), against the sampled spectrum.
     * Statistical error of a band mean: 1/sqrt(K x bins) < 1.5 %; bound 6 %. */
    double *re = malloc(M * sizeof *re), *im = malloc(M * sizeof *im);
    double *acc = calloc(3 * (M / 2), sizeof *acc);
    CHECK(re != NULL && im != NULL && acc != NULL);
    double w2 = 0.0;
    for (size_t n = 0; n < M; n++) {
        const double w = 0.5 - 0.5 * cos(2.0 * LV_PI * (double)n / (double)M);
        w2 += w * w;
    }
    for (int c = 0; c < 3; c++)
        for (size_t seg = 0; seg < K; seg++) {
            for (size_t n = 0; n < M; n++) {
                const double w = 0.5 - 0.5 * cos(2.0 * LV_PI * (double)n / (double)M);
                re[n] = w * x[c * N + seg * M + n];
                im[n] = 0.0;
            }
            fft(re, im, M);
            for (size_t j = 0; j < M / 2; j++)
                acc[c * (M / 2) + j] += (re[j] * re[j] + im[j] * im[j]) / (double)K;
        }
    const double scale = 2.0 * dh / (2.0 * LV_PI) / w2;
    for (int c = 0; c < 3; c++) {
        const int lat = c < 2;
        const double sg = lat ? sig_h : sig_v;
        double worst = 0.0;
        for (size_t j = 2; j < 256;) { /* bands growing geometrically: >= 4 bins each */
            size_t j1 = j + (j / 4 > 4 ? j / 4 : 4);
            double est = 0.0, ref = 0.0;
            for (size_t i = j; i < j1; i++) {
                const double om = 2.0 * LV_PI * (double)i / ((double)M * dh);
                est += scale * acc[c * (M / 2) + i];
                ref += phi_sampled(lat, sg, L, dh, om);
            }
            const double ratio = est / ref;
            if (fabs(ratio - 1.0) > fabs(worst))
                worst = ratio - 1.0;
            CHECK(fabs(ratio - 1.0) < 0.06);
            j = j1;
        }
        printf("component %d: Welch spectrum within %.2f %% of MIL-F-8785C (L om 0.25..25)\n",
               c, 100.0 * worst);
    }
    free(re);
    free(im);
    free(acc);
    free(x);
    lv_wind_disturbance_free(d);
}

/* ---- the streams: reproducible per (seed, run), distinct between runs -------------------- */

static void test_streams(void)
{
    const lv_dryden_spec spec = { 3.0, 2.0, 533.4, -1000.0, 20000.0 };
    lv_wind_disturbance *a = NULL, *b = NULL, *c = NULL, *e = NULL;
    lv_err err;
    CHECK_OK(lv_wind_disturbance_create(&spec, NULL, 0, 5, 3, &a, &err), &err);
    CHECK_OK(lv_wind_disturbance_create(&spec, NULL, 0, 5, 3, &b, &err), &err);
    CHECK_OK(lv_wind_disturbance_create(&spec, NULL, 0, 5, 4, &c, &err), &err);
    CHECK_OK(lv_wind_disturbance_create(&spec, NULL, 0, 6, 3, &e, &err), &err);
    int same = 1, diff_run = 0, diff_seed = 0;
    for (double h = 0.0; h < 19000.0; h += 37.0) {
        double va[3], vb[3], vc[3], ve[3];
        lv_wind_disturbance_eval(a, h, va);
        lv_wind_disturbance_eval(b, h, vb);
        lv_wind_disturbance_eval(c, h, vc);
        lv_wind_disturbance_eval(e, h, ve);
        same &= memcmp(va, vb, sizeof va) == 0;
        diff_run += va[0] != vc[0];
        diff_seed += va[0] != ve[0];
    }
    CHECK(same);
    CHECK(diff_run > 400 && diff_seed > 400);
    /* outside the layer: still air; inside the fade: less than the sample's value */
    double v[3];
    lv_wind_disturbance_eval(a, -1000.0, v);
    CHECK(v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0);
    lv_wind_disturbance_eval(a, 20000.5, v);
    CHECK(v[0] == 0.0);
    lv_wind_disturbance_free(a);
    lv_wind_disturbance_free(b);
    lv_wind_disturbance_free(c);
    lv_wind_disturbance_free(e);
}

static void test_bad_values(void)
{
    lv_wind_disturbance *d = NULL;
    lv_err err;
    const lv_dryden_spec bad[] = {
        { -1.0, 1.0, 500.0, 0.0, 1e4 },  /* sigma < 0 */
        { 1.0, NAN, 500.0, 0.0, 1e4 },   /* sigma NaN */
        { 1.0, 1.0, 0.0, 0.0, 1e4 },     /* L = 0 */
        { 1.0, 1.0, 500.0, 1e4, 1e4 },   /* from = to */
        { 1.0, 1.0, 1.0, 0.0, 1e9 },     /* 2e10 samples */
    };
    const char *word[] = { "sigma", "sigma", "length", "layer", "scale lengths" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        CHECK(lv_wind_disturbance_create(&bad[i], NULL, 0, 1, 0, &d, &err) == LV_ERR_INPUT);
        CHECK(d == NULL && strstr(err.msg, word[i]) != NULL);
    }
    const lv_gust_1cos g0 = { 1000.0, 0.0, { 1, 0, 0 } }, g1 = { 1000.0, 10.0, { 1, 600, 0 } };
    CHECK(lv_wind_disturbance_create(NULL, &g0, 1, 1, 0, &d, &err) == LV_ERR_INPUT);
    CHECK(strstr(err.msg, "half_width") != NULL);
    CHECK(lv_wind_disturbance_create(NULL, &g1, 1, 1, 0, &d, &err) == LV_ERR_INPUT);
    CHECK(strstr(err.msg, "east") != NULL);
}

int main(void)
{
    test_gust_shape();
    test_gust_response();
    test_dryden_statistics();
    test_streams();
    test_bad_values();
    return check_report("test_turbulence");
}
