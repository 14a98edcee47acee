/* summary.c - after a run (post-processing, liblvsim_post): summary.json (per phase: times, why it ended, events, statistics,
 * the hand-off, final state; per body: its phases and merged trajectory) and one merged CSV
 * trajectory per body across the phases it flies in. Written from the public API of a run
 * (lv_mission.h) only; JSON is built with cJSON. docs/result-files.md. */
#define _POSIX_C_SOURCE 200809L

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "core/utc.h"
#include "io/atomic.h"
#include "io/numfmt.h"
#include "lvsim/lv_mission.h"
#include "lvsim/lv_summary.h"
#include "lvsim/lvsim.h"
#include "post/json_print.h"

/* Name of state event `index` of a phase's model (recorded when the phase ran). */
static const char *event_name(const lv_phase_result *r, int index)
{
    return index >= 0 && (size_t)index < r->n_event_names ? r->event_names[index] : "event";
}

/* reference_<k>_<phase>.csv: the rows of phase k compared with its reference
 * (lv_run_reference_rows): the simulation's and the reference's h, v, m and the differences;
 * named in the phase's summary block `pj` as reference.file. Nothing without such rows. */
static lv_status write_reference_csv(const lv_run *run, size_t k, const char *outdir, cJSON *pj,
                                     lv_err *err)
{
    const lv_ref_row *rows;
    size_t n;
    cJSON *rj = cJSON_GetObjectItemCaseSensitive(pj, "reference");
    if (rj == NULL || lv_run_reference_rows(run, k, &rows, &n, NULL) != LV_OK || n == 0)
        return LV_OK;
    char file[512], path[4700];
    snprintf(file, sizeof file, "reference_%zu_%s.csv", k + 1,
             lv_mission_phase_name(lv_run_mission(run), k));
    snprintf(path, sizeof path, "%s/%s", outdir, file);
    lv_atomic out;
    lv_status st = lv_atomic_open(&out, path, err);
    if (st != LV_OK)
        return st;
    fputs("time [s],h [m],h_ref [m],v_rel [m/s],v_ref [m/s],m [kg],m_ref [kg],d_position [m],"
          "d_velocity [m/s],d_mass [kg]\n", out.fp);
    char line[10 * LV_NUMFMT_MAX + 16];
    for (size_t i = 0; i < n; i++) {
        const lv_ref_row *w = &rows[i];
        const double v[10] = {w->t, w->h, w->h_ref, w->v, w->v_ref, w->m, w->m_ref, w->d_pos,
                              w->d_vel, w->d_mass};
        char *p = line;
        for (int c = 0; c < 10; c++) {
            if (c > 0)
                *p++ = ',';
            p += lv_numfmt_double(v[c], p);
        }
        *p++ = '\n';
        fwrite(line, 1, (size_t)(p - line), out.fp);
    }
    if ((st = lv_atomic_commit(&out, err)) == LV_OK)
        cJSON_AddStringToObject(rj, "file", file);
    return st;
}

/* body_<stage>.csv: time, the phase, the merged trajectory's columns. */
static lv_status write_body_csv(const lv_run *run, size_t s, const char *path, lv_err *err)
{
    const lv_mission *m = lv_run_mission(run);
    lv_body_traj *b = NULL;
    lv_status st = lv_run_body_trajectory(run, s, &b, err);
    if (st != LV_OK)
        return st;
    lv_atomic out;
    if ((st = lv_atomic_open(&out, path, err)) != LV_OK) {
        lv_body_traj_free(b);
        return st;
    }
    FILE *f = out.fp;
    fprintf(f, "time [s],phase");
    for (size_t c = 1; c < b->n_cols; c++)
        fprintf(f, ",%s [%s]", b->names[c], b->units[c][0] ? b->units[c] : "1"); /* "1": lv_units.h */
    fputc('\n', f);
    /* numbers as the result CSVs write them: the shortest text that reads back exactly */
    char *line = malloc(b->n_cols * LV_NUMFMT_MAX + 1);
    if (line == NULL) {
        lv_atomic_abort(&out);
        lv_body_traj_free(b);
        return lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", path);
    }
    for (size_t i = 0; i < b->n_rows; i++) {
        const double *row = b->values + i * b->n_cols;
        char *p = line + lv_numfmt_double(row[0], line);
        fputs(line, f);
        fputc(',', f);
        fputs(lv_mission_phase_name(m, b->phase[i]), f);
        p = line;
        for (size_t c = 1; c < b->n_cols; c++) {
            *p++ = ',';
            p += lv_numfmt_double(row[c], p);
        }
        *p++ = '\n';
        fwrite(line, 1, (size_t)(p - line), f);
    }
    free(line);
    lv_body_traj_free(b);
    return lv_atomic_commit(&out, err);
}

