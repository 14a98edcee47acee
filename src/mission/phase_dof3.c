/* phase_dof3.c - the phase-model type "dof3": the 3-DoF variable-mass point over the rotating
 * planet (lv_dof3.h; the paper's sec. 2.2-2.3). The phase's stages fly as one mass point and
 * the bottom stage's engines burn. Its own phase keys: inputs (alpha, beta, mu, throttle,
 * constant or a control table) and aero (the phase's aerodynamic dataset: aero_def.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/names.h"
#include "core/status.h"
#include "core/table_unit.h"
#include "lvsim/lv_dof3.h"
#include "lvsim/lv_units.h"
#include "lvsim/lv_wind.h"
#include "mission/aero_def.h"
#include "mission/guidance_def.h"
#include "dynamics/guidance.h"
#include "mission/phase_kit.h"
#include "mission/phase_type.h"
#include "mission/reference.h"

static const char *const keys[] = {"inputs", "aero", "guidance", "throttle", "separation",
                                   "engines", "engine_out", "reference", NULL};
/* A runway phase's outputs r_eci_*, v_eci_* are this model's states: a climb-out starts where
 * the take-off roll lifted off (phase_runway.c). A dof6 phase's states r_eci_*, v_eci_*, m are
 * too: 6-DoF -> 3-DoF drops the attitude and rates (docs/models.md). */
static const char *const from_types[] = {"runway", "dof6", NULL};

/* The model's parameters that are the mission's shared parameter set (lv_dof3.h). */
static const lv_var mission_params[] = {LV_KIT_START_PARAMS};
static const lv_range mission_param_ranges[] = {LV_KIT_START_RANGES};


/* ---- the phase's own keys ------------------------------------------------------------ */

typedef struct dof3_cfg {
    lv_slot u[4];        /* alpha, beta, mu [rad], throttle [1]: constant inputs */
    char *inputs_file, *inputs_var;
    lv_table *inputs;    /* control history (outputs alpha, beta, mu, throttle) over `over` */
    int over;            /* lv_dof3_over: the variable its axis holds (`inputs: over:`) */
    double duration;     /* s: tau's duration, the time table's own span; NAN: the phase's
                            stop_time minus its start */
    lv_aero_def aero;    /* the phase's aerodynamic dataset (aero_def.h) */
    lv_guidance_def guid; /* steering and throttle laws (guidance_def.h) */
    int sep;             /* `separation:` given */
    lv_slot sep_dv[4];   /* m/s: along the parent's body x, then north, east, down */
} dof3_cfg;

static void dof3_cfg_free(void *p)
{
    dof3_cfg *c = p;
    if (c == NULL)
        return;
    free(c->inputs_file);
    free(c->inputs_var);
    lv_table_free(c->inputs);
    lv_aero_def_clear(&c->aero);
    lv_guidance_def_clear(&c->guid);
    free(c);
}

/* ---- `inputs: over:` - the variable a control history is evaluated at ---------------------- */

static const char *const over_words[] = {"time", "tau", "altitude", "speed", "mass", "energy",
                                         NULL};
static const char *const over_units[] = {"s", "1", "m", "m/s", "kg", "J/kg"};

/* 1 if axis or column name `s` means over-variable `over` (its accepted spellings). */
static int names_var(const char *s, int over)
{
    static const char *const alias[][3] = {{"time", "t", NULL},  {"tau", NULL, NULL},
                                           {"altitude", "h", NULL}, {"speed", "v", "v_rel"},
                                           {"mass", "m", NULL},     {"energy", NULL, NULL}};
    for (int i = 0; i < 3 && alias[over][i] != NULL; i++)
        if (strcmp(s, alias[over][i]) == 0)
            return 1;
    return 0;
}

/* The output of `t` named as variable `over`, or -1. */
static long column_of(const lv_table *t, int over)
{
    for (size_t k = 0; k < lv_table_n_out(t); k++)
        if (names_var(lv_table_out_name(t, k), over))
            return (long)k;
    return -1;
}

/* A copy of 1-axis table `src` whose axis is `x` [n breakpoints of src, in src's order; read
 * backwards when `rev`] named `axis` [unit]: the outputs at src's breakpoints but output `skip`
 * (the column that became the axis; -1: none), the same interpolation and extrapolation. */
