/* SPDX-License-Identifier: BSD-3-Clause */
/* equilibrium.c — an equilibrium f(t, y) = 0 of a model near a guess by Levenberg-
 * Marquardt steps on ||f||_2^2 / 2 (K. Levenberg 1944, D. W. Marquardt 1963; Nocedal &
 * Wright, Numerical Optimization, 2nd ed., sec. 10.3): (J^T J + mu I) d = -J^T f, solved by
 * Cholesky, mu = lambda * max_i (J^T J)_ii, lambda from 0.1 divided by 10 after a step
 * that lowers ||f||_2 (down to 1e-15: Newton's step near a regular solution) and multiplied
 * by 10 until one does, and until the step is no longer than max(||y||_inf, 1), so that the
 * search stays near the guess. The Jacobian is dyn_linearize's, formed again at every
 * accepted point. Converged when ||f||_inf is within the tolerance, or within
 * DYN_EQUILIBRIUM_FLOOR times it when no step lowers ||f|| any more (f has reached its
 * rounding). Where these steps fail (they can follow a valley in which |f| falls towards
 * infinity, as van der Pol's from (2, 0) does, where Newton's first step lands on the
 * origin), Gauss-Newton steps from the guess are tried, taken only when they converge. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "analysis/lm_step.h"
#include "dynkit/analysis.h"

#define LM_LAMBDA_START 0.1 /* a cautious first step: the equilibrium near the guess */
#define LM_LAMBDA_MIN 1e-15
#define LM_LAMBDA_MAX 1e12

size_t dyn_equilibrium_work_size(int n)
{
    const size_t N = (size_t)n;
    return 2 * N * N + 6 * N + dyn_linearize_work_size(n);
}

/* f(t, y) into f; 0, or the rhs status, or -1 when a component is not finite. */
static int eval(const dyn_model *m, double t, const double *y, void *par, double *f, long *calls)
{
    (*calls)++;
    const int rc = m->rhs(t, y, f, par);
    if (rc)
        return rc;
    for (int i = 0; i < m->n_states; i++)
        if (!isfinite(f[i]))
            return -1;
    return 0;
}

/* The tolerance on |f|_inf at y: rtol ||J||_inf max(|y|_inf, 1) (rtol > 0; rtol ||J||_inf
 * is dyn_stability_tol's, at least DBL_MIN) */
static double f_tolerance(int n, const double *J, const double *y, double rtol)
{
    return dyn_stability_tol(n, J, rtol) * fmax(lm_norm_inf(n, y), 1.0);
}

/* At most this many Gauss-Newton steps after Levenberg-Marquardt's failed */
#define GN_ITERATIONS 30

/* Gauss-Newton steps from y (overwritten): (J^T J + 1e-15 max diag I) d = -J^T f, until
 * |f|_inf is within the tolerance (info->tol set as the main loop's). J, H, minus_g, d, lw:
 * the main loop's work. 0 when it converged,
 * f then f(y); non-zero when a step or the Jacobian failed or it did not converge. */
static int gauss_newton(const dyn_model *m, double t, double *y, void *par,
                        const dyn_equilibrium_opts *opts, double rtol, double *J, double *H,
                        double *f, double *minus_g, double *d, double *lw, long *calls,
                        dyn_equilibrium_info *info)
{
    const int n = m->n_states;
    const size_t N = (size_t)n;
    if (eval(m, t, y, par, f, calls))
        return -1;
    for (int it = 0; it <= GN_ITERATIONS; it++) {
        dyn_linearize_info li;
        if (dyn_linearize(m, t, y, par, opts ? &opts->jac : NULL, J, lw, &li))
            return -1;
        *calls += li.rhs_calls;
        const double tol = f_tolerance(n, J, y, rtol);
        if (lm_norm_inf(n, f) <= tol) {
            info->tol = tol;
            return 0;
        }
        if (it == GN_ITERATIONS)
            break;
        info->iterations++;
        const double hmax = lm_normal_equations(n, n, J, f, H, minus_g);
        if (!(hmax > 0.0))
            return -1;
        memcpy(J, H, N * N * sizeof *J);
        memcpy(d, minus_g, N * sizeof *d);
        if (lm_damped_solve(n, J, LM_LAMBDA_MIN, hmax, d))
            return -1;
        for (size_t a = 0; a < N; a++)
            y[a] += d[a];
        if (eval(m, t, y, par, f, calls))
            return -1;
    }
    return -1;
}

