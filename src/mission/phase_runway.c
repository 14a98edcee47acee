/* phase_runway.c - the phase-model type "runway": the take-off roll or the landing roll-out
 * of the phase's stages on a runway over the rotating planet (lv_runway.h; docs/models.md,
 * "The runway model"). Its own phase keys: `runway` (the threshold and heading), `takeoff`
 * or `landing` (the roll's parameters), `aero` (the phase's aerodynamic dataset). It hands
 * over to "dof3" by its outputs r_eci_*, v_eci_* (named as dof3's states) and starts from a
 * "dof3" phase by projecting its final state onto the runway (touchdown). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/names.h"
#include "core/status.h"
#include "lvsim/lv_runway.h"
#include "lvsim/lv_units.h"
#include "lvsim/lv_wind.h"
#include "mission/aero_def.h"
#include "mission/phase_kit.h"
#include "mission/phase_type.h"

static const char *const keys[] = {"runway", "takeoff", "landing", "aero", "engines", NULL};
static const char *const from_types[] = {"dof3", NULL};
/* The named ends a roll takes (besides time and variable ends); it has no altitude of its own. */
static const char *const ends[] = {"burnout", "speed", NULL};
/* The runway model's own ends (src/dynamics/runway.c): `end_name:` names them */
static const char *const own_ends[] = {"liftoff", "at_rest", "stop", "overrun", NULL};
static const char *const crash_ends[] = {"overrun", NULL}; /* off the runway's end */


/* Touchdown tolerance of the hand-off from a dof3 phase (runway_handoff): a parent that ends
 * farther from the runway plane did not end at touchdown (an error in the mission). */
#define TOUCHDOWN_HEIGHT_MAX 10.0 /* m above or below the runway plane */
/* The runway's width when `runway:` gives none: 45 m, the ICAO minimum for aerodrome
 * reference code letters D to F (ICAO Annex 14, vol. I, 3.1.9): the wide-body and large
 * winged-vehicle runways lvsim's landings use. */
#define RUNWAY_WIDTH_DEFAULT 45.0

/* ---- the phase's own keys ---------------------------------------------------------------- */

enum { G_LAT, G_LON, G_H, G_HDG, G_LEN, G_WIDTH, G_N }; /* runway: (length, width optional) */
enum { R_MU, R_AG, R_VROT, R_AROT, R_RATE, R_VSTOP, R_S0, R_V0, R_THR, R_N }; /* the roll */

typedef struct runway_cfg {
    lv_runway_mode mode;
    lv_slot geo[G_N];
    lv_slot roll[R_N];   /* LV_NO_SLOT where the mode has no such parameter */
    lv_aero_def aero;
} runway_cfg;

static void runway_cfg_free(void *p)
{
    runway_cfg *c = p;
    if (c == NULL)
        return;
    lv_aero_def_clear(&c->aero);
    free(c);
}

/* runway: {lat_deg, lon_deg, elevation, heading_deg, length, width} (the first four required;
 * lat/lon/heading also in rad as lat, lon, heading; length: LV_NO_SLOT when not given, no
 * end; width default RUNWAY_WIDTH_DEFAULT). */
