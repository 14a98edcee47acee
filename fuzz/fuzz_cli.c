/* fuzz_cli.c - libFuzzer target: the lvsim command line, every command's argument parsing and
 * what it checks before it works (cli/cmd_*.c, through cli_main of cli/main.c, which returns the
 * exit code and never exits). The arguments are the input's lines; the files they can name are
 * the fixtures of a private temporary folder, the working directory during the call: a small
 * mission with a `targeting:` and a `dispersions:` section (m.yaml), one without air that
 * `lvsim compare` takes (e.yaml), a results folder with a staged viewer (out/), a table
 * (t.csv). Any command line must give an exit code of docs/cli.md (0, 1, 2, 3, 130), never a
 * crash, a leak, a hang or a sanitizer report.
 *
 * What would run long, write, or leave the process is replaced at link time (-Wl,--wrap,
 * fuzz/fuzz.cmake) by a failure saying so: results folders (lv_outdir_begin, lv_outdir_open),
 * campaigns, targeting solves, FMU exports, plots, exports, `lvsim view`'s socket (bind) and
 * child processes (fork, execv). lv_run_execute runs for real when it writes no files (run
 * --outputs none), lv_mission_compare with the phases' own output grid or one of at least
 * 0.1 s, lv_simulate with no result file and at most 5000 steps and 500 output intervals.
 * Arguments that start with '/' or contain ".." are not tried: nothing outside the folder.
 * Seeds: fuzz/corpus/cli (fuzz/make_seeds.sh). `make fuzz` (run with -close_fd_mask=3). */
#define _POSIX_C_SOURCE 200809L

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "core/status.h"
#include "lvsim/lv_campaign.h"
#include "lvsim/lv_export.h"
#include "lvsim/lv_fmu.h"
#include "lvsim/lv_mission.h"
#include "lvsim/lv_outdir.h"
#include "lvsim/lv_plot.h"
#include "lvsim/lv_sim.h"
#include "lvsim/lv_target.h"

#ifndef LV_FUZZ_DIR
#error "LV_FUZZ_DIR: the source tree (its data/ folder: the gravity coefficients)"
#endif

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* ---- what the commands may not do here ---------------------------------------------------- */

#define WRAP_FAIL(err, fn)                                                                   \
    lv_fail((err), LV_ERR_INPUT, "fuzz_cli: %s is not run under the fuzzer", fn)

lv_status __wrap_lv_outdir_begin(const char *outdir, const char *mission_file, unsigned flags,
                                 lv_outdir **out, lv_err *err);
lv_status __wrap_lv_outdir_begin(const char *outdir, const char *mission_file, unsigned flags,
                                 lv_outdir **out, lv_err *err)
{
    (void)outdir, (void)mission_file, (void)flags;
    *out = NULL;
    return WRAP_FAIL(err, "lv_outdir_begin");
}

lv_status __wrap_lv_outdir_open_live(const char *outdir, const char *mission_file,
                                     unsigned flags, const char *const *live, lv_outdir **out,
                                     lv_err *err);
lv_status __wrap_lv_outdir_open_live(const char *outdir, const char *mission_file,
                                     unsigned flags, const char *const *live, lv_outdir **out,
                                     lv_err *err)
{
    (void)outdir, (void)mission_file, (void)flags, (void)live;
    *out = NULL;
    return WRAP_FAIL(err, "lv_outdir_open_live");
}

lv_status __wrap_lv_outdir_open(const char *outdir, lv_outdir **out, lv_err *err);
lv_status __wrap_lv_outdir_open(const char *outdir, lv_outdir **out, lv_err *err)
{
    (void)outdir;
    *out = NULL;
    return WRAP_FAIL(err, "lv_outdir_open");
}

lv_status __wrap_lv_campaign_run(const lv_mission *m, const lv_campaign_options *o,
                                 lv_campaign_progress *out, lv_err *err);
lv_status __wrap_lv_campaign_run(const lv_mission *m, const lv_campaign_options *o,
                                 lv_campaign_progress *out, lv_err *err)
{
    (void)m, (void)o;
    if (out != NULL)
        memset(out, 0, sizeof *out);
    return WRAP_FAIL(err, "lv_campaign_run");
}

lv_status __wrap_lv_target_solve(lv_target *t, const lv_target_settings *s,
                                 const lv_target_result **out, lv_err *err);
