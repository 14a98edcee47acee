/* ocp_def.c - the `optimal_control:` section of a mission file (ocp_def.h): parsed with the
 * parse kit, then resolved against the loaded mission (phases by name, controls against the
 * phase type's, finals as `targeting:` resolves them). Format: docs/optimal-control.md. */
#define _POSIX_C_SOURCE 200809L

#include "mission/ocp_def.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/names.h"
#include "core/status.h"
#include "core/units.h"
#include "mission/mission_rt.h"
#include "mission/phase_type.h"
#include "mission/reference.h"

#define SEC "optimal_control"

static lv_src_loc loc_of(const lv_ynode *n)
{
    lv_src_loc l = {n->line, n->col};
    return l;
}

/* ---- parsing --------------------------------------------------------------------------- */

static lv_status parse_ctrl(const lv_pctx *c, const lv_ynode *n, const char *phase, size_t k,
                            lv_ocp_ctrl_def *u)
{
    static const char *const keys[] = {"name", "min", "max", "start", NULL};
    char what[LV_WHAT_MAX];
    const lv_ynode *x;
    lv_status st;
    snprintf(what, sizeof what, SEC ": phase '%.60s': control #%zu", phase, k + 1);
    if (n->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, n, "%s: a mapping such as {name: alpha_deg, min: -10, max: 10} "
                          "expected", what);
    if ((st = lv_pk_check_map(c, n, what, keys)) != LV_OK ||
        (st = lv_pk_need(c, n, what, "name", &x)) != LV_OK ||
        (st = lv_pk_str(c, x, what, "name", &u->name)) != LV_OK)
        return st;
    u->loc = loc_of(x);
    snprintf(what, sizeof what, SEC ": phase '%.60s': control '%.40s'", phase, u->name);
    const size_t len = strlen(u->name);
    u->deg = len > 4 && strcmp(u->name + len - 4, "_deg") == 0;
    const double f = u->deg ? LV_DEG : 1.0;
    if ((st = lv_pk_need(c, n, what, "min", &x)) != LV_OK ||
        (st = lv_pk_num(c, x, what, "min", &u->lo)) != LV_OK ||
        (st = lv_pk_need(c, n, what, "max", &x)) != LV_OK ||
        (st = lv_pk_num(c, x, what, "max", &u->hi)) != LV_OK)
        return st;
    if (!(u->lo < u->hi))
        return lv_pk_fail(c, x, "%s: max %g must be greater than min %g", what, u->hi, u->lo);
    u->start = NAN;
    if ((x = lv_pk_get(n, "start")) != NULL) {
        if ((st = lv_pk_num(c, x, what, "start", &u->start)) != LV_OK)
            return st;
        if (!(u->start >= u->lo && u->start <= u->hi))
            return lv_pk_fail(c, x, "%s: start %g is outside [min, max] = [%g, %g]", what,
                              u->start, u->lo, u->hi);
        u->start *= f;
    }
    u->lo *= f;
    u->hi *= f;
    return LV_OK;
}

