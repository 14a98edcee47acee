/* cmd_formats.c - `lvsim formats [results|exports] [--markdown]`: the result formats a run
 * writes per phase (lv_result_format_info) and the trajectory exports (lv_export_format_info),
 * as the libraries register them: the words of `simulate --format`, `run --outputs` and
 * `export --format`. --markdown prints the tables of docs/result-files.md and docs/exports.md,
 * which a test compares with this output.
 */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "common.h"

/* One table: result formats (exports 0) or exports (1); markdown or plain. */
static void print_table(int exports, int md)
{
    const char *name, *file, *desc;
    if (md)
        printf("| name | %s | what |\n| --- | --- | --- |\n", exports ? "writes" : "extension");
    else
        printf("%s\n", exports ? "exports (from a results folder: lvsim export --format, "
                                 "lvsim run --outputs):"
                               : "result formats (each phase's files: lvsim simulate --format, "
                                 "lvsim run --outputs):");
    for (size_t i = 0;
         (name = exports ? lv_export_format_info(i, &file, &desc)
                         : lv_result_format_info(i, &file, &desc)) != NULL;
         i++) {
        if (md)
            printf("| `%s` | `%s` | %s |\n", name, file, desc);
        else
            printf("  %-6s %-14s %s\n", name, file, desc);
    }
}

static int formats_run(const cli_cmd *self, int argc, char **argv)
{
    int md = 0, which = -1; /* -1 both, 0 results, 1 exports */
    for (int i = 0; i < argc; i++) {
        if (strcmp(argv[i], "--markdown") == 0)
            md = 1;
        else if (is_option(argv[i]))
            return usage_error(self, "unknown option", argv[i]);
        else if (which < 0 && strcmp(argv[i], "results") == 0)
            which = 0;
        else if (which < 0 && strcmp(argv[i], "exports") == 0)
            which = 1;
        else
            return usage_error(self, "expected 'results' or 'exports', got", argv[i]);
    }
    if (which != 1)
        print_table(0, md);
    if (which < 0)
        printf("\n");
    if (which != 0)
        print_table(1, md);
    return EXIT_OK;
}

const cli_cmd cli_cmd_formats = {
    "formats",
    "list the result formats and the exports",
    "[results|exports] [--markdown]",
    "Lists the result formats a run writes for each phase (the words of 'lvsim simulate\n"
    "--format' and 'lvsim run --outputs') and the trajectory exports made from a results\n"
    "folder (the words of 'lvsim export --format' and 'lvsim run --outputs'): name, the file\n"
    "written and what it holds; or only one of the two lists.\n"
    "  --markdown   the same as the tables of docs/result-files.md and docs/exports.md\n",
    formats_run,
};
