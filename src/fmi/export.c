/* export.c - lv_fmu_export (lv_fmu.h): one mission phase as an FMI 2.0 FMU archive.
 * modelDescription.xml follows the FMI 2.0.x specification, section 2.2: ScalarVariables with
 * the causality / variability / initial combinations of its table (2.2.7), UnitDefinitions in
 * SI base-unit exponents (2.2.2), ModelStructure with Outputs, Derivatives and InitialUnknowns
 * (2.2.8). The archive is written with libzip. */
#define _GNU_SOURCE /* dladdr */

#include <ctype.h>
#include <dlfcn.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include <nettle/sha2.h>
#include <zip.h>

#include "io/nettle_dl.h"
#include "core/status.h"
#include "core/table_unit.h"
#include "fmi/fmu_phase.h"
#include "fmi/zip_dl.h"
#include "lvsim/lv_fmu.h"
#include "lvsim/lvsim.h"

#define LV_FMU_MODULE "lvsim_fmu.so"
/* DefaultExperiment stepSize: at most this (s), and at most this many steps (modelDescription). */
#define LV_FMU_STEP_MAX 0.01
#define LV_FMU_STEPS_MAX 1e6

/* ---- a growing text ------------------------------------------------------------------------ */

typedef struct sbuf {
    char *s;
    size_t n, cap;
    int oom;
} sbuf;

static void sb_add(sbuf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void sb_add(sbuf *b, const char *fmt, ...)
{
    if (b->oom)
        return;
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        const int len = vsnprintf(b->s ? b->s + b->n : NULL, b->s ? b->cap - b->n : 0, fmt, ap);
        va_end(ap);
        if (len < 0) {
            b->oom = 1;
            return;
        }
        if (b->s != NULL && b->n + (size_t)len < b->cap) {
            b->n += (size_t)len;
            return;
        }
        size_t cap = b->cap ? 2 * b->cap : 4096;
        while (cap < b->n + (size_t)len + 1)
            cap *= 2;
        char *g = realloc(b->s, cap);
        if (g == NULL) {
            b->oom = 1;
            return;
        }
        b->s = g;
        b->cap = cap;
    }
}

/* XML text: & < > " ' escaped. */
static void sb_xml(sbuf *b, const char *text)
{
    for (const char *p = text; *p; p++) {
        switch (*p) {
        case '&': sb_add(b, "&amp;"); break;
        case '<': sb_add(b, "&lt;"); break;
        case '>': sb_add(b, "&gt;"); break;
        case '"': sb_add(b, "&quot;"); break;
        case '\'': sb_add(b, "&apos;"); break;
        default:
            if ((unsigned char)*p < 0x20 && *p != '\t')
                sb_add(b, " ");
            else
                sb_add(b, "%c", *p);
        }
    }
}

/* ---- units ------------------------------------------------------------------------------------ */

/* SI base units in FMI's BaseUnit order; rad is an attribute of its own. */
enum { U_KG, U_M, U_S, U_A, U_K, U_MOL, U_CD, U_RAD, U_N };
static const char *const base_attr[U_N] = {"kg", "m", "s", "A", "K", "mol", "cd", "rad"};

static const struct {
    const char *sym;
    int e[U_N];
} unit_syms[] = {
    /* longest first where one symbol starts another ("mol" before "m") */
    {"mol", {0, 0, 0, 0, 0, 1, 0, 0}}, {"rad", {0, 0, 0, 0, 0, 0, 0, 1}},
    {"kg", {1, 0, 0, 0, 0, 0, 0, 0}},  {"cd", {0, 0, 0, 0, 0, 0, 1, 0}},
    {"Pa", {1, -1, -2, 0, 0, 0, 0, 0}}, {"Hz", {0, 0, -1, 0, 0, 0, 0, 0}},
    {"m", {0, 1, 0, 0, 0, 0, 0, 0}},   {"s", {0, 0, 1, 0, 0, 0, 0, 0}},
    {"A", {0, 0, 0, 1, 0, 0, 0, 0}},   {"K", {0, 0, 0, 0, 1, 0, 0, 0}},
    {"N", {1, 1, -2, 0, 0, 0, 0, 0}},  {"J", {1, 2, -2, 0, 0, 0, 0, 0}},
    {"W", {1, 2, -3, 0, 0, 0, 0, 0}},
};

/* A unit string of lvsim's models, in the Modelica unit grammar (MLS 3.6 sec. 19.1: "m/s2",
 * "kg/m3", "N", "1/s", "m3/s2", "kg.m2"; a '^' before an exponent is read too), in SI
 * base-unit exponents. 0, or -1 when it has a symbol or a form not known here. */
