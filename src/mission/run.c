/* run.c - lv_run: one set of values for a mission's parameters and the phases' results.
 *
 * A phase runs as prepare (its model built from the run's values and the stage book, the
 * hand-off from its plan: parameters or the parent's finals, the carried stages' mass, the
 * overrides), lv_simulate, complete (the result, the stage book after the phase). Setting a
 * parameter marks the phases that read it; lv_run_execute simulates those, the phases that
 * never ran or failed, and all their descendants. Independent branches run in parallel
 * threads; a failing phase stops only its descendants. The mission is only read. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "core/names.h"
#include "core/status.h"
#include "core/units.h"
#include "integrate/integrator.h"
#include "io/sink.h"
#include "lvsim/lv_dispersion.h"
#include "lvsim/lv_units.h"
#include "lvsim/lv_io.h"
#include "mission/dispersion.h"
#include "mission/mission_rt.h"
#include "mission/reference.h"

/* ---- the run object ---------------------------------------------------------------------- */

typedef struct run_phase {
    lv_phase_result res;  /* the public view; arrays below */
    double *fvalues;      /* [plan n_final] */
    double *prop_end;     /* [n_stages]: propellant left after the phase, kg */
    double *prop_start;   /* [n_stages]: the book at the phase's start, kg */
    double *dry;          /* [n_stages]: the stages' dry masses in the run it ran with, kg */
    double *set_values;   /* [n_set]: this run's overrides */
    lv_result *rows;      /* in-memory rows, or NULL */
    char *stem;
    char method[2 * LV_EVENT_NAME_MAX + 16]; /* the integration method it ran with; for "auto",
                                               what ran and why: "auto (dop853: not stiff)" */
    lv_handoff_notes notes; /* what its hand-off absorbed (res.absorbed_* point here) */
    const char **labels;  /* [report.n_event_log]: the user's names of its events
                             (res.event_labels; the strings are the mission's) */
    size_t n_iip;         /* the phase's `iip_at:` times */
    const double *iip_t;  /*   (the mission's) */
    lv_iip_sample *iip;   /* [n_iip] its impact point at those times in the last execute */
    lv_ref_drift drift;   /* its drift from its `reference:` in the last execute */
    int has_drift;        /*   computed (a reference, rows kept) */
    lv_ref_row *drift_rows; /* [drift.n_rows] the rows compared, or NULL */
    int dirty;            /* an input changed since the phase last ran */
    int todo;             /* in the current execute: to run */
    int claimed;          /* in the current execute: taken by a worker */
} run_phase;

struct lv_run {
    const lv_mission *m;
    double *vals;         /* [n_slots] */
    run_phase *ph;        /* [n_phases] */
    size_t simulated;     /* phases simulated by the last execute */
    lv_run_tables *tables; /* copies of the dispersed tables with this run's factors, or NULL */
    uint64_t real_seed, real_run; /* the realisation of the turbulence it flies (seed, run):
                                     the turbulence's `seed:` and 0, or a campaign's draw */
    int profiles;         /* 1: flies the dispersed profiles of (real_seed, real_run), a
                             campaign's run (lv_run_disperse); 0: the nominal profiles */
    pthread_mutex_t lock;
    pthread_cond_t cv;
};

/* n samples at times t: not flying (none taken yet). */
static void iip_none(lv_iip_sample *s, const double *t, size_t n)
{
    for (size_t i = 0; s != NULL && i < n; i++)
        s[i] = (lv_iip_sample){t[i], LV_IIP_NOT_FLYING, NAN, NAN, NAN, NAN};
}

static void phase_clear(run_phase *p)
{
    lv_sim_report_clear(&p->res.report);
    lv_result_free(p->rows);
    free(p->stem);
    p->rows = NULL;
    p->stem = NULL;
    p->res.result_stem = NULL;
    p->res.result_formats = 0u;
    p->res.state = LV_PHASE_PENDING;
    p->res.error[0] = '\0';
    p->res.t_start = p->res.t_end = NAN;
    p->res.end_index = -1;
    p->res.end_value = NAN;
    free(p->labels);
    p->labels = NULL;
    p->res.event_labels = NULL;
    p->res.end_label = NULL;
    p->res.n_copied = 0;
    p->res.mass_from_stages = p->res.mass_start = NAN;
    p->notes.n = 0;
    p->res.n_absorbed = 0;
    iip_none(p->iip, p->iip_t, p->n_iip);
    free(p->drift_rows);
    p->drift_rows = NULL;
    p->has_drift = 0;
}

void lv_run_free(lv_run *r)
{
    if (r == NULL)
        return;
    for (size_t k = 0; r->ph != NULL && k < r->m->def->n_phases; k++) {
        run_phase *p = &r->ph[k];
        phase_clear(p);
        free(p->fvalues);
        free(p->prop_end);
        free(p->prop_start);
        free(p->dry);
        free(p->set_values);
        free(p->iip);
    }
    free(r->ph);
    free(r->vals);
    lv_run_tables_free(r->tables);
    pthread_mutex_destroy(&r->lock);
    pthread_cond_destroy(&r->cv);
    free(r);
}

