/* guid_laws.c - the registered steering and throttle laws (guidance.h): one line per law, in
 * the order mission files' messages list them; and the public API that names them
 * (lv_guidance.h: lv_laws_*, lv_steering_*, lv_throttle_*). A new law: its file
 * (guid_<name>.c or thr_<name>.c), one line here, its test and its row in docs/guidance.md.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/names.h"
#include "core/status.h"
#include "dynamics/guid_kit.h"

/* The laws, one line each: X(name) is lv_law_<name>, defined in the file named beside it.
 * The order is the one messages and listings use. */
#define STEERING_LAWS(X)                                                                       \
    X(inputs)           /* guid_inputs.c: no law, the model's inputs */                        \
    X(attitude)         /* guid_attitude.c */                                                  \
    X(gravity_turn)     /* guid_gravity_turn.c */                                              \
    X(linear_tangent)   /* guid_tangent.c */                                                   \
    X(bilinear_tangent) /* guid_tangent.c */                                                   \
    X(heading)          /* guid_heading.c */                                                   \
    X(retrograde)       /* guid_retrograde.c */                                                \
    X(prograde)         /* guid_prograde.c */                                                  \
    X(boostback)        /* guid_boostback.c */                                                 \
    X(flare)            /* guid_flare.c */
#define THROTTLE_LAWS(X)                                                                       \
    X(nominal)          /* thr_nominal.c */                                                    \
    X(landing)          /* thr_landing.c */                                                    \
    X(off)              /* thr_off.c */

#define DECLARE(name) extern const lv_law lv_law_##name;
STEERING_LAWS(DECLARE)
THROTTLE_LAWS(DECLARE)
#define ENTRY(name) &lv_law_##name,
static const lv_law *const steering_laws[] = {STEERING_LAWS(ENTRY) NULL};
static const lv_law *const throttle_laws[] = {THROTTLE_LAWS(ENTRY) NULL};
#undef DECLARE
#undef ENTRY

/* The keys every steering law takes (offsets into lv_steering). */
static const lv_law_key steering_common[] = {
    {.name = "target_lat", .type = LV_KEY_NUMBER, .unit = "rad", .lo = LV_KR_LAT_LO,
     .hi = LV_KR_LAT_HI, .dflt = NAN, .flags = LV_KEY_ANGLE | LV_KEY_OPTIONAL,
     .offset = offsetof(lv_steering, target_lat),
     .description = "geodetic latitude of the target (heading, boostback, the target "
                    "outputs); with target_lon, default the start point"},
    {.name = "target_lon", .type = LV_KEY_NUMBER, .unit = "rad", .lo = LV_KR_TURN_LO,
     .hi = LV_KR_TURN_HI, .dflt = NAN, .flags = LV_KEY_ANGLE | LV_KEY_OPTIONAL,
     .offset = offsetof(lv_steering, target_lon),
     .description = "longitude of the target; with target_lat, default the start point"},
};

const lv_law *const *lv_guid_laws(lv_law_kind kind)
{
    return kind == LV_LAW_THROTTLE ? throttle_laws : steering_laws;
}

const lv_law *lv_guid_law_find(lv_law_kind kind, const char *name)
{
    for (const lv_law *const *l = lv_guid_laws(kind); name != NULL && *l != NULL; l++)
        if (strcmp((*l)->name, name) == 0)
            return *l;
    return NULL;
}

const lv_law_key *lv_laws_common_keys(lv_law_kind kind, size_t *n)
{
    *n = kind == LV_LAW_STEERING ? sizeof steering_common / sizeof steering_common[0] : 0;
    return kind == LV_LAW_STEERING ? steering_common : NULL;
}

/* `name` among n keys, "NAME_deg" for an angle with *deg = 1. */
static const lv_law_key *find_in(const lv_law_key *keys, size_t n, const char *name, int *deg)
{
    const size_t len = strlen(name);
    for (size_t i = 0; i < n; i++) {
        const size_t kl = strlen(keys[i].name);
        if (strcmp(keys[i].name, name) == 0) {
            *deg = 0;
            return &keys[i];
        }
        if ((keys[i].flags & LV_KEY_ANGLE) && len == kl + 4 &&
            strncmp(keys[i].name, name, kl) == 0 && strcmp(name + kl, "_deg") == 0) {
            *deg = 1;
            return &keys[i];
        }
    }
    return NULL;
}