static cJSON *phase_json(const lv_run *run, size_t k)
{
    const lv_mission *m = lv_run_mission(run);
    lv_phase_info ph;
    lv_mission_phase_info(m, k, &ph);
    const lv_phase_result *r = lv_run_result(run, k);
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "index", (double)(k + 1));
    cJSON_AddNumberToObject(o, "file_index", (double)(ph.file_index + 1));
    cJSON_AddStringToObject(o, "name", ph.name);
    cJSON_AddStringToObject(o, "model", ph.model);
    cJSON *st = cJSON_AddArrayToObject(o, "stages");
    for (size_t i = 0; i < ph.n_stages; i++)
        cJSON_AddItemToArray(st, cJSON_CreateString(lv_mission_stage_name(m, ph.stages[i])));
    if (ph.parent >= 0)
        cJSON_AddStringToObject(o, "from", lv_mission_phase_name(m, (size_t)ph.parent));
    else
        cJSON_AddNullToObject(o, "from");
    cJSON_AddStringToObject(o, "state", lv_phase_state_name(r->state));
    if (r->state == LV_PHASE_FAILED || r->state == LV_PHASE_SKIPPED ||
        r->state == LV_PHASE_CRASHED)
        cJSON_AddStringToObject(o, "error", r->error);
    if (r->state == LV_PHASE_SKIPPED || r->state == LV_PHASE_PENDING)
        return o;
    cJSON_AddNumberToObject(o, "t_start", r->t_start);
    cJSON_AddNumberToObject(o, "t_end", r->t_end);

    const lv_sim_report *rep = &r->report;
    cJSON *end = cJSON_AddObjectToObject(o, "end");
    cJSON_AddStringToObject(end, "reason", r->state == LV_PHASE_CRASHED   ? "crashed"
                                           : rep->reason == LV_STOP_TIME  ? "stop_time"
                                           : rep->reason == LV_STOP_EVENT ? "event"
                                                                          : "failed");
    if (rep->reason == LV_STOP_EVENT && rep->stop_event >= 0) {
        cJSON_AddStringToObject(end, "event", event_name(r, rep->stop_event));
        if (!isnan(r->end_value))
            cJSON_AddNumberToObject(end, "value", r->end_value);
    } else if (rep->reason == LV_STOP_TIME && r->state != LV_PHASE_CRASHED) {
        cJSON_AddNumberToObject(end, "value", r->t_stop);
    }
    if (rep->reason == LV_STOP_EVENT && r->end_label != NULL) /* the user's name of it: MECO */
        cJSON_AddStringToObject(end, "label", r->end_label);
    cJSON *ev = cJSON_AddArrayToObject(o, "events");
    for (size_t i = 0; i < rep->n_event_log; i++) {
        const lv_event_record *e = &rep->event_log[i];
        cJSON *j = cJSON_CreateObject();
        cJSON_AddNumberToObject(j, "t", e->t);
        cJSON_AddStringToObject(j, "kind", e->is_state ? "state" : "time");
        /* a state event by its name, a time event by its source (table and breakpoint,
         * commanded action) as the model names it */
        cJSON_AddStringToObject(j, "name", e->is_state ? event_name(r, e->index)
                                           : e->name[0] ? e->name : "time event");
        if (e->is_state)
            cJSON_AddNumberToObject(j, "direction", e->direction);
        if (r->event_labels != NULL && r->event_labels[i] != NULL) /* `name:` in the file */
            cJSON_AddStringToObject(j, "label", r->event_labels[i]);
        cJSON_AddItemToArray(ev, j);
    }
    cJSON *sj = cJSON_AddObjectToObject(o, "stats");
    cJSON_AddNumberToObject(sj, "states", (double)rep->n_states);
    cJSON_AddNumberToObject(sj, "steps", (double)rep->stats.steps);
    cJSON_AddNumberToObject(sj, "rhs_evals", (double)rep->stats.rhs_evals);
    cJSON_AddNumberToObject(sj, "rhs_evals_steps", (double)rep->stats.rhs_evals_steps);
    cJSON_AddNumberToObject(sj, "rhs_evals_output", (double)rep->stats.rhs_evals_output);
    cJSON_AddNumberToObject(sj, "row_evals", (double)rep->stats.row_evals);
    cJSON_AddNumberToObject(sj, "jac_evals", (double)rep->stats.jac_evals);
    cJSON_AddNumberToObject(sj, "state_events", (double)rep->stats.state_events);
    cJSON_AddNumberToObject(sj, "time_events", (double)rep->stats.time_events);
    cJSON_AddNumberToObject(sj, "restarts", (double)rep->stats.restarts);
    cJSON_AddNumberToObject(sj, "rows", (double)rep->stats.output_rows);
    cJSON_AddNumberToObject(sj, "cpu_time", rep->stats.cpu_time);
    cJSON_AddStringToObject(sj, "method", r->method);
    cJSON_AddNumberToObject(sj, "tolerance", r->tolerance);

    cJSON *h = cJSON_AddObjectToObject(o, "handoff");
    cJSON_AddStringToObject(h, "from", ph.parent >= 0 ? lv_mission_phase_name(m, (size_t)ph.parent)
                                                       : "parameters");
    if (ph.parent >= 0) {
        lv_phase_info pp;
        lv_mission_phase_info(m, (size_t)ph.parent, &pp);
        if (strcmp(pp.model, ph.model) != 0) { /* a change of model (docs/models.md) */
            char tr[96];
            snprintf(tr, sizeof tr, "%s -> %s", pp.model, ph.model);
            cJSON_AddStringToObject(h, "transition", tr);
            if (ph.handoff_rule != NULL)
                cJSON_AddStringToObject(h, "rule", ph.handoff_rule);
        }
        cJSON_AddNumberToObject(h, "states_copied", (double)r->n_copied);
        cJSON_AddNumberToObject(h, "mass_from_stages", r->mass_from_stages);
        if (r->n_absorbed > 0) { /* what the hand-off absorbed (a touchdown's sink rate) */
            cJSON *ab = cJSON_AddObjectToObject(h, "absorbed");
            for (size_t i = 0; i < r->n_absorbed; i++)
                cJSON_AddNumberToObject(ab, r->absorbed_names[i], r->absorbed_values[i]);
        }
    }
    if (lv_mission_phase_has_reference(m, k)) { /* the drift from the optimiser's trajectory */
        cJSON *rj = cJSON_AddObjectToObject(o, "reference");
        lv_ref_drift d;
        if (lv_run_reference_drift(run, k, &d, NULL) == LV_OK) {
            cJSON_AddStringToObject(rj, "over", d.over_tau ? "tau" : "time");
            cJSON_AddStringToObject(rj, "start", d.start_from_reference ? "reference" : "parent");
            cJSON_AddNumberToObject(rj, "rows", (double)d.n_rows);
            if (d.n_rows > 0) {
                cJSON_AddNumberToObject(rj, "t_first", d.t_first);
                cJSON_AddNumberToObject(rj, "t_final", d.t_final);
                const char *const qn[3] = {"position", "velocity", "mass"};
                const double q[3][3] = {{d.pos_max, d.pos_max_t, d.pos_final},
                                        {d.vel_max, d.vel_max_t, d.vel_final},
                                        {d.mass_max, d.mass_max_t, d.mass_final}};
                for (int i = 0; i < 3; i++) {
                    cJSON *qj = cJSON_AddObjectToObject(rj, qn[i]);
                    cJSON_AddNumberToObject(qj, "max", q[i][0]);
                    cJSON_AddNumberToObject(qj, "t_max", q[i][1]);
                    cJSON_AddNumberToObject(qj, "final", q[i][2]);
                }
            }
            if (isfinite(d.ref_end) && isfinite(d.phase_end)) {
                cJSON *ej = cJSON_AddObjectToObject(rj, "end");
                cJSON_AddNumberToObject(ej, "reference", d.ref_end);
                cJSON_AddNumberToObject(ej, "phase", d.phase_end);
            }
        } else {
            cJSON_AddNullToObject(rj, "rows"); /* not run, or no rows kept */
        }
    }
    cJSON *ov = cJSON_AddObjectToObject(h, "overrides");
    for (size_t i = 0; i < r->n_set; i++)
        cJSON_AddNumberToObject(ov, r->set_names[i], r->set_values[i]);
    /* the propellant book of the phase's stages: the bottom one burns */
    cJSON *book = cJSON_AddObjectToObject(o, "propellant");
    for (size_t i = 0; i < ph.n_stages; i++) {
        const size_t si = ph.stages[i];
        cJSON *sj2 = cJSON_AddObjectToObject(book, lv_mission_stage_name(m, si));
        cJSON_AddNumberToObject(sj2, "dry_mass", r->dry_mass[si]);
        cJSON_AddNumberToObject(sj2, "start", r->propellant_start[si]);
        cJSON_AddNumberToObject(sj2, "end", r->propellant_end[si]);
        cJSON_AddBoolToObject(sj2, "burns", i == 0);
    }
    /* the stages' `geometry:` where the mission gives it (the CZML export's vehicle models) */
    cJSON *geo = NULL;
    for (size_t i = 0; i < ph.n_stages; i++) {
        double len, dia, span;
        if (!lv_mission_stage_geometry(m, ph.stages[i], &len, &dia, &span))
            continue;
        if (geo == NULL)
            geo = cJSON_AddObjectToObject(o, "geometry");
        cJSON *g = cJSON_AddObjectToObject(geo, lv_mission_stage_name(m, ph.stages[i]));
        cJSON_AddNumberToObject(g, "length", len);
        cJSON_AddNumberToObject(g, "diameter", dia);
        cJSON_AddNumberToObject(g, "span", span);
    }
    cJSON_AddNumberToObject(o, "payload", isfinite(r->payload) ? r->payload : 0.0);
    if (r->state == LV_PHASE_DONE || (r->state == LV_PHASE_CRASHED && r->n_final > 0)) {
        cJSON *fin = cJSON_AddObjectToObject(o, "final"); /* a crash end's too: flown */
        for (size_t i = 0; i < r->n_final; i++)
            if (isfinite(r->final_values[i]))
                cJSON_AddNumberToObject(fin, r->final_names[i], r->final_values[i]);
    }
    if (r->result_stem != NULL && r->result_formats != 0) { /* the files it wrote */
        char buf[4200];
        cJSON *files = cJSON_AddObjectToObject(o, "files");
        const char *base = strrchr(r->result_stem, '/');
        base = base ? base + 1 : r->result_stem;
        /* the sinks name a failed simulation's files; a crash end's are complete */
        const char *fail = r->state == LV_PHASE_FAILED ? ".failed" : "";
        const char *name, *ext;
        for (size_t i = 0; (name = lv_result_format_info(i, &ext, NULL)) != NULL; i++)
            if (r->result_formats & (1u << i)) { /* "mat": "phase_1_ascent.mat" */
                snprintf(buf, sizeof buf, "%s%s%s", base, fail, ext);
                cJSON_AddStringToObject(files, name, buf);
            }
    }
    return o;
}

