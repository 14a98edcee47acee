/* integrator.c - SUNDIALS 6.x (SUNContext API) behind lv_integ: CVODE for BDF and
 * Adams, ARKODE ERKStep for Dormand-Prince 5(4), classical RK4 and explicit Euler.
 * Root finding and stop times are SUNDIALS' own (CVodeRootInit, CVodeSetStopTime).
 * lvsim's own explicit methods dp5 and dop853 (erk.c) and "auto" (one of them, then CVODE BDF
 * once the problem is found stiff) are dispatched from here.
 */
#include "integrate/integrator.h"

#include "integrate/erk.h"

#include <arkode/arkode_erkstep.h>
#include <cvode/cvode.h>
#include <float.h>
#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include "core/status.h"
#include "integrate/sundials_dl.h"

struct lv_integ {
    lv_integ_problem p;
    double *atol;
    double *rtol_v;           /* [n] per-state relative tolerances, or NULL */
    unsigned char *quad;      /* [n] quadrature states (lv_integ_problem.quad), or NULL */
    double ewt_scale;         /* with quad: sqrt(n / n_controlled), the controlled weights' */
    int *g_dir;
    SUNContext ctx;
    N_Vector y;
    N_Vector atol_v;
    SUNMatrix A;
    SUNLinearSolver LS;
    SUNNonlinearSolver NLS;
    ARKodeButcherTable table; /* rk4/euler: our own tableau */
    void *mem;                /* CVODE or ARKODE memory */
    int is_cvode;
    double t;                 /* time reached */
    double tstop;             /* current stop time, or NAN */
    lv_integ_stats acc;       /* CVODE counters from before the last CVodeReInit */
    char sun_msg[256];        /* last message from SUNDIALS' error handler */
    /* ERKStep (dopri5, rk4, euler): the last right-hand side evaluation, reused when ARKODE
     * asks for exactly the same (t, x) again (its dense output, below), and our counts */
    int memo_ok;
    double memo_t;
    double *memo_x, *memo_f;  /* [n] each */
    long n_step, n_dense, n_reused;
    /* dp5, dop853, auto: lvsim's own explicit integrator; auto: CVODE BDF once stiff */
    lv_erk *erk;
    lv_integ *bdf;
    double t_switch;          /* auto: where BDF took over (NAN: from the start or never) */
    lv_integ_pace pace;       /* SUNDIALS methods: the step-size collapse check */
    /* SUNDIALS methods: the library and its objects are set up at the first advance
     * (sun_setup), so that a simulation created and freed without stepping - `lvsim check`
     * trying each phase's start - never loads SUNDIALS (integrate/cvode_dl.c) */
    int sun_ready;
    double *x_pending;        /* [n] the state to start from until then */
};

/* The explicit method of "auto": measured on the example missions and bench_flight
 * (docs/integration.md, "auto"). */
#define LV_METHOD_AUTO_EXPLICIT LV_METHOD_DOP853

static int is_own(lv_method m)
{
    return m == LV_METHOD_DP5 || m == LV_METHOD_DOP853 || m == LV_METHOD_AUTO;
}

/* ---- methods ------------------------------------------------------------------ */

static const struct {
    const char *name;
    lv_method m;
} method_names[] = {
    {"dassl", LV_METHOD_BDF},        {"bdf", LV_METHOD_BDF},       {"cvode-bdf", LV_METHOD_BDF},
    {"cvode-adams", LV_METHOD_ADAMS}, {"adams", LV_METHOD_ADAMS},  {"dopri5", LV_METHOD_DOPRI5},
    {"dopri45", LV_METHOD_DOPRI5},   {"rk4", LV_METHOD_RK4},       {"rungekutta", LV_METHOD_RK4},
    {"euler", LV_METHOD_EULER},       {"dp5", LV_METHOD_DP5},       {"dop853", LV_METHOD_DOP853},
    {"dopri853", LV_METHOD_DOP853},  {"auto", LV_METHOD_AUTO},
};
#define LV_METHOD_LIST "dassl, cvode-adams, dopri5, rk4, euler, dp5, dop853, auto"

lv_status lv_method_parse(const char *name, lv_method *out, lv_err *err)
{
    if (name == NULL || name[0] == '\0')
        return lv_fail(err, LV_ERR_INPUT, "integration method is empty; use one of "
                                          LV_METHOD_LIST);
    for (size_t i = 0; i < sizeof method_names / sizeof method_names[0]; i++) {
        if (strcasecmp(name, method_names[i].name) == 0) {
            *out = method_names[i].m;
            return LV_OK;
        }
    }
    return lv_fail(err, LV_ERR_INPUT,
                   "unknown integration method '%s'; use one of " LV_METHOD_LIST, name);
}

const char *lv_method_name(lv_method m)
{
    static const char *const names[LV_METHOD_COUNT] = {
        "dassl", "cvode-adams", "dopri5", "rk4", "euler", "dp5", "dop853", "auto"};
    return (m >= 0 && m < LV_METHOD_COUNT) ? names[m] : "?";
}

int lv_method_is_fixed_step(lv_method m) { return m == LV_METHOD_RK4 || m == LV_METHOD_EULER; }

/* ---- SUNDIALS callbacks ---------------------------------------------------------- */

static int sun_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void *user)
{
    lv_integ *ig = user;
    return ig->p.rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot), ig->p.user);
}

