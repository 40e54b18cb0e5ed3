/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/ode.h — the ODE core: systems, Butcher tables, the fixed-step driver.
 * (The adaptive driver, dense output and events: dynkit/solve.h.)
 *
 * A system is dy/dt = f(t, y; par) with the GSL/SUNDIALS calling convention: f writes
 * dydt and returns 0, or returns non-zero to stop the solve (the value is reported back).
 * Every explicit Runge–Kutta method is one Butcher table (dyn_tableau) driven by one stage
 * loop (Hairer, Nørsett & Wanner, "Solving ODEs I", sec. II.1). The fixed-step driver
 * follows the homework's [tout,yout] = Integrate_X(odefun, tspan, Ts, y0, par): samples at
 * t0 + k*Ts, the first one being y0.
 *
 * Memory: the library never allocates inside a solve. The caller owns the system, the
 * workspace (dyn_fixed_work_size doubles) and the outputs. Nothing here prints or exits.
 */
#ifndef DYNKIT_ODE_H
#define DYNKIT_ODE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Right-hand side: write f(t, y) into dydt (n values); return 0, or non-zero to stop. */
typedef int (*dyn_rhs_fn)(double t, const double *y, double *dydt, void *par);

/* Jacobian df/dy at (t, y) into J (n x n, row-major: J[i*n + j] = d f_i / d y_j);
 * return 0, or non-zero to stop. Used by the stiff methods. */
typedef int (*dyn_jac_fn)(double t, const double *y, double *J, void *par);

/* A banded Jacobian: d f_i / d y_j = 0 unless i - lower <= j <= i + upper (a 1-D grid with
 * interleaved unknowns, a chain of bodies). A banded Jacobian function (dyn_jac_fn in the
 * jacobian_band fields) writes only the band, in LAPACK's band storage (column-major, as
 * for dgbmv): J[j*(lower + upper + 1) + upper + i - j] = d f_i / d y_j, written with
 * DYN_BAND_AT below; entries outside the matrix (i < 0 or i >= n) are ignored. */
#define DYN_BAND_AT(J, lower, upper, i, j)                                                   \
    ((J)[(size_t)(j) * (size_t)((lower) + (upper) + 1) + (size_t)((upper) + (i) - (j))])

/* A linear solver for banded matrices in LAPACK's factor storage (dgbtrf): A(i, j) at
 * ab[j*ldab + lower + upper + i - j], ldab = 2 lower + upper + 1 (the first `lower` rows of
 * each column take the fill-in). factor: LU with partial pivoting in place, pivots into piv
 * (n, meaning private to the solver); 0, or > 0 when a pivot is exactly zero. solve:
 * b (n) := A^-1 b from the factors. The library's own is dyn_band_solver_builtin (ode/
 * linalg.c); the optional backend dynkit_lapack gives LAPACK's dgbtrf/dgbtrs. */
typedef struct dyn_band_solver {
    const char *name;
    int (*factor)(int n, int lower, int upper, double *ab, int ldab, int *piv);
    void (*solve)(int n, int lower, int upper, const double *ab, int ldab, const int *piv,
                  double *b);
} dyn_band_solver;
extern const dyn_band_solver dyn_band_solver_builtin;

/* A sparse Jacobian in compressed sparse columns (CSC, as KLU and SUNDIALS' SUNSparseMatrix
 * keep it): the entries of column j are in rows rowind[colptr[j] .. colptr[j + 1] - 1],
 * increasing, nnz = colptr[n] in all; a sparse Jacobian function (dyn_jac_fn in the
 * jacobian_sparse fields) writes the nnz values in that order. A pattern that the stiff
 * methods use holds every diagonal entry (zero or not), so I/(h gamma) - J has the same
 * pattern as J. */
typedef struct dyn_sparse_pattern {
    int n, nnz;
    const int *colptr;       /* (n + 1), colptr[0] = 0 */
    const int *rowind;       /* (nnz) */
} dyn_sparse_pattern;

/* 0 when p is a valid pattern of an n x n matrix (colptr non-decreasing from 0 to nnz, rows
 * increasing within a column and in [0, n)) that holds every diagonal entry; else 1 with the
 * reason in err. */
int dyn_sparse_pattern_check(const dyn_sparse_pattern *p, int n, char *err, size_t errlen);
/* The bandwidths of a pattern: the largest i - j (lower) and j - i (upper) of its entries
 * (0 for a diagonal pattern). */
