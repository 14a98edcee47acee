# The Python package (python/lvsim; docs/python.md), with Debian's interpreter: it sees Debian's
# python3-numpy, -pandas, -pytest, -scipy, -matplotlib, -nbconvert (a pyenv python3 earlier on
# PATH would not). The package comes from the build tree: PYTHONPATH=<build>/python.
#   test_python     tests/python/test_python.py (pytest): the C structures' mirrors, results bit
#                   for bit equal to `lvsim run`'s files, errors, sweeps, threads and the GIL,
#                   the one-phase call, targeting, Monte Carlo, freeing
#   test_python_doc the ```python blocks of docs/python.md and README.md run in order
#                   (tests/python/run_doc.py)
#   test_notebook   examples/notebook.ipynb executed by Debian's jupyter-nbconvert
#   test_python_install (in cmake/lv_install.cmake's install test) the installed package
# Under the sanitizers (make test-asan) Python is not instrumented: the C libraries' ASan and
# UBSan run-times are preloaded (LD_PRELOAD) and leak detection is off (the interpreter keeps
# memory to its exit by design); the notebook is left to the plain build (no-asan).
add_executable(py_layout ${PROJECT_SOURCE_DIR}/tests/python/py_layout.c)
target_link_libraries(py_layout PRIVATE lvsim)
lv_set_warnings(py_layout)

set(_py_env "PYTHONPATH=${PROJECT_BINARY_DIR}/python" "LV_SOURCE_DIR=${PROJECT_SOURCE_DIR}"
    "LVSIM=$<TARGET_FILE:lvsim_cli>" "LV_PY_LAYOUT=$<TARGET_FILE:py_layout>"
    "PYTHONDONTWRITEBYTECODE=1" "MPLBACKEND=Agg" "PYDEVD_DISABLE_FILE_VALIDATION=1")
if(LV_SANITIZE)
  set(_py_preload "")
  foreach(rt libasan.so libubsan.so)
    execute_process(COMMAND ${CMAKE_C_COMPILER} -print-file-name=${rt}
                    OUTPUT_VARIABLE _rt OUTPUT_STRIP_TRAILING_WHITESPACE)
    list(APPEND _py_preload ${_rt})
  endforeach()
  list(JOIN _py_preload ":" _py_preload)
  list(APPEND _py_env "LD_PRELOAD=${_py_preload}"
       "ASAN_OPTIONS=detect_leaks=0:halt_on_error=1" "UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1")
endif()

# -p no:cacheprovider: nothing written into the source tree; --junit-xml: a record in the build
add_test(NAME test_python
         COMMAND ${LV_PYTHON} -m pytest -q -p no:cacheprovider -rs
                 --junit-xml=${CMAKE_CURRENT_BINARY_DIR}/test_python.xml
                 ${PROJECT_SOURCE_DIR}/tests/python/test_python.py
         WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(test_python PROPERTIES ENVIRONMENT "${_py_env}" TIMEOUT 600)

# The package's ctypes prototypes against the public headers' LV_API declarations (the
# structures' layouts are checked by py_layout.c in test_python).
add_test(NAME test_python_signatures
         COMMAND ${LV_PYTHON} ${PROJECT_SOURCE_DIR}/tests/python/check_signatures.py
                 ${PROJECT_SOURCE_DIR}/include)
set_tests_properties(test_python_signatures PROPERTIES ENVIRONMENT "${_py_env}" TIMEOUT 60)

add_test(NAME test_python_doc
         COMMAND ${LV_PYTHON} ${PROJECT_SOURCE_DIR}/tests/python/run_doc.py ${PROJECT_SOURCE_DIR}
                 docs/python.md README.md
         WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(test_python_doc PROPERTIES ENVIRONMENT "${_py_env}" TIMEOUT 300)

# The notebook: executed in a copy (the source stays as committed), kernel python3 = Debian's
# /usr/bin/python3 (its kernel.json); fails on any cell's error.
find_program(LV_NBCONVERT jupyter-nbconvert)
if(LV_NBCONVERT)
  add_test(NAME test_notebook
           COMMAND ${LV_NBCONVERT} --to notebook --execute --ExecutePreprocessor.timeout=120
                   --ExecutePreprocessor.kernel_name=python3
                   --output-dir=${CMAKE_CURRENT_BINARY_DIR}/notebook
                   ${PROJECT_SOURCE_DIR}/examples/notebook.ipynb
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}/examples)
  set_tests_properties(test_notebook PROPERTIES ENVIRONMENT "${_py_env}" TIMEOUT 300
                       LABELS no-asan)
else()  # not skipped silently: the test fails and says what is missing
  message(WARNING "jupyter-nbconvert not found (Debian: jupyter-nbconvert): test_notebook fails")
  add_test(NAME test_notebook COMMAND sh -c "echo 'jupyter-nbconvert not found: scripts/install-deps.sh installs it (Debian: jupyter-nbconvert python3-ipykernel)'; exit 1")
  set_tests_properties(test_notebook PROPERTIES LABELS no-asan)
endif()
