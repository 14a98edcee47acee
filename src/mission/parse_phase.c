/* parse_phase.c - a mission file's `phases:`: each phase's common keys (name, model, stages,
 * from, times, end conditions, integrator, set:) and its type's own keys (phase_type.h), then
 * the phase tree ordered and checked (parse_tree.c). Format: docs/mission-format.md
 * ("phases"). */
#include "mission/mission.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/names.h"
#include "mission/parse_int.h"
#include "mission/phase_kit.h"
#include "mission/phase_type.h"

/* ---- phases --------------------------------------------------------------------------- */

static const char *const end_kind_names[] = { "burnout", "altitude", "speed", "apogee",
                                               "impact",  "var",      "time" };

const char *lv_end_kind_name(lv_end_kind k)
{
    return (unsigned)k < 7 ? end_kind_names[k] : "?";
}

/* e->name: the kind's (or variable's) name, "_2", "_3" for the second and third of a kind
 * among the phase's ends prev[0..k). */
static void end_name(size_t k, const lv_end_def *prev, lv_end_def *e)
{
    const char *label = e->kind == LV_END_VAR ? e->var : end_kind_names[e->kind];
    size_t same = 0;
    for (size_t j = 0; j < k; j++)
        same += prev[j].kind == e->kind &&
                (e->kind != LV_END_VAR || strcmp(prev[j].var, e->var) == 0);
    if (same > 0)
        snprintf(e->name, sizeof e->name, "%s_%zu", label, same + 1);
    else
        snprintf(e->name, sizeof e->name, "%s", label);
}

/* The value of end event #k of phase `phase` (of kind e->kind) at `v` (NULL: the ground, 0 m)
 * as slot "<phase>.end.<kind>", "_2", "_3" for the second and third of a kind. */
static lv_status end_slot(const lv_pctx *c, const lv_ynode *v, const char *what,
                          const char *key, const char *phase, size_t k, const lv_end_def *prev,
                          lv_end_def *e)
{
    char slot[2 * LV_NAME_MAX + 300];
    end_name(k, prev, e);
    snprintf(slot, sizeof slot, "%s.end.%s", phase, e->name);
    /* a variable's unit is known once the model is built (mission.c); "" until then */
    const char *unit = e->kind == LV_END_SPEED ? "m/s"
                       : e->kind == LV_END_TIME ? "s"
                       : e->kind == LV_END_VAR  ? (e->deg ? "rad" : "")
                                                : "m";
    /* a time the clock tells from 0; an end on a variable takes its variable's range when the
     * model is built (mission.c) */
    const lv_range range = e->kind == LV_END_SPEED  ? LV_RANGE_NONNEG
                           : e->kind == LV_END_TIME ? (lv_range){1e-9, HUGE_VAL, 0, 0}
                                                    : LV_RANGE_ANY;
    if (v == NULL)
        return lv_pk_slot_default(c, slot, unit, 0.0, range, &e->value);
    return lv_pk_slot(c, v, what, key, slot, unit, range, e->deg, &e->value);
}

/* End event #k of phase `phase`; its value is slot "<phase>.end.<kind>" ("_2", "_3" for the
 * second and third of a kind). */
