/* SPDX-License-Identifier: BSD-3-Clause */
/* Volterra integral and integro-differential equations on a fixed grid (dynkit/volterra.h):
 * product integration of the weakly singular factor (t - s)^(-mu) with the integrand's
 * values averaged over each interval (the trapezoidal rule when mu = 0), the trapezoidal
 * rule for the differential states, Newton's method on each step's implicit equations.
 * P. Linz, "Analytical and Numerical Methods for Volterra Equations", SIAM 1985, ch. 7-8;
 * the method of XPPAUT's "volterra" integrator, with its bounded memory of grid points. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dynkit/volterra.h"
#include "linalg.h"

/* Where each part of the workspace starts. */
typedef struct vlayout {
    double *hist;   /* max_points slots of n + m: y then I of grid point j at slot j % M */
    double *cnv;    /* m rows of M + 1: K_k(l h) */
    double *wmid;   /* m rows of M + 1: the weight of a point at lag l, 1 <= l <= M */
    double *sum;    /* m: the past's part of each integral */
    double *g;      /* m */
    double *ig;     /* m: the integrals at the Newton iterate */
    double *iprev;  /* m: at the last point */
    double *yg, *f, *f2, *fold, *res, *d; /* n each */
    double *jac;    /* n * n */
    int *piv;       /* n */
} vlayout;

size_t dyn_volterra_work_size(int n, int n_int, long max_points)
{
    const size_t M = (size_t)(max_points > 0 ? max_points : DYN_VOLTERRA_MAX_POINTS_DEFAULT);
    const size_t nn = (size_t)n, m = (size_t)n_int;
    return M * (nn + m) + 2 * m * (M + 1) + 4 * m + 6 * nn + nn * nn + nn + 1;
}

static void layout(int n, int m, long M, double *w, vlayout *L)
{
    L->hist = w;
    w += (size_t)M * (size_t)(n + m);
    L->cnv = w;
    w += (size_t)m * (size_t)(M + 1);
    L->wmid = w;
    w += (size_t)m * (size_t)(M + 1);
    L->sum = w;
    L->g = w + m;
    L->ig = w + 2 * m;
    L->iprev = w + 3 * m;
    w += 4 * m;
    L->yg = w;
    L->f = w + n;
    L->f2 = w + 2 * n;
    L->fold = w + 3 * n;
    L->res = w + 4 * n;
    L->d = w + 5 * n;
    w += 6 * n;
    L->jac = w;
    w += (size_t)n * (size_t)n;
    L->piv = (int *)w; /* n ints fit in n doubles */
}

/* int over lags [(l-1) h, l h] of x^(-mu) dx */
static double interval_weight(double mu, double h, long l)
{
    if (mu == 0.0)
        return h;
    const double e = 1.0 - mu;
    return pow(h, e) * (pow((double)l, e) - pow((double)(l - 1), e)) / e;
}

int dyn_volterra_start(const dyn_volterra *v, double t0, const double *y0, double *y0i,
                       double *work)
{
    for (int k = 0; k < v->n_int; k++)
        v->ints[k] = 0.0;
    double *f = work;
    const int rc = v->rhs(t0, y0, f, v->par);
    if (rc)
        return rc;
    for (int i = 0; i < v->n; i++)
        y0i[i] = v->is_int[i] ? f[i] : y0[i];
    return 0;
}

static int fail(dyn_volterra_result *res, int status, double t, const char *msg)
{
    res->r.status = status;
    res->r.fail_t = t;
    snprintf(res->r.message, sizeof res->r.message, "%s", msg);
    return status;
}

/* The integrals at (t, y) with their past parts in sum: ig = sum + (weight of the newest
 * point) * K(0) * g(t, t, y); ip are the integrals given to the integrand at t. */
static int integrals_at(const dyn_volterra *v, const vlayout *L, long M, double t, double h,
                        const double *y, const double *ip, double *ig, long *calls)
{
    const int m = v->n_int;
    if (m == 0)
        return 0;
    const int rc = v->integrand(t, t, y, ip, L->g, v->par);
    ++*calls;
    if (rc)
        return rc;
    for (int k = 0; k < m; k++) {
        const double w0 = 0.5 * interval_weight(v->mu[k], h, 1);
        const double c0 = v->conv[k] ? L->cnv[(size_t)k * (size_t)(M + 1)] : 1.0;
        ig[k] = L->sum[k] + w0 * c0 * L->g[k];
    }
    return 0;
}

