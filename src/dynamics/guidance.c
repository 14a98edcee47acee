/* guidance.c - what every steering and throttle law shares (guidance.h, lv_guidance.h;
 * docs/guidance.md): the checks of a law's keys against its table, the resolution of a
 * configuration for the hot path, the phase's start, the time events, the target outputs and
 * the Euler angles of an attitude. The laws themselves: guid_<name>.c, thr_<name>.c; their
 * registry: guid_laws.c.
 */
#include "dynamics/guidance.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/status.h"
#include "dynamics/guid_kit.h"
#include "lvsim/lv_units.h"

const char *const lv_guid_frame_words[] = {"aero", "local", "inertial", NULL};

static const char *kind_word(lv_law_kind kind)
{
    return kind == LV_LAW_THROTTLE ? "throttle" : "guidance";
}

static double num_at(const void *base, const lv_law_key *k)
{
    double v;
    memcpy(&v, (const char *)base + k->offset, sizeof v);
    return v;
}

/* Key `name` of law, or NULL. */
static const lv_law_key *own_key(const lv_law *law, const char *name)
{
    for (size_t i = 0; law != NULL && name != NULL && i < law->n_keys; i++)
        if (strcmp(law->keys[i].name, name) == 0)
            return &law->keys[i];
    return NULL;
}

/* 1 when key k (of law, values par) is given: a table set, an optional number away from its
 * "none", any other number. */
static int key_given(const lv_law_key *k, const void *par)
{
    if (k->type == LV_KEY_TABLE) {
        const lv_table *t;
        memcpy(&t, (const char *)par + k->offset, sizeof t);
        return t != NULL;
    }
    if (k->type == LV_KEY_NUMBER && (k->flags & LV_KEY_OPTIONAL)) {
        const double v = num_at(par, k);
        return !isnan(v) && !(v == k->dflt);
    }
    return 1;
}

int lv_guid_key_applies(const lv_law *law, const lv_law_key *k, const void *par)
{
    if (k->frames != 0) {
        for (size_t i = 0; i < law->n_keys; i++)
            if (law->keys[i].type == LV_KEY_CHOICE) {
                int fr;
                memcpy(&fr, (const char *)par + law->keys[i].offset, sizeof fr);
                if (fr < 0 || fr > 31 || !(k->frames & (1u << fr)))
                    return 0;
            }
    }
    const lv_law_key *alt = own_key(law, k->instead_of);
    if (alt != NULL && key_given(alt, par))
        return 0;
    const lv_law_key *need = own_key(law, k->needs);
    return need == NULL || key_given(need, par);
}

void lv_guid_par_defaults(const lv_law *law, lv_law_par *par)
{
    memset(par, 0, sizeof *par);
    for (size_t i = 0; i < law->n_keys; i++) {
        const lv_law_key *k = &law->keys[i];
        char *at = (char *)par->d + k->offset;
        if (k->type == LV_KEY_NUMBER) {
            memcpy(at, &k->dflt, sizeof k->dflt);
        } else if (k->type == LV_KEY_CHOICE) {
            const int c = (int)k->dflt;
            memcpy(at, &c, sizeof c);
        } /* tables: NULL */
    }
}

/* "> 0 and <= 1.5708" for key k's range. */
static void range_text(const lv_law_key *k, char *buf, size_t cap)
{
    const int has_lo = isfinite(k->lo), has_hi = isfinite(k->hi);
    if (has_lo && has_hi)
        snprintf(buf, cap, "%s %g and %s %g", k->lo_open ? ">" : ">=", k->lo,
                 k->hi_open ? "<" : "<=", k->hi);
    else if (has_lo)
        snprintf(buf, cap, "%s %g", k->lo_open ? ">" : ">=", k->lo);
    else if (has_hi)
        snprintf(buf, cap, "%s %g", k->hi_open ? "<" : "<=", k->hi);
    else
        snprintf(buf, cap, "finite");
}

static int in_range(const lv_law_key *k, double v)
{
    return isfinite(v) && (k->lo_open ? v > k->lo : v >= k->lo) &&
           (k->hi_open ? v < k->hi : v <= k->hi);
}