static lv_status retabulate(const lv_table *src, const double *x, int rev, long skip,
                            const char *axis, const char *unit, lv_table **out, lv_err *err)
{
    size_t n = 0;
    const double *b = lv_table_breakpoints(src, 0, &n);
    const size_t ns = lv_table_n_out(src), no = ns - (skip >= 0 ? 1 : 0);
    double *xs = malloc(n * sizeof *xs), *y = malloc((n * no + 1) * sizeof *y);
    double *row = malloc(ns * sizeof *row);
    const char **on = malloc((no + 1) * sizeof *on), **ou = malloc((no + 1) * sizeof *ou);
    lv_status st = LV_OK;
    if (xs == NULL || y == NULL || row == NULL || on == NULL || ou == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto fail;
    }
    if (no == 0) {
        st = lv_fail(err, LV_ERR_INPUT, "the table has no column besides '%s' (alpha, beta, mu "
                     "or throttle)", lv_table_out_name(src, (size_t)skip));
        goto fail;
    }
    for (size_t k = 0, o = 0; k < ns; k++)
        if ((long)k != skip) {
            on[o] = lv_table_out_name(src, k);
            ou[o++] = lv_table_out_unit(src, k);
        }
    for (size_t j = 0; j < n && st == LV_OK; j++) {
        const size_t i = rev ? n - 1 - j : j;
        xs[j] = x[i];
        st = lv_table_eval1(src, NULL, b[i], row, err); /* exact at a breakpoint */
        for (size_t k = 0, o = 0; k < ns; k++)
            if ((long)k != skip)
                y[j * no + o++] = row[k];
    }
    if (st == LV_OK) {
        const lv_table_spec spec = {.n_dims = 1, .n = {n}, .x = {xs}, .n_out = no, .y = y,
                                    .interp = lv_table_interp(src),
                                    .extrap = lv_table_extrap(src), .name = lv_table_name(src),
                                    .axis_name = {axis}, .axis_unit = {unit}, .out_name = on,
                                    .out_unit = ou};
        st = lv_table_create(&spec, out, err);
    }
fail:
    free(xs);
    free(y);
    free(row);
    free(on);
    free(ou);
    return st;
}

/* `over: tau | altitude | speed | mass | energy` (`at`: its value node): cfg->inputs made a
 * table over that variable. tau: an axis `tau` as it is (the phase's stop_time ends it: the
 * duration NAN), or a time axis rescaled by its own span, tau = (t - t_first) / (t_last -
 * t_first) (the duration that span). A variable: an axis already named so, or a time (tau)
 * axis re-tabulated over the table's own column of that variable (energy: v^2 / 2 + g0 h from
 * the columns h and v), which must be strictly monotone along the rows - refused otherwise,
 * naming the rows where it turns. */