static int unit_parse(const char *u, int e[U_N])
{
    memset(e, 0, U_N * sizeof *e);
    int sign = 1;
    const char *p = u;
    while (*p) {
        if (*p == '/') {
            if (sign < 0)
                return -1; /* one '/' at most */
            sign = -1;
            p++;
            continue;
        }
        if (*p == '.' || *p == '*' || *p == ' ') {
            p++;
            continue;
        }
        if (*p == '1' && (p[1] == '/' || p[1] == '\0')) { /* "1/s" */
            p++;
            continue;
        }
        size_t k, n = sizeof unit_syms / sizeof unit_syms[0];
        for (k = 0; k < n; k++)
            if (strncmp(p, unit_syms[k].sym, strlen(unit_syms[k].sym)) == 0)
                break;
        if (k == n)
            return -1;
        p += strlen(unit_syms[k].sym);
        if (*p == '^')
            p++;
        int ex = 1, neg = 0;
        if (*p == '-') {
            neg = 1;
            p++;
        }
        if (isdigit((unsigned char)*p)) {
            ex = 0;
            while (isdigit((unsigned char)*p))
                ex = 10 * ex + (*p++ - '0');
        } else if (neg) {
            return -1;
        }
        if (neg)
            ex = -ex;
        for (int i = 0; i < U_N; i++)
            e[i] += sign * ex * unit_syms[k].e[i];
    }
    return 0;
}

/* 1 when a unit needs no attribute: "1", or a ratio of like units ("rad/rad", a gain), whose
 * base exponents are all 0 and whose BaseUnit would say nothing (FMI 2.0.4 sec. 2.2.2 declares
 * a unit by its exponents; the compliance checkers refuse an empty one). */
static int unit_none(const char *u)
{
    if (LV_UNIT_ONE(u))
        return 1;
    int e[U_N];
    if (unit_parse(u, e) != 0)
        return 0;
    for (int k = 0; k < U_N; k++)
        if (e[k] != 0)
            return 0;
    return 1;
}

/* The distinct units of the variables, in first-use order. */
typedef struct unit_set {
    size_t n;
    char names[256][64];
} unit_set;

static lv_status unit_note(unit_set *us, const char *unit, const char *var, lv_err *err)
{
    if (unit_none(unit)) /* dimensionless: no unit attribute, nothing to declare */
        return LV_OK;
    for (size_t i = 0; i < us->n; i++)
        if (strcmp(us->names[i], unit) == 0)
            return LV_OK;
    int e[U_N];
    if (unit_parse(unit, e) != 0)
        return lv_fail(err, LV_ERR_INPUT, "variable '%s': unit '%s' is not one the FMU exporter "
                       "knows (SI symbols m, s, kg, N, Pa, J, W, Hz, K, A, mol, cd, rad with "
                       "integer powers)", var, unit);
    if (us->n == sizeof us->names / sizeof us->names[0] || strlen(unit) >= sizeof us->names[0])
        return lv_fail(err, LV_ERR_INPUT, "variable '%s': too many units, or unit '%s' too long",
                       var, unit);
    snprintf(us->names[us->n++], sizeof us->names[0], "%s", unit);
    return LV_OK;
}

/* ---- names and checks ---------------------------------------------------------------------- */

/* "kourou-leo" + "upper-burn-1" -> "kourou_leo_upper_burn_1" (a C identifier). */
static void make_identifier(const char *mission, const char *phase, char *out, size_t cap)
{
    snprintf(out, cap, "%s_%s", mission, phase);
    for (char *p = out; *p; p++)
        if (!isalnum((unsigned char)*p) && *p != '_')
            *p = '_';
    if (!isalpha((unsigned char)out[0]) && out[0] != '_') {
        memmove(out + 1, out, strnlen(out, cap - 2) + 1);
        out[0] = '_';
        out[cap - 1] = '\0';
    }
}

static int is_identifier(const char *s)
{
    if (!isalpha((unsigned char)s[0]) && s[0] != '_')
        return 0;
    for (const char *p = s; *p; p++)
        if (!isalnum((unsigned char)*p) && *p != '_')
            return 0;
    return 1;
}

/* The FMU binary next to this library: <libdir>/lvsim/lvsim_fmu.so. */
static const char anchor = 0;
static lv_status default_binary(char *out, size_t cap, lv_err *err)
{
    Dl_info info;
    char lib[PATH_MAX];
    if (dladdr(&anchor, &info) == 0 || info.dli_fname == NULL ||
        realpath(info.dli_fname, lib) == NULL)
        return lv_fail(err, LV_ERR_IO, "cannot tell where liblvsim_post is, so not where "
                       "the FMU binary %s is", LV_FMU_MODULE);
    char *slash = strrchr(lib, '/');
    if (slash != NULL)
        *slash = '\0';
    snprintf(out, cap, "%s/lvsim/%s", lib, LV_FMU_MODULE);
    return LV_OK;
}

/* FNV-1a, 64 bits, from a seed. */
static uint64_t fnv(uint64_t h, const void *data, size_t n)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < n; i++) {
        h ^= p[i];
        h *= 1099511628211ull;
    }
    return h;
}

