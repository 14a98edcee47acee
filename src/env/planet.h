/* planet.h - lv_vec3 adapters of lv_planet.h for code inside the library
 * (dynamics, outputs). Not exported; the public API uses double[3]. Matrices need
 * no adapter: pass lv_mat3.m, e.g. lv_frames_C_ned_ecef(lat, lon, C.m). */
#ifndef LV_ENV_PLANET_H
#define LV_ENV_PLANET_H

#include "core/vec3.h"
#include "lvsim/lv_planet.h"

static inline lv_vec3 lv_frames_geodetic_to_ecef_v(const lv_planet *p, double lat, double lon,
                                                   double h)
{
    double r[3];
    lv_frames_geodetic_to_ecef(p, lat, lon, h, r);
    return lv_v3(r[0], r[1], r[2]);
}

static inline void lv_frames_ecef_to_geodetic_v(const lv_planet *p, lv_vec3 r_ecef, double *lat,
                                                double *lon, double *h)
{
    const double r[3] = {r_ecef.x, r_ecef.y, r_ecef.z};
    lv_frames_ecef_to_geodetic(p, r, lat, lon, h);
}

/* Gravitational acceleration in ECEF (ws: lv_gravity_ws_size(g) doubles). */
static inline lv_vec3 lv_gravity_accel_ecef_v(const lv_gravity *g, double *ws, lv_vec3 r_ecef)
{
    const double r[3] = {r_ecef.x, r_ecef.y, r_ecef.z};
    double a[3];
    lv_gravity_eval(g, ws, r, a, NULL);
    return lv_v3(a[0], a[1], a[2]);
}

/* Gravitational acceleration in ECI at time t: rotate r_eci into ECEF, evaluate,
 * rotate back (docs/frames.md eq. F2). */
static inline lv_vec3 lv_gravity_accel_eci_v(const lv_gravity *g, const lv_planet *p, double t,
                                             double *ws, lv_vec3 r_eci)
{
    lv_mat3 C;
    lv_frames_C_ecef_eci(p, t, C.m);
    const lv_vec3 a_ecef = lv_gravity_accel_ecef_v(g, ws, lv_m3_mul_v3(&C, r_eci));
    return lv_m3t_mul_v3(&C, a_ecef);
}

#endif
