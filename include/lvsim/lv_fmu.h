/* lv_fmu.h - export one phase of a mission as an FMI 2.0 FMU (Model Exchange and
 * Co-Simulation in one archive): `lvsim fmu`, docs/fmi.md.
 *
 * The archive (a zip file, written with libzip) holds
 *   modelDescription.xml                 the phase model's variables (states, derivatives,
 *                                        parameters, outputs) with units, start and nominal
 *                                        values, the event indicators, ModelStructure
 *   binaries/linux64/<id>.so             the FMU binary (lvsim_fmu.so: the library linked in)
 *   resources/lvsim-fmu.txt              which mission file and phase, the GUID
 *   resources/mission/...                the mission file and every data file it names, with
 *                                        their relative layout
 * Part of liblvsim_post. */
#ifndef LVSIM_LV_FMU_H
#define LVSIM_LV_FMU_H

#include <stddef.h>

#include "lvsim/lv_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct lv_fmu_options {
    /* The FMU binary to put into the archive; NULL: lvsim_fmu.so in the folder "lvsim" next
     * to liblvsim_post (build/lib/lvsim/, <prefix>/lib/lvsim/). */
    const char *binary;
    /* The modelIdentifier (a C identifier; the binary's name in the archive); NULL: made of
     * the mission's and the phase's names ("kourou_leo_ascent"). */
    const char *model_identifier;
} lv_fmu_options;

typedef struct lv_fmu_info {
    char model_identifier[128];
    char guid[40];                /* "{xxxxxxxx-xxxx-xxxx-xxxx-xxxxxxxxxxxx}" */
    size_t n_states, n_params, n_outputs, n_event_indicators;
    size_t n_files;               /* the mission file and its data files in resources/ */
    double start_time, stop_time; /* s: the phase's start and its time limit */
} lv_fmu_info;

/* Writes the FMU of phase `phase` of the mission file `mission_path` to `fmu_path` (through
 * "<fmu_path>.tmp", renamed at the end). The phase's ancestors are simulated to give a child
 * phase its start state. `opt` and `info` may be NULL. Errors: LV_ERR_INPUT / LV_ERR_IO /
 * LV_ERR_NOTFOUND with a message naming the mission file, the phase (an unknown one lists
 * the phases), the data file or the output path; LV_ERR_SOLVER when an ancestor phase fails. */
LV_API lv_status lv_fmu_export(const char *mission_path, const char *phase, const char *fmu_path,
                               const lv_fmu_options *opt, lv_fmu_info *info, lv_err *err);

#ifdef __cplusplus
}
#endif
#endif
