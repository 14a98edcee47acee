list(APPEND LV_SOURCES src/integrate/integrator.c src/integrate/erk.c)
list(APPEND LV_DL_SOURCES src/integrate/cvode_dl.c src/integrate/arkode_dl.c)
