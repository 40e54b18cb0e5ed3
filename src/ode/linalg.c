/* SPDX-License-Identifier: BSD-3-Clause */
/* linalg.c — dense LU factorisation with partial pivoting and the triangular solves
 * (Golub & Van Loan, "Matrix Computations", 4th ed., Algorithm 3.4.1; the row-interchange
 * convention of LAPACK dgetrf/dgetrs). Row-major, in place, no allocation. */
#include <math.h>
#include <stddef.h>

#include "ode/linalg.h"

int dyn_lu_factor(int n, double *A, int *piv)
{
    const size_t N = (size_t)n;
    for (int k = 0; k < n; k++) {
        /* pivot: the largest magnitude in column k at or below the diagonal */
        int p = k;
        double big = fabs(A[(size_t)k * N + (size_t)k]);
        for (int i = k + 1; i < n; i++) {
            double v = fabs(A[(size_t)i * N + (size_t)k]);
            if (v > big) {
                big = v;
                p = i;
            }
        }
        piv[k] = p;
        if (!(big > 0.0) || !isfinite(big))
            return k + 1; /* exactly zero (or NaN/Inf) pivot */
        double *rk = A + (size_t)k * N;
        if (p != k) {
            double *rp = A + (size_t)p * N;
            for (int j = 0; j < n; j++) {
                double tmp = rk[j];
                rk[j] = rp[j];
                rp[j] = tmp;
            }
        }
        const double inv = 1.0 / rk[k];
        for (int i = k + 1; i < n; i++) {
            double *ri = A + (size_t)i * N;
            const double l = ri[k] * inv;
            ri[k] = l;
            if (l != 0.0)
                for (int j = k + 1; j < n; j++)
                    ri[j] -= l * rk[j];
        }
    }
    return 0;
}

void dyn_lu_solve(int n, const double *LU, const int *piv, double *b)
{
    const size_t N = (size_t)n;
    /* P b, in the order of the interchanges */
    for (int k = 0; k < n; k++) {
        int p = piv[k];
        if (p != k) {
            double tmp = b[k];
            b[k] = b[p];
            b[p] = tmp;
        }
    }
    /* L z = P b (unit lower triangle) */
    for (int i = 1; i < n; i++) {
        const double *ri = LU + (size_t)i * N;
        double s = b[i];
        for (int j = 0; j < i; j++)
            s -= ri[j] * b[j];
        b[i] = s;
    }
    /* U x = z */
    for (int i = n - 1; i >= 0; i--) {
        const double *ri = LU + (size_t)i * N;
        double s = b[i];
        for (int j = i + 1; j < n; j++)
            s -= ri[j] * b[j];
        b[i] = s / ri[i];
    }
}

void dyn_mat_vec(int n, const double *A, const double *x, double *y)
{
    const size_t N = (size_t)n;
    for (int i = 0; i < n; i++) {
        const double *ri = A + (size_t)i * N;
        double s = 0.0;
        for (int j = 0; j < n; j++)
            s += ri[j] * x[j];
        y[i] = s;
    }
}
