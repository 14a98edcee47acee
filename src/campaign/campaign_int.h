/* campaign_int.h - internals of the Monte Carlo campaign (lv_campaign.h): a run's record as
 * bytes (written by a worker, read by the database writer, sent between MPI ranks). */
#ifndef LV_CAMPAIGN_INT_H
#define LV_CAMPAIGN_INT_H

#include <stddef.h>
#include <stdint.h>

#include "lvsim/lv_campaign.h"

/* A growable byte buffer. */
typedef struct lv_bytes {
    unsigned char *p;
    size_t n, cap;
    int nomem;
} lv_bytes;

void lv_bytes_u64(lv_bytes *b, uint64_t v);
void lv_bytes_f64(lv_bytes *b, double v);
void lv_bytes_str(lv_bytes *b, const char *s);

/* A reader over a record; `bad` is set when it runs past the end. */
typedef struct lv_rd {
    const unsigned char *p;
    size_t n, at;
    int bad;
} lv_rd;
uint64_t lv_rd_u64(lv_rd *r);
double lv_rd_f64(lv_rd *r);
const char *lv_rd_str(lv_rd *r, size_t *len); /* points into the record; not NUL-terminated */

/* Record layout (all little-endian host order; one build writes and reads):
 *   u64 run, u64 status (0 ok, 1 a phase failed, 2 an input outside its range, 3 no phase
 *   failed but one ended on the ground by an `impact` end it was not meant to end by, 4 no
 *   phase failed but one crashed: a touchdown beyond the landing gear's limits),
 *   str message, u64 n_inputs, f64 inputs[n],
 *   u64 n_phases, per phase: u64 state (lv_phase_state, or LV_MC_IMPACT: done by such an
 *     impact), str end, f64 t_end, u64 steps,
 *     u64 rhs_evals, str error, u64 n_final, f64 finals[n_final], u64 n_events,
 *     per event: f64 t, str name, u64 n_iip (the phase's `iip_at:` times), per time:
 *     f64 t, u64 state (lv_iip_state), f64 lat, lon, tof, range (rad, s, m; NaN unless
 *     LV_IIP_IMPACT). */
enum { LV_MC_OK = 0, LV_MC_FAILED = 1, LV_MC_INPUT = 2, LV_MC_RUN_IMPACT = 3,
       LV_MC_RUN_CRASHED = 4 };
/* A phase's state in a record beside lv_phase_state's: done, but by an `impact` end where its
 * first written end (the one it is meant to end by) is another: the vehicle fell to the
 * ground. An outcome of the flight, not a failure of the model (docs/monte-carlo.md). */
enum { LV_MC_IMPACT = LV_PHASE_CRASHED + 1 };

#endif
