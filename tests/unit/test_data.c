/* test_data.c - run-time lookup of data files (lvsim/lv_data.h, src/core/data.c): the
 * search order, first match wins, the build tree's share/lvsim found next to the program
 * (this test links lvsim statically), and the error that lists every folder searched. */
#define _XOPEN_SOURCE 700 /* setenv, unsetenv, mkdir, realpath */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "check.h"
#include "core/data.h"

/* LV_BINARY_DIR: the build tree; LV_TEST_INSTALL_DATADIR: what data.c has compiled in. */

static void plant(const char *dir, const char *name, const char *text)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    mkdir(dir, 0755);
    char *slash = strrchr(path, '/');
    *slash = '\0';
    mkdir(path, 0755); /* one level below dir is enough here */
    *slash = '/';
    FILE *fp = fopen(path, "w");
    CHECK(fp != NULL);
    if (fp != NULL) {
        fputs(text, fp);
        fclose(fp);
    }
}

static int same_file(const char *a, const char *b)
{
    char ra[PATH_MAX], rb[PATH_MAX];
    return realpath(a, ra) != NULL && realpath(b, rb) != NULL && strcmp(ra, rb) == 0;
}

static void test_order(void)
{
    lv_data_dirs d;
    unsetenv(LV_DATA_ENV);
    lv_data_dirs_get(NULL, &d);
    /* build/tests/test_data -> build/share/lvsim, then the configured prefix */
    CHECK(d.n == 2);
    CHECK(!d.env_set);
    CHECK(same_file(d.dir[0], LV_BINARY_DIR "/share/lvsim"));
    CHECK(strcmp(d.origin[0], "next to the program") == 0);
    CHECK(strcmp(d.dir[d.n - 1], LV_TEST_INSTALL_DATADIR) == 0);
    CHECK(strcmp(d.origin[d.n - 1], "install prefix") == 0);

    setenv(LV_DATA_ENV, "from-env", 1);
    lv_data_dirs_get("from-arg", &d);
    CHECK(d.n == 4 && d.env_set);
    CHECK(strcmp(d.dir[0], "from-arg") == 0 && strcmp(d.origin[0], "argument") == 0);
    CHECK(strcmp(d.dir[1], "from-env") == 0 && strcmp(d.origin[1], LV_DATA_ENV) == 0);
    CHECK(same_file(d.dir[2], LV_BINARY_DIR "/share/lvsim"));

    /* the same folder twice is searched once; an empty LVSIM_DATA counts as unset */
    lv_data_dirs_get("from-env", &d);
    CHECK(d.n == 3 && strcmp(d.dir[1], "from-env") != 0);
    setenv(LV_DATA_ENV, "", 1);
    lv_data_dirs_get("", &d);
    CHECK(d.n == 2 && !d.env_set);
    unsetenv(LV_DATA_ENV);
}

static void test_find(void)
{
    char path[4096];
    lv_err err;
    plant("test_data_arg", "gravity/x.gfc", "arg\n");
    plant("test_data_env", "gravity/x.gfc", "env\n");
    plant("test_data_env", "viewer/only-env.txt", "env\n");

    setenv(LV_DATA_ENV, "test_data_env", 1);
    CHECK_OK(lv_data_find("test_data_arg", "gravity/x.gfc", path, sizeof path, &err), &err);
    CHECK(strcmp(path, "test_data_arg/gravity/x.gfc") == 0);
    CHECK_OK(lv_data_find(NULL, "gravity/x.gfc", path, sizeof path, &err), &err);
    CHECK(strcmp(path, "test_data_env/gravity/x.gfc") == 0);
    CHECK_OK(lv_data_find("test_data_arg", "viewer/only-env.txt", path, sizeof path, &err), &err);
    CHECK(strcmp(path, "test_data_env/viewer/only-env.txt") == 0);

    /* not in the folders above: the build tree's copy of data/ (cmake/lv_install.cmake) */
    CHECK_OK(lv_data_find("test_data_arg", "gravity/egm2008_n20.gfc", path, sizeof path, &err),
             &err);
    CHECK(same_file(path, LV_BINARY_DIR "/share/lvsim/gravity/egm2008_n20.gfc"));

    /* a folder is not a data file */
    CHECK_FAILS(lv_data_find("test_data_arg", "gravity", path, sizeof path, &err), &err,
                LV_ERR_NOTFOUND, "gravity: lvsim data file not found; searched test_data_arg "
                "(argument), test_data_env (LVSIM_DATA), ");

    /* not found: every folder, with why it was searched */
    CHECK_FAILS(lv_data_find("test_data_arg", "no/such.dat", path, sizeof path, &err), &err,
                LV_ERR_NOTFOUND, "no/such.dat: lvsim data file not found; searched");
    CHECK(strstr(err.msg, "share/lvsim (next to the program)") != NULL);
    CHECK(strstr(err.msg, ", " LV_TEST_INSTALL_DATADIR " (install prefix)") != NULL);
    unsetenv(LV_DATA_ENV);
    CHECK_FAILS(lv_data_find(NULL, "no/such.dat", path, sizeof path, &err), &err,
                LV_ERR_NOTFOUND, "no/such.dat: lvsim data file not found (LVSIM_DATA not set)");
    CHECK(strstr(err.msg, "test_data_env") == NULL && strstr(err.msg, "argument") == NULL);

    /* bad names, no room */
    CHECK_FAILS(lv_data_find(NULL, "", path, sizeof path, &err), &err, LV_ERR_INPUT,
                "relative to the data folder");
    CHECK_FAILS(lv_data_find(NULL, "/etc/passwd", path, sizeof path, &err), &err, LV_ERR_INPUT,
                "'/etc/passwd'");
    char small[16] = "unchanged";
    CHECK_FAILS(lv_data_find("test_data_arg", "gravity/x.gfc", small, sizeof small, &err), &err,
                LV_ERR_INPUT, "test_data_arg/gravity/x.gfc: path longer than 15 characters");
    CHECK(strcmp(small, "unchanged") == 0);

    remove("test_data_arg/gravity/x.gfc");
    remove("test_data_env/gravity/x.gfc");
    remove("test_data_env/viewer/only-env.txt");
}

int main(void)
{
    test_order();
    test_find();
    return check_report("test_data");
}
