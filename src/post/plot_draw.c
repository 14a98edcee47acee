/* plot_draw.c - the figures of a run, drawn with PLplot's cairo drivers (pngcairo, svgcairo):
 * quantities against time with every body's phases joined and the phase starts marked, the
 * ground track over PLplot's coastlines, and the paper's Figure 10 (speed and mass normalised).
 *
 * PLplot keeps global state (a table of streams and the current one): each figure makes its
 * own stream (plmkstrm), reports errors into it (plsError) instead of stderr, and ends it
 * (plend1); the caller's current stream is restored. Not thread-safe; never used by a run. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <plplot.h>
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>
#ifdef __linux__
#include <signal.h>
#include <sys/prctl.h>
#endif

#include "core/status.h"
#include "io/atomic.h"
#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_units.h"
#include "post/plot.h"

#define PAGE_W 1000 /* px (PNG) or pt (SVG) */
#define PAGE_H 700
#define RAD2DEG (1.0 / LV_DEG) /* degrees per rad, for the axes */
#define VP_X0 0.11 /* plot area, as a fraction of the page width; the legend goes right */
#define VP_X1 0.76

enum { COL_BG, COL_FG, COL_GRID, COL_PHASE, COL_LAND, COL_BODY0, N_COLS = COL_BODY0 + 8 };

/* white, black, grid grey, phase-line grey, coastline brown; bodies: Tableau-10 colours */
static const PLINT palette[N_COLS][3] = {
    {255, 255, 255}, {0, 0, 0},       {225, 225, 225}, {120, 120, 120}, {150, 125, 95},
    {31, 119, 180},  {255, 127, 14},  {44, 160, 44},   {214, 39, 40},   {148, 103, 189},
    {140, 86, 75},   {227, 119, 194}, {23, 190, 207}};

typedef struct curve {
    double *x, *y; /* owned */
    size_t n;
    char label[128];
    PLINT color, style; /* cmap0 index; PLplot line style 1 (solid) .. 8 */
    PLFLT width;
    size_t body;        /* index into lv_plot_data.bodies */
    int set;            /* which of a quantity's curves (main, second, third) */
} curve;

#define MAX_CURVES 32

typedef struct panel {
    char ylabel[96];
    curve c[MAX_CURVES];
    size_t n_c;
    double ylo, yhi; /* NAN: from the data */
} panel;

typedef struct figure {
    char title[128], subtitle[256]; /* what is plotted; the mission */
    const char *xlabel;
    panel p[2];
    size_t n_p;
    int map;           /* ground track: x longitude, y latitude [deg], the sites */
    int coast;         /* map: coastlines (drawn by the even side: it reports whether found) */
    int boundaries;    /* phase starts as vertical lines */
    double xlo, xhi;   /* x range */
    double mlo, mhi;   /* map: latitude range */
} figure;

static void figure_free(figure *f)
{
    for (size_t i = 0; i < f->n_p; i++)
        for (size_t j = 0; j < f->p[i].n_c; j++) {
            free(f->p[i].c[j].x);
            free(f->p[i].c[j].y);
        }
    memset(f, 0, sizeof *f);
}

/* ---- data: one body's value across its phases ------------------------------------------ */

/* First of `cols` that phase file `c` has, or -1. */
static long find_col(const lv_results_table *c, const char *const *cols)
{
    for (size_t i = 0; cols[i] != NULL; i++) {
        long k = lv_results_table_col(c, cols[i]);
        if (k >= 0)
            return k;
    }
    return -1;
}

/* Time and value (times `scale`) of body b across its phases, joined in time order (an event
 * instant appears twice: the step shows); with `vehicle`, over the phases where b is the
 * vehicle only (lv_plot_is_vehicle), the line broken (a NAN) where one such phase does not
 * start where the one before ended. Returns the number of points; 0 when no phase of the body
 * has any of `cols`; (size_t)-1 when out of memory. */
static size_t body_series(const lv_plot_data *d, const lv_plot_body *b, const char *const *cols,
                          double scale, int atmo, int vehicle, curve *c)
{
    const size_t bi = (size_t)(b - d->bodies);
    size_t n = 0;
    for (size_t i = 0; i < b->n; i++) {
        const lv_results_table *csv = d->phases[b->phase[i]].csv;
        if (csv != NULL && find_col(csv, cols) >= 0 &&
            (!vehicle || lv_plot_is_vehicle(d, bi, b->phase[i])))
            n += csv->n_rows + 1;
    }
    if (n == 0)
        return 0;
    c->x = malloc(n * sizeof *c->x);
    c->y = malloc(n * sizeof *c->y);
    if (c->x == NULL || c->y == NULL)
        return (size_t)-1;
    c->n = 0;
    for (size_t i = 0; i < b->n; i++) {
        const lv_results_table *csv = d->phases[b->phase[i]].csv;
        long k = csv ? find_col(csv, cols) : -1;
        if (vehicle && !lv_plot_is_vehicle(d, bi, b->phase[i]))
            continue;
        if (vehicle && k >= 0 && csv->n_rows > 0 && c->n > 0 &&
            c->x[c->n - 1] != csv->v[0]) { /* not where the last one ended: a gap */
            c->x[c->n] = c->y[c->n] = NAN;
            c->n++;
        }
        /* Mach and q: only where the atmosphere model is defined (rho > 0, h at most its
         * top): a NAN breaks the curve there */
        const long krho = atmo && csv ? lv_results_table_col(csv, "rho") : -1;
        const long kh = atmo && csv ? lv_results_table_col(csv, "h") : -1;
        for (size_t r = 0; k >= 0 && r < csv->n_rows; r++) {
            c->x[c->n] = csv->v[r * csv->n_cols];
            c->y[c->n] = csv->v[r * csv->n_cols + (size_t)k] * scale;
            if ((krho >= 0 && !(csv->v[r * csv->n_cols + (size_t)krho] > 0.0)) ||
                (kh >= 0 && csv->v[r * csv->n_cols + (size_t)kh] > LV_ATMO_ALT_MAX))
                c->y[c->n] = NAN;
            c->n++;
        }
    }
    return c->n;
}

/* ---- drawing ----------------------------------------------------------------------------- */

static void range_of(const panel *p, int want_x, double *lo, double *hi)
{
    *lo = INFINITY;
    *hi = -INFINITY;
    for (size_t j = 0; j < p->n_c; j++)
        for (size_t i = 0; i < p->c[j].n; i++) {
            double v = want_x ? p->c[j].x[i] : p->c[j].y[i];
            if (isfinite(v)) {
                *lo = fmin(*lo, v);
                *hi = fmax(*hi, v);
            }
        }
    if (!(*lo <= *hi)) {
        *lo = 0.0;
        *hi = 1.0;
    }
}

static void pad_range(double *lo, double *hi, double frac)
{
    double span = *hi - *lo;
    if (span <= 1e-12 * fmax(fabs(*lo), fabs(*hi)) || span == 0.0) {
        double h = fabs(*lo) > 0.0 ? 0.1 * fabs(*lo) : 1.0;
        *lo -= h;
        *hi += h;
        return;
    }
    *lo -= frac * span;
    *hi += frac * span;
}

/* Mission text for PLplot, which reads '#' as the start of an escape ("#u": superscript): a
 * '#' becomes the escape for its code point, "#[0x23]". */
static void pl_text(char *dst, size_t cap, const char *src)
{
    size_t n = 0;
    for (; *src && n + 8 < cap; src++) {
        if (*src == '#') {
            memcpy(dst + n, "#[0x23]", 7);
            n += 7;
        } else {
            dst[n++] = *src;
        }
    }
    dst[n] = '\0';
}

