/* main.c - the lvsim command line: looks the command up in the table (cli.h) and runs it;
 * `help`, `--help` and `version`. Every usage and help text comes from the table entries,
 * each command's in its own cli/cmd_<name>.c. Exit codes: 0 ok, 1 internal error, 2 bad
 * input, 3 simulation failure, 4 a body crashed, 130 stopped by Ctrl-C or SIGTERM
 * (docs/cli.md). main() is cli_main(), which returns the exit code and never exits, so a
 * program (fuzz/fuzz_cli.c) can call it.
 */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "common.h"

static int help_run(const cli_cmd *self, int argc, char **argv);
static int version_run(const cli_cmd *self, int argc, char **argv);

static const cli_cmd cmd_help = {
    "help",
    "list the commands, or show one command's usage and options",
    "[COMMAND | --markdown]",
    "Without a command: the list of commands. With one: its usage line, what it does and\n"
    "its options with their defaults and units; 'lvsim COMMAND --help' (or -h) is the\n"
    "same. An unknown command exits 2.\n"
    "\n"
    "options:\n"
    "  --markdown              the list of commands as the Markdown table of docs/cli.md\n"
    "                          (a command, its arguments before the first option, its\n"
    "                          summary; a test compares the page with it)\n",
    help_run,
};

static const cli_cmd cmd_version = {
    "version",
    "print the version",
    "",
    "Prints 'lvsim VERSION' (also: lvsim --version).\n",
    version_run,
};

/* The commands in the order `lvsim help` lists them. */
static const cli_cmd *const commands[] = {
    &cli_cmd_models,  &cli_cmd_vars,       &cli_cmd_laws,     &cli_cmd_simulate, &cli_cmd_run,
    &cli_cmd_mc,      &cli_cmd_check,      &cli_cmd_target,   &cli_cmd_optimize,   &cli_cmd_params,   &cli_cmd_compare,
    &cli_cmd_export,  &cli_cmd_formats,    &cli_cmd_fmu,      &cli_cmd_plot,     &cli_cmd_view,
    &cli_cmd_atmosphere, &cli_cmd_gravity, &cmd_help,         &cmd_version,      NULL,
};

static const cli_cmd *find_command(const char *name)
{
    for (const cli_cmd *const *c = commands; *c != NULL; c++)
        if (strcmp((*c)->name, name) == 0)
            return *c;
    return NULL;
}

/* Optimal string alignment distance (Levenshtein with adjacent transpositions); names
 * longer than 31 characters count as far from every command. */
static size_t edit_distance(const char *a, const char *b)
{
    enum { N = 32 };
    const size_t na = strlen(a), nb = strlen(b);
    if (na >= N || nb >= N)
        return N;
    size_t d[N][N];
    for (size_t i = 0; i <= na; i++)
        d[i][0] = i;
    for (size_t j = 0; j <= nb; j++)
        d[0][j] = j;
    for (size_t i = 1; i <= na; i++) {
        for (size_t j = 1; j <= nb; j++) {
            size_t best = d[i - 1][j - 1] + (a[i - 1] != b[j - 1]);
            if (d[i - 1][j] + 1 < best) best = d[i - 1][j] + 1;
            if (d[i][j - 1] + 1 < best) best = d[i][j - 1] + 1;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] &&
                d[i - 2][j - 2] + 1 < best)
                best = d[i - 2][j - 2] + 1;
            d[i][j] = best;
        }
    }
    return d[na][nb];
}

/* "unknown command 'x'", with the commands it may be a typo or an abbreviation of. */
static int unknown_command(const char *name)
{
    const size_t n = strlen(name), max_dist = n <= 3 ? 1 : 2;
    fprintf(stderr, "lvsim: unknown command '%s'", name);
    int shown = 0;
    for (size_t dist = 0; dist <= max_dist; dist++) {
        for (const cli_cmd *const *c = commands; *c != NULL; c++) {
            /* an abbreviation ("sim") counts as distance 0 */
            const int prefix = n >= 2 && strncmp(name, (*c)->name, n) == 0;
            if ((prefix ? 0 : edit_distance(name, (*c)->name)) != dist)
                continue;
            fprintf(stderr, "%s'%s'", shown ? ", " : "; did you mean ", (*c)->name);
            shown++;
        }
    }
    fprintf(stderr, "%s\n(see 'lvsim help')\n", shown ? "?" : "");
    return EXIT_INPUT;
}

