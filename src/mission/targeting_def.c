/* targeting_def.c - the `targeting:` section of a mission file (targeting_def.h): parsed with
 * the parse kit, then resolved against the loaded mission (parameters by lv_mission_param_find,
 * finals against each phase's model). Format: docs/targeting.md. */
#define _POSIX_C_SOURCE 200809L

#include "mission/targeting_def.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/names.h"
#include "core/status.h"
#include "core/units.h"
#include "mission/mission_rt.h"

/* ---- parsing --------------------------------------------------------------------------- */

static lv_src_loc loc_of(const lv_ynode *n)
{
    lv_src_loc l = {n->line, n->col};
    return l;
}

static lv_status dup_name(const lv_pctx *c, const lv_ynode *v, const char *what, const char *key,
                          char **out)
{
    const char *s;
    lv_status st = lv_pk_text(c, v, what, key, &s);
    if (st != LV_OK)
        return st;
    if ((*out = strdup(s)) == NULL)
        return lv_pk_nomem(c);
    return LV_OK;
}

/* An optional number: NAN when absent. */
static lv_status opt_num(const lv_pctx *c, const lv_ynode *map, const char *what,
                         const char *key, double *out)
{
    const lv_ynode *v = lv_pk_get(map, key);
    *out = NAN;
    return v != NULL ? lv_pk_num(c, v, what, key, out) : LV_OK;
}

static lv_status parse_var(const lv_pctx *c, const lv_ynode *n, size_t k, lv_tvar_def *v)
{
    static const char *const keys[] = {"name", "min", "max", "start", "scale", "step", NULL};
    char what[LV_WHAT_MAX];
    const lv_ynode *x;
    lv_status st;
    snprintf(what, sizeof what, "targeting: variable #%zu", k + 1);
    if (n->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, n, "%s: a mapping such as {name: P1.guidance.kick_deg, min: 0.5, "
                          "max: 8} expected", what);
    if ((st = lv_pk_check_map(c, n, what, keys)) != LV_OK ||
        (st = lv_pk_need(c, n, what, "name", &x)) != LV_OK ||
        (st = dup_name(c, x, what, "name", &v->name)) != LV_OK)
        return st;
    v->loc = loc_of(x);
    snprintf(what, sizeof what, "targeting: variable '%.60s'", v->name);
    if ((st = lv_pk_need(c, n, what, "min", &x)) != LV_OK ||
        (st = lv_pk_num(c, x, what, "min", &v->lo)) != LV_OK ||
        (st = lv_pk_need(c, n, what, "max", &x)) != LV_OK ||
        (st = lv_pk_num(c, x, what, "max", &v->hi)) != LV_OK ||
        (st = opt_num(c, n, what, "start", &v->start)) != LV_OK ||
        (st = opt_num(c, n, what, "scale", &v->scale)) != LV_OK ||
        (st = opt_num(c, n, what, "step", &v->step)) != LV_OK)
        return st;
    if (!(v->lo < v->hi))
        return lv_pk_fail(c, x, "%s: max %g must be greater than min %g", what, v->hi, v->lo);
    if ((x = lv_pk_get(n, "start")) != NULL)
        v->start_loc = loc_of(x);
    const double w = v->hi - v->lo;
    if ((x = lv_pk_get(n, "scale")) != NULL && !lv_tscale_ok(v->scale, w))
        return lv_pk_fail(c, x, "%s: scale %g is outside [%g, %g], %g to %g times max - min: a "
                          "typical change of the variable, in which it is solved for and from "
                          "which its difference steps follow (default (max - min) / 10)", what,
                          v->scale, LV_TSCALE_REL_MIN * w, LV_TSCALE_REL_MAX * w,
                          LV_TSCALE_REL_MIN, LV_TSCALE_REL_MAX);
    if ((x = lv_pk_get(n, "step")) != NULL && !(v->step > 0.0))
        return lv_pk_fail(c, x, "%s: step must be > 0, found %g", what, v->step);
    if (x != NULL && !(v->step < 0.5 * (v->hi - v->lo)))
        return lv_pk_fail(c, x, "%s: step %g must be less than half the range max - min = %g "
                          "(a difference step crosses the bounds otherwise)", what, v->step,
                          v->hi - v->lo);
    return LV_OK;
}

