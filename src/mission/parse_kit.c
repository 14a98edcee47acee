/* parse_kit.c - the mission parser's tools (parse_kit.h), shared by the parser's files and the
 * phase-model types that parse their own keys: messages at file:line:column, slots, mappings,
 * typed scalars and names, data-file paths and table references. Format:
 * docs/mission-format.md. */
#define _POSIX_C_SOURCE 200809L /* stat() */

#include "mission/mission.h"

#include <errno.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/names.h"
#include "lvsim/lv_units.h"
#include "mission/parse_int.h"

/* ---- messages ------------------------------------------------------------------------- */

lv_status lv_pk_fail(const lv_pctx *c, const lv_ynode *at, const char *fmt, ...)
{
    char msg[LV_ERR_MSG_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return lv_fail(c->err, LV_ERR_INPUT, "%s:%d:%d: %s", c->file, at->line, at->col, msg);
}

lv_status lv_pk_nomem(const lv_pctx *c)
{
    return lv_fail(c->err, LV_ERR_NOMEM, "%s: out of memory", c->file);
}

char *lv_pk_strdup(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d != NULL)
        memcpy(d, s, n);
    return d;
}

/* ---- slots -------------------------------------------------------------------------------- */

int lv_range_holds(lv_range r, double v)
{
    if (!isfinite(v))
        return 0;
    if (r.lo_open ? !(v > r.lo) : !(v >= r.lo))
        return 0;
    if (r.hi_open ? !(v < r.hi) : !(v <= r.hi))
        return 0;
    return 1;
}

/* Ten digits: a bound such as pi/2 rad reads 1.570796327, not 1.5708 (which it is not). */
void lv_range_text(lv_range r, char *text, size_t cap)
{
    const int lo = isfinite(r.lo), hi = isfinite(r.hi);
    if (!lo && !hi)
        snprintf(text, cap, "finite");
    else if (lo && !hi)
        snprintf(text, cap, "%s %.10g", r.lo_open ? ">" : ">=", r.lo);
    else if (!lo)
        snprintf(text, cap, "%s %.10g", r.hi_open ? "<" : "<=", r.hi);
    else
        snprintf(text, cap, "%s %.10g and %s %.10g", r.lo_open ? ">" : ">=", r.lo,
                 r.hi_open ? "<" : "<=", r.hi);
}

/* Slot names are unique: two stages, engines or phases whose names make the same parameter
 * name ("a.b" + "c" and "a" + "b.c") are refused, after the structural checks. */
static int slot_cmp(const void *a, const void *b)
{
    const lv_slot_def *const *x = a, *const *y = b;
    return strcmp((*x)->name, (*y)->name);
}

lv_status lv_pk_check_slot_names(const lv_pctx *c)
{
    lv_mission_def *m = c->m;
    if (m->n_slots < 2)
        return LV_OK;
    const lv_slot_def **v = malloc(m->n_slots * sizeof *v);
    if (v == NULL)
        return lv_pk_nomem(c);
    for (size_t i = 0; i < m->n_slots; i++)
        v[i] = &m->slots[i];
    qsort(v, m->n_slots, sizeof *v, slot_cmp);
    lv_status st = LV_OK;
    for (size_t i = 1; i < m->n_slots && st == LV_OK; i++)
        if (strcmp(v[i - 1]->name, v[i]->name) == 0) {
            const lv_slot_def *a = v[i - 1], *b = v[i];
            if (a->loc.line > b->loc.line || (a->loc.line == b->loc.line && a->loc.column > b->loc.column)) {
                const lv_slot_def *t = a;
                a = b;
                b = t;
            }
            st = lv_fail(c->err, LV_ERR_INPUT,
                         "%s:%d:%d: the parameter name '%s' comes out twice (first at line %d): "
                         "rename a stage, engine or phase",
                         m->path, b->loc.line, b->loc.column, b->name, a->loc.line);
        }
    free(v);
    return st;
}

