/* cli.h - the lvsim command table: one entry per command, defined in its cli/cmd_<name>.c
 * and listed in main.c. `lvsim help`, `lvsim help CMD`, `lvsim CMD --help` and the usage
 * line of every usage error are printed from these entries, never written anywhere else.
 */
#ifndef LVSIM_CLI_H
#define LVSIM_CLI_H

typedef struct cli_cmd cli_cmd;
struct cli_cmd {
    const char *name;    /* the word after `lvsim`: "simulate" */
    const char *summary; /* one line for the command list of `lvsim help` */
    const char *usage;   /* synopsis of the arguments after the name: "MODEL [options]";
                            "" when it takes none */
    const char *help;    /* what it does, then one line per option with its default and
                            unit; ends with a newline */
    /* Runs the command on the arguments after its name (argv[0] is the first of them; a
     * --help or -h among them never gets here: main.c prints the help). Prints its own
     * messages; returns the exit code (0 ok, 1 internal, 2 bad input, 3 simulation). */
    int (*run)(const cli_cmd *self, int argc, char **argv);
};

/* The whole command line (argv[0] the program, argv[1] the command): dispatches to the
 * command and returns its exit code; never exits (main.c's main() returns it). */
int cli_main(int argc, char **argv);

/* One per file cli/cmd_<name>.c (models and vars: cmd_models.c). */
extern const cli_cmd cli_cmd_models;
extern const cli_cmd cli_cmd_vars;
extern const cli_cmd cli_cmd_laws;
extern const cli_cmd cli_cmd_simulate;
extern const cli_cmd cli_cmd_run;
extern const cli_cmd cli_cmd_mc;
extern const cli_cmd cli_cmd_check;
extern const cli_cmd cli_cmd_target;
extern const cli_cmd cli_cmd_optimize;
extern const cli_cmd cli_cmd_params;
extern const cli_cmd cli_cmd_compare;
extern const cli_cmd cli_cmd_export;
extern const cli_cmd cli_cmd_formats;
extern const cli_cmd cli_cmd_plot;
extern const cli_cmd cli_cmd_view;
extern const cli_cmd cli_cmd_atmosphere;
extern const cli_cmd cli_cmd_gravity;
extern const cli_cmd cli_cmd_fmu;

#endif
