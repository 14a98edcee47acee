/* guidance_def.h - a phase's `guidance:` and `throttle:` keys: the steering and throttle laws
 * of lv_guidance.h as a file writes them, read from each law's key table (name, unit, range,
 * default): every number becomes a slot "<phase>.guidance.<key>", "<phase>.throttle.<key>"
 * or "<phase>.throttle.<law>.<key>" so that a run, a dispersion or a targeting loop can set
 * it by name; made into an lv_steering and lv_throttle_cfg with a run's values. The parser
 * names no law. Format: docs/mission-format.md ("guidance", "throttle"); laws:
 * docs/guidance.md.
 */
#ifndef LV_MISSION_GUIDANCE_DEF_H
#define LV_MISSION_GUIDANCE_DEF_H

#include "lvsim/lv_guidance.h"
#include "mission/parse_kit.h"

#define LV_LAW_KEYS_MAX 16 /* keys of one law */

/* One law as the file gives it. */
typedef struct lv_law_def {
    const lv_law *law;                    /* NULL: not given */
    lv_slot slot[LV_LAW_KEYS_MAX];        /* number keys; LV_NO_SLOT: the law's default */
    int choice[LV_LAW_KEYS_MAX];          /* choice keys: the word's index */
    lv_table *table[LV_LAW_KEYS_MAX];     /* table keys (owned), NULL: none */
    char *table_file[LV_LAW_KEYS_MAX], *table_var[LV_LAW_KEYS_MAX];
} lv_law_def;

typedef struct lv_guidance_def {
    lv_law_def steer;               /* `guidance:` */
    lv_slot target_lat, target_lon; /* LV_NO_SLOT: the launch site */
    lv_law_def thr;                 /* `throttle:` */
} lv_guidance_def;

/* Parses `guidance` (may be NULL) and `throttle` (may be NULL) of phase `phase`; `has_aero`:
 * the phase has an aerodynamic dataset (a law may need one); `dof3`: the keys that act in
 * 3-DoF phases only are accepted (else refused where written). */
lv_status lv_guidance_def_parse(const lv_pctx *c, const lv_ynode *guidance,
                                const lv_ynode *throttle, const char *phase, int has_aero,
                                int dof3, lv_guidance_def *g);

/* The laws with a run's slot values (laws not given: s, t unchanged). */
void lv_guidance_def_make(const lv_guidance_def *g, const double *vals, lv_steering *s,
                          lv_throttle_cfg *t);

/* The steering law's table gives the throttle (an attitude table's output "throttle"). */
int lv_guidance_def_gives_throttle(const lv_guidance_def *g);

/* The steering law `attitude` in a local or inertial frame: its table (pitch, heading, roll,
 * throttle over time, ...; owned by g, NULL when not given), which an optimiser's controls
 * replace (phase_dof3.c). NULL for any other law or the aero frame. */
lv_table **lv_guidance_def_attitude_table(lv_guidance_def *g);

/* The steering law's number `key` as the file gives it (m's slots), its default when not
 * written, NAN when the law has no such number (or no law steers). SI (an angle in rad). */
double lv_guidance_def_steer_number(const lv_guidance_def *g, const char *key,
                                    const lv_mission_def *m);

/* The slot of `throttle: {value: c}`, the phase's nominal throttle, or LV_NO_SLOT. */
lv_slot lv_guidance_def_throttle_value(const lv_guidance_def *g);

/* A throttle law that sets the throttle itself (`throttle: off`, `{landing: ..}`: a law not
 * written with the nominal's keys), or NULL; what it is in a message ("off", "the landing
 * law's") and how it is written ("off", "{landing: ..}"). */
const lv_law *lv_guidance_def_throttle_fixed(const lv_guidance_def *g, char *is, size_t is_cap,
                                             char *written, size_t written_cap);

void lv_guidance_def_clear(lv_guidance_def *g); /* accepts a zeroed one */

#endif
