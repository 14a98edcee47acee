/* test_plot.c - lv_plot_run() on three example runs (the paper's flat-world test case, the
 * 3-DoF branch over the Earth, the seven-phase winged launcher with its runway and fly-back):
 * every expected figure exists as a PNG (signature, IHDR size, not
 * a blank page by size) and an SVG, quantities a world lacks are skipped and said so, index.html
 * names every phase and figure and escapes mission text, nothing is printed, PLplot's current
 * stream is left as it was; errors name the file (and line). The PNGs' pixels are checked by
 * tests/unit/plot_png_check.py (ctest test_plot_png). The data of the Figure-10 plot
 * (plots/fig10_normalised.csv) are checked against the definition: one speed and one mass
 * reference for every body, the launcher's mass steps at the separation. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <plplot.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "check.h"
#include "lvsim/lv_mission.h"
#include "lvsim/lv_summary.h"
#include "lvsim/lv_plot.h"
#include "post/plot.h"

static const char *const all_figs[] = {"altitude", "speed", "mass", "mach", "dynamic_pressure",
                                       "load_factor", "flight_path_angle", "acceleration",
                                       "thrust", "ground_track", "ground_track_site",
                                       "fig10_normalised", "attitude", "angle_of_attack",
                                       "body_rates", "gimbal", "attitude_error", NULL};
/* not drawn for the paper's flat-world flight: no atmosphere, no aerodynamics, and a vertical
 * flight has no ground track to map */
static const char *const flat_skipped[] = {"mach", "dynamic_pressure", "load_factor",
                                           "flight_path_angle", "ground_track",
                                           "ground_track_site", "angle_of_attack", "gimbal",
                                           "attitude_error", NULL};
/* dof3-branch: no runway, and no stage comes back near the launch site; 3-DoF phases have an
 * attitude and aerodynamic angles but no body rates, gimbal or controller */
static const char *const dof3_skipped[] = {"ground_track_site", "body_rates", "gimbal",
                                           "attitude_error", NULL};
static const char *const rlv_skipped[] = {"body_rates", "gimbal", "attitude_error", NULL};

static int in_list(const char *const *l, const char *s)
{
    for (; *l; l++)
        if (strcmp(*l, s) == 0)
            return 1;
    return 0;
}

static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = malloc((size_t)n + 1);
    if (buf != NULL) {
        size_t got = fread(buf, 1, (size_t)n, f);
        buf[got] = '\0';
        if (len)
            *len = got;
    }
    fclose(f);
    return buf;
}

static int write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (f == NULL)
        return 0;
    fputs(text, f);
    return fclose(f) == 0;
}

static unsigned be32(const unsigned char *p)
{
    return (unsigned)p[0] << 24 | (unsigned)p[1] << 16 | (unsigned)p[2] << 8 | p[3];
}

/* A PNG: signature, IHDR first with the page size, at least `min_bytes` long. */
static void check_png(const char *path, size_t min_bytes)
{
    size_t n = 0;
    unsigned char *b = (unsigned char *)slurp(path, &n);
    CHECK(b != NULL);
    if (b == NULL) {
        fprintf(stderr, "missing %s\n", path);
        return;
    }
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    CHECK(n > 33 && memcmp(b, sig, 8) == 0);
    CHECK(n > 33 && memcmp(b + 12, "IHDR", 4) == 0 && be32(b + 8) == 13);
    CHECK(n > 33 && be32(b + 16) == 1000 && be32(b + 20) == 700);
    CHECK(n >= min_bytes);
    if (n < min_bytes)
        fprintf(stderr, "%s: only %zu bytes\n", path, n);
    free(b);
}

static void check_svg(const char *path)
{
    char *s = slurp(path, NULL);
    CHECK(s != NULL);
    if (s == NULL) {
        fprintf(stderr, "missing %s\n", path);
        return;
    }
    CHECK(strncmp(s, "<?xml", 5) == 0 || strncmp(s, "<svg", 4) == 0);
    const char *open = strstr(s, "<svg");
    CHECK(open != NULL && strstr(open, "</svg>") != NULL);
    CHECK(strlen(s) > 2000);
    free(s);
}

/* Removes what an earlier run of this test left in `dir`. */
static void clean(const char *dir)
{
    char path[512];
    for (size_t i = 0; all_figs[i]; i++) {
        snprintf(path, sizeof path, "%s/plots/%s.png", dir, all_figs[i]);
        remove(path);
        snprintf(path, sizeof path, "%s/plots/%s.svg", dir, all_figs[i]);
        remove(path);
    }
    snprintf(path, sizeof path, "%s/plots/fig10_normalised.csv", dir);
    remove(path);
    snprintf(path, sizeof path, "%s/plots", dir);
    remove(path);
    snprintf(path, sizeof path, "%s/index.html", dir);
    remove(path);
}

