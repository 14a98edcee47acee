/* guid_boostback.c - steering law `boostback`: body x toward the target over the local
 * horizon: heading = the bearing to the target (lv_steering.target_lat/lon), pitch `pitch`
 * above the horizon (local frame; docs/guidance.md).
 */
#include "dynamics/guid_kit.h"

typedef struct boostback_par {
    double pitch;       /* rad, above the local horizon */
    double cs_pitch[2]; /* init: cos, sin of pitch */
} boostback_par;

static const lv_law_key keys[] = {
    {.name = "pitch", .type = LV_KEY_NUMBER, .unit = "rad", .lo = LV_KR_LAT_LO,
     .hi = LV_KR_LAT_HI, .dflt = 0.0, .flags = LV_KEY_ANGLE,
     .offset = offsetof(boostback_par, pitch), .description = "pitch above the local horizon"},
};

static lv_status init(lv_guid *g, lv_err *err)
{
    (void)err;
    boostback_par *p = LV_GUID_PAR_W(boostback_par, g);
    p->cs_pitch[0] = cos(p->pitch);
    p->cs_pitch[1] = sin(p->pitch);
    return LV_OK;
}

static int attitude(const lv_guid *g, lv_guid_rt *rt, double t, const lv_flight_kin *k,
                    const lv_flight_air *a, double fpa0, double chi0, int full,
                    lv_flight_controls *c, lv_flight_axes *ax, lv_err *err)
{
    (void)t, (void)fpa0, (void)err;
    const boostback_par *p = LV_GUID_PAR(boostback_par, g);
    double b[2];
    lv_guid_bearing_cs(g, k, b);
    const double cs[3][2] = {{p->cs_pitch[0], p->cs_pitch[1]}, {b[0], b[1]}, {1.0, 0.0}};
    lv_guid_euler_attitude(g, rt, k, a, LV_FRAME_LOCAL, cs, chi0, full, c, ax);
    return 0;
}

const lv_law lv_law_boostback = {
    .name = "boostback",
    .description = "body x toward the target over the local horizon: heading = the bearing "
                   "to the target, pitch above the horizon",
    .kind = LV_LAW_STEERING,
    .form = LV_LAW_FORM_NAMED,
    .keys = keys,
    .n_keys = sizeof keys / sizeof keys[0],
    .par_size = sizeof(boostback_par),
    .init = init,
    .attitude = attitude,
};
