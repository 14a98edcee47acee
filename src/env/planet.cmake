# Planet, frames and gravity (owner: planet/frames/gravity). The shipped gravity
# coefficients are found through LV_GRAVITY_DATA_DIR (the source tree's data/gravity).
list(APPEND LV_SOURCES
  src/env/planet.c
  src/env/frames.c
  src/env/gravity.c
  src/env/gravity_sh.c)
set_source_files_properties(src/env/gravity.c PROPERTIES
  COMPILE_DEFINITIONS "LV_GRAVITY_DATA_DIR=\"${PROJECT_SOURCE_DIR}/data/gravity\"")
