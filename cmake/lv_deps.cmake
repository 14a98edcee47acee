# Third-party libraries, all from Debian packages (scripts/install-deps.sh):
#   SUNDIALS 6.4 (CMake config: CVODE, ARKODE), libmatio, libyaml, cJSON (pkg-config).
find_package(SUNDIALS 6 REQUIRED CONFIG)
find_package(PkgConfig REQUIRED)
pkg_check_modules(MATIO REQUIRED IMPORTED_TARGET matio)
pkg_check_modules(YAML REQUIRED IMPORTED_TARGET yaml-0.1)
pkg_check_modules(CJSON REQUIRED IMPORTED_TARGET libcjson)
pkg_check_modules(PLPLOT REQUIRED IMPORTED_TARGET plplot)  # src/plot only: PNG/SVG figures
find_package(Threads REQUIRED)

add_library(lv_deps INTERFACE)
target_link_libraries(lv_deps INTERFACE
  SUNDIALS::cvode_shared SUNDIALS::arkode_shared SUNDIALS::nvecserial_shared
  SUNDIALS::sunmatrixdense_shared SUNDIALS::sunlinsoldense_shared SUNDIALS::sunnonlinsolfixedpoint_shared
  PkgConfig::MATIO PkgConfig::YAML PkgConfig::CJSON PkgConfig::PLPLOT Threads::Threads m)
