/* SPDX-License-Identifier: BSD-3-Clause */
/* linearize.c — the Jacobian A = df/dy of a model at one state: the model's analytic
 * Jacobian, central differences (step eps^(1/3) times the column's scale), or central
 * differences extrapolated by Richardson's rule in Ridders' form (Ridders 1982, Adv. Eng.
 * Software 4(2) 75-76; Numerical Recipes, 3rd ed., sec. 5.7): steps h, h/2, h/4, ... (at
 * most 16) from h = 2^-3 times the column's scale, a Neville tableau in h^2 of up to six
 * columns, the extrapolation whose estimated error is least kept, stopped once it is below
 * 1e-7 relative and the extrapolations drift apart again (rounding has taken over). Steps
 * are powers of two and the increments actually taken are used, so no rounding of the
 * step enters the quotient. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dynkit/analysis.h"

#define RIDDERS_LEVELS 16 /* steps h0 ... h0 / 2^15 */
#define RIDDERS_COLS 6    /* the raw differences and 5 extrapolations (error O(h^12)) */
#define RIDDERS_SAFE 2.0
#define RIDDERS_CONVERGED 1e-7 /* relative error below which growing drift stops it */
#define RICHARDSON_ZERO 1e-12  /* relative size of an entry not told apart from 0 */
/* what central() returns for a difference that is not finite (f returned 0) */
#define NOT_FINITE INT_MIN

size_t dyn_linearize_work_size(int n)
{
    /* y, f(y), the column; f+-, two tableau rows of RIDDERS_COLS columns; the row sizes */
    return (size_t)n * (6 + 2 * RIDDERS_COLS);
}

/* The largest power of two not above x (x > 0, finite). */
static double pow2_below(double x)
{
    int e;
    frexp(x, &e);
    return ldexp(1.0, e - 1);
}

/* Central difference of column j with step h into d (n values): (f(y + h e_j) -
 * f(y - h e_j)) / (taken increments). Returns 0, the rhs status, or NOT_FINITE. */
static int central(const dyn_model *m, double t, double *yw, void *par, int j, double h, double *fp,
                   double *fm, double *d, long *calls)
{
    const int n = m->n_states;
    const double yj = yw[j];
    yw[j] = yj + h;
    const double hp = yw[j] - yj;
    int rc = m->rhs(t, yw, fp, par);
    yw[j] = yj - h;
    const double hm = yj - yw[j];
    if (!rc)
        rc = m->rhs(t, yw, fm, par);
    yw[j] = yj;
    *calls += 2;
    if (rc)
        return rc;
    const double inv = 1.0 / (hp + hm);
    for (int i = 0; i < n; i++) {
        d[i] = (fp[i] - fm[i]) * inv;
        if (!isfinite(d[i]))
            return NOT_FINITE;
    }
    return 0;
}

static double max_abs(int n, const double *v)
{
    double r = 0.0;
    for (int i = 0; i < n; i++)
        r = fmax(r, fabs(v[i]));
    return r;
}

static double max_diff(int n, const double *a, const double *b)
{
    double r = 0.0;
    for (int i = 0; i < n; i++)
        r = fmax(r, fabs(a[i] - b[i]));
    return r;
}

/* Ridders' extrapolation of column j into best (n values); *rel gets the estimated error
 * relative to the column's size. Returns 0 or the first failure of f at the first step
 * tried after all shrinking. */
static int ridders(const dyn_model *m, double t, double *yw, void *par, int j, double h0,
                   double fscale, double *work, double *best, double *rel, long *calls)
{
    const int n = m->n_states;
    const size_t N = (size_t)n;
    double *fp = work, *fm = work + N;
    double *prev = work + 2 * N, *cur = prev + RIDDERS_COLS * N;
    double h = h0, err = INFINITY;
    int rc = 0;
    /* a first step where f is defined and finite (shrink by 4 up to 12 times) */
    for (int tries = 0;; tries++) {
        rc = central(m, t, yw, par, j, h, fp, fm, prev, calls);
        if (rc == 0 || tries == 11)
            break;
        h *= 0.25;
    }
    if (rc)
        return rc;
    memcpy(best, prev, N * sizeof *best);
    for (int k = 1; k < RIDDERS_LEVELS; k++) {
        h *= 0.5;
        if (central(m, t, yw, par, j, h, fp, fm, cur, calls))
            break; /* keep the best so far */
        const int top = k < RIDDERS_COLS - 1 ? k : RIDDERS_COLS - 1;
        double fac = 4.0;
        for (int l = 1; l <= top; l++) {
            double *tl = cur + (size_t)l * N;
            const double *tl1 = cur + (size_t)(l - 1) * N, *pl1 = prev + (size_t)(l - 1) * N;
            for (int i = 0; i < n; i++)
                tl[i] = (fac * tl1[i] - pl1[i]) / (fac - 1.0);
            fac *= 4.0;
            const double e = fmax(max_diff(n, tl, tl1), max_diff(n, tl, pl1));
            if (e <= err) {
                err = e;
                memcpy(best, tl, N * sizeof *best);
            }
        }
        const int ptop = k - 1 < RIDDERS_COLS - 1 ? k - 1 : RIDDERS_COLS - 1;
        const double drift = max_diff(n, cur + (size_t)top * N, prev + (size_t)ptop * N);
        double *swap = prev;
        prev = cur;
        cur = swap;
        /* converged, and the extrapolations drift apart again: rounding has taken over */
        if (drift >= RIDDERS_SAFE * err &&
            err <= RIDDERS_CONVERGED * fmax(max_abs(n, best), fscale))
            break;
    }
    const double size = fmax(max_abs(n, best), fscale);
    *rel = size > 0.0 ? err / size : err;
    return 0;
}

