/* test_campaign.c - Monte Carlo dispersions and campaigns (issue 16) against known answers:
 *  - the generator: Philox4x32-10's known-answer vector, the inverse normal CDF against erfc;
 *  - one stream per parameter: a parameter's draws do not change when others are added;
 *  - a correlated pair (normal x normal: Pearson; uniform, truncated normal: the Gaussian
 *    copula's latent normals) reproduces the file's correlation within 4 standard errors;
 *  - the analytic Isp scatter: a drag-free vertical ascent in uniform gravity with constant
 *    thrust F has the burnout speed v_b = Isp g0 ln(m0/m_f) - g t_b, t_b = m_p Isp g0 / F, so
 *    v_b = K Isp with K = g0 (ln(m0/m_f) - g m_p / F): Isp ~ N(mu, s) gives v_b ~ N(K mu, K s)
 *    exactly (docs/monte-carlo.md, "Checks"); the campaign's sample mean and standard deviation
 *    agree within 4 standard errors (SE of the mean K s / sqrt(n), of the standard deviation
 *    K s / sqrt(2 (n - 1)));
 *  - a table dispersion: an engine table scaled by f (thrust and mass flow) burns for t_b / f;
 *  - bad `dispersions:` inputs give file:line:column. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <Random123/philox.h>

#include "check.h"
#include "lvsim/lv_campaign.h"
#include "lvsim/lv_dispersion.h"
#include "lvsim/lv_mission.h"

static char dir_buf[4096];
static const char *mc_dir(void)
{
    const char *root = getenv("LV_SOURCE_DIR");
    snprintf(dir_buf, sizeof dir_buf, "%s/tests/missions/mc", root ? root : "../..");
    return dir_buf;
}

static lv_mission *load(const char *name)
{
    char path[4200];
    lv_mission *m = NULL;
    lv_err err;
    snprintf(path, sizeof path, "%s/%s", mc_dir(), name);
    CHECK_OK(lv_mission_load(path, &m, &err), &err);
    return m;
}

static double phi(double x) { return 0.5 * erfc(-x / sqrt(2.0)); }

static void test_generator(void)
{
    /* Random123's known answer: philox4x32-10, counter 0, key 0 (kat_vectors) */
    const philox4x32_ctr_t c = { { 0, 0, 0, 0 } };
    const philox4x32_key_t k = { { 0, 0 } };
    const philox4x32_ctr_t r = philox4x32(c, k);
    CHECK(r.v[0] == 0x6627e8d5u && r.v[1] == 0xe169c58du && r.v[2] == 0xbc57ac4cu &&
          r.v[3] == 0x9b00dbd8u);
    /* AS 241 against erfc: Phi(Phi^-1(p)) = p */
    for (int i = 1; i < 400; i++) {
        const double p = pow(10.0, -15.0 + 15.0 * i / 400.0) * 0.999;
        const double z = lv_disp_norm_inv(p);
        CHECK_REL(phi(z), p, 1e-12);
        if (p >= 1e-3) /* 1 - p is exact enough there */
            CHECK_CLOSE(lv_disp_norm_inv(1.0 - p), -z, 1e-12 * fmax(1.0, fabs(z)));
    }
    CHECK_CLOSE(lv_disp_norm_inv(0.975), 1.959963984540054, 1e-14);
    /* uniforms in (0, 1), mean 1/2, variance 1/12 */
    double s = 0, ss = 0;
    const int n = 100000;
    for (int i = 0; i < n; i++) {
        const double u = lv_disp_uniform(42, lv_disp_stream("x"), (uint64_t)i);
        CHECK(u > 0.0 && u < 1.0);
        s += u;
        ss += u * u;
    }
    CHECK_CLOSE(s / n, 0.5, 4.0 * sqrt(1.0 / 12.0 / n));
    CHECK_CLOSE(ss / n - (s / n) * (s / n), 1.0 / 12.0, 4.0 * sqrt(1.0 / 180.0 / n));
}

