/* fmu.c - the binary of an lvsim FMU (FMI 2.0, Model Exchange and Co-Simulation): one
 * mission phase's model behind the standard's C functions (fmi2.h; FMI 2.0.x specification,
 * sections 2.1, 3.2 and 4.2). `lvsim fmu` (export.c) puts this module into the archive as
 * binaries/linux64/<modelIdentifier>.so beside resources/ (the mission and its data files,
 * lvsim-fmu.txt) and modelDescription.xml.
 *
 * At fmi2Instantiate the FMU loads the mission from its resources, runs the phase's ancestors
 * (a child phase starts from its parent's final state, computed here as by `lvsim run`) and
 * prepares the phase (lv_run_prepare). Value references are lv_model_vref's: states,
 * derivatives, parameters, outputs. Model Exchange evaluates the model's functions directly:
 * event indicators are the model's event functions, its domain bounds and the phase's ends on
 * a variable; time events are the model's, the phase's ends on time and its time limit.
 * Co-Simulation steps lvsim's own integrator (lv_sim, the phase's method and tolerance).
 * A phase end sets terminateSimulation (Model Exchange) or ends fmi2DoStep with fmi2Discard and
 * fmi2Terminated (Co-Simulation); leaving the model's domain is fmi2Error, as lv_simulate
 * fails. docs/fmi.md describes the behaviour for users.
 */
#define _POSIX_C_SOURCE 200809L

#include <float.h>
#include <math.h>
#include <nettle/sha2.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FMI2_EXPORT __attribute__((visibility("default")))
#define LV_FMI2_DECLARE_FUNCTIONS
#include "fmi/fmi2.h"
#include "fmi/fmu_phase.h"
#include "lvsim/lv_sim.h"
#include "sim/sim_state.h"

#define LV_FMU_CONFIG "lvsim-fmu.txt"

/* ---- the instance ------------------------------------------------------------------------ */

typedef enum fmu_mode {
    M_INSTANTIATED = 0,
    M_INIT,          /* initialization mode */
    M_EVENT,         /* Model Exchange: event mode */
    M_CONT,          /* Model Exchange: continuous-time mode */
    M_STEP_COMPLETE, /* Co-Simulation: between steps */
    M_STEP_FAILED,   /* Co-Simulation: a step ended early (phase end): fmi2Discard */
    M_TERMINATED,
    M_ERROR
} fmu_mode;

static const char *const mode_names[] = {"Instantiated",     "InitializationMode", "EventMode",
                                         "ContinuousTimeMode", "StepComplete",     "StepFailed",
                                         "Terminated",       "Error"};

enum { B_INST = 1 << M_INSTANTIATED, B_INIT = 1 << M_INIT, B_EVENT = 1 << M_EVENT,
       B_CONT = 1 << M_CONT, B_STEPOK = 1 << M_STEP_COMPLETE, B_STEPFAIL = 1 << M_STEP_FAILED,
       B_TERM = 1 << M_TERMINATED, B_ERR = 1 << M_ERROR };
#define B_RUN (B_INIT | B_EVENT | B_CONT | B_STEPOK | B_STEPFAIL | B_TERM | B_ERR)

/* Log categories (modelDescription.xml's LogCategories; export.c writes the same list). */
enum { C_EVENTS = 1, C_DISCARD = 2, C_ERROR = 4, C_CALLS = 8, C_WARNING = 16 };
static const struct { const char *name; unsigned bit; } categories[] = {
    {"logEvents", C_EVENTS}, {"logStatusDiscard", C_DISCARD},
    {"logStatusError", C_ERROR}, {"logCalls", C_CALLS}, {"logStatusWarning", C_WARNING}};
#define N_CATEGORIES (sizeof categories / sizeof categories[0])

/* A phase end on a variable or on time (lv_sim_stop) resolved. */
typedef struct fmu_stop {
    const char *name;
    int is_time;
    lv_var_kind kind;
    size_t index;
    double value;
    lv_dir dir;
} fmu_stop;

typedef struct fmu {
    fmi2Type type;
    char *name;
    char guid[128];
    fmi2CallbackFunctions cb;
    int logging;      /* debug logging on */
    unsigned cats;    /* the categories on */
    fmu_mode mode;

    lv_fmu_phase ph;
    const lv_model_def *d;
    void *inst;
    unsigned char *inst0; /* the instance's bytes after preparation (fmi2Reset) */
    size_t inst_size;
    size_t nx, np, ny, ng, nd, ns, ns_root, ni;
    fmu_stop *stops;  /* [ns] */

    double t, t_start, t_limit; /* s: current time, the experiment's start, the phase's limit */
    int stop_defined;           /* fmi2SetupExperiment's stopTimeDefined */
    double t_stop;              /* s: its stopTime: computing past it is fmi2Error */
    unsigned char *x_set;       /* [nx] the importer set the state (fmi2SetReal) */
    unsigned char *p_set;       /* [np] the importer set the parameter or input */
    size_t nr;                  /* run parameters of the mission (after the outputs' vrs) */
    int run_changed;            /* one was set: the phase was prepared again */
    unsigned gen;               /* preparations since instantiation (FMU states hold it) */
    unsigned char *start_reads; /* [np] the model's start() reads the parameter */
    double tol;                 /* the tolerance lvsim's integrator uses (Co-Simulation) */
    double *x, *p, *xdot, *y, *q, *xs, *ys; /* [nx] [np] [nx] [ny] [nd] [nx] [ny] */
    double *z, *z_pre;          /* [ni] event indicators now and at the last event */
    double *x_init, *p_init;    /* [nx] [np] as they were at fmi2ExitInitializationMode */
    double *x_prev;             /* [nx] the states before an event's handlers */
    int *fired;                 /* [ng] */
    int eval_ok;                /* xdot and y hold the model at (t, x) */
    int init_done;              /* the model's init() was called for the current start */
    double t_model_te, t_next, t_prev_event;
    int end_reached;            /* a phase end fired: terminateSimulation */
    char end_name[LV_EVENT_NAME_MAX];

    /* Co-Simulation */
    lv_sim *sim;
    lv_sim_settings cs;
    const char **cs_names;      /* [nx + np] */
    double *cs_values;          /* [nx + np] */
    double last_ok_time;        /* fmi2LastSuccessfulTime */
    int cs_terminated;          /* fmi2Terminated */
} fmu;

/* A saved state (fmi2GetFMUstate). It belongs to the instance that saved it (owner): the
 * registry below lists the live ones, so that a state of another instance, of another FMU,
 * or one already freed is refused without reading it. */
/* What an FMU state holds of an instance besides its arrays and the simulation: the scalars
 * fmi2GetFMUstate copies out and fmi2SetFMUstate copies back, listed once for both. */
#define FMU_SAVED_SCALARS(X)                                                                \
    X(mode) X(t) X(t_start) X(tol) X(init_done) X(end_reached) X(cs_terminated)             \
    X(t_model_te) X(t_next) X(t_prev_event) X(last_ok_time) X(stop_defined) X(t_stop)

typedef struct fmu_saved {
    fmu *owner;
    fmi2Type type;
    fmu_mode mode;
    double t, t_start, tol;
    double *x, *p, *z_pre, *x_init, *p_init;
    unsigned char *inst;
    int init_done, end_reached, cs_terminated;
    double t_model_te, t_next, t_prev_event, last_ok_time;
    int stop_defined;
    double t_stop;
    unsigned char *x_set;
    char end_name[LV_EVENT_NAME_MAX];
    lv_sim_saved *sim; /* Co-Simulation after initialization */
    unsigned gen;      /* the instance's preparation it was saved in */
} fmu_saved;

/* ---- the live instances and states of this binary ------------------------------------------ */

/* A call with an instance freed (or never returned by fmi2Instantiate) is refused without
 * reading it: its logger is gone with it, so the reason goes to stderr. Likewise a state is
 * used only when this registry holds it. Pointer lists under one mutex: a few entries. */
static pthread_mutex_t reg_lock = PTHREAD_MUTEX_INITIALIZER;
static void **reg_inst, **reg_state;
static size_t n_inst, cap_inst, n_state, cap_state;

static int reg_add(void ***list, size_t *n, size_t *cap, void *p)
{
    pthread_mutex_lock(&reg_lock);
    int rc = 0;
    if (*n == *cap) {
        size_t c = *cap ? 2 * *cap : 16;
        void **g = realloc(*list, c * sizeof *g);
        if (g == NULL)
            rc = -1;
        else {
            *list = g;
            *cap = c;
        }
    }
    if (rc == 0)
        (*list)[(*n)++] = p;
    pthread_mutex_unlock(&reg_lock);
    return rc;
}

/* Removes p; 1 when it was there. An empty list is freed (nothing is left behind when the
 * importer unloads the binary after freeing everything). */
static int reg_remove(void ***list, size_t *n, size_t *cap, const void *p)
{
    pthread_mutex_lock(&reg_lock);
    int found = 0;
    for (size_t i = 0; i < *n; i++)
        if ((*list)[i] == p) {
            (*list)[i] = (*list)[--*n];
            found = 1;
            break;
        }
    if (*n == 0) {
        free(*list);
        *list = NULL;
        *cap = 0;
    }
    pthread_mutex_unlock(&reg_lock);
    return found;
}

static int reg_has(void *const *list, const size_t *n, const void *p)
{
    pthread_mutex_lock(&reg_lock);
    int found = 0;
    for (size_t i = 0; i < *n && !found; i++)
        found = list[i] == p;
    pthread_mutex_unlock(&reg_lock);
    return found;
}

static int is_live(const void *c)
{
    return c != NULL && reg_has(reg_inst, &n_inst, c);
}

/* ---- logging ------------------------------------------------------------------------------ */

