/* SPDX-License-Identifier: BSD-3-Clause */
/* linear_reduce.c — a linearization restricted to admissible directions: with the columns
 * of P (n x k) spanning them, A_min = P^+ A P, P^+ = (P^T P)^-1 P^T the Moore-Penrose
 * pseudo-inverse of a P of full column rank, formed through the Cholesky factor of the
 * Gram matrix P^T P (Golub & Van Loan, Matrix Computations, 4th ed., sec. 4.2 and 5.3).
 * When span(P) is invariant under A (A P = P A_min), A_min has exactly the eigenvalues of
 * A on that subspace. */
#include <stddef.h>

#include "ode/cholesky.h"
#include "dynkit/analysis.h"

/* out (a x b) = X^T Y for X (r x a) and Y (r x b), all row-major. */
static void product_tn(size_t r, size_t a, size_t b, const double *X, const double *Y, double *out)
{
    for (size_t i = 0; i < a; i++)
        for (size_t j = 0; j < b; j++) {
            double s = 0.0;
            for (size_t l = 0; l < r; l++)
                s += X[l * a + i] * Y[l * b + j];
            out[i * b + j] = s;
        }
}

int dyn_linear_reduce(int n, int k, const double *A, const double *P, double *Amin, double *work)
{
    if (n < 1 || k < 1 || k > n)
        return DYN_ERR_ARG;
    const size_t N = (size_t)n, K = (size_t)k;
    /* A P (n x k), then P^T P (k x k) and P^T A P (k x k, into Amin) */
    double *AP = work, *G = work + N * K, *rhs = work + N * K + K * K;
    for (size_t i = 0; i < N; i++)
        for (size_t c = 0; c < K; c++) {
            double s = 0.0;
            for (size_t l = 0; l < N; l++)
                s += A[i * N + l] * P[l * K + c];
            AP[i * K + c] = s;
        }
    product_tn(N, K, K, P, P, G);
    product_tn(N, K, K, P, AP, Amin);
    if (dyn_cholesky_factor(k, G))
        return DYN_ERR_ARG;
    /* Amin = G^-1 (P^T A P), column by column */
    for (size_t c = 0; c < K; c++) {
        for (size_t a = 0; a < K; a++)
            rhs[a] = Amin[a * K + c];
        dyn_cholesky_solve(k, G, rhs);
        for (size_t a = 0; a < K; a++)
            Amin[a * K + c] = rhs[a];
    }
    return 0;
}
