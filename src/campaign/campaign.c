/* campaign.c - Monte Carlo campaigns: a worker turns a run index into a record (the run's
 * drawn inputs, every phase's state, end, final values, events, failure), and the threaded
 * driver hands run indices to worker threads while the calling thread stores their records
 * (store.c) in batched transactions. Design: docs/monte-carlo.md. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "campaign/campaign_int.h"
#include "core/status.h"
#include "lvsim/lv_dispersion.h"
#include "lvsim/lv_summary.h"

/* ---- bytes ------------------------------------------------------------------------------------ */

static void put(lv_bytes *b, const void *src, size_t n)
{
    if (b->nomem)
        return;
    if (b->n + n > b->cap) {
        size_t cap = b->cap ? b->cap : 1024;
        while (cap < b->n + n)
            cap *= 2;
        unsigned char *p = realloc(b->p, cap);
        if (p == NULL) {
            b->nomem = 1;
            return;
        }
        b->p = p;
        b->cap = cap;
    }
    memcpy(b->p + b->n, src, n);
    b->n += n;
}

void lv_bytes_u64(lv_bytes *b, uint64_t v) { put(b, &v, sizeof v); }
void lv_bytes_f64(lv_bytes *b, double v) { put(b, &v, sizeof v); }
void lv_bytes_str(lv_bytes *b, const char *s)
{
    const uint64_t n = s ? strlen(s) : 0;
    lv_bytes_u64(b, n);
    put(b, s ? s : "", (size_t)n);
}

static const void *take(lv_rd *r, size_t n)
{
    if (r->bad || r->n - r->at < n) {
        r->bad = 1;
        return NULL;
    }
    const void *p = r->p + r->at;
    r->at += n;
    return p;
}

uint64_t lv_rd_u64(lv_rd *r)
{
    uint64_t v = 0;
    const void *p = take(r, sizeof v);
    if (p)
        memcpy(&v, p, sizeof v);
    return v;
}

double lv_rd_f64(lv_rd *r)
{
    double v = NAN;
    const void *p = take(r, sizeof v);
    if (p)
        memcpy(&v, p, sizeof v);
    return v;
}

const char *lv_rd_str(lv_rd *r, size_t *len)
{
    const uint64_t n = lv_rd_u64(r);
    const char *p = n <= r->n ? take(r, (size_t)n) : NULL;
    if (n > r->n)
        r->bad = 1;
    *len = p ? (size_t)n : 0;
    return p ? p : "";
}

/* ---- options ---------------------------------------------------------------------------------- */

void lv_campaign_options_default(lv_campaign_options *o)
{
    memset(o, 0, sizeof *o);
    o->n_runs = 1;
    o->threads = 1;
}

/* ---- the worker: one run to one record -------------------------------------------------------- */

struct lv_mc_worker {
    const lv_mission *m;
    lv_campaign_options o;
    lv_run *run;
    double *inputs;
    lv_bytes rec;
};

void lv_mc_worker_free(lv_mc_worker *w)
{
    if (w == NULL)
        return;
    lv_run_free(w->run);
    free(w->inputs);
    free(w->rec.p);
    free(w);
}