static void fmu_log(fmu *f, fmi2Status st, unsigned cat, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
/* Errors, discards and warnings are always reported through the logger (the reason of the
 * status); events and calls only with debug logging on and their category enabled. Logging
 * fmi2Error puts the instance into the standard's Error state (FMI 2.0, 2.1.3: after fmi2Error
 * only the get functions, fmi2SetFMUstate, fmi2Reset and fmi2FreeInstance are allowed). */
static void fmu_log(fmu *f, fmi2Status st, unsigned cat, const char *fmt, ...)
{
    if (f == NULL)
        return;
    if (st == fmi2Error)
        f->mode = M_ERROR;
    if (f->cb.logger == NULL)
        return;
    const int always = cat == C_ERROR || cat == C_DISCARD || cat == C_WARNING;
    if (!always && !(f->logging && (f->cats & cat)))
        return;
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    const char *cname = "logEvents";
    for (size_t i = 0; i < N_CATEGORIES; i++)
        if (categories[i].bit == cat)
            cname = categories[i].name;
    /* the message itself is the logger's format, every '%' doubled and no arguments: an
     * importer that formats it shows the text, and so does one that prints it as it is
     * (FMI 2.0, 2.1.5: the message "is to be formatted" like printf) */
    char fmt_msg[2 * sizeof msg];
    size_t n = 0;
    for (const char *p = msg; *p && n + 2 < sizeof fmt_msg; p++) {
        if (*p == '%')
            fmt_msg[n++] = '%';
        fmt_msg[n++] = *p;
    }
    fmt_msg[n] = '\0';
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wformat-security"
#pragma GCC diagnostic ignored "-Wformat-nonliteral"
    f->cb.logger(f->cb.componentEnvironment, f->name, st, cname, fmt_msg);
#pragma GCC diagnostic pop
}

#define FAIL(f, ...) (fmu_log((f), fmi2Error, C_ERROR, __VA_ARGS__), fmi2Error)

/* The call is allowed in the current mode (mask of B_*), else fmi2Error with a message. */
static int allowed(fmu *f, const char *fn, unsigned mask)
{
    if (!is_live(f)) {
        fprintf(stderr, "lvsim FMU: %s: %p is not a live instance of this FMU (freed with "
                "fmi2FreeInstance, or not returned by fmi2Instantiate): fmi2Error\n", fn,
                (const void *)f);
        return 0;
    }
    fmu_log(f, fmi2OK, C_CALLS, "%s (in %s)", fn, mode_names[f->mode]);
    if ((1u << f->mode) & mask)
        return 1;
    fmu_log(f, fmi2Error, C_ERROR, "%s: not allowed in %s (the FMI 2.0 state machine)", fn,
            mode_names[f->mode]);
    return 0;
}

static int is_me(fmu *f, const char *fn)
{
    if (f->type == fmi2ModelExchange)
        return 1;
    fmu_log(f, fmi2Error, C_ERROR, "%s: a Model Exchange function; this instance is "
            "Co-Simulation", fn);
    return 0;
}

static int is_cs(fmu *f, const char *fn)
{
    if (f->type == fmi2CoSimulation)
        return 1;
    fmu_log(f, fmi2Error, C_ERROR, "%s: a Co-Simulation function; this instance is "
            "Model Exchange", fn);
    return 0;
}

/* ---- the model ---------------------------------------------------------------------------- */

static const char *model_why(const fmu *f)
{
    const char *why = f->d->last_error ? f->d->last_error(f->inst) : NULL;
    return why != NULL ? why : "";
}

/* The model's init() (modes consistent with the start) when the start changed since. */
static int ensure_init(fmu *f)
{
    if (f->init_done)
        return 0;
    if (f->d->init != NULL && f->d->init(f->t, f->x, f->p, f->inst) != 0)
        return -1;
    f->init_done = 1;
    f->eval_ok = 0;
    return 0;
}

/* Derivatives and outputs at (t, x): 0, or the model's nonzero return (values NaN). */
static int eval_model(fmu *f)
{
    if (f->eval_ok)
        return 0;
    if (ensure_init(f) != 0)
        return -1;
    int rc = f->d->rhs(f->t, f->x, f->p, f->xdot, f->inst);
    for (size_t i = 0; rc == 0 && i < f->nx; i++)
        if (!isfinite(f->xdot[i]))
            rc = 1;
    if (rc != 0)
        for (size_t i = 0; i < f->nx; i++)
            f->xdot[i] = NAN;
    int rc_y = f->ny > 0 ? f->d->outputs_fn(f->t, f->x, f->p, f->y, f->inst) : 0;
    if (rc_y != 0)
        for (size_t i = 0; i < f->ny; i++)
            f->y[i] = NAN;
    if (rc == 0 && rc_y == 0)
        f->eval_ok = 1;
    return rc != 0 ? rc : rc_y;
}

/* The event indicators at (t, x): the model's event functions, its domain bounds (q - lower),
 * the phase's ends on a variable (variable - value). 0, or the model's nonzero return. */
static int eval_indicators(fmu *f, double *z)
{
    if (ensure_init(f) != 0)
        return -1;
    int rc = f->ng > 0 ? f->d->event_g(f->t, f->x, f->p, z, f->inst) : 0;
    if (rc != 0)
        return rc;
    if (f->nd > 0) {
        if ((rc = f->d->domain_q(f->t, f->x, f->p, f->q, f->inst)) != 0)
            return rc;
        for (size_t i = 0; i < f->nd; i++)
            z[f->ng + i] = f->q[i] - f->d->domain[i].lower;
    }
    int have_xdot = 0, have_y = 0;
    size_t r = 0;
    for (size_t j = 0; j < f->ns; j++) {
        const fmu_stop *sp = &f->stops[j];
        if (sp->is_time)
            continue;
        double v = 0.0;
        switch (sp->kind) {
        case LV_VAR_STATE: v = f->x[sp->index]; break;
        case LV_VAR_PARAMETER: v = f->p[sp->index]; break;
        case LV_VAR_DERIVATIVE:
            if (!have_xdot && (rc = f->d->rhs(f->t, f->x, f->p, f->xs, f->inst)) != 0)
                return rc;
            have_xdot = 1;
            v = f->xs[sp->index];
            break;
        case LV_VAR_OUTPUT:
            if (!have_y && (rc = f->d->outputs_fn(f->t, f->x, f->p, f->ys, f->inst)) != 0)
                return rc;
            have_y = 1;
            v = f->ys[sp->index];
            break;
        }
        z[f->ng + f->nd + r++] = v - sp->value;
    }
    return 0;
}

/* The next time event after f->t: the model's, a phase end on time, the phase's limit. */
static void schedule(fmu *f)
{
    f->t_model_te = f->d->next_time_event ? f->d->next_time_event(f->t, f->p, f->inst) : INFINITY;
    double tn = f->t_model_te;
    for (size_t j = 0; j < f->ns; j++)
        if (f->stops[j].is_time && f->stops[j].value > f->t && f->stops[j].value < tn)
            tn = f->stops[j].value;
    if (f->t_limit < tn)
        tn = f->t_limit;
    f->t_next = tn;
}

/* ---- resources ---------------------------------------------------------------------------- */

/* The folder of a file:// URI ("file:///a/b", "file://localhost/a/b", "file:/a/b"), decoded
 * (%XX), without a trailing slash. NULL when it is no local file URI. */
static char *uri_to_path(const char *uri)
{
    const char *p;
    if (strncmp(uri, "file:///", 8) == 0)
        p = uri + 7;
    else if (strncmp(uri, "file://localhost/", 17) == 0)
        p = uri + 16;
    else if (strncmp(uri, "file:/", 6) == 0)
        p = uri + 5;
    else
        return NULL;
    char *out = malloc(strlen(p) + 1);
    if (out == NULL)
        return NULL;
    size_t n = 0;
    for (; *p; p++) {
        unsigned v;
        if (p[0] == '%' && p[1] && p[2] && sscanf(p + 1, "%2x", &v) == 1) {
            out[n++] = (char)v;
            p += 2;
        } else {
            out[n++] = *p;
        }
    }
    while (n > 1 && out[n - 1] == '/')
        n--;
    out[n] = '\0';
    return out;
}

#define LV_FMU_MAX_FILES 256
typedef struct fmu_config {
    char guid[128], mission[2048], phase[256];
    long counts[4]; /* states, parameters, outputs, event indicators */
    size_t n_files;
    char sha[LV_FMU_MAX_FILES][65];   /* SHA-256 of each resource file (hex) */
    char *file[LV_FMU_MAX_FILES];     /* its path under resources/ (malloc) */
    size_t n_run;
    char *run[LV_FMU_MAX_RUN];        /* the run parameters offered (malloc) */
} fmu_config;

static void config_free(fmu_config *c)
{
    for (size_t i = 0; i < c->n_files; i++)
        free(c->file[i]);
    c->n_files = 0;
    for (size_t i = 0; i < c->n_run; i++)
        free(c->run[i]);
    c->n_run = 0;
}

/* The SHA-256 of a file in hex; -1 when it cannot be read. */
static int sha256_hex(const char *path, char hex[65])
{
    FILE *fp = fopen(path, "rb");
    if (fp == NULL)
        return -1;
    struct sha256_ctx ctx;
    sha256_init(&ctx);
    unsigned char buf[1 << 14];
    size_t got;
    while ((got = fread(buf, 1, sizeof buf, fp)) > 0)
        sha256_update(&ctx, got, buf);
    const int bad = ferror(fp);
    fclose(fp);
    if (bad)
        return -1;
    unsigned char d[SHA256_DIGEST_SIZE];
    sha256_digest(&ctx, sizeof d, d);
    for (size_t i = 0; i < sizeof d; i++)
        snprintf(hex + 2 * i, 3, "%02x", d[i]);
    return 0;
}

/* resources/lvsim-fmu.txt: "key value" lines written by the exporter. */
static int read_config(const char *path, fmu_config *c, char *why, size_t cap)
{
    FILE *fp = fopen(path, "r");
    if (fp == NULL) {
        snprintf(why, cap, "cannot open '%s'", path);
        return -1;
    }
    memset(c, 0, sizeof *c);
    for (int i = 0; i < 4; i++)
        c->counts[i] = -1;
    char line[2400];
    int have_magic = 0;
    while (fgets(line, sizeof line, fp) != NULL) {
        line[strcspn(line, "\r\n")] = '\0';
        char *sp = strchr(line, ' ');
        if (sp == NULL)
            continue;
        *sp = '\0';
        const char *v = sp + 1;
        if (strcmp(line, "lvsim-fmu") == 0)
            have_magic = strcmp(v, "2") == 0;
        else if (strcmp(line, "guid") == 0)
            snprintf(c->guid, sizeof c->guid, "%s", v);
        else if (strcmp(line, "mission") == 0)
            snprintf(c->mission, sizeof c->mission, "%s", v);
        else if (strcmp(line, "phase") == 0)
            snprintf(c->phase, sizeof c->phase, "%s", v);
        else if (strcmp(line, "states") == 0)
            c->counts[0] = atol(v);
        else if (strcmp(line, "parameters") == 0)
            c->counts[1] = atol(v);
        else if (strcmp(line, "outputs") == 0)
            c->counts[2] = atol(v);
        else if (strcmp(line, "event_indicators") == 0)
            c->counts[3] = atol(v);
        else if (strcmp(line, "run_parameter") == 0 && c->n_run < LV_FMU_MAX_RUN) {
            if ((c->run[c->n_run] = strdup(v)) == NULL) {
                fclose(fp);
                config_free(c);
                snprintf(why, cap, "out of memory");
                return -1;
            }
            c->n_run++;
        }
        else if (strcmp(line, "sha256") == 0) {
            /* "sha256 HEX PATH": PATH under resources/, the rest of the line */
            if (strlen(v) < 66 || v[64] != ' ' || c->n_files == LV_FMU_MAX_FILES) {
                fclose(fp);
                config_free(c);
                snprintf(why, cap, "resources/%s: bad line 'sha256 %.80s' (expected: sha256, "
                         "64 hex digits, the file's path)", LV_FMU_CONFIG, v);
                return -1;
            }
            memcpy(c->sha[c->n_files], v, 64);
            c->sha[c->n_files][64] = '\0';
            if ((c->file[c->n_files] = strdup(v + 65)) == NULL) {
                fclose(fp);
                config_free(c);
                snprintf(why, cap, "out of memory");
                return -1;
            }
            c->n_files++;
        }
    }
    fclose(fp);
    if (!have_magic || !c->guid[0] || !c->mission[0] || !c->phase[0] || c->n_files == 0) {
        config_free(c);
        snprintf(why, cap, "resources/%s is not an lvsim FMU description (format 2: lvsim-fmu 2, "
                 "guid, mission, phase, the counts and a sha256 line per resource file)",
                 LV_FMU_CONFIG);
        return -1;
    }
    return 0;
}

/* ---- instantiate, free, reset ------------------------------------------------------------- */

static void saved_free(fmu_saved *s);

static void fmu_free(fmu *f)
{
    if (f == NULL)
        return;
    /* the states it saved and the importer did not free: they go with it */
    for (;;) {
        fmu_saved *s = NULL;
        pthread_mutex_lock(&reg_lock);
        for (size_t i = 0; i < n_state && s == NULL; i++)
            if (((fmu_saved *)reg_state[i])->owner == f)
                s = reg_state[i];
        pthread_mutex_unlock(&reg_lock);
        if (s == NULL)
            break;
        reg_remove(&reg_state, &n_state, &cap_state, s);
        saved_free(s);
    }
    lv_sim_free(f->sim);
    free(f->x_set);
    free(f->p_set);
    free(f->start_reads);
    lv_fmu_phase_close(&f->ph);
    free(f->name);
    free(f->inst0);
    free(f->stops);
    free(f->x);
    free(f->p);
    free(f->xdot);
    free(f->y);
    free(f->q);
    free(f->xs);
    free(f->ys);
    free(f->z);
    free(f->z_pre);
    free(f->x_init);
    free(f->p_init);
    free(f->x_prev);
    free(f->fired);
    free(f->cs_names);
    free(f->cs_values);
    free(f);
}

/* Back to the state right after instantiation: start values, the instance's bytes. */
static void to_start(fmu *f)
{
    lv_sim_free(f->sim);
    f->sim = NULL;
    memcpy(f->x, f->ph.x0, f->nx * sizeof *f->x);
    memcpy(f->p, f->ph.p0, f->np * sizeof *f->p);
    if (f->inst_size > 0)
        memcpy(f->inst, f->inst0, f->inst_size);
    f->t = f->t_start = f->ph.s->start_time;
    f->t_limit = f->ph.s->stop_time;
    f->tol = f->ph.s->tolerance;
    f->eval_ok = 0;
    f->init_done = 0;
    f->end_reached = 0;
    f->end_name[0] = '\0';
    f->cs_terminated = 0;
    f->last_ok_time = f->t;
    f->stop_defined = 0;
    f->t_stop = INFINITY;
    memset(f->x_set, 0, f->nx + 1);
    memset(f->p_set, 0, f->np + 1);
    f->mode = M_INSTANTIATED;
}

/* Which parameters the model's start() reads (start_lat, start_h ...): each one moved in turn,
 * the start values compared with those of the phase's. A parameter start() fails on when
 * moved counts as read. The instance's bytes are put back after. */
static void probe_start_params(fmu *f)
{
    if (f->d->start == NULL || f->np == 0)
        return;
    double *p = malloc((f->np + 1) * sizeof *p), *xa = malloc((f->nx + 1) * sizeof *xa),
           *xb = malloc((f->nx + 1) * sizeof *xb);
    if (p != NULL && xa != NULL && xb != NULL) {
        memcpy(p, f->ph.p0, f->np * sizeof *p);
        memcpy(xa, f->ph.x0, f->nx * sizeof *xa);
        const int rc_a = f->d->start(p, xa, f->inst);
        for (size_t j = 0; rc_a == 0 && j < f->np; j++) {
            memcpy(xb, f->ph.x0, f->nx * sizeof *xb);
            const double keep = p[j];
            p[j] = keep + fmax(1e-3, 1e-3 * fabs(keep));
            const int rc_b = f->d->start(p, xb, f->inst);
            p[j] = keep;
            f->start_reads[j] = rc_b != 0 || memcmp(xa, xb, f->nx * sizeof *xa) != 0;
        }
    }
    free(p);
    free(xa);
    free(xb);
    if (f->inst_size > 0)
        memcpy(f->inst, f->inst0, f->inst_size);
}

/* After a run parameter changed (lv_run_set on the phase's run): the phase prepared again
 * (its ancestors run again where they read it) and its new model taken in: the instance's
 * bytes, the phase's ends, the time limit, the start values - except the states and
 * parameters the importer set, which keep its values. fmi2Error (the old model kept) when the
 * phase cannot be prepared with the new value. */
static fmi2Status adopt_phase(fmu *f, const char *why)
{
    lv_err err;
    if (lv_fmu_phase_reprepare(&f->ph, &err) != LV_OK)
        return FAIL(f, "%s: the phase cannot be prepared again: %s", why, err.msg);
    f->d = f->ph.def; /* the same counts (lv_fmu_phase_reprepare refuses other ones) */
    f->inst = f->ph.inst;
    if (f->inst_size > 0)
        memcpy(f->inst0, f->inst, f->inst_size);
    for (size_t j = 0; j < f->ns; j++) {
        const lv_sim_stop *sp = &f->ph.s->stops[j];
        f->stops[j].name = sp->name;
        f->stops[j].value = sp->value;
        f->stops[j].dir = sp->direction;
    }
    f->t_limit = f->ph.s->stop_time;
    for (size_t i = 0; i < f->nx; i++)
        if (!f->x_set[i])
            f->x[i] = f->ph.x0[i];
    for (size_t j = 0; j < f->np; j++)
        if (!f->p_set[j])
            f->p[j] = f->ph.p0[j];
    probe_start_params(f);
    f->init_done = 0;
    f->eval_ok = 0;
    f->gen++;
    return fmi2OK;
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation,
                              const fmi2CallbackFunctions *functions, fmi2Boolean visible,
                              fmi2Boolean loggingOn)
{
    (void)visible;
    fmu *f = calloc(1, sizeof *f);
    if (f == NULL)
        return NULL;
    if (functions != NULL)
        f->cb = *functions;
    f->name = strdup(instanceName != NULL ? instanceName : "");
    f->logging = loggingOn != 0;
    f->cats = C_EVENTS | C_DISCARD | C_ERROR; /* logCalls only when asked for */
    f->type = fmuType;
    char *dir = NULL;
    char why[4200];
    lv_err err = {0};
    if (f->name == NULL)
        goto fail_nomsg;
    if (instanceName == NULL || instanceName[0] == '\0') {
        fmu_log(f, fmi2Error, C_ERROR, "fmi2Instantiate: instanceName is empty");
        goto fail_nomsg;
    }
    if (fmuType != fmi2ModelExchange && fmuType != fmi2CoSimulation) {
        fmu_log(f, fmi2Error, C_ERROR, "fmi2Instantiate: unknown fmuType %d", (int)fmuType);
        goto fail_nomsg;
    }
    if (fmuResourceLocation == NULL || (dir = uri_to_path(fmuResourceLocation)) == NULL) {
        fmu_log(f, fmi2Error, C_ERROR, "fmi2Instantiate: fmuResourceLocation '%s' is not a "
                "file:// URI of the FMU's resources folder",
                fmuResourceLocation ? fmuResourceLocation : "(null)");
        goto fail_nomsg;
    }
    char path[4096];
    fmu_config cfg = {0};
    snprintf(path, sizeof path, "%s/%s", dir, LV_FMU_CONFIG);
    if (read_config(path, &cfg, why, sizeof why) != 0) {
        fmu_log(f, fmi2Error, C_ERROR, "fmi2Instantiate: %s", why);
        goto fail_nomsg;
    }
    if (fmuGUID == NULL || strcmp(fmuGUID, cfg.guid) != 0) {
        fmu_log(f, fmi2Error, C_ERROR, "fmi2Instantiate: GUID '%s' is not this FMU's '%s' "
                "(modelDescription.xml and resources/ from different exports?)",
                fmuGUID ? fmuGUID : "(null)", cfg.guid);
        config_free(&cfg);
        goto fail_nomsg;
    }
    snprintf(f->guid, sizeof f->guid, "%s", cfg.guid);
    /* the resources as exported: an edited mission or data file would give numbers the
     * description does not describe (its start values, its counts) */
    for (size_t i = 0; i < cfg.n_files; i++) {
        char fpath[6200], hex[65];
        snprintf(fpath, sizeof fpath, "%s/%s", dir, cfg.file[i]);
        const int rc = sha256_hex(fpath, hex);
        if (rc != 0 || strcmp(hex, cfg.sha[i]) != 0) {
            fmu_log(f, fmi2Error, C_ERROR, "fmi2Instantiate: resources/%s %s: the FMU's "
                    "resources must be as exported (resources/%s lists their SHA-256); export "
                    "the FMU again after changing the mission", cfg.file[i],
                    rc != 0 ? "cannot be read" : "differs from the file exported (its SHA-256 "
                    "is not the one recorded)", LV_FMU_CONFIG);
            config_free(&cfg);
            goto fail_nomsg;
        }
    }
    char **run_names = NULL; /* taken from cfg before it is freed */
    const size_t n_run = cfg.n_run;
    if (n_run > 0) {
        run_names = calloc(n_run, sizeof *run_names);
        if (run_names == NULL) {
            config_free(&cfg);
            goto fail_nomem;
        }
        memcpy(run_names, cfg.run, n_run * sizeof *run_names);
        cfg.n_run = 0;
    }
    config_free(&cfg);
    char mission[6200];
    snprintf(mission, sizeof mission, "%s/%s", dir, cfg.mission);
    const lv_status st_open = lv_fmu_phase_open(mission, cfg.phase, &f->ph, &err);
    int run_ok = st_open == LV_OK;
    if (run_ok && n_run > 0) {
        f->ph.run_idx = calloc(n_run, sizeof *f->ph.run_idx);
        run_ok = f->ph.run_idx != NULL;
        for (size_t r = 0; run_ok && r < n_run; r++) {
            int deg;
            if (lv_mission_param_find(f->ph.mission, run_names[r], &f->ph.run_idx[r], &deg,
                                      &err) != LV_OK) {
                fmu_log(f, fmi2Error, C_ERROR, "fmi2Instantiate: resources/%s: run parameter "
                        "'%s': %s", LV_FMU_CONFIG, run_names[r], err.msg);
                run_ok = 0;
            }
        }
        f->ph.n_run = f->nr = n_run;
    }
    for (size_t r = 0; r < n_run; r++)
        free(run_names[r]);
    free(run_names);
    if (st_open != LV_OK) {
        fmu_log(f, fmi2Error, C_ERROR, "fmi2Instantiate: %s", err.msg);
        goto fail_nomsg;
    }
    if (!run_ok)
        goto fail_nomsg;
    f->d = f->ph.def;
    f->inst = f->ph.inst;
    f->inst_size = f->inst != NULL ? f->d->inst_size : 0;
    f->nx = f->d->n_states;
    f->np = f->d->n_params;
    f->ny = f->d->n_outputs;
    f->ng = f->d->n_events;
    f->nd = f->d->n_domain;
    f->ns = f->ph.s->n_stops;
    f->stops = calloc(f->ns + 1, sizeof *f->stops);
    if (f->stops == NULL)
        goto fail_nomem;
    for (size_t j = 0; j < f->ns; j++) {
        const lv_sim_stop *sp = &f->ph.s->stops[j];
        fmu_stop *fs = &f->stops[j];
        fs->name = sp->name;
        fs->value = sp->value;
        fs->dir = sp->direction;
        fs->is_time = strcmp(sp->variable, "time") == 0;
        if (!fs->is_time) {
            if (lv_model_find(f->d, sp->variable, &fs->kind, &fs->index, &err) != LV_OK) {
                fmu_log(f, fmi2Error, C_ERROR, "fmi2Instantiate: phase end '%s': %s", sp->name,
                        err.msg);
                goto fail_nomsg;
            }
            f->ns_root++;
        }
    }
    f->ni = f->ng + f->nd + f->ns_root;
    const long have[4] = {(long)f->nx, (long)f->np, (long)f->ny, (long)f->ni};
    static const char *const what[4] = {"states", "parameters", "outputs", "event indicators"};
    for (int i = 0; i < 4; i++)
        if (cfg.counts[i] != have[i]) {
            fmu_log(f, fmi2Error, C_ERROR, "fmi2Instantiate: the model of phase '%s' has %ld %s, "
                    "resources/%s says %ld: the binary, the mission in resources/ and "
                    "resources/%s are not from one export", cfg.phase, have[i], what[i],
                    LV_FMU_CONFIG, cfg.counts[i], LV_FMU_CONFIG);
            goto fail_nomsg;
        }
    f->x = calloc(f->nx + 1, sizeof(double));
    f->p = calloc(f->np + 1, sizeof(double));
    f->xdot = calloc(f->nx + 1, sizeof(double));
    f->y = calloc(f->ny + 1, sizeof(double));
    f->q = calloc(f->nd + 1, sizeof(double));
    f->xs = calloc(f->nx + 1, sizeof(double));
    f->ys = calloc(f->ny + 1, sizeof(double));
    f->z = calloc(f->ni + 1, sizeof(double));
    f->z_pre = calloc(f->ni + 1, sizeof(double));
    f->x_init = calloc(f->nx + 1, sizeof(double));
    f->p_init = calloc(f->np + 1, sizeof(double));
    f->x_prev = calloc(f->nx + 1, sizeof(double));
    f->fired = calloc(f->ng + 1, sizeof(int));
    f->cs_names = calloc(f->nx + f->np + 1, sizeof(const char *));
    f->cs_values = calloc(f->nx + f->np + 1, sizeof(double));
    f->inst0 = malloc(f->inst_size + 1);
    f->x_set = calloc(f->nx + 1, 1);
    f->p_set = calloc(f->np + 1, 1);
    f->start_reads = calloc(f->np + 1, 1);
    if (!f->x || !f->p || !f->xdot || !f->y || !f->q || !f->xs || !f->ys || !f->z || !f->z_pre ||
        !f->x_init || !f->p_init || !f->x_prev || !f->fired || !f->cs_names || !f->cs_values ||
        !f->inst0 || !f->x_set || !f->p_set || !f->start_reads)
        goto fail_nomem;
    if (f->inst_size > 0)
        memcpy(f->inst0, f->inst, f->inst_size);
    probe_start_params(f);
    if (reg_add(&reg_inst, &n_inst, &cap_inst, f) != 0)
        goto fail_nomem;
    to_start(f);
    free(dir);
    fmu_log(f, fmi2OK, C_EVENTS, "instantiated phase '%s' of %s (%s, %zu states, %zu event "
            "indicators) for %s", cfg.phase, cfg.mission, f->d->name, f->nx, f->ni,
            fmuType == fmi2ModelExchange ? "Model Exchange" : "Co-Simulation");
    return f;
fail_nomem:
    fmu_log(f, fmi2Error, C_ERROR, "fmi2Instantiate: out of memory");
fail_nomsg:
    free(dir);
    fmu_free(f);
    return NULL;
}

/* A second fmi2FreeInstance of the same instance (undefined by the standard) is refused
 * without touching it: the registry no longer holds it. */
void fmi2FreeInstance(fmi2Component c)
{
    if (c == NULL)
        return;
    if (!reg_remove(&reg_inst, &n_inst, &cap_inst, c)) {
        fprintf(stderr, "lvsim FMU: fmi2FreeInstance: %p is not a live instance of this FMU "
                "(freed already, or not returned by fmi2Instantiate): ignored\n", c);
        return;
    }
    fmu_free(c);
}

fmi2Status fmi2Reset(fmi2Component c)
{
    fmu *f = c;
    if (!allowed(f, "fmi2Reset", ~0u))
        return fmi2Error;
    if (f->run_changed) { /* the run parameters back to the mission's values */
        lv_run_reset(f->ph.run);
        memset(f->x_set, 0, f->nx + 1);
        memset(f->p_set, 0, f->np + 1);
        if (adopt_phase(f, "fmi2Reset") != fmi2OK)
            return fmi2Error;
        f->run_changed = 0;
    }
    to_start(f);
    return fmi2OK;
}

const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories_in[])
{
    fmu *f = c;
    if (!allowed(f, "fmi2SetDebugLogging", ~0u))
        return fmi2Error;
    if (nCategories == 0) {
        f->logging = loggingOn != 0;
        f->cats = loggingOn ? C_EVENTS | C_DISCARD | C_ERROR | C_CALLS : 0u;
        return fmi2OK;
    }
    if (categories_in == NULL)
        return FAIL(f, "fmi2SetDebugLogging: %zu categories but no array", nCategories);
    for (size_t i = 0; i < nCategories; i++) {
        unsigned bit = 0;
        for (size_t k = 0; k < N_CATEGORIES; k++)
            if (categories_in[i] != NULL && strcmp(categories_in[i], categories[k].name) == 0)
                bit = categories[k].bit;
        if (bit == 0)
            return FAIL(f, "fmi2SetDebugLogging: unknown log category '%s' (known: logEvents, "
                        "logStatusDiscard, logStatusError, logCalls)",
                        categories_in[i] ? categories_in[i] : "(null)");
        f->cats = loggingOn ? f->cats | bit : f->cats & ~bit;
    }
    if (loggingOn)
        f->logging = 1;
    return fmi2OK;
}

