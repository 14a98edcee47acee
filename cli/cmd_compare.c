/* cmd_compare.c - `lvsim compare MISSION.yaml`: the mission run sequentially and as one
 * end-to-end model (lv_mission_compare), as the paper's Table 2; text or JSON (cJSON).
 */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "common.h"

static cJSON *side_json(const lv_compare_side *sd)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "method", sd->method);
    cJSON_AddNumberToObject(o, "tolerance", sd->tolerance);
    cJSON_AddNumberToObject(o, "states", (double)sd->n_states);
    cJSON_AddNumberToObject(o, "state_events", (double)sd->state_events);
    cJSON_AddNumberToObject(o, "time_events", (double)sd->time_events);
    cJSON_AddNumberToObject(o, "steps", (double)sd->steps);
    cJSON_AddNumberToObject(o, "rhs_evals", (double)sd->rhs_evals);
    cJSON_AddNumberToObject(o, "rhs_evals_steps", (double)sd->rhs_evals_steps);
    cJSON_AddNumberToObject(o, "rhs_evals_output", (double)sd->rhs_evals_output);
    cJSON_AddNumberToObject(o, "jac_evals", (double)sd->jac_evals);
    cJSON_AddNumberToObject(o, "cpu_time", sd->cpu_time);
    return o;
}

/* {mission, output_interval, end_to_end {...}, sequential {...}, bodies [{name,
 * common_times, max_dpos, max_dvel, max_dmass}]} */
static cJSON *report_json(const char *path, double dt, const lv_compare_report *rep)
{
    cJSON *doc = cJSON_CreateObject();
    if (doc == NULL)
        return NULL;
    cJSON_AddStringToObject(doc, "mission", path);
    cJSON_AddNumberToObject(doc, "output_interval", dt);
    cJSON_AddItemToObject(doc, "end_to_end", side_json(&rep->e2e));
    cJSON_AddItemToObject(doc, "sequential", side_json(&rep->seq));
    cJSON *bodies = cJSON_AddArrayToObject(doc, "bodies");
    for (size_t b = 0; b < rep->n_bodies; b++) {
        const lv_compare_body *bd = &rep->bodies[b];
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "name", bd->name);
        cJSON_AddNumberToObject(o, "common_times", (double)bd->n_common);
        cJSON_AddNumberToObject(o, "max_dpos", bd->max_dpos);
        cJSON_AddNumberToObject(o, "max_dvel", bd->max_dvel);
        cJSON_AddNumberToObject(o, "max_dmass", bd->max_dmass);
        cJSON_AddItemToArray(bodies, o);
    }
    return doc;
}

static void print_table(const char *path, double dt, const lv_compare_report *rep)
{
    printf("%s: end-to-end versus sequential (the paper's Table 2)\n\n", path);
    printf("%-28s %14s %14s\n", "", "end-to-end", "sequential");
    printf("%-28s %14s %14s\n", "integration method", rep->e2e.method, rep->seq.method);
    printf("%-28s %14g %14g\n", "integration tolerance", rep->e2e.tolerance, rep->seq.tolerance);
    printf("%-28s %14zu %14zu\n", "number of states", rep->e2e.n_states, rep->seq.n_states);
    printf("%-28s %14ld %14ld\n", "state events (total)", rep->e2e.state_events,
           rep->seq.state_events);
    printf("%-28s %14ld %14ld\n", "time events (total)", rep->e2e.time_events,
           rep->seq.time_events);
    printf("%-28s %14ld %14ld\n", "steps", rep->e2e.steps, rep->seq.steps);
    printf("%-28s %14ld %14ld\n", "RHS evaluations", rep->e2e.rhs_evals, rep->seq.rhs_evals);
    printf("%-28s %14ld %14ld\n", "  on steps", rep->e2e.rhs_evals_steps, rep->seq.rhs_evals_steps);
    printf("%-28s %14ld %14ld\n", "  on output", rep->e2e.rhs_evals_output,
           rep->seq.rhs_evals_output);
    printf("%-28s %14ld %14ld\n", "Jacobian evaluations", rep->e2e.jac_evals,
           rep->seq.jac_evals);
    printf("%-28s %14.3f %14.3f\n", "CPU time [ms]", 1e3 * rep->e2e.cpu_time,
           1e3 * rep->seq.cpu_time);
    printf("\nlargest difference at every %g s output time of the sequential phases:\n", dt);
    printf("%-12s %8s %14s %14s %14s\n", "body", "times", "position [m]", "velocity [m/s]",
           "mass [kg]");
    for (size_t b = 0; b < rep->n_bodies; b++)
        printf("%-12s %8zu %14.3e %14.3e %14.3e\n", rep->bodies[b].name, rep->bodies[b].n_common,
               rep->bodies[b].max_dpos, rep->bodies[b].max_dvel, rep->bodies[b].max_dmass);
}

