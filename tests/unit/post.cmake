# Post-processing (src/post, liblvsim_post): the exports and the plots/report. Their tests link
# the static twin lvsim_post_static (internal headers visible) on top of lvsim_static.
include(${CMAKE_CURRENT_LIST_DIR}/post_export.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/post_plot.cmake)
# The one reader of a results folder (src/post/results.c), on hand-made folders.
lv_add_unit_test(test_results unit/test_results.c)
target_link_libraries(test_results PRIVATE lvsim_post_static)
# Run-atomic results folders (src/post/outdir.c) and SHA-256 through their API.
lv_add_unit_test(test_outdir_api unit/test_outdir_api.c)
target_link_libraries(test_outdir_api PRIVATE lvsim_post_static)
# The bodies' timelines (summary.json bodies[].timeline, lv_run_timeline) against the phase
# CSVs with Python's csv and json only: each event once per body, the ends against the phases'
# finals, max-q against the q_dyn column, separations, the run's table and the report
# (six examples, about 5 s).
add_test(NAME test_timeline
  COMMAND ${LV_PYTHON} ${PROJECT_SOURCE_DIR}/tests/python/check_timeline.py
          $<TARGET_FILE:lvsim_cli> ${PROJECT_SOURCE_DIR})
# A jettisoned fairing (a dof3 phase of its own stage, no engines, its drag) falls to its
# impact where an independent RK4 propagation with J2, rotation and drag puts it (about 4 s).
add_test(NAME test_fairing_impact
  COMMAND ${LV_PYTHON} ${PROJECT_SOURCE_DIR}/tests/python/check_fairing_impact.py
          $<TARGET_FILE:lvsim_cli>)