lv_status lv_tcon_parse(const lv_pctx *c, const lv_ynode *n, const char *sec, size_t k,
                        lv_tcon_def *con)
{
    static const char *const keys[] = {"final", "path", "equal", "min", "max", "tolerance",
                                       "end", NULL};
    static const char *const kinds[] = {"equal", "min", "max"};
    char what[LV_WHAT_MAX];
    const lv_ynode *x, *kv = NULL;
    lv_status st;
    snprintf(what, sizeof what, "%s: constraint #%zu", sec, k + 1);
    if (n->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, n, "%s: a mapping such as {final: P2.peri_alt, equal: 200000, "
                          "tolerance: 100} expected", what);
    if ((st = lv_pk_check_map(c, n, what, keys)) != LV_OK)
        return st;
    const lv_ynode *xp = lv_pk_get(n, "path");
    if (xp != NULL && lv_pk_get(n, "final") != NULL)
        return lv_pk_fail(c, lv_pk_key(n, "path"), "%s: give one of final and path (a final "
                          "value, or the largest or smallest over the phase)", what);
    con->path = xp != NULL;
    if (xp != NULL)
        x = xp;
    else if ((st = lv_pk_need(c, n, what, "final", &x)) != LV_OK)
        return st;
    if ((st = dup_name(c, x, what, con->path ? "path" : "final", &con->name)) != LV_OK)
        return st;
    con->loc = loc_of(x);
    snprintf(what, sizeof what, "%s: %sconstraint on '%.60s'", sec, con->path ? "path " : "",
             con->name);
    if ((x = lv_pk_get(n, "end")) != NULL) {
        if ((st = dup_name(c, x, what, "end", &con->end)) != LV_OK)
            return st;
        con->end_loc = loc_of(x);
    }
    for (int i = 0; i < 3; i++) {
        const lv_ynode *v = lv_pk_get(n, kinds[i]);
        if (v == NULL)
            continue;
        if (kv != NULL)
            return lv_pk_fail(c, lv_pk_key(n, kinds[i]), "%s: give one of equal, min and max "
                              "(a range is two constraints)", what);
        kv = v;
        con->kind = (lv_con_kind)i;
        if ((st = lv_pk_num(c, v, what, kinds[i], &con->value)) != LV_OK)
            return st;
    }
    if (kv == NULL)
        return lv_pk_fail(c, n, con->path ? "%s: give one of min and max (the smallest value "
                          "over the phase at least min, or the largest at most max)"
                          : "%s: give one of equal, min and max", what);
    if (con->path && con->kind == LV_CON_EQUAL)
        return lv_pk_fail(c, lv_pk_key(n, "equal"), "%s: a path constraint bounds the largest "
                          "(max) or the smallest (min) value over the phase: give min or max, "
                          "not equal (an equal value is a final: constraint)", what);
    if ((st = lv_pk_need(c, n, what, "tolerance", &x)) != LV_OK ||
        (st = lv_pk_num(c, x, what, "tolerance", &con->tol)) != LV_OK)
        return st;
    if (!(con->tol > 0.0))
        return lv_pk_fail(c, x, "%s: tolerance must be > 0, found %g", what, con->tol);
    /* residuals are (final - value) / tolerance: finite, and a tolerance a double can resolve
     * at the value (2^-50 of it: a few units in the last place) */
    if (!isfinite(1.0 / con->tol) || !isfinite(con->value / con->tol) ||
        con->tol < 0x1p-50 * fabs(con->value))
        return lv_pk_fail(c, x, "%s: tolerance %g is too small for the value %g: the residual "
                          "(final - value) / tolerance must be finite and a double must resolve "
                          "the tolerance at the value (at least %g)", what, con->tol,
                          con->value, fmax(0x1p-50 * fabs(con->value), 1e-300));
    return LV_OK;
}

