/* parse_vehicle.c - a mission file's `stages:` (masses, engines and their tables, rigid-body
 * data) into the definition's stage list, its numbers as slots "<stage>.<key>" and
 * "<stage>.<engine>.<key>". Format: docs/mission-format.md ("stages"). */
#include "mission/mission.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/table_unit.h"
#include "lvsim/lv_units.h"
#include "lvsim/lv_vehicle.h"
#include "mission/parse_int.h"

/* ---- engine tables -------------------------------------------------------------------- */

/* Outputs "thrust" and "mdot" by name, or a .mat matrix [t, thrust, mdot] (col2, col3). */
/* Thrust and mass flow are >= 0 at every breakpoint of an engine table (its interpolants,
 * linear or monotone PCHIP, then stay >= 0 between them): a negative thrust would push the
 * vehicle backwards, a negative mass flow would fill the tanks. */
static lv_status table_nonnegative(const lv_pctx *c, const lv_ynode *key, const char *what,
                                   const lv_engine_def *e)
{
    size_t n;
    const double *tb = lv_table_breakpoints(e->table, 0, &n);
    double y[64];
    if (lv_table_n_out(e->table) > sizeof y / sizeof y[0])
        return LV_OK; /* (a table of engines has 2 outputs) */
    for (size_t i = 0; i < n; i++) {
        if (lv_table_eval1(e->table, NULL, tb[i], y, NULL) != LV_OK)
            continue;
        const char *bad = !(y[e->thrust_out] >= 0.0) ? "thrust" : !(y[e->mdot_out] >= 0.0) ? "mdot"
                                                                                           : NULL;
        if (bad != NULL)
            return lv_pk_fail(c, key, "%s: table '%s': %s = %g %s at t = %g s: a thrust and a "
                              "mass flow must be >= 0", what, e->table_file, bad,
                              y[bad[0] == 't' ? e->thrust_out : e->mdot_out],
                              bad[0] == 't' ? "N" : "kg/s", tb[i]);
    }
    return LV_OK;
}

static lv_status table_outputs(const lv_pctx *c, const lv_ynode *key, const char *what,
                               lv_engine_def *e)
{
    const lv_table *t = e->table;
    if (lv_table_n_dims(t) != 1)
        return lv_pk_fail(c, key, "%s: table '%s' has %zu axes; an engine table has one (time, s)",
                    what, e->table_file, lv_table_n_dims(t));
    const size_t no = lv_table_n_out(t);
    int found = 0;
    if (lv_table_out_index(t, "thrust", &e->thrust_out, NULL) == LV_OK &&
        lv_table_out_index(t, "mdot", &e->mdot_out, NULL) == LV_OK) {
        found = 1;
    } else if (no == 2 && strcmp(lv_table_out_name(t, 0), "col2") == 0 &&
               strcmp(lv_table_out_name(t, 1), "col3") == 0) {
        e->thrust_out = 0;
        e->mdot_out = 1;
        found = 1;
    }
    if (found) { /* read in s, N, kg/s: a unit written must be those */
        if (lv_table_expect_unit(t, 1, 0, "s", NULL, c->err) != LV_OK ||
            lv_table_expect_unit(t, 0, e->thrust_out, "N", NULL, c->err) != LV_OK ||
            lv_table_expect_unit(t, 0, e->mdot_out, "kg/s", NULL, c->err) != LV_OK)
            return lv_pk_fail(c, key, "%s: %s", what, c->err->msg);
        return table_nonnegative(c, key, what, e);
    }
    char have[192] = "";
    size_t used = 0;
    for (size_t k = 0; k < no && used < sizeof have; k++)
        used += (size_t)snprintf(have + used, sizeof have - used, "%s'%.30s'", k ? ", " : "",
                                 lv_table_out_name(t, k));
    return lv_pk_fail(c, key, "%s: table '%s' needs outputs 'thrust' [N] and 'mdot' [kg/s] (a .mat "
                "matrix: columns t, thrust, mdot); it has %s", what, e->table_file, have);
}

