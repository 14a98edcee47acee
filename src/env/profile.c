/* profile.c - atmosphere and wind profiles from a file: the profile CSV (read by the table
 * loader, io/table_load.c) and the University of Wyoming sounding text list (TEXT:LIST, its
 * own reader below), both into levels over geometric altitude in SI units. Geopotential
 * heights are converted with US76 eq. (18), z = r0 H / (r0 - H); the missing one of T, p, rho
 * comes from the ideal-gas law with the dry-air gas constant R* / M0. docs/atmosphere.md,
 * "Profiles". */
#include "env/profile.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/names.h"
#include "io/numparse.h"
#include "io/readfile.h"
#include "io/table_load.h"
#include "lvsim/lv_atmosphere.h"

#define KNOT (1852.0 / 3600.0) /* m/s, the international knot */
#define DEG (3.14159265358979323846 / 180.0)
#define T_ZERO_C 273.15        /* K */

void lv_profile_clear(lv_profile *p)
{
    if (p == NULL)
        return;
    free(p->z_t);
    free(p->T);
    free(p->p);
    free(p->rho);
    free(p->z_w);
    free(p->north);
    free(p->east);
    memset(p, 0, sizeof *p);
}

static double geometric(double H)
{
    return LV_PROFILE_R0 * H / (LV_PROFILE_R0 - H);
}

static int alloc_levels(lv_profile *p, size_t n)
{
    const size_t sz = (n > 0 ? n : 1) * sizeof(double);
    p->z_t = malloc(sz);
    p->T = malloc(sz);
    p->p = malloc(sz);
    p->rho = malloc(sz);
    p->z_w = malloc(sz);
    p->north = malloc(sz);
    p->east = malloc(sz);
    return p->z_t && p->T && p->p && p->rho && p->z_w && p->north && p->east;
}

/* ---- where a CSV field is ----------------------------------------------------------------- */

static int blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r';
}

/* Line and column (1-based) of field `f` of the k-th line with content (0: the header, 1: the
 * first data row), counted as the table loader counts them (blank and '#' lines skipped). */
static void csv_where(const char *text, size_t k, size_t f, size_t *line, size_t *col)
{
    const char *s = text;
    size_t ln = 1, seen = 0;
    *line = *col = 0;
    while (*s != '\0') {
        const char *eol = strchr(s, '\n');
        const char *end = eol != NULL ? eol : s + strlen(s);
        const char *hash = memchr(s, '#', (size_t)(end - s));
        const char *stop = hash != NULL ? hash : end;
        const char *q = s;
        while (q < stop && blank(*q))
            q++;
        if (q < stop && seen++ == k) {
            const char *a = s;
            for (size_t j = 0; j < f; j++) {
                const char *comma = memchr(a, ',', (size_t)(stop - a));
                if (comma == NULL)
                    break;
                a = comma + 1;
            }
            while (a < stop && blank(*a))
                a++;
            *line = ln;
            *col = (size_t)(a - s) + 1;
            return;
        }
        if (eol == NULL)
            break;
        s = eol + 1;
        ln++;
    }
}

/* ---- the profile CSV ---------------------------------------------------------------------- */

enum pcol { P_T, P_P, P_RHO, P_SPEED, P_DIR, P_NORTH, P_EAST, P_N };
static const char *const PCOL_NAME[P_N] = { "T", "p", "rho", "speed", "direction", "north",
                                            "east" };

typedef struct unit_conv {
    const char *unit;
    double scale, offset; /* SI = scale * value + offset */
} unit_conv;

static const unit_conv U_ALT[] = { { "m", 1.0, 0.0 }, { "km", 1000.0, 0.0 }, { NULL, 0, 0 } };
static const unit_conv U_GPH[] = { { "m", 1.0, 0.0 }, { "gpm", 1.0, 0.0 }, { "km", 1000.0, 0.0 },
                                   { NULL, 0, 0 } };
static const unit_conv U_T[] = { { "K", 1.0, 0.0 }, { "degC", 1.0, T_ZERO_C },
                                 { "C", 1.0, T_ZERO_C }, { NULL, 0, 0 } };
static const unit_conv U_P[] = { { "Pa", 1.0, 0.0 }, { "hPa", 100.0, 0.0 },
                                 { "mbar", 100.0, 0.0 }, { "kPa", 1000.0, 0.0 }, { NULL, 0, 0 } };
static const unit_conv U_RHO[] = { { "kg/m3", 1.0, 0.0 }, { "kg/m^3", 1.0, 0.0 },
                                   { NULL, 0, 0 } };
