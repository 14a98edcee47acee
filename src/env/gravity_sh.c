/* gravity_sh.c - spherical-harmonic gravity from fully normalised coefficients,
 * by the Cunningham (1970) recursion of V_nm, W_nm in Cartesian coordinates
 * (Montenbruck & Gill, Satellite Orbits, 2000, sec. 3.2.4-3.2.5), normalised as
 * in docs/gravity.md: no division by cos(latitude), finite at the poles. Also
 * the reader of ICGEM .gfc coefficient files. */
#define _POSIX_C_SOURCE 200809L /* fmemopen */
#include <errno.h>
#include <pthread.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "env/gravity_impl.h"
#include "io/readfile.h"
#include "io/numparse.h"

lv_status lv_gravity_sh_alloc(lv_gravity *g, int degree, int order, lv_err *err)
{
    if (degree < 0 || order < 0 || order > degree)
        return lv_fail(err, LV_ERR_INPUT,
                       "gravity 'sh': degree %d, order %d: need 0 <= order <= degree", degree,
                       order);
    const size_t nc = lv_gravity_tri_count(degree), nr = lv_gravity_tri_count(degree + 1);
    const size_t total = 11 * nc + 2 * nr + (size_t)degree + 2;
    double *block = calloc(total, sizeof *block);
    if (block == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "gravity 'sh': out of memory for degree %d", degree);
    free(g->block);
    g->block = block;
    g->degree = degree;
    g->order = order;
    g->cnm = block;
    g->snm = g->cnm + nc;
    g->f1 = g->snm + nc;
    g->f2 = g->f1 + nc;
    g->f3 = g->f2 + nc;
    g->k6 = g->f3 + nc;
    g->alpha = g->k6 + 6 * nc;
    g->beta = g->alpha + nr;
    g->diag = g->beta + nr;
    g->cnm[0] = 1.0;

    /* Column recursion of the normalised V_nm (docs/gravity.md eq. G5):
     * alpha = sqrt((2n-1)(2n+1) / ((n-m)(n+m))),
     * beta = sqrt((2n+1)(n+m-1)(n-m-1) / ((2n-3)(n+m)(n-m))). */
    for (int n = 1; n <= degree + 1; n++) {
        for (int m = 0; m < n; m++) {
            const double dn = n, dm = m;
            const size_t k = lv_gravity_tri(n, m);
            g->alpha[k] = sqrt((2 * dn - 1) * (2 * dn + 1) / ((dn - dm) * (dn + dm)));
            if (n >= m + 2)
                g->beta[k] = sqrt((2 * dn + 1) * (dn + dm - 1) * (dn - dm - 1) /
                                  ((2 * dn - 3) * (dn + dm) * (dn - dm)));
        }
    }
    /* Sectoral step (eq. G4): sqrt(3) for m = 1, sqrt((2m+1)/(2m)) after. */
    for (int m = 1; m <= degree + 1; m++)
        g->diag[m] = m == 1 ? sqrt(3.0) : sqrt((2.0 * m + 1.0) / (2.0 * m));
    /* Acceleration factors (eq. G7): ratios of normalisation constants N_nm. */
    for (int n = 0; n <= degree; n++) {
        const double dn = n, q = (2 * dn + 1) / (2 * dn + 3);
        for (int m = 0; m <= n; m++) {
            const double dm = m;
            const size_t k = lv_gravity_tri(n, m);
            g->f1[k] = sqrt((m == 0 ? 0.5 : 1.0) * q * (dn + dm + 1) * (dn + dm + 2));
            if (m > 0)
                g->f2[k] = sqrt((m == 1 ? 2.0 : 1.0) * q * (dn - dm + 2) * (dn - dm + 1));
            g->f3[k] = sqrt(q * (dn + dm + 1) * (dn - dm + 1));
        }
    }
    lv_gravity_sh_finish(g);
    return LV_OK;
}

