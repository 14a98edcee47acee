/* parse.c - mission files (YAML) to lv_mission_def. Keys, types, units, names, references,
 * tables and the phase tree are validated before anything runs; every error reads
 * "file:line:column: message". Format: docs/mission-format.md. The shared parameter set is
 * the paper's userPar (sec. 2.1), the phase tree its sequential simulation (sec. 3). */
#define _POSIX_C_SOURCE 200809L /* stat() */

#include "mission/mission.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/names.h"
#include "core/status.h"
#include "core/table_unit.h"
#include "core/units.h"
#include "core/utc.h"
#include "lvsim/lv_planet.h"
#include "mission/dispersion.h"
#include "mission/parse_kit.h"
#include "mission/phase_type.h"
#include "mission/targeting_def.h"
#include "mission/yaml_tree.h"


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

static char *dup_text(const char *s)
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

static lv_status check_slot_names(const lv_pctx *c)
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
    *sd = (lv_slot_def){dup_text(name), dup_text(unit), value, range, owner, owner_index, loc};
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
static const char *describe(const lv_ynode *n, char *buf, size_t cap)
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
                    describe(n, buf, sizeof buf));
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
                    describe(v, buf, sizeof buf));
    if (is_nonfinite_word(v->text))
        return lv_pk_fail(c, v, "%s: %s: non-finite number '%s'", what, key, v->text);
    char *end = NULL;
    errno = 0;
    const double x = strtod(v->text, &end);
    if (end == v->text || *end != '\0' || end != v->text + v->len)
        return lv_pk_fail(c, v, "%s: %s: number expected, found %s", what, key,
                    describe(v, buf, sizeof buf));
    if (!isfinite(x) || (errno == ERANGE && fabs(x) > 1.0))
        return lv_pk_fail(c, v, "%s: %s: non-finite number '%.40s'", what, key, v->text);
    *out = x;
    return LV_OK;
}

static lv_status get_int(const lv_pctx *c, const lv_ynode *v, const char *what, const char *key,
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
                    describe(v, buf, sizeof buf));
    if (strlen(v->text) != v->len)
        return lv_pk_fail(c, v, "%s: %s: contains a NUL character", what, key);
    *out = v->text;
    return LV_OK;
}

