/* phase_types_api.c - the registered phase-model types seen from outside (lv_mission.h:
 * lv_phase_types_*): their names and keys, and each type's model built for a sample mission
 * of one stage and one phase, so that its variables (the names `set:`, `end:` and the result
 * files use) can be listed without a mission file (`lvsim models`, `lvsim vars dof3`).
 * The sample goes through the parser and the runner like any mission: what it lists is what
 * a phase of that type has. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "lvsim/lv_mission.h"
#include "mission/mission_rt.h"

size_t lv_phase_types_count(void)
{
    size_t n = 0;
    for (const lv_phase_type *const *t = lv_phase_types(); *t != NULL; t++)
        n++;
    return n;
}

lv_status lv_phase_types_get(size_t i, lv_phase_type_info *out, lv_err *err)
{
    if (i >= lv_phase_types_count())
        return lv_fail(err, LV_ERR_INPUT, "phase-model type index %zu out of range", i);
    const lv_phase_type *t = lv_phase_types()[i];
    out->name = t->name;
    out->description = t->description;
    out->flat_world = t->world == LV_WORLD_FLAT;
    out->keys = t->keys;
    out->n_mission_params = t->n_mission_params;
    out->mission_params = t->mission_params;
    out->mass_state = t->mass_state;
    out->ends = t->ends;
    return LV_OK;
}

struct lv_phase_sample {
    lv_mission *m;
    lv_run *r;
    lv_phase_call *call;
    char text[1024];
};

/* One constant-thrust stage, one phase of the type, nothing else: the smallest valid mission
 * in the type's world (the stage's rigid_body data serve the dof6 type, its engine aft of the
 * centre of mass for a controller; others ignore it). */
static void sample_text(const lv_phase_type *t, char *buf, size_t cap)
{
    const int flat = t->world == LV_WORLD_FLAT;
    snprintf(buf, cap,
             "mission: {name: sample-%s}\n"
             "%s"
             "stages:\n"
             "  - name: stage\n"
             "    dry_mass: 1000\n"
             "    propellant_mass: 4000\n"
             "    engines: [{thrust_vac: 1.0e5, isp_vac: 300}]\n"
             "    rigid_body: {inertia_full: {xx: 1.0e3, yy: 2.0e4, zz: 2.0e4},\n"
             "                 engine_position: {x: -5}}\n"
             "phases:\n"
             "  - {name: sample, model: %s, stages: [stage], stop_time: 10%s%s}\n",
             t->name,
             flat ? ""
             : t->n_mission_params == 0
                 ? "environment: {world: planet, planet: earth}\n"
                 : "environment: {world: planet, planet: earth}\n"
                   "parameters: {start_lat: 0, start_lon: 0, start_h: 0, start_vel: 1,\n"
                   "             start_fpa_deg: 89, start_chi: 0}\n",
             t->name, t->sample_keys != NULL ? ", " : "",
             t->sample_keys != NULL ? t->sample_keys : "");
}

lv_status lv_phase_types_sample(const char *name, lv_phase_sample **out, lv_err *err)
{
    *out = NULL;
    const lv_phase_type *t = NULL;
    for (const lv_phase_type *const *p = lv_phase_types(); *p != NULL; p++)
        if (name != NULL && strcmp((*p)->name, name) == 0)
            t = *p;
    if (t == NULL) {
        char known[256] = "";
        size_t n = 0;
        for (const lv_phase_type *const *p = lv_phase_types(); *p != NULL; p++)
            n += (size_t)snprintf(known + n, n < sizeof known ? sizeof known - n : 0, "%s%s",
                                  n ? ", " : "", (*p)->name);
        return lv_fail(err, LV_ERR_NOTFOUND, "unknown phase-model type '%s' (types: %s)",
                       name ? name : "(null)", known);
    }
    lv_phase_sample *s = calloc(1, sizeof *s);
    if (s == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    sample_text(t, s->text, sizeof s->text);
    lv_mission_def *d = NULL;
    char what[64];
    snprintf(what, sizeof what, "(sample %s mission)", t->name);
    lv_status st = lv_mission_def_parse(s->text, strlen(s->text), what, ".", &d, err);
    if (st == LV_OK)
        st = lv_mission_from_def(d, &s->m, err); /* takes d over */
    if (st == LV_OK)
        st = lv_run_create(s->m, &s->r, err);
    if (st == LV_OK)
        st = lv_run_prepare(s->r, 0, &s->call, err);
    if (st != LV_OK) {
        lv_phase_types_sample_free(s);
        return st;
    }
    *out = s;
    return LV_OK;
}

const lv_model_def *lv_phase_types_sample_model(const lv_phase_sample *s)
{
    return lv_phase_call_model(s->call);
}

void lv_phase_types_sample_free(lv_phase_sample *s)
{
    if (s == NULL)
        return;
    lv_phase_call_free(s->call);
    lv_run_free(s->r);
    lv_mission_free(s->m);
    free(s);
}

size_t lv_phase_types_end_count(void) { return 5; }

const char *lv_phase_types_end_name(size_t i)
{
    return i < 5 ? lv_end_kind_name((lv_end_kind)i) : NULL;
}
