/* cmd_mc.c - `lvsim mc MISSION.yaml -n N`: a Monte Carlo dispersion campaign (lv_campaign.h):
 * the mission loaded once, its runs on a thread pool (or across MPI ranks under mpirun), a
 * progress bar, the SQLite database, then statistics, figures, the report and KML.
 */
#define _GNU_SOURCE /* dladdr */

#include <dlfcn.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "common.h"
#include "lvsim/lv_campaign.h"
#include "lvsim/lv_dispersion.h"
#include "mc.h"

/* Under mpirun only rank 0 reports what every rank finds the same (the estimate, a refusal). */
static int is_rank0(void)
{
    const char *v = getenv("OMPI_COMM_WORLD_RANK");
    if (v == NULL)
        v = getenv("PMI_RANK");
    return v == NULL || atoi(v) == 0;
}

typedef struct bar {
    int tty;
    double last_line; /* elapsed time of the last plain line */
    uint64_t last_done;
} bar;

static void fmt_time(double s, char *buf, size_t cap)
{
    if (!isfinite(s) || s < 0) {
        snprintf(buf, cap, "--:--");
        return;
    }
    if (s >= 360000.0) { /* beyond 100 hours: days, never an overflowing clock */
        snprintf(buf, cap, "%.3g days", s / 86400.0);
        return;
    }
    const long t = (long)(s + 0.5);
    if (t >= 3600)
        snprintf(buf, cap, "%ld:%02ld:%02ld", t / 3600, t / 60 % 60, t % 60);
    else
        snprintf(buf, cap, "%ld:%02ld", t / 60, t % 60);
}

static void show_progress(const lv_campaign_progress *p, void *user)
{
    bar *b = user;
    char eta[32], el[32];
    fmt_time(p->eta, eta, sizeof eta);
    fmt_time(p->elapsed, el, sizeof el);
    const double frac = p->total ? (double)p->done / (double)p->total : 1.0;
    if (b->tty) {
        char fill[41];
        const int w = (int)(40.0 * frac);
        for (int i = 0; i < 40; i++)
            fill[i] = i < w ? '#' : '.';
        fill[40] = '\0';
        fprintf(stderr, "\r[%s] %5.1f%% %llu/%llu  %.1f runs/s  ETA %s  impact %llu  crashed %llu  "
                "failed %llu ", fill, 100.0 * frac, (unsigned long long)p->done,
                (unsigned long long)p->total, p->rate, eta, (unsigned long long)p->impacts,
                (unsigned long long)p->crashed, (unsigned long long)p->failed);
        if (p->done == p->total)
            fputc('\n', stderr);
    } else if (p->elapsed - b->last_line >= 10.0 || p->done == p->total ||
               (p->done - b->last_done) * 10 >= p->total) {
        fprintf(stderr, "mc: %llu/%llu runs (%.1f%%), %.1f runs/s, elapsed %s, ETA %s, impact "
                "%llu, crashed %llu, failed %llu\n", (unsigned long long)p->done,
                (unsigned long long)p->total, 100.0 * frac, p->rate, el, eta,
                (unsigned long long)p->impacts, (unsigned long long)p->crashed,
                (unsigned long long)p->failed);
        b->last_line = p->elapsed;
        b->last_done = p->done;
    }
    fflush(stderr);
}

static int parse_u64(const char *s, uint64_t *out)
{
    if (s == NULL || *s < '0' || *s > '9')
        return 0;
    char *end;
    errno = 0;
    const unsigned long long v = strtoull(s, &end, 10);
    if (errno != 0 || *end != '\0')
        return 0;
    *out = (uint64_t)v;
    return 1;
}

/* What the campaign will compute and store, before anything is made: the rows of a run (and
 * of a kept run) against --max-rows, as lv_campaign_open holds them (lv_run_check_output);
 * the database, the kept runs' files and the statistics' memory against the machine
 * (lv_campaign_check_size). The estimate goes to stderr, a refusal too (rank 0 only: every
 * rank finds the same); returns 0, or 2 refused (1 out of memory). */