void dyn_sparse_pattern_band(const dyn_sparse_pattern *p, int *lower, int *upper);
/* Groups of the columns of p for a difference Jacobian (Curtis, Powell & Reid 1974): two
 * columns that share a row are in different groups, so the columns of a group are perturbed
 * in one call of f. group (n) receives each column's group, 0 .. groups - 1, assigned
 * greedily in the columns' order (the smallest group none of the earlier columns sharing a
 * row has). Returns the number of groups (3 for a tridiagonal pattern, at most the largest
 * number of entries in a row times the largest in a column), or -1 when memory runs out. */
int dyn_sparse_groups(const dyn_sparse_pattern *p, int *group);

/* A sparse linear solver (a general sparse LU, e.g. SuiteSparse's KLU in the optional
 * backend dynkit_klu). Unlike the band solvers it keeps state (the ordering, the symbolic
 * analysis and the factors, which it allocates itself) in ctx. factor: factor the n x n
 * matrix with pattern p and values ax (p->nnz, in the pattern's order); every call of one
 * solve passes the same pattern, so the analysis of the first call can be kept. Returns 0,
 * > 0 when the matrix is singular (to working precision), < 0 when the solver failed
 * otherwise (out of memory). solve: b (n) := A^-1 b from the last factors. forget (may be
 * NULL): drop the numeric factors and keep the analysis of the pattern, so that the next
 * factor chooses its pivots anew; dyn_solve calls it when it starts, so a solve's numbers
 * do not depend on the solves before it with the same solver (a sweep's runs on one thread
 * share one solver and its analysis, dynkit/sweep.h). */
typedef struct dyn_sparse_solver {
    const char *name;
    void *ctx;
    int (*factor)(void *ctx, const dyn_sparse_pattern *p, const double *ax);
    void (*solve)(void *ctx, int n, double *b);
    void (*forget)(void *ctx);
} dyn_sparse_solver;

/* An event: a sign change of g(t, y; par), located on the solution (dyn_solve).
 * An event happens where g changes sign: from < 0 to > 0 (rising) or > 0 to < 0 (falling),
 * passing through or jumping over zero. A zero at the start time and a touch of zero
 * without a change of sign are not events. */
/* dyn_event.direction of an event that the flow never fires: only a reset at another
 * event's instant that takes g onto or across zero, either way (a cascade, solve.h), as
 * XPPAUT's `global 0` ("the condition vanishes identically"). */
#define DYN_EVENT_JUMPS 2

typedef struct dyn_event {
    const char *name;        /* e.g. "turn" */
    const char *description; /* one line for humans */
    double (*g)(double t, const double *y, void *par);
    int direction;           /* +1 rising only, -1 falling only, 0 both, DYN_EVENT_JUMPS */
    int terminal;            /* 1: stop the solve at the first occurrence (default for it) */
    /* Optional state reset (XPPAUT's `global` with assignments, a bouncing ball's impact):
     * NULL for none. At each occurrence of a non-terminal event the solver calls reset with
     * the state at the event, which it may change in place, and restarts the integration
     * from (t, y) as from a new initial value. Return 0, or non-zero to stop the solve
     * (DYN_ERR_RHS with that value). */
    int (*reset)(double t, double *y, void *par);
} dyn_event;

/* A system of n first-order ODEs; par is handed to f unchanged (the caller owns it). */
typedef struct dyn_system {
    dyn_rhs_fn f;
    int n;
    void *par;
} dyn_system;

/* A pattern of df/dy found by evaluating f: at `points` points near y (y_j plus a uniform
 * offset of up to 0.1 max(|y_j|, 1), Philox4x32-10 numbers of seed, point and j), each state
 * perturbed in turn, an entry is in the pattern where its difference is not zero at one of
 * them; every diagonal entry is. points (n + 1) calls of f. The pattern is allocated (give it
 * back with dyn_sparse_pattern_free). An entry that is zero at every point probed (a
 * coupling through a factor that vanishes there, a branch not taken) is missed, and the
 * Jacobian formed on the pattern is then wrong without a message: a declared or exact
 * pattern is safer (docs/stiff.md, "Sparse Jacobians"). 0, or -1 with a message (f failed,
 * out of memory). */
