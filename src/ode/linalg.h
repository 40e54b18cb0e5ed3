/* SPDX-License-Identifier: BSD-3-Clause */
/* linalg.h — dense LU factorisation with partial pivoting and its solve, for the small
 * linear systems (n up to a few dozen) of the stiff methods.
 *
 * Reference: G. H. Golub & C. F. Van Loan, "Matrix Computations", 4th ed., sec. 3.4
 * (Gaussian elimination with partial pivoting, Algorithm 3.4.1); the pivot convention of
 * LAPACK dgetrf/dgetrs (piv[k] is the row swapped with row k at step k).
 *
 * Private to the library. Nothing here allocates: the caller owns the matrix, the pivots
 * and the right-hand side. Matrices are flat row-major arrays, A[i*n + j].
 */
#ifndef DYN_ODE_LINALG_H
#define DYN_ODE_LINALG_H

#include "dynkit/ode.h"

/* Factor A (n x n, row-major) in place as P A = L U: on return the strict lower triangle
 * holds L (unit diagonal not stored) and the upper triangle U; piv (n) records the row
 * interchanges. Returns 0, or k + 1 > 0 when the pivot of column k is exactly zero or not
 * finite (A is singular or holds NaN/Inf; A and piv are then partly overwritten).
 * No threshold is applied: a tiny but non-zero pivot is accepted, as in LAPACK, because
 * the iteration matrices of stiff methods (I/(h gamma) - J with a singular J) are legitimately
 * close to singular relative to |J| for large h. */
int dyn_lu_factor(int n, double *A, int *piv);

/* Solve A x = b with the factors of dyn_lu_factor; b (n) is overwritten with x. */
void dyn_lu_solve(int n, const double *LU, const int *piv, double *b);

/* y = A x for A (n x n, row-major); y must not alias x. */
void dyn_mat_vec(int n, const double *A, const double *x, double *y);

/* Band LU with partial pivoting in LAPACK's factor storage (band_lu.c; the layout and the
 * contract of dyn_band_solver in dynkit/ode.h, the algorithm of LAPACK's dgbtf2/dgbtrs).
 * The first `lower` rows of each column of ab must be zero on entry (fill-in). */
int dyn_band_lu_factor(int n, int lower, int upper, double *ab, int ldab, int *piv);
void dyn_band_lu_solve(int n, int lower, int upper, const double *ab, int ldab, const int *piv,
                       double *b);

#endif /* DYN_ODE_LINALG_H */
