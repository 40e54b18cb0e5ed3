/* SPDX-License-Identifier: BSD-3-Clause */
/* Dense output: evaluation of a step's interpolation polynomial in Hairer's nested form
 * (a Horner-like scheme with the factors theta and 1 - theta, as DOPRI5's CONTD5 and
 * DOP853's CONTD8) and its derivative, and the caller-owned recorder that keeps the dense
 * output of every step (HNW I sec. II.6, "Dense output").
 */
#include <string.h>

#include "dynkit/solve.h"
#include "ode/stepper.h"

void dyn_dense_eval(const dyn_dense *d, double t, double *y)
{
    const int n = d->n, q = d->degree;
    const double s = (t - d->t0) / d->h, s1 = 1.0 - s;
    const double *c = d->coef;
    for (int i = 0; i < n; i++) {
        double v = c[(size_t)q * (size_t)n + (size_t)i];
        for (int j = q - 1; j >= 1; j--)
            v = c[(size_t)j * (size_t)n + (size_t)i] + ((j & 1) ? s1 : s) * v;
        y[i] = c[i] + s * v;
    }
}

void dyn_dense_deriv(const dyn_dense *d, double t, double *dydt)
{
    const int n = d->n, q = d->degree;
    const double s = (t - d->t0) / d->h, s1 = 1.0 - s;
    const double *c = d->coef;
    for (int i = 0; i < n; i++) {
        double v = c[(size_t)q * (size_t)n + (size_t)i], dv = 0.0; /* value and d/dtheta */
        for (int j = q - 1; j >= 1; j--) {
            const double w = (j & 1) ? s1 : s, dw = (j & 1) ? -1.0 : 1.0;
            dv = dw * v + w * dv;
            v = c[(size_t)j * (size_t)n + (size_t)i] + w * v;
        }
        dydt[i] = (v + s * dv) / d->h;
    }
}

int dyn_method_dense_degree(const dyn_tableau *m)
{
    const dyn_stepper_ops *ops = dyn_stepper_ops_for(m);
    return ops ? ops->dense_degree(m) : 0;
}

size_t dyn_dense_record_block(int n, int degree)
{
    return 2 + ((size_t)degree + 1) * (size_t)n;
}

void dyn_dense_record_init(dyn_dense_record *rec, int n, int degree, double *data,
                           long capacity)
{
    dyn_record_grow_fn grow = rec->grow;
    void *ctx = rec->grow_ctx;
    memset(rec, 0, sizeof *rec);
    rec->n = n;
    rec->degree = degree;
    rec->data = data;
    rec->capacity = data ? capacity : 0;
    rec->grow = grow;
    rec->grow_ctx = ctx;
}

int dyn_dense_record_step(const dyn_dense_record *rec, long i, dyn_dense *d)
{
    if (!rec || i < 0 || i >= rec->count)
        return DYN_ERR_ARG;
    const double *b = rec->data + (size_t)i * dyn_dense_record_block(rec->n, rec->degree);
    d->t0 = b[0];
    d->h = b[1];
    d->n = rec->n;
    d->degree = rec->degree;
    d->coef = b + 2;
    return 0;
}

int dyn_dense_record_eval(const dyn_dense_record *rec, double t, double *y)
{
    if (!rec || rec->count < 1)
        return DYN_ERR_ARG;
    const size_t block = dyn_dense_record_block(rec->n, rec->degree);
    const double *first = rec->data, *last = rec->data + (size_t)(rec->count - 1) * block;
    if (!(t >= first[0] && t <= last[0] + last[1]))
        return DYN_ERR_ARG;
    long lo = 0, hi = rec->count - 1; /* the last step with t0 <= t */
    while (lo < hi) {
        long mid = lo + (hi - lo + 1) / 2;
        if (rec->data[(size_t)mid * block] <= t)
            lo = mid;
        else
            hi = mid - 1;
    }
    dyn_dense d;
    dyn_dense_record_step(rec, lo, &d);
    dyn_dense_eval(&d, t, y);
    return 0;
}
