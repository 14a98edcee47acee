/* write.c - the converged mission: the original file with each variable's value replaced where
 * the file writes it (the slot's line and column, libyaml's character column), in the unit
 * it is written in (degrees after a `_deg` key), and the targeting section's `start:` values
 * too; every other character unchanged. Each value is written with the fewest digits that
 * read back as the same double. The written file is then loaded, run and compared with the
 * point it was written from (lv_target_write in lv_target.h). */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "io/atomic.h"
#include "lvsim/lv_units.h"
#include "target/target_int.h"

typedef struct edit {
    size_t at, len;  /* bytes of the original text replaced */
    char text[40];
} edit;

static lv_status read_all(const char *path, char **out, size_t *len, lv_err *err)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return lv_fail(err, LV_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    size_t cap = 4096, n = 0;
    char *s = malloc(cap);
    while (s != NULL) {
        const size_t got = fread(s + n, 1, cap - n - 1, f);
        n += got;
        if (got == 0)
            break;
        if (n + 1 == cap) {
            char *g = realloc(s, 2 * cap);
            if (g == NULL) {
                free(s);
                s = NULL;
                break;
            }
            s = g;
            cap *= 2;
        }
    }
    const int bad = ferror(f);
    fclose(f);
    if (s == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    if (bad) {
        free(s);
        return lv_fail(err, LV_ERR_IO, "%s: read error", path);
    }
    s[n] = '\0';
    *out = s;
    *len = n;
    return LV_OK;
}

/* Byte offset of (line, column), both 1-based, column in characters (UTF-8); SIZE_MAX when
 * the file has no such place. */
static size_t offset_of(const char *s, size_t len, int line, int col)
{
    size_t i = 0;
    if (len >= 3 && (unsigned char)s[0] == 0xEF && (unsigned char)s[1] == 0xBB &&
        (unsigned char)s[2] == 0xBF)
        i = 3; /* a byte-order mark is no character of line 1 */
    for (int l = 1; l < line; l++) {
        while (i < len && s[i] != '\n')
            i++;
        if (i >= len)
            return (size_t)-1;
        i++;
    }
    for (int c = 1; c < col; c++) {
        if (i >= len || s[i] == '\n')
            return (size_t)-1;
        i++;
        while (i < len && ((unsigned char)s[i] & 0xC0) == 0x80)
            i++;
    }
    return i;
}

static int token_char(char ch)
{
    return (ch >= '0' && ch <= '9') || (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') ||
           ch == '+' || ch == '-' || ch == '.' || ch == '_';
}

/* 1 when the key the value at `at` belongs to ends with "_deg" (the value is in degrees). */
static int key_is_deg(const char *s, size_t at)
{
    size_t i = at;
    while (i > 0 && (s[i - 1] == ' ' || s[i - 1] == '\t' || s[i - 1] == '\n' || s[i - 1] == '\r'))
        i--;
    if (i == 0 || s[i - 1] != ':')
        return 0; /* a list item: no key */
    i--;
    while (i > 0 && (s[i - 1] == ' ' || s[i - 1] == '\t'))
        i--;
    size_t end = i;
    if (i > 0 && (s[i - 1] == '"' || s[i - 1] == '\'')) { /* a quoted key */
        const char q = s[i - 1];
        end = --i;
        while (i > 0 && s[i - 1] != q)
            i--;
    } else {
        while (i > 0 && token_char(s[i - 1]))
            i--;
    }
    return end - i >= 4 && strncmp(s + end - 4, "_deg", 4) == 0;
}

/* The shortest %.Ng that reads back as x. */
static void shortest(double x, char *buf, size_t cap)
{
    for (int p = 6; p <= 17; p++) {
        snprintf(buf, cap, "%.*g", p, x);
        if (strtod(buf, NULL) == x)
            return;
    }
}

/* The edit replacing the number at (line, col), which must read as `expect` (in the unit it is
 * written in: *deg says whether that is degrees when `in_si`, i.e. expect is SI). */
static lv_status make_edit(const char *s, size_t len, const char *path, lv_src_loc loc,
                           const char *what, double expect, int in_si, double value_si,
                           double value_named, int named_deg, edit *e, lv_err *err)
{
    const size_t at = offset_of(s, len, loc.line, loc.column);
    size_t end = at;
    while (at != (size_t)-1 && end < len && token_char(s[end]))
        end++;
    char tok[64];
    const size_t n = at == (size_t)-1 ? 0 : end - at;
    if (n == 0 || n >= sizeof tok)
        return lv_fail(err, LV_ERR_INPUT, "%s:%d:%d: %s: no number found at its position (was "
                       "the file changed after it was loaded?)", path, loc.line, loc.column, what);
    memcpy(tok, s + at, n);
    tok[n] = '\0';
    char *stop = NULL;
    const double written = strtod(tok, &stop);
    const int deg = in_si ? key_is_deg(s, at) : 0;
    const double as_read = deg ? written * LV_DEG : written;
    if (*stop != '\0' || !(fabs(as_read - expect) <= 1e-12 * fmax(1.0, fabs(expect))))
        return lv_fail(err, LV_ERR_INPUT, "%s:%d:%d: %s: found '%s' where the mission had %.17g "
                       "(was the file changed after it was loaded?)", path, loc.line, loc.column,
                       what, tok, deg ? expect / LV_DEG : expect);
    double v;
    if (!in_si)
        v = value_named; /* the targeting section: the variable's own unit */
    else if (deg)
        v = named_deg ? value_named : value_si / LV_DEG;
    else
        v = value_si;
    e->at = at;
    e->len = n;
    shortest(v, e->text, sizeof e->text);
    return LV_OK;
}

static int edit_cmp(const void *a, const void *b)
{
    const edit *x = a, *y = b;
    return x->at < y->at ? -1 : (x->at > y->at);
}

/* The phases' finals of a run, for the constraints and the cost. */
static lv_status finals_of(const lv_run *r, const lv_mission *m, const lv_target *t, double *f,
                           double *cost, lv_err *err)
{
    for (size_t i = 0; i <= t->mc; i++) {
        const int is_cost = i == t->mc;
        if (is_cost && !t->cost.present)
            break;
        const char *name = is_cost ? t->cost.name : t->cons[i].name;
        lv_tfinal tf;
        lv_status st = lv_targeting_resolve_final(m, name, &tf, err);
        if (st != LV_OK)
            return st;
        const lv_phase_result *res = lv_run_result(r, tf.phase);
        if (res == NULL || res->state != LV_PHASE_DONE)
            return lv_fail(err, LV_ERR_SOLVER, "'%s': %s", name,
                           res && res->error[0] ? res->error : "its phase did not run");
        const double v = res->final_values[tf.index];
        *(is_cost ? cost : &f[i]) = tf.deg ? v / LV_DEG : v;
    }
    return LV_OK;
}

lv_status lv_target_write(lv_target *t, const double *x, const char *path, double *worst,
                          lv_err *err)
{
    const lv_mission_def *d = t->m->def;
    char *text = NULL;
    size_t len = 0;
    edit *edits = NULL;
    double *fref = NULL, *fnew = NULL;
    lv_mission *m2 = NULL;
    lv_run *r2 = NULL;
    lv_atomic a = {0};
    lv_status st;
    if (x == NULL || path == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_target_write: NULL argument");
    if (worst != NULL)
        *worst = NAN;
    if ((st = read_all(d->path, &text, &len, err)) != LV_OK)
        return st;
    edits = calloc(2 * t->n + 1, sizeof *edits);
    fref = calloc(t->mc + 1, sizeof *fref);
    fnew = calloc(t->mc + 1, sizeof *fnew);
    if (edits == NULL || fref == NULL || fnew == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto done;
    }
    size_t ne = 0;
    for (size_t j = 0; j < t->n; j++) {
        const tg_var *v = &t->vars[j];
        const lv_slot_def *sd = &d->slots[v->r.slot];
        const double si = v->r.deg ? x[j] * LV_DEG : x[j];
        if (!(x[j] >= v->r.lo && x[j] <= v->r.hi)) {
            st = lv_fail(err, LV_ERR_INPUT, "variable '%s' = %g is outside [%g, %g]", v->name,
                         x[j], v->r.lo, v->r.hi);
            goto done;
        }
        if (sd->loc.line <= 0) {
            st = lv_fail(err, LV_ERR_INPUT, "variable '%s': the mission file does not write the "
                         "parameter (its value is a default): nowhere to put %g", v->name, x[j]);
            goto done;
        }
        char what[160];
        snprintf(what, sizeof what, "variable '%s'", v->name);
        if ((st = make_edit(text, len, d->path, sd->loc, what, sd->value, 1, si, x[j], v->r.deg,
                            &edits[ne++], err)) != LV_OK)
            goto done;
        if (v->start_loc.line > 0) {
            snprintf(what, sizeof what, "targeting: variable '%s': start", v->name);
            if ((st = make_edit(text, len, d->path, v->start_loc, what, v->r.start, 0, si, x[j],
                                v->r.deg, &edits[ne++], err)) != LV_OK)
                goto done;
        }
    }
    qsort(edits, ne, sizeof *edits, edit_cmp);
    if ((st = lv_atomic_open(&a, path, err)) != LV_OK)
        goto done;
    size_t at = 0;
    for (size_t i = 0; i < ne; i++) {
        fwrite(text + at, 1, edits[i].at - at, a.fp);
        fputs(edits[i].text, a.fp);
        at = edits[i].at + edits[i].len;
    }
    fwrite(text + at, 1, len - at, a.fp);
    if ((st = lv_atomic_commit(&a, err)) != LV_OK)
        goto done;

    /* the point written, on this target's run: the reference */
    lv_err e;
    for (size_t j = 0; j < t->n; j++)
        if ((st = lv_run_set_index(t->run, t->vars[j].r.slot,
                                   t->vars[j].r.deg ? x[j] * LV_DEG : x[j], err)) != LV_OK)
            goto done;
    const lv_run_options opt = {.threads = 2, .no_rows = 1, .want = t->want};
    lv_run_execute(t->run, &opt, &e);
    double cref = NAN, cnew = NAN;
    if ((st = finals_of(t->run, t->m, t, fref, &cref, err)) != LV_OK) {
        lv_fail_prefix(err, st, "the point written fails");
        goto done;
    }
    /* the written file, loaded and run as `lvsim run` does: every phase */
    if ((st = lv_mission_load(path, &m2, err)) != LV_OK) {
        lv_fail_prefix(err, st, "%s: the converged mission does not load (a file it reads by "
                       "a relative path? write it into the mission's folder)", path);
        goto done;
    }
    if ((st = lv_run_create(m2, &r2, err)) != LV_OK)
        goto done;
    const lv_run_options all = {.threads = 2, .no_rows = 1};
    lv_run_execute(r2, &all, &e); /* a failure elsewhere does not concern the finals */
    if ((st = finals_of(r2, m2, t, fnew, &cnew, err)) != LV_OK) {
        lv_fail_prefix(err, st, "%s: the converged mission", path);
        goto done;
    }
    double w = 0.0;
    const char *wname = NULL;
    for (size_t i = 0; i < t->mc; i++) {
        const double dev = fabs(fnew[i] - fref[i]) / t->cons[i].tol;
        if (!(dev <= w)) {
            w = dev;
            wname = t->cons[i].name;
        }
    }
    double cdev = 0.0;
    if (t->cost.present) {
        const double scale = t->cost_scale > 0.0 ? t->cost_scale
                             : t->cost.scale > 0.0 ? t->cost.scale
                                                   : fmax(1.0, fabs(cref));
        cdev = fabs(cnew - cref) / scale;
    }
    if (worst != NULL)
        *worst = w;
    if (!(w <= 1e-3) || !(cdev <= 1e-6))
        st = lv_fail(err, LV_ERR_SOLVER, "%s: running the converged mission does not reproduce "
                     "the targeted finals: %s differs by %.3g of its tolerance, the cost by %.3g "
                     "of its scale", path, wname ? wname : "-", w, cdev);
done:
    if (a.fp != NULL)
        lv_atomic_abort(&a);
    lv_run_free(r2);
    lv_mission_free(m2);
    free(text);
    free(edits);
    free(fref);
    free(fnew);
    return st;
}
