/* SPDX-License-Identifier: BSD-3-Clause */
/* qr_gram_schmidt.c — the QR factorization of a tall matrix's columns by modified
 * Gram-Schmidt, each column orthogonalized twice against the previous ones (L. Giraud,
 * J. Langou, M. Rozloznik, Comput. Math. Appl. 50 (2005) 1069-1075: "twice is enough" for
 * orthogonality to rounding), Q overwritten by its orthonormal factor and the logarithms
 * of R's diagonal returned: the growth of each direction that Benettin's method sums. */
#include <math.h>

#include "dynkit/lyapunov.h"

int dyn_qr_log_diag(int n, int k, double *Q, double *logr)
{
    const size_t N = (size_t)n, K = (size_t)k;
    for (size_t j = 0; j < K; j++) {
        for (int pass = 0; pass < 2; pass++)
            for (size_t p = 0; p < j; p++) {
                double d = 0.0;
                for (size_t i = 0; i < N; i++)
                    d += Q[i * K + p] * Q[i * K + j];
                for (size_t i = 0; i < N; i++)
                    Q[i * K + j] -= d * Q[i * K + p];
            }
        /* the norm scaled against overflow of the squares */
        double big = 0.0;
        for (size_t i = 0; i < N; i++)
            big = fmax(big, fabs(Q[i * K + j]));
        if (!(big > 0.0) || !isfinite(big))
            return -1;
        double s = 0.0;
        for (size_t i = 0; i < N; i++) {
            const double x = Q[i * K + j] / big;
            s += x * x;
        }
        const double norm = big * sqrt(s);
        logr[j] = log(big) + 0.5 * log(s);
        for (size_t i = 0; i < N; i++)
            Q[i * K + j] /= norm;
    }
    return 0;
}
