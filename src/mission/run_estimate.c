/* run_estimate.c - how much a phase will write, at most, before it runs: rows from its
 * output grid and its longest possible duration, bytes from the rows and its columns. The
 * CLI refuses a mission beyond a limit (lvsim check/run --max-rows) instead of filling the
 * disk and the memory for hours. Reads the plan and the run's values only. */
#include <math.h>

#include "core/status.h"
#include "lvsim/lv_mission.h"
#include "mission/mission_rt.h"

/* lv_simulate's grid without output_interval or number_of_intervals (sim/simulate.c). */
#define GRID_DEFAULT_INTERVALS 500

/* Earliest time phase k can start: its start_time, or its parent's end when the parent is
 * done in this run, or its parent's earliest start (a phase ends after it starts). */
static double earliest_start(const lv_run *r, size_t k)
{
    const lv_mission_def *d = lv_run_mission(r)->def;
    const double *v = lv_run_vals(r);
    for (int depth = 0; depth <= (int)d->n_phases; depth++) {
        const lv_phase_def *ph = &d->phases[k];
        if (ph->t_start != LV_NO_SLOT)
            return v[ph->t_start];
        if (ph->parent < 0)
            return 0.0;
        const lv_phase_result *pr = lv_run_result(r, (size_t)ph->parent);
        if (pr->state == LV_PHASE_DONE && isfinite(pr->t_end))
            return pr->t_end;
        k = (size_t)ph->parent;
    }
    return 0.0;
}

lv_status lv_run_estimate_output(const lv_run *r, size_t k, double output_interval,
                                 lv_output_estimate *out, lv_err *err)
{
    const lv_mission *m = lv_run_mission(r);
    const lv_mission_def *d = m->def;
    if (k >= d->n_phases)
        return lv_fail(err, LV_ERR_INPUT, "phase index %zu out of range", k);
    const lv_phase_def *ph = &d->phases[k];
    const lv_phase_plan *pl = &m->plan[k];
    const double *v = lv_run_vals(r);
    const double t0 = earliest_start(r, k), tf = v[ph->t_stop];
    const double span = tf - t0;
    const double dt = output_interval > 0.0 ? output_interval : v[ph->output_interval];
    double intervals;
    if (!(span > 0.0))
        intervals = 1.0;
    else if (dt > 0.0)
        intervals = fmax(1.0, ceil(span / dt - 1e-9));
    else
        intervals = ph->intervals > 0 ? ph->intervals : GRID_DEFAULT_INTERVALS;
    out->duration = span > 0.0 ? span : 0.0;
    out->rows = intervals + 1.0;
    out->n_signals = pl->n_final + pl->n_states; /* time, states, outputs + derivatives */
    out->bytes_mat = out->rows * (double)out->n_signals * 8.0;
    out->bytes_csv = out->rows * (double)out->n_signals * 22.0;
    return LV_OK;
}