/* ERKStep's right-hand side. ARKODE 6.4's dense output for dopri5 is a degree-4 Hermite
 * polynomial that needs f at t_n - h/3 of the last step, at the state its cubic Hermite gives
 * there, and it evaluates that f again for every output time in the step, for every root
 * check and every root-finding iterate (arkInterpEvaluate_Hermite recomputes it each call).
 * Those calls repeat exactly the same (t, x): the model is a pure function of them (its mode
 * changes only at events, after which lv_integ_forget drops the memory), so the repeat is
 * answered from the remembered evaluation, bit for bit what the model would return. Output
 * then costs at most one RHS per step that holds output times, not one or two per output
 * time; every value stays the same.
 * The calls are counted as ARKODE makes them: a stage (and the FSAL, step-size and start
 * evaluations) is evaluated at ARKODE's current time t == tcur; the dense output's at
 * tcur - h_last/3, exactly as arkInterpEvaluate_Hermite computes it. */
static int sun_rhs_erk(sunrealtype t, N_Vector y, N_Vector ydot, void *user)
{
    lv_integ *ig = user;
    const size_t n = ig->p.n;
    const double *x = N_VGetArrayPointer(y);
    double *f = N_VGetArrayPointer(ydot);
    if (ig->memo_ok && t == ig->memo_t && memcmp(x, ig->memo_x, n * sizeof *x) == 0) {
        memcpy(f, ig->memo_f, n * sizeof *f);
        ig->n_reused++;
        return 0;
    }
    sunrealtype tcur = t, hlast = 0.0;
    ERKStepGetCurrentTime(ig->mem, &tcur);
    ERKStepGetLastStep(ig->mem, &hlast);
    if (t != tcur && t == tcur - hlast / 3.0)
        ig->n_dense++;
    else
        ig->n_step++;
    const int rc = ig->p.rhs(t, x, f, ig->p.user);
    ig->memo_ok = rc == 0;
    if (rc == 0) {
        ig->memo_t = t;
        memcpy(ig->memo_x, x, n * sizeof *x);
        memcpy(ig->memo_f, f, n * sizeof *f);
    }
    return rc;
}

void lv_integ_forget(lv_integ *ig)
{
    ig->memo_ok = 0;
}

/* Error weights with a relative tolerance per state: w_i = 1 / (rtol_i |y_i| + atol_i), the
 * weights CVODE and ARKODE form from scalar tolerances, with rtol_i = 0 for a state whose
 * error is controlled absolutely (a coordinate measured from a distant origin). With
 * quadrature states (lv_integ_problem.quad): theirs times LV_QUAD_EWT - not 0, which CVODE's
 * difference-quotient Jacobian divides by (its column of a quadrature, which no right-hand
 * side reads, is zero whatever the increment) - and the others' times sqrt(n / n_controlled), so
 * that the weighted RMS norm over n states is the norm over the controlled ones. */
#define LV_QUAD_EWT 1e-30
static int sun_ewt(N_Vector y, N_Vector w, void *user)
{
    const lv_integ *ig = user;
    const double *yv = N_VGetArrayPointer(y);
    double *wv = N_VGetArrayPointer(w);
    for (size_t i = 0; i < ig->p.n; i++) {
        const double d = ig->rtol_v[i] * fabs(yv[i]) + ig->atol[i];
        if (!(d > 0.0))
            return -1;
        wv[i] = 1.0 / d;
        if (ig->quad != NULL)
            wv[i] *= ig->quad[i] ? LV_QUAD_EWT : ig->ewt_scale;
    }
    return 0;
}

static int sun_g(sunrealtype t, N_Vector y, sunrealtype *g, void *user)
{
    lv_integ *ig = user;
    return ig->p.g(t, N_VGetArrayPointer(y), g, ig->p.user);
}

/* SUNDIALS would print to stderr; the library never prints, so keep the text. */
static void sun_err_handler(int code, const char *module, const char *function, char *msg,
                            void *user)
{
    (void)code;
    lv_integ *ig = user;
    /* Named after the method the user chose ("dassl" runs SUNDIALS' CVODE with BDF), then
     * the SUNDIALS module and function that complained. */
    snprintf(ig->sun_msg, sizeof ig->sun_msg, "(method %s: SUNDIALS %s, %s) %s",
             lv_method_name(ig->p.method), module, function, msg);
}

/* ---- creation ------------------------------------------------------------------ */

/* Classical RK4 and explicit Euler as Butcher tableaux: SUNDIALS 6.4 ships neither
 * among its named ERK tables, so they are given here and run by ERKStep.
 *
 * RK4 carries a fifth stage at c = 1 whose row equals b (weight 0). The result is
 * exactly classical RK4, and the method is then truly "first same as last": ARKODE
 * 6.4 treats every table with c[s-1] = 1 as FSAL and would otherwise reuse stage 4,
 * f(t + h, y + h k3), as if it were f(t + h, y_{n+1}) (fixed upstream in SUNDIALS
 * 6.5). The extra stage costs nothing: it is the next step's first stage. */