static int compare_run(const cli_cmd *self, int argc, char **argv)
{
    const char *path = NULL, *method = NULL;
    double tol = 0.0, dt = 1.0, max_rows = CLI_DEFAULT_MAX_ROWS;
    int json = 0;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--json") == 0) {
            json = 1;
        } else if (strcmp(a, "--max-rows") == 0) {
            const char *v = option_value(argc, argv, &i);
            if (v == NULL)
                return usage_error(self, "missing value for option", a);
            if (!parse_count(v, &max_rows))
                return usage_error(self, "--max-rows needs a whole number from 1 to 1e15, got", v);
        } else if (strcmp(a, "--method") == 0 || strcmp(a, "--tolerance") == 0 ||
                   strcmp(a, "--interval") == 0) {
            const char *v = option_value(argc, argv, &i);
            if (v == NULL)
                return usage_error(self, "missing value for option", a);
            if (a[2] == 'm' && !parse_method_option(self, a, v))
                return EXIT_INPUT;
            if (a[2] == 'm')
                method = v;
            else if (a[2] == 't' && !parse_tolerance_option(self, a, v, &tol))
                return EXIT_INPUT;
            else if (a[2] == 'i' && !parse_interval_option(self, a, v, &dt))
                return EXIT_INPUT;
        } else if (is_option(a)) {
            return usage_error(self, "unknown option", a);
        } else if (path != NULL) {
            return usage_error(self, "unexpected argument", a);
        } else {
            path = a;
        }
    }
    if (path == NULL)
        return usage_error(self, "compare needs a mission file", NULL);
    lv_compare_report rep;
    lv_err err;
    lv_mission *m = NULL;
    const int code = load_mission(path, &m);
    if (code != EXIT_OK)
        return code;
    lv_status st = lv_mission_compare(m, method, tol, dt, max_rows, &rep, &err);
    lv_mission_free(m);
    if (st != LV_OK)
        return print_err(NULL, &err, exit_code_for(st));
    if (json)
        return print_json(report_json(path, dt, &rep));
    print_table(path, dt, &rep);
    return EXIT_OK;
}

const cli_cmd cli_cmd_compare = {
    "compare",
    "sequential versus end-to-end simulation (the paper's Table 2)",
    "MISSION.yaml [--method M] [--tolerance TOL] [--interval DT] [--max-rows N] [--json]",
    "Runs a flat-world mission sequentially, phase by phase, and as one end-to-end model\n"
    "carrying every stage from liftoff (separations at the times the phases split the\n"
    "stack), and prints the paper's Table 2 (method, tolerance, states, events, steps,\n"
    "RHS and Jacobian evaluations, CPU time) and each body's largest difference in\n"
    "position [m], velocity [m/s] and mass [kg] at every output time of its sequential\n"
    "phases (the end-to-end model read there; event and separation instants left out).\n"
    "\n"
    "options:\n"
    "  --method M              integration method of both runs (default: each phase's own)\n"
    "  --tolerance TOL         relative tolerance of both runs, 1e-14 to 0.1 (default: each\n"
    "                          phase's own)\n"
    "  --interval DT           output interval of both runs [s], > 0 (default 1)\n"
    "  --max-rows N            output rows one sequential phase may hold in memory (default\n"
    "                          1e6): a phase beyond it is refused before anything runs\n"
    "  --json                  print the comparison as one JSON object\n",
    compare_run,
};