/* plline() over the finite runs of a curve: a NAN breaks the line. */
static void draw_curve(const curve *c)
{
    plcol0(c->color);
    pllsty(c->style);
    plwidth(c->width);
    size_t i = 0;
    while (i < c->n) {
        while (i < c->n && !(isfinite(c->x[i]) && isfinite(c->y[i])))
            i++;
        size_t j = i;
        while (j < c->n && isfinite(c->x[j]) && isfinite(c->y[j]))
            j++;
        if (j - i == 1)
            plpoin(1, &c->x[i], &c->y[i], 1);
        else if (j > i)
            plline((PLINT)(j - i), &c->x[i], &c->y[i]);
        i = j;
    }
    pllsty(1);
    plwidth(1.0);
}

/* A phase's number: its place in run order (summary.json's index), as the report numbers it. */
static int phase_number(const lv_plot_data *d, size_t k)
{
    return d->res->phases[k].index > 0 ? d->res->phases[k].index : (int)k + 1;
}

/* Dashed vertical lines at the phase starts, each labelled at the top with the numbers of the
 * phases that start there ("4,5"); the legend names them. A label that would overlap the one
 * before it goes one row lower (three rows, then the row with the most room). */
static void draw_boundaries(const lv_plot_data *d, double xlo, double xhi, double ylo, double yhi)
{
    plschr(0.0, 0.75);
    PLFLT def_mm, ht_mm, vx0, vx1, vy0, vy1, sx0, sx1, sy0, sy1;
    plgchr(&def_mm, &ht_mm);
    plgvpd(&vx0, &vx1, &vy0, &vy1);
    plgspa(&sx0, &sx1, &sy0, &sy1);
    const double w_mm = (vx1 - vx0) * (sx1 - sx0), h_mm = (vy1 - vy0) * (sy1 - sy0);
    const double cw = w_mm > 0.0 ? 0.75 * ht_mm * (xhi - xlo) / w_mm : 0.0; /* a digit, x */
    const double ch = h_mm > 0.0 ? ht_mm * (yhi - ylo) / h_mm : 0.0;        /* a line, y */
    double right[3] = {-INFINITY, -INFINITY, -INFINITY}; /* each row's last label's end */
    /* the starts in time order: phases are in run order, which is not time order */
    double t_prev = -INFINITY;
    for (;;) {
        double t = INFINITY;
        for (size_t k = 0; k < d->n_phases; k++)
            if (isfinite(d->phases[k].t0) && d->phases[k].t0 > t_prev && d->phases[k].t0 < t)
                t = d->phases[k].t0;
        if (!isfinite(t))
            break;
        t_prev = t;
        if (t < xlo || t > xhi)
            continue;
        char label[128] = "";
        size_t len = 0;
        for (size_t k = 0; k < d->n_phases; k++)
            if (d->phases[k].t0 == t && len + 12 < sizeof label)
                len += (size_t)snprintf(label + len, sizeof label - len, "%s%d", len ? "," : "",
                                        phase_number(d, k));
        PLFLT x[2] = {t, t}, y[2] = {ylo, yhi};
        plcol0(COL_PHASE);
        pllsty(3);
        plline(2, x, y);
        pllsty(1);
        /* right of the line; left of it where it would leave the plot */
        double w = ((double)len + 0.6) * cw, x0 = t + 0.4 * cw, just = 0.0;
        if (x0 + w > xhi) {
            x0 = t - 0.4 * cw;
            just = 1.0;
        }
        const double a = just == 0.0 ? t : t - w, b = just == 0.0 ? t + w : t;
        size_t row = 0;
        while (row < 3 && a < right[row])
            row++;
        if (row == 3) { /* no row free: the one whose last label ends first */
            row = 0;
            for (size_t r = 1; r < 3; r++)
                if (right[r] < right[row])
                    row = r;
        }
        right[row] = b;
        plcol0(COL_FG);
        plptex(x0, yhi - (1.0 + 1.4 * (double)row) * ch, 1.0, 0.0, just, label);
    }
    plschr(0.0, 1.0);
}

#define MAX_LEGEND (MAX_CURVES + 40)

/* The curves' legend; with `phases`, then the phases that ran, numbered as their lines. */
static void draw_legend(const lv_plot_data *d, const panel *p, int phases)
{
    PLINT opt[MAX_LEGEND], tcol[MAX_LEGEND], lcol[MAX_LEGEND], lsty[MAX_LEGEND];
    PLFLT lw[MAX_LEGEND];
    const char *text[MAX_LEGEND];
    char key[MAX_LEGEND - MAX_CURVES][80];
    PLINT n = 0;
    for (size_t j = 0; j < p->n_c; j++) {
        if (p->c[j].label[0] == '\0')
            continue;
        opt[n] = PL_LEGEND_LINE;
        tcol[n] = COL_FG;
        lcol[n] = p->c[j].color;
        lsty[n] = p->c[j].style;
        lw[n] = p->c[j].width;
        text[n] = p->c[j].label;
        n++;
    }
    size_t n_key = 0;
    for (size_t k = 0; phases && k < d->n_phases && n_key < MAX_LEGEND - MAX_CURVES; k++) {
        if (!isfinite(d->phases[k].t0))
            continue;
        char name[64];
        pl_text(name, sizeof name, d->phases[k].name);
        snprintf(key[n_key], sizeof key[0], "%d  %s", phase_number(d, k), name);
        opt[n] = PL_LEGEND_NONE;
        tcol[n] = COL_PHASE;
        lcol[n] = COL_BG;
        lsty[n] = 1;
        lw[n] = 1.0;
        text[n] = key[n_key++];
        n++;
    }
    if (n == 0)
        return;
    PLFLT w, h;
    plschr(0.0, 0.75);
    pllegend(&w, &h, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX,
             PL_POSITION_RIGHT | PL_POSITION_OUTSIDE, 0.012, 0.0, 0.05, COL_BG,
             COL_FG, 1, 0, 1, n, opt, 0.8, 0.9, 2.0, 0.0, tcol, text, NULL, NULL, NULL, NULL,
             lcol, lsty, lw, NULL, NULL, NULL, NULL);
    plschr(0.0, 1.0);
}

/* The sites on a map: a runway as a thick line from its threshold along the part rolled on,
 * and a triangle at its threshold (or at the launch site), labelled. A label that would cover
 * one drawn before (two runways 4 km apart on a 20 km map) moves down a line until it is
 * clear; the box of a label is estimated from its characters (0.009 of the map's width each
 * at the labels' size, a line 0.045 of its height: a bound, PLplot measures no text). */