/* Writes `text` to a temporary mission file next to the test missions' tables. */
static lv_status load_text(const char *text, lv_mission **m, lv_err *err)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/tmp_%ld.yaml", mc_dir(), (long)getpid());
    FILE *f = fopen(path, "w");
    if (f == NULL)
        return LV_ERR_IO;
    fputs(text, f);
    fclose(f);
    lv_status st = lv_mission_load(path, m, err);
    remove(path);
    return st;
}

static const char *base_mission =
    "mission: {name: t}\n"
    "environment: {world: flat, g: 9.81}\n"
    "parameters: {start_theta_deg: 90, start_x: 0}\n"
    "stages:\n"
    "  - name: s1\n"
    "    dry_mass: 1000\n"
    "    propellant_mass: 4000\n"
    "    engines: [{name: e1, thrust_vac: 100000, isp_vac: 300}]\n"
    "phases:\n"
    "  - {name: burn, model: flat6, stages: [s1], stop_time: 200, end: [burnout]}\n";

static void test_streams(void)
{
    char a[4096], b[4096];
    snprintf(a, sizeof a, "%sdispersions:\n  parameters:\n"
             "    e1.isp_vac: {dist: normal, sigma: 6}\n", base_mission);
    snprintf(b, sizeof b, "%sdispersions:\n  parameters:\n"
             "    s1.dry_mass: {dist: uniform, half_width: 10}\n"
             "    e1.isp_vac: {dist: normal, sigma: 6}\n"
             "    start_x: {dist: normal, sigma: 1}\n", base_mission);
    lv_mission *ma = NULL, *mb = NULL;
    lv_err err;
    CHECK_OK(load_text(a, &ma, &err), &err);
    CHECK_OK(load_text(b, &mb, &err), &err);
    if (ma == NULL || mb == NULL)
        return;
    CHECK(lv_mission_disp_count(ma) == 1 && lv_mission_disp_count(mb) == 3);
    for (uint64_t i = 0; i < 1000; i++) {
        double va[1], vb[3];
        lv_mission_disp_draw(ma, 99, i, va);
        lv_mission_disp_draw(mb, 99, i, vb);
        CHECK(memcmp(&va[0], &vb[1], sizeof va[0]) == 0); /* bit for bit */
    }
    /* a draw set on a run, read back */
    lv_run *r = NULL;
    double v[1], got;
    CHECK_OK(lv_run_create(ma, &r, &err), &err);
    CHECK_OK(lv_run_disperse(r, 5, 17, v, &err), &err);
    CHECK_OK(lv_run_get(r, "e1.isp_vac", &got, &err), &err);
    CHECK(got == v[0]);
    lv_run_free(r);
    lv_mission_free(ma);
    lv_mission_free(mb);
}

