/* SPDX-License-Identifier: BSD-3-Clause */
/* The steps of a discrete map (DYN_KIND_MAP, method "discrete") for dyn_fixed_solve:
 * y_{k+1} = f(t_k, y_k) on the sample grid t_k = t0 + k h, as XPPAUT iterates difference
 * equations (x(t+1)=..., or x'=... with meth=discrete; XPPAUT's manual, "Difference
 * equations"). The right-hand side writes the next state itself; nothing is combined, so
 * the iterates are f's values bit for bit. The contract is dyn_fixed_solve's: samples
 * every opts->every steps and at the end, progress, trace, the NaN/Inf check, counters,
 * and on failure y keeps the last good state. A map takes whole steps only (dyn_fixed_solve
 * refuses a span with a partial last step).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dynkit/io.h" /* dyn_shortest: numbers in messages */
#include "ode/map_steps.h"
#include "ode/result_fail.h"

static void trace_step(const dyn_fixed_opts *o, const dyn_tableau *m, long step, int n,
                       double t, double h, double tnext, const double *y, const double *ynew)
{
    dyn_trace_stage st = {.method = m, .step = step, .stage = 0, .t_n = t, .h = h,
                          .t_stage = t, .n = n, .y_n = y, .Y = y, .k = ynew};
    o->trace(&st, o->trace_ctx);
    st.stage = 1; /* the step's result: the new state in Y */
    st.t_stage = tnext;
    st.Y = ynew;
    st.k = NULL;
    o->trace(&st, o->trace_ctx);
}

int dyn_map_steps(const dyn_tableau *m, const dyn_system *sys, const dyn_grid *g, double *y,
                  double *spare, const dyn_fixed_opts *o, dyn_result *res)
{
    const int n = sys->n;
    const long steps = g->whole_steps, every = o->every > 1 ? o->every : 1;
    const long progress_every = o->progress_steps > 0 ? o->progress_steps : 65536;
    double *cur = y, *nxt = spare;
    long countdown = every, progress_countdown = progress_every, step = 0;
    int status = DYN_OK;
    double t_reached = g->t0;
    for (; step < steps; step++) {
        const double tn = g->t0 + (double)step * g->h;
        const double tnext = (g->ends_at_t1 && step + 1 == steps)
                                 ? g->t1
                                 : g->t0 + (double)(step + 1) * g->h;
        const int rc = sys->f(tn, cur, nxt, sys->par);
        if (rc) {
            res->rhs_status = rc;
            res->fail_t = tn;
            res->stats.rhs_calls = step + 1;
            status = dyn_result_fail(res, DYN_ERR_RHS, "the map failed at t = %s (status %d)",
                                     dyn_shortest(tn).s, rc);
            break;
        }
        if (o->trace && step < o->trace_steps)
            trace_step(o, m, step, n, tn, g->h, tnext, cur, nxt);
        if (!o->no_finite_check)
            for (int q = 0; q < n; q++)
                if (!isfinite(nxt[q])) {
                    res->stats.rhs_calls = step + 1;
                    res->fail_t = tnext;
                    res->fail_index = q;
                    status = dyn_result_fail(res, DYN_ERR_NONFINITE,
                                             "state %d became not finite at t = %s", q,
                                             dyn_shortest(tnext).s);
                    break;
                }
        if (status)
            break;
        double *swap = cur;
        cur = nxt;
        nxt = swap;
        t_reached = tnext;
        if (o->output && (--countdown == 0 || step + 1 == steps)) {
            countdown = every;
            res->stats.samples++;
            if (o->output(step + 1, tnext, cur, o->output_ctx)) {
                step++;
                status =
                    dyn_result_fail(res, DYN_STOPPED, "output stopped the run at t = %g", tnext);
                break;
            }
        }
        if (o->progress && --progress_countdown == 0) {
            progress_countdown = progress_every;
            if (o->progress(tnext, (double)(step + 1) / (double)steps, o->progress_ctx)) {
                step++;
                status = dyn_result_fail(res, DYN_CANCELLED, "cancelled at t = %g", tnext);
                break;
            }
        }
    }
    res->stats.steps = res->stats.accepted = step;
    if (status != DYN_ERR_RHS && status != DYN_ERR_NONFINITE)
        res->stats.rhs_calls = step;
    res->t = t_reached;
    if (cur != y)
        memcpy(y, cur, (size_t)n * sizeof *y);
    res->status = status;
    return status;
}
