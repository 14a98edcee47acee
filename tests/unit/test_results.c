/* test_results.c - src/post/results.c, the one reader of a results folder: summary.json into
 * structures, CSV files into tables by column name; bad input gives file and line, file names
 * that climb out of the folder are refused. Hand-made folders under results_out/. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "check.h"
#include "lvsim/lv_io.h"
#include "post/results.h"

#define DIR "results_out"

static int write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    if (f == NULL)
        return 0;
    fputs(text, f);
    return fclose(f) == 0;
}

static int same(const char *a, const char *b)
{
    return a != NULL && b != NULL && strcmp(a, b) == 0;
}

/* Position of result format `name` in the registry (lv_io.h); aborts the test when absent. */
static size_t format_index(const char *name)
{
    const char *f;
    for (size_t i = 0; (f = lv_result_format_info(i, NULL, NULL)) != NULL; i++)
        if (strcmp(f, name) == 0)
            return i;
    fprintf(stderr, "result format '%s' not registered\n", name);
    exit(1);
}

static const char summary[] =
    "{\"mission\": \"m1\", \"file\": \"m1.yaml\", \"lvsim\": \"0.1.0\",\n"
    " \"epoch\": \"2026-03-01T12:00:00Z\", \"world\": \"planet\", \"planet\": \"earth\",\n"
    " \"phases\": [\n"
    "  {\"index\": 1, \"name\": \"ascent\", \"model\": \"dof3\", \"stages\": [\"s1\", \"s2\"],\n"
    "   \"from\": null, \"state\": \"done\", \"t_start\": 0, \"t_end\": 120.5,\n"
    "   \"end\": {\"reason\": \"event\", \"event\": \"burnout\"},\n"
    "   \"events\": [{\"t\": 60, \"kind\": \"time\"},\n"
    "              {\"t\": 120.5, \"kind\": \"state\", \"name\": \"burnout\", \"direction\": -1}],\n"
    "   \"stats\": {\"steps\": 40, \"rhs_evals\": 90, \"state_events\": 1, \"time_events\": 1,\n"
    "             \"cpu_time\": 0.002},\n"
    "   \"files\": {\"mat\": \"ascent.mat\", \"csv\": \"ascent.csv\"}},\n"
    "  {\"index\": 2, \"name\": \"coast, \\\"upper\\\"\", \"model\": \"dof3\", \"stages\": [\"s2\"],\n"
    "   \"from\": \"ascent\", \"state\": \"failed\", \"error\": \"boom\", \"t_start\": 120.5,\n"
    "   \"t_end\": 130, \"end\": {\"reason\": \"stop_time\", \"value\": 130},\n"
    "   \"files\": {\"mat\": \"coast.failed.mat\", \"csv\": \"coast.failed.csv\"}},\n"
    "  {\"index\": 3, \"name\": \"later\", \"from\": \"nowhere\", \"state\": \"skipped\"}\n"
    " ],\n"
    " \"bodies\": [{\"name\": \"s2\", \"phases\": [\"ascent\", \"coast, \\\"upper\\\"\"],\n"
    "              \"trajectory\": \"body_s2.csv\"},\n"
    "             {\"name\": \"s1\", \"phases\": [\"ascent\"]}]}\n";