static lv_status parse_over(const lv_pctx *c, const lv_ynode *at, const char *what, int over,
                            dof3_cfg *cfg)
{
    lv_table *t = cfg->inputs, *nt = NULL;
    const char *ax = lv_table_axis_name(t, 0);
    char why[LV_ERR_MSG_MAX];
    lv_err e = {LV_OK, ""};
    size_t n = 0;
    const double *b = lv_table_breakpoints(t, 0, &n);
    cfg->over = over;
    cfg->duration = NAN;
    if (lv_table_n_dims(t) != 1)
        return lv_pk_fail(c, at, "%s: over: %s: the table must have one axis (it has %zu)", what,
                          over_words[over], lv_table_n_dims(t));
    const int time_axis = names_var(ax, LV_DOF3_OVER_TIME);
    if (names_var(ax, over) && strcmp(ax, over_words[over]) == 0)
        return LV_OK; /* already over it */
    double *x = malloc(n * sizeof *x), *buf = malloc(lv_table_n_out(t) * sizeof *buf);
    lv_status st = LV_OK;
    int rev = 0;
    long skip = -1; /* the column that becomes the axis */
    if (x == NULL || buf == NULL) {
        st = lv_pk_nomem(c);
        goto fail;
    }
    if (names_var(ax, over)) { /* an alias ("h"): the same values, the canonical name */
        memcpy(x, b, n * sizeof *x);
    } else if (over == LV_DOF3_OVER_TAU) {
        if (!time_axis) {
            st = lv_pk_fail(c, at, "%s: over: tau: the table's axis must be `tau` (the phase's "
                            "stop_time ends the phase time) or `time` (rescaled by its own span); "
                            "it is '%s'", what, ax);
            goto fail;
        }
        cfg->duration = b[n - 1] - b[0];
        for (size_t i = 0; i < n; i++)
            x[i] = (b[i] - b[0]) / cfg->duration;
        x[n - 1] = 1.0;
    } else {
        if (!time_axis && strcmp(ax, "tau") != 0) {
            st = lv_pk_fail(c, at, "%s: over: %s: the table's axis must be `%s` or, to read the "
                            "variable from the table's own column, `time` or `tau`; it is '%s'",
                            what, over_words[over], over_words[over], ax);
            goto fail;
        }
        const long kv = column_of(t, over);
        const long kh = column_of(t, LV_DOF3_OVER_ALTITUDE), ks = column_of(t, LV_DOF3_OVER_SPEED);
        if (kv < 0 && !(over == LV_DOF3_OVER_ENERGY && kh >= 0 && ks >= 0)) {
            st = lv_pk_fail(c, at, "%s: over: %s: the table '%s' has no column of it (%s%s)",
                            what, over_words[over], lv_table_name(t),
                            over == LV_DOF3_OVER_ENERGY ? "`energy`, or `h` and `v`"
                            : over == LV_DOF3_OVER_ALTITUDE ? "`altitude` or `h`"
                            : over == LV_DOF3_OVER_SPEED ? "`speed`, `v` or `v_rel`"
                                                         : "`mass` or `m`",
                            ", in SI");
            goto fail;
        }
        const long ku = kv >= 0 ? kv : kh;
        skip = kv;
        if ((st = lv_table_expect_unit(t, 0, (size_t)ku, kv >= 0 ? over_units[over] : "m", NULL,
                                       &e)) != LV_OK ||
            (kv < 0 && (st = lv_table_expect_unit(t, 0, (size_t)ks, "m/s", NULL, &e)) != LV_OK)) {
            st = lv_pk_fail(c, at, "%s: over: %s: %s", what, over_words[over], e.msg);
            goto fail;
        }
        for (size_t i = 0; i < n; i++) {
            if ((st = lv_table_eval1(t, NULL, b[i], buf, &e)) != LV_OK) {
                st = lv_pk_fail(c, at, "%s: over: %s: %s", what, over_words[over], e.msg);
                goto fail;
            }
            x[i] = kv >= 0 ? buf[kv] : 0.5 * buf[ks] * buf[ks] + LV_G0 * buf[kh];
        }
        /* strictly monotone along the rows, else no function of the variable */
        rev = n > 1 && x[1] < x[0];
        for (size_t i = 1; i < n; i++)
            if (rev ? !(x[i] < x[i - 1]) : !(x[i] > x[i - 1])) {
                snprintf(why, sizeof why, "%s %.9g at %s = %.9g, then %.9g at %s = %.9g (rows "
                         "%zu and %zu of the table, %s before)",
                         kv >= 0 ? lv_table_out_name(t, (size_t)kv) : "energy",
                         x[i - 1], ax, b[i - 1], x[i], ax, b[i], i, i + 1,
                         rev ? "falling" : i > 1 ? "rising" : "the first rows");
                st = lv_pk_fail(c, at, "%s: over: %s: the variable is not strictly monotone "
                                "along the table: %s; the inputs are no function of it (choose "
                                "a variable that only rises or only falls, e.g. mass while the "
                                "engines burn)", what, over_words[over], why);
                goto fail;
            }
    }
    if ((st = retabulate(t, x, rev, skip, over_words[over], over_units[over], &nt, &e)) != LV_OK) {
        st = lv_pk_fail(c, at, "%s: over: %s: %s", what, over_words[over], e.msg);
        goto fail;
    }
    lv_table_free(cfg->inputs);
    cfg->inputs = nt;
fail:
    free(x);
    free(buf);
    return st;
}

/* inputs: {alpha_deg, beta_deg, mu_deg, throttle, table}: constant, or from a control history
 * over mission time (outputs alpha, beta, mu [rad], throttle). Slots "<phase>.inputs.alpha"
 * ... (defaults 0, 0, 0 rad and throttle 1) exist where they act: no angles in a phase that a
 * guidance law steers (`steered`), no throttle where the throttle comes from elsewhere
 * (`throttle_elsewhere`: throttle.value, off, landing, the attitude table) unless written (the
 * caller refuses it then, naming both): a parameter that changes nothing is not offered to
 * targeting or dispersions. */
