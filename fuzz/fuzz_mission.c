/* fuzz_mission.c - libFuzzer target: arbitrary bytes into lv_mission_def_parse(), and a
 * definition that parses into the rest of loading (the environment, every phase's model built
 * from the file's values, the plans: lv_mission_from_def), as lv_mission_load does.
 * Any input must give LV_OK or an error record, never a crash, a leak or a hang. Relative
 * table paths resolve against LV_FUZZ_DIR (tests/missions), so seeds load real tables.
 * Build and run: `make fuzz` (fuzz/fuzz.cmake, fuzz/run.sh). */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "mission/mission.h"
#include "mission/mission_rt.h"

#ifndef LV_FUZZ_DIR
#define LV_FUZZ_DIR "."
#endif

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    lv_err err;
    lv_mission_def *m = NULL;
    const lv_status st = lv_mission_def_parse((const char *)data, size, "fuzz.yaml", LV_FUZZ_DIR,
                                              &m, &err);
    /* The contract: a mission exactly on success, and a terminated message on failure. */
    if ((st == LV_OK) != (m != NULL) || (st != LV_OK && memchr(err.msg, '\0', sizeof err.msg)
                                                            == NULL))
        __builtin_trap();
    if (m != NULL) { /* touch the structure the runner will read */
        for (size_t i = 0; i < m->n_phases; i++)
            if (m->phases[i].parent >= (int)i)
                __builtin_trap(); /* parents precede children */
        (void)lv_mission_def_param(m, "start_h", 0.0);
        lv_mission *mission = NULL;
        const lv_status ls = lv_mission_from_def(m, &mission, &err);
        if ((ls == LV_OK) != (mission != NULL) ||
            (ls != LV_OK && memchr(err.msg, '\0', sizeof err.msg) == NULL))
            __builtin_trap();
        lv_mission_free(mission);
    }
    return 0;
}