lv_status lv_mission_def_add_slot(lv_mission_def *m, const char *name, const char *unit,
                                  double value, lv_range range, lv_slot_owner owner,
                                  size_t owner_index, lv_src_loc loc, lv_slot *out, lv_err *err)
{
    if (m->n_slots == m->cap_slots) {
        size_t cap = m->cap_slots ? 2 * m->cap_slots : 32;
        lv_slot_def *grown = realloc(m->slots, cap * sizeof *grown);
        if (grown == NULL)
            return lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", m->path);
        m->slots = grown;
        m->cap_slots = cap;
    }
    lv_slot_def *sd = &m->slots[m->n_slots];
    /* a dimensionless number's unit is "1" (lv_units.h), however the caller wrote it */
    *sd = (lv_slot_def){lv_pk_strdup(name), lv_pk_strdup(LV_UNIT_ONE(unit) ? "1" : unit), value,
                        range, owner, owner_index, loc};
    if (sd->name == NULL || sd->unit == NULL) {
        free(sd->name);
        free(sd->unit);
        return lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", m->path);
    }
    *out = m->n_slots++;
    return LV_OK;
}

lv_status lv_pk_slot(const lv_pctx *c, const lv_ynode *v, const char *what, const char *key,
                     const char *name, const char *unit, lv_range range, int deg, lv_slot *out)
{
    double x;
    lv_status st = lv_pk_num(c, v, what, key, &x);
    if (st != LV_OK)
        return st;
    if (deg)
        x *= LV_DEG;
    if (!lv_range_holds(range, x)) {
        char rule[96];
        lv_range shown = range; /* the rule in the unit the value is written in */
        if (deg) {
            shown.lo /= LV_DEG;
            shown.hi /= LV_DEG;
        }
        lv_range_text(shown, rule, sizeof rule);
        const char *u = deg ? "deg" : unit;
        return lv_pk_fail(c, v, "%s: %s must be %s%s%s, found %g", what, key, rule,
                          u[0] ? " " : "", u, deg ? x / LV_DEG : x);
    }
    lv_src_loc loc = {v->line, v->col};
    return lv_mission_def_add_slot(c->m, name, unit, x, range, c->owner, c->owner_index, loc,
                                   out, c->err);
}

lv_status lv_pk_slot_default(const lv_pctx *c, const char *name, const char *unit, double value,
                             lv_range range, lv_slot *out)
{
    lv_src_loc none = {0, 0};
    return lv_mission_def_add_slot(c->m, name, unit, value, range, c->owner, c->owner_index,
                                   none, out, c->err);
}

/* "a mapping", "a list", "nothing", "'text'" or "the string \"text\"" for messages. */
const char *lv_pk_describe(const lv_ynode *n, char *buf, size_t cap)
{
    if (n->kind == LV_YNODE_MAP)
        return "a mapping";
    if (n->kind == LV_YNODE_SEQ)
        return "a list";
    if (lv_yaml_is_null(n))
        return "nothing";
    snprintf(buf, cap, n->plain ? "'%.40s'" : "the string \"%.40s\"", n->text);
    return buf;
}

/* ---- mappings ------------------------------------------------------------------------- */

const lv_ynode *lv_pk_key(const lv_ynode *map, const char *key)
{
    if (map == NULL || map->kind != LV_YNODE_MAP)
        return NULL;
    for (size_t i = 0; i + 1 < map->n; i += 2)
        if (strcmp(map->kids[i]->text, key) == 0)
            return map->kids[i];
    return NULL;
}

const lv_ynode *lv_pk_get(const lv_ynode *map, const char *key)
{
    if (map == NULL || map->kind != LV_YNODE_MAP)
        return NULL;
    for (size_t i = 0; i + 1 < map->n; i += 2)
        if (strcmp(map->kids[i]->text, key) == 0)
            return map->kids[i + 1];
    return NULL;
}

/* `n` must be a mapping without duplicate keys; with `known` (NULL-terminated), only those
 * keys. `what` names the object ("stage 'stage1'"). */
lv_status lv_pk_check_map(const lv_pctx *c, const lv_ynode *n, const char *what,
                           const char *const *known)
{
    char buf[64];
    if (n->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, n, "%s: a mapping (key: value) expected, found %s", what,
                    lv_pk_describe(n, buf, sizeof buf));
    for (size_t i = 0; i + 1 < n->n; i += 2) {
        const lv_ynode *k = n->kids[i];
        if (strlen(k->text) != k->len)
            return lv_pk_fail(c, k, "%s: key contains a NUL character", what);
        if (known != NULL) {
            size_t j = 0;
            while (known[j] != NULL && strcmp(known[j], k->text) != 0)
                j++;
            if (known[j] == NULL) {
                lv_suggest s;
                char hint[192];
                lv_suggest_init(&s, k->text);
                for (j = 0; known[j] != NULL; j++)
                    lv_suggest_add(&s, known[j]);
                lv_suggest_text(&s, hint, sizeof hint);
                return lv_pk_fail(c, k, "%s: unknown key '%.60s'%s", what, k->text, hint);
            }
        }
        for (size_t j = 0; j < i; j += 2)
            if (strcmp(n->kids[j]->text, k->text) == 0)
                return lv_pk_fail(c, k, "%s: duplicate key '%.60s' (first at line %d)", what, k->text,
                            n->kids[j]->line);
    }
    return LV_OK;
}

