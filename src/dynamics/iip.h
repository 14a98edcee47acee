/* iip.h - instantaneous impact point (IIP): where a vehicle would meet the planet's reference
 * ellipsoid (geodetic h = 0) if thrust stopped now and no drag acted, over the rotating planet
 * (docs/models.md, "Instantaneous impact point"). Not exported. */
#ifndef LV_DYNAMICS_IIP_H
#define LV_DYNAMICS_IIP_H

#include "lvsim/lv_planet.h"

typedef struct lv_iip {
    int valid;        /* 1: the drag-free path meets the ellipsoid; 0: it does not (in orbit,
                         escaping, or no crossing within the search time, at most
                         LV_IIP_HORIZON): lat, lon, tof, range are NAN then */
    double lat, lon;  /* rad: geodetic latitude, longitude (-pi, pi] of the impact point,
                         in the planet-fixed frame at the time of impact */
    double tof;       /* s, time of flight from the state to the impact, >= 0 */
    double r_eci[3];  /* m, the impact point in ECI */
    double r_ecef[3]; /* m, the impact point in ECEF at the time of impact */
} lv_iip;

/* The IIP of the Kepler conic of (r_eci, v_eci) at time t [s] under the point mass gm
 * [m^3/s^2]: the first descending crossing of the conic with the ellipsoid of p, found by
 * iterating the crossing radius on the ellipsoid's geocentric radius at the crossing's latitude
 * (the ellipsoid is symmetric about the rotation axis, so the crossing is found in ECI), the
 * time of flight by Kepler's equation (elliptic or hyperbolic; Vallado, Fundamentals of
 * Astrodynamics and Applications, 4th ed., secs. 2.2-2.3, eqs. 2-4 and 2-35; the position by
 * the f and g functions of the eccentric anomaly, sec. 2.3), the longitude from ECEF at t + tof
 * (the planet turned by omega tof). A state at or below the ellipsoid is its own impact point
 * (tof 0). No crossing (periapsis above the ellipsoid, an escaping path): valid = 0. Pure. */
void lv_iip_conic(const lv_planet *p, double gm, double t, const double r_eci[3],
                  const double v_eci[3], lv_iip *out);

/* The IIP by propagating the drag-free path in ECI under the gravity model g (evaluated in
 * ECEF at each time, so any model, "sh" included; ws: lv_gravity_ws_size(g) doubles of
 * scratch) with classical fourth-order Runge-Kutta steps of at most LV_IIP_STEP s near the
 * planet (at least LV_IIP_MIN_STEPS over the conic's time of flight), longer as (r/a)^1.5
 * above it (at most LV_IIP_MAX_STEPS steps in all), the crossing of the ellipsoid
 * located on the step that crosses it by the cubic Hermite interpolant of its end states
 * (regula falsi, Illinois). The conic (gm: g's GM) gives the verdict for paths whose
 * periapsis is more than LV_IIP_MARGIN above the equator's radius (no impact), the answer for
 * an impact less than LV_IIP_TOF_CONIC ahead, and the time limit of the search: 1.5 times
 * its time of flight + 60 s, or one period of the conic when
 * it misses a periapsis within the margin; never beyond LV_IIP_HORIZON: an impact later than
 * that (the conic's or the propagation's) is "no impact" (valid 0), which bounds the cost of a
 * row to about 1600 steps. Accuracy against a converged propagation:
 * docs/models.md (a few metres along the kourou-leo ascent). Not hot: meant for output rows. */
void lv_iip_propagate(const lv_planet *p, const lv_gravity *g, double *ws, double gm, double t,
                      const double r_eci[3], const double v_eci[3], lv_iip *out);

/* Great-circle distance [m] on the sphere of radius a between the directions of two ECEF
 * positions (as the `downrange` output measures): a times the angle between them, by atan2 of
 * their cross and dot products (accurate at all distances). */
double lv_iip_range(double a, const double r0_ecef[3], const double r1_ecef[3]);

#define LV_IIP_STEP 20.0      /* s, largest Runge-Kutta step of lv_iip_propagate */
#define LV_IIP_MIN_STEPS 8   /* fewest steps over the conic's time of flight */
#define LV_IIP_MAX_STEPS 4000 /* most steps of one propagation */
#define LV_IIP_MARGIN 50e3   /* m: periapsis above a + this: no impact without propagating */
#define LV_IIP_HORIZON 21600.0 /* s (6 h): impacts later than this are not looked for */
#define LV_IIP_TOF_CONIC 0.1   /* s: an impact sooner than this is the conic's (J2 moves it
                                  by < 0.1 mm) */

#endif
