/* phase_types.c - the registered phase-model types (phase_type.h): a mission phase's
 * `model:` names one of them. */
#include "mission/phase_type.h"

#include "core/status.h"

/* lv_phase_type_flat6 (phase_flat6.c) is declared in phase_type.h */
extern const lv_phase_type lv_phase_type_dof3;  /* phase_dof3.c */
extern const lv_phase_type lv_phase_type_runway; /* phase_runway.c */
extern const lv_phase_type lv_phase_type_dof6;  /* phase_dof6.c */

static const lv_phase_type *const types[] = {&lv_phase_type_flat6, &lv_phase_type_dof3,
                                             &lv_phase_type_runway, &lv_phase_type_dof6, NULL};

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
