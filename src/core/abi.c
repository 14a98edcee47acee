/* abi.c - the library's version and the sizes of its public structures as compiled, for
 * bindings that mirror them (the Python package checks them when it loads the library). */
#include <string.h>

#include "lvsim/lvsim.h"
#include "lvsim/lv_campaign.h"
#include "lvsim/lv_dispersion.h"

const char *lv_version(void) { return LVSIM_VERSION; }

#define T(type) {#type, sizeof(type)}
static const struct {
    const char *name;
    size_t size;
} abi_types[] = {
    T(lv_err),
    T(lv_var),
    T(lv_event_def),
    T(lv_model_def),
    T(lv_mission_info),
    T(lv_phase_info),
    T(lv_param_info),
    T(lv_sim_stats),
    T(lv_event_record),
    T(lv_sim_report),
    T(lv_phase_result),
    T(lv_run_options),
    T(lv_body_traj),
    T(lv_sink),
    T(lv_sim_stop),
    T(lv_sim_settings),
    T(lv_output_estimate),
    T(lv_target_var_info),
    T(lv_target_con_info),
    T(lv_target_cost_info),
    T(lv_target_iter),
    T(lv_target_eval),
    T(lv_target_settings),
    T(lv_target_end_mismatch),
    T(lv_target_result),
    T(lv_ocp_iteration),
    T(lv_ocp_settings),
    T(lv_ocp_result),
    T(lv_disp_info),
    T(lv_campaign_progress),
    T(lv_campaign_options),
    T(lv_outdir_record),
    T(lv_law_key),
    T(lv_law_info),
    T(lv_ref_drift),
};
#undef T

size_t lv_abi_sizeof(const char *type)
{
    if (type == NULL)
        return 0;
    for (size_t i = 0; i < sizeof abi_types / sizeof abi_types[0]; i++)
        if (strcmp(abi_types[i].name, type) == 0)
            return abi_types[i].size;
    return 0;
}
