/* targeting_def.h - a mission file's `targeting:` section: design variables (run parameters by
 * name, with bounds, start, scale), constraints on phases' final values or on their largest or
 * smallest values over the phase (path constraints), an optional cost and
 * the solver's settings. Parsed with the mission (the section's own keys, types and values),
 * then checked against the loaded mission (names, units, bounds), so `lvsim check` refuses
 * what `lvsim target` would. The solver: src/target, include/lvsim/lv_target.h. Format:
 * docs/targeting.md.
 */
#ifndef LV_MISSION_TARGETING_DEF_H
#define LV_MISSION_TARGETING_DEF_H

#include <stddef.h>

#include "lvsim/lv_mission.h"
#include "lvsim/lv_target.h"
#include "mission/mission.h"
#include "mission/parse_kit.h"

/* A variable's scale (the size of a typical change, in which it is solved for and from which
 * its difference steps follow) lies within [LV_TSCALE_REL_MIN, LV_TSCALE_REL_MAX] x (max - min):
 * beyond, the solvers answer "NOT MET" for a problem they solve at the default scale (measured,
 * the closed-form shot of test_target: Newton fails from 1e-6 x (max - min) down, where the
 * steps drown in the finals' round-off, COBYLA from 10 x (max - min) up, whose first simplex
 * leaves the bounds). The examples use 4e-4 to 0.1. */
#define LV_TSCALE_REL_MIN 1e-4
#define LV_TSCALE_REL_MAX 1.0
/* 1 when scale lies in that range for bounds max - min = w (a written 0.0055 for w = 55 is in:
 * the bounds allow 1e-9 of round-off) */
static inline int lv_tscale_ok(double scale, double w)
{
    return scale >= LV_TSCALE_REL_MIN * w * (1.0 - 1e-9) &&
           scale <= LV_TSCALE_REL_MAX * w * (1.0 + 1e-9);
}

/* A variable resolved against a mission: the parameter and its unit. */
typedef struct lv_tvar {
    size_t slot;        /* the parameter's index */
    int deg;            /* the name is NAME_deg: values in degrees */
    double lo, hi;      /* in the name's unit */
    double start;       /* in the name's unit */
    double scale;       /* > 0 */
    double step;        /* > 0, or NAN: from the scale */
} lv_tvar;

/* A final value "PHASE.NAME" resolved against a mission. */
typedef struct lv_tfinal {
    size_t phase;       /* run order */
    size_t index;       /* into the phase's final values (lv_phase_result.final_values) */
    int deg;            /* written NAME_deg: the value in degrees */
    char unit[24];      /* "deg" for a _deg name, else the variable's unit */
} lv_tfinal;

/* The end a phase read by the constraints or the cost is assumed to end by (docs/targeting.md,
 * "The end each constraint assumes"): an index into its `end:` list (file order), or one of
 * these. By default the phase's first end written (stop_time for a phase without `end:`). */
#define LV_TEND_STOP_TIME (-1) /* its stop time (`end: stop_time`) */
#define LV_TEND_ANY (-2)       /* any end: not checked (`end: any`) */
#define LV_TEND_NONE (-3)      /* no assumption: the phase is not checked */

typedef struct lv_tvar_def {
    char *name;
    double lo, hi, start, scale, step; /* start, scale, step NAN when not written */
    lv_src_loc loc;                    /* the name's value */
    lv_src_loc start_loc;              /* the start's value, or 0 */
    lv_tvar res;                       /* resolved when the mission is loaded */
} lv_tvar_def;

typedef struct lv_tcon_def {
    char *name;
    int path;           /* 1: `path:` - the phase's largest (max) or smallest (min) value of
                           NAME over its rows (docs/targeting.md, "Path constraints"); 0:
                           `final:` */
    lv_con_kind kind;
    double value, tol;
    lv_src_loc loc;
    lv_tfinal res;
    char *end;          /* the `end:` key (NULL: the phase's first end) */
    lv_src_loc end_loc;
    int end_index;      /* resolved: LV_TEND_* or an index into the phase's ends */
} lv_tcon_def;

typedef struct lv_tcost_def {
    int present, maximize;
    char *name;
    double scale;       /* NAN: from the start point */
    lv_src_loc loc;
    lv_tfinal res;
    char *end;          /* as lv_tcon_def */
    lv_src_loc end_loc;
    int end_index;
} lv_tcost_def;

typedef struct lv_targeting_def {
    size_t n_vars;
    lv_tvar_def *vars;
    size_t n_cons;
    lv_tcon_def *cons;
    lv_tcost_def cost;
    lv_target_method method;
    lv_target_diff differences;
    int max_iterations; /* 0: the solver's default */
    double xtol, ftol;  /* 0: the solver's default */
    int restarts;       /* SLSQP restarts from its best point (0: none) */
    lv_src_loc loc;
} lv_targeting_def;

/* A path constraint's extremum (docs/targeting.md, "Path constraints"): the largest (want_max)
 * or smallest value of the column `col` over the rows of `res`, refined by the parabola through
 * the extreme row and its two neighbours when those lie at three distinct times on the
 * output grid (not across an event instant, whose two rows share a time): the parabola's
 * vertex where it lies between them and is beyond the row. NaN values are skipped; *t_out
 * (may be NULL) receives its time. NAN when no row has a number. */
double lv_targeting_path_extremum(const double *t, const double *y, size_t n, int want_max,
                                  double *t_out);

/* One constraint (item k of a `constraints:` list) and the cost, parsed for section `sec`
 * ("targeting", "optimal_control": the same words in both, docs/optimal-control.md). */
lv_status lv_tcon_parse(const lv_pctx *c, const lv_ynode *n, const char *sec, size_t k,
                        lv_tcon_def *con);
lv_status lv_tcost_parse(const lv_pctx *c, const lv_ynode *n, const char *sec,
                         lv_tcost_def *cost);

/* Parses the `targeting:` mapping `n` (NULL or empty: none) into c->m->targeting. */
lv_status lv_targeting_def_parse(const lv_pctx *c, const lv_ynode *n);
/* Resolves and checks the section against the loaded mission m (its plans made): every
 * variable a parameter written in the file, with bounds in its allowed values and the start
 * within them; every final a phase's time, state or output. Errors: "file:line:column:
 * targeting: ...". No section: LV_OK. */
lv_status lv_targeting_def_check(lv_mission *m, lv_err *err);
void lv_targeting_def_free(lv_targeting_def *t); /* accepts NULL */

/* Resolution shared with the programmatic API (src/target); messages carry no position. */
lv_status lv_targeting_resolve_var(const lv_mission *m, const char *name, double lo, double hi,
                                   double start, double scale, double step, lv_tvar *out,
                                   lv_err *err);
lv_status lv_targeting_resolve_final(const lv_mission *m, const char *name, lv_tfinal *out,
                                     lv_err *err);
/* The end `end` of phase k (run order): one of its `end:` entries by its name in the results
 * ("sma", "burnout", "altitude_2"), "stop_time" or "any"; LV_ERR_INPUT naming the phase's ends
 * otherwise. end NULL: the default, its first end (LV_TEND_STOP_TIME without ends). */
lv_status lv_targeting_resolve_end(const lv_mission *m, size_t k, const char *end, int *out,
                                   lv_err *err);
/* The name of end `index` of phase k (LV_TEND_*: "stop_time", "any", "-"). */
const char *lv_targeting_end_name(const lv_mission *m, size_t k, int index);

#endif
