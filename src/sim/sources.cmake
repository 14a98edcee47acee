list(APPEND LV_SOURCES src/sim/model.c src/sim/simulate.c)
