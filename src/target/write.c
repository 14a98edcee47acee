/* write.c - the converged mission: the original file with each variable's value replaced where
 * the file writes it (the slot's line and column, libyaml's character column), in the unit
 * it is written in (degrees after a `_deg` key), and the targeting section's `start:` values
 * too; every other character unchanged. Each value is written with the fewest digits that
 * read back as the same double. Written into another folder, the files the mission reads by
 * relative paths (tables, coefficients, wind) are given paths relative to the new file's
 * folder. The written file is then loaded, run and compared with the point it was written
 * from (lv_target_write in lv_target.h). */
#define _XOPEN_SOURCE 700 /* realpath */

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/status.h"
#include "io/atomic.h"
#include "io/readfile.h"
#include "lvsim/lv_units.h"
#include "mission/yaml_tree.h"
#include "target/target_int.h"

typedef struct edit {
    size_t at, len;  /* bytes of the original text replaced */
    char text[40];
    char *long_text; /* a path: replaces text when set (owned) */
} edit;


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

/* ---- relative paths, when the file moves ---------------------------------------------------- */

/* The keys whose string values name files the mission reads (docs/mission-format.md). */
int lv_tw_path_key(const char *k)
{
    static const char *const keys[] = {"table", "file", "coefficients", "wind", "alpha_table",
                                       "CD", "CL", "CY", "CA", "CN", NULL};
    for (size_t i = 0; keys[i] != NULL; i++)
        if (strcmp(keys[i], k) == 0)
            return 1;
    return 0;
}

/* The folder of `path` (which need not exist yet) as an absolute, resolved path; NULL. */
char *lv_tw_dir_real(const char *path)
{
    const char *slash = strrchr(path, '/');
    char dir[LV_ATOMIC_PATH_MAX];
    if (slash == NULL)
        snprintf(dir, sizeof dir, ".");
    else if (slash == path)
        snprintf(dir, sizeof dir, "/");
    else
        snprintf(dir, sizeof dir, "%.*s", (int)(slash - path), path);
    return realpath(dir, NULL);
}

/* `target` (absolute, resolved) relative to folder `from` (absolute, resolved); absolute when
 * they share no folder but the root. */
char *lv_tw_relative_to(const char *target, const char *from)
{
    size_t common = 0, i = 0;
    for (; target[i] != '\0' && from[i] != '\0' && target[i] == from[i]; i++)
        if (target[i] == '/')
            common = i;
    if (from[i] == '\0' && target[i] == '/')
        common = i; /* from is a prefix folder of target */
    if (common == 0)
        return strdup(target);
    size_t ups = 0;
    for (const char *q = from + common; *q != '\0'; q++)
        ups += *q == '/' && q[1] != '\0';
    if (strcmp(from, "/") == 0)
        ups = 0;
    const char *rest = target + common + 1;
    const size_t n = 3 * ups + strlen(rest) + 1;
    char *out = malloc(n);
    if (out == NULL)
        return NULL;
    out[0] = '\0';
    for (size_t k = 0; k < ups; k++)
        strcat(out, "../");
    strcat(out, rest);
    return out;
}

char *lv_tw_rebase(const char *mdir, const char *odir, const char *key, const char *path,
                   size_t len, int *nomem)
{
    *nomem = 0;
    if (key == NULL || !lv_tw_path_key(key) || len == 0 || path[0] == '/' || strlen(path) != len)
        return NULL;
    char joined[2 * LV_ATOMIC_PATH_MAX];
    snprintf(joined, sizeof joined, "%s/%s", mdir, path);
    char *abs = realpath(joined, NULL);
    struct stat sb;
    if (abs == NULL || stat(abs, &sb) != 0 || !S_ISREG(sb.st_mode)) {
        free(abs);
        return NULL;
    }
    char *rel = lv_tw_relative_to(abs, odir);
    free(abs);
    *nomem = rel == NULL;
    return rel;
}

typedef struct path_walk {
    const char *text;
    size_t len;
    const char *mdir, *odir;  /* the mission's and the new file's folders (resolved) */
    edit *edits;
    size_t n, cap;
    lv_status st;
    lv_err *err;
    const char *path;
} path_walk;

