/* SPDX-License-Identifier: BSD-3-Clause */
/* jacobian.c — forward-difference Jacobian df/dy and time derivative df/dt.
 * Increments sqrt(eps) * max(|y_j|, typ_j) as in SUNDIALS CVODE's cvLsDenseDQJac and
 * Hairer & Wanner's RODAS/RADAU5 (HNW II, sec. IV.8), made exactly representable
 * (Dennis & Schnabel, sec. 5.4). */
#include <float.h>
#include <math.h>
#include <string.h>

#include "ode/jacobian.h"

int dyn_fd_jacobian(const dyn_system *sys, double t, const double *y, const double *f0,
                    const double *typ, double *J, double *work, long *rhs_calls)
{
    const int n = sys->n;
    const size_t N = (size_t)n;
    const double srur = sqrt(DBL_EPSILON);
    double *yp = work, *fp = work + N;
    memcpy(yp, y, N * sizeof *yp);
    for (int j = 0; j < n; j++) {
        const double scale = typ ? typ[j] : DYN_FD_TYPICAL;
        double d = srur * fmax(fabs(y[j]), scale);
        if (!(d > 0.0))
            d = srur; /* a zero or NaN typical value: fall back to an absolute increment */
        yp[j] = y[j] + d;
        d = yp[j] - y[j]; /* the increment actually taken */
        int rc = sys->f(t, yp, fp, sys->par);
        if (rhs_calls)
            (*rhs_calls)++;
        yp[j] = y[j];
        if (rc)
            return rc;
        const double inv = 1.0 / d;
        for (int i = 0; i < n; i++)
            J[(size_t)i * N + (size_t)j] = (fp[i] - f0[i]) * inv;
    }
    return 0;
}

int dyn_fd_dfdt(const dyn_system *sys, double t, const double *y, const double *f0,
                double tscale, double *ft, double *work, long *rhs_calls)
{
    const int n = sys->n;
    double d = sqrt(DBL_EPSILON) * fmax(fabs(t), fabs(tscale));
    if (!(d > 0.0))
        d = sqrt(DBL_EPSILON);
    if (tscale < 0.0)
        d = -d;
    const double tp = t + d;
    d = tp - t;
    int rc = sys->f(tp, y, work, sys->par);
    if (rhs_calls)
        (*rhs_calls)++;
    if (rc)
        return rc;
    const double inv = 1.0 / d;
    for (int i = 0; i < n; i++)
        ft[i] = (work[i] - f0[i]) * inv;
    return 0;
}
