/* SPDX-License-Identifier: BSD-3-Clause */
/* lyapunov.c — Benettin's method for the Lyapunov exponents (Benettin, Galgani, Giorgilli,
 * Strelcyn, Meccanica 15 (1980) 9-30; A. Wolf et al., Physica D 16 (1985) 285, sec. 3):
 * a flow's trajectory and k tangent vectors Q, Q' = J(t, y) Q, integrated together by an
 * adaptive Runge-Kutta pair over intervals of length tau, Q orthonormalized after each
 * (qr_gram_schmidt.c) and the logarithms of R's diagonal summed; a map's tangent vectors
 * multiplied by dF/dy at every iteration. After a transient the sums over the averaging
 * time give the exponents; the same sums over equal blocks of that time give block means
 * whose spread (standard deviation over sqrt(blocks)) estimates the error. J Q: the
 * model's exact Jacobian, or central differences along each column q of Q, (f(y + h q) -
 * f(y - h q)) / 2h with h = eps^(1/3) max(||y||, 1) / ||q||. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/lyapunov.h"

typedef struct tangent_sys {
    const dyn_model *m;
    void *par;
    int n, k, exact;
    double *J, *yw, *fp, *fm; /* scratch: n x n, then n each */
} tangent_sys;

/* dQ = J(t, y) Q (n x k) by the exact Jacobian or differences along Q's columns; f is
 * f(t, y) (used by nothing but kept for symmetry of the map's step). */
static int tangent(tangent_sys *s, double t, const double *y, const double *Q, double *dQ)
{
    const int n = s->n, k = s->k;
    const size_t N = (size_t)n, K = (size_t)k;
    if (s->exact) {
        const int rc = s->m->jacobian(t, y, s->J, s->par);
        if (rc)
            return rc;
        for (size_t i = 0; i < N; i++)
            for (size_t j = 0; j < K; j++) {
                double d = 0.0;
                for (size_t l = 0; l < N; l++)
                    d += s->J[i * N + l] * Q[l * K + j];
                dQ[i * K + j] = d;
            }
        return 0;
    }
    double ynorm = 0.0;
    for (size_t i = 0; i < N; i++)
        ynorm += y[i] * y[i];
    ynorm = sqrt(ynorm);
    for (size_t j = 0; j < K; j++) {
        double qn = 0.0;
        for (size_t i = 0; i < N; i++)
            qn += Q[i * K + j] * Q[i * K + j];
        qn = sqrt(qn);
        if (!(qn > 0.0)) {
            for (size_t i = 0; i < N; i++)
                dQ[i * K + j] = 0.0;
            continue;
        }
        const double h = cbrt(DBL_EPSILON) * fmax(ynorm, 1.0) / qn;
        for (size_t i = 0; i < N; i++)
            s->yw[i] = y[i] + h * Q[i * K + j];
        int rc = s->m->rhs(t, s->yw, s->fp, s->par);
        for (size_t i = 0; i < N && !rc; i++)
            s->yw[i] = y[i] - h * Q[i * K + j];
        if (!rc)
            rc = s->m->rhs(t, s->yw, s->fm, s->par);
        if (rc)
            return rc;
        for (size_t i = 0; i < N; i++)
            dQ[i * K + j] = (s->fp[i] - s->fm[i]) / (2.0 * h);
    }
    return 0;
}

/* The flow of the trajectory and its tangent vectors: Y = (y, Q). */
static int extended_rhs(double t, const double *Y, double *dY, void *ctx)
{
    tangent_sys *s = ctx;
    const int rc = s->m->rhs(t, Y, dY, s->par);
    return rc ? rc : tangent(s, t, Y, Y + s->n, dY + s->n);
}

/* The trajectory alone (the transient). */
static int trajectory_rhs(double t, const double *y, double *dy, void *ctx)
{
    tangent_sys *s = ctx;
    return s->m->rhs(t, y, dy, s->par);
}

