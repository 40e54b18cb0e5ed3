/* SPDX-License-Identifier: BSD-3-Clause */
/* Step-size selection of the general driver: Hairer's error norm, the initial step of
 * HNW I sec. II.4 (the algorithm of HINIT in DOPRI5/DOP853) and the PI controller of DOPRI5
 * (Gustafsson 1991; HNW I sec. II.4, HNW II sec. IV.2):
 *     fac = err^(1/(q+1) - 0.75 beta) / err_old^beta,
 *     h_new = h / clamp(fac / safety, 1/fac_max, 1/fac_min),
 * with err_old the error of the previous accepted step, no growth right after a rejection,
 * and the plain h / min(1/fac_min, err^(1/(q+1) - 0.75 beta) / safety) after a rejection.
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

/* err_old^beta. Computed when err_old is stored, so that the pow is off the next step's
 * dependency chain (same value, same steps); pow(x, 0) is exactly 1, so beta == 0 (the
 * I controller) needs none. */
static double old_pow(const dyn_controller *c)
{
    return c->beta == 0.0 ? 1.0 : pow(c->err_old, c->beta);
}

double dyn_controller_exponent(int q, double beta)
{
    return 1.0 / (double)((q > 0 ? q : 1) + 1) - 0.75 * beta;
}

void dyn_controller_init(dyn_controller *c, int q, double safety, double beta, double fac_min,
                         double fac_max)
{
    c->safety = safety > 0.0 ? safety : 0.9;
    c->beta = beta < 0.0 ? 0.0 : beta > 0.0 ? beta : 0.04;
    c->fac_min = fac_min > 0.0 ? fac_min : 0.2;
    c->fac_max = fac_max > 0.0 ? fac_max : 10.0;
    c->expo = dyn_controller_exponent(q, c->beta);
    c->err_old = 1e-4;
    c->err_old_pow = old_pow(c);
}

double dyn_controller_accept(dyn_controller *c, double h, double err, int rejected_before)
{
    double fac = pow(err, c->expo) / c->err_old_pow / c->safety;
    if (!(fac >= 1.0 / c->fac_max)) /* also err == 0 */
        fac = 1.0 / c->fac_max;
    if (fac > 1.0 / c->fac_min)
        fac = 1.0 / c->fac_min;
    c->err_old = fmax(err, 1e-4);
    c->err_old_pow = old_pow(c);
    double hnew = h / fac;
    if (rejected_before && hnew > h)
        hnew = h;
    return hnew;
}

double dyn_controller_reject(const dyn_controller *c, double h, double err)
{
    if (!isfinite(err))
        return 0.25 * h; /* the trial was not finite: no estimate, shrink firmly */
    double fac = pow(err, c->expo) / c->safety;
    if (fac > 1.0 / c->fac_min)
        fac = 1.0 / c->fac_min;
    if (!(fac > 1.0))
        fac = 1.0 / 0.9; /* cannot happen for err > 1 with these constants; stay safe */
    return h / fac;
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
