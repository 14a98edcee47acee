/* fuzz_fmu.c - libFuzzer target: an FMU's fmi2 functions (src/fmi/fmu.c, linked in) called as
 * an importer might, in any order and with any arguments: the bytes are decoded into a
 * sequence of calls on up to two instances of the FMU of examples/sounding-rocket's first
 * phase (exported by `lvsim fmu` at build time, LV_FUZZ_FMU_DIR: fuzz/fuzz.cmake). Every call
 * must return a status (fmi2OK .. fmi2Pending) and log, if at all, a message that is a format
 * without arguments ('%' doubled, FMI 2.0 section 2.1.5); never a crash, a leak or a sanitizer
 * report. Out-of-order calls, unknown value references, wrong array lengths, NaN and infinite
 * times, freed instances and states are all part of the game: the FMU refuses them itself.
 *
 * Input: byte 0 picks the first instance's type (bit 0: Co-Simulation) and its logging; then
 * one byte per call (which function) followed by its arguments' bytes (reader below).
 * Seeds: fuzz/corpus/fmu (fuzz/make_seeds.sh: the standard's calling sequences, 3.2.4 and
 * 4.2.4). `make fuzz`. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi/fmi2.h"
#define LV_FMI2_DECLARE(ret, name, args) ret name args;
LV_FMI2_FUNCTIONS(LV_FMI2_DECLARE)
#undef LV_FMI2_DECLARE

#ifndef LV_FUZZ_FMU_DIR
#error "LV_FUZZ_FMU_DIR: the unpacked FMU"
#endif

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* The FMU's description, read once from resources/lvsim-fmu.txt. */
static char guid[128];
static char uri[4200];
static size_t nx, np, ny, ni; /* states, parameters, outputs, event indicators */

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    char path[4200], line[512];
    snprintf(path, sizeof path, "%s/resources/lvsim-fmu.txt", LV_FUZZ_FMU_DIR);
    FILE *fp = fopen(path, "r");
    if (fp == NULL) {
        perror(path);
        abort();
    }
    while (fgets(line, sizeof line, fp) != NULL) {
        line[strcspn(line, "\n")] = '\0';
        if (strncmp(line, "guid ", 5) == 0)
            snprintf(guid, sizeof guid, "%s", line + 5);
        else if (strncmp(line, "states ", 7) == 0)
            nx = (size_t)atol(line + 7);
        else if (strncmp(line, "parameters ", 11) == 0)
            np = (size_t)atol(line + 11);
        else if (strncmp(line, "outputs ", 8) == 0)
            ny = (size_t)atol(line + 8);
        else if (strncmp(line, "event_indicators ", 17) == 0)
            ni = (size_t)atol(line + 17);
    }
    fclose(fp);
    if (guid[0] == '\0' || nx == 0) {
        fprintf(stderr, "%s: no guid or no states\n", path);
        abort();
    }
    snprintf(uri, sizeof uri, "file://%s/resources", LV_FUZZ_FMU_DIR);
    return 0;
}

/* ---- the importer's callbacks ---------------------------------------------------------- */

/* The message must be a format without conversions: every '%' doubled. */
static void logger(fmi2ComponentEnvironment env, fmi2String instance, fmi2Status status,
                   fmi2String category, fmi2String message, ...)
{
    (void)env;
    if (instance == NULL || category == NULL || message == NULL || (unsigned)status > fmi2Pending)
        __builtin_trap();
    for (const char *p = message; *p; p++)
        if (*p == '%' && *++p != '%')
            __builtin_trap();
    char buf[256];
    va_list ap;
    va_start(ap, message);
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wformat-nonliteral"
    vsnprintf(buf, sizeof buf, message, ap); /* an importer that formats it, as FMI says */
#pragma GCC diagnostic pop
    va_end(ap);
}

static const fmi2CallbackFunctions callbacks = {logger, calloc, free, NULL, NULL};
static const fmi2CallbackFunctions no_logger = {NULL, calloc, free, NULL, NULL};

/* ---- the byte reader ------------------------------------------------------------------- */

typedef struct reader {
    const uint8_t *p;
    size_t n;
} reader;

static unsigned u8(reader *r)
{
    if (r->n == 0)
        return 0;
    r->n--;
    return *r->p++;
}

