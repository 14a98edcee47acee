/* phase_dof6.c - the phase-model type "dof6": the 6-DoF variable-mass rigid body over the
 * rotating planet (lv_dof6.h; the paper's sec. 2.3, Table 1). The phase's stages fly as one
 * rigid body with the mass properties of its bottom stage's `rigid_body:` data; the bottom
 * stage's engines burn at their gimbal point. Its own phase keys: attitude and rates (the start
 * values psi, theta, phi, p, q, r of a root phase), inputs (gimbal angles, throttle: constants or
 * a table over time), aero (the force dataset: aero_def.h), moments (Cl, Cm, Cn, damping
 * derivatives, reference lengths and point), guidance (the steering laws of dof3:
 * guidance_def.h, the commanded attitude), controller (PD/PID gimbal control of pitch and yaw
 * with rate-limited actuators) and transition (the 3-DoF -> 6-DoF rates rule). Hand-offs from
 * and to "dof3": docs/models.md, "Level-of-detail transitions". */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/names.h"
#include "core/status.h"
#include "lvsim/lv_dof6.h"
#include "lvsim/lv_units.h"
#include "lvsim/lv_wind.h"
#include "mission/aero_def.h"
#include "mission/guidance_def.h"
#include "mission/phase_kit.h"
#include "mission/phase_type.h"
#include "mission/reference.h"

static const char *const keys[] = {"attitude", "rates",    "inputs",     "aero",
                                   "moments",  "guidance", "controller", "transition",
                                   "engines",  "engine_out", "reference", NULL};
/* The mission parameters only a root phase reads: a child starts with its parent's position,
 * velocity, attitude and rates (start_lat, start_lon: the steering laws' default target;
 * start_fpa, start_chi: the direction of the aerodynamic frame at zero air speed). */
static const char *const root_only[] = {"start_h",   "start_vel", "start_psi", "start_theta",
                                        "start_phi", "start_p",   "start_q",   "start_r",
                                        NULL};
/* A dof3 phase hands over its position, velocity and mass; the attitude is built here
 * (dof6_handoff). */
static const char *const from_types[] = {"dof3", NULL};

/* The model's parameters that are the mission's shared parameter set (lv_dof6.h): a start over
 * the planet, and the paper's Table 1, 6-DoF: the same as a root phase's `attitude:` and
 * `rates:` */
static const lv_var mission_params[] = {
    LV_KIT_START_PARAMS,
    {"start_psi", "rad", "Initial yaw attitude (3-2-1 Euler angles relative to NED)", 0, 0},
    {"start_theta", "rad", "Initial pitch attitude (3-2-1 Euler angles relative to NED)", 0, 0},
    {"start_phi", "rad", "Initial roll attitude (3-2-1 Euler angles relative to NED)", 0, 0},
    {"start_p", "rad/s", "Initial roll rate (relative to inertial space)", 0, 0},
    {"start_q", "rad/s", "Initial pitch rate (relative to inertial space)", 0, 0},
    {"start_r", "rad/s", "Initial yaw rate (relative to inertial space)", 0, 0},
};

static const lv_range mission_param_ranges[] = {
    LV_KIT_START_RANGES,
    {-2.0 * LV_PI, 2.0 * LV_PI, 0, 0}, {-0.5 * LV_PI, 0.5 * LV_PI, 0, 0},
    {-2.0 * LV_PI, 2.0 * LV_PI, 0, 0}, {-LV_DOF6_RATE_MAX, LV_DOF6_RATE_MAX, 0, 0},
    {-LV_DOF6_RATE_MAX, LV_DOF6_RATE_MAX, 0, 0}, {-LV_DOF6_RATE_MAX, LV_DOF6_RATE_MAX, 0, 0},
};


/* ---- the phase's own keys ------------------------------------------------------------ */

enum { A_PSI, A_THETA, A_PHI, A_P, A_Q, A_R, A_N };  /* attitude:, rates: */
enum { U_GP, U_GY, U_THR, U_N };                    /* inputs: */
enum { M_CL, M_CM, M_CN, M_CLP, M_CMQ, M_CNR, M_B, M_C, M_X, M_Y, M_Z, M_N }; /* moments: */
enum { G_KP, G_KD, G_KI, G_N };                     /* controller: pitch:, yaw: */
enum { C_LIM, C_RATE, C_TAU, C_N };                 /* controller: */

typedef struct dof6_cfg {
    lv_slot att[A_N];    /* rad, rad/s (LV_NO_SLOT: a phase with `from`) */
    lv_slot u[U_N];      /* gimbal pitch, yaw [rad], throttle */
    char *inputs_file, *inputs_var;
    lv_table *inputs;
    lv_aero_def aero;
    int has_moments;
    lv_slot mom[M_N];
    lv_table *mom_table; /* outputs Cl, Cm, Cn over mach, alpha, beta, altitude; or NULL */
    char *mom_file, *mom_var;
    lv_guidance_def guid; /* the steering law (guidance_def.h) */
    int ctl;              /* controller: 0 none, LV_DOF6_CTL_PD, LV_DOF6_CTL_PID */
    lv_slot gain[2][G_N]; /* pitch, yaw: kp [rad/rad], kd [s], ki [1/s] (LV_NO_SLOT: 0) */
    lv_slot ctl_num[C_N]; /* limit [rad], rate_limit [rad/s], tau [s] */
    lv_dof6_rates_rule rates_rule; /* transition: {rates: ...} */
    lv_src_loc transition_loc;     /* where `transition:` is written; line 0: not given */
} dof6_cfg;

static void dof6_cfg_free(void *p)
{
    dof6_cfg *c = p;
    if (c == NULL)
        return;
    free(c->inputs_file);
    free(c->inputs_var);
    lv_table_free(c->inputs);
    lv_aero_def_clear(&c->aero);
    lv_table_free(c->mom_table);
    free(c->mom_file);
    free(c->mom_var);
    lv_guidance_def_clear(&c->guid);
    free(c);
}

/* A mapping of named numbers (`names[k]`, also `<name>_deg` where deg[k]) as slots
 * "<phase>.<sub>.<name>" with defaults; `extra` (NULL-terminated, may be NULL): the mapping's
 * other keys, parsed by the caller. */
