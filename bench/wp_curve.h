/* SPDX-License-Identifier: BSD-3-Clause */
/* bench/wp_curve.h — a work-precision curve of one solver (error and time per tolerance) and
 * the time at a given error read off it, shared by the benchmarks of large stiff systems
 * (bench_band.c, bench_sparse.c). */
#ifndef DYNKIT_BENCH_WP_CURVE_H
#define DYNKIT_BENCH_WP_CURVE_H

#include <math.h>

#define MAX_TOL 9

static inline double max_err(const double *y, const double *ref, int n)
{
    double e = 0.0;
    for (int i = 0; i < n; i++)
        e = fmax(e, fabs(y[i] - ref[i]));
    return e;
}

/* One work-precision curve. */
typedef struct curve {
    int k;
    double err[MAX_TOL], time[MAX_TOL];
    long steps[MAX_TOL];
} curve;

/* The time at error e read off the curve: on its lower envelope (the points that no other
 * point beats in both error and time, sorted by error), linear in log(time) against
 * log(error) between the two envelope points whose errors bracket e; NAN when e is outside
 * the range of the envelope. (An error that does not fall with the tolerance, as CVODE's
 * sometimes does, thus never makes a solver look slower than a run it actually did.) */
static inline double time_at(const curve *c, double e)
{
    double ee[MAX_TOL], tt[MAX_TOL];
    int k = 0;
    for (int i = 0; i < c->k; i++) {
        int beaten = !(c->err[i] > 0.0);
        for (int j = 0; j < c->k && !beaten; j++)
            beaten = j != i && c->err[j] <= c->err[i] && c->time[j] <= c->time[i] &&
                     (c->err[j] < c->err[i] || c->time[j] < c->time[i]);
        if (!beaten) {
            int at = k++;
            while (at > 0 && ee[at - 1] < c->err[i]) { /* by decreasing error */
                ee[at] = ee[at - 1];
                tt[at] = tt[at - 1];
                at--;
            }
            ee[at] = c->err[i];
            tt[at] = c->time[i];
        }
    }
    for (int i = 0; i + 1 < k; i++)
        if (e <= ee[i] && e >= ee[i + 1]) {
            const double s = (log(e) - log(ee[i])) / (log(ee[i + 1]) - log(ee[i]));
            return exp(log(tt[i]) + s * (log(tt[i + 1]) - log(tt[i])));
        }
    return k == 1 && e == ee[0] ? tt[0] : NAN;
}

#endif /* DYNKIT_BENCH_WP_CURVE_H */
