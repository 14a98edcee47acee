/* progress.h - what the CLI shows while a mission runs and its results are written: on a
 * terminal one live line (on stderr) with every running phase's mission time, time limit
 * and rate, then the post-processing step under way; not on a terminal, plain lines (a
 * phase still running after 10 s, every 10 s; each post-processing step when done);
 * nothing with --quiet. Ctrl-C cancels the run through the progress callback.
 */
#ifndef LVSIM_CLI_PROGRESS_H
#define LVSIM_CLI_PROGRESS_H

#include <stdio.h>

#include "lvsim/lvsim.h"

typedef struct cli_progress cli_progress;

/* For a mission of n_phases (0: post-processing only). quiet: show nothing. NULL when out
 * of memory (the caller then runs without progress). */
cli_progress *progress_new(size_t n_phases, int quiet);
void progress_free(cli_progress *p);

/* lv_run_options.progress (user = the cli_progress): notes phase k at mission time t;
 * returns 1 after Ctrl-C (the run is then cancelled). */
int progress_phase(const lv_run *r, size_t k, double t, void *user);
/* Phase k ended (from on_phase, under the run's lock): forget its line. */
void progress_phase_done(cli_progress *p, size_t k);

/* Around anything else printed while the live line may be shown: takes the lock and
 * erases the line; progress_print_end redraws it and unlocks. */
void progress_print_begin(cli_progress *p);
void progress_print_end(cli_progress *p);

/* A post-processing step ("summary.json", "exports", "plots and index.html"): begin shows
 * it, end records its time (not on a terminal: one line "lvsim: WHAT (1.23 s)"). */
void progress_step_begin(cli_progress *p, const char *what);
void progress_step_end(cli_progress *p);

/* 1 once Ctrl-C (SIGINT) or SIGTERM came (cli_catch_stop, common.h): progress_phase returns
 * it too. */
int progress_interrupted(void);

#endif