static lv_status parse_numbers(const lv_pctx *c, const lv_ynode *n, const char *phase,
                               const char *sub, size_t nk, const char *const *names,
                               const char *const *units, const int *deg, const double *dflt,
                               const lv_range *range, const char *const *extra, lv_slot *out)
{
    char what[LV_WHAT_MAX], slot[LV_NAME_MAX + 48], dk[32];
    snprintf(what, sizeof what, "phase '%s', %s", phase, sub);
    lv_status st;
    if (n != NULL && lv_yaml_is_null(n))
        n = NULL;
    if (n != NULL && n->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, n, "%s: a mapping such as {%s%s: 0} expected", what, names[0],
                          deg[0] ? "_deg" : "");
    if (n != NULL) { /* every key is a name, its _deg spelling, or an extra */
        const char *list[48];
        char dks[24][32];
        size_t m = 0, dn = 0;
        for (size_t k = 0; k < nk && m < 40; k++) {
            list[m++] = names[k];
            if (deg[k] && dn < 24) {
                snprintf(dks[dn], sizeof dks[dn], "%s_deg", names[k]);
                list[m++] = dks[dn++];
            }
        }
        for (size_t k = 0; extra != NULL && extra[k] != NULL && m < 47; k++)
            list[m++] = extra[k];
        list[m] = NULL;
        if ((st = lv_pk_check_map(c, n, what, list)) != LV_OK)
            return st;
    }
    for (size_t k = 0; k < nk; k++) {
        snprintf(dk, sizeof dk, "%s_deg", names[k]);
        snprintf(slot, sizeof slot, "%s.%s.%s", phase, sub, names[k]);
        const lv_ynode *v = lv_pk_get(n, names[k]), *vd = deg[k] ? lv_pk_get(n, dk) : NULL;
        if (v != NULL && vd != NULL)
            return lv_pk_fail(c, lv_pk_key(n, dk), "%s: '%s' and '%s' given both", what,
                              names[k], dk);
        st = v != NULL || vd != NULL
                 ? lv_pk_slot(c, v ? v : vd, what, v ? names[k] : dk, slot, units[k], range[k],
                              vd != NULL, &out[k])
                 : lv_pk_slot_default(c, slot, units[k], dflt[k], range[k], &out[k]);
        if (st != LV_OK)
            return st;
    }
    return LV_OK;
}

/* attitude: {psi_deg, theta_deg, phi_deg} and rates: {p_deg, q_deg, r_deg} (deg/s): the start
 * values of Table 1 for a root phase (a phase with `from` starts with its parent's). */
static lv_status parse_start(const lv_pctx *c, const lv_ynode *n, const char *phase,
                             dof6_cfg *cfg)
{
    static const char *const an[3] = {"psi", "theta", "phi"}, *const rn[3] = {"p", "q", "r"};
    static const char *const au[3] = {"rad", "rad", "rad"}, *const ru[3] = {"rad/s", "rad/s",
                                                                            "rad/s"};
    static const int deg[3] = {1, 1, 1};
    static const double zero[3] = {0.0, 0.0, 0.0};
    const lv_range ar[3] = {{-2.0 * LV_PI, 2.0 * LV_PI, 0, 0},
                            {-0.5 * LV_PI, 0.5 * LV_PI, 0, 0},
                            {-2.0 * LV_PI, 2.0 * LV_PI, 0, 0}};
    const lv_range rmax = {-LV_DOF6_RATE_MAX, LV_DOF6_RATE_MAX, 0, 0}; /* 10 rev/s */
    const lv_range rr[3] = {rmax, rmax, rmax};
    const lv_ynode *a = lv_pk_get(n, "attitude"), *r = lv_pk_get(n, "rates");
    for (int k = 0; k < A_N; k++)
        cfg->att[k] = LV_NO_SLOT;
    if (lv_pk_get(n, "from") != NULL) {
        const char *key = a != NULL ? "attitude" : r != NULL ? "rates" : NULL;
        if (key != NULL)
            return lv_pk_fail(c, lv_pk_key(n, key), "phase '%s': '%s': a phase with `from` "
                              "starts with its parent's attitude and rates (from a dof3 parent: "
                              "its final attitude, rates zero; docs/models.md); override a state "
                              "with `set:` instead", phase, key);
        return LV_OK;
    }
    /* one source: the mission's parameter set (Table 1's names) or the phase's keys */
    static const char *const pn[A_N] = {"start_psi", "start_theta", "start_phi", "start_p",
                                        "start_q", "start_r"};
    for (size_t i = 0; i < c->m->n_params; i++)
        for (int k = 0; k < A_N; k++)
            if (strcmp(c->m->param_names[i], pn[k]) == 0 && (k < A_P ? a : r) != NULL)
                return lv_pk_fail(c, lv_pk_key(n, k < A_P ? "attitude" : "rates"),
                                  "phase '%s': '%s': the mission's `parameters:` give %s "
                                  "already: give the start %s in one place", phase,
                                  k < A_P ? "attitude" : "rates", pn[k],
                                  k < A_P ? "attitude" : "rates");
    lv_status st = parse_numbers(c, a, phase, "attitude", 3, an, au, deg, zero, ar, NULL,
                                 cfg->att);
    if (st == LV_OK)
        st = parse_numbers(c, r, phase, "rates", 3, rn, ru, deg, zero, rr, NULL, cfg->att + A_P);
    return st;
}

/* inputs: {gimbal_pitch_deg, gimbal_yaw_deg, throttle, table}: constants, or a table over time
 * with outputs gimbal_pitch, gimbal_yaw [rad], throttle [1] that replace them. */
