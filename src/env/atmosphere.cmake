# Atmosphere models (U.S. Standard Atmosphere 1976, exponential, table from a file) and their
# registry; wind tables.
list(APPEND LV_SOURCES
  src/env/atmosphere.c
  src/env/atmosphere_upper.c
  src/env/atmosphere_exp.c
  src/env/atmosphere_table.c
  src/env/atmosphere_registry.c
  src/env/wind.c)
