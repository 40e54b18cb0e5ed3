/* SPDX-License-Identifier: BSD-3-Clause */
/* Stochastic differential equations (dynkit/sde.h): Euler–Maruyama with fixed steps, Rößler's
 * SRIW1 (strong order 1.5: sde_sri.c) and the derivative-free Runge–Kutta Milstein scheme of
 * Kloeden and Platen (Numerical Solution of Stochastic Differential Equations, 1992, eq.
 * 11.1.5, strong order 1),
 *   Y+ = Y + a h + sum_j b_j dW_j + sum_j (b_j(t, K_j) - b_j(t, Y)) (dW_j^2 - h) / (2 sqrt h),
 *   K_j = Y + a h + b_j sqrt h,
 * applied noise by noise, which is Milstein's scheme when no b_j depends on a state that
 * another noise moves (additive, scalar or diagonal noise: dyn_noise_class); for additive
 * noise the correction vanishes and is not computed. The drift a and the columns b_j come
 * from the model's right-hand side, affine in its Wiener slots: a = f(w = 0),
 * b_j = f(w = e_j) - a.
 *
 * Adaptive steps: rkmil by step doubling (a step of h and two of h/2 on the same Brownian
 * path, their difference measured as the embedded pairs' error norm), SRIW1 by its embedded
 * estimate, both on the kept Brownian path of sde_path.c (rejection sampling with memory,
 * Rackauckas and Nie 2017). Steps land on the output times.
 *
 * Events (sde.h, "Events") with the library's event location and XPPAUT's cascade rules
 * (ode/events.c), on the straight line between a fixed step's ends or the broken line
 * through an adaptive step's three states; after a reset inside a fixed step, W at the
 * event comes from the Brownian bridge between the step's ends and the step's rest takes
 * the remaining increment. */
#include <math.h>
#include <string.h>

#include "dynkit/io.h"
#include "dynkit/sde.h"
#include "ode/events.h"
#include "result_fail.h"
#include "sde_path.h"
#include "sde_sri.h"

/* g sampled at EVENT_SAMPLES + 1 points of the interpolant of a step (or half step) */
#define EVENT_SAMPLES 4

static size_t event_work_size(int n, int ne)
{
    if (ne <= 0)
        return 0;
    /* memo, cascades (2 ne each), locator's scratch, hits, the interpolant (2 n), the
     * states before and after the resets (2 n) */
    return 4 * (size_t)ne + dyn_events_work(n, ne, EVENT_SAMPLES) +
           3 * (size_t)dyn_events_max_hits(ne, EVENT_SAMPLES) + 4 * (size_t)n;
}

size_t dyn_sde_work_size(int n, int n_noise, int n_events)
{
    const size_t N = (size_t)(n > 0 ? n : 0), M = (size_t)(n_noise > 0 ? n_noise : 0);
    return 14 * N + (M + 1) * N + 8 * M + (size_t)DYN_SDE_MAX_POINTS * (1 + 2 * M) +
           DYN_SRI_WORK(N, M) + 20 + event_work_size(n, n_events);
}

typedef struct sde_run {
    const dyn_sde *sde;
    int n, m;
    dyn_rng rng;
    dyn_result *res;
    int rhs_status;
    /* workspace */
    double *a, *b, *kk, *c0, *c1, *ymid, *ybig, *ysmall, *dw, *dw1, *dw2, *wend, *wmid;
    double *i10, *e1, *e2, *sri_work;
    dyn_bpath path; /* the Brownian path (sde_path.h) */
    /* events: the run's span (Zeno's window), memory between steps, the interpolant, the
     * states before (ybefore) and after (yafter) the resets of an instant at t_ev */
    double t0, t1;
    const dyn_event *ev;
    int ne, restarted, zeno, reset_idx, xppaut_globals;
    long n_resets;
    double t_last_reset, t_ev;
    double *memo, *casc, *ev_work, *hits, *coef, *ybefore, *yafter;
    dyn_event_sink sink;
} sde_run;

/* What the events of a piece of a step did. */
enum { SEG_NONE, SEG_RESET, SEG_STOP, SEG_FAIL };

static int first_nonfinite(const double *y, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(y[i]))
            return i;
    return -1;
}

