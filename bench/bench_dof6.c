/* bench_dof6.c - nanoseconds per right-hand side of the 6-DoF rigid body (lv_dof6.h) with full
 * aerodynamic moments and one gimballed engine: J2 gravity, US76 atmosphere, force coefficients
 * CA, CN from a 2-D table (Mach x alpha), Cm from a 2-D table, Cl and Cn constants, damping
 * derivatives Clp, Cmq, Cnr, a moment reference point away from the CG, inertia and CG varying
 * with the propellant, one engine gimballed in pitch and yaw with a misalignment, rotating
 * Earth. States sweep an ascent-like envelope (0-90 km, 50-3000 m/s, attitude and rates varying)
 * so table cursors and atmosphere layers move as in a run. Target (issue 15): <= 1 us per rhs.
 * Then the same with a steering law (gravity turn; linear tangent) and the PID attitude
 * controller with its actuators (18 states). CPU time; the 3-DoF model's figure for the same
 * envelope: bench_dof3. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_dof6.h"
#include "lvsim/lv_planet.h"
#include "lvsim/lv_table.h"

static double now_s(void) { return (double)clock() / CLOCKS_PER_SEC; }

#define N_MACH 12
#define N_ALPHA 7
#define N_PTS 4096
#define DEG (3.14159265358979323846 / 180.0)

static volatile double sink_;

#define N_X 18 /* states with a PID controller */

/* ns per right-hand side of the model `cfg` over the ascent envelope; -1 on failure. */
static double bench(const lv_dof6_config *cfg)
{
    lv_err err;
    lv_dof6 *m = NULL;
    if (lv_dof6_create(cfg, &m, &err) != LV_OK) {
        fprintf(stderr, "bench_dof6: %s\n", err.msg);
        return -1.0;
    }
    const lv_model_def *d = lv_dof6_def(m);
    void *inst = lv_dof6_inst(m);
    double p[64], x0[N_X], xdot[N_X];
    for (size_t i = 0; i < d->n_params; i++)
        p[i] = d->params[i].start;
    static double xs[N_PTS][N_X];
    for (int k = 0; k < N_PTS; k++) { /* an ascent: altitude, speed, pitch over */
        const double s = (double)k / (N_PTS - 1);
        p[2] = 90e3 * s * s;              /* start_h */
        p[3] = 50.0 + 2950.0 * s;         /* start_vel */
        p[4] = 1.5 * (1.0 - s);           /* start_fpa */
        p[7] = 1.2;                       /* start_psi */
        p[8] = 1.5 * (1.0 - s) + 0.03 * sin(40.0 * s); /* start_theta: alpha wanders */
        p[9] = 0.02 * cos(30.0 * s);      /* start_phi */
        p[10] = 0.01 * sin(50.0 * s);     /* start_p, q, r */
        p[11] = -0.005 + 0.01 * s;
        p[12] = 0.003 * cos(20.0 * s);
        for (size_t i = 0; i < d->n_states; i++)
            x0[i] = d->states[i].start;
        if (d->start(p, x0, inst) != 0) {
            fprintf(stderr, "bench_dof6: start failed: %s\n", lv_dof6_last_error(m));
            lv_dof6_free(m);
            return -1.0;
        }
        x0[LV_X6_M] = 150e3 - 100e3 * s;
        for (size_t i = LV_X6_N; i < d->n_states; i++) /* gimbal angles, integrals */
            x0[i] = 0.01 * sin(17.0 * s + (double)i);
        for (size_t i = 0; i < d->n_states; i++)
            xs[k][i] = x0[i];
    }
    if (d->init(0.0, xs[0], p, inst) != 0) {
        fprintf(stderr, "bench_dof6: init failed: %s\n", lv_dof6_last_error(m));
        lv_dof6_free(m);
        return -1.0;
    }
    const long reps = 500;
    double acc = 0.0;
    const double t0 = now_s();
    for (long r = 0; r < reps; r++)
        for (int k = 0; k < N_PTS; k++) {
            const int kk = (r & 1) ? N_PTS - 1 - k : k;
            if (d->rhs(0.1 * kk, xs[kk], p, xdot, inst) != 0) {
                fprintf(stderr, "bench_dof6: rhs failed: %s\n", lv_dof6_last_error(m));
                lv_dof6_free(m);
                return -1.0;
            }
            acc += xdot[LV_X6_Q];
        }
    const double dt = now_s() - t0;
    sink_ = acc;
    lv_dof6_free(m);
    return 1e9 * dt / (double)(reps * N_PTS);
}

