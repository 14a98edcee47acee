list(APPEND LV_SOURCES src/models/basic.c)
list(APPEND LV_SOURCES src/models/flat.c)
