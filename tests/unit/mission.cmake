# Mission files: the YAML parser and its validation (tests/missions/*.yaml, tables in
# tests/missions/data). The libFuzzer target and its bounded ctest: fuzz/fuzz.cmake.
lv_add_unit_test(test_mission_parse unit/test_mission_parse.c)
target_compile_definitions(test_mission_parse PRIVATE
  LV_MISSION_DIR="${PROJECT_SOURCE_DIR}/tests/missions")
include(${PROJECT_SOURCE_DIR}/fuzz/fuzz.cmake OPTIONAL)
# The runner's test writes summary.json too (liblvsim_post) and reads it with cJSON.
lv_add_unit_test(test_runner unit/test_runner.c)
target_link_libraries(test_runner PRIVATE lvsim_post_static)
# The environment a mission file defines (planet constants, flat-world air, wind forms, aero
# tables), flown through whole missions against closed forms.
lv_add_unit_test(test_mission_env unit/test_mission_env.c)
target_link_libraries(test_mission_env PRIVATE PkgConfig::MATIO) # writes struct .mat files
# One mission, many runs: parameters by name, dirty phases, threads against fresh loads.
lv_add_unit_test(test_run unit/test_run.c)
# The cross-type contracts of the phase-model registry, for every registered type (and types
# broken on purpose failing them): trajectory columns, mass state, from_types, hand-offs,
# mission parameters; no type named by a string outside the types and models (src/, cli/).
lv_add_unit_test(test_phase_types unit/test_phase_types.c)
# One convention for units (issue 27): every model's variables, every law key, every example's
# run parameters and phase models: SI strings, dimensionless "1".
lv_add_unit_test(test_units unit/test_units.c)
# A run is right or says why (issue 9): model domains, load-time checks, the propellant book,
# the run order.
lv_add_unit_test(test_checks unit/test_checks.c)
# Default settings give accurate answers (issue 9): a ball drop at lvsim's default method and
# tolerance against an independent integration of the same equations (scipy).
add_test(NAME test_drop
  COMMAND ${LV_PYTHON} ${PROJECT_SOURCE_DIR}/tests/python/check_drop.py
          $<TARGET_FILE:lvsim_cli> ${CMAKE_CURRENT_BINARY_DIR}/drop_out)
# The defaults meet the field's references (issue 24, item 3): a circular orbit after 10
# revolutions within 1 m of the closed form, a sphere with drag over rotating WGS-84 within 1 mm
# of a SciPy DOP853 1e-13 reference (tests/data), a torque-free body's energy and |H| to 1e-8.
add_test(NAME test_defaults
  COMMAND ${LV_PYTHON} ${PROJECT_SOURCE_DIR}/tests/python/check_defaults.py
          $<TARGET_FILE:lvsim_cli> ${CMAKE_CURRENT_BINARY_DIR}/defaults_out)
# A phase ends on any variable of its model or after a duration (issue 12).
lv_add_unit_test(test_ends unit/test_ends.c)
# a steering law losing its reference, an end behind the start: the phase fails at once
lv_add_unit_test(test_guards unit/test_guards.c)
# Guidance laws against known answers (issue 12): gravity turn, linear tangent, throttle
# limits, landing burn, heading law, attitude frames; bad input.
lv_add_unit_test(test_guidance unit/test_guidance.c)
target_compile_definitions(test_guidance PRIVATE
  LV_MISSION_DIR="${PROJECT_SOURCE_DIR}/tests/missions")
# Targeting and optimisation over the phase tree (issue 13): closed-form shots, a poor start,
# a failing trial point, no solution, the maximum range, the converged file, branches, the API,
# bad targeting sections.
lv_add_unit_test(test_target unit/test_target.c)
lv_add_unit_test(test_target_path unit/test_target_path.c)
# Monte Carlo dispersions and campaigns (issue 16): the generator, streams, correlations, the
# analytic Isp scatter, table dispersions, bad inputs (tests/missions/mc).
lv_add_unit_test(test_campaign unit/test_campaign.c)
target_link_libraries(test_campaign PRIVATE lvsim_post_static PkgConfig::SQLITE3)
# No silent wrong answer (issue 22, item 6): tolerances, angles, starts below the ground, name
# lengths and targeting scales refused where they enter, with file:line:column or the rule.
lv_add_unit_test(test_mission_valid unit/test_mission_valid.c)
# Engines by count (issue 27, item 3): n of N engines against the thrust and mass-flow closed
# forms, a landing whose one engine cannot throttle low enough (the saturation event against
# the rocket equation), an engine-out at a time, bad `engines:` / `engine_out:` values.
lv_add_unit_test(test_engines unit/test_engines.c)
lv_add_unit_test(test_flare unit/test_flare.c)
lv_add_unit_test(test_heating unit/test_heating.c)
lv_add_unit_test(test_heat_load unit/test_heat_load.c)
lv_add_unit_test(test_ocp unit/test_ocp.c)
