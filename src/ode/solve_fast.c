/* SPDX-License-Identifier: BSD-3-Clause */
/* dyn_solve: the embedded pairs with a generated kernel (bs23, dp45, dop853; see
 * dynkit/erk_kernels.h) through the fast path of dynkit/solve_inline.h, here with the
 * right-hand side behind its pointer, for the cases it takes (scalar tolerances, no events,
 * step callback, recorder or trace; output at every step or at a list of times); every
 * other case, bad arguments included, through the general driver (src/ode/solve.c). Both
 * give the same results bit for bit (tests/test_solve_inline.c); the fast path only leaves
 * out the general loop's per-step options and the table-driven stage loop. */
#include "dynkit/solve_inline.h"
#include "ode/solve_general.h"

int dyn_solve(const dyn_tableau *m, const dyn_system *sys, double t0, double t1, const double *y0,
              double *y, double *work, const dyn_solve_opts *opts, dyn_result *res)
{
    const int rc = dyn_sinl_try(m, sys, t0, t1, y0, y, work, opts, res);
    if (rc != DYN_SINL_DECLINED)
        return rc;
    return dyn_solve_general(m, sys, t0, t1, y0, y, work, opts, res);
}
