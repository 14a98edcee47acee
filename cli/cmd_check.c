/* cmd_check.c - `lvsim check MISSION.yaml`: reads and validates a mission with
 * lv_mission_load, the same call `lvsim run` makes, so both accept exactly the same files;
 * then what every phase would write at most, refused beyond --max-rows as `run` does.
 */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "common.h"

static int check_run(const cli_cmd *self, int argc, char **argv)
{
    const char *path = NULL;
    double max_rows = CLI_DEFAULT_MAX_ROWS;
    int quiet = 0;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--max-rows") == 0) {
            const char *v = option_value(argc, argv, &i);
            if (v == NULL)
                return usage_error(self, "missing value for option", a);
            if (!parse_count(v, &max_rows))
                return usage_error(self, "--max-rows needs a whole number from 1 to 1e15, got", v);
        } else if (strcmp(a, "--quiet") == 0 || strcmp(a, "-q") == 0) {
            quiet = 1;
        } else if (is_option(a)) {
            return usage_error(self, "unknown option", a);
        } else if (path != NULL) {
            return usage_error(self, "check takes one mission file; unexpected argument", a);
        } else {
            path = a;
        }
    }
    if (path == NULL)
        return usage_error(self, "check takes one mission file", NULL);
    lv_mission *m;
    int code = load_mission(path, &m);
    if (code != EXIT_OK)
        return code;
    /* the row limit first: a file refused for it is not called valid */
    code = check_output_bound(m, max_rows, 0.0, 0);
    if (code == EXIT_OK) {
        printf("%s: mission '%s' is valid: %zu phases\n", path, lv_mission_name(m),
               lv_mission_phase_count(m));
        if (!quiet)
            code = check_output_bound(m, max_rows, 0.0, 1);
    }
    lv_mission_free(m);
    return code;
}

const cli_cmd cli_cmd_check = {
    "check",
    "validate a mission file without running it",
    "MISSION.yaml [--max-rows N] [--quiet]",
    "Reads and validates a mission file exactly as 'lvsim run' does, and runs nothing:\n"
    "YAML syntax, keys, types, ranges, references, cycles, masses, tables, and that every\n"
    "phase's model and initial state can be built (docs/mission-format.md). Prints\n"
    "'FILE: mission 'NAME' is valid: N phases', then per phase the most it can write: rows\n"
    "(its output grid over its longest possible duration, by its stop time or a time end;\n"
    "each event adds two), columns, the size of its .mat and .csv, and what ends it. A phase\n"
    "that only its stop time ends and that is above --max-rows rows is refused, as 'lvsim\n"
    "run' refuses it, naming the phase, rows, bytes and the limit; a phase with an end event\n"
    "is not (its end usually comes first: 'run' stops it at the limit if it does not).\n"
    "Errors: 'file:line:column: message' on stderr, exit 2.\n"
    "\n"
    "options:\n"
    "  --max-rows N            output rows one phase may write (default 1e6)\n"
    "  --quiet, -q             no table of estimates\n",
    check_run,
};
