# Atmosphere models (U.S. Standard Atmosphere 1976, exponential) and their registry.
list(APPEND LV_SOURCES
  src/env/atmosphere.c
  src/env/atmosphere_upper.c
  src/env/atmosphere_exp.c
  src/env/atmosphere_registry.c)
