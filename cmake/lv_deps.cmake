# Third-party libraries, all from Debian packages (scripts/install-deps.sh):
#   SUNDIALS 6.4 (CMake config: CVODE, ARKODE), libmatio (and its HDF5), libyaml, NLopt, cJSON,
#   PLplot, Nettle, libzip, ERFA (pkg-config).
# The Python package (python/, docs/python.md) needs no build dependency: ctypes at run time,
# with Debian's /usr/bin/python3 and python3-numpy (pandas, matplotlib, pytest, nbconvert,
# setuptools for the tests and pip installs: tests/python/python.cmake).
find_package(SUNDIALS 6 REQUIRED CONFIG)
find_package(PkgConfig REQUIRED)
pkg_check_modules(MATIO REQUIRED IMPORTED_TARGET matio)
# HDF5 (a libmatio dependency; Debian: libhdf5-dev): src/io/table_load.c reads MAT v7.3
# variables that libmatio cannot classify directly. The serial library, as libmatio's.
pkg_search_module(HDF5 REQUIRED IMPORTED_TARGET hdf5-serial hdf5)
pkg_check_modules(YAML REQUIRED IMPORTED_TARGET yaml-0.1)
# NLopt (Debian: libnlopt-dev): the optimisers of src/target (SLSQP, COBYLA).
pkg_check_modules(NLOPT REQUIRED IMPORTED_TARGET nlopt)
# IPOPT (Debian: coinor-libipopt-dev): the NLP solver of lvsim optimize (src/optimal).
pkg_check_modules(IPOPT REQUIRED ipopt)
pkg_check_modules(CJSON REQUIRED IMPORTED_TARGET libcjson)
pkg_check_modules(PLPLOT REQUIRED IMPORTED_TARGET plplot)  # src/post only: PNG/SVG figures
pkg_check_modules(NETTLE REQUIRED IMPORTED_TARGET nettle)  # SHA-256: src/io/atomic.c (every file
# written, hashed as it goes out), src/post (the manifest), src/fmi
pkg_check_modules(PNG REQUIRED IMPORTED_TARGET libpng)   # src/post only: the figures' PNG files
pkg_check_modules(LIBZIP REQUIRED IMPORTED_TARGET libzip) # src/fmi only: the FMU archive
# SQLite 3 (Debian: libsqlite3-dev): the Monte Carlo campaign database (src/campaign).
pkg_check_modules(SQLITE3 REQUIRED IMPORTED_TARGET sqlite3)
# ERFA (Debian: liberfa-dev; the IAU SOFA algorithms): UTC with its leap seconds, the mission
# epoch (src/core/utc.c, in liblvsim and in liblvsim_post's helpers).
pkg_check_modules(ERFA REQUIRED IMPORTED_TARGET erfa)
find_package(Threads REQUIRED)
# Shortest round-trip digits of doubles for the CSV files (src/io/numfmt.cc); header-only.
find_package(dragonbox 1.1 REQUIRED CONFIG)
# Reading numbers back (src/io/numparse.cc, the results reader): fast_float, header-only.
find_path(LV_FASTFLOAT_INCLUDE fast_float/fast_float.h REQUIRED)
add_library(lv_fastfloat INTERFACE)
target_include_directories(lv_fastfloat INTERFACE ${LV_FASTFLOAT_INCLUDE})

# lv_soname(VAR LIB HINTS): the SONAME of the shared library LIB found (objdump -p), for the
# libraries lvsim loads with dlopen() the first time it needs them (src/io/dl_lib.h).
function(lv_soname var lib hints)
  set(so "lib${lib}.so")
  find_library(LV_${var}_LIB NAMES ${lib} HINTS ${hints})
  if(LV_${var}_LIB AND CMAKE_OBJDUMP)
    execute_process(COMMAND ${CMAKE_OBJDUMP} -p ${LV_${var}_LIB} OUTPUT_VARIABLE _lv_od ERROR_QUIET)
    if(_lv_od MATCHES "SONAME +([^ \n]+)")
      set(so "${CMAKE_MATCH_1}")
    endif()
  endif()
  message(STATUS "lib${lib}, loaded at run time: ${so}")
  set(${var} "${so}" PARENT_SCOPE)
endfunction()