static lv_status parse_table(const lv_pctx *c, const lv_ynode *key, const lv_ynode *v,
                             const char *what, lv_engine_def *e)
{
    lv_status st = lv_pk_table(c, key, v, what, LV_EXTRAP_CLAMP, &e->table_file,
                                   &e->table_var, &e->table);
    return st != LV_OK ? st : table_outputs(c, key, what, e);
}

/* ---- stages and engines --------------------------------------------------------------- */

static lv_status parse_engine(const lv_pctx *c, const lv_ynode *n, const char *stage, size_t k,
                              lv_engine_def *e)
{
    static const char *const keys[] = { "name", "table", "thrust_vac", "isp_vac", "mdot",
                                        "exit_area", "count", "throttle_min", "throttle_max",
                                        NULL };
    static const char *const constant[] = { "thrust_vac", "isp_vac", "mdot" };
    char what[LV_WHAT_MAX], eng[96];
    const lv_ynode *v;
    lv_status st;

    lv_pk_label(n, "engine", k, eng, sizeof eng);
    snprintf(what, sizeof what, "stage '%s', %s", stage, eng);
    st = lv_pk_check_map(c, n, what, keys);
    if (st != LV_OK)
        return st;
    e->loc = lv_pk_loc(n);
    e->count = 1;
    if ((v = lv_pk_get(n, "name")) != NULL) {
        st = lv_pk_name(c, v, what, 1, &e->name);
    } else {
        char def[LV_NAME_MAX + 32];
        snprintf(def, sizeof def, "%s.e%zu", stage, k + 1);
        e->name = lv_pk_strdup(def);
        st = e->name != NULL ? LV_OK : lv_pk_nomem(c);
    }
    if (st != LV_OK)
        return st;

    const lv_ynode *table = lv_pk_get(n, "table");
    for (size_t i = 0; i < 3; i++)
        if (table != NULL && lv_pk_get(n, constant[i]) != NULL)
            return lv_pk_fail(c, lv_pk_key(n, constant[i]), "%s: give either 'table' or constant data "
                        "(thrust_vac with isp_vac or mdot), not both", what);
    if (table == NULL && lv_pk_get(n, "thrust_vac") == NULL && lv_pk_get(n, "isp_vac") == NULL &&
        lv_pk_get(n, "mdot") == NULL)
        return lv_pk_fail(c, n, "%s: needs either 'table' or 'thrust_vac' with 'isp_vac' or 'mdot'",
                    what);
    char slot[2 * LV_NAME_MAX + 32];
    e->thrust_vac = e->isp_vac = e->mdot = LV_NO_SLOT;
    if (table == NULL) {
        snprintf(slot, sizeof slot, "%s.thrust_vac", e->name);
        if ((st = lv_pk_need(c, n, what, "thrust_vac", &v)) != LV_OK ||
            (st = lv_pk_slot(c, v, what, "thrust_vac", slot, "N", LV_RANGE_POS, 0,
                             &e->thrust_vac)) != LV_OK)
            return st;
        const lv_ynode *isp = lv_pk_get(n, "isp_vac"), *mdot = lv_pk_get(n, "mdot");
        if (isp != NULL && mdot != NULL)
            return lv_pk_fail(c, lv_pk_key(n, isp->line > mdot->line ||
                                           (isp->line == mdot->line && isp->col > mdot->col)
                                       ? "isp_vac" : "mdot"),
                        "%s: give exactly one of 'isp_vac' and 'mdot', not both", what);
        if (isp == NULL && mdot == NULL)
            return lv_pk_fail(c, n, "%s: a constant engine needs 'isp_vac' [s] or 'mdot' [kg/s]",
                        what);
        snprintf(slot, sizeof slot, "%s.%s", e->name, isp != NULL ? "isp_vac" : "mdot");
        if (isp != NULL)
            st = lv_pk_slot(c, isp, what, "isp_vac", slot, "s", LV_RANGE_POS, 0, &e->isp_vac);
        else
            st = lv_pk_slot(c, mdot, what, "mdot", slot, "kg/s", LV_RANGE_POS, 0, &e->mdot);
        if (st != LV_OK)
            return st;
    }
    snprintf(slot, sizeof slot, "%s.exit_area", e->name);
    if ((v = lv_pk_get(n, "exit_area")) != NULL)
        st = lv_pk_slot(c, v, what, "exit_area", slot, "m2", LV_RANGE_NONNEG, 0, &e->exit_area);
    else
        st = lv_pk_slot_default(c, slot, "m2", 0.0, LV_RANGE_NONNEG, &e->exit_area);
    if (st != LV_OK)
        return st;
    /* the throttle range c_s may take (guidance's throttle laws and tables are clamped into
     * it): 0 <= min <= max <= LV_THROTTLE_MAX (twice the rated thrust: lv_vehicle.h) */
    static const char *const tk[2] = {"throttle_min", "throttle_max"};
    lv_slot *ts[2] = {&e->throttle_min, &e->throttle_max};
    for (int i = 0; i < 2; i++) {
        snprintf(slot, sizeof slot, "%s.%s", e->name, tk[i]);
        const lv_range r = {0.0, LV_THROTTLE_MAX, i == 1, 0}; /* min >= 0, max > 0 */
        if ((v = lv_pk_get(n, tk[i])) != NULL)
            st = lv_pk_slot(c, v, what, tk[i], slot, "", r, 0, ts[i]);
        else
            st = lv_pk_slot_default(c, slot, "", (double)i, r, ts[i]);
        if (st != LV_OK)
            return st;
    }
    if (c->m->slots[e->throttle_min].value > c->m->slots[e->throttle_max].value)
        return lv_pk_fail(c, lv_pk_get(n, "throttle_min") ? lv_pk_get(n, "throttle_min")
                                                          : lv_pk_get(n, "throttle_max"),
                          "%s: throttle_min %g is above throttle_max %g", what,
                          c->m->slots[e->throttle_min].value, c->m->slots[e->throttle_max].value);
    if ((v = lv_pk_get(n, "count")) != NULL && (st = lv_pk_int(c, v, what, "count", 1, &e->count))
                                                 != LV_OK)
        return st;
    if (table != NULL)
        return parse_table(c, lv_pk_key(n, "table"), table, what, e);
    return LV_OK;
}

