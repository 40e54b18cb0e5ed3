/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/analysis.h — analysis of a model about a state: equilibria f(t, y) = 0, the
 * Jacobian A = df/dy (the model's own analytic one, or central differences with Richardson
 * extrapolation), its reduction to a subspace of admissible directions (A_min = P^+ A P),
 * and its eigenvalues, sorted and classified (asymptotically stable, unstable, marginal).
 * Over the public model API only
 * (dynkit/model.h); C11 + libm. Eigenvalues of a nonsymmetric matrix come from a solver
 * given by the caller (dyn_eig_solver): the optional backend dynkit_lapack provides LAPACK's
 * dgeev (dynkit/lapack.h); the core has none. docs/analysis.md states the accuracy. */
#ifndef DYNKIT_ANALYSIS_H
#define DYNKIT_ANALYSIS_H

#include <stddef.h>

#include "dynkit/model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* How the Jacobian is formed. */
typedef enum dyn_jac_scheme {
    DYN_JAC_AUTO = 0,      /* the model's analytic Jacobian when it has one, else RICHARDSON */
    DYN_JAC_ANALYTIC = 1,  /* the model's dyn_model.jacobian (an error when it has none) */
    DYN_JAC_CENTRAL = 2,   /* central differences, step eps^(1/3) * scale: 2n calls of f */
    DYN_JAC_RICHARDSON = 3 /* central differences at h, h/2, h/4, ... from h = 2^-3 *
                            * scale, extrapolated in Ridders' form until converged:
                            * 4 to 32 calls of f per column */
} dyn_jac_scheme;

typedef struct dyn_linearize_opts {
    dyn_jac_scheme scheme;
    /* Typical magnitude of each state (n values, > 0), or NULL for 1: the difference step of
     * column j is proportional to max(|y_j|, typ_j). */
    const double *typ;
} dyn_linearize_opts;

/* What dyn_linearize did. */
typedef struct dyn_linearize_info {
    dyn_jac_scheme scheme; /* the scheme used (never AUTO) */
    long rhs_calls;        /* evaluations of f */
    /* RICHARDSON: the largest over the columns of the estimated error (the difference of
     * the kept extrapolation from its neighbours in the tableau, max norm) relative to
     * max(|column|, |f|/scale); 0 for the others. */
    double err_est;
    char message[256]; /* why it failed, when it did */
} dyn_linearize_info;

/* Doubles of workspace dyn_linearize needs for n states. */
size_t dyn_linearize_work_size(int n);

/* A = df/dy of model m at (t, y) with the prepared parameter struct par (n x n, row-major,
 * A[i*n + j] = d f_i / d y_j). opts may be NULL (AUTO). work: dyn_linearize_work_size(n)
 * doubles. Returns 0; DYN_ERR_ARG (no analytic Jacobian, bad typ); DYN_ERR_RHS when f or
 * the Jacobian returns non-zero; DYN_ERR_NONFINITE when an entry is not finite (message
 * names the entry). info may be NULL. */
int dyn_linearize(const dyn_model *m, double t, const double *y, void *par,
                  const dyn_linearize_opts *opts, double *A, double *work,
                  dyn_linearize_info *info);

/* ---- equilibria ---- */

/* The default tolerance of dyn_equilibrium: converged when ||f||_inf <= tol * max(||A||_inf
 * max(||y||_inf, 1), DBL_MIN), or when no step lowers ||f|| and it is within
 * DYN_EQUILIBRIUM_FLOOR times that (f has reached its rounding, which can lie above tol
 * where f has large terms that cancel). */
#define DYN_EQUILIBRIUM_TOL 1e-14
#define DYN_EQUILIBRIUM_FLOOR 1e4

typedef struct dyn_equilibrium_opts {
    dyn_linearize_opts jac; /* how the Jacobian of each iteration is formed */
    double tol;             /* relative; 0: DYN_EQUILIBRIUM_TOL */
    int max_iter;           /* 0: 100 Jacobians */
} dyn_equilibrium_opts;

