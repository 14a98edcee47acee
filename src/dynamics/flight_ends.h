/* flight_ends.h - the named ends of a flight model over the planet (lv_dof3_end: altitude,
 * relative or inertial speed, apogee, impact) as state events after the model's burnout
 * event: their set-up and checks, the start's impact offset, the event functions. One piece
 * for every model over the planet (the 3-DoF and the 6-DoF models). */
#ifndef LV_FLIGHT_ENDS_H
#define LV_FLIGHT_ENDS_H

#include <stddef.h>

#include "dynamics/flight.h"
#include "lvsim/lv_dof3.h"
#include "lvsim/lv_model.h"
#include "lvsim/lv_status.h"

#define LV_FLIGHT_END_NAME_MAX 48

typedef struct lv_flight_ends {
    size_t n;
    lv_dof3_end *ends;    /* [n]; names point into names */
    double *off;          /* [n] m: an impact end's offset for a start on (or below) its level,
                             set by lv_flight_ends_start (one simulation at a time) */
    lv_event_def *events; /* [1 + n]: "burnout" (the model's event 0), then the ends */
    char (*names)[LV_FLIGHT_END_NAME_MAX];
} lv_flight_ends;

/* Copies ends[n] into fe (zeroed by the caller) and builds the events. `model` prefixes the
 * messages ("dof3"). Errors (LV_ERR_INPUT): an unknown kind, an empty, too long or repeated
 * name, a value that is not finite, a negative speed, an unknown direction. */
lv_status lv_flight_ends_init(lv_flight_ends *fe, const char *model, const lv_dof3_end *ends,
                              size_t n, lv_err *err);
void lv_flight_ends_clear(lv_flight_ends *fe); /* frees; fe may be zeroed */

/* Below an impact end's level by more than this at the start [m]: under the ground. */
#define LV_FLIGHT_ENDS_BELOW_TOL 1e-3

/* At the start (geodetic altitude h0 [m]): a vehicle that starts on its impact level (within
 * LV_FLIGHT_ENDS_BELOW_TOL: a parent's located impact) and sinks has no crossing from above to
 * find: its impact is 1 micrometre below the start. One that starts further below an impact
 * end's level would start under the ground it is to hit and never cross it: returns 1 with
 * the reason in why[cap] (naming the altitude, the end and its level); 0 otherwise. */
int lv_flight_ends_start(lv_flight_ends *fe, double h0, char *why, size_t cap);

/* g[0..n): the ends' event functions at ECI r, v [m, m/s]; kin holds lv_flight_to_ecef of
 * them (its geodetic altitude is computed here when an end needs it). */
void lv_flight_ends_eval(const lv_flight_ends *fe, const lv_flight_world *w, lv_flight_kin *kin,
                         const double r[3], const double v[3], double *g);

#endif
