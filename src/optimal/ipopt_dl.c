/* ipopt_dl.c - IPOPT's C interface, loaded the first time `lvsim optimize` solves (io/dl_lib.h):
 * only the optimiser needs it, and IPOPT brings MUMPS, LAPACK and gfortran with it. The
 * functions lvsim calls are defined here with IPOPT's own signatures and forward to the
 * library; lv_ipopt_error() says why it could not be loaded. Adding a function: one line. */
#define _GNU_SOURCE

#include <IpStdCInterface.h>

#include "io/dl_lib.h"
#include "optimal/ipopt_dl.h"

#ifndef LV_IPOPT_SONAME
#define LV_IPOPT_SONAME "libipopt.so.1" /* set by cmake/lv_deps.cmake */
#endif

#define IPOPT_FUNCS(X, V)                                                                      \
    X(IpoptProblem, CreateIpoptProblem,                                                        \
      (Index a, Number * b, Number * c, Index d, Number * e, Number * f, Index g, Index h,      \
       Index i, Eval_F_CB j, Eval_G_CB k, Eval_Grad_F_CB l, Eval_Jac_G_CB m, Eval_H_CB n),     \
      (a, b, c, d, e, f, g, h, i, j, k, l, m, n), NULL)                                        \
    V(FreeIpoptProblem, (IpoptProblem a), (a))                                                 \
    X(Bool, AddIpoptStrOption, (IpoptProblem a, char *b, char *c), (a, b, c), FALSE)           \
    X(Bool, AddIpoptNumOption, (IpoptProblem a, char *b, Number c), (a, b, c), FALSE)          \
    X(Bool, AddIpoptIntOption, (IpoptProblem a, char *b, Int c), (a, b, c), FALSE)            \
    X(Bool, SetIntermediateCallback, (IpoptProblem a, Intermediate_CB b), (a, b), FALSE)      \
    X(enum ApplicationReturnStatus, IpoptSolve,                                                \
      (IpoptProblem a, Number * b, Number * c, Number * d, Number * e, Number * f, Number * g, \
       UserDataPtr h),                                                                         \
      (a, b, c, d, e, f, g, h), Internal_Error)

LV_DL_LIBRARY(LV_IPOPT_SONAME, IPOPT_FUNCS)

const char *lv_ipopt_error(void) { return dl_error(); }
