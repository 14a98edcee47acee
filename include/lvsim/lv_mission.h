/* lv_mission.h - missions: one immutable definition read from a YAML file, and any number of
 * runs of it.
 *
 * A mission holds one parameter set (the paper's userPar) and a tree of phases. Each phase is
 * one lv_simulate() of its own small model, started from the parameters or from the final
 * state of an earlier phase (the hand-off: states copied by name, the mass of the stages it
 * carries, then the phase's `set:` overrides). One final state may seed several phases.
 * The file format: docs/mission-format.md; the design: docs/architecture.md.
 *
 *   lv_mission  the parsed, validated definition with its environment (planet, gravity,
 *               atmosphere, tables) and a plan per phase resolved once. Never changes after
 *               lv_mission_load; any number of threads may use one mission at once.
 *   lv_run      what varies and what results: a value for every number of the mission a run
 *               may vary (its PARAMETERS: "start_h", "stage2.propellant_mass",
 *               "P2.set.theta", "P2.stop_time", ...; `lvsim params MISSION` lists them),
 *               and each phase's result. lv_run_execute() simulates only the phases whose
 *               inputs changed since they last ran, and their descendants. One run is used
 *               by one thread at a time (its execute may use several worker threads).
 *
 *     lv_mission *m;   lv_mission_load("mission.yaml", &m, &err);
 *     lv_run *r;       lv_run_create(m, &r, &err);
 *     lv_run_execute(r, NULL, &err);                           every phase
 *     lv_run_set(r, "stage2.propellant_mass", 5200.0, &err);
 *     lv_run_execute(r, NULL, &err);                           the phases stage2 flies in
 *     lv_run_final(r, k, "h", &h, &err);
 *     lv_run_free(r);  lv_mission_free(m);
 *
 * The paper's Code 2 loop by hand: lv_run_prepare() gives phase k's model, instance and
 * settings with the start values of the hand-off filled in; call lv_simulate() yourself and
 * hand the outcome back with lv_run_complete() (examples/code2_loop.c).
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

/* Reads and validates a mission file: YAML syntax, keys, types, ranges, references, cycles,
 * masses, tables, and that every phase's model and initial state can be built. Errors are
 * "file:line:column: message" with LV_ERR_INPUT (LV_ERR_IO: the file cannot be read);
 * nothing runs. */
LV_API lv_status lv_mission_load(const char *path, lv_mission **out, lv_err *err);
LV_API void lv_mission_free(lv_mission *m); /* accepts NULL; no run of it may be left */

typedef struct lv_mission_info {
    const char *name;
    const char *description; /* NULL when the file has none */
    const char *path;        /* the mission file */
    const char *epoch;       /* ISO 8601 UTC of mission time 0 as written (23:59:60 only on
                                a leap-second day), or NULL; t counts SI seconds from it */
    int flat_world;          /* 1: flat world (the paper's test case), 0: planet */
    const char *planet;      /* "earth", "moon", "mars"; NULL on a flat world */
    double site_lat, site_lon; /* rad: a flat world's origin on the WGS-84 Earth */
    size_t n_phases, n_stages, n_params;
} lv_mission_info;
LV_API void lv_mission_get_info(const lv_mission *m, lv_mission_info *out);

LV_API const char *lv_mission_name(const lv_mission *m);
/* The files the mission reads: i = 0 the mission file, then every data file it names (tables,
 * wind, gravity coefficients), each once, in the order the parser met them, as it resolved
 * them (relative to the mission file's folder, or absolute when the file writes them so);
 * NULL past the end. What a package of the mission (an FMU, lv_fmu.h) must carry. */
LV_API size_t lv_mission_file_count(const lv_mission *m);
LV_API const char *lv_mission_file(const lv_mission *m, size_t i);

/* Flags of lv_output_check. */
enum { LV_OUTPUT_REPLACE = 1u /* an existing file may be replaced (the CLI's --force) */ };
/* Whether a command may write the file `path` of its own (a converged mission, an FMU, a
 * result file named by the user): refuses an empty name, a folder, a path that is the
 * mission file of `m` or one of its data files (compared by device and inode, so any
 * spelling of the path; m NULL: no mission) and a symbolic link (dangling or not) - always,
 * whatever the flags -, and an existing file unless LV_OUTPUT_REPLACE (then only a regular
 * file). A missing file is fine (its
 * folder is the writer's to check). Errors: LV_ERR_INPUT naming the path and what to do. */
