/* lv_model.h - what a simulation model is: named variables, a right-hand side, events.
 *
 * A model is data plus pure functions. It knows nothing about phases, files or
 * integrators. lv_simulate() (lv_sim.h) integrates it.
 *
 * Variables. Every model variable has a name, a unit and a description:
 *   - states x[i]            (integrated; `start` is the default start value,
 *                             `nominal` scales the absolute tolerance)
 *   - derivatives der(x[i])  (named automatically "der(<state>)", unit "<unit>/s")
 *   - parameters p[j]        (constant during a run; `start` is the default value)
 *   - outputs y[k]           (computed from t, x, p and the discrete mode)
 * Names are resolved to indices once, outside the hot path; the callbacks see
 * plain arrays indexed by the model's own enums.
 *
 * Discrete modes (engine on/off, connected/separated) live in the model's
 * instance data `inst`, which lv_simulate() passes to every callback. They
 * change only in event handlers, never by `if (t > t_sep)` inside rhs().
 *
 * Callback return convention (as SUNDIALS): 0 ok; > 0 the state is not
 * acceptable, retry with a smaller step; < 0 unrecoverable, stop the run.
 */
#ifndef LVSIM_LV_MODEL_H
#define LVSIM_LV_MODEL_H

#include <stddef.h>

#include "lvsim/lv_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One named variable. Strings are static (or outlive the model). */
typedef struct lv_var {
    const char *name;        /* e.g. "h", "body1.m", "start_lat" */
    const char *unit;        /* SI unit string, "1" for dimensionless (lv_units.h; "" means
                                the same, written "1") */
    const char *description; /* one line */
    double start;            /* default start (state) or value (parameter) */
    double nominal;          /* states: typical magnitude, > 0 (atol = rtol * nominal) */
} lv_var;

typedef enum lv_var_kind {
    LV_VAR_STATE,
    LV_VAR_DERIVATIVE,
    LV_VAR_PARAMETER,
    LV_VAR_OUTPUT
} lv_var_kind;

/* Direction of a zero crossing that counts as an event. */
typedef enum lv_dir {
    LV_DIR_BOTH = 0,
    LV_DIR_RISING = 1,  /* g goes from negative to positive */
    LV_DIR_FALLING = -1 /* g goes from positive to negative */
} lv_dir;

/* Bytes (with the NUL) an event's name keeps in the event log (lv_event_record). */
#define LV_EVENT_NAME_MAX 96

/* A state event: a zero crossing of g_i(t, x). */
typedef struct lv_event_def {
    const char *name;        /* "burnout", "impact" */
    const char *description; /* one line */
    lv_dir direction;
    /* 1: an end of the run (its handler stops it). lv_simulate() refuses a start at which
     * such an event with a direction (rising or falling) is already passed - g lies beyond
     * its crossing and moves further away (probed as the start's roots are): it could fire
     * only after turning back, so the run would go on to its stop time ("end already
     * passed at the start"). 0: a mode change, never checked. */
    int ends_run;
} lv_event_def;

/* What an event handler asks lv_simulate() to do next. */
typedef enum lv_event_action {
    LV_EVENT_CONTINUE = 0, /* nothing changed: continue without restarting */
    LV_EVENT_RESTART = 1,  /* mode or state changed: re-initialise the integrator */
    LV_EVENT_STOP = 2      /* end the run at this instant (a phase end) */
} lv_event_action;

/* A bound of the model's domain: quantity >= lower, where the model's equations hold (the
 * vehicle above the ground, an atmosphere evaluated inside its range). lv_simulate watches
 * every bound as a state event: crossing it ends the run, at the located instant, as failed
 * ("h = -5000 m is below -5000 m: <why>"); a start state outside the domain fails at once. */