static lv_status parse_phase(const lv_pctx *c, const lv_ynode *n, size_t k, lv_ocp_phase_def *p)
{
    static const char *const keys[] = {"name", "controls", "nodes", "segments", "duration",
                                       NULL};
    static const char *const dkeys[] = {"min", "max", "start", NULL};
    char what[LV_WHAT_MAX];
    const lv_ynode *x;
    lv_status st;
    snprintf(what, sizeof what, SEC ": phase #%zu", k + 1);
    if (n->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, n, "%s: a mapping such as {name: ascent, controls: [{name: "
                          "alpha_deg, min: -10, max: 10}], nodes: 11} expected", what);
    if ((st = lv_pk_check_map(c, n, what, keys)) != LV_OK ||
        (st = lv_pk_need(c, n, what, "name", &x)) != LV_OK ||
        (st = lv_pk_str(c, x, what, "name", &p->name)) != LV_OK)
        return st;
    p->loc = loc_of(x);
    snprintf(what, sizeof what, SEC ": phase '%.60s'", p->name);
    const lv_ynode *cl = lv_pk_get(n, "controls");
    if (cl == NULL || cl->kind != LV_YNODE_SEQ || cl->n == 0)
        return lv_pk_fail(c, cl ? cl : n, "%s: 'controls' needs a list of at least one control "
                          "({name: alpha_deg, min: -10, max: 10})", what);
    if (cl->n > LV_OCP_MAX_CONTROLS)
        return lv_pk_fail(c, cl, "%s: %zu controls, at most %d", what, cl->n,
                          LV_OCP_MAX_CONTROLS);
    if ((p->ctrl = calloc(cl->n, sizeof *p->ctrl)) == NULL)
        return lv_pk_nomem(c);
    p->n_ctrl = cl->n;
    for (size_t i = 0; i < cl->n; i++)
        if ((st = parse_ctrl(c, cl->kids[i], p->name, i, &p->ctrl[i])) != LV_OK)
            return st;
    for (size_t i = 0; i < cl->n; i++)
        for (size_t j = 0; j < i; j++)
            if (strcmp(p->ctrl[i].name, p->ctrl[j].name) == 0)
                return lv_pk_fail(c, cl->kids[i], "%s: control '%s' is given twice", what,
                                  p->ctrl[i].name);
    if ((st = lv_pk_need(c, n, what, "nodes", &x)) != LV_OK ||
        (st = lv_pk_int(c, x, what, "nodes", 2, &p->nodes)) != LV_OK)
        return st;
    if (p->nodes > LV_OCP_MAX_NODES)
        return lv_pk_fail(c, x, "%s: nodes: at most %d, found %d", what, LV_OCP_MAX_NODES,
                          p->nodes);
    p->segments = p->nodes - 1;
    if ((x = lv_pk_get(n, "segments")) != NULL) {
        if ((st = lv_pk_int(c, x, what, "segments", 1, &p->segments)) != LV_OK)
            return st;
        if (p->segments > LV_OCP_MAX_NODES)
            return lv_pk_fail(c, x, "%s: segments: at most %d, found %d", what,
                              LV_OCP_MAX_NODES, p->segments);
    }
    p->dur_start = NAN;
    const lv_ynode *dn = lv_pk_get(n, "duration");
    if (dn != NULL) {
        char dw[LV_WHAT_MAX + 16];
        snprintf(dw, sizeof dw, "%s: duration", what);
        if (dn->kind != LV_YNODE_MAP)
            return lv_pk_fail(c, dn, "%s: a mapping {min: s, max: s} (optionally start) "
                              "expected", dw);
        if ((st = lv_pk_check_map(c, dn, dw, dkeys)) != LV_OK ||
            (st = lv_pk_need(c, dn, dw, "min", &x)) != LV_OK ||
            (st = lv_pk_num(c, x, dw, "min", &p->dur_lo)) != LV_OK ||
            (st = lv_pk_need(c, dn, dw, "max", &x)) != LV_OK ||
            (st = lv_pk_num(c, x, dw, "max", &p->dur_hi)) != LV_OK)
            return st;
        if (!(p->dur_lo > 0.0))
            return lv_pk_fail(c, lv_pk_get(dn, "min"), "%s: min must be > 0 s, found %g", dw,
                              p->dur_lo);
        if (!(p->dur_lo < p->dur_hi))
            return lv_pk_fail(c, x, "%s: max %g s must be greater than min %g s", dw,
                              p->dur_hi, p->dur_lo);
        if ((x = lv_pk_get(dn, "start")) != NULL) {
            if ((st = lv_pk_num(c, x, dw, "start", &p->dur_start)) != LV_OK)
                return st;
            if (!(p->dur_start >= p->dur_lo && p->dur_start <= p->dur_hi))
                return lv_pk_fail(c, x, "%s: start %g s is outside [min, max] = [%g, %g] s",
                                  dw, p->dur_start, p->dur_lo, p->dur_hi);
        }
        p->free_duration = 1;
        p->dur_loc = loc_of(dn);
    }
    return LV_OK;
}

