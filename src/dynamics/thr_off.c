/* thr_off.c - throttle law `off`: the engines are off, a coast; no propellant is burnt
 * (docs/guidance.md, "Throttle laws").
 */
#include "dynamics/guid_kit.h"

static lv_status thr_init(lv_thr *t, lv_err *err)
{
    (void)err;
    t->engines_off = 1;
    return LV_OK;
}

const lv_law lv_law_off = {
    .name = "off",
    .description = "engines off: a coast, no propellant burnt",
    .kind = LV_LAW_THROTTLE,
    .form = LV_LAW_FORM_WORD,
    .thr_init = thr_init,
};
