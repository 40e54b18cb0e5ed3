/* SPDX-License-Identifier: BSD-3-Clause */
/* Step-size selection of the general driver: Hairer's error norm and the initial step of
 * HNW I sec. II.4 (the algorithm of HINIT in DOPRI5/DOP853). The PI controller of DOPRI5
 * is dyn_sinl_ctl_* of dynkit/solve_inline.h, one copy for both drivers.
 */
#include <float.h>
#include <math.h>

#include "ode/step_control.h"

double dyn_err_norm(const dyn_tol *tol, int n, const double *y, const double *ynew,
                    const double *err)
{
    double sum = 0.0;
    for (int i = 0; i < n; i++) {
        const double r = err[i] / dyn_tol_scale(tol, i, y[i], ynew[i]);
        sum += r * r;
    }
    return sqrt(sum / n);
}

/* RMS of v / (atol + rtol |y|). */
static double weighted_rms(const dyn_tol *tol, int n, const double *y, const double *v)
{
    double sum = 0.0;
    for (int i = 0; i < n; i++) {
        const double r = v[i] / dyn_tol_scale(tol, i, y[i], y[i]);
        sum += r * r;
    }
    return sqrt(sum / n);
}

int dyn_initial_step(dyn_stepper *st, double t0, const double *y0, int q, double hmax,
                     double *ytmp, double *ftmp, double *h)
{
    const int n = st->n;
    const double *f0;
    int rc = st->ops->deriv(st, t0, y0, &f0);
    if (rc)
        return rc;
    const double d0 = weighted_rms(&st->tol, n, y0, y0);
    const double d1 = weighted_rms(&st->tol, n, y0, f0);
    double h0 = (d0 < 1e-5 || d1 < 1e-5 || !isfinite(d0) || !isfinite(d1)) ? 1e-6
                                                                             : 0.01 * d0 / d1;
    h0 = fmin(h0, hmax);
    for (int i = 0; i < n; i++)
        ytmp[i] = y0[i] + h0 * f0[i];
    st->rhs_calls++;
    const double t1 = fmin(t0 + h0, st->tend);
    rc = st->f(t1, ytmp, ftmp, st->par);
    if (rc) {
        st->fail_t = t1;
        return rc;
    }
    double d2 = 0.0;
    for (int i = 0; i < n; i++)
        ytmp[i] = ftmp[i] - f0[i];
    d2 = weighted_rms(&st->tol, n, y0, ytmp) / h0;
    const double dmax = fmax(d1, d2);
    double h1;
    if (!(dmax > 1e-15) || !isfinite(dmax))
        h1 = fmax(1e-6, h0 * 1e-3);
    else
        h1 = pow(0.01 / dmax, 1.0 / (double)((q > 0 ? q : 1) + 1));
    *h = fmin(fmin(100.0 * h0, h1), hmax);
    if (!(*h > 0.0))
        *h = fmin(1e-6, hmax);
    return 0;
}
