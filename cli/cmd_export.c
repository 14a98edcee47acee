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
            name_list exports = {{0}, 0};
            name_list_add_exports(&exports);
            if (!parse_name_list(self, a, "export", &exports, 0, f, &formats))
                return EXIT_INPUT;
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
    lv_outdir *od;
    lv_status st = lv_outdir_open(dir, &od, &err);
    if (st != LV_OK)
        return print_err("lvsim export", &err, exit_code_for_input(st));
    /* written into a replica of the folder, which replaces it at the commit */
    const char *stage = lv_outdir_path(od);
    lv_export_report rep;
    st = lv_export_run_report(stage, formats ? formats : LV_EXPORT_ALL, &rep, &err);
    if (st != LV_OK) { /* nothing committed: the folder stays as it was, its manifest too */
        restage(err.msg, sizeof err.msg, stage, lv_outdir_final(od));
        lv_export_report_clear(&rep);
        lv_outdir_free(od);
        return print_err("lvsim export", &err, exit_code_for_input(st));
    }
    lv_err merr;
    const lv_outdir_record rec = {"export", "ok", NULL, 0, NULL};
    lv_status mst = lv_outdir_commit(od, &rec, &merr);
    if (mst != LV_OK) { /* what it wrote was not committed: not reported as written */
        lv_export_report_clear(&rep);
        lv_outdir_free(od);
        return print_err("lvsim export", &merr, exit_code_for_input(mst));
    }
    size_t written = 0;
    for (size_t i = 0; i < rep.n; i++) {
        const lv_export_item *it = &rep.items[i];
        if (it->file[0] != '\0') {
            written++;
            printf("export %s: wrote %s/%s%s%s\n", it->format, dir, it->file,
                   it->note[0] ? " - " : "", it->note);
        } else {
            char note[sizeof it->note];
            snprintf(note, sizeof note, "%s", it->note);
            restage(note, sizeof note, stage, lv_outdir_final(od));
            printf("export %s: %s\n", it->format, note);
        }
    }
    lv_export_report_clear(&rep);
    lv_outdir_free(od);
    if (written == 0)
        printf("export: no file written\n");
    return EXIT_OK;
}

const cli_cmd cli_cmd_export = {
    "export",
    "trajectory exports (CZML, KML, OEM) from a results folder",
    "OUTDIR [--format czml,kml,oem]",
    "Writes the trajectory exports from a results folder written by 'lvsim run -o OUTDIR'\n"
    "(docs/exports.md): OUTDIR/mission.czml (CesiumJS), mission.kml (Google Earth) and\n"
    "<stage>.oem (CCSDS OEM, orbital portions only), and says for each format what it\n"
    "wrote or why it wrote nothing (an OEM of a flat-world flight, a body that never\n"
    "leaves the atmosphere). Updates OUTDIR/manifest.json. Exits 2 when the folder has no\n"
    "summary.json, is in use by another lvsim, or a file is malformed (named with its\n"
    "line); the folder is then left as it was.\n"
    "\n"
    "options:\n"
    "  --format F              exports, comma-separated (lvsim formats exports: czml,\n"
    "                          kml, oem; default: all)\n",
    export_run,
};
