/* frames.c - conversions between ECI, ECEF, geodetic, geocentric, NED and body
 * frames (definitions and equations: docs/frames.md). Geodetic from ECEF solves
 * for the nearest point of the meridian ellipse with a Newton iteration that is
 * monotone from a bracketing start (Eberly, "Distance from a point to an
 * ellipse", 2011), valid everywhere, the poles and the centre included. */
#include <math.h>

#include "lvsim/lv_planet.h"

#include "core/units.h"

double lv_frames_theta(const lv_planet *p, double t) { return p->theta0 + p->omega * t; }

void lv_frames_C_ecef_eci(const lv_planet *p, double t, double C[3][3])
{
    const double th = lv_frames_theta(p, t), c = cos(th), s = sin(th);
    C[0][0] = c;   C[0][1] = s;   C[0][2] = 0.0;
    C[1][0] = -s;  C[1][1] = c;   C[1][2] = 0.0;
    C[2][0] = 0.0; C[2][1] = 0.0; C[2][2] = 1.0;
}

/* The two geodetic conversions work in long double (64-bit significand on x86):
 * in double, the rounding of N + h, cos, sin and their products alone moves h
 * by ~3 ulp(|r|) = 3e-9 m at the Earth's surface; with the wider type the round
 * trip is limited by the final rounding of x, y, z to double (< 1e-9 m there).
 * Where long double is double (MSVC, some ARM ABIs) expect ~3e-9 m. */
void lv_frames_geodetic_to_ecef(const lv_planet *p, double lat, double lon, double h,
                                double r_ecef[3])
{
    const long double f = p->f, e2 = f * (2.0L - f);
    const long double sl = sinl(lat), cl = cosl(lat);
    const long double n = p->a / sqrtl(1.0L - e2 * sl * sl); /* prime-vertical radius, m */
    r_ecef[0] = (double)((n + h) * cl * cosl(lon));
    r_ecef[1] = (double)((n + h) * cl * sinl(lon));
    r_ecef[2] = (double)((n * (1.0L - e2) + h) * sl);
}

/* Geodetic latitude of (w, z), w >= 0, z >= 0: the normal at the nearest point
 * (x0, z0) of the ellipse x^2/a^2 + z^2/b^2 = 1. With u = t + b^2 (t the Lagrange
 * multiplier, docs/frames.md eq. F6), F(u) = (a w / (u + c))^2 + (b z / u)^2 - 1,
 * c = a^2 - b^2, is convex and decreasing on u > 0; Newton from u0 with F(u0) >= 0
 * increases monotonically to the root. */
static long double geodetic_lat_quadrant(long double a, long double b, long double w,
                                         long double z)
{
    const long double c = (a - b) * (a + b);
    if (z == 0.0L) {
        if (w * a > c)
            return 0.0L;
        if (c == 0.0L) /* the centre of a sphere: every direction is normal */
            return (long double)LV_PI / 2;
        /* inside the evolute on the equator: limit z -> 0+ (eq. F8) */
        const long double q = a * w / c; /* x0 / a */
        return atan2l(c * sqrtl(1.0L - q * q), b * w);
    }
    const long double aw = a * w, bz = b * z;
    long double u = bz > aw - c ? bz : aw - c;
    for (int k = 0; k < 200; k++) {
        const long double s1 = aw / (u + c), s2 = bz / u;
        const long double f = s1 * s1 + s2 * s2 - 1.0L;
        if (!(f > 0.0L))
            break;
        const long double df = -2.0L * (s1 * s1 / (u + c) + s2 * s2 / u);
        const long double du = -f / df;
        u += du;
        if (du <= 1e-19L * u)
            break;
    }
    return atan2l(z * (u + c), w * u);
}

void lv_frames_ecef_to_geodetic(const lv_planet *p, const double r_ecef[3], double *lat,
                                double *lon, double *h)
{
    const long double a = p->a, f = p->f, b = a * (1.0L - f), e2 = f * (2.0L - f);
    const long double w = hypotl(r_ecef[0], r_ecef[1]), z = fabsl(r_ecef[2]);
    const long double phi = geodetic_lat_quadrant(a, b, w, z);
    const long double sp = sinl(phi), cp = cosl(phi);
    if (lat != NULL)
        *lat = (double)(r_ecef[2] < 0.0 ? -phi : phi);
    if (lon != NULL)
        *lon = atan2(r_ecef[1], r_ecef[0]);
    /* distance along the normal (eq. F7), well conditioned at all latitudes */
    if (h != NULL)
        *h = (double)(w * cp + z * sp - a * sqrtl(1.0L - e2 * sp * sp));
}

void lv_frames_geocentric_to_ecef(double lat_gc, double lon, double radius, double r_ecef[3])
{
    r_ecef[0] = radius * cos(lat_gc) * cos(lon);
    r_ecef[1] = radius * cos(lat_gc) * sin(lon);
    r_ecef[2] = radius * sin(lat_gc);
}

