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

/* ---- a body's timeline (docs/result-files.md, "timeline") ------------------------------- */

#define LV_TIMELINE_LABEL_MAX 288 /* bytes: a 63-character name of 4-byte UTF-8 characters, a prefix */

/* One event of a body's flight, with the state of the row that gives it: lift-off, max-q,
 * each end of a phase it flies in (by the user's name, `name: MECO`, or a label made from the
 * end condition: "burnout", "altitude 110 km"), burnouts and named events within a phase,
 * and each separation of stages it takes part in, once. */
typedef struct lv_timeline_row {
    char label[LV_TIMELINE_LABEL_MAX]; /* "lift-off", "max-q", "MECO", "separation of booster" */
    const char *kind;  /* "start" (a take-off roll's), "liftoff", "max_q", "event" (within a
                          phase), "end" (of a phase), "separation", "crash" (a hand-off
                          that crashed: a touchdown, at its parent's last row; a crash end,
                          a roll off the runway, at the phase's last row); static */
    const char *phase; /* the phase whose row gives the values (the mission's string) */
    const char *event; /* the condition or event as the results name it ("propellant_left",
                          "burnout", "stop_time", "failed"); NULL for lift-off, max-q and a
                          separation */
    int named;         /* 1: label is the user's name of the event */
    size_t row;        /* that phase's row (0-based; its CSV file's data row) */
    double t, h, speed, mach, q; /* s, m, m/s, 1, Pa: the row's time, h (z), v_rel (speed),
                                    mach, q_dyn; NAN where the phase's model has none,
                                    and Mach and q where the atmosphere model is not defined
                                    (rho = 0 or h > 1000 km) */
} lv_timeline_row;

/* Its strings are the mission's and the run's: valid while the run holds the phases' results
 * (until a phase runs again, lv_run_free). The last end row of a body is its final state. */
typedef struct lv_timeline {
    const char *body;      /* the stage's name */
    size_t n;
    lv_timeline_row *rows; /* [n], in time order (simultaneous events in flight order) */
} lv_timeline;

/* The timeline of stage s (a body: the phases it flies in, lv_run_body_phases) in run r,
 * from the rows the run kept: every value is that of a row, none interpolated. An end's row
 * is its phase's last, an event's within a phase the first row at its time (the one before
 * it), a separation's the first row of the body's phase after it (the last of the phase it
 * ended for a stage that flies no further), max-q the row of the largest q_dyn where the
 * atmosphere model is defined (rho > 0, h <= 1000 km). LV_ERR_INPUT when the run kept no
 * rows (lv_run_options.no_rows) or s is out of range; LV_ERR_NOMEM. A stage that flew in no
 * done phase has an empty timeline. lv_timeline_free when done. */
LV_API lv_status lv_run_timeline(const lv_run *r, size_t s, lv_timeline **out, lv_err *err);
LV_API void lv_timeline_free(lv_timeline *t); /* accepts NULL */

#ifdef __cplusplus
}
#endif
#endif
