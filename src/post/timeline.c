/* timeline.c - a body's timeline (liblvsim_post, lv_summary.h): lift-off, max-q, the end of
 * every phase it flies in (by the user's name of the end, `name: MECO`, or a label made from
 * the end condition), burnouts and named events within its phases, and each separation of
 * stages it takes part in, once; each with the time, altitude, speed, Mach number and dynamic
 * pressure of the row that gives it (never interpolated). From a run's rows in memory, so
 * that summary.json (summary.c) and `lvsim run`'s console table tell the same.
 * docs/result-files.md ("timeline"). */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "lvsim/lv_atmosphere.h"
#include "lvsim/lv_io.h"
#include "lvsim/lv_mission.h"
#include "lvsim/lv_summary.h"

#define START_SPEED_MAX 1.0 /* m/s: a root phase starting slower than this lifts off */

/* The columns a row's values come from; -1 when the model has none. */
typedef struct tl_cols {
    long t, h, v, mach, q, rho;
} tl_cols;

static long column(const lv_result *res, const char *a, const char *b)
{
    size_t c;
    if (lv_result_column(res, a, &c, NULL) == LV_OK)
        return (long)c;
    if (b != NULL && lv_result_column(res, b, &c, NULL) == LV_OK)
        return (long)c;
    return -1;
}

static tl_cols find_cols(const lv_result *res)
{
    tl_cols c = {column(res, "time", NULL), column(res, "h", "z"), column(res, "v_rel", "speed"),
                 column(res, "mach", NULL), column(res, "q_dyn", NULL), column(res, "rho", NULL)};
    return c;
}

static double val(const lv_result *res, size_t r, long c)
{
    return c >= 0 ? lv_result_value(res, r, (size_t)c) : NAN;
}

typedef struct tl_build {
    lv_timeline_row *rows;
    size_t *seq; /* insertion order: simultaneous events keep it */
    size_t n, cap;
} tl_build;

/* A new row with the values of row r of phase k's rows. NULL: out of memory. */
/* Drops a last UTF-8 sequence that a cut at the buffer's end left incomplete (a label longer
 * than LV_TIMELINE_LABEL_MAX bytes: "separation of" many long stage names), so that the JSON,
 * the report and the console get valid UTF-8. Every cut in this file is at the label's end. */
static void utf8_fit(char *s)
{
    size_t n = strlen(s), i = n;
    while (i > 0 && ((unsigned char)s[i - 1] & 0xC0u) == 0x80u) /* continuation bytes */
        i--;
    if (i == 0 || ((unsigned char)s[i - 1] & 0x80u) == 0)
        return; /* ASCII last (or nothing but continuations: left as it is) */
    const unsigned char lead = (unsigned char)s[i - 1];
    const size_t len = lead >= 0xF0u ? 4 : lead >= 0xE0u ? 3 : lead >= 0xC0u ? 2 : 1;
    if (n - (i - 1) < len)
        s[i - 1] = '\0';
}

static lv_timeline_row *add(tl_build *b, const lv_run *run, size_t k, size_t r, const char *kind,
                            const char *label)
{
    if (b->n == b->cap) {
        const size_t cap = b->cap ? 2 * b->cap : 16;
        lv_timeline_row *rows = realloc(b->rows, cap * sizeof *rows);
        if (rows == NULL)
            return NULL;
        b->rows = rows;
        size_t *seq = realloc(b->seq, cap * sizeof *seq);
        if (seq == NULL)
            return NULL;
        b->seq = seq;
        b->cap = cap;
    }
    const lv_result *res = lv_run_rows(run, k);
    const tl_cols c = find_cols(res);
    lv_timeline_row *w = &b->rows[b->n];
    memset(w, 0, sizeof *w);
    snprintf(w->label, sizeof w->label, "%s", label);
    utf8_fit(w->label);
    w->kind = kind;
    w->phase = lv_mission_phase_name(lv_run_mission(run), k);
    w->row = r;
    w->t = val(res, r, c.t);
    w->h = val(res, r, c.h);
    w->speed = val(res, r, c.v);
    /* Mach and q where the atmosphere model is defined (rho > 0, h <= 1000 km), as the
     * figures draw them: none above it */
    const double rho = val(res, r, c.rho);
    const int air = c.rho < 0 || (rho > 0.0 && w->h <= LV_ATMO_ALT_MAX);
    w->mach = air ? val(res, r, c.mach) : NAN;
    w->q = air ? val(res, r, c.q) : NAN;
    b->seq[b->n] = b->n;
    b->n++;
    return w;
}

