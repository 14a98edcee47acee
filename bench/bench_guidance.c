/* bench_guidance.c - what a steering or throttle law adds to the 3-DoF right-hand side
 * (lv_guidance.h; issue 12's goal: at most 100 ns). The model of bench_dof3 (J2, US76, a 2-D
 * aerodynamic table, one engine, rotating Earth) over the same ascent-like envelope, once
 * with the paper's inputs (constant alpha, beta, mu: the baseline) and once per law. Each
 * configuration is timed in several interleaved rounds and the fastest round counts, so that a
 * busy machine distorts less; CPU time. Prints ns per right-hand side and the difference to
 * the baseline measured in the same run. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_dof3.h"
#include "lvsim/lv_guidance.h"
#include "lvsim/lv_planet.h"
#include "lvsim/lv_table.h"

static double now_s(void) { return (double)clock() / CLOCKS_PER_SEC; }

#define N_MACH 12
#define N_ALPHA 7
#define N_PTS 4096
#define N_CASES 14
#define ROUNDS 7

static volatile double sink_;

typedef struct bench_case {
    const char *name;
    lv_steering steer;
    lv_throttle_cfg thr;
    lv_dof3 *m;
    double xs[N_PTS][LV_X3_N];
    double p[64];
    double best;
} bench_case;

static const double DEGR = 3.14159265358979323846 / 180.0;

int main(void)
{
    lv_err err;
    const lv_planet earth = lv_planet_earth();
    lv_gravity_config gc = {"j2", 0, -1, NULL};
    lv_gravity *grav = NULL;
    lv_atmo *atmo = NULL;
    lv_table *aero_tab = NULL, *att_tab = NULL, *in_tab = NULL;
    static bench_case cases[N_CASES];
    int n_cases = 0;
    if (lv_gravity_create(&earth, &gc, &grav, &err) != LV_OK ||
        lv_atmo_create("us76", &atmo, &err) != LV_OK)
        goto fail;

    double mach[N_MACH] = {0, 0.5, 0.8, 0.9, 1.0, 1.1, 1.2, 1.5, 2, 3, 5, 10};
    double alpha[N_ALPHA], y[N_MACH * N_ALPHA * 2];
    for (int j = 0; j < N_ALPHA; j++)
        alpha[j] = (-6.0 + 2.0 * j) * DEGR;
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
    /* a pitch program over time: 41 breakpoints over 400 s */
    double tt[41], pitch[41];
    for (int i = 0; i < 41; i++) {
        tt[i] = 10.0 * i;
        pitch[i] = (90.0 - 2.0 * i) * DEGR;
    }
    const char *pout[] = {"pitch"};
    lv_table_spec ps = {.n_dims = 1, .n = {41}, .x = {tt}, .n_out = 1, .y = pitch,
                        .interp = LV_INTERP_LINEAR, .extrap = LV_EXTRAP_CLAMP,
                        .name = "program", .axis_name = {"time"}, .out_name = pout};
    if (lv_table_create(&ps, &att_tab, &err) != LV_OK)
        goto fail;
    /* the same program as the paper's inputs: alpha over time */
    const char *iout[] = {"alpha"};
    lv_table_spec is = ps;
    is.out_name = iout;
    is.name = "inputs";
    double alpha_t[41];
    for (int i = 0; i < 41; i++)
        alpha_t[i] = 0.001 * i;
    is.y = alpha_t;
    if (lv_table_create(&is, &in_tab, &err) != LV_OK)
        goto fail;

    lv_engine_config eng;
    lv_engine_config_default(&eng);
    eng.thrust_vac = 2.0e6;
    eng.isp_vac = 310.0;
    eng.exit_area = 1.5;
    eng.throttle_min = 0.3;
    lv_aero_config aero;
    lv_aero_config_default(&aero);
    aero.s_ref = 10.0;
    aero.coef[0].table = aero_tab;
    aero.coef[1].table = aero_tab;

    /* the cases */
    lv_steering base;
    lv_throttle_cfg thr0;
    {
        lv_dof3_config c;
        lv_dof3_config_default(&c);
        base = c.steering;
        thr0 = c.throttle_law;
    }
#define ADD(nm) (cases[n_cases].name = (nm), cases[n_cases].steer = base, \
                 cases[n_cases].thr = thr0, &cases[n_cases++])
