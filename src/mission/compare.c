/* compare.c - the paper's Table 2: a flat6 mission run sequentially (one small model per
 * phase) and as one end-to-end model carrying every stage from liftoff (lv_flat_e2e), with
 * the separations at the times the sequential phases split the stack; every body is compared
 * at every output time of its sequential phases (their grids start at each phase's start, so
 * they need not fall on one grid): the end-to-end run is advanced to each of those times in
 * turn (lv_sim_advance: the integrator's own interpolation, the same steps). Event instants
 * (two rows at one time) and the separation instants are left out. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "lvsim/lv_flat.h"
#include "lvsim/lv_mission.h"
#include "lvsim/lv_units.h"
#include "mission/mission_rt.h"
#include "mission/phase_type.h"

/* Separation time of body k from body k+1: the end of the phase that carries both and whose
 * children split them. */
static lv_status separation_time(const lv_run *run, size_t sk, size_t sk1, double *t,
                                 lv_err *err)
{
    const lv_mission_def *d = lv_run_mission(run)->def;
    for (size_t p = 0; p < d->n_phases; p++) {
        const lv_phase_def *ph = &d->phases[p];
        int a = 0, b = 0;
        for (size_t i = 0; i < ph->n_stages; i++) {
            a |= ph->stages[i] == sk;
            b |= ph->stages[i] == sk1;
        }
        if (!a || !b)
            continue;
        for (size_t c = 0; c < d->n_phases; c++) {
            const lv_phase_def *ch = &d->phases[c];
            if (ch->parent != (int)p)
                continue;
            int ca = 0, cb = 0;
            for (size_t i = 0; i < ch->n_stages; i++) {
                ca |= ch->stages[i] == sk;
                cb |= ch->stages[i] == sk1;
            }
            if (ca != cb) {
                *t = lv_run_result(run, p)->t_end;
                return LV_OK;
            }
        }
    }
    return lv_fail(err, LV_ERR_INPUT,
                   "mission '%s': no phase separates stage '%s' from '%s'; compare needs a "
                   "mission whose phases split the stack",
                   d->name, d->stages[sk].name, d->stages[sk1].name);
}