void lv_gravity_sh_finish(lv_gravity *g)
{
    for (int n = 0; n <= g->degree; n++) {
        for (int m = 0; m <= n; m++) {
            const size_t k = lv_gravity_tri(n, m);
            const double c = g->cnm[k], s = g->snm[k], h = m == 0 ? 1.0 : 0.5;
            double *q = g->k6 + 6 * k;
            q[0] = h * g->f1[k] * c;
            q[1] = h * g->f1[k] * s;
            q[2] = 0.5 * g->f2[k] * c;
            q[3] = 0.5 * g->f2[k] * s;
            q[4] = g->f3[k] * c;
            q[5] = g->f3[k] * s;
        }
    }
}

void lv_gravity_sh_eval(const lv_gravity *g, double *ws, const double r[3], double a[3],
                        double *U)
{
    const int N = g->degree, M = g->order;
    const double R = g->r_ref;
    const double r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    const double rho = R / r2;
    const double xs = r[0] * rho, ys = r[1] * rho, zs = r[2] * rho, rr = R * rho;
    double *V = ws, *W = ws + lv_gravity_tri_count(N + 1);

    /* V_nm, W_nm for n <= N + 1, m <= min(n, M + 1) (eqs. G3-G5) */
    V[0] = R / sqrt(r2);
    W[0] = 0.0;
    for (int m = 0; m <= M + 1; m++) {
        const size_t kmm = lv_gravity_tri(m, m);
        if (m > 0) {
            const size_t kp = lv_gravity_tri(m - 1, m - 1);
            V[kmm] = g->diag[m] * (xs * V[kp] - ys * W[kp]);
            W[kmm] = g->diag[m] * (xs * W[kp] + ys * V[kp]);
        }
        if (m + 1 <= N + 1) {
            const size_t k = lv_gravity_tri(m + 1, m);
            V[k] = g->alpha[k] * zs * V[kmm];
            W[k] = g->alpha[k] * zs * W[kmm];
        }
        for (int n = m + 2; n <= N + 1; n++) {
            const size_t k = lv_gravity_tri(n, m), k1 = lv_gravity_tri(n - 1, m),
                         k2 = lv_gravity_tri(n - 2, m);
            V[k] = g->alpha[k] * zs * V[k1] - g->beta[k] * rr * V[k2];
            W[k] = g->alpha[k] * zs * W[k1] - g->beta[k] * rr * W[k2];
        }
    }

    /* Sum from the highest degree down: the small terms first (eq. G6-G7). */
    double ax = 0.0, ay = 0.0, az = 0.0, u = 0.0;
    for (int n = N; n >= 0; n--) {
        const int mtop = n < M ? n : M;
        const size_t kn = lv_gravity_tri(n, 0), kn1 = lv_gravity_tri(n + 1, 0);
        for (int m = mtop; m >= 1; m--) {
            const double *q = g->k6 + 6 * (kn + m);
            const double *vp = V + kn1 + m + 1, *wp = W + kn1 + m + 1;
            const double *vm = V + kn1 + m - 1, *wm = W + kn1 + m - 1;
            const double v0 = V[kn1 + m], w0 = W[kn1 + m];
            ax += -q[0] * *vp - q[1] * *wp + q[2] * *vm + q[3] * *wm;
            ay += -q[0] * *wp + q[1] * *vp - q[2] * *wm + q[3] * *vm;
            az += -q[4] * v0 - q[5] * w0;
            u += g->cnm[kn + m] * V[kn + m] + g->snm[kn + m] * W[kn + m];
        }
        const double *q = g->k6 + 6 * kn; /* m = 0: S(n,0) plays no part */
        ax -= q[0] * V[kn1 + 1];
        ay -= q[0] * W[kn1 + 1];
        az -= q[4] * V[kn1] + q[5] * W[kn1];
        u += g->cnm[kn] * V[kn] + g->snm[kn] * W[kn];
    }
    const double scale = g->gm / (R * R);
    a[0] = scale * ax;
    a[1] = scale * ay;
    a[2] = scale * az;
    if (U != NULL)
        *U = g->gm / R * u;
}