/* One {x, y, z}-like mapping of `rigid_body` (`sub`: its key): the components `comp[nc]` as
 * slots "<stage>.rigid_body.<sub>.<comp>" with `unit`; a missing one takes `dflt[i]` (NAN:
 * required). `angles`: the components may also be written `<comp>_deg`. */
static lv_status parse_rigid_vec(const lv_pctx *c, const lv_ynode *rb, const char *stage,
                                 const char *sub, const char *const *comp, size_t nc,
                                 const char *unit, lv_range range, const double *dflt,
                                 int angles, lv_slot *out)
{
    char what[LV_WHAT_MAX], slot[LV_NAME_MAX + 64], deg[32];
    const char *known[16];
    size_t nk = 0;
    for (size_t i = 0; i < nc; i++) {
        known[nk++] = comp[i];
        if (angles)
            known[nk++] = i == 0 ? "pitch_deg" : "yaw_deg";
    }
    known[nk] = NULL;
    snprintf(what, sizeof what, "stage '%s', rigid_body, %s", stage, sub);
    const lv_ynode *n = lv_pk_get(rb, sub);
    lv_status st;
    if (n != NULL && lv_yaml_is_null(n))
        n = NULL;
    if (n != NULL && n->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, n, "%s: a mapping such as {%s: ..} expected", what, comp[0]);
    if (n != NULL && (st = lv_pk_check_map(c, n, what, known)) != LV_OK)
        return st;
    for (size_t i = 0; i < nc; i++) {
        snprintf(deg, sizeof deg, "%s_deg", comp[i]);
        snprintf(slot, sizeof slot, "%s.rigid_body.%s.%s", stage, sub, comp[i]);
        const lv_ynode *v = lv_pk_get(n, comp[i]), *vd = angles ? lv_pk_get(n, deg) : NULL;
        if (v != NULL && vd != NULL)
            return lv_pk_fail(c, lv_pk_key(n, deg), "%s: '%s' and '%s' given both", what,
                              comp[i], deg);
        if (v == NULL && vd == NULL && isnan(dflt[i]))
            return lv_pk_fail(c, n != NULL ? n : lv_pk_key(rb, sub) ? lv_pk_key(rb, sub) : rb,
                              "%s: '%s' is missing", what, comp[i]);
        st = v != NULL || vd != NULL
                 ? lv_pk_slot(c, v ? v : vd, what, v ? comp[i] : deg, slot, unit, range,
                              vd != NULL, &out[i])
                 : lv_pk_slot_default(c, slot, unit, dflt[i], range, &out[i]);
        if (st != LV_OK)
            return st;
    }
    return LV_OK;
}

