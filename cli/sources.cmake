add_executable(lvsim_cli cli/main.c)
set_target_properties(lvsim_cli PROPERTIES OUTPUT_NAME lvsim RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR})
# The core library (run) and the post-processing one (export, plot, report).
target_link_libraries(lvsim_cli PRIVATE lvsim_post lvsim m)
lv_set_warnings(lvsim_cli)