/* f(t, y) with the noise slots at w (NULL: all zero; unit >= 0: slot unit 1, others 0). */
static int eval(sde_run *r, double t, const double *y, const double *w, int unit, double *out)
{
    const dyn_sde *s = r->sde;
    for (int j = 0; j < r->m; j++)
        s->noise[j] = w ? w[j] : (j == unit ? 1.0 : 0.0);
    r->res->stats.rhs_calls++;
    const int st = s->sys.f(t, y, out, s->sys.par);
    if (st) {
        r->rhs_status = st;
        r->res->fail_t = t;
    }
    return st;
}

/* The drift a and the columns b (m x n) at (t, y). */
static int drift_diffusion(sde_run *r, double t, const double *y)
{
    const int n = r->n;
    if (eval(r, t, y, NULL, -1, r->a))
        return 1;
    for (int j = 0; j < r->m; j++) {
        double *bj = r->b + (size_t)j * (size_t)n;
        if (eval(r, t, y, NULL, j, bj))
            return 1;
        for (int i = 0; i < n; i++)
            bj[i] -= r->a[i];
    }
    return 0;
}

/* One step of the Runge–Kutta Milstein scheme from (t, y) over h with increments dw, the
 * drift and diffusion at (t, y) already in r->a, r->b; the result into out (not y). */
static int rkmil_step(sde_run *r, double t, const double *y, double h, const double *dw,
                      double *out)
{
    const int n = r->n, m = r->m;
    for (int i = 0; i < n; i++)
        out[i] = y[i] + h * r->a[i];
    for (int j = 0; j < m; j++) {
        const double *bj = r->b + (size_t)j * (size_t)n;
        for (int i = 0; i < n; i++)
            out[i] += bj[i] * dw[j];
    }
    if (r->sde->noise_class == DYN_NOISE_ADDITIVE)
        return 0;
    const double sq = sqrt(h);
    for (int j = 0; j < m; j++) {
        const double *bj = r->b + (size_t)j * (size_t)n;
        for (int i = 0; i < n; i++)
            r->kk[i] = y[i] + h * r->a[i] + bj[i] * sq;
        if (eval(r, t, r->kk, NULL, j, r->c1) || eval(r, t, r->kk, NULL, -1, r->c0))
            return 1;
        const double g = (dw[j] * dw[j] - h) / (2.0 * sq);
        for (int i = 0; i < n; i++)
            out[i] += (r->c1[i] - r->c0[i] - bj[i]) * g;
    }
    return 0;
}

/* dyn_sri_eval_fn: the drift, or a noise column as f(w = e_unit) - f(w = 0). */
static int sri_eval(void *ctx, double t, const double *y, int unit, double *out)
{
    sde_run *r = ctx;
    if (eval(r, t, y, NULL, unit, out))
        return 1;
    if (unit < 0)
        return 0;
    if (eval(r, t, y, NULL, -1, r->c0))
        return 1;
    for (int i = 0; i < r->n; i++)
        out[i] -= r->c0[i];
    return 0;
}

/* One SRIW1 step from (t, y) to the kept point t + h of the path: the new state into
 * r->ysmall, the error estimate's parts into r->e1, r->e2. */
static int sri_attempt(sde_run *r, double t, double h, const double *y)
{
    dyn_bpath_increments(&r->path, t + h, r->dw, r->i10);
    if (drift_diffusion(r, t, y))
        return 1;
    return dyn_sri_step(&dyn_sriw1, r->n, r->m, r->sde->noise_class == DYN_NOISE_ADDITIVE, t,
                        h, y, r->dw, r->i10, r->a, r->b, sri_eval, r, r->sri_work, r->ysmall,
                        r->e1, r->e2);
}

static int rhs_fail(sde_run *r)
{
    r->res->rhs_status = r->rhs_status;
    return dyn_result_fail(r->res, DYN_ERR_RHS, "the right-hand side returned %d at t = %s",
                           r->rhs_status, dyn_shortest(r->res->fail_t).s);
}

static int nonfinite_fail(sde_run *r, double t, int bad)
{
    r->res->fail_t = t;
    r->res->fail_index = bad;
    return dyn_result_fail(r->res, DYN_ERR_NONFINITE, "state %d became not finite at t = %s",
                           bad, dyn_shortest(t).s);
}

