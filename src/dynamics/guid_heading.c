/* guid_heading.c - steering law `heading`: bank to turn toward the target (lv_steering
 * target_lat/lon): mu = clamp(gain (bearing - chi_air), +-bank_max), alpha = `alpha` or from
 * `alpha_table` over Mach (output "alpha"), beta 0; with n_max > 0, alpha is scaled down
 * smoothly so that the lift load factor L / (m g0) stays below n_max; with q_max > 0 that
 * limit yields as the dynamic pressure rises to q_max (lv_guid_heading_alpha; 3-DoF phases).
 * Needs an aerodynamic dataset. Equations: docs/guidance.md, "The heading law's limits".
 */
#include "core/table_unit.h"
#include "dynamics/guid_kit.h"

typedef struct heading_par {
    double bank_max;            /* rad, in (0, pi/2] */
    double gain;                /* bank per heading error, rad/rad */
    double n_max;               /* lift load-factor limit [g0]; 0: none */
    double q_max;               /* Pa, with n_max: the limit yields up to q_max; 0: none */
    double alpha;               /* rad, without alpha_table */
    const lv_table *alpha_table; /* 1 axis "mach", output "alpha" [rad], or NULL */
    int k_alpha;                /* init: the table's output "alpha" */
} heading_par;

static const lv_law_key keys[] = {
    {.name = "bank_max", .type = LV_KEY_NUMBER, .unit = "rad", .lo = 0.0, .hi = 0.5 * LV_PI,
     .lo_open = 1, .dflt = 45.0 * LV_DEG, .flags = LV_KEY_ANGLE,
     .offset = offsetof(heading_par, bank_max), .description = "largest bank angle"},
    {.name = "gain", .type = LV_KEY_NUMBER, .unit = "1", .lo = 0.0, .hi = 100.0, .lo_open = 1,
     .dflt = 1.0, .offset = offsetof(heading_par, gain),
     .description = "bank per heading error (rad/rad)"},
    {.name = "n_max", .type = LV_KEY_NUMBER, .unit = "1", .lo = 0.0, .hi = HUGE_VAL,
     .dflt = 0.0, .flags = LV_KEY_DOF3, .offset = offsetof(heading_par, n_max),
     .description = "lift load-factor limit L / (m g0), a soft saturation of alpha; 0: none"},
    {.name = "q_max", .type = LV_KEY_NUMBER, .unit = "Pa", .lo = 0.0, .hi = HUGE_VAL,
     .dflt = 0.0, .flags = LV_KEY_DOF3, .offset = offsetof(heading_par, q_max),
     .description = "dynamic pressure at which the n_max limit has yielded; 0: none"},
    {.name = "alpha", .type = LV_KEY_NUMBER, .unit = "rad", .lo = LV_KR_LAT_LO,
     .hi = LV_KR_LAT_HI, .dflt = NAN, .flags = LV_KEY_ANGLE, .instead_of = "alpha_table",
     .offset = offsetof(heading_par, alpha), .description = "angle of attack"},
    {.name = "alpha_table", .type = LV_KEY_TABLE, .unit = "",
     .offset = offsetof(heading_par, alpha_table),
     .description = "angle of attack over mach (output alpha)"},
};

/* The alpha table: one axis "mach", output "alpha" [rad]; *k its index. */
static lv_status table_check(const lv_table *t, int *k, lv_err *err)
{
    lv_status st = lv_guid_table_fits(t, err);
    if (st != LV_OK)
        return st;
    const char *ax = lv_table_n_dims(t) == 1 ? lv_table_axis_name(t, 0) : "";
    size_t idx;
    if (strcmp(ax, "mach") != 0)
        return lv_fail(err, LV_ERR_INPUT, "alpha table '%s' must have "
                       "one axis named 'mach' (it has %zu, the first '%s')", lv_table_name(t),
                       lv_table_n_dims(t), lv_table_axis_name(t, 0));
    if (lv_table_out_index(t, "alpha", &idx, NULL) != LV_OK)
        return lv_fail(err, LV_ERR_INPUT, "alpha table '%s' has no "
                       "output 'alpha' (its first is '%s')", lv_table_name(t),
                       lv_table_out_name(t, 0));
    if ((st = lv_table_expect_unit(t, 1, 0, "1", NULL, err)) != LV_OK ||
        (st = lv_table_expect_unit(t, 0, idx, "rad", NULL, err)) != LV_OK)
        return st;
    *k = (int)idx;
    return LV_OK;
}

