/* parse_env.c - a mission file's `environment:` (world, planet, gravity, atmosphere, wind) into
 * the definition's lv_env_def, its numbers as slots "environment.<...>". Format:
 * docs/mission-format.md ("environment"); models: docs/atmosphere.md, gravity.md, wind.md. */

#include "mission/mission.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/utc.h"
#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_wind.h"
#include "mission/parse_int.h"

static const char *const planet_presets[] = { "earth", "moon", "mars", NULL };

/* planet: {name, base, radius, flattening, gm, rotation_rate(_deg), r_ref, zonal,
 * coefficients, sutton_graves_k}: a planet by its constants (docs/mission-format.md). Written numbers are
 * slots "environment.planet.<key>" ("environment.planet.J2" ... for the zonal list). */
static lv_status parse_planet_map(const lv_pctx *c, const lv_ynode *n, lv_env_def *e,
                                  int *earth)
{
    static const char *const keys[] = { "name", "base", "radius", "flattening", "gm",
                                        "rotation_rate", "rotation_rate_deg", "r_ref", "zonal",
                                        "coefficients", "sutton_graves_k", NULL };
    const char *what = "environment, planet";
    lv_planet_def *pd = &e->pdef;
    const lv_ynode *v;
    lv_status st;
    size_t i, base = 0;
    if ((st = lv_pk_check_map(c, n, what, keys)) != LV_OK)
        return st;
    pd->custom = 1;
    pd->loc = lv_pk_loc(n);
    memset(&pd->base, 0, sizeof pd->base);
    if ((v = lv_pk_get(n, "base")) != NULL) {
        if ((st = lv_pk_enum(c, v, what, "base", planet_presets, &i)) != LV_OK ||
            (st = lv_planet_by_name(planet_presets[i], &pd->base, NULL)) != LV_OK)
            return st;
        pd->has_base = 1;
        base = i;
        *earth = i == 0;
    } else {
        const char *req[] = { "radius", "gm" };
        for (size_t k = 0; k < 2; k++)
            if (lv_pk_get(n, req[k]) == NULL)
                return lv_pk_fail(c, n, "%s: missing required key '%s' (or give 'base: earth', "
                                  "'moon' or 'mars' to start from a preset's constants)", what,
                                  req[k]);
    }
    const char *name = "custom";
    if ((v = lv_pk_get(n, "name")) != NULL) {
        if ((st = lv_pk_text(c, v, what, "name", &name)) != LV_OK)
            return st;
        if (!lv_pk_valid_name(name, 0) || strlen(name) >= LV_PLANET_NAME_MAX)
            return lv_pk_fail(c, v, "%s: name '%.40s' must be 1 to %d letters, digits, '_' or "
                              "'-'", what, name, LV_PLANET_NAME_MAX - 1);
        for (i = 0; planet_presets[i] != NULL; i++)
            if (strcmp(name, planet_presets[i]) == 0)
                return lv_pk_fail(c, v, "%s: name '%s' is a preset's; a planet given by its "
                                  "constants needs a name of its own (exports take '%s' for "
                                  "the preset)", what, name, name);
    }
    snprintf(pd->base.name, sizeof pd->base.name, "%s", name);
    if ((e->planet = lv_pk_strdup(name)) == NULL)
        return lv_pk_nomem(c);

    /* the constants; ranges hold any planet (the Sun: a = 7e8 m, GM = 1.3e20 m^3/s^2) */
    static const lv_range r_len = { 0.0, 1e10, 1, 0 }, r_gm = { 0.0, 1e21, 1, 0 },
                          r_f = { 0.0, 1.0, 0, 1 }, r_w = { -1.0, 1.0, 0, 0 },
                          r_j = { -1.0, 1.0, 1, 1 };
    const struct {
        const char *key, *unit;
        lv_range range;
        lv_slot *slot;
    } num[] = {
        { "radius", "m", r_len, &pd->radius },
        { "flattening", "", r_f, &pd->flattening },
        { "gm", "m3/s2", r_gm, &pd->gm },
        { "rotation_rate", "rad/s", r_w, &pd->rotation_rate },
        { "r_ref", "m", r_len, &pd->r_ref },
    };
    for (size_t k = 0; k < sizeof num / sizeof num[0]; k++) {
        char slot[64];
        *num[k].slot = LV_NO_SLOT;
        snprintf(slot, sizeof slot, "environment.planet.%s", num[k].key);
        const lv_ynode *vd = NULL;
        v = lv_pk_get(n, num[k].key);
        if (num[k].slot == &pd->rotation_rate && (vd = lv_pk_get(n, "rotation_rate_deg")) != NULL &&
            v != NULL)
            return lv_pk_fail(c, lv_pk_key(n, "rotation_rate_deg"), "%s: 'rotation_rate' and "
                              "'rotation_rate_deg' given both", what);
        if (v == NULL && vd == NULL)
            continue;
        if ((st = lv_pk_slot(c, v ? v : vd, what, v ? num[k].key : "rotation_rate_deg", slot,
                             num[k].unit, num[k].range, vd != NULL, num[k].slot)) != LV_OK)
            return st;
    }
    /* the heat flux's constant, kg^0.5/m: not a run parameter (no unit of the Modelica
     * grammar has the square root of a kilogram) */
    pd->sutton_graves_k = NAN;
    if ((v = lv_pk_get(n, "sutton_graves_k")) != NULL) {
        if ((st = lv_pk_num(c, v, what, "sutton_graves_k", &pd->sutton_graves_k)) != LV_OK)
            return st;
        if (!(pd->sutton_graves_k >= 0.0 && pd->sutton_graves_k < 1.0))
            return lv_pk_fail(c, v, "%s: sutton_graves_k: a constant in kg^0.5/m in [0, 1) "
                              "expected (air: 1.7415e-4), found %.6g", what, pd->sutton_graves_k);
    } else if (pd->has_base && strcmp(planet_presets[base], "mars") == 0) {
        pd->sutton_graves_k = LV_SUTTON_GRAVES_MARS;
    }
    if ((v = lv_pk_get(n, "zonal")) != NULL) {
        if (v->kind != LV_YNODE_SEQ && !lv_yaml_is_null(v))
            return lv_pk_fail(c, v, "%s: zonal: a list [J2, J3, ...] expected", what);
        pd->zonal_given = 1;
        pd->n_zonal = v->kind == LV_YNODE_SEQ ? v->n : 0;
        if (pd->n_zonal > LV_GRAVITY_ZONAL_MAX - 1)
            return lv_pk_fail(c, v, "%s: zonal: %zu coefficients; at most %d (J2 .. J%d)", what,
                              pd->n_zonal, LV_GRAVITY_ZONAL_MAX - 1, LV_GRAVITY_ZONAL_MAX);
        if (pd->n_zonal > 0 && (pd->zonal = calloc(pd->n_zonal, sizeof *pd->zonal)) == NULL)
            return lv_pk_nomem(c);
        for (size_t k = 0; k < pd->n_zonal; k++) {
            char slot[64], key[16];
            snprintf(key, sizeof key, "J%zu", k + 2);
            snprintf(slot, sizeof slot, "environment.planet.%s", key);
            if ((st = lv_pk_slot(c, v->kids[k], what, key, slot, "", r_j, 0, &pd->zonal[k])) !=
                LV_OK)
                return st;
        }
    }
    if ((v = lv_pk_get(n, "coefficients")) != NULL) {
        const char *rel;
        if ((st = lv_pk_text(c, v, what, "coefficients", &rel)) != LV_OK)
            return st;
        if ((pd->coef_file = lv_pk_resolve_file(c, rel)) == NULL)
            return lv_pk_nomem(c);
        if ((st = lv_pk_regular_file(c, v, what, "coefficients", pd->coef_file)) != LV_OK)
            return st;
    }
    /* the planet as the file gives it must hold together (lv_planet_check: the rotation) */
    lv_planet p = pd->base;
    const lv_mission_def *m = c->m;
    if (pd->radius != LV_NO_SLOT) p.a = m->slots[pd->radius].value;
    if (pd->flattening != LV_NO_SLOT) p.f = m->slots[pd->flattening].value;
    if (pd->gm != LV_NO_SLOT) p.gm = m->slots[pd->gm].value;
    if (pd->rotation_rate != LV_NO_SLOT) p.omega = m->slots[pd->rotation_rate].value;
    p.r_ref = pd->r_ref != LV_NO_SLOT ? m->slots[pd->r_ref].value : pd->has_base ? p.r_ref : p.a;
    lv_err perr;
    if (lv_planet_check(&p, &perr) != LV_OK)
        return lv_pk_fail(c, n, "%s: %s", what, perr.msg);
    return LV_OK;
}

