/* test_laws.c - the registered steering and throttle laws (src/dynamics/guid_laws.c) and
 * their C API (lv_guidance.h):
 *   (a) every registered law keeps the contract the parser, `lvsim laws`, Python and the
 *       right-hand side rely on (law_contract below): unique names and keys, units given,
 *       angles in rad, defaults within their ranges (NAN: required), keys inside the law's
 *       parameter struct, the functions the hot path calls present and a law made of its
 *       defaults valid; and laws broken on purpose, one defect each, fail it;
 *   (b) lv_laws_count/lv_laws_get list the same laws as the tables;
 *   (c) lv_steering_init/set/get, lv_throttle_*: keys by name, NAME_deg in degrees, unknown
 *       names refused with suggestions;
 *   (d) a model made from a configuration refuses bad values with the law, key and value.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "dynamics/guidance.h"
#include "lvsim/lv_dof3.h"
#include "lvsim/lv_dof6.h"
#include "mission/guidance_def.h"

/* ---- the contract ------------------------------------------------------------------------- */

static int why_(char *why, size_t cap, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, cap, fmt, ap);
    va_end(ap);
    return 1;
}

static size_t key_size(const lv_law_key *k)
{
    return k->type == LV_KEY_NUMBER ? sizeof(double)
           : k->type == LV_KEY_CHOICE ? sizeof(int)
                                      : sizeof(const lv_table *);
}

static const lv_law_key *key_named(const lv_law *law, const char *name)
{
    for (size_t i = 0; name != NULL && i < law->n_keys; i++)
        if (strcmp(law->keys[i].name, name) == 0)
            return &law->keys[i];
    return NULL;
}

static int in_range(const lv_law_key *k, double v)
{
    return (k->lo_open ? v > k->lo : v >= k->lo) && (k->hi_open ? v < k->hi : v <= k->hi);
}

/* A value within key k's range: the middle, one inside an open end, or 1. */
static double mid_value(const lv_law_key *k)
{
    if (isfinite(k->lo) && isfinite(k->hi))
        return 0.5 * (k->lo + k->hi);
    if (isfinite(k->lo))
        return k->lo + 1.0;
    if (isfinite(k->hi))
        return k->hi - 1.0;
    return 1.0;
}

