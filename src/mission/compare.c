/* compare.c - the paper's Table 2: a flat6 mission run sequentially (one small model per
 * phase) and as one end-to-end model carrying every stage from liftoff (lv_flat_e2e), with
 * the separations at the times the sequential phases split the stack; every body is compared
 * at the output times both runs share. */
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

/* Row of `r` at exactly time t that is not an event duplicate, or -1. */
static long row_at(const lv_result *r, size_t ct, double t, size_t *hint)
{
    size_t n = lv_result_rows(r);
    size_t i = *hint;
    while (i < n && lv_result_value(r, i, ct) < t)
        i++;
    *hint = i;
    if (i >= n || lv_result_value(r, i, ct) != t)
        return -1;
    if (i + 1 < n && lv_result_value(r, i + 1, ct) == t)
        return -1; /* an event instant: before/after rows, not comparable one to one */
    return (long)i;
}

lv_status lv_mission_compare(const lv_mission *m, const char *method, double tolerance,
                             double dt, lv_compare_report *rep, lv_err *err)
{
    memset(rep, 0, sizeof *rep);
    const lv_mission_def *d = m->def;
    lv_run *run = NULL;
    lv_flat_e2e *e2e = NULL;
    lv_result *rows = NULL;
    lv_sink mem = {0};
    lv_flat_stage *bodies = NULL;
    lv_flat_engine *engines = NULL;
    double *t_sep = NULL;
    lv_status st;
    const lv_phase_def *root = &d->phases[0];
    if (!(dt > 0.0) || !isfinite(dt)) {
        st = lv_fail(err, LV_ERR_INPUT, "compare: the output interval must be > 0 s (got %g)", dt);
        goto done;
    }
    if (d->env.world != LV_WORLD_FLAT || strcmp(root->type->name, "flat6") != 0 ||
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
    /* Same integrator settings on both sides. */
    lv_run_options opt = {.threads = 1, .output_interval = dt, .method = method,
                          .tolerance = tolerance};
    if ((st = lv_run_create(m, &run, err)) != LV_OK || (st = lv_run_execute(run, &opt, err)) != LV_OK)
        goto done;
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
    s.fixed_step = v[root->fixed_step];
    s.start_time = r0->t_start;
    s.stop_time = t_end;
    s.output_interval = dt;
    s.number_of_intervals = 0;
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
    if ((st = lv_sink_memory_create(&rows, &mem, err)) == LV_OK) {
        s.n_sinks = 1;
        s.sinks = &mem;
        lv_sim_report er;
        st = lv_simulate(md, lv_flat_e2e_inst(e2e), &s, NULL, &er, err);
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
    }
    free(names);
    free(values);
    if (st != LV_OK)
        goto done;

    /* Sequential totals. */
    snprintf(rep->seq.method, sizeof rep->seq.method, "%s", r0->method);
    rep->seq.tolerance = r0->tolerance;
    for (size_t k = 0; k < d->n_phases; k++) {
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

    /* Every body at the output times both runs share. */
    size_t ect;
    lv_result_column(rows, "time", &ect, NULL);
    size_t *ks = calloc(d->n_phases + 1, sizeof *ks);
    if (ks == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto done;
    }
    static const char *const pos[3] = {"x", "y", "z"}, *const vel[3] = {"vx", "vy", "vz"};
    rep->n_bodies = nb;
    for (size_t b = 0; b < nb && st == LV_OK; b++) {
        const size_t si = root->stages[b];
        lv_compare_body *cb = &rep->bodies[b];
        snprintf(cb->name, sizeof cb->name, "%s", d->stages[si].name);
        size_t ep[3], ev[3], em, hint = 0;
        char nm[160];
        for (int c = 0; c < 3; c++) {
            snprintf(nm, sizeof nm, "%s.%s", d->stages[si].name, pos[c]);
            lv_result_column(rows, nm, &ep[c], NULL);
            snprintf(nm, sizeof nm, "%s.%s", d->stages[si].name, vel[c]);
            lv_result_column(rows, nm, &ev[c], NULL);
        }
        snprintf(nm, sizeof nm, "%s.m", d->stages[si].name);
        lv_result_column(rows, nm, &em, NULL);
        lv_body_traj *bt = NULL;
        if ((st = lv_run_body_trajectory(run, si, &bt, err)) != LV_OK)
            break;
        size_t bm = 0;
        for (size_t c = 0; c < bt->n_cols; c++)
            if (strcmp(bt->names[c], "stage_mass") == 0)
                bm = c;
        size_t row_at_phase = 0; /* the body trajectory's rows follow the phases' rows */
        size_t nk = lv_run_body_phases(run, si, ks);
        for (size_t i = 0; i < nk; i++) {
            const lv_result *r = lv_run_rows(run, ks[i]);
            size_t ct, cp[3], cv[3];
            lv_result_column(r, "time", &ct, NULL);
            for (int c = 0; c < 3; c++) {
                lv_result_column(r, pos[c], &cp[c], NULL);
                lv_result_column(r, vel[c], &cv[c], NULL);
            }
            for (size_t row = 0; row < lv_result_rows(r); row++) {
                double t = lv_result_value(r, row, ct);
                if ((row + 1 < lv_result_rows(r) && lv_result_value(r, row + 1, ct) == t) ||
                    (row > 0 && lv_result_value(r, row - 1, ct) == t))
                    continue; /* event instant */
                if (hint > 0)
                    hint--;
                long er = row_at(rows, ect, t, &hint);
                if (er < 0)
                    continue;
                double dp = 0.0, dv = 0.0;
                for (int c = 0; c < 3; c++) {
                    double a = lv_result_value(r, row, cp[c]) - lv_result_value(rows, (size_t)er, ep[c]);
                    double w = lv_result_value(r, row, cv[c]) - lv_result_value(rows, (size_t)er, ev[c]);
                    dp += a * a;
                    dv += w * w;
                }
                double ms = bt->values[(row_at_phase + row) * bt->n_cols + bm];
                double dm = fabs(ms - lv_result_value(rows, (size_t)er, em));
                cb->max_dpos = fmax(cb->max_dpos, sqrt(dp));
                cb->max_dvel = fmax(cb->max_dvel, sqrt(dv));
                cb->max_dmass = fmax(cb->max_dmass, dm);
                cb->n_common++;
            }
            row_at_phase += lv_result_rows(r);
        }
        lv_body_traj_free(bt);
    }
    free(ks);
done:
    lv_sink_destroy(&mem);
    lv_result_free(rows);
    lv_flat_e2e_free(e2e);
    free(bodies);
    free(engines);
    free(t_sep);
    lv_run_free(run);
    return st;
}