static ARKodeButcherTable make_fixed_table(lv_method m)
{
    if (m == LV_METHOD_RK4) {
        const sunrealtype w1 = 1.0 / 6.0, w2 = 1.0 / 3.0;
        sunrealtype c[5] = {0.0, 0.5, 0.5, 1.0, 1.0};
        sunrealtype A[25] = {0,   0,   0,   0,   0,   /* k1 = f(t, y)             */
                             0.5, 0,   0,   0,   0,   /* k2 = f(t+h/2, y+h/2 k1)  */
                             0,   0.5, 0,   0,   0,   /* k3 = f(t+h/2, y+h/2 k2)  */
                             0,   0,   1.0, 0,   0,   /* k4 = f(t+h, y+h k3)      */
                             w1,  w2,  w2,  w1,  0};  /* k5 = f(t+h, y_{n+1})     */
        sunrealtype b[5] = {w1, w2, w2, w1, 0.0};
        return ARKodeButcherTable_Create(5, 4, 0, c, A, b, NULL);
    }
    /* Explicit Euler, declared of order 2: ARKODE caps the degree of its dense output (used
     * for output times, stop times and located events) at the declared order minus one, and
     * degree 0 - a constant - reported an event located inside a step with the step's end
     * state. The order has no other use for a fixed-step table without an embedding; with
     * it, the Lagrange interpolant of degree 1 is Euler's own straight line (test_simulate). */
    sunrealtype c[1] = {0.0}, A[1] = {0.0}, b[1] = {1.0};
    return ARKodeButcherTable_Create(1, 2, 0, c, A, b, NULL);
}

/* SUNDIALS' name of a return flag ("CV_TOO_MUCH_WORK"), copied: the library allocates the
 * string it returns and leaves freeing it to the caller. */
static const char *flag_name(const lv_integ *ig, int flag, char *buf, size_t cap)
{
    char *name = ig->is_cvode ? CVodeGetReturnFlagName(flag) : ERKStepGetReturnFlagName(flag);
    snprintf(buf, cap, "%s", name ? name : "?");
    free(name);
    return buf;
}

#define SUNCHK(call, what)                                                                  \
    do {                                                                                    \
        int flag_ = (call);                                                                 \
        if (flag_ < 0) {                                                                    \
            char fname_[64];                                                                \
            st = lv_fail(err, LV_ERR_SOLVER, "setting up %s: %s (%s)", (what),              \
                         flag_name(ig, flag_, fname_, sizeof fname_), ig->sun_msg);         \
            goto fail;                                                                      \
        }                                                                                   \
    } while (0)

lv_status lv_integ_create(const lv_integ_problem *p, double t0, const double *x0, lv_integ **out,
                          lv_err *err)
{
    lv_status st = LV_OK;
    *out = NULL;
    if (p->n == 0)
        return lv_fail(err, LV_ERR_INPUT, "integrator: a model needs at least one state");
    if (!(p->rtol > 0.0) || !isfinite(p->rtol))
        return lv_fail(err, LV_ERR_INPUT, "integrator: tolerance must be > 0 (got %g)", p->rtol);
    if (lv_method_is_fixed_step(p->method) && !(p->fixed_step > 0.0 && isfinite(p->fixed_step)))
        return lv_fail(err, LV_ERR_INPUT, "integrator: method %s needs a fixed step > 0 (got %g)",
                       lv_method_name(p->method), p->fixed_step);
    if (p->n_g > 0 && p->g == NULL)
        return lv_fail(err, LV_ERR_INPUT, "integrator: %zu event functions but no g()", p->n_g);

    lv_integ *ig = calloc(1, sizeof *ig);
    if (ig == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "integrator: out of memory");
    ig->p = *p;
    ig->t = t0;
    ig->tstop = NAN;
    ig->pace = (lv_integ_pace){t0, t0, 0, p->max_steps};
    ig->is_cvode = (p->method == LV_METHOD_BDF || p->method == LV_METHOD_ADAMS);
    ig->atol = malloc(p->n * sizeof *ig->atol);
    ig->g_dir = calloc(p->n_g ? p->n_g : 1, sizeof *ig->g_dir);
    if (ig->atol == NULL || ig->g_dir == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "integrator: out of memory");
        goto fail;
    }
    memcpy(ig->atol, p->atol, p->n * sizeof *ig->atol);
    if (!ig->is_cvode) {
        ig->memo_x = malloc(2 * p->n * sizeof *ig->memo_x);
        if (ig->memo_x == NULL) {
            st = lv_fail(err, LV_ERR_NOMEM, "integrator: out of memory");
            goto fail;
        }
        ig->memo_f = ig->memo_x + p->n;
    }
    size_t n_quad = 0;
    if (p->quad != NULL) {
        for (size_t i = 0; i < p->n; i++)
            n_quad += p->quad[i] != 0;
        if (n_quad == p->n) {
            st = lv_fail(err, LV_ERR_INPUT, "integrator: every state is a quadrature: none "
                         "left to control the error");
            goto fail;
        }
    }
    if (n_quad > 0) {
        if ((ig->quad = malloc(p->n)) == NULL) {
            st = lv_fail(err, LV_ERR_NOMEM, "integrator: out of memory");
            goto fail;
        }
        memcpy(ig->quad, p->quad, p->n);
        ig->ewt_scale = sqrt((double)p->n / (double)(p->n - n_quad));
    }
    ig->p.quad = ig->quad;
    if (p->rtol_v != NULL || n_quad > 0) { /* quadratures: the weight function sun_ewt */
        if ((ig->rtol_v = malloc(p->n * sizeof *ig->rtol_v)) == NULL) {
            st = lv_fail(err, LV_ERR_NOMEM, "integrator: out of memory");
            goto fail;
        }
        for (size_t i = 0; i < p->n; i++)
            ig->rtol_v[i] = p->rtol_v != NULL ? p->rtol_v[i] : p->rtol;
        ig->p.rtol_v = ig->rtol_v;
    }
    if (p->g_dir != NULL)
        memcpy(ig->g_dir, p->g_dir, p->n_g * sizeof *ig->g_dir);
    ig->p.atol = ig->atol;
    ig->p.g_dir = ig->g_dir;
    ig->t_switch = NAN;

    if (is_own(p->method)) {
        ig->is_cvode = 0;
        if (p->method == LV_METHOD_AUTO && p->stiff) {
            lv_integ_problem pb = ig->p;
            pb.method = LV_METHOD_BDF;
            st = lv_integ_create(&pb, t0, x0, &ig->bdf, err);
        } else {
            const lv_method m = p->method == LV_METHOD_AUTO ? LV_METHOD_AUTO_EXPLICIT : p->method;
            st = lv_erk_create(&ig->p, m == LV_METHOD_DOP853, t0, x0, &ig->erk, err);
        }
        if (st != LV_OK)
            goto fail;
        *out = ig;
        return LV_OK;
    }

    ig->x_pending = malloc(p->n * sizeof *ig->x_pending);
    if (ig->x_pending == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "integrator: out of memory");
        goto fail;
    }
    memcpy(ig->x_pending, x0, p->n * sizeof *ig->x_pending);
    *out = ig;
    return LV_OK;