static int exists(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0;
}

/* Runs `mission` into `outdir`, plots it, checks the files; returns the plotting time in ms. */
static double run_and_plot(const char *mission, const char *outdir, int flat,
                           const char *const *skipped)
{
    char path[4096];
    const char *root = getenv("LV_SOURCE_DIR");
    snprintf(path, sizeof path, "%s/%s", root ? root : "..", mission);
    lv_err err = {0};
    lv_mission *m = NULL;
    CHECK_OK(lv_mission_load(path, &m, &err), &err);
    if (m == NULL)
        return 0.0;
    lv_run_options opt = {.outdir = outdir, .threads = 1};
    lv_run *run = NULL;
    CHECK_OK(lv_run_create(m, &run, &err), &err);
    CHECK_OK(lv_run_execute(run, &opt, &err), &err);
    CHECK_OK(lv_run_write_summary(run, outdir, &err), &err);
    lv_run_free(run);

    /* The library prints nothing: stdout and stderr go to a file while plotting. */
    char quiet[4200];
    snprintf(quiet, sizeof quiet, "%s.stdio", outdir);
    fflush(stdout);
    fflush(stderr);
    int out_fd = dup(1), err_fd = dup(2);
    FILE *q = fopen(quiet, "w");
    CHECK(q != NULL && out_fd >= 0 && err_fd >= 0);
    if (q != NULL) {
        dup2(fileno(q), 1);
        dup2(fileno(q), 2);
    }
    PLINT strm_before = -1, strm_after = -2;
    plgstrm(&strm_before);
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    lv_status st = lv_plot_run(outdir, &err);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    plgstrm(&strm_after);
    fflush(stdout);
    fflush(stderr);
    dup2(out_fd, 1);
    dup2(err_fd, 2);
    close(out_fd);
    close(err_fd);
    if (q != NULL)
        fclose(q);
    CHECK_OK(st, &err);
    CHECK(strm_before == strm_after);
    size_t said = 0;
    char *text = slurp(quiet, &said);
    CHECK(text != NULL && said == 0);
    if (said > 0)
        fprintf(stderr, "printed while plotting: %s\n", text);
    free(text);
    remove(quiet);

    for (size_t i = 0; all_figs[i]; i++) {
        const int expect = !in_list(skipped, all_figs[i]);
        snprintf(path, sizeof path, "%s/plots/%s.png", outdir, all_figs[i]);
        CHECK(exists(path) == expect);
        if (exists(path) != expect)
            fprintf(stderr, "%s: expected %s\n", path, expect ? "a file" : "no file");
        if (expect)
            check_png(path, 12000);
        snprintf(path, sizeof path, "%s/plots/%s.svg", outdir, all_figs[i]);
        CHECK(exists(path) == expect);
        if (expect)
            check_svg(path);
        snprintf(path, sizeof path, "%s/plots/%s.png.tmp", outdir, all_figs[i]);
        CHECK(!exists(path));
    }

    snprintf(path, sizeof path, "%s/index.html", outdir);
    char *html = slurp(path, NULL);
    CHECK(html != NULL);
    if (html != NULL) {
        CHECK(strncmp(html, "<!DOCTYPE html>", 15) == 0 && strstr(html, "</html>") != NULL);
        CHECK(strstr(html, lv_mission_name(m)) != NULL);
        for (size_t k = 0; k < lv_mission_phase_count(m); k++) {
            char cell[256];
            snprintf(cell, sizeof cell, "<td class=\"l\">%s</td>", lv_mission_phase_name(m, k));
            CHECK(strstr(html, cell) != NULL);
        }
        for (size_t i = 0; all_figs[i]; i++) {
            const int expect = !in_list(skipped, all_figs[i]);
            char img[128], svg[128], skip[128];
            snprintf(img, sizeof img, "<img src=\"plots/%s.png\"", all_figs[i]);
            snprintf(svg, sizeof svg, "href=\"plots/%s.svg\"", all_figs[i]);
            snprintf(skip, sizeof skip, "<li><code>%s</code>: ", all_figs[i]);
            CHECK((strstr(html, img) != NULL) == expect);
            CHECK((strstr(html, svg) != NULL) == expect);
            CHECK((strstr(html, skip) != NULL) == !expect);
        }
        CHECK(strstr(html, "href=\"viewer/index.html\"") != NULL);
        CHECK(strstr(html, "lvsim view") != NULL && strstr(html, "file://") != NULL);
        /* key figures first, Figure 10 the first figure */
        const char *keys = strstr(html, "<h2 id=\"keys\">Key figures</h2>");
        const char *fig = strstr(html, "<img src=\"plots/");
        CHECK(keys != NULL && fig != NULL && keys < strstr(html, "<h2 id=\"phases\">"));
        static const char fig10[] = "<img src=\"plots/fig10_normalised.png\"";
        CHECK(fig != NULL && strncmp(fig, fig10, sizeof fig10 - 1) == 0);
        CHECK(strstr(html, "href=\"summary.json\"") != NULL);
        CHECK(strstr(html, ".mat\"") != NULL && strstr(html, "href=\"body_") != NULL);
        CHECK(strstr(html, "burnout") != NULL); /* end reasons and the event list */
        if (flat) /* the flat world has no inertial speed: the report says why */
            CHECK(strstr(html, "inertial curve not drawn") != NULL);
    }
    free(html);
    lv_mission_free(m);
    return 1e3 * ((double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec));
}

