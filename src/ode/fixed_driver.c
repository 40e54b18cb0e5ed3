/* SPDX-License-Identifier: BSD-3-Clause */
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

#include "dynkit/io.h" /* dyn_shortest: numbers in messages */
#include "dynkit/ode.h"
#include "ode/map_steps.h"
#include "ode/result_fail.h"
#include "ode/rk_stages.h"

static void result_init(dyn_result *res, double t0)
{
    memset(res, 0, sizeof *res);
    res->t = t0;
    res->fail_t = NAN;
    res->fail_index = -1;
}

static int first_nonfinite(const double *y, int n)
{
    for (int q = 0; q < n; q++)
        if (!isfinite(y[q]))
            return q;
    return -1;
}

/* The plain steps of the common tables' shapes (dyn_inl_euler_rows ... in
 * dynkit/ode_inline.h) by dyn_fixed_solve_inline's step, the summaries rows a constant at each
 * call: the same arithmetic as the plan's (its contract, tests/test_fixed_inline.c), in about
 * two thirds of the instructions (83 against 124 per Euler step on van der Pol besides the
 * right-hand side's 12; the pointer floor takes 17; timings in docs/performance.md). The
 * same contract as plain_steps below. */
DYN_RK_INLINE long plain_steps_known(const int S, const dyn_inl_row *rows, const dyn_tableau *m,
                                     dyn_rhs_fn f, void *par, int n, double t0, double h,
                                     double t1, long step, long count, int finite_check,
                                     double **cur, double **nxt, double *k, double *Y, int *rc,
                                     int *fail_stage, int *nonfinite)
{
    double *a = *cur, *b = *nxt;
    long i = 0;
    for (; i < count; i++) {
        const double tn = t0 + (double)(step + i) * h;
        int stage = 0, bad = 0;
        const int r =
            dyn_inl_step(S, m, rows, f, par, n, tn, h, t1, a, b, k, Y, &stage, &bad, finite_check);
        if (r) {
            *rc = r;
            *fail_stage = stage;
            break;
        }
        if (bad) {
            *nonfinite = 1;
            break;
        }
        double *swap = a;
        a = b;
        b = swap;
    }
    *cur = a;
    *nxt = b;
    return i;
}

/* The common shape m has (dyn_inl_euler_rows ... themselves, which plain_steps tells
 * apart), or NULL for any other table (the plan's loop). */
static const dyn_inl_row *known_shape(const dyn_tableau *m)
{
    static const struct {
        int stages;
        const dyn_inl_row *rows;
    } known[] = {{1, dyn_inl_euler_rows},      {2, dyn_inl_heun_rows},
                 {2, dyn_inl_heun_shape_rows}, {2, dyn_inl_midpoint_rows},
                 {4, dyn_inl_rk4_rows}};
    const int S = m->stages;
    if (S < 1 || S > 4)
        return NULL;
    dyn_inl_row rows[5];
    dyn_inl_rows_of(m, S, rows);
    for (size_t i = 0; i < sizeof known / sizeof known[0]; i++)
        if (S == known[i].stages && dyn_inl_rows_equal(rows, known[i].rows, S + 1))
            return known[i].rows;
    return NULL;
}

/* Whole steps step, step+1, ... (count of them, count >= 1) of size h with the plan p (or,
 * for a common shape, known_shape's rows), without trace or callbacks: the hot loop. *cur
 * holds the state and is advanced; *nxt is the spare state. Stops at a step whose right-hand
 * side fails (*rc != 0, *fail_stage) or, with finite_check, whose new state (left in *nxt) is
 * not finite (*nonfinite = 1); that step is not counted. Returns the number of steps
 * completed. */