/* The value of a required key: present and not empty. */
lv_status lv_pk_need(const lv_pctx *c, const lv_ynode *map, const char *what, const char *key,
                      const lv_ynode **out)
{
    const lv_ynode *v = lv_pk_get(map, key);
    *out = v;
    if (v == NULL)
        return lv_pk_fail(c, map, "%s: missing required key '%s'", what, key);
    if (lv_yaml_is_null(v))
        return lv_pk_fail(c, v, "%s: '%s' has no value", what, key);
    return LV_OK;
}

/* ---- scalars -------------------------------------------------------------------------- */

static int is_nonfinite_word(const char *s)
{
    static const char *const words[] = { ".inf", ".Inf", ".INF", ".nan", ".NaN", ".NAN" };
    if (*s == '+' || *s == '-')
        s++;
    for (size_t i = 0; i < sizeof words / sizeof words[0]; i++)
        if (strcmp(s, words[i]) == 0)
            return 1;
    return 0;
}

/* A finite number written as a plain scalar. */
lv_status lv_pk_num(const lv_pctx *c, const lv_ynode *v, const char *what, const char *key,
                         double *out)
{
    char buf[64];
    if (v->kind != LV_YNODE_SCALAR || !v->plain || lv_yaml_is_null(v))
        return lv_pk_fail(c, v, "%s: %s: number expected, found %s", what, key,
                    lv_pk_describe(v, buf, sizeof buf));
    if (is_nonfinite_word(v->text))
        return lv_pk_fail(c, v, "%s: %s: non-finite number '%s'", what, key, v->text);
    char *end = NULL;
    errno = 0;
    const double x = strtod(v->text, &end);
    if (end == v->text || *end != '\0' || end != v->text + v->len)
        return lv_pk_fail(c, v, "%s: %s: number expected, found %s", what, key,
                    lv_pk_describe(v, buf, sizeof buf));
    if (!isfinite(x) || (errno == ERANGE && fabs(x) > 1.0))
        return lv_pk_fail(c, v, "%s: %s: non-finite number '%.40s'", what, key, v->text);
    *out = x;
    return LV_OK;
}

lv_status lv_pk_int(const lv_pctx *c, const lv_ynode *v, const char *what, const char *key,
                         int min, int *out)
{
    double x;
    lv_status st = lv_pk_num(c, v, what, key, &x);
    if (st != LV_OK)
        return st;
    if (x != floor(x) || x < (double)min || x > (double)INT_MAX)
        return lv_pk_fail(c, v, "%s: %s: an integer >= %d expected, found %.40s", what, key, min,
                    v->text);
    *out = (int)x;
    return LV_OK;
}

/* A non-empty string (plain or quoted scalar) without NUL characters; *out borrows v. */
lv_status lv_pk_text(const lv_pctx *c, const lv_ynode *v, const char *what, const char *key,
                          const char **out)
{
    char buf[64];
    if (v->kind != LV_YNODE_SCALAR || lv_yaml_is_null(v) || v->len == 0)
        return lv_pk_fail(c, v, "%s: %s: a name or text expected, found %s", what, key,
                    lv_pk_describe(v, buf, sizeof buf));
    if (strlen(v->text) != v->len)
        return lv_pk_fail(c, v, "%s: %s: contains a NUL character", what, key);
    *out = v->text;
    return LV_OK;
}

lv_status lv_pk_str(const lv_pctx *c, const lv_ynode *v, const char *what, const char *key,
                         char **out)
{
    const char *s;
    lv_status st = lv_pk_text(c, v, what, key, &s);
    if (st != LV_OK)
        return st;
    *out = lv_pk_strdup(s);
    return *out != NULL ? LV_OK : lv_pk_nomem(c);
}