static const unit_conv U_V[] = { { "m/s", 1.0, 0.0 }, { "knot", KNOT, 0.0 }, { "kt", KNOT, 0.0 },
                                 { "km/h", 1.0 / 3.6, 0.0 }, { NULL, 0, 0 } };
static const unit_conv U_DIR[] = { { "deg", 1.0, 0.0 }, { NULL, 0, 0 } };
static const unit_conv *const PCOL_UNITS[P_N] = { U_T, U_P, U_RHO, U_V, U_DIR, U_V, U_V };

static const unit_conv *find_unit(const unit_conv *u, const char *unit)
{
    for (; u->unit != NULL; u++)
        if (strcmp(u->unit, unit) == 0)
            return u;
    return NULL;
}

static void unit_list(const unit_conv *u, char *buf, size_t cap)
{
    size_t len = 0;
    buf[0] = '\0';
    for (; u->unit != NULL && len + 1 < cap; u++) {
        int w = snprintf(buf + len, cap - len, "%s'%s'", len > 0 ? ", " : "", u->unit);
        if (w < 0)
            break;
        len += (size_t)w;
    }
}

typedef struct csv_load {
    const char *path, *text;
    lv_profile *out;
} csv_load;

static lv_status csv_fail_at(const csv_load *cl, size_t k, size_t f, lv_err *err,
                             const char *msg)
{
    size_t line, col;
    csv_where(cl->text, k, f, &line, &col);
    return lv_fail(err, LV_ERR_INPUT, "%s:%zu:%zu: %s", cl->path, line, col, msg);
}

