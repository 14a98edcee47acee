/* sqlite_dl.c - SQLite, loaded the first time a campaign database is opened (io/dl_lib.h).
 *
 * Only `lvsim mc` (and the campaign reader) uses SQLite, yet linking it costs every lvsim
 * process about 1.1 million instructions of loading and relocation (callgrind of a program
 * that links it and does nothing: 1.18 M against 0.13 M; issue 24). The SQLite functions
 * lvsim calls are defined here with SQLite's own signatures and forward to the library; when
 * it cannot be loaded a call fails as SQLite reports failure (SQLITE_CANTOPEN, NULL) and
 * sqlite3_errmsg() - like lv_sqlite_error() - says why. Adding a function: one line. */
#define _GNU_SOURCE

#include <sqlite3.h>

#include "campaign/sqlite_dl.h"
#include "io/dl_lib.h"

#ifndef LV_SQLITE3_SONAME
#define LV_SQLITE3_SONAME "libsqlite3.so.0" /* set by cmake/lv_deps.cmake */
#endif

typedef void (*lv_sqlite_destructor)(void *);
typedef int (*lv_sqlite_callback)(void *, int, char **, char **);

#define SQLITE_FUNCS(X, V)                                                                    \
    X(int, sqlite3_open_v2, (const char *a, sqlite3 **b, int c, const char *d), (a, b, c, d), \
      (*b = NULL, SQLITE_CANTOPEN))                                                           \
    X(int, sqlite3_close, (sqlite3 * a), (a), SQLITE_MISUSE)                                  \
    X(const char *, sqlite3_errmsg, (sqlite3 * a), (a), dl_why)                               \
    X(int, sqlite3_busy_timeout, (sqlite3 * a, int b), (a, b), SQLITE_MISUSE)                 \
    X(int, sqlite3_exec, (sqlite3 * a, const char *b, lv_sqlite_callback c, void *d, char **e), \
      (a, b, c, d, e), SQLITE_MISUSE)                                                         \
    V(sqlite3_free, (void *a), (a))                                                           \
    X(int, sqlite3_prepare_v2,                                                                \
      (sqlite3 * a, const char *b, int c, sqlite3_stmt **d, const char **e), (a, b, c, d, e), \
      (*d = NULL, SQLITE_MISUSE))                                                             \
    X(int, sqlite3_step, (sqlite3_stmt * a), (a), SQLITE_MISUSE)                              \
    X(int, sqlite3_reset, (sqlite3_stmt * a), (a), SQLITE_MISUSE)                             \
    X(int, sqlite3_finalize, (sqlite3_stmt * a), (a), SQLITE_OK)                              \
    X(int, sqlite3_bind_double, (sqlite3_stmt * a, int b, double c), (a, b, c), SQLITE_MISUSE) \
    X(int, sqlite3_bind_int, (sqlite3_stmt * a, int b, int c), (a, b, c), SQLITE_MISUSE)      \
    X(int, sqlite3_bind_int64, (sqlite3_stmt * a, int b, sqlite3_int64 c), (a, b, c),         \
      SQLITE_MISUSE)                                                                          \
    X(int, sqlite3_bind_null, (sqlite3_stmt * a, int b), (a, b), SQLITE_MISUSE)               \
    X(int, sqlite3_bind_text,                                                                 \
      (sqlite3_stmt * a, int b, const char *c, int d, lv_sqlite_destructor e),                \
      (a, b, c, d, e), SQLITE_MISUSE)                                                         \
    X(int, sqlite3_column_count, (sqlite3_stmt * a), (a), 0)                                  \
    X(double, sqlite3_column_double, (sqlite3_stmt * a, int b), (a, b), 0.0)                  \
    X(int, sqlite3_column_int, (sqlite3_stmt * a, int b), (a, b), 0)                          \
    X(sqlite3_int64, sqlite3_column_int64, (sqlite3_stmt * a, int b), (a, b), 0)              \
    X(const char *, sqlite3_column_name, (sqlite3_stmt * a, int b), (a, b), NULL)             \
    X(const unsigned char *, sqlite3_column_text, (sqlite3_stmt * a, int b), (a, b), NULL)    \
    X(int, sqlite3_column_type, (sqlite3_stmt * a, int b), (a, b), SQLITE_NULL)

LV_DL_LIBRARY(LV_SQLITE3_SONAME, SQLITE_FUNCS)

const char *lv_sqlite_error(void) { return dl_error(); }
