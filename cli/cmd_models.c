/* cmd_models.c - `lvsim models` (the built-in models) and `lvsim vars MODEL` (a model's
 * states, derivatives, parameters, outputs and events): both list the model registry.
 */
#include <stdio.h>

#include "cli.h"
#include "common.h"

static int models_run(const cli_cmd *self, int argc, char **argv)
{
    if (argc != 0) {
        const char *what = is_option(argv[0]) ? "unknown option" : "models takes no arguments; got";
        return usage_error(self, what, argv[0]);
    }
    for (const lv_model_def *const *all = lv_models_all(); *all; all++)
        printf("%-18s %s\n", (*all)->name, (*all)->description);
    return EXIT_OK;
}

const cli_cmd cli_cmd_models = {
    "models",
    "list the built-in models",
    "",
    "Lists the built-in models, one a line: name and a one-line description.\n"
    "'lvsim vars MODEL' lists a model's variables; 'lvsim simulate MODEL' runs it.\n",
    models_run,
};

static void print_vars(const char *kind, const lv_var *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        printf("%-10s %-16s %-8s %12g  %s\n", kind, v[i].name, v[i].unit[0] ? v[i].unit : "-",
               v[i].start, v[i].description);
}

static int vars_run(const cli_cmd *self, int argc, char **argv)
{
    if (argc != 1)
        return usage_error(self, "vars takes one model name", NULL);
    if (is_option(argv[0]))
        return usage_error(self, "unknown option", argv[0]);
    const lv_model_def *m = find_model(argv[0]);
    if (m == NULL)
        return EXIT_INPUT;
    printf("# model %s: %s\n# %-8s %-16s %-8s %12s  %s\n", m->name, m->description, "kind",
           "name", "unit", "start", "description");
    print_vars("state", m->states, m->n_states);
    for (size_t i = 0; i < m->n_states; i++) {
        char der[128];
        snprintf(der, sizeof der, "der(%s)", m->states[i].name);
        printf("%-10s %-16s %-8s %12s  Time derivative of %s\n", "derivative", der, "-", "",
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
    return EXIT_OK;
}

const cli_cmd cli_cmd_vars = {
    "vars",
    "list a model's variables (kind, name, unit, start value)",
    "MODEL",
    "Lists every variable of a built-in model (see 'lvsim models'), one a line: kind\n"
    "(state, derivative, parameter, output, event), name, unit (SI; '-' dimensionless),\n"
    "default start value and description. Every state and parameter can be given a start\n"
    "value with 'lvsim simulate MODEL --set NAME=VALUE'; every variable, and 'time', can be\n"
    "read with '--final NAME'. An event's unit column gives its direction.\n",
    vars_run,
};
