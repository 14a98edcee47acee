/* optimize.c - optimisation of a cost under the constraints with NLopt (Johnson, The NLopt
 * nonlinear-optimization package, https://github.com/stevengj/nlopt): SLSQP (Kraft, "A
 * software package for sequential quadratic programming", DFVLR-FB 88-28, 1988) with
 * finite-difference gradients, or COBYLA (Powell, "A direct search optimization method that
 * models the objective and constraint functions by linear interpolation", 1994), derivative
 * free. In scaled variables z = x / s (bounds lo / s, hi / s), NLopt minimises
 *     phi(z) = -+ cost / cost_scale     subject to  g_i(z) = (f_i - v_i) / tol_i = 0   (equal)
 *                                                   (v_i - f_i) / tol_i <= 0          (min)
 *                                                   (f_i - v_i) / tol_i <= 0          (max)
 * (without a cost, phi = sum r_i^2 / 2, the residuals' merit: an optimiser asked only to meet
 * the constraints). Every function and constraint call at one point shares one evaluation (a cache keyed by the
 * point), and the gradients are taken only when NLopt asks for them. A point where a phase
 * fails gets the best cost found plus a penalty of 1000 and every constraint violated by 1000
 * tolerances: SLSQP's line search (an L1 merit function) and COBYLA then step back from it. */
#include <math.h>
#include <nlopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "target/nlopt_dl.h"
#include "core/status.h"
#include "target/target_int.h"

#define PENALTY 1000.0

typedef struct opt_ctx {
    lv_target *t;
    nlopt_opt opt;
    tg_point cur, best;
    int have_cur, have_best, have_grad;
    double *Jg, *Jc;     /* sensitivities at cur: [m x n], [n] */
    double *zgrad;       /* the last point whose gradients were taken */
    int have_zgrad;
    double *zlast;       /* the point reported before cur */
    int have_zlast;
    double sign;         /* -1: maximise */
    size_t n_eq, n_in;
    size_t *eq, *in;     /* constraint indices */
    int points, max_points;
    int central_used;
    lv_status st;        /* an error inside a callback (NLopt is then stopped) */
    lv_err *err;
    char note[LV_ERR_MSG_MAX];
} opt_ctx;

/* The objective NLopt minimises: the signed, scaled cost; without a cost (an optimiser asked
 * to meet constraints only) the merit sum r_i^2 / 2 in tolerances, which is 0 exactly where
 * every constraint is met (a NaN or constant objective stalls SLSQP and COBYLA). */
static double objective_of(const opt_ctx *c, const tg_point *p)
{
    if (!c->t->cost.present)
        return p->merit;
    return c->sign * p->cost / c->t->cost_scale;
}

/* a better than b: meets the constraints where b does not; both meeting them: lower
 * objective; neither: smaller worst residual */
static int better(const opt_ctx *c, const tg_point *a, const tg_point *b)
{
    const lv_target *t = c->t;
    if (!a->ok)
        return 0;
    if (!b->ok)
        return 1;
    const int ma = tg_met(t, a), mb = tg_met(t, b);
    if (ma != mb)
        return ma;
    if (ma)
        return !t->cost.present || objective_of(c, a) < objective_of(c, b);
    return a->worst < b->worst;
}

/* The point z evaluated (and its gradients when `grad`): 0, or -1 after an error (NLopt is
 * told to stop). */
static int ensure(opt_ctx *c, const double *z, int grad)
{
    lv_target *t = c->t;
    const size_t n = t->n;
    if (c->st != LV_OK)
        return -1;
    int same = c->have_cur;
    for (size_t j = 0; j < n && same; j++) {
        const tg_var *v = &t->vars[j];
        same = c->cur.x[j] == fmin(v->r.hi, fmax(v->r.lo, z[j] * v->r.scale));
    }
    if (!same) {
        if (c->points >= c->max_points) {
            nlopt_force_stop(c->opt);
            return -1;
        }
        for (size_t j = 0; j < n; j++) {
            const tg_var *v = &t->vars[j];
            t->tmp_x[j] = fmin(v->r.hi, fmax(v->r.lo, z[j] * v->r.scale));
        }
        double step = NAN;
        if (c->have_cur) {
            step = 0.0;
            for (size_t j = 0; j < n; j++)
                step = hypot(step, (t->tmp_x[j] - c->cur.x[j]) / t->vars[j].r.scale);
        }
        t->iteration++;
        c->points++;
        lv_status st = tg_eval(t, t->tmp_x, "point", NULL, &c->cur, c->err);
        if (st != LV_OK) {
            c->st = st;
            nlopt_force_stop(c->opt);
            return -1;
        }
        c->have_cur = 1;
        c->have_grad = 0;
        tg_report(t, c->cur.ok ? "point" : "rejected", &c->cur, NAN, step,
                  c->cur.ok ? c->note : c->cur.why);
        c->note[0] = '\0';
        if (!c->have_best || better(c, &c->cur, &c->best)) {
            tg_point_copy(t, &c->best, &c->cur);
            c->have_best = 1;
        }
    }
    if (grad && !c->have_grad && c->cur.ok) {
        /* central differences where they pay: near an optimum (steps below 1% of the
         * variables' scales), where forward-difference errors would dominate the gradient */
        int central = t->set.differences == LV_DIFF_CENTRAL;
        if (t->set.differences == LV_DIFF_AUTO && c->have_zgrad) {
            double d = 0.0;
            for (size_t j = 0; j < n; j++)
                d = fmax(d, fabs(z[j] - c->zgrad[j]));
            central = d < 1e-2;
        }
        c->central_used |= central;
        lv_status st = tg_sensitivities(t, &c->cur, central, c->Jg, c->Jc, c->note,
                                        sizeof c->note, c->err);
        if (st != LV_OK) {
            c->st = st;
            nlopt_force_stop(c->opt);
            return -1;
        }
        memcpy(c->zgrad, z, n * sizeof *z);
        c->have_zgrad = 1;
        c->have_grad = 1;
    }
    return 0;
}

