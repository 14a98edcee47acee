/* common.c - helpers shared by the lvsim commands: exit codes, usage errors, number
 * parsing, library errors, model lookup and JSON output.
 */
#define _POSIX_C_SOURCE 200809L /* stat */

#include "common.h"

#include <errno.h>
#include <math.h>
#include <signal.h>
#include <unistd.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include "post/json_print.h"

int exit_code_for(lv_status st)
{
    switch (st) {
    case LV_OK: return EXIT_OK;
    case LV_ERR_SOLVER: return EXIT_SIM;
    case LV_ERR_NOMEM: return EXIT_INTERNAL;
    case LV_ERR_CANCELLED: return EXIT_STOPPED; /* Ctrl-C, SIGTERM: 128 + SIGINT, as shells */
    default: return EXIT_INPUT;
    }
}

int exit_code_for_input(lv_status st)
{
    const int code = exit_code_for(st);
    return code == EXIT_SIM ? EXIT_INPUT : code;
}

void print_usage_line(FILE *f, const cli_cmd *cmd)
{
    fprintf(f, "usage: lvsim %s%s%s\n", cmd->name, cmd->usage[0] ? " " : "", cmd->usage);
}

int usage_error(const cli_cmd *cmd, const char *what, const char *arg)
{
    fprintf(stderr, "lvsim: %s%s%s%s\n", what, arg ? " '" : "", arg ? arg : "", arg ? "'" : "");
    if (cmd != NULL) {
        print_usage_line(stderr, cmd);
        fprintf(stderr, "(see 'lvsim help %s')\n", cmd->name);
    } else {
        fprintf(stderr, "(see 'lvsim help')\n");
    }
    return EXIT_INPUT;
}

int is_option(const char *arg)
{
    double v;
    return arg[0] == '-' && arg[1] != '\0' && !parse_double(arg, &v);
}

const char *option_value(int argc, char **argv, int *i)
{
    if (*i + 1 >= argc)
        return NULL;
    return argv[++*i];
}

int parse_double(const char *s, double *out)
{
    /* a decimal number as written: not strtod's hexadecimal ("0x10" is 16) or leading space */
    if (s[strspn(s, "0123456789+-.eE")] != '\0')
        return 0;
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE || !isfinite(v))
        return 0;
    *out = v;
    return 1;
}

int parse_int(const char *s, int *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end != '\0' || errno == ERANGE || v < 0 || v > 100000000)
        return 0;
    *out = (int)v;
    return 1;
}

int print_err(const char *who, const lv_err *err, int code)
{
    if (who != NULL)
        fprintf(stderr, "%s: %s\n", who, err->msg);
    else
        fprintf(stderr, "%s\n", err->msg);
    return code;
}

const lv_model_def *find_model(const char *name)
{
    const lv_model_def *m = lv_models_find(name);
    if (m == NULL) {
        fprintf(stderr, "lvsim: unknown model '%s'; built-in models:", name);
        for (const lv_model_def *const *all = lv_models_all(); *all; all++)
            fprintf(stderr, " %s", (*all)->name);
        fprintf(stderr, "\n");
    }
    return m;
}

int print_json(cJSON *doc)
{
    char *text = doc != NULL ? lv_json_print(doc) : NULL;
    cJSON_Delete(doc);
    if (text == NULL) {
        fprintf(stderr, "lvsim: out of memory writing JSON\n");
        return EXIT_INTERNAL;
    }
    fputs(text, stdout);
    putchar('\n');
    cJSON_free(text);
    return EXIT_OK;
}

int load_mission(const char *path, lv_mission **m)
{
    struct stat sb;
    *m = NULL;
    if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode)) {
        fprintf(stderr, "lvsim: '%s' is a folder, not a mission file: name its YAML file "
                        "(e.g. %s/mission.yaml)\n", path, path);
        return EXIT_INPUT;
    }
    lv_err err;
    lv_status st = lv_mission_load(path, m, &err);
    if (st != LV_OK)
        return print_err(NULL, &err, exit_code_for_input(st));
    return EXIT_OK;
}

int parse_count(const char *s, double *out)
{
    double v;
    if (!parse_double(s, &v) || v < 1.0 || v > 1e15 || v != floor(v))
        return 0;
    *out = v;
    return 1;
}

