# Plots and the HTML report: lv_plot_run() on three example missions (test_plot), then the PNGs'
# pixels decoded with Python's zlib: not blank, several colours (test_plot_png).
lv_add_unit_test(test_plot unit/test_plot.c)
target_link_libraries(test_plot PRIVATE lvsim_post_static)
add_test(NAME test_plot_png
  COMMAND ${LV_PYTHON} ${PROJECT_SOURCE_DIR}/tests/unit/plot_png_check.py plot_paper plot_dof3 plot_rlv
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(test_plot PROPERTIES FIXTURES_SETUP lv_plot_outputs)
set_tests_properties(test_plot_png PROPERTIES FIXTURES_REQUIRED lv_plot_outputs)
# The report's key figures (key_figures.json, index.html) recomputed from the CSV files with
# Python's csv and math only, on both examples (about 3 s).
add_test(NAME test_key_figures
  COMMAND ${LV_PYTHON} ${PROJECT_SOURCE_DIR}/tests/python/check_key_figures.py
          $<TARGET_FILE:lvsim_cli> ${PROJECT_SOURCE_DIR})
