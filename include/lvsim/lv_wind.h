/* lv_wind.h - wind as a table over altitude (north, east and optionally down components),
 * or a constant.
 *
 * Contract: the wind is the velocity of the air relative to the ground (the rotating planet,
 * or the flat world), in the local NED frame (docs/frames.md), m/s, as a function of the
 * altitude h [m] (geodetic on a planet, z on the flat world). Models subtract it from the
 * velocity relative to the ground: v_air = v_rel - v_wind. A table is interpolated linearly
 * unless created with other options; outside its altitude range it is clamped by default
 * (above the top it keeps the top row's value, below the bottom the bottom row's), or
 * follows the options' extrapolation (LV_EXTRAP_LINEAR, or LV_EXTRAP_ERROR: an evaluation
 * error). A table of one row, and lv_wind_create_const, give the same wind at every altitude.
 * File format and conventions: docs/wind.md.
 *
 * Threads: an lv_wind is immutable after creation and may be shared read-only between
 * threads and simulations; the only mutable state is the caller's lv_table_cursor (one
 * per simulation, e.g. inside an lv_wind_user).
 */
#ifndef LVSIM_LV_WIND_H
#define LVSIM_LV_WIND_H

#include <stdint.h>

#include "lvsim/lv_perturbation.h"
#include "lvsim/lv_status.h"
#include "lvsim/lv_table.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct lv_wind lv_wind; /* opaque, immutable once created */

/* Loads a wind table. `path` ending in ".mat": MAT file, `var` the matrix
 * [h, north, east(, down)] (Modelica CombiTable1D layout, columns by position); otherwise
 * CSV with `var` NULL and the header "h [m], north [m/s], east [m/s][, down [m/s]]"
 * (also "v_north", "v_east", "v_down"; units optional, SI only; any column order).
 * Errors: LV_ERR_IO (unreadable), LV_ERR_INPUT (missing or unknown column, wrong unit,
 * non-increasing altitudes - path:line:column from the table loader), LV_ERR_NOTFOUND
 * (no variable `var` in the MAT file). lv_wind_free(*out) when done. */
LV_API lv_status lv_wind_create_table(const char *path, const char *var, lv_wind **out,
                                      lv_err *err);
/* The same with interpolation and extrapolation of the caller's choice (`opts` NULL:
 * LV_INTERP_LINEAR, LV_EXTRAP_CLAMP). A file of one row is a constant wind (any `opts`). */
LV_API lv_status lv_wind_create_table_opts(const char *path, const char *var,
                                           const lv_table_opts *opts, lv_wind **out,
                                           lv_err *err);
/* A constant wind, m/s: north, east, down (finite; LV_ERR_INPUT otherwise). */
LV_API lv_status lv_wind_create_const(double north, double east, double down, lv_wind **out,
                                      lv_err *err);
LV_API void lv_wind_free(lv_wind *w); /* accepts NULL */
/* A copy of `w` with every component c (north, east, down) replaced by
 * scale * c + bias[c] (`bias` NULL: no bias): a wind profile dispersed per run. A table without
 * a down column keeps down 0 (bias[2] ignored). lv_wind_free(*out) when done. */
LV_API lv_status lv_wind_create_affine(const lv_wind *w, double scale, const double bias[3],
                                       lv_wind **out, lv_err *err);


/* Winds from measured or forecast profiles (docs/wind.md, "Profiles"): n files (the profile
 * CSV or the University of Wyoming sounding text list: docs/atmosphere.md, "Profiles"), each
 * valid at mission time t[k] [s] (strictly increasing). At an altitude h each profile's wind
 * is its levels' interpolated linearly, the lowest level's below them, and above its top level
 * tapers linearly to zero over `blend` metres (zero above); then linearly in time between the
 * two profiles around t (the first before t[0], the last after t[n-1]). Down is 0.
 * 1 <= n <= LV_WIND_PROFILES_MAX. Errors: the profiles' (path:line:column), a file without a
 * wind, times not increasing. lv_wind_free(*out) when done. */