/* ---- experiment and initialization -------------------------------------------------------- */

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance,
                               fmi2Real startTime, fmi2Boolean stopTimeDefined, fmi2Real stopTime)
{
    fmu *f = c;
    if (!allowed(f, "fmi2SetupExperiment", B_INST))
        return fmi2Error;
    /* The start time is part of the phase's start: the hand-off's states hold at that mission
     * time, and the model is time-dependent (the Earth's rotation angle, guidance clocks,
     * tables over mission time). Another start time would integrate the hand-off state from
     * the wrong instant: refused. A few ulps of a decimal round trip are accepted. */
    const double t0 = f->ph.s->start_time;
    if (!(fabs(startTime - t0) <= 4.0 * DBL_EPSILON * fmax(1.0, fabs(t0))))
        return FAIL(f, "fmi2SetupExperiment: startTime %.17g s is not the phase's start "
                    "%.17g s (DefaultExperiment startTime): the start state holds at that "
                    "mission time and the model depends on time (the planet's rotation, "
                    "guidance clocks, tables over mission time), so the FMU starts there only",
                    startTime, t0);
    if (stopTimeDefined && !(stopTime >= t0) )
        return FAIL(f, "fmi2SetupExperiment: stopTime %.17g s is before startTime %.17g s",
                    stopTime, t0);
    if (toleranceDefined && (!(tolerance > 0.0) || !isfinite(tolerance)))
        return FAIL(f, "fmi2SetupExperiment: tolerance %g is not > 0", tolerance);
    /* Co-Simulation: lvsim's integrator uses it, held to lv_simulate's range (Model Exchange:
     * the importer's integrator, not ours) */
    if (toleranceDefined && f->type == fmi2CoSimulation &&
        !(tolerance >= LV_TOLERANCE_MIN && tolerance <= LV_TOLERANCE_MAX))
        return FAIL(f, "fmi2SetupExperiment: tolerance %g is outside [%g, %g], the relative "
                    "tolerances lvsim's integrator accepts", tolerance, LV_TOLERANCE_MIN,
                    LV_TOLERANCE_MAX);
    if (toleranceDefined)
        f->tol = tolerance;
    f->stop_defined = stopTimeDefined != 0;
    f->t_stop = stopTimeDefined ? stopTime : INFINITY;
    f->t = f->t_start = t0;
    f->init_done = 0;
    f->eval_ok = 0;
    return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c)
{
    fmu *f = c;
    if (!allowed(f, "fmi2EnterInitializationMode", B_INST))
        return fmi2Error;
    f->mode = M_INIT;
    return fmi2OK;
}

