/* SPDX-License-Identifier: BSD-3-Clause */
/* step_rosenbrock.c — the Rosenbrock stepper of the general driver (stepper.h): RODAS
 * (rosenbrock.h; Hairer & Wanner, "Solving ODEs II", sec. IV.7) under dyn_solve's step-size
 * control, dense output and events.
 * - A new point (retry = 0) is linearised once: f, J (the model's analytic Jacobian, else
 *   forward differences; with a declared band, band matrices throughout: the analytic band,
 *   else differences in lower + upper + 1 groups of columns, and a band LU; with a sparse
 *   pattern, the analytic sparse Jacobian and a sparse LU, dyn_sparse_solver) and df/dt
 *   (forward difference, backward near the end of the span
 *   so f is never evaluated past t1). A rejected step retries from the same point with the
 *   same J and df/dt and only refactorises I/(h gamma) - J (as RODAS does).
 * - Error norm: Hairer's, of the estimate y1 - y1_embedded (the last stage u6 for RODAS).
 *   A singular iteration matrix counts as an infinite error: the driver shrinks the step.
 * - Difference increments use the tolerances for the typical size of each state,
 *   typ_i = min(1, atol_i / rtol_i), the size below which the absolute tolerance governs.
 * - Dense output: RODAS's CONTRO interpolant, which is already in the nested form of
 *   dyn_dense_eval (dense.c): y = y0 + theta (y1 - y0 + (1 - theta) (q1 + theta q2)),
 *   coefficients (y0, y1 - y0, q1, q2), degree 3.
 * No trace of stages (the teaching trace is for explicit tables), no stiffness test.
 *
 * Workspace (doubles): the Rosenbrock block (dyn_ros_work_size), then the error estimate
 * (n), the increments' typical sizes (n) and one slot for the step size of the current
 * factorisation; ints: the n pivots.
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "ode/rosenbrock.h"
#include "ode/stepper.h"

static const dyn_ros_method *method_of(const dyn_tableau *m)
{
    return (const dyn_ros_method *)m->impl;
}

static size_t ros_work_size(const dyn_tableau *m, int n, const dyn_jac_shape *shape)
{
    const dyn_jac_shape dense = {0, 0, 0, NULL};
    const dyn_jac_shape *sh = shape ? shape : &dense;
    if (sh->sparse) {
        const size_t ros = dyn_ros_work_size_sparse(method_of(m), n, sh->sparse->nnz);
        return ros ? ros + 2 * (size_t)n + 1 : 0;
    }
    const size_t ros = dyn_ros_work_size_band(method_of(m), n, sh->banded, sh->lower, sh->upper);
    return ros ? ros + 2 * (size_t)n + 1 : 0;
}

static size_t ros_iwork_size(const dyn_tableau *m, int n)
{
    (void)m;
    return (size_t)n;
}

static int ros_dense_degree(const dyn_tableau *m)
{
    (void)m;
    return 3;
}

/* The views of the workspace, rebuilt at each call (the stepper keeps no other state). */
typedef struct ros_view {
    const dyn_ros_method *rm;
    dyn_ros_ws ws;
    double *err, *typ, *h_lu;
} ros_view;

static void view(dyn_stepper *st, ros_view *v)
{
    const int n = st->n;
    v->rm = method_of(st->m);
    const dyn_jac_shape *sh = &st->shape;
    double *rest;
    if (sh->sparse) {
        dyn_ros_ws_init_sparse(&v->ws, v->rm, n, sh->sparse, st->work, st->iwork);
        rest = st->work + dyn_ros_work_size_sparse(v->rm, n, sh->sparse->nnz);
    } else {
        dyn_ros_ws_init_band(&v->ws, v->rm, n, sh->banded, sh->lower, sh->upper, st->work,
                             st->iwork);
        rest = st->work + dyn_ros_work_size_band(v->rm, n, sh->banded, sh->lower, sh->upper);
    }
    v->err = rest;
    v->typ = rest + n;
    v->h_lu = rest + 2 * (size_t)n;
}