static lv_status parse_inputs(const lv_pctx *c, const lv_ynode *n, const char *phase,
                              int steered, int throttle_elsewhere, dof3_cfg *cfg)
{
    static const char *const ikeys[] = {"alpha", "beta", "mu", "throttle", "alpha_deg",
                                        "beta_deg", "mu_deg", "table", "over", NULL};
    static const char *const names[4] = {"alpha", "beta", "mu", "throttle"};
    static const char *const units[4] = {"rad", "rad", "rad", ""};
    static const double defaults[4] = {0.0, 0.0, 0.0, 1.0};
    char what[LV_WHAT_MAX], slot[LV_NAME_MAX + 32];
    lv_status st;
    snprintf(what, sizeof what, "phase '%s', inputs", phase);
    if (n != NULL && lv_yaml_is_null(n))
        n = NULL;
    if (n != NULL && (st = lv_pk_check_map(c, n, what, ikeys)) != LV_OK)
        return st;
    for (int k = 0; k < 4; k++) {
        char deg[16];
        snprintf(deg, sizeof deg, "%s_deg", names[k]);
        snprintf(slot, sizeof slot, "%s.inputs.%s", phase, names[k]);
        const lv_ynode *v = lv_pk_get(n, names[k]), *vd = k < 3 ? lv_pk_get(n, deg) : NULL;
        if (v != NULL && vd != NULL)
            return lv_pk_fail(c, lv_pk_key(n, deg), "%s: '%s' and '%s' given both", what,
                              names[k], deg);
        /* alpha, beta within [-180, 180] deg, the bank mu within a turn either way */
        const lv_range r = k == 3   ? LV_RANGE_NONNEG
                           : k == 2 ? LV_RANGE_TURN
                                    : LV_RANGE_AERO_ANGLE;
        if (v == NULL && vd == NULL && (k < 3 ? steered : throttle_elsewhere)) {
            cfg->u[k] = LV_NO_SLOT;
            continue;
        }
        if (v != NULL || vd != NULL)
            st = lv_pk_slot(c, v ? v : vd, what, v ? names[k] : deg, slot, units[k], r, vd != NULL,
                            &cfg->u[k]);
        else
            st = lv_pk_slot_default(c, slot, units[k], defaults[k], r, &cfg->u[k]);
        if (st != LV_OK)
            return st;
    }
    const lv_ynode *v = lv_pk_get(n, "table"), *ov = lv_pk_get(n, "over");
    size_t over = LV_DOF3_OVER_TIME;
    if (ov != NULL && (st = lv_pk_enum(c, ov, what, "over", over_words, &over)) != LV_OK)
        return st;
    if (ov != NULL && v == NULL)
        return lv_pk_fail(c, lv_pk_key(n, "over"), "%s: over: names the variable of a control "
                          "table: give `table:` too", what);
    if (v != NULL && (st = lv_pk_table(c, lv_pk_key(n, "table"), v, what, LV_EXTRAP_CLAMP,
                                       &cfg->inputs_file, &cfg->inputs_var, &cfg->inputs)) != LV_OK)
        return st;
    /* an input written in other units under another name is not read: refused, not flown 0 */
    for (int k = 0; v != NULL && k < 4; k++) {
        static const char *const other[4][2] = {{"alpha_deg", NULL}, {"beta_deg", NULL},
                                                {"mu_deg", NULL}, {"throttle_pct", "throttle_percent"}};
        size_t i;
        if (lv_table_out_index(cfg->inputs, names[k], &i, NULL) == LV_OK)
            continue;
        for (int a = 0; a < 2 && other[k][a] != NULL; a++)
            if (lv_table_out_index(cfg->inputs, other[k][a], &i, NULL) == LV_OK)
                return lv_pk_fail(c, lv_pk_key(n, "table"), "%s: table '%s' has a column '%s' "
                                  "but none '%s': the inputs are read from the columns alpha, "
                                  "beta, mu [rad] and throttle [1] (no unit is converted): "
                                  "write '%s [%s]'", what, lv_table_name(cfg->inputs),
                                  other[k][a], names[k], names[k], k < 3 ? "rad" : "1");
    }
    if (v != NULL && over != LV_DOF3_OVER_TIME)
        return parse_over(c, ov, what, (int)over, cfg);
    return LV_OK;
}

/* separation: {dv, dv_north, dv_east, dv_down, name}: the impulse this phase's body gets at
 * the hand-off, along the parent's final body x axis and in the local NED frame [m/s], and
 * the user's name of the separation (`name:` alone: a name, no impulse). */
static lv_status parse_separation(const lv_pctx *c, const lv_ynode *n, const lv_ynode *phase,
                                  const char *name, dof3_cfg *cfg, lv_phase_def *ph)
{
    static const char *const skeys[] = {"dv", "dv_north", "dv_east", "dv_down", "name", NULL};
    char what[LV_WHAT_MAX], slot[LV_NAME_MAX + 32];
    lv_status st;
    snprintf(what, sizeof what, "phase '%s', separation", name);
    for (int k = 0; k < 4; k++)
        cfg->sep_dv[k] = LV_NO_SLOT;
    if (n == NULL || lv_yaml_is_null(n))
        return LV_OK;
    if (lv_pk_get(phase, "from") == NULL)
        return lv_pk_fail(c, lv_pk_key(phase, "separation"), "%s: a separation is a hand-off "
                          "rule: only a phase with `from` has one", what);
    if (ph->reference != NULL && ph->reference->start) /* parsed before (phase_dof3_parse) */
        return lv_pk_fail(c, lv_pk_key(phase, "separation"), "%s: the phase starts from its "
                          "reference's first row (start: reference), which gives its velocity: "
                          "a separation impulse would be ignored; leave it out, or start from the "
                          "parent (start: parent)", what);
    if (n->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, n, "%s: a mapping such as {dv: -2} expected", what);
    if ((st = lv_pk_check_map(c, n, what, skeys)) != LV_OK)
        return st;
    const lv_ynode *nm = lv_pk_get(n, "name");
    if (nm != NULL && (st = lv_pk_event_label(c, nm, what, "name", &ph->separation_label)) != LV_OK)
        return st;
    if (nm != NULL && n->n == 2) /* {name: ...} alone: no impulse */
        return LV_OK;
    cfg->sep = 1;
    for (int k = 0; k < 4; k++) {
        snprintf(slot, sizeof slot, "%s.separation.%s", name, skeys[k]);
        const lv_ynode *v = lv_pk_get(n, skeys[k]);
        const lv_range r = {-1e4, 1e4, 0, 0}; /* m/s: a separation, not a propulsive burn */
        st = v != NULL ? lv_pk_slot(c, v, what, skeys[k], slot, "m/s", r, 0, &cfg->sep_dv[k])
                       : lv_pk_slot_default(c, slot, "m/s", 0.0, r, &cfg->sep_dv[k]);
        if (st != LV_OK)
            return st;
    }
    return LV_OK;
}