fail:
    lv_integ_free(ig);
    return st;
}

/* The SUNDIALS integrator of a dassl, cvode-adams, dopri5, rk4 or euler problem, from
 * (ig->t, ig->x_pending) with the stop time set so far: at the first advance. On failure the
 * objects made so far stay for lv_integ_free. */
static lv_status sun_setup(lv_integ *ig, lv_err *err)
{
    lv_status st = LV_OK;
    const lv_integ_problem *p = &ig->p;
    const double t0 = ig->t;
    const double *x0 = ig->x_pending;
    /* SUNDIALS is loaded on first use (integrate/cvode_dl.c): say why it cannot be */
    const char *why = lv_cvode_error();
    if (why == NULL && !ig->is_cvode)
        why = lv_arkode_error();
    if (why != NULL) {
        st = lv_fail(err, LV_ERR_IO, "integrator: method '%s' needs SUNDIALS: %s",
                     lv_method_name(p->method), why);
        goto fail;
    }
    if (SUNContext_Create(NULL, &ig->ctx) != 0) {
        st = lv_fail(err, LV_ERR_NOMEM, "integrator: cannot create SUNDIALS context");
        goto fail;
    }
    sunindextype n = (sunindextype)p->n;
    ig->y = N_VNew_Serial(n, ig->ctx);
    ig->atol_v = N_VNew_Serial(n, ig->ctx);
    if (ig->y == NULL || ig->atol_v == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "integrator: out of memory");
        goto fail;
    }
    memcpy(N_VGetArrayPointer(ig->y), x0, p->n * sizeof(double));
    memcpy(N_VGetArrayPointer(ig->atol_v), ig->atol, p->n * sizeof(double));

    if (ig->is_cvode) {
        ig->mem = CVodeCreate(p->method == LV_METHOD_BDF ? CV_BDF : CV_ADAMS, ig->ctx);
        if (ig->mem == NULL) {
            st = lv_fail(err, LV_ERR_NOMEM, "integrator: CVodeCreate failed");
            goto fail;
        }
        SUNCHK(CVodeSetErrHandlerFn(ig->mem, sun_err_handler, ig), "CVODE error handler");
        SUNCHK(CVodeInit(ig->mem, sun_rhs, t0, ig->y), "CVODE");
        SUNCHK(CVodeSetUserData(ig->mem, ig), "CVODE user data");
        if (ig->rtol_v != NULL)
            SUNCHK(CVodeWFtolerances(ig->mem, sun_ewt), "CVODE tolerances");
        else
            SUNCHK(CVodeSVtolerances(ig->mem, p->rtol, ig->atol_v), "CVODE tolerances");
        if (p->method == LV_METHOD_BDF) {
            ig->A = SUNDenseMatrix(n, n, ig->ctx);
            ig->LS = ig->A ? SUNLinSol_Dense(ig->y, ig->A, ig->ctx) : NULL;
            if (ig->LS == NULL) {
                st = lv_fail(err, LV_ERR_NOMEM, "integrator: cannot create dense linear solver");
                goto fail;
            }
            SUNCHK(CVodeSetLinearSolver(ig->mem, ig->LS, ig->A), "CVODE linear solver");
        } else {
            ig->NLS = SUNNonlinSol_FixedPoint(ig->y, 0, ig->ctx);
            if (ig->NLS == NULL) {
                st = lv_fail(err, LV_ERR_NOMEM, "integrator: cannot create fixed-point solver");
                goto fail;
            }
            SUNCHK(CVodeSetNonlinearSolver(ig->mem, ig->NLS), "CVODE nonlinear solver");
        }
        if (p->max_step > 0.0)
            SUNCHK(CVodeSetMaxStep(ig->mem, p->max_step), "CVODE max step");
        /* CVODE's first step after a start or a restart comes from an estimate bounded by the
         * distance to the next output time; on a far output grid (stop_time 1e30: 2e27 s
         * between rows) that estimate can be ~1e8 s, and the default 7 error-test failures
         * (each cutting h by at most 10x) end at h ~ 10 s, still failing: 30 let the step
         * shrink from there to the model's scale. A run that passes with 7 is unchanged. */
        SUNCHK(CVodeSetMaxErrTestFails(ig->mem, 30), "CVODE error-test failures");
        if (p->n_g > 0) {
            SUNCHK(CVodeRootInit(ig->mem, (int)p->n_g, sun_g), "CVODE root finding");
            SUNCHK(CVodeSetRootDirection(ig->mem, ig->g_dir), "CVODE root directions");
            SUNCHK(CVodeSetNoInactiveRootWarn(ig->mem), "CVODE root warnings");
        }
    } else {
        ig->mem = ERKStepCreate(sun_rhs_erk, t0, ig->y, ig->ctx);
        if (ig->mem == NULL) {
            st = lv_fail(err, LV_ERR_NOMEM, "integrator: ERKStepCreate failed");
            goto fail;
        }
        SUNCHK(ERKStepSetErrHandlerFn(ig->mem, sun_err_handler, ig), "ARKODE error handler");
        SUNCHK(ERKStepSetUserData(ig->mem, ig), "ARKODE user data");
        if (ig->rtol_v != NULL)
            SUNCHK(ERKStepWFtolerances(ig->mem, sun_ewt), "ARKODE tolerances");
        else
            SUNCHK(ERKStepSVtolerances(ig->mem, p->rtol, ig->atol_v), "ARKODE tolerances");
        if (p->method == LV_METHOD_DOPRI5) {
            SUNCHK(ERKStepSetTableNum(ig->mem, ARKODE_DORMAND_PRINCE_7_4_5), "ARKODE table");
            /* ARKODE's default dense output here is a degree-4 Hermite polynomial: outputs
             * as accurate as the steps (the cubic one made output errors 100x larger in
             * test_simulate). Its extra RHS evaluation is the same for every output time
             * of a step: sun_rhs_erk evaluates it once per step (docs/integration.md). */
        } else {
            ig->table = make_fixed_table(p->method);
            if (ig->table == NULL) {
                st = lv_fail(err, LV_ERR_NOMEM, "integrator: cannot create Butcher table");
                goto fail;
            }
            SUNCHK(ERKStepSetTable(ig->mem, ig->table), "ARKODE table");
            SUNCHK(ERKStepSetFixedStep(ig->mem, p->fixed_step), "ARKODE fixed step");
            /* ARKODE returns values at stop times, output times and located roots from its
             * dense output, whose degree it caps at the method's order minus one: for the
             * one-stage Euler table, degree 0 - a constant, so an event located inside a
             * step reported the step's end state (an altitude end at 5000 m gave 5510 m).
             * Euler's own interpolant is the straight line through y_n and y_{n+1}: the
             * Lagrange interpolant of degree 1 (6.4's Hermite one did not reproduce the
             * step's end point: it returned (y_n + y_{n+1})/2 at t_{n+1}). */
            if (p->method == LV_METHOD_EULER) {
                SUNCHK(ERKStepSetInterpolantType(ig->mem, ARK_INTERP_LAGRANGE),
                       "ARKODE interpolant");
                SUNCHK(ERKStepSetInterpolantDegree(ig->mem, 1), "ARKODE interpolant degree");
            }
        }
        if (p->max_step > 0.0)
            SUNCHK(ERKStepSetMaxStep(ig->mem, p->max_step), "ARKODE max step");
        if (p->n_g > 0) {
            SUNCHK(ERKStepRootInit(ig->mem, (int)p->n_g, sun_g), "ARKODE root finding");
            SUNCHK(ERKStepSetRootDirection(ig->mem, ig->g_dir), "ARKODE root directions");
            SUNCHK(ERKStepSetNoInactiveRootWarn(ig->mem), "ARKODE root warnings");
        }
    }
    if (!isnan(ig->tstop)) {
        const int flag = ig->is_cvode ? CVodeSetStopTime(ig->mem, ig->tstop)
                                      : ERKStepSetStopTime(ig->mem, ig->tstop);
        if (flag < 0) {
            st = lv_fail(err, LV_ERR_SOLVER, "integrator: cannot set stop time %.17g: %s",
                         ig->tstop, ig->sun_msg);
            goto fail;
        }
    }
    ig->sun_ready = 1;
    return LV_OK;

