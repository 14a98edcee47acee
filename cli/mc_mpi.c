/* mc_mpi.c - `mpirun -np K lvsim mc ...`: one campaign across K ranks (built only when MPI
 * is found; OpenMPI from Debian), as the module lvsim_mpi.so that `lvsim mc` loads only when
 * mpirun started it (cmd_mc.c): the MPI libraries are not loaded by any other command. Rank 0 opens the database and owns the list of runs still
 * to do; every rank, rank 0 included, asks for a chunk of run indices when it is ready for
 * more (dynamic load balancing; one request kept ahead, so a rank never waits for work), runs
 * it on its threads and sends the records back; rank 0 stores them (lv_campaign_store), so the
 * database is the threaded run's, whatever K. Only the main thread of a rank calls MPI
 * (MPI_THREAD_FUNNELED): rank 0's runs go to its worker threads, another rank's to a thread
 * while its main thread listens.
 * Stopping (a signal on any rank, or an error on rank 0): a rank that is signalled asks rank 0
 * to stop (TAG_STOPREQ); rank 0 then hands out no more work and tells every other rank
 * (TAG_STOP), whose running runs are cancelled within an integrator step and not stored (the
 * records of the runs they finished are). Every other rank receives exactly one TAG_STOP:
 * when the campaign stops, or at its normal end. */
#define _POSIX_C_SOURCE 200809L

#include <mpi.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "mc.h"

/* A growable byte buffer: a batch of records, each preceded by its length (u64), after the
 * count (u64). */
typedef struct lv_bytes {
    unsigned char *p;
    size_t n, cap;
    int nomem;
} lv_bytes;

