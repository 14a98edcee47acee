/* mc_data.h - a campaign database read back for statistics and figures (stats.c, plot.c). */
#ifndef LV_CAMPAIGN_MC_DATA_H
#define LV_CAMPAIGN_MC_DATA_H

#include <stddef.h>

#include "lvsim/lv_status.h"

typedef struct lv_mc_phase {
    char *name;
    char *stages;         /* the bodies it carries, "upper, payload" ("" before schema 3) */
    int parent;
    char tbl[128];
    size_t n_rows, n_cols;
    size_t *run;          /* [n_rows] the run of each row (ascending) */
    size_t *row_of;       /* [n_runs] the row of each run, or (size_t)-1 */
    unsigned char *state; /* [n_rows] 1 done, 2 failed, 3 skipped */
    char **end, **error;  /* [n_rows] */
    char **col;           /* [n_cols] the final values' names */
    double *v;            /* [n_rows * n_cols], NaN: none */
} lv_mc_phase;

/* A phase's impact point at one of its `iip_at:` times, over the runs (the table iip). */
typedef struct lv_mc_iip {
    char label[160];       /* "IIP at T+60 s (ascent)": the footprint's name in every output */
    int phase;             /* its phase's index */
    double t;              /* s, mission time */
    size_t n;              /* runs with a row */
    size_t n_impact, n_orbit, n_not_flying; /* by state */
    size_t *run;           /* [n] ascending */
    unsigned char *state;  /* [n] lv_iip_state: 0 impact, 1 in orbit, 2 not flying */
    double *lat, *lon;     /* [n] rad (NaN unless an impact) */
    double *tof, *range;   /* [n] s, m (NaN unless an impact) */
} lv_mc_iip;

typedef struct lv_mc_data {
    char mission[256], planet[64], seed[32];
    size_t n_runs, n_stored, n_input_fail;
    size_t n_run_failed, n_run_impact, n_run_crashed; /* stored runs by runs.status */
    size_t n_in;
    char **in_name, **in_unit;
    double *in;                /* [n_runs * n_in] NaN when not stored */
    unsigned char *run_status; /* [n_runs] 0 not stored, 1 ok (or an impact), 2 failed,
                                  3 input */
    size_t n_ph;
    lv_mc_phase *ph;
    size_t n_iip;              /* the IIP footprints: per phase, its `iip_at:` times */
    lv_mc_iip *iip;
} lv_mc_data;

lv_status lv_mc_data_load(const char *db_path, lv_mc_data **out, lv_err *err);
void lv_mc_data_free(lv_mc_data *d);
size_t lv_mc_col(const lv_mc_phase *p, const char *name); /* (size_t)-1: none */

typedef struct lv_mc_stat {
    size_t n;
    double mean, sd, p1, p50, p99, min, max;
} lv_mc_stat;
void lv_mc_summary(const double *x, size_t n, lv_mc_stat *s); /* finite values only */
double lv_mc_pearson(const double *x, const double *y, size_t n, size_t *used);

typedef struct lv_mc_ell {
    size_t n;
    double mx, my, sx, sy, rho;
    double a, b, theta; /* semi-axes (k sqrt(lambda)), major axis angle from +x, rad */
    double k;
} lv_mc_ell;
void lv_mc_ellipse(const double *x, const double *y, size_t n, double k, lv_mc_ell *e);

void lv_mc_planet(const lv_mc_data *d, double *a, double *e2);
void lv_mc_ground(const lv_mc_data *d, double lat0, double lon0, double lat, double lon,
                  double *east, double *north);
void lv_mc_ground_inv(const lv_mc_data *d, double lat0, double lon0, double east, double north,
                      double *lat, double *lon);
size_t lv_mc_ground_points(const lv_mc_data *d, const lv_mc_phase *p, double *east,
                           double *north, double *lat0, double *lon0);
/* The same for points given as lat[i], lon[i] (rad; a non-finite one is left out: east and
 * north NaN there); east, north may be lat, lon themselves (each point is read before it is
 * written). Returns the count of points. */
size_t lv_mc_ground_xy(const lv_mc_data *d, size_t n, const double *lat, const double *lon,
                       double *east, double *north, double *lat0, double *lon0);
int lv_mc_is_impact(const lv_mc_phase *p);
const char *lv_mc_cause(const char *error);
extern const char *const lv_mc_orbit_pairs[][2];

#endif