static void test_summary(void)
{
    lv_err err = {0};
    lv_results *r = NULL;
    CHECK(write_text(DIR "/summary.json", summary));
    CHECK_OK(lv_results_open(DIR, &r, &err), &err);
    if (r == NULL)
        return;
    CHECK(same(r->summary_path, DIR "/summary.json") && same(r->outdir, DIR));
    CHECK(same(r->mission, "m1") && same(r->file, "m1.yaml") && same(r->lvsim, "0.1.0"));
    CHECK(same(r->epoch, "2026-03-01T12:00:00Z") && same(r->world, "planet") && !r->flat);
    CHECK(same(r->planet, "earth"));
    CHECK(r->n_phases == 3 && r->n_bodies == 2);

    const lv_results_phase *a = &r->phases[0], *c = &r->phases[1], *l = &r->phases[2];
    CHECK(same(a->name, "ascent") && a->index == 1 && a->from == NULL && a->parent == -1);
    CHECK(same(a->state, "done") && a->done && a->error == NULL && same(a->model, "dof3"));
    CHECK(a->t_start == 0.0 && a->t_end == 120.5);
    CHECK(same(a->end_reason, "event") && same(a->end_event, "burnout") && isnan(a->end_value));
    CHECK(a->n_events == 2);
    if (a->n_events == 2) {
        CHECK(a->events[0].t == 60.0 && a->events[0].name == NULL);
        CHECK(same(a->events[0].kind, "time") && isnan(a->events[0].direction));
        CHECK(a->events[1].t == 120.5 && same(a->events[1].name, "burnout"));
        CHECK(same(a->events[1].kind, "state") && a->events[1].direction == -1.0);
    }
    CHECK(a->n_stages == 2 && same(a->stages[0], "s1") && same(a->stages[1], "s2"));
    /* files.<name> per registered result format, room for each of them */
    CHECK(lv_result_format_info(LV_RESULTS_MAX_FORMATS, NULL, NULL) == NULL);
    CHECK(same(a->csv, "ascent.csv") && same(a->files[format_index("csv")], "ascent.csv"));
    CHECK(same(a->files[format_index("mat")], "ascent.mat"));
    CHECK(a->steps == 40.0 && a->rhs_evals == 90.0 && a->state_events == 1.0);
    CHECK(a->time_events == 1.0 && a->cpu_time == 0.002);

    CHECK(same(c->name, "coast, \"upper\"") && c->index == 2 && c->parent == 0);
    CHECK(same(c->from, "ascent") && !c->done && same(c->state, "failed"));
    CHECK(same(c->error, "boom") && c->n_events == 0 && c->n_stages == 1);
    CHECK(same(c->end_reason, "stop_time") && c->end_event == NULL && c->end_value == 130.0);
    CHECK(isnan(c->steps) && isnan(c->cpu_time));

    /* Nothing but name, index, from, state: NULL and NAN for the rest; an unknown parent. */
    CHECK(same(l->name, "later") && l->index == 3 && same(l->from, "nowhere") && l->parent == -1);
    CHECK(!l->done && isnan(l->t_start) && isnan(l->t_end) && l->end_reason == NULL);
    CHECK(l->csv == NULL && l->files[format_index("mat")] == NULL && l->model == NULL &&
          l->n_events == 0);

    CHECK(same(r->bodies[0].name, "s2") && same(r->bodies[0].trajectory, "body_s2.csv"));
    CHECK(r->bodies[0].n_phases == 2 && r->bodies[0].phases[0] == 0 &&
          r->bodies[0].phases[1] == 1);
    CHECK(same(r->bodies[1].name, "s1") && r->bodies[1].trajectory == NULL);
    CHECK(r->bodies[1].n_phases == 1 && r->bodies[1].phases[0] == 0);

    CHECK(lv_results_phase_find(r, "coast, \"upper\"") == 1);
    CHECK(lv_results_phase_find(r, "coast") == -1 && lv_results_phase_find(r, NULL) == -1);
    CHECK(lv_results_exists(r, "summary.json") && !lv_results_exists(r, "ascent.csv"));
    lv_results_free(r);
    lv_results_free(NULL);
}

/* One broken copy of the summary: `from` replaced by `to`; the error's code and text. */
static void broken(const char *from, const char *to, lv_status code, const char *needle)
{
    const char *hit = strstr(summary, from);
    CHECK(hit != NULL);
    if (hit == NULL)
        return;
    char text[sizeof summary + 200];
    snprintf(text, sizeof text, "%.*s%s%s", (int)(hit - summary), summary, to,
             hit + strlen(from));
    CHECK(write_text(DIR "/summary.json", text));
    lv_err err = {0};
    lv_results *r = (lv_results *)&err; /* must become NULL */
    CHECK_FAILS(lv_results_open(DIR, &r, &err), &err, code, needle);
    CHECK(r == NULL);
}

