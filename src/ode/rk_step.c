/* SPDX-License-Identifier: BSD-3-Clause */
/* One explicit Runge–Kutta step through the shared stage loop (rk_stages.h), and the
 * workspace size of the fixed-step driver. */
#include <math.h>
#include <string.h>

#include "dynkit/ode.h"
#include "ode/rk_stages.h"

size_t dyn_fixed_work_size(const dyn_tableau *m, int n)
{
    if (!m || n <= 0)
        return 0;
    return DYN_RK_WORK(m->stages, n);
}

int dyn_rk_step(const dyn_tableau *m, const dyn_system *sys, double t, double h,
                const double *y0, double *y1, double *work, long *rhs_calls)
{
    const int n = sys->n;
    double *k = work, *Y = work + (size_t)m->stages * (size_t)n, *ynew = Y + n;
    int fail_stage = 0, rc;
    double finite; /* not used: dyn_rk_step does not check the state */
    dyn_rk_plan plan;
    if (dyn_rk_plan_init(&plan, m, k, n))
        rc = dyn_rk_stages(m, &plan, sys->f, sys->par, n, t, h, HUGE_VAL, y0, ynew, k, Y,
                           &fail_stage, &finite, NULL, NULL, 0);
    else
        rc = dyn_rk_stages_scan(m, sys->f, sys->par, n, t, h, HUGE_VAL, y0, ynew, k, Y,
                                &fail_stage, &finite, NULL, NULL, 0);
    if (rhs_calls)
        *rhs_calls += rc ? fail_stage + 1 : m->stages;
    if (!rc)
        memcpy(y1, ynew, (size_t)n * sizeof *y1);
    return rc;
}
