/* SPDX-License-Identifier: BSD-3-Clause */
/* rosenbrock.h — linearly implicit Rosenbrock methods for stiff systems: one step attempt
 * (new state, error estimate, dense output), the linearisation it needs, and a simple
 * adaptive loop for tests and reference computations.
 *
 * A method is data in the transformed form of Hairer & Wanner, "Solving ODEs II",
 * sec. IV.7, eq. (7.4') — the form of their code RODAS:
 *
 *   (I/(h gamma) - J) u_i = f(t + alpha_i h, y0 + sum_{j<i} a_ij u_j)
 *                           + sum_{j<i} (c_ij / h) u_j + gam_i h df/dt,   i = 1..s
 *   y1 = y0 + sum_i m_i u_i,      err = sum_i e_i u_i  (y1 minus the embedded solution)
 *
 * with J = df/dy and df/dt taken at (t, y0). One LU factorisation of I/(h gamma) - J serves
 * all stages. Dense output (Hairer's CONTRO form): with theta = (t - t_n)/h,
 *   y(theta) = (1 - theta) y0 + theta (y1 + (1 - theta) (q_1 + theta q_2)),
 *   q_k = sum_j dense[k][j] u_j.
 *
 * Memory: the caller owns the workspace (dyn_ros_work_size doubles and n ints) and every
 * output; nothing allocates and nothing prints. Private to the library.
 *
 * How a driver uses it (the adaptive driver of the explicit pairs works the same way):
 *   dyn_ros_linearize(p, t, h, y, ws, st);            once per accepted step
 *   do { rc = dyn_ros_step(m, p, t, h, y, ws, y1, err, cont, st);   tries with the same
 *        ... norm of err, accept or shrink h ... } while rejected;   linearisation
 */
#ifndef DYN_ODE_ROSENBROCK_H
#define DYN_ODE_ROSENBROCK_H

#include <stddef.h>

#include "dynkit/ode.h"

/* Largest number of stages of a registered Rosenbrock method. */
#define DYN_ROS_MAX_STAGES 6

/* Coefficients of a Rosenbrock method in transformed form (see the top of this file).
 * Matrices are (s x s) row-major and strictly lower triangular. */
typedef struct dyn_ros_method {
    const char *name;        /* canonical name, e.g. "rodas4" */
    const char *title;       /* one line for humans */
    const char *reference;   /* where the coefficients come from */
    int stages;              /* s */
    int order;               /* order p of y1 */
    int order_embedded;      /* order of the embedded solution y1 - err */
    int dense_order;         /* order of the dense output */
    double gamma;            /* diagonal gamma */
    const double *alpha;     /* (s) stage times t + alpha_i h */
    const double *gam;       /* (s) gamma_i, the coefficient of h df/dt in stage i */
    const double *a;         /* (s x s) a_ij */
    const double *c;         /* (s x s) c_ij */
    const double *m;         /* (s) weights of y1 */
    const double *e;         /* (s) weights of the error estimate */
    int dense_rows;          /* number of q_k rows (2 for the CONTRO form) */
    const double *dense;     /* (dense_rows x s) */
} dyn_ros_method;

/* Hairer & Wanner's RODAS, order 4(3), stiffly accurate, L-stable, dense output order 3. */
extern const dyn_ros_method dyn_ros_rodas4;

/* Method by name ("rodas4"), or NULL. */
const dyn_ros_method *dyn_ros_find(const char *name);

/* The stepper of the general driver for registry entries of kind DYN_KIND_ROSENBROCK whose
 * impl points to a dyn_ros_method (step_rosenbrock.c; the interface is ode/stepper.h). */
struct dyn_stepper_ops;
extern const struct dyn_stepper_ops dyn_ros_stepper_ops;

