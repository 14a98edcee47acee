/* lv_ocp.h - optimal control over a mission's phase tree: direct multiple shooting with IPOPT.
 *
 * A mission's `optimal_control:` section (docs/optimal-control.md) names the phases whose
 * control histories (dof3: alpha, beta, mu [rad], throttle [1]; piecewise linear in time
 * between equally spaced nodes) and durations are optimised, the constraints on finals and
 * the path constraints, and the cost, in the words of `targeting:`. The transcription:
 *
 *   variables  each optimised phase's state at the start of each of its shooting segments
 *              (the model's states: dof3's ECI position, velocity, mass, heat loads), its
 *              control node values and, when free, its duration;
 *   defects    simulate segment j with the phase's own model and integrator from its start
 *              state, minus the next segment's start state (states divided by their scales);
 *   links      an optimised phase's first state minus its start from the runner's hand-off
 *              (the parent's final state through lv_run_prepare: mass overrides, jettisons,
 *              separation impulses, the type conversions), or the mission's start values;
 *   phases     that are not optimised are flown whole from their parent's end, as `lvsim run`
 *              flies them (their ends, their laws); their finals enter the constraints;
 *   paths      a path constraint holds at every segment start and the end of its phase;
 *   finals     (f - value) / tolerance, equal, min or max;
 *   cost       the final to minimise or maximise, divided by its value at the start point.
 *
 * The constraint Jacobian is sparse: its pattern follows from the phase tree, and its columns
 * are taken in groups that touch disjoint rows (Curtis, Powell & Reid, IMA J. Appl. Math. 13,
 * 1974), each group one forward-difference evaluation of every segment, shared among threads.
 * IPOPT (Wächter & Biegler, Math. Program. 106, 2006) with its limited-memory quasi-Newton
 * Hessian solves the NLP.
 */
#ifndef LVSIM_LV_OCP_H
#define LVSIM_LV_OCP_H

#include <stddef.h>

#include "lvsim/lv_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct lv_ocp lv_ocp;

/* One IPOPT iteration, as reported to the callback. */
typedef struct lv_ocp_iteration {
    int iteration;
    double cost;       /* the cost's final in its unit (NAN: no cost) */
    double inf_pr;     /* the largest violation of the scaled constraints */
    double inf_du;     /* the scaled dual infeasibility */
    double mu;         /* the barrier parameter (log10 shown by IPOPT) */
    double step;       /* the primal step length alpha_pr */
    double wall;       /* s since the solve started */
    long segments;     /* segment simulations so far */
    int restoration;   /* 1: in IPOPT's feasibility restoration phase */
} lv_ocp_iteration;

typedef struct lv_ocp_settings {
    int threads;         /* workers for the finite differences (0: 2; at most 16) */
    int max_iterations;  /* 0: the section's (default 500) */
    int print_level;     /* IPOPT's own output to stdout (0: none, 5: IPOPT's default) */
    /* called after every iteration; return nonzero to stop (the result is then the best
     * point so far, LV_ERR_CANCELLED) */
    int (*on_iteration)(const lv_ocp_iteration *it, void *user);
    void *user;
    const volatile int *stop; /* set nonzero by another thread to stop; NULL: none */
} lv_ocp_settings;

typedef enum lv_ocp_outcome {
    LV_OCP_OPTIMAL = 0,    /* IPOPT converged: every constraint met */
    LV_OCP_INFEASIBLE,     /* IPOPT found the constraints locally infeasible */
    LV_OCP_NOT_CONVERGED,  /* iteration limit, or IPOPT stopped otherwise */
    LV_OCP_STOPPED         /* stopped by the callback or the stop flag */
} lv_ocp_outcome;