typedef struct dyn_equilibrium_info {
    int iterations;    /* Jacobians formed */
    double residual;   /* ||f(t, y)||_inf at the returned y */
    double tol;        /* the absolute tolerance the residual was held to */
    long rhs_calls;    /* evaluations of f, the Jacobians' included */
    char message[256]; /* why it failed, when it did */
} dyn_equilibrium_info;

/* Doubles of workspace dyn_equilibrium needs for n states. */
size_t dyn_equilibrium_work_size(int n);

/* An equilibrium f(t, y) = 0 of model m near the guess y (n values, overwritten by the
 * solution; the last iterate on failure) with the prepared parameters par: Levenberg-
 * Marquardt steps (J^T J + mu I) d = -J^T f with the Jacobian of dyn_linearize, mu = 0.1
 * times the largest diagonal entry of J^T J at first, divided by 10 after a step that
 * lowers ||f||_2 and multiplied by 10 until one does and the step is no longer than
 * max(||y||_inf, 1): Newton's method near a regular solution, a search that stays near the
 * guess, and a state that f does not depend on (an ignorable coordinate) left where it is.
 * opts may be
 * NULL. Returns 0 when converged; DYN_ERR_MAX_STEPS (max_iter reached), DYN_ERR_STEP_SIZE
 * (no step lowers ||f||: a minimum of ||f|| that is not a zero, or none near), with the
 * residual in the message; DYN_ERR_RHS, DYN_ERR_NONFINITE or DYN_ERR_ARG from f or the
 * Jacobian. info may be NULL. */
int dyn_equilibrium(const dyn_model *m, double t, double *y, void *par,
                    const dyn_equilibrium_opts *opts, double *work, dyn_equilibrium_info *info);

/* A reduced to the k admissible directions that are the columns of P (n x k, row-major,
 * full column rank): A_min = P^+ A P with P^+ = (P^T P)^-1 P^T (k x k into Amin). For a
 * constrained model whose motions stay in span(P) (coordinates and speeds of a minimal set,
 * dependent ones eliminated), Amin carries the eigenvalues of those motions. work: n k +
 * k k + k doubles. Returns 0, or DYN_ERR_ARG when P^T P is not positive definite (P's columns
 * are dependent). */
int dyn_linear_reduce(int n, int k, const double *A, const double *P, double *Amin, double *work);

/* An eigenvalue solver for a real nonsymmetric matrix: the eigenvalues of the n x n matrix
 * a (row-major; overwritten) into re, im (n values; a complex pair as consecutive entries,
 * positive imaginary part first). Returns 0, or non-zero with a message in err. */
typedef struct dyn_eig_solver {
    const char *name;
    int (*eigenvalues)(int n, double *a, double *re, double *im, char *err, size_t errlen);
} dyn_eig_solver;

/* Sort n eigenvalues by imaginary part, then real part (ascending), in place; the
 * imaginary parts of a pair are exact negatives, so each pair sits symmetrically. */
void dyn_eig_sort(int n, double *re, double *im);

/* Stability of a linearization from its eigenvalues. */
typedef enum dyn_stability {
    DYN_STABLE = 0,   /* asymptotically stable: every re < -tol */
    DYN_MARGINAL = 1, /* no re > tol, some |re| <= tol */
    DYN_UNSTABLE = 2  /* some re > tol */
} dyn_stability;

/* The default tolerance of dyn_classify relative to the matrix norm. */
#define DYN_STABILITY_RTOL 1e-8

/* The classification with tol (absolute: a real part within [-tol, tol] counts as zero). */
dyn_stability dyn_classify(int n, const double *re, double tol);
/* The tolerance dyn_classify is given by dynkit: rtol * ||A||_inf (max row sum of |a_ij|),
 * at least DBL_MIN; rtol 0 means DYN_STABILITY_RTOL. */
double dyn_stability_tol(int n, const double *A, double rtol);
/* "asymptotically stable", "marginal", "unstable". */
const char *dyn_stability_name(dyn_stability s);

/* For an eigenvalue re + i im with im != 0: the undamped natural frequency |lambda| (rad/s)
 * into *wn and the damping ratio -re/|lambda| into *zeta. */
void dyn_eig_mode(double re, double im, double *wn, double *zeta);

