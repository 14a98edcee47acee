/* nlopt_dl.c - NLopt, loaded the first time an optimiser runs (io/dl_lib.h).
 *
 * Only `lvsim target` with an NLopt method (SLSQP, COBYLA) uses NLopt, yet linking it costs
 * every process that links liblvsim its loading and relocation (callgrind: 0.31 M
 * instructions for a program that links it and does nothing, against 0.13 M; issue 24). The
 * NLopt functions lvsim calls are defined here with NLopt's own signatures and forward to the
 * library; lv_nlopt_error() says why it could not be loaded. Adding a function: one line. */
#define _GNU_SOURCE

#include <nlopt.h>

#include "io/dl_lib.h"
#include "target/nlopt_dl.h"

#ifndef LV_NLOPT_SONAME
#define LV_NLOPT_SONAME "libnlopt.so.0" /* set by cmake/lv_deps.cmake */
#endif

#define NLOPT_FUNCS(X, V)                                                                     \
    X(nlopt_opt, nlopt_create, (nlopt_algorithm a, unsigned b), (a, b), NULL)                 \
    V(nlopt_destroy, (nlopt_opt a), (a))                                                      \
    X(nlopt_result, nlopt_optimize, (nlopt_opt a, double *b, double *c), (a, b, c),           \
      NLOPT_FAILURE)                                                                          \
    X(nlopt_result, nlopt_force_stop, (nlopt_opt a), (a), NLOPT_FAILURE)                      \
    X(nlopt_result, nlopt_set_min_objective, (nlopt_opt a, nlopt_func b, void *c), (a, b, c), \
      NLOPT_FAILURE)                                                                          \
    X(nlopt_result, nlopt_add_equality_mconstraint,                                           \
      (nlopt_opt a, unsigned b, nlopt_mfunc c, void *d, const double *e), (a, b, c, d, e),    \
      NLOPT_FAILURE)                                                                          \
    X(nlopt_result, nlopt_add_inequality_mconstraint,                                         \
      (nlopt_opt a, unsigned b, nlopt_mfunc c, void *d, const double *e), (a, b, c, d, e),    \
      NLOPT_FAILURE)                                                                          \
    X(nlopt_result, nlopt_set_lower_bounds, (nlopt_opt a, const double *b), (a, b),           \
      NLOPT_FAILURE)                                                                          \
    X(nlopt_result, nlopt_set_upper_bounds, (nlopt_opt a, const double *b), (a, b),           \
      NLOPT_FAILURE)                                                                          \
    X(nlopt_result, nlopt_set_ftol_abs, (nlopt_opt a, double b), (a, b), NLOPT_FAILURE)       \
    X(nlopt_result, nlopt_set_xtol_abs1, (nlopt_opt a, double b), (a, b), NLOPT_FAILURE)      \
    X(nlopt_result, nlopt_set_initial_step1, (nlopt_opt a, double b), (a, b), NLOPT_FAILURE)

LV_DL_LIBRARY(LV_NLOPT_SONAME, NLOPT_FUNCS)

const char *lv_nlopt_error(void) { return dl_error(); }
