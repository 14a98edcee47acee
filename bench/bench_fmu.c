/* bench_fmu.c - the cost of running a phase as an FMU in Co-Simulation against lv_simulate of
 * the same phase (issue 17). The FMU is exported with `lvsim fmu`, unpacked with unzip and
 * loaded with dlopen, as an importer would.
 *
 *   lv_simulate   the phase's model from lv_run_prepare, its own settings (method, tolerance,
 *                 output grid), no sink: the simulation alone
 *   CS, H         fmi2Reset, fmi2SetupExperiment, initialization, then fmi2DoStep with the
 *                 communication step H until the phase ends (fmi2Discard + fmi2Terminated),
 *                 reading every state with fmi2GetReal after each step as a master would:
 *                 the whole run, measured as one
 *   per step      (CS - lv_simulate) / the number of fmi2DoStep calls
 * fmi2Instantiate (the mission loaded, the ancestors run) is timed apart. Thread CPU time,
 * fastest of the repetitions (a dedicated core is not guaranteed). */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "fmi/fmi2.h"
#include "lvsim/lvsim.h"

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void logger(fmi2ComponentEnvironment env, fmi2String inst, fmi2Status st, fmi2String cat,
                   fmi2String msg, ...)
{
    (void)env, (void)inst, (void)cat;
    if (st < fmi2Error)
        return;
    va_list ap;
    va_start(ap, msg);
    vfprintf(stderr, msg, ap);
    va_end(ap);
    fputc('\n', stderr);
}

typedef struct fmu_fns {
#define LV_FIELD(ret, name, args) name##TYPE *name;
    LV_FMI2_FUNCTIONS(LV_FIELD)
#undef LV_FIELD
} fmu_fns;

/* lv_simulate of phase k without sinks; the number of states. */
static int reference(const char *path, const char *phase, int reps, double *cpu, double *t_end)
{
    lv_err err;
    lv_mission *m = NULL;
    lv_run *r = NULL;
    size_t k;
    if (lv_mission_load(path, &m, &err) != LV_OK || lv_mission_phase_find(m, phase, &k, &err) ||
        lv_run_create(m, &r, &err) != LV_OK) {
        fprintf(stderr, "bench_fmu: %s\n", err.msg);
        return -1;
    }
    const int parent = lv_mission_phase_parent(m, k);
    if (parent >= 0) {
        unsigned char want[64] = {0};
        want[parent] = 1;
        lv_run_options opt = {0};
        opt.no_rows = 1;
        opt.want = want;
        lv_run_execute(r, &opt, &err);
    }
    *cpu = INFINITY;
    for (int i = 0; i < reps; i++) {
        lv_phase_call *c;
        if (lv_run_prepare(r, k, &c, &err) != LV_OK) {
            fprintf(stderr, "bench_fmu: %s\n", err.msg);
            return -1;
        }
        lv_sim_settings s = *lv_phase_call_settings(c);
        s.result_file = NULL;
        s.n_sinks = 0;
        s.sinks = NULL;
        s.n_final = 0;
        lv_sim_report rep;
        const double t0 = cpu_now();
        lv_status st = lv_simulate(lv_phase_call_model(c), lv_phase_call_inst(c), &s, NULL, &rep,
                                   &err);
        const double dt = cpu_now() - t0;
        *t_end = rep.end_time;
        lv_sim_report_clear(&rep);
        lv_phase_call_free(c);
        if (st != LV_OK) {
            fprintf(stderr, "bench_fmu: %s\n", err.msg);
            return -1;
        }
        if (dt < *cpu)
            *cpu = dt;
    }
    lv_run_free(r);
    lv_mission_free(m);
    return 0;
}