lv_status __wrap_lv_target_solve(lv_target *t, const lv_target_settings *s,
                                 const lv_target_result **out, lv_err *err)
{
    (void)t, (void)s;
    *out = NULL;
    return WRAP_FAIL(err, "lv_target_solve");
}

lv_status __wrap_lv_fmu_export(const char *mission_path, const char *phase, const char *fmu_path,
                               const lv_fmu_options *opt, lv_fmu_info *info, lv_err *err);
lv_status __wrap_lv_fmu_export(const char *mission_path, const char *phase, const char *fmu_path,
                               const lv_fmu_options *opt, lv_fmu_info *info, lv_err *err)
{
    (void)mission_path, (void)phase, (void)fmu_path, (void)opt;
    if (info != NULL)
        memset(info, 0, sizeof *info);
    return WRAP_FAIL(err, "lv_fmu_export");
}

lv_status __wrap_lv_plot_run(const char *outdir, lv_err *err);
lv_status __wrap_lv_plot_run(const char *outdir, lv_err *err)
{
    (void)outdir;
    return WRAP_FAIL(err, "lv_plot_run");
}

lv_status __wrap_lv_export_run(const char *outdir, unsigned formats, lv_err *err);
lv_status __wrap_lv_export_run(const char *outdir, unsigned formats, lv_err *err)
{
    (void)outdir, (void)formats;
    return WRAP_FAIL(err, "lv_export_run");
}

lv_status __wrap_lv_export_run_report(const char *outdir, unsigned formats, lv_export_report *rep,
                                      lv_err *err);
lv_status __wrap_lv_export_run_report(const char *outdir, unsigned formats, lv_export_report *rep,
                                      lv_err *err)
{
    (void)outdir, (void)formats;
    if (rep != NULL)
        memset(rep, 0, sizeof *rep);
    return WRAP_FAIL(err, "lv_export_run_report");
}

lv_status __real_lv_run_execute(lv_run *r, const lv_run_options *opt, lv_err *err);
lv_status __wrap_lv_run_execute(lv_run *r, const lv_run_options *opt, lv_err *err);
lv_status __wrap_lv_run_execute(lv_run *r, const lv_run_options *opt, lv_err *err)
{
    if (opt != NULL && opt->outdir == NULL) /* no files: the fixture's mission, a few ms */
        return __real_lv_run_execute(r, opt, err);
    return WRAP_FAIL(err, "lv_run_execute with a results folder");
}

lv_status __real_lv_mission_compare(const lv_mission *m, const char *method, double tolerance,
                                    double dt, double max_rows, lv_compare_report *rep,
                                    lv_err *err);
lv_status __wrap_lv_mission_compare(const lv_mission *m, const char *method, double tolerance,
                                    double dt, double max_rows, lv_compare_report *rep,
                                    lv_err *err);
lv_status __wrap_lv_mission_compare(const lv_mission *m, const char *method, double tolerance,
                                    double dt, double max_rows, lv_compare_report *rep,
                                    lv_err *err)
{
    if ((dt == 0.0 || dt >= 0.1) && (tolerance == 0.0 || tolerance >= 1e-10))
        return __real_lv_mission_compare(m, method, tolerance, dt, max_rows, rep, err);
    memset(rep, 0, sizeof *rep);
    return WRAP_FAIL(err, "lv_mission_compare on a fine grid or a tight tolerance");
}

lv_status __real_lv_simulate(const lv_model_def *model, void *inst, const lv_sim_settings *s,
                             double *final_values, lv_sim_report *rep, lv_err *err);
lv_status __wrap_lv_simulate(const lv_model_def *model, void *inst, const lv_sim_settings *s,
                             double *final_values, lv_sim_report *rep, lv_err *err);
lv_status __wrap_lv_simulate(const lv_model_def *model, void *inst, const lv_sim_settings *s,
                             double *final_values, lv_sim_report *rep, lv_err *err)
{
    lv_sim_settings b = *s; /* the command's settings, bounded: no file, a few ms */
    b.result_file = NULL;
    b.result_formats = 0;
    if (b.max_steps <= 0 || b.max_steps > 5000)
        b.max_steps = 5000;
    if (b.number_of_intervals > 500)
        b.number_of_intervals = 500;
    const double span = b.stop_time - b.start_time;
    if (b.output_interval > 0.0 && span > 500.0 * b.output_interval)
        b.output_interval = span / 500.0;
    return __real_lv_simulate(model, inst, &b, final_values, rep, err);
}

