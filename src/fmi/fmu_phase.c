/* fmu_phase.c - a mission's phase made ready to be an FMU's model (fmu_phase.h): the same
 * code at export and inside the FMU, so both compute the same start values. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "fmi/fmu_phase.h"

void lv_fmu_phase_close(lv_fmu_phase *fp)
{
    if (fp == NULL)
        return;
    lv_phase_call_free(fp->call);
    lv_run_free(fp->run);
    lv_mission_free(fp->mission);
    free(fp->x0);
    free(fp->p0);
    free(fp->is_input);
    free(fp->run_idx);
    memset(fp, 0, sizeof *fp);
}

lv_status lv_fmu_phase_start_values(const lv_model_def *d, void *inst, const lv_sim_settings *s,
                                    double *x, double *p, lv_err *err)
{
    for (size_t j = 0; j < d->n_params; j++)
        p[j] = d->params[j].start;
    for (int pass = 0; pass < 2; pass++) {
        for (size_t i = 0; i < s->n_initial; i++) {
            lv_var_kind kind;
            size_t idx;
            lv_status st = lv_model_find(d, s->initial_names[i], &kind, &idx, err);
            if (st != LV_OK)
                return st;
            if (pass == 0 && kind == LV_VAR_PARAMETER)
                p[idx] = s->initial_values[i];
            if (pass == 1 && kind == LV_VAR_STATE)
                x[idx] = s->initial_values[i];
        }
        if (pass == 0) {
            for (size_t i = 0; i < d->n_states; i++)
                x[i] = d->states[i].start;
            if (d->start != NULL && d->start(p, x, inst) != 0)
                return lv_fail(err, LV_ERR_INPUT, "model '%s': start values cannot be computed "
                               "from the parameters", d->name);
        }
    }
    for (size_t i = 0; i < d->n_states; i++)
        if (!isfinite(x[i]))
            return lv_fail(err, LV_ERR_INPUT, "model '%s': start value of '%s' is %g", d->name,
                           d->states[i].name, x[i]);
    return LV_OK;
}

/* The ancestors run where they are out of date (the hand-off), the phase prepared, its start
 * values and inputs. */
