/* lv_campaign.h - Monte Carlo dispersion campaigns (liblvsim_post): N runs of one loaded
 * mission, run i with the values its dispersions draw for (seed, i) (lv_dispersion.h), on a
 * thread pool or across MPI ranks, every run's drawn inputs and every phase's outcome stored
 * in an SQLite database; statistics, figures and exports from that database.
 * Format of `dispersions:`, database schema, statistics: docs/monte-carlo.md.
 *
 *     lv_campaign_options o;  lv_campaign_options_default(&o);
 *     o.n_runs = 10000;  o.seed = 1;  o.threads = 2;  o.db_path = "mc/campaign.db";
 *     lv_campaign_run(m, &o, &prog, &err);          runs, stores, resumable
 *     lv_campaign_stats("mc/campaign.db", "mc", &err);   stats.json, *.csv, footprint.kml
 *
 * Outcomes, not errors: a run whose phase fails (integrator failure, the vehicle leaves its
 * model's domain) or whose drawn value is outside its parameter's range is stored as such and
 * the campaign goes on. Errors (LV_ERR_IO, LV_ERR_INPUT, LV_ERR_NOMEM) are about the campaign
 * itself: the database cannot be written, a resumed database belongs to another campaign.
 *
 * Reproducible: run i's inputs and outcome do not depend on the thread or rank that ran it;
 * rows are keyed by run index, so databases of one (mission, seed, N) have the same contents
 * (sqlite3 .dump) whatever the thread and rank counts, and a killed campaign resumed with
 * `resume` ends with the contents of an uninterrupted one.
 */
#ifndef LVSIM_LV_CAMPAIGN_H
#define LVSIM_LV_CAMPAIGN_H

#include <stddef.h>
#include <stdint.h>

#include "lvsim/lv_mission.h"
#include "lvsim/lv_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct lv_campaign_progress {
    uint64_t total;      /* runs of the campaign */
    uint64_t done;       /* stored, this session's and earlier ones' */
    uint64_t this_session; /* stored by this call */
    uint64_t failed;     /* stored runs with a failed phase or an input out of range */
    double elapsed;      /* s since this call started */
    double rate;         /* runs per second in this call */
    double eta;          /* s left at that rate (NAN before the first run) */
    uint64_t impacts;    /* stored runs where no phase failed but one fell to the ground: it
                            ended by an `impact` end that is not its first written end (an
                            outcome of the flight, not a failure; docs/monte-carlo.md) */
    uint64_t crashed;    /* stored runs where no phase failed but one crashed: a touchdown
                            beyond the landing gear's limits (runs.status `crashed`; an
                            outcome of the flight, neither a failure nor an impact) */
} lv_campaign_progress;

typedef struct lv_campaign_options {
    uint64_t n_runs;      /* runs 0 .. n_runs - 1 (> 0) */
    uint64_t seed;        /* the campaign's seed (the mission's `seed:` by default) */
    int threads;          /* worker threads (<= 0: 1) */
    const char *db_path;  /* the SQLite database, created (required) */
    int resume;           /* 1: continue the database of the same campaign (mission, seed) */
    int overwrite;        /* 1: replace an existing database (else it is an error) */
    uint64_t keep_runs;   /* runs < keep_runs also write result files (phases, summary.json) */
    const char *keep_dir; /* ... into keep_dir/run_<i> (required with keep_runs) */
    const char *method;   /* non-NULL: every phase integrates with it (lv_run_options) */
    double tolerance;     /* nonzero: every phase's tolerance, within [LV_TOLERANCE_MIN,
                             LV_TOLERANCE_MAX] (lv_sim.h; out of range: LV_ERR_INPUT) */
    double output_interval; /* > 0: the output grid of every phase (s); 0: none (only start
                               and end: the fastest; the phases' own grid for kept runs) */
    /* called from the calling thread about every 0.25 s and once at the end */
    void (*progress)(const lv_campaign_progress *p, void *user);
    void *user;
    volatile int *stop;   /* set nonzero (a signal handler): no new run starts and every running
                             run is cancelled within one integrator step (lv_run_options.stop)
                             and not stored; the runs done are stored and the call returns
                             LV_ERR_CANCELLED. A resumed campaign runs the missing ones: its
                             database then equals an uninterrupted campaign's. */
    double max_rows;      /* > 0: lv_run_options.max_rows of every run (the records' and the
                             kept runs'): lv_campaign_open refuses (LV_ERR_INPUT) a phase of
                             the mission's own values that only its stop time ends and whose
                             grid has more rows; a run's phase with end events that reaches
                             it is a failed phase of that run (an outcome). 0: no limit */
} lv_campaign_options;

LV_API void lv_campaign_options_default(lv_campaign_options *o);

/* What a campaign of o->n_runs runs needs, estimated from the mission before anything runs.
 * The database and the statistics' memory grow linearly with the run count; nothing else of
 * a campaign does (the runs to do are kept as the ranges between stored runs). */
