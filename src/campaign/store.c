/* store.c - the campaign database (SQLite 3, WAL journal): the campaign's identity (mission,
 * its hash, seed, size, generator), the dispersions, the phases, and per run its drawn inputs,
 * every phase's outcome and final values, and its events. Rows are keyed by run index, so the
 * contents do not depend on the order runs complete in. Schema: docs/monte-carlo.md. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>
#include <unistd.h>

#include <sqlite3.h>

#include "campaign/sqlite_dl.h"
#include "campaign/campaign_int.h"
#include "core/status.h"
#include "lvsim/lv_dispersion.h"

/* 2: a phase's state and a run's status `impact` (a fall to the ground where another end was
 * meant) beside done/ok; 3: the table iip (a phase's impact point at its `iip_at:` times)
 * and phases.stages (the bodies a phase carries) */
#define LV_MC_SCHEMA 3
#define LV_MC_SCHEMA_TEXT "3"

struct lv_campaign {
    const lv_mission *m;
    lv_campaign_options o;
    sqlite3 *db;
    sqlite3_stmt *ins_run, *ins_event, *ins_iip;
    sqlite3_stmt **ins_phase; /* [n_phases] */
    size_t n_phases, n_disp;
    size_t *n_final;          /* [n_phases] */
    /* the runs not stored when it was opened, as ranges [gap[2i], gap[2i+1]) ascending: as
     * many as there are holes between stored runs, never a list of n_runs */
    uint64_t *gap;
    size_t n_gaps, gap_at;    /* the range handed out next */
    uint64_t next_run;        /* its next run */
    uint64_t n_todo;          /* runs not stored and not handed out yet */
    uint64_t done, this_session, failed, impacts, crashed;
    int in_tx;
    double t0;
};

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static lv_status db_fail(lv_campaign *c, lv_err *err, const char *what)
{
    return lv_fail(err, LV_ERR_IO, "%s: %s: %s", c->o.db_path, what,
                   c->db                  ? sqlite3_errmsg(c->db)
                   : lv_sqlite_error() ? lv_sqlite_error()
                                       : "cannot open");
}

static lv_status exec(lv_campaign *c, const char *sql, lv_err *err)
{
    char *msg = NULL;
    if (sqlite3_exec(c->db, sql, NULL, NULL, &msg) != SQLITE_OK) {
        lv_status st = lv_fail(err, LV_ERR_IO, "%s: %s (in: %.80s)", c->o.db_path,
                               msg ? msg : "error", sql);
        sqlite3_free(msg);
        return st;
    }
    return LV_OK;
}

/* Appends "name" as an SQL identifier (double quotes doubled). */
static void ident(char *buf, size_t cap, size_t *at, const char *name)
{
    if (*at + 1 < cap)
        buf[(*at)++] = '"';
    for (const char *p = name; *p && *at + 3 < cap; p++) {
        if (*p == '"')
            buf[(*at)++] = '"';
        buf[(*at)++] = *p;
    }
    if (*at + 1 < cap)
        buf[(*at)++] = '"';
    buf[*at < cap ? *at : cap - 1] = '\0';
}

static void cat(char *buf, size_t cap, size_t *at, const char *s)
{
    const size_t n = strlen(s);
    if (*at + n < cap) {
        memcpy(buf + *at, s, n + 1);
        *at += n;
    }
}

/* FNV-1a 64 over the bytes of a file, continuing from h; -1 when it cannot be read. */
static int hash_file(const char *path, uint64_t *h)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return -1;
    unsigned char buf[65536];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, f)) > 0)
        for (size_t i = 0; i < n; i++) {
            *h ^= buf[i];
            *h *= 1099511628211ULL;
        }
    fclose(f);
    return 0;
}

/* FNV-1a 64 of the mission file's bytes and of every data file it reads (profiles, tables,
 * gravity coefficients: lv_mission_file), each after its name: a resumed database must belong
 * to the same file and the same data (a sounding replaced between two sessions would mix two
 * days' weather in one campaign). */
static void mission_hash(const lv_mission *m, const char *path, char out[17])
{
    uint64_t h = 14695981039346656037ULL;
    hash_file(path, &h);
    for (size_t i = 0; i < lv_mission_file_count(m); i++) {
        const char *f = lv_mission_file(m, i);
        for (const unsigned char *q = (const unsigned char *)f; *q; q++) {
            h ^= *q;
            h *= 1099511628211ULL;
        }
        hash_file(f, &h);
    }
    snprintf(out, 17, "%016llx", (unsigned long long)h);
}

