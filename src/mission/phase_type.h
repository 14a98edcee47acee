/* phase_type.h - the registry of phase-model types: what a phase's `model:` names (not
 * exported). The parser, the mission, the run and the summary know no model by name: they
 * ask the phase's type to parse its own keys, to build its model from a run's values, and
 * to name the columns of the bodies' merged trajectories. A new model type is one file that
 * defines an lv_phase_type (its build made of the kit, phase_kit.h) and one line in
 * phase_types.c; tests/unit/test_phase_types.c checks the contracts every type keeps with the
 * merge, the exports and the other types (docs/architecture.md, "How to add a phase type").
 */
#ifndef LV_MISSION_PHASE_TYPE_H
#define LV_MISSION_PHASE_TYPE_H

#include <stddef.h>

#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_mission.h"
#include "lvsim/lv_model.h"
#include "lvsim/lv_planet.h"
#include "lvsim/lv_wind.h"
#include "mission/mission.h"
#include "mission/parse_kit.h"
#include "mission/yaml_tree.h"

/* The environment every phase shares, built once when the mission is loaded (read-only
 * afterwards; the wind table's cursor lives in each model instance). */
typedef struct lv_mission_env {
    lv_planet planet;
    lv_gravity *gravity; /* NULL on a flat world */
    lv_atmo *atmo;       /* NULL: vacuum */
    lv_wind *wind;       /* NULL: no wind */
} lv_mission_env;

/* Builds the environment from the file's values (mission.c, when the mission is loaded):
 * the planet and its gravity, the atmosphere and the wind, on either world. Errors carry the
 * position of the key that failed. lv_mission_env_clear frees it (a zeroed one too). */
lv_status lv_mission_env_make(const lv_mission_def *d, lv_mission_env *env, lv_err *err);
void lv_mission_env_clear(lv_mission_env *env);

/* What one phase model flies in for one run: the shared environment where the run's values
 * of the environment's slots (a planet's constants, the exponential atmosphere's parameters,
 * a constant wind) are the file's; objects made from the run's values otherwise, owned here
 * (lv_phase_env_clear, after the model that borrows them is freed). */
typedef struct lv_phase_env {
    lv_planet planet;          /* planet world */
    const lv_gravity *gravity; /* NULL on a flat world */
    const lv_atmo *atmo;       /* NULL: no atmosphere */
    const lv_wind *wind;       /* NULL: no wind */
    lv_gravity *own_gravity;
    lv_atmo *own_atmo;
    lv_wind *own_wind;
    lv_atmo *own_perturbed_atmo; /* the atmosphere with the run's density profile */
    lv_wind *own_perturbed;    /* the wind plus the run's wind perturbation profile */
    lv_wind *own_disturbed;    /* the wind plus the run's gusts and turbulence */
} lv_phase_env;

typedef struct lv_build_ctx lv_build_ctx;

/* What a hand-off absorbed: the parent's final quantities that the child's state cannot hold
 * (a touchdown's sink rate, the height the projection on the runway drops), recorded by the
 * type's handoff for the phase's result and summary.json ("handoff" / "absorbed"). */
#define LV_HANDOFF_NOTES_MAX 8
typedef struct lv_handoff_notes {
    size_t n;
    const char *name[LV_HANDOFF_NOTES_MAX]; /* static strings */
    const char *unit[LV_HANDOFF_NOTES_MAX]; /* SI, "" dimensionless */
    double value[LV_HANDOFF_NOTES_MAX];
    /* the hand-off is a crash (a touchdown beyond the landing gear's limits): the phase is
     * not flown, its state LV_PHASE_CRASHED with `why` (phase name and time prefixed) */
    int crashed;
    char why[512];
} lv_handoff_notes;
lv_status lv_phase_env_get(const lv_build_ctx *bc, lv_phase_env *pe, lv_err *err);
void lv_phase_env_clear(lv_phase_env *pe); /* accepts a zeroed one */