static lv_status check(const void *par, lv_law_at *at, lv_err *err)
{
    const heading_par *p = par;
    at->node = LV_AT_VALUE;
    if (p->q_max > 0.0 && !(p->n_max > 0.0)) {
        at->key = "q_max";
        return lv_fail(err, LV_ERR_INPUT, "q_max releases the load-factor limit as q rises: it "
                       "needs n_max > 0");
    }
    int k;
    at->key = "alpha_table";
    return p->alpha_table != NULL ? table_check(p->alpha_table, &k, err) : LV_OK;
}

static lv_status init(lv_guid *g, lv_err *err)
{
    heading_par *p = LV_GUID_PAR_W(heading_par, g);
    g->limits_alpha = p->n_max > 0.0;
    p->k_alpha = -1;
    return p->alpha_table != NULL ? table_check(p->alpha_table, &p->k_alpha, err) : LV_OK;
}

static int attitude(const lv_guid *g, lv_guid_rt *rt, double t, const lv_flight_kin *k,
                    const lv_flight_air *a, double fpa0, double chi0, int full,
                    lv_flight_controls *c, lv_flight_axes *ax, lv_err *err)
{
    (void)t, (void)full;
    const heading_par *p = LV_GUID_PAR(heading_par, g);
    double alpha = p->alpha;
    if (p->alpha_table != NULL) {
        if (lv_table_eval1(p->alpha_table, &rt->cur, a->mach, rt->buf, err) != LV_OK) {
            if (err)
                lv_fail_prefix(err, LV_ERR_INPUT, "guidance 'heading'");
            return 1;
        }
        alpha = rt->buf[p->k_alpha];
    }
    /* the heading error from the two directions' cross and dot products */
    double b[2];
    lv_guid_bearing_cs(g, k, b);
    const double vn = lv_v3_dot(a->v_air, k->n_ax), ve = lv_v3_dot(a->v_air, k->e_ax);
    double mu = p->gain * atan2(vn * b[1] - ve * b[0], vn * b[0] + ve * b[1]);
    mu = mu > p->bank_max ? p->bank_max : mu < -p->bank_max ? -p->bank_max : mu;
    const double ang[3] = {alpha, 0.0, mu};
    lv_guid_aero_angles(rt, k, a, ang, fpa0, chi0, c, ax);
    return 0;
}

static int reads_atmosphere(const lv_guid *g)
{
    (void)g;
    return 1; /* Mach: the alpha table; the limits: the dynamic pressure */
}

static double alpha_limited(const lv_guid *g, double alpha, double lift, double mass, double q)
{
    const heading_par *p = LV_GUID_PAR(heading_par, g);
    if (!(p->n_max > 0.0) || !(mass > 0.0))
        return alpha;
    return lv_guid_heading_alpha(alpha, fabs(lift) / (mass * LV_G0), p->n_max, q, p->q_max);
}

double lv_guid_heading_alpha(double alpha, double n, double n_max, double q, double q_max)
{
    if (!(n_max > 0.0) || !(n > 0.0))
        return alpha;
    /* soft saturation: alpha / (1 + (n / n_max)^8)^(1/8) */
    const double x = n / n_max, x2 = x * x, x4 = x2 * x2;
    const double f = sqrt(sqrt(sqrt(1.0 + x4 * x4)));
    const double a_n = alpha / f;
    if (!(q_max > 0.0))
        return a_n;
    /* the limit yields between q_max / 2 and q_max: smoothstep s(t) = 3 t^2 - 2 t^3 */
    double t = 2.0 * q / q_max - 1.0;
    t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
    const double s = t * t * (3.0 - 2.0 * t);
    return a_n + s * (alpha - a_n);
}

/* alpha and the bank about the air-relative velocity */
static unsigned refs(const lv_guid *g, const lv_guid_rt *rt, double t)
{
    (void)g, (void)rt, (void)t;
    return LV_GREF_WIND;
}

const lv_law lv_law_heading = {
    .name = "heading",
    .description = "bank to turn toward the target at a scheduled angle of attack, within "
                   "bank and load-factor limits",
    .kind = LV_LAW_STEERING,
    .form = LV_LAW_FORM_NAMED,
    .keys = keys,
    .n_keys = sizeof keys / sizeof keys[0],
    .par_size = sizeof(heading_par),
    .needs_aero = "banks the lift vector",
    .dof3_why = "limits the commanded angle of attack of a 3-DoF phase; a 6-DoF body flies "
                "the attitude its controller reaches",
    .check = check,
    .init = init,
    .attitude = attitude,
    .reads_atmosphere = reads_atmosphere,
    .alpha_limited = alpha_limited,
    .refs = refs,
};
