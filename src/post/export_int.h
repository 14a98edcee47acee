/* export_int.h - internal: a results folder (summary.json + body CSVs, read by post/results.h)
 * as the trajectory exports see it, and the helpers the CZML, KML and OEM writers share (not
 * exported). Contract of the files: docs/exports.md. */
#ifndef LV_POST_EXPORT_INT_H
#define LV_POST_EXPORT_INT_H

#include <stddef.h>
#include <stdio.h>

#include "core/utc.h"
#include "lvsim/lv_status.h"
#include "post/results.h"

#define LV_EX_PATH_CAP 4352 /* bytes of a file path in OUTDIR */

typedef struct lv_ex_row {
    double t;                  /* s, mission time */
    double lat, lon, h;        /* rad, rad, m: WGS-84 geodetic */
    double r_eci[3], v_eci[3]; /* m, m/s: lvsim's ECI (docs/frames.md); planet world only */
    double iip_lat, iip_lon;   /* rad: the instantaneous impact point (iip_lat, iip_lon of
                                  docs/models.md); NAN: no impact, or no such column */
    size_t line;               /* line of the body CSV, for messages */
} lv_ex_row;

/* Phases and events as the results reader gives them (post/results.h). */
typedef lv_results_event lv_ex_event;
typedef lv_results_phase lv_ex_phase;

/* The rows of one body in one phase: rows[first .. first + n) of the body. */
typedef struct lv_ex_track {
    size_t phase; /* position in lv_ex_run.phases */
    size_t first, n;
} lv_ex_track;

typedef struct lv_ex_body {
    const char *name;    /* borrowed from the results */
    char *path;          /* OUTDIR/body_<stage>.csv */
    lv_ex_row *rows;     /* CSV order; of rows with the same phase and time only the last */
    size_t n_rows;
    lv_ex_track *tracks; /* in the order of the CSV (phase start times) */
    size_t n_tracks;
    int has_eci;         /* r_eci_x .. v_eci_z columns present */
    int has_iip;         /* iip_lat, iip_lon columns present (rows may still be NAN) */
} lv_ex_body;

typedef struct lv_ex_run {
    const char *outdir;
    const char *mission; /* summary "mission" */
    lv_tai epoch;        /* summary "epoch" on the TAI scale (core/utc.h) */
    char time_note[256]; /* lv_utc_note over the done phases' span, or "" */
    int flat;            /* world "flat" (no OEM) */
    const char *planet;  /* summary "planet" when given, else NULL (Earth assumed, checked) */
    const lv_ex_phase *phases; /* the results' phases; every done one has finite times */
    size_t n_phases;
    int *phase_body;     /* per phase: a body flying in it (its rows give event positions); -1 */
    lv_ex_body *bodies;
    size_t n_bodies;
    double t0, t1;       /* s: first start and last end of the done phases */
    const lv_results *res; /* the folder as read (phase CSVs, summary JSON for the models) */
    struct lv_export_report *rep; /* what was written or not, or NULL */
} lv_ex_run;