lv_status lv_ocp_def_parse(const lv_pctx *c, const lv_ynode *n)
{
    static const char *const keys[] = {"phases", "constraints", "cost", "max_iterations",
                                       "tolerance", "acceptable_iterations",
                                       "integrator_tolerance", NULL};
    const char *what = SEC;
    lv_status st;
    if (n == NULL)
        return LV_OK;
    if (lv_yaml_is_null(n))
        return lv_pk_fail(c, n, "%s: the section is empty: give phases with controls, and "
                          "constraints or a cost, or remove the key", what);
    if ((st = lv_pk_check_map(c, n, what, keys)) != LV_OK)
        return st;
    lv_ocp_def *o = calloc(1, sizeof *o);
    if (o == NULL)
        return lv_pk_nomem(c);
    c->m->ocp = o;
    o->loc = loc_of(n);
    o->max_iterations = 500;
    o->tolerance = 1e-8;
    o->acceptable_iterations = 15; /* IPOPT's acceptable_iter */
    o->integrator_tolerance = 1e-10;
    const lv_ynode *v;
    if ((v = lv_pk_get(n, "max_iterations")) != NULL) {
        if ((st = lv_pk_int(c, v, what, "max_iterations", 1, &o->max_iterations)) != LV_OK)
            return st;
        if (o->max_iterations > 100000)
            return lv_pk_fail(c, v, "%s: max_iterations: at most 100000, found %d", what,
                              o->max_iterations);
    }
    if ((v = lv_pk_get(n, "tolerance")) != NULL) {
        if ((st = lv_pk_num(c, v, what, "tolerance", &o->tolerance)) != LV_OK)
            return st;
        if (!(o->tolerance >= 1e-14 && o->tolerance <= 1e-2))
            return lv_pk_fail(c, v, "%s: tolerance (IPOPT's, on the scaled problem) must lie in "
                              "[1e-14, 1e-2], found %g", what, o->tolerance);
    }
    if ((v = lv_pk_get(n, "acceptable_iterations")) != NULL) {
        if ((st = lv_pk_int(c, v, what, "acceptable_iterations", 1,
                            &o->acceptable_iterations)) != LV_OK)
            return st;
        if (o->acceptable_iterations > 1000)
            return lv_pk_fail(c, v, "%s: acceptable_iterations: at most 1000, found %d", what,
                              o->acceptable_iterations);
    }
    if ((v = lv_pk_get(n, "integrator_tolerance")) != NULL) {
        if ((st = lv_pk_num(c, v, what, "integrator_tolerance", &o->integrator_tolerance)) !=
            LV_OK)
            return st;
        if (!(o->integrator_tolerance >= 1e-14 && o->integrator_tolerance <= 1e-4))
            return lv_pk_fail(c, v, "%s: integrator_tolerance must lie in [1e-14, 1e-4] (the "
                              "finite differences need segments more accurate than their "
                              "steps), found %g", what, o->integrator_tolerance);
    }
    const lv_ynode *ph = lv_pk_get(n, "phases");
    if (ph == NULL || ph->kind != LV_YNODE_SEQ || ph->n == 0)
        return lv_pk_fail(c, ph ? ph : n, "%s: 'phases' needs a list of at least one phase "
                          "({name: P, controls: [...], nodes: N})", what);
    if ((o->phases = calloc(ph->n, sizeof *o->phases)) == NULL)
        return lv_pk_nomem(c);
    o->n_phases = ph->n;
    for (size_t k = 0; k < ph->n; k++)
        if ((st = parse_phase(c, ph->kids[k], k, &o->phases[k])) != LV_OK)
            return st;
    const lv_ynode *cons = lv_pk_get(n, "constraints");
    if (cons != NULL && !lv_yaml_is_null(cons)) {
        if (cons->kind != LV_YNODE_SEQ)
            return lv_pk_fail(c, cons, "%s: constraints: a list expected", what);
        if (cons->n > 0 && (o->cons = calloc(cons->n, sizeof *o->cons)) == NULL)
            return lv_pk_nomem(c);
        o->n_cons = cons->n;
        for (size_t k = 0; k < cons->n; k++) {
            if ((st = lv_tcon_parse(c, cons->kids[k], SEC, k, &o->cons[k])) != LV_OK)
                return st;
            if (o->cons[k].end != NULL)
                return lv_pk_fail(c, lv_pk_key(cons->kids[k], "end"), "%s: constraint on "
                                  "'%s': end: an optimised phase flies its duration, and the "
                                  "others end as their files say: there is no end to assume",
                                  what, o->cons[k].name);
        }
    }
    if ((v = lv_pk_get(n, "cost")) != NULL && !lv_yaml_is_null(v)) {
        if ((st = lv_tcost_parse(c, v, SEC, &o->cost)) != LV_OK)
            return st;
        if (o->cost.end != NULL)
            return lv_pk_fail(c, lv_pk_key(v, "end"), "%s: cost: end: an optimised phase flies "
                              "its duration: there is no end to assume", what);
    }
    if (o->n_cons == 0 && !o->cost.present)
        return lv_pk_fail(c, n, "%s: nothing to achieve: give 'constraints', a 'cost' or both",
                          what);
    return LV_OK;
}

