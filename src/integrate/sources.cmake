list(APPEND LV_SOURCES src/integrate/integrator.c src/integrate/erk.c
  src/integrate/cvode_dl.c src/integrate/arkode_dl.c)