static fmi2Status restart_from_params(fmu *f);

/* Round-off accepted beyond stopTime (a sum of communication steps). */
static double stop_slack(const fmu *f)
{
    return 1e-9 * fmax(1.0, fabs(f->t_stop));
}

/* Co-Simulation: lvsim's simulation from the current (t_start, x, p). */
static fmi2Status cs_create(fmu *f, const double *x, const double *p)
{
    const lv_sim_settings *ps = f->ph.s;
    lv_sim_settings *s = &f->cs;
    lv_sim_settings_default(s);
    s->start_time = f->t_start;
    s->stop_time = f->t_limit;
    s->number_of_intervals = ps->number_of_intervals;
    s->output_interval = ps->output_interval;
    s->method = ps->method;
    s->tolerance = f->tol;
    s->fixed_step = ps->fixed_step;
    s->result_file = NULL;
    s->result_formats = 0;
    s->max_steps = ps->max_steps;
    s->max_step_size = ps->max_step_size;
    s->n_stops = ps->n_stops;
    s->stops = ps->stops;
    for (size_t i = 0; i < f->nx; i++) {
        f->cs_names[i] = f->d->states[i].name;
        f->cs_values[i] = x[i];
    }
    for (size_t j = 0; j < f->np; j++) {
        f->cs_names[f->nx + j] = f->d->params[j].name;
        f->cs_values[f->nx + j] = p[j];
    }
    s->n_initial = f->nx + f->np;
    s->initial_names = f->cs_names;
    s->initial_values = f->cs_values;
    lv_err err;
    if (lv_sim_create(f->d, f->inst, s, &f->sim, &err) != LV_OK) {
        f->mode = M_ERROR;
        return FAIL(f, "%s", err.msg);
    }
    return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c)
{
    fmu *f = c;
    if (!allowed(f, "fmi2ExitInitializationMode", B_INIT))
        return fmi2Error;
    memcpy(f->x_init, f->x, f->nx * sizeof *f->x);
    memcpy(f->p_init, f->p, f->np * sizeof *f->p);
    f->end_reached = 0;
    f->t_prev_event = f->t;
    if (f->type == fmi2CoSimulation) {
        fmi2Status st = cs_create(f, f->x, f->p);
        if (st != fmi2OK)
            return st;
        f->last_ok_time = f->t;
        f->mode = M_STEP_COMPLETE;
        return fmi2OK;
    }
    f->init_done = 0;
    if (ensure_init(f) != 0) {
        f->mode = M_ERROR;
        const char *why = model_why(f);
        return FAIL(f, "model '%s': initialisation failed at t = %g s%s%s", f->d->name, f->t,
                    why[0] ? ": " : "", why);
    }
    if (f->nd > 0) {
        /* with the forces of the start, as lv_simulate (simulate.c): a failure shows later */
        if (f->d->rhs(f->t, f->x, f->p, f->xdot, f->inst) != 0) {
        }
        if (f->d->domain_q(f->t, f->x, f->p, f->q, f->inst) != 0) {
            f->mode = M_ERROR;
            return FAIL(f, "model '%s': the start state cannot be evaluated at t = %g s: %s",
                        f->d->name, f->t, model_why(f));
        }
        for (size_t i = 0; i < f->nd; i++)
            if (!f->d->domain[i].from_above && !(f->q[i] >= f->d->domain[i].lower)) {
                const lv_domain_def *b = &f->d->domain[i];
                f->mode = M_ERROR;
                return FAIL(f, "model '%s': the start state at t = %.9g s is outside the model's "
                            "domain: %s = %g %s is below its lower bound %g %s: %s", f->d->name,
                            f->t, b->quantity, f->q[i], b->unit, b->lower, b->unit, b->why);
            }
    }
    if (eval_indicators(f, f->z_pre) != 0) {
        f->mode = M_ERROR;
        return FAIL(f, "model '%s': the event indicators cannot be evaluated at the start "
                    "t = %g s: %s", f->d->name, f->t, model_why(f));
    }
    schedule(f);
    if (!(f->t_next > f->t)) {
        f->mode = M_ERROR;
        return FAIL(f, "model '%s': next time event %g is not after t = %g", f->d->name,
                    f->t_next, f->t);
    }
    f->mode = M_EVENT;
    return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component c)
{
    fmu *f = c;
    if (!allowed(f, "fmi2Terminate", B_EVENT | B_CONT | B_STEPOK | B_STEPFAIL))
        return fmi2Error;
    f->mode = M_TERMINATED;
    return fmi2OK;
}