static lv_status parse_geometry(const lv_pctx *c, const lv_ynode *phase, const lv_ynode *n,
                                const char *name, runway_cfg *cfg)
{
    static const char *const gkeys[] = {"lat", "lat_deg", "lon", "lon_deg", "elevation",
                                        "heading", "heading_deg", "length", "width", NULL};
    static const char *const base[G_N] = {"lat", "lon", "elevation", "heading", "length",
                                          "width"};
    static const char *const units[G_N] = {"rad", "rad", "m", "rad", "m", "m"};
    /* length and width: from a model runway (10 m) to beyond the longest built (5.5 km; the
     * Space Shuttle's landing facility 4.6 km) and the widest (100 m) with room */
    const lv_range ranges[G_N] = {{-0.5 * LV_PI, 0.5 * LV_PI, 0, 0},
                                  {-2.0 * LV_PI, 2.0 * LV_PI, 0, 0},
                                  {-1e4, 1e4, 0, 0}, {-2.0 * LV_PI, 2.0 * LV_PI, 0, 0},
                                  {10.0, 1e5, 0, 0}, {1.0, 1e3, 0, 0}};
    char what[LV_WHAT_MAX], slot[LV_NAME_MAX + 32];
    snprintf(what, sizeof what, "phase '%s', runway", name);
    if (n == NULL || lv_yaml_is_null(n))
        return lv_pk_fail(c, phase, "phase '%s': a runway phase needs `runway: {lat_deg, "
                          "lon_deg, elevation, heading_deg}` (its threshold and heading)", name);
    if (n->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, n, "%s: a mapping such as {lat_deg: 43.5, lon_deg: 1.4, "
                          "elevation: 150, heading_deg: 90} expected", what);
    lv_status st = lv_pk_check_map(c, n, what, gkeys);
    if (st != LV_OK)
        return st;
    for (int k = 0; k < G_N; k++) {
        char deg[24];
        snprintf(deg, sizeof deg, "%s_deg", base[k]);
        const int is_angle = k == G_LAT || k == G_LON || k == G_HDG;
        const lv_ynode *v = lv_pk_get(n, base[k]), *vd = is_angle ? lv_pk_get(n, deg) : NULL;
        if (v != NULL && vd != NULL)
            return lv_pk_fail(c, lv_pk_key(n, deg), "%s: '%s' and '%s' given both", what,
                              base[k], deg);
        snprintf(slot, sizeof slot, "%s.runway.%s", name, base[k]);
        if (v == NULL && k == G_LEN) { /* no length: the roll has no end */
            cfg->geo[k] = LV_NO_SLOT;
            continue;
        }
        if (v == NULL && k == G_WIDTH) {
            if ((st = lv_pk_slot_default(c, slot, units[k], RUNWAY_WIDTH_DEFAULT, ranges[k],
                                         &cfg->geo[k])) != LV_OK)
                return st;
            continue;
        }
        if (v == NULL && vd == NULL)
            return lv_pk_fail(c, n, "%s: '%s' is missing", what, is_angle ? deg : base[k]);
        if ((st = lv_pk_slot(c, v ? v : vd, what, v ? base[k] : deg, slot, units[k], ranges[k],
                             vd != NULL, &cfg->geo[k])) != LV_OK)
            return st;
    }
    return LV_OK;
}

/* takeoff: {mu, v_rot, alpha_rot_deg, rotation_rate_deg, alpha_ground_deg, throttle,
 *           start_distance, start_speed}
 * landing: {mu, v_stop, alpha_deg, start_distance, start_speed} */