const lv_law_key *lv_guid_key_find(const lv_law *law, lv_law_kind kind, const char *name,
                                   int *deg, int *common)
{
    size_t nc;
    const lv_law_key *ck = lv_laws_common_keys(kind, &nc);
    const lv_law_key *k = find_in(ck, nc, name, deg);
    *common = k != NULL;
    if (k == NULL && law != NULL)
        k = find_in(law->keys, law->n_keys, name, deg);
    return k;
}

size_t lv_laws_count(void)
{
    size_t n = 0;
    for (int kind = 0; kind < 2; kind++)
        for (const lv_law *const *l = lv_guid_laws((lv_law_kind)kind); *l != NULL; l++)
            n++;
    return n;
}

lv_status lv_laws_get(size_t i, lv_law_info *out, lv_err *err)
{
    size_t n = 0;
    for (int kind = 0; kind < 2; kind++)
        for (const lv_law *const *l = lv_guid_laws((lv_law_kind)kind); *l != NULL; l++, n++)
            if (n == i) {
                out->name = (*l)->name;
                out->description = (*l)->description;
                out->kind = (*l)->kind;
                out->form = (*l)->form;
                out->needs_aero = (*l)->needs_aero;
                out->n_keys = (*l)->n_keys;
                out->keys = (*l)->keys;
                return LV_OK;
            }
    return lv_fail(err, LV_ERR_INPUT, "law index %zu out of range (%zu laws)", i, n);
}

/* ---- a model's law, set by key ------------------------------------------------------------ */

static lv_status law_init(lv_law_kind kind, const lv_law **law, lv_law_par *par,
                          const char *name, lv_err *err)
{
    const lv_law *l = lv_guid_law_find(kind, name);
    if (l == NULL) {
        char list[256] = "";
        size_t used = 0;
        lv_suggest sug;
        lv_suggest_init(&sug, name != NULL ? name : "");
        for (const lv_law *const *p = lv_guid_laws(kind); *p != NULL; p++) {
            lv_suggest_add(&sug, (*p)->name);
            if (used < sizeof list)
                used += (size_t)snprintf(list + used, sizeof list - used, "%s%s",
                                         used ? ", " : "", (*p)->name);
        }
        char hint[192];
        lv_suggest_text(&sug, hint, sizeof hint);
        return lv_fail(err, LV_ERR_NOTFOUND, "unknown %s law '%.40s'%s (the laws: %s)",
                       kind == LV_LAW_THROTTLE ? "throttle" : "steering",
                       name != NULL ? name : "(null)", hint, list);
    }
    *law = l;
    lv_guid_par_defaults(l, par);
    return LV_OK;
}

/* Key `key` of type `type` of `law` or of the kind's common keys (*common: its offset is into
 * the lv_steering, else into the law's parameters). */
static lv_status law_key(lv_law_kind kind, const lv_law *law, const char *key, lv_key_type type,
                         const lv_law_key **out, int *common, int *deg, lv_err *err)
{
    const char *kw = kind == LV_LAW_THROTTLE ? "throttle" : "steering";
    const lv_law_key *k = lv_guid_key_find(law, kind, key != NULL ? key : "", deg, common);
    if (k == NULL && law == NULL)
        return lv_fail(err, LV_ERR_INPUT, "no %s law set: lv_%s_init first (key '%.40s')", kw,
                       kind == LV_LAW_THROTTLE ? "throttle" : "steering",
                       key != NULL ? key : "(null)");
    if (k == NULL) {
        lv_suggest sug;
        lv_suggest_init(&sug, key != NULL ? key : "");
        for (size_t i = 0; i < law->n_keys; i++)
            lv_suggest_add(&sug, law->keys[i].name);
        char hint[192];
        lv_suggest_text(&sug, hint, sizeof hint);
        return lv_fail(err, LV_ERR_NOTFOUND, "%s law '%s' has no key '%.40s'%s", kw, law->name,
                       key != NULL ? key : "(null)", hint);
    }
    static const char *const type_words[] = {"number", "table", "choice"};
    if (k->type != type)
        return lv_fail(err, LV_ERR_INPUT, "%s law '%s': key '%s' is a %s, not a %s", kw,
                       law != NULL ? law->name : "(none)", k->name, type_words[k->type],
                       type_words[type]);
    *out = k;
    return LV_OK;
}

