/* thr_landing.c - throttle law `landing`: a constant deceleration to touch down at `speed`
 * at `altitude`: the upward acceleration is held at a_up = (v_down^2 - speed^2) / (2 (h -
 * altitude)) (kinematics of constant acceleration); at or below the altitude none
 * (docs/guidance.md, "Throttle laws").
 */
#include "dynamics/guid_kit.h"

typedef struct landing_par {
    double altitude; /* m, geodetic */
    double speed;    /* m/s, touchdown */
} landing_par;

static const lv_law_key keys[] = {
    {.name = "altitude", .type = LV_KEY_NUMBER, .unit = "m", .lo = -HUGE_VAL, .hi = HUGE_VAL,
     .dflt = 0.0, .offset = offsetof(landing_par, altitude),
     .description = "geodetic altitude of the touchdown"},
    {.name = "speed", .type = LV_KEY_NUMBER, .unit = "m/s", .lo = 0.0, .hi = HUGE_VAL,
     .dflt = 0.0, .offset = offsetof(landing_par, speed),
     .description = "downward speed at touchdown"},
};

static lv_status thr_init(lv_thr *t, lv_err *err)
{
    (void)err;
    t->active = 1;
    return LV_OK;
}

static double throttle(const lv_thr *t, double c_nom, const lv_thr_in *in,
                       const lv_flight_air *a)
{
    (void)a;
    const landing_par *p = LV_GUID_PAR(landing_par, t);
    const double slope = in->t_full + in->p_ae; /* dT/dc, N */
    if (!(slope > 0.0))
        return c_nom;
    lv_vec3 a0, a1; /* acceleration relative to the planet at throttle c: a0 + c a1 */
    lv_guid_thr_accel(in, slope, &a0, &a1);
    /* constant deceleration from here to the landing point: v^2 - v_td^2 = 2 a dh */
    const double dh = in->h - p->altitude;
    const double vd = in->v_down > 0.0 ? in->v_down : 0.0;
    const double vt = p->speed;
    /* at or below the landing altitude the landing is over (the phase's impact end is there):
     * no vertical acceleration, so that the touchdown row shows no spike */
    const double a_req = dh > 0.0 ? (vd * vd - vt * vt) / (2.0 * dh) : 0.0;
    const double up1 = lv_v3_dot(in->up, a1);
    if (!(up1 > 0.0))
        return in->c_max;
    return (a_req - lv_v3_dot(in->up, a0)) / up1;
}

const lv_law lv_law_landing = {
    .name = "landing",
    .description = "a constant deceleration to touch down at `speed` at `altitude`",
    .kind = LV_LAW_THROTTLE,
    .form = LV_LAW_FORM_NESTED,
    .keys = keys,
    .n_keys = sizeof keys / sizeof keys[0],
    .par_size = sizeof(landing_par),
    .thr_init = thr_init,
    .throttle = throttle,
};