/* The first row at time t (an event instant has two: the one before it), else the last
 * before it; 0 when none is. */
static size_t row_at(const lv_result *res, double t)
{
    const long ct = column(res, "time", NULL);
    size_t best = 0;
    for (size_t r = 0; ct >= 0 && r < lv_result_rows(res); r++) {
        const double x = val(res, r, ct);
        if (x == t)
            return r;
        if (x < t)
            best = r;
    }
    return best;
}

/* "110 km", "400 m/s", "53000 kg": a value in its unit, metres from 1 km on in km. */
static void value_text(char *buf, size_t cap, double v, const char *unit)
{
    if (unit != NULL && strcmp(unit, "m") == 0 && fabs(v) >= 1000.0)
        snprintf(buf, cap, "%.10g km", v / 1000.0);
    else if (unit == NULL || unit[0] == '\0' || strcmp(unit, "1") == 0)
        snprintf(buf, cap, "%.10g", v);
    else
        snprintf(buf, cap, "%.10g %s", v, unit);
}

/* The label of an end without a user's name, from its condition: "burnout", "impact",
 * "lift-off", "altitude 110 km", "speed 400 m/s", "time 5400 s", "peri_alt 200 km",
 * "propellant_left 53000 kg"; "stop_time 140 s" (its time limit); "failed". */
static void end_text(const lv_phase_result *pr, const lv_result *res, char *buf, size_t cap)
{
    const lv_sim_report *rep = &pr->report;
    if (pr->state == LV_PHASE_FAILED || rep->reason == LV_STOP_FAILED) {
        snprintf(buf, cap, "failed");
        return;
    }
    if (rep->reason == LV_STOP_TIME) {
        char num[64];
        value_text(num, sizeof num, pr->t_stop, "s");
        snprintf(buf, cap, "stop_time %s", num);
        return;
    }
    const char *name = rep->stop_name;
    char base[LV_EVENT_NAME_MAX];
    snprintf(base, sizeof base, "%s", name);
    /* the second end of a kind is "altitude_2": shown by its kind */
    char *us = strrchr(base, '_');
    size_t col;
    if (us != NULL && us[1] != '\0' && strspn(us + 1, "0123456789") == strlen(us + 1) &&
        lv_result_column(res, base, &col, NULL) != LV_OK)
        *us = '\0';
    if (strcmp(base, "liftoff") == 0) {
        snprintf(buf, cap, "lift-off");
        return;
    }
    const double v = pr->end_value;
    if (isnan(v) || strcmp(base, "burnout") == 0 || strcmp(base, "apogee") == 0 ||
        (strcmp(base, "impact") == 0 && v == 0.0)) {
        snprintf(buf, cap, "%s", base);
        return;
    }
    const char *unit = strcmp(base, "altitude") == 0 || strcmp(base, "impact") == 0 ? "m"
                       : strcmp(base, "speed") == 0                                 ? "m/s"
                       : strcmp(base, "time") == 0                                  ? "s"
                       : lv_result_column(res, base, &col, NULL) == LV_OK
                           ? lv_result_unit(res, col)
                           : "";
    char num[64];
    value_text(num, sizeof num, v, unit);
    snprintf(buf, cap, "%.40s %.40s", base, num);
}

/* The stages of phase k not carried by any of its done children (a jettisoned fairing). */
static int in_phase(const lv_phase_info *p, size_t s)
{
    for (size_t i = 0; i < p->n_stages; i++)
        if (p->stages[i] == s)
            return 1;
    return 0;
}