/* Number key k at base: given when required, within its range; "none" of an optional one. */
static lv_status check_number(const lv_law *law, const lv_law_key *k, const void *base,
                              lv_err *err)
{
    const double v = num_at(base, k);
    const char *kw = kind_word(law->kind);
    if (isnan(v) && isnan(k->dflt)) {
        if (k->flags & LV_KEY_OPTIONAL)
            return LV_OK;
        return lv_fail(err, LV_ERR_INPUT, "%s '%s': %s is required", kw, law->name, k->name);
    }
    if ((k->flags & LV_KEY_OPTIONAL) && v == k->dflt)
        return LV_OK;
    if (in_range(k, v))
        return LV_OK;
    char rule[96];
    range_text(k, rule, sizeof rule);
    return lv_fail(err, LV_ERR_INPUT, "%s '%s': %s = %g%s%s must be %s%s%s", kw, law->name,
                   k->name, v, LV_UNIT_ONE(k->unit) ? "" : " ", LV_UNIT_AFTER_NUMBER(k->unit), rule,
                   LV_UNIT_ONE(k->unit) ? "" : " ", LV_UNIT_AFTER_NUMBER(k->unit));
}

lv_status lv_guid_law_check(const lv_law *law, const void *par, int has_aero, lv_law_at *at,
                            lv_err *err)
{
    const char *kw = kind_word(law->kind);
    at->key = NULL;
    at->node = LV_AT_MAP;
    if (law->needs_aero != NULL && !has_aero)
        return lv_fail(err, LV_ERR_INPUT, "%s '%s': the %s law %s: the phase needs an "
                       "aerodynamic dataset (aero:)", kw, law->name, law->name,
                       law->needs_aero);
    for (size_t i = 0; i < law->n_keys; i++) {
        const lv_law_key *k = &law->keys[i];
        if (k->type == LV_KEY_CHOICE) {
            int c;
            memcpy(&c, (const char *)par + k->offset, sizeof c);
            size_t n = 0;
            while (k->choices[n] != NULL)
                n++;
            if (c < 0 || (size_t)c >= n) {
                at->key = k->name;
                return lv_fail(err, LV_ERR_INPUT, "%s '%s': %s = %d: unknown (0 .. %zu)", kw,
                               law->name, k->name, c, n - 1);
            }
        }
    }
    for (size_t i = 0; i < law->n_keys; i++) {
        const lv_law_key *k = &law->keys[i];
        if (k->type != LV_KEY_NUMBER || !lv_guid_key_applies(law, k, par))
            continue;
        lv_status st = check_number(law, k, par, err);
        if (st != LV_OK) {
            at->key = k->name;
            at->node = LV_AT_VALUE;
            return st;
        }
    }
    if (law->check == NULL)
        return LV_OK;
    lv_status st = law->check(par, at, err);
    return st == LV_OK ? LV_OK : lv_fail_prefix(err, st, "%s '%s'", kw, law->name);
}

/* The law of a configuration (given: its law, NULL: the kind's default `dflt`) and its
 * parameters (the default law's defaults), checked: the law, across keys, ranges. */
static lv_status resolve(lv_law_kind kind, const lv_law *given, const lv_law_par *par,
                         const char *dflt, int has_aero, const lv_law **law, lv_law_par *out,
                         lv_err *err)
{
    *law = given != NULL ? given : lv_guid_law_find(kind, dflt);
    if ((*law)->kind != kind)
        return lv_fail(err, LV_ERR_INPUT, "%s: '%s' is a %s law", kind_word(kind),
                       (*law)->name, kind == LV_LAW_STEERING ? "throttle" : "steering");
    if (given != NULL)
        *out = *par;
    else
        lv_guid_par_defaults(*law, out);
    lv_law_at at;
    return lv_guid_law_check(*law, out, has_aero, &at, err);
}

lv_status lv_guid_init(lv_guid *g, const lv_steering *s, const lv_planet *planet, int has_aero,
                       lv_err *err)
{
    memset(g, 0, sizeof *g);
    lv_status st = resolve(LV_LAW_STEERING, s->law, &s->par, "inputs", has_aero, &g->law,
                           &g->par, err);
    if (st != LV_OK)
        return st;
    size_t n_common;
    const lv_law_key *common = lv_laws_common_keys(LV_LAW_STEERING, &n_common);
    for (size_t i = 0; i < n_common; i++) {
        st = check_number(g->law, &common[i], s, err);
        if (st == LV_OK && isnan(num_at(s, &common[i]))) /* the model puts its start there */
            st = lv_fail(err, LV_ERR_INPUT, "guidance '%s': %s is not set", g->law->name,
                         common[i].name);
        if (st != LV_OK)
            return st;
    }
    g->need_alpha = g->need_beta = 1; /* lv_dof3 narrows them down */
    g->planet = *planet;
    g->commands_accel = g->law->accel_command != NULL;
    if (g->law->init != NULL && (st = g->law->init(g, err)) != LV_OK)
        return lv_fail_prefix(err, st, "guidance '%s'", g->law->name);
    g->reads_atm = g->law->reads_atmosphere != NULL && g->law->reads_atmosphere(g);
    double r[3];
    lv_frames_geodetic_to_ecef(planet, s->target_lat, s->target_lon, 0.0, r);
    g->target_r = lv_v3(r[0], r[1], r[2]);
    g->target = lv_v3_unit(g->target_r);
    return LV_OK;
}

