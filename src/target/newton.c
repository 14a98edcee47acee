/* newton.c - targeting by damped Newton / Levenberg-Marquardt on the constraint residuals
 * r_i = (f_i - v_i) / tol_i (an inequality: its violation, 0 when met), in variables scaled by
 * their scale, z = x / s. Each step minimises the linear model within a trust region,
 *     min ||r_A + J_A p||  subject to  ||p|| <= Delta   (A: the equalities, violated inequalities)
 * whose solution is the Levenberg-Marquardt step (J_A^T J_A + lambda I) p = -J_A^T r_A with
 * lambda = 0 (the Gauss-Newton step) when that lies inside, else the lambda with ||p|| = Delta
 * (within 10 %, found by bisection in log lambda below ||J_A^T r_A|| / Delta); each solve is the
 * least-squares problem [J_A; sqrt(lambda) I] p = [-r_A; 0] by Householder QR. The radius
 * follows the ratio rho of the actual to the predicted reduction of sum r^2 / 2 (Moré, "The
 * Levenberg-Marquardt algorithm: implementation and theory", Lecture Notes in Mathematics 630,
 * 1978; Nocedal & Wright, Numerical Optimization, 2nd ed., alg. 4.1 and sec. 10.3): a trial
 * point where a phase fails is a rejected step (rho = -inf), and a rejected step shrinks the
 * radius to a quarter of the step actually tried. A step that would cross a bound takes the
 * first variable to reach one to that bound and holds it there, the others solved again (a
 * projected step).
 * The Jacobian is a finite-difference one, updated by Broyden's rank-one formula
 * J += (dg - J p) p^T / p^T p after an accepted step (Nocedal & Wright eq. 11.27), computed
 * afresh when a step is rejected or the model predicted poorly (rho < 0.25); with differences
 * `auto`, a rejected step with a fresh forward-difference Jacobian is retried with a central
 * one. It stops when every constraint is met, or at a stationary point of sum r^2 / 2: the
 * gradient J^T r is below 1e-5 of sum r^2 / 2 per unit of the scaled variables (a step of one
 * scale would gain less than that), or when the radius falls below 1e-8 (1 + ||z||). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "target/target_int.h"

/* min ||A x - b|| for A rows x cols (row-major, rows >= cols; destroyed, b too) by Householder
 * QR (Golub & Van Loan, Matrix Computations, alg. 5.3.2). Returns -1 when a column is zero
 * (rank deficient). */
static int lsq(size_t rows, size_t cols, double *A, double *b, double *x)
{
    for (size_t k = 0; k < cols; k++) {
        double norm = 0.0;
        for (size_t i = k; i < rows; i++)
            norm = hypot(norm, A[i * cols + k]);
        if (!(norm > 0.0))
            return -1;
        const double alpha = A[k * cols + k] > 0.0 ? -norm : norm;
        A[k * cols + k] -= alpha; /* v = column k below the diagonal, v_k shifted */
        double vv = 0.0;
        for (size_t i = k; i < rows; i++)
            vv += A[i * cols + k] * A[i * cols + k];
        for (size_t j = k + 1; j < cols; j++) {
            double s = 0.0;
            for (size_t i = k; i < rows; i++)
                s += A[i * cols + k] * A[i * cols + j];
            s = 2.0 * s / vv;
            for (size_t i = k; i < rows; i++)
                A[i * cols + j] -= s * A[i * cols + k];
        }
        double s = 0.0;
        for (size_t i = k; i < rows; i++)
            s += A[i * cols + k] * b[i];
        s = 2.0 * s / vv;
        for (size_t i = k; i < rows; i++)
            b[i] -= s * A[i * cols + k];
        A[k * cols + k] = alpha;
    }
    for (size_t k = cols; k-- > 0;) {
        double s = b[k];
        for (size_t j = k + 1; j < cols; j++)
            s -= A[k * cols + j] * x[j];
        x[k] = s / A[k * cols + k];
    }
    return 0;
}

typedef struct lm_work {
    size_t n, m;
    double *J;      /* [m x n] dg/dz */
    double *A, *b;  /* [(m + n) x n], [m + n] */
    double *p, *pf; /* [n] the step; the free variables' part */
    double *pfix;   /* [n] the step of a variable held at a bound (to the bound) */
    double *rr;     /* [m] the residuals with the held variables' steps taken */
    int *fixed;     /* [n] held at a bound */
    int *active;    /* [m] rows of the model */
} lm_work;

