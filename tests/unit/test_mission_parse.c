/* test_mission_parse.c - the mission-file parser: a good mission with a branch parses to the
 * expected structure (SI, degrees converted, parents before children, tables loaded from
 * CSV and .mat relative to the file); every class of bad input gives LV_ERR_INPUT at the
 * exact line and column. Files: tests/missions (LV_MISSION_DIR). */
#define _POSIX_C_SOURCE 200809L /* ftruncate, fileno */

#include <matio.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "lvsim/lv_table.h"
#include "mission/mission.h"
#include "mission/phase_type.h"

#define DEG (M_PI / 180.0)

/* Expect LV_ERR_INPUT with a message that starts with `want` ("bad.yaml:3:5: ..."). */
#define BAD(yaml, want) bad_((yaml), (want), __LINE__)
static void bad_(const char *yaml, const char *want, int line)
{
    lv_err err = { LV_OK, "" };
    lv_mission_def *m = NULL;
    lv_status st = lv_mission_def_parse(yaml, strlen(yaml), "bad.yaml", LV_MISSION_DIR, &m, &err);
    check_count_++;
    if (st != LV_ERR_INPUT || m != NULL || strncmp(err.msg, want, strlen(want)) != 0) {
        check_failures_++;
        fprintf(stderr, "%s:%d: expected LV_ERR_INPUT \"%s...\",\n    got %d \"%s\"\n", __FILE__,
                line, want, (int)st, err.msg);
    }
    lv_mission_def_free(m);
}

/* The same for a file under tests/missions. */
#define BAD_FILE(file, want) bad_file_((file), (want), __LINE__)
static void bad_file_(const char *file, const char *want, int line)
{
    char path[512], full[1024];
    snprintf(path, sizeof path, "%s/%s", LV_MISSION_DIR, file);
    snprintf(full, sizeof full, "%s/%s", LV_MISSION_DIR, want);
    lv_err err = { LV_OK, "" };
    lv_mission_def *m = NULL;
    lv_status st = lv_mission_def_load(path, &m, &err);
    check_count_++;
    if (st != LV_ERR_INPUT || m != NULL || strncmp(err.msg, full, strlen(full)) != 0) {
        check_failures_++;
        fprintf(stderr, "%s:%d: expected LV_ERR_INPUT \"%s...\",\n    got %d \"%s\"\n", __FILE__,
                line, full, (int)st, err.msg);
    }
    lv_mission_def_free(m);
}

/* The file's value of a slot; 0 for a key the file does not give (LV_NO_SLOT). */
static double slot_value(const lv_mission_def *m, lv_slot s)
{
    return s == LV_NO_SLOT ? 0.0 : lv_mission_def_value(m, s);
}
#define V(slot) slot_value(m, (slot))

static const lv_phase_def *phase(const lv_mission_def *m, const char *name)
{
    for (size_t i = 0; i < m->n_phases; i++)
        if (strcmp(m->phases[i].name, name) == 0)
            return &m->phases[i];
    return NULL;
}

static int ends_with(const char *s, const char *tail)
{
    size_t n = strlen(s), k = strlen(tail);
    return n >= k && strcmp(s + n - k, tail) == 0;
}

static void test_paper_branch(void)
{
    lv_err err = { LV_OK, "" };
    lv_mission_def *m = NULL;
    CHECK_OK(lv_mission_def_load(LV_MISSION_DIR "/paper_branch.yaml", &m, &err), &err);
    if (m == NULL)
        return;
    CHECK(strcmp(m->name, "paper-test-case") == 0);
    CHECK(m->description != NULL && strncmp(m->description, "vertical ascent", 15) == 0);
    CHECK(strcmp(m->dir, LV_MISSION_DIR) == 0);
    CHECK(m->env.world == LV_WORLD_FLAT);
    CHECK_CLOSE(V(m->env.g), 9.81, 0.0);
    CHECK(m->env.planet == NULL && m->env.gravity == NULL);
    CHECK(strcmp(m->env.atmosphere, "none") == 0);

    /* parameters: *_deg converted to rad and stored without the suffix */
    CHECK(m->n_params == 4);
    CHECK_CLOSE(lv_mission_def_param(m, "start_lat", -1.0), 5.236 * DEG, 1e-15);
    CHECK_CLOSE(lv_mission_def_param(m, "start_theta", -1.0), M_PI / 2, 1e-15);
    CHECK_CLOSE(lv_mission_def_param(m, "start_h", -1.0), 0.0, 0.0);
    CHECK_CLOSE(lv_mission_def_param(m, "start_lat_deg", -1.0), -1.0, 0.0);
    CHECK_CLOSE(lv_mission_def_param(m, "start_lon", 7.0), 7.0, 0.0);

    /* stages and engines */
    CHECK(m->n_stages == 3);
    const lv_stage_def *s1 = &m->stages[0], *s2 = &m->stages[1], *s3 = &m->stages[2];
    CHECK(strcmp(s1->name, "stage1") == 0 && strcmp(s3->name, "stage3") == 0);
    CHECK_CLOSE(V(s1->dry_mass), 1500.0, 0.0);
    CHECK_CLOSE(V(s1->propellant_mass), 8500.0, 0.0);
    CHECK(s1->loc.line == 19 && s1->loc.column == 5);
    CHECK(s1->n_engines == 1 && s2->n_engines == 1 && s3->n_engines == 1);

    const lv_engine_def *e1 = &s1->engines[0];
    CHECK(strcmp(e1->name, "s1e") == 0);
    CHECK(e1->table != NULL && e1->table_var == NULL);
    CHECK(strcmp(e1->table_file, LV_MISSION_DIR "/data/stage1.csv") == 0);
    CHECK(e1->count == 1 && V(e1->exit_area) == 0.0);
    if (e1->table != NULL) {
        double y[2];
        CHECK_OK(lv_table_eval1(e1->table, NULL, 50.0, y, &err), &err);
        CHECK_CLOSE(y[e1->thrust_out], 2.5e5, 1e-9);
        CHECK_CLOSE(y[e1->mdot_out], 85.0, 1e-12);
        /* engine tables hold their end values outside the time range by default */
        CHECK_OK(lv_table_eval1(e1->table, NULL, 500.0, y, &err), &err);
        CHECK_CLOSE(y[e1->thrust_out], 0.0, 0.0);
        CHECK(lv_table_interp(e1->table) == LV_INTERP_LINEAR);
    }
    const lv_engine_def *e2 = &s2->engines[0];
    CHECK(strcmp(e2->name, "stage2.e1") == 0); /* default name */
    CHECK(e2->table != NULL && e2->table_var != NULL && strcmp(e2->table_var, "stage2") == 0);
    CHECK(ends_with(e2->table_file, "/tests/missions/data/stage2.mat"));
    if (e2->table != NULL) { /* .mat matrix [t, thrust, mdot]: outputs col2, col3 */
        double y[2];
        CHECK(e2->thrust_out == 0 && e2->mdot_out == 1);
        CHECK_OK(lv_table_eval1(e2->table, NULL, 150.0, y, &err), &err);
        CHECK_CLOSE(y[e2->thrust_out], 8.0e4, 1e-9);
        CHECK_CLOSE(y[e2->mdot_out], 27.0, 1e-12);
        CHECK(lv_table_interp(e2->table) == LV_INTERP_PCHIP);
    }
    const lv_engine_def *e3 = &s3->engines[0];
    CHECK(e3->table == NULL && e3->table_file == NULL);
    CHECK_CLOSE(V(e3->thrust_vac), 3.0e4, 0.0);
    CHECK_CLOSE(V(e3->isp_vac), 310.0, 0.0);
    CHECK_CLOSE(V(e3->mdot), 0.0, 0.0);
    CHECK_CLOSE(V(e3->exit_area), 0.1, 0.0);
    CHECK(e3->count == 2);

    /* phases: file order P4 P1 P2 P3 P5; parents first, file order otherwise */
    static const char *const order[] = { "P1", "P2", "P4", "P3", "P5" };
    static const int parent[] = { -1, 0, 1, 1, 0 };
    CHECK(m->n_phases == 5);
    for (size_t i = 0; i < 5 && i < m->n_phases; i++) {
        CHECK(strcmp(m->phases[i].name, order[i]) == 0);
        CHECK(m->phases[i].parent == parent[i]);
        CHECK(strcmp(m->phases[i].type->name, "flat6") == 0);
    }
    const lv_phase_def *p1 = phase(m, "P1"), *p2 = phase(m, "P2"), *p3 = phase(m, "P3");
    const lv_phase_def *p4 = phase(m, "P4"), *p5 = phase(m, "P5");
    if (p1 == NULL || p2 == NULL || p3 == NULL || p4 == NULL || p5 == NULL) {
        CHECK(0);
        lv_mission_def_free(m);
        return;
    }
    CHECK(p1->loc.line == 46 && p1->loc.column == 5);
    CHECK(p1->n_stages == 3 && p1->stages[0] == 0 && p1->stages[1] == 1 && p1->stages[2] == 2);
    CHECK(p2->n_stages == 2 && p2->stages[0] == 1 && p2->stages[1] == 2);
    CHECK_CLOSE(V(p1->t_start), 0.0, 0.0);
    CHECK_CLOSE(V(p1->t_stop), 150.0, 0.0);
    CHECK(p2->t_start == LV_NO_SLOT);
    CHECK_CLOSE(V(p2->t_stop), 400.0, 0.0);
    CHECK(p1->n_ends == 2);
    if (p1->n_ends == 2) {
        CHECK(p1->ends[0].kind == LV_END_BURNOUT && p1->ends[0].direction == LV_DIR_FALLING);
        CHECK(p1->ends[1].kind == LV_END_ALTITUDE && p1->ends[1].direction == LV_DIR_RISING);
        CHECK_CLOSE(V(p1->ends[1].value), 1e5, 0.0);
        CHECK(p1->ends[1].loc.line == 51 && p1->ends[1].loc.column == 20);
    }
    CHECK(strcmp(p1->method, "dassl") == 0);
    CHECK_CLOSE(V(p1->tolerance), 1e-8, 0.0);
    CHECK_CLOSE(V(p1->output_interval), 0.5, 0.0);
    CHECK(p1->intervals == 0); /* output_interval given: no default interval count */
    CHECK(strcmp(p2->method, "auto") == 0 && p2->intervals == 500);
    CHECK_CLOSE(V(p2->tolerance), 1e-9, 0.0); /* the default (docs/integration.md) */
    CHECK(p2->n_set == 2);
    if (p2->n_set == 2) {
        CHECK(strcmp(p2->set_names[0], "stage1.m") == 0);
        CHECK_CLOSE(V(p2->set_values[0]), 0.0, 0.0);
        CHECK(strcmp(p2->set_names[1], "theta") == 0);
        CHECK_CLOSE(V(p2->set_values[1]), 89.5 * DEG, 1e-15);
        CHECK(p2->set_locs[1].line == 59 && p2->set_locs[1].column == 24);
    }
    CHECK(strcmp(p3->method, "rk4") == 0 && p3->intervals == 1000);
    CHECK_CLOSE(V(p3->fixed_step), 0.01, 0.0);
    CHECK(p3->n_ends == 2);
    if (p3->n_ends == 2) {
        CHECK(p3->ends[0].kind == LV_END_APOGEE && p3->ends[0].direction == LV_DIR_FALLING);
        CHECK(p3->ends[1].kind == LV_END_SPEED && p3->ends[1].direction == LV_DIR_FALLING);
        CHECK_CLOSE(V(p3->ends[1].value), 2000.0, 0.0);
    }
    CHECK(p4->n_ends == 1 && p4->ends[0].kind == LV_END_IMPACT && V(p4->ends[0].value) == 0.0);
    CHECK(p5->n_ends == 1 && p5->ends[0].kind == LV_END_IMPACT);
    if (p5->n_ends == 1) {
        CHECK_CLOSE(V(p5->ends[0].value), 50.0, 0.0);
        CHECK(p5->ends[0].direction == LV_DIR_FALLING);
    }
    lv_mission_def_free(m);
}

