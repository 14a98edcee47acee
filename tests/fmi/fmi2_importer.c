/* fmi2_importer.c - an FMI 2.0 importer written from the standard's text only (FMI 2.0.4,
 * "Functional Mock-up Interface for Model Exchange and Co-Simulation"), separate from the one
 * tests/unit/test_fmu.c has (written alongside the FMU): it includes nothing of lvsim, declares
 * the types and functions itself from the specification's section 2.1 (fmi2TypesPlatform.h,
 * fmi2FunctionTypes.h as documented), reads modelDescription.xml with a reader of its own for
 * the few attributes it needs (section 2.2), loads binaries/linux64/<modelIdentifier>.so with
 * dlopen (section 2.3) and simulates:
 *
 *   me-euler H   Model Exchange by the pseudo-code of section 3.2.4: explicit Euler with the
 *                fixed step H, time events at nextEventTime, state events detected by a sign
 *                change of an event indicator at the end of a step (no location inside it),
 *                fmi2CompletedIntegratorStep after every step, the event iteration
 *                "while newDiscreteStatesNeeded and not terminateSimulation", fmi2Terminate;
 *   me-rk4 H     the same loop with the classical Runge-Kutta step in place of Euler's (the
 *                four stages evaluated with fmi2SetTime/fmi2SetContinuousStates/
 *                fmi2GetDerivatives; section 3.2.4 leaves the integrator to the environment);
 *   cs H         Co-Simulation by section 4.2.5: fmi2DoStep with the communication step H until
 *                the stop time or until the slave ends the run (fmi2Discard, then
 *                fmi2GetBooleanStatus(fmi2Terminated) and fmi2GetRealStatus(
 *                fmi2LastSuccessfulTime), section 4.2.3).
 *
 * Usage: fmi2_importer DIR MODE H
 * DIR is the unpacked FMU. It prints "t_end T", then "x NAME VALUE" and "xdot NAME VALUE" for
 * each continuous state at the end (the derivative variables read with fmi2GetReal), in Model
 * Exchange "xdot_step NAME VALUE", the derivatives at the start of the last step (those the
 * step integrated with before the event at its end; Co-Simulation: xdot again), and
 * "steps N events E". Exit status 0 on a run that ended (stop time or terminateSimulation),
 * 1 on any other outcome, with the reason on stderr.
 */
#define _XOPEN_SOURCE 700 /* realpath */
#include <dlfcn.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- FMI 2.0 types (section 2.1.2, fmi2TypesPlatform.h; 2.1.3 to 2.1.9, fmi2FunctionTypes.h) */

typedef void *fmi2Component;
typedef void *fmi2ComponentEnvironment;
typedef void *fmi2FMUstate;
typedef unsigned int fmi2ValueReference;
typedef double fmi2Real;
typedef int fmi2Integer;
typedef int fmi2Boolean;
typedef char fmi2Char;
typedef const fmi2Char *fmi2String;
#define fmi2True 1
#define fmi2False 0

typedef enum { fmi2OK, fmi2Warning, fmi2Discard, fmi2Error, fmi2Fatal, fmi2Pending } fmi2Status;
typedef enum { fmi2ModelExchange, fmi2CoSimulation } fmi2Type;
typedef enum {
    fmi2DoStepStatus,
    fmi2PendingStatus,
    fmi2LastSuccessfulTime,
    fmi2Terminated
} fmi2StatusKind;

typedef void (*fmi2CallbackLogger)(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String,
                                   fmi2String, ...);
typedef void *(*fmi2CallbackAllocateMemory)(size_t, size_t);
typedef void (*fmi2CallbackFreeMemory)(void *);
typedef void (*fmi2StepFinished)(fmi2ComponentEnvironment, fmi2Status);
typedef struct {
    fmi2CallbackLogger logger;
    fmi2CallbackAllocateMemory allocateMemory;
    fmi2CallbackFreeMemory freeMemory;
    fmi2StepFinished stepFinished;
    fmi2ComponentEnvironment componentEnvironment;
} fmi2CallbackFunctions;

typedef struct {
    fmi2Boolean newDiscreteStatesNeeded;
    fmi2Boolean terminateSimulation;
    fmi2Boolean nominalsOfContinuousStatesChanged;
    fmi2Boolean valuesOfContinuousStatesChanged;
    fmi2Boolean nextEventTimeDefined;
    fmi2Real nextEventTime;
} fmi2EventInfo;