LV_API lv_status lv_output_check(const char *path, const lv_mission *m, unsigned flags,
                                 lv_err *err);
LV_API size_t lv_mission_phase_count(const lv_mission *m);
/* Phases are numbered in run order: a phase after its parent; among the phases ready to run
 * (their parents done), in file order. With several worker threads, phases that are ready
 * together start together in that order. */
LV_API const char *lv_mission_phase_name(const lv_mission *m, size_t k);
LV_API int lv_mission_phase_parent(const lv_mission *m, size_t k); /* -1: from parameters */
LV_API lv_status lv_mission_phase_find(const lv_mission *m, const char *name, size_t *k,
                                       lv_err *err);
LV_API size_t lv_mission_stage_count(const lv_mission *m);
LV_API const char *lv_mission_stage_name(const lv_mission *m, size_t s);
/* Stage s's `geometry:` (m): 1 with length, diameter, span (0: no wing) when the mission gives
 * it, else 0 (the exports then draw a default shape). Any out pointer may be NULL. */
LV_API int lv_mission_stage_geometry(const lv_mission *m, size_t s, double *length,
                                     double *diameter, double *span);

typedef struct lv_phase_info {
    const char *name;
    const char *model;      /* its model type ("dof3", "flat6") */
    int parent;             /* -1: starts from the parameter set */
    size_t n_stages;        /* the stages it carries, bottom first */
    const size_t *stages;   /* [n_stages] stage indices */
    const char *method;     /* its integration method */
    size_t file_index;      /* its position in the mission file (0-based) */
    const char *handoff_rule; /* the rule of its conversion from a parent of another model
                                 ("rates: zero"), or NULL */
} lv_phase_info;
LV_API void lv_mission_phase_info(const lv_mission *m, size_t k, lv_phase_info *out);
/* The user's name of the separation phase k starts with (`separation: {name: ...}`), or NULL
 * (none, or k out of range). */
LV_API const char *lv_mission_phase_separation_name(const lv_mission *m, size_t k);

/* ---- parameters: the numbers a run may vary -------------------------------------------- */

typedef struct lv_param_info {
    const char *name;  /* "start_h", "stage2.propellant_mass", "P2.set.theta" */
    const char *unit;  /* SI; "1" dimensionless (lv_units.h) */
    double value;      /* the mission file's value (or the default when the file has none) */
    int line;          /* where the file writes it; 0: not written (a default) */
    const char *rule;  /* allowed values: "finite", ">= 0", "> 0" ... */
} lv_param_info;

LV_API size_t lv_mission_param_count(const lv_mission *m);
LV_API void lv_mission_param_info(const lv_mission *m, size_t i, lv_param_info *out);
/* Index of a parameter by name; "NAME_deg" finds an angle NAME (the value is then in
 * degrees: *deg = 1). LV_ERR_NOTFOUND suggests the nearest names. */
LV_API lv_status lv_mission_param_find(const lv_mission *m, const char *name, size_t *i,
                                       int *deg, lv_err *err);

/* ---- runs ----------------------------------------------------------------------------- */

typedef struct lv_run lv_run;

LV_API lv_status lv_run_create(const lv_mission *m, lv_run **out, lv_err *err);
LV_API void lv_run_free(lv_run *r); /* accepts NULL */
LV_API const lv_mission *lv_run_mission(const lv_run *r);

/* Sets a parameter by name (SI; "NAME_deg" takes degrees for an angle). The value must lie
 * in the parameter's range (LV_ERR_INPUT naming it and the rule); an unknown name is
 * LV_ERR_NOTFOUND with "did you mean". The phases that use it, and their descendants, run
 * again at the next lv_run_execute. Setting the value it already has changes nothing. */
LV_API lv_status lv_run_set(lv_run *r, const char *name, double value, lv_err *err);
LV_API lv_status lv_run_get(const lv_run *r, const char *name, double *value, lv_err *err);
/* The same by index (lv_mission_param_find: names resolved once). */
LV_API lv_status lv_run_set_index(lv_run *r, size_t i, double value, lv_err *err);
LV_API double lv_run_get_index(const lv_run *r, size_t i);
/* Every parameter back to the mission file's value. */
LV_API void lv_run_reset(lv_run *r);