static int reset_fail(sde_run *r, int idx, double t, int status)
{
    r->res->rhs_status = status;
    r->res->fail_t = t;
    return dyn_result_fail(r->res, DYN_ERR_RHS,
                           "the reset of event %d (%s) failed at t = %s (status %d)", idx,
                           r->ev[idx].name ? r->ev[idx].name : "unnamed", dyn_shortest(t).s,
                           status);
}

/* The events of the piece of a step from (ta, ya) to (tb, yb), the state between on the
 * straight line: SEG_NONE (the memory moved to tb), SEG_RESET (the run restarts at t_ev
 * from yafter), SEG_STOP (a terminal event: t_ev and yafter are the last state), SEG_FAIL
 * (res says why). The instant's rules are dyn_solve's (solve.h, "Resets", "Cascades"). */
static int segment_events(sde_run *r, double ta, const double *ya, double tb, const double *yb)
{
    const int n = r->n, ne = r->ne;
    void *par = r->sde->sys.par;
    for (int i = 0; i < n; i++) {
        r->coef[i] = ya[i];
        r->coef[n + i] = yb[i] - ya[i];
    }
    const dyn_dense d = {ta, tb - ta, n, 1, r->coef};
    const int nh = dyn_events_step(r->ev, ne, par, &d, tb, yb, EVENT_SAMPLES, r->memo,
                                   r->ev_work, r->hits, NULL, r->restarted);
    r->restarted = 0;
    int reset = 0;
    double t_reset = tb;
    for (int k = 0; k < nh; k++) {
        double te = DYN_HIT_T(r->hits, k);
        const int idx = DYN_HIT_INDEX(r->hits, k), dir = DYN_HIT_DIR(r->hits, k);
        if (reset && te > t_reset)
            break; /* after a reset: the rest of the step is the old trajectory's */
        if (reset)
            te = t_reset; /* a crossing within the instant fires in it */
        else if (r->ev[idx].reset && r->xppaut_globals)
            te = dyn_events_instant(ta, te, tb);
        if (!reset) {
            /* ybefore: the state at the event (events at the time of a reset see it) */
            if (te == tb)
                memcpy(r->ybefore, yb, (size_t)n * sizeof *yb);
            else
                dyn_dense_eval(&d, te, r->ybefore);
        }
        if (dyn_events_report(idx, te, r->ybefore, dir, &r->sink)) {
            r->t_ev = te;
            memcpy(r->yafter, r->ybefore, (size_t)n * sizeof *r->yafter);
            return SEG_STOP;
        }
        if (r->ev[idx].reset) {
            if (!reset) {
                memcpy(r->yafter, r->ybefore, (size_t)n * sizeof *r->yafter);
                reset = 1;
                t_reset = te;
                r->reset_idx = idx;
            }
            const int st = r->ev[idx].reset(te, r->yafter, par);
            if (st) {
                reset_fail(r, idx, te, st);
                return SEG_FAIL;
            }
        }
    }
    if (!reset)
        return SEG_NONE;
    int which = -1, st = 0;
    const int how = dyn_events_cascades(r->ev, ne, par, t_reset, r->ybefore, r->yafter, r->hits,
                                        nh, r->memo, r->xppaut_globals ? DYN_EVENTS_TOL : 0.0,
                                        r->casc, dyn_events_report, &r->sink,
                                        &r->res->cascades, &which, &st);
    r->t_ev = t_reset;
    if (how == DYN_CASCADES_STOPPED)
        return SEG_STOP;
    if (how == DYN_CASCADES_RESET_FAILED) {
        reset_fail(r, which, t_reset, st);
        return SEG_FAIL;
    }
    const int bad = first_nonfinite(r->yafter, n);
    if (bad >= 0) {
        r->res->fail_t = t_reset;
        r->res->fail_index = bad;
        dyn_result_fail(r->res, DYN_ERR_NONFINITE,
                        "the reset of event %d made state %d not finite at t = %s",
                        r->reset_idx, bad, dyn_shortest(t_reset).s);
        return SEG_FAIL;
    }
    /* Zeno: resets that follow each other without time advancing */
    const double window = DYN_ZENO_WINDOW * fmax(fabs(t_reset), r->t1 - r->t0);
    r->zeno = r->n_resets > 0 && t_reset - r->t_last_reset <= window ? r->zeno + 1 : 0;
    if (r->zeno >= DYN_ZENO_RESETS) {
        r->res->fail_t = t_reset;
        dyn_result_fail(r->res, DYN_ERR_ZENO,
                        "Zeno behaviour: %d resets in a row, each less than %.3g s after the "
                        "one before, up to t = %s (event %d (%s) last): the resets accumulate "
                        "here",
                        r->zeno, window, dyn_shortest(t_reset).s, r->reset_idx,
                        r->ev[r->reset_idx].name ? r->ev[r->reset_idx].name : "unnamed");
        return SEG_FAIL;
    }
    r->n_resets++;
    r->t_last_reset = t_reset;
    dyn_events_restart(r->ev, ne, par, t_reset, r->ybefore, r->yafter, r->hits, nh, r->memo);
    r->restarted = 1;
    return SEG_RESET;
}

