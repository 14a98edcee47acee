/* thr_landing.c - throttle law `landing`: a constant deceleration to touch down at `speed`
 * at `altitude`: the upward acceleration is held at a_up = (v_down^2 - speed^2) / (2 (h -
 * altitude)) (kinematics of constant acceleration) while the time to go on that path,
 * 2 (h - altitude) / (v_down + speed), is at least LANDING_TAU; in the last LANDING_TAU and
 * at or below the altitude a_up = (v_down - speed) / LANDING_TAU, a first-order approach of
 * the touchdown speed (docs/guidance.md, "Throttle laws").
 */
#include "dynamics/guid_kit.h"

/* s: the shortest time to go the law divides by. a_up = (v^2 - v_t^2) / (2 dh) is 0/0 at the
 * touchdown (dh -> 0 with v -> v_t): its gain on the speed, v / dh, grows without bound, so the
 * integrator's errors of 1e-9 m/s became throttle spikes in the last microseconds and a
 * `throttle_max` event at the impact (issue 27); and at dh = 0 it jumped to 0. With the floor
 * the law is continuous everywhere, also at the altitude, and its gain at most 1 / LANDING_TAU.
 * The last 0.01 s change the touchdown speed by about 0.37 a LANDING_TAU (2 % of a 5 m/s^2
 * deceleration's 0.05 m/s at 2 m/s; a_up LANDING_TAU / 2 with speed 0, which now lands). */
#define LANDING_TAU 0.001

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
    /* (v^2 - v_t^2) / (2 dh) = (v - v_t) / t_go, t_go = 2 dh / (v + v_t), with t_go held
     * at LANDING_TAU or more: the same law where t_go >= LANDING_TAU, (v - v_t) / LANDING_TAU
     * in the last LANDING_TAU and at or below the altitude (continuous at both: no spike nor a
     * saturation that is not there at the touchdown row); 0 at rest on the altitude */
    const double den = fmax(2.0 * dh, LANDING_TAU * (vd + vt));
    const double a_req = den > 0.0 ? (vd * vd - vt * vt) / den : 0.0;
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
