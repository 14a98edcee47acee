/* gravity_impl.h - the gravity model object, shared by gravity.c (registry,
 * closed-form models) and gravity_sh.c (spherical harmonics). Not exported. */
#ifndef LV_ENV_GRAVITY_IMPL_H
#define LV_ENV_GRAVITY_IMPL_H

#include "lvsim/lv_planet.h"

/* Triangular index of (n, m), 0 <= m <= n, and the count up to degree n. */
static inline size_t lv_gravity_tri(int n, int m)
{
    return (size_t)n * (size_t)(n + 1) / 2 + (size_t)m;
}
static inline size_t lv_gravity_tri_count(int n) { return (size_t)(n + 1) * (size_t)(n + 2) / 2; }

struct lv_gravity {
    lv_gravity_kind kind;
    const char *name; /* registry name, static */
    double gm;        /* m^3/s^2 */
    double r_ref;     /* m */
    double jn[LV_GRAVITY_ZONAL_MAX + 1]; /* closed-form models: J_0..J_nz (J_0 = J_1 = 0) */
    int nz;           /* closed-form models: highest zonal degree (0 .. LV_GRAVITY_ZONAL_MAX) */
    /* "sh" only: one allocation, `block`, holds every array below */
    int degree, order;
    double *block;
    double *cnm, *snm;    /* [tri_count(degree)] fully normalised C, S */
    double *alpha, *beta; /* [tri_count(degree + 1)] column recursion factors */
    double *diag;         /* [degree + 2] sectoral recursion factors */
    double *f1, *f2, *f3; /* [tri_count(degree)] acceleration factors */
    double *k6;           /* [6 tri_count(degree)] per (n, m): C f1, S f1, C f2, S f2, C f3,
                           * S f3, with the 1/2 of eq. G7 folded in for m > 0 */
};

/* Allocates and fills the recursion tables for degree/order (C, S zeroed,
 * C(0,0) = 1). */
lv_status lv_gravity_sh_alloc(lv_gravity *g, int degree, int order, lv_err *err);
/* Recomputes k6 from cnm, snm: call after changing the coefficients. */
void lv_gravity_sh_finish(lv_gravity *g);
/* Reads an ICGEM .gfc file into g: gm, r_ref and the coefficients up to
 * `degree`/`order` (degree 0: the file's max_degree; order -1: degree). */
lv_status lv_gravity_sh_read_gfc(lv_gravity *g, const char *path, int degree, int order,
                                 lv_err *err);
void lv_gravity_sh_eval(const lv_gravity *g, double *ws, const double r[3], double a[3],
                        double *U);

#endif
