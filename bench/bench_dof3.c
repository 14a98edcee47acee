/* bench_dof3.c - nanoseconds per right-hand side of the full 3-DoF model (lv_dof3.h):
 * J2 gravity, US76 atmosphere, a 2-D aerodynamic table (CD, CL over Mach x alpha), one
 * engine with exit-pressure loss, rotating Earth. States sweep an ascent-like envelope
 * (0-90 km, 50-3000 m/s) so table cursors and atmosphere layers move as in a run. Also
 * the cost of the model's pieces: the exact geodetic conversion (used for the outputs;
 * the rhs uses one Bowring step), US76, the table, gravity. CPU time, so a loaded machine
 * distorts less; gravity by model and degree: bench_gravity. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_dof3.h"
#include "lvsim/lv_planet.h"
#include "lvsim/lv_table.h"

/* Process CPU time: other jobs on a loaded machine do not count. */
static double now_s(void) { return (double)clock() / CLOCKS_PER_SEC; }

#define N_MACH 12
#define N_ALPHA 7
#define N_PTS 4096

static volatile double sink_;

int main(void)
{
    lv_err err;
    const lv_planet earth = lv_planet_earth();
    lv_gravity_config gc = {"j2", 0, -1, NULL};
    lv_gravity *grav = NULL;
    lv_atmo *atmo = NULL;
    lv_table *aero_tab = NULL;
    lv_dof3 *m = NULL;
    if (lv_gravity_create(&earth, &gc, &grav, &err) != LV_OK ||
        lv_atmo_create("us76", &atmo, &err) != LV_OK)
        goto fail;

    double mach[N_MACH] = {0, 0.5, 0.8, 0.9, 1.0, 1.1, 1.2, 1.5, 2, 3, 5, 10};
    double alpha[N_ALPHA], y[N_MACH * N_ALPHA * 2];
    for (int j = 0; j < N_ALPHA; j++)
        alpha[j] = (-6.0 + 2.0 * j) * 3.14159265358979323846 / 180.0;
    for (int i = 0; i < N_MACH; i++)
        for (int j = 0; j < N_ALPHA; j++) {
            y[(i * N_ALPHA + j) * 2] = 0.3 + 0.2 * exp(-(mach[i] - 1) * (mach[i] - 1) * 4) +
                                       0.5 * alpha[j] * alpha[j];
            y[(i * N_ALPHA + j) * 2 + 1] = 2.5 * alpha[j];
        }
    const char *outs[] = {"CD", "CL"};
    lv_table_spec ts = {.n_dims = 2, .n = {N_MACH, N_ALPHA}, .x = {mach, alpha}, .n_out = 2,
                        .y = y, .interp = LV_INTERP_LINEAR, .extrap = LV_EXTRAP_CLAMP,
                        .name = "aero", .axis_name = {"mach", "alpha"}, .out_name = outs};
    if (lv_table_create(&ts, &aero_tab, &err) != LV_OK)
        goto fail;

    lv_engine_config eng;
    lv_engine_config_default(&eng);
    eng.thrust_vac = 2.0e6;
    eng.isp_vac = 310.0;
    eng.exit_area = 1.5;
    lv_aero_config aero;
    lv_aero_config_default(&aero);
    aero.s_ref = 10.0;
    aero.coef[0].table = aero_tab;
    aero.coef[1].table = aero_tab;
    lv_dof3_config cfg;
    lv_dof3_config_default(&cfg);
    cfg.gravity = grav;
    cfg.atmo = atmo;
    cfg.m0 = 150e3;
    cfg.propellant = 150e3 - 30e3;
    cfg.n_engines = 1;
    cfg.engines = &eng;
    cfg.aero = &aero;
    cfg.alpha = 0.02;
    cfg.start_lat = 0.5;
    cfg.start_lon = -1.3;
    cfg.start_fpa = 1.5;
    cfg.start_chi = 1.2;
    lv_dof3_end ends[] = {{"impact", LV_DOF3_END_IMPACT, 0.0, LV_DIR_FALLING, 1}};
    cfg.n_ends = 1;
    cfg.ends = ends;
    if (lv_dof3_create(&cfg, &m, &err) != LV_OK)
        goto fail;

    const lv_model_def *d = lv_dof3_def(m);
    void *inst = lv_dof3_inst(m);
    double p[64], x0[LV_X3_N], xdot[LV_X3_N];
    for (size_t i = 0; i < d->n_params; i++)
        p[i] = d->params[i].start;
    static double xs[N_PTS][LV_X3_N];
    for (int k = 0; k < N_PTS; k++) { /* sweep altitude and speed along a smooth ascent */
        const double s = (double)k / (N_PTS - 1);
        p[2] = 90e3 * s * s;                 /* start_h */
        p[3] = 50.0 + 2950.0 * s;            /* start_vel */
        p[4] = 1.5 * (1.0 - s);              /* start_fpa */
        for (int i = 0; i < LV_X3_N; i++)
            x0[i] = d->states[i].start;
        d->start(p, x0, inst);
        x0[LV_X3_M] = 150e3 - 100e3 * s;
        for (int i = 0; i < LV_X3_N; i++)
            xs[k][i] = x0[i];
    }
    d->init(0.0, xs[0], p, inst);

    const long reps = 500;
    double acc = 0.0;
    double t0 = now_s();
    for (long r = 0; r < reps; r++)
        for (int k = 0; k < N_PTS; k++) {
            const int kk = (r & 1) ? N_PTS - 1 - k : k; /* up and down the envelope */
            if (d->rhs(0.1 * kk, xs[kk], p, xdot, inst) != 0) {
                fprintf(stderr, "bench_dof3: rhs failed: %s\n", lv_dof3_last_error(m));
                return 1;
            }
            acc += xdot[LV_X3_VX];
        }
    double dt = now_s() - t0;
    sink_ = acc;
    printf("full 3-DoF rhs (j2, us76, 2-D aero table, 1 engine): %8.1f ns/rhs\n",
           1e9 * dt / (double)(reps * N_PTS));

    /* pieces */
    const long n = 2000000;
    double r_ecef[3] = {4.0e6, 3.0e6, 3.5e6}, lat, lon, h;
    t0 = now_s();
    for (long i = 0; i < n; i++) {
        r_ecef[0] += 1e-3;
        lv_frames_ecef_to_geodetic(&earth, r_ecef, &lat, &lon, &h);
        acc += h;
    }
    printf("  lv_frames_ecef_to_geodetic (outputs only, not rhs): %8.1f ns\n",
           1e9 * (now_s() - t0) / (double)n);
    const lv_atmo_model *am = lv_atmo_model_of(atmo);
    lv_atmo_state as;
    t0 = now_s();
    for (long i = 0; i < n; i++) {
        am->eval(lv_atmo_par(atmo), 1e3 + 0.04 * (double)i, &as, NULL);
        acc += as.rho;
    }
    printf("  us76 eval (0-80 km sweep):                          %8.1f ns\n",
           1e9 * (now_s() - t0) / (double)n);
    lv_table_cursor cur = LV_TABLE_CURSOR_INIT;
    double xy[2], yo[2];
    t0 = now_s();
    for (long i = 0; i < n; i++) {
        xy[0] = 5.0 * (double)(i % 1000) / 1000.0;
        xy[1] = 0.05;
        lv_table_eval(aero_tab, &cur, xy, yo, NULL);
        acc += yo[0];
    }
    printf("  2-D table eval (2 outputs):                         %8.1f ns\n",
           1e9 * (now_s() - t0) / (double)n);
    double a[3];
    t0 = now_s();
    for (long i = 0; i < n; i++) {
        r_ecef[2] += 1e-3;
        lv_gravity_eval(grav, NULL, r_ecef, a, NULL);
        acc += a[0];
    }
    printf("  j2 gravity eval:                                    %8.1f ns\n",
           1e9 * (now_s() - t0) / (double)n);
    printf("  (gravity by model and degree: see bench_gravity)\n");
    sink_ = acc;

    lv_dof3_free(m);
    lv_table_free(aero_tab);
    lv_atmo_free(atmo);
    lv_gravity_free(grav);
    return 0;
fail:
    fprintf(stderr, "bench_dof3: %s\n", err.msg);
    lv_dof3_free(m);
    lv_table_free(aero_tab);
    lv_atmo_free(atmo);
    lv_gravity_free(grav);
    return 1;
}
