/* SPDX-License-Identifier: BSD-3-Clause */
/* cholesky.c — G = L L^T in place and its solve (cholesky.h; Golub & Van Loan, Matrix
 * Computations, 4th ed., Algorithm 4.2.1), with a relative test of the pivots. */
#include <float.h>
#include <math.h>
#include <stddef.h>

#include "analysis/cholesky.h"

int dyn_cholesky_factor(int n, double *G)
{
    const size_t K = (size_t)n;
    for (size_t j = 0; j < K; j++) {
        const double gjj = G[j * K + j];
        double d = gjj;
        for (size_t l = 0; l < j; l++)
            d -= G[j * K + l] * G[j * K + l];
        /* column j within rounding of the span of the columns before it: dependent */
        if (!(d > 64.0 * DBL_EPSILON * gjj))
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

void dyn_cholesky_solve(int n, const double *L, double *b)
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
