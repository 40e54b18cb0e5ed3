/* Fixed-step driver: the homework's Integrate_X loop, streaming samples to a callback.
 *
 * Follows [tout,yout] = Integrate_ModifiedEuler(odefun, tspan, Ts, y0, par) of the
 * homework (H. Vallery, TU Delft 2014) with two differences, both deliberate: the step
 * after the last sample is never computed (the homework's loop computes and discards it),
 * and a span that is not a whole number of steps is handled by the end policy (grid.c).
 * Each new state is checked for NaN/Inf; on any failure y keeps the last good state.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dynkit/ode.h"
#include "ode/rk_stages.h"

static void result_init(dyn_result *res, double t0)
{
    memset(res, 0, sizeof *res);
    res->t = t0;
    res->fail_t = NAN;
    res->fail_index = -1;
}

static int result_fail(dyn_result *res, int status, const char *fmt, double a, double b)
{
    res->status = status;
    snprintf(res->message, sizeof res->message, fmt, a, b);
    return status;
}

static int first_nonfinite(const double *y, int n)
{
    for (int q = 0; q < n; q++)
        if (!isfinite(y[q]))
            return q;
    return -1;
}

static int check_args(const dyn_tableau *m, const dyn_system *sys, const double *y0,
                      const double *work, dyn_result *res)
{
    if (!m)
        return result_fail(res, DYN_ERR_ARG, "no method given%.0s%.0s", 0, 0);
    if (m->kind != DYN_KIND_EXPLICIT_RK)
        return result_fail(res, DYN_ERR_ARG,
                           "this method is not a fixed-step explicit Runge-Kutta method%.0s%.0s",
                           0, 0);
    if (!sys || !sys->f)
        return result_fail(res, DYN_ERR_ARG, "no right-hand side given%.0s%.0s", 0, 0);
    if (sys->n <= 0)
        return result_fail(res, DYN_ERR_ARG,
                           "number of states %.0f is not accepted: it must be >= 1%.0s",
                           (double)sys->n, 0);
    if (!y0 || !work)
        return result_fail(res, DYN_ERR_ARG, "initial state or workspace is NULL%.0s%.0s", 0,
                           0);
    return DYN_OK;
}

int dyn_fixed_solve(const dyn_tableau *m, const dyn_system *sys, double t0, double t1,
                    double h, const double *y0, double *y, double *work,
                    const dyn_fixed_opts *opts, dyn_result *res)
{
    static const dyn_fixed_opts no_opts;
    dyn_result local;
    if (!res)
        res = &local;
    if (!opts)
        opts = &no_opts;
    result_init(res, t0);
    if (check_args(m, sys, y0, work, res))
        return res->status;

    dyn_grid grid;
    if (dyn_grid_plan(t0, t1, h, opts->end, &grid, res->message, sizeof res->message)) {
        res->status = DYN_ERR_ARG;
        return res->status;
    }
    const int n = sys->n, s = m->stages;
    const dyn_rhs_fn f = sys->f;
    void *const par = sys->par;
    double *k = work, *Y = work + (size_t)s * (size_t)n, *spare = Y + n;
    if (!y)
        y = spare + n; /* the caller wants samples only: keep the state in the workspace */
    const long every = opts->every > 1 ? opts->every : 1;
    const long steps = grid.samples - 1;

    if (y != y0)
        memmove(y, y0, (size_t)n * sizeof *y);
    int bad = first_nonfinite(y, n);
    if (bad >= 0) {
        res->fail_t = t0;
        res->fail_index = bad;
        return result_fail(res, DYN_ERR_NONFINITE,
                           "initial state %.0f is not finite (%g)", (double)bad, y[bad]);
    }
    if (opts->output) {
        if (opts->output(0, t0, y, opts->output_ctx))
            return result_fail(res, DYN_STOPPED, "output stopped the run at t = %g%.0s", t0, 0);
        res->stats.samples = 1;
    }

    double *cur = y, *nxt = spare;
    long countdown = every;
    const long progress_every = opts->progress_steps > 0 ? opts->progress_steps : 65536;
    long progress_countdown = progress_every;
    int status = DYN_OK;
    for (long step = 0; step < steps; step++) {
        const double tn = dyn_grid_time(&grid, step);
        const double hn = step < grid.whole_steps ? h : t1 - tn;
        int fail_stage = 0, rc;
        if (opts->trace && step < opts->trace_steps)
            rc = dyn_rk_stages(m, f, par, n, tn, hn, cur, nxt, k, Y, &fail_stage, opts->trace,
                               opts->trace_ctx, step);
        else
            rc = dyn_rk_stages(m, f, par, n, tn, hn, cur, nxt, k, Y, &fail_stage, NULL, NULL,
                               step);
        if (rc) {
            res->stats.rhs_calls += fail_stage + 1;
            res->rhs_status = rc;
            res->fail_t = tn + m->c[fail_stage] * hn;
            status = result_fail(res, DYN_ERR_RHS,
                                 "the right-hand side failed at t = %.17g (status %.0f)",
                                 res->fail_t, (double)rc);
            break;
        }
        res->stats.rhs_calls += s;
        res->stats.steps++;
        const double tnext = dyn_grid_time(&grid, step + 1);
        if (!opts->no_finite_check && (bad = first_nonfinite(nxt, n)) >= 0) {
            res->fail_t = tnext;
            res->fail_index = bad;
            status = result_fail(res, DYN_ERR_NONFINITE,
                                 "state %.0f became not finite at t = %.17g", (double)bad,
                                 tnext);
            break;
        }
        double *swap = cur;
        cur = nxt;
        nxt = swap;
        res->t = tnext;
        if (opts->output && (--countdown == 0 || step + 1 == steps)) {
            countdown = every;
            res->stats.samples++;
            if (opts->output(step + 1, tnext, cur, opts->output_ctx)) {
                status = result_fail(res, DYN_STOPPED, "output stopped the run at t = %g%.0s",
                                     tnext, 0);
                break;
            }
        }
        if (opts->progress && --progress_countdown == 0) {
            progress_countdown = progress_every;
            if (opts->progress(tnext, (double)(step + 1) / (double)steps, opts->progress_ctx)) {
                status = result_fail(res, DYN_CANCELLED, "cancelled at t = %g%.0s", tnext, 0);
                break;
            }
        }
    }
    if (cur != y)
        memcpy(y, cur, (size_t)n * sizeof *y);
    res->status = status;
    return status;
}