static lv_status parse_end(const lv_pctx *c, const lv_ynode *n, const char *phase, size_t k,
                           const lv_end_def *prev, lv_end_def *e)
{
    static const char *const words[] = { "burnout", "apogee", "impact", "altitude", "speed",
                                         NULL };
    static const char *const dirs[] = { "rising", "falling", "both", NULL };
    static const lv_dir dir_of[] = { LV_DIR_RISING, LV_DIR_FALLING, LV_DIR_BOTH };
    char what[LV_WHAT_MAX], buf[64];
    const lv_ynode *v;
    size_t i;
    lv_status st;

    snprintf(what, sizeof what, "phase '%s', end event #%zu", phase, k + 1);
    e->loc = lv_pk_loc(n);
    e->value = LV_NO_SLOT;
    e->direction = LV_DIR_FALLING; /* burnout, apogee and impact: always falling */
    if (n->kind == LV_YNODE_SCALAR) {
        if ((st = lv_pk_enum(c, n, what, "end", words, &i)) != LV_OK)
            return st;
        if (i >= 3)
            return lv_pk_fail(c, n, "%s: '%s' needs a value: write {%s: <%s>}", what, n->text, n->text,
                        i == 3 ? "m" : "m/s");
        e->kind = i == 0 ? LV_END_BURNOUT : i == 1 ? LV_END_APOGEE : LV_END_IMPACT;
        if (e->kind == LV_END_IMPACT) /* ground level 0 m */
            return end_slot(c, NULL, what, NULL, phase, k, prev, e);
        end_name(k, prev, e);
        return LV_OK;
    }
    if (n->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, n, "%s: an event name (burnout, apogee, impact) or a mapping such as "
                    "{altitude: 100000} expected, found %s", what, lv_pk_describe(n, buf, sizeof buf));
    /* {altitude: h}, {speed: v}, {impact: h}, {time: dt}, {output: name, value: x}, or any
     * variable of the phase's model as the key: {mach: 1}, {fpa_deg: 0} (checked against the
     * model when the mission is loaded) */
    if ((st = lv_pk_check_map(c, n, what, NULL)) != LV_OK)
        return st;
    const lv_ynode *kind = NULL, *output = lv_pk_get(n, "output");
    for (size_t j = 0; j + 1 < n->n; j += 2) {
        const char *key = n->kids[j]->text;
        if (strcmp(key, "direction") == 0 || strcmp(key, "name") == 0 ||
            (output != NULL && (strcmp(key, "output") == 0 || strcmp(key, "value") == 0)))
            continue;
        if (kind != NULL)
            return lv_pk_fail(c, n->kids[j], "%s: one event per entry ('%s' and '%s'); write them "
                        "as two entries (an entry's other keys: direction, name)", what,
                        kind->text, key);
        kind = n->kids[j];
    }
    if (output != NULL && kind != NULL)
        return lv_pk_fail(c, kind, "%s: an entry with 'output' takes 'value', 'direction' "
                          "and 'name' only, not '%s'", what, kind->text);
    /* the user's name of the event: {propellant_left: 53000, name: MECO}, {burnout, name: ..} */
    if ((v = lv_pk_get(n, "name")) != NULL &&
        (st = lv_pk_event_label(c, v, what, "name", &e->label)) != LV_OK)
        return st;
    if (output != NULL) {
        const char *name;
        if ((st = lv_pk_text(c, output, what, "output", &name)) != LV_OK ||
            (st = lv_pk_need(c, n, what, "value", &v)) != LV_OK)
            return st;
        if (output->len > 255)
            return lv_pk_fail(c, output, "%s: output: a variable name of 1 to 255 characters "
                              "expected", what);
        e->kind = LV_END_VAR;
        char base[256];
        e->deg = lv_pk_strip_deg(name, base, sizeof base);
        if ((e->var = lv_pk_strdup(base)) == NULL)
            return lv_pk_nomem(c);
        if ((st = end_slot(c, v, what, "value", phase, k, prev, e)) != LV_OK)
            return st;
    } else {
        if (kind == NULL)
            return lv_pk_fail(c, n, "%s: which event? add altitude, speed, impact, time, or a "
                              "variable of the model such as {mach: 1}", what);
        v = lv_pk_get(n, kind->text);
        /* a kind without a value in a mapping that names it: {burnout, name: MECO} (YAML
         * reads the bare key as `burnout: null`) */
        const int bare = lv_yaml_is_null(v);
        if (strcmp(kind->text, "burnout") == 0 || strcmp(kind->text, "apogee") == 0) {
            if (!bare)
                return lv_pk_fail(c, kind, "%s: '%s' takes no value: write it as a plain list "
                                  "entry, or {%s, name: NAME} to name it", what, kind->text,
                                  kind->text);
            if (lv_pk_get(n, "direction") != NULL)
                return lv_pk_fail(c, lv_pk_key(n, "direction"), "%s: '%s' has a fixed "
                                  "direction (falling)", what, kind->text);
            e->kind = kind->text[0] == 'b' ? LV_END_BURNOUT : LV_END_APOGEE;
            end_name(k, prev, e);
            return LV_OK;
        }
        if (strcmp(kind->text, "impact") == 0) {
            e->kind = LV_END_IMPACT;
            if (bare) /* {impact, name: touchdown}: the ground, 0 m */
                v = NULL;
        } else if (strcmp(kind->text, "speed") == 0)
            e->kind = LV_END_SPEED;
        else if (strcmp(kind->text, "altitude") == 0)
            e->kind = LV_END_ALTITUDE;
        else if (strcmp(kind->text, "time") == 0)
            e->kind = LV_END_TIME;
        else {
            if (kind->len == 0 || kind->len > 255)
                return lv_pk_fail(c, kind, "%s: a variable name of 1 to 255 characters expected",
                                  what);
            char base[256];
            e->kind = LV_END_VAR;
            e->deg = lv_pk_strip_deg(kind->text, base, sizeof base);
            if ((e->var = lv_pk_strdup(base)) == NULL)
                return lv_pk_nomem(c);
        }
        if ((st = end_slot(c, v, what, kind->text, phase, k, prev, e)) != LV_OK)
            return st;
    }
    if (e->kind == LV_END_TIME) {
        if (lv_pk_get(n, "direction") != NULL)
            return lv_pk_fail(c, lv_pk_key(n, "direction"), "%s: a time end has no direction",
                              what);
        return LV_OK;
    }
    if ((v = lv_pk_get(n, "direction")) != NULL) {
        if ((st = lv_pk_enum(c, v, what, "direction", dirs, &i)) != LV_OK)
            return st;
        if (e->kind == LV_END_IMPACT && dir_of[i] != LV_DIR_FALLING)
            return lv_pk_fail(c, v, "%s: impact is always falling (altitude decreasing through "
                              "%g m)", what, lv_mission_def_value(c->m, e->value));
        e->direction = dir_of[i];
    } else if (e->kind == LV_END_VAR &&
               (strcmp(e->var, "heat_load") == 0 || strcmp(e->var, "heat_load_fm") == 0)) {
        /* the heat loads of dof3 and dof6 only grow: rising, so that a child whose parent's
         * load is already past the value fails as "already passed" instead of never firing
         * (mission.c refuses falling) */
        e->direction = LV_DIR_RISING;
    } else if (e->kind != LV_END_IMPACT) {
        e->direction = LV_DIR_BOTH;
    }
    return LV_OK;
}

