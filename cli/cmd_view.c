/* cmd_view.c - `lvsim view OUTDIR`: the results folder becomes a static site (OUTDIR/viewer/
 * with the CesiumJS page and its assets, ~14 MB) served on 127.0.0.1 by python3's
 * http.server. The viewer is a data file, staged by its own viewer/stage.sh.
 */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli.h"
#include "common.h"

/* Runs args[0] with args and waits; returns its exit status, or -1. */
static int run_program(char *const *args)
{
    pid_t pid = fork();
    if (pid < 0)
        return -1;
    if (pid == 0) {
        execv(args[0], args);
        _exit(127);
    }
    int status;
    if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status))
        return -1;
    return WEXITSTATUS(status);
}

static int file_exists(const char *dir, const char *name)
{
    char path[4200];
    struct stat sb;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return stat(path, &sb) == 0;
}

static int view_run(const cli_cmd *self, int argc, char **argv)
{
    const char *dir = NULL;
    int port = 8765, stage_only = 0;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--port") == 0) {
            const char *v = option_value(argc, argv, &i);
            if (v == NULL || !parse_int(v, &port) || port < 1 || port > 65535)
                return usage_error(self, "--port needs a number from 1 to 65535", NULL);
        } else if (strcmp(a, "--stage-only") == 0) {
            stage_only = 1;
        } else if (is_option(a)) {
            return usage_error(self, "unknown option", a);
        } else if (dir != NULL) {
            return usage_error(self, "unexpected argument", a);
        } else {
            dir = a;
        }
    }
    if (dir == NULL)
        return usage_error(self, "view needs a results folder (lvsim run -o OUTDIR)", NULL);
    if (!file_exists(dir, "summary.json")) {
        fprintf(stderr, "lvsim view: %s/summary.json not found: run a mission first "
                        "(lvsim run MISSION.yaml -o %s)\n", dir, dir);
        return EXIT_INPUT;
    }
    lv_err err;
    if (!file_exists(dir, "mission.czml") && lv_export_run(dir, LV_EXPORT_CZML, &err) != LV_OK)
        return print_err("lvsim view", &err, EXIT_INPUT);
    if (!file_exists(dir, "viewer/VERSION")) {
        /* the installed (or build tree's) share/lvsim/viewer; stage.sh copies from its folder */
        char script[4200];
        if (lv_data_find(NULL, "viewer/stage.sh", script, sizeof script, &err) != LV_OK)
            return print_err("lvsim view", &err, EXIT_INTERNAL);
        char *args[] = {script, (char *)dir, NULL}; /* executable, with its own #! */
        if (run_program(args) != 0) {
            fprintf(stderr, "lvsim view: staging the viewer with %s failed\n", script);
            return EXIT_INTERNAL;
        }
    }
    if (stage_only) {
        printf("viewer staged in %s/viewer/ (open with: lvsim view %s)\n", dir, dir);
        return EXIT_OK;
    }
    char port_s[16];
    snprintf(port_s, sizeof port_s, "%d", port);
    printf("lvsim view: http://127.0.0.1:%d/viewer/  (serving %s; Ctrl-C to stop)\n", port, dir);
    fflush(stdout);
    char *args[] = {"/usr/bin/python3", "-m", "http.server", "--bind", "127.0.0.1", port_s,
                    "--directory", (char *)dir, NULL};
    execv(args[0], args);
    fprintf(stderr, "lvsim view: cannot start %s: %s\n", args[0], strerror(errno));
    return EXIT_INTERNAL;
}

const cli_cmd cli_cmd_view = {
    "view",
    "3-D globe view of a results folder (CesiumJS, offline) on 127.0.0.1",
    "OUTDIR [--port N] [--stage-only]",
    "Stages the 3-D viewer into OUTDIR/viewer/ (the CesiumJS page and assets, ~14 MB; the\n"
    "folder is then a static site that can be shared), writes OUTDIR/mission.czml if it is\n"
    "missing, and serves OUTDIR on http://127.0.0.1:PORT/viewer/ until Ctrl-C (python3).\n"
    "The viewer is found like any data file: $LVSIM_DATA, else share/lvsim next to the\n"
    "library, else the install prefix (viewer/stage.sh there).\n"
    "\n"
    "options:\n"
    "  --port N                TCP port on 127.0.0.1, 1 to 65535 (default 8765)\n"
    "  --stage-only            stage the viewer and return without serving\n",
    view_run,
};
