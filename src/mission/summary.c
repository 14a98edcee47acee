/* summary.c - after a run: summary.json (per phase: times, why it ended, events, statistics,
 * the hand-off, final state; per body: its phases and merged trajectory) and one merged CSV
 * trajectory per body across the phases it flies in. JSON is built with cJSON. */
#define _POSIX_C_SOURCE 200809L

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "io/atomic.h"
#include "lvsim/lv_mission.h"
#include "lvsim/lv_planet.h"
#include "lvsim/lvsim.h"
#include "mission/runner.h"

static int phase_has_stage(const lv_phase_def *ph, size_t s)
{
    for (size_t i = 0; i < ph->n_stages; i++)
        if (ph->stages[i] == s)
            return 1;
    return 0;
}

size_t lv_runner_body_phases(const lv_mission *m, size_t s, size_t *out)
{
    const lv_mission_def *d = lv_runner_def(m);
    size_t n = 0;
    for (size_t k = 0; k < d->n_phases; k++) {
        const lv_phase_result *r = lv_mission_result(m, k);
        if (r->state != LV_PHASE_DONE || !phase_has_stage(&d->phases[k], s))
            continue;
        size_t pos = n++; /* insertion by start time: the path is short */
        while (pos > 0 && lv_mission_result(m, out[pos - 1])->t_start > r->t_start) {
            out[pos] = out[pos - 1];
            pos--;
        }
        out[pos] = k;
    }
    return n;
}

double lv_runner_stage_mass(const lv_mission *m, size_t k, size_t s, double m_body)
{
    const lv_mission_def *d = lv_runner_def(m);
    const lv_phase_def *ph = &d->phases[k];
    const double *prop0 = ph->parent >= 0 ? lv_runner_prop_end(m, (size_t)ph->parent) : NULL;
    double upper = 0.0, own = NAN;
    for (size_t i = 0; i < ph->n_stages; i++) {
        size_t si = ph->stages[i];
        double mi = d->stages[si].dry_mass + (prop0 ? prop0[si] : d->stages[si].propellant_mass);
        if (i > 0)
            upper += mi;
        if (si == s)
            own = mi;
    }
    return ph->stages[0] == s ? m_body - upper : own;
}

static const char *state_name(lv_phase_state st)
{
    switch (st) {
    case LV_PHASE_DONE: return "done";
    case LV_PHASE_FAILED: return "failed";
    case LV_PHASE_SKIPPED: return "skipped";
    default: return "pending";
    }
}

static const char *const end_kind_names[] = {"burnout", "altitude", "speed", "apogee", "impact"};

/* Name of state event `index` of a phase's model (recorded when the phase ran). */
static const char *event_name(const lv_phase_result *r, int index)
{
    return index >= 0 && (size_t)index < r->n_event_names ? r->event_names[index] : "event";
}

/* The value of the end condition an event stands for ("altitude" -> 100000), or NAN. */
static double end_value(const lv_phase_def *ph, const char *event)
{
    for (size_t j = 0; j < ph->n_ends; j++)
        if (strncmp(event, end_kind_names[ph->ends[j].kind], strlen(end_kind_names[ph->ends[j].kind])) == 0 &&
            ph->ends[j].kind != LV_END_BURNOUT && ph->ends[j].kind != LV_END_APOGEE)
            return ph->ends[j].value;
    return NAN;
}

