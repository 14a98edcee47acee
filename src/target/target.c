/* target.c - lv_target: a targeting / optimisation problem over a mission's runs (lv_target.h).
 * Variables are run parameters set on one lv_run; an evaluation executes it with only the
 * constraints' and the cost's phases wanted, so a changed variable re-simulates only the
 * phases it reaches. Sensitivities are finite differences with steps from each variable's
 * scale (Gill, Murray & Wright, Practical Optimization, 1981, sec. 8.6: h = sqrt(eta) x_typ
 * forward, eta^(1/3) x_typ central, eta the relative noise of the function), taken in an order
 * that re-simulates as little as possible. The solvers: newton.c, optimize.c. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/status.h"
#include "lvsim/lv_io.h"
#include "lvsim/lv_units.h"
#include "target/target_int.h"

/* ---- the problem -------------------------------------------------------------------------- */

void lv_target_free(lv_target *t)
{
    if (t == NULL)
        return;
    for (size_t i = 0; i < t->n; i++)
        free(t->vars[i].name);
    free(t->vars);
    for (size_t i = 0; i < t->mc; i++)
        free(t->cons[i].name);
    free(t->cons);
    free(t->cost.name);
    lv_run_free(t->run);
    for (int k = 0; k < TG_MAX_WORKERS - 1; k++)
        lv_run_free(t->aux[k]);
    free(t->want);
    free(t->expect);
    free(t->expect_named);
    free(t->chk);
    free(t->res_mm);
    free(t->tmp_x);
    free(t->order);
    free(t->res_x);
    free(t->res_f);
    free(t->res_r);
    free(t->res_met);
    free(t);
}