#define SITE_LABELS_MAX 16
static void draw_sites(const lv_plot_data *d, const figure *f, double ylo, double yhi)
{
    const double xm = 0.5 * (f->xlo + f->xhi);
    const double cw = 0.009 * (f->xhi - f->xlo), lh = 0.045 * (yhi - ylo);
    double lx[SITE_LABELS_MAX], ly[SITE_LABELS_MAX], lw[SITE_LABELS_MAX];
    size_t nl = 0;
    for (size_t i = 0; i < d->n_sites; i++) {
        const lv_plot_site *s = &d->sites[i];
        PLFLT x[2] = {s->lon * RAD2DEG, s->lon1 * RAD2DEG}, y[2] = {s->lat * RAD2DEG,
                                                                     s->lat1 * RAD2DEG};
        for (int k = 0; k < 2; k++) /* the longitude nearest the map's centre */
            x[k] += 360.0 * round((xm - x[k]) / 360.0);
        if (x[0] < f->xlo || x[0] > f->xhi || y[0] < ylo || y[0] > yhi)
            continue;
        plcol0(COL_FG);
        if (s->length > 0.0) {
            plwidth(5.0);
            plline(2, x, y);
            plwidth(1.0);
        }
        plschr(0.0, 1.1);
        plpoin(1, x, y, 7);
        char label[200];
        pl_text(label, sizeof label, s->label);
        double tx = x[0] + 0.015 * (f->xhi - f->xlo), ty = y[0] - 0.035 * (yhi - ylo);
        const double tw = cw * (double)strlen(label);
        for (int moved = 1, tries = 0; moved && tries < SITE_LABELS_MAX; tries++) {
            moved = 0;
            for (size_t j = 0; j < nl; j++)
                if (tx < lx[j] + lw[j] && lx[j] < tx + tw && fabs(ty - ly[j]) < lh) {
                    ty = ly[j] - lh; /* below the one it covers */
                    moved = 1;
                }
        }
        if (nl < SITE_LABELS_MAX) {
            lx[nl] = tx;
            ly[nl] = ty;
            lw[nl++] = tw;
        }
        plschr(0.0, 0.75);
        plptex(tx, ty, 1.0, 0.0, 0.0, label);
        plschr(0.0, 1.0);
    }
}

typedef void (*mapform_fn)(PLINT n, PLFLT *x, PLFLT *y);

static void draw_panel(const lv_plot_data *d, const figure *f, size_t ip, PLFLT y0, PLFLT y1,
                       int *map_ok, PLINT *code, char *msg)
{
    const panel *p = &f->p[ip];
    double ylo = p->ylo, yhi = p->yhi;
    if (!(isfinite(ylo) && isfinite(yhi))) {
        range_of(p, 0, &ylo, &yhi);
        pad_range(&ylo, &yhi, 0.05);
    }
    if (f->map) {
        ylo = f->mlo;
        yhi = f->mhi;
    }
    plvpor(VP_X0, VP_X1, y0, y1);
    plsxax(7, 0); /* plain numbers: no "(x10^4)" factor */
    plsyax(7, 0);
    plwind(f->xlo, f->xhi, ylo, yhi);
    plcol0(COL_GRID);
    plbox("g", 0.0, 0, "g", 0.0, 0);
    if (f->coast) {
        plcol0(COL_LAND);
        plwidth(1.2);
        plmap((mapform_fn)NULL, "globe", f->xlo, f->xhi, ylo, yhi);
        plwidth(1.0);
        if (*code != 0) { /* no shapefile: a graticule only */
            *map_ok = 0;
            *code = 0;
            msg[0] = '\0';
        }
    }
    if (f->boundaries)
        draw_boundaries(d, f->xlo, f->xhi, ylo, yhi);
    for (size_t j = 0; j < p->n_c; j++)
        draw_curve(&p->c[j]);
    if (f->map)
        draw_sites(d, f, ylo, yhi);
    if (f->map) /* start and end of each track (not of an IIP trace: set 1) */
        for (size_t j = 0; j < p->n_c; j++) {
            const curve *c = &p->c[j];
            if (c->n == 0 || c->set == 1)
                continue;
            plcol0(c->color);
            plschr(0.0, 1.3);
            plpoin(1, &c->x[0], &c->y[0], 4);
            plpoin(1, &c->x[c->n - 1], &c->y[c->n - 1], 5);
            plschr(0.0, 1.0);
        }
    plcol0(COL_FG);
    plbox(ip + 1 == f->n_p ? "bcnst" : "bcst", 0.0, 0, "bcnstv", 0.0, 0);
    plmtex("l", 4.6, 0.5, 0.5, p->ylabel);
    if (ip + 1 == f->n_p)
        plmtex("b", 3.0, 0.5, 0.5, f->xlabel);
    if (ip == 0) { /* title, and the mission's name under it at the right */
        plschr(0.0, 1.15);
        plmtex("t", 1.9, 0.5, 0.5, f->title);
        plschr(0.0, 0.8);
        plmtex("t", 0.6, 1.0, 1.0, f->subtitle);
        plschr(0.0, 1.0);
    }
    if (ip == 0 || f->p[ip].n_c != f->p[0].n_c)
        draw_legend(d, p, f->boundaries && ip == 0);
}

static int device_available(const char *dev)
{
    const char *menu[128], *names[128];
    const char **pm = menu, **pn = names;
    int n = 128;
    plgDevs(&pm, &pn, &n);
    for (int i = 0; i < n; i++)
        if (strcmp(names[i], dev) == 0)
            return 1;
    return 0;
}

/* Draws the figure's panels on the current stream (after plinit). */
static void draw_figure(const lv_plot_data *d, const figure *f, int *map_ok, PLINT *code,
                        char *msg)
{
    pladv(0);
    if (f->n_p == 1) {
        draw_panel(d, f, 0, 0.11, 0.89, map_ok, code, msg);
    } else {
        draw_panel(d, f, 0, 0.52, 0.89, map_ok, code, msg);
        draw_panel(d, f, 1, 0.11, 0.49, map_ok, code, msg);
    }
}

/* A new PLplot stream with our page and colours; its errors land in code/msg. */
static int stream_begin(PLINT *old, PLINT *code, char *msg)
{
    PLINT strm = -1;
    plgstrm(old);
    plmkstrm(&strm);
    if (strm < 0)
        return 0;
    plsError(code, msg);
    plspage(0.0, 0.0, PAGE_W, PAGE_H, 0, 0);
    plscmap0n(N_COLS);
    for (PLINT i = 0; i < N_COLS; i++)
        plscol0(i, palette[i][0], palette[i][1], palette[i][2]);
    return 1;
}

/* Writes the RGB image `rgb` (PAGE_W x PAGE_H, 3 bytes a pixel, rows top down) as a PNG to
 * `fp`. Cairo's own writer (pngcairo) compresses with zlib's default level and tries every
 * row filter: three quarters of all the plotting time. A figure is mostly flat colour, so the
 * fastest zlib level without row filters costs a fraction of that for files about as small
 * (docs/visualization.md). */
static int write_png(FILE *fp, unsigned char *rgb)
{
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png != NULL ? png_create_info_struct(png) : NULL;
    png_bytep rows[PAGE_H];
    if (info == NULL || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, info != NULL ? &info : NULL);
        return -1;
    }
    png_init_io(png, fp);
    png_set_IHDR(png, info, PAGE_W, PAGE_H, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_compression_level(png, 1);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_NONE);
    for (int y = 0; y < PAGE_H; y++)
        rows[y] = rgb + (size_t)y * PAGE_W * 3;
    png_set_rows(png, info, rows);
    png_write_png(png, info, PNG_TRANSFORM_IDENTITY, NULL);
    png_destroy_write_struct(&png, &info);
    return 0;
}

/* Draws `f` with PLplot device `dev` into `path` (through `path`.tmp). "png": PLplot's cairo
 * memory device (memcairo: the same cairo rendering as pngcairo, into our buffer) and
 * write_png; otherwise the device writes the file itself (svgcairo, svg). */
