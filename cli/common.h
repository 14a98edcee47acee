/* common.h - helpers shared by the lvsim commands: exit codes, usage errors, number
 * parsing, library errors, model lookup and JSON output. Only the CLI uses them.
 */
#ifndef LVSIM_CLI_COMMON_H
#define LVSIM_CLI_COMMON_H

#include <cjson/cJSON.h>
#include <stdio.h>

#include "cli.h"
#include "lvsim/lvsim.h"

enum { EXIT_OK = 0, EXIT_INTERNAL = 1, EXIT_INPUT = 2, EXIT_SIM = 3, EXIT_CRASHED = 4,
       EXIT_STOPPED = 130 };

/* The exit code of a library status: LV_ERR_SOLVER 3, LV_ERR_NOMEM 1, any other error 2. */
int exit_code_for(lv_status st);
/* The same for a step that only reads input (a mission file, a results folder): a failure
 * there is bad input (2), or 1 when out of memory. */
int exit_code_for_input(lv_status st);

/* "usage: lvsim NAME USAGE" from the table entry. */
void print_usage_line(FILE *f, const cli_cmd *cmd);
/* Prints "lvsim: WHAT 'ARG'" (ARG may be NULL), then cmd's usage line and "(see 'lvsim help
 * CMD')" (cmd NULL: "(see 'lvsim help')"), to stderr. Returns 2. */
int usage_error(const cli_cmd *cmd, const char *what, const char *arg);
/* A word that looks like an option: "-x", "--x", but not "-" or a negative number. */
int is_option(const char *arg);
/* The value of the option at argv[*i] (argv[*i + 1], and *i advances), or NULL when it is
 * the last argument. */
const char *option_value(int argc, char **argv, int *i);

/* A whole argument as a finite double / a count 0..1e8; 1 on success, 0 otherwise. */
int parse_double(const char *s, double *out);
int parse_int(const char *s, int *out);

/* Prints err's message to stderr ("WHO: message"; who NULL: the message alone, which
 * already starts with file:line) and returns `code`. */
int print_err(const char *who, const lv_err *err, int code);

/* A built-in model by name; when unknown, says so on stderr listing the models: NULL. */
const lv_model_def *find_model(const char *name);

/* lv_mission_load with the CLI's messages: a folder or a missing file named as such. Prints
 * the error and returns its exit code (2, or 1 out of memory); 0 with *m set. */
int load_mission(const char *path, lv_mission **m);

/* A whole number >= 1 up to 1e15 ("1000000", "1e6"); 1 on success, 0 otherwise. */
int parse_count(const char *s, double *out);

/* Format lists (`simulate --format`, `run --outputs`, `export --format`): the one parser.
 * The words a list may hold, in flag order (names[i] is bit i), from the library's tables. */
#define NAME_LIST_MAX 31 /* bits of an unsigned, 1u << n still defined */
typedef struct name_list {
    const char *names[NAME_LIST_MAX];
    size_t n;
} name_list;
/* Appends the result formats (lv_result_format_info: "mat", "csv") or the exports
 * (lv_export_format_info: "czml", "kml", "oem") to *l, in their tables' order. */
void name_list_add_results(name_list *l);
void name_list_add_exports(name_list *l);
/* Appends one word; returns its bit. */
unsigned name_list_add(name_list *l, const char *name);
/* "a, b and c" of names [first, first + n) of *l into buf. */
void name_list_join(const name_list *l, size_t first, size_t n, char *buf, size_t cap);
/* Parses LIST, comma-separated words each exactly one of l's names (or "none" alone, when
 * allow_none: 0), into *out (bit i for names[i]). Returns 1, or prints "lvsim: OPT: unknown
 * WHAT 'WORD' (known: a, b, c, none)" with cmd's usage (usage_error) and returns 0. */
int parse_name_list(const cli_cmd *cmd, const char *opt, const char *what, const name_list *l,
                    int allow_none, const char *list, unsigned *out);

