/* SPDX-License-Identifier: BSD-3-Clause */
/* The general driver of dyn_solve (dyn_solve_general; src/ode/solve_fast.c sends the
 * common cases of bs23, dp45 and dop853 to their kernels first): adaptive step-size control for embedded pairs (and fixed
 * steps for plain tables), output at requested times by dense output, recording of the
 * dense output, events, stiffness detection.
 *
 * Follows Hairer's DOPRI5/DOP853 (HNW I sec. II.4-II.6, II.10 and IV.2 of vol. II):
 * automatic initial step (HINIT), acceptance when the error norm is <= 1, PI control,
 * the last step shortened to land on t1 exactly (when t + 1.01 h passes t1), and DOPRI5's
 * stiffness test (|h lambda| above the stability boundary for 15 of the accepted steps
 * in a row, tested every stiff_check steps and at every step once suspicious). Output
 * times never shorten a step: values there come from the dense output, or are the step's
 * end state when the time is the step's end. Fixed-step tables take the steps of
 * dyn_fixed_solve (t0 + k*h computed, the same end policy, bit for bit the same states).
 * A step whose state is not finite is rejected and retried smaller; when that would need a
 * step below 16 eps |t|, the solve stops with DYN_ERR_NONFINITE (or DYN_ERR_STEP_SIZE when
 * the states are finite but the error is too large).
 */
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "dynkit/io.h" /* dyn_shortest: numbers in messages */
#include "dynkit/solve.h"
#include "dynkit/solve_inline.h" /* dyn_sinl_ctl: the step-size controller */
#include "ode/events.h"
#include "ode/result_fail.h"
#include "ode/solve_general.h"
#include "ode/step_control.h"
#include "ode/stepper.h"

#define DEFAULT_SAMPLES 8
#define MAX_SAMPLES 64
#define STIFF_SUSPICIOUS 15 /* DOPRI5: steps in a row above the boundary */
#define STIFF_CLEARED 6     /* DOPRI5: steps below it that clear the suspicion */

static void result_init(dyn_result *res, double t0)
{
    memset(res, 0, sizeof *res);
    res->t = t0;
    res->fail_t = NAN;
    res->fail_index = -1;
    res->event_index = -1;
    res->stiff_t = NAN;
}

static int first_nonfinite(const double *y, int n)
{
    for (int q = 0; q < n; q++)
        if (!isfinite(y[q]))
            return q;
    return -1;
}

/* A reset returned rc != 0 at te. */
static void reset_failed(dyn_result *res, const dyn_solve_opts *opts, int idx, double te, int rc)
{
    res->rhs_status = rc;
    res->fail_t = te;
    dyn_result_fail(res, DYN_ERR_RHS, "the reset of event %d (%s) failed at t = %s (status %d)",
                    idx, opts->events[idx].name ? opts->events[idx].name : "unnamed",
                    dyn_shortest(te).s, rc);
}

static int samples_of(const dyn_solve_opts *o)
{
    int m = o && o->event_samples > 0 ? o->event_samples : DEFAULT_SAMPLES;
    return m < 2 ? 2 : m > MAX_SAMPLES ? MAX_SAMPLES : m;
}

/* The sparse pattern the options ask the stiff methods to use, or NULL (dense or band). */
static const dyn_sparse_pattern *sparse_of(const dyn_solve_opts *o)
{
    return o && !o->jac_banded && o->jac_sparse.nnz > 0 && o->sparse_solver &&
                   (o->jacobian_sparse || (o->jac_groups && o->jac_n_groups > 0))
               ? &o->jac_sparse
               : NULL;
}

size_t dyn_solve_work_size(const dyn_tableau *m, int n, const dyn_solve_opts *opts)
{
    const dyn_stepper_ops *ops = dyn_stepper_ops_for(m);
    if (!ops || n <= 0)
        return 0;
    const size_t N = (size_t)n;
    const int q = ops->dense_degree(m);
    const int ne = opts && opts->events ? opts->n_events : 0;
    const dyn_jac_shape shape = {opts && opts->jac_banded, opts ? opts->jac_lower : 0,
                                 opts ? opts->jac_upper : 0, sparse_of(opts)};
    size_t size = ops->work_size(m, n, &shape);
    if (size == 0)
        return 0;
    size += 4 * N;                  /* y, ynew, yout, ytmp */
    size += ((size_t)q + 1) * N;    /* dense coefficients */
    if (ne > 0) {
        const int M = samples_of(opts);
        size += 4 * (size_t)ne;     /* event memo (g, sign); cascades (g before, fired) */
        size += dyn_events_work(n, ne, M);
        size += 3 * (size_t)dyn_events_max_hits(ne, M); /* hits (t, index, direction) */
    }
    return size;
}

