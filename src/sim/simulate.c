/* simulate.c - lv_simulate(): one model, one run, as Dymola's simulateExtendedModel
 * (paper, Code 1): start values by name, integration with events, result rows on an
 * output grid plus every event instant twice, final values by name, statistics.
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/status.h"
#include "core/table_unit.h"
#include "integrate/integrator.h"
#include "io/sink.h"
#include "lvsim/lv_sim.h"

#define LV_DEFAULT_INTERVALS 500
#define LV_DEFAULT_MAX_STEPS 1000000L
#define LV_ABS_RTOL_FLOOR 1e-14 /* relative tolerance of a state under absolute error control */

void lv_sim_settings_default(lv_sim_settings *s)
{
    memset(s, 0, sizeof *s);
    s->start_time = 0.0;
    s->stop_time = 1.0;
    s->method = "dassl";
    s->tolerance = 1e-4;
    s->result_file = "dsres";
    s->result_formats = lv_result_format_mask(); /* every registered format */
}

const char *const *lv_sim_methods(void)
{
    static const char *const names[] = {"dassl", "cvode-adams", "dopri5", "rk4",  "euler",
                                        "dp5",   "dop853",      "auto",   NULL};
    return names;
}

void lv_sim_report_clear(lv_sim_report *rep)
{
    if (rep == NULL)
        return;
    free(rep->event_log);
    memset(rep, 0, sizeof *rep);
}

/* ---- run context ------------------------------------------------------------- */

typedef struct sim_run {
    const lv_model_def *def;
    void *inst;
    size_t nx, np, ny, ng;
    size_t nd;    /* domain bounds: event functions ng .. ng + nd - 1 of the integrator */
    double *q;    /* [nd] the bounded quantities */
    size_t ns;    /* stop conditions (lv_sim_settings.stops) */
    struct stop_ref *stops; /* [ns] */
    size_t ns_root; /* of them crossings: event functions ng + nd .. ng + nd + ns_root - 1 */
    double *xs, *ys; /* [nx], [ny] scratch for the stops' derivatives and outputs */
    unsigned char *stop_need; /* [ny] 1 for an output a stop condition reads (outputs_some) */
    int g_rc;       /* the last event-function evaluation's outcome (sim_g) */
    double g_rc_t;  /* and its time, when it failed */
    double t_model_te; /* the model's own next time event (the stops' are merged in t_te) */
    double *p;    /* [np] parameter values */
    double *x;    /* [nx] state */
    double *xdot; /* [nx] scratch for output rows */
    double *y;    /* [ny] outputs */
    double *row;  /* [n_signals] */
    int *roots;   /* [ng] */
    int *g_dir;   /* [ng] */
    double *atol; /* [nx] */
    double *rtol_v; /* [nx] per-state relative tolerance (models with abs_error), or NULL */
    size_t bad_index; /* first non-finite derivative seen by the RHS guard */
    double bad_t;
    int bad_seen;
    int rhs_rc;       /* last nonzero return of the model's rhs, and when */
    double rhs_rc_t;
    const volatile int *stop; /* lv_sim_settings.stop, or NULL */
    int cancelled;    /* the rhs saw the stop flag: the integrator's failure is a cancel */

    /* result layout */
    size_t n_signals;
    lv_var *signals;
    lv_var_kind *kinds;
    char **owned; /* strings made for der(x) names and units */
    size_t n_owned;

    lv_var *rec_params;    /* the parameters the result files record (param_inactive left out), */
    double *rec_values;    /* and their values; NULL: all of them (r->def->params, r->p) */
    int x_set;             /* initial values set a state: the start_params records apply */
    lv_sink own_sinks[32]; /* one per registered result format (flags of an unsigned) */
    size_t n_own_sinks;
    lv_sink **sinks; /* own + borrowed */
    size_t n_sinks;
    int sinks_open;

    lv_sim_report *rep;
    size_t log_cap;
} sim_run;

/* The integrator's RHS: the model's, plus a guard that turns a NaN or Inf
 * derivative into "retry with a smaller step" and remembers which one it was. */
static int sim_rhs(double t, const double *x, double *xdot, void *user)
{
    sim_run *r = user;
    /* a stop asked for: an unrecoverable failure ends the integrator's call within its step */
    if (r->stop != NULL && __atomic_load_n(r->stop, __ATOMIC_RELAXED) != 0) {
        r->cancelled = 1;
        return -1;
    }
    int rc = r->def->rhs(t, x, r->p, xdot, r->inst);
    r->rhs_rc = rc; /* the last evaluation's outcome: a failure message names its reason */
    if (rc != 0) {
        r->rhs_rc_t = t;
        return rc;
    }
    double probe = 0.0;
    for (size_t i = 0; i < r->nx; i++)
        probe += xdot[i] * 0.0; /* NaN iff some xdot[i] is NaN or Inf */
    if (probe == 0.0)
        return 0;
    for (size_t i = 0; i < r->nx; i++) {
        if (!isfinite(xdot[i])) {
            r->bad_index = i;
            r->bad_t = t;
            r->bad_seen = 1;
            break;
        }
    }
    return 1;
}

/* A stop condition resolved: the variable's kind and index ("time": a time event). */
typedef struct stop_ref {
    int is_time;
    lv_var_kind kind;
    size_t index;
    double value;
    size_t root; /* its event function (crossings): ng + nd + root */
} stop_ref;

/* The model's event functions, then one per bound of its domain (q - lower), then one per
 * crossing stop condition (variable - value). */
static int stop_outputs(sim_run *r, double t, const double *x);

static int sim_g_eval(sim_run *r, double t, const double *x, double *g);

/* The event functions (sim_g_eval), their last outcome remembered as the right-hand side's
 * is: a failure message names the model's reason (an end on q_dyn above a table
 * atmosphere's top: "altitude 10000.0000000018 m is above the table's range 0 m to 10000 m"). */
static int sim_g(double t, const double *x, double *g, void *user)
{
    sim_run *r = user;
    const int rc = sim_g_eval(r, t, x, g);
    r->g_rc = rc;
    if (rc != 0)
        r->g_rc_t = t;
    return rc;
}

static int sim_g_eval(sim_run *r, double t, const double *x, double *g)
{
    int rc = r->ng > 0 ? r->def->event_g(t, x, r->p, g, r->inst) : 0;
    if (rc != 0)
        return rc;
    if (r->nd > 0) {
        if ((rc = r->def->domain_q(t, x, r->p, r->q, r->inst)) != 0)
            return rc;
        for (size_t i = 0; i < r->nd; i++)
            g[r->ng + i] = r->q[i] - r->def->domain[i].lower;
    }
    int have_xdot = 0, have_y = 0;
    for (size_t j = 0; j < r->ns; j++) {
        const stop_ref *sr = &r->stops[j];
        if (sr->is_time)
            continue;
        double v = 0.0;
        switch (sr->kind) {
        case LV_VAR_STATE: v = x[sr->index]; break;
        case LV_VAR_PARAMETER: v = r->p[sr->index]; break;
        case LV_VAR_DERIVATIVE:
            if (!have_xdot && (rc = r->def->rhs(t, x, r->p, r->xs, r->inst)) != 0)
                return rc;
            have_xdot = 1;
            v = r->xs[sr->index];
            break;
        case LV_VAR_OUTPUT:
            if (!have_y && (rc = stop_outputs(r, t, x)) != 0)
                return rc;
            have_y = 1;
            v = r->ys[sr->index];
            break;
        }
        g[r->ng + r->nd + sr->root] = v - sr->value;
    }
    return 0;
}

/* " (state at t: <the model's description>)" of the current r->x, or "" without one. */
static void describe_state(const sim_run *r, double t, char *buf, size_t cap)
{
    buf[0] = '\0';
    if (r->def->describe == NULL || cap < 32)
        return;
    char d[200] = "";
    r->def->describe(t, r->x, r->p, d, sizeof d, r->inst);
    if (d[0] != '\0')
        snprintf(buf, cap, " (state at t = %.9g s: %s)", t, d);
}

/* The message for bound i of the domain left (q = value) at t. */
static lv_status domain_fail(const sim_run *r, size_t i, double t, double value, int at_start,
                             lv_err *err)
{
    const lv_domain_def *b = &r->def->domain[i];
    if (at_start)
        return lv_fail(err, LV_ERR_INPUT,
                       "model '%s': the start state at t = %.9g s is outside the model's "
                       "domain: %s = %g %s is below its lower bound %g %s: %s",
                       r->def->name, t, b->quantity, value, b->unit, b->lower, b->unit, b->why);
    (void)value; /* at the located crossing the quantity is the bound */
    char state[256];
    describe_state(r, t, state, sizeof state);
    return lv_fail(err, LV_ERR_SOLVER,
                   "model '%s': at t = %.9g s the state left the model's domain: %s fell to its "
                   "lower bound %g %s: %s%s",
                   r->def->name, t, b->quantity, b->lower, b->unit, b->why, state);
}

static double thread_cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static char *own_string(sim_run *r, const char *a, const char *b, const char *c)
{
    const size_t la = strlen(a), lb = strlen(b), lc = strlen(c);
    char *s = malloc(la + lb + lc + 1);
    if (s == NULL)
        return NULL;
    memcpy(s, a, la); /* not snprintf: this runs for every state at every set-up */
    memcpy(s + la, b, lb);
    memcpy(s + la + lb, c, lc + 1);
    r->owned[r->n_owned++] = s;
    return s;
}

/* Unit of a time derivative (lv_unit_per_second), owned by the run. */
static char *derivative_unit(sim_run *r, const char *unit)
{
    char buf[96];
    return own_string(r, lv_unit_per_second(unit, buf, sizeof buf), "", "");
}

