/* test_phase_types.c - the cross-type contracts of the phase-model registry
 * (src/mission/phase_types.c), checked for every registered type by iterating the registry:
 *   (a) the type itself: a name, its functions, its mission parameters among its model's
 *       parameters (root-only ones among them), its end names known;
 *   (b) its mass state among its model's states;
 *   (c) the columns of a body's merged trajectory (lv_run_body_trajectory, body_<stage>.csv)
 *       that the exports read (src/post/export.c: lat, lon, h, and over the planet the ECI
 *       state r_eci_*, v_eci_*; the merge adds time and stage_mass) with body_mass, each
 *       sourced from a variable of its model or computed by its traj_extra;
 *   (d) `from_types` naming registered types; across a hand-off the merged trajectory takes
 *       the first phase's columns, so each type's sourced columns are variables of the other's
 *       model; a state of the child that the parent has no final of needs the type's handoff;
 *   (e) no type's name as a string literal outside the phase types and models (src/mission/
 *       phase_*.c, src/dynamics, src/models): the parser, the mission, the runs, the summary,
 *       post-processing and the CLI ask the registry.
 * Types broken on purpose, one defect each, fail the contract with the reason named (a
 * drag-free ballistic type whose trajectory had no `lat` once broke the exports with
 * "column 'lat': 'nan'"), and a source file naming a type fails (e). */
#include <dirent.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "check.h"
#include "lvsim/lv_mission.h"
#include "mission/phase_type.h"

#define MAX_TYPES 32

static int why_(char *why, size_t cap, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, cap, fmt, ap);
    va_end(ap);
    return 1;
}

/* name is a variable of md of one of the kinds (bits 1 << lv_var_kind). */
static int has_var(const lv_model_def *md, const char *name, unsigned kinds)
{
    lv_var_kind kind;
    size_t idx;
    return lv_model_find(md, name, &kind, &idx, NULL) == LV_OK && (kinds >> kind & 1u);
}
#define STATE (1u << LV_VAR_STATE)
#define PARAM (1u << LV_VAR_PARAMETER)
#define VALUE (1u << LV_VAR_STATE | 1u << LV_VAR_OUTPUT) /* a column of the phase's rows */

static int find_type(const lv_phase_type *const *types, const char *name)
{
    for (int i = 0; types[i] != NULL; i++)
        if (strcmp(types[i]->name, name) == 0)
            return i;
    return -1;
}

static const lv_traj_col *traj_col(const lv_phase_type *t, const char *name)
{
    for (size_t c = 0; c < t->n_traj; c++)
        if (strcmp(t->traj[c].name, name) == 0)
            return &t->traj[c];
    return NULL;
}

/* Type types[i]'s contracts (a) to (d), with defs[j] the model a phase of types[j] builds.
 * 0, or 1 with the first broken one in why[cap]. */