typedef struct lv_campaign_size {
    double rows_per_run;  /* output rows a run computes at most: every phase's grid with the
                             records' output interval (o->output_interval, else start and end
                             only) over its longest duration (lv_run_estimate_output), a phase
                             with end events at most o->max_rows (it fails there) */
    double rows_by_stop;  /* the same without that limit: what the stop times allow */
    double db_bytes;      /* the database at the end, about: per run its row of inputs, a row
                             per phase (outcome, finals) and one event per phase with an end,
                             at 9 bytes a value, 16 a row and 30 an event (zeros and whole
                             numbers take less, more events more: 6 % and 44 % above the size
                             measured for two of the examples) */
    double stats_bytes;   /* memory lv_campaign_stats and lv_campaign_plot need: every run's
                             inputs and finals as doubles, per phase its outcome, and their
                             work arrays */
    double kept_bytes;    /* the kept runs' files (o->keep_runs): every phase's .mat and .csv
                             that only its stop time ends, at most, with the grid they run
                             with (o->output_interval, else each phase's own) */
    double kept_bytes_max; /* the same with every phase: one with end events (or a child,
                             whose start is known when it runs) at what its stop time allows,
                             and no more than o->max_rows rows (the limit as it runs) */
    double kept_memory;   /* memory of o->threads kept runs at once: their rows */
    double mem_total;     /* bytes of physical memory of this machine (sysconf), or NAN */
    double disk_free;     /* bytes free to an unprivileged user in the folder of o->db_path
                             (statvfs), or NAN when it cannot be known */
} lv_campaign_size;
/* Fills *out for mission m and options o (o->db_path names the database to be: its folder
 * must exist for disk_free). LV_ERR_INPUT for n_runs 0. */
LV_API lv_status lv_campaign_estimate(const lv_mission *m, const lv_campaign_options *o,
                                      lv_campaign_size *out, lv_err *err);
/* The up-front bound of a campaign's size: LV_ERR_INPUT when half its database's estimate
 * (less what a resumed one holds already) and its kept runs' files exceed the free space of
 * the database's file system, when the kept runs' rows exceed the physical memory, or, with
 * `stats` 1, when the statistics' memory does: the message says what would be needed, the
 * limit, and what to do (fewer runs, --no-stats, a larger output interval). *out (may be
 * NULL) gets the estimate. LV_OK otherwise, and for a limit that cannot be known (NAN). */
LV_API lv_status lv_campaign_check_size(const lv_mission *m, const lv_campaign_options *o,
                                        int stats, lv_campaign_size *out, lv_err *err);

/* Runs the campaign's missing runs on o->threads threads, storing them in batched
 * transactions (WAL journal: a killed process keeps every committed run). */
LV_API lv_status lv_campaign_run(const lv_mission *m, const lv_campaign_options *o,
                                 lv_campaign_progress *out, lv_err *err);

/* ---- building blocks (a distributed campaign: cli/mc_mpi.c) --------------------------------
 * One writer opens the database and knows which runs are missing; workers anywhere turn run
 * indices into records (bytes, the same whatever the machine of one build); the writer
 * stores them. */
typedef struct lv_campaign lv_campaign;
LV_API lv_status lv_campaign_open(const lv_mission *m, const lv_campaign_options *o,
                                  lv_campaign **out, lv_err *err);
/* How many runs are neither stored nor handed out yet by lv_campaign_todo_next. */
LV_API uint64_t lv_campaign_todo_count(const lv_campaign *c);
/* Hands out the next runs not yet stored, ascending, at most `cap` of them into runs[];
 * returns how many (0: none left). Each run is handed out once per lv_campaign_open. */
LV_API size_t lv_campaign_todo_next(lv_campaign *c, uint64_t *runs, size_t cap);
/* Stores one record (a worker's bytes); committed in batches, or now by lv_campaign_commit. */
LV_API lv_status lv_campaign_store(lv_campaign *c, const void *rec, size_t len, lv_err *err);
LV_API lv_status lv_campaign_commit(lv_campaign *c, lv_err *err);
LV_API void lv_campaign_get_progress(const lv_campaign *c, lv_campaign_progress *p);
LV_API lv_status lv_campaign_close(lv_campaign *c, lv_err *err); /* commits; accepts NULL */

typedef struct lv_mc_worker lv_mc_worker;
LV_API lv_status lv_mc_worker_create(const lv_mission *m, const lv_campaign_options *o,
                                     lv_mc_worker **out, lv_err *err);
/* Runs run `run` and returns its record (owned by the worker, valid until its next run). A
 * failed phase or an input out of range is an outcome in the record, not an error.
 * LV_ERR_CANCELLED, and no record, when o->stop cut the run (or its kept run) short: a run
 * not finished is never stored, so a resumed campaign runs it again. */
LV_API lv_status lv_mc_worker_run(lv_mc_worker *w, uint64_t run, const void **rec, size_t *len,
                                  lv_err *err);
LV_API void lv_mc_worker_free(lv_mc_worker *w); /* accepts NULL */

/* ---- statistics ------------------------------------------------------------------------------
 * From a campaign database: per phase (a branch's end) and final value: n, mean, standard
 * deviation, percentiles 1, 50, 99; 3-sigma ellipses of the final ground points (lat, lon; in
 * metres and degrees) and of orbit elements; end reasons and failure rates by cause; the
 * correlation of every dispersed input with every final value. Writes into `outdir`:
 * stats.json, stats.csv, ellipses.csv, outcomes.csv, sensitivity.csv, footprint.kml.
 * Every run's values are held in memory: a campaign whose values exceed the machine's
 * physical memory is refused before anything is read (LV_ERR_INPUT, the sizes named). */
LV_API lv_status lv_campaign_stats(const char *db_path, const char *outdir, lv_err *err);
/* The figures (plots/mc_*.png, .svg: ground points over the map with their ellipses,
 * histograms, orbit-element scatter) and outdir/index.html, after lv_campaign_stats. PLplot:
 * not thread-safe. */
LV_API lv_status lv_campaign_plot(const char *db_path, const char *outdir, lv_err *err);

#ifdef __cplusplus
}
#endif
#endif
