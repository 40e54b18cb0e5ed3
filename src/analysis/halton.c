/* SPDX-License-Identifier: BSD-3-Clause */
/* halton.c — Halton's low-discrepancy sequence (J. H. Halton, Numer. Math. 2 (1960)
 * 84-90): coordinate j of point k is the radical inverse of k in the base of the j-th prime
 * (2, 3, 5, ...): k's digits in that base mirrored about the radix point. Deterministic
 * starting points that fill a box evenly in any number of dimensions. */
#include "dynkit/equilibria.h"

/* The j-th prime (j = 0: 2), by trial division: j is a state's index. */
static long nth_prime(int j)
{
    long p = 1;
    for (int found = -1; found < j;) {
        p++;
        int prime = 1;
        for (long d = 2; d * d <= p && prime; d++)
            prime = p % d != 0;
        found += prime;
    }
    return p;
}

double dyn_halton(long k, int j)
{
    const long base = nth_prime(j);
    double f = 1.0, r = 0.0;
    for (long i = k; i > 0; i /= base) {
        f /= (double)base;
        r += f * (double)(i % base);
    }
    return r;
}
