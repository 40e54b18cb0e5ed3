/* SPDX-License-Identifier: BSD-3-Clause */
/* The samples of a run for the bindings, stored as they come (row by row) and growing by
 * doubling between steps: times, states and optional outputs. */
#ifndef DYNKIT_BINDINGS_SAMPLES_H
#define DYNKIT_BINDINGS_SAMPLES_H

typedef struct dkb_samples {
    int n, n_out;       /* states, outputs per sample (0: none) */
    long count, cap;
    double *t, *y, *out; /* (cap), (cap x n), (cap x n_out) */
} dkb_samples;

/* Append a sample (out: n_out values, or ignored when n_out is 0); 0, or 1 out of memory. */
int dkb_samples_add(dkb_samples *s, double t, const double *y, const double *out);
void dkb_samples_free(dkb_samples *s);

#endif /* DYNKIT_BINDINGS_SAMPLES_H */
