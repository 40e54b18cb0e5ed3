/* SPDX-License-Identifier: BSD-3-Clause */
/* The past of a delay equation (dynkit/delay.h): the accepted steps' dense output in a
 * bounded store, read at t - lag by the method of steps, and the breaking points of
 * constant lags (Bellen & Zennaro, "Numerical Methods for Delay Differential Equations",
 * Oxford 2003, sec. 3.1 and 4.1). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/delay.h"

void dyn_history_init(dyn_history *h, int n, int degree, double t0, const double *y0,
                      dyn_history_fn before, const void *par, double max_delay, double *data,
                      long capacity)
{
    dyn_history_grow_fn grow = h->grow;
    void *ctx = h->grow_ctx;
    memset(h, 0, sizeof *h);
    h->n = n;
    h->degree = degree;
    h->t0 = t0;
    h->y0 = y0;
    h->before = before;
    h->par = par;
    h->max_delay = max_delay > 0.0 ? max_delay : 0.0;
    h->data = data;
    h->capacity = data ? capacity : 0;
    h->t_last = t0;
    h->grow = grow;
    h->grow_ctx = ctx;
    h->fail_state = -1;
}

static size_t block(const dyn_history *h) { return dyn_dense_record_block(h->n, h->degree); }

static double *at(const dyn_history *h, long k) /* k-th kept step, 0 the oldest */
{
    return h->data + (size_t)(h->first + k) * block(h);
}

int dyn_history_push(const dyn_dense *step, void *ctx)
{
    dyn_history *h = ctx;
    if (step->n != h->n || step->degree != h->degree)
        return DYN_ERR_ARG;
    /* a restart (after a reset) inside a kept step: the steps that begin after it go */
    while (h->count > 0 && at(h, h->count - 1)[0] >= step->t0)
        h->count--;
    /* the steps that end before the longest lag can reach go */
    const double end = step->t0 + step->h;
    if (h->max_delay > 0.0)
        while (h->count > 0) {
            const double *b = at(h, 0);
            if (!(b[0] + b[1] < end - h->max_delay * (1.0 + 1e-12)))
                break;
            h->first++;
            h->count--;
        }
    if (h->count == 0)
        h->first = 0;
    if (h->first + h->count >= h->capacity) {
        if (h->first > 0) { /* move the kept steps to the front */
            memmove(h->data, at(h, 0), (size_t)h->count * block(h) * sizeof *h->data);
            h->first = 0;
        }
        if (h->count >= h->capacity && (!h->grow || h->grow(h, h->grow_ctx) ||
                                        h->count >= h->capacity)) {
            h->failed = 4;
            h->fail_t = end;
            return DYN_ERR_CAPACITY;
        }
    }
    double *b = at(h, h->count);
    b[0] = step->t0;
    b[1] = step->h;
    h->t_last = end;
    memcpy(b + 2, step->coef, ((size_t)h->degree + 1) * (size_t)h->n * sizeof *b);
    h->count++;
    return 0;
}

/* Component i of a block's polynomial at t (dense.c's nested form). */
static double eval_block(const dyn_history *h, const double *b, int i, double t)
{
    const int n = h->n, q = h->degree;
    const double *c = b + 2;
    const double s = (t - b[0]) / b[1], s1 = 1.0 - s;
    double v = c[(size_t)q * (size_t)n + (size_t)i];
    for (int j = q - 1; j >= 1; j--)
        v = c[(size_t)j * (size_t)n + (size_t)i] + ((j & 1) ? s1 : s) * v;
    return c[i] + s * v;
}

static double refuse(dyn_history *h, int code, int i, double now, double lag)
{
    /* the latest: a run that fails, fails on it; but a NaN lag that the NaN of a refused
     * one made (the state it spoilt) does not hide that one */
    if (!(isnan(lag) && (h->failed == 1 || h->failed == 2))) {
        h->failed = code;
        h->fail_t = now;
        h->fail_lag = lag;
        h->fail_state = i;
    }
    return NAN;
}

