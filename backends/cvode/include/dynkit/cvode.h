/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/cvode.h — optional backend: SUNDIALS CVODE (BDF, Newton iteration with a dense
 * direct linear solver) for a dyn_system.
 *
 * Built as the separate library dynkit_cvode when CMake finds SUNDIALS (option
 * DYNKIT_WITH_SUNDIALS = AUTO/ON/OFF; Debian package libsundials-dev), so the core library
 * stays C11 + libm. Reference: A. C. Hindmarsh et al., "SUNDIALS: Suite of nonlinear and
 * differential/algebraic equation solvers", ACM TOMS 31 (2005) 363-396; the CVODE user
 * guide (v6.x), sections on CVodeCreate/CVodeInit/CVode and the dense linear solver.
 *
 * Unlike the core library, CVODE allocates: its memory, vectors and matrices are created
 * when dyn_cvode_solve starts and freed before it returns (none inside CVODE's step loop
 * beyond what CVODE itself does). Nothing prints: CVODE's error messages are caught and
 * copied into dyn_result.message.
 *
 * No events here, and so no resets of the state (dyn_event.reset): a model with events that
 * reset it runs with dyn_solve (the tool refuses it with --method cvode).
 */
#ifndef DYNKIT_CVODE_H
#define DYNKIT_CVODE_H

#include <stddef.h>

#include "dynkit/model.h"
#include "dynkit/ode.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Options of dyn_cvode_solve; zero-initialise, then set what you need. */
typedef struct dyn_cvode_opts {
    double rtol;            /* relative tolerance; 0: 1e-3 */
    double atol;            /* absolute tolerance, used when atolv is NULL; 0: 1e-6 */
    const double *atolv;    /* (n) absolute tolerances, or NULL */
    dyn_jac_fn jacobian;    /* analytic df/dy (row-major, as in ode.h), or NULL for CVODE's
                             * difference-quotient Jacobian */
    int max_order;          /* BDF order limit 1..5; 0: 5 */
    long max_steps;         /* steps allowed between two output times; 0: 100000 */
    double initial_step;    /* 0: CVODE's estimate */
    double max_step;        /* 0: no limit */
    int adams;              /* 1: Adams-Moulton (non-stiff) instead of BDF */
    const double *rtolv;    /* (n) relative tolerances, or NULL for rtol: then CVODE's error
                             * weights are 1 / (rtolv_i |y_i| + atol_i) (CVodeWFtolerances) */
    /* A banded Jacobian (jac_banded = 1, bandwidths jac_lower, jac_upper): CVODE's band
     * matrix and band solver (SUNBandMatrix, SUNLinSol_Band) instead of the dense ones, the
     * band from jacobian_band (DYN_BAND_AT storage, ode.h) or CVODE's banded difference
     * quotients (cvLsBandDQJac); `jacobian` is then unused. */
    int jac_banded, jac_lower, jac_upper;
    dyn_jac_fn jacobian_band;
    /* A sparse Jacobian (jac_sparse.nnz > 0 and jacobian_sparse, jac_banded 0; the pattern
     * holds every diagonal entry, ode.h): CVODE's compressed-column matrix and SUNDIALS' KLU
     * solver (SUNSparseMatrix, SUNLinSol_KLU) when the backend was built with them
     * (dyn_cvode_has_klu), else the dense matrix with `jacobian`. */
    dyn_sparse_pattern jac_sparse;
    dyn_jac_fn jacobian_sparse;
} dyn_cvode_opts;

/* 1 when the backend was built with SUNDIALS' KLU solver (sunlinsol_klu), else 0. */
int dyn_cvode_has_klu(void);

/* Integrate sys from (t0, y0) and report the state at each output time tout[0..n_out)
 * (increasing, in [t0, ...), the first may equal t0) through output (k = 0, 1, ...; may be
 * NULL; non-zero stops with DYN_STOPPED). CVODE is never asked for f beyond the last output
 * time (CVodeSetStopTime). y (n) receives the last state reached (may equal y0 or be NULL).
 * res gets the status (DYN_OK, DYN_ERR_ARG, DYN_ERR_RHS with rhs_status, DYN_ERR_MAX_STEPS,
 * DYN_ERR_STEP_SIZE for CVODE's error-test or convergence failures, DYN_STOPPED), the time
 * reached, CVODE's message, and the counters: accepted = CVODE's steps, rejected =
 * error-test plus convergence failures, steps = accepted + rejected (attempts, as
 * dyn_solve counts them), rhs_calls = f evaluations including those of the
 * difference-quotient Jacobian, jac_calls = Jacobian evaluations, samples. Returns
 * res->status. */
int dyn_cvode_solve(const dyn_system *sys, double t0, const double *y0, const double *tout,
                    long n_out, const dyn_cvode_opts *opts, dyn_output_fn output, void *ctx,
                    double *y, dyn_result *res);

/* The same from (t0, y0) to t1 > t0, reporting the state after every step CVODE takes
 * (CV_ONE_STEP, never past t1): sample 0 is y0 at t0, the last one is t1. opts->max_steps
 * limits the steps of the whole run (DYN_ERR_MAX_STEPS). Statuses and counters as for
 * dyn_cvode_solve. */
int dyn_cvode_solve_steps(const dyn_system *sys, double t0, double t1, const double *y0,
                          const dyn_cvode_opts *opts, dyn_output_fn output, void *ctx,
                          double *y, dyn_result *res);

/* dyn_run's CVODE family (dynkit/run.h): the run of model m as dyn_run_opts ro asks, at
 * its output times, its grid or every step; a dyn_run_cvode_fn for dyn_run_backends. */
struct dyn_run_opts;
int dyn_cvode_run(const dyn_model *m, void *par, const double *y0, const struct dyn_run_opts *ro,
                  dyn_output_fn output, void *output_ctx, double *y, dyn_result *res);

/* Version string of the SUNDIALS the backend was built with, e.g. "6.4.1". */
const char *dyn_cvode_version(void);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_CVODE_H */
