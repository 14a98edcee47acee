/* guidance_def.c - `guidance:` and `throttle:` of a 3-DoF phase (guidance_def.h). */
#include "mission/guidance_def.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynamics/guidance.h"
#include "lvsim/lv_units.h"

/* The laws as written in a file; linear_tangent and bilinear_tangent are one law. */
static const char *const law_words[] = {"attitude", "gravity_turn", "linear_tangent",
                                        "bilinear_tangent", "heading", "retrograde",
                                        "boostback", NULL};
static const lv_steer_law law_of[] = {LV_STEER_ATTITUDE, LV_STEER_GRAVITY_TURN,
                                      LV_STEER_TANGENT, LV_STEER_TANGENT, LV_STEER_HEADING,
                                      LV_STEER_RETROGRADE, LV_STEER_BOOSTBACK};

/* The keys each law takes besides `law` and the target (angles also as NAME_deg). */
static const char *const law_keys[][10] = {
    {"frame", "pitch", "heading", "roll", "alpha", "beta", "mu", "table", NULL},
    {"rise_time", "kick", "kick_time", "heading", NULL},
    {"a", "b", "heading", "frame", NULL},
    {"a", "b", "c", "d", "heading", "frame", NULL},
    {"bank_max", "gain", "n_max", "q_max", "alpha", "alpha_table", NULL},
    {NULL},
    {"pitch", NULL},
};
static const char *const angle_keys[] = {"pitch", "heading", "roll", "alpha", "beta", "mu",
                                         "kick", "bank_max", "target_lat", "target_lon", NULL};

static int is_angle(const char *key)
{
    for (size_t i = 0; angle_keys[i] != NULL; i++)
        if (strcmp(angle_keys[i], key) == 0)
            return 1;
    return 0;
}

/* `key` (or `key_deg` for an angle) of map n as slot "<phase>.<group>.<key>"; absent: the
 * default `def` (NAN: no slot, or an error when `required`). */
static lv_status num(const lv_pctx *c, const lv_ynode *n, const char *what, const char *phase,
                     const char *group, const char *key, const char *unit, lv_range range,
                     int required, double def, lv_slot *out)
{
    char deg[48], slot[LV_NAME_MAX + 64];
    snprintf(deg, sizeof deg, "%s_deg", key);
    snprintf(slot, sizeof slot, "%s.%s.%s", phase, group, key);
    const int ang = is_angle(key);
    const lv_ynode *v = lv_pk_get(n, key), *vd = ang ? lv_pk_get(n, deg) : NULL;
    *out = LV_NO_SLOT;
    if (v != NULL && vd != NULL)
        return lv_pk_fail(c, lv_pk_key(n, deg), "%s: '%s' and '%s' given both", what, key, deg);
    if (v != NULL || vd != NULL)
        return lv_pk_slot(c, v ? v : vd, what, v ? key : deg, slot, unit, range, vd != NULL, out);
    if (required)
        return lv_pk_fail(c, n, "%s: '%s' is required%s", what, ang ? deg : key,
                          ang ? " (or the same in rad without _deg)" : "");
    if (isnan(def))
        return LV_OK;
    return lv_pk_slot_default(c, slot, unit, def, range, out);
}

/* The keys of law `w` (with their _deg forms), `law` and the target, NULL-terminated. */
static void allowed_keys(size_t w, const char **keys, char (*deg)[48], size_t cap)
{
    size_t n = 0, nd = 0;
    keys[n++] = "law";
    static const char *const common[] = {"target_lat", "target_lon", NULL};
    for (int pass = 0; pass < 2; pass++) {
        const char *const *list = pass == 0 ? common : law_keys[w];
        for (size_t i = 0; list[i] != NULL && n + 2 < cap; i++) {
            keys[n++] = list[i];
            if (is_angle(list[i])) {
                snprintf(deg[nd], 48, "%s_deg", list[i]);
                keys[n++] = deg[nd++];
            }
        }
    }
    keys[n] = NULL;
}

