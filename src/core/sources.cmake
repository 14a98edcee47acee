list(APPEND LV_SOURCES
  src/core/status.c
  src/core/abi.c
  src/core/names.c
  src/core/data.c
  src/core/utc.c
  src/core/root.c
  src/core/random.c)
include(src/core/tables.cmake OPTIONAL)
# data.c: the install prefix's datadir is the last place searched for data files; the
# others are found at run time (lvsim/lv_data.h).
include(GNUInstallDirs)
set_source_files_properties(src/core/data.c PROPERTIES
  COMPILE_DEFINITIONS "LV_INSTALL_DATADIR=\"${CMAKE_INSTALL_FULL_DATADIR}/lvsim\"")
