/* iip.c - instantaneous impact point: the Kepler conic's crossing of the reference ellipsoid
 * (Vallado, Fundamentals of Astrodynamics and Applications, 4th ed., secs. 2.2-2.3) and a
 * drag-free RK4 propagation under the mission's gravity model to the ellipsoid, the crossing
 * located by cubic Hermite interpolation. Method and measured accuracy: docs/models.md. */
#include <math.h>
#include <string.h>

#include "core/vec3.h"
#include "dynamics/iip.h"
#include "env/planet.h"

#define TWO_PI 6.28318530717958647692

/* The ellipsoid's implicit function (x^2 + y^2) / a^2 + z^2 / b^2 - 1: < 0 inside, 0 on it,
 * > 0 outside; the same in ECI and ECEF (symmetric about z). */
static double surf(double ia2, double ib2, lv_vec3 r)
{
    return (r.x * r.x + r.y * r.y) * ia2 + r.z * r.z * ib2 - 1.0;
}

static void set_invalid(lv_iip *out)
{
    out->valid = 0;
    out->lat = out->lon = out->tof = NAN;
    for (int k = 0; k < 3; k++)
        out->r_eci[k] = out->r_ecef[k] = NAN;
}

/* The impact at r_imp (ECI) after tof: ECEF at t + tof, geodetic latitude and longitude. */
static void set_impact(const lv_planet *p, double t, double tof, lv_vec3 r_imp, lv_iip *out)
{
    const double r[3] = {r_imp.x, r_imp.y, r_imp.z};
    out->valid = 1;
    out->tof = tof;
    memcpy(out->r_eci, r, sizeof r);
    lv_frames_eci_to_ecef(p, t + tof, r, NULL, out->r_ecef, NULL);
    lv_frames_ecef_to_geodetic(p, out->r_ecef, &out->lat, &out->lon, NULL);
}

/* The conic's shape: 1 / semi-major axis (alpha = 2 / r - v^2 / gm, vis-viva), eccentricity,
 * periapsis radius. */
typedef struct conic {
    double r, rv, alpha, e, r_peri;
} conic;

static conic conic_of(double gm, lv_vec3 r, lv_vec3 v)
{
    conic c;
    c.r = lv_v3_norm(r);
    c.rv = lv_v3_dot(r, v);
    c.alpha = 2.0 / c.r - lv_v3_dot(v, v) / gm;
    const lv_vec3 h = lv_v3_cross(r, v);
    const double p = lv_v3_dot(h, h) / gm; /* semi-latus rectum */
    c.e = sqrt(fmax(0.0, 1.0 - p * c.alpha)); /* e^2 = 1 - p / a */
    c.r_peri = p / (1.0 + c.e);
    return c;
}

void lv_iip_conic(const lv_planet *p, double gm, double t, const double r_eci[3],
                  const double v_eci[3], lv_iip *out)
{
    set_invalid(out);
    const double b = p->a * (1.0 - p->f);
    const double ia2 = 1.0 / (p->a * p->a), ib2 = 1.0 / (b * b);
    const lv_vec3 r0 = {r_eci[0], r_eci[1], r_eci[2]}, v0 = {v_eci[0], v_eci[1], v_eci[2]};
    if (surf(ia2, ib2, r0) <= 0.0) { /* at or below the ellipsoid: here, now */
        set_impact(p, t, 0.0, r0, out);
        return;
    }
    const conic c = conic_of(gm, r0, v0);
    if (!(c.r_peri < p->a) || !(c.e > 0.0))
        return; /* the conic never comes inside the ellipsoid's equatorial sphere */
    if (c.alpha <= 0.0 && c.rv >= 0.0)
        return; /* open and outbound: escaping */
    if (c.alpha == 0.0)
        return; /* parabola: not handled (measure zero) */
    /* the ellipsoid's geocentric radius under the vehicle: |r| / sqrt(surf + 1) */
    double R = c.r / sqrt(surf(ia2, ib2, r0) + 1.0);
    lv_vec3 ri = r0;
    double tof = NAN;
    for (int it = 0; it < 30; it++) {
        double fc, gc; /* f and g functions: ri = fc r0 + gc v0 (Vallado eq. 2-65 ff.) */
        const double e = c.e, a_sm = 1.0 / c.alpha;
        const double cE = (1.0 - R * c.alpha) / e; /* e cos E = 1 - r / a at r = R */
        if (c.alpha > 0.0) { /* ellipse: r = a (1 - e cos E), M = E - e sin E */
            const double n = sqrt(gm * c.alpha * c.alpha * c.alpha);
            const double esE0 = c.rv / sqrt(gm * a_sm); /* r.v = sqrt(gm a) e sin E */
            const double E0 = atan2(esE0, 1.0 - c.r * c.alpha);
            if (cE > 1.0)
                return; /* R below the periapsis: no crossing */
            double E1 = -acos(fmax(-1.0, cE)); /* descending: sin E < 0 */
            if (E1 <= E0)
                E1 += TWO_PI;
            const double dE = E1 - E0;
            tof = (dE - e * sin(E1) + esE0) / n;
            fc = 1.0 - a_sm / c.r * (1.0 - cos(dE));
            gc = tof - (dE - sin(dE)) / n;
        } else { /* hyperbola, inbound: r = a (1 - e cosh F), M = e sinh F - F */
            const double n = sqrt(gm * -c.alpha * c.alpha * c.alpha);
            const double esF0 = c.rv / sqrt(-gm * a_sm); /* r.v = sqrt(-gm a) e sinh F */
            const double F0 = asinh(esF0 / e);
            if (cE < 1.0)
                return; /* R below the periapsis */
            const double F1 = -acosh(cE);
            if (F1 <= F0)
                return;
            const double dF = F1 - F0;
            tof = (e * sinh(F1) - F1 - esF0 + F0) / n;
            fc = 1.0 - a_sm / c.r * (1.0 - cosh(dF));
            gc = tof - (sinh(dF) - dF) / n;
        }
        ri = lv_v3_add(lv_v3_scale(r0, fc), lv_v3_scale(v0, gc));
        const double rn = lv_v3_norm(ri);
        const double R_new = rn / sqrt(surf(ia2, ib2, ri) + 1.0); /* at ri's latitude */
        const double dR = R_new - R;
        R = R_new;
        if (fabs(dR) < 1e-6)
            break;
    }
    set_impact(p, t, tof, ri, out);
}