static lv_status dof3_parse(const lv_pctx *c, const lv_ynode *n, lv_phase_def *ph)
{
    dof3_cfg *cfg = calloc(1, sizeof *cfg);
    if (cfg == NULL)
        return lv_pk_nomem(c);
    ph->type_cfg = cfg;
    for (int k = 0; k < 4; k++)
        cfg->u[k] = LV_NO_SLOT;
    cfg->duration = NAN;
    lv_status st = lv_reference_parse(c, lv_pk_key(n, "reference"), lv_pk_get(n, "reference"), ph);
    if (st != LV_OK)
        return st;
    st = lv_aero_def_parse(c, lv_pk_get(n, "aero"), ph->name, 0, &cfg->aero);
    if (st == LV_OK)
        st = lv_guidance_def_parse(c, lv_pk_get(n, "guidance"), lv_pk_get(n, "throttle"),
                                   ph->name, cfg->aero.present, 1, &cfg->guid);
    char thr_is[64], thr_written[64];
    const lv_law *thr_fixed = lv_guidance_def_throttle_fixed(&cfg->guid, thr_is, sizeof thr_is,
                                                             thr_written, sizeof thr_written);
    const int table_thr = st == LV_OK && lv_guidance_def_gives_throttle(&cfg->guid);
    const int thr_elsewhere = table_thr || thr_fixed != NULL ||
                              lv_guidance_def_throttle_value(&cfg->guid) != LV_NO_SLOT;
    if (st == LV_OK)
        st = parse_inputs(c, lv_pk_get(n, "inputs"), ph->name, cfg->guid.steer.law != NULL,
                          thr_elsewhere,
                          cfg);
    if (st == LV_OK)
        st = parse_separation(c, lv_pk_get(n, "separation"), n, ph->name, cfg, ph);
    if (st != LV_OK)
        return st;
    /* one source for each input: a guidance law steers instead of the inputs' angles, a
     * throttle value replaces the inputs' throttle */
    const lv_ynode *in = lv_pk_get(n, "inputs");
    if (cfg->guid.steer.law != NULL && in != NULL && in->kind == LV_YNODE_MAP) {
        static const char *const angles[] = {"alpha", "beta", "mu", "alpha_deg", "beta_deg",
                                             "mu_deg", "table", NULL};
        for (size_t i = 0; angles[i] != NULL; i++)
            if (lv_pk_get(in, angles[i]) != NULL)
                return lv_pk_fail(c, lv_pk_key(in, angles[i]), "phase '%s', inputs: '%s' and "
                                  "`guidance:` both steer the vehicle: give the attitude in one "
                                  "place (the attitude law takes angles and a table)", ph->name,
                                  angles[i]);
    }
    /* one source for the throttle: inputs.throttle, throttle.value or the attitude table's
     * "throttle" output, and none where the throttle law decides (off, landing) */
    const lv_ynode *in_thr = in != NULL && in->kind == LV_YNODE_MAP ? lv_pk_key(in, "throttle")
                                                                      : NULL;
    const lv_ynode *thr = lv_pk_get(n, "throttle");
    const lv_ynode *thr_val = thr != NULL && thr->kind == LV_YNODE_MAP ? lv_pk_key(thr, "value")
                                                                         : NULL;
    if (in_thr != NULL && thr_val != NULL)
        return lv_pk_fail(c, in_thr, "phase '%s', inputs: throttle is also given as "
                          "throttle.value: give it once", ph->name);
    if (table_thr && (in_thr != NULL || thr_val != NULL))
        return lv_pk_fail(c, in_thr != NULL ? in_thr : thr_val, "phase '%s': the attitude "
                          "table gives the throttle (its output 'throttle'): give it once",
                          ph->name);
    if (thr_fixed != NULL && (in_thr != NULL || table_thr))
        return lv_pk_fail(c, in_thr != NULL ? in_thr : lv_pk_key(n, "throttle"),
                          "phase '%s': the throttle is '%s' (throttle: %s): a throttle %s has no "
                          "effect", ph->name, thr_is, thr_written, in_thr != NULL ? "in inputs" : "in the attitude table");
    return LV_OK;
}

