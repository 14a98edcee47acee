list(APPEND LV_SOURCES src/integrate/integrator.c src/integrate/erk.c)
