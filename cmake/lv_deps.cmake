# Third-party libraries, all from Debian packages (scripts/install-deps.sh):
#   SUNDIALS 6.4 (CMake config: CVODE, ARKODE), libmatio (and its HDF5), libyaml, NLopt, cJSON,
#   PLplot (pkg-config).
find_package(SUNDIALS 6 REQUIRED CONFIG)
find_package(PkgConfig REQUIRED)
pkg_check_modules(MATIO REQUIRED IMPORTED_TARGET matio)
# HDF5 (a libmatio dependency; Debian: libhdf5-dev): src/io/table_load.c reads MAT v7.3
# variables that libmatio cannot classify directly. The serial library, as libmatio's.
pkg_search_module(HDF5 REQUIRED IMPORTED_TARGET hdf5-serial hdf5)
pkg_check_modules(YAML REQUIRED IMPORTED_TARGET yaml-0.1)
# NLopt (Debian: libnlopt-dev): the optimisers of src/target (SLSQP, COBYLA).
pkg_check_modules(NLOPT REQUIRED IMPORTED_TARGET nlopt)
pkg_check_modules(CJSON REQUIRED IMPORTED_TARGET libcjson)
pkg_check_modules(PLPLOT REQUIRED IMPORTED_TARGET plplot)  # src/post only: PNG/SVG figures
find_package(Threads REQUIRED)

# The core library, liblvsim.
add_library(lv_deps INTERFACE)
target_link_libraries(lv_deps INTERFACE
  SUNDIALS::cvode_shared SUNDIALS::arkode_shared SUNDIALS::nvecserial_shared
  SUNDIALS::sunmatrixdense_shared SUNDIALS::sunlinsoldense_shared SUNDIALS::sunnonlinsolfixedpoint_shared
  PkgConfig::MATIO PkgConfig::HDF5 PkgConfig::YAML PkgConfig::NLOPT Threads::Threads m)

# The post-processing library, liblvsim_post (src/post): never PLplot in the core library.
add_library(lv_post_deps INTERFACE)
target_link_libraries(lv_post_deps INTERFACE PkgConfig::CJSON PkgConfig::PLPLOT m)