static lv_status build_layout(sim_run *r, lv_err *err)
{
    const lv_model_def *d = r->def;
    r->n_signals = 1 + 2 * r->nx + r->ny;
    r->signals = calloc(r->n_signals, sizeof *r->signals);
    r->kinds = calloc(r->n_signals, sizeof *r->kinds);
    r->owned = calloc(3 * r->nx + 1, sizeof *r->owned);
    r->row = calloc(r->n_signals, sizeof *r->row);
    if (!r->signals || !r->kinds || !r->owned || !r->row)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    r->signals[0] = (lv_var){"time", "s", "Simulation time", 0.0, 1.0};
    r->kinds[0] = LV_VAR_OUTPUT;
    for (size_t i = 0; i < r->nx; i++) {
        const lv_var *v = &d->states[i];
        r->signals[1 + i] = *v;
        r->kinds[1 + i] = LV_VAR_STATE;
        char *name = own_string(r, "der(", v->name, ")");
        char *unit = name ? derivative_unit(r, v->unit) : NULL;
        char *desc = unit ? own_string(r, "Time derivative of ", v->name, "") : NULL;
        if (desc == NULL)
            return lv_fail(err, LV_ERR_NOMEM, "out of memory");
        r->signals[1 + r->nx + i] = (lv_var){name, unit, desc, 0.0, 1.0};
        r->kinds[1 + r->nx + i] = LV_VAR_DERIVATIVE;
    }
    for (size_t i = 0; i < r->ny; i++) {
        r->signals[1 + 2 * r->nx + i] = d->outputs[i];
        r->kinds[1 + 2 * r->nx + i] = LV_VAR_OUTPUT;
    }
    return LV_OK;
}

/* One result row at (t, x): time, states, derivatives, outputs. A derivative or
 * output the model cannot evaluate there is written as NaN. Without a sink nobody reads the
 * row: it is counted, not evaluated (the final values are evaluated apart). */
static lv_status emit_row(sim_run *r, double t, lv_err *err)
{
    r->row[0] = t;
    if (r->n_sinks == 0) {
        r->rep->stats.output_rows++;
        return LV_OK;
    }
    r->rep->stats.row_evals++;
    memcpy(r->row + 1, r->x, r->nx * sizeof(double));
    if (r->def->rhs(t, r->x, r->p, r->xdot, r->inst) != 0)
        for (size_t i = 0; i < r->nx; i++)
            r->xdot[i] = NAN;
    memcpy(r->row + 1 + r->nx, r->xdot, r->nx * sizeof(double));
    if (r->ny > 0) {
        if (r->def->outputs_fn(t, r->x, r->p, r->y, r->inst) != 0)
            for (size_t i = 0; i < r->ny; i++)
                r->y[i] = NAN;
        memcpy(r->row + 1 + 2 * r->nx, r->y, r->ny * sizeof(double));
    }
    for (size_t k = 0; k < r->n_sinks; k++) {
        lv_sink *s = r->sinks[k];
        lv_status st = s->vt->row(s->self, r->row, err);
        if (st != LV_OK)
            return st;
    }
    r->rep->stats.output_rows++;
    return LV_OK;
}

static lv_status log_event(sim_run *r, double t, int is_state, int index, int direction,
                           const char *name)
{
    lv_sim_report *rep = r->rep;
    if (rep->n_event_log == r->log_cap) {
        size_t cap = r->log_cap ? 2 * r->log_cap : 16;
        lv_event_record *grown = realloc(rep->event_log, cap * sizeof *grown);
        if (grown == NULL)
            return LV_ERR_NOMEM;
        rep->event_log = grown;
        r->log_cap = cap;
    }
    lv_event_record *e = &rep->event_log[rep->n_event_log++];
    *e = (lv_event_record){t, is_state, index, direction, ""};
    snprintf(e->name, sizeof e->name, "%s", name != NULL && name[0] != '\0' ? name : "time event");
    return LV_OK;
}

/* ---- settings and names -------------------------------------------------------- */

static lv_status check_settings(const lv_model_def *d, const lv_sim_settings *s, lv_method *m,
                                lv_err *err)
{
    const char *mn = d->name;
    if (!isfinite(s->start_time) || !isfinite(s->stop_time))
        return lv_fail(err, LV_ERR_INPUT, "model '%s': startTime and stopTime must be finite "
                                          "(got %g, %g)", mn, s->start_time, s->stop_time);
    if (s->stop_time < s->start_time)
        return lv_fail(err, LV_ERR_INPUT, "model '%s': stopTime %g s is before startTime %g s", mn,
                       s->stop_time, s->start_time);
    if (!(s->tolerance >= LV_TOLERANCE_MIN && s->tolerance <= LV_TOLERANCE_MAX))
        return lv_fail(err, LV_ERR_INPUT, "model '%s': tolerance must be >= %g and <= %g (got %g)",
                       mn, LV_TOLERANCE_MIN, LV_TOLERANCE_MAX, s->tolerance);
    if (s->number_of_intervals < 0)
        return lv_fail(err, LV_ERR_INPUT, "model '%s': numberOfIntervals must be >= 0 (got %d)",
                       mn, s->number_of_intervals);
    if (!(s->output_interval >= 0.0) || !isfinite(s->output_interval))
        return lv_fail(err, LV_ERR_INPUT, "model '%s': outputInterval must be >= 0 (got %g)", mn,
                       s->output_interval);
    if (!(s->fixed_step >= 0.0) || !isfinite(s->fixed_step))
        return lv_fail(err, LV_ERR_INPUT, "model '%s': fixedstepsize must be >= 0 (got %g)", mn,
                       s->fixed_step);
    if (!(s->max_step_size >= 0.0) || !isfinite(s->max_step_size))
        return lv_fail(err, LV_ERR_INPUT, "model '%s': max step size must be >= 0 (got %g)", mn,
                       s->max_step_size);
    if (s->max_steps < 0)
        return lv_fail(err, LV_ERR_INPUT, "model '%s': max steps must be >= 0 (got %ld)", mn,
                       s->max_steps);
    if (!(s->max_rows >= 0.0))
        return lv_fail(err, LV_ERR_INPUT, "model '%s': max rows must be >= 0 (got %g)", mn,
                       s->max_rows);
    if ((s->n_initial > 0 && (s->initial_names == NULL || s->initial_values == NULL)) ||
        (s->n_final > 0 && s->final_names == NULL) || (s->n_sinks > 0 && s->sinks == NULL))
        return lv_fail(err, LV_ERR_INPUT, "model '%s': name/value arrays are NULL", mn);
    lv_status st = lv_method_parse(s->method ? s->method : "dassl", m, err);
    if (st != LV_OK)
        return lv_fail_prefix(err, st, "model '%s'", mn);
    return LV_OK;
}

/* Parameters first (start values may derive from them), then the model's
 * start(), then state overrides. */
static lv_status apply_initial(sim_run *r, const lv_sim_settings *s, lv_err *err)
{
    const lv_model_def *d = r->def;
    for (size_t j = 0; j < r->np; j++)
        r->p[j] = d->params[j].start;
    for (int pass = 0; pass < 2; pass++) {
        for (size_t i = 0; i < s->n_initial; i++) {
            lv_var_kind kind;
            size_t idx;
            const char *name = s->initial_names[i];
            lv_status st = lv_model_find(d, name, &kind, &idx, err);
            if (st != LV_OK)
                return lv_fail_prefix(err, st, "initialNames[%zu]", i);
            double v = s->initial_values[i];
            if (pass == 0 && !isfinite(v))
                return lv_fail(err, LV_ERR_INPUT,
                               "model '%s': initialValues[%zu] for '%s' is %g (must be finite)",
                               d->name, i, name, v);
            if (kind == LV_VAR_DERIVATIVE || kind == LV_VAR_OUTPUT)
                return lv_fail(err, LV_ERR_INPUT,
                               "model '%s': '%s' is %s; only states and parameters can be set",
                               d->name, name,
                               kind == LV_VAR_OUTPUT ? "an output" : "a derivative");
            if (pass == 0 && kind == LV_VAR_PARAMETER)
                r->p[idx] = v;
            if (pass == 1 && kind == LV_VAR_STATE) {
                r->x[idx] = v;
                r->x_set = 1;
            }
        }
        if (pass == 0) {
            for (size_t i = 0; i < r->nx; i++)
                r->x[i] = d->states[i].start;
            if (d->start != NULL && d->start(r->p, r->x, r->inst) != 0) {
                const char *why = d->last_error ? d->last_error(r->inst) : NULL;
                return lv_fail(err, LV_ERR_INPUT,
                               "model '%s': start values cannot be computed from the parameters"
                               "%s%s", d->name, why && why[0] ? ": " : "", why ? why : "");
            }
        }
    }
    for (size_t i = 0; i < r->nx; i++)
        if (!isfinite(r->x[i]))
            return lv_fail(err, LV_ERR_INPUT, "model '%s': start value of '%s' is %g", d->name,
                           d->states[i].name, r->x[i]);
    return LV_OK;
}

typedef struct final_ref {
    lv_var_kind kind;
    size_t index;
    int is_time;
} final_ref;

/* The variable after (kind, index) in lv_model_find's order (states, parameters, outputs), if
 * it is named `name`; prev NULL: the first. Names are unique across kinds (lv_model_validate),
 * so a hit is lv_model_find's answer. */