/* atmosphere: us76 | exp | none | {table: path, var: name} | {model: exp, rho0, scale_height,
 * temperature} (the exponential model's parameters: slots "environment.atmosphere.<key>"). */
static lv_status parse_atmosphere(const lv_pctx *c, const lv_ynode *v, size_t deflt,
                                  lv_env_def *e)
{
    static const char *const atmos[] = { "us76", "exp", "none", NULL };
    static const char *const keys[] = { "table", "var", "model", "rho0", "scale_height",
                                        "temperature", "profile", "blend", NULL };
    static const char *const pkeys[3] = { "rho0", "scale_height", "temperature" };
    static const char *const punit[3] = { "kg/m3", "m", "K" };
    const char *what = "environment, atmosphere";
    size_t i = deflt;
    lv_status st;
    for (size_t k = 0; k < 3; k++)
        e->atmo_par[k] = LV_NO_SLOT;
    if (v != NULL && v->kind == LV_YNODE_MAP) {
        if ((st = lv_pk_check_map(c, v, what, keys)) != LV_OK)
            return st;
        const lv_ynode *mv = lv_pk_get(v, "model");
        e->atmo_blend = LV_ATMO_PROFILE_BLEND;
        if (lv_pk_get(v, "profile") != NULL) { /* {profile: path, blend: m}: measured data */
            static const char *const other[] = { "table", "var", "model", "rho0",
                                                 "scale_height", "temperature", NULL };
            for (size_t k = 0; other[k] != NULL; k++)
                if (lv_pk_get(v, other[k]) != NULL)
                    return lv_pk_fail(c, lv_pk_key(v, other[k]), "%s: '%s' does not go with "
                                      "'profile' (a profile file, blended into US76 above its "
                                      "top)", what, other[k]);
            const lv_ynode *pv = lv_pk_get(v, "profile"), *bv = lv_pk_get(v, "blend");
            const char *rel;
            if ((st = lv_pk_text(c, pv, what, "profile", &rel)) != LV_OK)
                return st;
            if ((e->atmo_file = lv_pk_resolve_file(c, rel)) == NULL)
                return lv_pk_nomem(c);
            if ((st = lv_pk_regular_file(c, pv, what, "profile", e->atmo_file)) != LV_OK)
                return st;
            if (bv != NULL) {
                if ((st = lv_pk_num(c, bv, what, "blend", &e->atmo_blend)) != LV_OK)
                    return st;
                if (!(e->atmo_blend > 0.0 && e->atmo_blend <= 1e6))
                    return lv_pk_fail(c, bv, "%s: blend = %g m is out of range (0, 1e6] m", what,
                                      e->atmo_blend);
            }
            e->atmosphere = lv_pk_strdup("profile");
            return e->atmosphere != NULL ? LV_OK : lv_pk_nomem(c);
        }
        if (lv_pk_get(v, "blend") != NULL)
            return lv_pk_fail(c, lv_pk_key(v, "blend"), "%s: 'blend' goes with 'profile'", what);
        if (lv_pk_get(v, "table") != NULL) { /* {table: path, var: name}: from a file */
            if (mv != NULL)
                return lv_pk_fail(c, lv_pk_key(v, "model"), "%s: give either 'table' (a file) "
                                  "or 'model', not both", what);
            for (size_t k = 0; k < 3; k++)
                if (lv_pk_get(v, pkeys[k]) != NULL)
                    return lv_pk_fail(c, lv_pk_key(v, pkeys[k]), "%s: '%s' belongs to model: "
                                      "exp", what, pkeys[k]);
            if ((st = lv_pk_table_file(c, v, what, "table", &e->atmo_file, &e->atmo_var)) != LV_OK ||
                (st = lv_pk_regular_file(c, lv_pk_get(v, "table"), what, "table", e->atmo_file)) !=
                    LV_OK)
                return st;
            e->atmosphere = lv_pk_strdup("table");
            return e->atmosphere != NULL ? LV_OK : lv_pk_nomem(c);
        }
        if (lv_pk_get(v, "var") != NULL)
            return lv_pk_fail(c, lv_pk_key(v, "var"), "%s: 'var' goes with 'table'", what);
        if ((st = lv_pk_need(c, v, what, "model", &mv)) != LV_OK ||
            (st = lv_pk_enum(c, mv, what, "model", atmos, &i)) != LV_OK)
            return st;
        for (size_t k = 0; k < 3; k++) {
            const lv_ynode *pv = lv_pk_get(v, pkeys[k]);
            if (pv == NULL)
                continue;
            if (i != 1)
                return lv_pk_fail(c, lv_pk_key(v, pkeys[k]), "%s: '%s' belongs to model: exp "
                                  "(this is %s)", what, pkeys[k], atmos[i]);
            char slot[64];
            snprintf(slot, sizeof slot, "environment.atmosphere.%s", pkeys[k]);
            if ((st = lv_pk_slot(c, pv, what, pkeys[k], slot, punit[k], LV_RANGE_POS, 0,
                                 &e->atmo_par[k])) != LV_OK)
                return st;
        }
    } else if (v != NULL && (st = lv_pk_enum(c, v, "environment", "atmosphere", atmos, &i)) !=
                                LV_OK) {
        return st;
    }
    e->atmosphere = lv_pk_strdup(atmos[i]);
    return e->atmosphere != NULL ? LV_OK : lv_pk_nomem(c);
}