void lv_frames_ecef_to_geocentric(const double r_ecef[3], double *lat_gc, double *lon,
                                  double *radius)
{
    const double w = hypot(r_ecef[0], r_ecef[1]);
    if (lat_gc != NULL)
        *lat_gc = atan2(r_ecef[2], w);
    if (lon != NULL)
        *lon = atan2(r_ecef[1], r_ecef[0]);
    if (radius != NULL)
        *radius = hypot(w, r_ecef[2]);
}

void lv_frames_eci_to_ecef(const lv_planet *p, double t, const double r_eci[3],
                           const double v_eci[3], double r_ecef[3], double v_ecef[3])
{
    const double th = lv_frames_theta(p, t), c = cos(th), s = sin(th);
    r_ecef[0] = c * r_eci[0] + s * r_eci[1];
    r_ecef[1] = -s * r_eci[0] + c * r_eci[1];
    r_ecef[2] = r_eci[2];
    if (v_eci != NULL && v_ecef != NULL) {
        /* v_rel = v_eci - w x r_eci, w = (0, 0, omega) (eq. F3) */
        const double vx = v_eci[0] + p->omega * r_eci[1];
        const double vy = v_eci[1] - p->omega * r_eci[0];
        v_ecef[0] = c * vx + s * vy;
        v_ecef[1] = -s * vx + c * vy;
        v_ecef[2] = v_eci[2];
    }
}

void lv_frames_ecef_to_eci(const lv_planet *p, double t, const double r_ecef[3],
                           const double v_ecef[3], double r_eci[3], double v_eci[3])
{
    const double th = lv_frames_theta(p, t), c = cos(th), s = sin(th);
    r_eci[0] = c * r_ecef[0] - s * r_ecef[1];
    r_eci[1] = s * r_ecef[0] + c * r_ecef[1];
    r_eci[2] = r_ecef[2];
    if (v_ecef != NULL && v_eci != NULL) {
        v_eci[0] = c * v_ecef[0] - s * v_ecef[1] - p->omega * r_eci[1];
        v_eci[1] = s * v_ecef[0] + c * v_ecef[1] + p->omega * r_eci[0];
        v_eci[2] = v_ecef[2];
    }
}

void lv_frames_C_ned_ecef(double lat, double lon, double C[3][3])
{
    const double sp = sin(lat), cp = cos(lat), sl = sin(lon), cl = cos(lon);
    C[0][0] = -sp * cl; C[0][1] = -sp * sl; C[0][2] = cp;  /* north */
    C[1][0] = -sl;      C[1][1] = cl;       C[1][2] = 0.0; /* east  */
    C[2][0] = -cp * cl; C[2][1] = -cp * sl; C[2][2] = -sp; /* down  */
}

void lv_frames_C_body_ned(double psi, double theta, double phi, double C[3][3])
{
    const double cs = cos(psi), ss = sin(psi), ct = cos(theta), st = sin(theta);
    const double cf = cos(phi), sf = sin(phi);
    C[0][0] = ct * cs;                C[0][1] = ct * ss;                C[0][2] = -st;
    C[1][0] = sf * st * cs - cf * ss; C[1][1] = sf * st * ss + cf * cs; C[1][2] = sf * ct;
    C[2][0] = cf * st * cs + sf * ss; C[2][1] = cf * st * ss - sf * cs; C[2][2] = cf * ct;
}

void lv_frames_euler_from_C_body_ned(const double C[3][3], double *psi, double *theta,
                                     double *phi)
{
    const double ct = hypot(C[0][0], C[0][1]);
    /* atan2 rather than asin(-C13): well conditioned near theta = +-pi/2 */
    *theta = atan2(-C[0][2], ct);
    if (ct > 1e-12) {
        *psi = atan2(C[0][1], C[0][0]);
        *phi = atan2(C[1][2], C[2][2]);
    } else { /* gimbal lock: with phi = 0, C21 = -sin psi, C22 = cos psi */
        *psi = atan2(-C[1][0], C[1][1]);
        *phi = 0.0;
    }
}

void lv_frames_fpa_from_ned(const double v_ned[3], double *speed, double *gamma, double *chi)
{
    const double vh = hypot(v_ned[0], v_ned[1]);
    if (speed != NULL)
        *speed = hypot(vh, v_ned[2]);
    if (gamma != NULL)
        *gamma = atan2(-v_ned[2], vh);
    if (chi != NULL) {
        double c = vh > 0.0 ? atan2(v_ned[1], v_ned[0]) : 0.0;
        if (c < 0.0)
            c += 2.0 * LV_PI;
        *chi = c >= 2.0 * LV_PI ? 0.0 : c;
    }
}

void lv_frames_ned_from_fpa(double speed, double gamma, double chi, double v_ned[3])
{
    v_ned[0] = speed * cos(gamma) * cos(chi);
    v_ned[1] = speed * cos(gamma) * sin(chi);
    v_ned[2] = -speed * sin(gamma);
}
