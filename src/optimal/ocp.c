/* ocp.c - optimal control over a mission's phase tree by direct multiple shooting (lv_ocp.h):
 * the transcription (variables, defects, links, paths, finals), its evaluation with lvsim's
 * own phase models and integrators (lv_run_prepare, lv_sim_*, lv_run_complete: the runner's
 * hand-offs), the sparse finite-difference Jacobian in column groups on threads, and IPOPT.
 * Docs: docs/optimal-control.md.
 *
 * References: Bock & Plitt, "A multiple shooting algorithm for direct solution of optimal
 * control problems", IFAC World Congress 1984 (the transcription); Betts, Practical Methods for
 * Optimal Control and Estimation Using Nonlinear Programming, 2nd ed., SIAM 2010, ch. 3-4
 * (scaling, sparse finite differences); Curtis, Powell & Reid, IMA J. Appl. Math. 13 (1974)
 * 117 (column groups); Wächter & Biegler, Math. Program. 106 (2006) 25 (IPOPT).
 */
#define _POSIX_C_SOURCE 200809L

#include <IpStdCInterface.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/status.h"
#include "core/units.h"
#include "mission/phase_type.h"
#include "optimal/ipopt_dl.h"
#include "optimal/ocp_int.h"

#define OC_INF 1e20                /* IPOPT's infinity (nlp_*_bound_inf: 1e19) */
#define OC_DEFECT_VIOLATED 1e-6    /* a defect or link beyond this (of the state's scale) */

static double wall_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- workers -------------------------------------------------------------------------------- */

static void worker_clear(oc_worker *w)
{
    lv_run_free(w->r);
    lv_mission_free(w->m);
    free(w->x);
    free(w->g);
    free(w->g2);
    memset(w, 0, sizeof *w);
}

