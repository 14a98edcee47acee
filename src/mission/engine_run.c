/* engine_run.c - a phase's `engines:` (how many of the bottom stage's identical engines run)
 * and `engine_out:` (running engines that stop at a time within the phase), for the model
 * types with engines (their keys lists name them: dof3, dof6; runway `engines:` only).
 * Format: docs/mission-format.md ("Engines a phase runs"). The build applies them in
 * lv_kit_engines (phase_kit.c).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/names.h"
#include "mission/parse_int.h"

/* The kind `name` among the stage's engines, or (size_t)-1. */
static size_t kind_of(const lv_stage_def *s, const char *name)
{
    for (size_t e = 0; e < s->n_engines; e++)
        if (strcmp(s->engines[e].name, name) == 0)
            return e;
    return (size_t)-1;
}

/* "'booster.e1' (9), 'booster.vernier' (2)" */
static void kinds_text(const lv_stage_def *s, char *buf, size_t cap)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t e = 0; e < s->n_engines && used < cap; e++)
        used += (size_t)snprintf(buf + used, cap - used, "%s'%.40s' (count %d)", e ? ", " : "",
                                 s->engines[e].name, s->engines[e].count);
}

static lv_status unknown_kind(const lv_pctx *c, const lv_ynode *at, const char *what,
                              const char *key, const char *name, const lv_stage_def *s)
{
    lv_suggest sug;
    lv_suggest_init(&sug, name);
    for (size_t e = 0; e < s->n_engines; e++)
        lv_suggest_add(&sug, s->engines[e].name);
    char hint[192], kinds[256];
    lv_suggest_text(&sug, hint, sizeof hint);
    kinds_text(s, kinds, sizeof kinds);
    return lv_pk_fail(c, at, "%s: %s: stage '%s' has no engine '%.60s'%s (its engines: %s)",
                      what, key, s->name, name, hint, kinds);
}

/* One running count: an integer 0 .. the kind's count. */
static lv_status run_count(const lv_pctx *c, const lv_ynode *v, const char *what,
                           const lv_stage_def *s, size_t e, int *out)
{
    char key[96];
    snprintf(key, sizeof key, s->n_engines > 1 ? "engines.%.60s" : "engines",
             s->engines[e].name);
    lv_status st = lv_pk_int(c, v, what, key, 0, out);
    if (st != LV_OK)
        return st;
    if (*out > s->engines[e].count)
        return lv_pk_fail(c, v, "%s: %s: %d engines cannot run: stage '%s' has %d of engine "
                          "'%s' (its count)", what, key, *out, s->name, s->engines[e].count,
                          s->engines[e].name);
    return LV_OK;
}

/* engines: N (one engine kind), or {kind: N, ...} naming every kind of the stage. */
static lv_status parse_run(const lv_pctx *c, const lv_ynode *n, const char *what,
                           const lv_stage_def *s, lv_phase_def *ph)
{
    char kinds[256];
    kinds_text(s, kinds, sizeof kinds);
    if ((ph->engines_run = calloc(s->n_engines, sizeof *ph->engines_run)) == NULL)
        return lv_pk_nomem(c);
    if (n->kind == LV_YNODE_SCALAR) {
        if (s->n_engines > 1)
            return lv_pk_fail(c, n, "%s: engines: stage '%s' has %zu kinds of engines (%s): give "
                              "how many of each run, e.g. {%s: %d, ...}", what, s->name,
                              s->n_engines, kinds, s->engines[0].name, s->engines[0].count);
        return run_count(c, n, what, s, 0, &ph->engines_run[0]);
    }
    if (n->kind != LV_YNODE_MAP) {
        char buf[64];
        return lv_pk_fail(c, n, "%s: engines: a count (an integer) or a mapping {engine: count} "
                          "expected, found %s", what, lv_pk_describe(n, buf, sizeof buf));
    }
    for (size_t e = 0; e < s->n_engines; e++)
        ph->engines_run[e] = -1;
    for (size_t i = 0; i + 1 < n->n; i += 2) {
        const char *name = n->kids[i]->text;
        const size_t e = kind_of(s, name);
        if (e == (size_t)-1)
            return unknown_kind(c, n->kids[i], what, "engines", name, s);
        if (ph->engines_run[e] >= 0)
            return lv_pk_fail(c, n->kids[i], "%s: engines: '%s' given twice", what, name);
        lv_status st = run_count(c, n->kids[i + 1], what, s, e, &ph->engines_run[e]);
        if (st != LV_OK)
            return st;
    }
    for (size_t e = 0; e < s->n_engines; e++)
        if (ph->engines_run[e] < 0)
            return lv_pk_fail(c, n, "%s: engines: how many of '%s' run is not given (stage '%s' "
                              "has %s: give each kind's count, 0 for none)", what,
                              s->engines[e].name, s->name, kinds);
    return LV_OK;
}