static lv_status render(const lv_plot_data *d, const figure *f, const char *dev, const char *path,
                        int *map_ok, lv_err *err)
{
    const int png = strcmp(dev, "png") == 0;
    /* PLplot writes the temporary file by name, and exits the process when it cannot open
     * it: make sure it can. The PNG is written by us, through the stream. */
    lv_atomic out;
    lv_status st = png ? lv_atomic_open(&out, path, err) : lv_atomic_init(&out, path, err);
    if (st == LV_OK && !png)
        st = lv_atomic_reserve(&out, err);
    if (st != LV_OK)
        return st;
    unsigned char *rgb = NULL;
    if (png) {
        rgb = malloc((size_t)PAGE_W * PAGE_H * 3);
        if (rgb == NULL) {
            lv_atomic_abort(&out);
            return lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", path);
        }
        memset(rgb, 255, (size_t)PAGE_W * PAGE_H * 3); /* the background, colour 0: white */
    }
    PLINT old = 0, code = 0;
    char msg[1024] = "";
    if (!stream_begin(&old, &code, msg)) {
        free(rgb);
        lv_atomic_abort(&out);
        return lv_fail(err, LV_ERR_IO, "%s: PLplot has no free stream", path);
    }
    if (png) {
        plsdev("memcairo");
        plsmem(PAGE_W, PAGE_H, rgb);
    } else {
        plsdev(dev);
        plsfnam(out.tmp);
    }
    plinit();
    if (code == 0)
        draw_figure(d, f, map_ok, &code, msg);
    plend1();
    plsstrm(old);
    if (code != 0) {
        free(rgb);
        lv_atomic_abort(&out);
        return lv_fail(err, LV_ERR_IO, "%s: PLplot: %s", path, msg);
    }
    if (png) {
        const int bad = write_png(out.fp, rgb);
        free(rgb);
        if (bad) {
            lv_atomic_abort(&out);
            return lv_fail(err, LV_ERR_IO, "%s: cannot write the PNG image", out.tmp);
        }
        return lv_atomic_commit(&out, err);
    }
    struct stat sb;
    if (stat(out.tmp, &sb) != 0 || sb.st_size == 0) {
        lv_atomic_abort(&out);
        return lv_fail(err, LV_ERR_IO, "%s: PLplot (%s) wrote nothing", path, dev);
    }
    return lv_atomic_commit(&out, err);
}

/* The figure as PNG and SVG. */
static lv_status render_pair(const lv_plot_data *d, const figure *f, const char *plotdir,
                             const char *stem, int *map_ok, lv_err *err)
{
    char path[4400];
    const char *svg = device_available("svgcairo") ? "svgcairo" : "svg";
    if (!device_available("memcairo"))
        return lv_fail(err, LV_ERR_IO,
                       "%s/%s.png: PLplot has no 'memcairo' driver (Debian: plplot-driver-cairo)",
                       plotdir, stem);
    snprintf(path, sizeof path, "%s/%s.png", plotdir, stem);
    lv_status st = render(d, f, "png", path, map_ok, err);
    snprintf(path, sizeof path, "%s/%s.svg", plotdir, stem);
    if (st == LV_OK)
        st = render(d, f, svg, path, map_ok, err);
    return st;
}

/* ---- two processes draw -----------------------------------------------------------------
 * PLplot's state is global, so figures cannot be drawn by threads; they can by processes. When
 * the calling process has one thread (fork() is then safe; lvsim plot, lvsim run), a child
 * process is forked before anything is drawn: it goes through the same figures and draws
 * every other one, this process the rest (map figures here: they report whether the
 * coastlines were found), so two cores draw. The child starts from this process's state
 * before any drawing (pango starts threads of its own once it draws text: no fork after that),
 * touches nothing of the caller's and reports through a pipe, then _exit()s. It dies with its
 * parent (PR_SET_PDEATHSIG on Linux): a parent killed with SIGKILL leaves no drawer behind that
 * goes on writing into a staging folder the next run removes. */
enum { DRAW_ALL = 0, DRAW_EVEN = 1, DRAW_ODD = 2 };

/* Draws the figure (or leaves it to the other process), and lists it. */
static lv_status render_both(const lv_plot_data *d, const figure *f, const char *plotdir,
                             const char *stem, lv_plot_list *list, int *map_ok, lv_err *err)
{
    lv_status st = LV_OK;
    int mine = 1;
    if (list->draw_role != DRAW_ALL) {
        if (f->coast)
            mine = list->draw_role == DRAW_EVEN;
        else
            mine = (list->draw_index++ % 2 == 0) == (list->draw_role == DRAW_EVEN);
    }
    if (mine)
        st = render_pair(d, f, plotdir, stem, map_ok, err);
    if (st == LV_OK && list->n_made < LV_PLOT_MAX_FIGS) {
        snprintf(list->made[list->n_made].stem, sizeof list->made[0].stem, "%s", stem);
        snprintf(list->made[list->n_made].title, sizeof list->made[0].title, "%s", f->title);
        list->n_made++;
    }
    return st;
}

/* One thread in this process (from /proc/self/status): fork() is safe. */
static int single_threaded(void)
{
    FILE *f = fopen("/proc/self/status", "r");
    char line[256];
    int threads = 0;
    while (f != NULL && fgets(line, sizeof line, f) != NULL)
        if (sscanf(line, "Threads: %d", &threads) == 1)
            break;
    if (f != NULL)
        fclose(f);
    return threads == 1;
}

typedef struct child_msg {
    lv_status st;
    lv_err err;
} child_msg;

static void add_skip(lv_plot_list *l, const char *what, const char *why)
{
    if (l->n_skipped >= LV_PLOT_MAX_FIGS)
        return;
    snprintf(l->skipped[l->n_skipped].what, sizeof l->skipped[0].what, "%s", what);
    snprintf(l->skipped[l->n_skipped].why, sizeof l->skipped[0].why, "%s", why);
    l->n_skipped++;
}

static void add_note(lv_plot_list *l, const char *note)
{
    if (l->n_notes < LV_PLOT_MAX_FIGS)
        snprintf(l->notes[l->n_notes++], sizeof l->notes[0], "%s", note);
}

/* ---- the figures --------------------------------------------------------------------------- */

typedef struct quantity {
    int atmo;          /* 1: only where the atmosphere model is defined (Mach, q) */
    const char *stem, *title, *ylabel;
    const char *a[3];  /* columns of the main curve, first found wins (planet, flat world; the
                          6-DoF model's name before the 3-DoF model's) */
    const char *b[3];  /* a second, dashed curve, when the phases have it */
    const char *a_label, *b_label;
    double scale;      /* SI -> the unit of ylabel */
    const char *c[3];  /* a third curve (dash-dotted), when the phases have it */
    const char *c_label;
    int vehicle;       /* 1: a vehicle's attitude: one curve per phase's vehicle (its bottom
                          stage: lv_plot_is_vehicle), one colour per vehicle, one line style
                          per quantity (solid, dashed, dash-dotted), a legend of each */
    int own_time;      /* 1: the time axis spans the rows that have the quantity (6-DoF
                          phases only), not the whole mission */
} quantity;

