# FMI 2.0 export (docs/fmi.md): test_fmu exports FMUs with `lvsim fmu`, unpacks them (unzip),
# checks modelDescription.xml (tests/fmi/check_model_description.py, Python's xml.etree), and
# simulates them with an importer of its own (dlopen; Model Exchange and Co-Simulation) against
# lv_simulate of the same phases. test_fmu_cli: bad input to `lvsim fmu`.
lv_add_unit_test(test_fmu unit/test_fmu.c)
target_compile_definitions(test_fmu PRIVATE LV_LVSIM="$<TARGET_FILE:lvsim_cli>")
target_link_libraries(test_fmu PRIVATE ${CMAKE_DL_LIBS})
add_dependencies(test_fmu lvsim_cli lvsim_fmu)
set_tests_properties(test_fmu PROPERTIES TIMEOUT 300)
add_test(NAME test_fmu_cli COMMAND ${PROJECT_SOURCE_DIR}/tests/cli/test_fmu_cli.sh
         $<TARGET_FILE:lvsim_cli> ${PROJECT_SOURCE_DIR})
# Issue 27: an FMI 2.0 importer written from the standard's text alone (tests/fmi/fmi2_importer.c,
# nothing of lvsim included) runs the examples' phases in Model Exchange (the pseudo-code of FMI
# 2.0.4 section 3.2.4, RK4 and Euler) and Co-Simulation against `lvsim run`; and the FMU binary
# needs only libc and libm, exports only fmi2* (tests/fmi/check_fmu_binary.sh).
add_executable(fmi2_importer ${PROJECT_SOURCE_DIR}/tests/fmi/fmi2_importer.c)
target_link_libraries(fmi2_importer PRIVATE ${CMAKE_DL_LIBS} m)
lv_set_warnings(fmi2_importer)
add_test(NAME test_fmi2_importer
         COMMAND ${LV_PYTHON} ${PROJECT_SOURCE_DIR}/tests/fmi/check_importer.py
                 $<TARGET_FILE:lvsim_cli> $<TARGET_FILE:fmi2_importer> ${PROJECT_SOURCE_DIR})
# every phase of every example (53 phases, ~60 s); not under the sanitizers, for CI's time
# (test_fmu runs the FMU's fmi2 calls there)
set_tests_properties(test_fmi2_importer PROPERTIES TIMEOUT 600 LABELS no-asan)
# (not under the sanitizers: their runtime is then among the binary's NEEDED libraries)
if(NOT LV_SANITIZE)
  add_test(NAME test_fmu_binary COMMAND ${PROJECT_SOURCE_DIR}/tests/fmi/check_fmu_binary.sh
           $<TARGET_FILE:lvsim_cli> ${PROJECT_SOURCE_DIR})
endif()
