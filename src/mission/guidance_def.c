/* guidance_def.c - `guidance:` and `throttle:` of a phase (guidance_def.h): a generic reader of
 * the registered laws' key tables (src/dynamics/guid_laws.c). It knows the file's shapes
 * (`{law: NAME, ..}`; the throttle's `off`, `{KEY: ..}`, `{NAME: {..}}`) and no law.
 */
#include "mission/guidance_def.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynamics/guidance.h"
#include "lvsim/lv_units.h"

#define KNOWN_MAX (2 * LV_LAW_KEYS_MAX + 8)

/* The keys of a law's mapping (with the _deg forms of angles), NULL-terminated: `first`
 * (may be NULL), the kind's common keys, the law's keys, then `extra` (NULL-terminated, may be
 * NULL). deg[] holds the _deg names. */
typedef struct known_keys {
    const char *keys[KNOWN_MAX + 1];
    char deg[KNOWN_MAX][48];
    size_t n, nd;
} known_keys;

static void known_add(known_keys *kk, const lv_law_key *k)
{
    if (kk->n + 2 > KNOWN_MAX)
        return;
    kk->keys[kk->n++] = k->name;
    if (k->flags & LV_KEY_ANGLE) {
        snprintf(kk->deg[kk->nd], sizeof kk->deg[0], "%s_deg", k->name);
        kk->keys[kk->n++] = kk->deg[kk->nd++];
    }
}

static void known_make(known_keys *kk, const char *first, const lv_law *law,
                       const char *const *extra)
{
    kk->n = kk->nd = 0;
    if (first != NULL)
        kk->keys[kk->n++] = first;
    size_t nc;
    const lv_law_key *common = lv_laws_common_keys(law->kind, &nc);
    for (size_t i = 0; i < nc; i++)
        known_add(kk, &common[i]);
    for (size_t i = 0; i < law->n_keys; i++)
        known_add(kk, &law->keys[i]);
    for (size_t i = 0; extra != NULL && extra[i] != NULL && kk->n < KNOWN_MAX; i++)
        kk->keys[kk->n++] = extra[i];
    kk->keys[kk->n] = NULL;
}

/* The key node of key k as written (NAME or NAME_deg), or NULL; *text its name. */
static const lv_ynode *written(const lv_ynode *n, const lv_law_key *k, const char **text)
{
    const lv_ynode *key = lv_pk_key(n, k->name);
    if (key == NULL && (k->flags & LV_KEY_ANGLE)) {
        char deg[48];
        snprintf(deg, sizeof deg, "%s_deg", k->name);
        key = lv_pk_key(n, deg);
    }
    if (text != NULL)
        *text = key != NULL ? key->text : k->name;
    return key;
}

/* The value node of key `name` of law (or a common key) as written, or NULL. */
static const lv_ynode *value_of(const lv_ynode *n, const lv_law *law, const char *name)
{
    int deg, common;
    const lv_law_key *k = lv_guid_key_find(law, law->kind, name, &deg, &common);
    const lv_ynode *key = k != NULL ? written(n, k, NULL) : NULL;
    return key != NULL ? lv_pk_get(n, key->text) : NULL;
}

/* Number key k of map n as slot "<phase>.<group>.<name>" (or NAME_deg in degrees); absent:
 * its default (a slot), nothing (optional), or an error (required). */
static lv_status num(const lv_pctx *c, const lv_ynode *n, const char *what, const char *phase,
                     const char *group, const lv_law_key *k, int required, lv_slot *out)
{
    char deg[48], slot[LV_NAME_MAX + 96];
    snprintf(deg, sizeof deg, "%s_deg", k->name);
    snprintf(slot, sizeof slot, "%s.%s.%s", phase, group, k->name);
    const int ang = (k->flags & LV_KEY_ANGLE) != 0;
    const lv_range range = {k->lo, k->hi, (unsigned char)k->lo_open, (unsigned char)k->hi_open};
    const lv_ynode *v = lv_pk_get(n, k->name), *vd = ang ? lv_pk_get(n, deg) : NULL;
    *out = LV_NO_SLOT;
    if (v != NULL && vd != NULL)
        return lv_pk_fail(c, lv_pk_key(n, deg), "%s: '%s' and '%s' given both", what, k->name,
                          deg);
    if (v != NULL || vd != NULL)
        return lv_pk_slot(c, v ? v : vd, what, v ? k->name : deg, slot, k->unit, range,
                          vd != NULL, out);
    if (required)
        return lv_pk_fail(c, n, "%s: '%s' is required%s", what, ang ? deg : k->name,
                          ang ? " (or the same in rad without _deg)" : "");
    if ((k->flags & LV_KEY_OPTIONAL) || isnan(k->dflt))
        return LV_OK;
    return lv_pk_slot_default(c, slot, k->unit, k->dflt, range, out);
}

