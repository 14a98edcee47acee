/* cmd_check.c - `lvsim check MISSION.yaml`: reads and validates a mission with
 * lv_mission_load, the same call `lvsim run` makes, so both accept exactly the same files.
 */
#include <stdio.h>

#include "cli.h"
#include "common.h"

static int check_run(const cli_cmd *self, int argc, char **argv)
{
    if (argc == 1 && is_option(argv[0]))
        return usage_error(self, "unknown option", argv[0]);
    if (argc != 1)
        return usage_error(self, "check takes one mission file", NULL);
    lv_mission *m;
    lv_err err;
    lv_status st = lv_mission_load(argv[0], &m, &err);
    if (st != LV_OK)
        return print_err(NULL, &err, exit_code_for_input(st));
    printf("%s: mission '%s' is valid: %zu phases\n", argv[0], lv_mission_name(m),
           lv_mission_phase_count(m));
    lv_mission_free(m);
    return EXIT_OK;
}

const cli_cmd cli_cmd_check = {
    "check",
    "validate a mission file without running it",
    "MISSION.yaml",
    "Reads and validates a mission file exactly as 'lvsim run' does, and runs nothing:\n"
    "YAML syntax, keys, types, ranges, references, cycles, masses, tables, and that every\n"
    "phase's model and initial state can be built (docs/mission-format.md). Prints\n"
    "'FILE: mission 'NAME' is valid: N phases', or 'file:line:column: message' on stderr\n"
    "and exits 2.\n",
    check_run,
};