/* Sample correlation of latent normals, within 4 standard errors (1 - rho^2) / sqrt(n). */
static void test_correlation(void)
{
    lv_mission *m = load("correlated.yaml");
    if (m == NULL)
        return;
    const size_t n = 20000, nd = lv_mission_disp_count(m);
    CHECK(nd == 5);
    double *x = malloc(n * nd * sizeof *x);
    lv_disp_info in[5];
    for (size_t j = 0; j < nd; j++)
        lv_mission_disp_info(m, j, &in[j]);
    for (size_t i = 0; i < n; i++)
        lv_mission_disp_draw(m, 7, i, x + i * nd);
    /* to latent normals: normal marginals standardised; uniform and truncated normal through
     * their CDFs and Phi^-1 (the Gaussian copula's definition) */
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < nd; j++) {
            double *v = &x[i * nd + j];
            const lv_disp_info *d = &in[j];
            const double f = d->relative ? *v / d->nominal : *v;
            if (d->kind == LV_DIST_NORMAL) {
                *v = (f - d->mean) / d->sigma;
            } else if (d->kind == LV_DIST_UNIFORM) {
                *v = lv_disp_norm_inv((f - d->min) / (d->max - d->min));
            } else {
                const double pa = phi((d->min - d->mean) / d->sigma);
                const double pb = phi((d->max - d->mean) / d->sigma);
                *v = lv_disp_norm_inv((phi((f - d->mean) / d->sigma) - pa) / (pb - pa));
            }
        }
    for (size_t a = 0; a < nd; a++)
        for (size_t b = a + 1; b < nd; b++) {
            double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
            for (size_t i = 0; i < n; i++) {
                const double p = x[i * nd + a], q = x[i * nd + b];
                sa += p, sb += q, saa += p * p, sbb += q * q, sab += p * q;
            }
            const double dn = (double)n;
            const double cov = sab / dn - sa / dn * sb / dn;
            const double r =
                cov / sqrt((saa / dn - sa / dn * sa / dn) * (sbb / dn - sb / dn * sb / dn));
            const double rho = lv_mission_disp_correlation(m, a, b);
            const double se = (1.0 - rho * rho) / sqrt((double)n);
            if (!(fabs(r - rho) <= 4.0 * se + 1e-3))
                fprintf(stderr, "correlation %s, %s: %g, want %g\n", in[a].name, in[b].name, r,
                        rho);
            CHECK(fabs(r - rho) <= 4.0 * se + 1e-3);
        }
    /* the marginals: a uniform's mean and bounds, a truncated normal inside its cut */
    for (size_t i = 0; i < n; i++) {
        double v[5];
        lv_mission_disp_draw(m, 7, i, v);
        CHECK(v[2] >= -10.0 && v[2] <= 10.0);
        CHECK(v[3] >= -5.0 && v[3] <= 10.0);
        CHECK(v[4] >= 297.0 && v[4] <= 303.0);
    }
    free(x);
    lv_mission_free(m);
}

static void test_isp_scatter(void)
{
    lv_mission *m = load("isp_scatter.yaml");
    if (m == NULL)
        return;
    const char *db = "test_campaign_isp.db";
    remove(db);
    lv_campaign_options o;
    lv_campaign_options_default(&o);
    o.n_runs = 4000;
    o.threads = 2;
    o.db_path = db;
    CHECK(lv_mission_disp_seed(m, &o.seed) == 1 && o.seed == 2026);
    lv_campaign_progress p;
    lv_err err;
    CHECK_OK(lv_campaign_run(m, &o, &p, &err), &err);
    CHECK(p.done == 4000 && p.failed == 0);
    /* the closed form (the file's numbers) */
    const double g0 = 9.80665, g = 9.81, F = 1e5, m0 = 5000, mf = 1000, mp = 4000;
    const double mu = 300, s = 6;
    const double K = g0 * (log(m0 / mf) - g * mp / F);
    sqlite3 *h = NULL;
    sqlite3_stmt *q = NULL;
    CHECK(sqlite3_open_v2(db, &h, SQLITE_OPEN_READONLY, NULL) == SQLITE_OK);
    CHECK(sqlite3_prepare_v2(h, "SELECT vz, time, r.\"e1.isp_vac\" FROM phase_burn JOIN runs r "
                             "USING (run) WHERE state = 'done' ORDER BY run", -1, &q, NULL) ==
          SQLITE_OK);
    double sum = 0, ss = 0, max_tb = 0;
    size_t n = 0;
    while (q && sqlite3_step(q) == SQLITE_ROW) {
        const double v = sqlite3_column_double(q, 0), t = sqlite3_column_double(q, 1);
        const double isp = sqlite3_column_double(q, 2);
        sum += v;
        ss += v * v;
        n++;
        /* each run on its own: v_b = K Isp, t_b = m_p Isp g0 / F */
        max_tb = fmax(max_tb, fabs(t - mp * isp * g0 / F));
        CHECK_REL(v, K * isp, 1e-6);
    }
    sqlite3_finalize(q);
    sqlite3_close(h);
    CHECK(n == 4000);
    CHECK(max_tb < 1e-6);
    const double dn = (double)n;
    const double mean = sum / dn, sd = sqrt((ss - dn * mean * mean) / (dn - 1.0));
    printf("isp scatter: v_b mean %.3f (closed form %.3f, SE %.3f), sd %.3f (closed form %.3f, "
           "SE %.3f)\n", mean, K * mu, K * s / sqrt(dn), sd, K * s, K * s / sqrt(2.0 * (dn - 1.0)));
    CHECK_CLOSE(mean, K * mu, 4.0 * K * s / sqrt((double)n));
    CHECK_CLOSE(sd, K * s, 4.0 * K * s / sqrt(2.0 * (dn - 1.0)));
    remove(db);
    lv_mission_free(m);
}

