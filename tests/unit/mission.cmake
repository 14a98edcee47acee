# Mission files: the YAML parser and its validation (tests/missions/*.yaml, tables in
# tests/missions/data). The libFuzzer target and its bounded ctest: fuzz/fuzz.cmake.
lv_add_unit_test(test_mission_parse unit/test_mission_parse.c)
target_compile_definitions(test_mission_parse PRIVATE
  LV_MISSION_DIR="${PROJECT_SOURCE_DIR}/tests/missions")
include(${PROJECT_SOURCE_DIR}/fuzz/fuzz.cmake OPTIONAL)
# The runner's test writes summary.json too (liblvsim_post) and reads it with cJSON.
lv_add_unit_test(test_runner unit/test_runner.c)
target_link_libraries(test_runner PRIVATE lvsim_post_static)