/* Where key k's value lives: in self (a common key) or in par. */
static char *key_at(const lv_law_key *k, int common, void *self, lv_law_par *par)
{
    return common ? (char *)self + k->offset : (char *)par->d + k->offset;
}

static lv_status law_set(lv_law_kind kind, const lv_law *law, void *self, lv_law_par *par,
                         const char *key, double value, lv_err *err)
{
    const lv_law_key *k;
    int common, deg;
    lv_status st = law_key(kind, law, key, LV_KEY_NUMBER, &k, &common, &deg, err);
    if (st != LV_OK)
        return st;
    const double v = deg ? value * LV_DEG : value;
    memcpy(key_at(k, common, self, par), &v, sizeof v);
    return LV_OK;
}

static lv_status law_get(lv_law_kind kind, const lv_law *law, const void *self,
                         const lv_law_par *par, const char *key, double *value, lv_err *err)
{
    const lv_law_key *k;
    int common, deg;
    lv_status st = law_key(kind, law, key, LV_KEY_NUMBER, &k, &common, &deg, err);
    if (st != LV_OK)
        return st;
    double v;
    memcpy(&v, common ? (const char *)self + k->offset : (const char *)par->d + k->offset,
           sizeof v);
    *value = deg ? v / LV_DEG : v;
    return LV_OK;
}

lv_status lv_steering_init(lv_steering *s, const char *law, lv_err *err)
{
    lv_status st = law_init(LV_LAW_STEERING, &s->law, &s->par, law, err);
    if (st == LV_OK)
        s->target_lat = s->target_lon = NAN;
    return st;
}

lv_status lv_steering_set(lv_steering *s, const char *key, double value, lv_err *err)
{
    return law_set(LV_LAW_STEERING, s->law, s, &s->par, key, value, err);
}

lv_status lv_steering_get(const lv_steering *s, const char *key, double *value, lv_err *err)
{
    return law_get(LV_LAW_STEERING, s->law, s, &s->par, key, value, err);
}

lv_status lv_steering_set_table(lv_steering *s, const char *key, const lv_table *t, lv_err *err)
{
    const lv_law_key *k;
    int common, deg;
    lv_status st = law_key(LV_LAW_STEERING, s->law, key, LV_KEY_TABLE, &k, &common, &deg, err);
    if (st == LV_OK)
        memcpy(key_at(k, common, s, &s->par), &t, sizeof t);
    return st;
}

lv_status lv_steering_set_choice(lv_steering *s, const char *key, const char *word, lv_err *err)
{
    const lv_law_key *k;
    int common, deg;
    lv_status st = law_key(LV_LAW_STEERING, s->law, key, LV_KEY_CHOICE, &k, &common, &deg, err);
    if (st != LV_OK)
        return st;
    for (int i = 0; k->choices[i] != NULL; i++)
        if (word != NULL && strcmp(k->choices[i], word) == 0) {
            memcpy(key_at(k, common, s, &s->par), &i, sizeof i);
            return LV_OK;
        }
    return lv_fail(err, LV_ERR_INPUT, "steering law '%s': %s '%.40s' is not one of its words",
                   s->law->name, k->name, word != NULL ? word : "(null)");
}

const char *lv_steering_law(const lv_steering *s)
{
    return s->law != NULL ? s->law->name : "inputs";
}

lv_status lv_throttle_init(lv_throttle_cfg *t, const char *law, lv_err *err)
{
    return law_init(LV_LAW_THROTTLE, &t->law, &t->par, law, err);
}

lv_status lv_throttle_set(lv_throttle_cfg *t, const char *key, double value, lv_err *err)
{
    return law_set(LV_LAW_THROTTLE, t->law, t, &t->par, key, value, err);
}

lv_status lv_throttle_get(const lv_throttle_cfg *t, const char *key, double *value, lv_err *err)
{
    return law_get(LV_LAW_THROTTLE, t->law, t, &t->par, key, value, err);
}

const char *lv_throttle_law(const lv_throttle_cfg *t)
{
    return t->law != NULL ? t->law->name : "nominal";
}