int parse_tolerance_option(const cli_cmd *cmd, const char *opt, const char *v, double *out)
{
    double x;
    if (parse_double(v, &x) && x >= LV_TOLERANCE_MIN && x <= LV_TOLERANCE_MAX) {
        *out = x;
        return 1;
    }
    char what[160];
    snprintf(what, sizeof what, "%s needs a relative tolerance from %g to %g (the range of a "
             "phase's integrator tolerance), got", opt, LV_TOLERANCE_MIN, LV_TOLERANCE_MAX);
    usage_error(cmd, what, v);
    return 0;
}

unsigned name_list_add(name_list *l, const char *name)
{
    if (l->n >= NAME_LIST_MAX) /* not reached: 31 flags */
        return 0u;
    l->names[l->n] = name;
    return 1u << l->n++;
}

void name_list_add_results(name_list *l)
{
    const char *name;
    for (size_t i = 0; (name = lv_result_format_info(i, NULL, NULL)) != NULL; i++)
        name_list_add(l, name);
}

void name_list_add_exports(name_list *l)
{
    const char *name;
    for (size_t i = 0; (name = lv_export_format_info(i, NULL, NULL)) != NULL; i++)
        name_list_add(l, name);
}

void name_list_join(const name_list *l, size_t first, size_t n, char *buf, size_t cap)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < n && first + i < l->n && used < cap; i++)
        used += (size_t)snprintf(buf + used, cap - used, "%s%s",
                                 i == 0 ? "" : i + 1 == n ? " and " : ", ", l->names[first + i]);
}

int parse_name_list(const cli_cmd *cmd, const char *opt, const char *what, const name_list *l,
                    int allow_none, const char *list, unsigned *out)
{
    *out = 0;
    if (allow_none && strcmp(list, "none") == 0)
        return 1;
    for (const char *p = list;;) {
        const char *comma = strchr(p, ',');
        const size_t len = comma ? (size_t)(comma - p) : strlen(p);
        size_t i = 0;
        while (i < l->n && !(strlen(l->names[i]) == len && strncmp(l->names[i], p, len) == 0))
            i++;
        if (i == l->n && allow_none && len == 4 && strncmp(p, "none", 4) == 0) {
            char msg[160];
            snprintf(msg, sizeof msg, "%s: 'none' stands alone, not in a list", opt);
            usage_error(cmd, msg, list);
            return 0;
        }
        if (i == l->n) {
            char msg[512]; /* "--format: unknown format 'xmatx' (known: mat, csv, none)" */
            size_t used = (size_t)snprintf(msg, sizeof msg, "%s: unknown %s '%.*s' (known: ", opt,
                                           what, (int)(len < 100 ? len : 100), p);
            for (size_t k = 0; k < l->n && used < sizeof msg; k++)
                used += (size_t)snprintf(msg + used, sizeof msg - used, "%s%s", k ? ", " : "",
                                         l->names[k]);
            if (used < sizeof msg)
                snprintf(msg + used, sizeof msg - used, "%s)", allow_none ? ", none" : "");
            usage_error(cmd, msg, NULL);
            return 0;
        }
        *out |= 1u << i;
        if (comma == NULL)
            return 1;
        p = comma + 1;
    }
}

int parse_method_option(const cli_cmd *cmd, const char *opt, const char *v)
{
    char what[160];
    size_t n = 0;
    n += (size_t)snprintf(what, sizeof what, "%s needs an integration method (", opt);
    for (const char *const *m = lv_sim_methods(); *m != NULL; m++) {
        if (strcasecmp(*m, v) == 0)
            return 1;
        if (n < sizeof what)
            n += (size_t)snprintf(what + n, sizeof what - n, "%s%s",
                                  m == lv_sim_methods() ? "" : ", ", *m);
    }
    if (n < sizeof what)
        snprintf(what + n, sizeof what - n, "), got");
    usage_error(cmd, what, v);
    return 0;
}

int parse_interval_option(const cli_cmd *cmd, const char *opt, const char *v, double *out)
{
    double x;
    if (parse_double(v, &x) && x > 0.0) {
        *out = x;
        return 1;
    }
    char what[96];
    snprintf(what, sizeof what, "%s needs seconds > 0, got", opt);
    usage_error(cmd, what, v);
    return 0;
}

