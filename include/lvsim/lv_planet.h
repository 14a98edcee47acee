/* lv_planet.h - central bodies (reference ellipsoid, GM, rotation), frame conversions
 * and gravity models.
 *
 * Frames (ECI, ECEF, geodetic, geocentric, NED, body), their axes, origins, signs and
 * angle ranges are defined once, in docs/frames.md; the gravity models and the
 * coefficient file format in docs/gravity.md. SI units and radians everywhere:
 * positions in m, velocities in m/s, accelerations in m/s^2, `t` in SI seconds since
 * the mission epoch (a leap second inside the mission is one more second like any other).
 * The epoch's date never enters the physics: ECEF is ECI turned by theta0 + omega t, so
 * theta(0) = theta0 whatever the date (no GMST or Earth rotation angle of the epoch).
 * Vectors are `double[3]` (x, y, z or north, east, down);
 * matrices are row-major `double[3][3]`, and C_a_b maps b-frame components to a.
 */
#ifndef LVSIM_LV_PLANET_H
#define LVSIM_LV_PLANET_H

#include <stddef.h>

#include "lvsim/lv_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------- planets -- */

#define LV_PLANET_NAME_MAX 16

/* A central body: plain data, copied by value. The reference ellipsoid (a, f) is
 * used for geodetic coordinates; gm, r_ref and j2..j4 feed the "pointmass", "j2"
 * and "zonal" gravity models; omega and theta0 give the ECI -> ECEF rotation
 * theta(t) = theta0 + omega * t about the common z axis. */
typedef struct lv_planet {
    char name[LV_PLANET_NAME_MAX]; /* "earth", "moon", "mars" or the user's */
    double a;                      /* equatorial radius of the ellipsoid, m */
    double f;                      /* flattening (a - b) / a, -; 0 for a sphere */
    double gm;                     /* gravitational parameter, m^3/s^2 */
    double omega;                  /* rotation rate about +z, rad/s */
    double theta0;                 /* rotation angle ECI -> ECEF at t = 0, rad */
    double r_ref;                  /* reference radius of j2..j4, m */
    double j2, j3, j4;             /* unnormalised zonal coefficients J_n = -C_n0, - */
} lv_planet;

/* Earth: WGS-84 ellipsoid, GM and rotation rate (NIMA TR8350.2, 3rd ed., 2000,
 * chapter 3); J2..J4 from the EGM2008 C(n,0) shipped in data/gravity, at its
 * reference radius 6378136.3 m. theta0 = 0. */
LV_API lv_planet lv_planet_earth(void);
/* Moon: sphere of Wieczorek (2015) (R = 1737151 m, GM = 4.9028001e12 m^3/s^2,
 * omega = 2.6617073e-6 rad/s); J2..J4 = 0: take them from a lunar field model. */
LV_API lv_planet lv_planet_moon(void);
/* Mars: NASA NSSDC Mars fact sheet (a = 3396.2 km, f = 0.00589,
 * GM = 42828 km^3/s^2, J2 = 1960.45e-6, sidereal day 24.6229 h); J3 = J4 = 0. */
LV_API lv_planet lv_planet_mars(void);

/* Preset by name ("earth", "moon", "mars"). Unknown name: LV_ERR_NOTFOUND with
 * a nearest-name suggestion. */
LV_API lv_status lv_planet_by_name(const char *name, lv_planet *out, lv_err *err);
/* Checks a user-built planet: a > 0, 0 <= f < 1, gm > 0, r_ref > 0, all finite, and
 * |omega| < sqrt(gm / a^3) (the equator turns slower than a circular orbit there).
 * LV_ERR_INPUT names the planet and the field. */
LV_API lv_status lv_planet_check(const lv_planet *p, lv_err *err);

LV_API double lv_planet_b(const lv_planet *p);  /* polar radius a (1 - f), m */
LV_API double lv_planet_e2(const lv_planet *p); /* first eccentricity squared f (2 - f), - */
/* J_n (n = 2, 4, 6, ...) of the normal gravity field of the level ellipsoid
 * (a, f, gm, omega) (Heiskanen & Moritz 1967, ch. 2, series of the normal potential;
 * formulas in docs/gravity.md); 0 for odd n. */
LV_API double lv_planet_normal_j(const lv_planet *p, int n);

/* ----------------------------------------------------------------- frames -- */

/* Rotation angle theta(t) = theta0 + omega t of ECEF relative to ECI, rad. */
LV_API double lv_frames_theta(const lv_planet *p, double t);
/* C_ecef_eci(t) = R3(theta(t)). */
LV_API void lv_frames_C_ecef_eci(const lv_planet *p, double t, double C[3][3]);

