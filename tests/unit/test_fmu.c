/* test_fmu.c - `lvsim fmu` checked from the outside: an FMI 2.0 importer written here from the
 * standard's documented calling sequence (FMI 2.0.x, sections 3.2.4 and 4.2.4) unpacks the
 * FMU (Debian's unzip), loads its binary with dlopen and simulates it
 *   - as Model Exchange with its own loop: classical RK4 with a fixed step, event indicators
 *     watched for a sign change (z > 0 versus z <= 0) located by bisection of the step, time
 *     events at nextEventTime, fmi2CompletedIntegratorStep after every step;
 *   - as Co-Simulation with fmi2DoStep (lvsim's own integrator inside);
 * and compares both with lv_simulate of the same phase of the same mission (lv_run_prepare),
 * the end event's time included. Also: modelDescription.xml against the standard's rules
 * (tests/fmi/check_model_description.py, Python's xml.etree), FMU states saved and restored
 * (the continuation bit-identical), calls out of the state machine's order and unknown value
 * references (fmi2Error with a logged message); every other Model Exchange run ends the way
 * the FMU compliance checker ends one (Continuous-Time Mode after terminateSimulation, then
 * fmi2Terminate: FMI 2.0.4, 3.2.3); the inputs (check_inputs) and the run parameters
 * (check_run_params) against lv_simulate with the same values set by lv_run_set.
 *
 * Tolerances (stated, with the measured differences printed): Model Exchange with RK4 at
 * h = 0.01 s against CVODE at the mission's 1e-8: end time within 1 ms, position within 1 m,
 * velocity within 1 mm/s... see the CHECKs. Co-Simulation with communication steps on the
 * phase's output grid reproduces lv_simulate exactly (lv_sim: "advancing to the output grid
 * points reproduces lv_simulate bit for bit"); with other steps to the tolerance.
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "fmi/fmi2.h"
#include "lvsim/lvsim.h"

#ifndef LV_LVSIM
#error "LV_LVSIM: the lvsim program"
#endif

/* ---- the FMU's functions ------------------------------------------------------------------ */

typedef struct fmu_lib {
    void *h;
#define LV_FIELD(ret, name, args) name##TYPE *name;
    LV_FMI2_FUNCTIONS(LV_FIELD)
#undef LV_FIELD
    char dir[PATH_MAX];   /* unpacked */
    char uri[PATH_MAX + 32];
    char guid[64];
} fmu_lib;

static char log_text[8192]; /* the latest messages of the FMU's logger */
static char log_fmt[8192];  /* the latest message as passed, before formatting */
static int log_count;

static void logger(fmi2ComponentEnvironment env, fmi2String instance, fmi2Status status,
                   fmi2String category, fmi2String message, ...)
{
    (void)env;
    char msg[2048];
    va_list ap;
    va_start(ap, message);
    vsnprintf(msg, sizeof msg, message, ap);
    va_end(ap);
    snprintf(log_fmt, sizeof log_fmt, "%s", message);
    snprintf(log_text, sizeof log_text, "[%s %d %s] %s", instance, (int)status, category, msg);
    log_count++;
    if (getenv("LV_FMU_TEST_VERBOSE") != NULL)
        fprintf(stderr, "%s\n", log_text);
}

static const fmi2CallbackFunctions callbacks = {logger, calloc, free, NULL, NULL};

