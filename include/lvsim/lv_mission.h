/* lv_mission.h - missions: the phase tree read from a YAML file, run phase by phase.
 *
 * A mission holds one parameter set (the paper's userPar) and phases. Each phase is one
 * lv_simulate() of its own small model, started from the parameters or from the final state
 * of an earlier phase (the hand-off: states copied by name, the mass of the stages it carries,
 * then the phase's `set:` overrides). Phases form a tree: one final state may seed several.
 * The file format: docs/mission-format.md.
 *
 * Two ways to run:
 *   - lv_mission_run(): every phase in dependency order (independent branches in parallel
 *     threads); a failing phase stops only its descendants.
 *   - the paper's Code 2 loop, by hand: lv_mission_phase_model() gives phase k's model; call
 *     lv_simulate() with the start values you choose and read the finals you need
 *     (examples/code2_loop.c).
 */
#ifndef LVSIM_LV_MISSION_H
#define LVSIM_LV_MISSION_H

#include <stddef.h>

#include "lvsim/lv_model.h"
#include "lvsim/lv_sim.h"
#include "lvsim/lv_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct lv_mission lv_mission;

/* Reads and validates a mission file: YAML syntax, keys, types, references, cycles, masses,
 * tables, and that every phase's initial state can be built. Errors are
 * "file:line:column: message" with LV_ERR_INPUT; nothing runs. */
LV_API lv_status lv_mission_load(const char *path, lv_mission **out, lv_err *err);
LV_API void lv_mission_free(lv_mission *m);

LV_API const char *lv_mission_name(const lv_mission *m);
LV_API size_t lv_mission_phase_count(const lv_mission *m);
/* Phases are numbered in run order (every parent before its children). */
LV_API const char *lv_mission_phase_name(const lv_mission *m, size_t k);
LV_API int lv_mission_phase_parent(const lv_mission *m, size_t k); /* -1: from parameters */
LV_API lv_status lv_mission_phase_find(const lv_mission *m, const char *name, size_t *k,
                                       lv_err *err);

/* ---- running ------------------------------------------------------------------------- */

typedef enum lv_phase_state {
    LV_PHASE_PENDING = 0,
    LV_PHASE_DONE,    /* simulated */
    LV_PHASE_FAILED,  /* its simulation failed (see error) */
    LV_PHASE_SKIPPED  /* an ancestor failed */
} lv_phase_state;

/* What one phase did. Owned by the mission; valid until lv_mission_free(). */
typedef struct lv_phase_result {
    const char *name;
    lv_phase_state state;
    char error[LV_ERR_MSG_MAX];  /* FAILED / SKIPPED: phase, time and reason */
    double t_start, t_end;       /* s */
    lv_sim_report report;        /* statistics, stop reason, event log */
    size_t n_final;              /* the final state: every state and output, by name */
    const char *const *final_names;
    const double *final_values;
    const char *result_stem;     /* "OUTDIR/phase_<k>_<name>" when files were written */
    size_t n_event_names;        /* the phase model's state-event functions, by index: */
    const char *const *event_names; /*   report.event_log[i].index names one of them */
} lv_phase_result;

typedef struct lv_run_options {
    const char *outdir;   /* result files go here (created); NULL: no files */
    int threads;          /* worker threads for independent branches (0: 2) */
    /* Called after each phase, from the thread that ran it, under the mission's lock. */
    void (*on_phase)(const lv_mission *m, size_t k, const lv_phase_result *r, void *user);
    void *user;
    double output_interval; /* > 0: overrides every phase's output grid (s), e.g. to compare */
} lv_run_options;

/* Runs every phase not yet run. Returns LV_OK when all succeeded, LV_ERR_SOLVER when some
 * failed (their results say why; the others are complete), LV_ERR_IO when a file could not
 * be written. */
LV_API lv_status lv_mission_run(lv_mission *m, const lv_run_options *opt, lv_err *err);

/* Runs phase k alone; its parent must be done. */
LV_API lv_status lv_mission_run_phase(lv_mission *m, size_t k, const lv_run_options *opt,
                                      lv_err *err);

LV_API const lv_phase_result *lv_mission_result(const lv_mission *m, size_t k);
/* A final value of a done phase by name ("time", "z", "m", ...). */
LV_API lv_status lv_mission_final(const lv_mission *m, size_t k, const char *name, double *value,
                                  lv_err *err);

/* summary.json: per phase start/end time, why it ended, final state, events, statistics,
 * the hand-off; per body the phases it flies in and its merged trajectory file. */
LV_API lv_status lv_mission_write_summary(const lv_mission *m, const char *outdir, lv_err *err);

/* ---- the Code 2 loop by hand -------------------------------------------------------------- */

/* Phase k's model, built from the mission (stages, engines, ends, world). `prop` gives the
 * propellant left in each of the phase's stages [kg], bottom first (NULL: the mission's
 * liftoff values). The caller frees it. */
typedef struct lv_phase_model lv_phase_model;
LV_API lv_status lv_mission_phase_model(const lv_mission *m, size_t k, const double *prop,
                                        lv_phase_model **out, lv_err *err);
LV_API const lv_model_def *lv_phase_model_def(const lv_phase_model *pm);
LV_API void *lv_phase_model_inst(lv_phase_model *pm);
LV_API void lv_phase_model_free(lv_phase_model *pm);
/* Phase k's settings as the mission gives them (start/stop time, method, tolerance, grid).
 * start_time is NAN when it comes from the parent's end. */
LV_API void lv_mission_phase_settings(const lv_mission *m, size_t k, lv_sim_settings *s);

/* ---- sequential versus end-to-end (the paper's Table 2) ------------------------------------- */

typedef struct lv_compare_side {
    char method[32];
    double tolerance;
    size_t n_states;       /* per model (sequential: the largest phase model) */
    long state_events, time_events, steps, rhs_evals, jac_evals;
    double cpu_time;       /* s, sum over phases */
} lv_compare_side;

typedef struct lv_compare_body {
    char name[64];
    double max_dpos, max_dvel, max_dmass; /* m, m/s, kg: largest difference at common times */
    size_t n_common;                      /* common output times compared */
} lv_compare_body;

typedef struct lv_compare_report {
    lv_compare_side seq, e2e;
    size_t n_bodies;
    lv_compare_body bodies[8];
} lv_compare_report;

/* Runs the mission sequentially and as one end-to-end model (flat6 missions whose phases
 * split the stack at their ends), both with `method`/`tolerance` (NULL/0: each phase's own)
 * and the output interval `dt` (s), and compares every body at common output times. */
LV_API lv_status lv_mission_compare(const char *path, const char *method, double tolerance,
                                    double dt, lv_compare_report *rep, lv_err *err);

#ifdef __cplusplus
}
#endif
#endif
