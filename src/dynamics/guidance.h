/* guidance.h - the steering and throttle laws of lv_guidance.h in the right-hand side (not
 * exported). Step 3 of flight.h ("controls") for a model that steers: the law gives the body
 * axes and the aerodynamic angles that result (lv_guid_attitude), and, once the forces
 * without thrust are known, the throttle (lv_guid_throttle). Pure functions of their
 * arguments except the table cursors and the trigonometry cache in lv_guid_rt; nothing is
 * allocated or looked up by name. Equations: docs/guidance.md.
 *
 * A law is an lv_law: its name, the table of its keys (lv_law_key, offsets into its own
 * parameter struct) and its functions. Each lives in one file (guid_<name>.c for a steering
 * law, thr_<name>.c for a throttle law) and is listed once in guid_laws.c; a new law is that
 * file, that line, its test and its row in docs/guidance.md (docs/architecture.md).
 */
#ifndef LV_DYNAMICS_GUIDANCE_H
#define LV_DYNAMICS_GUIDANCE_H

#include "core/vec3.h"
#include "dynamics/flight.h"
#include "lvsim/lv_guidance.h"
#include "lvsim/lv_status.h"

typedef struct lv_guid lv_guid;
typedef struct lv_guid_rt lv_guid_rt;
typedef struct lv_thr lv_thr;
typedef struct lv_thr_in lv_thr_in;

/* What a law with accel_command asks of the 3-DoF model: the angle of attack alpha in
 * [alpha_lo, alpha_hi] at which the vehicle's acceleration relative to the planet,
 * a = (T x_b + F_aero) / m + g - 2 w x v_rel - w x (w x r), has the component `accel` along
 * the unit vector `dir` (ECEF); alpha_lo or alpha_hi when no alpha in the range gives it. */
typedef struct lv_guid_accel_cmd {
    lv_vec3 dir;             /* unit, ECEF */
    double accel;            /* m/s^2 */
    double alpha_lo, alpha_hi; /* rad */
} lv_guid_accel_cmd;

/* Where a law's check found the problem: the parser points its message at that node of the
 * law's mapping (key NULL: the mapping itself). */
typedef enum lv_law_node { LV_AT_MAP, LV_AT_KEY, LV_AT_VALUE } lv_law_node;
typedef struct lv_law_at {
    const char *key;
    lv_law_node node;
} lv_law_at;

struct lv_law {
    const char *name;        /* the word a mission file writes: "gravity_turn" */
    const char *description; /* one line */
    lv_law_kind kind;
    lv_law_form form;
    const lv_law_key *keys;  /* [n_keys]: the order files list them and slots are made */
    size_t n_keys;
    size_t par_size;         /* sizeof its parameter struct (<= sizeof(lv_law_par)) */
    const char *needs_aero;  /* why it needs an aerodynamic dataset ("banks the lift vector"),
                                or NULL */
    const char *dof3_why;    /* why its LV_KEY_DOF3 keys act in a 3-DoF phase only */

    /* Checks across keys and of the tables, the keys' own ranges being held: LV_ERR_INPUT
     * with a message naming the key and value (no prefix) and *at where it points. NULL:
     * none. Called when a mission is read (the file's values) and when a model is made. */
    lv_status (*check)(const void *par, lv_law_at *at, lv_err *err);

    /* ---- steering laws ---- */
    /* Resolves g->par for the hot path (table outputs, cosines; g->limits_alpha; places on
     * g->planet), after the check. NULL: nothing to resolve. */
    lv_status (*init)(lv_guid *g, lv_err *err);
    /* At the phase's start (kinematics k): what the law takes from the start state into
     * rt->s0 (the flare's time constant). Returns 0, or nonzero with the reason in msg[cap]
     * (the phase cannot start). NULL: nothing. */
    int (*start)(const lv_guid *g, lv_guid_rt *rt, const lv_flight_kin *k, char *msg,
                 size_t cap);
    /* A law that commands an acceleration instead of an angle of attack (g->commands_accel,
     * 3-DoF only): at time t the acceleration relative to the planet it wants along a
     * direction and the range of alpha the model may use for it (lv_guid_accel_cmd); the
     * attitude has set beta and the bank. NULL: none. */
    void (*accel_command)(const lv_guid *g, const lv_guid_rt *rt, double t,
                          const lv_flight_kin *k, lv_guid_accel_cmd *cmd);
    /* Why the law is for 3-DoF phases only (its angle of attack is solved by the point-mass
     * model), or NULL. */
    const char *dof3_only;
    /* The body axes at time t, as lv_guid_attitude (c->u[throttle] holds the throttle of the
     * controls; a law with a throttle table overwrites it). NULL: the model's inputs. */
    int (*attitude)(const lv_guid *g, lv_guid_rt *rt, double t, const lv_flight_kin *k,
                    const lv_flight_air *a, double fpa0, double chi0, int full,
                    lv_flight_controls *c, lv_flight_axes *ax, lv_err *err);
    /* The law's next breakpoint after t, or INFINITY; what it is at t, or NULL. May be NULL. */
    double (*next_time_event)(const lv_guid *g, const lv_guid_rt *rt, double t);
    const char *(*time_event_label)(const lv_guid *g, const lv_guid_rt *rt, double t);
    /* 1 when the attitude reads the atmosphere (Mach), 0 when the kinematics and the
     * air-relative velocity suffice. NULL: 0. */
    int (*reads_atmosphere)(const lv_guid *g);
    /* With g->limits_alpha: the angle of attack `alpha` [rad] limited, given the lift L [N]
     * it gives, the mass [kg] and the dynamic pressure q [Pa] (3-DoF models). */
    double (*alpha_limited)(const lv_guid *g, double alpha, double lift, double mass, double q);
    /* 1 when the law (its table) gives the throttle. NULL: 0. */
    int (*gives_throttle)(const void *par);
    /* What the attitude rests on at time t (LV_GREF_*; rt NULL: at any time of the phase):
     * the flight models' domain guards (flight_model.c) fail the phase where it is undefined.
     * NULL: nothing beyond the local or inertial frame (defined everywhere). */
    unsigned (*refs)(const lv_guid *g, const lv_guid_rt *rt, double t);