static lv_status get_str(const lv_pctx *c, const lv_ynode *v, const char *what, const char *key,
                         char **out)
{
    const char *s;
    lv_status st = lv_pk_text(c, v, what, key, &s);
    if (st != LV_OK)
        return st;
    *out = dup_text(s);
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

static int valid_name(const char *s, int allow_dot)
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

static lv_status get_name(const lv_pctx *c, const lv_ynode *v, const char *what, int allow_dot,
                          char **out)
{
    const char *s;
    lv_status st = lv_pk_text(c, v, what, "name", &s);
    if (st != LV_OK)
        return st;
    if (!valid_name(s, allow_dot))
        return lv_pk_fail(c, v, "%s: name '%.40s' must be 1 to %d letters, digits, '_' or '-'%s", what,
                    s, LV_NAME_MAX, allow_dot ? " or '.'" : "");
    *out = dup_text(s);
    return *out != NULL ? LV_OK : lv_pk_nomem(c);
}

/* "stage 'stage1'" when the item has a usable name, else "stage #2" (1-based). */
static void label(const lv_ynode *item, const char *kind, size_t k, char *buf, size_t cap)
{
    const lv_ynode *nm = lv_pk_get(item, "name");
    if (nm != NULL && nm->kind == LV_YNODE_SCALAR && nm->len > 0 && !lv_yaml_is_null(nm) &&
        strlen(nm->text) == nm->len && nm->len <= LV_NAME_MAX)
        snprintf(buf, cap, "%s '%s'", kind, nm->text);
    else
        snprintf(buf, cap, "%s #%zu", kind, k + 1);
}

static lv_src_loc loc_of(const lv_ynode *n)
{
    lv_src_loc l = { n->line, n->col };
    return l;
}

/* ---- environment ---------------------------------------------------------------------- */

static char *resolve_path(const char *dir, const char *rel);
static char *resolve_file(const lv_pctx *c, const char *rel);

/* {<file_key>: path, var: name} of a table read later by its model (atmosphere, wind). */
static lv_status table_file(const lv_pctx *c, const lv_ynode *n, const char *what,
                            const char *file_key, char **file, char **var)
{
    const lv_ynode *v;
    const char *rel;
    lv_status st;
    if ((st = lv_pk_need(c, n, what, file_key, &v)) != LV_OK ||
        (st = lv_pk_text(c, v, what, file_key, &rel)) != LV_OK)
        return st;
    if ((*file = resolve_file(c, rel)) == NULL)
        return lv_pk_nomem(c);
    if ((v = lv_pk_get(n, "var")) != NULL && (st = get_str(c, v, what, "var", var)) != LV_OK)
        return st;
    return LV_OK;
}

/* Only regular files: a device or a FIFO could block the parser forever. */
static lv_status regular_file(const lv_pctx *c, const lv_ynode *at, const char *what,
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

static const char *const planet_presets[] = { "earth", "moon", "mars", NULL };

/* planet: {name, base, radius, flattening, gm, rotation_rate(_deg), r_ref, zonal,
 * coefficients}: a planet by its constants (docs/mission-format.md). Written numbers are
 * slots "environment.planet.<key>" ("environment.planet.J2" ... for the zonal list). */
static lv_status parse_planet_map(const lv_pctx *c, const lv_ynode *n, lv_env_def *e,
                                  int *earth)
{
    static const char *const keys[] = { "name", "base", "radius", "flattening", "gm",
                                        "rotation_rate", "rotation_rate_deg", "r_ref", "zonal",
                                        "coefficients", NULL };
    const char *what = "environment, planet";
    lv_planet_def *pd = &e->pdef;
    const lv_ynode *v;
    lv_status st;
    size_t i;
    if ((st = lv_pk_check_map(c, n, what, keys)) != LV_OK)
        return st;
    pd->custom = 1;
    pd->loc = loc_of(n);
    memset(&pd->base, 0, sizeof pd->base);
    if ((v = lv_pk_get(n, "base")) != NULL) {
        if ((st = lv_pk_enum(c, v, what, "base", planet_presets, &i)) != LV_OK ||
            (st = lv_planet_by_name(planet_presets[i], &pd->base, NULL)) != LV_OK)
            return st;
        pd->has_base = 1;
        *earth = i == 0;
    } else {
        const char *req[] = { "radius", "gm" };
        for (size_t k = 0; k < 2; k++)
            if (lv_pk_get(n, req[k]) == NULL)
                return lv_pk_fail(c, n, "%s: missing required key '%s' (or give 'base: earth', "
                                  "'moon' or 'mars' to start from a preset's constants)", what,
                                  req[k]);
    }
    const char *name = "custom";
    if ((v = lv_pk_get(n, "name")) != NULL) {
        if ((st = lv_pk_text(c, v, what, "name", &name)) != LV_OK)
            return st;
        if (!valid_name(name, 0) || strlen(name) >= LV_PLANET_NAME_MAX)
            return lv_pk_fail(c, v, "%s: name '%.40s' must be 1 to %d letters, digits, '_' or "
                              "'-'", what, name, LV_PLANET_NAME_MAX - 1);
        for (i = 0; planet_presets[i] != NULL; i++)
            if (strcmp(name, planet_presets[i]) == 0)
                return lv_pk_fail(c, v, "%s: name '%s' is a preset's; a planet given by its "
                                  "constants needs a name of its own (exports take '%s' for "
                                  "the preset)", what, name, name);
    }
    snprintf(pd->base.name, sizeof pd->base.name, "%s", name);
    if ((e->planet = dup_text(name)) == NULL)
        return lv_pk_nomem(c);

    /* the constants; ranges hold any planet (the Sun: a = 7e8 m, GM = 1.3e20 m^3/s^2) */
    static const lv_range r_len = { 0.0, 1e10, 1, 0 }, r_gm = { 0.0, 1e21, 1, 0 },
                          r_f = { 0.0, 1.0, 0, 1 }, r_w = { -1.0, 1.0, 0, 0 },
                          r_j = { -1.0, 1.0, 1, 1 };
    const struct {
        const char *key, *unit;
        lv_range range;
        lv_slot *slot;
    } num[] = {
        { "radius", "m", r_len, &pd->radius },
        { "flattening", "", r_f, &pd->flattening },
        { "gm", "m^3/s^2", r_gm, &pd->gm },
        { "rotation_rate", "rad/s", r_w, &pd->rotation_rate },
        { "r_ref", "m", r_len, &pd->r_ref },
    };
    for (size_t k = 0; k < sizeof num / sizeof num[0]; k++) {
        char slot[64];
        *num[k].slot = LV_NO_SLOT;
        snprintf(slot, sizeof slot, "environment.planet.%s", num[k].key);
        const lv_ynode *vd = NULL;
        v = lv_pk_get(n, num[k].key);
        if (num[k].slot == &pd->rotation_rate && (vd = lv_pk_get(n, "rotation_rate_deg")) != NULL &&
            v != NULL)
            return lv_pk_fail(c, lv_pk_key(n, "rotation_rate_deg"), "%s: 'rotation_rate' and "
                              "'rotation_rate_deg' given both", what);
        if (v == NULL && vd == NULL)
            continue;
        if ((st = lv_pk_slot(c, v ? v : vd, what, v ? num[k].key : "rotation_rate_deg", slot,
                             num[k].unit, num[k].range, vd != NULL, num[k].slot)) != LV_OK)
            return st;
    }
    if ((v = lv_pk_get(n, "zonal")) != NULL) {
        if (v->kind != LV_YNODE_SEQ && !lv_yaml_is_null(v))
            return lv_pk_fail(c, v, "%s: zonal: a list [J2, J3, ...] expected", what);
        pd->zonal_given = 1;
        pd->n_zonal = v->kind == LV_YNODE_SEQ ? v->n : 0;
        if (pd->n_zonal > LV_GRAVITY_ZONAL_MAX - 1)
            return lv_pk_fail(c, v, "%s: zonal: %zu coefficients; at most %d (J2 .. J%d)", what,
                              pd->n_zonal, LV_GRAVITY_ZONAL_MAX - 1, LV_GRAVITY_ZONAL_MAX);
        if (pd->n_zonal > 0 && (pd->zonal = calloc(pd->n_zonal, sizeof *pd->zonal)) == NULL)
            return lv_pk_nomem(c);
        for (size_t k = 0; k < pd->n_zonal; k++) {
            char slot[64], key[16];
            snprintf(key, sizeof key, "J%zu", k + 2);
            snprintf(slot, sizeof slot, "environment.planet.%s", key);
            if ((st = lv_pk_slot(c, v->kids[k], what, key, slot, "", r_j, 0, &pd->zonal[k])) !=
                LV_OK)
                return st;
        }
    }
    if ((v = lv_pk_get(n, "coefficients")) != NULL) {
        const char *rel;
        if ((st = lv_pk_text(c, v, what, "coefficients", &rel)) != LV_OK)
            return st;
        if ((pd->coef_file = resolve_file(c, rel)) == NULL)
            return lv_pk_nomem(c);
        if ((st = regular_file(c, v, what, "coefficients", pd->coef_file)) != LV_OK)
            return st;
    }
    /* the planet as the file gives it must hold together (lv_planet_check: the rotation) */
    lv_planet p = pd->base;
    const lv_mission_def *m = c->m;
    if (pd->radius != LV_NO_SLOT) p.a = m->slots[pd->radius].value;
    if (pd->flattening != LV_NO_SLOT) p.f = m->slots[pd->flattening].value;
    if (pd->gm != LV_NO_SLOT) p.gm = m->slots[pd->gm].value;
    if (pd->rotation_rate != LV_NO_SLOT) p.omega = m->slots[pd->rotation_rate].value;
    p.r_ref = pd->r_ref != LV_NO_SLOT ? m->slots[pd->r_ref].value : pd->has_base ? p.r_ref : p.a;
    lv_err perr;
    if (lv_planet_check(&p, &perr) != LV_OK)
        return lv_pk_fail(c, n, "%s: %s", what, perr.msg);
    return LV_OK;
}

/* atmosphere: us76 | exp | none | {table: path, var: name} | {model: exp, rho0, scale_height,
 * temperature} (the exponential model's parameters: slots "environment.atmosphere.<key>"). */
static lv_status parse_atmosphere(const lv_pctx *c, const lv_ynode *v, size_t deflt,
                                  lv_env_def *e)
{
    static const char *const atmos[] = { "us76", "exp", "none", NULL };
    static const char *const keys[] = { "table", "var", "model", "rho0", "scale_height",
                                        "temperature", NULL };
    static const char *const pkeys[3] = { "rho0", "scale_height", "temperature" };
    static const char *const punit[3] = { "kg/m^3", "m", "K" };
    const char *what = "environment, atmosphere";
    size_t i = deflt;
    lv_status st;
    for (size_t k = 0; k < 3; k++)
        e->atmo_par[k] = LV_NO_SLOT;
    if (v != NULL && v->kind == LV_YNODE_MAP) {
        if ((st = lv_pk_check_map(c, v, what, keys)) != LV_OK)
            return st;
        const lv_ynode *mv = lv_pk_get(v, "model");
        if (lv_pk_get(v, "table") != NULL) { /* {table: path, var: name}: from a file */
            if (mv != NULL)
                return lv_pk_fail(c, lv_pk_key(v, "model"), "%s: give either 'table' (a file) "
                                  "or 'model', not both", what);
            for (size_t k = 0; k < 3; k++)
                if (lv_pk_get(v, pkeys[k]) != NULL)
                    return lv_pk_fail(c, lv_pk_key(v, pkeys[k]), "%s: '%s' belongs to model: "
                                      "exp", what, pkeys[k]);
            if ((st = table_file(c, v, what, "table", &e->atmo_file, &e->atmo_var)) != LV_OK ||
                (st = regular_file(c, lv_pk_get(v, "table"), what, "table", e->atmo_file)) !=
                    LV_OK)
                return st;
            e->atmosphere = dup_text("table");
            return e->atmosphere != NULL ? LV_OK : lv_pk_nomem(c);
        }
        if (lv_pk_get(v, "var") != NULL)
            return lv_pk_fail(c, lv_pk_key(v, "var"), "%s: 'var' goes with 'table'", what);
        if ((st = lv_pk_need(c, v, what, "model", &mv)) != LV_OK ||
            (st = lv_pk_enum(c, mv, what, "model", atmos, &i)) != LV_OK)
            return st;
        for (size_t k = 0; k < 3; k++) {
            const lv_ynode *pv = lv_pk_get(v, pkeys[k]);
            if (pv == NULL)
                continue;
            if (i != 1)
                return lv_pk_fail(c, lv_pk_key(v, pkeys[k]), "%s: '%s' belongs to model: exp "
                                  "(this is %s)", what, pkeys[k], atmos[i]);
            char slot[64];
            snprintf(slot, sizeof slot, "environment.atmosphere.%s", pkeys[k]);
            if ((st = lv_pk_slot(c, pv, what, pkeys[k], slot, punit[k], LV_RANGE_POS, 0,
                                 &e->atmo_par[k])) != LV_OK)
                return st;
        }
    } else if (v != NULL && (st = lv_pk_enum(c, v, "environment", "atmosphere", atmos, &i)) !=
                                LV_OK) {
        return st;
    }
    e->atmosphere = dup_text(atmos[i]);
    return e->atmosphere != NULL ? LV_OK : lv_pk_nomem(c);
}

/* wind: path | {file: path, var, interp, extrap} | {north, east, down}: a table over
 * altitude or a constant (slots "environment.wind.north" ...), docs/wind.md. */
static lv_status parse_wind(const lv_pctx *c, const lv_ynode *v, lv_env_def *e)
{
    static const char *const keys[] = { "file", "var", "interp", "extrap", "north", "east",
                                        "down", NULL };
    static const char *const comp[3] = { "north", "east", "down" };
    static const char *const interps[] = { "linear", "pchip", NULL };
    static const char *const extraps[] = { "clamp", "error", "linear", NULL };
    static const lv_extrap extrap_of[] = { LV_EXTRAP_CLAMP, LV_EXTRAP_ERROR, LV_EXTRAP_LINEAR };
    static const lv_range r_wind = { -500.0, 500.0, 0, 0 }; /* m/s: beyond any jet stream */
    const char *what = "environment, wind";
    lv_status st;
    size_t i;
    e->wind_interp = LV_INTERP_LINEAR;
    e->wind_extrap = LV_EXTRAP_CLAMP;
    e->wind_loc = loc_of(v);
    if (v->kind != LV_YNODE_MAP) {
        const char *rel;
        if ((st = lv_pk_text(c, v, "environment", "wind", &rel)) != LV_OK)
            return st;
        if ((e->wind_file = resolve_file(c, rel)) == NULL)
            return lv_pk_nomem(c);
        return regular_file(c, v, "environment", "wind", e->wind_file);
    }
    if ((st = lv_pk_check_map(c, v, what, keys)) != LV_OK)
        return st;
    const lv_ynode *f = lv_pk_get(v, "file"), *o;
    for (size_t k = 0; k < 3; k++) {
        const lv_ynode *cv = lv_pk_get(v, comp[k]);
        if (cv != NULL && f != NULL)
            return lv_pk_fail(c, lv_pk_key(v, comp[k]), "%s: give either 'file' (a table) or "
                              "the constant components north, east[, down], not both", what);
    }
    if (f != NULL) {
        if ((st = table_file(c, v, what, "file", &e->wind_file, &e->wind_var)) != LV_OK ||
            (st = regular_file(c, f, what, "file", e->wind_file)) != LV_OK)
            return st;
        if ((o = lv_pk_get(v, "interp")) != NULL) {
            if ((st = lv_pk_enum(c, o, what, "interp", interps, &i)) != LV_OK)
                return st;
            e->wind_interp = i == 0 ? LV_INTERP_LINEAR : LV_INTERP_PCHIP;
        }
        if ((o = lv_pk_get(v, "extrap")) != NULL) {
            if ((st = lv_pk_enum(c, o, what, "extrap", extraps, &i)) != LV_OK)
                return st;
            e->wind_extrap = extrap_of[i];
        }
        return LV_OK;
    }
    const char *tkeys[] = { "var", "interp", "extrap" };
    for (size_t k = 0; k < 3; k++)
        if (lv_pk_get(v, tkeys[k]) != NULL)
            return lv_pk_fail(c, lv_pk_key(v, tkeys[k]), "%s: '%s' goes with 'file' (a wind "
                              "table)", what, tkeys[k]);
    e->wind_const = 1;
    for (size_t k = 0; k < 3; k++) {
        char slot[64];
        e->wind_ned[k] = LV_NO_SLOT;
        snprintf(slot, sizeof slot, "environment.wind.%s", comp[k]);
        if (k < 2 && (st = lv_pk_need(c, v, what, comp[k], &o)) != LV_OK)
            return st;
        if ((o = lv_pk_get(v, comp[k])) != NULL &&
            (st = lv_pk_slot(c, o, what, comp[k], slot, "m/s", r_wind, 0, &e->wind_ned[k])) !=
                LV_OK)
            return st;
    }
    return LV_OK;
}

static lv_status parse_env(const lv_pctx *c, const lv_ynode *n)
{
    static const char *const keys[] = { "world", "g", "planet", "gravity", "atmosphere",
                                        "wind", "site_lat_deg", "site_lon_deg", NULL };
    static const char *const worlds[] = { "flat", "planet", NULL };
    const char *what = "environment";
    lv_env_def *e = &c->m->env;
    const lv_ynode *v;
    size_t i = 0;
    lv_status st;

    e->world = LV_WORLD_FLAT;
    e->pdef.radius = e->pdef.flattening = e->pdef.gm = LV_NO_SLOT;
    e->pdef.rotation_rate = e->pdef.r_ref = LV_NO_SLOT;
    for (size_t k = 0; k < 3; k++)
        e->atmo_par[k] = e->wind_ned[k] = LV_NO_SLOT;
    e->wind_interp = LV_INTERP_LINEAR;
    e->wind_extrap = LV_EXTRAP_CLAMP;
    if (n != NULL && !lv_yaml_is_null(n)) {
        st = lv_pk_check_map(c, n, what, keys);
        if (st != LV_OK)
            return st;
        e->loc = loc_of(n);
        if ((v = lv_pk_get(n, "world")) != NULL) {
            st = lv_pk_enum(c, v, what, "world", worlds, &i);
            if (st != LV_OK)
                return st;
            e->world = i == 0 ? LV_WORLD_FLAT : LV_WORLD_PLANET;
        }
    } else {
        n = NULL;
    }
    const int flat = e->world == LV_WORLD_FLAT;
    e->gravity_loc = e->atmo_loc = e->wind_loc = e->loc;

    e->g = LV_NO_SLOT;
    if ((v = lv_pk_get(n, "g")) != NULL) {
        if (!flat)
            return lv_pk_fail(c, lv_pk_key(n, "g"), "%s: 'g' applies to world: flat only (a planet "
                        "world takes its gravity from 'planet' and 'gravity')", what);
        if ((st = lv_pk_slot(c, v, what, "g", "environment.g", "m/s^2", LV_RANGE_POS, 0,
                             &e->g)) != LV_OK)
            return st;
    } else if (flat && (st = lv_pk_slot_default(c, "environment.g", "m/s^2", 9.81, LV_RANGE_POS,
                                                &e->g)) != LV_OK) {
        return st;
    }
    /* Where the flat world's origin lies on the Earth, for maps and the globe view. */
    const char *skeys[] = { "site_lat_deg", "site_lon_deg" };
    double *sval[] = { &e->site_lat, &e->site_lon };
    for (size_t k = 0; k < 2; k++) {
        if ((v = lv_pk_get(n, skeys[k])) == NULL)
            continue;
        if (!flat)
            return lv_pk_fail(c, lv_pk_key(n, skeys[k]), "%s: '%s' applies to world: flat only (a "
                        "planet world starts at the parameters start_lat, start_lon)", what,
                        skeys[k]);
        if ((st = lv_pk_num(c, v, what, skeys[k], sval[k])) != LV_OK)
            return st;
        if (fabs(*sval[k]) > (k == 0 ? 90.0 : 360.0))
            return lv_pk_fail(c, v, "%s: %s = %g is out of range", what, skeys[k], *sval[k]);
        *sval[k] *= LV_DEG;
    }
    const char *pkeys[] = { "planet", "gravity" };
    for (size_t k = 0; k < 2; k++)
        if (flat && lv_pk_get(n, pkeys[k]) != NULL)
            return lv_pk_fail(c, lv_pk_key(n, pkeys[k]), "%s: '%s' applies to world: planet only",
                        what, pkeys[k]);

    int earth = 0; /* US76 is an Earth atmosphere: the default on the Earth only */
    if (!flat) {
        lv_planet_def *pd = &e->pdef;
        if ((v = lv_pk_get(n, "planet")) != NULL && v->kind == LV_YNODE_MAP) {
            if ((st = parse_planet_map(c, v, e, &earth)) != LV_OK)
                return st;
        } else {
            i = 0;
            if (v != NULL && (st = lv_pk_enum(c, v, what, "planet", planet_presets, &i)) != LV_OK)
                return st;
            if ((e->planet = dup_text(planet_presets[i])) == NULL)
                return lv_pk_nomem(c);
            earth = i == 0;
        }
        /* gravity: checked here, where its position is known */
        lv_gravity_config gc;
        lv_err gerr;
        if ((v = lv_pk_get(n, "gravity")) != NULL) {
            if ((st = get_str(c, v, what, "gravity", &e->gravity)) != LV_OK)
                return st;
            if (lv_gravity_parse_spec(e->gravity, &gc, &gerr) != LV_OK)
                return lv_pk_fail(c, v, "%s: gravity: %s", what, gerr.msg);
            e->gravity_loc = loc_of(v);
        } else {
            e->gravity = dup_text(!pd->custom ? "j2" : pd->coef_file != NULL ? "sh" : "zonal");
            if (e->gravity == NULL)
                return lv_pk_nomem(c);
            (void)lv_gravity_parse_spec(e->gravity, &gc, NULL);
        }
        const int sh = strcmp(gc.model, "sh") == 0;
        const lv_ynode *at = v != NULL ? v : n;
        if (pd->coef_file != NULL && !sh)
            return lv_pk_fail(c, at, "%s: gravity '%s' does not use the planet's coefficient "
                              "file (only 'sh' does)", what, e->gravity);
        if (sh && pd->coef_file == NULL && !earth)
            return lv_pk_fail(c, at, "%s: gravity '%s' would read the shipped EGM2008 "
                              "coefficients, which are the Earth's; give this planet's own "
                              "file: planet: {..., coefficients: file.gfc}", what, e->gravity);
    }
    v = lv_pk_get(n, "atmosphere");
    if (v != NULL)
        e->atmo_loc = loc_of(v);
    if ((st = parse_atmosphere(c, v, earth ? 0 : 2, e)) != LV_OK)
        return st;
    /* wind: a table of north/east(/down) components over altitude, or a constant */
    if ((v = lv_pk_get(n, "wind")) != NULL && !lv_yaml_is_null(v)) {
        if ((st = parse_wind(c, v, e)) != LV_OK)
            return st;
        if (strcmp(e->atmosphere, "none") == 0)
            return lv_pk_fail(c, lv_pk_key(n, "wind"), "%s: a wind moves air, and there is "
                              "none (atmosphere: none%s): give an atmosphere, or no wind", what,
                              lv_pk_get(n, "atmosphere") != NULL ? "" : ", the default here");
    }
    return LV_OK;
}

/* ---- engine tables -------------------------------------------------------------------- */

/* `rel` against the mission's directory, unless absolute. */
static char *resolve_path(const char *dir, const char *rel)
{
    if (rel[0] == '/' || dir == NULL || dir[0] == '\0')
        return dup_text(rel);
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
static char *resolve_file(const lv_pctx *c, const char *rel)
{
    char *p = resolve_path(c->m->dir, rel);
    if (p == NULL)
        return NULL;
    lv_mission_def *m = c->m;
    for (size_t i = 0; i < m->n_files; i++)
        if (strcmp(m->files[i], p) == 0)
            return p;
    char **grown = realloc(m->files, (m->n_files + 1) * sizeof *grown);
    char *copy = dup_text(p);
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

/* Outputs "thrust" and "mdot" by name, or a .mat matrix [t, thrust, mdot] (col2, col3). */
/* Thrust and mass flow are >= 0 at every breakpoint of an engine table (its interpolants,
 * linear or monotone PCHIP, then stay >= 0 between them): a negative thrust would push the
 * vehicle backwards, a negative mass flow would fill the tanks. */
static lv_status table_nonnegative(const lv_pctx *c, const lv_ynode *key, const char *what,
                                   const lv_engine_def *e)
{
    size_t n;
    const double *tb = lv_table_breakpoints(e->table, 0, &n);
    double y[64];
    if (lv_table_n_out(e->table) > sizeof y / sizeof y[0])
        return LV_OK; /* (a table of engines has 2 outputs) */
    for (size_t i = 0; i < n; i++) {
        if (lv_table_eval1(e->table, NULL, tb[i], y, NULL) != LV_OK)
            continue;
        const char *bad = !(y[e->thrust_out] >= 0.0) ? "thrust" : !(y[e->mdot_out] >= 0.0) ? "mdot"
                                                                                           : NULL;
        if (bad != NULL)
            return lv_pk_fail(c, key, "%s: table '%s': %s = %g %s at t = %g s: a thrust and a "
                              "mass flow must be >= 0", what, e->table_file, bad,
                              y[bad[0] == 't' ? e->thrust_out : e->mdot_out],
                              bad[0] == 't' ? "N" : "kg/s", tb[i]);
    }
    return LV_OK;
}

static lv_status table_outputs(const lv_pctx *c, const lv_ynode *key, const char *what,
                               lv_engine_def *e)
{
    const lv_table *t = e->table;
    if (lv_table_n_dims(t) != 1)
        return lv_pk_fail(c, key, "%s: table '%s' has %zu axes; an engine table has one (time, s)",
                    what, e->table_file, lv_table_n_dims(t));
    const size_t no = lv_table_n_out(t);
    int found = 0;
    if (lv_table_out_index(t, "thrust", &e->thrust_out, NULL) == LV_OK &&
        lv_table_out_index(t, "mdot", &e->mdot_out, NULL) == LV_OK) {
        found = 1;
    } else if (no == 2 && strcmp(lv_table_out_name(t, 0), "col2") == 0 &&
               strcmp(lv_table_out_name(t, 1), "col3") == 0) {
        e->thrust_out = 0;
        e->mdot_out = 1;
        found = 1;
    }
    if (found) { /* read in s, N, kg/s: a unit written must be those */
        if (lv_table_expect_unit(t, 1, 0, "s", NULL, c->err) != LV_OK ||
            lv_table_expect_unit(t, 0, e->thrust_out, "N", NULL, c->err) != LV_OK ||
            lv_table_expect_unit(t, 0, e->mdot_out, "kg/s", NULL, c->err) != LV_OK)
            return lv_pk_fail(c, key, "%s: %s", what, c->err->msg);
        return table_nonnegative(c, key, what, e);
    }
    char have[192] = "";
    size_t used = 0;
    for (size_t k = 0; k < no && used < sizeof have; k++)
        used += (size_t)snprintf(have + used, sizeof have - used, "%s'%.30s'", k ? ", " : "",
                                 lv_table_out_name(t, k));
    return lv_pk_fail(c, key, "%s: table '%s' needs outputs 'thrust' [N] and 'mdot' [kg/s] (a .mat "
                "matrix: columns t, thrust, mdot); it has %s", what, e->table_file, have);
}

/* A table given as `path` or {file, var, interp, extrap}: loaded into *tab; the resolved
 * path and .mat variable go to *file and *var. `extrap_default` applies when not given. */
lv_status lv_pk_table(const lv_pctx *c, const lv_ynode *key, const lv_ynode *v,
                      const char *what, lv_extrap extrap_default, char **file_out,
                      char **var_out, lv_table **tab)
{
    return lv_pk_table_out(c, key, v, what, extrap_default, file_out, var_out, NULL, tab);
}

lv_status lv_pk_table_out(const lv_pctx *c, const lv_ynode *key, const lv_ynode *v,
                          const char *what, lv_extrap extrap_default, char **file_out,
                          char **var_out, const lv_ynode **output, lv_table **tab)
{
    static const char *const keys_out[] = { "file", "var", "interp", "extrap", "output", NULL };
    static const char *const keys_plain[] = { "file", "var", "interp", "extrap", NULL };
    static const char *const interps[] = { "linear", "pchip", NULL };
    static const char *const extraps[] = { "clamp", "error", "linear", NULL };
    static const lv_extrap extrap_of[] = { LV_EXTRAP_CLAMP, LV_EXTRAP_ERROR, LV_EXTRAP_LINEAR };
    const char *const *keys = output != NULL ? keys_out : keys_plain;
    lv_table_opts opts = { LV_INTERP_LINEAR, extrap_default };
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
            (st = get_str(c, o, what, "var", var_out)) != LV_OK)
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
    *file_out = resolve_file(c, rel);
    if (*var_out == NULL && lv_table_path_is_mat(rel))
        *var_out = file_stem(rel);
    if (*file_out == NULL || (lv_table_path_is_mat(rel) && *var_out == NULL))
        return lv_pk_nomem(c);

    /* Only regular files: a device or a FIFO could block the parser forever. */
    struct stat sb;
    if (stat(*file_out, &sb) != 0)
        return lv_pk_fail(c, at, "%s: %s: cannot read '%s': %s", what, key->text, *file_out,
                          LV_STRERROR(errno));
    if (!S_ISREG(sb.st_mode))
        return lv_pk_fail(c, at, "%s: %s: '%s' is not a regular file", what, key->text,
                          *file_out);

    if (*var_out != NULL)
        st = lv_table_load_mat(*file_out, *var_out, &opts, tab, c->err);
    else
        st = lv_table_load_csv(*file_out, &opts, tab, c->err);
    if (st != LV_OK)
        return lv_fail_prefix(c->err, st == LV_ERR_NOMEM ? st : LV_ERR_INPUT, "%s:%d:%d: %s: %s",
                              c->file, key->line, key->col, what, key->text);
    return LV_OK;
}

static lv_status parse_table(const lv_pctx *c, const lv_ynode *key, const lv_ynode *v,
                             const char *what, lv_engine_def *e)
{
    lv_status st = lv_pk_table(c, key, v, what, LV_EXTRAP_CLAMP, &e->table_file,
                                   &e->table_var, &e->table);
    return st != LV_OK ? st : table_outputs(c, key, what, e);
}

/* ---- stages and engines --------------------------------------------------------------- */

static lv_status parse_engine(const lv_pctx *c, const lv_ynode *n, const char *stage, size_t k,
                              lv_engine_def *e)
{
    static const char *const keys[] = { "name", "table", "thrust_vac", "isp_vac", "mdot",
                                        "exit_area", "count", "throttle_min", "throttle_max",
                                        NULL };
    static const char *const constant[] = { "thrust_vac", "isp_vac", "mdot" };
    char what[LV_WHAT_MAX], eng[96];
    const lv_ynode *v;
    lv_status st;

    label(n, "engine", k, eng, sizeof eng);
    snprintf(what, sizeof what, "stage '%s', %s", stage, eng);
    st = lv_pk_check_map(c, n, what, keys);
    if (st != LV_OK)
        return st;
    e->loc = loc_of(n);
    e->count = 1;
    if ((v = lv_pk_get(n, "name")) != NULL) {
        st = get_name(c, v, what, 1, &e->name);
    } else {
        char def[LV_NAME_MAX + 32];
        snprintf(def, sizeof def, "%s.e%zu", stage, k + 1);
        e->name = dup_text(def);
        st = e->name != NULL ? LV_OK : lv_pk_nomem(c);
    }
    if (st != LV_OK)
        return st;

    const lv_ynode *table = lv_pk_get(n, "table");
    for (size_t i = 0; i < 3; i++)
        if (table != NULL && lv_pk_get(n, constant[i]) != NULL)
            return lv_pk_fail(c, lv_pk_key(n, constant[i]), "%s: give either 'table' or constant data "
                        "(thrust_vac with isp_vac or mdot), not both", what);
    if (table == NULL && lv_pk_get(n, "thrust_vac") == NULL && lv_pk_get(n, "isp_vac") == NULL &&
        lv_pk_get(n, "mdot") == NULL)
        return lv_pk_fail(c, n, "%s: needs either 'table' or 'thrust_vac' with 'isp_vac' or 'mdot'",
                    what);
    char slot[2 * LV_NAME_MAX + 32];
    e->thrust_vac = e->isp_vac = e->mdot = LV_NO_SLOT;
    if (table == NULL) {
        snprintf(slot, sizeof slot, "%s.thrust_vac", e->name);
        if ((st = lv_pk_need(c, n, what, "thrust_vac", &v)) != LV_OK ||
            (st = lv_pk_slot(c, v, what, "thrust_vac", slot, "N", LV_RANGE_POS, 0,
                             &e->thrust_vac)) != LV_OK)
            return st;
        const lv_ynode *isp = lv_pk_get(n, "isp_vac"), *mdot = lv_pk_get(n, "mdot");
        if (isp != NULL && mdot != NULL)
            return lv_pk_fail(c, lv_pk_key(n, isp->line > mdot->line ||
                                           (isp->line == mdot->line && isp->col > mdot->col)
                                       ? "isp_vac" : "mdot"),
                        "%s: give exactly one of 'isp_vac' and 'mdot', not both", what);
        if (isp == NULL && mdot == NULL)
            return lv_pk_fail(c, n, "%s: a constant engine needs 'isp_vac' [s] or 'mdot' [kg/s]",
                        what);
        snprintf(slot, sizeof slot, "%s.%s", e->name, isp != NULL ? "isp_vac" : "mdot");
        if (isp != NULL)
            st = lv_pk_slot(c, isp, what, "isp_vac", slot, "s", LV_RANGE_POS, 0, &e->isp_vac);
        else
            st = lv_pk_slot(c, mdot, what, "mdot", slot, "kg/s", LV_RANGE_POS, 0, &e->mdot);
        if (st != LV_OK)
            return st;
    }
    snprintf(slot, sizeof slot, "%s.exit_area", e->name);
    if ((v = lv_pk_get(n, "exit_area")) != NULL)
        st = lv_pk_slot(c, v, what, "exit_area", slot, "m^2", LV_RANGE_NONNEG, 0, &e->exit_area);
    else
        st = lv_pk_slot_default(c, slot, "m^2", 0.0, LV_RANGE_NONNEG, &e->exit_area);
    if (st != LV_OK)
        return st;
    /* the throttle range c_s may take (guidance's throttle laws and tables are clamped into
     * it): 0 <= min <= max */
    static const char *const tk[2] = {"throttle_min", "throttle_max"};
    lv_slot *ts[2] = {&e->throttle_min, &e->throttle_max};
    for (int i = 0; i < 2; i++) {
        snprintf(slot, sizeof slot, "%s.%s", e->name, tk[i]);
        const lv_range r = i == 0 ? LV_RANGE_NONNEG : LV_RANGE_POS;
        if ((v = lv_pk_get(n, tk[i])) != NULL)
            st = lv_pk_slot(c, v, what, tk[i], slot, "", r, 0, ts[i]);
        else
            st = lv_pk_slot_default(c, slot, "", (double)i, r, ts[i]);
        if (st != LV_OK)
            return st;
    }
    if (c->m->slots[e->throttle_min].value > c->m->slots[e->throttle_max].value)
        return lv_pk_fail(c, lv_pk_get(n, "throttle_min") ? lv_pk_get(n, "throttle_min")
                                                          : lv_pk_get(n, "throttle_max"),
                          "%s: throttle_min %g is above throttle_max %g", what,
                          c->m->slots[e->throttle_min].value, c->m->slots[e->throttle_max].value);
    if ((v = lv_pk_get(n, "count")) != NULL && (st = get_int(c, v, what, "count", 1, &e->count))
                                                 != LV_OK)
        return st;
    if (table != NULL)
        return parse_table(c, lv_pk_key(n, "table"), table, what, e);
    return LV_OK;
}

/* One {x, y, z}-like mapping of `rigid_body` (`sub`: its key): the components `comp[nc]` as
 * slots "<stage>.rigid_body.<sub>.<comp>" with `unit`; a missing one takes `dflt[i]` (NAN:
 * required). `angles`: the components may also be written `<comp>_deg`. */
static lv_status parse_rigid_vec(const lv_pctx *c, const lv_ynode *rb, const char *stage,
                                 const char *sub, const char *const *comp, size_t nc,
                                 const char *unit, lv_range range, const double *dflt,
                                 int angles, lv_slot *out)
{
    char what[LV_WHAT_MAX], slot[LV_NAME_MAX + 64], deg[32];
    const char *known[16];
    size_t nk = 0;
    for (size_t i = 0; i < nc; i++) {
        known[nk++] = comp[i];
        if (angles)
            known[nk++] = i == 0 ? "pitch_deg" : "yaw_deg";
    }
    known[nk] = NULL;
    snprintf(what, sizeof what, "stage '%s', rigid_body, %s", stage, sub);
    const lv_ynode *n = lv_pk_get(rb, sub);
    lv_status st;
    if (n != NULL && lv_yaml_is_null(n))
        n = NULL;
    if (n != NULL && n->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, n, "%s: a mapping such as {%s: ..} expected", what, comp[0]);
    if (n != NULL && (st = lv_pk_check_map(c, n, what, known)) != LV_OK)
        return st;
    for (size_t i = 0; i < nc; i++) {
        snprintf(deg, sizeof deg, "%s_deg", comp[i]);
        snprintf(slot, sizeof slot, "%s.rigid_body.%s.%s", stage, sub, comp[i]);
        const lv_ynode *v = lv_pk_get(n, comp[i]), *vd = angles ? lv_pk_get(n, deg) : NULL;
        if (v != NULL && vd != NULL)
            return lv_pk_fail(c, lv_pk_key(n, deg), "%s: '%s' and '%s' given both", what,
                              comp[i], deg);
        if (v == NULL && vd == NULL && isnan(dflt[i]))
            return lv_pk_fail(c, n != NULL ? n : lv_pk_key(rb, sub) ? lv_pk_key(rb, sub) : rb,
                              "%s: '%s' is missing", what, comp[i]);
        st = v != NULL || vd != NULL
                 ? lv_pk_slot(c, v ? v : vd, what, v ? comp[i] : deg, slot, unit, range,
                              vd != NULL, &out[i])
                 : lv_pk_slot_default(c, slot, unit, dflt[i], range, &out[i]);
        if (st != LV_OK)
            return st;
    }
    return LV_OK;
}

/* rigid_body: {inertia_full: {xx, yy, zz, xy, xz, yz}, inertia_empty: {..}, cg_full: {x, y, z},
 * cg_empty: {..}, engine_position: {x, y, z}, misalignment: {pitch_deg, yaw_deg}}: the 6-DoF
 * data of the stack this stage drives (lv_rigid_body_def). inertia_full's xx, yy, zz are
 * required; the empty values default to the full ones as written, the rest to 0. */
static lv_status parse_rigid_body(const lv_pctx *c, const lv_ynode *rb, lv_stage_def *s)
{
    static const char *const keys[] = {"inertia_full", "inertia_empty", "cg_full", "cg_empty",
                                       "engine_position", "misalignment", NULL};
    static const char *const ic[6] = {"xx", "yy", "zz", "xy", "xz", "yz"};
    static const char *const xyz[3] = {"x", "y", "z"};
    static const char *const py[2] = {"pitch", "yaw"};
    char what[LV_WHAT_MAX];
    lv_status st;
    lv_rigid_body_def *r = &s->rigid;
    if (rb == NULL || lv_yaml_is_null(rb))
        return LV_OK;
    snprintf(what, sizeof what, "stage '%s', rigid_body", s->name);
    if (rb->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, rb, "%s: a mapping such as {inertia_full: {xx: 1e5, yy: 4e6, zz: "
                          "4e6}} expected", what);
    if ((st = lv_pk_check_map(c, rb, what, keys)) != LV_OK)
        return st;
    if (lv_pk_get(rb, "inertia_full") == NULL)
        return lv_pk_fail(c, rb, "%s: 'inertia_full' is missing (at least {xx, yy, zz} in kg "
                          "m^2)", what);
    r->present = 1;
    r->loc = loc_of(rb);
    const double need[6] = {NAN, NAN, NAN, 0.0, 0.0, 0.0}, zero[3] = {0.0, 0.0, 0.0};
    if ((st = parse_rigid_vec(c, rb, s->name, "inertia_full", ic, 6, "kg.m2", LV_RANGE_ANY, need,
                              0, r->inertia_full)) != LV_OK)
        return st;
    double full[6];
    for (int i = 0; i < 6; i++)
        full[i] = c->m->slots[r->inertia_full[i]].value;
    if ((st = parse_rigid_vec(c, rb, s->name, "inertia_empty", ic, 6, "kg.m2", LV_RANGE_ANY, full,
                              0, r->inertia_empty)) != LV_OK ||
        (st = parse_rigid_vec(c, rb, s->name, "cg_full", xyz, 3, "m", LV_RANGE_ANY, zero, 0,
                              r->cg_full)) != LV_OK)
        return st;
    for (int i = 0; i < 3; i++)
        full[i] = c->m->slots[r->cg_full[i]].value;
    lv_slot mis[2];
    if ((st = parse_rigid_vec(c, rb, s->name, "cg_empty", xyz, 3, "m", LV_RANGE_ANY, full, 0,
                              r->cg_empty)) != LV_OK ||
        (st = parse_rigid_vec(c, rb, s->name, "engine_position", xyz, 3, "m", LV_RANGE_ANY, zero,
                              0, r->engine_pos)) != LV_OK ||
        (st = parse_rigid_vec(c, rb, s->name, "misalignment", py, 2, "rad",
                              (lv_range){-0.1, 0.1, 0, 0}, zero, 1, mis)) != LV_OK)
        return st;
    r->mis_pitch = mis[0];
    r->mis_yaw = mis[1];
    return LV_OK;
}

static lv_status parse_stage(const lv_pctx *pc, const lv_ynode *n, size_t k, lv_stage_def *s)
{
    static const char *const keys[] = { "name", "dry_mass", "propellant_mass", "engines",
                                        "rigid_body", NULL };
    char what[LV_WHAT_MAX], buf[64], slot[LV_NAME_MAX + 32];
    const lv_ynode *v;
    lv_status st;
    lv_pctx sc = *pc; /* the stage owns its slots and its engines' */
    sc.owner = LV_OWN_STAGE;
    sc.owner_index = k;
    const lv_pctx *c = &sc;

    label(n, "stage", k, what, sizeof what);
    if ((st = lv_pk_check_map(c, n, what, keys)) != LV_OK)
        return st;
    s->loc = loc_of(n);
    if ((st = lv_pk_need(c, n, what, "name", &v)) != LV_OK ||
        (st = get_name(c, v, what, 0, &s->name)) != LV_OK)
        return st;
    snprintf(slot, sizeof slot, "%s.dry_mass", s->name);
    if ((st = lv_pk_need(c, n, what, "dry_mass", &v)) != LV_OK ||
        (st = lv_pk_slot(c, v, what, "dry_mass", slot, "kg", LV_RANGE_NONNEG, 0, &s->dry_mass)) !=
            LV_OK)
        return st;
    snprintf(slot, sizeof slot, "%s.propellant_mass", s->name);
    if ((st = lv_pk_need(c, n, what, "propellant_mass", &v)) != LV_OK ||
        (st = lv_pk_slot(c, v, what, "propellant_mass", slot, "kg", LV_RANGE_NONNEG, 0,
                         &s->propellant_mass)) != LV_OK)
        return st;
    if ((st = parse_rigid_body(c, lv_pk_get(n, "rigid_body"), s)) != LV_OK)
        return st;

    v = lv_pk_get(n, "engines");
    if (v == NULL || lv_yaml_is_null(v))
        return LV_OK;
    if (v->kind != LV_YNODE_SEQ)
        return lv_pk_fail(c, v, "%s: engines: a list expected, found %s", what,
                    describe(v, buf, sizeof buf));
    if (v->n == 0)
        return LV_OK;
    s->engines = calloc(v->n, sizeof *s->engines);
    if (s->engines == NULL)
        return lv_pk_nomem(c);
    s->n_engines = v->n;
    for (size_t i = 0; i < v->n; i++)
        if ((st = parse_engine(c, v->kids[i], s->name, i, &s->engines[i])) != LV_OK)
            return st;
    return LV_OK;
}

static lv_status parse_stages(const lv_pctx *c, const lv_ynode *n)
{
    lv_mission_def *m = c->m;
    char buf[64];
    lv_status st;

    if (n->kind != LV_YNODE_SEQ || n->n == 0)
        return lv_pk_fail(c, n, "stages: a list of at least one stage expected, found %s",
                    n->kind == LV_YNODE_SEQ ? "an empty list" : describe(n, buf, sizeof buf));
    m->stages = calloc(n->n, sizeof *m->stages);
    if (m->stages == NULL)
        return lv_pk_nomem(c);
    m->n_stages = n->n;
    for (size_t i = 0; i < n->n; i++) {
        if ((st = parse_stage(c, n->kids[i], i, &m->stages[i])) != LV_OK)
            return st;
        for (size_t j = 0; j < i; j++)
            if (strcmp(m->stages[j].name, m->stages[i].name) == 0)
                return lv_pk_fail(c, lv_pk_get(n->kids[i], "name"), "stage '%s': duplicate stage name "
                            "(first at line %d)", m->stages[i].name, m->stages[j].loc.line);
    }
    /* Engine names are unique in the whole mission: outputs are named after them. */
    for (size_t i = 0; i < m->n_stages; i++)
        for (size_t a = 0; a < m->stages[i].n_engines; a++)
            for (size_t j = 0; j <= i; j++)
                for (size_t b = 0; b < (j == i ? a : m->stages[j].n_engines); b++)
                    if (strcmp(m->stages[i].engines[a].name, m->stages[j].engines[b].name) == 0) {
                        const lv_ynode *en = n->kids[i];
                        const lv_ynode *at = lv_pk_get(lv_pk_get(en, "engines")->kids[a], "name");
                        return lv_pk_fail(c, at != NULL ? at : lv_pk_get(en, "engines")->kids[a],
                                    "stage '%s': duplicate engine name '%s' (first at line %d)",
                                    m->stages[i].name, m->stages[i].engines[a].name,
                                    m->stages[j].engines[b].loc.line);
                    }
    return LV_OK;
}

/* ---- the parameter set (userPar) ------------------------------------------------------ */

/* The shared parameter set: the parameters of the registered model types that a root phase
 * takes from the mission (phase_type.h), e.g. start_lat [rad], start_h [m]. */
static const lv_var *mission_param(const char *name)
{
    for (const lv_phase_type *const *t = lv_phase_types(); *t != NULL; t++)
        for (size_t i = 0; i < (*t)->n_mission_params; i++)
            if (strcmp((*t)->mission_params[i].name, name) == 0)
                return &(*t)->mission_params[i];
    return NULL;
}

/* Its allowed values: the narrowest every type that takes it accepts. */
static lv_range mission_param_range(const char *name)
{
    lv_range r = LV_RANGE_ANY;
    for (const lv_phase_type *const *t = lv_phase_types(); *t != NULL; t++)
        for (size_t i = 0; i < (*t)->n_mission_params; i++)
            if ((*t)->mission_param_ranges != NULL &&
                strcmp((*t)->mission_params[i].name, name) == 0) {
                const lv_range q = (*t)->mission_param_ranges[i];
                if (q.lo > r.lo || (q.lo == r.lo && q.lo_open)) {
                    r.lo = q.lo;
                    r.lo_open = q.lo_open;
                }
                if (q.hi < r.hi || (q.hi == r.hi && q.hi_open)) {
                    r.hi = q.hi;
                    r.hi_open = q.hi_open;
                }
            }
    return r;
}

/* Angles (rad) and angular rates (rad/s): these alone may be written as *_deg. */
static int is_angular(const char *unit)
{
    return strcmp(unit, "rad") == 0 || strcmp(unit, "rad/s") == 0;
}

/* Copies `key` without a trailing "_deg" into buf; returns 1 if it had one. */
static int strip_deg(const char *key, char *buf, size_t cap)
{
    size_t n = strlen(key);
    const int deg = n > 4 && strcmp(key + n - 4, "_deg") == 0;
    if (deg)
        n -= 4;
    if (n >= cap)
        n = cap - 1;
    memcpy(buf, key, n);
    buf[n] = '\0';
    return deg;
}

static lv_status parse_params(const lv_pctx *pc, const lv_ynode *n)
{
    lv_mission_def *m = pc->m;
    const char *what = "parameters";
    lv_status st;
    lv_pctx sc = *pc;
    sc.owner = LV_OWN_PARAM;
    const lv_pctx *c = &sc;

    if (n == NULL || lv_yaml_is_null(n))
        return LV_OK;
    if ((st = lv_pk_check_map(c, n, what, NULL)) != LV_OK)
        return st;
    const size_t np = n->n / 2;
    if (np == 0)
        return LV_OK;
    m->param_names = calloc(np, sizeof *m->param_names);
    m->param_values = calloc(np, sizeof *m->param_values);
    if (m->param_names == NULL || m->param_values == NULL)
        return lv_pk_nomem(c);
    for (size_t i = 0; i < np; i++) {
        const lv_ynode *k = n->kids[2 * i], *v = n->kids[2 * i + 1];
        char base[LV_NAME_MAX + 1];
        const int deg = strip_deg(k->text, base, sizeof base);
        const lv_var *pv = k->len > LV_NAME_MAX ? NULL : mission_param(base);
        if (pv == NULL) {
            lv_suggest s;
            char hint[192], degs[64][LV_NAME_MAX + 8];
            size_t nd = 0;
            lv_suggest_init(&s, k->text);
            for (int pass = 0; pass < 2; pass++) /* the names, then the angles' _deg forms */
                for (const lv_phase_type *const *t = lv_phase_types(); *t != NULL; t++)
                    for (size_t j = 0; j < (*t)->n_mission_params; j++) {
                        const lv_var *q = &(*t)->mission_params[j];
                        if (mission_param(q->name) != q)
                            continue; /* named by an earlier type already */
                        if (pass == 0)
                            lv_suggest_add(&s, q->name);
                        else if (is_angular(q->unit) && nd < 64) {
                            snprintf(degs[nd], sizeof degs[nd], "%s_deg", q->name);
                            lv_suggest_add(&s, degs[nd++]);
                        }
                    }
            lv_suggest_text(&s, hint, sizeof hint);
            return lv_pk_fail(c, k, "%s: unknown parameter '%.60s'%s", what, k->text, hint);
        }
        if (deg && !is_angular(pv->unit))
            return lv_pk_fail(c, k, "%s: '%s' is not an angle: write '%s' in SI units (m, m/s) "
                        "without _deg", what, k->text, base);
        for (size_t j = 0; j < i; j++)
            if (strcmp(m->param_names[j], base) == 0)
                return lv_pk_fail(c, k, "%s: '%s' given twice (as '%s' at line %d)", what, base,
                            n->kids[2 * j]->text, n->kids[2 * j]->line);
        if ((st = lv_pk_slot(c, v, what, k->text, base, pv->unit, mission_param_range(base),
                             deg, &m->param_values[i])) != LV_OK)
            return st;
        if ((m->param_names[i] = dup_text(base)) == NULL)
            return lv_pk_nomem(c);
        m->n_params = i + 1;
    }
    return LV_OK;
}

/* ---- phases --------------------------------------------------------------------------- */

static const char *const end_kind_names[] = { "burnout", "altitude", "speed", "apogee",
                                               "impact",  "var",      "time" };

const char *lv_end_kind_name(lv_end_kind k)
{
    return (unsigned)k < 7 ? end_kind_names[k] : "?";
}

/* e->name: the kind's (or variable's) name, "_2", "_3" for the second and third of a kind
 * among the phase's ends prev[0..k). */
static void end_name(size_t k, const lv_end_def *prev, lv_end_def *e)
{
    const char *label = e->kind == LV_END_VAR ? e->var : end_kind_names[e->kind];
    size_t same = 0;
    for (size_t j = 0; j < k; j++)
        same += prev[j].kind == e->kind &&
                (e->kind != LV_END_VAR || strcmp(prev[j].var, e->var) == 0);
    if (same > 0)
        snprintf(e->name, sizeof e->name, "%s_%zu", label, same + 1);
    else
        snprintf(e->name, sizeof e->name, "%s", label);
}

/* The value of end event #k of phase `phase` (of kind e->kind) at `v` (NULL: the ground, 0 m)
 * as slot "<phase>.end.<kind>", "_2", "_3" for the second and third of a kind. */
static lv_status end_slot(const lv_pctx *c, const lv_ynode *v, const char *what,
                          const char *key, const char *phase, size_t k, const lv_end_def *prev,
                          lv_end_def *e)
{
    char slot[2 * LV_NAME_MAX + 300];
    end_name(k, prev, e);
    snprintf(slot, sizeof slot, "%s.end.%s", phase, e->name);
    /* a variable's unit is known once the model is built (mission.c); "" until then */
    const char *unit = e->kind == LV_END_SPEED ? "m/s"
                       : e->kind == LV_END_TIME ? "s"
                       : e->kind == LV_END_VAR  ? (e->deg ? "rad" : "")
                                                : "m";
    /* a time the clock tells from 0; an end on a variable takes its variable's range when the
     * model is built (mission.c) */
    const lv_range range = e->kind == LV_END_SPEED  ? LV_RANGE_NONNEG
                           : e->kind == LV_END_TIME ? (lv_range){1e-9, HUGE_VAL, 0, 0}
                                                    : LV_RANGE_ANY;
    if (v == NULL)
        return lv_pk_slot_default(c, slot, unit, 0.0, range, &e->value);
    return lv_pk_slot(c, v, what, key, slot, unit, range, e->deg, &e->value);
}

/* End event #k of phase `phase`; its value is slot "<phase>.end.<kind>" ("_2", "_3" for the
 * second and third of a kind). */
static lv_status parse_end(const lv_pctx *c, const lv_ynode *n, const char *phase, size_t k,
                           const lv_end_def *prev, lv_end_def *e)
{
    static const char *const words[] = { "burnout", "apogee", "impact", "altitude", "speed",
                                         NULL };
    static const char *const dirs[] = { "rising", "falling", "both", NULL };
    static const lv_dir dir_of[] = { LV_DIR_RISING, LV_DIR_FALLING, LV_DIR_BOTH };
    char what[LV_WHAT_MAX], buf[64];
    const lv_ynode *v;
    size_t i;
    lv_status st;

    snprintf(what, sizeof what, "phase '%s', end event #%zu", phase, k + 1);
    e->loc = loc_of(n);
    e->value = LV_NO_SLOT;
    e->direction = LV_DIR_FALLING; /* burnout, apogee and impact: always falling */
    if (n->kind == LV_YNODE_SCALAR) {
        if ((st = lv_pk_enum(c, n, what, "end", words, &i)) != LV_OK)
            return st;
        if (i >= 3)
            return lv_pk_fail(c, n, "%s: '%s' needs a value: write {%s: <%s>}", what, n->text, n->text,
                        i == 3 ? "m" : "m/s");
        e->kind = i == 0 ? LV_END_BURNOUT : i == 1 ? LV_END_APOGEE : LV_END_IMPACT;
        if (e->kind == LV_END_IMPACT) /* ground level 0 m */
            return end_slot(c, NULL, what, NULL, phase, k, prev, e);
        end_name(k, prev, e);
        return LV_OK;
    }
    if (n->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, n, "%s: an event name (burnout, apogee, impact) or a mapping such as "
                    "{altitude: 100000} expected, found %s", what, describe(n, buf, sizeof buf));
    /* {altitude: h}, {speed: v}, {impact: h}, {time: dt}, {output: name, value: x}, or any
     * variable of the phase's model as the key: {mach: 1}, {fpa_deg: 0} (checked against the
     * model when the mission is loaded) */
    if ((st = lv_pk_check_map(c, n, what, NULL)) != LV_OK)
        return st;
    const lv_ynode *kind = NULL, *output = lv_pk_get(n, "output");
    for (size_t j = 0; j + 1 < n->n; j += 2) {
        const char *key = n->kids[j]->text;
        if (strcmp(key, "direction") == 0 || (output != NULL && (strcmp(key, "output") == 0 ||
                                                                 strcmp(key, "value") == 0)))
            continue;
        if (kind != NULL)
            return lv_pk_fail(c, n->kids[j], "%s: one event per entry ('%s' and '%s'); write them "
                        "as two entries", what, kind->text, key);
        kind = n->kids[j];
    }
    if (output != NULL && kind != NULL)
        return lv_pk_fail(c, kind, "%s: an entry with 'output' takes 'value' and 'direction' "
                          "only, not '%s'", what, kind->text);
    if (output != NULL) {
        const char *name;
        if ((st = lv_pk_text(c, output, what, "output", &name)) != LV_OK ||
            (st = lv_pk_need(c, n, what, "value", &v)) != LV_OK)
            return st;
        if (output->len > 255)
            return lv_pk_fail(c, output, "%s: output: a variable name of 1 to 255 characters "
                              "expected", what);
        e->kind = LV_END_VAR;
        char base[256];
        e->deg = strip_deg(name, base, sizeof base);
        if ((e->var = dup_text(base)) == NULL)
            return lv_pk_nomem(c);
        if ((st = end_slot(c, v, what, "value", phase, k, prev, e)) != LV_OK)
            return st;
    } else {
        if (kind == NULL)
            return lv_pk_fail(c, n, "%s: which event? add altitude, speed, impact, time, or a "
                              "variable of the model such as {mach: 1}", what);
        v = lv_pk_get(n, kind->text);
        if (strcmp(kind->text, "burnout") == 0 || strcmp(kind->text, "apogee") == 0)
            return lv_pk_fail(c, kind, "%s: '%s' takes no value: write it as a plain list entry",
                              what, kind->text);
        if (strcmp(kind->text, "impact") == 0)
            e->kind = LV_END_IMPACT;
        else if (strcmp(kind->text, "speed") == 0)
            e->kind = LV_END_SPEED;
        else if (strcmp(kind->text, "altitude") == 0)
            e->kind = LV_END_ALTITUDE;
        else if (strcmp(kind->text, "time") == 0)
            e->kind = LV_END_TIME;
        else {
            if (kind->len == 0 || kind->len > 255)
                return lv_pk_fail(c, kind, "%s: a variable name of 1 to 255 characters expected",
                                  what);
            char base[256];
            e->kind = LV_END_VAR;
            e->deg = strip_deg(kind->text, base, sizeof base);
            if ((e->var = dup_text(base)) == NULL)
                return lv_pk_nomem(c);
        }
        if ((st = end_slot(c, v, what, kind->text, phase, k, prev, e)) != LV_OK)
            return st;
    }
    if (e->kind == LV_END_TIME) {
        if (lv_pk_get(n, "direction") != NULL)
            return lv_pk_fail(c, lv_pk_key(n, "direction"), "%s: a time end has no direction",
                              what);
        return LV_OK;
    }
    if ((v = lv_pk_get(n, "direction")) != NULL) {
        if ((st = lv_pk_enum(c, v, what, "direction", dirs, &i)) != LV_OK)
            return st;
        if (e->kind == LV_END_IMPACT && dir_of[i] != LV_DIR_FALLING)
            return lv_pk_fail(c, v, "%s: impact is always falling (altitude decreasing through "
                              "%g m)", what, lv_mission_def_value(c->m, e->value));
        e->direction = dir_of[i];
    } else if (e->kind != LV_END_IMPACT) {
        e->direction = LV_DIR_BOTH;
    }
    return LV_OK;
}

static lv_status parse_integrator(const lv_pctx *c, const lv_ynode *n, const char *phase,
                                  lv_phase_def *ph)
{
    static const char *const keys[] = { "method", "tolerance", "intervals", "output_interval",
                                        "fixed_step", NULL };
    static const char *const methods[] = { "dassl", "cvode-adams", "dopri5", "rk4", "euler",
                                           NULL };
    static const char *const nkeys[3] = { "tolerance", "output_interval", "fixed_step" };
    static const char *const units[3] = { "", "s", "s" };
    static const double defaults[3] = { 1e-6, 0.0, 0.0 };
    char what[LV_WHAT_MAX], slot[LV_NAME_MAX + 48];
    const lv_ynode *v;
    size_t i = 0;
    lv_status st;

    snprintf(what, sizeof what, "phase '%s', integrator", phase);
    ph->intervals = 500;
    if (n != NULL && lv_yaml_is_null(n))
        n = NULL;
    if (n != NULL && (st = lv_pk_check_map(c, n, what, keys)) != LV_OK)
        return st;
    if ((v = lv_pk_get(n, "method")) != NULL &&
        (st = lv_pk_enum(c, v, what, "method", methods, &i)) != LV_OK)
        return st;
    if ((ph->method = dup_text(methods[i])) == NULL)
        return lv_pk_nomem(c);
    lv_slot *out[3] = { &ph->tolerance, &ph->output_interval, &ph->fixed_step };
    for (int j = 0; j < 3; j++) {
        snprintf(slot, sizeof slot, "%s.integrator.%s", phase, nkeys[j]);
        const lv_range r = j == 0 ? LV_RANGE_TOLERANCE : LV_RANGE_NONNEG;
        if ((v = lv_pk_get(n, nkeys[j])) != NULL)
            st = lv_pk_slot(c, v, what, nkeys[j], slot, units[j], r, 0, out[j]);
        else
            st = lv_pk_slot_default(c, slot, units[j], defaults[j], r, out[j]);
        if (st != LV_OK)
            return st;
    }
    if (lv_pk_get(n, "output_interval") != NULL &&
        lv_mission_def_value(c->m, ph->output_interval) > 0.0)
        ph->intervals = 0;
    if ((v = lv_pk_get(n, "intervals")) != NULL) {
        if ((st = get_int(c, v, what, "intervals", 0, &ph->intervals)) != LV_OK)
            return st;
        if (ph->intervals > 0 && lv_mission_def_value(c->m, ph->output_interval) > 0.0)
            return lv_pk_fail(c, lv_pk_key(n, "intervals"), "%s: give either 'intervals' or "
                        "'output_interval', not both", what);
    }
    return LV_OK;
}

/* set: {name: value}: overrides of the phase model's states and parameters after the
 * hand-off, slots "<phase>.set.<name>" (units known once the model is built: mission.c). */
static lv_status parse_set(const lv_pctx *c, const lv_ynode *n, const char *phase,
                           lv_phase_def *ph)
{
    char what[LV_WHAT_MAX];
    lv_status st;

    snprintf(what, sizeof what, "phase '%s', set", phase);
    if (n == NULL || lv_yaml_is_null(n))
        return LV_OK;
    if ((st = lv_pk_check_map(c, n, what, NULL)) != LV_OK)
        return st;
    const size_t ns = n->n / 2;
    if (ns == 0)
        return LV_OK;
    ph->set_names = calloc(ns, sizeof *ph->set_names);
    ph->set_values = calloc(ns, sizeof *ph->set_values);
    ph->set_locs = calloc(ns, sizeof *ph->set_locs);
    ph->set_deg = calloc(ns, sizeof *ph->set_deg);
    if (ph->set_names == NULL || ph->set_values == NULL || ph->set_locs == NULL ||
        ph->set_deg == NULL)
        return lv_pk_nomem(c);
    for (size_t i = 0; i < ns; i++) {
        const lv_ynode *k = n->kids[2 * i], *v = n->kids[2 * i + 1];
        if (k->len == 0 || k->len > 255)
            return lv_pk_fail(c, k, "%s: a variable name of 1 to 255 characters expected", what);
        char base[256], slot[LV_NAME_MAX + 270];
        const int deg = strip_deg(k->text, base, sizeof base);
        for (size_t j = 0; j < i; j++)
            if (strcmp(ph->set_names[j], base) == 0)
                return lv_pk_fail(c, k, "%s: '%s' set twice (line %d)", what, base,
                            ph->set_locs[j].line);
        snprintf(slot, sizeof slot, "%s.set.%s", phase, base);
        /* its variable's range once the model is built (mission.c) */
        if ((st = lv_pk_slot(c, v, what, k->text, slot, "", LV_RANGE_ANY, deg,
                             &ph->set_values[i])) != LV_OK)
            return st;
        ph->set_locs[i] = loc_of(k);
        ph->set_deg[i] = (unsigned char)deg;
        if ((ph->set_names[i] = dup_text(base)) == NULL)
            return lv_pk_nomem(c);
        ph->n_set = i + 1;
    }
    return LV_OK;
}

static lv_status find_stage(const lv_pctx *c, const lv_ynode *v, const char *what, size_t *idx)
{
    const lv_mission_def *m = c->m;
    const char *s;
    lv_status st = lv_pk_text(c, v, what, "stages", &s);
    if (st != LV_OK)
        return st;
    lv_suggest sug;
    lv_suggest_init(&sug, s);
    for (size_t i = 0; i < m->n_stages; i++) {
        if (strcmp(m->stages[i].name, s) == 0) {
            *idx = i;
            return LV_OK;
        }
        lv_suggest_add(&sug, m->stages[i].name);
    }
    char hint[192];
    lv_suggest_text(&sug, hint, sizeof hint);
    return lv_pk_fail(c, v, "%s: stages: no stage named '%.60s'%s", what, s, hint);
}

/* The keys every phase has; a model type adds its own (phase_type.h). */
static const char *const phase_keys[] = { "name", "model", "stages", "from", "start_time",
                                          "stop_time", "end", "integrator", "set",
                                          "alternative", NULL };

/* Checks the phase's keys: the common ones and its type's. A key that belongs to another
 * model type says which. */
static lv_status check_phase_keys(const lv_pctx *c, const lv_ynode *n, const char *what,
                                  const lv_phase_type *type)
{
    const char *known[64];
    size_t nk = 0;
    for (size_t i = 0; phase_keys[i] != NULL; i++)
        known[nk++] = phase_keys[i];
    for (size_t i = 0; type->keys != NULL && type->keys[i] != NULL && nk < 63; i++)
        known[nk++] = type->keys[i];
    known[nk] = NULL;
    for (size_t i = 0; i + 1 < n->n; i += 2) {
        const char *key = n->kids[i]->text;
        int mine = 0;
        for (size_t j = 0; j < nk && !mine; j++)
            mine = strcmp(known[j], key) == 0;
        if (mine)
            continue;
        char owners[160] = "";
        size_t used = 0, n_own = 0;
        for (const lv_phase_type *const *t = lv_phase_types(); *t != NULL; t++)
            for (size_t j = 0; (*t)->keys != NULL && (*t)->keys[j] != NULL; j++)
                if (strcmp((*t)->keys[j], key) == 0 && used < sizeof owners) {
                    used += (size_t)snprintf(owners + used, sizeof owners - used, "%s%s",
                                             used ? ", " : "", (*t)->name);
                    n_own++;
                }
        if (used > 0)
            return lv_pk_fail(c, n->kids[i], "%s: '%s' applies to the %s model%s only (this "
                              "phase's model is %s)", what, key, owners, n_own > 1 ? "s" : "",
                              type->name);
    }
    return lv_pk_check_map(c, n, what, known);
}

/* Everything but `from`, which needs all names: its node goes to *from. */
static lv_status parse_phase(const lv_pctx *pc, const lv_ynode *n, size_t k, lv_phase_def *ph,
                             const lv_ynode **from)
{
    char what[LV_WHAT_MAX], buf[64], slot[LV_NAME_MAX + 32];
    const lv_ynode *v;
    lv_status st;
    lv_pctx sc = *pc; /* the phase owns its slots (file index; reordered with the phases) */
    sc.owner = LV_OWN_PHASE;
    sc.owner_index = k;
    const lv_pctx *c = &sc;
    const lv_world_kind world = c->m->env.world;

    label(n, "phase", k, what, sizeof what);
    ph->parent = -1;
    ph->t_start = LV_NO_SLOT;
    if (n->kind != LV_YNODE_MAP)
        return lv_pk_check_map(c, n, what, phase_keys);
    ph->loc = loc_of(n);

    /* the model first: it decides which keys the phase may have */
    const char *models[16];
    size_t nm = 0, i;
    for (const lv_phase_type *const *t = lv_phase_types(); *t != NULL && nm < 15; t++)
        models[nm++] = (*t)->name;
    models[nm] = NULL;
    if ((st = lv_pk_need(c, n, what, "model", &v)) != LV_OK ||
        (st = lv_pk_enum(c, v, what, "model", models, &i)) != LV_OK)
        return st;
    ph->type = lv_phase_types()[i];
    if (ph->type->world != world)
        return lv_pk_fail(c, v, "%s: model %s needs environment world: %s (this mission's world is "
                    "%s)", what, models[i], world == LV_WORLD_FLAT ? "planet" : "flat",
                    world == LV_WORLD_FLAT ? "flat" : "planet");
    if ((st = check_phase_keys(c, n, what, ph->type)) != LV_OK)
        return st;
    if ((st = lv_pk_need(c, n, what, "name", &v)) != LV_OK ||
        (st = get_name(c, v, what, 0, &ph->name)) != LV_OK)
        return st;
    label(n, "phase", k, what, sizeof what);

    if ((st = lv_pk_need(c, n, what, "stages", &v)) != LV_OK)
        return st;
    if (v->kind != LV_YNODE_SEQ || v->n == 0)
        return lv_pk_fail(c, v, "%s: stages: a list of stage names (bottom first) expected, found %s",
                    what, v->kind == LV_YNODE_SEQ ? "an empty list" : describe(v, buf, sizeof buf));
    if ((ph->stages = calloc(v->n, sizeof *ph->stages)) == NULL ||
        (ph->stage_locs = calloc(v->n, sizeof *ph->stage_locs)) == NULL)
        return lv_pk_nomem(c);
    for (size_t j = 0; j < v->n; j++) {
        if ((st = find_stage(c, v->kids[j], what, &ph->stages[j])) != LV_OK)
            return st;
        ph->stage_locs[j] = loc_of(v->kids[j]);
        ph->n_stages = j + 1;
        for (size_t q = 0; q < j; q++)
            if (ph->stages[q] == ph->stages[j])
                return lv_pk_fail(c, v->kids[j], "%s: stages: '%s' listed twice", what,
                            v->kids[j]->text);
    }

    if ((v = lv_pk_get(n, "alternative")) != NULL) {
        static const char *const bools[] = { "false", "true", NULL };
        size_t b;
        if ((st = lv_pk_enum(c, v, what, "alternative", bools, &b)) != LV_OK)
            return st;
        ph->alternative = b == 1;
    }
    const char *parent_name;
    *from = lv_pk_get(n, "from");
    if (*from != NULL && (st = lv_pk_text(c, *from, what, "from", &parent_name)) != LV_OK)
        return st;
    double t0 = *from == NULL ? 0.0 : -INFINITY, t_stop;
    if ((v = lv_pk_get(n, "start_time")) != NULL) {
        snprintf(slot, sizeof slot, "%s.start_time", ph->name);
        if ((st = lv_pk_slot(c, v, what, "start_time", slot, "s", LV_RANGE_ANY, 0,
                             &ph->t_start)) != LV_OK)
            return st;
        t0 = lv_mission_def_value(c->m, ph->t_start);
    }
    /* Without `from` and start_time the phase starts at 0; with `from` at the parent's end,
     * known only when the parent has run. */
    if ((st = lv_pk_need(c, n, what, "stop_time", &v)) != LV_OK ||
        (st = lv_pk_num(c, v, what, "stop_time", &t_stop)) != LV_OK)
        return st;
    if (!(t_stop > t0))
        return lv_pk_fail(c, v, "%s: stop_time %g s must be greater than the start time %g s", what,
                    t_stop, t0);
    snprintf(slot, sizeof slot, "%s.stop_time", ph->name);
    if ((st = lv_pk_slot(c, v, what, "stop_time", slot, "s", LV_RANGE_ANY, 0, &ph->t_stop)) !=
        LV_OK)
        return st;

    v = lv_pk_get(n, "end");
    if (v != NULL && !lv_yaml_is_null(v)) {
        if (v->kind != LV_YNODE_SEQ)
            return lv_pk_fail(c, v, "%s: end: a list of events expected, e.g. [burnout, apogee], "
                        "found %s", what, describe(v, buf, sizeof buf));
        if (v->n > 0) {
            if ((ph->ends = calloc(v->n, sizeof *ph->ends)) == NULL)
                return lv_pk_nomem(c);
            for (size_t j = 0; j < v->n; j++) {
                ph->n_ends = j + 1; /* counted first: a failed entry's name is freed too */
                if ((st = parse_end(c, v->kids[j], ph->name, j, ph->ends, &ph->ends[j])) != LV_OK)
                    return st;
            }
        }
    }
    if ((st = parse_integrator(c, lv_pk_get(n, "integrator"), ph->name, ph)) != LV_OK)
        return st;
    if (ph->type->parse != NULL && (st = ph->type->parse(c, n, ph)) != LV_OK)
        return st;
    if ((st = parse_set(c, lv_pk_get(n, "set"), ph->name, ph)) != LV_OK)
        return st;
    return ph->type->check != NULL ? ph->type->check(c, n, ph) : LV_OK;
}

/* A `from` chain that comes back: "P2 -> P3 -> P2", from the first member in file order. */
static lv_status check_cycles(const lv_pctx *c, const lv_ynode *const *from)
{
    const lv_mission_def *m = c->m;
    const size_t n = m->n_phases;
    size_t *seen = calloc(n, sizeof *seen); /* walk number + 1 that reached the phase */
    unsigned char *done = calloc(n, 1);
    lv_status st = LV_OK;
    if (seen == NULL || done == NULL) {
        st = lv_pk_nomem(c);
        goto fail;
    }
    for (size_t i = 0; i < n; i++) {
        long j = (long)i;
        while (j >= 0 && !done[j] && seen[j] != i + 1) {
            seen[j] = i + 1;
            j = m->phases[j].parent;
        }
        if (j >= 0 && !done[j]) { /* back on this walk: a cycle through j */
            size_t first = (size_t)j;
            for (long q = m->phases[j].parent; q != j; q = m->phases[q].parent)
                if ((size_t)q < first)
                    first = (size_t)q;
            char path[320];
            size_t used = (size_t)snprintf(path, sizeof path, "%s", m->phases[first].name);
            long q = (long)first;
            do {
                q = m->phases[q].parent;
                if (used < sizeof path)
                    used += (size_t)snprintf(path + used, sizeof path - used, " -> %s",
                                             m->phases[q].name);
            } while ((size_t)q != first);
            st = lv_pk_fail(c, from[first], "phase '%s': from: cycle %s (each phase starts from the "
                      "next); a root phase has no 'from'", m->phases[first].name, path);
            goto fail;
        }
        for (j = (long)i; j >= 0 && !done[j]; j = m->phases[j].parent)
            done[j] = 1;
    }
fail:
    free(seen);
    free(done);
    return st;
}

/* Parents before children; otherwise file order: repeatedly take the lowest file index
 * whose parent has been taken (a binary min-heap of ready phases). */
static lv_status order_phases(const lv_pctx *c)
{
    lv_mission_def *m = c->m;
    const size_t n = m->n_phases;
    size_t *heap = malloc(n * sizeof *heap), *pos = malloc(n * sizeof *pos);
    size_t *kid_first = malloc(n * sizeof *kid_first), *kid_next = malloc(n * sizeof *kid_next);
    lv_phase_def *out = malloc(n * sizeof *out);
    size_t nh = 0, taken = 0;
    lv_status st = LV_OK;
    if (heap == NULL || pos == NULL || kid_first == NULL || kid_next == NULL || out == NULL) {
        st = lv_pk_nomem(c);
        goto fail;
    }
    for (size_t i = 0; i < n; i++)
        kid_first[i] = SIZE_MAX;
    for (size_t i = n; i-- > 0;) { /* children lists in file order */
        if (m->phases[i].parent >= 0) {
            const size_t p = (size_t)m->phases[i].parent;
            kid_next[i] = kid_first[p];
            kid_first[p] = i;
        }
    }
    for (size_t i = 0; i < n; i++) /* the roots, ascending: already a min-heap */
        if (m->phases[i].parent < 0)
            heap[nh++] = i;
    while (nh > 0) {
        const size_t top = heap[0];
        heap[0] = heap[--nh];
        for (size_t a = 0;;) { /* sift down */
            size_t b = 2 * a + 1;
            if (b >= nh)
                break;
            if (b + 1 < nh && heap[b + 1] < heap[b])
                b++;
            if (heap[a] <= heap[b])
                break;
            const size_t t = heap[a];
            heap[a] = heap[b];
            heap[b] = t;
            a = b;
        }
        pos[top] = taken++;
        for (size_t k = kid_first[top]; k != SIZE_MAX; k = kid_next[k]) {
            size_t a = nh++; /* sift up */
            heap[a] = k;
            while (a > 0 && heap[(a - 1) / 2] > heap[a]) {
                const size_t t = heap[a];
                heap[a] = heap[(a - 1) / 2];
                heap[(a - 1) / 2] = t;
                a = (a - 1) / 2;
            }
        }
    }
    /* taken == n: check_cycles() ran first, every phase reaches a root */
    for (size_t i = 0; i < n; i++) {
        out[pos[i]] = m->phases[i];
        const int p = m->phases[i].parent;
        out[pos[i]].parent = p >= 0 ? (int)pos[p] : -1;
        out[pos[i]].file_index = i;
    }
    free(m->phases);
    m->phases = out;
    out = NULL;
    for (size_t i = 0; i < m->n_slots; i++) /* the phases' slots follow them */
        if (m->slots[i].owner == LV_OWN_PHASE)
            m->slots[i].owner_index = pos[m->slots[i].owner_index];
fail:
    free(heap);
    free(pos);
    free(kid_first);
    free(kid_next);
    free(out);
    return st;
}

/* 1 if phase a is phase d or one of its ancestors. */
static int is_ancestor(const lv_mission_def *m, int a, int d)
{
    for (; d >= 0; d = m->phases[d].parent)
        if (d == a)
            return 1;
    return 0;
}

/* The child of `anc` on the way down to `d` (anc an ancestor of d, anc != d); anc = -1: the
 * root of d. */
static int child_towards(const lv_mission_def *m, int anc, int d)
{
    while (m->phases[d].parent != anc)
        d = m->phases[d].parent;
    return d;
}

static lv_src_loc slot_loc(const lv_mission_def *m, lv_slot s, lv_src_loc fallback)
{
    return s != LV_NO_SLOT && m->slots[s].loc.line > 0 ? m->slots[s].loc : fallback;
}

/* What the phase tree must satisfy to be flown (after ordering, parents first):
 *  - a child carries only stages its parent carries (a stage cannot appear from nowhere);
 *  - a stage flies in one branch at a time: two phases whose branches split at a phase X both
 *    carry it only if one of the two branches is marked `alternative: true` (abort cases);
 *  - a child's stop_time is after its parent's stop_time (the latest its parent can end:
 *    otherwise it may have nothing to run), and a child's start_time, if written, is its
 *    parent's end (known only when the parent ends at its stop_time, without end events). */
static lv_status check_tree(const lv_pctx *c)
{
    const lv_mission_def *m = c->m;
    for (size_t k = 0; k < m->n_phases; k++) {
        const lv_phase_def *ph = &m->phases[k];
        if (ph->parent < 0)
            continue;
        const lv_phase_def *par = &m->phases[ph->parent];
        if (ph->type->check_parent != NULL) {
            const lv_status st = ph->type->check_parent(c, ph, par);
            if (st != LV_OK)
                return st;
        }
        for (size_t i = 0; i < ph->n_stages; i++) {
            int carried = 0;
            for (size_t j = 0; j < par->n_stages; j++)
                carried |= par->stages[j] == ph->stages[i];
            if (!carried)
                return lv_fail(c->err, LV_ERR_INPUT,
                               "%s:%d:%d: phase '%s': stages: '%s' is not carried by its parent "
                               "'%s' (stages: a child carries some of its parent's stages)",
                               m->path, ph->stage_locs[i].line, ph->stage_locs[i].column,
                               ph->name, m->stages[ph->stages[i]].name, par->name);
        }
        const double stop = lv_mission_def_value(m, ph->t_stop);
        const double pstop = lv_mission_def_value(m, par->t_stop);
        lv_src_loc at = slot_loc(m, ph->t_stop, ph->loc);
        if (!(stop > pstop))
            return lv_fail(c->err, LV_ERR_INPUT,
                           "%s:%d:%d: phase '%s': stop_time %g s is not after the stop_time %g "
                           "s of its parent '%s': it would have nothing to run when '%s' runs "
                           "to its limit",
                           m->path, at.line, at.column, ph->name, stop, pstop, par->name,
                           par->name);
        if (ph->t_start != LV_NO_SLOT) {
            const double t0 = lv_mission_def_value(m, ph->t_start);
            at = slot_loc(m, ph->t_start, ph->loc);
            if (par->n_ends > 0)
                return lv_fail(c->err, LV_ERR_INPUT,
                               "%s:%d:%d: phase '%s': start_time: a phase with `from` starts "
                               "when its parent '%s' ends, which an end event decides: remove "
                               "start_time",
                               m->path, at.line, at.column, ph->name, par->name);
            if (t0 != pstop)
                return lv_fail(c->err, LV_ERR_INPUT,
                               "%s:%d:%d: phase '%s': start_time %g s is not the end %g s of its "
                               "parent '%s' (a phase starts from its parent's final state: "
                               "remove start_time)",
                               m->path, at.line, at.column, ph->name, t0, pstop, par->name);
        }
    }
    /* a stage in two branches at once */
    for (size_t a = 0; a < m->n_phases; a++)
        for (size_t b = a + 1; b < m->n_phases; b++) {
            const lv_phase_def *pa = &m->phases[a], *pb = &m->phases[b];
            if (is_ancestor(m, (int)a, (int)b))
                continue;
            for (size_t i = 0; i < pa->n_stages; i++)
                for (size_t j = 0; j < pb->n_stages; j++) {
                    if (pa->stages[i] != pb->stages[j])
                        continue;
                    int x = pa->parent; /* the phase where the two branches split (-1: roots) */
                    while (x >= 0 && !is_ancestor(m, x, (int)b))
                        x = m->phases[x].parent;
                    const lv_phase_def *ca = &m->phases[child_towards(m, x, (int)a)];
                    const lv_phase_def *cb = &m->phases[child_towards(m, x, (int)b)];
                    if (ca->alternative || cb->alternative)
                        continue;
                    return lv_fail(c->err, LV_ERR_INPUT,
                                   "%s:%d:%d: phase '%s': stages: '%s' also flies in phase '%s' "
                                   "(line %d) of another branch%s%s%s: a stage is in one place "
                                   "at a time; if the branches are alternatives (an abort "
                                   "case), mark one `alternative: true`",
                                   m->path, pb->stage_locs[j].line, pb->stage_locs[j].column,
                                   pb->name, m->stages[pb->stages[j]].name, pa->name,
                                   pa->loc.line, x >= 0 ? " (they split after '" : "",
                                   x >= 0 ? m->phases[x].name : "", x >= 0 ? "')" : "");
                }
        }
    return LV_OK;
}

static lv_status parse_phases(const lv_pctx *c, const lv_ynode *n)
{
    lv_mission_def *m = c->m;
    const lv_ynode **from = NULL;
    char buf[64];
    lv_status st;

    if (n->kind != LV_YNODE_SEQ || n->n == 0)
        return lv_pk_fail(c, n, "phases: a list of at least one phase expected, found %s",
                    n->kind == LV_YNODE_SEQ ? "an empty list" : describe(n, buf, sizeof buf));
    if (n->n > (size_t)INT_MAX)
        return lv_pk_fail(c, n, "phases: too many phases");
    m->phases = calloc(n->n, sizeof *m->phases);
    from = calloc(n->n, sizeof *from);
    if (m->phases == NULL || from == NULL) {
        st = lv_pk_nomem(c);
        goto fail;
    }
    m->n_phases = n->n;
    for (size_t i = 0; i < n->n; i++) {
        if ((st = parse_phase(c, n->kids[i], i, &m->phases[i], &from[i])) != LV_OK)
            goto fail;
        for (size_t j = 0; j < i; j++)
            if (strcmp(m->phases[j].name, m->phases[i].name) == 0) {
                st = lv_pk_fail(c, lv_pk_get(n->kids[i], "name"), "phase '%s': duplicate phase name "
                          "(first at line %d)", m->phases[i].name, m->phases[j].loc.line);
                goto fail;
            }
    }
    for (size_t i = 0; i < n->n; i++) {
        if (from[i] == NULL)
            continue;
        lv_suggest sug;
        lv_suggest_init(&sug, from[i]->text);
        for (size_t j = 0; j < n->n && m->phases[i].parent < 0; j++) {
            if (strcmp(m->phases[j].name, from[i]->text) == 0)
                m->phases[i].parent = (int)j;
            lv_suggest_add(&sug, m->phases[j].name);
        }
        if (m->phases[i].parent == (int)i) {
            st = lv_pk_fail(c, from[i], "phase '%s': from: a phase cannot start from itself",
                      m->phases[i].name);
            goto fail;
        }
        if (m->phases[i].parent < 0) {
            char hint[192];
            lv_suggest_text(&sug, hint, sizeof hint);
            st = lv_pk_fail(c, from[i], "phase '%s': from: no phase named '%.60s'%s",
                      m->phases[i].name, from[i]->text, hint);
            goto fail;
        }
    }
    if ((st = check_cycles(c, from)) == LV_OK && (st = order_phases(c)) == LV_OK)
        st = check_tree(c);
fail:
    free(from);
    return st;
}

/* ---- the file ------------------------------------------------------------------------- */

/* NULL when `s` is a UTC instant written "YYYY-MM-DDThh:mm:ss[.f...]Z" that exists in the
 * proleptic Gregorian calendar and in UTC; otherwise why not. A second 60 exists only in a leap
 * second, 23:59:60 of a day that ended with one (ERFA's table of them, core/utc.h): mission
 * time counts SI seconds from the epoch, and the exports place the epoch and every later
 * instant with the same table. */
static const char *epoch_check(const char *s)
{
    static const char *const form = "an ISO 8601 UTC time like 2026-03-01T12:00:00Z expected";
    /* the fixed part: digits at these positions, separators at the others */
    static const char tmpl[] = "dddd-dd-ddTdd:dd:dd";
    for (size_t i = 0; i < sizeof tmpl - 1; i++) {
        const char ch = s[i];
        if (tmpl[i] == 'd' ? !(ch >= '0' && ch <= '9') : ch != tmpl[i])
            return form;
    }
    const char *p = s + sizeof tmpl - 1;
    if (*p == '.') { /* a fraction of a second: one digit or more */
        const char *q = ++p;
        while (*p >= '0' && *p <= '9')
            p++;
        if (p == q)
            return form;
    }
    if (p[0] != 'Z')
        return "the time must end with Z (UTC), without a zone offset";
    if (p[1] != '\0')
        return "text after the Z";
    int v[6];
    static const int at[6] = {0, 5, 8, 11, 14, 17}, len[6] = {4, 2, 2, 2, 2, 2};
    for (int k = 0; k < 6; k++) {
        v[k] = 0;
        for (int i = 0; i < len[k]; i++)
            v[k] = 10 * v[k] + (s[at[k] + i] - '0');
    }
    const int y = v[0], mo = v[1], d = v[2];
    static const int mdays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    const int leap = (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
    if (mo < 1 || mo > 12)
        return "the month must be 01 to 12";
    if (d < 1 || d > mdays[mo - 1] + (mo == 2 && leap))
        return "no such day in that month";
    if (v[3] > 23)
        return "the hour must be 00 to 23";
    if (v[4] > 59)
        return "the minute must be 00 to 59";
    if (v[5] > 60)
        return "the second must be 00 to 59 (60 only in a leap second)";
    lv_tai tai;
    if (v[5] == 60 && lv_utc_parse(s, &tai) == LV_UTC_NO_LEAP)
        return "no leap second here: a second 60 exists only as 23:59:60 at the end of a day "
               "that had one (IERS Bulletin C, e.g. 2016-12-31T23:59:60Z)";
    return NULL;
}

/* The mission's `key` (a scalar) holds at most `max` bytes and, with `line`, no control
 * character: what every result file copies stays bounded and one line (an OEM header, a CSV
 * title). */
static lv_status text_bounded(const lv_pctx *c, const lv_ynode *v, const char *key, size_t max,
                              int line)
{
    if (v->kind != LV_YNODE_SCALAR)
        return LV_OK; /* lv_pk_text says what it is */
    if (v->len > max)
        return lv_pk_fail(c, v, "mission: %s of %zu bytes: at most %zu (it is copied into every "
                          "result file)", key, v->len, max);
    for (size_t i = 0; line && i < v->len; i++) {
        const unsigned char ch = (unsigned char)v->text[i];
        if (ch < 0x20 || ch == 0x7f)
            return lv_pk_fail(c, v, "mission: %s: one line of text without control characters "
                              "(byte %zu is 0x%02x)", key, i + 1, ch);
    }
    return LV_OK;
}

static lv_status parse_root(const lv_pctx *c, const lv_ynode *root)
{
    static const char *const keys[] = { "mission", "environment", "parameters", "stages",
                                        "phases", "dispersions", "targeting", NULL };
    static const char *const mkeys[] = { "name", "description", "epoch", NULL };
    lv_mission_def *m = c->m;
    const lv_ynode *v, *info;
    char buf[64];
    lv_status st;

    if (root->kind != LV_YNODE_MAP)
        return lv_pk_fail(c, root, "the top level must be a mapping with 'mission', 'stages' and "
                    "'phases', found %s", describe(root, buf, sizeof buf));
    if ((st = lv_pk_check_map(c, root, "top level", keys)) != LV_OK ||
        (st = lv_pk_need(c, root, "top level", "mission", &info)) != LV_OK ||
        (st = lv_pk_check_map(c, info, "mission", mkeys)) != LV_OK ||
        (st = lv_pk_need(c, info, "mission", "name", &v)) != LV_OK ||
        (st = text_bounded(c, v, "name", LV_MISSION_NAME_MAX, 1)) != LV_OK ||
        (st = get_str(c, v, "mission", "name", &m->name)) != LV_OK)
        return st;
    if ((v = lv_pk_get(info, "epoch")) != NULL) {
        const char *ep;
        if ((st = lv_pk_text(c, v, "mission", "epoch", &ep)) != LV_OK)
            return st;
        /* ISO 8601 UTC, as CZML and CCSDS OEM want it: 2026-03-01T12:00:00Z */
        const char *why = epoch_check(ep);
        if (why != NULL)
            return lv_pk_fail(c, v, "mission: epoch: '%.40s': %s", ep, why);
        if ((m->epoch = dup_text(ep)) == NULL)
            return lv_pk_nomem(c);
    }
    if ((v = lv_pk_get(info, "description")) != NULL && !lv_yaml_is_null(v) &&
        ((st = text_bounded(c, v, "description", LV_DESCRIPTION_MAX, 0)) != LV_OK ||
         (st = get_str(c, v, "mission", "description", &m->description)) != LV_OK))
        return st;
    if ((st = parse_env(c, lv_pk_get(root, "environment"))) != LV_OK ||
        (st = parse_params(c, lv_pk_get(root, "parameters"))) != LV_OK)
        return st;
    if ((st = lv_pk_need(c, root, "top level", "stages", &v)) != LV_OK ||
        (st = parse_stages(c, v)) != LV_OK)
        return st;
    if ((st = lv_pk_need(c, root, "top level", "phases", &v)) != LV_OK ||
        (st = parse_phases(c, v)) != LV_OK ||
        (st = lv_targeting_def_parse(c, lv_pk_get(root, "targeting"))) != LV_OK)
        return st;
    /* after everything else: it names the parameters the other sections register */
    if ((st = lv_disp_def_parse(c, lv_pk_get(root, "dispersions"))) != LV_OK)
        return st;
    return check_slot_names(c);
}

lv_status lv_mission_def_parse(const char *text, size_t len, const char *name, const char *dir,
                               lv_mission_def **out, lv_err *err)
{
    lv_ynode *root = NULL;
    lv_status st;

    if (out == NULL || (text == NULL && len > 0))
        return lv_fail(err, LV_ERR_INPUT, "lv_mission_def_parse: NULL argument");
    *out = NULL;
    lv_mission_def *m = calloc(1, sizeof *m);
    if (m == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", name ? name : "mission");
    m->path = dup_text(name != NULL ? name : "<mission>");
    m->dir = dup_text(dir != NULL ? dir : ".");
    if (m->path == NULL || m->dir == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", name ? name : "mission");
        goto fail;
    }
    const lv_pctx c = { m->path, err, m, LV_OWN_ENV, 0 };
    if ((st = lv_yaml_load(text != NULL ? text : "", len, m->path, &root, err)) != LV_OK ||
        (st = parse_root(&c, root)) != LV_OK)
        goto fail;
    lv_yaml_free(root);
    *out = m;
    return LV_OK;
fail:
    lv_yaml_free(root);
    lv_mission_def_free(m);
    return st;
}

lv_status lv_mission_def_load(const char *path, lv_mission_def **out, lv_err *err)
{
    char *text = NULL, *dir = NULL;
    size_t len = 0, cap = 0;
    FILE *f = NULL;
    lv_status st;

    if (out == NULL || path == NULL)
        return lv_fail(err, LV_ERR_INPUT, "lv_mission_def_load: NULL argument");
    *out = NULL;
    f = fopen(path, "rb");
    if (f == NULL)
        return lv_fail(err, LV_ERR_IO, "%s: cannot open the mission file: %s", path,
                       LV_STRERROR(errno));
    for (;;) {
        if (len == cap) {
            cap = cap ? 2 * cap : 4096;
            char *t = realloc(text, cap);
            if (t == NULL) {
                st = lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", path);
                goto fail;
            }
            text = t;
        }
        const size_t got = fread(text + len, 1, cap - len, f);
        len += got;
        if (got == 0)
            break;
    }
    if (ferror(f)) {
        st = lv_fail(err, LV_ERR_IO, "%s: cannot read: %s", path, LV_STRERROR(errno ? errno : EIO));
        goto fail;
    }
    const char *slash = strrchr(path, '/');
    const size_t nd = slash == NULL ? 1 : (slash == path ? 1 : (size_t)(slash - path));
    if ((dir = malloc(nd + 1)) == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "%s: out of memory", path);
        goto fail;
    }
    memcpy(dir, slash == NULL ? "." : path, nd);
    dir[nd] = '\0';
    st = lv_mission_def_parse(text, len, path, dir, out, err);
fail:
    if (f != NULL)
        fclose(f);
    free(text);
    free(dir);
    return st;
}

void lv_mission_def_free(lv_mission_def *m)
{
    if (m == NULL)
        return;
    free(m->name);
    free(m->description);
    free(m->epoch);
    free(m->env.atmo_file);
    free(m->env.atmo_var);
    free(m->env.wind_file);
    free(m->env.wind_var);
    free(m->path);
    free(m->dir);
    for (size_t i = 0; i < m->n_files; i++)
        free(m->files[i]);
    free(m->files);
    free(m->env.planet);
    free(m->env.pdef.zonal);
    free(m->env.pdef.coef_file);
    free(m->env.gravity);
    free(m->env.atmosphere);
    for (size_t i = 0; i < m->n_params; i++)
        free(m->param_names[i]);
    free(m->param_names);
    free(m->param_values);
    for (size_t i = 0; i < m->n_slots; i++) {
        free(m->slots[i].name);
        free(m->slots[i].unit);
    }
    free(m->slots);
    for (size_t i = 0; i < m->n_stages; i++) {
        lv_stage_def *s = &m->stages[i];
        for (size_t k = 0; k < s->n_engines; k++) {
            free(s->engines[k].name);
            free(s->engines[k].table_file);
            free(s->engines[k].table_var);
            lv_table_free(s->engines[k].table);
        }
        free(s->engines);
        free(s->name);
    }
    free(m->stages);
    for (size_t i = 0; i < m->n_phases; i++) {
        lv_phase_def *ph = &m->phases[i];
        free(ph->name);
        if (ph->type != NULL && ph->type->cfg_free != NULL)
            ph->type->cfg_free(ph->type_cfg);
        free(ph->stages);
        free(ph->stage_locs);
        for (size_t j = 0; j < ph->n_ends; j++)
            free(ph->ends[j].var);
        free(ph->ends);
        free(ph->method);
        for (size_t k = 0; k < ph->n_set; k++)
            free(ph->set_names[k]);
        free(ph->set_names);
        free(ph->set_values);
        free(ph->set_locs);
        free(ph->set_deg);
    }
    free(m->phases);
    lv_targeting_def_free(m->targeting);
    lv_disp_def_free(m->disp);
    free(m);
}

double lv_mission_def_param(const lv_mission_def *m, const char *name, double fallback)
{
    if (m == NULL || name == NULL)
        return fallback;
    for (size_t i = 0; i < m->n_params; i++)
        if (strcmp(m->param_names[i], name) == 0)
            return m->slots[m->param_values[i]].value;
    return fallback;
}

double lv_mission_def_value(const lv_mission_def *m, lv_slot s)
{
    return s < m->n_slots ? m->slots[s].value : NAN;
}

lv_slot lv_mission_def_slot(const lv_mission_def *m, const char *name)
{
    for (size_t i = 0; i < m->n_slots; i++)
        if (strcmp(m->slots[i].name, name) == 0)
            return i;
    return LV_NO_SLOT;
}