typedef enum lv_phase_state {
    LV_PHASE_PENDING = 0,
    LV_PHASE_DONE,    /* simulated */
    LV_PHASE_FAILED,  /* its simulation failed (see error) */
    LV_PHASE_SKIPPED, /* an ancestor failed or crashed */
    LV_PHASE_CRASHED  /* not flown: its start is a crash (a touchdown beyond the landing gear's
                         limits; see error). Not a simulation failure: lv_run_execute succeeds */
} lv_phase_state;

/* The word for a phase state in every output (summary.json, the CLI's table, the report,
 * Python): "pending", "done", "failed", "skipped", "crashed". */
LV_API const char *lv_phase_state_name(lv_phase_state st);

/* What one phase did in a run. Owned by the run; valid until the phase runs again or
 * lv_run_free(). */
typedef struct lv_phase_result {
    const char *name;
    lv_phase_state state;
    char error[LV_ERR_MSG_MAX];  /* FAILED / SKIPPED / CRASHED: phase, time and reason */
    double t_start, t_end;       /* s */
    double t_stop;               /* s, its stop time (time limit) in this run */
    const char *method;          /* integration method and tolerance used */
    double tolerance;
    lv_sim_report report;        /* statistics, stop reason, event log */
    int end_index;               /* the phase's end condition (0-based, in file order) that
                                    ended it, or -1 (stop time, failure) */
    double end_value;            /* that condition's value (m, m/s) in this run, or NAN */
    size_t n_final;              /* the final state: time, every state and output, by name */
    const char *const *final_names;
    const double *final_values;
    const char *result_stem;     /* "OUTDIR/phase_<k>_<name>" when files were written */
    size_t n_event_names;        /* the phase model's state-event functions, by index: */
    const char *const *event_names; /*   report.event_log[i].index names one of them */
    /* the hand-off */
    size_t n_copied;             /* states copied from the parent */
    double mass_from_stages;     /* kg, the mass the stage book gave (NAN for a root) */
    double mass_start;           /* kg, the initial mass after overrides */
    size_t n_set;                /* the `set:` overrides with this run's values */
    const char *const *set_names;
    const double *set_values;
    /* the propellant book: every stage of the mission, kg; a phase burns only its bottom
     * stage's propellant (burnout when it is gone), and mass beyond its stages' dry mass and
     * propellant (a `set:` of the mass) is payload, never burnt */
    const double *propellant_start; /* [n_stages of the mission], kg at the phase's start */
    const double *propellant_end;   /* [n_stages of the mission], kg left after the phase */
    const double *dry_mass;         /* [n_stages of the mission], kg in this run */
    double payload;                 /* kg, the start mass beyond the carried stages */
    unsigned result_formats;     /* the files written under result_stem: LV_RESULT_MAT |
                                    LV_RESULT_CSV (0 when result_stem is NULL) */
    /* what the hand-off absorbed: the parent's final quantities the phase's state cannot
     * hold (a touchdown on a runway: the height above the runway plane, the sink rate, the
     * lateral offset and speed), by name, SI unit and value */
    size_t n_absorbed;
    const char *const *absorbed_names;
    const char *const *absorbed_units;
    const double *absorbed_values;
    /* the user's names of its events (`name:` in the mission file; docs/mission-format.md,
     * "Named events"): end_label names the end that ended it (its own `name:`, else the
     * phase's `end_name:`), NULL when unnamed or not ended by an event; event_labels[i] names
     * report.event_log[i] (the stopping event, an engine-out), NULL each unnamed one; the
     * array itself is NULL when none is named */
    const char *end_label;
    const char *const *event_labels;
} lv_phase_result;

