# N-D lookup tables: evaluation (table.c). Their CSV/MAT loaders are I/O: src/io/table_load.c.
list(APPEND LV_SOURCES
  src/core/table.c
  src/core/table_unit.c)