static lv_status csv_from_spec(const lv_table_spec *sp, void *user, lv_err *err)
{
    csv_load *cl = user;
    lv_profile *pr = cl->out;
    char msg[512], units[128];
    if (sp->n_dims != 1)
        return lv_fail(err, LV_ERR_INPUT, "%s: a profile has one axis (altitude), this one has "
                       "%zu", cl->path, sp->n_dims);
    /* the altitude: h (geometric) or gph (geopotential height) */
    const char *an = sp->axis_name[0] != NULL ? sp->axis_name[0] : "";
    const char *au = sp->axis_unit[0] != NULL ? sp->axis_unit[0] : "";
    const int gph = strcmp(an, "gph") == 0;
    if (!gph && strcmp(an, "h") != 0) {
        snprintf(msg, sizeof msg, "profile: the first column is the altitude, 'h [m]' "
                 "(geometric) or 'gph [m]' (geopotential height), not '%.60s'", an);
        return csv_fail_at(cl, 0, 0, err, msg);
    }
    const unit_conv *ua = find_unit(gph ? U_GPH : U_ALT, au);
    if (ua == NULL) {
        unit_list(gph ? U_GPH : U_ALT, units, sizeof units);
        snprintf(msg, sizeof msg, "profile: column '%s' has %s'%.40s'; a profile gives every "
                 "unit, here one of %s", an, au[0] ? "unit " : "no unit ", au, units);
        return csv_fail_at(cl, 0, 0, err, msg);
    }
    size_t k[P_N];
    const unit_conv *uc[P_N] = { NULL };
    for (size_t c = 0; c < P_N; c++)
        k[c] = (size_t)-1;
    for (size_t j = 0; j < sp->n_out; j++) {
        const char *nm = sp->out_name != NULL && sp->out_name[j] ? sp->out_name[j] : "";
        const char *u = sp->out_unit != NULL && sp->out_unit[j] ? sp->out_unit[j] : "";
        size_t c = 0;
        while (c < P_N && strcmp(nm, PCOL_NAME[c]) != 0)
            c++;
        if (c == P_N) {
            lv_suggest sg;
            char hint[128];
            lv_suggest_init(&sg, nm);
            for (size_t i = 0; i < P_N; i++)
                lv_suggest_add(&sg, PCOL_NAME[i]);
            lv_suggest_text(&sg, hint, sizeof hint);
            snprintf(msg, sizeof msg, "profile: unknown column '%.60s'%s (columns: T, p, rho, "
                     "speed, direction, north, east)", nm, hint);
            return csv_fail_at(cl, 0, j + 1, err, msg);
        }
        if (k[c] != (size_t)-1) {
            snprintf(msg, sizeof msg, "profile: a second column '%s'", nm);
            return csv_fail_at(cl, 0, j + 1, err, msg);
        }
        if ((uc[c] = find_unit(PCOL_UNITS[c], u)) == NULL) {
            unit_list(PCOL_UNITS[c], units, sizeof units);
            snprintf(msg, sizeof msg, "profile: column '%s' has %s'%.40s'; a profile gives every "
                     "unit, here one of %s", nm, u[0] ? "unit " : "no unit ", u, units);
            return csv_fail_at(cl, 0, j + 1, err, msg);
        }
        k[c] = j;
    }
    const int n_thermo = (k[P_T] != (size_t)-1) + (k[P_P] != (size_t)-1) +
                         (k[P_RHO] != (size_t)-1);
    const int polar = k[P_SPEED] != (size_t)-1 || k[P_DIR] != (size_t)-1;
    const int ned = k[P_NORTH] != (size_t)-1 || k[P_EAST] != (size_t)-1;
    if (n_thermo == 1)
        return csv_fail_at(cl, 0, 0, err, "profile: one of T, p, rho is not enough: give two "
                           "(the third follows from p = rho R T) or all three");
    if (polar && ned)
        return csv_fail_at(cl, 0, 0, err, "profile: give the wind either as speed and "
                           "direction or as north and east components, not both");
    if ((polar && (k[P_SPEED] == (size_t)-1 || k[P_DIR] == (size_t)-1)) ||
        (ned && (k[P_NORTH] == (size_t)-1 || k[P_EAST] == (size_t)-1)))
        return csv_fail_at(cl, 0, 0, err, polar ? "profile: a wind speed column needs a "
                           "direction column and the other way round" : "profile: the wind "
                           "needs both 'north' and 'east'");
    if (n_thermo == 0 && !polar && !ned)
        return csv_fail_at(cl, 0, 0, err, "profile: no columns after the altitude; give two or "
                           "three of T, p, rho and/or the wind (speed, direction or north, east)");
    const size_t n = sp->n[0];
    if (n < 2)
        return lv_fail(err, LV_ERR_INPUT, "%s: a profile needs at least two levels, this one has "
                       "%zu", cl->path, n);
    if (!alloc_levels(pr, n))
        return lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", cl->path);
    for (size_t i = 0; i < n; i++) {
        const double *row = sp->y + i * sp->n_out;
        double z = ua->scale * sp->x[0][i];
        if (gph) {
            if (!(z < 0.5 * LV_PROFILE_R0)) /* eq. (18) inverted needs H < r0 */
                return csv_fail_at(cl, i + 1, 0, err, "profile: geopotential height beyond any "
                                   "atmosphere");
            z = geometric(z);
        }
        if (z < LV_ATMO_ALT_MIN) {
            snprintf(msg, sizeof msg, "profile: level at %.9g m is below the surface: the "
                     "atmosphere models start at %.9g m", z, LV_ATMO_ALT_MIN);
            return csv_fail_at(cl, i + 1, 0, err, msg);
        }
        double v[P_N];
        for (size_t c = 0; c < P_N; c++)
            v[c] = k[c] != (size_t)-1 ? uc[c]->scale * row[k[c]] + uc[c]->offset : NAN;
        for (size_t c = P_T; c <= P_RHO; c++)
            if (k[c] != (size_t)-1 && !(v[c] > 0.0)) {
                snprintf(msg, sizeof msg, "profile: %s = %.9g %s must be positive", PCOL_NAME[c],
                         row[k[c]], uc[c]->unit);
                return csv_fail_at(cl, i + 1, k[c] + 1, err, msg);
            }
        if (polar) {
            if (!(v[P_SPEED] >= 0.0)) {
                snprintf(msg, sizeof msg, "profile: wind speed %.9g must not be negative",
                         row[k[P_SPEED]]);
                return csv_fail_at(cl, i + 1, k[P_SPEED] + 1, err, msg);
            }
            if (!(v[P_DIR] >= 0.0 && v[P_DIR] <= 360.0)) {
                snprintf(msg, sizeof msg, "profile: wind direction %.9g deg is outside [0, 360]",
                         v[P_DIR]);
                return csv_fail_at(cl, i + 1, k[P_DIR] + 1, err, msg);
            }
            /* meteorological: the direction the wind blows FROM, clockwise from north */
            v[P_NORTH] = -v[P_SPEED] * cos(v[P_DIR] * DEG);
            v[P_EAST] = -v[P_SPEED] * sin(v[P_DIR] * DEG);
        }
        if (n_thermo >= 2) {
            if (k[P_T] == (size_t)-1)
                v[P_T] = v[P_P] / (v[P_RHO] * LV_PROFILE_R_AIR);
            else if (k[P_P] == (size_t)-1)
                v[P_P] = v[P_RHO] * LV_PROFILE_R_AIR * v[P_T];
            else if (k[P_RHO] == (size_t)-1)
                v[P_RHO] = v[P_P] / (LV_PROFILE_R_AIR * v[P_T]);
            pr->z_t[i] = z;
            pr->T[i] = v[P_T];
            pr->p[i] = v[P_P];
            pr->rho[i] = v[P_RHO];
        }
        if (polar || ned) {
            pr->z_w[i] = z;
            pr->north[i] = v[P_NORTH];
            pr->east[i] = v[P_EAST];
        }
    }
    pr->n_t = n_thermo >= 2 ? n : 0;
    pr->n_w = polar || ned ? n : 0;
    return LV_OK;
}