/* ---- variables ---------------------------------------------------------------------------- */

/* The kind and index of a value reference, or -1. */
static int split_vr(const fmu *f, fmi2ValueReference vr, lv_var_kind *kind, size_t *idx)
{
    size_t v = vr;
    if (v < f->nx) {
        *kind = LV_VAR_STATE;
        *idx = v;
    } else if (v < 2 * f->nx) {
        *kind = LV_VAR_DERIVATIVE;
        *idx = v - f->nx;
    } else if (v < 2 * f->nx + f->np) {
        *kind = LV_VAR_PARAMETER;
        *idx = v - 2 * f->nx;
    } else if (v < 2 * f->nx + f->np + f->ny) {
        *kind = LV_VAR_OUTPUT;
        *idx = v - 2 * f->nx - f->np;
    } else {
        return -1;
    }
    return 0;
}

/* The run parameter of a value reference (after the outputs), or -1. */
static long run_of(const fmu *f, fmi2ValueReference vr)
{
    const size_t base = 2 * f->nx + f->np + f->ny;
    return vr >= base && vr < base + f->nr ? (long)(vr - base) : -1;
}

static const char *run_name(const fmu *f, size_t r)
{
    lv_param_info pi;
    lv_mission_param_info(f->ph.mission, f->ph.run_idx[r], &pi);
    return pi.name;
}

static const char *var_name(const fmu *f, lv_var_kind kind, size_t idx)
{
    switch (kind) {
    case LV_VAR_STATE: return f->d->states[idx].name;
    case LV_VAR_DERIVATIVE: return f->d->states[idx].name; /* der(...) */
    case LV_VAR_PARAMETER: return f->d->params[idx].name;
    case LV_VAR_OUTPUT: return f->d->outputs[idx].name;
    }
    return "?";
}

static int check_vrs(fmu *f, const char *fn, const fmi2ValueReference vr[], size_t nvr,
                     const void *values)
{
    if (nvr > 0 && (vr == NULL || values == NULL)) {
        fmu_log(f, fmi2Error, C_ERROR, "%s: NULL array for %zu values", fn, nvr);
        return -1;
    }
    for (size_t i = 0; i < nvr; i++) {
        lv_var_kind kind;
        size_t idx;
        if (split_vr(f, vr[i], &kind, &idx) != 0 && run_of(f, vr[i]) < 0) {
            fmu_log(f, fmi2Error, C_ERROR, "%s: unknown value reference %u (this FMU's Real "
                    "variables are 0 .. %zu)", fn, vr[i], 2 * f->nx + f->np + f->ny + f->nr - 1);
            return -1;
        }
    }
    return 0;
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       fmi2Real value[])
{
    fmu *f = c;
    if (!allowed(f, "fmi2GetReal", B_RUN) || check_vrs(f, "fmi2GetReal", vr, nvr, value) != 0)
        return fmi2Error;
    if (nvr == 0)
        return fmi2OK;
    int any_run = 0;
    for (size_t i = 0; i < nvr; i++)
        any_run |= run_of(f, vr[i]) >= 0;
    if (any_run) { /* the run parameters from the run, the others one by one */
        fmi2Status worst = fmi2OK;
        for (size_t i = 0; i < nvr; i++) {
            const long r = run_of(f, vr[i]);
            if (r >= 0) {
                value[i] = lv_run_get_index(f->ph.run, f->ph.run_idx[r]);
                continue;
            }
            const fmi2Status st = fmi2GetReal(c, &vr[i], 1, &value[i]);
            if (st > worst)
                worst = st;
            if (st == fmi2Error)
                return st;
        }
        return worst;
    }
    if (f->sim != NULL) { /* Co-Simulation after initialization: lvsim's simulation */
        lv_err err;
        if (lv_sim_get(f->sim, vr, nvr, value, &err) != LV_OK)
            return FAIL(f, "fmi2GetReal: %s", err.msg);
        for (size_t i = 0; i < nvr; i++)
            if (isnan(value[i])) {
                fmu_log(f, fmi2Discard, C_DISCARD, "fmi2GetReal: the model cannot be evaluated "
                        "at t = %.9g s: %s", lv_sim_time(f->sim), model_why(f));
                return fmi2Discard;
            }
        return fmi2OK;
    }
    int need_eval = 0;
    for (size_t i = 0; i < nvr; i++) {
        lv_var_kind kind;
        size_t idx;
        split_vr(f, vr[i], &kind, &idx);
        need_eval |= kind == LV_VAR_DERIVATIVE || kind == LV_VAR_OUTPUT;
    }
    int rc = need_eval ? eval_model(f) : 0;
    for (size_t i = 0; i < nvr; i++) {
        lv_var_kind kind;
        size_t idx;
        split_vr(f, vr[i], &kind, &idx);
        switch (kind) {
        case LV_VAR_STATE: value[i] = f->x[idx]; break;
        case LV_VAR_DERIVATIVE: value[i] = f->xdot[idx]; break;
        case LV_VAR_PARAMETER: value[i] = f->p[idx]; break;
        case LV_VAR_OUTPUT: value[i] = f->y[idx]; break;
        }
    }
    if (rc != 0) {
        fmu_log(f, fmi2Discard, C_DISCARD, "fmi2GetReal: the model cannot be evaluated at "
                "t = %.9g s: %s", f->t, model_why(f));
        return fmi2Discard;
    }
    return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       const fmi2Real value[])
{
    fmu *f = c;
    if (!allowed(f, "fmi2SetReal", B_INST | B_INIT | B_EVENT | B_CONT | B_STEPOK) ||
        check_vrs(f, "fmi2SetReal", vr, nvr, value) != 0)
        return fmi2Error;
    for (size_t i = 0; i < nvr; i++) {
        lv_var_kind kind;
        size_t idx;
        const long r = run_of(f, vr[i]);
        if (r >= 0) {
            /* FMI 2.0.4, 2.2.7: a fixed parameter is set before fmi2ExitInitializationMode */
            if (f->mode != M_INSTANTIATED && f->mode != M_INIT)
                return FAIL(f, "fmi2SetReal: '%s' (value reference %u) is a run parameter of the "
                            "mission (fixed): it can be set only before "
                            "fmi2ExitInitializationMode", run_name(f, (size_t)r), vr[i]);
            if (!isfinite(value[i]))
                return FAIL(f, "fmi2SetReal: value %g for '%s' is not finite", value[i],
                            run_name(f, (size_t)r));
            continue;
        }
        split_vr(f, vr[i], &kind, &idx);
        const char *nm = var_name(f, kind, idx);
        if (kind == LV_VAR_DERIVATIVE || kind == LV_VAR_OUTPUT)
            return FAIL(f, "fmi2SetReal: '%s%s%s' (value reference %u) is %s, computed by the "
                        "model: it cannot be set", kind == LV_VAR_DERIVATIVE ? "der(" : "", nm,
                        kind == LV_VAR_DERIVATIVE ? ")" : "", vr[i],
                        kind == LV_VAR_OUTPUT ? "an output" : "a derivative");
        const int input = kind == LV_VAR_PARAMETER && f->ph.is_input[idx];
        if (f->mode != M_INSTANTIATED && f->mode != M_INIT && !input)
            return FAIL(f, "fmi2SetReal: '%s' (value reference %u) is a %s: it can be set only "
                        "before fmi2ExitInitializationMode%s", nm, vr[i],
                        kind == LV_VAR_STATE ? "state" : "fixed parameter",
                        kind == LV_VAR_STATE && f->type == fmi2ModelExchange
                            ? " (then with fmi2SetContinuousStates)" : "");
        if (!isfinite(value[i]))
            return FAIL(f, "fmi2SetReal: value %g for '%s' is not finite", value[i], nm);
    }
    /* the run parameters first: the phase prepared again, then the states and parameters of
     * this call (and of earlier ones) set on top */
    int run_moved = 0;
    for (size_t i = 0; i < nvr; i++) {
        const long r = run_of(f, vr[i]);
        if (r < 0)
            continue;
        const size_t mi = f->ph.run_idx[r];
        if (lv_run_get_index(f->ph.run, mi) == value[i])
            continue;
        lv_err err;
        if (lv_run_set_index(f->ph.run, mi, value[i], &err) != LV_OK)
            return FAIL(f, "fmi2SetReal: '%s': %s", run_name(f, (size_t)r), err.msg);
        run_moved = 1;
    }
    if (run_moved) {
        f->run_changed = 1;
        if (adopt_phase(f, "fmi2SetReal") != fmi2OK)
            return fmi2Error;
    }
    if (f->sim != NULL) {
        /* Co-Simulation after initialization: inputs only (checked above), into lvsim's
         * simulation, which restarts its integrator there (lv_sim_set) */
        lv_err err;
        if (lv_sim_set(f->sim, vr, nvr, value, &err) != LV_OK)
            return FAIL(f, "fmi2SetReal: %s", err.msg);
        for (size_t i = 0; i < nvr; i++)
            f->p[vr[i] - 2 * f->nx] = value[i];
        return fmi2OK;
    }
    int start_moved = 0;
    const char *child_start = NULL;
    for (size_t i = 0; i < nvr; i++) {
        lv_var_kind kind;
        size_t idx;
        if (run_of(f, vr[i]) >= 0)
            continue;
        split_vr(f, vr[i], &kind, &idx);
        if (kind == LV_VAR_STATE) {
            f->x[idx] = value[i];
            f->x_set[idx] = 1;
        } else {
            f->p_set[idx] = 1;
            if (f->start_reads[idx] && f->p[idx] != value[i]) {
                start_moved = 1;
                if (child_start == NULL)
                    child_start = f->d->params[idx].name;
            }
            f->p[idx] = value[i];
        }
    }
    if (nvr > 0) {
        /* before initialization the model's init() runs again for the new start; an input set
         * in Event or Continuous-Time Mode changes the right-hand side only (the model's modes
         * stay as they are) */
        if (f->mode == M_INSTANTIATED || f->mode == M_INIT)
            f->init_done = 0;
        f->eval_ok = 0;
    }
    if (start_moved && f->ph.parent < 0)
        return restart_from_params(f);
    if (start_moved) {
        /* a child phase: the hand-off gives every state */
        fmu_log(f, fmi2Warning, C_WARNING, "fmi2SetReal: '%s' is a start-value parameter of "
                "model '%s', but phase '%s' starts from the final state of phase '%s': the "
                "start state stays the hand-off's (set the states to move it); the value "
                "counts only where the model's equations read it", child_start, f->d->name,
                lv_mission_phase_name(f->ph.mission, f->ph.k),
                lv_mission_phase_name(f->ph.mission, (size_t)f->ph.parent));
        return fmi2Warning;
    }
    return fmi2OK;
}