int dyn_sparse_probe(const dyn_system *sys, double t, const double *y, int points,
                     uint64_t seed, dyn_sparse_pattern *out, char *err, size_t errlen);
void dyn_sparse_pattern_free(dyn_sparse_pattern *p);

/* Status of a solve. 0 is success; the others say why a solve stopped. */
typedef enum dyn_status {
    DYN_OK = 0,
    DYN_ERR_ARG = 1,       /* bad argument (message says which and what is accepted) */
    DYN_ERR_RHS = 2,       /* the right-hand side returned non-zero (see rhs_status) */
    DYN_ERR_NONFINITE = 3, /* a state became NaN or Inf (see fail_t, fail_index) */
    DYN_STOPPED = 4,       /* the output callback asked to stop */
    DYN_ERR_IO = 5,        /* an output could not be written */
    DYN_CANCELLED = 6,     /* the progress callback cancelled the solve */
    DYN_ERR_STEP_SIZE = 7, /* adaptive: the step size fell below 16 eps |t| (see fail_t) */
    DYN_ERR_MAX_STEPS = 8, /* adaptive: the limit on the number of steps was reached */
    DYN_ERR_CAPACITY = 9,  /* a dense-output recorder was full and could not grow */
    DYN_ERR_ZENO = 10      /* events' resets accumulate: more than DYN_ZENO_RESETS of them
                            * without time advancing (solve.h) */
} dyn_status;

/* Short English name of a status ("ok", "bad argument", ...); never NULL. */
const char *dyn_status_name(int status);

/* Kinds of method, so every solver (fixed step, adaptive pairs, implicit) shares one
 * registry. dyn_fixed_solve runs DYN_KIND_EXPLICIT_RK and DYN_KIND_MAP; dyn_solve (solve.h)
 * runs all but DYN_KIND_MAP. */
typedef enum dyn_method_kind {
    DYN_KIND_EXPLICIT_RK = 0, /* fixed-step explicit Runge–Kutta: a, b, c */
    DYN_KIND_EMBEDDED_RK = 1, /* adaptive explicit Runge–Kutta pair: a, b, c and e */
    DYN_KIND_ROSENBROCK = 2,  /* linearly implicit Rosenbrock method for stiff problems:
                               * coefficients in impl (src/ode/rosenbrock.h), c = stage
                               * times, a and b NULL */
    DYN_KIND_MAP = 3          /* a discrete map (difference equation), not an integrator:
                               * y_{k+1} = f(t_k, y_k), t_{k+1} = t_k + h (XPPAUT's
                               * meth=discrete); the right-hand side returns the next state */
} dyn_method_kind;

/* Butcher table of an explicit Runge–Kutta method with s stages.
 * a is (s x s) row-major, strictly lower triangular; b and c have s entries.
 * The members after c describe adaptive pairs and dense output; fixed-step tables leave
 * them zero (designated initializers). */
typedef struct dyn_tableau {
    const char *name;        /* canonical name, e.g. "rk4" */
    const char *alias;       /* other accepted name or NULL, e.g. "modified-euler" */
    const char *title;       /* one line for humans */
    const char *reference;   /* where the coefficients come from */
    dyn_method_kind kind;
    int stages;              /* s */
    int order;               /* classical order p */
    const double *a;         /* (s x s) */
    const double *b;         /* (s) */
    const double *c;         /* (s) */
    /* ---- embedded pair (DYN_KIND_EMBEDDED_RK) ---- */
    const double *e;         /* (s) error weights b - bhat: local error estimate h sum e_i k_i */
    const double *e3;        /* (s) or NULL: a second, lower-order estimate h sum e3_i k_i;
                              * then the error norm is DOP853's |E5|^2 / sqrt(|E5|^2 +
                              * 0.01 |E3|^2) (HNW I sec. II.10) */
    int embedded_order;      /* order of the embedded solution b - e */
    int error_order;         /* q: the error estimate behaves like h^(q+1), so the step-size
                              * controller uses the exponent 1/(q+1) */
    int fsal;                /* 1: first same as last: the last stage is f(t + h, y_{n+1})
                              * (its row of a equals b, c = 1) and is the next step's first */
    /* ---- dense output, in the nested form of dyn_dense (solve.h): the cubic Hermite
     * interpolant of the step's ends (c0..c3) plus the corrections
     * c_j = h sum_i D[j-4][i] k_i, j = 4..dense_degree, over dense_stages stages. For a
     * table without FSAL whose dense output needs more than s stages, stage s is
     * f(t + h, y_{n+1}) and the rows of dense_a give the stages after it. */
    int dense_degree;        /* q; 0 or 3: the cubic Hermite interpolant */
    int dense_stages;        /* length of the rows of D */
    const double *dense;     /* ((dense_degree - 3) x dense_stages) D, or NULL */
    const double *dense_a;   /* ((dense_stages - s - 1) x dense_stages) or NULL */
    const double *dense_c;   /* (dense_stages - s - 1) or NULL */
    /* ---- stiffness detection (DOPRI5, HNW I sec. IV.2): |h lambda| estimated from stage
     * stiff_stage (c = 1) and f(t + h, y_{n+1}); the problem looks stiff when it stays
     * above stiff_bound, the real stability boundary. stiff_bound 0: no detection. */
    int stiff_stage;
    double stiff_bound;
    /* ---- other kinds of method: their own data (e.g. a Rosenbrock table), or NULL ---- */
    const void *impl;
    /* ---- step-size control: the pair's safety factor when dyn_solve_opts.safety is 0;
     * 0 here means 0.9 (DOPRI5's and DOP853's). ---- */
    double safety;
} dyn_tableau;

