/* mission.h - the mission as data: environment, stages, the shared parameter set (the
 * paper's userPar) and the phase tree. Built by the YAML parser (parse.c), validated before
 * anything runs, never changed afterwards: runs (run.c) only read it.
 *
 * Numbers a run may vary are SLOTS: every numeric key of the file a user would want to vary
 * (a parameter, a stage's masses, an engine's thrust, a phase's stop time, end values,
 * overrides, the model's inputs...) is registered under a name ("start_h",
 * "stage2.propellant_mass", "P2.set.theta", "P2.inputs.alpha") with its unit, its allowed
 * range, the file position and the value the file gives. The definition keeps slot indices,
 * never the numbers themselves: a run holds one value per slot, and every model is built from
 * the run's values. Units: everything SI and radians; the parser converts "*_deg" keys.
 */
#ifndef LV_MISSION_MISSION_H
#define LV_MISSION_MISSION_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "lvsim/lv_model.h"
#include "lvsim/lv_planet.h"
#include "lvsim/lv_sim.h"
#include "lvsim/lv_status.h"
#include "lvsim/lv_table.h"
#include "lvsim/lv_units.h"
#include "lvsim/lv_wind.h"

/* Where a value came from in the mission file, for messages after parsing. */
typedef struct lv_src_loc {
    int line, column; /* 1-based; 0 when not from a file */
} lv_src_loc;

/* ---- slots: the numbers a run may vary ------------------------------------------------- */

typedef size_t lv_slot;
#define LV_NO_SLOT ((lv_slot)-1)

/* Allowed values: lo < v (lo_open) or lo <= v, and v < hi / v <= hi; always finite. */
typedef struct lv_range {
    double lo, hi;
    unsigned char lo_open, hi_open;
} lv_range;

/* Who owns a slot: which phases use its value directly (their descendants follow). */
typedef enum lv_slot_owner {
    LV_OWN_ENV = 0,   /* the environment: every phase */
    LV_OWN_PARAM,     /* the shared parameter set: the phases whose model has the parameter */
    LV_OWN_STAGE,     /* stage `owner_index` (and its engines): the phases that carry it */
    LV_OWN_PHASE      /* phase `owner_index` */
} lv_slot_owner;

typedef struct lv_slot_def {
    char *name;        /* unique in the mission */
    char *unit;        /* SI ("m", "kg", "rad", "" for dimensionless) */
    double value;      /* the value the file gives (or the default when not written) */
    lv_range range;
    lv_slot_owner owner;
    size_t owner_index;
    lv_src_loc loc;    /* where the value is written; 0 when defaulted */
} lv_slot_def;

/* ---- environment ---------------------------------------------------------------------- */

typedef enum lv_world_kind {
    LV_WORLD_FLAT = 0, /* flat, non-rotating; uniform gravity g along -z (paper test case) */
    LV_WORLD_PLANET = 1 /* rotating ellipsoidal planet (3-DoF model) */
} lv_world_kind;

/* A planet given by its constants (`planet: {radius: .., gm: ..}`) instead of a preset.
 * Constants the file writes are slots (owner LV_OWN_ENV); the others come from `base`. */
typedef struct lv_planet_def {
    int custom;              /* 0: the preset named by lv_env_def.planet */
    int has_base;            /* `base:` written: the constants not written are the preset's */
    lv_planet base;          /* the preset, or a = 0 (radius required), f 0, omega 0, no J;
                                name: the planet's name */
    lv_slot radius;          /* m, equatorial radius a; LV_NO_SLOT: base's */
    lv_slot flattening;      /* -, (a - b) / a; LV_NO_SLOT: base's */
    lv_slot gm;              /* m^3/s^2; LV_NO_SLOT: base's */
    lv_slot rotation_rate;   /* rad/s about +z; LV_NO_SLOT: base's */
    lv_slot r_ref;           /* m, reference radius of the zonal coefficients; LV_NO_SLOT:
                                base's with a base, else the radius */
    double sutton_graves_k;  /* kg^0.5/m, the heat flux's gas constant; NaN: the base's
                                (lv_kit_heating) */
    int zonal_given;         /* `zonal:` written (it replaces base's J2..J4, even when empty) */
    size_t n_zonal;          /* J2 .. J_(n_zonal + 1) */
    lv_slot *zonal;          /* [n_zonal] */
    char *coef_file;         /* ICGEM coefficient file for gravity sh (resolved), or NULL */
    lv_src_loc loc;          /* the planet mapping */
} lv_planet_def;