static int type_contract(const lv_phase_type *const *types, const lv_model_def *const *defs,
                         int i, char *why, size_t cap)
{
    const lv_phase_type *t = types[i];
    const lv_model_def *md = defs[i];
    /* (a) */
    if (t->name == NULL || t->name[0] == '\0' || t->description == NULL)
        return why_(why, cap, "a type without a name or description");
    if (find_type(types, t->name) != i)
        return why_(why, cap, "%s: registered twice", t->name);
    if (t->build == NULL || t->free_self == NULL || (t->keys != NULL && t->parse == NULL))
        return why_(why, cap, "%s: build, free_self (and parse, with keys) are required", t->name);
    for (size_t k = 0; k < t->n_mission_params; k++) {
        if (!has_var(md, t->mission_params[k].name, PARAM))
            return why_(why, cap, "%s: mission parameter '%s' is not a parameter of its model",
                        t->name, t->mission_params[k].name);
        if (t->mission_param_ranges != NULL &&
            !(t->mission_param_ranges[k].lo <= t->mission_param_ranges[k].hi))
            return why_(why, cap, "%s: mission parameter '%s': empty range", t->name,
                        t->mission_params[k].name);
    }
    for (const char *const *r = t->root_only_params; r != NULL && *r != NULL; r++) {
        int known = 0;
        for (size_t k = 0; k < t->n_mission_params; k++)
            known |= strcmp(t->mission_params[k].name, *r) == 0;
        if (!known)
            return why_(why, cap, "%s: root-only parameter '%s' is not one of its mission "
                        "parameters", t->name, *r);
    }
    for (const char *const *e = t->ends; e != NULL && *e != NULL; e++) {
        int known = 0;
        for (size_t k = 0; k < lv_phase_types_end_count(); k++)
            known |= strcmp(lv_phase_types_end_name(k), *e) == 0;
        if (!known)
            return why_(why, cap, "%s: end '%s' is not a named end", t->name, *e);
    }
    /* (b) */
    if (t->mass_state == NULL || !has_var(md, t->mass_state, STATE))
        return why_(why, cap, "%s: mass state '%s' is not a state of its model", t->name,
                    t->mass_state ? t->mass_state : "(null)");
    /* (c) */
    static const char *const need_all[] = {"lat", "lon", "h", "body_mass", NULL};
    static const char *const need_planet[] = {"r_eci_x", "r_eci_y", "r_eci_z", "v_eci_x",
                                              "v_eci_y", "v_eci_z", NULL};
    for (int w = 0; w < 2; w++)
        for (const char *const *c = w ? need_planet : need_all; *c != NULL; c++)
            if ((w == 0 || t->world == LV_WORLD_PLANET) && traj_col(t, *c) == NULL)
                return why_(why, cap, "%s: the merged trajectory has no column '%s' (the exports "
                            "read it)", t->name, *c);
    for (size_t c = 0; c < t->n_traj; c++) {
        const lv_traj_col *col = &t->traj[c];
        if (col->source == NULL && t->traj_extra == NULL)
            return why_(why, cap, "%s: trajectory column '%s' is computed, but the type has no "
                        "traj_extra", t->name, col->name);
        if (col->source != NULL && !has_var(md, col->source, VALUE))
            return why_(why, cap, "%s: trajectory column '%s' copies '%s', not a state or "
                        "output of its model", t->name, col->name, col->source);
    }
    const lv_traj_col *bm = traj_col(t, "body_mass");
    if (bm->source == NULL || strcmp(bm->source, t->mass_state) != 0)
        return why_(why, cap, "%s: trajectory column 'body_mass' must copy the mass state '%s'",
                    t->name, t->mass_state);
    /* (d) */
    for (const char *const *f = t->from_types; f != NULL && *f != NULL; f++) {
        const int j = find_type(types, *f);
        if (j < 0)
            return why_(why, cap, "%s: from_types names '%s', not a registered type", t->name,
                        *f);
        const lv_phase_type *p = types[j];
        if (p->world != t->world)
            return why_(why, cap, "%s: from '%s', a type of another world", t->name, *f);
        for (int side = 0; side < 2; side++) {
            const lv_phase_type *a = side ? p : t, *b = side ? t : p;
            const lv_model_def *mb = side ? md : defs[j];
            for (size_t c = 0; c < a->n_traj; c++)
                if (a->traj[c].source != NULL && !has_var(mb, a->traj[c].source, VALUE))
                    return why_(why, cap, "%s from %s: a body's trajectory that starts in %s "
                                "reads '%s', which %s does not have", t->name, p->name, a->name,
                                a->traj[c].source, b->name);
        }
        for (size_t s = 0; s < md->n_states && t->handoff == NULL; s++)
            if (!has_var(defs[j], md->states[s].name, VALUE))
                return why_(why, cap, "%s from %s: state '%s' has no final in the parent: the "
                            "type needs a handoff", t->name, p->name, md->states[s].name);
    }
    return 0;
}

/* ---- (e) no type's name outside the types and models -------------------------------------- */

/* Whether `text` (C source) names a registered type as a string literal outside comments. */
static const char *names_type(const char *text, const lv_phase_type *const *types)
{
    static char lit[80];
    int in_comment = 0;
    for (const char *p = text; *p != '\0'; p++) {
        if (in_comment) {
            if (p[0] == '*' && p[1] == '/')
                in_comment = 0, p++;
            continue;
        }
        if (p[0] == '/' && p[1] == '*') {
            in_comment = 1, p++;
            continue;
        }
        if (p[0] == '/' && p[1] == '/') {
            while (*p != '\0' && *p != '\n')
                p++;
            if (*p == '\0')
                break;
            continue;
        }
        if (*p != '"')
            continue;
        for (int i = 0; types[i] != NULL; i++) {
            snprintf(lit, sizeof lit, "\"%s\"", types[i]->name);
            if (strncmp(p, lit, strlen(lit)) == 0)
                return lit;
        }
        for (p++; *p != '\0' && *p != '"' && *p != '\n'; p++) /* skip the literal */
            if (*p == '\\' && p[1] != '\0')
                p++;
        if (*p == '\0')
            break;
    }
    return NULL;
}

