/* SPDX-License-Identifier: BSD-3-Clause */
/* The report's study of problem 3: how fragile the Euler answer is. Euler and RK4 at the
 * homework's step over its end time, each through dyn_sweep, from the same 1,000 starts:
 * every non-zero initial state x_j changed to x_j (1 + 1e-14 z), z standard normal, drawn by
 * Philox4x32-10 with a fixed seed (dyn_sweep_sample: the same starts on any number of
 * threads). Per start, the distance between the final centres of mass and the principal
 * angle between the final orientations (as the report's answer); their mean, extremes and
 * percentiles (linear between order statistics, numpy's default) over the runs that
 * finished. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/plane.h"
#include "dynkit/report_studies.h"
#include "dynkit/sweep.h"
#include "report/hw_common.h"

static const double percent[DYN_STUDY_PERCENTILES] = {5, 25, 50, 75, 95};

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Mean, extremes and percentiles of the finite values of v (n), sorted into scratch. */
static void summarise(const double *v, long n, double *scratch, double *mean, double *min,
                      double *max, double *pct)
{
    long k = 0;
    double sum = 0.0;
    for (long i = 0; i < n; i++)
        if (isfinite(v[i])) {
            scratch[k++] = v[i];
            sum += v[i];
        }
    *mean = *min = *max = NAN;
    for (int q = 0; q < DYN_STUDY_PERCENTILES; q++)
        pct[q] = NAN;
    if (k == 0)
        return;
    qsort(scratch, (size_t)k, sizeof *scratch, cmp_double);
    *mean = sum / (double)k;
    *min = scratch[0];
    *max = scratch[k - 1];
    for (int q = 0; q < DYN_STUDY_PERCENTILES; q++) {
        const double pos = percent[q] / 100.0 * (double)(k - 1);
        const long lo = (long)floor(pos);
        const long hi = lo + 1 < k ? lo + 1 : lo;
        pct[q] = scratch[lo] + (pos - (double)lo) * (scratch[hi] - scratch[lo]);
    }
}

int dyn_study_plane_compute(dyn_study_plane *s, int threads, char *err, size_t errlen)
{
    const dyn_model *m = &dyn_model_plane;
    const long n = DYN_STUDY_PLANE_RUNS;
    dyn_plane_par p;
    double y0[12];
    memset(s, 0, sizeof *s);
    if (dyn_model_default_params(m, &p, err, errlen))
        return 1;
    dyn_model_initial_state(m, &p, y0);
    s->n_runs = n;
    s->seed = 1;
    s->perturbation = 1e-14;
    dyn_sweep_var vars[12];
    dyn_dist dists[12];
    for (int j = 0; j < 12; j++)
        if (y0[j] != 0.0) {
            vars[s->n_changed] = (dyn_sweep_var){DYN_SWEEP_STATE, j};
            dists[s->n_changed] = (dyn_dist){DYN_DIST_NORMAL, y0[j], fabs(y0[j]) * s->perturbation};
            s->n_changed++;
        }
    dyn_reduce red[12];
    int n_red = 0;
    if (dyn_reduce_parse(m, "final", red, 12, &n_red, err, errlen))
        return 1;
    const int nc = s->n_changed;
    double *values = malloc((size_t)n * (size_t)(nc > 0 ? nc : 1) * sizeof *values);
    double *euler = malloc((size_t)n * 12 * sizeof *euler);
    double *rk4 = malloc((size_t)n * 12 * sizeof *rk4);
    int *status = malloc((size_t)n * 2 * sizeof *status);
    int rc = values && euler && rk4 && status ? 0 : DYN_ERR_CAPACITY;
    if (rc == 0) {
        dyn_sweep_sample(dists, nc, s->seed, 0, n, values);
        dyn_sweep sw = {0};
        sw.model = m;
        sw.par = &p;
        sw.y0 = y0;
        sw.n_vars = nc, sw.vars = vars, sw.n_runs = n, sw.values = values;
        sw.t0 = 0.0, sw.t1 = m->t1, sw.step = m->step;
        sw.n_reduce = n_red, sw.reduce = red;
        sw.threads = threads;
        sw.method = dyn_method_find("euler");
        rc = dyn_sweep_run(&sw, euler, status, err, errlen);
        sw.method = dyn_method_find("rk4");
        rc = rc ? rc : dyn_sweep_run(&sw, rk4, status + n, err, errlen);
    }
    for (long i = 0; i < n && rc == 0; i++) {
        s->distance_m[i] = s->angle_rad[i] = NAN;
        if (status[i] != DYN_OK || status[n + i] != DYN_OK) {
            s->n_failed++;
            continue;
        }
        hw_plane_compare(euler + 12 * i, rk4 + 12 * i, &s->distance_m[i], &s->angle_rad[i]);
    }
    if (rc == 0) { /* euler's memory is free for sorting now */
        summarise(s->distance_m, n, euler, &s->distance_mean, &s->distance_min, &s->distance_max,
                  s->distance_pct);
        summarise(s->angle_rad, n, euler, &s->angle_mean, &s->angle_min, &s->angle_max,
                  s->angle_pct);
    }
    if (rc == DYN_ERR_CAPACITY && err && errlen)
        snprintf(err, errlen, "out of memory for the plane's %ld runs", n);
    free(values);
    free(euler);
    free(rk4);
    free(status);
    return rc;
}
