/* root.c - Brent's method for a bracketed root (root.h). The variables follow Brent's
 * procedure "zero" (1973, ch. 4, sec. 6): b the best estimate, a the previous one, c the
 * point with f(c) of the other sign, so that the root stays in [b, c]; e the step before
 * last and d the last. */
#include "core/root.h"

#include <float.h>
#include <math.h>

int lv_root_brent(lv_root_fn f, void *user, double a, double b, double fa, double fb,
                  double tol, int max_eval, double *x)
{
    if (fa == 0.0) {
        *x = a;
        return 0;
    }
    if (fb == 0.0) {
        *x = b;
        return 0;
    }
    if ((fa > 0.0) == (fb > 0.0)) {
        *x = fabs(fa) < fabs(fb) ? a : b;
        return 1;
    }
    double c = a, fc = fa, d = b - a, e = d;
    for (int n = 0;; n++) {
        if ((fb > 0.0) == (fc > 0.0)) { /* keep the root between b and c */
            c = a, fc = fa;
            d = e = b - a;
        }
        if (fabs(fc) < fabs(fb)) { /* b the better end */
            a = b, b = c, c = a;
            fa = fb, fb = fc, fc = fa;
        }
        const double t = 2.0 * DBL_EPSILON * fabs(b) + tol, m = 0.5 * (c - b);
        if (fabs(m) <= t || fb == 0.0) {
            *x = b;
            return 0;
        }
        if (n >= max_eval) {
            *x = b;
            return 2;
        }
        if (fabs(e) < t || fabs(fa) <= fabs(fb)) {
            d = e = m; /* bisection */
        } else {
            double p, q, s = fb / fa;
            if (a == c) { /* the secant */
                p = 2.0 * m * s;
                q = 1.0 - s;
            } else { /* inverse quadratic interpolation */
                const double qa = fa / fc, r = fb / fc;
                p = s * (2.0 * m * qa * (qa - r) - (b - a) * (r - 1.0));
                q = (qa - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if (p > 0.0)
                q = -q;
            else
                p = -p;
            /* accept the interpolation when it falls well inside the bracket and shrinks
             * faster than the step before last; bisect otherwise */
            if (2.0 * p < 3.0 * m * q - fabs(t * q) && p < fabs(0.5 * e * q)) {
                e = d;
                d = p / q;
            } else {
                d = e = m;
            }
        }
        a = b, fa = fb;
        b += fabs(d) > t ? d : (m > 0.0 ? t : -t);
        const int rc = f(b, &fb, user);
        if (rc != 0) {
            *x = b;
            return rc;
        }
    }
}
