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
    volatile int *stop;   /* set nonzero (a signal handler): no new run starts; the runs done
                             are stored and the call returns LV_ERR_CANCELLED */
} lv_campaign_options;

LV_API void lv_campaign_options_default(lv_campaign_options *o);

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
/* The runs not yet stored, ascending; borrowed (valid until lv_campaign_close). */
LV_API size_t lv_campaign_todo(const lv_campaign *c, const uint64_t **runs);
/* Stores one record (a worker's bytes); committed in batches, or now by lv_campaign_commit. */
LV_API lv_status lv_campaign_store(lv_campaign *c, const void *rec, size_t len, lv_err *err);
LV_API lv_status lv_campaign_commit(lv_campaign *c, lv_err *err);
LV_API void lv_campaign_get_progress(const lv_campaign *c, lv_campaign_progress *p);
LV_API lv_status lv_campaign_close(lv_campaign *c, lv_err *err); /* commits; accepts NULL */

typedef struct lv_mc_worker lv_mc_worker;
LV_API lv_status lv_mc_worker_create(const lv_mission *m, const lv_campaign_options *o,
                                     lv_mc_worker **out, lv_err *err);
/* Runs run `run` and returns its record (owned by the worker, valid until its next run). A
 * failed phase or an input out of range is an outcome in the record, not an error. */
LV_API lv_status lv_mc_worker_run(lv_mc_worker *w, uint64_t run, const void **rec, size_t *len,
                                  lv_err *err);
LV_API void lv_mc_worker_free(lv_mc_worker *w); /* accepts NULL */

/* ---- statistics ------------------------------------------------------------------------------
 * From a campaign database: per phase (a branch's end) and final value: n, mean, standard
 * deviation, percentiles 1, 50, 99; 3-sigma ellipses of the final ground points (lat, lon; in
 * metres and degrees) and of orbit elements; end reasons and failure rates by cause; the
 * correlation of every dispersed input with every final value. Writes into `outdir`:
 * stats.json, stats.csv, ellipses.csv, outcomes.csv, sensitivity.csv, footprint.kml. */
LV_API lv_status lv_campaign_stats(const char *db_path, const char *outdir, lv_err *err);
/* The figures (plots/mc_*.png, .svg: ground points over the map with their ellipses,
 * histograms, orbit-element scatter) and outdir/index.html, after lv_campaign_stats. PLplot:
 * not thread-safe. */
LV_API lv_status lv_campaign_plot(const char *db_path, const char *outdir, lv_err *err);

#ifdef __cplusplus
}
#endif
#endif
