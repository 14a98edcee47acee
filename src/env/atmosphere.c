/* atmosphere.c - the "us76" model: U.S. Standard Atmosphere 1976, -5 km to 1000 km.
 * Below 86 km the seven layers in geopotential height of the document's Section 1.2
 * (eqs. 18, 23, 33a, 33b, 42, 50, 51; Tables 4 and 8); above 86 km the precomputed
 * species table of atmosphere_upper.c (p = N k T, rho = sum n_i M_i / N_A). */
#include <math.h>
#include <stdlib.h>

#include "core/status.h"
#include "env/atmosphere.h"

#define US76_NLAYER 7

/* Table 4: geopotential heights of the layer bases (m') and molecular-scale temperature
 * gradients (K/m'); T_M and P at the bases follow from T0 = 288.15 K, P0 = 101325 Pa. */
static const double LAYER_H[US76_NLAYER + 1] = { 0.0,     11000.0, 20000.0, 32000.0,
                                                 47000.0, 51000.0, 71000.0, 84852.0 };
static const double LAYER_L[US76_NLAYER] = { -0.0065, 0.0, 0.0010, 0.0028,
                                             0.0,     -0.0028, -0.0020 };

/* Table 8: M/M0 from 80 km to 86 km geometric, every 0.5 km. */
#define MRATIO_Z0 80000.0
#define MRATIO_DZ 500.0
static const double MRATIO[13] = { 1.000000, 0.999996, 0.999989, 0.999971, 0.999941,
                                   0.999909, 0.999870, 0.999829, 0.999786, 0.999741,
                                   0.999694, 0.999641, 0.999579 };

typedef struct us76_par {
    double TM_b[US76_NLAYER];   /* K, molecular-scale temperature at each base */
    double P_b[US76_NLAYER];    /* Pa, pressure at each base */
    double expo[US76_NLAYER];   /* g0 M0 / (R* L_b), or g0 M0 / (R* T_M,b) when L_b = 0 */
    const lv_us76_upper *up;    /* 86 km to 1000 km: the table compiled in */
} us76_par;

static void us76_par_free(void *par)
{
    free(par);
}

static lv_status us76_par_create(void **out, lv_err *err)
{
    *out = NULL;
    us76_par *p = calloc(1, sizeof *p);
    if (p == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "atmosphere model 'us76': out of memory");
    const double gMR = LV_US76_G0 * LV_US76_M0 / LV_US76_RSTAR; /* K/m' */
    double TM = 288.15, P = 101325.0;
    for (int b = 0; b < US76_NLAYER; b++) {
        const double L = LAYER_L[b], dH = LAYER_H[b + 1] - LAYER_H[b];
        p->TM_b[b] = TM;
        p->P_b[b] = P;
        p->expo[b] = L != 0.0 ? gMR / L : gMR / TM;
        const double TM_next = TM + L * dH; /* eq. (23) */
        P = L != 0.0 ? P * pow(TM / TM_next, p->expo[b]) /* eq. (33a) */
                     : P * exp(-p->expo[b] * dH);         /* eq. (33b) */
        TM = TM_next;
    }
    /* The upper atmosphere was integrated at build time (atmosphere_us76_gen.c). */
    p->up = &lv_us76_upper_1976;
    *out = p;
    return LV_OK;
}

static lv_status us76_par_set(void *par, const char *key, double value, lv_err *err)
{
    (void)par;
    (void)value;
    return lv_fail(err, LV_ERR_NOTFOUND,
                   "atmosphere model 'us76' has no parameter '%s' (it has none)", key);
}

static lv_status out_of_range(const char *model, double alt_m, lv_err *err)
{
    if (isnan(alt_m))
        return lv_fail(err, LV_ERR_INPUT,
                       "atmosphere model '%s': altitude is NaN; valid range is %.0f m to "
                       "%.0f m",
                       model, LV_ATMO_ALT_MIN, LV_ATMO_ALT_MAX);
    return lv_fail(err, LV_ERR_INPUT,
                   "atmosphere model '%s': altitude %.9g m is outside the valid range "
                   "%.0f m to %.0f m",
                   model, alt_m, LV_ATMO_ALT_MIN, LV_ATMO_ALT_MAX);
}

/* Sutherland's law, eq. (51); kinetic temperature. */
static double viscosity(double T)
{
    return LV_US76_BETA * T * sqrt(T) / (T + LV_US76_S);
}

static lv_status us76_eval(const void *par, double z, lv_atmo_state *out, lv_err *err)
{
    const us76_par *p = par;
    if (!(z >= LV_ATMO_ALT_MIN && z <= LV_ATMO_ALT_MAX))
        return out_of_range("us76", z, err);

    if (z < LV_US76_Z7) {
        const double H = LV_US76_R0 * z / (LV_US76_R0 + z); /* geopotential, eq. (18) */
        int b = US76_NLAYER - 1;
        while (b > 0 && H < LAYER_H[b])
            b--;
        const double dH = H - LAYER_H[b], L = LAYER_L[b];
        const double TM = p->TM_b[b] + L * dH;                       /* eq. (23) */
        const double P = L != 0.0 ? p->P_b[b] * pow(p->TM_b[b] / TM, p->expo[b])
                                  : p->P_b[b] * exp(-p->expo[b] * dH); /* eq. (33a, b) */
        double ratio = 1.0; /* M/M0, Table 8 */
        if (z > MRATIO_Z0) {
            const double u = (z - MRATIO_Z0) / MRATIO_DZ;
            int i = (int)u;
            if (i > 11)
                i = 11;
            ratio = MRATIO[i] + (MRATIO[i + 1] - MRATIO[i]) * (u - (double)i);
        }
        out->T = TM * ratio;                          /* T = T_M M / M0 */
        out->p = P;
        out->rho = P * LV_US76_M0 / (LV_US76_RSTAR * TM);               /* eq. (42) */
        out->a = sqrt(LV_US76_GAMMA * LV_US76_RSTAR / LV_US76_M0 * TM); /* eq. (50) */
        /* eq. (51) as the document's tables apply it below 86 km: with the molecular-scale
         * temperature (its Table I prints mu = 1.2647e-5 Pa s at 85 km: TM = 188.898 K gives
         * 1.26471e-5, the kinetic T = 188.836 K 1.26436e-5); T and TM differ only above 80 km */
        out->mu = viscosity(TM);
        out->M = LV_US76_M0 * ratio;
        return LV_OK;
    }

    double dT, lnNT, lnrhoT;
    const double T = lv_us76_upper_T(z, &dT);
    lv_us76_upper_lookup(p->up, z, &lnNT, &lnrhoT);
    const double NT = exp(lnNT), rhoT = exp(lnrhoT);
    const double M = rhoT * LV_US76_NA / NT; /* mean molecular weight */
    out->T = T;
    out->p = NT * LV_US76_K;                 /* p = N k T */
    out->rho = rhoT / T;                     /* sum n_i M_i / N_A */
    /* Beyond the document (it tabulates a and mu only to 86 km): eq. (50) with the
     * molecular-scale temperature T M0 / M, and eq. (51) with the kinetic T. */
    out->a = sqrt(LV_US76_GAMMA * LV_US76_RSTAR * T / M);
    out->mu = viscosity(T);
    out->M = M;
    return LV_OK;
}

const lv_atmo_model lv_atmo_us76 = {
    "us76",
    "U.S. Standard Atmosphere 1976, -5 km to 1000 km",
    us76_par_create,
    us76_par_free,
    us76_par_set,
    us76_eval,
};