void human_bytes(double b, char *buf, size_t cap)
{
    static const char *const unit[] = {"B", "kB", "MB", "GB", "TB", "PB"};
    size_t u = 0;
    while (b >= 1000.0 && u + 1 < sizeof unit / sizeof unit[0]) {
        b /= 1000.0;
        u++;
    }
    if (u == 0)
        snprintf(buf, cap, "%.0f B", b);
    else
        snprintf(buf, cap, "%.3g %s", b, unit[u]);
}

/* A row count for the table: exact below ten million, "1.4e+11" above. */
static void fmt_rows(double n, char *buf, size_t cap)
{
    snprintf(buf, cap, n < 1e7 ? "%.0f" : "%.3g", n);
}

int check_output_bound_as(const lv_mission *m, double max_rows, double output_interval, int list,
                          const char *context, int strict)
{
    lv_run *run = NULL;
    lv_err err;
    lv_status st = lv_run_create(m, &run, &err);
    if (st != LV_OK)
        return print_err("lvsim", &err, exit_code_for(st));
    int code = EXIT_OK;
    const size_t n = lv_mission_phase_count(m);
    if (list)
        printf("%-3s %-12s %12s %8s %11s %11s  %s\n", "#", "phase", "rows (max)", "columns",
               ".mat", ".csv", "ends at");
    for (size_t k = 0; (list || strict) && k < n && code == EXIT_OK; k++) {
        lv_output_estimate e;
        if ((st = lv_run_estimate_output(run, k, output_interval, &e, &err)) != LV_OK) {
            code = print_err("lvsim", &err, exit_code_for(st));
            break;
        }
        char rows[32], mat[32], csv[32];
        fmt_rows(e.rows, rows, sizeof rows);
        human_bytes(e.bytes_mat, mat, sizeof mat);
        human_bytes(e.bytes_csv, csv, sizeof csv);
        lv_phase_info pi;
        lv_mission_phase_info(m, k, &pi);
        if (list)
            printf("%-3zu %-12s %12s %8zu %11s %11s  %s\n", k + 1, lv_mission_phase_name(m, k),
                   rows, e.n_signals, mat, csv,
                   e.bounded         ? "stop time"
                   : pi.parent >= 0 ? "its parent's end or an end event: checked as it runs"
                                    : "an end event: rows limited as it runs");
        if (strict && !e.bounded && e.rows > max_rows) {
            char lim[32];
            fmt_rows(max_rows, lim, sizeof lim);
            fprintf(stderr, "lvsim: %s%sphase %zu '%s' could write up to %s rows by its stop "
                    "time (%.6g s of mission time) - more than the limit of %s rows per phase; "
                    "its end events may come earlier, but nothing holds the limit as it runs "
                    "there. Give it a larger output interval or an earlier stop_time, or allow "
                    "it with --max-rows\n", context ? context : "", context ? ": " : "", k + 1,
                    lv_mission_phase_name(m, k), rows, e.duration, lim);
            code = EXIT_INPUT;
        }
    }
    /* the verdict is the library's, as lv_run_execute gives it with the same options */
    lv_run_options o = {0};
    o.output_interval = output_interval;
    o.max_rows = max_rows;
    if (code == EXIT_OK && (st = lv_run_check_output(run, &o, &err)) != LV_OK) {
        if (context != NULL)
            fprintf(stderr, "lvsim: %s: %s\n", context, err.msg);
        else
            print_err("lvsim", &err, 0);
        code = exit_code_for_input(st);
    }
    lv_run_free(run);
    return code;
}

void restage(char *msg, size_t cap, const char *stage, const char *final)
{
    char out[LV_ERR_MSG_MAX];
    size_t n = 0;
    const size_t ls = strlen(stage);
    for (const char *p = msg; *p != '\0' && n + 1 < sizeof out;) {
        if (ls > 0 && strncmp(p, stage, ls) == 0) {
            n += (size_t)snprintf(out + n, sizeof out - n, "%s", final);
            p += ls;
        } else {
            out[n++] = *p++;
        }
    }
    out[n < sizeof out ? n : sizeof out - 1] = '\0';
    snprintf(msg, cap, "%s", out);
}