static void test_planet_and_defaults(void)
{
    lv_err err = { LV_OK, "" };
    lv_mission_def *m = NULL;
    CHECK_OK(lv_mission_def_load(LV_MISSION_DIR "/planet_dof3.yaml", &m, &err), &err);
    if (m != NULL) {
        CHECK(m->env.world == LV_WORLD_PLANET);
        CHECK(strcmp(m->env.planet, "earth") == 0 && strcmp(m->env.gravity, "j2") == 0);
        CHECK(strcmp(m->env.atmosphere, "us76") == 0);
        CHECK(m->description == NULL);
        CHECK_CLOSE(lv_mission_def_param(m, "start_lon", 0.0), -52.775 * DEG, 1e-15);
        CHECK_CLOSE(V(m->stages[0].engines[0].mdot), 850.0, 0.0);
        CHECK_CLOSE(V(m->stages[0].engines[0].isp_vac), 0.0, 0.0);
        CHECK_CLOSE(V(m->stages[1].engines[0].isp_vac), 340.0, 0.0);
        CHECK(strcmp(m->stages[1].engines[0].name, "upper.e1") == 0);
        CHECK(m->n_phases == 2 && m->phases[1].parent == 0);
        CHECK(strcmp(m->phases[1].type->name, "dof3") == 0);
        CHECK(strcmp(m->phases[1].method, "cvode-adams") == 0);
        CHECK(m->phases[1].ends[1].direction == LV_DIR_BOTH);
        CHECK(m->phases[1].n_ends == 3 && m->phases[1].ends[2].kind == LV_END_IMPACT);
        CHECK(m->phases[1].intervals == 500);
    }
    lv_mission_def_free(m);

    m = NULL;
    CHECK_OK(lv_mission_def_load(LV_MISSION_DIR "/minimal.yaml", &m, &err), &err);
    if (m != NULL) {
        CHECK(m->env.world == LV_WORLD_FLAT && V(m->env.g) == 9.81);
        CHECK(strcmp(m->env.atmosphere, "none") == 0);
        CHECK(m->n_params == 0 && m->n_stages == 1 && m->n_phases == 1);
        CHECK(m->stages[0].n_engines == 0 && m->stages[0].engines == NULL);
        const lv_phase_def *p = &m->phases[0];
        CHECK(p->parent == -1 && p->t_start == LV_NO_SLOT && V(p->t_stop) == 10.0);
        CHECK(p->n_ends == 0 && p->n_set == 0);
        CHECK(strcmp(p->method, "auto") == 0 && V(p->tolerance) == 1e-9 && p->intervals == 500);
        CHECK(V(p->output_interval) == 0.0 && V(p->fixed_step) == 0.0);
    }
    lv_mission_def_free(m);

    /* other planets: no atmosphere unless asked; world flat, planet-only keys absent */
    const char *moon = "mission: {name: m}\n"
                       "environment: {world: planet, planet: moon, gravity: zonal}\n"
                       "stages: [{name: s, dry_mass: 1, propellant_mass: 0}]\n"
                       "phases: [{name: p, model: dof3, stages: [s], stop_time: 1}]\n";
    m = NULL;
    CHECK_OK(lv_mission_def_parse(moon, strlen(moon), "moon.yaml", NULL, &m, &err), &err);
    if (m != NULL) {
        CHECK(strcmp(m->env.planet, "moon") == 0 && strcmp(m->env.gravity, "zonal") == 0);
        CHECK(strcmp(m->env.atmosphere, "none") == 0);
        CHECK(strcmp(m->dir, ".") == 0 && strcmp(m->path, "moon.yaml") == 0);
    }
    lv_mission_def_free(m);
    lv_mission_def_free(NULL);
    CHECK(lv_mission_def_param(NULL, "start_h", 3.0) == 3.0);
    m = NULL;
    CHECK_FAILS(lv_mission_def_load(LV_MISSION_DIR "/no_such.yaml", &m, &err), &err, LV_ERR_IO,
                "no_such.yaml: cannot open the mission file: No such file or directory");
    CHECK(m == NULL);
}

/* A file of `size` bytes that holds nothing (sparse: no disk space, no time to make). */
static int sparse_file(const char *path, off_t size)
{
    FILE *f = fopen(path, "w");
    if (f == NULL)
        return 0;
    const int ok = ftruncate(fileno(f), size) == 0;
    fclose(f);
    return ok;
}

/* What is read whole is refused beyond its size before anything is allocated (issue 22's
 * breaker: a sparse 3 GB table took 54 s and 3.1 GB of memory before its error, a 2 GB mission
 * 30 s and 2.1 GB): a mission file beyond 16 MiB, a CSV or MAT table beyond 1 GiB. */
