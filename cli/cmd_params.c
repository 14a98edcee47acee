/* cmd_params.c - `lvsim params MISSION.yaml`: the run parameters of a mission, the numbers a
 * run may vary (lv_mission_param_count / lv_mission_param_info): name, value, unit, allowed
 * values and where the file writes it; as text or JSON (cJSON).
 */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "common.h"

/* [{name, value, unit, rule, line}], line null for a default the file does not write. */
static cJSON *params_json(const lv_mission *m)
{
    cJSON *doc = cJSON_CreateArray();
    if (doc == NULL)
        return NULL;
    for (size_t i = 0; i < lv_mission_param_count(m); i++) {
        lv_param_info p;
        lv_mission_param_info(m, i, &p);
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "name", p.name);
        cJSON_AddNumberToObject(o, "value", p.value);
        cJSON_AddStringToObject(o, "unit", p.unit);
        cJSON_AddStringToObject(o, "rule", p.rule);
        if (p.line > 0)
            cJSON_AddNumberToObject(o, "line", p.line);
        else
            cJSON_AddNullToObject(o, "line");
        cJSON_AddItemToArray(doc, o);
    }
    return doc;
}

static void print_params(const char *path, const lv_mission *m)
{
    const size_t n = lv_mission_param_count(m);
    printf("# mission '%s' (%s): %zu parameters\n", lv_mission_name(m), path, n);
    int w = 10;  /* the allowed-values column: as wide as its widest rule */
    int wn = 32; /* the names' column likewise (a breaker: 40-character names shifted the
                  * value column out of line) */
    int wu = 8;  /* and the units' (a table's unit may be longer: "kg.m2/s2") */
    for (size_t i = 0; i < n; i++) {
        lv_param_info p;
        lv_mission_param_info(m, i, &p);
        if ((int)strlen(p.rule) > w)
            w = (int)strlen(p.rule);
        if ((int)strlen(p.name) > wn)
            wn = (int)strlen(p.name);
        if ((int)strlen(p.unit) > wu)
            wu = (int)strlen(p.unit);
    }
    /* %.10g of a double is at most 16 characters ("-1.234567891e-100"'s 17 with a 3-digit
     * exponent: the column then grows by one for that line only) */
    printf("# %-*s %16s  %-*s %-*s %s\n", wn - 2, "name", "value", wu, "unit", w, "allowed",
           "line");
    for (size_t i = 0; i < n; i++) {
        lv_param_info p;
        lv_mission_param_info(m, i, &p);
        char line[32];
        if (p.line > 0)
            snprintf(line, sizeof line, "%d", p.line);
        else
            snprintf(line, sizeof line, "default");
        printf("%-*s %16.10g  %-*s %-*s %s\n", wn, p.name, p.value, wu,
               p.unit[0] ? p.unit : LV_UNIT_DIMENSIONLESS, w, p.rule, line);
    }
}

static int params_run(const cli_cmd *self, int argc, char **argv)
{
    const char *path = NULL;
    int json = 0;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--json") == 0)
            json = 1;
        else if (is_option(a))
            return usage_error(self, "unknown option", a);
        else if (path != NULL)
            return usage_error(self, "unexpected argument", a);
        else
            path = a;
    }
    if (path == NULL)
        return usage_error(self, "params needs a mission file", NULL);
    lv_mission *m;
    int rc = load_mission(path, &m);
    if (rc != EXIT_OK)
        return rc;
    if (json)
        rc = print_json(params_json(m));
    else
        print_params(path, m);
    lv_mission_free(m);
    return rc;
}

const cli_cmd cli_cmd_params = {
    "params",
    "list a mission's run parameters (the numbers a run may vary)",
    "MISSION.yaml [--json]",
    "Reads a mission file (as 'lvsim check') and lists its run parameters, the numbers a\n"
    "run may vary (lv_run_set): every numeric key of the file, such as start_h,\n"
    "stage2.propellant_mass, P2.stop_time or P2.set.theta, and the per-phase defaults the\n"
    "file does not write. One a line: name, value (SI: angles in rad, the file's *_deg\n"
    "keys converted), unit ('1' dimensionless), allowed values (may hold spaces: '> 0'),\n"
    "and the line of the file that writes it, or 'default'. A bad mission file exits 2.\n"
    "\n"
    "options:\n"
    "  --json                  print a JSON array of {name, value, unit, rule, line}\n"
    "                          objects (line null for a default)\n",
    params_run,
};