/* `lvsim fmu` of the phase into build/tests/fmu_<id>.fmu, unpacked into fmu_<id>/. */
static int export_fmu(const char *mission, const char *phase, const char *id, fmu_lib *L)
{
    memset(L, 0, sizeof *L);
    char cmd[4 * PATH_MAX];
    snprintf(cmd, sizeof cmd, "rm -rf fmu_%s && \"%s\" fmu \"%s/%s\" --phase %s -o fmu_%s.fmu --force "
             "> fmu_%s.log 2>&1 && unzip -q -o fmu_%s.fmu -d fmu_%s", id, LV_LVSIM,
             getenv("LV_SOURCE_DIR"), mission, phase, id, id, id, id);
    if (system(cmd) != 0) {
        fprintf(stderr, "failed: %s\n", cmd);
        return -1;
    }
    char rel[PATH_MAX];
    snprintf(rel, sizeof rel, "fmu_%s", id);
    if (realpath(rel, L->dir) == NULL)
        return -1;
    snprintf(L->uri, sizeof L->uri, "file://%s/resources", L->dir);
    char so[PATH_MAX + 64];
    snprintf(so, sizeof so, "%s/binaries/linux64/%s.so", L->dir, id);
    /* the GUID from modelDescription.xml */
    char md[PATH_MAX + 32];
    snprintf(md, sizeof md, "%s/modelDescription.xml", L->dir);
    FILE *fp = fopen(md, "r");
    char buf[4096];
    size_t n = fp ? fread(buf, 1, sizeof buf - 1, fp) : 0;
    if (fp)
        fclose(fp);
    buf[n] = '\0';
    const char *g = strstr(buf, "guid=\"");
    if (g == NULL)
        return -1;
    snprintf(L->guid, sizeof L->guid, "%.*s", (int)strcspn(g + 6, "\""), g + 6);
    L->h = dlopen(so, RTLD_NOW | RTLD_LOCAL);
    if (L->h == NULL) {
        fprintf(stderr, "dlopen: %s\n", dlerror());
        return -1;
    }
#define LV_LOAD(ret, name, args)                                                                 \
    {                                                                                            \
        void *sym_ = dlsym(L->h, #name);                                                          \
        if (sym_ == NULL) {                                                                      \
            fprintf(stderr, "%s: no %s\n", so, #name);                                           \
            return -1;                                                                           \
        }                                                                                        \
        memcpy(&L->name, &sym_, sizeof sym_);                                                    \
    }
    LV_FMI2_FUNCTIONS(LV_LOAD)
#undef LV_LOAD
    return 0;
}

static void fmu_close(fmu_lib *L)
{
    if (L->h != NULL)
        dlclose(L->h);
    L->h = NULL;
}

/* ---- the reference: lv_simulate of the same phase ------------------------------------------ */

typedef struct reference {
    double t0, t_end;
    double x0[32], x_end[32];
    char end[LV_EVENT_NAME_MAX];
    size_t nx, np; /* the model's states and parameters */
    double tol, dt_out;
} reference;

/* A run parameter the next simulate_reference sets before preparing the phase (NULL: none). */
static const char *ref_set_name;
static double ref_set_value;

/* tol > 0: instead of the phase's own tolerance. */
static int simulate_reference(const char *mission, const char *phase, double tol, reference *ref)
{
    char path[PATH_MAX];
    snprintf(path, sizeof path, "%s/%s", getenv("LV_SOURCE_DIR"), mission);
    lv_err err;
    lv_mission *m = NULL;
    lv_run *r = NULL;
    lv_phase_call *c = NULL;
    size_t k;
    int rc = -1;
    if (lv_mission_load(path, &m, &err) != LV_OK || lv_mission_phase_find(m, phase, &k, &err) ||
        lv_run_create(m, &r, &err) != LV_OK) {
        fprintf(stderr, "%s\n", err.msg);
        goto out;
    }
    if (ref_set_name != NULL && lv_run_set(r, ref_set_name, ref_set_value, &err) != LV_OK) {
        fprintf(stderr, "%s\n", err.msg);
        goto out;
    }
    const int parent = lv_mission_phase_parent(m, k);
    if (parent >= 0) {
        unsigned char want[64] = {0};
        want[parent] = 1;
        lv_run_options opt = {0};
        opt.no_rows = 1;
        opt.want = want;
        if (lv_run_execute(r, &opt, &err) != LV_OK) {
            fprintf(stderr, "%s\n", err.msg);
            goto out;
        }
    }
    if (lv_run_prepare(r, k, &c, &err) != LV_OK) {
        fprintf(stderr, "%s\n", err.msg);
        goto out;
    }
    const lv_model_def *d = lv_phase_call_model(c);
    lv_sim_settings *s = lv_phase_call_settings(c);
    s->result_file = NULL;
    if (tol > 0.0)
        s->tolerance = tol;
    ref->nx = d->n_states;
    ref->np = d->n_params;
    ref->t0 = s->start_time;
    ref->tol = s->tolerance;
    ref->dt_out = s->output_interval;
    lv_sim_report rep;
    double *fin = lv_phase_call_finals(c);
    if (lv_simulate(d, lv_phase_call_inst(c), s, fin, &rep, &err) != LV_OK) {
        fprintf(stderr, "%s\n", err.msg);
        lv_sim_report_clear(&rep);
        goto out;
    }
    ref->t_end = rep.end_time;
    snprintf(ref->end, sizeof ref->end, "%s", rep.stop_name);
    lv_sim_report_clear(&rep);
    for (size_t i = 0; i < d->n_states; i++)
        for (size_t j = 0; j < s->n_final; j++)
            if (strcmp(s->final_names[j], d->states[i].name) == 0)
                ref->x_end[i] = fin[j];
    rc = 0;
out:
    lv_phase_call_free(c);
    lv_run_free(r);
    lv_mission_free(m);
    return rc;
}

/* ---- Model Exchange: the importer's own loop ----------------------------------------------- */

typedef struct me_result {
    double t_end;
    double x[32];
    int terminated;
    long steps, events;
} me_result;

typedef struct me_run {
    fmu_lib *L;
    fmi2Component c;
    size_t nx, ni;
    double t, x[32], z[64];
    fmi2EventInfo ev;
} me_run;

static int derivs(me_run *m, double t, const double *x, double *dx)
{
    if (m->L->fmi2SetTime(m->c, t) != fmi2OK ||
        m->L->fmi2SetContinuousStates(m->c, x, m->nx) != fmi2OK)
        return -1;
    return m->L->fmi2GetDerivatives(m->c, dx, m->nx) == fmi2OK ? 0 : -1;
}

/* One classical RK4 step of size h from (t, x) to xo. */
static int rk4(me_run *m, double t, const double *x, double h, double *xo)
{
    double k1[32], k2[32], k3[32], k4[32], xt[32];
    const size_t n = m->nx;
    if (derivs(m, t, x, k1) != 0)
        return -1;
    for (size_t i = 0; i < n; i++)
        xt[i] = x[i] + 0.5 * h * k1[i];
    if (derivs(m, t + 0.5 * h, xt, k2) != 0)
        return -1;
    for (size_t i = 0; i < n; i++)
        xt[i] = x[i] + 0.5 * h * k2[i];
    if (derivs(m, t + 0.5 * h, xt, k3) != 0)
        return -1;
    for (size_t i = 0; i < n; i++)
        xt[i] = x[i] + h * k3[i];
    if (derivs(m, t + h, xt, k4) != 0)
        return -1;
    for (size_t i = 0; i < n; i++)
        xo[i] = x[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    return 0;
}

/* Event indicators at (t, x); 1 when one changed its side of zero against z. */
static int crossed(me_run *m, double t, const double *x, double *zo)
{
    m->L->fmi2SetTime(m->c, t);
    m->L->fmi2SetContinuousStates(m->c, x, m->nx);
    if (m->ni > 0 && m->L->fmi2GetEventIndicators(m->c, zo, m->ni) != fmi2OK)
        return -1;
    for (size_t i = 0; i < m->ni; i++)
        if ((m->z[i] > 0.0) != (zo[i] > 0.0))
            return 1;
    return 0;
}

/* The event iteration (fmi2NewDiscreteStates until no new iteration is needed). */
static int event_iteration(me_run *m)
{
    m->ev.newDiscreteStatesNeeded = fmi2True;
    m->ev.terminateSimulation = fmi2False;
    while (m->ev.newDiscreteStatesNeeded && !m->ev.terminateSimulation)
        if (m->L->fmi2NewDiscreteStates(m->c, &m->ev) != fmi2OK)
            return -1;
    return 0;
}

static int me_runs, checker_sequences; /* run_me calls; those ended the checker's way */

static int run_me(fmu_lib *L, double t0, size_t nx, size_t ni, double h, me_result *res,
                  double t_save, fmi2FMUstate *saved)
{
    me_runs++;
    me_run m = {0};
    m.L = L;
    m.nx = nx;
    m.ni = ni;
    memset(res, 0, sizeof *res);
    m.c = L->fmi2Instantiate("me", fmi2ModelExchange, L->guid, L->uri, &callbacks, fmi2False,
                             fmi2False);
    if (m.c == NULL)
        return -1;
    int rc = -1;
    if (L->fmi2SetupExperiment(m.c, fmi2False, 0.0, t0, fmi2False, 0.0) != fmi2OK ||
        L->fmi2EnterInitializationMode(m.c) != fmi2OK ||
        L->fmi2ExitInitializationMode(m.c) != fmi2OK || event_iteration(&m) != 0)
        goto out;
    if (m.ev.terminateSimulation)
        goto done;
    if (L->fmi2EnterContinuousTimeMode(m.c) != fmi2OK ||
        L->fmi2GetContinuousStates(m.c, m.x, nx) != fmi2OK ||
        (ni > 0 && L->fmi2GetEventIndicators(m.c, m.z, ni) != fmi2OK))
        goto out;
    m.t = t0;
    int saved_once = 0;
    for (;;) {
        if (saved != NULL && !saved_once && m.t >= t_save) {
            /* save; 50 steps on; restore (the states are the saved ones); the same 50 steps
             * again: bit-identical; restore once more and go on as if nothing happened */
            double xs[32], xa[32], xb[32], xr[32];
            memcpy(xs, m.x, sizeof xs);
            if (L->fmi2GetFMUstate(m.c, saved) != fmi2OK)
                goto out;
            for (int pass = 0; pass < 2; pass++) {
                double *xo = pass == 0 ? xa : xb;
                memcpy(xo, xs, sizeof xa);
                for (int k = 0; k < 50; k++)
                    if (rk4(&m, m.t + k * h, xo, h, xo) != 0)
                        goto out;
                if (L->fmi2SetFMUstate(m.c, *saved) != fmi2OK ||
                    L->fmi2GetContinuousStates(m.c, xr, nx) != fmi2OK)
                    goto out;
                CHECK(memcmp(xr, xs, nx * sizeof *xr) == 0);
            }
            CHECK(memcmp(xa, xb, nx * sizeof *xa) == 0);
            printf("  ME state round trip: saved at t = %g s, 50 steps on twice: %s\n", m.t,
                   memcmp(xa, xb, nx * sizeof *xa) == 0 ? "bit-identical" : "DIFFERENT");
            saved_once = 1;
        }
        double step = h, t1 = m.t + h;
        int time_event = 0;
        if (m.ev.nextEventTimeDefined && t1 >= m.ev.nextEventTime) {
            t1 = m.ev.nextEventTime;
            step = t1 - m.t;
            time_event = 1;
        }
        double x1[32], z1[64];
        if (rk4(&m, m.t, m.x, step, x1) != 0)
            goto out;
        int c = crossed(&m, t1, x1, z1);
        if (c < 0)
            goto out;
        if (c > 0) { /* bisection of the step: the first instant past the crossing */
            double lo = 0.0, hi = step;
            double xh[32], zh[64];
            memcpy(xh, x1, sizeof xh);
            memcpy(zh, z1, sizeof zh);
            while (hi - lo > 1e-10 * fmax(1.0, fabs(m.t))) {
                const double mid = 0.5 * (lo + hi);
                double xm[32], zm[64];
                if (rk4(&m, m.t, m.x, mid, xm) != 0)
                    goto out;
                const int cm = crossed(&m, m.t + mid, xm, zm);
                if (cm < 0)
                    goto out;
                if (cm) {
                    hi = mid;
                    memcpy(xh, xm, sizeof xh);
                    memcpy(zh, zm, sizeof zh);
                } else {
                    lo = mid;
                }
            }
            t1 = m.t + hi;
            memcpy(x1, xh, sizeof x1);
            memcpy(z1, zh, sizeof z1);
            time_event = 0;
        }
        m.t = t1;
        memcpy(m.x, x1, sizeof m.x);
        memcpy(m.z, z1, sizeof m.z);
        L->fmi2SetTime(m.c, m.t);
        L->fmi2SetContinuousStates(m.c, m.x, nx);
        res->steps++;
        fmi2Boolean enter = fmi2False, term = fmi2False;
        if (L->fmi2CompletedIntegratorStep(m.c, fmi2True, &enter, &term) != fmi2OK)
            goto out;
        if (term)
            break;
        if (c > 0 || time_event || enter) {
            res->events++;
            if (L->fmi2EnterEventMode(m.c) != fmi2OK || event_iteration(&m) != 0)
                goto out;
            if (m.ev.terminateSimulation && (me_runs % 2) == 1) {
                /* every other run: the FMU compliance checker's sequence, legal by FMI 2.0.4
                 * 3.2.3 (fmi2EnterContinuousTimeMode is allowed in Event Mode, fmi2Terminate
                 * in Continuous-Time Mode): accepted, the request to terminate repeated by
                 * fmi2CompletedIntegratorStep, then fmi2Terminate from Continuous-Time Mode
                 * (below). Issue 27: both calls were refused. */
                fmi2Boolean e2 = fmi2True, t2 = fmi2False;
                CHECK(L->fmi2EnterContinuousTimeMode(m.c) == fmi2OK);
                CHECK(L->fmi2CompletedIntegratorStep(m.c, fmi2True, &e2, &t2) == fmi2OK);
                CHECK(t2 == fmi2True && e2 == fmi2False);
                double xc[32];
                CHECK(L->fmi2GetContinuousStates(m.c, xc, nx) == fmi2OK);
                CHECK(memcmp(xc, m.x, nx * sizeof *xc) == 0 || m.ev.valuesOfContinuousStatesChanged);
                checker_sequences++;
            }
            if (m.ev.terminateSimulation)
                break;
            if (L->fmi2EnterContinuousTimeMode(m.c) != fmi2OK)
                goto out;
            if (m.ev.valuesOfContinuousStatesChanged &&
                L->fmi2GetContinuousStates(m.c, m.x, nx) != fmi2OK)
                goto out;
            if (ni > 0 && L->fmi2GetEventIndicators(m.c, m.z, ni) != fmi2OK)
                goto out;
        }
    }
done:
    res->terminated = 1;
    res->t_end = m.t;
    L->fmi2GetContinuousStates(m.c, res->x, nx);
    rc = L->fmi2Terminate(m.c) == fmi2OK ? 0 : -1;
out:
    if (saved != NULL && *saved != NULL)
        L->fmi2FreeFMUstate(m.c, saved);
    L->fmi2FreeInstance(m.c);
    return rc;
}

/* ---- Co-Simulation ----------------------------------------------------------------------------- */

typedef struct cs_result {
    double t_end;
    double x[32];
    int terminated;
    long steps;
} cs_result;

/* fmi2DoStep of H until the FMU reports it terminated; the states by value reference 0..nx-1. */
static int run_cs(fmu_lib *L, double t0, size_t nx, double H, cs_result *res)
{
    memset(res, 0, sizeof *res);
    fmi2Component c = L->fmi2Instantiate("cs", fmi2CoSimulation, L->guid, L->uri, &callbacks,
                                         fmi2False, fmi2False);
    if (c == NULL)
        return -1;
    int rc = -1;
    fmi2ValueReference vr[32];
    for (size_t i = 0; i < nx; i++)
        vr[i] = (fmi2ValueReference)i;
    if (L->fmi2SetupExperiment(c, fmi2False, 0.0, t0, fmi2False, 0.0) != fmi2OK ||
        L->fmi2EnterInitializationMode(c) != fmi2OK || L->fmi2ExitInitializationMode(c) != fmi2OK)
        goto out;
    double t = t0;
    for (long k = 1; k < 10000000; k++) {
        const double tn = t0 + (double)k * H; /* no drift: the points are t0 + k H */
        fmi2Status st = L->fmi2DoStep(c, t, tn - t, fmi2True);
        res->steps++;
        if (st == fmi2Discard) {
            fmi2Boolean term = fmi2False;
            if (L->fmi2GetBooleanStatus(c, fmi2Terminated, &term) != fmi2OK || !term ||
                L->fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &res->t_end) != fmi2OK)
                goto out;
            res->terminated = 1;
            break;
        }
        if (st != fmi2OK)
            goto out;
        t = tn;
        fmi2Boolean term = fmi2False;
        L->fmi2GetBooleanStatus(c, fmi2Terminated, &term);
        if (term) { /* ended exactly at a communication point */
            res->terminated = 1;
            res->t_end = t;
            break;
        }
    }
    if (L->fmi2GetReal(c, vr, nx, res->x) != fmi2OK || L->fmi2Terminate(c) != fmi2OK)
        goto out;
    rc = 0;
out:
    L->fmi2FreeInstance(c);
    return rc;
}

/* CS: save after n1 steps, n2 more (a), restore, the same n2 (b), restore, again (c): b and c
 * bit-identical (a restore restarts the integrator at the saved point); a, which went on
 * without a restart (saving changes nothing), agrees with them to the tolerance. */
static void check_cs_state_roundtrip(fmu_lib *L, double t0, size_t nx, double H, long n1, long n2)
{
    fmi2Component c = L->fmi2Instantiate("cs-state", fmi2CoSimulation, L->guid, L->uri,
                                         &callbacks, fmi2False, fmi2False);
    CHECK(c != NULL);
    if (c == NULL)
        return;
    fmi2ValueReference vr[32];
    for (size_t i = 0; i < nx; i++)
        vr[i] = (fmi2ValueReference)i;
    CHECK(L->fmi2SetupExperiment(c, fmi2False, 0.0, t0, fmi2False, 0.0) == fmi2OK);
    CHECK(L->fmi2EnterInitializationMode(c) == fmi2OK);
    CHECK(L->fmi2ExitInitializationMode(c) == fmi2OK);
    double t = t0;
    for (long k = 0; k < n1; k++, t += H)
        CHECK(L->fmi2DoStep(c, t, H, fmi2False) == fmi2OK);
    fmi2FMUstate s = NULL;
    CHECK(L->fmi2GetFMUstate(c, &s) == fmi2OK);
    const double t_saved = t;
    double xa[32], xb[32], xc[32];
    double *out[3] = {xa, xb, xc};
    for (int pass = 0; pass < 3; pass++) {
        if (pass > 0) {
            CHECK(L->fmi2SetFMUstate(c, s) == fmi2OK);
            t = t_saved;
        }
        for (long k = 0; k < n2; k++, t += H)
            CHECK(L->fmi2DoStep(c, t, H, fmi2False) == fmi2OK);
        CHECK(L->fmi2GetReal(c, vr, nx, out[pass]) == fmi2OK);
    }
    CHECK(memcmp(xb, xc, nx * sizeof *xb) == 0);
    double dr = 0.0;
    for (int i = 0; i < 3; i++)
        dr = fmax(dr, fabs(xa[i] - xb[i]));
    printf("  CS state round trip: saved at t = %g s, %ld steps on after two restores: %s; "
           "after the save itself (no restart): |dr| = %.3g m\n", t_saved, n2,
           memcmp(xb, xc, nx * sizeof *xb) == 0 ? "bit-identical" : "DIFFERENT", dr);
    CHECK(dr <= 0.05);
    /* serialization is declared unsupported: fmi2Error with a message */
    size_t sz = 0;
    log_count = 0;
    CHECK(L->fmi2SerializedFMUstateSize(c, s, &sz) == fmi2Error);
    CHECK(log_count > 0 && strstr(log_text, "canSerializeFMUstate") != NULL);
    CHECK(L->fmi2FreeFMUstate(c, &s) == fmi2OK);
    CHECK(s == NULL);
    L->fmi2FreeInstance(c);
}

/* CS: a master that saves (and frees) a state after every step gets the same numbers, bit for
 * bit, as one that never saves: fmi2GetFMUstate has no side effect. */
static void check_cs_getstate_free_of_effects(fmu_lib *L, double t0, size_t nx, double H, long n)
{
    double x[2][32];
    fmi2ValueReference vr[32];
    for (size_t i = 0; i < nx; i++)
        vr[i] = (fmi2ValueReference)i;
    for (int save = 0; save < 2; save++) {
        fmi2Component c = L->fmi2Instantiate("cs-getstate", fmi2CoSimulation, L->guid, L->uri,
                                             &callbacks, fmi2False, fmi2False);
        CHECK(c != NULL);
        if (c == NULL)
            return;
        CHECK(L->fmi2SetupExperiment(c, fmi2False, 0.0, t0, fmi2False, 0.0) == fmi2OK);
        CHECK(L->fmi2EnterInitializationMode(c) == fmi2OK);
        CHECK(L->fmi2ExitInitializationMode(c) == fmi2OK);
        for (long k = 0; k < n; k++) {
            CHECK(L->fmi2DoStep(c, t0 + (double)k * H, H, fmi2False) == fmi2OK);
            if (save) {
                fmi2FMUstate s = NULL;
                CHECK(L->fmi2GetFMUstate(c, &s) == fmi2OK);
                CHECK(L->fmi2FreeFMUstate(c, &s) == fmi2OK);
            }
        }
        CHECK(L->fmi2GetReal(c, vr, nx, x[save]) == fmi2OK);
        L->fmi2FreeInstance(c);
    }
    CHECK(memcmp(x[0], x[1], nx * sizeof x[0][0]) == 0);
    printf("  CS with fmi2GetFMUstate after each of %ld steps: %s the run without\n", n,
           memcmp(x[0], x[1], nx * sizeof x[0][0]) == 0 ? "bit-identical to" : "DIFFERENT from");
}

/* ---- bad calls -------------------------------------------------------------------------------- */

#define CHECK_ERROR_LOGGED(call, text)                                                        \
    do {                                                                                      \
        log_count = 0;                                                                        \
        log_text[0] = '\0';                                                                   \
        CHECK((call) == fmi2Error);                                                           \
        CHECK(log_count > 0 && strstr(log_text, text) != NULL);                               \
        if (strstr(log_text, text) == NULL)                                                   \
            fprintf(stderr, "  expected '%s' in the log, got: %s\n", text, log_text);         \
    } while (0)

/* An instance through initialization: ready to step (Co-Simulation) or in Event Mode. */
static fmi2Component started(fmu_lib *L, fmi2Type type, const char *name, double t0)
{
    fmi2Component c = L->fmi2Instantiate(name, type, L->guid, L->uri, &callbacks, fmi2False,
                                         fmi2False);
    CHECK(c != NULL);
    if (c == NULL)
        return NULL;
    CHECK(L->fmi2SetupExperiment(c, fmi2False, 0.0, t0, fmi2False, 0.0) == fmi2OK);
    CHECK(L->fmi2EnterInitializationMode(c) == fmi2OK);
    CHECK(L->fmi2ExitInitializationMode(c) == fmi2OK);
    return c;
}

/* After fmi2Error the instance is in the standard's Error state: a step is refused, the get
 * functions are not, fmi2Reset brings it back to Instantiated. */
static void check_in_error(fmu_lib *L, fmi2Component c, double t0)
{
    double v = 0.0;
    fmi2ValueReference st0 = 0;
    CHECK_ERROR_LOGGED(L->fmi2EnterInitializationMode(c), "not allowed in Error");
    CHECK(L->fmi2GetReal(c, &st0, 1, &v) == fmi2OK);
    CHECK(L->fmi2Reset(c) == fmi2OK);
    CHECK(L->fmi2SetupExperiment(c, fmi2False, 0.0, t0, fmi2False, 0.0) == fmi2OK);
}

static void check_bad_calls(fmu_lib *L, double t0, size_t nx, size_t np, size_t ni)
{
    /* the first output: after the states, their derivatives and the parameters */
    fmi2ValueReference bad = 100000, out_vr = (fmi2ValueReference)(2 * nx + np);
    double v = 0.0;
    /* a wrong GUID: no instance, and the logger says why */
    log_count = 0;
    CHECK(L->fmi2Instantiate("x", fmi2CoSimulation, "{wrong}", L->uri, &callbacks, fmi2False,
                             fmi2False) == NULL);
    CHECK(log_count > 0 && strstr(log_text, "GUID") != NULL);
    log_count = 0;
    CHECK(L->fmi2Instantiate("x", fmi2ModelExchange, L->guid, "http://example/res", &callbacks,
                             fmi2False, fmi2False) == NULL);
    CHECK(log_count > 0 && strstr(log_text, "file://") != NULL);

    fmi2Component c = L->fmi2Instantiate("bad", fmi2CoSimulation, L->guid, L->uri, &callbacks,
                                         fmi2False, fmi2False);
    CHECK(c != NULL);
    if (c == NULL)
        return;
    /* each error puts the instance into Error (FMI 2.0): fmi2Reset, and on */
    CHECK_ERROR_LOGGED(L->fmi2DoStep(c, t0, 1.0, fmi2True), "not allowed in Instantiated");
    check_in_error(L, c, t0);
    CHECK(L->fmi2Reset(c) == fmi2OK);
    CHECK_ERROR_LOGGED(L->fmi2ExitInitializationMode(c), "not allowed in Instantiated");
    CHECK(L->fmi2Reset(c) == fmi2OK);
    /* a tolerance that is not > 0: fmi2Error, and initialization is refused after it */
    CHECK_ERROR_LOGGED(L->fmi2SetupExperiment(c, fmi2True, 0.0, t0, fmi2False, 0.0),
                       "tolerance 0 is not > 0");
    check_in_error(L, c, t0);
    /* the start time is the phase's (the hand-off's time): another one is refused, naming both */
    CHECK(L->fmi2Reset(c) == fmi2OK);
    char want[128];
    const double t_other = t0 == 0.0 ? -5.0 : 0.0;
    snprintf(want, sizeof want, "startTime %.17g s is not the phase's start %.17g s", t_other,
             t0);
    CHECK_ERROR_LOGGED(L->fmi2SetupExperiment(c, fmi2False, 0.0, t_other, fmi2False, 0.0), want);
    CHECK(L->fmi2Reset(c) == fmi2OK);
    CHECK_ERROR_LOGGED(L->fmi2SetupExperiment(c, fmi2False, 0.0, t0 + 1.0, fmi2False, 0.0),
                       "is not the phase's start");
    CHECK(L->fmi2Reset(c) == fmi2OK);
    CHECK(L->fmi2SetupExperiment(c, fmi2False, 0.0, t0, fmi2False, 0.0) == fmi2OK);
    CHECK(L->fmi2EnterInitializationMode(c) == fmi2OK);
    CHECK_ERROR_LOGGED(L->fmi2GetReal(c, &bad, 1, &v), "unknown value reference 100000");
    CHECK(L->fmi2Reset(c) == fmi2OK);
    CHECK(L->fmi2SetupExperiment(c, fmi2False, 0.0, t0, fmi2False, 0.0) == fmi2OK);
    CHECK(L->fmi2EnterInitializationMode(c) == fmi2OK);
    CHECK_ERROR_LOGGED(L->fmi2SetReal(c, &out_vr, 1, &v), "cannot be set");
    CHECK(L->fmi2Reset(c) == fmi2OK);
    CHECK_ERROR_LOGGED(L->fmi2GetInteger(c, &bad, 1, (fmi2Integer *)&v), "unknown value reference");
    L->fmi2FreeInstance(c);

    c = started(L, fmi2CoSimulation, "bad-cs", t0);
    if (c == NULL)
        return;
    fmi2ValueReference st0 = 0;
    CHECK_ERROR_LOGGED(L->fmi2SetReal(c, &st0, 1, &v), "before fmi2ExitInitializationMode");
    L->fmi2FreeInstance(c);
    c = started(L, fmi2CoSimulation, "bad-cs", t0);
    CHECK_ERROR_LOGGED(L->fmi2DoStep(c, t0 + 5.0, 1.0, fmi2True), "currentCommunicationPoint");
    L->fmi2FreeInstance(c);
    c = started(L, fmi2CoSimulation, "bad-cs", t0);
    CHECK_ERROR_LOGGED(L->fmi2NewDiscreteStates(c, &(fmi2EventInfo){0}),
                       "not allowed in StepComplete");
    L->fmi2FreeInstance(c);
    c = started(L, fmi2CoSimulation, "bad-cs", t0);
    CHECK_ERROR_LOGGED(L->fmi2CancelStep(c), "no step to cancel");
    L->fmi2FreeInstance(c);
    c = started(L, fmi2CoSimulation, "bad-cs", t0);
    fmi2Status ds;
    CHECK(L->fmi2GetStatus(c, fmi2DoStepStatus, &ds) == fmi2Discard);
    CHECK(L->fmi2DoStep(c, t0, 1.0, fmi2True) == fmi2OK);
    CHECK(L->fmi2Terminate(c) == fmi2OK);
    CHECK_ERROR_LOGGED(L->fmi2DoStep(c, t0 + 1.0, 1.0, fmi2True), "not allowed in Terminated");
    CHECK(L->fmi2Reset(c) == fmi2OK); /* back to Instantiated: a second run works */
    /* stopTime defined: a step past it is fmi2Error; up to it (round-off included) is not */
    CHECK(L->fmi2SetupExperiment(c, fmi2False, 0.0, t0, fmi2True, t0 + 1.5) == fmi2OK);
    CHECK(L->fmi2EnterInitializationMode(c) == fmi2OK);
    CHECK(L->fmi2ExitInitializationMode(c) == fmi2OK);
    CHECK(L->fmi2DoStep(c, t0, 1.0, fmi2True) == fmi2OK);
    CHECK_ERROR_LOGGED(L->fmi2DoStep(c, t0 + 1.0, 1.0, fmi2True), "past stopTime");
    CHECK(L->fmi2Reset(c) == fmi2OK);
    CHECK(L->fmi2SetupExperiment(c, fmi2False, 0.0, t0, fmi2True, t0 + 1.5) == fmi2OK);
    CHECK(L->fmi2EnterInitializationMode(c) == fmi2OK);
    CHECK(L->fmi2ExitInitializationMode(c) == fmi2OK);
    CHECK(L->fmi2DoStep(c, t0, 1.0, fmi2True) == fmi2OK);
    CHECK(L->fmi2DoStep(c, t0 + 1.0, 0.5 + 1e-13, fmi2True) == fmi2OK);
    fmi2Real t_last = 0.0;
    CHECK(L->fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &t_last) == fmi2OK);
    CHECK(t_last == t0 + 1.5);
    /* a log message with '%': the logger's format has it doubled, the text shows it once */
    log_count = 0;
    CHECK(L->fmi2SetDebugLogging(c, fmi2True, 1, (fmi2String[]){"100%s"}) == fmi2Error);
    CHECK(strstr(log_fmt, "'100%%s'") != NULL && strstr(log_text, "'100%s'") != NULL);
    L->fmi2FreeInstance(c);

    fmi2Component me = started(L, fmi2ModelExchange, "bad-me", t0);
    if (me == NULL)
        return;
    CHECK_ERROR_LOGGED(L->fmi2SetContinuousStates(me, &v, 1), "not allowed in EventMode");
    L->fmi2FreeInstance(me);
    me = started(L, fmi2ModelExchange, "bad-me", t0);
    CHECK_ERROR_LOGGED(L->fmi2DoStep(me, t0, 1.0, fmi2True), "not allowed in EventMode");
    L->fmi2FreeInstance(me);
    me = started(L, fmi2ModelExchange, "bad-me", t0);
    CHECK_ERROR_LOGGED(L->fmi2SetDebugLogging(me, fmi2True, 1, (fmi2String[]){"logNothing"}),
                       "unknown log category");
    L->fmi2FreeInstance(me);
    me = started(L, fmi2ModelExchange, "bad-me", t0);
    CHECK(L->fmi2SetDebugLogging(me, fmi2True, 1, (fmi2String[]){"logEvents"}) == fmi2OK);
    fmi2EventInfo ev;
    CHECK(L->fmi2NewDiscreteStates(me, &ev) == fmi2OK);
    CHECK(L->fmi2EnterContinuousTimeMode(me) == fmi2OK);
    /* NULL arrays are named as such */
    CHECK_ERROR_LOGGED(L->fmi2GetDerivatives(me, NULL, nx), "'derivatives' is NULL");
    L->fmi2FreeInstance(me);
    me = started(L, fmi2ModelExchange, "bad-me", t0);
    CHECK(L->fmi2NewDiscreteStates(me, &ev) == fmi2OK);
    CHECK(L->fmi2EnterContinuousTimeMode(me) == fmi2OK);
    CHECK_ERROR_LOGGED(L->fmi2NewDiscreteStates(me, &ev), "not allowed in ContinuousTimeMode");
    L->fmi2FreeInstance(me);
    me = started(L, fmi2ModelExchange, "bad-me", t0);
    CHECK_ERROR_LOGGED(L->fmi2GetDirectionalDerivative(me, NULL, 0, NULL, 0, NULL, NULL),
                       "providesDirectionalDerivative");
    L->fmi2FreeInstance(me);
    /* fmi2SetTime only in Event and Continuous-Time Mode */
    me = L->fmi2Instantiate("me-time", fmi2ModelExchange, L->guid, L->uri, &callbacks, fmi2False,
                            fmi2False);
    CHECK_ERROR_LOGGED(L->fmi2SetTime(me, t0), "not allowed in Instantiated");
    L->fmi2FreeInstance(me);
    /* stopTime in Model Exchange: fmi2SetTime past it is fmi2Error */
    me = L->fmi2Instantiate("me-stop", fmi2ModelExchange, L->guid, L->uri, &callbacks, fmi2False,
                            fmi2False);
    CHECK(L->fmi2SetupExperiment(me, fmi2False, 0.0, t0, fmi2True, t0 + 2.0) == fmi2OK);
    CHECK(L->fmi2EnterInitializationMode(me) == fmi2OK);
    CHECK(L->fmi2ExitInitializationMode(me) == fmi2OK);
    CHECK(L->fmi2NewDiscreteStates(me, &ev) == fmi2OK);
    CHECK(L->fmi2EnterContinuousTimeMode(me) == fmi2OK);
    CHECK(L->fmi2SetTime(me, t0 + 2.0) == fmi2OK);
    CHECK_ERROR_LOGGED(L->fmi2SetTime(me, t0 + 2.5), "past stopTime");
    L->fmi2FreeInstance(me);
    /* states that are not finite: indicators and derivatives both fmi2Discard */
    me = started(L, fmi2ModelExchange, "me-nan", t0);
    CHECK(L->fmi2NewDiscreteStates(me, &ev) == fmi2OK);
    CHECK(L->fmi2EnterContinuousTimeMode(me) == fmi2OK);
    double xn[32], dx[32], z[64];
    for (size_t i = 0; i < nx; i++)
        xn[i] = NAN;
    CHECK(L->fmi2SetContinuousStates(me, xn, nx) == fmi2OK);
    CHECK(L->fmi2GetDerivatives(me, dx, nx) == fmi2Discard);
    if (ni > 0) /* with indicators: the same status as the derivatives */
        CHECK(L->fmi2GetEventIndicators(me, z, ni) == fmi2Discard);
    L->fmi2FreeInstance(me);
}

/* FMU states belong to the instance that saved it: a state of another instance (also after
 * that one is freed), of the other kind, or a freed one, is refused with a message; a state
 * into or an instance freed twice does no harm (valgrind and ASan watch this test). */
static void check_foreign_states(fmu_lib *L, fmu_lib *other, double t0, double t0_other)
{
    fmi2Component a = started(L, fmi2CoSimulation, "A", t0);
    fmi2Component b = started(L, fmi2CoSimulation, "B", t0);
    fmi2Component m = started(L, fmi2ModelExchange, "M", t0);
    fmi2Component o = started(other, fmi2CoSimulation, "O", t0_other);
    if (a == NULL || b == NULL || m == NULL || o == NULL)
        return;
    fmi2FMUstate sa = NULL, sm = NULL, so = NULL;
    CHECK(L->fmi2GetFMUstate(a, &sa) == fmi2OK);
    CHECK(L->fmi2GetFMUstate(m, &sm) == fmi2OK);
    CHECK(other->fmi2GetFMUstate(o, &so) == fmi2OK);
    CHECK_ERROR_LOGGED(L->fmi2SetFMUstate(b, sa), "saved by instance 'A'");
    CHECK(L->fmi2Reset(b) == fmi2OK);
    CHECK_ERROR_LOGGED(L->fmi2SetFMUstate(b, sm), "(Model Exchange");
    CHECK(L->fmi2Reset(b) == fmi2OK);
    CHECK_ERROR_LOGGED(L->fmi2SetFMUstate(b, so), "not a live FMU state of this FMU");
    CHECK(L->fmi2Reset(b) == fmi2OK);
    CHECK_ERROR_LOGGED(L->fmi2FreeFMUstate(b, &sa), "saved by instance 'A'");
    CHECK(sa != NULL);
    L->fmi2FreeInstance(a); /* frees sa with it */
    CHECK_ERROR_LOGGED(L->fmi2SetFMUstate(b, sa), "not a live FMU state");
    CHECK(L->fmi2Reset(b) == fmi2OK);
    /* a state into an instance already freed, an instance freed twice: refused, no harm */
    CHECK(L->fmi2SetFMUstate(a, sm) == fmi2Error);
    L->fmi2FreeInstance(a);
    CHECK(L->fmi2SetupExperiment(b, fmi2False, 0.0, t0, fmi2False, 0.0) == fmi2OK);
    CHECK(L->fmi2EnterInitializationMode(b) == fmi2OK);
    CHECK(L->fmi2ExitInitializationMode(b) == fmi2OK);
    CHECK(L->fmi2DoStep(b, t0, 1.0, fmi2True) == fmi2OK);
    CHECK(other->fmi2FreeFMUstate(o, &so) == fmi2OK);
    L->fmi2FreeInstance(b);
    L->fmi2FreeInstance(m); /* sm is freed with it */
    other->fmi2FreeInstance(o);
}

/* The start-value parameters (start_lat ...): a root phase computes its start states from them
 * again (those the importer set are kept); a child phase starts from the hand-off, and says so
 * with fmi2Warning. */
static void check_start_params(fmu_lib *L, double t0, size_t nx, int root)
{
    fmi2Component c = L->fmi2Instantiate("start", fmi2CoSimulation, L->guid, L->uri, &callbacks,
                                         fmi2False, fmi2False);
    CHECK(c != NULL);
    if (c == NULL)
        return;
    const fmi2ValueReference lat = (fmi2ValueReference)(2 * nx); /* the first parameter */
    fmi2ValueReference vr[32];
    for (size_t i = 0; i < nx; i++)
        vr[i] = (fmi2ValueReference)i;
    double x0[32], x1[32], lat0 = 0.0;
    CHECK(L->fmi2SetupExperiment(c, fmi2False, 0.0, t0, fmi2False, 0.0) == fmi2OK);
    CHECK(L->fmi2EnterInitializationMode(c) == fmi2OK);
    CHECK(L->fmi2GetReal(c, vr, nx, x0) == fmi2OK);
    CHECK(L->fmi2GetReal(c, &lat, 1, &lat0) == fmi2OK);
    const double lat1 = lat0 + 0.1, mass = x0[nx - 1] + 1.0;
    fmi2ValueReference vm = (fmi2ValueReference)(nx - 1);
    CHECK(L->fmi2SetReal(c, &vm, 1, &mass) == fmi2OK);
    log_count = 0;
    const fmi2Status st = L->fmi2SetReal(c, &lat, 1, &lat1);
    CHECK(L->fmi2GetReal(c, vr, nx, x1) == fmi2OK);
    if (root) {
        CHECK(st == fmi2OK);
        CHECK(x1[0] != x0[0] && x1[2] != x0[2]); /* the position moved */
        CHECK(x1[nx - 1] == mass);                /* the state set stays */
        printf("  root phase: start_lat + 0.1 rad moves the start by %.0f m in z\n",
               x1[2] - x0[2]);
    } else {
        CHECK(st == fmi2Warning);
        CHECK(log_count > 0 && strstr(log_text, "starts from the final state of phase") != NULL);
        CHECK(memcmp(x1, x0, (nx - 1) * sizeof *x0) == 0);
    }
    log_count = 0;
    CHECK(L->fmi2ExitInitializationMode(c) == fmi2OK);
    if (log_count > 0)
        fprintf(stderr, "  %s\n", log_text);
    L->fmi2FreeInstance(c);
}

/* Edited resources: the mission (its SHA-256 differs from the one recorded) and the counts
 * of resources/lvsim-fmu.txt: no instance, and the message names the file. */
static void check_edited_resources(fmu_lib *L)
{
    char cmd[6 * PATH_MAX], uri[PATH_MAX + 64];
    snprintf(cmd, sizeof cmd, "rm -rf '%s.ed' && cp -r '%s' '%s.ed' && echo '# edited' >> "
             "'%s.ed/resources/mission/mission.yaml'", L->dir, L->dir, L->dir, L->dir);
    CHECK(system(cmd) == 0);
    snprintf(uri, sizeof uri, "file://%s.ed/resources", L->dir);
    log_count = 0;
    CHECK(L->fmi2Instantiate("ed", fmi2CoSimulation, L->guid, uri, &callbacks, fmi2False,
                             fmi2False) == NULL);
    CHECK(strstr(log_text, "resources/mission/mission.yaml differs") != NULL);
    snprintf(cmd, sizeof cmd, "rm -rf '%s.ed' && cp -r '%s' '%s.ed' && sed -i "
             "'s/^states \\(.*\\)/states 99/' '%s.ed/resources/lvsim-fmu.txt'", L->dir, L->dir,
             L->dir, L->dir);
    CHECK(system(cmd) == 0);
    log_count = 0;
    CHECK(L->fmi2Instantiate("ed", fmi2CoSimulation, L->guid, uri, &callbacks, fmi2False,
                             fmi2False) == NULL);
    CHECK(strstr(log_text, "resources/lvsim-fmu.txt says 99") != NULL);
    snprintf(cmd, sizeof cmd, "rm -rf '%s.ed'", L->dir);
    CHECK(system(cmd) == 0);
}

/* ---- one phase ------------------------------------------------------------------------------ */

static void check_phase(const char *mission, const char *phase, const char *id, double h_me,
                        double pos_tol, double vel_tol, double t_tol)
{
    printf("%s, phase %s:\n", mission, phase);
    reference ref = {0}, tight = {0};
    fmu_lib L;
    CHECK(simulate_reference(mission, phase, 0.0, &ref) == 0);
    CHECK(simulate_reference(mission, phase, 1e-12, &tight) == 0);
    if (export_fmu(mission, phase, id, &L) != 0) {
        CHECK(!"export and load");
        return;
    }
    char cmd[2 * PATH_MAX];
    snprintf(cmd, sizeof cmd, "/usr/bin/python3 \"%s/tests/fmi/check_model_description.py\" "
             "\"%s\"", getenv("LV_SOURCE_DIR"), L.dir);
    CHECK(system(cmd) == 0);
    const size_t nx = ref.nx;
    printf("  lv_simulate: ends at t = %.9f s (%s); at tolerance 1e-12: t = %.9f s, "
           "|dr| = %.3g m from the mission's tolerance %g\n", ref.t_end, ref.end, tight.t_end,
           fmax(fabs(ref.x_end[0] - tight.x_end[0]), fmax(fabs(ref.x_end[1] - tight.x_end[1]),
                fabs(ref.x_end[2] - tight.x_end[2]))), ref.tol);

    /* Model Exchange: number of event indicators from the description */
    size_t ni = 0;
    {
        char md[PATH_MAX + 32];
        snprintf(md, sizeof md, "%s/modelDescription.xml", L.dir);
        FILE *fp = fopen(md, "r");
        char buf[4096];
        size_t n = fp ? fread(buf, 1, sizeof buf - 1, fp) : 0;
        if (fp)
            fclose(fp);
        buf[n] = '\0';
        const char *p = strstr(buf, "numberOfEventIndicators=\"");
        if (p)
            ni = (size_t)atol(p + 25);
    }
    if (getenv("LV_FMU_TEST_H") != NULL)
        h_me = atof(getenv("LV_FMU_TEST_H"));
    me_result me;
    CHECK(run_me(&L, ref.t0, nx, ni, h_me, &me, INFINITY, NULL) == 0);
    CHECK(me.terminated);
    double dpos = 0, dvel = 0;
    for (int i = 0; i < 3; i++) {
        dpos = fmax(dpos, fabs(me.x[i] - tight.x_end[i]));
        dvel = fmax(dvel, fabs(me.x[3 + i] - tight.x_end[3 + i]));
    }
    printf("  Model Exchange (RK4, h = %g s, %ld steps, %ld events): ends at t = %.9f s; "
           "against lv_simulate at 1e-12: |dt_end| = %.3g s, |dr| = %.3g m, |dv| = %.3g m/s, |dm| = %.3g kg\n", h_me, me.steps,
           me.events, me.t_end, fabs(me.t_end - tight.t_end), dpos, dvel,
           fabs(me.x[nx - 1] - tight.x_end[nx - 1]));
    CHECK_CLOSE(me.t_end, tight.t_end, t_tol);
    CHECK(dpos <= pos_tol);
    CHECK(dvel <= vel_tol);
    CHECK_CLOSE(me.x[nx - 1], tight.x_end[nx - 1], 1e-3 * fmax(1.0, fabs(tight.x_end[nx - 1])) + 0.5);

    /* Model Exchange: save in the middle, finish, restore into a second instance run: the same
     * loop from the same state gives the same numbers */
    me_result me2;
    fmi2FMUstate s = NULL;
    CHECK(run_me(&L, ref.t0, nx, ni, h_me, &me2, ref.t0 + 0.5 * (ref.t_end - ref.t0), &s) == 0);
    CHECK(memcmp(me2.x, me.x, nx * sizeof *me.x) == 0 && me2.t_end == me.t_end);

    /* Co-Simulation on the output grid: lv_simulate exactly */
    cs_result cs;
    CHECK(run_cs(&L, ref.t0, nx, ref.dt_out, &cs) == 0);
    CHECK(cs.terminated);
    double cpos = 0, cvel = 0;
    for (int i = 0; i < 3; i++) {
        cpos = fmax(cpos, fabs(cs.x[i] - ref.x_end[i]));
        cvel = fmax(cvel, fabs(cs.x[3 + i] - ref.x_end[3 + i]));
    }
    printf("  Co-Simulation (H = %g s, the output grid, %ld steps): ends at t = %.9f s; "
           "|dt_end| = %.3g s, |dr| = %.3g m, |dv| = %.3g m/s\n", ref.dt_out, cs.steps, cs.t_end,
           fabs(cs.t_end - ref.t_end), cpos, cvel);
    CHECK(cs.t_end == ref.t_end);
    CHECK(memcmp(cs.x, ref.x_end, nx * sizeof *cs.x) == 0);
    /* Co-Simulation with steps off the grid: to the tolerance */
    CHECK(run_cs(&L, ref.t0, nx, 0.37, &cs) == 0);
    cpos = cvel = 0;
    for (int i = 0; i < 3; i++) {
        cpos = fmax(cpos, fabs(cs.x[i] - ref.x_end[i]));
        cvel = fmax(cvel, fabs(cs.x[3 + i] - ref.x_end[3 + i]));
    }
    printf("  Co-Simulation (H = 0.37 s, %ld steps): ends at t = %.9f s; |dt_end| = %.3g s, "
           "|dr| = %.3g m, |dv| = %.3g m/s\n", cs.steps, cs.t_end, fabs(cs.t_end - ref.t_end),
           cpos, cvel);
    CHECK(cs.terminated);
    CHECK_CLOSE(cs.t_end, ref.t_end, 1e-4);
    CHECK(cpos <= 0.05 && cvel <= 1e-3);

    check_cs_state_roundtrip(&L, ref.t0, nx, (ref.t_end - ref.t0) / 100.0, 30, 40);
    check_cs_getstate_free_of_effects(&L, ref.t0, nx, 0.37 * (ref.t_end - ref.t0) / 100.0, 90);
    check_bad_calls(&L, ref.t0, nx, ref.np, ni);
    check_start_params(&L, ref.t0, nx, strcmp(phase, "ascent") == 0);
    check_edited_resources(&L);
    fmu_close(&L);
}

/* The inputs (issue 27): dof3-branch's ascent is driven by constant inputs (alpha, throttle in
 * the mission; beta, mu at their defaults), so its FMU declares alpha, beta, mu and throttle as
 * inputs (causality input). Checked:
 *  - set before initialization, an input is the mission's run parameter "ascent.inputs.alpha"
 *    changed: Co-Simulation on the output grid reproduces lv_simulate of the phase with
 *    lv_run_set("ascent.inputs.alpha") bit for bit (lv_sim's own promise on the output grid);
 *  - set between steps (Co-Simulation) it changes the continuation only: the states at the
 *    instant it is set are those of the run without it, the end differs;
 *  - in Model Exchange's Continuous-Time Mode it changes the derivatives at once, and setting
 *    the old value back gives the old derivatives bit for bit;
 *  - a parameter that is not an input is still refused after initialization. */
static void check_inputs(void)
{
    fmu_lib L;
    printf("inputs (dof3-branch ascent):\n");
    if (export_fmu("examples/dof3-branch/mission.yaml", "ascent", "dof3_branch_ascent", &L) != 0) {
        CHECK(!"export and load dof3-branch ascent");
        return;
    }
    char md[PATH_MAX + 32], *x = NULL;
    snprintf(md, sizeof md, "%s/modelDescription.xml", L.dir);
    FILE *fp = fopen(md, "r");
    if (fp != NULL) {
        x = calloc(1, 1 << 20);
        if (x != NULL)
            CHECK(fread(x, 1, (1 << 20) - 1, fp) > 0);
        fclose(fp);
    }
    CHECK(x != NULL);
    const char *const inputs[] = {"alpha", "beta", "mu", "throttle"};
    fmi2ValueReference vr_in[4] = {0};
    for (int i = 0; x != NULL && i < 4; i++) {
        char pat[64];
        snprintf(pat, sizeof pat, "name=\"%s\" valueReference=\"", inputs[i]);
        const char *q = strstr(x, pat);
        CHECK(q != NULL);
        if (q == NULL)
            continue;
        vr_in[i] = (fmi2ValueReference)strtoul(q + strlen(pat), NULL, 10);
        const char *end = strchr(q, '>');
        CHECK(end != NULL && strstr(q, "causality=\"input\"") != NULL &&
              strstr(q, "causality=\"input\"") < end);
    }
    const char *pq = x ? strstr(x, "name=\"propellant\" valueReference=\"") : NULL;
    CHECK(pq != NULL);
    const char *pv = pq != NULL ? strstr(pq, "valueReference=\"") : NULL;
    const fmi2ValueReference vr_prop =
        pv != NULL ? (fmi2ValueReference)strtoul(pv + strlen("valueReference=\""), NULL, 10) : 0;
    free(x);
    const double alpha = 0.02; /* rad */
    reference ref = {0};
    ref_set_name = "ascent.inputs.alpha";
    ref_set_value = alpha;
    CHECK(simulate_reference("examples/dof3-branch/mission.yaml", "ascent", 0.0, &ref) == 0);
    ref_set_name = NULL;
    const size_t nx = ref.nx;
    fmi2ValueReference vr_x[32];
    for (size_t i = 0; i < nx; i++)
        vr_x[i] = (fmi2ValueReference)i;
    /* 1. set before initialization: lv_simulate with the run parameter, bit for bit */
    double xe[32] = {0}, t_end = NAN;
    fmi2Component c = L.fmi2Instantiate("in", fmi2CoSimulation, L.guid, L.uri, &callbacks,
                                        fmi2False, fmi2False);
    CHECK(c != NULL);
    if (c != NULL) {
        CHECK(L.fmi2SetupExperiment(c, fmi2False, 0.0, ref.t0, fmi2False, 0.0) == fmi2OK);
        CHECK(L.fmi2EnterInitializationMode(c) == fmi2OK);
        CHECK(L.fmi2SetReal(c, &vr_in[0], 1, &alpha) == fmi2OK);
        CHECK(L.fmi2ExitInitializationMode(c) == fmi2OK);
        double t = ref.t0;
        for (int k = 0; k < 100000; k++) {
            fmi2Status st = L.fmi2DoStep(c, t, ref.dt_out, fmi2True);
            if (st == fmi2Discard) {
                L.fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &t);
                break;
            }
            CHECK(st == fmi2OK);
            if (st != fmi2OK)
                break;
            t = ref.t0 + (k + 1) * ref.dt_out;
            fmi2Boolean term = fmi2False;
            if (L.fmi2GetBooleanStatus(c, fmi2Terminated, &term) == fmi2OK && term)
                break;
        }
        t_end = t;
        CHECK(L.fmi2GetReal(c, vr_x, nx, xe) == fmi2OK);
        CHECK(L.fmi2Terminate(c) == fmi2OK);
        L.fmi2FreeInstance(c);
    }
    double dmax = fabs(t_end - ref.t_end);
    for (size_t i = 0; i < nx; i++)
        dmax = fmax(dmax, fabs(xe[i] - ref.x_end[i]));
    printf("  alpha = %g rad set before initialization: CS on the output grid vs lv_simulate "
           "with ascent.inputs.alpha: max difference %g (end t = %.9g s)\n", alpha, dmax, t_end);
    CHECK(dmax == 0.0);
    /* 2. set between Co-Simulation steps: the continuation changes, not the past */
    double x_at[2][32], x_fin[2][32];
    const double t_set = ref.t0 + 20.0 * ref.dt_out;
    for (int pass = 0; pass < 2; pass++) {
        c = L.fmi2Instantiate("in2", fmi2CoSimulation, L.guid, L.uri, &callbacks, fmi2False,
                              fmi2False);
        CHECK(c != NULL);
        if (c == NULL)
            break;
        CHECK(L.fmi2SetupExperiment(c, fmi2False, 0.0, ref.t0, fmi2False, 0.0) == fmi2OK);
        CHECK(L.fmi2EnterInitializationMode(c) == fmi2OK);
        CHECK(L.fmi2ExitInitializationMode(c) == fmi2OK);
        double t = ref.t0;
        int set = 0;
        for (int k = 0; k < 100000; k++) {
            if (!set && t >= t_set - 1e-9) {
                CHECK(L.fmi2GetReal(c, vr_x, nx, x_at[pass]) == fmi2OK);
                if (pass == 1) {
                    CHECK(L.fmi2SetReal(c, &vr_in[0], 1, &alpha) == fmi2OK);
                    double v = 1.0;
                    CHECK_ERROR_LOGGED(L.fmi2SetReal(c, &vr_prop, 1, &v), "can be set only");
                    break; /* the instance is in Error now: a fresh one for the rest */
                }
                set = 1;
            }
            fmi2Status st = L.fmi2DoStep(c, t, ref.dt_out, fmi2True);
            if (st == fmi2Discard)
                break;
            if (st != fmi2OK)
                break;
            t = ref.t0 + (k + 1) * ref.dt_out;
            fmi2Boolean term = fmi2False;
            if (L.fmi2GetBooleanStatus(c, fmi2Terminated, &term) == fmi2OK && term)
                break;
        }
        if (pass == 0)
            CHECK(L.fmi2GetReal(c, vr_x, nx, x_fin[0]) == fmi2OK);
        L.fmi2FreeInstance(c);
    }
    /* pass 1 again, now going on after the input was set */
    c = L.fmi2Instantiate("in3", fmi2CoSimulation, L.guid, L.uri, &callbacks, fmi2False,
                          fmi2False);
    CHECK(c != NULL);
    if (c != NULL) {
        CHECK(L.fmi2SetupExperiment(c, fmi2False, 0.0, ref.t0, fmi2False, 0.0) == fmi2OK);
        CHECK(L.fmi2EnterInitializationMode(c) == fmi2OK);
        CHECK(L.fmi2ExitInitializationMode(c) == fmi2OK);
        double t = ref.t0;
        int set = 0;
        for (int k = 0; k < 100000; k++) {
            if (!set && t >= t_set - 1e-9) {
                CHECK(L.fmi2GetReal(c, vr_x, nx, x_at[1]) == fmi2OK);
                CHECK(L.fmi2SetReal(c, &vr_in[0], 1, &alpha) == fmi2OK);
                double a = NAN;
                CHECK(L.fmi2GetReal(c, &vr_in[0], 1, &a) == fmi2OK && a == alpha);
                set = 1;
            }
            fmi2Status st = L.fmi2DoStep(c, t, ref.dt_out, fmi2True);
            if (st != fmi2OK)
                break;
            t = ref.t0 + (k + 1) * ref.dt_out;
            fmi2Boolean term = fmi2False;
            if (L.fmi2GetBooleanStatus(c, fmi2Terminated, &term) == fmi2OK && term)
                break;
        }
        CHECK(set);
        CHECK(L.fmi2GetReal(c, vr_x, nx, x_fin[1]) == fmi2OK);
        L.fmi2FreeInstance(c);
    }
    CHECK(memcmp(x_at[0], x_at[1], nx * sizeof(double)) == 0);
    double dv = 0.0;
    for (size_t i = 3; i < 6 && i < nx; i++)
        dv = fmax(dv, fabs(x_fin[1][i] - x_fin[0][i]));
    printf("  alpha set at t = %g s between steps: states there identical, end velocity moved "
           "by %g m/s\n", t_set, dv);
    CHECK(dv > 1.0);
    /* 3. Model Exchange, Continuous-Time Mode: derivatives follow the input at once */
    c = L.fmi2Instantiate("in4", fmi2ModelExchange, L.guid, L.uri, &callbacks, fmi2False,
                          fmi2False);
    CHECK(c != NULL);
    if (c != NULL) {
        fmi2EventInfo ev = {0};
        CHECK(L.fmi2SetupExperiment(c, fmi2False, 0.0, ref.t0, fmi2False, 0.0) == fmi2OK);
        CHECK(L.fmi2EnterInitializationMode(c) == fmi2OK);
        CHECK(L.fmi2ExitInitializationMode(c) == fmi2OK);
        CHECK(L.fmi2NewDiscreteStates(c, &ev) == fmi2OK);
        CHECK(L.fmi2EnterContinuousTimeMode(c) == fmi2OK);
        CHECK(L.fmi2SetTime(c, ref.t0 + 10.0) == fmi2OK);
        double d0[32], d1[32], d2[32], zero = 0.0;
        CHECK(L.fmi2GetDerivatives(c, d0, nx) == fmi2OK);
        CHECK(L.fmi2SetReal(c, &vr_in[0], 1, &alpha) == fmi2OK);
        CHECK(L.fmi2GetDerivatives(c, d1, nx) == fmi2OK);
        CHECK(L.fmi2SetReal(c, &vr_in[0], 1, &zero) == fmi2OK);
        CHECK(L.fmi2GetDerivatives(c, d2, nx) == fmi2OK);
        CHECK(memcmp(d0, d1, nx * sizeof *d0) != 0);
        CHECK(memcmp(d0, d2, nx * sizeof *d0) == 0);
        /* the throttle too: half throttle, less thrust: a smaller mass flow */
        const double half = 0.5;
        CHECK(L.fmi2SetReal(c, &vr_in[3], 1, &half) == fmi2OK);
        CHECK(L.fmi2GetDerivatives(c, d1, nx) == fmi2OK);
        const size_t im = LV_X3_M; /* der(m): the mass is not the last state (the heat loads follow) */
        printf("  ME: der(m) %g kg/s at throttle 1, %g at 0.5\n", d0[im], d1[im]);
        CHECK(fabs(d1[im] - 0.5 * d0[im]) <= 1e-9 * fabs(d0[im]));
        CHECK(L.fmi2Terminate(c) == fmi2OK);
        L.fmi2FreeInstance(c);
    }
    fmu_close(&L);
}

