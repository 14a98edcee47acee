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
#include <sys/statvfs.h>
#include <time.h>
#include <unistd.h>

#include "campaign/campaign_int.h"
#include "core/status.h"
#include "lvsim/lv_dispersion.h"
#include "lvsim/lv_outdir.h"
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

/* ---- the size of a campaign, before it runs ---------------------------------------------------- */

/* The database's bytes, as SQLite 3.40 stores the campaign's rows (measured on the examples:
 * dof3-branch 1.73 kB a run for 3 phases of 56 finals and 7 inputs, estimated 1.84 kB;
 * isp_scatter 202 B for one phase of 20 finals, estimated 292 B: zeros and whole numbers
 * take less than 9 bytes). */
#define DB_ROW_BYTES 16.0    /* a row beyond its values: cell header, key, text columns */
#define DB_VALUE_BYTES 9.0   /* a REAL and its type byte */
#define DB_EVENT_BYTES 30.0  /* an event's row */
#define DB_SURE_FRACTION 0.5 /* of the estimate, what is refused against the free space */

lv_status lv_campaign_estimate(const lv_mission *m, const lv_campaign_options *o,
                               lv_campaign_size *out, lv_err *err)
{
    memset(out, 0, sizeof *out);
    if (o == NULL || o->n_runs == 0)
        return lv_fail(err, LV_ERR_INPUT, "campaign: at least one run is needed");
    lv_run *r = NULL;
    lv_status st = lv_run_create(m, &r, err);
    if (st != LV_OK)
        return st;
    const double N = (double)o->n_runs, nd = (double)lv_mission_disp_count(m);
    const double K = (double)(o->keep_runs < o->n_runs ? o->keep_runs : o->n_runs);
    /* per run: the runs row (status, message, the inputs); the statistics hold the inputs,
     * a status byte, and four work arrays of doubles (stats.c, plot.c) */
    double db_run = DB_ROW_BYTES + 8.0 + DB_VALUE_BYTES * nd;
    double mem_run = 8.0 * nd + 1.0 + 4.0 * 8.0;
    double kept_files = 0.0, kept_rows = 0.0, kept_max = 0.0;
    for (size_t k = 0; k < lv_mission_phase_count(m) && st == LV_OK; k++) {
        const double nf = (double)lv_run_result(r, k)->n_final;
        lv_output_estimate e, ek;
        st = lv_run_estimate_output(r, k, o->output_interval > 0.0 ? o->output_interval : 1e300,
                                    &e, err);
        if (st == LV_OK)
            st = lv_run_estimate_output(r, k, o->output_interval, &ek, err);
        if (st != LV_OK)
            break;
        /* a phase with ends computes at most max_rows rows (the limit as it runs) */
        out->rows_per_run += !e.bounded && o->max_rows > 0.0 ? fmin(e.rows, o->max_rows) : e.rows;
        out->rows_by_stop += e.rows;
        /* its row: state, end, t_end, steps, rhs evaluations, error, the finals; an end's
         * event */
        db_run += DB_ROW_BYTES + 24.0 + DB_VALUE_BYTES * (1.0 + nf) +
                  (e.bounded ? 0.0 : DB_EVENT_BYTES);
        /* in the statistics: the finals, the row index, run, state, end and error */
        mem_run += 8.0 * nf + 8.0 + 8.0 + 1.0 + 16.0 + 32.0;
        /* its `iip_at:` times: a row each (run, phase, t, state, four values); in the
         * statistics the run, state and four values */
        const double ni = (double)lv_mission_phase_iip_count(m, k);
        db_run += ni * (DB_ROW_BYTES + 12.0 + 5.0 * DB_VALUE_BYTES);
        mem_run += ni * (8.0 + 1.0 + 4.0 * 8.0);
        /* the kept runs: only what is known now (a phase with ends may write less than its
         * stop time allows, and never more than max_rows rows) */
        if (ek.bounded) {
            kept_files += ek.bytes_mat + ek.bytes_csv;
            kept_rows += ek.bytes_mat;
        }
        const double rows_max = !ek.bounded && o->max_rows > 0.0 ? fmin(ek.rows, o->max_rows)
                                                                 : ek.rows;
        kept_max += (ek.bytes_mat + ek.bytes_csv) / ek.rows * rows_max;
    }
    lv_run_free(r);
    if (st != LV_OK)
        return st;
    out->db_bytes = N * db_run;
    out->stats_bytes = N * mem_run;
    out->kept_bytes = K * kept_files;
    out->kept_bytes_max = K * kept_max;
    const double busy = fmin(K, (double)(o->threads > 0 ? o->threads : 1));
    out->kept_memory = busy * kept_rows;
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    out->mem_total = pages > 0 && page > 0 ? (double)pages * (double)page : NAN;
    out->disk_free = NAN;
    /* the database's folder, or the nearest folder above it that exists (it may be made
     * only when the campaign starts) */
    char dir[4096];
    snprintf(dir, sizeof dir, "%s", o->db_path != NULL ? o->db_path : "");
    for (int depth = 0; o->db_path != NULL && depth < 64; depth++) {
        char *slash = strrchr(dir, '/');
        if (slash == dir)
            dir[1] = '\0';
        else if (slash != NULL)
            *slash = '\0';
        else
            snprintf(dir, sizeof dir, ".");
        struct statvfs fs;
        if (statvfs(dir, &fs) == 0) {
            out->disk_free = (double)fs.f_bavail * (double)fs.f_frsize;
            break;
        }
        if (strcmp(dir, ".") == 0 || strcmp(dir, "/") == 0)
            break;
    }
    return LV_OK;
}