/* Number of registered methods; dyn_method_at(i) for 0 <= i < count, NULL otherwise. */
int dyn_method_count(void);
const dyn_tableau *dyn_method_at(int i);
/* Method by canonical name or alias (case-sensitive); NULL if unknown. */
const dyn_tableau *dyn_method_find(const char *name);
/* Comma-separated list of all accepted method names into buf (for messages); returns buf. */
char *dyn_method_names(char *buf, size_t size);

/* 1 if the method adapts its step (embedded pairs and later kinds), 0 for fixed-step tables
 * and discrete maps. */
int dyn_method_is_adaptive(const dyn_tableau *m);
/* 1 if the method is meant for stiff problems (implicit kinds), else 0. */
int dyn_method_is_stiff(const dyn_tableau *m);
/* 1 for a discrete map (DYN_KIND_MAP: "discrete"), which iterates f instead of integrating
 * it: run with dyn_fixed_solve, without events. */
int dyn_method_is_map(const dyn_tableau *m);
/* Right-hand-side calls per accepted step without rejections: s, or s - 1 for FSAL
 * tables. Rosenbrock methods: the calls of a step from a new point with an analytic
 * Jacobian, i.e. f(t, y), each stage that needs its own evaluation and one for df/dt
 * (rodas4: 7); the Jacobian comes on top (dyn_method_jac_per_step; by differences it
 * costs n more calls of f), and a rejected step's retry costs only its stages (5). */
int dyn_method_calls_per_step(const dyn_tableau *m);
/* Jacobian evaluations per accepted step without rejections: 1 for stiff methods (once
 * per new point), 0 for explicit ones. */
int dyn_method_jac_per_step(const dyn_tableau *m);

/* Largest error in the order conditions of a table up to order p: for every rooted tree t
 * with |t| <= min(p, 8) (200 trees), |b . Phi(t) - 1/gamma(t)| (Butcher; HNW I sec. II.2),
 * and the row sums c_i = sum_j a_ij. Returns max |residual|; 0 for an exact table.
 * Tables of more than 16 stages are checked to a lower order (6 for 64 stages). */
double dyn_tableau_order_residual(const dyn_tableau *tab, int p);
/* The same for other weights w (s) with the table's a and c, e.g. an embedded solution
 * b - e. */
double dyn_tableau_weights_residual(const dyn_tableau *tab, const double *w, int p);

/* What to do when (t1 - t0) / h is not a whole number of steps (within 1e-10 relative, and
 * never more than 1e-3 steps). */
typedef enum dyn_end_policy {
    DYN_END_EXACT = 0, /* default: a last, shorter step lands exactly on t1 */
    DYN_END_GRID = 1   /* MATLAB's t0:h:t1: stop at the last t0 + k*h <= t1 */
} dyn_end_policy;

/* The sample grid of a fixed-step run. */
typedef struct dyn_grid {
    double t0, t1, h;
    long whole_steps;   /* number of full steps of size h */
    int partial;        /* 1 if a last step of size t1 - (t0 + whole_steps*h) follows */
    long samples;       /* whole_steps + partial + 1 */
    int ends_at_t1;     /* 1 if the last sample is t1 (whole span, or partial step) */
} dyn_grid;