lv_status lv_run_create(const lv_mission *m, lv_run **out, lv_err *err)
{
    if (m == NULL || out == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_run_create: NULL argument");
    *out = NULL;
    const lv_mission_def *d = m->def;
    lv_run *r = calloc(1, sizeof *r);
    if (r == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    pthread_mutex_init(&r->lock, NULL);
    pthread_cond_init(&r->cv, NULL);
    r->m = m;
    r->vals = malloc((d->n_slots + 1) * sizeof *r->vals);
    r->ph = calloc(d->n_phases, sizeof *r->ph);
    if (r->vals == NULL || r->ph == NULL) {
        lv_run_free(r);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    memcpy(r->vals, m->defaults, d->n_slots * sizeof *r->vals);
    r->real_seed = d->env.turb_seed;
    r->real_run = 0;
    for (size_t k = 0; k < d->n_phases; k++) {
        run_phase *p = &r->ph[k];
        const lv_phase_def *ph = &d->phases[k];
        const lv_phase_plan *pl = &m->plan[k];
        p->fvalues = calloc(pl->n_final, sizeof *p->fvalues);
        p->prop_end = calloc(d->n_stages + 1, sizeof *p->prop_end);
        p->prop_start = calloc(d->n_stages + 1, sizeof *p->prop_start);
        p->dry = calloc(d->n_stages + 1, sizeof *p->dry);
        p->set_values = calloc(ph->n_set + 1, sizeof *p->set_values);
        p->n_iip = ph->n_iip_at;
        p->iip_t = ph->iip_at;
        p->iip = calloc(ph->n_iip_at + 1, sizeof *p->iip);
        if (!p->fvalues || !p->prop_end || !p->prop_start || !p->dry || !p->set_values ||
            !p->iip) {
            lv_run_free(r);
            return lv_fail(err, LV_ERR_NOMEM, "out of memory");
        }
        p->res.name = ph->name;
        snprintf(p->method, sizeof p->method, "%s",
                 ph->method ? ph->method : LV_PHASE_METHOD_DEFAULT);
        p->res.method = p->method;
        p->res.n_final = pl->n_final;
        p->res.final_names = (const char *const *)pl->final_names;
        p->res.final_values = p->fvalues;
        p->res.n_event_names = pl->n_events;
        p->res.event_names = (const char *const *)pl->event_names;
        p->res.n_set = ph->n_set;
        p->res.set_names = (const char *const *)ph->set_names;
        p->res.set_values = p->set_values;
        p->res.propellant_end = p->prop_end;
        p->res.propellant_start = p->prop_start;
        p->res.dry_mass = p->dry;
        phase_clear(p);
        p->dirty = 1;
    }
    *out = r;
    return LV_OK;
}

const lv_mission *lv_run_mission(const lv_run *r) { return r->m; }
const double *lv_run_vals(const lv_run *r) { return r->vals; }

/* ---- parameters ----------------------------------------------------------------------------- */

static lv_status set_slot(lv_run *r, size_t i, double v, int deg, lv_err *err)
{
    const lv_mission_def *d = r->m->def;
    const lv_slot_def *sd = &d->slots[i];
    /* in degrees, the value lv_run_get gives back is the value it has (x / LV_DEG * LV_DEG
     * may differ from x in the last bit: a get/set round trip must change nothing) */
    const double x = deg ? (v == r->vals[i] / LV_DEG ? r->vals[i] : v * LV_DEG) : v;
    if (!lv_range_holds(sd->range, x))
        return lv_fail(err, LV_ERR_INPUT, "mission '%s': %s%s = %g %s: must be %s%s%s", d->name,
                       sd->name, deg ? "_deg" : "", v, deg ? "deg" : LV_UNIT_AFTER_NUMBER(sd->unit),
                       r->m->rules[i], !LV_UNIT_ONE(sd->unit) && !deg ? " " : "",
                       deg ? "" : LV_UNIT_AFTER_NUMBER(sd->unit));
    if (memcmp(&x, &r->vals[i], sizeof x) == 0)
        return LV_OK; /* unchanged: nothing to run again */
    r->vals[i] = x;
    size_t *ks = malloc((d->n_phases + 1) * sizeof *ks);
    if (ks == NULL) {
        for (size_t k = 0; k < d->n_phases; k++) /* conservative: everything again */
            r->ph[k].dirty = 1;
        return LV_OK;
    }
    size_t n = lv_mission_slot_phases(r->m, i, ks);
    for (size_t j = 0; j < n; j++)
        r->ph[ks[j]].dirty = 1;
    free(ks);
    return LV_OK;
}

lv_status lv_run_set(lv_run *r, const char *name, double value, lv_err *err)
{
    size_t i;
    int deg;
    lv_status st = lv_mission_param_find(r->m, name, &i, &deg, err);
    return st != LV_OK ? st : set_slot(r, i, value, deg, err);
}

lv_status lv_run_get(const lv_run *r, const char *name, double *value, lv_err *err)
{
    size_t i;
    int deg;
    lv_status st = lv_mission_param_find(r->m, name, &i, &deg, err);
    if (st == LV_OK)
        *value = deg ? r->vals[i] / LV_DEG : r->vals[i];
    return st;
}

lv_status lv_run_set_index(lv_run *r, size_t i, double value, lv_err *err)
{
    if (i >= r->m->def->n_slots)
        return lv_fail(err, LV_ERR_INPUT, "mission '%s': parameter index %zu out of range",
                       r->m->def->name, i);
    return set_slot(r, i, value, 0, err);
}

double lv_run_get_index(const lv_run *r, size_t i)
{
    return i < r->m->def->n_slots ? r->vals[i] : NAN;
}

void lv_run_reset(lv_run *r)
{
    for (size_t i = 0; i < r->m->def->n_slots; i++)
        set_slot(r, i, r->m->defaults[i], 0, NULL);
}

/* ---- one phase: prepare, simulate, complete -------------------------------------------------- */

struct lv_phase_call {
    lv_run *r;
    size_t k;
    lv_phase_model *pm;
    lv_sim_settings s;
    const char **names;  /* hand-off [n_init] */
    double *values;
    double *finals;      /* [n_final] */
    double *prop;        /* [n_stages] the stage book at the phase start */
    double mass_book;    /* kg, the carried stages' mass from the book (NAN for a root) */
    lv_sim_stop *stops;  /* [plan n_stops] the ends on any variable or on time */
    lv_handoff_notes notes; /* what the hand-off absorbed */
    lv_result *rows;
    lv_sink mem;
    lv_iip_sample *iip;  /* [phase's n_iip_at] the impact point at its `iip_at:` times */
};

void lv_phase_call_free(lv_phase_call *c)
{
    if (c == NULL)
        return;
    lv_phase_model_free(c->pm);
    free(c->names);
    free(c->values);
    free(c->finals);
    free(c->prop);
    free(c->stops);
    free(c->iip);
    lv_sink_destroy(&c->mem);
    lv_result_free(c->rows);
    free(c);
}

const lv_model_def *lv_phase_call_model(const lv_phase_call *c) { return c->pm->def; }
void *lv_phase_call_inst(lv_phase_call *c) { return c->pm->inst; }
lv_sim_settings *lv_phase_call_settings(lv_phase_call *c) { return &c->s; }
double *lv_phase_call_finals(lv_phase_call *c) { return c->finals; }

/* Prepares phase k with the run's method/tolerance/grid overrides and rows kept or not. */
static lv_status prepare(lv_run *r, size_t k, const lv_run_options *opt, lv_phase_call **out,
                         lv_err *err)
{
    const lv_mission *m = r->m;
    const lv_mission_def *d = m->def;
    const lv_phase_def *ph = &d->phases[k];
    const lv_phase_plan *pl = &m->plan[k];
    const run_phase *par = ph->parent >= 0 ? &r->ph[ph->parent] : NULL;
    const double *v = r->vals;
    *out = NULL;
    if (par != NULL && par->res.state != LV_PHASE_DONE)
        return lv_fail(err, LV_ERR_INPUT, "phase '%s' needs its parent '%s' to have run", ph->name,
                       d->phases[ph->parent].name);
    lv_phase_call *c = calloc(1, sizeof *c);
    if (c == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    c->r = r;
    c->k = k;
    /* room for a start from the reference (up to 7 start values and the mass appended) */
    c->names = calloc(pl->n_init + 8, sizeof *c->names);
    c->values = calloc(pl->n_init + 8, sizeof *c->values);
    c->finals = calloc(pl->n_final, sizeof *c->finals);
    c->prop = calloc(d->n_stages + 1, sizeof *c->prop);
    c->stops = calloc(pl->n_stops + 1, sizeof *c->stops);
    c->iip = calloc(ph->n_iip_at + 1, sizeof *c->iip);
    if (!c->names || !c->values || !c->finals || !c->prop || !c->stops || !c->iip) {
        lv_phase_call_free(c);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    iip_none(c->iip, ph->iip_at, ph->n_iip_at);
    /* the stage book: what the parent left, or the run's propellant loads */
    for (size_t s = 0; s < d->n_stages; s++)
        c->prop[s] = par ? par->prop_end[s] : v[d->stages[s].propellant_mass];
    /* a start mass of its own (the reference's, a set:) sets the burning stage's propellant */
    lv_status st = lv_phase_start_book(d, k, v, c->prop, err);
    if (st != LV_OK) {
        lv_phase_call_free(c);
        return st;
    }
    const lv_build_ctx bc = {d, &m->env, k, v, c->prop, r->tables, &c->notes};
    st = lv_phase_model_build(&bc, &c->pm, err);
    if (st != LV_OK) {
        lv_phase_call_free(c);
        return lv_fail_prefix(err, st, "%s:%d:%d: phase '%s'", d->path, ph->loc.line,
                              ph->loc.column, ph->name);
    }

    lv_sim_settings *s = &c->s;
    lv_sim_settings_default(s);
    s->start_time = ph->t_start != LV_NO_SLOT ? v[ph->t_start] : (par ? par->res.t_end : 0.0);
    /* a child started from a time-axis reference starts at the reference's first time: not
     * before its parent's end (its bodies would fly back in time: their trajectories and
     * timelines run backwards), at the end when the two differ by round-off */
    if (par != NULL && ph->t_start == LV_NO_SLOT && ph->reference != NULL &&
        !isnan(lv_reference_start_time(ph->reference))) {
        const double t_ref = lv_reference_start_time(ph->reference), te = par->res.t_end;
        if (t_ref < te - 1e-9 * fmax(1.0, fabs(te))) {
            lv_phase_call_free(c);
            return lv_fail(err, LV_ERR_INPUT, "%s:%d:%d: phase '%s': reference: it starts at "
                           "t = %.17g s, before its parent '%s' ended (t = %.17g s): the "
                           "bodies would fly back in time; start the reference at the "
                           "hand-off, or the phase from its parent (start: parent)", d->path,
                           ph->reference->loc.line, ph->reference->loc.column, ph->name,
                           t_ref, d->phases[ph->parent].name, te);
        }
        s->start_time = t_ref > te ? t_ref : te;
    }
    s->stop_time = v[ph->t_stop];
    s->method = opt && opt->method ? opt->method
                                   : (ph->method ? ph->method : LV_PHASE_METHOD_DEFAULT);
    s->tolerance = opt && opt->tolerance != 0.0 ? opt->tolerance : v[ph->tolerance];
    s->number_of_intervals = ph->intervals;
    s->output_interval = v[ph->output_interval];
    s->fixed_step = v[ph->fixed_step];
    if (opt && opt->output_interval > 0.0) {
        s->output_interval = opt->output_interval;
        s->number_of_intervals = 0;
    }
    s->result_file = NULL;
    s->stop = opt ? opt->stop : NULL;
    s->max_rows = opt && opt->max_rows > 0.0 ? opt->max_rows : 0.0;
    c->mass_book = NAN;
    if (par != NULL) {
        c->mass_book = 0.0;
        for (size_t i = 0; i < ph->n_stages; i++)
            c->mass_book += v[d->stages[ph->stages[i]].dry_mass] + c->prop[ph->stages[i]];
    }
    for (size_t i = 0; i < pl->n_init; i++) {
        const lv_init_src *src = &pl->init[i];
        c->names[i] = pl->init_names[i];
        switch (src->kind) {
        case LV_INIT_SLOT: c->values[i] = v[src->index]; break;
        case LV_INIT_PARENT: c->values[i] = par->fvalues[src->index]; break;
        case LV_INIT_MASS: c->values[i] = c->mass_book; break;
        case LV_INIT_START_TIME: c->values[i] = s->start_time; break;
        case LV_INIT_CONVERT: c->values[i] = NAN; break; /* the type's handoff gives it */
        }
    }
    if (par != NULL && ph->type->handoff != NULL &&
        (st = ph->type->handoff(&bc, c->pm, (const char *const *)m->plan[ph->parent].final_names,
                                par->fvalues, m->plan[ph->parent].n_final, c->names, c->values,
                                pl->n_init, err)) != LV_OK) {
        lv_phase_call_free(c);
        return lv_fail_prefix(err, st, "%s:%d:%d: phase '%s'", d->path, ph->loc.line,
                              ph->loc.column, ph->name);
    }
    size_t n_init = pl->n_init;
    if (ph->reference != NULL && ph->reference->start &&
        (st = lv_reference_start(ph->reference, &m->env.planet, s->start_time, par == NULL,
                                 ph->type->mass_state, c->names, c->values, &n_init,
                                 pl->n_init + 8, err)) != LV_OK) {
        lv_phase_call_free(c);
        return lv_fail_prefix(err, st, "%s:%d:%d: phase '%s'", d->path, ph->reference->loc.line,
                              ph->reference->loc.column, ph->name);
    }
    for (size_t i = 0; i < pl->n_init; i++)
        if (pl->init[i].kind == LV_INIT_CONVERT && isnan(c->values[i])) {
            lv_phase_call_free(c);
            return lv_fail(err, LV_ERR_INPUT, "%s:%d:%d: phase '%s': the hand-off from phase "
                           "'%s' gives no value for the state '%s'", d->path, ph->loc.line,
                           ph->loc.column, ph->name, d->phases[ph->parent].name,
                           pl->init_names[i]);
        }
    s->n_initial = n_init;
    s->initial_names = c->names;
    s->initial_values = c->values;
    s->n_final = pl->n_final;
    s->final_names = (const char *const *)pl->final_names;
    lv_phase_stops(d, pl, k, v, s->start_time, c->stops);
    s->n_stops = pl->n_stops;
    s->stops = c->stops;
    if (!(opt && opt->no_rows)) {
        if ((st = lv_sink_memory_create(&c->rows, &c->mem, err)) != LV_OK) {
            lv_phase_call_free(c);
            return st;
        }
        s->n_sinks = 1;
        s->sinks = &c->mem;
    }
    if (!(s->stop_time > s->start_time)) {
        st = lv_fail(err, LV_ERR_INPUT,
                     "%s:%d:%d: phase '%s': stop_time %g s is not after its start %g s (the "
                     "parent '%s' ended then)",
                     d->path, ph->loc.line, ph->loc.column, ph->name, s->stop_time,
                     s->start_time, par ? par->res.name : "-");
        lv_phase_call_free(c);
        return st;
    }
    /* an engine-out the file gives that the phase would never reach (its start known only
     * now: a child's; a root's was checked at load, parse_tree.c). A time a run sets (a
     * dispersion, targeting) beyond the phase's end is a run without the failure
     * (docs/monte-carlo.md), not an error. */
    for (size_t j = 0; j < ph->n_engine_out; j++) {
        const lv_engine_out_def *o = &ph->engine_out[j];
        const double dt = v[o->time];
        if (dt != m->defaults[o->time] || s->start_time + dt < s->stop_time)
            continue;
        const lv_src_loc at = d->slots[o->time].loc.line > 0 ? d->slots[o->time].loc : o->loc;
        st = lv_fail(err, LV_ERR_INPUT,
                     "%s:%d:%d: phase '%s', engine_out: time %g s after the phase's start (at "
                     "t = %g s) is at or after its stop_time %g s: the engine-out would never "
                     "happen",
                     d->path, at.line, at.column, ph->name, dt, s->start_time, s->stop_time);
        lv_phase_call_free(c);
        return st;
    }
    *out = c;
    return LV_OK;
}

const char *lv_phase_state_name(lv_phase_state st)
{
    switch (st) {
    case LV_PHASE_DONE: return "done";
    case LV_PHASE_FAILED: return "failed";
    case LV_PHASE_SKIPPED: return "skipped";
    case LV_PHASE_CRASHED: return "crashed";
    default: return "pending";
    }
}

lv_status lv_run_prepare(lv_run *r, size_t k, lv_phase_call **out, lv_err *err)
{
    if (k >= r->m->def->n_phases)
        return lv_fail(err, LV_ERR_INPUT, "phase index %zu out of range", k);
    lv_status st = lv_run_tables_update(r->m->def, r->m->env.wind, r->vals, r->real_seed, r->real_run,
                                          r->profiles, &r->tables, err);
    if (st == LV_OK && (st = prepare(r, k, NULL, out, err)) == LV_OK && (*out)->notes.crashed) {
        /* a touchdown beyond the landing gear's limits: nothing to fly */
        st = lv_fail(err, LV_ERR_INPUT, "phase '%s': %s at t = %.9g s", r->m->def->phases[k].name,
                     (*out)->notes.why, (*out)->s.start_time);
        lv_phase_call_free(*out);
        *out = NULL;
    }
    return st;
}

/* The user's names (`name:`) of phase k's logged events: the end that ended it (its own
 * name, else the phase's `end_name`) on the event that stopped it, an engine-out's on the time
 * event at its time (start + dt, the sum the engine model schedules). */
static void label_events(const lv_run *r, size_t k, run_phase *p)
{
    const lv_phase_def *ph = &r->m->def->phases[k];
    const lv_sim_report *rep = &p->res.report;
    const int j = p->res.end_index;
    const char *end = j >= 0 ? (ph->ends[j].label ? ph->ends[j].label : ph->end_name) : NULL;
    /* the type's own ends (a roll's stop) take the phase's end_name too, but a crash end (a
     * roll off the runway's end) keeps its own name: a crash is no "wheels stop" */
    int crash = 0;
    for (size_t i = 0; ph->type->crash_ends != NULL && ph->type->crash_ends[i] != NULL; i++)
        crash |= strcmp(ph->type->crash_ends[i], rep->stop_name) == 0;
    for (size_t i = 0; j < 0 && !crash && rep->reason == LV_STOP_EVENT &&
                       ph->type->own_ends != NULL && ph->type->own_ends[i] != NULL; i++)
        if (strcmp(ph->type->own_ends[i], rep->stop_name) == 0)
            end = ph->end_name;
    int any = end != NULL;
    for (size_t i = 0; i < ph->n_engine_out; i++)
        any |= ph->engine_out[i].label != NULL;
    if (!any || rep->n_event_log == 0 || (p->labels = calloc(rep->n_event_log,
                                                             sizeof *p->labels)) == NULL) {
        p->res.end_label = end; /* (out of memory: the end keeps its name, the log none) */
        return;
    }
    p->res.end_label = end;
    for (size_t i = 0; i < rep->n_event_log; i++) {
        const lv_event_record *e = &rep->event_log[i];
        for (size_t o = 0; !e->is_state && o < ph->n_engine_out; o++)
            if (ph->engine_out[o].label != NULL && strstr(e->name, "engine-out") != NULL &&
                e->t == p->res.t_start + r->vals[ph->engine_out[o].time])
                p->labels[i] = ph->engine_out[o].label;
    }
    /* the stopping event: the last one logged at the end time under the end's name */
    for (size_t i = rep->n_event_log; end != NULL && rep->reason == LV_STOP_EVENT && i-- > 0;) {
        const lv_event_record *e = &rep->event_log[i];
        if (e->t == rep->end_time && strcmp(e->name, rep->stop_name) == 0) {
            p->labels[i] = end;
            break;
        }
    }
    p->res.event_labels = p->labels;
}

/* A flown phase that ended by one of its type's crash ends (a roll off the runway's end):
 * crashed, with its rows, files and finals (the run's lock held). */
static void crash_end(lv_run *r, const lv_phase_call *c)
{
    const lv_phase_def *ph = &r->m->def->phases[c->k];
    run_phase *p = &r->ph[c->k];
    const lv_sim_report *rep = &p->res.report;
    if (p->res.state != LV_PHASE_DONE || rep->reason != LV_STOP_EVENT ||
        ph->type->crash_ends == NULL)
        return;
    for (size_t i = 0; ph->type->crash_ends[i] != NULL; i++)
        if (strcmp(ph->type->crash_ends[i], rep->stop_name) == 0) {
            const lv_model_def *md = c->pm->def;
            const char *why = rep->stop_event >= 0 && (size_t)rep->stop_event < md->n_events
                                  ? md->events[rep->stop_event].description
                                  : rep->stop_name;
            p->res.state = LV_PHASE_CRASHED;
            /* the state there in the model's words (a roll: its distance and speed; not the
             * mass, which says nothing of the crash) */
            char state[200] = "";
            size_t used = 0;
            for (size_t f = 0; f < p->res.n_final && used < sizeof state; f++)
                for (size_t v = 0; v < md->n_states && used < sizeof state; v++)
                    if (strcmp(p->res.final_names[f], md->states[v].name) == 0 &&
                        strcmp(md->states[v].unit, "kg") != 0)
                        used += (size_t)snprintf(state + used, sizeof state - used,
                                                 "%s%s = %.6g %s", used ? ", " : "",
                                                 md->states[v].name, p->res.final_values[f],
                                                 md->states[v].unit);
            snprintf(p->res.error, sizeof p->res.error, "phase '%.60s': crashed at t = %.9g s: "
                     "%s: %.400s%s%.200s%s", ph->name, rep->end_time, rep->stop_name, why,
                     state[0] ? " (" : "", state, state[0] ? ")" : "");
            return;
        }
}

/* The phase's result from a finished call (the run's lock is held when workers run). */
static void record(lv_run *r, lv_phase_call *c, lv_status st, const lv_err *sim_err,
                   lv_sim_report *rep)
{
    const lv_mission_def *d = r->m->def;
    const lv_phase_def *ph = &d->phases[c->k];
    const lv_phase_plan *pl = &r->m->plan[c->k];
    run_phase *p = &r->ph[c->k];
    phase_clear(p);
    p->res.state = st == LV_OK ? LV_PHASE_DONE : LV_PHASE_FAILED;
    if (st != LV_OK)
        snprintf(p->res.error, sizeof p->res.error, "phase '%.60s': %.940s", ph->name,
                 sim_err ? sim_err->msg : lv_status_str(st));
    if (rep != NULL) {
        p->res.report = *rep;
        memset(rep, 0, sizeof *rep); /* the event log moves into the result */
    }
    p->res.t_start = c->s.start_time;
    p->res.t_end = p->res.report.end_time;
    p->res.t_stop = c->s.stop_time;
    if (strcasecmp(c->s.method, "auto") != 0 || p->res.report.method_used[0] == '\0')
        snprintf(p->method, sizeof p->method, "%s", c->s.method);
    else /* auto: what ran, and why */
        snprintf(p->method, sizeof p->method, "%s (%s: %s)", c->s.method,
                 p->res.report.method_used, p->res.report.method_why);
    p->res.method = p->method;
    p->res.tolerance = c->s.tolerance;
    p->res.n_copied = pl->n_copied;
    p->res.mass_from_stages = c->mass_book;
    p->notes = c->notes;
    p->res.n_absorbed = p->notes.n;
    p->res.absorbed_names = p->notes.name;
    p->res.absorbed_units = p->notes.unit;
    p->res.absorbed_values = p->notes.value;
    for (size_t i = 0; i < ph->n_set; i++)
        p->set_values[i] = r->vals[ph->set_values[i]];
    if (p->res.report.reason == LV_STOP_EVENT && p->res.report.stop_event >= 0 &&
        (size_t)p->res.report.stop_event < pl->n_events) {
        const size_t ev = (size_t)p->res.report.stop_event;
        int j = ev < pl->n_model_events ? c->pm->event_end[ev]
                                        : (int)pl->stop_end[ev - pl->n_model_events];
        p->res.end_index = j;
        if (j >= 0 && ph->ends[j].value != LV_NO_SLOT)
            p->res.end_value = r->vals[ph->ends[j].value];
    }
    label_events(r, c->k, p);
    memcpy(p->fvalues, c->finals, pl->n_final * sizeof *p->fvalues);
    memcpy(p->iip, c->iip, ph->n_iip_at * sizeof *p->iip);
    p->rows = c->rows;
    c->rows = NULL;
    /* the drift from the phase's reference, at the rows kept */
    p->has_drift = 0;
    if (ph->reference != NULL && p->rows != NULL && lv_result_rows(p->rows) > 0) {
        lv_err e = {LV_OK, ""};
        p->has_drift = lv_reference_drift(ph->reference, &r->m->env.planet, p->rows,
                                          ph->type->mass_state, c->s.start_time, c->s.stop_time,
                                          &p->drift, &p->drift_rows, &e) == LV_OK;
    }
    p->stem = c->s.result_file ? strdup(c->s.result_file) : NULL;
    p->res.result_stem = p->stem;
    p->res.result_formats = p->stem ? c->s.result_formats : 0u;
    /* the mass at the start: the hand-off's last word on the mass state */
    double m0 = NAN;
    for (size_t i = 0; i < c->s.n_initial; i++)
        if (strcmp(c->names[i], ph->type->mass_state) == 0)
            m0 = c->values[i];
    for (size_t i = 0; isnan(m0) && i < c->pm->def->n_states; i++)
        if (strcmp(c->pm->def->states[i].name, ph->type->mass_state) == 0)
            m0 = c->pm->def->states[i].start;
    p->res.mass_start = m0;
    /* the stage book: what the phase burned came out of its bottom stage; the start mass
     * beyond the carried stages is payload */
    memcpy(p->prop_start, c->prop, d->n_stages * sizeof *p->prop_start);
    memcpy(p->prop_end, c->prop, d->n_stages * sizeof *p->prop_end);
    double stages = 0.0;
    for (size_t s = 0; s < d->n_stages; s++)
        p->dry[s] = r->vals[d->stages[s].dry_mass];
    for (size_t i = 0; i < ph->n_stages; i++)
        stages += p->dry[ph->stages[i]] + c->prop[ph->stages[i]];
    p->res.payload = m0 - stages;
    if (st == LV_OK && pl->mass_final != (size_t)-1) {
        const size_t bottom = ph->stages[0];
        const double burned = m0 - c->finals[pl->mass_final];
        if (burned > 0.0)
            p->prop_end[bottom] = fmax(0.0, p->prop_end[bottom] - burned);
    }
    p->dirty = 0;
}

lv_status lv_run_complete(lv_run *r, lv_phase_call *c, lv_status st, const lv_err *sim_err,
                          lv_sim_report *rep, lv_err *err)
{
    if (c == NULL || c->r != r)
        return lv_fail(err, LV_ERR_INPUT, "lv_run_complete: the call is not this run's");
    record(r, c, st, sim_err, rep);
    lv_phase_call_free(c);
    return LV_OK;
}

/* ---- executing the tree ------------------------------------------------------------------------ */

static int mkdir_p(const char *dir)
{
    char buf[4096];
    size_t n = strlen(dir);
    if (n == 0 || n >= sizeof buf)
        return -1;
    memcpy(buf, dir, n + 1);
    for (size_t i = 1; i <= n; i++) {
        if (buf[i] == '/' || buf[i] == '\0') {
            char ch = buf[i];
            buf[i] = '\0';
            if (mkdir(buf, 0777) != 0 && errno != EEXIST)
                return -1;
            buf[i] = ch;
        }
    }
    return 0;
}

typedef struct progress_ctx {
    const lv_run *r;
    size_t k;
    const lv_run_options *opt;
} progress_ctx;

static int stop_requested(const lv_run_options *opt)
{
    return opt && opt->stop && __atomic_load_n(opt->stop, __ATOMIC_RELAXED) != 0;
}

static int progress_thunk(double t, void *user)
{
    const progress_ctx *pc = user;
    if (stop_requested(pc->opt))
        return 1;
    return pc->opt->progress ? pc->opt->progress(pc->r, pc->k, t, pc->opt->user) : 0;
}

/* lv_simulate with stops at the phase's `iip_at:` times: the integrator is advanced to each
 * time t inside the phase (lv_sim_advance: its own interpolation; the steps, rows and finals
 * are those of lv_simulate) and the iip_* outputs are evaluated at the state there. A time
 * before the start, after an end or the stop time, or after a failure is not flown. */
static lv_status simulate_iip(lv_phase_call *c, const lv_phase_def *ph, lv_sim_report *rep,
                              lv_err *err)
{
    const lv_model_def *md = c->pm->def;
    lv_vref ref[LV_IIP_N_OUT];
    for (size_t j = 0; j < LV_IIP_N_OUT; j++) {
        lv_status st = lv_model_vref(md, lv_iip_out_names[j], &ref[j], err);
        if (st != LV_OK) { /* refused when the mission was loaded (mission.c) */
            memset(rep, 0, sizeof *rep);
            rep->stop_event = -1;
            rep->reason = LV_STOP_FAILED;
            snprintf(rep->stop_name, sizeof rep->stop_name, "failed");
            rep->end_time = c->s.start_time;
            return st;
        }
    }
    lv_sim *sim = NULL;
    lv_status st = lv_sim_create(md, c->pm->inst, &c->s, &sim, err);
    if (st != LV_OK) { /* the report lv_simulate gives a run that did not start */
        memset(rep, 0, sizeof *rep);
        rep->stop_event = -1;
        rep->reason = LV_STOP_FAILED;
        snprintf(rep->stop_name, sizeof rep->stop_name, "failed");
        rep->end_time = c->s.start_time;
        return st;
    }
    for (size_t i = 0; i < ph->n_iip_at && st == LV_OK; i++) {
        const double t = ph->iip_at[i];
        if (t < c->s.start_time || t > c->s.stop_time)
            continue;
        if ((st = lv_sim_advance(sim, t, err)) != LV_OK)
            break;
        if (lv_sim_time(sim) != t) /* ended before t */
            break;
        double y[LV_IIP_N_OUT];
        if ((st = lv_sim_get(sim, ref, LV_IIP_N_OUT, y, err)) != LV_OK)
            break;
        lv_iip_sample *o = &c->iip[i];
        o->state = isnan(y[0]) || isnan(y[1]) ? LV_IIP_IN_ORBIT : LV_IIP_IMPACT;
        if (o->state == LV_IIP_IMPACT) {
            o->lat = y[0];
            o->lon = y[1];
            o->tof = y[2];
            o->range = y[3];
        }
    }
    if (st == LV_OK)
        lv_sim_advance(sim, c->s.stop_time, err);
    /* a failure: lv_sim_finish gives it back with the report */
    st = lv_sim_finish(sim, c->finals, rep, err);
    lv_sim_free(sim);
    return st;
}

/* Runs phase k: prepare, simulate, then (under the lock) record. Called without the lock. */

static lv_status run_one(lv_run *r, size_t k, const lv_run_options *opt, lv_err *err)
{
    const lv_phase_def *ph = &r->m->def->phases[k];
    lv_phase_call *c = NULL;
    /* a child's rows are known once its parent has ended: refused now beyond the limit */
    lv_status st = stop_requested(opt) ? lv_fail(err, LV_ERR_CANCELLED, "stopped before it began")
                                       : lv_run_check_phase_output(r, k, opt, err);
    if (st == LV_OK)
        st = prepare(r, k, opt, &c, err);
    if (st != LV_OK) {
        pthread_mutex_lock(&r->lock);
        run_phase *p = &r->ph[k];
        phase_clear(p);
        p->res.state = LV_PHASE_FAILED;
        char named[80], numbered[96];
        snprintf(named, sizeof named, "phase '%.60s'", ph->name);
        snprintf(numbered, sizeof numbered, "phase %zu '%.60s'", k + 1, ph->name);
        if (strstr(err->msg, named) != NULL || strstr(err->msg, numbered) != NULL)
            /* "FILE:L:C: phase 'P': ..." or "phase 3 'P' would ..." names it already */
            snprintf(p->res.error, sizeof p->res.error, "%.1000s", err->msg);
        else
            snprintf(p->res.error, sizeof p->res.error, "%s: %.940s", named, err->msg);
        p->dirty = 0;
        pthread_mutex_unlock(&r->lock);
        return st;
    }
    if (c->notes.crashed) { /* a touchdown beyond the landing gear's limits: not flown */
        lv_err why;
        snprintf(why.msg, sizeof why.msg, "%.900s at t = %.9g s", c->notes.why, c->s.start_time);
        pthread_mutex_lock(&r->lock);
        record(r, c, LV_ERR_INPUT, &why, NULL); /* the hand-off's notes, no finals */
        run_phase *p = &r->ph[k];
        p->res.state = LV_PHASE_CRASHED;
        p->res.t_end = p->res.t_start;
        pthread_mutex_unlock(&r->lock);
        lv_phase_call_free(c);
        return LV_OK;
    }
    char stem[4096];
    const unsigned formats = opt ? opt->result_formats : 0u;
    if (opt && opt->outdir && !(formats & LV_RUN_NO_PHASE_FILES)) {
        snprintf(stem, sizeof stem, "%s/phase_%zu_%s", opt->outdir, k + 1, ph->name);
        c->s.result_file = stem;
        if (formats & lv_result_format_mask())
            c->s.result_formats = formats & lv_result_format_mask();
    }
    progress_ctx pc = {r, k, opt};
    if (opt && (opt->progress || opt->stop)) {
        c->s.progress = progress_thunk;
        c->s.progress_user = &pc;
    }
    lv_sim_report rep;
    st = ph->n_iip_at > 0 ? simulate_iip(c, ph, &rep, err)
                          : lv_simulate(c->pm->def, c->pm->inst, &c->s, c->finals, &rep, err);
    if (st != LV_OK && err != NULL)
        lv_drop_model_prefix(err, ph->name);
    pthread_mutex_lock(&r->lock);
    record(r, c, st, err, &rep);
    crash_end(r, c);
    pthread_mutex_unlock(&r->lock);
    lv_phase_call_free(c);
    if (st != LV_OK)
        lv_fail_prefix(err, st, "phase '%s'", ph->name);
    return st;
}

typedef struct worker_ctx {
    lv_run *r;
    const lv_run_options *opt;
    int any_failed, cancelled;
} worker_ctx;

/* With the lock held: the next phase that can run, marking skipped ones on the way; -1 when
 * none is ready now. Phases are taken in run order among those ready. */
static long next_ready(lv_run *r, int *pending)
{
    const lv_mission_def *d = r->m->def;
    *pending = 0;
    for (size_t k = 0; k < d->n_phases; k++) {
        run_phase *p = &r->ph[k];
        if (!p->todo || p->claimed || p->res.state != LV_PHASE_PENDING)
            continue;
        int par = d->phases[k].parent;
        lv_phase_state ps = par < 0 ? LV_PHASE_DONE : r->ph[par].res.state;
        if (ps == LV_PHASE_FAILED || ps == LV_PHASE_SKIPPED || ps == LV_PHASE_CRASHED) {
            p->res.state = LV_PHASE_SKIPPED;
            p->dirty = 0;
            snprintf(p->res.error, sizeof p->res.error, "phase '%s' not run: its parent '%s' %s",
                     p->res.name, d->phases[par].name,
                     ps == LV_PHASE_FAILED    ? "failed"
                     : ps == LV_PHASE_CRASHED ? "crashed"
                                              : "was not run");
            k = (size_t)-1; /* a new skip can skip more: rescan */
            continue;
        }
        if (ps == LV_PHASE_DONE) /* a parent to run is PENDING until it is done */
            return (long)k;
        *pending = 1;
    }
    return -1;
}

static void *worker(void *arg)
{
    worker_ctx *w = arg;
    lv_run *r = w->r;
    pthread_mutex_lock(&r->lock);
    for (;;) {
        int pending;
        long k = next_ready(r, &pending);
        if (k < 0) {
            if (!pending)
                break; /* nothing left that this worker could ever run */
            pthread_cond_wait(&r->cv, &r->lock); /* a running parent will wake us */
            continue;
        }
        r->ph[k].claimed = 1;
        r->simulated++;
        pthread_mutex_unlock(&r->lock);
        lv_err err;
        lv_status st = run_one(r, (size_t)k, w->opt, &err);
        pthread_mutex_lock(&r->lock);
        if (st != LV_OK) {
            w->any_failed = 1;
            w->cancelled |= st == LV_ERR_CANCELLED;
        }
        if (w->opt && w->opt->on_phase)
            w->opt->on_phase(r, (size_t)k, &r->ph[k].res, w->opt->user);
        pthread_cond_broadcast(&r->cv);
    }
    pthread_cond_broadcast(&r->cv);
    pthread_mutex_unlock(&r->lock);
    return NULL;
}

/* The options that override every phase's settings: a value out of range is refused, never
 * replaced by the phases' own (only 0 / NULL mean "each phase's own"). */
static lv_status check_options(const lv_run_options *opt, lv_err *err)
{
    if (opt == NULL)
        return LV_OK;
    if (opt->tolerance != 0.0 &&
        !(opt->tolerance >= LV_TOLERANCE_MIN && opt->tolerance <= LV_TOLERANCE_MAX))
        return lv_fail(err, LV_ERR_INPUT, "run options: tolerance must be >= %g and <= %g, or 0 "
                       "for each phase's own (got %g)", LV_TOLERANCE_MIN, LV_TOLERANCE_MAX,
                       opt->tolerance);
    if (!(opt->output_interval >= 0.0) || !isfinite(opt->output_interval))
        return lv_fail(err, LV_ERR_INPUT, "run options: output_interval must be > 0 s, or 0 for "
                       "each phase's own grid (got %g)", opt->output_interval);
    if (opt->threads < 0)
        return lv_fail(err, LV_ERR_INPUT, "run options: threads must be >= 0 (0: 2), got %d",
                       opt->threads);
    if (!(opt->max_rows >= 0.0))
        return lv_fail(err, LV_ERR_INPUT, "run options: max_rows must be >= 0 (0: no limit), "
                       "got %g", opt->max_rows);
    if (opt->method != NULL) {
        lv_method mth;
        if (lv_method_parse(opt->method, &mth, err) != LV_OK)
            return lv_fail_prefix(err, LV_ERR_INPUT, "run options");
    }
    return LV_OK;
}

lv_status lv_run_execute(lv_run *r, const lv_run_options *opt, lv_err *err)
{
    const lv_mission_def *d = r->m->def;
    lv_status ost = check_options(opt, err);
    if (ost != LV_OK)
        return ost;
    lv_status cst = lv_run_check_output(r, opt, err); /* nothing runs past the limit */
    if (cst != LV_OK)
        return cst;
    if (opt && opt->outdir && mkdir_p(opt->outdir) != 0)
        return lv_fail(err, LV_ERR_IO, "cannot create output directory '%s': %s", opt->outdir,
                       LV_STRERROR(errno));
    /* the dispersed tables with this run's factors (phase builds only read them) */
    lv_status tst = lv_run_tables_update(d, r->m->env.wind, r->vals, r->real_seed, r->real_run,
                                           r->profiles, &r->tables, err);
    if (tst != LV_OK)
        return tst;
    /* what runs: changed, never run, failed, skipped, and every descendant of those */
    r->simulated = 0;
    unsigned char *need = NULL; /* opt->want and their ancestors */
    if (opt && opt->want && (need = calloc(d->n_phases, 1)) != NULL)
        for (size_t k = 0; k < d->n_phases; k++)
            for (int j = opt->want[k] ? (int)k : -1; j >= 0 && !need[j]; j = d->phases[j].parent)
                need[j] = 1;
    for (size_t k = 0; k < d->n_phases; k++) {
        run_phase *p = &r->ph[k];
        const int par = d->phases[k].parent;
        p->claimed = 0;
        p->todo = p->dirty || p->res.state != LV_PHASE_DONE ||
                  (par >= 0 && (r->ph[par].todo || r->ph[par].res.state != LV_PHASE_DONE));
        if (p->todo)
            phase_clear(p);
        if (p->todo && need != NULL && !need[k]) { /* not wanted: pending (never run) */
            p->todo = 0;
            p->dirty = 1;
        }
    }
    free(need);
    int threads = opt && opt->threads > 0 ? opt->threads : 2;
    if (threads > 16)
        threads = 16;
    worker_ctx w = {r, opt, 0, 0};
    pthread_t tid[16];
    int started = 0;
    for (int i = 1; i < threads; i++)
        if (pthread_create(&tid[started], NULL, worker, &w) == 0)
            started++;
    worker(&w);
    for (int i = 0; i < started; i++)
        pthread_join(tid[i], NULL);
    size_t failed = 0, skipped = 0;
    for (size_t k = 0; k < d->n_phases; k++) {
        failed += r->ph[k].res.state == LV_PHASE_FAILED;
        skipped += r->ph[k].res.state == LV_PHASE_SKIPPED;
        r->ph[k].todo = 0;
    }
    if (failed > 0)
        return lv_fail(err, w.cancelled ? LV_ERR_CANCELLED : LV_ERR_SOLVER,
                       "mission '%s': %zu phase(s) %s, %zu not run", d->name, failed,
                       w.cancelled ? "cancelled or failed" : "failed", skipped);
    return LV_OK;
}

size_t lv_run_simulated(const lv_run *r) { return r->simulated; }

lv_status lv_run_invalidate(lv_run *r, size_t k, lv_err *err)
{
    const size_t n = r->m->def->n_phases;
    if (k == LV_RUN_ALL_PHASES) {
        for (size_t j = 0; j < n; j++)
            r->ph[j].dirty = 1;
        return LV_OK;
    }
    if (k >= n)
        return lv_fail(err, LV_ERR_INPUT, "mission '%s': phase index %zu out of range (0..%zu)",
                       r->m->def->name, k, n - 1);
    r->ph[k].dirty = 1;
    return LV_OK;
}

int lv_run_stale(const lv_run *r, size_t k)
{
    const lv_mission_def *d = r->m->def;
    if (k >= d->n_phases)
        return 0;
    for (int j = (int)k; j >= 0; j = d->phases[j].parent)
        if (r->ph[j].dirty || r->ph[j].res.state == LV_PHASE_PENDING)
            return 1;
    return 0;
}

/* ---- results ------------------------------------------------------------------------------------- */

const lv_phase_result *lv_run_result(const lv_run *r, size_t k)
{
    return k < r->m->def->n_phases ? &r->ph[k].res : NULL;
}

const lv_result *lv_run_rows(const lv_run *r, size_t k)
{
    return k < r->m->def->n_phases ? r->ph[k].rows : NULL;
}

int lv_mission_phase_has_reference(const lv_mission *m, size_t k)
{
    return m != NULL && k < m->def->n_phases && m->def->phases[k].reference != NULL;
}

lv_status lv_run_reference_drift(const lv_run *r, size_t k, lv_ref_drift *out, lv_err *err)
{
    if (r == NULL || out == NULL || k >= r->m->def->n_phases)
        return lv_fail(err, LV_ERR_INPUT, "lv_run_reference_drift: phase index %zu out of range",
                       k);
    const lv_phase_def *ph = &r->m->def->phases[k];
    if (ph->reference == NULL)
        return lv_fail(err, LV_ERR_NOTFOUND, "phase '%s' has no reference", ph->name);
    if (!r->ph[k].has_drift)
        return lv_fail(err, LV_ERR_NOTFOUND, "phase '%s': no drift from its reference (not run, "
                       "or run without rows)", ph->name);
    *out = r->ph[k].drift;
    return LV_OK;
}

lv_status lv_run_reference_rows(const lv_run *r, size_t k, const lv_ref_row **rows, size_t *n,
                                lv_err *err)
{
    lv_ref_drift d;
    lv_status st = lv_run_reference_drift(r, k, &d, err);
    if (st != LV_OK)
        return st;
    *rows = r->ph[k].drift_rows;
    *n = d.n_rows;
    return LV_OK;
}

lv_status lv_run_iip(const lv_run *r, size_t k, size_t i, lv_iip_sample *out, lv_err *err)
{
    if (r == NULL || out == NULL || k >= r->m->def->n_phases)
        return lv_fail(err, LV_ERR_INPUT, "lv_run_iip: phase index %zu out of range", k);
    const run_phase *p = &r->ph[k];
    if (i >= p->n_iip)
        return lv_fail(err, LV_ERR_INPUT, "lv_run_iip: phase '%s' lists %zu iip_at time%s, "
                       "index %zu asked", p->res.name, p->n_iip, p->n_iip == 1 ? "" : "s", i);
    *out = p->iip[i];
    return LV_OK;
}

lv_status lv_run_final(const lv_run *r, size_t k, const char *name, double *value, lv_err *err)
{
    if (k >= r->m->def->n_phases)
        return lv_fail(err, LV_ERR_INPUT, "phase index %zu out of range", k);
    const run_phase *p = &r->ph[k];
    if (p->res.state != LV_PHASE_DONE)
        return lv_fail(err, LV_ERR_INPUT, "phase '%s' has not run successfully", p->res.name);
    for (size_t i = 0; i < p->res.n_final; i++)
        if (strcmp(p->res.final_names[i], name) == 0) {
            *value = p->fvalues[i];
            return LV_OK;
        }
    lv_suggest sg;
    lv_suggest_init(&sg, name);
    for (size_t i = 0; i < p->res.n_final; i++)
        lv_suggest_add(&sg, p->res.final_names[i]);
    char hint[160];
    lv_suggest_text(&sg, hint, sizeof hint);
    return lv_fail(err, LV_ERR_NOTFOUND, "phase '%s' has no final value '%s'%s", p->res.name,
                   name, hint);
}

/* ---- bodies ---------------------------------------------------------------------------------------- */

size_t lv_run_body_phases(const lv_run *r, size_t s, size_t *out)
{
    const lv_mission_def *d = r->m->def;
    size_t n = 0;
    for (size_t k = 0; k < d->n_phases; k++) {
        const lv_phase_result *res = &r->ph[k].res;
        /* flown: done, or crashed by a crash end (its rows complete; a crash at the hand-off
         * is not flown) */
        const int flown = res->state == LV_PHASE_DONE ||
                          (res->state == LV_PHASE_CRASHED && r->ph[k].rows != NULL &&
                           lv_result_rows(r->ph[k].rows) > 0);
        if (!flown || !lv_mission_phase_has_stage(d, k, s))
            continue;
        size_t pos = n++; /* insertion by start time: the path is short */
        while (pos > 0 && r->ph[out[pos - 1]].res.t_start > res->t_start) {
            out[pos] = out[pos - 1];
            pos--;
        }
        out[pos] = k;
    }
    return n;
}

/* Mass of stage s in phase k when the body's mass is m_body: the bottom stage is the body's
 * mass minus the stages above it; an upper stage keeps its dry mass plus its propellant at the
 * phase start. */
static double stage_mass(const lv_run *r, size_t k, size_t s, double m_body)
{
    const lv_mission_def *d = r->m->def;
    const lv_phase_def *ph = &d->phases[k];
    const double *prop0 = ph->parent >= 0 ? r->ph[ph->parent].prop_end : NULL;
    double upper = 0.0, own = NAN;
    for (size_t i = 0; i < ph->n_stages; i++) {
        size_t si = ph->stages[i];
        double mi = r->vals[d->stages[si].dry_mass] +
                    (prop0 ? prop0[si] : r->vals[d->stages[si].propellant_mass]);
        if (i > 0)
            upper += mi;
        if (si == s)
            own = mi;
    }
    return ph->stages[0] == s ? m_body - upper : own;
}

/* One block: the struct, then names, units, values and phase indices. */
typedef struct body_block {
    lv_body_traj pub;
    const char *names[64];
    const char *units[64];
} body_block;

void lv_body_traj_free(lv_body_traj *b)
{
    if (b == NULL)
        return;
    free((void *)b->values);
    free((void *)b->phase);
    free(b);
}

lv_status lv_run_body_trajectory(const lv_run *r, size_t s, lv_body_traj **out, lv_err *err)
{
    const lv_mission_def *d = r->m->def;
    *out = NULL;
    if (s >= d->n_stages)
        return lv_fail(err, LV_ERR_INPUT, "stage index %zu out of range", s);
    size_t *ks = calloc(d->n_phases + 1, sizeof *ks);
    body_block *b = calloc(1, sizeof *b);
    if (ks == NULL || b == NULL) {
        free(ks);
        free(b);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    const size_t n = lv_run_body_phases(r, s, ks);
    /* columns: time, the first phase's type's sourced columns, stage_mass, the computed ones */
    const lv_phase_type *type = n > 0 ? d->phases[ks[0]].type : NULL;
    size_t nc = 0, n_src = 0;
    b->names[nc] = "time";
    b->units[nc++] = "s";
    for (size_t c = 0; type && c < type->n_traj && nc < 62; c++)
        if (type->traj[c].source != NULL) {
            b->names[nc] = type->traj[c].name;
            b->units[nc++] = type->traj[c].unit;
            n_src++;
        }
    const size_t c_stage = nc;
    b->names[nc] = "stage_mass";
    b->units[nc++] = "kg";
    for (size_t c = 0; type && c < type->n_traj && nc < 63; c++)
        if (type->traj[c].source == NULL) {
            b->names[nc] = type->traj[c].name;
            b->units[nc++] = type->traj[c].unit;
        }
    size_t rows = 0;
    for (size_t i = 0; i < n; i++)
        rows += r->ph[ks[i]].rows ? lv_result_rows(r->ph[ks[i]].rows) : 0;
    double *v = malloc((rows * nc + 1) * sizeof *v);
    size_t *phase = malloc((rows + 1) * sizeof *phase);
    double row[64];
    if (v == NULL || phase == NULL) {
        free(v);
        free(phase);
        free(ks);
        free(b);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    size_t at = 0;
    for (size_t i = 0; i < n; i++) {
        const size_t k = ks[i];
        const lv_result *res = r->ph[k].rows;
        if (res == NULL)
            continue;
        const lv_phase_type *t = d->phases[k].type;
        size_t idx[64], ct = 0, cm = (size_t)-1;
        int have[64];
        lv_result_column(res, "time", &ct, NULL);
        size_t q = 0;
        for (size_t c = 0; c < type->n_traj; c++) {
            if (type->traj[c].source == NULL)
                continue;
            have[q] = lv_result_column(res, type->traj[c].source, &idx[q], NULL) == LV_OK;
            if (strcmp(type->traj[c].source, t->mass_state) == 0 && have[q])
                cm = idx[q];
            q++;
        }
        for (size_t j = 0; j < lv_result_rows(res); j++) {
            row[0] = lv_result_value(res, j, ct);
            for (size_t c = 0; c < n_src; c++)
                row[1 + c] = have[c] ? lv_result_value(res, j, idx[c]) : NAN;
            row[c_stage] = cm != (size_t)-1 ? stage_mass(r, k, s, lv_result_value(res, j, cm))
                                            : NAN;
            if (nc > c_stage + 1) {
                /* the type's extras read its full traj row: sourced columns in its order */
                double trow[64];
                size_t sc = 0, ec = 0;
                for (size_t c = 0; c < type->n_traj; c++)
                    trow[c] = type->traj[c].source ? row[1 + sc++] : NAN;
                if (t == type && type->traj_extra != NULL)
                    type->traj_extra(d, trow);
                for (size_t c = 0; c < type->n_traj; c++)
                    if (type->traj[c].source == NULL)
                        row[c_stage + 1 + ec++] = t == type ? trow[c] : NAN;
            }
            memcpy(v + at * nc, row, nc * sizeof *v);
            phase[at++] = k;
        }
    }
    free(ks);
    b->pub = (lv_body_traj){d->stages[s].name, at, nc, b->names, b->units, v, phase};
    *out = &b->pub;
    return LV_OK;
}

/* ---- dispersions (lv_dispersion.h) ------------------------------------------------------ */

lv_status lv_run_disperse(lv_run *r, uint64_t seed, uint64_t run, double *values, lv_err *err)
{
    const lv_mission *m = r->m;
    const lv_disp_def *dd = m->def->disp;
    const int prof = dd != NULL && dd->n_prof > 0;
    if ((m->def->env.turbulent || prof) &&
        (seed != r->real_seed || run != r->real_run || r->profiles != prof)) {
        r->real_seed = seed; /* the run's own realisation of the turbulence and of the */
        r->real_run = run;   /* dispersed profiles: every phase may fly through them */
        r->profiles = prof;
        lv_run_invalidate(r, LV_RUN_ALL_PHASES, NULL);
    }
    if (dd == NULL)
        return LV_OK;
    double buf[256], *v = values != NULL ? values : dd->n <= 256 ? buf : NULL;
    if (v == NULL && (v = malloc(dd->n * sizeof *v)) == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    lv_mission_disp_draw(m, seed, run, v);
    lv_status st = LV_OK;
    for (size_t j = 0; j < dd->n && st == LV_OK; j++)
        st = lv_run_set_index(r, dd->p[j].slot, dd->p[j].deg ? v[j] * LV_DEG : v[j], err);
    /* values each within its range may still make a layer that cannot be drawn */
    if (st == LV_OK)
        st = lv_run_disturbance_check(m->def, r->vals, err);
    if (st != LV_OK)
        lv_fail_prefix(err, st, "run %llu: dispersion", (unsigned long long)run);
    if (v != values && v != buf)
        free(v);
    return st;
}
