/* integrator.h - one interface over SUNDIALS CVODE (BDF, Adams), ARKODE ERKStep
 * (Dormand-Prince, RK4, Euler) and lvsim's own explicit Runge-Kutta methods (erk.c:
 * Dormand-Prince 5(4) "dp5", DOP853 "dop853"), with root finding and stop times, and "auto":
 * an explicit method until Hairer's stiffness test fires, then CVODE's BDF.
 *
 * This is the only module that includes SUNDIALS headers. It knows nothing
 * about models, names or files: a plain ODE x' = f(t, x) with event functions.
 */
#ifndef LV_INTEGRATE_INTEGRATOR_H
#define LV_INTEGRATE_INTEGRATOR_H

#include <stddef.h>

#include "lvsim/lv_status.h"

typedef enum lv_method {
    LV_METHOD_BDF = 0,   /* "dassl": CVODE BDF, Newton + dense LU, DQ Jacobian */
    LV_METHOD_ADAMS,     /* "cvode-adams": CVODE Adams-Moulton, fixed-point iteration */
    LV_METHOD_DOPRI5,    /* "dopri5": ARKODE ERK Dormand-Prince 5(4), adaptive */
    LV_METHOD_RK4,       /* "rk4": ARKODE ERK classical RK4, fixed step */
    LV_METHOD_EULER,     /* "euler": ARKODE ERK explicit Euler, fixed step */
    LV_METHOD_DP5,       /* "dp5": lvsim's Dormand-Prince 5(4), 4th-order dense output */
    LV_METHOD_DOP853,    /* "dop853" ("dopri853"): lvsim's DOP853, 7th-order dense output */
    LV_METHOD_AUTO,      /* "auto": the explicit method (LV_METHOD_AUTO_EXPLICIT) while the
                            problem is not stiff, CVODE BDF from where Hairer's test finds it
                            stiff (or from the start when the problem says so: stiff) */
    LV_METHOD_COUNT
} lv_method;

/* Parses a method name (case-insensitive; "dassl", "bdf", "cvode-bdf" are one
 * method). Unknown names fail with the list of known ones. */
lv_status lv_method_parse(const char *name, lv_method *out, lv_err *err);
const char *lv_method_name(lv_method m);
int lv_method_is_fixed_step(lv_method m);

/* Right-hand side and event functions, SUNDIALS return convention:
 * 0 ok, > 0 recoverable (retry smaller step), < 0 unrecoverable. */
typedef int (*lv_integ_rhs_fn)(double t, const double *x, double *xdot, void *user);
typedef int (*lv_integ_g_fn)(double t, const double *x, double *g, void *user);

typedef struct lv_integ_problem {
    size_t n;              /* states */
    size_t n_g;            /* event functions (may be 0) */
    const int *g_dir;      /* [n_g] +1 rising, -1 falling, 0 both; NULL: both */
    lv_integ_rhs_fn rhs;
    lv_integ_g_fn g;       /* required when n_g > 0 */
    void *user;            /* passed to rhs and g */
    lv_method method;
    double rtol;           /* > 0 */
    const double *atol;    /* [n] > 0 */
    const double *rtol_v;  /* [n] >= 0: each state's relative tolerance (0: absolute error
                              control only); NULL: rtol for every state */
    double fixed_step;     /* rk4/euler: > 0 */
    double max_step;       /* 0: unlimited */
    long max_steps;        /* total internal steps allowed, > 0 */
    int stiff;             /* auto: the model declares itself stiff: BDF from the start */
    double init_step;      /* dp5, dop853: the first step after a start or restart; 0: the
                              heuristic of HNW I, II.4 */
    const unsigned char *quad; /* [n] 1 where a state is a quadrature: integrated with the
                              others, by the same steps, but left out of the error control (as
                              CVODES' quadratures with errconQ off), so it never shrinks a step;
                              no right-hand side may read it (event functions may). At least one state must not be.
                              NULL: none. dp5, dop853: out of the error norm, the first step's
                              estimate and the stiffness test, exactly; SUNDIALS methods: error
                              weight 1e-8 of its tolerance's, the others' scaled by
                              sqrt(n / n_controlled) so that the norm is theirs (its own part
                              is below 1e-8 of the norm's). */
} lv_integ_problem;

typedef struct lv_integ lv_integ;

