# Result sinks. test_io writes io_out/*.mat in the test directory; test_io_dsres
# reads them back with scipy and an independent dsres reader (fixture: running
# test_io_dsres alone runs test_io first).
lv_add_unit_test(test_io ${PROJECT_SOURCE_DIR}/tests/unit/test_io.c)
set_tests_properties(test_io PROPERTIES FIXTURES_SETUP io_result_files)
add_test(NAME test_io_dsres
  COMMAND ${LV_PYTHON} ${PROJECT_SOURCE_DIR}/tests/python/check_dsres.py
          ${CMAKE_CURRENT_BINARY_DIR}/io_out/sine.mat
          ${CMAKE_CURRENT_BINARY_DIR}/io_out/sine_fail.failed.mat
          ${CMAKE_CURRENT_BINARY_DIR}/io_out/empty.failed.mat)
set_tests_properties(test_io_dsres PROPERTIES FIXTURES_REQUIRED io_result_files)
# Temporary name, then rename (src/io/atomic.c): every writer's way of finishing a file.
lv_add_unit_test(test_atomic ${PROJECT_SOURCE_DIR}/tests/unit/test_atomic.c)
# The shortest round-trip number formatter of the CSV files (src/io/numfmt.cc).
lv_add_unit_test(test_numfmt ${PROJECT_SOURCE_DIR}/tests/unit/test_numfmt.c)
