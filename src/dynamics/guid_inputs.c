/* guid_inputs.c - the `inputs` pseudo-law: no steering law; the model's own inputs (the
 * paper's alpha, beta, mu and throttle: constants or a table over time, lv_dof3_config.inputs)
 * give the attitude. A mission phase without `guidance:` has it; files never name it.
 */
#include "dynamics/guid_kit.h"

/* The inputs' alpha, beta, mu are aerodynamic angles: the attitude follows the wind. */
static unsigned refs(const lv_guid *g, const lv_guid_rt *rt, double t)
{
    (void)g, (void)rt, (void)t;
    return LV_GREF_WIND;
}

const lv_law lv_law_inputs = {
    .name = "inputs",
    .description = "no steering law: the phase's inputs (alpha, beta, mu; constants or a "
                   "table over time) give the attitude",
    .kind = LV_LAW_STEERING,
    .form = LV_LAW_FORM_NONE,
    .refs = refs,
};