static lv_status parse_integrator(const lv_pctx *c, const lv_ynode *n, const char *phase,
                                  lv_phase_def *ph)
{
    static const char *const keys[] = { "method", "tolerance", "intervals", "output_interval",
                                        "fixed_step", NULL };
    /* lv_sim_methods(), then Dymola's name for DOP853 (read as "dop853") */
    static const char *const methods[] = { "dassl", "cvode-adams", "dopri5", "rk4", "euler",
                                           "dp5", "dop853", "auto", "dopri853", NULL };
    enum { METHOD_DEFAULT = 7 /* LV_PHASE_METHOD_DEFAULT, "auto" */, METHOD_DOPRI853 = 8 };
    static const char *const nkeys[3] = { "tolerance", "output_interval", "fixed_step" };
    static const char *const units[3] = { "", "s", "s" };
    static const double defaults[3] = { 1e-9, 0.0, 0.0 };
    char what[LV_WHAT_MAX], slot[LV_NAME_MAX + 48];
    const lv_ynode *v;
    size_t i = METHOD_DEFAULT;
    lv_status st;

    snprintf(what, sizeof what, "phase '%s', integrator", phase);
    ph->intervals = 500;
    if (n != NULL && lv_yaml_is_null(n))
        n = NULL;
    if (n != NULL && (st = lv_pk_check_map(c, n, what, keys)) != LV_OK)
        return st;
    if ((v = lv_pk_get(n, "method")) != NULL &&
        (st = lv_pk_enum(c, v, what, "method", methods, &i)) != LV_OK)
        return st;
    if (i == METHOD_DOPRI853)
        i = 6;
    if ((ph->method = lv_pk_strdup(methods[i])) == NULL)
        return lv_pk_nomem(c);
    lv_slot *out[3] = { &ph->tolerance, &ph->output_interval, &ph->fixed_step };
    for (int j = 0; j < 3; j++) {
        snprintf(slot, sizeof slot, "%s.integrator.%s", phase, nkeys[j]);
        const lv_range r = j == 0 ? LV_RANGE_TOLERANCE : LV_RANGE_NONNEG;
        if ((v = lv_pk_get(n, nkeys[j])) != NULL)
            st = lv_pk_slot(c, v, what, nkeys[j], slot, units[j], r, 0, out[j]);
        else
            st = lv_pk_slot_default(c, slot, units[j], defaults[j], r, out[j]);
        if (st != LV_OK)
            return st;
    }
    if (lv_pk_get(n, "output_interval") != NULL &&
        lv_mission_def_value(c->m, ph->output_interval) > 0.0)
        ph->intervals = 0;
    if ((v = lv_pk_get(n, "intervals")) != NULL) {
        if ((st = lv_pk_int(c, v, what, "intervals", 0, &ph->intervals)) != LV_OK)
            return st;
        if (ph->intervals > 0 && lv_mission_def_value(c->m, ph->output_interval) > 0.0)
            return lv_pk_fail(c, lv_pk_key(n, "intervals"), "%s: give either 'intervals' or "
                        "'output_interval', not both", what);
    }
    return LV_OK;
}