    /* ---- throttle laws ---- */
    /* Sets t->active, t->reads_drho, t->engines_off from t->par. */
    lv_status (*thr_init)(lv_thr *t, lv_err *err);
    /* The throttle given the nominal throttle c_nom, before the engines' clamp into [c_min,
     * c_max]: outside it the law asks for more (or less) than the engines can give. NULL:
     * the engines are off. */
    double (*throttle)(const lv_thr *t, double c_nom, const lv_thr_in *in,
                       const lv_flight_air *a);
};

/* What a steering law's attitude rests on (lv_law.refs). */
enum {
    /* the body axes follow the air-relative velocity (the aero frame: alpha, beta, mu, and
     * the laws that hold them): no direction at zero air-relative speed, and the bank's
     * reference (the vertical plane through it) none in vertical flight */
    LV_GREF_WIND = 1u,
};
/* law->refs(g, rt, t), or 0 when the law has none. */
unsigned lv_guid_refs(const lv_guid *g, const lv_guid_rt *rt, double t);

/* The registered laws of `kind`, NULL-terminated (guid_laws.c), and one by name. */
const lv_law *const *lv_guid_laws(lv_law_kind kind);
const lv_law *lv_guid_law_find(lv_law_kind kind, const char *name);
/* The key `name` of law (NULL: the kind's common keys only) or of the kind's common keys;
 * "NAME_deg" of an angle key finds NAME with *deg = 1. *common: it is a common key (its
 * offset is into lv_steering). NULL when none. */
const lv_law_key *lv_guid_key_find(const lv_law *law, lv_law_kind kind, const char *name,
                                   int *deg, int *common);
/* 1 when number key k applies with the law's parameters par: its frame (k->frames) is the
 * one chosen, the table that replaces it (k->instead_of) is not given. */
int lv_guid_key_applies(const lv_law *law, const lv_law_key *k, const void *par);
/* Sets par to law's defaults (required keys NAN, tables NULL, choices their default). */
void lv_guid_par_defaults(const lv_law *law, lv_law_par *par);
/* The law's checks on values par: each applicable number key within its range (required
 * ones given), an aerodynamic dataset when the law needs one (has_aero), then law->check.
 * LV_ERR_INPUT "guidance 'NAME': ..." (throttle: "throttle 'NAME': ...") with *at set. */
lv_status lv_guid_law_check(const lv_law *law, const void *par, int has_aero, lv_law_at *at,
                            lv_err *err);

/* What a table's axis is read against (the attitude law). */
typedef enum { LV_GAXIS_TIME, LV_GAXIS_ALTITUDE, LV_GAXIS_SPEED, LV_GAXIS_MACH } lv_gaxis;

/* A steering law resolved for the hot path (one per model; read-only while flying). */
struct lv_guid {
    const lv_law *law;    /* never NULL after lv_guid_init ("inputs") */
    lv_law_par par;       /* the law's parameters, resolved by its init */
    lv_vec3 target;       /* unit vector of the target point, ECEF (geocentric direction) */
    lv_vec3 target_r;     /* m, the target point on the ellipsoid, ECEF */
    int need_alpha, need_beta; /* the aerodynamic tables read alpha, beta (else the right-hand
                                  side skips them: outputs only) */
    int reads_atm;        /* law->reads_atmosphere */
    int limits_alpha;     /* law->alpha_limited acts (3-DoF) */
    int commands_accel;   /* law->accel_command gives alpha (3-DoF) */
    lv_planet planet;     /* the planet the law's points are placed on */
};