/* The value reference of variable `name` in an unpacked FMU's modelDescription.xml; -1. */
static long md_vr(const fmu_lib *L, const char *name)
{
    char md[PATH_MAX + 32], pat[300];
    snprintf(md, sizeof md, "%s/modelDescription.xml", L->dir);
    FILE *fp = fopen(md, "r");
    if (fp == NULL)
        return -1;
    char *x = calloc(1, 1 << 21);
    long vr = -1;
    if (x != NULL && fread(x, 1, (1 << 21) - 1, fp) > 0) {
        snprintf(pat, sizeof pat, "name=\"%s\" valueReference=\"", name);
        const char *q = strstr(x, pat);
        if (q != NULL)
            vr = strtol(q + strlen(pat), NULL, 10);
    }
    free(x);
    fclose(fp);
    return vr;
}

/* The run parameters (issue 27): the mission's parameters that change a phase are FMI
 * parameters of its FMU (fixed: set before fmi2ExitInitializationMode). Checked on kourou-leo's
 * upper-burn-1 (a child of the ascent):
 *  - "ascent.guidance.kick" moves the ascent's burnout, so the hand-off's time: not offered
 *    (the FMU's start time is the DefaultExperiment's); "upper-burn-1.end.altitude" is;
 *  - set to 115 km in Instantiated, Co-Simulation on the output grid reproduces lv_simulate of
 *    upper-burn-1 after lv_run_set("upper-burn-1.end.altitude") bit for bit, and ends later
 *    than at the mission's 110 km;
 *  - after initialization it is refused (fmi2Error naming it);
 *  - fmi2Reset puts it back: the run then ends where the mission's does. */
