/* gravity.c - gravity model registry ("pointmass", "j2", "zonal", "sh"), the
 * closed-form zonal models (docs/gravity.md eqs. G1-G2: the zonal series of the
 * potential differentiated with Bonnet's Legendre recursions), and local (NED) gravity. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/data.h"
#include "core/names.h"
#include "core/status.h"
#include "env/gravity_impl.h"

typedef struct gravity_entry {
    const char *name;
    lv_gravity_kind kind;
    int nz; /* highest zonal degree of the closed-form models */
} gravity_entry;

static const gravity_entry registry[] = {
    {"pointmass", LV_GRAVITY_POINTMASS, 0},
    {"j2", LV_GRAVITY_J2, 2},
    {"zonal", LV_GRAVITY_ZONAL, 4},
    {"sh", LV_GRAVITY_SH, 0},
};
#define N_REGISTRY (sizeof registry / sizeof registry[0])

lv_status lv_gravity_default_file(char *path, size_t size, lv_err *err)
{
    return lv_data_find(NULL, LV_GRAVITY_DEFAULT_FILE, path, size, err);
}

static const gravity_entry *find_model(const char *name, size_t len)
{
    for (size_t k = 0; k < N_REGISTRY; k++)
        if (strlen(registry[k].name) == len && strncmp(registry[k].name, name, len) == 0)
            return &registry[k];
    return NULL;
}

static lv_status unknown_model(const char *name, lv_err *err)
{
    lv_suggest s;
    char hint[160];
    lv_suggest_init(&s, name);
    for (size_t k = 0; k < N_REGISTRY; k++)
        lv_suggest_add(&s, registry[k].name);
    lv_suggest_text(&s, hint, sizeof hint);
    return lv_fail(err, LV_ERR_NOTFOUND,
                   "unknown gravity model '%s'%s (known: pointmass, j2, zonal, sh[:N[xM]])",
                   name, hint);
}

lv_status lv_gravity_parse_spec(const char *spec, lv_gravity_config *cfg, lv_err *err)
{
    if (spec == NULL)
        return lv_fail(err, LV_ERR_INPUT, "gravity model: no name given");
    const char *colon = strchr(spec, ':');
    const size_t len = colon != NULL ? (size_t)(colon - spec) : strlen(spec);
    const gravity_entry *e = find_model(spec, len);
    if (e == NULL) {
        char name[64];
        snprintf(name, sizeof name, "%.*s", (int)(len < 63 ? len : 63), spec);
        return unknown_model(name, err);
    }
    cfg->model = e->name;
    cfg->degree = 0;
    cfg->order = 0;
    cfg->coef_path = NULL;
    if (colon == NULL)
        return LV_OK;
    if (e->kind != LV_GRAVITY_SH)
        return lv_fail(err, LV_ERR_INPUT, "gravity model '%s': '%s' takes no degree/order",
                       spec, e->name);
    char *end = NULL;
    long n = strtol(colon + 1, &end, 10), m = 0;
    if (end == colon + 1 || n < 1 || n > 10000)
        return lv_fail(err, LV_ERR_INPUT, "gravity model '%s': degree must be 1..10000", spec);
    if (*end == 'x') {
        const char *ms = end + 1;
        m = strtol(ms, &end, 10);
        if (end == ms || m < 0 || m > n)
            return lv_fail(err, LV_ERR_INPUT, "gravity model '%s': order must be 0..%ld", spec,
                           n);
        if (m == 0)
            m = LV_GRAVITY_ORDER_ZONAL;
    }
    if (*end != '\0')
        return lv_fail(err, LV_ERR_INPUT, "gravity model '%s': expected sh:N or sh:NxM", spec);
    cfg->degree = (int)n;
    cfg->order = (int)m;
    return LV_OK;
}

