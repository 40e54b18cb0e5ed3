/* SPDX-License-Identifier: BSD-3-Clause */
/* Bands over the runs of a sweep (dynkit sweep --bands FILE): every run's states on a grid
 * of times, then at each time the mean and the 5th, 50th and 95th percentiles over the runs
 * that finished (docs/sweeps.md, "Noise: runs over realisations"). */
#ifndef DYNKIT_CLI_SWEEP_BANDS_H
#define DYNKIT_CLI_SWEEP_BANDS_H

#include "cli.h"

/* At most this many times in a band table (the runs' samples are thinned to it). */
#define SWEEP_BANDS_MAX_TIMES 2001

typedef struct sweep_bands {
    dyn_grid grid;   /* the runs' samples */
    long every;      /* every-th sample is kept */
    long n_times;
    double *series;  /* (n_runs x n_times x n_states), NaN where a run did not reach */
} sweep_bands;

/* The grid of run's samples (the step's) and the series of n_runs runs; CLI_OK, or a usage
 * error (printed: no grid, too much memory) or CLI_FAILED (out of memory). */
int sweep_bands_plan(const cli_run *run, long n_runs, sweep_bands *b);
/* The band table to path in the format of its extension: t, then mean_X, p5_X, p50_X,
 * p95_X for each state X, over the runs whose status is DYN_OK. CLI_OK or CLI_FAILED
 * (printed). */
int sweep_bands_write(const char *path, const sweep_bands *b, const cli_run *run,
                      const int *status, long n_runs);
void sweep_bands_free(sweep_bands *b);

#endif