/* Adds an item to r->rep (when there is one): `file` written, or `note` why not (printf). */
void lv_ex_report(const lv_ex_run *r, const char *format, const char *file, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* Time t (SI seconds since the epoch) as whole TAI microseconds (the resolution of every
 * written time) and as ISO 8601 UTC text "YYYY-MM-DDThh:mm:ss[.ffffff]" + suffix ("Z" or ""),
 * fraction only when not zero, leap seconds counted: an instant inside one is 23:59:60.ffffff.
 * lv_ex_iso_no60 writes such an instant as 23:59:59.999999 (KML's xsd:dateTime has no second
 * 60) and returns 1 for it. buf: at least 48 bytes. docs/exports.md, "Times". */
lv_tai lv_ex_ticks(const lv_ex_run *r, double t);
void lv_ex_iso(const lv_ex_run *r, double t, const char *suffix, char *buf, size_t cap);
int lv_ex_iso_no60(const lv_ex_run *r, double t, const char *suffix, char *buf, size_t cap);

/* The same text as lv_ex_iso (no60 0) or lv_ex_iso_no60 (no60 1; the return value is its
 * in-leap flag) for the many times of a trajectory, without ERFA for each: `c` remembers the
 * UTC day of the last call that went through lv_utc_format, and a later time in the first
 * 86399 s of that day is written from it by arithmetic on whole microseconds. Only where TAI -
 * UTC is a whole number of seconds (1972 on, and before 1960 where lvsim takes it as 0): a
 * day's seconds then are SI seconds and a leap second can only come after 23:59:59, which is
 * never cached (docs/exports.md, "Times"). A zeroed lv_ex_clock is an empty one. */
typedef struct lv_ex_clock {
    lv_tai day0;   /* TAI microseconds at 00:00:00 UTC of the cached day */
    int ok;        /* 1: day0 and date hold a day */
    char date[12]; /* "YYYY-MM-DD" */
} lv_ex_clock;
int lv_ex_clock_iso(const lv_ex_run *r, lv_ex_clock *c, double t, int no60, const char *suffix,
                    char *buf, size_t cap);

/* Geodetic position of body b at time t inside track k (linear between rows; clamped). */
void lv_ex_locate(const lv_ex_body *b, const lv_ex_track *k, double t, double *lat, double *lon,
                  double *h);
/* Track of body b for phase p, or NULL. */
const lv_ex_track *lv_ex_track_of(const lv_ex_body *b, size_t p);

/* Colour of phase p (palette by summary index): r, g, b in 0..255. */
void lv_ex_colour(const lv_ex_run *r, size_t p, int rgb[3]);

/* Label of event e: its name as summary.json gives it ("burnout", "impact", "stage 'stage3'
 * thrust table breakpoint t = 481 s"), "time event" when it has none. */
const char *lv_ex_event_label(const lv_ex_event *e);
/* Label of marker k of phase p: k = 0 its start ("separation (P2)" where the stack splits,
 * else "P2 start"), k >= 1 its events by their names (lv_ex_event_label). */
void lv_ex_marker_label(const lv_ex_run *r, size_t p, size_t k, char *buf, size_t cap);

/* JSON in cJSON_Print's layout (export_czml.c, which streams its document with them).
 * lv_ex_json_number: d into buf (LV_EX_JSON_NUM_CAP bytes) as lv_json_print writes numbers
 * (post/json_print.h): "null" for NaN and infinities, else the shortest decimal text that
 * reads back to d (io/numfmt.h: %.17g's layout, '.' whatever the locale; cJSON 1.7.15's own
 * 15 digits read back to another double for 8.5 % of trajectory-like numbers). Returns the length.
 * lv_ex_json_string: s quoted and escaped as print_string_ptr does: \" \\ \b \f \n \r \t,
 * other bytes below 0x20 as \u00XX, every other byte (UTF-8) as it is; NULL as "". */
#define LV_EX_JSON_NUM_CAP 32
size_t lv_ex_json_number(double d, char *buf);
void lv_ex_json_string(FILE *f, const char *s);

/* An export: one file src/post/export_<name>.c defines its writer and this descriptor, one line
 * in the table of export.c registers it. Its flag in lv_export_run's `formats` is 1u << (its
 * position in the table): the order of the table is the public flags' (LV_EXPORT_CZML, ..). */
typedef struct lv_ex_format {
    const char *name;        /* "czml": the word of --format/--outputs and lv_export_item.format;
                                at most 7 characters */
    const char *files;       /* what it writes in OUTDIR, as the docs say it: "mission.czml",
                                "<stage>.oem" */
    const char *pattern;     /* the same as an fnmatch(3) pattern, for the results folder's
                                ownership (outdir.c): "mission.czml", "*.oem" */
    const char *description; /* one line, for `lvsim formats`, the docs and Python */
    /* Writes its files into r->outdir (through io/atomic.h) and reports each one, or why none
     * was written, with lv_ex_report. */
    lv_status (*write)(const lv_ex_run *r, lv_err *err);
} lv_ex_format;

extern const lv_ex_format lv_ex_czml; /* export_czml.c */
extern const lv_ex_format lv_ex_kml;  /* export_kml.c */
extern const lv_ex_format lv_ex_oem;  /* export_oem.c: OUTDIR/<body>.oem for the bodies with
                                         orbital portions (docs/exports.md) */

/* A stage's shape for the vehicle models (docs/exports.md, "Vehicle models"): m. */
typedef struct lv_ex_shape {
    double length, diameter, span; /* span 0: no wing */
} lv_ex_shape;
/* A binary glTF 2.0 (.glb, malloc'ed into *glb, *len bytes) of the stages st[0] (aft) ..
 * st[n-1] (nose) in a row along the body x axis, the origin at the middle of the stack:
 * cylinders in two greys, a nose cone (and any wing and fin) in colour rgb (0..255). glTF
 * axes: body x = +z, body y = -x, body z = -y (export_glb.c). Errors: LV_ERR_NOMEM. */
lv_status lv_ex_glb_stack(const lv_ex_shape *st, size_t n, const int rgb[3], unsigned char **glb,
                          size_t *len, lv_err *err);
/* p[0..n) as RFC 4648 base64 with padding, NUL-terminated, malloc'ed; NULL: no memory. */
char *lv_ex_base64(const unsigned char *p, size_t n);

/* The registered exports, NULL-terminated (export.c), and their number. */
extern const lv_ex_format *const lv_ex_formats[];
size_t lv_ex_format_count(void);

#endif