# libmatio is not linked but loaded when a MAT file is first read or written (src/io/matio_dl.c:
# its HDF5 build brings ~40 libraries that cost ~5 ms at every start). Its header is used; its
# SONAME, read from the library found, is what matio_dl.c opens.
lv_soname(LV_MATIO_SONAME matio "${MATIO_LIBRARY_DIRS}")
add_library(lv_matio_headers INTERFACE)
target_include_directories(lv_matio_headers INTERFACE ${MATIO_INCLUDE_DIRS})
target_compile_definitions(lv_matio_headers INTERFACE LV_MATIO_SONAME="${LV_MATIO_SONAME}")
# HDF5 the same way (src/io/hdf5_dl.c): only a MAT v7.3 variable libmatio cannot classify needs
# it. Its headers are used; the SONAME of the library found is what hdf5_dl.c opens.
find_library(LV_HDF5_LIB NAMES hdf5_serial hdf5 HINTS ${HDF5_LIBRARY_DIRS})
get_filename_component(_lv_hdf5_name "${LV_HDF5_LIB}" NAME_WE)
string(REGEX REPLACE "^lib" "" _lv_hdf5_name "${_lv_hdf5_name}")
lv_soname(LV_HDF5_SONAME "${_lv_hdf5_name}" "${HDF5_LIBRARY_DIRS}")
target_include_directories(lv_matio_headers INTERFACE ${HDF5_INCLUDE_DIRS})
target_compile_definitions(lv_matio_headers INTERFACE LV_HDF5_SONAME="${LV_HDF5_SONAME}")
# The libraries only some commands need, loaded on first use the same way (issue 24: together
# about half of the instructions `lvsim --version` spent loading): NLopt (src/target/nlopt_dl.c,
# an optimiser), SQLite (src/campaign/sqlite_dl.c, a campaign), libzip (src/fmi/zip_dl.c, an
# FMU archive; it brings OpenSSL's libcrypto). Their headers are used, never their libraries.
lv_soname(LV_NLOPT_SONAME nlopt "${NLOPT_LIBRARY_DIRS}")
lv_soname(LV_IPOPT_SONAME ipopt "${IPOPT_LIBRARY_DIRS}")
lv_soname(LV_SQLITE3_SONAME sqlite3 "${SQLITE3_LIBRARY_DIRS}")
lv_soname(LV_ZIP_SONAME zip "${LIBZIP_LIBRARY_DIRS}")
# SUNDIALS the same way (src/integrate/cvode_dl.c, arkode_dl.c): a phase integrates with lvsim's
# own Runge-Kutta methods unless it is stiff, and linking CVODE and ARKODE cost every process
# about 806,000 instructions of loading. Debian's libsundials_cvode carries the serial vector,
# the dense matrix and solvers and the context; its headers are used, never the libraries.
lv_soname(LV_CVODE_SONAME sundials_cvode "")
lv_soname(LV_ARKODE_SONAME sundials_arkode "")
add_library(lv_sundials_headers INTERFACE)
target_include_directories(lv_sundials_headers INTERFACE
  $<TARGET_PROPERTY:SUNDIALS::cvode_shared,INTERFACE_INCLUDE_DIRECTORIES>
  $<TARGET_PROPERTY:SUNDIALS::arkode_shared,INTERFACE_INCLUDE_DIRECTORIES>)
target_compile_definitions(lv_sundials_headers INTERFACE LV_CVODE_SONAME="${LV_CVODE_SONAME}"
  LV_ARKODE_SONAME="${LV_ARKODE_SONAME}")
# Nettle the same way (src/io/nettle_dl.c): only a process that writes a file hashes; linked,
# its loading cost every process ~333,000 instructions. Its header is used, never the library.
lv_soname(LV_NETTLE_SONAME nettle "${NETTLE_LIBRARY_DIRS}")
add_library(lv_nettle_headers INTERFACE)
target_include_directories(lv_nettle_headers INTERFACE ${NETTLE_INCLUDE_DIRS})
target_compile_definitions(lv_nettle_headers INTERFACE LV_NETTLE_SONAME="${LV_NETTLE_SONAME}")
add_library(lv_dl_headers INTERFACE)
target_include_directories(lv_dl_headers INTERFACE ${NLOPT_INCLUDE_DIRS} ${SQLITE3_INCLUDE_DIRS}
  ${IPOPT_INCLUDE_DIRS}
  ${LIBZIP_INCLUDE_DIRS})
target_compile_definitions(lv_dl_headers INTERFACE LV_NLOPT_SONAME="${LV_NLOPT_SONAME}"
  LV_IPOPT_SONAME="${LV_IPOPT_SONAME}"
  LV_SQLITE3_SONAME="${LV_SQLITE3_SONAME}" LV_ZIP_SONAME="${LV_ZIP_SONAME}")

# Random123 (Debian: librandom123-dev, header-only): the Philox4x32-10 counter-based generator
# of the dispersions (src/mission/dispersion.c).
find_path(RANDOM123_INCLUDE_DIR Random123/philox.h REQUIRED)
# OpenMPI (Debian: libopenmpi-dev, openmpi-bin), optional: `mpirun -np K lvsim mc` when found.
option(LV_WITH_MPI "Build lvsim mc with MPI when an MPI library is found" ON)
if(LV_WITH_MPI)
  find_package(MPI COMPONENTS C QUIET)
endif()

# The core library, liblvsim.
add_library(lv_deps INTERFACE)
target_link_libraries(lv_deps INTERFACE
  lv_sundials_headers lv_nettle_headers lv_matio_headers lv_dl_headers PkgConfig::YAML PkgConfig::ERFA Threads::Threads
  dragonbox::dragonbox lv_fastfloat ${CMAKE_DL_LIBS} m)
target_include_directories(lv_deps INTERFACE ${RANDOM123_INCLUDE_DIR})

# The post-processing library, liblvsim_post (src/post): cJSON; dlopen for its figures' module.
add_library(lv_post_deps INTERFACE)
target_link_libraries(lv_post_deps INTERFACE PkgConfig::CJSON lv_nettle_headers lv_dl_headers
  PkgConfig::ERFA
  Threads::Threads ${CMAKE_DL_LIBS} m)
# The figures' module, lvsim_plot.so (src/post/plot_draw.c): never PLplot in liblvsim_post.
add_library(lv_plot_deps INTERFACE)
target_link_libraries(lv_plot_deps INTERFACE PkgConfig::CJSON PkgConfig::PLPLOT PkgConfig::PNG lv_nettle_headers m)
