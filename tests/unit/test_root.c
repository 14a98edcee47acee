/* test_root.c - Brent's bracketed root (src/core/root.c) against roots known in closed form or
 * to every digit from the literature. */
#include <math.h>

#include "check.h"
#include "core/root.h"

typedef struct counted {
    int n;
    int kind;
} counted;

static int fn(double x, double *fx, void *user)
{
    counted *c = user;
    c->n++;
    switch (c->kind) {
    case 0: *fx = x * x * x - 2.0 * x - 5.0; break; /* Newton's cubic (Wallis) */
    case 1: *fx = cos(x) - x; break;                /* the Dottie number */
    case 2: *fx = x - 1.0 / 3.0; break;             /* linear: the secant is exact */
    case 3: *fx = x < 0.3 ? -1.0 : 1.0; break;      /* a jump: bisection only */
    default: *fx = exp(x) - 2.0; break;             /* ln 2 */
    }
    return 0;
}

static double solve(int kind, double a, double b, double tol, int *evals, int *rc)
{
    counted c = {0, kind};
    double fa, fb, x = NAN;
    fn(a, &fa, &c);
    fn(b, &fb, &c);
    *rc = lv_root_brent(fn, &c, a, b, fa, fb, tol, 100, &x);
    *evals = c.n;
    return x;
}

int main(void)
{
    int n, rc;
    /* x^3 - 2x - 5 = 0: 2.0945514815423265... (Newton's example, 1669; digits from the
     * closed form of the depressed cubic, Cardano: cbrt(5/2 + sqrt(643/108)) +
     * cbrt(5/2 - sqrt(643/108))) */
    const double cubic = cbrt(2.5 + sqrt(643.0 / 108.0)) + cbrt(2.5 - sqrt(643.0 / 108.0));
    CHECK_CLOSE(solve(0, 2.0, 3.0, 1e-15, &n, &rc), cubic, 4e-15);
    CHECK(rc == 0 && n <= 12);
    /* cos x = x: 0.739085133215160641655... (the Dottie number, OEIS A003957) */
    CHECK_CLOSE(solve(1, 0.0, 1.0, 1e-15, &n, &rc), 0.7390851332151607, 3e-16);
    CHECK(rc == 0 && n <= 12);
    CHECK_CLOSE(solve(2, -5.0, 5.0, 1e-14, &n, &rc), 1.0 / 3.0, 1e-14);
    CHECK(rc == 0 && n <= 5);
    /* a sign change without a zero: the bracket shrinks to the jump by bisection */
    CHECK_CLOSE(solve(3, 0.0, 1.0, 1e-12, &n, &rc), 0.3, 2e-12);
    CHECK(rc == 0 && n <= 50);
    CHECK_CLOSE(solve(4, 5.0, -3.0, 1e-15, &n, &rc), log(2.0), 1e-15); /* a > b works */
    CHECK(rc == 0);
    /* same signs: 1, the better end, nothing evaluated */
    CHECK_CLOSE(solve(4, 1.0, 3.0, 1e-12, &n, &rc), 1.0, 0.0);
    CHECK(rc == 1 && n == 2);
    /* the evaluation bound */
    counted c = {0, 1};
    double fa, fb, x;
    fn(0.0, &fa, &c);
    fn(1.0, &fb, &c);
    CHECK(lv_root_brent(fn, &c, 0.0, 1.0, fa, fb, 0.0, 2, &x) == 2 && x >= 0.0 && x <= 1.0);
    return check_report("test_root");
}