static void print_overview(FILE *f)
{
    fprintf(f, "lvsim %s - mission-dependent sequential simulation of launch vehicles\n\n"
               "usage: lvsim COMMAND [arguments]\n\ncommands:\n", LVSIM_VERSION);
    for (const cli_cmd *const *c = commands; *c != NULL; c++)
        fprintf(f, "  %-12s %s\n", (*c)->name, (*c)->summary);
    fprintf(f, "\n'lvsim help COMMAND' or 'lvsim COMMAND --help' shows a command's usage and "
               "options.\n"
               "exit codes: 0 ok, 1 internal error, 2 bad input, 3 simulation failure, 4 a body\n"
               "crashed (run: a touchdown beyond the landing gear's limits), 130 stopped\n"
               "by Ctrl-C or SIGTERM (a second one ends the process at once)\n"
               "data files (gravity coefficients, the viewer): $LVSIM_DATA, else share/lvsim\n"
               "next to the library, else the install prefix\n");
}

static void print_command_help(FILE *f, const cli_cmd *c)
{
    print_usage_line(f, c);
    fprintf(f, "%s: %s\n\n%s", c->name, c->summary, c->help);
}

/* The command list as docs/cli.md's table: `NAME ARGS` (the usage's words before the first
 * option or optional part) and the summary; tests/cli/check_help_doc.sh compares them. */
static void print_markdown(void)
{
    printf("| command | what |\n| --- | --- |\n");
    for (const cli_cmd *const *c = commands; *c != NULL; c++) {
        printf("| `%s", (*c)->name);
        const char *u = (*c)->usage;
        while (*u != '\0') {
            while (*u == ' ' || *u == '\n')
                u++;
            const size_t n = strcspn(u, " \n");
            if (n == 0 || *u == '[' || *u == '-')
                break;
            printf(" %.*s", (int)n, u);
            u += n;
        }
        printf("` | %s |\n", (*c)->summary);
    }
}

static int help_run(const cli_cmd *self, int argc, char **argv)
{
    if (argc == 0) {
        print_overview(stdout);
        return EXIT_OK;
    }
    if (argc == 1 && strcmp(argv[0], "--markdown") == 0) {
        print_markdown();
        return EXIT_OK;
    }
    if (argc > 1)
        return usage_error(self, "help takes at most one command name", NULL);
    const cli_cmd *c = find_command(argv[0]);
    if (c == NULL)
        return unknown_command(argv[0]);
    print_command_help(stdout, c);
    return EXIT_OK;
}

static int version_run(const cli_cmd *self, int argc, char **argv)
{
    if (argc != 0) {
        const char *what =
            is_option(argv[0]) ? "unknown option" : "version takes no arguments; got";
        return usage_error(self, what, argv[0]);
    }
    printf("lvsim %s\n", LVSIM_VERSION);
    return EXIT_OK;
}

int cli_main(int argc, char **argv)
{
    if (argc < 2) {
        print_overview(stderr);
        return EXIT_INPUT;
    }
    const char *name = argv[1];
    if (strcmp(name, "--help") == 0 || strcmp(name, "-h") == 0)
        name = "help";
    else if (strcmp(name, "--version") == 0)
        name = "version";
    const cli_cmd *c = find_command(name);
    if (c == NULL)
        return unknown_command(name);
    /* --help or -h anywhere among a command's arguments: its help, whatever else is there */
    for (int i = 2; i < argc; i++)
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            print_command_help(stdout, c);
            return EXIT_OK;
        }
    return c->run(c, argc - 2, argv + 2);
}

#ifndef LV_CLI_NO_MAIN /* the fuzz target fuzz/fuzz_cli.c calls cli_main itself */
int main(int argc, char **argv) { return cli_main(argc, argv); }
#endif
