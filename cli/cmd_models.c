/* cmd_models.c - `lvsim models` (the mission model types a phase's `model:` names, and the
 * built-in models of `lvsim simulate`) and `lvsim vars MODEL` (a model's states,
 * derivatives, parameters, outputs and events with units: for a mission type the names of
 * `set:`, `end:` and the result files).
 */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "common.h"

static int models_run(const cli_cmd *self, int argc, char **argv)
{
    if (argc != 0) {
        const char *what = is_option(argv[0]) ? "unknown option" : "models takes no arguments; got";
        return usage_error(self, what, argv[0]);
    }
    printf("# mission model types (a phase's 'model:'; 'lvsim vars TYPE')\n");
    for (size_t i = 0; i < lv_phase_types_count(); i++) {
        lv_phase_type_info t;
        if (lv_phase_types_get(i, &t, NULL) == LV_OK)
            printf("%-18s %s (%s world)\n", t.name, t.description,
                   t.flat_world ? "flat" : "planet");
    }
    printf("# built-in models ('lvsim simulate MODEL'; 'lvsim vars MODEL')\n");
    for (const lv_model_def *const *all = lv_models_all(); *all; all++)
        printf("%-18s %s\n", (*all)->name, (*all)->description);
    return EXIT_OK;
}

const cli_cmd cli_cmd_models = {
    "models",
    "list the mission model types and the built-in models",
    "",
    "Lists the mission model types (every name a phase's 'model:' takes, first) and the\n"
    "built-in models of 'lvsim simulate', one a line: name and a one-line description.\n"
    "'lvsim vars NAME' lists either's variables; 'lvsim simulate MODEL' runs a built-in one.\n",
    models_run,
};

static void print_vars(const char *kind, const lv_var *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        printf("%-10s %-16s %-8s %12g  %s\n", kind, v[i].name, v[i].unit[0] ? v[i].unit : LV_UNIT_DIMENSIONLESS,
               v[i].start, v[i].description);
}

static int is_phase_type(const char *name)
{
    for (size_t i = 0; i < lv_phase_types_count(); i++) {
        lv_phase_type_info t;
        if (lv_phase_types_get(i, &t, NULL) == LV_OK && strcmp(t.name, name) == 0)
            return 1;
    }
    return 0;
}

/* The phase-level words of a mission type: parameters of a root phase, keys, end:. */
static void print_type_extras(const char *name)
{
    for (size_t i = 0; i < lv_phase_types_count(); i++) {
        lv_phase_type_info t;
        if (lv_phase_types_get(i, &t, NULL) != LV_OK || strcmp(t.name, name) != 0)
            continue;
        printf("# mission type %s: %s (%s world); mass state '%s'\n", t.name, t.description,
               t.flat_world ? "flat" : "planet", t.mass_state);
        printf(t.n_mission_params > 0
                   ? "# a root phase takes these from the mission's 'parameters:':\n"
                   : "# a root phase takes nothing from the mission's 'parameters:' (its own "
                     "keys give its start)\n");
        for (size_t j = 0; j < t.n_mission_params; j++) {
            const lv_var *v = &t.mission_params[j];
            printf("%-10s %-16s %-8s %12s  %s\n", "mission", v->name, v->unit[0] ? v->unit : LV_UNIT_DIMENSIONLESS,
                   "", v->description);
        }
        printf("# phase keys of its own:");
        for (size_t j = 0; t.keys != NULL && t.keys[j] != NULL; j++)
            printf(" %s", t.keys[j]);
        printf("%s\n", t.keys && t.keys[0] ? "" : " none");
        for (size_t j = 0; t.keys != NULL && t.keys[j] != NULL; j++) /* the laws' sections */
            for (int kind = 0; kind < 2; kind++) {
                if (strcmp(t.keys[j], kind == LV_LAW_STEERING ? "guidance" : "throttle") != 0)
                    continue;
                printf("# '%s:' laws ('lvsim laws'):", t.keys[j]);
                for (size_t li = 0; li < lv_laws_count(); li++) {
                    lv_law_info l;
                    if (lv_laws_get(li, &l, NULL) == LV_OK && l.kind == (lv_law_kind)kind &&
                        l.form != LV_LAW_FORM_NONE)
                        printf(" %s", l.name);
                }
                printf("\n");
            }
        printf("# end conditions ('end:'):");
        for (size_t j = 0; t.ends == NULL && j < lv_phase_types_end_count(); j++)
            printf(" %s", lv_phase_types_end_name(j));
        for (size_t j = 0; t.ends != NULL && t.ends[j] != NULL; j++)
            printf(" %s", t.ends[j]);
        printf(", {time: DT} (s after the phase's start), or any state or output below crossing a "
               "value: {NAME: X}, {NAME_deg: X} for an angle, {output: NAME, value: X} (docs/mission-format.md)\n"
               "# 'set:' takes any state or parameter below; the "
               "result files have time, the states, their derivatives and the outputs\n");
    }
}