/* 0 when `law`, registered as a law of `kind`, keeps the contract; 1 with the reason. */
static int law_contract(const lv_law *law, lv_law_kind kind, char *why, size_t cap)
{
    if (law->name == NULL || law->name[0] == '\0' || strchr(law->name, ' ') != NULL)
        return why_(why, cap, "name '%s' empty or with a space", law->name ? law->name : "");
    const char *ln = law->name;
    if (law->description == NULL || law->description[0] == '\0')
        return why_(why, cap, "%s: no description", ln);
    if (law->kind != kind)
        return why_(why, cap, "%s: kind %d in the table of kind %d", ln, law->kind, kind);
    const int steering = kind == LV_LAW_STEERING;
    if (steering ? !(law->form == LV_LAW_FORM_NAMED || law->form == LV_LAW_FORM_NONE)
                 : !(law->form >= LV_LAW_FORM_KEYS && law->form <= LV_LAW_FORM_WORD))
        return why_(why, cap, "%s: form %d is not a %s law's", ln, law->form,
                    steering ? "steering" : "throttle");
    if (law->form == LV_LAW_FORM_WORD && law->n_keys > 0)
        return why_(why, cap, "%s: a law written as a word has no keys", ln);
    if (law->n_keys > LV_LAW_KEYS_MAX || (law->n_keys > 0 && law->keys == NULL))
        return why_(why, cap, "%s: %zu keys (at most %d)", ln, law->n_keys, LV_LAW_KEYS_MAX);
    if (law->par_size > sizeof(lv_law_par))
        return why_(why, cap, "%s: parameters of %zu bytes (room for %zu)", ln, law->par_size,
                    sizeof(lv_law_par));
    size_t n_common, n_choice = 0, n_choices = 0;
    const lv_law_key *common = lv_laws_common_keys(kind, &n_common);
    for (size_t i = 0; i < law->n_keys; i++)
        if (law->keys[i].type == LV_KEY_CHOICE) {
            n_choice++;
            for (n_choices = 0; law->keys[i].choices && law->keys[i].choices[n_choices];)
                n_choices++;
        }
    for (size_t i = 0; i < law->n_keys; i++) {
        const lv_law_key *k = &law->keys[i];
        const char *kn = k->name;
        if (kn == NULL || kn[0] == '\0' || strcmp(kn, "law") == 0)
            return why_(why, cap, "%s: key %zu has no name (or 'law')", ln, i);
        const size_t len = strlen(kn);
        if (len > 4 && strcmp(kn + len - 4, "_deg") == 0)
            return why_(why, cap, "%s.%s: a key's name never ends in _deg", ln, kn);
        for (size_t j = 0; j < i; j++)
            if (strcmp(law->keys[j].name, kn) == 0)
                return why_(why, cap, "%s.%s: key given twice", ln, kn);
        for (size_t j = 0; j < n_common; j++)
            if (strcmp(common[j].name, kn) == 0)
                return why_(why, cap, "%s.%s: a common key of every law", ln, kn);
        if (k->unit == NULL)
            return why_(why, cap, "%s.%s: no unit (\"\" when dimensionless)", ln, kn);
        if (k->description == NULL || k->description[0] == '\0')
            return why_(why, cap, "%s.%s: no description", ln, kn);
        if (k->offset + key_size(k) > law->par_size)
            return why_(why, cap, "%s.%s: offset %zu outside the parameters (%zu bytes)", ln,
                        kn, k->offset, law->par_size);
        const int ang = (k->flags & LV_KEY_ANGLE) != 0;
        if (k->type == LV_KEY_NUMBER) {
            if (!(k->lo <= k->hi))
                return why_(why, cap, "%s.%s: range [%g, %g] empty", ln, kn, k->lo, k->hi);
            if (ang != (strcmp(k->unit, "rad") == 0))
                return why_(why, cap, "%s.%s: an angle is in rad, and a key in rad an angle "
                            "(unit '%s', flag %d)", ln, kn, k->unit, ang);
            const int required = isnan(k->dflt) && !(k->flags & LV_KEY_OPTIONAL);
            if (!required && !(k->flags & LV_KEY_OPTIONAL) && !in_range(k, k->dflt))
                return why_(why, cap, "%s.%s: default %g outside its range [%g, %g]", ln, kn,
                            k->dflt, k->lo, k->hi);
        } else {
            if (ang || k->unit[0] != '\0')
                return why_(why, cap, "%s.%s: a table or choice has no unit", ln, kn);
        }
        if (k->type == LV_KEY_CHOICE &&
            (k->choices == NULL || k->choices[0] == NULL || !(k->dflt >= 0.0) ||
             k->dflt != floor(k->dflt) || (size_t)k->dflt >= n_choices))
            return why_(why, cap, "%s.%s: a choice needs words and a default among them", ln,
                        kn);
        if (k->frames != 0 && (n_choice != 1 || (k->frames >> n_choices) != 0))
            return why_(why, cap, "%s.%s: frames 0x%x without one choice key of as many "
                        "words", ln, kn, k->frames);
        const lv_law_key *alt = key_named(law, k->instead_of);
        if (k->instead_of != NULL && (alt == NULL || alt->type != LV_KEY_TABLE))
            return why_(why, cap, "%s.%s: instead_of '%s' is not a table key of the law", ln,
                        kn, k->instead_of);
        if (k->needs != NULL && key_named(law, k->needs) == NULL)
            return why_(why, cap, "%s.%s: needs '%s', not a key of the law", ln, kn, k->needs);
        if ((k->flags & LV_KEY_DOF3) && law->dof3_why == NULL)
            return why_(why, cap, "%s.%s: a 3-DoF key without the law's dof3_why", ln, kn);
    }
    /* the functions the right-hand side calls, on the law made of its defaults (a required
     * key in the middle of its range) */
    lv_law_par par;
    lv_guid_par_defaults(law, &par);
    for (size_t i = 0; i < law->n_keys; i++)
        if (law->keys[i].type == LV_KEY_NUMBER && isnan(law->keys[i].dflt) &&
            !(law->keys[i].flags & LV_KEY_OPTIONAL)) {
            const double v = mid_value(&law->keys[i]);
            memcpy((char *)par.d + law->keys[i].offset, &v, sizeof v);
        }
    lv_err err = {LV_OK, ""};
    if (steering) {
        if ((law->form == LV_LAW_FORM_NAMED) != (law->attitude != NULL))
            return why_(why, cap, "%s: a law a file names has an attitude function, the "
                        "inputs none", ln);
        if (law->throttle != NULL || law->thr_init != NULL)
            return why_(why, cap, "%s: a steering law with throttle functions", ln);
        lv_steering s = {law, 0.1, 0.2, par};
        lv_guid g;
        const lv_planet earth = lv_planet_earth();
        if (lv_guid_init(&g, &s, &earth, 1, &err) != LV_OK)
            return why_(why, cap, "%s: its defaults are refused: %s", ln, err.msg);
        if (g.limits_alpha && law->alpha_limited == NULL)
            return why_(why, cap, "%s: limits alpha without alpha_limited", ln);
    } else {
        if (law->attitude != NULL || law->thr_init == NULL)
            return why_(why, cap, "%s: a throttle law needs thr_init and no attitude", ln);
        lv_throttle_cfg tc = {law, par};
        lv_thr t;
        if (lv_thr_init(&t, &tc, &err) != LV_OK)
            return why_(why, cap, "%s: its defaults are refused: %s", ln, err.msg);
        if (t.active && law->throttle == NULL)
            return why_(why, cap, "%s: active without a throttle function", ln);
        if (!t.engines_off && law->throttle == NULL && law->form != LV_LAW_FORM_KEYS)
            return why_(why, cap, "%s: sets the throttle itself without a function", ln);
    }
    return 0;
}

