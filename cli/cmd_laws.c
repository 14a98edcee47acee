/* cmd_laws.c - `lvsim laws [NAME] [--markdown]`: the registered steering and throttle laws
 * (lv_guidance.h, lv_laws_get) with their keys, units, ranges, defaults and descriptions, as
 * mission files write them (`guidance:`, `throttle:`). --markdown prints the key tables of
 * docs/guidance.md, which a test compares with this output.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "common.h"

/* "[-90, 90] deg", "(0, 100]", ">= 0 s", "any" for a number key; the words of a choice. */
static void range_text(const lv_law_key *k, int md, char *buf, size_t cap)
{
    if (k->type == LV_KEY_TABLE) {
        snprintf(buf, cap, "%s", md ? "a table" : "table");
        return;
    }
    if (k->type == LV_KEY_CHOICE) {
        size_t used = 0;
        buf[0] = '\0';
        for (size_t i = 0; k->choices[i] != NULL && used < cap; i++)
            used += (size_t)snprintf(buf + used, cap - used, md ? "%s`%s`" : "%s%s",
                                     i ? (md ? ", " : "|") : "", k->choices[i]);
        return;
    }
    const int ang = (k->flags & LV_KEY_ANGLE) != 0;
    const double f = ang ? 1.0 / LV_DEG : 1.0;
    const char *unit = ang ? " deg" : LV_UNIT_ONE(k->unit) ? "" : " ";
    const char *u = ang ? "" : LV_UNIT_AFTER_NUMBER(k->unit);
    const int lo = isfinite(k->lo), hi = isfinite(k->hi);
    if (lo && hi)
        snprintf(buf, cap, "%c%.10g, %.10g%c%s%s", k->lo_open ? '(' : '[', k->lo * f, k->hi * f,
                 k->hi_open ? ')' : ']', unit, u);
    else if (lo)
        snprintf(buf, cap, "%s %.10g%s%s", k->lo_open ? ">" : ">=", k->lo * f, unit, u);
    else if (hi)
        snprintf(buf, cap, "%s %.10g%s%s", k->hi_open ? "<" : "<=", k->hi * f, unit, u);
    else
        snprintf(buf, cap, "any");
}

static int in_range(const lv_law_key *k, double v)
{
    return (k->lo_open ? v > k->lo : v >= k->lo) && (k->hi_open ? v < k->hi : v <= k->hi);
}

static void default_text(const lv_law_key *k, char *buf, size_t cap)
{
    if (k->type == LV_KEY_TABLE) {
        snprintf(buf, cap, "none");
    } else if (k->type == LV_KEY_CHOICE) {
        snprintf(buf, cap, "%s", k->choices[(int)k->dflt]);
    } else if (isnan(k->dflt) && !(k->flags & LV_KEY_OPTIONAL)) {
        snprintf(buf, cap, k->instead_of ? "required without %s" : "required",
                 k->instead_of ? k->instead_of : "");
    } else if (isnan(k->dflt) || !in_range(k, k->dflt)) {
        snprintf(buf, cap, "none");
    } else {
        const int ang = (k->flags & LV_KEY_ANGLE) != 0;
        snprintf(buf, cap, "%.10g%s%s", ang ? k->dflt / LV_DEG : k->dflt,
                 ang ? " deg" : LV_UNIT_ONE(k->unit) ? "" : " ",
                 ang ? "" : LV_UNIT_AFTER_NUMBER(k->unit));
    }
}

/* The key's description with where it applies: "(frame aero)", "(with q_max)", "(dof3)". */
static void description(const lv_law_key *k, const lv_law_info *law, char *buf, size_t cap)
{
    size_t used = (size_t)snprintf(buf, cap, "%s", k->description);
    const lv_law_key *fk = NULL;
    for (size_t i = 0; law != NULL && i < law->n_keys; i++)
        if (law->keys[i].type == LV_KEY_CHOICE)
            fk = &law->keys[i];
    if (k->frames != 0 && fk != NULL && used < cap) {
        used += (size_t)snprintf(buf + used, cap - used, " (frame");
        const char *sep = " ";
        for (unsigned i = 0; fk->choices[i] != NULL && i < 32 && used < cap; i++)
            if (k->frames & (1u << i)) {
                used += (size_t)snprintf(buf + used, cap - used, "%s%s", sep, fk->choices[i]);
                sep = " or ";
            }
        if (used < cap)
            used += (size_t)snprintf(buf + used, cap - used, ")");
    }
    if (k->needs != NULL && used < cap)
        used += (size_t)snprintf(buf + used, cap - used, " (with %s)", k->needs);
    if ((k->flags & LV_KEY_DOF3) && used < cap)
        snprintf(buf + used, cap - used, " (dof3 phases only)");
}

static const char *unit_text(const lv_law_key *k)
{
    /* a number's unit ("1" dimensionless); "-" for a choice or a table: no unit applies */
    return k->type != LV_KEY_NUMBER ? "-" : k->unit[0] ? k->unit : LV_UNIT_DIMENSIONLESS;
}