static lv_status parse_roll(const lv_pctx *c, const lv_ynode *phase, const char *name,
                            runway_cfg *cfg)
{
    static const char *const names[R_N] = {"mu", "alpha_ground", "v_rot", "alpha_rot",
                                           "rotation_rate", "v_stop", "start_distance",
                                           "start_speed", "throttle"};
    static const char *const units[R_N] = {"", "rad", "m/s", "rad", "rad/s", "m/s", "m", "m/s",
                                           ""};
    static const int angle[R_N] = {0, 1, 0, 1, 1, 0, 0, 0, 0};
    /* take-off: every parameter but v_stop; landing: mu, v_stop, alpha (the ground attitude)
     * and the start values */
    static const int in_takeoff[R_N] = {1, 1, 1, 1, 1, 0, 1, 1, 1};
    static const int in_landing[R_N] = {1, 1, 0, 0, 0, 1, 1, 1, 0};
    static const int required_to[R_N] = {1, 0, 1, 1, 0, 0, 0, 0, 0};
    static const int required_la[R_N] = {1, 0, 0, 0, 0, 1, 0, 0, 0};
    static const double defaults[R_N] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0};
    static const char *const tkeys[] = {"mu", "v_rot", "alpha_rot", "alpha_rot_deg",
                                        "rotation_rate", "rotation_rate_deg", "alpha_ground",
                                        "alpha_ground_deg", "throttle", "start_distance",
                                        "start_speed", NULL};
    static const char *const lkeys[] = {"mu", "v_stop", "alpha", "alpha_deg", "start_distance",
                                        "start_speed", NULL};
    const lv_ynode *to = lv_pk_get(phase, "takeoff"), *la = lv_pk_get(phase, "landing");
    if (to != NULL && la != NULL)
        return lv_pk_fail(c, lv_pk_key(phase, "landing"), "phase '%s': `takeoff` and `landing` "
                          "given both: a runway phase is one roll", name);
    if (to == NULL && la == NULL)
        return lv_pk_fail(c, phase, "phase '%s': a runway phase needs `takeoff: {mu, v_rot, "
                          "alpha_rot_deg, ...}` or `landing: {mu, v_stop}`", name);
    cfg->mode = to != NULL ? LV_RUNWAY_TAKEOFF : LV_RUNWAY_LANDING;
    const lv_ynode *n = to != NULL ? to : la;
    const char *mode = to != NULL ? "takeoff" : "landing";
    char what[LV_WHAT_MAX], slot[LV_NAME_MAX + 48];
    snprintf(what, sizeof what, "phase '%s', %s", name, mode);
    if (n->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, n, "%s: a mapping such as %s expected", what,
                          to != NULL ? "{mu: 0.02, v_rot: 110, alpha_rot_deg: 10}"
                                     : "{mu: 0.3, v_stop: 1}");
    lv_status st = lv_pk_check_map(c, n, what, to != NULL ? tkeys : lkeys);
    if (st != LV_OK)
        return st;
    const int has_from = lv_pk_get(phase, "from") != NULL;
    for (int k = 0; k < R_N; k++) {
        cfg->roll[k] = LV_NO_SLOT;
        if (!(to != NULL ? in_takeoff[k] : in_landing[k]))
            continue;
        /* the landing roll's ground attitude is written `alpha` */
        const char *key = la != NULL && k == R_AG ? "alpha" : names[k];
        char deg[32];
        snprintf(deg, sizeof deg, "%s_deg", key);
        const lv_ynode *v = lv_pk_get(n, key), *vd = angle[k] ? lv_pk_get(n, deg) : NULL;
        if (v != NULL && vd != NULL)
            return lv_pk_fail(c, lv_pk_key(n, deg), "%s: '%s' and '%s' given both", what, key,
                              deg);
        if ((k == R_S0 || k == R_V0) && has_from && v != NULL)
            return lv_pk_fail(c, lv_pk_key(n, key), "%s: '%s': a phase with `from` starts where "
                              "its parent ended", what, key);
        if (v == NULL && vd == NULL && (to != NULL ? required_to[k] : required_la[k]))
            return lv_pk_fail(c, n, "%s: '%s' is missing", what, angle[k] ? deg : key);
        /* angles of attack on the wheels within +-90 deg (the thrust points forwards), the
         * rotation rate >= 0 within 10 rev/s (LV_RANGE_RATE); the start distance, like every
         * other, >= 0: before the threshold is off the runway */
        const lv_range r = k == R_VROT || k == R_VSTOP ? LV_RANGE_POS
                           : k == R_AG || k == R_AROT ? LV_RANGE_LAT
                           : k == R_RATE              ? (lv_range){0.0, 20.0 * LV_PI, 0, 0}
                                                      : LV_RANGE_NONNEG;
        snprintf(slot, sizeof slot, "%s.%s.%s", name, mode, names[k]);
        st = v != NULL || vd != NULL
                 ? lv_pk_slot(c, v ? v : vd, what, v ? key : deg, slot, units[k], r, vd != NULL,
                              &cfg->roll[k])
                 : lv_pk_slot_default(c, slot, units[k], defaults[k], r, &cfg->roll[k]);
        if (st != LV_OK)
            return st;
    }
    return LV_OK;
}