/* ------------------------------------------------------------ .gfc reader -- */

#define GFC_LINE_MAX 1024

static int next_token(char **cur, char **tok)
{
    char *p = *cur;
    while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n')
        p++;
    if (*p == '\0')
        return 0;
    *tok = p;
    while (*p != '\0' && *p != ' ' && *p != '\t' && *p != '\r' && *p != '\n')
        p++;
    if (*p != '\0')
        *p++ = '\0';
    *cur = p;
    return 1;
}

/* A real number, Fortran 'D' exponents accepted; finite only. */
static int parse_real(const char *tok, double *out)
{
    char buf[64];
    size_t n = strlen(tok);
    if (n == 0 || n >= sizeof buf)
        return 0;
    for (size_t i = 0; i <= n; i++)
        buf[i] = (tok[i] == 'D' || tok[i] == 'd') ? 'e' : tok[i];
    if (lv_numparse_field(buf, n, out) == 0) /* a normal number: fast_float (io/numparse.h) */
        return 1;
    char *end = NULL; /* the rest with strtod: an underflow reads as 0 or subnormal here */
    double v = strtod(buf, &end);
    if (end == buf || *end != '\0' || !isfinite(v))
        return 0;
    *out = v;
    return 1;
}

static int parse_int(const char *tok, int *out)
{
    char *end = NULL;
    errno = 0;
    long v = strtol(tok, &end, 10);
    if (end == tok || *end != '\0' || errno != 0 || v < -1000000 || v > 1000000)
        return 0;
    *out = (int)v;
    return 1;
}

/* Reads one line; 0 at end of file, -1 if it does not fit the buffer. */
static int read_line(FILE *fp, char *buf, size_t cap)
{
    if (fgets(buf, (int)cap, fp) == NULL)
        return 0;
    size_t n = strlen(buf);
    if (n + 1 == cap && buf[n - 1] != '\n' && !feof(fp)) {
        int ch;
        while ((ch = fgetc(fp)) != EOF && ch != '\n') {
        }
        return -1;
    }
    return 1;
}