static lv_status read_file(const char *path, char **out, size_t *len, lv_err *err)
{
    FILE *fp = fopen(path, "rb");
    if (fp == NULL)
        return lv_fail(err, LV_ERR_IO, "cannot read '%s': %s", path, LV_STRERROR(errno));
    char *buf = NULL;
    size_t n = 0, cap = 0;
    for (;;) {
        if (n == cap) {
            cap = cap ? 2 * cap : 65536;
            char *g = realloc(buf, cap);
            if (g == NULL) {
                free(buf);
                fclose(fp);
                return lv_fail(err, LV_ERR_NOMEM, "out of memory");
            }
            buf = g;
        }
        size_t got = fread(buf + n, 1, cap - n, fp);
        n += got;
        if (got == 0)
            break;
    }
    const int bad = ferror(fp), e = errno;
    fclose(fp);
    if (bad) {
        free(buf);
        return lv_fail(err, LV_ERR_IO, "cannot read '%s': %s", path, LV_STRERROR(e ? e : EIO));
    }
    *out = buf;
    *len = n;
    return LV_OK;
}

/* ---- the resources: the mission's files with their relative layout -------------------------- */

typedef struct res_file {
    char real[PATH_MAX]; /* on disk */
    char arc[PATH_MAX];  /* in the archive, under resources/mission/ */
} res_file;

/* Every file's real path; the archive paths relative to their deepest common folder. */
static lv_status plan_resources(const lv_mission *m, res_file *rf, size_t n, lv_err *err)
{
    const char *mpath = lv_mission_file(m, 0);
    char mdir[PATH_MAX];
    snprintf(mdir, sizeof mdir, "%s", mpath);
    char *sl = strrchr(mdir, '/');
    if (sl != NULL)
        *sl = '\0';
    else
        snprintf(mdir, sizeof mdir, ".");
    for (size_t i = 0; i < n; i++) {
        const char *f = lv_mission_file(m, i);
        /* a data file named by an absolute path would be read from there, not from the copy */
        if (i > 0 && !(strncmp(f, mdir, strlen(mdir)) == 0 && f[strlen(mdir)] == '/'))
            return lv_fail(err, LV_ERR_INPUT, "%s: data file '%s' is named by an absolute path: "
                           "an FMU carries the mission's files in resources/ and reads them from "
                           "there, so name it relative to the mission file", mpath, f);
        if (realpath(f, rf[i].real) == NULL)
            return lv_fail(err, LV_ERR_IO, "%s: cannot find data file '%s': %s", mpath, f,
                           LV_STRERROR(errno));
    }
    /* the deepest folder that holds them all */
    char common[PATH_MAX];
    snprintf(common, sizeof common, "%s", rf[0].real);
    *strrchr(common, '/') = '\0'; /* the mission's folder ("" for the root) */
    for (size_t i = 1; i < n; i++) {
        for (;;) {
            const size_t lc = strlen(common);
            if (strncmp(rf[i].real, common, lc) == 0 && rf[i].real[lc] == '/')
                break;
            *strrchr(common, '/') = '\0'; /* real paths are absolute: a '/' is left */
        }
    }
    const size_t lc = strlen(common);
    for (size_t i = 0; i < n; i++)
        snprintf(rf[i].arc, sizeof rf[i].arc, "%s", rf[i].real + lc + 1);
    return LV_OK;
}

/* The output must not be the mission or one of its data files (lv_output_check: any spelling
 * of the path; the archive's temporary file is libzip's own, beside it, never an input). */
static lv_status refuse_inputs(const char *mission_path, const char *fmu_path, lv_err *err)
{
    lv_mission *m = NULL;
    lv_status st = lv_mission_load(mission_path, &m, err);
    if (st == LV_OK)
        st = lv_output_check(fmu_path, m, LV_OUTPUT_REPLACE, err);
    lv_mission_free(m);
    return st;
}

/* ---- modelDescription.xml ------------------------------------------------------------------ */

static void var_open(sbuf *b, const char *name, unsigned vr, const char *desc,
                     const char *causality, const char *variability, const char *initial)
{
    sb_add(b, "    <ScalarVariable name=\"");
    sb_xml(b, name);
    sb_add(b, "\" valueReference=\"%u\"", vr);
    if (desc != NULL && desc[0] != '\0') {
        sb_add(b, " description=\"");
        sb_xml(b, desc);
        sb_add(b, "\"");
    }
    sb_add(b, " causality=\"%s\" variability=\"%s\"", causality, variability);
    if (initial != NULL)
        sb_add(b, " initial=\"%s\"", initial);
    sb_add(b, ">\n");
}