static lv_status runway_parse(const lv_pctx *c, const lv_ynode *n, lv_phase_def *ph)
{
    runway_cfg *cfg = calloc(1, sizeof *cfg);
    if (cfg == NULL)
        return lv_pk_nomem(c);
    ph->type_cfg = cfg;
    /* the ends a roll has: its speed, burnout, a variable or a time; no altitude */
    for (size_t j = 0; j < ph->n_ends; j++) {
        const lv_end_def *e = &ph->ends[j];
        int known = e->kind == LV_END_VAR || e->kind == LV_END_TIME;
        for (size_t i = 0; ends[i] != NULL; i++)
            known |= strcmp(ends[i], lv_end_kind_name(e->kind)) == 0;
        if (!known)
            return lv_fail(c->err, LV_ERR_INPUT, "%s:%d:%d: phase '%s': end '%s': a runway phase "
                           "rolls on the ground: it ends at lift-off (take-off) or stop "
                           "(landing) by itself, and takes speed, burnout, time and variable "
                           "ends", c->file, e->loc.line, e->loc.column, ph->name,
                           lv_end_kind_name(e->kind));
    }
    lv_status st = parse_geometry(c, n, lv_pk_get(n, "runway"), ph->name, cfg);
    if (st == LV_OK)
        st = parse_roll(c, n, ph->name, cfg);
    if (st == LV_OK)
        st = lv_aero_def_parse(c, lv_pk_get(n, "aero"), ph->name, 0, &cfg->aero);
    return st;
}

/* Once `engines:` is read: a take-off's written throttle within the range of the engines that
 * run, refused at its position (lv_pk_check_throttle). */
static lv_status runway_check(const lv_pctx *c, const lv_ynode *n, lv_phase_def *ph)
{
    (void)n;
    const runway_cfg *cfg = ph->type_cfg;
    return lv_pk_check_throttle(c, ph, cfg->roll[R_THR], "takeoff: throttle");
}

/* ---- the model ---------------------------------------------------------------------------- */

typedef struct runway_self {
    lv_kit_model kit; /* environment, engines, ends (phase_kit.h) */
    lv_runway *model;
} runway_self;

static void runway_free_self(void *p)
{
    runway_self *s = p;
    if (s == NULL)
        return;
    lv_runway_free(s->model);
    lv_kit_clear(&s->kit);
    free(s);
}