/* wind: {profile: path | [{file: path, t: s | utc: ISO 8601}, ...], blend: m}: winds from
 * profile files at mission times (docs/wind.md, "Profiles"). */
static lv_status parse_wind_profiles(const lv_pctx *c, const lv_ynode *v, lv_env_def *e)
{
    const char *what = "environment, wind";
    static const char *const other[] = { "file", "var", "interp", "extrap", "north", "east",
                                         "down", NULL };
    static const char *const ikeys[] = { "file", "t", "utc", NULL };
    lv_status st;
    for (size_t k = 0; other[k] != NULL; k++)
        if (lv_pk_get(v, other[k]) != NULL)
            return lv_pk_fail(c, lv_pk_key(v, other[k]), "%s: '%s' does not go with 'profile' "
                              "(winds from profile files)", what, other[k]);
    const lv_ynode *pv = lv_pk_get(v, "profile"), *bv = lv_pk_get(v, "blend");
    e->wind_blend = LV_ATMO_PROFILE_BLEND;
    if (bv != NULL) {
        if ((st = lv_pk_num(c, bv, what, "blend", &e->wind_blend)) != LV_OK)
            return st;
        if (!(e->wind_blend > 0.0 && e->wind_blend <= 1e6))
            return lv_pk_fail(c, bv, "%s: blend = %g m is out of range (0, 1e6] m", what,
                              e->wind_blend);
    }
    const size_t n = pv->kind == LV_YNODE_SEQ ? pv->n : 1;
    if (n < 1 || n > LV_WIND_PROFILES_MAX)
        return lv_pk_fail(c, pv, "%s: profile: %zu profiles; 1 to %d", what, n,
                          LV_WIND_PROFILES_MAX);
    e->wind_prof_file = calloc(n, sizeof *e->wind_prof_file);
    e->wind_prof_t = calloc(n, sizeof *e->wind_prof_t);
    if (e->wind_prof_file == NULL || e->wind_prof_t == NULL)
        return lv_pk_nomem(c);
    for (size_t k = 0; k < n; k++) {
        const lv_ynode *it = pv->kind == LV_YNODE_SEQ ? pv->kids[k] : pv, *fv = it, *tv;
        const char *rel;
        char item[48];
        snprintf(item, sizeof item, "%s, profile #%zu", what, k + 1);
        if (it->kind == LV_YNODE_MAP) {
            if ((st = lv_pk_check_map(c, it, item, ikeys)) != LV_OK ||
                (st = lv_pk_need(c, it, item, "file", &fv)) != LV_OK)
                return st;
            const lv_ynode *uv = lv_pk_get(it, "utc");
            tv = lv_pk_get(it, "t");
            if ((tv == NULL) == (uv == NULL))
                return lv_pk_fail(c, it, "%s: give its time, either 't' (s, mission time) or "
                                  "'utc' (ISO 8601)", item);
            if (tv != NULL && (st = lv_pk_num(c, tv, item, "t", &e->wind_prof_t[k])) != LV_OK)
                return st;
            if (uv != NULL) {
                const char *utc;
                lv_tai tai = 0, epoch = 0;
                if ((st = lv_pk_text(c, uv, item, "utc", &utc)) != LV_OK)
                    return st;
                if (c->m->epoch == NULL)
                    return lv_pk_fail(c, uv, "%s: a profile at a UTC time needs the mission's "
                                      "epoch (mission: epoch: ...), or give 't' in mission "
                                      "time", item);
                const int r = lv_utc_parse(utc, &tai);
                if (r != LV_UTC_OK && r != LV_UTC_DUBIOUS)
                    return lv_pk_fail(c, uv, "%s: utc: '%.40s' is not a UTC time "
                                      "YYYY-MM-DDThh:mm:ss[.f]Z", item, utc);
                (void)lv_utc_parse(c->m->epoch, &epoch); /* checked with the mission */
                e->wind_prof_t[k] = (double)(tai - epoch) * 1e-6;
            }
            if (k > 0 && !(e->wind_prof_t[k] > e->wind_prof_t[k - 1]))
                return lv_pk_fail(c, tv != NULL ? tv : lv_pk_get(it, "utc"), "%s: at t = %.9g s, "
                                  "not after the profile before it (t = %.9g s): list the "
                                  "profiles in time order", item, e->wind_prof_t[k],
                                  e->wind_prof_t[k - 1]);
        } else if (n > 1) {
            return lv_pk_fail(c, it, "%s: {file: path, t: s} or {file: path, utc: time} "
                              "expected", item);
        }
        if ((st = lv_pk_text(c, fv, item, "file", &rel)) != LV_OK)
            return st;
        if ((e->wind_prof_file[k] = lv_pk_resolve_file(c, rel)) == NULL)
            return lv_pk_nomem(c);
        e->n_wind_prof = k + 1;
        if ((st = lv_pk_regular_file(c, fv, item, "file", e->wind_prof_file[k])) != LV_OK)
            return st;
    }
    return LV_OK;
}