lv_status lv_thr_init(lv_thr *t, const lv_throttle_cfg *cfg, lv_err *err)
{
    memset(t, 0, sizeof *t);
    lv_status st = resolve(LV_LAW_THROTTLE, cfg->law, &cfg->par, "nominal", 1, &t->law, &t->par,
                           err);
    if (st == LV_OK && t->law->thr_init != NULL && (st = t->law->thr_init(t, err)) != LV_OK)
        return lv_fail_prefix(err, st, "throttle '%s'", t->law->name);
    return st;
}

int lv_thr_engines_off(const lv_throttle_cfg *cfg)
{
    lv_thr t;
    return lv_thr_init(&t, cfg, NULL) == LV_OK && t.engines_off;
}

int lv_guid_gives_throttle(const lv_steering *s)
{
    return s->law != NULL && s->law->gives_throttle != NULL && s->law->gives_throttle(&s->par);
}

const lv_law_key *lv_guid_dof3_key(const lv_steering *s)
{
    for (size_t i = 0; s->law != NULL && i < s->law->n_keys; i++) {
        const lv_law_key *k = &s->law->keys[i];
        if ((k->flags & LV_KEY_DOF3) && k->type == LV_KEY_NUMBER &&
            !(num_at(&s->par, k) == k->dflt))
            return k;
    }
    return NULL;
}

int lv_guid_start(const lv_guid *g, lv_guid_rt *rt, double t0, const lv_flight_kin *k,
                  char *msg, size_t cap)
{
    rt->t0 = t0;
    rt->cur = (lv_table_cursor)LV_TABLE_CURSOR_INIT;
    for (int i = 0; i < 3; i++)
        rt->ang[i] = NAN;
    /* ECEF -> ECI: R3(theta)^T with theta the angle k->c_th, k->s_th stand for */
    const lv_vec3 ax[3] = {k->n_ax, k->e_ax, k->d_ax};
    for (int i = 0; i < 3; i++)
        rt->f0[i] = lv_v3(k->c_th * ax[i].x - k->s_th * ax[i].y,
                          k->s_th * ax[i].x + k->c_th * ax[i].y, ax[i].z);
    for (int i = 0; i < 4; i++)
        rt->s0[i] = NAN;
    return g->law->start != NULL ? g->law->start(g, rt, k, msg, cap) : 0;
}

unsigned lv_guid_refs(const lv_guid *g, const lv_guid_rt *rt, double t)
{
    return g->law->refs != NULL ? g->law->refs(g, rt, t) : 0u;
}

double lv_guid_next_time_event(const lv_guid *g, const lv_guid_rt *rt, double t)
{
    return g->law->next_time_event != NULL ? g->law->next_time_event(g, rt, t) : INFINITY;
}

const char *lv_guid_time_event_label(const lv_guid *g, const lv_guid_rt *rt, double t)
{
    return g->law->time_event_label != NULL ? g->law->time_event_label(g, rt, t) : NULL;
}

double lv_guid_alpha_limited(const lv_guid *g, double alpha, double lift, double mass, double q)
{
    return g->limits_alpha ? g->law->alpha_limited(g, alpha, lift, mass, q) : alpha;
}

void lv_guid_target(const lv_guid *g, const lv_flight_kin *k, double radius, double g_up,
                    double *distance, double *bearing, double *overshoot)
{
    double b[2];
    lv_guid_bearing_cs(g, k, b);
    *bearing = atan2(b[1], b[0]);
    if (*bearing < 0.0) /* [0, 2 pi), as the headings */
        *bearing += 2.0 * LV_PI;
    /* from the point on the ellipsoid below the vehicle (along its geodetic vertical), so that
     * a vehicle above the target is at distance 0 */
    const lv_vec3 foot = lv_v3_unit(lv_v3_add(k->r_ecef, lv_v3_scale(k->d_ax, k->h)));
    *distance =
        radius * atan2(lv_v3_norm(lv_v3_cross(foot, g->target)), lv_v3_dot(foot, g->target));
    /* vacuum ballistic flight over flat ground: t_fall from h' = v_up - g t, h(t_f) = 0 */
    const double v_up = -lv_v3_dot(k->v_rel, k->d_ax);
    const double hh = k->h > 0.0 ? k->h : 0.0;
    const double gg = g_up > 0.0 ? g_up : LV_G0;
    const double t_fall = (v_up + sqrt(v_up * v_up + 2.0 * gg * hh)) / gg;
    const double v_toward = lv_v3_dot(k->v_rel, lv_flight_from_ned(k, b[0], b[1], 0.0));
    *overshoot = v_toward * (t_fall > 0.0 ? t_fall : 0.0) - *distance;
}

