/* vehicle.h - engines and aerodynamic sets resolved for the hot path (not exported).
 *
 * lv_engine_init / lv_aero_init check a configuration (lv_vehicle.h), resolve table
 * outputs and axes to indices and keep the table cursors. The _eval functions allocate
 * nothing and look nothing up by name. One resolved object per simulation instance
 * (cursors are mutable); the tables themselves are borrowed and shared.
 */
#ifndef LV_VEHICLE_VEHICLE_H
#define LV_VEHICLE_VEHICLE_H

#include <stddef.h>

#include "lvsim/lv_table.h"
#include "lvsim/lv_vehicle.h"

/* ---- engines ---- */

#define LV_ENGINE_NAME_MAX 48

typedef struct lv_engine {
    char name[LV_ENGINE_NAME_MAX];
    double thrust_vac;      /* N, constant engines */
    double mdot_full;       /* kg/s, constant engines */
    double mdot_per_thrust; /* s/m = 1 / (Isp g0); table engines without an "mdot" column */
    double exit_area;       /* m^2 */
    double thr_min, thr_max;
    const lv_table *table;  /* borrowed; NULL: constant */
    size_t k_thrust, k_mdot; /* output indices; k_mdot = (size_t)-1: from mdot_per_thrust */
    size_t n_out;
    lv_table_cursor cur;
    double out_after;       /* s after the start (lv_engine_config.out_after); INFINITY: never */
    double t_out;           /* s, mission time of the engine-out: start + out_after (set at
                               the model's start, lv_engine_start) */
    int out;                /* mode: 1 once the engine-out happened (no thrust, no flow) */
} lv_engine;

/* Checks configuration `c` (engine number `index`, for messages) and fills `e`.
 * LV_ERR_INPUT names the engine, the field and the value. */
lv_status lv_engine_init(lv_engine *e, const lv_engine_config *c, size_t index, lv_err *err);

/* The model's start at mission time t0 [s]: the engine runs, its engine-out instant is
 * t0 + out_after (INFINITY: never). */
void lv_engine_start(lv_engine *e, double t0);

/* At a time event t: the engine stops if its engine-out instant is t (or passed). Returns 1
 * when it stopped now. */
int lv_engine_out_event(lv_engine *e, double t);

/* Throttle c clamped into [thr_min, thr_max] (documented for tables and guidance). */
double lv_engine_throttle(const lv_engine *e, double throttle);

/* Thrust (N, along body x) and mass flow (kg/s, > 0 while burning; 0 and 0 once out) at time
 * t [s],
 * commanded throttle (clamped) and ambient pressure p_amb [Pa]. `buf` holds at least
 * e->n_out doubles (table engines). Returns LV_OK or the table's LV_ERR_INPUT (time
 * outside the table under LV_EXTRAP_ERROR; the message is formatted only if err). */
lv_status lv_engine_eval(lv_engine *e, double t, double throttle, double p_amb, double *buf,
                         double *thrust, double *mdot, lv_err *err);

/* ---- aerodynamics ---- */

enum { LV_AERO_IN_MACH, LV_AERO_IN_ALPHA, LV_AERO_IN_BETA, LV_AERO_IN_ALT, LV_AERO_IN_N };

typedef struct lv_aero_tab {
    const lv_table *table;               /* borrowed */
    size_t n_dims;
    int input[LV_TABLE_MAX_DIMS];        /* LV_AERO_IN_* feeding each axis */
    lv_table_cursor cur;
    double *y;                           /* [n_out], owned */
} lv_aero_tab;

typedef struct lv_aero {
    lv_aero_axes axes;
    double s_ref;           /* m^2 */
    size_t n_tab;           /* distinct tables, <= 3 */
    lv_aero_tab tab[3];
    int coef_tab[3];        /* index into tab[], or -1: constant */
    size_t coef_k[3];       /* output index in that table */
    double coef_value[3];   /* constants */
} lv_aero;

/* Checks `c` and fills `a` (allocates the output buffers: lv_aero_clear() frees them).
 * LV_ERR_INPUT / LV_ERR_NOTFOUND name the coefficient, table, axis or output. */
lv_status lv_aero_init(lv_aero *a, const lv_aero_config *c, lv_err *err);
void lv_aero_clear(lv_aero *a); /* accepts a zeroed or cleared lv_aero */

/* Coefficients coef[0..2] (CD, CL, CY or CA, CN, CY) at Mach, alpha, beta [rad] and
 * geodetic altitude h [m]. Each table is evaluated once. */
lv_status lv_aero_coefs(lv_aero *a, double mach, double alpha, double beta, double h,
                        double coef[3], lv_err *err);

/* Aerodynamic force in wind-frame components f_w[3] (N) from the coefficients, the
 * product q S_ref (N) and the aerodynamic angles (cos/sin of alpha and beta). Body
 * coefficients are rotated with C_wind_body = (R2(alpha) R3(-beta))^T. */
void lv_aero_force_wind(const lv_aero *a, const double coef[3], double qs, double ca, double sa,
                        double cb, double sb, double f_w[3]);

#endif
