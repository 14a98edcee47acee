/* planet.c - central-body presets (WGS-84 Earth, Moon, Mars) and the normal
 * gravity field of a level ellipsoid (Heiskanen & Moritz, Physical Geodesy, 1967,
 * ch. 2: series expansion of the normal potential). Sources of the constants:
 * include/lvsim/lv_planet.h. */
#include "lvsim/lv_planet.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/names.h"
#include "core/status.h"

#include "core/units.h"

static lv_planet make_planet(const char *name, double a, double f, double gm, double omega,
                             double r_ref, double j2, double j3, double j4)
{
    lv_planet p;
    memset(&p, 0, sizeof p);
    snprintf(p.name, sizeof p.name, "%s", name);
    p.a = a;
    p.f = f;
    p.gm = gm;
    p.omega = omega;
    p.theta0 = 0.0;
    p.r_ref = r_ref;
    p.j2 = j2;
    p.j3 = j3;
    p.j4 = j4;
    return p;
}

lv_planet lv_planet_earth(void)
{
    /* EGM2008 fully normalised C(n,0) (data/gravity/egm2008_n20.gfc, tide free);
     * J_n = -sqrt(2n + 1) C(n,0) (full normalisation, docs/gravity.md). */
    const double c20 = -0.484165143790815e-03, c30 = 0.957161207093473e-06,
                 c40 = 0.539965866638991e-06;
    return make_planet("earth", 6378137.0, 1.0 / 298.257223563, 3.986004418e14, 7.292115e-5,
                       6378136.3, -sqrt(5.0) * c20, -sqrt(7.0) * c30, -3.0 * c40);
}

lv_planet lv_planet_moon(void)
{
    /* Wieczorek, M. A. (2015), Gravity and topography of the terrestrial planets,
     * Treatise on Geophysics 10, 153-193 (values as in the Boule library's MOON). */
    return make_planet("moon", 1737151.0, 0.0, 4.9028001e12, 2.6617073e-6, 1737151.0, 0.0, 0.0,
                       0.0);
}

lv_planet lv_planet_mars(void)
{
    /* NASA NSSDC Mars fact sheet (nssdc.gsfc.nasa.gov/planetary/factsheet/marsfact.html):
     * equatorial radius 3396.2 km, flattening 0.00589, GM 0.042828e6 km^3/s^2,
     * J2 1960.45e-6, sidereal rotation period 24.6229 h. */
    return make_planet("mars", 3396.2e3, 0.00589, 4.2828e13, 2.0 * LV_PI / (24.6229 * 3600.0),
                       3396.2e3, 1960.45e-6, 0.0, 0.0);
}

lv_status lv_planet_by_name(const char *name, lv_planet *out, lv_err *err)
{
    static const char *const names[] = {"earth", "moon", "mars"};
    if (name == NULL)
        return lv_fail(err, LV_ERR_INPUT, "planet: no name given");
    if (strcmp(name, "earth") == 0) {
        *out = lv_planet_earth();
    } else if (strcmp(name, "moon") == 0) {
        *out = lv_planet_moon();
    } else if (strcmp(name, "mars") == 0) {
        *out = lv_planet_mars();
    } else {
        lv_suggest s;
        char hint[128];
        lv_suggest_init(&s, name);
        for (size_t k = 0; k < sizeof names / sizeof names[0]; k++)
            lv_suggest_add(&s, names[k]);
        lv_suggest_text(&s, hint, sizeof hint);
        return lv_fail(err, LV_ERR_NOTFOUND,
                       "unknown planet '%s'%s (known: earth, moon, mars)", name, hint);
    }
    return LV_OK;
}

lv_status lv_planet_check(const lv_planet *p, lv_err *err)
{
    const char *who = p->name[0] != '\0' ? p->name : "(unnamed)";
    if (!(isfinite(p->a) && p->a > 0.0))
        return lv_fail(err, LV_ERR_INPUT, "planet '%s': a = %g m must be > 0", who, p->a);
    if (!(isfinite(p->f) && p->f >= 0.0 && p->f < 1.0))
        return lv_fail(err, LV_ERR_INPUT, "planet '%s': f = %g must be in [0, 1)", who, p->f);
    if (!(isfinite(p->gm) && p->gm > 0.0))
        return lv_fail(err, LV_ERR_INPUT, "planet '%s': gm = %g m^3/s^2 must be > 0", who, p->gm);
    if (!(isfinite(p->r_ref) && p->r_ref > 0.0))
        return lv_fail(err, LV_ERR_INPUT, "planet '%s': r_ref = %g m must be > 0", who,
                       p->r_ref);
    if (!isfinite(p->omega) || !isfinite(p->theta0))
        return lv_fail(err, LV_ERR_INPUT, "planet '%s': omega and theta0 must be finite", who);
    if (!isfinite(p->j2) || !isfinite(p->j3) || !isfinite(p->j4))
        return lv_fail(err, LV_ERR_INPUT, "planet '%s': j2, j3, j4 must be finite", who);
    /* the equator may not turn faster than a circular orbit at its radius: omega^2 a < GM/a^2 */
    const double w_orbit = sqrt(p->gm / (p->a * p->a * p->a));
    if (!(fabs(p->omega) < w_orbit))
        return lv_fail(err, LV_ERR_INPUT, "planet '%s': rotation rate %g rad/s must be below "
                       "sqrt(gm / a^3) = %g rad/s (faster, the equator would fly off)", who,
                       p->omega, w_orbit);
    return LV_OK;
}

double lv_planet_b(const lv_planet *p) { return p->a * (1.0 - p->f); }

double lv_planet_e2(const lv_planet *p) { return p->f * (2.0 - p->f); }

/* q0 = 1/2 [(1 + 3/e'^2) atan e' - 3/e'] (H&M). The closed form loses
 * ~6 digits to cancellation for the Earth's e' = 0.082, so small e' uses the
 * series q0 = sum_k (-1)^(k+1) 2k e'^(2k+1) / ((2k+1)(2k+3)). */
static double q0_of(double ep)
{
    if (ep > 0.5)
        return 0.5 * ((1.0 + 3.0 / (ep * ep)) * atan(ep) - 3.0 / ep);
    double sum = 0.0, pw = ep * ep * ep, sign = 1.0;
    for (int k = 1; k < 200; k++) {
        double term = sign * 2.0 * k * pw / ((2.0 * k + 1.0) * (2.0 * k + 3.0));
        sum += term;
        if (fabs(term) < 1e-18 * fabs(sum))
            break;
        pw *= ep * ep;
        sign = -sign;
    }
    return sum;
}

double lv_planet_normal_j(const lv_planet *p, int n)
{
    if (n < 2 || n % 2 != 0 || p->f <= 0.0)
        return 0.0;
    const double a = p->a, b = lv_planet_b(p), e2 = lv_planet_e2(p);
    const double ep = sqrt(a * a - b * b) / b;       /* second eccentricity */
    const double m = p->omega * p->omega * a * a * b / p->gm; /* H&M's m */
    const double j2 = e2 / 3.0 * (1.0 - 2.0 / 15.0 * m * ep / q0_of(ep)); /* H&M */
    if (n == 2)
        return j2;
    /* H&M: J_2k = (-1)^(k+1) 3 e^2k / ((2k+1)(2k+3)) (1 - k + 5k J2 / e^2) */
    const int k = n / 2;
    const double sign = (k % 2 == 1) ? 1.0 : -1.0;
    return sign * 3.0 * pow(e2, (double)k) / ((2.0 * k + 1.0) * (2.0 * k + 3.0)) *
           (1.0 - k + 5.0 * k * j2 / e2);
}