static int write_body_csv(const lv_mission *m, size_t s, const char *path, lv_err *err)
{
    const lv_mission_def *d = lv_runner_def(m);
    size_t *ks = calloc(d->n_phases + 1, sizeof *ks);
    if (ks == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    size_t n = lv_runner_body_phases(m, s, ks);
    lv_atomic out;
    lv_status ost = lv_atomic_open(&out, path, err);
    if (ost != LV_OK) {
        free(ks);
        return ost;
    }
    FILE *f = out.fp;
    /* Columns: the states of the phases' model (every phase of a body has the same model:
     * the world decides it), plus, for the 3-DoF model, where the body is over the planet. */
    const lv_result *r0 = n ? lv_runner_rows(m, ks[0]) : NULL;
    static const char *const flat_cols[] = {"x", "y", "z", "vx", "vy", "vz", "psi", "theta",
                                            "phi", "p", "q", "r", "m", NULL};
    static const char *const flat_units[] = {"m", "m", "m", "m/s", "m/s", "m/s", "rad", "rad",
                                             "rad", "rad/s", "rad/s", "rad/s", "kg"};
    static const char *const dof3_cols[] = {"r_eci_x", "r_eci_y", "r_eci_z", "v_eci_x",
                                            "v_eci_y", "v_eci_z", "m", "lat", "lon", "h",
                                            "v_rel", "mach", "q_dyn", NULL};
    static const char *const dof3_units[] = {"m", "m", "m", "m/s", "m/s", "m/s", "kg", "rad",
                                             "rad", "m", "m/s", "1", "Pa"};
    const int flat = d->env.world == LV_WORLD_FLAT;
    const char *const *cols = flat ? flat_cols : dof3_cols;
    const char *const *units = flat ? flat_units : dof3_units;
    size_t nc = 0;
    while (cols[nc] != NULL)
        nc++;
    fprintf(f, "time [s],phase");
    for (size_t c = 0; c < nc; c++)
        fprintf(f, ",%s [%s]", strcmp(cols[c], "m") == 0 ? "body_mass" : cols[c], units[c]);
    fprintf(f, ",stage_mass [kg]%s\n", flat ? ",lat [rad],lon [rad],h [m]" : "");
    /* The flat world's origin sits at the mission's site (WGS-84) with x east, y north, z up:
     * geodetic coordinates for maps and the globe. */
    const lv_planet earth = lv_planet_earth();
    double r_site[3], C_ned_ecef[3][3];
    lv_frames_geodetic_to_ecef(&earth, d->env.site_lat, d->env.site_lon, 0.0, r_site);
    lv_frames_C_ned_ecef(d->env.site_lat, d->env.site_lon, C_ned_ecef);
    for (size_t i = 0; i < n && r0; i++) {
        const lv_result *r = lv_runner_rows(m, ks[i]);
        size_t idx[16], ct, cm = 0;
        if (lv_result_column(r, "time", &ct, NULL) != LV_OK)
            continue;
        int ok = 1;
        for (size_t c = 0; c < nc; c++) {
            ok &= lv_result_column(r, cols[c], &idx[c], NULL) == LV_OK;
            if (strcmp(cols[c], "m") == 0)
                cm = idx[c];
        }
        if (!ok)
            continue;
        for (size_t row = 0; row < lv_result_rows(r); row++) {
            fprintf(f, "%.17g,%s", lv_result_value(r, row, ct), d->phases[ks[i]].name);
            for (size_t c = 0; c < nc; c++)
                fprintf(f, ",%.17g", lv_result_value(r, row, idx[c]));
            fprintf(f, ",%.17g", lv_runner_stage_mass(m, ks[i], s, lv_result_value(r, row, cm)));
            if (flat) {
                const double ned[3] = {lv_result_value(r, row, idx[1]),
                                       lv_result_value(r, row, idx[0]),
                                       -lv_result_value(r, row, idx[2])};
                double r_ecef[3], lat, lon, h;
                for (int a = 0; a < 3; a++)
                    r_ecef[a] = r_site[a] + C_ned_ecef[0][a] * ned[0] +
                                C_ned_ecef[1][a] * ned[1] + C_ned_ecef[2][a] * ned[2];
                lv_frames_ecef_to_geodetic(&earth, r_ecef, &lat, &lon, &h);
                fprintf(f, ",%.17g,%.17g,%.17g", lat, lon, h);
            }
            fputc('\n', f);
        }
    }
    free(ks);
    return lv_atomic_commit(&out, err);
}

static cJSON *phase_json(const lv_mission *m, size_t k)
{
    const lv_mission_def *d = lv_runner_def(m);
    const lv_phase_def *ph = &d->phases[k];
    const lv_phase_result *r = lv_mission_result(m, k);
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "index", (double)(k + 1));
    cJSON_AddStringToObject(o, "name", ph->name);
    cJSON_AddStringToObject(o, "model", ph->model);
    cJSON *st = cJSON_AddArrayToObject(o, "stages");
    for (size_t i = 0; i < ph->n_stages; i++)
        cJSON_AddItemToArray(st, cJSON_CreateString(d->stages[ph->stages[i]].name));
    if (ph->parent >= 0)
        cJSON_AddStringToObject(o, "from", d->phases[ph->parent].name);
    else
        cJSON_AddNullToObject(o, "from");
    cJSON_AddStringToObject(o, "state", state_name(r->state));
    if (r->state == LV_PHASE_FAILED || r->state == LV_PHASE_SKIPPED)
        cJSON_AddStringToObject(o, "error", r->error);
    if (r->state == LV_PHASE_SKIPPED || r->state == LV_PHASE_PENDING)
        return o;
    cJSON_AddNumberToObject(o, "t_start", r->t_start);
    cJSON_AddNumberToObject(o, "t_end", r->t_end);

    const lv_sim_report *rep = &r->report;
    cJSON *end = cJSON_AddObjectToObject(o, "end");
    cJSON_AddStringToObject(end, "reason", rep->reason == LV_STOP_TIME    ? "stop_time"
                                           : rep->reason == LV_STOP_EVENT ? "event"
                                                                          : "failed");
    if (rep->reason == LV_STOP_EVENT && rep->stop_event >= 0) {
        const char *ev = event_name(r, rep->stop_event);
        cJSON_AddStringToObject(end, "event", ev);
        double v = end_value(ph, ev);
        if (!isnan(v))
            cJSON_AddNumberToObject(end, "value", v);
    } else if (rep->reason == LV_STOP_TIME) {
        cJSON_AddNumberToObject(end, "value", ph->t_stop);
    }
    cJSON *ev = cJSON_AddArrayToObject(o, "events");
    for (size_t i = 0; i < rep->n_event_log; i++) {
        const lv_event_record *e = &rep->event_log[i];
        cJSON *j = cJSON_CreateObject();
        cJSON_AddNumberToObject(j, "t", e->t);
        cJSON_AddStringToObject(j, "kind", e->is_state ? "state" : "time");
        if (e->is_state) {
            cJSON_AddStringToObject(j, "name", event_name(r, e->index));
            cJSON_AddNumberToObject(j, "direction", e->direction);
        }
        cJSON_AddItemToArray(ev, j);
    }
    cJSON *sj = cJSON_AddObjectToObject(o, "stats");
    cJSON_AddNumberToObject(sj, "states", (double)rep->n_states);
    cJSON_AddNumberToObject(sj, "steps", (double)rep->stats.steps);
    cJSON_AddNumberToObject(sj, "rhs_evals", (double)rep->stats.rhs_evals);
    cJSON_AddNumberToObject(sj, "jac_evals", (double)rep->stats.jac_evals);
    cJSON_AddNumberToObject(sj, "state_events", (double)rep->stats.state_events);
    cJSON_AddNumberToObject(sj, "time_events", (double)rep->stats.time_events);
    cJSON_AddNumberToObject(sj, "restarts", (double)rep->stats.restarts);
    cJSON_AddNumberToObject(sj, "rows", (double)rep->stats.output_rows);
    cJSON_AddNumberToObject(sj, "cpu_time", rep->stats.cpu_time);
    cJSON_AddStringToObject(sj, "method", ph->method ? ph->method : "dassl");
    cJSON_AddNumberToObject(sj, "tolerance", ph->tolerance);

    cJSON *h = cJSON_AddObjectToObject(o, "handoff");
    cJSON_AddStringToObject(h, "from", ph->parent >= 0 ? d->phases[ph->parent].name : "parameters");
    if (ph->parent >= 0) {
        cJSON_AddNumberToObject(h, "states_copied", (double)lv_runner_n_copied(m, k));
        cJSON_AddNumberToObject(h, "mass_from_stages", lv_runner_mass_handoff(m, k));
    }
    cJSON *ov = cJSON_AddObjectToObject(h, "overrides");
    for (size_t i = 0; i < ph->n_set; i++)
        cJSON_AddNumberToObject(ov, ph->set_names[i], ph->set_values[i]);
    if (r->state == LV_PHASE_DONE) {
        cJSON *fin = cJSON_AddObjectToObject(o, "final");
        for (size_t i = 0; i < r->n_final; i++)
            if (isfinite(r->final_values[i]))
                cJSON_AddNumberToObject(fin, r->final_names[i], r->final_values[i]);
    }
    if (r->result_stem != NULL) {
        char buf[4200];
        cJSON *files = cJSON_AddObjectToObject(o, "files");
        const char *base = strrchr(r->result_stem, '/');
        base = base ? base + 1 : r->result_stem;
        const char *fail = r->state == LV_PHASE_DONE ? "" : ".failed";
        snprintf(buf, sizeof buf, "%s%s.mat", base, fail);
        cJSON_AddStringToObject(files, "mat", buf);
        snprintf(buf, sizeof buf, "%s%s.csv", base, fail);
        cJSON_AddStringToObject(files, "csv", buf);
    }
    return o;
}

