list(APPEND LV_SOURCES
  src/mission/yaml_tree.c
  src/mission/parse.c
  src/mission/runner.c
  src/mission/summary.c
  src/mission/compare.c)