/* wind: path | {file: path, var, interp, extrap} | {north, east, down} | {profile, blend}: a
 * table over altitude, a constant (slots "environment.wind.north" ...) or profiles,
 * docs/wind.md. */
static lv_status parse_wind(const lv_pctx *c, const lv_ynode *v, lv_env_def *e)
{
    static const char *const keys[] = { "file", "var", "interp", "extrap", "north", "east",
                                        "down", "profile", "blend", NULL };
    static const char *const comp[3] = { "north", "east", "down" };
    static const char *const interps[] = { "linear", "pchip", NULL };
    static const char *const extraps[] = { "clamp", "error", "linear", NULL };
    static const lv_extrap extrap_of[] = { LV_EXTRAP_CLAMP, LV_EXTRAP_ERROR, LV_EXTRAP_LINEAR };
    static const lv_range r_wind = { -500.0, 500.0, 0, 0 }; /* m/s: beyond any jet stream */
    const char *what = "environment, wind";
    lv_status st;
    size_t i;
    e->wind_interp = LV_INTERP_LINEAR;
    e->wind_extrap = LV_EXTRAP_CLAMP;
    e->wind_loc = lv_pk_loc(v);
    if (v->kind != LV_YNODE_MAP) {
        const char *rel;
        if ((st = lv_pk_text(c, v, "environment", "wind", &rel)) != LV_OK)
            return st;
        if ((e->wind_file = lv_pk_resolve_file(c, rel)) == NULL)
            return lv_pk_nomem(c);
        return lv_pk_regular_file(c, v, "environment", "wind", e->wind_file);
    }
    if ((st = lv_pk_check_map(c, v, what, keys)) != LV_OK)
        return st;
    if (lv_pk_get(v, "profile") != NULL)
        return parse_wind_profiles(c, v, e);
    if (lv_pk_get(v, "blend") != NULL)
        return lv_pk_fail(c, lv_pk_key(v, "blend"), "%s: 'blend' goes with 'profile'", what);
    const lv_ynode *f = lv_pk_get(v, "file"), *o;
    for (size_t k = 0; k < 3; k++) {
        const lv_ynode *cv = lv_pk_get(v, comp[k]);
        if (cv != NULL && f != NULL)
            return lv_pk_fail(c, lv_pk_key(v, comp[k]), "%s: give either 'file' (a table) or "
                              "the constant components north, east[, down], not both", what);
    }
    if (f != NULL) {
        if ((st = lv_pk_table_file(c, v, what, "file", &e->wind_file, &e->wind_var)) != LV_OK ||
            (st = lv_pk_regular_file(c, f, what, "file", e->wind_file)) != LV_OK)
            return st;
        if ((o = lv_pk_get(v, "interp")) != NULL) {
            if ((st = lv_pk_enum(c, o, what, "interp", interps, &i)) != LV_OK)
                return st;
            e->wind_interp = i == 0 ? LV_INTERP_LINEAR : LV_INTERP_PCHIP;
        }
        if ((o = lv_pk_get(v, "extrap")) != NULL) {
            if ((st = lv_pk_enum(c, o, what, "extrap", extraps, &i)) != LV_OK)
                return st;
            e->wind_extrap = extrap_of[i];
        }
        return LV_OK;
    }
    const char *tkeys[] = { "var", "interp", "extrap" };
    for (size_t k = 0; k < 3; k++)
        if (lv_pk_get(v, tkeys[k]) != NULL)
            return lv_pk_fail(c, lv_pk_key(v, tkeys[k]), "%s: '%s' goes with 'file' (a wind "
                              "table)", what, tkeys[k]);
    e->wind_const = 1;
    for (size_t k = 0; k < 3; k++) {
        char slot[64];
        e->wind_ned[k] = LV_NO_SLOT;
        snprintf(slot, sizeof slot, "environment.wind.%s", comp[k]);
        if (k < 2 && (st = lv_pk_need(c, v, what, comp[k], &o)) != LV_OK)
            return st;
        if ((o = lv_pk_get(v, comp[k])) != NULL &&
            (st = lv_pk_slot(c, o, what, comp[k], slot, "m/s", r_wind, 0, &e->wind_ned[k])) !=
                LV_OK)
            return st;
    }
    return LV_OK;
}

