/* sim_state.h - a steppable simulation's state saved and restored (internal: the FMU's
 * fmi2GetFMUstate / fmi2SetFMUstate in Co-Simulation, src/fmi/fmu.c).
 *
 * What is saved: the time, the states and parameters, the model's instance data (its
 * inst_size bytes: discrete modes, table cursors, the steering law's frozen frame), the
 * position on the output grid and the next time event, the run's state (running, finished,
 * failed) and its report with the event log. Not saved: the rows already given to the sinks
 * (meant for simulations without sinks) and the integrator's history. Saving changes nothing
 * in the simulation (its integrator goes on as if no state had been taken); restoring restarts
 * the integrator at the saved point. So two restores of one state continue bit-identically
 * (with CVODE and the fixed-step methods; ARKODE's dopri5 keeps its step-size history across
 * a restart, so there they agree to the tolerance only), while the continuation right after
 * the save (no restart) and one after a restore (a restart) agree to the tolerance: the
 * restart is what an event does to the integration.
 *
 * The instance data are copied as bytes: a model whose instance holds pointers to memory it
 * changes during a run would not be restored by this (lvsim's models keep such memory in the
 * model, set up once). A saved state belongs to the simulation it was taken from (or one of
 * the same model and instance): its pointers are not meant for another process. */
#ifndef LV_SIM_SIM_STATE_H
#define LV_SIM_SIM_STATE_H

#include "lvsim/lv_sim.h"

typedef struct lv_sim_saved lv_sim_saved;

/* Saves sim's state into a new *out (lv_sim_saved_free); sim is not changed. */
lv_status lv_sim_save(const lv_sim *sim, lv_sim_saved **out, lv_err *err);
/* Puts sim back into the saved state (the same model: counts checked) and restarts its
 * integrator there. A failed simulation runs again from the saved point. */
lv_status lv_sim_restore(lv_sim *sim, const lv_sim_saved *saved, lv_err *err);
void lv_sim_saved_free(lv_sim_saved *saved); /* accepts NULL */

#endif
