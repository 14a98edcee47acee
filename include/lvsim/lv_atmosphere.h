/* lv_atmosphere.h - atmosphere models: U.S. Standard Atmosphere 1976, an exponential model
 * and a table read from a file.
 *
 * Contract: the input is geometric altitude above the reference surface in m; the output
 * is an lv_atmo_state in SI units. Models are looked up by name ("us76", "exp", "table",
 * "profile");
 * each has its own parameter block, created and freed through the model (or through an
 * lv_atmo handle, which pairs a model with its parameters). Evaluation allocates nothing and is
 * safe to call from several threads on the same parameters.
 *
 * Valid range: -5 km to 1000 km for "us76" and "exp" (the range of the 1976 tables); for
 * "table", the altitudes of its file. An altitude outside it, or NaN, gives LV_ERR_INPUT
 * naming the altitude and the range.
 *
 * Above 86 km the 1976 document defines T, p, rho and M but not the speed of sound or the
 * viscosity; "us76" then returns its 86 km formulas applied to the local state (see
 * docs/atmosphere.md): a = sqrt(gamma R* T / M), mu = beta T^1.5 / (T + S).
 */
#ifndef LVSIM_LV_ATMOSPHERE_H
#define LVSIM_LV_ATMOSPHERE_H

#include <stddef.h>

#include "lvsim/lv_perturbation.h"
#include "lvsim/lv_status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LV_ATMO_ALT_MIN (-5000.0)  /* m, lowest altitude of every model */
#define LV_ATMO_ALT_MAX 1000000.0  /* m, highest altitude of every model */

/* Atmospheric state at one altitude. */
typedef struct lv_atmo_state {
    double T;   /* K, kinetic temperature */
    double p;   /* Pa, pressure */
    double rho; /* kg/m^3, mass density */
    double a;   /* m/s, speed of sound */
    double mu;  /* Pa s, dynamic viscosity */
    double M;   /* kg/kmol, mean molecular weight */
} lv_atmo_state;

/* A model: name and functions; its parameters live apart, in a block it creates.
 * `eval` is the hot path: no allocation, no lookup by name. */
typedef struct lv_atmo_model {
    const char *name;        /* key used in mission files: "us76", "exp", "table" */
    const char *description; /* one line */
    /* Creates the parameter block with default values (for "us76": a few constants; its
     * upper-atmosphere table is computed at build time and shared, nothing is integrated). */
    lv_status (*par_create)(void **par, lv_err *err);
    void (*par_free)(void *par); /* accepts NULL */
    /* Sets one parameter by key; unknown keys give LV_ERR_NOTFOUND with suggestions. */
    lv_status (*par_set)(void *par, const char *key, double value, lv_err *err);
    lv_status (*eval)(const void *par, double alt_m, lv_atmo_state *out, lv_err *err);
} lv_atmo_model;

/* U.S. Standard Atmosphere 1976, -5 km to 1000 km; no settable parameters. */
LV_API extern const lv_atmo_model lv_atmo_us76;

/* Exponential density rho = rho0 exp(-h / H), constant temperature T; p = rho R* T / M0,
 * a and mu from T with the US76 constants. Keys: "rho0" (kg/m^3, default 1.225),
 * "H" (m, default 7200), "T" (K, default 288.15). */
LV_API extern const lv_atmo_model lv_atmo_exp;

/* Parameters of lv_atmo_exp (the block its par_create allocates). */
typedef struct lv_atmo_exp_par {
    double rho0; /* kg/m^3, density at h = 0 */
    double H;    /* m, density scale height */
    double T;    /* K, temperature */
} lv_atmo_exp_par;

/* A table over geometric altitude from a file (docs/atmosphere.md, "Table atmosphere"):
 * T [K] interpolated linearly, p [Pa] and rho [kg/m^3] log-linearly; a [m/s] and mu [Pa s]
 * from the file if it has them, else from T as in "exp" (eqs. 50, 51 with M0); M = M0.
 * No extrapolation: outside the file's altitudes, LV_ERR_INPUT. No settable parameters:
 * its par_create fails (the data come from a file); use lv_atmo_create_table. */
LV_API extern const lv_atmo_model lv_atmo_table;

/* Loads the parameter block of lv_atmo_table (*par; free it with lv_atmo_table.par_free)
 * from `path`: ".mat" - MAT file, `var` the matrix [h, T, p, rho(, a(, mu))] (Modelica
 * CombiTable1D layout, columns by position); otherwise CSV with `var` NULL and a header
 * "h [m], T [K], p [Pa], rho [kg/m3]" plus optional "a [m/s]", "mu [Pa s]" (any order;
 * units optional, SI only). Errors: LV_ERR_IO (unreadable); LV_ERR_INPUT naming the file:
 * a missing column (with the nearest names), an unknown column or unit, a non-positive
 * T, p, rho, a or mu (path:line for CSV, the row for MAT), non-increasing altitudes
 * (path:line:column, from the table loader); LV_ERR_NOTFOUND: no variable `var`. */