static double fun(unsigned n, const double *z, double *grad, void *data)
{
    opt_ctx *c = data;
    if (ensure(c, z, grad != NULL) != 0 || !c->cur.ok) {
        if (grad != NULL)
            memset(grad, 0, n * sizeof *grad);
        return (c->have_best ? objective_of(c, &c->best) : 0.0) + PENALTY;
    }
    if (grad != NULL && c->t->cost.present)
        for (unsigned j = 0; j < n; j++)
            grad[j] = c->sign * c->Jc[j];
    else if (grad != NULL) /* d(sum r_i^2 / 2)/dz_j = sum r_i dg_i/dz_j (r_i = 0 when met) */
        for (unsigned j = 0; j < n; j++) {
            grad[j] = 0.0;
            for (size_t i = 0; i < c->t->mc; i++)
                grad[j] += c->cur.r[i] * c->Jg[i * n + j];
        }
    return objective_of(c, &c->cur);
}

/* The constraints of list idx[k] (sgn: +1 g, -1 -g) */
static void cons(opt_ctx *c, unsigned mk, double *res, unsigned n, const double *z, double *grad,
                 const size_t *idx, int ineq)
{
    const size_t nn = c->t->n;
    if (ensure(c, z, grad != NULL) != 0 || !c->cur.ok) {
        for (unsigned k = 0; k < mk; k++)
            res[k] = PENALTY;
        if (grad != NULL)
            memset(grad, 0, (size_t)mk * n * sizeof *grad);
        return;
    }
    for (unsigned k = 0; k < mk; k++) {
        const size_t i = idx[k];
        const double s = ineq && c->t->cons[i].kind == LV_CON_MIN ? -1.0 : 1.0;
        res[k] = s * c->cur.g[i];
        if (grad != NULL)
            for (size_t j = 0; j < nn; j++)
                grad[k * n + j] = s * c->Jg[i * nn + j];
    }
}

static void eq_cons(unsigned m, double *res, unsigned n, const double *z, double *grad,
                    void *data)
{
    opt_ctx *c = data;
    cons(c, m, res, n, z, grad, c->eq, 0);
}

static void in_cons(unsigned m, double *res, unsigned n, const double *z, double *grad,
                    void *data)
{
    opt_ctx *c = data;
    cons(c, m, res, n, z, grad, c->in, 1);
}

static const char *result_text(nlopt_result r)
{
    switch (r) {
    case NLOPT_SUCCESS: return "stopped: success";
    case NLOPT_STOPVAL_REACHED: return "stopped: cost limit reached";
    case NLOPT_FTOL_REACHED: return "stopped: the cost changes less than ftol";
    case NLOPT_XTOL_REACHED: return "stopped: the variables change less than xtol";
    case NLOPT_MAXEVAL_REACHED: return "the evaluation limit was reached";
    case NLOPT_MAXTIME_REACHED: return "the time limit was reached";
    case NLOPT_FAILURE: return "failed";
    case NLOPT_INVALID_ARGS: return "invalid arguments";
    case NLOPT_OUT_OF_MEMORY: return "out of memory";
    case NLOPT_ROUNDOFF_LIMITED: return "stopped by roundoff";
    case NLOPT_FORCED_STOP: return "the iteration limit was reached";
    default: return "unknown result";
    }
}