/* The step-size collapse check every integrator makes: at the end of each window of
 * LV_INTEG_PACE_WINDOW accepted steps, the mean step of the window must be at least the time
 * flown since the run's start over LV_INTEG_PACE_FACTOR times the step limit - at a slower
 * pace, flying as long again as flown so far would take more than ten times the steps
 * allowed. A solution that slow has met something it cannot follow - a force or frame that
 * flips from one side to the other (a reference the model loses), a discontinuity the model
 * does not announce as an event - and would otherwise spend the whole step limit (1e6 steps,
 * seconds of CPU) chattering in place; it fails after a thousand steps with the time and the
 * pace. Sound dynamics stay far from it whatever their time scale: they cannot be followed
 * within the step limit at that pace either. */
#define LV_INTEG_PACE_WINDOW 10000
#define LV_INTEG_PACE_FACTOR 10.0

typedef struct lv_integ_pace {
    double t0;      /* the run's start */
    double t_mark;  /* the time at the window's start */
    long n_mark;    /* the accepted steps there */
    long max_steps; /* the step limit */
} lv_integ_pace;

/* At `steps` accepted steps and time t: 1 (with the message in msg[cap]) when the window
 * that ends here was slower than the pace floor; 0 otherwise (a window that ends here starts
 * the next). */
int lv_integ_pace_collapsed(lv_integ_pace *pc, double t, long steps, char *msg, size_t cap);

typedef enum lv_integ_result {
    LV_INTEG_REACHED = 0, /* reached tout (or the stop time, when tout == stop time) */
    LV_INTEG_ROOT = 1     /* an event function crossed zero at *t (before tout) */
} lv_integ_result;

typedef struct lv_integ_stats {
    long steps, rhs_evals, jac_evals, err_test_fails, nonlin_fails, g_evals, restarts;
    long rhs_step;  /* of rhs_evals: for the steps (stages, Jacobians, step-size selection) */
    long rhs_dense; /* of rhs_evals: for output between steps (dopri5's dense output) */
    long rhs_reused; /* repeated calls answered from the last evaluation (not in rhs_evals) */
} lv_integ_stats;

/* Copies the problem; `atol` and `g_dir` are copied too. */
lv_status lv_integ_create(const lv_integ_problem *p, double t0, const double *x0, lv_integ **out,
                          lv_err *err);
void lv_integ_free(lv_integ *ig);

/* The integrator never steps past `tstop` (> current time). */
lv_status lv_integ_set_stop_time(lv_integ *ig, double tstop, lv_err *err);

/* Advance towards `tout`; on return *t is tout, or the root time, and x the
 * state there (length n). On LV_INTEG_ROOT, roots[i] (length n_g) is +1/-1 for
 * the functions that crossed (rising/falling), 0 otherwise. On failure the
 * message holds the time and SUNDIALS' reason; *t is the time reached. */
lv_status lv_integ_advance(lv_integ *ig, double tout, double *t, double *x, lv_integ_result *res,
                           int *roots, lv_err *err);

/* Forget the remembered last right-hand side evaluation (the model's discrete mode may have
 * changed: an event handler ran). lv_integ_restart does it too. */
void lv_integ_forget(lv_integ *ig);

/* Restart at (t, x) after a discontinuity: history discarded, order 1. */
lv_status lv_integ_restart(lv_integ *ig, double t, const double *x, lv_err *err);

/* 1 when the integrator's steps and the roots it locates do not depend on the output times it
 * is advanced to, so that a caller that writes no rows may leave them out and get the same
 * results bit for bit: lvsim's own explicit methods (dp5, dop853, auto until it turns to BDF),
 * whose roots are searched on each step's end and located on the step's dense output, the
 * output interpolated. 0 for the SUNDIALS methods: CVODE and ARKODE split a root search at an
 * intermediate output time (a located root moves by round-off). */
int lv_integ_outputs_free(const lv_integ *ig);

/* Cumulative over restarts. */
void lv_integ_get_stats(const lv_integ *ig, lv_integ_stats *st);

/* What ran and why, for reports: `used` gets the method's name ("dop853", "dassl", or for auto
 * "dop853, then dassl"), `why` (may be NULL) the reason ("chosen"; auto: "not stiff",
 * "stiff at t = 12.5 s (Hairer's test)", "declared stiff by the model"). */
void lv_integ_method_used(const lv_integ *ig, char *used, size_t used_cap, char *why,
                          size_t why_cap);

#endif