/* set: {name: value}: overrides of the phase model's states and parameters after the
 * hand-off, slots "<phase>.set.<name>" (units known once the model is built: mission.c). */
static lv_status parse_set(const lv_pctx *c, const lv_ynode *n, const char *phase,
                           lv_phase_def *ph)
{
    char what[LV_WHAT_MAX];
    lv_status st;

    snprintf(what, sizeof what, "phase '%s', set", phase);
    if (n == NULL || lv_yaml_is_null(n))
        return LV_OK;
    if ((st = lv_pk_check_map(c, n, what, NULL)) != LV_OK)
        return st;
    const size_t ns = n->n / 2;
    if (ns == 0)
        return LV_OK;
    ph->set_names = calloc(ns, sizeof *ph->set_names);
    ph->set_values = calloc(ns, sizeof *ph->set_values);
    ph->set_locs = calloc(ns, sizeof *ph->set_locs);
    ph->set_deg = calloc(ns, sizeof *ph->set_deg);
    if (ph->set_names == NULL || ph->set_values == NULL || ph->set_locs == NULL ||
        ph->set_deg == NULL)
        return lv_pk_nomem(c);
    for (size_t i = 0; i < ns; i++) {
        const lv_ynode *k = n->kids[2 * i], *v = n->kids[2 * i + 1];
        if (k->len == 0 || k->len > 255)
            return lv_pk_fail(c, k, "%s: a variable name of 1 to 255 characters expected", what);
        char base[256], slot[LV_NAME_MAX + 270];
        const int deg = lv_pk_strip_deg(k->text, base, sizeof base);
        for (size_t j = 0; j < i; j++)
            if (strcmp(ph->set_names[j], base) == 0)
                return lv_pk_fail(c, k, "%s: '%s' set twice (line %d)", what, base,
                            ph->set_locs[j].line);
        snprintf(slot, sizeof slot, "%s.set.%s", phase, base);
        /* its variable's range once the model is built (mission.c) */
        if ((st = lv_pk_slot(c, v, what, k->text, slot, "", LV_RANGE_ANY, deg,
                             &ph->set_values[i])) != LV_OK)
            return st;
        ph->set_locs[i] = lv_pk_loc(k);
        ph->set_deg[i] = (unsigned char)deg;
        if ((ph->set_names[i] = lv_pk_strdup(base)) == NULL)
            return lv_pk_nomem(c);
        ph->n_set = i + 1;
    }
    return LV_OK;
}

