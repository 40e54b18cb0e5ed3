/* SPDX-License-Identifier: BSD-3-Clause */
/* The sample grid of fixed-step runs: t_k = t0 + k*h, computed, never accumulated.
 *
 * A span is a whole number of steps when (t1 - t0)/h is within 1e-10 (relative; at most
 * 1e-3 steps, so spans of billions of steps are not rounded to whole ones) of an
 * integer N; the grid then has exactly N + 1 samples, the homework's
 * tout = (tspan(1):Ts:tspan(end))', and the last one is reported as t1 itself (as MATLAB's
 * colon operator does) rather than t0 + N*h, which can differ from t1 in the last
 * bit. Otherwise DYN_END_EXACT adds one shorter step that lands on t1, and DYN_END_GRID stops at the last whole step (MATLAB's colon operator).
 * A span shorter than one step (however much shorter: h = 1e300 over [0, 1]) is one step
 * to t1 with DYN_END_EXACT (and no step with DYN_END_GRID, as MATLAB's 0:2:1 is 0).
 */
#include <math.h>
#include <stdio.h>

#include "dynkit/io.h" /* dyn_shortest */
#include "dynkit/ode.h"

/* Largest number of steps: k*h stays exact in the index and fits a long everywhere. */
#define MAX_STEPS 9007199254740992.0 /* 2^53 */

#if defined(__GNUC__)
__attribute__((format(printf, 3, 0)))
#endif
static int fail(char *err, size_t errlen, const char *msg, double value)
{
    if (err && errlen)
        snprintf(err, errlen, msg, value);
    return DYN_ERR_ARG;
}

int dyn_grid_plan(double t0, double t1, double h, dyn_end_policy end, dyn_grid *grid,
                  char *err, size_t errlen)
{
    if (!grid)
        return fail(err, errlen, "no grid to fill%.0f", 0.0);
    if (!isfinite(t0))
        return fail(err, errlen, "start time t0 = %g is not finite", t0);
    if (!isfinite(t1))
        return fail(err, errlen, "end time t1 = %g is not finite", t1);
    if (!(t1 >= t0))
        return fail(err, errlen, "end time must not be before the start time (t1 - t0 = %g)",
                    t1 - t0);
    if (!(h > 0.0) || !isfinite(h))
        return fail(err, errlen, "step %g is not accepted: it must be a finite number > 0", h);
    if (end != DYN_END_EXACT && end != DYN_END_GRID)
        return fail(err, errlen, "unknown end policy %g (accepted: exact, grid)", (double)end);

    double ratio = (t1 - t0) / h;
    if (!(ratio < MAX_STEPS))
        return fail(err, errlen, "step is too small for the span: %.3g steps (at most 2^53)",
                    ratio);
    double nearest = nearbyint(ratio);
    grid->t0 = t0;
    grid->t1 = t1;
    grid->h = h;
    /* rounding in (t1 - t0)/h is a few ulps of the ratio; never call a span whole that is
     * more than 1e-3 steps away from it, and never call a span shorter than a step (however
     * much shorter) zero whole steps: it is one shorter step to t1 (exact) */
    if (fabs(ratio - nearest) <= fmin(1e-10 * fmax(1.0, nearest), 1e-3) &&
        (nearest >= 1.0 || t1 == t0)) {
        grid->whole_steps = (long)nearest;
        grid->partial = 0;
        grid->ends_at_t1 = 1;
    } else {
        grid->whole_steps = (long)floor(ratio);
        grid->partial = (end == DYN_END_EXACT);
        grid->ends_at_t1 = grid->partial;
    }
    grid->samples = grid->whole_steps + grid->partial + 1;
    return DYN_OK;
}

int dyn_grid_check_steps(const dyn_grid *grid, long max_steps, char *err, size_t errlen)
{
    const long steps = grid->samples - 1;
    if (max_steps <= 0 || steps <= max_steps)
        return DYN_OK;
    if (err && errlen)
        snprintf(err, errlen,
                 "%ld steps of h = %g from t = %s to %s are more than the limit of %ld steps: "
                 "raise the limit, or take a longer step",
                 steps, grid->h, dyn_shortest(grid->t0).s, dyn_shortest(grid->t1).s, max_steps);
    return DYN_ERR_MAX_STEPS;
}

double dyn_grid_time(const dyn_grid *grid, long k)
{
    if (grid->ends_at_t1 && k == grid->samples - 1)
        return grid->t1; /* t0 + N*h within rounding when whole; the partial step's end */
    return grid->t0 + (double)k * grid->h;
}