static int meta_get(lv_campaign *c, const char *key, char *val, size_t cap)
{
    sqlite3_stmt *s = NULL;
    int found = 0;
    if (sqlite3_prepare_v2(c->db, "SELECT value FROM campaign WHERE key = ?", -1, &s, NULL) ==
        SQLITE_OK) {
        sqlite3_bind_text(s, 1, key, -1, SQLITE_STATIC);
        if (sqlite3_step(s) == SQLITE_ROW) {
            snprintf(val, cap, "%s", (const char *)sqlite3_column_text(s, 0));
            found = 1;
        }
    }
    sqlite3_finalize(s);
    return found;
}

/* A file that is an lvsim campaign database: SQLite with the campaign table and its schema
 * row (what create_schema writes). Only such a file is replaced by --force / overwrite. */
static int is_campaign_db(const char *path)
{
    sqlite3 *db = NULL;
    int ok = 0;
    if (sqlite3_open_v2(path, &db, SQLITE_OPEN_READONLY, NULL) == SQLITE_OK) {
        sqlite3_stmt *s = NULL;
        if (sqlite3_prepare_v2(db, "SELECT value FROM campaign WHERE key = 'schema'", -1, &s,
                               NULL) == SQLITE_OK &&
            sqlite3_step(s) == SQLITE_ROW)
            ok = 1;
        sqlite3_finalize(s);
    }
    sqlite3_close(db);
    return ok;
}

static lv_status meta_put(lv_campaign *c, const char *key, const char *val, lv_err *err)
{
    sqlite3_stmt *s = NULL;
    if (sqlite3_prepare_v2(c->db, "INSERT OR REPLACE INTO campaign(key, value) VALUES (?, ?)",
                           -1, &s, NULL) != SQLITE_OK)
        return db_fail(c, err, "metadata");
    sqlite3_bind_text(s, 1, key, -1, SQLITE_STATIC);
    sqlite3_bind_text(s, 2, val, -1, SQLITE_STATIC);
    const int rc = sqlite3_step(s);
    sqlite3_finalize(s);
    return rc == SQLITE_DONE ? LV_OK : db_fail(c, err, "metadata");
}