static int next_var_is(const lv_model_def *d, const final_ref *prev, const char *name,
                       final_ref *out)
{
    const lv_var *vars[3] = {d->states, d->params, d->outputs};
    const size_t n[3] = {d->n_states, d->n_params, d->n_outputs};
    const lv_var_kind kinds[3] = {LV_VAR_STATE, LV_VAR_PARAMETER, LV_VAR_OUTPUT};
    int k = 0;
    size_t i = 0;
    if (prev != NULL) {
        while (k < 3 && kinds[k] != prev->kind)
            k++;
        i = prev->index + 1;
    }
    while (k < 3 && i >= n[k]) {
        k++;
        i = 0;
    }
    if (k == 3 || name == NULL || strcmp(vars[k][i].name, name) != 0)
        return 0;
    out->kind = kinds[k];
    out->index = i;
    return 1;
}

static lv_status resolve_finals(const lv_model_def *d, const lv_sim_settings *s, final_ref *refs,
                                lv_err *err)
{
    const final_ref *prev = NULL; /* the last variable found: the finals of a mission's phase
                                   * are its model's variables in order (every state and
                                   * output), so the next one is tried first - a lookup of
                                   * each name among ~60 cost ~2,200 string comparisons at
                                   * every simulation's set-up */
    for (size_t i = 0; i < s->n_final; i++) {
        refs[i].is_time = s->final_names[i] != NULL && strcmp(s->final_names[i], "time") == 0;
        if (refs[i].is_time)
            continue;
        if (next_var_is(d, prev, s->final_names[i], &refs[i])) {
            prev = &refs[i];
            continue;
        }
        lv_status st = lv_model_find(d, s->final_names[i], &refs[i].kind, &refs[i].index, err);
        if (st == LV_OK && refs[i].kind != LV_VAR_DERIVATIVE)
            prev = &refs[i];
        if (st != LV_OK)
            return lv_fail_prefix(err, st, "finalNames[%zu]", i);
    }
    return LV_OK;
}

/* The stop conditions: their variables resolved, crossings numbered after the domain's. */
static lv_status resolve_stops(sim_run *r, const lv_sim_settings *s, lv_err *err)
{
    const lv_model_def *d = r->def;
    r->ns_root = 0;
    for (size_t j = 0; j < s->n_stops; j++) {
        const lv_sim_stop *sp = &s->stops[j];
        stop_ref *sr = &r->stops[j];
        if (sp->name == NULL || sp->variable == NULL || !isfinite(sp->value))
            return lv_fail(err, LV_ERR_INPUT, "model '%s': stop condition %zu: no name or "
                           "variable, or a value that is not finite", d->name, j + 1);
        sr->value = sp->value;
        if (strcmp(sp->variable, "time") == 0) {
            sr->is_time = 1;
            continue;
        }
        lv_status st = lv_model_find(d, sp->variable, &sr->kind, &sr->index, err);
        if (st != LV_OK)
            return lv_fail_prefix(err, st, "stop condition '%s'", sp->name);
        if (sr->kind == LV_VAR_PARAMETER)
            return lv_fail(err, LV_ERR_INPUT, "model '%s': stop condition '%s': '%s' is a "
                           "parameter: constant during a run, it never crosses %g", d->name,
                           sp->name, sp->variable, sp->value);
        if (sr->kind == LV_VAR_OUTPUT)
            r->stop_need[sr->index] = 1;
        sr->root = r->ns_root++;
    }
    return LV_OK;
}

/* The outputs the stop conditions read, at (t, x), into r->ys: only those where the model can
 * compute a part of them (outputs_some). */
static int stop_outputs(sim_run *r, double t, const double *x)
{
    if (r->def->outputs_some != NULL)
        return r->def->outputs_some(t, x, r->p, r->ys, r->stop_need, r->inst);
    return r->def->outputs_fn(t, x, r->p, r->ys, r->inst);
}

/* ---- sinks ------------------------------------------------------------------------ */