/* rigid_body.terms: {jet_damping: on|off, inertia_rate: on|off, rate_damping_frame:
 * air|inertial}: the switchable rigid-body terms (docs/models.md, "Rigid-body terms"); a key
 * not written takes its default (on, on, air). */
static lv_status parse_rigid_terms(const lv_pctx *c, const lv_ynode *rb, const char *stage,
                                   lv_rigid_body_def *r)
{
    static const char *const keys[] = {"jet_damping", "inertia_rate", "rate_damping_frame",
                                       NULL};
    static const char *const onoff[] = {"off", "on", NULL};
    static const char *const frames[] = {"air", "inertial", NULL};
    r->jet_damping = r->inertia_rate = 1;
    r->rate_damping_frame = 0;
    const lv_ynode *n = lv_pk_get(rb, "terms");
    if (n == NULL || lv_yaml_is_null(n))
        return LV_OK;
    char what[LV_WHAT_MAX];
    snprintf(what, sizeof what, "stage '%s', rigid_body, terms", stage);
    if (n->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, n, "%s: a mapping such as {jet_damping: on, inertia_rate: on, "
                          "rate_damping_frame: air} expected", what);
    lv_status st = lv_pk_check_map(c, n, what, keys);
    int *const dst[3] = {&r->jet_damping, &r->inertia_rate, &r->rate_damping_frame};
    for (int k = 0; k < 3 && st == LV_OK; k++) {
        const lv_ynode *v = lv_pk_get(n, keys[k]);
        size_t idx;
        if (v != NULL && (st = lv_pk_enum(c, v, what, keys[k], k < 2 ? onoff : frames, &idx)) ==
                             LV_OK)
            *dst[k] = (int)idx;
    }
    return st;
}

/* rigid_body: {inertia_full: {xx, yy, zz, xy, xz, yz}, inertia_empty: {..}, cg_full: {x, y, z},
 * cg_empty: {..}, engine_position: {x, y, z}, nozzle_exit: {x, y, z}, misalignment: {pitch_deg,
 * yaw_deg}, terms: {..}}:
 * the 6-DoF data of the stack this stage drives (lv_rigid_body_def). inertia_full's xx, yy, zz
 * are required, and engine_position's x (y, z default to 0) when the stage has engines: the
 * thrust moment and the jet damping act there, and no position is guessed; the empty values
 * default to the full ones as written, the rest to 0. */
