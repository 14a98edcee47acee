/* dispersion.h - a mission's `dispersions:` section as data (not exported): which parameters a
 * Monte Carlo campaign perturbs, by which distribution, with which correlations, and the
 * table dispersions (a scale factor or an additive bias on a table's outputs) with the per-run
 * table copies they need. Format: docs/monte-carlo.md; public view: lvsim/lv_dispersion.h.
 */
#ifndef LV_MISSION_DISPERSION_H
#define LV_MISSION_DISPERSION_H

#include <stddef.h>
#include <stdint.h>

#include "lvsim/lv_dispersion.h"
#include "lvsim/lv_perturbation.h"
#include "lvsim/lv_table.h"
#include "lvsim/lv_wind.h"
#include "mission/mission.h"
#include "mission/parse_kit.h"

/* One dispersed parameter. Numbers are in the unit the name is written in (degrees for a
 * "*_deg" name) or, with `relative`, of the factor that multiplies the file's value. */
typedef struct lv_disp_param {
    char *name;          /* as written: "core-engine.isp_vac", "start_fpa_deg" */
    lv_slot slot;
    int deg;             /* the name ends in _deg: values in degrees */
    lv_disp_dist dist;
    int relative;        /* value = nominal * factor; mean, sigma, lo, hi describe the factor */
    double nominal;      /* the file's value, in the written unit */
    double mean, sigma;  /* normal, truncated normal */
    double lo, hi;       /* truncated normal (-inf, +inf when not given), uniform */
    uint64_t stream;     /* FNV-1a 64 of the name: the parameter's stream */
    int group;           /* correlation group, or -1 */
    size_t gpos;         /* position in its group */
    lv_src_loc loc;
} lv_disp_param;

typedef struct lv_disp_group {
    size_t n;
    size_t *member;      /* [n] indices into the parameters */
    double *corr;        /* [n * n] the correlation matrix as given */
    double *chol;        /* [n * n] its Cholesky factor L (lower, row-major): corr = L L^T */
    lv_src_loc loc;
} lv_disp_group;

/* A table dispersion: slot `slot` (registered by the parser, "<table>[.<output>].scale" or
 * ".bias") acting on output `out` (SIZE_MAX: every output) of an engine table (`table`) or of
 * the wind (`wind`: outputs 0 north, 1 east, 2 down; `table` NULL). */
typedef struct lv_table_xf {
    const lv_table *table;
    int wind;
    size_t out;
    int bias;            /* 0: scale factor (identity 1); 1: additive bias (identity 0) */
    lv_slot slot;
} lv_table_xf;

/* A dispersed profile (`profiles:`): a perturbation profile drawn per Monte Carlo run
 * (lv_perturbation.h) added to the wind (north, east; m/s) or multiplying the density
 * (1 + delta). */
typedef enum lv_prof_target { LV_PROF_WIND, LV_PROF_DENSITY } lv_prof_target;
typedef struct lv_disp_profile {
    lv_prof_target target;
    const char *name;      /* "environment.wind", "environment.atmosphere.density" */
    size_t n_sigma;
    double sigma_h[LV_PERTURBATION_SIGMA_MAX], sigma[LV_PERTURBATION_SIGMA_MAX];
    double length, h_from, h_to; /* m */
    uint64_t stream[LV_PERTURBATION_COMP_MAX]; /* "profiles.<name>[.north|.east]" */
    lv_src_loc loc;
} lv_disp_profile;

typedef struct lv_disp_def {
    size_t n_prof;
    lv_disp_profile prof[2];
    int has_seed;
    uint64_t seed;
    size_t n;
    lv_disp_param *p;
    size_t n_groups;
    lv_disp_group *groups;
    size_t n_xf;
    lv_table_xf *xf;
} lv_disp_def;

/* Parses `dispersions:` (n: its value, may be NULL or empty: none) after every other section,
 * so that every parameter exists; registers the table dispersions' slots. Sets c->m->disp. */
lv_status lv_disp_def_parse(const lv_pctx *c, const lv_ynode *n);
void lv_disp_def_free(lv_disp_def *d); /* accepts NULL */

/* ---- per-run table copies ---------------------------------------------------------------
 * A run whose table-dispersion slots differ from the identity flies copies of the tables (and
 * of the wind) with its factors applied. lv_run_tables_update (single-threaded: before a run
 * executes or prepares a phase) rebuilds the copies whose values changed; phase builds then
 * only read them through lv_build_table / lv_build_wind (phase_type.h). */
typedef struct lv_run_tables lv_run_tables;
/* Also the run's gusts and turbulence (the environment's `gust:`, `turbulence:`): made from
 * its slot values and the realisation (seed, run), again when any of them changed. */
/* And, when `profiles` is 1 (a Monte Carlo run: lv_run_disperse), the realisations of the
 * dispersed profiles for (seed, run); 0: the nominal (none). */
lv_status lv_run_tables_update(const lv_mission_def *d, const lv_wind *wind, const double *vals,
                               uint64_t seed, uint64_t run, int profiles, lv_run_tables **rt,
                               lv_err *err);
void lv_run_tables_free(lv_run_tables *rt); /* accepts NULL */
/* The run's copy of `t` (t itself when no dispersion applies or rt is NULL). */
const lv_table *lv_run_tables_get(const lv_run_tables *rt, const lv_table *t);
/* The run's wind when a wind dispersion applies, else NULL. */
const lv_wind *lv_run_tables_wind(const lv_run_tables *rt);
/* The run's perturbation of `target`, or NULL (not dispersed, or a nominal run). */
const lv_perturbation *lv_run_tables_profile(const lv_run_tables *rt, lv_prof_target target);
/* Whether the run's values make gusts and turbulence that can be drawn (a dispersed layer
 * turned upside down, too deep): LV_ERR_INPUT naming the value otherwise. */
lv_status lv_run_disturbance_check(const lv_mission_def *d, const double *vals, lv_err *err);
/* The run's gusts and turbulence, or NULL (none in the mission). */
const lv_wind_disturbance *lv_run_tables_disturbance(const lv_run_tables *rt);

#endif
