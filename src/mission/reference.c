/* reference.c - a phase's `reference:`, an external optimiser's trajectory: parsing, the start
 * from its first row, the drift of the re-simulation from it (reference.h; the paper's sec. 4.2:
 * phases started "from the output vectors of previously simulated phases or the start values
 * of the trajectory optimization results for each phase", and Figure 10). Frames: geodetic
 * over the planet's ellipsoid, velocity relative to the rotating planet in NED
 * (docs/frames.md). */
#include "mission/reference.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/table_unit.h"
#include "lvsim/lv_units.h"

const char *const lv_ref_columns[LV_REF_N] = {"h", "lat", "lon", "v", "fpa", "heading", "m"};
static const char *const ref_alias[LV_REF_N][3] = {
    {"h", "altitude", NULL}, {"lat", NULL, NULL},         {"lon", NULL, NULL},
    {"v", "speed", "v_rel"}, {"fpa", NULL, NULL},         {"heading", "azimuth", "chi"},
    {"m", "mass", NULL}};
static const char *const ref_units[LV_REF_N] = {"m", "rad", "rad", "m/s", "rad", "rad", "kg"};

void lv_reference_free(lv_reference_def *r)
{
    if (r == NULL)
        return;
    lv_table_free(r->table);
    free(r->file);
    free(r->var);
    free(r);
}

/* The output of r->table that column j is, by any of its names: LV_OK, or LV_ERR_NOTFOUND;
 * *second: a second of its names also present (the first found in *k), else NULL. */
static lv_status find_column(const lv_table *t, size_t j, size_t *k, const char **first,
                             const char **second)
{
    size_t k2;
    lv_status st = LV_ERR_NOTFOUND;
    *second = NULL;
    for (int a = 0; a < 3 && ref_alias[j][a] != NULL; a++) {
        if (lv_table_out_index(t, ref_alias[j][a], st == LV_OK ? &k2 : k, NULL) != LV_OK)
            continue;
        if (st == LV_OK) {
            *second = ref_alias[j][a];
            break;
        }
        *first = ref_alias[j][a];
        st = LV_OK;
    }
    return st;
}

/* Each row's values possible (|lat|, |fpa| <= pi/2; lon, heading within [-2 pi, 2 pi]; v >= 0;
 * m > 0): LV_OK, or a message naming the row, its axis value and the column. */