static void test_summary_errors(void)
{
    lv_err err = {0};
    lv_results *r = NULL;
    remove(DIR "/summary.json");
    CHECK_FAILS(lv_results_open(DIR, &r, &err), &err, LV_ERR_IO,
                DIR "/summary.json: cannot open: No such file or directory");
    CHECK_FAILS(lv_results_open("", &r, &err), &err, LV_ERR_INPUT, "no folder");
    broken("\"from\": null,", "\"from\": nul,", LV_ERR_INPUT, DIR "/summary.json:5: malformed JSON");
    broken("\"phases\"", "\"phasen\"", LV_ERR_INPUT, "no 'phases' or 'bodies' array");
    broken("\"name\": \"ascent\"", "\"nam\": \"ascent\"", LV_ERR_INPUT, "phases[0]: no 'name'");
    broken("\"index\": 2", "\"index\": 0", LV_ERR_INPUT, "phase 'coast, \"upper\"': index 0");
    broken("\"phases\": [\"ascent\"]", "\"phases\": [\"descent\"]", LV_ERR_INPUT,
           "body 's1': phases[0] 'descent' is not a phase");
    broken("{\"name\": \"s1\", \"phases\": [\"ascent\"]}", "{\"name\": \"s1\"}", LV_ERR_INPUT,
           "bodies[1]: no 'name' or no 'phases' array");
    /* File names that leave the folder. */
    broken("\"body_s2.csv\"", "\"../body_s2.csv\"", LV_ERR_INPUT,
           "body 's2': trajectory '../body_s2.csv' is not a file name in the folder");
    broken("\"body_s2.csv\"", "\"/etc/passwd\"", LV_ERR_INPUT, "'/etc/passwd' is not a file");
    broken("\"body_s2.csv\"", "\"..\"", LV_ERR_INPUT, "trajectory '..' is not a file");
    broken("\"csv\": \"ascent.csv\"", "\"csv\": \"sub/ascent.csv\"", LV_ERR_INPUT,
           "phase 'ascent': files.csv 'sub/ascent.csv' is not a file name in the folder");
    broken("\"mat\": \"ascent.mat\"", "\"mat\": \"\"", LV_ERR_INPUT, "files.mat '' is not");
    /* A name with dots that stays inside is fine. */
    CHECK(write_text(DIR "/summary.json", summary));
    CHECK_OK(lv_results_open(DIR, &r, &err), &err);
    lv_results_free(r);
}

