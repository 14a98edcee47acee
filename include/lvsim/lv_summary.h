/* lv_summary.h - what a run leaves in its results folder besides the phases' own files:
 * summary.json and one merged trajectory per body. The post-processing (exports, plots, the
 * report, the 3-D view) reads these files; docs/result-files.md describes them. */
#ifndef LVSIM_LV_SUMMARY_H
#define LVSIM_LV_SUMMARY_H

#include "lvsim/lv_mission.h"
#include "lvsim/lv_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Writes OUTDIR/summary.json (the epoch and "time": TAI - UTC at the epoch, the UTC of the
 * first start and the last end, the leap seconds between with their mission times, a note
 * when the dates lie past ERFA's leap-second table; per phase: start and end time, why it
 * ended, events, statistics, the hand-off, the final state, its files; per body: the phases
 * it flies in and its merged trajectory file) and OUTDIR/body_<stage>.csv for every stage
 * that flew (needs the run's rows: lv_run_options.no_rows = 0). Each file is written under a
 * temporary name and renamed. Errors: LV_ERR_IO naming the file, LV_ERR_NOMEM. */
LV_API lv_status lv_run_write_summary(const lv_run *r, const char *outdir, lv_err *err);

/* The same, choosing the files (lvsim run --outputs): LV_SUMMARY_JSON (summary.json; it names
 * the body files only when they are written too) and/or LV_SUMMARY_BODIES (body_<stage>.csv).
 * lv_run_write_summary writes both. */
#define LV_SUMMARY_JSON 1u
#define LV_SUMMARY_BODIES 2u
LV_API lv_status lv_run_write_summary_files(const lv_run *r, const char *outdir, unsigned what,
                                            lv_err *err);

#ifdef __cplusplus
}
#endif
#endif
