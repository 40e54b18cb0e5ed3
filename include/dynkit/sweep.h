/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/sweep.h — many runs of one model: parameter sweeps and Monte Carlo ensembles.
 *
 * A sweep runs a model once per row of a run table (values of chosen parameters and initial
 * states, by index into the model's params and states), with one method and one set of
 * options, and reduces each run to a few numbers (its final state, the maximum of an output,
 * the time of an event, ...) written into a caller-owned (runs x columns) array, with a
 * status per run. It is the library of the command `dynkit sweep` (docs/sweeps.md) and
 * usable from a program of one's own (library dynkit_sweep, -ldynkit_sweep with OpenMP).
 *
 * Determinism: run i depends on row i of the table alone. Each run writes only its own row
 * and status, nothing is accumulated across runs, and a run's arithmetic is the same on any
 * thread, so the results are the same bits for any number of threads and any order of the
 * runs. Random tables (dyn_sweep_sample) depend on (seed, run index) alone: a counter-based
 * generator, Philox4x32-10 (Salmon, Moraes, Dror, Shaw, "Parallel random numbers: as easy as
 * 1, 2, 3", SC'11).
 *
 * Threads: OpenMP (dynkit_sweep is compiled with -fopenmp; the core library stays C11 +
 * libm). Each thread gets its workspace once (parameters, states, the solver's workspace,
 * the reductions' accumulators), allocated before the runs start; nothing is allocated per
 * run. A run that fails (a state NaN or Inf, the step size underflowing, the step limit, the
 * model's prepare refusing the parameters, ...) is a row of NaN with its status, and the
 * sweep goes on.
 */
#ifndef DYNKIT_SWEEP_H
#define DYNKIT_SWEEP_H

#include <stddef.h>
#include <stdint.h>

#include "dynkit/model.h"
#include "dynkit/sde.h"
#include "dynkit/solve.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- the run table ---- */

/* What a column of the run table sets: a parameter or an initial state of the model. */
typedef enum dyn_sweep_kind { DYN_SWEEP_PARAM = 0, DYN_SWEEP_STATE = 1 } dyn_sweep_kind;
typedef struct dyn_sweep_var {
    dyn_sweep_kind kind;
    int index; /* into model->params or model->states */
} dyn_sweep_var;

/* The column a name sets: a parameter first, then a state. 0, or -1 with a message naming
 * the model's parameters and states in err. */
int dyn_sweep_var_find(const dyn_model *m, const char *name, dyn_sweep_var *var, char *err,
                       size_t errlen);
/* The name of a column (the parameter's or the state's name). */
const char *dyn_sweep_var_name(const dyn_model *m, const dyn_sweep_var *var);

/* ---- reductions: what each run is reduced to ---- */

typedef enum dyn_reduce_op {
    DYN_REDUCE_FINAL = 0,  /* value at the end of the run (t1, or a terminal event) */
    DYN_REDUCE_MAX = 1,    /* largest value over the samples */
    DYN_REDUCE_MIN = 2,    /* smallest value over the samples */
    DYN_REDUCE_MEAN = 3,   /* time average over the samples (trapezoidal rule, below) */
    DYN_REDUCE_ARGMAX = 4, /* time of the (first) largest sample */
    DYN_REDUCE_ARGMIN = 5, /* time of the (first) smallest sample */
    DYN_REDUCE_EVENT = 6,  /* time of the first occurrence of an event, NaN if none */
    DYN_REDUCE_COUNT = 7   /* number of occurrences of an event */
} dyn_reduce_op;

typedef enum dyn_reduce_source {
    DYN_SOURCE_STATE = 0,  /* index into model->states */
    DYN_SOURCE_OUTPUT = 1, /* index into model->outputs */
    DYN_SOURCE_EVENT = 2   /* index into model->events (event and count only) */
} dyn_reduce_source;

/* One result column. The samples of max, min, mean, argmax and argmin are those of the run:
 * every step of a fixed-step method (t0 + k*h, and t1 after a shorter last step), the grid
 * t0 + k*step of an adaptive method by dense output (dyn_sweep.step > 0) or every accepted
 * step (step = 0); the first sample is the initial state, the last the final one; samples
 * before the model's t_trans are left out. mean is the time average of the piecewise-linear
 * function through the samples: sum over intervals of (t_{k+1} - t_k)(x_k + x_{k+1})/2,
 * divided by t_last - t_first (for an even grid: the samples' average with the two ends
 * weighted 1/2); with a single sample, that sample. */
typedef struct dyn_reduce {
    dyn_reduce_op op;
    dyn_reduce_source source;
    int index;
} dyn_reduce;

/* Parse a comma-separated list of reductions: final (one column per state: final:NAME for
 * each), final:NAME, max:NAME, min:NAME, mean:NAME, argmax:NAME, argmin:NAME (NAME a state
 * or an output), event:NAME, count:NAME (NAME one of the model's events). Up to max columns
 * into out; *count receives how many. Returns 0, or -1 with a message in err (an unknown
 * reduction or name, naming what is accepted; more than max columns). */
int dyn_reduce_parse(const dyn_model *m, const char *list, dyn_reduce *out, int max,
                     int *count, char *err, size_t errlen);
/* The column's name, "OP_NAME" (e.g. "max_height", "event_turn" for max:height and
 * event:turn: a name that NumPy, pandas, MATLAB and Octave keep as it is), into buf;
 * returns buf. */
char *dyn_reduce_name(const dyn_model *m, const dyn_reduce *r, char *buf, size_t size);

/* ---- the sweep ---- */

/* Status of a run that did not finish: the sweep was cancelled before or during it. The
 * statuses of finished runs are dyn_status values (DYN_OK, DYN_ERR_NONFINITE, ...; the
 * model's prepare refusing the run's parameters is DYN_ERR_ARG, a state exceeding the
 * model's bound DYN_STOPPED). */
#define DYN_SWEEP_NOT_RUN (-1)

/* Called after each finished run, one call at a time (never concurrently), from whichever
 * thread finished it: the run's index, its status, runs finished so far and runs to do
 * (those not skipped). Return non-zero to cancel the sweep. */
typedef int (*dyn_sweep_progress_fn)(long run, int status, long done, long total, void *ctx);
/* Polled from every thread, concurrently, before each run and every progress_steps steps
 * within a run: return non-zero to cancel (e.g. read a flag a signal handler sets). */
typedef int (*dyn_sweep_cancel_fn)(void *ctx);

/* A sweep: zero-initialise, then set what you need. */
typedef struct dyn_sweep {
    const dyn_model *model;
    /* The base of every run: parameters (model->par_size bytes, prepared) or NULL for the
     * model's defaults; initial state (n_states) or NULL for each run's
     * dyn_model_initial_state (which may depend on the run's parameters). A run copies them,
     * sets its table row's values, runs the model's prepare, then sets its states. */
    const void *par;
    const double *y0;
    /* The run table: n_runs rows of n_vars values, row-major (run i: values[i*n_vars ..]). */
    int n_vars;
    const dyn_sweep_var *vars;
    long n_runs;
    const double *values;
    /* The runs' method, span and options (as dyn_fixed_solve and dyn_solve take them). */
    const dyn_tableau *method;
    double t0, t1;
    double step;              /* fixed-step: the step (required); adaptive: the sample grid
                               * of the reductions, 0: every accepted step */
    dyn_end_policy end;
    double rtol, atol;        /* 0: the defaults (solve.h) */
    const double *rtolv, *atolv; /* (n_states) or NULL */
    double initial_step, max_step; /* 0: automatic */
    long max_steps;                /* 0: no limit; fixed steps: a longer grid refused at once */
    /* The reductions: one result column each. */
    int n_reduce;
    const dyn_reduce *reduce;
    /* Events of the model (indices into model->events) that end a run at their first
     * occurrence (like --event NAME:stop); may be NULL. The model's events that reset the
     * state always take part. */
    int n_stop;
    const int *stop;
    /* Runs to leave alone (their rows and statuses untouched, e.g. finished before a
     * resume): (n_runs) flags, or NULL. */
    const unsigned char *skip;
    /* Threads: 0 for OpenMP's default (all cores, or OMP_NUM_THREADS), 1 for none. */
    int threads;
    dyn_sweep_progress_fn progress; /* may be NULL */
    void *progress_ctx;
    dyn_sweep_cancel_fn cancel;     /* may be NULL */
    void *cancel_ctx;
    long progress_steps;      /* steps between polls of cancel within a run; 0: 65536 */
    /* A model with noise (model->n_noise > 0, dynkit/sde.h): each run integrated by
     * dyn_sde_solve with noise_method (a dyn_sde_method; method then only names it), its
     * noise that of stream = the run's index under seed, so a run's noise is the same on
     * any number of threads or ranks. */
    uint64_t seed;
    int noise_method;
    /* Time series of every run (for bands over runs), or NULL: series is
     * (n_runs x n_series x n_states), row-major, caller-owned; run i's state at sample
     * k * series_every (k < n_series; sample k of a fixed step at t0 + k step, of an
     * adaptive method on the grid of step, which must then be > 0) goes to
     * series[(i n_series + k) n_states ..]; what a run does not reach is left alone. */
    double *series;
    long n_series, series_every;
    /* The linear algebra of a stiff method (rodas4), as a single run takes it
     * (dyn_solve_opts): the model's band (model->jac_banded) is always used, factored by
     * band_solver (NULL: dyn_band_solver_builtin). With sparse_open, a model with a sparse
     * pattern (model->jac_pattern; its values from jacobian_sparse, or by differences in
     * groups of columns, dyn_sparse_groups) and no band runs with sparse matrices: each thread has a dyn_sparse_solver of its own, filled by sparse_open
     * (e.g. dyn_klu_init, dynkit/klu.h) before its first run and given back to sparse_close
     * after its last, so one analysis of the pattern serves all of the thread's runs (each
     * run pivots anew: dyn_sparse_solver.forget, and the results stay those of any number
     * of threads). NULL: dense matrices. */
    const dyn_band_solver *band_solver;
    int (*sparse_open)(dyn_sparse_solver *solver);
    void (*sparse_close)(dyn_sparse_solver *solver);
} dyn_sweep;

/* Run the sweep: results is (n_runs x n_reduce) doubles, row-major, status (n_runs) ints;
 * both caller-owned. A finished run's row holds its reductions (NaN for an event that did not
 * occur), a failed run's row NaN, a run not run (cancelled) NaN with DYN_SWEEP_NOT_RUN.
 * Returns DYN_OK when every run finished (some may have failed: see status), DYN_CANCELLED
 * when cancelled, DYN_ERR_ARG (a bad sweep: message in err) or DYN_ERR_CAPACITY (out of
 * memory for the workspaces; nothing was run). Thread-safe: sweeps may run concurrently. */
int dyn_sweep_run(const dyn_sweep *s, double *results, int *status, char *err,
                  size_t errlen);

/* ---- run tables: grids and random samples (sample.c) ---- */

/* Value k (0 <= k < n) of n evenly spaced values from a to b: a + k ((b - a)/(n - 1)) (the
 * step first, as numpy's linspace), computed from k (never accumulated), with the ends
 * exactly a (k = 0) and b (k = n - 1); a for n = 1. */
double dyn_linspace_at(double a, double b, long n, long k);
/* The full grid of n_axes axes (axis j: counts[j] values at axes[j]) as a run table of
 * prod(counts) rows and n_axes columns, row-major into values; the last axis varies
 * fastest (row r = sum_j k_j prod_{l > j} counts[l]), like nested loops with the last
 * axis innermost. Returns the number of rows, or -1 when it would exceed max_rows. */
long dyn_sweep_grid(int n_axes, const double *const *axes, const long *counts, double *values,
                    long max_rows);

/* dyn_philox4x32, the generator: dynkit/sde.h (part of the core). */

/* Distributions of random run tables. */
typedef enum dyn_dist_kind {
    DYN_DIST_UNIFORM = 0,   /* uniform on (a, b) */
    DYN_DIST_NORMAL = 1,    /* normal with mean a and standard deviation b */
    DYN_DIST_LOGNORMAL = 2  /* exp of a normal with mean a and standard deviation b (the
                             * parameters of the logarithm, as numpy's lognormal) */
} dyn_dist_kind;
typedef struct dyn_dist {
    dyn_dist_kind kind;
    double a, b;
} dyn_dist;

/* The random value of run `run` and column `column` for seed: one Philox4x32-10 block with
 * counter (run low 32 bits, run high 32 bits, column, 0) and key (seed low, seed high). Its
 * words give two uniform numbers in (0, 1) with 53 random bits each,
 * u = (((w0 << 32 | w1) >> 11) + 1/2) 2^-53 and likewise from w2, w3; uniform(a, b) is
 * a + (b - a) u1; normal values come from the Box–Muller transform
 * z = sqrt(-2 ln u1) cos(2 pi u2) (one value per block). The value depends on
 * (seed, run, column) alone. */
double dyn_dist_value(const dyn_dist *d, uint64_t seed, uint64_t run, uint32_t column);
/* Rows first_run .. first_run + n_runs - 1 of a random run table with n_cols columns
 * (column j drawn from dists[j]) into values (n_runs x n_cols, row-major). */
void dyn_sweep_sample(const dyn_dist *dists, int n_cols, uint64_t seed, long first_run,
                      long n_runs, double *values);

/* The number of threads dyn_sweep_run uses for threads (0: the default), and 1 when
 * dynkit_sweep was built without OpenMP. */
int dyn_sweep_threads(int threads);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_SWEEP_H */