/* A number, null when not finite. lv_json_print writes it as the result CSVs do (the shortest
 * text that reads back exactly), so a timeline's values equal the rows they come from. */
static void num_or_null(cJSON *o, const char *key, double v)
{
    if (isfinite(v))
        cJSON_AddNumberToObject(o, key, v);
    else
        cJSON_AddNullToObject(o, key);
}

/* bodies[].timeline (lv_run_timeline): each event of the body's flight with its row's state.
 * Left out when the run kept no rows (lv_run_options.no_rows). */
static lv_status timeline_json(cJSON *body, const lv_run *run, size_t s, lv_err *err)
{
    lv_timeline *tl = NULL;
    lv_err e;
    const lv_status st = lv_run_timeline(run, s, &tl, &e);
    if (st == LV_ERR_NOMEM)
        return lv_fail(err, st, "%s", e.msg);
    if (st != LV_OK)
        return LV_OK; /* no rows: no timeline */
    cJSON *a = cJSON_AddArrayToObject(body, "timeline");
    for (size_t i = 0; i < tl->n; i++) {
        const lv_timeline_row *w = &tl->rows[i];
        cJSON *j = cJSON_CreateObject();
        cJSON_AddStringToObject(j, "label", w->label);
        cJSON_AddStringToObject(j, "kind", w->kind);
        if (w->event != NULL)
            cJSON_AddStringToObject(j, "event", w->event);
        if (w->named)
            cJSON_AddBoolToObject(j, "named", 1);
        cJSON_AddStringToObject(j, "phase", w->phase);
        cJSON_AddNumberToObject(j, "row", (double)w->row);
        num_or_null(j, "t", w->t);
        num_or_null(j, "h", w->h);
        num_or_null(j, "speed", w->speed);
        num_or_null(j, "mach", w->mach);
        num_or_null(j, "q", w->q);
        cJSON_AddItemToArray(a, j);
    }
    lv_timeline_free(tl);
    return LV_OK;
}