/* Constraints of a mechanism given as a model's outputs (dyn_mech_constraints_to_c,
 * dynkit/mbs.h): the states are n coordinates q then their n speeds u; an output with the
 * unit "holonomic" or "speeds" is a constraint's value on the speeds h = D(q, t) u + h_t,
 * and one with the unit "position" or "prescribed" the value f(q, t) of a holonomic
 * constraint, in the order of the holonomic ones among the first. dyn_project_constraints
 * moves y onto them by minimal-norm corrections (docs/mechanisms.md, "Initial values"):
 * Gauss-Newton on the coordinates, q <- q - G' (G G')^-1 f with G = df/dq
 * (dyn_holonomic_gradient; with declared speeds dh/du = G W, not G), until f stops
 * decreasing; then the speeds, u <- u - D' (D D')^-1 h (linear: one step and one to
 * clean up rounding). D comes from central differences of h in u (exact but for rounding, h
 * being linear in u). Returns 0 with y projected, DYN_ERR_ARG when the rows are dependent
 * (*bad the first dependent constraint's index among the h outputs) or when the coordinates
 * do not reach the constraints, the largest |f| left above dyn_constraint_tolerance of the
 * coordinates (*bad -1, y left at the coordinates with the smallest |f| found, that |f| in
 * residual[0]), with a message in err. The largest |f| and |h| left go to residual[0],
 * residual[1] (may be NULL). */
int dyn_project_constraints(const dyn_model *cm, const void *par, double t, double *y,
                            double residual[2], int *bad, char *err, size_t errlen);

/* The largest |value| of a constraint that holds at the n coordinates (or speeds) v:
 * 1e-9 max(1, |v_j|), the scale capped at 1e6 (so 1e-3 at most: a coordinate of 1e16 rad
 * does not make any value pass). */
double dyn_constraint_tolerance(const double *v, int n);

/* The constraints' values at (t, y) as dyn_project_constraints reads them: h (the outputs
 * "holonomic" and "speeds", m of them) and f (one per holonomic constraint, in h's order;
 * f[r] is 0 for a constraint on the speeds), m returned (or -1 when the outputs fail).
 * h and f hold cm->n_outputs values each. */
int dyn_constraint_values(const dyn_model *cm, const void *par, double t, const double *y,
                          double *h, double *f, int *holonomic);

/* The gradient of the holonomic constraints with respect to the coordinates at (t, y):
 * G (m x n, row-major, n = cm->n_states / 2) with G[r][k] = df_r/dq_k for each holonomic
 * constraint r (rows in dyn_constraint_values' order; zero for a constraint on the
 * speeds), by central differences of f: steps a power of two near 6e-6 of each
 * coordinate's scale max(1, |q_k|), divided by the increments actually taken (an error of
 * about 1e-11). When Dh is not NULL it also gets dh_r/dy_j (m x 2n) for every constraint
 * and every state by the same steps (no truncation error in the speeds, where h is
 * linear). G and Dh hold cm->n_outputs rows. Returns m, or -1 when the outputs fail. Used
 * by dyn_project_constraints and dynkit linearize's admissible directions. */
int dyn_holonomic_gradient(const dyn_model *cm, const void *par, double t, const double *y,
                           double *G, double *Dh);

/* The values of k parameters (indices params into m->params) that make k outputs (indices
 * outs) zero at (t, y): the inputs that give the forces of prescribed motions (dynkit
 * inverse --inputs). Newton's method from the parameters' values in par, the Jacobian by
 * forward differences of steps max(1, |p|) (exact but for rounding when the outputs are
 * affine in the parameters), until the outputs stop decreasing; the model's prepare is
 * called after each change. The solution is left in par and the largest |output| left in
 * *residual. Returns 0, or DYN_ERR_ARG with a message in err: the outputs are not finite,
 * or the parameters do not move them independently (*bad the column found dependent). */
int dyn_zero_outputs(const dyn_model *m, void *par, double t, const double *y, int k,
                     const int *params, const int *outs, double *residual, int *bad,
                     char *err, size_t errlen);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_ANALYSIS_H */