static void walk_paths(path_walk *w, const lv_ynode *n, const char *key)
{
    if (w->st != LV_OK || n == NULL)
        return;
    if (n->kind == LV_YNODE_MAP) {
        for (size_t i = 0; i + 1 < n->n; i += 2)
            walk_paths(w, n->kids[i + 1], n->kids[i]->text);
        return;
    }
    if (n->kind == LV_YNODE_SEQ) {
        for (size_t i = 0; i < n->n; i++)
            walk_paths(w, n->kids[i], key);
        return;
    }
    int nomem = 0;
    char *rel = lv_tw_rebase(w->mdir, w->odir, key, n->text, n->len, &nomem);
    if (rel == NULL) {
        if (nomem)
            w->st = lv_fail(w->err, LV_ERR_NOMEM, "out of memory");
        return; /* not a file: a model's name, a number */
    }
    size_t at = offset_of(w->text, w->len, n->line, n->col);
    const int quoted = !n->plain;
    if (at != (size_t)-1 && quoted)
        at++; /* after the quote */
    if (at == (size_t)-1 || at + n->len > w->len || memcmp(w->text + at, n->text, n->len) != 0) {
        free(rel);
        w->st = lv_fail(w->err, LV_ERR_INPUT, "%s:%d:%d: the path '%s' is written with escapes: "
                        "write the converged mission into the mission's folder", w->path,
                        n->line, n->col, n->text);
        return;
    }
    int plain_ok = 1; /* a plain scalar that stays plain */
    for (const char *q = rel; *q != '\0'; q++)
        plain_ok &= (*q >= 'a' && *q <= 'z') || (*q >= 'A' && *q <= 'Z') ||
                    (*q >= '0' && *q <= '9') || *q == '.' || *q == '/' || *q == '_' || *q == '-';
    if (w->n == w->cap) {
        const size_t cap = w->cap ? 2 * w->cap : 8;
        edit *e = realloc(w->edits, cap * sizeof *e);
        if (e == NULL) {
            free(rel);
            w->st = lv_fail(w->err, LV_ERR_NOMEM, "out of memory");
            return;
        }
        w->edits = e;
        w->cap = cap;
    }
    edit *e = &w->edits[w->n++];
    memset(e, 0, sizeof *e);
    e->at = at;
    e->len = n->len;
    if (!quoted && !plain_ok) { /* quote it */
        e->long_text = malloc(strlen(rel) + 3);
        if (e->long_text != NULL)
            sprintf(e->long_text, "\"%s\"", rel);
        free(rel);
    } else {
        e->long_text = rel;
    }
    if (e->long_text == NULL)
        w->st = lv_fail(w->err, LV_ERR_NOMEM, "out of memory");
}

/* Edits giving every relative file path of the mission text a path from the new file's
 * folder (none when it is the mission's folder). */
static lv_status path_edits(const char *text, size_t len, const lv_mission_def *d,
                            const char *out, edit **edits, size_t *n, lv_err *err)
{
    *edits = NULL;
    *n = 0;
    char *mdir = realpath(d->dir, NULL), *odir = lv_tw_dir_real(out);
    lv_ynode *root = NULL;
    lv_status st = LV_OK;
    if (mdir == NULL || odir == NULL) {
        st = lv_fail(err, LV_ERR_IO, "%s: cannot resolve its folder", mdir == NULL ? d->dir : out);
        goto done;
    }
    if (strcmp(mdir, odir) == 0)
        goto done;
    if ((st = lv_yaml_load(text, len, d->path, &root, err)) != LV_OK)
        goto done;
    path_walk w = {text, len, mdir, odir, NULL, 0, 0, LV_OK, err, d->path};
    walk_paths(&w, root, NULL);
    st = w.st;
    *edits = w.edits;
    *n = w.n;
done:
    lv_yaml_free(root);
    free(mdir);
    free(odir);
    return st;
}

/* The header of a written file: lines that begin with this (a previous one is replaced). */
#define HEADER "# lvsim target:"

/* The length of the header lines at the start of text (after a byte-order mark at `at`). */
static size_t header_len(const char *text, size_t len, size_t at)
{
    size_t i = at;
    const size_t hl = strlen(HEADER);
    while (i + hl <= len && strncmp(text + i, HEADER, hl) == 0) {
        while (i < len && text[i] != '\n')
            i++;
        if (i < len)
            i++;
    }
    return i - at;
}

/* The header: where the file comes from and how each checked phase ended at the point
 * written (run r), a WARNING line for each that ended otherwise than assumed. */