static const quantity quantities[] = {
    {0, "altitude", "Altitude", "altitude [km]", {"h", "z", NULL}, {NULL}, "", "", 1e-3, {NULL}, "", 0, 0},
    {0, "speed", "Speed", "speed [m/s]", {"v_rel", "speed", NULL}, {"v_inertial", NULL},
     "relative", "inertial", 1.0, {NULL}, "", 0, 0},
    {0, "mass", "Mass", "mass [t]", {"m", NULL}, {NULL}, "", "", 1e-3, {NULL}, "", 0, 0},
    {1, "mach", "Mach number", "Mach number [1]", {"mach", NULL}, {NULL}, "", "", 1.0, {NULL}, "", 0, 0},
    {1, "dynamic_pressure", "Dynamic pressure", "dynamic pressure [kPa]", {"q_dyn", NULL},
     {NULL}, "", "", 1e-3, {NULL}, "", 0, 0},
    {1, "heat_flux", "Stagnation-point heat flux (Sutton-Graves)", "heat flux [kW/m\xc2\xb2]",
     {"heat_flux", NULL}, {NULL}, "", "", 1e-3, {NULL}, "", 0, 0},
    {0, "heat_load", "Stagnation-point heat load (the heat flux's time integral)",
     "heat load [MJ/m\xc2\xb2]", {"heat_load", NULL}, {NULL}, "", "", 1e-6, {NULL}, "", 0, 0},
    {0, "load_factor", "Load factor", "load factor [g\xe2\x82\x80]", {"n_axial", NULL},
     {"n_normal", NULL}, "axial", "normal", 1.0, {NULL}, "", 0, 0},
    {0, "flight_path_angle", "Flight-path angle", "flight-path angle [deg]", {"fpa", NULL},
     {"fpa_inertial", NULL}, "relative", "inertial", RAD2DEG, {NULL}, "", 0, 0},
    {0, "acceleration", "Acceleration", "acceleration [m/s\xc2\xb2]", {"accel", NULL}, {NULL},
     "", "", 1.0, {NULL}, "", 0, 0},
    {0, "thrust", "Thrust", "thrust [kN]", {"thrust", NULL}, {NULL}, "", "", 1e-3, {NULL}, "", 0, 0},
    /* attitude and control (6-DoF phases; the 3-DoF model's attitude and aerodynamic angles
     * are outputs too: theta, psi, phi, alpha_in, beta_in) */
    {0, "attitude", "Attitude (3-2-1 Euler angles, local NED)", "angle [deg]", {"theta", NULL},
     {"psi", NULL}, "pitch", "heading", RAD2DEG, {"phi", NULL}, "roll", 1, 0},
    {0, "angle_of_attack", "Angle of attack and sideslip", "angle [deg]",
     {"alpha", "alpha_in", NULL}, {"beta", "beta_in", NULL}, "alpha", "beta", RAD2DEG, {NULL},
     "", 1, 0},
    {0, "body_rates", "Body rates", "rate [deg/s]", {"q", NULL}, {"r", NULL}, "pitch q", "yaw r",
     RAD2DEG, {"p", NULL}, "roll p", 1, 1},
    {0, "gimbal", "Gimbal angles", "gimbal angle [deg]", {"gimbal_pitch_in", NULL},
     {"gimbal_yaw_in", NULL}, "pitch", "yaw", RAD2DEG, {NULL}, "", 1, 1},
    {0, "attitude_error", "Attitude error (controller)", "error [deg]", {"err_pitch", NULL},
     {"err_yaw", NULL}, "pitch", "yaw", RAD2DEG, {"err_roll", NULL}, "roll", 1, 1},
};

/* "mission <name>", for a figure's subtitle. */
static void mission_line(const lv_plot_data *d, char *dst, size_t cap)
{
    char name[200];
    pl_text(name, sizeof name, d->res->mission != NULL ? d->res->mission : "?");
    snprintf(dst, cap, "mission %s", name);
}

/* A body's name for a legend. */
static const char *body_label(const lv_plot_data *d, size_t i, char *buf, size_t cap)
{
    pl_text(buf, cap, d->bodies[i].name);
    return buf;
}

static void time_range(const lv_plot_data *d, double *lo, double *hi)
{
    *lo = INFINITY;
    *hi = -INFINITY;
    for (size_t k = 0; k < d->n_phases; k++) {
        const lv_results_table *c = d->phases[k].csv;
        for (size_t r = 0; c != NULL && r < c->n_rows; r++) {
            *lo = fmin(*lo, c->v[r * c->n_cols]);
            *hi = fmax(*hi, c->v[r * c->n_cols]);
        }
    }
    if (!(*lo < *hi)) {
        *lo = isfinite(*lo) ? *lo : 0.0;
        *hi = *lo + 1.0;
    }
}

static PLFLT body_width(size_t i)
{
    return fmax(1.2, 3.2 - 0.7 * (double)i); /* later bodies thinner: shared phases show all */
}

/* Bodies flying together have the same values in their shared phases: besides its colour,
 * each body gets its own dash pattern (and a thinner line than the one before), so every
 * body stays visible where the curves lie on top of each other. PLplot styles: 1 solid,
 * 3 long dashes with long gaps, 2 short dashes, 5 long and short dashes; the second curve
 * of a quantity: 4, 6, 7, 8. */
static PLINT body_style(size_t i, int second)
{
    static const PLINT main_style[4] = {1, 3, 2, 5}, second_style[4] = {4, 6, 7, 8};
    static const PLINT third_style[4] = {5, 2, 1, 3};
    return second == 2 ? third_style[i % 4] : second ? second_style[i % 4] : main_style[i % 4];
}

/* The line styles of a vehicle-attitude figure's quantities (docs/visualization.md): the
 * first solid, the second dashed (PLplot 4: long dashes, short gaps), the third dash-dotted
 * (5: long and short dashes). */
static const PLINT quantity_style[3] = {1, 4, 5};

/* One figure of quantity q: a curve per body (two when q has a second column); with
 * q->vehicle a curve per vehicle over the phases it flies as the vehicle; a quantity no
 * phase file has is added to the list's skipped ones. */