/* The words of a frame mask: "aero", "local or inertial". */
static void mask_words(unsigned mask, const char *const *words, char *buf, size_t cap)
{
    size_t used = 0;
    buf[0] = '\0';
    for (unsigned i = 0; words[i] != NULL && i < 32; i++)
        if ((mask & (1u << i)) && used < cap)
            used += (size_t)snprintf(buf + used, cap - used, "%s%s", used ? " or " : "",
                                     words[i]);
}

/* The law's frame: the value of its choice key (0 without one). */
static int frame_of(const lv_law_def *d)
{
    for (size_t i = 0; i < d->law->n_keys; i++)
        if (d->law->keys[i].type == LV_KEY_CHOICE)
            return d->choice[i];
    return 0;
}

/* A 3-DoF key (LV_KEY_DOF3) written in another model's phase. */
static lv_status refuse_dof3(const lv_pctx *c, const lv_ynode *n, const char *what,
                             const lv_law *law)
{
    if (law->dof3_only != NULL)
        return lv_pk_fail(c, n, "%s is for 3-DoF phases: %s", what, law->dof3_only);
    for (size_t i = 0; i < law->n_keys; i++) {
        const char *text;
        const lv_ynode *key = written(n, &law->keys[i], &text);
        if (key != NULL && (law->keys[i].flags & LV_KEY_DOF3))
            return lv_pk_fail(c, key, "%s: '%s' %s: not in a dof6 phase", what, text,
                              law->dof3_why);
    }
    return LV_OK;
}

/* Keys written that do not apply in the frame chosen (k->frames). */
static lv_status refuse_frames(const lv_pctx *c, const lv_ynode *n, const char *what,
                               const lv_law_def *d)
{
    const lv_law *law = d->law;
    const lv_law_key *fk = NULL; /* the law's choice key (its frame) */
    const int frame = frame_of(d);
    for (size_t i = 0; i < law->n_keys; i++)
        if (law->keys[i].type == LV_KEY_CHOICE)
            fk = &law->keys[i];
    for (size_t i = 0; i < law->n_keys; i++) {
        const lv_law_key *k = &law->keys[i];
        const char *text;
        const lv_ynode *key = written(n, k, &text);
        if (key == NULL || fk == NULL || k->frames == 0 || (k->frames & (1u << frame)))
            continue;
        char its[64], takes[128] = "";
        mask_words(k->frames, fk->choices, its, sizeof its);
        size_t used = 0;
        for (size_t j = 0; j < law->n_keys; j++)
            if (law->keys[j].frames & (1u << frame) && used < sizeof takes)
                used += (size_t)snprintf(takes + used, sizeof takes - used, "%s%s",
                                         used ? ", " : "", law->keys[j].name);
        return lv_pk_fail(c, key, "%s: '%s' is an angle of the %s frame; frame %s takes %s",
                          what, text, its, fk->choices[frame], takes);
    }
    return LV_OK;
}

/* The law's values from the file (m: the slots' values) or a run (vals). */
static void make_par(const lv_law_def *d, const double *vals, const lv_mission_def *m,
                     lv_law_par *par)
{
    lv_guid_par_defaults(d->law, par);
    for (size_t i = 0; i < d->law->n_keys; i++) {
        const lv_law_key *k = &d->law->keys[i];
        char *at = (char *)par->d + k->offset;
        if (k->type == LV_KEY_NUMBER && d->slot[i] != LV_NO_SLOT) {
            const double v = vals != NULL ? vals[d->slot[i]] : m->slots[d->slot[i]].value;
            memcpy(at, &v, sizeof v);
        } else if (k->type == LV_KEY_CHOICE) {
            memcpy(at, &d->choice[i], sizeof d->choice[i]);
        } else if (k->type == LV_KEY_TABLE) {
            const lv_table *t = d->table[i];
            memcpy(at, &t, sizeof t);
        }
    }
}

/* The keys of law d->law in map n (keys already checked): choices, numbers as slots of
 * `group`, tables; then the law's own check on the file's values. */