typedef struct lv_env_def {
    lv_world_kind world;
    lv_slot g;            /* m/s^2, flat world: uniform gravity magnitude (default 9.81) */
    char *planet;         /* planet world: "earth" (WGS-84, default), "moon", "mars", or the
                             name of a planet given by its constants; NULL: flat */
    lv_planet_def pdef;   /* planet world: the planet's constants when pdef.custom */
    char *gravity;        /* planet world: gravity spec, e.g. "j2", "sh:8" (default "j2";
                             "zonal" for a planet by its constants, "sh" with a coefficient
                             file); NULL on a flat world */
    lv_src_loc gravity_loc;
    char *atmosphere;     /* "us76" (default on the Earth), "exp", "table", "profile", "none" */
    lv_slot atmo_par[3];  /* "exp": rho0 [kg/m^3], scale height H [m], temperature T [K];
                             LV_NO_SLOT: the model's default */
    lv_src_loc atmo_loc;
    double site_lat, site_lon; /* rad: flat world: geodetic position of the origin (WGS-84) */
    char *atmo_file, *atmo_var; /* atmosphere "table": the file (resolved) and .mat variable */
    char *wind_file, *wind_var; /* wind table over altitude, or NULL: no wind (or constant) */
    lv_interp wind_interp;      /* the wind table's interpolation (default linear) */
    lv_extrap wind_extrap;      /* and its extrapolation (default clamp) */
    lv_slot wind_ned[3];  /* m/s: a constant wind's north, east, down; LV_NO_SLOT: none (or a
                             table); down not written: LV_NO_SLOT with north and east given */
    int wind_const;       /* 1: the constant wind of wind_ned */
    lv_src_loc wind_loc;
    double atmo_blend;    /* m: atmosphere "profile" (atmo_file): the blend band into US76 */
    size_t n_wind_prof;   /* wind from profiles: their number (0: none) */
    char **wind_prof_file; /* [n_wind_prof] the files (resolved) */
    double *wind_prof_t;  /* [n_wind_prof] s, the mission time each is valid at */
    double wind_blend;    /* m: the winds' taper to zero above each profile's top */
    /* gusts and turbulence (docs/wind.md, "Gusts and turbulence"): slots
     * "environment.gust<k>.altitude", ".half_width", ".north", ".east", ".down" (k from 1), and
     * "environment.turbulence.sigma", ".sigma_vertical" (default: the file's sigma), ".length",
     * ".from", ".to" */
    size_t n_gusts;
    lv_slot gust[LV_GUSTS_MAX][5];
    int turbulent;
    lv_slot turb[5];
    uint64_t turb_seed;   /* the realisation `lvsim run` flies (turbulence `seed:`, default 1) */
    lv_src_loc gust_loc, turb_loc;
    lv_src_loc loc;
} lv_env_def;

/* ---- vehicle ---------------------------------------------------------------------------- */

/* One engine. Either constant (thrust_vac with isp or mdot) or from a time table with
 * outputs "thrust" [N] and "mdot" [kg/s] (table time is mission time, s). */
