/* SPDX-License-Identifier: BSD-3-Clause */
/* sparse_pattern.c — patterns of sparse Jacobians in compressed sparse columns (dynkit/ode.h,
 * dyn_sparse_pattern; the storage of KLU and of SUNDIALS' CSC_MAT): the check of a pattern
 * the stiff methods are given, and its bandwidths (a narrow band is factored by a band LU,
 * docs/stiff.md "Large systems"). */
#include <stdio.h>

#include "dynkit/ode.h"

int dyn_sparse_pattern_check(const dyn_sparse_pattern *p, int n, char *err, size_t errlen)
{
#define PATTERN_FAIL(...)                                                                    \
    do {                                                                                     \
        if (err && errlen)                                                                   \
            snprintf(err, errlen, __VA_ARGS__);                                              \
        return 1;                                                                            \
    } while (0)
    if (!p || p->n != n || !p->colptr || !p->rowind || p->nnz < n)
        PATTERN_FAIL("the sparse pattern of the Jacobian must be for n = %d states with at "
                     "least the n diagonal entries (got n = %d, nnz = %d)",
                     n, p ? p->n : -1, p ? p->nnz : -1);
    if (p->colptr[0] != 0 || p->colptr[n] != p->nnz)
        PATTERN_FAIL("the sparse pattern's column pointers must run from 0 to nnz = %d",
                     p->nnz);
    for (int j = 0; j < n; j++) {
        int diag = 0;
        if (p->colptr[j + 1] < p->colptr[j])
            PATTERN_FAIL("the sparse pattern's column pointers decrease at column %d", j);
        for (int k = p->colptr[j]; k < p->colptr[j + 1]; k++) {
            const int i = p->rowind[k];
            if (i < 0 || i >= n || (k > p->colptr[j] && i <= p->rowind[k - 1]))
                PATTERN_FAIL("the sparse pattern's rows in column %d must increase within "
                             "[0, %d)",
                             j, n);
            diag |= i == j;
        }
        if (!diag)
            PATTERN_FAIL("the sparse pattern lacks the diagonal entry of column %d (the stiff "
                         "methods need every one)",
                         j);
    }
    return 0;
#undef PATTERN_FAIL
}

void dyn_sparse_pattern_band(const dyn_sparse_pattern *p, int *lower, int *upper)
{
    int lo = 0, up = 0;
    for (int j = 0; j < p->n; j++)
        for (int k = p->colptr[j]; k < p->colptr[j + 1]; k++) {
            const int d = p->rowind[k] - j;
            if (d > lo)
                lo = d;
            if (-d > up)
                up = -d;
        }
    *lower = lo;
    *upper = up;
}
