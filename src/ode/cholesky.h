/* SPDX-License-Identifier: BSD-3-Clause */
/* cholesky.h — the Cholesky factorisation G = L L^T of a symmetric positive definite
 * matrix and its solve, with the test of the pivots as an argument: the normal-equation
 * systems of the analysis layer (the reduction P^+ A P, the Levenberg-Marquardt steps of
 * equilibria) and the checks of a mechanism's mass matrix and constraint rows (src/mbs).
 * Golub & Van Loan, Matrix Computations, 4th ed., sec. 4.2 (Algorithm 4.2.1, the gaxpy
 * form).
 *
 * Private to the library. Row-major, in place, nothing allocated. The functions are
 * static inline so that the layers that do not link the core (dynkit_lang) share them. */
#ifndef DYN_ODE_CHOLESKY_H
#define DYN_ODE_CHOLESKY_H

#include <float.h>
#include <math.h>
#include <stddef.h>

/* Factor G (n x n, row-major; only the lower triangle is read) in place: L in the lower
 * triangle. A pivot d_j (the diagonal entry less the squares of the row's factors) must
 * exceed tol times the diagonal entry g_jj it came from, or, with of_largest, tol times
 * the largest |g_jj| of G. Returns 0, or k + 1 for the first column k whose pivot does not
 * (G is not positive definite to that tolerance: column k depends on the ones before it). */
static inline int dyn_cholesky_factor_tol(int n, double *G, double tol, int of_largest)
{
    const size_t K = (size_t)n;
    double big = 0.0;
    for (size_t j = 0; j < K && of_largest; j++)
        big = fmax(big, fabs(G[j * K + j]));
    for (size_t j = 0; j < K; j++) {
        const double gjj = G[j * K + j];
        double d = gjj;
        for (size_t l = 0; l < j; l++)
            d -= G[j * K + l] * G[j * K + l];
        if (!(d > tol * (of_largest ? big : gjj)))
            return (int)j + 1;
        d = sqrt(d);
        G[j * K + j] = d;
        for (size_t i = j + 1; i < K; i++) {
            double s = G[i * K + j];
            for (size_t l = 0; l < j; l++)
                s -= G[i * K + l] * G[j * K + l];
            G[i * K + j] = s / d;
        }
    }
    return 0;
}

/* The analysis layer's test: a pivot above 64 eps times its own diagonal entry. */
static inline int dyn_cholesky_factor(int n, double *G)
{
    return dyn_cholesky_factor_tol(n, G, 64.0 * DBL_EPSILON, 0);
}

/* Solve L L^T x = b with the factor of dyn_cholesky_factor(_tol); b (n) is overwritten by
 * x. */
static inline void dyn_cholesky_solve(int n, const double *L, double *b)
{
    const size_t K = (size_t)n;
    for (size_t i = 0; i < K; i++) { /* L z = b */
        double s = b[i];
        for (size_t l = 0; l < i; l++)
            s -= L[i * K + l] * b[l];
        b[i] = s / L[i * K + i];
    }
    for (size_t i = K; i-- > 0;) { /* L^T x = z */
        double s = b[i];
        for (size_t l = i + 1; l < K; l++)
            s -= L[l * K + i] * b[l];
        b[i] = s / L[i * K + i];
    }
}

#endif /* DYN_ODE_CHOLESKY_H */
