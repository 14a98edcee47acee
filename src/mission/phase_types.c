/* phase_types.c - the registered phase-model types (phase_type.h): a mission phase's
 * `model:` names one of them. */
#include "mission/phase_type.h"

#include <stdarg.h>
#include <stdio.h>

#include "core/status.h"

/* The registered types in the order `lvsim models` lists them: one name a type, whose object
 * lv_phase_type_<name> its file src/mission/phase_<name>.c defines. */
#define LV_PHASE_TYPE_LIST(X) X(flat6) X(dof3) X(runway) X(dof6)

#define LV_DECLARE_TYPE(n) extern const lv_phase_type lv_phase_type_##n;
LV_PHASE_TYPE_LIST(LV_DECLARE_TYPE)
#define LV_TYPE_ENTRY(n) &lv_phase_type_##n,
static const lv_phase_type *const types[] = {LV_PHASE_TYPE_LIST(LV_TYPE_ENTRY) NULL};

const lv_phase_type *const *lv_phase_types(void) { return types; }

lv_status lv_phase_model_build(const lv_build_ctx *bc, lv_phase_model **out, lv_err *err)
{
    const lv_phase_type *t = bc->def->phases[bc->k].type;
    lv_status st = t->build(bc, out, err);
    if (st == LV_OK)
        (*out)->type = t;
    return st;
}

void lv_phase_model_free(lv_phase_model *pm)
{
    if (pm != NULL)
        pm->type->free_self(pm->self);
}

void lv_build_crash(const lv_build_ctx *bc, const char *fmt, ...)
{
    lv_handoff_notes *n = bc->notes;
    if (n == NULL)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(n->why, sizeof n->why, fmt, ap);
    va_end(ap);
    n->crashed = 1;
}

void lv_build_note(const lv_build_ctx *bc, const char *name, const char *unit, double value)
{
    lv_handoff_notes *n = bc->notes;
    if (n == NULL || n->n >= LV_HANDOFF_NOTES_MAX)
        return;
    n->name[n->n] = name;
    n->unit[n->n] = unit;
    n->value[n->n] = value;
    n->n++;
}
