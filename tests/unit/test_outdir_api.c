/* test_outdir_api.c - lv_outdir (include/lvsim/lv_outdir.h) through its API, in one process:
 * a new folder appears only at commit, with its manifest; a second writer is refused while
 * the first holds the lock (flock locks open files, so even in one process); a folder lvsim
 * did not write (also one with a foreign summary.json or manifest.json), a file, "", "." are
 * refused and left alone byte for byte; with LV_OUTDIR_FORCE the user's files are kept (the
 * same inode, not in the manifest) and a commit that would replace one is refused; a file of
 * lvsim's changed since is the user's; a stale staging folder is removed and reported only
 * when it is lvsim's; -o reused leaves nothing of the earlier run; an uncommitted folder
 * leaves OUTDIR as it was; an in-place update works in a replica and adds to the manifest's
 * history; modes follow the umask and a replaced folder keeps its mode; a live folder (a
 * campaign's) claims its names at once. SHA-256 against the FIPS 180-4 examples ("abc", the
 * empty message). The manifest takes the digest a file written through lv_atomic's stream
 * carries (io/atomic.h) while the file is unchanged, without reading it, and reads the file
 * otherwise. The CLI's behaviour (concurrent processes, kill -9) is
 * tests/cli/test_outdir.sh. */
#define _GNU_SOURCE /* lsetxattr */

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/xattr.h>
#include <unistd.h>

#include "check.h"
#include "io/atomic.h"
#include "lvsim/lv_outdir.h"

#define ROOT "outdir_api"

static int exists(const char *p)
{
    struct stat sb;
    return stat(p, &sb) == 0;
}

static void put(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (f != NULL) {
        fputs(text, f);
        fclose(f);
    }
}

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return NULL;
    char *buf = calloc(1, 1 << 16);
    if (buf != NULL && fread(buf, 1, (1 << 16) - 1, f) == 0)
        buf[0] = '\0';
    fclose(f);
    return buf;
}

/* Entries of ROOT whose name starts with `prefix`. */
static int count_entries(const char *prefix)
{
    DIR *d = opendir(ROOT);
    int n = 0;
    struct dirent *e;
    while (d != NULL && (e = readdir(d)) != NULL)
        n += strncmp(e->d_name, prefix, strlen(prefix)) == 0;
    if (d != NULL)
        closedir(d);
    return n;
}

static void rm_rf(const char *path)
{
    char cmd[512];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", path);
    if (system(cmd) != 0)
        fprintf(stderr, "cannot remove %s\n", path);
}