static void test_tables(void)
{
    lv_err err = {0};
    lv_results *r = NULL;
    CHECK(write_text(DIR "/summary.json", summary));
    CHECK_OK(lv_results_open(DIR, &r, &err), &err);
    if (r == NULL)
        return;
    /* Units, a quoted header field with a comma, CRLF, a comment, a blank line, text, numbers
     * with blanks, a field that is not a number (NAN), quoted phase names. */
    CHECK(write_text(DIR "/body_s2.csv",
                     "# made by hand\r\n"
                     "time [s],phase,\"a, b [m/s]\",h [m],note\r\n"
                     "0,ascent,1.5,100,x\r\n"
                     "\r\n"
                     "1, ascent ,2.5 ,200,nan\r\n"
                     "# a comment line\n"
                     "2,\"coast, \"\"upper\"\"\",-3e2,300,7\n"
                     "3,\"coast, \"\"upper\"\"\",4,400,\n"));
    static const char *const text[] = {"phase", NULL};
    static const char *const finite[] = {"time", "h", "missing", NULL};
    const lv_results_csv_spec spec = {text, finite};
    lv_results_table *t = NULL;
    CHECK_OK(lv_results_load(r, "body_s2.csv", &spec, &t, &err), &err);
    if (t != NULL) {
        CHECK(same(t->path, DIR "/body_s2.csv") && t->header_line == 2 && t->n_lines == 8);
        CHECK(t->n_cols == 5 && t->n_rows == 4);
        CHECK(lv_results_table_col(t, "time") == 0 && lv_results_table_col(t, "phase") == 1);
        CHECK(lv_results_table_col(t, "a, b") == 2 && lv_results_table_col(t, "h") == 3);
        CHECK(lv_results_table_col(t, "note") == 4 && lv_results_table_col(t, "m") == -1);
        CHECK(lv_results_table_col(NULL, "time") == -1);
        CHECK(same(t->cols[0].unit, "s") && same(t->cols[2].unit, "m/s"));
        CHECK(same(t->cols[1].unit, "") && same(t->cols[4].unit, ""));
        CHECK(t->cols[1].text != NULL && t->cols[0].text == NULL);
        const size_t lines[4] = {3, 5, 7, 8};
        const double a[4] = {1.5, 2.5, -300.0, 4.0};
        for (size_t i = 0; i < 4 && t->n_rows == 4; i++) {
            CHECK(t->line[i] == lines[i]);
            CHECK(t->v[i * 5] == (double)i && t->v[i * 5 + 3] == 100.0 * (double)(i + 1));
            CHECK(t->v[i * 5 + 2] == a[i]);
            CHECK(isnan(t->v[i * 5 + 1]));
            CHECK(lv_results_table_text(t, i, 0) == NULL);
        }
        if (t->n_rows == 4) {
            CHECK(same(lv_results_table_text(t, 0, 1), "ascent"));
            CHECK(same(lv_results_table_text(t, 1, 1), " ascent "));
            CHECK(same(lv_results_table_text(t, 2, 1), "coast, \"upper\""));
            CHECK(same(lv_results_table_text(t, 3, 1), "coast, \"upper\""));
            /* "x" and "" are not numbers; "nan" is one (not a finite column) */
            CHECK(isnan(t->v[4]) && isnan(t->v[9]) && t->v[14] == 7.0 && isnan(t->v[19]));
        }
        lv_results_table_free(t);
    }
    lv_results_table_free(NULL);
    /* Without a spec every column is numbers. */
    CHECK_OK(lv_results_load(r, "body_s2.csv", NULL, &t, &err), &err);
    CHECK(t != NULL && t->cols[1].text == NULL && isnan(t->v[1]));
    lv_results_table_free(t);

    /* Errors: file and line. */
    t = (lv_results_table *)&err; /* must become NULL */
    CHECK_FAILS(lv_results_load(r, "ascent.csv", &spec, &t, &err), &err, LV_ERR_IO,
                DIR "/ascent.csv: cannot read: No such file or directory");
    CHECK(t == NULL);
    CHECK_FAILS(lv_results_load(r, "../summary.json", NULL, &t, &err), &err, LV_ERR_INPUT,
                "'../summary.json' is not a file name in the folder");
    CHECK(write_text(DIR "/ascent.csv", "time [s],h [m]\n0,1\n1,2,3\n"));
    CHECK_FAILS(lv_results_load(r, "ascent.csv", &spec, &t, &err), &err, LV_ERR_INPUT,
                DIR "/ascent.csv:3: 3 fields, the header has 2");
    CHECK(write_text(DIR "/ascent.csv", "time [s],h [m]\n0,1\n\n1,1e999\n"));
    CHECK_FAILS(lv_results_load(r, "ascent.csv", &spec, &t, &err), &err, LV_ERR_INPUT,
                DIR "/ascent.csv:4: column 'h': '1e999' is not a finite number");
    CHECK(write_text(DIR "/ascent.csv", "time [s],h [m]\n0,1\n1.5x,2\n"));
    CHECK_FAILS(lv_results_load(r, "ascent.csv", &spec, &t, &err), &err, LV_ERR_INPUT,
                DIR "/ascent.csv:3: column 'time': '1.5x' is not a finite number");
    CHECK_OK(lv_results_load(r, "ascent.csv", NULL, &t, &err), &err); /* not finite: NAN */
    CHECK(t != NULL && t->n_rows == 2 && isnan(t->v[2]) && t->v[3] == 2.0);
    lv_results_table_free(t);
    CHECK(write_text(DIR "/ascent.csv", "time [s],phase\n0,\"open\n"));
    CHECK_FAILS(lv_results_load(r, "ascent.csv", &spec, &t, &err), &err, LV_ERR_INPUT,
                DIR "/ascent.csv:2: unterminated quote");
    CHECK(write_text(DIR "/ascent.csv", "time [s],phase\n0,\"a\"b\n"));
    CHECK_FAILS(lv_results_load(r, "ascent.csv", &spec, &t, &err), &err, LV_ERR_INPUT,
                DIR "/ascent.csv:2: unterminated quote");
    CHECK(write_text(DIR "/ascent.csv", "# only a comment\n\n"));
    CHECK_FAILS(lv_results_load(r, "ascent.csv", &spec, &t, &err), &err, LV_ERR_INPUT,
                DIR "/ascent.csv:2: no header");
    /* A header and no rows is a table of no rows. */
    CHECK(write_text(DIR "/ascent.csv", "time [s],phase\n"));
    CHECK_OK(lv_results_load(r, "ascent.csv", &spec, &t, &err), &err);
    CHECK(t != NULL && t->n_rows == 0 && t->n_cols == 2);
    lv_results_table_free(t);
    remove(DIR "/ascent.csv");
    lv_results_free(r);
}

int main(void)
{
    mkdir(DIR, 0777);
    test_summary();
    test_summary_errors();
    test_tables();
    return check_report("test_results");
}