/* ---- the University of Wyoming sounding text list ----------------------------------------- */

/* Its own reader, not the CSV loader: the text list is fixed-width (7 characters a column,
 * names right-aligned over their fields), not comma-separated, and its cells are blank where
 * a quantity was not reported (dew point above the humidity sensor's range, winds at
 * temperature-only levels), which the table loader rightly refuses. Layout (the archive's
 * column description, weather.uwyo.edu/upperair/columns.html):
 *
 *     -----------------------------------------------------------------------------
 *        PRES   HGHT   TEMP   DWPT   RELH   MIXR   DRCT   SKNT   THTA   THTE   THTV
 *         hPa     m      C      C      %    g/kg    deg   knot     K      K      K
 *     -----------------------------------------------------------------------------
 *      1000.0    102   14.2   11.9     86   8.78    140      6  287.4  312.0  289.0
 *
 * HGHT is the geopotential height. Rows end at the first line that is not a row of numbers
 * ("Station information and sounding indices", "</PRE>", a blank line); the station block's
 * "Station elevation: 14.0" is the surface. */

enum wcol { W_PRES, W_HGHT, W_TEMP, W_DRCT, W_SKNT, W_NCOL };
static const char *const WCOL_NAME[W_NCOL] = { "PRES", "HGHT", "TEMP", "DRCT", "SKNT" };
static const char *const WCOL_UNIT[W_NCOL] = { "hPa", "m", "C", "deg", "knot" };

typedef struct wline {
    const char *s;
    size_t len, no; /* text, length without '\r', 1-based line number */
} wline;

static int next_wline(const char **pos, size_t *no, wline *l)
{
    if (**pos == '\0')
        return 0;
    const char *s = *pos, *eol = strchr(s, '\n');
    size_t len = eol != NULL ? (size_t)(eol - s) : strlen(s);
    *pos = eol != NULL ? eol + 1 : s + len;
    l->s = s;
    l->no = ++*no;
    while (len > 0 && s[len - 1] == '\r')
        len--;
    l->len = len;
    return 1;
}

/* The i-th blank-separated token of a line: [*a, *b); 0 if there is none. */
static int token(const wline *l, size_t i, size_t *a, size_t *b)
{
    size_t p = 0;
    for (size_t t = 0;; t++) {
        while (p < l->len && (l->s[p] == ' ' || l->s[p] == '\t'))
            p++;
        if (p == l->len)
            return 0;
        const size_t q0 = p;
        while (p < l->len && l->s[p] != ' ' && l->s[p] != '\t')
            p++;
        if (t == i) {
            *a = q0;
            *b = p;
            return 1;
        }
    }
}

static int token_is(const wline *l, size_t i, const char *w)
{
    size_t a, b;
    return token(l, i, &a, &b) && b - a == strlen(w) && memcmp(l->s + a, w, b - a) == 0;
}

static int is_sounding_header(const wline *l)
{
    return token_is(l, 0, "PRES") && token_is(l, 1, "HGHT");
}

static int is_sounding(const char *text)
{
    const char *pos = text;
    size_t no = 0;
    wline l;
    while (next_wline(&pos, &no, &l))
        if (is_sounding_header(&l))
            return 1;
    return 0;
}

