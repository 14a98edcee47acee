/* table.c - N-D lookup tables: validation, multilinear and PCHIP evaluation, breakpoints.
 *
 * PCHIP: monotone piecewise cubic Hermite (Fritsch & Carlson, SIAM J. Numer. Anal. 17(2),
 * 1980) with the weighted harmonic-mean slopes of Fritsch & Butland (SIAM J. Sci. Stat.
 * Comput. 5(2), 1984) and the shape-preserving three-point end slopes of Moler, "Numerical
 * Computing with MATLAB", sec. 3.4 (pchip). N-D: multilinear in coordinates warped by one
 * monotone Hermite shape per axis interval (compute_shapes), monotone along every axis.
 */
#include "lvsim/lv_table.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/names.h"
#include "core/status.h"

struct lv_table {
    size_t n_dims, n_out;
    size_t n[LV_TABLE_MAX_DIMS];
    size_t stride[LV_TABLE_MAX_DIMS]; /* in doubles, outputs included */
    double *x[LV_TABLE_MAX_DIMS];     /* into `data` */
    double *y;                        /* into `data` */
    double *slope;                    /* 1-D PCHIP: dy/dx at each node [n[0] * n_out], or NULL */
    double *shape[LV_TABLE_MAX_DIMS]; /* N-D PCHIP: alpha, beta per interval and output:
                                       * [((i * n_out) + k) * 2 + {0, 1}], or NULL */
    double *data;                     /* the one block of numbers */
    lv_interp interp;
    lv_extrap extrap;
    char *name;
    char *axis_name[LV_TABLE_MAX_DIMS];
    char *axis_unit[LV_TABLE_MAX_DIMS];
    char **out_name; /* [n_out] */
    char **out_unit; /* [n_out] */
};

/* ---- PCHIP slopes (Fritsch-Butland; Moler's pchip) ---------------------------------- */

/* Slope at an interior node between intervals of width h0, h1 and secants d0, d1:
 * zero at a local extremum, else the weighted harmonic mean, which satisfies the
 * Fritsch-Carlson monotonicity conditions (|m| <= 3 min(|d0|, |d1|)). */
static double pchip_inner(double h0, double d0, double h1, double d1)
{
    if (d0 * d1 <= 0.0)
        return 0.0;
    const double w0 = 2.0 * h1 + h0, w1 = h1 + 2.0 * h0;
    return (w0 + w1) / (w0 / d0 + w1 / d1);
}

/* Slope at an end node: the non-centred three-point formula, limited so that the end
 * interval stays monotone (h0, d0: the end interval; h1, d1: its neighbour). */
static int sign(double v)
{
    return (v > 0.0) - (v < 0.0);
}

static double pchip_end(double h0, double d0, double h1, double d1)
{
    const double m = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
    if (sign(m) != sign(d0))
        return 0.0;
    if (sign(d0) != sign(d1) && fabs(m) > fabs(3.0 * d0))
        return 3.0 * d0;
    return m;
}

/* Slope at node j of xs[0..m-1] / vs[0..m-1] (values `sv` apart). Node 0 and node m-1 get
 * the end formula, so callers pass a stencil that ends only where the axis ends (or only
 * ask for interior nodes). Two nodes: the secant. */
static double pchip_slope(const double *xs, const double *vs, size_t sv, size_t m, size_t j)
{
    if (m == 2)
        return (vs[sv] - vs[0]) / (xs[1] - xs[0]);
    if (j == 0) {
        const double h0 = xs[1] - xs[0], h1 = xs[2] - xs[1];
        return pchip_end(h0, (vs[sv] - vs[0]) / h0, h1, (vs[2 * sv] - vs[sv]) / h1);
    }
    if (j == m - 1) {
        const double h0 = xs[j] - xs[j - 1], h1 = xs[j - 1] - xs[j - 2];
        return pchip_end(h0, (vs[j * sv] - vs[(j - 1) * sv]) / h0, h1,
                         (vs[(j - 1) * sv] - vs[(j - 2) * sv]) / h1);
    }
    const double h0 = xs[j] - xs[j - 1], h1 = xs[j + 1] - xs[j];
    return pchip_inner(h0, (vs[j * sv] - vs[(j - 1) * sv]) / h0, h1,
                       (vs[(j + 1) * sv] - vs[j * sv]) / h1);
}