/* A root phase whose start-value parameters (start_lat, start_h ...) were set: the start
 * states computed again from the parameters as lv_simulate computes them (the states'
 * defaults, the model's start(), the states the mission names), then the states the importer
 * set kept. On failure the parameters' old values are not known here: fmi2Error, and the
 * instance is in the Error state (fmi2Reset starts again). */
static fmi2Status restart_from_params(fmu *f)
{
    const lv_sim_settings *s = f->ph.s;
    double *xn = f->xs; /* scratch [nx] */
    for (size_t i = 0; i < f->nx; i++)
        xn[i] = f->d->states[i].start;
    if (f->d->start(f->p, xn, f->inst) != 0)
        return FAIL(f, "fmi2SetReal: model '%s': the start state cannot be computed from the "
                    "start-value parameters: %s", f->d->name, model_why(f));
    for (size_t i = 0; i < s->n_initial; i++) {
        lv_var_kind kind;
        size_t idx;
        lv_err err;
        if (lv_model_find(f->d, s->initial_names[i], &kind, &idx, &err) == LV_OK &&
            kind == LV_VAR_STATE)
            xn[idx] = s->initial_values[i];
    }
    for (size_t i = 0; i < f->nx; i++) {
        if (!f->x_set[i])
            f->x[i] = xn[i];
        if (!isfinite(f->x[i]))
            return FAIL(f, "fmi2SetReal: model '%s': start value of '%s' is %g", f->d->name,
                        f->d->states[i].name, f->x[i]);
    }
    f->init_done = 0;
    f->eval_ok = 0;
    return fmi2OK;
}

/* No Integer, Boolean or String variables: every reference is unknown. */
#define NO_VARS(fn)                                                                           \
    fmu *f = c;                                                                               \
    (void)value;                                                                              \
    if (!allowed(f, #fn, ~0u))                                                                \
        return fmi2Error;                                                                     \
    if (nvr == 0)                                                                             \
        return fmi2OK;                                                                        \
    return FAIL(f, "%s: unknown value reference %u: this FMU has Real variables only", #fn,  \
                vr != NULL ? vr[0] : 0u)

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Integer value[]) { NO_VARS(fmi2GetInteger); }
fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Boolean value[]) { NO_VARS(fmi2GetBoolean); }
fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                         fmi2String value[]) { NO_VARS(fmi2GetString); }
fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Integer value[]) { NO_VARS(fmi2SetInteger); }
fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Boolean value[]) { NO_VARS(fmi2SetBoolean); }
fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                         const fmi2String value[]) { NO_VARS(fmi2SetString); }

fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference vUnknown_ref[],
                                        size_t nUnknown, const fmi2ValueReference vKnown_ref[],
                                        size_t nKnown, const fmi2Real dvKnown[],
                                        fmi2Real dvUnknown[])
{
    (void)vUnknown_ref, (void)nUnknown, (void)vKnown_ref, (void)nKnown, (void)dvKnown;
    (void)dvUnknown;
    fmu *f = c;
    if (!allowed(f, "fmi2GetDirectionalDerivative", ~0u))
        return fmi2Error;
    return FAIL(f, "fmi2GetDirectionalDerivative: not provided (providesDirectionalDerivative "
                "is false)");
}

/* ---- FMU states ---------------------------------------------------------------------------- */

static void saved_free(fmu_saved *s)
{
    if (s == NULL)
        return;
    free(s->x);
    free(s->p);
    free(s->z_pre);
    free(s->x_init);
    free(s->p_init);
    free(s->x_set);
    free(s->inst);
    lv_sim_saved_free(s->sim);
    free(s);
}

static const char *type_name(fmi2Type t)
{
    return t == fmi2ModelExchange ? "Model Exchange" : "Co-Simulation";
}

/* The state is a live one of instance f: 1; else fmi2Error logged (why) and 0. The state is
 * looked up in the registry before it is read: a freed one, one of another FMU (another
 * binary, so another registry) or any other pointer is refused without touching it. */
static int own_state(fmu *f, const char *fn, const void *state)
{
    if (!reg_has(reg_state, &n_state, state)) {
        fmu_log(f, fmi2Error, C_ERROR, "%s: %p is not a live FMU state of this FMU (freed with "
                "fmi2FreeFMUstate or with its instance, saved by another FMU, or not returned "
                "by fmi2GetFMUstate)", fn, state);
        return 0;
    }
    const fmu_saved *s = state;
    if (s->owner != f) {
        /* the owner is live: its states are freed with it */
        fmu_log(f, fmi2Error, C_ERROR, "%s: the state was saved by instance '%s' (%s, GUID %s), "
                "not by this instance '%s' (%s, GUID %s): an FMU state belongs to the instance "
                "that saved it", fn, s->owner->name, type_name(s->type), s->owner->guid,
                f->name, type_name(f->type), f->guid);
        return 0;
    }
    return 1;
}

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *FMUstate)
{
    fmu *f = c;
    if (!allowed(f, "fmi2GetFMUstate", ~0u))
        return fmi2Error;
    if (FMUstate == NULL)
        return FAIL(f, "fmi2GetFMUstate: NULL pointer");
    fmu_saved *s = *FMUstate; /* an earlier state given back is overwritten */
    if (s != NULL && !own_state(f, "fmi2GetFMUstate", s))
        return fmi2Error;
    const int fresh = s == NULL;
    if (fresh && (s = calloc(1, sizeof *s)) == NULL)
        return FAIL(f, "fmi2GetFMUstate: out of memory");
    s->owner = f;
    s->type = f->type;
    lv_sim_saved_free(s->sim);
    s->sim = NULL;
    if ((s->x == NULL && (s->x = malloc((f->nx + 1) * sizeof(double))) == NULL) ||
        (s->p == NULL && (s->p = malloc((f->np + 1) * sizeof(double))) == NULL) ||
        (s->z_pre == NULL && (s->z_pre = malloc((f->ni + 1) * sizeof(double))) == NULL) ||
        (s->x_init == NULL && (s->x_init = malloc((f->nx + 1) * sizeof(double))) == NULL) ||
        (s->p_init == NULL && (s->p_init = malloc((f->np + 1) * sizeof(double))) == NULL) ||
        (s->x_set == NULL && (s->x_set = malloc(f->nx + 1)) == NULL) ||
        (s->inst == NULL && (s->inst = malloc(f->inst_size + 1)) == NULL)) {
        if (fresh)
            saved_free(s);
        return FAIL(f, "fmi2GetFMUstate: out of memory");
    }
    if (f->sim != NULL) {
        /* side-effect free: the simulation's integrator goes on untouched */
        lv_err err;
        if (lv_sim_save(f->sim, &s->sim, &err) != LV_OK) {
            if (fresh)
                saved_free(s);
            return FAIL(f, "fmi2GetFMUstate: %s", err.msg);
        }
    }
    if (fresh && reg_add(&reg_state, &n_state, &cap_state, s) != 0) {
        saved_free(s);
        return FAIL(f, "fmi2GetFMUstate: out of memory");
    }
#define COPY_OUT(field) s->field = f->field;
    FMU_SAVED_SCALARS(COPY_OUT)
#undef COPY_OUT
    memcpy(s->x, f->x, f->nx * sizeof(double));
    memcpy(s->p, f->p, f->np * sizeof(double));
    memcpy(s->z_pre, f->z_pre, f->ni * sizeof(double));
    memcpy(s->x_init, f->x_init, f->nx * sizeof(double));
    memcpy(s->p_init, f->p_init, f->np * sizeof(double));
    memcpy(s->x_set, f->x_set, f->nx);
    if (f->inst_size > 0)
        memcpy(s->inst, f->inst, f->inst_size);
    memcpy(s->end_name, f->end_name, sizeof s->end_name);
    s->gen = f->gen;
    *FMUstate = s;
    return fmi2OK;
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate FMUstate)
{
    fmu *f = c;
    if (!allowed(f, "fmi2SetFMUstate", ~0u))
        return fmi2Error;
    if (FMUstate == NULL)
        return FAIL(f, "fmi2SetFMUstate: NULL state");
    if (!own_state(f, "fmi2SetFMUstate", FMUstate))
        return fmi2Error;
    const fmu_saved *s = FMUstate;
    if (s->gen != f->gen)
        return FAIL(f, "fmi2SetFMUstate: the state was saved before a run parameter (or "
                    "fmi2Reset after one) prepared the phase's model again: it holds the old "
                    "model's instance");
    const int after_init = s->mode != M_INSTANTIATED && s->mode != M_INIT;
    f->t_start = s->t_start;
    f->tol = s->tol;
    memcpy(f->x_init, s->x_init, f->nx * sizeof(double));
    memcpy(f->p_init, s->p_init, f->np * sizeof(double));
    if (after_init && f->type == fmi2CoSimulation && s->sim != NULL) {
        if (f->sim == NULL) { /* after fmi2Reset: the simulation made again, then restored */
            if (cs_create(f, s->x_init, s->p_init) != fmi2OK)
                return fmi2Error;
        }
        lv_err err;
        if (lv_sim_restore(f->sim, s->sim, &err) != LV_OK)
            return FAIL(f, "fmi2SetFMUstate: %s", err.msg);
    } else if (after_init && f->type == fmi2ModelExchange && f->d->init != NULL) {
        /* the model's init() may set up more than its instance (an impact level's offset):
         * done again for the saved start, then the instance's bytes are the saved ones */
        f->d->init(s->t_start, s->x_init, s->p_init, f->inst);
    }
    if (!after_init || f->type == fmi2ModelExchange) {
        lv_sim_free(f->sim);
        f->sim = NULL;
    }
#define COPY_BACK(field) f->field = s->field;
    FMU_SAVED_SCALARS(COPY_BACK)
#undef COPY_BACK
    memcpy(f->x, s->x, f->nx * sizeof(double));
    memcpy(f->p, s->p, f->np * sizeof(double));
    memcpy(f->z_pre, s->z_pre, f->ni * sizeof(double));
    memcpy(f->x_set, s->x_set, f->nx);
    if (f->inst_size > 0)
        memcpy(f->inst, s->inst, f->inst_size);
    memcpy(f->end_name, s->end_name, sizeof f->end_name);
    f->eval_ok = 0;
    return fmi2OK;
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *FMUstate)
{
    fmu *f = c;
    if (!allowed(f, "fmi2FreeFMUstate", ~0u))
        return fmi2Error;
    if (FMUstate == NULL)
        return FAIL(f, "fmi2FreeFMUstate: NULL pointer");
    if (*FMUstate == NULL)
        return fmi2OK;
    if (!own_state(f, "fmi2FreeFMUstate", *FMUstate))
        return fmi2Error;
    reg_remove(&reg_state, &n_state, &cap_state, *FMUstate);
    saved_free(*FMUstate);
    *FMUstate = NULL;
    return fmi2OK;
}