static lv_status parse_steering(const lv_pctx *c, const lv_ynode *n, const char *phase,
                                int has_aero, lv_guidance_def *g)
{
    static const char *const frames[] = {"aero", "local", "inertial", NULL};
    const lv_range any = LV_RANGE_ANY, nonneg = LV_RANGE_NONNEG;
    const lv_range lat = LV_RANGE_LAT;                      /* [-90, 90] deg */
    const lv_range half = LV_RANGE_LAT;                     /* pitch, alpha: [-90, 90] deg */
    const lv_range turn = LV_RANGE_TURN;  /* longitudes, headings, roll, bank: [-360, 360] deg */
    const lv_range aero = LV_RANGE_AERO_ANGLE;              /* sideslip: [-180, 180] deg */
    const lv_range kick = {0.0, 0.5 * LV_PI, 0, 0};          /* [0, 90] deg */
    const lv_range gain = {0.0, 100.0, 1, 0};                /* (0, 100] */
    const char *G = "guidance";
    char what[LV_WHAT_MAX];
    const lv_ynode *v;
    size_t w = 0, fi = 0;
    lv_status st;
    snprintf(what, sizeof what, "phase '%s', guidance", phase);
    if (n->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, n, "%s: a mapping such as {law: gravity_turn, ...} expected", what);
    if ((st = lv_pk_check_map(c, n, what, NULL)) != LV_OK ||
        (st = lv_pk_need(c, n, what, "law", &v)) != LV_OK ||
        (st = lv_pk_enum(c, v, what, "law", law_words, &w)) != LV_OK)
        return st;
    const char *keys[40];
    char deg[20][48];
    allowed_keys(w, keys, deg, 40);
    snprintf(what, sizeof what, "phase '%s', guidance '%s'", phase, law_words[w]);
    if ((st = lv_pk_check_map(c, n, what, keys)) != LV_OK)
        return st;
    g->given = 1;
    g->law = law_of[w];
    for (int i = 0; i < 3; i++)
        g->angle[i] = LV_NO_SLOT;
    g->rise_time = g->kick = g->kick_time = g->heading = LV_NO_SLOT;
    g->a = g->b = g->c = g->d = LV_NO_SLOT;
    g->bank_max = g->gain = g->n_max = g->hq_max = g->alpha = g->pitch = LV_NO_SLOT;
    if ((st = num(c, n, what, phase, G, "target_lat", "rad", lat, 0, NAN, &g->target_lat)) !=
            LV_OK ||
        (st = num(c, n, what, phase, G, "target_lon", "rad", turn, 0, NAN, &g->target_lon)) !=
            LV_OK)
        return st;
    if ((g->target_lat == LV_NO_SLOT) != (g->target_lon == LV_NO_SLOT))
        return lv_pk_fail(c, n, "%s: give both target_lat and target_lon (or neither: the "
                          "launch site)", what);
    if (g->target_lat != LV_NO_SLOT && fabs(c->m->slots[g->target_lat].value) > 0.5 * LV_PI)
        return lv_pk_fail(c, lv_pk_get(n, "target_lat") ? lv_pk_get(n, "target_lat")
                                                         : lv_pk_get(n, "target_lat_deg"),
                          "%s: target_lat must be within [-90, 90] deg", what);
    if ((v = lv_pk_get(n, "frame")) != NULL &&
        (st = lv_pk_enum(c, v, what, "frame", frames, &fi)) != LV_OK)
        return st;
    switch (g->law) {
    case LV_STEER_ATTITUDE: {
        g->frame = v != NULL ? (lv_att_frame)fi : LV_FRAME_LOCAL;
        static const char *const aero_k[3] = {"alpha", "beta", "mu"};
        static const char *const att_k[3] = {"pitch", "heading", "roll"};
        const char *const *mine = g->frame == LV_FRAME_AERO ? aero_k : att_k;
        const char *const *other = g->frame == LV_FRAME_AERO ? att_k : aero_k;
        for (int i = 0; i < 3; i++) {
            char od[48];
            snprintf(od, sizeof od, "%s_deg", other[i]);
            const lv_ynode *k = lv_pk_key(n, other[i]) ? lv_pk_key(n, other[i]) : lv_pk_key(n, od);
            if (k != NULL)
                return lv_pk_fail(c, k, "%s: '%s' is an angle of the %s frame; frame %s takes %s, "
                                  "%s, %s", what, k->text, g->frame == LV_FRAME_AERO ? "local or "
                                  "inertial" : "aero", frames[g->frame], mine[0], mine[1],
                                  mine[2]);
        }
        /* pitch (and alpha) within +-90 deg, sideslip +-180 deg, heading, roll and bank a turn
         * either way */
        for (int i = 0; i < 3; i++)
            if ((st = num(c, n, what, phase, G, mine[i], "rad",
                          i == 0                                  ? half
                          : i == 1 && g->frame == LV_FRAME_AERO ? aero
                                                                  : turn,
                          0, 0.0, &g->angle[i])) != LV_OK)
                return st;
        if ((v = lv_pk_get(n, "table")) != NULL) {
            if ((st = lv_pk_table(c, lv_pk_key(n, "table"), v, what, LV_EXTRAP_CLAMP,
                                  &g->table_file, &g->table_var, &g->table)) != LV_OK)
                return st;
            if ((st = lv_guid_table_check(g->table, g->law, g->frame, NULL, c->err)) != LV_OK)
                return lv_pk_fail(c, v, "%s: %s", what, c->err->msg);
        }
        return LV_OK;
    }
    case LV_STEER_GRAVITY_TURN:
        if ((st = num(c, n, what, phase, G, "rise_time", "s", nonneg, 0, 0.0, &g->rise_time)) ||
            (st = num(c, n, what, phase, G, "kick", "rad", kick, 1, 0.0, &g->kick)) ||
            (st = num(c, n, what, phase, G, "kick_time", "s", nonneg, 1, 0.0, &g->kick_time)) ||
            (st = num(c, n, what, phase, G, "heading", "rad", turn, 1, 0.0, &g->heading)))
            return st;
        if (c->m->slots[g->kick].value > 0.0 && !(c->m->slots[g->kick_time].value > 0.0))
            return lv_pk_fail(c, lv_pk_get(n, "kick_time"), "%s: a kick needs kick_time > 0 s",
                              what);
        for (int i = 0; i < 2; i++) { /* durations the integrator's clock can tell from 0 */
            const lv_slot sl = i == 0 ? g->rise_time : g->kick_time;
            const double dt = c->m->slots[sl].value;
            if (dt > 0.0 && dt < 1e-9)
                return lv_pk_fail(c, lv_pk_get(n, i == 0 ? "rise_time" : "kick_time"),
                                  "%s: %s = %g s: give 0 or at least 1e-9 s", what,
                                  i == 0 ? "rise_time" : "kick_time", dt);
        }
        return LV_OK;
    case LV_STEER_TANGENT: {
        const int bilinear = w == 3;
        g->frame = v != NULL ? (lv_att_frame)fi : LV_FRAME_INERTIAL;
        if (g->frame == LV_FRAME_AERO)
            return lv_pk_fail(c, v, "%s: the pitch is measured in the local or the inertial "
                              "frame", what);
        /* c >= 0: the denominator c + d tau is not negative at the phase's start (theta
         * within +-90 deg; c = 0 starts vertical); linear tangent: no c, d (1, 0) */
        const lv_range cpos = LV_RANGE_NONNEG;
        if ((st = num(c, n, what, phase, G, "a", "", any, 1, 0.0, &g->a)) ||
            (st = num(c, n, what, phase, G, "b", "1/s", any, 1, 0.0, &g->b)) ||
            (st = num(c, n, what, phase, G, "c", "", cpos, bilinear, NAN, &g->c)) ||
            (st = num(c, n, what, phase, G, "d", "1/s", any, bilinear, NAN, &g->d)) ||
            (st = num(c, n, what, phase, G, "heading", "rad", turn, 1, 0.0, &g->heading)))
            return st;
        return LV_OK;
    }
    case LV_STEER_HEADING: {
        if (!has_aero)
            return lv_pk_fail(c, lv_pk_get(n, "law"), "%s: the heading law banks the lift "
                              "vector: the phase needs an aerodynamic dataset (aero:)", what);
        const lv_range bank = {0.0, 0.5 * LV_PI, 1, 0};
        if ((st = num(c, n, what, phase, G, "bank_max", "rad", bank, 0, 45.0 * LV_DEG,
                      &g->bank_max)) ||
            (st = num(c, n, what, phase, G, "gain", "", gain, 0, 1.0, &g->gain)) ||
            (st = num(c, n, what, phase, G, "n_max", "", nonneg, 0, 0.0, &g->n_max)) ||
            (st = num(c, n, what, phase, G, "q_max", "Pa", nonneg, 0, 0.0, &g->hq_max)))
            return st;
        if (c->m->slots[g->hq_max].value > 0.0 && !(c->m->slots[g->n_max].value > 0.0))
            return lv_pk_fail(c, lv_pk_get(n, "q_max"), "%s: q_max releases the load-factor "
                              "limit as q rises: it needs n_max > 0", what);
        const lv_ynode *at = lv_pk_get(n, "alpha_table");
        if (at != NULL && (lv_pk_get(n, "alpha") || lv_pk_get(n, "alpha_deg")))
            return lv_pk_fail(c, lv_pk_key(n, "alpha_table"), "%s: alpha and alpha_table given "
                              "both", what);
        if ((st = num(c, n, what, phase, G, "alpha", "rad", half, at == NULL,
                      at == NULL ? 0.0 : NAN, &g->alpha)))
            return st;
        if (at != NULL) {
            if ((st = lv_pk_table(c, lv_pk_key(n, "alpha_table"), at, what, LV_EXTRAP_CLAMP,
                                  &g->table_file, &g->table_var, &g->table)) != LV_OK)
                return st;
            if ((st = lv_guid_table_check(g->table, g->law, LV_FRAME_AERO, NULL, c->err)) !=
                LV_OK)
                return lv_pk_fail(c, at, "%s: %s", what, c->err->msg);
        }
        return LV_OK;
    }
    case LV_STEER_BOOSTBACK:
        return num(c, n, what, phase, G, "pitch", "rad", half, 0, 0.0, &g->pitch);
    default:
        return LV_OK;
    }
}