static lv_status parse_inputs(const lv_pctx *c, const lv_ynode *n, const char *phase,
                              dof6_cfg *cfg)
{
    if (cfg->ctl && n != NULL && n->kind == LV_YNODE_MAP) { /* the controller gives them */
        static const char *const g[] = {"gimbal_pitch", "gimbal_pitch_deg", "gimbal_yaw",
                                        "gimbal_yaw_deg", NULL};
        for (size_t i = 0; g[i] != NULL; i++)
            if (lv_pk_get(n, g[i]) != NULL)
                return lv_pk_fail(c, lv_pk_key(n, g[i]), "phase '%s', inputs: '%s': the "
                                  "controller gives the gimbal angles: give them in one place",
                                  phase, g[i]);
    }
    static const char *const names[U_N] = {"gimbal_pitch", "gimbal_yaw", "throttle"};
    static const char *const units[U_N] = {"rad", "rad", ""};
    static const int deg[U_N] = {1, 1, 0};
    static const double dflt[U_N] = {0.0, 0.0, 1.0};
    static const char *const extra[] = {"table", NULL};
    const lv_range g = {-0.5 * LV_PI, 0.5 * LV_PI, 0, 0};
    const lv_range range[U_N] = {g, g, LV_RANGE_NONNEG};
    /* with a controller only the throttle: gimbal angles that would change nothing are not
     * parameters of the run */
    const int k0 = cfg->ctl ? U_THR : U_GP;
    cfg->u[U_GP] = cfg->u[U_GY] = LV_NO_SLOT;
    lv_status st = parse_numbers(c, n, phase, "inputs", (size_t)(U_N - k0), names + k0,
                                 units + k0, deg + k0, dflt + k0, range + k0, extra,
                                 cfg->u + k0);
    if (st != LV_OK)
        return st;
    const lv_ynode *v = n != NULL && n->kind == LV_YNODE_MAP ? lv_pk_get(n, "table") : NULL;
    if (v == NULL)
        return LV_OK;
    char what[LV_WHAT_MAX];
    snprintf(what, sizeof what, "phase '%s', inputs", phase);
    if ((st = lv_pk_table(c, lv_pk_key(n, "table"), v, what, LV_EXTRAP_CLAMP, &cfg->inputs_file,
                          &cfg->inputs_var, &cfg->inputs)) != LV_OK)
        return st;
    /* one source per input: a column of the table replaces the constant, so both is an error */
    for (int k = 0; k < U_N; k++) {
        char dk[32];
        snprintf(dk, sizeof dk, "%s_deg", names[k]);
        const lv_ynode *key = lv_pk_key(n, names[k]) ? lv_pk_key(n, names[k])
                              : deg[k] ? lv_pk_key(n, dk) : NULL;
        size_t idx;
        if (key != NULL && lv_table_out_index(cfg->inputs, names[k], &idx, NULL) == LV_OK)
            return lv_pk_fail(c, key, "%s: '%s' is also a column of table '%s': give it once",
                              what, names[k], lv_table_name(cfg->inputs));
    }
    for (int k = U_GP; cfg->ctl && k <= U_GY; k++) {
        size_t idx;
        if (lv_table_out_index(cfg->inputs, names[k], &idx, NULL) == LV_OK)
            return lv_pk_fail(c, v, "%s: table '%s' has the column '%s': the controller gives "
                              "the gimbal angles", what, lv_table_name(cfg->inputs), names[k]);
    }
    return LV_OK;
}

/* controller: {pitch: {kp, kd, ki}, yaw: {kp, kd, ki}, limit_deg, rate_limit_deg, tau}: slots
 * "<phase>.controller.pitch.kp", ..., "<phase>.controller.limit"; PID when either axis writes
 * `ki`. The ranges: kp in (0, 100] rad/rad, kd in [0, 100] s, ki in [0, 100] 1/s, the
 * deflection limit in (0, 90] deg, the rate limit in (0, 1000] deg/s, tau in (0, 10] s. */
static lv_status parse_controller(const lv_pctx *c, const lv_ynode *phase_n, const lv_ynode *n,
                                  const char *phase, dof6_cfg *cfg)
{
    for (int a = 0; a < 2; a++)
        for (int k = 0; k < G_N; k++)
            cfg->gain[a][k] = LV_NO_SLOT;
    for (int k = 0; k < C_N; k++)
        cfg->ctl_num[k] = LV_NO_SLOT;
    if (n == NULL || lv_yaml_is_null(n))
        return LV_OK;
    char what[LV_WHAT_MAX];
    snprintf(what, sizeof what, "phase '%s', controller", phase);
    if (cfg->guid.steer.law == NULL)
        return lv_pk_fail(c, lv_pk_key(phase_n, "controller"), "%s: the controller holds the "
                          "attitude a steering law commands: the phase needs `guidance:` "
                          "(docs/guidance.md)", what);
    if (n->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, n, "%s: a mapping such as {pitch: {kp: 2, kd: 0.5}, yaw: {kp: 2, "
                          "kd: 0.5}, limit_deg: 6, rate_limit_deg: 20} expected", what);
    /* an unknown key first (with a suggestion), before what is missing: a misspelt key is
     * the likelier mistake */
    static const char *const known[] = {"pitch",      "yaw",            "limit", "limit_deg",
                                        "rate_limit", "rate_limit_deg", "tau",   NULL};
    static const char *const gknown[] = {"kp", "kd", "ki", NULL};
    lv_status st = lv_pk_check_map(c, n, what, known);
    if (st != LV_OK)
        return st;
    static const char *const req[] = {"pitch", "yaw", "limit_deg", "rate_limit_deg", NULL};
    for (size_t i = 0; req[i] != NULL; i++) {
        const int ang = i >= 2;
        char plain[32];
        snprintf(plain, sizeof plain, "%.*s", (int)strlen(req[i]) - (ang ? 4 : 0), req[i]);
        if (lv_pk_get(n, req[i]) == NULL && (!ang || lv_pk_get(n, plain) == NULL))
            return lv_pk_fail(c, n, "%s: '%s' is missing%s", what, req[i],
                              ang ? " (or the same in rad without _deg)" : "");
    }
    static const char *const gn[G_N] = {"kp", "kd", "ki"};
    static const char *const gu[G_N] = {"rad/rad", "s", "1/s"};
    static const int gdeg[G_N] = {0, 0, 0};
    static const double gd[G_N] = {NAN, 0.0, 0.0};
    const lv_range gr[G_N] = {{0.0, 100.0, 1, 0}, {0.0, 100.0, 0, 0}, {0.0, 100.0, 0, 0}};
    static const char *const axes[2] = {"pitch", "yaw"};
    int pid = 0;
    for (int a = 0; a < 2; a++) {
        const lv_ynode *g = lv_pk_get(n, axes[a]);
        pid |= g->kind == LV_YNODE_MAP && lv_pk_get(g, "ki") != NULL;
    }
    for (int a = 0; a < 2; a++) {
        const lv_ynode *g = lv_pk_get(n, axes[a]);
        char sub[48], gw[LV_WHAT_MAX];
        snprintf(sub, sizeof sub, "controller.%s", axes[a]);
        snprintf(gw, sizeof gw, "%.150s.%s", what, axes[a]);
        if (g->kind != LV_YNODE_MAP)
            return lv_pk_fail(c, g, "%s: a mapping {kp: rad/rad, kd: s, ki: 1/s} expected", gw);
        if ((st = lv_pk_check_map(c, g, gw, gknown)) != LV_OK)
            return st;
        if (lv_pk_get(g, "kp") == NULL)
            return lv_pk_fail(c, g, "%s: 'kp' is missing (rad of deflection per rad of "
                              "attitude error)", gw);
        if ((st = parse_numbers(c, g, phase, sub, pid ? G_N : G_KI, gn, gu, gdeg, gd, gr, NULL,
                                cfg->gain[a])) != LV_OK)
            return st;
    }
    static const char *const cn[C_N] = {"limit", "rate_limit", "tau"};
    static const char *const cu[C_N] = {"rad", "rad/s", "s"};
    static const int cdeg[C_N] = {1, 1, 0};
    static const double cd[C_N] = {NAN, NAN, 0.05};
    const lv_range cr[C_N] = {{0.0, 0.5 * LV_PI, 1, 0},
                              {0.0, 1000.0 * LV_PI / 180.0, 1, 0},
                              {0.0, 10.0, 1, 0}};
    static const char *const extra[] = {"pitch", "yaw", NULL};
    if ((st = parse_numbers(c, n, phase, "controller", C_N, cn, cu, cdeg, cd, cr, extra,
                            cfg->ctl_num)) != LV_OK)
        return st;
    cfg->ctl = pid ? LV_DOF6_CTL_PID : LV_DOF6_CTL_PD;
    return LV_OK;
}

