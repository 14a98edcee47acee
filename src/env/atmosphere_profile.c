/* atmosphere_profile.c - the "profile" model: a measured or forecast profile (a sounding, a
 * forecast's levels; env/profile.c reads it) up to its top level, blended into US76 above:
 * over the band [z_top, z_top + blend] the differences in T, ln p and ln rho at the top decay
 * linearly in altitude to zero, US76 alone above. Below the lowest level (a sounding starts at
 * its station, a booster may land lower) the lowest level's temperature is held and p, rho
 * follow the isothermal hydrostatic law down to -5 km. Between levels as the "table" model: T
 * linearly, p and rho log-linearly; a and mu from T with US76 eqs. (50), (51).
 * docs/atmosphere.md, "Profiles". */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "env/atmosphere.h"
#include "env/profile.h"
#include "lvsim/lv_table.h"

typedef struct profile_par {
    lv_table *tab;              /* over z [m]: T, ln p, ln rho at the file's levels */
    double z_lo, z_top, blend;  /* m: lowest and top level, blend band */
    double T_lo, p_lo, rho_lo;  /* K, Pa, kg/m^3 at z_lo */
    double dT, dlnp, dlnrho;    /* profile - US76 at z_top: K, and of the logarithms */
    void *us76;                 /* the US76 parameters (owned) */
    char src[256];
} profile_par;

static void profile_par_free(void *par)
{
    profile_par *p = par;
    if (p == NULL)
        return;
    lv_table_free(p->tab);
    lv_atmo_us76.par_free(p->us76);
    free(p);
}

static lv_status profile_par_create(void **out, lv_err *err)
{
    *out = NULL;
    return lv_fail(err, LV_ERR_INPUT,
                   "atmosphere model 'profile' reads its data from a file: create it with "
                   "lv_atmo_create_profile(path, blend, ...)");
}

static lv_status profile_par_set(void *par, const char *key, double value, lv_err *err)
{
    (void)value;
    const profile_par *p = par;
    return lv_fail(err, LV_ERR_NOTFOUND,
                   "atmosphere model 'profile' (%s) has no parameter '%s' (its data come from "
                   "the file, the blend band from lv_atmo_create_profile)", p->src, key);
}

static void from_T(double T, lv_atmo_state *out)
{
    out->a = sqrt(LV_US76_GAMMA * LV_US76_RSTAR * T / LV_US76_M0); /* eq. (50) */
    out->mu = LV_US76_BETA * T * sqrt(T) / (T + LV_US76_S);       /* eq. (51) */
    out->M = LV_US76_M0;
}

static lv_status profile_eval(const void *par, double h, lv_atmo_state *out, lv_err *err)
{
    const profile_par *p = par;
    if (!(h >= LV_ATMO_ALT_MIN && h <= LV_ATMO_ALT_MAX)) {
        if (isnan(h))
            return lv_fail(err, LV_ERR_INPUT, "atmosphere model 'profile' (%s): altitude is NaN",
                           p->src);
        return lv_fail(err, LV_ERR_INPUT,
                       "atmosphere model 'profile' (%s): altitude %.9g m is outside the valid "
                       "range %.9g m to %.9g m",
                       p->src, h, LV_ATMO_ALT_MIN, LV_ATMO_ALT_MAX);
    }
    if (h < p->z_lo) { /* isothermal below: dp/dH = -g0 p / (R T), H geopotential (eq. 18) */
        const double r0 = LV_US76_R0;
        const double dH = r0 * h / (r0 + h) - r0 * p->z_lo / (r0 + p->z_lo); /* < 0 */
        const double f = exp(-LV_US76_G0 * LV_US76_M0 * dH / (LV_US76_RSTAR * p->T_lo));
        out->T = p->T_lo;
        out->p = p->p_lo * f;
        out->rho = p->rho_lo * f;
        from_T(out->T, out);
        return LV_OK;
    }
    if (h <= p->z_top) {
        double y[3];
        const lv_status st = lv_table_eval1(p->tab, NULL, h, y, err);
        if (st != LV_OK)
            return st;
        out->T = y[0];
        out->p = exp(y[1]);
        out->rho = exp(y[2]);
        from_T(out->T, out);
        return LV_OK;
    }
    const lv_status st = lv_atmo_us76.eval(p->us76, h, out, err);
    if (st != LV_OK || h >= p->z_top + p->blend)
        return st;
    const double f = 1.0 - (h - p->z_top) / p->blend; /* 1 at the top, 0 at the band's end */
    out->T += f * p->dT;
    out->p *= exp(f * p->dlnp);
    out->rho *= exp(f * p->dlnrho);
    from_T(out->T, out);
    return LV_OK;
}

