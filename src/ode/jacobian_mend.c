/* SPDX-License-Identifier: BSD-3-Clause */
/* jacobian_mend.c — an exact Jacobian mended where it cannot be evaluated (dynkit/ode.h,
 * dyn_jacobian_mend): a column with an entry that is not finite while f(t, y) is finite is
 * formed by differences instead, one call of f per such column. The case: f's formula
 * passes through an infinity that a later operation takes back to a finite value
 * (1/(1 + k (1 + 1/p)) at p = 0 is 0), while its derivative multiplies that infinity by
 * zero (NaN). Forward differences with the increments of jacobian.c (SUNDIALS CVODE's
 * cvLsDenseDQJac, Hairer & Wanner's RODAS), backward when the forward column is not
 * finite either (a formula defined on one side only). Dense, band and sparse storage. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "ode/jacobian.h"

/* Column j of df/dy at (t, y) by a one-sided difference into col (n); yp (n) holds y and
 * is given back holding y. 0, or the non-zero value of f. */
static int difference_column(const dyn_system *sys, double t, const double *y, const double *f0,
                             const double *typ, int j, double *yp, double *col, long *calls)
{
    const int n = sys->n;
    const double srur = sqrt(DBL_EPSILON);
    double d = srur * fmax(fabs(y[j]), typ ? typ[j] : DYN_FD_TYPICAL);
    if (!(d > 0.0))
        d = srur;
    for (int side = 0; side < 2; side++) {
        yp[j] = y[j] + (side ? -d : d);
        const double taken = yp[j] - y[j]; /* the increment actually taken */
        const int rc = sys->f(t, yp, col, sys->par);
        yp[j] = y[j];
        ++*calls;
        if (rc)
            return rc;
        int finite = 1;
        for (int i = 0; i < n; i++) {
            col[i] = (col[i] - f0[i]) / taken;
            finite &= isfinite(col[i]) != 0;
        }
        if (finite)
            break;
    }
    return 0;
}

static int all_finite(const double *v, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return 0;
    return 1;
}

int dyn_jacobian_mend(const dyn_system *sys, double t, const double *y, const double *f0,
                      const double *typ, double *J, double *work, long *rhs_calls,
                      long *columns)
{
    const int n = sys->n;
    const size_t N = (size_t)n;
    if (!all_finite(f0, n))
        return 0;
    double *yp = work, *col = work + N;
    memcpy(yp, y, N * sizeof *yp);
    long calls = 0, mended = 0;
    int rc = 0;
    for (int j = 0; j < n && !rc; j++) {
        int finite = 1;
        for (int i = 0; i < n && finite; i++)
            finite = isfinite(J[(size_t)i * N + (size_t)j]) != 0;
        if (finite)
            continue;
        rc = difference_column(sys, t, y, f0, typ, j, yp, col, &calls);
        for (int i = 0; i < n && !rc; i++)
            J[(size_t)i * N + (size_t)j] = col[i];
        mended += !rc;
    }
    if (rhs_calls)
        *rhs_calls += calls;
    if (columns)
        *columns += mended;
    return rc;
}

int dyn_jacobian_band_mend(const dyn_system *sys, double t, const double *y, const double *f0,
                           const double *typ, int lower, int upper, double *J, double *work,
                           long *rhs_calls, long *columns)
{
    const int n = sys->n;
    if (!all_finite(f0, n))
        return 0;
    double *yp = work, *col = work + (size_t)n;
    memcpy(yp, y, (size_t)n * sizeof *yp);
    long calls = 0, mended = 0;
    int rc = 0;
    for (int j = 0; j < n && !rc; j++) {
        const int i0 = j - upper > 0 ? j - upper : 0;
        const int i1 = j + lower < n - 1 ? j + lower : n - 1;
        int finite = 1;
        for (int i = i0; i <= i1 && finite; i++)
            finite = isfinite(DYN_BAND_AT(J, lower, upper, i, j)) != 0;
        if (finite)
            continue;
        rc = difference_column(sys, t, y, f0, typ, j, yp, col, &calls);
        for (int i = i0; i <= i1 && !rc; i++)
            DYN_BAND_AT(J, lower, upper, i, j) = col[i];
        mended += !rc;
    }
    if (rhs_calls)
        *rhs_calls += calls;
    if (columns)
        *columns += mended;
    return rc;
}

int dyn_jacobian_sparse_mend(const dyn_system *sys, double t, const double *y, const double *f0,
                             const double *typ, const dyn_sparse_pattern *p, double *J,
                             double *work, long *rhs_calls, long *columns)
{
    const int n = sys->n;
    if (!all_finite(f0, n))
        return 0;
    double *yp = work, *col = work + (size_t)n;
    memcpy(yp, y, (size_t)n * sizeof *yp);
    long calls = 0, mended = 0;
    int rc = 0;
    for (int j = 0; j < n && !rc; j++) {
        const int k0 = p->colptr[j], k1 = p->colptr[j + 1];
        if (all_finite(J + k0, k1 - k0))
            continue;
        rc = difference_column(sys, t, y, f0, typ, j, yp, col, &calls);
        for (int k = k0; k < k1 && !rc; k++)
            J[k] = col[p->rowind[k]];
        mended += !rc;
    }
    if (rhs_calls)
        *rhs_calls += calls;
    if (columns)
        *columns += mended;
    return rc;
}