typedef struct api {
    fmi2Component (*Instantiate)(fmi2String, fmi2Type, fmi2String, fmi2String,
                                 const fmi2CallbackFunctions *, fmi2Boolean, fmi2Boolean);
    void (*FreeInstance)(fmi2Component);
    fmi2Status (*SetupExperiment)(fmi2Component, fmi2Boolean, fmi2Real, fmi2Real, fmi2Boolean,
                                  fmi2Real);
    fmi2Status (*EnterInitializationMode)(fmi2Component);
    fmi2Status (*ExitInitializationMode)(fmi2Component);
    fmi2Status (*Terminate)(fmi2Component);
    fmi2Status (*GetReal)(fmi2Component, const fmi2ValueReference[], size_t, fmi2Real[]);
    /* Model Exchange (section 3.2.1) */
    fmi2Status (*EnterEventMode)(fmi2Component);
    fmi2Status (*NewDiscreteStates)(fmi2Component, fmi2EventInfo *);
    fmi2Status (*EnterContinuousTimeMode)(fmi2Component);
    fmi2Status (*CompletedIntegratorStep)(fmi2Component, fmi2Boolean, fmi2Boolean *,
                                          fmi2Boolean *);
    fmi2Status (*SetTime)(fmi2Component, fmi2Real);
    fmi2Status (*SetContinuousStates)(fmi2Component, const fmi2Real[], size_t);
    fmi2Status (*GetDerivatives)(fmi2Component, fmi2Real[], size_t);
    fmi2Status (*GetEventIndicators)(fmi2Component, fmi2Real[], size_t);
    fmi2Status (*GetContinuousStates)(fmi2Component, fmi2Real[], size_t);
    /* Co-Simulation (section 4.2) */
    fmi2Status (*DoStep)(fmi2Component, fmi2Real, fmi2Real, fmi2Boolean);
    fmi2Status (*GetRealStatus)(fmi2Component, fmi2StatusKind, fmi2Real *);
    fmi2Status (*GetBooleanStatus)(fmi2Component, fmi2StatusKind, fmi2Boolean *);
} api;

/* ---- modelDescription.xml: the attributes this importer needs ---------------------------- */

#define MAXV 4096
typedef struct var {
    char name[128];
    unsigned vr;
    int derivative_of; /* 1-based index of the state it is the derivative of; 0: none */
} var;

typedef struct md {
    char guid[128], id_me[128], id_cs[128];
    size_t ni;
    double t_start, t_stop, step, tol;
    int has_stop, has_step, has_tol;
    var v[MAXV];
    size_t nv;
} md;

static char *slurp(const char *path)
{
    FILE *fp = fopen(path, "rb");
    if (fp == NULL)
        return NULL;
    fseek(fp, 0, SEEK_END);
    long n = ftell(fp);
    fseek(fp, 0, SEEK_SET);
    char *b = malloc((size_t)n + 1);
    if (b == NULL || fread(b, 1, (size_t)n, fp) != (size_t)n) {
        fclose(fp);
        free(b);
        return NULL;
    }
    b[n] = '\0';
    fclose(fp);
    return b;
}

/* The value of attribute `name` of the element starting at el (up to its '>'), unescaped for
 * the five predefined entities; 0 if absent. */
static int attr(const char *el, const char *name, char *out, size_t cap)
{
    const char *end = strchr(el, '>');
    size_t nl = strlen(name);
    for (const char *p = el; p != NULL && p < end; p++) {
        if ((p[-1] == ' ' || p[-1] == '\n' || p[-1] == '\t' || p[-1] == '\r') &&
            strncmp(p, name, nl) == 0 && p[nl] == '=' && (p[nl + 1] == '"' || p[nl + 1] == '\'')) {
            const char q = p[nl + 1];
            const char *s = p + nl + 2;
            size_t k = 0;
            while (*s && *s != q && k + 1 < cap) {
                static const struct { const char *e; char c; } ents[] = {
                    {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}};
                int done = 0;
                for (size_t i = 0; i < 5 && !done; i++)
                    if (strncmp(s, ents[i].e, strlen(ents[i].e)) == 0) {
                        out[k++] = ents[i].c;
                        s += strlen(ents[i].e);
                        done = 1;
                    }
                if (!done)
                    out[k++] = *s++;
            }
            out[k] = '\0';
            return 1;
        }
    }
    return 0;
}

/* The first element <tag ...> (tag followed by a blank, '>' or '/'), from p. */
static const char *element(const char *p, const char *tag)
{
    size_t n = strlen(tag);
    for (const char *q = strstr(p, tag); q != NULL; q = strstr(q + 1, tag))
        if (q > p && q[-1] == '<' && (q[n] == ' ' || q[n] == '>' || q[n] == '/' || q[n] == '\n' ||
                                      q[n] == '\t' || q[n] == '\r'))
            return q;
    return NULL;
}