static lv_status parse_rigid_body(const lv_pctx *c, const lv_ynode *rb, const lv_ynode *stage_n,
                                  lv_stage_def *s)
{
    static const char *const keys[] = {"inertia_full", "inertia_empty", "cg_full", "cg_empty",
                                       "engine_position", "nozzle_exit", "misalignment",
                                       "terms", NULL};
    static const char *const ic[6] = {"xx", "yy", "zz", "xy", "xz", "yz"};
    static const char *const xyz[3] = {"x", "y", "z"};
    static const char *const py[2] = {"pitch", "yaw"};
    char what[LV_WHAT_MAX];
    lv_status st;
    lv_rigid_body_def *r = &s->rigid;
    if (rb == NULL || lv_yaml_is_null(rb))
        return LV_OK;
    snprintf(what, sizeof what, "stage '%s', rigid_body", s->name);
    if (rb->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, rb, "%s: a mapping such as {inertia_full: {xx: 1e5, yy: 4e6, zz: "
                          "4e6}} expected", what);
    if ((st = lv_pk_check_map(c, rb, what, keys)) != LV_OK)
        return st;
    if (lv_pk_get(rb, "inertia_full") == NULL)
        return lv_pk_fail(c, rb, "%s: 'inertia_full' is missing (at least {xx, yy, zz} in kg "
                          "m^2)", what);
    if ((st = parse_rigid_terms(c, rb, s->name, r)) != LV_OK)
        return st;
    const lv_ynode *eng = lv_pk_get(stage_n, "engines");
    const lv_ynode *ep = lv_pk_get(rb, "engine_position");
    if (eng != NULL && eng->kind == LV_YNODE_SEQ && eng->n > 0 &&
        (ep == NULL || lv_yaml_is_null(ep) ||
         (ep->kind == LV_YNODE_MAP && lv_pk_get(ep, "x") == NULL)))
        return lv_pk_fail(c, ep != NULL ? ep : rb, "%s: 'engine_position%s' is missing: the "
                          "stage has engines, and their thrust moment%s act%s at their gimbal "
                          "point (m, body x from the structural origin; no default is guessed)",
                          what, ep != NULL ? ".x" : "",
                          r->jet_damping ? " and jet damping" : "", r->jet_damping ? "" : "s");
    r->present = 1;
    r->loc = lv_pk_loc(rb);
    const double need[6] = {NAN, NAN, NAN, 0.0, 0.0, 0.0}, zero[3] = {0.0, 0.0, 0.0};
    /* positions in the body frame: within 1 km of the structure's origin (the largest launch
     * vehicles are ~120 m long); 1e300 made `run` fail at the first step with der(p) not
     * finite and no word of the key (issue 24's breaker) */
    const lv_range body_pos = {-1000.0, 1000.0, 0, 0};
    if ((st = parse_rigid_vec(c, rb, s->name, "inertia_full", ic, 6, "kg.m2", LV_RANGE_ANY, need,
                              0, r->inertia_full)) != LV_OK)
        return st;
    double full[6];
    for (int i = 0; i < 6; i++)
        full[i] = c->m->slots[r->inertia_full[i]].value;
    if ((st = parse_rigid_vec(c, rb, s->name, "inertia_empty", ic, 6, "kg.m2", LV_RANGE_ANY, full,
                              0, r->inertia_empty)) != LV_OK ||
        (st = parse_rigid_vec(c, rb, s->name, "cg_full", xyz, 3, "m", body_pos, zero, 0,
                              r->cg_full)) != LV_OK)
        return st;
    for (int i = 0; i < 3; i++)
        full[i] = c->m->slots[r->cg_full[i]].value;
    lv_slot mis[2];
    if ((st = parse_rigid_vec(c, rb, s->name, "cg_empty", xyz, 3, "m", body_pos, full, 0,
                              r->cg_empty)) != LV_OK ||
        (st = parse_rigid_vec(c, rb, s->name, "engine_position", xyz, 3, "m", body_pos, zero,
                              0, r->engine_pos)) != LV_OK ||
        (st = parse_rigid_vec(c, rb, s->name, "misalignment", py, 2, "rad",
                              (lv_range){-0.1, 0.1, 0, 0}, zero, 1, mis)) != LV_OK)
        return st;
    r->mis_pitch = mis[0];
    r->mis_yaw = mis[1];
    /* nozzle_exit: {x, y, z}, all three written (where the jet damping's exhaust leaves) */
    const lv_ynode *ne = lv_pk_get(rb, "nozzle_exit");
    if (ne == NULL || lv_yaml_is_null(ne))
        return LV_OK;
    const double need3[3] = {NAN, NAN, NAN};
    if ((st = parse_rigid_vec(c, rb, s->name, "nozzle_exit", xyz, 3, "m", body_pos, need3, 0,
                              r->nozzle_exit)) != LV_OK)
        return st;
    r->has_exit = 1;
    return LV_OK;
}