/* 1 when row `row` of `r` (time column ct) is one of an event instant's two rows. */
static int event_row(const lv_result *r, size_t row, size_t ct)
{
    const double t = lv_result_value(r, row, ct);
    return (row + 1 < lv_result_rows(r) && lv_result_value(r, row + 1, ct) == t) ||
           (row > 0 && lv_result_value(r, row - 1, ct) == t);
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The first failed phase's message, for an error that says more than "1 phase(s) failed". */
static lv_status run_failed(const lv_run *run, lv_status st, lv_err *err)
{
    const lv_mission_def *d = lv_run_mission(run)->def;
    for (size_t k = 0; k < d->n_phases; k++) {
        const lv_phase_result *res = lv_run_result(run, k);
        if (res->state == LV_PHASE_FAILED)
            return lv_fail(err, st, "compare: the sequential run failed: %.900s", res->error);
    }
    return lv_fail_prefix(err, st, "compare: the sequential run");
}

lv_status lv_mission_compare(const lv_mission *m, const char *method, double tolerance,
                             double dt, double max_rows, lv_compare_report *rep, lv_err *err)
{
    memset(rep, 0, sizeof *rep);
    const lv_mission_def *d = m->def;
    lv_run *run = NULL;
    lv_flat_e2e *e2e = NULL;
    lv_sim *sim = NULL;
    lv_flat_stage *bodies = NULL;
    lv_flat_engine *engines = NULL;
    double *t_sep = NULL, *times = NULL, *e2e_vals = NULL;
    size_t *ks = NULL;
    lv_status st;
    const lv_phase_def *root = &d->phases[0];
    if (!(dt > 0.0) || !isfinite(dt)) {
        st = lv_fail(err, LV_ERR_INPUT, "compare: the output interval must be > 0 s (got %g)", dt);
        goto done;
    }
    if (d->env.world != LV_WORLD_FLAT || root->type != &lv_phase_type_flat6 ||
        root->parent >= 0) {
        st = lv_fail(err, LV_ERR_INPUT, "compare: '%s' is not a flat-world (flat6) mission",
                     d->path);
        goto done;
    }
    /* The end-to-end model flies without air (lv_flat_e2e): no atmosphere, no wind, no drag. */
    if (d->env.atmosphere != NULL && strcmp(d->env.atmosphere, "none") != 0) {
        st = lv_fail(err, LV_ERR_INPUT, "compare: '%s' has an atmosphere (%s); the end-to-end "
                     "model has no air, so the two would not fly the same mission", d->path,
                     d->env.atmosphere);
        goto done;
    }
    if (!(max_rows >= 0.0)) {
        st = lv_fail(err, LV_ERR_INPUT, "compare: max_rows must be >= 0 (0: no limit), got %g",
                     max_rows);
        goto done;
    }
    /* Same integrator settings on both sides; the sequential rows are kept in memory: bounded
     * by max_rows before anything runs (lv_run_check_output) and as the phases run. */
    lv_run_options opt = {.threads = 1, .output_interval = dt, .method = method,
                          .tolerance = tolerance, .max_rows = max_rows};
    if ((st = lv_run_create(m, &run, err)) != LV_OK)
        goto done;
    if ((st = lv_run_execute(run, &opt, err)) != LV_OK) {
        if (st == LV_ERR_SOLVER || st == LV_ERR_NOMEM)
            st = run_failed(run, st, err);
        goto done;
    }
    const double *v = lv_run_vals(run);

    /* The end-to-end model: the root phase's stages as bodies, stacked. */
    const size_t nb = root->n_stages;
    if (nb > sizeof rep->bodies / sizeof rep->bodies[0]) {
        st = lv_fail(err, LV_ERR_INPUT, "compare: at most 8 bodies");
        goto done;
    }
    size_t n_eng = 0;
    for (size_t i = 0; i < nb; i++)
        n_eng += d->stages[root->stages[i]].n_engines;
    bodies = calloc(nb, sizeof *bodies);
    engines = calloc(n_eng + 1, sizeof *engines);
    t_sep = calloc(nb, sizeof *t_sep);
    if (!bodies || !engines || !t_sep) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto done;
    }
    size_t e0 = 0;
    double t_end = 0.0;
    for (size_t k = 0; k < d->n_phases; k++)
        t_end = fmax(t_end, lv_run_result(run, k)->t_end);
    for (size_t i = 0; i < nb; i++) {
        const lv_stage_def *sd = &d->stages[root->stages[i]];
        for (size_t e = 0; e < sd->n_engines; e++) {
            const lv_engine_def *ed = &sd->engines[e];
            const double thrust = ed->thrust_vac != LV_NO_SLOT ? v[ed->thrust_vac] : 0.0;
            double mdot = ed->mdot != LV_NO_SLOT ? v[ed->mdot] : 0.0;
            if (ed->table == NULL && !(mdot > 0.0) && ed->isp_vac != LV_NO_SLOT)
                mdot = thrust / (v[ed->isp_vac] * LV_G0);
            engines[e0 + e] = (lv_flat_engine){ed->table, ed->thrust_out, ed->mdot_out, thrust,
                                               mdot, ed->count};
        }
        bodies[i] = (lv_flat_stage){sd->name, v[sd->dry_mass], v[sd->propellant_mass],
                                    sd->n_engines, engines + e0};
        e0 += sd->n_engines;
        if (i + 1 < nb &&
            (st = separation_time(run, root->stages[i], root->stages[i + 1], &t_sep[i], err)) !=
                LV_OK)
            goto done;
    }
    lv_flat_e2e_config cfg = {"end_to_end", v[d->env.g], nb, bodies, t_sep};
    if ((st = lv_flat_e2e_create(&cfg, &e2e, err)) != LV_OK)
        goto done;
    /* the root phase's settings (the same method and tolerance as the sequential runs) */
    const lv_phase_result *r0 = lv_run_result(run, 0);
    lv_sim_settings s;
    lv_sim_settings_default(&s);
    s.result_file = NULL;
    s.method = r0->method;
    s.tolerance = r0->tolerance;
    s.start_time = r0->t_start;
    s.stop_time = t_end;
    /* no rows of its own: it is read at the sequential output times (a fixed step defaults
     * to the output interval dt, as the sequential phases' do) */
    s.fixed_step = v[root->fixed_step] > 0.0 ? v[root->fixed_step] : dt;
    s.output_interval = 0.0;
    s.number_of_intervals = 1;
    const lv_model_def *md = lv_flat_e2e_def(e2e);
    /* the shared parameter set, as the root phase gets it */
    const char **names = calloc(d->n_params + 2, sizeof *names);
    double *values = calloc(d->n_params + 2, sizeof *values);
    if (!names || !values) {
        free(names);
        free(values);
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto done;
    }
    size_t n = 0;
    names[n] = "g";
    values[n++] = v[d->env.g];
    for (size_t j = 0; j < d->n_params; j++) {
        lv_var_kind kind;
        size_t idx;
        if (lv_model_find(md, d->param_names[j], &kind, &idx, NULL) == LV_OK) {
            names[n] = d->param_names[j];
            values[n++] = v[d->param_values[j]];
        }
    }
    s.n_initial = n;
    s.initial_names = names;
    s.initial_values = values;
    /* The times to compare at: every output time of the bodies' sequential phases, but
     * event instants and the separations (the end-to-end model's own events). */
    const size_t nph = d->n_phases;
    size_t n_times = 0, cap = 0;
    ks = calloc(nph + 1, sizeof *ks);
    if (ks == NULL)
        goto nomem;
    for (size_t k = 0; k < nph; k++)
        cap += lv_result_rows(lv_run_rows(run, k));
    times = malloc((cap + 1) * sizeof *times);
    if (times == NULL)
        goto nomem;
    for (size_t k = 0; k < nph; k++) {
        const lv_result *r = lv_run_rows(run, k);
        size_t ct;
        lv_result_column(r, "time", &ct, NULL);
        for (size_t row = 0; row < lv_result_rows(r); row++) {
            const double tr = lv_result_value(r, row, ct);
            int sep = 0;
            for (size_t b = 0; b + 1 < nb; b++)
                sep |= tr == t_sep[b];
            if (!event_row(r, row, ct) && !sep)
                times[n_times++] = tr;
        }
    }
    qsort(times, n_times, sizeof *times, cmp_double);
    size_t n_u = 0;
    for (size_t i = 0; i < n_times; i++)
        if (n_u == 0 || times[i] != times[n_u - 1])
            times[n_u++] = times[i];
    n_times = n_u;

    /* The end-to-end run advanced to each of them: every body's position, velocity, mass. */
    static const char *const col[7] = {"x", "y", "z", "vx", "vy", "vz", "m"};
    lv_vref refs[8 * 7];
    for (size_t b = 0; b < nb; b++)
        for (int c = 0; c < 7; c++) {
            char nm[96];
            snprintf(nm, sizeof nm, "%s.%s", d->stages[root->stages[b]].name, col[c]);
            if ((st = lv_model_vref(md, nm, &refs[b * 7 + (size_t)c], err)) != LV_OK) {
                free(names);
                free(values);
                goto done;
            }
        }
    const size_t nref = nb * 7;
    e2e_vals = malloc((n_times + 1) * nref * sizeof *e2e_vals);
    if (e2e_vals == NULL) {
        free(names);
        free(values);
        goto nomem;
    }
    st = lv_sim_create(md, lv_flat_e2e_inst(e2e), &s, &sim, err);
    for (size_t i = 0; st == LV_OK && i < n_times; i++) {
        if (times[i] < s.start_time)
            continue;
        if ((st = lv_sim_advance(sim, times[i], err)) != LV_OK)
            break;
        if (lv_sim_time(sim) != times[i]) {
            st = lv_fail(err, LV_ERR_SOLVER, "compare: the end-to-end run ended at t = %.9g s, "
                         "before the sequential output time %.9g s", lv_sim_time(sim),
                         times[i]);
            break;
        }
        st = lv_sim_get(sim, refs, nref, e2e_vals + i * nref, err);
    }
    if (st == LV_OK)
        st = lv_sim_advance(sim, s.stop_time, err); /* the whole run, for its statistics */
    lv_sim_report er;
    memset(&er, 0, sizeof er);
    if (sim != NULL) {
        lv_err ferr;
        const lv_status fst = lv_sim_finish(sim, NULL, &er, st == LV_OK ? err : &ferr);
        if (st == LV_OK)
            st = fst;
    }
    lv_compare_side *e = &rep->e2e;
    snprintf(e->method, sizeof e->method, "%s", s.method);
    e->tolerance = s.tolerance;
    e->n_states = md->n_states;
    e->state_events = er.stats.state_events;
    e->time_events = er.stats.time_events;
    e->steps = er.stats.steps;
    e->rhs_evals = er.stats.rhs_evals;
    e->rhs_evals_steps = er.stats.rhs_evals_steps;
    e->rhs_evals_output = er.stats.rhs_evals_output;
    e->jac_evals = er.stats.jac_evals;
    e->cpu_time = er.stats.cpu_time;
    lv_sim_report_clear(&er);
    free(names);
    free(values);
    if (st != LV_OK) {
        lv_fail_prefix(err, st, "compare: the end-to-end run");
        goto done;
    }

    /* Sequential totals. */
    snprintf(rep->seq.method, sizeof rep->seq.method, "%s", r0->method);
    rep->seq.tolerance = r0->tolerance;
    for (size_t k = 0; k < nph; k++) {
        const lv_sim_report *r = &lv_run_result(run, k)->report;
        if (r->n_states > rep->seq.n_states)
            rep->seq.n_states = r->n_states;
        rep->seq.state_events += r->stats.state_events;
        rep->seq.time_events += r->stats.time_events;
        rep->seq.steps += r->stats.steps;
        rep->seq.rhs_evals += r->stats.rhs_evals;
        rep->seq.rhs_evals_steps += r->stats.rhs_evals_steps;
        rep->seq.rhs_evals_output += r->stats.rhs_evals_output;
        rep->seq.jac_evals += r->stats.jac_evals;
        rep->seq.cpu_time += r->stats.cpu_time;
    }

    /* Every body at every output time of its sequential phases. */
    rep->n_bodies = nb;
    for (size_t b = 0; b < nb && st == LV_OK; b++) {
        const size_t si = root->stages[b];
        lv_compare_body *cb = &rep->bodies[b];
        snprintf(cb->name, sizeof cb->name, "%s", d->stages[si].name);
        lv_body_traj *bt = NULL;
        if ((st = lv_run_body_trajectory(run, si, &bt, err)) != LV_OK)
            break;
        size_t bm = 0;
        for (size_t c = 0; c < bt->n_cols; c++)
            if (strcmp(bt->names[c], "stage_mass") == 0)
                bm = c;
        size_t row_at_phase = 0; /* the body trajectory's rows follow the phases' rows */
        const size_t nk = lv_run_body_phases(run, si, ks);
        for (size_t i = 0; i < nk; i++) {
            const lv_result *r = lv_run_rows(run, ks[i]);
            size_t ct, cr[6];
            lv_result_column(r, "time", &ct, NULL);
            for (int c = 0; c < 6; c++)
                lv_result_column(r, col[c], &cr[c], NULL);
            for (size_t row = 0; row < lv_result_rows(r); row++) {
                const double tr = lv_result_value(r, row, ct);
                const double *hit = event_row(r, row, ct) ? NULL
                                    : bsearch(&tr, times, n_times, sizeof *times, cmp_double);
                if (hit == NULL || tr < s.start_time)
                    continue; /* an event instant or a separation */
                const double *ev = e2e_vals + (size_t)(hit - times) * nref + b * 7;
                double dp = 0.0, dv = 0.0;
                for (int c = 0; c < 3; c++) {
                    const double a = lv_result_value(r, row, cr[c]) - ev[c];
                    const double w = lv_result_value(r, row, cr[3 + c]) - ev[3 + c];
                    dp += a * a;
                    dv += w * w;
                }
                const double ms = bt->values[(row_at_phase + row) * bt->n_cols + bm];
                cb->max_dpos = fmax(cb->max_dpos, sqrt(dp));
                cb->max_dvel = fmax(cb->max_dvel, sqrt(dv));
                cb->max_dmass = fmax(cb->max_dmass, fabs(ms - ev[6]));
                cb->n_common++;
            }
            row_at_phase += lv_result_rows(r);
        }
        lv_body_traj_free(bt);
    }
    goto done;
nomem:
    st = lv_fail(err, LV_ERR_NOMEM, "compare: out of memory");
done:
    lv_sim_free(sim);
    lv_flat_e2e_free(e2e);
    free(bodies);
    free(engines);
    free(t_sep);
    free(times);
    free(e2e_vals);
    free(ks);
    lv_run_free(run);
    return st;
}