/* Options that override a mission key are held to that key's range (docs/cli.md): refused,
 * never replaced. Each returns 1 with the value, or prints "lvsim: OPT needs ..., got 'V'"
 * with cmd's usage (usage_error) and returns 0; the caller then exits 2.
 *   a relative tolerance within [LV_TOLERANCE_MIN, LV_TOLERANCE_MAX] (integrator.tolerance) */
int parse_tolerance_option(const cli_cmd *cmd, const char *opt, const char *v, double *out);
/*   an integration method of lv_sim_methods(), any case (integrator.method) */
int parse_method_option(const cli_cmd *cmd, const char *opt, const char *v);
/*   seconds > 0 (integrator.output_interval) */
int parse_interval_option(const cli_cmd *cmd, const char *opt, const char *v, double *out);

/* The default of --max-rows: output rows one phase may write (docs/cli.md). */
#define CLI_DEFAULT_MAX_ROWS 1e6

/* Estimates every phase's output (lv_run_estimate_output with output_interval) and refuses,
 * as lv_run_execute with lv_run_options.max_rows would (lv_run_check_output), a phase that
 * only its stop time ends and that would write more than max_rows rows: prints "lvsim: phase
 * ...: up to N rows ..." naming the phase, rows, bytes and the limit to stderr and returns 2.
 * A phase with end events is not refused here: the run stops it at max_rows. list: also
 * prints each phase's estimate to stdout. Returns 0, 2, or 1 out of memory. */
int check_output_bound(const lv_mission *m, double max_rows, double output_interval, int list);
/* `-o FILE` names a file (not a folder, `what` in the message: "CONVERGED.yaml") in a folder
 * that exists and is writable: EXIT_OK, else the usage error's or EXIT_INPUT with a message. */
int check_out_file(const cli_cmd *cmd, const char *out, const char *what);
/* Option `opt`'s value v as an integer from lo to hi (also written 1e3, as the files' counts):
 * EXIT_OK with *out, else the usage error's exit code ("OPT needs an integer from lo to hi"). */
int parse_int_option(const cli_cmd *cmd, const char *opt, const char *v, double lo, double hi,
                     int *out);
/* The same, the message prefixed "lvsim: CONTEXT: " (context NULL: "lvsim: "); strict: a
 * phase with end events is refused too when its stop time allows more than max_rows rows
 * (where nothing holds the limit as it runs: an FMU's importer). */
int check_output_bound_as(const lv_mission *m, double max_rows, double output_interval, int list,
                          const char *context, int strict);

/* "12.3 MB", "512 B": a byte count for people. */
void human_bytes(double bytes, char *buf, size_t cap);

/* Prints `s` to stdout cut to at most `max` characters and padded with spaces to `width`
 * characters, counting UTF-8 characters, not bytes (a user's event name "été"), never cutting
 * one in half. Each character counts one column (East Asian wide ones take two in a
 * terminal: their rows are that much wider). */
void print_padded(const char *s, size_t width, size_t max);

/* Prints a document built with cJSON (cJSON_Print, indented with spaces) to stdout and
 * deletes it. Returns 0, or 1 when doc is NULL or printing runs out of memory. */
int print_json(cJSON *doc);

/* Replaces every STAGE in msg by FINAL: the staging folder's name never reaches the user. */
void restage(char *msg, size_t cap, const char *stage, const char *final);

/* After a commit with LV_OUTDIR_FORCE: "kept N files lvsim did not write in OUTDIR/: a, b"
 * on stdout (nothing when none). */
void print_kept(const lv_outdir *od);

/* Ctrl-C (SIGINT) and SIGTERM stop the command: the first one sets cli_stop_flag (given as
 * lv_run_options.stop, lv_sim_settings.stop, lv_campaign_options.stop, lv_target_settings.stop:
 * what runs is cancelled within an integrator step, and the command ends as it documents);
 * the handler is reset by that first signal (SA_RESETHAND), so a second one ends the process
 * as usual. */
void cli_catch_stop(void);
/* A command still running this long after the first signal ends at once with EXIT_STOPPED
 * (SIGALRM; what it was writing is left as a temporary or staging file, as after kill -9). */
#define CLI_STOP_GRACE_S 5
#define CLI_STOP_GRACE_TEXT "5"
extern volatile int cli_stop_flag;

#endif