/* gust: {altitude, half_width, north, east, down} or a list of them: 1-cosine gusts over
 * altitude (slots "environment.gust<k>.<key>", k from 1), docs/wind.md "Gusts and turbulence". */
static lv_status parse_gusts(const lv_pctx *c, const lv_ynode *v, lv_env_def *e)
{
    static const char *const keys[] = { "altitude", "half_width", "north", "east", "down", NULL };
    static const char *const units[] = { "m", "m", "m/s", "m/s", "m/s" };
    static const lv_range ranges[] = { { -1e5, 1e7, 0, 0 }, { 0.0, 1e6, 1, 0 },
                                       { -500.0, 500.0, 0, 0 }, { -500.0, 500.0, 0, 0 },
                                       { -500.0, 500.0, 0, 0 } };
    const size_t n = v->kind == LV_YNODE_SEQ ? v->n : 1;
    e->gust_loc = lv_pk_loc(v);
    if (v->kind == LV_YNODE_SEQ && (n == 0 || n > LV_GUSTS_MAX))
        return lv_pk_fail(c, v, "environment, gust: %zu gusts; 1 to %d", n, LV_GUSTS_MAX);
    for (size_t k = 0; k < n; k++) {
        const lv_ynode *g = v->kind == LV_YNODE_SEQ ? v->kids[k] : v;
        char what[48];
        snprintf(what, sizeof what, "environment, gust %zu", k + 1);
        lv_status st = lv_pk_check_map(c, g, what, keys);
        if (st != LV_OK)
            return st;
        const lv_ynode *o;
        for (size_t i = 0; i < 2; i++)
            if ((st = lv_pk_need(c, g, what, keys[i], &o)) != LV_OK)
                return st;
        if (lv_pk_get(g, "north") == NULL && lv_pk_get(g, "east") == NULL &&
            lv_pk_get(g, "down") == NULL)
            return lv_pk_fail(c, g, "%s: give the peak wind it adds: north, east and/or down "
                              "[m/s]", what);
        for (size_t i = 0; i < 5; i++) {
            char slot[64];
            snprintf(slot, sizeof slot, "environment.gust%zu.%s", k + 1, keys[i]);
            st = (o = lv_pk_get(g, keys[i])) != NULL
                     ? lv_pk_slot(c, o, what, keys[i], slot, units[i], ranges[i], 0, &e->gust[k][i])
                     : lv_pk_slot_default(c, slot, units[i], 0.0, ranges[i], &e->gust[k][i]);
            if (st != LV_OK)
                return st;
        }
        e->n_gusts = k + 1;
    }
    return LV_OK;
}