static int read_md(const char *dir, md *m)
{
    char path[PATH_MAX], buf[256];
    snprintf(path, sizeof path, "%s/modelDescription.xml", dir);
    char *x = slurp(path);
    if (x == NULL) {
        fprintf(stderr, "cannot read %s\n", path);
        return -1;
    }
    memset(m, 0, sizeof *m);
    const char *e = element(x, "fmiModelDescription");
    if (e == NULL || !attr(e, "guid", m->guid, sizeof m->guid)) {
        fprintf(stderr, "%s: no fmiModelDescription guid\n", path);
        free(x);
        return -1;
    }
    if (attr(e, "numberOfEventIndicators", buf, sizeof buf))
        m->ni = strtoul(buf, NULL, 10);
    if ((e = element(x, "ModelExchange")) != NULL)
        attr(e, "modelIdentifier", m->id_me, sizeof m->id_me);
    if ((e = element(x, "CoSimulation")) != NULL)
        attr(e, "modelIdentifier", m->id_cs, sizeof m->id_cs);
    if ((e = element(x, "DefaultExperiment")) != NULL) {
        if (attr(e, "startTime", buf, sizeof buf))
            m->t_start = strtod(buf, NULL);
        if ((m->has_stop = attr(e, "stopTime", buf, sizeof buf)))
            m->t_stop = strtod(buf, NULL);
        if ((m->has_step = attr(e, "stepSize", buf, sizeof buf)))
            m->step = strtod(buf, NULL);
        if ((m->has_tol = attr(e, "tolerance", buf, sizeof buf)))
            m->tol = strtod(buf, NULL);
    }
    /* ModelVariables, in order (the index a derivative= attribute names, section 2.2.7) */
    const char *mv = element(x, "ModelVariables");
    for (const char *p = mv ? element(mv, "ScalarVariable") : NULL; p != NULL;
         p = element(p + 1, "ScalarVariable")) {
        if (m->nv == MAXV) {
            fprintf(stderr, "more than %d variables\n", MAXV);
            free(x);
            return -1;
        }
        var *v = &m->v[m->nv++];
        attr(p, "name", v->name, sizeof v->name);
        attr(p, "valueReference", buf, sizeof buf);
        v->vr = (unsigned)strtoul(buf, NULL, 10);
        const char *close = strstr(p, "</ScalarVariable>");
        const char *r = element(p, "Real");
        if (r != NULL && close != NULL && r < close && attr(r, "derivative", buf, sizeof buf))
            v->derivative_of = atoi(buf);
    }
    free(x);
    return 0;
}

/* ---- the run ------------------------------------------------------------------------------ */

static int verbose;
static void logger(fmi2ComponentEnvironment env, fmi2String inst, fmi2Status st, fmi2String cat,
                   fmi2String msg, ...)
{
    (void)env;
    if (!verbose && st < fmi2Discard)
        return;
    va_list ap;
    va_start(ap, msg);
    fprintf(stderr, "[%s %d %s] ", inst, (int)st, cat);
    vfprintf(stderr, msg, ap);
    fputc('\n', stderr);
    va_end(ap);
}

static void *load(void *h, const char *name)
{
    void *p = dlsym(h, name);
    if (p == NULL)
        fprintf(stderr, "the binary has no %s\n", name);
    return p;
}

#define OK(call)                                                                                  \
    do {                                                                                          \
        fmi2Status st_ = (call);                                                                  \
        if (st_ > fmi2Warning) {                                                                  \
            fprintf(stderr, "%s returned %d at t = %.9g\n", #call, (int)st_, t);                  \
            goto fail;                                                                            \
        }                                                                                         \
    } while (0)

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: fmi2_importer DIR me-euler|me-rk4|cs H\n");
        return 2;
    }
    verbose = getenv("FMI2_IMPORTER_VERBOSE") != NULL;
    const char *dir = argv[1], *mode = argv[2];
    const double H = strtod(argv[3], NULL);
    const int cs = strcmp(mode, "cs") == 0, rk4 = strcmp(mode, "me-rk4") == 0;
    if (!(H > 0.0) || (!cs && !rk4 && strcmp(mode, "me-euler") != 0)) {
        fprintf(stderr, "bad mode or step\n");
        return 2;
    }
    static md m;
    if (read_md(dir, &m) != 0)
        return 1;
    const char *id = cs ? m.id_cs : m.id_me;
    if (!id[0]) {
        fprintf(stderr, "the FMU has no %s\n", cs ? "CoSimulation" : "ModelExchange");
        return 1;
    }
    /* states: the variables that a derivative names (section 2.2.8, Derivatives) */
    size_t nx = 0;
    static fmi2ValueReference vr_x[MAXV], vr_dx[MAXV];
    static const char *names[MAXV];
    for (size_t i = 0; i < m.nv; i++)
        if (m.v[i].derivative_of > 0 && (size_t)m.v[i].derivative_of <= m.nv) {
            vr_x[nx] = m.v[m.v[i].derivative_of - 1].vr;
            names[nx] = m.v[m.v[i].derivative_of - 1].name;
            vr_dx[nx++] = m.v[i].vr;
        }
    char so[PATH_MAX], uri[PATH_MAX + 32], rdir[PATH_MAX];
    snprintf(so, sizeof so, "%s/binaries/linux64/%s.so", dir, id);
    if (realpath(dir, rdir) == NULL) {
        fprintf(stderr, "no folder %s\n", dir);
        return 1;
    }
    snprintf(uri, sizeof uri, "file://%s/resources", rdir);
    void *h = dlopen(so, RTLD_NOW | RTLD_LOCAL);
    if (h == NULL) {
        fprintf(stderr, "dlopen %s: %s\n", so, dlerror());
        return 1;
    }
    api f;
    memset(&f, 0, sizeof f);
    int missing = 0;