static void test_file_sizes(void)
{
    lv_mission_def *m = NULL;
    lv_err err;
    const char *big = "big_mission.yaml";
    CHECK(sparse_file(big, (off_t)(16 << 20) + 1));
    CHECK_FAILS(lv_mission_def_load(big, &m, &err), &err, LV_ERR_INPUT,
                "big_mission.yaml: 16.8 MB; at most 16.8 MB are read (the mission file)");
    CHECK(m == NULL);
    CHECK(sparse_file(big, (off_t)(16 << 20))); /* exactly the limit: read (and refused as YAML) */
    CHECK_FAILS(lv_mission_def_load(big, &m, &err), &err, LV_ERR_INPUT, "big_mission.yaml:");
    CHECK(strstr(err.msg, "at most") == NULL);
    remove(big);
    lv_table *t = NULL;
    CHECK(sparse_file("big_table.csv", ((off_t)1 << 30) + 1));
    CHECK_FAILS(lv_table_load_csv("big_table.csv", NULL, &t, &err), &err, LV_ERR_INPUT,
                "big_table.csv: 1.07 GB; at most 1.07 GB are read (a table file)");
    remove("big_table.csv");
    CHECK(sparse_file("big_table.mat", ((off_t)3 << 30)));
    CHECK_FAILS(lv_table_load_mat("big_table.mat", "x", NULL, &t, &err), &err, LV_ERR_INPUT,
                "big_table.mat: 3.22 GB; at most 1.07 GB are read (a table file)");
    remove("big_table.mat");
    CHECK(t == NULL);
}

/* A .mat table written here with libmatio, relative to the directory given to parse(). */
static void test_mat_generated(void)
{
    static const double tab[] = { 0.0, 10.0, 20.0,     /* t, column-major [3 x 3] */
                                  1e5, 1e5,  0.0,      /* thrust */
                                  30.0, 30.0, 0.0 };   /* mdot */
    size_t dims[2] = { 3, 3 };
    mat_t *mat = Mat_CreateVer("gen_engine.mat", NULL, MAT_FT_MAT5);
    CHECK(mat != NULL);
    if (mat == NULL)
        return;
    matvar_t *mv = Mat_VarCreate("gen_engine", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims,
                                 (void *)tab, MAT_F_DONT_COPY_DATA);
    CHECK(mv != NULL && Mat_VarWrite(mat, mv, MAT_COMPRESSION_NONE) == 0);
    Mat_VarFree(mv);
    Mat_Close(mat);

    const char *yaml = "mission: {name: gen}\n"
                       "stages:\n"
                       "  - name: s\n"
                       "    dry_mass: 10\n"
                       "    propellant_mass: 20\n"
                       "    engines: [{table: gen_engine.mat, count: 3}]\n"
                       "phases: [{name: p, model: flat6, stages: [s], stop_time: 5}]\n";
    lv_err err = { LV_OK, "" };
    lv_mission_def *m = NULL;
    CHECK_OK(lv_mission_def_parse(yaml, strlen(yaml), "gen.yaml", ".", &m, &err), &err);
    if (m != NULL) {
        const lv_engine_def *e = &m->stages[0].engines[0];
        double y[2];
        CHECK(strcmp(e->table_file, "./gen_engine.mat") == 0);
        CHECK(strcmp(e->table_var, "gen_engine") == 0); /* the file stem by default */
        CHECK(e->count == 3);
        CHECK_OK(lv_table_eval1(e->table, NULL, 15.0, y, &err), &err);
        CHECK_CLOSE(y[e->thrust_out], 5e4, 1e-9);
        CHECK_CLOSE(y[e->mdot_out], 15.0, 1e-12);
    }
    lv_mission_def_free(m);
    /* a missing variable: the loader's suggestion, prefixed with the mission position */
    const char *yaml2 = "mission: {name: gen}\n"
                        "stages:\n"
                        "  - name: s\n"
                        "    dry_mass: 10\n"
                        "    propellant_mass: 20\n"
                        "    engines: [{table: {file: gen_engine.mat, var: gen_engin}}]\n"
                        "phases: [{name: p, model: flat6, stages: [s], stop_time: 5}]\n";
    err.msg[0] = '\0';
    m = NULL;
    lv_status st = lv_mission_def_parse(yaml2, strlen(yaml2), "gen.yaml", ".", &m, &err);
    CHECK(st == LV_ERR_INPUT && m == NULL);
    CHECK(strncmp(err.msg, "gen.yaml:6:16: stage 's', engine #1: table: ./gen_engine.mat", 60)
          == 0);
    CHECK(strstr(err.msg, "did you mean 'gen_engine'") != NULL);
    lv_mission_def_free(m);
    remove("gen_engine.mat");
}

#define HEAD "mission: {name: t}\n"                                        /* line 1 */
#define STAGES "stages:\n  - {name: s1, dry_mass: 1, propellant_mass: 1}\n" /* lines 2-3 */
#define PHASE "phases:\n  - {name: P1, model: flat6, stages: [s1], stop_time: 1}\n"

static void test_syntax(void)
{
    BAD("mission: {name: t\nstages: []\n",
        "bad.yaml:2:7: YAML syntax error: did not find expected ',' or '}' (while parsing a flow "
        "mapping at line 1, column 10)");
    BAD("mission:\n  name: t\n bad: 1\n", "bad.yaml:3:2: YAML syntax error: did not find "
        "expected key (while parsing a block mapping at line 1, column 1)");
    BAD("a: b: c\n", "bad.yaml:1:5: YAML syntax error: mapping values are not allowed");
    BAD("mission: \"\\q\"\n", "bad.yaml:1:11: YAML syntax error: found unknown escape character (while parsing a quoted "
        "scalar at line 1, column 10)");
    BAD("mission: \xff\xfe\n", "bad.yaml:1:10: invalid YAML input: invalid leading UTF-8 octet (byte 9)");
    BAD("", "bad.yaml:1:1: empty document");
    BAD("# nothing but a comment\n\n", "bad.yaml:1:1: empty document");
    BAD("---\n...\n", "bad.yaml:1:1: empty document");
    BAD("~\n", "bad.yaml:1:1: empty document");
    BAD(HEAD STAGES PHASE "---\nmission: {name: u}\n",
        "bad.yaml:6:1: a second YAML document; a mission file holds exactly one");
    BAD("- mission\n- stages\n", "bad.yaml:1:1: the top level must be a mapping with 'mission', "
        "'stages' and 'phases', found a list");
    BAD("mission: &m {name: t}\n", "bad.yaml:1:10: anchors (&m) and aliases are not supported");
    BAD("mission: {name: t}\nother: *m\n", "bad.yaml:2:8: aliases (*m) and anchors are not "
        "supported");
    BAD("mission: !!map {name: t}\n", "bad.yaml:1:10: tags (tag:yaml.org,2002:map) are not "
        "supported");
    BAD("? [a, b]\n: 1\n", "bad.yaml:1:3: a mapping key must be a plain name, not a list");
    char deep[400] = "mission: ";
    for (int i = 0; i < 70; i++)
        strcat(deep, "[");
    BAD(deep, "bad.yaml:1:73: nested deeper than 64 levels");
}