lv_status __wrap_lv_campaign_stats(const char *db, const char *outdir, lv_err *err);
lv_status __wrap_lv_campaign_stats(const char *db, const char *outdir, lv_err *err)
{
    (void)db, (void)outdir;
    return WRAP_FAIL(err, "lv_campaign_stats");
}

lv_status __wrap_lv_campaign_plot(const char *db, const char *outdir, lv_err *err);
lv_status __wrap_lv_campaign_plot(const char *db, const char *outdir, lv_err *err)
{
    (void)db, (void)outdir;
    return WRAP_FAIL(err, "lv_campaign_plot");
}

int __wrap_bind(int fd, const struct sockaddr *a, socklen_t len);
int __wrap_bind(int fd, const struct sockaddr *a, socklen_t len)
{
    (void)fd, (void)a, (void)len;
    errno = EADDRINUSE;
    return -1;
}

pid_t __wrap_fork(void);
pid_t __wrap_fork(void)
{
    errno = EAGAIN;
    return -1;
}

int __wrap_execv(const char *path, char *const argv[]);
int __wrap_execv(const char *path, char *const argv[])
{
    (void)path, (void)argv;
    errno = ENOENT;
    return -1;
}

/* ---- the folder -------------------------------------------------------------------------- */

static char dir[4200];
static int home = -1; /* the working directory before (libFuzzer's relative paths) */

static const char mission_yaml[] =
    "# the fuzzer's mission: two flat-world phases, a targeting and a dispersions section\n"
    "mission: {name: fuzz}\n"
    "environment: {world: flat, atmosphere: us76}\n"
    "parameters: {start_z: 0, start_vel: 10}\n"
    "stages:\n"
    "  - {name: s, dry_mass: 100, propellant_mass: 20,\n"
    "     engines: [{name: e, thrust_vac: 3000, isp_vac: 250}]}\n"
    "phases:\n"
    "  - {name: burn, model: flat6, stages: [s], stop_time: 5, end: [burnout],\n"
    "     aero: {s_ref: 0.03, CD: t.csv}, integrator: {output_interval: 0.5}}\n"
    "  - {name: coast, model: flat6, stages: [s], from: burn, stop_time: 60, end: [apogee],\n"
    "     integrator: {output_interval: 1}}\n"
    "targeting:\n"
    "  variables: [{name: start_vel, min: 0, max: 100}]\n"
    "  constraints: [{final: coast.z, max: 1000, tolerance: 1}]\n"
    "dispersions:\n"
    "  seed: 7\n"
    "  parameters: {s.dry_mass: {dist: normal, sigma: 1}}\n";
/* the same without air: what `lvsim compare` accepts (its end-to-end model has none) */
static const char mission_e2e_yaml[] =
    "mission: {name: fuzz-e2e}\n"
    "parameters: {start_z: 0, start_vel: 10}\n"
    "stages:\n"
    "  - {name: s1, dry_mass: 100, propellant_mass: 20,\n"
    "     engines: [{name: e1, thrust_vac: 5000, isp_vac: 250}]}\n"
    "  - {name: s2, dry_mass: 50, propellant_mass: 10,\n"
    "     engines: [{name: e2, thrust_vac: 1000, isp_vac: 300}]}\n"
    "phases:\n"
    "  - {name: burn1, model: flat6, stages: [s1, s2], stop_time: 20, end: [burnout]}\n"
    "  - {name: burn2, model: flat6, stages: [s2], from: burn1, stop_time: 60, end: [burnout]}\n"
    "  - {name: fall, model: flat6, stages: [s1], from: burn1, stop_time: 200, end: [impact]}\n";
static const char table_csv[] = "mach [1], CD [1]\n0, 0.3\n1, 0.5\n5, 0.25\n";

/* The fixtures: every other entry of the folder (and of out/) is removed after each input. */
static const char *const fixtures[] = {"m.yaml", "e.yaml", "t.csv", "out", NULL};
static const char *const out_fixtures[] = {"summary.json", "mission.czml", "viewer", NULL};