lv_status lv_tcost_parse(const lv_pctx *c, const lv_ynode *n, const char *sec, lv_tcost_def *cost)
{
    static const char *const keys[] = {"maximize", "minimize", "scale", "end", NULL};
    char what[LV_WHAT_MAX];
    snprintf(what, sizeof what, "%s: cost", sec);
    lv_status st;
    if (n->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, n, "%s: a mapping such as {maximize: P4.m} expected", what);
    if ((st = lv_pk_check_map(c, n, what, keys)) != LV_OK)
        return st;
    const lv_ynode *mx = lv_pk_get(n, "maximize"), *mn = lv_pk_get(n, "minimize");
    if ((mx == NULL) == (mn == NULL))
        return lv_pk_fail(c, mx && mn ? lv_pk_key(n, "minimize") : n,
                          "%s: give one of maximize and minimize (a final value PHASE.NAME)",
                          what);
    const lv_ynode *v = mx ? mx : mn;
    if ((st = dup_name(c, v, what, mx ? "maximize" : "minimize", &cost->name)) != LV_OK ||
        (st = opt_num(c, n, what, "scale", &cost->scale)) != LV_OK)
        return st;
    if (lv_pk_get(n, "scale") != NULL && !(cost->scale > 0.0))
        return lv_pk_fail(c, lv_pk_get(n, "scale"), "%s: scale must be > 0, found %g", what,
                          cost->scale);
    const lv_ynode *e = lv_pk_get(n, "end");
    if (e != NULL) {
        if ((st = dup_name(c, e, what, "end", &cost->end)) != LV_OK)
            return st;
        cost->end_loc = loc_of(e);
    }
    cost->present = 1;
    cost->maximize = mx != NULL;
    cost->loc = loc_of(v);
    return LV_OK;
}

static lv_status parse_list(const lv_pctx *c, const lv_ynode *n, const char *key, size_t *count,
                            void **items, size_t size)
{
    if (n == NULL || lv_yaml_is_null(n))
        return LV_OK;
    if (n->kind != LV_YNODE_SEQ)
        return lv_pk_fail(c, n, "targeting: %s: a list expected", key);
    if (n->n == 0)
        return LV_OK;
    if ((*items = calloc(n->n, size)) == NULL)
        return lv_pk_nomem(c);
    *count = n->n;
    return LV_OK;
}