/* What a step needs about the problem. */
typedef struct dyn_ros_problem {
    dyn_system sys;          /* f, n, par */
    dyn_jac_fn jac;          /* analytic df/dy, or NULL for forward differences */
    int autonomous;          /* 1: f does not depend on t; df/dt is taken as zero (saves
                              * one call of f per step) */
    const double *typ;       /* (n) typical magnitudes of the states for the difference
                              * increments, or NULL (see ode/jacobian.h) */
    /* banded Jacobian (banded = 1, with the bandwidths of the workspace): J from jac_band
     * (DYN_BAND_AT storage) or banded differences; W factored by band_solver (NULL: the
     * built-in). jac is then unused. */
    int banded;
    dyn_jac_fn jac_band;
    const dyn_band_solver *band_solver;
    /* sparse Jacobian (with a workspace laid out by dyn_ros_ws_init_sparse): J from
     * jac_sparse (the values of the workspace's pattern), W factored by sparse_solver. */
    dyn_jac_fn jac_sparse;
    const dyn_sparse_solver *sparse_solver;
    /* sparse without jac_sparse: differences with the columns in n_groups groups (group:
     * each column's, dyn_sparse_groups), n_groups calls of f a Jacobian */
    const int *groups;
    int n_groups;
} dyn_ros_problem;

/* Counters, added to by the functions below (zero-initialise). */
typedef struct dyn_ros_stats {
    long steps;              /* step attempts (dyn_ros_step calls that ran all stages) */
    long rhs_calls;          /* every evaluation of f, including those below */
    long jac_evals;          /* Jacobians formed: analytic calls or difference matrices */
    long jac_rhs_calls;      /* evaluations of f for difference Jacobians and df/dt */
    long jac_fd_columns;     /* columns of the analytic Jacobian formed by differences, an
                              * entry not being finite (dyn_jacobian_mend) */
    long lu_decomps;         /* factorisations of I/(h gamma) - J */
    long lin_solves;         /* forward/back substitutions (one per stage) */
} dyn_ros_stats;

/* Status of the functions below. */
typedef enum dyn_ros_status {
    DYN_ROS_OK = 0,
    DYN_ROS_RHS_FAIL = 1,    /* f returned non-zero: its value is in ws->rhs_status */
    DYN_ROS_JAC_FAIL = 2,    /* the analytic Jacobian returned non-zero (ws->rhs_status) */
    DYN_ROS_SINGULAR = 3     /* I/(h gamma) - J is singular: retry with another h */
} dyn_ros_status;

/* The workspace: views into one caller-owned block of doubles and one of ints. */
typedef struct dyn_ros_ws {
    int n, s;
    int banded, lower, upper; /* band matrices: J in DYN_BAND_AT storage (n (lower + upper
                              * + 1)), W in LAPACK's factor storage (n ldab) */
    int ldab;                /* 2 lower + upper + 1 when banded */
    const dyn_sparse_pattern *pattern; /* sparse matrices (or NULL): J and W hold the
                              * pattern's nnz values each */
    double *f0;              /* (n) f(t, y0) */
    double *J;               /* (n x n) df/dy at (t, y0), or its band */
    double *ft;              /* (n) df/dt at (t, y0); zero when autonomous */
    double *W;               /* (n x n) LU factors of I/(h gamma) - J, or (n ldab) band */
    int *piv;                /* (n) pivots of W */
    double *u;               /* (s x n) stage increments u_i */
    double *Y;               /* (n) stage state */
    double *fy;              /* (n) stage derivative, then the stage's right-hand side */
    double *scratch;         /* (2n) difference quotients */
    double h_lu;             /* h of the factorisation in W (0: none) */
    int rhs_status;          /* the non-zero value f or jac returned */
} dyn_ros_ws;

/* Doubles of workspace for method m and n states: 2 n^2 + (s + 6) n. */
size_t dyn_ros_work_size(const dyn_ros_method *m, int n);

/* Lay the workspace out over work (dyn_ros_work_size doubles) and piv (n ints). */
void dyn_ros_ws_init(dyn_ros_ws *ws, const dyn_ros_method *m, int n, double *work, int *piv);

/* The same for band matrices (banded = 1, bandwidths lower and upper, 0 <= both < n):
 * (3 lower + 2 upper + 2) n + (s + 6) n doubles; banded = 0 is the dense layout above. */
size_t dyn_ros_work_size_band(const dyn_ros_method *m, int n, int banded, int lower, int upper);
void dyn_ros_ws_init_band(dyn_ros_ws *ws, const dyn_ros_method *m, int n, int banded,
                          int lower, int upper, double *work, int *piv);

/* The same for sparse matrices with pattern p (every diagonal entry in it; kept by the
 * caller while the workspace is used): 2 nnz + (s + 6) n doubles. */