static void lm_free(lm_work *w)
{
    free(w->J);
    free(w->A);
    free(w->b);
    free(w->p);
    free(w->pf);
    free(w->pfix);
    free(w->rr);
    free(w->fixed);
    free(w->active);
}

static double norm2(const double *v, size_t n)
{
    double s = 0.0;
    for (size_t j = 0; j < n; j++)
        s = hypot(s, v[j]);
    return s;
}

/* The step of the free variables for damping lambda into w->p (0 for the fixed ones), for
 * the residuals w->rr; -1 when the system is singular. */
static int lm_solve(lm_work *w, double lambda)
{
    const size_t n = w->n, m = w->m;
    size_t nf = 0, row = 0;
    for (size_t j = 0; j < n; j++)
        nf += (size_t)!w->fixed[j];
    memset(w->p, 0, n * sizeof *w->p);
    if (nf == 0)
        return 0;
    for (size_t i = 0; i < m; i++) {
        if (!w->active[i])
            continue;
        for (size_t j = 0, c = 0; j < n; j++)
            if (!w->fixed[j])
                w->A[row * nf + c++] = w->J[i * n + j];
        w->b[row++] = -w->rr[i];
    }
    for (size_t j = 0, c = 0; j < n; j++) {
        if (w->fixed[j])
            continue;
        for (size_t q = 0; q < nf; q++)
            w->A[row * nf + q] = 0.0;
        w->A[row * nf + c++] = sqrt(lambda);
        w->b[row++] = 0.0;
    }
    if (lsq(row, nf, w->A, w->b, w->pf) != 0)
        return -1;
    for (size_t j = 0, c = 0; j < n; j++)
        if (!w->fixed[j])
            w->p[j] = w->pf[c++];
    for (size_t j = 0; j < n; j++)
        if (!isfinite(w->p[j]))
            return -1;
    return 0;
}

/* ||J_A^T r_A|| over the free variables (r: w->rr), and its largest component. */
static double gradient(const lm_work *w, double *gmax)
{
    double g = 0.0;
    *gmax = 0.0;
    for (size_t j = 0; j < w->n; j++) {
        if (w->fixed[j])
            continue;
        double s = 0.0;
        for (size_t i = 0; i < w->m; i++)
            if (w->active[i])
                s += w->J[i * w->n + j] * w->rr[i];
        g = hypot(g, s);
        *gmax = fmax(*gmax, fabs(s));
    }
    return g;
}

/* The trust-region step from point p within radius delta (scaled variables), in the bounds:
 * w->p, its lambda and predicted reduction. A step that would cross a bound takes the variable
 * whose bound comes first along it to that bound, holds it there, and solves again for the
 * others (their residuals with that move taken, the radius what remains of delta). */
