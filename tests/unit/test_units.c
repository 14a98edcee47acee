/* test_units.c - one convention for units (issue 27): every variable of every model (the
 * built-in models, each phase type's sample model, and the model of every phase of every
 * example mission, steering laws and controllers included), every number key of every law and
 * every run parameter of every example has an SI unit string, and a dimensionless one is "1"
 * (lv_units.h), never "" or "-". Reference: the quantities below are dimensionless by their
 * definition (a ratio of like quantities: Mach number v/a, load factor f/g0, eccentricity,
 * throttle fraction, quaternion components, a friction coefficient, on/off flags), so their
 * unit must be "1" (SI Brochure, 9th ed., 2019, sec. 2.3.3: "the unit one, symbol 1"; Modelica
 * Language Specification 3.6, sec. 19.1: unit = "1"). The CLI's and the files' renderings of
 * the same strings are checked by tests/cli/check_units.sh. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "lvsim/lvsim.h"

/* Dimensionless by definition (see the top). */
static const char *const dimensionless[] = {
    "mach", "n_axial", "n_normal", "n_lateral", "ecc", "throttle", "throttle_in", "engine_on",
    "q_w", "q_x", "q_y", "q_z", "quat_norm", "lift_margin", "rotating", "burning", "e",
    "stop_at_apogee", NULL};

static size_t n_vars, n_one;

/* An SI unit string as lvsim writes them, in the Modelica unit grammar (MLS 3.6 sec. 19.1,
 * which .mat readers and FMI importers parse): "1", "m", "m/s2", "kg/m3", "rad.s", "1/rad",
 * "m2", "m3/s2" - an exponent follows its symbol directly, never after '^'. */
