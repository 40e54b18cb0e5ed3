/* SPDX-License-Identifier: BSD-3-Clause */
/* sparse_probe.c — a sparsity pattern of df/dy found by evaluating f (dyn_sparse_probe,
 * dynkit/ode.h): at a few points near y, each state perturbed in turn; an entry is in the
 * pattern when its difference quotient is not zero at one of the points (the union over
 * the points), and every diagonal entry is. The points are y plus uniform random offsets
 * of up to a tenth of max(|y_j|, 1), Philox4x32-10 numbers of (seed, point, state), so the
 * pattern depends on its arguments alone. An entry that vanishes at every point probed (a
 * coupling through a factor that is zero there, a branch not taken) is missed: the risk is
 * the caller's, stated in docs/stiff.md. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/ode.h"
#include "dynkit/sde.h"

/* The uniform number in (-1, 1) of (seed, point, state). */
static double offset(uint64_t seed, int point, int j)
{
    const uint32_t ctr[4] = {(uint32_t)j, (uint32_t)point, 0x70726f62u, 0};
    const uint32_t key[2] = {(uint32_t)seed, (uint32_t)(seed >> 32)};
    uint32_t out[4];
    dyn_philox4x32(ctr, key, 10, out);
    return 2.0 * dyn_philox_unit(out[0], out[1]) - 1.0;
}

int dyn_sparse_probe(const dyn_system *sys, double t, const double *y, int points,
                     uint64_t seed, dyn_sparse_pattern *out, char *err, size_t errlen)
{
    const int n = sys->n;
    const size_t N = (size_t)n;
    memset(out, 0, sizeof *out);
    if (n <= 0 || points < 1 || points > 64) {
        snprintf(err, errlen, "probing a pattern needs n > 0 states and 1 to 64 points (got "
                              "%d and %d)", n, points);
        return -1;
    }
    const size_t P = (size_t)points;
    /* the points and f there, (points x n) each; the rows of the column being probed */
    double *yq = malloc(P * N * sizeof *yq), *fq = malloc(P * N * sizeof *fq);
    double *f1 = malloc(N * sizeof *f1);
    int *mark = malloc(N * sizeof *mark), *colptr = malloc((N + 1) * sizeof *colptr);
    size_t cap = 4 * N + 16, nnz = 0;
    int *rowind = malloc(cap * sizeof *rowind), rc = -1;
    if (!yq || !fq || !f1 || !mark || !colptr || !rowind) {
        snprintf(err, errlen, "out of memory probing the pattern of %d states", n);
        goto done;
    }
    for (int q = 0; q < points; q++) {
        double *yp = yq + (size_t)q * N;
        for (int j = 0; j < n; j++)
            yp[j] = y[j] + 0.1 * fmax(fabs(y[j]), 1.0) * offset(seed, q, j);
        if (sys->f(t, yp, fq + (size_t)q * N, sys->par)) {
            snprintf(err, errlen, "the right-hand side failed at probe point %d", q + 1);
            goto done;
        }
    }
    for (int j = 0; j < n; j++)
        mark[j] = -1;
    for (int j = 0; j < n; j++) {
        colptr[j] = (int)nnz;
        mark[j] = j; /* the diagonal */
        for (int q = 0; q < points; q++) {
            double *yp = yq + (size_t)q * N;
            const double *f0 = fq + (size_t)q * N;
            const double keep = yp[j], d = sqrt(DBL_EPSILON) * fmax(fabs(keep), 1.0);
            yp[j] = keep + d;
            const int bad = sys->f(t, yp, f1, sys->par);
            yp[j] = keep;
            if (bad) {
                snprintf(err, errlen, "the right-hand side failed at probe point %d with "
                                      "state %d perturbed", q + 1, j);
                goto done;
            }
            for (int i = 0; i < n; i++)
                if (f1[i] != f0[i] || !isfinite(f1[i]))
                    mark[i] = j;
        }
        for (int i = 0; i < n; i++) /* the rows in increasing order */
            if (mark[i] == j) {
                if (nnz == cap) {
                    int *more = nnz < 0x3fffffff ? realloc(rowind, 2 * cap * sizeof *more)
                                                 : NULL;
                    if (!more) {
                        snprintf(err, errlen, "out of memory for a pattern of %zu entries",
                                 nnz);
                        goto done;
                    }
                    rowind = more;
                    cap *= 2;
                }
                rowind[nnz++] = i;
            }
    }
    colptr[n] = (int)nnz;
    *out = (dyn_sparse_pattern){n, (int)nnz, colptr, rowind};
    colptr = rowind = NULL;
    rc = 0;
done:
    free(yq);
    free(fq);
    free(f1);
    free(mark);
    free(colptr);
    free(rowind);
    return rc;
}

void dyn_sparse_pattern_free(dyn_sparse_pattern *p)
{
    if (!p)
        return;
    free((void *)p->colptr);
    free((void *)p->rowind);
    memset(p, 0, sizeof *p);
}
