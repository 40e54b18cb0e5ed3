/* SPDX-License-Identifier: BSD-3-Clause */
/* constraint_rows.c — a mechanism's constraints read from the outputs of the model that
 * dyn_mech_constraints_to_c writes (dynkit/analysis.h): their values h on the speeds and f
 * of the holonomic ones (dyn_constraint_values), and the gradient G = df/dq of the
 * holonomic ones by central differences of f in the coordinates (dyn_holonomic_gradient),
 * each step a power of two near eps^(1/3) of the coordinate's scale and the increments
 * actually taken used as the divisor (Nocedal & Wright, Numerical Optimization, 2nd ed.,
 * sec. 8.1: an error of about 1e-11). Used by dyn_project_constraints and by the
 * linearization's admissible directions (dynkit linearize). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/analysis.h"

static int unit_is(const dyn_var *v, const char *u) { return v->unit && strcmp(v->unit, u) == 0; }

int dyn_constraint_values(const dyn_model *cm, const void *par, double t, const double *y,
                          double *h, double *f, int *holonomic)
{
    double *out = malloc((size_t)(cm->n_outputs + 1) * sizeof *out);
    if (!out || !cm->compute_outputs || cm->compute_outputs(t, y, par, out)) {
        free(out);
        return -1;
    }
    int m = 0, nf = 0;
    for (int i = 0; i < cm->n_outputs; i++) {
        const dyn_var *v = &cm->outputs[i];
        if (unit_is(v, "holonomic") || unit_is(v, "speeds")) {
            holonomic[m] = unit_is(v, "holonomic");
            f[m] = 0.0;
            h[m++] = out[i];
        }
    }
    for (int i = 0; i < cm->n_outputs; i++) {
        const dyn_var *v = &cm->outputs[i];
        if (unit_is(v, "position") || unit_is(v, "prescribed")) {
            while (nf < m && !holonomic[nf])
                nf++;
            if (nf < m)
                f[nf++] = out[i];
        }
    }
    free(out);
    return m;
}

/* a power of two near eps^(1/3) of the scale of x */
static double step_of(double x) { return ldexp(1.0, (int)floor(log2(6e-6 * fmax(1.0, fabs(x))))); }

int dyn_holonomic_gradient(const dyn_model *cm, const void *par, double t, const double *y,
                           double *G, double *Dh)
{
    const int N = cm->n_states, n = N / 2;
    const size_t mo = (size_t)cm->n_outputs + 1;
    double *buf = malloc((4 * mo + (size_t)N) * sizeof *buf);
    int *hol = malloc(mo * sizeof *hol);
    if (!buf || !hol || N % 2) {
        free(buf);
        free(hol);
        return -1;
    }
    double *h = buf, *f = h + mo, *hp = f + mo, *fp = hp + mo, *yy = fp + mo;
    memcpy(yy, y, (size_t)N * sizeof *yy);
    int m = dyn_constraint_values(cm, par, t, y, h, f, hol);
    for (int k = 0; k < (Dh ? N : n) && m >= 0; k++) {
        const double step = step_of(y[k]);
        yy[k] = y[k] + step;
        const double up = yy[k] - y[k];
        if (dyn_constraint_values(cm, par, t, yy, hp, fp, hol) != m)
            m = -1;
        yy[k] = y[k] - step;
        const double down = y[k] - yy[k];
        if (m >= 0 && dyn_constraint_values(cm, par, t, yy, h, f, hol) != m)
            m = -1;
        yy[k] = y[k];
        for (int r = 0; r < m; r++) {
            if (k < n)
                G[r * n + k] = hol[r] ? (fp[r] - f[r]) / (up + down) : 0.0;
            if (Dh)
                Dh[r * N + k] = (hp[r] - h[r]) / (up + down);
        }
    }
    free(buf);
    free(hol);
    return m;
}