/* An engine table scaled by f in thrust and mass flow: Isp unchanged, burn time t_b / f. */
static void test_table_scale(void)
{
    lv_mission *m = load("table_scale.yaml");
    if (m == NULL)
        return;
    lv_run *r = NULL;
    lv_err err;
    CHECK_OK(lv_run_create(m, &r, &err), &err);
    const lv_run_options o = {.threads = 1, .no_rows = 1};
    const double g0 = 9.80665, g = 9.81, F = 1e5, mdot = 30.0, mp = 3000, m0 = 4000, mf = 1000;
    const double isp = F / (mdot * g0);
    for (int i = 0; i < 3; i++) {
        const double f = 0.9 + 0.1 * i;
        CHECK_OK(lv_run_set(r, "e1.table.scale", f, &err), &err);
        CHECK_OK(lv_run_execute(r, &o, &err), &err);
        double t, vz;
        CHECK_OK(lv_run_final(r, 0, "time", &t, &err), &err);
        CHECK_OK(lv_run_final(r, 0, "vz", &vz, &err), &err);
        CHECK_REL(t, mp / (f * mdot), 1e-8);
        CHECK_REL(vz, isp * g0 * log(m0 / mf) - g * mp / (f * mdot), 1e-6);
    }
    /* a thrust bias alone: thrust F + b at the same mass flow */
    CHECK_OK(lv_run_set(r, "e1.table.scale", 1.0, &err), &err);
    CHECK_OK(lv_run_set(r, "e1.table.thrust.bias", 5000.0, &err), &err);
    CHECK_OK(lv_run_execute(r, &o, &err), &err);
    double vz;
    CHECK_OK(lv_run_final(r, 0, "vz", &vz, &err), &err);
    CHECK_REL(vz, (F + 5000.0) / mdot * log(m0 / mf) - g * mp / mdot, 1e-6);
    lv_run_free(r);
    lv_mission_free(m);
}