/* a + t (b - a), exact at t = 0 and t = 1 and for a == b, within [a, b] for t in [0, 1]:
 * from the nearer end (1 - t is exact for t >= 0.5). Outside [0, 1]: the same line. */
static double lerp(double a, double b, double t)
{
    return t < 0.5 ? a + t * (b - a) : b - (1.0 - t) * (b - a);
}

/* Cubic Hermite on [x0, x0 + h] at t = (x - x0) / h, written from the nearer end as lerp()
 * so that grid values, flat stretches and the two end values are reproduced exactly.
 * Outside [0, 1] (only under LV_EXTRAP_LINEAR): the line through the end value with the
 * end slope. */
static double hermite(double t, double h, double v0, double m0, double v1, double m1)
{
    if (t < 0.0)
        return v0 + m0 * (t * h);
    if (t > 1.0)
        return v1 + m1 * ((t - 1.0) * h);
    const double u = 1.0 - t;
    const double slopes = h * (t * u * u * m0 - t * t * u * m1);
    if (t < 0.5)
        return v0 + (v1 - v0) * (t * t * (3.0 - 2.0 * t)) + slopes;
    return v1 - (v1 - v0) * ((1.0 + 2.0 * t) * u * u) + slopes;
}

/* Normalised cubic Hermite shape on a cell: H(0) = 0, H(1) = 1, H'(0) = alpha,
 * H'(1) = beta. Monotone for alpha, beta in [0, 3] (Fritsch-Carlson). Linear beyond the
 * cell (LV_EXTRAP_LINEAR). */
static double warp(double t, double alpha, double beta)
{
    if (t < 0.0)
        return alpha * t;
    if (t > 1.0)
        return 1.0 + beta * (t - 1.0);
    const double u = 1.0 - t;
    return t * t * (3.0 - 2.0 * t) + t * u * (alpha * u - beta * t);
}

/* N-D PCHIP shapes. On interval i of axis d, every grid line along d (each position on
 * the other axes) has 1-D PCHIP end slopes m0, m1 and secant delta with m0 / delta and
 * m1 / delta in [0, 3], the Fritsch-Carlson region. The axis gets one shape per interval
 * and output: H with H'(0) = alpha = sum |m0| / sum |delta| and H'(1) = beta = sum |m1| /
 * sum |delta| over those lines; alpha, beta are in [0, 3] too, so H is monotone.
 * Multilinear interpolation in (H_1(t_1), .., H_N(t_N)) is then monotone along every axis
 * wherever the data are, within each cell's corner values, exact on the grid, and
 * continuous (a shape belongs to a slab, shared by the cells on either side of a face).
 * Where the lines along an axis are proportional it is their 1-D PCHIP; in general it is
 * only C0 across cell faces: C1 would need one shape per line, which breaks monotonicity
 * along the other axes. */
static void compute_shapes(lv_table *t)
{
    size_t np = 1;
    for (size_t d = 0; d < t->n_dims; d++)
        np *= t->n[d];
    for (size_t d = 0; d < t->n_dims; d++) {
        const size_t n = t->n[d], sd = t->stride[d], no = t->n_out;
        double *ab = t->shape[d];                /* [(n-1) * no * 2]: alpha, beta */
        double *sdel = ab + (n - 1) * no * 2;    /* [(n-1) * no]: sum |delta| */
        for (size_t q = 0; q < (n - 1) * no * 3; q++)
            ab[q] = 0.0;
        for (size_t p = 0; p < np; p++) { /* grid point p: the lower node of interval i */
            const size_t i = (p * no / sd) % n;
            if (i == n - 1)
                continue;
            const size_t lo = i > 0 ? i - 1 : 0, hi = i + 2 < n ? i + 2 : n - 1;
            const double *xs = t->x[d] + lo;
            for (size_t k = 0; k < no; k++) {
                const double *v = t->y + p * no + k - (i - lo) * sd; /* node lo of the line */
                double *acc = ab + (i * no + k) * 2;
                acc[0] += fabs(pchip_slope(xs, v, sd, hi - lo + 1, i - lo));
                acc[1] += fabs(pchip_slope(xs, v, sd, hi - lo + 1, i - lo + 1));
                sdel[i * no + k] += fabs(v[(i - lo + 1) * sd] - v[(i - lo) * sd])
                                    / (t->x[d][i + 1] - t->x[d][i]);
            }
        }
        for (size_t q = 0; q < (n - 1) * no; q++) {
            if (sdel[q] > 0.0) {
                ab[2 * q] /= sdel[q];
                ab[2 * q + 1] /= sdel[q];
            } else { /* flat slab: the shape does not matter; keep it linear */
                ab[2 * q] = ab[2 * q + 1] = 1.0;
            }
        }
    }
}

