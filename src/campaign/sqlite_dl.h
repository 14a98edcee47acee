/* sqlite_dl.h - internal: SQLite is loaded when first used (sqlite_dl.c defines the SQLite
 * functions lvsim calls and forwards them); include <sqlite3.h> for the functions. */
#ifndef LV_CAMPAIGN_SQLITE_DL_H
#define LV_CAMPAIGN_SQLITE_DL_H

/* Why SQLite could not be loaded (a SQLite function then fails), or NULL when it is loaded.
 * Loads it if no SQLite function has yet. */
const char *lv_sqlite_error(void);

#endif