static void write_header(FILE *fp, const lv_target *t, const lv_run *r)
{
    const lv_mission_def *d = t->m->def;
    fprintf(fp, HEADER " written from %s with the targeting's variables at the point solved "
            "for\n", d->path);
    size_t ok = 0;
    for (size_t i = 0; i < t->n_chk; i++) {
        const size_t k = t->chk[i];
        const lv_phase_result *res = lv_run_result(r, k);
        if (res->state != LV_PHASE_DONE)
            continue;
        const int got = res->end_index >= 0 ? res->end_index : LV_TEND_STOP_TIME;
        if (got == t->expect[k]) {
            ok++;
            continue;
        }
        fprintf(fp, HEADER " WARNING: phase '%s' ended by %s at t = %.10g s, not by %s, the "
                "end its constraints assume: the constraints are met on another trajectory "
                "than the one targeted\n", d->phases[k].name,
                lv_targeting_end_name(t->m, k, got), res->t_end,
                lv_targeting_end_name(t->m, k, t->expect[k]));
    }
    if (ok > 0) {
        fprintf(fp, HEADER " ended as the constraints assume:");
        for (size_t i = 0; i < t->n_chk; i++) {
            const size_t k = t->chk[i];
            const lv_phase_result *res = lv_run_result(r, k);
            const int got = res->end_index >= 0 ? res->end_index : LV_TEND_STOP_TIME;
            if (res->state == LV_PHASE_DONE && got == t->expect[k])
                fprintf(fp, " %s by %s at t = %.10g s%s", d->phases[k].name,
                        lv_targeting_end_name(t->m, k, got), res->t_end,
                        --ok > 0 ? "," : "");
        }
        fprintf(fp, "\n");
    }
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
        if (!is_cost && t->cons[i].path) { /* the extremum over the rows, in mission m */
            tg_con c = t->cons[i];
            c.f = tf;
            f[i] = tg_con_value(m, r, &c);
            continue;
        }
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
    size_t nedits = 0;
    lv_status st;
    if (x == NULL || path == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_target_write: NULL argument");
    if (worst != NULL)
        *worst = NAN;
    /* never the mission it reads or one of its data files (the caller decides on another
     * existing file: lvsim target refuses one without --force) */
    if ((st = lv_output_check(path, t->m, LV_OUTPUT_REPLACE, err)) != LV_OK)
        return st;
    if ((st = lv_read_file(d->path, LV_MISSION_FILE_MAX, "the mission file", &text, &len, err)) != LV_OK)
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
    edit *pe = NULL;
    size_t npe = 0;
    if ((st = path_edits(text, len, d, path, &pe, &npe, err)) != LV_OK) {
        free(pe);
        goto done;
    }
    if (npe > 0) {
        edit *all = realloc(edits, (ne + npe + 1) * sizeof *all);
        if (all == NULL) {
            for (size_t i = 0; i < npe; i++)
                free(pe[i].long_text);
            free(pe);
            st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
            goto done;
        }
        edits = all;
        memcpy(edits + ne, pe, npe * sizeof *pe);
        ne += npe;
    }
    free(pe);
    nedits = ne;
    qsort(edits, ne, sizeof *edits, edit_cmp);
    /* the point written, on this target's run: the reference */
    lv_err e;
    for (size_t j = 0; j < t->n; j++)
        if ((st = lv_run_set_index(t->run, t->vars[j].r.slot,
                                   t->vars[j].r.deg ? x[j] * LV_DEG : x[j], err)) != LV_OK)
            goto done;
    const lv_run_options opt = {.threads = 2, .no_rows = !tg_keep_rows(t), .want = t->want};
    lv_run_execute(t->run, &opt, &e);
    double cref = NAN, cnew = NAN;
    if ((st = finals_of(t->run, t->m, t, fref, &cref, err)) != LV_OK) {
        lv_fail_prefix(err, st, "the point written fails");
        goto done;
    }
    /* the header (after a byte-order mark), instead of the one a converged file has */
    size_t at = len >= 3 && (unsigned char)text[0] == 0xEF && (unsigned char)text[1] == 0xBB &&
                        (unsigned char)text[2] == 0xBF
                    ? 3
                    : 0;
    if ((st = lv_atomic_open(&a, path, err)) != LV_OK)
        goto done;
    fwrite(text, 1, at, a.fp);
    write_header(a.fp, t, t->run);
    at += header_len(text, len, at);
    for (size_t i = 0; i < ne; i++) {
        fwrite(text + at, 1, edits[i].at - at, a.fp);
        fputs(edits[i].long_text ? edits[i].long_text : edits[i].text, a.fp);
        at = edits[i].at + edits[i].len;
    }
    fwrite(text + at, 1, len - at, a.fp);
    if (fflush(a.fp) != 0) {
        st = lv_fail(err, LV_ERR_IO, "%s: cannot write: %s", a.tmp, LV_STRERROR(errno));
        goto done;
    }

    /* the written file (still under its temporary name: a file that fails here is not
     * left behind), loaded and run as `lvsim run` does: every phase */
    if ((st = lv_mission_load(a.tmp, &m2, err)) != LV_OK) {
        char msg[sizeof err->msg];
        const size_t nt = strlen(a.tmp);
        if (strncmp(err->msg, a.tmp, nt) == 0) /* the messages name the file to be */
            snprintf(msg, sizeof msg, "%s%s", path, err->msg + nt);
        else
            snprintf(msg, sizeof msg, "%s", err->msg);
        lv_fail(err, st, "%s: the converged values make a mission that does not load, not "
                "written: %s", path, msg);
        goto done;
    }
    if ((st = lv_run_create(m2, &r2, err)) != LV_OK)
        goto done;
    const lv_run_options all = {.threads = 2, .no_rows = !tg_keep_rows(t)};
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
                     "of its scale; not written", path, wname ? wname : "-", w, cdev);
    if (st == LV_OK)
        st = lv_atomic_commit(&a, err);
done:
    if (a.fp != NULL)
        lv_atomic_abort(&a);
    lv_run_free(r2);
    lv_mission_free(m2);
    free(text);
    for (size_t i = 0; edits != NULL && i < nedits; i++)
        free(edits[i].long_text);
    free(edits);
    free(fref);
    free(fnew);
    return st;
}
