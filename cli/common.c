/* common.c - helpers shared by the lvsim commands: exit codes, usage errors, number
 * parsing, library errors, model lookup and JSON output.
 */
#include "common.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int exit_code_for(lv_status st)
{
    switch (st) {
    case LV_OK: return EXIT_OK;
    case LV_ERR_SOLVER: return EXIT_SIM;
    case LV_ERR_NOMEM: return EXIT_INTERNAL;
    default: return EXIT_INPUT;
    }
}

int exit_code_for_input(lv_status st)
{
    const int code = exit_code_for(st);
    return code == EXIT_SIM ? EXIT_INPUT : code;
}

void print_usage_line(FILE *f, const cli_cmd *cmd)
{
    fprintf(f, "usage: lvsim %s%s%s\n", cmd->name, cmd->usage[0] ? " " : "", cmd->usage);
}

int usage_error(const cli_cmd *cmd, const char *what, const char *arg)
{
    fprintf(stderr, "lvsim: %s%s%s%s\n", what, arg ? " '" : "", arg ? arg : "", arg ? "'" : "");
    if (cmd != NULL) {
        print_usage_line(stderr, cmd);
        fprintf(stderr, "(see 'lvsim help %s')\n", cmd->name);
    } else {
        fprintf(stderr, "(see 'lvsim help')\n");
    }
    return EXIT_INPUT;
}

int is_option(const char *arg)
{
    double v;
    return arg[0] == '-' && arg[1] != '\0' && !parse_double(arg, &v);
}

const char *option_value(int argc, char **argv, int *i)
{
    if (*i + 1 >= argc)
        return NULL;
    return argv[++*i];
}

int parse_double(const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE || !isfinite(v))
        return 0;
    *out = v;
    return 1;
}

int parse_int(const char *s, int *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end != '\0' || errno == ERANGE || v < 0 || v > 100000000)
        return 0;
    *out = (int)v;
    return 1;
}

int print_err(const char *who, const lv_err *err, int code)
{
    if (who != NULL)
        fprintf(stderr, "%s: %s\n", who, err->msg);
    else
        fprintf(stderr, "%s\n", err->msg);
    return code;
}

const lv_model_def *find_model(const char *name)
{
    const lv_model_def *m = lv_models_find(name);
    if (m == NULL) {
        fprintf(stderr, "lvsim: unknown model '%s'; built-in models:", name);
        for (const lv_model_def *const *all = lv_models_all(); *all; all++)
            fprintf(stderr, " %s", (*all)->name);
        fprintf(stderr, "\n");
    }
    return m;
}

int print_json(cJSON *doc)
{
    char *text = doc != NULL ? cJSON_Print(doc) : NULL;
    cJSON_Delete(doc);
    if (text == NULL) {
        fprintf(stderr, "lvsim: out of memory writing JSON\n");
        return EXIT_INTERNAL;
    }
    fputs(text, stdout);
    putchar('\n');
    cJSON_free(text);
    return EXIT_OK;
}