lv_status lv_gravity_create(const lv_planet *planet, const lv_gravity_config *cfg,
                            lv_gravity **out, lv_err *err)
{
    lv_status st = LV_OK;
    lv_gravity *g = NULL;
    *out = NULL;
    if (cfg == NULL || cfg->model == NULL)
        return lv_fail(err, LV_ERR_INPUT, "gravity model: no name given");
    const gravity_entry *e = find_model(cfg->model, strlen(cfg->model));
    if (e == NULL)
        return unknown_model(cfg->model, err);
    st = lv_planet_check(planet, err);
    if (st != LV_OK)
        return st;
    g = calloc(1, sizeof *g);
    if (g == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "gravity '%s': out of memory", e->name);
    g->kind = e->kind;
    g->name = e->name;
    g->gm = planet->gm;
    g->r_ref = planet->r_ref;
    g->nz = e->nz;
    if (e->nz >= 2)
        g->jn[2] = planet->j2;
    if (e->nz >= 4) {
        g->jn[3] = planet->j3;
        g->jn[4] = planet->j4;
    }
    g->degree = e->nz;
    g->order = 0;
    if (e->kind == LV_GRAVITY_SH) {
        if (cfg->degree < 0) {
            st = lv_fail(err, LV_ERR_INPUT, "gravity 'sh': degree %d must be >= 0 (0: the file's)",
                         cfg->degree);
            goto fail;
        }
        if (cfg->order < LV_GRAVITY_ORDER_ZONAL) {
            st = lv_fail(err, LV_ERR_INPUT, "gravity 'sh': order %d must be >= 0", cfg->order);
            goto fail;
        }
        /* the reader takes -1 for "order = degree" */
        const int order = cfg->order == 0                        ? -1
                          : cfg->order == LV_GRAVITY_ORDER_ZONAL ? 0
                                                                 : cfg->order;
        char shipped[LV_DATA_PATH_MAX];
        const char *path = cfg->coef_path;
        if (path == NULL) {
            st = lv_gravity_default_file(shipped, sizeof shipped, err);
            if (st != LV_OK) {
                lv_fail_prefix(err, st, "gravity 'sh'");
                goto fail;
            }
            path = shipped;
        }
        st = lv_gravity_sh_read_gfc(g, path, cfg->degree, order, err);
        if (st != LV_OK)
            goto fail;
    }
    *out = g;
    return LV_OK;

fail:
    lv_gravity_free(g);
    return st;
}

lv_status lv_gravity_create_zonal(const lv_planet *planet, const char *model,
                                  const double *zonal, int n_zonal, lv_gravity **out,
                                  lv_err *err)
{
    *out = NULL;
    const gravity_entry *e = model != NULL ? find_model(model, strlen(model)) : NULL;
    if (e == NULL || e->kind == LV_GRAVITY_SH)
        return lv_fail(err, LV_ERR_INPUT, "gravity '%s': zonal coefficients go with "
                       "'pointmass', 'j2' or 'zonal'", model != NULL ? model : "(null)");
    if (zonal == NULL || n_zonal < 1 || n_zonal > LV_GRAVITY_ZONAL_MAX - 1)
        return lv_fail(err, LV_ERR_INPUT, "gravity '%s': %d zonal coefficients (J2 .. J%d: "
                       "1 to %d of them)", e->name, n_zonal, LV_GRAVITY_ZONAL_MAX,
                       LV_GRAVITY_ZONAL_MAX - 1);
    for (int k = 0; k < n_zonal; k++)
        if (!(fabs(zonal[k]) < 1.0))
            return lv_fail(err, LV_ERR_INPUT, "gravity '%s': J%d = %g must be finite and "
                           "|J| < 1", e->name, k + 2, zonal[k]);
    const lv_gravity_config cfg = {e->name, 0, 0, NULL};
    lv_status st = lv_gravity_create(planet, &cfg, out, err);
    if (st != LV_OK)
        return st;
    lv_gravity *g = *out; /* the caller's J2 (j2), or J2 .. Jn (zonal), replace the planet's */
    memset(g->jn, 0, sizeof g->jn);
    g->nz = e->kind == LV_GRAVITY_POINTMASS ? 0 : e->kind == LV_GRAVITY_J2 ? 2 : n_zonal + 1;
    for (int n = 2; n <= g->nz; n++)
        g->jn[n] = zonal[n - 2];
    g->degree = g->nz;
    return LV_OK;
}