size_t dyn_solve_iwork_size(const dyn_tableau *m, int n)
{
    const dyn_stepper_ops *ops = dyn_stepper_ops_for(m);
    return ops && n > 0 ? ops->iwork_size(m, n) : 0;
}

/* Where output samples go: a grid, a list of times, or every step. */
typedef struct out_plan {
    int mode; /* 0: every step, 1: grid, 2: list */
    dyn_grid grid;
    const double *times;
    long count;  /* samples of the grid or the list */
    long next;   /* index of the next sample to emit */
    long k;      /* index handed to the output callback */
} out_plan;

static double out_time(const out_plan *o, long i)
{
    return o->mode == 1 ? dyn_grid_time(&o->grid, i) : o->times[i];
}

/* The state at time t inside the step [ta, tb]: the end state at tb, else the interpolant. */
static const double *state_at(double t, double tb, const double *ynew, const dyn_dense *d,
                              double *buf)
{
    if (t == tb)
        return ynew;
    dyn_dense_eval(d, t, buf);
    return buf;
}

static int check_tolerances(const dyn_solve_opts *o, int n, dyn_tol *tol, dyn_result *res)
{
    tol->rtol = o && o->rtol != 0.0 ? o->rtol : DYN_DEFAULT_RTOL;
    tol->atol = o && o->atol != 0.0 ? o->atol : DYN_DEFAULT_ATOL;
    tol->rtolv = o ? o->rtolv : NULL;
    tol->atolv = o ? o->atolv : NULL;
    if (!(tol->rtol >= 0.0) || !isfinite(tol->rtol))
        return dyn_result_fail(res, DYN_ERR_ARG,
                               "rtol %g is not accepted: it must be a finite number >= 0",
                               tol->rtol);
    if (tol->rtol < DYN_MIN_RTOL) { /* below rounding: MATLAB's floor */
        tol->rtol = DYN_MIN_RTOL;
        res->rtol_raised = 1;
    }
    if (!(tol->atol >= 0.0) || !isfinite(tol->atol))
        return dyn_result_fail(res, DYN_ERR_ARG,
                               "atol %g is not accepted: it must be a finite number >= 0",
                               tol->atol);
    for (int i = 0; i < n; i++) {
        const double r = tol->rtolv ? tol->rtolv[i] : tol->rtol;
        const double a = tol->atolv ? tol->atolv[i] : tol->atol;
        if (!(r >= 0.0) || !isfinite(r) || !(a >= 0.0) || !isfinite(a))
            return dyn_result_fail(
                res, DYN_ERR_ARG,
                "tolerance of state %d (rtol %g, atol %g) is not accepted: both must be "
                "finite numbers >= 0",
                i, r, a);
        if (r > 0.0 && r < DYN_MIN_RTOL)
            return dyn_result_fail(
                res, DYN_ERR_ARG,
                "rtol %g of state %d is below rounding: give 0 or at least %g (100 "
                "eps)",
                r, i, DYN_MIN_RTOL);
        if (r == 0.0 && a == 0.0)
            return dyn_result_fail(
                res, DYN_ERR_ARG, "state %d has rtol = atol = 0: give at least one of them > 0", i);
    }
    return DYN_OK;
}

static int plan_output(const dyn_solve_opts *o, double t0, double t1, out_plan *out,
                       double *t_end, dyn_result *res)
{
    memset(out, 0, sizeof *out);
    *t_end = t1;
    if (o && o->out_step != 0.0 && o->out_times)
        return dyn_result_fail(res, DYN_ERR_ARG, "give either out_step or out_times, not both");
    if (o && o->out_step != 0.0) {
        out->mode = 1;
        if (dyn_grid_plan(t0, t1, o->out_step, o->end, &out->grid, res->message,
                          sizeof res->message)) {
            res->status = DYN_ERR_ARG;
            return DYN_ERR_ARG;
        }
        out->count = out->grid.samples;
        *t_end = dyn_grid_time(&out->grid, out->count - 1);
    } else if (o && o->out_times) {
        out->mode = 2;
        out->times = o->out_times;
        out->count = o->n_out_times;
        for (long i = 0; i < out->count; i++) {
            const double ti = out->times[i];
            if (!(ti >= t0 && ti <= t1))
                return dyn_result_fail(
                    res, DYN_ERR_ARG, "output time %s (number %ld) is outside the span [%s, %s]",
                    dyn_shortest(ti).s, i + 1, dyn_shortest(t0).s, dyn_shortest(t1).s);
            if (i > 0 && ti < out->times[i - 1])
                return dyn_result_fail(
                    res, DYN_ERR_ARG, "output times must not decrease: %s (number %ld) follows %s",
                    dyn_shortest(ti).s, i + 1, dyn_shortest(out->times[i - 1]).s);
        }
    }
    return DYN_OK;
}

