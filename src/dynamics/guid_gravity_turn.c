/* guid_gravity_turn.c - steering law `gravity_turn`: a vertical rise for rise_time, a
 * pitch-over of `kick` at a constant rate over kick_time in the plane of `heading` (local
 * frame), then zero angle of attack, sideslip and bank (thrust along the air-relative
 * velocity). Times from the phase's start; both breakpoints are time events. Wiesel,
 * Spaceflight Dynamics, 3rd ed., sec. 9; the closed form for a constant thrust acceleration:
 * Culler & Fried, J. Appl. Phys. 28 (1957) 672 (docs/guidance.md).
 */
#include "dynamics/guid_kit.h"

typedef struct gravity_turn_par {
    double rise_time; /* s */
    double kick;      /* rad, pitch-over angle */
    double kick_time; /* s */
    double heading;   /* rad, of the plane of the turn */
} gravity_turn_par;

static const lv_law_key keys[] = {
    {.name = "rise_time", .type = LV_KEY_NUMBER, .unit = "s", .lo = 0.0, .hi = HUGE_VAL,
     .dflt = 0.0, .offset = offsetof(gravity_turn_par, rise_time),
     .description = "vertical rise from the phase's start"},
    {.name = "kick", .type = LV_KEY_NUMBER, .unit = "rad", .lo = 0.0, .hi = 0.5 * LV_PI,
     .dflt = NAN, .flags = LV_KEY_ANGLE, .offset = offsetof(gravity_turn_par, kick),
     .description = "pitch-over from the vertical, at a constant rate"},
    {.name = "kick_time", .type = LV_KEY_NUMBER, .unit = "s", .lo = 0.0, .hi = HUGE_VAL,
     .dflt = NAN, .offset = offsetof(gravity_turn_par, kick_time),
     .description = "duration of the pitch-over (> 0 with a kick)"},
    {.name = "heading", .type = LV_KEY_NUMBER, .unit = "rad", .lo = LV_KR_TURN_LO,
     .hi = LV_KR_TURN_HI, .dflt = NAN, .flags = LV_KEY_ANGLE,
     .offset = offsetof(gravity_turn_par, heading),
     .description = "heading of the plane of the turn (the launch azimuth)"},
};

static lv_status check(const void *par, lv_law_at *at, lv_err *err)
{
    const gravity_turn_par *p = par;
    at->node = LV_AT_VALUE;
    if (p->kick > 0.0 && !(p->kick_time > 0.0)) {
        at->key = "kick_time";
        return lv_fail(err, LV_ERR_INPUT, "a kick needs kick_time > 0 s");
    }
    for (int i = 0; i < 2; i++) { /* durations the integrator's clock can tell from 0 */
        const double dt = i == 0 ? p->rise_time : p->kick_time;
        at->key = i == 0 ? "rise_time" : "kick_time";
        if (dt > 0.0 && dt < 1e-9)
            return lv_fail(err, LV_ERR_INPUT, "%s = %g s: give 0 or at least 1e-9 s", at->key,
                           dt);
    }
    return LV_OK;
}

static int attitude(const lv_guid *g, lv_guid_rt *rt, double t, const lv_flight_kin *k,
                    const lv_flight_air *a, double fpa0, double chi0, int full,
                    lv_flight_controls *c, lv_flight_axes *ax, lv_err *err)
{
    (void)fpa0, (void)err;
    const gravity_turn_par *p = LV_GUID_PAR(gravity_turn_par, g);
    const double tau = t - rt->t0;
    if (tau >= p->rise_time + p->kick_time) { /* zero angle of attack; at rest (no velocity
                                                  to follow yet): straight up */
        static const double zero[3] = {0.0, 0.0, 0.0};
        lv_guid_aero_angles(rt, k, a, zero, 0.5 * LV_PI, p->heading, c, ax);
        return 0;
    }
    double pitch = 0.5 * LV_PI;
    if (tau > p->rise_time)
        pitch -= p->kick * (tau - p->rise_time) / p->kick_time;
    const double ang[3] = {pitch, p->heading, 0.0};
    lv_guid_trig3(rt, ang);
    lv_guid_euler_attitude(g, rt, k, a, LV_FRAME_LOCAL, (const double(*)[2])rt->cs, chi0, full,
                           c, ax);
    return 0;
}

static double next_time_event(const lv_guid *g, const lv_guid_rt *rt, double t)
{
    const gravity_turn_par *p = LV_GUID_PAR(gravity_turn_par, g);
    const double t1 = rt->t0 + p->rise_time, t2 = t1 + p->kick_time;
    if (t1 > t)
        return t1;
    if (t2 > t)
        return t2;
    return INFINITY;
}

static const char *time_event_label(const lv_guid *g, const lv_guid_rt *rt, double t)
{
    const gravity_turn_par *p = LV_GUID_PAR(gravity_turn_par, g);
    const double t1 = rt->t0 + p->rise_time;
    if (t == t1 && p->kick_time > 0.0)
        return "guidance: end of the vertical rise, start of the kick";
    if (t == t1 + p->kick_time)
        return p->kick_time > 0.0 ? "guidance: end of the kick, zero angle of attack"
                                  : "guidance: end of the vertical rise, zero angle of attack";
    return NULL;
}

/* The local frame until the end of the kick, the wind's direction after it. */
static unsigned refs(const lv_guid *g, const lv_guid_rt *rt, double t)
{
    const gravity_turn_par *p = LV_GUID_PAR(gravity_turn_par, g);
    return rt == NULL || t - rt->t0 >= p->rise_time + p->kick_time ? LV_GREF_WIND : 0u;
}

const lv_law lv_law_gravity_turn = {
    .name = "gravity_turn",
    .description = "vertical rise, a pitch-over (kick) at a constant rate in the plane of "
                   "heading, then zero angle of attack",
    .kind = LV_LAW_STEERING,
    .form = LV_LAW_FORM_NAMED,
    .keys = keys,
    .n_keys = sizeof keys / sizeof keys[0],
    .par_size = sizeof(gravity_turn_par),
    .check = check,
    .attitude = attitude,
    .next_time_event = next_time_event,
    .time_event_label = time_event_label,
    .refs = refs,
};