typedef struct lv_engine_def {
    char *name;
    lv_slot thrust_vac; /* N, vacuum thrust (constant engines; LV_NO_SLOT for tables) */
    lv_slot isp_vac;    /* s, vacuum specific impulse (LV_NO_SLOT: mdot given) */
    lv_slot mdot;       /* kg/s, mass flow (LV_NO_SLOT: from isp) */
    lv_slot exit_area;  /* m^2, nozzle exit area (thrust loss p_amb * A_exit), default 0 */
    lv_slot throttle_min, throttle_max; /* the throttle range, default [0, 1] */
    int count;          /* identical engines (default 1) */
    char *table_file;   /* thrust/mdot time table: CSV or .mat path (resolved) */
    char *table_var;    /* variable name inside a .mat file */
    lv_table *table;    /* loaded by the parser; owned */
    size_t thrust_out;  /* table: index of the thrust output [N] (resolved by the parser) */
    size_t mdot_out;    /* table: index of the mass-flow output [kg/s] */
    lv_src_loc loc;
} lv_engine_def;

/* A stage's rigid-body data (`rigid_body:`, docs/mission-format.md), for the phases it burns
 * in as the bottom stage of a 6-DoF model (lv_dof6.h): the mass properties of the whole stack
 * the phase flies, with the stage's propellant full and empty, and its engines' geometry.
 * Body axes (x forward, z down in the plane of symmetry) from a structural origin. */
typedef struct lv_rigid_body_def {
    int present;                  /* `rigid_body:` given */
    lv_slot inertia_full[6];      /* kg m^2: tensor elements xx, yy, zz, xy, xz, yz */
    lv_slot inertia_empty[6];     /* kg m^2 (default: the full values as written) */
    lv_slot cg_full[3];           /* m (default 0) */
    lv_slot cg_empty[3];          /* m (default: the full values as written) */
    lv_slot engine_pos[3];        /* m, the engines' gimbal point (required with engines;
                                     0 without: no thrust acts there) */
    lv_slot mis_pitch, mis_yaw;   /* rad, thrust misalignment (default 0) */
    int has_exit;                 /* `nozzle_exit:` given */
    lv_slot nozzle_exit[3];       /* m, the engines' nozzle exit centre (jet damping); with
                                     has_exit 0 the jet damping takes engine_pos */
    /* `terms:` the switchable rigid-body terms (lv_dof6_terms; docs/models.md, "Rigid-body
     * terms"): 1 on / 0 off; rate_damping_frame 0 air, 1 inertial. Defaults 1, 1, 0. */
    int jet_damping, inertia_rate, rate_damping_frame;
    lv_src_loc loc;
} lv_rigid_body_def;

/* The landing gear's limits at touchdown (a stage's `landing_gear:`; docs/models.md,
 * "Landing gear limits at touchdown"): what a touchdown on a runway may have. */
typedef enum lv_gear_limit {
    LV_GEAR_SINK_RATE = 0, /* m/s, sink rate (descending positive) at most */
    LV_GEAR_LATERAL_SPEED, /* m/s, |speed across the centre line| at most */
    LV_GEAR_GROUND_SPEED,  /* m/s, horizontal speed relative to the ground at most */
    LV_GEAR_BANK,          /* rad, |roll attitude| at most */
    LV_GEAR_PITCH_MIN,     /* rad, pitch attitude at least (main gear first) */
    LV_GEAR_PITCH_MAX,     /* rad, pitch attitude at most (tail strike) */
    LV_GEAR_N
} lv_gear_limit;

/* Each limit's key (`landing_gear: {sink_rate_max: ..}`; angles also NAME_deg), SI unit and
 * the default a stage without `landing_gear:` (or a key not written) has. */
typedef struct lv_gear_key {
    const char *key;
    const char *unit;
    double dflt;
    int angle;
} lv_gear_key;
extern const lv_gear_key lv_gear_keys[LV_GEAR_N];

