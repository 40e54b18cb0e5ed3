/* SPDX-License-Identifier: BSD-3-Clause */
/* dyn_homework_studies: the report's three studies of many runs (report_studies.h), timed by
 * the wall clock (they run on several threads). */
#define _POSIX_C_SOURCE 200809L
#include <string.h>
#include <time.h>

#include "dynkit/report_studies.h"
#include "dynkit/sweep.h"

int dyn_homework_studies(dyn_homework *hw, int threads, char *err, size_t errlen)
{
    dyn_hw_studies *s = &hw->studies;
    struct timespec a, b;
    clock_gettime(CLOCK_MONOTONIC, &a);
    memset(s, 0, sizeof *s);
    int rc = dyn_study_period_compute(&s->period, threads, err, errlen);
    rc = rc ? rc : dyn_study_plane_compute(&s->plane, threads, err, errlen);
    rc = rc ? rc : dyn_study_cart_compute(&s->cart, threads, err, errlen);
    clock_gettime(CLOCK_MONOTONIC, &b);
    s->wall_seconds = (double)(b.tv_sec - a.tv_sec) + 1e-9 * (double)(b.tv_nsec - a.tv_nsec);
    s->threads = dyn_sweep_threads(threads);
    s->runs = s->period.n + 2 * s->plane.n_runs + (long)s->cart.n_v0 * s->cart.n_f;
    s->computed = rc == 0;
    return rc;
}
