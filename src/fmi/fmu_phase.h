/* fmu_phase.h - one phase of a mission made ready to be an FMU's model: the mission loaded,
 * the phase's ancestors simulated (a child phase starts from its parent's final state), the
 * phase prepared (lv_run_prepare: its model, instance and settings), and its start values
 * computed as lv_simulate computes them. The exporter (export.c) writes these start values into
 * modelDescription.xml; the FMU (fmu.c) does the same at fmi2Instantiate from the copy of the
 * mission in its resources, and gets the same numbers. Public API of liblvsim only. */
#ifndef LV_FMI_FMU_PHASE_H
#define LV_FMI_FMU_PHASE_H

#include <stddef.h>

#include "lvsim/lv_mission.h"

typedef struct lv_fmu_phase {
    lv_mission *mission;
    lv_run *run;
    size_t k;                  /* the phase's index */
    int parent;                /* its parent's index, or -1 */
    lv_phase_call *call;       /* lv_run_prepare's: owns the model and its instance */
    const lv_model_def *def;
    void *inst;
    const lv_sim_settings *s;  /* the phase's settings: times, method, tolerance, stops */
    double *x0, *p0;           /* [n_states], [n_params]: the start values */
    unsigned char *is_input;   /* [n_params]: an FMI input (lv_fmu_phase_inputs) */
    size_t n_inputs;
    size_t n_run;              /* the run parameters the FMU offers (lv_fmu_phase_run_params) */
    size_t *run_idx;           /* [n_run] their indices in the mission's parameters */
} lv_fmu_phase;

/* Loads `mission_path`, runs the ancestors of phase `phase` (by name) and prepares it.
 * Errors name the mission file, the phase and the reason (an unknown phase lists the names;
 * a parent that fails gives its error). On failure *fp is cleared. */
lv_status lv_fmu_phase_open(const char *mission_path, const char *phase, lv_fmu_phase *fp,
                            lv_err *err);
void lv_fmu_phase_close(lv_fmu_phase *fp); /* accepts a cleared one */

/* The start values of states x[n_states] and parameters p[n_params] from the phase's settings,
 * as lv_simulate sets them: parameters at their defaults, then those the hand-off names; the
 * states' defaults, the model's start() from the parameters, then the states the hand-off
 * names. */
lv_status lv_fmu_phase_start_values(const lv_model_def *def, void *inst, const lv_sim_settings *s,
                                    double *x, double *p, lv_err *err);

/* The model parameters that are the phase's inputs (issue 27; the paper's controls alpha,
 * beta, mu and the throttle c_s of a 3-DoF phase): a parameter P is an FMI input (causality
 * "input", variability "continuous", start = its value) when the mission has the run parameter
 * "<phase>.inputs.P" - the phase types create it only where the constant input acts: not where
 * a steering law gives the angles, nor where a throttle law or table gives the throttle - and
 * when moving it moves the right-hand side at the start (so an inputs table over time, which
 * replaces the constant, leaves it a parameter). Sets fp->is_input, fp->n_inputs; the model
 * instance's bytes are put back after. Called by lv_fmu_phase_open. */
void lv_fmu_phase_inputs(lv_fmu_phase *fp);

/* The mission's run parameters (lvsim params: stage masses, engine data, guidance and law
 * coefficients, the start values of a root phase) that change this phase - read by it or by an
 * ancestor - found on a scratch run: the phase run once, then each parameter moved by a
 * relative 1e-6 and lv_run_stale asked, then put back (and the phase run again). Left out: the
 * model's own parameters (already FMI parameters or inputs), the phases' integrator settings
 * and start times, and for a child phase every parameter that moves the hand-off's time (the
 * FMU's start time is the DefaultExperiment's: a burnout that comes later would move it). A
 * phase that does not complete
 * on the scratch run offers none. Sets fp->run_idx, fp->n_run (export time; the FMU reads the
 * names from its resources). */
#define LV_FMU_MAX_RUN 256 /* run parameters offered at most (the first ones in the mission) */
lv_status lv_fmu_phase_run_params(lv_fmu_phase *fp, lv_err *err);

/* The phase made ready again after lv_run_set on fp->run (a run parameter changed): the
 * ancestors run again where they read it, the phase prepared again, its start values and
 * inputs computed again. The model (fp->def, fp->inst, fp->s) is a new one: the old pointers
 * are invalid after. On failure fp keeps the old model (its ancestors may have run again). */
lv_status lv_fmu_phase_reprepare(lv_fmu_phase *fp, lv_err *err);

#endif