lv_status lv_targeting_def_parse(const lv_pctx *c, const lv_ynode *n)
{
    static const char *const keys[] = {"method", "differences", "max_iterations", "xtol",
                                       "ftol", "restarts", "variables", "constraints", "cost",
                                       NULL};
    static const char *const methods[] = {"auto", "newton", "slsqp", "cobyla", NULL};
    static const char *const diffs[] = {"auto", "forward", "central", NULL};
    const char *what = "targeting";
    lv_status st;
    if (n == NULL)
        return LV_OK;
    if (lv_yaml_is_null(n))
        return lv_pk_fail(c, n, "%s: the section is empty: give variables and constraints (or a "
                          "cost), or remove the key", what);
    if ((st = lv_pk_check_map(c, n, what, keys)) != LV_OK)
        return st;
    lv_targeting_def *t = calloc(1, sizeof *t);
    if (t == NULL)
        return lv_pk_nomem(c);
    c->m->targeting = t;
    t->loc = loc_of(n);
    const lv_ynode *v;
    size_t idx;
    if ((v = lv_pk_get(n, "method")) != NULL) {
        if ((st = lv_pk_enum(c, v, what, "method", methods, &idx)) != LV_OK)
            return st;
        t->method = (lv_target_method)idx;
    }
    if ((v = lv_pk_get(n, "differences")) != NULL) {
        if ((st = lv_pk_enum(c, v, what, "differences", diffs, &idx)) != LV_OK)
            return st;
        t->differences = (lv_target_diff)idx;
    }
    if ((v = lv_pk_get(n, "max_iterations")) != NULL) {
        double x;
        if ((st = lv_pk_num(c, v, what, "max_iterations", &x)) != LV_OK)
            return st;
        if (x != floor(x) || x < 1.0 || x > 100000.0)
            return lv_pk_fail(c, v, "%s: max_iterations: an integer from 1 to 100000 expected, "
                              "found %s", what, v->text);
        t->max_iterations = (int)x;
    }
    if ((v = lv_pk_get(n, "restarts")) != NULL) {
        double x;
        if ((st = lv_pk_num(c, v, what, "restarts", &x)) != LV_OK)
            return st;
        if (x != floor(x) || x < 0.0 || x > 100.0)
            return lv_pk_fail(c, v, "%s: restarts: an integer from 0 to 100 expected, found %s",
                              what, v->text);
        t->restarts = (int)x;
    }
    static const char *const tols[] = {"xtol", "ftol"};
    double *tv[] = {&t->xtol, &t->ftol};
    for (int i = 0; i < 2; i++)
        if ((v = lv_pk_get(n, tols[i])) != NULL) {
            if ((st = lv_pk_num(c, v, what, tols[i], tv[i])) != LV_OK)
                return st;
            if (!(*tv[i] > 0.0 && *tv[i] < 1.0))
                return lv_pk_fail(c, v, "%s: %s must be > 0 and < 1, found %g", what, tols[i],
                                  *tv[i]);
        }
    const lv_ynode *vars = lv_pk_get(n, "variables"), *cons = lv_pk_get(n, "constraints");
    if (vars == NULL || lv_yaml_is_null(vars) || (vars->kind == LV_YNODE_SEQ && vars->n == 0))
        return lv_pk_fail(c, vars ? vars : n, "%s: 'variables' needs at least one variable "
                          "({name: PARAMETER, min: .., max: ..})", what);
    if ((st = parse_list(c, vars, "variables", &t->n_vars, (void **)&t->vars, sizeof *t->vars)) !=
            LV_OK ||
        (st = parse_list(c, cons, "constraints", &t->n_cons, (void **)&t->cons,
                         sizeof *t->cons)) != LV_OK)
        return st;
    for (size_t k = 0; k < t->n_vars; k++)
        if ((st = parse_var(c, vars->kids[k], k, &t->vars[k])) != LV_OK)
            return st;
    for (size_t k = 0; k < t->n_cons; k++)
        if ((st = lv_tcon_parse(c, cons->kids[k], "targeting", k, &t->cons[k])) != LV_OK)
            return st;
    if ((v = lv_pk_get(n, "cost")) != NULL && !lv_yaml_is_null(v) &&
        (st = lv_tcost_parse(c, v, "targeting", &t->cost)) != LV_OK)
        return st;
    if (t->n_cons == 0 && !t->cost.present)
        return lv_pk_fail(c, n, "%s: nothing to achieve: give 'constraints', a 'cost' or both",
                          what);
    if (t->method == LV_TARGET_NEWTON && t->cost.present)
        return lv_pk_fail(c, lv_pk_get(n, "method"), "%s: method newton meets constraints and "
                          "optimises no cost: use auto, slsqp or cobyla with a cost", what);
    if (t->method == LV_TARGET_NEWTON && t->n_cons == 0)
        return lv_pk_fail(c, lv_pk_get(n, "method"), "%s: method newton needs constraints",
                          what);
    return LV_OK;
}

void lv_targeting_def_free(lv_targeting_def *t)
{
    if (t == NULL)
        return;
    for (size_t k = 0; k < t->n_vars; k++)
        free(t->vars[k].name);
    free(t->vars);
    for (size_t k = 0; k < t->n_cons; k++) {
        free(t->cons[k].name);
        free(t->cons[k].end);
    }
    free(t->cons);
    free(t->cost.name);
    free(t->cost.end);
    free(t);
}

/* ---- resolution against a loaded mission ------------------------------------------------- */

