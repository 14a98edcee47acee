/* erk.h - lvsim's own explicit Runge-Kutta integrators behind lv_integ: Dormand-Prince 5(4)
 * ("dp5") and DOP853 ("dop853"), after Hairer, Norsett & Wanner, Solving Ordinary Differential
 * Equations I (2nd ed., 1993): the methods of II.5 (Table 5.2) and II.10 (DOP853), their dense
 * output (II.6), step-size control (II.4, with the PI controller of IV.2 / Gustafsson), the
 * initial step of II.4 and the stiffness test of IV.2 / Hairer's codes.
 *
 * Internal to the integrate layer: integrator.c dispatches lv_integ's calls here for these
 * methods. Same contract as lv_integ_advance (integrator.h): output at tout from the dense
 * output, roots located on it per event function (Illinois) with direction, the stop time
 * never passed and hit exactly. Memory is allocated once by lv_erk_create; a step allocates
 * nothing and calls nothing but the problem's rhs and g.
 */
#ifndef LV_INTEGRATE_ERK_H
#define LV_INTEGRATE_ERK_H

#include "integrate/integrator.h"

typedef struct lv_erk lv_erk;

/* Beside the results of lv_integ_advance: with stop_on_stiff, an advance that finds the
 * problem stiff (Hairer's test, lv_erk_stiff) returns at the end of the last accepted step,
 * before tout, with this result (no root there). */
#define LV_ERK_STIFF 2

/* p->method is LV_METHOD_DP5 or LV_METHOD_DOP853 (anything else: dop853's tableau is not
 * chosen, dp5 is). Borrows p->atol, p->rtol_v, p->quad and p->g_dir: they must outlive the object. */
lv_status lv_erk_create(const lv_integ_problem *p, int dop853, double t0, const double *x0,
                        lv_erk **out, lv_err *err);
void lv_erk_free(lv_erk *e);
lv_status lv_erk_set_stop_time(lv_erk *e, double tstop, lv_err *err);
/* *res is LV_INTEG_REACHED, LV_INTEG_ROOT or (stop_on_stiff) LV_ERK_STIFF. */
lv_status lv_erk_advance(lv_erk *e, double tout, int stop_on_stiff, double *t, double *x,
                         int *res, int *roots, lv_err *err);
lv_status lv_erk_restart(lv_erk *e, double t, const double *x, lv_err *err);
void lv_erk_get_stats(const lv_erk *e, lv_integ_stats *st);
/* 1 once Hairer's stiffness test has fired (15 positive tests without 6 negative ones in a
 * row), with the time of the step that made it fire. */
int lv_erk_stiff(const lv_erk *e, double *t_detected);
/* The time reached (end of the last return). */
double lv_erk_time(const lv_erk *e);

#endif
