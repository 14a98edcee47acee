# libFuzzer target for the mission parser (fuzz/fuzz_mission.c), built with clang whatever
# compiler the project uses, and a bounded run registered as ctest `fuzz_mission` (labels
# fuzz and no-asan: the ASan suite, built with gcc, skips it). Only when clang's libFuzzer
# runtime is available (Debian: clang, libclang-rt-14-dev). `make fuzz` runs it longer.
# Included from tests/unit/mission.cmake.
find_program(LV_CLANG NAMES clang-14 clang)
if(LV_CLANG AND NOT DEFINED LV_HAVE_LIBFUZZER)
  set(_probe ${CMAKE_BINARY_DIR}/fuzz_probe)
  file(WRITE ${_probe}.c
    "#include <stddef.h>\n#include <stdint.h>\n"
    "int LLVMFuzzerTestOneInput(const uint8_t *d, size_t n);\n"
    "int LLVMFuzzerTestOneInput(const uint8_t *d, size_t n) { (void)d; (void)n; return 0; }\n")
  execute_process(COMMAND ${LV_CLANG} -fsanitize=fuzzer,address,undefined ${_probe}.c -o ${_probe}
                  RESULT_VARIABLE _rc OUTPUT_QUIET ERROR_QUIET)
  if(_rc EQUAL 0)
    set(LV_HAVE_LIBFUZZER ON CACHE BOOL "clang can link libFuzzer")
  else()
    set(LV_HAVE_LIBFUZZER OFF CACHE BOOL "clang can link libFuzzer")
  endif()
  message(STATUS "libFuzzer (${LV_CLANG}): ${LV_HAVE_LIBFUZZER}")
endif()

if(LV_HAVE_LIBFUZZER)
  # The library's sources that loading a mission uses (checking a root phase's start state
  # sets up its simulation: SUNDIALS too), without runs, targeting and post-processing (NLopt,
  # cJSON, PLplot).
  set(_src ${LV_SOURCES})
  list(FILTER _src EXCLUDE REGEX "^src/(mission/(run|run_estimate|phase_types_api|compare)\\.c|post/|target/)")
  list(PREPEND _src fuzz/fuzz_mission.c)
  # the C++ number formatter and parser (src/io/numfmt.cc, numparse.cc): compiled apart, with
  # clang++, and linked in
  set(_cxx ${_src})
  list(FILTER _cxx INCLUDE REGEX "\\.cc$")
  list(FILTER _src EXCLUDE REGEX "\\.cc$")
  find_program(LV_CLANGXX NAMES clang++-14 clang++ REQUIRED)
  get_target_property(_dbx dragonbox::dragonbox INTERFACE_INCLUDE_DIRECTORIES)
  set(_cxx_obj)
  foreach(_f ${_cxx})
    get_filename_component(_n ${_f} NAME_WE)
    set(_o ${CMAKE_BINARY_DIR}/fuzz/${_n}.o)
    add_custom_command(OUTPUT ${_o}
      COMMAND ${LV_CLANGXX} -std=c++17 -g -O1 -fno-omit-frame-pointer -fno-exceptions -fno-rtti
              -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
              -I${PROJECT_SOURCE_DIR}/include -I${PROJECT_SOURCE_DIR}/src -I${_dbx}
              -I${LV_FASTFLOAT_INCLUDE} -c ${PROJECT_SOURCE_DIR}/${_f} -o ${_o}
      DEPENDS ${PROJECT_SOURCE_DIR}/${_f} VERBATIM)
    list(APPEND _cxx_obj ${_o})
  endforeach()
  file(GLOB_RECURSE _hdr CONFIGURE_DEPENDS RELATIVE ${PROJECT_SOURCE_DIR}
       ${PROJECT_SOURCE_DIR}/src/*.h ${PROJECT_SOURCE_DIR}/include/lvsim/*.h)
  list(TRANSFORM _src PREPEND ${PROJECT_SOURCE_DIR}/ REGEX "^[^/]") # generated: absolute
  list(TRANSFORM _hdr PREPEND ${PROJECT_SOURCE_DIR}/)
  set(_inc -I${PROJECT_SOURCE_DIR}/include -I${PROJECT_SOURCE_DIR}/src)
  foreach(_d ${YAML_INCLUDE_DIRS} ${MATIO_INCLUDE_DIRS} ${HDF5_INCLUDE_DIRS} ${ERFA_INCLUDE_DIRS})
    list(APPEND _inc -I${_d})
  endforeach()
  set(LV_FUZZ_BIN ${CMAKE_BINARY_DIR}/fuzz/fuzz_mission)
  file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/fuzz)
  add_custom_command(OUTPUT ${LV_FUZZ_BIN}
    COMMAND ${LV_CLANG} -std=c11 -g -O1 -fno-omit-frame-pointer
            -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined
            -Wall -Wextra -Wshadow -Wconversion -Wno-sign-conversion -Wstrict-prototypes
            -Wmissing-prototypes -Wformat=2 -ffp-contract=off
            -DLV_FUZZ_DIR="${PROJECT_SOURCE_DIR}/tests/missions" ${_inc} ${_src} ${_cxx_obj}
            -o ${LV_FUZZ_BIN} ${YAML_LINK_LIBRARIES} ${MATIO_LINK_LIBRARIES}
            $<TARGET_FILE:SUNDIALS::cvode_shared> $<TARGET_FILE:SUNDIALS::arkode_shared>
            $<TARGET_FILE:SUNDIALS::nvecserial_shared>
            $<TARGET_FILE:SUNDIALS::sunmatrixdense_shared>
            $<TARGET_FILE:SUNDIALS::sunlinsoldense_shared>
            $<TARGET_FILE:SUNDIALS::sunnonlinsolfixedpoint_shared>
            ${HDF5_LINK_LIBRARIES} ${ERFA_LINK_LIBRARIES} -lm
    DEPENDS ${_src} ${_hdr} ${_cxx_obj}
    COMMENT "Building the libFuzzer target fuzz_mission with ${LV_CLANG}"
    COMMAND_EXPAND_LISTS VERBATIM)
  add_custom_target(fuzz_mission ALL DEPENDS ${LV_FUZZ_BIN})
  add_dependencies(fuzz_mission lv_generated) # the US76 table (src/env/atmosphere.cmake)
  add_test(NAME fuzz_mission
    COMMAND ${PROJECT_SOURCE_DIR}/fuzz/run.sh ${LV_FUZZ_BIN} 20)
  set_tests_properties(fuzz_mission PROPERTIES LABELS "fuzz;no-asan" TIMEOUT 180)
endif()