/* The campaign's tables (new database). */
static lv_status create_schema(lv_campaign *c, const lv_run *r, lv_err *err)
{
    const lv_mission *m = c->m;
    lv_status st;
    char *sql = malloc(1 << 20);
    if (sql == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    size_t at = 0;
    const size_t cap = 1 << 20;
    st = exec(c, "CREATE TABLE campaign(key TEXT PRIMARY KEY, value TEXT) WITHOUT ROWID;"
                 "CREATE TABLE dispersions(j INTEGER PRIMARY KEY, name TEXT, unit TEXT, dist TEXT,"
                 " relative INTEGER, nominal REAL, mean REAL, sigma REAL, min REAL, max REAL,"
                 " grp INTEGER, stream TEXT);"
                 "CREATE TABLE correlations(a INTEGER, b INTEGER, rho REAL, PRIMARY KEY(a, b))"
                 " WITHOUT ROWID;"
                 "CREATE TABLE phases(k INTEGER PRIMARY KEY, name TEXT, parent INTEGER,"
                 " model TEXT, tbl TEXT, stages TEXT);"
                 "CREATE TABLE events(run INTEGER, phase INTEGER, seq INTEGER, t REAL, name TEXT,"
                 " PRIMARY KEY(run, phase, seq)) WITHOUT ROWID;"
                 "CREATE TABLE iip(run INTEGER, phase INTEGER, t REAL, state TEXT, lat REAL,"
                 " lon REAL, tof REAL, range REAL, PRIMARY KEY(run, phase, t)) WITHOUT ROWID;",
              err);
    /* runs: one row per run, the drawn inputs as columns (named as written) */
    at = 0;
    cat(sql, cap, &at, "CREATE TABLE runs(run INTEGER PRIMARY KEY, status TEXT, message TEXT");
    for (size_t j = 0; j < c->n_disp; j++) {
        lv_disp_info di;
        lv_mission_disp_info(m, j, &di);
        cat(sql, cap, &at, ", ");
        ident(sql, cap, &at, di.name);
        cat(sql, cap, &at, " REAL");
    }
    cat(sql, cap, &at, ");");
    if (st == LV_OK)
        st = exec(c, sql, err);
    for (size_t k = 0; k < c->n_phases && st == LV_OK; k++) {
        const lv_phase_result *res = lv_run_result(r, k);
        char tbl[128];
        snprintf(tbl, sizeof tbl, "phase_%s", res->name);
        at = 0;
        cat(sql, cap, &at, "CREATE TABLE ");
        ident(sql, cap, &at, tbl);
        cat(sql, cap, &at, "(run INTEGER PRIMARY KEY, state TEXT, end_reason TEXT, t_end REAL,"
                           " steps INTEGER, rhs_evals INTEGER, error TEXT");
        for (size_t i = 0; i < res->n_final; i++) {
            char col[160];
            /* "time" is the end time already; keep every final under its own name */
            snprintf(col, sizeof col, "%s", res->final_names[i]);
            cat(sql, cap, &at, ", ");
            ident(sql, cap, &at, col);
            cat(sql, cap, &at, " REAL");
        }
        cat(sql, cap, &at, ");");
        st = exec(c, sql, err);
    }
    free(sql);
    if (st != LV_OK)
        return st;
    /* what the campaign is */
    lv_mission_info mi;
    lv_mission_get_info(m, &mi);
    char buf[64], hash[17] = "";
    mission_hash(m, mi.path, hash);
    snprintf(buf, sizeof buf, "%llu", (unsigned long long)c->o.seed);
    if ((st = meta_put(c, "schema", LV_MC_SCHEMA_TEXT, err)) != LV_OK ||
        (st = meta_put(c, "mission", mi.name, err)) != LV_OK ||
        (st = meta_put(c, "mission_file", mi.path, err)) != LV_OK ||
        (st = meta_put(c, "mission_hash", hash, err)) != LV_OK ||
        (st = meta_put(c, "planet", mi.planet ? mi.planet : "", err)) != LV_OK ||
        (st = meta_put(c, "seed", buf, err)) != LV_OK ||
        (st = meta_put(c, "generator", "philox4x32-10 (Random123); key (seed), counter (run, "
                                       "FNV-1a 64 of the parameter's name)", err)) != LV_OK ||
        (st = meta_put(c, "method", c->o.method ? c->o.method : "", err)) != LV_OK)
        return st;
    snprintf(buf, sizeof buf, "%.17g", c->o.tolerance);
    if ((st = meta_put(c, "tolerance", buf, err)) != LV_OK)
        return st;
    snprintf(buf, sizeof buf, "%.17g", c->o.output_interval);
    if ((st = meta_put(c, "output_interval", buf, err)) != LV_OK)
        return st;
    sqlite3_stmt *s = NULL;
    if (sqlite3_prepare_v2(c->db, "INSERT INTO dispersions VALUES (?,?,?,?,?,?,?,?,?,?,?,?)", -1,
                           &s, NULL) != SQLITE_OK)
        return db_fail(c, err, "dispersions");
    for (size_t j = 0; j < c->n_disp; j++) {
        lv_disp_info di;
        lv_mission_disp_info(m, j, &di);
        char stream[24];
        snprintf(stream, sizeof stream, "%016llx", (unsigned long long)di.stream);
        sqlite3_reset(s);
        sqlite3_bind_int64(s, 1, (sqlite3_int64)j);
        sqlite3_bind_text(s, 2, di.name, -1, SQLITE_TRANSIENT);
        sqlite3_bind_text(s, 3, di.unit, -1, SQLITE_TRANSIENT);
        sqlite3_bind_text(s, 4, di.dist, -1, SQLITE_TRANSIENT);
        sqlite3_bind_int(s, 5, di.relative);
        const double v[5] = { di.nominal, di.mean, di.sigma, di.min, di.max };
        for (int i = 0; i < 5; i++)
            if (isfinite(v[i]) && !(i == 2 && di.kind == LV_DIST_UNIFORM) &&
                !(i >= 3 && di.kind == LV_DIST_NORMAL) && !(i == 1 && di.kind == LV_DIST_UNIFORM))
                sqlite3_bind_double(s, 6 + i, v[i]);
            else
                sqlite3_bind_null(s, 6 + i);
        if (di.group >= 0)
            sqlite3_bind_int(s, 11, di.group);
        else
            sqlite3_bind_null(s, 11);
        sqlite3_bind_text(s, 12, stream, -1, SQLITE_TRANSIENT);
        if (sqlite3_step(s) != SQLITE_DONE) {
            sqlite3_finalize(s);
            return db_fail(c, err, "dispersions");
        }
    }
    sqlite3_finalize(s);
    if (sqlite3_prepare_v2(c->db, "INSERT INTO correlations VALUES (?,?,?)", -1, &s, NULL) !=
        SQLITE_OK)
        return db_fail(c, err, "correlations");
    for (size_t a = 0; a < c->n_disp; a++)
        for (size_t b = a + 1; b < c->n_disp; b++) {
            const double rho = lv_mission_disp_correlation(m, a, b);
            if (rho == 0.0)
                continue;
            sqlite3_reset(s);
            sqlite3_bind_int64(s, 1, (sqlite3_int64)a);
            sqlite3_bind_int64(s, 2, (sqlite3_int64)b);
            sqlite3_bind_double(s, 3, rho);
            if (sqlite3_step(s) != SQLITE_DONE) {
                sqlite3_finalize(s);
                return db_fail(c, err, "correlations");
            }
        }
    sqlite3_finalize(s);
    if (sqlite3_prepare_v2(c->db, "INSERT INTO phases VALUES (?,?,?,?,?,?)", -1, &s, NULL) !=
        SQLITE_OK)
        return db_fail(c, err, "phases");
    for (size_t k = 0; k < c->n_phases; k++) {
        lv_phase_info pi;
        lv_mission_phase_info(m, k, &pi);
        char tbl[128];
        snprintf(tbl, sizeof tbl, "phase_%s", pi.name);
        sqlite3_reset(s);
        sqlite3_bind_int64(s, 1, (sqlite3_int64)k);
        sqlite3_bind_text(s, 2, pi.name, -1, SQLITE_TRANSIENT);
        sqlite3_bind_int(s, 3, pi.parent);
        sqlite3_bind_text(s, 4, pi.model, -1, SQLITE_TRANSIENT);
        sqlite3_bind_text(s, 5, tbl, -1, SQLITE_TRANSIENT);
        /* the bodies it carries, bottom first: a jettisoned part's fall names its part */
        char stages[1024];
        size_t used = 0;
        stages[0] = '\0';
        for (size_t i = 0; i < pi.n_stages && used < sizeof stages; i++)
            used += (size_t)snprintf(stages + used, sizeof stages - used, "%s%s", i ? ", " : "",
                                     lv_mission_stage_name(m, pi.stages[i]));
        sqlite3_bind_text(s, 6, stages, -1, SQLITE_TRANSIENT);
        if (sqlite3_step(s) != SQLITE_DONE) {
            sqlite3_finalize(s);
            return db_fail(c, err, "phases");
        }
    }
    sqlite3_finalize(s);
    return LV_OK;
}

static lv_status prepare_inserts(lv_campaign *c, const lv_run *r, lv_err *err)
{
    char sql[65536];
    size_t at = 0;
    cat(sql, sizeof sql, &at, "INSERT OR REPLACE INTO runs VALUES (?, ?, ?");
    for (size_t j = 0; j < c->n_disp; j++)
        cat(sql, sizeof sql, &at, ", ?");
    cat(sql, sizeof sql, &at, ")");
    if (sqlite3_prepare_v2(c->db, sql, -1, &c->ins_run, NULL) != SQLITE_OK ||
        sqlite3_prepare_v2(c->db, "INSERT OR REPLACE INTO events VALUES (?, ?, ?, ?, ?)", -1,
                           &c->ins_event, NULL) != SQLITE_OK ||
        sqlite3_prepare_v2(c->db, "INSERT OR REPLACE INTO iip VALUES (?, ?, ?, ?, ?, ?, ?, ?)",
                           -1, &c->ins_iip, NULL) != SQLITE_OK)
        return db_fail(c, err, "prepare");
    for (size_t k = 0; k < c->n_phases; k++) {
        const lv_phase_result *res = lv_run_result(r, k);
        char tbl[128];
        snprintf(tbl, sizeof tbl, "phase_%s", res->name);
        at = 0;
        cat(sql, sizeof sql, &at, "INSERT OR REPLACE INTO ");
        ident(sql, sizeof sql, &at, tbl);
        cat(sql, sizeof sql, &at, " VALUES (?, ?, ?, ?, ?, ?, ?");
        for (size_t i = 0; i < res->n_final; i++)
            cat(sql, sizeof sql, &at, ", ?");
        cat(sql, sizeof sql, &at, ")");
        if (sqlite3_prepare_v2(c->db, sql, -1, &c->ins_phase[k], NULL) != SQLITE_OK)
            return db_fail(c, err, "prepare");
        c->n_final[k] = res->n_final;
    }
    return LV_OK;
}

/* Appends the runs [lo, hi) to the ranges to do. */
static lv_status add_gap(lv_campaign *c, size_t *cap, uint64_t lo, uint64_t hi, lv_err *err)
{
    if (c->n_gaps == *cap) {
        const size_t nc = *cap ? 2 * *cap : 16;
        uint64_t *g = realloc(c->gap, 2 * nc * sizeof *g);
        if (g == NULL)
            return lv_fail(err, LV_ERR_NOMEM, "out of memory");
        c->gap = g;
        *cap = nc;
    }
    c->gap[2 * c->n_gaps] = lo;
    c->gap[2 * c->n_gaps + 1] = hi;
    c->n_gaps++;
    c->n_todo += hi - lo;
    return LV_OK;
}

lv_status lv_campaign_close(lv_campaign *c, lv_err *err)
{
    if (c == NULL)
        return LV_OK;
    lv_status st = LV_OK;
    if (c->db != NULL && c->in_tx)
        st = lv_campaign_commit(c, err);
    /* back to a rollback journal: the database is one self-contained file again, which
     * readers (statistics, sqlite3) may open read-only */
    if (c->db != NULL && st == LV_OK)
        sqlite3_exec(c->db, "PRAGMA journal_mode=DELETE", NULL, NULL, NULL);
    sqlite3_finalize(c->ins_run);
    sqlite3_finalize(c->ins_event);
    sqlite3_finalize(c->ins_iip);
    for (size_t k = 0; c->ins_phase && k < c->n_phases; k++)
        sqlite3_finalize(c->ins_phase[k]);
    if (c->db != NULL && sqlite3_close(c->db) != SQLITE_OK && st == LV_OK)
        st = lv_fail(err, LV_ERR_IO, "%s: cannot close", c->o.db_path);
    free(c->ins_phase);
    free(c->n_final);
    free(c->gap);
    free(c);
    return st;
}

lv_status lv_campaign_open(const lv_mission *m, const lv_campaign_options *o, lv_campaign **out,
                           lv_err *err)
{
    *out = NULL;
    if (o == NULL || o->db_path == NULL || o->n_runs == 0)
        return lv_fail(err, LV_ERR_INPUT, "campaign: a database path and at least one run are "
                       "needed");
    if (lv_mission_disp_count(m) == 0 && !lv_mission_turbulent(m) &&
        lv_mission_disp_profile_count(m) == 0)
        return lv_fail(err, LV_ERR_INPUT, "mission '%s' has no dispersions: add a "
                       "'dispersions:' section (docs/monte-carlo.md)", lv_mission_name(m));
    if (o->keep_runs > 0 && o->keep_dir == NULL)
        return lv_fail(err, LV_ERR_INPUT, "campaign: keep_runs needs keep_dir");
    /* the overrides of every phase's settings: out of range is refused, not replaced */
    if (o->tolerance != 0.0 && !(o->tolerance >= LV_TOLERANCE_MIN && o->tolerance <= LV_TOLERANCE_MAX))
        return lv_fail(err, LV_ERR_INPUT, "campaign: tolerance must be >= %g and <= %g, or 0 for "
                       "each phase's own (got %g)", LV_TOLERANCE_MIN, LV_TOLERANCE_MAX,
                       o->tolerance);
    if (!(o->output_interval >= 0.0) || !isfinite(o->output_interval))
        return lv_fail(err, LV_ERR_INPUT, "campaign: output_interval must be > 0 s, or 0 (got %g)",
                       o->output_interval);
    if (o->method != NULL) {
        const char *const *mn = lv_sim_methods();
        while (*mn != NULL && strcasecmp(*mn, o->method) != 0)
            mn++;
        if (*mn == NULL)
            return lv_fail(err, LV_ERR_INPUT, "campaign: unknown integration method '%s'",
                           o->method);
    }
    lv_campaign *c = calloc(1, sizeof *c);
    lv_run *r = NULL;
    if (c == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    c->m = m;
    c->o = *o;
    c->t0 = now_s();
    c->n_phases = lv_mission_phase_count(m);
    c->n_disp = lv_mission_disp_count(m);
    c->ins_phase = calloc(c->n_phases + 1, sizeof *c->ins_phase);
    c->n_final = calloc(c->n_phases + 1, sizeof *c->n_final);
    lv_status st;
    if (c->ins_phase == NULL || c->n_final == NULL) {
        st = lv_fail(err, LV_ERR_NOMEM, "out of memory");
        goto fail;
    }
    if ((st = lv_run_create(m, &r, err)) != LV_OK)
        goto fail;
    /* the row limit, up front, as every run will hold it (lv_mc_worker_run's options) */
    if (o->max_rows > 0.0) {
        lv_run_options ro = {0};
        ro.max_rows = o->max_rows;
        ro.output_interval = o->output_interval > 0.0 ? o->output_interval : 1e300;
        if ((st = lv_run_check_output(r, &ro, err)) != LV_OK)
            goto fail;
        ro.output_interval = o->output_interval;
        if (o->keep_runs > 0 && (st = lv_run_check_output(r, &ro, err)) != LV_OK) {
            lv_fail_prefix(err, st, "the kept runs (each phase's own output grid)");
            goto fail;
        }
    }
    const int exists = access(o->db_path, F_OK) == 0;
    if (exists && !o->resume && !o->overwrite) {
        st = lv_fail(err, LV_ERR_INPUT, "%s exists: continue it with --resume, or replace it "
                     "with --force", o->db_path);
        goto fail;
    }
    if (exists && o->overwrite && !o->resume) {
        if (!is_campaign_db(o->db_path)) {
            st = lv_fail(err, LV_ERR_INPUT, "%s is not an lvsim campaign database: it is not "
                         "replaced (also with --force); move it away or choose another path",
                         o->db_path);
            goto fail;
        }
        char side[4200];
        remove(o->db_path);
        snprintf(side, sizeof side, "%s-wal", o->db_path);
        remove(side);
        snprintf(side, sizeof side, "%s-shm", o->db_path);
        remove(side);
    }
    const int fresh = !(exists && o->resume);
    if (sqlite3_open_v2(o->db_path, &c->db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, NULL) !=
        SQLITE_OK) {
        st = db_fail(c, err, "cannot open");
        goto fail;
    }
    sqlite3_busy_timeout(c->db, 5000);
    /* WAL: a transaction is durable once committed, a kill -9 loses only the open batch */
    if ((st = exec(c, "PRAGMA journal_mode=WAL; PRAGMA synchronous=NORMAL;", err)) != LV_OK)
        goto fail;
    if (fresh) {
        if ((st = exec(c, "BEGIN", err)) != LV_OK || (st = create_schema(c, r, err)) != LV_OK ||
            (st = exec(c, "COMMIT", err)) != LV_OK)
            goto fail;
    } else {
        /* the same campaign: mission file (by its bytes) and seed */
        char v[256], hash[17] = "", want[64];
        lv_mission_info mi;
        lv_mission_get_info(m, &mi);
        mission_hash(m, mi.path, hash);
        snprintf(want, sizeof want, "%llu", (unsigned long long)o->seed);
        if (!meta_get(c, "schema", v, sizeof v) || strcmp(v, LV_MC_SCHEMA_TEXT) != 0) {
            st = lv_fail(err, LV_ERR_INPUT, "%s is not an lvsim campaign database (schema %d)",
                         o->db_path, LV_MC_SCHEMA);
            goto fail;
        }
        if (!meta_get(c, "mission_hash", v, sizeof v) || strcmp(v, hash) != 0) {
            st = lv_fail(err, LV_ERR_INPUT, "%s was made from another mission file or other data "
                         "files (hash %s, now %s: the mission and every file it reads): resume "
                         "with the same files, or start anew (--force)",
                         o->db_path, v, hash);
            goto fail;
        }
        if (!meta_get(c, "seed", v, sizeof v) || strcmp(v, want) != 0) {
            st = lv_fail(err, LV_ERR_INPUT, "%s has seed %s, not %s: resume with --seed %s",
                         o->db_path, v, want, v);
            goto fail;
        }
        static const char *const keys[] = { "method", "tolerance", "output_interval" };
        char mine[3][64];
        snprintf(mine[0], 64, "%s", o->method ? o->method : "");
        snprintf(mine[1], 64, "%.17g", o->tolerance);
        snprintf(mine[2], 64, "%.17g", o->output_interval);
        for (int i = 0; i < 3; i++)
            if (meta_get(c, keys[i], v, sizeof v) && strcmp(v, mine[i]) != 0) {
                st = lv_fail(err, LV_ERR_INPUT, "%s was run with %s '%s', not '%s': resume with "
                             "the same options", o->db_path, keys[i], v, mine[i]);
                goto fail;
            }
        /* a campaign grows, it does not shrink: its statistics would leave stored runs out */
        sqlite3_stmt *q = NULL;
        sqlite3_int64 last = -1;
        if (sqlite3_prepare_v2(c->db, "SELECT MAX(run) FROM runs", -1, &q, NULL) == SQLITE_OK &&
            sqlite3_step(q) == SQLITE_ROW && sqlite3_column_type(q, 0) != SQLITE_NULL)
            last = sqlite3_column_int64(q, 0);
        sqlite3_finalize(q);
        if (last >= 0 && (uint64_t)last >= o->n_runs) {
            st = lv_fail(err, LV_ERR_INPUT, "%s holds runs up to run %lld: resume with -n %lld "
                         "or more (a campaign grows, it is not cut short)", o->db_path,
                         (long long)last, (long long)last + 1);
            goto fail;
        }
    }
    char nbuf[32];
    snprintf(nbuf, sizeof nbuf, "%llu", (unsigned long long)o->n_runs);
    if ((st = meta_put(c, "n_runs", nbuf, err)) != LV_OK ||
        (st = prepare_inserts(c, r, err)) != LV_OK)
        goto fail;
    /* which runs are stored already: the holes between them (in run order) are to do */
    sqlite3_stmt *s = NULL;
    if (sqlite3_prepare_v2(c->db, "SELECT run, status FROM runs ORDER BY run", -1, &s, NULL) !=
        SQLITE_OK) {
        st = db_fail(c, err, "runs");
        goto fail;
    }
    uint64_t from = 0; /* the first run not known to be stored */
    size_t cap = 0;
    while (st == LV_OK && sqlite3_step(s) == SQLITE_ROW) {
        const sqlite3_int64 i = sqlite3_column_int64(s, 0);
        if (i < 0 || (uint64_t)i >= o->n_runs)
            continue;
        if ((uint64_t)i > from)
            st = add_gap(c, &cap, from, (uint64_t)i, err);
        from = (uint64_t)i + 1;
        c->done++;
        const char *stt = (const char *)sqlite3_column_text(s, 1);
        c->failed += stt != NULL && strcmp(stt, "ok") != 0 && strcmp(stt, "impact") != 0 &&
                     strcmp(stt, "crashed") != 0;
        c->impacts += stt != NULL && strcmp(stt, "impact") == 0;
        c->crashed += stt != NULL && strcmp(stt, "crashed") == 0;
    }
    sqlite3_finalize(s);
    if (st == LV_OK && from < o->n_runs)
        st = add_gap(c, &cap, from, o->n_runs, err);
    if (st != LV_OK)
        goto fail;
    c->next_run = c->n_gaps > 0 ? c->gap[0] : 0;
    lv_run_free(r);
    *out = c;
    return LV_OK;
fail:
    lv_run_free(r);
    lv_campaign_close(c, NULL);
    return st;
}

uint64_t lv_campaign_todo_count(const lv_campaign *c) { return c->n_todo; }

size_t lv_campaign_todo_next(lv_campaign *c, uint64_t *runs, size_t cap)
{
    size_t n = 0;
    while (n < cap && c->gap_at < c->n_gaps) {
        if (c->next_run >= c->gap[2 * c->gap_at + 1]) {
            if (++c->gap_at < c->n_gaps)
                c->next_run = c->gap[2 * c->gap_at];
            continue;
        }
        runs[n++] = c->next_run++;
        c->n_todo--;
    }
    return n;
}

static void bind_real(sqlite3_stmt *s, int i, double v)
{
    if (isnan(v))
        sqlite3_bind_null(s, i);
    else
        sqlite3_bind_double(s, i, v);
}

lv_status lv_campaign_store(lv_campaign *c, const void *rec, size_t len, lv_err *err)
{
    static const char *const status_name[] = { "ok", "failed", "input", "impact", "crashed" };
    /* lv_phase_state's words (lv_phase_state_name), then LV_MC_IMPACT's */
    static const char *const state_name[] = { "pending", "done", "failed", "skipped", "crashed",
                                              "impact" };
    lv_rd rd = { rec, len, 0, 0 };
    lv_status st;
    if (!c->in_tx) {
        if ((st = exec(c, "BEGIN", err)) != LV_OK)
            return st;
        c->in_tx = 1;
    }
    const uint64_t run = lv_rd_u64(&rd), status = lv_rd_u64(&rd);
    size_t n;
    const char *msg = lv_rd_str(&rd, &n);
    const uint64_t nd = lv_rd_u64(&rd);
    if (rd.bad || nd != c->n_disp || status > LV_MC_RUN_CRASHED || run >= c->o.n_runs)
        return lv_fail(err, LV_ERR_INPUT, "campaign: a malformed record (run %llu)",
                       (unsigned long long)run);
    sqlite3_stmt *s = c->ins_run;
    sqlite3_reset(s);
    sqlite3_bind_int64(s, 1, (sqlite3_int64)run);
    sqlite3_bind_text(s, 2, status_name[status], -1, SQLITE_STATIC);
    sqlite3_bind_text(s, 3, msg, (int)n, SQLITE_TRANSIENT);
    for (size_t j = 0; j < nd; j++)
        bind_real(s, 4 + (int)j, lv_rd_f64(&rd));
    if (sqlite3_step(s) != SQLITE_DONE)
        return db_fail(c, err, "runs");
    const uint64_t np = lv_rd_u64(&rd);
    if (np != c->n_phases)
        return lv_fail(err, LV_ERR_INPUT, "campaign: a malformed record (run %llu)",
                       (unsigned long long)run);
    for (size_t k = 0; k < np; k++) {
        s = c->ins_phase[k];
        sqlite3_reset(s);
        const uint64_t state = lv_rd_u64(&rd);
        const char *end = lv_rd_str(&rd, &n);
        sqlite3_bind_int64(s, 1, (sqlite3_int64)run);
        sqlite3_bind_text(s, 2, state_name[state <= LV_MC_IMPACT ? state : 0], -1, SQLITE_STATIC);
        sqlite3_bind_text(s, 3, end, (int)n, SQLITE_TRANSIENT);
        bind_real(s, 4, lv_rd_f64(&rd));
        sqlite3_bind_int64(s, 5, (sqlite3_int64)lv_rd_u64(&rd));
        sqlite3_bind_int64(s, 6, (sqlite3_int64)lv_rd_u64(&rd));
        const char *e = lv_rd_str(&rd, &n);
        if (n > 0)
            sqlite3_bind_text(s, 7, e, (int)n, SQLITE_TRANSIENT);
        else
            sqlite3_bind_null(s, 7);
        const uint64_t nf = lv_rd_u64(&rd);
        if (nf != c->n_final[k] || rd.bad)
            return lv_fail(err, LV_ERR_INPUT, "campaign: a malformed record (run %llu)",
                           (unsigned long long)run);
        for (size_t i = 0; i < nf; i++)
            bind_real(s, 8 + (int)i, lv_rd_f64(&rd));
        if (sqlite3_step(s) != SQLITE_DONE)
            return db_fail(c, err, "phase outcome");
        const uint64_t ne = lv_rd_u64(&rd);
        for (uint64_t i = 0; i < ne && !rd.bad; i++) {
            const double t = lv_rd_f64(&rd);
            const char *name = lv_rd_str(&rd, &n);
            sqlite3_stmt *ev = c->ins_event;
            sqlite3_reset(ev);
            sqlite3_bind_int64(ev, 1, (sqlite3_int64)run);
            sqlite3_bind_int64(ev, 2, (sqlite3_int64)k);
            sqlite3_bind_int64(ev, 3, (sqlite3_int64)i);
            bind_real(ev, 4, t);
            sqlite3_bind_text(ev, 5, name, (int)n, SQLITE_TRANSIENT);
            if (sqlite3_step(ev) != SQLITE_DONE)
                return db_fail(c, err, "events");
        }
        /* lv_iip_state's words */
        static const char *const iip_state[] = { "impact", "in orbit", "not flying" };
        const uint64_t ni = lv_rd_u64(&rd);
        for (uint64_t i = 0; i < ni && !rd.bad; i++) {
            const double t = lv_rd_f64(&rd);
            const uint64_t is = lv_rd_u64(&rd);
            sqlite3_stmt *q = c->ins_iip;
            sqlite3_reset(q);
            sqlite3_bind_int64(q, 1, (sqlite3_int64)run);
            sqlite3_bind_int64(q, 2, (sqlite3_int64)k);
            bind_real(q, 3, t);
            sqlite3_bind_text(q, 4, iip_state[is <= LV_IIP_NOT_FLYING ? is : LV_IIP_NOT_FLYING],
                              -1, SQLITE_STATIC);
            for (int j = 0; j < 4; j++)
                bind_real(q, 5 + j, lv_rd_f64(&rd));
            if (!rd.bad && sqlite3_step(q) != SQLITE_DONE)
                return db_fail(c, err, "iip");
        }
    }
    if (rd.bad)
        return lv_fail(err, LV_ERR_INPUT, "campaign: a malformed record (run %llu)",
                       (unsigned long long)run);
    c->done++;
    c->this_session++;
    c->failed += status == LV_MC_FAILED || status == LV_MC_INPUT;
    c->impacts += status == LV_MC_RUN_IMPACT;
    c->crashed += status == LV_MC_RUN_CRASHED;
    return LV_OK;
}

lv_status lv_campaign_commit(lv_campaign *c, lv_err *err)
{
    if (!c->in_tx)
        return LV_OK;
    c->in_tx = 0;
    return exec(c, "COMMIT", err);
}

void lv_campaign_get_progress(const lv_campaign *c, lv_campaign_progress *p)
{
    memset(p, 0, sizeof *p);
    p->total = c->o.n_runs;
    p->done = c->done;
    p->this_session = c->this_session;
    p->failed = c->failed;
    p->impacts = c->impacts;
    p->crashed = c->crashed;
    p->elapsed = now_s() - c->t0;
    p->rate = p->elapsed > 0.0 ? (double)c->this_session / p->elapsed : 0.0;
    p->eta = p->rate > 0.0 ? (double)(p->total - p->done) / p->rate : NAN;
}
