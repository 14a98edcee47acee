/* guid_inputs.c - the `inputs` pseudo-law: no steering law; the model's own inputs (the
 * paper's alpha, beta, mu and throttle: constants or a table over time, lv_dof3_config.inputs)
 * give the attitude. A mission phase without `guidance:` has it; files never name it.
 */
#include "dynamics/guid_kit.h"

const lv_law lv_law_inputs = {
    .name = "inputs",
    .description = "no steering law: the phase's inputs (alpha, beta, mu; constants or a "
                   "table over time) give the attitude",
    .kind = LV_LAW_STEERING,
    .form = LV_LAW_FORM_NONE,
};