static lv_status prepare(lv_fmu_phase *fp, const char *path, const char *phase, lv_err *err)
{
    lv_status st = LV_OK;
    if (fp->parent >= 0) {
        /* the hand-off: the ancestors run (no files, no rows kept) to give the start state */
        const size_t n = lv_mission_phase_count(fp->mission);
        unsigned char *want = calloc(n, 1);
        if (want == NULL)
            return lv_fail(err, LV_ERR_NOMEM, "out of memory");
        want[fp->parent] = 1;
        lv_run_options opt = {0};
        opt.threads = 1;
        opt.no_rows = 1;
        opt.want = want;
        lv_err run_err;
        st = lv_run_execute(fp->run, &opt, &run_err);
        free(want);
        const lv_phase_result *pr = lv_run_result(fp->run, (size_t)fp->parent);
        if (pr == NULL || pr->state != LV_PHASE_DONE)
            return lv_fail(err, st != LV_OK ? st : LV_ERR_SOLVER,
                           "%s: phase '%s' starts from phase '%s', which did not complete: %s",
                           path, phase, lv_mission_phase_name(fp->mission, (size_t)fp->parent),
                           pr != NULL && pr->error[0] ? pr->error : run_err.msg);
    }
    if ((st = lv_run_prepare(fp->run, fp->k, &fp->call, err)) != LV_OK) {
        lv_fail_prefix(err, st, "%s: phase '%s'", path, phase);
        return st;
    }
    fp->def = lv_phase_call_model(fp->call);
    fp->inst = lv_phase_call_inst(fp->call);
    fp->s = lv_phase_call_settings(fp->call);
    fp->x0 = calloc(fp->def->n_states + 1, sizeof *fp->x0);
    fp->p0 = calloc(fp->def->n_params + 1, sizeof *fp->p0);
    fp->is_input = calloc(fp->def->n_params + 1, 1);
    if (fp->x0 == NULL || fp->p0 == NULL || fp->is_input == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    if ((st = lv_fmu_phase_start_values(fp->def, fp->inst, fp->s, fp->x0, fp->p0, err)) != LV_OK) {
        lv_fail_prefix(err, st, "%s: phase '%s'", path, phase);
        return st;
    }
    lv_fmu_phase_inputs(fp);
    return LV_OK;
}

lv_status lv_fmu_phase_open(const char *path, const char *phase, lv_fmu_phase *fp, lv_err *err)
{
    memset(fp, 0, sizeof *fp);
    lv_status st = lv_mission_load(path, &fp->mission, err);
    if (st != LV_OK)
        goto fail;
    if ((st = lv_mission_phase_find(fp->mission, phase, &fp->k, err)) != LV_OK) {
        char names[256] = "";
        size_t used = 0;
        for (size_t i = 0; i < lv_mission_phase_count(fp->mission) && used < sizeof names; i++) {
            int n = snprintf(names + used, sizeof names - used, "%s%s", i ? ", " : "",
                             lv_mission_phase_name(fp->mission, i));
            used += n > 0 ? (size_t)n : 0;
        }
        st = lv_fail(err, st, "%s: unknown phase '%s' (the phases: %s)", path, phase, names);
        goto fail;
    }
    if ((st = lv_run_create(fp->mission, &fp->run, err)) != LV_OK)
        goto fail;
    fp->parent = lv_mission_phase_parent(fp->mission, fp->k);
    if ((st = prepare(fp, path, phase, err)) != LV_OK)
        goto fail;
    return LV_OK;
fail:
    lv_fmu_phase_close(fp);
    return st;
}

lv_status lv_fmu_phase_reprepare(lv_fmu_phase *fp, lv_err *err)
{
    const lv_fmu_phase old = *fp;
    fp->call = NULL;
    fp->x0 = fp->p0 = NULL;
    fp->is_input = NULL;
    lv_status st = prepare(fp, "the mission", lv_mission_phase_name(fp->mission, fp->k), err);
    if (st == LV_OK) {
        /* the FMU's variables and arrays are the old model's: the new one must match */
        const lv_model_def *a = old.def, *b = fp->def;
        const size_t ia = old.inst != NULL ? a->inst_size : 0;
        const size_t ib = fp->inst != NULL ? b->inst_size : 0;
        if (a->n_states != b->n_states || a->n_params != b->n_params ||
            a->n_outputs != b->n_outputs || a->n_events != b->n_events ||
            a->n_domain != b->n_domain || old.s->n_stops != fp->s->n_stops || ia != ib)
            st = lv_fail(err, LV_ERR_INPUT, "phase '%s': the model prepared again has other "
                         "variables, events or ends than the FMU's", lv_mission_phase_name(
                             fp->mission, fp->k));
        /* the FMU's start time is fixed (its DefaultExperiment and the importer's setup): a
         * run parameter whose new value moves the hand-off is refused, not flown from another
         * time. The export leaves out the ones a small change moves (lv_fmu_phase_run_params);
         * a larger change can move others (a throttle limit that sets when a burn ends). */
        else if (old.s->start_time != fp->s->start_time)
            st = lv_fail(err, LV_ERR_INPUT, "phase '%s': with these parameters the phase starts "
                         "at t = %.9g s, not at the FMU's start time %.9g s: the parameters "
                         "that change when an earlier phase ends cannot be set in this FMU",
                         lv_mission_phase_name(fp->mission, fp->k), fp->s->start_time,
                         old.s->start_time);
    }
    const lv_fmu_phase *drop = &old;
    lv_fmu_phase failed;
    if (st != LV_OK) { /* the old model stays */
        failed = *fp;
        fp->call = old.call;
        fp->def = old.def;
        fp->inst = old.inst;
        fp->s = old.s;
        fp->x0 = old.x0;
        fp->p0 = old.p0;
        fp->is_input = old.is_input;
        fp->n_inputs = old.n_inputs;
        drop = &failed;
    }
    lv_phase_call_free(drop->call);
    free(drop->x0);
    free(drop->p0);
    free(drop->is_input);
    return st;
}

lv_status lv_fmu_phase_run_params(lv_fmu_phase *fp, lv_err *err)
{
    const lv_mission *m = fp->mission;
    const size_t np = lv_mission_param_count(m), nph = lv_mission_phase_count(m);
    const char *phase = lv_mission_phase_name(m, fp->k);
    fp->n_run = 0;
    free(fp->run_idx);
    fp->run_idx = calloc(np + 1, sizeof *fp->run_idx);
    unsigned char *want = calloc(nph + 1, 1);
    lv_run *r = NULL;
    lv_status st = LV_OK;
    if (fp->run_idx == NULL || want == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto out;
    }
    if ((st = lv_run_create(m, &r, err)) != LV_OK)
        goto out;
    want[fp->k] = 1;
    lv_run_options opt = {0};
    opt.threads = 1;
    opt.no_rows = 1;
    opt.want = want;
    lv_err run_err;
    lv_run_execute(r, &opt, &run_err);
    const lv_phase_result *pr = lv_run_result(r, fp->k);
    if (pr == NULL || pr->state != LV_PHASE_DONE)
        goto out; /* nothing to compare with: no run parameters */
    const double t0 = pr->t_start;
    for (size_t i = 0; i < np; i++) {
        lv_param_info pi;
        lv_mission_param_info(m, i, &pi);
        const char *dot = strrchr(pi.name, '.');
        const char *last = dot != NULL ? dot + 1 : pi.name;
        if (strstr(pi.name, ".integrator.") != NULL || strcmp(last, "start_time") == 0)
            continue;
        /* the model's own variable (start_h of a root phase is its parameter) or an input */
        int model_param;
        lv_var_kind kind;
        size_t idx;
        model_param = lv_model_find(fp->def, pi.name, &kind, &idx, NULL) == LV_OK;
        char own[512];
        snprintf(own, sizeof own, "%s.inputs.", phase);
        if (model_param || strncmp(pi.name, own, strlen(own)) == 0)
            continue;
        const double v = lv_run_get_index(r, i);
        const double dv = fmax(1e-6 * fabs(v), 1e-9);
        if (lv_run_set_index(r, i, v + dv, NULL) != LV_OK &&
            lv_run_set_index(r, i, v - dv, NULL) != LV_OK)
            continue;
        const int stale = lv_run_stale(r, fp->k);
        int keep = stale;
        if (stale && fp->parent >= 0) {
            /* a parameter that moves the hand-off's time would move the FMU's start time,
             * which is the DefaultExperiment's: not offered */
            lv_run_execute(r, &opt, &run_err);
            const lv_phase_result *q = lv_run_result(r, fp->k);
            keep = q != NULL && q->state == LV_PHASE_DONE && q->t_start == t0;
        }
        lv_run_set_index(r, i, v, NULL);
        if (keep && fp->n_run < LV_FMU_MAX_RUN)
            fp->run_idx[fp->n_run++] = i;
        if (stale)
            lv_run_execute(r, &opt, &run_err);
    }
out:
    lv_run_free(r);
    free(want);
    return st;
}

void lv_fmu_phase_inputs(lv_fmu_phase *fp)
{
    const lv_model_def *d = fp->def;
    const size_t nx = d->n_states, np = d->n_params;
    const size_t isz = fp->inst != NULL ? d->inst_size : 0;
    fp->n_inputs = 0;
    double *p = malloc((np + 1) * sizeof *p), *xa = malloc((nx + 1) * sizeof *xa),
           *xb = malloc((nx + 1) * sizeof *xb);
    unsigned char *inst0 = malloc(isz + 1);
    if (p == NULL || xa == NULL || xb == NULL || inst0 == NULL)
        goto out;
    if (isz > 0)
        memcpy(inst0, fp->inst, isz);
    const double t0 = fp->s->start_time;
    const char *phase = lv_mission_phase_name(fp->mission, fp->k);
    /* the candidates: a run parameter "<phase>.inputs.P" exists */
    for (size_t j = 0; j < np; j++) {
        char slot[512];
        size_t i;
        int deg;
        snprintf(slot, sizeof slot, "%s.inputs.%s", phase, d->params[j].name);
        fp->is_input[j] = lv_mission_param_find(fp->mission, slot, &i, &deg, NULL) == LV_OK;
    }
    /* each candidate moved from a point where all are moved, so that one acting only beside
     * another (the bank angle mu at zero angle of attack and sideslip) shows; a step that
     * keeps a throttle within [0, 1] and an angle within its range */
    memcpy(p, fp->p0, np * sizeof *p);
    for (size_t j = 0; j < np; j++)
        if (fp->is_input[j])
            p[j] = fp->p0[j] > 0.5 ? fp->p0[j] - 1e-3 : fp->p0[j] + 1e-3;
    if ((d->init != NULL && d->init(t0, fp->x0, p, fp->inst) != 0) ||
        d->rhs(t0, fp->x0, p, xa, fp->inst) != 0) {
        memset(fp->is_input, 0, np);
        goto out;
    }
    for (size_t j = 0; j < np; j++) {
        if (!fp->is_input[j])
            continue;
        const double moved = p[j];
        p[j] = fp->p0[j];
        const int rc = d->rhs(t0, fp->x0, p, xb, fp->inst);
        p[j] = moved;
        fp->is_input[j] = rc == 0 && memcmp(xa, xb, nx * sizeof *xa) != 0;
        fp->n_inputs += fp->is_input[j];
    }
out:
    if (isz > 0 && inst0 != NULL)
        memcpy(fp->inst, inst0, isz);
    free(p);
    free(xa);
    free(xb);
    free(inst0);
}