/* A fixed step from ts to tn split at te by a reset: its Wiener slots' increments over
 * [ts, tn] (dw, or dw (tn - ts) for Euler–Maruyama's values dW/dt) become those over
 * [te, tn], W(te) drawn from the Brownian bridge; normal and uniform slots keep their
 * values. */
static void split_increments(sde_run *r, int em, double ts, double te, double tn)
{
    const dyn_sde *s = r->sde;
    const double hs = tn - ts, h1 = te - ts, h2 = tn - te;
    const double sd = sqrt(h1 * h2 / hs);
    for (int j = 0; j < r->m; j++) {
        if (s->kinds && s->kinds[j] != DYN_NOISE_WIENER)
            continue;
        const double whole = em ? r->dw[j] * hs : r->dw[j];
        const double rest = whole - (h1 / hs * whole + sd * dyn_rng_normal(&r->rng));
        r->dw[j] = em ? rest / h2 : rest;
    }
}

/* The state of a terminal event is the run's last sample. */
static int stop_sample(sde_run *r, const dyn_sde_opts *o, long k, double *y, double *t)
{
    *t = r->t_ev;
    r->res->t = *t;
    memcpy(y, r->yafter, (size_t)r->n * sizeof *y);
    if (o->output) {
        r->res->stats.samples++;
        if (o->output(k, *t, y, o->output_ctx))
            return dyn_result_fail(r->res, DYN_STOPPED, "output stopped the run at t = %g",
                                   *t);
    }
    return DYN_OK;
}

/* The jumps at the start of a step (Markov states): the step's slots written first. */
static int jump(sde_run *r, dyn_jump_fn fn, double t, double h, double *y)
{
    const dyn_sde *s = r->sde;
    for (int j = 0; j < r->m; j++)
        s->noise[j] = r->dw[j];
    const int st = fn(t, h, y, s->sys.par);
    if (!st)
        return 0;
    r->res->rhs_status = st;
    r->res->fail_t = t;
    dyn_result_fail(r->res, DYN_ERR_RHS,
                    "a transition rate of a Markov state is negative or not a number at t = %s "
                    "(the jumps returned %d; the states are left as they were)",
                    dyn_shortest(t).s, st);
    return 1;
}

/* Fixed steps on the grid of h: Euler–Maruyama (every slot drawn once per step), SRIW1 (per
 * step and noise, dW and then its time integral) or the Runge–Kutta Milstein scheme (Wiener
 * increments sqrt(dt) z). */