#define NO_SERIALIZE(fn)                                                                      \
    fmu *f = c;                                                                               \
    if (!allowed(f, #fn, ~0u))                                                                \
        return fmi2Error;                                                                     \
    return FAIL(f, "%s: not supported (canSerializeFMUstate is false: a saved state holds "   \
                "the model's instance data, pointers included, valid in this process only)", #fn)

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate FMUstate, size_t *size)
{
    (void)FMUstate, (void)size;
    NO_SERIALIZE(fmi2SerializedFMUstateSize);
}
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate FMUstate,
                                 fmi2Byte serializedState[], size_t size)
{
    (void)FMUstate, (void)serializedState, (void)size;
    NO_SERIALIZE(fmi2SerializeFMUstate);
}
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte serializedState[], size_t size,
                                   fmi2FMUstate *FMUstate)
{
    (void)serializedState, (void)size, (void)FMUstate;
    NO_SERIALIZE(fmi2DeSerializeFMUstate);
}

/* ---- Model Exchange ------------------------------------------------------------------------ */

fmi2Status fmi2EnterEventMode(fmi2Component c)
{
    fmu *f = c;
    if (!allowed(f, "fmi2EnterEventMode", B_EVENT | B_CONT) || !is_me(f, "fmi2EnterEventMode"))
        return fmi2Error;
    f->mode = M_EVENT;
    return fmi2OK;
}

static void note_end(fmu *f, const char *name)
{
    if (!f->end_reached)
        snprintf(f->end_name, sizeof f->end_name, "%s", name);
    f->end_reached = 1;
}

/* The events at f->t, in lv_simulate's order: the model's state events (one on_event call),
 * the phase's ends (crossings, then times), the model's time event; then the domain. */
fmi2Status fmi2NewDiscreteStates(fmi2Component c, fmi2EventInfo *ev)
{
    fmu *f = c;
    if (!allowed(f, "fmi2NewDiscreteStates", B_EVENT) || !is_me(f, "fmi2NewDiscreteStates"))
        return fmi2Error;
    if (ev == NULL)
        return FAIL(f, "fmi2NewDiscreteStates: NULL eventInfo");
    const lv_model_def *d = f->d;
    memset(ev, 0, sizeof *ev);
    if (eval_indicators(f, f->z) != 0) {
        f->mode = M_ERROR;
        return FAIL(f, "model '%s': the event indicators cannot be evaluated at t = %.9g s: %s",
                    d->name, f->t, model_why(f));
    }
    double *x_before = f->x_prev;
    memcpy(x_before, f->x, f->nx * sizeof *x_before);
    /* a crossing: z leaves (0, inf) or enters it (the standard's z > 0 / z <= 0) */
#define CROSS(i) ((f->z_pre[i] > 0.0) == (f->z[i] > 0.0) ? 0 : f->z[i] > 0.0 ? 1 : -1)
    int any = 0;
    for (size_t i = 0; i < f->ng; i++) {
        const int s = CROSS(i);
        const int want = (int)d->events[i].direction;
        f->fired[i] = s != 0 && (want == 0 || want == s) ? s : 0;
        any |= f->fired[i] != 0;
    }
    if (any) {
        for (size_t i = 0; i < f->ng; i++)
            if (f->fired[i])
                fmu_log(f, fmi2OK, C_EVENTS, "t = %.9g s: state event '%s' (%s)", f->t,
                        d->events[i].name, f->fired[i] > 0 ? "rising" : "falling");
        lv_event_action a = d->on_event ? d->on_event(f->t, f->x, f->p, f->fired, f->inst)
                                        : LV_EVENT_STOP;
        if (a == LV_EVENT_STOP) {
            const char *nm = "event";
            for (size_t i = 0; i < f->ng; i++)
                if (f->fired[i]) {
                    nm = d->events[i].name;
                    break;
                }
            note_end(f, nm);
        }
    }
    size_t r = 0;
    for (size_t j = 0; j < f->ns; j++) {
        const fmu_stop *sp = &f->stops[j];
        int hit;
        if (sp->is_time) {
            hit = sp->value > f->t_prev_event && f->t >= sp->value;
        } else {
            const int s = CROSS(f->ng + f->nd + r);
            hit = s != 0 && (sp->dir == LV_DIR_BOTH || (int)sp->dir == s);
            r++;
        }
        if (hit) {
            fmu_log(f, fmi2OK, C_EVENTS, "t = %.9g s: the phase's end '%s'", f->t, sp->name);
            note_end(f, sp->name);
        }
    }
    if (f->t >= f->t_model_te) {
        const char *tev = d->time_event_name ? d->time_event_name(f->t, f->p, f->inst) : NULL;
        fmu_log(f, fmi2OK, C_EVENTS, "t = %.9g s: time event (%s)", f->t,
                tev != NULL ? tev : "time event");
        lv_event_action a = d->on_time_event ? d->on_time_event(f->t, f->x, f->p, f->inst)
                                             : LV_EVENT_RESTART;
        if (a == LV_EVENT_STOP)
            note_end(f, tev != NULL ? tev : "time event");
    }
    if (f->t >= f->t_limit) {
        fmu_log(f, fmi2OK, C_EVENTS, "t = %.9g s: the phase's time limit", f->t);
        note_end(f, "stop_time");
    }
    for (size_t i = 0; i < f->nd; i++) {
        if (CROSS(f->ng + i) < 0 && !f->end_reached) {
            const lv_domain_def *b = &d->domain[i];
            f->mode = M_ERROR;
            return FAIL(f, "model '%s': at t = %.9g s the state left the model's domain: %s fell "
                        "to its lower bound %g %s: %s", d->name, f->t, b->quantity, b->lower,
                        b->unit, b->why);
        }
    }
#undef CROSS
    for (size_t i = 0; i < f->nx; i++)
        if (!isfinite(f->x[i])) {
            f->mode = M_ERROR;
            return FAIL(f, "model '%s': event handler at t = %.9g s made '%s' = %g", d->name,
                        f->t, d->states[i].name, f->x[i]);
        }
    ev->valuesOfContinuousStatesChanged =
        memcmp(x_before, f->x, f->nx * sizeof *x_before) != 0 ? fmi2True : fmi2False;
    f->eval_ok = 0;
    if (eval_indicators(f, f->z_pre) != 0) {
        f->mode = M_ERROR;
        return FAIL(f, "model '%s': the event indicators cannot be evaluated after the event at "
                    "t = %.9g s: %s", d->name, f->t, model_why(f));
    }
    f->t_prev_event = f->t;
    if (f->end_reached) {
        fmu_log(f, fmi2OK, C_EVENTS, "t = %.9g s: the phase ends ('%s'): terminateSimulation",
                f->t, f->end_name);
        ev->terminateSimulation = fmi2True;
        return fmi2OK;
    }
    schedule(f);
    if (!(f->t_next > f->t)) {
        f->mode = M_ERROR;
        return FAIL(f, "model '%s': next time event %g is not after t = %g", d->name, f->t_next,
                    f->t);
    }
    ev->nextEventTimeDefined = fmi2True;
    ev->nextEventTime = f->t_next;
    return fmi2OK;
}

fmi2Status fmi2EnterContinuousTimeMode(fmi2Component c)
{
    fmu *f = c;
    if (!allowed(f, "fmi2EnterContinuousTimeMode", B_EVENT) ||
        !is_me(f, "fmi2EnterContinuousTimeMode"))
        return fmi2Error;
    /* FMI 2.0.4, 3.2.3 (the Model Exchange state machine): fmi2EnterContinuousTimeMode is
     * allowed in Event Mode whatever eventInfo said, and fmi2Terminate is allowed in Event
     * and Continuous-Time Mode. An importer that enters Continuous-Time Mode after the
     * phase's end (terminateSimulation) before it calls fmi2Terminate - the compliance
     * checker's loop does - follows the state machine: accepted. The model is still
     * evaluated where it is asked (past its end the phase is not lvsim's any more), and
     * fmi2CompletedIntegratorStep repeats terminateSimulation. */
    if (f->end_reached)
        fmu_log(f, fmi2OK, C_EVENTS, "fmi2EnterContinuousTimeMode: the phase ended at "
                "t = %.9g s ('%s'): terminateSimulation stays set", f->t, f->end_name);
    f->mode = M_CONT;
    return fmi2OK;
}

fmi2Status fmi2CompletedIntegratorStep(fmi2Component c, fmi2Boolean noSetFMUStatePriorToCurrentPoint,
                                       fmi2Boolean *enterEventMode,
                                       fmi2Boolean *terminateSimulation)
{
    (void)noSetFMUStatePriorToCurrentPoint;
    fmu *f = c;
    if (!allowed(f, "fmi2CompletedIntegratorStep", B_CONT) ||
        !is_me(f, "fmi2CompletedIntegratorStep"))
        return fmi2Error;
    if (enterEventMode == NULL || terminateSimulation == NULL)
        return FAIL(f, "fmi2CompletedIntegratorStep: NULL pointer");
    *enterEventMode = fmi2False; /* no step events: every event is a state or time event */
    /* after the phase's end (a legal Continuous-Time Mode, above) the request to terminate
     * is repeated here (FMI 2.0.4, 3.2.2: "terminateSimulation ... the environment has to
     * call fmi2Terminate") */
    *terminateSimulation = f->end_reached ? fmi2True : fmi2False;
    return fmi2OK;
}

fmi2Status fmi2SetTime(fmi2Component c, fmi2Real time)
{
    fmu *f = c;
    /* the standard's Event and Continuous-Time Modes only: the start time is
     * fmi2SetupExperiment's */
    if (!allowed(f, "fmi2SetTime", B_EVENT | B_CONT) || !is_me(f, "fmi2SetTime"))
        return fmi2Error;
    if (!isfinite(time))
        return FAIL(f, "fmi2SetTime: time %g is not finite", time);
    if (f->stop_defined && time > f->t_stop + stop_slack(f))
        return FAIL(f, "fmi2SetTime: time %.17g s is past stopTime %.17g s of "
                    "fmi2SetupExperiment (stopTimeDefined): the FMU computes up to stopTime "
                    "only", time, f->t_stop);
    f->t = time;
    f->eval_ok = 0;
    return fmi2OK;
}

fmi2Status fmi2SetContinuousStates(fmi2Component c, const fmi2Real x[], size_t nx)
{
    fmu *f = c;
    if (!allowed(f, "fmi2SetContinuousStates", B_CONT) || !is_me(f, "fmi2SetContinuousStates"))
        return fmi2Error;
    if (nx > 0 && x == NULL)
        return FAIL(f, "fmi2SetContinuousStates: the array 'x' is NULL (%zu states)", nx);
    if (nx != f->nx)
        return FAIL(f, "fmi2SetContinuousStates: %zu states given, the model has %zu", nx, f->nx);
    memcpy(f->x, x, nx * sizeof *x);
    f->eval_ok = 0;
    return fmi2OK;
}

