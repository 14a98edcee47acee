/* cmd_fmu.c - `lvsim fmu MISSION.yaml --phase NAME -o NAME.fmu`: one phase of a mission as an
 * FMI 2.0 FMU, Model Exchange and Co-Simulation in one archive (lv_fmu_export, docs/fmi.md).
 */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "common.h"
#include "lvsim/lv_fmu.h"

static int fmu_run(const cli_cmd *self, int argc, char **argv)
{
    const char *path = NULL, *phase = NULL, *out = NULL, *id = NULL, *rows = NULL;
    double max_rows = CLI_DEFAULT_MAX_ROWS;
    int force = 0;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--force") == 0) {
            force = 1;
        } else if (strcmp(a, "--phase") == 0 || strcmp(a, "-o") == 0 ||
            strcmp(a, "--model-identifier") == 0 || strcmp(a, "--max-rows") == 0) {
            const char *v = option_value(argc, argv, &i);
            if (v == NULL)
                return usage_error(self, "missing value for option", a);
            /* one value each: a repeated option is refused, never silently the last one */
            const char **slot = strcmp(a, "--phase") == 0 ? &phase
                                : strcmp(a, "-o") == 0    ? &out
                                : strcmp(a, "--max-rows") == 0 ? &rows
                                                               : &id;
            if (*slot != NULL) {
                char what[64];
                snprintf(what, sizeof what, "%s given twice; the second is", a);
                return usage_error(self, what, v);
            }
            *slot = v;
            if (slot == &rows && !parse_count(v, &max_rows))
                return usage_error(self, "--max-rows needs a whole number from 1 to 1e15, got", v);
        } else if (is_option(a)) {
            return usage_error(self, "unknown option", a);
        } else if (path != NULL) {
            return usage_error(self, "unexpected argument", a);
        } else {
            path = a;
        }
    }
    if (path == NULL)
        return usage_error(self, "fmu needs a mission file", NULL);
    if (phase == NULL)
        return usage_error(self, "fmu needs the phase to export: --phase NAME", NULL);
    if (out == NULL)
        return usage_error(self, "fmu needs the output file: -o NAME.fmu", NULL);
    /* the mission read as `lvsim check` and `run` read it (their messages: a folder, a
     * missing file), and the same bound on the rows a phase writes: the FMU's
     * DefaultExperiment stepSize is the phase's output interval, the step an importer samples
     * at */
    lv_mission *m;
    int code = load_mission(path, &m);
    if (code != EXIT_OK)
        return code;
    code = check_output_bound_as(m, max_rows, 0.0, 0, "fmu", 1);
    lv_err err;
    /* never an input; an existing file only with --force (lv_output_check) */
    if (code == EXIT_OK && lv_output_check(out, m, force ? LV_OUTPUT_REPLACE : 0u, &err) != LV_OK)
        code = print_err("lvsim fmu", &err, EXIT_INPUT);
    lv_mission_free(m);
    if (code != EXIT_OK)
        return code;
    lv_fmu_options opt = {0};
    opt.model_identifier = id;
    lv_fmu_info info;
    lv_status st = lv_fmu_export(path, phase, out, &opt, &info, &err);
    if (st != LV_OK)
        return print_err("lvsim fmu", &err, exit_code_for(st));
    printf("wrote %s: FMI 2.0 Model Exchange and Co-Simulation, model identifier %s\n", out,
           info.model_identifier);
    printf("  phase '%s': %zu states, %zu parameters, %zu outputs, %zu event indicators; "
           "t = %.9g .. %.9g s\n", phase, info.n_states, info.n_params, info.n_outputs,
           info.n_event_indicators, info.start_time, info.stop_time);
    printf("  resources: the mission file and %zu data file%s; guid %s\n", info.n_files - 1,
           info.n_files == 2 ? "" : "s", info.guid);
    return EXIT_OK;
}

const cli_cmd cli_cmd_fmu = {
    "fmu",
    "export one phase's model as an FMI 2.0 FMU (Model Exchange and Co-Simulation)",
    "MISSION.yaml --phase NAME -o FILE.fmu [--force] [--model-identifier ID] [--max-rows N]",
    "Writes an FMI 2.0 FMU of the phase's model: modelDescription.xml (states, derivatives,\n"
    "parameters and outputs with units and start values, event indicators, ModelStructure),\n"
    "the binary binaries/linux64/ID.so and the mission with its data files in resources/.\n"
    "A child phase's start values are its parent's final state: the ancestors are simulated\n"
    "now, and again by the FMU when it is instantiated. The phase's ends stop the FMU\n"
    "(terminateSimulation; fmi2Discard with fmi2Terminated in Co-Simulation). See docs/fmi.md.\n"
    "  --phase NAME             the phase to export (required)\n"
    "  -o FILE.fmu              the archive to write (required; written whole or not at all;\n"
    "                           it must end in .fmu and must not be the mission or one of its\n"
    "                           data files; an existing file is refused unless --force)\n"
    "  --force                  replace an existing FILE.fmu (never an input)\n"
    "  --model-identifier ID    the FMU's modelIdentifier, a C identifier (default: the mission's\n"
    "                           and the phase's names, e.g. kourou_leo_ascent)\n"
    "  --max-rows N             output rows one phase may write by its stop time (default 1e6),\n"
    "                           end events or not: the FMU's stepSize is the phase's output\n"
    "                           interval, and an importer samples it up to stopTime\n"
    "Each option may be given once.\n"
    "Exit codes: 2 bad input (unknown phase, unwritable path, an output that is an input),\n"
    "3 an ancestor phase failed.\n",
    fmu_run,
};