static int vars_run(const cli_cmd *self, int argc, char **argv)
{
    if (argc != 1)
        return usage_error(self, "vars takes one model name", NULL);
    if (is_option(argv[0]))
        return usage_error(self, "unknown option", argv[0]);
    lv_phase_sample *sample = NULL;
    const lv_model_def *m = NULL;
    if (is_phase_type(argv[0])) {
        lv_err err;
        lv_status st = lv_phase_types_sample(argv[0], &sample, &err);
        if (st != LV_OK)
            return print_err("lvsim", &err, exit_code_for(st));
        m = lv_phase_types_sample_model(sample);
        print_type_extras(argv[0]);
    } else {
        m = lv_models_find(argv[0]);
    }
    if (m == NULL) {
        fprintf(stderr, "lvsim: unknown model '%s'; mission model types:", argv[0]);
        for (size_t i = 0; i < lv_phase_types_count(); i++) {
            lv_phase_type_info t;
            if (lv_phase_types_get(i, &t, NULL) == LV_OK)
                fprintf(stderr, " %s", t.name);
        }
        fprintf(stderr, "; built-in models:");
        for (const lv_model_def *const *all = lv_models_all(); *all; all++)
            fprintf(stderr, " %s", (*all)->name);
        fprintf(stderr, "\n");
        return EXIT_INPUT;
    }
    printf("# model %s: %s\n# %-8s %-16s %-8s %12s  %s\n", sample ? argv[0] : m->name,
           m->description, "kind", "name", "unit", "start", "description");
    print_vars("state", m->states, m->n_states);
    for (size_t i = 0; i < m->n_states; i++) {
        char der[128];
        snprintf(der, sizeof der, "der(%s)", m->states[i].name);
        char unit[64]; /* as the result files write it */
        lv_unit_per_second(m->states[i].unit, unit, sizeof unit);
        printf("%-10s %-16s %-8s %12s  Time derivative of %s\n", "derivative", der, unit, "",
               m->states[i].name);
    }
    print_vars("parameter", m->params, m->n_params);
    print_vars("output", m->outputs, m->n_outputs);
    for (size_t i = 0; i < m->n_events; i++)
        printf("%-10s %-16s %-8s %12s  %s\n", "event", m->events[i].name,
               m->events[i].direction > 0   ? "rising"
               : m->events[i].direction < 0 ? "falling"
                                            : "both",
               "", m->events[i].description);
    lv_phase_types_sample_free(sample);
    return EXIT_OK;
}

const cli_cmd cli_cmd_vars = {
    "vars",
    "list a model's variables (kind, name, unit, start value)",
    "MODEL",
    "Lists every variable of a mission model type or a built-in model (see 'lvsim models'),\n"
    "one a line: kind (state, derivative, parameter, output, event), name, unit (SI; '1'\n"
    "dimensionless), default start value and description. For a mission type (dof3,\n"
    "flat6) these are the names a phase's 'set:' takes (states, parameters) and the\n"
    "columns of its result files, listed for a sample phase of one stage; before them, what\n"
    "a root phase takes from 'parameters:', the type's own phase keys and the 'end:'\n"
    "conditions. For a built-in model every state and parameter can be given a start value\n"
    "with 'lvsim simulate MODEL --set NAME=VALUE'; every variable, and 'time', can be read\n"
    "with '--final NAME'. An event's unit column gives its direction.\n",
    vars_run,
};
