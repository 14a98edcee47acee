/* reference.h - internal: a phase's `reference:`, an external optimiser's trajectory (the
 * paper's "start values of the trajectory optimization results for each phase", its Figure 10
 * of the simulated against the optimised trajectory): parsed with the phase, a start from its
 * first row, and the re-simulation's drift from it at the result rows
 * (docs/optimal-control.md, "Importing an optimiser's trajectory"). */
#ifndef LV_MISSION_REFERENCE_H
#define LV_MISSION_REFERENCE_H

#include "lvsim/lv_io.h"
#include "lvsim/lv_mission.h"
#include "lvsim/lv_planet.h"
#include "mission/mission.h"
#include "mission/parse_kit.h"

/* The reference's columns, in this order: geodetic altitude h [m], geodetic latitude lat and
 * longitude lon [rad], speed v relative to the rotating planet [m/s], its flight-path angle
 * fpa (up positive) and heading (from north to east) [rad], mass m [kg]. */
enum { LV_REF_H, LV_REF_LAT, LV_REF_LON, LV_REF_V, LV_REF_FPA, LV_REF_HEADING, LV_REF_M,
       LV_REF_N };
extern const char *const lv_ref_columns[LV_REF_N];

typedef struct lv_reference_def {
    lv_table *table;      /* one axis: mission time ("time"/"t", s) or "tau" [1]; the columns */
    char *file, *var;     /* the resolved path, the .mat variable (or NULL) */
    int over_tau;         /* the axis is tau = (t - t_start) / (t_stop - t_start) */
    int start;            /* `start: reference`: the phase starts from the first row */
    size_t k[LV_REF_N];   /* the table's output of each column */
    lv_src_loc loc;       /* the `reference` key */
} lv_reference_def;

/* Phase `ph`'s `reference:` at node `v` (key `key`), NULL: none. `reference: PATH` or
 * `reference: {table: TABLE, start: parent | reference}` with TABLE a table reference (a path
 * or {file, var, interp, extrap}); the columns above by name (aliases: altitude; speed, v_rel;
 * azimuth, chi; mass), in SI (a column written in other units is refused); the axis time or
 * tau. Sets ph->reference. Errors at the offending node (file:line:column). */
lv_status lv_reference_parse(const lv_pctx *c, const lv_ynode *key, const lv_ynode *v,
                             lv_phase_def *ph);
void lv_reference_free(lv_reference_def *r); /* accepts NULL */

/* Column j (LV_REF_H ..) of the reference's first row. */
double lv_reference_first(const lv_reference_def *r, size_t j);

/* The reference against the phase's time span, at load: t_start [s] the phase's start (NAN:
 * not known before the run, a child's without `start_time:`), t_stop its stop_time [s]. A time
 * axis must reach into [t_start, t_stop] (else it covers no part of the phase); with `start:
 * reference` its first time must be the phase's start within 1e-9 s relative (a child without
 * `start_time:` starts at it instead: lv_reference_start_time), a tau axis must start at tau
 * = 0. LV_ERR_INPUT naming the reference's table and both times (no file position: the caller
 * adds it). */
lv_status lv_reference_check_span(const lv_reference_def *r, double t_start, double t_stop,
                                  lv_err *err);

/* The mission time a phase started from a time-axis reference starts at: its first time;
 * NAN for a tau axis or without `start: reference`. */
double lv_reference_start_time(const lv_reference_def *r);

/* A start from the reference's first row (`start: reference`), placed at mission time t0: a
 * root phase (`root`) gets the parameters start_lat, start_lon, start_h, start_vel,
 * start_fpa, start_chi, a child its states r_eci_*, v_eci_* (ECI at t0 on `planet`); both the
 * mass state `mass_state`. Names already in names[0 .. *n - 1] are overwritten, the others
 * appended (at most `cap` in all). */
lv_status lv_reference_start(const lv_reference_def *r, const lv_planet *planet, double t0,
                             int root, const char *mass_state, const char **names,
                             double *values, size_t *n, size_t cap, lv_err *err);

/* The drift of the rows `rows` (columns time, h, lat, lon, v_north, v_east, v_down and the
 * mass state) from the reference (lv_ref_drift), compared in ECEF: the reference's position
 * interpolated by cubic Hermite with its own velocity, its velocity components with the
 * table's interpolation (no wrap of longitude or heading, no pole singularity); t_start, t_stop: the phase's (tau). *series
 * receives the compared rows (out->n_rows of them; malloc'ed, the caller frees; NULL when
 * none). */
lv_status lv_reference_drift(const lv_reference_def *r, const lv_planet *planet,
                             const lv_result *rows, const char *mass_state, double t_start,
                             double t_stop, lv_ref_drift *out, lv_ref_row **series,
                             lv_err *err);

#endif