/* One of `allowed` (NULL-terminated); *idx is its index. */
lv_status lv_pk_enum(const lv_pctx *c, const lv_ynode *v, const char *what, const char *key,
                          const char *const *allowed, size_t *idx)
{
    const char *s;
    lv_status st = lv_pk_text(c, v, what, key, &s);
    if (st != LV_OK)
        return st;
    char list[160] = "";
    size_t used = 0;
    lv_suggest sug;
    lv_suggest_init(&sug, s);
    for (size_t i = 0; allowed[i] != NULL; i++) {
        if (strcmp(s, allowed[i]) == 0) {
            *idx = i;
            return LV_OK;
        }
        lv_suggest_add(&sug, allowed[i]);
        if (used < sizeof list)
            used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "",
                                     allowed[i]);
    }
    char hint[192];
    lv_suggest_text(&sug, hint, sizeof hint);
    return lv_pk_fail(c, v, "%s: %s: unknown value '%.40s'%s (expected one of: %s)", what, key, s,
                hint, list);
}

int lv_pk_valid_name(const char *s, int allow_dot)
{
    size_t n = 0;
    for (; s[n] != '\0'; n++) {
        const char ch = s[n];
        const int ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') ||
                       (ch >= '0' && ch <= '9') || ch == '_' || ch == '-' ||
                       (allow_dot && ch == '.');
        if (!ok)
            return 0;
    }
    return n > 0 && n <= LV_NAME_MAX;
}

lv_status lv_pk_name(const lv_pctx *c, const lv_ynode *v, const char *what, int allow_dot,
                          char **out)
{
    const char *s;
    lv_status st = lv_pk_text(c, v, what, "name", &s);
    if (st != LV_OK)
        return st;
    if (!lv_pk_valid_name(s, allow_dot))
        return lv_pk_fail(c, v, "%s: name '%.40s' must be 1 to %d letters, digits, '_' or '-'%s", what,
                    s, LV_NAME_MAX, allow_dot ? " or '.'" : "");
    *out = lv_pk_strdup(s);
    return *out != NULL ? LV_OK : lv_pk_nomem(c);
}

/* An event's user name: printable, 1 to LV_EVENT_LABEL_MAX characters, no space at its ends.
 * `key`: the key that gives it, in messages ("name", "end_name"). */
lv_status lv_pk_event_label(const lv_pctx *c, const lv_ynode *v, const char *what,
                            const char *key, char **out)
{
    const char *s;
    lv_status st = lv_pk_text(c, v, what, key, &s);
    if (st != LV_OK)
        return st;
    size_t chars = 0;
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        if (*p < 0x20 || *p == 0x7f)
            return lv_pk_fail(c, v, "%s: %s: a control character (0x%02x) at character %zu: "
                              "a name is printable text", what, key, *p, chars + 1);
        chars += (*p & 0xc0) != 0x80; /* UTF-8: count the first byte of each character */
    }
    if (chars > LV_EVENT_LABEL_MAX)
        return lv_pk_fail(c, v, "%s: %s: %zu characters, at most %d ('%.20s...')", what, key,
                          chars, LV_EVENT_LABEL_MAX, s);
    if (s[0] == ' ' || s[strlen(s) - 1] == ' ')
        return lv_pk_fail(c, v, "%s: %s '%s' starts or ends with a space", what, key, s);
    *out = lv_pk_strdup(s);
    return *out != NULL ? LV_OK : lv_pk_nomem(c);
}

/* "stage 'stage1'" when the item has a usable name, else "stage #2" (1-based). */
void lv_pk_label(const lv_ynode *item, const char *kind, size_t k, char *buf, size_t cap)
{
    const lv_ynode *nm = lv_pk_get(item, "name");
    if (nm != NULL && nm->kind == LV_YNODE_SCALAR && nm->len > 0 && !lv_yaml_is_null(nm) &&
        strlen(nm->text) == nm->len && nm->len <= LV_NAME_MAX)
        snprintf(buf, cap, "%s '%s'", kind, nm->text);
    else
        snprintf(buf, cap, "%s #%zu", kind, k + 1);
}

lv_src_loc lv_pk_loc(const lv_ynode *n)
{
    lv_src_loc l = { n->line, n->col };
    return l;
}