/* Plan the grid for [t0, t1] with step h > 0 (t1 > t0). Returns DYN_OK or DYN_ERR_ARG with
 * a message in err (may be NULL). Sample k is t0 + k*h; with a partial step the last is t1.
 * A span shorter than one step, however much shorter, is one shorter step to t1
 * (DYN_END_EXACT) or no step (DYN_END_GRID, as MATLAB's 0:2:1 is 0). */
int dyn_grid_plan(double t0, double t1, double h, dyn_end_policy end, dyn_grid *grid,
                  char *err, size_t errlen);
/* DYN_OK when the grid takes at most max_steps steps (or max_steps <= 0: no limit), else
 * DYN_ERR_MAX_STEPS with a message in err naming the steps and the limit: a fixed-step run
 * over the limit is refused before its first step. */
int dyn_grid_check_steps(const dyn_grid *grid, long max_steps, char *err, size_t errlen);
/* Time of sample k (0 <= k < samples): t0 + k*h, computed, never accumulated; the last
 * sample is t1 itself when ends_at_t1. */
double dyn_grid_time(const dyn_grid *grid, long k);

/* Counters of a solve, filled by the drivers. */
typedef struct dyn_stats {
    long steps;      /* steps taken (adaptive: attempted, accepted + rejected) */
    long rhs_calls;  /* evaluations of f */
    long samples;    /* samples handed to the output */
    long accepted;   /* accepted steps (for fixed steps: every step) */
    long rejected;   /* adaptive: rejected steps */
    long jac_calls;  /* evaluations of the Jacobian (stiff methods) */
    long jac_fd_columns; /* columns of exact Jacobians formed by differences instead, an
                          * entry not being finite (dyn_jacobian_mend) */
} dyn_stats;

/* Called with every kept sample (k = sample index); return non-zero to stop the solve. */
typedef int (*dyn_output_fn)(long k, double t, const double *y, void *ctx);

/* One stage of one step, for teaching traces: Y is the stage state y_n + h*sum a_ij k_j,
 * k = f(t_n + c_i h, Y). After the last stage, stage == stages and y holds y_{n+1}. */
typedef struct dyn_trace_stage {
    const dyn_tableau *method;
    long step;        /* 0-based step index */
    int stage;        /* 0 .. stages-1; == stages for the step's result */
    double t_n, h;    /* start time and size of the step */
    double t_stage;   /* t_n + c_i h (t_n + h for the result) */
    int n;
    const double *y_n;     /* state at the start of the step */
    const double *Y;       /* stage state (the result y_{n+1} when stage == stages) */
    const double *k;       /* stage derivative (NULL when stage == stages) */
} dyn_trace_stage;
typedef void (*dyn_trace_fn)(const dyn_trace_stage *st, void *ctx);

/* Progress of a long solve: time reached and fraction done in [0, 1]; non-zero cancels. */
typedef int (*dyn_progress_fn)(double t, double fraction, void *ctx);

/* Options of the fixed-step driver; zero-initialise, then set what you need. */
typedef struct dyn_fixed_opts {
    dyn_end_policy end;      /* default DYN_END_EXACT */
    long every;              /* keep every K-th sample (and always the last); 0 or 1 = all */
    dyn_output_fn output;    /* may be NULL: only the final state is returned */
    void *output_ctx;
    dyn_trace_fn trace;      /* may be NULL; called for each stage of the first trace_steps */
    void *trace_ctx;
    long trace_steps;
    int no_finite_check;     /* 1 skips the NaN/Inf check after each step */
    dyn_progress_fn progress; /* may be NULL; called every progress_steps steps */
    void *progress_ctx;
    long progress_steps;     /* 0 = every 65536 steps */
    long max_steps;          /* 0: no limit; a grid of more steps is refused before the first
                              * (DYN_ERR_MAX_STEPS, dyn_grid_check_steps) */
} dyn_fixed_opts;