static void put(const char *path, const char *text)
{
    FILE *fp = fopen(path, "w");
    if (fp == NULL || fputs(text, fp) == EOF || fclose(fp) != 0) {
        perror(path);
        abort();
    }
}

static void remove_tree(const char *p)
{
    struct stat sb;
    if (lstat(p, &sb) != 0)
        return;
    if (S_ISDIR(sb.st_mode)) {
        DIR *dp = opendir(p);
        struct dirent *e;
        char q[4200];
        while (dp != NULL && (e = readdir(dp)) != NULL) {
            if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
                continue;
            snprintf(q, sizeof q, "%s/%s", p, e->d_name);
            remove_tree(q);
        }
        if (dp != NULL)
            closedir(dp);
        rmdir(p);
    } else {
        unlink(p);
    }
}

/* Removes what is not a fixture from folder `d`. */
static void prune(const char *d, const char *const *keep)
{
    DIR *dp = opendir(d);
    if (dp == NULL)
        return;
    struct dirent *e;
    char q[4200];
    while ((e = readdir(dp)) != NULL) {
        int fixed = strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0;
        for (size_t i = 0; keep[i] != NULL && !fixed; i++)
            fixed = strcmp(e->d_name, keep[i]) == 0;
        if (!fixed) {
            snprintf(q, sizeof q, "%s/%s", d, e->d_name);
            remove_tree(q);
        }
    }
    closedir(dp);
}

static void cleanup(void)
{
    if (home >= 0 && fchdir(home) != 0)
        return;
    remove_tree(dir);
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    const char *tmp = getenv("TMPDIR");
    snprintf(dir, sizeof dir, "%s/lvsim-fuzz-cli-XXXXXX",
             tmp != NULL && tmp[0] != '\0' && strlen(tmp) < 4096 ? tmp : "/tmp");
    if (mkdtemp(dir) == NULL || (home = open(".", O_RDONLY | O_DIRECTORY)) < 0 ||
        chdir(dir) != 0) {
        perror("fuzz_cli: the temporary folder");
        abort();
    }
    put("m.yaml", mission_yaml);
    put("e.yaml", mission_e2e_yaml);
    put("t.csv", table_csv);
    if (mkdir("out", 0777) != 0 || mkdir("out/viewer", 0777) != 0) {
        perror("fuzz_cli: out/");
        abort();
    }
    put("out/summary.json", "{\"mission\": \"fuzz\", \"phases\": [], \"bodies\": []}\n");
    put("out/mission.czml", "[]\n");
    put("out/viewer/VERSION", "lvsim viewer, CesiumJS 0.0.0\n");
    if (fchdir(home) != 0)
        abort();
    atexit(cleanup);
    /* the gravity coefficients of `lvsim gravity --model sh` (read only) */
    setenv("LVSIM_DATA", LV_FUZZ_DIR "/data", 1);
    return 0;
}

#define MAX_ARGS 24

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (memchr(data, '\0', size) != NULL) /* a NUL cannot be in an argument */
        return 0;
    char *text = malloc(size + 1);
    if (text == NULL)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    char *argv[MAX_ARGS + 2] = {"lvsim"};
    int argc = 1;
    for (char *p = text; argc <= MAX_ARGS;) { /* one argument per line */
        char *nl = strchr(p, '\n');
        if (nl != NULL)
            *nl = '\0';
        if (p[0] == '/' || strstr(p, "..") != NULL) { /* nothing outside the folder */
            free(text);
            return 0;
        }
        argv[argc++] = p;
        if (nl == NULL)
            break;
        p = nl + 1;
    }
    argv[argc] = NULL;
    struct sigaction old_int, old_term;
    sigaction(SIGINT, NULL, &old_int);
    sigaction(SIGTERM, NULL, &old_term);
    if (chdir(dir) != 0)
        abort();
    const int code = cli_main(argc, argv);
    fflush(stdout);
    fflush(stderr);
    prune(".", fixtures);
    prune("out", out_fixtures);
    if (fchdir(home) != 0)
        abort();
    sigaction(SIGINT, &old_int, NULL);
    sigaction(SIGTERM, &old_term, NULL);
    free(text);
    if (code != 0 && code != 1 && code != 2 && code != 3 && code != 130)
        __builtin_trap();
    return 0;
}