static int bench_phase(const char *mission, const char *phase, const char *id, int reps)
{
    char path[PATH_MAX], cmd[4 * PATH_MAX], dir[PATH_MAX];
    snprintf(path, sizeof path, "%s/%s", LV_SOURCE_DIR, mission);
    snprintf(dir, sizeof dir, "/tmp/bench_fmu_%d_%s", (int)getpid(), id);
    snprintf(cmd, sizeof cmd, "rm -rf '%s' && mkdir -p '%s' && '%s' fmu '%s' --phase %s -o "
             "'%s/x.fmu' > /dev/null && unzip -q '%s/x.fmu' -d '%s'", dir, dir, LV_LVSIM, path,
             phase, dir, dir, dir);
    if (system(cmd) != 0) {
        fprintf(stderr, "bench_fmu: failed: %s\n", cmd);
        return -1;
    }
    char so[PATH_MAX + 64], uri[PATH_MAX + 32], md[PATH_MAX + 32], guid[64] = "";
    snprintf(so, sizeof so, "%s/binaries/linux64/%s.so", dir, id);
    snprintf(uri, sizeof uri, "file://%s/resources", dir);
    snprintf(md, sizeof md, "%s/modelDescription.xml", dir);
    FILE *fp = fopen(md, "r");
    char buf[4096];
    size_t n = fp ? fread(buf, 1, sizeof buf - 1, fp) : 0;
    if (fp)
        fclose(fp);
    buf[n] = '\0';
    const char *g = strstr(buf, "guid=\"");
    if (g != NULL)
        snprintf(guid, sizeof guid, "%.*s", (int)strcspn(g + 6, "\""), g + 6);
    void *h = dlopen(so, RTLD_NOW | RTLD_LOCAL);
    if (h == NULL) {
        fprintf(stderr, "bench_fmu: %s\n", dlerror());
        return -1;
    }
    fmu_fns F;
#define LV_LOAD(ret, name, args)                                                                 \
    {                                                                                            \
        void *s_ = dlsym(h, #name);                                                               \
        memcpy(&F.name, &s_, sizeof s_);                                                          \
    }
    LV_FMI2_FUNCTIONS(LV_LOAD)
#undef LV_LOAD

    double t_ref, t_end;
    if (reference(path, phase, reps, &t_ref, &t_end) != 0)
        return -1;
    const fmi2CallbackFunctions cb = {logger, calloc, free, NULL, NULL};
    double t0 = cpu_now();
    fmi2Component c = F.fmi2Instantiate("bench", fmi2CoSimulation, guid, uri, &cb, 0, 0);
    const double t_inst = cpu_now() - t0;
    if (c == NULL)
        return -1;
    double t_start = 0.0;
    {
        const char *p = strstr(buf, "startTime=\"");
        if (p)
            t_start = atof(p + 11);
    }
    printf("%s, phase %s (%.1f s of flight): lv_simulate %.3f ms; fmi2Instantiate %.1f ms "
           "(mission loaded, ancestors run)\n", mission, phase, t_end - t_start, 1e3 * t_ref,
           1e3 * t_inst);
    printf("  %-10s %10s %12s %12s %10s\n", "H [s]", "doSteps", "CS [ms]", "per step [us]",
           "CS/lv_sim");
    const double Hs[] = {10.0, 1.0, 0.1, 0.01};
    fmi2ValueReference vr[7] = {0, 1, 2, 3, 4, 5, 6};
    for (size_t j = 0; j < sizeof Hs / sizeof Hs[0]; j++) {
        const double H = Hs[j];
        double best = INFINITY;
        long steps = 0;
        for (int i = 0; i < reps; i++) {
            double x[7];
            t0 = cpu_now();
            F.fmi2Reset(c);
            F.fmi2SetupExperiment(c, 0, 0.0, t_start, 0, 0.0);
            F.fmi2EnterInitializationMode(c);
            F.fmi2ExitInitializationMode(c);
            double t = t_start;
            steps = 0;
            for (long k = 1;; k++) {
                const double tn = t_start + (double)k * H;
                fmi2Status st = F.fmi2DoStep(c, t, tn - t, fmi2True);
                steps++;
                F.fmi2GetReal(c, vr, 7, x);
                if (st != fmi2OK)
                    break;
                t = tn;
            }
            const double dt = cpu_now() - t0;
            if (dt < best)
                best = dt;
        }
        printf("  %-10g %10ld %12.3f %12.2f %10.2f\n", H, steps, 1e3 * best,
               1e6 * (best - t_ref) / (double)steps, best / t_ref);
    }
    F.fmi2FreeInstance(c);
    dlclose(h);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    return system(cmd) == 0 ? 0 : -1;
}

int main(int argc, char **argv)
{
    const int reps = argc > 1 ? atoi(argv[1]) : 20;
    int rc = bench_phase("examples/kourou-leo/mission.yaml", "ascent", "kourou_leo_ascent", reps);
    rc |= bench_phase("examples/kourou-leo/mission.yaml", "upper-burn-1",
                      "kourou_leo_upper_burn_1", reps);
    return rc != 0;
}