/* "time": how t maps to UTC over the span of the phases that ran (docs/exports.md, "Times"):
 * TAI - UTC at the epoch, the UTC of the first start and last end, the leap seconds between
 * (UTC and t of their start), the note when ERFA's table cannot vouch for the span. */
static void time_json(cJSON *root, const lv_run *run, size_t n_phases, const char *epoch)
{
    lv_tai e;
    if (lv_utc_parse(epoch, &e) < 0) /* the parser checked it: not reached */
        return;
    char buf[320];
    cJSON *o = cJSON_AddObjectToObject(root, "time");
    snprintf(buf, sizeof buf, "SI seconds since the epoch; UTC counts the leap seconds of "
             "ERFA %s's table", lv_utc_erfa_version());
    cJSON_AddStringToObject(o, "t", buf);
    cJSON_AddNumberToObject(o, "tai_minus_utc", lv_utc_tai_minus_utc(e));
    double t0 = INFINITY, t1 = -INFINITY;
    for (size_t k = 0; k < n_phases; k++) {
        const lv_phase_result *r = lv_run_result(run, k);
        if ((r->state == LV_PHASE_DONE || r->state == LV_PHASE_FAILED ||
             r->state == LV_PHASE_CRASHED) &&
            isfinite(r->t_start) && isfinite(r->t_end)) {
            t0 = fmin(t0, r->t_start);
            t1 = fmax(t1, fmax(r->t_start, r->t_end));
        }
    }
    if (!(t0 <= t1))
        return;
    const lv_tai a = lv_utc_add(e, t0), b = lv_utc_add(e, t1);
    lv_utc_format(a, 0, "Z", buf, sizeof buf, NULL);
    cJSON_AddStringToObject(o, "start", buf);
    lv_utc_format(b, 0, "Z", buf, sizeof buf, NULL);
    cJSON_AddStringToObject(o, "end", buf);
    cJSON *leaps = cJSON_AddArrayToObject(o, "leap_seconds");
    lv_tai s[8];
    const size_t n = lv_utc_leaps(a, b, s, 8);
    for (size_t i = 0; i < n && i < 8; i++) {
        cJSON *l = cJSON_CreateObject();
        lv_utc_format(s[i], 0, "Z", buf, sizeof buf, NULL);
        cJSON_AddStringToObject(l, "utc", buf);
        cJSON_AddNumberToObject(l, "t", (double)(s[i] - e) / 1e6);
        cJSON_AddItemToArray(leaps, l);
    }
    if (lv_utc_note(a, b, buf, sizeof buf))
        cJSON_AddStringToObject(o, "note", buf);
}

