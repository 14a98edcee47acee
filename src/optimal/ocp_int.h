/* ocp_int.h - internal: the transcription of an `optimal_control:` section (lv_ocp.h), shared
 * by the solver (ocp.c) and the optimal mission's writer (ocp_write.c). Not exported. */
#ifndef LV_OPTIMAL_OCP_INT_H
#define LV_OPTIMAL_OCP_INT_H

#include <stddef.h>

#include "lvsim/lv_mission.h"
#include "lvsim/lv_ocp.h"
#include "lvsim/lv_sim.h"
#include "mission/mission_rt.h"
#include "mission/ocp_def.h"

#define OC_MAX_WORKERS 16

/* An optimised phase: its share of the variables and rows. */
typedef struct oc_ph {
    size_t k;                   /* the mission's phase index */
    const lv_ocp_phase_def *def;
    size_t nx, nu, nn, ns;      /* states, controls, control nodes, segments */
    char **xname;               /* [nx] the model's states */
    size_t im;                  /* the mass state's index, or (size_t)-1 */
    double *xs;                 /* [nx] their scales (variables and defect rows) */
    size_t ix;                  /* segment j's start state: variables ix + j nx .. */
    size_t iu;                  /* node i's controls: variables iu + i nu .. */
    long iD;                    /* the duration's variable, or -1 (fixed: D) */
    double D;                   /* s, the fixed duration (or the start's) */
    size_t r_link;              /* nx rows: X_0 - the hand-off's start */
    size_t r_def;               /* (ns - 1) nx rows: segment j's at r_def + j nx */
    size_t n_path;              /* the path constraints on this phase */
    size_t *path_con;           /* [n_path] their indices in the section's constraints */
    size_t r_path;              /* n_path (ns + 1) rows: con q at node j: r_path + q (ns+1) + j */
    char (*path_out)[64];       /* [n_path] the output's name (no _deg) */
    int burns;                  /* the phase starts with propellant in its burning stage */
    size_t r_mass;              /* the row: final mass - burnout mass >= 0, or (size_t)-1 */
} oc_ph;

/* A worker: a mission and run of its own (its control tables are its own). */
typedef struct oc_worker {
    lv_mission *m;
    lv_run *r;
    double *x, *g, *g2;         /* [n], [m + 1] x2: a point and its rows (g[m]: the cost) */
    long segments;
    char why[LV_ERR_MSG_MAX];
} oc_worker;

struct lv_ocp {
    char *path;                 /* the mission file */
    const lv_ocp_def *def;      /* the section (of w[0]'s mission) */
    size_t n_phases;            /* the mission's */
    int *opt_of;                /* [n_phases] index into ph, or -1 */
    unsigned char *needed;      /* [n_phases] flown in an evaluation */
    size_t np;
    oc_ph *ph;                  /* [np] the optimised phases, in run order */
    size_t n, m;                /* variables, constraint rows (the cost is row m) */
    double *sx;                 /* [n] variable scales: x = z sx */
    double *zl, *zu;            /* [n] scaled bounds */
    double *gl, *gu;            /* [m] row bounds */
    char (*vname)[128];          /* [n] what each variable is (messages) */
    size_t r_fin;               /* the final constraints' rows: r_fin + c (path ones unused) */
    double cost_scale;          /* > 0; the cost's sign: -1 for maximize */
    double cost_sign;
    /* Jacobian: the pattern by column (rows sorted; the cost row m included) */
    size_t *jc;                 /* [n + 1] column starts into jr */
    size_t *jr;                 /* rows */
    size_t nnz;                 /* entries without the cost row */
    size_t n_groups;
    size_t *grp_start, *grp_col; /* group g: columns grp_col[grp_start[g] .. grp_start[g+1]) */
    double *jv;                 /* [jc[n]] values dg/dz by column */
    /* the current point */
    double *z_base;             /* [n] scaled point of g_base; NAN first */
    double *g_base;             /* [m + 1] */
    int base_ok;
    double *z_jac;              /* [n] the point jv belongs to */
    int jac_ok;
    double itol;                /* the segments' relative tolerance */
    int n_workers;
    oc_worker w[OC_MAX_WORKERS];
    double *z_best;             /* [n] the point to return */
    /* a solve */
    const lv_ocp_settings *set;
    lv_ocp_result res;
    double t0_wall;
    long evaluations;
    int stopped;
    int iter_last;
    int solved;                 /* lv_ocp_solve has run (res holds its outcome) */
    int best_feasible;          /* z_best meets every row */
    double best_cost, best_worst; /* its scaled cost and largest violation */
    double cost_start;
};

/* Evaluates every row at the scaled point z on worker w: g[m + 1] (the cost divided by its
 * scale, signed to be minimised, in g[m]). With `propagate`, each segment's start state in z
 * is first set to where the previous segment ended (and each optimised phase's first state to
 * its hand-off's start): the defects and links are then 0. 1 when every phase flew; 0 with
 * w->why otherwise. */
int oc_evaluate(lv_ocp *o, oc_worker *w, double *z, double *g, int propagate);

/* The settings of segment [ta, tb] of optimised phase p, prepared with settings cs, from its
 * state x (the hand-off's other start values kept, no ends, no rows, the segments' tolerance);
 * names/values: room for cs->n_initial + p->nx entries. */
void oc_segment_settings(const lv_ocp *o, const lv_sim_settings *cs, const oc_ph *p,
                         const double *x, double m_burnout, double ta, double tb,
                         const char **names, double *values, lv_sim_settings *s);
/* Phase p's start from its prepared model, def, inst and settings cs: its states x[nx] and
 * the mass at which its burning stage burns out (its start mass less its propellant then;
 * NAN for a model without both: a segment starts with the propellant its mass holds above
 * it). */
lv_status oc_phase_start(const oc_ph *p, const lv_model_def *def, void *inst,
                         const lv_sim_settings *cs, double *x, double *m_burnout, lv_err *err);

/* The run of worker 0 at the point z flown by oc_evaluate (its phases' results). */
double oc_phase_t0(const lv_ocp *o, const oc_worker *w, size_t k);

#endif
