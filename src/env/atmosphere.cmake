# Atmosphere models (U.S. Standard Atmosphere 1976, exponential, table from a file) and their
# registry; wind tables, profiles, gusts and turbulence.
list(APPEND LV_SOURCES
  src/env/atmosphere.c
  src/env/atmosphere_upper.c
  src/env/atmosphere_exp.c
  src/env/atmosphere_table.c
  src/env/atmosphere_profile.c
  src/env/profile.c
  src/env/atmosphere_registry.c
  src/env/wind.c
  src/env/turbulence.c
  src/env/perturbation.c)

# The US76 upper-atmosphere table (86-1000 km) is integrated once, at build time, by a small
# host program built from the same code (atmosphere_us76_gen.c + atmosphere_upper.c), and
# compiled into the library: no process integrates it at run time (docs/atmosphere.md).
add_executable(lvsim_us76_gen
  src/env/atmosphere_us76_gen.c src/env/atmosphere_upper.c src/core/status.c)
target_include_directories(lvsim_us76_gen PRIVATE ${PROJECT_SOURCE_DIR}/include
                                                  ${PROJECT_SOURCE_DIR}/src)
target_link_libraries(lvsim_us76_gen PRIVATE m)
lv_set_warnings(lvsim_us76_gen)
set(LV_US76_TABLE ${PROJECT_BINARY_DIR}/generated/us76_upper_table.c)
add_custom_command(
  OUTPUT ${LV_US76_TABLE}
  COMMAND ${CMAKE_COMMAND} -E make_directory ${PROJECT_BINARY_DIR}/generated
  COMMAND lvsim_us76_gen ${LV_US76_TABLE}
  DEPENDS lvsim_us76_gen
  COMMENT "Integrating the US76 upper atmosphere (us76_upper_table.c)"
  VERBATIM)
list(APPEND LV_SOURCES ${LV_US76_TABLE})
add_custom_target(lv_generated DEPENDS ${LV_US76_TABLE}) # for targets built outside lv_obj
