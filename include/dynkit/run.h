/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/run.h — one run of any model: the library's single entry.
 *
 * A model may need one of several solver families: the fixed-step driver (dyn_fixed_solve),
 * the general driver with events, resets and stiff methods (dyn_solve), the methods for noise
 * and Markov jumps (dyn_sde_solve), delay equations (a history fed by dyn_solve's steps),
 * Volterra integrals (dyn_volterra_solve), or CVODE (an optional backend). dyn_run chooses by
 * the model and the method, exactly as `dynkit run` does, so that every front door (the
 * command line, the Python package, the MEX functions, a live page) runs every model kind
 * the same. It also applies a model's output rules (XPPAUT's @ trans and bound) and fires the
 * model's resets (global events) on every run.
 *
 * dyn_run allocates the workspace of the run (once, before the first step) and frees it
 * before it returns; it never prints. Optional linear algebra (LAPACK's band LU, KLU) and the
 * CVODE backend come in through dyn_run_backends, which the core does not link.
 */
#ifndef DYNKIT_RUN_H
#define DYNKIT_RUN_H

#include <stdint.h>

#include "dynkit/model.h"
#include "dynkit/solve.h"

#ifdef __cplusplus
extern "C" {
#endif

struct dyn_run_opts;

/* CVODE's run of a model (backends/cvode: dyn_cvode_run); the samples go to output. */
typedef int (*dyn_run_cvode_fn)(const dyn_model *m, void *par, const double *y0,
                                const struct dyn_run_opts *o, dyn_output_fn output,
                                void *output_ctx, double *y, dyn_result *res);

/* The optional parts a run may use; any member may be NULL (the library's own, or none). */
typedef struct dyn_run_backends {
    const dyn_band_solver *band;              /* band LU of stiff runs (NULL: built-in) */
    int (*sparse_open)(dyn_sparse_solver *s); /* a sparse LU: 0 when opened (NULL: none) */
    void (*sparse_close)(dyn_sparse_solver *s);
    dyn_run_cvode_fn cvode;                   /* NULL: dynkit built without SUNDIALS */
    int cvode_has_klu;                        /* CVODE takes sparse matrices (KLU) */
} dyn_run_backends;

/* The matrices of a stiff run of a model: dense, band (the model's band, declared or found
 * in its exact pattern) or sparse (a pattern that is not banded, when a sparse LU exists),
 * and why, in words. */
typedef enum dyn_linear_kind {
    DYN_LINEAR_DENSE = 0,
    DYN_LINEAR_BAND = 1,
    DYN_LINEAR_SPARSE = 2
} dyn_linear_kind;
typedef struct dyn_linear_choice {
    dyn_linear_kind kind;
    int lower, upper, nnz; /* the band (of the pattern, when there is one); entries */
    char why[256];
} dyn_linear_choice;
/* A sparse LU pays against the dense one from this many states on, for a pattern with at
 * most a quarter of the entries. */
#define DYN_SPARSE_MIN_STATES 32
/* The choice for model m with method (NULL: any stiff method of the library) and the
 * backends b (may be NULL: none). */
void dyn_run_linear_choose(const dyn_model *m, const dyn_tableau *method,
                           const dyn_run_backends *b, dyn_linear_choice *lin);

/* A warning of a run that goes on (e.g. Volterra integrals that stop reaching back to t0). */
typedef void (*dyn_run_warn_fn)(const char *message, void *ctx);

/* One run. Zero-initialise, then set what is needed: method, t0, t1, step at least. */
typedef struct dyn_run_opts {
    const dyn_tableau *method;  /* dyn_run_method_find(name) */
    double t0, t1;
    double step;                /* fixed-step methods: the step; adaptive: the output grid */
    dyn_end_policy end;         /* the last partial step (dyn_grid_plan) */
    /* adaptive methods */
    double rtol, atol;          /* 0: DYN_MODEL_RTOL / DYN_MODEL_ATOL or the model's own */
    const double *rtolv, *atolv; /* per-state tolerances (n_states), or NULL */
    const double *times;        /* output times (n_times), or NULL: the grid of step */
    long n_times;
    int at_steps;               /* 1: a sample at every accepted step instead of the grid */
    double max_step, initial_step; /* 0: automatic */
    long max_steps;                /* 0: no limit; fixed steps: a longer grid refused at once */
    /* the events to report, the model's by name with terminal flags as asked (the model's
     * resets run in any case); (n_events) or NULL */
    const dyn_event *events;
    int n_events;
    /* noise and Markov jumps: the seed and the run's stream */
    uint64_t seed, stream;
    long every;                 /* every K-th sample to output (0, 1: all) */
    dyn_output_fn output;       /* the samples; may be NULL */
    void *output_ctx;
    dyn_event_fn on_event;      /* the events of `events` found (index into events) */
    void *event_ctx;
    dyn_progress_fn progress;
    void *progress_ctx;
    dyn_trace_fn trace;         /* stage-by-stage traces of the first trace_steps steps */
    void *trace_ctx;
    long trace_steps;
    dyn_run_warn_fn warn;       /* warnings (NULL: dropped) */
    void *warn_ctx;
    const dyn_run_backends *backends; /* NULL: the library's own linear algebra, no CVODE */
} dyn_run_opts;

/* Run model m with the prepared parameter struct par (m->par_size bytes; a delay model's
 * history is attached to it during the run) from y0 over [t0, t1]. y (n_states) receives the
 * last good state. Returns res->status (DYN_OK, or an error with res->message), or -1 when
 * memory ran out. */
int dyn_run(const dyn_model *m, void *par, const double *y0, const dyn_run_opts *o, double *y,
            dyn_result *res);

/* The methods of dyn_run: the library's registry (dyn_method_find, aliases, case as given)
 * and the descriptors of the other solver families: "rkmil" and "sriw1" (models with noise),
 * "volterra" (Volterra integrals), "cvode" (the CVODE backend; its runs need
 * dyn_run_backends.cvode). NULL when unknown. */
const dyn_tableau *dyn_run_method_find(const char *name);
/* The descriptors themselves, for tests of a method's family. */
const dyn_tableau *dyn_run_method_rkmil(void);
const dyn_tableau *dyn_run_method_sriw1(void);
const dyn_tableau *dyn_run_method_volterra(void);
const dyn_tableau *dyn_run_method_cvode(void);
/* The dyn_sde_method a noise run of method m uses (Euler–Maruyama for fixed-step ones). */
int dyn_run_sde_method(const dyn_tableau *m);

/* The tolerances of a run that gives none: the model's own, else DYN_MODEL_RTOL and
 * DYN_MODEL_ATOL, or 1e-3 and 1e-6 for a model with noise (rkmil's strong order 1). */
double dyn_run_default_rtol(const dyn_model *m);
double dyn_run_default_atol(const dyn_model *m);
/* The scalar tolerances of a run: o's when > 0, else the defaults above. */
void dyn_run_tolerances(const dyn_model *m, const struct dyn_run_opts *o, double *rtol,
                        double *atol);

/* The number of the model's events that reset the state (its globals). */
int dyn_run_resets(const dyn_model *m);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_RUN_H */