static void real_elem(sbuf *b, const char *unit, const double *start, double nominal,
                      long derivative)
{
    sb_add(b, "      <Real");
    if (!unit_none(unit)) {
        sb_add(b, " unit=\"");
        sb_xml(b, unit);
        sb_add(b, "\"");
    }
    if (start != NULL)
        sb_add(b, " start=\"%.17g\"", *start);
    if (nominal > 0.0)
        sb_add(b, " nominal=\"%.17g\"", nominal);
    if (derivative > 0)
        sb_add(b, " derivative=\"%ld\"", derivative);
    sb_add(b, "/>\n    </ScalarVariable>\n");
}

/* Everything after the root element's opening tag (the GUID is hashed over it). */
static lv_status write_body(const lv_fmu_phase *fp, const char *id, size_t ni, sbuf *b,
                            lv_err *err)
{
    const lv_model_def *d = fp->def;
    const size_t nx = d->n_states, np = d->n_params, ny = d->n_outputs;
    const lv_sim_settings *s = fp->s;
    char dunits[256][64];
    if (nx > 256)
        return lv_fail(err, LV_ERR_INPUT, "model '%s': more than 256 states", d->name);
    unit_set *us = calloc(1, sizeof *us);
    if (us == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    lv_status st = LV_OK;
    for (size_t i = 0; i < nx && st == LV_OK; i++) {
        lv_unit_per_second(d->states[i].unit, dunits[i], sizeof dunits[i]);
        st = unit_note(us, d->states[i].unit, d->states[i].name, err);
        if (st == LV_OK)
            st = unit_note(us, dunits[i], d->states[i].name, err);
    }
    for (size_t j = 0; j < np && st == LV_OK; j++)
        st = unit_note(us, d->params[j].unit, d->params[j].name, err);
    for (size_t k = 0; k < ny && st == LV_OK; k++)
        st = unit_note(us, d->outputs[k].unit, d->outputs[k].name, err);
    /* the run parameters' units as `lvsim params` writes them ("m2", "1"): declared where the
     * exporter knows them in base units, left out otherwise (a unit is optional) */
    const size_t nr = fp->n_run;
    char(*runits)[64] = calloc(nr + 1, sizeof *runits);
    if (runits == NULL)
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
    for (size_t r = 0; r < nr && st == LV_OK; r++) {
        lv_param_info pi;
        lv_mission_param_info(fp->mission, fp->run_idx[r], &pi);
        int e[U_N];
        if (!unit_none(pi.unit) && strlen(pi.unit) < sizeof runits[r] &&
            unit_parse(pi.unit, e) == 0) {
            snprintf(runits[r], sizeof runits[r], "%s", pi.unit);
            st = unit_note(us, pi.unit, pi.name, err);
        }
    }
    if (st != LV_OK) {
        free(us);
        free(runits);
        return st;
    }
    static const char *const flags =
        "needsExecutionTool=\"false\" canBeInstantiatedOnlyOncePerProcess=\"false\" "
        "canNotUseMemoryManagementFunctions=\"true\" canGetAndSetFMUstate=\"true\" "
        "canSerializeFMUstate=\"false\" providesDirectionalDerivative=\"false\"";
    sb_add(b, "  <ModelExchange modelIdentifier=\"%s\" completedIntegratorStepNotNeeded=\"true\" "
              "%s/>\n", id, flags);
    sb_add(b, "  <CoSimulation modelIdentifier=\"%s\" canHandleVariableCommunicationStepSize="
              "\"true\" canInterpolateInputs=\"false\" maxOutputDerivativeOrder=\"0\" "
              "canRunAsynchronuously=\"false\" %s/>\n", id, flags);
    sb_add(b, "  <UnitDefinitions>\n");
    for (size_t i = 0; i < us->n; i++) {
        int e[U_N];
        unit_parse(us->names[i], e);
        sb_add(b, "    <Unit name=\"");
        sb_xml(b, us->names[i]);
        sb_add(b, "\">\n      <BaseUnit");
        for (int k = 0; k < U_N; k++)
            if (e[k] != 0)
                sb_add(b, " %s=\"%d\"", base_attr[k], e[k]);
        sb_add(b, "/>\n");
        /* angles shown in degrees: value_deg = factor * value_rad */
        if (strcmp(us->names[i], "rad") == 0 || strcmp(us->names[i], "rad/s") == 0)
            sb_add(b, "      <DisplayUnit name=\"%s\" factor=\"%.17g\"/>\n",
                   strcmp(us->names[i], "rad") == 0 ? "deg" : "deg/s", 180.0 / 3.14159265358979323846);
        sb_add(b, "    </Unit>\n");
    }
    sb_add(b, "  </UnitDefinitions>\n");
    free(us);
    sb_add(b, "  <LogCategories>\n"
              "    <Category name=\"logEvents\" description=\"state and time events, the "
              "phase's end\"/>\n"
              "    <Category name=\"logStatusDiscard\" description=\"why a call returned "
              "fmi2Discard (always reported)\"/>\n"
              "    <Category name=\"logStatusError\" description=\"why a call returned "
              "fmi2Error (always reported)\"/>\n"
              "    <Category name=\"logCalls\" description=\"every FMI function called\"/>\n"
              "    <Category name=\"logStatusWarning\" description=\"why a call returned "
              "fmi2Warning (always reported)\"/>\n"
              "  </LogCategories>\n");
    /* stepSize: the step a fixed-step importer integrates Model Exchange with (FMPy's Euler,
     * the compliance checker), and what most use as their output interval too. The phase's
     * output interval (1 s and more in the examples) made explicit Euler miss the kourou-leo
     * ascent's burnout by 29 km (issue 27); Euler is first order, its error there ~3e4 m per
     * second of step (tests/fmi/check_importer.py prints it): LV_FMU_STEP_MAX = 0.01 s, the
     * output interval where that is finer, and never more than LV_FMU_STEPS_MAX steps to the
     * phase's time limit (a 90-minute coast: 5.4e5 steps). */
    const double span = s->stop_time - s->start_time;
    const double interval = s->output_interval > 0.0 ? s->output_interval
                            : span / (s->number_of_intervals > 0 ? s->number_of_intervals : 500);
    const double step = fmax(fmin(interval, LV_FMU_STEP_MAX), span / LV_FMU_STEPS_MAX);
    sb_add(b, "  <DefaultExperiment startTime=\"%.17g\" stopTime=\"%.17g\" tolerance=\"%.17g\" "
              "stepSize=\"%.17g\"/>\n", s->start_time, s->stop_time, s->tolerance, step);
    sb_add(b, "  <ModelVariables>\n");
    unsigned vr = 0;
    for (size_t i = 0; i < nx; i++, vr++) {
        sb_add(b, "    <!-- index %u: state -->\n", vr + 1);
        var_open(b, d->states[i].name, vr, d->states[i].description, "local", "continuous",
                 "exact");
        real_elem(b, d->states[i].unit, &fp->x0[i], d->states[i].nominal, 0);
    }
    for (size_t i = 0; i < nx; i++, vr++) {
        char name[256], desc[300];
        snprintf(name, sizeof name, "der(%s)", d->states[i].name);
        snprintf(desc, sizeof desc, "Time derivative of %s", d->states[i].name);
        sb_add(b, "    <!-- index %u: derivative -->\n", vr + 1);
        var_open(b, name, vr, desc, "local", "continuous", "calculated");
        real_elem(b, dunits[i], NULL, 0.0, (long)i + 1);
    }
    for (size_t j = 0; j < np; j++, vr++) {
        /* the phase's inputs (lv_fmu_phase_inputs): causality input, variability continuous,
         * no initial (FMI 2.0.4, 2.2.7: not allowed for an input) and a start value (required:
         * the value the phase's law gives, used until the importer sets one) */
        const int in = fp->is_input != NULL && fp->is_input[j];
        sb_add(b, "    <!-- index %u: %s -->\n", vr + 1, in ? "input" : "parameter");
        var_open(b, d->params[j].name, vr, d->params[j].description, in ? "input" : "parameter",
                 in ? "continuous" : "fixed", in ? NULL : "exact");
        real_elem(b, d->params[j].unit, &fp->p0[j], 0.0, 0);
    }
    for (size_t k = 0; k < ny; k++, vr++) {
        sb_add(b, "    <!-- index %u: output -->\n", vr + 1);
        var_open(b, d->outputs[k].name, vr, d->outputs[k].description, "output", "continuous",
                 "calculated");
        real_elem(b, d->outputs[k].unit, NULL, 0.0, 0);
    }
    /* the mission's run parameters that change the phase (lv_fmu_phase_run_params): fixed
     * parameters (FMI 2.0.4, 2.2.7: set before fmi2ExitInitializationMode), start = the
     * mission's value */
    for (size_t r = 0; r < nr; r++, vr++) {
        lv_param_info pi;
        lv_mission_param_info(fp->mission, fp->run_idx[r], &pi);
        char desc[400];
        snprintf(desc, sizeof desc, "run parameter of the mission (lvsim params; allowed: %s): "
                 "setting it before fmi2ExitInitializationMode prepares the phase again, its "
                 "ancestors run again where they read it", pi.rule ? pi.rule : "finite");
        sb_add(b, "    <!-- index %u: run parameter -->\n", vr + 1);
        var_open(b, pi.name, vr, desc, "parameter", "fixed", "exact");
        const double v = pi.value;
        real_elem(b, runits[r], &v, 0.0, 0);
    }
    free(runits);
    sb_add(b, "  </ModelVariables>\n  <ModelStructure>\n");
    if (ny > 0) {
        sb_add(b, "    <Outputs>\n");
        for (size_t k = 0; k < ny; k++)
            sb_add(b, "      <Unknown index=\"%zu\"/>\n", 2 * nx + np + k + 1);
        sb_add(b, "    </Outputs>\n");
    }
    if (nx > 0) {
        sb_add(b, "    <Derivatives>\n");
        for (size_t i = 0; i < nx; i++)
            sb_add(b, "      <Unknown index=\"%zu\"/>\n", nx + i + 1);
        sb_add(b, "    </Derivatives>\n");
    }
    /* the derivatives and outputs: initial="calculated" (states and parameters are exact) */
    if (nx + ny > 0) {
        sb_add(b, "    <InitialUnknowns>\n");
        for (size_t i = 0; i < nx; i++)
            sb_add(b, "      <Unknown index=\"%zu\"/>\n", nx + i + 1);
        for (size_t k = 0; k < ny; k++)
            sb_add(b, "      <Unknown index=\"%zu\"/>\n", 2 * nx + np + k + 1);
        sb_add(b, "    </InitialUnknowns>\n");
    }
    sb_add(b, "  </ModelStructure>\n</fmiModelDescription>\n");
    (void)ni;
    return b->oom ? lv_fail(err, LV_ERR_NOMEM, "out of memory") : LV_OK;
}

/* ---- the archive ----------------------------------------------------------------------------- */

static lv_status zip_fail(zip_t *za, const char *tmp, const char *out, lv_err *err)
{
    lv_status st = lv_fail(err, LV_ERR_IO, "cannot write '%s': %s", out,
                           za != NULL ? zip_strerror(za) : "zip error");
    if (za != NULL)
        zip_discard(za);
    unlink(tmp);
    return st;
}

static int add_buffer(zip_t *za, const char *name, const char *data, size_t len)
{
    zip_source_t *src = zip_source_buffer(za, data, len, 0);
    if (src == NULL)
        return -1;
    if (zip_file_add(za, name, src, ZIP_FL_OVERWRITE | ZIP_FL_ENC_UTF_8) < 0) {
        zip_source_free(src);
        return -1;
    }
    return 0;
}

static int add_file(zip_t *za, const char *name, const char *path, unsigned mode)
{
    zip_source_t *src = zip_source_file(za, path, 0, -1);
    if (src == NULL)
        return -1;
    zip_int64_t idx = zip_file_add(za, name, src, ZIP_FL_OVERWRITE | ZIP_FL_ENC_UTF_8);
    if (idx < 0) {
        zip_source_free(src);
        return -1;
    }
    return zip_file_set_external_attributes(za, (zip_uint64_t)idx, 0, ZIP_OPSYS_UNIX,
                                            (zip_uint32_t)(0100000u | mode) << 16);
}

lv_status lv_fmu_export(const char *mission_path, const char *phase, const char *fmu_path,
                        const lv_fmu_options *opt, lv_fmu_info *info, lv_err *err)
{
    lv_err local;
    if (err == NULL)
        err = &local;
    if (mission_path == NULL || phase == NULL || phase[0] == '\0' || fmu_path == NULL ||
        fmu_path[0] == '\0')
        return lv_fail(err, LV_ERR_INPUT, "a mission file, a phase name and an output path "
                       "are needed");
    /* FMI 2.0, 2.3: an FMU is a zip file with the extension ".fmu". Required of the output,
     * so that -o never replaces a file of another kind (a mission, a table, a result). */
    const size_t lo = strlen(fmu_path);
    if (lo < 5 || strcmp(fmu_path + lo - 4, ".fmu") != 0)
        return lv_fail(err, LV_ERR_INPUT, "output '%s' does not end in '.fmu': an FMU is a zip "
                       "archive named NAME.fmu (FMI 2.0, section 2.3)", fmu_path);
    lv_fmu_options o = {0};
    if (opt != NULL)
        o = *opt;
    char binary[PATH_MAX + 64];
    lv_status st;
    if (o.binary != NULL)
        snprintf(binary, sizeof binary, "%s", o.binary);
    else if ((st = default_binary(binary, sizeof binary, err)) != LV_OK)
        return st;
    struct stat sb;
    if (stat(binary, &sb) != 0 || !S_ISREG(sb.st_mode))
        return lv_fail(err, LV_ERR_IO, "the FMU binary '%s' is missing (built with lvsim as "
                       "<libdir>/lvsim/%s; reinstall, or build the target lvsim_fmu)", binary,
                       LV_FMU_MODULE);
    const char *why = lv_nettle_error(); /* the resources' SHA-256 (io/nettle_dl.c) */
    if (why != NULL)
        return lv_fail(err, LV_ERR_IO, "cannot export an FMU: its resources' SHA-256 needs "
                       "Nettle: %s", why);
    /* the output's folder must exist and be writable before the phases run */
    char outdir[PATH_MAX];
    snprintf(outdir, sizeof outdir, "%s", fmu_path);
    char *sl = strrchr(outdir, '/');
    if (sl == NULL)
        snprintf(outdir, sizeof outdir, ".");
    else if (sl == outdir)
        sl[1] = '\0';
    else
        *sl = '\0';
    if (stat(outdir, &sb) != 0 || !S_ISDIR(sb.st_mode))
        return lv_fail(err, LV_ERR_IO, "cannot write '%s': '%s' %s", fmu_path, outdir,
                       stat(outdir, &sb) == 0 ? "is a file, not a folder" : "does not exist");
    if (access(outdir, W_OK) != 0)
        return lv_fail(err, LV_ERR_IO, "cannot write '%s': folder '%s': %s", fmu_path, outdir,
                       LV_STRERROR(errno));
    if (stat(fmu_path, &sb) == 0 && S_ISDIR(sb.st_mode))
        return lv_fail(err, LV_ERR_IO, "cannot write '%s': it is a folder", fmu_path);
    if ((st = refuse_inputs(mission_path, fmu_path, err)) != LV_OK)
        return st;

    lv_fmu_phase fp;
    if ((st = lv_fmu_phase_open(mission_path, phase, &fp, err)) != LV_OK)
        return st;
    if ((st = lv_fmu_phase_run_params(&fp, err)) != LV_OK) {
        lv_fmu_phase_close(&fp);
        return st;
    }
    const lv_model_def *d = fp.def;
    lv_mission_info mi;
    lv_mission_get_info(fp.mission, &mi);
    char id[128];
    if (o.model_identifier != NULL) {
        if (strlen(o.model_identifier) >= sizeof id) {
            lv_fmu_phase_close(&fp);
            return lv_fail(err, LV_ERR_INPUT, "model identifier '%.40s...' is too long (%zu "
                           "characters; max %zu)", o.model_identifier,
                           strlen(o.model_identifier), sizeof id - 1);
        }
        if (!is_identifier(o.model_identifier)) {
            lv_fmu_phase_close(&fp);
            return lv_fail(err, LV_ERR_INPUT, "model identifier '%s' is not a C identifier "
                           "(letters, digits, '_'; not starting with a digit)",
                           o.model_identifier);
        }
        snprintf(id, sizeof id, "%s", o.model_identifier);
    } else {
        make_identifier(mi.name, phase, id, sizeof id);
    }
    size_t ns_root = 0;
    for (size_t j = 0; j < fp.s->n_stops; j++)
        ns_root += strcmp(fp.s->stops[j].variable, "time") != 0;
    const size_t ni = d->n_events + d->n_domain + ns_root;

    const size_t nf = lv_mission_file_count(fp.mission);
    res_file *rf = calloc(nf, sizeof *rf);
    sbuf body = {0}, head = {0}, cfg = {0};
    char **data = calloc(nf, sizeof *data);
    size_t *dlen = calloc(nf, sizeof *dlen);
    zip_t *za = NULL;
    char tmp[PATH_MAX + 8];
    snprintf(tmp, sizeof tmp, "%s.tmp", fmu_path);
    if (rf == NULL || data == NULL || dlen == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto out;
    }
    if ((st = plan_resources(fp.mission, rf, nf, err)) != LV_OK)
        goto out;
    for (size_t i = 0; i < nf; i++)
        if ((st = read_file(rf[i].real, &data[i], &dlen[i], err)) != LV_OK)
            goto out;
    if ((st = write_body(&fp, id, ni, &body, err)) != LV_OK)
        goto out;

    /* GUID: a hash of the description and of every resource file */
    uint64_t h1 = 14695981039346656037ull, h2 = 0x9e3779b97f4a7c15ull;
    h1 = fnv(h1, body.s, body.n);
    h2 = fnv(h2, body.s, body.n);
    for (size_t i = 0; i < nf; i++) {
        h1 = fnv(fnv(h1, rf[i].arc, strlen(rf[i].arc)), data[i], dlen[i]);
        h2 = fnv(fnv(h2, data[i], dlen[i]), rf[i].arc, strlen(rf[i].arc));
    }
    char guid[40];
    snprintf(guid, sizeof guid, "{%08x-%04x-%04x-%04x-%012llx}", (unsigned)(h1 >> 32),
             (unsigned)(h1 >> 16) & 0xffffu, (unsigned)h1 & 0xffffu, (unsigned)(h2 >> 48),
             (unsigned long long)(h2 & 0xffffffffffffull));

    char when[32];
    time_t now = time(NULL);
    const char *sde = getenv("SOURCE_DATE_EPOCH"); /* reproducible archives */
    if (sde != NULL && sde[0] != '\0')
        now = (time_t)strtoll(sde, NULL, 10);
    struct tm tmv;
    gmtime_r(&now, &tmv);
    strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", &tmv);
    lv_phase_info pi;
    lv_mission_phase_info(fp.mission, fp.k, &pi);
    sb_add(&head, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<fmiModelDescription "
                  "fmiVersion=\"2.0\" modelName=\"");
    sb_xml(&head, mi.name);
    sb_add(&head, ".");
    sb_xml(&head, phase);
    sb_add(&head, "\" guid=\"%s\" description=\"", guid);
    char desc[1024];
    snprintf(desc, sizeof desc, "phase '%s' of mission '%s' (model %s: %s)%s%s", phase, mi.name,
             pi.model, d->description ? d->description : d->name,
             fp.parent >= 0 ? "; starts from the final state of phase " : "",
             fp.parent >= 0 ? lv_mission_phase_name(fp.mission, (size_t)fp.parent) : "");
    sb_xml(&head, desc);
    sb_add(&head, "\" generationTool=\"lvsim %s\" generationDateAndTime=\"%s\" "
                  "variableNamingConvention=\"flat\" numberOfEventIndicators=\"%zu\">\n",
           LVSIM_VERSION, when, ni);
    sb_add(&head, "%s", body.s);

    sb_add(&cfg, "lvsim-fmu 2\nguid %s\nmission mission/%s\nphase %s\nstates %zu\n"
                 "parameters %zu\noutputs %zu\nevent_indicators %zu\n", guid, rf[0].arc, phase,
           d->n_states, d->n_params, d->n_outputs, ni);
    for (size_t r = 0; r < fp.n_run; r++) {
        lv_param_info rp;
        lv_mission_param_info(fp.mission, fp.run_idx[r], &rp);
        sb_add(&cfg, "run_parameter %s\n", rp.name);
    }
    /* the SHA-256 of each resource file as packed: the FMU refuses edited resources */
    for (size_t i = 0; i < nf; i++) {
        struct sha256_ctx sc;
        unsigned char dg[SHA256_DIGEST_SIZE];
        sha256_init(&sc);
        sha256_update(&sc, dlen[i], (const uint8_t *)data[i]);
        sha256_digest(&sc, sizeof dg, dg);
        sb_add(&cfg, "sha256 ");
        for (size_t k = 0; k < sizeof dg; k++)
            sb_add(&cfg, "%02x", dg[k]);
        sb_add(&cfg, " mission/%s\n", rf[i].arc);
    }
    if (head.oom || cfg.oom) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto out;
    }

    int zerr = 0;
    const char *no_zip = lv_zip_error(); /* loaded now, the first time it is needed */
    if (no_zip != NULL) {
        st = lv_fail(err, LV_ERR_IO, "cannot write '%s': libzip cannot be loaded: %s", fmu_path,
                     no_zip);
        goto out;
    }
    if ((za = zip_open(tmp, ZIP_CREATE | ZIP_TRUNCATE, &zerr)) == NULL) {
        zip_error_t ze;
        zip_error_init_with_code(&ze, zerr);
        st = lv_fail(err, LV_ERR_IO, "cannot write '%s': %s", tmp, zip_error_strerror(&ze));
        zip_error_fini(&ze);
        goto out;
    }
    char arc[PATH_MAX + 64];
    snprintf(arc, sizeof arc, "binaries/linux64/%s.so", id);
    if (add_buffer(za, "modelDescription.xml", head.s, head.n) != 0 ||
        add_file(za, arc, binary, 0755) != 0 ||
        add_buffer(za, "resources/lvsim-fmu.txt", cfg.s, cfg.n) != 0) {
        st = zip_fail(za, tmp, fmu_path, err);
        za = NULL;
        goto out;
    }
    for (size_t i = 0; i < nf; i++) {
        snprintf(arc, sizeof arc, "resources/mission/%s", rf[i].arc);
        if (add_buffer(za, arc, data[i], dlen[i]) != 0) {
            st = zip_fail(za, tmp, fmu_path, err);
            za = NULL;
            goto out;
        }
    }
    if (zip_close(za) != 0) {
        st = zip_fail(za, tmp, fmu_path, err);
        za = NULL;
        goto out;
    }
    za = NULL;
    if (rename(tmp, fmu_path) != 0) {
        st = lv_fail(err, LV_ERR_IO, "cannot write '%s': %s", fmu_path, LV_STRERROR(errno));
        unlink(tmp);
        goto out;
    }
    if (info != NULL) {
        memset(info, 0, sizeof *info);
        snprintf(info->model_identifier, sizeof info->model_identifier, "%s", id);
        snprintf(info->guid, sizeof info->guid, "%s", guid);
        info->n_states = d->n_states;
        info->n_params = d->n_params;
        info->n_outputs = d->n_outputs;
        info->n_event_indicators = ni;
        info->n_files = nf;
        info->start_time = fp.s->start_time;
        info->stop_time = fp.s->stop_time;
    }
    st = LV_OK;
out:
    for (size_t i = 0; data != NULL && i < nf; i++)
        free(data[i]);
    free(data);
    free(dlen);
    free(rf);
    free(body.s);
    free(head.s);
    free(cfg.s);
    lv_fmu_phase_close(&fp);
    return st;
}
