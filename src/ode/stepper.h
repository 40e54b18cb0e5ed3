/* SPDX-License-Identifier: BSD-3-Clause */
/* stepper.h — one-step methods as the general driver (solve.c) sees them (private).
 *
 * The driver owns time, step-size control, output, dense-output recording and events; a
 * stepper owns the arithmetic of one kind of method: it attempts a step and judges its
 * error, and after acceptance gives the dense output of the step. Explicit Runge–Kutta
 * tables, fixed-step and embedded pairs, are step_erk.c. Another kind (e.g. a Rosenbrock
 * method, HNW II sec. IV.7) plugs in by
 *   1. adding its kind to dyn_method_kind (ode.h) and a registry entry whose `impl` points
 *      to its own coefficients (order, error_order and dense_degree filled in the entry);
 *   2. writing a dyn_stepper_ops (below) and returning it from dyn_stepper_ops_for
 *      (step_erk.c) for that kind; its private state goes into the union of dyn_stepper;
 *   3. dyn_method_is_adaptive / dyn_method_is_stiff (tableaus.c) say what it is.
 * Contract of the operations, in the order the driver calls them:
 *   start      once, at (t0, y0): lay out the workspace; no evaluation required.
 *   deriv      f(t, y) at the current point (the driver's initial step choice needs it).
 *   attempt    step of size h from (t, y) to ynew; *err = the scaled error norm
 *              (dyn_err_norm; <= 1 accepts; 0 for methods without an estimate; NaN/Inf
 *              when the trial is not finite). retry = 1 when the last attempt from the same
 *              (t, y) was rejected (a Jacobian or factorisation may be reused then).
 *   stiffness  (may be NULL) |h lambda| estimate of the accepted step, or < 0 if none.
 *   dense      (only when the driver needs it) the dense output of the accepted step as
 *              ((degree + 1) x n) coefficients c_j of Hairer's nested form (dyn_dense):
 *              y = c0 + theta (c1 + (1-theta) (c2 + theta (c3 + ...))), c0 = y,
 *              c1 = ynew - y. RODAS's y = (1-theta) y0 + theta (y1 + (1-theta) (q1 +
 *              theta q2)) is c0 = y0, c1 = y1 - y0, c2 = q1, c3 = q2 (not powers of theta).
 *   accept     the accepted step's end becomes the current point (e.g. FSAL reuse).
 * Operations return 0, or the non-zero value f (or the Jacobian) returned, with
 * st->fail_t set. Counts go to st->rhs_calls and st->jac_calls. Nothing allocates.
 */
#ifndef DYN_ODE_STEPPER_H
#define DYN_ODE_STEPPER_H

#include <math.h>
#include <stddef.h>

#include "dynkit/ode.h"
#include "ode/rk_stages.h"

/* Tolerances: per state when rtolv/atolv are set, else the scalars. */
typedef struct dyn_tol {
    double rtol, atol;
    const double *rtolv, *atolv;
} dyn_tol;

/* The scale of state i: atol_i + rtol_i max(|y|, |ynew|) (HNW I eq. II.4.10). */
static inline double dyn_tol_scale(const dyn_tol *tol, int i, double y, double ynew)
{
    const double r = tol->rtolv ? tol->rtolv[i] : tol->rtol;
    const double a = tol->atolv ? tol->atolv[i] : tol->atol;
    return a + r * fmax(fabs(y), fabs(ynew));
}

/* Hairer's error norm sqrt(1/n sum (err_i / scale_i)^2) of an error vector err (n). */
double dyn_err_norm(const dyn_tol *tol, int n, const double *y, const double *ynew,
                    const double *err);

typedef struct dyn_stepper dyn_stepper;

/* The shape of the Jacobian of stiff kinds: dense, banded with the given bandwidths
 * (dyn_solve_opts.jac_banded) or sparse (dyn_solve_opts.jac_sparse). */