/* From Initialization Mode: fmi2ExitInitializationMode, fmi2DoStep by H to the phase's end. */
static int cs_to_end(fmu_lib *L, fmi2Component c, double t0, double H, double *t_end, double *x)
{
    fmi2ValueReference vr_x[7] = {0, 1, 2, 3, 4, 5, 6};
    double t = t0;
    if (L->fmi2ExitInitializationMode(c) != fmi2OK)
        return -1;
    for (int k = 0; k < 100000; k++) {
        fmi2Status st = L->fmi2DoStep(c, t, H, fmi2True);
        if (st == fmi2Discard) {
            L->fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &t);
            break;
        }
        if (st != fmi2OK)
            return -1;
        t = t0 + (k + 1) * H;
        fmi2Boolean term = fmi2False;
        if (L->fmi2GetBooleanStatus(c, fmi2Terminated, &term) == fmi2OK && term)
            break;
    }
    *t_end = t;
    return L->fmi2GetReal(c, vr_x, 7, x) == fmi2OK ? 0 : -1;
}

static void check_run_params(void)
{
    fmu_lib L;
    printf("run parameters (kourou-leo upper-burn-1):\n");
    if (export_fmu("examples/kourou-leo/mission.yaml", "upper-burn-1", "kourou_leo_upper_burn_1",
                   &L) != 0) {
        CHECK(!"export and load kourou-leo upper-burn-1");
        return;
    }
    CHECK(md_vr(&L, "ascent.guidance.kick") == -1);
    const long va = md_vr(&L, "upper-burn-1.end.altitude");
    CHECK(va >= 0);
    if (va < 0) {
        fmu_close(&L);
        return;
    }
    const fmi2ValueReference vr_alt = (fmi2ValueReference)va;
    const double alt = 115000.0; /* m; the mission's 110 km */
    reference ref = {0}, ref0 = {0};
    ref_set_name = "upper-burn-1.end.altitude";
    ref_set_value = alt;
    CHECK(simulate_reference("examples/kourou-leo/mission.yaml", "upper-burn-1", 0.0, &ref) == 0);
    ref_set_name = NULL;
    CHECK(simulate_reference("examples/kourou-leo/mission.yaml", "upper-burn-1", 0.0, &ref0) == 0);
    fmi2Component c = L.fmi2Instantiate("rp", fmi2CoSimulation, L.guid, L.uri, &callbacks,
                                        fmi2False, fmi2False);
    CHECK(c != NULL);
    if (c == NULL) {
        fmu_close(&L);
        return;
    }
    double alt0 = NAN, now = NAN, t_end = NAN, xe[7] = {0};
    CHECK(L.fmi2SetupExperiment(c, fmi2False, 0.0, ref.t0, fmi2False, 0.0) == fmi2OK);
    CHECK(L.fmi2EnterInitializationMode(c) == fmi2OK);
    CHECK(L.fmi2GetReal(c, &vr_alt, 1, &alt0) == fmi2OK && alt0 == 110000.0);
    CHECK(L.fmi2SetReal(c, &vr_alt, 1, &alt) == fmi2OK);
    CHECK(L.fmi2GetReal(c, &vr_alt, 1, &now) == fmi2OK && now == alt);
    CHECK(cs_to_end(&L, c, ref.t0, ref.dt_out, &t_end, xe) == 0);
    double dmax = fabs(t_end - ref.t_end);
    for (size_t i = 0; i < 7; i++)
        dmax = fmax(dmax, fabs(xe[i] - ref.x_end[i]));
    printf("  end.altitude 115 km: ends at t = %.9g s (110 km: %.9g s); CS on the output grid vs "
           "lv_simulate with lv_run_set: max difference %g\n", t_end, ref0.t_end, dmax);
    CHECK(dmax == 0.0);
    CHECK(ref.t_end > ref0.t_end + 0.1);
    {   /* after initialization (StepComplete): refused, naming it */
        fmi2Component c2 = L.fmi2Instantiate("rp2", fmi2CoSimulation, L.guid, L.uri,
                                             &callbacks, fmi2False, fmi2False);
        CHECK(c2 != NULL);
        if (c2 != NULL) {
            CHECK(L.fmi2SetupExperiment(c2, fmi2False, 0.0, ref0.t0, fmi2False, 0.0) == fmi2OK);
            CHECK(L.fmi2EnterInitializationMode(c2) == fmi2OK);
            CHECK(L.fmi2ExitInitializationMode(c2) == fmi2OK);
            CHECK_ERROR_LOGGED(L.fmi2SetReal(c2, &vr_alt, 1, &alt), "can be set only before");
            CHECK(strstr(log_text, "upper-burn-1.end.altitude") != NULL);
            L.fmi2FreeInstance(c2);
        }
    }
    {   /* a value that moves the hand-off (the ascent's throttle floor raised from 0.04 to 0.9:
         * its q and g limits then end the ascent 4 s later; a breaker's case) is refused, not
         * flown from another time than the FMU's start time */
        const long vt = md_vr(&L, "booster-engine.throttle_min");
        CHECK(vt >= 0);
        fmi2Component c3 = L.fmi2Instantiate("rp3", fmi2CoSimulation, L.guid, L.uri,
                                             &callbacks, fmi2False, fmi2False);
        CHECK(c3 != NULL);
        if (c3 != NULL && vt >= 0) {
            const fmi2ValueReference vr_t = (fmi2ValueReference)vt;
            const double tmin = 0.9;
            CHECK(L.fmi2SetupExperiment(c3, fmi2False, 0.0, ref0.t0, fmi2False, 0.0) == fmi2OK);
            CHECK(L.fmi2EnterInitializationMode(c3) == fmi2OK);
            CHECK_ERROR_LOGGED(L.fmi2SetReal(c3, &vr_t, 1, &tmin), "not at the FMU's start time");
        }
        if (c3 != NULL)
            L.fmi2FreeInstance(c3);
    }
    CHECK(L.fmi2Reset(c) == fmi2OK);
    CHECK(L.fmi2SetupExperiment(c, fmi2False, 0.0, ref0.t0, fmi2False, 0.0) == fmi2OK);
    CHECK(L.fmi2EnterInitializationMode(c) == fmi2OK);
    CHECK(L.fmi2GetReal(c, &vr_alt, 1, &now) == fmi2OK && now == alt0);
    CHECK(cs_to_end(&L, c, ref0.t0, ref0.dt_out, &t_end, xe) == 0);
    dmax = fabs(t_end - ref0.t_end);
    for (size_t i = 0; i < 7; i++)
        dmax = fmax(dmax, fabs(xe[i] - ref0.x_end[i]));
    printf("  after fmi2Reset: max difference %g from the mission's run\n", dmax);
    CHECK(dmax == 0.0);
    L.fmi2FreeInstance(c);
    fmu_close(&L);
}

