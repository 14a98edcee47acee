/* parse_params.c - a mission file's `parameters:`: the shared parameter set (the paper's
 * userPar, sec. 2.1) that root phases take their start values from; which names exist comes
 * from the registered phase types (phase_type.h). Format: docs/mission-format.md. */
#include "mission/mission.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/names.h"
#include "mission/parse_int.h"
#include "mission/phase_type.h"

/* ---- the parameter set (userPar) ------------------------------------------------------ */

/* The shared parameter set: the parameters of the registered model types that a root phase
 * takes from the mission (phase_type.h), e.g. start_lat [rad], start_h [m]. */
static const lv_var *mission_param(const char *name)
{
    for (const lv_phase_type *const *t = lv_phase_types(); *t != NULL; t++)
        for (size_t i = 0; i < (*t)->n_mission_params; i++)
            if (strcmp((*t)->mission_params[i].name, name) == 0)
                return &(*t)->mission_params[i];
    return NULL;
}

/* Its allowed values: the narrowest every type that takes it accepts. */
static lv_range mission_param_range(const char *name)
{
    lv_range r = LV_RANGE_ANY;
    for (const lv_phase_type *const *t = lv_phase_types(); *t != NULL; t++)
        for (size_t i = 0; i < (*t)->n_mission_params; i++)
            if ((*t)->mission_param_ranges != NULL &&
                strcmp((*t)->mission_params[i].name, name) == 0) {
                const lv_range q = (*t)->mission_param_ranges[i];
                if (q.lo > r.lo || (q.lo == r.lo && q.lo_open)) {
                    r.lo = q.lo;
                    r.lo_open = q.lo_open;
                }
                if (q.hi < r.hi || (q.hi == r.hi && q.hi_open)) {
                    r.hi = q.hi;
                    r.hi_open = q.hi_open;
                }
            }
    return r;
}

/* Angles (rad) and angular rates (rad/s): these alone may be written as *_deg. */
static int is_angular(const char *unit)
{
    return strcmp(unit, "rad") == 0 || strcmp(unit, "rad/s") == 0;
}

/* Copies `key` without a trailing "_deg" into buf; returns 1 if it had one. */
int lv_pk_strip_deg(const char *key, char *buf, size_t cap)
{
    size_t n = strlen(key);
    const int deg = n > 4 && strcmp(key + n - 4, "_deg") == 0;
    if (deg)
        n -= 4;
    if (n >= cap)
        n = cap - 1;
    memcpy(buf, key, n);
    buf[n] = '\0';
    return deg;
}

lv_status lv_parse_params(const lv_pctx *pc, const lv_ynode *n)
{
    lv_mission_def *m = pc->m;
    const char *what = "parameters";
    lv_status st;
    lv_pctx sc = *pc;
    sc.owner = LV_OWN_PARAM;
    const lv_pctx *c = &sc;

    if (n == NULL || lv_yaml_is_null(n))
        return LV_OK;
    if ((st = lv_pk_check_map(c, n, what, NULL)) != LV_OK)
        return st;
    const size_t np = n->n / 2;
    if (np == 0)
        return LV_OK;
    m->param_names = calloc(np, sizeof *m->param_names);
    m->param_values = calloc(np, sizeof *m->param_values);
    if (m->param_names == NULL || m->param_values == NULL)
        return lv_pk_nomem(c);
    for (size_t i = 0; i < np; i++) {
        const lv_ynode *k = n->kids[2 * i], *v = n->kids[2 * i + 1];
        char base[LV_NAME_MAX + 1];
        const int deg = lv_pk_strip_deg(k->text, base, sizeof base);
        const lv_var *pv = k->len > LV_NAME_MAX ? NULL : mission_param(base);
        if (pv == NULL) {
            lv_suggest s;
            char hint[192], degs[64][LV_NAME_MAX + 8];
            size_t nd = 0;
            lv_suggest_init(&s, k->text);
            for (int pass = 0; pass < 2; pass++) /* the names, then the angles' _deg forms */
                for (const lv_phase_type *const *t = lv_phase_types(); *t != NULL; t++)
                    for (size_t j = 0; j < (*t)->n_mission_params; j++) {
                        const lv_var *q = &(*t)->mission_params[j];
                        if (mission_param(q->name) != q)
                            continue; /* named by an earlier type already */
                        if (pass == 0)
                            lv_suggest_add(&s, q->name);
                        else if (is_angular(q->unit) && nd < 64) {
                            snprintf(degs[nd], sizeof degs[nd], "%s_deg", q->name);
                            lv_suggest_add(&s, degs[nd++]);
                        }
                    }
            lv_suggest_text(&s, hint, sizeof hint);
            return lv_pk_fail(c, k, "%s: unknown parameter '%.60s'%s", what, k->text, hint);
        }
        if (deg && !is_angular(pv->unit))
            return lv_pk_fail(c, k, "%s: '%s' is not an angle: write '%s' in SI units (m, m/s) "
                        "without _deg", what, k->text, base);
        for (size_t j = 0; j < i; j++)
            if (strcmp(m->param_names[j], base) == 0)
                return lv_pk_fail(c, k, "%s: '%s' given twice (as '%s' at line %d)", what, base,
                            n->kids[2 * j]->text, n->kids[2 * j]->line);
        if ((st = lv_pk_slot(c, v, what, k->text, base, pv->unit, mission_param_range(base),
                             deg, &m->param_values[i])) != LV_OK)
            return st;
        if ((m->param_names[i] = lv_pk_strdup(base)) == NULL)
            return lv_pk_nomem(c);
        m->n_params = i + 1;
    }
    return LV_OK;
}