fmi2Status fmi2GetDerivatives(fmi2Component c, fmi2Real derivatives[], size_t nx)
{
    fmu *f = c;
    if (!allowed(f, "fmi2GetDerivatives", B_INIT | B_EVENT | B_CONT | B_TERM | B_ERR) ||
        !is_me(f, "fmi2GetDerivatives"))
        return fmi2Error;
    if (nx > 0 && derivatives == NULL)
        return FAIL(f, "fmi2GetDerivatives: the array 'derivatives' is NULL (%zu asked for)",
                    nx);
    if (nx != f->nx)
        return FAIL(f, "fmi2GetDerivatives: %zu derivatives asked for, the model has %zu", nx,
                    f->nx);
    int rc = eval_model(f);
    memcpy(derivatives, f->xdot, nx * sizeof *derivatives);
    if (rc == 0)
        return fmi2OK;
    if (rc < 0) {
        f->mode = M_ERROR;
        return FAIL(f, "model '%s': right-hand side returned %d at t = %.9g s: %s", f->d->name,
                    rc, f->t, model_why(f));
    }
    /* outside the model's domain (a table's range, a state it cannot take): the standard's
     * fmi2Discard - the importer retries with a smaller step */
    fmu_log(f, fmi2Discard, C_DISCARD, "model '%s': the right-hand side cannot be evaluated at "
            "t = %.9g s: %s", f->d->name, f->t, model_why(f)[0] ? model_why(f)
                                                             : "a derivative is not finite");
    return fmi2Discard;
}

fmi2Status fmi2GetEventIndicators(fmi2Component c, fmi2Real eventIndicators[], size_t ni)
{
    fmu *f = c;
    if (!allowed(f, "fmi2GetEventIndicators", B_INIT | B_EVENT | B_CONT | B_TERM | B_ERR) ||
        !is_me(f, "fmi2GetEventIndicators"))
        return fmi2Error;
    if (ni > 0 && eventIndicators == NULL)
        return FAIL(f, "fmi2GetEventIndicators: the array 'eventIndicators' is NULL (%zu asked "
                    "for)", ni);
    if (ni != f->ni)
        return FAIL(f, "fmi2GetEventIndicators: %zu indicators asked for, the FMU has %zu", ni,
                    f->ni);
    int rc = eval_indicators(f, eventIndicators);
    for (size_t i = 0; rc == 0 && i < ni; i++)
        if (!isfinite(eventIndicators[i])) {
            /* as fmi2GetDerivatives: a value that is not finite is a point outside the
             * model's domain (fmi2Discard), never an indicator to compare */
            fmu_log(f, fmi2Discard, C_DISCARD, "model '%s': event indicator %zu is %g at "
                    "t = %.9g s (states not finite, or outside the model's domain)",
                    f->d->name, i, eventIndicators[i], f->t);
            return fmi2Discard;
        }
    if (rc == 0)
        return fmi2OK;
    fmu_log(f, fmi2Discard, C_DISCARD, "model '%s': the event indicators cannot be evaluated "
            "at t = %.9g s: %s", f->d->name, f->t, model_why(f));
    return fmi2Discard;
}

fmi2Status fmi2GetContinuousStates(fmi2Component c, fmi2Real x[], size_t nx)
{
    fmu *f = c;
    if (!allowed(f, "fmi2GetContinuousStates", B_INIT | B_EVENT | B_CONT | B_TERM | B_ERR) ||
        !is_me(f, "fmi2GetContinuousStates"))
        return fmi2Error;
    if (nx > 0 && x == NULL)
        return FAIL(f, "fmi2GetContinuousStates: the array 'x' is NULL (%zu asked for)", nx);
    if (nx != f->nx)
        return FAIL(f, "fmi2GetContinuousStates: %zu states asked for, the model has %zu", nx,
                    f->nx);
    memcpy(x, f->x, nx * sizeof *x);
    return fmi2OK;
}

fmi2Status fmi2GetNominalsOfContinuousStates(fmi2Component c, fmi2Real x_nominal[], size_t nx)
{
    fmu *f = c;
    if (!allowed(f, "fmi2GetNominalsOfContinuousStates", B_RUN | B_INST) ||
        !is_me(f, "fmi2GetNominalsOfContinuousStates"))
        return fmi2Error;
    if (nx != f->nx || x_nominal == NULL)
        return FAIL(f, "fmi2GetNominalsOfContinuousStates: %zu asked for, the model has %zu", nx,
                    f->nx);
    for (size_t i = 0; i < nx; i++)
        x_nominal[i] = f->d->states[i].nominal;
    return fmi2OK;
}

/* ---- Co-Simulation ------------------------------------------------------------------------- */

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[])
{
    (void)order, (void)value;
    fmu *f = c;
    if (!allowed(f, "fmi2SetRealInputDerivatives", ~0u) || !is_cs(f, "fmi2SetRealInputDerivatives"))
        return fmi2Error;
    return FAIL(f, "fmi2SetRealInputDerivatives: not provided (canInterpolateInputs is false: "
                "an input holds its value over a communication step)%s%u", nvr > 0 ? "; value reference " : "", nvr > 0 && vr ? vr[0] : 0u);
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[])
{
    (void)vr, (void)nvr, (void)order, (void)value;
    fmu *f = c;
    if (!allowed(f, "fmi2GetRealOutputDerivatives", ~0u) ||
        !is_cs(f, "fmi2GetRealOutputDerivatives"))
        return fmi2Error;
    return FAIL(f, "fmi2GetRealOutputDerivatives: not provided (maxOutputDerivativeOrder is 0)");
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint,
                      fmi2Real communicationStepSize, fmi2Boolean noSetFMUStatePriorToCurrentPoint)
{
    (void)noSetFMUStatePriorToCurrentPoint;
    fmu *f = c;
    if (!allowed(f, "fmi2DoStep", B_STEPOK) || !is_cs(f, "fmi2DoStep"))
        return fmi2Error;
    const double t_now = lv_sim_time(f->sim);
    if (!(communicationStepSize > 0.0) || !isfinite(communicationStepSize))
        return FAIL(f, "fmi2DoStep: communicationStepSize %g is not > 0", communicationStepSize);
    /* the master's time and the slave's agree to round-off (a sum of steps) */
    if (!(fabs(currentCommunicationPoint - t_now) <= 1e-9 * fmax(1.0, fabs(t_now))))
        return FAIL(f, "fmi2DoStep: currentCommunicationPoint %.17g s is not the FMU's time "
                    "%.17g s", currentCommunicationPoint, t_now);
    if (lv_sim_done(f->sim)) {
        f->mode = M_STEP_FAILED;
        f->cs_terminated = 1;
        fmu_log(f, fmi2Discard, C_DISCARD, "fmi2DoStep: the phase has ended at t = %.9g s",
                t_now);
        return fmi2Discard;
    }
    double target = currentCommunicationPoint + communicationStepSize;
    if (f->stop_defined && target > f->t_stop) {
        if (target > f->t_stop + stop_slack(f))
            return FAIL(f, "fmi2DoStep: the step from %.17g s by %.17g s ends at %.17g s, past "
                        "stopTime %.17g s of fmi2SetupExperiment (stopTimeDefined): the FMU "
                        "computes up to stopTime only", currentCommunicationPoint,
                        communicationStepSize, target, f->t_stop);
        target = f->t_stop; /* round-off of the master's sum */
    }
    lv_err err;
    lv_status st = lv_sim_advance(f->sim, target, &err);
    const double t = lv_sim_time(f->sim);
    f->t = t;
    if (st != LV_OK) {
        f->mode = M_ERROR;
        f->last_ok_time = t;
        return FAIL(f, "fmi2DoStep: %s", err.msg);
    }
    f->last_ok_time = t;
    if (lv_sim_done(f->sim)) { /* a phase end, or its time limit */
        const lv_sim_report *rep = lv_sim_report_get(f->sim);
        f->cs_terminated = 1;
        snprintf(f->end_name, sizeof f->end_name, "%s", rep->stop_name);
        fmu_log(f, fmi2OK, C_EVENTS, "t = %.9g s: the phase ends ('%s')", t, rep->stop_name);
        if (t < target && fabs(target - t) > 1e-12 * fmax(1.0, fabs(t))) {
            f->mode = M_STEP_FAILED;
            fmu_log(f, fmi2Discard, C_DISCARD, "fmi2DoStep: the phase ended at t = %.17g s "
                    "('%s'), before the end of the step at %.17g s: fmi2Terminated, "
                    "fmi2LastSuccessfulTime", t, rep->stop_name, target);
            return fmi2Discard;
        }
    }
    return fmi2OK;
}

fmi2Status fmi2CancelStep(fmi2Component c)
{
    fmu *f = c;
    if (!allowed(f, "fmi2CancelStep", ~0u) || !is_cs(f, "fmi2CancelStep"))
        return fmi2Error;
    return FAIL(f, "fmi2CancelStep: fmi2DoStep runs synchronously and never returns fmi2Pending: "
                "there is no step to cancel");
}

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value)
{
    (void)value;
    fmu *f = c;
    if (!allowed(f, "fmi2GetStatus", ~0u) || !is_cs(f, "fmi2GetStatus"))
        return fmi2Error;
    fmu_log(f, fmi2Discard, C_DISCARD, "fmi2GetStatus(%d): no status of this kind (fmi2DoStep "
            "is synchronous: it never returns fmi2Pending)", (int)s);
    return fmi2Discard;
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *value)
{
    fmu *f = c;
    if (!allowed(f, "fmi2GetRealStatus", ~0u) || !is_cs(f, "fmi2GetRealStatus"))
        return fmi2Error;
    if (value == NULL)
        return FAIL(f, "fmi2GetRealStatus: NULL pointer");
    if (s == fmi2LastSuccessfulTime) {
        *value = f->last_ok_time;
        return fmi2OK;
    }
    fmu_log(f, fmi2Discard, C_DISCARD, "fmi2GetRealStatus(%d): only fmi2LastSuccessfulTime",
            (int)s);
    return fmi2Discard;
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *value)
{
    (void)value;
    fmu *f = c;
    if (!allowed(f, "fmi2GetIntegerStatus", ~0u) || !is_cs(f, "fmi2GetIntegerStatus"))
        return fmi2Error;
    fmu_log(f, fmi2Discard, C_DISCARD, "fmi2GetIntegerStatus(%d): no integer status", (int)s);
    return fmi2Discard;
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *value)
{
    fmu *f = c;
    if (!allowed(f, "fmi2GetBooleanStatus", ~0u) || !is_cs(f, "fmi2GetBooleanStatus"))
        return fmi2Error;
    if (value == NULL)
        return FAIL(f, "fmi2GetBooleanStatus: NULL pointer");
    if (s == fmi2Terminated) {
        *value = f->cs_terminated ? fmi2True : fmi2False;
        return fmi2OK;
    }
    fmu_log(f, fmi2Discard, C_DISCARD, "fmi2GetBooleanStatus(%d): only fmi2Terminated", (int)s);
    return fmi2Discard;
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *value)
{
    (void)value;
    fmu *f = c;
    if (!allowed(f, "fmi2GetStringStatus", ~0u) || !is_cs(f, "fmi2GetStringStatus"))
        return fmi2Error;
    fmu_log(f, fmi2Discard, C_DISCARD, "fmi2GetStringStatus(%d): no pending step, no status "
            "text", (int)s);
    return fmi2Discard;
}