/* transition: {rates: zero | curvature}: the start body rates of a 3-DoF -> 6-DoF hand-off. */
static lv_status parse_transition(const lv_pctx *c, const lv_ynode *phase_n, const lv_ynode *n,
                                  const char *phase, dof6_cfg *cfg)
{
    static const char *const tkeys[] = {"rates", NULL};
    static const char *const rules[] = {"zero", "curvature", NULL};
    char what[LV_WHAT_MAX];
    snprintf(what, sizeof what, "phase '%s', transition", phase);
    cfg->rates_rule = LV_DOF6_RATES_ZERO;
    if (n == NULL || lv_yaml_is_null(n))
        return LV_OK;
    if (lv_pk_get(phase_n, "from") == NULL)
        return lv_pk_fail(c, lv_pk_key(phase_n, "transition"), "%s: a transition is a hand-off "
                          "rule: only a phase with `from` has one (a root phase takes "
                          "`attitude:` and `rates:`)", what);
    if (n->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, n, "%s: a mapping such as {rates: curvature} expected", what);
    const lv_ynode *k = lv_pk_key(phase_n, "transition");
    cfg->transition_loc = (lv_src_loc){k->line, k->col};
    lv_status st = lv_pk_check_map(c, n, what, tkeys);
    const lv_ynode *v = lv_pk_get(n, "rates");
    size_t idx = 0;
    if (st == LV_OK && v != NULL && (st = lv_pk_enum(c, v, what, "rates", rules, &idx)) == LV_OK)
        cfg->rates_rule = (lv_dof6_rates_rule)idx;
    return st;
}

/* moments: {Cl, Cm, Cn, Clp, Cmq, Cnr, b_ref, c_ref, mrp_x, mrp_y, mrp_z, table}. */
static lv_status parse_moments(const lv_pctx *c, const lv_ynode *phase_n, const lv_ynode *n,
                               const char *phase, dof6_cfg *cfg)
{
    static const char *const names[M_N] = {"Cl",    "Cm",    "Cn",    "Clp",   "Cmq",  "Cnr",
                                           "b_ref", "c_ref", "mrp_x", "mrp_y", "mrp_z"};
    static const char *const units[M_N] = {"", "", "", "1/rad", "1/rad", "1/rad",
                                           "m", "m", "m", "m", "m"};
    static const int deg[M_N] = {0};
    static const double dflt[M_N] = {0, 0, 0, 0, 0, 0, NAN, NAN, 0, 0, 0};
    static const char *const extra[] = {"table", NULL};
    lv_range range[M_N];
    for (int k = 0; k < M_N; k++)
        range[k] = k == M_B || k == M_C ? LV_RANGE_POS : LV_RANGE_ANY;
    if (n == NULL || lv_yaml_is_null(n))
        return LV_OK;
    char what[LV_WHAT_MAX];
    snprintf(what, sizeof what, "phase '%s', moments", phase);
    if (!cfg->aero.present)
        return lv_pk_fail(c, lv_pk_key(phase_n, "moments"), "%s: aerodynamic moments need the "
                          "phase's `aero:` (its reference area s_ref)", what);
    if (n->kind == LV_YNODE_MAP)
        for (int k = M_B; k <= M_C; k++)
            if (lv_pk_get(n, names[k]) == NULL)
                return lv_pk_fail(c, n, "%s: '%s' is missing (the reference %s, m)", what,
                                  names[k], k == M_B ? "span b (roll, yaw)" : "chord c (pitch)");
    double d[M_N];
    memcpy(d, dflt, sizeof d);
    d[M_B] = d[M_C] = 1.0; /* given: checked above */
    lv_status st = parse_numbers(c, n, phase, "moments", M_N, names, units, deg, d, range, extra,
                                 cfg->mom);
    if (st != LV_OK)
        return st;
    cfg->has_moments = 1;
    const lv_ynode *v = lv_pk_get(n, "table");
    if (v == NULL)
        return LV_OK;
    if ((st = lv_pk_table(c, lv_pk_key(n, "table"), v, what, LV_EXTRAP_CLAMP, &cfg->mom_file,
                          &cfg->mom_var, &cfg->mom_table)) != LV_OK)
        return st;
    int any = 0;
    for (int k = M_CL; k <= M_CN; k++) {
        size_t idx;
        if (lv_table_out_index(cfg->mom_table, names[k], &idx, NULL) != LV_OK)
            continue;
        any = 1;
        if (lv_pk_get(n, names[k]) != NULL)
            return lv_pk_fail(c, lv_pk_key(n, names[k]), "%s: '%s' is given as a constant and "
                              "as an output of the table: give it once", what, names[k]);
    }
    if (!any)
        return lv_pk_fail(c, v, "%s: table '%s' has none of the outputs Cl, Cm, Cn", what,
                          lv_table_name(cfg->mom_table));
    return LV_OK;
}