/* ---- creation ------------------------------------------------------------------------- */

static char *dup_text(const char *s)
{
    if (s == NULL)
        s = "";
    const size_t len = strlen(s);
    char *d = malloc(len + 1);
    if (d != NULL)
        memcpy(d, s, len + 1);
    return d;
}

static const char *tname(const lv_table_spec *s)
{
    return (s->name != NULL && s->name[0] != '\0') ? s->name : "(unnamed)";
}

static lv_status check_spec(const lv_table_spec *s, size_t *n_points, lv_err *err)
{
    if (s->n_dims < 1 || s->n_dims > LV_TABLE_MAX_DIMS)
        return lv_fail(err, LV_ERR_INPUT, "table '%s': %zu axes; 1 to %d are supported",
                       tname(s), s->n_dims, LV_TABLE_MAX_DIMS);
    if (s->n_out < 1)
        return lv_fail(err, LV_ERR_INPUT, "table '%s': no outputs (n_out = 0)", tname(s));
    if (s->interp != LV_INTERP_LINEAR && s->interp != LV_INTERP_PCHIP)
        return lv_fail(err, LV_ERR_INPUT, "table '%s': unknown interpolation %d", tname(s),
                       (int)s->interp);
    if (s->extrap != LV_EXTRAP_ERROR && s->extrap != LV_EXTRAP_CLAMP
        && s->extrap != LV_EXTRAP_LINEAR)
        return lv_fail(err, LV_ERR_INPUT, "table '%s': unknown extrapolation %d", tname(s),
                       (int)s->extrap);
    size_t np = 1;
    for (size_t d = 0; d < s->n_dims; d++) {
        const double *b = s->x[d];
        if (s->n[d] < 2)
            return lv_fail(err, LV_ERR_INPUT,
                           "table '%s': axis %zu has %zu breakpoint(s); at least 2 needed",
                           tname(s), d, s->n[d]);
        if (b == NULL)
            return lv_fail(err, LV_ERR_INPUT, "table '%s': axis %zu: no breakpoints given",
                           tname(s), d);
        for (size_t i = 0; i < s->n[d]; i++) {
            if (!isfinite(b[i]))
                return lv_fail(err, LV_ERR_INPUT,
                               "table '%s': axis %zu breakpoint %zu is %g (not finite)",
                               tname(s), d, i, b[i]);
            if (i > 0 && !(b[i] > b[i - 1]))
                return lv_fail(err, LV_ERR_INPUT,
                               "table '%s': axis %zu breakpoints not strictly increasing: "
                               "x[%zu] = %.17g after x[%zu] = %.17g",
                               tname(s), d, i, b[i], i - 1, b[i - 1]);
        }
        if (np > ((size_t)-1) / s->n[d])
            return lv_fail(err, LV_ERR_INPUT, "table '%s': grid too large", tname(s));
        np *= s->n[d];
    }
    if (np > ((size_t)-1) / sizeof(double) / s->n_out)
        return lv_fail(err, LV_ERR_INPUT, "table '%s': grid too large", tname(s));
    if (s->y == NULL)
        return lv_fail(err, LV_ERR_INPUT, "table '%s': no values given", tname(s));
    for (size_t p = 0; p < np * s->n_out; p++) {
        if (isfinite(s->y[p]))
            continue;
        /* Name the grid index (i0, i1, ..) and output of the offending value. */
        char where[96];
        size_t rest = p / s->n_out, len = 0;
        size_t idx[LV_TABLE_MAX_DIMS];
        for (size_t d = s->n_dims; d-- > 0;) {
            idx[d] = rest % s->n[d];
            rest /= s->n[d];
        }
        where[0] = '\0';
        for (size_t d = 0; d < s->n_dims && len < sizeof where; d++) {
            int w = snprintf(where + len, sizeof where - len, "%s%zu", d ? ", " : "", idx[d]);
            len += w > 0 ? (size_t)w : 0;
        }
        return lv_fail(err, LV_ERR_INPUT,
                       "table '%s': value at grid index (%s), output %zu is %g (not finite)",
                       tname(s), where, p % s->n_out, s->y[p]);
    }
    *n_points = np;
    return LV_OK;
}