lv_status lv_run_write_summary(const lv_run *run, const char *outdir, lv_err *err)
{
    return lv_run_write_summary_files(run, outdir, LV_SUMMARY_JSON | LV_SUMMARY_BODIES, err);
}

lv_status lv_run_write_summary_files(const lv_run *run, const char *outdir, unsigned what,
                                     lv_err *err)
{
    const lv_mission *m = lv_run_mission(run);
    lv_mission_info mi;
    lv_mission_get_info(m, &mi);
    cJSON *root = cJSON_CreateObject();
    if (root == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    cJSON_AddStringToObject(root, "mission", mi.name);
    cJSON_AddStringToObject(root, "file", mi.path);
    cJSON_AddStringToObject(root, "lvsim", LVSIM_VERSION);
    /* the run as a whole: "ok" when every phase is done; "crashed" when every phase not done
     * crashed or follows one that did (a touchdown beyond the landing gear's limits: the
     * simulation is complete); else "failed" (kept, marked) */
    int all_done = 1, failed = 0;
    for (size_t k = 0; k < mi.n_phases; k++) {
        const lv_phase_state ps = lv_run_result(run, k)->state;
        all_done &= ps == LV_PHASE_DONE;
        failed |= ps == LV_PHASE_FAILED || ps == LV_PHASE_PENDING;
    }
    cJSON_AddStringToObject(root, "status", all_done ? "ok" : failed ? "failed" : "crashed");
    cJSON_AddStringToObject(root, "epoch", mi.epoch ? mi.epoch : "2000-01-01T12:00:00Z");
    time_json(root, run, mi.n_phases, mi.epoch ? mi.epoch : "2000-01-01T12:00:00Z");
    cJSON_AddStringToObject(root, "world", mi.flat_world ? "flat" : "planet");
    if (!mi.flat_world)
        cJSON_AddStringToObject(root, "planet", mi.planet);
    if (mi.flat_world) {
        cJSON *site = cJSON_AddObjectToObject(root, "site");
        cJSON_AddNumberToObject(site, "lat", mi.site_lat);
        cJSON_AddNumberToObject(site, "lon", mi.site_lon);
    }
    cJSON_AddStringToObject(root, "phase_order",
                            "run order: a phase after its parent; among the phases ready "
                            "together, file order (index: run order, file_index: position in "
                            "the file)");
    cJSON *phases = cJSON_AddArrayToObject(root, "phases");
    lv_status st = LV_OK;
    for (size_t k = 0; k < mi.n_phases; k++) {
        cJSON *pj = phase_json(run, k);
        cJSON_AddItemToArray(phases, pj);
        if (st == LV_OK && (what & LV_SUMMARY_BODIES))
            st = write_reference_csv(run, k, outdir, pj, err);
    }
    cJSON *bodies = cJSON_AddArrayToObject(root, "bodies");
    size_t *ks = calloc(mi.n_phases + 1, sizeof *ks);
    if (st == LV_OK && ks == NULL)
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
    for (size_t s = 0; s < mi.n_stages && st == LV_OK; s++) {
        size_t n = lv_run_body_phases(run, s, ks);
        if (n == 0)
            continue;
        const char *stage = lv_mission_stage_name(m, s);
        cJSON *b = cJSON_CreateObject();
        cJSON_AddStringToObject(b, "name", stage);
        cJSON *pl = cJSON_AddArrayToObject(b, "phases");
        for (size_t i = 0; i < n; i++)
            cJSON_AddItemToArray(pl, cJSON_CreateString(lv_mission_phase_name(m, ks[i])));
        char file[512], path[4700];
        snprintf(file, sizeof file, "body_%s.csv", stage);
        snprintf(path, sizeof path, "%s/%s", outdir, file);
        cJSON_AddItemToArray(bodies, b);
        if ((what & LV_SUMMARY_JSON) && (st = timeline_json(b, run, s, err)) != LV_OK)
            break;
        if (what & LV_SUMMARY_BODIES) {
            cJSON_AddStringToObject(b, "trajectory", file);
            st = write_body_csv(run, s, path, err);
        }
    }
    free(ks);
    char *text = st == LV_OK && (what & LV_SUMMARY_JSON) ? lv_json_print(root) : NULL;
    cJSON_Delete(root);
    if (st != LV_OK || !(what & LV_SUMMARY_JSON))
        return st;
    if (text == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    char path[4200];
    snprintf(path, sizeof path, "%s/summary.json", outdir);
    lv_atomic out;
    if ((st = lv_atomic_open(&out, path, err)) == LV_OK) {
        fputs(text, out.fp);
        fputc('\n', out.fp);
        st = lv_atomic_commit(&out, err); /* checks that every write reached the file */
    }
    cJSON_free(text);
    return st;
}