lv_status lv_gravity_create_sh(double gm, double r_ref, int degree, int order, const double *cnm,
                               const double *snm, lv_gravity **out, lv_err *err)
{
    lv_status st = LV_OK;
    *out = NULL;
    if (!(isfinite(gm) && gm > 0.0 && isfinite(r_ref) && r_ref > 0.0))
        return lv_fail(err, LV_ERR_INPUT, "gravity 'sh': gm = %g and r_ref = %g must be > 0", gm,
                       r_ref);
    if (cnm == NULL)
        return lv_fail(err, LV_ERR_INPUT, "gravity 'sh': no coefficients given");
    lv_gravity *g = calloc(1, sizeof *g);
    if (g == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "gravity 'sh': out of memory");
    g->kind = LV_GRAVITY_SH;
    g->name = "sh";
    g->gm = gm;
    g->r_ref = r_ref;
    st = lv_gravity_sh_alloc(g, degree, order, err);
    if (st != LV_OK)
        goto fail;
    for (int n = 0; n <= degree; n++) {
        for (int m = 0; m <= n; m++) {
            const size_t k = lv_gravity_tri(n, m);
            const double s = snm != NULL ? snm[k] : 0.0;
            if (!isfinite(cnm[k]) || !isfinite(s)) {
                st = lv_fail(err, LV_ERR_INPUT, "gravity 'sh': coefficient (%d, %d) not finite",
                             n, m);
                goto fail;
            }
            g->cnm[k] = cnm[k];
            g->snm[k] = s;
        }
    }
    lv_gravity_sh_finish(g);
    *out = g;
    return LV_OK;

fail:
    lv_gravity_free(g);
    return st;
}

void lv_gravity_free(lv_gravity *g)
{
    if (g == NULL)
        return;
    free(g->block);
    free(g);
}

void lv_gravity_info_get(const lv_gravity *g, lv_gravity_info *info)
{
    memset(info, 0, sizeof *info);
    info->name = g->name;
    info->kind = g->kind;
    info->degree = g->degree;
    info->order = g->order;
    info->gm = g->gm;
    info->r_ref = g->r_ref;
    if (g->kind == LV_GRAVITY_SH) {
        for (int n = 2; n <= 4 && n <= g->degree; n++)
            info->jn[n] = -sqrt(2.0 * n + 1.0) * g->cnm[lv_gravity_tri(n, 0)];
    } else {
        for (int n = 2; n <= 4 && n <= g->nz; n++)
            info->jn[n] = g->jn[n];
    }
}

size_t lv_gravity_ws_size(const lv_gravity *g)
{
    return g->kind == LV_GRAVITY_SH ? 2 * lv_gravity_tri_count(g->degree + 1) : 0;
}

/* Point mass plus zonals J_2..J_nz (docs/gravity.md eq. G2):
 *   a_x = mu/r^3 [-x + x sum J_n q^n P'_{n+1}(u)]           (same for y)
 *   a_z = mu/r^3 [-z + r sum J_n q^n (n + 1) P_{n+1}(u)]
 *   U   = mu/r  [1 - sum J_n q^n P_n(u)],  u = z/r, q = R/r.
 * Free of 1/cos(latitude), so exact at the poles. */
/* The same for J2 alone, the sums written out (P_2 = (3u^2 - 1)/2, P_3 = (5u^3 - 3u)/2,
 * P'_3 = (15u^2 - 3)/2): one square root and one division instead of the recursion's four
 * divisions. The most common field (every `gravity: j2` mission's right-hand side, and the
 * instantaneous impact point's propagation, lv_iip_propagate, at each output row). */
static void j2_eval(const lv_gravity *g, const double r[3], double a[3], double *U)
{
    const double r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    const double rn = sqrt(r2), ir = 1.0 / rn, ir2 = ir * ir;
    const double u = r[2] * ir, u2 = u * u;
    const double mu_r3 = g->gm * ir2 * ir;
    const double jq = g->jn[2] * (g->r_ref * g->r_ref) * ir2; /* J2 q^2 */
    const double sxy = jq * (7.5 * u2 - 1.5);     /* J2 q^2 P'_3(u) */
    const double sz = jq * u * (7.5 * u2 - 4.5);  /* J2 q^2 3 P_3(u) */
    a[0] = mu_r3 * (r[0] * sxy - r[0]);
    a[1] = mu_r3 * (r[1] * sxy - r[1]);
    a[2] = mu_r3 * (rn * sz - r[2]);
    if (U != NULL)
        *U = g->gm * ir * (1.0 - jq * (1.5 * u2 - 0.5)); /* 1 - J2 q^2 P_2(u) */
}