lv_status lv_campaign_check_size(const lv_mission *m, const lv_campaign_options *o, int stats,
                                 lv_campaign_size *out, lv_err *err)
{
    lv_campaign_size z;
    lv_status st = lv_campaign_estimate(m, o, &z, err);
    if (out != NULL)
        *out = z;
    if (st != LV_OK)
        return st;
    /* what a resumed database holds already needs no more room */
    double have = 0.0;
    struct stat sb;
    if (o->resume && o->db_path != NULL && stat(o->db_path, &sb) == 0)
        have = (double)sb.st_size;
    const double disk = fmax(0.0, z.db_bytes - have) + z.kept_bytes;
    /* the database's estimate may be high by half (zeros are short): refused only when even
     * half of it would not fit */
    const int over_disk = DB_SURE_FRACTION * fmax(0.0, z.db_bytes - have) + z.kept_bytes >
                          z.disk_free, over_stats = stats && z.stats_bytes > z.mem_total,
              over_kept = z.kept_memory > z.mem_total;
    if (!over_disk && !over_stats && !over_kept)
        return LV_OK;
    char n[32], a[32], b[32], c[32], msg[LV_ERR_MSG_MAX];
    size_t at = 0;
    msg[0] = '\0';
    lv_fmt_count((double)o->n_runs, n, sizeof n);
    if (over_disk)
        at += (size_t)snprintf(msg + at, sizeof msg - at, "; its database%s would need about "
                               "%s (%s a run) and the file system of %s has %s free",
                               z.kept_bytes > 0.0 ? " and kept runs" : "",
                               lv_fmt_bytes(disk, a, sizeof a),
                               lv_fmt_bytes(z.db_bytes / (double)o->n_runs, b, sizeof b),
                               o->db_path, lv_fmt_bytes(z.disk_free, c, sizeof c));
    if (over_stats && at < sizeof msg)
        at += (size_t)snprintf(msg + at, sizeof msg - at, "; its statistics would need %s of "
                               "memory (%s a run) and this machine has %s",
                               lv_fmt_bytes(z.stats_bytes, a, sizeof a),
                               lv_fmt_bytes(z.stats_bytes / (double)o->n_runs, b, sizeof b),
                               lv_fmt_bytes(z.mem_total, c, sizeof c));
    if (over_kept && at < sizeof msg)
        snprintf(msg + at, sizeof msg - at, "; its kept runs would hold %s of rows in memory "
                 "at once and this machine has %s", lv_fmt_bytes(z.kept_memory, a, sizeof a),
                 lv_fmt_bytes(z.mem_total, c, sizeof c));
    return lv_fail(err, LV_ERR_INPUT, "a campaign of %s runs is too large%s: run fewer (-n)%s%s",
                   n, msg,
                   over_stats ? ", or skip the statistics (--no-stats)" : "",
                   over_kept ? ", keep fewer runs or give them a larger output interval" : "");
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

/* The campaign's stop flag is up. */
static int stopped(const lv_campaign_options *o)
{
    return o->stop != NULL && __atomic_load_n(o->stop, __ATOMIC_RELAXED) != 0;
}

/* 1 when a done phase ended by an `impact` end that is not its first written end (the end
 * it is meant to end by: an upper stage's burnout, an orbit's periapsis): it fell to the
 * ground. A phase whose first end is `impact` (a spent stage's fall) ended as meant. */
static int unintended_impact(const lv_phase_result *res)
{
    return res->state == LV_PHASE_DONE && res->end_index > 0 &&
           strcmp(res->report.stop_name, "impact") == 0;
}

/* The end a done phase reached: the event's name, or "stop_time". Any event that stopped it,
 * as summary.json's end.event: one of its written ends (end_index >= 0) or one the phase type
 * ends by itself (a runway's `liftoff`, `stop`: end_index -1, yet no stop time). */
static const char *end_of(const lv_phase_result *res)
{
    const lv_sim_report *rep = &res->report;
    switch (res->state) {
    case LV_PHASE_DONE:
        if (rep->reason != LV_STOP_EVENT)
            return "stop_time";
        if (rep->stop_event >= 0 && (size_t)rep->stop_event < res->n_event_names &&
            res->event_names[rep->stop_event] != NULL)
            return res->event_names[rep->stop_event];
        return rep->stop_name[0] ? rep->stop_name : "event";
    case LV_PHASE_FAILED:
        return "failed";
    case LV_PHASE_SKIPPED:
        return "skipped";
    case LV_PHASE_CRASHED:
        return "crashed";
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
        ro.stop = w->o.stop;
        ro.max_rows = w->o.max_rows;
        char dir[4096];
        const int keep = run < w->o.keep_runs && w->o.keep_dir != NULL;
        st = lv_run_execute(w->run, &ro, &rerr);
        if (st == LV_ERR_NOMEM || st == LV_ERR_IO)
            return lv_fail(err, st, "run %llu: %s", (unsigned long long)run, rerr.msg);
        /* cut short by the stop: no record (a resumed campaign runs it again); a run that
         * failed while the stop was up may owe its failure to it: the same */
        if (st == LV_ERR_CANCELLED || (st != LV_OK && stopped(&w->o)))
            return lv_fail(err, LV_ERR_CANCELLED, "run %llu: stopped", (unsigned long long)run);
        if (st != LV_OK) {
            status = LV_MC_FAILED;
            msg = rerr.msg;
        }
        ran = 1;
        if (keep) { /* the files of this run: again, with the phases' own output grids, as
                     * a results folder of its own (lv_outdir.h: never a user's file replaced) */
            lv_run *kr = NULL;
            lv_outdir *kod = NULL;
            lv_err kerr;
            lv_mission_info mi;
            lv_mission_get_info(m, &mi);
            snprintf(dir, sizeof dir, "%s/run_%llu", w->o.keep_dir, (unsigned long long)run);
            lv_status kst = lv_outdir_begin(dir, mi.path, 0, &kod, &kerr);
            if (kst != LV_OK)
                return lv_fail(err, kst == LV_ERR_NOMEM ? kst : LV_ERR_IO, "run %llu: %s",
                               (unsigned long long)run, kerr.msg);
            lv_run_options ko = ro;
            ko.no_rows = 0;
            ko.output_interval = w->o.output_interval;
            ko.outdir = lv_outdir_path(kod);
            lv_status rst = LV_ERR_INPUT;
            int cut = 0;
            if (lv_run_create(m, &kr, &kerr) == LV_OK &&
                lv_run_disperse(kr, w->o.seed, run, NULL, &kerr) == LV_OK) {
                rst = lv_run_execute(kr, &ko, &kerr);
                cut = rst == LV_ERR_CANCELLED || (rst != LV_OK && stopped(&w->o));
                if (!cut && lv_run_write_summary(kr, ko.outdir, &kerr) != LV_OK)
                    rst = LV_ERR_IO;
            }
            if (!cut) {
                /* a run's results folder (the campaign's own manifest says "mc") */
                const lv_outdir_record krec = {"run", rst == LV_OK ? "ok" : "failed", mi.name, 0,
                                               NULL};
                kst = lv_outdir_commit(kod, &krec, &kerr);
            }
            lv_outdir_free(kod); /* cut short: not committed, the folder as it was */
            lv_run_free(kr);
            if (cut) /* its files would be incomplete: the run is done again on resume */
                return lv_fail(err, LV_ERR_CANCELLED, "run %llu: stopped",
                               (unsigned long long)run);
            if (kst != LV_OK)
                return lv_fail(err, kst == LV_ERR_NOMEM ? kst : LV_ERR_IO, "run %llu: %s",
                               (unsigned long long)run, kerr.msg);
        }
    }
    for (size_t k = 0; ran && status == LV_MC_OK && k < np; k++)
        if (lv_run_result(w->run, k)->state == LV_PHASE_CRASHED)
            status = LV_MC_RUN_CRASHED;
    for (size_t k = 0; ran && status == LV_MC_OK && k < np; k++)
        if (unintended_impact(lv_run_result(w->run, k)))
            status = LV_MC_RUN_IMPACT;
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
        lv_bytes_u64(b, ran && unintended_impact(res) ? (uint64_t)LV_MC_IMPACT : (uint64_t)ps);
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
        /* its impact point at its `iip_at:` times: none where it did not run */
        const size_t ni = lv_mission_phase_iip_count(m, k);
        lv_bytes_u64(b, ni);
        for (size_t i = 0; i < ni; i++) {
            lv_iip_sample sm;
            if (lv_run_iip(w->run, k, i, &sm, NULL) != LV_OK)
                sm = (lv_iip_sample){NAN, LV_IIP_NOT_FLYING, NAN, NAN, NAN, NAN};
            if (!ran || ps == LV_PHASE_SKIPPED)
                sm = (lv_iip_sample){sm.t, LV_IIP_NOT_FLYING, NAN, NAN, NAN, NAN};
            lv_bytes_f64(b, sm.t);
            lv_bytes_u64(b, (uint64_t)sm.state);
            lv_bytes_f64(b, sm.lat);
            lv_bytes_f64(b, sm.lon);
            lv_bytes_f64(b, sm.tof);
            lv_bytes_f64(b, sm.range);
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
    lv_campaign *c;       /* hands out the runs to do (under `lock`) */
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
        const int stop = st != LV_OK || p->st != LV_OK || stopped(p->o);
        uint64_t run = 0;
        const size_t got = stop ? 0 : lv_campaign_todo_next(p->c, &run, 1);
        pthread_mutex_unlock(&p->lock);
        if (got == 0)
            break;
        const void *rec;
        size_t len;
        st = lv_mc_worker_run(w, run, &rec, &len, &err);
        if (st == LV_ERR_CANCELLED) { /* stopped: not stored, not an error */
            st = LV_OK;
            break;
        }
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
    p.c = c;
    const uint64_t n_todo = lv_campaign_todo_count(c);
    pthread_mutex_init(&p.lock, NULL);
    pthread_cond_init(&p.cv, NULL);
    int nt = o->threads > 0 ? o->threads : 1;
    if (nt > 256)
        nt = 256;
    pthread_t tid[256];
    int started = 0;
    for (int i = 0; i < nt && (uint64_t)i < (n_todo ? n_todo : 1); i++) {
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
    if (started == 0 && n_todo > 0)
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
                     "(the database is consistent: resume it to continue)", (unsigned long long)prog.done,
                     (unsigned long long)prog.total);
    return st;
}
