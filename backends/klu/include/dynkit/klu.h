/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/klu.h — the optional backend dynkit_klu: SuiteSparse's KLU (a sparse LU with a
 * fill-reducing ordering, Davis & Palamadai Natarajan, ACM TOMS 37(3), 2010) as the
 * dyn_sparse_solver of the stiff methods (dynkit/ode.h, dyn_solve_opts.sparse_solver), so
 * I/(h gamma) - J of a large model with a sparse Jacobian is factored in time that grows
 * with its entries, not with n^3. Built when CMake finds KLU (Debian: libsuitesparse-dev);
 * the dynkit tool uses it for models whose exact Jacobian is sparse and not banded. */
#ifndef DYNKIT_KLU_H
#define DYNKIT_KLU_H

#include "dynkit/ode.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Fill s with KLU's factor, solve and forget and a new context of its own (ordering by
 * AMD, the symbolic analysis made at the first factorisation and kept while the pattern is
 * the same, across solves too; later factorisations of a solve refactor with the same
 * pivots while KLU's condition estimate stays above eps^(2/3), else factor anew, as
 * SUNDIALS' SUNLinSol_KLU does; each solve starts with a factorisation that pivots anew).
 * 0, or 1 when memory runs out. One solver serves one solve at a time, and solve after
 * solve (a sweep's thread); give it back with dyn_klu_release. */
int dyn_klu_init(dyn_sparse_solver *s);
/* Free what dyn_klu_init and the factorisations allocated; s may be zeroed or released. */
void dyn_klu_release(dyn_sparse_solver *s);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_KLU_H */