static lv_status quantity_figure(const lv_plot_data *d, const quantity *q, const char *plotdir,
                                 lv_plot_list *list, lv_err *err)
{
    figure f;
    memset(&f, 0, sizeof f);
    snprintf(f.title, sizeof f.title, "%s", q->title);
    mission_line(d, f.subtitle, sizeof f.subtitle);
    f.xlabel = "time [s]";
    f.n_p = 1;
    f.boundaries = 1;
    f.p[0].ylo = f.p[0].yhi = NAN;
    snprintf(f.p[0].ylabel, sizeof f.p[0].ylabel, "%s", q->ylabel);
    time_range(d, &f.xlo, &f.xhi);
    size_t n_a = 0, n_b = 0, n_c = 0;
    lv_status st = LV_OK;
    for (int pass = 0; pass < 3 && st == LV_OK; pass++) {
        const char *const *cols = pass == 0 ? q->a : pass == 1 ? q->b : q->c;
        if (cols[0] == NULL)
            continue;
        for (size_t i = 0; i < d->n_bodies && f.p[0].n_c < MAX_CURVES; i++) {
            curve *c = &f.p[0].c[f.p[0].n_c];
            size_t n = body_series(d, &d->bodies[i], cols, q->scale, q->atmo, q->vehicle, c);
            if (n == (size_t)-1) {
                st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
                f.p[0].n_c++; /* freed below */
                break;
            }
            if (n == 0)
                continue;
            c->color = COL_BODY0 + (PLINT)(i % (N_COLS - COL_BODY0));
            c->style = q->vehicle ? quantity_style[pass] : body_style(i, pass);
            c->body = i;
            c->set = pass;
            c->width = q->vehicle ? 2.0 : body_width(i);
            f.p[0].n_c++;
            *(pass == 0 ? &n_a : pass == 1 ? &n_b : &n_c) += 1;
        }
    }
    char why[200];
    if (st == LV_OK && n_a == 0) {
        snprintf(why, sizeof why, "no phase file has the output '%s' (%s world)", q->a[0],
                 d->flat ? "flat" : "planet");
        add_skip(list, q->stem, why);
    }
    if (st == LV_OK && n_a > 0 && q->own_time) /* the rows that have it */
        range_of(&f.p[0], 1, &f.xlo, &f.xhi);
    if (st == LV_OK && n_a > 0 && q->vehicle) {
        /* the legend: each vehicle's colour, then each quantity's line style (data curves
         * unlabelled; legend entries as curves without points) */
        const size_t n_data = f.p[0].n_c;
        for (size_t i = 0; i < d->n_bodies && f.p[0].n_c < MAX_CURVES; i++) {
            int drawn = 0;
            for (size_t j = 0; j < n_data; j++)
                drawn |= f.p[0].c[j].body == i;
            if (!drawn)
                continue;
            curve *c = &f.p[0].c[f.p[0].n_c++];
            c->color = COL_BODY0 + (PLINT)(i % (N_COLS - COL_BODY0));
            c->style = 1;
            c->width = 2.0;
            c->body = i;
            body_label(d, i, c->label, sizeof c->label);
        }
        const size_t n_set[3] = {n_a, n_b, n_c};
        const char *const set_label[3] = {q->a_label, q->b_label, q->c_label};
        for (int k = 0; k < 3 && f.p[0].n_c < MAX_CURVES; k++) {
            if (n_set[k] == 0)
                continue;
            curve *c = &f.p[0].c[f.p[0].n_c++];
            c->color = COL_FG;
            c->style = quantity_style[k];
            c->width = 2.0;
            c->set = k;
            snprintf(c->label, sizeof c->label, "%s", set_label[k]);
        }
    }
    if (st == LV_OK && n_a > 0) {
        char name[96];
        for (size_t j = 0; j < f.p[0].n_c && !q->vehicle; j++) { /* body, which curve if two */
            curve *c = &f.p[0].c[j];
            if (n_b > 0 || n_c > 0)
                snprintf(c->label, sizeof c->label, "%.96s, %.16s",
                         body_label(d, c->body, name, sizeof name),
                         c->set == 0 ? q->a_label : c->set == 1 ? q->b_label : q->c_label);
            else
                body_label(d, c->body, c->label, sizeof c->label);
        }
        if (q->b[0] != NULL && n_b == 0) {
            snprintf(why, sizeof why, "%s: %s curve not drawn: no phase file has '%s' (%s)",
                     q->stem, q->b_label, q->b[0],
                     d->flat ? "flat world: its frame is inertial" : "not an output");
            add_note(list, why);
        }
        int map_ok = 1;
        st = render_both(d, &f, plotdir, q->stem, list, &map_ok, err);
    }
    figure_free(&f);
    return st;
}

/* The paper's Figure 10: every body's speed over v_max, the largest speed of any body, and its
 * mass over m_0, the mission's initial mass (lv_plot_fig10_refs): where bodies fly together
 * their curves coincide, and a separation's steps show each part's share of m_0. */
static lv_status fig10(const lv_plot_data *d, const char *plotdir, lv_plot_list *list,
                       lv_err *err)
{
    static const char *const v_cols[] = {"v_rel", "speed", NULL};
    static const char *const m_cols[] = {"m", NULL};
    if (!(isfinite(d->v_max) && isfinite(d->m_0))) {
        add_skip(list, "fig10_normalised", "no phase file has a speed and the mass 'm'");
        return LV_OK;
    }
    figure f;
    memset(&f, 0, sizeof f);
    snprintf(f.title, sizeof f.title, "Normalised speed and mass (as the paper's Figure 10)");
    mission_line(d, f.subtitle, sizeof f.subtitle);
    f.xlabel = "time [s]";
    f.n_p = 2;
    f.boundaries = 1;
    time_range(d, &f.xlo, &f.xhi);
    snprintf(f.p[0].ylabel, sizeof f.p[0].ylabel, "v / v#dmax#u (v#dmax#u = %.0f m/s)",
             d->v_max);
    snprintf(f.p[1].ylabel, sizeof f.p[1].ylabel, "m / m#d0#u (m#d0#u = %.4g t)", d->m_0 * 1e-3);
    lv_status st = LV_OK;
    for (size_t ip = 0; ip < 2 && st == LV_OK; ip++) {
        panel *p = &f.p[ip];
        p->ylo = 0.0;
        p->yhi = 1.08;
        for (size_t i = 0; i < d->n_bodies && p->n_c < MAX_CURVES; i++) {
            curve *c = &p->c[p->n_c];
            const double ref = ip == 0 ? d->v_max : d->m_0;
            size_t n = body_series(d, &d->bodies[i], ip == 0 ? v_cols : m_cols, 1.0 / ref, 0, 0,
                                   c);
            if (n == (size_t)-1) {
                p->n_c++;
                st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
                break;
            }
            if (n == 0)
                continue;
            for (size_t k = 0; ip == 0 && k < n; k++)
                c->y[k] = fabs(c->y[k]);
            c->color = COL_BODY0 + (PLINT)(i % (N_COLS - COL_BODY0));
            c->style = body_style(i, 0);
            c->width = body_width(i);
            body_label(d, i, c->label, sizeof c->label);
            p->n_c++;
        }
    }
    if (st == LV_OK) {
        int map_ok = 1;
        st = render_both(d, &f, plotdir, "fig10_normalised", list, &map_ok, err);
    }
    figure_free(&f);
    return st;
}

/* A curve of column `col` (times `scale`) of table t over its first column (time). Returns
 * its points, 0 when t has no such column, (size_t)-1 out of memory. */
static size_t table_curve(const lv_results_table *t, const char *col, double scale, curve *c)
{
    const long k = lv_results_table_col(t, col);
    if (k < 0 || t->n_rows == 0)
        return 0;
    c->x = malloc(t->n_rows * sizeof *c->x);
    c->y = malloc(t->n_rows * sizeof *c->y);
    if (c->x == NULL || c->y == NULL)
        return (size_t)-1;
    for (size_t r = 0; r < t->n_rows; r++) {
        c->x[r] = t->v[r * t->n_cols];
        c->y[r] = t->v[r * t->n_cols + (size_t)k] * scale;
    }
    return c->n = t->n_rows;
}

/* Each phase with a reference (an optimiser's trajectory): its altitude and speed against the
 * reference's at the rows compared (reference_<k>_<name>.csv), as the paper's Figure 10 sets
 * the simulated beside the optimised trajectory; the drift's figures in the subtitle. */
static lv_status reference_figures(const lv_plot_data *d, const char *plotdir,
                                   lv_plot_list *list, lv_err *err)
{
    lv_status st = LV_OK;
    for (size_t k = 0; k < d->n_phases && st == LV_OK; k++) {
        const lv_results_table *t = d->phases[k].ref;
        const lv_results_phase *rp = &d->res->phases[k];
        if (t == NULL || t->n_rows == 0)
            continue;
        char stem[48], name[96];
        snprintf(stem, sizeof stem, "reference_%zu", k + 1);
        pl_text(name, sizeof name, d->phases[k].name);
        figure f;
        memset(&f, 0, sizeof f);
        snprintf(f.title, sizeof f.title, "Phase %s against its reference", name);
        snprintf(f.subtitle, sizeof f.subtitle, "largest drift %.3g m (t = %.6g s), %.3g m/s, "
                 "%.3g kg", rp->ref.pos_max, rp->ref.pos_max_t, rp->ref.vel_max,
                 rp->ref.mass_max);
        f.xlabel = "time [s]";
        f.n_p = 2;
        static const char *const cols[2][2] = {{"h", "h_ref"}, {"v_rel", "v_ref"}};
        static const double scale[2] = {1e-3, 1.0};
        snprintf(f.p[0].ylabel, sizeof f.p[0].ylabel, "altitude [km]");
        snprintf(f.p[1].ylabel, sizeof f.p[1].ylabel, "speed [m/s]");
        for (size_t ip = 0; ip < 2 && st == LV_OK; ip++) {
            panel *p = &f.p[ip];
            p->ylo = p->yhi = NAN;
            for (int j = 0; j < 2 && st == LV_OK; j++) {
                curve *c = &p->c[p->n_c++];
                if (table_curve(t, cols[ip][j], scale[ip], c) == (size_t)-1)
                    st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
                c->color = j == 0 ? COL_BODY0 : COL_FG;
                c->style = j == 0 ? 1 : 2;  /* the simulation solid, the reference dashed */
                c->width = j == 0 ? 2.6 : 1.6;
                snprintf(c->label, sizeof c->label, "%s", j == 0 ? "simulation" : "reference");
            }
        }
        if (st == LV_OK) {
            range_of(&f.p[0], 1, &f.xlo, &f.xhi);
            if (!(f.xlo < f.xhi))
                f.xhi = f.xlo + 1.0;
            int map_ok = 1;
            if (list->n_made >= LV_PLOT_MAX_FIGS)
                add_skip(list, stem, "the report's list of figures is full");
            else
                st = render_both(d, &f, plotdir, stem, list, &map_ok, err);
        }
        figure_free(&f);
    }
    return st;
}

