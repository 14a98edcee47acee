/* cmd_export.c - `lvsim export OUTDIR`: the trajectory exports (CZML, KML, CCSDS OEM) from a
 * results folder alone, through liblvsim_post (lv_export_run).
 */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "common.h"

static int export_run(const cli_cmd *self, int argc, char **argv)
{
    const char *dir = NULL;
    unsigned formats = 0;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--format") == 0) {
            const char *f = option_value(argc, argv, &i);
            if (f == NULL)
                return usage_error(self, "missing value for option", a);
            if (strstr(f, "czml")) formats |= LV_EXPORT_CZML;
            if (strstr(f, "kml")) formats |= LV_EXPORT_KML;
            if (strstr(f, "oem")) formats |= LV_EXPORT_OEM;
            if (formats == 0)
                return usage_error(self, "--format takes czml, kml, oem (comma-separated), got",
                                   f);
        } else if (is_option(a)) {
            return usage_error(self, "unknown option", a);
        } else if (dir != NULL) {
            return usage_error(self, "unexpected argument", a);
        } else {
            dir = a;
        }
    }
    if (dir == NULL)
        return usage_error(self, "export needs a results folder (lvsim run -o OUTDIR)", NULL);
    lv_err err;
    lv_status st = lv_export_run(dir, formats ? formats : LV_EXPORT_ALL, &err);
    if (st != LV_OK)
        return print_err("lvsim export", &err, exit_code_for_input(st));
    printf("exports written to %s/ (mission.czml, mission.kml, <stage>.oem for orbital "
           "portions)\n", dir);
    return EXIT_OK;
}

const cli_cmd cli_cmd_export = {
    "export",
    "trajectory exports (CZML, KML, OEM) from a results folder",
    "OUTDIR [--format czml,kml,oem]",
    "Writes the trajectory exports from a results folder written by 'lvsim run -o OUTDIR'\n"
    "(docs/exports.md): OUTDIR/mission.czml (CesiumJS), mission.kml (Google Earth) and\n"
    "<stage>.oem (CCSDS OEM, orbital portions only). Exits 2 when the folder has no\n"
    "summary.json or a file is malformed (named with its line).\n"
    "\n"
    "options:\n"
    "  --format F              czml, kml, oem, comma-separated (default: all three)\n",
    export_run,
};
