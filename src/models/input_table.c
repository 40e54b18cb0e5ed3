/* SPDX-License-Identifier: BSD-3-Clause */
/* input_table.c — dynkit/input.h: a table of inputs read at any time t, with the rules of
 * the homework's force table (zero-order hold at index round(t/Ts) of a uniform table, the
 * nearest sample otherwise, or linear interpolation; end values held outside). */
#include <math.h>
#include <stdio.h>

#include "dynkit/input.h"
#include "dynkit/io.h"

int dyn_input_table_set(dyn_input_table *it, const double *table, long rows, int n_inputs,
                        dyn_interp interp, char *err, size_t errlen)
{
    const int w = 1 + n_inputs;
    if (!table && rows == 0) {
        *it = (dyn_input_table){NULL, 0, n_inputs, interp, 0.0};
        return 0;
    }
    if (!table || rows < 1 || n_inputs < 1) {
        snprintf(err, errlen, "input table: need at least 1 row of t and %d input%s", n_inputs,
                 n_inputs == 1 ? "" : "s");
        return 1;
    }
    if (interp != DYN_INTERP_HOLD && interp != DYN_INTERP_LINEAR) {
        snprintf(err, errlen, "input table: unknown interpolation %d (accepted: hold, linear)",
                 (int)interp);
        return 1;
    }
    for (long k = 0; k < rows; k++) {
        const double *r = table + w * k;
        for (int j = 0; j < w; j++)
            if (!isfinite(r[j])) {
                snprintf(err, errlen, "input table: row %ld (t = %g) has a value that is not "
                         "finite", k + 1, r[0]);
                return 1;
            }
        if (k > 0 && !(r[0] > r[-w])) {
            snprintf(err, errlen, "input table: time must increase strictly, but row %ld has "
                     "t = %s after t = %s", k + 1, dyn_shortest(r[0]).s, dyn_shortest(r[-w]).s);
            return 1;
        }
    }
    double dt = 0.0;
    if (rows > 1) {
        dt = (table[w * (rows - 1)] - table[0]) / (double)(rows - 1);
        for (long k = 1; k < rows - 1 && dt > 0.0; k++)
            if (!(fabs(table[w * k] - (table[0] + (double)k * dt)) <= 1e-9 * dt))
                dt = 0.0;
    }
    *it = (dyn_input_table){table, rows, n_inputs, interp, dt};
    return 0;
}

double dyn_input_table_at(const dyn_input_table *it, double t, int k, double fallback)
{
    const double *tab = it->table;
    const long n = it->rows;
    const int w = 1 + it->n_inputs;
    if (!tab || n < 1 || k < 0 || k >= it->n_inputs)
        return fallback;
    if (n == 1 || !(t > tab[0]))
        return tab[1 + k];
    if (t >= tab[w * (n - 1)])
        return tab[w * (n - 1) + 1 + k];
    if (it->interp == DYN_INTERP_HOLD && it->dt > 0.0) {
        const double x = round((t - tab[0]) / it->dt);
        const long i = x <= 0.0 ? 0 : x >= (double)(n - 1) ? n - 1 : (long)x;
        return tab[w * i + 1 + k];
    }
    long lo = 0, hi = n - 1; /* t_lo <= t < t_hi */
    while (hi - lo > 1) {
        const long mid = lo + (hi - lo) / 2;
        if (tab[w * mid] <= t)
            lo = mid;
        else
            hi = mid;
    }
    const double *a = tab + w * lo, *b = a + w;
    if (it->interp == DYN_INTERP_LINEAR)
        return a[1 + k] + (t - a[0]) / (b[0] - a[0]) * (b[1 + k] - a[1 + k]);
    return b[0] - t <= t - a[0] ? b[1 + k] : a[1 + k]; /* a tie: the later sample */
}
