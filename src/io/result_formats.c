/* result_formats.c - the table of the result-file formats a run writes per phase: one line per
 * format (its sink and descriptor in src/io/result_<name>.c). The runner, the summary, the
 * results reader, the command line and the Python package iterate it (docs/architecture.md,
 * "A result format"). A format's flag is 1u << its position: keep the order of LV_RESULT_*.
 */
#include <stddef.h>

#include "io/sink.h"
#include "lvsim/lv_io.h"

const lv_result_format *const lv_result_formats[] = {
    &lv_result_format_mat, /* LV_RESULT_MAT */
    &lv_result_format_csv, /* LV_RESULT_CSV */
    NULL};

size_t lv_result_format_count(void)
{
    size_t n = 0;
    while (lv_result_formats[n] != NULL)
        n++;
    return n;
}

unsigned lv_result_format_mask(void)
{
    return (1u << lv_result_format_count()) - 1u;
}

LV_API const char *lv_result_format_info(size_t i, const char **ext, const char **description)
{
    if (i >= lv_result_format_count())
        return NULL;
    if (ext != NULL)
        *ext = lv_result_formats[i]->ext;
    if (description != NULL)
        *description = lv_result_formats[i]->description;
    return lv_result_formats[i]->name;
}