/* Reads the coefficients from `fp` (the file `path`, for messages), closes fp. */
static lv_status read_gfc_stream(lv_gravity *g, FILE *fp, const char *path, int degree, int order,
                                 lv_err *err)
{
    lv_status st = LV_OK;
    unsigned char *seen = NULL;
    char line[GFC_LINE_MAX];
    int lineno = 0, rc, file_max = -1, max_line = 0, in_head = 1;
    double gm = NAN, radius = NAN;

    /* Header (ICGEM format 2.0 section 3): "key value" lines up to end_of_head. */
    while (in_head && (rc = read_line(fp, line, sizeof line)) != 0) {
        lineno++;
        char *cur = line, *key = NULL, *val = NULL;
        if (rc < 0 || !next_token(&cur, &key))
            continue;
        if (strcmp(key, "end_of_head") == 0) {
            in_head = 0;
            break;
        }
        if (!next_token(&cur, &val))
            continue;
        if (strcmp(key, "earth_gravity_constant") == 0 || strcmp(key, "gravity_constant") == 0) {
            if (!parse_real(val, &gm) || gm <= 0.0) {
                st = lv_fail(err, LV_ERR_INPUT, "%s:%d: bad %s '%s'", path, lineno, key, val);
                goto fail;
            }
        } else if (strcmp(key, "radius") == 0) {
            if (!parse_real(val, &radius) || radius <= 0.0) {
                st = lv_fail(err, LV_ERR_INPUT, "%s:%d: bad radius '%s'", path, lineno, val);
                goto fail;
            }
        } else if (strcmp(key, "max_degree") == 0) {
            if (!parse_int(val, &file_max) || file_max < 0) {
                st = lv_fail(err, LV_ERR_INPUT, "%s:%d: bad max_degree '%s'", path, lineno, val);
                goto fail;
            }
            max_line = lineno;
        } else if (strcmp(key, "norm") == 0) {
            if (strcmp(val, "fully_normalized") != 0) {
                st = lv_fail(err, LV_ERR_INPUT,
                             "%s:%d: norm '%s' not supported (need fully_normalized)", path,
                             lineno, val);
                goto fail;
            }
        }
    }
    if (in_head) {
        st = lv_fail(err, LV_ERR_INPUT, "%s:%d: no end_of_head line: not an ICGEM .gfc file",
                     path, lineno);
        goto fail;
    }
    if (isnan(gm) || isnan(radius) || file_max < 0) {
        st = lv_fail(err, LV_ERR_INPUT,
                     "%s:%d: header lacks %s (earth_gravity_constant, radius and max_degree "
                     "are required)",
                     path, lineno,
                     isnan(gm) ? "earth_gravity_constant" : isnan(radius) ? "radius" : "max_degree");
        goto fail;
    }
    if (degree == 0)
        degree = file_max;
    if (order < 0)
        order = degree;
    if (degree < 0 || degree > file_max || order > degree) {
        st = lv_fail(err, LV_ERR_INPUT,
                     "%s: requested degree %d, order %d: need order <= degree <= max_degree %d",
                     path, degree, order, file_max);
        goto fail;
    }
    /* The arrays are sized by the degree before a data line is read (fuzz/fuzz_tables.c:
     * max_degree 70920 in an 800-byte file asked for 260 GB). A coefficient takes a line
     * "gfc n m C S" of 11 bytes at least; a degree for which the rest of the file does not
     * hold even a byte per coefficient is refused now, which keeps the arrays (about 100
     * bytes per coefficient) within about 100 times the file's size, and leaves a file that
     * is merely short to the line-by-line checks below, which name the missing line. */
    {
        const long here = ftell(fp);
        long end = -1;
        if (here >= 0 && fseek(fp, 0, SEEK_END) == 0)
            end = ftell(fp);
        if (end < 0 || fseek(fp, here, SEEK_SET) != 0) {
            st = lv_fail(err, LV_ERR_IO, "%s: cannot read: %s", path, strerror(errno));
            goto fail;
        }
        uint64_t need = 0; /* the (n, m) lines with 2 <= n <= degree, m <= min(n, order) */
        for (int n = 2; n <= degree; n++)
            need += (uint64_t)(n < order ? n : order) + 1;
        if (need > (uint64_t)(end - here)) {
            st = lv_fail(err, LV_ERR_INPUT,
                         "%s:%d: max_degree %d: degree %d, order %d needs %llu 'gfc' lines; the "
                         "%ld bytes after end_of_head cannot hold them",
                         path, max_line, file_max, degree, order, (unsigned long long)need,
                         end - here);
            goto fail;
        }
    }
    st = lv_gravity_sh_alloc(g, degree, order, err);
    if (st != LV_OK)
        goto fail;
    g->gm = gm;
    g->r_ref = radius;
    seen = calloc(lv_gravity_tri_count(degree), 1);
    if (seen == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", path);
        goto fail;
    }

    /* Data: "gfc n m C S [sigma_C sigma_S]" */
    while ((rc = read_line(fp, line, sizeof line)) != 0) {
        lineno++;
        char *cur = line, *key = NULL, *tn = NULL, *tm = NULL, *tc = NULL, *ts = NULL;
        if (rc < 0) {
            st = lv_fail(err, LV_ERR_INPUT, "%s:%d: line longer than %d characters", path, lineno,
                         GFC_LINE_MAX - 2);
            goto fail;
        }
        if (!next_token(&cur, &key))
            continue;
        if (strcmp(key, "gfc") != 0) {
            st = lv_fail(err, LV_ERR_INPUT,
                         "%s:%d: key '%s' not supported (only static 'gfc' lines)", path, lineno,
                         key);
            goto fail;
        }
        int n = 0, m = 0;
        double c = 0.0, s = 0.0;
        if (!next_token(&cur, &tn) || !next_token(&cur, &tm) || !next_token(&cur, &tc) ||
            !next_token(&cur, &ts)) {
            st = lv_fail(err, LV_ERR_INPUT, "%s:%d: expected 'gfc n m C S'", path, lineno);
            goto fail;
        }
        if (!parse_int(tn, &n) || !parse_int(tm, &m)) {
            st = lv_fail(err, LV_ERR_INPUT, "%s:%d: degree/order '%s %s' not integers", path,
                         lineno, tn, tm);
            goto fail;
        }
        if (n < 0 || m < 0 || m > n || n > file_max) {
            st = lv_fail(err, LV_ERR_INPUT,
                         "%s:%d: degree/order (%d, %d) invalid: need 0 <= m <= n <= max_degree %d",
                         path, lineno, n, m, file_max);
            goto fail;
        }
        if (!parse_real(tc, &c) || !parse_real(ts, &s)) {
            st = lv_fail(err, LV_ERR_INPUT, "%s:%d: coefficient (%d, %d): bad value '%s' or '%s'",
                         path, lineno, n, m, tc, ts);
            goto fail;
        }
        if (n > degree || m > order)
            continue; /* truncated away */
        const size_t k = lv_gravity_tri(n, m);
        if (seen[k]) {
            st = lv_fail(err, LV_ERR_INPUT, "%s:%d: coefficient (%d, %d) given twice", path,
                         lineno, n, m);
            goto fail;
        }
        seen[k] = 1;
        g->cnm[k] = c;
        g->snm[k] = s;
    }
    if (ferror(fp)) {
        st = lv_fail(err, LV_ERR_IO, "%s:%d: cannot read: %s", path, lineno,
                     LV_STRERROR(errno ? errno : EIO));
        goto fail;
    }
    /* Degrees 0 and 1 may be left out (C00 = 1, degree 1 = 0 in a geocentric
     * frame); every other (n, m) up to the requested degree/order must be there. */
    for (int n = 2; n <= degree; n++) {
        for (int m = 0; m <= n && m <= order; m++) {
            if (!seen[lv_gravity_tri(n, m)]) {
                st = lv_fail(err, LV_ERR_INPUT,
                             "%s:%d: end of file: coefficient (%d, %d) missing "
                             "(requested degree %d, order %d)",
                             path, lineno, n, m, degree, order);
                goto fail;
            }
        }
    }
    lv_gravity_sh_finish(g);

fail:
    free(seen);
    fclose(fp);
    return st;
}