static int check_bounds(const lv_mission *m, const lv_campaign_options *o, int stats)
{
    const int say = is_rank0();
    lv_err err;
    lv_run *r = NULL;
    lv_status st = lv_run_create(m, &r, &err);
    const char *ctx = "mc";
    char nctx[48];
    lv_run_options ro = {0};
    ro.max_rows = o->max_rows;
    ro.output_interval = o->output_interval > 0.0 ? o->output_interval : 1e300; /* the records */
    if (st == LV_OK)
        st = lv_run_check_output(r, &ro, &err);
    if (st == LV_OK && o->keep_runs > 0) {
        ro.output_interval = o->output_interval; /* 0: each phase's own grid */
        ctx = "mc --keep-runs";
        st = lv_run_check_output(r, &ro, &err);
    }
    lv_run_free(r);
    lv_campaign_size z;
    if (st == LV_OK) {
        snprintf(nctx, sizeof nctx, "mc -n %llu", (unsigned long long)o->n_runs);
        ctx = nctx;
        st = lv_campaign_check_size(m, o, stats, &z, &err);
    }
    if (st != LV_OK) {
        if (say)
            fprintf(stderr, "lvsim: %s: %s\n", ctx, err.msg);
        return exit_code_for_input(st);
    }
    if (!say)
        return EXIT_OK;
    char rows[32], stop[64] = "", db[32], mem[32], kept[32];
    snprintf(rows, sizeof rows, z.rows_per_run < 1e7 ? "%.0f" : "%.3g", z.rows_per_run);
    if (z.rows_by_stop > z.rows_per_run)
        snprintf(stop, sizeof stop, z.rows_by_stop < 1e7 ? " (%.0f by the stop times)"
                                                         : " (%.3g by the stop times)",
                 z.rows_by_stop);
    human_bytes(z.db_bytes, db, sizeof db);
    human_bytes(z.stats_bytes, mem, sizeof mem);
    human_bytes(z.kept_bytes, kept, sizeof kept);
    fprintf(stderr, "mc: estimate: up to %s output rows a run%s, a database of about %s%s%s%s\n",
            rows, stop, db, stats ? ", statistics in about " : "", stats ? mem : "",
            stats ? " of memory" : "");
    if (z.rows_by_stop > z.rows_per_run)
        fprintf(stderr, "mc: note: a phase with an end event that does not fire within "
                "--max-rows %.*g rows fails there\n", o->max_rows < 1e7 ? 7 : 3, o->max_rows);
    if (o->keep_runs > 0 && z.kept_bytes_max > z.kept_bytes) {
        char kmax[32], dfree[32];
        human_bytes(z.kept_bytes_max, kmax, sizeof kmax);
        fprintf(stderr, "mc: estimate: the kept runs' files about %s, up to %s where phases "
                "with end events run to their stop times or the row limit\n", kept, kmax);
        if (z.kept_bytes_max > z.disk_free) {
            human_bytes(z.disk_free, dfree, sizeof dfree);
            fprintf(stderr, "mc: warning: that is more than the %s free where the campaign "
                    "writes; keep fewer runs (--keep-runs), give them a larger output interval "
                    "or a lower --max-rows\n", dfree);
        }
    } else if (o->keep_runs > 0) {
        fprintf(stderr, "mc: estimate: the kept runs' files about %s\n", kept);
    }
    return EXIT_OK;
}

