# FMI 2.0 export (issue 17, docs/fmi.md). The exporter (export.c, lv_fmu.h) is part of
# liblvsim_post and writes the archive with libzip; fmu_phase.c (the phase made ready: mission,
# ancestors, start values) is shared by the exporter and the FMU binary.
# libzip is loaded when the first archive is written (src/fmi/zip_dl.c, io/dl_lib.h).
list(APPEND LV_POST_SOURCES src/fmi/export.c src/fmi/fmu_phase.c src/fmi/zip_dl.c)