/* plots/fig10_normalised.csv of a run: v_norm = v / v_max and m_norm = m / m_0 with one
 * v_max and one m_0 for every body: the largest v_norm is 1 exactly and none exceeds it, every
 * body (all start in one stack in these examples) starts at m_norm 1, times do not go back.
 * With `rlv`, the seven-phase launcher's numbers: m_0 = 401 t, the upper stage's share at the
 * separation 66 t / 401 t, the stack's mass the sum of its parts' there, and every body's speed
 * continuous across each boundary (a 1 m/s separation impulse at most). */
typedef struct f10_row {
    double t, v, m;
    char body[32], phase[32];
} f10_row;

static void check_fig10_csv(const char *outdir, int rlv)
{
    char path[512], line[512];
    snprintf(path, sizeof path, "%s/plots/fig10_normalised.csv", outdir);
    FILE *f = fopen(path, "r");
    CHECK(f != NULL);
    if (f == NULL)
        return;
    double v_max = NAN, m_0 = NAN;
    CHECK(fgets(line, sizeof line, f) != NULL &&
          sscanf(line, "# the paper's Figure 10: v_norm = speed / v_max, m_norm = m / m_0; "
                       "v_max = %lf m/s, m_0 = %lf kg", &v_max, &m_0) == 2);
    CHECK(v_max > 0.0 && m_0 > 0.0);
    CHECK(fgets(line, sizeof line, f) != NULL &&
          strcmp(line, "time [s],body,phase,v_norm,m_norm\n") == 0);
    size_t n = 0, cap = 4096;
    f10_row *rows = malloc(cap * sizeof *rows);
    CHECK(rows != NULL);
    while (rows != NULL && fgets(line, sizeof line, f) != NULL) {
        if (n == cap) {
            f10_row *r = realloc(rows, 2 * cap * sizeof *rows);
            CHECK(r != NULL);
            if (r == NULL)
                break;
            rows = r;
            cap *= 2;
        }
        f10_row *r = &rows[n];
        CHECK(sscanf(line, "%lf,%31[^,],%31[^,],%lf,%lf", &r->t, r->body, r->phase, &r->v,
                     &r->m) == 5);
        n++;
    }
    fclose(f);
    CHECK(n > 10);
    double v_top = -1.0;
    for (size_t i = 0; rows != NULL && i < n; i++) {
        v_top = fmax(v_top, rows[i].v);
        CHECK(rows[i].v >= 0.0 && rows[i].v <= 1.0);
        CHECK(rows[i].m > 0.0 && rows[i].m <= 1.0);
        const int first = i == 0 || strcmp(rows[i].body, rows[i - 1].body) != 0;
        if (first)
            CHECK(rows[i].m == 1.0);
        else
            CHECK(rows[i].t >= rows[i - 1].t);
        /* a phase boundary of the same body: speed continuous */
        if (!first && strcmp(rows[i].phase, rows[i - 1].phase) != 0) {
            CHECK(rows[i].t == rows[i - 1].t);
            CHECK(fabs(rows[i].v - rows[i - 1].v) <= 1.01 / v_max + 1e-12);
            if (fabs(rows[i].v - rows[i - 1].v) > 1.01 / v_max + 1e-12)
                fprintf(stderr, "%s: %s -> %s at %g s: v_norm %.9g -> %.9g\n", rows[i].body,
                        rows[i - 1].phase, rows[i].phase, rows[i].t, rows[i - 1].v, rows[i].v);
        }
    }
    CHECK(v_top == 1.0);
    if (rlv && rows != NULL) {
        CHECK(m_0 == 401000.0);
        double m_stack = NAN, m_us = NAN, m_ms = NAN;
        for (size_t i = 0; i < n; i++) {
            if (strcmp(rows[i].body, "ms") == 0 && strcmp(rows[i].phase, "ballistic") == 0)
                m_stack = rows[i].m; /* its last row: the separation state */
            if (isnan(m_us) && strcmp(rows[i].body, "us") == 0 &&
                strcmp(rows[i].phase, "us-ascent") == 0)
                m_us = rows[i].m;
            if (isnan(m_ms) && strcmp(rows[i].body, "ms") == 0 &&
                strcmp(rows[i].phase, "turn-around") == 0)
                m_ms = rows[i].m;
        }
        CHECK(fabs(m_us - 66000.0 / 401000.0) < 1e-12);
        CHECK(fabs(m_stack - (m_us + m_ms)) < 1e-9);
        CHECK(m_ms > 0.25 && m_ms < 0.35); /* the MS with its reserve: ~120 t */
    }
    free(rows);
}