/* F at (t, y) with its integrals; the residual of the step into r */
static int residual(const dyn_volterra *v, const vlayout *L, long M, double t, double h,
                    const double *y, const double *yn, double *f, double *r, dyn_stats *st)
{
    int rc = integrals_at(v, L, M, t, h, y, L->iprev, L->ig, &st->rhs_calls);
    if (rc)
        return rc;
    memcpy(v->ints, L->ig, (size_t)v->n_int * sizeof *L->ig);
    rc = v->rhs(t, y, f, v->par);
    st->rhs_calls++;
    if (rc)
        return rc;
    for (int i = 0; i < v->n; i++)
        r[i] = v->is_int[i] ? f[i] - y[i] : yn[i] + 0.5 * h * (L->fold[i] + f[i]) - y[i];
    return 0;
}

int dyn_volterra_solve(const dyn_volterra *v, double t0, double h, long nsteps,
                       const double *y0, double *y, double *work, const dyn_volterra_opts *opts,
                       dyn_volterra_result *res)
{
    static const dyn_volterra_opts none = {0};
    const dyn_volterra_opts *o = opts ? opts : &none;
    memset(res, 0, sizeof *res);
    res->forgot = NAN;
    res->r.t = t0;
    res->r.fail_index = -1;
    const int n = v->n, m = v->n_int;
    const long M = o->max_points > 0 ? o->max_points : DYN_VOLTERRA_MAX_POINTS_DEFAULT;
    if (n < 1 || m < 0 || !(h > 0.0) || nsteps < 0 || !v->rhs || (m > 0 && !v->integrand))
        return fail(res, DYN_ERR_ARG, t0, "Volterra solve: need n >= 1 states, a step h > 0, "
                                          "nsteps >= 0 and the right-hand side");
    for (int k = 0; k < m; k++) {
        if (!(v->mu[k] >= 0.0 && v->mu[k] < 1.0)) {
            char msg[160];
            snprintf(msg, sizeof msg,
                     "integral %d: the exponent of (t-t')^-m is %g; accepted: 0 <= m < 1", k + 1,
                     v->mu[k]);
            return fail(res, DYN_ERR_ARG, t0, msg);
        }
        if (v->conv[k] && !v->kernel)
            return fail(res, DYN_ERR_ARG, t0, "Volterra solve: a convolution needs its kernel");
    }
    const double tol = o->tol > 0.0 ? o->tol : 1e-10;
    const int max_iter = o->max_iter > 0 ? o->max_iter : 20;
    const long every = o->every > 1 ? o->every : 1;
    const size_t stride = (size_t)(n + m);
    vlayout L;
    layout(n, m, M, work, &L);
    dyn_stats *st = &res->r.stats;

    /* the tables of the kernels and of the weights of the points inside the window */
    double *kv = L.g;
    for (long l = 0; l <= M; l++) {
        if (v->kernel) {
            const int rc = v->kernel((double)l * h, kv, v->par);
            if (rc) {
                res->r.rhs_status = rc;
                return fail(res, DYN_ERR_RHS, t0, "the kernel of an integral returned an error");
            }
        }
        for (int k = 0; k < m; k++) {
            L.cnv[(size_t)k * (size_t)(M + 1) + (size_t)l] = v->conv[k] ? kv[k] : 1.0;
            L.wmid[(size_t)k * (size_t)(M + 1) + (size_t)l] =
                l == 0 ? 0.0
                       : 0.5 * (interval_weight(v->mu[k], h, l) +
                                interval_weight(v->mu[k], h, l + 1));
        }
    }

    /* the first point */
    double *yn = L.hist;
    int rc = dyn_volterra_start(v, t0, y0, yn, L.f);
    st->rhs_calls++;
    if (rc) {
        res->r.rhs_status = rc;
        return fail(res, DYN_ERR_RHS, t0, "the right-hand side returned an error at t0");
    }
    memset(yn + n, 0, (size_t)m * sizeof *yn);
    memset(L.iprev, 0, (size_t)m * sizeof *L.iprev);
    if (y)
        memcpy(y, yn, (size_t)n * sizeof *y);
    if (o->output && o->output(0, t0, yn, o->output_ctx)) {
        st->samples++;
        res->r.status = DYN_STOPPED;
        return DYN_STOPPED;
    }
    st->samples++;
    if (o->step && o->step(t0, yn, o->step_ctx))
        return fail(res, DYN_STOPPED, t0, "stopped");

    for (long N = 1; N <= nsteps; N++) {
        const double t = t0 + (double)N * h, tn = t0 + (double)(N - 1) * h;
        const double *ylast = L.hist + (size_t)((N - 1) % M) * stride;
        /* F at the last point, with its integrals */
        memcpy(v->ints, ylast + n, (size_t)m * sizeof *v->ints);
        rc = v->rhs(tn, ylast, L.fold, v->par);
        st->rhs_calls++;
        /* the past's part of each integral: points i0 .. N-1 */
        const long i0 = N - M > 0 ? N - M : 0;
        if (i0 > 0 && isnan(res->forgot))
            res->forgot = t;
        for (int k = 0; k < m; k++)
            L.sum[k] = 0.0;
        for (long j = i0; j < N && !rc && m > 0; j++) {
            const double *pj = L.hist + (size_t)(j % M) * stride;
            rc = v->integrand(t, t0 + (double)j * h, pj, pj + n, L.g, v->par);
            st->rhs_calls++;
            const long l = N - j;
            for (int k = 0; k < m && !rc; k++) {
                const size_t row = (size_t)k * (size_t)(M + 1);
                const double w =
                    j == i0 ? 0.5 * interval_weight(v->mu[k], h, l) : L.wmid[row + (size_t)l];
                L.sum[k] += w * L.cnv[row + (size_t)l] * L.g[k];
            }
        }
        /* Newton's method from the last point */
        memcpy(L.yg, ylast, (size_t)n * sizeof *L.yg);
        memcpy(L.iprev, ylast + n, (size_t)m * sizeof *L.iprev);
        int converged = 0;
        for (int it = 0; it < max_iter && !rc && !converged; it++) {
            rc = residual(v, &L, M, t, h, L.yg, ylast, L.f, L.res, st);
            for (int i = 0; i < n && !rc; i++) {
                const double yi = L.yg[i];
                const double del = 1e-7 * fmax(1e-7, fabs(yi));
                L.yg[i] = yi + del;
                rc = residual(v, &L, M, t, h, L.yg, ylast, L.f2, L.d, st);
                L.yg[i] = yi;
                for (int r = 0; r < n && !rc; r++)
                    L.jac[(size_t)r * (size_t)n + (size_t)i] = (L.d[r] - L.res[r]) / del;
            }
            if (rc)
                break;
            st->jac_calls++;
            if (dyn_lu_factor(n, L.jac, L.piv)) {
                char msg[200];
                snprintf(msg, sizeof msg,
                         "the Newton matrix of the step to t = %g is singular: take another dt",
                         t);
                return fail(res, DYN_ERR_STEP_SIZE, t, msg);
            }
            dyn_lu_solve(n, L.jac, L.piv, L.res);
            converged = 1;
            for (int i = 0; i < n; i++) {
                L.yg[i] -= L.res[i];
                if (!(fabs(L.res[i]) <= tol * fmax(1.0, fabs(L.yg[i]))))
                    converged = 0;
            }
        }
        if (rc) {
            res->r.rhs_status = rc;
            return fail(res, DYN_ERR_RHS, t, "the right-hand side returned an error");
        }
        for (int i = 0; i < n; i++)
            if (!isfinite(L.yg[i])) {
                res->r.fail_index = i;
                char msg[200];
                snprintf(msg, sizeof msg, "state %d is not finite at t = %g", i, t);
                return fail(res, DYN_ERR_NONFINITE, t, msg);
            }
        if (!converged) {
            char msg[200];
            snprintf(msg, sizeof msg,
                     "Newton's iteration of the step to t = %g did not converge in %d "
                     "iterations: take a smaller dt",
                     t, max_iter);
            return fail(res, DYN_ERR_STEP_SIZE, t, msg);
        }
        /* the new point, with its integrals */
        rc = integrals_at(v, &L, M, t, h, L.yg, L.iprev, L.ig, &st->rhs_calls);
        if (rc) {
            res->r.rhs_status = rc;
            return fail(res, DYN_ERR_RHS, t, "an integrand returned an error");
        }
        double *pN = L.hist + (size_t)(N % M) * stride;
        memcpy(pN, L.yg, (size_t)n * sizeof *pN);
        memcpy(pN + n, L.ig, (size_t)m * sizeof *pN);
        memcpy(v->ints, L.ig, (size_t)m * sizeof *L.ig); /* for the outputs read at t */
        st->steps++;
        st->accepted++;
        res->r.t = t;
        if (y)
            memcpy(y, pN, (size_t)n * sizeof *y);
        if (o->step && o->step(t, pN, o->step_ctx))
            return fail(res, DYN_STOPPED, t, "stopped");
        if ((N % every == 0 || N == nsteps) && o->output) {
            st->samples++;
            if (o->output(N, t, pN, o->output_ctx)) {
                res->r.status = DYN_STOPPED;
                return DYN_STOPPED;
            }
        }
        if (o->progress && (N & 1023) == 0 &&
            o->progress(t, (double)N / (double)nsteps, o->progress_ctx)) {
            res->r.status = DYN_CANCELLED;
            return DYN_CANCELLED;
        }
    }
    return DYN_OK;
}
