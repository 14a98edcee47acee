/* mission_kit.h - what the unit tests that write a mission file and run it share: the file
 * written (checked), a mission loaded and run from its text, and a flat world to fly in.
 * Include after check.h. */
#ifndef LV_TEST_MISSION_KIT_H
#define LV_TEST_MISSION_KIT_H

#include <stdio.h>

#include "check.h"
#include "lvsim/lv_mission.h"

/* Writes `text` to `path` (a failure to open it is a failed check). */
static inline void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (f != NULL) {
        fputs(text, f);
        fclose(f);
    }
}

/* Loads and runs `yaml` (written to `path`); NULL when it fails to load. */
static inline lv_run *run_text(const char *path, const char *yaml, lv_mission **m)
{
    lv_err err;
    lv_run *r = NULL;
    write_file(path, yaml);
    *m = NULL;
    CHECK_OK(lv_mission_load(path, m, &err), &err);
    if (*m == NULL)
        return NULL;
    CHECK_OK(lv_run_create(*m, &r, &err), &err);
    if (r != NULL)
        CHECK_OK(lv_run_execute(r, NULL, &err), &err);
    return r;
}

/* The flat world: a non-rotating sphere of radius 1e10 m with g = g0 at its surface. */
#define FLAT_WORLD                                                                         \
    "environment:\n  world: planet\n"                                                     \
    "  planet: {name: flatland, radius: 1.0e10, gm: 9.80665e20, rotation_rate: 0}\n"      \
    "  atmosphere: none\n"

#endif