lv_status lv_mission_write_summary(const lv_mission *m, const char *outdir, lv_err *err)
{
    const lv_mission_def *d = lv_runner_def(m);
    cJSON *root = cJSON_CreateObject();
    if (root == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    cJSON_AddStringToObject(root, "mission", d->name);
    cJSON_AddStringToObject(root, "file", d->path);
    cJSON_AddStringToObject(root, "lvsim", LVSIM_VERSION);
    cJSON_AddStringToObject(root, "epoch", d->epoch ? d->epoch : "2000-01-01T12:00:00Z");
    cJSON_AddStringToObject(root, "world", d->env.world == LV_WORLD_FLAT ? "flat" : "planet");
    if (d->env.world == LV_WORLD_PLANET)
        cJSON_AddStringToObject(root, "planet", d->env.planet ? d->env.planet : "earth");
    if (d->env.world == LV_WORLD_FLAT) {
        cJSON *site = cJSON_AddObjectToObject(root, "site");
        cJSON_AddNumberToObject(site, "lat", d->env.site_lat);
        cJSON_AddNumberToObject(site, "lon", d->env.site_lon);
    }
    cJSON *phases = cJSON_AddArrayToObject(root, "phases");
    for (size_t k = 0; k < d->n_phases; k++)
        cJSON_AddItemToArray(phases, phase_json(m, k));
    cJSON *bodies = cJSON_AddArrayToObject(root, "bodies");
    size_t *ks = calloc(d->n_phases + 1, sizeof *ks);
    lv_status st = ks ? LV_OK : lv_fail(err, LV_ERR_NOMEM, "out of memory");
    for (size_t s = 0; s < d->n_stages && st == LV_OK; s++) {
        size_t n = lv_runner_body_phases(m, s, ks);
        if (n == 0)
            continue;
        cJSON *b = cJSON_CreateObject();
        cJSON_AddStringToObject(b, "name", d->stages[s].name);
        cJSON *pl = cJSON_AddArrayToObject(b, "phases");
        for (size_t i = 0; i < n; i++)
            cJSON_AddItemToArray(pl, cJSON_CreateString(d->phases[ks[i]].name));
        char file[512], path[4700];
        snprintf(file, sizeof file, "body_%s.csv", d->stages[s].name);
        snprintf(path, sizeof path, "%s/%s", outdir, file);
        cJSON_AddStringToObject(b, "trajectory", file);
        cJSON_AddItemToArray(bodies, b);
        st = write_body_csv(m, s, path, err);
    }
    free(ks);
    char *text = st == LV_OK ? cJSON_Print(root) : NULL;
    cJSON_Delete(root);
    if (st != LV_OK)
        return st;
    if (text == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    char path[4200];
    snprintf(path, sizeof path, "%s/summary.json", outdir);
    lv_atomic out;
    st = lv_atomic_open(&out, path, err);
    if (st == LV_OK) {
        fputs(text, out.fp);
        fputc('\n', out.fp);
        st = lv_atomic_commit(&out, err); /* checks the writes */
    }
    cJSON_free(text);
    return st;
}
