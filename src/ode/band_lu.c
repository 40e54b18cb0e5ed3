/* SPDX-License-Identifier: BSD-3-Clause */
/* band_lu.c — LU factorisation with partial pivoting of a band matrix and its solve, in
 * LAPACK's factor storage (the library's own dyn_band_solver). The algorithm and storage
 * are those of LAPACK's unblocked dgbtf2 and of dgbtrs (no transpose): at step j the pivot
 * is sought among the `lower` rows below the diagonal, the interchange and the update reach
 * at most column j + lower + upper, so U has lower + upper superdiagonals (Golub & Van Loan,
 * "Matrix Computations", 4th ed., sec. 4.3.5). Work O(n lower (lower + upper)). 0-based
 * pivots: piv[j] is the row interchanged with row j. */
#include <math.h>
#include <stddef.h>

#include "ode/linalg.h"

/* A(i, j) of the factor storage, kv = lower + upper. */
#define AB(i, j) ab[(size_t)(j) * (size_t)ldab + (size_t)(kv + (i) - (j))]

int dyn_band_lu_factor(int n, int lower, int upper, double *ab, int ldab, int *piv)
{
    const int kv = lower + upper;
    int ju = 0; /* last column reached by the interchanges so far */
    for (int j = 0; j < n; j++) {
        const int km = lower < n - 1 - j ? lower : n - 1 - j;
        int jp = 0;
        double big = fabs(AB(j, j));
        for (int i = 1; i <= km; i++) {
            const double v = fabs(AB(j + i, j));
            if (v > big) {
                big = v;
                jp = i;
            }
        }
        piv[j] = j + jp;
        if (!(big > 0.0) || !isfinite(big))
            return j + 1;
        const int reach = j + upper + jp < n - 1 ? j + upper + jp : n - 1;
        if (reach > ju)
            ju = reach;
        if (jp != 0)
            for (int c = j; c <= ju; c++) {
                const double tmp = AB(j, c);
                AB(j, c) = AB(j + jp, c);
                AB(j + jp, c) = tmp;
            }
        const double inv = 1.0 / AB(j, j);
        for (int i = 1; i <= km; i++)
            AB(j + i, j) *= inv;
        for (int c = j + 1; c <= ju; c++) {
            const double a = AB(j, c);
            if (a != 0.0)
                for (int i = 1; i <= km; i++)
                    AB(j + i, c) -= AB(j + i, j) * a;
        }
    }
    return 0;
}

void dyn_band_lu_solve(int n, int lower, int upper, const double *ab, int ldab, const int *piv,
                       double *b)
{
    const int kv = lower + upper;
    /* L z = P b, the interchanges applied as they were made */
    for (int j = 0; j < n - 1; j++) {
        const int lm = lower < n - 1 - j ? lower : n - 1 - j;
        const int p = piv[j];
        if (p != j) {
            const double tmp = b[p];
            b[p] = b[j];
            b[j] = tmp;
        }
        const double bj = b[j];
        if (bj != 0.0)
            for (int i = 1; i <= lm; i++)
                b[j + i] -= AB(j + i, j) * bj;
    }
    /* U x = z, by columns */
    for (int j = n - 1; j >= 0; j--) {
        const double xj = b[j] / AB(j, j);
        b[j] = xj;
        const int i0 = j - kv > 0 ? j - kv : 0;
        if (xj != 0.0)
            for (int i = i0; i < j; i++)
                b[i] -= AB(i, j) * xj;
    }
}

const dyn_band_solver dyn_band_solver_builtin = {
    "builtin", dyn_band_lu_factor, dyn_band_lu_solve,
};
