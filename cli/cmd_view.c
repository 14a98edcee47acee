/* cmd_view.c - `lvsim view OUTDIR`: the results folder becomes a static site (OUTDIR/viewer/
 * with the CesiumJS page and its assets, ~14 MB) served on 127.0.0.1 by python3's
 * http.server (behind a token, a Host check and the folder's real path: serve_py). The
 * viewer is a data file, staged by its own viewer/stage.sh.
 */
#define _POSIX_C_SOURCE 200809L

#include <arpa/inet.h>
#include <errno.h>
#include <netinet/in.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/random.h>
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

/* The URL's token: 128 bits from the kernel's random source, in hex (33 bytes with the NUL);
 * -1 with errno. */
static int make_token(char hex[33])
{
    unsigned char b[16];
    size_t got = 0;
    while (got < sizeof b) {
        const ssize_t n = getrandom(b + got, sizeof b - got, 0);
        if (n < 0 && errno != EINTR)
            return -1;
        if (n > 0)
            got += (size_t)n;
    }
    for (size_t i = 0; i < sizeof b; i++)
        snprintf(hex + 2 * i, 3, "%02x", b[i]);
    return 0;
}

/* The server: Python's http.server (a well-kept library; /usr/bin/python3 is already a
 * dependency) on the socket lvsim opened (fd 3: no port race), with a handler of its own,
 * because SimpleHTTPRequestHandler answers any Host header (a web page the user visits could
 * read the results through DNS rebinding), lists folders and follows symlinks out of the
 * folder. This one, read-only (GET and HEAD; any other method: 501, http.server's own answer):
 *  - the Host header must be 127.0.0.1:PORT or localhost:PORT, exactly one (else 421);
 *  - the first path segment must be the token (else 403, naming no file): 128 random bits
 *    from lvsim, given in the environment (the command line is readable by every local user,
 *    who can reach 127.0.0.1 too), so the pages' relative URLs (viewer/index.html ->
 *    cesium/..., ../mission.czml, ../summary.json; the report's viewer/index.html) keep it;
 *  - the rest, percent-decoded segment by segment: no '.', '..', empty segment (but a
 *    trailing slash), encoded '/' or NUL; the real path (symlinks resolved) must lie under
 *    the folder's real path, and only a regular file is served (opened O_NOFOLLOW and
 *    O_NONBLOCK: a FIFO cannot hold a thread); a folder gives its index.html, never a
 *    listing (404 without one), and one without its trailing slash a redirect;
 *  - no request log, no traceback at Ctrl-C, no Referer carrying the token elsewhere.
 * argv[1]: the folder served; $LVSIM_VIEW_TOKEN: the token. python3 -I -B: no module from
 * the working folder or PYTHON* variables, no .pyc written. */
