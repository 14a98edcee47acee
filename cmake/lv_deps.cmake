# Third-party libraries, all from Debian packages (scripts/install-deps.sh):
#   SUNDIALS 6.4 (CMake config: CVODE, ARKODE), libmatio, libyaml, cJSON, PLplot (pkg-config).
find_package(SUNDIALS 6 REQUIRED CONFIG)
find_package(PkgConfig REQUIRED)
pkg_check_modules(MATIO REQUIRED IMPORTED_TARGET matio)
pkg_check_modules(YAML REQUIRED IMPORTED_TARGET yaml-0.1)
pkg_check_modules(CJSON REQUIRED IMPORTED_TARGET libcjson)
pkg_check_modules(PLPLOT REQUIRED IMPORTED_TARGET plplot)  # src/post only: PNG/SVG figures
pkg_check_modules(PNG REQUIRED IMPORTED_TARGET libpng)   # src/post only: the figures' PNG files
find_package(Threads REQUIRED)
# Shortest round-trip digits of doubles for the CSV files (src/io/numfmt.cc); header-only.
find_package(dragonbox 1.1 REQUIRED CONFIG)

# The core library, liblvsim.
add_library(lv_deps INTERFACE)
target_link_libraries(lv_deps INTERFACE
  SUNDIALS::cvode_shared SUNDIALS::arkode_shared SUNDIALS::nvecserial_shared
  SUNDIALS::sunmatrixdense_shared SUNDIALS::sunlinsoldense_shared SUNDIALS::sunnonlinsolfixedpoint_shared
  PkgConfig::MATIO PkgConfig::YAML Threads::Threads dragonbox::dragonbox m)

# The post-processing library, liblvsim_post (src/post): cJSON; dlopen for its figures' module.
add_library(lv_post_deps INTERFACE)
target_link_libraries(lv_post_deps INTERFACE PkgConfig::CJSON ${CMAKE_DL_LIBS} m)
# The figures' module, lvsim_plot.so (src/post/plot_draw.c): never PLplot in liblvsim_post.
add_library(lv_plot_deps INTERFACE)
target_link_libraries(lv_plot_deps INTERFACE PkgConfig::CJSON PkgConfig::PLPLOT PkgConfig::PNG m)