static int solve_fixed(sde_run *r, dyn_sde_method method, double t0, double t1,
                       const dyn_sde_opts *o, double *y)
{
    dyn_result *res = r->res;
    dyn_grid grid;
    if (dyn_grid_plan(t0, t1, o->h, o->end, &grid, res->message, sizeof res->message))
        return res->status = DYN_ERR_ARG;
    if ((res->status = dyn_grid_check_steps(&grid, o->max_steps, res->message,
                                            sizeof res->message)) != DYN_OK)
        return res->status;
    const int n = r->n, m = r->m;
    const dyn_sde *s = r->sde;
    const long steps = grid.samples - 1, every = o->every > 1 ? o->every : 1;
    long countdown = every, progress_countdown = 65536;
    double t = t0;
    for (long k = 0; k < steps; k++) {
        const double tn = dyn_grid_time(&grid, k + 1), h = tn - t;
        const int em = method == DYN_SDE_EM || method == DYN_SDE_MAP;
        if (em) {
            for (int j = 0; j < m; j++) {
                const int kind = s->kinds ? s->kinds[j] : DYN_NOISE_WIENER;
                r->dw[j] = kind == DYN_NOISE_UNIFORM  ? dyn_rng_uniform(&r->rng)
                           : kind == DYN_NOISE_NORMAL ? dyn_rng_normal(&r->rng)
                                                      : dyn_rng_normal(&r->rng) / sqrt(h);
            }
            if (o->jump && jump(r, o->jump, t, h, y))
                return DYN_ERR_RHS;
        } else if (method == DYN_SDE_SRIW1) {
            /* the path is empty: a new point, dW then J per noise */
            dyn_bpath_at(&r->path, tn, r->wend);
        } else {
            const double sq = sqrt(h);
            for (int j = 0; j < m; j++)
                r->dw[j] = sq * dyn_rng_normal(&r->rng);
        }
        for (;;) { /* the step, or its rest after a reset inside it */
            if (em) {
                if (eval(r, t, y, r->dw, -1, r->a))
                    return rhs_fail(r);
                for (int i = 0; i < n; i++)
                    r->ysmall[i] = method == DYN_SDE_MAP ? r->a[i] : y[i] + (tn - t) * r->a[i];
            } else if (method == DYN_SDE_SRIW1) {
                if (sri_attempt(r, t, tn - t, y))
                    return rhs_fail(r);
            } else if (drift_diffusion(r, t, y) || rkmil_step(r, t, y, tn - t, r->dw, r->ysmall)) {
                return rhs_fail(r);
            }
            res->stats.steps++;
            res->stats.accepted++;
            const int bad = first_nonfinite(r->ysmall, n);
            if (bad >= 0)
                return nonfinite_fail(r, tn, bad);
            const int seg = r->ne > 0 ? segment_events(r, t, y, tn, r->ysmall) : SEG_NONE;
            if (seg == SEG_NONE)
                break;
            if (seg == SEG_FAIL)
                return res->status;
            if (seg == SEG_STOP)
                return stop_sample(r, o, k + 1, y, &res->t);
            if (r->t_ev == tn) { /* reset at the grid point: the step ends there */
                memcpy(r->ysmall, r->yafter, (size_t)n * sizeof *y);
                break;
            }
            split_increments(r, em, t, r->t_ev, tn);
            t = r->t_ev;
            memcpy(y, r->yafter, (size_t)n * sizeof *y);
        }
        if (method == DYN_SDE_SRIW1)
            dyn_bpath_advance(&r->path, tn);
        memcpy(y, r->ysmall, (size_t)n * sizeof *y);
        t = tn;
        res->t = t;
        if (o->output && (--countdown == 0 || k + 1 == steps)) {
            countdown = every;
            res->stats.samples++;
            if (o->output(k + 1, t, y, o->output_ctx))
                return dyn_result_fail(res, DYN_STOPPED, "output stopped the run at t = %g", t);
        }
        if (o->progress && --progress_countdown == 0) {
            progress_countdown = 65536;
            if (o->progress(t, (double)(k + 1) / (double)steps, o->progress_ctx))
                return dyn_result_fail(res, DYN_CANCELLED, "cancelled at t = %g", t);
        }
    }
    return DYN_OK;
}

/* The error norm of the step-doubling difference (Hairer's RMS norm). */
static double error_norm(const sde_run *r, const double *y, const dyn_sde_opts *o)
{
    const double rtol = o->rtol > 0 ? o->rtol : 1e-3, atol = o->atol > 0 ? o->atol : 1e-6;
    double sum = 0.0;
    for (int i = 0; i < r->n; i++) {
        const double sc = atol + rtol * fmax(fabs(y[i]), fabs(r->ysmall[i]));
        const double e = (r->ysmall[i] - r->ybig[i]) / sc;
        sum += e * e;
    }
    return sqrt(sum / (r->n > 0 ? r->n : 1));
}

/* SRIW1's error norm: (delta E1 + E2) / (atol + rtol max(|y|, |y+|)) in the RMS norm, with
 * the weight delta = 1/6 of the drift's part (Rackauckas and Nie 2017). */