static lv_status dof6_parse(const lv_pctx *c, const lv_ynode *n, lv_phase_def *ph)
{
    dof6_cfg *cfg = calloc(1, sizeof *cfg);
    if (cfg == NULL)
        return lv_pk_nomem(c);
    ph->type_cfg = cfg;
    for (int k = 0; k < M_N; k++)
        cfg->mom[k] = LV_NO_SLOT;
    lv_status rst = lv_reference_parse(c, lv_pk_key(n, "reference"), lv_pk_get(n, "reference"),
                                       ph);
    if (rst != LV_OK)
        return rst;
    const lv_stage_def *bottom = &c->m->stages[ph->stages[0]];
    if (!bottom->rigid.present)
        return lv_pk_fail(c, n, "phase '%s': model dof6 needs the rigid-body data of its bottom "
                          "stage '%s' (`rigid_body: {inertia_full: {xx, yy, zz}, ...}` in the "
                          "stage; docs/mission-format.md)", ph->name, bottom->name);
    lv_status st = parse_start(c, n, ph->name, cfg);
    if (st == LV_OK)
        st = lv_aero_def_parse(c, lv_pk_get(n, "aero"), ph->name, 0, &cfg->aero);
    if (st == LV_OK)
        st = lv_guidance_def_parse(c, lv_pk_get(n, "guidance"), NULL, ph->name,
                                   cfg->aero.present, 0, &cfg->guid);
    if (st == LV_OK)
        st = parse_controller(c, n, lv_pk_get(n, "controller"), ph->name, cfg);
    if (st == LV_OK)
        st = parse_inputs(c, lv_pk_get(n, "inputs"), ph->name, cfg);
    if (st == LV_OK)
        st = parse_moments(c, n, lv_pk_get(n, "moments"), ph->name, cfg);
    if (st == LV_OK)
        st = parse_transition(c, n, lv_pk_get(n, "transition"), ph->name, cfg);
    if (st != LV_OK)
        return st;
    /* one source for the throttle: inputs (constant, table) or the attitude table */
    const lv_ynode *in = lv_pk_get(n, "inputs");
    if (lv_guidance_def_gives_throttle(&cfg->guid) && in != NULL && in->kind == LV_YNODE_MAP) {
        size_t ik;
        const lv_ynode *k = lv_pk_key(in, "throttle");
        if (k == NULL && cfg->inputs != NULL &&
            lv_table_out_index(cfg->inputs, "throttle", &ik, NULL) == LV_OK)
            k = lv_pk_key(in, "table");
        if (k != NULL)
            return lv_pk_fail(c, k, "phase '%s', inputs: the attitude table gives the throttle "
                              "(its output 'throttle'): give it once", ph->name);
    }
    return LV_OK;
}

/* The start values `set:` gives the body rates and the controller's states, refused where the
 * file writes them with the ranges the model checks when it starts (lv_dof6.h, dof6_init), so
 * that `lvsim check` and `lvsim run` accept the same files (a child's states are set only when
 * it starts, after its parent has run):
 *   p, q, r                 |w| <= 10 rev/s (LV_DOF6_RATE_MAX);
 *   act_pitch, act_yaw      with a controller, within its deflection limit;
 *   int_pitch, int_yaw      with a PID controller, |ki int| <= the deflection limit: the
 *                           integral's share of the command within what the actuator can
 *                           deflect (a larger start is a wound-up integrator that would hold
 *                           the gimbal at its limit until the error unwinds it); 0 on an axis
 *                           with ki = 0, where the integral does not act.
 * A controller state in a phase without the controller is named as such. */
static lv_status check_set_ranges(const lv_pctx *c, const lv_phase_def *ph)
{
    const dof6_cfg *cfg = ph->type_cfg;
    static const char *const wn[3] = {"p", "q", "r"};
    static const char *const cn[4] = {"act_pitch", "act_yaw", "int_pitch", "int_yaw"};
    for (size_t i = 0; i < ph->n_set; i++) {
        const char *name = ph->set_names[i];
        const double v = c->m->slots[ph->set_values[i]].value;
        const lv_src_loc loc = ph->set_locs != NULL ? ph->set_locs[i] : ph->loc;
        for (int k = 0; k < 3; k++)
            if (strcmp(name, wn[k]) == 0 && !(fabs(v) <= LV_DOF6_RATE_MAX))
                return lv_fail(c->err, LV_ERR_INPUT, "%s:%d:%d: phase '%s': set: start body "
                               "rate %s = %g rad/s is outside [-%g, %g] rad/s (10 rev/s)",
                               c->file, loc.line, loc.column, ph->name, name, v,
                               LV_DOF6_RATE_MAX, LV_DOF6_RATE_MAX);
        int k = 0;
        while (k < 4 && strcmp(name, cn[k]) != 0)
            k++;
        if (k == 4)
            continue;
        if (!cfg->ctl || (k >= 2 && cfg->ctl != LV_DOF6_CTL_PID))
            return lv_fail(c->err, LV_ERR_INPUT, "%s:%d:%d: phase '%s': set: '%s' is a state of "
                           "the %s controller: the phase has %s", c->file, loc.line, loc.column,
                           ph->name, name, k >= 2 ? "PID" : "attitude",
                           !cfg->ctl ? "no `controller:`" : "a PD controller (no `ki`)");
        const double lim = c->m->slots[cfg->ctl_num[C_LIM]].value;
        if (k < 2 && !(fabs(v) <= lim))
            return lv_fail(c->err, LV_ERR_INPUT, "%s:%d:%d: phase '%s': set: start %s = %g rad "
                           "(%g deg) is outside the controller's deflection limit +-%g deg",
                           c->file, loc.line, loc.column, ph->name, name, v, v / LV_DEG,
                           lim / LV_DEG);
        if (k < 2)
            continue;
        const lv_slot ks = cfg->gain[k - 2][G_KI];
        const double ki = ks == LV_NO_SLOT ? 0.0 : c->m->slots[ks].value;
        if (ki == 0.0 && v != 0.0)
            return lv_fail(c->err, LV_ERR_INPUT, "%s:%d:%d: phase '%s': set: start %s = %g rad s "
                           "on an axis with ki = 0, where the integral does not act: 0 or "
                           "nothing", c->file, loc.line, loc.column, ph->name, name, v);
        if (ki > 0.0 && !(fabs(ki * v) <= lim))
            return lv_fail(c->err, LV_ERR_INPUT, "%s:%d:%d: phase '%s': set: start %s = %g rad s "
                           "is outside +-%g rad s: its part of the command, ki %s = %g deg, "
                           "beyond the deflection limit %g deg (a wound-up integrator)",
                           c->file, loc.line, loc.column, ph->name, name, v, lim / ki, name,
                           ki * v / LV_DEG, lim / LV_DEG);
    }
    return LV_OK;
}

/* After `set:` (parse.c): a written constant throttle within the engines' range
 * (lv_pk_check_throttle); the start values in the model's ranges (check_set_ranges); the
 * quaternion states set all four together, as a unit quaternion (a partial set would leave
 * the attitude undefined: the model refuses a start quaternion whose norm is not 1). */
