/* data.h - the folders lv_data_find() searches (internal; the API is lvsim/lv_data.h).
 * Exposed so that tests can check the order without planting files everywhere. */
#ifndef LV_CORE_DATA_H
#define LV_CORE_DATA_H

#include "lvsim/lv_data.h"

enum { LV_DATA_MAX_DIRS = 5, LV_DATA_PATH_MAX = 4096 };

typedef struct lv_data_dirs {
    size_t n;
    char dir[LV_DATA_MAX_DIRS][LV_DATA_PATH_MAX]; /* search order, duplicates removed */
    const char *origin[LV_DATA_MAX_DIRS];         /* static text: "LVSIM_DATA", ... */
    int env_set;                                  /* LVSIM_DATA was set and not empty */
} lv_data_dirs;

/* Fills `out` with the folders of the search order in lvsim/lv_data.h (`dir` may be NULL).
 * A folder that does not fit in LV_DATA_PATH_MAX is left out. */
void lv_data_dirs_get(const char *dir, lv_data_dirs *out);

#endif