#define SITE_NEAR 1.0 /* deg: a track that ends this close to the first site came back to it */

/* The window of the site figure: around the first site (a runway, else the launch site), wide
 * enough for the runway and for every track's end within SITE_NEAR of it (x 1.3), at least
 * 0.1 deg (about 11 km on the Earth) and at most 0.6 deg from the centre. 0: no site, or
 * neither a runway nor a track that comes back (the site figure is not drawn). */
static int site_window(const lv_plot_data *d, const panel *p, double *xm, double *ym,
                       double *half)
{
    if (d->n_sites == 0)
        return 0;
    const lv_plot_site *s = &d->sites[0];
    *xm = 0.5 * (s->lon + s->lon1) * RAD2DEG;
    *ym = 0.5 * (s->lat + s->lat1) * RAD2DEG;
    const double coslat = fmax(cos(*ym / RAD2DEG), 0.2);
    double r = 3.0 * hypot(s->lat1 - s->lat, (s->lon1 - s->lon) * coslat) * RAD2DEG;
    int back = s->length > 0.0;
    for (size_t j = 0; j < p->n_c; j++) {
        const curve *c = &p->c[j];
        if (c->n == 0)
            continue;
        const double dlon = c->x[c->n - 1] - *xm;
        const double dist = hypot(c->y[c->n - 1] - *ym,
                                  (dlon - 360.0 * round(dlon / 360.0)) * coslat);
        if (c->n > 0 && dist < SITE_NEAR) {
            r = fmax(r, 1.3 * dist);
            back = 1;
        }
    }
    *half = fmin(fmax(r, 0.1), 0.6);
    return back;
}

/* The ground track on a map with coastlines (site 0), or (site 1) without them, around the
 * first site: the runway, the take-off and the return. */
