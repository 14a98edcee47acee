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
