/* ocp_def.h - a mission file's `optimal_control:` section: the phases whose control histories
 * (a phase type's controls: dof3's alpha, beta, mu, throttle, or its attitude law's pitch,
 * heading, roll) and durations are optimised, with
 * bounds and node counts, and the boundary constraints, path constraints and cost in the words
 * of `targeting:` (targeting_def.h). Parsed with the mission, then checked against the loaded
 * mission, so `lvsim check` refuses what `lvsim optimize` would. The transcription and the
 * solver: src/optimal (lv_ocp.h). Format: docs/optimal-control.md.
 */
#ifndef LV_MISSION_OCP_DEF_H
#define LV_MISSION_OCP_DEF_H

#include <stddef.h>

#include "mission/mission.h"
#include "mission/parse_kit.h"
#include "mission/targeting_def.h"

#define LV_OCP_MAX_NODES 1000    /* control nodes and shooting segments of one phase at most */
#define LV_OCP_MAX_CONTROLS 8

/* One control of an optimised phase. */
typedef struct lv_ocp_ctrl_def {
    char *name;         /* as written: "alpha_deg", "throttle" */
    size_t input;       /* index into the phase type's controls (lv_phase_type.controls) */
    int deg;            /* written NAME_deg: bounds and start in degrees in the file */
    double lo, hi;      /* SI (rad) */
    double start;       /* SI, or NAN: the phase's own input along its first flight */
    lv_src_loc loc;
} lv_ocp_ctrl_def;

typedef struct lv_ocp_phase_def {
    char *name;
    size_t phase;       /* resolved: its index (run order) */
    lv_src_loc loc;
    size_t n_ctrl;
    lv_ocp_ctrl_def *ctrl;
    int nodes;          /* control nodes over the phase, equally spaced in time (>= 2) */
    int segments;       /* shooting segments (>= 1; default nodes - 1) */
    int free_duration;  /* `duration:` given: the duration is a variable */
    double dur_lo, dur_hi, dur_start; /* s; dur_start NAN: the phase's duration as flown */
    lv_src_loc dur_loc;
} lv_ocp_phase_def;

typedef struct lv_ocp_def {
    size_t n_phases;
    lv_ocp_phase_def *phases;
    size_t n_cons;
    lv_tcon_def *cons;  /* final: a phase's final; path: at every node of an optimised phase */
    lv_tcost_def cost;
    int max_iterations; /* default 500 */
    double tolerance;   /* IPOPT's tol on the scaled problem (default 1e-8) */
    /* IPOPT's acceptable_iter: consecutive iterations at its acceptable level (acceptable_tol
     * = max(100 tol, 1e-6)) that end the solve there (default 15, IPOPT's) */
    int acceptable_iterations;
    double integrator_tolerance; /* the segments' relative tolerance (default 1e-10) */
    lv_src_loc loc;
} lv_ocp_def;

/* Parses the `optimal_control:` mapping `n` (NULL: none) into c->m->ocp. */
lv_status lv_ocp_def_parse(const lv_pctx *c, const lv_ynode *n);
/* Resolves and checks the section against the loaded mission m: phases by name, each control
 * one its type takes and the phase does not give otherwise (a steering law, a throttle law),
 * finals and path outputs of the phases. Errors: "file:line:column: optimal_control: ...".
 * No section: LV_OK. */
lv_status lv_ocp_def_check(lv_mission *m, lv_err *err);
void lv_ocp_def_free(lv_ocp_def *o); /* accepts NULL */

#endif
