/* lv_table.h - N-dimensional lookup tables (1 to 4 axes, several outputs per grid point).
 *
 * Thrust and mass flow over time, aerodynamic coefficients over Mach/alpha/beta/altitude,
 * wind over altitude, control histories from an optimiser. Interpolation is multilinear or
 * monotone piecewise cubic (PCHIP: Fritsch & Carlson 1980, slopes of Fritsch & Butland 1984,
 * as MATLAB pchip and SciPy PchipInterpolator; N-D: multilinear in per-axis monotone Hermite
 * coordinates). Formats, conventions and examples: docs/tables.md.
 *
 * Threads: a table is immutable after creation and may be shared read-only between threads
 * and simulations. The interval last used is remembered in a caller-owned lv_table_cursor,
 * one per table per simulation. lv_table_eval() allocates nothing and looks nothing up by name.
 */
#ifndef LVSIM_LV_TABLE_H
#define LVSIM_LV_TABLE_H

#include <stddef.h>

#include "lvsim/lv_status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LV_TABLE_MAX_DIMS 4

typedef struct lv_table lv_table; /* opaque, immutable once created */

typedef enum lv_interp {
    LV_INTERP_LINEAR = 0, /* multilinear: exact for a + b x + c y + d x y; C0 */
    LV_INTERP_PCHIP = 1   /* monotone cubic Hermite: 1-D C1; N-D monotone along every
                           * axis, exact on the grid, C0 (docs/tables.md) */
} lv_interp;

/* What happens when a coordinate lies outside [first, last] breakpoint of its axis.
 * The zero value is ERROR, so a zero-initialised spec never extrapolates silently. */
typedef enum lv_extrap {
    LV_EXTRAP_ERROR = 0,  /* lv_table_eval() returns LV_ERR_INPUT naming axis, value, range */
    LV_EXTRAP_CLAMP = 1,  /* hold the end value (the coordinate is clamped to the range) */
    LV_EXTRAP_LINEAR = 2  /* continue with the end slope (LINEAR: the end cell's; PCHIP: the
                           * end derivative, so the result stays C1) */
} lv_extrap;

/* Arguments of lv_table_create(); everything is copied.
 * Values are stored row-major: the last axis varies fastest and the n_out outputs of one
 * grid point are adjacent:
 *     y[((i0 * n[1] + i1) * n[2] + i2) * n_out + k]     (3 axes, output k)
 * Names and units are optional (NULL: ""); they only serve messages and look-ups by name. */
typedef struct lv_table_spec {
    size_t n_dims;                          /* 1 .. LV_TABLE_MAX_DIMS */
    size_t n[LV_TABLE_MAX_DIMS];            /* breakpoints per axis, >= 2 */
    const double *x[LV_TABLE_MAX_DIMS];     /* x[d][0 .. n[d]-1], finite, strictly increasing */
    size_t n_out;                           /* outputs per grid point, >= 1 */
    const double *y;                        /* [n[0] * .. * n[n_dims-1] * n_out], finite */
    lv_interp interp;
    lv_extrap extrap;
    const char *name;                       /* "stage1_thrust"; used in error messages */
    const char *axis_name[LV_TABLE_MAX_DIMS];  /* "t", "mach", "alpha" */
    const char *axis_unit[LV_TABLE_MAX_DIMS];  /* "s", "1", "rad" */
    const char *const *out_name;            /* [n_out] or NULL: "y1", "y2", ... */
    const char *const *out_unit;            /* [n_out] or NULL */
} lv_table_spec;

/* Validates and copies `spec` into a new table (*out). LV_ERR_INPUT names the axis and
 * index of a non-increasing or non-finite breakpoint, the grid index of a non-finite value,
 * or the inconsistent size. lv_table_free(*out) when done. */
LV_API lv_status lv_table_create(const lv_table_spec *spec, lv_table **out, lv_err *err);
LV_API void lv_table_free(lv_table *tab); /* accepts NULL */

/* The interval last used on each axis: a hint, never needed for correctness (any content,
 * including one used with another table, gives the same results). Zero-initialise it. */
typedef struct lv_table_cursor {
    size_t i[LV_TABLE_MAX_DIMS];
} lv_table_cursor;
#define LV_TABLE_CURSOR_INIT { { 0 } }

/* A copy of `tab` whose outputs are y_k' = scale[k] * y_k + bias[k] (k < n_out; `scale` or
 * `bias` NULL: 1 or 0 for every output), with the same axes, names, interpolation and
 * extrapolation (PCHIP slopes are those of the new values). Used for table dispersions: a
 * thrust curve, an aerodynamic coefficient or a wind profile scaled or biased per run.
 * LV_ERR_INPUT for a non-finite factor; lv_table_free(*out) when done. */
LV_API lv_status lv_table_create_affine(const lv_table *tab, const double *scale,
                                        const double *bias, lv_table **out, lv_err *err);