static double sri_error_norm(const sde_run *r, const double *y, const dyn_sde_opts *o)
{
    const double rtol = o->rtol > 0 ? o->rtol : 1e-3, atol = o->atol > 0 ? o->atol : 1e-6;
    double sum = 0.0;
    for (int i = 0; i < r->n; i++) {
        const double sc = atol + rtol * fmax(fabs(y[i]), fabs(r->ysmall[i]));
        const double e = (r->e1[i] / 6.0 + r->e2[i]) / sc;
        sum += e * e;
    }
    return sqrt(sum / (r->n > 0 ? r->n : 1));
}

static int solve_adaptive(sde_run *r, double t0, double t1, const dyn_sde_opts *o, double *y)
{
    dyn_result *res = r->res;
    const int n = r->n, m = r->m;
    const double span = t1 - t0;
    const double hmax = o->max_step > 0 ? fmin(o->max_step, span) : span;
    const long max_steps = o->max_steps > 0 ? o->max_steps : 10000000L;
    double h = o->h > 0 ? fmin(o->h, hmax) : 1e-3 * span;
    long k_out = 1, sample = 0, progress_countdown = 4096;
    double t = t0;
    while (t < t1) {
        double limit = t1;
        if (o->out_step > 0) {
            const double tk = t0 + (double)k_out * o->out_step;
            if (tk < t1 && t1 - tk > 1e-10 * o->out_step)
                limit = tk;
        }
        const int clipped = t + h >= limit || limit - (t + h) < 1e-10 * h;
        const double tn = clipped ? limit : t + h, hh = tn - t;
        if (hh <= 16.0 * 2.220446049250313e-16 * fmax(fabs(t), fabs(tn))) {
            res->fail_t = t;
            return dyn_result_fail(res, DYN_ERR_STEP_SIZE,
                                   "the step size fell to %g at t = %s (the noise or the "
                                   "tolerances ask too much)",
                                   hh, dyn_shortest(t).s);
        }
        if (res->stats.steps >= max_steps)
            return dyn_result_fail(res, DYN_ERR_MAX_STEPS,
                                   "%ld steps reached at t = %s (raise the step limit or the "
                                   "tolerances)",
                                   max_steps, dyn_shortest(t).s);
        const double tm = t + 0.5 * hh;
        if (dyn_bpath_at(&r->path, tn, r->wend) ||
            (!r->path.area && dyn_bpath_at(&r->path, tm, r->wmid)))
            return dyn_result_fail(res, DYN_ERR_CAPACITY,
                                   "more than %d points of the Brownian path ahead of t = %s "
                                   "(too many rejected steps)",
                                   DYN_SDE_MAX_POINTS, dyn_shortest(t).s);
        res->stats.steps++;
        double err;
        if (r->path.area) {
            if (sri_attempt(r, t, hh, y))
                return rhs_fail(r);
            err = sri_error_norm(r, y, o);
        } else {
            for (int j = 0; j < m; j++) {
                r->dw[j] = r->wend[j] - r->path.wc[j];
                r->dw1[j] = r->wmid[j] - r->path.wc[j];
                r->dw2[j] = r->wend[j] - r->wmid[j];
            }
            if (drift_diffusion(r, t, y) || rkmil_step(r, t, y, hh, r->dw, r->ybig) ||
                rkmil_step(r, t, y, 0.5 * hh, r->dw1, r->ymid) ||
                drift_diffusion(r, tm, r->ymid) ||
                rkmil_step(r, tm, r->ymid, 0.5 * hh, r->dw2, r->ysmall))
                return rhs_fail(r);
            err = error_norm(r, y, o);
        }
        if (!isfinite(err))
            err = 1e10;
        const double fac = err > 0 ? 0.9 * pow(err, -0.5) : 5.0;
        if (err > 1.0) {
            res->stats.rejected++;
            h = hh * fmax(0.2, fmin(0.9, fac));
            continue;
        }
        res->stats.accepted++;
        const int bad = first_nonfinite(r->ysmall, n);
        if (bad >= 0)
            return nonfinite_fail(r, tn, bad);
        int seg = r->ne > 0 ? segment_events(r, t, y, tm, r->ymid) : SEG_NONE;
        if (seg == SEG_NONE && r->ne > 0)
            seg = segment_events(r, tm, r->ymid, tn, r->ysmall);
        if (seg == SEG_FAIL)
            return res->status;
        if (seg == SEG_STOP)
            return stop_sample(r, o, sample + 1, y, &t);
        if (seg == SEG_RESET) {
            /* on from the event: W there joins the path (a bridge between known points) */
            if (r->t_ev < tn && dyn_bpath_at(&r->path, r->t_ev, r->wmid))
                return dyn_result_fail(res, DYN_ERR_CAPACITY,
                                       "more than %d points of the Brownian path ahead of t = %s",
                                       DYN_SDE_MAX_POINTS, dyn_shortest(t).s);
            dyn_bpath_advance(&r->path, r->t_ev);
            t = r->t_ev;
            res->t = t;
            res->h_last = r->t_ev - t;
            memcpy(y, r->yafter, (size_t)n * sizeof *y);
            if (o->output && o->out_step <= 0) {
                res->stats.samples++;
                if (o->output(++sample, t, y, o->output_ctx))
                    return dyn_result_fail(res, DYN_STOPPED, "output stopped the run at t = %g",
                                           t);
            }
            if (t == limit && o->out_step > 0)
                k_out++;
            continue;
        }
        memcpy(y, r->ysmall, (size_t)n * sizeof *y);
        dyn_bpath_advance(&r->path, tn);
        t = tn;
        res->t = t;
        res->h_last = hh;
        /* a step shortened to land on a sample does not hold the next one back */
        h = fmin(hmax, fmax(clipped ? h : hh * fmin(5.0, fac), hh * fmin(5.0, fac)));
        if (o->output && (o->out_step <= 0 || t == limit)) {
            if (t == limit && o->out_step > 0)
                k_out++;
            res->stats.samples++;
            if (o->output(++sample, t, y, o->output_ctx))
                return dyn_result_fail(res, DYN_STOPPED, "output stopped the run at t = %g", t);
        } else if (t == limit && o->out_step > 0) {
            k_out++;
        }
        if (o->progress && --progress_countdown == 0) {
            progress_countdown = 4096;
            if (o->progress(t, (t - t0) / span, o->progress_ctx))
                return dyn_result_fail(res, DYN_CANCELLED, "cancelled at t = %g", t);
        }
    }
    return DYN_OK;
}