const lv_atmo_model lv_atmo_profile = {
    "profile",
    "a measured or forecast profile (CSV or sounding text list), blended into US76 above it",
    profile_par_create,
    profile_par_free,
    profile_par_set,
    profile_eval,
};

lv_status lv_atmo_profile_load(const char *path, double blend, void **par, lv_err *err)
{
    lv_profile pr;
    profile_par *p = NULL;
    double *y = NULL;
    lv_status st;
    if (par == NULL || path == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_atmo_profile_load: NULL argument");
    *par = NULL;
    if (!(blend > 0.0 && blend <= LV_ATMO_ALT_MAX))
        return lv_fail(err, LV_ERR_INPUT, "%s: blend band %.9g m must be in (0, %.9g] m", path,
                       blend, LV_ATMO_ALT_MAX);
    if ((st = lv_profile_load(path, &pr, err)) != LV_OK)
        return st;
    const size_t n = pr.n_t;
    if (n == 0) {
        st = lv_fail(err, LV_ERR_INPUT, "%s: the profile has no temperature, pressure or density "
                     "(an atmosphere needs two of T, p, rho at two levels at least)", path);
        goto fail;
    }
    if (pr.z_t[n - 1] + blend > LV_ATMO_ALT_MAX) {
        st = lv_fail(err, LV_ERR_INPUT, "%s: the profile's top %.9g m plus the blend band %.9g m "
                     "is above %.9g m, where US76 ends", path, pr.z_t[n - 1], blend,
                     LV_ATMO_ALT_MAX);
        goto fail;
    }
    st = LV_ERR_NOMEM;
    p = calloc(1, sizeof *p);
    y = malloc(3 * n * sizeof *y);
    if (p == NULL || y == NULL) {
        lv_fail(err, st, "%s: out of memory", path);
        goto fail;
    }
    for (size_t i = 0; i < n; i++) {
        y[3 * i] = pr.T[i];
        y[3 * i + 1] = log(pr.p[i]);
        y[3 * i + 2] = log(pr.rho[i]);
    }
    static const char *const names[3] = { "T", "ln_p", "ln_rho" };
    static const char *const units[3] = { "K", "ln Pa", "ln kg/m3" };
    lv_table_spec spec = { 0 };
    spec.n_dims = 1;
    spec.n[0] = n;
    spec.x[0] = pr.z_t;
    spec.n_out = 3;
    spec.y = y;
    spec.interp = LV_INTERP_LINEAR;
    spec.extrap = LV_EXTRAP_ERROR;
    spec.name = "profile";
    spec.axis_name[0] = "h";
    spec.axis_unit[0] = "m";
    spec.out_name = names;
    spec.out_unit = units;
    if ((st = lv_table_create(&spec, &p->tab, err)) != LV_OK ||
        (st = lv_atmo_us76.par_create(&p->us76, err)) != LV_OK) {
        lv_fail_prefix(err, st, "%s", path);
        goto fail;
    }
    lv_atmo_state s76;
    if ((st = lv_atmo_us76.eval(p->us76, pr.z_t[n - 1], &s76, err)) != LV_OK) {
        lv_fail_prefix(err, st, "%s", path);
        goto fail;
    }
    p->z_lo = pr.z_t[0];
    p->T_lo = pr.T[0];
    p->p_lo = pr.p[0];
    p->rho_lo = pr.rho[0];
    p->z_top = pr.z_t[n - 1];
    p->blend = blend;
    p->dT = pr.T[n - 1] - s76.T;
    p->dlnp = log(pr.p[n - 1]) - log(s76.p);
    p->dlnrho = log(pr.rho[n - 1]) - log(s76.rho);
    snprintf(p->src, sizeof p->src, "%s", path);
    *par = p;
    p = NULL;
    st = LV_OK;
fail:
    profile_par_free(p);
    free(y);
    lv_profile_clear(&pr);
    return st;
}