static void test_registered(void)
{
    size_t n = 0, n_keys_form = 0;
    const lv_law *seen[64];
    for (int kind = 0; kind < 2; kind++)
        for (const lv_law *const *l = lv_guid_laws((lv_law_kind)kind); *l != NULL; l++) {
            char why[256] = "";
            const int bad = law_contract(*l, (lv_law_kind)kind, why, sizeof why);
            if (bad)
                fprintf(stderr, "  contract: %s\n", why);
            CHECK(!bad);
            for (size_t j = 0; j < n; j++) /* names unique across both kinds */
                CHECK(strcmp(seen[j]->name, (*l)->name) != 0);
            n_keys_form += (*l)->form == LV_LAW_FORM_KEYS;
            if (n < 64)
                seen[n++] = *l;
            /* the table finds it by name, and lv_laws_get lists it in the same order */
            CHECK(lv_guid_law_find((lv_law_kind)kind, (*l)->name) == *l);
        }
    CHECK(n_keys_form == 1); /* `throttle: {KEY: ..}`: one law takes the keys directly */
    CHECK(n >= 11);          /* 8 steering laws with inputs, 3 throttle laws */
    CHECK(lv_laws_count() == n);
    lv_law_info info;
    lv_err err;
    for (size_t i = 0; i < n; i++) {
        CHECK_OK(lv_laws_get(i, &info, &err), &err);
        CHECK(strcmp(info.name, seen[i]->name) == 0 && info.keys == seen[i]->keys &&
              info.n_keys == seen[i]->n_keys && info.kind == seen[i]->kind &&
              info.form == seen[i]->form);
    }
    CHECK(lv_laws_get(n, &info, &err) == LV_ERR_INPUT && strstr(err.msg, "out of range"));
    size_t nc;
    const lv_law_key *common = lv_laws_common_keys(LV_LAW_STEERING, &nc);
    CHECK(nc == 2 && strcmp(common[0].name, "target_lat") == 0 &&
          strcmp(common[1].name, "target_lon") == 0);
    CHECK(lv_laws_common_keys(LV_LAW_THROTTLE, &nc) == NULL && nc == 0);
}

/* ---- laws broken on purpose --------------------------------------------------------------- */

typedef struct toy_par {
    double gain;        /* - */
    double angle;       /* rad */
    const lv_table *tab;
} toy_par;

static int toy_attitude(const lv_guid *g, lv_guid_rt *rt, double t, const lv_flight_kin *k,
                        const lv_flight_air *a, double fpa0, double chi0, int full,
                        lv_flight_controls *c, lv_flight_axes *ax, lv_err *err)
{
    (void)g, (void)rt, (void)t, (void)k, (void)a, (void)fpa0, (void)chi0, (void)full, (void)c;
    (void)ax, (void)err;
    return 0;
}

static const lv_law_key toy_keys[] = {
    {.name = "gain", .type = LV_KEY_NUMBER, .unit = "", .lo = 0.0, .hi = 10.0, .dflt = 1.0,
     .offset = offsetof(toy_par, gain), .description = "a gain"},
    {.name = "angle", .type = LV_KEY_NUMBER, .unit = "rad", .lo = -1.0, .hi = 1.0, .dflt = NAN,
     .flags = LV_KEY_ANGLE, .instead_of = "tab", .offset = offsetof(toy_par, angle),
     .description = "an angle"},
    {.name = "tab", .type = LV_KEY_TABLE, .unit = "", .offset = offsetof(toy_par, tab),
     .description = "a table"},
};

