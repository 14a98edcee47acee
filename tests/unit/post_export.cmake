# Trajectory exports. test_export runs two example missions into export_out/{paper,dof3} in
# the test directory, exports them, and exports export_out/names (a copy of the paper folder
# with XML and CSV metacharacters in its names); test_export_formats checks the documents
# with Python (fixture: running test_export_formats alone runs test_export first).
lv_add_unit_test(test_export ${PROJECT_SOURCE_DIR}/tests/unit/test_export.c)
target_link_libraries(test_export PRIVATE lvsim_post_static)
set_tests_properties(test_export PROPERTIES FIXTURES_SETUP export_files)
add_test(NAME test_export_formats
  COMMAND ${LV_PYTHON} ${PROJECT_SOURCE_DIR}/tests/python/check_exports.py
          ${CMAKE_CURRENT_BINARY_DIR}/export_out/paper
          ${CMAKE_CURRENT_BINARY_DIR}/export_out/dof3
          ${CMAKE_CURRENT_BINARY_DIR}/export_out/names)
set_tests_properties(test_export_formats PROPERTIES FIXTURES_REQUIRED export_files)
# The CZML vehicle models' orientation against the attitude in the result files
# (examples/two-stage-6dof: its 6-DoF quaternion and a 3-DoF phase's alpha, beta, mu).
lv_add_unit_test(test_czml_attitude ${PROJECT_SOURCE_DIR}/tests/unit/test_czml_attitude.c)
target_link_libraries(test_czml_attitude PRIVATE lvsim_post_static)
