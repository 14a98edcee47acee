/* lv_guidance.h - steering and throttle laws of the flight models (lv_dof3.h, lv_dof6.h).
 *
 * A steering law gives the vehicle's attitude (its body axes: thrust acts along body x) at
 * every instant; a throttle law the throttle c_s. Each law is a registered object with a
 * table of its keys (name, unit, range, default, description): a model's configuration names
 * the law and sets its keys by name, and the same table drives the mission files' `guidance:`
 * and `throttle:` keys, `lvsim laws`, the documentation and the Python package. Equations,
 * frames and the source of each law: docs/guidance.md. All values SI: angles in radians
 * (a key NAME_deg takes degrees where the functions below say so), times in seconds.
 *
 *     lv_steering s;
 *     lv_steering_init(&s, "gravity_turn", &err);      required keys NAN, the others defaults
 *     lv_steering_set(&s, "kick_deg", 3.0, &err);      or "kick", 3.0 * LV_DEG
 *     lv_steering_set(&s, "kick_time", 10.0, &err);    ... then cfg.steering = s
 *
 * Attitude frames (the key `frame` of the laws that take one):
 *   LV_FRAME_AERO      angle of attack alpha, sideslip beta and bank mu about the
 *                      air-relative velocity (the paper's inputs; Stevens & Lewis sec. 2.3).
 *   LV_FRAME_LOCAL     pitch theta, heading (yaw) psi and roll phi of the body axes relative
 *                      to the local NED frame at the vehicle: C_body_ned = R1(phi) R2(theta)
 *                      R3(psi) (3-2-1 Euler angles; theta = 90 deg points body x straight up).
 *   LV_FRAME_INERTIAL  the same angles relative to the NED frame at the phase's start,
 *                      frozen in inertial space (exo-atmospheric steering).
 * Whatever the frame, lift and drag act on the air-relative velocity; the angles of attack,
 * sideslip and bank that result, and the attitude relative to local NED, are outputs.
 */
#ifndef LVSIM_LV_GUIDANCE_H
#define LVSIM_LV_GUIDANCE_H

#include <stddef.h>

#include "lvsim/lv_status.h"
#include "lvsim/lv_table.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum lv_att_frame {
    LV_FRAME_AERO = 0,
    LV_FRAME_LOCAL = 1,
    LV_FRAME_INERTIAL = 2
} lv_att_frame;

/* ---- the registered laws and their keys ------------------------------------------------ */

typedef struct lv_law lv_law; /* a registered law (its functions are the library's own) */

typedef enum lv_law_kind { LV_LAW_STEERING = 0, LV_LAW_THROTTLE = 1 } lv_law_kind;

/* How a mission file writes a law. */
typedef enum lv_law_form {
    LV_LAW_FORM_NONE = 0,   /* not written: the model's inputs (no `guidance:`) */
    LV_LAW_FORM_NAMED = 1,  /* `guidance: {law: NAME, KEY: ..}` */
    LV_LAW_FORM_KEYS = 2,   /* `throttle: {KEY: ..}`: its keys directly (the nominal law) */
    LV_LAW_FORM_NESTED = 3, /* `throttle: {NAME: {KEY: ..}}` */
    LV_LAW_FORM_WORD = 4    /* `throttle: NAME` (a law without keys) */
} lv_law_form;

typedef enum lv_key_type {
    LV_KEY_NUMBER = 0, /* a double: a run parameter "<phase>.guidance.<key>" in a mission */
    LV_KEY_TABLE = 1,  /* a table (const lv_table *, borrowed); a file gives its path */
    LV_KEY_CHOICE = 2  /* one of `choices` (an int, its index) */
} lv_key_type;

#define LV_KEY_ANGLE 1u    /* an angle (rad): NAME_deg takes degrees */
#define LV_KEY_OPTIONAL 2u /* absent: no run parameter; the law takes `dflt`, which may lie
                              outside the range and then means "none" (0: no limit) */
#define LV_KEY_DOF3 4u     /* acts in 3-DoF phases only (a 6-DoF phase refuses it) */

/* One key of a law. Required: a NUMBER with dflt NAN and without LV_KEY_OPTIONAL (unless the
 * table `instead_of` replaces it). */