/* The landing gear's limits at touchdown (mission.h, lv_gear_limit). Defaults:
 * docs/models.md, "Landing gear limits at touchdown". */
const lv_gear_key lv_gear_keys[LV_GEAR_N] = {
    [LV_GEAR_SINK_RATE] = {"sink_rate_max", "m/s", 3.048, 0},     /* 10 ft/s: 14 CFR 25.473 */
    [LV_GEAR_LATERAL_SPEED] = {"lateral_speed_max", "m/s", 2.0, 0},
    [LV_GEAR_GROUND_SPEED] = {"ground_speed_max", "m/s", 115.7, 0}, /* 225 kt */
    [LV_GEAR_BANK] = {"bank_max", "rad", 10.0 * LV_DEG, 1},
    [LV_GEAR_PITCH_MIN] = {"pitch_min", "rad", 0.0, 1},
    [LV_GEAR_PITCH_MAX] = {"pitch_max", "rad", 15.0 * LV_DEG, 1},
};

/* `landing_gear: {sink_rate_max: 3, pitch_max_deg: 14, ...}`: every limit a slot (the
 * defaults for the keys not written). */
static lv_status parse_gear(const lv_pctx *c, const lv_ynode *n, const char *stage_what,
                            lv_stage_def *s)
{
    char what[LV_WHAT_MAX + 16], buf[64], slot[LV_NAME_MAX + 48];
    for (int i = 0; i < LV_GEAR_N; i++)
        s->gear[i] = LV_NO_SLOT;
    if (n == NULL)
        return LV_OK;
    snprintf(what, sizeof what, "%.140s, landing_gear", stage_what);
    if (n->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, n, "%s: a mapping such as {sink_rate_max: 3} expected, found %s",
                          what, lv_pk_describe(n, buf, sizeof buf));
    static const char *const known[] = {"sink_rate_max", "lateral_speed_max",
                                        "ground_speed_max", "bank_max", "bank_max_deg",
                                        "pitch_min", "pitch_min_deg", "pitch_max",
                                        "pitch_max_deg", NULL};
    lv_status st = lv_pk_check_map(c, n, what, known);
    if (st != LV_OK)
        return st;
    for (int i = 0; i < LV_GEAR_N; i++) {
        const lv_gear_key *g = &lv_gear_keys[i];
        char deg[40];
        snprintf(deg, sizeof deg, "%s_deg", g->key);
        const lv_ynode *v = lv_pk_get(n, g->key), *vd = g->angle ? lv_pk_get(n, deg) : NULL;
        if (v != NULL && vd != NULL)
            return lv_pk_fail(c, lv_pk_key(n, deg), "%s: '%s' and '%s' given both", what,
                              g->key, deg);
        /* speeds > 0; bank in (0, 90] deg; pitch in [-90, 90] deg */
        const lv_range r = i <= LV_GEAR_GROUND_SPEED ? (lv_range){0.0, HUGE_VAL, 1, 0}
                           : i == LV_GEAR_BANK       ? (lv_range){0.0, 0.5 * LV_PI, 1, 0}
                                                     : (lv_range){-0.5 * LV_PI, 0.5 * LV_PI, 0, 0};
        snprintf(slot, sizeof slot, "%s.landing_gear.%s", s->name, g->key);
        st = v != NULL || vd != NULL
                 ? lv_pk_slot(c, v != NULL ? v : vd, what, v != NULL ? g->key : deg, slot,
                              g->unit, r, vd != NULL, &s->gear[i])
                 : lv_pk_slot_default(c, slot, g->unit, g->dflt, r, &s->gear[i]);
        if (st != LV_OK)
            return st;
    }
    const lv_slot_def *lo = &c->m->slots[s->gear[LV_GEAR_PITCH_MIN]];
    const lv_slot_def *hi = &c->m->slots[s->gear[LV_GEAR_PITCH_MAX]];
    if (!(hi->value > lo->value))
        return lv_pk_fail(c, n, "%s: pitch_max %.6g deg must be above pitch_min %.6g deg", what,
                          hi->value / LV_DEG, lo->value / LV_DEG);
    return LV_OK;
}

