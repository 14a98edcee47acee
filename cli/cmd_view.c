/* cmd_view.c - `lvsim view OUTDIR`: the results folder becomes a static site (OUTDIR/viewer/
 * with the CesiumJS page and its assets, ~14 MB) served on 127.0.0.1 by python3's
 * http.server. The viewer is a data file, staged by its own viewer/stage.sh.
 */
#define _POSIX_C_SOURCE 200809L

#include <arpa/inet.h>
#include <errno.h>
#include <netinet/in.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
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

/* A listening TCP socket on 127.0.0.1:port (0: any free port); -1 with errno. */
static int listen_on(int port, int *bound)
{
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    if (fd < 0)
        return -1;
    int one = 1;
    setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    struct sockaddr_in a;
    memset(&a, 0, sizeof a);
    a.sin_family = AF_INET;
    a.sin_port = htons((unsigned short)port);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof a;
    if (bind(fd, (struct sockaddr *)&a, sizeof a) != 0 || listen(fd, 64) != 0 ||
        getsockname(fd, (struct sockaddr *)&a, &len) != 0) {
        const int e = errno;
        close(fd);
        errno = e;
        return -1;
    }
    *bound = ntohs(a.sin_port);
    return fd;
}

/* Python's http.server on the socket lvsim opened (fd 3): no port race, no request log, no
 * traceback at Ctrl-C. argv[1]: the folder served. */
static const char serve_py[] =
    "import functools, http.server, signal, socket, sys\n"
    "signal.signal(signal.SIGINT, signal.default_int_handler)  # also when started ignoring it\n"
    "signal.signal(signal.SIGTERM, lambda *a: sys.exit(0))\n"
    "class Quiet(http.server.SimpleHTTPRequestHandler):\n"
    "    def log_message(self, *args):\n"
    "        pass\n"
    "handler = functools.partial(Quiet, directory=sys.argv[1])\n"
    "srv = http.server.ThreadingHTTPServer(('127.0.0.1', 0), handler, bind_and_activate=False)\n"
    "srv.socket.close()\n"
    "srv.socket = socket.socket(fileno=3)\n"
    "srv.server_name, srv.server_port = srv.socket.getsockname()[:2]\n"
    "try:\n"
    "    srv.serve_forever()\n"
    "except KeyboardInterrupt:\n"
    "    pass\n";

static int view_run(const cli_cmd *self, int argc, char **argv)
{
    const char *dir = NULL;
    int port = 8765, stage_only = 0, port_given = 0;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--port") == 0) {
            const char *v = option_value(argc, argv, &i);
            if (v == NULL || !parse_int(v, &port) || port < 1 || port > 65535)
                return usage_error(self, "--port needs a number from 1 to 65535", NULL);
            port_given = 1;
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
    const int need_czml = !file_exists(dir, "mission.czml"),
              need_viewer = !file_exists(dir, "viewer/VERSION");
    if (need_czml || need_viewer) {
        lv_outdir *od;
        if (lv_outdir_open(dir, &od, &err) != LV_OK)
            return print_err("lvsim view", &err, EXIT_INPUT);
        int code = EXIT_OK;
        const char *stage = lv_outdir_path(od); /* a replica of the folder, see lv_outdir.h */
        if (need_czml && lv_export_run(stage, LV_EXPORT_CZML, &err) != LV_OK) {
            restage(err.msg, sizeof err.msg, stage, lv_outdir_final(od));
            code = print_err("lvsim view", &err, EXIT_INPUT);
        }
        if (code == EXIT_OK && need_viewer) {
            /* the installed (or build tree's) share/lvsim/viewer; stage.sh copies from its
             * folder */
            char script[4200];
            if (lv_data_find(NULL, "viewer/stage.sh", script, sizeof script, &err) != LV_OK) {
                code = print_err("lvsim view", &err, EXIT_INTERNAL);
            } else {
                char *args[] = {script, (char *)stage, NULL}; /* executable, its own #! */
                if (run_program(args) != 0) {
                    fprintf(stderr, "lvsim view: staging the viewer with %s failed\n", script);
                    code = EXIT_INTERNAL;
                }
            }
        }
        const lv_outdir_record rec = {"view", code == EXIT_OK ? "ok" : "failed", NULL, 0, NULL};
        if (lv_outdir_commit(od, &rec, &err) != LV_OK && code == EXIT_OK)
            code = print_err("lvsim view", &err, EXIT_INPUT);
        lv_outdir_free(od);
        if (code != EXIT_OK)
            return code;
    }
    if (stage_only) {
        printf("viewer staged in %s/viewer/ (open with: lvsim view %s)\n", dir, dir);
        return EXIT_OK;
    }
    /* the port: the one asked for, or the default and the next 20, else any free one */
    int bound = 0, fd = -1;
    for (int p = port; fd < 0 && p <= (port_given ? port : port + 20) && p <= 65535; p++)
        fd = listen_on(p, &bound);
    if (fd < 0 && port_given) {
        fprintf(stderr, "lvsim view: port %d on 127.0.0.1 is busy (%s): choose another with "
                        "--port, or leave --port out to take a free one\n", port,
                strerror(errno));
        return EXIT_INPUT;
    }
    if (fd < 0 && (fd = listen_on(0, &bound)) < 0) {
        fprintf(stderr, "lvsim view: cannot listen on 127.0.0.1: %s\n", strerror(errno));
        return EXIT_INTERNAL;
    }
    if (fd != 3) {
        if (dup2(fd, 3) < 0) {
            fprintf(stderr, "lvsim view: %s\n", strerror(errno));
            return EXIT_INTERNAL;
        }
        close(fd);
    }
    if (!port_given && bound != port)
        printf("lvsim view: port %d is busy; using %d\n", port, bound);
    printf("lvsim view: http://127.0.0.1:%d/viewer/  (serving %s; Ctrl-C to stop)\n", bound, dir);
    fflush(stdout);
    char *args[] = {"/usr/bin/python3", "-c", (char *)serve_py, (char *)dir, NULL};
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
    "missing, and serves OUTDIR on http://127.0.0.1:PORT/viewer/ until Ctrl-C (python3;\n"
    "a browser cannot load the viewer's data from a file:// page, hence the server).\n"
    "The viewer is found like any data file: $LVSIM_DATA, else share/lvsim next to the\n"
    "library, else the install prefix (viewer/stage.sh there).\n"
    "\n"
    "options:\n"
    "  --port N                TCP port on 127.0.0.1, 1 to 65535; busy: exit 2 (default\n"
    "                          8765, or the next free one after it)\n"
    "  --stage-only            stage the viewer and return without serving\n",
    view_run,
};
