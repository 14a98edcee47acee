/* cmd_plot.c - `lvsim plot OUTDIR`: the figures (PLplot) and index.html of a results folder,
 * through liblvsim_post (lv_plot_run).
 */
#include <stdio.h>

#include "cli.h"
#include "common.h"
#include "progress.h"

static int plot_run(const cli_cmd *self, int argc, char **argv)
{
    if (argc == 1 && is_option(argv[0]))
        return usage_error(self, "unknown option", argv[0]);
    if (argc != 1)
        return usage_error(self, "plot takes one results folder (lvsim run -o OUTDIR)", NULL);
    lv_err err;
    lv_outdir *od;
    lv_status st = lv_outdir_open(argv[0], &od, &err);
    if (st != LV_OK)
        return print_err("lvsim plot", &err, exit_code_for_input(st));
    cli_progress *prog = progress_new(0, 0);
    progress_step_begin(prog, "plots and index.html");
    st = lv_plot_run(lv_outdir_path(od), &err); /* a replica of the folder, see lv_outdir.h */
    if (st != LV_OK)
        restage(err.msg, sizeof err.msg, lv_outdir_path(od), lv_outdir_final(od));
    progress_step_end(prog);
    progress_free(prog);
    if (st != LV_OK) { /* nothing committed: the folder stays as it was, its manifest too */
        lv_outdir_free(od);
        return print_err("lvsim plot", &err, exit_code_for_input(st));
    }
    lv_err merr;
    const lv_outdir_record rec = {"plot", "ok", NULL, 0, NULL};
    lv_status mst = lv_outdir_commit(od, &rec, &merr);
    lv_outdir_free(od);
    if (mst != LV_OK)
        return print_err("lvsim plot", &merr, exit_code_for_input(mst));
    printf("plots in %s/plots/, report %s/index.html\n", argv[0], argv[0]);
    return EXIT_OK;
}

const cli_cmd cli_cmd_plot = {
    "plot",
    "plots and index.html from a results folder",
    "OUTDIR",
    "Draws the plots of a results folder written by 'lvsim run -o OUTDIR' into\n"
    "OUTDIR/plots/ (PLplot, PNG and SVG: altitude, speed, mass, thrust, ... against time,\n"
    "one curve per body; the ground track) and the report OUTDIR/index.html\n"
    "(docs/visualization.md). 'lvsim run' does this itself unless given --no-plots.\n"
    "Updates OUTDIR/manifest.json. Exits 2 when the folder cannot be read or is in use by\n"
    "another lvsim.\n",
    plot_run,
};
