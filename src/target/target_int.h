/* target_int.h - internal: the targeting problem (lv_target), its evaluations on one lv_run and
 * finite-difference sensitivities, shared by the solvers (newton.c, optimize.c) and the
 * converged-file writer (write.c). Not exported. */
#ifndef LV_TARGET_TARGET_INT_H
#define LV_TARGET_TARGET_INT_H

#include <stddef.h>
#include <time.h>

#include "lvsim/lv_target.h"
#include "mission/mission_rt.h"
#include "mission/targeting_def.h"

#define TG_MAX_WORKERS 16 /* threads taking sensitivities */

typedef struct tg_var {
    char *name;
    lv_tvar r;          /* parameter, deg, bounds, start, scale, step (name's unit) */
    size_t first_phase; /* the first phase (run order) the parameter reaches */
    lv_src_loc start_loc; /* the targeting section's `start:` value, or 0 */
} tg_var;

typedef struct tg_con {
    char *name;
    int path;           /* 1: the phase's largest (max) or smallest (min) value of the final's
                           column over its rows (lv_targeting_path_extremum); 0: its final */
    lv_con_kind kind;
    double value, tol;  /* in the final's unit as named */
    lv_tfinal f;
} tg_con;

typedef struct tg_cost {
    int present, maximize;
    char *name;
    double scale;       /* NAN: from the start point */
    lv_tfinal f;
} tg_cost;

/* One evaluated point. */
typedef struct tg_point {
    double *x;      /* [n] the variables (their units) */
    double *f;      /* [m] the constraints' finals */
    double *g;      /* [m] (f - v) / tol */
    double *r;      /* [m] residuals: g for equal, its violation for min / max (0 when met) */
    double cost;    /* the cost's final (NAN: none) */
    double worst;   /* max |r| */
    double merit;   /* sum r^2 / 2 */
    int ok;         /* 0: a phase failed (why) */
    char why[LV_ERR_MSG_MAX];
    int *end_got;   /* [n_chk] the end each checked phase reached (LV_TEND_NONE: not done) */
    double *end_t;  /* [n_chk] s, when it ended */
    size_t n_chk;   /* the arrays' size */
    size_t ends_off; /* how many of them ended otherwise than assumed */
} tg_point;

struct lv_target {
    const lv_mission *m;
    size_t n, cap_n;       /* variables */
    tg_var *vars;
    size_t mc, cap_m;      /* constraints */
    tg_con *cons;
    tg_cost cost;
    /* the settings the file gives (0: defaults) */
    lv_target_method method;
    lv_target_diff diff;
    int max_iter;
    double xtol, ftol;
    int restarts;
    /* the run every evaluation sets and executes; more for the sensitivities' workers */
    lv_run *run;
    lv_run *aux[TG_MAX_WORKERS - 1];
    unsigned char *want;   /* [n_phases] the constraints' and the cost's phases */
    /* the end each phase is assumed to end by (lv_target_set_end): LV_TEND_NONE (not
     * checked), LV_TEND_ANY, LV_TEND_STOP_TIME or an index into its ends */
    int *expect;           /* [n_phases] */
    unsigned char *expect_named; /* [n_phases] 1: named (`end:`, lv_target_set_end) */
    size_t n_chk;
    size_t *chk;           /* [n_chk] the phases checked (expect an end or stop_time) */
    /* one solve */
    lv_target_settings set;
    struct timespec t0;
    size_t runs, phases;   /* totals */
    size_t rep_runs, rep_phases; /* totals at the last iteration reported */
    size_t iteration;      /* the current iteration */
    const char *solver;    /* "newton", "slsqp", "cobyla" */
    double cost_scale;     /* > 0 */
    double *tmp_x;         /* [n] scratch for evaluations */
    size_t *order;         /* [n] the variables in the order sensitivities are taken */
    /* the result */
    lv_target_result res;
    double *res_x, *res_f, *res_r;
    int *res_met;
    lv_target_end_mismatch *res_mm; /* [n_chk] */
    char method_used[48];
    char note[2 * LV_ERR_MSG_MAX]; /* an iteration's note with the ends (tg_report) */
};

/* ---- points and evaluations (target.c) ------------------------------------------------------ */

/* Constraint c's value in run r of mission m: its phase's final, or for a path constraint the
 * extremum over the phase's rows (the run kept them: tg_keep_rows). NAN when the phase has no
 * rows or no number in the column. */