/* Once `engines:` is read: a written constant throttle (inputs.throttle, throttle.value) within
 * the range of the engines that run, refused at its position (lv_pk_check_throttle); a table's
 * is clamped and logged instead. */
static lv_status dof3_check(const lv_pctx *c, const lv_ynode *n, lv_phase_def *ph)
{
    (void)n;
    const dof3_cfg *cfg = ph->type_cfg;
    size_t k;
    if (cfg->inputs != NULL && lv_table_out_index(cfg->inputs, "throttle", &k, NULL) == LV_OK)
        return LV_OK; /* the table gives the throttle: the constant does not act */
    const lv_slot v = lv_guidance_def_throttle_value(&cfg->guid);
    if (v != LV_NO_SLOT)
        return lv_pk_check_throttle(c, ph, v, "throttle: value");
    return lv_pk_check_throttle(c, ph, cfg->u[3], "inputs: throttle");
}

/* ---- the model ---------------------------------------------------------------------------- */

typedef struct dof3_self {
    lv_kit_model kit; /* environment, engines, ends (phase_kit.h) */
    lv_dof3 *model;
} dof3_self;

static void dof3_free_self(void *p)
{
    dof3_self *s = p;
    if (s == NULL)
        return;
    lv_dof3_free(s->model);
    lv_kit_clear(&s->kit);
    free(s);
}