typedef struct lv_ocp_result {
    lv_ocp_outcome outcome;
    int ipopt_status;      /* IPOPT's ApplicationReturnStatus */
    char ipopt_text[80];   /* its name ("Solve_Succeeded", "Infeasible_Problem_Detected") */
    int iterations;
    double cost;           /* the cost's final in its unit at the point returned (NAN: none) */
    double cost_start;     /*   at the start point */
    double max_violation;  /* the largest constraint violation at the point returned, in units
                              of each row's scale (defects: the state's scale; finals: their
                              tolerance) */
    size_t n_violated;     /* rows violated at the point returned (lv_ocp_violation) */
    size_t n_vars, n_cons, nnz_jac, n_groups; /* the NLP's size; Jacobian column groups */
    long segments;         /* segment simulations in all */
    long evaluations;      /* whole evaluations of the transcription (base and perturbed) */
    double wall, cpu;      /* s; cpu: the process's */
    double wall_jac;       /* s of wall time spent in the Jacobians */
    double wall_eval;      /* s of wall time spent in the base evaluations */
    char last_failure[512]; /* why the last evaluation that failed did ("" none): a phase that
                               did not fly at a trial point IPOPT then stepped back from */
} lv_ocp_result;

/* Loads the mission at `path` (its `optimal_control:` section: LV_ERR_INPUT without one) and
 * builds the transcription's start point: each optimised phase flown once with its start
 * controls and duration, the node states from that flight (zero defects). */
LV_API lv_status lv_ocp_create(const char *path, lv_ocp **out, lv_err *err);
LV_API void lv_ocp_free(lv_ocp *o); /* accepts NULL */

/* Solves the NLP from the start point (or from where the last solve ended). LV_OK with the
 * outcome in res (an infeasible or unconverged problem is an outcome, not an error); errors:
 * LV_ERR_NOMEM, LV_ERR_CANCELLED (res filled with the best point), LV_ERR_SOLVER (IPOPT could
 * not be loaded or refused the problem). */
LV_API lv_status lv_ocp_solve(lv_ocp *o, const lv_ocp_settings *s, lv_ocp_result *res,
                              lv_err *err);

/* The i-th violated row at the point returned (i < res.n_violated), largest first: its name
 * ("final 'orbit.sma' = 24361.2 km, equal 24361.14 km, tolerance 0.01 km", "defect of phase
 * 'ascent' at segment 3 of 10, state 'm'", "path 'ascent.q_dyn' at node 4 (t = 34.2 s)") and
 * its violation in units of its scale. */
LV_API lv_status lv_ocp_violation(const lv_ocp *o, size_t i, char *text, size_t cap,
                                  double *violation, lv_err *err);

/* The point returned, phase by phase: an optimised phase's start and end times [s] (k: the
 * mission's phase index; LV_ERR_INPUT for a phase not optimised). */
LV_API lv_status lv_ocp_phase_times(const lv_ocp *o, size_t k, double *t0, double *t1,
                                    lv_err *err);

/* Writes the optimal mission at `path` (a new file; an existing file lvsim did not write is
 * refused): the mission with each optimised phase flying its control nodes as an inputs table
 * over mission time (PATH-stem_<phase>_controls.csv beside it), its stop_time the optimal end
 * and no other ends, and the NLP's trajectory as its `reference:` (PATH-stem_<phase>_reference.csv:
 * time, h, lat, lon, v, fpa, heading, m: 50 rows per segment and its events), so that
 * `lvsim run` re-flies it and reports its drift from the optimum. `flags`: lv_output_check's
 * (LV_OUTPUT_REPLACE: existing files may be replaced; never an input of the mission). */
LV_API lv_status lv_ocp_write(lv_ocp *o, const char *path, unsigned flags, lv_err *err);
/* The checks of lv_ocp_write's names alone (the mission and its tables beside it: a .yaml
 * name, never an input, an existing file only as flags allow), for a caller that wants the
 * refusal before a long solve. lv_ocp_write refuses too without an optimal last solve
 * (LV_ERR_INPUT "no optimum to write"). */
LV_API lv_status lv_ocp_check_write(const lv_ocp *o, const char *path, unsigned flags,
                                    lv_err *err);

#ifdef __cplusplus
}
#endif

#endif
