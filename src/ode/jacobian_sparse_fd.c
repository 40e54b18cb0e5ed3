/* SPDX-License-Identifier: BSD-3-Clause */
/* jacobian_sparse_fd.c — a forward-difference Jacobian in the storage of a sparse pattern
 * with its columns in groups: columns that share no row are perturbed in the same call of
 * f, so a Jacobian costs (number of groups) calls instead of n (Curtis, Powell & Reid, "On
 * the estimation of sparse Jacobian matrices", IMA J. Appl. Math. 13 (1974), their greedy
 * assignment in the columns' order; Coleman & Moré, SIAM J. Numer. Anal. 20 (1983), for the
 * groups as a colouring of the column intersection graph). Increments as in jacobian.c. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/ode.h"
#include "ode/jacobian.h"

int dyn_sparse_groups(const dyn_sparse_pattern *p, int *group)
{
    const int n = p->n, nnz = p->nnz;
    /* the rows' columns (the pattern transposed), and the last column that used a group */
    int *rowptr = calloc((size_t)n + 1, sizeof *rowptr);
    int *cols = malloc(((size_t)nnz + 1) * sizeof *cols);
    int *seen = malloc(((size_t)n + 1) * sizeof *seen);
    int groups = -1;
    if (!rowptr || !cols || !seen)
        goto done;
    for (int k = 0; k < nnz; k++)
        rowptr[p->rowind[k] + 1]++;
    for (int i = 0; i < n; i++)
        rowptr[i + 1] += rowptr[i];
    for (int j = 0; j < n; j++)
        for (int k = p->colptr[j]; k < p->colptr[j + 1]; k++)
            cols[rowptr[p->rowind[k]]++] = j;
    for (int i = n; i > 0; i--) /* back to the rows' starts */
        rowptr[i] = rowptr[i - 1];
    rowptr[0] = 0;
    for (int g = 0; g <= n; g++)
        seen[g] = -1;
    groups = 0;
    for (int j = 0; j < n; j++) {
        /* the groups of the earlier columns that share a row with j are taken */
        for (int k = p->colptr[j]; k < p->colptr[j + 1]; k++) {
            const int i = p->rowind[k];
            for (int q = rowptr[i]; q < rowptr[i + 1] && cols[q] < j; q++)
                seen[group[cols[q]]] = j;
        }
        int g = 0;
        while (seen[g] == j)
            g++;
        group[j] = g;
        if (g + 1 > groups)
            groups = g + 1;
    }
done:
    free(rowptr);
    free(cols);
    free(seen);
    return groups;
}

int dyn_fd_jacobian_sparse(const dyn_system *sys, double t, const double *y, const double *f0,
                           const double *typ, const dyn_sparse_pattern *p, const int *group,
                           int n_groups, double *J, double *work, long *rhs_calls)
{
    const int n = sys->n;
    const double srur = sqrt(DBL_EPSILON);
    double *yp = work, *fp = work + n;
    memcpy(yp, y, (size_t)n * sizeof *yp);
    for (int g = 0; g < n_groups; g++) {
        for (int j = 0; j < n; j++)
            if (group[j] == g) {
                const double scale = typ ? typ[j] : DYN_FD_TYPICAL;
                double d = srur * fmax(fabs(y[j]), scale);
                if (!(d > 0.0))
                    d = srur;
                yp[j] = y[j] + d;
            }
        const int rc = sys->f(t, yp, fp, sys->par);
        if (rhs_calls)
            (*rhs_calls)++;
        if (rc) {
            memcpy(yp, y, (size_t)n * sizeof *yp);
            return rc;
        }
        for (int j = 0; j < n; j++)
            if (group[j] == g) {
                const double inv = 1.0 / (yp[j] - y[j]); /* the increment actually taken */
                yp[j] = y[j];
                for (int k = p->colptr[j]; k < p->colptr[j + 1]; k++)
                    J[k] = (fp[p->rowind[k]] - f0[p->rowind[k]]) * inv;
            }
    }
    return 0;
}
