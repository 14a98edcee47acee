# libFuzzer targets, one per input surface (docs/fuzzing.md): the mission parser, the table files
# (CSV, MAT; atmosphere, wind, aerodynamic and thrust tables, gravity coefficients), the
# command line's arguments, an FMU's fmi2 calls and the results-folder reader. Built with clang
# whatever compiler the project uses, from clang-compiled copies of the library's sources
# (build/fuzz/obj/, one object per source, header dependencies tracked), all by the one target
# lv_fuzz; a bounded run of each is a ctest `fuzz_<name>` (labels fuzz and no-asan: the ASan
# suite, built with gcc, skips them). Only when clang's libFuzzer runtime is available
# (Debian: clang, libclang-rt-14-dev). `make fuzz` runs each longer (docs/fuzzing.md). From
# tests/unit/mission.cmake.
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
  find_program(LV_CLANGXX NAMES clang++-14 clang++ REQUIRED)
  set(_fz ${CMAKE_BINARY_DIR}/fuzz)
  file(MAKE_DIRECTORY ${_fz}/obj)
  get_target_property(_dbx dragonbox::dragonbox INTERFACE_INCLUDE_DIRECTORIES)
  set(_inc -I${PROJECT_SOURCE_DIR}/include -I${PROJECT_SOURCE_DIR}/src -I${_dbx}
           -I${LV_FASTFLOAT_INCLUDE} -I${RANDOM123_INCLUDE_DIR})
  foreach(_d ${YAML_INCLUDE_DIRS} ${MATIO_INCLUDE_DIRS} ${HDF5_INCLUDE_DIRS} ${CJSON_INCLUDE_DIRS}
             ${NLOPT_INCLUDE_DIRS} ${IPOPT_INCLUDE_DIRS} ${NETTLE_INCLUDE_DIRS} ${SQLITE3_INCLUDE_DIRS}
             ${LIBZIP_INCLUDE_DIRS} ${ERFA_INCLUDE_DIRS})
    list(APPEND _inc -I${_d})
  endforeach()
  set(_san -g -O1 -fno-omit-frame-pointer -fsanitize=fuzzer-no-link,address,undefined
           -fno-sanitize-recover=undefined -ffp-contract=off)
  set(_warn -Wall -Wextra -Wshadow -Wconversion -Wno-sign-conversion -Wformat=2)
  set(_cflags -std=c11 ${_san} ${_warn} -Wstrict-prototypes -Wmissing-prototypes
              -DLV_MATIO_SONAME="${LV_MATIO_SONAME}" -DLV_HDF5_SONAME="${LV_HDF5_SONAME}"
              -DLV_CVODE_SONAME="${LV_CVODE_SONAME}" -DLV_ARKODE_SONAME="${LV_ARKODE_SONAME}")
  set(_cxxflags -std=c++17 ${_san} ${_warn} -fno-exceptions -fno-rtti)

  # _lv_fuzz_objects(OUT SET DEFS sources...): each source compiled once into
  # build/fuzz/obj/SET/, with the source's own COMPILE_DEFINITIONS (src/core/data.c's datadir)
  function(_lv_fuzz_objects out set defs)
    set(_objs)
    foreach(_f ${ARGN})
      if(IS_ABSOLUTE ${_f})
        file(RELATIVE_PATH _rel ${CMAKE_BINARY_DIR} ${_f}) # generated: the US76 table
        set(_path ${_f})
      else()
        set(_rel ${_f})
        set(_path ${PROJECT_SOURCE_DIR}/${_f})
      endif()
      set(_o ${_fz}/obj/${set}/${_rel}.o)
      get_filename_component(_od ${_o} DIRECTORY)
      file(MAKE_DIRECTORY ${_od})
      get_source_file_property(_sd ${_path} DIRECTORY ${PROJECT_SOURCE_DIR} COMPILE_DEFINITIONS)
      set(_own)
      if(_sd)
        foreach(_d ${_sd})
          list(APPEND _own -D${_d})
        endforeach()
      endif()
      if(_f MATCHES "\\.cc$")
        set(_cmd ${LV_CLANGXX} ${_cxxflags})
      else()
        set(_cmd ${LV_CLANG} ${_cflags})
      endif()
      add_custom_command(OUTPUT ${_o}
        COMMAND ${_cmd} ${defs} ${_own} ${_inc} -MD -MF ${_o}.d -c ${_path} -o ${_o}
        DEPENDS ${_path} DEPFILE ${_o}.d
        COMMENT "fuzz: ${_rel}" VERBATIM)
      list(APPEND _objs ${_o})
    endforeach()
    set(${out} ${_objs} PARENT_SCOPE)
  endfunction()

  # liblvsim (core), liblvsim_post (post: results, exports, campaign, the FMU exporter) and the
  # CLI (its main() left out: fuzz_cli calls cli_main)
  _lv_fuzz_objects(_core_obj lib "-DLV_BUILDING_LIBRARY" ${LV_SOURCES} ${LV_DL_SOURCES})
  _lv_fuzz_objects(_post_obj lib "-DLV_BUILDING_LIBRARY" ${LV_POST_SOURCES} src/post/plot_load.c)
  get_target_property(_cli_src lvsim_cli SOURCES)
  list(FILTER _cli_src EXCLUDE REGEX "mc_mpi\\.c$")
  _lv_fuzz_objects(_cli_obj cli "-DLV_CLI_NO_MAIN" ${_cli_src})
  _lv_fuzz_objects(_fmu_obj lib "-DLV_BUILDING_LIBRARY" src/fmi/fmu.c)
  set(_core_a ${_fz}/liblv_fuzz_core.a)
  set(_post_a ${_fz}/liblv_fuzz_post.a)
  foreach(_pair "core_a;core_obj" "post_a;post_obj")
    list(GET _pair 0 _a)
    list(GET _pair 1 _o)
    add_custom_command(OUTPUT ${_${_a}}
      COMMAND ${CMAKE_COMMAND} -E rm -f ${_${_a}}
      COMMAND ${CMAKE_AR} qcs ${_${_a}} ${_${_o}}
      DEPENDS ${_${_o}} VERBATIM)
  endforeach()

  set(_libs ${YAML_LINK_LIBRARIES} ${NLOPT_LINK_LIBRARIES} ${ERFA_LINK_LIBRARIES}
      -ldl -lpthread -lm)
  set(_post_libs ${CJSON_LINK_LIBRARIES} ${SQLITE3_LINK_LIBRARIES}
      ${LIBZIP_LINK_LIBRARIES})

  # _lv_fuzz_target(NAME HARNESS DEFS... -- LINK...): build/fuzz/fuzz_NAME
  set(LV_FUZZ_BINS)
  function(_lv_fuzz_target name harness)
    cmake_parse_arguments(F "" "" "DEFS;LINK;DEPENDS" ${ARGN})
    set(_bin ${_fz}/fuzz_${name})
    add_custom_command(OUTPUT ${_bin}
      COMMAND ${LV_CLANG} ${_cflags} -fsanitize=fuzzer ${F_DEFS} ${_inc}
              ${PROJECT_SOURCE_DIR}/${harness} ${F_LINK} -o ${_bin}
      DEPENDS ${PROJECT_SOURCE_DIR}/${harness} ${F_DEPENDS}
      COMMENT "Building the libFuzzer target fuzz_${name} with ${LV_CLANG}"
      COMMAND_EXPAND_LISTS VERBATIM)
    set(LV_FUZZ_BINS ${LV_FUZZ_BINS} ${_bin} PARENT_SCOPE)
  endfunction()

  # the mission parser and loader (relative table paths against tests/missions)
  _lv_fuzz_target(mission fuzz/fuzz_mission.c
    DEFS -DLV_FUZZ_DIR="${PROJECT_SOURCE_DIR}/tests/missions"
    LINK ${_core_a} ${_libs} DEPENDS ${_core_a})
  # table files through every reader of them
  _lv_fuzz_target(tables fuzz/fuzz_tables.c
    LINK ${_core_a} ${_libs} DEPENDS ${_core_a})
  # the results-folder reader (post/results.c)
  _lv_fuzz_target(results fuzz/fuzz_results.c
    LINK ${_post_a} ${_core_a} ${_libs} ${_post_libs} DEPENDS ${_post_a} ${_core_a})
  # an FMU's fmi2 calls (src/fmi/fmu.c linked in) on the resources of an FMU exported by
  # `lvsim fmu` from a small example phase (unpacked into build/fuzz/fmu/)
  set(_fmu_dir ${_fz}/fmu)
  set(_fmu_cfg ${_fmu_dir}/resources/lvsim-fmu.txt)
  add_custom_command(OUTPUT ${_fmu_cfg}
    COMMAND ${CMAKE_COMMAND} -E rm -rf ${_fmu_dir}
    COMMAND $<TARGET_FILE:lvsim_cli> fmu ${PROJECT_SOURCE_DIR}/examples/sounding-rocket/mission.yaml
            --phase boost -o ${_fz}/fuzz_fmu.fmu --force
    COMMAND unzip -q -o ${_fz}/fuzz_fmu.fmu -d ${_fmu_dir}
    DEPENDS lvsim_cli lvsim_fmu ${PROJECT_SOURCE_DIR}/examples/sounding-rocket/mission.yaml
    COMMENT "fuzz: the FMU of examples/sounding-rocket's first phase" VERBATIM)
  _lv_fuzz_target(fmu fuzz/fuzz_fmu.c
    DEFS -DLV_FUZZ_FMU_DIR="${_fmu_dir}"
    LINK ${_fmu_obj} ${_post_a} ${_core_a} ${_libs} ${_post_libs}
    DEPENDS ${_fmu_obj} ${_post_a} ${_core_a} ${_fmu_cfg})
  # the command line: every command's arguments, dispatched by cli_main (cli/main.c); what
  # would run long or leave the process (simulations, campaigns, targeting, the results
  # folder, exporting, serving) replaced by a failure (fuzz/fuzz_cli.c)
  set(_wrap lv_outdir_begin lv_outdir_open lv_outdir_open_live lv_run_execute lv_simulate lv_mission_compare
            lv_campaign_run lv_campaign_stats lv_campaign_plot lv_target_solve lv_fmu_export
            lv_plot_run lv_export_run lv_export_run_report bind fork execv)
  list(TRANSFORM _wrap PREPEND "-Wl,--wrap=")
  _lv_fuzz_target(cli fuzz/fuzz_cli.c
    DEFS -DLV_FUZZ_DIR="${PROJECT_SOURCE_DIR}" -I${PROJECT_SOURCE_DIR}/cli
    LINK ${_wrap} ${_cli_obj} ${_post_a} ${_core_a} ${_libs} ${_post_libs}
    DEPENDS ${_cli_obj} ${_post_a} ${_core_a})

  add_custom_target(lv_fuzz ALL DEPENDS ${LV_FUZZ_BINS})
  add_dependencies(lv_fuzz lv_generated) # the US76 table (src/env/atmosphere.cmake)
  # ctest: the mission parser 20 s, the others 6 s each (each first replays its corpus)
  foreach(_t mission tables results fmu cli)
    set(_secs 6)
    if(_t STREQUAL "mission")
      set(_secs 20)
    endif()
    add_test(NAME fuzz_${_t} COMMAND ${PROJECT_SOURCE_DIR}/fuzz/run.sh ${_fz}/fuzz_${_t} ${_secs})
    set_tests_properties(fuzz_${_t} PROPERTIES LABELS "fuzz;no-asan" TIMEOUT 180)
  endforeach()
endif()