lv_status lv_targeting_resolve_var(const lv_mission *m, const char *name, double lo, double hi,
                                   double start, double scale, double step, lv_tvar *out,
                                   lv_err *err)
{
    const lv_mission_def *d = m->def;
    size_t i;
    int deg;
    lv_status st = lv_mission_param_find(m, name, &i, &deg, err);
    if (st != LV_OK)
        return lv_fail_prefix(err, st == LV_ERR_NOTFOUND ? LV_ERR_INPUT : st, "variable '%s'",
                              name);
    const lv_slot_def *sd = &d->slots[i];
    const double f = deg ? LV_DEG : 1.0;
    const char *unit = deg ? "deg" : sd->unit;
    if (!(isfinite(lo) && isfinite(hi) && lo < hi))
        return lv_fail(err, LV_ERR_INPUT, "variable '%s': the bounds must be finite with min < "
                       "max, found [%g, %g]", name, lo, hi);
    for (int b = 0; b < 2; b++) {
        const double x = b ? hi : lo;
        if (!lv_range_holds(sd->range, x * f)) {
            char rule[96];
            lv_range shown = sd->range;
            shown.lo /= f;
            shown.hi /= f;
            lv_range_text(shown, rule, sizeof rule);
            return lv_fail(err, LV_ERR_INPUT, "variable '%s': %s %g %s is outside the "
                           "parameter's allowed values (%s)", name, b ? "max" : "min", x, unit,
                           rule);
        }
    }
    const int given = !isnan(start);
    if (!given)
        start = m->defaults[i] / f;
    if (!(start >= lo && start <= hi))
        return lv_fail(err, LV_ERR_INPUT, "variable '%s': the %s %.10g %s is outside [%g, %g]%s",
                       name, given ? "start" : "start (the mission file's value)", start, unit,
                       lo, hi, given ? "" : ": give a start");
    /* NAN: the defaults; any other value is held to its rule, never replaced */
    const double w = hi - lo;
    if (isnan(scale))
        scale = w / 10.0;
    else if (!lv_tscale_ok(scale, w))
        return lv_fail(err, LV_ERR_INPUT, "variable '%s': scale %g %s is outside [%g, %g], %g "
                       "to %g times max - min (NAN: (max - min) / 10)", name, scale, unit,
                       LV_TSCALE_REL_MIN * w, LV_TSCALE_REL_MAX * w, LV_TSCALE_REL_MIN,
                       LV_TSCALE_REL_MAX);
    if (!isnan(step) && !(step > 0.0 && step < 0.5 * w))
        return lv_fail(err, LV_ERR_INPUT, "variable '%s': step %g %s must be > 0 and less than "
                       "half the range max - min = %g (NAN: from the scale)", name, step, unit, w);
    *out = (lv_tvar){i, deg, lo, hi, start, scale, step};
    return LV_OK;
}