/* Geodetic (lat, lon, h over the ellipsoid) -> ECEF position. */
LV_API void lv_frames_geodetic_to_ecef(const lv_planet *p, double lat, double lon, double h,
                                       double r_ecef[3]);
/* ECEF -> geodetic. lat in [-pi/2, pi/2], lon in (-pi, pi], h the signed distance
 * along the normal to the nearest point of the ellipsoid (docs/frames.md,
 * "Geodetic from ECEF"). Accurate to ~1e-15 rad and a few 1e-10 m everywhere,
 * poles and the centre included; any pointer may be NULL. */
LV_API void lv_frames_ecef_to_geodetic(const lv_planet *p, const double r_ecef[3], double *lat,
                                       double *lon, double *h);
/* Geocentric (lat_gc, lon, radius) <-> ECEF. At the centre lat_gc = 0. */
LV_API void lv_frames_geocentric_to_ecef(double lat_gc, double lon, double radius,
                                         double r_ecef[3]);
LV_API void lv_frames_ecef_to_geocentric(const double r_ecef[3], double *lat_gc, double *lon,
                                         double *radius);

/* ECI <-> ECEF position and velocity at time t. The ECEF velocity is relative to
 * the rotating planet: v_ecef = C_ecef_eci (v_eci - w x r_eci). A velocity
 * pointer may be NULL (position only); input and output may not alias. */
LV_API void lv_frames_eci_to_ecef(const lv_planet *p, double t, const double r_eci[3],
                                  const double v_eci[3], double r_ecef[3], double v_ecef[3]);
LV_API void lv_frames_ecef_to_eci(const lv_planet *p, double t, const double r_ecef[3],
                                  const double v_ecef[3], double r_eci[3], double v_eci[3]);

/* C_ned_ecef at geodetic (lat, lon): rows are the north, east and down axes. */
LV_API void lv_frames_C_ned_ecef(double lat, double lon, double C[3][3]);
/* C_body_ned = R1(phi) R2(theta) R3(psi), 3-2-1 Euler angles (yaw psi, pitch
 * theta, roll phi). */
LV_API void lv_frames_C_body_ned(double psi, double theta, double phi, double C[3][3]);
/* Inverse: psi, phi in (-pi, pi], theta in [-pi/2, pi/2]; at theta = +-pi/2
 * (gimbal lock) phi = 0 and psi takes the whole rotation about the vertical. */
LV_API void lv_frames_euler_from_C_body_ned(const double C[3][3], double *psi, double *theta,
                                            double *phi);

/* Speed, flight-path angle gamma (positive up, [-pi/2, pi/2]) and heading chi
 * (from north towards east, [0, 2 pi)) of a NED velocity; at zero horizontal
 * speed chi = 0. Any output pointer may be NULL. */
LV_API void lv_frames_fpa_from_ned(const double v_ned[3], double *speed, double *gamma,
                                   double *chi);
LV_API void lv_frames_ned_from_fpa(double speed, double gamma, double chi, double v_ned[3]);

/* ---------------------------------------------------------------- gravity -- */

/* A gravity model instance: read-only after creation, so one instance may be
 * shared by several threads; each thread passes its own workspace. */
typedef struct lv_gravity lv_gravity;

typedef enum lv_gravity_kind {
    LV_GRAVITY_POINTMASS, /* "pointmass": -GM r / |r|^3 */
    LV_GRAVITY_J2,        /* "j2": point mass + J2 */
    LV_GRAVITY_ZONAL,     /* "zonal": point mass + J2, J3, J4 (or J2 .. Jn given) */
    LV_GRAVITY_SH         /* "sh": spherical harmonics to degree/order from a file */
} lv_gravity_kind;

/* Zero-initialised fields give the defaults: whole file, all orders, shipped file. */
#define LV_GRAVITY_ORDER_ZONAL (-1) /* lv_gravity_config.order: zonal terms (m = 0) only */
#define LV_GRAVITY_ZONAL_MAX 40     /* highest degree of the closed-form zonal model */
typedef struct lv_gravity_config {
    const char *model;     /* "pointmass", "j2", "zonal" or "sh" */
    int degree;            /* "sh": maximum degree n; 0 = the file's max_degree */
    int order;             /* "sh": maximum order m <= degree; 0 = degree (all orders);
                            * LV_GRAVITY_ORDER_ZONAL = 0 (zonal terms only) */
    const char *coef_path; /* "sh": ICGEM .gfc file; NULL = lv_gravity_default_file() */
} lv_gravity_config;

/* What a model is, for reports and for analytic checks (e.g. J2 secular rates
 * dOmega/dt = -3/2 n J2 (r_ref/p)^2 cos i need gm, r_ref and jn[2]). */