static lv_status parse_keys(const lv_pctx *c, const lv_ynode *n, const char *what,
                            const char *phase, const char *group, int dof3, lv_law_def *d)
{
    const lv_law *law = d->law;
    lv_status st;
    for (size_t i = 0; i < law->n_keys; i++) {
        const lv_law_key *k = &law->keys[i];
        d->slot[i] = LV_NO_SLOT;
        d->choice[i] = k->type == LV_KEY_CHOICE ? (int)k->dflt : 0;
        const lv_ynode *v = lv_pk_get(n, k->name);
        size_t idx;
        if (k->type == LV_KEY_CHOICE && v != NULL) {
            if ((st = lv_pk_enum(c, v, what, k->name, k->choices, &idx)) != LV_OK)
                return st;
            d->choice[i] = (int)idx;
        }
    }
    if ((st = refuse_frames(c, n, what, d)) != LV_OK)
        return st;
    for (size_t i = 0; i < law->n_keys; i++) {
        const lv_law_key *k = &law->keys[i];
        if (k->type != LV_KEY_NUMBER)
            continue;
        if (k->frames != 0 && !(k->frames & (1u << frame_of(d))))
            continue; /* another frame's (refused above when written) */
        const lv_ynode *alt = k->instead_of != NULL ? lv_pk_key(n, k->instead_of) : NULL;
        if (alt != NULL) {
            if (written(n, k, NULL) != NULL)
                return lv_pk_fail(c, alt, "%s: %s and %s given both", what, k->name,
                                  k->instead_of);
            continue;
        }
        if (k->needs != NULL && value_of(n, law, k->needs) == NULL) {
            const lv_ynode *key = written(n, k, NULL);
            if (key != NULL)
                return lv_pk_fail(c, key, "%s: %s applies to %s", what, k->name, k->needs);
            continue;
        }
        const int required = isnan(k->dflt) && !(k->flags & LV_KEY_OPTIONAL);
        if ((st = num(c, n, what, phase, group, k, required, &d->slot[i])) != LV_OK)
            return st;
    }
    for (size_t i = 0; i < law->n_keys; i++) {
        const lv_law_key *k = &law->keys[i];
        const lv_ynode *v = lv_pk_get(n, k->name);
        if (k->type == LV_KEY_TABLE && v != NULL &&
            (st = lv_pk_table(c, lv_pk_key(n, k->name), v, what, LV_EXTRAP_CLAMP,
                              &d->table_file[i], &d->table_var[i], &d->table[i])) != LV_OK)
            return st;
    }
    if (law->check == NULL)
        return dof3 ? LV_OK : refuse_dof3(c, n, what, law);
    lv_law_par par;
    make_par(d, NULL, c->m, &par);
    lv_law_at at = {NULL, LV_AT_MAP};
    if ((st = law->check(&par, &at, c->err)) == LV_OK)
        return dof3 ? LV_OK : refuse_dof3(c, n, what, law);
    char msg[sizeof c->err->msg];
    snprintf(msg, sizeof msg, "%s", c->err->msg);
    const lv_ynode *node = NULL;
    if (at.key != NULL) {
        int deg, common;
        const lv_law_key *k = lv_guid_key_find(law, law->kind, at.key, &deg, &common);
        const lv_ynode *key = k != NULL ? written(n, k, NULL) : NULL;
        node = key == NULL ? NULL : at.node == LV_AT_KEY ? key : lv_pk_get(n, key->text);
    }
    return lv_pk_fail(c, node != NULL ? node : n, "%s: %s", what, msg);
}

