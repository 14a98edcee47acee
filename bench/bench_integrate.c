/* bench_integrate.c - cost of lv_simulate per method on the vertical ascent and the Kepler
 * orbit, beside the same problems driven by a bare SUNDIALS loop (same equations, same
 * tolerances, same event functions, same output grid, no lvsim layer).
 *
 * Prints steps, RHS evaluations, ns per RHS evaluation and per step, and the ratio of
 * lvsim's time per step to the bare loop's. A benchmark, not a test: numbers are noisy;
 * each figure is the fastest of several repetitions.
 */
#define _POSIX_C_SOURCE 200809L

#include <arkode/arkode_erkstep.h>
#include <cvode/cvode.h>
#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdio.h>
#include <string.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>
#include <time.h>

#include "lvsim/lv_models.h"
#include "lvsim/lv_sim.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Thread CPU time: a run preempted by another process is not charged for the wait. */
static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- the problems ----------------------------------------------------------------------- */

typedef struct problem {
    const char *name;
    const lv_model_def *model;
    size_t n, ng;
    double tf, tol;
    int intervals;
    const char *const *set_names;
    const double *set_values;
    size_t n_set;
    double x0[6], atol_nominal[6];
    int g_dir[3];
} problem;

/* Ascent: thrust 30 kN, 10 kg/s, 1000 -> 400 kg, stop at apogee. */
static const char *const asc_names[] = {"stop_at_apogee"};
static const double asc_values[] = {1.0};

typedef struct bare_state {
    int engine_on;
    long nfe;
} bare_state;

static int asc_f(sunrealtype t, N_Vector y, N_Vector yd, void *u)
{
    (void)t;
    bare_state *b = u;
    const double *x = N_VGetArrayPointer(y);
    double *d = N_VGetArrayPointer(yd);
    const double F = b->engine_on ? 30000.0 : 0.0;
    d[0] = x[1];
    d[1] = F / x[2] - 9.81;
    d[2] = b->engine_on ? -10.0 : 0.0;
    return 0;
}
static int asc_gf(sunrealtype t, N_Vector y, sunrealtype *g, void *u)
{
    (void)t;
    bare_state *b = u;
    const double *x = N_VGetArrayPointer(y);
    g[0] = b->engine_on ? x[2] - 400.0 : 1.0;
    g[1] = x[1];
    g[2] = x[0];
    return 0;
}
static int kep_f(sunrealtype t, N_Vector y, N_Vector yd, void *u)
{
    (void)t, (void)u;
    const double *x = N_VGetArrayPointer(y);
    double *d = N_VGetArrayPointer(yd);
    const double r2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
    const double k = -3.986004418e14 / (r2 * sqrt(r2));
    d[0] = x[3], d[1] = x[4], d[2] = x[5];
    d[3] = k * x[0], d[4] = k * x[1], d[5] = k * x[2];
    return 0;
}
static int kep_gf(sunrealtype t, N_Vector y, sunrealtype *g, void *u)
{
    (void)t, (void)u;
    const double *x = N_VGetArrayPointer(y);
    g[0] = x[0] * x[3] + x[1] * x[4] + x[2] * x[5];
    return 0;
}

/* ---- bare SUNDIALS loop ------------------------------------------------------------------- */

typedef struct bare_result {
    long steps, nfe;
    double seconds;
} bare_result;

