/* lv_sim.h - lv_simulate(): the simulateExtendedModel of the paper's Code 1.
 *
 * Integrates a model from start_time to stop_time with SUNDIALS, sets start
 * values by name, handles state and time events, streams result rows to
 * sinks (.mat in Dymola's dsres layout, .csv) and returns final values by name
 * and run statistics.
 *
 * Methods (`method`, case-insensitive):
 *   "dassl"       variable-order (1-5) BDF, CVODE, Newton with dense LU and
 *                 difference-quotient Jacobian (the Dymola default's family)
 *   "cvode-adams" variable-order (1-12) Adams-Moulton, CVODE, fixed-point iteration
 *   "dopri5"      Dormand-Prince 5(4), ARKODE ERKStep, adaptive
 *   "rk4"         classical Runge-Kutta 4, ARKODE ERKStep, fixed step
 *   "euler"       explicit Euler, ARKODE ERKStep, fixed step
 *   "dp5"         Dormand-Prince 5(4), lvsim's own (src/integrate/erk.c), 4th-order dense
 *                 output, Hairer's stiffness test
 *   "dop853"      DOP853 8(5,3), lvsim's own, 7th-order dense output (alias "dopri853")
 *   "auto"        dop853 while the problem is not stiff; CVODE BDF ("dassl") from where
 *                 Hairer's stiffness test finds it stiff, or from the start for a model that
 *                 declares itself stiff (lv_model_def.stiff); report.method_used/_why say which
 * Tolerances: rtol = tolerance; atol_i = tolerance * nominal_i per state. The tolerance lies in
 * [LV_TOLERANCE_MIN, LV_TOLERANCE_MAX] (docs/integration.md, "Tolerance range").
 *
 * Events at one instant are handled in this order (docs/result-files.md):
 *   1. all state events located at that instant, in one on_event() call
 *      (fired[i] != 0 in ascending index i);
 *   2. then the time events scheduled at that instant (on_time_event());
 *   3. a stop requested by any handler ends the run after both; otherwise the
 *      integrator restarts once if any handler asked for it.
 * The result gets one row before and one after the instant.
 */
#ifndef LVSIM_LV_SIM_H
#define LVSIM_LV_SIM_H

#include <stddef.h>