typedef struct lv_run_options {
    const char *outdir;   /* result files go here (created); NULL: no files */
    int threads;          /* worker threads for independent branches (0: 2; at most 16 are
                             used) */
    /* Called after each phase, from the thread that ran it, under the run's lock. */
    void (*on_phase)(const lv_run *r, size_t k, const lv_phase_result *res, void *user);
    void *user;           /* passed to on_phase and progress */
    double output_interval; /* > 0: overrides every phase's output grid (s), e.g. to compare;
                               0: each phase's own */
    const char *method;   /* non-NULL: every phase integrates with this method (lv_sim_methods) */
    double tolerance;     /* nonzero: every phase uses this tolerance, within [LV_TOLERANCE_MIN,
                             LV_TOLERANCE_MAX] (lv_sim.h); 0: each phase's own */
    /* Called with the mission time reached in phase k at every output row, from the thread
     * that runs it; nonzero cancels the run (the phase fails with LV_ERR_CANCELLED). */
    int (*progress)(const lv_run *r, size_t k, double t, void *user);
    int no_rows;          /* 1: keep no rows in memory (no merged trajectories): faster */
    /* With outdir: the files of each phase, LV_RESULT_MAT | LV_RESULT_CSV; 0: both (the
     * default); LV_RUN_NO_PHASE_FILES: neither (summary and bodies may still be written). */
    unsigned result_formats;
    /* [n_phases] or NULL (every phase): nonzero for the phases whose results are wanted
     * (a targeting loop's constraints). Only those and their ancestors are simulated; a phase
     * outside them whose inputs changed is left PENDING for a later execute. */
    const unsigned char *want;
    /* NULL, or a flag another thread (a signal handler) may set nonzero to stop the run: each
     * running phase is cancelled within one integrator step (lv_sim_settings.stop: read at
     * every right-hand side evaluation and output row), and no phase starts after (they
     * fail with LV_ERR_CANCELLED, "stopped"); lv_run_execute returns LV_ERR_CANCELLED. Costs
     * no callback: bindings use it for Ctrl-C. */
    const volatile int *stop;
    /* > 0: the most output rows one phase may write (its output grid's points; the two rows
     * of each event instant are not counted). Before anything runs, lv_run_execute refuses
     * (LV_ERR_INPUT, lv_run_check_output) a phase to run that only its stop time (or a `time`
     * end) can end and whose grid over its longest possible duration has more rows (a child
     * whose parent has not run: as it is about to start, when its start is known); a phase
     * with other ends (burnout, altitude, ...) is not refused for a generous stop_time but
     * stopped as it runs: when it reaches max_rows rows before an end fires it fails
     * (LV_ERR_SOLVER, the phase, the time reached, the rows and the limit; its files kept as
     * *.failed.*). 0: no limit. */
    double max_rows;
} lv_run_options;

#define LV_RUN_NO_PHASE_FILES 0x100u /* lv_run_options.result_formats: no phase files */

/* Simulates every phase whose inputs changed since it last ran (or that never ran, or
 * failed), and its descendants; the others keep their results. Independent branches run in
 * parallel threads; a failing phase stops only its descendants. Returns LV_OK when all
 * succeeded, LV_ERR_SOLVER when some failed (their results say why; the others are
 * complete), LV_ERR_CANCELLED, LV_ERR_IO when the output folder cannot be made, LV_ERR_INPUT
 * (nothing runs) for options out of range: a tolerance outside [LV_TOLERANCE_MIN,
 * LV_TOLERANCE_MAX] (not 0), a negative or non-finite output_interval, an unknown method,
 * negative threads. */
LV_API lv_status lv_run_execute(lv_run *r, const lv_run_options *opt, lv_err *err);
/* How many phases the last lv_run_execute simulated. */
LV_API size_t lv_run_simulated(const lv_run *r);

#define LV_RUN_ALL_PHASES ((size_t)-1) /* lv_run_invalidate: every phase */
/* Marks phase k (LV_RUN_ALL_PHASES: every phase) to run again at the next lv_run_execute,
 * and with it its descendants, as a changed input would (e.g. because the options that shape
 * its results - method, tolerance, output grid, rows kept - differ from those it ran with).
 * Its result stays readable until then; lv_run_stale says it is out of date. LV_ERR_INPUT
 * for k out of range. */
LV_API lv_status lv_run_invalidate(lv_run *r, size_t k, lv_err *err);
/* 1 when phase k's result is out of date: an input of it or of an ancestor changed since it
 * ran (lv_run_set, lv_run_disperse, lv_run_invalidate) and no lv_run_execute ran it again;
 * also for a phase never run. 0 otherwise, and for k out of range. */
LV_API int lv_run_stale(const lv_run *r, size_t k);

LV_API const lv_phase_result *lv_run_result(const lv_run *r, size_t k);
/* A final value of a done phase by name ("time", "z", "m", ...). */
LV_API lv_status lv_run_final(const lv_run *r, size_t k, const char *name, double *value,
                              lv_err *err);
/* Phase k's rows in memory (every output row and event instant), or NULL. */
LV_API const lv_result *lv_run_rows(const lv_run *r, size_t k);

