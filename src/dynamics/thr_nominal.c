/* thr_nominal.c - throttle law `nominal`: the nominal throttle (`value`, else the inputs' or
 * the attitude table's) with limits: c_s = min(c_nominal, c_g, c_q), later clamped into each
 * engine's limits; c_g keeps the axial load factor (thrust + axial aerodynamic force) / (m g0)
 * at g_limit; c_q makes the dynamic pressure obey dq/dt <= q_gain (q_max - q), so that q
 * approaches q_max without crossing it (docs/guidance.md, "Throttle laws").
 */
#include "dynamics/guid_kit.h"

typedef struct nominal_par {
    double value;   /* the nominal throttle; NAN: the inputs' (a mission phase's constant
                       throttle: lv_dof3_config.throttle in the C API) */
    double g_limit; /* axial load factor limit [g0]; 0: none */
    double q_max;   /* Pa; 0: none */
    double q_gain;  /* 1/s */
} nominal_par;

static const lv_law_key keys[] = {
    {.name = "value", .type = LV_KEY_NUMBER, .unit = "1", .lo = 0.0, .hi = HUGE_VAL,
     .dflt = NAN, .flags = LV_KEY_OPTIONAL, .offset = offsetof(nominal_par, value),
     .description = "the nominal throttle (else inputs.throttle or the attitude table's, "
                    "default 1); in the C API lv_dof3_config.throttle"},
    {.name = "g_limit", .type = LV_KEY_NUMBER, .unit = "1", .lo = 0.0, .hi = HUGE_VAL,
     .lo_open = 1, .dflt = 0.0, .flags = LV_KEY_OPTIONAL,
     .offset = offsetof(nominal_par, g_limit),
     .description = "axial load factor limit (thrust + axial aerodynamic force) / (m g0)"},
    {.name = "q_max", .type = LV_KEY_NUMBER, .unit = "Pa", .lo = 0.0, .hi = HUGE_VAL,
     .lo_open = 1, .dflt = 0.0, .flags = LV_KEY_OPTIONAL, .offset = offsetof(nominal_par, q_max),
     .description = "dynamic pressure limit, approached as dq/dt <= q_gain (q_max - q)"},
    {.name = "q_gain", .type = LV_KEY_NUMBER, .unit = "1/s", .lo = 0.0, .hi = 100.0,
     .lo_open = 1, .dflt = 1.0, .needs = "q_max", .offset = offsetof(nominal_par, q_gain),
     .description = "rate at which q may approach q_max"},
};

static lv_status thr_init(lv_thr *t, lv_err *err)
{
    (void)err;
    const nominal_par *p = LV_GUID_PAR(nominal_par, t);
    t->active = p->g_limit > 0.0 || p->q_max > 0.0;
    t->reads_drho = p->q_max > 0.0;
    return LV_OK;
}

static double throttle(const lv_thr *t, double c_nom, const lv_thr_in *in,
                       const lv_flight_air *a)
{
    const nominal_par *p = LV_GUID_PAR(nominal_par, t);
    const double slope = in->t_full + in->p_ae; /* dT/dc, N */
    if (!(slope > 0.0))
        return c_nom;
    double c = c_nom;
    if (p->g_limit > 0.0) { /* (T(c) + F_aero . x_b) / m <= n g0 */
        const double cg = (p->g_limit * LV_G0 * in->mass - lv_v3_dot(in->f_aero, in->xb) +
                           in->p_ae) / slope;
        if (cg < c)
            c = cg;
    }
    if (p->q_max > 0.0 && a->v_air_n > LV_GUID_V_AIR_MIN && a->rho > 0.0) {
        /* acceleration relative to the planet at throttle c: a0 + c a1 */
        lv_vec3 a0, a1;
        lv_guid_thr_accel(in, slope, &a0, &a1);
        /* q' = rho' h' V^2 / 2 + rho V V' with V' = x_w . (a0 + c a1) <= k (q_max - q) */
        const lv_vec3 xw = lv_v3_scale(a->v_air, 1.0 / a->v_air_n);
        const double V = a->v_air_n;
        const double A = 0.5 * in->drho_dh * in->h_dot * V * V + a->rho * V * lv_v3_dot(xw, a0);
        const double B = a->rho * V * lv_v3_dot(xw, a1);
        if (B > 0.0) {
            const double cq = (p->q_gain * (p->q_max - a->q) - A) / B;
            if (cq < c)
                c = cq;
        }
    }
    return c;
}

const lv_law lv_law_nominal = {
    .name = "nominal",
    .description = "the nominal throttle with an axial load-factor limit and a dynamic "
                   "pressure limit",
    .kind = LV_LAW_THROTTLE,
    .form = LV_LAW_FORM_KEYS,
    .keys = keys,
    .n_keys = sizeof keys / sizeof keys[0],
    .par_size = sizeof(nominal_par),
    .thr_init = thr_init,
    .throttle = throttle,
};