#include "lvsim/lv_io.h"
#include "lvsim/lv_model.h"
#include "lvsim/lv_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The relative tolerances lv_simulate accepts (others: LV_ERR_INPUT naming the range), and with
 * it every mission phase, run option, campaign and command-line option that sets one. Below
 * 1e-14 (45 units of double round-off, SUNDIALS' unit roundoff 2.2e-16) no method gets more
 * accurate (dopri5's Kepler energy error stays at 1.0e-12 from 1e-14 down) and CVODE and ARKODE
 * stop with "too much accuracy requested" from about 1e-16; above 0.1 the error estimate no
 * longer bounds anything (the sounding-rocket example: its apogee 5 times too high at 1). */
#define LV_TOLERANCE_MIN 1e-14
#define LV_TOLERANCE_MAX 0.1

/* Result files of a run (lv_sim_settings.result_formats, lv_run_options.result_formats): the
 * flag of format i of lv_result_format_info() (lv_io.h) is 1u << i. */
enum { LV_RESULT_MAT = 1u, LV_RESULT_CSV = 2u };

/* A condition that ends the run - a phase's end on any of the model's variables: the variable
 * crosses `value` in `direction` (located as a state event), or, for "time", the run reaches
 * time `value` [s] (a time event, hit exactly). The run then stops as by an event of the model,
 * with this name in the report and the event log (index: the model's n_events + the stop's
 * position in `stops`). */
typedef struct lv_sim_stop {
    const char *name;     /* "mach", "apoapsis": reported; copied */
    const char *variable; /* a state, derivative or output of the model ("mach", "der(h)"), or
                             "time"; resolved when the simulation is created */
    double value;         /* in the variable's unit */
    lv_dir direction;     /* crossings that count (ignored for "time") */
} lv_sim_stop;

typedef struct lv_sim_settings {
    double start_time;       /* s (default 0) */
    double stop_time;        /* s (default 1); >= start_time */
    int number_of_intervals; /* output intervals (default 0: 500 unless output_interval) */
    double output_interval;  /* s (default 0); takes precedence when > 0 */
    const char *method;      /* see above (default "dassl") */
    double tolerance;        /* relative tolerance (default 1e-4), in [LV_TOLERANCE_MIN,
                                LV_TOLERANCE_MAX] */
    double fixed_step;       /* s, rk4/euler (default 0: the output interval) */
    const char *result_file; /* path without extension ("dsres"); NULL: no file */
    unsigned result_formats; /* LV_RESULT_MAT | LV_RESULT_CSV (default both) */

    size_t n_initial;                  /* set before the run, by name: */
    const char *const *initial_names;  /*   states or parameters */
    const double *initial_values;      /*   [n_initial], finite */
    size_t n_final;                    /* read after the run, by name: */
    const char *const *final_names;    /*   any variable */

    long max_steps;       /* internal steps allowed in total (default 0: 1e6) */
    double max_step_size; /* s (default 0: no limit) */
    size_t n_sinks;       /* extra sinks (memory, ...), borrowed */
    lv_sink *sinks;

    /* Optional: called after every output row of the grid with the time reached [s];
     * return nonzero to cancel the run (it then fails with LV_ERR_CANCELLED). Called from
     * the thread that runs the simulation. */
    int (*progress)(double t, void *user);
    void *progress_user;

    size_t n_stops;            /* ends of the run besides the model's own events */
    const lv_sim_stop *stops;  /* [n_stops], borrowed until the simulation ends */

    /* Optional: a flag another thread (a signal handler) may set nonzero to stop the run. It
     * is read at every right-hand side evaluation and output row, so a run stops within one
     * integrator step (LV_ERR_CANCELLED, "cancelled at t = ..."; the sinks keep the rows
     * written and are closed as failed). Borrowed; NULL: none. */
    const volatile int *stop;
    /* > 0: the most output-grid rows the run may write (the start row and every grid point,
     * not the two rows of each event instant). The run that would write one more, because
     * neither stop_time nor an end of it came first, fails at once (LV_ERR_SOLVER) with a
     * message naming the time reached, the rows and the limit; the sinks keep the rows and
     * are closed as failed. 0 (default): no limit. */
    double max_rows;
} lv_sim_settings;

/* Dymola's defaults: start 0, stop 1, 500 intervals, dassl, 1e-4, "dsres". */
LV_API void lv_sim_settings_default(lv_sim_settings *s);

typedef struct lv_sim_stats {
    long steps;          /* accepted internal steps */
    long rhs_evals;      /* right-hand side evaluations (incl. for Jacobians) */
    long jac_evals;      /* Jacobian evaluations (dassl) */
    long err_test_fails; /* rejected steps (local error test) */
    long nonlin_fails;   /* nonlinear solver convergence failures */
    long g_evals;        /* event function evaluations */
    long state_events;   /* state events handled */
    long time_events;    /* time events handled */
    long restarts;       /* integrator re-initialisations */
    long output_rows;    /* rows written to sinks */
    double cpu_time;     /* s, thread CPU time of the run */
    /* rhs_evals = rhs_evals_steps + rhs_evals_output (docs/integration.md, "Output cost"): */
    long rhs_evals_steps;  /* spent on the steps: stages, Jacobians, step-size selection */
    long rhs_evals_output; /* spent on output between steps: dopri5's dense output (at most
                              one per step that holds output times); CVODE's is free */
    long row_evals;        /* model evaluations (derivatives and outputs) for the result rows
                              and the final values; none when no sink takes the rows */
} lv_sim_stats;

typedef enum lv_stop_reason {
    LV_STOP_TIME = 0,  /* reached stop_time */
    LV_STOP_EVENT = 1, /* an event handler ended the run */
    LV_STOP_FAILED = 2 /* error; see err */
} lv_stop_reason;

typedef struct lv_event_record {
    double t;      /* s */
    int is_state;  /* 1 state event, 0 time event */
    int index;     /* event function index (state events), -1 for time events */
    int direction; /* +1 rising, -1 falling, 0 time event */
    char name[LV_EVENT_NAME_MAX]; /* a state event's name ("burnout"); a time event's source
                                     (lv_model_def.time_event_name), else "time event" */
} lv_event_record;

typedef struct lv_sim_report {
    lv_sim_stats stats;
    lv_stop_reason reason;
    double end_time;          /* s: stop_time, the stopping event, or the failure time */
    int stop_event;           /* index of the state event that stopped the run, or -1 */
    char stop_name[LV_EVENT_NAME_MAX]; /* "stop_time", the event's name or "failed" */
    size_t n_states;          /* number of continuous states */
    size_t n_event_log;       /* events handled, in order */
    lv_event_record *event_log; /* owned; free with lv_sim_report_clear() */
    char method_used[LV_EVENT_NAME_MAX]; /* the method(s) that ran: "dassl", "dop853", for
                                            "auto" e.g. "dop853, then dassl" */
    char method_why[LV_EVENT_NAME_MAX];  /* why: "chosen" (named in the settings), or for
                                            "auto": "not stiff", "stiff at t = 12.5 s (Hairer's
                                            test)", "declared stiff by the model" */
} lv_sim_report;

LV_API void lv_sim_report_clear(lv_sim_report *rep);

/* Run one simulation. `final_values` receives n_final values (may be NULL when
 * n_final is 0). `rep` may be NULL. `inst` is the model's instance data.
 * Returns LV_OK (the ok flag) or an error naming the model, the time and the
 * reason; result files then keep the rows computed before the failure.
 * The same as lv_sim_create, lv_sim_advance(stop_time), lv_sim_finish, lv_sim_free. */
LV_API lv_status lv_simulate(const lv_model_def *model, void *inst, const lv_sim_settings *s,
                             double *final_values, lv_sim_report *rep, lv_err *err);

/* ---- a simulation in steps ------------------------------------------------------------
 *
 * The run of lv_simulate, advanced by the caller (a co-simulation master, a loop that
 * watches or changes variables):
 *
 *     lv_sim *sim;
 *     lv_sim_create(model, inst, &settings, &sim, &err);  start values, first row
 *     while (!lv_sim_done(sim) && lv_sim_time(sim) < t_end)
 *         lv_sim_advance(sim, lv_sim_time(sim) + h, &err);  rows and events on the way
 *     lv_sim_finish(sim, finals, &report, &err);  final values, sinks closed
 *     lv_sim_free(sim);
 *
 * Advancing to the output grid points reproduces lv_simulate bit for bit; any other target
 * only adds an interpolated stop of the integrator there (same steps, same rows; a state
 * event inside the step that contains the target may be located differently by round-off).
 * An event that ends the run, or stop_time, ends it: lv_sim_done() is then 1 and the time
 * is the end time. A borrowed `inst`, the settings' arrays and sinks must live until
 * lv_sim_finish (or lv_sim_free). One simulation is used by one thread at a time. */
typedef struct lv_sim lv_sim;

/* Sets the start values and writes the first row. On failure *out is NULL and the sinks
 * that were opened are closed as failed. */
LV_API lv_status lv_sim_create(const lv_model_def *model, void *inst, const lv_sim_settings *s,
                               lv_sim **out, lv_err *err);
/* Integrates to time t [s] (no further than stop_time or an ending event). t at or before
 * the current time does nothing. A failure ends the simulation: later calls return it. */
LV_API lv_status lv_sim_advance(lv_sim *sim, double t, lv_err *err);
LV_API double lv_sim_time(const lv_sim *sim); /* s */
LV_API int lv_sim_done(const lv_sim *sim);    /* 1: ended (stop time, event or failure) */
/* Statistics and events so far (steps are counted by lv_sim_finish). */
LV_API const lv_sim_report *lv_sim_report_get(const lv_sim *sim);

/* A variable's value reference: names resolved once (as FMI's value references are), the
 * same for every simulation of the model. Order: states, derivatives, parameters, outputs. */
typedef unsigned lv_vref;
LV_API lv_status lv_model_vref(const lv_model_def *model, const char *name, lv_vref *ref,
                               lv_err *err);
/* Values at the current time: states and parameters as they are, derivatives and outputs
 * evaluated at (t, x) (NaN where the model cannot evaluate them). */
LV_API lv_status lv_sim_get(lv_sim *sim, const lv_vref *refs, size_t n, double *values,
                            lv_err *err);
/* Sets states and parameters at the current time (finite values only). The integrator
 * restarts there, as after an event; the model's discrete modes are left as they are. */
LV_API lv_status lv_sim_set(lv_sim *sim, const lv_vref *refs, size_t n, const double *values,
                            lv_err *err);
/* Ends the run: final values (as lv_simulate), the report (its event log then belongs to the
 * caller: lv_sim_report_clear), the sinks closed - complete, or marked failed when the run
 * failed or had not reached its end. Returns the run's status. */
LV_API lv_status lv_sim_finish(lv_sim *sim, double *final_values, lv_sim_report *rep,
                               lv_err *err);
LV_API void lv_sim_free(lv_sim *sim); /* accepts NULL; closes unfinished sinks as failed */

/* Canonical method names, NULL-terminated (for help texts). */
LV_API const char *const *lv_sim_methods(void);

#ifdef __cplusplus
}
#endif
#endif