static lv_status find_stage(const lv_pctx *c, const lv_ynode *v, const char *what, size_t *idx)
{
    const lv_mission_def *m = c->m;
    const char *s;
    lv_status st = lv_pk_text(c, v, what, "stages", &s);
    if (st != LV_OK)
        return st;
    lv_suggest sug;
    lv_suggest_init(&sug, s);
    for (size_t i = 0; i < m->n_stages; i++) {
        if (strcmp(m->stages[i].name, s) == 0) {
            *idx = i;
            return LV_OK;
        }
        lv_suggest_add(&sug, m->stages[i].name);
    }
    char hint[192];
    lv_suggest_text(&sug, hint, sizeof hint);
    return lv_pk_fail(c, v, "%s: stages: no stage named '%.60s'%s", what, s, hint);
}

/* The keys every phase has; a model type adds its own (phase_type.h). */
static const char *const phase_keys[] = { "name", "model", "stages", "from", "start_time",
                                          "stop_time", "end", "end_name", "integrator", "set",
                                          "alternative", "iip_at", NULL };

/* The most `iip_at:` times a phase may list. */
#define IIP_AT_MAX 1000

/* `iip_at: [60, 120]`: mission times [s] at which a run records the phase's instantaneous
 * impact point; finite, strictly increasing, at most IIP_AT_MAX. Whether the model has the
 * iip_* outputs is checked when the mission is loaded (mission.c). */
static lv_status parse_iip_at(const lv_pctx *c, const lv_ynode *key, const lv_ynode *v,
                              const char *what, lv_phase_def *ph)
{
    char buf[64];
    if (v->kind != LV_YNODE_SEQ || v->n == 0)
        return lv_pk_fail(c, v, "%s: iip_at: a list of mission times in s expected, e.g. "
                          "[60, 120], found %s", what,
                          v->kind == LV_YNODE_SEQ ? "an empty list"
                                                  : lv_pk_describe(v, buf, sizeof buf));
    if (v->n > IIP_AT_MAX)
        return lv_pk_fail(c, v, "%s: iip_at: %zu times, at most %d", what, v->n, IIP_AT_MAX);
    if ((ph->iip_at = calloc(v->n, sizeof *ph->iip_at)) == NULL)
        return lv_pk_nomem(c);
    for (size_t j = 0; j < v->n; j++) {
        lv_status st = lv_pk_num(c, v->kids[j], what, "iip_at", &ph->iip_at[j]);
        if (st != LV_OK)
            return st;
        if (j > 0 && !(ph->iip_at[j] > ph->iip_at[j - 1]))
            return lv_pk_fail(c, v->kids[j], "%s: iip_at: the times must increase: %g s after "
                              "%g s", what, ph->iip_at[j], ph->iip_at[j - 1]);
        ph->n_iip_at = j + 1;
    }
    ph->iip_at_loc = lv_pk_loc(key);
    return LV_OK;
}

/* The user's names of a phase's events are unique within it (`name:` of its ends and
 * engine-outs; `end_name:` is the default of the unnamed ends, not counted). */
static lv_status check_labels(const lv_pctx *c, const lv_ynode *n, const char *what)
{
    const lv_ynode *named[256];
    size_t nn = 0;
    const lv_ynode *lists[2] = {lv_pk_get(n, "end"), lv_pk_get(n, "engine_out")};
    for (int l = 0; l < 2; l++) {
        const lv_ynode *v = lists[l];
        if (v == NULL)
            continue;
        const size_t ni = v->kind == LV_YNODE_SEQ ? v->n : 1;
        for (size_t i = 0; i < ni && nn < 256; i++) {
            const lv_ynode *it = v->kind == LV_YNODE_SEQ ? v->kids[i] : v;
            const lv_ynode *nm = it->kind == LV_YNODE_MAP ? lv_pk_get(it, "name") : NULL;
            if (nm == NULL)
                continue;
            for (size_t j = 0; j < nn; j++)
                if (strcmp(named[j]->text, nm->text) == 0)
                    return lv_pk_fail(c, nm, "%s: event name '%s' given twice (first at line "
                                      "%d): the names of a phase's events are unique", what,
                                      nm->text, named[j]->line);
            named[nn++] = nm;
        }
    }
    return LV_OK;
}

