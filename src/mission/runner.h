/* runner.h - internal views of a mission run, for the summary, merged trajectories and the
 * end-to-end comparison (not exported). */
#ifndef LV_MISSION_RUNNER_H
#define LV_MISSION_RUNNER_H

#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_io.h"
#include "lvsim/lv_planet.h"
#include "lvsim/lv_wind.h"
#include "lvsim/lv_mission.h"
#include "mission/mission.h"

/* What a planet world shares between phases (read-only during a run). */
typedef struct lv_runner_env {
    lv_planet planet;
    lv_gravity *gravity; /* NULL on a flat world */
    lv_atmo *atmo;       /* NULL: vacuum */
    lv_wind *wind;       /* NULL: no wind */
} lv_runner_env;

/* Phase k's model with `prop_all[s]` kg of propellant left in mission stage s (NULL: liftoff). */
lv_status lv_runner_build_model(const lv_mission_def *d, const lv_runner_env *env, size_t k,
                                const double *prop_all, lv_phase_model **out, lv_err *err);
const lv_runner_env *lv_runner_environment(const lv_mission *m);

const lv_mission_def *lv_runner_def(const lv_mission *m);
const lv_result *lv_runner_rows(const lv_mission *m, size_t k); /* NULL before the run */
double lv_runner_mass_start(const lv_mission *m, size_t k);     /* kg */
double lv_runner_mass_handoff(const lv_mission *m, size_t k);   /* kg; NAN for a root */
size_t lv_runner_n_copied(const lv_mission *m, size_t k);
const double *lv_runner_prop_end(const lv_mission *m, size_t k); /* [n_stages] kg */

/* The phases stage `s` flies in, in time order (a path in the phase tree); returns the count
 * written to `out` (capacity n_phases). */
size_t lv_runner_body_phases(const lv_mission *m, size_t s, size_t *out);

/* Mass of stage `s` at row `row` of phase k: the bottom stage is the body's mass minus the
 * stages above it; an upper stage keeps its dry mass plus its propellant at the phase start. */
double lv_runner_stage_mass(const lv_mission *m, size_t k, size_t s, double m_body);

#endif