static int run_mc(const cli_cmd *self, int argc, char **argv)
{
    const char *path = NULL, *outdir = "lvsim-mc", *method = NULL;
    uint64_t n = 0, seed = 0, keep = 0;
    int threads = 1, seed_given = 0, resume = 0, force = 0, plots = 1, stats = 1;
    double tol = 0.0, dt_out = 0.0, max_rows = CLI_DEFAULT_MAX_ROWS;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "-n") == 0 || strcmp(a, "-j") == 0 || strcmp(a, "--threads") == 0 ||
            strcmp(a, "--seed") == 0 || strcmp(a, "-o") == 0 || strcmp(a, "--keep-runs") == 0 ||
            strcmp(a, "--method") == 0 || strcmp(a, "--tolerance") == 0 ||
            strcmp(a, "--output-interval") == 0 || strcmp(a, "--max-rows") == 0) {
            const char *v = option_value(argc, argv, &i);
            if (v == NULL)
                return usage_error(self, "missing value for option", a);
            if (strcmp(a, "-n") == 0) {
                double c; /* 10000 or 1e4, as --max-rows */
                if (parse_u64(v, &n) ? n == 0 : !(parse_count(v, &c) && (n = (uint64_t)c) > 0))
                    return usage_error(self, "-n needs a whole run count >= 1, got", v);
            } else if (strcmp(a, "-j") == 0 || strcmp(a, "--threads") == 0) {
                if (!parse_int(v, &threads) || threads < 1 || threads > 256)
                    return usage_error(self, "-j needs a thread count 1..256, got", v);
            } else if (strcmp(a, "--seed") == 0) {
                if (!parse_u64(v, &seed))
                    return usage_error(self, "--seed needs an integer 0..2^64-1, got", v);
                seed_given = 1;
            } else if (strcmp(a, "--keep-runs") == 0) {
                if (!parse_u64(v, &keep))
                    return usage_error(self, "--keep-runs needs a count >= 0, got", v);
            } else if (strcmp(a, "--method") == 0) {
                if (!parse_method_option(self, a, v))
                    return EXIT_INPUT;
                method = v;
            } else if (strcmp(a, "--tolerance") == 0) {
                if (!parse_tolerance_option(self, a, v, &tol))
                    return EXIT_INPUT;
            } else if (strcmp(a, "--output-interval") == 0) {
                if (!parse_interval_option(self, a, v, &dt_out))
                    return EXIT_INPUT;
            } else if (strcmp(a, "--max-rows") == 0) {
                if (!parse_count(v, &max_rows))
                    return usage_error(self, "--max-rows needs a whole number from 1 to 1e15, got", v);
            } else {
                outdir = v;
            }
        } else if (strcmp(a, "--resume") == 0) {
            resume = 1;
        } else if (strcmp(a, "--force") == 0) {
            force = 1;
        } else if (strcmp(a, "--no-plots") == 0) {
            plots = 0;
        } else if (strcmp(a, "--no-stats") == 0) {
            stats = 0, plots = 0;
        } else if (is_option(a)) {
            return usage_error(self, "unknown option", a);
        } else if (path != NULL) {
            return usage_error(self, "unexpected argument", a);
        } else {
            path = a;
        }
    }
    if (path == NULL)
        return usage_error(self, "mc needs a mission file", NULL);
    if (n == 0)
        return usage_error(self, "mc needs the run count: -n N", NULL);
    if (resume && force)
        return usage_error(self, "--resume and --force exclude each other", NULL);
    lv_mission *m;
    lv_err err;
    lv_status st = lv_mission_load(path, &m, &err);
    if (st != LV_OK)
        return print_err(NULL, &err, exit_code_for_input(st));
    if (lv_mission_disp_count(m) == 0 && !lv_mission_turbulent(m) &&
        lv_mission_disp_profile_count(m) == 0) {
        fprintf(stderr, "lvsim: %s has no 'dispersions:' section (and no turbulence): nothing "
                "to disperse (docs/monte-carlo.md)\n", path);
        lv_mission_free(m);
        return EXIT_INPUT;
    }
    if (!seed_given && !lv_mission_disp_seed(m, &seed))
        seed = 1;
    const int world = mc_mpi_world_size();
    char db[4300], keep_dir[4300], final_dir[4200];
    /* DIR is lvsim's (lv_outdir.h): the database and the kept runs are written in it as the
     * campaign goes (its manifest claims them at once), the statistics and figures in a
     * replica that replaces it at the end. Rank 0 alone owns it. */
    static const char *const live[] = {"campaign.db", "campaign.db-wal", "campaign.db-shm",
                                       "campaign.db-journal", "runs", NULL};
    snprintf(db, sizeof db, "%s/campaign.db", outdir);
    {
        lv_campaign_options bo; /* the bounds, before anything is made */
        lv_campaign_options_default(&bo);
        bo.n_runs = n, bo.threads = threads, bo.db_path = db, bo.resume = resume;
        bo.keep_runs = keep, bo.output_interval = dt_out, bo.max_rows = max_rows;
        const int code = check_bounds(m, &bo, stats);
        if (code != EXIT_OK) {
            lv_mission_free(m);
            return code;
        }
    }
    /* refused before DIR is opened (which writes its manifest at once): a command refused
     * leaves the folder as it was */
    if (!resume && !force && access(db, F_OK) == 0) {
        fprintf(stderr, "lvsim: %s exists: continue it with --resume, or replace it with "
                "--force\n", db);
        lv_mission_free(m);
        return EXIT_INPUT;
    }
    lv_outdir *od = NULL;
    if (mc_mpi_env_rank() == 0) {
        st = lv_outdir_open_live(outdir, path, force ? LV_OUTDIR_FORCE : 0u, live, &od, &err);
        if (st != LV_OK) {
            lv_mission_free(m);
            return print_err("lvsim", &err, exit_code_for_input(st));
        }
        for (size_t i = 0; i < lv_outdir_stale_count(od); i++)
            fprintf(stderr, "lvsim: removed '%s', the unfinished folder of an interrupted "
                    "command\n", lv_outdir_stale(od, i));
        snprintf(final_dir, sizeof final_dir, "%s", lv_outdir_final(od));
        outdir = final_dir;
    }
    snprintf(db, sizeof db, "%s/campaign.db", outdir);
    snprintf(keep_dir, sizeof keep_dir, "%s/runs", outdir);
    lv_campaign_options o;
    lv_campaign_options_default(&o);
    o.n_runs = n;
    o.seed = seed;
    o.threads = threads;
    o.db_path = db;
    o.resume = resume;
    o.overwrite = force;
    o.keep_runs = keep;
    o.keep_dir = keep > 0 ? keep_dir : NULL;
    o.method = method;
    o.tolerance = tol;
    o.output_interval = dt_out;
    o.max_rows = max_rows;
    bar b = { isatty(2), -1e9, 0 };
    o.progress = show_progress;
    o.user = &b;
    o.stop = &cli_stop_flag; /* every running run cancelled within an integrator step */
    cli_catch_stop();
    lv_campaign_progress prog;
    memset(&prog, 0, sizeof prog);
    int rank0 = 1;
    if (world > 1) {
        st = mc_mpi_run(m, &o, &prog, &rank0, &err);
    } else {
        fprintf(stderr, "mc: mission '%s', %llu runs, seed %llu, %d thread%s -> %s\n",
                lv_mission_name(m), (unsigned long long)n, (unsigned long long)seed, threads,
                threads == 1 ? "" : "s", db);
        st = lv_campaign_run(m, &o, &prog, &err);
    }
    lv_mission_free(m);
    if (!rank0) {
        lv_outdir_free(od);
        return st == LV_OK ? EXIT_OK : exit_code_for(st);
    }
    if (st != LV_OK) { /* the folder stays as it is, its manifest saying "incomplete" ... */
        if (st == LV_ERR_INPUT && prog.this_session == 0)
            lv_outdir_discard(od); /* ... or as it was, when refused before any run */
        else
            lv_outdir_free(od);
        print_err("lvsim", &err, 0);
        return exit_code_for(st);
    }
    printf("mc: %llu runs in %s (%llu this session in %.2f s: %.1f runs/s), %llu with a failed "
           "phase or an input out of range, %llu with a phase that fell to the ground (an "
           "impact end other than its first), %llu crashed (a touchdown beyond the landing "
           "gear's limits)\n", (unsigned long long)prog.done, db,
           (unsigned long long)prog.this_session, prog.elapsed, prog.rate,
           (unsigned long long)prog.failed, (unsigned long long)prog.impacts,
           (unsigned long long)prog.crashed);
    lv_err serr;
    lv_status sst = stats ? lv_outdir_stage(od, &serr) : LV_OK;
    const char *stage = lv_outdir_path(od);
    if (stats && sst == LV_OK)
        sst = lv_campaign_stats(db, stage, &serr);
    if (stats && sst == LV_OK && plots)
        sst = lv_campaign_plot(db, stage, &serr);
    if (sst != LV_OK) {
        restage(serr.msg, sizeof serr.msg, stage, lv_outdir_final(od));
        lv_outdir_free(od);
        return print_err("lvsim", &serr, exit_code_for_input(sst));
    }
    const lv_outdir_record rec = {"mc", "ok", NULL, 0, NULL};
    if ((sst = lv_outdir_commit(od, &rec, &serr)) != LV_OK) {
        lv_outdir_free(od);
        return print_err("lvsim", &serr, exit_code_for_input(sst));
    }
    print_kept(od);
    lv_outdir_free(od);
    if (stats)
        printf("statistics: %s/stats.json, stats.csv, ellipses.csv, outcomes.csv, "
               "sensitivity.csv, footprint.kml%s\n", outdir, plots ? ", plots/, index.html" : "");
    return EXIT_OK;
}