/* Result details of a solve: the status, where it failed, and the counters. */
typedef struct dyn_result {
    int status;          /* dyn_status */
    int rhs_status;      /* the non-zero value f returned, for DYN_ERR_RHS */
    double t;            /* time reached (of the last good state in y) */
    double fail_t;       /* time of the failing evaluation or state */
    int fail_index;      /* state index that was not finite, or -1 */
    dyn_stats stats;
    char message[256];   /* human-readable reason when status != DYN_OK */
    /* dyn_solve only (zero from the fixed-step driver): */
    int stopped_by_event;  /* 1: a terminal event ended the solve at t (status DYN_OK) */
    int event_index;       /* which event, when stopped_by_event */
    long events;           /* events found (reported through dyn_solve_opts.on_event) */
    long cascades;         /* of them, fired by a reset at the same instant (solve.h) */
    int stiff;             /* 1: the problem looked stiff (see stiff_t, stiff_message) */
    double stiff_t;        /* time where stiffness was detected first */
    char stiff_message[192];
    double h_last;         /* size of the last accepted step */
    int rtol_raised;       /* 1: rtol was below DYN_MIN_RTOL and was raised to it */
} dyn_result;

/* Doubles of workspace the fixed-step driver needs for method m and n states. */
size_t dyn_fixed_work_size(const dyn_tableau *m, int n);

/* Integrate sys from (t0, y0) to t1 with step h using method m.
 * y (n) receives the last good state (also on failure), or is NULL when only the samples
 * are wanted; y may equal y0. work has dyn_fixed_work_size
 * doubles. Output samples stream through opts->output. Never allocates.
 * Returns res->status (DYN_OK on success). opts may be NULL. */
int dyn_fixed_solve(const dyn_tableau *m, const dyn_system *sys, double t0, double t1,
                    double h, const double *y0, double *y, double *work,
                    const dyn_fixed_opts *opts, dyn_result *res);

/* One step y1 = y0 + h * sum b_i k_i from (t, y0). work as for dyn_fixed_solve.
 * y1 may equal y0. Returns 0 or the non-zero value of f. Adds s to *rhs_calls if non-NULL. */
int dyn_rk_step(const dyn_tableau *m, const dyn_system *sys, double t, double h,
                const double *y0, double *y1, double *work, long *rhs_calls);

/* An exact Jacobian J (n x n, row-major, from a dyn_jac_fn at (t, y)) mended where it
 * cannot be evaluated: each column with an entry that is not finite, while f0 = f(t, y) is
 * finite, is formed by a forward difference instead (backward when that is not finite
 * either), with the increments of the stiff methods' difference Jacobians: sqrt(eps)
 * max(|y_j|, typ_j), typ (n) the states' typical magnitudes or NULL for 1. A formula can
 * be finite where its derivative is not: 1/(1 + 1/p) is 0 at p = 0, its derivative's
 * formula inf * 0. work has 2n doubles. Adds the columns replaced to *columns and the
 * calls of f to *rhs_calls (either may be NULL). Returns 0 or the non-zero value of f. The
 * stiff methods (rodas4, cvode) call it on every exact Jacobian. */
int dyn_jacobian_mend(const dyn_system *sys, double t, const double *y, const double *f0,
                      const double *typ, double *J, double *work, long *rhs_calls,
                      long *columns);
/* The same for a banded Jacobian in DYN_BAND_AT storage (entries outside the matrix are
 * neither read nor written). */
int dyn_jacobian_band_mend(const dyn_system *sys, double t, const double *y, const double *f0,
                           const double *typ, int lower, int upper, double *J, double *work,
                           long *rhs_calls, long *columns);

/* The same for a sparse Jacobian (values J in the order of the pattern p). */
int dyn_jacobian_sparse_mend(const dyn_system *sys, double t, const double *y, const double *f0,
                             const double *typ, const dyn_sparse_pattern *p, double *J,
                             double *work, long *rhs_calls, long *columns);

/* The homework's [tout, yout] = Integrate_X(odefun, tspan, Ts, y0, par), into caller arrays:
 * tout has grid->samples entries and yout is (samples x n) row-major, where the grid is
 * dyn_grid_plan(tspan[0], tspan[1], Ts, DYN_END_EXACT). On failure the rows up to the last
 * good sample are filled and res says where it stopped. Returns the status. */
int dyn_integrate(const dyn_tableau *m, dyn_rhs_fn f, const double tspan[2], double Ts,
                  const double *y0, int n, void *par, double *tout, double *yout,
                  double *work, dyn_result *res);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_ODE_H */