typedef struct lv_stage_def {
    char *name;
    lv_slot dry_mass;        /* kg */
    lv_slot propellant_mass; /* kg, at liftoff */
    size_t n_engines;
    lv_engine_def *engines;
    lv_rigid_body_def rigid; /* 6-DoF data (rigid.present 0: none) */
    lv_slot nose_radius;     /* m: the nose's radius when this stage is the top of a stack (the
                                heat flux output); LV_NO_SLOT: 1 m (lv_kit_heating) */
    lv_slot gear[LV_GEAR_N]; /* `landing_gear:` limits (slots "<stage>.landing_gear.<key>");
                                LV_NO_SLOT each without `landing_gear:`: the defaults */
    /* `geometry: {length, diameter, span}` (m): the shape of the CZML export's vehicle model
     * only, no physics; length 0: not given (docs/mission-format.md, "Stages") */
    double geom_length, geom_diameter, geom_span;
    lv_src_loc loc;
} lv_stage_def;

/* ---- phases ------------------------------------------------------------------------------- */

typedef enum lv_end_kind {
    LV_END_BURNOUT = 0, /* propellant of the burning stage exhausted */
    LV_END_ALTITUDE,    /* altitude crosses `value` (m) */
    LV_END_SPEED,       /* speed crosses `value` (m/s) */
    LV_END_APOGEE,      /* vertical/radial velocity falls through zero */
    LV_END_IMPACT,      /* altitude falls through `value` (m, default 0) */
    LV_END_VAR,         /* any state, derivative or output of the model (`var`) crosses `value`
                           in `direction`: a stop condition of the simulation (lv_sim_stop) */
    LV_END_TIME         /* `value` s after the phase's start (a time event) */
} lv_end_kind;

/* "burnout", "altitude", "speed", "apogee", "impact", "var", "time". */
const char *lv_end_kind_name(lv_end_kind k);

typedef struct lv_end_def {
    lv_end_kind kind;
    lv_slot value;      /* altitude, speed, impact, var, time; LV_NO_SLOT for burnout, apogee */
    lv_dir direction;
    char *var;          /* LV_END_VAR: the variable's name ("mach", "der(h)") */
    int deg;            /* LV_END_VAR: the value was written in degrees (`fpa_deg`) */
    char name[288];     /* the event's name in results and the value's slot after
                           "<phase>.end.": "altitude", "mach", "time"; the second end of a
                           kind (or of a variable) "altitude_2", the third "_3" */
    char *label;        /* the user's name of the event (`name: MECO`), or NULL */
    lv_src_loc loc;
} lv_end_def;

typedef struct lv_phase_type lv_phase_type; /* phase_type.h */

/* An engine-out of a phase (`engine_out:`): `count` running engines of the bottom stage's
 * engine kind `engine` (index into its engines) stop `time` s after the phase's start. */
typedef struct lv_engine_out_def {
    size_t engine;
    int count;
    lv_slot time;         /* s, > 0: "<phase>.engine_out.time" ("...engine_out.<i>.time") */
    char *label;          /* the user's name of the event (`name:`), or NULL */
    lv_src_loc loc;
} lv_engine_out_def;

