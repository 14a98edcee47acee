/* model.c - name lookup and consistency checks for lv_model_def. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/names.h"
#include "core/status.h"
#include "lvsim/lv_model.h"

/* "der(h)" -> "h"; NULL when `name` is not of that form. */
static const char *derivative_of(const char *name, char *buf, size_t cap)
{
    size_t len = strlen(name);
    if (len < 6 || strncmp(name, "der(", 4) != 0 || name[len - 1] != ')' || len - 5 >= cap)
        return NULL;
    memcpy(buf, name + 4, len - 5);
    buf[len - 5] = '\0';
    return buf;
}

static int find_in(const lv_var *vars, size_t n, const char *name, size_t *index)
{
    for (size_t i = 0; i < n; i++) {
        if (strcmp(vars[i].name, name) == 0) {
            *index = i;
            return 1;
        }
    }
    return 0;
}

lv_status lv_model_find(const lv_model_def *def, const char *name, lv_var_kind *kind,
                        size_t *index, lv_err *err)
{
    if (name == NULL)
        return lv_fail(err, LV_ERR_INPUT, "model '%s': variable name is NULL", def->name);
    if (find_in(def->states, def->n_states, name, index)) {
        *kind = LV_VAR_STATE;
        return LV_OK;
    }
    if (find_in(def->params, def->n_params, name, index)) {
        *kind = LV_VAR_PARAMETER;
        return LV_OK;
    }
    if (find_in(def->outputs, def->n_outputs, name, index)) {
        *kind = LV_VAR_OUTPUT;
        return LV_OK;
    }
    char inner[256];
    const char *state = derivative_of(name, inner, sizeof inner);
    if (state != NULL && find_in(def->states, def->n_states, state, index)) {
        *kind = LV_VAR_DERIVATIVE;
        return LV_OK;
    }

    lv_suggest sg;
    lv_suggest_init(&sg, name);
    for (size_t i = 0; i < def->n_states; i++)
        lv_suggest_add(&sg, def->states[i].name);
    for (size_t i = 0; i < def->n_params; i++)
        lv_suggest_add(&sg, def->params[i].name);
    for (size_t i = 0; i < def->n_outputs; i++)
        lv_suggest_add(&sg, def->outputs[i].name);
    char hint[200];
    lv_suggest_text(&sg, hint, sizeof hint);
    return lv_fail(err, LV_ERR_NOTFOUND, "model '%s' has no variable '%s'%s", def->name, name,
                   hint);
}

static lv_status check_vars(const lv_model_def *def, const char *what, const lv_var *vars,
                            size_t n, int is_state, lv_err *err)
{
    if (n > 0 && vars == NULL)
        return lv_fail(err, LV_ERR_INPUT, "model '%s': %zu %s but no descriptions", def->name, n,
                       what);
    for (size_t i = 0; i < n; i++) {
        const lv_var *v = &vars[i];
        if (v->name == NULL || v->name[0] == '\0' || v->unit == NULL || v->description == NULL)
            return lv_fail(err, LV_ERR_INPUT,
                           "model '%s': %s %zu lacks a name, unit or description", def->name, what,
                           i);
        if (is_state && !(v->nominal > 0.0 && isfinite(v->nominal)))
            return lv_fail(err, LV_ERR_INPUT, "model '%s': state '%s' has nominal %g (must be > 0)",
                           def->name, v->name, v->nominal);
    }
    return LV_OK;
}

lv_status lv_model_validate(const lv_model_def *def, lv_err *err)
{
    if (def == NULL || def->name == NULL)
        return lv_fail(err, LV_ERR_INPUT, "model definition is NULL or has no name");
    if (def->n_states == 0)
        return lv_fail(err, LV_ERR_INPUT, "model '%s' has no states", def->name);
    if (def->rhs == NULL)
        return lv_fail(err, LV_ERR_INPUT, "model '%s' has no right-hand side", def->name);
    if (def->n_events > 0 && (def->event_g == NULL || def->events == NULL))
        return lv_fail(err, LV_ERR_INPUT, "model '%s': %zu events but no event function",
                       def->name, def->n_events);
    if (def->n_domain > 0 && (def->domain == NULL || def->domain_q == NULL))
        return lv_fail(err, LV_ERR_INPUT, "model '%s': %zu domain bounds but no function",
                       def->name, def->n_domain);
    if (def->n_outputs > 0 && def->outputs_fn == NULL)
        return lv_fail(err, LV_ERR_INPUT, "model '%s': %zu outputs but no output function",
                       def->name, def->n_outputs);
    lv_status st;
    if ((st = check_vars(def, "state", def->states, def->n_states, 1, err)) != LV_OK ||
        (st = check_vars(def, "parameter", def->params, def->n_params, 0, err)) != LV_OK ||
        (st = check_vars(def, "output", def->outputs, def->n_outputs, 0, err)) != LV_OK)
        return st;

    /* Names are unique across kinds: a name addresses exactly one variable. Hashed: this runs
     * at every simulation's set-up (lv_sim_create) and a model's 60 names would otherwise be
     * 1,770 string comparisons. */
    const size_t n = def->n_states + def->n_params + def->n_outputs;
    const char *stack[256];
    const char **names = n <= 256 ? stack : malloc(n * sizeof *names);
    if (names == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "model '%s': out of memory", def->name);
    size_t k = 0;
    for (size_t i = 0; i < def->n_states; i++)
        names[k++] = def->states[i].name;
    for (size_t i = 0; i < def->n_params; i++)
        names[k++] = def->params[i].name;
    for (size_t i = 0; i < def->n_outputs; i++)
        names[k++] = def->outputs[i].name;
    const size_t dup = lv_names_duplicate(names, n);
    const char *twice = dup < n ? names[dup] : NULL;
    if (names != stack)
        free(names);
    if (twice != NULL)
        return lv_fail(err, LV_ERR_INPUT, "model '%s': variable name '%s' is used twice", def->name,
                       twice);
    for (size_t i = 0; i < def->n_events; i++)
        if (def->events[i].name == NULL)
            return lv_fail(err, LV_ERR_INPUT, "model '%s': event %zu has no name", def->name, i);
    return LV_OK;
}
