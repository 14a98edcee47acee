/* root.h - a bracketed root of a scalar function (not exported).
 *
 * Brent's method: inverse quadratic interpolation or the secant, falling back to bisection
 * whenever the interpolated point is not safely inside the bracket or the bracket does not
 * shrink fast enough (R. P. Brent, Algorithms for Minimization without Derivatives,
 * Prentice-Hall 1973, ch. 4, procedure "zero"). It never leaves the bracket and converges in
 * at most about (log2((b - a) / tol))^2 evaluations, superlinearly for a smooth function.
 * Written here rather than taken from a library because it is a few lines of the numerics
 * lvsim exists for (its flight models call it inside the right-hand side, without
 * allocation or callbacks through a library's state object).
 */
#ifndef LV_CORE_ROOT_H
#define LV_CORE_ROOT_H

/* f(x, user): 0 and *fx set, or nonzero to abort (the code is returned). */
typedef int (*lv_root_fn)(double x, double *fx, void *user);

/* A root of f in [a, b] with fa = f(a), fb = f(b) of opposite signs (or one of them 0):
 * *x within 2 eps |x| + tol of a sign change of f. max_eval bounds the evaluations (beyond:
 * *x is the best point so far and 2 is returned). Returns 0, 1 when fa and fb have the same
 * sign (nothing done), 2 at max_eval, or f's nonzero code. */
int lv_root_brent(lv_root_fn f, void *user, double a, double b, double fa, double fb,
                  double tol, int max_eval, double *x);

#endif
