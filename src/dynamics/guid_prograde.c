/* guid_prograde.c - steering law `prograde`: body x along the air-relative velocity (alpha =
 * beta = mu = 0): thrust along the velocity, no lift (a zero-lift turn, the gravity turn after
 * its kick). At rest relative to the air the body points along the phase's start direction
 * (start_fpa, start_chi), as the aerodynamic frame does (docs/guidance.md).
 */
#include "dynamics/guid_kit.h"

static int attitude(const lv_guid *g, lv_guid_rt *rt, double t, const lv_flight_kin *k,
                    const lv_flight_air *a, double fpa0, double chi0, int full,
                    lv_flight_controls *c, lv_flight_axes *ax, lv_err *err)
{
    (void)g, (void)t, (void)full, (void)err;
    static const double zero[3] = {0.0, 0.0, 0.0};
    lv_guid_aero_angles(rt, k, a, zero, fpa0, chi0, c, ax);
    return 0;
}

static unsigned refs(const lv_guid *g, const lv_guid_rt *rt, double t)
{
    (void)g, (void)rt, (void)t;
    return LV_GREF_WIND;
}

const lv_law lv_law_prograde = {
    .name = "prograde",
    .description = "body x along the air-relative velocity (alpha = beta = mu = 0)",
    .kind = LV_LAW_STEERING,
    .form = LV_LAW_FORM_NAMED,
    .attitude = attitude,
    .refs = refs,
};