int main(void)
{
    if (getenv("LV_SOURCE_DIR") == NULL) {
        fprintf(stderr, "LV_SOURCE_DIR is not set\n");
        return 1;
    }
    /* A root phase: a gravity turn with time events (the end of the rise and of the kick),
     * ending at burnout (a state event of the model). Its throttle law (q_max, g_limit) makes
     * the right-hand side non-smooth where the limits switch, without events there: a fixed-step
     * RK4 meets those switches inside its steps, and its error wanders with h (measured against
     * lv_simulate at 1e-12: 0.08 m at h = 0.01 s, 4.5 m at 0.002 s, 1.5 mm at 0.001 s), hence
     * the looser bound. lv_simulate at the mission's 1e-8 is itself 2.5 m from the 1e-12 run. */
    check_phase("examples/kourou-leo/mission.yaml", "ascent", "kourou_leo_ascent", 0.01, 10.0,
                0.25, 1e-3);
    /* A child phase: from the ascent's final state (the FMU runs the ascent when instantiated),
     * ending at 110 km (a named end: a state event); smooth, so RK4 agrees to centimetres. */
    check_phase("examples/kourou-leo/mission.yaml", "upper-burn-1", "kourou_leo_upper_burn_1",
                0.01, 0.01, 1e-4, 1e-6);
    /* A grandchild with an end on time (a time event ends it) after a long coast: h = 1 s. */
    check_phase("examples/kourou-leo/mission.yaml", "orbit-coast", "kourou_leo_orbit_coast", 1.0,
                1.0, 1e-3, 1e-9);
    /* FMU states across instances, kinds and FMUs (two FMUs loaded at once) */
    {
        fmu_lib A, B;
        reference ra = {0}, rb = {0};
        CHECK(simulate_reference("examples/kourou-leo/mission.yaml", "ascent", 0.0, &ra) == 0);
        CHECK(simulate_reference("examples/kourou-leo/mission.yaml", "upper-burn-1", 0.0,
                                 &rb) == 0);
        if (export_fmu("examples/kourou-leo/mission.yaml", "ascent", "kourou_leo_ascent", &A) ==
                0 &&
            export_fmu("examples/kourou-leo/mission.yaml", "upper-burn-1",
                       "kourou_leo_upper_burn_1", &B) == 0) {
            printf("FMU states across instances and FMUs:\n");
            check_foreign_states(&A, &B, ra.t0, rb.t0);
        } else {
            CHECK(!"export and load");
        }
        fmu_close(&A);
        fmu_close(&B);
    }
    check_inputs();
    check_run_params();
    /* every phase above ended once the compliance checker's way (one run of two) */
    printf("Model Exchange ends by the compliance checker's sequence: %d of %d runs\n",
           checker_sequences, me_runs);
    CHECK(checker_sequences >= 3);
    return check_report("test_fmu");
}
