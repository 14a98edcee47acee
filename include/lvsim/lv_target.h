/* lv_target.h - targeting and optimisation over a mission's phase tree (POST2's targeting and
 * optimisation, GMAT's Target/Vary/Achieve and Optimize blocks).
 *
 * A problem has
 *   VARIABLES    run parameters by name (lv_mission_param_find: "P1.guidance.kick_deg",
 *                "P2.guidance.a", "P2.end.peri_alt", "stage2.propellant_mass"), each with
 *                bounds [lo, hi], a start value and a scale (the size of a typical change);
 *                values in the unit of the name (degrees for a `_deg` name, SI otherwise);
 *   CONSTRAINTS  on final values of phases by name ("P2.peri_alt", "P2.inc_deg",
 *                "booster-land.target_distance"): equal, min or max a value, with a
 *                tolerance > 0 (same unit): met when |f - v| <= tol (equal), f >= v - tol
 *                (min), f <= v + tol (max);
 *   a COST       (optional): a final value to maximise or minimise.
 * It comes from the mission file's `targeting:` section (lv_target_create) or is built by a
 * program (lv_target_create_empty and the add functions). Format and algorithms:
 * docs/targeting.md.
 *
 * Solvers (lv_target_settings.method):
 *   newton   damped Newton / Levenberg-Marquardt on the residuals r_i = (f_i - v_i) / tol_i
 *            (inequalities: their violation), in variables scaled by their scale, with a
 *            trust-region update of the damping and the step projected into the bounds
 *            (Moré, "The Levenberg-Marquardt algorithm: implementation and theory", Lecture
 *            Notes in Mathematics 630, 1978; Nocedal & Wright, Numerical Optimization, 2nd ed.,
 *            sec. 10.3) and Broyden's rank-one update between finite-difference Jacobians
 *            (Nocedal & Wright sec. 11.1). Converged when every constraint is met.
 *   slsqp    NLopt's SLSQP (Kraft 1988): sequential quadratic programming with the cost, the
 *            constraints and their finite-difference gradients.
 *   cobyla   NLopt's COBYLA (Powell 1994): derivative-free, linear approximations.
 *   auto     newton without a cost; with one: newton first when the start violates the
 *            constraints, then SLSQP, then COBYLA from SLSQP's best point if SLSQP does not
 *            end at a point that meets the constraints.
 * Sensitivities are finite differences with steps from each variable's scale (forward;
 * central where the forward ones fail a step or near an optimum). Every evaluation sets the
 * variables on one lv_run and executes it, so only the phases a changed variable reaches are
 * simulated again, and only the phases the constraints and the cost read (and their
 * ancestors) are simulated at all. A trial point where a phase fails (the vehicle leaves its
 * model's domain, the integrator fails, a stop time is not after the start) is a rejected
 * step, never an error. Each phase a constraint or the cost reads is assumed to end by its
 * first end written (or the one named: lv_target_set_end, a constraint's `end:`); the result
 * lists those that ended otherwise at its point (end_mismatch): met on another trajectory.
 *
 * Not thread-safe on one lv_target; separate targets of one mission may run in parallel.
 */
#ifndef LVSIM_LV_TARGET_H
#define LVSIM_LV_TARGET_H

#include <stddef.h>

#include "lvsim/lv_mission.h"
#include "lvsim/lv_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct lv_target lv_target;

typedef enum lv_target_method {
    LV_TARGET_AUTO = 0,
    LV_TARGET_NEWTON,
    LV_TARGET_SLSQP,
    LV_TARGET_COBYLA
} lv_target_method;

typedef enum lv_target_diff {
    LV_DIFF_AUTO = 0,  /* forward; central after a rejected step and near an optimum */
    LV_DIFF_FORWARD,
    LV_DIFF_CENTRAL
} lv_target_diff;

typedef enum lv_con_kind { LV_CON_EQUAL = 0, LV_CON_MIN, LV_CON_MAX } lv_con_kind;

/* The problem of mission m's `targeting:` section (checked when the mission was loaded).
 * LV_ERR_INPUT when the mission has none. Borrows m: it must outlive the target. */
LV_API lv_status lv_target_create(const lv_mission *m, lv_target **out, lv_err *err);
/* An empty problem over mission m, for the add functions; the settings the file would give
 * (method, iterations, ...) are the defaults. */
LV_API lv_status lv_target_create_empty(const lv_mission *m, lv_target **out, lv_err *err);
LV_API void lv_target_free(lv_target *t); /* accepts NULL */

/* A variable: a run parameter by name, values in the name's unit. start NAN: the mission
 * file's value; scale NAN: (hi - lo) / 10, else within [1e-4, 1] x (hi - lo); step NAN: from
 * the scale, else > 0 and < (hi - lo) / 2 (see docs/targeting.md). lo < hi within the
 * parameter's allowed values, lo <= start <= hi. Out of range: LV_ERR_INPUT naming it. */