/* Gravitational acceleration in ECI at mission time t: a field symmetric about the rotation
 * axis (point mass, zonal terms: `axisym`) is the same function in ECI as in ECEF, so it is
 * evaluated at r_eci directly; any other in ECEF at t, turned back. */
static lv_vec3 accel(const lv_planet *p, const lv_gravity *g, double *ws, int axisym, double t,
                     lv_vec3 r)
{
    if (axisym)
        return lv_gravity_accel_ecef_v(g, ws, r);
    return lv_gravity_accel_eci_v(g, p, t, ws, r);
}

/* Cubic Hermite interpolant of the position over a step of length h at s in [0, 1]. */
static lv_vec3 hermite(lv_vec3 r0, lv_vec3 v0, lv_vec3 r1, lv_vec3 v1, double h, double s)
{
    const double s2 = s * s, s3 = s2 * s;
    const double h00 = 2.0 * s3 - 3.0 * s2 + 1.0, h10 = s3 - 2.0 * s2 + s;
    const double h01 = -2.0 * s3 + 3.0 * s2, h11 = s3 - s2;
    return lv_v3_add(lv_v3_add(lv_v3_scale(r0, h00), lv_v3_scale(v0, h10 * h)),
                     lv_v3_add(lv_v3_scale(r1, h01), lv_v3_scale(v1, h11 * h)));
}

