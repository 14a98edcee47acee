/* cvode_dl.c - SUNDIALS' CVODE (with its serial vector, dense matrix and linear solver and
 * fixed-point solver, which Debian's libsundials_cvode carries), loaded the first time lvsim
 * creates a SUNDIALS integrator.
 *
 * Since issue 24 a mission phase integrates with lvsim's own explicit Runge-Kutta methods
 * (integrate/erk.c) unless it is stiff, so most processes never call SUNDIALS: `lvsim
 * --version`, `check`, the post-processing commands and every non-stiff run. Linking CVODE and
 * ARKODE cost each of them their loading and relocation, about 806,000 instructions (callgrind,
 * an empty program linked with both: 934,096 against 128,522), 41 % of `lvsim --version`.
 * These forwarders (io/dl_lib.h) have SUNDIALS' own signatures (its headers are included) and
 * open the library once per process at the first call. The vector, matrix, solver and context
 * functions come from this library for both CVODE and ARKODE (arkode_dl.c): the objects they
 * make are plain SUNDIALS 6.4 structures that either library's code accepts.
 * lv_cvode_error() says why the library could not be loaded; integrate/integrator.c asks it
 * before it creates a SUNDIALS integrator. Adding a function: one line below. */
#define _GNU_SOURCE
/* SUNDIALS' headers mark every function visibility("default"): without this these forwarders
 * would be exported from liblvsim (test_symbols), beside SUNDIALS' own */
#define SUNDIALS_STATIC_DEFINE

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include "integrate/sundials_dl.h"
#include "io/dl_lib.h"

#ifndef LV_CVODE_SONAME
#define LV_CVODE_SONAME "libsundials_cvode.so.6" /* set by cmake/lv_deps.cmake */
#endif

/* X(return type, name, parameters, arguments, value on failure); V(name, ...) for void */
#define CVODE_FUNCS(X, V)                                                                     \
    X(int, SUNContext_Create, (void *a, SUNContext *b), (a, b), -1)                           \
    X(int, SUNContext_Free, (SUNContext * a), (a), -1)                                        \
    X(N_Vector, N_VNew_Serial, (sunindextype a, SUNContext b), (a, b), NULL)                  \
    X(realtype *, N_VGetArrayPointer, (N_Vector a), (a), NULL)                                \
    V(N_VDestroy, (N_Vector a), (a))                                                          \
    X(SUNMatrix, SUNDenseMatrix, (sunindextype a, sunindextype b, SUNContext c), (a, b, c),   \
      NULL)                                                                                   \
    V(SUNMatDestroy, (SUNMatrix a), (a))                                                      \
    X(SUNLinearSolver, SUNLinSol_Dense, (N_Vector a, SUNMatrix b, SUNContext c), (a, b, c),   \
      NULL)                                                                                   \
    X(int, SUNLinSolFree, (SUNLinearSolver a), (a), -1)                                       \
    X(SUNNonlinearSolver, SUNNonlinSol_FixedPoint, (N_Vector a, int b, SUNContext c),         \
      (a, b, c), NULL)                                                                        \
    X(int, SUNNonlinSolFree, (SUNNonlinearSolver a), (a), -1)                                 \
    X(void *, CVodeCreate, (int a, SUNContext b), (a, b), NULL)                               \
    V(CVodeFree, (void **a), (a))                                                             \
    X(int, CVodeInit, (void *a, CVRhsFn b, realtype c, N_Vector d), (a, b, c, d), -1)         \
    X(int, CVodeReInit, (void *a, realtype b, N_Vector c), (a, b, c), -1)                     \
    X(int, CVode, (void *a, realtype b, N_Vector c, realtype *d, int e), (a, b, c, d, e), -1) \
    X(int, CVodeSVtolerances, (void *a, realtype b, N_Vector c), (a, b, c), -1)               \
    X(int, CVodeWFtolerances, (void *a, CVEwtFn b), (a, b), -1)                               \
    X(int, CVodeSetUserData, (void *a, void *b), (a, b), -1)                                  \
    X(int, CVodeSetErrHandlerFn, (void *a, CVErrHandlerFn b, void *c), (a, b, c), -1)         \
    X(int, CVodeSetStopTime, (void *a, realtype b), (a, b), -1)                               \
    X(int, CVodeSetMaxStep, (void *a, realtype b), (a, b), -1)                                \
    X(int, CVodeSetMaxNumSteps, (void *a, long int b), (a, b), -1)                            \
    X(int, CVodeSetMaxErrTestFails, (void *a, int b), (a, b), -1)                             \
    X(int, CVodeSetLinearSolver, (void *a, SUNLinearSolver b, SUNMatrix c), (a, b, c), -1)    \
    X(int, CVodeSetNonlinearSolver, (void *a, SUNNonlinearSolver b), (a, b), -1)              \
    X(int, CVodeRootInit, (void *a, int b, CVRootFn c), (a, b, c), -1)                        \
    X(int, CVodeSetRootDirection, (void *a, int *b), (a, b), -1)                              \
    X(int, CVodeSetNoInactiveRootWarn, (void *a), (a), -1)                                    \
    X(int, CVodeGetRootInfo, (void *a, int *b), (a, b), -1)                                   \
    X(char *, CVodeGetReturnFlagName, (long int a), (a), NULL)                                \
    X(int, CVodeGetNumSteps, (void *a, long int *b), (a, b), -1)                              \
    X(int, CVodeGetNumRhsEvals, (void *a, long int *b), (a, b), -1)                           \
    X(int, CVodeGetNumLinRhsEvals, (void *a, long int *b), (a, b), -1)                        \
    X(int, CVodeGetNumJacEvals, (void *a, long int *b), (a, b), -1)                           \
    X(int, CVodeGetNumGEvals, (void *a, long int *b), (a, b), -1)                             \
    X(int, CVodeGetNumErrTestFails, (void *a, long int *b), (a, b), -1)                       \
    X(int, CVodeGetNumNonlinSolvConvFails, (void *a, long int *b), (a, b), -1)

LV_DL_LIBRARY(LV_CVODE_SONAME, CVODE_FUNCS)

const char *lv_cvode_error(void) { return dl_error(); }