/* {<file_key>: path, var: name} of a table read later by its model (atmosphere, wind). */
lv_status lv_pk_table_file(const lv_pctx *c, const lv_ynode *n, const char *what,
                            const char *file_key, char **file, char **var)
{
    const lv_ynode *v;
    const char *rel;
    lv_status st;
    if ((st = lv_pk_need(c, n, what, file_key, &v)) != LV_OK ||
        (st = lv_pk_text(c, v, what, file_key, &rel)) != LV_OK)
        return st;
    if ((*file = lv_pk_resolve_file(c, rel)) == NULL)
        return lv_pk_nomem(c);
    if ((v = lv_pk_get(n, "var")) != NULL && (st = lv_pk_str(c, v, what, "var", var)) != LV_OK)
        return st;
    return LV_OK;
}

/* Only regular files: a device or a FIFO could block the parser forever. */
lv_status lv_pk_regular_file(const lv_pctx *c, const lv_ynode *at, const char *what,
                              const char *key, const char *path)
{
    struct stat sb;
    if (stat(path, &sb) != 0)
        return lv_pk_fail(c, at, "%s: %s: cannot read '%s': %s", what, key, path,
                          LV_STRERROR(errno));
    if (!S_ISREG(sb.st_mode))
        return lv_pk_fail(c, at, "%s: %s: '%s' is not a regular file", what, key, path);
    return LV_OK;
}


/* `rel` against the mission's directory, unless absolute. */
static char *resolve_path(const char *dir, const char *rel)
{
    if (rel[0] == '/' || dir == NULL || dir[0] == '\0')
        return lv_pk_strdup(rel);
    const size_t nd = strlen(dir), nr = strlen(rel);
    char *p = malloc(nd + nr + 2);
    if (p == NULL)
        return NULL;
    memcpy(p, dir, nd);
    p[nd] = '/';
    memcpy(p + nd + 1, rel, nr + 1);
    return p;
}

/* resolve_path, and the path noted in the mission's list of the files it reads (once; an
 * FMU or any other package of the mission carries them). NULL: out of memory. */
char *lv_pk_resolve_file(const lv_pctx *c, const char *rel)
{
    char *p = resolve_path(c->m->dir, rel);
    if (p == NULL)
        return NULL;
    lv_mission_def *m = c->m;
    for (size_t i = 0; i < m->n_files; i++)
        if (strcmp(m->files[i], p) == 0)
            return p;
    char **grown = realloc(m->files, (m->n_files + 1) * sizeof *grown);
    char *copy = lv_pk_strdup(p);
    if (grown == NULL || copy == NULL) {
        if (grown != NULL)
            m->files = grown;
        free(copy);
        free(p);
        return NULL;
    }
    m->files = grown;
    m->files[m->n_files++] = copy;
    return p;
}

/* The file name without directory and extension: the default .mat variable. */
static char *file_stem(const char *path)
{
    const char *b = strrchr(path, '/');
    b = b != NULL ? b + 1 : path;
    const char *dot = strrchr(b, '.');
    const size_t n = dot != NULL && dot != b ? (size_t)(dot - b) : strlen(b);
    char *s = malloc(n + 1);
    if (s != NULL) {
        memcpy(s, b, n);
        s[n] = '\0';
    }
    return s;
}

/* A table given as `path` or {file, var, interp, extrap}: loaded into *tab; the resolved
 * path and .mat variable go to *file and *var. `extrap_default` applies when not given. */
static lv_status table_any(const lv_pctx *c, const lv_ynode *key, const lv_ynode *v,
                           const char *what, lv_extrap extrap_default, int repeats_last,
                           char **file_out, char **var_out, const lv_ynode **output,
                           lv_table **tab);

lv_status lv_pk_table(const lv_pctx *c, const lv_ynode *key, const lv_ynode *v,
                      const char *what, lv_extrap extrap_default, char **file_out,
                      char **var_out, lv_table **tab)
{
    return table_any(c, key, v, what, extrap_default, 0, file_out, var_out, NULL, tab);
}

lv_status lv_pk_table_traj(const lv_pctx *c, const lv_ynode *key, const lv_ynode *v,
                           const char *what, lv_extrap extrap_default, char **file_out,
                           char **var_out, lv_table **tab)
{
    return table_any(c, key, v, what, extrap_default, 1, file_out, var_out, NULL, tab);
}