/* "a+b" of the stages of p that `keep` says, in p's order (bottom first). */
static void stage_list(const lv_mission *m, const lv_phase_info *p, const unsigned char *keep,
                       char *buf, size_t cap)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < p->n_stages && used < cap; i++)
        if (keep[i])
            used += (size_t)snprintf(buf + used, cap - used, "%s%s", used ? "+" : "",
                                     lv_mission_stage_name(m, p->stages[i]));
}

/* Phase k's separation, if its children carry fewer stages than it does: the row of body s
 * (the first row of its child that carries s, or k's last row when s flies no further) and
 * its label: the user's (`separation: {name: ...}` of the first child that has one), else
 * "separation of X": X the stages that the child carrying the most stages does not carry
 * (the stack goes on, the booster or the fairing leaves, whether or not the part that leaves
 * flies a phase of its own); when two children carry equally many, the part that holds k's
 * bottom (burning) stage (a spent stage under two payloads). 0: none. */
static int separation(const lv_run *run, size_t k, size_t s, size_t *k_row, char *label,
                      size_t cap, int *named)
{
    const lv_mission *m = lv_run_mission(run);
    const size_t n = lv_mission_phase_count(m);
    lv_phase_info p;
    lv_mission_phase_info(m, k, &p);
    if (p.n_stages > 64)
        return 0;
    unsigned char carried[64] = {0}, part[64] = {0};
    size_t child_of_s = (size_t)-1, child_of_bottom = (size_t)-1;
    size_t largest = (size_t)-1, largest_n = 0; /* the child carrying the most; -1 on a tie */
    int fewer = 0;
    const char *user = NULL; /* the first child's `separation: {name: ...}` */
    for (size_t c = 0; c < n; c++) {
        if (lv_mission_phase_parent(m, c) != (int)k || lv_run_result(run, c)->state != LV_PHASE_DONE)
            continue;
        lv_phase_info cp;
        lv_mission_phase_info(m, c, &cp);
        if (cp.n_stages >= p.n_stages) /* carries on whole (an alternative with the stack) */
            continue;
        fewer = 1;
        if (cp.n_stages > largest_n) {
            largest = c;
            largest_n = cp.n_stages;
        } else if (cp.n_stages == largest_n) {
            largest = (size_t)-1;
        }
        if (user == NULL)
            user = lv_mission_phase_separation_name(m, c);
        for (size_t i = 0; i < p.n_stages; i++)
            carried[i] = (unsigned char)(carried[i] | in_phase(&cp, p.stages[i]));
        if (child_of_s == (size_t)-1 && in_phase(&cp, s) && lv_run_rows(run, c) != NULL &&
            lv_result_rows(lv_run_rows(run, c)) > 0)
            child_of_s = c;
        if (child_of_bottom == (size_t)-1 && in_phase(&cp, p.stages[0]))
            child_of_bottom = c;
    }
    if (!fewer)
        return 0;
    if (largest != (size_t)-1) { /* the stack goes on: name what leaves it */
        lv_phase_info lp;
        lv_mission_phase_info(m, largest, &lp);
        for (size_t i = 0; i < p.n_stages; i++)
            part[i] = (unsigned char)!in_phase(&lp, p.stages[i]);
    } else if (child_of_bottom == (size_t)-1) { /* the bottom stage is dropped */
        for (size_t i = 0; i < p.n_stages; i++)
            part[i] = !carried[i];
    } else {
        lv_phase_info bp;
        lv_mission_phase_info(m, child_of_bottom, &bp);
        for (size_t i = 0; i < p.n_stages; i++)
            part[i] = (unsigned char)in_phase(&bp, p.stages[i]);
    }
    char what[LV_TIMELINE_LABEL_MAX];
    stage_list(m, &p, part, what, sizeof what);
    if (user != NULL)
        snprintf(label, cap, "%s", user);
    else
        snprintf(label, cap, "separation of %s", what);
    *named = user != NULL;
    *k_row = child_of_s;
    return 1;
}

static int by_time(const void *a, const void *b, const lv_timeline_row *rows)
{
    const size_t i = *(const size_t *)a, j = *(const size_t *)b;
    if (rows[i].t != rows[j].t && !isnan(rows[i].t) && !isnan(rows[j].t))
        return rows[i].t < rows[j].t ? -1 : 1;
    return i < j ? -1 : i > j;
}