/* ---- the instantaneous impact point at given times (a phase's `iip_at:`) -------------------
 *
 * A phase that lists `iip_at: [t1, t2, ...]` (mission times, s) records, in every run, its
 * iip_* outputs (docs/models.md, "Instantaneous impact point") at exactly those times: the
 * integrator stops there on its own interpolation (lv_sim_advance: the same steps, rows and
 * final values as without) and the outputs are evaluated at that state. Design and use in
 * Monte Carlo campaigns: docs/monte-carlo.md, "The IIP at given times". */
typedef enum lv_iip_state {
    LV_IIP_IMPACT = 0,     /* flying at t with an impact point: lat, lon, tof, range hold it */
    LV_IIP_IN_ORBIT = 1,   /* flying at t, its drag-free path meets no ground (NaN outputs) */
    LV_IIP_NOT_FLYING = 2  /* the phase did not fly at t: it started later, ended earlier (an
                              end, its stop time, a failure before t), or did not run */
} lv_iip_state;

typedef struct lv_iip_sample {
    double t;           /* s, mission time (the phase's iip_at entry) */
    lv_iip_state state;
    double lat, lon;    /* rad, geodetic latitude and longitude of the impact point */
    double tof;         /* s, time of flight from t to the impact */
    double range;       /* m, great-circle range from the point under the vehicle at t */
} lv_iip_sample;       /* lat, lon, tof, range are NaN unless state is LV_IIP_IMPACT */

/* How many times phase k lists in `iip_at:` (0 when none, or k out of range). */
LV_API size_t lv_mission_phase_iip_count(const lv_mission *m, size_t k);
/* Phase k's i-th IIP sample of the run's last execute (LV_IIP_NOT_FLYING before any).
 * LV_ERR_INPUT when k or i is out of range. */
LV_API lv_status lv_run_iip(const lv_run *r, size_t k, size_t i, lv_iip_sample *out,
                            lv_err *err);

/* How far a phase's re-simulation drifts from its `reference:` (an optimiser's trajectory;
 * docs/optimal-control.md, "Importing an optimiser's trajectory"), compared at the phase's
 * result rows whose time (or tau) lies within the reference's range, the reference
 * interpolated there. Position: the 3-D distance between the two ECEF positions (from the
 * geodetic h, lat, lon of each), m; velocity: the magnitude of the difference of the two
 * velocities relative to the rotating planet (ECEF; the reference's from v, fpa, heading), m/s;
 * mass: |m_sim - m_ref|, kg. _max is the largest over the rows, at mission time _max_t;
 * _final the value at the last row compared (time t_final). A row up to 1e-6 of the
 * reference's span beyond either end of it is compared too (the position extrapolated with the
 * end row's velocity): a phase end located by an event next to the optimiser's final time. */
typedef struct lv_ref_drift {
    size_t n_rows;              /* result rows compared; 0: none lay in the reference's range */
    int over_tau;               /* 1: the reference is over tau = (t - t_start) / (t_stop -
                                   t_start), 0: over mission time */
    int start_from_reference;   /* 1: `start: reference` (the phase started from its first row) */
    double t_first, t_final;    /* s, mission time of the first and last row compared */
    double pos_max, pos_max_t, pos_final;    /* m, s, m */
    double vel_max, vel_max_t, vel_final;    /* m/s, s, m/s */
    double mass_max, mass_max_t, mass_final; /* kg, s, kg */
    double ref_end;             /* the reference's last axis value: s, or tau [1] */
    double phase_end;           /* the phase's end on that axis: its last row's time [s], or
                                   tau there (< 1: it ended before its stop_time, and the tau
                                   reference was laid over a span it did not fly) */
} lv_ref_drift;

/* One compared row of lv_run_reference_rows: the simulation's and the reference's geodetic
 * altitude, speed relative to the planet and mass, and the differences of lv_ref_drift. */
typedef struct lv_ref_row {
    double t;                   /* s, mission time of the result row */
    double h, h_ref;            /* m */
    double v, v_ref;            /* m/s */
    double m, m_ref;            /* kg */
    double d_pos, d_vel, d_mass; /* m, m/s, kg */
} lv_ref_row;

/* 1 if phase k has a `reference:` (0 when not, or k out of range). */
LV_API int lv_mission_phase_has_reference(const lv_mission *m, size_t k);
/* Phase k's drift from its reference in the run's last execute. LV_ERR_NOTFOUND when the phase
 * has no reference, has not run, or ran without keeping its rows (lv_run_options.no_rows);
 * LV_ERR_INPUT when k is out of range. */
