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
    size_t iseg;                /* its segments' propellant in lv_ocp.prop_book: iseg + j */
    long ph_el;                 /* the model's parameter phase_elapsed, or -1 */
    unsigned char *ph_x0;       /* [nx] the model takes phase_start_<state> */
    char (*ph_x0_name)[48];     /* [nx] "phase_start_<state>" */
    size_t r_mass;              /* the row: final mass - burnout mass >= 0, or (size_t)-1 */
} oc_ph;

/* Where a fixed burn's segments take their propellant (oc_segment_propellant). */
typedef enum oc_book {
    OC_BOOK_OWN, /* the segment's start mass less the burnout mass */
    OC_BOOK_SET, /* the same, recorded in lv_ocp.prop_book: the base point's */
    OC_BOOK_USE  /* the base point's, recorded: a difference step's */
} oc_book;

/* A worker: a mission and run of its own (its control tables are its own). */
typedef struct oc_worker {
    oc_book book;
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
    double *prop_book;          /* [segments] a fixed burn's segment's propellant at z_base */
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
/* oc_evaluate of z_base into g_base on worker 0, recording the fixed burns' propellant that
 * the differences at z_base take (OC_BOOK_SET). */
int oc_evaluate_base(lv_ocp *o);

/* The propellant that segment j of optimised phase p starts with, from its start state x and
 * the phase's burnout mass (NAN: none given, the model's own). Where the optimiser decides the
 * burn (a throttle control, a free duration: the row r_mass) all but 1e-9 of the mass; where
 * the burn is fixed, the mass above the burnout mass - and on a worker taking differences
 * (OC_BOOK_USE) the base point's value, so that a step in a mass (its own, or a parent's that
 * moves the burnout mass) does not move a burnout into a segment that ends before it: Delta
 * III's fixed burns end 1.7 kg of propellant before their burnout, and a step of 4.6e-4 of a
 * 200 t mass scale is 92 kg. Frozen like an integrator's step sequence in internal numerical
 * differentiation (Bock, 1981; Albersmeyer & Diehl, SIAM J. Optim. 2010), the difference is
 * the derivative of the branch the base point flies. */
double oc_segment_propellant(const lv_ocp *o, const oc_worker *w, const oc_ph *p, size_t j,
                             const double *x, double m_burnout);
/* The settings of segment [ta, tb] of optimised phase p, prepared with settings cs, from its
 * state x and propellant prop (oc_segment_propellant; NAN: the model's own) (the hand-off's
 * other start values kept, no ends, no rows, the segments' tolerance), and the phase's start
 * x0 at mission time t0 for a model that keeps something from it (phase_elapsed,
 * phase_start_*: a steering law's frame and time, the downrange origin); names/values: room for cs->n_initial + 2 p->nx + 2
 * entries. */
void oc_segment_settings(const lv_ocp *o, const lv_sim_settings *cs, const oc_ph *p,
                         const double *x0, double t0, const double *x, double prop, double ta,
                         double tb, const char **names, double *values, lv_sim_settings *s);
/* Phase p's start from its prepared model, def, inst and settings cs: its states x[nx] and
 * the mass at which its burning stage burns out (its start mass less its propellant then;
 * NAN for a model without both: a segment starts with the propellant its mass holds above
 * it). */
lv_status oc_phase_start(const oc_ph *p, const lv_model_def *def, void *inst,
                         const lv_sim_settings *cs, double *x, double *m_burnout, lv_err *err);

/* The run of worker 0 at the point z flown by oc_evaluate (its phases' results). */
double oc_phase_t0(const lv_ocp *o, const oc_worker *w, size_t k);

#endif