LV_API lv_status lv_atmo_table_load(const char *path, const char *var, void **par,
                                    lv_err *err);

/* A measured or forecast profile (docs/atmosphere.md, "Profiles"): the profile CSV or the
 * University of Wyoming sounding text list, read at its levels as "table" reads its rows (T
 * linearly, p and rho log-linearly; a, mu from T; M = M0) and blended into US76 above its top
 * level z_top: over [z_top, z_top + blend] the differences T - T_US76, ln p - ln p_US76 and
 * ln rho - ln rho_US76 at z_top fall linearly in altitude to 0; US76 alone above (to 1000 km).
 * Below the lowest level z_lo, down to -5 km: T held at the lowest level's, p and rho
 * isothermal-hydrostatic, x(z) = x(z_lo) exp(-g0 (H(z) - H(z_lo)) / (R T)) with the
 * geopotential H of US76 eq. (18). No settable parameters. */
LV_API extern const lv_atmo_model lv_atmo_profile;
#define LV_ATMO_PROFILE_BLEND 10000.0 /* m, the default blend band */

/* Loads the parameter block of lv_atmo_profile from `path` with blend band `blend` [m]
 * (0 < blend; z_top + blend <= 1000 km). Errors: LV_ERR_IO (unreadable); LV_ERR_INPUT with
 * path:line:column for what the file gets wrong (a missing or unknown column or unit, NaN or an
 * empty cell, altitudes not increasing, a level below the surface, a non-positive value), or a
 * file without two of T, p, rho. */
LV_API lv_status lv_atmo_profile_load(const char *path, double blend, void **par, lv_err *err);

/* Registry. Finds a model by name; LV_ERR_NOTFOUND with "did you mean" otherwise. */
LV_API lv_status lv_atmo_model_find(const char *name, const lv_atmo_model **out, lv_err *err);
LV_API size_t lv_atmo_model_count(void);
LV_API const lv_atmo_model *lv_atmo_model_at(size_t i); /* NULL when i >= count */

/* A model with its parameters. Whoever calls _create calls _free. */
typedef struct lv_atmo lv_atmo;
LV_API lv_status lv_atmo_create(const char *name, lv_atmo **out, lv_err *err);
/* The "table" model with the data of `path` (`var`: MAT variable, or NULL for CSV); see
 * lv_atmo_table_load. The handle works like any other (lv_atmo_eval, lv_dof3_config.atmo). */
LV_API lv_status lv_atmo_create_table(const char *path, const char *var, lv_atmo **out,
                                      lv_err *err);
/* The "profile" model with the data of `path` and blend band `blend` [m]; see
 * lv_atmo_profile_load. */
LV_API lv_status lv_atmo_create_profile(const char *path, double blend, lv_atmo **out,
                                        lv_err *err);
LV_API void lv_atmo_free(lv_atmo *atm);
LV_API lv_status lv_atmo_set(lv_atmo *atm, const char *key, double value, lv_err *err);
LV_API const lv_atmo_model *lv_atmo_model_of(const lv_atmo *atm);
LV_API const void *lv_atmo_par(const lv_atmo *atm); /* for direct model->eval calls */
LV_API lv_status lv_atmo_eval(const lv_atmo *atm, double alt_m, lv_atmo_state *out,
                              lv_err *err);

/* An atmosphere dispersed by a one-component perturbation profile delta(h) (lv_perturbation.h;
 * docs/atmosphere.md, "Dispersed profiles"): the density relative, the pressure kept,
 *     f = max(1 + delta(h), LV_ATMO_PERTURBED_FLOOR),  rho' = f rho,  p' = p,
 *     T' = T / f (the gas law p = rho R* T / M with M kept),  a' = a / sqrt(f) (a ~ sqrt(T/M)),
 *     mu' = mu (T'/T)^1.5 (T + S) / (T' + S) (Sutherland's law's ratio, S = 110.4 K), M' = M,
 * over any base model (us76, exp, table, profile, or another perturbed one). Both borrowed:
 * they must outlive *out. Evaluation errors are the base's. The handle's model is
 * "perturbed" (not in the registry: no par_create). LV_ERR_INPUT unless p has 1 component. */
#define LV_ATMO_PERTURBED_FLOOR 0.05
LV_API lv_status lv_atmo_create_perturbed(const lv_atmo *base, const lv_perturbation *p,
                                          lv_atmo **out, lv_err *err);

/* Convenience for the CLI: default parameters of model `name`, evaluated at n altitudes
 * alt_m[0..n-1] into out[0..n-1]. Stops at the first failing altitude. */
LV_API lv_status lv_atmo_eval_by_name(const char *name, const double *alt_m, size_t n,
                                      lv_atmo_state *out, lv_err *err);

#ifdef __cplusplus
}
#endif
#endif