int main(void)
{
    lv_err err;
    const lv_planet earth = lv_planet_earth();
    lv_gravity_config gc = {"j2", 0, -1, NULL};
    lv_gravity *grav = NULL;
    lv_atmo *atmo = NULL;
    lv_table *tab = NULL;
    lv_dof6 *m = NULL;
    if (lv_gravity_create(&earth, &gc, &grav, &err) != LV_OK ||
        lv_atmo_create("us76", &atmo, &err) != LV_OK)
        goto fail;

    double mach[N_MACH] = {0, 0.5, 0.8, 0.9, 1.0, 1.1, 1.2, 1.5, 2, 3, 5, 10};
    double alpha[N_ALPHA], y[N_MACH * N_ALPHA * 3];
    for (int j = 0; j < N_ALPHA; j++)
        alpha[j] = (-6.0 + 2.0 * j) * DEG;
    for (int i = 0; i < N_MACH; i++)
        for (int j = 0; j < N_ALPHA; j++) {
            double *o = y + (i * N_ALPHA + j) * 3;
            o[0] = 0.3 + 0.2 * exp(-(mach[i] - 1) * (mach[i] - 1) * 4); /* CA */
            o[1] = 2.5 * alpha[j];                                       /* CN */
            o[2] = -0.8 * alpha[j];                                      /* Cm */
        }
    const char *outs[] = {"CA", "CN", "Cm"};
    lv_table_spec ts = {.n_dims = 2, .n = {N_MACH, N_ALPHA}, .x = {mach, alpha}, .n_out = 3,
                        .y = y, .interp = LV_INTERP_LINEAR, .extrap = LV_EXTRAP_CLAMP,
                        .name = "aero", .axis_name = {"mach", "alpha"}, .out_name = outs};
    if (lv_table_create(&ts, &tab, &err) != LV_OK)
        goto fail;

    lv_engine_config eng;
    lv_engine_config_default(&eng);
    eng.thrust_vac = 2.0e6;
    eng.isp_vac = 310.0;
    eng.exit_area = 1.5;
    const lv_dof6_engine_geom geom = {{-30.0, 0.0, 0.0}, 0.05 * DEG, -0.03 * DEG};
    lv_aero_config aero;
    lv_aero_config_default(&aero);
    aero.axes = LV_AERO_BODY;
    aero.s_ref = 10.0;
    aero.coef[0] = (lv_aero_coef){tab, "CA", 0.0};
    aero.coef[1] = (lv_aero_coef){tab, "CN", 0.0};
    lv_dof6_moments mo = {.cl = {NULL, NULL, 0.001},
                          .cm = {tab, "Cm", 0.0},
                          .cn = {NULL, NULL, -0.002},
                          .clp = -0.5, .cmq = -5.0, .cnr = -5.0,
                          .b_ref = 3.5, .c_ref = 3.5, .r_mrp = {-12.0, 0.0, 0.0}};
    lv_dof6_config cfg;
    lv_dof6_config_default(&cfg);
    cfg.gravity = grav;
    cfg.atmo = atmo;
    cfg.m0 = 150e3;
    cfg.propellant = 150e3 - 30e3;
    const lv_dof6_mass mp = {150e3, 30e3, {4e5, 2e7, 2e7, 0, 0, 0}, {1e5, 5e6, 5e6, 0, 0, 0},
                             {-14.0, 0.0, 0.0}, {-20.0, 0.0, 0.0}};
    cfg.mass = mp;
    cfg.n_engines = 1;
    cfg.engines = &eng;
    cfg.engine_geom = &geom;
    cfg.aero = &aero;
    cfg.moments = &mo;
    cfg.gimbal_pitch = 0.5 * DEG;
    cfg.gimbal_yaw = -0.2 * DEG;
    cfg.start_lat = 0.5;
    cfg.start_lon = -1.3;
    cfg.start_chi = 1.2;
    lv_dof3_end ends[] = {{"impact", LV_DOF3_END_IMPACT, 0.0, LV_DIR_FALLING, 1}};
    cfg.n_ends = 1;
    cfg.ends = ends;
    const double ns0 = bench(&cfg);
    if (ns0 < 0.0)
        goto fail;
    printf("full 6-DoF rhs (j2, us76, 2-D force and moment tables, Cl Cn Clp Cmq Cnr, moment "
           "transfer, 1 gimballed engine, variable inertia): %8.1f ns/rhs (target <= 1000)\n",
           ns0);
    /* the attitude controller (PID, actuators) holding a steering law's attitude */
    cfg.controller = (lv_dof6_controller){LV_DOF6_CTL_PID, {1.5, 1.5}, {1.2, 1.2}, {0.3, 0.3},
                                          6.0 * DEG, 20.0 * DEG, 0.05};
    lv_steering *st = &cfg.steering;
    if (lv_steering_init(st, "gravity_turn", &err) != LV_OK ||
        lv_steering_set(st, "rise_time", 5.0, &err) != LV_OK ||
        lv_steering_set(st, "kick", 3.0 * DEG, &err) != LV_OK ||
        lv_steering_set(st, "kick_time", 10.0, &err) != LV_OK ||
        lv_steering_set(st, "heading", 1.2, &err) != LV_OK)
        goto fail;
    const double ns1 = bench(&cfg);
    if (lv_steering_init(st, "linear_tangent", &err) != LV_OK ||
        lv_steering_set_choice(st, "frame", "local", &err) != LV_OK ||
        lv_steering_set(st, "a", 1.0, &err) != LV_OK ||
        lv_steering_set(st, "b", -0.004, &err) != LV_OK ||
        lv_steering_set(st, "heading", 1.2, &err) != LV_OK)
        goto fail;
    const double ns2 = bench(&cfg);
    if (ns1 < 0.0 || ns2 < 0.0)
        goto fail;
    printf("  + PID controller (18 states) and gravity turn (zero alpha):      %8.1f ns/rhs "
           "(target <= 1000)\n", ns1);
    printf("  + PID controller (18 states) and linear tangent (local frame):   %8.1f ns/rhs "
           "(target <= 1000)\n", ns2);
    lv_dof6_free(m);
    lv_table_free(tab);
    lv_atmo_free(atmo);
    lv_gravity_free(grav);
    return 0;
fail:
    fprintf(stderr, "bench_dof6: %s\n", err.msg);
    lv_dof6_free(m);
    lv_table_free(tab);
    lv_atmo_free(atmo);
    lv_gravity_free(grav);
    return 1;
}