/* geometry: {length, diameter, span} in m: the stage's shape in the CZML export's vehicle
 * model (docs/exports.md, "Vehicle models"), no physics. length and diameter in [0.01, 1000]
 * m required, span 0 or in [0.01, 1000] m optional (a delta wing where > 0): from a model
 * rocket to ten times the largest launch vehicle (Starship 121 m, 9 m), so that the glTF's
 * sizes and normals stay finite (a 1e-300 m stage gave NaN normals). */
#define GEOM_MIN 0.01
#define GEOM_MAX 1000.0
static lv_status parse_geometry(const lv_pctx *c, const lv_ynode *g, lv_stage_def *s)
{
    static const char *const keys[] = {"length", "diameter", "span", NULL};
    static const char *const need[] = {"length", "diameter"};
    char what[LV_WHAT_MAX];
    const lv_ynode *v;
    lv_status st;
    if (g == NULL)
        return LV_OK;
    snprintf(what, sizeof what, "stage '%s', geometry", s->name);
    if ((st = lv_pk_check_map(c, g, what, keys)) != LV_OK)
        return st;
    double *dst[2] = {&s->geom_length, &s->geom_diameter};
    for (int i = 0; i < 2; i++) {
        if ((st = lv_pk_need(c, g, what, need[i], &v)) != LV_OK ||
            (st = lv_pk_num(c, v, what, need[i], dst[i])) != LV_OK)
            return st;
        if (!(*dst[i] >= GEOM_MIN && *dst[i] <= GEOM_MAX))
            return lv_pk_fail(c, v, "%s: %s: a length from %g to %g m expected, found %.17g",
                              what, need[i], GEOM_MIN, GEOM_MAX, *dst[i]);
    }
    s->geom_span = 0.0;
    if ((v = lv_pk_get(g, "span")) != NULL) {
        if ((st = lv_pk_num(c, v, what, "span", &s->geom_span)) != LV_OK)
            return st;
        if (!(s->geom_span == 0.0 || (s->geom_span >= GEOM_MIN && s->geom_span <= GEOM_MAX)))
            return lv_pk_fail(c, v, "%s: span: 0 (no wing) or a length from %g to %g m "
                              "expected, found %.17g", what, GEOM_MIN, GEOM_MAX, s->geom_span);
    }
    return LV_OK;
}