int dyn_sde_solve(dyn_sde_method method, const dyn_sde *sde, double t0, double t1,
                  const double *y0, double *y, double *work, const dyn_sde_opts *opts,
                  dyn_result *res)
{
    memset(res, 0, sizeof *res);
    res->t = t0;
    res->fail_index = -1;
    const dyn_sde_opts zero = {0};
    const dyn_sde_opts *o = opts ? opts : &zero;
    const int n = sde->sys.n, m = sde->n_noise;
    if (n < 1 || m < 0 || !(t1 > t0) || !isfinite(t0) || !isfinite(t1) || (m > 0 && !sde->noise))
        return dyn_result_fail(res, DYN_ERR_ARG,
                               "a system with noise needs n >= 1 states, noise slots when "
                               "n_noise > 0, and a span t0 < t1 (got n = %d, n_noise = %d, "
                               "%g:%g)",
                               n, m, t0, t1);
    const int adaptive_method = method == DYN_SDE_RKMIL || method == DYN_SDE_SRIW1;
    const int fixed = !adaptive_method || o->fixed;
    if (fixed && !(o->h > 0))
        return dyn_result_fail(res, DYN_ERR_ARG,
                               "%s takes fixed steps: give the step h > 0 (got %g)",
                               method == DYN_SDE_EM      ? "Euler-Maruyama"
                               : method == DYN_SDE_MAP   ? "a discrete map"
                               : method == DYN_SDE_SRIW1 ? "sriw1"
                                                         : "rkmil",
                               o->h);
    const int ne = o->events ? o->n_events : 0;
    if (ne < 0 || (ne > 0 && (method == DYN_SDE_MAP || method == DYN_SDE_SRIW1)))
        return dyn_result_fail(res, DYN_ERR_ARG,
                               "events with noise are located by Euler-Maruyama and rkmil, not "
                               "by %s (got %d events)",
                               method == DYN_SDE_MAP ? "a discrete map" : "sriw1", ne);
    for (int i = 0; i < ne; i++)
        if (!o->events[i].g)
            return dyn_result_fail(res, DYN_ERR_ARG, "event %d has no function g", i);
    if (method != DYN_SDE_EM && method != DYN_SDE_MAP && o->jump)
        return dyn_result_fail(res, DYN_ERR_ARG,
                               "Markov states jump at the start of each step, with probability "
                               "rate*h: %s cannot take them; use Euler-Maruyama (method euler)",
                               method == DYN_SDE_SRIW1 ? "sriw1" : "rkmil");
    if (adaptive_method && sde->noise_class == DYN_NOISE_GENERAL)
        return dyn_result_fail(res, DYN_ERR_ARG,
                               "%s needs a right-hand side affine in Wiener noise that is "
                               "additive, scalar or diagonal (no normal() or ran(), no noise "
                               "coefficient that depends on a state another noise moves): "
                               "use Euler-Maruyama (method euler)",
                               method == DYN_SDE_SRIW1 ? "sriw1" : "rkmil");
    sde_run r = {0};
    r.sde = sde;
    r.n = n;
    r.m = m;
    r.res = res;
    r.path.m = m;
    r.path.area = method == DYN_SDE_SRIW1;
    r.path.rng = &r.rng;
    dyn_rng_init(&r.rng, o->seed, o->stream);
    const size_t N = (size_t)n, M = (size_t)m;
    double *p = work;
    r.a = p, p += N;
    r.kk = p, p += N;
    r.c0 = p, p += N;
    r.c1 = p, p += N;
    r.ymid = p, p += N;
    r.ybig = p, p += N;
    r.ysmall = p, p += N;
    r.e1 = p, p += N;
    r.e2 = p, p += N;
    double *state = p;
    p += N;
    r.b = p, p += M * N;
    r.dw = p, p += M + 1;
    r.dw1 = p, p += M + 1;
    r.dw2 = p, p += M + 1;
    r.wend = p, p += M + 1;
    r.wmid = p, p += M + 1;
    r.path.wc = p, p += M + 1;
    r.i10 = p, p += M + 1;
    r.path.anew = p, p += M + 1;
    r.path.tq = p, p += DYN_SDE_MAX_POINTS;
    r.path.wq = p, p += (size_t)DYN_SDE_MAX_POINTS * M;
    r.path.aq = p, p += (size_t)DYN_SDE_MAX_POINTS * M;
    r.sri_work = p, p += DYN_SRI_WORK(N, M);
    r.path.tc = t0;
    r.t0 = t0;
    r.t1 = t1;
    r.ev = o->events;
    r.xppaut_globals = o->xppaut_globals;
    r.ne = ne;
    r.sink = (dyn_event_sink){o->events, o->on_event, o->event_ctx, res};
    r.reset_idx = -1;
    if (ne > 0) {
        r.memo = p, p += 2 * (size_t)ne;
        r.casc = p, p += 2 * (size_t)ne;
        r.hits = p, p += 3 * (size_t)dyn_events_max_hits(ne, EVENT_SAMPLES);
        r.coef = p, p += 2 * N;
        r.ybefore = p, p += N;
        r.yafter = p, p += N;
        r.ev_work = p;
    }
    res->event_index = -1;
    for (int j = 0; j < m; j++)
        r.path.wc[j] = 0.0;
    memcpy(state, y0, N * sizeof *state);
    const int bad = first_nonfinite(state, n);
    if (bad >= 0) {
        res->fail_index = bad;
        return dyn_result_fail(res, DYN_ERR_NONFINITE, "initial state %d is not finite (%g)",
                               bad, state[bad]);
    }
    if (ne > 0)
        dyn_events_start(o->events, ne, sde->sys.par, t0, state, r.memo);
    int status = DYN_OK;
    if (o->output) {
        res->stats.samples++;
        if (o->output(0, t0, state, o->output_ctx))
            status = dyn_result_fail(res, DYN_STOPPED, "output stopped the run at t = %g", t0);
    }
    if (status == DYN_OK)
        status = fixed ? solve_fixed(&r, method, t0, t1, o, state)
                       : solve_adaptive(&r, t0, t1, o, state);
    for (int j = 0; j < m; j++)
        sde->noise[j] = 0.0;
    if (y)
        memcpy(y, state, N * sizeof *y);
    res->status = status;
    return status;
}
