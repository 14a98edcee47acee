/* flat.c - rocket stages as 6-DoF point masses over a flat world with uniform gravity (the
 * paper's test case, section 4.1): the sequential one-body model lv_flat6 and the end-to-end
 * multibody model lv_flat_e2e, over one body law (flat_body_deriv); lv_flat6 optionally in
 * air (atmosphere over z, wind, drag along -v_air: flat_air_eval). See lv_flat.h. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "lvsim/lv_flat.h"

#define FLAT_TABLE_MAX_OUT 16

/* ---- the body law ------------------------------------------------------------------------ */

/* Derivatives of one body: translation under uniform gravity g (-z) plus the vertical
 * acceleration a_thrust = F_z / m_stack; 3-2-1 Euler kinematics for constant body rates
 * (no torques on a point mass); dm/dt = -mdot. Valid for |theta| < 90 deg. */
static void flat_body_deriv(const double *x, double a_thrust, double g, double mdot, int frozen,
                            double *dx)
{
    const double phi = x[LV_FLAT_PHI], theta = x[LV_FLAT_THETA];
    const double p = x[LV_FLAT_P], q = x[LV_FLAT_Q], r = x[LV_FLAT_R];
    dx[LV_FLAT_X] = x[LV_FLAT_VX];
    dx[LV_FLAT_Y] = x[LV_FLAT_VY];
    dx[LV_FLAT_Z] = x[LV_FLAT_VZ];
    dx[LV_FLAT_VX] = 0.0;
    dx[LV_FLAT_VY] = 0.0;
    dx[LV_FLAT_VZ] = frozen ? 0.0 : a_thrust - g;
    const double sphi = sin(phi), cphi = cos(phi), ctheta = cos(theta);
    dx[LV_FLAT_PSI] = (q * sphi + r * cphi) / ctheta;
    dx[LV_FLAT_THETA] = q * cphi - r * sphi;
    dx[LV_FLAT_PHI] = p + (q * sphi + r * cphi) * tan(theta);
    dx[LV_FLAT_P] = 0.0;
    dx[LV_FLAT_Q] = 0.0;
    dx[LV_FLAT_R] = 0.0;
    dx[LV_FLAT_M] = -mdot;
}

/* ---- engines --------------------------------------------------------------------------- */

typedef struct flat_engine_rt {
    const lv_table *table;
    size_t i_thrust, i_mdot;
    lv_table_cursor cur;
    double thrust, mdot;
    int count;
} flat_engine_rt;

typedef struct flat_stage_rt {
    char *name;
    double dry_mass, prop_mass;
    size_t n_engines;
    flat_engine_rt *engines;
} flat_stage_rt;

/* Thrust and mass flow of a stage's engines at time t. Fails (and says why) when a table
 * cannot be evaluated there. */
static int stage_thrust(flat_stage_rt *s, double t, double *F, double *mdot, char *why,
                        size_t cap)
{
    double f = 0.0, md = 0.0;
    for (size_t e = 0; e < s->n_engines; e++) {
        flat_engine_rt *en = &s->engines[e];
        if (en->table != NULL) {
            double y[FLAT_TABLE_MAX_OUT];
            if (lv_table_eval1(en->table, &en->cur, t, y, NULL) != LV_OK) {
                lv_err err;
                lv_table_eval1(en->table, NULL, t, y, &err);
                snprintf(why, cap, "stage '%.60s': %.900s", s->name, err.msg);
                return -1;
            }
            f += en->count * y[en->i_thrust];
            md += en->count * y[en->i_mdot];
        } else {
            f += en->count * en->thrust;
            md += en->count * en->mdot;
        }
    }
    *F = f;
    *mdot = md;
    return 0;
}

/* "stage 'stage3' thrust table breakpoint t = 481 s" when one of the stage's engine tables
 * has a breakpoint at exactly t; "" otherwise. */
static void stage_breakpoint_name(const flat_stage_rt *s, double t, char *buf, size_t cap)
{
    buf[0] = '\0';
    for (size_t e = 0; e < s->n_engines; e++) {
        size_t n = 0;
        const double *b = s->engines[e].table ? lv_table_breakpoints(s->engines[e].table, 0, &n)
                                              : NULL;
        for (size_t i = 0; b != NULL && i < n; i++)
            if (b[i] == t) {
                snprintf(buf, cap, "stage '%.40s' thrust table breakpoint t = %.9g s", s->name, t);
                return;
            }
    }
}

static double stage_next_breakpoint(const flat_stage_rt *s, double t)
{
    double next = INFINITY;
    for (size_t e = 0; e < s->n_engines; e++)
        if (s->engines[e].table != NULL) {
            double b = lv_table_next_breakpoint(s->engines[e].table, 0, t);
            if (b < next)
                next = b;
        }
    return next;
}