/* Checks the phase's keys: the common ones and its type's. A key that belongs to another
 * model type says which. */
static lv_status check_phase_keys(const lv_pctx *c, const lv_ynode *n, const char *what,
                                  const lv_phase_type *type)
{
    const char *known[64];
    size_t nk = 0;
    for (size_t i = 0; phase_keys[i] != NULL; i++)
        known[nk++] = phase_keys[i];
    for (size_t i = 0; type->keys != NULL && type->keys[i] != NULL && nk < 63; i++)
        known[nk++] = type->keys[i];
    known[nk] = NULL;
    for (size_t i = 0; i + 1 < n->n; i += 2) {
        const char *key = n->kids[i]->text;
        int mine = 0;
        for (size_t j = 0; j < nk && !mine; j++)
            mine = strcmp(known[j], key) == 0;
        if (mine)
            continue;
        char owners[160] = "";
        size_t used = 0, n_own = 0;
        for (const lv_phase_type *const *t = lv_phase_types(); *t != NULL; t++)
            for (size_t j = 0; (*t)->keys != NULL && (*t)->keys[j] != NULL; j++)
                if (strcmp((*t)->keys[j], key) == 0 && used < sizeof owners) {
                    used += (size_t)snprintf(owners + used, sizeof owners - used, "%s%s",
                                             used ? ", " : "", (*t)->name);
                    n_own++;
                }
        if (used > 0)
            return lv_pk_fail(c, n->kids[i], "%s: '%s' applies to the %s model%s only (this "
                              "phase's model is %s)", what, key, owners, n_own > 1 ? "s" : "",
                              type->name);
    }
    return lv_pk_check_map(c, n, what, known);
}