lv_status lv_pk_table_out(const lv_pctx *c, const lv_ynode *key, const lv_ynode *v,
                          const char *what, lv_extrap extrap_default, char **file_out,
                          char **var_out, const lv_ynode **output, lv_table **tab)
{
    return table_any(c, key, v, what, extrap_default, 0, file_out, var_out, output, tab);
}

static lv_status table_any(const lv_pctx *c, const lv_ynode *key, const lv_ynode *v,
                           const char *what, lv_extrap extrap_default, int repeats_last,
                           char **file_out, char **var_out, const lv_ynode **output,
                           lv_table **tab)
{
    static const char *const keys_out[] = { "file", "var", "interp", "extrap", "output", NULL };
    static const char *const keys_plain[] = { "file", "var", "interp", "extrap", NULL };
    static const char *const interps[] = { "linear", "pchip", NULL };
    static const char *const extraps[] = { "clamp", "error", "linear", NULL };
    static const lv_extrap extrap_of[] = { LV_EXTRAP_CLAMP, LV_EXTRAP_ERROR, LV_EXTRAP_LINEAR };
    const char *const *keys = output != NULL ? keys_out : keys_plain;
    lv_table_opts opts = { LV_INTERP_LINEAR, extrap_default, repeats_last };
    const lv_ynode *file = v, *at = v;
    const char *rel = NULL;
    lv_status st;

    if (output != NULL)
        *output = NULL;

    if (v->kind == LV_YNODE_MAP) {
        st = lv_pk_check_map(c, v, what, keys);
        if (st == LV_OK)
            st = lv_pk_need(c, v, what, "file", &file);
        if (st != LV_OK)
            return st;
        const lv_ynode *o;
        size_t i;
        if ((o = lv_pk_get(v, "var")) != NULL &&
            (st = lv_pk_str(c, o, what, "var", var_out)) != LV_OK)
            return st;
        if ((o = lv_pk_get(v, "interp")) != NULL) {
            if ((st = lv_pk_enum(c, o, what, "interp", interps, &i)) != LV_OK)
                return st;
            opts.interp = i == 0 ? LV_INTERP_LINEAR : LV_INTERP_PCHIP;
        }
        if ((o = lv_pk_get(v, "extrap")) != NULL) {
            if ((st = lv_pk_enum(c, o, what, "extrap", extraps, &i)) != LV_OK)
                return st;
            opts.extrap = extrap_of[i];
        }
        if (output != NULL && (o = lv_pk_get(v, "output")) != NULL) {
            const char *name;
            if ((st = lv_pk_text(c, o, what, "output", &name)) != LV_OK)
                return st;
            *output = o;
        }
        at = file;
    }
    st = lv_pk_text(c, file, what, "table", &rel);
    if (st != LV_OK)
        return st;
    *file_out = lv_pk_resolve_file(c, rel);
    if (*var_out == NULL && lv_table_path_is_mat(rel))
        *var_out = file_stem(rel);
    if (*file_out == NULL || (lv_table_path_is_mat(rel) && *var_out == NULL))
        return lv_pk_nomem(c);

    if ((st = lv_pk_regular_file(c, at, what, key->text, *file_out)) != LV_OK)
        return st;

    if (*var_out != NULL)
        st = lv_table_load_mat(*file_out, *var_out, &opts, tab, c->err);
    else
        st = lv_table_load_csv(*file_out, &opts, tab, c->err);
    if (st != LV_OK)
        return lv_fail_prefix(c->err, st == LV_ERR_NOMEM ? st : LV_ERR_INPUT, "%s:%d:%d: %s: %s",
                              c->file, key->line, key->col, what, key->text);
    return LV_OK;
}

lv_status lv_pk_seed(const lv_pctx *c, const lv_ynode *v, const char *what, uint64_t *out)
{
    const char *s = v->kind == LV_YNODE_SCALAR ? v->text : "";
    int ok = v->kind == LV_YNODE_SCALAR && v->plain && s[0] >= '0' && s[0] <= '9';
    for (const char *q = s; ok && *q; q++)
        ok = *q >= '0' && *q <= '9';
    errno = 0;
    const unsigned long long x = ok ? strtoull(s, NULL, 10) : 0;
    if (!ok || errno == ERANGE)
        return lv_pk_fail(c, v, "%s: seed: an integer from 0 to 18446744073709551615 "
                          "expected, found '%.40s'", what,
                          v->kind == LV_YNODE_SCALAR ? s : "a collection");
    *out = (uint64_t)x;
    return LV_OK;
}