/* Insertion sort of the order by time (a timeline has tens of rows); ties keep flight order. */
static void sort_rows(tl_build *b)
{
    for (size_t i = 1; i < b->n; i++)
        for (size_t j = i; j > 0 && by_time(&b->seq[j - 1], &b->seq[j], b->rows) > 0; j--) {
            const size_t x = b->seq[j];
            b->seq[j] = b->seq[j - 1];
            b->seq[j - 1] = x;
        }
}

/* Phase k's events within it (not its end): burnouts, and the events the user named. */
static int phase_events(tl_build *b, const lv_run *run, size_t k)
{
    const lv_phase_result *pr = lv_run_result(run, k);
    const lv_sim_report *rep = &pr->report;
    const lv_result *res = lv_run_rows(run, k);
    for (size_t i = 0; i < rep->n_event_log; i++) {
        const lv_event_record *e = &rep->event_log[i];
        const char *named = pr->event_labels != NULL ? pr->event_labels[i] : NULL;
        /* the event that ended the phase is its end's row (a model may log it twice) */
        const int stop = rep->reason == LV_STOP_EVENT && e->t == rep->end_time &&
                         strcmp(e->name, rep->stop_name) == 0;
        if (stop || (named == NULL && !(e->is_state && strcmp(e->name, "burnout") == 0)))
            continue;
        lv_timeline_row *w = add(b, run, k, row_at(res, e->t), "event",
                                 named != NULL ? named : e->name);
        if (w == NULL)
            return -1;
        /* as summary.json's events[].name: a state event's name, a time event's source */
        w->event = e->is_state && e->index >= 0 && (size_t)e->index < pr->n_event_names
                       ? pr->event_names[e->index]
                   : e->name[0] ? e->name
                                : "time event";
        w->named = named != NULL;
    }
    return 0;
}