static void tr_step(const lv_target *t, lm_work *w, const tg_point *p, double delta,
                    double *lambda_out, double *pred)
{
    const size_t n = w->n, m = w->m;
    double jmax = 0.0;
    for (size_t i = 0; i < m * n; i++)
        jmax = fmax(jmax, fabs(w->J[i]));
    const double lam0 = 1e-12 * (1.0 + jmax * jmax); /* regularises a rank-deficient J */
    double lambda = lam0;
    for (size_t i = 0; i < m; i++)
        w->active[i] = t->cons[i].kind == LV_CON_EQUAL || p->r[i] != 0.0;
    memset(w->fixed, 0, n * sizeof *w->fixed);
    memset(w->pfix, 0, n * sizeof *w->pfix);
    for (size_t pass = 0; pass <= n; pass++) {
        double fixlen = 0.0;
        for (size_t i = 0; i < m; i++) {
            w->rr[i] = p->r[i];
            for (size_t j = 0; j < n; j++)
                w->rr[i] += w->J[i * n + j] * w->pfix[j];
        }
        fixlen = norm2(w->pfix, n);
        const double room = fixlen < delta ? sqrt(delta * delta - fixlen * fixlen) : 0.0;
        lambda = lam0;
        if (lm_solve(w, lambda) != 0)
            break;
        if (norm2(w->p, n) > room) {
            double gmax;
            double lo = lam0, hi = gradient(w, &gmax) / fmax(room, 1e-300);
            for (int it = 0; it < 80 && hi > lo; it++) {
                lambda = sqrt(lo * hi);
                if (lm_solve(w, lambda) != 0)
                    break;
                const double len = norm2(w->p, n);
                if (len > 1.1 * room)
                    lo = lambda;
                else if (len < 0.9 * room)
                    hi = lambda;
                else
                    break;
            }
        }
        /* the first bound met along the step: that variable goes to it and is held */
        size_t first = (size_t)-1;
        double tmin = 1.0;
        for (size_t j = 0; j < n; j++) {
            const tg_var *v = &t->vars[j];
            if (w->fixed[j] || w->p[j] == 0.0)
                continue;
            const double z = p->x[j] / v->r.scale;
            const double bound = (w->p[j] > 0.0 ? v->r.hi : v->r.lo) / v->r.scale;
            const double tj = (bound - z) / w->p[j]; /* >= 0: z lies in the bounds */
            if (tj < tmin) {
                tmin = tj;
                first = j;
            }
        }
        if (first == (size_t)-1)
            break;
        const tg_var *v = &t->vars[first];
        w->pfix[first] = ((w->p[first] > 0.0 ? v->r.hi : v->r.lo) - p->x[first]) / v->r.scale;
        w->fixed[first] = 1;
    }
    for (size_t j = 0; j < n; j++) {
        if (w->fixed[j])
            w->p[j] = w->pfix[j];
        /* into the bounds (rounding) */
        const tg_var *v = &t->vars[j];
        const double x = fmin(v->r.hi, fmax(v->r.lo, p->x[j] + w->p[j] * v->r.scale));
        w->p[j] = (x - p->x[j]) / v->r.scale;
    }
    double lin = 0.0; /* the linear model's sum r^2 / 2 over the rows of the model */
    for (size_t i = 0; i < m; i++) {
        if (!w->active[i])
            continue;
        double ri = p->r[i];
        for (size_t j = 0; j < n; j++)
            ri += w->J[i * n + j] * w->p[j];
        lin += 0.5 * ri * ri;
    }
    *pred = p->merit - lin;
    *lambda_out = lambda <= lam0 ? 0.0 : lambda;
}

/* max over the variables of |d(sum r^2 / 2) / dz| relative to sum r^2 / 2 (fresh J). */
static double stationarity(lm_work *w, const lv_target *t, const tg_point *p)
{
    for (size_t i = 0; i < w->m; i++)
        w->active[i] = t->cons[i].kind == LV_CON_EQUAL || p->r[i] != 0.0;
    memset(w->fixed, 0, w->n * sizeof *w->fixed);
    memcpy(w->rr, p->r, w->m * sizeof *w->rr);
    double gmax;
    gradient(w, &gmax);
    return p->merit > 0.0 ? gmax / p->merit : INFINITY;
}