static int refuse(const dyn_model *m, const dyn_lyapunov_opts *o, int k, dyn_lyapunov_info *info)
{
    const char *why = m->delay      ? "a delay equation (delay(x, tau))"
                      : m->volterra ? "Volterra integrals (int{...}, volt)"
                      : m->jump     ? "Markov states (markov lines)"
                                    : NULL;
    if (why) {
        snprintf(info->message, sizeof info->message,
                 "%s has %s: its Lyapunov exponents are not supported", m->name, why);
        return DYN_ERR_ARG;
    }
    if (k < 1 || k > m->n_states) {
        snprintf(info->message, sizeof info->message,
                 "exponents wanted: %d; give 1 to %d (the states)", k, m->n_states);
        return DYN_ERR_ARG;
    }
    if (!(o->t_avg > 0.0) || !isfinite(o->t_avg) || !(o->t_trans >= 0.0) || !isfinite(o->t_trans) ||
        (!o->map && !(o->tau > 0.0 && isfinite(o->tau)))) {
        snprintf(info->message, sizeof info->message,
                 "the averaging time must be > 0, the transient >= 0 and the interval > 0 "
                 "(got %.17g, %.17g, %.17g)",
                 o->t_avg, o->t_trans, o->tau);
        return DYN_ERR_ARG;
    }
    if (o->scheme == DYN_JAC_ANALYTIC && !m->jacobian) {
        snprintf(info->message, sizeof info->message,
                 "%s has no analytic Jacobian (use differences)", m->name);
        return DYN_ERR_ARG;
    }
    return 0;
}

/* exponents and err from the sums: total over M steps of length dt, blocks of it */
static void finish(int k, int blocks, long M, double dt, const double *total, const double *bsum,
                   const long *blen, double *exponents, double *err)
{
    for (int j = 0; j < k; j++) {
        exponents[j] = total[j] / ((double)M * dt);
        double mean = 0.0, var = 0.0;
        for (int b = 0; b < blocks; b++)
            mean += bsum[(size_t)b * (size_t)k + (size_t)j] / ((double)blen[b] * dt);
        mean /= blocks;
        for (int b = 0; b < blocks; b++) {
            const double d =
                bsum[(size_t)b * (size_t)k + (size_t)j] / ((double)blen[b] * dt) - mean;
            var += d * d;
        }
        if (err)
            err[j] = sqrt(var / (blocks - 1)) / sqrt((double)blocks);
    }
    /* largest first (Gram-Schmidt's order is that in the limit; a short run may differ) */
    for (int a = 1; a < k; a++)
        for (int b = a; b > 0 && exponents[b] > exponents[b - 1]; b--) {
            const double x = exponents[b];
            exponents[b] = exponents[b - 1];
            exponents[b - 1] = x;
            if (err) {
                const double e = err[b];
                err[b] = err[b - 1];
                err[b - 1] = e;
            }
        }
}

/* Advance a map one iteration: y <- F(t, y), Q <- dF/dy(y) Q; t advanced by the caller. */
static int map_step(tangent_sys *s, double t, double *y, double *Q, double *ynew, double *Qnew,
                    int with_q)
{
    int rc = s->m->rhs(t, y, ynew, s->par);
    if (!rc && with_q)
        rc = tangent(s, t, y, Q, Qnew);
    if (rc)
        return rc;
    const size_t N = (size_t)s->n;
    memcpy(y, ynew, N * sizeof *y);
    if (with_q)
        memcpy(Q, Qnew, N * (size_t)s->k * sizeof *Q);
    for (size_t i = 0; i < N; i++)
        if (!isfinite(y[i]))
            return DYN_ERR_NONFINITE;
    return 0;
}

