# The targeting examples (issue 13): examples/kourou-leo-targeted, kourou-rtls-targeted and
# delta3-gto's mass book; the Delta III optimisations (~4 s) as a test of their own, left out
# of the sanitizer suite (label no-asan).
lv_add_unit_test(test_examples_target unit/test_examples_target.c)
add_test(NAME test_examples_target_optimise COMMAND test_examples_target optimise
         WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(test_examples_target_optimise PROPERTIES
  ENVIRONMENT "LV_SOURCE_DIR=${PROJECT_SOURCE_DIR}" LABELS "no-asan")