static lv_status dof6_check_set(const lv_pctx *c, const lv_ynode *n, lv_phase_def *ph)
{
    (void)n;
    static const char *const qn[4] = {"q_w", "q_x", "q_y", "q_z"};
    const dof6_cfg *pc = ph->type_cfg;
    lv_status st = check_set_ranges(c, ph);
    if (st == LV_OK) /* a constant throttle the engines can give (the table's is clamped) */
        st = lv_pk_check_throttle(c, ph, pc->u[U_THR], "inputs: throttle");
    if (st != LV_OK)
        return st;
    int idx[4] = {-1, -1, -1, -1}, first = -1, given = 0;
    for (size_t i = 0; i < ph->n_set; i++)
        for (int k = 0; k < 4; k++)
            if (strcmp(ph->set_names[i], qn[k]) == 0) {
                idx[k] = (int)i;
                given++;
                if (first < 0)
                    first = (int)i;
            }
    if (given == 0)
        return LV_OK;
    const lv_src_loc loc = ph->set_locs != NULL ? ph->set_locs[first] : ph->loc;
    if (given < 4) {
        char missing[32] = "";
        size_t len = 0;
        for (int k = 0; k < 4; k++)
            if (idx[k] < 0)
                len += (size_t)snprintf(missing + len, sizeof missing - len, "%s%s",
                                        len ? ", " : "", qn[k]);
        return lv_fail(c->err, LV_ERR_INPUT, "%s:%d:%d: phase '%s': set: the attitude quaternion "
                       "is set by its four components q_w, q_x, q_y, q_z together (missing: %s), "
                       "a unit quaternion body -> ECI", c->file, loc.line, loc.column, ph->name,
                       missing);
    }
    double n2 = 0.0;
    for (int k = 0; k < 4; k++) {
        const double v = c->m->slots[ph->set_values[idx[k]]].value;
        n2 += v * v;
    }
    if (!(fabs(sqrt(n2) - 1.0) < 1e-6))
        return lv_fail(c->err, LV_ERR_INPUT, "%s:%d:%d: phase '%s': set: the quaternion (q_w, "
                       "q_x, q_y, q_z) has norm %.9g: it must be 1 (within 1e-6)", c->file,
                       loc.line, loc.column, ph->name, sqrt(n2));
    return LV_OK;
}

/* Once the phase tree is known (parse.c, check_tree): a `transition:` is the rule of a change
 * of model; from a dof6 parent the attitude and rates are states of both models, copied. */
static lv_status dof6_check_parent(const lv_pctx *c, const lv_phase_def *ph,
                                   const lv_phase_def *parent)
{
    const dof6_cfg *cfg = ph->type_cfg;
    if (cfg == NULL || cfg->transition_loc.line == 0 || parent->type != ph->type)
        return LV_OK;
    return lv_fail(c->err, LV_ERR_INPUT, "%s:%d:%d: phase '%s', transition: applies to a change "
                   "of model (from a dof3 parent); the parent '%s' is dof6: its rates are copied",
                   c->file, cfg->transition_loc.line, cfg->transition_loc.column, ph->name,
                   parent->name);
}

/* The conversion's rule of a 3-DoF -> 6-DoF hand-off, for summary.json. */
static const char *dof6_handoff_rule(const lv_phase_def *ph)
{
    const dof6_cfg *cfg = ph->type_cfg;
    return cfg != NULL && cfg->rates_rule == LV_DOF6_RATES_CURVATURE ? "rates: curvature"
                                                                     : "rates: zero";
}

/* ---- the model ---------------------------------------------------------------------------- */

typedef struct dof6_self {
    lv_kit_model kit; /* environment, engines, ends (phase_kit.h) */
    lv_dof6 *model;
    lv_dof6_moments mom;
    lv_dof6_engine_geom *geom;
    double *exit;     /* [3 n_engines] m, the nozzle exits (rigid_body.nozzle_exit) */
} dof6_self;

static void dof6_free_self(void *p)
{
    dof6_self *s = p;
    if (s == NULL)
        return;
    lv_dof6_free(s->model);
    lv_kit_clear(&s->kit);
    free(s->geom);
    free(s->exit);
    free(s);
}