/* Entries of an extrapolated difference Jacobian below RICHARDSON_ZERO times the larger of
 * the largest entries of their row and column are not told apart from zero (the measured
 * error is 6e-14 of that size): they are set to 0. So the column of a state that f does not
 * depend on through terms that cancel (sin^2 + cos^2) comes out exactly zero, and so do its
 * eigenvalues, instead of rounding noise that a Jordan block would raise to its square
 * root. rowmax: n doubles of workspace. */
static void flush_noise(int n, double *A, double *rowmax)
{
    const size_t N = (size_t)n;
    for (size_t i = 0; i < N; i++)
        rowmax[i] = max_abs(n, A + i * N);
    for (size_t j = 0; j < N; j++) {
        double colmax = 0.0;
        for (size_t i = 0; i < N; i++)
            colmax = fmax(colmax, fabs(A[i * N + j]));
        for (size_t i = 0; i < N; i++)
            if (fabs(A[i * N + j]) <= RICHARDSON_ZERO * fmax(rowmax[i], colmax))
                A[i * N + j] = 0.0;
    }
}

static int jac_differences(const dyn_model *m, double t, const double *y, void *par,
                           const dyn_linearize_opts *o, int richardson, double *A, double *work,
                           dyn_linearize_info *info)
{
    const int n = m->n_states;
    const size_t N = (size_t)n;
    double *yw = work, *f0 = work + N, *col = work + 2 * N, *rest = work + 3 * N;
    memcpy(yw, y, N * sizeof *yw);
    long calls = 0;
    int rc = m->rhs(t, y, f0, par);
    calls++;
    const double fnorm = max_abs(n, f0);
    double worst = 0.0;
    for (int j = 0; j < n && rc == 0; j++) {
        const double typ = o && o->typ ? o->typ[j] : 1.0;
        if (!(typ > 0.0) || !isfinite(typ)) {
            snprintf(info->message, sizeof info->message,
                     "the typical magnitude of state %s must be a finite number > 0 (got %g)",
                     m->states[j].name, typ);
            return DYN_ERR_ARG;
        }
        const double scale = fmax(fabs(y[j]), typ);
        if (richardson) {
            double rel = 0.0;
            rc = ridders(m, t, yw, par, j, pow2_below(0.125 * scale), fnorm / scale, rest, col,
                         &rel, &calls);
            worst = fmax(worst, rel);
        } else {
            rc = central(m, t, yw, par, j, pow2_below(cbrt(DBL_EPSILON) * scale), rest, rest + N,
                         col, &calls);
        }
        if (rc == NOT_FINITE) {
            snprintf(info->message, sizeof info->message,
                     "the differences in %s are not finite at every step tried", m->states[j].name);
            return DYN_ERR_NONFINITE;
        }
        for (int i = 0; i < n; i++)
            A[(size_t)i * N + (size_t)j] = col[i];
    }
    info->rhs_calls = calls;
    info->err_est = richardson ? worst : 0.0;
    if (richardson && rc == 0)
        flush_noise(n, A, rest);
    if (rc) {
        snprintf(info->message, sizeof info->message,
                 "the right-hand side of %s failed (status %d)", m->name, rc);
        return DYN_ERR_RHS;
    }
    return 0;
}

int dyn_linearize(const dyn_model *m, double t, const double *y, void *par,
                  const dyn_linearize_opts *opts, double *A, double *work, dyn_linearize_info *info)
{
    dyn_jac_scheme s = opts ? opts->scheme : DYN_JAC_AUTO;
    dyn_linearize_info local;
    if (!info)
        info = &local;
    memset(info, 0, sizeof *info);
    if (m->delay) {
        snprintf(info->message, sizeof info->message,
                 "%s is a delay equation (delay(x, tau)): its linearization is not a matrix "
                 "A (the delayed states enter with their lags), not supported",
                 m->name);
        return DYN_ERR_ARG;
    }
    if (m->volterra) {
        snprintf(info->message, sizeof info->message,
                 "%s has Volterra integrals (int{...}, volt): its right-hand side reads the "
                 "whole past, so it has no Jacobian matrix A; not supported",
                 m->name);
        return DYN_ERR_ARG;
    }
    if (s == DYN_JAC_AUTO)
        s = m->jacobian ? DYN_JAC_ANALYTIC : DYN_JAC_RICHARDSON;
    info->scheme = s;
    const int n = m->n_states;
    int rc;
    if (s == DYN_JAC_ANALYTIC) {
        if (!m->jacobian) {
            snprintf(info->message, sizeof info->message,
                     "%s has no analytic Jacobian (use differences)", m->name);
            return DYN_ERR_ARG;
        }
        rc = m->jacobian(t, y, A, par);
        if (rc) {
            snprintf(info->message, sizeof info->message, "the Jacobian of %s failed (status %d)",
                     m->name, rc);
            return DYN_ERR_RHS;
        }
    } else if (s == DYN_JAC_CENTRAL || s == DYN_JAC_RICHARDSON) {
        rc = jac_differences(m, t, y, par, opts, s == DYN_JAC_RICHARDSON, A, work, info);
        if (rc)
            return rc;
    } else {
        snprintf(info->message, sizeof info->message,
                 "unknown Jacobian scheme %d (accepted: 0 to 3)", (int)s);
        return DYN_ERR_ARG;
    }
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            if (!isfinite(A[(size_t)i * (size_t)n + (size_t)j])) {
                snprintf(info->message, sizeof info->message, "d %s / d %s is not finite",
                         m->states[i].name, m->states[j].name);
                return DYN_ERR_NONFINITE;
            }
    return 0;
}
