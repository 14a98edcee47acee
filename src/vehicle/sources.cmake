list(APPEND LV_SOURCES
  src/vehicle/engine.c
  src/vehicle/aero.c)