static void print_key(const lv_law_key *k, const lv_law_info *law, int md)
{
    char name[64], range[160], dflt[64], desc[512];
    snprintf(name, sizeof name, md ? "`%s`%s" : "%s%s", k->name,
             (k->flags & LV_KEY_ANGLE) ? (md ? " (`_deg`)" : "[_deg]") : "");
    range_text(k, md, range, sizeof range);
    default_text(k, dflt, sizeof dflt);
    description(k, law, desc, sizeof desc);
    if (md)
        printf("| | %s | %s | %s | %s | %s |\n", name, unit_text(k), range, dflt, desc);
    else
        printf("  %-16s %-5s %-22s %-28s %s\n", name, unit_text(k), range, dflt, desc);
}

/* How a file writes the law. */
static void written(const lv_law_info *l, char *buf, size_t cap)
{
    switch (l->form) {
    case LV_LAW_FORM_NAMED: snprintf(buf, cap, "guidance: {law: %s, ...}", l->name); break;
    case LV_LAW_FORM_KEYS: snprintf(buf, cap, "throttle: {KEY: ..}"); break;
    case LV_LAW_FORM_NESTED: snprintf(buf, cap, "throttle: {%s: {KEY: ..}}", l->name); break;
    case LV_LAW_FORM_WORD: snprintf(buf, cap, "throttle: %s", l->name); break;
    default: snprintf(buf, cap, "a phase without guidance:"); break;
    }
}

static void print_law(const lv_law_info *l, int md)
{
    char how[128];
    written(l, how, sizeof how);
    if (md) {
        printf("| `%s` | | | | | %s; %s%s%s%s%s |\n", l->name, l->description,
               l->form == LV_LAW_FORM_NONE ? "" : "`", how,
               l->form == LV_LAW_FORM_NONE ? "" : "`", l->needs_aero ? "; needs `aero:`" : "",
               l->n_keys == 0 ? "; no keys" : "");
    } else {
        printf("%s: %s\n  (%s%s)\n", l->name, l->description, how,
               l->needs_aero ? "; needs an aerodynamic dataset, aero:" : "");
    }
    for (size_t j = 0; j < l->n_keys; j++)
        print_key(&l->keys[j], l, md);
}

static void print_kind(lv_law_kind kind, const char *only, int md)
{
    size_t nc;
    const lv_law_key *common = lv_laws_common_keys(kind, &nc);
    const char *what = kind == LV_LAW_STEERING ? "Steering laws (`guidance:`)"
                                               : "Throttle laws (`throttle:`)";
    if (only == NULL) {
        if (md)
            printf("**%s**\n\n| law | key | unit | range | default | description |\n"
                   "|---|---|---|---|---|---|\n", what);
        else
            printf("# %s\n", what);
        if (nc > 0)
            printf(md ? "| every law | | | | | |\n" : "every law also takes:\n");
        for (size_t j = 0; j < nc; j++)
            print_key(&common[j], NULL, md);
    }
    for (size_t i = 0; i < lv_laws_count(); i++) {
        lv_law_info l;
        if (lv_laws_get(i, &l, NULL) == LV_OK && l.kind == kind &&
            (only == NULL || strcmp(only, l.name) == 0))
            print_law(&l, md);
    }
}

static int laws_run(const cli_cmd *self, int argc, char **argv)
{
    const char *only = NULL;
    int md = 0;
    for (int i = 0; i < argc; i++) {
        if (strcmp(argv[i], "--markdown") == 0)
            md = 1;
        else if (is_option(argv[i]))
            return usage_error(self, "unknown option", argv[i]);
        else if (only != NULL)
            return usage_error(self, "laws takes at most one law name; got", argv[i]);
        else
            only = argv[i];
    }
    if (only != NULL) {
        int found = 0;
        for (size_t i = 0; i < lv_laws_count(); i++) {
            lv_law_info l;
            found |= lv_laws_get(i, &l, NULL) == LV_OK && strcmp(l.name, only) == 0;
        }
        if (!found) {
            fprintf(stderr, "lvsim: unknown law '%s'; the laws:", only);
            for (size_t i = 0; i < lv_laws_count(); i++) {
                lv_law_info l;
                if (lv_laws_get(i, &l, NULL) == LV_OK)
                    fprintf(stderr, " %s", l.name);
            }
            fprintf(stderr, "\n");
            return EXIT_INPUT;
        }
    }
    print_kind(LV_LAW_STEERING, only, md);
    if (only == NULL)
        printf("\n");
    print_kind(LV_LAW_THROTTLE, only, md);
    return EXIT_OK;
}

const cli_cmd cli_cmd_laws = {
    "laws",
    "list the steering and throttle laws with their keys",
    "[LAW] [--markdown]",
    "Lists the steering laws (a dof3 or dof6 phase's 'guidance: {law: NAME, ...}') and the\n"
    "throttle laws (a dof3 phase's 'throttle:'), or only LAW: one line per law (its name,\n"
    "what it does and how a file writes it), then one per key: name ('[_deg]': an angle also\n"
    "taken in degrees as NAME_deg), unit (SI), the values allowed (angles in degrees), the\n"
    "default ('required', 'none': not given, no run parameter) and what it is. Every number\n"
    "a file writes is a run parameter '<phase>.guidance.<key>' ('lvsim params').\n"
    "  --markdown   the same as the tables of docs/guidance.md\n",
    laws_run,
};