/* The stages are one mass point; the bottom stage's engines burn. */
static lv_status dof3_build(const lv_build_ctx *bc, lv_phase_model **out, lv_err *err)
{
    const lv_mission_def *d = bc->def;
    const lv_phase_def *ph = &d->phases[bc->k];
    const dof3_cfg *pc = ph->type_cfg;
    const lv_stage_def *bottom = &d->stages[ph->stages[0]];
    *out = NULL;
    dof3_self *s = calloc(1, sizeof *s);
    if (s == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    lv_status st = lv_kit_begin(bc, &s->kit, 1, sizeof(lv_dof3_end), 1, err);
    if (st != LV_OK) {
        free(s);
        return st;
    }
    lv_dof3_config cfg;
    lv_dof3_config_default(&cfg);
    cfg.name = ph->name;
    lv_kit_world(&s->kit, &cfg.planet, &cfg.gravity, &cfg.atmo, &cfg.wind, &cfg.wind_user);
    const double prop0 = bc->prop[ph->stages[0]];
    cfg.m0 = lv_kit_stack_mass(bc, 0);
    lv_kit_heating(bc, &cfg.nose_radius, &cfg.k_sutton_graves);
    cfg.propellant = prop0;
    const size_t ne = prop0 > 0.0 ? lv_kit_engines(bc, bottom, s->kit.engines) : 0;
    cfg.n_engines = ne;
    cfg.engines = s->kit.engines;
    cfg.start_lat = lv_kit_param(bc, LV_KIT_START_LAT, 0.0);
    cfg.start_lon = lv_kit_param(bc, LV_KIT_START_LON, 0.0);
    cfg.start_h = lv_kit_param(bc, LV_KIT_START_H, 0.0);
    cfg.start_vel = lv_kit_param(bc, LV_KIT_START_VEL, 0.0);
    cfg.start_fpa = lv_kit_param(bc, LV_KIT_START_FPA, 0.0);
    cfg.start_chi = lv_kit_param(bc, LV_KIT_START_CHI, 0.0);
    cfg.n_ends = lv_kit_flight_ends(bc, &s->kit, &cfg.stop_at_burnout);
    cfg.ends = s->kit.ends;
    /* an input without a slot does not act (a guidance law steers, the throttle comes from
     * elsewhere): its default */
    cfg.alpha = lv_kit_val(bc, pc->u[0], 0.0);
    cfg.beta = lv_kit_val(bc, pc->u[1], 0.0);
    cfg.mu = lv_kit_val(bc, pc->u[2], 0.0);
    const lv_slot thr_value = lv_guidance_def_throttle_value(&pc->guid);
    cfg.throttle = lv_kit_val(bc, thr_value, lv_kit_val(bc, pc->u[3], 1.0));
    /* a throttle nobody wrote is full throttle within every engine's range */
    const lv_slot_def *ts = pc->u[3] != LV_NO_SLOT ? &d->slots[pc->u[3]] : NULL;
    if (thr_value == LV_NO_SLOT &&
        (ts == NULL || (ts->loc.line == 0 && cfg.throttle == ts->value)))
        cfg.throttle = lv_kit_full_throttle(s->kit.engines, ne);
    cfg.inputs = pc->inputs;
    cfg.inputs_over = pc->over;
    cfg.inputs_duration = pc->duration;
    cfg.inputs_stop_time = bc->vals[ph->t_stop];
    lv_guidance_def_make(&pc->guid, bc->vals, &cfg.steering, &cfg.throttle_law);
    /* the phase's aerodynamic dataset: each coefficient a constant, a table of its own, an
     * output of the dataset's table, or 0 */
    cfg.aero = lv_kit_aero(bc, &pc->aero, &s->kit);
    st = lv_dof3_create(&cfg, &s->model, err);
    if (st != LV_OK) {
        dof3_free_self(s);
        return st;
    }
    lv_kit_done(&s->kit, lv_dof3_def(s->model), lv_dof3_inst(s->model), s, out);
    return LV_OK;
}

/* The separation impulse: dv along the parent's final body x (its attitude theta, psi relative
 * to local NED at its final geodetic position) plus (dv_north, dv_east, dv_down) there, added
 * to the inertial velocity copied from the parent: v_eci += R3(theta0 + omega t)^T
 * C_ned_ecef^T dv_ned (a velocity change: no w x r term). */
static lv_status dof3_handoff(const lv_build_ctx *bc, const lv_phase_model *pm,
                              const char *const *pnames, const double *pvalues, size_t np,
                              const char *const *names, double *values, size_t n, lv_err *err)
{
    const dof3_cfg *pc = bc->def->phases[bc->k].type_cfg;
    const dof3_self *s = pm->self;
    /* heat loads a parent has none of (a runway roll: no heating model, at rolling speeds
     * none to speak of) start from 0 (docs/models.md, "Aerothermal heating") */
    static const char *const qn[2] = {"heat_load", "heat_load_fm"};
    for (int i = 0; i < 2; i++) {
        const size_t j = lv_names_find(names, n, qn[i]);
        if (j != (size_t)-1 && isnan(values[j]))
            values[j] = 0.0;
    }
    /* a runway parent must have lifted off: lift and thrust carry the weight (margin 1 at the
     * located lift-off); a roll that ended otherwise leaves the vehicle on the runway */
    const size_t im = lv_names_find(pnames, np, "lift_margin"), in = lv_names_find(pnames, np, "normal_force");
    if (im != (size_t)-1 && in != (size_t)-1 && pvalues[im] < 1.0 - 1e-6)
        return lv_fail(err, LV_ERR_INPUT, "the parent roll did not lift off (it ended with a "
                       "normal force of %.6g N, lift margin %.6g): a flight phase starts at "
                       "lift-off: end the roll with its lift-off (the default), or give it more "
                       "thrust, lift or runway time", pvalues[in], pvalues[im]);
    if (!pc->sep)
        return LV_OK;
    static const char *const need[] = {"time", "theta", "psi", "lat", "lon"};
    double f[5];
    for (int i = 0; i < 5; i++) {
        const size_t j = lv_names_find(pnames, np, need[i]);
        if (j == (size_t)-1)
            return lv_fail(err, LV_ERR_INPUT, "separation: the parent's final '%s' is unknown "
                           "(its model is not dof3)", need[i]);
        f[i] = pvalues[j];
    }
    size_t iv[3];
    static const char *const vnames[3] = {"v_eci_x", "v_eci_y", "v_eci_z"};
    for (int i = 0; i < 3; i++)
        if ((iv[i] = lv_names_find(names, n, vnames[i])) == (size_t)-1)
            return lv_fail(err, LV_ERR_INPUT, "separation: the velocity '%s' is not handed over "
                           "from the parent", vnames[i]);
    const double dv = lv_kit_val(bc, pc->sep_dv[0], 0.0);
    const double ct = cos(f[1]), st = sin(f[1]), cp = cos(f[2]), sp = sin(f[2]);
    const double dv_ned[3] = {dv * ct * cp + lv_kit_val(bc, pc->sep_dv[1], 0.0),
                              dv * ct * sp + lv_kit_val(bc, pc->sep_dv[2], 0.0),
                              -dv * st + lv_kit_val(bc, pc->sep_dv[3], 0.0)};
    double C[3][3], dv_ecef[3], zero[3] = {0.0, 0.0, 0.0}, r_eci[3], dv_eci[3];
    lv_frames_C_ned_ecef(f[3], f[4], C);
    for (int i = 0; i < 3; i++)
        dv_ecef[i] = C[0][i] * dv_ned[0] + C[1][i] * dv_ned[1] + C[2][i] * dv_ned[2];
    lv_frames_ecef_to_eci(&s->kit.env.planet, f[0], zero, dv_ecef, r_eci, dv_eci);
    for (int i = 0; i < 3; i++)
        values[iv[i]] += dv_eci[i];
    return LV_OK;
}

/* ---- controls from an optimiser (optimal_control:, docs/optimal-control.md) ------------------ */

/* The model's inputs alpha, beta, mu, throttle (its inputs table), or the angles of the
 * steering law `attitude` in a local or inertial frame (its table: pitch, heading, roll, and
 * the throttle with them): the thrust's direction in a frame that does not turn with the
 * air-relative velocity, which a start at rest needs. */
enum { C_ALPHA, C_BETA, C_MU, C_THROTTLE, C_PITCH };
static const char *const dof3_controls[] = {"alpha", "beta",    "mu",   "throttle",
                                            "pitch", "heading", "roll", NULL};

/* The attitude law's table slot that the controls replace, or NULL (the inputs table). */
static lv_table **attitude_slot(const lv_phase_def *ph)
{
    return lv_guidance_def_attitude_table(&((dof3_cfg *)ph->type_cfg)->guid);
}

static int dof3_control_conflict(const lv_phase_def *ph, size_t input, char *why, size_t cap)
{
    const dof3_cfg *cfg = ph->type_cfg;
    const int att = attitude_slot(ph) != NULL;
    if (input >= C_PITCH && !att) {
        snprintf(why, cap, "'%s' is an angle of the steering law 'attitude' in a local or "
                 "inertial frame: give the phase `guidance: {law: attitude, frame: inertial}` "
                 "(or local); the optimiser then flies its table", dof3_controls[input]);
        return 1;
    }
    if (input < C_THROTTLE && cfg->guid.steer.law != NULL) {
        snprintf(why, cap, "the phase steers with the guidance law '%s', which gives the "
                 "angles: remove `guidance:` to optimise them%s", cfg->guid.steer.law->name,
                 att ? ", or optimise the law's pitch, heading, roll" : "");
        return 1;
    }
    if (input == C_THROTTLE && cfg->guid.steer.law != NULL && !att) {
        snprintf(why, cap, "the phase steers with the guidance law '%s', which flies the "
                 "throttle as a constant: a throttle history is the inputs table's (no "
                 "`guidance:`) or an attitude law's table (`guidance: {law: attitude, frame: "
                 "inertial}` or local)", cfg->guid.steer.law->name);
        return 1;
    }
    if (input == C_THROTTLE && cfg->guid.thr.law != NULL) {
        snprintf(why, cap, "the phase's `throttle:` (law '%s') gives the throttle: remove it to "
                 "optimise the throttle", cfg->guid.thr.law->name);
        return 1;
    }
    return 0;
}

static const lv_table *dof3_own_inputs(const lv_phase_def *ph)
{
    lv_table **slot = attitude_slot(ph);
    return slot != NULL ? *slot : ((const dof3_cfg *)ph->type_cfg)->inputs;
}

static double dof3_control_constant(const lv_phase_def *ph, const lv_mission_def *d,
                                    size_t input)
{
    if (input < C_PITCH || attitude_slot(ph) == NULL)
        return NAN; /* alpha .. throttle: the flight's own alpha_in .. throttle_in */
    return lv_guidance_def_steer_number(&((dof3_cfg *)ph->type_cfg)->guid,
                                        dof3_controls[input], d);
}

static const char *dof3_controls_key(const lv_phase_def *ph)
{
    return attitude_slot(ph) != NULL ? "guidance" : "inputs";
}

static void dof3_set_controls(lv_phase_def *ph, lv_table *t)
{
    dof3_cfg *cfg = ph->type_cfg;
    lv_table **slot = attitude_slot(ph);
    if (slot != NULL) {
        lv_table_free(*slot);
        *slot = t;
        return;
    }
    lv_table_free(cfg->inputs);
    cfg->inputs = t;
    cfg->over = LV_DOF3_OVER_TIME;
    cfg->duration = NAN;
}

const lv_phase_type lv_phase_type_dof3 = {
    .name = "dof3",
    .description = "3-DoF variable-mass point over the rotating planet: engines, aerodynamics, "
                   "inputs alpha, beta, mu, throttle or steering and throttle laws",
    .world = LV_WORLD_PLANET,
    .keys = keys,
    .from_types = from_types,
    .n_mission_params = sizeof mission_params / sizeof mission_params[0],
    .mission_params = mission_params,
    .mission_param_ranges = mission_param_ranges,
    .mass_state = "m",
    .parse = dof3_parse,
    .cfg_free = dof3_cfg_free,
    .build = dof3_build,
    .free_self = dof3_free_self,
    .n_traj = LV_KIT_PLANET_TRAJ_N,
    .traj = lv_kit_planet_traj,
    .traj_extra = NULL,
    .handoff = dof3_handoff,
    .check = dof3_check,
    .controls = dof3_controls,
    .control_conflict = dof3_control_conflict,
    .set_controls = dof3_set_controls,
    .own_inputs = dof3_own_inputs,
    .control_constant = dof3_control_constant,
    .controls_key = dof3_controls_key,
};