typedef struct lv_phase_def {
    char *name;
    const lv_phase_type *type; /* the phase's model type (phase_type.h registry) */
    void *type_cfg;       /* what the type parsed from the phase's own keys; owned by the type */
    struct lv_reference_def *reference; /* `reference:` (reference.h), or NULL; owned */
    lv_slot *params;      /* [type->n_mission_params]: the slot of each of its type's mission
                             parameters in the file's `parameters:`, LV_NO_SLOT where not given
                             (phase_kit.h, lv_kit_param); NULL when the type has none */
    size_t n_stages;      /* the bodies this phase carries, bottom first */
    size_t *stages;       /* indices into lv_mission_def.stages */
    lv_src_loc *stage_locs; /* [n_stages] where each is named */
    int alternative;      /* 1: an alternative outcome of its parent (an abort case): it may
                             carry stages that a sibling branch carries */
    int parent;           /* index of the phase whose final state seeds this one; -1: parameters */
    size_t file_index;    /* its position in the file (0-based); phases are kept in run order */
    lv_slot t_start;      /* s; LV_NO_SLOT: the parent's end time (or 0 without parent) */
    lv_slot t_stop;       /* s; the fixed stop time or the time limit of the phase */
    size_t n_ends;        /* events that end the phase before t_stop */
    lv_end_def *ends;
    char *separation_label; /* the user's name of the separation this phase starts with
                             (`separation: {name: ...}`, dof3), or NULL */
    char *end_name;       /* `end_name:`: the user's name of any of its ends that has none of
                             its own (a main engine cut-off by propellant_left or burnout), or
                             NULL */
    char *method;         /* integrator, default LV_PHASE_METHOD_DEFAULT */
    lv_slot tolerance;    /* default 1e-9 (docs/integration.md) */
    int intervals;        /* numberOfIntervals (0: use output_interval or 500) */
    lv_slot output_interval; /* s, default 0 */
    lv_slot fixed_step;   /* s, default 0 */
    size_t n_set;         /* overrides applied after the hand-off: name = value (SI) */
    char **set_names;
    lv_slot *set_values;
    lv_src_loc *set_locs; /* [n_set] where each override was written, for later messages */
    unsigned char *set_deg; /* [n_set] 1: written NAME_deg (the variable must be an angle) */
    /* the bottom stage's engines this phase runs (`engines:`, `engine_out:`; engine_run.c) */
    int *engines_run;     /* [bottom stage's n_engines]: how many of each kind run; NULL: all */
    size_t n_engine_out;  /* engine-outs: `count` engines of kind `engine` stop `time` s after */
    lv_engine_out_def *engine_out; /*   the phase's start */
    /* `iip_at: [t1, t2, ...]`: mission times [s], strictly increasing, at which every run
     * records the phase's instantaneous impact point (lv_run_iip; docs/monte-carlo.md,
     * "The IIP at given times"); the phase's model must have the iip_* outputs */
    size_t n_iip_at;
    double *iip_at;
    lv_src_loc iip_at_loc; /* the key */
    lv_src_loc loc;
} lv_phase_def;

/* ---- mission --------------------------------------------------------------------------------- */

typedef struct lv_targeting_def lv_targeting_def; /* targeting_def.h */

typedef struct lv_mission_def {
    char *name;
    char *description;
    char *epoch;   /* ISO 8601 UTC of mission time 0, or NULL (exports use 2000-01-01T12:00:00Z) */
    char *path;    /* the mission file */
    char *dir;     /* its directory: relative table paths resolve against it */
    size_t n_files; /* the data files it names (tables, wind, gravity coefficients), resolved */
    char **files;   /* against dir, each once, in the order the parser met them */
    lv_env_def env;
    size_t n_params; /* the shared parameter set written in the file (start_lat, start_h, ...) */
    char **param_names;
    lv_slot *param_values;
    size_t n_stages;
    lv_stage_def *stages;
    size_t n_phases; /* in run order: parents before children, file order otherwise */
    lv_phase_def *phases;
    size_t n_slots;  /* every number a run may vary */
    lv_slot_def *slots;
    size_t cap_slots;
    lv_targeting_def *targeting; /* the `targeting:` section, or NULL */
    struct lv_ocp_def *ocp;      /* the `optimal_control:` section (ocp_def.h), or NULL */
    struct lv_disp_def *disp; /* `dispersions:` (mission/dispersion.h), or NULL */
} lv_mission_def;

/* The outputs a phase's `iip_at:` reads, in lv_iip_sample's order: iip_lat, iip_lon,
 * iip_tof, iip_range (mission.c). */
#define LV_IIP_N_OUT 4
extern const char *const lv_iip_out_names[LV_IIP_N_OUT];

/* Parse and validate a mission file. Errors are "file:line:column: message". */
lv_status lv_mission_def_load(const char *path, lv_mission_def **out, lv_err *err);
/* The same from memory (`name` is used in messages; relative paths resolve against `dir`). */
lv_status lv_mission_def_parse(const char *text, size_t len, const char *name, const char *dir,
                               lv_mission_def **out, lv_err *err);