fail:
    return st;
}

void lv_integ_free(lv_integ *ig)
{
    if (ig == NULL)
        return;
    if (ig->mem != NULL) {
        if (ig->is_cvode)
            CVodeFree(&ig->mem);
        else
            ERKStepFree(&ig->mem);
    }
    if (ig->table != NULL)
        ARKodeButcherTable_Free(ig->table);
    if (ig->LS != NULL)
        SUNLinSolFree(ig->LS);
    if (ig->NLS != NULL)
        SUNNonlinSolFree(ig->NLS);
    if (ig->A != NULL)
        SUNMatDestroy(ig->A);
    if (ig->y != NULL)
        N_VDestroy(ig->y);
    if (ig->atol_v != NULL)
        N_VDestroy(ig->atol_v);
    if (ig->ctx != NULL)
        SUNContext_Free(&ig->ctx);
    free(ig->atol);
    free(ig->rtol_v);
    free(ig->quad);
    free(ig->g_dir);
    free(ig->memo_x);
    free(ig->x_pending);
    lv_erk_free(ig->erk);
    lv_integ_free(ig->bdf);
    free(ig);
}

/* ---- stepping ------------------------------------------------------------------ */

static void raw_stats(const lv_integ *ig, lv_integ_stats *s)
{
    memset(s, 0, sizeof *s);
    if (!ig->sun_ready)
        return; /* no step yet */
    if (ig->is_cvode) {
        long nfe_ls = 0;
        CVodeGetNumSteps(ig->mem, &s->steps);
        CVodeGetNumRhsEvals(ig->mem, &s->rhs_evals);
        CVodeGetNumErrTestFails(ig->mem, &s->err_test_fails);
        CVodeGetNumNonlinSolvConvFails(ig->mem, &s->nonlin_fails);
        if (ig->p.n_g > 0)
            CVodeGetNumGEvals(ig->mem, &s->g_evals);
        if (ig->p.method == LV_METHOD_BDF) {
            CVodeGetNumJacEvals(ig->mem, &s->jac_evals);
            CVodeGetNumLinRhsEvals(ig->mem, &nfe_ls); /* f calls for DQ Jacobians */
        }
        s->rhs_evals += nfe_ls;
        s->rhs_step = s->rhs_evals; /* CVODE interpolates from its history: no RHS */
    } else {
        /* the model's own evaluations (sun_rhs_erk): ARKODE's count also has the repeats */
        ERKStepGetNumSteps(ig->mem, &s->steps);
        s->rhs_evals = ig->n_step + ig->n_dense;
        ERKStepGetNumErrTestFails(ig->mem, &s->err_test_fails);
        if (ig->p.n_g > 0)
            ERKStepGetNumGEvals(ig->mem, &s->g_evals);
        s->rhs_step = ig->n_step;
        s->rhs_dense = ig->n_dense;
        s->rhs_reused = ig->n_reused;
    }
}