const cli_cmd cli_cmd_mc = {
    "mc",
    "Monte Carlo dispersion campaign: N runs, SQLite database, statistics",
    "MISSION.yaml -n N [-j THREADS] [--seed S] [-o DIR] [--resume] [options]",
    "Runs N missions with the values the mission's 'dispersions:' section draws for each\n"
    "run (docs/monte-carlo.md): the mission is loaded once, the runs go to a pool of\n"
    "threads, and each run's drawn inputs, every phase's end, final values, events and\n"
    "failure are stored in DIR/campaign.db (SQLite, committed in batches: a killed campaign\n"
    "keeps every stored run and --resume continues it). Run i draws the same values whatever\n"
    "-j, the rank count under mpirun, or the order runs finish in. A failing run is an\n"
    "outcome, never the end of the campaign; a phase that ends on the ground by an\n"
    "'impact' end other than its first written end (a stage that fell back) is an impact\n"
    "outcome, counted apart from the failures. Then writes stats.json, stats.csv,\n"
    "ellipses.csv, outcomes.csv, sensitivity.csv, footprint.kml, plots/ and index.html.\n"
    "Under 'mpirun -np K lvsim mc ...' rank 0 owns the database and hands out runs in\n"
    "chunks to every rank (itself included).\n"
    "Before anything runs it estimates a run's output rows (refusing, as 'lvsim check', a\n"
    "phase only its stop time ends beyond --max-rows; a phase with an end event that reaches\n"
    "it fails in that run), the database's size and the statistics' memory, and refuses\n"
    "(exit 2) a run count whose database would not fit the free disk space or whose\n"
    "statistics would not fit the machine's memory. Ctrl-C or SIGTERM stops it within a\n"
    "second: the runs under way are cancelled and not stored, the database stays\n"
    "consistent, --resume continues it (exit 130).\n"
    "\n"
    "options:\n"
    "  -n N                    runs 0 .. N-1 (required)\n"
    "  -j, --threads T         worker threads per process (default 1)\n"
    "  --seed S                the campaign's seed, 0..2^64-1 (default: the file's\n"
    "                          dispersions: seed, else 1)\n"
    "  -o DIR                  output folder (default lvsim-mc): new, empty, or one of lvsim\n"
    "                          (its manifest.json lists every file; others are refused)\n"
    "  --resume                continue DIR/campaign.db (same mission file, seed, options)\n"
    "  --force                 replace an existing DIR/campaign.db; DIR may hold files lvsim\n"
    "                          did not write: they are kept, never replaced\n"
    "  --keep-runs K           runs 0 .. K-1 also write their result files to DIR/runs/\n"
    "                          run_<i>/ (phases, summary.json) (default 0)\n"
    "  --method M, --tolerance T   every phase's integration method / tolerance (1e-14 to\n"
    "                          0.1)\n"
    "  --output-interval S     every phase's output grid (default none: start and end only)\n"
    "  --max-rows N            output rows a phase of a run may compute (default 1e6)\n"
    "  --no-plots              statistics without plots/ and index.html\n"
    "  --no-stats              the database only\n",
    run_mc,
};

