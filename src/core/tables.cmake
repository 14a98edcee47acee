# N-D lookup tables: evaluation (table.c) and CSV/MAT loaders (table_load.c, libmatio).
list(APPEND LV_SOURCES
  src/core/table.c
  src/core/table_load.c)
