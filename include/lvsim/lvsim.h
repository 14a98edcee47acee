/* lvsim.h - umbrella header of liblvsim: mission-dependent sequential simulation of
 * launch vehicles. Include this, or the single headers it lists. */
#ifndef LVSIM_LVSIM_H
#define LVSIM_LVSIM_H

#define LVSIM_VERSION "0.1.0"

#include "lvsim/lv_status.h"
#include "lvsim/lv_units.h"
#include "lvsim/lv_data.h"
#include "lvsim/lv_model.h"
#include "lvsim/lv_io.h"
#include "lvsim/lv_sim.h"
#include "lvsim/lv_models.h"
#include "lvsim/lv_planet.h"
#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_wind.h"
#include "lvsim/lv_perturbation.h"
#include "lvsim/lv_table.h"
#include "lvsim/lv_flat.h"
#include "lvsim/lv_mission.h"
#include "lvsim/lv_target.h"
#include "lvsim/lv_ocp.h"
#include "lvsim/lv_summary.h"
#include "lvsim/lv_export.h"
#include "lvsim/lv_plot.h"
#include "lvsim/lv_outdir.h"
#include "lvsim/lv_vehicle.h"
#include "lvsim/lv_guidance.h"
#include "lvsim/lv_dof3.h"
#include "lvsim/lv_dof6.h"

#endif
