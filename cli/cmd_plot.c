/* cmd_plot.c - `lvsim plot OUTDIR`: the figures (PLplot) and index.html of a results folder,
 * through liblvsim_post (lv_plot_run).
 */
#include <stdio.h>

#include "cli.h"
#include "common.h"

static int plot_run(const cli_cmd *self, int argc, char **argv)
{
    if (argc == 1 && is_option(argv[0]))
        return usage_error(self, "unknown option", argv[0]);
    if (argc != 1)
        return usage_error(self, "plot takes one results folder (lvsim run -o OUTDIR)", NULL);
    lv_err err;
    lv_status st = lv_plot_run(argv[0], &err);
    if (st != LV_OK)
        return print_err("lvsim plot", &err, exit_code_for_input(st));
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
    "Exits 2 when the folder cannot be read.\n",
    plot_run,
};