static void put(lv_bytes *b, const void *src, size_t n)
{
    if (b->nomem)
        return;
    if (b->n + n > b->cap) {
        size_t cap = b->cap ? b->cap : 4096;
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

static void put_u64(lv_bytes *b, uint64_t v) { put(b, &v, sizeof v); }

static lv_status mc_fail(lv_err *err, lv_status code, const char *msg)
{
    if (err != NULL) {
        err->code = code;
        snprintf(err->msg, sizeof err->msg, "%s", msg);
    }
    return code;
}

enum { TAG_REQ = 1, TAG_WORK = 2, TAG_RECS = 3, TAG_STOP = 4, TAG_STOPREQ = 5 };

static int stop_up(const lv_campaign_options *o)
{
    return o->stop != NULL && __atomic_load_n(o->stop, __ATOMIC_RELAXED) != 0;
}

static void nap(long ns)
{
    struct timespec ts = { 0, ns };
    nanosleep(&ts, NULL);
}

/* ---- running a chunk on a rank's threads -------------------------------------------------- */

typedef struct chunk_job {
    lv_mc_worker **w;
    int threads;
    const uint64_t *runs;
    size_t n, next;
    const lv_campaign_options *o; /* its stop flag: no run starts after it */
    lv_bytes *out;        /* [n] each run's record (none for a run the stop cut short) */
    lv_status st;
    lv_err err;
    pthread_mutex_t lock;
} chunk_job;

static void *chunk_thread(void *arg)
{
    chunk_job *j = ((void **)arg)[0];
    lv_mc_worker *w = ((void **)arg)[1];
    for (;;) {
        pthread_mutex_lock(&j->lock);
        const size_t i = j->st == LV_OK && j->next < j->n && !stop_up(j->o) ? j->next++
                                                                             : (size_t)-1;
        pthread_mutex_unlock(&j->lock);
        if (i == (size_t)-1)
            break;
        const void *rec;
        size_t len;
        lv_err err;
        lv_status st = lv_mc_worker_run(w, j->runs[i], &rec, &len, &err);
        pthread_mutex_lock(&j->lock);
        if (st == LV_ERR_CANCELLED) {
            /* stopped: no record, the run stays to do */
        } else if (st != LV_OK && j->st == LV_OK) {
            j->st = st;
            j->err = err;
        } else if (st == LV_OK) {
            j->out[i].n = 0;
            put_u64(&j->out[i], len); /* length prefix, then the record */
            put(&j->out[i], rec, len);
        }
        pthread_mutex_unlock(&j->lock);
    }
    return NULL;
}

/* Runs `runs` on the workers' threads; the records, each preceded by its length, go to *batch
 * (u64 count first): those of the runs done (the stop may leave some out). */
static lv_status run_chunk(lv_mc_worker **w, int threads, const lv_campaign_options *o,
                           const uint64_t *runs, size_t n, lv_bytes *batch, lv_err *err)
{
    chunk_job j;
    memset(&j, 0, sizeof j);
    j.w = w;
    j.threads = threads;
    j.runs = runs;
    j.n = n;
    j.o = o;
    j.out = calloc(n + 1, sizeof *j.out);
    if (j.out == NULL)
        return mc_fail(err, LV_ERR_NOMEM, "out of memory");
    pthread_mutex_init(&j.lock, NULL);
    pthread_t tid[256];
    void *args[256][2];
    int started = 0;
    for (int t = 1; t < threads && (size_t)t < n; t++) {
        args[t][0] = &j;
        args[t][1] = w[t];
        if (pthread_create(&tid[started], NULL, chunk_thread, args[t]) == 0)
            started++;
    }
    args[0][0] = &j;
    args[0][1] = w[0];
    chunk_thread(args[0]);
    for (int t = 0; t < started; t++)
        pthread_join(tid[t], NULL);
    pthread_mutex_destroy(&j.lock);
    lv_status st = j.st;
    if (st != LV_OK && err)
        *err = j.err;
    batch->n = 0;
    batch->nomem = 0;
    uint64_t have = 0;
    for (size_t i = 0; i < n; i++)
        have += j.out[i].n > 0;
    put_u64(batch, have);
    for (size_t i = 0; i < n; i++) {
        put(batch, j.out[i].p, j.out[i].n);
        if ((j.out[i].nomem || batch->nomem) && st == LV_OK)
            st = mc_fail(err, LV_ERR_NOMEM, "out of memory");
        free(j.out[i].p);
    }
    free(j.out);
    return st;
}

/* ---- rank 0: the writer and dispatcher ------------------------------------------------------- */

typedef struct local_ctx {
    lv_mc_worker **w;
    int threads;
    const lv_campaign_options *o;
    pthread_mutex_t lock;
    /* work handed to this rank's own threads */
    uint64_t *runs;
    size_t n_runs;
    int has_work, no_more, busy;
    /* a finished chunk waiting to be stored */
    lv_bytes done;
    int has_done;
    lv_status st;
    lv_err err;
} local_ctx;

static void *local_thread(void *arg)
{
    local_ctx *lc = arg;
    lv_bytes batch = { 0 };
    for (;;) {
        pthread_mutex_lock(&lc->lock);
        while (!lc->has_work && !lc->no_more) {
            pthread_mutex_unlock(&lc->lock);
            nap(200000);
            pthread_mutex_lock(&lc->lock);
        }
        if (!lc->has_work) {
            pthread_mutex_unlock(&lc->lock);
            break;
        }
        uint64_t *runs = lc->runs;
        const size_t n = lc->n_runs;
        lc->runs = NULL;
        lc->has_work = 0;
        lc->busy = 1;
        pthread_mutex_unlock(&lc->lock);
        lv_err err;
        lv_status st = run_chunk(lc->w, lc->threads, lc->o, runs, n, &batch, &err);
        free(runs);
        pthread_mutex_lock(&lc->lock);
        while (lc->has_done) { /* the writer has not taken the last one yet */
            pthread_mutex_unlock(&lc->lock);
            nap(100000);
            pthread_mutex_lock(&lc->lock);
        }
        if (st != LV_OK) {
            lc->st = st;
            lc->err = err;
        } else {
            lv_bytes t = lc->done;
            lc->done = batch;
            batch = t;
            lc->has_done = 1;
        }
        lc->busy = 0;
        pthread_mutex_unlock(&lc->lock);
        if (st != LV_OK)
            break;
    }
    free(batch.p);
    return NULL;
}

static lv_status store_batch(lv_campaign *c, const unsigned char *p, size_t len, lv_err *err)
{
    uint64_t n, rl;
    size_t at = sizeof n;
    if (len < sizeof n)
        return mc_fail(err, LV_ERR_INPUT, "campaign: a malformed batch from a rank");
    memcpy(&n, p, sizeof n);
    for (uint64_t i = 0; i < n; i++) {
        if (len - at < sizeof rl)
            return mc_fail(err, LV_ERR_INPUT, "campaign: a malformed batch from a rank");
        memcpy(&rl, p + at, sizeof rl);
        at += sizeof rl;
        if (rl > len - at)
            return mc_fail(err, LV_ERR_INPUT, "campaign: a malformed batch from a rank");
        lv_status st = lv_campaign_store(c, p + at, (size_t)rl, err);
        if (st != LV_OK)
            return st;
        at += (size_t)rl;
    }
    return LV_OK;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static lv_status rank0(const lv_mission *m, const lv_campaign_options *o, int world,
                       lv_mc_worker **w, lv_campaign_progress *out, lv_err *err)
{
    lv_campaign *c = NULL;
    lv_status st = lv_campaign_open(m, o, &c, err);
    if (st != LV_OK) {
        /* tell the others there is nothing to do, then their one TAG_STOP */
        for (int r = 1; r < world; r++) {
            uint64_t dummy;
            MPI_Recv(&dummy, 0, MPI_BYTE, r, TAG_REQ, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
            MPI_Send(&dummy, 0, MPI_UINT64_T, r, TAG_WORK, MPI_COMM_WORLD);
            MPI_Send(NULL, 0, MPI_BYTE, r, TAG_STOP, MPI_COMM_WORLD);
        }
        return st;
    }
    uint64_t work[64]; /* a chunk for another rank */
    const int threads = o->threads > 0 ? o->threads : 1;
    fprintf(stderr, "mc: mission '%s', %llu runs, seed %llu, %d ranks x %d thread%s -> %s\n",
            lv_mission_name(m), (unsigned long long)o->n_runs, (unsigned long long)o->seed, world,
            threads, threads == 1 ? "" : "s", o->db_path);
    local_ctx lc;
    memset(&lc, 0, sizeof lc);
    lc.w = w;
    lc.threads = threads;
    lc.o = o;
    pthread_mutex_init(&lc.lock, NULL);
    pthread_t tid;
    const int local = pthread_create(&tid, NULL, local_thread, &lc) == 0;
    if (!local)
        lc.no_more = 1; /* the other ranks do it all */
    int finished_ranks = 0;   /* ranks told "no more" */
    int outstanding = 0;      /* chunks handed to other ranks and not back yet */
    double last_commit = now_s(), last_prog = last_commit;
    unsigned char *buf = NULL;
    size_t buf_cap = 0;
    /* the chunk size: about 8 chunks per worker thread over what is left, 1 .. 64 runs */
    const size_t total_threads = (size_t)world * (size_t)threads;
    int stop_sent = 0;
    for (;;) {
        const int stopping = st != LV_OK || stop_up(o);
        if (stopping && !stop_sent) { /* the other ranks cancel their running runs */
            for (int r = 1; r < world; r++)
                MPI_Send(NULL, 0, MPI_BYTE, r, TAG_STOP, MPI_COMM_WORLD);
            stop_sent = 1;
        }
        const uint64_t left = lv_campaign_todo_count(c);
        uint64_t want = left / (8 * total_threads);
        want = want < 1 ? 1 : want > 64 ? 64 : want;
        /* the local threads */
        pthread_mutex_lock(&lc.lock);
        if (!lc.has_work && !lc.no_more) {
            if (left > 0 && !stopping) {
                lc.runs = malloc((size_t)want * sizeof *lc.runs);
                if (lc.runs != NULL) {
                    lc.n_runs = lv_campaign_todo_next(c, lc.runs, (size_t)want);
                    lc.has_work = 1;
                }
            } else {
                lc.no_more = 1;
            }
        }
        int took = 0;
        lv_bytes mine = { 0 };
        if (lc.has_done) {
            mine = lc.done;
            memset(&lc.done, 0, sizeof lc.done);
            lc.has_done = 0;
            took = 1;
        }
        if (lc.st != LV_OK && st == LV_OK) {
            st = lc.st;
            if (err)
                *err = lc.err;
        }
        const int local_idle = lc.no_more && !lc.has_work && !lc.busy && !lc.has_done;
        pthread_mutex_unlock(&lc.lock);
        if (took) {
            if (st == LV_OK)
                st = store_batch(c, mine.p, mine.n, err);
            free(mine.p);
        }
        /* messages from the other ranks */
        int flag = 0;
        MPI_Status ms;
        MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &ms);
        if (flag) {
            int count = 0;
            MPI_Get_count(&ms, MPI_BYTE, &count);
            if ((size_t)count > buf_cap) {
                unsigned char *nb = realloc(buf, (size_t)count);
                if (nb == NULL)
                    MPI_Abort(MPI_COMM_WORLD, 1);
                buf = nb;
                buf_cap = (size_t)count;
            }
            MPI_Recv(buf, count, MPI_BYTE, ms.MPI_SOURCE, ms.MPI_TAG, MPI_COMM_WORLD,
                     MPI_STATUS_IGNORE);
            if (ms.MPI_TAG == TAG_REQ) {
                size_t k = 0;
                if (!stopping && lv_campaign_todo_count(c) > 0) {
                    k = lv_campaign_todo_next(c, work, (size_t)want);
                    outstanding++;
                } else {
                    finished_ranks++;
                }
                MPI_Send(work, (int)k, MPI_UINT64_T, ms.MPI_SOURCE, TAG_WORK, MPI_COMM_WORLD);
            } else if (ms.MPI_TAG == TAG_STOPREQ) { /* a signal on that rank: stop all */
                if (o->stop != NULL)
                    *o->stop = 1;
            } else if (ms.MPI_TAG == TAG_RECS) {
                outstanding--;
                if (st == LV_OK)
                    st = store_batch(c, buf, (size_t)count, err);
            }
        } else if (!took) {
            nap(500000); /* 0.5 ms: a rank's request waits at most this */
        }
        const double t = now_s();
        const int done = finished_ranks == world - 1 && outstanding == 0 &&
                         (local_idle || !local);
        if (st == LV_OK && (t - last_commit > 0.5 || done)) {
            st = lv_campaign_commit(c, err);
            last_commit = t;
        }
        if (o->progress && (t - last_prog > 0.25 || done)) {
            lv_campaign_progress p;
            lv_campaign_get_progress(c, &p);
            o->progress(&p, o->user);
            last_prog = t;
        }
        if (done)
            break;
    }
    if (!stop_sent) /* every other rank waits for its one TAG_STOP */
        for (int r = 1; r < world; r++)
            MPI_Send(NULL, 0, MPI_BYTE, r, TAG_STOP, MPI_COMM_WORLD);
    if (local)
        pthread_join(tid, NULL);
    pthread_mutex_destroy(&lc.lock);
    free(lc.done.p);
    free(lc.runs);
    free(buf);
    lv_campaign_get_progress(c, out);
    lv_err cerr;
    const lv_status cst = lv_campaign_close(c, &cerr);
    if (st == LV_OK && cst != LV_OK) {
        st = cst;
        if (err)
            *err = cerr;
    }
    if (st == LV_OK && o->stop && *o->stop && out->done < out->total)
        st = mc_fail(err, LV_ERR_CANCELLED, "campaign stopped (continue with --resume)");
    return st;
}

/* ---- the other ranks -------------------------------------------------------------------------- */

/* A chunk run by a thread while the rank's main thread listens to rank 0. */
typedef struct remote_job {
    lv_mc_worker **w;
    int threads;
    const lv_campaign_options *o;
    const uint64_t *runs;
    size_t n;
    lv_bytes *batch;
    lv_status st;
    lv_err err;
    int done;             /* under lock */
    pthread_mutex_t lock;
} remote_job;

static void *remote_thread(void *arg)
{
    remote_job *rj = arg;
    lv_err err;
    const lv_status st = run_chunk(rj->w, rj->threads, rj->o, rj->runs, rj->n, rj->batch, &err);
    pthread_mutex_lock(&rj->lock);
    rj->st = st;
    rj->err = err;
    rj->done = 1;
    pthread_mutex_unlock(&rj->lock);
    return NULL;
}

/* Rank 0's TAG_STOP, if it came: then the runs of this rank stop too. */
static void poll_stop(const lv_campaign_options *o, int *got_stop)
{
    int flag = 0;
    if (*got_stop)
        return;
    MPI_Iprobe(0, TAG_STOP, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE);
    if (flag) {
        MPI_Recv(NULL, 0, MPI_BYTE, 0, TAG_STOP, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        *got_stop = 1;
        if (o->stop != NULL)
            *o->stop = 1;
    }
}

/* A signal on this rank: rank 0 is asked, once, to stop the campaign (only while a chunk
 * runs or just after it, before its records go: rank 0 then still listens). */

static void poll_signal(const lv_campaign_options *o, int got_stop, int *asked)
{
    if (!*asked && !got_stop && stop_up(o)) {
        MPI_Send(NULL, 0, MPI_BYTE, 0, TAG_STOPREQ, MPI_COMM_WORLD);
        *asked = 1;
    }
}

static lv_status worker_rank(lv_mc_worker **w, int threads, const lv_campaign_options *o,
                             lv_err *err)
{
    uint64_t *cur = malloc(64 * sizeof *cur), *nxt = malloc(64 * sizeof *nxt);
    lv_bytes batch = { 0 };
    lv_status st = LV_OK;
    if (cur == NULL || nxt == NULL)
        MPI_Abort(MPI_COMM_WORLD, 1);
    MPI_Status ms;
    int n = 0, got_stop = 0, asked = 0;
    MPI_Send(NULL, 0, MPI_BYTE, 0, TAG_REQ, MPI_COMM_WORLD);
    MPI_Recv(cur, 64, MPI_UINT64_T, 0, TAG_WORK, MPI_COMM_WORLD, &ms);
    MPI_Get_count(&ms, MPI_UINT64_T, &n);
    while (n > 0) {
        /* ask for the next chunk now: it is there when this one is done */
        MPI_Request req;
        MPI_Send(NULL, 0, MPI_BYTE, 0, TAG_REQ, MPI_COMM_WORLD);
        MPI_Irecv(nxt, 64, MPI_UINT64_T, 0, TAG_WORK, MPI_COMM_WORLD, &req);
        remote_job rj = { w, threads, o, cur, (size_t)n, &batch, LV_OK, { 0 }, 0,
                          PTHREAD_MUTEX_INITIALIZER };
        pthread_t tid;
        if (pthread_create(&tid, NULL, remote_thread, &rj) != 0) {
            remote_thread(&rj);
        } else {
            for (int done = 0; !done;) { /* listen while the chunk runs */
                poll_stop(o, &got_stop);
                poll_signal(o, got_stop, &asked);
                pthread_mutex_lock(&rj.lock);
                done = rj.done;
                pthread_mutex_unlock(&rj.lock);
                if (!done)
                    nap(200000);
            }
            pthread_join(tid, NULL);
        }
        poll_signal(o, got_stop, &asked); /* a signal that cut the chunk's last run short */
        pthread_mutex_destroy(&rj.lock);
        st = rj.st;
        if (st != LV_OK) {
            fprintf(stderr, "lvsim: rank: %s\n", rj.err.msg);
            if (err)
                *err = rj.err;
            MPI_Abort(MPI_COMM_WORLD, 1);
        }
        MPI_Send(batch.p, (int)batch.n, MPI_BYTE, 0, TAG_RECS, MPI_COMM_WORLD);
        int flag = 0;
        while (!flag) { /* poll gently: a blocking wait would spin on a shared core */
            MPI_Test(&req, &flag, &ms);
            if (!flag)
                nap(200000);
        }
        MPI_Get_count(&ms, MPI_UINT64_T, &n);
        uint64_t *t = cur;
        cur = nxt;
        nxt = t;
    }
    while (!got_stop) { /* rank 0's one TAG_STOP, when it stopped or at the end */
        poll_stop(o, &got_stop);
        if (!got_stop)
            nap(200000);
    }
    free(cur);
    free(nxt);
    free(batch.p);
    return st;
}

__attribute__((visibility("default"))) lv_status
lv_mc_mpi_run(const lv_mission *m, const lv_campaign_options *o, lv_campaign_progress *out,
              int *is_rank0, lv_err *err)
{
    int provided = 0, rank = 0, world = 1;
    MPI_Init_thread(NULL, NULL, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &world);
    *is_rank0 = rank == 0;
    memset(out, 0, sizeof *out);
    const int threads = o->threads > 0 ? (o->threads > 256 ? 256 : o->threads) : 1;
    lv_mc_worker *w[256];
    lv_status st = LV_OK;
    int made = 0;
    for (; made < threads && st == LV_OK; made++)
        st = lv_mc_worker_create(m, o, &w[made], err);
    if (st != LV_OK) {
        fprintf(stderr, "lvsim: rank %d: %s\n", rank, err ? err->msg : "error");
        MPI_Abort(MPI_COMM_WORLD, 1);
    }
    if (rank == 0)
        st = rank0(m, o, world, w, out, err);
    else
        st = worker_rank(w, threads, o, err);
    for (int i = 0; i < made; i++)
        lv_mc_worker_free(w[i]);
    /* the campaign is over: a signal now ends the process as usual (mpirun, when rank 0
     * exits with 130, terminates the other ranks, which may still be finalizing) */
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    MPI_Barrier(MPI_COMM_WORLD);
    MPI_Finalize();
    return st;
}