typedef struct lv_domain_def {
    const char *quantity; /* "h" */
    const char *unit;     /* "m" */
    double lower;         /* the domain: quantity >= lower */
    const char *why;      /* what leaving it means and what to do: "the vehicle is under the
                             ground: end the phase with an `impact` end" */
    /* 1: a guard that holds only once the quantity has been above `lower`: a start below it
     * is accepted (a launch from rest below a speed guard) and only a crossing from above
     * fails the run. A model that does not need the bound at (t, x) returns a large positive
     * q there (LV_DOMAIN_OFF). 0: the start must lie inside too. */
    int from_above;
} lv_domain_def;

/* The quantity of a domain bound that does not apply at (t, x) (see from_above). */
#define LV_DOMAIN_OFF 1e30

typedef struct lv_model_def lv_model_def;

struct lv_model_def {
    const char *name;        /* "vertical_ascent" */
    const char *description; /* one line */

    size_t n_states, n_params, n_outputs, n_events;
    const lv_var *states;        /* [n_states] */
    const lv_var *params;        /* [n_params] */
    const lv_var *outputs;       /* [n_outputs] */
    const lv_event_def *events;  /* [n_events] */
    size_t inst_size;            /* bytes of instance data (modes); lv_simulate() allocates
                                    a zeroed block of this size when called with inst == NULL */

    /* Optional. Compute state start values from the parameters (e.g. position
     * from start_lat/start_lon/start_h). Default: each state's `start`. Called
     * after parameters named in initialNames are set and before states named
     * there override the result. */
    int (*start)(const double *p, double *x, void *inst);

    /* Optional. Set discrete modes consistent with the initial (t0, x, p), e.g.
     * engine on iff propellant remains. Called once, just before integration. */
    int (*init)(double t0, const double *x, const double *p, void *inst);

    /* Required. dx/dt = f(t, x, p, mode). The hot path: allocate nothing. */
    int (*rhs)(double t, const double *x, const double *p, double *xdot, void *inst);

    /* Optional (required when n_events > 0). g[i] for every event function. */
    int (*event_g)(double t, const double *x, const double *p, double *g, void *inst);

    /* Optional. Handle the state events that fired at `t`: fired[i] is +1
     * (rising), -1 (falling) or 0. May change the mode in `inst` and the state
     * `x` in place. NULL means: stop at the first event. */
    lv_event_action (*on_event)(double t, double *x, const double *p, const int *fired,
                                void *inst);

    /* Optional. Earliest scheduled time event strictly after `t` (table
     * breakpoints, commanded actions), or INFINITY when none remain. */
    double (*next_time_event)(double t, const double *p, void *inst);

    /* Optional. Handle the time event(s) scheduled at exactly `t`. */
    lv_event_action (*on_time_event)(double t, double *x, const double *p, void *inst);

    /* Optional (required when n_outputs > 0). Outputs at (t, x). Not hot. */
    int (*outputs_fn)(double t, const double *x, const double *p, double *y, void *inst);

    /* Optional: [n_states], 1 where a state's error is controlled absolutely, to
     * tolerance * nominal, without the relative part tolerance * |x| (a coordinate measured
     * from a distant origin: for an ECI position, |r| = 6.4e6 m would turn a relative
     * tolerance of 1e-6 into 6 m; docs/integration.md). Its relative tolerance is 1e-14 (or
     * the tolerance, when smaller): no accuracy below the coordinate's own resolution is
     * asked for. NULL: every state both. */
    const unsigned char *abs_error;

    /* Optional: the bounds of the model's domain, and the function that evaluates their
     * quantities q[n_domain] at (t, x) (allocation-free: it runs with the event functions). */
    size_t n_domain;
    const lv_domain_def *domain;
    int (*domain_q)(double t, const double *x, const double *p, double *q, void *inst);

    /* Optional. The state at (t, x) in the model's own terms, for failure messages
     * ("h = 28887 m, v_rel = 0.01 m/s, fpa = -87.1 deg"): at most cap bytes into buf. */
    void (*describe)(double t, const double *x, const double *p, char *buf, size_t cap,
                     void *inst);