lv_status lv_targeting_resolve_final(const lv_mission *m, const char *name, lv_tfinal *out,
                                     lv_err *err)
{
    const lv_mission_def *d = m->def;
    const char *dot = strchr(name, '.');
    if (dot == NULL || dot == name || dot[1] == '\0')
        return lv_fail(err, LV_ERR_INPUT, "'%s': a final value is PHASE.NAME (P2.peri_alt)",
                       name);
    char phase[LV_NAME_MAX + 8], var[128];
    const size_t np = (size_t)(dot - name);
    if (np >= sizeof phase || strlen(dot + 1) >= sizeof var)
        return lv_fail(err, LV_ERR_INPUT, "'%.80s': name too long", name);
    memcpy(phase, name, np);
    phase[np] = '\0';
    snprintf(var, sizeof var, "%s", dot + 1);
    size_t k;
    lv_status st = lv_mission_phase_find(m, phase, &k, err);
    if (st != LV_OK)
        return lv_fail_prefix(err, LV_ERR_INPUT, "'%s'", name);
    const lv_phase_plan *pl = &m->plan[k];
    /* the variable's unit: the phase's model built with the file's values */
    double *prop = calloc(d->n_stages + 1, sizeof *prop);
    if (prop == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    for (size_t s = 0; s < d->n_stages; s++)
        prop[s] = m->defaults[d->stages[s].propellant_mass];
    const lv_build_ctx bc = {d, &m->env, k, m->defaults, prop, NULL, NULL};
    lv_phase_model *pm = NULL;
    st = lv_phase_model_build(&bc, &pm, err);
    free(prop);
    if (st != LV_OK)
        return st;
    int deg = 0;
    size_t idx = (size_t)-1;
    const char *unit = NULL;
    for (int pass = 0; pass < 2 && idx == (size_t)-1; pass++) {
        char look[128];
        snprintf(look, sizeof look, "%s", var);
        if (pass == 1) { /* NAME_deg: an angle in degrees */
            const size_t n = strlen(look);
            if (n < 5 || strcmp(look + n - 4, "_deg") != 0)
                break;
            look[n - 4] = '\0';
        }
        for (size_t i = 0; i < pl->n_final; i++)
            if (strcmp(pl->final_names[i], look) == 0)
                idx = i;
        if (idx == (size_t)-1)
            continue;
        lv_var_kind kind;
        size_t vi;
        if (idx == 0)
            unit = "s"; /* "time" */
        else if (lv_model_find(pm->def, look, &kind, &vi, NULL) == LV_OK)
            unit = kind == LV_VAR_STATE    ? pm->def->states[vi].unit
                   : kind == LV_VAR_OUTPUT ? pm->def->outputs[vi].unit
                                           : "";
        else
            unit = "";
        deg = pass == 1;
        if (deg && strcmp(unit, "rad") != 0) {
            st = lv_fail(err, LV_ERR_INPUT, "'%s': '%s' is not an angle (its unit is '%s'): "
                         "name it without _deg", name, look, unit);
            lv_phase_model_free(pm);
            return st;
        }
    }
    if (idx == (size_t)-1) {
        lv_suggest sg;
        lv_suggest_init(&sg, var);
        for (size_t i = 0; i < pl->n_final; i++)
            lv_suggest_add(&sg, pl->final_names[i]);
        char hint[200];
        lv_suggest_text(&sg, hint, sizeof hint);
        lv_phase_model_free(pm);
        return lv_fail(err, LV_ERR_INPUT, "'%s': phase '%s' (model %s) has no final value '%s'%s",
                       name, phase, d->phases[k].type->name, var, hint);
    }
    out->phase = k;
    out->index = idx;
    out->deg = deg;
    snprintf(out->unit, sizeof out->unit, "%s", deg ? "deg" : unit);
    lv_phase_model_free(pm);
    return LV_OK;
}

lv_status lv_targeting_resolve_end(const lv_mission *m, size_t k, const char *end, int *out,
                                   lv_err *err)
{
    const lv_phase_def *ph = &m->def->phases[k];
    if (end == NULL) {
        *out = ph->n_ends > 0 ? 0 : LV_TEND_STOP_TIME;
        return LV_OK;
    }
    for (size_t j = 0; j < ph->n_ends; j++)
        if (strcmp(ph->ends[j].name, end) == 0) {
            *out = (int)j;
            return LV_OK;
        }
    if (strcmp(end, "stop_time") == 0 || strcmp(end, "any") == 0) {
        *out = end[0] == 's' ? LV_TEND_STOP_TIME : LV_TEND_ANY;
        return LV_OK;
    }
    lv_suggest sg;
    lv_suggest_init(&sg, end);
    char ends[400] = "";
    for (size_t j = 0; j < ph->n_ends; j++) {
        lv_suggest_add(&sg, ph->ends[j].name);
        const size_t n = strlen(ends);
        snprintf(ends + n, sizeof ends - n, "%s%s", n ? ", " : "", ph->ends[j].name);
    }
    lv_suggest_add(&sg, "stop_time");
    lv_suggest_add(&sg, "any");
    char hint[200];
    lv_suggest_text(&sg, hint, sizeof hint);
    return lv_fail(err, LV_ERR_INPUT, "end '%s': phase '%s' has no such end%s (its ends: %s%s"
                   "stop_time; or any)", end, ph->name, hint, ends, ends[0] ? ", " : "");
}

const char *lv_targeting_end_name(const lv_mission *m, size_t k, int index)
{
    const lv_phase_def *ph = &m->def->phases[k];
    if (index >= 0 && (size_t)index < ph->n_ends)
        return ph->ends[index].name;
    return index == LV_TEND_STOP_TIME ? "stop_time" : index == LV_TEND_ANY ? "any" : "-";
}

/* The `end:` of a constraint or the cost (loc: where it is written), resolved against its
 * phase; one named end per phase: a phase ends one way. `named` [n_phases] holds the index of
 * the constraint (+1; n_cons + 1 for the cost) that named each phase's end first. */
static lv_status check_end(lv_mission *m, const char *what, const char *final, size_t phase,
                           const char *end, lv_src_loc loc, int *index, size_t *named,
                           size_t self, lv_err *e)
{
    lv_targeting_def *t = m->def->targeting;
    lv_status st = lv_targeting_resolve_end(m, phase, end, index, e);
    if (st != LV_OK)
        return lv_fail_prefix(e, st, "%s:%d:%d: targeting: %s on '%s'", m->def->path,
                              loc.line, loc.column, what, final);
    if (end == NULL)
        return LV_OK;
    if (named[phase] == 0) {
        named[phase] = self + 1;
        return LV_OK;
    }
    const size_t o = named[phase] - 1;
    const int other = o < t->n_cons ? t->cons[o].end_index : t->cost.end_index;
    if (other == *index)
        return LV_OK;
    const lv_src_loc ol = o < t->n_cons ? t->cons[o].end_loc : t->cost.end_loc;
    return lv_fail(e, LV_ERR_INPUT, "%s:%d:%d: targeting: %s on '%s': end '%s', but line %d "
                   "assumes phase '%s' ends by '%s': a phase ends one way (name its end once)",
                   m->def->path, loc.line, loc.column, what, final, end, ol.line,
                   m->def->phases[phase].name, lv_targeting_end_name(m, phase, other));
}

lv_status lv_targeting_def_check(lv_mission *m, lv_err *err)
{
    lv_mission_def *d = m->def;
    lv_targeting_def *t = d->targeting;
    lv_status st = LV_OK;
    lv_err e = {LV_OK, ""};
    if (t == NULL)
        return LV_OK;
    for (size_t k = 0; k < t->n_vars && st == LV_OK; k++) {
        lv_tvar_def *v = &t->vars[k];
        lv_src_loc l = v->loc;
        st = lv_targeting_resolve_var(m, v->name, v->lo, v->hi, v->start, v->scale, v->step,
                                      &v->res, &e);
        const char *by = NULL;
        if (st == LV_OK && lv_mission_def_slot_overridden(d, v->res.slot, &by))
            st = lv_fail(&e, LV_ERR_INPUT, "variable '%s' has no effect: phase '%s' starts from "
                         "its reference (start: reference), whose first row replaces it "
                         "(vary the reference, or start: parent)", v->name, by);
        if (st == LV_OK && d->slots[v->res.slot].loc.line <= 0)
            st = lv_fail(&e, LV_ERR_INPUT, "variable '%s': the mission file does not write "
                         "this parameter (its value is a default): write it in the file so "
                         "that the converged mission can carry the value", v->name);
        for (size_t j = 0; j < k && st == LV_OK; j++)
            if (t->vars[j].res.slot == v->res.slot)
                st = lv_fail(&e, LV_ERR_INPUT, "variable '%s': the parameter is already a "
                             "variable (line %d)", v->name, t->vars[j].loc.line);
        if (st == LV_ERR_INPUT && v->start_loc.line > 0 && strstr(e.msg, "the start") != NULL)
            l = v->start_loc;
        if (st != LV_OK)
            st = lv_fail_prefix(&e, st, "%s:%d:%d: targeting", d->path, l.line, l.column);
    }
    for (size_t k = 0; k < t->n_cons && st == LV_OK; k++) {
        lv_tcon_def *c = &t->cons[k];
        if ((st = lv_targeting_resolve_final(m, c->name, &c->res, &e)) != LV_OK)
            st = lv_fail_prefix(&e, st, "%s:%d:%d: targeting: %sconstraint", d->path,
                                c->loc.line, c->loc.column, c->path ? "path " : "");
        if (st == LV_OK && c->path && c->res.index == 0)
            st = lv_fail(&e, LV_ERR_INPUT, "%s:%d:%d: targeting: path constraint on '%s': the "
                         "time only grows over a phase: its largest is the final time (a "
                         "final: constraint), its smallest the start", d->path, c->loc.line,
                         c->loc.column, c->name);
        /* the same final twice as `equal`, or twice as `min` (`max`): one is enough (two equal
         * rows make the sensitivities singular) */
        for (size_t j = 0; j < k && st == LV_OK; j++) {
            const lv_tcon_def *o = &t->cons[j];
            if (o->res.phase == c->res.phase && o->res.index == c->res.index &&
                o->kind == c->kind && o->path == c->path)
                st = lv_fail(&e, LV_ERR_INPUT, "%s:%d:%d: targeting: constraint on '%s': the "
                             "%s is already constrained the same way (line %d): give it once",
                             d->path, c->loc.line, c->loc.column, c->name,
                             c->path ? "path" : "final", o->loc.line);
        }
    }
    if (st == LV_OK && t->cost.present &&
        (st = lv_targeting_resolve_final(m, t->cost.name, &t->cost.res, &e)) != LV_OK)
        st = lv_fail_prefix(&e, st, "%s:%d:%d: targeting: cost", d->path, t->cost.loc.line,
                            t->cost.loc.column);
    /* the end each read phase is assumed to end by */
    size_t *named = st == LV_OK ? calloc(d->n_phases + 1, sizeof *named) : NULL;
    if (st == LV_OK && named == NULL)
        st = lv_fail(&e, LV_ERR_NOMEM, "out of memory");
    for (size_t k = 0; k < t->n_cons && st == LV_OK; k++) {
        lv_tcon_def *c = &t->cons[k];
        st = check_end(m, "constraint", c->name, c->res.phase, c->end,
                       c->end ? c->end_loc : c->loc, &c->end_index, named, k, &e);
    }
    if (st == LV_OK && t->cost.present)
        st = check_end(m, "cost", t->cost.name, t->cost.res.phase, t->cost.end,
                       t->cost.end ? t->cost.end_loc : t->cost.loc, &t->cost.end_index, named,
                       t->n_cons, &e);
    free(named);
    return st == LV_OK ? LV_OK : lv_fail(err, st, "%s", e.msg);
}

double lv_targeting_path_extremum(const double *t, const double *y, size_t n, int want_max,
                                  double *t_out)
{
    const double sg = want_max ? 1.0 : -1.0;
    size_t best = (size_t)-1;
    for (size_t i = 0; i < n; i++)
        if (!isnan(y[i]) && (best == (size_t)-1 || sg * y[i] > sg * y[best]))
            best = i;
    if (best == (size_t)-1) {
        if (t_out != NULL)
            *t_out = NAN;
        return NAN;
    }
    double v = y[best], tv = t[best];
    if (best > 0 && best + 1 < n && t[best - 1] < t[best] && t[best] < t[best + 1] &&
        !isnan(y[best - 1]) && !isnan(y[best + 1])) {
        /* the parabola through (a, fa), (b, fb), (c, fc), in sg-scaled values: its vertex
         * (Brent's parabolic step; Press et al., Numerical Recipes, 3rd ed., eq. 10.3.1) */
        const double a = t[best - 1], b = t[best], c = t[best + 1];
        const double fa = sg * y[best - 1], fb = sg * y[best], fc = sg * y[best + 1];
        const double p = (b - a) * (b - a) * (fb - fc) - (b - c) * (b - c) * (fb - fa);
        const double q = (b - a) * (fb - fc) - (b - c) * (fb - fa);
        if (q != 0.0) {
            const double x = b - 0.5 * p / q;
            if (x > a && x < c) {
                const double fx = fa * (x - b) * (x - c) / ((a - b) * (a - c)) +
                                  fb * (x - a) * (x - c) / ((b - a) * (b - c)) +
                                  fc * (x - a) * (x - b) / ((c - a) * (c - b));
                if (fx > fb) {
                    v = sg * fx;
                    tv = x;
                }
            }
        }
    }
    if (t_out != NULL)
        *t_out = tv;
    return v;
}