/* Everything but `from`, which needs all names: its node goes to *from. */
static lv_status parse_phase(const lv_pctx *pc, const lv_ynode *n, size_t k, lv_phase_def *ph,
                             const lv_ynode **from)
{
    char what[LV_WHAT_MAX], buf[64], slot[LV_NAME_MAX + 32];
    const lv_ynode *v;
    lv_status st;
    lv_pctx sc = *pc; /* the phase owns its slots (file index; reordered with the phases) */
    sc.owner = LV_OWN_PHASE;
    sc.owner_index = k;
    const lv_pctx *c = &sc;
    const lv_world_kind world = c->m->env.world;

    lv_pk_label(n, "phase", k, what, sizeof what);
    ph->parent = -1;
    ph->t_start = LV_NO_SLOT;
    if (n->kind != LV_YNODE_MAP)
        return lv_pk_check_map(c, n, what, phase_keys);
    ph->loc = lv_pk_loc(n);

    /* the model first: it decides which keys the phase may have */
    const char *models[16];
    size_t nm = 0, i;
    for (const lv_phase_type *const *t = lv_phase_types(); *t != NULL && nm < 15; t++)
        models[nm++] = (*t)->name;
    models[nm] = NULL;
    if ((st = lv_pk_need(c, n, what, "model", &v)) != LV_OK ||
        (st = lv_pk_enum(c, v, what, "model", models, &i)) != LV_OK)
        return st;
    ph->type = lv_phase_types()[i];
    if ((st = lv_kit_resolve_params(c->m, ph, c->err)) != LV_OK)
        return st;
    if (ph->type->world != world)
        return lv_pk_fail(c, v, "%s: model %s needs environment world: %s (this mission's world is "
                    "%s)", what, models[i], world == LV_WORLD_FLAT ? "planet" : "flat",
                    world == LV_WORLD_FLAT ? "flat" : "planet");
    if ((st = check_phase_keys(c, n, what, ph->type)) != LV_OK)
        return st;
    if ((st = lv_pk_need(c, n, what, "name", &v)) != LV_OK ||
        (st = lv_pk_name(c, v, what, 0, &ph->name)) != LV_OK)
        return st;
    lv_pk_label(n, "phase", k, what, sizeof what);

    if ((st = lv_pk_need(c, n, what, "stages", &v)) != LV_OK)
        return st;
    if (v->kind != LV_YNODE_SEQ || v->n == 0)
        return lv_pk_fail(c, v, "%s: stages: a list of stage names (bottom first) expected, found %s",
                    what, v->kind == LV_YNODE_SEQ ? "an empty list" : lv_pk_describe(v, buf, sizeof buf));
    if ((ph->stages = calloc(v->n, sizeof *ph->stages)) == NULL ||
        (ph->stage_locs = calloc(v->n, sizeof *ph->stage_locs)) == NULL)
        return lv_pk_nomem(c);
    for (size_t j = 0; j < v->n; j++) {
        if ((st = find_stage(c, v->kids[j], what, &ph->stages[j])) != LV_OK)
            return st;
        ph->stage_locs[j] = lv_pk_loc(v->kids[j]);
        ph->n_stages = j + 1;
        for (size_t q = 0; q < j; q++)
            if (ph->stages[q] == ph->stages[j])
                return lv_pk_fail(c, v->kids[j], "%s: stages: '%s' listed twice", what,
                            v->kids[j]->text);
    }

    if ((v = lv_pk_get(n, "alternative")) != NULL) {
        static const char *const bools[] = { "false", "true", NULL };
        size_t b;
        if ((st = lv_pk_enum(c, v, what, "alternative", bools, &b)) != LV_OK)
            return st;
        ph->alternative = b == 1;
    }
    const char *parent_name;
    *from = lv_pk_get(n, "from");
    if (*from != NULL && (st = lv_pk_text(c, *from, what, "from", &parent_name)) != LV_OK)
        return st;
    double t0 = *from == NULL ? 0.0 : -INFINITY, t_stop;
    if ((v = lv_pk_get(n, "start_time")) != NULL) {
        snprintf(slot, sizeof slot, "%s.start_time", ph->name);
        if ((st = lv_pk_slot(c, v, what, "start_time", slot, "s", LV_RANGE_ANY, 0,
                             &ph->t_start)) != LV_OK)
            return st;
        t0 = lv_mission_def_value(c->m, ph->t_start);
    }
    /* Without `from` and start_time the phase starts at 0; with `from` at the parent's end,
     * known only when the parent has run. */
    if ((st = lv_pk_need(c, n, what, "stop_time", &v)) != LV_OK ||
        (st = lv_pk_num(c, v, what, "stop_time", &t_stop)) != LV_OK)
        return st;
    if (!(t_stop > t0))
        return lv_pk_fail(c, v, "%s: stop_time %g s must be greater than the start time %g s", what,
                    t_stop, t0);
    snprintf(slot, sizeof slot, "%s.stop_time", ph->name);
    if ((st = lv_pk_slot(c, v, what, "stop_time", slot, "s", LV_RANGE_ANY, 0, &ph->t_stop)) !=
        LV_OK)
        return st;

    v = lv_pk_get(n, "end");
    if (v != NULL && !lv_yaml_is_null(v)) {
        if (v->kind != LV_YNODE_SEQ)
            return lv_pk_fail(c, v, "%s: end: a list of events expected, e.g. [burnout, apogee], "
                        "found %s", what, lv_pk_describe(v, buf, sizeof buf));
        if (v->n > 0) {
            if ((ph->ends = calloc(v->n, sizeof *ph->ends)) == NULL)
                return lv_pk_nomem(c);
            for (size_t j = 0; j < v->n; j++) {
                ph->n_ends = j + 1; /* counted first: a failed entry's name is freed too */
                if ((st = parse_end(c, v->kids[j], ph->name, j, ph->ends, &ph->ends[j])) != LV_OK)
                    return st;
            }
        }
    }
    if ((v = lv_pk_get(n, "end_name")) != NULL) { /* the name of whichever end fires */
        if (ph->n_ends == 0 && ph->type->own_ends == NULL)
            return lv_pk_fail(c, lv_pk_key(n, "end_name"), "%s: end_name names the phase's "
                              "end events, and it has none ('end:')", what);
        if ((st = lv_pk_event_label(c, v, what, "end_name", &ph->end_name)) != LV_OK)
            return st;
    }
    if ((st = parse_integrator(c, lv_pk_get(n, "integrator"), ph->name, ph)) != LV_OK)
        return st;
    if ((v = lv_pk_get(n, "iip_at")) != NULL &&
        (st = parse_iip_at(c, lv_pk_key(n, "iip_at"), v, what, ph)) != LV_OK)
        return st;
    if (ph->type->parse != NULL && (st = ph->type->parse(c, n, ph)) != LV_OK)
        return st;
    if ((st = lv_parse_engine_run(c, n, ph)) != LV_OK)
        return st;
    if ((st = parse_set(c, lv_pk_get(n, "set"), ph->name, ph)) != LV_OK ||
        (st = check_labels(c, n, what)) != LV_OK)
        return st;
    return ph->type->check != NULL ? ph->type->check(c, n, ph) : LV_OK;
}