lv_status lv_target_create_empty(const lv_mission *m, lv_target **out, lv_err *err)
{
    if (m == NULL || out == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_target_create: NULL argument");
    *out = NULL;
    lv_target *t = calloc(1, sizeof *t);
    if (t == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    t->m = m;
    t->cost.scale = NAN;
    const size_t np = m->def->n_phases;
    t->want = calloc(np + 1, 1);
    t->expect = calloc(np + 1, sizeof *t->expect);
    t->expect_named = calloc(np + 1, 1);
    t->chk = calloc(np + 1, sizeof *t->chk);
    for (size_t k = 0; t->expect != NULL && k < np; k++)
        t->expect[k] = LV_TEND_NONE;
    lv_status st = t->want == NULL || t->expect == NULL || t->expect_named == NULL ||
                           t->chk == NULL
                       ? lv_fail(err, LV_ERR_NOMEM, "out of memory")
                       : lv_run_create(m, &t->run, err);
    if (st != LV_OK) {
        lv_target_free(t);
        return st;
    }
    *out = t;
    return LV_OK;
}

static lv_status push_var(lv_target *t, const char *name, const lv_tvar *r, lv_src_loc start_loc,
                          lv_err *err)
{
    for (size_t i = 0; i < t->n; i++)
        if (t->vars[i].r.slot == r->slot)
            return lv_fail(err, LV_ERR_INPUT, "variable '%s': the parameter is already the "
                           "variable '%s'", name, t->vars[i].name);
    if (t->n == t->cap_n) {
        const size_t cap = t->cap_n ? 2 * t->cap_n : 8;
        tg_var *v = realloc(t->vars, cap * sizeof *v);
        if (v == NULL)
            return lv_fail(err, LV_ERR_NOMEM, "out of memory");
        t->vars = v;
        t->cap_n = cap;
    }
    tg_var *v = &t->vars[t->n];
    memset(v, 0, sizeof *v);
    if ((v->name = strdup(name)) == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    v->r = *r;
    v->start_loc = start_loc;
    /* the first phase (run order) the parameter reaches: sensitivities are taken deepest
     * first, so that restoring one variable and perturbing the next re-simulates little */
    const size_t np = t->m->def->n_phases;
    size_t *ks = malloc((np + 1) * sizeof *ks);
    v->first_phase = 0;
    if (ks != NULL) {
        const size_t nk = lv_mission_slot_phases(t->m, r->slot, ks);
        v->first_phase = nk > 0 ? ks[0] : np;
        for (size_t i = 1; i < nk; i++)
            v->first_phase = ks[i] < v->first_phase ? ks[i] : v->first_phase;
        free(ks);
    }
    t->n++;
    return LV_OK;
}

lv_status lv_target_add_var(lv_target *t, const char *name, double lo, double hi, double start,
                            double scale, double step, lv_err *err)
{
    if (t == NULL || name == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_target_add_var: NULL argument");
    lv_tvar r;
    lv_status st = lv_targeting_resolve_var(t->m, name, lo, hi, start, scale, step, &r, err);
    const lv_src_loc none = {0, 0};
    return st != LV_OK ? st : push_var(t, name, &r, none, err);
}

/* Phase k is assumed to end by end `idx` (LV_TEND_*); `named`: said so (a constraint's `end:`,
 * lv_target_set_end), else the default, which a named end overrides. */
static void expect_end(lv_target *t, size_t k, int idx, int named)
{
    if (named) {
        t->expect[k] = idx;
        t->expect_named[k] = 1;
    } else if (!t->expect_named[k]) {
        t->expect[k] = idx;
    }
    t->n_chk = 0;
    for (size_t j = 0; j < t->m->def->n_phases; j++)
        if (t->expect[j] != LV_TEND_NONE && t->expect[j] != LV_TEND_ANY)
            t->chk[t->n_chk++] = j;
}

static lv_status push_con(lv_target *t, const char *name, int path, lv_con_kind kind,
                          double value, double tol, const lv_tfinal *f, int end, int named,
                          lv_err *err)
{
    if (t->mc == t->cap_m) {
        const size_t cap = t->cap_m ? 2 * t->cap_m : 8;
        tg_con *c = realloc(t->cons, cap * sizeof *c);
        if (c == NULL)
            return lv_fail(err, LV_ERR_NOMEM, "out of memory");
        t->cons = c;
        t->cap_m = cap;
    }
    tg_con *c = &t->cons[t->mc];
    if ((c->name = strdup(name)) == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    c->path = path;
    c->kind = kind;
    c->value = value;
    c->tol = tol;
    c->f = *f;
    t->want[f->phase] = 1;
    expect_end(t, f->phase, end, named);
    t->mc++;
    return LV_OK;
}

lv_status lv_target_add_con(lv_target *t, const char *final, lv_con_kind kind, double value,
                            double tol, lv_err *err)
{
    if (t == NULL || final == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_target_add_con: NULL argument");
    if (kind != LV_CON_EQUAL && kind != LV_CON_MIN && kind != LV_CON_MAX)
        return lv_fail(err, LV_ERR_INPUT, "constraint '%s': unknown kind %d", final, (int)kind);
    if (!isfinite(value) || !(tol > 0.0) || !isfinite(tol))
        return lv_fail(err, LV_ERR_INPUT, "constraint '%s': value %g and tolerance %g: a finite "
                       "value and a tolerance > 0 expected", final, value, tol);
    lv_tfinal f;
    int end = LV_TEND_NONE;
    lv_status st = lv_targeting_resolve_final(t->m, final, &f, err);
    if (st == LV_OK)
        st = lv_targeting_resolve_end(t->m, f.phase, NULL, &end, err);
    return st != LV_OK ? lv_fail_prefix(err, st, "constraint")
                       : push_con(t, final, 0, kind, value, tol, &f, end, 0, err);
}

lv_status lv_target_set_cost(lv_target *t, const char *final, int maximize, double scale,
                             lv_err *err)
{
    if (t == NULL || final == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_target_set_cost: NULL argument");
    if (!isnan(scale) && !(scale > 0.0 && isfinite(scale)))
        return lv_fail(err, LV_ERR_INPUT, "cost '%s': scale %g: > 0 expected (or NAN)", final,
                       scale);
    lv_tfinal f;
    int end = LV_TEND_NONE;
    lv_status st = lv_targeting_resolve_final(t->m, final, &f, err);
    if (st == LV_OK)
        st = lv_targeting_resolve_end(t->m, f.phase, NULL, &end, err);
    if (st != LV_OK)
        return lv_fail_prefix(err, st, "cost");
    char *name = strdup(final);
    if (name == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    free(t->cost.name);
    t->cost = (tg_cost){1, maximize != 0, name, scale, f};
    memcpy(t->want, t->expect_named, t->m->def->n_phases); /* the phases checked by name */
    for (size_t i = 0; i < t->mc; i++)
        t->want[t->cons[i].f.phase] = 1;
    t->want[f.phase] = 1;
    expect_end(t, f.phase, end, 0);
    return LV_OK;
}

lv_status lv_target_create(const lv_mission *m, lv_target **out, lv_err *err)
{
    if (m == NULL || out == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_target_create: NULL argument");
    *out = NULL;
    const lv_targeting_def *d = m->def->targeting;
    if (d == NULL)
        return lv_fail(err, LV_ERR_INPUT, "%s: the mission has no `targeting:` section "
                       "(docs/targeting.md)", m->def->path);
    lv_target *t;
    lv_status st = lv_target_create_empty(m, &t, err);
    for (size_t i = 0; i < d->n_vars && st == LV_OK; i++)
        st = push_var(t, d->vars[i].name, &d->vars[i].res, d->vars[i].start_loc, err);
    for (size_t i = 0; i < d->n_cons && st == LV_OK; i++)
        st = push_con(t, d->cons[i].name, d->cons[i].path, d->cons[i].kind, d->cons[i].value,
                      d->cons[i].tol, &d->cons[i].res, d->cons[i].end_index,
                      d->cons[i].end != NULL, err);
    if (st == LV_OK && d->cost.present) {
        char *name = strdup(d->cost.name);
        if (name == NULL)
            st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        else {
            t->cost = (tg_cost){1, d->cost.maximize, name, d->cost.scale, d->cost.res};
            t->want[d->cost.res.phase] = 1;
            expect_end(t, d->cost.res.phase, d->cost.end_index, d->cost.end != NULL);
        }
    }
    if (st != LV_OK) {
        lv_target_free(t);
        return st;
    }
    t->method = d->method;
    t->diff = d->differences;
    t->max_iter = d->max_iterations;
    t->xtol = d->xtol;
    t->ftol = d->ftol;
    t->restarts = d->restarts;
    *out = t;
    return LV_OK;
}

lv_status lv_target_set_end(lv_target *t, const char *phase, const char *end, lv_err *err)
{
    if (t == NULL || phase == NULL || end == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_target_set_end: NULL argument");
    size_t k;
    int idx;
    lv_status st = lv_mission_phase_find(t->m, phase, &k, err);
    if (st != LV_OK)
        return lv_fail_prefix(err, LV_ERR_INPUT, "lv_target_set_end");
    if ((st = lv_targeting_resolve_end(t->m, k, end, &idx, err)) != LV_OK)
        return st;
    expect_end(t, k, idx, 1);
    t->want[k] = 1; /* simulated (with its ancestors) to be checked */
    return LV_OK;
}

size_t lv_target_var_count(const lv_target *t) { return t->n; }
size_t lv_target_con_count(const lv_target *t) { return t->mc; }

void lv_target_var_info_get(const lv_target *t, size_t i, lv_target_var_info *out)
{
    const tg_var *v = &t->vars[i];
    *out = (lv_target_var_info){v->name,
                                v->r.deg ? "deg" : t->m->def->slots[v->r.slot].unit,
                                v->r.slot,
                                v->r.deg,
                                v->r.lo,
                                v->r.hi,
                                v->r.start,
                                v->r.scale,
                                tg_step(t, i, 0)};
}

void lv_target_con_info_get(const lv_target *t, size_t i, lv_target_con_info *out)
{
    const tg_con *c = &t->cons[i];
    *out = (lv_target_con_info){c->name, c->f.unit, c->f.phase, c->kind, c->value, c->tol};
}

void lv_target_cost_info_get(const lv_target *t, lv_target_cost_info *out)
{
    const tg_cost *c = &t->cost;
    *out = (lv_target_cost_info){c->present,        c->name,     c->present ? c->f.unit : NULL,
                                 c->f.phase,        c->maximize, c->scale};
}

lv_run *lv_target_run(lv_target *t) { return t->run; }

/* ---- points ---------------------------------------------------------------------------------- */

lv_status tg_point_init(const lv_target *t, tg_point *p)
{
    memset(p, 0, sizeof *p);
    p->x = calloc(t->n + 1, sizeof *p->x);
    p->f = calloc(t->mc + 1, sizeof *p->f);
    p->g = calloc(t->mc + 1, sizeof *p->g);
    p->r = calloc(t->mc + 1, sizeof *p->r);
    p->end_got = calloc(t->n_chk + 1, sizeof *p->end_got);
    p->end_t = calloc(t->n_chk + 1, sizeof *p->end_t);
    p->n_chk = t->n_chk;
    p->cost = NAN;
    if (p->x == NULL || p->f == NULL || p->g == NULL || p->r == NULL || p->end_got == NULL ||
        p->end_t == NULL) {
        tg_point_free(p);
        return LV_ERR_NOMEM;
    }
    return LV_OK;
}

void tg_point_free(tg_point *p)
{
    free(p->x);
    free(p->f);
    free(p->g);
    free(p->r);
    free(p->end_got);
    free(p->end_t);
    p->x = p->f = p->g = p->r = NULL;
    p->end_got = NULL;
    p->end_t = NULL;
}

void tg_point_copy(const lv_target *t, tg_point *dst, const tg_point *src)
{
    memcpy(dst->x, src->x, t->n * sizeof *dst->x);
    memcpy(dst->f, src->f, t->mc * sizeof *dst->f);
    memcpy(dst->g, src->g, t->mc * sizeof *dst->g);
    memcpy(dst->r, src->r, t->mc * sizeof *dst->r);
    dst->cost = src->cost;
    dst->worst = src->worst;
    dst->merit = src->merit;
    dst->ok = src->ok;
    memcpy(dst->why, src->why, sizeof dst->why);
    memcpy(dst->end_got, src->end_got, t->n_chk * sizeof *dst->end_got);
    memcpy(dst->end_t, src->end_t, t->n_chk * sizeof *dst->end_t);
    dst->ends_off = src->ends_off;
}

int tg_met(const lv_target *t, const tg_point *p)
{
    if (!p->ok)
        return 0;
    for (size_t i = 0; i < t->mc; i++)
        if (!(fabs(p->r[i]) <= 1.0))
            return 0;
    return 1;
}

/* ---- evaluations ----------------------------------------------------------------------------- */

double tg_wall(const lv_target *t)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (double)(now.tv_sec - t->t0.tv_sec) + 1e-9 * (double)(now.tv_nsec - t->t0.tv_nsec);
}

/* The final value of phase f.phase in run r (its unit as named). */
static double final_of(const lv_run *r, const lv_tfinal *f)
{
    const lv_phase_result *res = lv_run_result(r, f->phase);
    const double v = res->final_values[f->index];
    return f->deg ? v / LV_DEG : v;
}

double tg_con_value(const lv_mission *m, const lv_run *r, const tg_con *c)
{
    if (!c->path)
        return final_of(r, &c->f);
    const lv_result *rows = lv_run_rows(r, c->f.phase);
    size_t col = 0, ct = 0, n = rows != NULL ? lv_result_rows(rows) : 0;
    if (n == 0 || lv_result_column(rows, "time", &ct, NULL) != LV_OK ||
        lv_result_column(rows, m->plan[c->f.phase].final_names[c->f.index], &col, NULL) != LV_OK)
        return NAN;
    double *tv = malloc(2 * n * sizeof *tv);
    if (tv == NULL)
        return NAN;
    double *yv = tv + n;
    for (size_t i = 0; i < n; i++) {
        tv[i] = lv_result_value(rows, i, ct);
        yv[i] = lv_result_value(rows, i, col);
    }
    const double v = lv_targeting_path_extremum(tv, yv, n, c->kind == LV_CON_MAX, NULL);
    free(tv);
    return c->f.deg ? v / LV_DEG : v;
}

int tg_keep_rows(const lv_target *t)
{
    for (size_t i = 0; i < t->mc; i++)
        if (t->cons[i].path)
            return 1;
    return 0;
}

/* The point failed: the first failed (else skipped) phase the constraints need says why. */
static int point_failed(const lv_target *t, const lv_run *r, char *why, size_t cap)
{
    const size_t np = t->m->def->n_phases;
    const lv_phase_result *bad = NULL;
    for (size_t k = 0; k < np; k++) {
        const lv_phase_result *res = lv_run_result(r, k);
        if (res->state == LV_PHASE_FAILED && bad == NULL)
            bad = res;
    }
    for (size_t k = 0; k < np && bad == NULL; k++)
        if (t->want[k] && lv_run_result(r, k)->state != LV_PHASE_DONE)
            bad = lv_run_result(r, k);
    for (size_t k = 0; k < np; k++)
        if (t->want[k] && lv_run_result(r, k)->state != LV_PHASE_DONE) {
            snprintf(why, cap, "%s", bad->error[0] ? bad->error : "a phase did not run");
            return 1;
        }
    return 0;
}

/* The end each checked phase reached in run r (LV_TEND_NONE where it is not done), and how
 * many ended otherwise than assumed. */
static void record_ends(const lv_target *t, const lv_run *r, tg_point *p)
{
    p->ends_off = 0;
    for (size_t i = 0; i < t->n_chk && i < p->n_chk; i++) {
        const lv_phase_result *res = lv_run_result(r, t->chk[i]);
        const int done = res->state == LV_PHASE_DONE;
        p->end_got[i] = !done ? LV_TEND_NONE
                        : res->end_index >= 0 ? res->end_index
                                              : LV_TEND_STOP_TIME;
        p->end_t[i] = done ? res->t_end : NAN;
        p->ends_off += done && p->end_got[i] != t->expect[t->chk[i]];
    }
}

void tg_ends_text(const lv_target *t, const tg_point *p, char *buf, size_t cap)
{
    size_t n = 0;
    if (cap > 0)
        buf[0] = '\0';
    for (size_t i = 0; i < t->n_chk && i < p->n_chk && n + 1 < cap; i++) {
        const size_t k = t->chk[i];
        if (p->end_got[i] == LV_TEND_NONE || p->end_got[i] == t->expect[k])
            continue;
        const int w = snprintf(buf + n, cap - n, "%sphase '%s' ended by %s at t = %.6g s, not "
                               "by %s", n ? "; " : "", t->m->def->phases[k].name,
                               lv_targeting_end_name(t->m, k, p->end_got[i]), p->end_t[i],
                               lv_targeting_end_name(t->m, k, t->expect[k]));
        if (w < 0)
            break;
        n += (size_t)w < cap - n ? (size_t)w : cap - n - 1;
    }
}

/* x set on run r, executed with `threads` workers for its branches; p filled, *runs and
 * *phases counted. Only reads the target: several runs may evaluate at once. */
static lv_status eval_run(const lv_target *t, lv_run *r, int threads, const double *x,
                          tg_point *p, size_t *runs, size_t *phases, lv_err *err)
{
    memcpy(p->x, x, t->n * sizeof *p->x);
    p->ok = 1;
    p->why[0] = '\0';
    p->cost = NAN;
    lv_err e;
    for (size_t j = 0; j < t->n; j++) {
        const tg_var *v = &t->vars[j];
        if (lv_run_set_index(r, v->r.slot, v->r.deg ? x[j] * LV_DEG : x[j], &e) != LV_OK) {
            p->ok = 0;
            snprintf(p->why, sizeof p->why, "%s", e.msg);
        }
    }
    if (p->ok) {
        const lv_run_options opt = {.threads = threads, .no_rows = !tg_keep_rows(t),
                                    .want = t->want,
                                    .stop = t->set.stop, .max_rows = t->set.max_rows};
        lv_status st = lv_run_execute(r, &opt, &e);
        (*runs)++;
        *phases += lv_run_simulated(r);
        if (st == LV_ERR_CANCELLED || st == LV_ERR_NOMEM || st == LV_ERR_IO)
            return lv_fail(err, st, "%s", e.msg);
        if (st == LV_ERR_INPUT) { /* refused before it ran (the row limit): a failed point */
            p->ok = 0;
            snprintf(p->why, sizeof p->why, "%s", e.msg);
        } else if (point_failed(t, r, p->why, sizeof p->why)) {
            p->ok = 0;
        }
    }
    p->ends_off = 0;
    if (p->ok)
        record_ends(t, r, p);
    p->worst = p->merit = p->ok ? 0.0 : INFINITY;
    for (size_t i = 0; i < t->mc; i++) {
        const tg_con *c = &t->cons[i];
        if (!p->ok) {
            p->f[i] = p->g[i] = p->r[i] = NAN;
            continue;
        }
        p->f[i] = tg_con_value(t->m, r, c);
        p->g[i] = (p->f[i] - c->value) / c->tol;
        p->r[i] = c->kind == LV_CON_EQUAL ? p->g[i]
                  : c->kind == LV_CON_MIN ? fmin(0.0, p->g[i])
                                          : fmax(0.0, p->g[i]);
        p->worst = fmax(p->worst, fabs(p->r[i]));
        p->merit += 0.5 * p->r[i] * p->r[i];
    }
    if (p->ok && t->cost.present)
        p->cost = final_of(r, &t->cost.f);
    if (p->ok && (!isfinite(p->merit) || (t->cost.present && !isfinite(p->cost)))) {
        p->ok = 0;
        if (t->cost.present && !isfinite(p->cost))
            snprintf(p->why, sizeof p->why, "the cost's final %s is not finite", t->cost.name);
        else
            snprintf(p->why, sizeof p->why, "the residuals' sum of squares overflows");
        for (size_t i = 0; i < t->mc; i++)
            if (!isfinite(p->f[i])) {
                snprintf(p->why, sizeof p->why, "the final %s is not finite", t->cons[i].name);
                break;
            } else if (!isfinite(p->r[i]) || !isfinite(0.5 * p->r[i] * p->r[i])) {
                snprintf(p->why, sizeof p->why, "the residual of %s, (%g - %g) / %g, overflows",
                         t->cons[i].name, p->f[i], t->cons[i].value, t->cons[i].tol);
                break;
            }
        p->worst = p->merit = INFINITY;
    }
    return LV_OK;
}

static int threads_of(const lv_target *t) { return t->set.threads > 0 ? t->set.threads : 2; }

/* The on_evaluation callback (serialised: sensitivities call it from their workers). */
static lv_status announce(lv_target *t, const char *purpose, const char *var, lv_err *err)
{
    if (t->set.stop != NULL && __atomic_load_n(t->set.stop, __ATOMIC_RELAXED) != 0)
        return lv_fail(err, LV_ERR_CANCELLED, "targeting stopped at iteration %zu",
                       t->iteration);
    if (t->set.on_evaluation == NULL)
        return LV_OK;
    const lv_target_eval ev = {t->iteration, purpose, var, t->runs, t->phases, tg_wall(t)};
    if (t->set.on_evaluation(t, &ev, t->set.user) != 0)
        return lv_fail(err, LV_ERR_CANCELLED, "targeting cancelled at iteration %zu",
                       t->iteration);
    return LV_OK;
}

lv_status tg_eval(lv_target *t, const double *x, const char *purpose, const char *var,
                  tg_point *p, lv_err *err)
{
    lv_status st = announce(t, purpose, var, err);
    return st != LV_OK ? st : eval_run(t, t->run, threads_of(t), x, p, &t->runs, &t->phases,
                                       err);
}

/* eta: the relative noise of the finals, taken as the largest integrator tolerance of the
 * phases simulated (a run's finals are accurate to about its tolerance). */
static double noise(const lv_target *t)
{
    const lv_mission_def *d = t->m->def;
    double eta = 1e-12;
    for (size_t k = 0; k < d->n_phases; k++) {
        int need = 0;
        for (size_t j = 0; j < d->n_phases && !need; j++)
            for (int a = t->want[j] ? (int)j : -1; a >= 0 && !need; a = d->phases[a].parent)
                need = (size_t)a == k;
        if (need)
            eta = fmax(eta, lv_run_get_index(t->run, d->phases[k].tolerance));
    }
    return fmin(eta, 1e-2);
}

double tg_step(const lv_target *t, size_t j, int central)
{
    const tg_var *v = &t->vars[j];
    if (v->r.step > 0.0)
        return central ? v->r.step * 2.0 : v->r.step;
    const double eta = noise(t);
    return v->r.scale * (central ? cbrt(eta) : sqrt(eta));
}

/* ---- sensitivities: one column per variable, taken by workers on runs of their own ----------- */

typedef struct sens_ctx {
    lv_target *t;
    const tg_point *base;
    int central;
    double *Jg, *Jc;
    double *h;               /* [n] steps */
    pthread_mutex_t lock;
    size_t next;             /* the next position in t->order */
    int stop;
    lv_status st;
    lv_err err;
    char (*why)[200];        /* [n] why a column is zero, or "" */
} sens_ctx;

typedef struct sens_worker {
    sens_ctx *c;
    lv_run *run;
    int threads;             /* lv_run_execute's workers */
    double *x;               /* [n] */
    tg_point a, b;
    size_t runs, phases;
    lv_status st;
    lv_err err;
} sens_worker;

/* Column j at the base point, on the worker's run: forward (or, at the upper bound, backward)
 * differences, or central ones; a side whose point fails is replaced by the other. */
static lv_status sens_column(sens_worker *w, size_t j)
{
    sens_ctx *c = w->c;
    const lv_target *t = c->t;
    const size_t n = t->n, m = t->mc;
    const tg_var *v = &t->vars[j];
    const double x0 = c->base->x[j];
    double h = c->h[j];
    if (x0 + h > v->r.hi && x0 - h < v->r.lo) /* bounds closer than the step: the farther */
        h = fmax(v->r.hi - x0, x0 - v->r.lo);
    const int up = x0 + h <= v->r.hi, down = x0 - h >= v->r.lo;
    double xa = NAN, xb = x0;
    const tg_point *pa = NULL, *pb = c->base;
    lv_status st;
    memcpy(w->x, c->base->x, n * sizeof *w->x);
    if (c->central && up && down) {
        w->x[j] = x0 + h;
        if ((st = eval_run(t, w->run, w->threads, w->x, &w->a, &w->runs, &w->phases, &w->err)) !=
            LV_OK)
            return st;
        w->x[j] = x0 - h;
        if ((st = eval_run(t, w->run, w->threads, w->x, &w->b, &w->runs, &w->phases, &w->err)) !=
            LV_OK)
            return st;
        if (w->a.ok && w->b.ok) {
            pa = &w->a, pb = &w->b;
            xa = x0 + h, xb = x0 - h;
        } else if (w->a.ok) {
            pa = &w->a, xa = x0 + h;
        } else if (w->b.ok) {
            pa = &w->b, xa = x0 - h;
        }
    } else {
        xa = up ? x0 + h : x0 - h;
        w->x[j] = xa;
        if ((st = eval_run(t, w->run, w->threads, w->x, &w->a, &w->runs, &w->phases, &w->err)) !=
            LV_OK)
            return st;
        if (!w->a.ok && up && down) { /* the other side */
            w->x[j] = xa = x0 - h;
            if ((st = eval_run(t, w->run, w->threads, w->x, &w->a, &w->runs, &w->phases,
                               &w->err)) != LV_OK)
                return st;
        }
        if (w->a.ok)
            pa = &w->a;
    }
    const double dz = (xa - xb) / v->r.scale;
    for (size_t i = 0; i < m; i++)
        c->Jg[i * n + j] = pa != NULL ? (pa->g[i] - pb->g[i]) / dz : 0.0;
    if (c->Jc != NULL)
        c->Jc[j] = pa != NULL && t->cost.present ? (pa->cost - pb->cost) / t->cost_scale / dz
                                                 : 0.0;
    if (pa == NULL)
        snprintf(c->why[j], sizeof c->why[j], "%.190s", w->a.why);
    return LV_OK;
}

static void *sens_work(void *arg)
{
    sens_worker *w = arg;
    sens_ctx *c = w->c;
    lv_target *t = c->t;
    for (;;) {
        pthread_mutex_lock(&c->lock);
        const size_t q = c->next++;
        int stop = c->stop || q >= t->n;
        if (!stop) {
            const lv_status st = announce(t, "sensitivity", t->vars[t->order[q]].name, &w->err);
            if (st != LV_OK) {
                c->stop = stop = 1;
                w->st = st;
            }
        }
        pthread_mutex_unlock(&c->lock);
        if (stop)
            break;
        lv_status st = sens_column(w, t->order[q]);
        if (st != LV_OK) {
            w->st = st;
            pthread_mutex_lock(&c->lock);
            c->stop = 1;
            pthread_mutex_unlock(&c->lock);
            break;
        }
    }
    return NULL;
}

lv_status tg_sensitivities(lv_target *t, const tg_point *base, int central, double *Jg,
                           double *Jc, char *note, size_t note_cap, lv_err *err)
{
    const size_t n = t->n;
    int nw = threads_of(t);
    if ((size_t)nw > n)
        nw = (int)n;
    if (nw > TG_MAX_WORKERS)
        nw = TG_MAX_WORKERS;
    sens_ctx c = {t, base, central, Jg, Jc, NULL, PTHREAD_MUTEX_INITIALIZER, 0, 0, LV_OK,
                  {LV_OK, ""}, NULL};
    sens_worker w[TG_MAX_WORKERS];
    lv_status st = LV_OK;
    int made = 0;
    memset(w, 0, sizeof w);
    if (note != NULL && note_cap > 0)
        note[0] = '\0';
    c.h = calloc(n + 1, sizeof *c.h);
    c.why = calloc(n + 1, sizeof *c.why);
    if (c.h == NULL || c.why == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (size_t j = 0; j < n; j++)
        c.h[j] = tg_step(t, j, central);
    /* worker 0 takes the target's run; the others runs of their own (kept for later) */
    for (int k = 0; k < nw; k++) {
        if (k > 0 && t->aux[k - 1] == NULL &&
            lv_run_create(t->m, &t->aux[k - 1], err) != LV_OK)
            break;
        w[k].c = &c;
        w[k].run = k == 0 ? t->run : t->aux[k - 1];
        w[k].threads = nw > 1 ? 1 : threads_of(t);
        w[k].x = calloc(n + 1, sizeof *w[k].x);
        if (w[k].x == NULL || tg_point_init(t, &w[k].a) != LV_OK ||
            tg_point_init(t, &w[k].b) != LV_OK) {
            free(w[k].x);
            tg_point_free(&w[k].a);
            break;
        }
        made++;
    }
    if (made == 0) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto done;
    }
    pthread_t tid[TG_MAX_WORKERS];
    int started = 0;
    for (int k = 1; k < made; k++)
        if (pthread_create(&tid[started], NULL, sens_work, &w[k]) == 0)
            started++;
    sens_work(&w[0]);
    for (int k = 0; k < started; k++)
        pthread_join(tid[k], NULL);
    for (int k = 0; k < made; k++) {
        t->runs += w[k].runs;
        t->phases += w[k].phases;
        if (w[k].st != LV_OK && st == LV_OK)
            st = lv_fail(err, w[k].st, "%s", w[k].err.msg);
    }
    for (size_t j = 0; j < n && note != NULL && st == LV_OK; j++)
        if (c.why[j][0]) {
            const size_t used = strlen(note);
            snprintf(note + used, note_cap - used, "%ssensitivity to %s: every perturbed point "
                     "fails (%.120s)", used ? "; " : "", t->vars[j].name, c.why[j]);
        }
done:
    for (int k = 0; k < made; k++) {
        free(w[k].x);
        tg_point_free(&w[k].a);
        tg_point_free(&w[k].b);
    }
    free(c.h);
    free(c.why);
    return st;
}

void tg_report(lv_target *t, const char *event, const tg_point *p, double damping, double step,
               const char *note)
{
    if (t->set.on_iteration != NULL) {
        /* the note, and the phases of an evaluated point that ended otherwise than assumed */
        snprintf(t->note, sizeof t->note, "%s", note != NULL ? note : "");
        if (p->ok && p->ends_off > 0) {
            const size_t n = strlen(t->note);
            snprintf(t->note + n, sizeof t->note - n, "%s", n ? "; " : "");
            const size_t n2 = strlen(t->note);
            tg_ends_text(t, p, t->note + n2, sizeof t->note - n2);
        }
        const lv_target_iter it = {t->iteration,
                                   t->solver,
                                   event,
                                   t->note[0] ? t->note : NULL,
                                   p->x,
                                   p->f,
                                   p->r,
                                   p->cost,
                                   p->worst,
                                   damping,
                                   step,
                                   t->runs - t->rep_runs,
                                   t->phases - t->rep_phases,
                                   t->runs,
                                   t->phases,
                                   tg_wall(t)};
        t->set.on_iteration(t, &it, t->set.user);
    }
    t->rep_runs = t->runs;
    t->rep_phases = t->phases;
}

/* ---- solving --------------------------------------------------------------------------------- */

void lv_target_settings_default(lv_target_settings *s) { memset(s, 0, sizeof *s); }

static int order_cmp_first(const lv_target *t, size_t a, size_t b)
{
    const size_t fa = t->vars[a].first_phase, fb = t->vars[b].first_phase;
    if (fa != fb)
        return fa > fb ? -1 : 1; /* deepest first */
    return a < b ? -1 : (a > b);
}

static void make_order(lv_target *t)
{
    for (size_t i = 0; i < t->n; i++)
        t->order[i] = i;
    for (size_t i = 1; i < t->n; i++) /* insertion sort: few variables */
        for (size_t j = i; j > 0 && order_cmp_first(t, t->order[j - 1], t->order[j]) > 0; j--) {
            const size_t s = t->order[j];
            t->order[j] = t->order[j - 1];
            t->order[j - 1] = s;
        }
}

static lv_status prepare_solve(lv_target *t, const lv_target_settings *s, lv_err *err)
{
    t->set = s != NULL ? *s : (lv_target_settings){0};
    if (t->set.method == LV_TARGET_AUTO)
        t->set.method = t->method;
    if (t->set.differences == LV_DIFF_AUTO)
        t->set.differences = t->diff;
    if (t->set.max_iterations <= 0)
        t->set.max_iterations = t->max_iter;
    if (!(t->set.xtol > 0.0))
        t->set.xtol = t->xtol > 0.0 ? t->xtol : 1e-5;
    if (!(t->set.ftol > 0.0))
        t->set.ftol = t->ftol > 0.0 ? t->ftol : 1e-7;
    if (t->set.restarts <= 0)
        t->set.restarts = t->restarts;
    if (t->n == 0)
        return lv_fail(err, LV_ERR_INPUT, "targeting: no variables");
    if (t->mc == 0 && !t->cost.present)
        return lv_fail(err, LV_ERR_INPUT, "targeting: no constraints and no cost");
    if (t->set.method == LV_TARGET_NEWTON && t->cost.present)
        return lv_fail(err, LV_ERR_INPUT, "targeting: method newton meets constraints and "
                       "optimises no cost: use auto, slsqp or cobyla");
    if (t->set.method == LV_TARGET_NEWTON && t->mc == 0)
        return lv_fail(err, LV_ERR_INPUT, "targeting: method newton needs constraints");
    free(t->tmp_x);
    free(t->order);
    free(t->res_x);
    free(t->res_f);
    free(t->res_r);
    free(t->res_met);
    free(t->res_mm);
    t->res_mm = calloc(t->n_chk + 1, sizeof *t->res_mm);
    t->tmp_x = calloc(t->n + 1, sizeof *t->tmp_x);
    t->order = calloc(t->n + 1, sizeof *t->order);
    t->res_x = calloc(t->n + 1, sizeof *t->res_x);
    t->res_f = calloc(t->mc + 1, sizeof *t->res_f);
    t->res_r = calloc(t->mc + 1, sizeof *t->res_r);
    t->res_met = calloc(t->mc + 1, sizeof *t->res_met);
    if (!t->tmp_x || !t->order || !t->res_x || !t->res_f || !t->res_r || !t->res_met ||
        !t->res_mm)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    make_order(t);
    t->runs = t->phases = t->rep_runs = t->rep_phases = 0;
    t->iteration = 0;
    t->method_used[0] = '\0';
    clock_gettime(CLOCK_MONOTONIC, &t->t0);
    return LV_OK;
}

static void used(lv_target *t, const char *name)
{
    const size_t n = strlen(t->method_used);
    snprintf(t->method_used + n, sizeof t->method_used - n, "%s%s", n ? "+" : "", name);
}

/* SLSQP, then again from its best point (a fresh quasi-Newton Hessian) up to `restarts` times
 * while a run gains more than 1000 ftol of the cost's scale: with finite-difference gradients
 * its BFGS approximation can stall short of the optimum. */
static lv_status slsqp_restarted(lv_target *t, tg_point *p, int max_it, tg_opt_end *oe,
                                 char *reason, size_t cap, lv_err *err)
{
    lv_status st = tg_optimize(t, LV_TARGET_SLSQP, p, max_it, oe, reason, cap, err);
    const double sign = t->cost.maximize ? 1.0 : -1.0;
    int k = 0;
    for (; st == LV_OK && *oe == TG_OPT_CONVERGED && k < t->set.restarts; k++) {
        const double before = p->cost;
        st = tg_optimize(t, LV_TARGET_SLSQP, p, max_it, oe, reason, cap, err);
        if (sign * (p->cost - before) < 1e3 * t->set.ftol * t->cost_scale) {
            k++;
            break;
        }
    }
    if (st == LV_OK && k > 0) {
        const size_t n = strlen(reason);
        snprintf(reason + n, cap - n, " (run %d times from its best point)", k + 1);
    }
    return st;
}

lv_status lv_target_solve(lv_target *t, const lv_target_settings *s,
                          const lv_target_result **out, lv_err *err)
{
    if (t == NULL || out == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_target_solve: NULL argument");
    *out = NULL;
    lv_status st = prepare_solve(t, s, err);
    if (st != LV_OK)
        return st;
    tg_point p;
    if (tg_point_init(t, &p) != LV_OK)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    for (size_t j = 0; j < t->n; j++)
        t->tmp_x[j] = t->vars[j].r.start;
    t->solver = "start";
    if ((st = tg_eval(t, t->tmp_x, "start", NULL, &p, err)) != LV_OK)
        goto done;
    if (!p.ok) {
        st = lv_fail(err, LV_ERR_SOLVER, "the start point fails: %s", p.why);
        goto done;
    }
    t->cost_scale = 1.0;
    if (t->cost.present)
        t->cost_scale = t->cost.scale > 0.0 ? t->cost.scale
                                            : (fabs(p.cost) > 0.0 ? fabs(p.cost) : 1.0);
    tg_report(t, "start", &p, NAN, NAN, NULL);
    /* the start's finals, to tell a problem whose constraints do not move from a hard one */
    double *f0 = malloc((t->mc + 1) * sizeof *f0), *x0 = malloc((t->n + 1) * sizeof *x0);
    if (f0 == NULL || x0 == NULL) {
        free(f0);
        free(x0);
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto done;
    }
    memcpy(f0, p.f, t->mc * sizeof *f0);
    memcpy(x0, p.x, t->n * sizeof *x0);

    int conv = 0;
    char reason[LV_ERR_MSG_MAX] = "";
    const int max_it = t->set.max_iterations;
    /* the optimisers count every point they evaluate: by default 50 + 25 per variable */
    const int opt_it = max_it > 0 ? max_it : 50 + 25 * (int)t->n;
    tg_opt_end oe = TG_OPT_FAILED;
    switch (t->set.method) {
    case LV_TARGET_NEWTON:
        used(t, "newton");
        st = tg_newton(t, &p, max_it > 0 ? max_it : 50, &conv, reason, sizeof reason, err);
        break;
    case LV_TARGET_SLSQP:
    case LV_TARGET_COBYLA:
        used(t, t->set.method == LV_TARGET_SLSQP ? "slsqp" : "cobyla");
        st = t->set.method == LV_TARGET_SLSQP
                 ? slsqp_restarted(t, &p, opt_it, &oe, reason, sizeof reason, err)
                 : tg_optimize(t, t->set.method, &p, opt_it, &oe, reason, sizeof reason, err);
        conv = oe == TG_OPT_CONVERGED;
        break;
    case LV_TARGET_AUTO:
    default:
        if (!t->cost.present || (t->mc > 0 && !tg_met(t, &p))) {
            used(t, "newton");
            st = tg_newton(t, &p, max_it > 0 ? max_it : 50, &conv, reason, sizeof reason, err);
        }
        if (st == LV_OK && t->cost.present) {
            used(t, "slsqp");
            st = slsqp_restarted(t, &p, opt_it, &oe, reason, sizeof reason, err);
            conv = oe == TG_OPT_CONVERGED;
            if (st == LV_OK && oe == TG_OPT_FAILED) { /* COBYLA from SLSQP's best point */
                char why[LV_ERR_MSG_MAX];
                snprintf(why, sizeof why, "%s", reason);
                used(t, "cobyla");
                st = tg_optimize(t, LV_TARGET_COBYLA, &p, opt_it, &oe, reason, sizeof reason,
                                 err);
                conv = oe == TG_OPT_CONVERGED;
                if (st == LV_OK) {
                    const size_t nr = strlen(reason);
                    snprintf(reason + nr, sizeof reason - nr, " (after SLSQP: %.200s)", why);
                }
            }
        }
        break;
    }
    /* cancelled (on_evaluation returned nonzero, or the stop flag cut an evaluation short):
     * the best point so far is the result, not converged, and not evaluated again */
    int cancelled = 0;
    if (st == LV_ERR_CANCELLED && p.ok) {
        cancelled = 1;
        conv = 0;
        snprintf(reason, sizeof reason, "cancelled at iteration %zu: the best point so far",
                 t->iteration);
        st = LV_OK;
    }
    /* not met, the variables moved by a scale or more and no final moved by more than 1e-6
     * of its size: the constraints do not depend on the variables (only integration noise
     * moved them) */
    if (st == LV_OK && !cancelled && !tg_met(t, &p) && p.ok && t->mc > 0) {
        double dz = 0.0, df = 0.0;
        for (size_t j = 0; j < t->n; j++)
            dz = hypot(dz, (p.x[j] - x0[j]) / t->vars[j].r.scale);
        for (size_t i = 0; i < t->mc; i++)
            df = fmax(df, fabs(p.f[i] - f0[i]) / fmax(fabs(f0[i]), t->cons[i].tol));
        const size_t nr = strlen(reason);
        if (dz >= 1.0 && df <= 1e-6)
            snprintf(reason + nr, sizeof reason - nr, "; the constraints do not depend on the "
                     "variables: moving them by %.3g scales changed no final by more than %.2g "
                     "of its size", dz, df);
    }
    free(f0);
    free(x0);
    if (st != LV_OK)
        goto done;
    /* the run holds the result's point (a cancelled solve stops at once: it holds the last
     * point evaluated) */
    if (!cancelled) {
        tg_point q;
        if (tg_point_init(t, &q) != LV_OK) {
            st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
            goto done;
        }
        t->solver = "result";
        st = tg_eval(t, p.x, "point", NULL, &q, err);
        if (st == LV_OK && q.ok) { /* the ends as the run now holds them */
            memcpy(p.end_got, q.end_got, t->n_chk * sizeof *p.end_got);
            memcpy(p.end_t, q.end_t, t->n_chk * sizeof *p.end_t);
        }
        tg_point_free(&q);
        if (st == LV_ERR_CANCELLED) { /* stopped now: the point is known all the same */
            cancelled = 1;
            conv = 0;
            snprintf(reason, sizeof reason, "cancelled at iteration %zu: the best point so far",
                     t->iteration);
            st = LV_OK;
        }
        if (st != LV_OK)
            goto done;
    }
    memcpy(t->res_x, p.x, t->n * sizeof *t->res_x);
    memcpy(t->res_f, p.f, t->mc * sizeof *t->res_f);
    memcpy(t->res_r, p.r, t->mc * sizeof *t->res_r);
    for (size_t i = 0; i < t->mc; i++)
        t->res_met[i] = p.ok && fabs(p.r[i]) <= 1.0;
    t->res = (lv_target_result){0};
    t->res.converged = conv && tg_met(t, &p);
    t->res.cancelled = cancelled;
    snprintf(t->res.reason, sizeof t->res.reason, "%s", reason);
    t->res.method = t->method_used;
    t->res.n_vars = t->n;
    t->res.n_cons = t->mc;
    t->res.x = t->res_x;
    t->res.finals = t->res_f;
    t->res.residual = t->res_r;
    t->res.met = t->res_met;
    t->res.cost = p.cost;
    t->res.worst = p.worst;
    t->res.iterations = t->iteration;
    t->res.runs = t->runs;
    t->res.phases = t->phases;
    t->res.wall = tg_wall(t);
    /* the phases that ended otherwise than assumed at the result's point */
    size_t nmm = 0;
    for (size_t i = 0; p.ok && i < t->n_chk; i++) {
        const size_t k = t->chk[i];
        if (p.end_got[i] == LV_TEND_NONE || p.end_got[i] == t->expect[k])
            continue;
        t->res_mm[nmm++] = (lv_target_end_mismatch){k, t->m->def->phases[k].name,
                                                    lv_targeting_end_name(t->m, k, t->expect[k]),
                                                    lv_targeting_end_name(t->m, k, p.end_got[i]),
                                                    p.end_t[i]};
    }
    t->res.n_end_mismatch = nmm;
    t->res.end_mismatch = t->res_mm;
    *out = &t->res;
done:
    tg_point_free(&p);
    return st;
}
