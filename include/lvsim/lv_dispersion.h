/* lv_dispersion.h - the dispersions of a mission (its `dispersions:` section): which
 * parameters a Monte Carlo campaign perturbs and how, and the values run i of a campaign
 * draws. Format, generator and streams: docs/monte-carlo.md.
 *
 * Generator: Philox4x32-10 (Salmon, Moraes, Dror, Shaw, "Parallel random numbers: as easy as
 * 1, 2, 3", SC'11; Random123, Debian librandom123-dev), a counter-based generator: the draw
 * of parameter p in run i is one call philox4x32(counter, key) with
 *     key     = (seed mod 2^32, seed / 2^32)
 *     counter = (i mod 2^32, i / 2^32, h mod 2^32, h / 2^32),  h = FNV-1a 64 of p's name,
 * so run i draws the same values whatever the thread or MPI rank that runs it, the order of
 * the runs, and whatever other parameters the file disperses (one stream per parameter).
 * The 64 high bits of the output give u in (0, 1) (u01fixedpt_open_open_64_double); a normal
 * is the inverse normal CDF of u (Wichura, AS 241, 1988), a truncated normal inverts its own
 * CDF, a uniform is lo + (hi - lo) u. A correlation group draws z from its members' streams and
 * uses x = L z (L: the Cholesky factor of the correlation matrix): normal members take x
 * directly, the others u = Phi(x) (a Gaussian copula).
 *
 * Threads: the mission is read-only; any thread may draw.
 */
#ifndef LVSIM_LV_DISPERSION_H
#define LVSIM_LV_DISPERSION_H

#include <stddef.h>
#include <stdint.h>

#include "lvsim/lv_mission.h"
#include "lvsim/lv_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum lv_disp_dist {
    LV_DIST_NORMAL = 0,       /* mean, sigma */
    LV_DIST_TRUNCATED_NORMAL, /* mean, sigma, cut to [min, max] (either may be infinite) */
    LV_DIST_UNIFORM           /* [min, max] */
} lv_disp_dist;

typedef struct lv_disp_info {
    const char *name;     /* as written: "core-engine.isp_vac", "start_fpa_deg" */
    const char *unit;     /* of the drawn value: the parameter's SI unit, "deg" for *_deg */
    const char *dist;     /* "normal", "truncated_normal", "uniform" */
    lv_disp_dist kind;
    int relative;         /* 1: value = nominal * factor; mean .. max describe the factor */
    double nominal;       /* the file's value (in `unit`) */
    double mean, sigma;   /* normal, truncated normal (of the value, or of the factor) */
    double min, max;      /* truncated normal (+-INFINITY when open), uniform */
    size_t param;         /* its lv_mission_param index */
    int group;            /* its correlation group, or -1 */
    uint64_t stream;      /* FNV-1a 64 of the name */
    int line, column;     /* where the file writes it */
} lv_disp_info;

/* The dispersed parameters, in file order. */
LV_API size_t lv_mission_disp_count(const lv_mission *m);
LV_API void lv_mission_disp_info(const lv_mission *m, size_t j, lv_disp_info *out);
/* The correlation the file gives between dispersed parameters a and b (1 for a == b, 0 when
 * they are not in one group). */
LV_API double lv_mission_disp_correlation(const lv_mission *m, size_t a, size_t b);
/* 1 when the mission flies turbulence (`environment: turbulence:`, docs/wind.md): every run
 * of a campaign flies its own realisation, drawn from (seed, run) like its dispersions, so a
 * campaign varies even without a `dispersions:` section. */
LV_API int lv_mission_turbulent(const lv_mission *m);
/* The number of dispersed profiles (`dispersions: profiles:`, docs/monte-carlo.md "Dispersed
 * profiles"): each run of a campaign flies its own perturbation profiles, drawn from
 * (seed, run), so a campaign varies even without dispersed parameters. */
LV_API size_t lv_mission_disp_profile_count(const lv_mission *m);
/* The file's `seed:` (1), or 0 when it gives none (*seed untouched). */
LV_API int lv_mission_disp_seed(const lv_mission *m, uint64_t *seed);

/* The values run `run` of a campaign with seed `seed` draws: values[j] for dispersed
 * parameter j, in its written unit (degrees for *_deg). Pure: the same arguments give the
 * same bits. */
LV_API void lv_mission_disp_draw(const lv_mission *m, uint64_t seed, uint64_t run,
                                 double *values);
/* Draws run `run`'s values and sets them on `r` (values may be NULL; else they are returned
 * as by lv_mission_disp_draw). A drawn value outside its parameter's range (a negative mass
 * from a wide normal) is LV_ERR_INPUT naming it; the run keeps its earlier values then.
 * From then on the run also flies the turbulence and the dispersed profiles of (seed, run);
 * a run never dispersed flies the nominal profiles (no perturbation). */
LV_API lv_status lv_run_disperse(lv_run *r, uint64_t seed, uint64_t run, double *values,
                                 lv_err *err);

/* The generator itself: u in (0, 1) for (seed, stream, run), and the inverse standard normal
 * CDF (AS 241, relative accuracy about 1e-16). */
LV_API double lv_disp_uniform(uint64_t seed, uint64_t stream, uint64_t run);
LV_API double lv_disp_norm_inv(double p);
/* FNV-1a 64 of a name: its stream. */
LV_API uint64_t lv_disp_stream(const char *name);

#ifdef __cplusplus
}
#endif
#endif
