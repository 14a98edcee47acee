/* mission.c - lv_mission: a mission file loaded once, immutable afterwards. Parses and validates
 * the definition (parse.c), builds the environment every phase shares (planet, gravity,
 * atmosphere, wind: env.c), builds each phase's model once with the file's values to check it
 * and to resolve its plan (the hand-off's names to indices, the names of its finals and
 * events), and answers questions about the mission and its parameters (slots, mission.h). */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/names.h"
#include "core/status.h"
#include "core/table_unit.h"
#include "mission/mission_rt.h"
#include "mission/reference.h"
#include "mission/ocp_def.h"
#include "mission/targeting_def.h"
#include "lvsim/lv_units.h"

/* ---- plans ------------------------------------------------------------------------------- */

int lv_mission_phase_has_stage(const lv_mission_def *d, size_t k, size_t s)
{
    const lv_phase_def *ph = &d->phases[k];
    for (size_t i = 0; i < ph->n_stages; i++)
        if (ph->stages[i] == s)
            return 1;
    return 0;
}

static void plan_clear(lv_phase_plan *p)
{
    for (size_t i = 0; i < p->n_final; i++)
        free(p->final_names[i]);
    free(p->final_names);
    for (size_t i = 0; i < p->n_events; i++)
        free(p->event_names[i]);
    free(p->event_names);
    free(p->stop_end);
    free(p->init_names);
    free(p->init);
    memset(p, 0, sizeof *p);
}

static int model_has(const lv_model_def *md, const char *name)
{
    lv_var_kind kind;
    size_t idx;
    return lv_model_find(md, name, &kind, &idx, NULL) == LV_OK;
}

/* A phase of type t may start from a phase of type p: the same type, or one t lists in its
 * from_types (phase_type.h). */
static int type_accepts(const lv_phase_type *t, const lv_phase_type *p)
{
    for (size_t i = 0; t->from_types != NULL && t->from_types[i] != NULL; i++)
        if (strcmp(t->from_types[i], p->name) == 0)
            return 1;
    return 0;
}

/* Phase k's plan from its model `md` (built with the file's values) and its parent's plan. */
static lv_status make_plan(const lv_mission *m, size_t k, const lv_model_def *md,
                           lv_phase_plan *p, lv_err *err)
{
    const lv_mission_def *d = m->def;
    const lv_phase_def *ph = &d->phases[k];
    p->n_states = md->n_states;
    p->n_final = 1 + md->n_states + md->n_outputs;
    p->n_model_events = md->n_events;
    for (size_t j = 0; j < ph->n_ends; j++)
        p->n_stops += ph->ends[j].kind == LV_END_VAR || ph->ends[j].kind == LV_END_TIME;
    p->n_events = md->n_events + p->n_stops;
    p->stop_end = calloc(p->n_stops + 1, sizeof *p->stop_end);
    p->final_names = calloc(p->n_final, sizeof *p->final_names);
    p->event_names = calloc(p->n_events + 1, sizeof *p->event_names);
    const size_t cap = 2 + d->n_params + md->n_states + ph->n_set;
    p->init_names = calloc(cap, sizeof *p->init_names);
    p->init = calloc(cap, sizeof *p->init);
    if (!p->final_names || !p->event_names || !p->init_names || !p->init || !p->stop_end)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    p->final_names[0] = strdup("time");
    for (size_t i = 0; i < md->n_states; i++)
        p->final_names[1 + i] = strdup(md->states[i].name);
    for (size_t i = 0; i < md->n_outputs; i++)
        p->final_names[1 + md->n_states + i] = strdup(md->outputs[i].name);
    for (size_t i = 0; i < md->n_events; i++)
        p->event_names[i] = strdup(md->events[i].name);
    for (size_t j = 0, q = 0; j < ph->n_ends; j++) {
        const lv_end_def *e = &ph->ends[j];
        if (e->kind != LV_END_VAR && e->kind != LV_END_TIME)
            continue;
        p->stop_end[q] = j;
        p->event_names[md->n_events + q++] = strdup(e->name);
    }
    for (size_t i = 0; i < p->n_final; i++)
        if (p->final_names[i] == NULL)
            return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    for (size_t i = 0; i < p->n_events; i++)
        if (p->event_names[i] == NULL)
            return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    const char *mass = ph->type->mass_state;
    p->mass_final = (size_t)-1;
    for (size_t i = 0; i < md->n_states; i++)
        if (strcmp(md->states[i].name, mass) == 0)
            p->mass_final = 1 + i;

    /* The hand-off, in this order (later entries win): the world's g; a root phase's
     * parameters, or the parent's final states by name and the carried stages' mass; the
     * start time; the overrides. */
    size_t n = 0;
    if (d->env.g != LV_NO_SLOT && model_has(md, "g")) {
        p->init_names[n] = "g";
        p->init[n++] = (lv_init_src){LV_INIT_SLOT, d->env.g};
    }
    if (ph->parent < 0) {
        for (size_t j = 0; j < d->n_params; j++)
            if (model_has(md, d->param_names[j])) {
                p->init_names[n] = d->param_names[j];
                p->init[n++] = (lv_init_src){LV_INIT_SLOT, d->param_values[j]};
            }
    } else {
        const lv_phase_plan *par = &m->plan[ph->parent];
        const lv_phase_def *pph = &d->phases[ph->parent];
        const int other = pph->type != ph->type;
        if (other && !type_accepts(ph->type, pph->type))
            return lv_fail(err, LV_ERR_INPUT,
                           "model %s cannot start from phase '%s' (model %s): no conversion "
                           "between the two models",
                           ph->type->name, pph->name, pph->type->name);
        for (size_t i = 0; i < md->n_states; i++) {
            const char *sn = md->states[i].name;
            if (strcmp(sn, mass) == 0) {
                p->init_names[n] = p->final_names[1 + i];
                p->init[n++] = (lv_init_src){LV_INIT_MASS, 0};
                continue;
            }
            size_t j = 0;
            while (j < par->n_final && strcmp(par->final_names[j], sn) != 0)
                j++;
            if (j < par->n_final) {
                p->init_names[n] = p->final_names[1 + i];
                p->init[n++] = (lv_init_src){LV_INIT_PARENT, j};
                p->n_copied++;
            } else if (other) { /* converted by the child's type from the parent's finals */
                if (ph->type->handoff == NULL)
                    return lv_fail(err, LV_ERR_INPUT, "model %s cannot start from phase '%s' "
                                   "(model %s): its state '%s' has no value there", ph->type->name,
                                   pph->name, pph->type->name, sn);
                p->init_names[n] = p->final_names[1 + i];
                p->init[n++] = (lv_init_src){LV_INIT_CONVERT, 0};
            }
        }
    }
    if (model_has(md, "start_time")) {
        p->init_names[n] = "start_time";
        p->init[n++] = (lv_init_src){LV_INIT_START_TIME, 0};
    }
    for (size_t i = 0; i < ph->n_set; i++) {
        p->init_names[n] = ph->set_names[i];
        p->init[n++] = (lv_init_src){LV_INIT_SLOT, ph->set_values[i]};
    }
    p->n_init = n;
    return LV_OK;
}

