# Gravity evaluation cost (ns per call) by model and degree.
add_executable(bench_gravity bench_gravity.c)
target_link_libraries(bench_gravity PRIVATE lvsim_static)
lv_set_warnings(bench_gravity)
# The instantaneous impact point (issue 28): ns per output row, propagated and conic alone.
add_executable(bench_iip bench_iip.c)
target_link_libraries(bench_iip PRIVATE lvsim_static)
lv_set_warnings(bench_iip)
# Launch-day environment (issue 28): what gusts and Dryden turbulence add to the 3-DoF
# right-hand side, drawing a realisation, the heat-flux outputs per row.
add_executable(bench_disturbance bench_disturbance.c)
target_link_libraries(bench_disturbance PRIVATE lvsim_static)
lv_set_warnings(bench_disturbance)