typedef struct lv_law_key {
    const char *name;          /* "kick" */
    lv_key_type type;
    const char *unit;          /* SI: "rad", "s", "Pa", "1/s", "1" (dimensionless); "" for a
                                  table or a choice (lv_units.h) */
    double lo, hi;             /* NUMBER: allowed values lo <= v <= hi (< with the flags) */
    int lo_open, hi_open;
    double dflt;               /* NUMBER: the default (NAN: required); CHOICE: its index */
    unsigned flags;            /* LV_KEY_ANGLE, LV_KEY_OPTIONAL, LV_KEY_DOF3 */
    unsigned frames;           /* bits 1 << lv_att_frame: the key applies in those frames
                                  only (the law's CHOICE key "frame"); 0: always */
    const char *instead_of;    /* NUMBER: the TABLE key that replaces it when given, or NULL */
    const char *needs;         /* the key applies only when key `needs` is given, or NULL */
    const char *const *choices; /* CHOICE: the words, NULL-terminated */
    size_t offset;             /* where the value lives in the law's parameters */
    const char *description;   /* one line */
} lv_law_key;

typedef struct lv_law_info {
    const char *name;        /* "gravity_turn": the word a mission file writes */
    const char *description; /* one line */
    lv_law_kind kind;
    lv_law_form form;
    const char *needs_aero;  /* why the law needs an aerodynamic dataset, or NULL */
    size_t n_keys;
    const lv_law_key *keys;  /* [n_keys], in the order files list them */
} lv_law_info;

/* The registered laws, steering laws first, in registry order: i = 0 .. count - 1. */
LV_API size_t lv_laws_count(void);
LV_API lv_status lv_laws_get(size_t i, lv_law_info *out, lv_err *err);
/* The keys every law of `kind` takes besides its own (steering: target_lat, target_lon). */
LV_API const lv_law_key *lv_laws_common_keys(lv_law_kind kind, size_t *n);

/* ---- a model's steering and throttle law ---------------------------------------------------- */

#define LV_LAW_PAR_MAX 32 /* doubles of room for a law's parameters */
typedef union lv_law_par {
    double d[LV_LAW_PAR_MAX];
    const void *p; /* alignment */
} lv_law_par;

/* A steering law with its parameters. law NULL: the model's inputs (as "inputs"). */
typedef struct lv_steering {
    const lv_law *law;
    double target_lat;      /* rad, geodetic: the heading and boostback laws' target and the
                               target outputs; NAN: the start point */
    double target_lon;      /* rad */
    lv_law_par par;         /* the law's keys: set them with the functions below */
} lv_steering;

/* A throttle law with its parameters. law NULL: "nominal" without limits. */
typedef struct lv_throttle_cfg {
    const lv_law *law;
    lv_law_par par;
} lv_throttle_cfg;

/* Sets s to steering law `law` ("gravity_turn"; "inputs": none) with every key at its
 * default (required keys NAN, tables NULL) and the target at the start point (NAN).
 * LV_ERR_NOTFOUND for an unknown name (the message lists the laws). */
LV_API lv_status lv_steering_init(lv_steering *s, const char *law, lv_err *err);
/* Number key `key` of the law (or target_lat, target_lon) = value, SI; "NAME_deg" for an
 * angle takes degrees. LV_ERR_NOTFOUND for a key the law does not have (with suggestions),
 * LV_ERR_INPUT for a table or choice key. Ranges are checked when the model is created. */
LV_API lv_status lv_steering_set(lv_steering *s, const char *key, double value, lv_err *err);
/* The value of number key `key` (SI; "NAME_deg": degrees). */
LV_API lv_status lv_steering_get(const lv_steering *s, const char *key, double *value,
                                 lv_err *err);
/* Table key `key` (attitude's "table", heading's "alpha_table") = t (borrowed; NULL: none). */
LV_API lv_status lv_steering_set_table(lv_steering *s, const char *key, const lv_table *t,
                                       lv_err *err);
/* Choice key `key` ("frame") = `word` ("local"). */
LV_API lv_status lv_steering_set_choice(lv_steering *s, const char *key, const char *word,
                                        lv_err *err);
/* The law's name ("inputs" for law NULL). */
LV_API const char *lv_steering_law(const lv_steering *s);

/* The same for a throttle law ("nominal", "landing", "off"). */
LV_API lv_status lv_throttle_init(lv_throttle_cfg *t, const char *law, lv_err *err);
LV_API lv_status lv_throttle_set(lv_throttle_cfg *t, const char *key, double value, lv_err *err);
LV_API lv_status lv_throttle_get(const lv_throttle_cfg *t, const char *key, double *value,
                                 lv_err *err);
LV_API const char *lv_throttle_law(const lv_throttle_cfg *t);

#ifdef __cplusplus
}
#endif
#endif