lv_status lv_table_create(const lv_table_spec *spec, lv_table **out, lv_err *err)
{
    lv_table *t = NULL;
    size_t np = 0;
    lv_status st;
    if (out == NULL || spec == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_table_create: NULL argument");
    *out = NULL;
    st = check_spec(spec, &np, err);
    if (st != LV_OK)
        return st;

    st = LV_ERR_NOMEM;
    t = calloc(1, sizeof *t);
    if (t == NULL)
        goto fail;
    t->n_dims = spec->n_dims;
    t->n_out = spec->n_out;
    t->interp = spec->interp;
    t->extrap = spec->extrap;

    size_t n_x = 0;
    for (size_t d = 0; d < t->n_dims; d++)
        n_x += spec->n[d];
    const size_t n_y = np * t->n_out;
    const size_t n_slope = (t->n_dims == 1 && t->interp == LV_INTERP_PCHIP) ? n_y : 0;
    size_t n_shape = 0; /* per axis: 2 per interval and output + scratch, 1 per (i, k) */
    if (t->n_dims > 1 && t->interp == LV_INTERP_PCHIP)
        for (size_t d = 0; d < t->n_dims; d++)
            n_shape += (spec->n[d] - 1) * t->n_out * 3;
    t->data = malloc((n_x + n_y + n_slope + n_shape) * sizeof(double));
    if (t->data == NULL)
        goto fail;
    double *p = t->data;
    for (size_t d = 0; d < t->n_dims; d++) {
        t->n[d] = spec->n[d];
        t->x[d] = p;
        memcpy(p, spec->x[d], t->n[d] * sizeof(double));
        p += t->n[d];
    }
    t->y = p;
    memcpy(p, spec->y, n_y * sizeof(double));
    p += n_y;
    size_t stride = t->n_out;
    for (size_t d = t->n_dims; d-- > 0;) {
        t->stride[d] = stride;
        stride *= t->n[d];
    }
    if (n_slope > 0) { /* 1-D PCHIP: the node slopes depend on the data only */
        t->slope = p;
        for (size_t k = 0; k < t->n_out; k++)
            for (size_t j = 0; j < t->n[0]; j++)
                t->slope[j * t->n_out + k] =
                    pchip_slope(t->x[0], t->y + k, t->n_out, t->n[0], j);
    }
    if (n_shape > 0) {
        for (size_t d = 0; d < t->n_dims; d++) {
            t->shape[d] = p;
            p += (t->n[d] - 1) * t->n_out * 3;
        }
        compute_shapes(t);
    }

    t->name = dup_text(spec->name);
    if (t->name == NULL)
        goto fail;
    for (size_t d = 0; d < t->n_dims; d++) {
        t->axis_name[d] = dup_text(spec->axis_name[d]);
        t->axis_unit[d] = dup_text(spec->axis_unit[d]);
        if (t->axis_name[d] == NULL || t->axis_unit[d] == NULL)
            goto fail;
    }
    t->out_name = calloc(t->n_out, sizeof *t->out_name);
    t->out_unit = calloc(t->n_out, sizeof *t->out_unit);
    if (t->out_name == NULL || t->out_unit == NULL)
        goto fail;
    for (size_t k = 0; k < t->n_out; k++) {
        char deflt[32];
        snprintf(deflt, sizeof deflt, "y%zu", k + 1);
        const char *nm = spec->out_name != NULL ? spec->out_name[k] : NULL;
        t->out_name[k] = dup_text(nm != NULL && nm[0] != '\0' ? nm : deflt);
        t->out_unit[k] = dup_text(spec->out_unit != NULL ? spec->out_unit[k] : NULL);
        if (t->out_name[k] == NULL || t->out_unit[k] == NULL)
            goto fail;
    }
    *out = t;
    return LV_OK;

fail:
    lv_table_free(t);
    return lv_fail(err, st, "table '%s': out of memory", tname(spec));
}

void lv_table_free(lv_table *tab)
{
    if (tab == NULL)
        return;
    for (size_t d = 0; d < LV_TABLE_MAX_DIMS; d++) {
        free(tab->axis_name[d]);
        free(tab->axis_unit[d]);
    }
    for (size_t k = 0; tab->out_name != NULL && k < tab->n_out; k++)
        free(tab->out_name[k]);
    for (size_t k = 0; tab->out_unit != NULL && k < tab->n_out; k++)
        free(tab->out_unit[k]);
    free(tab->out_name);
    free(tab->out_unit);
    free(tab->name);
    free(tab->data);
    free(tab);
}

/* ---- evaluation ------------------------------------------------------------------------ */

/* Interval i in [0, n-2] with b[i] <= x < b[i+1] (first or last interval outside the
 * range). Tries the cursor's interval and its neighbours first: sequential time stepping
 * costs two comparisons; otherwise bisection. */
static size_t locate(const double *b, size_t n, double x, size_t guess)
{
    size_t i = guess < n - 1 ? guess : 0;
    size_t lo, hi;
    if (x >= b[i]) {
        if (i == n - 2 || x < b[i + 1])
            return i;
        if (i + 1 == n - 2 || x < b[i + 2])
            return i + 1;
        lo = i + 2;
        hi = n - 2;
    } else {
        if (i <= 1 || x >= b[i - 1]) /* also x < b[0] from interval 1 */
            return i == 0 ? 0 : i - 1;
        lo = 0;
        hi = i - 2;
    }
    while (lo < hi) { /* largest j in [lo, hi] with b[j] <= x (lo if none) */
        const size_t mid = lo + (hi - lo + 1) / 2;
        if (b[mid] <= x)
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo;
}

static lv_status out_of_range(const lv_table *tab, size_t d, double x, lv_err *err)
{
    if (err == NULL)
        return LV_ERR_INPUT;
    const char *nm = tab->axis_name[d][0] != '\0' ? tab->axis_name[d] : "x";
    if (isnan(x))
        return lv_fail(err, LV_ERR_INPUT, "table '%s': axis %zu '%s' is NaN", tab->name, d, nm);
    return lv_fail(err, LV_ERR_INPUT,
                   "table '%s': axis %zu '%s' [%s] = %.17g is outside [%.17g, %.17g] "
                   "(extrapolation: error)",
                   tab->name, d, nm, tab->axis_unit[d], x, tab->x[d][0],
                   tab->x[d][tab->n[d] - 1]);
}

/* Per-axis interval and fraction (t outside [0, 1] only under LV_EXTRAP_LINEAR). */
static lv_status place(const lv_table *tab, lv_table_cursor *cur, const double *x, size_t *iv,
                       double *tv, lv_err *err)
{
    for (size_t d = 0; d < tab->n_dims; d++) {
        const double *b = tab->x[d];
        const size_t n = tab->n[d];
        double xd = x[d];
        if (!(xd >= b[0] && xd <= b[n - 1])) { /* also catches NaN */
            if (isnan(xd) || tab->extrap == LV_EXTRAP_ERROR)
                return out_of_range(tab, d, xd, err);
            if (tab->extrap == LV_EXTRAP_CLAMP)
                xd = xd < b[0] ? b[0] : b[n - 1];
        }
        const size_t i = locate(b, n, xd, cur != NULL ? cur->i[d] : 0);
        if (cur != NULL)
            cur->i[d] = i;
        iv[d] = i;
        tv[d] = (xd - b[i]) / (b[i + 1] - b[i]);
    }
    return LV_OK;
}

/* Multilinear interpolation of the 2^N cell corners, reduced one axis at a time with
 * lerp() (last axis first), in the coordinates w_d = t_d (LINEAR) or w_d = H_d(t_d)
 * (N-D PCHIP, see compute_shapes()). Grid values and constant data come out exactly. */
static void eval_cell(const lv_table *tab, const size_t *iv, const double *tv, double *y)
{
    const size_t nd = tab->n_dims, nc = (size_t)1 << nd;
    size_t off[1u << LV_TABLE_MAX_DIMS];
    double buf[1u << LV_TABLE_MAX_DIMS], w[LV_TABLE_MAX_DIMS];
    size_t base = 0;
    for (size_t d = 0; d < nd; d++) {
        base += iv[d] * tab->stride[d];
        w[d] = tv[d];
    }
    for (size_t c = 0; c < nc; c++) { /* bit (nd-1-d) of c: upper node on axis d */
        off[c] = base;
        for (size_t d = 0; d < nd; d++)
            if (c & ((size_t)1 << (nd - 1 - d)))
                off[c] += tab->stride[d];
    }
    for (size_t k = 0; k < tab->n_out; k++) {
        if (tab->interp == LV_INTERP_PCHIP) {
            for (size_t d = 0; d < nd; d++) {
                const double *ab = tab->shape[d] + (iv[d] * tab->n_out + k) * 2;
                w[d] = warp(tv[d], ab[0], ab[1]);
            }
        }
        for (size_t c = 0; c < nc; c++)
            buf[c] = tab->y[off[c] + k];
        size_t cnt = nc;
        for (size_t d = nd; d-- > 0;) {
            cnt /= 2;
            for (size_t q = 0; q < cnt; q++)
                buf[q] = lerp(buf[2 * q], buf[2 * q + 1], w[d]);
        }
        y[k] = buf[0];
    }
}

lv_status lv_table_eval(const lv_table *tab, lv_table_cursor *cur, const double *x, double *y,
                        lv_err *err)
{
    size_t iv[LV_TABLE_MAX_DIMS];
    double tv[LV_TABLE_MAX_DIMS];
    const lv_status st = place(tab, cur, x, iv, tv, err);
    if (st != LV_OK)
        return st;
    if (tab->interp == LV_INTERP_LINEAR && tab->n_dims == 1) {
        const size_t no = tab->n_out;
        const double *v0 = tab->y + iv[0] * no;
        for (size_t k = 0; k < no; k++)
            y[k] = lerp(v0[k], v0[no + k], tv[0]);
    } else if (tab->interp == LV_INTERP_LINEAR || tab->slope == NULL) {
        eval_cell(tab, iv, tv, y); /* N-D: multilinear, or in PCHIP shapes */
    } else { /* 1-D PCHIP, slopes precomputed */
        const size_t no = tab->n_out, i = iv[0];
        const double h = tab->x[0][i + 1] - tab->x[0][i];
        const double *v0 = tab->y + i * no, *s0 = tab->slope + i * no;
        for (size_t k = 0; k < no; k++)
            y[k] = hermite(tv[0], h, v0[k], s0[k], v0[no + k], s0[no + k]);
    }
    return LV_OK;
}

lv_status lv_table_eval1(const lv_table *tab, lv_table_cursor *cur, double x, double *y,
                         lv_err *err)
{
    if (tab->n_dims != 1)
        return lv_fail(err, LV_ERR_INPUT, "table '%s': lv_table_eval1 on a %zu-axis table",
                       tab->name, tab->n_dims);
    return lv_table_eval(tab, cur, &x, y, err);
}

/* ---- breakpoints, names ---------------------------------------------------------------- */

double lv_table_next_breakpoint(const lv_table *tab, size_t dim, double x)
{
    if (tab == NULL || dim >= tab->n_dims || isnan(x))
        return INFINITY;
    const double *b = tab->x[dim];
    size_t lo = 0, hi = tab->n[dim]; /* first index with b > x, in [lo, hi] */
    while (lo < hi) {
        const size_t mid = lo + (hi - lo) / 2;
        if (b[mid] > x)
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo < tab->n[dim] ? b[lo] : INFINITY;
}

size_t lv_table_n_dims(const lv_table *tab)
{
    return tab->n_dims;
}

size_t lv_table_n_out(const lv_table *tab)
{
    return tab->n_out;
}

const double *lv_table_breakpoints(const lv_table *tab, size_t dim, size_t *n)
{
    if (dim >= tab->n_dims) {
        if (n != NULL)
            *n = 0;
        return NULL;
    }
    if (n != NULL)
        *n = tab->n[dim];
    return tab->x[dim];
}

lv_interp lv_table_interp(const lv_table *tab)
{
    return tab->interp;
}

lv_extrap lv_table_extrap(const lv_table *tab)
{
    return tab->extrap;
}

const char *lv_table_name(const lv_table *tab)
{
    return tab->name;
}

const char *lv_table_axis_name(const lv_table *tab, size_t dim)
{
    return dim < tab->n_dims ? tab->axis_name[dim] : "";
}

const char *lv_table_axis_unit(const lv_table *tab, size_t dim)
{
    return dim < tab->n_dims ? tab->axis_unit[dim] : "";
}

const char *lv_table_out_name(const lv_table *tab, size_t k)
{
    return k < tab->n_out ? tab->out_name[k] : "";
}

const char *lv_table_out_unit(const lv_table *tab, size_t k)
{
    return k < tab->n_out ? tab->out_unit[k] : "";
}

lv_status lv_table_out_index(const lv_table *tab, const char *name, size_t *k, lv_err *err)
{
    lv_suggest sg;
    char hint[128];
    lv_suggest_init(&sg, name);
    for (size_t j = 0; j < tab->n_out; j++) {
        if (strcmp(tab->out_name[j], name) == 0) {
            *k = j;
            return LV_OK;
        }
        lv_suggest_add(&sg, tab->out_name[j]);
    }
    lv_suggest_text(&sg, hint, sizeof hint);
    return lv_fail(err, LV_ERR_NOTFOUND, "table '%s': no output '%s'%s", tab->name, name, hint);
}

/* ---- affine copies (table dispersions) ------------------------------------------------ */

lv_status lv_table_create_affine(const lv_table *tab, const double *scale, const double *bias,
                                 lv_table **out, lv_err *err)
{
    if (tab == NULL || out == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_table_create_affine: NULL argument");
    *out = NULL;
    size_t np = 1;
    lv_table_spec sp;
    memset(&sp, 0, sizeof sp);
    sp.n_dims = tab->n_dims;
    for (size_t d = 0; d < tab->n_dims; d++) {
        sp.n[d] = tab->n[d];
        sp.x[d] = tab->x[d];
        sp.axis_name[d] = tab->axis_name[d];
        sp.axis_unit[d] = tab->axis_unit[d];
        np *= tab->n[d];
    }
    for (size_t k = 0; k < tab->n_out; k++)
        if ((scale != NULL && !isfinite(scale[k])) || (bias != NULL && !isfinite(bias[k])))
            return lv_fail(err, LV_ERR_INPUT, "table '%s': output '%s': scale %g and bias %g "
                           "must be finite", tab->name ? tab->name : "",
                           tab->out_name ? tab->out_name[k] : "", scale ? scale[k] : 1.0,
                           bias ? bias[k] : 0.0);
    double *y = malloc(np * tab->n_out * sizeof *y);
    if (y == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    for (size_t i = 0; i < np; i++)
        for (size_t k = 0; k < tab->n_out; k++) {
            const size_t j = i * tab->n_out + k;
            y[j] = (scale ? scale[k] : 1.0) * tab->y[j] + (bias ? bias[k] : 0.0);
        }
    sp.n_out = tab->n_out;
    sp.y = y;
    sp.interp = tab->interp;
    sp.extrap = tab->extrap;
    sp.name = tab->name;
    sp.out_name = (const char *const *)tab->out_name;
    sp.out_unit = (const char *const *)tab->out_unit;
    const lv_status st = lv_table_create(&sp, out, err);
    free(y);
    return st;
}