static int ros_start(dyn_stepper *st, double t0, const double *y0)
{
    (void)t0;
    (void)y0;
    ros_view v;
    view(st, &v);
    for (int i = 0; i < st->n; i++) {
        const double r = st->tol.rtolv ? st->tol.rtolv[i] : st->tol.rtol;
        const double a = st->tol.atolv ? st->tol.atolv[i] : st->tol.atol;
        v.typ[i] = r > 0.0 ? fmin(1.0, a / r) : 1.0;
    }
    *v.h_lu = 0.0;
    return 0;
}

static int ros_deriv(dyn_stepper *st, double t, const double *y, const double **f)
{
    ros_view v;
    view(st, &v);
    st->rhs_calls++;
    int rc = st->f(t, y, v.ws.f0, st->par);
    if (rc) {
        st->fail_t = t;
        return rc;
    }
    *f = v.ws.f0;
    return 0;
}

static int ros_attempt(dyn_stepper *st, double t, double h, const double *y, double *ynew,
                       double *err, int retry)
{
    ros_view v;
    view(st, &v);
    const int n = st->n;
    dyn_ros_problem p = {{st->f, n, st->par}, st->jac, 0, v.typ, st->shape.banded,
                         st->jac_band, st->band_solver, st->jac_sparse, st->sparse_solver,
                         st->jac_groups, st->jac_n_groups};
    dyn_ros_stats rs = {0};
    int rc = DYN_ROS_OK;
    v.ws.h_lu = retry ? *v.h_lu : 0.0;
    if (!retry) {
        /* df/dt forward unless t + increment would pass the end of the span */
        const double d = sqrt(DBL_EPSILON) * fmax(fabs(t), fabs(h));
        rc = dyn_ros_linearize(&p, t, t + d > st->tend ? -h : h, y, &v.ws, &rs);
    }
    if (rc == DYN_ROS_OK)
        rc = dyn_ros_step(v.rm, &p, t, h, y, &v.ws, ynew, v.err, NULL, &rs);
    st->rhs_calls += rs.rhs_calls;
    st->jac_calls += rs.jac_evals;
    st->jac_fd_columns += rs.jac_fd_columns;
    *v.h_lu = v.ws.h_lu;
    if (rc == DYN_ROS_SINGULAR) {
        *err = INFINITY;
        return 0;
    }
    if (rc) {
        st->fail_t = t;
        return v.ws.rhs_status ? v.ws.rhs_status : -1;
    }
    *err = dyn_err_norm(&st->tol, n, y, ynew, v.err);
    return 0;
}

static int ros_dense(dyn_stepper *st, double t, double h, const double *y, const double *ynew,
                     double *coef)
{
    (void)t;
    (void)h;
    ros_view v;
    view(st, &v);
    const int n = st->n, s = v.rm->stages;
    const size_t N = (size_t)n;
    const double *d1 = v.rm->dense, *d2 = v.rm->dense + s;
    for (int k = 0; k < n; k++) {
        double q1 = 0.0, q2 = 0.0;
        for (int i = 0; i < s; i++) {
            const double u = v.ws.u[(size_t)i * N + (size_t)k];
            q1 += d1[i] * u;
            q2 += d2[i] * u;
        }
        coef[k] = y[k];
        coef[N + (size_t)k] = ynew[k] - y[k];
        coef[2 * N + (size_t)k] = q1;
        coef[3 * N + (size_t)k] = q2;
    }
    return 0;
}

static void ros_accept(dyn_stepper *st, double t, double h, const double *ynew)
{
    (void)st;
    (void)t;
    (void)h;
    (void)ynew;
}

const dyn_stepper_ops dyn_ros_stepper_ops = {
    .work_size = ros_work_size,
    .iwork_size = ros_iwork_size,
    .dense_degree = ros_dense_degree,
    .start = ros_start,
    .deriv = ros_deriv,
    .attempt = ros_attempt,
    .stiffness = NULL,
    .dense = ros_dense,
    .accept = ros_accept,
};