void lv_guid_euler_local(const lv_flight_kin *k, const lv_flight_axes *ax, double *theta,
                         double *psi, double *phi)
{
    /* rows of C_body_ned: the body axes in NED components */
    const double x_n = lv_v3_dot(ax->xb, k->n_ax), x_e = lv_v3_dot(ax->xb, k->e_ax);
    const double x_d = lv_v3_dot(ax->xb, k->d_ax);
    const double y_d = lv_v3_dot(ax->yb, k->d_ax), z_d = lv_v3_dot(ax->zb, k->d_ax);
    *theta = -asin(x_d > 1.0 ? 1.0 : x_d < -1.0 ? -1.0 : x_d);
    if (x_n * x_n + x_e * x_e > 1e-18) {
        *psi = atan2(x_e, x_n);
        *phi = atan2(y_d, z_d);
    } else { /* body x vertical (gimbal lock): psi and phi are one rotation; phi = 0, so that
                body y = (-sin psi, cos psi, 0) gives psi */
        *psi = atan2(-lv_v3_dot(ax->yb, k->n_ax), lv_v3_dot(ax->yb, k->e_ax));
        *phi = 0.0;
    }
    if (*psi < 0.0) /* [0, 2 pi), as the headings */
        *psi += 2.0 * LV_PI;
}

/* ---- a flight model's time events -------------------------------------------------------- */

double lv_flight_next_time_event(const lv_table *inputs, const lv_engine *eng, size_t n_eng,
                                 const lv_guid *g, const lv_guid_rt *rt, double t)
{
    double tn = inputs != NULL ? lv_table_next_breakpoint(inputs, 0, t) : INFINITY;
    for (size_t i = 0; i < n_eng; i++) {
        if (eng[i].table != NULL)
            tn = fmin(tn, lv_table_next_breakpoint(eng[i].table, 0, t));
        if (!eng[i].out && eng[i].t_out > t) /* an engine-out: the thrust drops there */
            tn = fmin(tn, eng[i].t_out);
    }
    return g != NULL ? fmin(tn, lv_guid_next_time_event(g, rt, t)) : tn;
}

/* 1 if table `tab` has a breakpoint at exactly t on its first axis (time). */
static int breakpoint_at(const lv_table *tab, double t)
{
    size_t n = 0;
    const double *b = tab != NULL ? lv_table_breakpoints(tab, 0, &n) : NULL;
    for (size_t i = 0; b != NULL && i < n; i++)
        if (b[i] == t)
            return 1;
    return 0;
}

const char *lv_flight_time_event_label(const lv_table *inputs, const lv_engine *eng,
                                       size_t n_eng, const lv_guid *g, const lv_guid_rt *rt,
                                       double t, char *buf, size_t cap)
{
    size_t len = 0;
    buf[0] = '\0';
    if (breakpoint_at(inputs, t))
        len += (size_t)snprintf(buf, cap, "inputs table '%.40s' breakpoint", lv_table_name(inputs));
    const char *gl = g != NULL ? lv_guid_time_event_label(g, rt, t) : NULL;
    if (gl != NULL && len < cap)
        len += (size_t)snprintf(buf + len, cap - len, "%s%s", len ? "; " : "", gl);
    for (size_t i = 0; i < n_eng && len < cap; i++)
        if (breakpoint_at(eng[i].table, t))
            len += (size_t)snprintf(buf + len, cap - len, "%sengine '%.24s' table breakpoint",
                                    len ? "; " : "", eng[i].name);
    /* engine-outs at t: "engine-out 1 x 'merlin'" (identical engines share a name) */
    for (size_t i = 0; i < n_eng && len < cap; i++) {
        if (eng[i].t_out != t || (i > 0 && eng[i - 1].t_out == t &&
                                  strcmp(eng[i - 1].name, eng[i].name) == 0))
            continue;
        size_t n = 1;
        while (i + n < n_eng && eng[i + n].t_out == t && strcmp(eng[i + n].name, eng[i].name) == 0)
            n++;
        len += (size_t)snprintf(buf + len, cap - len, "%sengine-out %zu x '%.24s'",
                                len ? "; " : "", n, eng[i].name);
    }
    if (len > 0 && len < cap)
        snprintf(buf + len, cap - len, " t = %.9g s", t);
    return buf;
}