LV_API lv_status lv_run_reference_drift(const lv_run *r, size_t k, lv_ref_drift *out,
                                        lv_err *err);
/* The rows behind it: *rows[0 .. *n - 1] (owned by the run, valid until its next execute or
 * lv_run_free); the same errors. */
LV_API lv_status lv_run_reference_rows(const lv_run *r, size_t k, const lv_ref_row **rows,
                                       size_t *n, lv_err *err);

/* ---- output size, before running --------------------------------------------------------- */

/* What phase k will write at most with the run's current values: its output grid over its
 * longest possible duration: its stop time, or its first `time` end when that comes earlier,
 * minus its start_time, or minus the end of its parent when that is done and up to date in
 * this run, else minus the parent's earliest start. Each event instant adds two rows more
 * (not counted). The other ends (burnout, altitude, speed, apogee, impact, a variable's
 * crossing) are not estimated: when they fire is known only by running. */
typedef struct lv_output_estimate {
    double duration;   /* s */
    double rows;       /* output grid points */
    size_t n_signals;  /* columns: time, states, their derivatives, outputs */
    double bytes_mat;  /* the .mat file's data: 8 bytes a value (and the run's rows in
                          memory when it keeps them: lv_run_options.no_rows = 0) */
    double bytes_csv;  /* the .csv file: about 22 bytes a value (%.17g and a comma) */
    int bounded;       /* 1: rows is a bound known now: only the stop time (or a `time` end)
                          ends the phase and its start is known; 0: it has other ends, which
                          may end it earlier, and rows is what its stop time allows
                          (lv_run_options.max_rows is then enforced as it runs), or it is a
                          child whose parent has not run, counted from the parent's earliest
                          start (its rows are checked when it is about to start) */
} lv_output_estimate;
/* `output_interval` > 0: the grid lv_run_options.output_interval would impose. */
LV_API lv_status lv_run_estimate_output(const lv_run *r, size_t k, double output_interval,
                                        lv_output_estimate *out, lv_err *err);

/* The up-front half of opt->max_rows (lv_run_options; nothing runs): LV_ERR_INPUT when a
 * phase lv_run_execute(r, opt) would run (opt->want and their ancestors; every phase when
 * want is NULL) is bounded (lv_output_estimate.bounded) and its grid, with
 * opt->output_interval, has more than opt->max_rows rows. The message names the first such
 * phase, its rows and mission time (as "1.4e+11 rows", "140 s"), columns, bytes, the limit,
 * the other phases over it, and a limit that allows them all. LV_OK when none is, when opt is
 * NULL or opt->max_rows is 0. A child phase whose parent has not run yet is checked the same
 * way by lv_run_execute as it is about to start (its start, the parent's end, known then); it
 * fails then with this message, and is not simulated. */
LV_API lv_status lv_run_check_output(const lv_run *r, const lv_run_options *opt, lv_err *err);

/* ---- the bodies: each stage's trajectory across the phases it flies in ------------------ */

/* The phases stage `s` flies in, done, in time order; returns the count written to `out`
 * (capacity: the mission's phase count). */
LV_API size_t lv_run_body_phases(const lv_run *r, size_t s, size_t *out);

typedef struct lv_body_traj {
    const char *stage;             /* the stage's name */
    size_t n_rows, n_cols;
    const char *const *names;      /* [n_cols]: "time", the model's columns, "stage_mass" ... */
    const char *const *units;      /* [n_cols] */
    const double *values;          /* [n_rows * n_cols], row-major */
    const size_t *phase;           /* [n_rows]: the phase each row comes from */
} lv_body_traj;

/* Stage s's merged trajectory: every row of every done phase it flies in, in time order,
 * with the stage's own mass (the bottom stage: the body's mass minus the stages above it).
 * Needs the rows (lv_run_options.no_rows = 0). lv_body_traj_free when done. */
LV_API lv_status lv_run_body_trajectory(const lv_run *r, size_t s, lv_body_traj **out,
                                        lv_err *err);
LV_API void lv_body_traj_free(lv_body_traj *b);

/* ---- the paper's Code 2 loop by hand ------------------------------------------------------ */

typedef struct lv_phase_call lv_phase_call;

/* Phase k of run r, ready to simulate: its model built from the run's values and the stage
 * book, and settings with its start and stop time, grid, method and tolerance, the hand-off
 * as initial names and values (the parameter set for a root phase; the parent's final states,
 * the carried stages' mass and the overrides otherwise), every state and output as final
 * names, and a memory sink for the run's rows. The parent must be done in this run. */