/* A hand-made output directory: hostile names are escaped, bad files give file and line. */
static void test_errors_and_escaping(void)
{
    const char *dir = "plot_hand";
    char path[512];
    lv_err err = {0};
    mkdir(dir, 0777);
    remove("plot_hand/summary.json");
    CHECK_FAILS(lv_plot_run(dir, &err), &err, LV_ERR_IO, "plot_hand/summary.json");
    CHECK_FAILS(lv_plot_run("plot_no_such_dir", &err), &err, LV_ERR_IO,
                "plot_no_such_dir/summary.json");
    CHECK_FAILS(lv_plot_run("", &err), &err, LV_ERR_INPUT, "no output directory");

    CHECK(write_text("plot_hand/summary.json", "{\n  \"mission\": \"x\",\n  \"phases\": [\n"
                                               "    {\"name\": \"a\",}\n  ]\n}\n"));
    CHECK_FAILS(lv_plot_run(dir, &err), &err, LV_ERR_INPUT, "plot_hand/summary.json:4");

    static const char summary[] =
        "{\"mission\": \"<script>alert('x')</script> & co #u1\", \"epoch\": \"2026-01-01T00:00:00Z\","
        " \"world\": \"flat\", \"file\": \"m.yaml\", \"lvsim\": \"0\",\n"
        " \"phases\": [{\"index\": 1, \"name\": \"up<&>\", \"model\": \"flat6\","
        " \"stages\": [\"s\\\"1\"], \"from\": null, \"state\": \"done\", \"t_start\": 0,"
        " \"t_end\": 2, \"end\": {\"reason\": \"stop_time\", \"value\": 2}, \"events\": [],"
        " \"stats\": {\"steps\": 3, \"rhs_evals\": 9, \"state_events\": 0, \"time_events\": 0,"
        " \"cpu_time\": 0.001}, \"files\": {\"csv\": \"p 1.csv\", \"mat\": \"p 1.mat\"}}],\n"
        " \"bodies\": [{\"name\": \"s\\\"1\", \"phases\": [\"up<&>\"],"
        " \"trajectory\": \"b.csv\"}]}\n";
    CHECK(write_text("plot_hand/summary.json", summary));
    CHECK_FAILS(lv_plot_run(dir, &err), &err, LV_ERR_IO, "plot_hand/p 1.csv");
    CHECK(write_text("plot_hand/p 1.csv", "time [s],z [m],speed [m/s],m [kg]\n"
                                          "0,0,0,100\n1,5,10,90\n2,20,20\n"));
    CHECK_FAILS(lv_plot_run(dir, &err), &err, LV_ERR_INPUT, "plot_hand/p 1.csv:4");
    CHECK(write_text("plot_hand/p 1.csv", "time [s],z [m],speed [m/s],m [kg]\n"
                                          "0,0,0,100\n1,5,10,90\n1,5,10,80\n2,20,20,70\n"));
    CHECK(write_text("plot_hand/b.csv", "time [s],phase,lat [rad],lon [rad]\n"
                                        "0,up,0.1,0.2\n2,up,0.1001,0.2001\n"));
    CHECK_OK(lv_plot_run(dir, &err), &err);
    char *html = slurp("plot_hand/index.html", NULL);
    CHECK(html != NULL);
    if (html != NULL) {
        CHECK(strstr(html, "<script>") == NULL);
        CHECK(strstr(html, "&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt; &amp; co #u1") != NULL);
        CHECK(strstr(html, "up&lt;&amp;&gt;") != NULL && strstr(html, "up<&>") == NULL);
        CHECK(strstr(html, "s&quot;1") != NULL);
        CHECK(strstr(html, "href=\"p%201.csv\"") != NULL);
        CHECK(strstr(html, "<img src=\"plots/altitude.png\"") != NULL);
    }
    free(html);
    snprintf(path, sizeof path, "%s/plots/altitude.png", dir);
    check_png(path, 5000);

    /* An unwritable plots/ (a file of that name): LV_ERR_IO naming it, nothing printed. */
    CHECK(write_text("plot_hand/summary.json", summary));
    clean(dir);
    CHECK(write_text("plot_hand/plots", "not a directory"));
    CHECK_FAILS(lv_plot_run(dir, &err), &err, LV_ERR_IO, "plot_hand/plots");
    remove("plot_hand/plots");
}