typedef struct dyn_jac_shape {
    int banded, lower, upper;
    const dyn_sparse_pattern *sparse; /* sparse matrices with this pattern, or NULL */
} dyn_jac_shape;

typedef struct dyn_stepper_ops {
    size_t (*work_size)(const dyn_tableau *m, int n, const dyn_jac_shape *shape); /* doubles */
    size_t (*iwork_size)(const dyn_tableau *m, int n); /* ints */
    int (*dense_degree)(const dyn_tableau *m);
    int (*start)(dyn_stepper *st, double t0, const double *y0);
    int (*deriv)(dyn_stepper *st, double t, const double *y, const double **f);
    int (*attempt)(dyn_stepper *st, double t, double h, const double *y, double *ynew,
                   double *err, int retry);
    double (*stiffness)(dyn_stepper *st, double t, double h, const double *y,
                        const double *ynew);
    int (*dense)(dyn_stepper *st, double t, double h, const double *y, const double *ynew,
                 double *coef);
    void (*accept)(dyn_stepper *st, double t, double h, const double *ynew);
    /* 1: attempt gives the square of the error norm (the explicit pairs: no square root
     * between a step's error and the next step size; dyn_sinl_ctl_init's `squared`) */
    int err_squared;
} dyn_stepper_ops;

/* Explicit Runge–Kutta state (step_erk.c). */
typedef struct dyn_erk_state {
    dyn_rk_plan plan;
    int planned;       /* 0: more stages than a plan holds (dyn_rk_stages_scan) */
    double *k;         /* (kslots x n): stage derivatives; slot s is f(t + h, ynew) */
    double *Y;         /* (n) stage state */
    double *tmp;       /* (n) */
    int kslots;
    int k0_valid;      /* k[0] holds f at the current point */
    int fnew_valid;    /* f(t + h, ynew) of the last accepted step is at hand */
    int ne, ne3;       /* non-zero error weights */
    /* the error sums' terms, set up once per solve: weight ec[q] multiplies the stage
     * derivative at ekp[q] (e3: DOP853's 3rd-order estimate) */
    double ec[DYN_RK_PLAN_MAX_STAGES], e3c[DYN_RK_PLAN_MAX_STAGES];
    const double *ekp[DYN_RK_PLAN_MAX_STAGES], *e3kp[DYN_RK_PLAN_MAX_STAGES];
} dyn_erk_state;

struct dyn_stepper {
    const dyn_stepper_ops *ops;
    const dyn_tableau *m;
    dyn_rhs_fn f;
    void *par;
    int n;
    dyn_jac_fn jac;     /* stiff kinds: analytic Jacobian or NULL */
    dyn_jac_shape shape;           /* stiff kinds: dense or banded */
    dyn_jac_fn jac_band;           /* banded: analytic band or NULL */
    const dyn_band_solver *band_solver; /* banded: NULL for the built-in */
    dyn_jac_fn jac_sparse;         /* sparse: the values of the pattern */
    const dyn_sparse_solver *sparse_solver;
    const int *jac_groups;         /* sparse without jac_sparse: differences in groups */
    int jac_n_groups;
    double tend;        /* stage times are clamped to it (dyn_rk_stage_time) */
    dyn_tol tol;
    double *work;       /* ops->work_size doubles */
    int *iwork;         /* ops->iwork_size ints */
    long rhs_calls, jac_calls;
    long jac_fd_columns; /* exact Jacobians' columns formed by differences */
    double fail_t;      /* time of the failing evaluation */
    dyn_trace_fn trace; /* stages of the first trace_steps attempts */
    void *trace_ctx;
    long trace_steps;
    long attempts;
    union {
        dyn_erk_state erk;
        /* other kinds: their state here */
    } u;
};

/* The operations for method m's kind, or NULL when no stepper runs it. */
const dyn_stepper_ops *dyn_stepper_ops_for(const dyn_tableau *m);

#endif /* DYN_ODE_STEPPER_H */
