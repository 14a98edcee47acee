/* table_load.h - the table loaders' first half, for code that wants the data before (or
 * instead of) an lv_table (not exported). lv_table_load_spec reads a CSV or MAT file exactly
 * as lv_table_load does (formats: docs/tables.md) and hands the result to `fn` as an
 * lv_table_spec, whose arrays live only during the call. Unlike lv_table_create, `fn` also
 * sees what a table cannot hold: a 1-D file with a single row (spec->n[0] == 1), e.g. a
 * constant wind. The loaders' own errors carry path:line:column (CSV) or the variable (MAT);
 * `fn`'s status is returned as it is.
 */
#ifndef LV_IO_TABLE_LOAD_H
#define LV_IO_TABLE_LOAD_H

#include "lvsim/lv_table.h"

typedef lv_status (*lv_table_spec_fn)(const lv_table_spec *spec, void *user, lv_err *err);

lv_status lv_table_load_spec(const char *path, const char *var, const lv_table_opts *opts,
                             lv_table_spec_fn fn, void *user, lv_err *err);

#endif