void lv_ocp_def_free(lv_ocp_def *o)
{
    if (o == NULL)
        return;
    for (size_t k = 0; k < o->n_phases; k++) {
        for (size_t i = 0; i < o->phases[k].n_ctrl; i++)
            free(o->phases[k].ctrl[i].name);
        free(o->phases[k].ctrl);
        free(o->phases[k].name);
    }
    free(o->phases);
    for (size_t k = 0; k < o->n_cons; k++) {
        free(o->cons[k].name);
        free(o->cons[k].end);
    }
    free(o->cons);
    free(o->cost.name);
    free(o->cost.end);
    free(o);
}

/* ---- resolution against a loaded mission ------------------------------------------------- */

#define FAIL_AT(l, ...)                                                                       \
    lv_fail(err, LV_ERR_INPUT, "%s:%d:%d: " SEC ": %s", d->path, (l).line, (l).column,        \
            (snprintf(msg, sizeof msg, __VA_ARGS__), msg))

static lv_status check_phase(lv_mission *m, lv_ocp_phase_def *p, size_t idx, lv_err *err)
{
    const lv_mission_def *d = m->def;
    char msg[LV_ERR_MSG_MAX - 200];
    size_t k;
    lv_err e = {LV_OK, ""};
    if (lv_mission_phase_find(m, p->name, &k, &e) != LV_OK)
        return FAIL_AT(p->loc, "%s", e.msg);
    p->phase = k;
    for (size_t j = 0; j < idx; j++)
        if (d->ocp->phases[j].phase == k)
            return FAIL_AT(p->loc, "phase '%s' is given twice (line %d)", p->name,
                           d->ocp->phases[j].loc.line);
    const lv_phase_def *ph = &d->phases[k];
    const lv_phase_type *ty = ph->type;
    if (ty->controls == NULL || ty->set_controls == NULL)
        return FAIL_AT(p->loc, "phase '%s': its model %s takes no controls from an optimiser "
                       "(dof3 phases do: alpha, beta, mu, throttle; pitch, heading, roll of "
                       "an attitude law)", p->name, ty->name);
    if (ph->reference != NULL && ph->reference->start)
        return FAIL_AT(p->loc, "phase '%s' starts from its reference (start: reference): an "
                       "optimised phase starts from its parent or the mission's start values",
                       p->name);
    for (size_t i = 0; i < p->n_ctrl; i++) {
        lv_ocp_ctrl_def *u = &p->ctrl[i];
        char base[64];
        snprintf(base, sizeof base, "%.*s", (int)(strlen(u->name) - (u->deg ? 4 : 0)), u->name);
        size_t j = 0;
        while (ty->controls[j] != NULL && strcmp(ty->controls[j], base) != 0)
            j++;
        if (ty->controls[j] == NULL) {
            char list[256] = "";
            for (size_t a = 0; ty->controls[a] != NULL; a++)
                snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s%s",
                         a ? ", " : "", ty->controls[a],
                         strcmp(ty->controls[a], "throttle") != 0 ? "_deg" : "");
            return FAIL_AT(u->loc, "phase '%s': control '%s': its model %s takes the controls "
                           "%s", p->name, u->name, ty->name, list);
        }
        u->input = j;
        const int is_angle = strcmp(base, "throttle") != 0;
        if (is_angle && !u->deg)
            return FAIL_AT(u->loc, "phase '%s': control '%s': an angle is given in degrees: "
                           "name it %s_deg", p->name, u->name, base);
        if (!is_angle && u->deg)
            return FAIL_AT(u->loc, "phase '%s': control '%s': '%s' is not an angle: name it "
                           "without _deg", p->name, u->name, base);
        if (is_angle && !(u->lo >= -LV_PI && u->hi <= LV_PI))
            return FAIL_AT(u->loc, "phase '%s': control '%s': its bounds must lie within "
                           "[-180, 180] deg", p->name, u->name);
        char why[256];
        if (ty->control_conflict != NULL && ty->control_conflict(ph, j, why, sizeof why))
            return FAIL_AT(u->loc, "phase '%s': control '%s': %s", p->name, u->name, why);
        /* the throttle's bounds within every running engine's range, as a constant's
         * (engine_run.c): beyond, the engines clamp what the optimiser thinks it flies */
        const lv_stage_def *st = &d->stages[ph->stages[0]];
        for (size_t ei = 0; !is_angle && ei < st->n_engines; ei++) {
            const lv_engine_def *ed = &st->engines[ei];
            if (ph->engines_run != NULL && ph->engines_run[ei] == 0)
                continue;
            const double lo = ed->throttle_min != LV_NO_SLOT ? d->slots[ed->throttle_min].value
                                                             : 0.0;
            const double hi = ed->throttle_max != LV_NO_SLOT ? d->slots[ed->throttle_max].value
                                                             : 1.0;
            if (u->lo < lo || u->hi > hi)
                return FAIL_AT(u->loc, "phase '%s': control 'throttle': [%g, %g] is not within "
                               "the throttle range [%g, %g] of engine '%s' (stage '%s'): the "
                               "engine would clamp what the optimiser flies", p->name, u->lo,
                               u->hi, lo, hi, ed->name, st->name);
        }
    }
    /* the phase's own inputs table is replaced by the controls' (the start samples it): a
     * column of it that is no control would be dropped without a word */
    const lv_table *own = ty->own_inputs != NULL ? ty->own_inputs(ph) : NULL;
    for (size_t c = 0; own != NULL && c < lv_table_n_out(own); c++) {
        const char *col = lv_table_out_name(own, c);
        size_t i = 0;
        while (i < p->n_ctrl && strcmp(ty->controls[p->ctrl[i].input], col) != 0)
            i++;
        if (i == p->n_ctrl) {
            const int law = ty->controls_key != NULL &&
                            strcmp(ty->controls_key(ph), "guidance") == 0;
            return FAIL_AT(p->loc, "phase '%s': its %s table '%s' gives '%s', which is no "
                           "control: the optimiser flies the controls' table instead, so make "
                           "'%s' a control too, or give it as a constant (%s: {%s%s: ...})",
                           p->name, law ? "steering law's" : "inputs", lv_table_name(own),
                           col, col, law && strcmp(col, "throttle") != 0 ? "guidance" : "inputs",
                           col, strcmp(col, "throttle") != 0 ? "_deg" : "");
        }
    }
    return LV_OK;
}