static const char serve_py[] =
    "import hmac, http.server, os, signal, socket, stat, sys, urllib.parse\n"
    "signal.signal(signal.SIGINT, signal.default_int_handler)  # also when started ignoring it\n"
    "signal.signal(signal.SIGTERM, lambda *a: sys.exit(0))\n"
    "ROOT = os.path.realpath(sys.argv[1])\n"
    "TOKEN = os.environ.pop('LVSIM_VIEW_TOKEN').encode('ascii')\n"
    "sock = socket.socket(fileno=3)\n"
    "PORT = sock.getsockname()[1]\n"
    "HOSTS = {'127.0.0.1:%d' % PORT, 'localhost:%d' % PORT}\n"
    "if PORT == 80:\n"
    "    HOSTS |= {'127.0.0.1', 'localhost'}\n"
    "def inside(real):\n"
    "    return os.path.commonpath([ROOT, real]) == ROOT\n"
    "class Handler(http.server.SimpleHTTPRequestHandler):\n"
    "    def version_string(self):\n"
    "        return 'lvsim-view'\n"
    "    error_content_type = 'text/plain; charset=utf-8'\n"
    "    error_message_format = '%(code)d %(message)s\\n'\n"
    "    timeout = 60\n"
    "    def log_message(self, *args):\n"
    "        pass\n"
    "    def end_headers(self):\n"
    "        self.send_header('Referrer-Policy', 'no-referrer')\n"
    "        self.send_header('X-Content-Type-Options', 'nosniff')\n"
    "        super().end_headers()\n"
    "    def send_head(self):\n"
    "        host = self.headers.get_all('Host') or []\n"
    "        if len(host) != 1 or host[0].strip().lower() not in HOSTS:\n"
    "            return self.send_error(421, 'answers only to the URL lvsim view printed')\n"
    "        target, _, query = self.path.partition('#')[0].partition('?')\n"
    "        segs = target.split('/')\n"
    "        if (len(segs) < 2 or segs[0] != ''\n"
    "                or not hmac.compare_digest(segs[1].encode('latin-1'), TOKEN)):\n"
    "            return self.send_error(403, 'open the URL lvsim view printed: it has the token')\n"
    "        names = []\n"
    "        for i, s in enumerate(segs[2:], 3):\n"
    "            b = urllib.parse.unquote_to_bytes(s)\n"
    "            if ((b == b'' and i != len(segs)) or b in (b'.', b'..') or b'/' in b\n"
    "                    or b'\\0' in b):\n"
    "                return self.send_error(404, 'not found')\n"
    "            names.append(os.fsdecode(b))\n"
    "        real = os.path.realpath(os.path.join(ROOT, *names))\n"
    "        if not inside(real):\n"
    "            return self.send_error(404, 'not found')\n"
    "        if os.path.isdir(real):\n"
    "            if not target.endswith('/'):\n"
    "                self.send_response(301)\n"
    "                self.send_header('Location', target + '/' + ('?' + query if query else ''))\n"
    "                self.send_header('Content-Length', '0')\n"
    "                self.end_headers()\n"
    "                return None\n"
    "            real = os.path.realpath(os.path.join(real, 'index.html'))\n"
    "            if not inside(real):\n"
    "                return self.send_error(404, 'not found')\n"
    "        try:\n"
    "            fd = os.open(real, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)\n"
    "        except OSError:\n"
    "            return self.send_error(404, 'not found')\n"
    "        f = os.fdopen(fd, 'rb')\n"
    "        st = os.fstat(fd)\n"
    "        if not stat.S_ISREG(st.st_mode):\n"
    "            f.close()\n"
    "            return self.send_error(404, 'not found')\n"
    "        self.send_response(200)\n"
    "        self.send_header('Content-Type', self.guess_type(real))\n"
    "        self.send_header('Content-Length', str(st.st_size))\n"
    "        self.send_header('Last-Modified', self.date_time_string(int(st.st_mtime)))\n"
    "        self.end_headers()\n"
    "        return f\n"
    "srv = http.server.ThreadingHTTPServer(('127.0.0.1', 0), Handler, bind_and_activate=False)\n"
    "srv.socket.close()\n"
    "srv.socket = sock\n"
    "srv.server_name, srv.server_port = '127.0.0.1', PORT\n"
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
        /* suggest the run only where it would be accepted: a new folder (not '.', a system
         * folder or a campaign's, which lvsim run refuses) */
        if (file_exists(dir, "stats.json"))
            fprintf(stderr, "lvsim view: '%s' is a Monte Carlo campaign's folder: its report is "
                            "%s/index.html; the 3D view shows one run's results folder "
                            "(lvsim run MISSION.yaml -o DIR)\n", dir, dir);
        else
            fprintf(stderr, "lvsim view: '%s' is not a results folder (no summary.json): "
                            "give the folder of a run (lvsim run MISSION.yaml -o DIR)\n", dir);
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
        const lv_outdir_record rec = {"view", "ok", NULL, 0, NULL};
        if (code == EXIT_OK && lv_outdir_commit(od, &rec, &err) != LV_OK) /* failed: untouched */
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
    char token[33];
    if (make_token(token) != 0 || setenv("LVSIM_VIEW_TOKEN", token, 1) != 0) {
        fprintf(stderr, "lvsim view: no random token for the URL: %s\n", strerror(errno));
        return EXIT_INTERNAL;
    }
    if (!port_given && bound != port)
        printf("lvsim view: port %d is busy; using %d\n", port, bound);
    printf("lvsim view: http://127.0.0.1:%d/%s/viewer/  (serving %s; Ctrl-C to stop)\n",
           bound, token, dir);
    fflush(stdout);
    char *args[] = {"/usr/bin/python3", "-I", "-B", "-c", (char *)serve_py, (char *)dir, NULL};
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
    "missing, and serves OUTDIR on http://127.0.0.1:PORT/TOKEN/viewer/ until Ctrl-C\n"
    "(python3; a browser cannot load the viewer's data from a file:// page, hence the\n"
    "server). Read-only: GET and HEAD, only with the random TOKEN of the URL it prints and\n"
    "a Host header 127.0.0.1:PORT or localhost:PORT, no folder listings, nothing outside\n"
    "OUTDIR (symlinks resolved).\n"
    "The viewer is found like any data file: $LVSIM_DATA, else share/lvsim next to the\n"
    "library, else the install prefix (viewer/stage.sh there).\n"
    "\n"
    "options:\n"
    "  --port N                TCP port on 127.0.0.1, 1 to 65535; busy: exit 2 (default\n"
    "                          8765, or the next free one after it)\n"
    "  --stage-only            stage the viewer and return without serving\n",
    view_run,
};
