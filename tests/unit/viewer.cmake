# The 3-D viewer (viewer/): end-to-end test in headless Chromium (Debian's chromium driven by
# playwright-core from viewer/node_modules, installed by viewer/install.sh on first run).
# Exit 77 = skipped, only when chromium cannot start. LVSIM lets it also test a real run
# exported by `lvsim export` when the CLI has that command, and a run of two-stage-6dof for the
# vehicle models (about 200 s alone in software WebGL: the timeout leaves room for a busy box).
find_program(LV_NODE node)
if(LV_NODE)
  add_test(NAME test_viewer COMMAND ${LV_NODE} ${PROJECT_SOURCE_DIR}/tests/viewer/test_viewer.js
           WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
  set_tests_properties(test_viewer PROPERTIES
    ENVIRONMENT "LV_SOURCE_DIR=${PROJECT_SOURCE_DIR};LVSIM=$<TARGET_FILE:lvsim_cli>;LV_VIEWER_OUT=${CMAKE_CURRENT_BINARY_DIR}/viewer"
    SKIP_RETURN_CODE 77
    TIMEOUT 600
    RESOURCE_LOCK npm
    LABELS "viewer;no-asan")
else()
  message(STATUS "node not found: test_viewer not registered (the viewer's test needs Node.js >= 18)")
endif()
# `lvsim view`'s server over HTTP: the token, the Host check, no listing, no symlink out of
# the folder, no '..', GET and HEAD only, nothing written (a stand-in CesiumJS: a few seconds).
add_test(NAME test_view_server COMMAND ${LV_PYTHON} ${PROJECT_SOURCE_DIR}/tests/viewer/test_view_server.py
         $<TARGET_FILE:lvsim_cli> ${PROJECT_SOURCE_DIR})
set_tests_properties(test_view_server PROPERTIES TIMEOUT 60 LABELS viewer)