/* Per simulation instance: the phase's start, the frozen inertial frame, cursors, scratch. */
struct lv_guid_rt {
    double t0;              /* s, the phase's start */
    lv_vec3 f0[3];          /* N0, E0, D0 at the phase's start, ECI components */
    lv_table_cursor cur;    /* the law's table */
    double buf[16];         /* table outputs (tables with more outputs are refused) */
    double ang[3], cs[3][2]; /* trigonometry of the last attitude angles */
    double s0[4];           /* what the law's start took from the start state */
};

/* Resolves `s` (law NULL: "inputs"; target NAN: refused, the model puts its start point
 * there) into g: lv_guid_law_check, then the law's init. `planet` places the target.
 * LV_ERR_INPUT "guidance 'NAME': ..." naming the key and value. */
lv_status lv_guid_init(lv_guid *g, const lv_steering *s, const lv_planet *planet, int has_aero,
                       lv_err *err);

/* 1 when the law gives the attitude; 0 for "inputs" (the model's own angles). */
static inline int lv_guid_steers(const lv_guid *g) { return g->law->attitude != NULL; }
static inline int lv_guid_cfg_steers(const lv_steering *s)
{
    return s->law != NULL && s->law->attitude != NULL;
}

/* 1 when the law's attitude reads the atmosphere (Mach: an attitude table over Mach, the
 * heading law's alpha over Mach), 0 when it needs only the kinematics and the air-relative
 * velocity. */
static inline int lv_guid_reads_atmosphere(const lv_guid *g) { return g->reads_atm; }

/* 1 when steering law s (with its table) gives the throttle. */
int lv_guid_gives_throttle(const lv_steering *s);

/* The first LV_KEY_DOF3 key of s's law set away from its default (in effect), or NULL. */
const lv_law_key *lv_guid_dof3_key(const lv_steering *s);

/* At the phase's start (time t0, kinematics k): freezes the inertial frame, resets the
 * cursors, then the law's start. Returns 0, or nonzero with the reason in msg[cap]. */
int lv_guid_start(const lv_guid *g, lv_guid_rt *rt, double t0, const lv_flight_kin *k,
                  char *msg, size_t cap);

/* The acceleration g->law commands (g->commands_accel): law->accel_command. */
static inline void lv_guid_accel_command(const lv_guid *g, const lv_guid_rt *rt, double t,
                                         const lv_flight_kin *k, lv_guid_accel_cmd *cmd)
{
    g->law->accel_command(g, rt, t, k, cmd);
}

/* The next breakpoint of the law after t (gravity turn: end of the rise and of the kick;
 * an attitude table over time: its breakpoints), or INFINITY. */
double lv_guid_next_time_event(const lv_guid *g, const lv_guid_rt *rt, double t);

/* What the law's time event at t is ("end of the vertical rise", "end of the kick", "attitude
 * table breakpoint"), or NULL when the law has none at t. */
const char *lv_guid_time_event_label(const lv_guid *g, const lv_guid_rt *rt, double t);

/* The time events of a flight model over the planet (dof3, dof6): the breakpoints on the first
 * axis (time) of its inputs table and of its engines' tables, and its steering law's events
 * (g NULL: no law). The next one after t, or INFINITY. */
double lv_flight_next_time_event(const lv_table *inputs, const lv_engine *eng, size_t n_eng,
                                 const lv_guid *g, const lv_guid_rt *rt, double t);

/* What those events at t are, written into buf[cap] ("inputs table 'x' breakpoint; end of
 * the kick t = 14 s"); "" when none. Returns buf. */
const char *lv_flight_time_event_label(const lv_table *inputs, const lv_engine *eng,
                                       size_t n_eng, const lv_guid *g, const lv_guid_rt *rt,
                                       double t, char *buf, size_t cap);

/* Attitude at time t of a law that steers (lv_guid_steers): fills ax (wind and body axes,
 * ECEF) and c->u[alpha, beta, mu] with their cosines and sines (the angles that result for an
 * attitude frame; 0 below 1e-6 m/s of air-relative speed, where the wind axes are the body
 * axes), and c->u[throttle] from `throttle` or the law's table; the bank mu that results from
 * an attitude only when `full` (outputs: the force does not need it; NAN otherwise). (fpa0,
 * chi0): the direction the aerodynamic frame takes without air-relative speed
 * (lv_flight_axes_eval). Returns 0, or 1 when a table cannot be evaluated (err, may be NULL). */