static const lv_law toy = {
    .name = "toy",
    .description = "a law of the test",
    .kind = LV_LAW_STEERING,
    .form = LV_LAW_FORM_NAMED,
    .keys = toy_keys,
    .n_keys = 3,
    .par_size = sizeof(toy_par),
    .attitude = toy_attitude,
};

/* `law` fails the contract with a reason containing `want` (NULL: keeps it). */
static void broken(const lv_law *law, const char *want)
{
    char why[256] = "";
    const int bad = law_contract(law, LV_LAW_STEERING, why, sizeof why);
    if (want == NULL) {
        if (bad)
            fprintf(stderr, "  toy: %s\n", why);
        CHECK(!bad);
    } else {
        CHECK(bad);
        if (strstr(why, want) == NULL) {
            fprintf(stderr, "  broken law: got '%s', want '%s'\n", why, want);
            CHECK(0);
        }
    }
}

static void test_broken(void)
{
    broken(&toy, NULL); /* the toy itself keeps the contract */
    lv_law_key keys[3];
    lv_law bad = toy;
    bad.keys = keys;
#define WITH(i, field, value)                                                                  \
    (memcpy(keys, toy_keys, sizeof keys), keys[i].field = (value), &bad)
    broken(WITH(1, name, "gain"), "toy.gain: key given twice");
    broken(WITH(0, dflt, 11.0), "toy.gain: default 11 outside its range [0, 10]");
    broken(WITH(1, unit, "deg"), "toy.angle: an angle is in rad");
    broken(WITH(0, unit, "rad"), "toy.gain: an angle is in rad, and a key in rad an angle");
    broken(WITH(0, unit, NULL), "toy.gain: no unit");
    broken(WITH(1, instead_of, "gain"), "toy.angle: instead_of 'gain' is not a table key");
    broken(WITH(0, name, "target_lat"), "toy.target_lat: a common key of every law");
    broken(WITH(1, name, "angle_deg"), "toy.angle_deg: a key's name never ends in _deg");
    broken(WITH(0, offset, sizeof(toy_par)), "toy.gain: offset 24 outside the parameters");
    broken(WITH(0, flags, LV_KEY_DOF3), "toy.gain: a 3-DoF key without the law's dof3_why");
    broken(WITH(0, frames, 2u), "toy.gain: frames 0x2 without one choice key");
#undef WITH
    memcpy(keys, toy_keys, sizeof keys);
    bad.attitude = NULL; /* the right-hand side would call a NULL function */
    broken(&bad, "toy: a law a file names has an attitude function");
    bad = toy;
    bad.par_size = sizeof(lv_law_par) + 8;
    broken(&bad, "toy: parameters of");
    bad = toy;
    bad.kind = LV_LAW_THROTTLE;
    broken(&bad, "toy: kind 1 in the table of kind 0");
}

/* ---- the C API ----------------------------------------------------------------------------- */