/* turbulence: {sigma, sigma_vertical, length, from, to, seed}: Dryden turbulence over altitude
 * (slots "environment.turbulence.<key>"), docs/wind.md "Gusts and turbulence". */
static lv_status parse_turbulence(const lv_pctx *c, const lv_ynode *v, lv_env_def *e)
{
    static const char *const keys[] = { "model", "sigma", "sigma_vertical", "length", "from",
                                        "to", "seed", NULL };
    static const char *const models[] = { "dryden", NULL };
    static const char *const sk[5] = { "sigma", "sigma_vertical", "length", "from", "to" };
    static const char *const units[5] = { "m/s", "m/s", "m", "m", "m" };
    static const double defaults[5] = { NAN, NAN, 533.4, 0.0, 20000.0 };
    static const lv_range ranges[5] = { { 0.0, 100.0, 0, 0 }, { 0.0, 100.0, 0, 0 },
                                        { 1.0, 1e5, 0, 0 }, { -1e5, 1e7, 0, 0 },
                                        { -1e5, 1e7, 0, 0 } };
    const char *what = "environment, turbulence";
    lv_status st = lv_pk_check_map(c, v, what, keys);
    if (st != LV_OK)
        return st;
    const lv_ynode *o;
    size_t i;
    if ((o = lv_pk_get(v, "model")) != NULL && (st = lv_pk_enum(c, o, what, "model", models, &i)) != LV_OK)
        return st;
    if ((st = lv_pk_need(c, v, what, "sigma", &o)) != LV_OK)
        return st;
    e->turb_loc = lv_pk_loc(v);
    e->turb_seed = 1;
    if ((o = lv_pk_get(v, "seed")) != NULL && (st = lv_pk_seed(c, o, what, &e->turb_seed)) != LV_OK)
        return st;
    double sigma = NAN; /* sigma_vertical's default: the file's sigma */
    if ((st = lv_pk_num(c, lv_pk_get(v, "sigma"), what, "sigma", &sigma)) != LV_OK)
        return st;
    for (size_t k = 0; k < 5; k++) {
        char slot[64];
        snprintf(slot, sizeof slot, "environment.turbulence.%s", sk[k]);
        e->turb[k] = LV_NO_SLOT;
        if ((o = lv_pk_get(v, sk[k])) != NULL)
            st = lv_pk_slot(c, o, what, sk[k], slot, units[k], ranges[k], 0, &e->turb[k]);
        else
            st = lv_pk_slot_default(c, slot, units[k], k == 1 ? sigma : defaults[k], ranges[k],
                                    &e->turb[k]);
        if (st != LV_OK)
            return st;
    }
    const lv_ynode *f = lv_pk_get(v, "from"), *t = lv_pk_get(v, "to");
    double hf = 0.0, ht = 20000.0;
    if ((f != NULL && lv_pk_num(c, f, what, "from", &hf) != LV_OK) ||
        (t != NULL && lv_pk_num(c, t, what, "to", &ht) != LV_OK))
        return LV_ERR_INPUT;
    if (!(ht > hf))
        return lv_pk_fail(c, t != NULL ? t : f, "%s: the layer from %.9g m to %.9g m: 'to' must "
                          "be above 'from'", what, hf, ht);
    /* the realisation's size (lv_wind_disturbance_create checks it again for a run's values) */
    double len = 533.4;
    const lv_ynode *lv = lv_pk_get(v, "length");
    if (lv != NULL && lv_pk_num(c, lv, what, "length", &len) != LV_OK)
        return LV_ERR_INPUT;
    if ((ht - hf) / len * 20.0 > 4194300.0)
        return lv_pk_fail(c, t != NULL ? t : v, "%s: the layer from %.9g m to %.9g m is %.9g "
                          "scale lengths of %.9g m deep; at most 209715 (2^22 samples at L/20)",
                          what, hf, ht, (ht - hf) / len, len);
    e->turbulent = 1;
    return LV_OK;
}