double tg_con_value(const lv_mission *m, const lv_run *r, const tg_con *c);
/* 1 when a constraint reads a phase's rows (a path constraint): the runs keep them. */
int tg_keep_rows(const lv_target *t);

lv_status tg_point_init(const lv_target *t, tg_point *p);
void tg_point_free(tg_point *p);
void tg_point_copy(const lv_target *t, tg_point *dst, const tg_point *src);

/* Sets x on the run and executes it (only the phases whose inputs changed and that the
 * constraints and cost need); fills p (p->ok = 0 with p->why when a phase failed: a rejected
 * point, not an error). `purpose` and `var` go to the on_evaluation callback. Errors:
 * LV_ERR_CANCELLED, LV_ERR_NOMEM. */
lv_status tg_eval(lv_target *t, const double *x, const char *purpose, const char *var,
                  tg_point *p, lv_err *err);

/* Finite-difference sensitivities at `base` (evaluated, ok) in scaled variables z = x / scale:
 * Jg[i * n + j] = dg_i / dz_j, Jc[j] = d(cost / cost_scale) / dz_j (Jc may be NULL). Central
 * differences when `central`. A variable whose perturbed points fail on both sides gets a zero
 * column (*note names it, may be NULL). The columns are shared among set.threads workers, each
 * with a run of its own (the target's, then t->aux); every run is left at some perturbed
 * point. */
lv_status tg_sensitivities(lv_target *t, const tg_point *base, int central, double *Jg,
                           double *Jc, char *note, size_t note_cap, lv_err *err);

/* The forward (central: 1) difference step of variable j, in its unit. */
double tg_step(const lv_target *t, size_t j, int central);

/* "phase 'P2' ended by burnout at t = 512.3 s, not by sma; ..." for the checked phases of p
 * that ended otherwise than assumed ("" when none). */
void tg_ends_text(const lv_target *t, const tg_point *p, char *buf, size_t cap);

/* 1 when every constraint is met (|r_i| <= 1). */
int tg_met(const lv_target *t, const tg_point *p);

/* Reports an iteration to the on_iteration callback (and counts runs since the last). */
void tg_report(lv_target *t, const char *event, const tg_point *p, double damping, double step,
               const char *note);

double tg_wall(const lv_target *t); /* s since the solve started */

/* ---- solvers ---------------------------------------------------------------------------------- */

/* Levenberg-Marquardt from p (evaluated, ok) for at most `max_iter` trial steps; p becomes the
 * best point. *converged: every constraint met. */
lv_status tg_newton(lv_target *t, tg_point *p, int max_iter, int *converged, char *reason,
                    size_t reason_cap, lv_err *err);

/* How an optimiser ended. */
typedef enum tg_opt_end {
    TG_OPT_CONVERGED = 0, /* stopped on its tolerances at a point that meets every constraint */
    TG_OPT_LIMIT,         /* the iteration limit */
    TG_OPT_FAILED         /* it failed, or stopped where a constraint is not met */
} tg_opt_end;

/* NLopt's SLSQP or COBYLA from p (evaluated, ok) for at most max_iter points; p becomes the
 * best point (meeting the constraints first, then the lowest cost). */
lv_status tg_optimize(lv_target *t, lv_target_method alg, tg_point *p, int max_iter,
                      tg_opt_end *end, char *reason, size_t reason_cap, lv_err *err);

/* ---- paths in a written mission (write.c) ---------------------------------------------------- */

/* 1 when key k's string values name files the mission reads (docs/mission-format.md). */
int lv_tw_path_key(const char *k);
/* The folder of `path` (which need not exist yet), absolute and resolved; NULL. Free it. */
char *lv_tw_dir_real(const char *path);
/* `target` (absolute, resolved) relative to folder `from` (absolute, resolved); absolute when
 * they share no folder but the root. Free it; NULL: out of memory. */
char *lv_tw_relative_to(const char *target, const char *from);
/* The value `path` (len bytes) of key `key` in a mission (folder mdir) as seen from folder odir
 * (both resolved): a new string when key names files (lv_tw_path_key) and path is a relative
 * path to a regular file, else NULL (*nomem 0: an absolute path, a model's name, a number) or
 * NULL when memory ran out (*nomem 1). */
char *lv_tw_rebase(const char *mdir, const char *odir, const char *key, const char *path,
                   size_t len, int *nomem);

#endif