static lv_status sounding_load(const char *path, const char *text, lv_profile *pr, lv_err *err)
{
    const char *pos = text;
    size_t no = 0;
    wline l, hdr = { 0 }, units;
    while (next_wline(&pos, &no, &l))
        if (is_sounding_header(&l)) {
            hdr = l;
            break;
        }
    /* field j spans (end of name j-1, end of name j]: the names are right-aligned */
    size_t lo[W_NCOL], hi[W_NCOL], ucol[W_NCOL];
    int found[W_NCOL] = { 0 };
    size_t a, b, prev_end = 0;
    for (size_t t = 0; token(&hdr, t, &a, &b); t++) {
        for (size_t c = 0; c < W_NCOL; c++)
            if (b - a == strlen(WCOL_NAME[c]) && memcmp(hdr.s + a, WCOL_NAME[c], b - a) == 0) {
                found[c] = 1;
                lo[c] = prev_end;
                hi[c] = b;
                ucol[c] = t;
            }
        prev_end = b;
    }
    for (size_t c = 0; c < W_NCOL; c++)
        if (!found[c])
            return lv_fail(err, LV_ERR_INPUT, "%s:%zu:1: sounding: no column %s in the header "
                           "(the text list needs PRES, HGHT, TEMP, DRCT, SKNT)", path, hdr.no,
                           WCOL_NAME[c]);
    if (!next_wline(&pos, &no, &units))
        return lv_fail(err, LV_ERR_INPUT, "%s:%zu: sounding: the units line is missing", path,
                       no + 1);
    for (size_t c = 0; c < W_NCOL; c++) {
        if (!token(&units, ucol[c], &a, &b))
            return lv_fail(err, LV_ERR_INPUT, "%s:%zu:%zu: sounding: no unit for %s (expected "
                           "'%s')", path, units.no, units.len + 1, WCOL_NAME[c], WCOL_UNIT[c]);
        if (b - a != strlen(WCOL_UNIT[c]) || memcmp(units.s + a, WCOL_UNIT[c], b - a) != 0)
            return lv_fail(err, LV_ERR_INPUT, "%s:%zu:%zu: sounding: %s in '%.*s'; the text list "
                           "gives it in '%s'", path, units.no, a + 1, WCOL_NAME[c],
                           (int)(b - a > 20 ? 20 : b - a), units.s + a, WCOL_UNIT[c]);
    }
    /* the station elevation, when the file has the station block */
    double elev = NAN;
    const char *se = strstr(pos, "Station elevation:");
    if (se != NULL) {
        char *end;
        const double e = strtod(se + strlen("Station elevation:"), &end);
        if (end != se + strlen("Station elevation:") && isfinite(e))
            elev = e;
    }
    /* rows: after the dashed line under the units */
    const char *rows = pos;
    size_t rows_no = no;
    if (next_wline(&pos, &no, &l) && l.len > 0 && l.s[0] == '-') {
        rows = pos; /* else the rows start right under the units */
        rows_no = no;
    }
    size_t cap = 0;
    for (const char *s = rows; *s != '\0'; s++)
        cap += *s == '\n';
    if (!alloc_levels(pr, cap + 1))
        return lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", path);
    pos = rows;
    no = rows_no;
    double H_prev = -INFINITY;
    size_t line_prev = 0;
    while (next_wline(&pos, &no, &l)) {
        size_t p = 0;
        while (p < l.len && l.s[p] == ' ')
            p++;
        if (p == l.len || !(l.s[p] == '-' || l.s[p] == '.' || (l.s[p] >= '0' && l.s[p] <= '9')))
            break; /* the end of the rows */
        double v[W_NCOL];
        int have[W_NCOL];
        for (size_t c = 0; c < W_NCOL; c++) {
            size_t f0 = lo[c] < l.len ? lo[c] : l.len, f1 = hi[c] < l.len ? hi[c] : l.len;
            while (f0 < f1 && l.s[f0] == ' ')
                f0++;
            while (f1 > f0 && l.s[f1 - 1] == ' ')
                f1--;
            have[c] = f1 > f0;
            if (have[c] && lv_numparse_field(l.s + f0, f1 - f0, &v[c]) != 0)
                return lv_fail(err, LV_ERR_INPUT, "%s:%zu:%zu: sounding: %s: expected a finite "
                               "number, found '%.*s'", path, l.no, f0 + 1, WCOL_NAME[c],
                               (int)(f1 - f0 > 20 ? 20 : f1 - f0), l.s + f0);
        }
        for (size_t c = W_PRES; c <= W_HGHT; c++)
            if (!have[c])
                return lv_fail(err, LV_ERR_INPUT, "%s:%zu:%zu: sounding: %s is missing (a gap in "
                               "the list: every row needs PRES and HGHT)", path, l.no, lo[c] + 1,
                               WCOL_NAME[c]);
        const double H = v[W_HGHT];
        if (!(H > H_prev))
            return lv_fail(err, LV_ERR_INPUT, "%s:%zu:%zu: sounding: HGHT %.9g m is not above the "
                           "previous row's %.9g m (line %zu); heights must increase", path, l.no,
                           lo[W_HGHT] + 1, H, H_prev, line_prev);
        H_prev = H;
        line_prev = l.no;
        const int thermo = have[W_TEMP], wind = have[W_DRCT] && have[W_SKNT];
        if (!thermo && !wind)
            continue; /* a mandatory level the archive lists with its height only */
        if (isfinite(elev) && H < elev)
            return lv_fail(err, LV_ERR_INPUT, "%s:%zu:%zu: sounding: a level at %.9g m, below "
                           "the surface (station elevation %.9g m)", path, l.no, lo[W_HGHT] + 1,
                           H, elev);
        if (!(v[W_PRES] > 0.0))
            return lv_fail(err, LV_ERR_INPUT, "%s:%zu:%zu: sounding: PRES %.9g hPa must be "
                           "positive", path, l.no, lo[W_PRES] + 1, v[W_PRES]);
        if (!(H < 0.5 * LV_PROFILE_R0) || geometric(H) < LV_ATMO_ALT_MIN)
            return lv_fail(err, LV_ERR_INPUT, "%s:%zu:%zu: sounding: HGHT %.9g m is outside the "
                           "atmosphere models' %.9g m to %.9g m", path, l.no, lo[W_HGHT] + 1, H,
                           LV_ATMO_ALT_MIN, LV_ATMO_ALT_MAX);
        const double z = geometric(H);
        if (thermo) {
            const double T = v[W_TEMP] + T_ZERO_C, pp = 100.0 * v[W_PRES];
            if (!(T > 0.0))
                return lv_fail(err, LV_ERR_INPUT, "%s:%zu:%zu: sounding: TEMP %.9g C is below "
                               "absolute zero", path, l.no, lo[W_TEMP] + 1, v[W_TEMP]);
            pr->z_t[pr->n_t] = z;
            pr->T[pr->n_t] = T;
            pr->p[pr->n_t] = pp;
            pr->rho[pr->n_t] = pp / (LV_PROFILE_R_AIR * T); /* dry air: humidity ignored */
            pr->n_t++;
        }
        if (wind) {
            if (!(v[W_SKNT] >= 0.0) || !(v[W_DRCT] >= 0.0 && v[W_DRCT] <= 360.0))
                return lv_fail(err, LV_ERR_INPUT, "%s:%zu:%zu: sounding: wind %.9g deg, %.9g knot: "
                               "the direction must be in [0, 360], the speed not negative", path,
                               l.no, lo[W_DRCT] + 1, v[W_DRCT], v[W_SKNT]);
            const double V = v[W_SKNT] * KNOT, d = v[W_DRCT] * DEG;
            pr->z_w[pr->n_w] = z;
            pr->north[pr->n_w] = -V * cos(d); /* DRCT: where the wind comes from */
            pr->east[pr->n_w] = -V * sin(d);
            pr->n_w++;
        }
    }
    if (pr->n_t < 2 && pr->n_w < 2)
        return lv_fail(err, LV_ERR_INPUT, "%s:%zu: sounding: fewer than two levels with a "
                       "temperature or a wind", path, hdr.no);
    if (pr->n_t < 2)
        pr->n_t = 0;
    if (pr->n_w < 2)
        pr->n_w = 0;
    return LV_OK;
}

lv_status lv_profile_load(const char *path, lv_profile *out, lv_err *err)
{
    memset(out, 0, sizeof *out);
    if (path == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_profile_load: NULL path");
    snprintf(out->src, sizeof out->src, "%s", path);
    char *text = NULL;
    size_t len = 0;
    lv_status st = lv_read_file(path, LV_TABLE_FILE_MAX, "the profile", &text, &len, err);
    if (st != LV_OK)
        return st;
    if (strlen(text) != len) {
        st = lv_fail(err, LV_ERR_INPUT, "%s: a NUL byte: not a text file", path);
    } else if (is_sounding(text)) {
        st = sounding_load(path, text, out, err);
    } else {
        csv_load cl = { path, text, out };
        st = lv_table_load_spec(path, NULL, NULL, csv_from_spec, &cl, err);
    }
    free(text);
    if (st != LV_OK) {
        char src[sizeof out->src];
        memcpy(src, out->src, sizeof src);
        lv_profile_clear(out);
        memcpy(out->src, src, sizeof src);
    }
    return st;
}