static void test_sha256(void)
{
    lv_err err;
    char hex[65];
    unsigned long long n = 99;
    put(ROOT "/abc.txt", "abc");
    CHECK_OK(lv_sha256_file(ROOT "/abc.txt", hex, &n, &err), &err);
    CHECK(strcmp(hex, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad") == 0);
    CHECK(n == 3);
    put(ROOT "/empty.txt", "");
    CHECK_OK(lv_sha256_file(ROOT "/empty.txt", hex, &n, &err), &err);
    CHECK(strcmp(hex, "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855") == 0);
    CHECK(n == 0);
    CHECK(lv_sha256_file(ROOT "/none.txt", hex, &n, &err) == LV_ERR_IO);
    CHECK(strstr(err.msg, ROOT "/none.txt: cannot read") != NULL);
}

static void test_run_folder(void)
{
    lv_err err;
    lv_outdir *a = NULL, *b = NULL;
    const char *out = ROOT "/out";
    put(ROOT "/m.yaml", "abc");
    CHECK_OK(lv_outdir_begin(out, ROOT "/m.yaml", 0, &a, &err), &err);
    if (a == NULL)
        return;
    /* writing goes to a staging folder beside OUTDIR; OUTDIR does not exist yet */
    const char *stage = lv_outdir_path(a);
    CHECK(strncmp(stage, ROOT "/.out.staging-", strlen(ROOT "/.out.staging-")) == 0);
    CHECK(exists(stage) && !exists(out) && exists(ROOT "/.out.lock"));
    /* a second writer is refused at once, naming the folder */
    CHECK(lv_outdir_begin(out, NULL, 0, &b, &err) == LV_ERR_INPUT && b == NULL);
    CHECK(strstr(err.msg, "results folder '" ROOT "/out' is in use by another lvsim") != NULL);
    CHECK(lv_outdir_open(out, &b, &err) == LV_ERR_INPUT && b == NULL); /* not a folder yet */
    char path[4200];
    snprintf(path, sizeof path, "%s/phase_1_a.csv", stage);
    put(path, "time [s]\n0\n");
    const char *notes[] = {"a note"};
    const lv_outdir_record rec = {"run", "failed", "m", 1, notes};
    CHECK_OK(lv_outdir_commit(a, &rec, &err), &err);
    CHECK(exists(out) && !exists(stage) && !exists(ROOT "/.out.lock"));
    CHECK(lv_outdir_file_count(a) == 1 && strcmp(lv_outdir_files(a)[0].name, "phase_1_a.csv") == 0 &&
          lv_outdir_files(a)[0].bytes == 11);
    lv_outdir_free(a);
    char *man = slurp(ROOT "/out/manifest.json");
    CHECK(man != NULL && strstr(man, "\"status\":\t\"failed\"") != NULL &&
          strstr(man, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad") != NULL &&
          strstr(man, "\"a note\"") != NULL && strstr(man, "\"phase_1_a.csv\"") != NULL);
    free(man);

    /* an uncommitted run leaves OUTDIR as it was and no staging folder */
    CHECK_OK(lv_outdir_begin(out, NULL, 0, &a, &err), &err);
    lv_outdir_free(a);
    CHECK(exists(ROOT "/out/phase_1_a.csv") && count_entries(".out.staging-") == 0);

    /* -o reused: the folder is replaced, nothing of the earlier run remains */
    CHECK_OK(lv_outdir_begin(ROOT "/out/", NULL, 0, &a, &err), &err); /* trailing slash: the same */
    snprintf(path, sizeof path, "%s/phase_1_b.csv", lv_outdir_path(a));
    put(path, "time [s]\n");
    const lv_outdir_record ok = {"run", "ok", NULL, 0, NULL};
    CHECK_OK(lv_outdir_commit(a, &ok, &err), &err);
    lv_outdir_free(a);
    CHECK(exists(ROOT "/out/phase_1_b.csv") && !exists(ROOT "/out/phase_1_a.csv"));

    /* a stale staging folder of a killed run (marked by lvsim) is removed and reported; one
     * that is not provably lvsim's (no marker, no lvsim manifest) is left alone */
    mkdir(ROOT "/.out.staging-Ab12Cd", 0777);
    put(ROOT "/.out.staging-Ab12Cd/.lvsim-staging", "");
    put(ROOT "/.out.staging-Ab12Cd/phase_9_x.csv.tmp", "half");
    mkdir(ROOT "/.out.staging-Zz99Yy", 0777);
    put(ROOT "/.out.staging-Zz99Yy/mine.txt", "a user's folder of an unlucky name");
    CHECK_OK(lv_outdir_begin(out, NULL, 0, &a, &err), &err);
    CHECK(lv_outdir_stale_count(a) == 1 && strcmp(lv_outdir_stale(a, 0), ".out.staging-Ab12Cd") == 0);
    CHECK(!exists(ROOT "/.out.staging-Ab12Cd") && exists(ROOT "/.out.staging-Zz99Yy/mine.txt"));
    lv_outdir_free(a);
    rm_rf(ROOT "/.out.staging-Zz99Yy");

    /* in place (export, plot, view): a replica to write in; the manifest keeps its run and
     * gains a history entry */
    CHECK_OK(lv_outdir_open(out, &a, &err), &err);
    CHECK(strcmp(lv_outdir_path(a), out) != 0);
    snprintf(path, sizeof path, "%s/phase_1_b.csv", lv_outdir_path(a));
    CHECK(exists(path)); /* the replica has the folder's files */
    snprintf(path, sizeof path, "%s/mission.kml", lv_outdir_path(a));
    put(path, "<kml/>");
    CHECK(!exists(ROOT "/out/mission.kml")); /* nothing in OUTDIR before the commit */
    const lv_outdir_record ex = {"export", "ok", NULL, 0, NULL};
    CHECK_OK(lv_outdir_commit(a, &ex, &err), &err);
    CHECK(lv_outdir_file_count(a) == 2);
    lv_outdir_free(a);
    man = slurp(ROOT "/out/manifest.json");
    CHECK(man != NULL && strstr(man, "\"command\":\t\"export\"") != NULL &&
          strstr(man, "\"mission.kml\"") != NULL && strstr(man, "\"command\":\t\"run\"") != NULL);
    free(man);
}

static void test_refused(void)
{
    lv_err err;
    lv_outdir *a = (lv_outdir *)&err; /* must come back NULL */
    CHECK(lv_outdir_begin("", NULL, 0, &a, &err) == LV_ERR_INPUT && a == NULL);
    CHECK(strstr(err.msg, "name is empty") != NULL);
    CHECK(lv_outdir_begin(".", NULL, 0, &a, &err) == LV_ERR_INPUT && a == NULL);
    CHECK(strstr(err.msg, "cannot be a results folder") != NULL);
    put(ROOT "/file", "x");
    CHECK(lv_outdir_begin(ROOT "/file", NULL, 0, &a, &err) == LV_ERR_INPUT);
    CHECK(strstr(err.msg, "'" ROOT "/file' is a file, not a folder") != NULL);
    CHECK(lv_outdir_begin(ROOT "/file/sub", NULL, 0, &a, &err) == LV_ERR_INPUT);
    mkdir(ROOT "/mine", 0777);
    put(ROOT "/mine/notes.txt", "keep");
    CHECK(lv_outdir_begin(ROOT "/mine", NULL, 0, &a, &err) == LV_ERR_INPUT);
    CHECK(strstr(err.msg, "holds 1 file lvsim did not write (notes.txt)") != NULL);
    char *kept = slurp(ROOT "/mine/notes.txt");
    CHECK(kept != NULL && strcmp(kept, "keep") == 0);
    free(kept);
    CHECK(count_entries(".mine.") == 0 && count_entries(".file.") == 0); /* no lock left */
    CHECK(lv_outdir_begin(ROOT "/new", ROOT "/no-such-mission.yaml", 0, &a, &err) == LV_ERR_IO);
    CHECK(!exists(ROOT "/new") && count_entries(".new.") == 0);
}

/* Byte-for-byte snapshot of a small folder tree: "name\tcontent\n" per file, sorted (find). */
static char *snapshot(const char *dir)
{
    char cmd[512];
    snprintf(cmd, sizeof cmd,
             "cd '%s' && find . -print | LC_ALL=C sort | while read -r f; do "
             "if [ -f \"$f\" ]; then printf '%%s\\t' \"$f\"; sha256sum < \"$f\"; "
             "else printf '%%s\\n' \"$f\"; fi; done", dir);
    FILE *p = popen(cmd, "r");
    if (p == NULL)
        return NULL;
    char *buf = calloc(1, 1 << 16);
    size_t n = buf != NULL ? fread(buf, 1, (1 << 16) - 1, p) : 0;
    if (buf != NULL)
        buf[n] = '\0';
    pclose(p);
    return buf;
}

static ino_t inode_of(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0 ? sb.st_ino : 0;
}

/* The decoy: a folder with thesis.tex, a subfolder and a summary.json from another
 * tool. Refused and untouched byte for byte; with LV_OUTDIR_FORCE a commit whose results
 * have a summary.json is refused (OUTDIR as it was), one without keeps every user's file as
 * itself (same inode), and the manifest lists only lvsim's files. */
static void test_decoy(void)
{
    lv_err err;
    lv_outdir *a = NULL;
    const char *dec = ROOT "/decoy";
    mkdir(dec, 0777);
    mkdir(ROOT "/decoy/figures", 0777);
    put(ROOT "/decoy/thesis.tex", "\\documentclass{article}");
    put(ROOT "/decoy/figures/f1.pdf", "%PDF-1.4");
    put(ROOT "/decoy/summary.json", "{\"from\": \"another tool\"}");
    char *before = snapshot(dec);
    CHECK(lv_outdir_begin(dec, NULL, 0, &a, &err) == LV_ERR_INPUT && a == NULL);
    CHECK(strstr(err.msg, "holds 3 files lvsim did not write (figures/, summary.json, "
                          "thesis.tex)") != NULL);
    CHECK(strstr(err.msg, "--force") != NULL);
    char *after = snapshot(dec);
    CHECK(before != NULL && after != NULL && strcmp(before, after) == 0);
    free(after);
    /* a user's manifest.json is never replaced, even with force */
    put(ROOT "/decoy/manifest.json", "{\"mine\": true}");
    CHECK(lv_outdir_begin(dec, NULL, LV_OUTDIR_FORCE, &a, &err) == LV_ERR_INPUT);
    CHECK(strstr(err.msg, "'" ROOT "/decoy/manifest.json' is not lvsim's") != NULL);
    remove(ROOT "/decoy/manifest.json");
    /* force, and a user's summary.json, a name every run writes: refused before the work,
     * not at the commit after it (issue 22's breaker), nothing changed */
    CHECK(lv_outdir_begin(dec, NULL, LV_OUTDIR_FORCE, &a, &err) == LV_ERR_INPUT && a == NULL);
    CHECK(strstr(err.msg, "'" ROOT "/decoy/summary.json' is not lvsim's and lvsim must write a "
                          "file of that name") != NULL);
    after = snapshot(dec);
    CHECK(after != NULL && strcmp(before, after) == 0);
    free(after);
    remove(ROOT "/decoy/summary.json");
    put(ROOT "/decoy/notes.txt", "mine");
    free(before);
    before = snapshot(dec);
    /* force, and the results have a file of the user's name after all: refused at commit,
     * nothing changed */
    CHECK_OK(lv_outdir_begin(dec, NULL, LV_OUTDIR_FORCE, &a, &err), &err);
    char path[4200];
    snprintf(path, sizeof path, "%s/notes.txt", lv_outdir_path(a));
    put(path, "{\"lvsim\": 1}");
    const lv_outdir_record ok = {"run", "ok", NULL, 0, NULL};
    CHECK(lv_outdir_commit(a, &ok, &err) == LV_ERR_INPUT);
    CHECK(strstr(err.msg, "'" ROOT "/decoy/notes.txt' is not lvsim's, and the new results "
                          "have a file of that name: nothing was replaced") != NULL);
    lv_outdir_free(a);
    after = snapshot(dec);
    CHECK(after != NULL && strcmp(before, after) == 0 && count_entries(".decoy.") == 0);
    free(after);
    /* force without a collision: the user's files kept as themselves */
    const ino_t thesis = inode_of(ROOT "/decoy/thesis.tex");
    CHECK_OK(lv_outdir_begin(dec, NULL, LV_OUTDIR_FORCE, &a, &err), &err);
    snprintf(path, sizeof path, "%s/phase_1_a.csv", lv_outdir_path(a));
    put(path, "time [s]\n0\n");
    CHECK_OK(lv_outdir_commit(a, &ok, &err), &err);
    CHECK(lv_outdir_kept_count(a) == 3 && strcmp(lv_outdir_kept(a, 0), "figures/f1.pdf") == 0);
    CHECK(lv_outdir_file_count(a) == 1 && strcmp(lv_outdir_files(a)[0].name, "phase_1_a.csv") == 0);
    lv_outdir_free(a);
    CHECK(inode_of(ROOT "/decoy/thesis.tex") == thesis && exists(ROOT "/decoy/figures/f1.pdf"));
    char *man = slurp(ROOT "/decoy/manifest.json");
    CHECK(man != NULL && strstr(man, "thesis.tex") == NULL && strstr(man, "phase_1_a.csv") != NULL);
    free(man);
    /* a second run without force: still refused (the user's files are still there) */
    CHECK(lv_outdir_begin(dec, NULL, 0, &a, &err) == LV_ERR_INPUT);
    CHECK(strstr(err.msg, "holds 3 files lvsim did not write") != NULL);
    free(before);
}

/* A file lvsim wrote and the user changed since is the user's: a rerun is refused; in place
 * (open), a writer that replaces a user's file makes the commit fail with OUTDIR as it was,
 * while the user's files added to a results folder survive an update. */
static void test_changed_and_in_place(void)
{
    lv_err err;
    lv_outdir *a = NULL;
    const char *out = ROOT "/res";
    char path[4200];
    const lv_outdir_record ok = {"run", "ok", NULL, 0, NULL};
    CHECK_OK(lv_outdir_begin(out, NULL, 0, &a, &err), &err);
    snprintf(path, sizeof path, "%s/summary.json", lv_outdir_path(a));
    put(path, "{\"status\": \"ok\"}");
    CHECK_OK(lv_outdir_commit(a, &ok, &err), &err);
    lv_outdir_free(a);
    /* the user edits it (same size, new content) */
    put(ROOT "/res/summary.json", "{\"status\": \"OK\"}");
    CHECK(lv_outdir_begin(out, NULL, 0, &a, &err) == LV_ERR_INPUT);
    CHECK(strstr(err.msg, "summary.json: changed since lvsim wrote it") != NULL);
    put(ROOT "/res/summary.json", "{\"status\": \"ok\"}"); /* back as lvsim wrote it */
    CHECK_OK(lv_outdir_begin(out, NULL, 0, &a, &err), &err);
    lv_outdir_free(a);
    /* a note the user adds to the results survives an export, not listed in the manifest */
    put(ROOT "/res/notes.txt", "my notes");
    const ino_t notes = inode_of(ROOT "/res/notes.txt");
    CHECK_OK(lv_outdir_open(out, &a, &err), &err);
    snprintf(path, sizeof path, "%s/mission.czml", lv_outdir_path(a));
    put(path, "[]");
    const lv_outdir_record ex = {"export", "ok", NULL, 0, NULL};
    CHECK_OK(lv_outdir_commit(a, &ex, &err), &err);
    lv_outdir_free(a);
    CHECK(inode_of(ROOT "/res/notes.txt") == notes && exists(ROOT "/res/mission.czml"));
    char *man = slurp(ROOT "/res/manifest.json");
    CHECK(man != NULL && strstr(man, "notes.txt") == NULL && strstr(man, "mission.czml") != NULL);
    free(man);
    /* an update that would replace the user's file: refused, OUTDIR as it was */
    char *before = snapshot(out);
    CHECK_OK(lv_outdir_open(out, &a, &err), &err);
    snprintf(path, sizeof path, "%s/notes.txt", lv_outdir_path(a));
    remove(path); /* as a writer's rename over it would */
    put(path, "lvsim's notes");
    CHECK(lv_outdir_commit(a, &ex, &err) == LV_ERR_INPUT);
    CHECK(strstr(err.msg, "'" ROOT "/res/notes.txt' is not lvsim's") != NULL);
    lv_outdir_free(a);
    char *after = snapshot(out);
    CHECK(before != NULL && after != NULL && strcmp(before, after) == 0);
    free(before);
    free(after);
    /* open needs lvsim's folder */
    mkdir(ROOT "/plain", 0777);
    put(ROOT "/plain/summary.json", "{}");
    CHECK(lv_outdir_open(ROOT "/plain", &a, &err) == LV_ERR_INPUT);
    CHECK(strstr(err.msg, "is not a results folder of lvsim") != NULL);
    /* a lock file beside the folder that is not lvsim's is left alone */
    put(ROOT "/.res.lock", "a user's file");
    CHECK(lv_outdir_begin(out, NULL, 0, &a, &err) == LV_ERR_INPUT);
    CHECK(strstr(err.msg, "is not lvsim's lock file") != NULL);
    char *lk = slurp(ROOT "/.res.lock");
    CHECK(lk != NULL && strcmp(lk, "a user's file") == 0);
    free(lk);
    remove(ROOT "/.res.lock");
}

/* Modes: a new folder 0777 less the umask (022 and 077); a replaced folder keeps its mode. */
static void test_modes(void)
{
    lv_err err;
    lv_outdir *a = NULL;
    const lv_outdir_record ok = {"run", "ok", NULL, 0, NULL};
    const mode_t masks[2] = {022, 077}, want[2] = {0755, 0700};
    for (int i = 0; i < 2; i++) {
        const mode_t old = umask(masks[i]);
        char out[64];
        snprintf(out, sizeof out, ROOT "/mode%d", i);
        CHECK_OK(lv_outdir_begin(out, NULL, 0, &a, &err), &err);
        CHECK_OK(lv_outdir_commit(a, &ok, &err), &err);
        lv_outdir_free(a);
        struct stat sb;
        CHECK(stat(out, &sb) == 0 && (sb.st_mode & 07777) == want[i]);
        umask(old);
    }
    chmod(ROOT "/mode1", 0750);
    const mode_t old = umask(077);
    CHECK_OK(lv_outdir_begin(ROOT "/mode1", NULL, 0, &a, &err), &err);
    CHECK_OK(lv_outdir_commit(a, &ok, &err), &err);
    lv_outdir_free(a);
    umask(old);
    struct stat sb;
    CHECK(stat(ROOT "/mode1", &sb) == 0 && (sb.st_mode & 07777) == 0750);
    /* a read-only results folder: replaced, still read-only, nothing left beside it */
    chmod(ROOT "/mode1", 0555);
    CHECK_OK(lv_outdir_begin(ROOT "/mode1", NULL, 0, &a, &err), &err);
    char path[4200];
    snprintf(path, sizeof path, "%s/summary.json", lv_outdir_path(a));
    put(path, "{}");
    CHECK_OK(lv_outdir_commit(a, &ok, &err), &err);
    lv_outdir_free(a);
    CHECK(stat(ROOT "/mode1", &sb) == 0 && (sb.st_mode & 07777) == 0555);
    CHECK(exists(ROOT "/mode1/summary.json") && count_entries(".mode1.") == 0);
    chmod(ROOT "/mode1", 0755);
}

/* A live folder (lvsim mc): created with its manifest at once, status "incomplete", its live
 * names lvsim's whatever they hold; a user's file of a live name refused even with force;
 * staged, committed, the manifest lists the database. */
static void test_live(void)
{
    lv_err err;
    lv_outdir *a = NULL, *b = NULL;
    const char *dir = ROOT "/mc";
    const char *live[] = {"campaign.db", "runs", NULL};
    CHECK_OK(lv_outdir_open_live(dir, NULL, 0, live, &a, &err), &err);
    CHECK(strcmp(lv_outdir_path(a), dir) == 0);
    char *man = slurp(ROOT "/mc/manifest.json");
    CHECK(man != NULL && strstr(man, "\"incomplete\"") != NULL && strstr(man, "\"campaign.db\"") != NULL);
    free(man);
    CHECK(lv_outdir_open_live(dir, NULL, 0, live, &b, &err) == LV_ERR_INPUT); /* in use */
    put(ROOT "/mc/campaign.db", "rows");
    lv_outdir_free(a); /* killed, say: the folder stays lvsim's */
    put(ROOT "/mc/campaign.db", "more rows");
    CHECK_OK(lv_outdir_open_live(dir, NULL, 0, live, &a, &err), &err);
    CHECK_OK(lv_outdir_stage(a, &err), &err);
    CHECK(strcmp(lv_outdir_path(a), dir) != 0);
    char path[4200];
    snprintf(path, sizeof path, "%s/stats.json", lv_outdir_path(a));
    put(path, "{}");
    const lv_outdir_record ok = {"mc", "ok", NULL, 0, NULL};
    CHECK_OK(lv_outdir_commit(a, &ok, &err), &err);
    CHECK(lv_outdir_file_count(a) == 2);
    lv_outdir_free(a);
    man = slurp(ROOT "/mc/manifest.json");
    CHECK(man != NULL && strstr(man, "\"status\":\t\"ok\"") != NULL &&
          strstr(man, "\"stats.json\"") != NULL);
    free(man);
    /* a user's campaign.db in a user's folder: refused, also with force */
    mkdir(ROOT "/mine2", 0777);
    put(ROOT "/mine2/campaign.db", "not lvsim's");
    CHECK(lv_outdir_open_live(ROOT "/mine2", NULL, LV_OUTDIR_FORCE, live, &a, &err) == LV_ERR_INPUT);
    CHECK(strstr(err.msg, "campaign.db' is not lvsim's") != NULL);
    /* a user's stats.json, a name a campaign writes: refused before the campaign runs, also
     * with force (issue 22's breaker: the whole campaign ran, then the commit refused) */
    put(ROOT "/mine2/stats.json", "mine");
    remove(ROOT "/mine2/campaign.db");
    CHECK(lv_outdir_open_live(ROOT "/mine2", NULL, 0, live, &a, &err) == LV_ERR_INPUT);
    CHECK(lv_outdir_open_live(ROOT "/mine2", NULL, LV_OUTDIR_FORCE, live, &a, &err) ==
          LV_ERR_INPUT);
    CHECK(strstr(err.msg, "mine2/stats.json' is not lvsim's and lvsim must write a file of that "
                          "name") != NULL);
    char *kept = slurp(ROOT "/mine2/stats.json");
    CHECK(kept != NULL && strcmp(kept, "mine") == 0 && !exists(ROOT "/mine2/manifest.json"));
    free(kept);
    /* a user's file of another name, then a result of that name after all: the commit
     * refuses, the user's file stays */
    rename(ROOT "/mine2/stats.json", ROOT "/mine2/notes.csv");
    CHECK_OK(lv_outdir_open_live(ROOT "/mine2", NULL, LV_OUTDIR_FORCE, live, &a, &err), &err);
    CHECK_OK(lv_outdir_stage(a, &err), &err);
    snprintf(path, sizeof path, "%s/notes.csv", lv_outdir_path(a));
    remove(path);
    put(path, "{}");
    CHECK(lv_outdir_commit(a, &ok, &err) == LV_ERR_INPUT); /* would replace the user's */
    lv_outdir_free(a);
    kept = slurp(ROOT "/mine2/notes.csv");
    CHECK(kept != NULL && strcmp(kept, "mine") == 0);
    free(kept);
}

/* The "sha256" of `name` in the manifest text `man` ("" when not listed). */
static const char *listed_sha(const char *man, const char *name, char out[65])
{
    char key[300];
    out[0] = '\0';
    snprintf(key, sizeof key, "\"name\":\t\"%s\"", name);
    const char *e = man != NULL ? strstr(man, key) : NULL;
    const char *h = e != NULL ? strstr(e, "\"sha256\":\t\"") : NULL;
    if (h != NULL && sscanf(h + strlen("\"sha256\":\t\""), "%64[0-9a-f]", out) != 1)
        out[0] = '\0';
    return out;
}

/* Writes `text` to DIR/name through lv_atomic's stream. */
static void put_atomic(const char *dir, const char *name, const char *text)
{
    char path[4200];
    lv_err err;
    lv_atomic a;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    if (lv_atomic_open(&a, path, &err) != LV_OK)
        return;
    fputs(text, a.fp);
    CHECK_OK(lv_atomic_commit(&a, &err), &err);
}

/* Rewrites DIR/name in place with `text` (the same inode); `same_mtime`: its modification
 * time set back to the one before (what no ordinary write does), else set 1 us apart (a write
 * within one tick of the kernel's clock may keep it: made explicit). */
static void rewrite(const char *dir, const char *name, const char *text, int same_mtime)
{
    char path[4200];
    struct stat sb;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    if (stat(path, &sb) != 0)
        return;
    FILE *f = fopen(path, "r+");
    if (f != NULL) {
        fputs(text, f);
        fclose(f);
    }
    struct timespec t[2] = {sb.st_atim, sb.st_mtim};
    if (!same_mtime)
        t[1].tv_nsec = (t[1].tv_nsec + 1000) % 1000000000;
    CHECK(utimensat(AT_FDCWD, path, t, 0) == 0);
}

/* The manifest's digest of a file written through lv_atomic's stream is the one computed as
 * the bytes went out: "abc" (FIPS 180-2 B.1) rewritten in place to "xbc" with its mtime set
 * back is still listed with the digest of "abc" - the file was not read again (what the record
 * trusts, as the old manifest's reuse does: the same inode, size and mtime). Rewritten with
 * another mtime, or written without the stream, or carrying a copied record (another inode),
 * it is read: "xbc" rewritten to "abc" is listed with the digest of "abc". */
static void test_recorded_digest(void)
{
    lv_err err;
    lv_outdir *a = NULL;
    const char *out = ROOT "/rec";
    const char *abc = "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad";
    CHECK_OK(lv_outdir_begin(out, NULL, 0, &a, &err), &err);
    if (a == NULL)
        return;
    const char *st = lv_outdir_path(a);
    put_atomic(st, "as_written.txt", "abc");
    put_atomic(st, "trusted.txt", "abc");
    rewrite(st, "trusted.txt", "x", 1);
    put_atomic(st, "changed.txt", "xbc");
    rewrite(st, "changed.txt", "a", 0);
    char path[4200], from[4200], rec[256];
    snprintf(path, sizeof path, "%s/plain.txt", st);
    put(path, "abc");
    snprintf(from, sizeof from, "%s/as_written.txt", st);
    snprintf(path, sizeof path, "%s/copied.txt", st);
    put(path, "xbc");
    const ssize_t n = lgetxattr(from, LV_ATOMIC_XATTR, rec, sizeof rec);
    CHECK(n > 64 && lsetxattr(path, LV_ATOMIC_XATTR, rec, n > 0 ? (size_t)n : 0, 0) == 0);
    const lv_outdir_record ok = {"run", "ok", NULL, 0, NULL};
    CHECK_OK(lv_outdir_commit(a, &ok, &err), &err);
    lv_outdir_free(a);
    char *man = slurp(ROOT "/rec/manifest.json");
    char h[65], xbc[65];
    unsigned long long bytes = 0;
    CHECK_OK(lv_sha256_file(ROOT "/rec/copied.txt", xbc, &bytes, &err), &err);
    CHECK(strcmp(listed_sha(man, "as_written.txt", h), abc) == 0);
    CHECK(strcmp(listed_sha(man, "trusted.txt", h), abc) == 0);
    CHECK(strcmp(listed_sha(man, "changed.txt", h), abc) == 0);
    CHECK(strcmp(listed_sha(man, "plain.txt", h), abc) == 0);
    CHECK(strcmp(xbc, abc) != 0 && strcmp(listed_sha(man, "copied.txt", h), xbc) == 0);
    free(man);
}

int main(void)
{
    rm_rf(ROOT);
    if (mkdir(ROOT, 0777) != 0 && errno != EEXIST) {
        perror(ROOT);
        return 1;
    }
    test_sha256();
    test_run_folder();
    test_refused();
    test_decoy();
    test_changed_and_in_place();
    test_modes();
    test_live();
    test_recorded_digest();
    rm_rf(ROOT);
    return check_report("test_outdir_api");
}