static lv_status runway_build(const lv_build_ctx *bc, lv_phase_model **out, lv_err *err)
{
    const lv_mission_def *d = bc->def;
    const lv_phase_def *ph = &d->phases[bc->k];
    const runway_cfg *pc = ph->type_cfg;
    const lv_stage_def *bottom = &d->stages[ph->stages[0]];
    *out = NULL;
    runway_self *s = calloc(1, sizeof *s);
    if (s == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    /* its own events: burnout, rotation, lift-off or stop, at rest, overrun */
    lv_status st = lv_kit_begin(bc, &s->kit, 1, sizeof(lv_runway_end), LV_RUNWAY_OWN_EVENTS,
                                err);
    if (st != LV_OK) {
        free(s);
        return st;
    }
    lv_runway_config cfg;
    lv_runway_config_default(&cfg);
    cfg.name = ph->name;
    lv_kit_world(&s->kit, &cfg.planet, &cfg.gravity, &cfg.atmo, &cfg.wind, &cfg.wind_user);
    cfg.mode = pc->mode;
    const double prop0 = bc->prop[ph->stages[0]];
    cfg.m0 = lv_kit_stack_mass(bc, 0);
    cfg.propellant = prop0;
    /* a landing roll-out's engines are off */
    cfg.n_engines = pc->mode == LV_RUNWAY_TAKEOFF && prop0 > 0.0
                        ? lv_kit_engines(bc, bottom, s->kit.engines)
                        : 0;
    cfg.engines = s->kit.engines;
    cfg.runway_lat = bc->vals[pc->geo[G_LAT]];
    cfg.runway_lon = bc->vals[pc->geo[G_LON]];
    cfg.runway_h = bc->vals[pc->geo[G_H]];
    cfg.runway_heading = bc->vals[pc->geo[G_HDG]];
    cfg.runway_length = pc->geo[G_LEN] != LV_NO_SLOT ? bc->vals[pc->geo[G_LEN]] : INFINITY;
    cfg.mu = lv_kit_val(bc, pc->roll[R_MU], 0.0);
    cfg.alpha_ground = lv_kit_val(bc, pc->roll[R_AG], 0.0);
    cfg.v_rot = lv_kit_val(bc, pc->roll[R_VROT], cfg.v_rot);
    cfg.alpha_rot = lv_kit_val(bc, pc->roll[R_AROT], cfg.alpha_ground);
    cfg.rotation_rate = lv_kit_val(bc, pc->roll[R_RATE], 0.0);
    cfg.v_stop = lv_kit_val(bc, pc->roll[R_VSTOP], cfg.v_stop);
    cfg.start_distance = lv_kit_val(bc, pc->roll[R_S0], 0.0);
    cfg.start_speed = lv_kit_val(bc, pc->roll[R_V0], 0.0);
    cfg.throttle = lv_kit_val(bc, pc->roll[R_THR], 1.0);
    /* the ends a roll takes (runway_parse): burnout, and speeds */
    cfg.n_ends = lv_kit_ends(bc, &s->kit, 1, &cfg.stop_at_burnout);
    lv_runway_end *rw_ends = s->kit.ends;
    for (size_t i = 0; i < cfg.n_ends; i++)
        rw_ends[i] = (lv_runway_end){s->kit.end[i].def->name, s->kit.end[i].value,
                                     s->kit.end[i].def->direction};
    cfg.ends = rw_ends;
    cfg.aero = lv_kit_aero(bc, &pc->aero, &s->kit);
    st = lv_runway_create(&cfg, &s->model, err);
    if (st != LV_OK) {
        runway_free_self(s);
        return st;
    }
    lv_kit_done(&s->kit, lv_runway_def(s->model), lv_runway_inst(s->model), s, out);
    return LV_OK;
}

/* The landing gear's limits at a touchdown (mission.h, lv_gear_limit): the roll-out's bottom
 * stage's `landing_gear:` in this run, or the defaults. The touchdown's ground speed, pitch and
 * roll attitude (the parent's final `theta`, `phi`: relative to the local horizon, within
 * 1e-3 rad of the runway plane's tilt over a few km) are recorded with the rest; every limit
 * exceeded is named in the crash's reason (docs/models.md, "Landing gear limits at
 * touchdown"). */
static lv_status touchdown_gear(const lv_build_ctx *bc, const char *const *pnames,
                                const double *pvalues, size_t np, const lv_runway_pos *td)
{
    const lv_phase_def *ph = &bc->def->phases[bc->k];
    const runway_cfg *pc = ph->type_cfg;
    const lv_stage_def *st = &bc->def->stages[ph->stages[0]];
    double lim[LV_GEAR_N];
    for (int i = 0; i < LV_GEAR_N; i++)
        lim[i] = st->gear[i] != LV_NO_SLOT ? bc->vals[st->gear[i]] : lv_gear_keys[i].dflt;
    const size_t ith = lv_names_find(pnames, np, "theta"), iph = lv_names_find(pnames, np, "phi");
    const double pitch = ith != (size_t)-1 ? pvalues[ith] : NAN;
    const double bank = iph != (size_t)-1 ? pvalues[iph] : NAN;
    const double ground = hypot(td->speed, td->lateral_speed);
    lv_build_note(bc, "ground_speed", "m/s", ground);
    lv_build_note(bc, "pitch", "rad", pitch);
    lv_build_note(bc, "bank", "rad", bank);
    char why[480] = "";
    size_t used = 0;
#define EXCEEDED(...)                                                                         \
    do {                                                                                       \
        if (used < sizeof why)                                                                 \
            used += (size_t)snprintf(why + used, sizeof why - used, "%s", used ? "; " : "");   \
        if (used < sizeof why)                                                                 \
            used += (size_t)snprintf(why + used, sizeof why - used, __VA_ARGS__);               \
    } while (0)
    if (!(td->sink_rate <= lim[LV_GEAR_SINK_RATE]))
        EXCEEDED("sink rate %.3g m/s > %.3g m/s", td->sink_rate, lim[LV_GEAR_SINK_RATE]);
    if (!(fabs(td->lateral_speed) <= lim[LV_GEAR_LATERAL_SPEED]))
        EXCEEDED("lateral speed %.3g m/s beyond +-%.3g m/s", td->lateral_speed,
                 lim[LV_GEAR_LATERAL_SPEED]);
    if (!(ground <= lim[LV_GEAR_GROUND_SPEED]))
        EXCEEDED("ground speed %.4g m/s > %.4g m/s", ground, lim[LV_GEAR_GROUND_SPEED]);
    if (!isnan(bank) && !(fabs(bank) <= lim[LV_GEAR_BANK]))
        EXCEEDED("bank %.3g deg beyond +-%.3g deg", bank / LV_DEG, lim[LV_GEAR_BANK] / LV_DEG);
    if (!isnan(pitch) && !(pitch >= lim[LV_GEAR_PITCH_MIN] && pitch <= lim[LV_GEAR_PITCH_MAX]))
        EXCEEDED("pitch %.3g deg outside [%.3g, %.3g] deg", pitch / LV_DEG,
                 lim[LV_GEAR_PITCH_MIN] / LV_DEG, lim[LV_GEAR_PITCH_MAX] / LV_DEG);
#undef EXCEEDED
    /* on the runway: past its threshold, before its end, within its half-width */
    const double length = pc->geo[G_LEN] != LV_NO_SLOT ? bc->vals[pc->geo[G_LEN]] : INFINITY;
    const double half = 0.5 * bc->vals[pc->geo[G_WIDTH]];
    char off[240] = "";
    size_t n_off = 0;
#define OFF(...)                                                                              \
    do {                                                                                       \
        if (n_off < sizeof off)                                                                \
            n_off += (size_t)snprintf(off + n_off, sizeof off - n_off, "%s", n_off ? "; " : ""); \
        if (n_off < sizeof off)                                                                \
            n_off += (size_t)snprintf(off + n_off, sizeof off - n_off, __VA_ARGS__);            \
    } while (0)
    if (!(td->distance >= 0.0))
        OFF("%.4g m before the runway's threshold (undershoot)", -td->distance);
    if (!(td->distance <= length))
        OFF("%.4g m past the runway's end (length %.4g m)", td->distance - length, length);
    if (!(fabs(td->lateral) <= half))
        OFF("%.3g m %s of the centre line, beyond the half-width %.3g m (runway excursion)",
            fabs(td->lateral), td->lateral > 0.0 ? "right" : "left", half);
#undef OFF
    if (n_off > 0 || used > 0)
        lv_build_crash(bc, "crashed at touchdown: %s%s%s%s%s%s", off, n_off && used ? "; " : "",
                       why, used ? " (landing gear of stage '" : "", used ? st->name : "",
                       !used                      ? ""
                       : st->gear[0] != LV_NO_SLOT ? "')"
                                                   : "': the default limits)");
    return LV_OK;
}

/* Touchdown: a landing roll that starts from a dof3 phase takes the parent's final ECI state,
 * turned into ECEF position and velocity relative to the planet at the parent's end time and
 * projected on the runway: distance = (r - r0) . u, speed = v_rel . u. What the projection
 * drops (the height above the runway plane, the sink rate, the lateral offset and speed) is
 * what the touchdown absorbs, recorded in the phase's result (summary.json: handoff /
 * absorbed): a parent that ends more than 10 m above or below the runway plane or moving
 * backwards is refused, naming the values (end the approach at touchdown: `{altitude:
 * <elevation>}` or `impact`); one that touches down off the runway (before its threshold,
 * past its end, beyond its half-width) or beyond the landing gear's limits crashes
 * (touchdown_gear). */
static lv_status runway_handoff(const lv_build_ctx *bc, const lv_phase_model *pm,
                                const char *const *pnames, const double *pvalues, size_t np,
                                const char *const *names, double *values, size_t n, lv_err *err)
{
    const runway_self *s = pm->self;
    const runway_cfg *pc = bc->def->phases[bc->k].type_cfg;
    const size_t is = lv_names_find(names, n, "distance"), iv = lv_names_find(names, n, "speed");
    const size_t im = lv_names_find(pnames, np, "lift_margin"); /* a runway parent has it */
    if (is == (size_t)-1 || iv == (size_t)-1)
        return LV_OK;
    if (pc->mode == LV_RUNWAY_TAKEOFF && im == (size_t)-1)
        return lv_fail(err, LV_ERR_INPUT, "take-off: a take-off roll starts on the runway, not "
                       "from a flight phase (a landing roll-out does: `landing:`)");
    if (pc->mode == LV_RUNWAY_TAKEOFF && !(pvalues[im] < 1.0 - 1e-6))
        return lv_fail(err, LV_ERR_INPUT, "take-off: the parent roll ended at lift-off (lift "
                       "margin %.6g): the flight goes on in a dof3 phase", pvalues[im]);
    static const char *const need[] = {"time", "r_eci_x", "r_eci_y", "r_eci_z",
                                       "v_eci_x", "v_eci_y", "v_eci_z"};
    double f[7];
    for (int i = 0; i < 7; i++) {
        const size_t j = lv_names_find(pnames, np, need[i]);
        if (j == (size_t)-1)
            return lv_fail(err, LV_ERR_INPUT, "touchdown: the parent's final '%s' is unknown "
                           "(its model is not dof3)", need[i]);
        f[i] = pvalues[j];
    }
    /* ECI -> ECEF with the relative velocity: the inverse of lv_frames_ecef_to_eci */
    const lv_planet *pl = &s->kit.env.planet;
    const double th = pl->theta0 + pl->omega * f[0], c = cos(th), sn = sin(th);
    const double vx = f[4] + pl->omega * f[2], vy = f[5] - pl->omega * f[1];
    const double r[3] = {c * f[1] + sn * f[2], -sn * f[1] + c * f[2], f[3]};
    const double v[3] = {c * vx + sn * vy, -sn * vx + c * vy, f[6]};
    lv_runway_pos td;
    lv_runway_project(s->model, r, v, &td);
    const double height = td.height, lateral = td.lateral, speed = td.speed;
    if (!(fabs(height) <= TOUCHDOWN_HEIGHT_MAX) || !(speed >= 0.0))
        return lv_fail(err, LV_ERR_INPUT, "touchdown: the parent ends %.3g m above the runway "
                       "plane, %.3g m right of its centre line (negative: left), at %.4g m/s "
                       "along it: a roll-out starts on the runway's plane (within %g m), rolling "
                       "forwards; end the parent at touchdown", height, lateral, speed,
                       TOUCHDOWN_HEIGHT_MAX);
    values[is] = td.distance;
    values[iv] = speed;
    lv_build_note(bc, "distance", "m", td.distance);
    lv_build_note(bc, "height", "m", td.height);
    lv_build_note(bc, "sink_rate", "m/s", td.sink_rate);
    lv_build_note(bc, "lateral", "m", td.lateral);
    lv_build_note(bc, "lateral_speed", "m/s", td.lateral_speed);
    return pc->mode == LV_RUNWAY_LANDING ? touchdown_gear(bc, pnames, pvalues, np, &td)
                                         : LV_OK;
}

const lv_phase_type lv_phase_type_runway = {
    .name = "runway",
    .description = "take-off roll or landing roll-out on a runway over the rotating planet: "
                   "thrust, aerodynamics, friction, rotation, lift-off or stop",
    .world = LV_WORLD_PLANET,
    .keys = keys,
    .from_types = from_types,
    .ends = ends,
    .own_ends = own_ends,
    .crash_ends = crash_ends,
    .sample_keys = "runway: {lat_deg: 0, lon_deg: 0, elevation: 0, heading_deg: 90}, "
                   "takeoff: {mu: 0.02, v_rot: 80, alpha_rot_deg: 8}",
    .n_mission_params = 0,
    .mission_params = NULL,
    .mission_param_ranges = NULL,
    .mass_state = "m",
    .parse = runway_parse,
    .cfg_free = runway_cfg_free,
    .build = runway_build,
    .free_self = runway_free_self,
    .n_traj = LV_KIT_PLANET_TRAJ_N,
    .traj = lv_kit_planet_traj,
    .traj_extra = NULL,
    .handoff = runway_handoff,
    .check = runway_check,
};
