/* progress.c - the live progress line of lvsim run (progress.h). Called from the run's
 * worker threads: everything under one mutex; redrawn at most every 0.1 s on a terminal,
 * a plain line every 10 s otherwise. */
#define _POSIX_C_SOURCE 200809L

#include "progress.h"

#include "common.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

int progress_interrupted(void) { return cli_stop_flag != 0; }

typedef struct phase_prog {
    int running;
    double t, t_first;  /* s: latest and first mission time seen */
    double t_stop;      /* s: its time limit, NAN when unknown */
    double wall_first;  /* s: wall clock at the first row */
    double wall_plain;  /* s: wall clock of its last plain line */
    const char *name;
} phase_prog;

struct cli_progress {
    pthread_mutex_t mu;
    int tty, quiet, shown; /* shown: the live line is on the screen */
    size_t n;
    phase_prog *ph;
    double wall_drawn;     /* s: last redraw */
    const char *step;      /* post-processing step under way, or NULL */
    double step_wall;
};

static double wall_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

cli_progress *progress_new(size_t n_phases, int quiet)
{
    cli_progress *p = calloc(1, sizeof *p);
    if (p == NULL)
        return NULL;
    p->ph = calloc(n_phases + 1, sizeof *p->ph);
    if (p->ph == NULL) {
        free(p);
        return NULL;
    }
    pthread_mutex_init(&p->mu, NULL);
    p->n = n_phases;
    p->quiet = quiet;
    p->tty = isatty(fileno(stderr));
    return p;
}

void progress_free(cli_progress *p)
{
    if (p == NULL)
        return;
    pthread_mutex_destroy(&p->mu);
    free(p->ph);
    free(p);
}

/* "1.2 ks/s": simulated seconds per wall-clock second. */
static void rate_text(double rate, char *buf, size_t cap)
{
    if (!isfinite(rate) || rate <= 0.0)
        snprintf(buf, cap, "-");
    else if (rate >= 1e6)
        snprintf(buf, cap, "%.1f Ms/s", rate / 1e6);
    else if (rate >= 1e3)
        snprintf(buf, cap, "%.1f ks/s", rate / 1e3);
    else
        snprintf(buf, cap, "%.3g s/s", rate);
}

static void phase_text(const phase_prog *q, double now, char *buf, size_t cap)
{
    char rate[32];
    const double dw = now - q->wall_first;
    rate_text(dw > 0.0 ? (q->t - q->t_first) / dw : NAN, rate, sizeof rate);
    if (isfinite(q->t_stop))
        snprintf(buf, cap, "%s t = %.1f s (limit %.6g s), %s", q->name, q->t, q->t_stop, rate);
    else
        snprintf(buf, cap, "%s t = %.1f s, %s", q->name, q->t, rate);
}

static void erase(cli_progress *p)
{
    if (p->shown) {
        fputs("\r\033[K", stderr);
        fflush(stderr);
        p->shown = 0;
    }
}

/* The live line: every running phase, or the post-processing step. Lock held. */
static void draw(cli_progress *p, double now)
{
    char line[512];
    size_t len = 0;
    for (size_t k = 0; k < p->n && len + 80 < sizeof line; k++) {
        if (!p->ph[k].running)
            continue;
        char one[200];
        phase_text(&p->ph[k], now, one, sizeof one);
        len += (size_t)snprintf(line + len, sizeof line - len, "%s%s", len ? " | " : "running ", one);
    }
    if (p->step != NULL)
        len += (size_t)snprintf(line + len, sizeof line - len, "%s%s ... %.1f s",
                                len ? " | " : "", p->step, now - p->step_wall);
    if (len == 0) {
        erase(p);
        return;
    }
    fprintf(stderr, "\r\033[K%.*s", 150, line); /* one screen line on most terminals */
    fflush(stderr);
    p->shown = 1;
    p->wall_drawn = now;
}

int progress_phase(const lv_run *r, size_t k, double t, void *user)
{
    cli_progress *p = user;
    if (p == NULL || p->quiet || k >= p->n)
        return progress_interrupted();
    pthread_mutex_lock(&p->mu);
    phase_prog *q = &p->ph[k];
    const double now = wall_now();
    if (!q->running) {
        const lv_mission *m = lv_run_mission(r);
        char slot[160];
        q->running = 1;
        q->name = lv_mission_phase_name(m, k);
        q->t_first = t;
        q->wall_first = q->wall_plain = now;
        snprintf(slot, sizeof slot, "%s.stop_time", q->name);
        if (lv_run_get(r, slot, &q->t_stop, NULL) != LV_OK)
            q->t_stop = NAN;
    }
    q->t = t;
    if (p->tty) {
        if (now - p->wall_drawn >= 0.1)
            draw(p, now);
    } else if (now - q->wall_plain >= 10.0) {
        char one[200];
        phase_text(q, now, one, sizeof one);
        fprintf(stderr, "lvsim: running %s\n", one);
        fflush(stderr);
        q->wall_plain = now;
    }
    pthread_mutex_unlock(&p->mu);
    return progress_interrupted();
}

void progress_phase_done(cli_progress *p, size_t k)
{
    if (p != NULL && k < p->n)
        p->ph[k].running = 0; /* the caller holds the lock (progress_print_begin) */
}

void progress_print_begin(cli_progress *p)
{
    if (p == NULL)
        return;
    pthread_mutex_lock(&p->mu);
    erase(p);
}

void progress_print_end(cli_progress *p)
{
    if (p == NULL)
        return;
    fflush(stdout);
    if (p->tty && !p->quiet)
        draw(p, wall_now());
    pthread_mutex_unlock(&p->mu);
}

void progress_step_begin(cli_progress *p, const char *what)
{
    if (p == NULL || p->quiet)
        return;
    pthread_mutex_lock(&p->mu);
    p->step = what;
    p->step_wall = wall_now();
    if (p->tty)
        draw(p, p->step_wall);
    pthread_mutex_unlock(&p->mu);
}

void progress_step_end(cli_progress *p)
{
    if (p == NULL || p->quiet || p->step == NULL)
        return;
    pthread_mutex_lock(&p->mu);
    const double dt = wall_now() - p->step_wall;
    if (p->tty) {
        erase(p);
    } else {
        fprintf(stderr, "lvsim: %s (%.2f s)\n", p->step, dt);
        fflush(stderr);
    }
    p->step = NULL;
    pthread_mutex_unlock(&p->mu);
}
