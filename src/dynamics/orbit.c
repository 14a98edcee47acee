/* orbit.c - osculating elements from position and velocity (Vallado, Fundamentals of
 * Astrodynamics and Applications, 4th ed., algorithm 9). */
#include <math.h>

#include "core/vec3.h"
#include "dynamics/orbit.h"

#define TWO_PI 6.28318530717958647692

static double wrap_2pi(double x)
{
    double y = fmod(x, TWO_PI);
    return y < 0.0 ? y + TWO_PI : y;
}

/* Angle between unit-free vectors a and b, in [0, pi]; from atan2 for accuracy. */
static double angle_between(lv_vec3 a, lv_vec3 b)
{
    return atan2(lv_v3_norm(lv_v3_cross(a, b)), lv_v3_dot(a, b));
}

void lv_orbit_elements(double gm, const double r_in[3], const double v_in[3], lv_orbit_elem *el)
{
    const lv_vec3 r = {r_in[0], r_in[1], r_in[2]}, v = {v_in[0], v_in[1], v_in[2]};
    const double rn = lv_v3_norm(r), v2 = lv_v3_dot(v, v);
    const lv_vec3 h = lv_v3_cross(r, v);
    const double hn = lv_v3_norm(h);
    const lv_vec3 node = {-h.y, h.x, 0.0}; /* z x h */
    const double nn = hypot(node.x, node.y);
    /* eccentricity vector e = ((v^2 - gm/r) r - (r.v) v) / gm */
    const lv_vec3 ev = lv_v3_scale(
        lv_v3_sub(lv_v3_scale(r, v2 - gm / rn), lv_v3_scale(v, lv_v3_dot(r, v))), 1.0 / gm);
    const double e = lv_v3_norm(ev);
    const double energy = 0.5 * v2 - gm / rn;
    const double p = hn * hn / gm;

    el->e = e;
    el->a = energy != 0.0 ? -gm / (2.0 * energy) : INFINITY;
    el->i = atan2(hypot(h.x, h.y), h.z);
    el->r_peri = p / (1.0 + e);
    /* bound (negative energy): a (1 + e), finite also for a radial (rectilinear, e = 1) path;
     * p / (1 - e) would divide by zero there */
    el->r_apo = energy < 0.0 ? el->a * (1.0 + e) : INFINITY;

    const double eps = 1e-11;
    const int equatorial = nn <= eps * hn;
    const int circular = e <= eps;
    el->raan = equatorial ? 0.0 : wrap_2pi(atan2(node.y, node.x));

    /* Reference direction in the orbit plane for argp and nu. */
    const lv_vec3 ref = equatorial ? lv_v3(1.0, 0.0, 0.0) : node;
    const lv_vec3 hu = lv_v3_scale(h, 1.0 / hn);
    /* signed angle from a to b about the orbit normal */
#define SIGNED_ANGLE(a, b)                                                                 \
    wrap_2pi(lv_v3_dot(lv_v3_cross((a), (b)), hu) >= 0.0 ? angle_between((a), (b))         \
                                                         : -angle_between((a), (b)))
    if (circular) {
        el->argp = 0.0;
        el->nu = SIGNED_ANGLE(ref, r);
    } else {
        el->argp = SIGNED_ANGLE(ref, ev);
        el->nu = SIGNED_ANGLE(ev, r);
    }
#undef SIGNED_ANGLE
}