static long plain_steps(const dyn_inl_row *shape, const dyn_tableau *m, const dyn_rk_plan *p,
                        dyn_rhs_fn f, void *par, int n, double t0, double h, double t1, long step,
                        long count, int finite_check, double **cur, double **nxt, double *k,
                        double *Y, int *rc, int *fail_stage, int *nonfinite)
{
#define KNOWN(S, rows)                                                                             \
    plain_steps_known(S, rows, m, f, par, n, t0, h, t1, step, count, finite_check, cur, nxt, k, \
                      Y, rc, fail_stage, nonfinite)
    if (shape == dyn_inl_euler_rows)
        return KNOWN(1, dyn_inl_euler_rows);
    if (shape == dyn_inl_heun_rows)
        return KNOWN(2, dyn_inl_heun_rows);
    if (shape == dyn_inl_heun_shape_rows)
        return KNOWN(2, dyn_inl_heun_shape_rows);
    if (shape == dyn_inl_midpoint_rows)
        return KNOWN(2, dyn_inl_midpoint_rows);
    if (shape == dyn_inl_rk4_rows)
        return KNOWN(4, dyn_inl_rk4_rows);
#undef KNOWN
    double *a = *cur, *b = *nxt;
    long i = 0;
    for (; i < count; i++) {
        const double tn = t0 + (double)(step + i) * h;
        double finite;
        const int r = dyn_rk_stages(m, p, f, par, n, tn, h, t1, a, b, k, Y, fail_stage, &finite,
                                    NULL, NULL, 0);
        if (r) {
            *rc = r;
            break;
        }
        if (finite_check && finite != 0.0) {
            *nonfinite = 1;
            break;
        }
        double *swap = a;
        a = b;
        b = swap;
    }
    *cur = a;
    *nxt = b;
    return i;
}