lv_status lv_mc_worker_create(const lv_mission *m, const lv_campaign_options *o,
                              lv_mc_worker **out, lv_err *err)
{
    *out = NULL;
    lv_mc_worker *w = calloc(1, sizeof *w);
    if (w == NULL || (w->inputs = calloc(lv_mission_disp_count(m) + 1, sizeof(double))) == NULL) {
        free(w);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    w->m = m;
    w->o = *o;
    lv_status st = lv_run_create(m, &w->run, err);
    if (st != LV_OK) {
        lv_mc_worker_free(w);
        return st;
    }
    *out = w;
    return LV_OK;
}

static int mkdir_p(const char *dir)
{
    char buf[4096];
    const size_t n = strlen(dir);
    if (n == 0 || n >= sizeof buf)
        return -1;
    memcpy(buf, dir, n + 1);
    for (size_t i = 1; i <= n; i++)
        if (buf[i] == '/' || buf[i] == '\0') {
            const char ch = buf[i];
            buf[i] = '\0';
            if (mkdir(buf, 0777) != 0 && errno != EEXIST)
                return -1;
            buf[i] = ch;
        }
    return 0;
}

/* The end a done phase reached: the event's name, or "stop_time". */
static const char *end_of(const lv_phase_result *res)
{
    switch (res->state) {
    case LV_PHASE_DONE:
        return res->end_index >= 0 && res->report.stop_name[0] ? res->report.stop_name
                                                               : "stop_time";
    case LV_PHASE_FAILED:
        return "failed";
    case LV_PHASE_SKIPPED:
        return "skipped";
    default:
        return "pending";
    }
}

lv_status lv_mc_worker_run(lv_mc_worker *w, uint64_t run, const void **rec, size_t *len,
                           lv_err *err)
{
    const lv_mission *m = w->m;
    const size_t nd = lv_mission_disp_count(m), np = lv_mission_phase_count(m);
    lv_bytes *b = &w->rec;
    lv_err rerr;
    b->n = 0;
    b->nomem = 0;
    uint64_t status = LV_MC_OK;
    const char *msg = "";
    lv_status st = lv_run_disperse(w->run, w->o.seed, run, w->inputs, &rerr);
    if (st == LV_ERR_NOMEM)
        return lv_fail(err, st, "%s", rerr.msg);
    int ran = 0;
    if (st != LV_OK) {
        status = LV_MC_INPUT;
        msg = rerr.msg;
    } else {
        lv_run_options ro = {0};
        ro.threads = 1;
        ro.no_rows = 1;
        ro.method = w->o.method;
        ro.tolerance = w->o.tolerance;
        ro.output_interval = w->o.output_interval > 0.0 ? w->o.output_interval : 1e300;
        char dir[4096];
        const int keep = run < w->o.keep_runs && w->o.keep_dir != NULL;
        st = lv_run_execute(w->run, &ro, &rerr);
        if (st == LV_ERR_NOMEM || st == LV_ERR_IO)
            return lv_fail(err, st, "run %llu: %s", (unsigned long long)run, rerr.msg);
        if (st != LV_OK) {
            status = LV_MC_FAILED;
            msg = rerr.msg;
        }
        ran = 1;
        if (keep) { /* the files of this run: again, with the phases' own output grids */
            lv_run *kr = NULL;
            lv_err kerr;
            snprintf(dir, sizeof dir, "%s/run_%llu", w->o.keep_dir, (unsigned long long)run);
            lv_run_options ko = ro;
            ko.no_rows = 0;
            ko.output_interval = w->o.output_interval;
            ko.outdir = dir;
            if (mkdir_p(dir) != 0)
                return lv_fail(err, LV_ERR_IO, "cannot create '%s': %s", dir, LV_STRERROR(errno));
            if (lv_run_create(m, &kr, &kerr) == LV_OK &&
                lv_run_disperse(kr, w->o.seed, run, NULL, &kerr) == LV_OK) {
                lv_run_execute(kr, &ko, &kerr);
                lv_run_write_summary(kr, dir, &kerr);
            }
            lv_run_free(kr);
        }
    }
    lv_bytes_u64(b, run);
    lv_bytes_u64(b, status);
    lv_bytes_str(b, msg);
    lv_bytes_u64(b, nd);
    for (size_t j = 0; j < nd; j++)
        lv_bytes_f64(b, w->inputs[j]);
    lv_bytes_u64(b, np);
    for (size_t k = 0; k < np; k++) {
        const lv_phase_result *res = lv_run_result(w->run, k);
        const lv_phase_state ps = ran ? res->state : LV_PHASE_SKIPPED;
        lv_bytes_u64(b, (uint64_t)ps);
        lv_bytes_str(b, ran ? end_of(res) : "skipped");
        const int done = ps == LV_PHASE_DONE;
        lv_bytes_f64(b, ran && ps != LV_PHASE_SKIPPED ? res->t_end : NAN);
        lv_bytes_u64(b, ran ? (uint64_t)res->report.stats.steps : 0);
        lv_bytes_u64(b, ran ? (uint64_t)res->report.stats.rhs_evals : 0);
        lv_bytes_str(b, ran ? res->error : "input outside its range: not run");
        lv_bytes_u64(b, res->n_final);
        for (size_t i = 0; i < res->n_final; i++)
            lv_bytes_f64(b, done ? res->final_values[i] : NAN);
        const size_t ne = ran && ps != LV_PHASE_SKIPPED ? res->report.n_event_log : 0;
        lv_bytes_u64(b, ne);
        for (size_t i = 0; i < ne; i++) {
            const lv_event_record *ev = &res->report.event_log[i];
            lv_bytes_f64(b, ev->t);
            lv_bytes_str(b, ev->is_state && ev->index >= 0 &&
                                    (size_t)ev->index < res->n_event_names
                                ? res->event_names[ev->index]
                                : "time event");
        }
    }
    if (b->nomem)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    *rec = b->p;
    *len = b->n;
    return LV_OK;
}

/* ---- the threaded driver ---------------------------------------------------------------------- */

typedef struct rec_node {
    struct rec_node *next;
    size_t len;
    unsigned char data[];
} rec_node;

typedef struct pool {
    const lv_mission *m;
    const lv_campaign_options *o;
    const uint64_t *todo;
    size_t n_todo, next;
    rec_node *head, *tail;
    int active;           /* workers still running */
    lv_status st;         /* the first worker error */
    lv_err err;
    pthread_mutex_t lock;
    pthread_cond_t cv;
} pool;

static void *pool_worker(void *arg)
{
    pool *p = arg;
    lv_mc_worker *w = NULL;
    lv_err err;
    lv_status st = lv_mc_worker_create(p->m, p->o, &w, &err);
    for (;;) {
        pthread_mutex_lock(&p->lock);
        const int stop = st != LV_OK || p->st != LV_OK || (p->o->stop && *p->o->stop);
        const size_t i = p->next < p->n_todo && !stop ? p->next++ : (size_t)-1;
        pthread_mutex_unlock(&p->lock);
        if (i == (size_t)-1)
            break;
        const void *rec;
        size_t len;
        st = lv_mc_worker_run(w, p->todo[i], &rec, &len, &err);
        if (st != LV_OK)
            break;
        rec_node *n = malloc(sizeof *n + len);
        if (n == NULL) {
            st = lv_fail(&err, LV_ERR_NOMEM, "out of memory");
            break;
        }
        n->next = NULL;
        n->len = len;
        memcpy(n->data, rec, len);
        pthread_mutex_lock(&p->lock);
        if (p->tail)
            p->tail->next = n;
        else
            p->head = n;
        p->tail = n;
        pthread_cond_signal(&p->cv);
        pthread_mutex_unlock(&p->lock);
    }
    lv_mc_worker_free(w);
    pthread_mutex_lock(&p->lock);
    if (st != LV_OK && p->st == LV_OK) {
        p->st = st;
        p->err = err;
    }
    p->active--;
    pthread_cond_signal(&p->cv);
    pthread_mutex_unlock(&p->lock);
    return NULL;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

lv_status lv_campaign_run(const lv_mission *m, const lv_campaign_options *o,
                          lv_campaign_progress *out, lv_err *err)
{
    lv_campaign *c = NULL;
    lv_status st = lv_campaign_open(m, o, &c, err);
    if (st != LV_OK)
        return st;
    pool p;
    memset(&p, 0, sizeof p);
    p.m = m;
    p.o = o;
    p.n_todo = lv_campaign_todo(c, &p.todo);
    pthread_mutex_init(&p.lock, NULL);
    pthread_cond_init(&p.cv, NULL);
    int nt = o->threads > 0 ? o->threads : 1;
    if (nt > 256)
        nt = 256;
    pthread_t tid[256];
    int started = 0;
    for (int i = 0; i < nt && (size_t)i < (p.n_todo ? p.n_todo : 1); i++) {
        pthread_mutex_lock(&p.lock);
        p.active++;
        pthread_mutex_unlock(&p.lock);
        if (pthread_create(&tid[started], NULL, pool_worker, &p) == 0) {
            started++;
        } else {
            pthread_mutex_lock(&p.lock);
            p.active--;
            pthread_mutex_unlock(&p.lock);
        }
    }
    if (started == 0 && p.n_todo > 0)
        st = lv_fail(err, LV_ERR_NOMEM, "cannot start a worker thread");
    /* the writer: this thread stores what the workers made, a batch per transaction */
    double last_prog = now_s(), last_commit = last_prog;
    lv_campaign_progress prog;
    for (;;) {
        pthread_mutex_lock(&p.lock);
        while (p.head == NULL && p.active > 0) {
            struct timespec ts;
            clock_gettime(CLOCK_REALTIME, &ts);
            ts.tv_nsec += 100000000L;
            if (ts.tv_nsec >= 1000000000L) {
                ts.tv_sec++;
                ts.tv_nsec -= 1000000000L;
            }
            if (pthread_cond_timedwait(&p.cv, &p.lock, &ts) == ETIMEDOUT)
                break;
        }
        rec_node *batch = p.head;
        p.head = p.tail = NULL;
        const int finished = p.active == 0 && batch == NULL;
        pthread_mutex_unlock(&p.lock);
        while (batch != NULL) {
            rec_node *n = batch;
            batch = n->next;
            if (st == LV_OK)
                st = lv_campaign_store(c, n->data, n->len, err);
            free(n);
        }
        if (st != LV_OK) { /* stop the workers: nothing more can be stored */
            pthread_mutex_lock(&p.lock);
            if (p.st == LV_OK)
                p.st = st;
            pthread_mutex_unlock(&p.lock);
        }
        const double t = now_s();
        if (st == LV_OK && (t - last_commit > 0.5 || finished)) {
            st = lv_campaign_commit(c, err);
            last_commit = t;
        }
        if (o->progress && (t - last_prog > 0.25 || finished)) {
            lv_campaign_get_progress(c, &prog);
            o->progress(&prog, o->user);
            last_prog = t;
        }
        if (finished)
            break;
    }
    for (int i = 0; i < started; i++)
        pthread_join(tid[i], NULL);
    if (st == LV_OK && p.st != LV_OK) {
        st = p.st;
        if (err)
            *err = p.err;
    }
    lv_campaign_get_progress(c, &prog);
    if (out)
        *out = prog;
    lv_err cerr;
    const lv_status cst = lv_campaign_close(c, &cerr);
    if (st == LV_OK && cst != LV_OK) {
        st = cst;
        if (err)
            *err = cerr;
    }
    pthread_mutex_destroy(&p.lock);
    pthread_cond_destroy(&p.cv);
    if (st == LV_OK && o->stop && *o->stop && prog.done < prog.total)
        st = lv_fail(err, LV_ERR_CANCELLED, "campaign stopped: %llu of %llu runs stored "
                     "(continue with resume)", (unsigned long long)prog.done,
                     (unsigned long long)prog.total);
    return st;
}