const char *const lv_iip_out_names[LV_IIP_N_OUT] = {"iip_lat", "iip_lon", "iip_tof",
                                                     "iip_range"};

size_t lv_mission_phase_iip_count(const lv_mission *m, size_t k)
{
    return m != NULL && k < m->def->n_phases ? m->def->phases[k].n_iip_at : 0;
}

void lv_phase_stops(const lv_mission_def *d, const lv_phase_plan *pl, size_t k, const double *v,
                    double start_time, lv_sim_stop *out)
{
    const lv_phase_def *ph = &d->phases[k];
    for (size_t j = 0; j < pl->n_stops; j++) {
        const lv_end_def *e = &ph->ends[pl->stop_end[j]];
        const int is_time = e->kind == LV_END_TIME;
        out[j] = (lv_sim_stop){pl->event_names[pl->n_model_events + j],
                               is_time ? "time" : e->var,
                               is_time ? start_time + v[e->value] : v[e->value], e->direction};
    }
}

lv_status lv_phase_start_book(const lv_mission_def *d, size_t k, const double *v, double *prop,
                              lv_err *err)
{
    const lv_phase_def *ph = &d->phases[k];
    if (ph->n_stages == 0 || ph->type->mass_state == NULL)
        return LV_OK;
    const int from_ref = ph->reference != NULL && ph->reference->start;
    double m = NAN;
    lv_src_loc loc = ph->loc;
    const char *what = "set: ";
    if (from_ref) {
        m = lv_reference_first(ph->reference, LV_REF_M);
        loc = ph->reference->loc;
        what = "reference: its first mass ";
    } else {
        int found = 0;
        for (size_t i = 0; i < ph->n_set; i++)
            if (strcmp(ph->set_names[i], ph->type->mass_state) == 0) {
                m = v[ph->set_values[i]];
                loc = ph->set_locs != NULL ? ph->set_locs[i] : ph->loc;
                found = 1;
            }
        if (!found)
            return LV_OK; /* no mass of its own: the stages' */
    }
    const size_t bottom = ph->stages[0];
    double dry = 0.0, above = 0.0; /* the dry masses; the propellant that does not burn */
    for (size_t i = 0; i < ph->n_stages; i++) {
        dry += v[d->stages[ph->stages[i]].dry_mass];
        if (i > 0)
            above += prop[ph->stages[i]];
    }
    const double rest = dry + above, load = v[d->stages[bottom].propellant_mass];
    const double tol = 1e-9 * (rest + load);
    char plus[128] = "";
    if (above > 0.0)
        snprintf(plus, sizeof plus, " plus the %g kg of propellant of the stages above the "
                 "burning one", above);
    if (!(m > 0.0))
        return lv_fail(err, LV_ERR_INPUT, "%s:%d:%d: phase '%s': %s%s = %g kg: a mass must be > 0",
                       d->path, loc.line, loc.column, ph->name, what, ph->type->mass_state, m);
    if (m < rest - tol)
        return lv_fail(err, LV_ERR_INPUT, "%s:%d:%d: phase '%s': %s%s = %g kg is less than the "
                       "dry mass %g kg of the stages it carries%s (%s starts the phase with it; "
                       "the burning stage '%s' holds the mass beyond that as propellant)",
                       d->path, loc.line, loc.column, ph->name, what, ph->type->mass_state, m,
                       dry, plus, from_ref ? "start: reference" : "the set:",
                       d->stages[bottom].name);
    if (from_ref && m > rest + load + tol)
        return lv_fail(err, LV_ERR_INPUT, "%s:%d:%d: phase '%s': %s%s = %g kg is more than the "
                       "%g kg of the stages it carries full (dry mass %g kg%s, the burning stage "
                       "'%s' with its whole load %g kg): a reference's start mass is the stack's "
                       "(start: reference)", d->path, loc.line, loc.column, ph->name, what,
                       ph->type->mass_state, m, rest + load, dry, plus, d->stages[bottom].name,
                       load);
    if (from_ref || m < rest + prop[bottom])
        prop[bottom] = fmin(fmax(m - rest, 0.0), from_ref ? load : prop[bottom]);
    return LV_OK;
}

