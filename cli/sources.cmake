# The lvsim command line: main.c dispatches through the command table (cli.h); one file per
# command; common.c holds the helpers they share.
add_executable(lvsim_cli
  cli/main.c
  cli/common.c
  cli/cmd_models.c
  cli/cmd_laws.c
  cli/cmd_simulate.c
  cli/cmd_run.c
  cli/cmd_mc.c
  cli/cmd_check.c
  cli/cmd_target.c
  cli/cmd_optimize.c
  cli/cmd_params.c
  cli/cmd_compare.c
  cli/cmd_export.c
  cli/cmd_formats.c
  cli/cmd_fmu.c
  cli/cmd_plot.c
  cli/cmd_view.c
  cli/cmd_atmosphere.c
  cli/cmd_gravity.c
  cli/progress.c
  src/post/json_print.c  # the --json documents with exact numbers (its own copy: hidden in
  src/io/numfmt.cc)      # liblvsim_post)
set_target_properties(lvsim_cli PROPERTIES OUTPUT_NAME lvsim RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}
                                           LINKER_LANGUAGE C) # numfmt.cc needs no libstdc++
# The core library (run), the post-processing one (export, plot, report) and cJSON for the
# --json documents of simulate, compare and params.
target_link_libraries(lvsim_cli PRIVATE lvsim_post lvsim PkgConfig::CJSON Threads::Threads m
                                        dragonbox::dragonbox)
target_include_directories(lvsim_cli PRIVATE ${PROJECT_SOURCE_DIR}/src) # post/json_print.h, io/numfmt.h
lv_set_warnings(lvsim_cli)
# `mpirun -np K lvsim mc`: only when MPI is found (cmake/lv_deps.cmake); the plain build needs
# none. The MPI side (cli/mc_mpi.c) is the module lvsim_mpi.so, beside the figures' module,
# which cmd_mc.c loads only when mpirun started the process: no other command loads Open MPI
# (its libraries were a seventh of every lvsim start, issue 24). Without it cmd_mc.c runs
# every campaign on threads.
if(MPI_C_FOUND)
  include(GNUInstallDirs)
  add_library(lvsim_mpi MODULE cli/mc_mpi.c)
  set_target_properties(lvsim_mpi PROPERTIES PREFIX "" OUTPUT_NAME lvsim_mpi
    C_VISIBILITY_PRESET hidden LIBRARY_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/${CMAKE_INSTALL_LIBDIR}/lvsim)
  target_include_directories(lvsim_mpi PRIVATE ${PROJECT_SOURCE_DIR}/include ${PROJECT_SOURCE_DIR}/cli)
  target_link_libraries(lvsim_mpi PRIVATE lvsim_post lvsim MPI::MPI_C Threads::Threads)
  target_link_options(lvsim_mpi PRIVATE ${LV_NO_UNDEFINED})
  lv_set_warnings(lvsim_mpi)
  target_compile_definitions(lvsim_cli PRIVATE LV_WITH_MPI)
  add_dependencies(lvsim_cli lvsim_mpi)
endif()
target_link_libraries(lvsim_cli PRIVATE ${CMAKE_DL_LIBS})
