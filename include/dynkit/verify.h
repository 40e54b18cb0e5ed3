/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/verify.h — every method on problems with known solutions: the accuracy reached
 * and the work spent, per method and tolerance (or step).
 *
 * The problems (dyn_verify_problem_at) and their references:
 *   vanderpol-mu1     van der Pol mu = 1, y0 = (2, 0), t = 15: __float128 Taylor series and
 *                     RK4 with Richardson extrapolation (references.c, "vanderpol-mu1-15");
 *   arenstorf         Arenstorf's orbit over one period T (HNW I sec. II.0): back at its
 *                     start; the reference is y(T) of the problem with double data, which
 *                     equals y(0) to 1.5e-11 ("arenstorf-period");
 *   oscillator        x'' = -x, x(0) = 1, x'(0) = 0 on [0, 20]: exact (cos 20, -sin 20);
 *   vanderpol-mu1000  van der Pol mu = 1000, y0 = (2, 0) on [0, 3000] (__float128 Taylor
 *                     series, which at t = 2000 confirms the Test Set's vdpolm value;
 *                     "vanderpol-mu1000-3000");
 *   robertson         Robertson to t = 1e11, Test Set for IVP Solvers, ROBER
 *                     ("robertson-1e11");
 *   hires             HIRES to t = 321.8122, Test Set for IVP Solvers ("hires-321.8122").
 * The error is the max norm of y(t1) - reference: absolute for the first three (states of
 * size one), relative per component (|y_i - ref_i| / |ref_i|) for the stiff ones, whose
 * components range over many orders of magnitude; digits = -log10(error) (the Test Set's
 * "significant correct digits").
 *
 * Methods: fixed-step tables at a few step counts (each half the step of the one before)
 * with the observed order log2(e(h) / e(h/2)); adaptive methods at rtol = 1e-3, 1e-6, 1e-9
 * with atol = atol_scale * rtol (per problem: 1 for the non-stiff ones, 1e-3 for
 * vanderpol-mu1000, 1e-6 for robertson, 1e-4 for hires — about the size of the smallest
 * components that matter).
 * On the stiff problems fixed-step explicit methods are skipped (stability would need
 * millions of steps) and adaptive explicit ones are limited to explicit_max_steps steps
 * (reported as too many steps, with the stiffness test's finding). Methods outside the
 * core library (the CVODE backend) come in through dyn_verify_method.
 *
 * The library prints nothing: rows are handed back (and to a callback as they finish); the
 * tool's `dynkit verify` prints them. Workspaces are allocated before each solve, never in
 * a step loop.
 */
#ifndef DYNKIT_VERIFY_H
#define DYNKIT_VERIFY_H

#include <stddef.h>

#include "dynkit/ode.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A verification problem. */
typedef struct dyn_verify_problem {
    const char *name;        /* e.g. "robertson" */
    const char *title;       /* one line */
    const char *reference;   /* the reference and where it comes from (citation) */
    const char *model;       /* built-in model it runs, or NULL (the oscillator) */
    double t0, t1;
    int n;                   /* states */
    int stiff;               /* 1: from the stiff test sets */
    int relative;            /* error norm: 1 max_i |y_i - ref_i| / |ref_i|, 0 max_i |y_i - ref_i| */
    double atol_scale;       /* adaptive runs: atol = atol_scale * rtol */
    int n_fixed;             /* step counts of fixed-step methods (0: skipped, stiff) */
    const long *fixed_steps; /* (n_fixed) increasing, each twice the one before */
} dyn_verify_problem;

int dyn_verify_problem_count(void);
const dyn_verify_problem *dyn_verify_problem_at(int i);
const dyn_verify_problem *dyn_verify_problem_find(const char *name);
/* The reference state at t1 (problem->n values) into ref; 0, or non-zero with a message. */
int dyn_verify_reference(const dyn_verify_problem *p, double *ref, char *err, size_t errlen);

/* A method outside the core library (e.g. the CVODE backend): integrate sys from (t0, y0)
 * to t1 with the tolerances (and jac, the problem's analytic Jacobian), at most max_steps
 * steps when > 0; fill y (n) and res (status, counters: steps, accepted, rejected,
 * rhs_calls, jac_calls). Returns res->status. */
typedef int (*dyn_verify_solve_fn)(const dyn_system *sys, dyn_jac_fn jac, double t0, double t1,
                                   const double *y0, double rtol, double atol, long max_steps,
                                   double *y, dyn_result *res, void *ctx);
typedef struct dyn_verify_method {
    const char *name;
    int stiff;               /* 1: meant for stiff problems (no step limit on them) */
    dyn_verify_solve_fn solve;
    void *ctx;
} dyn_verify_method;

/* Outcome of a row. */
typedef enum dyn_verify_outcome {
    DYN_VERIFY_DONE = 0,     /* reached t1: error measured */
    DYN_VERIFY_SKIPPED = 1,  /* not run: a fixed-step explicit method on a stiff problem */
    DYN_VERIFY_LIMIT = 2,    /* stopped: step limit or step size too small (note says which) */
    DYN_VERIFY_FAILED = 3    /* stopped otherwise (NaN/Inf, right-hand side, ...) */
} dyn_verify_outcome;

/* One run: a problem, a method, a tolerance or a step, and what it achieved. */
typedef struct dyn_verify_row {
    const dyn_verify_problem *problem;
    const char *method;      /* canonical name */
    int adaptive;            /* 1: rtol/atol; 0: fixed steps h = (t1 - t0) / steps */
    int stiff_method;        /* the method is meant for stiff problems */
    double rtol, atol;       /* adaptive */
    double h;                /* fixed */
    long steps;              /* fixed: number of steps */
    dyn_verify_outcome outcome;
    int status;              /* dyn_status of the solve (0 when skipped) */
    double error;            /* max-norm error at t1 (problem->relative), NaN if not reached */
    double digits;           /* -log10(error); +Inf for error 0; NaN if not reached */
    double order;            /* fixed: observed order against the previous step count; NaN */
    dyn_stats stats;         /* rhs_calls, jac_calls, accepted, rejected, steps */
    double seconds;          /* wall time of the solve */
    double t_reached;
    int stiff_detected;      /* the explicit pairs' stiffness test fired */
    int ok;                  /* 1: done, skipped, or an explicit method at its limit on a
                              * stiff problem; 0: an unexpected failure */
    char note[160];          /* why it stopped or what was seen, or "" */
} dyn_verify_row;

/* Called with each finished row; non-zero stops the run (DYN_STOPPED). */
typedef int (*dyn_verify_row_fn)(const dyn_verify_row *row, void *ctx);

/* Options; zero-initialise. */
typedef struct dyn_verify_opts {
    int quick;               /* a small subset: rtol 1e-3 and 1e-6, two step counts, a lower
                              * step limit; every problem and method still appears */
    const char *problem;     /* only this problem, or NULL */
    const char *method;      /* only this method (name or alias, or an extra's name), or NULL */
    const dyn_verify_method *extra; /* (n_extra) methods outside the core library */
    int n_extra;
    long explicit_max_steps; /* step limit of explicit adaptive methods on stiff problems;
                              * 0: 100000 (quick: 20000) */
    dyn_verify_row_fn on_row;
    void *row_ctx;
} dyn_verify_opts;

/* Rows the options give (checks the names): >= 0, or -1 with a message in err naming what is
 * accepted. */
long dyn_verify_count(const dyn_verify_opts *opts, char *err, size_t errlen);

/* Run every row into rows (capacity at least dyn_verify_count). *n_rows gets the rows made.
 * Returns DYN_OK (also when some rows failed: see row.ok), DYN_ERR_ARG (bad names, too
 * little capacity, out of memory; message in err) or DYN_STOPPED (on_row stopped it). */
int dyn_verify_run(const dyn_verify_opts *opts, dyn_verify_row *rows, long capacity,
                   long *n_rows, char *err, size_t errlen);

/* Tolerances of the adaptive rows (quick: the first two). */
#define DYN_VERIFY_N_RTOL 3
extern const double dyn_verify_rtols[DYN_VERIFY_N_RTOL];

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_VERIFY_H */