static void test_keys_and_types(void)
{
    BAD(HEAD STAGES PHASE "stagez: []\n",
        "bad.yaml:6:1: top level: unknown key 'stagez'; did you mean 'stages' or 'phases'?");
    BAD(HEAD "stages:\n  - {name: s1, dry_mass: 1, propellant_mas: 1}\n" PHASE,
        "bad.yaml:3:29: stage 's1': unknown key 'propellant_mas'; did you mean "
        "'propellant_mass'?");
    BAD(HEAD STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1], stop_time: 1, "
        "integrator: {metod: rk4}}\n",
        "bad.yaml:5:71: phase 'P1', integrator: unknown key 'metod'; did you mean 'method'?");
    BAD(HEAD STAGES PHASE "mission: {name: u}\n",
        "bad.yaml:6:1: top level: duplicate key 'mission' (first at line 1)");
    /* missing required fields: reported where the mapping starts */
    BAD(HEAD STAGES, "bad.yaml:1:1: top level: missing required key 'phases'");
    BAD("stages: []\n", "bad.yaml:1:1: top level: missing required key 'mission'");
    BAD("mission: {description: x}\n", "bad.yaml:1:10: mission: missing required key 'name'");
    BAD(HEAD "stages:\n  - name: s1\n    dry_mass: 1\n" PHASE,
        "bad.yaml:3:5: stage 's1': missing required key 'propellant_mass'");
    BAD(HEAD STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1]}\n",
        "bad.yaml:5:5: phase 'P1': missing required key 'stop_time'");
    BAD(HEAD STAGES "phases:\n  - name: P1\n    model:\n    stages: [s1]\n    stop_time: 1\n",
        "bad.yaml:6:11: phase 'P1': 'model' has no value");
    /* wrong types */
    BAD(HEAD "stages:\n  - {name: s1, dry_mass: heavy, propellant_mass: 1}\n" PHASE,
        "bad.yaml:3:26: stage 's1': dry_mass: number expected, found 'heavy'");
    BAD(HEAD "stages:\n  - {name: s1, dry_mass: \"5\", propellant_mass: 1}\n" PHASE,
        "bad.yaml:3:26: stage 's1': dry_mass: number expected, found the string \"5\"");
    BAD(HEAD "stages:\n  - {name: s1, dry_mass: [5], propellant_mass: 1}\n" PHASE,
        "bad.yaml:3:26: stage 's1': dry_mass: number expected, found a list");
    BAD(HEAD "stages: {name: s1}\n" PHASE,
        "bad.yaml:2:9: stages: a list of at least one stage expected, found a mapping");
    BAD(HEAD "stages: []\n" PHASE,
        "bad.yaml:2:9: stages: a list of at least one stage expected, found an empty list");
    BAD(HEAD STAGES "phases:\n  - {name: P1, model: flat6, stages: s1, stop_time: 1}\n",
        "bad.yaml:5:38: phase 'P1': stages: a list of stage names (bottom first) expected, "
        "found 's1'");
    BAD(HEAD STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1], stop_time: 1, end: "
        "burnout}\n", "bad.yaml:5:63: phase 'P1': end: a list of events expected");
    BAD(HEAD "stages:\n  - {name: s1, dry_mass: 1, propellant_mass: 1, engines: {a: 1}}\n" PHASE,
        "bad.yaml:3:58: stage 's1': engines: a list expected, found a mapping");
    BAD(HEAD "stages:\n  - [s1]\n" PHASE,
        "bad.yaml:3:5: stage #1: a mapping (key: value) expected, found a list");
    BAD(HEAD STAGES PHASE "parameters: [start_h]\n",
        "bad.yaml:6:13: parameters: a mapping (key: value) expected, found a list");
    BAD(HEAD STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1], stop_time: 1, "
        "integrator: {intervals: 2.5}}\n",
        "bad.yaml:5:82: phase 'P1', integrator: intervals: an integer >= 0 expected, found 2.5");
    /* non-finite numbers */
    BAD(HEAD "stages:\n  - {name: s1, dry_mass: .inf, propellant_mass: 1}\n" PHASE,
        "bad.yaml:3:26: stage 's1': dry_mass: non-finite number '.inf'");
    BAD(HEAD "stages:\n  - {name: s1, dry_mass: 1, propellant_mass: 1e999}\n" PHASE,
        "bad.yaml:3:46: stage 's1': propellant_mass: non-finite number '1e999'");
    BAD(HEAD "stages:\n  - {name: s1, dry_mass: nan, propellant_mass: 1}\n" PHASE,
        "bad.yaml:3:26: stage 's1': dry_mass: non-finite number 'nan'");
    BAD(HEAD STAGES PHASE "parameters: {start_h: -.Inf}\n",
        "bad.yaml:6:23: parameters: start_h: non-finite number '-.Inf'");
    /* names */
    BAD(HEAD "stages:\n  - {name: stage one, dry_mass: 1, propellant_mass: 1}\n" PHASE,
        "bad.yaml:3:12: stage 'stage one': name 'stage one' must be 1 to 64 letters, digits, '_' or '-'");
    /* an unknown model lists the registered types (lv_phase_types_get: no list kept here) */
    char want[512] = "bad.yaml:5:23: phase 'P1': model: unknown value 'flat9'; did you mean "
                     "'flat6'? (expected one of: ";
    for (size_t i = 0; i < lv_phase_types_count(); i++) {
        lv_phase_type_info ti;
        lv_err e = {LV_OK, ""};
        CHECK_OK(lv_phase_types_get(i, &ti, &e), &e);
        snprintf(want + strlen(want), sizeof want - strlen(want), "%s%s", i ? ", " : "",
                 ti.name);
    }
    snprintf(want + strlen(want), sizeof want - strlen(want), ")");
    BAD(HEAD STAGES "phases:\n  - {name: P1, model: flat9, stages: [s1], stop_time: 1}\n", want);
}

static void test_references(void)
{
    BAD(HEAD STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1, s2], stop_time: 1}\n",
        "bad.yaml:5:43: phase 'P1': stages: no stage named 's2'; did you mean 's1'?");
    BAD(HEAD STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1, s1], stop_time: 1}\n",
        "bad.yaml:5:43: phase 'P1': stages: 's1' listed twice");
    BAD(HEAD "stages:\n  - {name: s1, dry_mass: 1, propellant_mass: 1}\n"
        "  - {name: s1, dry_mass: 2, propellant_mass: 2}\n" PHASE,
        "bad.yaml:4:12: stage 's1': duplicate stage name (first at line 3)");
    BAD(HEAD STAGES PHASE "  - {name: P1, model: flat6, stages: [s1], stop_time: 2}\n",
        "bad.yaml:6:12: phase 'P1': duplicate phase name (first at line 5)");
    BAD(HEAD STAGES PHASE "  - {name: P2, model: flat6, stages: [s1], stop_time: 2, from: P0}\n",
        "bad.yaml:6:64: phase 'P2': from: no phase named 'P0'; did you mean 'P1' or 'P2'?");
    BAD(HEAD STAGES PHASE "  - {name: P2, model: flat6, stages: [s1], stop_time: 2, from: P2}\n",
        "bad.yaml:6:64: phase 'P2': from: a phase cannot start from itself");
    BAD(HEAD "stages:\n  - name: s1\n    dry_mass: 1\n    propellant_mass: 1\n"
        "    engines:\n      - {thrust_vac: 1, mdot: 1}\n      - {name: s1.e1, thrust_vac: 1, "
        "mdot: 1}\n" PHASE,
        "bad.yaml:8:16: stage 's1': duplicate engine name 's1.e1' (first at line 7)");
    BAD_FILE("bad_cycle.yaml",
             "bad_cycle.yaml:15:11: phase 'P2': from: cycle P2 -> P4 -> P3 -> P2 (each phase "
             "starts from the next)");
}