static unsigned u32(reader *r)
{
    unsigned v = 0;
    for (int i = 0; i < 4; i++)
        v = v << 8 | u8(r);
    return v;
}

/* A real: mostly the values that matter (0, the phase's times, huge, tiny, NaN, infinite),
 * else 8 raw bytes. */
static double real(reader *r)
{
    static const double table[] = {0.0, 1.0, -1.0, 0.5, 1e-9, 1e-300, 5e-324, 10.0, 30.0, 60.0,
                                   59.999999, 60.000001, 1e6, 1e300, -1e300, 100.0, 1000.0,
                                   150.0, 350.0, -0.0, 2.0, 0.1};
    const unsigned sel = u8(r);
    const size_t nt = sizeof table / sizeof table[0];
    if (sel < nt)
        return table[sel];
    if (sel == 250)
        return NAN;
    if (sel == 251)
        return INFINITY;
    if (sel == 252)
        return -INFINITY;
    if (sel < 240)
        return (double)(sel - nt) * 0.25;
    double d;
    uint8_t b[8];
    for (int i = 0; i < 8; i++)
        b[i] = (uint8_t)u8(r);
    memcpy(&d, b, sizeof d);
    return d;
}

/* A value reference: mostly one of the FMU's (0 .. 2 nx + np + ny - 1), else any. */
static fmi2ValueReference vref(reader *r)
{
    const unsigned sel = u8(r);
    const size_t n_real = 2 * nx + np + ny;
    if (sel < 250)
        return (fmi2ValueReference)(sel % (n_real + 1));
    return (fmi2ValueReference)u32(r);
}

/* An array length: the right one mostly, else 0, one more, one less or a small number. */
static size_t length(reader *r, size_t right)
{
    const unsigned sel = u8(r);
    switch (sel & 7) {
    case 1: return 0;
    case 2: return right + 1;
    case 3: return right > 0 ? right - 1 : 0;
    case 4: return sel >> 3;
    default: return right;
    }
}

/* ---- the calls --------------------------------------------------------------------------- */

#define N_INST 2
#define N_STATE 4
#define MAX_CALLS 200

typedef struct session {
    fmi2Component inst[N_INST];   /* may be freed: the FMU must refuse it, not read it */
    int live[N_INST];             /* not yet freed by the harness */
    fmi2FMUstate state[N_STATE];  /* may be freed or another instance's */
    int instantiations;
} session;

static void status_ok(fmi2Status st)
{
    if ((unsigned)st > fmi2Pending)
        __builtin_trap();
}

static void instantiate(session *s, int k, unsigned how)
{
    if (s->live[k]) {
        fmi2FreeInstance(s->inst[k]);
        s->live[k] = 0;
    }
    if (s->instantiations++ >= 4) /* each loads the mission: a few per input */
        return;
    const fmi2Type type = (how & 1) ? fmi2CoSimulation : fmi2ModelExchange;
    const char *name = (how & 8) ? "" : k ? "second" : "first";
    const char *g = (how & 16) ? "{00000000-0000-0000-0000-000000000000}" : guid;
    const char *loc = (how & 32) ? "http://example.org/resources" : uri;
    const fmi2Type t = (how & 64) ? (fmi2Type)7 : type;
    fmi2Component c = fmi2Instantiate(name, t, g, loc, (how & 128) ? &no_logger : &callbacks,
                                      fmi2False, (how & 2) != 0);
    if (c != NULL) {
        s->inst[k] = c;
        s->live[k] = 1;
    }
}

