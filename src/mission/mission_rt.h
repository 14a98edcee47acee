/* mission_rt.h - internal: a loaded mission (its definition, the environment every phase
 * shares, and each phase's plan resolved once), as run.c and compare.c read it. */
#ifndef LV_MISSION_MISSION_RT_H
#define LV_MISSION_MISSION_RT_H

#include <stddef.h>

#include "lvsim/lv_mission.h"
#include "mission/mission.h"
#include "mission/phase_type.h"

/* Where an initial value of the hand-off comes from. */
typedef enum lv_init_kind {
    LV_INIT_SLOT = 0,   /* the run's value of slot `index` (parameters, g, overrides) */
    LV_INIT_PARENT,     /* the parent's final value `index` (a state copied by name) */
    LV_INIT_MASS,       /* the carried stages' mass from the stage book */
    LV_INIT_START_TIME, /* the phase's start time (the ECI <-> ECEF angle of dof3) */
    LV_INIT_CONVERT     /* a state the parent (of another type) has no final of: its type's
                           handoff converts it from the parent's finals (phase_type.h) */
} lv_init_kind;

typedef struct lv_init_src {
    lv_init_kind kind;
    size_t index;
} lv_init_src;

/* Phase k's plan: names resolved once, when the mission is loaded. */
typedef struct lv_phase_plan {
    size_t n_init;            /* the hand-off, in the order lv_simulate applies it */
    const char **init_names;  /* [n_init], pointing into the plan's or the definition's names */
    lv_init_src *init;        /* [n_init] */
    size_t n_copied;          /* states copied from the parent */
    size_t n_final;           /* "time", the model's states, its outputs */
    char **final_names;       /* [n_final] */
    size_t mass_final;        /* the mass state's index in final_names, or (size_t)-1 */
    size_t n_events;          /* the model's state events, then the stop conditions */
    char **event_names;       /* [n_events] */
    size_t n_model_events;    /* the model's own */
    size_t n_stops;           /* the phase's ends on any variable or on time: stop conditions */
    size_t *stop_end;         /* [n_stops] each one's index in the phase's ends */
    size_t n_states;
} lv_phase_plan;

struct lv_mission {
    lv_mission_def *def;
    lv_mission_env env;
    lv_phase_plan *plan;      /* [n_phases] */
    char (*rules)[48];        /* [n_slots]: each slot's allowed values as text */
    double *defaults;         /* [n_slots]: the file's values */
};

/* The mission from a parsed definition (taken over, also on failure): the environment, every
 * phase's model built once with the file's values, the plans. lv_mission_load = parse + this. */
lv_status lv_mission_from_def(lv_mission_def *d, lv_mission **out, lv_err *err);

/* Phase k's stop conditions (its ends on any variable or on time) as lv_simulate takes them,
 * into out[pl->n_stops], with the slots' values v and the phase's start time (a time end is
 * counted from it). The same for a run (run.c) and the load's start check (mission.c). */
void lv_phase_stops(const lv_mission_def *d, const lv_phase_plan *pl, size_t k, const double *v,
                    double start_time, lv_sim_stop *out);

/* The stage book of phase k as it starts with a mass of its own (docs/mission-format.md, "One
 * propellant book"): the reference's first mass (`start: reference`) or else a `set:` of its
 * mass state (v: the slots' values; neither: nothing to do). prop[n_stages] [kg] is the book the
 * phase would start with (the parent's, or the loads) and is changed in place. The mass m is
 * the carried stages' dry masses and the propellant of the stages above the burning (bottom)
 * one first - m less than that is refused -, then the burning stage's propellant: m below the
 * full stack leaves it m minus the rest (burnout earlier); a set: mass above the full stack is
 * payload, a reference's mass more than the bottom stage's load `v[propellant_mass]` can hold
 * is refused. LV_ERR_INPUT with file:line:column of the set value or the reference. */
lv_status lv_phase_start_book(const lv_mission_def *d, size_t k, const double *v, double *prop,
                              lv_err *err);

/* The phases (indices) whose models read slot s directly; returns the count written to out
 * (capacity: n_phases). */
size_t lv_mission_slot_phases(const lv_mission *m, lv_slot s, size_t *out);

/* The run's value of every slot [n_slots] (run.c). */
const double *lv_run_vals(const lv_run *r);

/* lv_run_check_output for phase k alone, as it is about to run (its parent has ended, so a
 * child's rows are known): LV_ERR_INPUT with the same message beyond opt->max_rows
 * (run_estimate.c). */
lv_status lv_run_check_phase_output(const lv_run *r, size_t k, const lv_run_options *opt,
                                    lv_err *err);

/* 1 if phase k carries stage s. */
int lv_mission_phase_has_stage(const lv_mission_def *d, size_t k, size_t s);

/* Drops a leading "model '<phase>': " from err->msg (a phase's model is named after the
 * phase, which the caller names already). */
void lv_drop_model_prefix(lv_err *err, const char *phase);

#endif