int dyn_lyapunov(const dyn_model *m, void *par, double t0, const double *y0,
                 const dyn_lyapunov_opts *o, double *exponents, double *err,
                 dyn_lyapunov_info *info)
{
    dyn_lyapunov_info local;
    if (!info)
        info = &local;
    memset(info, 0, sizeof *info);
    const int k = o->k > 0 ? o->k : 1, n = m->n_states;
    int rc = refuse(m, o, k, info);
    if (rc)
        return rc;
    const int blocks = o->blocks >= 2 ? o->blocks : DYN_LYAPUNOV_BLOCKS;
    const size_t N = (size_t)n, K = (size_t)k, NE = N + N * K;
    const dyn_tableau *method = o->method ? o->method : dyn_method_find("dop853");
    dyn_solve_opts so;
    memset(&so, 0, sizeof so);
    so.rtol = o->rtol > 0.0 ? o->rtol : 1e-10;
    so.atol = o->atol > 0.0 ? o->atol : 1e-10;
    const size_t sw = o->map ? 0 : dyn_solve_work_size(method, (int)NE, &so);
    tangent_sys s = {m,    par,  n,    k,   m->jacobian && o->scheme <= DYN_JAC_ANALYTIC,
                     NULL, NULL, NULL, NULL};
    info->exact_jacobian = s.exact;
    double *mem = malloc((N * N + 3 * N + 3 * NE + 3 * K + (size_t)blocks * K + sw) * sizeof *mem);
    long *blen = calloc((size_t)blocks, sizeof *blen);
    if (!mem || !blen || (!o->map && (!method || dyn_method_is_map(method)))) {
        free(mem);
        free(blen);
        snprintf(info->message, sizeof info->message,
                 mem && blen ? "no adaptive method" : "out of memory");
        return mem && blen ? DYN_ERR_ARG : DYN_ERR_CAPACITY;
    }
    s.J = mem;
    s.yw = s.J + N * N;
    s.fp = s.yw + N;
    s.fm = s.fp + N;
    double *Y = s.fm + N, *Ynew = Y + NE, *Qtmp = Ynew + NE, *logr = Qtmp + NE, *total = logr + K,
           *spare = total + K, *bsum = spare + K, *work = bsum + (size_t)blocks * K;
    memcpy(Y, y0, N * sizeof *Y);
    memset(total, 0, K * sizeof *total);
    memset(bsum, 0, (size_t)blocks * K * sizeof *bsum);
    double *Q = Y + N;
    const double dt = o->map ? (o->tau > 0.0 ? o->tau : 1.0) : 0.0;
    /* the transient */
    double t = t0;
    if (o->map) {
        const long trans = lround(o->t_trans);
        for (long i = 0; i < trans && !rc; i++) {
            rc = map_step(&s, t, Y, Q, Ynew, Qtmp, 0);
            t = t0 + (double)(i + 1) * dt;
        }
    } else if (o->t_trans > 0.0) {
        const dyn_system sys = {trajectory_rhs, n, &s};
        dyn_result res;
        rc = dyn_solve(method, &sys, t0, t0 + o->t_trans, Y, Y, work, &so, &res);
        info->rhs_calls += res.stats.rhs_calls;
        if (rc)
            snprintf(info->message, sizeof info->message, "the transient: %.200s", res.message);
        t = t0 + o->t_trans;
    }
    /* the tangent vectors: the first k unit vectors */
    memset(Q, 0, N * K * sizeof *Q);
    for (size_t j = 0; j < K; j++)
        Q[j * K + j] = 1.0;
    const double ts = t;
    const long M = o->map ? lround(o->t_avg) : (long)ceil(o->t_avg / o->tau - 1e-9);
    const double step = o->map ? dt : o->t_avg / (double)(M > 0 ? M : 1);
    if (M < blocks && !rc) {
        snprintf(info->message, sizeof info->message,
                 "%ld %s for %d blocks: give a longer averaging time", M,
                 o->map ? "iterations" : "intervals", blocks);
        rc = DYN_ERR_ARG;
    }
    const dyn_system ext = {extended_rhs, (int)NE, &s};
    for (long i = 0; i < M && !rc; i++) {
        const double t_next = ts + (double)(i + 1) * step;
        if (o->map) {
            rc = map_step(&s, t, Y, Q, Ynew, Qtmp, 1);
            if (rc)
                snprintf(info->message, sizeof info->message,
                         "the map fails or leaves the finite numbers at iteration %ld", i + 1);
        } else {
            dyn_result res;
            rc = dyn_solve(method, &ext, t, t_next, Y, Y, work, &so, &res);
            info->rhs_calls += res.stats.rhs_calls;
            if (rc)
                snprintf(info->message, sizeof info->message, "at t = %.17g: %.200s", t,
                         res.message);
        }
        t = t_next;
        if (rc)
            break;
        if (dyn_qr_log_diag(n, k, Q, logr)) {
            snprintf(info->message, sizeof info->message,
                     "the tangent vectors collapsed or overflowed at t = %.17g (a shorter "
                     "interval between orthonormalizations helps)",
                     t);
            rc = DYN_ERR_NONFINITE;
            break;
        }
        info->orthonormalizations++;
        const long b = i * blocks / M;
        blen[b]++;
        for (size_t j = 0; j < K; j++) {
            total[j] += logr[j];
            bsum[(size_t)b * K + j] += logr[j];
        }
    }
    info->t_end = t;
    if (!rc)
        finish(k, blocks, M, step, total, bsum, blen, exponents, err);
    free(mem);
    free(blen);
    return rc;
}