static lv_status dof6_build(const lv_build_ctx *bc, lv_phase_model **out, lv_err *err)
{
    const lv_mission_def *d = bc->def;
    const lv_phase_def *ph = &d->phases[bc->k];
    const dof6_cfg *pc = ph->type_cfg;
    const lv_stage_def *bottom = &d->stages[ph->stages[0]];
    const lv_rigid_body_def *rb = &bottom->rigid;
    *out = NULL;
    dof6_self *s = calloc(1, sizeof *s);
    if (s == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    lv_status st = lv_kit_begin(bc, &s->kit, 1, sizeof(lv_dof3_end), 1, err);
    if (st != LV_OK) {
        free(s);
        return st;
    }
    if ((s->geom = calloc(lv_kit_engine_count(bottom) + 1, sizeof *s->geom)) == NULL ||
        (s->exit = calloc(3 * lv_kit_engine_count(bottom) + 3, sizeof *s->exit)) == NULL) {
        dof6_free_self(s);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    lv_dof6_config cfg;
    lv_dof6_config_default(&cfg);
    cfg.name = ph->name;
    lv_kit_world(&s->kit, &cfg.planet, &cfg.gravity, &cfg.atmo, &cfg.wind, &cfg.wind_user);
    /* the stack: its mass now, and with the bottom stage's propellant full and gone */
    const double m_upper = lv_kit_stack_mass(bc, 1);
    const double prop0 = bc->prop[ph->stages[0]];
    cfg.m0 = lv_kit_stack_mass(bc, 0);
    lv_kit_heating(bc, &cfg.nose_radius, &cfg.k_sutton_graves);
    cfg.propellant = prop0;
    cfg.mass.m_full = lv_kit_val(bc, bottom->dry_mass, 0.0) +
                      lv_kit_val(bc, bottom->propellant_mass, 0.0) + m_upper;
    cfg.mass.m_empty = cfg.mass.m_full - lv_kit_val(bc, bottom->propellant_mass, 0.0);
    for (int i = 0; i < 6; i++) {
        cfg.mass.inertia_full[i] = bc->vals[rb->inertia_full[i]];
        cfg.mass.inertia_empty[i] = bc->vals[rb->inertia_empty[i]];
    }
    for (int i = 0; i < 3; i++) {
        cfg.mass.cg_full[i] = bc->vals[rb->cg_full[i]];
        cfg.mass.cg_empty[i] = bc->vals[rb->cg_empty[i]];
    }
    /* every engine at the stage's gimbal point, with its misalignment */
    const size_t ne = prop0 > 0.0 ? lv_kit_engines(bc, bottom, s->kit.engines) : 0;
    for (size_t e = 0; e < ne; e++) {
        for (int i = 0; i < 3; i++)
            s->geom[e].pos[i] = bc->vals[rb->engine_pos[i]];
        s->geom[e].mis_pitch = bc->vals[rb->mis_pitch];
        s->geom[e].mis_yaw = bc->vals[rb->mis_yaw];
        for (int i = 0; rb->has_exit && i < 3; i++)
            s->exit[3 * e + i] = bc->vals[rb->nozzle_exit[i]];
    }
    cfg.n_engines = ne;
    cfg.engines = s->kit.engines;
    cfg.engine_geom = s->geom;
    cfg.engine_exit = rb->has_exit ? s->exit : NULL;
    cfg.terms = (lv_dof6_terms){rb->jet_damping, rb->inertia_rate,
                                (lv_dof6_damping_frame)rb->rate_damping_frame};
    cfg.start_lat = lv_kit_param(bc, LV_KIT_START_LAT, 0.0);
    cfg.start_lon = lv_kit_param(bc, LV_KIT_START_LON, 0.0);
    cfg.start_h = lv_kit_param(bc, LV_KIT_START_H, 0.0);
    cfg.start_vel = lv_kit_param(bc, LV_KIT_START_VEL, 0.0);
    cfg.start_fpa = lv_kit_param(bc, LV_KIT_START_FPA, 0.0);
    cfg.start_chi = lv_kit_param(bc, LV_KIT_START_CHI, 0.0);
    cfg.start_psi = lv_kit_val(bc, pc->att[A_PSI], 0.0);
    cfg.start_theta = lv_kit_val(bc, pc->att[A_THETA], 0.0);
    cfg.start_phi = lv_kit_val(bc, pc->att[A_PHI], 0.0);
    cfg.start_p = lv_kit_val(bc, pc->att[A_P], 0.0);
    cfg.start_q = lv_kit_val(bc, pc->att[A_Q], 0.0);
    cfg.start_r = lv_kit_val(bc, pc->att[A_R], 0.0);
    cfg.gimbal_pitch = lv_kit_val(bc, pc->u[U_GP], 0.0);
    cfg.gimbal_yaw = lv_kit_val(bc, pc->u[U_GY], 0.0);
    cfg.throttle = lv_kit_val(bc, pc->u[U_THR], 1.0);
    const lv_slot_def *ts = &d->slots[pc->u[U_THR]]; /* always a slot (default 1) */
    if (ts->loc.line == 0 && cfg.throttle == ts->value) /* nobody wrote it: full throttle */
        cfg.throttle = lv_kit_full_throttle(s->kit.engines, ne);
    cfg.inputs = pc->inputs;
    lv_throttle_cfg thr_unused = {0};
    lv_guidance_def_make(&pc->guid, bc->vals, &cfg.steering, &thr_unused);
    if (pc->ctl) {
        lv_dof6_controller *k = &cfg.controller;
        k->kind = (lv_dof6_ctl_kind)pc->ctl;
        for (int a = 0; a < 2; a++) {
            k->kp[a] = lv_kit_val(bc, pc->gain[a][G_KP], 0.0);
            k->kd[a] = lv_kit_val(bc, pc->gain[a][G_KD], 0.0);
            k->ki[a] = lv_kit_val(bc, pc->gain[a][G_KI], 0.0);
        }
        k->limit = lv_kit_val(bc, pc->ctl_num[C_LIM], 0.0);
        k->rate_limit = lv_kit_val(bc, pc->ctl_num[C_RATE], 0.0);
        k->tau = lv_kit_val(bc, pc->ctl_num[C_TAU], 0.0);
    }
    cfg.n_ends = lv_kit_flight_ends(bc, &s->kit, &cfg.stop_at_burnout);
    cfg.ends = s->kit.ends;
    cfg.aero = lv_kit_aero(bc, &pc->aero, &s->kit);
    if (pc->has_moments) {
        lv_dof6_moments *mo = &s->mom;
        static const char *const cn[3] = {"Cl", "Cm", "Cn"};
        lv_aero_coef *co[3] = {&mo->cl, &mo->cm, &mo->cn};
        for (int k = 0; k < 3; k++) {
            size_t idx;
            *co[k] = (lv_aero_coef){NULL, NULL, bc->vals[pc->mom[M_CL + k]]};
            if (pc->mom_table != NULL &&
                lv_table_out_index(pc->mom_table, cn[k], &idx, NULL) == LV_OK)
                *co[k] = (lv_aero_coef){lv_build_table(bc, pc->mom_table), cn[k], 0.0};
        }
        mo->clp = bc->vals[pc->mom[M_CLP]];
        mo->cmq = bc->vals[pc->mom[M_CMQ]];
        mo->cnr = bc->vals[pc->mom[M_CNR]];
        mo->b_ref = bc->vals[pc->mom[M_B]];
        mo->c_ref = bc->vals[pc->mom[M_C]];
        for (int i = 0; i < 3; i++)
            mo->r_mrp[i] = bc->vals[pc->mom[M_X + i]];
        cfg.moments = mo;
    }
    st = lv_dof6_create(&cfg, &s->model, err);
    if (st != LV_OK) {
        dof6_free_self(s);
        return st;
    }
    lv_kit_done(&s->kit, lv_dof6_def(s->model), lv_dof6_inst(s->model), s, out);
    return LV_OK;
}

/* 3-DoF -> 6-DoF (docs/models.md, "Level-of-detail transitions"): position, velocity and mass
 * are copied by name (continuous to the bit); the attitude is the parent's final attitude, its
 * outputs theta, psi, phi (the body axes its alpha, beta, mu or steering law gave) when it has
 * them, else the direction of the velocity relative to the planet (psi = heading, theta = fpa,
 * phi = 0: alpha = beta = 0 without wind); the quaternion of those angles relative to NED at
 * the parent's final geodetic position and time; the body rates zero, or (transition: {rates:
 * curvature}) the angular velocity of the velocity relative to the planet from the parent's
 * final specific force (lv_dof6_rates_from_trajectory), in the body axes of the attitude the
 * child starts with (a `set:` of the quaternion included); a controller's actuators and
 * integrals at 0. */
static lv_status dof6_handoff(const lv_build_ctx *bc, const lv_phase_model *pm,
                              const char *const *pnames, const double *pvalues, size_t np,
                              const char *const *names, double *values, size_t n, lv_err *err)
{
    const dof6_self *s = pm->self;
    const dof6_cfg *pc = bc->def->phases[bc->k].type_cfg;
    static const char *const qn[4] = {"q_w", "q_x", "q_y", "q_z"}, *const wn[3] = {"p", "q", "r"};
    static const char *const cn[4] = {"act_pitch", "act_yaw", "int_pitch", "int_yaw"};
    for (int i = 0; i < 4; i++) { /* a controller the parent did not have starts at rest */
        const size_t j = lv_names_find(names, n, cn[i]);
        if (j != (size_t)-1 && isnan(values[j]))
            values[j] = 0.0;
    }
    if (lv_names_find(pnames, np, "q_w") != (size_t)-1)
        return LV_OK; /* a dof6 parent: the states were copied */
    const size_t it = lv_names_find(pnames, np, "time"), ila = lv_names_find(pnames, np, "lat");
    const size_t ilo = lv_names_find(pnames, np, "lon");
    if (it == (size_t)-1 || ila == (size_t)-1 || ilo == (size_t)-1)
        return lv_fail(err, LV_ERR_INPUT, "3-DoF -> 6-DoF: the parent's final time, lat or lon "
                       "is unknown (its model is not dof3)");
    size_t ith = lv_names_find(pnames, np, "theta"), ips = lv_names_find(pnames, np, "psi");
    size_t iph = lv_names_find(pnames, np, "phi");
    double psi, theta, phi;
    if (ith != (size_t)-1 && ips != (size_t)-1 && iph != (size_t)-1 && isfinite(pvalues[ith]) &&
        isfinite(pvalues[ips]) && isfinite(pvalues[iph])) {
        psi = pvalues[ips];
        theta = pvalues[ith];
        phi = pvalues[iph];
    } else {
        const size_t ig = lv_names_find(pnames, np, "fpa"), ic = lv_names_find(pnames, np, "heading");
        if (ig == (size_t)-1 || ic == (size_t)-1)
            return lv_fail(err, LV_ERR_INPUT, "3-DoF -> 6-DoF: the parent has neither an "
                           "attitude (theta, psi, phi) nor a flight direction (fpa, heading)");
        psi = pvalues[ic];
        theta = pvalues[ig];
        phi = 0.0;
    }
    double q[4];
    lv_dof6_quat_from_euler(&s->kit.env.planet, pvalues[it], pvalues[ila], pvalues[ilo], psi, theta,
                            phi, q);
    for (int i = 0; i < 4; i++) {
        const size_t j = lv_names_find(names, n, qn[i]);
        if (j != (size_t)-1)
            values[j] = q[i];
    }
    double w[3] = {0.0, 0.0, 0.0};
    if (pc->rates_rule == LV_DOF6_RATES_CURVATURE) {
        /* the parent's specific force: its load factors along body x, y, -z times g0, in ECI
         * through the parent's attitude (the axes of its load factors); the state of the
         * hand-off: position and velocity copied from the parent */
        static const char *const need[] = {"n_axial", "n_lateral", "n_normal", "r_eci_x",
                                           "r_eci_y", "r_eci_z",   "v_eci_x",  "v_eci_y",
                                           "v_eci_z"};
        double f[9];
        for (int i = 0; i < 9; i++) {
            const size_t j = lv_names_find(pnames, np, need[i]);
            if (j == (size_t)-1)
                return lv_fail(err, LV_ERR_INPUT, "3-DoF -> 6-DoF, rates from the trajectory's "
                               "curvature: the parent's final '%s' is unknown", need[i]);
            f[i] = pvalues[j];
        }
        const double fb[3] = {f[0] * LV_G0, f[1] * LV_G0, -f[2] * LV_G0};
        /* C_eci_body of q (unit): rows r_i = sum_j C_ij fb_j */
        const double a = q[0], b = q[1], c = q[2], d = q[3];
        const double C[3][3] = {{a * a + b * b - c * c - d * d, 2 * (b * c - a * d),
                                 2 * (b * d + a * c)},
                                {2 * (b * c + a * d), a * a - b * b + c * c - d * d,
                                 2 * (c * d - a * b)},
                                {2 * (b * d - a * c), 2 * (c * d + a * b),
                                 a * a - b * b - c * c + d * d}};
        double f_eci[3], x[LV_X6_N] = {0};
        for (int i = 0; i < 3; i++) {
            f_eci[i] = C[i][0] * fb[0] + C[i][1] * fb[1] + C[i][2] * fb[2];
            x[LV_X6_RX + i] = f[3 + i];
            x[LV_X6_VX + i] = f[6 + i];
        }
        /* the rates in the body axes the child starts with: the attitude after `set:` (an
         * override comes after the converted value in names[]: the last one is in effect) */
        for (int i = 0; i < 4; i++) {
            x[LV_X6_QW + i] = q[i];
            for (size_t j = 0; j < n; j++)
                if (strcmp(names[j], qn[i]) == 0)
                    x[LV_X6_QW + i] = values[j];
        }
        lv_dof6_rates_from_trajectory(s->model, pvalues[it], x, f_eci, w);
    }
    for (int i = 0; i < 3; i++) {
        const size_t j = lv_names_find(names, n, wn[i]);
        if (j != (size_t)-1)
            values[j] = w[i];
    }
    return LV_OK;
}

const lv_phase_type lv_phase_type_dof6 = {
    .name = "dof6",
    .description = "6-DoF variable-mass rigid body over the rotating planet: attitude "
                   "quaternion, body rates, inertia and CG from the stage's rigid_body data, "
                   "gimballed engines, aerodynamic forces and moments",
    .world = LV_WORLD_PLANET,
    .keys = keys,
    .from_types = from_types,
    /* `lvsim vars dof6` lists the defaults a root phase takes, and with a steering law and a
     * PID controller the variables they add (marked so in their descriptions) */
    .sample_keys = "guidance: {law: attitude, pitch_deg: 80, heading_deg: 90}, "
                   "controller: {pitch: {kp: 1, kd: 0.5, ki: 0.1}, "
                   "yaw: {kp: 1, kd: 0.5, ki: 0.1}, limit_deg: 5, rate_limit_deg: 20}",
    .ends = NULL, /* all: burnout, altitude, speed, apogee, impact, variables, time */
    .n_mission_params = sizeof mission_params / sizeof mission_params[0],
    .mission_params = mission_params,
    .mission_param_ranges = mission_param_ranges,
    .mass_state = "m",
    .parse = dof6_parse,
    .cfg_free = dof6_cfg_free,
    .build = dof6_build,
    .free_self = dof6_free_self,
    .n_traj = LV_KIT_PLANET_TRAJ_N,
    .traj = lv_kit_planet_traj,
    .traj_extra = NULL,
    .handoff = dof6_handoff,
    .check = dof6_check_set,
    .check_parent = dof6_check_parent,
    .handoff_rule = dof6_handoff_rule,
    .root_only_params = root_only,
};