#define L(fld) missing |= (*(void **)&f.fld = load(h, "fmi2" #fld)) == NULL
    L(Instantiate); L(FreeInstance); L(SetupExperiment); L(EnterInitializationMode);
    L(ExitInitializationMode); L(Terminate); L(GetReal);
    if (cs) {
        L(DoStep); L(GetRealStatus); L(GetBooleanStatus);
    } else {
        L(EnterEventMode); L(NewDiscreteStates); L(EnterContinuousTimeMode);
        L(CompletedIntegratorStep); L(SetTime); L(SetContinuousStates); L(GetDerivatives);
        L(GetEventIndicators); L(GetContinuousStates);
    }
#undef L
    if (missing)
        return 1;
    const fmi2CallbackFunctions cb = {logger, calloc, free, NULL, NULL};
    double t = m.t_start;
    const double t_end = m.has_stop ? m.t_stop : INFINITY;
    long steps = 0, events = 0;
    int ended = 0;
    double *x = calloc(nx + 1, sizeof *x), *dx = calloc(nx + 1, sizeof *dx);
    double *k = calloc(4 * (nx + 1), sizeof *k), *xs = calloc(nx + 1, sizeof *xs);
    double *z = calloc(m.ni + 1, sizeof *z), *zp = calloc(m.ni + 1, sizeof *zp);
    double *dx_step = calloc(nx + 1, sizeof *dx_step); /* derivatives at the last step's start */
    fmi2Component c = f.Instantiate("importer", cs ? fmi2CoSimulation : fmi2ModelExchange,
                                    m.guid, uri, &cb, fmi2False, verbose);
    if (c == NULL) {
        fprintf(stderr, "fmi2Instantiate returned NULL\n");
        return 1;
    }
    OK(f.SetupExperiment(c, m.has_tol, m.tol, m.t_start, m.has_stop, t_end));
    OK(f.EnterInitializationMode(c));
    OK(f.ExitInitializationMode(c));
    if (cs) {
        /* section 4.2.5: the communication loop */
        while (t < t_end) {
            const double hs = fmin(H, t_end - t);
            fmi2Status st = f.DoStep(c, t, hs, fmi2True);
            steps++;
            if (st == fmi2Discard) {
                fmi2Boolean term = fmi2False;
                OK(f.GetBooleanStatus(c, fmi2Terminated, &term));
                if (!term) {
                    fprintf(stderr, "fmi2DoStep discarded without fmi2Terminated\n");
                    goto fail;
                }
                OK(f.GetRealStatus(c, fmi2LastSuccessfulTime, &t));
                ended = 1;
                break;
            }
            OK(st);
            t = (t_end - (t + hs) < 1e-12 * fmax(1.0, fabs(t_end))) ? t_end : t + hs;
            fmi2Boolean term = fmi2False;
            /* the slave may end the run exactly at a communication point */
            if (f.GetBooleanStatus(c, fmi2Terminated, &term) == fmi2OK && term) {
                ended = 1;
                break;
            }
        }
        if (t >= t_end)
            ended = 1;
    } else {
        /* section 3.2.4: the event iteration after initialization */
        fmi2EventInfo ev = {fmi2True, fmi2False, fmi2False, fmi2False, fmi2False, 0.0};
        while (ev.newDiscreteStatesNeeded && !ev.terminateSimulation)
            OK(f.NewDiscreteStates(c, &ev));
        if (ev.terminateSimulation) {
            ended = 1;
            goto terminate;
        }
        OK(f.EnterContinuousTimeMode(c));
        OK(f.GetContinuousStates(c, x, nx));
        if (m.ni > 0)
            OK(f.GetEventIndicators(c, zp, m.ni));
        double t_next = ev.nextEventTimeDefined ? fmin(ev.nextEventTime, t_end) : t_end;
        while (t < t_end) {
            OK(f.GetDerivatives(c, dx, nx));
            memcpy(dx_step, dx, nx * sizeof *dx);
            const double hs = fmin(H, t_next - t);
            const double t1 = (t_next - (t + hs) <= 1e-13 * fmax(1.0, fabs(t_next))) ? t_next
                                                                                     : t + hs;
            if (!rk4) {
                for (size_t i = 0; i < nx; i++)
                    x[i] += hs * dx[i];
            } else {
                /* k1 = dx; k2, k3 at t + h/2, k4 at t + h */
                double *k2 = k, *k3 = k + nx + 1, *k4 = k + 2 * (nx + 1);
                for (size_t i = 0; i < nx; i++)
                    xs[i] = x[i] + 0.5 * hs * dx[i];
                OK(f.SetTime(c, t + 0.5 * hs));
                OK(f.SetContinuousStates(c, xs, nx));
                OK(f.GetDerivatives(c, k2, nx));
                for (size_t i = 0; i < nx; i++)
                    xs[i] = x[i] + 0.5 * hs * k2[i];
                OK(f.SetContinuousStates(c, xs, nx));
                OK(f.GetDerivatives(c, k3, nx));
                for (size_t i = 0; i < nx; i++)
                    xs[i] = x[i] + hs * k3[i];
                OK(f.SetTime(c, t1));
                OK(f.SetContinuousStates(c, xs, nx));
                OK(f.GetDerivatives(c, k4, nx));
                for (size_t i = 0; i < nx; i++)
                    x[i] += hs / 6.0 * (dx[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            }
            t = t1;
            OK(f.SetTime(c, t));
            OK(f.SetContinuousStates(c, x, nx));
            steps++;
            int state_event = 0;
            if (m.ni > 0) {
                OK(f.GetEventIndicators(c, z, m.ni));
                /* a state event: an indicator changed its domain, z > 0 or z <= 0 (section 3.1) */
                for (size_t i = 0; i < m.ni; i++)
                    if ((z[i] > 0.0) != (zp[i] > 0.0))
                        state_event = 1;
            }
            const int time_event = ev.nextEventTimeDefined && t >= ev.nextEventTime;
            fmi2Boolean enter = fmi2False, term = fmi2False;
            OK(f.CompletedIntegratorStep(c, fmi2True, &enter, &term));
            if (term) {
                ended = 1;
                break;
            }
            if (enter || state_event || time_event) {
                events++;
                OK(f.EnterEventMode(c));
                ev.newDiscreteStatesNeeded = fmi2True;
                ev.terminateSimulation = fmi2False;
                while (ev.newDiscreteStatesNeeded && !ev.terminateSimulation)
                    OK(f.NewDiscreteStates(c, &ev));
                if (ev.terminateSimulation) {
                    ended = 1;
                    break;
                }
                OK(f.EnterContinuousTimeMode(c));
                if (ev.valuesOfContinuousStatesChanged)
                    OK(f.GetContinuousStates(c, x, nx));
                t_next = ev.nextEventTimeDefined ? fmin(ev.nextEventTime, t_end) : t_end;
                if (m.ni > 0)
                    OK(f.GetEventIndicators(c, z, m.ni));
            }
            if (m.ni > 0)
                memcpy(zp, z, m.ni * sizeof *z);
        }
        if (t >= t_end)
            ended = 1;
    }
terminate:
    OK(f.Terminate(c));
    /* final values (section 2.1.7: fmi2GetReal is allowed in Terminated) */
    OK(f.GetReal(c, vr_x, nx, x));
    OK(f.GetReal(c, vr_dx, nx, dx));
    printf("t_end %.17g\n", t);
    for (size_t i = 0; i < nx; i++)
        printf("x %s %.17g\nxdot %s %.17g\nxdot_step %s %.17g\n", names[i], x[i], names[i],
               dx[i], names[i], cs ? dx[i] : dx_step[i]);
    printf("steps %ld events %ld\n", steps, events);
    f.FreeInstance(c);
    dlclose(h);
    free(x), free(dx), free(k), free(xs), free(z), free(zp), free(dx_step);
    return ended ? 0 : 1;
fail:
    f.FreeInstance(c);
    dlclose(h);
    return 1;
}