void lv_iip_propagate(const lv_planet *p, const lv_gravity *g, double *ws, double gm, double t,
                      const double r_eci[3], const double v_eci[3], lv_iip *out)
{
    lv_iip con;
    lv_iip_conic(p, gm, t, r_eci, v_eci, &con);
    const lv_vec3 r_start = {r_eci[0], r_eci[1], r_eci[2]};
    const lv_vec3 v_start = {v_eci[0], v_eci[1], v_eci[2]};
    const double b = p->a * (1.0 - p->f);
    const double ia2 = 1.0 / (p->a * p->a), ib2 = 1.0 / (b * b);
    if (con.valid && con.tof < LV_IIP_TOF_CONIC) { /* at or below the ellipsoid, or about to
                                                       hit it: the conic is exact enough */
        *out = con;
        return;
    }
    double tof_est, t_lim;
    if (con.valid) {
        if (!(con.tof <= LV_IIP_HORIZON)) { /* comes down, but not within the horizon */
            set_invalid(out);
            return;
        }
        tof_est = con.tof;
        t_lim = 1.5 * con.tof + 60.0;
    } else {
        const conic c = conic_of(gm, r_start, v_start);
        if (!(c.alpha > 0.0) || !(c.r_peri < p->a + LV_IIP_MARGIN)) {
            *out = con; /* escaping, or periapsis well clear of the ellipsoid */
            return;
        }
        /* bound and grazing: the conic misses, the field may not; one period */
        tof_est = t_lim = TWO_PI / sqrt(gm * c.alpha * c.alpha * c.alpha);
    }
    if (t_lim > LV_IIP_HORIZON) /* no search beyond the horizon */
        t_lim = LV_IIP_HORIZON;
    if (tof_est > t_lim)
        tof_est = t_lim;
    set_invalid(out);
    double n_steps = ceil(tof_est / LV_IIP_STEP);
    if (n_steps < LV_IIP_MIN_STEPS)
        n_steps = LV_IIP_MIN_STEPS;
    const double h_near = tof_est / n_steps; /* the step near the ellipsoid */
    if (!(h_near > 0.0) || !isfinite(h_near))
        return;

    lv_gravity_info gi;
    lv_gravity_info_get(g, &gi);
    const int axisym = gi.kind != LV_GRAVITY_SH || gi.order == 0;
    lv_vec3 r0 = r_start, v0 = v_start, a0 = accel(p, g, ws, axisym, t, r0);
    /* the step grows as r^1.5 (the orbital period's scale) away from the planet: a high arc
     * takes as many steps per radian of its path as a low one; at most LV_IIP_MAX_STEPS */
    double tau = 0.0;
    for (long k = 0; k < LV_IIP_MAX_STEPS && tau < t_lim; k++) {
        const double rr = lv_v3_norm(r0) / p->a;
        const double h = rr > 1.0 ? h_near * rr * sqrt(rr) : h_near;
        /* classical RK4 (Hairer, Norsett & Wanner, Solving ODEs I, sec. II.1, table 1.2) */
        const double tm = t + tau + 0.5 * h, te = t + tau + h;
        const lv_vec3 r2 = lv_v3_add(r0, lv_v3_scale(v0, 0.5 * h));
        const lv_vec3 v2 = lv_v3_add(v0, lv_v3_scale(a0, 0.5 * h));
        const lv_vec3 a2 = accel(p, g, ws, axisym, tm, r2);
        const lv_vec3 r3 = lv_v3_add(r0, lv_v3_scale(v2, 0.5 * h));
        const lv_vec3 v3 = lv_v3_add(v0, lv_v3_scale(a2, 0.5 * h));
        const lv_vec3 a3 = accel(p, g, ws, axisym, tm, r3);
        const lv_vec3 r4 = lv_v3_add(r0, lv_v3_scale(v3, h));
        const lv_vec3 v4 = lv_v3_add(v0, lv_v3_scale(a3, h));
        const lv_vec3 a4 = accel(p, g, ws, axisym, te, r4);
        const double h6 = h / 6.0;
        const lv_vec3 r1 = lv_v3_add(
            r0, lv_v3_scale(lv_v3_add(lv_v3_add(v0, v4), lv_v3_scale(lv_v3_add(v2, v3), 2.0)), h6));
        const lv_vec3 v1 = lv_v3_add(
            v0, lv_v3_scale(lv_v3_add(lv_v3_add(a0, a4), lv_v3_scale(lv_v3_add(a2, a3), 2.0)), h6));
        const double F1 = surf(ia2, ib2, r1);
        if (F1 <= 0.0) {
            /* the crossing inside this step: regula falsi (Illinois variant) on the ellipsoid
             * function of the Hermite interpolant, whose position error is O(h^4) */
            double sa = 0.0, fa = surf(ia2, ib2, r0), sb = 1.0, fb = F1, s = 1.0;
            int side = 0;
            for (int it = 0; it < 100; it++) {
                s = (sa * fb - sb * fa) / (fb - fa);
                const double fs = surf(ia2, ib2, hermite(r0, v0, r1, v1, h, s));
                if (fabs(fs) < 1e-15 || sb - sa < 1e-12)
                    break;
                if ((fs > 0.0) == (fa > 0.0)) {
                    sa = s;
                    fa = fs;
                    if (side == -1)
                        fb *= 0.5;
                    side = -1;
                } else {
                    sb = s;
                    fb = fs;
                    if (side == 1)
                        fa *= 0.5;
                    side = 1;
                }
            }
            if (tau + s * h <= LV_IIP_HORIZON)
                set_impact(p, t, tau + s * h, hermite(r0, v0, r1, v1, h, s), out);
            return;
        }
        r0 = r1;
        v0 = v1;
        a0 = accel(p, g, ws, axisym, te, r1);
        tau += h;
    }
}

double lv_iip_range(double a, const double r0_ecef[3], const double r1_ecef[3])
{
    const lv_vec3 u = {r0_ecef[0], r0_ecef[1], r0_ecef[2]};
    const lv_vec3 w = {r1_ecef[0], r1_ecef[1], r1_ecef[2]};
    return a * atan2(lv_v3_norm(lv_v3_cross(u, w)), lv_v3_dot(u, w));
}