size_t dyn_ros_work_size_sparse(const dyn_ros_method *m, int n, int nnz);
void dyn_ros_ws_init_sparse(dyn_ros_ws *ws, const dyn_ros_method *m, int n,
                            const dyn_sparse_pattern *p, double *work, int *piv);

/* Evaluate f0 = f(t, y), J = df/dy (analytic or forward differences) and df/dt (forward
 * difference with time scale |h|; zero when autonomous) into ws. Invalidates the
 * factorisation. Returns DYN_ROS_OK, DYN_ROS_RHS_FAIL or DYN_ROS_JAC_FAIL. */
int dyn_ros_linearize(const dyn_ros_problem *p, double t, double h, const double *y,
                      dyn_ros_ws *ws, dyn_ros_stats *st);

/* Attempt one step of size h (either sign) from (t, y) with the linearisation in ws, which
 * must come from dyn_ros_linearize at the same (t, y). Writes y1 (n), err (n, the local
 * error estimate y1 - embedded; may be NULL) and cont ((2 + m->dense_rows) x n dense output
 * coefficients [y0, y1, q_1, ...]; may be NULL). y1 must not alias y. Factorises
 * I/(h gamma) - J unless ws holds it for this h already. Does not judge the error.
 * Returns DYN_ROS_OK, DYN_ROS_RHS_FAIL (a stage's f failed) or DYN_ROS_SINGULAR. */
int dyn_ros_step(const dyn_ros_method *m, const dyn_ros_problem *p, double t, double h,
                 const double *y, dyn_ros_ws *ws, double *y1, double *err, double *cont,
                 dyn_ros_stats *st);

/* The dense output at theta = (t - t_n)/h in [0, 1] from cont of dyn_ros_step: out (n). */
void dyn_ros_dense(const dyn_ros_method *m, int n, const double *cont, double theta,
                   double *out);

/* ---- a simple adaptive loop (tests, reference computations) ----
 * Step-size control of Hairer & Wanner's RODAS: error norm
 * sqrt(mean((err_i / (atol_i + rtol max(|y0_i|, |y1_i|)))^2)), accept when <= 1, new step
 * h * min(6, max(0.2, 0.9 / err^(1/(q+1)))) with q the embedded order, Gustafsson's
 * predictive controller after accepted steps, no growth right after a rejection. */
typedef struct dyn_ros_opts {
    double rtol;             /* relative tolerance (> 0) */
    double atol;             /* absolute tolerance, used when atolv is NULL */
    const double *atolv;     /* (n) absolute tolerances, or NULL */
    double h0;               /* first step (0: |t1 - t0| * 1e-6) */
    double hmax;             /* largest |h| (0: |t1 - t0|) */
    long max_steps;          /* 0: 1000000 */
    /* called after each accepted step with the dense output of [t_old, t_new]; non-zero
     * stops the loop (DYN_STOPPED). May be NULL. */
    int (*on_step)(double t_old, double t_new, const double *y, const double *cont,
                   void *ctx);
    void *ctx;
    double *cont;            /* ((2 + dense_rows) x n) for on_step; NULL when no on_step */
} dyn_ros_opts;

/* Integrate from (t0, y) to t1 (either direction), y (n) in and out; y1buf and errbuf are
 * (n) caller scratch. Returns a dyn_status: DYN_OK, DYN_ERR_RHS (f or jac failed; value in
 * ws->rhs_status), DYN_ERR_NONFINITE, DYN_STOPPED, DYN_ERR_MAX_STEPS, DYN_ERR_STEP_SIZE (step
 * size underflow or a repeatedly singular matrix) or DYN_ERR_ARG (bad options), with a
 * message in msg (msglen bytes; may be NULL). *t_reached (may be NULL) is the time of y on
 * return. (dyn_solve with method "rodas4" is the full driver: output times, events.) */
int dyn_ros_integrate(const dyn_ros_method *m, const dyn_ros_problem *p, double t0, double t1,
                      double *y, const dyn_ros_opts *o, dyn_ros_ws *ws, double *y1buf,
                      double *errbuf, dyn_ros_stats *st, double *t_reached, char *msg,
                      size_t msglen);

#endif /* DYN_ODE_ROSENBROCK_H */