static char *read_text(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return NULL;
    fseek(f, 0, SEEK_END);
    const long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *s = malloc((size_t)n + 1);
    if (s != NULL && fread(s, 1, (size_t)n, f) == (size_t)n)
        s[n] = '\0';
    else {
        free(s);
        s = NULL;
    }
    fclose(f);
    return s;
}

/* Where the phase types and their models live: they may name types (from_types, their own
 * names in messages). rel: the path below the source tree. */
static int may_name_types(const char *rel)
{
    return strncmp(rel, "src/mission/phase_", 18) == 0 || strncmp(rel, "src/dynamics/", 13) == 0 ||
           strncmp(rel, "src/models/", 11) == 0;
}

/* Scans the .c and .h files below root/rel; returns the number of offenders, each printed. */
static int scan_sources(const char *root, const char *rel, const lv_phase_type *const *types,
                        size_t *n_files)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", root, rel);
    DIR *d = opendir(path);
    if (d == NULL)
        return 0;
    int bad = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.')
            continue;
        char sub[1024], full[2048];
        snprintf(sub, sizeof sub, "%s/%s", rel, e->d_name);
        snprintf(full, sizeof full, "%s/%s", root, sub);
        struct stat st;
        if (stat(full, &st) != 0)
            continue;
        if (S_ISDIR(st.st_mode)) {
            bad += scan_sources(root, sub, types, n_files);
            continue;
        }
        const size_t n = strlen(sub);
        if (n < 2 || (strcmp(sub + n - 2, ".c") != 0 && strcmp(sub + n - 2, ".h") != 0) ||
            may_name_types(sub))
            continue;
        char *text = read_text(full);
        if (text == NULL)
            continue;
        (*n_files)++;
        const char *lit = names_type(text, types);
        if (lit != NULL) {
            fprintf(stderr, "%s: names the phase type %s: ask the registry (phase_type.h)\n",
                    sub, lit);
            bad++;
        }
        free(text);
    }
    closedir(d);
    return bad;
}

/* ---- the tests ------------------------------------------------------------------------------ */

static void test_registry(const lv_phase_type *const *types, const lv_model_def *const *defs)
{
    char why[512];
    size_t n = 0, kept = 0;
    for (int i = 0; types[i] != NULL; i++, n++) {
        const int bad = type_contract(types, defs, i, why, sizeof why);
        CHECK(!bad);
        if (bad)
            fprintf(stderr, "contract: %s\n", why);
        kept += !bad;
    }
    CHECK(n == lv_phase_types_count());
    printf("registry: %zu of %zu types keep the contract\n", kept, n);
}

/* A copy of types[i] broken by `breakit`: the contract names `want`. */
static void expect_broken(const lv_phase_type *const *types, const lv_model_def *const *defs,
                          int i, const lv_phase_type *broken, const char *want)
{
    const lv_phase_type *list[MAX_TYPES];
    int n = 0;
    for (; types[n] != NULL; n++)
        list[n] = n == i ? broken : types[n];
    list[n] = NULL;
    char why[512] = "";
    const int bad = type_contract(list, defs, i, why, sizeof why);
    CHECK(bad && strstr(why, want) != NULL);
    if (!bad || strstr(why, want) == NULL)
        fprintf(stderr, "broken type: expected '%s', got '%s'\n", want, bad ? why : "(kept)");
    else
        printf("broken on purpose: %s\n", why);
}

/* Whether types[i] converts from another type: a state of its model that a type of its
 * from_types has no final of. */
static int converts(const lv_phase_type *const *types, const lv_model_def *const *defs, int i)
{
    for (const char *const *f = types[i]->from_types; f != NULL && *f != NULL; f++) {
        const int j = find_type(types, *f);
        for (size_t s = 0; j >= 0 && s < defs[i]->n_states; s++)
            if (!has_var(defs[j], defs[i]->states[s].name, VALUE))
                return 1;
    }
    return 0;
}

