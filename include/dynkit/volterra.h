/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/volterra.h — Volterra integral and integro-differential equations on a fixed grid.
 *
 * A system mixes states of two kinds: differential ones, y_i' = F_i(t, y, I), and integral
 * ones, y_i(t) = F_i(t, y, I), where I = (I_1..I_m) are integrals over the past,
 *
 *     I_k(t) = int_{t0}^{t} (t - s)^(-mu_k) K_k(t - s) g_k(t, s, y(s)) ds,   0 <= mu_k < 1,
 *
 * with K_k = 1 unless the integral is a convolution (XPPAUT's int{K#u}: K a function of the
 * lag, tabulated once on the grid) and g_k the integrand read at the past point s.
 *
 * Method (XPPAUT's "volterra" method, after P. Linz, "Analytical and Numerical Methods for
 * Volterra Equations", SIAM 1985, ch. 7 and 8): on the grid t_j = t0 + j h, each interval
 * [t_j, t_j+1] contributes int (t - s)^(-mu) ds over it, shared half and half by the values
 * of K g at its two ends (for mu = 0 the trapezoidal rule); the differential states take
 * the trapezoidal rule, and the implicit equations of one step are solved by Newton's
 * method with a difference Jacobian. Observed order: 2 for mu = 0, 2 - mu for mu > 0
 * (tests/test_volterra.c).
 *
 * Memory: the solver keeps the last max_points grid points of (y, I) (XPPAUT's MaxPoints,
 * @ vmaxpts, default 4000). Beyond them the integrals cover [t - (max_points - 1) h, t]
 * only, as XPPAUT's do; res.forgot says from which time on that happened. Nothing is
 * allocated: the caller provides dyn_volterra_work_size doubles.
 */
#ifndef DYNKIT_VOLTERRA_H
#define DYNKIT_VOLTERRA_H

#include <stddef.h>

#include "dynkit/ode.h"

#ifdef __cplusplus
extern "C" {
#endif

#define DYN_VOLTERRA_MAX_POINTS_DEFAULT 4000L

/* The integrands g_k at the past point (tp, yp) seen from t, with ip the integrals'
 * values at tp: g[k] for every k. Return 0, or non-zero to stop. */
typedef int (*dyn_volterra_integrand_fn)(double t, double tp, const double *yp,
                                         const double *ip, double *g, void *par);
/* The kernels K_k(lag) of the convolutions: kv[k] for each k with conv[k] (the others are
 * not read). Return 0, or non-zero to stop. */
typedef int (*dyn_volterra_kernel_fn)(double lag, double *kv, void *par);

typedef struct dyn_volterra {
    int n;                        /* states */
    const unsigned char *is_int;  /* n flags: 1 integral state y = F, 0 differential y' = F */
    int n_int;                    /* integrals m (>= 0) */
    const double *mu;             /* m exponents, 0 <= mu < 1 */
    const unsigned char *conv;    /* m flags: a convolution with a kernel of the lag */
    dyn_rhs_fn rhs;               /* F(t, y, out, par), reading the integrals from ints */
    dyn_volterra_integrand_fn integrand;
    dyn_volterra_kernel_fn kernel; /* may be NULL when no conv[k] */
    double *ints;                 /* m values that rhs reads (the solver writes them) */
    void *par;
} dyn_volterra;

typedef struct dyn_volterra_opts {
    long max_points;         /* grid points kept; 0: DYN_VOLTERRA_MAX_POINTS_DEFAULT */
    double tol;              /* Newton: stop when the largest correction is below (1e-10) */
    int max_iter;            /* Newton iterations per step (0: 20) */
    long every;              /* keep every K-th sample (and always the last); 0 or 1 = all */
    dyn_output_fn output;    /* may be NULL */
    void *output_ctx;
    /* called after each step with the new point (t, y), or NULL: a delay history, say */
    int (*step)(double t, const double *y, void *ctx);
    void *step_ctx;
    dyn_progress_fn progress;
    void *progress_ctx;
} dyn_volterra_opts;

typedef struct dyn_volterra_result {
    dyn_result r;
    double forgot; /* first time the integrals no longer reached back to t0, or NaN */
} dyn_volterra_result;

/* A model file's Volterra integrals (dyn_model.volterra): the integrals' values are n_int
 * doubles at byte ints_offset of the parameter struct, which rhs and compute_outputs read
 * and the solver writes (followed by one double the integrand uses for its time t). */
typedef struct dyn_volterra_model {
    int n_int;
    const double *mu;
    const unsigned char *conv;
    const unsigned char *is_int; /* one flag per state */
    size_t ints_offset;
    long max_points;             /* @ vmaxpts; 0: not given */
    dyn_volterra_integrand_fn integrand;
    dyn_volterra_kernel_fn kernel;
} dyn_volterra_model;

size_t dyn_volterra_work_size(int n, int n_int, long max_points);

/* The integral states' values at t0 from y0 (their F with every integral 0), into y0i
 * (n; the differential states copied). Returns 0 or the rhs's status. */
int dyn_volterra_start(const dyn_volterra *v, double t0, const double *y0, double *y0i,
                       double *work);

/* nsteps steps of h from (t0, y0) (y0's integral states replaced as dyn_volterra_start
 * does); samples k = 0..nsteps at t0 + k h through opts->output; y (n) the last state.
 * Returns res->r.status. */
int dyn_volterra_solve(const dyn_volterra *v, double t0, double h, long nsteps,
                       const double *y0, double *y, double *work, const dyn_volterra_opts *opts,
                       dyn_volterra_result *res);

#ifdef __cplusplus
}
#endif

#endif /* DYNKIT_VOLTERRA_H */