/* ---- coefficient files read once per process -----------------------------------------------
 * Parsing a .gfc file is most of what loading a mission with "sh" gravity costs (1 M
 * instructions for the shipped degree-20 file, mostly strtod). A process that loads missions
 * again and again (a study, a benchmark, a service) reads the file's bytes each time, which is
 * cheap, and parses them once: the result for a (path, degree, order) is kept together with
 * the bytes it came from, and used again only when the file still holds exactly those bytes
 * (a changed file is parsed again). The cache is process-wide, guarded by a mutex, and its
 * entries never change once made (lv_gravity objects copy their coefficients from them); a
 * file that fails to parse is not kept, so its error is reported every time. At most
 * GFC_CACHE_MAX entries; they live until the process ends. */
#define GFC_CACHE_MAX 16

typedef struct gfc_entry {
    char *path;
    int degree, order;    /* as requested */
    char *bytes;          /* the file's content */
    size_t size;
    double gm, r_ref;
    int deg, ord;         /* as read: the file's max_degree when 0 was asked, ... */
    double *cnm, *snm;    /* [tri_count(deg)] */
} gfc_entry;

static pthread_mutex_t gfc_lock = PTHREAD_MUTEX_INITIALIZER;
static gfc_entry *gfc_cache[GFC_CACHE_MAX]; /* guarded by gfc_lock; entries immutable */
static size_t gfc_count;