/* What a type needs to build phase k's model for one run. */
struct lv_build_ctx {
    const lv_mission_def *def;
    const lv_mission_env *env;
    size_t k;           /* the phase */
    const double *vals; /* [def->n_slots]: the run's value of every slot */
    const double *prop; /* [def->n_stages]: kg of propellant left in each stage at the start */
    const struct lv_run_tables *tables; /* the run's dispersed tables (dispersion.h), or NULL */
    lv_handoff_notes *notes; /* where the handoff records what it absorbed, or NULL */
};

/* Records name = value [unit] in bc->notes (nothing when bc->notes is NULL or full). */
void lv_build_note(const lv_build_ctx *bc, const char *name, const char *unit, double value);
/* Marks the hand-off a crash with the reason (bc->notes NULL: nothing). */
void lv_build_crash(const lv_build_ctx *bc, const char *fmt, ...) LV_PRINTF(2, 3);

/* The table a phase flies for the definition's table `t`: the run's dispersed copy (a scale
 * factor or bias drawn for the run: dispersion.h), or `t` itself. Borrowed for the build. */
const lv_table *lv_build_table(const lv_build_ctx *bc, const lv_table *t);

/* A built phase model: what one simulation of the phase gets. */
typedef struct lv_phase_model lv_phase_model;
struct lv_phase_model {
    const lv_phase_type *type;
    const lv_model_def *def;
    void *inst;
    const int *event_end; /* [def->n_events]: the phase end (index into ph->ends) each state
                             event stands for, or -1 */
    void *self;           /* the type's own object (freed by type->free_self) */
};

/* One column of a body's merged trajectory (body_<stage>.csv). */
typedef struct lv_traj_col {
    const char *name;   /* column name ("r_eci_x", "lat") */
    const char *unit;
    const char *source; /* the phase result's column it copies, or NULL: computed by
                           traj_extra */
} lv_traj_col;

struct lv_phase_type {
    const char *name;        /* the `model:` value: "dof3" */
    const char *description; /* one line */
    lv_world_kind world;     /* the world it flies in */
    const char *const *keys; /* phase keys it parses itself besides the common ones (name,
                                model, stages, from, start_time, stop_time, end, integrator,
                                set), NULL-terminated; may be NULL */
    /* The other types whose phases a phase of this type may start from (`from:`),
     * NULL-terminated; NULL: its own type only. The hand-off copies the parent's finals
     * (states and outputs) by the names of this type's states; a state the parent has no
     * final of is given by `handoff` (the conversion), which must then exist. */
    const char *const *from_types;
    /* The keys a sample phase of this type needs besides name, model, stages and stop_time
     * (`lvsim models`, `lvsim vars <type>`), as YAML flow-mapping entries; NULL: none. */
    const char *sample_keys;
    /* The named end conditions (lv_end_kind_name) its phases take, NULL-terminated; NULL: all.
     * The type's parse refuses the others at their position. */
    const char *const *ends;
    /* The ends its model has of its own, whatever `end:` lists (a runway roll's "liftoff",
     * "stop"), NULL-terminated; NULL: none. A phase's `end_name:` names them too, so it needs
     * no `end:` list for them. */
    const char *const *own_ends;
    /* Those of its own ends that are a crash (a roll that runs off the runway's end:
     * "overrun"), NULL-terminated; NULL: none. A phase that ends by one is flown (its rows,
     * files and finals complete) and then `crashed` (lv_phase_state), its error the end's
     * description. */
    const char *const *crash_ends;
    /* The model parameters a root phase takes from the mission's shared parameter set
     * (name, SI unit, description; `start` unused). */
    size_t n_mission_params;
    const lv_var *mission_params;
    const lv_range *mission_param_ranges; /* [n_mission_params] allowed values; NULL: finite */
    const char *mass_state;  /* the state that holds the vehicle's mass: "m" */

    /* Parses the type's own keys of phase `ph` (`n`: its mapping, keys already checked),
     * registers their numbers as slots (c->owner is the phase) and stores what it read in
     * ph->type_cfg. NULL: the type has no keys of its own. */
    lv_status (*parse)(const lv_pctx *c, const lv_ynode *n, lv_phase_def *ph);
    void (*cfg_free)(void *cfg); /* accepts NULL */