/* dp5, dop853, auto: the explicit integrator's and BDF's counts added */
static void own_stats(const lv_integ *ig, lv_integ_stats *st)
{
    lv_integ_stats a = {0}, b = {0};
    if (ig->erk != NULL)
        lv_erk_get_stats(ig->erk, &a);
    if (ig->bdf != NULL)
        lv_integ_get_stats(ig->bdf, &b);
    st->steps = a.steps + b.steps;
    st->rhs_evals = a.rhs_evals + b.rhs_evals;
    st->jac_evals = a.jac_evals + b.jac_evals;
    st->err_test_fails = a.err_test_fails + b.err_test_fails;
    st->nonlin_fails = a.nonlin_fails + b.nonlin_fails;
    st->g_evals = a.g_evals + b.g_evals;
    st->restarts = ig->acc.restarts;
    st->rhs_step = a.rhs_step + b.rhs_step;
    st->rhs_dense = a.rhs_dense + b.rhs_dense;
    st->rhs_reused = a.rhs_reused + b.rhs_reused;
}

void lv_integ_method_used(const lv_integ *ig, char *used, size_t used_cap, char *why,
                          size_t why_cap)
{
    const char *name = lv_method_name(ig->p.method);
    char dummy[8];
    if (why == NULL) {
        why = dummy;
        why_cap = sizeof dummy;
    }
    if (ig->p.method != LV_METHOD_AUTO) {
        snprintf(used, used_cap, "%s", name);
        snprintf(why, why_cap, "chosen");
        return;
    }
    const char *ex = lv_method_name(LV_METHOD_AUTO_EXPLICIT);
    if (ig->erk == NULL) {
        snprintf(used, used_cap, "%s", lv_method_name(LV_METHOD_BDF));
        snprintf(why, why_cap, "declared stiff by the model");
    } else if (ig->bdf != NULL) {
        snprintf(used, used_cap, "%s, then %s", ex, lv_method_name(LV_METHOD_BDF));
        snprintf(why, why_cap, "stiff at t = %.6g s (Hairer's test)", ig->t_switch);
    } else {
        snprintf(used, used_cap, "%s", ex);
        snprintf(why, why_cap, "not stiff");
    }
}

void lv_integ_get_stats(const lv_integ *ig, lv_integ_stats *st)
{
    if (is_own(ig->p.method)) {
        own_stats(ig, st);
        return;
    }
    lv_integ_stats cur;
    raw_stats(ig, &cur);
    st->steps = ig->acc.steps + cur.steps;
    st->rhs_evals = ig->acc.rhs_evals + cur.rhs_evals;
    st->jac_evals = ig->acc.jac_evals + cur.jac_evals;
    st->err_test_fails = ig->acc.err_test_fails + cur.err_test_fails;
    st->nonlin_fails = ig->acc.nonlin_fails + cur.nonlin_fails;
    st->g_evals = ig->acc.g_evals + cur.g_evals;
    st->restarts = ig->acc.restarts;
    st->rhs_step = ig->acc.rhs_step + cur.rhs_step;
    st->rhs_dense = cur.rhs_dense; /* ERKStep: our counters, never reset */
    st->rhs_reused = cur.rhs_reused;
}