void lv_mission_def_free(lv_mission_def *m);

/* The file's value of a slot (NAN for LV_NO_SLOT). */
double lv_mission_def_value(const lv_mission_def *m, lv_slot s);
/* Parameter value by name, or `fallback` when the mission does not set it. */
double lv_mission_def_param(const lv_mission_def *m, const char *name, double fallback);
/* Slot by exact name, or LV_NO_SLOT. */
lv_slot lv_mission_def_slot(const lv_mission_def *m, const char *name);
/* 1 if slot s acts on no phase because a `start: reference` replaces it: every phase that
 * reads it either starts from its reference, which sets that value (a root's start_lat,
 * start_lon, start_h, start_vel, start_fpa, start_chi; a `set:` of the mass or, in a child, of
 * r_eci_*, v_eci_*), or does not read it at all (a child and a root's start value: its
 * position and velocity come from its parent), and at
 * least one does the first; *phase then names one such phase. 0 otherwise. */
int lv_mission_def_slot_overridden(const lv_mission_def *m, lv_slot s, const char **phase);

/* Adds a slot (used by the parser and the model types). Names must be unique: a duplicate
 * is LV_ERR_INPUT naming both. */
lv_status lv_mission_def_add_slot(lv_mission_def *m, const char *name, const char *unit,
                                  double value, lv_range range, lv_slot_owner owner,
                                  size_t owner_index, lv_src_loc loc, lv_slot *out, lv_err *err);
/* 1 if v lies in r; `text` (may be NULL) receives "> 0", ">= 0 and <= 1", "finite"... */
int lv_range_holds(lv_range r, double v);
void lv_range_text(lv_range r, char *text, size_t cap);

/* Common ranges. */
#define LV_RANGE_ANY ((lv_range){-HUGE_VAL, HUGE_VAL, 0, 0})
#define LV_RANGE_POS ((lv_range){0.0, HUGE_VAL, 1, 0})      /* > 0 */
#define LV_RANGE_NONNEG ((lv_range){0.0, HUGE_VAL, 0, 0})   /* >= 0 */
/* A relative integration tolerance: what lv_simulate accepts (lv_sim.h). */
/* A phase's integration method when its file names none (issue 24: the explicit method while
 * the phase is not stiff, then BDF; docs/integration.md, "auto"). */
#define LV_PHASE_METHOD_DEFAULT "auto"
#define LV_RANGE_TOLERANCE ((lv_range){LV_TOLERANCE_MIN, LV_TOLERANCE_MAX, 0, 0})

/* Angles (rad) and rates (rad/s) by kind: every angle of a mission file takes one, so that a
 * value no vehicle has (theta_deg: 1e300) is refused where it is written (docs/mission-format.md,
 * "Angle ranges"). In degrees: */
#define LV_RANGE_LAT ((lv_range){-0.5 * LV_PI, 0.5 * LV_PI, 0, 0})  /* [-90, 90]: latitudes,
                                                    flight-path angles, a 3-2-1 pitch */
#define LV_RANGE_TURN ((lv_range){-2.0 * LV_PI, 2.0 * LV_PI, 0, 0}) /* [-360, 360]: longitudes,
                                                    headings, yaw, roll and bank angles */
#define LV_RANGE_AERO_ANGLE ((lv_range){-LV_PI, LV_PI, 0, 0})     /* [-180, 180]: angle of
                                                    attack, sideslip */
#define LV_RANGE_ANGLE ((lv_range){-4.0 * LV_PI, 4.0 * LV_PI, 0, 0}) /* [-720, 720]: any other
                                                    angle (two turns either way) */
#define LV_RANGE_RATE ((lv_range){-20.0 * LV_PI, 20.0 * LV_PI, 0, 0}) /* [-3600, 3600] deg/s:
                                                    10 rev/s (LV_DOF6_RATE_MAX) */

#endif