LV_API lv_status lv_run_prepare(lv_run *r, size_t k, lv_phase_call **out, lv_err *err);
LV_API const lv_model_def *lv_phase_call_model(const lv_phase_call *c);
LV_API void *lv_phase_call_inst(lv_phase_call *c);
/* Yours to adjust before simulating (e.g. result_file); keep its sinks, add none. */
LV_API lv_sim_settings *lv_phase_call_settings(lv_phase_call *c);
LV_API double *lv_phase_call_finals(lv_phase_call *c); /* [settings->n_final] */
/* Records what lv_simulate returned (st, its err and report, whose event log moves into the
 * result) as phase k's result: its children can then be prepared. Frees the call. */
LV_API lv_status lv_run_complete(lv_run *r, lv_phase_call *c, lv_status st, const lv_err *sim_err,
                                 lv_sim_report *rep, lv_err *err);
LV_API void lv_phase_call_free(lv_phase_call *c); /* a call not completed; accepts NULL */

/* ---- the phase-model types: what a phase's `model:` may name ---------------------------- */

typedef struct lv_phase_type_info {
    const char *name;           /* "flat6", "dof3" */
    const char *description;    /* one line */
    int flat_world;             /* 1: flies in the flat world; 0: over a planet */
    const char *const *keys;    /* the phase keys it reads besides the common ones,
                                   NULL-terminated; may be NULL */
    size_t n_mission_params;    /* what a root phase takes from the mission's `parameters:` */
    const lv_var *mission_params;
    const char *mass_state;     /* the state holding the vehicle's mass: "m" */
    const char *const *ends;    /* the named end conditions its `end:` takes (NULL-terminated),
                                   or NULL: all of lv_phase_types_end_name */
} lv_phase_type_info;

/* The registered types, in registry order: i = 0 .. count - 1. */
LV_API size_t lv_phase_types_count(void);
LV_API lv_status lv_phase_types_get(size_t i, lv_phase_type_info *out, lv_err *err);

/* A type's model as a phase of a sample mission builds it (one stage of 1000 kg dry and
 * 4000 kg of propellant, one constant engine, one phase of 10 s; a planet type flies over the
 * WGS-84 Earth): its states, parameters, outputs and events are those of every phase of the
 * type, by name and unit (the names of `set:`, `end:` and the result files); the values are
 * the sample's. LV_ERR_NOTFOUND for an unknown name (the message lists the types). */
typedef struct lv_phase_sample lv_phase_sample;
LV_API lv_status lv_phase_types_sample(const char *name, lv_phase_sample **out, lv_err *err);
LV_API const lv_model_def *lv_phase_types_sample_model(const lv_phase_sample *s);
LV_API void lv_phase_types_sample_free(lv_phase_sample *s); /* accepts NULL */

/* The end conditions a phase's `end:` may name ("burnout", "altitude", "speed", "apogee",
 * "impact"): i = 0 .. count - 1. */
LV_API size_t lv_phase_types_end_count(void);
LV_API const char *lv_phase_types_end_name(size_t i);

/* ---- sequential versus end-to-end (the paper's Table 2) ------------------------------------- */

typedef struct lv_compare_side {
    char method[32];
    double tolerance;
    size_t n_states;       /* per model (sequential: the largest phase model) */
    long state_events, time_events, steps, rhs_evals, jac_evals;
    double cpu_time;       /* s, sum over phases */
    long rhs_evals_steps, rhs_evals_output; /* rhs_evals split (lv_sim_stats) */
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
 * split the stack at their ends), both with `method`/`tolerance` (NULL/0: each phase's own;
 * otherwise as lv_run_options: LV_ERR_INPUT out of range) and the output interval `dt` (s,
 * > 0), and compares every body at every output time of its sequential phases (each phase's
 * grid starts at its own start), the end-to-end model read there by its integrator's
 * interpolation; event and separation instants are left out. The sequential rows are held in
 * memory: `max_rows` (> 0; 0: no limit) bounds each phase's as lv_run_options.max_rows does,
 * before anything runs and as it runs. A failed phase's message is the error's. */
LV_API lv_status lv_mission_compare(const lv_mission *m, const char *method, double tolerance,
                                    double dt, double max_rows, lv_compare_report *rep,
                                    lv_err *err);

#ifdef __cplusplus
}
#endif
#endif