static lv_status ground_track(const lv_plot_data *d, const char *plotdir, lv_plot_list *list,
                              int site, lv_err *err)
{
    const char *stem = site ? "ground_track_site" : "ground_track";
    figure f;
    memset(&f, 0, sizeof f);
    if (site && d->n_sites > 0) {
        char where[200];
        pl_text(where, sizeof where, d->sites[0].label);
        snprintf(f.title, sizeof f.title, "Ground track around %s%.100s", strncmp(where, "launch", 6) == 0 ? "the " : "",
                 where);
    } else {
        snprintf(f.title, sizeof f.title, "Ground track");
    }
    mission_line(d, f.subtitle, sizeof f.subtitle);
    f.xlabel = "longitude [deg]";
    f.n_p = 1;
    f.map = 1;
    f.coast = !site;
    snprintf(f.p[0].ylabel, sizeof f.p[0].ylabel, "latitude [deg]");
    panel *p = &f.p[0];
    lv_status st = LV_OK;
    for (size_t i = 0; i < d->n_bodies && p->n_c < MAX_CURVES; i++) {
        const lv_results_table *t = d->bodies[i].traj;
        long klat = lv_results_table_col(t, "lat"), klon = lv_results_table_col(t, "lon");
        if (klat < 0 || klon < 0 || t->n_rows == 0)
            continue;
        curve *c = &p->c[p->n_c++];
        c->x = malloc(t->n_rows * sizeof *c->x);
        c->y = malloc(t->n_rows * sizeof *c->y);
        if (c->x == NULL || c->y == NULL) {
            st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
            break;
        }
        for (size_t r = 0; r < t->n_rows; r++) {
            double lon = t->v[r * t->n_cols + (size_t)klon] * RAD2DEG;
            if (c->n > 0 && isfinite(c->x[c->n - 1])) /* continuous across +-180 deg */
                lon += 360.0 * round((c->x[c->n - 1] - lon) / 360.0);
            c->x[c->n] = lon;
            c->y[c->n] = t->v[r * t->n_cols + (size_t)klat] * RAD2DEG;
            c->n++;
        }
        c->color = COL_BODY0 + (PLINT)(i % (N_COLS - COL_BODY0));
        c->style = body_style(i, 0);
        c->width = body_width(i);
        body_label(d, i, c->label, sizeof c->label);
    }
    /* the instantaneous impact point's trace of each body (iip_lat, iip_lon of dof3 and
     * dof6 in its phase files; NAN rows, no impact, break it), on the whole map: a thinner
     * line of the body's colour in its second style, no start and end marks (set 1). Bodies
     * flying together share the trace: a phase's is drawn once, with the first body that
     * flies in it. */
    unsigned char *drawn = calloc(d->n_phases + 1, 1);
    if (drawn == NULL)
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
    for (size_t i = 0; !site && st == LV_OK && i < d->n_bodies && p->n_c < MAX_CURVES; i++) {
        const lv_plot_body *b = &d->bodies[i];
        size_t n_ok = 0, n_rows = 0;
        for (size_t j = 0; j < b->n; j++) {
            const lv_results_table *t = d->phases[b->phase[j]].csv;
            const long klat = lv_results_table_col(t, "iip_lat");
            const long klon = lv_results_table_col(t, "iip_lon");
            if (t == NULL || klat < 0 || klon < 0 || drawn[b->phase[j]])
                continue;
            n_rows += t->n_rows + 1;
            for (size_t r = 0; r < t->n_rows; r++)
                n_ok += isfinite(t->v[r * t->n_cols + (size_t)klat]) &&
                        isfinite(t->v[r * t->n_cols + (size_t)klon]);
        }
        if (n_ok < 2)
            continue;
        curve *c = &p->c[p->n_c++];
        c->x = malloc(n_rows * sizeof *c->x);
        c->y = malloc(n_rows * sizeof *c->y);
        if (c->x == NULL || c->y == NULL) {
            st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
            break;
        }
        double last = NAN; /* the last finite longitude: continuous across +-180 deg */
        for (size_t j = 0; j < b->n; j++) {
            const lv_results_table *t = d->phases[b->phase[j]].csv;
            const long klat = lv_results_table_col(t, "iip_lat");
            const long klon = lv_results_table_col(t, "iip_lon");
            if (t == NULL || klat < 0 || klon < 0 || drawn[b->phase[j]])
                continue;
            drawn[b->phase[j]] = 1;
            for (size_t r = 0; r < t->n_rows; r++) {
                double lon = t->v[r * t->n_cols + (size_t)klon] * RAD2DEG;
                if (isfinite(last) && isfinite(lon))
                    lon += 360.0 * round((last - lon) / 360.0);
                if (isfinite(lon))
                    last = lon;
                c->x[c->n] = lon;
                c->y[c->n] = t->v[r * t->n_cols + (size_t)klat] * RAD2DEG;
                c->n++;
            }
        }
        c->color = COL_BODY0 + (PLINT)(i % (N_COLS - COL_BODY0));
        c->style = body_style(i, 1);
        c->width = 0.6 * body_width(i);
        c->set = 1;
        char body[112];
        body_label(d, i, body, sizeof body);
        snprintf(c->label, sizeof c->label, "IIP %s", body);
    }
    free(drawn);
    /* a track that never leaves the launch site (a vertical flight) makes an empty map */
    double extent = 0.0;
    for (size_t j = 0; st == LV_OK && j < p->n_c; j++)
        for (size_t r = 0; r < p->c[j].n; r++) {
            const double dlat = p->c[j].y[r] - p->c[j].y[0];
            const double dlon = (p->c[j].x[r] - p->c[j].x[0]) * cos(p->c[j].y[0] / RAD2DEG);
            if (isfinite(dlat) && isfinite(dlon))
                extent = fmax(extent, hypot(dlat, dlon));
        }
    double xm = 0.0, ym = 0.0, half = 0.0;
    if (st == LV_OK && site && !site_window(d, p, &xm, &ym, &half)) {
        add_skip(list, stem, d->n_sites == 0 ? "no launch site: no phase file has 'lat' and 'lon'"
                                             : "no runway phase, and no track ends within 1 deg "
                                               "of the launch site");
        figure_free(&f);
        return LV_OK;
    }
    if (st == LV_OK && p->n_c > 0 && extent < 0.01) { /* deg: about 1 km */
        add_skip(list, stem, d->flat ? "flat world: every body flies within 1 km of "
                                                 "the launch site (no ground track to map)"
                                               : "every body stays within 1 km of the launch "
                                                 "site (no ground track to map)");
        figure_free(&f);
        return LV_OK;
    }
    if (st == LV_OK && p->n_c == 0) {
        add_skip(list, stem, "no body trajectory has 'lat' and 'lon'");
        figure_free(&f);
        return LV_OK;
    }
    if (st == LV_OK) {
        /* The tracks with a margin, at least 4 deg, widened so that a degree of longitude
         * (times cos latitude) and of latitude take about the same length on the page. */
        double xlo, xhi, ylo, yhi;
        range_of(p, 1, &xlo, &xhi);
        range_of(p, 0, &ylo, &yhi);
        double lon_span = fmax(xhi - xlo, 4.0), lat_span = fmax(yhi - ylo, 4.0);
        if (site) {
            xlo = xm - half / fmax(cos(ym / RAD2DEG), 0.2);
            xhi = xm + half / fmax(cos(ym / RAD2DEG), 0.2);
            ylo = ym - half;
            yhi = ym + half;
            lon_span = (xhi - xlo) / 1.3;
            lat_span = (yhi - ylo) / 1.3;
        }
        double coslat = fmax(cos(0.5 * (ylo + yhi) / RAD2DEG), 0.2);
        const double aspect = ((VP_X1 - VP_X0) * PAGE_W) / (0.78 * PAGE_H); /* viewport width / height */
        lon_span *= 1.3;
        lat_span *= 1.3;
        if (lon_span * coslat < aspect * lat_span)
            lon_span = aspect * lat_span / coslat;
        else
            lat_span = lon_span * coslat / aspect;
        xm = 0.5 * (xlo + xhi);
        ym = 0.5 * (ylo + yhi);
        f.xlo = xm - 0.5 * lon_span;
        f.xhi = xm + 0.5 * lon_span;
        f.mlo = fmax(ym - 0.5 * lat_span, -90.0);
        f.mhi = fmin(ym + 0.5 * lat_span, 90.0);
        int map_ok = 1;
        st = render_both(d, &f, plotdir, stem, list, &map_ok, err);
        if (st == LV_OK && site)
            add_note(list, "ground_track_site: the runway drawn is the part of it a runway phase "
                           "rolled on, from its threshold (triangle)");
        else if (st == LV_OK && !map_ok)
            add_note(list, "ground_track: PLplot's coastline data ('globe' shapefile, Debian "
                           "package libplplot-data) not found: latitude/longitude grid only");
        else if (st == LV_OK)
            add_note(list, "ground_track: coastlines from PLplot's 'globe' shapefile; "
                           "o marks the start, x the end of each body's track; the thin "
                           "lines 'IIP' trace the instantaneous impact point");
    }
    figure_free(&f);
    return st;
}

static lv_status draw_all(const lv_plot_data *d, const char *plotdir, lv_plot_list *list,
                          lv_err *err)
{
    /* the paper's Figure 10 first: the run at a glance */
    lv_status st = fig10(d, plotdir, list, err);
    for (size_t i = 0; i < sizeof quantities / sizeof quantities[0] && st == LV_OK; i++)
        st = quantity_figure(d, &quantities[i], plotdir, list, err);
    if (st == LV_OK)
        st = ground_track(d, plotdir, list, 0, err);
    if (st == LV_OK)
        st = ground_track(d, plotdir, list, 1, err);
    if (st == LV_OK)
        st = reference_figures(d, plotdir, list, err);
    return st;
}

lv_status lv_plot_draw_figures(const lv_plot_data *d, const char *plotdir, lv_plot_list *list,
                               lv_err *err)
{
    list->draw_role = DRAW_ALL;
    list->draw_index = 0;
    int fds[2] = {-1, -1};
    pid_t pid = -1;
    if (single_threaded() && pipe(fds) == 0) {
        /* nothing buffered for the child to write twice, should PLplot ever exit() in it */
        fflush(NULL);
        const pid_t parent = getpid();
        pid = fork();
        if (pid == 0) { /* the child: the odd figures; its list is a copy, thrown away */
#ifdef __linux__
            /* the parent may have died before the request: then it would never come */
            if (prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || getppid() != parent)
                _exit(1);
#else
            (void)parent;
#endif
            close(fds[0]);
            child_msg msg;
            memset(&msg, 0, sizeof msg);
            list->draw_role = DRAW_ODD;
            msg.st = draw_all(d, plotdir, list, &msg.err);
            const ssize_t w = write(fds[1], &msg, sizeof msg);
            _exit(w == (ssize_t)sizeof msg ? 0 : 1);
        }
        close(fds[1]);
        if (pid > 0)
            list->draw_role = DRAW_EVEN;
        else
            close(fds[0]); /* no fork: draw everything here */
    }
    lv_status st = draw_all(d, plotdir, list, err);
    if (pid > 0) { /* the child's figures and its verdict */
        child_msg msg;
        memset(&msg, 0, sizeof msg);
        ssize_t got;
        while ((got = read(fds[0], &msg, sizeof msg)) < 0 && errno == EINTR) {
        }
        int status = 0;
        while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
        }
        close(fds[0]);
        if (st == LV_OK && (got != (ssize_t)sizeof msg || !WIFEXITED(status)))
            st = lv_fail(err, LV_ERR_IO, "%s: the process drawing half of the figures ended "
                                         "without a word%s",
                         plotdir, WIFSIGNALED(status) ? " (killed by a signal)" : "");
        else if (st == LV_OK && msg.st != LV_OK) {
            st = msg.st;
            if (err != NULL)
                *err = msg.err;
        }
    }
    return st;
}