/* y[0 .. n_out-1] = table at x[0 .. n_dims-1]. `cur` may be NULL (a fresh search).
 * Returns LV_OK, or LV_ERR_INPUT when a coordinate is NaN, or outside its axis under
 * LV_EXTRAP_ERROR ("table 'thrust': axis 0 't' [s] = 130 is outside [0, 120]"); the
 * message is formatted only on failure and only if err != NULL; y is then unchanged.
 * Hot path: no allocation, no names, no file. */
LV_API lv_status lv_table_eval(const lv_table *tab, lv_table_cursor *cur, const double *x,
                               double *y, lv_err *err);
/* The same for a 1-axis table: y[0 .. n_out-1] at x. */
LV_API lv_status lv_table_eval1(const lv_table *tab, lv_table_cursor *cur, double x, double *y,
                                lv_err *err);

/* Smallest breakpoint of axis `dim` strictly greater than x; INFINITY if none (or if dim
 * is out of range). With time as axis 0, a model schedules a time event at each kink:
 * t_next = lv_table_next_breakpoint(tab, 0, t). */
LV_API double lv_table_next_breakpoint(const lv_table *tab, size_t dim, double x);

LV_API size_t lv_table_n_dims(const lv_table *tab);
LV_API size_t lv_table_n_out(const lv_table *tab);
/* Breakpoints of axis `dim` (*n of them), owned by the table; NULL and *n = 0 if dim is
 * out of range. */
LV_API const double *lv_table_breakpoints(const lv_table *tab, size_t dim, size_t *n);
LV_API lv_interp lv_table_interp(const lv_table *tab);
LV_API lv_extrap lv_table_extrap(const lv_table *tab);
/* Names and units, owned by the table, never NULL ("" when unknown or out of range). */
LV_API const char *lv_table_name(const lv_table *tab);
LV_API const char *lv_table_axis_name(const lv_table *tab, size_t dim);
LV_API const char *lv_table_axis_unit(const lv_table *tab, size_t dim);
LV_API const char *lv_table_out_name(const lv_table *tab, size_t k);
LV_API const char *lv_table_out_unit(const lv_table *tab, size_t k);
/* Index of output `name` (resolve once, when a phase is built). LV_ERR_NOTFOUND lists the
 * nearest names. */
LV_API lv_status lv_table_out_index(const lv_table *tab, const char *name, size_t *k,
                                   lv_err *err);

/* Interpolation and extrapolation for the loaders (zero: LINEAR, ERROR, repeats refused). */
typedef struct lv_table_opts {
    lv_interp interp;
    lv_extrap extrap;
    int repeats_last;   /* CSV: 1: a row whose breakpoint equals the previous row's replaces
                           it (the last of the pair wins: lvsim's own result rows write an
                           event instant twice, before and after); 0: refused */
} lv_table_opts;

/* CSV, format detected from the first line that is not blank or a '#' comment:
 *  - 1-D: a header "t [s], thrust [N], mdot [kg/s]"; each row: breakpoint, n_out values.
 *  - 2-D grid (Modelica CombiTable2D layout): first row "mach [1] \ alpha [rad], a1, a2..",
 *    i.e. an optional label, then the axis-1 breakpoints; each further row: one axis-0
 *    breakpoint, then its values. One output, named after the file stem.
 * Errors name path:line:column (LV_ERR_IO: cannot read; LV_ERR_INPUT: bad content).
 * opts may be NULL (LINEAR, ERROR). */
LV_API lv_status lv_table_load_csv(const char *path, const lv_table_opts *opts,
                                   lv_table **out, lv_err *err);

/* MATLAB/Octave MAT file (v4, v5, v7 compressed, v7.3 HDF5; read by libmatio):
 *  - `var` alone, a real matrix [m x (1 + n_out)]: Modelica CombiTable1D/CombiTimeTable
 *    convention, first column the breakpoints, the others the outputs ("col2", "col3", ..).
 *  - `var` a 1 x 1 struct of named fields: the vector fields are the axes in field order,
 *    the arrays n1 x .. x nN the outputs (1-D: the first field is the axis); names = fields.
 *  - `var` with `var_x1` .. `var_xN`: N-D gridded, V(i1, .., iN) = f(x1(i1), .., xN(iN))
 *    (MATLAB ndgrid/interpn order), size [n1 .. nN] or [n1 .. nN n_out].
 * Double, single and integer classes are accepted (converted to double); complex, sparse,
 * cell and char variables are not. v7.3 variables that libmatio cannot classify (written by
 * other HDF5 writers, e.g. a null-padded MATLAB_class) are read with HDF5 (docs/tables.md).
 * A missing `var` gives LV_ERR_NOTFOUND with the nearest names in the file; an unreadable
 * file LV_ERR_IO. */
LV_API lv_status lv_table_load_mat(const char *path, const char *var, const lv_table_opts *opts,
                                   lv_table **out, lv_err *err);

/* A table file by its name: "*.mat" (any case) is read by lv_table_load_mat() and needs
 * `var`; anything else is CSV (lv_table_load_csv()) and `var` must be NULL. */
LV_API int lv_table_path_is_mat(const char *path);
LV_API lv_status lv_table_load(const char *path, const char *var, const lv_table_opts *opts,
                               lv_table **out, lv_err *err);

#ifdef __cplusplus
}
#endif
#endif