static lv_status parse_throttle(const lv_pctx *c, const lv_ynode *n, const char *phase,
                                lv_guidance_def *g)
{
    static const char *const tkeys[] = {"value", "g_limit", "q_max", "q_gain", "landing", NULL};
    static const char *const lkeys[] = {"altitude", "speed", NULL};
    const char *T = "throttle";
    char what[LV_WHAT_MAX];
    lv_status st;
    snprintf(what, sizeof what, "phase '%s', throttle", phase);
    g->thr_given = 1;
    g->thr_value = g->g_limit = g->q_max = g->q_gain = LV_NO_SLOT;
    g->land_altitude = g->land_speed = LV_NO_SLOT;
    if (n->kind == LV_YNODE_SCALAR && strcmp(n->text, "off") == 0) {
        g->thr_law = LV_THROTTLE_OFF;
        return LV_OK;
    }
    if (n->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, n, "%s: 'off' or a mapping such as {g_limit: 4.5, q_max: 35000} "
                          "expected", what);
    if ((st = lv_pk_check_map(c, n, what, tkeys)) != LV_OK)
        return st;
    const lv_range nonneg = LV_RANGE_NONNEG, pos = LV_RANGE_POS, any = LV_RANGE_ANY;
    const lv_ynode *land = lv_pk_get(n, "landing");
    if (land != NULL) {
        for (size_t i = 0; tkeys[i] != NULL; i++)
            if (strcmp(tkeys[i], "landing") != 0 && lv_pk_get(n, tkeys[i]) != NULL)
                return lv_pk_fail(c, lv_pk_key(n, tkeys[i]), "%s: the landing law sets the "
                                  "throttle itself: '%s' does not go with it", what, tkeys[i]);
        char lwhat[LV_WHAT_MAX + 16];
        snprintf(lwhat, sizeof lwhat, "%s, landing", what);
        if (land->kind != LV_YNODE_MAP)
            return lv_pk_fail(c, land, "%s: a mapping {altitude: m, speed: m/s} expected", lwhat);
        if ((st = lv_pk_check_map(c, land, lwhat, lkeys)) != LV_OK)
            return st;
        g->thr_law = LV_THROTTLE_LANDING;
        char pre[LV_NAME_MAX + 16];
        snprintf(pre, sizeof pre, "%s", phase);
        if ((st = num(c, land, lwhat, pre, "throttle.landing", "altitude", "m", any, 0, 0.0,
                      &g->land_altitude)) ||
            (st = num(c, land, lwhat, pre, "throttle.landing", "speed", "m/s", nonneg, 0, 0.0,
                      &g->land_speed)))
            return st;
        return LV_OK;
    }
    g->thr_law = LV_THROTTLE_NOMINAL;
    if ((st = num(c, n, what, phase, T, "value", "", nonneg, 0, NAN, &g->thr_value)) ||
        (st = num(c, n, what, phase, T, "g_limit", "", pos, 0, NAN, &g->g_limit)) ||
        (st = num(c, n, what, phase, T, "q_max", "Pa", pos, 0, NAN, &g->q_max)))
        return st;
    if (g->q_max == LV_NO_SLOT && lv_pk_get(n, "q_gain") != NULL)
        return lv_pk_fail(c, lv_pk_key(n, "q_gain"), "%s: q_gain applies to q_max", what);
    const lv_range qg = {0.0, 100.0, 1, 0}; /* (0, 100] 1/s */
    if (g->q_max != LV_NO_SLOT &&
        (st = num(c, n, what, phase, T, "q_gain", "1/s", qg, 0, 1.0, &g->q_gain)))
        return st;
    return LV_OK;
}

