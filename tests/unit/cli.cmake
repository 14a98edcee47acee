add_test(NAME test_cli COMMAND ${PROJECT_SOURCE_DIR}/tests/cli/test_cli.sh $<TARGET_FILE:lvsim_cli>)
# docs/guidance.md's key tables are `lvsim laws --markdown` (the laws' own key tables).
add_test(NAME test_laws_doc COMMAND ${PROJECT_SOURCE_DIR}/tests/cli/check_laws_doc.sh
         $<TARGET_FILE:lvsim_cli> ${PROJECT_SOURCE_DIR})
# docs/result-files.md's and docs/exports.md's format tables are `lvsim formats --markdown`.
add_test(NAME test_formats_doc COMMAND ${PROJECT_SOURCE_DIR}/tests/cli/check_formats_doc.sh
         $<TARGET_FILE:lvsim_cli> ${PROJECT_SOURCE_DIR})
# One convention for dimensionless units (issue 27): "1" / "[1]" in lvsim vars, params, laws,
# the CSV headers and .mat descriptions of a run, and the Python package (test_units: the tables).
# (the Python part only where the library loads into Python: not in a sanitizer build, whose
# ASan runtime must come first; the normal build checks it)
if(LV_SANITIZE)
  set(LV_UNITS_PY "")
else()
  set(LV_UNITS_PY ${PROJECT_BINARY_DIR}/python)
endif()
add_test(NAME test_units_cli COMMAND ${PROJECT_SOURCE_DIR}/tests/cli/check_units.sh
         $<TARGET_FILE:lvsim_cli> ${PROJECT_SOURCE_DIR} ${LV_UNITS_PY})
set_tests_properties(test_units_cli PROPERTIES ENVIRONMENT "LV_PYTHON=${LV_PYTHON}")
# docs/cli.md's command table is `lvsim help --markdown`; each command has its section.
add_test(NAME test_help_doc COMMAND ${PROJECT_SOURCE_DIR}/tests/cli/check_help_doc.sh
         $<TARGET_FILE:lvsim_cli> ${PROJECT_SOURCE_DIR})
add_test(NAME test_symbols COMMAND ${PROJECT_SOURCE_DIR}/tests/cli/check_symbols.sh
         $<TARGET_FILE:lvsim> $<TARGET_FILE:lvsim_post> $<TARGET_FILE:lvsim_plot>)
# The libraries only some commands need are loaded by those commands alone (src/io/dl_lib.h).
add_test(NAME test_lazy_libs COMMAND ${PROJECT_SOURCE_DIR}/tests/cli/check_lazy_libs.sh
         $<TARGET_FILE:lvsim_cli> ${PROJECT_SOURCE_DIR})
# Run-atomic results folders: manifest checked by tests/python/check_manifest.py, path errors,
# the lock, concurrent runs, kill -9 at random points, SIGTERM (about 35 s; a minute under ASan).
add_test(NAME test_outdir COMMAND ${PROJECT_SOURCE_DIR}/tests/cli/test_outdir.sh
         $<TARGET_FILE:lvsim_cli> ${PROJECT_SOURCE_DIR})
set_tests_properties(test_outdir PROPERTIES TIMEOUT 180)
# Every CSV value of the examples' phases reads back to the .mat file's double, bit for bit.
add_test(NAME test_csv_mat COMMAND ${LV_PYTHON} ${PROJECT_SOURCE_DIR}/tests/python/check_csv_mat.py
         $<TARGET_FILE:lvsim_cli>)
# lvsim mc (issue 16): databases equal across -j 1 / -j 2, kill -9 then --resume, errors.
add_test(NAME test_mc COMMAND ${PROJECT_SOURCE_DIR}/tests/cli/test_mc.sh
         $<TARGET_FILE:lvsim_cli> ${PROJECT_SOURCE_DIR})
# ... and under `mpirun --oversubscribe -np 2` when MPI is built in (OpenMPI leaks at exit by
# design: not under the sanitizers).
if(MPI_C_FOUND)
  add_test(NAME test_mc_mpi COMMAND ${PROJECT_SOURCE_DIR}/tests/cli/test_mc.sh
           $<TARGET_FILE:lvsim_cli> ${PROJECT_SOURCE_DIR} 1)
  set_tests_properties(test_mc_mpi PROPERTIES LABELS no-asan)
endif()
# The IIP at given times in lvsim mc (issue 28, item 5): a phase's iip_at:, against the
# coasting body's own impact and a kept run's rows; counts, files, bad input.
add_test(NAME test_mc_iip COMMAND ${PROJECT_SOURCE_DIR}/tests/cli/test_mc_iip.sh
         $<TARGET_FILE:lvsim_cli> ${PROJECT_SOURCE_DIR})
# Atmosphere and wind profiles in missions (issue 28, item 1): run, check/run errors, mc.
add_test(NAME test_profile_cli COMMAND ${PROJECT_SOURCE_DIR}/tests/cli/test_profile_cli.sh
         $<TARGET_FILE:lvsim_cli> ${PROJECT_SOURCE_DIR})
# Dispersed profiles (issue 28, item 3): run flies the nominal, mc a profile per run; bad entries.
add_test(NAME test_dprof_cli COMMAND ${PROJECT_SOURCE_DIR}/tests/cli/test_dprof_cli.sh
         $<TARGET_FILE:lvsim_cli> ${PROJECT_SOURCE_DIR})
# An optimiser's trajectory as a phase's inputs (over time, tau, mass) and reference (issue 25,
# item 3): drift against closed-form Kepler coasts, start from the reference, bad input.
add_test(NAME test_reference_cli COMMAND ${LV_PYTHON} ${PROJECT_SOURCE_DIR}/tests/python/test_reference_cli.py
         $<TARGET_FILE:lvsim_cli>)
# Optimal control by direct multiple shooting with IPOPT (issue 25, items 1-2): the linear
# tangent law's closed form, its least-time dual, zero defects, infeasible, bad sections.
# Not under the sanitizers (about 1,000 IPOPT iterations; the C paths run there in test_ocp and
# test_python).
add_test(NAME test_optimize_cli COMMAND ${LV_PYTHON} ${PROJECT_SOURCE_DIR}/tests/python/test_optimize_cli.py
         $<TARGET_FILE:lvsim_cli>)
set_tests_properties(test_optimize_cli PROPERTIES LABELS no-asan TIMEOUT 300)
# examples/goddard flies Bryson's normalised Goddard rocket (COPS 3.0, sec. 10) exactly: its SI
# numbers are the mapping's, and lvsim's h, v, m agree with SciPy's DOP853 (rtol 1e-12)
# integration of the normalised ODE under the same throttle table to 1e-9 (pytest).
add_test(NAME test_goddard_dynamics
         COMMAND ${LV_PYTHON} -m pytest -q -p no:cacheprovider -rs
                 ${PROJECT_SOURCE_DIR}/tests/python/test_goddard_dynamics.py
         WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(test_goddard_dynamics PROPERTIES
                     ENVIRONMENT "LVSIM=$<TARGET_FILE:lvsim_cli>;PYTHONDONTWRITEBYTECODE=1"
                     TIMEOUT 120)
