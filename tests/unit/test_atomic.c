/* test_atomic.c - src/io/atomic.c: "<path>.tmp" written, then renamed; a reader never finds half
 * a file under the final name. Works in atomic_out/ of the test directory. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "core/status.h"
#include "io/atomic.h"

#define OUT "atomic_out"

static int exists(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0;
}

/* The file's text (at most cap - 1 bytes), "" when it cannot be read. */
static const char *text_of(const char *path, char *buf, size_t cap)
{
    buf[0] = '\0';
    FILE *f = fopen(path, "r");
    if (f == NULL)
        return buf;
    const size_t n = fread(buf, 1, cap - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (f != NULL) {
        fputs(text, f);
        fclose(f);
    }
}

/* A complete file replaces the old one only at commit; until then the old one is intact. */
static void test_commit_replaces(void)
{
    char buf[256];
    lv_err err = {0};
    lv_atomic a;
    write_text(OUT "/doc.txt", "old\n");
    CHECK_OK(lv_atomic_open(&a, OUT "/doc.txt", &err), &err);
    CHECK(strcmp(a.path, OUT "/doc.txt") == 0 && strcmp(a.tmp, OUT "/doc.txt.tmp") == 0);
    fputs("new text\n", a.fp);
    fflush(a.fp);
    CHECK(exists(OUT "/doc.txt.tmp"));
    CHECK(strcmp(text_of(OUT "/doc.txt", buf, sizeof buf), "old\n") == 0);
    CHECK_OK(lv_atomic_commit(&a, &err), &err);
    CHECK(a.fp == NULL);
    CHECK(strcmp(text_of(OUT "/doc.txt", buf, sizeof buf), "new text\n") == 0);
    CHECK(!exists(OUT "/doc.txt.tmp"));
}

/* abort removes the temporary file and leaves the old final file alone. */
static void test_abort(void)
{
    char buf[256];
    lv_err err = {0};
    lv_atomic a;
    write_text(OUT "/kept.txt", "complete\n");
    CHECK_OK(lv_atomic_open(&a, OUT "/kept.txt", &err), &err);
    fputs("half", a.fp);
    lv_atomic_abort(&a);
    CHECK(a.fp == NULL && !exists(OUT "/kept.txt.tmp"));
    CHECK(strcmp(text_of(OUT "/kept.txt", buf, sizeof buf), "complete\n") == 0);
    lv_atomic_abort(&a); /* twice: nothing left to do */
    lv_atomic zero;
    memset(&zero, 0, sizeof zero);
    lv_atomic_abort(&zero);
    lv_atomic_release(&zero);
    lv_atomic_abort(NULL);
    lv_atomic_release(NULL);
}

/* release closes the stream and leaves the temporary file as it is. */
static void test_release(void)
{
    char buf[256];
    lv_err err = {0};
    lv_atomic a;
    remove(OUT "/left.txt");
    CHECK_OK(lv_atomic_open(&a, OUT "/left.txt", &err), &err);
    fputs("rows so far\n", a.fp);
    lv_atomic_release(&a);
    CHECK(a.fp == NULL && !exists(OUT "/left.txt"));
    CHECK(strcmp(text_of(OUT "/left.txt.tmp", buf, sizeof buf), "rows so far\n") == 0);
    remove(OUT "/left.txt.tmp");
}

/* A writer that takes a file name: init + reserve, it writes tmp, commit_as another name. */
static void test_by_name(void)
{
    char buf[256];
    lv_err err = {0};
    lv_atomic a;
    remove(OUT "/run.mat");
    remove(OUT "/run.failed.mat");
    CHECK_OK(lv_atomic_init(&a, OUT "/run.mat", &err), &err);
    CHECK(a.fp == NULL && a.keep == 0 && !exists(a.tmp));
    CHECK_OK(lv_atomic_reserve(&a, &err), &err);
    CHECK(exists(OUT "/run.mat.tmp"));
    write_text(a.tmp, "by name\n");
    CHECK_OK(lv_atomic_commit_as(&a, OUT "/run.failed.mat", &err), &err);
    CHECK(strcmp(text_of(OUT "/run.failed.mat", buf, sizeof buf), "by name\n") == 0);
    CHECK(!exists(OUT "/run.mat") && !exists(OUT "/run.mat.tmp"));
}

/* lvsim's temporary file never replaces a file: an existing "<path>.tmp" (a user's) is left
 * as it is and another name taken; a file replaced through a hard link (a staging replica of
 * a results folder) leaves the other name's data as it was. */
static void test_never_truncates(void)
{
    char buf[256];
    lv_err err = {0};
    lv_atomic a;
    write_text(OUT "/user.txt.tmp", "the user's own file\n");
    CHECK_OK(lv_atomic_open(&a, OUT "/user.txt", &err), &err);
    CHECK(strcmp(a.tmp, OUT "/user.txt.tmp") != 0 &&
          strncmp(a.tmp, OUT "/user.txt.tmp.", strlen(OUT "/user.txt.tmp.")) == 0);
    fputs("lvsim's\n", a.fp);
    CHECK_OK(lv_atomic_commit(&a, &err), &err);
    CHECK(strcmp(text_of(OUT "/user.txt.tmp", buf, sizeof buf), "the user's own file\n") == 0);
    CHECK(strcmp(text_of(OUT "/user.txt", buf, sizeof buf), "lvsim's\n") == 0);
    CHECK(!exists(a.tmp));
    /* by name (init + reserve), the same */
    CHECK_OK(lv_atomic_init(&a, OUT "/user.txt", &err), &err);
    CHECK_OK(lv_atomic_reserve(&a, &err), &err);
    CHECK(strcmp(a.tmp, OUT "/user.txt.tmp") != 0);
    lv_atomic_abort(&a);
    CHECK(strcmp(text_of(OUT "/user.txt.tmp", buf, sizeof buf), "the user's own file\n") == 0);
    remove(OUT "/user.txt.tmp");
    remove(OUT "/user.txt");
    /* a hard link replaced: the other name keeps its data */
    mkdir(OUT "/replica", 0777);
    write_text(OUT "/orig.txt", "original\n");
    remove(OUT "/replica/orig.txt");
    CHECK(link(OUT "/orig.txt", OUT "/replica/orig.txt") == 0);
    CHECK_OK(lv_atomic_open(&a, OUT "/replica/orig.txt", &err), &err);
    fputs("replaced\n", a.fp);
    CHECK_OK(lv_atomic_commit(&a, &err), &err);
    CHECK(strcmp(text_of(OUT "/orig.txt", buf, sizeof buf), "original\n") == 0);
    CHECK(strcmp(text_of(OUT "/replica/orig.txt", buf, sizeof buf), "replaced\n") == 0);
}

/* lv_strerror, the one helper of every system error message: the C library's text (glibc,
 * C locale; POSIX names the errors, glibc's string.h the texts), never "error 13" for a value
 * it knows; its buffer bounded. */
static void test_strerror(void)
{
    char buf[LV_STRERROR_MAX], tiny[4];
    CHECK(strcmp(lv_strerror(EACCES, buf, sizeof buf), "Permission denied") == 0);
    CHECK(strcmp(lv_strerror(ENOENT, buf, sizeof buf), "No such file or directory") == 0);
    CHECK(strcmp(LV_STRERROR(ENOTDIR), "Not a directory") == 0);
    CHECK(strlen(lv_strerror(EACCES, tiny, sizeof tiny)) < sizeof tiny);
    CHECK(strcmp(lv_strerror(EACCES, buf, 0), "") == 0);
}

/* Errors name the temporary file and the system's reason. */
static void test_errors(void)
{
    lv_err err = {0};
    lv_atomic a;
    CHECK_FAILS(lv_atomic_open(&a, OUT "/no_such_dir/x.txt", &err), &err, LV_ERR_IO,
                OUT "/no_such_dir/x.txt.tmp: cannot create: No such file or directory");
    CHECK(a.fp == NULL);
    CHECK_FAILS(lv_atomic_init(&a, "", &err), &err, LV_ERR_INPUT, "empty path");
    CHECK_FAILS(lv_atomic_init(&a, NULL, &err), &err, LV_ERR_INPUT, "empty path");
    char *huge = malloc(LV_ATOMIC_PATH_MAX + 10);
    if (huge != NULL) {
        memset(huge, 'a', LV_ATOMIC_PATH_MAX + 9);
        huge[LV_ATOMIC_PATH_MAX + 9] = '\0';
        CHECK_FAILS(lv_atomic_open(&a, huge, &err), &err, LV_ERR_INPUT, "too long");
        free(huge);
    }
    CHECK_FAILS(lv_atomic_init(&a, OUT "/no_such_dir/y.mat", &err) == LV_OK
                    ? lv_atomic_reserve(&a, &err)
                    : LV_ERR_INPUT,
                &err, LV_ERR_IO, OUT "/no_such_dir/y.mat.tmp: cannot create");

    /* The final name is a non-empty directory: the rename fails. keep = 0 removes the
     * temporary file, keep = 1 leaves it. */
    mkdir(OUT "/busy", 0777);
    write_text(OUT "/busy/inside", "x");
    for (int keep = 0; keep <= 1; keep++) {
        CHECK_OK(lv_atomic_open(&a, OUT "/busy", &err), &err);
        a.keep = keep;
        fputs("complete", a.fp);
        CHECK_FAILS(lv_atomic_commit(&a, &err), &err, LV_ERR_IO,
                    OUT "/busy.tmp: cannot rename to '" OUT "/busy': ");
        CHECK(a.fp == NULL && exists(OUT "/busy.tmp") == keep);
        remove(OUT "/busy.tmp");
    }

    /* A write that cannot reach the disk (file size limit): "cannot write", the reason, and
     * neither the final nor the temporary file remains. */
    struct rlimit old;
    if (getrlimit(RLIMIT_FSIZE, &old) == 0) {
        void (*old_handler)(int) = signal(SIGXFSZ, SIG_IGN);
        remove(OUT "/big.txt");
        CHECK_OK(lv_atomic_open(&a, OUT "/big.txt", &err), &err);
        struct rlimit small = old;
        small.rlim_cur = 1000;
        setrlimit(RLIMIT_FSIZE, &small);
        for (int i = 0; i < 500; i++)
            fprintf(a.fp, "line %d of a file larger than the limit\n", i);
        lv_status st = lv_atomic_commit(&a, &err);
        setrlimit(RLIMIT_FSIZE, &old);
        signal(SIGXFSZ, old_handler);
        CHECK(st == LV_ERR_IO && strstr(err.msg, OUT "/big.txt.tmp: cannot write: ") != NULL &&
              strstr(err.msg, "too large") != NULL);
        CHECK(!exists(OUT "/big.txt") && !exists(OUT "/big.txt.tmp"));
    }
}

int main(void)
{
    mkdir(OUT, 0777);
    test_commit_replaces();
    test_abort();
    test_release();
    test_by_name();
    test_never_truncates();
    test_strerror();
    test_errors();
    return check_report("test_atomic");
}