/* One engine-out {time, count, engine, name}; `index` 0 for a single mapping, else 1-based. */
static lv_status parse_out(const lv_pctx *c, const lv_ynode *n, const char *what,
                           const lv_stage_def *s, const lv_phase_def *ph, size_t index,
                           lv_engine_out_def *o)
{
    static const char *const keys[] = {"time", "count", "engine", "name", NULL};
    char w[LV_WHAT_MAX + 40], slot[LV_NAME_MAX + 48], buf[64];
    if (index > 0)
        snprintf(w, sizeof w, "%.140s, engine_out %zu", what, index);
    else
        snprintf(w, sizeof w, "%.140s, engine_out", what);
    if (n->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, n, "%s: a mapping such as {time: 12.5, count: 1} expected, found %s",
                          w, lv_pk_describe(n, buf, sizeof buf));
    lv_status st = lv_pk_check_map(c, n, w, keys);
    const lv_ynode *v;
    if (st != LV_OK || (st = lv_pk_need(c, n, w, "time", &v)) != LV_OK)
        return st;
    o->loc = lv_pk_loc(n);
    if (index > 0)
        snprintf(slot, sizeof slot, "%s.engine_out.%zu.time", ph->name, index);
    else
        snprintf(slot, sizeof slot, "%s.engine_out.time", ph->name);
    if ((st = lv_pk_slot(c, v, w, "time", slot, "s", LV_RANGE_POS, 0, &o->time)) != LV_OK)
        return st;
    if ((v = lv_pk_get(n, "name")) != NULL && /* the user's name of the event */
        (st = lv_pk_event_label(c, v, w, "name", &o->label)) != LV_OK)
        return st;
    o->count = 1;
    if ((v = lv_pk_get(n, "count")) != NULL && (st = lv_pk_int(c, v, w, "count", 1, &o->count)) !=
                                                   LV_OK)
        return st;
    o->engine = 0;
    if ((v = lv_pk_get(n, "engine")) != NULL) {
        const char *name;
        if ((st = lv_pk_text(c, v, w, "engine", &name)) != LV_OK)
            return st;
        if ((o->engine = kind_of(s, name)) == (size_t)-1)
            return unknown_kind(c, v, w, "engine", name, s);
    } else if (s->n_engines > 1) {
        char kinds[256];
        kinds_text(s, kinds, sizeof kinds);
        return lv_pk_fail(c, n, "%s: 'engine' is missing: stage '%s' has %zu kinds of engines "
                          "(%s): name the one that stops", w, s->name, s->n_engines, kinds);
    }
    return LV_OK;
}

lv_status lv_parse_engine_run(const lv_pctx *c, const lv_ynode *n, lv_phase_def *ph)
{
    const lv_ynode *run = lv_pk_get(n, "engines"), *out = lv_pk_get(n, "engine_out");
    if (run != NULL && lv_yaml_is_null(run))
        run = NULL;
    if (out != NULL && lv_yaml_is_null(out))
        out = NULL;
    if (run == NULL && out == NULL)
        return LV_OK;
    char what[LV_WHAT_MAX];
    snprintf(what, sizeof what, "phase '%s'", ph->name);
    const lv_stage_def *s = &c->m->stages[ph->stages[0]];
    if (s->n_engines == 0)
        return lv_pk_fail(c, lv_pk_key(n, run != NULL ? "engines" : "engine_out"),
                          "%s: %s: stage '%s' (the phase's bottom stage, whose engines burn) has "
                          "no engines", what, run != NULL ? "engines" : "engine_out", s->name);
    lv_status st;
    if (run != NULL && (st = parse_run(c, run, what, s, ph)) != LV_OK)
        return st;
    if (out == NULL)
        return LV_OK;
    const int list = out->kind == LV_YNODE_SEQ;
    const size_t n_out = list ? out->n : 1;
    if (n_out == 0)
        return LV_OK;
    if ((ph->engine_out = calloc(n_out, sizeof *ph->engine_out)) == NULL)
        return lv_pk_nomem(c);
    for (size_t i = 0; i < n_out; i++) {
        const lv_ynode *o = list ? out->kids[i] : out;
        ph->n_engine_out = i + 1;
        if ((st = parse_out(c, o, what, s, ph, list ? i + 1 : 0, &ph->engine_out[i])) != LV_OK)
            return st;
        /* the engines that stop run: no more out than run, per kind */
        const size_t e = ph->engine_out[i].engine;
        const int running = ph->engines_run != NULL ? ph->engines_run[e] : s->engines[e].count;
        int total = 0;
        for (size_t j = 0; j <= i; j++)
            if (ph->engine_out[j].engine == e)
                total += ph->engine_out[j].count;
        if (total > running)
            return lv_pk_fail(c, lv_pk_get(o, "count") ? lv_pk_get(o, "count") : o,
                              "%s, engine_out: %d engine%s of '%s' stop%s, but only %d run%s in "
                              "this phase", what, total, total == 1 ? "" : "s",
                              s->engines[e].name, total == 1 ? "s" : "", running,
                              running == 1 ? "s" : "");
    }
    return LV_OK;
}

lv_status lv_pk_check_throttle(const lv_pctx *c, const lv_phase_def *ph, lv_slot thr,
                                  const char *key)
{
    if (thr == LV_NO_SLOT || c->m->slots[thr].loc.line == 0)
        return LV_OK;
    const lv_slot_def *sd = &c->m->slots[thr];
    const double v = sd->value;
    const lv_stage_def *s = &c->m->stages[ph->stages[0]];
    for (size_t e = 0; e < s->n_engines; e++) {
        const lv_engine_def *ed = &s->engines[e];
        if (ph->engines_run != NULL && ph->engines_run[e] == 0)
            continue; /* none of this kind runs */
        const double lo = ed->throttle_min != LV_NO_SLOT ? c->m->slots[ed->throttle_min].value
                                                         : 0.0;
        const double hi = ed->throttle_max != LV_NO_SLOT ? c->m->slots[ed->throttle_max].value
                                                         : 1.0;
        if (!(v >= lo && v <= hi))
            return lv_fail(c->err, LV_ERR_INPUT, "%s:%d:%d: phase '%s': %s = %g is outside the "
                           "throttle range [%g, %g] of engine '%s' (stage '%s'): a constant "
                           "throttle must be one the engines can give (a throttle law's or a "
                           "table's is clamped and logged as throttle_min / throttle_max events)",
                           c->file, sd->loc.line, sd->loc.column, ph->name, key, v, lo, hi,
                           ed->name, s->name);
    }
    return LV_OK;
}