LV_API lv_status lv_target_add_var(lv_target *t, const char *name, double lo, double hi,
                                   double start, double scale, double step, lv_err *err);
/* A constraint on final value "PHASE.NAME" (time, a state or output of the phase's model;
 * "PHASE.NAME_deg" for an angle in degrees). tol > 0. */
LV_API lv_status lv_target_add_con(lv_target *t, const char *final, lv_con_kind kind,
                                   double value, double tol, lv_err *err);
/* The cost: final value "PHASE.NAME" maximised (maximize = 1) or minimised; scale > 0 the size
 * of a significant change (NAN: |value at the start|, or 1 when that is 0). */
LV_API lv_status lv_target_set_cost(lv_target *t, const char *final, int maximize, double scale,
                                    lv_err *err);

/* The end the problem assumes phase `phase` ends by: one of its `end:` entries by its name in
 * the results ("sma", "burnout", "altitude_2"), "stop_time" (its time limit) or "any" (not
 * checked). By default every phase a constraint or the cost reads is assumed to end by its
 * first end written (stop_time when it has none); a phase named here that nothing reads is
 * simulated in every evaluation (with its ancestors) to be checked. At every evaluated point
 * the end that fired is compared with it: the result lists the phases that ended otherwise
 * (lv_target_result.end_mismatch), the iterations' notes name them. LV_ERR_INPUT for an
 * unknown phase or end (the message lists the phase's ends). */
LV_API lv_status lv_target_set_end(lv_target *t, const char *phase, const char *end,
                                   lv_err *err);

typedef struct lv_target_var_info {
    const char *name;  /* as given: "P1.guidance.kick_deg" */
    const char *unit;  /* "deg" for a _deg name, else the parameter's SI unit */
    size_t param;      /* the parameter's index (lv_mission_param_info) */
    int deg;           /* 1: values in degrees */
    double lo, hi, start, scale, step; /* step: the forward-difference step */
} lv_target_var_info;

typedef struct lv_target_con_info {
    const char *name;  /* "P2.peri_alt" as given */
    const char *unit;  /* "deg" for a _deg name, else the final's unit */
    size_t phase;      /* the phase (run order) */
    lv_con_kind kind;
    double value, tol;
} lv_target_con_info;

typedef struct lv_target_cost_info {
    int present;
    const char *name, *unit;
    size_t phase;
    int maximize;
    double scale;      /* NAN: from the start point */
} lv_target_cost_info;

LV_API size_t lv_target_var_count(const lv_target *t);
LV_API size_t lv_target_con_count(const lv_target *t);
LV_API void lv_target_var_info_get(const lv_target *t, size_t i, lv_target_var_info *out);
LV_API void lv_target_con_info_get(const lv_target *t, size_t i, lv_target_con_info *out);
LV_API void lv_target_cost_info_get(const lv_target *t, lv_target_cost_info *out);

/* ---- solving ---------------------------------------------------------------------------- */

/* One iteration: a Newton step tried, or an optimiser's point with its gradients. The arrays
 * are valid during the callback only. */
typedef struct lv_target_iter {
    size_t iteration;     /* 0: the start point */
    const char *solver;   /* "newton", "slsqp", "cobyla" */
    const char *event;    /* "start", "accepted", "rejected", "jacobian", "point" */
    const char *note;     /* why a step was rejected ("phase 'P2' failed: ..."), or NULL */
    const double *x;      /* [n_vars] in the variables' units */
    const double *finals; /* [n_cons] the constraints' finals (NAN where the point failed) */
    const double *residual; /* [n_cons] in tolerances: (f - v) / tol for equal, the violation
                               for min and max (0 when met); NAN where the point failed */
    double cost;          /* the cost's final, NAN without a cost */
    double worst;         /* max |residual| */
    double damping;       /* Levenberg-Marquardt lambda (NAN for the optimisers) */
    double step;          /* length of the step in scaled variables, NAN for the start */
    size_t runs, phases;  /* executions and phase simulations since the previous iteration */
    size_t runs_total, phases_total;
    double wall;          /* s since the solve started */
} lv_target_iter;

/* One execution of the run (a trial point or a sensitivity), for a progress display. */
typedef struct lv_target_eval {
    size_t iteration;     /* the iteration it belongs to */
    const char *purpose;  /* "start", "trial", "sensitivity", "point" */
    const char *var;      /* the variable perturbed (sensitivity), else NULL */
    size_t runs_total, phases_total;
    double wall;          /* s since the solve started */
} lv_target_eval;

