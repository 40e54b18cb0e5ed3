/* SPDX-License-Identifier: BSD-3-Clause */
/* cholesky.h — the Cholesky factorisation G = L L^T of a symmetric positive definite
 * matrix and its solve, for the small normal-equation systems of the analysis layer (the
 * reduction P^+ A P, the Levenberg-Marquardt steps of equilibria). Golub & Van Loan,
 * Matrix Computations, 4th ed., sec. 4.2 (Algorithm 4.2.1, the gaxpy form).
 *
 * Private to the library. Row-major, in place, nothing allocated. */
#ifndef DYN_ANALYSIS_CHOLESKY_H
#define DYN_ANALYSIS_CHOLESKY_H

/* Factor G (n x n, row-major; only the lower triangle is read) in place: L in the lower
 * triangle. Returns 0, or k + 1 when the pivot of column k is not above 64 eps times the
 * diagonal entry it came from (G is not positive definite to working precision: its
 * column k depends on the ones before it). */
int dyn_cholesky_factor(int n, double *G);

/* Solve L L^T x = b with the factor of dyn_cholesky_factor; b (n) is overwritten by x. */
void dyn_cholesky_solve(int n, const double *L, double *b);

#endif /* DYN_ANALYSIS_CHOLESKY_H */
