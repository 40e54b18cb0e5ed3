/* SPDX-License-Identifier: BSD-3-Clause */
/* The general driver behind dyn_solve (src/ode/solve.c): every method and option. dyn_solve
 * (src/ode/solve_fast.c) sends the cases of the kernels of dynkit/erk_kernels.h to the fast
 * path of dynkit/solve_inline.h first; the tests compare the two bit for bit. */
#ifndef DYNKIT_SRC_ODE_SOLVE_GENERAL_H
#define DYNKIT_SRC_ODE_SOLVE_GENERAL_H

#include "dynkit/solve.h"

/* dyn_solve's contract and results, without the fast path. */
int dyn_solve_general(const dyn_tableau *m, const dyn_system *sys, double t0, double t1,
                      const double *y0, double *y, double *work, const dyn_solve_opts *opts,
                      dyn_result *res);

#endif