lv_status lv_run_timeline(const lv_run *run, size_t s, lv_timeline **out, lv_err *err)
{
    *out = NULL;
    const lv_mission *m = lv_run_mission(run);
    const size_t n_ph = lv_mission_phase_count(m);
    if (s >= lv_mission_stage_count(m))
        return lv_fail(err, LV_ERR_INPUT, "lv_run_timeline: stage index %zu out of range", s);
    size_t *ks = calloc(n_ph + 1, sizeof *ks);
    lv_timeline *tl = calloc(1, sizeof *tl);
    tl_build b = {0};
    if (ks == NULL || tl == NULL) {
        free(ks);
        free(tl);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    tl->body = lv_mission_stage_name(m, s);
    const size_t n = lv_run_body_phases(run, s, ks);
    lv_status st = LV_OK;
    for (size_t i = 0; i < n && st == LV_OK; i++)
        if (lv_run_rows(run, ks[i]) == NULL)
            st = lv_fail(err, LV_ERR_INPUT, "the timeline of '%s' needs the run's rows (phase "
                         "'%s' kept none: lv_run_options.no_rows)", tl->body,
                         lv_mission_phase_name(m, ks[i]));
    /* max-q over every row of the body's phases where the atmosphere model is defined */
    double q_max = 0.0;
    size_t q_k = 0, q_r = 0;
    int nomem = 0;
    for (size_t i = 0; i < n && st == LV_OK && !nomem; i++) {
        const size_t k = ks[i];
        const lv_phase_result *pr = lv_run_result(run, k);
        const lv_result *res = lv_run_rows(run, k);
        const size_t nr = lv_result_rows(res);
        if (nr == 0)
            continue;
        const tl_cols c = find_cols(res);
        for (size_t r = 0; r < nr && c.q >= 0; r++) {
            const double q = val(res, r, c.q), rho = val(res, r, c.rho), h = val(res, r, c.h);
            if (isfinite(q) && rho > 0.0 && h <= LV_ATMO_ALT_MAX && q > q_max) {
                q_max = q;
                q_k = k;
                q_r = r;
            }
        }
        char label[LV_TIMELINE_LABEL_MAX];
        end_text(pr, res, label, sizeof label);
        const int takeoff = strcmp(label, "lift-off") == 0; /* a runway's lift-off end */
        if (i == 0) { /* the body's start: a lift-off, or a take-off roll's start */
            const double v0 = val(res, 0, c.v);
            const int root = lv_mission_phase_parent(m, k) < 0;
            /* a roll on the ground (a runway phase: its rows have the lift margin) starts on
             * the ground whether it lifts off or not (an aborted take-off, an overrun) */
            size_t col;
            const int roll = lv_result_column(res, "lift_margin", &col, NULL) == LV_OK;
            const char *lbl = takeoff ? "start of take-off roll"
                              : roll  ? "start of roll"
                              : root && !(fabs(v0) >= START_SPEED_MAX) ? "lift-off"
                                                                       : "start";
            nomem |= add(&b, run, k, 0, takeoff || roll ? "start" : root ? "liftoff" : "start",
                         lbl) == NULL;
        }
        nomem |= phase_events(&b, run, k) != 0;
        lv_timeline_row *w = nomem ? NULL
                                   : add(&b, run, k, nr - 1, takeoff ? "liftoff" : "end",
                                         pr->end_label != NULL ? pr->end_label : label);
        if (w == NULL) {
            nomem = 1;
            break;
        }
        w->named = pr->end_label != NULL;
        if (pr->state == LV_PHASE_CRASHED) { /* flown to a crash end (a roll off the runway) */
            lv_timeline_row *cw = add(&b, run, k, nr - 1, "crash", "crashed");
            if (cw == NULL) {
                nomem = 1;
                break;
            }
            cw->event = "crashed";
            w = &b.rows[b.n - 2]; /* add may have moved the rows */
        }
        w->event = pr->state == LV_PHASE_FAILED               ? "failed"
                   : pr->report.reason == LV_STOP_TIME        ? "stop_time"
                   : pr->report.reason == LV_STOP_EVENT       ? pr->report.stop_name
                                                              : "failed";
        size_t kc;
        int named = 0;
        if (separation(run, k, s, &kc, label, sizeof label, &named)) {
            w = kc != (size_t)-1 ? add(&b, run, kc, 0, "separation", label)
                                 : add(&b, run, k, nr - 1, "separation", label);
            nomem |= w == NULL;
            if (w != NULL)
                w->named = named;
        }
        /* a child of k that carries the body and crashed at its hand-off (a touchdown off
         * the runway or beyond the landing gear) is not flown: the crash is k's last row */
        for (size_t ch = 0; ch < n_ph && !nomem; ch++) {
            lv_phase_info cp;
            if (lv_mission_phase_parent(m, ch) != (int)k ||
                lv_run_result(run, ch)->state != LV_PHASE_CRASHED ||
                lv_result_rows(lv_run_rows(run, ch)) > 0) /* flown: its own row, below */
                continue;
            lv_mission_phase_info(m, ch, &cp);
            if (!in_phase(&cp, s))
                continue;
            w = add(&b, run, k, nr - 1, "crash", "crashed");
            nomem |= w == NULL;
            if (w != NULL)
                w->event = "crashed";
        }
    }
    if (st == LV_OK && !nomem && q_max > 0.0)
        nomem |= add(&b, run, q_k, q_r, "max_q", "max-q") == NULL;
    free(ks);
    if (st == LV_OK && nomem)
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
    if (st == LV_OK && b.n > 0) {
        sort_rows(&b);
        if ((tl->rows = malloc(b.n * sizeof *tl->rows)) == NULL)
            st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        for (size_t i = 0; st == LV_OK && i < b.n; i++)
            tl->rows[i] = b.rows[b.seq[i]];
        tl->n = st == LV_OK ? b.n : 0;
    }
    free(b.rows);
    free(b.seq);
    if (st != LV_OK) {
        lv_timeline_free(tl);
        return st;
    }
    *out = tl;
    return LV_OK;
}

void lv_timeline_free(lv_timeline *t)
{
    if (t == NULL)
        return;
    free(t->rows);
    free(t);
}