#define LV_WIND_PROFILES_MAX 24
LV_API lv_status lv_wind_create_profiles(const char *const *paths, const double *t, size_t n,
                                         double blend, lv_wind **out, lv_err *err);
/* The number of profiles of a profile wind; 0 for any other wind. */
LV_API size_t lv_wind_profile_count(const lv_wind *w);

/* ---- gusts and turbulence (docs/wind.md, "Gusts and turbulence") --------------------------
 *
 * A disturbance is a field over altitude h [m] added to a wind: discrete 1-cosine gusts and
 * Dryden continuous turbulence, frozen over altitude (Taylor's hypothesis along the vertical
 * path of a rising or falling vehicle: the air a vehicle meets at an altitude is the same on
 * every pass). Components in local NED, m/s.
 *
 * 1-cosine gust (MIL-F-8785C sec. 3.7.4; MIL-HDBK-1797 sec. 4.9.1), peak v_max at `altitude`,
 * zero beyond +-half_width d:  v(h) = v_max (1 + cos(pi (h - altitude) / d)) / 2, |h - altitude| <= d.
 *
 * Dryden turbulence (MIL-F-8785C sec. 3.7.2, spectra in the spatial frequency Omega [rad/m],
 * one-sided, integral over (0, inf) = sigma^2): along the path, the vertical component (down),
 *     Phi_long(Omega) = sigma^2 (2 L / pi) / (1 + (L Omega)^2),
 * across it, north and east,
 *     Phi_lat(Omega)  = sigma^2 (L / pi) (1 + 3 (L Omega)^2) / (1 + (L Omega)^2)^2.
 * A realisation is drawn once, at spacing L / 20, by the exact discretisation of the
 * spectra's first- and second-order shaping filters (samples of the continuous process, not an
 * approximation of it), driven by the seeded stream (seed, run): the same (seed, run) gives the
 * same bits on any thread or rank. Between samples the natural cubic spline through them (C2). Inside
 * [h_from, h_to], faded in and out over one L at each end by (1 - cos)/2; zero outside. */
typedef struct lv_gust_1cos {
    double altitude;   /* m, where the gust peaks */
    double half_width; /* m, d > 0: the gust builds up over d and decays over d */
    double v_max[3];   /* m/s, the peak wind added: north, east, down */
} lv_gust_1cos;

typedef struct lv_dryden_spec {
    double sigma_h;    /* m/s, >= 0: the north and east components' standard deviation */
    double sigma_v;    /* m/s, >= 0: the vertical component's */
    double length;     /* m, L > 0: the scale length (MIL-F-8785C above 2000 ft: 1750 ft = 533.4 m) */
    double h_from, h_to; /* m, h_from < h_to: the layer (at most 2^22 samples: (h_to - h_from) / (L/20)) */
} lv_dryden_spec;

#define LV_GUSTS_MAX 16
typedef struct lv_wind_disturbance lv_wind_disturbance; /* opaque, immutable once created */

/* A disturbance: `turb` (NULL: no turbulence) and n_gusts <= LV_GUSTS_MAX gusts (NULL when 0),
 * the turbulence realised from the stream (seed, run) (lv_dispersion.h's generator; stream
 * "environment.turbulence"). LV_ERR_INPUT for a value out of its domain, naming it.
 * lv_wind_disturbance_free(*out) when done. */
LV_API lv_status lv_wind_disturbance_create(const lv_dryden_spec *turb, const lv_gust_1cos *gusts,
                                            size_t n_gusts, uint64_t seed, uint64_t run,
                                            lv_wind_disturbance **out, lv_err *err);
LV_API void lv_wind_disturbance_free(lv_wind_disturbance *d); /* accepts NULL */
/* The checks of lv_wind_disturbance_create alone (nothing drawn): LV_OK, or LV_ERR_INPUT with
 * the value out of its domain named. */
LV_API lv_status lv_wind_disturbance_check(const lv_dryden_spec *turb, const lv_gust_1cos *gusts,
                                           size_t n_gusts, lv_err *err);