int dyn_equilibrium(const dyn_model *m, double t, double *y, void *par,
                    const dyn_equilibrium_opts *opts, double *work, dyn_equilibrium_info *info)
{
    const int n = m->n_states;
    const size_t N = (size_t)n;
    double *J = work, *H = J + N * N, *f = H + N * N, *minus_g = f + N, *d = minus_g + N,
           *yt = d + N, *ft = yt + N, *guess = ft + N, *lw = guess + N;
    const double rtol = opts && opts->tol > 0.0 ? opts->tol : DYN_EQUILIBRIUM_TOL;
    const int max_iter = opts && opts->max_iter > 0 ? opts->max_iter : 100;
    dyn_equilibrium_info local;
    if (!info)
        info = &local;
    memset(info, 0, sizeof *info);
    if (m->delay) {
        snprintf(info->message, sizeof info->message,
                 "%s is a delay equation (delay(x, tau)): equilibria of delay equations are not "
                 "supported", m->name);
        return DYN_ERR_ARG;
    }
    if (m->volterra) {
        snprintf(info->message, sizeof info->message,
                 "%s has Volterra integrals (int{...}, volt): their equilibria are not "
                 "supported", m->name);
        return DYN_ERR_ARG;
    }
    long calls = 0;
    if (eval(m, t, y, par, f, &calls)) {
        snprintf(info->message, sizeof info->message,
                 "the right-hand side of %s fails or is not finite at the guess", m->name);
        info->rhs_calls = calls;
        return DYN_ERR_RHS;
    }
    memcpy(guess, y, N * sizeof *guess);
    double fn = lm_norm_2(n, f), lambda = LM_LAMBDA_START;
    int status = DYN_ERR_MAX_STEPS;
    for (;;) {
        dyn_linearize_info li;
        const int rc = dyn_linearize(m, t, y, par, opts ? &opts->jac : NULL, J, lw, &li);
        calls += li.rhs_calls;
        if (rc) {
            snprintf(info->message, sizeof info->message, "%s", li.message);
            status = rc;
            break;
        }
        info->tol = f_tolerance(n, J, y, rtol);
        if (lm_norm_inf(n, f) <= info->tol) {
            status = 0;
            break;
        }
        if (info->iterations >= max_iter) {
            snprintf(info->message, sizeof info->message,
                     "no equilibrium within %d iterations: |f|_inf = %.3g (tolerance %.3g)",
                     max_iter, lm_norm_inf(n, f), info->tol);
            break;
        }
        info->iterations++;
        /* H = J^T J, minus_g = -J^T f */
        const double hmax = lm_normal_equations(n, n, J, f, H, minus_g);
        if (!(hmax > 0.0)) {
            snprintf(info->message, sizeof info->message,
                     "f does not depend on the state here (J = 0): |f|_inf = %.3g stays",
                     lm_norm_inf(n, f));
            status = DYN_ERR_STEP_SIZE;
            break;
        }
        int accepted = 0;
        while (!accepted && lambda <= LM_LAMBDA_MAX) {
            /* (H + mu I) d = -g: H + mu I factored in J's place (J is formed again at the
             * next point) */
            memcpy(J, H, N * N * sizeof *J);
            memcpy(d, minus_g, N * sizeof *d);
            if (lm_damped_solve(n, J, lambda, hmax, d)) {
                lambda *= 10.0;
                continue;
            }
            /* no step longer than the state's size (at least 1): not a jump to a far
             * equilibrium */
            if (lm_norm_inf(n, d) > fmax(lm_norm_inf(n, y), 1.0)) {
                lambda *= 10.0;
                continue;
            }
            for (size_t a = 0; a < N; a++)
                yt[a] = y[a] + d[a];
            const double ftn = eval(m, t, yt, par, ft, &calls) ? INFINITY : lm_norm_2(n, ft);
            if (ftn < fn) {
                memcpy(y, yt, N * sizeof *y);
                memcpy(f, ft, N * sizeof *f);
                fn = ftn;
                lambda = fmax(lambda / 10.0, LM_LAMBDA_MIN);
                accepted = 1;
            } else {
                lambda *= 10.0;
            }
        }
        if (!accepted && lm_norm_inf(n, f) <= DYN_EQUILIBRIUM_FLOOR * info->tol) {
            status = 0; /* f is at its rounding: no step can lower it */
            break;
        }
        if (!accepted) {
            snprintf(info->message, sizeof info->message,
                     "no step lowers |f| (a minimum of |f| that is not an equilibrium, or "
                     "none near the guess): |f|_inf = %.3g",
                     lm_norm_inf(n, f));
            status = DYN_ERR_STEP_SIZE;
            break;
        }
    }
    if (status && gauss_newton(m, t, guess, par, opts, rtol, J, H, f, minus_g, d, lw, &calls, info) == 0) {
        memcpy(y, guess, N * sizeof *y);
        info->message[0] = '\0';
        status = 0;
    }
    info->residual = lm_norm_inf(n, f);
    info->rhs_calls = calls;
    return status;
}
