/* bench_disturbance.c - what the launch-day environment costs (issue 28: "the right-hand-side
 * cost added by turbulence and heating outputs (goal <= 50 ns each)"):
 *   - the full 3-DoF right-hand side (J2, US76, one engine, a constant CD) without wind, with
 *     a constant wind, and with the same wind plus a 1-cosine gust and Dryden turbulence, over
 *     an ascent-like envelope (0-30 km, where the turbulence layer is): the difference is what
 *     the disturbance adds per right-hand side;
 *   - one lv_wind_disturbance_eval alone, and drawing a run's realisation (0-20 km, L = 533.4 m);
 *   - the two heat-flux outputs per output row (they are outputs, not in the right-hand side).
 * CPU time (clock()), so a loaded machine distorts less; prints figures, asserts nothing. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "dynamics/flight.h"
#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_dof3.h"
#include "lvsim/lv_planet.h"
#include "lvsim/lv_units.h"
#include "lvsim/lv_wind.h"

static double now_s(void) { return (double)clock() / CLOCKS_PER_SEC; }

#define N_PTS 4096
static volatile double sink_;

/* ns per right-hand side over the envelope xs, reps passes up and down */
static double rhs_ns(const lv_model_def *d, void *inst, const double *p, double (*xs)[LV_X3_N])
{
    const long reps = 300;
    double xdot[LV_X3_N], acc = 0.0;
    const double t0 = now_s();
    for (long r = 0; r < reps; r++)
        for (int k = 0; k < N_PTS; k++) {
            const int kk = (r & 1) ? N_PTS - 1 - k : k;
            if (d->rhs(0.1 * kk, xs[kk], p, xdot, inst) != 0)
                return NAN;
            acc += xdot[LV_X3_VX];
        }
    sink_ = acc;
    return 1e9 * (now_s() - t0) / (double)(reps * N_PTS);
}

int main(void)
{
    lv_err err;
    const lv_planet earth = lv_planet_earth();
    lv_gravity_config gc = {"j2", 0, -1, NULL};
    lv_gravity *grav = NULL;
    lv_atmo *atmo = NULL;
    lv_wind *w_const = NULL, *w_dist = NULL;
    lv_wind_disturbance *dist = NULL;
    if (lv_gravity_create(&earth, &gc, &grav, &err) != LV_OK ||
        lv_atmo_create("us76", &atmo, &err) != LV_OK ||
        lv_wind_create_const(3.0, 12.0, 0.0, &w_const, &err) != LV_OK)
        goto fail;
    const lv_gust_1cos gust = {11000.0, 150.0, {0.0, 9.0, 0.0}};
    const lv_dryden_spec turb = {2.0, 1.5, 533.4, 0.0, 20000.0};
    double t0 = now_s();
    const int n_draw = 50;
    for (int i = 0; i < n_draw; i++) {
        lv_wind_disturbance_free(dist);
        dist = NULL;
        if (lv_wind_disturbance_create(&turb, &gust, 1, 1, (uint64_t)i, &dist, &err) != LV_OK)
            goto fail;
    }
    const double draw_ms = 1e3 * (now_s() - t0) / n_draw;
    if (lv_wind_create_disturbed(w_const, dist, &w_dist, &err) != LV_OK)
        goto fail;

    lv_engine_config eng;
    lv_engine_config_default(&eng);
    eng.thrust_vac = 2.0e6;
    eng.isp_vac = 310.0;
    eng.exit_area = 1.5;
    lv_aero_config aero;
    lv_aero_config_default(&aero);
    aero.s_ref = 10.0;
    aero.coef[0].value = 0.4;
    double ns[3];
    const lv_wind *winds[3] = {NULL, w_const, w_dist};
    for (int c = 0; c < 3; c++) {
        lv_wind_user wu = LV_WIND_USER_INIT(winds[c]);
        lv_dof3_config cfg;
        lv_dof3_config_default(&cfg);
        cfg.gravity = grav;
        cfg.atmo = atmo;
        cfg.m0 = 150e3;
        cfg.propellant = 120e3;
        cfg.n_engines = 1;
        cfg.engines = &eng;
        cfg.aero = &aero;
        cfg.start_lat = 0.5;
        cfg.start_lon = -1.3;
        cfg.start_fpa = 1.5;
        cfg.start_chi = 1.2;
        if (winds[c] != NULL) {
            cfg.wind = lv_wind_fn_table;
            cfg.wind_user = &wu;
        }
        lv_dof3 *m = NULL;
        if (lv_dof3_create(&cfg, &m, &err) != LV_OK)
            goto fail;
        const lv_model_def *d = lv_dof3_def(m);
        void *inst = lv_dof3_inst(m);
        double p[64], x0[LV_X3_N];
        static double xs[N_PTS][LV_X3_N];
        for (size_t i = 0; i < d->n_params; i++)
            p[i] = d->params[i].start;
        for (int k = 0; k < N_PTS; k++) { /* 0-30 km, 100-1500 m/s */
            const double s = (double)k / (N_PTS - 1);
            p[2] = 30e3 * s;
            p[3] = 100.0 + 1400.0 * s;
            p[4] = 1.5 * (1.0 - 0.6 * s);
            for (int i = 0; i < LV_X3_N; i++)
                x0[i] = d->states[i].start;
            d->start(p, x0, inst);
            for (int i = 0; i < LV_X3_N; i++)
                xs[k][i] = x0[i];
        }
        d->init(0.0, xs[0], p, inst);
        ns[c] = rhs_ns(d, inst, p, xs);
        lv_dof3_free(m);
    }
    printf("3-DoF rhs (j2, us76, constant CD, 1 engine; 0-30 km envelope):\n");
    printf("  no wind:                                   %7.1f ns/rhs\n", ns[0]);
    printf("  constant wind:                             %7.1f ns/rhs\n", ns[1]);
    printf("  constant wind + gust + Dryden turbulence:  %7.1f ns/rhs\n", ns[2]);
    printf("  the disturbance adds:                      %7.1f ns/rhs (goal <= 50)\n",
           ns[2] - ns[1]);

    const long n = 4000000;
    double v[3], acc = 0.0;
    t0 = now_s();
    for (long i = 0; i < n; i++) {
        lv_wind_disturbance_eval(dist, 25000.0 * (double)(i % 100000) / 1e5, v);
        acc += v[0];
    }
    printf("lv_wind_disturbance_eval alone (gust + turbulence, 0-25 km): %6.1f ns\n",
           1e9 * (now_s() - t0) / (double)n);
    printf("drawing a run's realisation (0-20 km, L = 533.4 m, %.0f samples): %.3f ms\n",
           20000.0 / (533.4 / 20.0) + 4.0, draw_ms);

    t0 = now_s();
    for (long i = 0; i < n; i++) {
        const double rho = 1e-4 * (1.0 + 1e-7 * (double)(i & 1023)), vv = 2000.0 + (double)(i & 511);
        acc += lv_flight_heat_flux_sg(LV_SUTTON_GRAVES_EARTH, rho, 0.5, vv) +
               lv_flight_heat_flux_fm(rho, vv);
    }
    printf("heat_flux + heat_flux_fm per output row: %.1f ns (outputs, not in the rhs)\n",
           1e9 * (now_s() - t0) / (double)n);
    sink_ = acc;
    lv_wind_free(w_dist);
    lv_wind_free(w_const);
    lv_wind_disturbance_free(dist);
    lv_atmo_free(atmo);
    lv_gravity_free(grav);
    return 0;
fail:
    fprintf(stderr, "bench_disturbance: %s\n", err.msg);
    return 1;
}