void print_kept(const lv_outdir *od)
{
    const size_t n = lv_outdir_kept_count(od);
    if (n == 0)
        return;
    printf("kept %zu file%s lvsim did not write in %s/ (not in its manifest):", n,
           n == 1 ? "" : "s", lv_outdir_final(od));
    for (size_t i = 0; i < n && i < 8; i++)
        printf("%s %s", i ? "," : "", lv_outdir_kept(od, i));
    if (n > 8)
        printf(" and %zu more", n - 8);
    printf("\n");
}

int check_output_bound(const lv_mission *m, double max_rows, double output_interval, int list)
{
    return check_output_bound_as(m, max_rows, output_interval, list, NULL, 0);
}

/* ---- stopping ------------------------------------------------------------------------------ */

volatile int cli_stop_flag = 0; /* the one piece of process state: a handler sets a flag */

/* What a command that has not stopped CLI_STOP_GRACE_S seconds after the signal does: ends
 * now, as a second Ctrl-C would (async-signal-safe: write and _exit only). */
static void on_stop_overdue(int sig)
{
    (void)sig;
    static const char msg[] = "\nlvsim: not stopped within " CLI_STOP_GRACE_TEXT " s of the "
                              "signal: ended now (what it was writing is left unfinished, "
                              "never in place of a finished result)\n";
    ssize_t ignored = write(STDERR_FILENO, msg, sizeof msg - 1);
    (void)ignored;
    _exit(EXIT_STOPPED);
}

static void on_stop_signal(int sig)
{
    (void)sig;
    cli_stop_flag = 1;
    /* the flag is read between integrator steps; a library call that never returns to them
     * (SUNDIALS stuck on an absurd scale: issue 22's breaker) must not keep the process.
     * SIGALRM is taken only now (sigaction and alarm are async-signal-safe): until a stop is
     * asked for, the process's alarm stays whoever's it is (libFuzzer's per-input timeout) */
    static struct sigaction od; /* zeroed: no flags, an empty mask */
    od.sa_handler = on_stop_overdue;
    sigaction(SIGALRM, &od, NULL);
    alarm(CLI_STOP_GRACE_S);
}

void cli_catch_stop(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_stop_signal;
    sa.sa_flags = SA_RESETHAND; /* a second signal ends the process */
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
}

void print_padded(const char *s, size_t width, size_t max)
{
    size_t bytes = 0, chars = 0;
    while (s[bytes] != '\0' && chars < max) {
        size_t len = 1; /* the character at `bytes`: its lead byte and continuations */
        while (((unsigned char)s[bytes + len] & 0xC0u) == 0x80u)
            len++;
        bytes += len;
        chars++;
    }
    fwrite(s, 1, bytes, stdout);
    for (; chars < width; chars++)
        putchar(' ');
}

int check_out_file(const cli_cmd *cmd, const char *out, const char *what)
{
    struct stat sb;
    char dir[4096];
    snprintf(dir, sizeof dir, "%s", out);
    char *slash = strrchr(dir, '/');
    if (slash == dir)
        dir[1] = '\0';
    else if (slash != NULL)
        *slash = '\0';
    else
        snprintf(dir, sizeof dir, ".");
    if (out[0] == '\0' || out[strlen(out) - 1] == '/' ||
        (stat(out, &sb) == 0 && S_ISDIR(sb.st_mode))) {
        char msg[96];
        snprintf(msg, sizeof msg, "-o names the file to write (%s), not a folder:", what);
        return usage_error(cmd, msg, out);
    }
    if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode)) {
        fprintf(stderr, "lvsim: -o %s: '%s' %s\n", out, dir,
                stat(dir, &sb) == 0 ? "is a file, not a folder" : "does not exist");
        return EXIT_INPUT;
    }
    if (access(dir, W_OK) != 0) {
        fprintf(stderr, "lvsim: -o %s: cannot write into '%s': %s\n", out, dir, strerror(errno));
        return EXIT_INPUT;
    }
    return EXIT_OK;
}

int parse_int_option(const cli_cmd *cmd, const char *opt, const char *v, double lo, double hi,
                     int *out)
{
    double x;
    if (!parse_double(v, &x) || x != floor(x) || x < lo || x > hi) {
        char msg[96];
        snprintf(msg, sizeof msg, "%s needs an integer from %g to %g, got", opt, lo, hi);
        return usage_error(cmd, msg, v);
    }
    *out = (int)x;
    return EXIT_OK;
}
