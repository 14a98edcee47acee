/* arkode_dl.c - SUNDIALS' ARKODE (ERKStep: the `dopri5`, `rk4` and `euler` methods), loaded the
 * first time lvsim creates one of those integrators; see cvode_dl.c for why, and for the
 * vector, matrix and context functions, which come from CVODE's library. lv_arkode_error()
 * says why the library could not be loaded. Adding a function: one line below. */
#define _GNU_SOURCE
/* SUNDIALS' headers mark every function visibility("default"): without this these forwarders
 * would be exported from liblvsim (test_symbols), beside SUNDIALS' own */
#define SUNDIALS_STATIC_DEFINE

#include <stdio.h> /* arkode_butcher.h uses FILE without including it */

#include <arkode/arkode_butcher.h>
#include <arkode/arkode_erkstep.h>

#include "integrate/sundials_dl.h"
#include "io/dl_lib.h"

#ifndef LV_ARKODE_SONAME
#define LV_ARKODE_SONAME "libsundials_arkode.so.5" /* set by cmake/lv_deps.cmake */
#endif

/* X(return type, name, parameters, arguments, value on failure); V(name, ...) for void */
#define ARKODE_FUNCS(X, V)                                                                    \
    X(void *, ERKStepCreate, (ARKRhsFn a, realtype b, N_Vector c, SUNContext d), (a, b, c, d), \
      NULL)                                                                                   \
    V(ERKStepFree, (void **a), (a))                                                           \
    X(int, ERKStepReset, (void *a, realtype b, N_Vector c), (a, b, c), -1)                    \
    X(int, ERKStepEvolve, (void *a, realtype b, N_Vector c, realtype *d, int e),              \
      (a, b, c, d, e), -1)                                                                    \
    X(int, ERKStepSVtolerances, (void *a, realtype b, N_Vector c), (a, b, c), -1)             \
    X(int, ERKStepWFtolerances, (void *a, ARKEwtFn b), (a, b), -1)                            \
    X(int, ERKStepSetUserData, (void *a, void *b), (a, b), -1)                                \
    X(int, ERKStepSetErrHandlerFn, (void *a, ARKErrHandlerFn b, void *c), (a, b, c), -1)      \
    X(int, ERKStepSetTableNum, (void *a, ARKODE_ERKTableID b), (a, b), -1)                    \
    X(int, ERKStepSetTable, (void *a, ARKodeButcherTable b), (a, b), -1)                      \
    X(int, ERKStepSetStopTime, (void *a, realtype b), (a, b), -1)                             \
    X(int, ERKStepSetMaxStep, (void *a, realtype b), (a, b), -1)                              \
    X(int, ERKStepSetMaxNumSteps, (void *a, long int b), (a, b), -1)                          \
    X(int, ERKStepSetFixedStep, (void *a, realtype b), (a, b), -1)                            \
    X(int, ERKStepSetInterpolantType, (void *a, int b), (a, b), -1)                           \
    X(int, ERKStepSetInterpolantDegree, (void *a, int b), (a, b), -1)                         \
    X(int, ERKStepRootInit, (void *a, int b, ARKRootFn c), (a, b, c), -1)                     \
    X(int, ERKStepSetRootDirection, (void *a, int *b), (a, b), -1)                            \
    X(int, ERKStepSetNoInactiveRootWarn, (void *a), (a), -1)                                  \
    X(int, ERKStepGetRootInfo, (void *a, int *b), (a, b), -1)                                 \
    X(char *, ERKStepGetReturnFlagName, (long int a), (a), NULL)                              \
    X(int, ERKStepGetNumSteps, (void *a, long int *b), (a, b), -1)                            \
    X(int, ERKStepGetNumGEvals, (void *a, long int *b), (a, b), -1)                           \
    X(int, ERKStepGetNumErrTestFails, (void *a, long int *b), (a, b), -1)                     \
    X(int, ERKStepGetLastStep, (void *a, realtype *b), (a, b), -1)                            \
    X(int, ERKStepGetCurrentTime, (void *a, realtype *b), (a, b), -1)                         \
    X(ARKodeButcherTable, ARKodeButcherTable_Create,                                          \
      (int a, int b, int c, realtype *d, realtype *e, realtype *f, realtype *g),              \
      (a, b, c, d, e, f, g), NULL)                                                            \
    V(ARKodeButcherTable_Free, (ARKodeButcherTable a), (a))

LV_DL_LIBRARY(LV_ARKODE_SONAME, ARKODE_FUNCS)

const char *lv_arkode_error(void) { return dl_error(); }
