/* test_atomic.c - src/io/atomic.c: "<path>.tmp" written, then renamed; a reader never finds half
 * a file under the final name; the stream's SHA-256, computed as the bytes are written, against
 * the FIPS 180-2 examples, and its record (lv_atomic_digest) valid only for the same file
 * unchanged. Works in atomic_out/ of the test directory. */
#define _GNU_SOURCE /* lgetxattr, lsetxattr */

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/xattr.h>
#include <time.h>
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

/* ---- the digest --------------------------------------------------------------------------- */

/* FIPS 180-2 (2002), Appendix B: SHA-256 of "abc" (B.1), of the 448-bit two-block message
 * (B.2) and of one million 'a' (B.3); the empty message: NIST CAVP SHA256ShortMsg.rsp, Len = 0. */
#define SHA_ABC "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
#define MSG_448 "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"
#define SHA_448 "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1"
#define SHA_MILLION_A "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0"
#define SHA_EMPTY "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"

/* The record on `path` is lv_atomic's and names `sha` for the file as it is now. */
static int recorded(const char *path, const char *sha)
{
    struct stat sb;
    char hex[65];
    return lstat(path, &sb) == 0 && lv_atomic_digest(path, &sb, hex) && strcmp(hex, sha) == 0;
}

/* `msg` (n bytes) written through the stream in pieces of the sizes `cut` (cycled; fwrite,
 * with fputc for pieces of 1 byte), committed to `path`: a.sha256 and the record. */
static void write_cut(const char *path, const char *msg, size_t n, const size_t *cut,
                      size_t n_cut, const char *sha)
{
    lv_err err = {0};
    lv_atomic a;
    remove(path);
    CHECK_OK(lv_atomic_open(&a, path, &err), &err);
    if (a.fp == NULL)
        return;
    size_t at = 0;
    for (size_t k = 0; at < n; k++) {
        size_t len = cut[k % n_cut];
        if (len > n - at)
            len = n - at;
        if (len == 1)
            fputc(msg[at], a.fp);
        else
            fwrite(msg + at, 1, len, a.fp);
        if (k % 7 == 3)
            CHECK(ftell(a.fp) == (long)(at + len)); /* a tell is no seek: the digest stays */
        at += len;
    }
    CHECK_OK(lv_atomic_commit(&a, &err), &err);
    if (strcmp(a.sha256, sha) != 0)
        fprintf(stderr, "%s: %s, want %s\n", path, a.sha256, sha);
    CHECK(strcmp(a.sha256, sha) == 0);
    CHECK(recorded(path, sha));
}

static void test_digest_vectors(void)
{
    static const size_t odd[] = {1, 63, 64, 65, 4097, 1, 65535, 65536, 65537, 100003, 127};
    static const size_t ones[] = {1};
    static const size_t big[] = {1 << 20};
    write_cut(OUT "/abc.txt", "abc", 3, odd, 11, SHA_ABC);
    write_cut(OUT "/abc1.txt", "abc", 3, ones, 1, SHA_ABC);
    write_cut(OUT "/m448.txt", MSG_448, strlen(MSG_448), odd, 11, SHA_448);
    write_cut(OUT "/m448b.txt", MSG_448, strlen(MSG_448), ones, 1, SHA_448);
    write_cut(OUT "/empty.txt", "", 0, odd, 11, SHA_EMPTY);
    char *million = malloc(1000000);
    if (million != NULL) {
        memset(million, 'a', 1000000);
        write_cut(OUT "/million.txt", million, 1000000, odd, 11, SHA_MILLION_A);
        write_cut(OUT "/million1.txt", million, 1000000, big, 1, SHA_MILLION_A);
        free(million);
    }
    /* fprintf through the stream, as the exports write */
    lv_err err = {0};
    lv_atomic a;
    remove(OUT "/printf.txt");
    CHECK_OK(lv_atomic_open(&a, OUT "/printf.txt", &err), &err);
    fprintf(a.fp, "%s%c%s", "abcdbcdecdefdefgefgh", 'f', "ghighijhijkijkljklmklmnlmnomnopnopq");
    CHECK_OK(lv_atomic_commit(&a, &err), &err);
    CHECK(strcmp(a.sha256, SHA_448) == 0 && recorded(OUT "/printf.txt", SHA_448));
}

/* A writer that seeks and rewrites (the MAT sink patches its header at close): the digest is
 * of the file as it is at commit, hashed from the open descriptor; so is a file with a hole
 * written at its end and one rewritten through a seek back to 0 then forth to the end. */