static void test_api(void)
{
    lv_steering s;
    lv_err err;
    double v;
    CHECK(lv_steering_init(&s, "gravity_trun", &err) == LV_ERR_NOTFOUND &&
          strstr(err.msg, "unknown steering law 'gravity_trun'; did you mean 'gravity_turn'?"));
    CHECK_OK(lv_steering_init(&s, "gravity_turn", &err), &err);
    CHECK(strcmp(lv_steering_law(&s), "gravity_turn") == 0);
    CHECK(isnan(s.target_lat) && isnan(s.target_lon)); /* the start point */
    CHECK_OK(lv_steering_get(&s, "rise_time", &v, &err), &err);
    CHECK(v == 0.0);                                   /* its default */
    CHECK_OK(lv_steering_get(&s, "kick", &v, &err), &err);
    CHECK(isnan(v));                                   /* required */
    /* NAME_deg takes degrees: kick = 3 deg = 3 LV_DEG rad (the definition of the unit) */
    CHECK_OK(lv_steering_set(&s, "kick_deg", 3.0, &err), &err);
    CHECK_OK(lv_steering_get(&s, "kick", &v, &err), &err);
    CHECK(v == 3.0 * LV_DEG);
    CHECK_OK(lv_steering_get(&s, "kick_deg", &v, &err), &err);
    CHECK_CLOSE(v, 3.0, 1e-15);
    CHECK_OK(lv_steering_set(&s, "target_lat_deg", 10.0, &err), &err);
    CHECK(s.target_lat == 10.0 * LV_DEG);
    CHECK(lv_steering_set(&s, "kik_time", 1.0, &err) == LV_ERR_NOTFOUND &&
          strstr(err.msg, "steering law 'gravity_turn' has no key 'kik_time'; did you mean "
                          "'kick_time'"));
    CHECK(lv_steering_set(&s, "rise_time_deg", 1.0, &err) == LV_ERR_NOTFOUND); /* not an angle */
    CHECK(lv_steering_set_table(&s, "kick", NULL, &err) == LV_ERR_INPUT &&
          strstr(err.msg, "key 'kick' is a number, not a table"));
    CHECK_OK(lv_steering_init(&s, "linear_tangent", &err), &err);
    CHECK(lv_steering_set_choice(&s, "frame", "wind", &err) == LV_ERR_INPUT);
    CHECK_OK(lv_steering_set_choice(&s, "frame", "local", &err), &err);

    lv_throttle_cfg t;
    CHECK(lv_throttle_init(&t, "landin", &err) == LV_ERR_NOTFOUND &&
          strstr(err.msg, "did you mean 'landing'"));
    CHECK_OK(lv_throttle_init(&t, "landing", &err), &err);
    CHECK_OK(lv_throttle_set(&t, "speed", 2.0, &err), &err);
    CHECK_OK(lv_throttle_get(&t, "altitude", &v, &err), &err);
    CHECK(v == 0.0 && strcmp(lv_throttle_law(&t), "landing") == 0);
    lv_throttle_cfg none = {0}; /* law NULL: the nominal law without limits */
    CHECK(strcmp(lv_throttle_law(&none), "nominal") == 0);
    CHECK(lv_throttle_set(&none, "g_limit", 3.0, &err) == LV_ERR_INPUT &&
          strstr(err.msg, "lv_throttle_init first"));
    lv_steering zero = {0}; /* law NULL: the inputs; the common keys only */
    CHECK_OK(lv_steering_set(&zero, "target_lon_deg", 90.0, &err), &err);
    CHECK(zero.target_lon == 90.0 * LV_DEG);
    CHECK(lv_steering_set_table(&zero, "target_lat", NULL, &err) == LV_ERR_INPUT &&
          strstr(err.msg, "key 'target_lat' is a number, not a table"));
}

/* A 3-DoF model of one engine made with steering s and throttle t: its status, *err. */
static lv_status make_dof3(const lv_steering *s, const lv_throttle_cfg *t, int aero,
                           lv_err *err)
{
    const lv_planet earth = lv_planet_earth();
    lv_gravity_config gc = {"j2", 0, -1, NULL};
    lv_gravity *grav = NULL;
    lv_status st = lv_gravity_create(&earth, &gc, &grav, err);
    if (st != LV_OK)
        return st;
    lv_engine_config eng;
    lv_engine_config_default(&eng);
    eng.thrust_vac = 1e5;
    eng.isp_vac = 300.0;
    lv_aero_config ac;
    lv_aero_config_default(&ac);
    ac.s_ref = 1.0;
    lv_dof3_config cfg;
    lv_dof3_config_default(&cfg);
    cfg.gravity = grav;
    cfg.m0 = 5000.0;
    cfg.propellant = 4000.0;
    cfg.n_engines = 1;
    cfg.engines = &eng;
    cfg.aero = aero ? &ac : NULL;
    if (s != NULL)
        cfg.steering = *s;
    if (t != NULL)
        cfg.throttle_law = *t;
    lv_dof3 *m = NULL;
    st = lv_dof3_create(&cfg, &m, err);
    lv_dof3_free(m);
    lv_gravity_free(grav);
    return st;
}

static void want_refused(lv_status st, const lv_err *err, const char *want)
{
    CHECK(st == LV_ERR_INPUT);
    if (st != LV_OK && strstr(err->msg, want) == NULL) {
        fprintf(stderr, "  got:  %s\n  want: %s\n", err->msg, want);
        CHECK(0);
    }
}