static void test_values(void)
{
    BAD(HEAD "stages:\n  - {name: s1, dry_mass: -1, propellant_mass: 1}\n" PHASE,
        "bad.yaml:3:26: stage 's1': dry_mass must be >= 0 kg, found -1");
    BAD(HEAD "stages:\n  - {name: s1, dry_mass: 1, propellant_mass: -0.5}\n" PHASE,
        "bad.yaml:3:46: stage 's1': propellant_mass must be >= 0 kg, found -0.5");
    BAD(HEAD STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1], start_time: 5, "
        "stop_time: 5}\n",
        "bad.yaml:5:70: phase 'P1': stop_time 5 s must be greater than the start time 5 s");
    BAD(HEAD STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1], stop_time: -1}\n",
        "bad.yaml:5:55: phase 'P1': stop_time -1 s must be greater than the start time 0 s");
    BAD(HEAD STAGES PHASE "environment: {g: 0}\n",
        "bad.yaml:6:18: environment: g must be > 0 m/s2, found 0");
    BAD(HEAD STAGES PHASE "environment: {world: planet, g: 3.7}\n",
        "bad.yaml:6:30: environment: 'g' applies to world: flat only");
    BAD(HEAD STAGES PHASE "environment: {gravity: j2}\n",
        "bad.yaml:6:15: environment: 'gravity' applies to world: planet only");
    BAD(HEAD STAGES PHASE "environment: {world: planet, planet: venus}\n",
        "bad.yaml:6:38: environment: planet: unknown value 'venus' (expected one of: earth, "
        "moon, mars)");
    BAD(HEAD STAGES PHASE "environment: {atmosphere: us67}\n",
        "bad.yaml:6:27: environment: atmosphere: unknown value 'us67'; did you mean 'us76'?");
    /* model/world mismatch */
    BAD(HEAD STAGES "phases:\n  - {name: P1, model: dof3, stages: [s1], stop_time: 1}\n",
        "bad.yaml:5:23: phase 'P1': model dof3 needs environment world: planet (this mission's "
        "world is flat)");
    BAD_FILE("bad_world.yaml", "bad_world.yaml:12:12: phase 'ascent': model flat6 needs "
             "environment world: flat (this mission's world is planet)");
    /* parameters */
    BAD(HEAD STAGES PHASE "parameters: {start_lattitude: 5}\n",
        "bad.yaml:6:14: parameters: unknown parameter 'start_lattitude'; did you mean "
        "'start_lat_deg', 'start_lat' or 'start_theta'?");
    BAD(HEAD STAGES PHASE "parameters: {start_h_deg: 5}\n",
        "bad.yaml:6:14: parameters: 'start_h_deg' is not an angle: write 'start_h' in SI units");
    BAD(HEAD STAGES PHASE "parameters: {start_lat_deg: 5, start_lat: 0.1}\n",
        "bad.yaml:6:32: parameters: 'start_lat' given twice (as 'start_lat_deg' at line 6)");
    BAD(HEAD STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1], stop_time: 1, set: "
        "{theta_deg: 1, theta: 2}}\n",
        "bad.yaml:5:78: phase 'P1', set: 'theta' set twice (line 5)");
    /* end events */
    BAD(HEAD STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1], stop_time: 1, end: "
        "[burnout, apogée]}\n",
        "bad.yaml:5:73: phase 'P1', end event #2: end: unknown value 'apogée'; did you mean "
        "'apogee'?");
    BAD(HEAD STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1], stop_time: 1, end: "
        "[altitude]}\n",
        "bad.yaml:5:64: phase 'P1', end event #1: 'altitude' needs a value: write {altitude: <m>}");
    BAD(HEAD STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1], stop_time: 1, end: "
        "[{impact: 0, direction: rising}]}\n",
        "bad.yaml:5:87: phase 'P1', end event #1: impact is always falling");
    BAD(HEAD STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1], stop_time: 1, end: "
        "[{altitude: 1, speed: 2}]}\n",
        "bad.yaml:5:78: phase 'P1', end event #1: one event per entry ('altitude' and 'speed')");
    BAD(HEAD STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1], stop_time: 1, end: "
        "[{altitude: 1, direction: up}]}\n",
        "bad.yaml:5:89: phase 'P1', end event #1: direction: unknown value 'up' (expected one "
        "of: rising, falling, both)");
    /* integrator */
    BAD(HEAD STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1], stop_time: 1, "
        "integrator: {method: dasl}}\n",
        "bad.yaml:5:79: phase 'P1', integrator: method: unknown value 'dasl'; did you mean "
        "'dassl' or 'dp5'?");
    BAD(HEAD STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1], stop_time: 1, "
        "integrator: {tolerance: 0}}\n",
        "bad.yaml:5:82: phase 'P1', integrator: tolerance must be >= 1e-14 and <= 0.1, found 0");
    BAD(HEAD STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1], stop_time: 1, "
        "integrator: {output_interval: 1, intervals: 10}}\n",
        "bad.yaml:5:91: phase 'P1', integrator: give either 'intervals' or 'output_interval'");
}

#define ENG(body) HEAD "stages:\n  - name: s1\n    dry_mass: 1\n    propellant_mass: 1\n" \
                       "    engines:\n      - " body "\n" PHASE                          /* l. 7 */

static void test_engines(void)
{
    BAD(ENG("{table: data/stage1.csv, thrust_vac: 1000}"),
        "bad.yaml:7:34: stage 's1', engine #1: give either 'table' or constant data "
        "(thrust_vac with isp_vac or mdot), not both");
    BAD(ENG("{name: e, count: 2}"),
        "bad.yaml:7:9: stage 's1', engine 'e': needs either 'table' or 'thrust_vac' with "
        "'isp_vac' or 'mdot'");
    BAD(ENG("{thrust_vac: 1000, isp_vac: 300, mdot: 2}"),
        "bad.yaml:7:42: stage 's1', engine #1: give exactly one of 'isp_vac' and 'mdot'");
    BAD(ENG("{thrust_vac: 1000}"),
        "bad.yaml:7:9: stage 's1', engine #1: a constant engine needs 'isp_vac' [s] or 'mdot'");
    BAD(ENG("{isp_vac: 300}"), "bad.yaml:7:9: stage 's1', engine #1: missing required key "
        "'thrust_vac'");
    BAD(ENG("{thrust_vac: 0, isp_vac: 300}"),
        "bad.yaml:7:22: stage 's1', engine #1: thrust_vac must be > 0 N, found 0");
    BAD(ENG("{thrust_vac: 1, isp_vac: 300, count: 0}"),
        "bad.yaml:7:46: stage 's1', engine #1: count: an integer >= 1 expected, found 0");
    BAD(ENG("{thrust_vac: 1, mdot: 1, exit_area: -1}"),
        "bad.yaml:7:45: stage 's1', engine #1: exit_area must be >= 0 m2, found -1");
    /* tables that do not load: the loader's message behind the mission's position */
    BAD(ENG("{name: e, table: data/bad_order.csv}"),
        "bad.yaml:7:19: stage 's1', engine 'e': table: " LV_MISSION_DIR "/data/bad_order.csv:5:");
    BAD(ENG("{name: e, table: data/missing.csv}"),
        "bad.yaml:7:26: stage 's1', engine 'e': table: cannot read '" LV_MISSION_DIR
        "/data/missing.csv': No such file or directory");
    BAD(ENG("{name: e, table: data}"),
        "bad.yaml:7:26: stage 's1', engine 'e': table: '" LV_MISSION_DIR "/data' is not a "
        "regular file");
    BAD(ENG("{name: e, table: data/no_mdot.csv}"),
        "bad.yaml:7:19: stage 's1', engine 'e': table '" LV_MISSION_DIR "/data/no_mdot.csv' "
        "needs outputs 'thrust' [N] and 'mdot' [kg/s] (a .mat matrix: columns t, thrust, "
        "mdot); it has 'thrust'");
    BAD(ENG("{name: e, table: {file: data/stage2.mat, var: stage3}}"),
        "bad.yaml:7:19: stage 's1', engine 'e': table: " LV_MISSION_DIR "/data/stage2.mat: no "
        "variable 'stage3'; did you mean 'stage2'?");
    BAD(ENG("{name: e, table: {file: data/stage1.csv, extrap: hold}}"),
        "bad.yaml:7:58: stage 's1', engine 'e': extrap: unknown value 'hold' (expected one of: "
        "clamp, error, linear)");
    BAD(ENG("{name: e, table: {var: x}}"),
        "bad.yaml:7:26: stage 's1', engine 'e': missing required key 'file'");
    BAD_FILE("bad_table.yaml", "bad_table.yaml:9:9: stage 'stage1', engine 's1e': table: "
             LV_MISSION_DIR "/data/bad_order.csv:5:");
}

/* Issue 9, item 3: what cannot be flown is refused when the file is read, with its position:
 * an epoch that is not a date, a tree whose branches contradict each other, a stop time a child
 * cannot reach, a negative thrust, an out-of-range angle. */