lv_status lv_integ_set_stop_time(lv_integ *ig, double tstop, lv_err *err)
{
    if (!(tstop > ig->t))
        return lv_fail(err, LV_ERR_SOLVER, "integrator: stop time %.17g is not after t = %.17g",
                       tstop, ig->t);
    if (is_own(ig->p.method)) {
        lv_status st = ig->bdf != NULL ? lv_integ_set_stop_time(ig->bdf, tstop, err)
                                       : lv_erk_set_stop_time(ig->erk, tstop, err);
        if (st == LV_OK)
            ig->tstop = tstop;
        return st;
    }
    if (!ig->sun_ready) { /* set at the first advance (sun_setup) */
        ig->tstop = tstop;
        return LV_OK;
    }
    int flag = ig->is_cvode ? CVodeSetStopTime(ig->mem, tstop) : ERKStepSetStopTime(ig->mem, tstop);
    if (flag < 0)
        return lv_fail(err, LV_ERR_SOLVER, "integrator: cannot set stop time %.17g: %s", tstop,
                       ig->sun_msg);
    ig->tstop = tstop;
    return LV_OK;
}

int lv_integ_pace_collapsed(lv_integ_pace *pc, double t, long steps, char *msg, size_t cap)
{
    const long n = steps - pc->n_mark;
    if (n < LV_INTEG_PACE_WINDOW)
        return 0;
    const double dt = t - pc->t_mark, age = t - pc->t0;
    pc->t_mark = t;
    pc->n_mark = steps;
    if (!(dt * LV_INTEG_PACE_FACTOR * (double)pc->max_steps < (double)n * age))
        return 0;
    snprintf(msg, cap, "at t = %.9g s: the step size collapsed: the last %ld steps advanced "
             "the time by %.3g s (mean step %.3g s; at that pace the %.6g s flown would take "
             "%.2g steps, the limit is %ld): the solution changes faster than it can be "
             "followed - a force or frame that flips from step to step, or a discontinuity "
             "that is no event", t, n, dt, dt / (double)n, age, (double)n * age / dt,
             pc->max_steps);
    return 1;
}

/* Translate SUNDIALS failure flags into what an engineer reads. */
static const char *flag_meaning(int flag)
{
    switch (flag) {
    case CV_TOO_MUCH_WORK:
        return "too much work (step limit reached)";
    case CV_TOO_MUCH_ACC:
        return "tolerance too small for machine precision";
    case CV_ERR_FAILURE:
        return "error test failed repeatedly or step size underflow";
    case CV_CONV_FAILURE:
        return "nonlinear solver failed to converge repeatedly or step size underflow";
    case CV_RHSFUNC_FAIL:
        return "right-hand side failed unrecoverably";
    case CV_FIRST_RHSFUNC_ERR:
        return "right-hand side failed at the first call";
    case CV_REPTD_RHSFUNC_ERR:
        return "right-hand side failed repeatedly (state not acceptable)";
    case CV_UNREC_RHSFUNC_ERR:
        return "right-hand side failed and could not recover";
    case CV_RTFUNC_FAIL:
        return "event function failed";
    default:
        return "integrator failure";
    }
}

static long current_steps(const lv_integ *ig)
{
    long n = 0;
    if (!ig->sun_ready)
        return ig->acc.steps;
    if (ig->is_cvode)
        CVodeGetNumSteps(ig->mem, &n);
    else
        ERKStepGetNumSteps(ig->mem, &n);
    return ig->acc.steps + n;
}

/* auto: the explicit method found the problem stiff at (t, x): CVODE BDF from there, with the
 * stop time and the steps left. */
static lv_status switch_to_bdf(lv_integ *ig, double t, const double *x, lv_err *err)
{
    lv_integ_stats a;
    lv_erk_get_stats(ig->erk, &a);
    lv_integ_problem pb = ig->p;
    pb.method = LV_METHOD_BDF;
    pb.max_steps = ig->p.max_steps - a.steps > 1 ? ig->p.max_steps - a.steps : 1;
    lv_status st = lv_integ_create(&pb, t, x, &ig->bdf, err);
    if (st == LV_OK && !isnan(ig->tstop))
        st = lv_integ_set_stop_time(ig->bdf, ig->tstop, err);
    if (st != LV_OK)
        return lv_fail_prefix(err, st, "at t = %.9g s: switching from %s to BDF (stiff)", t,
                              lv_method_name(LV_METHOD_AUTO_EXPLICIT));
    ig->t_switch = t;
    ig->bdf->pace.t0 = ig->pace.t0; /* the age counts from the run's start */
    return LV_OK;
}

int lv_integ_outputs_free(const lv_integ *ig)
{
    return ig != NULL && ig->erk != NULL && ig->bdf == NULL;
}

static lv_status own_advance(lv_integ *ig, double tout, double *t, double *x,
                             lv_integ_result *res, int *roots, lv_err *err)
{
    lv_status st;
    if (ig->bdf == NULL) {
        int r = LV_INTEG_REACHED;
        st = lv_erk_advance(ig->erk, tout, ig->p.method == LV_METHOD_AUTO, t, x, &r, roots, err);
        ig->t = *t;
        if (st != LV_OK || r != LV_ERK_STIFF) {
            *res = (lv_integ_result)r;
            return st;
        }
        if ((st = switch_to_bdf(ig, *t, x, err)) != LV_OK)
            return st;
    }
    st = lv_integ_advance(ig->bdf, tout, t, x, res, roots, err);
    ig->t = *t;
    return st;
}