/* The vehicle-attitude figures' rule (lv_plot_is_vehicle, docs/visualization.md): a body's
 * curve covers the phases whose bottom stage (the first of `stages`) it is. The two-stage
 * launcher of examples/two-stage-6dof: lift-off and boost carry [booster, upper, payload] (the
 * booster's attitude: one curve, the booster's, not three that coincide), coast and upper burn
 * [upper, payload] (the upper stage's), a fall-back of [booster] alone and a payload released
 * into its own phase: each the vehicle of its phase. */
static void test_vehicle_rule(void)
{
    const char *stack[] = {"booster", "upper", "payload"}, *upper[] = {"upper", "payload"};
    const char *booster[] = {"booster"}, *payload[] = {"payload"};
    lv_results_phase ph[6];
    memset(ph, 0, sizeof ph);
    const char **stages[6] = {stack, stack, upper, upper, booster, payload};
    const size_t n_st[6] = {3, 3, 2, 2, 1, 1};
    for (int k = 0; k < 6; k++) {
        ph[k].stages = stages[k];
        ph[k].n_stages = n_st[k];
    }
    lv_results res;
    memset(&res, 0, sizeof res);
    res.phases = ph;
    res.n_phases = 6;
    lv_plot_phase pp[6];
    memset(pp, 0, sizeof pp);
    lv_plot_body bodies[3];
    memset(bodies, 0, sizeof bodies);
    for (int b = 0; b < 3; b++)
        bodies[b].name = stack[b];
    lv_plot_data d;
    memset(&d, 0, sizeof d);
    d.res = &res;
    d.n_phases = 6;
    d.phases = pp;
    d.n_bodies = 3;
    d.bodies = bodies;
    /* expected[b][k]: body b (booster, upper, payload) is the vehicle of phase k */
    static const int expected[3][6] = {{1, 1, 0, 0, 1, 0}, {0, 0, 1, 1, 0, 0}, {0, 0, 0, 0, 0, 1}};
    for (size_t b = 0; b < 3; b++)
        for (size_t k = 0; k < 6; k++)
            CHECK(lv_plot_is_vehicle(&d, b, k) == expected[b][k]);
    /* every phase has exactly one vehicle: one curve per phase and quantity */
    for (size_t k = 0; k < 6; k++) {
        int n = 0;
        for (size_t b = 0; b < 3; b++)
            n += lv_plot_is_vehicle(&d, b, k);
        CHECK(n == 1);
    }
    CHECK(!lv_plot_is_vehicle(&d, 3, 0) && !lv_plot_is_vehicle(&d, 0, 6)); /* out of range */
}

int main(void)
{
    clean("plot_paper");
    clean("plot_dof3");
    clean("plot_rlv");
    clean("plot_hand");
    remove("plot_hand/p 1.csv");
    remove("plot_hand/b.csv");
    double ms_paper =
        run_and_plot("examples/paper-test-case/mission.yaml", "plot_paper", 1, flat_skipped);
    double ms_dof3 =
        run_and_plot("examples/dof3-branch/mission.yaml", "plot_dof3", 0, dof3_skipped);
    double ms_rlv = run_and_plot("examples/rlv-hthl/mission.yaml", "plot_rlv", 0, rlv_skipped);
    printf("lv_plot_run: paper-test-case %.0f ms, dof3-branch %.0f ms, rlv-hthl %.0f ms\n",
           ms_paper, ms_dof3, ms_rlv);
    check_fig10_csv("plot_paper", 0);
    check_fig10_csv("plot_dof3", 0);
    check_fig10_csv("plot_rlv", 1);
    test_errors_and_escaping();
    test_vehicle_rule();
    return check_report("test_plot");
}
