/* atmosphere_exp.c - the "exp" model: exponential density with a constant temperature.
 * rho = rho0 exp(-h / H); p = rho R* T / M0 (ideal gas, sea-level air); a and mu from T
 * with the U.S. Standard Atmosphere 1976 formulas (its eqs. 50 and 51). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/names.h"
#include "core/status.h"
#include "env/atmosphere.h"

static const char *const EXP_KEYS[] = { "rho0", "H", "T" };
#define EXP_NKEYS (sizeof EXP_KEYS / sizeof EXP_KEYS[0])

static lv_status exp_par_create(void **out, lv_err *err)
{
    lv_atmo_exp_par *p = malloc(sizeof *p);
    *out = NULL;
    if (p == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "atmosphere model 'exp': out of memory");
    p->rho0 = 1.225; /* kg/m^3, US76 sea level */
    p->H = 7200.0;   /* m, a common fit of the US76 density to 100 km */
    p->T = 288.15;   /* K */
    *out = p;
    return LV_OK;
}

static void exp_par_free(void *par)
{
    free(par);
}

static lv_status exp_par_set(void *par, const char *key, double value, lv_err *err)
{
    lv_atmo_exp_par *p = par;
    double *field = NULL;
    if (strcmp(key, "rho0") == 0)
        field = &p->rho0;
    else if (strcmp(key, "H") == 0)
        field = &p->H;
    else if (strcmp(key, "T") == 0)
        field = &p->T;
    if (field == NULL) {
        lv_suggest sg;
        char hint[128];
        lv_suggest_init(&sg, key);
        for (size_t i = 0; i < EXP_NKEYS; i++)
            lv_suggest_add(&sg, EXP_KEYS[i]);
        lv_suggest_text(&sg, hint, sizeof hint);
        return lv_fail(err, LV_ERR_NOTFOUND,
                       "atmosphere model 'exp': unknown parameter '%s'%s (keys: rho0, H, T)",
                       key, hint);
    }
    if (!(value > 0.0) || isinf(value))
        return lv_fail(err, LV_ERR_INPUT,
                       "atmosphere model 'exp': parameter '%s' = %g must be positive and "
                       "finite",
                       key, value);
    *field = value;
    return LV_OK;
}

static lv_status exp_eval(const void *par, double h, lv_atmo_state *out, lv_err *err)
{
    const lv_atmo_exp_par *p = par;
    if (!(h >= LV_ATMO_ALT_MIN && h <= LV_ATMO_ALT_MAX)) {
        if (isnan(h))
            return lv_fail(err, LV_ERR_INPUT,
                           "atmosphere model 'exp': altitude is NaN; valid range is %.0f m "
                           "to %.0f m",
                           LV_ATMO_ALT_MIN, LV_ATMO_ALT_MAX);
        return lv_fail(err, LV_ERR_INPUT,
                       "atmosphere model 'exp': altitude %.9g m is outside the valid range "
                       "%.0f m to %.0f m",
                       h, LV_ATMO_ALT_MIN, LV_ATMO_ALT_MAX);
    }
    const double T = p->T;
    out->T = T;
    out->rho = p->rho0 * exp(-h / p->H);
    out->p = out->rho * LV_US76_RSTAR * T / LV_US76_M0;
    out->a = sqrt(LV_US76_GAMMA * LV_US76_RSTAR * T / LV_US76_M0);
    out->mu = LV_US76_BETA * T * sqrt(T) / (T + LV_US76_S);
    out->M = LV_US76_M0;
    return LV_OK;
}

const lv_atmo_model lv_atmo_exp = {
    "exp",
    "exponential density rho0 exp(-h/H), constant temperature T",
    exp_par_create,
    exp_par_free,
    exp_par_set,
    exp_eval,
};