static void test_unflyable(void)
{
#define TWO_STAGES "stages:\n  - {name: s1, dry_mass: 1, propellant_mass: 1}\n" \
                   "  - {name: s2, dry_mass: 1, propellant_mass: 1}\n" /* lines 2-4 */
    /* epochs: no 30 February, no hour -1, nothing after the Z, no second 60 on a day without
     * a leap second (IERS Bulletin C 52: the last one was 2016-12-31T23:59:60Z) */
    BAD("mission: {name: t, epoch: 2026-02-30T12:00:00Z}\n" STAGES PHASE,
        "bad.yaml:1:27: mission: epoch: '2026-02-30T12:00:00Z': no such day in that month");
    BAD("mission: {name: t, epoch: 2026-03-01T-1:00:00Z}\n" STAGES PHASE,
        "bad.yaml:1:27: mission: epoch: '2026-03-01T-1:00:00Z': an ISO 8601 UTC time like");
    BAD("mission: {name: t, epoch: 2026-03-01T12:00:00Zx}\n" STAGES PHASE,
        "bad.yaml:1:27: mission: epoch: '2026-03-01T12:00:00Zx': text after the Z");
    BAD("mission: {name: t, epoch: 2016-12-30T23:59:60Z}\n" STAGES PHASE,
        "bad.yaml:1:27: mission: epoch: '2016-12-30T23:59:60Z': no leap second here");
    BAD("mission: {name: t, epoch: 2016-12-31T23:58:60Z}\n" STAGES PHASE,
        "bad.yaml:1:27: mission: epoch: '2016-12-31T23:58:60Z': no leap second here");
    BAD("mission: {name: t, epoch: 2016-12-31T23:59:61Z}\n" STAGES PHASE,
        "bad.yaml:1:27: mission: epoch: '2016-12-31T23:59:61Z': the second must be 00 to 59");
    BAD("mission: {name: t, epoch: 2026-03-01T12:00:00+01:00}\n" STAGES PHASE,
        "bad.yaml:1:27: mission: epoch: '2026-03-01T12:00:00+01:00': the time must end with Z");
    /* 29 February of a leap year, a fraction of a second, and the leap seconds of 2016-12-31
     * and 2015-06-30 are fine */
    static const char *const good[] = {"2024-02-29T23:59:59.25Z", "2016-12-31T23:59:60Z",
                                       "2015-06-30T23:59:60.5Z"};
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
        char ok[512];
        snprintf(ok, sizeof ok, "mission: {name: t, epoch: %s}\n" STAGES PHASE, good[i]);
        lv_err err;
        lv_mission_def *m = NULL;
        CHECK_OK(lv_mission_def_parse(ok, strlen(ok), "ok.yaml", LV_MISSION_DIR, &m, &err), &err);
        CHECK(m != NULL && m->epoch != NULL && strcmp(m->epoch, good[i]) == 0);
        lv_mission_def_free(m);
    }
    /* a child carries only its parent's stages */
    BAD(HEAD TWO_STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1], stop_time: 1}\n"
        "  - {name: P2, model: flat6, stages: [s1, s2], from: P1, stop_time: 2}\n",
        "bad.yaml:7:43: phase 'P2': stages: 's2' is not carried by its parent 'P1'");
    /* a stage in one place at a time, unless the branches are alternatives */
    BAD(HEAD TWO_STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1, s2], stop_time: 1}\n"
        "  - {name: A, model: flat6, stages: [s1], from: P1, stop_time: 2}\n"
        "  - {name: B, model: flat6, stages: [s2, s1], from: P1, stop_time: 2}\n",
        "bad.yaml:8:42: phase 'B': stages: 's1' also flies in phase 'A' (line 7) of another "
        "branch (they split after 'P1')");
    BAD(HEAD TWO_STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1], stop_time: 5}\n"
        "  - {name: P2, model: flat6, stages: [s1], stop_time: 5}\n",
        "bad.yaml:7:39: phase 'P2': stages: 's1' also flies in phase 'P1' (line 6)");
    {
        const char *ok = HEAD TWO_STAGES
            "phases:\n  - {name: P1, model: flat6, stages: [s1, s2], stop_time: 1}\n"
            "  - {name: A, model: flat6, stages: [s1], from: P1, stop_time: 2}\n"
            "  - {name: B, model: flat6, stages: [s2, s1], from: P1, stop_time: 2, "
            "alternative: true}\n";
        lv_err err;
        lv_mission_def *m = NULL;
        CHECK_OK(lv_mission_def_parse(ok, strlen(ok), "ok.yaml", LV_MISSION_DIR, &m, &err), &err);
        CHECK(m != NULL && m->phases[2].alternative == 1 && m->phases[1].alternative == 0);
        lv_mission_def_free(m);
    }
    BAD(HEAD TWO_STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1, s2], stop_time: 5}\n"
        "  - {name: A, model: flat6, stages: [s1], from: P1, stop_time: 2, alternative: maybe}\n",
        "bad.yaml:7:80: phase 'A': alternative: unknown value 'maybe'");
    /* a child's stop time after its parent's, and no start time of its own */
    BAD(HEAD TWO_STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1, s2], stop_time: 5}\n"
        "  - {name: A, model: flat6, stages: [s1], from: P1, stop_time: 5}\n",
        "bad.yaml:7:64: phase 'A': stop_time 5 s is not after the stop_time 5 s of its parent");
    BAD(HEAD TWO_STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1, s2], stop_time: 5, "
        "end: [burnout]}\n"
        "  - {name: A, model: flat6, stages: [s1], from: P1, start_time: 5, stop_time: 9}\n",
        "bad.yaml:7:65: phase 'A': start_time: a phase with `from` starts when its parent 'P1' "
        "ends, which an end event decides");
    BAD(HEAD TWO_STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1, s2], stop_time: 5}\n"
        "  - {name: A, model: flat6, stages: [s1], from: P1, start_time: 4, stop_time: 9}\n",
        "bad.yaml:7:65: phase 'A': start_time 4 s is not the end 5 s of its parent 'P1'");
    /* a thrust table that turns negative: a thrust and a mass flow are >= 0 */
    BAD(HEAD "stages:\n  - {name: s1, dry_mass: 1, propellant_mass: 1,\n"
        "     engines: [{table: data/negative_thrust.csv}]}\n" PHASE,
        "bad.yaml:4:17: stage 's1', engine #1: table '" LV_MISSION_DIR
        "/data/negative_thrust.csv': thrust = -10000 N at t = 20 s");
    /* the parameter set's ranges: a latitude beyond the pole, a negative speed */
    BAD(HEAD "environment: {world: planet}\nparameters: {start_lat_deg: 95}\n" STAGES
        "phases:\n  - {name: P1, model: dof3, stages: [s1], stop_time: 1}\n",
        "bad.yaml:3:29: parameters: start_lat_deg must be >= -90 and <= 90 deg, found 95");
    BAD(HEAD "parameters: {start_vel: -3}\n" STAGES PHASE,
        "bad.yaml:2:25: parameters: start_vel must be >= 0 m/s, found -3");
#undef TWO_STAGES
}

/* The environment's own keys (docs/mission-format.md, "environment"): a planet by its
 * constants, gravity checked where it is written, the exponential atmosphere's parameters,
 * the wind's forms; every number a slot of the environment, every bad value refused at its
 * line and column. */