static void test_models_refuse(void)
{
    lv_steering s;
    lv_throttle_cfg t;
    lv_err err;
    CHECK_OK(make_dof3(NULL, NULL, 0, &err), &err); /* the defaults: inputs, nominal */
    CHECK_OK(lv_steering_init(&s, "gravity_turn", &err), &err);
    CHECK_OK(lv_steering_set(&s, "kick_time", 10.0, &err), &err);
    CHECK_OK(lv_steering_set(&s, "heading", 1.0, &err), &err);
    want_refused(make_dof3(&s, NULL, 0, &err), &err,
                 "dof3: guidance 'gravity_turn': kick is required");
    CHECK_OK(lv_steering_set(&s, "kick_deg", 95.0, &err), &err);
    want_refused(make_dof3(&s, NULL, 0, &err), &err,
                 "dof3: guidance 'gravity_turn': kick = 1.65806 rad must be >= 0 and <= 1.5708 "
                 "rad");
    CHECK_OK(lv_steering_set(&s, "kick_deg", 3.0, &err), &err);
    CHECK_OK(lv_steering_set(&s, "kick_time", 0.0, &err), &err);
    want_refused(make_dof3(&s, NULL, 0, &err), &err,
                 "dof3: guidance 'gravity_turn': a kick needs kick_time > 0 s");
    CHECK_OK(lv_steering_set(&s, "kick_time", 10.0, &err), &err);
    CHECK_OK(make_dof3(&s, NULL, 0, &err), &err);

    CHECK_OK(lv_steering_init(&s, "heading", &err), &err);
    CHECK_OK(lv_steering_set(&s, "alpha_deg", 5.0, &err), &err);
    want_refused(make_dof3(&s, NULL, 0, &err), &err,
                 "dof3: guidance 'heading': the heading law banks the lift vector: the phase "
                 "needs an aerodynamic dataset");
    CHECK_OK(lv_steering_set(&s, "q_max", 3000.0, &err), &err);
    want_refused(make_dof3(&s, NULL, 1, &err), &err,
                 "dof3: guidance 'heading': q_max releases the load-factor limit as q rises: "
                 "it needs n_max > 0");
    CHECK_OK(lv_steering_set(&s, "n_max", 2.5, &err), &err);
    CHECK_OK(make_dof3(&s, NULL, 1, &err), &err);

    CHECK_OK(lv_steering_init(&s, "bilinear_tangent", &err), &err);
    const char *abcd[] = {"a", "b", "c", "d", "heading"};
    for (int i = 0; i < 5; i++)
        CHECK_OK(lv_steering_set(&s, abcd[i], 0.0, &err), &err);
    want_refused(make_dof3(&s, NULL, 0, &err), &err,
                 "dof3: guidance 'bilinear_tangent': a, b, c and d are all 0");

    CHECK_OK(lv_throttle_init(&t, "nominal", &err), &err);
    CHECK_OK(lv_throttle_set(&t, "g_limit", -1.0, &err), &err);
    want_refused(make_dof3(NULL, &t, 0, &err), &err,
                 "dof3: throttle 'nominal': g_limit = -1 must be > 0");
    CHECK_OK(lv_throttle_set(&t, "g_limit", 0.0, &err), &err); /* 0: none */
    CHECK_OK(lv_throttle_set(&t, "q_max", 3e4, &err), &err);
    CHECK_OK(lv_throttle_set(&t, "q_gain", 0.0, &err), &err);
    want_refused(make_dof3(NULL, &t, 0, &err), &err,
                 "dof3: throttle 'nominal': q_gain = 0 1/s must be > 0 and <= 100 1/s");
    CHECK_OK(lv_throttle_init(&t, "landing", &err), &err);
    CHECK_OK(lv_throttle_set(&t, "speed", -1.0, &err), &err);
    want_refused(make_dof3(NULL, &t, 0, &err), &err,
                 "dof3: throttle 'landing': speed = -1 m/s must be >= 0 m/s");

    /* the keys a 6-DoF model refuses: those of 3-DoF limits, away from their defaults */
    CHECK_OK(lv_steering_init(&s, "heading", &err), &err);
    CHECK(lv_guid_dof3_key(&s) == NULL);
    CHECK_OK(lv_steering_set(&s, "q_max", 3000.0, &err), &err);
    CHECK(lv_guid_dof3_key(&s) != NULL && strcmp(lv_guid_dof3_key(&s)->name, "q_max") == 0);

    /* a steering law given where a throttle law goes */
    CHECK_OK(lv_steering_init(&s, "retrograde", &err), &err);
    t.law = s.law;
    want_refused(make_dof3(NULL, &t, 0, &err), &err, "'retrograde' is a steering law");
}

int main(void)
{
    test_registered();
    test_broken();
    test_api();
    test_models_refuse();
    return check_report("test_laws");
}
