/* mission.h - the mission as data: environment, stages, the shared parameter set (the
 * paper's userPar) and the phase tree. Built by the YAML parser (parse.c), validated
 * before anything runs, read by the runner (runner.c). Immutable during a run.
 *
 * Units: everything here is SI and radians; the parser converts "*_deg" keys.
 */
#ifndef LV_MISSION_MISSION_H
#define LV_MISSION_MISSION_H

#include <stddef.h>

#include "lvsim/lv_model.h"
#include "lvsim/lv_status.h"
#include "lvsim/lv_table.h"

/* Where a value came from in the mission file, for messages after parsing. */
typedef struct lv_src_loc {
    int line, column; /* 1-based; 0 when not from a file */
} lv_src_loc;

/* ---- environment ---------------------------------------------------------------------- */

typedef enum lv_world_kind {
    LV_WORLD_FLAT = 0, /* flat, non-rotating; uniform gravity g along -z (paper test case) */
    LV_WORLD_PLANET = 1 /* rotating ellipsoidal planet (3-DoF model) */
} lv_world_kind;

typedef struct lv_env_def {
    lv_world_kind world;
    double g;             /* m/s^2, flat world: uniform gravity magnitude (default 9.81) */
    char *planet;         /* planet world: "earth" (WGS-84, default), "moon", "mars"; NULL: flat */
    char *gravity;        /* planet world: gravity spec, e.g. "j2", "sh:8" (default "j2");
                             NULL on a flat world */
    char *atmosphere;     /* "us76" (default for earth), "exp", "none" */
    double site_lat, site_lon; /* rad: flat world: geodetic position of the origin (WGS-84) */
    char *atmo_file, *atmo_var; /* atmosphere "table": the file (resolved) and .mat variable */
    char *wind_file, *wind_var; /* wind table over altitude, or NULL: no wind */
    lv_src_loc wind_loc;
    lv_src_loc loc;
} lv_env_def;

/* ---- vehicle ---------------------------------------------------------------------------- */

/* One engine. Either constant (thrust_vac with isp or mdot) or from a time table with
 * outputs "thrust" [N] and "mdot" [kg/s] (table time is mission time, s). */
typedef struct lv_engine_def {
    char *name;
    double thrust_vac; /* N, vacuum thrust (constant engines) */
    double isp_vac;    /* s, vacuum specific impulse (0: use mdot) */
    double mdot;       /* kg/s, mass flow (0: from isp) */
    double exit_area;  /* m^2, nozzle exit area (thrust loss p_amb * A_exit) */
    int count;         /* identical engines (default 1) */
    char *table_file;  /* thrust/mdot time table: CSV or .mat path (resolved) */
    char *table_var;   /* variable name inside a .mat file */
    lv_table *table;   /* loaded by the parser; owned */
    size_t thrust_out; /* table: index of the thrust output [N] (resolved by the parser) */
    size_t mdot_out;   /* table: index of the mass-flow output [kg/s] */
    lv_src_loc loc;
} lv_engine_def;

typedef struct lv_stage_def {
    char *name;
    double dry_mass;        /* kg */
    double propellant_mass; /* kg, at liftoff */
    size_t n_engines;
    lv_engine_def *engines;
    lv_src_loc loc;
} lv_stage_def;

/* ---- phases ------------------------------------------------------------------------------- */

typedef enum lv_end_kind {
    LV_END_BURNOUT = 0, /* propellant of the burning stage exhausted */
    LV_END_ALTITUDE,    /* altitude crosses `value` (m) */
    LV_END_SPEED,       /* speed crosses `value` (m/s) */
    LV_END_APOGEE,      /* vertical/radial velocity falls through zero */
    LV_END_IMPACT       /* altitude falls through `value` (m, default 0) */
} lv_end_kind;

typedef struct lv_end_def {
    lv_end_kind kind;
    double value;
    lv_dir direction;
    lv_src_loc loc;
} lv_end_def;

typedef struct lv_phase_def {
    char *name;
    char *model;          /* "flat6" (6-DoF point mass, flat world) or "dof3" */
    size_t n_stages;      /* the bodies this phase carries, bottom first */
    size_t *stages;       /* indices into lv_mission_def.stages */
    int parent;           /* index of the phase whose final state seeds this one; -1: parameters */
    double t_start;       /* s; NAN: the parent's end time (or 0 without parent) */
    double t_stop;        /* s; the fixed stop time or the time limit of the phase */
    size_t n_ends;        /* events that end the phase before t_stop */
    lv_end_def *ends;
    char *method;         /* integrator, default "dassl" */
    double tolerance;     /* default 1e-6 */
    int intervals;        /* numberOfIntervals (0: use output_interval or 500) */
    double output_interval; /* s */
    double fixed_step;    /* s */
    size_t n_set;         /* overrides applied after the hand-off: name = value (SI) */
    char **set_names;
    double *set_values;
    lv_src_loc *set_locs; /* [n_set] where each override was written, for later messages */
    /* dof3 only: inputs (NAN: the model's default) and a control history over time */
    double alpha, beta, mu; /* rad */
    double throttle;        /* - */
    char *inputs_file, *inputs_var;
    lv_table *inputs;       /* outputs alpha, beta, mu [rad], throttle; owned */
    /* dof3 only: the phase's aerodynamic dataset */
    int has_aero;
    int aero_body_axes;     /* 0: CD, CL, CY (wind axes); 1: CA, CN, CY (body axes) */
    double aero_s_ref;      /* m^2 */
    double aero_coef[3];    /* constant coefficients, NAN: from the table (or 0) */
    char *aero_file, *aero_var;
    lv_table *aero_table;   /* outputs named as the coefficients; owned */
    lv_src_loc loc;
} lv_phase_def;

/* ---- mission --------------------------------------------------------------------------------- */

typedef struct lv_mission_def {
    char *name;
    char *description;
    char *epoch;   /* ISO 8601 UTC of mission time 0, or NULL (exports use 2000-01-01T12:00:00Z) */
    char *path;    /* the mission file */
    char *dir;     /* its directory: relative table paths resolve against it */
    lv_env_def env;
    size_t n_params; /* the shared parameter set, SI (start_lat, start_h, ...) */
    char **param_names;
    double *param_values;
    size_t n_stages;
    lv_stage_def *stages;
    size_t n_phases; /* in file order; parents always precede children after validation */
    lv_phase_def *phases;
} lv_mission_def;

/* Parse and validate a mission file. Errors are "file:line:column: message". */
lv_status lv_mission_def_load(const char *path, lv_mission_def **out, lv_err *err);
/* The same from memory (`name` is used in messages; relative paths resolve against `dir`). */
lv_status lv_mission_def_parse(const char *text, size_t len, const char *name, const char *dir,
                               lv_mission_def **out, lv_err *err);
void lv_mission_def_free(lv_mission_def *m);

/* Parameter value by name, or `fallback` when the mission does not set it. */
double lv_mission_def_param(const lv_mission_def *m, const char *name, double fallback);

#endif
