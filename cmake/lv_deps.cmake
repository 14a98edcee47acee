# Third-party libraries, all from Debian packages (scripts/install-deps.sh):
#   SUNDIALS 6.4 (CMake config: CVODE, ARKODE), libmatio (and its HDF5), libyaml, cJSON, PLplot (pkg-config).
find_package(SUNDIALS 6 REQUIRED CONFIG)
find_package(PkgConfig REQUIRED)
pkg_check_modules(MATIO REQUIRED IMPORTED_TARGET matio)
# HDF5 (a libmatio dependency; Debian: libhdf5-dev): src/io/table_load.c reads MAT v7.3
# variables that libmatio cannot classify directly. The serial library, as libmatio's.
pkg_search_module(HDF5 REQUIRED IMPORTED_TARGET hdf5-serial hdf5)
pkg_check_modules(YAML REQUIRED IMPORTED_TARGET yaml-0.1)
pkg_check_modules(CJSON REQUIRED IMPORTED_TARGET libcjson)
pkg_check_modules(PLPLOT REQUIRED IMPORTED_TARGET plplot)  # src/post only: PNG/SVG figures
find_package(Threads REQUIRED)
# Random123 (Debian: librandom123-dev, header-only): the Philox4x32-10 counter-based generator
# of the dispersions (src/mission/dispersion.c).
find_path(RANDOM123_INCLUDE_DIR Random123/philox.h REQUIRED)
# SQLite 3 (Debian: libsqlite3-dev): the Monte Carlo campaign database (src/campaign).
pkg_check_modules(SQLITE3 REQUIRED IMPORTED_TARGET sqlite3)
# OpenMPI (Debian: libopenmpi-dev, openmpi-bin), optional: `mpirun -np K lvsim mc` when found.
option(LV_WITH_MPI "Build lvsim mc with MPI when an MPI library is found" ON)
if(LV_WITH_MPI)
  find_package(MPI COMPONENTS C QUIET)
endif()

# The core library, liblvsim.
add_library(lv_deps INTERFACE)
target_link_libraries(lv_deps INTERFACE
  SUNDIALS::cvode_shared SUNDIALS::arkode_shared SUNDIALS::nvecserial_shared
  SUNDIALS::sunmatrixdense_shared SUNDIALS::sunlinsoldense_shared SUNDIALS::sunnonlinsolfixedpoint_shared
  PkgConfig::MATIO PkgConfig::HDF5 PkgConfig::YAML Threads::Threads m)
target_include_directories(lv_deps INTERFACE ${RANDOM123_INCLUDE_DIR})

# The post-processing library, liblvsim_post (src/post): never PLplot in the core library.
add_library(lv_post_deps INTERFACE)
target_link_libraries(lv_post_deps INTERFACE PkgConfig::CJSON PkgConfig::PLPLOT PkgConfig::SQLITE3 Threads::Threads m)