double dyn_history_value(dyn_history *h, int i, double now, double t)
{
    if (!h)
        return NAN; /* no history attached: the model's functions return before this */
    const double lag = now - t;
    if (isnan(lag))
        return refuse(h, 3, i, now, lag);
    if (!(lag >= 0.0))
        return refuse(h, 2, i, now, lag);
    if (h->max_delay > 0.0 && lag > h->max_delay * (1.0 + 1e-12))
        return refuse(h, 1, i, now, lag);
    /* before t0 the history; at t0 itself the history's left limit for a stage inside or
     * at the end of a step (the step that ends on the breaking point t0 + lag), the initial
     * state for a step that starts there (they differ when the history jumps at t0) */
    if (t < h->t0 || (t == h->t0 && now > h->t_last))
        return h->before ? h->before(i, t, h->par, h->y0) : h->y0[i];
    if (h->count == 0)
        return h->y0[i]; /* the first step reads its own start */
    /* the last step that begins at or before t (the later one where two overlap) */
    long lo = 0, hi = h->count - 1;
    if (at(h, 0)[0] > t)
        return h->y0[i]; /* dropped: only when the lag exceeds a max_delay of rounding */
    while (lo < hi) {
        const long mid = lo + (hi - lo + 1) / 2;
        if (at(h, mid)[0] <= t)
            lo = mid;
        else
            hi = mid - 1;
    }
    return eval_block(h, at(h, lo), i, t);
}

char *dyn_history_message(const dyn_history *h, const char *const *names, char *buf,
                          size_t size)
{
    char name[32];
    if (names && h->fail_state >= 0)
        snprintf(name, sizeof name, "%.24s", names[h->fail_state]);
    else
        snprintf(name, sizeof name, "y%d", h->fail_state);
    if (h->failed == 1)
        snprintf(buf, size,
                 "delay(%s, ...) at t = %.17g asks for a lag of %.17g, longer than the maximal "
                 "delay %g (the model's @ delay=): raise it",
                 name, h->fail_t, h->fail_lag, h->max_delay);
    else if (h->failed == 2)
        snprintf(buf, size,
                 "delay(%s, ...) at t = %.17g asks for a negative lag %.17g, the value at "
                 "t = %.17g, after the present (the future): a lag must be >= 0",
                 name, h->fail_t, h->fail_lag, h->fail_t - h->fail_lag);
    else if (h->failed == 3)
        snprintf(buf, size,
                 "delay(%s, ...) at t = %.17g asks for a lag that is not a number (NaN): the "
                 "lag's formula gave NaN there",
                 name, h->fail_t);
    else if (h->failed == 4)
        snprintf(buf, size,
                 "out of memory for the delay history at t = %.17g: %ld steps kept (%.1f MB); "
                 "a file's '@ delay=' (the longest lag) keeps only the steps within it",
                 h->fail_t, h->count,
                 (double)h->count * (double)block(h) * sizeof(double) / 1048576.0);
    else
        snprintf(buf, size, "no delay failed");
    return buf;
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Every sum t0 + sum k_j lags[j] with sum k_j <= levels in (t0, t1], depth-first from lag
 * j on (each combination once); at most cap kept, the caller sorts. */
static void sums(double t, double t1, const double *lags, int n_lags, int j, int left,
                 double *out, long cap, long *count)
{
    for (int k = j; k < n_lags && left > 0; k++) {
        const double s = t + lags[k];
        if (!(s <= t1))
            continue;
        if (*count < cap)
            out[(*count)++] = s;
        sums(s, t1, lags, n_lags, k, left - 1, out, cap, count);
    }
}

long dyn_delay_breaks(double t0, double t1, const double *lags, int n_lags, int levels,
                      double *out, long cap)
{
    long count = 0;
    double distinct[DYN_DELAY_MAX_LAGS];
    int nd = 0;
    for (int k = 0; k < n_lags; k++) {
        if (!(lags[k] > 0.0) || !isfinite(lags[k]))
            return 0;
        int seen = 0;
        for (int j = 0; j < nd && !seen; j++)
            seen = fabs(distinct[j] - lags[k]) <= 1e-14 * lags[k];
        if (!seen && nd < DYN_DELAY_MAX_LAGS)
            distinct[nd++] = lags[k];
    }
    if (cap <= 0 || nd == 0 || levels <= 0)
        return 0;
    sums(t0, t1, distinct, nd, 0, levels, out, cap, &count);
    qsort(out, (size_t)count, sizeof *out, cmp_double);
    long m = 0;
    for (long k = 0; k < count; k++)
        if (m == 0 || out[k] - out[m - 1] > 1e-12 * fmax(fabs(out[k]), 1.0))
            out[m++] = out[k];
    return m;
}