static void bare_run(const problem *pb, const char *method, double h_fixed, bare_result *res)
{
    int is_asc = pb->model == &lv_model_vertical_ascent;
    SUNContext ctx;
    SUNContext_Create(NULL, &ctx);
    N_Vector y = N_VNew_Serial((sunindextype)pb->n, ctx);
    N_Vector atol = N_VNew_Serial((sunindextype)pb->n, ctx);
    memcpy(N_VGetArrayPointer(y), pb->x0, pb->n * sizeof(double));
    for (size_t i = 0; i < pb->n; i++)
        N_VGetArrayPointer(atol)[i] = pb->tol * pb->atol_nominal[i];
    bare_state bs = {1, 0};
    static double out[4096][6]; /* the bare loop stores its output rows */
    ARKRhsFn f = is_asc ? asc_f : kep_f;
    ARKRootFn g = is_asc ? asc_gf : kep_gf;
    int cv = strcmp(method, "dassl") == 0 || strcmp(method, "cvode-adams") == 0;
    void *mem;
    SUNMatrix A = NULL;
    SUNLinearSolver LS = NULL;
    SUNNonlinearSolver NLS = NULL;
    ARKodeButcherTable B = NULL;
    double t0 = now();
    if (cv) {
        mem = CVodeCreate(strcmp(method, "dassl") == 0 ? CV_BDF : CV_ADAMS, ctx);
        CVodeInit(mem, f, 0.0, y);
        CVodeSetUserData(mem, &bs);
        CVodeSVtolerances(mem, pb->tol, atol);
        if (strcmp(method, "dassl") == 0) {
            A = SUNDenseMatrix((sunindextype)pb->n, (sunindextype)pb->n, ctx);
            LS = SUNLinSol_Dense(y, A, ctx);
            CVodeSetLinearSolver(mem, LS, A);
        } else {
            NLS = SUNNonlinSol_FixedPoint(y, 0, ctx);
            CVodeSetNonlinearSolver(mem, NLS);
        }
        CVodeRootInit(mem, (int)pb->ng, g);
        CVodeSetRootDirection(mem, (int *)pb->g_dir);
        CVodeSetNoInactiveRootWarn(mem);
        CVodeSetMaxNumSteps(mem, 1000000);
        CVodeSetStopTime(mem, pb->tf);
    } else {
        mem = ERKStepCreate(f, 0.0, y, ctx);
        ERKStepSetUserData(mem, &bs);
        ERKStepSVtolerances(mem, pb->tol, atol);
        if (strcmp(method, "dopri5") == 0) {
            ERKStepSetTableNum(mem, ARKODE_DORMAND_PRINCE_7_4_5);
        } else if (strcmp(method, "rk4") == 0) {
            /* the same FSAL-safe classical RK4 tableau lvsim uses */
            const double w1 = 1.0 / 6.0, w2 = 1.0 / 3.0;
            double c[5] = {0, 0.5, 0.5, 1, 1};
            double Am[25] = {0, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 0, 0.5, 0, 0, 0,
                             0, 0, 1, 0, 0, w1, w2, w2, w1, 0};
            double b[5] = {w1, w2, w2, w1, 0};
            B = ARKodeButcherTable_Create(5, 4, 0, c, Am, b, NULL);
            ERKStepSetTable(mem, B);
            ERKStepSetFixedStep(mem, h_fixed);
        } else {
            double c[1] = {0}, Am[1] = {0}, b[1] = {1};
            ERKStepSetInterpolantType(mem, ARK_INTERP_LAGRANGE);
            B = ARKodeButcherTable_Create(1, 1, 0, c, Am, b, NULL);
            ERKStepSetTable(mem, B);
            ERKStepSetFixedStep(mem, h_fixed);
        }
        ERKStepRootInit(mem, (int)pb->ng, g);
        ERKStepSetRootDirection(mem, (int *)pb->g_dir);
        ERKStepSetNoInactiveRootWarn(mem);
        ERKStepSetMaxNumSteps(mem, 1000000);
        ERKStepSetStopTime(mem, pb->tf);
    }
    long acc_steps = 0, acc_nfe = 0;
    double t = 0.0;
    int k = 1, done = 0;
    while (!done) {
        double tout = k >= pb->intervals ? pb->tf : pb->tf * k / pb->intervals;
        int flag = cv ? CVode(mem, tout, y, &t, CV_NORMAL)
                      : ERKStepEvolve(mem, tout, y, &t, ARK_NORMAL);
        if (flag < 0)
            break;
        memcpy(out[k % 4096], N_VGetArrayPointer(y), pb->n * sizeof(double));
        if (flag == CV_ROOT_RETURN) {
            int roots[3];
            if (cv)
                CVodeGetRootInfo(mem, roots);
            else
                ERKStepGetRootInfo(mem, roots);
            if (t >= tout)
                k++; /* the root fell on the grid point */
            if (is_asc && (roots[1] || roots[2]))
                done = 1; /* apogee or impact */
            else if (is_asc && roots[0]) {
                bs.engine_on = 0;
                if (cv) {
                    long s1, f1, f2 = 0;
                    CVodeGetNumSteps(mem, &s1);
                    CVodeGetNumRhsEvals(mem, &f1);
                    if (LS)
                        CVodeGetNumLinRhsEvals(mem, &f2);
                    acc_steps += s1;
                    acc_nfe += f1 + f2;
                    CVodeReInit(mem, t, y);
                    CVodeSetStopTime(mem, pb->tf);
                } else {
                    ERKStepReset(mem, t, y);
                    ERKStepSetStopTime(mem, pb->tf);
                }
            }
        } else {
            k++;
            if (t >= pb->tf)
                done = 1;
        }
    }
    res->seconds = now() - t0;
    long s1 = 0, f1 = 0, f2 = 0;
    if (cv) {
        CVodeGetNumSteps(mem, &s1);
        CVodeGetNumRhsEvals(mem, &f1);
        if (LS)
            CVodeGetNumLinRhsEvals(mem, &f2);
        CVodeFree(&mem);
    } else {
        ERKStepGetNumSteps(mem, &s1);
        ERKStepGetNumRhsEvals(mem, &f1);
        ERKStepFree(&mem);
    }
    res->steps = acc_steps + s1;
    res->nfe = acc_nfe + f1 + f2;
    if (B)
        ARKodeButcherTable_Free(B);
    if (LS)
        SUNLinSolFree(LS);
    if (NLS)
        SUNNonlinSolFree(NLS);
    if (A)
        SUNMatDestroy(A);
    N_VDestroy(y);
    N_VDestroy(atol);
    SUNContext_Free(&ctx);
}

