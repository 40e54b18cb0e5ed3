/* SPDX-License-Identifier: BSD-3-Clause */
/* Stochastic jumps of model files (dynkit/sde.h): one step of a Markov chain with the
 * transition rule of XPPAUT's `markov` (Ermentrout, Simulating, Analyzing, and Animating
 * Dynamical Systems, SIAM 2002, "Markov models": leave state i for j with probability
 * rate(i, j) dt per step, the states tried in order against one uniform number), and one
 * reaction of Gillespie's direct method (Gillespie, J. Phys. Chem. 81, 2340, 1977: the
 * waiting time is exponential with the total rate, the reaction is chosen with
 * probability proportional to its rate), XPPAUT's `gill`. */
#include <math.h>

#include "dynkit/sde.h"

int dyn_markov_step(double *z, int n, const double *rates, double h, double u)
{
    int from = -1;
    for (int i = 0; i < n; i++)
        if (fabs(*z - (double)i) < 1e-4) {
            from = i;
            break;
        }
    if (from < 0)
        return 0;
    const double *row = rates + (long)from * n;
    for (int j = 0; j < n; j++)
        if (j != from && !(row[j] >= 0.0 && isfinite(row[j])))
            return -1; /* *z as it was: the last good state shows it */
    double sum = 0.0;
    for (int j = 0; j < n; j++) {
        if (j == from)
            continue;
        sum += h * row[j];
        if (u < sum) {
            *z = (double)j;
            return 0;
        }
    }
    return 0;
}

int dyn_gillespie_step(double *out, int m, const double *rates, double u1, double u2)
{
    double total = 0.0;
    for (int k = 0; k < m; k++) {
        if (!(rates[k] >= 0.0 && isfinite(rates[k]))) {
            for (int i = 0; i <= m; i++)
                out[i] = NAN;
            return -1;
        }
        total += rates[k];
        out[1 + k] = 0.0;
    }
    if (!(total > 0.0)) {
        out[0] = 0.0;
        return 0;
    }
    out[0] = -log1p(-u1) / total;
    const double target = u2 * total;
    double sum = 0.0;
    int last = -1;
    for (int k = 0; k < m; k++) {
        if (rates[k] > 0.0)
            last = k;
        sum += rates[k];
        if (target < sum && rates[k] > 0.0) {
            out[1 + k] = 1.0;
            return 0;
        }
    }
    out[1 + last] = 1.0; /* u2 R rounded up to the sum: the last reaction that can happen */
    return 0;
}