static lv_status parse_stage(const lv_pctx *pc, const lv_ynode *n, size_t k, lv_stage_def *s)
{
    static const char *const keys[] = { "name", "dry_mass", "propellant_mass", "engines",
                                        "rigid_body", "landing_gear", "geometry", "nose_radius",
                                        NULL };
    char what[LV_WHAT_MAX], buf[64], slot[LV_NAME_MAX + 32];
    const lv_ynode *v;
    lv_status st;
    lv_pctx sc = *pc; /* the stage owns its slots and its engines' */
    sc.owner = LV_OWN_STAGE;
    sc.owner_index = k;
    const lv_pctx *c = &sc;

    lv_pk_label(n, "stage", k, what, sizeof what);
    if ((st = lv_pk_check_map(c, n, what, keys)) != LV_OK)
        return st;
    s->loc = lv_pk_loc(n);
    if ((st = lv_pk_need(c, n, what, "name", &v)) != LV_OK ||
        (st = lv_pk_name(c, v, what, 0, &s->name)) != LV_OK)
        return st;
    snprintf(slot, sizeof slot, "%s.dry_mass", s->name);
    if ((st = lv_pk_need(c, n, what, "dry_mass", &v)) != LV_OK ||
        (st = lv_pk_slot(c, v, what, "dry_mass", slot, "kg", LV_RANGE_NONNEG, 0, &s->dry_mass)) !=
            LV_OK)
        return st;
    snprintf(slot, sizeof slot, "%s.propellant_mass", s->name);
    if ((st = lv_pk_need(c, n, what, "propellant_mass", &v)) != LV_OK ||
        (st = lv_pk_slot(c, v, what, "propellant_mass", slot, "kg", LV_RANGE_NONNEG, 0,
                         &s->propellant_mass)) != LV_OK)
        return st;
    if ((st = parse_rigid_body(c, lv_pk_get(n, "rigid_body"), n, s)) != LV_OK ||
        (st = parse_gear(c, lv_pk_get(n, "landing_gear"), what, s)) != LV_OK)
        return st;
    if ((st = parse_geometry(c, lv_pk_get(n, "geometry"), s)) != LV_OK)
        return st;
    s->nose_radius = LV_NO_SLOT;
    if ((v = lv_pk_get(n, "nose_radius")) != NULL) {
        snprintf(slot, sizeof slot, "%s.nose_radius", s->name);
        if ((st = lv_pk_slot(c, v, what, "nose_radius", slot, "m", LV_RANGE_POS, 0,
                             &s->nose_radius)) != LV_OK)
            return st;
    }

    v = lv_pk_get(n, "engines");
    if (v == NULL || lv_yaml_is_null(v))
        return LV_OK;
    if (v->kind != LV_YNODE_SEQ)
        return lv_pk_fail(c, v, "%s: engines: a list expected, found %s", what,
                    lv_pk_describe(v, buf, sizeof buf));
    if (v->n == 0)
        return LV_OK;
    s->engines = calloc(v->n, sizeof *s->engines);
    if (s->engines == NULL)
        return lv_pk_nomem(c);
    s->n_engines = v->n;
    for (size_t i = 0; i < v->n; i++)
        if ((st = parse_engine(c, v->kids[i], s->name, i, &s->engines[i])) != LV_OK)
            return st;
    return LV_OK;
}

lv_status lv_parse_stages(const lv_pctx *c, const lv_ynode *n)
{
    lv_mission_def *m = c->m;
    char buf[64];
    lv_status st;

    if (n->kind != LV_YNODE_SEQ || n->n == 0)
        return lv_pk_fail(c, n, "stages: a list of at least one stage expected, found %s",
                    n->kind == LV_YNODE_SEQ ? "an empty list" : lv_pk_describe(n, buf, sizeof buf));
    m->stages = calloc(n->n, sizeof *m->stages);
    if (m->stages == NULL)
        return lv_pk_nomem(c);
    m->n_stages = n->n;
    for (size_t i = 0; i < n->n; i++) {
        if ((st = parse_stage(c, n->kids[i], i, &m->stages[i])) != LV_OK)
            return st;
        for (size_t j = 0; j < i; j++)
            if (strcmp(m->stages[j].name, m->stages[i].name) == 0)
                return lv_pk_fail(c, lv_pk_get(n->kids[i], "name"), "stage '%s': duplicate stage name "
                            "(first at line %d)", m->stages[i].name, m->stages[j].loc.line);
    }
    /* Engine names are unique in the whole mission: outputs are named after them. */
    for (size_t i = 0; i < m->n_stages; i++)
        for (size_t a = 0; a < m->stages[i].n_engines; a++)
            for (size_t j = 0; j <= i; j++)
                for (size_t b = 0; b < (j == i ? a : m->stages[j].n_engines); b++)
                    if (strcmp(m->stages[i].engines[a].name, m->stages[j].engines[b].name) == 0) {
                        const lv_ynode *en = n->kids[i];
                        const lv_ynode *at = lv_pk_get(lv_pk_get(en, "engines")->kids[a], "name");
                        return lv_pk_fail(c, at != NULL ? at : lv_pk_get(en, "engines")->kids[a],
                                    "stage '%s': duplicate engine name '%s' (first at line %d)",
                                    m->stages[i].name, m->stages[i].engines[a].name,
                                    m->stages[j].engines[b].loc.line);
                    }
    return LV_OK;
}