    /* Builds phase bc->k's model from the run's values. Errors name the field and value. */
    lv_status (*build)(const lv_build_ctx *bc, lv_phase_model **out, lv_err *err);
    void (*free_self)(void *self);

    /* The columns of a body's merged trajectory, and the function that computes those with
     * source NULL from the sourced ones (row[] in column order; `def` for the world). */
    size_t n_traj;
    const lv_traj_col *traj;
    void (*traj_extra)(const lv_mission_def *def, double *row);

    /* The hand-off's own rules (a separation impulse): adjusts a child phase's initial values
     * (names/values[n]: the states copied from the parent, the overrides) from its parent's
     * final values (pnames/pvalues[np]: time, states, outputs), with the run's values in bc
     * and the child's built model pm. NULL: none. Errors name the phase and the reason. */
    lv_status (*handoff)(const lv_build_ctx *bc, const lv_phase_model *pm,
                         const char *const *pnames, const double *pvalues, size_t np,
                         const char *const *names, double *values, size_t n, lv_err *err);

    /* Checks of the phase as a whole once its common keys (`set:` included: ph->set_names,
     * set_values, set_locs) are read; errors at file:line:column. NULL: none. */
    lv_status (*check)(const lv_pctx *c, const lv_ynode *n, lv_phase_def *ph);
    /* Checks of a child phase against its parent once the phase tree is known (parse.c,
     * check_tree); errors at file:line:column. NULL: none. */
    lv_status (*check_parent)(const lv_pctx *c, const lv_phase_def *ph,
                              const lv_phase_def *parent);
    /* The rule of its conversion from a parent of another type, in words for summary.json
     * ("rates: zero"); NULL: none to name. */
    const char *(*handoff_rule)(const lv_phase_def *ph);
    /* The mission parameters (of mission_params) only a root phase of this type reads,
     * NULL-terminated; NULL: a child reads them all. A parameter that only children read is
     * refused where the file writes it. */
    const char *const *root_only_params;

    /* The model inputs an optimiser may give a phase of this type as controls
     * (`optimal_control:`, docs/optimal-control.md), SI names ("alpha", "throttle"; an angle's
     * unit is rad), NULL-terminated; NULL: none. */
    const char *const *controls;
    /* Nonzero, with the reason in why, when phase ph cannot take control `input` (an index
     * into controls) from the optimiser: something else gives it (a steering law the angles, a
     * throttle law the throttle). NULL: no conflicts. */
    int (*control_conflict)(const lv_phase_def *ph, size_t input, char *why, size_t cap);
    /* Makes phase ph fly the 1-D table t over mission time (outputs named as controls,
     * linear) as its controls, in place of its own table of them (its inputs table, or its
     * steering law's: controls_key); ph takes t over (frees it). */
    void (*set_controls)(lv_phase_def *ph, lv_table *t);
    /* The phase's own table of controls as the file gives it (which set_controls replaces),
     * or NULL. */
    const lv_table *(*own_inputs)(const lv_phase_def *ph);
    /* The constant phase ph flies for control `input` when no table gives it (the attitude
     * law's pitch, heading, roll keys), from mission d's file values; NAN: none or unknown
     * (the optimiser's start point then takes the controls' bounds). NULL: none. */
    double (*control_constant)(const lv_phase_def *ph, const lv_mission_def *d, size_t input);
    /* The phase's key in the mission file whose `table:` the controls replace: "inputs"
     * (written with `over: time`) or "guidance" (the attitude law's table over time). NULL:
     * "inputs". */
    const char *(*controls_key)(const lv_phase_def *ph);
};

/* The type whose model compare.c flies end to end (the paper's flat-world test case): a study
 * made for one model names its type by this object, never by a string. */
extern const lv_phase_type lv_phase_type_flat6; /* phase_flat6.c */

/* The registered types, NULL-terminated (phase_types.c). */
const lv_phase_type *const *lv_phase_types(void);

/* Builds phase bc->k's model with its type's build; lv_phase_model_free releases it. */
lv_status lv_phase_model_build(const lv_build_ctx *bc, lv_phase_model **out, lv_err *err);
void lv_phase_model_free(lv_phase_model *pm); /* accepts NULL */

#endif