typedef struct lv_target_settings {
    lv_target_method method;  /* default: the file's, else auto */
    lv_target_diff differences; /* default: the file's, else auto */
    int max_iterations;   /* newton: steps tried; optimisers: points evaluated (each with
                             its gradients when SLSQP asks for them). 0: the file's, else 50
                             (newton) / 50 + 25 per variable (each optimiser) */
    double xtol;          /* optimisers: stop when a step changes every variable by less than
                             xtol of its scale (0: the file's, else 1e-5) */
    double ftol;          /* optimisers: stop when the cost changes by less than ftol of its
                             scale (0: the file's, else 1e-7) */
    int restarts;         /* SLSQP again from its best point, with a fresh quasi-Newton
                             Hessian, up to this many times while a run gains more than 1000
                             ftol of the cost's scale (0: the file's, else none) */
    int threads;          /* worker threads (0: 2): the sensitivities' columns are shared among
                             them, each on a run of its own; a single evaluation runs
                             independent branches in them (lv_run_execute) */
    void (*on_iteration)(const lv_target *t, const lv_target_iter *it, void *user);
    /* Called before every execution, one call at a time but possibly from a worker thread
     * (sensitivities); nonzero stops the solve (LV_ERR_CANCELLED). */
    int (*on_evaluation)(const lv_target *t, const lv_target_eval *ev, void *user);
    void *user;
    /* NULL, or a flag another thread (a signal handler) may set nonzero to stop the solve:
     * every evaluation under way is cancelled within one integrator step
     * (lv_run_options.stop) and none starts after; the result is the best point so far, as
     * when on_evaluation stops it. */
    const volatile int *stop;
    /* > 0: lv_run_options.max_rows of every evaluation (the phases' rows, although none are
     * kept: they cost time): a trial point whose phase is refused or stopped by it fails. */
    double max_rows;
} lv_target_settings;

/* All zero: the file's settings (or the defaults) and no callbacks. */
LV_API void lv_target_settings_default(lv_target_settings *s);

/* A phase that ended otherwise than the problem assumes (lv_target_set_end). */
typedef struct lv_target_end_mismatch {
    size_t phase;          /* run order */
    const char *phase_name;
    const char *expected;  /* the end assumed: "sma", "stop_time" */
    const char *actual;    /* the end that fired: "burnout", "stop_time" */
    double t_end;          /* s, mission time the phase ended */
} lv_target_end_mismatch;

typedef struct lv_target_result {
    int converged;        /* 1: every constraint met (and the optimiser stopped on its
                             tolerances: a local optimum); 0: the best point found */
    int cancelled;        /* 1: on_evaluation stopped the solve: the best point so far */
    char reason[LV_ERR_MSG_MAX]; /* how it ended, one sentence */
    const char *method;   /* the solver(s) used: "newton", "newton+slsqp", ... */
    size_t n_vars, n_cons;
    const double *x;      /* [n_vars] the converged or best point */
    const double *finals; /* [n_cons] its constraint finals */
    const double *residual; /* [n_cons] in tolerances (as lv_target_iter) */
    const int *met;       /* [n_cons] 1: within its tolerance */
    double cost;          /* the cost's final at x, NAN without a cost */
    double worst;         /* max |residual| */
    size_t iterations, runs, phases;
    double wall;          /* s */
    /* the phases that ended at x otherwise than the problem assumes (lv_target_set_end): a
     * converged point on another trajectory than the one targeted (an upper stage cut off by
     * burnout instead of its orbit's end). Converged or not; 0 when every checked phase ended
     * as assumed. */
    size_t n_end_mismatch;
    const lv_target_end_mismatch *end_mismatch; /* [n_end_mismatch] */
} lv_target_result;

/* Solves: returns LV_OK with *out filled whether or not the target was met (out->converged
 * says; out->x is the best point then); LV_ERR_SOLVER when the start point itself fails
 * (err names the phase and why); LV_ERR_CANCELLED when on_evaluation asked to stop before
 * the start point was evaluated (later, the result is the best point so far, `cancelled` 1). *out is
 * owned by t and valid until the next solve or lv_target_free. */
LV_API lv_status lv_target_solve(lv_target *t, const lv_target_settings *s,
                                 const lv_target_result **out, lv_err *err);

/* The run holding the last point evaluated (the result's point after a solve; after a
 * cancelled one the last point tried, whose phases may have been cut short): its phases'
 * results and finals (lv_run_result, lv_run_final). Owned by t. */
LV_API lv_run *lv_target_run(lv_target *t);

/* Writes the mission file with each variable's value replaced by x[i] (the result's point)
 * at the place the file writes it, in the unit it is written in, and the `start:` of the
 * targeting section's variables too; comments, layout and every other character unchanged
 * (written under a temporary name, then renamed; `path` must not be the mission file or one of
 * its data files: lv_output_check). Then loads the written file, runs it and checks
 * that it reproduces the constraints' finals and the cost at x (every difference below 1e-3
 * of the tolerance and 1e-6 of the cost's scale): *worst (may be NULL) receives the largest
 * difference in tolerances. LV_ERR_INPUT when a variable's value is not written in the file
 * (a default) or `path` is an input, LV_ERR_IO, LV_ERR_SOLVER when the written file does not reproduce them. */
LV_API lv_status lv_target_write(lv_target *t, const double *x, const char *path,
                                 double *worst, lv_err *err);

#ifdef __cplusplus
}
#endif
#endif
