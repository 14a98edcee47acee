list(APPEND LV_SOURCES
  src/core/status.c
  src/core/names.c)
include(src/core/tables.cmake OPTIONAL)