lv_status tg_optimize(lv_target *t, lv_target_method alg, tg_point *p, int max_iter,
                      tg_opt_end *end, char *reason, size_t reason_cap, lv_err *err)
{
    const size_t n = t->n, m = t->mc;
    opt_ctx c;
    memset(&c, 0, sizeof c);
    c.t = t;
    c.err = err;
    c.sign = t->cost.present && t->cost.maximize ? -1.0 : 1.0;
    c.max_points = max_iter;
    *end = TG_OPT_FAILED;
    t->solver = alg == LV_TARGET_SLSQP ? "slsqp" : "cobyla";
    double *z = calloc(n + 1, sizeof *z), *lo = calloc(n + 1, sizeof *lo),
           *hi = calloc(n + 1, sizeof *hi), *ctol = calloc(m + 1, sizeof *ctol);
    c.Jg = calloc(m * n + 1, sizeof *c.Jg);
    c.Jc = calloc(n + 1, sizeof *c.Jc);
    c.zgrad = calloc(n + 1, sizeof *c.zgrad);
    c.zlast = calloc(n + 1, sizeof *c.zlast);
    c.eq = calloc(m + 1, sizeof *c.eq);
    c.in = calloc(m + 1, sizeof *c.in);
    lv_status st = LV_OK;
    if (!z || !lo || !hi || !ctol || !c.Jg || !c.Jc || !c.zgrad || !c.zlast || !c.eq || !c.in ||
        tg_point_init(t, &c.cur) != LV_OK || tg_point_init(t, &c.best) != LV_OK) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (size_t i = 0; i < m; i++) {
        if (t->cons[i].kind == LV_CON_EQUAL)
            c.eq[c.n_eq++] = i;
        else
            c.in[c.n_in++] = i;
        ctol[i] = 0.1; /* NLopt's feasibility test, in tolerances */
    }
    for (size_t j = 0; j < n; j++) {
        const tg_var *v = &t->vars[j];
        z[j] = p->x[j] / v->r.scale;
        lo[j] = v->r.lo / v->r.scale;
        hi[j] = v->r.hi / v->r.scale;
    }
    /* the start point is known: the cache and the best point begin with it */
    tg_point_copy(t, &c.cur, p);
    tg_point_copy(t, &c.best, p);
    for (size_t j = 0; j < n; j++)
        c.cur.x[j] = fmin(t->vars[j].r.hi, fmax(t->vars[j].r.lo, z[j] * t->vars[j].r.scale));
    c.have_cur = c.have_best = 1;
    c.opt = nlopt_create(alg == LV_TARGET_SLSQP ? NLOPT_LD_SLSQP : NLOPT_LN_COBYLA,
                         (unsigned)n);
    if (c.opt == NULL) {
        const char *why = lv_nlopt_error();
        st = why != NULL ? lv_fail(err, LV_ERR_IO, "NLopt cannot be loaded: %s", why)
                         : lv_fail(err, LV_ERR_NOMEM, "out of memory (nlopt_create)");
        goto done;
    }
    nlopt_set_lower_bounds(c.opt, lo);
    nlopt_set_upper_bounds(c.opt, hi);
    nlopt_set_min_objective(c.opt, fun, &c);
    if (c.n_eq > 0)
        nlopt_add_equality_mconstraint(c.opt, (unsigned)c.n_eq, eq_cons, &c, ctol);
    if (c.n_in > 0)
        nlopt_add_inequality_mconstraint(c.opt, (unsigned)c.n_in, in_cons, &c, ctol);
    nlopt_set_xtol_abs1(c.opt, t->set.xtol);
    nlopt_set_ftol_abs(c.opt, t->set.ftol);
    if (alg == LV_TARGET_COBYLA) {
        /* COBYLA's first simplex: a tenth of each scale after another solver, else half */
        double dx = strcmp(t->method_used, "cobyla") == 0 ? 0.5 : 0.1;
        nlopt_set_initial_step1(c.opt, dx);
    }
    double fmin_val = 0.0;
    const nlopt_result r = nlopt_optimize(c.opt, z, &fmin_val);
    if (c.st != LV_OK) {
        st = c.st;
        if (st == LV_ERR_CANCELLED) /* the caller reports the best point so far */
            tg_point_copy(t, p, &c.best);
        goto done;
    }
    tg_point_copy(t, p, &c.best);
    const int met = tg_met(t, p);
    const int stopped_ok = r == NLOPT_SUCCESS || r == NLOPT_FTOL_REACHED ||
                           r == NLOPT_XTOL_REACHED;
    const int limit = r == NLOPT_FORCED_STOP && c.points >= c.max_points;
    *end = stopped_ok && met ? TG_OPT_CONVERGED : limit ? TG_OPT_LIMIT : TG_OPT_FAILED;
    if (*end == TG_OPT_CONVERGED)
        snprintf(reason, reason_cap, "%s %s after %d points%s", t->solver, result_text(r),
                 c.points, c.central_used ? " (central differences near the optimum)" : "");
    else
        snprintf(reason, reason_cap, "%s %s after %d points; %s", t->solver,
                 r == NLOPT_FORCED_STOP && !limit ? "was stopped" : result_text(r),
                 c.points, met ? "the best point meets every constraint"
                               : "no point met every constraint");
done:
    if (c.opt != NULL)
        nlopt_destroy(c.opt);
    tg_point_free(&c.cur);
    tg_point_free(&c.best);
    free(z);
    free(lo);
    free(hi);
    free(ctol);
    free(c.Jg);
    free(c.Jc);
    free(c.zgrad);
    free(c.zlast);
    free(c.eq);
    free(c.in);
    return st;
}