static lv_status open_sinks(sim_run *r, const lv_sim_settings *s, lv_err *err)
{
    size_t n = s->n_sinks + lv_result_format_count();
    r->sinks = calloc(n, sizeof *r->sinks);
    if (r->sinks == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    if (s->result_file != NULL && s->result_file[0] != '\0') {
        for (size_t k = 0; lv_result_formats[k] != NULL; k++) {
            const lv_result_format *f = lv_result_formats[k];
            if (!(s->result_formats & (1u << k)))
                continue;
            size_t len = strlen(s->result_file) + strlen(f->ext) + 1;
            char *path = malloc(len);
            if (path == NULL)
                return lv_fail(err, LV_ERR_NOMEM, "out of memory");
            snprintf(path, len, "%s%s", s->result_file, f->ext);
            lv_status st = f->create(path, &r->own_sinks[r->n_own_sinks], err);
            free(path);
            if (st != LV_OK)
                return st;
            r->sinks[r->n_sinks++] = &r->own_sinks[r->n_own_sinks++];
        }
    }
    for (size_t k = 0; k < s->n_sinks; k++)
        r->sinks[r->n_sinks++] = &s->sinks[k];

    /* the parameters that act: one a law or a table replaces is not recorded as a constant
     * (lv_model_def.param_inactive); the start parameters as the run started, where initial
     * values set its states (lv_model_def.start_params: a child phase's own start) */
    const lv_var *rec_params = r->def->params;
    const double *rec_values = r->p;
    size_t n_rec = r->np;
    const int restart = r->x_set && r->def->start_params != NULL;
    if ((r->def->param_inactive != NULL || restart) && r->np > 0) {
        r->rec_params = malloc(r->np * sizeof *r->rec_params);
        r->rec_values = malloc(r->np * sizeof *r->rec_values);
        if (r->rec_params == NULL || r->rec_values == NULL)
            return lv_fail(err, LV_ERR_NOMEM, "out of memory");
        memcpy(r->rec_values, r->p, r->np * sizeof *r->rec_values);
        if (restart && r->def->start_params(s->start_time, r->x, r->rec_values, r->inst) != 0)
            memcpy(r->rec_values, r->p, r->np * sizeof *r->rec_values);
        n_rec = 0;
        for (size_t j = 0; j < r->np; j++)
            if (r->def->param_inactive == NULL || !r->def->param_inactive[j]) {
                r->rec_params[n_rec] = r->def->params[j];
                r->rec_values[n_rec++] = r->rec_values[j];
            }
        rec_params = r->rec_params;
        rec_values = r->rec_values;
    }
    lv_result_info info = {r->def->name,  r->def->description ? r->def->description : "",
                           n_rec,         rec_params,
                           rec_values,    r->n_signals,
                           r->signals,    r->kinds};
    for (size_t k = 0; k < r->n_sinks; k++) {
        lv_status st = r->sinks[k]->vt->open(r->sinks[k]->self, &info, err);
        if (st != LV_OK) {
            /* Close the ones already open as failed, so no temp file stays behind. */
            for (size_t j = 0; j < k; j++)
                r->sinks[j]->vt->close(r->sinks[j]->self, "could not open all result sinks", NULL);
            return st;
        }
    }
    r->sinks_open = 1;
    return LV_OK;
}

static lv_status close_sinks(sim_run *r, const char *failure, lv_err *err)
{
    lv_status first = LV_OK;
    if (!r->sinks_open)
        return LV_OK;
    for (size_t k = 0; k < r->n_sinks; k++) {
        lv_err tmp;
        lv_status st = r->sinks[k]->vt->close(r->sinks[k]->self, failure, &tmp);
        if (st != LV_OK && first == LV_OK) {
            first = st;
            if (err != NULL)
                *err = tmp;
        }
    }
    r->sinks_open = 0;
    return first;
}

static void free_run(sim_run *r)
{
    for (size_t k = 0; k < r->n_own_sinks; k++)
        lv_sink_destroy(&r->own_sinks[k]);
    free(r->sinks);
    free(r->rec_params);
    free(r->rec_values);
    for (size_t i = 0; i < r->n_owned; i++)
        free(r->owned[i]);
    free(r->owned);
    free(r->signals);
    free(r->kinds);
    free(r->p);
    free(r->x);
    free(r->xdot);
    free(r->y);
    free(r->row);
    free(r->roots);
    free(r->g_dir);
    free(r->q);
    free(r->stops);
    free(r->xs);
    free(r->ys);
    free(r->stop_need);
    free(r->atol);
    free(r->rtol_v);
}

/* ---- the run ---------------------------------------------------------------------- */

/* Output grid: k = 0..K; the last point is exactly stop_time. */
typedef struct out_grid {
    double t0, tf, dt;
    long K;
} out_grid;

static out_grid make_grid(const lv_sim_settings *s)
{
    out_grid g = {s->start_time, s->stop_time, 0.0, 1};
    double span = s->stop_time - s->start_time;
    if (s->output_interval > 0.0) {
        g.dt = s->output_interval;
        double n = span / g.dt;
        g.K = n > 1e15 ? (long)1e15 : (long)ceil(n - 1e-9);
    } else {
        g.K = s->number_of_intervals > 0 ? s->number_of_intervals : LV_DEFAULT_INTERVALS;
        g.dt = span / (double)g.K;
    }
    if (g.K < 1)
        g.K = 1;
    return g;
}

static double grid_time(const out_grid *g, long k)
{
    return k >= g->K ? g->tf : g->t0 + (double)k * g->dt;
}

static double next_time_event(sim_run *r, double t)
{
    double tn = r->def->next_time_event != NULL ? r->def->next_time_event(t, r->p, r->inst)
                                                : INFINITY;
    r->t_model_te = tn;
    for (size_t j = 0; j < r->ns; j++)
        if (r->stops[j].is_time && r->stops[j].value > t && r->stops[j].value < tn)
            tn = r->stops[j].value;
    return tn;
}

/* A simulation in progress: what lv_simulate() did in one call, in steps. */
typedef enum sim_phase { SIM_RUNNING = 0, SIM_FINISHED, SIM_FAILED } sim_phase;

struct lv_sim {
    sim_run r;
    lv_sim_settings s;  /* copy; arrays and sinks borrowed until lv_sim_finish */
    lv_sim_report rep;  /* owned until lv_sim_finish hands it over */
    final_ref *refs;    /* [n_final] */
    void *own_inst;     /* inst allocated here when the caller passed NULL */
    lv_integ *ig;       /* NULL when stop_time == start_time */
    out_grid grid;
    double t;           /* current time */
    double t_te;        /* next scheduled time event */
    double tstop_set;   /* stop time given to the integrator, or NAN */
    long k;             /* next output grid index */
    sim_phase state;
    lv_status fail_st;  /* SIM_FAILED: the status and message of the failure */
    lv_err fail;
    double cpu;         /* s, thread CPU spent inside this simulation's calls */
    int start_roots;    /* r->roots holds event functions that are 0 at the start and move
                           through 0 in their direction: they fire at the start */
};

/* An event function exactly 0 at the start is one the integrator never reports (CVODE masks a
 * root at t0 until the function leaves 0, and leaving it is no crossing): a free fall from
 * h = 0, a burnout with no propellant. Which way each such function moves is probed with one
 * classical RK4 step of the model's own right-hand side (second order in the state, so a body
 * at rest on the ground that gravity pulls down is seen falling), of length 1e-6 of the run or
 * of its first output interval; a function that then lies on its event's side (below 0 for a
 * falling event, above for a rising one, either for both) fires at the start, in the same
 * order and with the same handling as any event (when the model cannot be evaluated there,
 * nothing fires: the run's first step reports the failure). A function within TINY_G of 0
 * that the probe step takes across 0 fires at the start the same way. The same probe finds
 * the ends already passed at the start (passed_end). */
/* An event function this close to 0 at the start is taken as on its surface when the probe
 * step crosses it (CVODE resolves no root closer to t0 than ~100 ulp of the step). */
#define TINY_G 1e-100

/* End k of the run (k < ng: the model's event k; then the stop conditions): 1 when it is
 * one whose function can lie behind the start (an event with ends_run, or a crossing stop
 * condition), with *i its event function and *dir its direction (0: both). */
static int end_function(const lv_sim *S, size_t k, size_t *i, int *dir)
{
    const sim_run *r = &S->r;
    if (k < r->ng) {
        *i = k;
        *dir = (int)r->def->events[k].direction;
        return r->def->events[k].ends_run != 0;
    }
    const stop_ref *sr = &r->stops[k - r->ng];
    *i = r->ng + r->nd + sr->root;
    *dir = (int)S->s.stops[k - r->ng].direction;
    return !sr->is_time;
}

/* 1 when an end's function lies beyond its crossing at the start (g0 dir > 0). */
static int maybe_passed(const lv_sim *S, const double *g0)
{
    for (size_t k = 0; k < S->r.ng + S->r.ns; k++) {
        size_t i;
        int dir;
        if (end_function(S, k, &i, &dir) && dir != 0 && g0[i] * dir > 0.0)
            return 1;
    }
    return 0;
}

/* An end with a direction whose function lies beyond its crossing at the start (g0 dir > 0)
 * and that the probe step takes further away ((g1 - g0) dir > 0) is already passed:
 * LV_ERR_INPUT naming it. */
static lv_status passed_end(const lv_sim *S, const double *g0, const double *g1, lv_err *err)
{
    const sim_run *r = &S->r;
    const lv_model_def *d = r->def;
    const double t0 = S->t;
    for (size_t k = 0; k < r->ng + r->ns; k++) {
        size_t i;
        int dir;
        if (!end_function(S, k, &i, &dir) || dir == 0 || !(g0[i] * dir > 0.0) ||
            fabs(g0[i]) < TINY_G || !((g1[i] - g0[i]) * dir > 0.0))
            continue;
        const lv_sim_stop *sp = k >= r->ng ? &S->s.stops[k - r->ng] : NULL;
        const char *way = dir < 0 ? "falls" : "rises", *now = dir < 0 ? "falling" : "rising";
        char what[200], state[256];
        if (sp != NULL)
            snprintf(what, sizeof what, "when %s %s through %g, but there %s = %g and is still %s",
                     sp->variable, way, sp->value, sp->variable, sp->value + g0[i], now);
        else
            snprintf(what, sizeof what, "when its quantity %s through its value (%s), but there it "
                     "is already %g %s it and still %s", way, d->events[k].description,
                     fabs(g0[i]), dir < 0 ? "below" : "above", now);
        describe_state(r, t0, state, sizeof state);
        return lv_fail(err, LV_ERR_INPUT,
                       "model '%s': the end '%s' is already passed at the start t = %.9g s: it "
                       "fires %s; it could fire only after turning back, so the run would end "
                       "otherwise (by another end, or at its stop time). Check the end's value "
                       "and direction against the state the phase starts from%s",
                       d->name, sp != NULL ? sp->name : d->events[k].name, t0, what, state);
    }
    return LV_OK;
}

/* The start's roots (above) and the ends already passed (passed_end). LV_OK also when the
 * model cannot be evaluated near the start (nothing fires: the run's first step reports it). */
static lv_status probe_start(lv_sim *S, lv_err *err)
{
    sim_run *r = &S->r;
    const size_t ng = r->ng + r->nd + r->ns_root, nx = r->nx;
    if (ng == 0)
        return LV_OK;
    const double t0 = S->t, span = S->s.stop_time - t0;
    double h = 1e-6 * (S->grid.dt > 0.0 && S->grid.dt < span ? S->grid.dt : span);
    if (!(h > 0.0) || !isfinite(h))
        return LV_OK;
    double *g0 = calloc(2 * ng + 6 * nx, sizeof *g0);
    if (g0 == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    double *g1 = g0 + ng, *k1 = g1 + ng, *k2 = k1 + nx, *k3 = k2 + nx, *k4 = k3 + nx,
           *xt = k4 + nx, *x1 = xt + nx;
    int rc = sim_g(t0, r->x, g0, r), any = 0;
    for (size_t i = 0; rc == 0 && i < ng; i++)
        any |= fabs(g0[i]) < TINY_G; /* 0 included */
    const int passed = rc == 0 && maybe_passed(S, g0);
    lv_status st = LV_OK;
    if (rc == 0 && (any || passed)) {
        const lv_model_def *d = r->def;
        rc = d->rhs(t0, r->x, r->p, k1, r->inst);
        for (size_t i = 0; i < nx; i++)
            xt[i] = r->x[i] + 0.5 * h * k1[i];
        rc = rc ? rc : d->rhs(t0 + 0.5 * h, xt, r->p, k2, r->inst);
        for (size_t i = 0; i < nx; i++)
            xt[i] = r->x[i] + 0.5 * h * k2[i];
        rc = rc ? rc : d->rhs(t0 + 0.5 * h, xt, r->p, k3, r->inst);
        for (size_t i = 0; i < nx; i++)
            xt[i] = r->x[i] + h * k3[i];
        rc = rc ? rc : d->rhs(t0 + h, xt, r->p, k4, r->inst);
        for (size_t i = 0; i < nx; i++)
            x1[i] = r->x[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        rc = rc ? rc : sim_g(t0 + h, x1, g1, r);
        for (size_t i = 0; rc == 0 && any && i < ng; i++) {
            const int dir = g1[i] < 0.0 ? -1 : g1[i] > 0.0 ? 1 : 0;
            const int want = r->g_dir[i];
            /* 0 at the start, or so close to it that the crossing lies within the probe
             * step, where the integrator's root check cannot resolve it from t0 (a free
             * fall from h = 1e-300 m: issue 22's breaker) */
            const int at_start = fabs(g0[i]) < TINY_G && g0[i] * dir <= 0.0;
            r->roots[i] = at_start && dir != 0 && (want == 0 || want == dir) ? dir : 0;
            S->start_roots |= r->roots[i] != 0;
        }
        if (rc == 0 && passed)
            st = passed_end(S, g0, g1, err);
    }
    free(g0);
    if (rc != 0) {
        memset(r->roots, 0, ng * sizeof *r->roots);
        S->start_roots = 0;
    }
    return st;
}

/* Ends the run as failed: keeps the message for lv_sim_finish and the caller. */
static lv_status sim_failed(lv_sim *S, lv_status st, lv_err *err)
{
    S->state = SIM_FAILED;
    S->fail_st = st;
    if (err != NULL)
        S->fail = *err;
    return st;
}

/* The integrator's stop time: the next time event or stop_time, given when it changed. */
static lv_status set_stop_target(lv_sim *S, lv_err *err)
{
    const double tf = S->s.stop_time;
    double target = S->t_te < tf ? S->t_te : tf;
    if (target != S->tstop_set) {
        lv_status st = lv_integ_set_stop_time(S->ig, target, err);
        if (st != LV_OK)
            return st;
        S->tstop_set = target;
    }
    return LV_OK;
}

/* A run that writes no rows (no sink: Monte Carlo, targeting, --outputs none) with an
 * integrator whose results do not depend on its output times (lv_integ_outputs_free): the
 * grid times are counted, not stopped at. Each stop interpolated the state (DOP853: three more
 * right-hand sides per step that holds one) for a row nobody keeps: 19 % of a targeting run's
 * instructions. The rows, events, finals and statistics are the same bit for bit. */
static int grid_skipped(const lv_sim *S)
{
    return S->r.n_sinks == 0 && lv_integ_outputs_free(S->ig);
}

/* The next integrator return: one lv_integ_advance to the nearest of the next grid time
 * (*t_grid), the stop time and t_adv, or the events that fire at the start (no step). When the
 * grid is skipped (grid_skipped), to the nearest of the stop time, t_adv and the grid time at
 * which the row limit would stop the run; the grid points passed on the way are then counted as
 * rows (as emit_row counts them without a sink) and *t_grid is the next one. */
static lv_status advance_to_next(lv_sim *S, double t_adv, double *t, double *t_grid,
                                 lv_integ_result *res, int *at_start, lv_err *err)
{
    *t_grid = grid_time(&S->grid, S->k);
    const int skip = grid_skipped(S);
    double tout = *t_grid < S->tstop_set ? *t_grid : S->tstop_set;
    if (skip) {
        tout = S->tstop_set;
        const double lim = S->s.max_rows;
        if (lim > 0.0 && lim <= (double)S->grid.K) { /* grid_row fails at row k >= max_rows */
            const double t_lim = grid_time(&S->grid, (long)ceil(lim));
            if (t_lim < tout)
                tout = t_lim;
        }
    }
    if (t_adv < tout)
        tout = t_adv;
    *t = S->t;
    *at_start = S->start_roots;
    if (*at_start) {
        S->start_roots = 0;
        *res = LV_INTEG_ROOT;
        return LV_OK;
    }
    lv_status st = lv_integ_advance(S->ig, tout, t, S->r.x, res, S->r.roots, err);
    if (skip) {
        while (S->k <= S->grid.K && grid_time(&S->grid, S->k) < *t) {
            S->r.rep->stats.output_rows++;
            S->k++;
        }
        *t_grid = grid_time(&S->grid, S->k);
    }
    return st;
}

/* The integrator failed at t: the last accepted state is written as the result's final row,
 * and the message says why in the model's terms (cancel, a non-finite derivative, the
 * right-hand side's own failure and reason), else the integrator's. */
static lv_status integration_failed(sim_run *r, double t, lv_status st, lv_err *err)
{
    const lv_model_def *d = r->def;
    lv_err row_err;
    if (t > r->row[0])
        emit_row(r, t, &row_err);
    if (r->cancelled)
        return lv_fail(err, LV_ERR_CANCELLED, "model '%s': cancelled at t = %.9g s", d->name, t);
    if (r->bad_seen)
        return lv_fail_prefix(err, st, "model '%s': der(%s) is not finite at t = %.9g s", d->name,
                              d->states[r->bad_index].name, r->bad_t);
    const char *why = d->last_error ? d->last_error(r->inst) : NULL;
    if (r->rhs_rc < 0)
        return lv_fail_prefix(err, st, "model '%s': right-hand side returned %d at t = %.9g s%s%s",
                              d->name, r->rhs_rc, r->rhs_rc_t, why ? ": " : "", why ? why : "");
    /* a state the model could not accept (it said why): the reason first */
    if (r->rhs_rc > 0 && why != NULL && why[0] != '\0')
        return lv_fail_prefix(err, st,
                              "model '%s': the right-hand side cannot be evaluated at "
                              "t = %.9g s: %s",
                              d->name, r->rhs_rc_t, why);
    /* an event function (the model's events, its domain, the stop conditions' outputs)
     * the model could not evaluate: its reason */
    if (r->g_rc != 0 && why != NULL && why[0] != '\0')
        return lv_fail_prefix(err, st,
                              "model '%s': the event functions (its events and the run's ends) "
                              "cannot be evaluated at t = %.9g s: %s",
                              d->name, r->g_rc_t, why);
    /* the integrator's own failure (the step size collapsed, the step limit): where the
     * model was, in its terms (r->x holds the last accepted state) */
    char state[256];
    describe_state(r, t, state, sizeof state);
    if (state[0] != '\0' && err != NULL) {
        const size_t len = strlen(err->msg);
        snprintf(err->msg + len, sizeof err->msg - len, "%s", state);
    }
    return lv_fail_prefix(err, st, "model '%s'", d->name);
}

/* The model's own state events at t (r->roots[0 .. ng-1]): counted and logged in index order,
 * then its handler; *action raised to what it asks. */
static lv_status model_state_events(sim_run *r, double t, lv_event_action *action, lv_err *err)
{
    const lv_model_def *d = r->def;
    lv_sim_report *rep = r->rep;
    int first = -1;
    for (size_t i = 0; i < r->ng; i++) {
        if (r->roots[i] == 0)
            continue;
        if (first < 0)
            first = (int)i;
        rep->stats.state_events++;
        if (log_event(r, t, 1, (int)i, r->roots[i], d->events[i].name) != LV_OK)
            return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    lv_event_action a =
        d->on_event ? d->on_event(t, r->x, r->p, r->roots, r->inst) : LV_EVENT_STOP;
    if (a == LV_EVENT_STOP && *action != LV_EVENT_STOP) {
        rep->stop_event = first;
        snprintf(rep->stop_name, sizeof rep->stop_name, "%s",
                 first >= 0 ? d->events[first].name : "event");
    }
    if (a > *action)
        *action = a;
    return LV_OK;
}

/* A crossing the integrator located on an output that is NaN at t, or just after it (x moved
 * on by 1e-6 s along its derivative): not a crossing but the edge of the output's domain (an
 * impact point output where the path stops coming down, docs/models.md), which a root search
 * takes for a sign change. 1 then, with *t_nan where it was NaN. */
static int nan_edge(sim_run *r, double t, size_t index, double *t_nan)
{
    const lv_model_def *d = r->def;
    *t_nan = t;
    if (stop_outputs(r, t, r->x) != 0)
        return 0;
    if (isnan(r->ys[index]))
        return 1;
    const double dt = 1e-6;
    if (d->rhs(t, r->x, r->p, r->xs, r->inst) != 0)
        return 0;
    for (size_t i = 0; i < r->nx; i++)
        r->xdot[i] = r->x[i] + dt * r->xs[i];
    *t_nan = t + dt;
    return stop_outputs(r, t + dt, r->xdot) == 0 && isnan(r->ys[index]);
}

/* The run's stop conditions that hold at t: crossings located by the integrator, then times
 * reached; the first one names the stop. A crossing on an output that turns NaN there is a
 * failure (nan_edge). */
static lv_status stop_conditions(sim_run *r, const lv_sim_settings *s, double t, int state_event,
                                 int time_event, lv_event_action *action, lv_err *err)
{
    lv_sim_report *rep = r->rep;
    for (size_t j = 0; j < r->ns; j++) {
        const stop_ref *sr = &r->stops[j];
        const int hit = sr->is_time ? (time_event && t == sr->value)
                                    : (state_event && r->roots[r->ng + r->nd + sr->root] != 0);
        if (!hit)
            continue;
        double t_nan;
        if (!sr->is_time && sr->kind == LV_VAR_OUTPUT && nan_edge(r, t, sr->index, &t_nan))
            return lv_fail(err, LV_ERR_SOLVER, "model '%s': the end '%s' did not cross %g: its "
                           "variable %s turns NaN at t = %.9g s (undefined from there: an impact "
                           "point output once the path no longer comes down, docs/models.md)",
                           r->def->name, s->stops[j].name, s->stops[j].value,
                           s->stops[j].variable, t_nan);
        const int dir = sr->is_time ? 0 : r->roots[r->ng + r->nd + sr->root];
        if (sr->is_time)
            rep->stats.time_events++;
        else
            rep->stats.state_events++;
        if (log_event(r, t, !sr->is_time, (int)(r->ng + j), dir, s->stops[j].name) != LV_OK)
            return lv_fail(err, LV_ERR_NOMEM, "out of memory");
        if (*action != LV_EVENT_STOP) {
            rep->stop_event = (int)(r->ng + j);
            snprintf(rep->stop_name, sizeof rep->stop_name, "%s", s->stops[j].name);
            *action = LV_EVENT_STOP;
        }
    }
    return LV_OK;
}

/* The model's own time event at t: counted, logged, its handler (none: a restart). */
static lv_status model_time_event(sim_run *r, double t, lv_event_action *action, lv_err *err)
{
    const lv_model_def *d = r->def;
    lv_sim_report *rep = r->rep;
    rep->stats.time_events++;
    const char *tev = d->time_event_name ? d->time_event_name(t, r->p, r->inst) : NULL;
    if (log_event(r, t, 0, -1, 0, tev) != LV_OK)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    /* Without a handler a time event is a kink: restart the integrator. */
    lv_event_action a =
        d->on_time_event ? d->on_time_event(t, r->x, r->p, r->inst) : LV_EVENT_RESTART;
    if (a == LV_EVENT_STOP && *action != LV_EVENT_STOP)
        snprintf(rep->stop_name, sizeof rep->stop_name, "%s",
                 rep->event_log[rep->n_event_log - 1].name);
    if (a > *action)
        *action = a;
    return LV_OK;
}

/* Everything that happens at an event instant t: the row just before, the model's state
 * events, the stop conditions, the model's time event, in that order; a domain left or a
 * non-finite state after the handlers fails the run; a restart; the row just after; the run
 * ends on a stop, else the next time event is scheduled. *done is set when the run ended. */
static lv_status handle_events(lv_sim *S, double t, double t_grid, int state_event,
                               int time_event, int at_start, int *done, lv_err *err)
{
    sim_run *r = &S->r;
    const lv_model_def *d = r->def;
    lv_status st;
    /* just before the event (at the start: the start row is that row) */
    if (!at_start && (st = emit_row(r, t, err)) != LV_OK)
        return st;
    lv_event_action action = LV_EVENT_CONTINUE;
    int domain_left = -1; /* a bound of the domain crossed at t */
    for (size_t i = 0; state_event && i < r->nd; i++)
        if (r->roots[r->ng + i] != 0 && domain_left < 0)
            domain_left = (int)i;
    int model_event = 0;
    for (size_t i = 0; state_event && i < r->ng; i++)
        model_event |= r->roots[i] != 0;
    if (model_event && (st = model_state_events(r, t, &action, err)) != LV_OK)
        return st;
    if ((st = stop_conditions(r, &S->s, t, state_event, time_event, &action, err)) != LV_OK)
        return st;
    if (time_event && t >= r->t_model_te && (st = model_time_event(r, t, &action, err)) != LV_OK)
        return st;
    lv_integ_forget(S->ig); /* a handler ran: the model's mode may differ now */
    /* leaving the domain ends the run as failed, unless one of the model's own ends
     * (an `impact` end at the same instant) ended it */
    if (domain_left >= 0 && action != LV_EVENT_STOP) {
        double qv = NAN;
        if (d->domain_q(t, r->x, r->p, r->q, r->inst) == 0)
            qv = r->q[domain_left];
        return domain_fail(r, (size_t)domain_left, t, qv, 0, err);
    }
    for (size_t i = 0; i < r->nx; i++)
        if (!isfinite(r->x[i]))
            return lv_fail(err, LV_ERR_SOLVER,
                           "model '%s': event handler at t = %.9g s made '%s' = %g", d->name, t,
                           d->states[i].name, r->x[i]);
    if (action == LV_EVENT_RESTART) {
        if ((st = lv_integ_restart(S->ig, t, r->x, err)) != LV_OK)
            return lv_fail_prefix(err, st, "model '%s'", d->name);
        S->tstop_set = NAN;
    }
    if ((st = emit_row(r, t, err)) != LV_OK) /* just after the event */
        return st;
    if (t == t_grid)
        S->k++; /* the event rows stand for this grid point */
    if (action == LV_EVENT_STOP) {
        r->rep->reason = LV_STOP_EVENT;
        S->state = SIM_FINISHED;
        *done = 1;
        return LV_OK;
    }
    double next = next_time_event(r, t);
    if (!(next > t))
        return lv_fail(err, LV_ERR_INPUT, "model '%s': next time event %g is not after t = %g",
                       d->name, next, t);
    S->t_te = next;
    return LV_OK;
}

/* The row of output grid point k at t, within the row limit; then the progress callback and the
 * stop flag may cancel the run. */
static lv_status grid_row(lv_sim *S, double t, lv_err *err)
{
    sim_run *r = &S->r;
    const lv_sim_settings *s = &S->s;
    lv_status st;
    /* grid rows 0 .. k - 1 are written: one more would pass the limit */
    if (s->max_rows > 0.0 && (double)S->k >= s->max_rows) {
        char lim[32];
        lv_fmt_count(s->max_rows, lim, sizeof lim);
        return lv_fail(err, LV_ERR_SOLVER,
                       "model '%s': stopped at t = %.9g s by the row limit: %s output "
                       "rows (max_rows) and no end of the run reached; give it a "
                       "larger output interval, an earlier stop_time or an end that "
                       "fires, or raise the limit (max_rows; lvsim --max-rows)",
                       r->def->name, t, lim);
    }
    if ((st = emit_row(r, t, err)) != LV_OK)
        return st;
    S->k++;
    if ((s->progress != NULL && s->progress(t, s->progress_user) != 0) ||
        (r->stop != NULL && __atomic_load_n(r->stop, __ATOMIC_RELAXED) != 0))
        return lv_fail(err, LV_ERR_CANCELLED, "model '%s': cancelled at t = %.9g s", r->def->name,
                       t);
    return LV_OK;
}

/* Integrates until t_adv, an event that stops the run, or stop_time. Writes the rows of
 * the output grid and of every event instant on the way. With t_adv >= stop_time this is
 * exactly the loop of a whole run: an earlier t_adv only adds an interpolated return of
 * the integrator at t_adv (its steps are the same; a root located inside the step that
 * contains t_adv may move by round-off, as the root search interval is split there). */
static lv_status run_loop(lv_sim *S, double t_adv, lv_err *err)
{
    sim_run *r = &S->r;
    lv_sim_report *rep = r->rep;
    const double tf = S->s.stop_time;
    for (;;) {
        double t, t_grid;
        lv_integ_result res;
        int at_start;
        lv_status st = set_stop_target(S, err);
        if (st != LV_OK)
            return st;
        st = advance_to_next(S, t_adv, &t, &t_grid, &res, &at_start, err);
        S->t = t;
        rep->end_time = t;
        if (st != LV_OK)
            return integration_failed(r, t, st, err);
        /* the progress callback of the rows left out (grid_skipped), once per return */
        if (!at_start && S->r.n_sinks == 0 && t != t_grid && S->s.progress != NULL &&
            S->s.progress(t, S->s.progress_user) != 0)
            return lv_fail(err, LV_ERR_CANCELLED, "model '%s': cancelled at t = %.9g s",
                           r->def->name, t);
        const int state_event = (res == LV_INTEG_ROOT);
        const int time_event = (t >= S->t_te);
        if (state_event || time_event) {
            int done = 0;
            if ((st = handle_events(S, t, t_grid, state_event, time_event, at_start, &done,
                                    err)) != LV_OK)
                return st;
            if (done)
                return LV_OK;
        } else if (t == t_grid && (st = grid_row(S, t, err)) != LV_OK) {
            return st;
        }
        if (t >= tf) {
            rep->reason = LV_STOP_TIME;
            snprintf(rep->stop_name, sizeof rep->stop_name, "stop_time");
            S->state = SIM_FINISHED;
            return LV_OK;
        }
        if (t >= t_adv)
            return LV_OK;
    }
}

/* Every variable's value at the current (t, x): derivatives and outputs are computed. */
static void eval_all(sim_run *r, double t)
{
    r->rep->stats.row_evals++;
    if (r->def->rhs(t, r->x, r->p, r->xdot, r->inst) != 0)
        for (size_t i = 0; i < r->nx; i++)
            r->xdot[i] = NAN;
    if (r->ny > 0 && r->def->outputs_fn(t, r->x, r->p, r->y, r->inst) != 0)
        for (size_t i = 0; i < r->ny; i++)
            r->y[i] = NAN;
}

static void read_finals(sim_run *r, const lv_sim_settings *s, const final_ref *refs, double t,
                        double *out)
{
    if (s->n_final == 0 || out == NULL)
        return;
    eval_all(r, t);
    for (size_t i = 0; i < s->n_final; i++) {
        const final_ref *f = &refs[i];
        if (f->is_time) {
            out[i] = t;
            continue;
        }
        switch (f->kind) {
        case LV_VAR_STATE: out[i] = r->x[f->index]; break;
        case LV_VAR_DERIVATIVE: out[i] = r->xdot[f->index]; break;
        case LV_VAR_PARAMETER: out[i] = r->p[f->index]; break;
        case LV_VAR_OUTPUT: out[i] = r->y[f->index]; break;
        }
    }
}

lv_status lv_sim_create(const lv_model_def *d, void *inst, const lv_sim_settings *s,
                        lv_sim **out, lv_err *err)
{
    double cpu0 = thread_cpu_seconds();
    lv_err local_err;
    if (err == NULL)
        err = &local_err;
    if (out == NULL || s == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_sim_create: NULL argument");
    *out = NULL;
    lv_sim *S = calloc(1, sizeof *S);
    if (S == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    S->s = *s;
    lv_sim_report *rep = &S->rep;
    rep->stop_event = -1;
    rep->reason = LV_STOP_FAILED;
    snprintf(rep->stop_name, sizeof rep->stop_name, "failed");
    rep->end_time = s->start_time;
    S->t = s->start_time;
    S->tstop_set = NAN;
    S->k = 1;

    sim_run *r = &S->r;
    lv_method method;
    lv_status st = lv_model_validate(d, err);
    if (st != LV_OK)
        goto fail;
    if ((st = check_settings(d, s, &method, err)) != LV_OK)
        goto fail;
    if (inst == NULL && d->inst_size > 0) {
        inst = S->own_inst = calloc(1, d->inst_size);
        if (inst == NULL) {
            st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
            goto fail;
        }
    }
    r->def = d;
    r->inst = inst;
    r->rep = rep;
    r->stop = s->stop;
    r->nx = d->n_states;
    r->np = d->n_params;
    r->ny = d->n_outputs;
    r->ng = d->n_events;
    r->nd = d->n_domain;
    rep->n_states = r->nx;
    r->p = calloc(r->np + 1, sizeof *r->p);
    r->x = calloc(r->nx, sizeof *r->x);
    r->xdot = calloc(r->nx, sizeof *r->xdot);
    r->y = calloc(r->ny + 1, sizeof *r->y);
    r->roots = calloc(r->ng + r->nd + s->n_stops + 1, sizeof *r->roots);
    r->g_dir = calloc(r->ng + r->nd + s->n_stops + 1, sizeof *r->g_dir);
    r->q = calloc(r->nd + 1, sizeof *r->q);
    r->ns = s->n_stops;
    r->stops = calloc(r->ns + 1, sizeof *r->stops);
    r->xs = calloc(r->nx + 1, sizeof *r->xs);
    r->ys = calloc(r->ny + 1, sizeof *r->ys);
    r->stop_need = calloc(r->ny + 1, sizeof *r->stop_need);
    r->atol = calloc(r->nx, sizeof *r->atol);
    S->refs = calloc(s->n_final + 1, sizeof *S->refs);
    if (!r->p || !r->x || !r->xdot || !r->y || !r->roots || !r->g_dir || !r->q || !r->atol ||
        !S->refs || !r->stops || !r->xs || !r->ys || !r->stop_need) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto fail;
    }
    if ((st = resolve_finals(d, s, S->refs, err)) != LV_OK)
        goto fail;
    if ((st = resolve_stops(r, s, err)) != LV_OK)
        goto fail;
    if ((st = apply_initial(r, s, err)) != LV_OK)
        goto fail;
    if (d->init != NULL && d->init(s->start_time, r->x, r->p, inst) != 0) {
        const char *why = d->last_error ? d->last_error(inst) : NULL;
        st = lv_fail(err, LV_ERR_INPUT, "model '%s': initialisation failed at t = %g s%s%s",
                     d->name, s->start_time, why && why[0] ? ": " : "", why ? why : "");
        goto fail;
    }
    if (r->nd > 0) { /* the start state must lie in the model's domain */
        /* with the forces of the start, which guards depend on (a flight model's guard of the
         * wind's vertical plane applies while its engines thrust); a right-hand side that
         * fails here fails again at the first step, where the integrator reports it */
        if (d->rhs(s->start_time, r->x, r->p, r->xdot, inst) != 0) {
        }
        if (d->domain_q(s->start_time, r->x, r->p, r->q, inst) != 0) {
            const char *why = d->last_error ? d->last_error(inst) : NULL;
            st = lv_fail(err, LV_ERR_INPUT, "model '%s': the start state cannot be evaluated "
                         "at t = %g s%s%s", d->name, s->start_time, why && why[0] ? ": " : "",
                         why ? why : "");
            goto fail;
        }
        for (size_t i = 0; i < r->nd; i++)
            if (!d->domain[i].from_above && !(r->q[i] >= d->domain[i].lower)) {
                st = domain_fail(r, i, s->start_time, r->q[i], 1, err);
                goto fail;
            }
    }
    if ((st = build_layout(r, err)) != LV_OK)
        goto fail;
    if ((st = open_sinks(r, s, err)) != LV_OK)
        goto fail;
    if ((st = emit_row(r, s->start_time, err)) != LV_OK)
        goto fail;

    if (s->stop_time > s->start_time) {
        S->grid = make_grid(s);
        for (size_t i = 0; i < r->nx; i++)
            r->atol[i] = s->tolerance * d->states[i].nominal;
        if (d->abs_error != NULL) {
            if ((r->rtol_v = malloc(r->nx * sizeof *r->rtol_v)) == NULL) {
                st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
                goto fail;
            }
            /* an absolute state keeps a relative floor of 1e-14 (50 ulps): accuracy below the
             * coordinate's own resolution cannot be asked for (CVODE: "too much accuracy") */
            for (size_t i = 0; i < r->nx; i++)
                r->rtol_v[i] = d->abs_error[i] ? fmin(LV_ABS_RTOL_FLOOR, s->tolerance)
                                               : s->tolerance;
        }
        for (size_t i = 0; i < r->ng; i++)
            r->g_dir[i] = (int)d->events[i].direction;
        for (size_t i = 0; i < r->nd; i++)
            r->g_dir[r->ng + i] = (int)LV_DIR_FALLING;
        for (size_t j = 0; j < r->ns; j++)
            if (!r->stops[j].is_time)
                r->g_dir[r->ng + r->nd + r->stops[j].root] = (int)s->stops[j].direction;
        lv_integ_problem prob = {
            .n = r->nx,
            .n_g = r->ng + r->nd + r->ns_root,
            .g_dir = r->g_dir,
            .rhs = sim_rhs,
            .g = sim_g,
            .user = r,
            .method = method,
            .rtol = s->tolerance,
            .atol = r->atol,
            .rtol_v = r->rtol_v,
            .fixed_step = s->fixed_step > 0.0 ? s->fixed_step : S->grid.dt,
            .max_step = s->max_step_size,
            .max_steps = s->max_steps > 0 ? s->max_steps : LV_DEFAULT_MAX_STEPS,
            .stiff = d->stiff,
            .quad = d->quadrature,
        };
        if ((st = lv_integ_create(&prob, s->start_time, r->x, &S->ig, err)) != LV_OK) {
            lv_fail_prefix(err, st, "model '%s'", d->name);
            goto fail;
        }
        S->t_te = next_time_event(r, S->t);
        if (!(S->t_te > S->t)) {
            st = lv_fail(err, LV_ERR_INPUT, "model '%s': next time event %g is not after t = %g",
                         d->name, S->t_te, S->t);
            goto fail;
        }
        if ((st = probe_start(S, err)) != LV_OK)
            goto fail;
    } else {
        rep->reason = LV_STOP_TIME;
        snprintf(rep->stop_name, sizeof rep->stop_name, "stop_time");
        S->state = SIM_FINISHED;
    }
    S->cpu = thread_cpu_seconds() - cpu0;
    *out = S;
    return LV_OK;
fail:
    /* A simulation that never started: the sinks already open are closed as failed. */
    close_sinks(r, err->msg, NULL);
    lv_sim_free(S);
    return st;
}

lv_status lv_sim_advance(lv_sim *S, double t, lv_err *err)
{
    if (S == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_sim_advance: NULL simulation");
    if (S->state == SIM_FAILED) {
        if (err != NULL)
            *err = S->fail;
        return S->fail_st;
    }
    if (S->state == SIM_FINISHED)
        return LV_OK;
    if (isnan(t))
        return lv_fail(err, LV_ERR_INPUT, "model '%s': advance to NaN", S->r.def->name);
    if (t <= S->t)
        return LV_OK;
    double cpu0 = thread_cpu_seconds();
    lv_err local_err;
    if (err == NULL)
        err = &local_err;
    lv_status st = run_loop(S, t, err);
    S->cpu += thread_cpu_seconds() - cpu0;
    if (st != LV_OK)
        return sim_failed(S, st, err);
    return LV_OK;
}

double lv_sim_time(const lv_sim *S) { return S->t; }

int lv_sim_done(const lv_sim *S) { return S->state != SIM_RUNNING; }

const lv_sim_report *lv_sim_report_get(const lv_sim *S) { return &S->rep; }

/* ---- variables by reference ------------------------------------------------------------ */

lv_status lv_model_vref(const lv_model_def *d, const char *name, lv_vref *ref, lv_err *err)
{
    lv_var_kind kind;
    size_t idx;
    lv_status st = lv_model_find(d, name, &kind, &idx, err);
    if (st != LV_OK)
        return st;
    switch (kind) {
    case LV_VAR_STATE: *ref = (lv_vref)idx; break;
    case LV_VAR_DERIVATIVE: *ref = (lv_vref)(d->n_states + idx); break;
    case LV_VAR_PARAMETER: *ref = (lv_vref)(2 * d->n_states + idx); break;
    case LV_VAR_OUTPUT: *ref = (lv_vref)(2 * d->n_states + d->n_params + idx); break;
    }
    return LV_OK;
}

/* The kind and index a reference stands for, or -1. */
static int vref_split(const sim_run *r, lv_vref ref, lv_var_kind *kind, size_t *idx)
{
    size_t v = (size_t)ref;
    if (v < r->nx) {
        *kind = LV_VAR_STATE;
        *idx = v;
    } else if (v < 2 * r->nx) {
        *kind = LV_VAR_DERIVATIVE;
        *idx = v - r->nx;
    } else if (v < 2 * r->nx + r->np) {
        *kind = LV_VAR_PARAMETER;
        *idx = v - 2 * r->nx;
    } else if (v < 2 * r->nx + r->np + r->ny) {
        *kind = LV_VAR_OUTPUT;
        *idx = v - 2 * r->nx - r->np;
    } else {
        return -1;
    }
    return 0;
}

lv_status lv_sim_get(lv_sim *S, const lv_vref *refs, size_t n, double *values, lv_err *err)
{
    sim_run *r = &S->r;
    if (r->def == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_sim_get: the simulation was not set up");
    int need_eval = 0;
    for (size_t i = 0; i < n; i++) {
        lv_var_kind kind;
        size_t idx;
        if (vref_split(r, refs[i], &kind, &idx) != 0)
            return lv_fail(err, LV_ERR_INPUT, "model '%s': value reference %u out of range",
                           r->def->name, refs[i]);
        need_eval |= kind == LV_VAR_DERIVATIVE || kind == LV_VAR_OUTPUT;
    }
    if (need_eval)
        eval_all(r, S->t);
    for (size_t i = 0; i < n; i++) {
        lv_var_kind kind;
        size_t idx;
        vref_split(r, refs[i], &kind, &idx);
        switch (kind) {
        case LV_VAR_STATE: values[i] = r->x[idx]; break;
        case LV_VAR_DERIVATIVE: values[i] = r->xdot[idx]; break;
        case LV_VAR_PARAMETER: values[i] = r->p[idx]; break;
        case LV_VAR_OUTPUT: values[i] = r->y[idx]; break;
        }
    }
    return LV_OK;
}

lv_status lv_sim_set(lv_sim *S, const lv_vref *refs, size_t n, const double *values, lv_err *err)
{
    lv_err local_err;
    if (err == NULL)
        err = &local_err;
    sim_run *r = &S->r;
    if (r->def == NULL || S->state == SIM_FAILED)
        return lv_fail(err, LV_ERR_INPUT, "lv_sim_set: the simulation %s",
                       r->def == NULL ? "was not set up" : "has failed");
    const char *mn = r->def->name;
    for (size_t i = 0; i < n; i++) {
        lv_var_kind kind;
        size_t idx;
        if (vref_split(r, refs[i], &kind, &idx) != 0)
            return lv_fail(err, LV_ERR_INPUT, "model '%s': value reference %u out of range", mn,
                           refs[i]);
        if (kind != LV_VAR_STATE && kind != LV_VAR_PARAMETER)
            return lv_fail(err, LV_ERR_INPUT, "model '%s': '%s' is %s; only states and "
                           "parameters can be set", mn,
                           kind == LV_VAR_OUTPUT ? r->def->outputs[idx].name
                                                 : r->def->states[idx].name,
                           kind == LV_VAR_OUTPUT ? "an output" : "a derivative");
        if (!isfinite(values[i]))
            return lv_fail(err, LV_ERR_INPUT, "model '%s': value %g for '%s' is not finite", mn,
                           values[i],
                           kind == LV_VAR_STATE ? r->def->states[idx].name
                                                : r->def->params[idx].name);
    }
    for (size_t i = 0; i < n; i++) {
        lv_var_kind kind;
        size_t idx;
        vref_split(r, refs[i], &kind, &idx);
        if (kind == LV_VAR_STATE)
            r->x[idx] = values[i];
        else
            r->p[idx] = values[i];
    }
    /* A changed state or parameter is a discontinuity: the integrator starts afresh here. */
    if (S->ig != NULL && S->state == SIM_RUNNING && n > 0) {
        lv_status st = lv_integ_restart(S->ig, S->t, r->x, err);
        if (st != LV_OK)
            return sim_failed(S, lv_fail_prefix(err, st, "model '%s'", mn), err);
        S->tstop_set = NAN;
    }
    return LV_OK;
}

/* ---- the end -------------------------------------------------------------------------------- */

lv_status lv_sim_finish(lv_sim *S, double *final_values, lv_sim_report *rep_out, lv_err *err)
{
    double cpu0 = thread_cpu_seconds();
    lv_err local_err;
    if (err == NULL)
        err = &local_err;
    sim_run *r = &S->r;
    lv_sim_report *rep = &S->rep;
    lv_status st;
    if (S->state == SIM_RUNNING) /* finishing early: the run ends where it is */
        st = sim_failed(S, lv_fail(err, LV_ERR_INPUT, "model '%s': finished at t = %.9g s "
                                   "before its end (stop time %.9g s)",
                                   r->def->name, S->t, S->s.stop_time), err);
    if (S->ig != NULL) {
        lv_integ_stats is;
        lv_integ_get_stats(S->ig, &is);
        rep->stats.steps = is.steps;
        rep->stats.rhs_evals = is.rhs_evals;
        rep->stats.rhs_evals_steps = is.rhs_step;
        rep->stats.rhs_evals_output = is.rhs_dense;
        rep->stats.jac_evals = is.jac_evals;
        rep->stats.err_test_fails = is.err_test_fails;
        rep->stats.nonlin_fails = is.nonlin_fails;
        rep->stats.g_evals = is.g_evals;
        rep->stats.restarts = is.restarts;
        lv_integ_method_used(S->ig, rep->method_used, sizeof rep->method_used, rep->method_why,
                             sizeof rep->method_why);
    } else { /* stop_time == start_time: nothing integrated */
        snprintf(rep->method_used, sizeof rep->method_used, "%s",
                 S->s.method != NULL ? S->s.method : "dassl");
        snprintf(rep->method_why, sizeof rep->method_why, "no integration (zero length)");
    }
    if (S->state == SIM_FINISHED) {
        read_finals(r, &S->s, S->refs, rep->end_time, final_values);
        st = close_sinks(r, NULL, err);
    } else {
        st = S->fail_st;
        *err = S->fail;
        rep->reason = LV_STOP_FAILED;
        snprintf(rep->stop_name, sizeof rep->stop_name, "failed");
        close_sinks(r, err->msg, NULL);
    }
    S->cpu += thread_cpu_seconds() - cpu0;
    rep->stats.cpu_time = S->cpu;
    if (rep_out != NULL) {
        *rep_out = *rep;
        memset(rep, 0, sizeof *rep); /* the event log now belongs to the caller */
    }
    return st;
}

void lv_sim_free(lv_sim *S)
{
    if (S == NULL)
        return;
    close_sinks(&S->r, "simulation abandoned before it finished", NULL);
    lv_integ_free(S->ig);
    free_run(&S->r);
    free(S->refs);
    free(S->own_inst);
    lv_sim_report_clear(&S->rep);
    free(S);
}

lv_status lv_simulate(const lv_model_def *d, void *inst, const lv_sim_settings *s,
                      double *final_values, lv_sim_report *rep_out, lv_err *err)
{
    double cpu0 = thread_cpu_seconds();
    lv_sim *S = NULL;
    lv_status st = lv_sim_create(d, inst, s, &S, err);
    if (st != LV_OK) {
        if (rep_out != NULL) {
            memset(rep_out, 0, sizeof *rep_out);
            rep_out->stop_event = -1;
            rep_out->reason = LV_STOP_FAILED;
            snprintf(rep_out->stop_name, sizeof rep_out->stop_name, "failed");
            rep_out->end_time = s != NULL ? s->start_time : 0.0;
            rep_out->stats.cpu_time = thread_cpu_seconds() - cpu0;
        }
        return st;
    }
    lv_sim_advance(S, s->stop_time, err);
    st = lv_sim_finish(S, final_values, rep_out, err);
    lv_sim_free(S);
    return st;
}

/* ---- saved states (sim_state.h) -------------------------------------------------------- */

#include "sim/sim_state.h"

struct lv_sim_saved {
    const lv_model_def *def;   /* the model it was taken from (counts checked on restore) */
    double t, t_te, t_model_te;
    long k;
    sim_phase state;
    lv_status fail_st;
    lv_err fail;
    double *x, *p;             /* [nx], [np] */
    unsigned char *inst;       /* [inst_size] */
    lv_sim_report rep;         /* with its own copy of the event log */
};

void lv_sim_saved_free(lv_sim_saved *sv)
{
    if (sv == NULL)
        return;
    free(sv->x);
    free(sv->p);
    free(sv->inst);
    free(sv->rep.event_log);
    free(sv);
}

/* A fresh start of the integrator at the current point (saving, restoring). */
static lv_status sim_restart_here(lv_sim *S, lv_err *err)
{
    if (S->ig == NULL || S->state != SIM_RUNNING)
        return LV_OK;
    lv_status st = lv_integ_restart(S->ig, S->t, S->r.x, err);
    if (st != LV_OK)
        return sim_failed(S, lv_fail_prefix(err, st, "model '%s'", S->r.def->name), err);
    S->tstop_set = NAN;
    return LV_OK;
}

lv_status lv_sim_save(const lv_sim *S, lv_sim_saved **out, lv_err *err)
{
    *out = NULL;
    const sim_run *r = &S->r;
    if (r->def == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_sim_save: the simulation was not set up");
    lv_sim_saved *sv = calloc(1, sizeof *sv);
    if (sv == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    const size_t ni = r->inst != NULL ? r->def->inst_size : 0;
    sv->x = malloc((r->nx + 1) * sizeof *sv->x);
    sv->p = malloc((r->np + 1) * sizeof *sv->p);
    sv->inst = malloc(ni + 1);
    sv->rep = S->rep;
    sv->rep.event_log = malloc((S->rep.n_event_log + 1) * sizeof *sv->rep.event_log);
    if (!sv->x || !sv->p || !sv->inst || !sv->rep.event_log) {
        lv_sim_saved_free(sv);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    sv->def = r->def;
    memcpy(sv->x, r->x, r->nx * sizeof *sv->x);
    memcpy(sv->p, r->p, r->np * sizeof *sv->p);
    if (ni > 0)
        memcpy(sv->inst, r->inst, ni);
    if (S->rep.n_event_log > 0)
        memcpy(sv->rep.event_log, S->rep.event_log,
               S->rep.n_event_log * sizeof *S->rep.event_log);
    sv->t = S->t;
    sv->t_te = S->t_te;
    sv->t_model_te = r->t_model_te;
    sv->k = S->k;
    sv->state = S->state;
    sv->fail_st = S->fail_st;
    sv->fail = S->fail;
    /* nothing of S changes: saving is free of side effects (the integrator goes on as if no
     * state had been taken) */
    *out = sv;
    (void)err;
    return LV_OK;
}

lv_status lv_sim_restore(lv_sim *S, const lv_sim_saved *sv, lv_err *err)
{
    sim_run *r = &S->r;
    if (r->def == NULL || sv == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_sim_restore: no simulation or no saved state");
    if (sv->def->n_states != r->nx || sv->def->n_params != r->np ||
        sv->def->inst_size != r->def->inst_size)
        return lv_fail(err, LV_ERR_INPUT, "model '%s': the saved state is of another model ('%s')",
                       r->def->name, sv->def->name);
    lv_event_record *log = S->rep.event_log;
    if (sv->rep.n_event_log > 0) {
        log = realloc(S->rep.event_log, sv->rep.n_event_log * sizeof *log);
        if (log == NULL)
            return lv_fail(err, LV_ERR_NOMEM, "out of memory");
        memcpy(log, sv->rep.event_log, sv->rep.n_event_log * sizeof *log);
        r->log_cap = sv->rep.n_event_log; /* the buffer's size now */
    }
    S->rep = sv->rep;
    S->rep.event_log = log;
    memcpy(r->x, sv->x, r->nx * sizeof *r->x);
    memcpy(r->p, sv->p, r->np * sizeof *r->p);
    if (r->inst != NULL && r->def->inst_size > 0)
        memcpy(r->inst, sv->inst, r->def->inst_size);
    S->t = sv->t;
    S->t_te = sv->t_te;
    r->t_model_te = sv->t_model_te;
    S->k = sv->k;
    S->state = sv->state;
    S->fail_st = sv->fail_st;
    S->fail = sv->fail;
    r->row[0] = sv->t;
    r->bad_seen = 0;
    r->rhs_rc = 0;
    return sim_restart_here(S, err);
}