#define DPHASE "phases:\n  - {name: P1, model: dof3, stages: [s1], stop_time: 1}\n"
static void test_environment(void)
{
    lv_err err;
    lv_mission_def *m = NULL;
    const char *sphere =
        HEAD STAGES DPHASE
        "environment:\n"
        "  world: planet\n"
        "  planet: {name: sphere, radius: 6371000, gm: 3.986004418e14, rotation_rate_deg: 0.001,\n"
        "           zonal: [1.0e-3, 0, -2.0e-6]}\n"
        "  atmosphere: {model: exp, rho0: 1.2, scale_height: 8000}\n"
        "  wind: {north: 5, east: -3}\n";
    CHECK_OK(lv_mission_def_parse(sphere, strlen(sphere), "env.yaml", LV_MISSION_DIR, &m, &err),
             &err);
    if (m != NULL) {
        const lv_env_def *e = &m->env;
        CHECK(strcmp(e->planet, "sphere") == 0 && e->pdef.custom && !e->pdef.has_base);
        CHECK(strcmp(e->gravity, "zonal") == 0); /* default for a planet by its constants */
        CHECK(strcmp(e->atmosphere, "exp") == 0);
        CHECK(m->slots[e->pdef.radius].value == 6371000.0);
        CHECK(strcmp(m->slots[e->pdef.gm].name, "environment.planet.gm") == 0);
        CHECK(m->slots[e->pdef.rotation_rate].value == 0.001 * M_PI / 180.0);
        CHECK(strcmp(m->slots[e->pdef.rotation_rate].unit, "rad/s") == 0);
        CHECK(e->pdef.flattening == LV_NO_SLOT && e->pdef.r_ref == LV_NO_SLOT);
        CHECK(e->pdef.n_zonal == 3 && m->slots[e->pdef.zonal[2]].value == -2.0e-6);
        CHECK(strcmp(m->slots[e->pdef.zonal[0]].name, "environment.planet.J2") == 0);
        CHECK(m->slots[e->atmo_par[0]].value == 1.2 && e->atmo_par[2] == LV_NO_SLOT);
        CHECK(strcmp(m->slots[e->atmo_par[1]].name, "environment.atmosphere.scale_height") == 0);
        CHECK(e->wind_const && m->slots[e->wind_ned[1]].value == -3.0);
        CHECK(e->wind_ned[2] == LV_NO_SLOT); /* down not written: 0, not a parameter */
        for (size_t i = 0; i < m->n_slots; i++)
            if (strncmp(m->slots[i].name, "environment.", 12) == 0)
                CHECK(m->slots[i].owner == LV_OWN_ENV);
    }
    lv_mission_def_free(m);
    m = NULL;
    /* a preset changed: a non-rotating Earth keeps WGS-84, J2..J4 and US76; its gravity is
     * "zonal" (every zonal term it has), as for every planet given by its constants */
    const char *still = HEAD STAGES DPHASE
                        "environment: {world: planet, planet: {name: still, base: earth, "
                        "rotation_rate: 0}, wind: {file: data/wind_one_row.csv, extrap: error}}\n";
    CHECK_OK(lv_mission_def_parse(still, strlen(still), "env.yaml", LV_MISSION_DIR, &m, &err),
             &err);
    if (m != NULL) {
        const lv_env_def *e = &m->env;
        CHECK(e->pdef.has_base && e->pdef.base.a == 6378137.0 && !e->pdef.zonal_given);
        CHECK(strcmp(e->atmosphere, "us76") == 0 && strcmp(e->gravity, "zonal") == 0);
        CHECK(e->wind_extrap == LV_EXTRAP_ERROR && e->wind_interp == LV_INTERP_LINEAR);
    }
    lv_mission_def_free(m);

#define PW HEAD STAGES DPHASE "environment:\n  world: planet\n" /* lines 1-7 */
    BAD(PW "  planet: {radius: 6371000}\n",
        "bad.yaml:8:11: environment, planet: missing required key 'gm' (or give 'base: earth'");
    BAD(PW "  planet: {radius: -1, gm: 1}\n",
        "bad.yaml:8:20: environment, planet: radius must be > 0 and <= 1e+10 m, found -1");
    BAD(PW "  planet: {radius: 1e6, gm: 4e14, flattening: 1}\n",
        "bad.yaml:8:47: environment, planet: flattening must be >= 0 and < 1, found 1");
    BAD(PW "  planet: {name: earth, base: earth}\n",
        "bad.yaml:8:18: environment, planet: name 'earth' is a preset's");
    BAD(PW "  planet: {base: venus}\n",
        "bad.yaml:8:18: environment, planet: base: unknown value 'venus'");
    BAD(PW "  planet: {base: earth, rotation_rate: 0.01}\n",
        "bad.yaml:8:11: environment, planet: planet 'custom': rotation rate 0.01 rad/s must be "
        "below sqrt(gm / a^3) = 0.00123945 rad/s");
    BAD(PW "  planet: {base: earth, rotation_rate: 0, rotation_rate_deg: 0}\n",
        "bad.yaml:8:43: environment, planet: 'rotation_rate' and 'rotation_rate_deg' given both");
    BAD(PW "  planet: {base: earth, zonal: 1e-3}\n",
        "bad.yaml:8:32: environment, planet: zonal: a list [J2, J3, ...] expected");
    BAD(PW "  planet: {base: earth, zonal: [1e-3, 2]}\n",
        "bad.yaml:8:39: environment, planet: J3 must be > -1 and < 1, found 2");
    BAD(PW "  planet: {base: earth, zonal: [1e-3, x]}\n",
        "bad.yaml:8:39: environment, planet: J3: number expected, found 'x'");
    BAD(PW "  planet: {base: mars, coefficients: no_such.gfc}\n",
        "bad.yaml:8:38: environment, planet: coefficients: cannot read");
    BAD(PW "  planet: {base: mars, coefficients: data/wind_one_row.csv}\n  gravity: j2\n",
        "bad.yaml:9:12: environment: gravity 'j2' does not use the planet's coefficient file");
    BAD(PW "  planet: moon\n  gravity: sh:8\n",
        "bad.yaml:9:12: environment: gravity 'sh:8' would read the shipped EGM2008 "
        "coefficients, which are the Earth's");
    BAD(PW "  gravity: zonl\n",
        "bad.yaml:8:12: environment: gravity: unknown gravity model 'zonl'; did you mean 'zonal'?");
    BAD(PW "  gravity: sh:0\n",
        "bad.yaml:8:12: environment: gravity: gravity model 'sh:0': degree must be 1..10000");
    BAD(PW "  atmosphere: {model: exp, rho0: 0}\n",
        "bad.yaml:8:34: environment, atmosphere: rho0 must be > 0 kg/m3, found 0");
    BAD(PW "  atmosphere: {model: us76, scale_height: 7000}\n",
        "bad.yaml:8:29: environment, atmosphere: 'scale_height' belongs to model: exp (this is "
        "us76)");
    BAD(PW "  atmosphere: {table: data/wind_one_row.csv, model: exp}\n",
        "bad.yaml:8:46: environment, atmosphere: give either 'table' (a file) or 'model'");
    BAD(PW "  atmosphere: {table: /dev/null}\n",
        "bad.yaml:8:23: environment, atmosphere: table: '/dev/null' is not a regular file");
    BAD(PW "  atmosphere: {rho0: 1}\n",
        "bad.yaml:8:15: environment, atmosphere: missing required key 'model'");
    BAD(PW "  wind: {north: 5}\n",
        "bad.yaml:8:9: environment, wind: missing required key 'east'");
    BAD(PW "  wind: {north: 5, east: 600}\n",
        "bad.yaml:8:26: environment, wind: east must be >= -500 and <= 500 m/s, found 600");
    BAD(PW "  wind: {north: 5, east: 1, extrap: error}\n",
        "bad.yaml:8:29: environment, wind: 'extrap' goes with 'file' (a wind table)");
    BAD(PW "  wind: {file: data/wind_one_row.csv, east: 1}\n",
        "bad.yaml:8:39: environment, wind: give either 'file' (a table) or the constant");
    BAD(PW "  wind: {file: data/wind_one_row.csv, extrap: clmp}\n",
        "bad.yaml:8:47: environment, wind: extrap: unknown value 'clmp'; did you mean 'clamp'?");
    BAD(PW "  wind: no_such_wind.csv\n",
        "bad.yaml:8:9: environment: wind: cannot read");
    BAD(PW "  planet: mars\n  wind: {north: 1, east: 2}\n",
        "bad.yaml:9:3: environment: a wind moves air, and there is none (atmosphere: none, the "
        "default here)");
    BAD(HEAD STAGES PHASE "environment: {wind: {north: 1, east: 2}, atmosphere: none}\n",
        "bad.yaml:6:15: environment: a wind moves air, and there is none (atmosphere: none)");
#undef PW
    /* aerodynamic datasets: a table per coefficient (docs/mission-format.md, "aero") */
#define AERO(a) HEAD STAGES "phases:\n  - {name: P1, model: dof3, stages: [s1], stop_time: 1,\n" \
                "     aero: " a "}\nenvironment: {world: planet}\n" /* aero on line 6 */
    m = NULL;
    const char *ok = AERO("{s_ref: 1, axes: body, CA: {file: data/aero_two.csv, output: CA}, "
                          "CN: {file: data/aero_two.csv, output: CN, interp: pchip}, CY: 0.01}");
    CHECK_OK(lv_mission_def_parse(ok, strlen(ok), "aero.yaml", LV_MISSION_DIR, &m, &err), &err);
    lv_mission_def_free(m);
    BAD(AERO("{s_ref: 1, axes: body, CY: data/aero_two.csv}"),
        "bad.yaml:6:35: phase 'P1', aero: CY: table 'aero_two' has several outputs (CA, CN) and "
        "none is named CY");
    BAD(AERO("{s_ref: 1, CD: data/aero_two.csv}"),
        "bad.yaml:6:23: phase 'P1', aero: CD: table 'aero_two' has several outputs (CA, CN) and "
        "none is named CD: say which with {file: .., output: name}");
    BAD(AERO("{s_ref: 1, axes: body, CA: {file: data/aero_two.csv, output: CX}}"),
        "bad.yaml:6:73: phase 'P1', aero: CA: table 'aero_two' has no output 'CX' (its outputs: "
        "CA, CN)");
    BAD(AERO("{s_ref: 1, CD: data/aero_badaxis.csv}"),
        "bad.yaml:6:23: phase 'P1', aero: CD: table 'aero_badaxis': axis 1 is named 'speed'; the "
        "axes of an aerodynamic table are mach");
    BAD(AERO("{s_ref: 1, table: data/aero_two.csv}"),
        "bad.yaml:6:23: phase 'P1', aero: table 'aero_two' gives none of CD, CL, CY (its "
        "outputs: CA, CN)");
    BAD(AERO("{s_ref: 1, CD: data/no_such.csv}"),
        "bad.yaml:6:27: phase 'P1', aero: CD: cannot read");
    BAD(AERO("{s_ref: 1, CD: .nan}"),
        "bad.yaml:6:27: phase 'P1', aero: CD: non-finite number '.nan'");
    BAD(HEAD STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1], stop_time: 1,\n"
        "     aero: {s_ref: 1, CD: 0.3, CL: 0.1}}\nenvironment: {atmosphere: us76}\n",
        "bad.yaml:6:32: phase 'P1', aero: 'CL': the flat world's body flies at zero angle of "
        "attack and has no lift or side force; it takes CD only");