/* v_ned = the disturbance at altitude h [m] (0 for a NaN h). No allocation: for right-hand
 * sides. */
LV_API void lv_wind_disturbance_eval(const lv_wind_disturbance *d, double h, double v_ned[3]);
/* The turbulence's sample spacing [m] and first sample's altitude (0, 0 without turbulence):
 * the realisation's value at h_from + k * spacing is its k-th sample (for spectral checks). */
LV_API void lv_wind_disturbance_grid(const lv_wind_disturbance *d, double *h0, double *spacing);

/* A wind plus a disturbance: base (NULL: still air) + d at every (t, h). Both borrowed: they
 * must outlive *out. Evaluation errors are the base's. lv_wind_free(*out) when done. */
LV_API lv_status lv_wind_create_disturbed(const lv_wind *base, const lv_wind_disturbance *d,
                                          lv_wind **out, lv_err *err);

/* A wind dispersed by a perturbation profile (lv_perturbation.h; docs/wind.md, "Dispersed
 * profiles"): base (NULL: still air) plus the perturbation's two components as north and
 * east, m/s, at every (t, h): every profile of a multi-profile wind alike; down unchanged.
 * Both borrowed: they must outlive *out. LV_ERR_INPUT unless p has 2 components. Evaluation
 * errors are the base's. lv_wind_free(*out) when done. */
LV_API lv_status lv_wind_create_perturbed(const lv_wind *base, const lv_perturbation *p,
                                          lv_wind **out, lv_err *err);

/* 1 for a constant wind (lv_wind_create_const, or a table of one row). */
LV_API int lv_wind_is_constant(const lv_wind *w);
/* Altitude range of the table [m]; -INFINITY, INFINITY for a constant wind. */
LV_API void lv_wind_range(const lv_wind *w, double *h_lo, double *h_hi);

/* v_ned = wind at altitude h [m]: north, east, down in m/s (down 0 when the table has no
 * down column). `cur` may be NULL. Hot path: no allocation; a message is formatted only on
 * failure and only if err != NULL. Fails (LV_ERR_INPUT; v_ned unchanged) for a NaN altitude,
 * and outside the table under LV_EXTRAP_ERROR ("wind: table 'w': axis 0 'h' [m] = 21000 is
 * outside [0, 20000] ..."). */
LV_API lv_status lv_wind_eval(const lv_wind *w, lv_table_cursor *cur, double h,
                              double v_ned[3], lv_err *err);

/* The same at mission time t [s]: the time matters only for a wind of several profiles
 * (lv_wind_create_profiles; lv_wind_eval evaluates it at t = 0). LV_ERR_INPUT for a NaN t
 * there. */
LV_API lv_status lv_wind_eval_at(const lv_wind *w, lv_table_cursor *cur, double t, double h,
                                 double v_ned[3], lv_err *err);

/* The `user` block of lv_wind_fn_table: the (borrowed) wind and one cursor. One per
 * simulation; zero-initialise the cursor (LV_WIND_USER_INIT(w)). */
typedef struct lv_wind_user {
    const lv_wind *w;    /* borrowed; must outlive the simulation */
    lv_table_cursor cur; /* interval last used */
} lv_wind_user;
#define LV_WIND_USER_INIT(w) { (w), LV_TABLE_CURSOR_INIT }

/* An lv_wind_fn (lv_vehicle.h) for the 3-DoF model:
 *     lv_wind_user wu = LV_WIND_USER_INIT(wind);
 *     cfg.wind = lv_wind_fn_table;  cfg.wind_user = &wu;
 * `user` is an lv_wind_user *. Ignores lat and lon; t only for a wind of profiles. Returns 0; 1 (state not acceptable)
 * for a NaN altitude; -1 (stop the run) outside the table under LV_EXTRAP_ERROR, as an
 * engine table outside its range stops it. */
LV_API int lv_wind_fn_table(double t, double h, double lat, double lon, double v_wind_ned[3],
                            void *user);

#ifdef __cplusplus
}
#endif
#endif