static lv_status stage_copy(const lv_flat_stage *in, flat_stage_rt *out, lv_err *err)
{
    const char *nm = in->name ? in->name : "stage";
    if (!(in->dry_mass >= 0.0) || !(in->prop_mass >= 0.0) || !isfinite(in->dry_mass) ||
        !isfinite(in->prop_mass))
        return lv_fail(err, LV_ERR_INPUT,
                       "stage '%s': dry mass %g kg and propellant %g kg must be finite and >= 0",
                       nm, in->dry_mass, in->prop_mass);
    out->name = strdup(nm);
    out->dry_mass = in->dry_mass;
    out->prop_mass = in->prop_mass;
    out->n_engines = in->n_engines;
    out->engines = calloc(in->n_engines + 1, sizeof *out->engines);
    if (out->name == NULL || out->engines == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    for (size_t e = 0; e < in->n_engines; e++) {
        const lv_flat_engine *ei = &in->engines[e];
        flat_engine_rt *eo = &out->engines[e];
        eo->table = ei->table;
        eo->thrust = ei->thrust;
        eo->mdot = ei->mdot;
        eo->count = ei->count > 0 ? ei->count : 1;
        if (ei->table != NULL) {
            size_t n_out = lv_table_n_out(ei->table);
            if (lv_table_n_dims(ei->table) != 1 || n_out > FLAT_TABLE_MAX_OUT ||
                ei->thrust_out >= n_out || ei->mdot_out >= n_out)
                return lv_fail(err, LV_ERR_INPUT,
                               "stage '%s': engine table '%s' must have one axis (time), at most "
                               "%d outputs, and hold the thrust and mass-flow outputs named",
                               nm, lv_table_name(ei->table), FLAT_TABLE_MAX_OUT);
            eo->i_thrust = ei->thrust_out;
            eo->i_mdot = ei->mdot_out;
        } else if (!(ei->thrust >= 0.0) || !(ei->mdot >= 0.0) || !isfinite(ei->thrust) ||
                   !isfinite(ei->mdot)) {
            return lv_fail(err, LV_ERR_INPUT,
                           "stage '%s': engine %zu: thrust %g N and mass flow %g kg/s must be "
                           "finite and >= 0",
                           nm, e + 1, ei->thrust, ei->mdot);
        }
    }
    return LV_OK;
}

static void stage_free(flat_stage_rt *s)
{
    free(s->name);
    free(s->engines);
}

/* ---- variable lists ------------------------------------------------------------------ */

static const lv_var body_states[LV_FLAT_N] = {
    {"x", "m", "Position east of the launch point", 0.0, 1e4},
    {"y", "m", "Position north of the launch point", 0.0, 1e4},
    {"z", "m", "Altitude above the flat ground", 0.0, 1e4},
    {"vx", "m/s", "Velocity east", 0.0, 1e3},
    {"vy", "m/s", "Velocity north", 0.0, 1e3},
    {"vz", "m/s", "Velocity up", 0.0, 1e3},
    {"psi", "rad", "Heading (yaw) angle, 3-2-1 Euler, body to local NED", 0.0, 1.0},
    {"theta", "rad", "Pitch angle, 3-2-1 Euler", 0.0, 1.0},
    {"phi", "rad", "Bank (roll) angle, 3-2-1 Euler", 0.0, 1.0},
    {"p", "rad/s", "Roll rate, body x", 0.0, 1.0},
    {"q", "rad/s", "Pitch rate, body y", 0.0, 1.0},
    {"r", "rad/s", "Yaw rate, body z", 0.0, 1.0},
    {"m", "kg", "Mass of the body (all stages it carries)", 0.0, 1e3},
};

enum { PF_X, PF_Y, PF_Z, PF_VEL, PF_FPA, PF_CHI, PF_PSI, PF_THETA, PF_PHI, PF_P, PF_Q, PF_R,
       PF_G, PF_N };
static const lv_var flat_params[PF_N] = {
    {"start_x", "m", "Initial position east", 0.0, 0},
    {"start_y", "m", "Initial position north", 0.0, 0},
    {"start_z", "m", "Initial altitude", 0.0, 0},
    {"start_vel", "m/s", "Initial speed", 0.0, 0},
    {"start_fpa", "rad", "Initial flight-path angle above the x-y plane", 1.5707963267948966, 0},
    {"start_chi", "rad", "Initial heading, from north (+y) towards east (+x)", 0.0, 0},
    {"start_psi", "rad", "Initial heading angle (yaw)", 0.0, 0},
    {"start_theta", "rad", "Initial pitch angle", 0.0, 0},
    {"start_phi", "rad", "Initial bank angle", 0.0, 0},
    {"start_p", "rad/s", "Initial roll rate", 0.0, 0},
    {"start_q", "rad/s", "Initial pitch rate", 0.0, 0},
    {"start_r", "rad/s", "Initial yaw rate", 0.0, 0},
    {"g", "m/s2", "Uniform gravity acceleration along -z", 9.81, 0},
};

/* Body state from the shared parameter set (the paper's userPar). */
static void body_start(const double *p, double *x)
{
    const double v = p[PF_VEL], fpa = p[PF_FPA], chi = p[PF_CHI];
    x[LV_FLAT_X] = p[PF_X];
    x[LV_FLAT_Y] = p[PF_Y];
    x[LV_FLAT_Z] = p[PF_Z];
    x[LV_FLAT_VX] = v * cos(fpa) * sin(chi);
    x[LV_FLAT_VY] = v * cos(fpa) * cos(chi);
    x[LV_FLAT_VZ] = v * sin(fpa);
    x[LV_FLAT_PSI] = p[PF_PSI];
    x[LV_FLAT_THETA] = p[PF_THETA];
    x[LV_FLAT_PHI] = p[PF_PHI];
    x[LV_FLAT_P] = p[PF_P];
    x[LV_FLAT_Q] = p[PF_Q];
    x[LV_FLAT_R] = p[PF_R];
}

/* Its inverse: the start parameters of body state x (lv_model_def.start_params of flat6: the
 * records of a phase that starts from its parent's end). */
static void body_start_params(const double *x, double *p)
{
    const double vx = x[LV_FLAT_VX], vy = x[LV_FLAT_VY], vz = x[LV_FLAT_VZ];
    p[PF_X] = x[LV_FLAT_X];
    p[PF_Y] = x[LV_FLAT_Y];
    p[PF_Z] = x[LV_FLAT_Z];
    p[PF_VEL] = sqrt(vx * vx + vy * vy + vz * vz);
    p[PF_FPA] = atan2(vz, hypot(vx, vy));
    p[PF_CHI] = atan2(vx, vy);
    p[PF_PSI] = x[LV_FLAT_PSI];
    p[PF_THETA] = x[LV_FLAT_THETA];
    p[PF_PHI] = x[LV_FLAT_PHI];
    p[PF_P] = x[LV_FLAT_P];
    p[PF_Q] = x[LV_FLAT_Q];
    p[PF_R] = x[LV_FLAT_R];
}

static double stage_mass(const flat_stage_rt *s) { return s->dry_mass + s->prop_mass; }

/* ---- air: atmosphere, wind and drag of lv_flat6 ---------------------------------------------- */

enum { AIR_IN_MACH, AIR_IN_ALPHA, AIR_IN_BETA, AIR_IN_ALT, AIR_IN_N };

typedef struct flat_air {
    int on;                         /* an atmosphere: air data, outputs */
    const lv_atmo_model *atmo_model;
    const void *atmo_par;
    const lv_wind *wind;            /* NULL: still air */
    lv_table_cursor wind_cur;
    int drag;                       /* an aerodynamic set */
    double s_ref;                   /* m^2 */
    double cd;                      /* constant CD (cd_tab NULL) */
    const lv_table *cd_tab;         /* borrowed */
    size_t cd_k, cd_dims;           /* output index, axes */
    int cd_in[LV_TABLE_MAX_DIMS];   /* AIR_IN_* feeding each axis */
    lv_table_cursor cd_cur;
    double *cd_y;                   /* [n_out] */
} flat_air;

/* The flight condition at one state. */
typedef struct flat_air_state {
    double rho, p, a;   /* kg/m^3, Pa, m/s */
    double v_air[3];    /* m/s, air-relative velocity, x east, y north, z up */
    double speed;       /* m/s, |v_air| */
    double mach, q;     /* -, Pa */
    double cd, drag;    /* -, N */
} flat_air_state;

static void air_clear(flat_air *a)
{
    free(a->cd_y);
    memset(a, 0, sizeof *a);
}

/* Checks and resolves cfg's air (the table's axes and output once, here). */
static lv_status air_init(flat_air *a, const lv_flat6_config *cfg, lv_err *err)
{
    static const char *const in_names[AIR_IN_N] = {"mach", "alpha", "beta", "altitude"};
    memset(a, 0, sizeof *a);
    if (cfg->atmo == NULL) {
        if (cfg->wind != NULL || cfg->aero != NULL)
            return lv_fail(err, LV_ERR_INPUT, "flat6: a wind or an aerodynamic set needs an "
                           "atmosphere (cfg.atmo)");
        return LV_OK;
    }
    a->on = 1;
    a->atmo_model = lv_atmo_model_of(cfg->atmo);
    a->atmo_par = lv_atmo_par(cfg->atmo);
    a->wind = cfg->wind;
    const lv_aero_config *ac = cfg->aero;
    if (ac == NULL)
        return LV_OK;
    const char *cn = ac->axes == LV_AERO_BODY ? "CA" : "CD";
    if (ac->axes != LV_AERO_WIND && ac->axes != LV_AERO_BODY)
        return lv_fail(err, LV_ERR_INPUT, "flat6: aerodynamics: axes = %d", (int)ac->axes);
    if (!(ac->s_ref > 0.0) || !isfinite(ac->s_ref))
        return lv_fail(err, LV_ERR_INPUT, "flat6: aerodynamics: s_ref = %g m^2 (must be > 0)",
                       ac->s_ref);
    for (int i = 1; i < 3; i++)
        if (ac->coef[i].table != NULL || ac->coef[i].value != 0.0)
            return lv_fail(err, LV_ERR_INPUT, "flat6: aerodynamics: %s must be 0: the flat "
                           "world's body flies at zero angle of attack, drag only (no lift or "
                           "side force)", ac->axes == LV_AERO_BODY ? (i == 1 ? "CN" : "CY")
                                                                   : (i == 1 ? "CL" : "CY"));
    a->drag = 1;
    a->s_ref = ac->s_ref;
    const lv_aero_coef *k = &ac->coef[0];
    if (k->table == NULL) {
        if (!isfinite(k->value))
            return lv_fail(err, LV_ERR_INPUT, "flat6: aerodynamics %s = %g", cn, k->value);
        a->cd = k->value;
        return LV_OK;
    }
    const lv_table *t = k->table;
    a->cd_tab = t;
    a->cd_dims = lv_table_n_dims(t);
    int used[AIR_IN_N] = {0};
    for (size_t d = 0; d < a->cd_dims; d++) {
        const char *ax = lv_table_axis_name(t, d);
        int in = -1;
        for (int j = 0; j < AIR_IN_N; j++)
            if (strcmp(ax, in_names[j]) == 0)
                in = j;
        if (in < 0 || used[in]++)
            return lv_fail(err, LV_ERR_INPUT, "flat6: aerodynamics %s: table '%s': axis %zu is "
                           "'%s'; an aerodynamic table's axes are 'mach', 'alpha', 'beta', "
                           "'altitude', each at most once", cn, lv_table_name(t), d, ax);
        a->cd_in[d] = in;
    }
    const char *out = k->output;
    lv_status st = LV_OK;
    if (out == NULL && lv_table_n_out(t) == 1)
        a->cd_k = 0;
    else if ((st = lv_table_out_index(t, out != NULL ? out : cn, &a->cd_k, err)) != LV_OK)
        return lv_fail_prefix(err, st, "flat6: aerodynamics %s: table '%s'", cn,
                              lv_table_name(t));
    if ((a->cd_y = malloc(lv_table_n_out(t) * sizeof *a->cd_y)) == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    return LV_OK;
}

/* Air data at body state x (time t): atmosphere at the altitude z (vacuum above the
 * models' top, with the top's speed of sound), wind, v_air, Mach, q and the drag. Returns 0;
 * 1 (state not acceptable: below the atmosphere's floor or outside a table atmosphere, as the
 * 3-DoF model); or -1 (stop: the wind or the drag table evaluated outside its range under
 * extrap: error, as an engine table), with the reason in why. */
static int flat_air_eval(flat_air *a, double t, const double *x, flat_air_state *o, char *why,
                         size_t cap)
{
    lv_err err;
    memset(o, 0, sizeof *o);
    o->a = 1.0;
    const double h = x[LV_FLAT_Z];
    if (!(h >= LV_ATMO_ALT_MIN)) {
        snprintf(why, cap, "altitude z = %g m below the atmosphere (%g m) at t = %.9g s", h,
                 LV_ATMO_ALT_MIN, t);
        return 1;
    }
    lv_atmo_state as;
    const double ha = h < LV_ATMO_ALT_MAX ? h : LV_ATMO_ALT_MAX;
    if (a->atmo_model->eval(a->atmo_par, ha, &as, NULL) != LV_OK) {
        a->atmo_model->eval(a->atmo_par, ha, &as, &err);
        snprintf(why, cap, "at t = %.9g s: %.900s", t, err.msg);
        return 1;
    }
    o->a = as.a;
    if (h <= LV_ATMO_ALT_MAX) {
        o->rho = as.rho;
        o->p = as.p;
    }
    o->v_air[0] = x[LV_FLAT_VX];
    o->v_air[1] = x[LV_FLAT_VY];
    o->v_air[2] = x[LV_FLAT_VZ];
    if (a->wind != NULL) {
        double w[3];
        if (lv_wind_eval_at(a->wind, &a->wind_cur, t, h, w, NULL) != LV_OK) {
            lv_wind_eval_at(a->wind, NULL, t, h, w, &err);
            snprintf(why, cap, "at t = %.9g s: %.900s", t, err.msg);
            return isnan(h) ? 1 : -1;
        }
        o->v_air[0] -= w[1]; /* NED to x east, y north, z up */
        o->v_air[1] -= w[0];
        o->v_air[2] += w[2];
    }
    o->speed = sqrt(o->v_air[0] * o->v_air[0] + o->v_air[1] * o->v_air[1] +
                    o->v_air[2] * o->v_air[2]);
    o->mach = o->speed / o->a;
    o->q = 0.5 * o->rho * o->speed * o->speed;
    if (!a->drag)
        return 0;
    o->cd = a->cd;
    if (a->cd_tab != NULL) {
        const double in[AIR_IN_N] = {o->mach, 0.0, 0.0, h};
        double xin[LV_TABLE_MAX_DIMS];
        for (size_t d = 0; d < a->cd_dims; d++)
            xin[d] = in[a->cd_in[d]];
        if (lv_table_eval(a->cd_tab, &a->cd_cur, xin, a->cd_y, NULL) != LV_OK) {
            lv_table_eval(a->cd_tab, NULL, xin, a->cd_y, &err);
            snprintf(why, cap, "at t = %.9g s: aerodynamics: %.900s", t, err.msg);
            return isnan(o->mach) ? 1 : -1;
        }
        o->cd = a->cd_y[a->cd_k];
    }
    o->drag = o->q * a->s_ref * o->cd;
    return 0;
}

/* The drag's acceleration, -D/m v_air/|v_air| (zero at zero air speed). */
static void drag_accel(const flat_air_state *o, double m, double acc[3])
{
    const double k = o->speed > 0.0 ? o->drag / (m * o->speed) : 0.0;
    for (int i = 0; i < 3; i++)
        acc[i] = -k * o->v_air[i];
}

/* ---- lv_flat6: one body, sequential approach ---------------------------------------------- */

enum { OF_THRUST, OF_MDOT, OF_SPEED, OF_ACCEL, OF_BURNING, OF_PROP, OF_N,
       OF_MACH = OF_N, OF_Q, OF_RHO, OF_P, OF_VAIR, OF_DRAG, OF_N_AIR };
static const lv_var flat6_outputs[OF_N_AIR] = {
    {"thrust", "N", "Thrust of the burning stage, along +z", 0, 0},
    {"mdot", "kg/s", "Propellant mass flow", 0, 0},
    {"speed", "m/s", "Speed |v|", 0, 0},
    {"accel", "m/s2", "Vertical acceleration dvz/dt", 0, 0},
    {"burning", "1", "1 while the bottom stage burns", 0, 0},
    {"propellant", "kg", "Propellant left in the bottom stage", 0, 0},
    /* with an atmosphere: */
    {"mach", "1", "Mach number of the air-relative velocity", 0, 0},
    {"q_dyn", "Pa", "Dynamic pressure rho |v_air|^2 / 2", 0, 0},
    {"rho", "kg/m3", "Air density at the altitude z", 0, 0},
    {"p_amb", "Pa", "Ambient pressure at the altitude z", 0, 0},
    {"v_air", "m/s", "Air-relative speed |v - v_wind|", 0, 0},
    {"drag", "N", "Drag q S_ref CD, along -v_air", 0, 0},
};

struct lv_flat6 {
    lv_model_def def;
    char *name;
    lv_var states[LV_FLAT_N];
    lv_var params[PF_N];      /* g defaults to the configuration's */
    lv_event_def *events; /* [1 + n_ends] */
    char (*event_names)[32]; /* [n_ends] "altitude", a second one "altitude_2" */
    lv_flat_end *ends;
    size_t n_ends;
    size_t n_stages;
    flat_stage_rt *stages;
    flat_air air;
    /* mode */
    int burning;
    double m_burnout; /* kg: the mass at which the bottom stage's propellant is gone */
    char why[LV_ERR_MSG_MAX];
    char tev[LV_EVENT_NAME_MAX]; /* the name of the latest time event */
};

static int flat6_thrust(lv_flat6 *s, double t, double *F, double *mdot)
{
    if (!s->burning) {
        *F = *mdot = 0.0;
        return 0;
    }
    return stage_thrust(&s->stages[0], t, F, mdot, s->why, sizeof s->why);
}

static int flat6_rhs(double t, const double *x, const double *p, double *dx, void *inst)
{
    lv_flat6 *s = inst;
    const double m = x[LV_FLAT_M];
    if (!(m > 0.0))
        return 1;
    double F, mdot;
    if (flat6_thrust(s, t, &F, &mdot) != 0)
        return -1;
    flat_body_deriv(x, F / m, p[PF_G], mdot, 0, dx);
    if (s->air.on) { /* the drag adds to thrust and gravity */
        flat_air_state as;
        double acc[3];
        const int rc = flat_air_eval(&s->air, t, x, &as, s->why, sizeof s->why);
        if (rc != 0)
            return rc;
        drag_accel(&as, m, acc);
        dx[LV_FLAT_VX] += acc[0];
        dx[LV_FLAT_VY] += acc[1];
        dx[LV_FLAT_VZ] += acc[2];
    }
    return 0;
}

static int flat6_start(const double *p, double *x, void *inst)
{
    (void)inst;
    body_start(p, x);
    return 0;
}

static int flat6_start_params(double t0, const double *x, double *p, void *inst)
{
    (void)t0, (void)inst;
    body_start_params(x, p);
    return 0;
}

static int flat6_init(double t0, const double *x, const double *p, void *inst)
{
    (void)t0;
    (void)p;
    lv_flat6 *s = inst;
    s->why[0] = '\0';
    /* below an impact end's level (beyond a parent's located impact, 1 mm) the body would start
     * under the ground it is to hit and never cross it */
    for (size_t k = 0; k < s->n_ends; k++)
        if (s->ends[k].kind == LV_FLAT_END_IMPACT && x[LV_FLAT_Z] < s->ends[k].value - 1e-3) {
            snprintf(s->why, sizeof s->why, "the start altitude z = %.9g m is below the level "
                     "%g m of its end '%s': the body would start under the ground it is to hit, "
                     "and never cross it (start higher, or give the ground's level: {impact: "
                     "%.6g})", x[LV_FLAT_Z], s->ends[k].value, s->event_names[k], x[LV_FLAT_Z]);
            return 1;
        }
    s->m_burnout = x[LV_FLAT_M] - s->stages[0].prop_mass;
    s->burning = s->stages[0].prop_mass > 0.0 && s->stages[0].n_engines > 0;
    for (size_t e = 0; e < s->stages[0].n_engines; e++)
        s->stages[0].engines[e].cur = (lv_table_cursor)LV_TABLE_CURSOR_INIT;
    s->air.wind_cur = (lv_table_cursor)LV_TABLE_CURSOR_INIT;
    s->air.cd_cur = (lv_table_cursor)LV_TABLE_CURSOR_INIT;
    return 0;
}

static int flat6_g(double t, const double *x, const double *p, double *g, void *inst)
{
    (void)t;
    (void)p;
    const lv_flat6 *s = inst;
    g[0] = s->burning ? x[LV_FLAT_M] - s->m_burnout : 1.0; /* disarmed after cut-off */
    const double speed = sqrt(x[LV_FLAT_VX] * x[LV_FLAT_VX] + x[LV_FLAT_VY] * x[LV_FLAT_VY] +
                              x[LV_FLAT_VZ] * x[LV_FLAT_VZ]);
    for (size_t k = 0; k < s->n_ends; k++) {
        const lv_flat_end *e = &s->ends[k];
        double v = 1.0;
        switch (e->kind) {
        case LV_FLAT_END_BURNOUT: v = g[0]; break;
        case LV_FLAT_END_ALTITUDE: v = x[LV_FLAT_Z] - e->value; break;
        case LV_FLAT_END_SPEED: v = speed - e->value; break;
        case LV_FLAT_END_APOGEE: v = x[LV_FLAT_VZ]; break;
        case LV_FLAT_END_IMPACT: v = x[LV_FLAT_Z] - e->value; break;
        }
        g[1 + k] = v;
    }
    return 0;
}

/* The model's domain: above the flat ground, with a margin of 5 km so that a start on the
 * ground is inside (a root of z exactly at the start would not be seen as a crossing). */
static const lv_domain_def flat6_domain[] = {
    {"z", "m", -5000.0,
     "the vehicle is under the flat ground (5 km below it); an `impact` end ends the phase on "
     "the ground",
     0},
};

static int flat6_domain_q(double t, const double *x, const double *p, double *q, void *inst)
{
    (void)t;
    (void)p;
    (void)inst;
    q[0] = x[LV_FLAT_Z];
    return 0;
}

static lv_event_action flat6_event(double t, double *x, const double *p, const int *fired,
                                   void *inst)
{
    (void)t;
    (void)x;
    (void)p;
    lv_flat6 *s = inst;
    lv_event_action action = LV_EVENT_CONTINUE;
    if (fired[0] && s->burning) {
        s->burning = 0; /* cut-off: thrust and mass flow stop */
        action = LV_EVENT_RESTART;
    }
    for (size_t k = 0; k < s->n_ends; k++)
        if (fired[1 + k])
            action = LV_EVENT_STOP;
    return action;
}

static double flat6_next_time_event(double t, const double *p, void *inst)
{
    (void)p;
    const lv_flat6 *s = inst;
    return s->burning ? stage_next_breakpoint(&s->stages[0], t) : INFINITY;
}

static const char *flat6_time_event_name(double t, const double *p, void *inst)
{
    (void)p;
    lv_flat6 *s = inst;
    stage_breakpoint_name(&s->stages[0], t, s->tev, sizeof s->tev);
    return s->tev;
}

static int flat6_outputs_fn(double t, const double *x, const double *p, double *y, void *inst)
{
    lv_flat6 *s = inst;
    double F, mdot;
    if (flat6_thrust(s, t, &F, &mdot) != 0)
        return -1;
    y[OF_THRUST] = F;
    y[OF_MDOT] = mdot;
    y[OF_SPEED] = sqrt(x[LV_FLAT_VX] * x[LV_FLAT_VX] + x[LV_FLAT_VY] * x[LV_FLAT_VY] +
                       x[LV_FLAT_VZ] * x[LV_FLAT_VZ]);
    y[OF_ACCEL] = F / x[LV_FLAT_M] - p[PF_G];
    y[OF_BURNING] = s->burning;
    y[OF_PROP] = s->burning ? x[LV_FLAT_M] - s->m_burnout : 0.0;
    if (s->air.on) {
        flat_air_state as;
        double acc[3];
        if (flat_air_eval(&s->air, t, x, &as, s->why, sizeof s->why) != 0)
            return -1;
        drag_accel(&as, x[LV_FLAT_M], acc);
        y[OF_ACCEL] += acc[2];
        y[OF_MACH] = as.mach;
        y[OF_Q] = as.q;
        y[OF_RHO] = as.rho;
        y[OF_P] = as.p;
        y[OF_VAIR] = as.speed;
        y[OF_DRAG] = as.drag;
    }
    return 0;
}

static const char *flat6_last_error(const void *inst)
{
    const lv_flat6 *s = inst;
    return s->why[0] ? s->why : NULL;
}

static const char *const end_names[] = {"burnout", "altitude", "speed", "apogee", "impact"};

void lv_flat6_free(lv_flat6 *m)
{
    if (m == NULL)
        return;
    for (size_t i = 0; i < m->n_stages; i++)
        stage_free(&m->stages[i]);
    air_clear(&m->air);
    free(m->stages);
    free(m->events);
    free(m->event_names);
    free(m->ends);
    free(m->name);
    free(m);
}

lv_status lv_flat6_create(const lv_flat6_config *cfg, lv_flat6 **out, lv_err *err)
{
    *out = NULL;
    lv_status st = LV_OK;
    if (cfg->n_stages == 0 || cfg->stages == NULL)
        return lv_fail(err, LV_ERR_INPUT, "flat6: a body needs at least one stage");
    if (!(cfg->g > 0.0) || !isfinite(cfg->g))
        return lv_fail(err, LV_ERR_INPUT, "flat6: gravity g = %g m/s^2 must be > 0", cfg->g);
    lv_flat6 *m = calloc(1, sizeof *m);
    if (m == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    m->name = strdup(cfg->name ? cfg->name : "flat6");
    m->stages = calloc(cfg->n_stages, sizeof *m->stages);
    m->events = calloc(1 + cfg->n_ends, sizeof *m->events);
    m->ends = calloc(cfg->n_ends + 1, sizeof *m->ends);
    m->event_names = calloc(cfg->n_ends + 1, sizeof *m->event_names);
    if (!m->name || !m->stages || !m->events || !m->ends || !m->event_names) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto fail;
    }
    double mass = 0.0;
    for (size_t i = 0; i < cfg->n_stages; i++) {
        m->n_stages = i + 1;
        if ((st = stage_copy(&cfg->stages[i], &m->stages[i], err)) != LV_OK)
            goto fail;
        mass += stage_mass(&m->stages[i]);
    }
    if (!(mass > 0.0)) {
        st = lv_fail(err, LV_ERR_INPUT, "flat6: the body's mass is %g kg (must be > 0)", mass);
        goto fail;
    }
    if ((st = air_init(&m->air, cfg, err)) != LV_OK)
        goto fail;
    memcpy(m->states, body_states, sizeof body_states);
    m->states[LV_FLAT_M].start = mass;
    memcpy(m->params, flat_params, sizeof flat_params);
    m->params[PF_G].start = cfg->g;
    m->events[0] = (lv_event_def){"burnout", "Bottom stage's propellant exhausted: engines stop",
                                  LV_DIR_FALLING, 0};
    m->n_ends = cfg->n_ends;
    for (size_t k = 0; k < cfg->n_ends; k++) {
        lv_flat_end e = cfg->ends[k];
        if ((int)e.kind < 0 || e.kind > LV_FLAT_END_IMPACT || !isfinite(e.value)) {
            st = lv_fail(err, LV_ERR_INPUT, "flat6: end condition %zu is invalid", k + 1);
            goto fail;
        }
        if (e.kind == LV_FLAT_END_APOGEE || e.kind == LV_FLAT_END_IMPACT ||
            e.kind == LV_FLAT_END_BURNOUT)
            e.direction = LV_DIR_FALLING;
        m->ends[k] = e;
        size_t same = 0; /* a second end of a kind is "<kind>_2", as its parameter */
        for (size_t j = 0; j < k; j++)
            same += cfg->ends[j].kind == e.kind;
        if (same > 0)
            snprintf(m->event_names[k], sizeof m->event_names[0], "%s_%zu", end_names[e.kind],
                     same + 1);
        else
            snprintf(m->event_names[k], sizeof m->event_names[0], "%s", end_names[e.kind]);
        m->events[1 + k] = (lv_event_def){m->event_names[k], "Ends the phase", e.direction, 1};
    }
    m->def = (lv_model_def){
        .name = m->name,
        .description = "point mass with the paper's 13 states (attitude at constant rates, no moments) carrying a stack of stages over a flat world",
        .n_states = LV_FLAT_N,
        .n_params = PF_N,
        .n_outputs = m->air.on ? OF_N_AIR : OF_N,
        .n_events = 1 + cfg->n_ends,
        .states = m->states,
        .params = m->params,
        .outputs = flat6_outputs,
        .events = m->events,
        .start = flat6_start,
        .start_params = flat6_start_params,
        .init = flat6_init,
        .rhs = flat6_rhs,
        .event_g = flat6_g,
        .on_event = flat6_event,
        .next_time_event = flat6_next_time_event,
        .outputs_fn = flat6_outputs_fn,
        .last_error = flat6_last_error,
        .n_domain = 1,
        .domain = flat6_domain,
        .domain_q = flat6_domain_q,
        .time_event_name = flat6_time_event_name,
    };
    *out = m;
    return LV_OK;
fail:
    lv_flat6_free(m);
    return st;
}

const lv_model_def *lv_flat6_def(const lv_flat6 *m) { return &m->def; }
void *lv_flat6_inst(lv_flat6 *m) { return m; }

/* ---- lv_flat_e2e: all bodies, end-to-end approach ------------------------------------------ */

struct lv_flat_e2e {
    lv_model_def def;
    char *name;
    size_t n;             /* bodies */
    flat_stage_rt *bodies;
    lv_var *states;       /* [13 n] */
    lv_var *params;       /* [PF_N + n - 1] */
    lv_var *outputs;      /* [n] */
    lv_event_def *events; /* [2 n]: burnout_k, impact_k */
    char **strings;       /* owned names and descriptions */
    size_t n_strings;
    /* mode */
    int *connected;       /* [n - 1]: body k attached to body k+1 */
    int *burning;         /* [n] */
    int *landed;          /* [n] */
    double *F, *mdot;     /* [n] scratch: thrust of each body's engines */
    char why[LV_ERR_MSG_MAX];
    char tev[LV_EVENT_NAME_MAX]; /* the name of the latest time event */
};

static char *e2e_str(lv_flat_e2e *m, const char *fmt, ...) LV_PRINTF(2, 3);
static char *e2e_str(lv_flat_e2e *m, const char *fmt, ...)
{
    char buf[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    char *s = strdup(buf);
    if (s != NULL)
        m->strings[m->n_strings++] = s;
    return s;
}

/* Groups of connected bodies: body k is the bottom of a group when k == 0 or it is no
 * longer attached to body k-1. */
static int e2e_is_bottom(const lv_flat_e2e *m, size_t k)
{
    return k == 0 || !m->connected[k - 1];
}

static int e2e_rhs(double t, const double *x, const double *p, double *dx, void *inst)
{
    lv_flat_e2e *m = inst;
    for (size_t k = 0; k < m->n; k++) {
        if (!(x[k * LV_FLAT_N + LV_FLAT_M] > 0.0))
            return 1;
        m->F[k] = m->mdot[k] = 0.0;
        if (m->burning[k] &&
            stage_thrust(&m->bodies[k], t, &m->F[k], &m->mdot[k], m->why, sizeof m->why) != 0)
            return -1;
    }
    /* Each group moves as one rigid stack: a = (sum F) / (sum m) - g for every member. */
    size_t k = 0;
    while (k < m->n) {
        size_t j = k;
        double F = m->F[k], M = x[k * LV_FLAT_N + LV_FLAT_M];
        while (j + 1 < m->n && m->connected[j]) {
            j++;
            F += m->F[j];
            M += x[j * LV_FLAT_N + LV_FLAT_M];
        }
        for (size_t b = k; b <= j; b++)
            flat_body_deriv(x + b * LV_FLAT_N, F / M, p[PF_G], m->mdot[b], m->landed[k],
                            dx + b * LV_FLAT_N);
        k = j + 1;
    }
    return 0;
}

static int e2e_start(const double *p, double *x, void *inst)
{
    const lv_flat_e2e *m = inst;
    for (size_t k = 0; k < m->n; k++)
        body_start(p, x + k * LV_FLAT_N);
    return 0;
}

static int e2e_init(double t0, const double *x, const double *p, void *inst)
{
    lv_flat_e2e *m = inst;
    for (size_t k = 0; k + 1 < m->n; k++)
        m->connected[k] = t0 < p[PF_N + k];
    for (size_t k = 0; k < m->n; k++) {
        m->landed[k] = 0;
        m->burning[k] = e2e_is_bottom(m, k) && m->bodies[k].n_engines > 0 &&
                        x[k * LV_FLAT_N + LV_FLAT_M] > m->bodies[k].dry_mass;
        for (size_t e = 0; e < m->bodies[k].n_engines; e++)
            m->bodies[k].engines[e].cur = (lv_table_cursor)LV_TABLE_CURSOR_INIT;
    }
    return 0;
}

static int e2e_g(double t, const double *x, const double *p, double *g, void *inst)
{
    (void)t;
    (void)p;
    const lv_flat_e2e *m = inst;
    for (size_t k = 0; k < m->n; k++) {
        const double *xb = x + k * LV_FLAT_N;
        g[2 * k] = m->burning[k] ? xb[LV_FLAT_M] - m->bodies[k].dry_mass : 1.0;
        g[2 * k + 1] = m->landed[k] ? 1.0 : xb[LV_FLAT_Z];
    }
    return 0;
}

static lv_event_action e2e_event(double t, double *x, const double *p, const int *fired,
                                 void *inst)
{
    (void)t;
    (void)p;
    lv_flat_e2e *m = inst;
    lv_event_action action = LV_EVENT_CONTINUE;
    for (size_t k = 0; k < m->n; k++) {
        if (fired[2 * k] && m->burning[k]) {
            m->burning[k] = 0;
            action = LV_EVENT_RESTART;
        }
        if (fired[2 * k + 1] && !m->landed[k]) {
            /* on the ground: the body and whatever is attached to it stay there */
            m->landed[k] = 1;
            m->burning[k] = 0;
            for (size_t b = k; b < m->n; b++) {
                if (b > k && !m->connected[b - 1])
                    break;
                double *xb = x + b * LV_FLAT_N;
                xb[LV_FLAT_VX] = xb[LV_FLAT_VY] = xb[LV_FLAT_VZ] = 0.0;
            }
            action = LV_EVENT_RESTART;
        }
    }
    return action;
}

static double e2e_next_time_event(double t, const double *p, void *inst)
{
    const lv_flat_e2e *m = inst;
    double next = INFINITY;
    for (size_t k = 0; k + 1 < m->n; k++)
        if (m->connected[k] && p[PF_N + k] > t && p[PF_N + k] < next)
            next = p[PF_N + k];
    for (size_t k = 0; k < m->n; k++)
        if (m->burning[k]) {
            double b = stage_next_breakpoint(&m->bodies[k], t);
            if (b < next)
                next = b;
        }
    return next;
}

static lv_event_action e2e_time_event(double t, double *x, const double *p, void *inst)
{
    lv_flat_e2e *m = inst;
    for (size_t k = 0; k + 1 < m->n; k++) {
        if (m->connected[k] && p[PF_N + k] == t) {
            m->connected[k] = 0; /* separation: body k+1 is now the bottom of its group */
            const size_t b = k + 1;
            m->burning[b] = m->bodies[b].n_engines > 0 &&
                            x[b * LV_FLAT_N + LV_FLAT_M] > m->bodies[b].dry_mass;
        }
    }
    return LV_EVENT_RESTART; /* a separation or a table kink: restart the integrator */
}

/* The commanded separations at t, else a burning body's thrust-table breakpoint. */
static const char *e2e_time_event_name(double t, const double *p, void *inst)
{
    lv_flat_e2e *m = inst;
    size_t len = 0;
    m->tev[0] = '\0';
    for (size_t k = 0; k + 1 < m->n && len < sizeof m->tev; k++)
        if (m->connected[k] && p[PF_N + k] == t)
            len += (size_t)snprintf(m->tev + len, sizeof m->tev - len, "%sseparation of '%.32s'",
                                    len ? "; " : "", m->bodies[k + 1].name);
    for (size_t k = 0; k < m->n && len == 0; k++)
        if (m->burning[k])
            stage_breakpoint_name(&m->bodies[k], t, m->tev, sizeof m->tev), len = strlen(m->tev);
    return m->tev;
}

static int e2e_outputs_fn(double t, const double *x, const double *p, double *y, void *inst)
{
    (void)x;
    (void)p;
    lv_flat_e2e *m = inst;
    for (size_t k = 0; k < m->n; k++) {
        double F = 0.0, md = 0.0;
        if (m->burning[k] &&
            stage_thrust(&m->bodies[k], t, &F, &md, m->why, sizeof m->why) != 0)
            return -1;
        y[k] = F;
    }
    return 0;
}

static const char *e2e_last_error(const void *inst)
{
    const lv_flat_e2e *m = inst;
    return m->why[0] ? m->why : NULL;
}

void lv_flat_e2e_free(lv_flat_e2e *m)
{
    if (m == NULL)
        return;
    for (size_t k = 0; m->bodies && k < m->n; k++)
        stage_free(&m->bodies[k]);
    for (size_t i = 0; i < m->n_strings; i++)
        free(m->strings[i]);
    free(m->strings);
    free(m->bodies);
    free(m->states);
    free(m->params);
    free(m->outputs);
    free(m->events);
    free(m->connected);
    free(m->burning);
    free(m->landed);
    free(m->F);
    free(m->mdot);
    free(m->name);
    free(m);
}

lv_status lv_flat_e2e_create(const lv_flat_e2e_config *cfg, lv_flat_e2e **out, lv_err *err)
{
    *out = NULL;
    lv_status st = LV_OK;
    const size_t n = cfg->n_bodies;
    if (n == 0 || cfg->bodies == NULL)
        return lv_fail(err, LV_ERR_INPUT, "flat_e2e: needs at least one body");
    if (!(cfg->g > 0.0) || !isfinite(cfg->g))
        return lv_fail(err, LV_ERR_INPUT, "flat_e2e: gravity g = %g m/s^2 must be > 0", cfg->g);
    if (n > 1 && cfg->t_sep == NULL)
        return lv_fail(err, LV_ERR_INPUT, "flat_e2e: %zu bodies need %zu separation times", n,
                       n - 1);
    lv_flat_e2e *m = calloc(1, sizeof *m);
    if (m == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    m->n = n;
    m->name = strdup(cfg->name ? cfg->name : "flat_e2e");
    m->bodies = calloc(n, sizeof *m->bodies);
    m->states = calloc(n * LV_FLAT_N, sizeof *m->states);
    m->params = calloc(PF_N + n, sizeof *m->params);
    m->outputs = calloc(n, sizeof *m->outputs);
    m->events = calloc(2 * n, sizeof *m->events);
    m->strings = calloc(4 * n * LV_FLAT_N + 8 * n + 8, sizeof *m->strings);
    m->connected = calloc(n, sizeof *m->connected);
    m->burning = calloc(n, sizeof *m->burning);
    m->landed = calloc(n, sizeof *m->landed);
    m->F = calloc(n, sizeof *m->F);
    m->mdot = calloc(n, sizeof *m->mdot);
    if (!m->name || !m->bodies || !m->states || !m->params || !m->outputs || !m->events ||
        !m->strings || !m->connected || !m->burning || !m->landed || !m->F || !m->mdot) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto fail;
    }
    memcpy(m->params, flat_params, sizeof flat_params);
    for (size_t k = 0; k < n; k++) {
        if ((st = stage_copy(&cfg->bodies[k], &m->bodies[k], err)) != LV_OK)
            goto fail;
        const char *bn = m->bodies[k].name;
        for (size_t i = 0; i < LV_FLAT_N; i++) {
            lv_var v = body_states[i];
            v.name = e2e_str(m, "%s.%s", bn, body_states[i].name);
            v.description = e2e_str(m, "%s: %s", bn, body_states[i].description);
            if (v.name == NULL || v.description == NULL) {
                st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
                goto fail;
            }
            m->states[k * LV_FLAT_N + i] = v;
        }
        m->states[k * LV_FLAT_N + LV_FLAT_M].start = stage_mass(&m->bodies[k]);
        m->outputs[k] = (lv_var){e2e_str(m, "%s.thrust", bn), "N",
                                 e2e_str(m, "%s: thrust of its engines", bn), 0, 0};
        m->events[2 * k] = (lv_event_def){e2e_str(m, "%s.burnout", bn),
                                          "Stage propellant exhausted", LV_DIR_FALLING, 0};
        m->events[2 * k + 1] = (lv_event_def){e2e_str(m, "%s.impact", bn),
                                              "Body reaches the ground", LV_DIR_FALLING, 0};
        if (k + 1 < n) {
            if (!isfinite(cfg->t_sep[k])) {
                st = lv_fail(err, LV_ERR_INPUT, "flat_e2e: separation time %zu is %g", k + 1,
                             cfg->t_sep[k]);
                goto fail;
            }
            m->params[PF_N + k] =
                (lv_var){e2e_str(m, "t_sep%zu", k + 1), "s",
                         e2e_str(m, "Separation of %s from the stage above", bn), cfg->t_sep[k],
                         0};
        }
        if (!m->outputs[k].name || !m->events[2 * k].name || !m->events[2 * k + 1].name ||
            (k + 1 < n && !m->params[PF_N + k].name)) {
            st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
            goto fail;
        }
    }
    m->params[PF_G].start = cfg->g;
    m->def = (lv_model_def){
        .name = m->name,
        .description = "End-to-end: every stage a point mass with attitude kinematics, joined until separation",
        .n_states = n * LV_FLAT_N,
        .n_params = PF_N + n - 1,
        .n_outputs = n,
        .n_events = 2 * n,
        .states = m->states,
        .params = m->params,
        .outputs = m->outputs,
        .events = m->events,
        .start = e2e_start,
        .init = e2e_init,
        .rhs = e2e_rhs,
        .event_g = e2e_g,
        .on_event = e2e_event,
        .next_time_event = e2e_next_time_event,
        .on_time_event = e2e_time_event,
        .outputs_fn = e2e_outputs_fn,
        .last_error = e2e_last_error,
        .time_event_name = e2e_time_event_name,
    };
    *out = m;
    return LV_OK;
fail:
    lv_flat_e2e_free(m);
    return st;
}

const lv_model_def *lv_flat_e2e_def(const lv_flat_e2e *m) { return &m->def; }
void *lv_flat_e2e_inst(lv_flat_e2e *m) { return m; }