#undef AERO
}

/* Named events (docs/mission-format.md, "Named events"): `name:` on an end entry (also the
 * bare kinds: {burnout, name: MECO}, {impact, name: touchdown}) and on an engine-out,
 * `end_name:` for whichever end has none; bad names at their line and column. */
static void test_event_names(void)
{
    static const char good[] =
        "mission: {name: t}\n"
        "environment: {world: planet}\n"
        "stages:\n"
        "  - {name: s1, dry_mass: 100, propellant_mass: 50,\n"
        "     engines: [{name: e, count: 3, thrust_vac: 5000, isp_vac: 300}]}\n"
        "phases:\n"
        "  - name: P1\n"
        "    model: dof3\n"
        "    stages: [s1]\n"
        "    stop_time: 100\n"
        "    end: [{burnout, name: MECO}, {altitude: 1000, direction: rising, name: \"1 km \u00fc\"},\n"
        "          {impact, name: touchdown}, apogee, {speed: 3}]\n"
        "    end_name: cut-off\n"
        "    engine_out: [{time: 1, name: engine 1 out}, {time: 2}]\n";
    lv_err err = {LV_OK, ""};
    lv_mission_def *m = NULL;
    CHECK_OK(lv_mission_def_parse(good, strlen(good), "good.yaml", LV_MISSION_DIR, &m, &err), &err);
    if (m != NULL) {
        const lv_phase_def *ph = &m->phases[0];
        CHECK(ph->n_ends == 5);
        CHECK(ph->ends[0].kind == LV_END_BURNOUT && strcmp(ph->ends[0].label, "MECO") == 0 &&
              strcmp(ph->ends[0].name, "burnout") == 0);
        CHECK(ph->ends[1].kind == LV_END_ALTITUDE && V(ph->ends[1].value) == 1000.0 &&
              ph->ends[1].direction == LV_DIR_RISING &&
              strcmp(ph->ends[1].label, "1 km \xc3\xbc") == 0);
        /* {impact, name: ..}: the ground, 0 m, its slot as for a plain `impact` */
        CHECK(ph->ends[2].kind == LV_END_IMPACT && V(ph->ends[2].value) == 0.0 &&
              ph->ends[2].value != LV_NO_SLOT && strcmp(ph->ends[2].label, "touchdown") == 0);
        CHECK(ph->ends[3].kind == LV_END_APOGEE && ph->ends[3].label == NULL);
        CHECK(ph->ends[4].kind == LV_END_SPEED && ph->ends[4].label == NULL);
        CHECK(ph->end_name != NULL && strcmp(ph->end_name, "cut-off") == 0);
        CHECK(ph->n_engine_out == 2 && strcmp(ph->engine_out[0].label, "engine 1 out") == 0 &&
              ph->engine_out[1].label == NULL);
    }
    lv_mission_def_free(m);
#define NPHASE "phases:\n  - {name: P1, model: flat6, stages: [s1], stop_time: 1, end: "
    /* line 5, column 64: the first entry of `end` */
    BAD(HEAD STAGES NPHASE "[{burnout, name: X}, {apogee, name: X}]}\n",
        "bad.yaml:5:99: phase 'P1': event name 'X' given twice (first at line 5): the names "
        "of a phase's events are unique");
    BAD(HEAD STAGES NPHASE "[{burnout, name: \"\"}]}\n",
        "bad.yaml:5:80: phase 'P1', end event #1: name: a name or text expected");
    BAD(HEAD STAGES NPHASE "[{burnout, name: \"a\\tb\"}]}\n",
        "bad.yaml:5:80: phase 'P1', end event #1: name: a control character (0x09) at "
        "character 2: a name is printable text");
    BAD(HEAD STAGES NPHASE "[{burnout, name: \" MECO\"}]}\n",
        "bad.yaml:5:80: phase 'P1', end event #1: name ' MECO' starts or ends with a space");
    BAD(HEAD STAGES NPHASE "[{burnout, name: "
        "a234567890123456789012345678901234567890123456789012345678901234}]}\n",
        "bad.yaml:5:80: phase 'P1', end event #1: name: 64 characters, at most 63");
    BAD(HEAD STAGES NPHASE "[{burnout, name: [MECO]}]}\n",
        "bad.yaml:5:80: phase 'P1', end event #1: name: a name or text expected, found a list");
    BAD(HEAD STAGES NPHASE "[{burnout: 1, name: MECO}]}\n",
        "bad.yaml:5:65: phase 'P1', end event #1: 'burnout' takes no value: write it as a plain "
        "list entry, or {burnout, name: NAME} to name it");
    BAD(HEAD STAGES NPHASE "[{name: MECO}]}\n",
        "bad.yaml:5:64: phase 'P1', end event #1: which event?");
    BAD(HEAD STAGES NPHASE "[{burnout, direction: rising, name: MECO}]}\n",
        "bad.yaml:5:74: phase 'P1', end event #1: 'burnout' has a fixed direction (falling)");
    BAD(HEAD STAGES "phases:\n  - {name: P1, model: flat6, stages: [s1], stop_time: 1, "
        "end_name: MECO}\n",
        "bad.yaml:5:58: phase 'P1': end_name names the phase's end events, and it has none");
    /* 63 characters, two of them two bytes long in UTF-8: accepted */
    static const char ok63[] = HEAD STAGES NPHASE "[{burnout, name: \"\u00fc\u00fc"
        "3456789012345678901234567890123456789012345678901234567890123\"}]}\n";
    CHECK_OK(lv_mission_def_parse(ok63, strlen(ok63), "ok.yaml", LV_MISSION_DIR, &m, &err), &err);
    lv_mission_def_free(m);
#undef NPHASE
    /* an engine-out's name: the same rules, unique among the phase's ends and engine-outs */
    static const char planet[] =
        "mission: {name: t}\n"
        "environment: {world: planet}\n"
        "stages:\n"
        "  - {name: s1, dry_mass: 100, propellant_mass: 50,\n"
        "     engines: [{name: e, count: 3, thrust_vac: 5000, isp_vac: 300}]}\n"
        "phases:\n"
        "  - name: P1\n"
        "    model: dof3\n"
        "    stages: [s1]\n"
        "    stop_time: 100\n"
        "    end: [{burnout, name: out}]\n";
    char buf[1024];
    snprintf(buf, sizeof buf, "%s    engine_out: {time: 1, name: out}\n", planet);
    BAD(buf, "bad.yaml:12:33: phase 'P1': event name 'out' given twice (first at line 11)");
    snprintf(buf, sizeof buf, "%s    engine_out: {time: 1, name: ~}\n", planet);
    BAD(buf, "bad.yaml:12:33: phase 'P1', engine_out: name: a name or text expected");
    /* a separation's name: the same rules; {name: ...} alone gives no impulse */
    snprintf(buf, sizeof buf, "%s  - {name: P2, model: dof3, stages: [s1], from: P1, "
             "stop_time: 200, separation: {dv: 1, name: \"\\nx\"}}\n", planet);
    BAD(buf, "bad.yaml:12:95: phase 'P2', separation: name: a control character (0x0a)");
    snprintf(buf, sizeof buf, "%s  - {name: P2, model: dof3, stages: [s1], from: P1, "
             "stop_time: 200, separation: {name: stage separation}}\n", planet);
    CHECK_OK(lv_mission_def_parse(buf, strlen(buf), "ok.yaml", LV_MISSION_DIR, &m, &err), &err);
    if (m != NULL) {
        const lv_phase_def *p2 = phase(m, "P2");
        CHECK(p2 != NULL && strcmp(p2->separation_label, "stage separation") == 0);
        CHECK(lv_mission_def_slot(m, "P2.separation.dv") == LV_NO_SLOT);
    }
    lv_mission_def_free(m);
    snprintf(buf, sizeof buf, "%s    engine_out: [{time: 1, name: a}, {time: 2, name: a}]\n",
             planet);
    BAD(buf, "bad.yaml:12:54: phase 'P1': event name 'a' given twice (first at line 12)");
}

int main(void)
{
    test_event_names();
    test_file_sizes();
    test_unflyable();
    test_paper_branch();
    test_planet_and_defaults();
    test_environment();
    test_mat_generated();
    test_syntax();
    test_keys_and_types();
    test_references();
    test_values();
    test_engines();
    return check_report("test_mission_parse");
}