#define LAW(b, law) ok &= lv_steering_init(&(b)->steer, law, &err) == LV_OK
#define SET(b, key, v) ok &= lv_steering_set(&(b)->steer, key, v, &err) == LV_OK
#define THR(b, law) ok &= lv_throttle_init(&(b)->thr, law, &err) == LV_OK
#define TSET(b, key, v) ok &= lv_throttle_set(&(b)->thr, key, v, &err) == LV_OK
    bench_case *b;
    int ok = 1;
    ADD("inputs alpha, beta, mu (baseline)");
    b = ADD("inputs from a table over time"); /* the table is set below: cfg.inputs */
    b = ADD("attitude, local frame");
    LAW(b, "attitude"), SET(b, "pitch_deg", 60), SET(b, "heading_deg", 90);
    b = ADD("attitude, inertial frame");
    LAW(b, "attitude"), SET(b, "pitch_deg", 60), SET(b, "heading_deg", 90);
    ok &= lv_steering_set_choice(&b->steer, "frame", "inertial", &err) == LV_OK;
    b = ADD("attitude, pitch table over time");
    LAW(b, "attitude"), SET(b, "heading_deg", 90);
    ok &= lv_steering_set_table(&b->steer, "table", att_tab, &err) == LV_OK;
    b = ADD("gravity turn, during the kick");
    LAW(b, "gravity_turn"), SET(b, "kick_deg", 10), SET(b, "kick_time", 1e6);
    SET(b, "heading_deg", 90);
    b = ADD("gravity turn, alpha = 0");
    LAW(b, "gravity_turn"), SET(b, "kick", 0), SET(b, "kick_time", 0), SET(b, "heading_deg", 90);
    b = ADD("linear tangent, inertial frame");
    LAW(b, "linear_tangent"), SET(b, "a", 2.0), SET(b, "b", -0.01), SET(b, "heading_deg", 90);
    b = ADD("heading (bank to turn), n_max");
    LAW(b, "heading"), SET(b, "alpha_deg", 5), SET(b, "n_max", 3.0);
    SET(b, "target_lat", 0.3), SET(b, "target_lon", -1.0);
    b = ADD("retrograde");
    LAW(b, "retrograde");
    b = ADD("boostback");
    LAW(b, "boostback"), SET(b, "pitch_deg", 5);
    b = ADD("throttle: g-limit");
    TSET(b, "g_limit", 3.0);
    b = ADD("throttle: max-q (and g-limit)");
    TSET(b, "q_max", 30000.0), TSET(b, "g_limit", 3.0);
    b = ADD("throttle: landing, retrograde");
    LAW(b, "retrograde"), THR(b, "landing");
    if (!ok)
        goto fail;
#undef LAW
#undef SET
#undef THR
#undef TSET
#undef ADD

    for (int ci = 0; ci < n_cases; ci++) {
        bench_case *bc = &cases[ci];
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
        cfg.steering = bc->steer;
        if (ci == 1)
            cfg.inputs = in_tab;
        cfg.throttle_law = bc->thr;
        if (lv_dof3_create(&cfg, &bc->m, &err) != LV_OK)
            goto fail;
        const lv_model_def *d = lv_dof3_def(bc->m);
        void *inst = lv_dof3_inst(bc->m);
        double x0[LV_X3_N];
        for (size_t i = 0; i < d->n_params; i++)
            bc->p[i] = d->params[i].start;
        for (int k = 0; k < N_PTS; k++) { /* the envelope of bench_dof3 */
            const double s = (double)k / (N_PTS - 1);
            bc->p[2] = 90e3 * s * s;
            bc->p[3] = 50.0 + 2950.0 * s;
            bc->p[4] = 1.5 * (1.0 - s);
            for (int i = 0; i < LV_X3_N; i++)
                x0[i] = d->states[i].start;
            d->start(bc->p, x0, inst);
            x0[LV_X3_M] = 150e3 - 100e3 * s;
            memcpy(bc->xs[k], x0, sizeof x0);
        }
        if (d->init(0.0, bc->xs[0], bc->p, inst) != 0) {
            fprintf(stderr, "bench_guidance: %s: init failed: %s\n", bc->name,
                    lv_dof3_last_error(bc->m));
            return 1;
        }
        bc->best = INFINITY;
    }

    const long reps = 60;
    double acc = 0.0, xdot[LV_X3_N];
    for (int round = 0; round < ROUNDS; round++)
        for (int ci = 0; ci < n_cases; ci++) {
            bench_case *bc = &cases[ci];
            const lv_model_def *d = lv_dof3_def(bc->m);
            void *inst = lv_dof3_inst(bc->m);
            const double t0 = now_s();
            for (long r = 0; r < reps; r++)
                for (int k = 0; k < N_PTS; k++) {
                    const int kk = (r & 1) ? N_PTS - 1 - k : k;
                    if (d->rhs(0.1 * kk, bc->xs[kk], bc->p, xdot, inst) != 0) {
                        fprintf(stderr, "bench_guidance: %s: rhs failed: %s\n", bc->name,
                                lv_dof3_last_error(bc->m));
                        return 1;
                    }
                    acc += xdot[LV_X3_VX];
                }
            const double ns = 1e9 * (now_s() - t0) / (double)(reps * N_PTS);
            if (ns < bc->best)
                bc->best = ns;
        }
    sink_ = acc;
    printf("3-DoF right-hand side with each law (j2, us76, 2-D aero table, 1 engine), fastest "
           "of %d rounds:\n", ROUNDS);
    printf("  %-38s %9s %12s\n", "law", "ns/rhs", "vs baseline");
    for (int ci = 0; ci < n_cases; ci++)
        printf("  %-38s %9.1f %+11.1f\n", cases[ci].name, cases[ci].best,
               cases[ci].best - cases[0].best);
    for (int ci = 0; ci < n_cases; ci++)
        lv_dof3_free(cases[ci].m);
    lv_table_free(aero_tab);
    lv_table_free(att_tab);
    lv_table_free(in_tab);
    lv_atmo_free(atmo);
    lv_gravity_free(grav);
    return 0;
fail:
    fprintf(stderr, "bench_guidance: %s\n", err.msg);
    for (int ci = 0; ci < n_cases; ci++)
        lv_dof3_free(cases[ci].m);
    lv_table_free(aero_tab);
    lv_table_free(att_tab);
    lv_table_free(in_tab);
    lv_atmo_free(atmo);
    lv_gravity_free(grav);
    return 1;
}