lv_status lv_parse_env(const lv_pctx *c, const lv_ynode *n)
{
    static const char *const keys[] = { "world", "g", "planet", "gravity", "atmosphere",
                                        "wind", "gust", "turbulence", "site_lat_deg",
                                        "site_lon_deg", NULL };
    static const char *const worlds[] = { "flat", "planet", NULL };
    const char *what = "environment";
    lv_env_def *e = &c->m->env;
    const lv_ynode *v;
    size_t i = 0;
    lv_status st;

    e->world = LV_WORLD_FLAT;
    e->pdef.radius = e->pdef.flattening = e->pdef.gm = LV_NO_SLOT;
    e->pdef.rotation_rate = e->pdef.r_ref = LV_NO_SLOT;
    e->pdef.sutton_graves_k = NAN;
    for (size_t k = 0; k < 3; k++)
        e->atmo_par[k] = e->wind_ned[k] = LV_NO_SLOT;
    e->wind_interp = LV_INTERP_LINEAR;
    e->wind_extrap = LV_EXTRAP_CLAMP;
    if (n != NULL && !lv_yaml_is_null(n)) {
        st = lv_pk_check_map(c, n, what, keys);
        if (st != LV_OK)
            return st;
        e->loc = lv_pk_loc(n);
        if ((v = lv_pk_get(n, "world")) != NULL) {
            st = lv_pk_enum(c, v, what, "world", worlds, &i);
            if (st != LV_OK)
                return st;
            e->world = i == 0 ? LV_WORLD_FLAT : LV_WORLD_PLANET;
        }
    } else {
        n = NULL;
    }
    const int flat = e->world == LV_WORLD_FLAT;
    e->gravity_loc = e->atmo_loc = e->wind_loc = e->loc;

    e->g = LV_NO_SLOT;
    if ((v = lv_pk_get(n, "g")) != NULL) {
        if (!flat)
            return lv_pk_fail(c, lv_pk_key(n, "g"), "%s: 'g' applies to world: flat only (a planet "
                        "world takes its gravity from 'planet' and 'gravity')", what);
        if ((st = lv_pk_slot(c, v, what, "g", "environment.g", "m/s2", LV_RANGE_POS, 0,
                             &e->g)) != LV_OK)
            return st;
    } else if (flat && (st = lv_pk_slot_default(c, "environment.g", "m/s2", 9.81, LV_RANGE_POS,
                                                &e->g)) != LV_OK) {
        return st;
    }
    /* Where the flat world's origin lies on the Earth, for maps and the globe view. */
    const char *skeys[] = { "site_lat_deg", "site_lon_deg" };
    double *sval[] = { &e->site_lat, &e->site_lon };
    for (size_t k = 0; k < 2; k++) {
        if ((v = lv_pk_get(n, skeys[k])) == NULL)
            continue;
        if (!flat)
            return lv_pk_fail(c, lv_pk_key(n, skeys[k]), "%s: '%s' applies to world: flat only (a "
                        "planet world starts at the parameters start_lat, start_lon)", what,
                        skeys[k]);
        if ((st = lv_pk_num(c, v, what, skeys[k], sval[k])) != LV_OK)
            return st;
        if (fabs(*sval[k]) > (k == 0 ? 90.0 : 360.0))
            return lv_pk_fail(c, v, "%s: %s = %g is out of range [%g, %g] deg", what, skeys[k],
                              *sval[k], k == 0 ? -90.0 : -360.0, k == 0 ? 90.0 : 360.0);
        *sval[k] *= LV_DEG;
    }
    const char *pkeys[] = { "planet", "gravity" };
    for (size_t k = 0; k < 2; k++)
        if (flat && lv_pk_get(n, pkeys[k]) != NULL)
            return lv_pk_fail(c, lv_pk_key(n, pkeys[k]), "%s: '%s' applies to world: planet only",
                        what, pkeys[k]);

    int earth = 0; /* US76 is an Earth atmosphere: the default on the Earth only */
    if (!flat) {
        lv_planet_def *pd = &e->pdef;
        if ((v = lv_pk_get(n, "planet")) != NULL && v->kind == LV_YNODE_MAP) {
            if ((st = parse_planet_map(c, v, e, &earth)) != LV_OK)
                return st;
        } else {
            i = 0;
            if (v != NULL && (st = lv_pk_enum(c, v, what, "planet", planet_presets, &i)) != LV_OK)
                return st;
            if ((e->planet = lv_pk_strdup(planet_presets[i])) == NULL)
                return lv_pk_nomem(c);
            earth = i == 0;
        }
        /* gravity: checked here, where its position is known */
        lv_gravity_config gc;
        lv_err gerr;
        if ((v = lv_pk_get(n, "gravity")) != NULL) {
            if ((st = lv_pk_str(c, v, what, "gravity", &e->gravity)) != LV_OK)
                return st;
            if (lv_gravity_parse_spec(e->gravity, &gc, &gerr) != LV_OK)
                return lv_pk_fail(c, v, "%s: gravity: %s", what, gerr.msg);
            e->gravity_loc = lv_pk_loc(v);
        } else {
            e->gravity = lv_pk_strdup(!pd->custom ? "j2" : pd->coef_file != NULL ? "sh" : "zonal");
            if (e->gravity == NULL)
                return lv_pk_nomem(c);
            (void)lv_gravity_parse_spec(e->gravity, &gc, NULL);
        }
        const int sh = strcmp(gc.model, "sh") == 0;
        const lv_ynode *at = v != NULL ? v : n;
        if (pd->coef_file != NULL && !sh)
            return lv_pk_fail(c, at, "%s: gravity '%s' does not use the planet's coefficient "
                              "file (only 'sh' does)", what, e->gravity);
        if (sh && pd->coef_file == NULL && !earth)
            return lv_pk_fail(c, at, "%s: gravity '%s' would read the shipped EGM2008 "
                              "coefficients, which are the Earth's; give this planet's own "
                              "file: planet: {..., coefficients: file.gfc}", what, e->gravity);
    }
    v = lv_pk_get(n, "atmosphere");
    if (v != NULL)
        e->atmo_loc = lv_pk_loc(v);
    if ((st = parse_atmosphere(c, v, earth ? 0 : 2, e)) != LV_OK)
        return st;
    /* wind: a table of north/east(/down) components over altitude, or a constant */
    if ((v = lv_pk_get(n, "wind")) != NULL && !lv_yaml_is_null(v)) {
        if ((st = parse_wind(c, v, e)) != LV_OK)
            return st;
        if (strcmp(e->atmosphere, "none") == 0)
            return lv_pk_fail(c, lv_pk_key(n, "wind"), "%s: a wind moves air, and there is "
                              "none (atmosphere: none%s): give an atmosphere, or no wind", what,
                              lv_pk_get(n, "atmosphere") != NULL ? "" : ", the default here");
    }
    /* gusts and turbulence: added to the wind (or to still air) */
    static const char *const dist_keys[] = { "gust", "turbulence" };
    for (size_t k = 0; k < 2; k++) {
        if ((v = lv_pk_get(n, dist_keys[k])) == NULL || lv_yaml_is_null(v))
            continue;
        if ((st = k == 0 ? parse_gusts(c, v, e) : parse_turbulence(c, v, e)) != LV_OK)
            return st;
        if (strcmp(e->atmosphere, "none") == 0)
            return lv_pk_fail(c, lv_pk_key(n, dist_keys[k]), "%s: a %s moves air, and there is "
                              "none (atmosphere: none%s): give an atmosphere, or no %s", what,
                              dist_keys[k], lv_pk_get(n, "atmosphere") != NULL ? "" : ", the default here",
                              dist_keys[k]);
    }
    return LV_OK;
}
