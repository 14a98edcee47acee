# Planet, frames and gravity (owner: planet/frames/gravity). The shipped gravity
# coefficients are data file gravity/egm2008_n20.gfc, found at run time (core/data.c).
list(APPEND LV_SOURCES
  src/env/planet.c
  src/env/frames.c
  src/env/gravity.c
  src/env/gravity_sh.c)