    /* Optional. Why the last callback failed ("table 'stage1' : t = 130 is outside
     * [0, 120]"), or NULL; lv_simulate() adds it to its failure message. */
    const char *(*last_error)(const void *inst);

    /* Optional. What the time event(s) scheduled at exactly `t` are, by their source: which
     * table and breakpoint, which commanded action ("engine table 'stage3' breakpoint
     * t = 481 s", "separation of stage2"). Called at `t` before on_time_event(); the text
     * may live in `inst` (it is copied at once). NULL (or no function): "time event". */
    const char *(*time_event_name)(double t, const double *p, void *inst);

    /* Optional: nonzero when the model is stiff by construction (runway friction, fast
     * actuator lags: eigenvalues far beyond 1 / the steps an explicit method would take). The
     * method "auto" then integrates it with BDF ("dassl") from the start, instead of an
     * explicit method until Hairer's stiffness test fires (docs/integration.md). */
    int stiff;

    /* Optional: [n_params], 1 where a parameter has no effect in this configuration because
     * something else gives the value it would set: a steering law the angle of attack, a
     * throttle law or an input table the throttle. Result files leave such a parameter out of
     * their parameter records (the .mat file's data_1), so that no record claims a constant
     * that did not act; the values in effect are outputs of the model (a 3-DoF phase's
     * alpha_in, beta_in, mu_in, throttle_in; docs/result-files.md). It stays a parameter
     * (lv_model_find, initial values). NULL: every parameter acts. */
    const unsigned char *param_inactive;

    /* Optional. The start parameters as the run actually started: when initial values set
     * states (a phase's hand-off from its parent, a `set:` override), the parameters start()
     * reads (start_lat, start_h, start_vel ... of the mission's root phase) describe a start
     * the run did not fly. lv_simulate() then calls this once, after init(), with (t0, x) the
     * start state and p a copy of the parameters, and the model overwrites in p those that
     * describe the start (position, velocity, attitude, rates, start time) with the values of
     * that state: the copy is what the result files record (the .mat file's data_1), so a
     * child phase's records show its own start. The run itself keeps the parameters as they
     * were. Returns 0; nonzero leaves the records as the parameters are. NULL: records are the
     * parameters. */
    int (*start_params)(double t0, const double *x, double *p, void *inst);

    /* Optional: [n_states], 1 where a state is a quadrature - the time integral of a quantity
     * of the others (a heat load, the integral of the heat flux) that no right-hand side reads
     * back (an event may: a phase end on it). It is integrated with the other states, by the same steps
     * and to the method's order, but left out of the error control (as CVODES' quadratures with
     * errconQ off: lv_integ_problem.quad), so that adding it changes neither the steps nor the
     * other states. At least one state must not be one. NULL: none. */
    const unsigned char *quadrature;

    /* Optional. The outputs y[i] with need[i] != 0 at (t, x) (need: [n_outputs]); the others
     * may be left as they are. lv_simulate() calls it, when given, for the stop conditions
     * that read outputs (at every step's end and in a root search), with only their outputs
     * needed: an end on `sma` then does not pay for the model's expensive outputs (the
     * instantaneous impact point's propagation of dof3 and dof6: a fifth of Delta III
     * targeting's instructions). Must give outputs_fn's values for those needed, bit for bit.
     * NULL: outputs_fn, all of them. */
    int (*outputs_some)(double t, const double *x, const double *p, double *y,
                        const unsigned char *need, void *inst);
};

/* Look a variable up by name. Returns LV_OK and sets *kind and *index, or
 * LV_ERR_NOTFOUND with a message that suggests the nearest names. "time" is
 * not a model variable. */
LV_API lv_status lv_model_find(const lv_model_def *def, const char *name, lv_var_kind *kind,
                               size_t *index, lv_err *err);

/* Checks a model definition for consistency (counts, names unique, nominal > 0,
 * required callbacks present). */
LV_API lv_status lv_model_validate(const lv_model_def *def, lv_err *err);

#ifdef __cplusplus
}
#endif
#endif
