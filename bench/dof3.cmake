# 3-DoF model: ns per right-hand side of the full model, and of its pieces.
add_executable(bench_dof3 ${CMAKE_CURRENT_LIST_DIR}/bench_dof3.c)
target_link_libraries(bench_dof3 PRIVATE lvsim_static)
lv_set_warnings(bench_dof3)
# Guidance: what each steering and throttle law adds to the 3-DoF right-hand side.
add_executable(bench_guidance ${CMAKE_CURRENT_LIST_DIR}/bench_guidance.c)
target_link_libraries(bench_guidance PRIVATE lvsim_static)
lv_set_warnings(bench_guidance)
# 6-DoF rigid body: ns per right-hand side with full aerodynamic moments and one gimballed engine
# (issue 15's target: <= 1 us).
add_executable(bench_dof6 ${CMAKE_CURRENT_LIST_DIR}/bench_dof6.c)
target_link_libraries(bench_dof6 PRIVATE lvsim_static)
lv_set_warnings(bench_dof6)