static lv_status parse_steering(const lv_pctx *c, const lv_ynode *n, const char *phase,
                                int has_aero, int dof3, lv_guidance_def *g)
{
    char what[LV_WHAT_MAX];
    const lv_ynode *v;
    size_t w = 0;
    lv_status st;
    snprintf(what, sizeof what, "phase '%s', guidance", phase);
    if (n->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, n, "%s: a mapping such as {law: gravity_turn, ...} expected", what);
    const char *words[65];
    const lv_law *laws[64];
    size_t nw = 0;
    for (const lv_law *const *l = lv_guid_laws(LV_LAW_STEERING); *l != NULL && nw < 64; l++)
        if ((*l)->form == LV_LAW_FORM_NAMED)
            laws[nw] = *l, words[nw++] = (*l)->name;
    words[nw] = NULL;
    if ((st = lv_pk_check_map(c, n, what, NULL)) != LV_OK ||
        (st = lv_pk_need(c, n, what, "law", &v)) != LV_OK ||
        (st = lv_pk_enum(c, v, what, "law", words, &w)) != LV_OK)
        return st;
    const lv_law *law = laws[w];
    known_keys kk;
    known_make(&kk, "law", law, NULL);
    snprintf(what, sizeof what, "phase '%s', guidance '%s'", phase, law->name);
    if ((st = lv_pk_check_map(c, n, what, kk.keys)) != LV_OK)
        return st;
    g->steer.law = law;
    size_t nc;
    const lv_law_key *common = lv_laws_common_keys(LV_LAW_STEERING, &nc);
    lv_slot *target[2] = {&g->target_lat, &g->target_lon};
    for (size_t i = 0; i < nc && i < 2; i++)
        if ((st = num(c, n, what, phase, "guidance", &common[i], 0, target[i])) != LV_OK)
            return st;
    if ((g->target_lat == LV_NO_SLOT) != (g->target_lon == LV_NO_SLOT))
        return lv_pk_fail(c, n, "%s: give both target_lat and target_lon (or neither: the "
                          "launch site)", what);
    if (law->needs_aero != NULL && !has_aero)
        return lv_pk_fail(c, v, "%s: the %s law %s: the phase needs an aerodynamic dataset "
                          "(aero:)", what, law->name, law->needs_aero);
    return parse_keys(c, n, what, phase, "guidance", dof3, &g->steer);
}

/* The throttle laws written as a word (`throttle: off`), as the nominal's keys, nested. */
static const lv_law *throttle_form(lv_law_form form, size_t i)
{
    for (const lv_law *const *l = lv_guid_laws(LV_LAW_THROTTLE); *l != NULL; l++)
        if ((*l)->form == form && i-- == 0)
            return *l;
    return NULL;
}

static lv_status parse_throttle(const lv_pctx *c, const lv_ynode *n, const char *phase,
                                lv_guidance_def *g)
{
    char what[LV_WHAT_MAX], words[128] = "";
    lv_status st;
    snprintf(what, sizeof what, "phase '%s', throttle", phase);
    size_t used = 0;
    const lv_law *l;
    for (size_t i = 0; (l = throttle_form(LV_LAW_FORM_WORD, i)) != NULL; i++) {
        if (n->kind == LV_YNODE_SCALAR && strcmp(n->text, l->name) == 0) {
            g->thr.law = l;
            return LV_OK;
        }
        if (used < sizeof words)
            used += (size_t)snprintf(words + used, sizeof words - used, "'%s' or ", l->name);
    }
    if (n->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, n, "%s: %sa mapping such as {g_limit: 4.5, q_max: 35000} expected",
                          what, words);
    const lv_law *keys_law = throttle_form(LV_LAW_FORM_KEYS, 0);
    const char *nested[16];
    size_t nn = 0;
    for (; nn < 15 && (l = throttle_form(LV_LAW_FORM_NESTED, nn)) != NULL; nn++)
        nested[nn] = l->name;
    nested[nn] = NULL;
    known_keys kk;
    known_make(&kk, NULL, keys_law, nested);
    if ((st = lv_pk_check_map(c, n, what, kk.keys)) != LV_OK)
        return st;
    for (size_t i = 0; i < nn; i++) {
        const lv_ynode *sub = lv_pk_get(n, nested[i]);
        if (sub == NULL)
            continue;
        l = throttle_form(LV_LAW_FORM_NESTED, i);
        for (size_t j = 0; kk.keys[j] != NULL; j++)
            if (strcmp(kk.keys[j], l->name) != 0 && lv_pk_get(n, kk.keys[j]) != NULL)
                return lv_pk_fail(c, lv_pk_key(n, kk.keys[j]), "%s: the %s law sets the "
                                  "throttle itself: '%s' does not go with it", what, l->name,
                                  kk.keys[j]);
        char lwhat[LV_WHAT_MAX + 16], shape[160] = "";
        snprintf(lwhat, sizeof lwhat, "%s, %s", what, l->name);
        size_t su = 0;
        for (size_t j = 0; j < l->n_keys && su < sizeof shape; j++)
            su += (size_t)snprintf(shape + su, sizeof shape - su, "%s%s: %s", j ? ", " : "",
                                   l->keys[j].name, l->keys[j].type != LV_KEY_NUMBER ? "-"
                                   : l->keys[j].unit[0]                 ? l->keys[j].unit
                                                                        : "1");
        if (sub->kind != LV_YNODE_MAP)
            return lv_pk_fail(c, sub, "%s: a mapping {%s} expected", lwhat, shape);
        known_keys lk;
        known_make(&lk, NULL, l, NULL);
        if ((st = lv_pk_check_map(c, sub, lwhat, lk.keys)) != LV_OK)
            return st;
        char group[64];
        snprintf(group, sizeof group, "throttle.%s", l->name);
        g->thr.law = l;
        return parse_keys(c, sub, lwhat, phase, group, 1, &g->thr);
    }
    g->thr.law = keys_law;
    return parse_keys(c, n, what, phase, "throttle", 1, &g->thr);
}