/* A mission of the worker's own, whose optimised phases fly their durations: no ends. */
static lv_status worker_init(lv_ocp *o, oc_worker *w, lv_err *err)
{
    lv_status st = lv_mission_load(o->path, &w->m, err);
    if (st != LV_OK)
        return st;
    for (size_t p = 0; p < o->np; p++)
        w->m->def->phases[o->ph[p].k].n_ends = 0;
    if ((st = lv_run_create(w->m, &w->r, err)) != LV_OK)
        return st;
    w->x = calloc(o->n + 1, sizeof *w->x);
    w->g = calloc(o->m + 2, sizeof *w->g);
    w->g2 = calloc(o->m + 2, sizeof *w->g2);
    if (w->x == NULL || w->g == NULL || w->g2 == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    return LV_OK;
}

/* ---- one evaluation ------------------------------------------------------------------------- */

double oc_phase_t0(const lv_ocp *o, const oc_worker *w, size_t k)
{
    const lv_phase_def *ph = &w->m->def->phases[k];
    (void)o;
    if (ph->t_start != LV_NO_SLOT)
        return lv_run_vals(w->r)[ph->t_start];
    if (ph->parent >= 0)
        return lv_run_result(w->r, (size_t)ph->parent)->t_end;
    return 0.0;
}

/* Phase p's controls from z as its inputs table over mission time [t0, t0 + D]. */
static lv_status set_controls(const lv_ocp *o, oc_worker *w, const oc_ph *p, const double *z,
                              double t0, double D, lv_err *err)
{
    double t[LV_OCP_MAX_NODES + 1], y[(LV_OCP_MAX_NODES + 1) * LV_OCP_MAX_CONTROLS];
    const char *names[LV_OCP_MAX_CONTROLS], *units[LV_OCP_MAX_CONTROLS];
    lv_phase_def *ph = &w->m->def->phases[p->k];
    for (size_t i = 0; i < p->nn; i++) {
        t[i] = i + 1 == p->nn ? t0 + D : t0 + D * (double)i / (double)(p->nn - 1);
        for (size_t c = 0; c < p->nu; c++) {
            const size_t v = p->iu + i * p->nu + c;
            y[i * p->nu + c] = z[v] * o->sx[v];
        }
    }
    for (size_t c = 0; c < p->nu; c++) {
        names[c] = ph->type->controls[p->def->ctrl[c].input];
        units[c] = p->def->ctrl[c].deg ? "rad" : "1";
    }
    lv_table_spec spec = {.n_dims = 1, .n = {p->nn}, .x = {t}, .n_out = p->nu, .y = y,
                          .interp = LV_INTERP_LINEAR, .extrap = LV_EXTRAP_CLAMP,
                          .name = "optimal_controls", .axis_name = {"time"},
                          .axis_unit = {"s"}, .out_name = names, .out_unit = units};
    lv_table *tab;
    lv_status st = lv_table_create(&spec, &tab, err);
    if (st != LV_OK)
        return st;
    ph->type->set_controls(ph, tab);
    return LV_OK;
}

/* Settings of one segment [ta, tb] of a prepared phase from state x (the hand-off's other
 * values kept): names/values hold room for the call's initial values and the states. */
double oc_segment_propellant(const lv_ocp *o, const oc_worker *w, const oc_ph *p, size_t j,
                             const double *x, double m_burnout)
{
    if (isnan(m_burnout) || p->im == (size_t)-1)
        return NAN;
    /* Where the optimiser decides how much burns none burns out within a segment: the book is
     * a row of the NLP instead (the final mass at least the burnout mass: r_mass), so the
     * throttle stops the burn - no event that a difference step moves across a segment, no
     * mass below which the controls stop acting (Goddard's burn failed 2 of 3 node counts
     * with the burnout inside). The models' book wants the propellant less than the mass. Where
     * the burn is fixed (throttle and duration), the row would be constant - 0 at a phase that
     * ends at its burnout, with no gradient (Delta III's fixed phases: dual infeasibility
     * 1e8) - and the segment burns out where the phase's book says. */
    if (p->r_mass != (size_t)-1)
        return x[p->im] * (1.0 - 1e-9);
    double *book = &o->prop_book[p->iseg + j];
    if (w->book == OC_BOOK_USE)
        return *book;
    const double prop = fmax(0.0, x[p->im] - m_burnout);
    if (w->book == OC_BOOK_SET)
        *book = prop;
    return prop;
}

void oc_segment_settings(const lv_ocp *o, const lv_sim_settings *cs, const oc_ph *p,
                         const double *x0, double t0, const double *x, double prop, double ta,
                         double tb, const char **names, double *values, lv_sim_settings *s)
{
    size_t n = 0;
    /* what the phase keeps from its start (a steering law's frame and time, the downrange
     * origin): the phase's start, for a model that takes it (dof3: phase_elapsed and
     * phase_start_*); segment 0 starts the phase */
    if (p->ph_el >= 0 && ta > t0) {
        names[n] = "phase_elapsed";
        values[n++] = ta - t0;
        for (size_t j = 0; j < p->nx; j++)
            if (p->ph_x0[j]) {
                names[n] = p->ph_x0_name[j];
                values[n++] = x0[j];
            }
    }
    for (size_t i = 0; i < cs->n_initial; i++) {
        size_t j = 0;
        while (j < p->nx && strcmp(cs->initial_names[i], p->xname[j]) != 0)
            j++;
        if (j < p->nx || strcmp(cs->initial_names[i], "propellant") == 0)
            continue; /* a state, the propellant: the segment's own */
        names[n] = cs->initial_names[i];
        values[n++] = cs->initial_values[i];
    }
    for (size_t j = 0; j < p->nx; j++) {
        names[n] = p->xname[j];
        values[n++] = x[j];
    }
    if (!isnan(prop)) {
        names[n] = "propellant";
        values[n++] = prop;
    }
    *s = *cs;
    s->start_time = ta;
    s->stop_time = tb;
    s->tolerance = o->itol;
    s->n_initial = n;
    s->initial_names = names;
    s->initial_values = values;
    s->n_final = 0;
    s->final_names = NULL;
    s->n_sinks = 0;
    s->sinks = NULL;
    s->n_stops = 0;
    s->stops = NULL;
    s->max_rows = 0.0;
    s->result_file = NULL;
    s->progress = NULL;
    s->stop = NULL;
    s->number_of_intervals = 1;
    s->output_interval = 0.0;
}

static int fail_why(oc_worker *w, const char *phase, const char *what, const lv_err *e)
{
    snprintf(w->why, sizeof w->why, "phase '%.60s': %s%.900s", phase, what, e->msg);
    return 0;
}

/* The value of a final or path row: (y - value) / tolerance, y in degrees for a _deg name. */
static double con_row(const lv_tcon_def *c, double y)
{
    if (c->res.deg)
        y /= LV_DEG;
    return (y - c->value) / c->tol;
}

/* Phase k's final rows and the cost from its finals f. */
static void final_rows(const lv_ocp *o, size_t k, const double *f, double *g)
{
    const lv_ocp_def *d = o->def;
    for (size_t c = 0; c < d->n_cons; c++)
        if (!d->cons[c].path && d->cons[c].res.phase == k)
            g[o->r_fin + c] = con_row(&d->cons[c], f[d->cons[c].res.index]);
    if (d->cost.present && d->cost.res.phase == k) {
        double y = f[d->cost.res.index];
        if (d->cost.res.deg)
            y /= LV_DEG;
        g[o->m] = o->cost_sign * y / o->cost_scale;
    }
}

/* Phase p's start as its prepared model sets it (the hand-off's values, the model's start):
 * the states x[nx] and the mass at which its burning stage burns out, the start mass less the
 * models' "propellant" parameter there (NAN for a model without both). One simulation made
 * and freed: the links' right-hand side and the segments' propellant book. */
lv_status oc_phase_start(const oc_ph *p, const lv_model_def *def, void *inst,
                         const lv_sim_settings *cs, double *x, double *m_burnout, lv_err *err)
{
    *m_burnout = NAN;
    lv_vref rx[32], rp;
    if (p->nx > 32)
        return lv_fail(err, LV_ERR_INPUT, "%zu states: at most 32", p->nx);
    for (size_t i = 0; i < p->nx; i++)
        if (lv_model_vref(def, p->xname[i], &rx[i], err) != LV_OK)
            return err->code;
    const int has_prop = p->im != (size_t)-1 && lv_model_vref(def, "propellant", &rp, NULL) == LV_OK;
    lv_sim_settings s = *cs;
    s.n_sinks = 0, s.sinks = NULL, s.n_stops = 0, s.stops = NULL, s.n_final = 0;
    s.final_names = NULL, s.result_file = NULL, s.max_rows = 0.0;
    lv_sim *sim = NULL;
    double prop = NAN;
    lv_status st = lv_sim_create(def, inst, &s, &sim, err);
    if (st == LV_OK)
        st = lv_sim_get(sim, rx, p->nx, x, err);
    if (st == LV_OK && has_prop && (st = lv_sim_get(sim, &rp, 1, &prop, err)) == LV_OK)
        *m_burnout = x[p->im] - prop;
    lv_sim_free(sim);
    return st;
}

/* Flies optimised phase p from its segments' start states in z. */
static int fly_optimised(lv_ocp *o, oc_worker *w, const oc_ph *p, double *z, double *g,
                         int propagate)
{
    const lv_phase_def *ph = &w->m->def->phases[p->k];
    lv_err e = {LV_OK, ""};
    const double t0 = oc_phase_t0(o, w, p->k);
    const double D = p->iD >= 0 ? z[p->iD] * o->sx[p->iD] : p->D;
    if (!(D > 0.0))
        return fail_why(w, ph->name, "", &(lv_err){LV_ERR_INPUT, "duration <= 0"});
    if (set_controls(o, w, p, z, t0, D, &e) != LV_OK ||
        lv_run_set_index(w->r, ph->t_stop, t0 + D, &e) != LV_OK)
        return fail_why(w, ph->name, "", &e);
    lv_phase_call *c;
    if (lv_run_prepare(w->r, p->k, &c, &e) != LV_OK)
        return fail_why(w, ph->name, "", &e);
    const lv_model_def *def = lv_phase_call_model(c);
    void *inst = lv_phase_call_inst(c);
    const lv_sim_settings *cs = lv_phase_call_settings(c);
    const size_t nx = p->nx;
    const char *names[96 + 3 * 32];
    double values[96 + 3 * 32], xa[32], xb[32], yp[LV_OCP_MAX_CONTROLS * 4 + 8], m_bo;
    lv_vref rx[32], rp[32];
    int ok = 1;
    if (cs->n_initial + 2 * nx + 2 > sizeof names / sizeof names[0] || nx > 32 ||
        p->n_path > 32) {
        lv_phase_call_free(c);
        return fail_why(w, ph->name, "",
                        &(lv_err){LV_ERR_INPUT, "too many start values or states"});
    }
    for (size_t i = 0; i < nx && ok; i++)
        ok = lv_model_vref(def, p->xname[i], &rx[i], &e) == LV_OK;
    for (size_t q = 0; q < p->n_path && ok; q++)
        ok = lv_model_vref(def, p->path_out[q], &rp[q], &e) == LV_OK;
    if (!ok) {
        lv_phase_call_free(c);
        return fail_why(w, ph->name, "", &e);
    }
    /* the hand-off's start: the link rows */
    if (oc_phase_start(p, def, inst, cs, xa, &m_bo, &e) != LV_OK) {
        lv_phase_call_free(c);
        return fail_why(w, ph->name, "its start: ", &e);
    }
    double x0[32];
    for (size_t i = 0; i < nx; i++) {
        const size_t v = p->ix + i;
        if (propagate)
            z[v] = xa[i] / o->sx[v];
        g[p->r_link + i] = (z[v] * o->sx[v] - xa[i]) / p->xs[i];
        x0[i] = xa[i];
    }
    const double h = D / (double)p->ns;
    double *finals = lv_phase_call_finals(c);
    lv_sim_report rep;
    memset(&rep, 0, sizeof rep);
    for (size_t j = 0; j < p->ns && ok; j++) {
        const double ta = t0 + h * (double)j;
        const double tb = j + 1 == p->ns ? t0 + D : t0 + h * (double)(j + 1);
        for (size_t i = 0; i < nx; i++)
            xa[i] = z[p->ix + j * nx + i] * o->sx[p->ix + j * nx + i];
        lv_sim_settings s;
        oc_segment_settings(o, cs, p, x0, t0, xa, oc_segment_propellant(o, w, p, j, xa, m_bo),
                            ta, tb, names, values, &s);
        const int last = j + 1 == p->ns;
        if (last) {
            s.n_final = cs->n_final;
            s.final_names = cs->final_names;
        }
        lv_sim *sim = NULL;
        lv_status st = lv_sim_create(def, inst, &s, &sim, &e);
        if (st == LV_OK && p->n_path > 0 && (st = lv_sim_get(sim, rp, p->n_path, yp, &e)) == LV_OK)
            for (size_t q = 0; q < p->n_path; q++)
                g[p->r_path + q * (p->ns + 1) + j] = con_row(&o->def->cons[p->path_con[q]], yp[q]);
        if (st == LV_OK)
            st = lv_sim_advance(sim, tb, &e);
        w->segments++;
        if (st == LV_OK && lv_sim_time(sim) < tb) {
            const lv_sim_report *r = lv_sim_report_get(sim);
            snprintf(e.msg, sizeof e.msg, "segment %zu of %zu ended at t = %.9g s by '%s', "
                     "before its end %.9g s", j + 1, p->ns, lv_sim_time(sim), r->stop_name, tb);
            st = LV_ERR_SOLVER;
        }
        if (st == LV_OK)
            st = lv_sim_get(sim, rx, nx, xb, &e);
        if (st == LV_OK && last)
            st = lv_sim_finish(sim, finals, &rep, &e); /* then freed, as every other */
        lv_sim_free(sim);
        if (st != LV_OK) {
            ok = fail_why(w, ph->name, "", &e);
            break;
        }
        if (!last)
            for (size_t i = 0; i < nx; i++) {
                const size_t v = p->ix + (j + 1) * nx + i;
                if (propagate)
                    z[v] = xb[i] / o->sx[v];
                g[p->r_def + j * nx + i] = (xb[i] - z[v] * o->sx[v]) / p->xs[i];
            }
    }
    if (!ok) {
        lv_sim_report_clear(&rep);
        lv_phase_call_free(c);
        return 0;
    }
    /* the end node's path rows, from the finals */
    for (size_t q = 0; q < p->n_path; q++) {
        const lv_tcon_def *cd = &o->def->cons[p->path_con[q]];
        g[p->r_path + q * (p->ns + 1) + p->ns] = con_row(cd, finals[cd->res.index]);
    }
    final_rows(o, p->k, finals, g);
    if (p->r_mass != (size_t)-1)
        g[p->r_mass] = (xb[p->im] - m_bo) / p->xs[p->im];
    rep.end_time = t0 + D;
    lv_run_complete(w->r, c, LV_OK, NULL, &rep, &e);
    lv_sim_report_clear(&rep);
    return 1;
}

/* Flies phase k as `lvsim run` does (not optimised). */
static int fly_whole(lv_ocp *o, oc_worker *w, size_t k, double *g)
{
    const lv_phase_def *ph = &w->m->def->phases[k];
    lv_err e = {LV_OK, ""}, se = {LV_OK, ""};
    lv_phase_call *c;
    if (lv_run_prepare(w->r, k, &c, &e) != LV_OK)
        return fail_why(w, ph->name, "", &e);
    lv_sim_settings *s = lv_phase_call_settings(c);
    s->n_sinks = 0;
    s->sinks = NULL;
    lv_sim_report rep;
    memset(&rep, 0, sizeof rep);
    const lv_status st = lv_simulate(lv_phase_call_model(c), lv_phase_call_inst(c), s,
                                     lv_phase_call_finals(c), &rep, &se);
    w->segments++;
    if (st == LV_OK)
        final_rows(o, k, lv_phase_call_finals(c), g);
    lv_run_complete(w->r, c, st, &se, &rep, &e);
    lv_sim_report_clear(&rep);
    if (st != LV_OK)
        return fail_why(w, ph->name, "", &se);
    return 1;
}

int oc_evaluate_base(lv_ocp *o)
{
    o->w[0].book = OC_BOOK_SET; /* the differences at z_base take its propellants */
    const int ok = oc_evaluate(o, &o->w[0], o->z_base, o->g_base, 0);
    o->w[0].book = OC_BOOK_OWN;
    return ok;
}

int oc_evaluate(lv_ocp *o, oc_worker *w, double *z, double *g, int propagate)
{
    w->why[0] = '\0';
    for (size_t i = 0; i <= o->m; i++)
        g[i] = 0.0;
    for (size_t k = 0; k < o->n_phases; k++) {
        if (!o->needed[k])
            continue;
        const int ok = o->opt_of[k] >= 0
                           ? fly_optimised(o, w, &o->ph[o->opt_of[k]], z, g, propagate)
                           : fly_whole(o, w, k, g);
        if (!ok)
            return 0;
    }
    for (size_t i = 0; i <= o->m; i++)
        if (!isfinite(g[i])) {
            snprintf(w->why, sizeof w->why, "row %zu is not a number", i);
            return 0;
        }
    return 1;
}

/* ---- the Jacobian's pattern and groups --------------------------------------------------------- */

typedef struct rowset {
    unsigned char *on; /* [m + 1] */
} rowset;

static void mark_range(unsigned char *on, size_t a, size_t n)
{
    for (size_t i = 0; i < n; i++)
        on[a + i] = 1;
}

/* Every row of phase k's subtree (its own and its descendants'), or with `own` 0 only the
 * rows that its finals reach: its end node's paths, its final rows, its descendants' rows. */
static void mark_subtree(const lv_ocp *o, const lv_mission_def *d, size_t k, int own,
                         unsigned char *on)
{
    const int pi = o->opt_of[k];
    if (pi >= 0) {
        const oc_ph *p = &o->ph[pi];
        if (own) {
            mark_range(on, p->r_link, p->nx);
            mark_range(on, p->r_def, (p->ns - 1) * p->nx);
        }
        for (size_t q = 0; q < p->n_path; q++) {
            if (own)
                mark_range(on, p->r_path + q * (p->ns + 1), p->ns + 1);
            else
                on[p->r_path + q * (p->ns + 1) + p->ns] = 1;
        }
        if (p->r_mass != (size_t)-1)
            on[p->r_mass] = 1;
    }
    for (size_t c = 0; c < o->def->n_cons; c++)
        if (!o->def->cons[c].path && o->def->cons[c].res.phase == k)
            on[o->r_fin + c] = 1;
    if (o->def->cost.present && o->def->cost.res.phase == k)
        on[o->m] = 1;
    for (size_t j = k + 1; j < d->n_phases; j++)
        if (d->phases[j].parent == (int)k && o->needed[j])
            mark_subtree(o, d, j, 1, on);
}

/* The rows variable v of phase p reaches (a superset: the pattern). */
static void column_rows(const lv_ocp *o, const lv_mission_def *d, const oc_ph *p, size_t v,
                        unsigned char *on)
{
    const size_t nx = p->nx, ns = p->ns;
    if (v >= p->ix && v < p->ix + ns * nx) { /* segment j's start state */
        const size_t j = (v - p->ix) / nx;
        if (j == 0)
            mark_range(on, p->r_link, nx);
        if (j + 1 < ns)
            mark_range(on, p->r_def + j * nx, nx);
        if (j > 0)
            on[p->r_def + (j - 1) * nx + (v - p->ix) % nx] = 1;
        for (size_t q = 0; q < p->n_path; q++)
            on[p->r_path + q * (ns + 1) + j] = 1;
        if (j + 1 == ns)
            mark_subtree(o, d, p->k, 0, on);
        return;
    }
    if (v >= p->iu && v < p->iu + p->nn * p->nu) { /* a control node: the segments it shapes */
        const size_t a = (v - p->iu) / p->nu;
        const double ta = a > 0 ? (double)(a - 1) / (double)(p->nn - 1) : 0.0;
        const double tb = a + 1 < p->nn ? (double)(a + 1) / (double)(p->nn - 1) : 1.0;
        for (size_t j = 0; j < ns; j++) {
            const double sa = (double)j / (double)ns, sb = (double)(j + 1) / (double)ns;
            if (sb < ta - 1e-12 || sa > tb + 1e-12)
                continue;
            if (j + 1 < ns)
                mark_range(on, p->r_def + j * nx, nx);
            else
                mark_subtree(o, d, p->k, 0, on);
            for (size_t q = 0; q < p->n_path; q++) {
                on[p->r_path + q * (ns + 1) + j] = 1;
                on[p->r_path + q * (ns + 1) + j + 1] = 1;
            }
        }
        return;
    }
    /* the duration: every row of the phase and below */
    mark_subtree(o, d, p->k, 1, on);
}

static lv_status build_pattern(lv_ocp *o, const lv_mission_def *d, lv_err *err)
{
    unsigned char *on = malloc(o->m + 1);
    size_t cap = 1024, nnz = 0;
    o->jc = calloc(o->n + 1, sizeof *o->jc);
    o->jr = malloc(cap * sizeof *o->jr);
    if (on == NULL || o->jc == NULL || o->jr == NULL) {
        free(on);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    o->nnz = 0;
    for (size_t p = 0; p < o->np; p++) {
        const oc_ph *ph = &o->ph[p];
        const size_t v_end = ph->iD >= 0 ? (size_t)ph->iD + 1 : ph->iu + ph->nn * ph->nu;
        for (size_t v = ph->ix; v < v_end; v++) {
            memset(on, 0, o->m + 1);
            column_rows(o, d, ph, v, on);
            o->jc[v] = nnz;
            for (size_t r = 0; r <= o->m; r++) {
                if (!on[r])
                    continue;
                if (nnz == cap) {
                    size_t *t = realloc(o->jr, 2 * cap * sizeof *t);
                    if (t == NULL) {
                        free(on);
                        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
                    }
                    o->jr = t;
                    cap *= 2;
                }
                o->jr[nnz++] = r;
                if (r < o->m)
                    o->nnz++;
            }
        }
    }
    o->jc[o->n] = nnz;
    /* groups: greedy, each column into the first group none of whose rows it reaches */
    unsigned char *used = NULL;
    size_t ng = 0;
    size_t *gof = malloc(o->n * sizeof *gof);
    if (gof == NULL) {
        free(on);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    for (size_t v = 0; v < o->n; v++) {
        size_t g = 0;
        for (; g < ng; g++) {
            const unsigned char *u = used + g * (o->m + 1);
            size_t e = o->jc[v];
            while (e < o->jc[v + 1] && !u[o->jr[e]])
                e++;
            if (e == o->jc[v + 1])
                break;
        }
        if (g == ng) {
            unsigned char *t = realloc(used, (ng + 1) * (o->m + 1));
            if (t == NULL) {
                free(used), free(gof), free(on);
                return lv_fail(err, LV_ERR_NOMEM, "out of memory");
            }
            used = t;
            memset(used + ng * (o->m + 1), 0, o->m + 1);
            ng++;
        }
        for (size_t e = o->jc[v]; e < o->jc[v + 1]; e++)
            used[g * (o->m + 1) + o->jr[e]] = 1;
        gof[v] = g;
    }
    free(used);
    free(on);
    o->n_groups = ng;
    o->grp_start = calloc(ng + 1, sizeof *o->grp_start);
    o->grp_col = malloc((o->n + 1) * sizeof *o->grp_col);
    o->jv = calloc(nnz + 1, sizeof *o->jv);
    if (o->grp_start == NULL || o->grp_col == NULL || o->jv == NULL) {
        free(gof);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    for (size_t v = 0; v < o->n; v++)
        o->grp_start[gof[v] + 1]++;
    for (size_t g = 0; g < ng; g++)
        o->grp_start[g + 1] += o->grp_start[g];
    size_t *fill = calloc(ng + 1, sizeof *fill);
    if (fill == NULL) {
        free(gof);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    for (size_t v = 0; v < o->n; v++)
        o->grp_col[o->grp_start[gof[v]] + fill[gof[v]]++] = v;
    free(fill);
    free(gof);
    return LV_OK;
}

/* ---- the problem ----------------------------------------------------------------------------- */

void lv_ocp_free(lv_ocp *o)
{
    if (o == NULL)
        return;
    for (size_t p = 0; p < o->np; p++) {
        for (size_t i = 0; i < o->ph[p].nx; i++)
            free(o->ph[p].xname[i]);
        free(o->ph[p].xname);
        free(o->ph[p].xs);
        free(o->ph[p].ph_x0);
        free(o->ph[p].ph_x0_name);
        free(o->ph[p].path_con);
        free(o->ph[p].path_out);
    }
    free(o->ph);
    for (int i = 0; i < OC_MAX_WORKERS; i++)
        worker_clear(&o->w[i]);
    free(o->opt_of);
    free(o->needed);
    free(o->sx), free(o->zl), free(o->zu), free(o->gl), free(o->gu), free(o->vname);
    free(o->jc), free(o->jr), free(o->grp_start), free(o->grp_col), free(o->jv);
    free(o->z_base), free(o->g_base), free(o->z_jac), free(o->z_best);
    free(o->prop_book);
    free(o->path);
    free(o);
}

/* The value of column `col` of rows `res` at time t (linear between rows; clamped). */
static double rows_at(const lv_result *res, size_t tcol, size_t col, double t)
{
    const size_t n = lv_result_rows(res);
    if (n == 0)
        return NAN;
    if (t <= lv_result_value(res, 0, tcol))
        return lv_result_value(res, 0, col);
    for (size_t i = 1; i < n; i++) {
        const double tb = lv_result_value(res, i, tcol);
        if (t <= tb) {
            const double ta = lv_result_value(res, i - 1, tcol);
            const double ya = lv_result_value(res, i - 1, col), yb = lv_result_value(res, i, col);
            return tb > ta ? ya + (yb - ya) * (t - ta) / (tb - ta) : yb;
        }
    }
    return lv_result_value(res, n - 1, col);
}

/* The start point from run r of mission m, flown as written with its rows: the durations and
 * the control nodes (a control's `start:`, else its own input along that flight, else the
 * phase's own table of it over time, else its constant, else the middle of its bounds). */
static void start_point(lv_ocp *o, const lv_mission *m, const lv_run *r, double *x)
{
    for (size_t p = 0; p < o->np; p++) {
        oc_ph *ph = &o->ph[p];
        const lv_phase_result *res = lv_run_result(r, ph->k);
        const lv_ocp_phase_def *pd = ph->def;
        double D = res->t_end - res->t_start;
        if (pd->free_duration)
            D = isnan(pd->dur_start) ? fmin(fmax(D, pd->dur_lo), pd->dur_hi) : pd->dur_start;
        ph->D = D;
        if (ph->iD >= 0)
            x[ph->iD] = D;
        const lv_result *rows = lv_run_rows(r, ph->k);
        size_t tcol = 0;
        const int have_rows = rows != NULL && lv_result_rows(rows) > 0 &&
                              lv_result_column(rows, "time", &tcol, NULL) == LV_OK;
        for (size_t c = 0; c < ph->nu; c++) {
            const lv_ocp_ctrl_def *u = &pd->ctrl[c];
            char col_name[80];
            snprintf(col_name, sizeof col_name, "%s_in",
                     m->def->phases[ph->k].type->controls[u->input]);
            size_t col, tk;
            const int have = have_rows && lv_result_column(rows, col_name, &col, NULL) == LV_OK;
            /* an input the model does not output (the attitude law's pitch in its frame):
             * the phase's own table of it over time */
            const lv_phase_def *pd_m = &m->def->phases[ph->k];
            const lv_table *own = pd_m->type->own_inputs ? pd_m->type->own_inputs(pd_m) : NULL;
            const int have_own = !have && own != NULL && lv_table_n_dims(own) == 1 &&
                                 (strcmp(lv_table_axis_name(own, 0), "time") == 0 ||
                                  strcmp(lv_table_axis_name(own, 0), "t") == 0) &&
                                 lv_table_out_index(own, pd_m->type->controls[u->input], &tk,
                                                    NULL) == LV_OK;
            double *buf = have_own ? calloc(lv_table_n_out(own) + 1, sizeof *buf) : NULL;
            const double cst = !have && !have_own && pd_m->type->control_constant != NULL
                                   ? pd_m->type->control_constant(pd_m, m->def, u->input)
                                   : NAN;
            lv_table_cursor cur = {0};
            for (size_t i = 0; i < ph->nn; i++) {
                const double t = res->t_start + D * (double)i / (double)(ph->nn - 1);
                double y = !isnan(u->start) ? u->start
                           : have            ? rows_at(rows, tcol, col, t)
                           : buf != NULL && lv_table_eval1(own, &cur, t, buf, NULL) == LV_OK
                               ? buf[tk]
                           : !isnan(cst) ? cst
                                         : 0.5 * (u->lo + u->hi);
                if (isnan(y))
                    y = 0.5 * (u->lo + u->hi);
                x[ph->iu + i * ph->nu + c] = fmin(fmax(y, u->lo), u->hi);
            }
            free(buf);
        }
    }
}

/* Phase p's states: names and nominal magnitudes from its model (prepared on run r, whose
 * ancestors of it have flown). */
static lv_status phase_states(oc_ph *p, lv_run *r, lv_err *err)
{
    lv_phase_call *c;
    lv_status st = lv_run_prepare(r, p->k, &c, err);
    if (st != LV_OK)
        return st;
    const lv_model_def *def = lv_phase_call_model(c);
    p->nx = def->n_states;
    p->xname = calloc(p->nx + 1, sizeof *p->xname);
    p->xs = calloc(p->nx + 1, sizeof *p->xs);
    p->ph_x0 = calloc(p->nx + 1, sizeof *p->ph_x0);
    p->ph_x0_name = calloc(p->nx + 1, sizeof *p->ph_x0_name);
    if (p->xname == NULL || p->xs == NULL || p->ph_x0 == NULL || p->ph_x0_name == NULL) {
        lv_phase_call_free(c);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    p->im = (size_t)-1;
    p->r_mass = (size_t)-1;
    p->ph_el = -1;
    for (size_t i = 0; i < def->n_params; i++) {
        if (strcmp(def->params[i].name, "propellant") == 0)
            p->burns = def->params[i].start > 0.0;
        if (strcmp(def->params[i].name, "phase_elapsed") == 0)
            p->ph_el = (long)i;
    }
    for (size_t i = 0; i < p->nx; i++) {
        if (strcmp(def->states[i].name, lv_run_mission(r)->def->phases[p->k].type->mass_state) == 0)
            p->im = i;
        p->xname[i] = strdup(def->states[i].name);
        p->xs[i] = def->states[i].nominal > 0.0 ? def->states[i].nominal : 1.0;
        if (p->xname[i] != NULL && strlen(p->xname[i]) < sizeof p->ph_x0_name[0] - 13) {
            snprintf(p->ph_x0_name[i], sizeof p->ph_x0_name[0], "phase_start_%s", p->xname[i]);
            for (size_t q = 0; q < def->n_params; q++)
                p->ph_x0[i] |= strcmp(def->params[q].name, p->ph_x0_name[i]) == 0;
        }
        if (p->xname[i] == NULL) {
            lv_phase_call_free(c);
            return lv_fail(err, LV_ERR_NOMEM, "out of memory");
        }
    }
    lv_phase_call_free(c);
    return LV_OK;
}

lv_status lv_ocp_create(const char *path, lv_ocp **out, lv_err *err)
{
    *out = NULL;
    lv_ocp *o = calloc(1, sizeof *o);
    if (o == NULL || (o->path = strdup(path)) == NULL) {
        free(o);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    lv_mission *m0 = NULL; /* the setup's copy; the workers load their own */
    lv_run *r0 = NULL;     /* m0 flown as written */
    lv_status st = lv_mission_load(path, &m0, err);
    if (st != LV_OK) {
        lv_ocp_free(o);
        return st;
    }
    const lv_mission_def *d = m0->def;
    o->def = d->ocp;
    if (o->def == NULL) {
        st = lv_fail(err, LV_ERR_INPUT, "%s: the mission has no optimal_control: section "
                     "(docs/optimal-control.md)", path);
        goto fail;
    }
    const lv_ocp_def *od = o->def;
    o->n_phases = d->n_phases;
    o->itol = od->integrator_tolerance;
    o->opt_of = malloc(o->n_phases * sizeof *o->opt_of);
    o->needed = calloc(o->n_phases + 1, 1);
    o->ph = calloc(od->n_phases, sizeof *o->ph);
    if (o->opt_of == NULL || o->needed == NULL || o->ph == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto fail;
    }
    for (size_t k = 0; k < o->n_phases; k++)
        o->opt_of[k] = -1;
    /* the optimised phases in run order */
    for (size_t k = 0; k < o->n_phases; k++)
        for (size_t j = 0; j < od->n_phases; j++)
            if (od->phases[j].phase == k) {
                o->ph[o->np].k = k;
                o->ph[o->np].def = &od->phases[j];
                o->opt_of[k] = (int)o->np++;
            }
    /* the phases flown: the optimised ones, those the constraints and the cost read, their
     * ancestors */
    for (size_t p = 0; p < o->np; p++)
        o->needed[o->ph[p].k] = 1;
    for (size_t c = 0; c < od->n_cons; c++)
        o->needed[od->cons[c].res.phase] = 1;
    if (od->cost.present)
        o->needed[od->cost.res.phase] = 1;
    for (size_t k = o->n_phases; k-- > 0;)
        if (o->needed[k] && d->phases[k].parent >= 0)
            o->needed[d->phases[k].parent] = 1;

    /* the mission flown once as written, with its rows: every phase flown here must fly, the
     * optimised phases' states come from their models, the start point from the flight */
    if ((st = lv_run_create(m0, &r0, err)) != LV_OK)
        goto fail;
    if ((st = lv_run_execute(r0, NULL, err)) != LV_OK) {
        if (strstr(err->msg, "the start point") == NULL)
            st = lv_fail_prefix(err, st, "%s: the start point (the mission flown as written)",
                                path);
        goto fail;
    }
    for (size_t k = 0; k < o->n_phases; k++) {
        const lv_phase_result *res = lv_run_result(r0, k);
        if (o->needed[k] && res->state != LV_PHASE_DONE) {
            st = lv_fail(err, LV_ERR_INPUT, "%s: the start point: phase '%s' did not fly as "
                         "written: %s", path, res->name, res->error);
            goto fail;
        }
    }
    for (size_t p = 0; p < o->np; p++)
        if ((st = phase_states(&o->ph[p], r0, err)) != LV_OK)
            goto fail;
    /* variables and rows */
    size_t n = 0, m = 0, n_seg = 0;
    for (size_t p = 0; p < o->np; p++) {
        oc_ph *ph = &o->ph[p];
        ph->nu = ph->def->n_ctrl;
        ph->nn = (size_t)ph->def->nodes;
        ph->ns = (size_t)ph->def->segments;
        ph->iseg = n_seg;
        n_seg += ph->ns;
        ph->ix = n;
        n += ph->ns * ph->nx;
        ph->iu = n;
        n += ph->nn * ph->nu;
        ph->iD = ph->def->free_duration ? (long)n++ : -1;
        ph->r_link = m;
        m += ph->nx;
        ph->r_def = m;
        m += (ph->ns - 1) * ph->nx;
        ph->path_con = calloc(od->n_cons + 1, sizeof *ph->path_con);
        ph->path_out = calloc(od->n_cons + 1, sizeof *ph->path_out);
        if (ph->path_con == NULL || ph->path_out == NULL) {
            st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
            goto fail;
        }
        for (size_t c = 0; c < od->n_cons; c++)
            if (od->cons[c].path && od->cons[c].res.phase == ph->k) {
                const lv_phase_plan *pl = &m0->plan[ph->k];
                snprintf(ph->path_out[ph->n_path], sizeof ph->path_out[0], "%s",
                         pl->final_names[od->cons[c].res.index]);
                ph->path_con[ph->n_path++] = c;
            }
        ph->r_path = m;
        m += ph->n_path * (ph->ns + 1);
        int thr_ctl = 0;
        for (size_t c = 0; c < ph->nu; c++)
            thr_ctl |= strcmp(d->phases[ph->k].type->controls[ph->def->ctrl[c].input],
                              "throttle") == 0;
        ph->r_mass = ph->burns && (thr_ctl || ph->iD >= 0) ? m++ : (size_t)-1;
    }
    o->r_fin = m;
    m += od->n_cons;
    o->n = n;
    o->m = m;
    o->sx = calloc(n + 1, sizeof *o->sx);
    o->zl = calloc(n + 1, sizeof *o->zl);
    o->zu = calloc(n + 1, sizeof *o->zu);
    o->gl = calloc(m + 1, sizeof *o->gl);
    o->gu = calloc(m + 1, sizeof *o->gu);
    o->vname = calloc(n + 1, sizeof *o->vname);
    o->z_base = calloc(n + 1, sizeof *o->z_base);
    o->g_base = calloc(m + 2, sizeof *o->g_base);
    o->z_jac = calloc(n + 1, sizeof *o->z_jac);
    o->z_best = calloc(n + 1, sizeof *o->z_best);
    o->prop_book = calloc(n_seg + 1, sizeof *o->prop_book);
    double *x = calloc(n + 1, sizeof *x);
    if (!o->sx || !o->zl || !o->zu || !o->gl || !o->gu || !o->vname || !o->z_base ||
        !o->g_base || !o->z_jac || !o->z_best || !o->prop_book || !x) {
        free(x);
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto fail;
    }
    for (size_t i = 0; i < n; i++)
        o->sx[i] = 1.0;
    start_point(o, m0, r0, x);
    /* bounds, names; states unbounded */
    for (size_t p = 0; p < o->np; p++) {
        oc_ph *ph = &o->ph[p];
        const char *pn = d->phases[ph->k].name;
        for (size_t j = 0; j < ph->ns; j++)
            for (size_t i = 0; i < ph->nx; i++) {
                const size_t v = ph->ix + j * ph->nx + i;
                o->zl[v] = -OC_INF, o->zu[v] = OC_INF;
                snprintf(o->vname[v], sizeof o->vname[0], "phase '%.30s' segment %zu state '%.20s'",
                         pn, j + 1, ph->xname[i]);
            }
        for (size_t a = 0; a < ph->nn; a++)
            for (size_t c = 0; c < ph->nu; c++) {
                const size_t v = ph->iu + a * ph->nu + c;
                const lv_ocp_ctrl_def *u = &ph->def->ctrl[c];
                o->sx[v] = u->hi - u->lo;
                o->zl[v] = u->lo / o->sx[v];
                o->zu[v] = u->hi / o->sx[v];
                snprintf(o->vname[v], sizeof o->vname[0], "phase '%.30s' node %zu control '%.20s'",
                         pn, a + 1, u->name);
            }
        if (ph->iD >= 0) {
            const size_t v = (size_t)ph->iD;
            o->sx[v] = ph->def->dur_hi - ph->def->dur_lo;
            o->zl[v] = ph->def->dur_lo / o->sx[v];
            o->zu[v] = ph->def->dur_hi / o->sx[v];
            snprintf(o->vname[v], sizeof o->vname[0], "phase '%.30s' duration", pn);
        }
    }
    for (size_t v = 0; v < n; v++)
        o->z_base[v] = x[v] / o->sx[v];
    free(x);
    /* rows: links and defects 0; paths and finals as the constraints say */
    for (size_t c = 0; c < od->n_cons; c++) {
        const lv_tcon_def *cd = &od->cons[c];
        const double lo = cd->kind == LV_CON_MAX ? -OC_INF : 0.0;
        const double hi = cd->kind == LV_CON_MIN ? OC_INF : 0.0;
        if (!cd->path) {
            o->gl[o->r_fin + c] = lo, o->gu[o->r_fin + c] = hi;
            continue;
        }
        const oc_ph *ph = &o->ph[o->opt_of[cd->res.phase]];
        for (size_t q = 0; q < ph->n_path; q++)
            if (ph->path_con[q] == c)
                for (size_t j = 0; j <= ph->ns; j++) {
                    o->gl[ph->r_path + q * (ph->ns + 1) + j] = lo;
                    o->gu[ph->r_path + q * (ph->ns + 1) + j] = hi;
                }
    }
    for (size_t p = 0; p < o->np; p++)
        if (o->ph[p].r_mass != (size_t)-1)
            o->gl[o->ph[p].r_mass] = 0.0, o->gu[o->ph[p].r_mass] = OC_INF;
    /* the start point's states: each segment from where the one before ended */
    o->cost_sign = od->cost.present && od->cost.maximize ? -1.0 : 1.0;
    o->cost_scale = 1.0;
    if ((st = worker_init(o, &o->w[0], err)) != LV_OK)
        goto fail;
    /* worker_init loaded a second copy; the section lives in it from here */
    o->def = o->w[0].m->def->ocp;
    for (size_t p = 0; p < o->np; p++)
        for (size_t j = 0; j < o->def->n_phases; j++)
            if (o->def->phases[j].phase == o->ph[p].k)
                o->ph[p].def = &o->def->phases[j];
    if (!oc_evaluate(o, &o->w[0], o->z_base, o->g_base, 1)) {
        st = lv_fail(err, LV_ERR_INPUT, "%s: the start point: %s", path, o->w[0].why);
        goto fail;
    }
    /* state scales: how much each state varies along the start point (an ECI position's
     * magnitude is the planet's radius, its change the trajectory's), at least its nominal */
    for (size_t p = 0; p < o->np; p++) {
        oc_ph *ph = &o->ph[p];
        for (size_t i = 0; i < ph->nx; i++) {
            double lo = INFINITY, hi = -INFINITY;
            for (size_t j = 0; j < ph->ns; j++) {
                lo = fmin(lo, o->z_base[ph->ix + j * ph->nx + i]);
                hi = fmax(hi, o->z_base[ph->ix + j * ph->nx + i]);
            }
            ph->xs[i] = fmax(ph->xs[i], hi - lo);
            for (size_t j = 0; j < ph->ns; j++) {
                const size_t v = ph->ix + j * ph->nx + i;
                o->z_base[v] /= ph->xs[i];
                o->sx[v] = ph->xs[i];
            }
        }
    }
    if (od->cost.present) {
        const double c0 = o->g_base[m] * o->cost_sign; /* the cost's value at scale 1 */
        o->cost_start = c0;
        o->cost_scale = !isnan(od->cost.scale) ? od->cost.scale
                        : fabs(c0) > 0.0       ? fabs(c0)
                                               : 1.0;
    } else {
        o->cost_start = NAN;
    }
    if (!oc_evaluate_base(o)) {
        st = lv_fail(err, LV_ERR_INPUT, "%s: the start point: %s", path, o->w[0].why);
        goto fail;
    }
    o->base_ok = 1;
    memcpy(o->z_best, o->z_base, n * sizeof *o->z_best);
    if ((st = build_pattern(o, d, err)) != LV_OK)
        goto fail;
    o->n_workers = 1;
    lv_run_free(r0);
    lv_mission_free(m0);
    *out = o;
    return LV_OK;
fail:
    o->def = NULL;
    lv_ocp_free(o);
    lv_run_free(r0);
    lv_mission_free(m0);
    return st;
}

/* ---- the Jacobian: column groups on the workers ----------------------------------------------- */

/* The central-difference step in scaled units: the cube root of the segments' relative
 * tolerance, their noise (Gill, Murray & Wright, Practical Optimization, 1981, sec. 8.6.1: the
 * error h^2 f3 / 6 + eps / h is least near h = eps^(1/3)): 4.6e-4 at 1e-10. Forward differences'
 * truncation error h f2 / 2 held IPOPT's dual infeasibility at 2e-5 (the linear tangent: 500
 * iterations without convergence after the optimum was found at the 12th). */
static double fd_step(const lv_ocp *o)
{
    return cbrt(o->itol);
}

/* The pair of points z + a h, z + b h of variable v: (1, -1), or both inside a bound that the
 * central pair would cross (one-sided, of second order through z). */
static void fd_pair(const lv_ocp *o, size_t v, const double *z, double h, double *a, double *b)
{
    *a = 1.0, *b = -1.0;
    if (z[v] + h > o->zu[v])
        *a = -1.0, *b = -2.0;
    else if (z[v] - h < o->zl[v])
        *a = 2.0, *b = 1.0;
}

typedef struct jac_job {
    lv_ocp *o;
    const double *z;
    size_t next;          /* the next group to take */
    size_t n_fallback;    /* groups taken column by column (a moved point did not fly) */
    pthread_mutex_t lock;
    int failed;
    char why[LV_ERR_MSG_MAX];
} jac_job;

/* Column v's entries from the rows at z + a h (ga) and z + b h (gb) about the base: the
 * parabola f0 + d s + c s^2 through s = a h and b h has d = (fa b^2 - fb a^2) / (a b (b - a)
 * h); (1, -1) is the central difference (fa - fb) / 2h. gb NULL: the first-order fa / (a h). */
static void column_from(lv_ocp *o, size_t v, const double *ga, const double *gb, double a,
                        double b, double h)
{
    for (size_t q = o->jc[v]; q < o->jc[v + 1]; q++) {
        const double f0 = o->g_base[o->jr[q]], fa = ga[o->jr[q]] - f0;
        if (gb == NULL) {
            o->jv[q] = fa / (a * h);
            continue;
        }
        const double fb = gb[o->jr[q]] - f0;
        o->jv[q] = a == 1.0 && b == -1.0 ? (fa - fb) / (2.0 * h)
                                         : (fa * b * b - fb * a * a) / (a * b * (b - a) * h);
    }
}

/* The rows at z moved by `side` (0: a h, 1: b h) in the given columns (NULL: group g's). */
static int eval_moved(lv_ocp *o, oc_worker *w, const double *z, size_t g, const size_t *one,
                      int side, double h, double *out)
{
    memcpy(w->x, z, o->n * sizeof *w->x);
    const size_t e0 = one ? 0 : o->grp_start[g], e1 = one ? 1 : o->grp_start[g + 1];
    for (size_t e = e0; e < e1; e++) {
        const size_t v = one ? *one : o->grp_col[e];
        double a, b;
        fd_pair(o, v, z, h, &a, &b);
        w->x[v] += (side == 0 ? a : b) * h;
    }
    return oc_evaluate(o, w, w->x, out, 0);
}

static void *jac_worker(void *arg)
{
    jac_job *jj = ((void **)arg)[0];
    oc_worker *w = ((void **)arg)[1];
    lv_ocp *o = jj->o;
    w->book = OC_BOOK_USE;
    for (;;) {
        pthread_mutex_lock(&jj->lock);
        const size_t g = jj->next++;
        const int stop = jj->failed || (o->set && o->set->stop && *o->set->stop);
        pthread_mutex_unlock(&jj->lock);
        if (g >= o->n_groups || stop)
            break;
        const double h = fd_step(o);
        if (eval_moved(o, w, jj->z, g, NULL, 0, h, w->g) &&
            eval_moved(o, w, jj->z, g, NULL, 1, h, w->g2)) {
            for (size_t e = o->grp_start[g]; e < o->grp_start[g + 1]; e++) {
                double a, b;
                fd_pair(o, o->grp_col[e], jj->z, h, &a, &b);
                column_from(o, o->grp_col[e], w->g, w->g2, a, b, h);
            }
            continue;
        }
        /* a moved point did not fly (a domain guard, an event ending a segment early): the
         * group's columns one by one, the pair, else the side that flies (first order), else
         * a zero column (its variable then moves on the cost and the other rows' say) */
        pthread_mutex_lock(&jj->lock);
        if (jj->n_fallback++ == 0)
            snprintf(jj->why, sizeof jj->why, "a difference step did not fly: %.900s", w->why);
        pthread_mutex_unlock(&jj->lock);
        for (size_t e = o->grp_start[g]; e < o->grp_start[g + 1]; e++) {
            const size_t v = o->grp_col[e];
            double a, b;
            fd_pair(o, v, jj->z, h, &a, &b);
            const int ok_a = eval_moved(o, w, jj->z, g, &v, 0, h, w->g);
            const int ok_b = eval_moved(o, w, jj->z, g, &v, 1, h, w->g2);
            if (ok_a && ok_b)
                column_from(o, v, w->g, w->g2, a, b, h);
            else if (ok_a || ok_b)
                column_from(o, v, ok_a ? w->g : w->g2, NULL, ok_a ? a : b, 0.0, h);
            else
                for (size_t q = o->jc[v]; q < o->jc[v + 1]; q++)
                    o->jv[q] = 0.0;
        }
    }
    w->book = OC_BOOK_OWN;
    return NULL;
}

static int ensure_base(lv_ocp *o, const double *z)
{
    if (o->base_ok && memcmp(z, o->z_base, o->n * sizeof *z) == 0)
        return 1;
    const double t = wall_now();
    memcpy(o->z_base, z, o->n * sizeof *z);
    o->base_ok = oc_evaluate_base(o);
    if (!o->base_ok)
        snprintf(o->res.last_failure, sizeof o->res.last_failure, "%.500s", o->w[0].why);
    o->evaluations++;
    o->res.wall_eval += wall_now() - t;
    o->jac_ok = 0;
    return o->base_ok;
}

static int ensure_jac(lv_ocp *o, const double *z)
{
    if (!ensure_base(o, z))
        return 0;
    if (o->jac_ok && memcmp(z, o->z_jac, o->n * sizeof *z) == 0)
        return 1;
    const double t = wall_now();
    jac_job jj = {.o = o, .z = o->z_base};
    pthread_mutex_init(&jj.lock, NULL);
    pthread_t th[OC_MAX_WORKERS];
    void *args[OC_MAX_WORKERS][2];
    int started[OC_MAX_WORKERS] = {0};
    for (int i = 1; i < o->n_workers; i++) {
        args[i][0] = &jj, args[i][1] = &o->w[i];
        started[i] = pthread_create(&th[i], NULL, jac_worker, args[i]) == 0;
    }
    /* the main thread works too, on a worker of its own (w[0] keeps the base point's run) */
    args[0][0] = &jj, args[0][1] = &o->w[o->n_workers];
    jac_worker(args[0]);
    for (int i = 1; i < o->n_workers; i++)
        if (started[i])
            pthread_join(th[i], NULL);
    pthread_mutex_destroy(&jj.lock);
    o->evaluations += 2 * (long)o->n_groups;
    o->res.wall_jac += wall_now() - t;
    if (jj.n_fallback > 0)
        snprintf(o->res.last_failure, sizeof o->res.last_failure, "%.500s", jj.why);
    if (jj.failed)
        return 0;
    memcpy(o->z_jac, z, o->n * sizeof *z);
    o->jac_ok = 1;
    return 1;
}

/* 1 when row r is a path row (of some phase). */
static int is_path_row(const lv_ocp *o, size_t r)
{
    for (size_t p = 0; p < o->np; p++) {
        const oc_ph *ph = &o->ph[p];
        if (r >= ph->r_path && r < ph->r_path + ph->n_path * (ph->ns + 1))
            return 1;
    }
    return 0;
}

/* A row's violation in units of its scale (0 when met). */
static double row_violation(const lv_ocp *o, size_t r, double g)
{
    return fmax(0.0, fmax(o->gl[r] - g, g - o->gu[r]));
}

/* 1 when row r is violated: a final or path row beyond its tolerance (1), a defect or link
 * beyond OC_DEFECT_VIOLATED of its state's scale. */
static int row_is_violated(const lv_ocp *o, size_t r, double viol)
{
    return viol > (r >= o->r_fin || is_path_row(o, r) ? 1.0 : OC_DEFECT_VIOLATED);
}

/* ---- IPOPT's callbacks --------------------------------------------------------------------------- */

static Bool cb_f(Index n, Number *x, Bool new_x, Number *f, UserDataPtr u)
{
    (void)n, (void)new_x;
    lv_ocp *o = u;
    if (!ensure_base(o, x))
        return FALSE;
    *f = o->def->cost.present ? o->g_base[o->m] : 0.0;
    return TRUE;
}

static Bool cb_grad_f(Index n, Number *x, Bool new_x, Number *grad, UserDataPtr u)
{
    (void)new_x;
    lv_ocp *o = u;
    for (Index i = 0; i < n; i++)
        grad[i] = 0.0;
    if (!o->def->cost.present)
        return TRUE;
    if (!ensure_jac(o, x))
        return FALSE;
    for (size_t v = 0; v < o->n; v++)
        if (o->jc[v + 1] > o->jc[v] && o->jr[o->jc[v + 1] - 1] == o->m)
            grad[v] = o->jv[o->jc[v + 1] - 1];
    return TRUE;
}

static Bool cb_g(Index n, Number *x, Bool new_x, Index m, Number *g, UserDataPtr u)
{
    (void)n, (void)new_x;
    lv_ocp *o = u;
    if (!ensure_base(o, x))
        return FALSE;
    memcpy(g, o->g_base, (size_t)m * sizeof *g);
    return TRUE;
}

static Bool cb_jac(Index n, Number *x, Bool new_x, Index m, Index nele, Index *ir, Index *jc,
                   Number *val, UserDataPtr u)
{
    (void)n, (void)new_x, (void)m, (void)nele;
    lv_ocp *o = u;
    size_t e = 0;
    if (val == NULL) {
        for (size_t v = 0; v < o->n; v++)
            for (size_t q = o->jc[v]; q < o->jc[v + 1]; q++)
                if (o->jr[q] < o->m) {
                    ir[e] = (Index)o->jr[q];
                    jc[e++] = (Index)v;
                }
        return TRUE;
    }
    if (!ensure_jac(o, x))
        return FALSE;
    for (size_t v = 0; v < o->n; v++)
        for (size_t q = o->jc[v]; q < o->jc[v + 1]; q++)
            if (o->jr[q] < o->m)
                val[e++] = o->jv[q];
    return TRUE;
}

static Bool cb_h(Index n, Number *x, Bool new_x, Number obj_factor, Index m, Number *lambda,
                 Bool new_lambda, Index nele, Index *ir, Index *jc, Number *val, UserDataPtr u)
{
    (void)n, (void)x, (void)new_x, (void)obj_factor, (void)m, (void)lambda, (void)new_lambda;
    (void)nele, (void)ir, (void)jc, (void)val, (void)u;
    return FALSE; /* limited-memory quasi-Newton: never called */
}

static Bool cb_iter(Index mode, Index iter, Number obj, Number inf_pr, Number inf_du, Number mu,
                    Number d_norm, Number reg, Number alpha_du, Number alpha_pr, Index ls,
                    UserDataPtr u)
{
    (void)d_norm, (void)reg, (void)alpha_du, (void)ls;
    lv_ocp *o = u;
    o->iter_last = iter;
    /* the point to return if IPOPT does not converge: the feasible iterate (every row within
     * its threshold, row_is_violated) with the best cost, else the least violating one. The
     * iterate is the point last evaluated (IPOPT's accepted trial point). */
    if (mode == 0 && o->base_ok) {
        double worst = 0.0;
        int feasible = 1;
        for (size_t r = 0; r < o->m; r++) {
            const double v = row_violation(o, r, o->g_base[r]);
            feasible &= !row_is_violated(o, r, v);
            worst = fmax(worst, v);
        }
        const double cost = o->def->cost.present ? o->g_base[o->m] : 0.0;
        const int better = feasible ? !o->best_feasible || cost <= o->best_cost
                                    : !o->best_feasible && worst <= o->best_worst;
        if (better) {
            memcpy(o->z_best, o->z_base, o->n * sizeof *o->z_best);
            o->best_feasible = feasible;
            o->best_cost = cost;
            o->best_worst = worst;
        }
    }
    if (o->set->on_iteration != NULL) {
        long segs = 0;
        for (int i = 0; i <= o->n_workers; i++)
            segs += o->w[i].segments;
        const lv_ocp_iteration it = {
            .iteration = iter,
            .cost = o->def->cost.present ? obj * o->cost_scale * o->cost_sign : NAN,
            .inf_pr = inf_pr, .inf_du = inf_du, .mu = mu, .step = alpha_pr,
            .wall = wall_now() - o->t0_wall, .segments = segs, .restoration = mode == 1};
        if (o->set->on_iteration(&it, o->set->user) != 0)
            o->stopped = 1;
    }
    if (o->set->stop != NULL && *o->set->stop)
        o->stopped = 1;
    return o->stopped ? FALSE : TRUE;
}

static const char *ipopt_name(int s)
{
    switch (s) {
    case Solve_Succeeded: return "Solve_Succeeded";
    case Solved_To_Acceptable_Level: return "Solved_To_Acceptable_Level";
    case Infeasible_Problem_Detected: return "Infeasible_Problem_Detected";
    case Search_Direction_Becomes_Too_Small: return "Search_Direction_Becomes_Too_Small";
    case Diverging_Iterates: return "Diverging_Iterates";
    case User_Requested_Stop: return "User_Requested_Stop";
    case Feasible_Point_Found: return "Feasible_Point_Found";
    case Maximum_Iterations_Exceeded: return "Maximum_Iterations_Exceeded";
    case Restoration_Failed: return "Restoration_Failed";
    case Error_In_Step_Computation: return "Error_In_Step_Computation";
    case Maximum_CpuTime_Exceeded: return "Maximum_CpuTime_Exceeded";
    case Not_Enough_Degrees_Of_Freedom: return "Not_Enough_Degrees_Of_Freedom";
    case Invalid_Problem_Definition: return "Invalid_Problem_Definition";
    case Invalid_Option: return "Invalid_Option";
    case Invalid_Number_Detected: return "Invalid_Number_Detected";
    default: return "IPOPT_Error";
    }
}

/* What row r is, with its value at g (messages). */
static void row_name(const lv_ocp *o, size_t r, const double *g, char *buf, size_t cap)
{
    const lv_mission_def *d = o->w[0].m->def;
    for (size_t p = 0; p < o->np; p++) {
        const oc_ph *ph = &o->ph[p];
        const char *pn = d->phases[ph->k].name;
        if (r >= ph->r_link && r < ph->r_link + ph->nx) {
            snprintf(buf, cap, "link of phase '%s' to its start, state '%s': %.6g x its scale "
                     "%.6g", pn, ph->xname[r - ph->r_link], g[r], ph->xs[r - ph->r_link]);
            return;
        }
        if (r >= ph->r_def && r < ph->r_def + (ph->ns - 1) * ph->nx) {
            const size_t j = (r - ph->r_def) / ph->nx, i = (r - ph->r_def) % ph->nx;
            snprintf(buf, cap, "defect of phase '%s' at the end of segment %zu of %zu, state "
                     "'%s': %.6g x its scale %.6g", pn, j + 1, ph->ns, ph->xname[i], g[r],
                     ph->xs[i]);
            return;
        }
        if (r == ph->r_mass) {
            snprintf(buf, cap, "propellant of phase '%s': its final mass is %.6g kg below its "
                     "burning stage's burnout mass (more propellant burnt than it holds)", pn,
                     -g[r] * ph->xs[ph->im]);
            return;
        }
        if (r >= ph->r_path && r < ph->r_path + ph->n_path * (ph->ns + 1)) {
            const size_t q = (r - ph->r_path) / (ph->ns + 1), j = (r - ph->r_path) % (ph->ns + 1);
            const lv_tcon_def *c = &o->def->cons[ph->path_con[q]];
            snprintf(buf, cap, "path '%s' at node %zu of %zu: %.9g, %s %.9g, tolerance %.6g", c->name,
                     j + 1, ph->ns + 1, c->value + g[r] * c->tol,
                     c->kind == LV_CON_MIN ? "min" : "max", c->value, c->tol);
            return;
        }
    }
    const lv_tcon_def *c = &o->def->cons[r - o->r_fin];
    snprintf(buf, cap, "final '%s' = %.9g %s, %s %.9g, tolerance %.6g", c->name,
             c->value + g[r] * c->tol, c->res.unit,
             c->kind == LV_CON_EQUAL ? "equal" : c->kind == LV_CON_MIN ? "min" : "max", c->value,
             c->tol);
}

lv_status lv_ocp_solve(lv_ocp *o, const lv_ocp_settings *s, lv_ocp_result *res, lv_err *err)
{
    static const lv_ocp_settings dflt = {0};
    if (s == NULL)
        s = &dflt;
    memset(&o->res, 0, sizeof o->res);
    o->set = s;
    o->stopped = 0;
    o->evaluations = 0;
    o->iter_last = 0;
    o->best_feasible = 0;
    o->best_worst = INFINITY;
    o->best_cost = INFINITY;
    o->t0_wall = wall_now();
    const double cpu0 = cpu_now();
    const char *why = lv_ipopt_error();
    if (why != NULL)
        return lv_fail(err, LV_ERR_SOLVER, "IPOPT could not be loaded (%s): install Debian's "
                       "coinor-libipopt-dev (scripts/install-deps.sh)", why);
    int threads = s->threads > 0 ? s->threads : 2;
    if (threads > OC_MAX_WORKERS - 1)
        threads = OC_MAX_WORKERS - 1;
    if ((size_t)threads > o->n_groups)
        threads = (int)o->n_groups;
    if (threads < 1)
        threads = 1;
    lv_status st = LV_OK;
    for (int i = 1; i <= threads && st == LV_OK; i++)
        if (o->w[i].m == NULL)
            st = worker_init(o, &o->w[i], err);
    if (st != LV_OK)
        return st;
    o->n_workers = threads;
    for (int i = 0; i <= threads; i++)
        o->w[i].segments = 0;

    IpoptProblem nlp = CreateIpoptProblem((Index)o->n, o->zl, o->zu, (Index)o->m, o->gl, o->gu,
                                          (Index)o->nnz, 0, 0, cb_f, cb_g, cb_grad_f, cb_jac,
                                          cb_h);
    if (nlp == NULL)
        return lv_fail(err, LV_ERR_SOLVER, "IPOPT refused the problem (%zu variables, %zu "
                       "constraints)", o->n, o->m);
    const int max_iter = s->max_iterations > 0 ? s->max_iterations : o->def->max_iterations;
    AddIpoptStrOption(nlp, "hessian_approximation", "limited-memory");
    AddIpoptStrOption(nlp, "mu_strategy", "adaptive");
    AddIpoptIntOption(nlp, "print_level", s->print_level);
    AddIpoptStrOption(nlp, "sb", "yes"); /* no banner */
    AddIpoptIntOption(nlp, "max_iter", max_iter);
    AddIpoptNumOption(nlp, "tol", o->def->tolerance);
    AddIpoptNumOption(nlp, "constr_viol_tol", fmin(1e-8, o->def->tolerance));
    AddIpoptNumOption(nlp, "acceptable_tol", fmax(1e2 * o->def->tolerance, 1e-6));
    AddIpoptIntOption(nlp, "acceptable_iter", o->def->acceptable_iterations);
    AddIpoptNumOption(nlp, "bound_relax_factor", 0.0);
    SetIntermediateCallback(nlp, cb_iter);
    double *z = malloc(o->n * sizeof *z);
    double *g = malloc((o->m + 1) * sizeof *g);
    if (z == NULL || g == NULL) {
        free(z), free(g);
        FreeIpoptProblem(nlp);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    memcpy(z, o->z_best, o->n * sizeof *z);
    double obj = NAN;
    /* a problem without a cost whose start point meets every row is solved: its finals and
     * paths within their tolerances, its defects and links within IPOPT's constraint
     * tolerance (IPOPT would move it off towards the bounds' analytic centre) */
    int feasible = !o->def->cost.present && ensure_base(o, z);
    for (size_t r = 0; r < o->m && feasible; r++)
        feasible = row_violation(o, r, o->g_base[r]) <=
                   (r >= o->r_fin || is_path_row(o, r) ? 1.0 : fmin(1e-8, o->def->tolerance));
    const enum ApplicationReturnStatus rs =
        feasible ? Solve_Succeeded : IpoptSolve(nlp, z, NULL, &obj, NULL, NULL, NULL, o);
    if (feasible)
        o->iter_last = 0;
    FreeIpoptProblem(nlp);
    lv_ocp_result *rr = &o->res;
    rr->ipopt_status = (int)rs;
    snprintf(rr->ipopt_text, sizeof rr->ipopt_text, "%s", ipopt_name((int)rs));
    /* IPOPT's solution when it converged, else the best iterate (cb_iter) */
    if (rs == Solve_Succeeded || rs == Solved_To_Acceptable_Level)
        memcpy(o->z_best, z, o->n * sizeof *z);
    free(z);
    rr->outcome = o->stopped                      ? LV_OCP_STOPPED
                  : rs == Solve_Succeeded ||
                          rs == Solved_To_Acceptable_Level ? LV_OCP_OPTIMAL
                  : rs == Infeasible_Problem_Detected ? LV_OCP_INFEASIBLE
                                                      : LV_OCP_NOT_CONVERGED;
    rr->iterations = o->iter_last;
    rr->n_vars = o->n, rr->n_cons = o->m, rr->nnz_jac = o->nnz, rr->n_groups = o->n_groups;
    rr->cost_start = o->cost_start;
    /* the point returned, evaluated again */
    const int ok = ensure_base(o, o->z_best);
    memcpy(g, o->g_base, (o->m + 1) * sizeof *g);
    rr->cost = o->def->cost.present && ok ? g[o->m] * o->cost_scale * o->cost_sign : NAN;
    rr->max_violation = 0.0;
    rr->n_violated = 0;
    for (size_t r = 0; r < o->m && ok; r++) {
        const double v = row_violation(o, r, g[r]);
        rr->max_violation = fmax(rr->max_violation, v);
        rr->n_violated += row_is_violated(o, r, v);
    }
    if (!ok) {
        rr->max_violation = INFINITY;
        rr->outcome = rr->outcome == LV_OCP_OPTIMAL ? LV_OCP_NOT_CONVERGED : rr->outcome;
    }
    if (rr->outcome == LV_OCP_OPTIMAL && rr->n_violated > 0)
        rr->outcome = LV_OCP_NOT_CONVERGED; /* acceptable to IPOPT, not to the tolerances */
    free(g);
    for (int i = 0; i <= o->n_workers; i++)
        rr->segments += o->w[i].segments;
    rr->evaluations = o->evaluations;
    rr->wall = wall_now() - o->t0_wall;
    rr->cpu = cpu_now() - cpu0;
    o->solved = 1;
    if (res != NULL)
        *res = *rr;
    if (o->stopped)
        return lv_fail(err, LV_ERR_CANCELLED, "stopped after %d iterations", rr->iterations);
    return LV_OK;
}

typedef struct viol_ix {
    size_t r;
    double v;
} viol_ix;

static int viol_cmp(const void *a, const void *b)
{
    const double x = ((const viol_ix *)a)->v, y = ((const viol_ix *)b)->v;
    return x < y ? 1 : x > y ? -1 : 0;
}

lv_status lv_ocp_violation(const lv_ocp *o, size_t i, char *text, size_t cap, double *violation,
                           lv_err *err)
{
    viol_ix *vi = malloc((o->m + 1) * sizeof *vi);
    if (vi == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    size_t n = 0;
    for (size_t r = 0; r < o->m; r++) {
        const double v = row_violation(o, r, o->g_base[r]);
        if (row_is_violated(o, r, v))
            vi[n++] = (viol_ix){r, v};
    }
    qsort(vi, n, sizeof *vi, viol_cmp);
    if (i >= n) {
        free(vi);
        return lv_fail(err, LV_ERR_INPUT, "violation %zu: only %zu rows are violated", i, n);
    }
    row_name(o, vi[i].r, o->g_base, text, cap);
    if (violation != NULL)
        *violation = vi[i].v;
    free(vi);
    return LV_OK;
}

lv_status lv_ocp_phase_times(const lv_ocp *o, size_t k, double *t0, double *t1, lv_err *err)
{
    if (k >= o->n_phases || o->opt_of[k] < 0)
        return lv_fail(err, LV_ERR_INPUT, "phase %zu is not optimised", k);
    const lv_phase_result *r = lv_run_result(o->w[0].r, k);
    *t0 = r->t_start;
    *t1 = r->t_end;
    return LV_OK;
}