static lv_status check_rows(const lv_reference_def *r, lv_err *err)
{
    static const double lim[LV_REF_N][2] = {
        {-HUGE_VAL, HUGE_VAL}, {-LV_PI / 2, LV_PI / 2}, {-2 * LV_PI, 2 * LV_PI}, {0.0, HUGE_VAL},
        {-LV_PI / 2, LV_PI / 2}, {-2 * LV_PI, 2 * LV_PI}, {0.0, HUGE_VAL}};
    static const char *const rule[LV_REF_N] = {
        "", "a latitude within [-pi/2, pi/2] rad (is it in degrees?)",
        "a longitude within a turn either way, [-2 pi, 2 pi] rad (is it in degrees?)",
        "a speed >= 0", "a flight-path angle within [-pi/2, pi/2] rad (is it in degrees?)",
        "a heading within a turn either way, [-2 pi, 2 pi] rad (is it in degrees?)", "a mass > 0"};
    size_t nb = 0;
    const double *b = lv_table_breakpoints(r->table, 0, &nb);
    double *buf = malloc(lv_table_n_out(r->table) * sizeof *buf);
    if (buf == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    lv_status st = LV_OK;
    for (size_t i = 0; i < nb && st == LV_OK; i++) {
        if ((st = lv_table_eval1(r->table, NULL, b[i], buf, err)) != LV_OK)
            break;
        for (size_t j = 1; j < LV_REF_N; j++) {
            const double x = buf[r->k[j]], tol = 1e-12 * (j == LV_REF_V ? 1.0 : 1.0 + lim[j][1]);
            const int bad = j == LV_REF_M ? !(x > 0.0)
                                          : !(x >= lim[j][0] - tol && x <= lim[j][1] + tol);
            if (bad) {
                st = lv_fail(err, LV_ERR_INPUT, "table '%s', data row %zu (%s = %.17g), column "
                             "'%s': %.17g is not %s", lv_table_name(r->table), i + 1,
                             lv_table_axis_name(r->table, 0), b[i],
                             lv_table_out_name(r->table, r->k[j]), x, rule[j]);
                break;
            }
        }
    }
    free(buf);
    return st;
}

lv_status lv_reference_parse(const lv_pctx *c, const lv_ynode *key, const lv_ynode *v,
                             lv_phase_def *ph)
{
    static const char *const rkeys[] = {"table", "start", NULL};
    static const char *const starts[] = {"parent", "reference", NULL};
    char what[LV_WHAT_MAX];
    lv_status st;
    if (v == NULL || lv_yaml_is_null(v))
        return LV_OK;
    snprintf(what, sizeof what, "phase '%s', reference", ph->name);
    lv_reference_def *r = calloc(1, sizeof *r);
    if (r == NULL)
        return lv_pk_nomem(c);
    ph->reference = r; /* freed with the phase */
    r->loc = lv_pk_loc(key);
    const lv_ynode *tab = v, *tab_key = key;
    if (v->kind == LV_YNODE_MAP) {
        if ((st = lv_pk_check_map(c, v, what, rkeys)) != LV_OK ||
            (st = lv_pk_need(c, v, what, "table", &tab)) != LV_OK)
            return st;
        tab_key = lv_pk_key(v, "table");
        const lv_ynode *s = lv_pk_get(v, "start");
        size_t i = 0;
        if (s != NULL && (st = lv_pk_enum(c, s, what, "start", starts, &i)) != LV_OK)
            return st;
        r->start = i == 1;
    }
    if ((st = lv_pk_table_traj(c, tab_key, tab, what, LV_EXTRAP_CLAMP, &r->file, &r->var,
                               &r->table)) != LV_OK)
        return st;
    const lv_table *t = r->table;
    const char *ax = lv_table_axis_name(t, 0);
    if (lv_table_n_dims(t) != 1)
        return lv_pk_fail(c, tab, "%s: table '%s' must have one axis, mission time (`time`, s) "
                          "or the normalised phase time (`tau`); it has %zu", what,
                          lv_table_name(t), lv_table_n_dims(t));
    r->over_tau = strcmp(ax, "tau") == 0;
    if (!r->over_tau && strcmp(ax, "time") != 0 && strcmp(ax, "t") != 0)
        return lv_pk_fail(c, tab, "%s: table '%s': its axis '%s' must be mission time (`time` or "
                          "`t`, s) or the normalised phase time (`tau`, from 0 at the phase's "
                          "start to 1 at its stop_time)", what, lv_table_name(t), ax);
    lv_err e = {LV_OK, ""};
    if ((st = lv_table_expect_unit(t, 1, 0, r->over_tau ? "1" : "s", NULL, &e)) != LV_OK)
        return lv_pk_fail(c, tab, "%s: %s", what, e.msg);
    char missing[160] = "";
    size_t used = 0;
    for (size_t j = 0; j < LV_REF_N; j++) {
        const char *first = NULL, *second = NULL;
        if (find_column(t, j, &r->k[j], &first, &second) == LV_OK && second != NULL)
            return lv_pk_fail(c, tab, "%s: table '%s' has both '%s' and '%s', two names of the "
                              "column %s: give it once", what, lv_table_name(t), first, second,
                              lv_ref_columns[j]);
        if (first == NULL) {
            used += (size_t)snprintf(missing + used, sizeof missing - used, "%s%s",
                                     used ? ", " : "", lv_ref_columns[j]);
            if (used >= sizeof missing)
                used = sizeof missing - 1;
            continue;
        }
        if ((st = lv_table_expect_unit(t, 0, r->k[j], ref_units[j], NULL, &e)) != LV_OK)
            return lv_pk_fail(c, tab, "%s: %s", what, e.msg);
    }
    if (used > 0)
        return lv_pk_fail(c, tab, "%s: table '%s' lacks the column%s %s (a reference gives h "
                          "[m], lat, lon [rad], v [m/s], fpa, heading [rad] and m [kg]; its first "
                          "output is '%s')", what, lv_table_name(t),
                          strchr(missing, ',') ? "s" : "", missing, lv_table_out_name(t, 0));
    size_t n = 0;
    const double *b = lv_table_breakpoints(t, 0, &n);
    /* tau within [0, 1], to round-off (an optimiser's 1 + 1e-15 is its 1) */
    if (r->over_tau && (b[0] < -1e-12 || b[n - 1] > 1.0 + 1e-12))
        return lv_pk_fail(c, tab, "%s: table '%s': tau runs from %.17g to %.17g; it must lie "
                          "within [0, 1] (to 1e-12)", what, lv_table_name(t), b[0], b[n - 1]);
    if ((st = check_rows(r, &e)) != LV_OK)
        return lv_pk_fail(c, tab, "%s: %s", what, e.msg);
    return LV_OK;
}

/* The reference's columns at axis value x (clamped into its range). */
static lv_status ref_eval(const lv_reference_def *r, lv_table_cursor *cur, double x,
                          double *buf, double s[LV_REF_N], lv_err *err)
{
    lv_status st = lv_table_eval1(r->table, cur, x, buf, err);
    for (size_t j = 0; st == LV_OK && j < LV_REF_N; j++)
        s[j] = buf[r->k[j]];
    return st;
}

double lv_reference_first(const lv_reference_def *r, size_t j)
{
    size_t nb = 0;
    const double *b = lv_table_breakpoints(r->table, 0, &nb);
    double *buf = malloc(lv_table_n_out(r->table) * sizeof *buf), v = NAN;
    if (buf != NULL && lv_table_eval1(r->table, NULL, b[0], buf, NULL) == LV_OK)
        v = buf[r->k[j]];
    free(buf);
    return v;
}

double lv_reference_start_time(const lv_reference_def *r)
{
    size_t nb = 0;
    if (r == NULL || !r->start || r->over_tau)
        return NAN;
    return lv_table_breakpoints(r->table, 0, &nb)[0];
}

lv_status lv_reference_check_span(const lv_reference_def *r, double t_start, double t_stop,
                                  lv_err *err)
{
    size_t nb = 0;
    const double *b = lv_table_breakpoints(r->table, 0, &nb);
    const double lo = b[0], hi = b[nb - 1];
    const char *tn = lv_table_name(r->table);
    if (r->over_tau) {
        if (r->start && lo > 1e-9)
            return lv_fail(err, LV_ERR_INPUT, "reference: table '%s' starts at tau = %.17g, "
                           "but start: reference starts the phase from its first row at tau = 0 "
                           "(the phase's start)", tn, lo);
        return LV_OK;
    }
    const double tol = 1e-9 * fmax(1.0, fabs(isnan(t_start) ? lo : t_start));
    if (isnan(t_start) && lo > t_stop + tol)
        return lv_fail(err, LV_ERR_INPUT, "reference: table '%s' covers t = %.9g .. %.9g s, no "
                       "part of the phase, which stops at t = %.9g s (its axis is mission time; "
                       "a reference over the phase's own time is `tau`)", tn, lo, hi, t_stop);
    if (!isnan(t_start) && (lo > t_stop + tol || hi < t_start - tol))
        return lv_fail(err, LV_ERR_INPUT, "reference: table '%s' covers t = %.9g .. %.9g s, no "
                       "part of the phase's t = %.9g .. %.9g s (its axis is mission time; a "
                       "reference over the phase's own time is `tau`)", tn, lo, hi, t_start,
                       t_stop);
    if (r->start && !isnan(t_start) && fabs(lo - t_start) > tol)
        return lv_fail(err, LV_ERR_INPUT, "reference: table '%s' starts at t = %.17g s, but the "
                       "phase starts at t = %.17g s: start: reference takes the state of its "
                       "first row at the phase's start (make start_time %.17g, or the table "
                       "start there)", tn, lo, t_start, lo);
    return LV_OK;
}

/* ECEF position and velocity relative to the planet of geodetic h, lat, lon and v, fpa,
 * heading. */
static void ref_ecef(const lv_planet *p, const double s[LV_REF_N], double r[3], double v[3])
{
    double ned[3], C[3][3];
    lv_frames_geodetic_to_ecef(p, s[LV_REF_LAT], s[LV_REF_LON], s[LV_REF_H], r);
    lv_frames_ned_from_fpa(s[LV_REF_V], s[LV_REF_FPA], s[LV_REF_HEADING], ned);
    lv_frames_C_ned_ecef(s[LV_REF_LAT], s[LV_REF_LON], C);
    for (int i = 0; i < 3; i++)
        v[i] = C[0][i] * ned[0] + C[1][i] * ned[1] + C[2][i] * ned[2];
}

/* Sets names[i] = value, appended when absent (cap: the room). */
static lv_status put(const char *name, double value, const char **names, double *values,
                     size_t *n, size_t cap, lv_err *err)
{
    for (size_t i = 0; i < *n; i++)
        if (strcmp(names[i], name) == 0) {
            values[i] = value;
            return LV_OK;
        }
    if (*n >= cap)
        return lv_fail(err, LV_ERR_INPUT, "reference start: no room for '%s'", name);
    names[*n] = name;
    values[(*n)++] = value;
    return LV_OK;
}

lv_status lv_reference_start(const lv_reference_def *r, const lv_planet *planet, double t0,
                             int root, const char *mass_state, const char **names,
                             double *values, size_t *n, size_t cap, lv_err *err)
{
    size_t nb = 0;
    const double *b = lv_table_breakpoints(r->table, 0, &nb);
    double *buf = malloc(lv_table_n_out(r->table) * sizeof *buf), s[LV_REF_N];
    if (buf == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    lv_status st = ref_eval(r, NULL, b[0], buf, s, err);
    free(buf);
    if (st != LV_OK)
        return st;
    if (!(s[LV_REF_M] > 0.0))
        return lv_fail(err, LV_ERR_INPUT, "reference: its first mass m = %g kg is not positive",
                       s[LV_REF_M]);
    if (root) {
        static const char *const pn[6] = {"start_lat", "start_lon", "start_h",
                                          "start_vel", "start_fpa", "start_chi"};
        const double pv[6] = {s[LV_REF_LAT], s[LV_REF_LON], s[LV_REF_H],
                              s[LV_REF_V],   s[LV_REF_FPA], s[LV_REF_HEADING]};
        for (int i = 0; i < 6 && st == LV_OK; i++)
            st = put(pn[i], pv[i], names, values, n, cap, err);
    } else {
        static const char *const rn[3] = {"r_eci_x", "r_eci_y", "r_eci_z"};
        static const char *const vn[3] = {"v_eci_x", "v_eci_y", "v_eci_z"};
        double r_ecef[3], v_ecef[3], r_eci[3], v_eci[3];
        ref_ecef(planet, s, r_ecef, v_ecef);
        lv_frames_ecef_to_eci(planet, t0, r_ecef, v_ecef, r_eci, v_eci);
        for (int i = 0; i < 3 && st == LV_OK; i++)
            if ((st = put(rn[i], r_eci[i], names, values, n, cap, err)) == LV_OK)
                st = put(vn[i], v_eci[i], names, values, n, cap, err);
    }
    return st == LV_OK ? put(mass_state, s[LV_REF_M], names, values, n, cap, err) : st;
}

/* The reference in ECEF at its breakpoints b[nb]: positions R and their derivatives along the
 * axis D = v_rel * dt/dx [nb][3] (the velocity relative to the rotating planet is the time
 * derivative of the ECEF position), and a table of the ECEF velocity over the same axis and
 * with the table's own interpolation (*vt). Cartesian: a longitude through +-pi, a heading
 * through north and a pass over a pole interpolate as smoothly as anything else. */
static lv_status ref_cartesian(const lv_reference_def *r, const lv_planet *planet, double dtdx,
                               double *R, double *D, lv_table **vt, lv_err *err)
{
    size_t nb = 0;
    const double *b = lv_table_breakpoints(r->table, 0, &nb);
    double *buf = malloc(lv_table_n_out(r->table) * sizeof *buf), *V = malloc(nb * 3 * sizeof *V);
    lv_status st = buf == NULL || V == NULL ? lv_fail(err, LV_ERR_NOMEM, "out of memory") : LV_OK;
    for (size_t i = 0; i < nb && st == LV_OK; i++) {
        double s[LV_REF_N];
        if ((st = ref_eval(r, NULL, b[i], buf, s, err)) != LV_OK) /* exact at a breakpoint */
            break;
        ref_ecef(planet, s, R + 3 * i, V + 3 * i);
        for (int a = 0; a < 3; a++)
            D[3 * i + a] = V[3 * i + a] * dtdx;
    }
    if (st == LV_OK) {
        static const char *const names[3] = {"v_x", "v_y", "v_z"};
        static const char *const units[3] = {"m/s", "m/s", "m/s"};
        const lv_table_spec spec = {.n_dims = 1, .n = {nb}, .x = {b}, .n_out = 3, .y = V,
                                    .interp = lv_table_interp(r->table),
                                    .extrap = LV_EXTRAP_CLAMP, .name = lv_table_name(r->table),
                                    .axis_name = {lv_table_axis_name(r->table, 0)},
                                    .out_name = names, .out_unit = units};
        st = lv_table_create(&spec, vt, err);
    }
    free(buf);
    free(V);
    return st;
}

/* The cubic Hermite interpolant of the positions R with derivatives D at the breakpoints
 * b[nb] (ref_cartesian), at x within [b[0], b[nb-1]] (a little beyond: the end interval's
 * cubic): exact for a trajectory whose position is a cubic in x between two rows; *i a hint of
 * the interval (rows in order: no search). */
static void hermite(const double *b, size_t nb, const double *R, const double *D, double x,
                    size_t *i, double out[3])
{
    while (*i + 2 < nb && x > b[*i + 1])
        ++*i;
    while (*i > 0 && x < b[*i])
        --*i;
    const size_t j = *i;
    const double h = b[j + 1] - b[j], u = (x - b[j]) / h; /* (just) beyond an end: extrapolated */
    const double u2 = u * u, u3 = u2 * u;
    const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = 3 * u2 - 2 * u3,
                 h11 = u3 - u2;
    for (int a = 0; a < 3; a++)
        out[a] = h00 * R[3 * j + a] + h10 * h * D[3 * j + a] + h01 * R[3 * (j + 1) + a] +
                 h11 * h * D[3 * (j + 1) + a];
}

lv_status lv_reference_drift(const lv_reference_def *r, const lv_planet *planet,
                             const lv_result *rows, const char *mass_state, double t_start,
                             double t_stop, lv_ref_drift *out, lv_ref_row **series,
                             lv_err *err)
{
    static const char *const need[] = {"time", "h", "lat", "lon", "v_north", "v_east", "v_down"};
    size_t col[8];
    lv_status st;
    memset(out, 0, sizeof *out);
    out->over_tau = r->over_tau;
    out->start_from_reference = r->start;
    out->t_first = out->t_final = out->pos_max_t = out->vel_max_t = out->mass_max_t = NAN;
    out->pos_final = out->vel_final = out->mass_final = NAN;
    out->ref_end = out->phase_end = NAN;
    *series = NULL;
    for (size_t j = 0; j < 8; j++)
        if ((st = lv_result_column(rows, j < 7 ? need[j] : mass_state, &col[j], err)) != LV_OK)
            return lv_fail_prefix(err, st, "reference drift");
    size_t nb = 0;
    const double *b = lv_table_breakpoints(r->table, 0, &nb);
    /* a row just beyond either end is compared: an event-located phase end next to the
     * optimiser's final time (1e-6 of the span) */
    const double lo = b[0], hi = b[nb - 1];
    const double eps = 1e-9 * (1.0 + fmax(fabs(lo), fabs(hi))) + 1e-6 * (hi - lo);
    const size_t nr = lv_result_rows(rows);
    out->ref_end = hi;
    out->phase_end = NAN;
    if (nr > 0) {
        const double te = lv_result_value(rows, nr - 1, col[0]);
        out->phase_end = r->over_tau ? (te - t_start) / (t_stop - t_start) : te;
    }
    double *buf = malloc(lv_table_n_out(r->table) * sizeof *buf);
    double *R = malloc(nb * 6 * sizeof *R), *D = R != NULL ? R + 3 * nb : NULL;
    lv_ref_row *ser = malloc((nr + 1) * sizeof *ser);
    lv_table *vt = NULL;
    if (buf == NULL || ser == NULL || R == NULL) {
        free(buf);
        free(ser);
        free(R);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    st = ref_cartesian(r, planet, r->over_tau ? t_stop - t_start : 1.0, R, D, &vt, err);
    lv_table_cursor cur = LV_TABLE_CURSOR_INIT, vcur = LV_TABLE_CURSOR_INIT;
    size_t hint = 0;
    for (size_t i = 0; i < nr && st == LV_OK; i++) {
        double y[8];
        for (size_t j = 0; j < 8; j++)
            y[j] = lv_result_value(rows, i, col[j]);
        const double t = y[0], x = r->over_tau ? (t - t_start) / (t_stop - t_start) : t;
        if (!(x >= lo - eps && x <= hi + eps))
            continue;
        const double xc = fmin(fmax(x, lo), hi);
        double s[LV_REF_N], rr[3], vr[3], rs[3], vs[3], C[3][3];
        if ((st = ref_eval(r, &cur, xc, buf, s, err)) != LV_OK ||
            (st = lv_table_eval1(vt, &vcur, xc, vr, err)) != LV_OK)
            break;
        hermite(b, nb, R, D, x, &hint, rr);
        lv_frames_geodetic_to_ecef(planet, y[2], y[3], y[1], rs);
        lv_frames_C_ned_ecef(y[2], y[3], C);
        for (int a = 0; a < 3; a++)
            vs[a] = C[0][a] * y[4] + C[1][a] * y[5] + C[2][a] * y[6];
        const double dp = hypot(hypot(rs[0] - rr[0], rs[1] - rr[1]), rs[2] - rr[2]);
        const double dv = hypot(hypot(vs[0] - vr[0], vs[1] - vr[1]), vs[2] - vr[2]);
        const double dm = fabs(y[7] - s[LV_REF_M]);
        const double v_sim = sqrt(y[4] * y[4] + y[5] * y[5] + y[6] * y[6]);
        ser[out->n_rows] = (lv_ref_row){t,         y[1],        s[LV_REF_H], v_sim, s[LV_REF_V],
                                        y[7],      s[LV_REF_M], dp,          dv,    dm};
        if (out->n_rows++ == 0)
            out->t_first = t;
        if (out->n_rows == 1 || dp > out->pos_max) {
            out->pos_max = dp;
            out->pos_max_t = t;
        }
        if (out->n_rows == 1 || dv > out->vel_max) {
            out->vel_max = dv;
            out->vel_max_t = t;
        }
        if (out->n_rows == 1 || dm > out->mass_max) {
            out->mass_max = dm;
            out->mass_max_t = t;
        }
        out->t_final = t;
        out->pos_final = dp;
        out->vel_final = dv;
        out->mass_final = dm;
    }
    free(buf);
    free(R);
    lv_table_free(vt);
    if (out->n_rows == 0)
        out->pos_max = out->vel_max = out->mass_max = NAN;
    if (st == LV_OK && out->n_rows > 0)
        *series = ser;
    else
        free(ser);
    return st;
}