/* ---- lvsim ------------------------------------------------------------------------------- */

static int lvsim_run(const problem *pb, const char *method, double h_fixed, lv_sim_report *rep)
{
    lv_sim_settings s;
    lv_sim_settings_default(&s);
    s.result_file = NULL; /* rows are still computed (derivatives, outputs), not stored */
    s.method = method;
    s.tolerance = pb->tol;
    s.stop_time = pb->tf;
    s.number_of_intervals = pb->intervals;
    s.fixed_step = h_fixed;
    s.n_initial = pb->n_set;
    s.initial_names = pb->set_names;
    s.initial_values = pb->set_values;
    lv_err err;
    if (lv_simulate(pb->model, NULL, &s, NULL, rep, &err) != LV_OK) {
        fprintf(stderr, "bench: %s\n", err.msg);
        return 0;
    }
    return 1;
}

int main(void)
{
    const double T = 2.0 * M_PI * sqrt(pow(7.0e6, 3) / 3.986004418e14);
    const double rp = 7.0e6 * 0.9, vp = sqrt(3.986004418e14 * 1.1 / rp);
    problem probs[2] = {
        {"ascent", &lv_model_vertical_ascent, 3, 3, 500.0, 1e-7, 500, asc_names, asc_values, 1,
         {0, 0, 1000}, {1e4, 1e3, 1e3}, {-1, -1, -1}},
        {"kepler", &lv_model_kepler, 6, 1, 10.0 * T, 1e-7, 500, NULL, NULL, 0,
         {rp, 0, 0, 0, vp, 0}, {1e7, 1e7, 1e7, 1e4, 1e4, 1e4}, {1, 0, 0}},
    };
    const char *methods[] = {"dassl", "cvode-adams", "dopri5", "rk4", "euler"};
    printf("# lv_simulate vs a bare SUNDIALS loop (same RHS, tolerances, events, output grid)\n");
    printf("# tol 1e-7, 500 output intervals; thread CPU time, fastest of the repetitions\n");
    printf("%-7s %-12s %8s %8s %9s %9s %10s %10s %10s %7s\n", "problem", "method", "steps",
           "bare", "rhs", "ns/rhs", "ns/step", "bare/step", "ms/run", "ratio");
    for (int p = 0; p < 2; p++) {
        for (int m = 0; m < 5; m++) {
            double h = p == 0 ? (m == 4 ? 0.002 : 0.02) : (m == 4 ? T / 20000.0 : T / 2000.0);
            lv_sim_report rep;
            bare_result bare = {0};
            double best_lv = INFINITY, best_bare = INFINITY;
            int reps = m >= 3 ? 7 : 30;
            for (int r = 0; r < reps; r++) {
                double t0 = now();
                if (!lvsim_run(&probs[p], methods[m], h, &rep))
                    return 1;
                best_lv = fmin(best_lv, now() - t0);
                if (r + 1 < reps)
                    lv_sim_report_clear(&rep);
                bare_run(&probs[p], methods[m], h, &bare);
                best_bare = fmin(best_bare, bare.seconds);
            }
            double ns_step = 1e9 * best_lv / (double)rep.stats.steps;
            double ns_bare = 1e9 * best_bare / (double)bare.steps;
            printf("%-7s %-12s %8ld %8ld %9ld %9.1f %10.1f %10.1f %10.3f %7.3f\n", probs[p].name,
                   methods[m], rep.stats.steps, bare.steps, rep.stats.rhs_evals,
                   1e9 * best_lv / (double)rep.stats.rhs_evals, ns_step, ns_bare, 1e3 * best_lv,
                   ns_step / ns_bare);
            lv_sim_report_clear(&rep);
        }
    }
    printf("# ratio = lvsim ns/step over bare ns/step (goal <= 1.20 at equal steps)\n");
    return 0;
}