static void test_broken(const lv_phase_type *const *types, const lv_model_def *const *defs)
{
    int planet = -1, flat = -1, handed = -1;
    for (int i = 0; types[i] != NULL; i++) {
        if (types[i]->world == LV_WORLD_PLANET && planet < 0)
            planet = i;
        if (types[i]->world == LV_WORLD_FLAT && flat < 0)
            flat = i;
        if (converts(types, defs, i) && handed < 0)
            handed = i;
    }
    CHECK(planet >= 0 && flat >= 0 && handed >= 0);
    if (planet < 0 || flat < 0 || handed < 0)
        return;
    /* a drag-free ballistic point over the planet whose merged trajectory forgot lat, lon, h:
     * the merge wrote 'nan' and the exports refused body_<stage>.csv */
    static const lv_traj_col eci_only[] = {
        {"r_eci_x", "m", "r_eci_x"}, {"r_eci_y", "m", "r_eci_y"}, {"r_eci_z", "m", "r_eci_z"},
        {"v_eci_x", "m/s", "v_eci_x"}, {"v_eci_y", "m/s", "v_eci_y"},
        {"v_eci_z", "m/s", "v_eci_z"}, {"body_mass", "kg", "m"}};
    lv_phase_type t = *types[planet];
    t.traj = eci_only;
    t.n_traj = sizeof eci_only / sizeof eci_only[0];
    expect_broken(types, defs, planet, &t, "has no column 'lat'");
    /* a column copied from a variable its model does not have */
    static const lv_traj_col typo[] = {
        {"r_eci_x", "m", "r_eci_x"}, {"r_eci_y", "m", "r_eci_y"}, {"r_eci_z", "m", "r_eci_z"},
        {"v_eci_x", "m/s", "v_eci_x"}, {"v_eci_y", "m/s", "v_eci_y"},
        {"v_eci_z", "m/s", "v_eci_z"}, {"body_mass", "kg", "m"},     {"lat", "rad", "latitude"},
        {"lon", "rad", "lon"},         {"h", "m", "h"}};
    t = *types[planet];
    t.traj = typo;
    t.n_traj = sizeof typo / sizeof typo[0];
    expect_broken(types, defs, planet, &t, "copies 'latitude', not a state or output");
    /* a flat-world type that computes lat, lon, h without a function to compute them */
    t = *types[flat];
    t.traj_extra = NULL;
    expect_broken(types, defs, flat, &t, "has no traj_extra");
    /* a mass state that is not a state */
    t = *types[planet];
    t.mass_state = "mass";
    expect_broken(types, defs, planet, &t, "mass state 'mass' is not a state");
    /* from_types naming a type that does not exist */
    static const char *const from_unknown[] = {"dof4", NULL};
    t = *types[handed];
    t.from_types = from_unknown;
    expect_broken(types, defs, handed, &t, "from_types names 'dof4', not a registered type");
    /* a conversion without the function that converts */
    t = *types[handed];
    t.handoff = NULL;
    expect_broken(types, defs, handed, &t, "needs a handoff");
    /* a mission parameter its model does not have */
    static const lv_var odd[] = {{"start_odd", "m", "not a parameter of the model", 0, 0}};
    t = *types[planet];
    t.mission_params = odd;
    t.n_mission_params = 1;
    t.mission_param_ranges = NULL;
    t.root_only_params = NULL;
    expect_broken(types, defs, planet, &t, "mission parameter 'start_odd' is not a parameter");
}

static void test_sources(const lv_phase_type *const *types)
{
    const char *root = getenv("LV_SOURCE_DIR");
    CHECK(root != NULL);
    if (root == NULL)
        return;
    size_t n = 0;
    const int bad = scan_sources(root, "src", types, &n) + scan_sources(root, "cli", types, &n);
    CHECK(bad == 0);
    CHECK(n > 100); /* the scan read the tree */
    printf("sources: %zu files outside the types and models name no type\n", n);
    /* the scan finds a name in code, not in comments or inside other literals */
    CHECK(names_type("x = strcmp(t->name, \"runway\");", types) != NULL);
    CHECK(names_type("/* a \"runway\" phase */ x = 1; // \"dof3\"\n", types) == NULL);
    CHECK(names_type("s = \"a dof3 phase\";", types) == NULL);
    CHECK(may_name_types("src/mission/phase_dof3.c") && !may_name_types("src/mission/run.c"));
}

int main(void)
{
    const lv_phase_type *const *types = lv_phase_types();
    const lv_model_def *defs[MAX_TYPES] = {0};
    lv_phase_sample *samples[MAX_TYPES] = {0};
    lv_err err = {LV_OK, ""};
    int n = 0, ok = 1;
    for (; types[n] != NULL && n < MAX_TYPES; n++) {
        /* the model a phase of the type builds, from its sample mission (lvsim vars <type>) */
        lv_status st = lv_phase_types_sample(types[n]->name, &samples[n], &err);
        CHECK_OK(st, &err);
        ok &= st == LV_OK;
        defs[n] = st == LV_OK ? lv_phase_types_sample_model(samples[n]) : NULL;
    }
    if (ok) {
        test_registry(types, defs);
        test_broken(types, defs);
    }
    test_sources(types);
    for (int i = 0; i < n; i++)
        lv_phase_types_sample_free(samples[i]);
    return check_report("test_phase_types");
}