lv_status tg_newton(lv_target *t, tg_point *p, int max_iter, int *converged, char *reason,
                    size_t reason_cap, lv_err *err)
{
    const size_t n = t->n, m = t->mc;
    lm_work w = {n, m, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL};
    tg_point q;
    lv_status st = LV_OK;
    char note[LV_ERR_MSG_MAX] = "";
    *converged = 0;
    t->solver = "newton";
    w.J = calloc(m * n + 1, sizeof *w.J);
    w.A = calloc((m + n) * n + 1, sizeof *w.A);
    w.b = calloc(m + n + 1, sizeof *w.b);
    w.p = calloc(n + 1, sizeof *w.p);
    w.pf = calloc(n + 1, sizeof *w.pf);
    w.pfix = calloc(n + 1, sizeof *w.pfix);
    w.rr = calloc(m + 1, sizeof *w.rr);
    w.fixed = calloc(n + 1, sizeof *w.fixed);
    w.active = calloc(m + 1, sizeof *w.active);
    if (!w.J || !w.A || !w.b || !w.p || !w.pf || !w.pfix || !w.rr || !w.fixed || !w.active ||
        tg_point_init(t, &q) != LV_OK) {
        lm_free(&w);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    if (tg_met(t, p)) {
        *converged = 1;
        snprintf(reason, reason_cap, "every constraint is met at the start point");
        goto done;
    }
    const lv_target_diff diff = t->set.differences;
    int central = diff == LV_DIFF_CENTRAL, fresh = 1;
    if ((st = tg_sensitivities(t, p, central, w.J, NULL, note, sizeof note, err)) != LV_OK)
        goto done;
    double delta = 10.0; /* ten scales */
    int tries = 0;
    snprintf(reason, reason_cap, "the iteration limit (%d steps) was reached", max_iter);
    for (;;) {
        double zlen = 0.0;
        for (size_t j = 0; j < n; j++)
            zlen = hypot(zlen, p->x[j] / t->vars[j].r.scale);
        if (fresh && stationarity(&w, t, p) <= 1e-5) {
            snprintf(reason, reason_cap, "the constraints cannot all be met from here: the "
                     "residuals' sum of squares is at a minimum (its gradient vanishes)%s%s",
                     note[0] ? "; " : "", note);
            break;
        }
        if (delta < 1e-8 * (1.0 + zlen)) {
            snprintf(reason, reason_cap, "no step reduces the residuals further (the trust "
                     "region shrank to nothing)%s%s", note[0] ? "; " : "", note);
            break;
        }
        if (tries >= max_iter)
            break;
        double pred, lambda;
        tr_step(t, &w, p, delta, &lambda, &pred);
        const double plen = norm2(w.p, n);
        if (!(plen > 1e-12 * (1.0 + zlen)) || !(pred > 0.0)) {
            if (!fresh || (diff == LV_DIFF_AUTO && !central)) { /* a better Jacobian first */
                if (fresh)
                    central = 1;
                if ((st = tg_sensitivities(t, p, central, w.J, NULL, note, sizeof note, err)) !=
                    LV_OK)
                    goto done;
                fresh = 1;
                continue;
            }
            snprintf(reason, reason_cap, "no step reduces the residuals further (bounds or a "
                     "local minimum of their sum of squares)%s%s", note[0] ? "; " : "", note);
            break;
        }
        tries++;
        t->iteration++;
        for (size_t j = 0; j < n; j++) /* the trial point x + p s */
            t->tmp_x[j] = fmin(t->vars[j].r.hi,
                               fmax(t->vars[j].r.lo, p->x[j] + w.p[j] * t->vars[j].r.scale));
        if ((st = tg_eval(t, t->tmp_x, "trial", NULL, &q, err)) != LV_OK)
            goto done;
        const double actual = q.ok ? p->merit - q.merit : -INFINITY;
        const double rho = actual / pred;
        if (q.ok && rho > 1e-4) {
            /* Broyden's update of the whole Jacobian (every row) with the step taken */
            for (size_t i = 0; i < m; i++) {
                double jp = 0.0;
                for (size_t j = 0; j < n; j++)
                    jp += w.J[i * n + j] * w.p[j];
                const double c = (q.g[i] - p->g[i] - jp) / (plen * plen);
                for (size_t j = 0; j < n; j++)
                    w.J[i * n + j] += c * w.p[j];
            }
            tg_point_copy(t, p, &q);
            tg_report(t, "accepted", p, lambda, plen, note);
            note[0] = '\0';
            fresh = 0;
            if (tg_met(t, p)) {
                *converged = 1;
                snprintf(reason, reason_cap, "every constraint met in %d steps", tries);
                break;
            }
            if (rho > 0.75)
                delta = fmin(1e6, fmax(delta, 2.0 * plen));
            else if (rho < 0.25) { /* the model predicted poorly: smaller, a fresh Jacobian */
                delta = 0.5 * plen;
                if ((st = tg_sensitivities(t, p, central, w.J, NULL, note, sizeof note, err)) !=
                    LV_OK)
                    goto done;
                fresh = 1;
            }
        } else {
            char why[LV_ERR_MSG_MAX];
            if (!q.ok)
                snprintf(why, sizeof why, "%s", q.why);
            else
                snprintf(why, sizeof why, "the residuals %s (ratio %.2g)",
                         actual < 0.0 ? "grew" : "fell too little", rho);
            tg_report(t, "rejected", &q, lambda, plen, why);
            delta = 0.25 * plen;
            if (!fresh || (diff == LV_DIFF_AUTO && !central && q.ok)) {
                /* a stale (Broyden) Jacobian, or a forward-difference one: compute it again
                 * (central differences after a fresh forward one) */
                if (fresh)
                    central = 1;
                if ((st = tg_sensitivities(t, p, central, w.J, NULL, note, sizeof note, err)) !=
                    LV_OK)
                    goto done;
                fresh = 1;
            }
        }
    }
done:
    tg_point_free(&q);
    lm_free(&w);
    return st;
}
