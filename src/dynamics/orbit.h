/* orbit.h - osculating Keplerian elements from an inertial state (not exported). */
#ifndef LV_DYNAMICS_ORBIT_H
#define LV_DYNAMICS_ORBIT_H

typedef struct lv_orbit_elem {
    double a;      /* m, semi-major axis; < 0 for a hyperbola, INFINITY for a parabola */
    double e;      /* -, eccentricity */
    double i;      /* rad, inclination [0, pi] */
    double raan;   /* rad, right ascension of the ascending node [0, 2 pi); 0 if i = 0 */
    double argp;   /* rad, argument of periapsis [0, 2 pi); 0 if e = 0 */
    double nu;     /* rad, true anomaly [0, 2 pi) (from the node line / x axis if e = 0) */
    double r_apo;  /* m, apoapsis radius a (1 + e); INFINITY if e >= 1 */
    double r_peri; /* m, periapsis radius p / (1 + e) */
} lv_orbit_elem;

/* Elements of (r, v) in the inertial frame whose z axis is the planet's axis, for the
 * gravitational parameter gm (m^3/s^2). Vallado, Fundamentals of Astrodynamics and
 * Applications, 4th ed., algorithm 9 (RV2COE). Circular or equatorial orbits get the
 * conventions noted above instead of undefined angles. */
void lv_orbit_elements(double gm, const double r[3], const double v[3], lv_orbit_elem *el);

#endif