static int check_args(const dyn_tableau *m, const dyn_system *sys, const double *y0,
                      const double *work, dyn_result *res)
{
    if (!m)
        return dyn_result_fail(res, DYN_ERR_ARG, "no method given");
    if (m->kind != DYN_KIND_EXPLICIT_RK && m->kind != DYN_KIND_MAP)
        return dyn_result_fail(res, DYN_ERR_ARG,
                               "%s is not a fixed-step method (dyn_solve runs it)", m->name);
    if (!sys || !sys->f)
        return dyn_result_fail(res, DYN_ERR_ARG, "no right-hand side given");
    if (sys->n <= 0)
        return dyn_result_fail(res, DYN_ERR_ARG,
                               "number of states %d is not accepted: it must be >= 1", sys->n);
    if (!y0 || !work)
        return dyn_result_fail(res, DYN_ERR_ARG, "initial state or workspace is NULL");
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
    if (m->kind == DYN_KIND_MAP && grid.partial)
        return dyn_result_fail(res, DYN_ERR_ARG,
                               "a discrete map takes whole steps: [%s, %s] is not a whole number "
                               "of steps of %s (give a span of whole steps, or DYN_END_GRID)",
                               dyn_shortest(t0).s, dyn_shortest(t1).s, dyn_shortest(h).s);
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
        return dyn_result_fail(res, DYN_ERR_NONFINITE, "initial state %d is not finite (%g)", bad,
                               y[bad]);
    }
    if ((res->status = dyn_grid_check_steps(&grid, opts->max_steps, res->message,
                                            sizeof res->message)) != DYN_OK)
        return res->status;
    if (opts->output) {
        if (opts->output(0, t0, y, opts->output_ctx))
            return dyn_result_fail(res, DYN_STOPPED, "output stopped the run at t = %g", t0);
        res->stats.samples = 1;
    }
    if (m->kind == DYN_KIND_MAP)
        return dyn_map_steps(m, sys, &grid, y, spare, opts, res);

    /* Everything the step loop reads is hoisted into locals: the loop then keeps no state
     * in *res or *opts (which the compiler would have to reload after every call of f). */
    dyn_rk_plan plan;
    const int planned = dyn_rk_plan_init(&plan, m, k, n);
    const dyn_inl_row *const shape = known_shape(m);
    const dyn_output_fn output = opts->output;
    void *const output_ctx = opts->output_ctx;
    const dyn_trace_fn trace = opts->trace;
    void *const trace_ctx = opts->trace_ctx;
    const long trace_steps = trace ? opts->trace_steps : 0;
    const int finite_check = !opts->no_finite_check;
    const dyn_progress_fn progress = opts->progress;
    void *const progress_ctx = opts->progress_ctx;
    const long progress_every = opts->progress_steps > 0 ? opts->progress_steps : 65536;
    const long whole_steps = grid.whole_steps;
    const int last_is_t1 = grid.ends_at_t1;

    double *cur = y, *nxt = spare;
    long countdown = every, progress_countdown = progress_every;
    long done = 0, samples = res->stats.samples;
    double t_reached = t0;
    int status = DYN_OK;
    long step = 0;
    while (step < steps) {
        int fail_stage = 0, rc = 0, nonfinite = 0;
        /* A run of plain steps: whole steps, no trace, and no callback due before its end. */
        long run = planned && step >= trace_steps ? whole_steps - step : 0;
        if (output && run > countdown - 1)
            run = countdown - 1;
        if (output && run > steps - 1 - step)
            run = steps - 1 - step; /* the last sample is always output */
        if (progress && run > progress_countdown - 1)
            run = progress_countdown - 1;
        if (run > 0) {
            const long got = plain_steps(shape, m, &plan, f, par, n, t0, h, t1, step, run,
                                         finite_check, &cur, &nxt, k, Y, &rc, &fail_stage,
                                         &nonfinite);
            done += got;
            step += got;
            countdown -= got;
            progress_countdown -= got;
            if (got > 0)
                t_reached = t0 + (double)step * h; /* step < steps: never the last sample */
            if (!rc && !nonfinite)
                continue;
        } else {
            /* One step with everything: trace, a partial last step, callbacks. */
            const double tn = t0 + (double)step * h;
            const double hn = step < whole_steps ? h : t1 - tn;
            double finite = 0.0;
            if (!planned)
                rc = dyn_rk_stages_scan(m, f, par, n, tn, hn, t1, cur, nxt, k, Y, &fail_stage,
                                        &finite, step < trace_steps ? trace : NULL, trace_ctx,
                                        step);
            else
                rc = dyn_rk_stages(m, &plan, f, par, n, tn, hn, t1, cur, nxt, k, Y, &fail_stage,
                                   &finite, step < trace_steps ? trace : NULL, trace_ctx, step);
            nonfinite = !rc && finite_check && finite != 0.0;
        }
        /* t_k = t0 + k*h as dyn_grid_time computes it: the last sample is t1 itself when
         * the grid ends there (a step never starts at the last sample). */
        const double tn = t0 + (double)step * h;
        const double hn = step < whole_steps ? h : t1 - tn;
        if (rc) {
            res->stats.rhs_calls = done * s + fail_stage + 1;
            res->rhs_status = rc;
            res->fail_t = dyn_rk_stage_time(tn, m->c[fail_stage], hn, t1);
            status = dyn_result_fail(res, DYN_ERR_RHS,
                                     "the right-hand side failed at t = %s (status %d)",
                                     dyn_shortest(res->fail_t).s, rc);
            break;
        }
        const double tnext =
            (last_is_t1 && step + 1 == steps) ? t1 : t0 + (double)(step + 1) * h;
        if (nonfinite && (bad = first_nonfinite(nxt, n)) >= 0) {
            /* the step was taken (its evaluations count) but its result is not kept */
            res->stats.rhs_calls = (done + 1) * s;
            res->fail_t = tnext;
            res->fail_index = bad;
            status = dyn_result_fail(res, DYN_ERR_NONFINITE, "state %d became not finite at t = %s",
                                     bad, dyn_shortest(tnext).s);
            break;
        }
        done++;
        double *swap = cur;
        cur = nxt;
        nxt = swap;
        t_reached = tnext;
        step++;
        if (output && (--countdown == 0 || step == steps)) {
            countdown = every;
            samples++;
            if (output(step, tnext, cur, output_ctx)) {
                status =
                    dyn_result_fail(res, DYN_STOPPED, "output stopped the run at t = %g", tnext);
                break;
            }
        }
        if (progress && --progress_countdown == 0) {
            progress_countdown = progress_every;
            if (progress(tnext, (double)step / (double)steps, progress_ctx)) {
                status = dyn_result_fail(res, DYN_CANCELLED, "cancelled at t = %g", tnext);
                break;
            }
        }
    }
    res->stats.steps = done;
    res->stats.accepted = done; /* every fixed step is accepted */
    if (status != DYN_ERR_RHS && status != DYN_ERR_NONFINITE)
        res->stats.rhs_calls = done * s;
    res->stats.samples = samples;
    res->t = t_reached;
    if (cur != y)
        memcpy(y, cur, (size_t)n * sizeof *y);
    res->status = status;
    return status;
}
