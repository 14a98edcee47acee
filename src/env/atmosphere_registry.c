/* atmosphere_registry.c - atmosphere models by name, and the lv_atmo handle that pairs a
 * model with its parameter block. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/names.h"
#include "core/status.h"
#include "env/atmosphere.h"

static const lv_atmo_model *const MODELS[] = { &lv_atmo_us76, &lv_atmo_exp, &lv_atmo_table,
                                                &lv_atmo_profile };
#define NMODELS (sizeof MODELS / sizeof MODELS[0])

struct lv_atmo {
    const lv_atmo_model *model;
    void *par; /* owned; created and freed by the model */
};

size_t lv_atmo_model_count(void)
{
    return NMODELS;
}

const lv_atmo_model *lv_atmo_model_at(size_t i)
{
    return i < NMODELS ? MODELS[i] : NULL;
}

lv_status lv_atmo_model_find(const char *name, const lv_atmo_model **out, lv_err *err)
{
    *out = NULL;
    if (name == NULL)
        return lv_fail(err, LV_ERR_INPUT, "atmosphere model name is NULL");
    for (size_t i = 0; i < NMODELS; i++)
        if (strcmp(MODELS[i]->name, name) == 0) {
            *out = MODELS[i];
            return LV_OK;
        }
    lv_suggest sg;
    char hint[160];
    lv_suggest_init(&sg, name);
    for (size_t i = 0; i < NMODELS; i++)
        lv_suggest_add(&sg, MODELS[i]->name);
    lv_suggest_text(&sg, hint, sizeof hint);
    return lv_fail(err, LV_ERR_NOTFOUND,
                   "unknown atmosphere model '%s'%s (models: us76, exp, table, profile)", name, hint);
}

lv_status lv_atmo_create(const char *name, lv_atmo **out, lv_err *err)
{
    *out = NULL;
    const lv_atmo_model *m = NULL;
    lv_status st = lv_atmo_model_find(name, &m, err);
    if (st != LV_OK)
        return st;
    lv_atmo *atm = calloc(1, sizeof *atm);
    if (atm == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "atmosphere model '%s': out of memory", name);
    atm->model = m;
    st = m->par_create(&atm->par, err);
    if (st != LV_OK) {
        free(atm);
        return st;
    }
    *out = atm;
    return LV_OK;
}

