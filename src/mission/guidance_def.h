/* guidance_def.h - a phase's `guidance:` and `throttle:` keys (the 3-DoF model's steering and
 * throttle laws, lv_guidance.h): parsed into slots "<phase>.guidance.<key>" and
 * "<phase>.throttle.<key>" so that a run, a dispersion or a targeting loop can set every
 * coefficient by name; made into an lv_steering and lv_throttle_cfg with a run's values.
 * Format: docs/mission-format.md ("guidance", "throttle"); laws: docs/guidance.md.
 */
#ifndef LV_MISSION_GUIDANCE_DEF_H
#define LV_MISSION_GUIDANCE_DEF_H

#include "lvsim/lv_guidance.h"
#include "mission/parse_kit.h"

typedef struct lv_guidance_def {
    int given;                /* `guidance:` present */
    lv_steer_law law;
    lv_att_frame frame;
    lv_slot angle[3];         /* attitude: alpha, beta, mu | pitch, heading, roll [rad] */
    lv_slot rise_time, kick, kick_time, heading;
    lv_slot a, b, c, d;
    lv_slot target_lat, target_lon; /* LV_NO_SLOT: the launch site */
    lv_slot bank_max, gain, n_max, hq_max, alpha, pitch; /* hq_max: the heading law's q_max */
    char *table_file, *table_var;
    lv_table *table;          /* attitude table or heading's alpha table */

    int thr_given;            /* `throttle:` present */
    lv_throttle_law thr_law;
    lv_slot thr_value;        /* nominal throttle, LV_NO_SLOT: the inputs' */
    lv_slot g_limit, q_max, q_gain, land_altitude, land_speed;
} lv_guidance_def;

/* Parses `guidance` (may be NULL) and `throttle` (may be NULL) of phase `phase`; `has_aero`:
 * the phase has an aerodynamic dataset (the heading law needs one). */
lv_status lv_guidance_def_parse(const lv_pctx *c, const lv_ynode *guidance,
                                const lv_ynode *throttle, const char *phase, int has_aero,
                                lv_guidance_def *g);

/* The laws with a run's slot values. */
void lv_guidance_def_make(const lv_guidance_def *g, const double *vals, lv_steering *s,
                          lv_throttle_cfg *t);

void lv_guidance_def_clear(lv_guidance_def *g); /* accepts a zeroed one */

#endif