static int unit_ok(const char *u)
{
    if (u == NULL || u[0] == '\0' || strcmp(u, "-") == 0)
        return 0;
    for (const char *c = u; *c; c++)
        if (!((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') ||
              *c == '/' || *c == '.' || *c == '-'))
            return 0;
    return 1;
}

static void check_var(const char *model, const char *kind, const lv_var *v)
{
    n_vars++;
    const int ok = unit_ok(v->unit);
    if (!ok)
        printf("%s: %s '%s' has unit '%s' (SI, dimensionless \"1\")\n", model, kind, v->name,
               v->unit ? v->unit : "(null)");
    CHECK(ok);
    for (size_t i = 0; dimensionless[i] != NULL; i++)
        if (strcmp(v->name, dimensionless[i]) == 0) {
            const int one = v->unit != NULL && strcmp(v->unit, "1") == 0;
            if (!one)
                printf("%s: %s '%s' is dimensionless: unit '%s', not \"1\"\n", model, kind,
                       v->name, v->unit ? v->unit : "(null)");
            CHECK(one);
            n_one += one;
        }
}

static void check_model(const char *where, const lv_model_def *d)
{
    char model[512];
    snprintf(model, sizeof model, "%s (model %s)", where, d->name);
    for (size_t i = 0; i < d->n_states; i++)
        check_var(model, "state", &d->states[i]);
    for (size_t i = 0; i < d->n_params; i++)
        check_var(model, "parameter", &d->params[i]);
    for (size_t i = 0; i < d->n_outputs; i++)
        check_var(model, "output", &d->outputs[i]);
}

/* Every phase of an example: run it (no files), then build each phase's model again. */
static void check_example(const char *dir, const char *name)
{
    char path[1400];
    snprintf(path, sizeof path, "%.1024s/%.255s/mission.yaml", dir, name);
    lv_mission *m = NULL;
    lv_run *r = NULL;
    lv_err err;
    if (lv_mission_load(path, &m, &err) != LV_OK) {
        printf("%s: %s\n", path, err.msg);
        CHECK(0);
        return;
    }
    for (size_t i = 0; i < lv_mission_param_count(m); i++) {
        lv_param_info p;
        lv_mission_param_info(m, i, &p);
        n_vars++;
        const int ok = unit_ok(p.unit);
        if (!ok)
            printf("%s: run parameter '%s' has unit '%s'\n", path, p.name, p.unit);
        CHECK(ok);
    }
    CHECK_OK(lv_run_create(m, &r, &err), &err);
    lv_run_options o = {0};
    o.no_rows = 1;
    o.threads = 1;
    if (r != NULL && lv_run_execute(r, &o, &err) == LV_OK) {
        for (size_t k = 0; k < lv_mission_phase_count(m); k++) {
            lv_phase_call *c = NULL;
            if (lv_run_prepare(r, k, &c, &err) != LV_OK) {
                printf("%s: phase %zu: %s\n", path, k, err.msg);
                CHECK(0);
                continue;
            }
            char where[600];
            snprintf(where, sizeof where, "%s, phase '%s'", name, lv_mission_phase_name(m, k));
            check_model(where, lv_phase_call_model(c));
            lv_phase_call_free(c);
        }
    } else {
        printf("%s: %s\n", path, err.msg);
        CHECK(0);
    }
    lv_run_free(r);
    lv_mission_free(m);
}

int main(void)
{
    lv_err err;
    /* the built-in models */
    for (const lv_model_def *const *d = lv_models_all(); *d != NULL; d++)
        check_model("built-in", *d);
    /* each phase type's sample model (lvsim vars TYPE) and what a root takes from parameters: */
    for (size_t i = 0; i < lv_phase_types_count(); i++) {
        lv_phase_type_info ti;
        CHECK_OK(lv_phase_types_get(i, &ti, &err), &err);
        for (size_t j = 0; j < ti.n_mission_params; j++)
            check_var(ti.name, "mission parameter", &ti.mission_params[j]);
        lv_phase_sample *s = NULL;
        CHECK_OK(lv_phase_types_sample(ti.name, &s, &err), &err);
        if (s != NULL)
            check_model(ti.name, lv_phase_types_sample_model(s));
        lv_phase_types_sample_free(s);
    }
    /* every number key of every law (and the kinds' common keys) */
    size_t n_keys = 0;
    for (size_t i = 0; i < lv_laws_count(); i++) {
        lv_law_info li;
        CHECK_OK(lv_laws_get(i, &li, &err), &err);
        for (size_t j = 0; j < li.n_keys; j++) {
            const lv_law_key *k = &li.keys[j];
            if (k->type != LV_KEY_NUMBER) {
                CHECK(k->unit != NULL && k->unit[0] == '\0'); /* no unit applies */
                continue;
            }
            n_keys++;
            const int ok = unit_ok(k->unit);
            if (!ok)
                printf("law '%s': key '%s' has unit '%s'\n", li.name, k->name, k->unit);
            CHECK(ok);
        }
    }
    /* every example mission: its run parameters and the models of its phases */
    const char *root = getenv("LV_SOURCE_DIR");
    char dir[1024];
    snprintf(dir, sizeof dir, "%.1000s/examples", root ? root : "..");
    DIR *dp = opendir(dir);
    CHECK(dp != NULL);
    size_t n_ex = 0;
    for (struct dirent *e; dp != NULL && (e = readdir(dp)) != NULL;) {
        char p[1400];
        snprintf(p, sizeof p, "%.1024s/%.255s/mission.yaml", dir, e->d_name);
        FILE *f = e->d_name[0] != '.' ? fopen(p, "r") : NULL;
        if (f == NULL)
            continue;
        fclose(f);
        check_example(dir, e->d_name);
        n_ex++;
    }
    if (dp != NULL)
        closedir(dp);
    CHECK(n_ex >= 9);
    CHECK(n_one >= 20); /* the dimensionless quantities were met, in several models */
    CHECK(n_keys >= 20);
    printf("units: %zu variables and run parameters of %zu examples, the built-in models and the "
           "types, %zu law keys; %zu dimensionless by definition, all \"1\"\n",
           n_vars, n_ex, n_keys, n_one);
    return check_report("test_units");
}