typedef struct lv_gravity_info {
    const char *name;     /* registry name, static */
    lv_gravity_kind kind;
    int degree, order;    /* highest degree and order evaluated */
    double gm;            /* m^3/s^2 */
    double r_ref;         /* m */
    double jn[5];         /* J_0..J_4, unnormalised (jn[0] = jn[1] = 0);
                           * for "sh" -sqrt(2n+1) C(n,0) of the file */
} lv_gravity_info;

/* The shipped coefficient file (EGM2008 to degree and order 20), data file
 * gravity/egm2008_n20.gfc, found at run time by lv_data_find() (lvsim/lv_data.h:
 * $LVSIM_DATA, next to the library, the install prefix). Writes its path to path[size].
 * Not found: LV_ERR_NOTFOUND, the message lists the folders searched. */
#define LV_GRAVITY_DEFAULT_FILE "gravity/egm2008_n20.gfc"
LV_API lv_status lv_gravity_default_file(char *path, size_t size, lv_err *err);

/* Parses "pointmass", "j2", "zonal", "sh", "sh:N" or "sh:NxM" into cfg ("sh:Nx0"
 * gives order LV_GRAVITY_ORDER_ZONAL; degree and order 0, coef_path NULL unless
 * given). cfg->model points into a static table.
 * Unknown name: LV_ERR_NOTFOUND with a nearest-name suggestion; bad N or M:
 * LV_ERR_INPUT. */
LV_API lv_status lv_gravity_parse_spec(const char *spec, lv_gravity_config *cfg, lv_err *err);

/* Creates a model for `planet` (copied; not kept). "sh" reads the coefficient
 * file now (see docs/gravity.md for the format and the errors, which carry
 * file:line) and uses the file's GM and radius; the other models use planet->gm,
 * r_ref and j2..j4. The caller frees *out with lv_gravity_free(). */
LV_API lv_status lv_gravity_create(const lv_planet *planet, const lv_gravity_config *cfg,
                                   lv_gravity **out, lv_err *err);
/* A closed-form model with the caller's zonal coefficients instead of the planet's
 * j2..j4: zonal[0 .. n_zonal-1] = J2, J3, .. J_(n_zonal + 1) (unnormalised, at planet->r_ref;
 * copied). `model` "zonal" takes all of them, "j2" only J2, "pointmass" none. LV_ERR_INPUT
 * for n_zonal outside 1 .. LV_GRAVITY_ZONAL_MAX - 1, a coefficient not finite or |J| >= 1,
 * or another model. */
LV_API lv_status lv_gravity_create_zonal(const lv_planet *planet, const char *model,
                                         const double *zonal, int n_zonal, lv_gravity **out,
                                         lv_err *err);
/* Creates an "sh" model from fully normalised coefficients given in memory:
 * cnm[k], snm[k] with k = n (n + 1) / 2 + m, 0 <= m <= n <= degree (the arrays
 * hold (degree + 1)(degree + 2) / 2 values each; snm may be NULL: all zero). The
 * values are copied. */
LV_API lv_status lv_gravity_create_sh(double gm, double r_ref, int degree, int order,
                                      const double *cnm, const double *snm, lv_gravity **out,
                                      lv_err *err);
LV_API void lv_gravity_free(lv_gravity *g);

LV_API void lv_gravity_info_get(const lv_gravity *g, lv_gravity_info *info);

/* Workspace an evaluation needs, in doubles (0 for the closed-form models, for
 * which ws may be NULL). Allocate it once per thread, outside the hot path. */
LV_API size_t lv_gravity_ws_size(const lv_gravity *g);

/* Gravitational acceleration a = grad U at r_ecef (ECEF, m; |r| > 0), m/s^2, and
 * optionally the potential U (> 0, GM/r for a point mass), m^2/s^2 (U may be
 * NULL). Allocates nothing, never fails, finite at the poles. ws: at least
 * lv_gravity_ws_size(g) doubles, used as scratch. */
LV_API void lv_gravity_eval(const lv_gravity *g, double *ws, const double r_ecef[3],
                            double a_ecef[3], double *U);

/* Gravity at a geodetic point, for reports and the CLI (allocates its own
 * workspace, so not for the hot path). */
typedef struct lv_gravity_local {
    double r_ecef[3];    /* position, ECEF, m */
    double g_ned[3];     /* gravitation, NED, m/s^2 */
    double g_eff_ned[3]; /* gravitation + centrifugal (planet-fixed observer), NED, m/s^2 */
    double potential;    /* gravitational potential U, m^2/s^2 */
} lv_gravity_local;
LV_API lv_status lv_gravity_at_geodetic(const lv_gravity *g, const lv_planet *planet, double lat,
                                        double lon, double h, lv_gravity_local *out, lv_err *err);

#ifdef __cplusplus
}
#endif
#endif