/* Phase k's start state lies in its model's domain: a root phase's whole start state (the
 * parameters and overrides as the file gives them: lv_sim_create evaluates start(), init() and
 * the domain), a child's overridden mass (its other states come from its parent at run time). */
static lv_status check_start(const lv_mission *m, size_t k, lv_phase_model *pm, lv_err *err)
{
    const lv_mission_def *d = m->def;
    const lv_phase_def *ph = &d->phases[k];
    const lv_phase_plan *pl = &m->plan[k];
    if (ph->reference != NULL) { /* the reference against the phase's span */
        const double t0 = ph->t_start != LV_NO_SLOT ? m->defaults[ph->t_start]
                          : ph->parent >= 0          ? NAN
                                                     : 0.0;
        lv_status rs = lv_reference_check_span(ph->reference, t0, m->defaults[ph->t_stop], err);
        if (rs != LV_OK)
            return lv_fail_prefix(err, rs, "%s:%d:%d: phase '%s'", d->path,
                                  ph->reference->loc.line, ph->reference->loc.column, ph->name);
    }
    if (ph->parent >= 0)
        return LV_OK;
    double *values = calloc(pl->n_init + 8, sizeof *values);
    const char **names = calloc(pl->n_init + 8, sizeof *names);
    lv_sim_stop *stops = calloc(pl->n_stops + 1, sizeof *stops);
    if (values == NULL || stops == NULL || names == NULL) {
        free(values);
        free(names);
        free(stops);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    lv_sim_settings s;
    lv_sim_settings_default(&s);
    s.result_file = NULL;
    s.start_time = ph->t_start != LV_NO_SLOT ? m->defaults[ph->t_start] : 0.0;
    s.stop_time = m->defaults[ph->t_stop];
    s.method = ph->method ? ph->method : LV_PHASE_METHOD_DEFAULT;
    s.tolerance = m->defaults[ph->tolerance];
    s.output_interval = m->defaults[ph->output_interval];
    s.number_of_intervals = ph->intervals;
    s.fixed_step = m->defaults[ph->fixed_step];
    for (size_t i = 0; i < pl->n_init; i++)
        values[i] = pl->init[i].kind == LV_INIT_START_TIME ? s.start_time
                                                            : m->defaults[pl->init[i].index];
    size_t n_init = pl->n_init;
    for (size_t i = 0; i < n_init; i++)
        names[i] = pl->init_names[i];
    /* a start from the reference's first row (reference.h), as a run makes it */
    if (ph->reference != NULL && ph->reference->start) {
        lv_status rs = lv_reference_start(ph->reference, &m->env.planet, s.start_time, 1,
                                          ph->type->mass_state, names, values, &n_init,
                                          pl->n_init + 8, err);
        if (rs != LV_OK) {
            free(values);
            free(names);
            free(stops);
            return lv_fail_prefix(err, rs, "%s:%d:%d: phase '%s'", d->path,
                                  ph->reference->loc.line, ph->reference->loc.column, ph->name);
        }
    }
    s.n_initial = n_init;
    s.initial_names = names;
    s.initial_values = values;
    /* the ends on variables too, as the run gives them: one passed at the start is refused */
    lv_phase_stops(d, pl, k, m->defaults, s.start_time, stops);
    s.n_stops = pl->n_stops;
    s.stops = stops;
    lv_sim *sim = NULL;
    lv_status st = lv_sim_create(pm->def, pm->inst, &s, &sim, err);
    lv_sim_free(sim);
    free(values);
    free(names);
    free(stops);
    if (st != LV_OK && err != NULL)
        lv_drop_model_prefix(err, ph->name);
    if (st != LV_OK)
        return lv_fail_prefix(err, st, "%s:%d:%d: phase '%s'", d->path, ph->loc.line,
                              ph->loc.column, ph->name);
    return LV_OK;
}

/* A phase's model is named after the phase: "model 'P': " at the head of the simulation's
 * message repeats the "phase 'P'" the message gets, and goes. */
void lv_drop_model_prefix(lv_err *err, const char *phase)
{
    char head[LV_ERR_MSG_MAX];
    const int n = snprintf(head, sizeof head, "model '%s': ", phase);
    if (n > 0 && (size_t)n < sizeof head && strncmp(err->msg, head, (size_t)n) == 0)
        memmove(err->msg, err->msg + n, strlen(err->msg + n) + 1);
}

/* lv_model_find on a phase's model, whose model is named after the phase: a miss reads "the
 * dof3 model has no variable 'x'" rather than "model 'P' has ...", since the message is
 * prefixed with the phase already. */
static lv_status find_phase_var(const lv_phase_def *ph, const lv_model_def *md, const char *name,
                                lv_var_kind *kind, size_t *idx, lv_err *err)
{
    lv_status st = lv_model_find(md, name, kind, idx, err);
    if (st == LV_OK || err == NULL)
        return st;
    char was[sizeof err->msg];
    const int n = snprintf(was, sizeof was, "model '%s' has ", md->name);
    if (n > 0 && (size_t)n < sizeof was && strncmp(err->msg, was, (size_t)n) == 0) {
        snprintf(was, sizeof was, "%s", err->msg + n);
        return lv_fail(err, err->code, "the %s model has %s", ph->type->name, was);
    }
    return st;
}

/* The range of a `set:` override or a variable end once its variable is known (the parser took
 * any finite number): a root parameter of the phase's type its own
 * (start_lat within +-90 deg), any other angle two turns either way, a rate 10 rev/s; other
 * units keep `cur` (docs/mission-format.md, "Angle ranges"). */
static lv_range var_range(const lv_phase_type *t, const char *name, const char *unit,
                          lv_range cur)
{
    for (size_t i = 0; t->mission_param_ranges != NULL && i < t->n_mission_params; i++)
        if (strcmp(t->mission_params[i].name, name) == 0)
            return t->mission_param_ranges[i];
    if (strcmp(unit, "rad") == 0)
        return LV_RANGE_ANGLE;
    if (strcmp(unit, "rad/s") == 0)
        return LV_RANGE_RATE;
    return cur;
}

/* Slot s of phase `ph` takes range r (and the rule `lvsim params` shows); the file's value is
 * held to it where it is written: "phase 'P', WHERE: KEY must be ..., found V". */
static lv_status narrow_slot(lv_mission *m, const lv_phase_def *ph, lv_slot s, lv_range r,
                             const char *where, const char *var, int deg, lv_err *err)
{
    lv_mission_def *d = m->def;
    lv_slot_def *sd = &d->slots[s];
    sd->range = r;
    lv_range_text(r, m->rules[s], sizeof m->rules[s]);
    if (lv_range_holds(r, sd->value))
        return LV_OK;
    lv_range shown = r; /* the rule in the unit the value is written in */
    if (deg) {
        shown.lo /= LV_DEG;
        shown.hi /= LV_DEG;
    }
    char rule[96];
    lv_range_text(shown, rule, sizeof rule);
    const char *u = deg ? "deg" : LV_UNIT_AFTER_NUMBER(sd->unit);
    return lv_fail(err, LV_ERR_INPUT, "%s:%d:%d: phase '%s', %s: %s%s must be %s%s%s, found %g",
                   d->path, sd->loc.line, sd->loc.column, ph->name, where, var, deg ? "_deg" : "",
                   rule, u[0] ? " " : "", u, deg ? sd->value / LV_DEG : sd->value);
}

/* An end on a variable names a state, derivative or output of the phase's model (a parameter
 * never crosses); its slot takes the variable's unit and range; `_deg` only for an angle. */
static lv_status check_var_end(lv_mission *m, const lv_phase_def *ph, const lv_end_def *e,
                               const lv_model_def *md, lv_err *err)
{
    lv_mission_def *d = m->def;
    if (e->kind != LV_END_VAR)
        return LV_OK;
    lv_var_kind kind;
    size_t idx;
    lv_status st = find_phase_var(ph, md, e->var, &kind, &idx, err);
    if (st == LV_OK && kind == LV_VAR_PARAMETER)
        st = lv_fail(err, LV_ERR_INPUT, "'%s' is a parameter of the model: constant during the "
                     "phase, it never crosses a value", e->var);
    const char *unit = NULL;
    char dunit[72];
    if (st == LV_OK) {
        unit = kind == LV_VAR_STATE    ? md->states[idx].unit
               : kind == LV_VAR_OUTPUT ? md->outputs[idx].unit
                                       : "";
        if (kind == LV_VAR_DERIVATIVE) /* the state's unit per second */
            unit = lv_unit_per_second(md->states[idx].unit, dunit, sizeof dunit);
        if (e->deg && strcmp(unit, "rad") != 0)
            st = lv_fail(err, LV_ERR_INPUT, "'%s' is not an angle (its unit is '%s'): write its "
                         "value without _deg", e->var, unit);
    }
    if (st != LV_OK)
        return lv_fail_prefix(err, st, "%s:%d:%d: phase '%s': end", d->path, e->loc.line,
                              e->loc.column, ph->name);
    lv_slot_def *sd = &d->slots[e->value];
    char *u = strdup(unit);
    if (u == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    free(sd->unit);
    sd->unit = u;
    if (strcmp(unit, "rad") == 0 || strcmp(unit, "rad/s") == 0)
        return narrow_slot(m, ph, e->value, strcmp(unit, "rad") == 0 ? LV_RANGE_ANGLE
                                                                     : LV_RANGE_RATE,
                           "end", e->var, e->deg, err);
    /* the heat loads of dof3 and dof6 (quadrature states: the time integrals of heat fluxes,
     * never negative; docs/models.md "Heat load") only grow from their start (0, or the
     * parent's load): an end below or at 0, or one asked to fire falling, never fires */
    static const char *const rising[] = {"heat_load", "heat_load_fm"};
    for (size_t i = 0; kind == LV_VAR_STATE && md->quadrature != NULL && md->quadrature[idx] &&
                       i < sizeof rising / sizeof rising[0]; i++) {
        if (strcmp(e->var, rising[i]) != 0)
            continue;
        if (e->direction == LV_DIR_FALLING)
            return lv_fail(err, LV_ERR_INPUT, "%s:%d:%d: phase '%s': end: %s never decreases "
                           "(the time integral of a heat flux, which is never negative): an end "
                           "with direction: falling never fires; leave the direction out or "
                           "write rising", d->path, e->loc.line, e->loc.column, ph->name,
                           e->var);
        return narrow_slot(m, ph, e->value, LV_RANGE_POS, "end", e->var, 0, err);
    }
    return LV_OK;
}

/* Every phase's model can be built with the file's values, every `set:` name is a state or
 * parameter of it (its slot takes that variable's unit), every parameter is used by some
 * phase's model; the plans are made on the way. */
static lv_status check_and_plan(lv_mission *m, lv_err *err)
{
    lv_mission_def *d = m->def;
    int *param_used = calloc(d->n_params + 1, sizeof *param_used);
    size_t *param_child = calloc(d->n_params + 1, sizeof *param_child); /* phase + 1 */
    double *prop = calloc(d->n_stages + 1, sizeof *prop);
    if (param_used == NULL || param_child == NULL || prop == NULL) {
        free(param_used);
        free(param_child);
        free(prop);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    for (size_t s = 0; s < d->n_stages; s++)
        prop[s] = m->defaults[d->stages[s].propellant_mass];
    lv_status st = LV_OK;
    for (size_t k = 0; k < d->n_phases && st == LV_OK; k++) {
        const lv_phase_def *ph = &d->phases[k];
        lv_phase_model *pm = NULL;
        /* the stage book as the phase starts: the loads, less what its own start mass leaves
         * out of the burning stage (a child's parent burns at run time: the loads here) */
        for (size_t s = 0; s < d->n_stages; s++)
            prop[s] = m->defaults[d->stages[s].propellant_mass];
        if ((st = lv_phase_start_book(d, k, m->defaults, prop, err)) != LV_OK)
            break;
        const lv_build_ctx bc = {d, &m->env, k, m->defaults, prop, NULL, NULL};
        if ((st = lv_phase_model_build(&bc, &pm, err)) != LV_OK) {
            st = lv_fail_prefix(err, st, "%s:%d:%d: phase '%s'", d->path, ph->loc.line,
                                ph->loc.column, ph->name);
            break;
        }
        const lv_model_def *md = pm->def;
        for (size_t i = 0; i < ph->n_set && st == LV_OK; i++) {
            lv_var_kind kind;
            size_t idx;
            st = find_phase_var(ph, md, ph->set_names[i], &kind, &idx, err);
            if (st == LV_OK && kind != LV_VAR_STATE && kind != LV_VAR_PARAMETER)
                st = lv_fail(err, LV_ERR_INPUT, "'%s' is not a state or parameter",
                             ph->set_names[i]);
            /* start: reference gives the start state and mass (a child's states, a root's
             * start_* parameters): a set: of them would override it on a child and be
             * overridden on a root (and a mass below the reference's broke the stage book) */
            if (st == LV_OK && ph->reference != NULL && ph->reference->start &&
                (kind == LV_VAR_STATE || strncmp(ph->set_names[i], "start_", 6) == 0))
                st = lv_fail(err, LV_ERR_INPUT, "'%s': the phase starts from its reference's "
                             "first row (start: reference), which gives its start state and "
                             "mass; leave '%s' out of set:, or start from the parent (start: "
                             "parent)", ph->set_names[i], ph->set_names[i]);
            if (st == LV_OK && ph->set_deg != NULL && ph->set_deg[i]) {
                const char *u = kind == LV_VAR_STATE ? md->states[idx].unit
                                                     : md->params[idx].unit;
                if (strcmp(u, "rad") != 0)
                    st = lv_fail(err, LV_ERR_INPUT, "'%s' is not an angle (its unit is '%s'): "
                                 "write its value without _deg", ph->set_names[i],
                                 u[0] ? u : "1");
            }
            if (st != LV_OK) {
                lv_src_loc loc = ph->set_locs ? ph->set_locs[i] : ph->loc;
                st = lv_fail_prefix(err, LV_ERR_INPUT, "%s:%d:%d: phase '%s': set", d->path,
                                    loc.line, loc.column, ph->name);
                break;
            }
            const lv_var *var = kind == LV_VAR_STATE ? &md->states[idx] : &md->params[idx];
            lv_slot_def *sd = &d->slots[ph->set_values[i]];
            char *unit = strdup(var->unit);
            if (unit == NULL) {
                st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
                break;
            }
            free(sd->unit);
            sd->unit = unit;
            const lv_range r = var_range(ph->type, ph->set_names[i], var->unit, sd->range);
            if ((st = narrow_slot(m, ph, ph->set_values[i], r, "set", ph->set_names[i],
                                  ph->set_deg != NULL && ph->set_deg[i], err)) != LV_OK)
                break;
        }
        for (size_t j = 0; j < ph->n_ends && st == LV_OK; j++)
            st = check_var_end(m, ph, &ph->ends[j], md, err);
        for (size_t j = 0; ph->n_iip_at > 0 && st == LV_OK && j < LV_IIP_N_OUT; j++) {
            lv_var_kind kind;
            size_t idx;
            if (lv_model_find(md, lv_iip_out_names[j], &kind, &idx, NULL) != LV_OK ||
                kind != LV_VAR_OUTPUT)
                st = lv_fail(err, LV_ERR_INPUT, "%s:%d:%d: phase '%s': iip_at: the %s model has "
                             "no impact-point output '%s' (the dof3, dof6 and runway models "
                             "have them)",
                             d->path, ph->iip_at_loc.line, ph->iip_at_loc.column, ph->name,
                             ph->type->name, lv_iip_out_names[j]);
        }
        for (size_t j = 0; j < d->n_params; j++) {
            lv_var_kind kind;
            size_t idx;
            if (lv_model_find(md, d->param_names[j], &kind, &idx, NULL) != LV_OK ||
                kind != LV_VAR_PARAMETER)
                continue;
            /* a child phase does not read the start values its type lists as a root's only */
            int root_only = 0;
            for (const char *const *r = ph->type->root_only_params; ph->parent >= 0 && r != NULL &&
                                                                     *r != NULL; r++)
                root_only |= strcmp(*r, d->param_names[j]) == 0;
            if (!root_only)
                param_used[j] = 1;
            else if (param_child[j] == 0)
                param_child[j] = k + 1;
        }
        if (st == LV_OK && (st = make_plan(m, k, md, &m->plan[k], err)) != LV_OK)
            st = lv_fail_prefix(err, st, "%s:%d:%d: phase '%s'", d->path, ph->loc.line,
                                ph->loc.column, ph->name);
        if (st == LV_OK)
            st = check_start(m, k, pm, err);
        lv_phase_model_free(pm);
    }
    for (size_t j = 0; j < d->n_params && st == LV_OK; j++) {
        if (param_used[j])
            continue;
        if (param_child[j] > 0) {
            const lv_phase_def *ph = &d->phases[param_child[j] - 1];
            const lv_slot_def *sd = &d->slots[d->param_values[j]];
            st = lv_fail(err, LV_ERR_INPUT, "%s:%d:%d: parameter '%s' would start only phase "
                         "'%s' (model %s), which starts from its parent '%s' (`from`) with the "
                         "parent's final state: the parameters start a root phase only; override "
                         "a state of the child with `set:` instead", d->path, sd->loc.line,
                         sd->loc.column, d->param_names[j], ph->name, ph->type->name,
                         d->phases[ph->parent].name);
            break;
        }
        char known[640] = "";
        size_t used = 0;
        for (const lv_phase_type *const *t = lv_phase_types(); *t != NULL; t++) {
            if ((*t)->n_mission_params == 0 || used >= sizeof known)
                continue;
            used += (size_t)snprintf(known + used, sizeof known - used, "%s%s knows",
                                     used ? "; " : "", (*t)->name);
            for (size_t i = 0; i < (*t)->n_mission_params && used < sizeof known; i++)
                used += (size_t)snprintf(known + used, sizeof known - used, "%s %s",
                                         i ? "," : "", (*t)->mission_params[i].name);
        }
        st = lv_fail(err, LV_ERR_INPUT,
                     "%s: parameter '%s' is not used by any phase's model (%s)", d->path,
                     d->param_names[j], known);
    }
    free(param_used);
    free(param_child);
    free(prop);
    return st;
}

/* ---- load and free -------------------------------------------------------------------------- */

void lv_mission_free(lv_mission *m)
{
    if (m == NULL)
        return;
    for (size_t k = 0; m->plan != NULL && k < m->def->n_phases; k++)
        plan_clear(&m->plan[k]);
    free(m->plan);
    free(m->rules);
    free(m->defaults);
    lv_mission_env_clear(&m->env);
    lv_mission_def_free(m->def);
    free(m);
}

lv_status lv_mission_from_def(lv_mission_def *d, lv_mission **out, lv_err *err)
{
    *out = NULL;
    lv_mission *m = calloc(1, sizeof *m);
    if (m == NULL) {
        lv_mission_def_free(d);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    m->def = d;
    m->plan = calloc(d->n_phases, sizeof *m->plan);
    m->rules = calloc(d->n_slots + 1, sizeof *m->rules);
    m->defaults = calloc(d->n_slots + 1, sizeof *m->defaults);
    if (m->plan == NULL || m->rules == NULL || m->defaults == NULL) {
        lv_mission_free(m);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    for (size_t i = 0; i < d->n_slots; i++) {
        m->defaults[i] = d->slots[i].value;
        lv_range_text(d->slots[i].range, m->rules[i], sizeof m->rules[i]);
    }
    lv_status st;
    if ((st = lv_mission_env_make(d, &m->env, err)) != LV_OK ||
        (st = check_and_plan(m, err)) != LV_OK ||
        (st = lv_targeting_def_check(m, err)) != LV_OK ||
        (st = lv_ocp_def_check(m, err)) != LV_OK) {
        lv_mission_free(m);
        return st;
    }
    *out = m;
    return LV_OK;
}

lv_status lv_mission_load(const char *path, lv_mission **out, lv_err *err)
{
    if (out == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_mission_load: NULL argument");
    *out = NULL;
    lv_mission_def *d = NULL;
    lv_status st = lv_mission_def_load(path, &d, err);
    if (st != LV_OK)
        return st;
    return lv_mission_from_def(d, out, err);
}

/* ---- questions ------------------------------------------------------------------------------ */

void lv_mission_get_info(const lv_mission *m, lv_mission_info *out)
{
    const lv_mission_def *d = m->def;
    *out = (lv_mission_info){d->name,
                             d->description,
                             d->path,
                             d->epoch,
                             d->env.world == LV_WORLD_FLAT,
                             d->env.world == LV_WORLD_FLAT ? NULL
                                                           : (d->env.planet ? d->env.planet
                                                                            : "earth"),
                             d->env.site_lat,
                             d->env.site_lon,
                             d->n_phases,
                             d->n_stages,
                             d->n_slots};
}

const char *lv_mission_name(const lv_mission *m) { return m->def->name; }
size_t lv_mission_phase_count(const lv_mission *m) { return m->def->n_phases; }
size_t lv_mission_file_count(const lv_mission *m) { return 1 + m->def->n_files; }
const char *lv_mission_file(const lv_mission *m, size_t i)
{
    return i == 0 ? m->def->path : i <= m->def->n_files ? m->def->files[i - 1] : NULL;
}
const char *lv_mission_phase_name(const lv_mission *m, size_t k)
{
    return k < m->def->n_phases ? m->def->phases[k].name : NULL;
}
int lv_mission_phase_parent(const lv_mission *m, size_t k)
{
    return k < m->def->n_phases ? m->def->phases[k].parent : -1;
}
size_t lv_mission_stage_count(const lv_mission *m) { return m->def->n_stages; }
const char *lv_mission_stage_name(const lv_mission *m, size_t s)
{
    return s < m->def->n_stages ? m->def->stages[s].name : NULL;
}

int lv_mission_stage_geometry(const lv_mission *m, size_t s, double *length, double *diameter,
                              double *span)
{
    if (s >= m->def->n_stages || !(m->def->stages[s].geom_length > 0.0))
        return 0;
    const lv_stage_def *d = &m->def->stages[s];
    if (length != NULL)
        *length = d->geom_length;
    if (diameter != NULL)
        *diameter = d->geom_diameter;
    if (span != NULL)
        *span = d->geom_span;
    return 1;
}

lv_status lv_mission_phase_find(const lv_mission *m, const char *name, size_t *k, lv_err *err)
{
    lv_suggest sg;
    lv_suggest_init(&sg, name);
    for (size_t i = 0; i < m->def->n_phases; i++) {
        if (strcmp(m->def->phases[i].name, name) == 0) {
            *k = i;
            return LV_OK;
        }
        lv_suggest_add(&sg, m->def->phases[i].name);
    }
    char hint[160];
    lv_suggest_text(&sg, hint, sizeof hint);
    return lv_fail(err, LV_ERR_NOTFOUND, "mission '%s' has no phase '%s'%s", m->def->name, name,
                   hint);
}

void lv_mission_phase_info(const lv_mission *m, size_t k, lv_phase_info *out)
{
    const lv_phase_def *ph = &m->def->phases[k];
    *out = (lv_phase_info){ph->name,     ph->type->name, ph->parent,
                           ph->n_stages, ph->stages,     ph->method ? ph->method : LV_PHASE_METHOD_DEFAULT,
                           ph->file_index, NULL};
    if (ph->parent >= 0 && m->def->phases[ph->parent].type != ph->type &&
        ph->type->handoff_rule != NULL)
        out->handoff_rule = ph->type->handoff_rule(ph);
}

const char *lv_mission_phase_separation_name(const lv_mission *m, size_t k)
{
    return k < m->def->n_phases ? m->def->phases[k].separation_label : NULL;
}

size_t lv_mission_param_count(const lv_mission *m) { return m->def->n_slots; }

void lv_mission_param_info(const lv_mission *m, size_t i, lv_param_info *out)
{
    const lv_slot_def *sd = &m->def->slots[i];
    *out = (lv_param_info){sd->name, sd->unit, m->defaults[i], sd->loc.line, m->rules[i]};
}

lv_status lv_mission_param_find(const lv_mission *m, const char *name, size_t *i, int *deg,
                                lv_err *err)
{
    const lv_mission_def *d = m->def;
    if (name == NULL)
        return lv_fail(err, LV_ERR_INPUT, "mission '%s': parameter name is NULL", d->name);
    const size_t n = strlen(name);
    if (deg != NULL)
        *deg = 0;
    lv_suggest sg;
    lv_suggest_init(&sg, name);
    for (size_t s = 0; s < d->n_slots; s++) {
        const char *sn = d->slots[s].name;
        if (strcmp(sn, name) == 0) {
            *i = s;
            return LV_OK;
        }
        /* NAME_deg: an angle in degrees */
        const size_t ns = strlen(sn);
        if (deg != NULL && n == ns + 4 && strncmp(name, sn, ns) == 0 &&
            strcmp(name + ns, "_deg") == 0 &&
            (strcmp(d->slots[s].unit, "rad") == 0 || strcmp(d->slots[s].unit, "rad/s") == 0)) {
            *i = s;
            *deg = 1;
            return LV_OK;
        }
        lv_suggest_add(&sg, sn);
    }
    char hint[200];
    lv_suggest_text(&sg, hint, sizeof hint);
    return lv_fail(err, LV_ERR_NOTFOUND,
                   "mission '%s' has no parameter '%s'%s (lvsim params MISSION.yaml lists "
                   "them)",
                   d->name, name, hint);
}

int lv_mission_def_slot_overridden(const lv_mission_def *d, lv_slot s, const char **phase)
{
    static const char *const root_set[] = {"start_lat", "start_lon", "start_h", "start_vel",
                                           "start_fpa", "start_chi", NULL};
    static const char *const child_set[] = {"r_eci_x", "r_eci_y", "r_eci_z", "v_eci_x",
                                            "v_eci_y", "v_eci_z", NULL};
    const lv_slot_def *sd = &d->slots[s];
    int any = 0;
    if (sd->owner != LV_OWN_PARAM && sd->owner != LV_OWN_PHASE)
        return 0;
    for (size_t k = 0; k < d->n_phases; k++) {
        const lv_phase_def *ph = &d->phases[k];
        const int from_ref = ph->reference != NULL && ph->reference->start;
        const char *name = NULL; /* the value the slot gives the phase */
        if (sd->owner == LV_OWN_PARAM) {
            int reads = 0, root_only = 0;
            for (size_t i = 0; i < ph->type->n_mission_params && !reads; i++)
                reads = strcmp(ph->type->mission_params[i].name, sd->name) == 0;
            for (const char *const *r = ph->type->root_only_params; r != NULL && *r != NULL; r++)
                root_only |= strcmp(*r, sd->name) == 0;
            for (const char *const *r = root_set; *r != NULL; r++) /* a child's come from */
                root_only |= strcmp(*r, sd->name) == 0;             /* its parent */
            if (!reads || (ph->parent >= 0 && root_only))
                continue; /* not read here */
            name = sd->name;
        } else {
            if (sd->owner_index != k)
                continue;
            for (size_t i = 0; i < ph->n_set; i++)
                if (ph->set_values[i] == s)
                    name = ph->set_names[i];
            if (name == NULL)
                return 0; /* another key of the phase: not a start value */
        }
        int replaced = from_ref && ph->type->mass_state != NULL &&
                       strcmp(name, ph->type->mass_state) == 0;
        for (const char *const *r = ph->parent >= 0 ? child_set : root_set; from_ref && *r; r++)
            replaced |= strcmp(*r, name) == 0;
        if (!replaced)
            return 0;
        if (!any++ && phase != NULL)
            *phase = ph->name;
    }
    return any > 0;
}

size_t lv_mission_slot_phases(const lv_mission *m, lv_slot s, size_t *out)
{
    const lv_mission_def *d = m->def;
    const lv_slot_def *sd = &d->slots[s];
    size_t n = 0;
    for (size_t k = 0; k < d->n_phases; k++) {
        int uses = 0;
        switch (sd->owner) {
        case LV_OWN_ENV:
            uses = 1;
            break;
        case LV_OWN_PHASE:
            uses = sd->owner_index == k;
            break;
        case LV_OWN_STAGE:
            uses = lv_mission_phase_has_stage(d, k, sd->owner_index);
            break;
        case LV_OWN_PARAM: /* a model type that takes the parameter set reads it */
            for (size_t i = 0; i < d->phases[k].type->n_mission_params && !uses; i++)
                uses = strcmp(d->phases[k].type->mission_params[i].name, sd->name) == 0;
            break;
        }
        if (uses)
            out[n++] = k;
    }
    return n;
}