static const gfc_entry *gfc_find(const char *path, int degree, int order, const char *bytes,
                                 size_t size)
{
    const gfc_entry *hit = NULL;
    pthread_mutex_lock(&gfc_lock);
    for (size_t i = 0; i < gfc_count && hit == NULL; i++) {
        const gfc_entry *e = gfc_cache[i];
        if (e->degree == degree && e->order == order && e->size == size &&
            strcmp(e->path, path) == 0 && memcmp(e->bytes, bytes, size) == 0)
            hit = e;
    }
    pthread_mutex_unlock(&gfc_lock);
    return hit;
}

/* Keeps g's coefficients as read from `bytes` (taken over, or freed when not kept). */
static void gfc_keep(const lv_gravity *g, const char *path, int degree, int order, char *bytes,
                     size_t size)
{
    const size_t nc = lv_gravity_tri_count(g->degree), lp = strlen(path) + 1;
    gfc_entry *e = malloc(sizeof *e + 2 * nc * sizeof(double) + lp);
    if (e == NULL) {
        free(bytes);
        return;
    }
    e->cnm = (double *)(e + 1);
    e->snm = e->cnm + nc;
    e->path = (char *)(e->snm + nc);
    memcpy(e->path, path, lp);
    memcpy(e->cnm, g->cnm, nc * sizeof(double));
    memcpy(e->snm, g->snm, nc * sizeof(double));
    e->degree = degree;
    e->order = order;
    e->bytes = bytes;
    e->size = size;
    e->gm = g->gm;
    e->r_ref = g->r_ref;
    e->deg = g->degree;
    e->ord = g->order;
    pthread_mutex_lock(&gfc_lock);
    const int kept = gfc_count < GFC_CACHE_MAX;
    if (kept)
        gfc_cache[gfc_count++] = e;
    pthread_mutex_unlock(&gfc_lock);
    if (!kept) {
        free(e->bytes);
        free(e);
    }
}

lv_status lv_gravity_sh_read_gfc(lv_gravity *g, const char *path, int degree, int order,
                                 lv_err *err)
{
    size_t size = 0;
    char *bytes = NULL;
    lv_status rst = lv_read_file(path, LV_GRAVITY_FILE_MAX, "gravity coefficient file", &bytes,
                                 &size, err);
    if (rst != LV_OK)
        return rst;
    const gfc_entry *e = gfc_find(path, degree, order, bytes, size);
    if (e != NULL) { /* read before, the same bytes: the same coefficients */
        free(bytes);
        lv_status st = lv_gravity_sh_alloc(g, e->deg, e->ord, err);
        if (st != LV_OK)
            return st;
        const size_t nc = lv_gravity_tri_count(e->deg);
        g->gm = e->gm;
        g->r_ref = e->r_ref;
        memcpy(g->cnm, e->cnm, nc * sizeof(double));
        memcpy(g->snm, e->snm, nc * sizeof(double));
        lv_gravity_sh_finish(g);
        return LV_OK;
    }
    /* parse the bytes read (not the file again: what is kept is what was parsed) */
    FILE *fp = size > 0 ? fmemopen(bytes, size, "r") : fopen(path, "r");
    if (fp == NULL) {
        const int e_no = errno;
        free(bytes);
        return lv_fail(err, LV_ERR_IO, "%s: cannot open gravity coefficient file: %s", path,
                       LV_STRERROR(e_no));
    }
    lv_status st = read_gfc_stream(g, fp, path, degree, order, err); /* closes fp */
    if (st == LV_OK && size > 0)
        gfc_keep(g, path, degree, order, bytes, size);
    else
        free(bytes);
    return st;
}