static void one_call(session *s, reader *r)
{
    const unsigned op = u8(r), who = u8(r);
    const int k = (int)(who & 1);
    fmi2Component c = s->inst[k]; /* NULL, live or freed */
    fmi2FMUstate *slot = &s->state[(who >> 1) % N_STATE];
    fmi2ValueReference vr[8];
    double v[8];
    fmi2Integer iv[8];
    fmi2Boolean bv[8];
    fmi2String sv[8];
    size_t n;
    double *buf;
    switch (op % 34) {
    case 0:
        instantiate(s, k, u8(r));
        break;
    case 1:
        if (s->live[k]) { /* freed once; the pointer stays for the calls that follow */
            fmi2FreeInstance(c);
            s->live[k] = 0;
        }
        break;
    case 2: {
        const int tol_def = (int)(u8(r) & 1);
        const double tol = real(r), t0 = real(r);
        const int stop_def = (int)(u8(r) & 1);
        status_ok(fmi2SetupExperiment(c, tol_def, tol, t0, stop_def, real(r)));
        break;
    }
    case 3: status_ok(fmi2EnterInitializationMode(c)); break;
    case 4: status_ok(fmi2ExitInitializationMode(c)); break;
    case 5: status_ok(fmi2Terminate(c)); break;
    case 6: status_ok(fmi2Reset(c)); break;
    case 7:
    case 8:
        n = u8(r) % 9;
        for (size_t i = 0; i < n; i++)
            vr[i] = vref(r);
        if (op % 34 == 7) {
            buf = malloc(n * sizeof *buf + 1);
            status_ok(fmi2GetReal(c, n ? vr : NULL, n, n ? buf : NULL));
            free(buf);
        } else {
            for (size_t i = 0; i < n; i++)
                v[i] = real(r);
            status_ok(fmi2SetReal(c, vr, n, v));
        }
        break;
    case 9:
        n = u8(r) % 4;
        for (size_t i = 0; i < n; i++) {
            vr[i] = vref(r);
            iv[i] = (fmi2Integer)u32(r);
            bv[i] = (fmi2Boolean)u8(r);
            sv[i] = "x";
        }
        switch (u8(r) % 6) {
        case 0: status_ok(fmi2GetInteger(c, vr, n, iv)); break;
        case 1: status_ok(fmi2GetBoolean(c, vr, n, bv)); break;
        case 2: status_ok(fmi2GetString(c, vr, n, sv)); break;
        case 3: status_ok(fmi2SetInteger(c, vr, n, iv)); break;
        case 4: status_ok(fmi2SetBoolean(c, vr, n, bv)); break;
        default: status_ok(fmi2SetString(c, vr, n, sv)); break;
        }
        break;
    case 10: status_ok(fmi2GetFMUstate(c, slot)); break;
    case 11: status_ok(fmi2SetFMUstate(c, *slot)); break;
    case 12: {
        /* a state freed by the harness keeps its (stale) pointer in another slot */
        fmi2FMUstate keep = *slot;
        status_ok(fmi2FreeFMUstate(c, slot));
        if (u8(r) & 1)
            s->state[(who >> 3) % N_STATE] = keep;
        break;
    }
    case 13: {
        size_t sz = 0;
        status_ok(fmi2SerializedFMUstateSize(c, *slot, &sz));
        char b[16];
        status_ok(fmi2SerializeFMUstate(c, *slot, b, sizeof b));
        fmi2FMUstate out = NULL;
        status_ok(fmi2DeSerializeFMUstate(c, b, sizeof b, &out));
        if (out != NULL) /* it says it cannot: nothing may come back */
            __builtin_trap();
        break;
    }
    case 14: {
        const size_t nu = u8(r) % 5, nk = u8(r) % 5;
        fmi2ValueReference ku[8];
        for (size_t i = 0; i < nu; i++)
            vr[i] = vref(r);
        for (size_t i = 0; i < nk; i++) {
            ku[i] = vref(r);
            v[i] = real(r);
        }
        double du[8];
        status_ok(fmi2GetDirectionalDerivative(c, vr, nu, ku, nk, v, du));
        break;
    }
    case 15: status_ok(fmi2EnterEventMode(c)); break;
    case 16: {
        fmi2EventInfo ev;
        memset(&ev, 0xa5, sizeof ev);
        status_ok(fmi2NewDiscreteStates(c, (u8(r) & 7) == 7 ? NULL : &ev));
        break;
    }
    case 17: status_ok(fmi2EnterContinuousTimeMode(c)); break;
    case 18: {
        fmi2Boolean enter = 0, term = 0;
        const unsigned b = u8(r);
        status_ok(fmi2CompletedIntegratorStep(c, (int)(b & 1), (b & 2) ? NULL : &enter,
                                              (b & 4) ? NULL : &term));
        break;
    }
    case 19: status_ok(fmi2SetTime(c, real(r))); break;
    case 20:
        n = length(r, nx);
        buf = malloc(n * sizeof *buf + 1);
        for (size_t i = 0; i < n; i++)
            buf[i] = real(r);
        status_ok(fmi2SetContinuousStates(c, buf, n));
        free(buf);
        break;
    case 21:
    case 22:
    case 23:
    case 24: {
        const size_t right = op % 34 == 22 ? ni : nx;
        n = length(r, right);
        buf = malloc(n * sizeof *buf + 1);
        const int null = (u8(r) & 15) == 15;
        double *b = null ? NULL : buf;
        switch (op % 34) {
        case 21: status_ok(fmi2GetDerivatives(c, b, n)); break;
        case 22: status_ok(fmi2GetEventIndicators(c, b, n)); break;
        case 23: status_ok(fmi2GetContinuousStates(c, b, n)); break;
        default: status_ok(fmi2GetNominalsOfContinuousStates(c, b, n)); break;
        }
        free(buf);
        break;
    }
    case 25: {
        n = u8(r) % 4;
        fmi2Integer order[8];
        for (size_t i = 0; i < n; i++) {
            vr[i] = vref(r);
            order[i] = (fmi2Integer)(u8(r) % 4);
            v[i] = real(r);
        }
        if (u8(r) & 1)
            status_ok(fmi2SetRealInputDerivatives(c, vr, n, order, v));
        else
            status_ok(fmi2GetRealOutputDerivatives(c, vr, n, order, v));
        break;
    }
    case 26:
    case 27: {
        const double t = real(r), h = real(r);
        status_ok(fmi2DoStep(c, t, h, (int)(u8(r) & 1)));
        break;
    }
    case 28: status_ok(fmi2CancelStep(c)); break;
    case 29: {
        const fmi2StatusKind kind = (fmi2StatusKind)(u8(r) % 6);
        fmi2Status sst;
        fmi2Real rst;
        fmi2Integer ist;
        fmi2Boolean bst;
        fmi2String strst;
        switch (u8(r) % 4) {
        case 0: status_ok(fmi2GetStatus(c, kind, &sst)); break;
        case 1: status_ok(fmi2GetRealStatus(c, kind, &rst)); break;
        case 2: status_ok(fmi2GetIntegerStatus(c, kind, &ist)); break;
        default: status_ok(fmi2GetBooleanStatus(c, kind, &bst)); break;
        }
        status_ok(fmi2GetStringStatus(c, kind, &strst));
        break;
    }
    case 30: {
        static const char *const cats[] = {"logEvents", "logStatusDiscard", "logStatusError",
                                           "logCalls", "logStatusWarning", "nope", ""};
        const char *list[8];
        n = u8(r) % 8;
        for (size_t i = 0; i < n; i++)
            list[i] = cats[u8(r) % 7];
        const unsigned b = u8(r);
        status_ok(fmi2SetDebugLogging(c, (int)(b & 1), n, (b & 2) && n == 0 ? NULL : list));
        break;
    }
    case 31:
        if (strcmp(fmi2GetVersion(), fmi2Version) != 0 ||
            strcmp(fmi2GetTypesPlatform(), fmi2TypesPlatform) != 0)
            __builtin_trap();
        break;
    default: { /* Co-Simulation's usual loop: a few steps in a row */
        const double h = real(r);
        double t = real(r);
        for (int i = 0; i < 4; i++, t += h)
            status_ok(fmi2DoStep(c, t, h, fmi2True));
        break;
    }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    reader r = {data, size};
    session s;
    memset(&s, 0, sizeof s);
    instantiate(&s, 0, u8(&r) & 0x83); /* the type, logging, the logger */
    for (int calls = 0; r.n > 0 && calls < MAX_CALLS; calls++)
        one_call(&s, &r);
    /* the importer's duty at the end: its states and instances freed */
    for (int k = 0; k < N_INST; k++) {
        if (!s.live[k])
            continue;
        for (int j = 0; j < N_STATE; j++)
            if (s.state[j] != NULL) /* ours, another's or stale: the FMU sorts them out */
                (void)fmi2FreeFMUstate(s.inst[k], &s.state[j]);
        fmi2FreeInstance(s.inst[k]);
    }
    return 0;
}