/* 1 when phase k is optimised */
static int optimised(const lv_ocp_def *o, size_t k)
{
    for (size_t j = 0; j < o->n_phases; j++)
        if (o->phases[j].phase == k)
            return 1;
    return 0;
}

lv_status lv_ocp_def_check(lv_mission *m, lv_err *err)
{
    lv_mission_def *d = m->def;
    lv_ocp_def *o = d->ocp;
    char msg[LV_ERR_MSG_MAX - 200];
    lv_status st;
    lv_err e = {LV_OK, ""};
    if (o == NULL)
        return LV_OK;
    for (size_t k = 0; k < o->n_phases; k++)
        if ((st = check_phase(m, &o->phases[k], k, err)) != LV_OK)
            return st;
    for (size_t k = 0; k < o->n_cons; k++) {
        lv_tcon_def *c = &o->cons[k];
        if (lv_targeting_resolve_final(m, c->name, &c->res, &e) != LV_OK)
            return FAIL_AT(c->loc, "%sconstraint: %s", c->path ? "path " : "", e.msg);
        if (c->path && c->res.index == 0)
            return FAIL_AT(c->loc, "path constraint on '%s': the time only grows over a phase: "
                           "constrain its final instead", c->name);
        if (c->path && !optimised(o, c->res.phase))
            return FAIL_AT(c->loc, "path constraint on '%s': phase '%s' is not optimised: a "
                           "path constraint holds at the nodes of an optimised phase (list it "
                           "under phases, or use lvsim target's path constraints)", c->name,
                           d->phases[c->res.phase].name);
        for (size_t j = 0; j < k; j++) {
            const lv_tcon_def *q = &o->cons[j];
            if (q->res.phase == c->res.phase && q->res.index == c->res.index &&
                q->kind == c->kind && q->path == c->path)
                return FAIL_AT(c->loc, "constraint on '%s': the %s is already constrained the "
                               "same way (line %d): give it once", c->name,
                               c->path ? "path" : "final", q->loc.line);
        }
    }
    if (o->cost.present && lv_targeting_resolve_final(m, o->cost.name, &o->cost.res, &e) != LV_OK)
        return FAIL_AT(o->cost.loc, "cost: %s", e.msg);
    return LV_OK;
}
