/* random.c - lvsim's random streams (lv_dispersion.h, docs/monte-carlo.md "The generator and
 * the streams"): Philox4x32-10, a counter-based generator (Salmon, Moraes, Dror, Shaw, "Parallel
 * random numbers: as easy as 1, 2, 3", SC'11; Random123, Debian librandom123-dev), keyed by the
 * campaign's seed, counted by (run, stream); and the inverse normal CDF of Wichura (Applied
 * Statistics AS 241, 1988, PPND16). In core because the dispersions (mission/) and the
 * turbulence's white noise (env/) draw from the same streams. */
#include <math.h>
#include <stdint.h>

#include <Random123/philox.h>
#include <Random123/u01fixedpt.h>

#include "core/random.h"
#include "lvsim/lv_dispersion.h"

void lv_rand_u01x2(uint64_t seed, uint64_t run, uint64_t stream, double u[2])
{
    const philox4x32_key_t k = { { (uint32_t)seed, (uint32_t)(seed >> 32) } };
    const philox4x32_ctr_t c = { { (uint32_t)run, (uint32_t)(run >> 32), (uint32_t)stream,
                                   (uint32_t)(stream >> 32) } };
    const philox4x32_ctr_t r = philox4x32(c, k);
    u[0] = u01fixedpt_open_open_64_double(((uint64_t)r.v[0] << 32) | r.v[1]);
    u[1] = u01fixedpt_open_open_64_double(((uint64_t)r.v[2] << 32) | r.v[3]);
}

void lv_rand_normal2(uint64_t seed, uint64_t run, uint64_t stream, double z[2])
{
    double u[2];
    lv_rand_u01x2(seed, run, stream, u);
    z[0] = lv_disp_norm_inv(u[0]);
    z[1] = lv_disp_norm_inv(u[1]);
}

uint64_t lv_disp_stream(const char *name)
{
    uint64_t h = 14695981039346656037ULL; /* FNV-1a 64 offset basis */
    for (const unsigned char *p = (const unsigned char *)name; *p; p++) {
        h ^= *p;
        h *= 1099511628211ULL; /* FNV prime */
    }
    return h;
}

double lv_disp_uniform(uint64_t seed, uint64_t stream, uint64_t run)
{
    double u[2];
    lv_rand_u01x2(seed, run, stream, u);
    return u[0];
}

/* AS 241 PPND16: the normal deviate z with Phi(z) = p, 0 < p < 1, relative accuracy about
 * 1e-16. Coefficients from Wichura, Appl. Statist. 37(3), 477-484 (1988). */
static double poly(const double *c, int n, double x)
{
    double s = c[n - 1];
    for (int i = n - 2; i >= 0; i--)
        s = s * x + c[i];
    return s;
}

double lv_disp_norm_inv(double p)
{
    static const double a[8] = { 3.3871328727963666080e0, 1.3314166789178437745e+2,
                                 1.9715909503065514427e+3, 1.3731693765509461125e+4,
                                 4.5921953931549871457e+4, 6.7265770927008700853e+4,
                                 3.3430575583588128105e+4, 2.5090809287301226727e+3 };
    static const double b[8] = { 1.0, 4.2313330701600911252e+1, 6.8718700749205790830e+2,
                                 5.3941960214247511077e+3, 2.1213794301586595867e+4,
                                 3.9307895800092710610e+4, 2.8729085735721942674e+4,
                                 5.2264952788528545610e+3 };
    static const double c[8] = { 1.42343711074968357734e0, 4.63033784615654529590e0,
                                 5.76949722146069140550e0, 3.64784832476320460504e0,
                                 1.27045825245236838258e0, 2.41780725177450611770e-1,
                                 2.27238449892691845833e-2, 7.74545014278341407640e-4 };
    static const double d[8] = { 1.0, 2.05319162663775882187e0, 1.67638483018380384940e0,
                                 6.89767334985100004550e-1, 1.48103976427480074590e-1,
                                 1.51986665636164571966e-2, 5.47593808499534494600e-4,
                                 1.05075007164441684324e-9 };
    static const double e[8] = { 6.65790464350110377720e0, 5.46378491116411436990e0,
                                 1.78482653991729133580e0, 2.96560571828504891230e-1,
                                 2.65321895265761230930e-2, 1.24266094738807843860e-3,
                                 2.71155556874348757815e-5, 2.01033439929228813265e-7 };
    static const double f[8] = { 1.0, 5.99832206555887937690e-1, 1.36929880922735805310e-1,
                                 1.48753612908506148525e-2, 7.86869131145613259100e-4,
                                 1.84631831751005468180e-5, 1.42151175831644588870e-7,
                                 2.04426310338993978564e-15 };
    if (!(p > 0.0 && p < 1.0))
        return p == 0.0 ? -INFINITY : p == 1.0 ? INFINITY : NAN;
    const double q = p - 0.5;
    if (fabs(q) <= 0.425) {
        const double r = 0.180625 - q * q;
        return q * poly(a, 8, r) / poly(b, 8, r);
    }
    double r = sqrt(-log(q < 0.0 ? p : 1.0 - p));
    double z;
    if (r <= 5.0) {
        r -= 1.6;
        z = poly(c, 8, r) / poly(d, 8, r);
    } else {
        r -= 5.0;
        z = poly(e, 8, r) / poly(f, 8, r);
    }
    return q < 0.0 ? -z : z;
}