static void zonal_eval(const lv_gravity *g, const double r[3], double a[3], double *U)
{
    if (g->nz == 2) {
        j2_eval(g, r, a, U);
        return;
    }
    const double r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    const double rn = sqrt(r2), u = r[2] / rn, q = g->r_ref / rn;
    const double mu_r3 = g->gm / (r2 * rn);
    double p[LV_GRAVITY_ZONAL_MAX + 2], dp[LV_GRAVITY_ZONAL_MAX + 2]; /* P_n, P'_n, n <= nz + 1 */
    p[0] = 1.0;
    p[1] = u;
    dp[0] = 0.0;
    dp[1] = 1.0;
    for (int n = 1; n <= g->nz; n++) {
        /* Bonnet: (n+1) P_{n+1} = (2n+1) u P_n - n P_{n-1}; P'_{n+1} = P'_{n-1} + (2n+1) P_n */
        p[n + 1] = ((2.0 * n + 1.0) * u * p[n] - n * p[n - 1]) / (n + 1.0);
        dp[n + 1] = dp[n - 1] + (2.0 * n + 1.0) * p[n];
    }
    double sxy = 0.0, sz = 0.0, su = 0.0, qn = q;
    for (int n = 2; n <= g->nz; n++) {
        qn *= q;
        const double jq = g->jn[n] * qn;
        sxy += jq * dp[n + 1];
        sz += jq * (n + 1.0) * p[n + 1];
        su += jq * p[n];
    }
    a[0] = mu_r3 * (r[0] * sxy - r[0]);
    a[1] = mu_r3 * (r[1] * sxy - r[1]);
    a[2] = mu_r3 * (rn * sz - r[2]);
    if (U != NULL)
        *U = g->gm / rn * (1.0 - su);
}

void lv_gravity_eval(const lv_gravity *g, double *ws, const double r_ecef[3], double a_ecef[3],
                     double *U)
{
    if (g->kind == LV_GRAVITY_SH)
        lv_gravity_sh_eval(g, ws, r_ecef, a_ecef, U);
    else
        zonal_eval(g, r_ecef, a_ecef, U);
}

lv_status lv_gravity_at_geodetic(const lv_gravity *g, const lv_planet *planet, double lat,
                                 double lon, double h, lv_gravity_local *out, lv_err *err)
{
    double C[3][3], a[3], r[3];
    const size_t nws = lv_gravity_ws_size(g);
    double *ws = NULL;
    if (!isfinite(lat) || !isfinite(lon) || !isfinite(h) || fabs(lat) > asin(1.0))
        return lv_fail(err, LV_ERR_INPUT, "gravity at lat %g rad, lon %g rad, h %g m: out of range",
                       lat, lon, h);
    lv_frames_geodetic_to_ecef(planet, lat, lon, h, r);
    if (hypot(hypot(r[0], r[1]), r[2]) <= 0.0)
        return lv_fail(err, LV_ERR_INPUT, "gravity at h %g m: the centre of the planet", h);
    if (nws > 0) {
        ws = malloc(nws * sizeof *ws);
        if (ws == NULL)
            return lv_fail(err, LV_ERR_NOMEM, "gravity '%s': out of memory", g->name);
    }
    lv_gravity_eval(g, ws, r, a, &out->potential);
    free(ws);
    lv_frames_C_ned_ecef(lat, lon, C);
    /* centrifugal acceleration -w x (w x r) = omega^2 (x, y, 0) in ECEF */
    const double w2 = planet->omega * planet->omega;
    const double ac[3] = {w2 * r[0], w2 * r[1], 0.0};
    for (int i = 0; i < 3; i++) {
        out->r_ecef[i] = r[i];
        out->g_ned[i] = C[i][0] * a[0] + C[i][1] * a[1] + C[i][2] * a[2];
        out->g_eff_ned[i] = out->g_ned[i] + C[i][0] * ac[0] + C[i][1] * ac[1] + C[i][2] * ac[2];
    }
    return LV_OK;
}