lv_status lv_guidance_def_parse(const lv_pctx *c, const lv_ynode *guidance,
                                const lv_ynode *throttle, const char *phase, int has_aero,
                                int dof3, lv_guidance_def *g)
{
    lv_status st;
    if (guidance != NULL && !lv_yaml_is_null(guidance) &&
        (st = parse_steering(c, guidance, phase, has_aero, dof3, g)) != LV_OK)
        return st;
    if (throttle != NULL && !lv_yaml_is_null(throttle) &&
        (st = parse_throttle(c, throttle, phase, g)) != LV_OK)
        return st;
    return LV_OK;
}

void lv_guidance_def_make(const lv_guidance_def *g, const double *vals, lv_steering *s,
                          lv_throttle_cfg *t)
{
    if (g->steer.law != NULL) {
        s->law = g->steer.law;
        make_par(&g->steer, vals, NULL, &s->par);
        s->target_lat = g->target_lat == LV_NO_SLOT ? NAN : vals[g->target_lat];
        s->target_lon = g->target_lon == LV_NO_SLOT ? NAN : vals[g->target_lon];
    }
    if (g->thr.law != NULL) {
        t->law = g->thr.law;
        make_par(&g->thr, vals, NULL, &t->par);
    }
}

int lv_guidance_def_gives_throttle(const lv_guidance_def *g)
{
    if (g->steer.law == NULL || g->steer.law->gives_throttle == NULL)
        return 0;
    lv_law_par par; /* the tables are what matters: the defaults for the numbers */
    lv_law_def d = g->steer;
    for (size_t i = 0; i < LV_LAW_KEYS_MAX; i++)
        d.slot[i] = LV_NO_SLOT;
    make_par(&d, NULL, NULL, &par);
    return g->steer.law->gives_throttle(&par);
}

lv_table **lv_guidance_def_attitude_table(lv_guidance_def *g)
{
    if (g->steer.law == NULL || strcmp(g->steer.law->name, "attitude") != 0 ||
        frame_of(&g->steer) == LV_FRAME_AERO)
        return NULL;
    for (size_t i = 0; i < g->steer.law->n_keys; i++)
        if (g->steer.law->keys[i].type == LV_KEY_TABLE)
            return &g->steer.table[i];
    return NULL;
}

double lv_guidance_def_steer_number(const lv_guidance_def *g, const char *key,
                                    const lv_mission_def *m)
{
    for (size_t i = 0; g->steer.law != NULL && i < g->steer.law->n_keys; i++) {
        const lv_law_key *k = &g->steer.law->keys[i];
        if (k->type == LV_KEY_NUMBER && strcmp(k->name, key) == 0)
            return g->steer.slot[i] != LV_NO_SLOT ? m->slots[g->steer.slot[i]].value : k->dflt;
    }
    return NAN;
}

lv_slot lv_guidance_def_throttle_value(const lv_guidance_def *g)
{
    for (size_t i = 0; g->thr.law != NULL && i < g->thr.law->n_keys; i++)
        if (strcmp(g->thr.law->keys[i].name, "value") == 0)
            return g->thr.slot[i];
    return LV_NO_SLOT;
}

const lv_law *lv_guidance_def_throttle_fixed(const lv_guidance_def *g, char *is, size_t is_cap,
                                             char *written_as, size_t written_cap)
{
    const lv_law *l = g->thr.law;
    if (l == NULL || l->form == LV_LAW_FORM_KEYS)
        return NULL;
    const int word = l->form == LV_LAW_FORM_WORD;
    snprintf(is, is_cap, word ? "%s" : "the %s law's", l->name);
    snprintf(written_as, written_cap, word ? "%s" : "{%s: ..}", l->name);
    return l;
}

static void law_def_clear(lv_law_def *d)
{
    for (size_t i = 0; i < LV_LAW_KEYS_MAX; i++) {
        free(d->table_file[i]);
        free(d->table_var[i]);
        lv_table_free(d->table[i]);
    }
}

void lv_guidance_def_clear(lv_guidance_def *g)
{
    law_def_clear(&g->steer);
    law_def_clear(&g->thr);
    memset(g, 0, sizeof *g);
}