lv_status lv_parse_phases(const lv_pctx *c, const lv_ynode *n)
{
    lv_mission_def *m = c->m;
    const lv_ynode **from = NULL;
    char buf[64];
    lv_status st;

    if (n->kind != LV_YNODE_SEQ || n->n == 0)
        return lv_pk_fail(c, n, "phases: a list of at least one phase expected, found %s",
                    n->kind == LV_YNODE_SEQ ? "an empty list" : lv_pk_describe(n, buf, sizeof buf));
    if (n->n > (size_t)INT_MAX)
        return lv_pk_fail(c, n, "phases: too many phases");
    m->phases = calloc(n->n, sizeof *m->phases);
    from = calloc(n->n, sizeof *from);
    if (m->phases == NULL || from == NULL) {
        st = lv_pk_nomem(c);
        goto fail;
    }
    m->n_phases = n->n;
    for (size_t i = 0; i < n->n; i++) {
        if ((st = parse_phase(c, n->kids[i], i, &m->phases[i], &from[i])) != LV_OK)
            goto fail;
        for (size_t j = 0; j < i; j++)
            if (strcmp(m->phases[j].name, m->phases[i].name) == 0) {
                st = lv_pk_fail(c, lv_pk_get(n->kids[i], "name"), "phase '%s': duplicate phase name "
                          "(first at line %d)", m->phases[i].name, m->phases[j].loc.line);
                goto fail;
            }
    }
    for (size_t i = 0; i < n->n; i++) {
        if (from[i] == NULL)
            continue;
        lv_suggest sug;
        lv_suggest_init(&sug, from[i]->text);
        for (size_t j = 0; j < n->n && m->phases[i].parent < 0; j++) {
            if (strcmp(m->phases[j].name, from[i]->text) == 0)
                m->phases[i].parent = (int)j;
            lv_suggest_add(&sug, m->phases[j].name);
        }
        if (m->phases[i].parent == (int)i) {
            st = lv_pk_fail(c, from[i], "phase '%s': from: a phase cannot start from itself",
                      m->phases[i].name);
            goto fail;
        }
        if (m->phases[i].parent < 0) {
            char hint[192];
            lv_suggest_text(&sug, hint, sizeof hint);
            st = lv_pk_fail(c, from[i], "phase '%s': from: no phase named '%.60s'%s",
                      m->phases[i].name, from[i]->text, hint);
            goto fail;
        }
    }
    if ((st = lv_parse_check_cycles(c, from)) == LV_OK && (st = lv_parse_order_phases(c)) == LV_OK)
        st = lv_parse_check_tree(c);
fail:
    free(from);
    return st;
}