static inline int lv_guid_attitude(const lv_guid *g, lv_guid_rt *rt, double t,
                                   const lv_flight_kin *k, const lv_flight_air *a,
                                   double throttle, double fpa0, double chi0, int full,
                                   lv_flight_controls *c, lv_flight_axes *ax, lv_err *err)
{
    c->u[LV_CTRL_THROTTLE] = throttle;
    return g->law->attitude(g, rt, t, k, a, fpa0, chi0, full, c, ax, err);
}

/* With g->limits_alpha (the heading law's n_max): the commanded angle of attack `alpha`
 * [rad] limited, given the lift L [N] it gives, the mass [kg] and the dynamic pressure q
 * [Pa]; otherwise alpha. */
double lv_guid_alpha_limited(const lv_guid *g, double alpha, double lift, double mass, double q);

/* The heading law's limits on its scheduled angle of attack `alpha` [rad] (pure; equations
 * in docs/guidance.md, "heading"; guid_heading.c). n: the lift load factor L / (m g0) at
 * `alpha`; n_max > 0. Load-factor limit, a soft saturation: a_n = alpha / (1 + (n /
 * n_max)^8)^(1/8); for a lift coefficient proportional to alpha the lift load factor becomes
 * n / (1 + (n/n_max)^8)^(1/8), below n_max for every n, within 0.1 % of n below n_max / 2 and
 * tending to n_max as n grows (a smooth function of the state: no switch for the integrator
 * to resolve). Dynamic-pressure release, q_max > 0: alpha_cmd = a_n + s (alpha - a_n), s =
 * 3 t^2 - 2 t^3, t = clamp(2 q / q_max - 1, 0, 1): at q >= q_max the schedule's alpha (the
 * drag and lift of the high angle of attack stop a dive instead of the limit lowering alpha
 * and letting q grow), at q <= q_max / 2 the limited one. q_max 0: a_n. n <= 0 or n_max <= 0:
 * alpha. */
double lv_guid_heading_alpha(double alpha, double n, double n_max, double q, double q_max);

/* The forces a throttle law needs, thrust excluded. T(c) = c (t_full + p_ae) - p_ae is the
 * engines' net thrust at throttle c [N]. */
struct lv_thr_in {
    double mass;        /* kg */
    double t_full;      /* N, net thrust at full throttle (c = 1) */
    double p_ae;        /* N, ambient pressure x the engines' exit areas */
    double c_min, c_max; /* the throttle range every engine accepts */
    lv_vec3 xb;         /* body x, ECEF */
    lv_vec3 f_aero;     /* N, ECEF */
    lv_vec3 a_nothrust; /* m/s^2, ECEF: acceleration relative to the rotating planet without
                           thrust: g + f_aero/m - 2 w x v_rel - w x (w x r) */
    lv_vec3 up;         /* local vertical (-d), ECEF */
    double h;           /* m, geodetic altitude */
    double v_down;      /* m/s, downward speed relative to the planet */
    double h_dot;       /* m/s */
    double drho_dh;     /* kg/m^4 (with reads_drho only) */
};

/* A throttle law resolved for the hot path. */
struct lv_thr {
    const lv_law *law;  /* never NULL after lv_thr_init ("nominal") */
    lv_law_par par;
    int active;         /* the law changes the nominal throttle (a limit, landing) */
    int reads_drho;     /* it reads lv_thr_in.drho_dh */
    int engines_off;    /* the engines are off: a coast */
};

/* Resolves `cfg` (law NULL: "nominal") into t: lv_guid_law_check, then the law's thr_init.
 * LV_ERR_INPUT "throttle 'NAME': ..." naming the key and value. */
lv_status lv_thr_init(lv_thr *t, const lv_throttle_cfg *cfg, lv_err *err);

/* 1 when throttle law cfg switches the engines off (a valid "off"). */
int lv_thr_engines_off(const lv_throttle_cfg *cfg);

/* The throttle of an active law given the nominal throttle `c_nom` (law->throttle). */
static inline double lv_guid_throttle(const lv_thr *t, double c_nom, const lv_thr_in *in,
                                      const lv_flight_air *a)
{
    return t->law->throttle(t, c_nom, in, a);
}

/* Target outputs: great-circle distance [m] on the sphere of radius `radius` and initial
 * bearing [rad, from north to east] from the vehicle to the target, and the overshoot [m]
 * of a vacuum ballistic flight over flat ground in uniform gravity `g` from here along that
 * bearing: (horizontal velocity toward the target) x (time to fall to h = 0) - distance. */
void lv_guid_target(const lv_guid *g, const lv_flight_kin *k, double radius, double g_up,
                    double *distance, double *bearing, double *overshoot);

/* Attitude relative to local NED (3-2-1 Euler angles) of body axes ax. */
void lv_guid_euler_local(const lv_flight_kin *k, const lv_flight_axes *ax, double *theta,
                         double *psi, double *phi);

#endif
