/* SPDX-License-Identifier: BSD-3-Clause */
/* Run tables of a sweep (dynkit/sweep.h): evenly spaced values with exact ends, full grids
 * (the last axis fastest), and random samples from Philox4x32-10 (the core's
 * dyn_philox4x32, src/ode/philox.c); normal values by the Box–Muller transform. */
#include <math.h>

#include "dynkit/sweep.h"

double dyn_linspace_at(double a, double b, long n, long k)
{
    if (n <= 1 || k <= 0)
        return a;
    if (k >= n - 1)
        return b;
    return a + (double)k * ((b - a) / (double)(n - 1));
}

long dyn_sweep_grid(int n_axes, const double *const *axes, const long *counts, double *values,
                    long max_rows)
{
    long rows = 1;
    for (int j = 0; j < n_axes; j++) {
        if (counts[j] < 1 || rows > max_rows / counts[j])
            return -1;
        rows *= counts[j];
    }
    if (!values)
        return rows;
    for (long r = 0; r < rows; r++) {
        long rest = r;
        for (int j = n_axes - 1; j >= 0; j--) {
            values[(size_t)r * (size_t)n_axes + (size_t)j] = axes[j][rest % counts[j]];
            rest /= counts[j];
        }
    }
    return rows;
}

double dyn_dist_value(const dyn_dist *d, uint64_t seed, uint64_t run, uint32_t column)
{
    const uint32_t ctr[4] = {(uint32_t)run, (uint32_t)(run >> 32), column, 0};
    const uint32_t key[2] = {(uint32_t)seed, (uint32_t)(seed >> 32)};
    uint32_t w[4];
    dyn_philox4x32(ctr, key, 10, w);
    const double u1 = dyn_philox_unit(w[0], w[1]);
    if (d->kind == DYN_DIST_UNIFORM)
        return d->a + (d->b - d->a) * u1;
    const double u2 = dyn_philox_unit(w[2], w[3]);
    const double z = sqrt(-2.0 * log(u1)) * cos(2.0 * DYN_PI * u2);
    const double x = d->a + d->b * z;
    return d->kind == DYN_DIST_LOGNORMAL ? exp(x) : x;
}

void dyn_sweep_sample(const dyn_dist *dists, int n_cols, uint64_t seed, long first_run,
                      long n_runs, double *values)
{
    for (long i = 0; i < n_runs; i++)
        for (int j = 0; j < n_cols; j++)
            values[(size_t)i * (size_t)n_cols + (size_t)j] =
                dyn_dist_value(&dists[j], seed, (uint64_t)(first_run + i), (uint32_t)j);
}