static void test_digest_seek(void)
{
    lv_err err = {0};
    lv_atomic a;
    remove(OUT "/patched.txt");
    CHECK_OK(lv_atomic_open(&a, OUT "/patched.txt", &err), &err);
    fputs("xbcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopQ", a.fp);
    fseek(a.fp, 0, SEEK_SET);
    fputc('a', a.fp);
    fseek(a.fp, -1, SEEK_END);
    fputc('q', a.fp);
    CHECK_OK(lv_atomic_commit(&a, &err), &err);
    CHECK(strcmp(a.sha256, SHA_448) == 0 && recorded(OUT "/patched.txt", SHA_448));

    /* the same, announced (the MAT sink): hashed once, at commit */
    remove(OUT "/patched2.txt");
    CHECK_OK(lv_atomic_open(&a, OUT "/patched2.txt", &err), &err);
    lv_atomic_hash_at_commit(&a);
    fputs("xbcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq", a.fp);
    fseek(a.fp, 0, SEEK_SET);
    fputc('a', a.fp);
    CHECK_OK(lv_atomic_commit(&a, &err), &err);
    CHECK(strcmp(a.sha256, SHA_448) == 0 && recorded(OUT "/patched2.txt", SHA_448));
    /* announced, and not patched after all: the same digest */
    remove(OUT "/plain2.txt");
    CHECK_OK(lv_atomic_open(&a, OUT "/plain2.txt", &err), &err);
    lv_atomic_hash_at_commit(&a);
    fputs("abc", a.fp);
    CHECK_OK(lv_atomic_commit(&a, &err), &err);
    CHECK(strcmp(a.sha256, SHA_ABC) == 0 && recorded(OUT "/plain2.txt", SHA_ABC));

    /* a seek that moves nowhere (to the end, before writing on) keeps the running digest */
    remove(OUT "/nowhere.txt");
    CHECK_OK(lv_atomic_open(&a, OUT "/nowhere.txt", &err), &err);
    fputs("ab", a.fp);
    fseek(a.fp, 0, SEEK_END);
    fputs("c", a.fp);
    CHECK_OK(lv_atomic_commit(&a, &err), &err);
    CHECK(strcmp(a.sha256, SHA_ABC) == 0 && recorded(OUT "/nowhere.txt", SHA_ABC));

    /* a hole: "ab", 1 byte skipped (a zero), then "c": not "abc" */
    remove(OUT "/hole.txt");
    CHECK_OK(lv_atomic_open(&a, OUT "/hole.txt", &err), &err);
    fputs("ab", a.fp);
    fseek(a.fp, 1, SEEK_CUR);
    fputs("c", a.fp);
    CHECK_OK(lv_atomic_commit(&a, &err), &err);
    CHECK(a.sha256[0] != '\0' && strcmp(a.sha256, SHA_ABC) != 0);
    struct stat sb;
    CHECK(stat(OUT "/hole.txt", &sb) == 0 && sb.st_size == 4);
}

/* The record holds for the file as lvsim closed it, and only for it: a hard link (a replica)
 * is the same file; a byte appended, the same size rewritten with another mtime, a copy (another
 * inode, even with the record copied) are not. Nothing is recorded for a stream released or
 * aborted, nor for a file a library wrote by name. */
static void test_digest_identity(void)
{
    lv_err err = {0};
    lv_atomic a;
    const size_t one[] = {1};
    write_cut(OUT "/id.txt", "abc", 3, one, 1, SHA_ABC);
    remove(OUT "/id-link.txt");
    CHECK(link(OUT "/id.txt", OUT "/id-link.txt") == 0);
    CHECK(recorded(OUT "/id-link.txt", SHA_ABC));

    /* a copy carrying the record (cp --preserve=xattr): another inode, not believed */
    char rec[256];
    const ssize_t n = lgetxattr(OUT "/id.txt", LV_ATOMIC_XATTR, rec, sizeof rec);
    CHECK(n > 64 && strncmp(rec, SHA_ABC " 3 ", strlen(SHA_ABC " 3 ")) == 0);
    write_text(OUT "/id-copy.txt", "abc");
    if (n > 0)
        CHECK(lsetxattr(OUT "/id-copy.txt", LV_ATOMIC_XATTR, rec, (size_t)n, 0) == 0);
    CHECK(!recorded(OUT "/id-copy.txt", SHA_ABC));

    /* rewritten in place, the same size: the mtime differs (set apart explicitly: the kernel's
     * clock may not tick between two writes) */
    struct stat sb;
    CHECK(stat(OUT "/id.txt", &sb) == 0);
    write_text(OUT "/id-link.txt", "xyz");
    struct timespec t[2] = {sb.st_atim, sb.st_mtim};
    t[1].tv_nsec = (t[1].tv_nsec + 1000) % 1000000000;
    CHECK(utimensat(AT_FDCWD, OUT "/id.txt", t, 0) == 0);
    CHECK(!recorded(OUT "/id.txt", SHA_ABC));

    /* a byte appended: another size */
    write_cut(OUT "/id2.txt", "abc", 3, one, 1, SHA_ABC);
    FILE *f = fopen(OUT "/id2.txt", "a");
    if (f != NULL) {
        fputc('d', f);
        fclose(f);
    }
    CHECK(!recorded(OUT "/id2.txt", SHA_ABC));

    /* released (a sink destroyed without close) or aborted: no digest, no record */
    remove(OUT "/rel.txt.tmp");
    CHECK_OK(lv_atomic_open(&a, OUT "/rel.txt", &err), &err);
    fputs("abc", a.fp);
    lv_atomic_release(&a);
    CHECK(a.sha256[0] == '\0' && a.stream == NULL && !recorded(OUT "/rel.txt.tmp", SHA_ABC));
    remove(OUT "/rel.txt.tmp");

    /* by name: the library's bytes are not the stream's */
    CHECK_OK(lv_atomic_init(&a, OUT "/lib.txt", &err), &err);
    CHECK_OK(lv_atomic_reserve(&a, &err), &err);
    write_text(a.tmp, "abc");
    CHECK_OK(lv_atomic_commit(&a, &err), &err);
    CHECK(a.sha256[0] == '\0' && !recorded(OUT "/lib.txt", SHA_ABC));
    char hex[65];
    CHECK(stat(OUT "/lib.txt", &sb) == 0 && !lv_atomic_digest(OUT "/lib.txt", &sb, hex));
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
    test_digest_vectors();
    test_digest_seek();
    test_digest_identity();
    return check_report("test_atomic");
}
