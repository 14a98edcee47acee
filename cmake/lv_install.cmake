# lv_install.cmake - the layout of the build tree and of an installation (GNUInstallDirs):
#   bin/lvsim                        the command line (RUNPATH: its own ../lib)
#   lib/liblvsim.so.0                shared libraries, with SOVERSION
#   include/lvsim/*.h                the public headers
#   share/lvsim/{gravity,viewer}/    run-time data, found next to the library (src/core/data.c)
#   lib/cmake/lvsim/                 find_package(lvsim) -> lvsim::lvsim
# The build tree gets the same relative layout (build/<libdir>/liblvsim.so,
# build/share/lvsim/), so data are found there as in an installation, without paths
# compiled in. Included once, at the end of CMakeLists.txt, after the targets exist.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# Libraries and programs to install: a shared library goes into the package (lvsim::<name>).
set(LV_INSTALL_TARGETS lvsim lvsim_cli)
if(TARGET lvsim_post)
  list(APPEND LV_INSTALL_TARGETS lvsim_post)
endif()

set(LV_INSTALL_LIBS "")
set(LV_INSTALL_PROGRAMS "")
foreach(t IN LISTS LV_INSTALL_TARGETS)
  get_target_property(_lv_type ${t} TYPE)
  if(_lv_type STREQUAL "SHARED_LIBRARY")
    list(APPEND LV_INSTALL_LIBS ${t})
  elseif(_lv_type STREQUAL "EXECUTABLE")
    list(APPEND LV_INSTALL_PROGRAMS ${t})
  else()
    message(FATAL_ERROR "lv_install.cmake: ${t} is a ${_lv_type}; expected shared libraries "
                        "and executables")
  endif()
endforeach()

# ---- build tree --------------------------------------------------------------------------

# Shared libraries in build/<libdir> so that <libdir>/../share/lvsim is build/share/lvsim.
set_target_properties(${LV_INSTALL_LIBS} PROPERTIES
  LIBRARY_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/${CMAKE_INSTALL_LIBDIR})

# data/ and viewer/ copied to build/share/lvsim at every build (only changed files), before
# any library, so tests and the CLI find them; the same list is installed below.
add_custom_target(lv_data ALL
  COMMAND ${CMAKE_COMMAND} -DLV_SRC=${PROJECT_SOURCE_DIR}
          -DLV_DST=${PROJECT_BINARY_DIR}/share/lvsim -P ${CMAKE_CURRENT_LIST_DIR}/lv_data_files.cmake
  COMMENT "Copying data/ and viewer/ to ${PROJECT_BINARY_DIR}/share/lvsim"
  VERBATIM)
foreach(t IN LISTS LV_INSTALL_TARGETS ITEMS lvsim_static)
  if(TARGET ${t})
    add_dependencies(${t} lv_data)
  endif()
endforeach()

# ---- installation ------------------------------------------------------------------------

# Include directories of the source tree hold only while building: the installed targets
# use <prefix>/include (INCLUDES DESTINATION below).
foreach(t IN LISTS LV_INSTALL_LIBS)
  get_target_property(_lv_inc ${t} INTERFACE_INCLUDE_DIRECTORIES)
  if(_lv_inc)
    set(_lv_wrapped "")
    foreach(d IN LISTS _lv_inc)
      if(d MATCHES "^\\$<")
        list(APPEND _lv_wrapped "${d}")
      else()
        list(APPEND _lv_wrapped "$<BUILD_INTERFACE:${d}>")
      endif()
    endforeach()
    set_property(TARGET ${t} PROPERTY INTERFACE_INCLUDE_DIRECTORIES "${_lv_wrapped}")
  endif()
endforeach()

# RUNPATH: an installed program finds the installed libraries from its own folder (and a
# library its sibling libraries), wherever the prefix is moved; none for a system libdir.
file(RELATIVE_PATH _lv_bin_to_lib ${CMAKE_INSTALL_FULL_BINDIR} ${CMAKE_INSTALL_FULL_LIBDIR})
if(NOT CMAKE_INSTALL_FULL_LIBDIR IN_LIST CMAKE_C_IMPLICIT_LINK_DIRECTORIES)
  set_target_properties(${LV_INSTALL_PROGRAMS} PROPERTIES INSTALL_RPATH "$ORIGIN/${_lv_bin_to_lib}")
  set_target_properties(${LV_INSTALL_LIBS} PROPERTIES INSTALL_RPATH "$ORIGIN")
