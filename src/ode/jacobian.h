/* SPDX-License-Identifier: BSD-3-Clause */
/* jacobian.h — finite-difference Jacobian df/dy and time derivative df/dt of a system, for
 * the stiff methods when the model gives no analytic Jacobian.
 *
 * Forward differences, one column per right-hand-side call, with the increment of
 * SUNDIALS CVODE's dense difference-quotient Jacobian and of Hairer & Wanner's codes:
 * d_j = sqrt(eps) * max(|y_j|, typ_j), then rounded so that (y_j + d_j) - y_j == d_j exactly
 * (Dennis & Schnabel, "Numerical Methods for Unconstrained Optimization", sec. 5.4).
 * The error of a column is O(d_j |f''|) + O(eps |f| / d_j), about sqrt(eps) relative when
 * y_j and typ_j are of the size of the solution.
 *
 * Private to the library; nothing allocates (caller-owned work) and nothing prints.
 */
#ifndef DYN_ODE_JACOBIAN_H
#define DYN_ODE_JACOBIAN_H

#include "dynkit/ode.h"

/* Typical magnitude of a state component when the caller gives none (typ == NULL): the
 * increment of a component near zero is sqrt(eps) * DYN_FD_TYPICAL. One suits the states of
 * mechanical models (angles, metres, their rates) that start at rest: a smaller floor makes
 * the increment of a zero state so small that rounding in f (eps |f| / d) spoils the
 * column. States that live far below one (concentrations, Robertson's y2 ~ 1e-5) need
 * their own typ; an adaptive driver passes typ_j = atol_j / rtol, the size below which the
 * absolute tolerance governs, as SUNDIALS scales its increments by the error weights. */
#define DYN_FD_TYPICAL 1.0

/* Doubles of work dyn_fd_jacobian needs for n states. */
#define DYN_FD_JAC_WORK(n) (2 * (size_t)(n))

/* J (n x n, row-major, J[i*n + j] = d f_i / d y_j) at (t, y) by forward differences.
 * f0 (n) must hold f(t, y). typ (n) gives typical magnitudes of the states (> 0), or NULL
 * for DYN_FD_TYPICAL. work has DYN_FD_JAC_WORK(n) doubles; y is not modified.
 * Returns 0, or the non-zero value of f (J is then incomplete). Adds the calls of f (n on
 * success) to *rhs_calls when it is not NULL. */
int dyn_fd_jacobian(const dyn_system *sys, double t, const double *y, const double *f0,
                    const double *typ, double *J, double *work, long *rhs_calls);

/* The same for a Jacobian with `lower` and `upper` bandwidths, into J in DYN_BAND_AT
 * storage (n (lower + upper + 1) doubles; the entries outside the matrix are left alone),
 * with the columns in groups: lower + upper + 1 calls of f instead of n
 * (jacobian_band.c). work as above. */
/* The Jacobian in the storage of pattern p (J: p->nnz values) by forward differences with
 * the columns of each of the n_groups groups (group: dyn_sparse_groups) perturbed together:
 * n_groups calls of f. work: 2n doubles. Returns 0 or the non-zero value f returned. */
int dyn_fd_jacobian_sparse(const dyn_system *sys, double t, const double *y, const double *f0,
                           const double *typ, const dyn_sparse_pattern *p, const int *group,
                           int n_groups, double *J, double *work, long *rhs_calls);
int dyn_fd_jacobian_band(const dyn_system *sys, double t, const double *y, const double *f0,
                         const double *typ, int lower, int upper, double *J, double *work,
                         long *rhs_calls);

/* df/dt (n) at (t, y) by a one-sided difference with increment sqrt(eps) * max(|t|, |tscale|);
 * |tscale| is a time scale of the problem (the step size is a good one), and its sign the
 * side: tscale < 0 differences backward (f is then never evaluated after t, e.g. at the end
 * of the span). f0 (n) must hold f(t, y); work has n doubles. Returns 0 or the non-zero
 * value of f; adds 1 to *rhs_calls. */
int dyn_fd_dfdt(const dyn_system *sys, double t, const double *y, const double *f0,
                double tscale, double *ft, double *work, long *rhs_calls);

#endif /* DYN_ODE_JACOBIAN_H */
