/* lv_vehicle.h - vehicle data of a stage: engines and aerodynamic coefficient sets.
 *
 * Plain configuration records, copied by the model that uses them (lv_dof3.h); tables
 * (lv_table.h) are borrowed and must outlive that model. Equations, frames and sign
 * conventions: docs/models.md. SI units and radians everywhere.
 */
#ifndef LVSIM_LV_VEHICLE_H
#define LVSIM_LV_VEHICLE_H

#include <stddef.h>

#include "lvsim/lv_status.h"
#include "lvsim/lv_table.h"
#include "lvsim/lv_units.h" /* LV_G0 of the Isp definition mdot = F_vac / (Isp g0) */

#ifdef __cplusplus
extern "C" {
#endif


/* ------------------------------------------------------------------ engines -- */

/* One engine; thrust acts along the body x axis (3-DoF: no cant, no gimbal).
 *
 *   thrust = max(0, c F_vac(t) - p_amb A_exit)       N
 *   mdot   = c mdot_full(t)                           kg/s
 *
 * c is the throttle in effect, F_vac the full-throttle vacuum thrust. Constant
 * engines give F_vac = thrust_vac and mdot_full = mdot, or thrust_vac / (isp_vac g0)
 * when mdot is 0. With `table`, a 1-axis table over "time" (or "t") [s] gives
 * F_vac(t) from its output "thrust" [N] and mdot_full(t) from its output "mdot"
 * [kg/s] if it has one, else F_vac(t) / (isp_vac g0). Its breakpoints become time
 * events of the model, so no integration step crosses a kink; outside its time range
 * the table's own extrapolation rule applies. */
/* The largest throttle an engine's range may reach: 2, twice the thrust its thrust_vac and
 * mdot describe. c multiplies them, so they are the engine's rated (100 %) point; flown
 * engines throttle up to about 1.09 of it (the RS-25 at 109 %), and 2 leaves room for a rating
 * below the maximum, while a range up to 1e9 is a typing error that would let a law ask for
 * any thrust. lv_engine_init refuses a throttle_max above it, and a non-finite one. */
#define LV_THROTTLE_MAX 2.0

typedef struct lv_engine_config {
    const char *name;      /* for messages ("stage1.engine2"); copied; NULL: "engine<i>" */
    double thrust_vac;     /* N, vacuum thrust at full throttle (constant engines), > 0 */
    double isp_vac;        /* s, vacuum specific impulse; used when mdot is 0 */
    double mdot;           /* kg/s, mass flow at full throttle; 0: from isp_vac */
    double exit_area;      /* m^2, nozzle exit area A_exit, >= 0 */
    double throttle_min;   /* -, lowest throttle, >= 0 (default 0) */
    double throttle_max;   /* -, highest throttle, >= throttle_min, > 0, at most
                              LV_THROTTLE_MAX (default 1) */
    const lv_table *table; /* borrowed; NULL: constant engine (see above) */
    double out_after;      /* s, > 0: the engine stops (an engine-out) this long after the
                              model's start time, a time event of the model at which its
                              thrust and mass flow drop to 0; 0 (default): it never stops */
} lv_engine_config;

/* thrust_vac 0, isp_vac 0, mdot 0, exit_area 0, throttle [0, 1], no table, never out. */
LV_API void lv_engine_config_default(lv_engine_config *c);

/* ------------------------------------------------------------- aerodynamics -- */

/* Which axes the coefficients refer to (docs/models.md, "Aerodynamics"). */
typedef enum lv_aero_axes {
    LV_AERO_WIND = 0, /* coef[0..2] = CD, CL, CY: drag along -x_w, lift along -z_w,
                         side force along +y_w */
    LV_AERO_BODY = 1  /* coef[0..2] = CA, CN, CY: axial along -x_b, normal along -z_b,
                         side force along +y_b */
} lv_aero_axes;

/* One coefficient: a table output, or a constant. A table's axes are named after the
 * inputs that feed them: "mach" [-], "alpha" [rad], "beta" [rad], "altitude" [m]
 * (geodetic); any other axis name is an error at creation. Several coefficients may
 * share one table: it is then evaluated once per right-hand side. */
typedef struct lv_aero_coef {
    const lv_table *table; /* borrowed; NULL: the coefficient is `value` */
    const char *output;    /* output name in `table`; NULL: the table's only output, or
                              the coefficient's own name ("CD", "CL", "CY", "CA", "CN") */
    double value;          /* -, used when table is NULL */
} lv_aero_coef;

/* An aerodynamic data set: F = q S_ref C. One set per model configuration; a mission
 * switches sets by switching phases. */
typedef struct lv_aero_config {
    lv_aero_axes axes;
    double s_ref;         /* m^2, reference area, > 0 */
    lv_aero_coef coef[3]; /* CD, CL, CY (LV_AERO_WIND) or CA, CN, CY (LV_AERO_BODY) */
} lv_aero_config;

/* Wind axes, s_ref 1, every coefficient the constant 0. */
LV_API void lv_aero_config_default(lv_aero_config *c);

/* ---------------------------------------------------------------------- wind -- */

/* Wind velocity (air relative to the rotating planet), NED at the vehicle, m/s, at
 * geodetic altitude h [m], latitude and longitude [rad], time t [s]. Called from the
 * right-hand side: it must allocate nothing. Returns 0 (ok), > 0 (state not
 * acceptable: retry a smaller step) or < 0 (stop the run). `user` is the pointer
 * stored next to the function. */
typedef int (*lv_wind_fn)(double t, double h, double lat, double lon, double v_wind_ned[3],
                          void *user);

#ifdef __cplusplus
}
#endif
#endif
