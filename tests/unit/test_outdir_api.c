/* test_outdir_api.c - lv_outdir (include/lvsim/lv_outdir.h) through its API, in one process:
 * a new folder appears only at commit, with its manifest; a second writer is refused while
 * the first holds the lock (flock locks open files, so even in one process); a folder lvsim
 * did not write, a file, "", "." are refused and left alone; a stale staging folder is
 * removed and reported; -o reused leaves nothing of the earlier run; an uncommitted folder
 * leaves OUTDIR as it was; an in-place update adds to the manifest's history. SHA-256 against
 * the FIPS 180-4 examples ("abc", the empty message). The CLI's behaviour (concurrent
 * processes, kill -9) is tests/cli/test_outdir.sh. */
#define _POSIX_C_SOURCE 200809L

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
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
    CHECK_OK(lv_outdir_begin(out, ROOT "/m.yaml", &a, &err), &err);
    if (a == NULL)
        return;
    /* writing goes to a staging folder beside OUTDIR; OUTDIR does not exist yet */
    const char *stage = lv_outdir_path(a);
    CHECK(strncmp(stage, ROOT "/.out.staging-", strlen(ROOT "/.out.staging-")) == 0);
    CHECK(exists(stage) && !exists(out) && exists(ROOT "/.out.lock"));
    /* a second writer is refused at once, naming the folder */
    CHECK(lv_outdir_begin(out, NULL, &b, &err) == LV_ERR_INPUT && b == NULL);
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
    CHECK_OK(lv_outdir_begin(out, NULL, &a, &err), &err);
    lv_outdir_free(a);
    CHECK(exists(ROOT "/out/phase_1_a.csv") && count_entries(".out.staging-") == 0);

    /* -o reused: the folder is replaced, nothing of the earlier run remains */
    CHECK_OK(lv_outdir_begin(ROOT "/out/", NULL, &a, &err), &err); /* trailing slash: the same */
    snprintf(path, sizeof path, "%s/phase_1_b.csv", lv_outdir_path(a));
    put(path, "time [s]\n");
    const lv_outdir_record ok = {"run", "ok", NULL, 0, NULL};
    CHECK_OK(lv_outdir_commit(a, &ok, &err), &err);
    lv_outdir_free(a);
    CHECK(exists(ROOT "/out/phase_1_b.csv") && !exists(ROOT "/out/phase_1_a.csv"));

    /* a stale staging folder of a killed run is removed and reported */
    mkdir(ROOT "/.out.staging-Ab12Cd", 0777);
    put(ROOT "/.out.staging-Ab12Cd/phase_9_x.csv.tmp", "half");
    CHECK_OK(lv_outdir_begin(out, NULL, &a, &err), &err);
    CHECK(lv_outdir_stale_count(a) == 1 && strcmp(lv_outdir_stale(a, 0), ".out.staging-Ab12Cd") == 0);
    CHECK(!exists(ROOT "/.out.staging-Ab12Cd"));
    lv_outdir_free(a);

    /* in place (export, plot, view): the manifest keeps its run and gains a history entry */
    CHECK_OK(lv_outdir_open(out, &a, &err), &err);
    CHECK(strcmp(lv_outdir_path(a), out) == 0);
    put(ROOT "/out/mission.kml", "<kml/>");
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
    CHECK(lv_outdir_begin("", NULL, &a, &err) == LV_ERR_INPUT && a == NULL);
    CHECK(strstr(err.msg, "name is empty") != NULL);
    CHECK(lv_outdir_begin(".", NULL, &a, &err) == LV_ERR_INPUT && a == NULL);
    CHECK(strstr(err.msg, "cannot be a results folder") != NULL);
    put(ROOT "/file", "x");
    CHECK(lv_outdir_begin(ROOT "/file", NULL, &a, &err) == LV_ERR_INPUT);
    CHECK(strstr(err.msg, "'" ROOT "/file' is a file, not a folder") != NULL);
    CHECK(lv_outdir_begin(ROOT "/file/sub", NULL, &a, &err) == LV_ERR_INPUT);
    mkdir(ROOT "/mine", 0777);
    put(ROOT "/mine/notes.txt", "keep");
    CHECK(lv_outdir_begin(ROOT "/mine", NULL, &a, &err) == LV_ERR_INPUT);
    CHECK(strstr(err.msg, "holds files lvsim did not write") != NULL);
    char *kept = slurp(ROOT "/mine/notes.txt");
    CHECK(kept != NULL && strcmp(kept, "keep") == 0);
    free(kept);
    CHECK(count_entries(".mine.") == 0 && count_entries(".file.") == 0); /* no lock left */
    CHECK(lv_outdir_begin(ROOT "/new", ROOT "/no-such-mission.yaml", &a, &err) == LV_ERR_IO);
    CHECK(!exists(ROOT "/new") && count_entries(".new.") == 0);
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
    rm_rf(ROOT);
    return check_report("test_outdir_api");
}