lv_status lv_atmo_create_table(const char *path, const char *var, lv_atmo **out, lv_err *err)
{
    if (out == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_atmo_create_table: NULL argument");
    *out = NULL;
    lv_atmo *atm = calloc(1, sizeof *atm);
    if (atm == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "atmosphere model 'table': out of memory");
    atm->model = &lv_atmo_table;
    const lv_status st = lv_atmo_table_load(path, var, &atm->par, err);
    if (st != LV_OK) {
        free(atm);
        return st;
    }
    *out = atm;
    return LV_OK;
}

lv_status lv_atmo_create_profile(const char *path, double blend, lv_atmo **out, lv_err *err)
{
    if (out == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_atmo_create_profile: NULL argument");
    *out = NULL;
    lv_atmo *atm = calloc(1, sizeof *atm);
    if (atm == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "atmosphere model 'profile': out of memory");
    atm->model = &lv_atmo_profile;
    const lv_status st = lv_atmo_profile_load(path, blend, &atm->par, err);
    if (st != LV_OK) {
        free(atm);
        return st;
    }
    *out = atm;
    return LV_OK;
}

void lv_atmo_free(lv_atmo *atm)
{
    if (atm == NULL)
        return;
    atm->model->par_free(atm->par);
    free(atm);
}

lv_status lv_atmo_set(lv_atmo *atm, const char *key, double value, lv_err *err)
{
    return atm->model->par_set(atm->par, key, value, err);
}

const lv_atmo_model *lv_atmo_model_of(const lv_atmo *atm)
{
    return atm->model;
}

const void *lv_atmo_par(const lv_atmo *atm)
{
    return atm->par;
}

lv_status lv_atmo_eval(const lv_atmo *atm, double alt_m, lv_atmo_state *out, lv_err *err)
{
    return atm->model->eval(atm->par, alt_m, out, err);
}

lv_status lv_atmo_eval_by_name(const char *name, const double *alt_m, size_t n,
                               lv_atmo_state *out, lv_err *err)
{
    lv_atmo *atm = NULL;
    lv_status st = lv_atmo_create(name, &atm, err);
    if (st != LV_OK)
        return st;
    for (size_t i = 0; i < n && st == LV_OK; i++)
        st = lv_atmo_eval(atm, alt_m[i], &out[i], err);
    lv_atmo_free(atm);
    return st;
}

/* ---- a perturbed atmosphere (lv_atmo_create_perturbed) ----------------------------------- */

typedef struct perturbed_par {
    const lv_atmo_model *base_model; /* borrowed, with its parameters */
    const void *base_par;
    const lv_perturbation *p;        /* borrowed */
} perturbed_par;

static lv_status perturbed_par_create(void **par, lv_err *err)
{
    *par = NULL;
    return lv_fail(err, LV_ERR_INPUT, "atmosphere model 'perturbed': made by "
                   "lv_atmo_create_perturbed from a base atmosphere");
}

static void perturbed_par_free(void *par)
{
    free(par);
}

static lv_status perturbed_par_set(void *par, const char *key, double value, lv_err *err)
{
    (void)par;
    (void)value;
    return lv_fail(err, LV_ERR_NOTFOUND, "atmosphere model 'perturbed' has no parameter '%s' "
                   "(set its base's)", key);
}

/* rho' = f rho, p kept, T' = T / f, a' = a / sqrt(f), mu by Sutherland's ratio (lv_atmosphere.h) */
static lv_status perturbed_eval(const void *par, double z, lv_atmo_state *out, lv_err *err)
{
    const perturbed_par *pp = par;
    const lv_status st = pp->base_model->eval(pp->base_par, z, out, err);
    if (st != LV_OK)
        return st;
    double d;
    lv_perturbation_eval(pp->p, z, &d);
    const double f = 1.0 + d > LV_ATMO_PERTURBED_FLOOR ? 1.0 + d : LV_ATMO_PERTURBED_FLOOR;
    const double T = out->T, T1 = T / f;
    out->rho *= f;
    out->T = T1;
    out->a /= sqrt(f);
    out->mu *= (T1 / T) * sqrt(T1 / T) * (T + LV_US76_S) / (T1 + LV_US76_S);
    return LV_OK;
}

static const lv_atmo_model lv_atmo_perturbed = {
    "perturbed",
    "a base atmosphere with a density perturbation profile (lv_atmo_create_perturbed)",
    perturbed_par_create,
    perturbed_par_free,
    perturbed_par_set,
    perturbed_eval,
};

lv_status lv_atmo_create_perturbed(const lv_atmo *base, const lv_perturbation *p, lv_atmo **out,
                                   lv_err *err)
{
    if (base == NULL || p == NULL || out == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_atmo_create_perturbed: NULL argument");
    *out = NULL;
    if (lv_perturbation_comp(p) != 1)
        return lv_fail(err, LV_ERR_INPUT, "lv_atmo_create_perturbed: the perturbation has %zu "
                       "components; a density's has 1", lv_perturbation_comp(p));
    lv_atmo *atm = calloc(1, sizeof *atm);
    perturbed_par *pp = calloc(1, sizeof *pp);
    if (atm == NULL || pp == NULL) {
        free(atm);
        free(pp);
        return lv_fail(err, LV_ERR_NOMEM, "atmosphere model 'perturbed': out of memory");
    }
    pp->base_model = base->model;
    pp->base_par = base->par;
    pp->p = p;
    atm->model = &lv_atmo_perturbed;
    atm->par = pp;
    *out = atm;
    return LV_OK;
}
