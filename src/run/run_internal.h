/* SPDX-License-Identifier: BSD-3-Clause */
/* What the files of src/run share: one run's model, parameters, initial state and options,
 * and the pieces of the delay and Volterra families. Not installed. */
#ifndef DYNKIT_RUN_INTERNAL_H
#define DYNKIT_RUN_INTERNAL_H

#include <stddef.h>

#include "dynkit/delay.h"
#include "dynkit/run.h"

typedef struct run_ctx {
    const dyn_model *m;
    void *par;
    const double *y0;
    const dyn_run_opts *o;
} run_ctx;

/* The history of a delay run (run_delay.c), attached to the parameters between start and
 * finish; breaks are the breaking points the steps land on. */
typedef struct run_delay {
    dyn_history *history;
    double *breaks;
    long n_breaks;
} run_delay;

/* The store of a history grows by doubling (dyn_history.grow). */
int run_history_grow(dyn_history *h, void *ctx);
/* For a model with delays: attach a history to the parameters and set the step callback and
 * stops of opts; nothing for other models. 0, or 1 with the reason in err. */
int run_delay_start(const run_ctx *rc, run_delay *cd, dyn_solve_opts *opts, char *err,
                    size_t errlen);
/* Detach and free the history; when it refused a lag, its message replaces res's. */
void run_delay_finish(const run_ctx *rc, run_delay *cd, dyn_result *res);

/* A run of a model with Volterra integrals (run_volterra.c). */
int run_volterra(const run_ctx *rc, dyn_output_fn output, void *output_ctx, double *y,
                 dyn_result *res);

#endif /* DYNKIT_RUN_INTERNAL_H */