endif()

install(TARGETS ${LV_INSTALL_LIBS} EXPORT lvsimTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS ${LV_INSTALL_PROGRAMS} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The figures' module, where liblvsim_post looks for it: <libdir>/lvsim/lvsim_plot.so.
if(TARGET lvsim_plot)
  install(TARGETS lvsim_plot LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/lvsim)
endif()
# The FMU binary, where lv_fmu_export looks for it: <libdir>/lvsim/lvsim_fmu.so.
if(TARGET lvsim_fmu)
  install(TARGETS lvsim_fmu LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/lvsim)
endif()
# The MPI side of `lvsim mc`, where cmd_mc.c looks for it: <libdir>/lvsim/lvsim_mpi.so.
if(TARGET lvsim_mpi)
  install(TARGETS lvsim_mpi LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/lvsim)
endif()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/lvsim DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  FILES_MATCHING PATTERN "*.h")

# share/lvsim: the files of the build tree's share/lvsim, from the source tree, with the
# CesiumJS build if viewer/node_modules holds it at install time.
if(IS_ABSOLUTE "${CMAKE_INSTALL_DATADIR}")
  set(_lv_datadir "${CMAKE_INSTALL_DATADIR}/lvsim")
else()
  set(_lv_datadir "\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_DATADIR}/lvsim")
endif()
install(CODE "set(LV_MODE INSTALL)
  set(LV_SRC \"${PROJECT_SOURCE_DIR}\")
  set(LV_DST \"${_lv_datadir}\")
  include(\"${CMAKE_CURRENT_LIST_DIR}/lv_data_files.cmake\")")

# The CMake package: lvsimConfig.cmake, lvsimConfigVersion.cmake, lvsimTargets.cmake.
set(LV_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/lvsim)
set(LV_PACKAGE_DATADIR ${CMAKE_INSTALL_DATADIR}/lvsim)
install(EXPORT lvsimTargets NAMESPACE lvsim:: DESTINATION ${LV_CMAKE_DIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/lvsimConfig.cmake.in
  ${PROJECT_BINARY_DIR}/lvsimConfig.cmake
  INSTALL_DESTINATION ${LV_CMAKE_DIR}
  PATH_VARS LV_PACKAGE_DATADIR)
# 0.x: a minor version may change the API
write_basic_package_version_file(${PROJECT_BINARY_DIR}/lvsimConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/lvsimConfig.cmake ${PROJECT_BINARY_DIR}/lvsimConfigVersion.cmake
  DESTINATION ${LV_CMAKE_DIR})

# The install test: a copy of the source tree configured, built and installed, then deleted;
# a consumer built with find_package(lvsim) runs a mission from the prefix (~1 min).
if(LV_BUILD_TESTS)
  add_test(NAME test_install
           COMMAND ${PROJECT_SOURCE_DIR}/tests/install/test_install.sh ${PROJECT_SOURCE_DIR}
                   ${PROJECT_BINARY_DIR} ${CMAKE_COMMAND})
  set_tests_properties(test_install PROPERTIES LABELS "install;no-asan" TIMEOUT 600)
  # The README's `make demo` in a clean copy of the sources: short output, Debian's libraries
  # only, a failed build shows its log (~1 min; 77: skipped without npm).
  add_test(NAME test_fresh_clone
           COMMAND ${PROJECT_SOURCE_DIR}/tests/install/test_fresh_clone.sh ${PROJECT_SOURCE_DIR})
  # RESOURCE_LOCK npm: never beside test_viewer, which may run viewer/install.sh too.
  set_tests_properties(test_fresh_clone PROPERTIES LABELS "install;no-asan" TIMEOUT 600
                       SKIP_RETURN_CODE 77 RESOURCE_LOCK npm)
endif()
