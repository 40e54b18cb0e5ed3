/* SPDX-License-Identifier: BSD-3-Clause */
/* jacobian_band.c — forward-difference Jacobian of a banded system with its columns in
 * groups: columns j and j + w (w = lower + upper + 1) touch disjoint rows, so every w-th
 * column is perturbed in the same call of f and w calls give the whole band (Curtis, Powell
 * & Reid, "On the estimation of sparse Jacobian matrices", IMA J. Appl. Math. 13 (1974);
 * SUNDIALS CVODE's cvLsBandDQJac). Increments as in jacobian.c. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "ode/jacobian.h"

int dyn_fd_jacobian_band(const dyn_system *sys, double t, const double *y, const double *f0,
                         const double *typ, int lower, int upper, double *J, double *work,
                         long *rhs_calls)
{
    const int n = sys->n, w = lower + upper + 1;
    const double srur = sqrt(DBL_EPSILON);
    double *yp = work, *fp = work + n;
    memcpy(yp, y, (size_t)n * sizeof *yp);
    for (int g = 0; g < w && g < n; g++) {
        for (int j = g; j < n; j += w) {
            const double scale = typ ? typ[j] : DYN_FD_TYPICAL;
            double d = srur * fmax(fabs(y[j]), scale);
            if (!(d > 0.0))
                d = srur;
            yp[j] = y[j] + d;
        }
        int rc = sys->f(t, yp, fp, sys->par);
        if (rhs_calls)
            (*rhs_calls)++;
        if (rc) {
            memcpy(yp, y, (size_t)n * sizeof *yp);
            return rc;
        }
        for (int j = g; j < n; j += w) {
            const double inv = 1.0 / (yp[j] - y[j]); /* the increment actually taken */
            yp[j] = y[j];
            const int i0 = j - upper > 0 ? j - upper : 0;
            const int i1 = j + lower < n - 1 ? j + lower : n - 1;
            for (int i = i0; i <= i1; i++)
                DYN_BAND_AT(J, lower, upper, i, j) = (fp[i] - f0[i]) * inv;
        }
    }
    return 0;
}