lv_status lv_guidance_def_parse(const lv_pctx *c, const lv_ynode *guidance,
                                const lv_ynode *throttle, const char *phase, int has_aero,
                                lv_guidance_def *g)
{
    lv_status st;
    if (guidance != NULL && !lv_yaml_is_null(guidance) &&
        (st = parse_steering(c, guidance, phase, has_aero, g)) != LV_OK)
        return st;
    if (throttle != NULL && !lv_yaml_is_null(throttle) &&
        (st = parse_throttle(c, throttle, phase, g)) != LV_OK)
        return st;
    return LV_OK;
}

static double val(const double *vals, lv_slot s, double def)
{
    return s == LV_NO_SLOT ? def : vals[s];
}

void lv_guidance_def_make(const lv_guidance_def *g, const double *vals, lv_steering *s,
                          lv_throttle_cfg *t)
{
    if (g->given) {
        s->law = g->law;
        s->frame = g->frame;
        for (int i = 0; i < 3; i++)
            s->angle[i] = val(vals, g->angle[i], 0.0);
        s->table = g->law == LV_STEER_ATTITUDE ? g->table : NULL;
        s->alpha_table = g->law == LV_STEER_HEADING ? g->table : NULL;
        s->rise_time = val(vals, g->rise_time, 0.0);
        s->kick = val(vals, g->kick, 0.0);
        s->kick_time = val(vals, g->kick_time, 0.0);
        s->heading = val(vals, g->heading, 0.0);
        s->a = val(vals, g->a, 0.0);
        s->b = val(vals, g->b, 0.0);
        s->c = val(vals, g->c, 1.0);
        s->d = val(vals, g->d, 0.0);
        s->target_lat = val(vals, g->target_lat, NAN);
        s->target_lon = val(vals, g->target_lon, NAN);
        s->bank_max = val(vals, g->bank_max, s->bank_max);
        s->gain = val(vals, g->gain, s->gain);
        s->n_max = val(vals, g->n_max, 0.0);
        s->q_max = val(vals, g->hq_max, 0.0);
        s->alpha = val(vals, g->alpha, 0.0);
        s->pitch = val(vals, g->pitch, 0.0);
    }
    if (g->thr_given) {
        t->law = g->thr_law;
        t->g_limit = val(vals, g->g_limit, 0.0);
        t->q_max = val(vals, g->q_max, 0.0);
        t->q_gain = val(vals, g->q_gain, 1.0);
        t->land_altitude = val(vals, g->land_altitude, 0.0);
        t->land_speed = val(vals, g->land_speed, 0.0);
    }
}

void lv_guidance_def_clear(lv_guidance_def *g)
{
    free(g->table_file);
    free(g->table_var);
    lv_table_free(g->table);
    memset(g, 0, sizeof *g);
}