/* Emit the samples of the list or grid with time <= limit (and < limit when !incl). */
static int emit_until(out_plan *out, const dyn_solve_opts *o, double limit, int incl, double tb,
                      const double *ynew, const dyn_dense *d, double *buf, dyn_result *res)
{
    while (out->mode != 0 && out->next < out->count) {
        const double to = out_time(out, out->next);
        if (incl ? !(to <= limit) : !(to < limit))
            break;
        const double *yo = state_at(to, tb, ynew, d, buf);
        out->next++;
        if (o->output) {
            res->stats.samples++;
            if (o->output(out->k++, to, yo, o->output_ctx))
                return dyn_result_fail(res, DYN_STOPPED, "output stopped the run at t = %g", to);
        }
    }
    return DYN_OK;
}

int dyn_solve_general(const dyn_tableau *m, const dyn_system *sys, double t0, double t1,
                      const double *y0, double *y, double *work, const dyn_solve_opts *opts,
                      dyn_result *res)
{
    static const dyn_solve_opts no_opts;
    dyn_result local;
    if (!res)
        res = &local;
    result_init(res, t0);
    if (!opts)
        opts = &no_opts;
    const dyn_stepper_ops *ops = dyn_stepper_ops_for(m);
    if (!m)
        return dyn_result_fail(res, DYN_ERR_ARG, "no method given");
    if (m->kind == DYN_KIND_MAP)
        return dyn_result_fail(
            res, DYN_ERR_ARG,
            "%s is a discrete map: dyn_fixed_solve iterates it (events, resets and "
            "samples between its steps need an integrator)",
            m->name);
    if (!ops)
        return dyn_result_fail(res, DYN_ERR_ARG, "method %s cannot be run by dyn_solve", m->name);
    if (!sys || !sys->f)
        return dyn_result_fail(res, DYN_ERR_ARG, "no right-hand side given");
    const int n = sys->n;
    if (n <= 0)
        return dyn_result_fail(res, DYN_ERR_ARG,
                               "number of states %d is not accepted: it must be >= 1", n);
    if (!y0 || !work)
        return dyn_result_fail(res, DYN_ERR_ARG, "initial state or workspace is NULL");
    if (!isfinite(t0) || !isfinite(t1) || !(t1 > t0))
        return dyn_result_fail(
            res, DYN_ERR_ARG,
            "time span [%g, %g] is not accepted: t0 and t1 must be finite and t1 > t0", t0, t1);
    const int fixed = !dyn_method_is_adaptive(m);
    dyn_grid steps;
    if (fixed && dyn_grid_plan(t0, t1, opts->h, opts->end, &steps, res->message,
                               sizeof res->message)) {
        res->status = DYN_ERR_ARG;
        return DYN_ERR_ARG;
    }
    if (fixed && (res->status = dyn_grid_check_steps(&steps, opts->max_steps, res->message,
                                                     sizeof res->message)) != DYN_OK)
        return res->status;
    dyn_tol tol;
    if (!fixed && check_tolerances(opts, n, &tol, res))
        return res->status;
    if (fixed)
        memset(&tol, 0, sizeof tol);
    if (!fixed && (!(opts->max_step >= 0.0) || !(opts->initial_step >= 0.0)))
        return dyn_result_fail(res, DYN_ERR_ARG,
                               "max_step %g and initial_step %g must be >= 0 (0: automatic)",
                               opts->max_step, opts->initial_step);
    if (!fixed && opts->beta > 0.0 && !(dyn_sinl_ctl_exponent(m->error_order, opts->beta) > 0.0))
        return dyn_result_fail(
            res, DYN_ERR_ARG,
            "beta %g is not accepted for %s: the step-size exponent 1/(q+1) - 0.75 beta "
            "must stay > 0 (q = %d), so beta < %g",
            opts->beta, m->name, m->error_order,
            1.0 / (0.75 * (double)((m->error_order > 0 ? m->error_order : 1) + 1)));
    const int ne = opts->events ? opts->n_events : 0;
    if (ne < 0)
        return dyn_result_fail(res, DYN_ERR_ARG, "n_events %d is not accepted", ne);
    for (int i = 0; i < ne; i++)
        if (!opts->events[i].g)
            return dyn_result_fail(res, DYN_ERR_ARG, "event %d has no function g", i);
    if (opts->jac_banded && (opts->jac_lower < 0 || opts->jac_upper < 0 ||
                             opts->jac_lower >= n || opts->jac_upper >= n))
        return dyn_result_fail(
            res, DYN_ERR_ARG,
            "the band of the Jacobian (lower %d, upper %d) must have 0 <= lower, upper < "
            "n = %d",
            opts->jac_lower, opts->jac_upper, n);
    char why[160];
    if (sparse_of(opts) && dyn_sparse_pattern_check(&opts->jac_sparse, n, why, sizeof why))
        return dyn_result_fail(res, DYN_ERR_ARG, "%s", why);
    if (dyn_solve_iwork_size(m, n) > 0 && !opts->iwork)
        return dyn_result_fail(res, DYN_ERR_ARG, "method %s needs integer workspace (opts.iwork)",
                               m->name);
    out_plan out;
    double t_end;
    if (plan_output(opts, t0, t1, &out, &t_end, res))
        return res->status;
    if (fixed && opts->end == DYN_END_GRID)
        t_end = fmin(t_end, dyn_grid_time(&steps, steps.samples - 1));
    const int q = ops->dense_degree(m);
    dyn_dense_record *rec = opts->record;
    if (rec && (rec->n != n || rec->degree != q))
        return dyn_result_fail(
            res, DYN_ERR_ARG,
            "the recorder is for %d states and degree %d; method %s needs %d states and "
            "degree %d (dyn_method_dense_degree)",
            rec->n, rec->degree, m->name, n, q);

    /* workspace */
    const size_t N = (size_t)n;
    double *w = work;
    dyn_stepper st;
    memset(&st, 0, sizeof st);
    st.ops = ops;
    st.m = m;
    st.f = sys->f;
    st.par = sys->par;
    st.n = n;
    st.jac = opts->jacobian;
    st.shape.banded = opts->jac_banded != 0;
    st.shape.lower = opts->jac_lower;
    st.shape.upper = opts->jac_upper;
    st.jac_band = opts->jacobian_band;
    st.band_solver = opts->band_solver;
    st.shape.sparse = sparse_of(opts);
    st.jac_sparse = opts->jacobian_sparse;
    st.sparse_solver = opts->sparse_solver;
    st.jac_groups = opts->jacobian_sparse ? NULL : opts->jac_groups;
    st.jac_n_groups = opts->jac_n_groups;
    if (st.shape.sparse && st.sparse_solver->forget)
        st.sparse_solver->forget(st.sparse_solver->ctx); /* pivots of this solve's own */
    st.tend = t1;
    st.tol = tol;
    st.work = w;
    st.iwork = opts->iwork;
    st.trace = opts->trace;
    st.trace_ctx = opts->trace_ctx;
    st.trace_steps = opts->trace ? opts->trace_steps : 0;
    w += ops->work_size(m, n, &st.shape);
    double *ycur = w, *ynew = w + N, *yout = w + 2 * N, *ytmp = w + 3 * N;
    w += 4 * N;
    double *coef = w;
    w += ((size_t)q + 1) * N;
    const int M = samples_of(opts);
    double *memo = NULL, *ev_work = NULL, *hits = NULL, *casc = NULL;
    if (ne > 0) {
        memo = w;
        w += 2 * (size_t)ne;
        casc = w;
        w += 2 * (size_t)ne;
        ev_work = w;
        w += dyn_events_work(n, ne, M);
        hits = w;
        w += 3 * (size_t)dyn_events_max_hits(ne, M);
    }
    double t = t0;

    /* the initial state */
    memmove(ycur, y0, N * sizeof *ycur);
    int bad = first_nonfinite(ycur, n);
    if (bad >= 0) {
        res->fail_t = t0;
        res->fail_index = bad;
        return dyn_result_fail(res, DYN_ERR_NONFINITE, "initial state %d is not finite (%g)", bad,
                               ycur[bad]);
    }
    int rc = ops->start(&st, t0, ycur);
    if (rc)
        goto rhs_failed;
    if (ne > 0)
        dyn_events_start(opts->events, ne, sys->par, t0, ycur, memo);
    if (out.mode == 0 || (out.count > 0 && out_time(&out, 0) == t0)) {
        /* sample 0: the initial state (every step, grid, or the list's leading t0s) */
        do {
            if (opts->output) {
                res->stats.samples++;
                if (opts->output(out.k++, t0, ycur, opts->output_ctx)) {
                    dyn_result_fail(res, DYN_STOPPED, "output stopped the run at t = %g", t0);
                    goto finish;
                }
            }
            if (out.mode != 0)
                out.next++;
        } while (out.mode != 0 && out.next < out.count && out_time(&out, out.next) == t0);
    }

    /* step size */
    double h = 0.0, hmax = t_end - t0;
    dyn_sinl_ctl ctl = {0}; /* set up below for adaptive methods */
    if (!fixed) {
        if (opts->max_step > 0.0)
            hmax = fmin(hmax, opts->max_step);
        dyn_sinl_ctl_init(&ctl, m->error_order, dyn_sinl_ctl_safety(m, opts->safety),
                          opts->beta, opts->fac_min, opts->fac_max, ops->err_squared);
        if (opts->initial_step > 0.0) {
            h = fmin(opts->initial_step, hmax);
        } else {
            rc = dyn_initial_step(&st, t0, ycur, m->error_order, hmax, ytmp, ynew, &h);
            if (rc)
                goto rhs_failed;
        }
    }
    const long stiff_every = opts->stiff_check > 0 ? opts->stiff_check : 1000;
    const long progress_every = opts->progress_steps > 0 ? opts->progress_steps : 4096;
    long progress_countdown = progress_every;
    /* invariants of the step loop, read once (the compiler cannot hoist reads through opts:
     * the loop stores through res and calls out) */
    const long max_steps = opts->max_steps;
    const int stiff_test = !fixed && m->stiff_bound > 0.0 && ops->stiffness;
    long stiff_countdown = stiff_every; /* accepted % stiff_every == 0, without a division */
    const int dense_always = ne > 0 || opts->step || rec;
    const dyn_output_fn output = opts->output;
    const dyn_progress_fn progress = opts->progress;
    int stiff_count = 0, nonstiff_count = 0;
    int rejected_before = 0, retry = 0;
    long step = 0; /* fixed: index of the step */
    long stop_i = 0; /* adaptive: the next of opts->stops */
    /* resets: the first event that reset at this step's time, resets in a row close in time
     * (Zeno), whether the step starts at a restart */
    int reset_idx = -1, zeno = 0, restarted = 0;
    long n_resets = 0;
    double t_last_reset = t0;
    dyn_dense d = {0.0, 0.0, n, q, coef};
    dyn_event_sink sink = {opts->events, opts->on_event, opts->event_ctx, res};

    while (t < t_end) {
        double hn, tnext;
        int last = 0, at_stop = 0, off_grid = 0;
        if (fixed) {
            if (step >= steps.samples - 1)
                break;
            const double tn = t0 + (double)step * opts->h;
            hn = step < steps.whole_steps ? opts->h : t1 - tn;
            tnext = (steps.ends_at_t1 && step + 1 == steps.samples - 1)
                        ? t1
                        : t0 + (double)(step + 1) * opts->h;
            if (t != tn)
                hn = tnext - t; /* after a reset or a stop inside the step: on to the grid */
            while (stop_i < opts->n_stops && !(opts->stops[stop_i] > t + 1e-12 * fabs(t)))
                stop_i++;
            if (stop_i < opts->n_stops &&
                fabs(opts->stops[stop_i] - tnext) <= 1e-12 * fabs(tnext)) {
                at_stop = 1; /* a stop on the grid: f anew after it */
                stop_i++;
            } else if (stop_i < opts->n_stops && opts->stops[stop_i] < tnext) {
                /* a stop inside the step (a breaking point between grid points): a partial
                 * step onto it keeps the order, the grid goes on after it */
                tnext = opts->stops[stop_i++];
                hn = tnext - t;
                at_stop = off_grid = 1;
            }
        } else {
            while (stop_i < opts->n_stops && !(opts->stops[stop_i] > t))
                stop_i++;
            if (stop_i < opts->n_stops && opts->stops[stop_i] < t_end &&
                t + 1.01 * h >= opts->stops[stop_i]) {
                hn = opts->stops[stop_i] - t; /* onto the stop (a breaking point) */
                tnext = opts->stops[stop_i];
                at_stop = 1;
            } else if (t + 1.01 * h >= t_end) {
                hn = t_end - t;
                tnext = t_end;
                last = 1;
            } else {
                hn = h;
                tnext = t + h;
            }
        }
        if (max_steps > 0 && res->stats.steps >= max_steps) {
            dyn_result_fail(res, DYN_ERR_MAX_STEPS,
                            "reached the limit of %ld steps at t = %s (h = %g): raise the limit, "
                            "loosen the tolerances, or use a method for stiff problems",
                            max_steps, dyn_shortest(t).s, h);
            goto finish;
        }
        double err = 0.0;
        res->stats.steps++;
        rc = ops->attempt(&st, t, hn, ycur, ynew, &err, retry);
        if (rc)
            goto rhs_failed;
        if (fixed) {
            if (err != 0.0 || (bad = first_nonfinite(ynew, n)) >= 0) {
                bad = first_nonfinite(ynew, n);
                res->fail_t = tnext;
                res->fail_index = bad;
                dyn_result_fail(res, DYN_ERR_NONFINITE, "state %d became not finite at t = %s", bad,
                                dyn_shortest(tnext).s);
                goto finish;
            }
        } else if (!(err <= 1.0)) {
            /* rejected */
            res->stats.rejected++;
            retry = 1;
            rejected_before = 1;
            h = dyn_sinl_ctl_reject(&ctl, hn, err);
            /* near t = 0, a step below eps^2 of the span is no step either */
            const double hmin =
                16.0 * DBL_EPSILON * fmax(fabs(t), fmax(DBL_EPSILON * (t_end - t0), DBL_MIN));
            if (!(h >= hmin) || t + h == t) {
                bad = first_nonfinite(ynew, n);
                if (bad >= 0) {
                    res->fail_t = tnext;
                    res->fail_index = bad;
                    dyn_result_fail(
                        res, DYN_ERR_NONFINITE,
                        "state %d became not finite at t = %s for every step size down to "
                        "%g",
                        bad, dyn_shortest(tnext).s, hn);
                } else {
                    res->fail_t = t;
                    dyn_result_fail(
                        res, DYN_ERR_STEP_SIZE,
                        "step size underflow at t = %s: the error test fails with h = %g "
                        "(a singularity, a discontinuity, or tolerances below rounding)",
                        dyn_shortest(t).s, hn);
                }
                goto finish;
            }
            continue;
        }
        /* accepted */
        res->stats.accepted++;
        retry = 0;
        const int stiff_due = --stiff_countdown == 0;
        if (stiff_due)
            stiff_countdown = stiff_every;
        if (stiff_test && (stiff_due || stiff_count > 0)) {
            const double hl = ops->stiffness(&st, t, hn, ycur, ynew);
            if (hl > m->stiff_bound) {
                nonstiff_count = 0;
                if (++stiff_count == STIFF_SUSPICIOUS && !res->stiff) {
                    res->stiff = 1;
                    res->stiff_t = t;
                    snprintf(res->stiff_message, sizeof res->stiff_message,
                             "the problem looks stiff from t = %.6g: %s's step size is limited "
                             "by stability (|h lambda| > %g for %d steps in a row), not by "
                             "accuracy",
                             t, m->name, m->stiff_bound, STIFF_SUSPICIOUS);
                }
            } else if (hl >= 0.0 && ++nonstiff_count == STIFF_CLEARED) {
                stiff_count = 0;
            }
        }
        const int want_dense =
            dense_always ||
            (out.mode != 0 && out.next < out.count && out_time(&out, out.next) < tnext);
        if (want_dense) {
            rc = ops->dense(&st, t, hn, ycur, ynew, coef);
            if (rc)
                goto rhs_failed;
            d.t0 = t;
            d.h = hn;
        }
        if (rec) {
            if (rec->count >= rec->capacity &&
                !(rec->grow && rec->grow(rec, rec->grow_ctx) == 0 &&
                  rec->count < rec->capacity)) {
                dyn_result_fail(res, DYN_ERR_CAPACITY,
                                "the dense-output recorder is full (%ld steps) at t = %s",
                                rec->count, dyn_shortest(t).s);
                goto finish;
            }
            double *b = rec->data + (size_t)rec->count * dyn_dense_record_block(n, q);
            b[0] = t;
            b[1] = hn;
            memcpy(b + 2, coef, ((size_t)q + 1) * N * sizeof *coef);
            rec->count++;
        }
        if (opts->step && opts->step(&d, opts->step_ctx)) {
            dyn_result_fail(res, DYN_STOPPED, "the step callback stopped the run at t = %g", tnext);
            goto finish;
        }
        /* events and output samples of this step, in time order */
        int nh = ne > 0 ? dyn_events_step(opts->events, ne, sys->par, &d, tnext, ynew, M, memo,
                                          ev_work, hits, NULL, restarted)
                        : 0;
        int stop = 0, reset = 0;
        double t_stop = tnext, t_reset = tnext;
        for (int k = 0; k < nh && !stop; k++) {
            double te = DYN_HIT_T(hits, k);
            const int idx = DYN_HIT_INDEX(hits, k), dir = DYN_HIT_DIR(hits, k);
            if (reset && te > t_reset)
                break; /* after a reset: the rest of the step is the old trajectory's */
            if (reset)
                te = t_reset; /* a crossing within the instant fires in it */
            else if (opts->events[idx].reset && opts->xppaut_globals)
                te = dyn_events_instant(t, te, tnext);
            if (!reset && emit_until(&out, opts, te, 1, tnext, ynew, &d, yout, res))
                goto finish;
            /* events at the time of a reset see the state before the resets */
            const double *ye = reset ? ycur : state_at(te, tnext, ynew, &d, ytmp);
            if (dyn_events_report(idx, te, ye, dir, &sink)) {
                stop = 1;
                t_stop = te;
                if (ye != ycur)
                    memcpy(ycur, ye, N * sizeof *ycur);
            } else if (opts->events[idx].reset) {
                if (!reset) {
                    /* ycur: the state at the event (kept if a reset fails); ytmp: reset */
                    if (ye != ycur)
                        memcpy(ycur, ye, N * sizeof *ycur);
                    memcpy(ytmp, ycur, N * sizeof *ytmp);
                    reset = 1;
                    t_reset = te;
                    reset_idx = idx;
                }
                rc = opts->events[idx].reset(te, ytmp, sys->par);
                if (rc) {
                    t = te;
                    reset_failed(res, opts, idx, te, rc);
                    goto finish;
                }
            }
        }
        if (reset && !stop) {
            /* cascades: events whose g the resets carried onto or across zero fire at the
             * same instant, each once, in cycles (index order within one) */
            int which = -1;
            const int how =
                dyn_events_cascades(opts->events, ne, sys->par, t_reset, ycur, ytmp, hits, nh,
                                    memo, opts->xppaut_globals ? DYN_EVENTS_TOL : 0.0, casc,
                                    dyn_events_report, &sink, &res->cascades, &which, &rc);
            if (how == DYN_CASCADES_STOPPED) {
                stop = 1;
                t_stop = t_reset;
                memcpy(ycur, ytmp, N * sizeof *ycur);
            } else if (how == DYN_CASCADES_RESET_FAILED) {
                t = t_reset;
                reset_failed(res, opts, which, t_reset, rc);
                goto finish;
            }
        }
        if (reset && !stop) {
            /* restart from (t_reset, ytmp) as from a new initial value */
            bad = first_nonfinite(ytmp, n);
            t = t_reset;
            if (bad >= 0) {
                res->fail_t = t;
                res->fail_index = bad;
                dyn_result_fail(res, DYN_ERR_NONFINITE,
                                "the reset of event %d made state %d not finite at t = %s",
                                reset_idx, bad, dyn_shortest(t).s);
                goto finish;
            }
            /* Zeno: resets that follow each other without time advancing */
            const double window = DYN_ZENO_WINDOW * fmax(fabs(t), t1 - t0);
            zeno = n_resets > 0 && t - t_last_reset <= window ? zeno + 1 : 0;
            if (zeno >= DYN_ZENO_RESETS) {
                dyn_result_fail(
                    res, DYN_ERR_ZENO,
                    "Zeno behaviour: %d resets in a row, each less than %.3g s after the one "
                    "before, up to t = %s (event %d (%s) last): the resets accumulate here",
                    zeno, window, dyn_shortest(t).s, reset_idx,
                    opts->events[reset_idx].name ? opts->events[reset_idx].name : "unnamed");
                goto finish;
            }
            n_resets++;
            t_last_reset = t;
            dyn_events_restart(opts->events, ne, sys->par, t, ycur, ytmp, hits, nh, memo);
            restarted = 1;
            memcpy(ycur, ytmp, N * sizeof *ycur);
            res->h_last = hn;
            if (out.mode == 0 && output) {
                /* with a sample at every step, the state after the reset at the event */
                res->stats.samples++;
                if (output(out.k++, t, ycur, opts->output_ctx)) {
                    dyn_result_fail(res, DYN_STOPPED, "output stopped the run at t = %g", t);
                    goto finish;
                }
            }
            rc = ops->start(&st, t, ycur);
            if (rc)
                goto rhs_failed;
            retry = 0;
            if (fixed) {
                if (t == tnext && !off_grid)
                    step++; /* the reset is at a grid point: whole steps go on from it */
            } else {
                dyn_sinl_ctl_init(&ctl, m->error_order, dyn_sinl_ctl_safety(m, opts->safety),
                                  opts->beta, opts->fac_min, opts->fac_max, ops->err_squared);
                rejected_before = 0;
                /* the step the controller had, or the starting step at the new state when
                 * that is smaller (the reset may make the solution change faster) */
                double h0 = opts->initial_step;
                if (!(h0 > 0.0)) {
                    rc = dyn_initial_step(&st, t, ycur, m->error_order, hmax, yout, ynew, &h0);
                    if (rc)
                        goto rhs_failed;
                }
                h = fmin(fmin(h, h0), hmax);
            }
            continue;
        }
        restarted = 0;
        if (stop) {
            /* the event is the last sample (unless it was one already) */
            const int already = out.mode != 0 && out.next > 0 &&
                                out_time(&out, out.next - 1) == t_stop;
            if (!already && opts->output) {
                res->stats.samples++;
                if (opts->output(out.k++, t_stop, ycur, opts->output_ctx)) {
                    dyn_result_fail(res, DYN_STOPPED, "output stopped the run at t = %g", t_stop);
                    t = t_stop;
                    goto finish;
                }
            }
            t = t_stop;
            res->h_last = hn;
            break;
        }
        if (out.mode != 0 && emit_until(&out, opts, tnext, 1, tnext, ynew, &d, yout, res))
            goto finish;
        ops->accept(&st, t, hn, ynew);
        memcpy(ycur, ynew, N * sizeof *ycur);
        t = tnext;
        res->h_last = hn;
        if (!off_grid)
            step++;
        if (at_stop) { /* f anew past the stop: the right-hand side may jump there */
            rc = ops->start(&st, t, ycur);
            if (rc)
                goto rhs_failed;
        }
        if (out.mode == 0 && output) {
            res->stats.samples++;
            if (output(out.k++, t, ycur, opts->output_ctx)) {
                dyn_result_fail(res, DYN_STOPPED, "output stopped the run at t = %g", t);
                goto finish;
            }
        }
        if (progress && --progress_countdown == 0) {
            progress_countdown = progress_every;
            if (progress(t, (t - t0) / (t_end - t0), opts->progress_ctx)) {
                dyn_result_fail(res, DYN_CANCELLED, "cancelled at t = %g", t);
                goto finish;
            }
        }
        if (!fixed) {
            h = fmin(dyn_sinl_ctl_accept(&ctl, hn, err, rejected_before), hmax);
            if (last)
                h = fmax(h, hn); /* no meaning past the end */
            rejected_before = 0;
        }
    }
    goto finish;

rhs_failed:
    res->rhs_status = rc;
    res->fail_t = st.fail_t;
    dyn_result_fail(res, DYN_ERR_RHS, "the right-hand side failed at t = %s (status %d)",
                    dyn_shortest(st.fail_t).s, rc);

finish:
    res->t = t;
    res->stats.rhs_calls = st.rhs_calls;
    res->stats.jac_calls = st.jac_calls;
    res->stats.jac_fd_columns = st.jac_fd_columns;
    if (y && y != ycur)
        memcpy(y, ycur, N * sizeof *y);
    return res->status;
}