int mc_mpi_world_size(void)
{
    const char *v = getenv("OMPI_COMM_WORLD_SIZE");
    if (v == NULL)
        v = getenv("PMI_SIZE");
    return v != NULL && atoi(v) > 1 ? atoi(v) : 1;
}

int mc_mpi_env_rank(void)
{
    const char *v = getenv("OMPI_COMM_WORLD_RANK");
    if (v == NULL)
        v = getenv("PMI_RANK");
    return v != NULL ? atoi(v) : 0;
}

static lv_status mc_fail(lv_err *err, lv_status code, const char *what, const char *why)
{
    if (err != NULL) {
        err->code = code;
        snprintf(err->msg, sizeof err->msg, "%s%s", what, why);
    }
    return code;
}

lv_status mc_mpi_run(const lv_mission *m, const lv_campaign_options *o, lv_campaign_progress *out,
                     int *rank0, lv_err *err)
{
    if (mc_mpi_world_size() == 1) {
        *rank0 = 1;
        return lv_campaign_run(m, o, out, err);
    }
    *rank0 = mc_mpi_env_rank() == 0;
#ifndef LV_WITH_MPI
    return mc_fail(err, LV_ERR_INPUT,
                   "started by mpirun, but this lvsim was built without MPI (the build found no "
                   "MPI library: install libopenmpi-dev and rebuild)", "");
#else
    /* the module beside liblvsim_post: <libdir>/lvsim/lvsim_mpi.so (as its figures' module) */
    Dl_info info;
    char lib[PATH_MAX], path[PATH_MAX + 32];
    void *anchor;
    lv_status (*in_post)(const lv_mission *, const lv_campaign_options *,
                         lv_campaign_progress *, lv_err *) = lv_campaign_run;
    memcpy(&anchor, &in_post, sizeof anchor); /* an address inside liblvsim_post */
    if (dladdr(anchor, &info) == 0 || info.dli_fname == NULL ||
        realpath(info.dli_fname, lib) == NULL)
        return mc_fail(err, LV_ERR_IO,
                       "cannot tell where liblvsim_post is, so not where lvsim_mpi.so is", "");
    char *slash = strrchr(lib, '/');
    if (slash != NULL)
        *slash = '\0';
    snprintf(path, sizeof path, "%s/lvsim/lvsim_mpi.so", lib);
    /* RTLD_GLOBAL: Open MPI's components, loaded by MPI_Init, resolve symbols of libmpi */
    void *h = dlopen(path, RTLD_NOW | RTLD_GLOBAL);
    void *sym = h != NULL ? dlsym(h, "lv_mc_mpi_run") : NULL;
    if (sym == NULL)
        return mc_fail(err, LV_ERR_IO, "cannot load the MPI module: ", dlerror());
    lv_mc_mpi_run_fn fn;
    memcpy(&fn, &sym, sizeof fn); /* POSIX: the pointer dlsym returns names the function */
    return fn(m, o, out, rank0, err);
#endif
}
