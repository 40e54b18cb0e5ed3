/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/input.h — a time table of a model's inputs (dyn_model.inputs), read at any time
 * as the built-in cart reads its force table: zero-order hold at the nearest sample (for a
 * uniform table the sample round((t - t_0)/dt), else the nearest sample time, ties to the
 * later one) or linear interpolation, the end values held outside the table. Models
 * translated from files (mechanisms' `input` lines) keep one in their parameters. */
#ifndef DYNKIT_INPUT_H
#define DYNKIT_INPUT_H

#include <stddef.h>

#include "dynkit/model.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct dyn_input_table {
    const double *table; /* (rows x (1 + n_inputs)) row-major, t first; borrowed; NULL: none */
    long rows;
    int n_inputs;
    dyn_interp interp;
    double dt;           /* the sample time of a uniform table, else 0 */
} dyn_input_table;

/* Check and attach a table (t finite and strictly increasing, values finite, rows >= 1);
 * table NULL with rows 0 detaches it. 0, or non-zero with a message naming the bad row in
 * err (it unchanged). */
int dyn_input_table_set(dyn_input_table *it, const double *table, long rows, int n_inputs,
                        dyn_interp interp, char *err, size_t errlen);

/* Input k (0-based) at time t, or fallback when no table is attached. */
double dyn_input_table_at(const dyn_input_table *it, double t, int k, double fallback);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_INPUT_H */
