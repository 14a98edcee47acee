list(APPEND LV_SOURCES src/models/basic.c)