static void test_bad_inputs(void)
{
    static const struct {
        const char *section; /* appended to the base mission (its line 11 onwards) */
        const char *want;    /* the message's position and text */
    } cases[] = {
        {"dispersions:\n  parameters:\n    e1.isp: {dist: normal, sigma: 1}\n",
         ":13:5: dispersions: no parameter 'e1.isp'; did you mean 'e1.isp_vac'"},
        {"dispersions:\n  parameters:\n    e1.isp_vac: {dist: gauss, sigma: 1}\n",
         ":13:24: dispersions: 'e1.isp_vac': dist: unknown value 'gauss'"},
        {"dispersions:\n  parameters:\n    e1.isp_vac: {dist: normal, sigma: -1}\n",
         ":13:39: dispersions: 'e1.isp_vac': sigma must be >= 0, found -1"},
        {"dispersions:\n  parameters:\n    e1.isp_vac: {dist: normal}\n",
         ":13:17: dispersions: 'e1.isp_vac': missing required key 'sigma'"},
        {"dispersions:\n  parameters:\n    e1.isp_vac: {dist: uniform, min: 5, max: 1}\n",
         ":13:46: dispersions: 'e1.isp_vac': max 1 must be greater than min 5"},
        {"dispersions:\n  parameters:\n    s1.dry_mass: {dist: uniform, min: -5, max: 1}\n",
         ":13:39: dispersions: 's1.dry_mass': the lower bound -5 kg gives s1.dry_mass = -5 kg, "
         "outside its range >= 0"},
        {"dispersions:\n  parameters:\n    e1.isp_vac: {dist: normal, sigma: 1, min: 2}\n",
         ":13:42: dispersions: 'e1.isp_vac': dist normal takes no 'min'"},
        {"dispersions:\n  seed: -3\n  parameters:\n    e1.isp_vac: {dist: normal, sigma: 1}\n",
         ":12:9: dispersions: seed: an integer"},
        {"dispersions:\n  parameters:\n    e1.isp_vac: {dist: normal, sigma: 1}\n"
         "    start_x: {dist: normal, sigma: 1}\n"
         "  correlations:\n    - {parameters: [e1.isp_vac, start_x], rho: 1.5}\n",
         ":16:48: dispersions: correlations #1: rho must lie in (-1, 1), found 1.5"},
        {"dispersions:\n  parameters:\n    e1.isp_vac: {dist: normal, sigma: 1}\n"
         "    start_x: {dist: normal, sigma: 1}\n"
         "    s1.dry_mass: {dist: normal, sigma: 1}\n"
         "  correlations:\n    - parameters: [e1.isp_vac, start_x, s1.dry_mass]\n"
         "      matrix: [[1, 0.9, -0.9], [0.9, 1, 0.9], [-0.9, 0.9, 1]]\n",
         ":18:15: dispersions: correlations #1: the correlation matrix is not positive definite"},
        {"dispersions:\n  parameters:\n    e1.isp_vac: {dist: normal, sigma: 1}\n"
         "  correlations:\n    - {parameters: [e1.isp_vac, start_x], rho: 0.5}\n",
         ":15:33: dispersions: correlations #1: 'start_x' is not dispersed"},
        {"dispersions:\n  parameters:\n    e1.table.scale: {dist: normal, mean: 1, sigma: 1}\n",
         ":13:5: dispersions: 'e1.table.scale': engine 'e1' has no table"},
        {"dispersions:\n  parameters:\n    environment.wind.scale: {dist: normal, sigma: 1}\n",
         ":13:5: dispersions: 'environment.wind.scale': the mission has no wind table"},
        {"dispersions:\n  parmeters: {}\n", ":12:3: dispersions: unknown key 'parmeters'"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char text[8192];
        snprintf(text, sizeof text, "%s%s", base_mission, cases[i].section);
        lv_mission *m = NULL;
        lv_err err;
        err.msg[0] = '\0';
        const lv_status st = load_text(text, &m, &err);
        CHECK(st == LV_ERR_INPUT);
        if (strstr(err.msg, cases[i].want) == NULL)
            fprintf(stderr, "case %zu: got '%s'\n      want '%s'\n", i, err.msg, cases[i].want);
        CHECK(strstr(err.msg, cases[i].want) != NULL);
        lv_mission_free(m);
    }
}

/* The runs to do are the holes between stored runs, handed out in order, whatever n_runs:
 * a campaign of 10^12 runs opens without a list of them (8 TB as uint64). The size estimate
 * is linear in the run count and close to what SQLite stores. */
static void test_todo_and_size(void)
{
    lv_mission *m = load("isp_scatter.yaml");
    if (m == NULL)
        return;
    const char *db = "test_campaign_todo.db";
    remove(db);
    lv_campaign_options o;
    lv_campaign_options_default(&o);
    o.n_runs = 50;
    o.seed = 2026;
    o.db_path = db;
    lv_campaign_progress p;
    lv_err err;
    CHECK_OK(lv_campaign_run(m, &o, &p, &err), &err);
    sqlite3 *h = NULL;
    CHECK(sqlite3_open(db, &h) == SQLITE_OK);
    CHECK(sqlite3_exec(h, "DELETE FROM runs WHERE run IN (0, 1, 7, 8, 9, 30, 49)", NULL, NULL,
                       NULL) == SQLITE_OK);
    sqlite3_close(h);
    o.resume = 1;
    lv_campaign *c = NULL;
    CHECK_OK(lv_campaign_open(m, &o, &c, &err), &err);
    if (c != NULL) {
        static const uint64_t want[] = {0, 1, 7, 8, 9, 30, 49};
        uint64_t got[8];
        size_t n = 0, k;
        CHECK(lv_campaign_todo_count(c) == 7);
        while ((k = lv_campaign_todo_next(c, got + n, n + 3 <= 8 ? 3 : 8 - n)) > 0)
            n += k;
        CHECK(n == 7 && memcmp(got, want, sizeof want) == 0);
        CHECK(lv_campaign_todo_count(c) == 0);
        CHECK_OK(lv_campaign_close(c, &err), &err);
    }
    CHECK_OK(lv_campaign_run(m, &o, &p, &err), &err);
    CHECK(p.done == 50 && p.this_session == 7);
    /* 10^12 runs: nothing of that size is allocated when it opens */
    const char *big = "test_campaign_big.db";
    remove(big);
    lv_campaign_options ob = o;
    ob.resume = 0;
    ob.n_runs = 1000000000000ULL;
    ob.db_path = big;
    c = NULL;
    CHECK_OK(lv_campaign_open(m, &ob, &c, &err), &err);
    if (c != NULL) {
        uint64_t got[4];
        CHECK(lv_campaign_todo_count(c) == 1000000000000ULL);
        CHECK(lv_campaign_todo_next(c, got, 4) == 4 && got[0] == 0 && got[3] == 3);
        CHECK(lv_campaign_todo_count(c) == 1000000000000ULL - 4);
        lv_campaign_close(c, NULL);
        /* its statistics would hold 10^12 runs' values: refused before reading them */
        CHECK(lv_campaign_stats(big, ".", &err) == LV_ERR_INPUT);
        CHECK(strstr(err.msg, "the statistics of its 1e+12 runs would need") != NULL);
    }
    remove(big);
    /* ... but refused before it runs: its database would not fit any disk */
    lv_campaign_size z;
    CHECK(lv_campaign_check_size(m, &ob, 1, &z, &err) == LV_ERR_INPUT);
    CHECK(strstr(err.msg, "a campaign of 1e+12 runs is too large; its database would need "
                          "about") != NULL);
    CHECK(strstr(err.msg, "its statistics would need") != NULL);
    printf("refused: %s\n", err.msg);
    /* the estimate: linear in the runs, and the size SQLite stored for 50 within a factor 2
     * (9 bytes a value, zeros take less) */
    lv_campaign_size z50, z100;
    o.resume = 0;
    CHECK_OK(lv_campaign_estimate(m, &o, &z50, &err), &err);
    o.n_runs = 100;
    CHECK_OK(lv_campaign_estimate(m, &o, &z100, &err), &err);
    CHECK_REL(z100.db_bytes, 2.0 * z50.db_bytes, 1e-12);
    CHECK_REL(z100.stats_bytes, 2.0 * z50.stats_bytes, 1e-12);
    CHECK(z50.rows_per_run == 2.0); /* one phase, start and end rows */
    CHECK(z50.mem_total > 0.0 && z50.disk_free > 0.0);
    CHECK_OK(lv_campaign_check_size(m, &o, 1, NULL, &err), &err);
    FILE *f = fopen(db, "rb");
    long bytes = 0;
    if (f != NULL && fseek(f, 0, SEEK_END) == 0)
        bytes = ftell(f);
    if (f != NULL)
        fclose(f);
    /* the stored size beyond the schema's few pages (measured: 5 pages of 4 kB for 0 runs) */
    const double per_run = ((double)bytes - 5.0 * 4096.0) / 50.0;
    printf("database: %.0f B a run stored, %.0f B estimated\n", per_run, z50.db_bytes / 50.0);
    CHECK(per_run > 0.5 * z50.db_bytes / 50.0 && per_run < 2.0 * z50.db_bytes / 50.0);
    remove(db);
    lv_mission_free(m);
}

int main(void)
{
    test_generator();
    test_streams();
    test_correlation();
    test_isp_scatter();
    test_table_scale();
    test_bad_inputs();
    test_todo_and_size();
    return check_report("test_campaign");
}
