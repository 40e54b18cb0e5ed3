/* SPDX-License-Identifier: BSD-3-Clause */
/* eq_box.c — the default box of the equilibrium search (eq_box.h): the range of the
 * model's default run from its initial state, widened, and the file's phase window. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "commands/eq_box.h"

typedef struct range_ctx {
    int n;
    double *lo, *hi;
    long samples;
} range_ctx;

static int track_range(long k, double t, const double *y, void *ctx)
{
    (void)k;
    (void)t;
    range_ctx *r = ctx;
    for (int i = 0; i < r->n; i++)
        if (isfinite(y[i])) {
            r->lo[i] = fmin(r->lo[i], y[i]);
            r->hi[i] = fmax(r->hi[i], y[i]);
        }
    r->samples++;
    return 0;
}

void cli_eq_default_box(const cli_run *run, double *lo, double *hi, int *from_file)
{
    const dyn_model *m = run->model;
    const int n = m->n_states;
    range_ctx r = {n, lo, hi, 0};
    for (int i = 0; i < n; i++)
        lo[i] = hi[i] = run->y0[i];
    double *y = malloc((size_t)n * sizeof *y);
    dyn_result res;
    memset(&res, 0, sizeof res);
    if (y)
        cli_run_solve(run, 1, track_range, &r, NULL, NULL, NULL, NULL, y, &res);
    free(y);
    for (int i = 0; i < n; i++) {
        const double margin = fmax(0.5 * (hi[i] - lo[i]), 1.0);
        lo[i] -= margin;
        hi[i] += margin;
        from_file[i] = 0;
    }
    const char *axis[2] = {m->phase_x, m->phase_y};
    for (int a = 0; a < 2; a++) {
        const int i = axis[a] ? dyn_model_state_index(m, axis[a]) : -1;
        const double wlo = m->phase_window[2 * a], whi = m->phase_window[2 * a + 1];
        if (i >= 0 && wlo < whi) {
            lo[i] = wlo;
            hi[i] = whi;
            from_file[i] = 1;
        }
    }
}
