/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/lapack.h — the optional backend dynkit_lapack: LAPACK's banded LU (dgbtrf, dgbtrs)
 * as a dyn_band_solver for the stiff methods, so band matrices are factored by the
 * reference implementation (or an optimised LAPACK) instead of the library's own
 * (dyn_band_solver_builtin). Give it in dyn_solve_opts.band_solver; the dynkit tool does
 * when it is built with this backend. And LAPACK's dgeev as the dyn_eig_solver of the
 * analysis layer (dynkit/analysis.h: eigenvalues of a linearization), which the core does
 * not have. Built when CMake finds LAPACK (Debian: liblapack-dev). */
#ifndef DYNKIT_LAPACK_H
#define DYNKIT_LAPACK_H

#include "dynkit/analysis.h"
#include "dynkit/ode.h"

#ifdef __cplusplus
extern "C" {
#endif

extern const dyn_band_solver dyn_band_solver_lapack;
/* Eigenvalues of a real nonsymmetric matrix by dgeev (allocates its workspace per call). */
extern const dyn_eig_solver dyn_eig_solver_lapack;

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_LAPACK_H */