lv_status lv_integ_advance(lv_integ *ig, double tout, double *t, double *x, lv_integ_result *res,
                           int *roots, lv_err *err)
{
    if (is_own(ig->p.method))
        return own_advance(ig, tout, t, x, res, roots, err);
    if (!ig->sun_ready) {
        const lv_status st = sun_setup(ig, err);
        if (st != LV_OK)
            return st;
    }
    /* CVODE and ARKODE refuse a tout within two units of round-off of the time they start
     * from (CV_TOO_CLOSE), as an output time just after a restart at an event can be (the
     * grid's 3 * 0.1 after an event at 0.3; issue 22's breaker). The state there is the
     * current one to round-off: returned as reached, the integrator left where it is. */
    if (fabs(tout - ig->t) <= 4.0 * DBL_EPSILON * fmax(fabs(ig->t), fabs(tout))) {
        memcpy(x, N_VGetArrayPointer(ig->y), ig->p.n * sizeof(double));
        *t = tout;
        *res = LV_INTEG_REACHED;
        return LV_OK;
    }
    /* SUNDIALS limits steps per call; ours is a total for the run. The calls are cut into
     * the windows of the step-size collapse check (lv_integ_pace_collapsed). */
    sunrealtype tret = ig->t;
    int flag;
    for (;;) {
        const long done = current_steps(ig), remaining = ig->p.max_steps - done;
        if (remaining <= 0)
            return lv_fail(err, LV_ERR_SOLVER, "at t = %.9g s: too much work (%ld steps "
                           "allowed)", ig->t, ig->p.max_steps);
        const long window = LV_INTEG_PACE_WINDOW - (done - ig->pace.n_mark);
        const long chunk = remaining < window ? remaining : window > 0 ? window : 1;
        if (ig->is_cvode)
            CVodeSetMaxNumSteps(ig->mem, chunk);
        else
            ERKStepSetMaxNumSteps(ig->mem, chunk);
        ig->sun_msg[0] = '\0';
        flag = ig->is_cvode ? CVode(ig->mem, tout, ig->y, &tret, CV_NORMAL)
                            : ERKStepEvolve(ig->mem, tout, ig->y, &tret, ARK_NORMAL);
        ig->t = tret;
        if (flag != CV_TOO_MUCH_WORK || chunk == remaining) /* not a window's end */
            break;
        char why[LV_ERR_MSG_MAX - 32];
        if (lv_integ_pace_collapsed(&ig->pace, tret, current_steps(ig), why, sizeof why)) {
            memcpy(x, N_VGetArrayPointer(ig->y), ig->p.n * sizeof(double));
            *t = tret;
            return lv_fail(err, LV_ERR_SOLVER, "%s [%s]", why, lv_method_name(ig->p.method));
        }
    }
    memcpy(x, N_VGetArrayPointer(ig->y), ig->p.n * sizeof(double));
    *t = tret;
    if (flag < 0) {
        char fname[64];
        /* ARKODE's flags share CVODE's values for these failures (ARK_TOO_MUCH_WORK = -1 ...). */
        return lv_fail(err, LV_ERR_SOLVER, "at t = %.9g s: %s [%s] %s", tret, flag_meaning(flag),
                       flag_name(ig, flag, fname, sizeof fname),
                       ig->sun_msg);
    }
    /* CV_ROOT_RETURN == ARK_ROOT_RETURN == 2 */
    if (flag == CV_ROOT_RETURN) {
        *res = LV_INTEG_ROOT;
        if (ig->is_cvode)
            CVodeGetRootInfo(ig->mem, roots);
        else
            ERKStepGetRootInfo(ig->mem, roots);
    } else {
        *res = LV_INTEG_REACHED;
    }
    return LV_OK;
}

lv_status lv_integ_restart(lv_integ *ig, double t, const double *x, lv_err *err)
{
    ig->memo_ok = 0; /* a discontinuity: the model's mode or parameters may have changed */
    if (is_own(ig->p.method)) {
        /* auto stays with BDF once the problem was found stiff */
        lv_status st = ig->bdf != NULL ? lv_integ_restart(ig->bdf, t, x, err)
                                       : lv_erk_restart(ig->erk, t, x, err);
        if (st != LV_OK)
            return st;
        ig->acc.restarts++;
        ig->t = t;
        ig->tstop = NAN;
        return LV_OK;
    }
    if (!ig->sun_ready) { /* not stepped yet: start from here (sun_setup) */
        memcpy(ig->x_pending, x, ig->p.n * sizeof *ig->x_pending);
        ig->acc.restarts++;
        ig->t = t;
        ig->tstop = NAN;
        return LV_OK;
    }
    memcpy(N_VGetArrayPointer(ig->y), x, ig->p.n * sizeof(double));
    int flag;
    if (ig->is_cvode) {
        /* CVodeReInit zeroes the counters: bank them first. */
        lv_integ_stats cur;
        raw_stats(ig, &cur);
        ig->acc.steps += cur.steps;
        ig->acc.rhs_evals += cur.rhs_evals;
        ig->acc.jac_evals += cur.jac_evals;
        ig->acc.err_test_fails += cur.err_test_fails;
        ig->acc.nonlin_fails += cur.nonlin_fails;
        ig->acc.g_evals += cur.g_evals;
        ig->acc.rhs_step += cur.rhs_step;
        flag = CVodeReInit(ig->mem, t, ig->y);
    } else {
        flag = ERKStepReset(ig->mem, t, ig->y); /* keeps counters and options */
    }
    if (flag < 0)
        return lv_fail(err, LV_ERR_SOLVER, "at t = %.9g s: integrator restart failed: %s", t,
                       ig->sun_msg);
    ig->acc.restarts++;
    ig->t = t;
    ig->tstop = NAN;
    return LV_OK;
}
