/* lv_plot.h - after a run: figures (PNG and SVG, drawn with PLplot) and an index.html report
 * from the files a run left in its output directory (summary.json, body_<stage>.csv and the
 * phase CSVs). Post-processing only; the simulation knows nothing about it. docs/visualization.md.
 *
 * Thread safety: PLplot keeps global state (its table of streams, the current stream). Each
 * figure gets its own PLplot stream, made and ended inside the call, and the caller's current
 * stream is restored, but two lv_plot_run() calls (or other PLplot users) must not run at the
 * same time in one process. Run it after lv_run_execute() has returned, from one thread.
 */
#ifndef LVSIM_LV_PLOT_H
#define LVSIM_LV_PLOT_H

#include "lvsim/lv_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Reads OUTDIR/summary.json (lv_run_write_summary), the body trajectories and the phase
 * CSVs it names, and writes
 *   OUTDIR/plots/<quantity>.png and .svg   one figure per quantity, every body a curve over
 *                                          all its phases, phase starts as labelled lines:
 *                                          altitude, speed (relative and inertial), mass, mach,
 *                                          dynamic_pressure, load_factor, flight_path_angle,
 *                                          acceleration, thrust; a quantity no phase file has
 *                                          (Mach in a flat world) is skipped;
 *   OUTDIR/plots/ground_track.png/.svg     latitude/longitude of every body over coastlines;
 *   OUTDIR/plots/fig10_normalised.png/.svg speed / its maximum and mass / initial mass per body
 *                                          over all phases (the paper's Figure 10);
 *   OUTDIR/index.html                      mission, phase table, events, the figures, links to
 *                                          the result files and to viewer/index.html.
 * Every file is written under a temporary name and renamed. Prints nothing.
 * Errors: LV_ERR_IO naming the file (a missing or unwritable file), LV_ERR_INPUT naming the
 * file and line (a malformed summary or CSV), LV_ERR_NOMEM. */
LV_API lv_status lv_plot_run(const char *outdir, lv_err *err);

#ifdef __cplusplus
}
#endif
#endif
