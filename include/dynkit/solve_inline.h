/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/solve_inline.h — dyn_solve for the explicit FSAL pairs compiled into the caller.
 *
 * dyn_solve (solve.h) calls the right-hand side through a pointer and runs every table through
 * one generic stage loop. dyn_solve_inline is the same solve as a static inline function for
 * the embedded pairs with first-same-as-last of 4 or 7 stages (bs23, dp45): when the
 * right-hand side is defined in the calling translation unit and sys is built there, the
 * compiler can inline it into the stage loop, whose stage count is a compile-time constant
 * (gcc 12 -O3 does when the right-hand side is declared always_inline; a plain static one stays a
 * direct call). It follows dyn_solve step for step (HNW I sec. II.4-II.6, IV.2, as dyn_solve
 * does; see src/ode/solve.c): the initial step of HINIT, the stage combinations y + h * (sum
 * of the non-zero a_ij k_j, left to right; a single power-of-two coefficient folded into h)
 * from a plan of each row's non-zero terms as in the library's stage loop, Hairer's error norm
 * sum_q e_q k_q from 0.0, the PI controller of DOPRI5 (fac = err^expo / err_old^beta / safety,
 * clamped; no growth right after a rejection), the last step shortened to land on t1 when t +
 * 1.01 h passes it, DOPRI5's stiffness test every stiff_check accepted steps, and output at
 * the requested times from the step's end state or the same dense output (dyn_dense_eval). So
 * the results are dyn_solve's bit for bit: states, samples, counters, messages
 * (tests/test_solve_inline.c checks it).
 *
 * Contract: exactly dyn_solve's (arguments, workspace dyn_solve_work_size). It takes the
 * inline path for such a table with scalar tolerances (rtol >= DYN_MIN_RTOL), no events,
 * step callback, recorder, trace or progress callback, and output either at every step or
 * at a list of times (out_times); everything else, including bad arguments, goes to
 * dyn_solve, so it never behaves differently.
 * Cost: code size (the right-hand side is inlined once per stage, per call site).
 */
#ifndef DYNKIT_SOLVE_INLINE_H
#define DYNKIT_SOLVE_INLINE_H

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dynkit/ode_inline.h" /* dyn_inl_is_pow2 */
#include "dynkit/solve.h"

#ifdef __cplusplus
extern "C" {
#endif

#if defined(__GNUC__)
#define DYN_SINL static inline __attribute__((always_inline))
#else
#define DYN_SINL static inline
#endif
#ifdef __cplusplus
#define DYN_SRESTRICT __restrict
#else
#define DYN_SRESTRICT restrict
#endif

#define DYN_SINL_MAX_STAGES 7

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#define DYN_SINL_SCALAR(v) __asm__("" : "+x"(v))
#elif defined(__GNUC__) && defined(__aarch64__)
#define DYN_SINL_SCALAR(v) __asm__("" : "+w"(v))
#else
#define DYN_SINL_SCALAR(v) ((void)0)
#endif

/* The PI controller of src/ode/step_control.c (dyn_controller_*), the same operations. */
typedef struct dyn_sinl_ctl {
    double safety, beta, fac_min, fac_max, expo, err_old, err_old_pow;
} dyn_sinl_ctl;

DYN_SINL void dyn_sinl_ctl_init(dyn_sinl_ctl *c, int q, const dyn_solve_opts *o)
{
    c->safety = o->safety > 0.0 ? o->safety : 0.9;
    c->beta = o->beta < 0.0 ? 0.0 : o->beta > 0.0 ? o->beta : 0.04;
    c->fac_min = o->fac_min > 0.0 ? o->fac_min : 0.2;
    c->fac_max = o->fac_max > 0.0 ? o->fac_max : 10.0;
    c->expo = 1.0 / (double)((q > 0 ? q : 1) + 1) - 0.75 * c->beta;
    c->err_old = 1e-4;
    c->err_old_pow = c->beta == 0.0 ? 1.0 : pow(c->err_old, c->beta);
}

DYN_SINL double dyn_sinl_ctl_accept(dyn_sinl_ctl *c, double h, double err, int rejected_before)
{
    double fac = pow(err, c->expo) / c->err_old_pow / c->safety;
    if (!(fac >= 1.0 / c->fac_max))
        fac = 1.0 / c->fac_max;
    if (fac > 1.0 / c->fac_min)
        fac = 1.0 / c->fac_min;
    c->err_old = fmax(err, 1e-4);
    c->err_old_pow = c->beta == 0.0 ? 1.0 : pow(c->err_old, c->beta);
    double hnew = h / fac;
    if (rejected_before && hnew > h)
        hnew = h;
    return hnew;
}

DYN_SINL double dyn_sinl_ctl_reject(const dyn_sinl_ctl *c, double h, double err)
{
    if (!isfinite(err))
        return 0.25 * h;
    double fac = pow(err, c->expo) / c->safety;
    if (fac > 1.0 / c->fac_min)
        fac = 1.0 / c->fac_min;
    if (!(fac > 1.0))
        fac = 1.0 / 0.9;
    return h / fac;
}

/* RMS of v / (atol + rtol max(|y|, |y|)) (dyn_initial_step's norm). */
DYN_SINL double dyn_sinl_rms(double rtol, double atol, int n, const double *y, const double *v)
{
    double sum = 0.0;
    for (int i = 0; i < n; i++) {
        const double r = v[i] / (atol + rtol * fmax(fabs(y[i]), fabs(y[i])));
        sum += r * r;
    }
    return sqrt(sum / n);
}

DYN_SINL double dyn_sinl_stage_time(double t, double c, double h, double tend)
{
    const double ti = t + c * h;
    return ti > tend ? tend : ti;
}

/* The non-zero terms of each row of a (rows 0 .. S-1) and of b (row S), as the library's
 * stage plan (src/ode/rk_stages.h): terms first[r] .. first[r + 1] - 1 are coef * kp, with
 * kp pointing at the k_j they multiply. */
typedef struct dyn_sinl_plan {
    int first[DYN_SINL_MAX_STAGES + 2];
    double coef[DYN_SINL_MAX_STAGES * (DYN_SINL_MAX_STAGES + 1)];
    const double *kp[DYN_SINL_MAX_STAGES * (DYN_SINL_MAX_STAGES + 1)];
    int fold[DYN_SINL_MAX_STAGES + 1]; /* the row's only term is a power of two */
} dyn_sinl_plan;

DYN_SINL void dyn_sinl_plan_init(dyn_sinl_plan *p, const dyn_tableau *m, int S, const double *k,
                                 int n)
{
    int t = 0;
    for (int r = 0; r <= S; r++) {
        const double *row = r < S ? m->a + (size_t)r * (size_t)S : m->b;
        const int len = r < S ? r : S;
        p->first[r] = t;
        for (int j = 0; j < len; j++)
            if (row[j] != 0.0) {
                p->coef[t] = row[j];
                p->kp[t] = k + (size_t)j * (size_t)n;
                t++;
            }
        p->fold[r] = t - p->first[r] == 1 && dyn_inl_is_pow2(p->coef[t - 1]);
    }
    p->first[S + 1] = t;
}

/* out = y + h * (sum of the row's terms, left to right), or y + (h c) k for a single
 * power-of-two term: the library's arithmetic. Returns the number of terms. */
DYN_SINL int dyn_sinl_combine(const dyn_sinl_plan *p, int r, int n, double h,
                              const double *DYN_SRESTRICT y, double *DYN_SRESTRICT out)
{
    const int t0 = p->first[r], nt = p->first[r + 1] - t0;
    const double *c = p->coef + t0;
    const double *const *kp = p->kp + t0;
    if (nt == 0)
        return 0;
    if (p->fold[r]) {
        const double hc = h * c[0];
        const double *k0 = kp[0];
        for (int q = 0; q < n; q++) {
            double v = y[q] + hc * k0[q];
            DYN_SINL_SCALAR(v);
            out[q] = v;
        }
        return 1;
    }
    for (int q = 0; q < n; q++) {
        double acc = c[0] * kp[0][q];
        for (int t = 1; t < nt; t++)
            acc += c[t] * kp[t][q];
        double v = y[q] + h * acc;
        DYN_SINL_SCALAR(v);
        out[q] = v;
    }
    return nt;
}

#if defined(__GNUC__)
#define DYN_SINL_COLD static __attribute__((noinline, cold, unused))
#else
#define DYN_SINL_COLD static
#endif

/* DOPRI5's |h lambda| from stage j (c = 1) and f(t + h, ynew) = k_{S-1} (FSAL), as
 * erk_stiffness; out of line (once every stiff_check steps), so that the step loop stays
 * small enough for the right-hand side to be inlined into it. */
DYN_SINL_COLD double dyn_sinl_stiffness(const dyn_tableau *m, int S, int n, double hn,
                                        const double *k, const double *ycur, const double *ynew,
                                        double *Yj)
{
    const size_t N = (size_t)n;
    const int j = m->stiff_stage;
    const double *f1 = k + (size_t)(S - 1) * N, *kj = k + (size_t)j * N;
    const double *row = m->a + (size_t)j * (size_t)S;
    for (int i = 0; i < n; i++) {
        double acc = 0.0;
        for (int p = 0; p < j; p++)
            if (row[p] != 0.0)
                acc += row[p] * k[(size_t)p * N + (size_t)i];
        Yj[i] = ycur[i] + hn * acc;
    }
    double num = 0.0, den = 0.0;
    for (int i = 0; i < n; i++) {
        num += (f1[i] - kj[i]) * (f1[i] - kj[i]);
        den += (ynew[i] - Yj[i]) * (ynew[i] - Yj[i]);
    }
    return den > 0.0 ? fabs(hn) * sqrt(num / den) : -1.0;
}

/* The dense output of the step (erk_dense): the cubic Hermite part and the corrections. */
DYN_SINL_COLD void dyn_sinl_dense(const dyn_tableau *m, int S, int q, int n, double hn,
                                  const double *k, const double *ycur, const double *ynew,
                                  double *coef)
{
    const size_t N = (size_t)n;
    const double *f0 = k, *f1 = k + (size_t)(S - 1) * N;
    for (size_t i = 0; i < N; i++) {
        const double dy = ynew[i] - ycur[i];
        coef[i] = ycur[i];
        coef[N + i] = dy;
        coef[2 * N + i] = hn * f0[i] - dy;
        coef[3 * N + i] = 2.0 * dy - hn * (f0[i] + f1[i]);
    }
    for (int jj = 4; jj <= q; jj++) {
        const double *D = m->dense + (size_t)(jj - 4) * (size_t)m->dense_stages;
        double *cj = coef + (size_t)jj * N;
        for (size_t i = 0; i < N; i++) {
            double acc = 0.0;
            for (int r = 0; r < m->dense_stages; r++)
                if (D[r] != 0.0)
                    acc += D[r] * k[(size_t)r * N + i];
            cj[i] = hn * acc;
        }
    }
}

/* The inline solve for an S-stage FSAL pair. */
DYN_SINL int dyn_sinl_solve(const int S, const dyn_tableau *m, dyn_rhs_fn f, void *par, const int n,
                            double t0, double t1, const double *y0, double *y, double *work,
                            const dyn_solve_opts *o, double rtol, double atol, dyn_result *res)
{
    const size_t N = (size_t)n;
    const int q = m->dense_degree > 3 && m->dense ? m->dense_degree : 3;
    /* the workspace of dyn_solve: k (S) | Y | tmp | ycur ynew yout ytmp | coef (q + 1) */
    double *k = work, *Y = k + (size_t)S * N, *Yj = Y + N;
    double *ycur = Yj + N, *ynew = ycur + N, *yout = ynew + N, *ytmp = yout + N;
    double *coef = ytmp + N;
    const int mode = o->out_times ? 2 : 0;
    const double *times = o->out_times;
    const long count = mode == 2 ? o->n_out_times : 0;
    long next = 0, kout = 0, rhs_calls = 0;
    const dyn_output_fn output = o->output;
    double t = t0, h;
    int rc = 0, k0_valid = 0;
    memmove(ycur, y0, N * sizeof *ycur);
    if (mode == 0 || (count > 0 && times[0] == t0)) {
        do {
            if (output) {
                res->stats.samples++;
                if (output(kout++, t0, ycur, o->output_ctx)) {
                    res->status = DYN_STOPPED;
                    snprintf(res->message, sizeof res->message, "output stopped the run at t = %g",
                             t0);
                    goto finish;
                }
            }
            if (mode != 0)
                next++;
        } while (mode != 0 && next < count && times[next] == t0);
    }
    {
        const double t_end = t1;
        double hmax = t_end - t0;
        if (o->max_step > 0.0)
            hmax = fmin(hmax, o->max_step);
        dyn_sinl_ctl ctl;
        dyn_sinl_ctl_init(&ctl, m->error_order, o);
        if (o->initial_step > 0.0) {
            h = fmin(o->initial_step, hmax);
        } else {
            /* HINIT (dyn_initial_step) */
            rhs_calls++;
            rc = f(t0, ycur, k, par);
            if (rc) {
                res->fail_t = t0;
                goto rhs_failed;
            }
            k0_valid = 1;
            const double d0 = dyn_sinl_rms(rtol, atol, n, ycur, ycur);
            const double d1 = dyn_sinl_rms(rtol, atol, n, ycur, k);
            double h0 =
                (d0 < 1e-5 || d1 < 1e-5 || !isfinite(d0) || !isfinite(d1)) ? 1e-6 : 0.01 * d0 / d1;
            h0 = fmin(h0, hmax);
            for (int i = 0; i < n; i++)
                ytmp[i] = ycur[i] + h0 * k[i];
            rhs_calls++;
            const double ta = fmin(t0 + h0, t1);
            rc = f(ta, ytmp, ynew, par);
            if (rc) {
                res->fail_t = ta;
                goto rhs_failed;
            }
            for (int i = 0; i < n; i++)
                ytmp[i] = ynew[i] - k[i];
            const double d2 = dyn_sinl_rms(rtol, atol, n, ycur, ytmp) / h0;
            const double dmax = fmax(d1, d2);
            double h1;
            if (!(dmax > 1e-15) || !isfinite(dmax))
                h1 = fmax(1e-6, h0 * 1e-3);
            else
                h1 =
                    pow(0.01 / dmax, 1.0 / (double)((m->error_order > 0 ? m->error_order : 1) + 1));
            h = fmin(fmin(100.0 * h0, h1), hmax);
            if (!(h > 0.0))
                h = fmin(1e-6, hmax);
        }
        {
            const long stiff_every = o->stiff_check > 0 ? o->stiff_check : 1000;
            const long max_steps = o->max_steps;
            const int stiff_test = m->stiff_bound > 0.0 && m->stiff_stage >= 0 &&
                                   m->stiff_stage < S && m->c[m->stiff_stage] == 1.0;
            long stiff_countdown = stiff_every;
            int stiff_count = 0, nonstiff_count = 0, rejected_before = 0;
            const double *c = m->c, *e = m->e;
            dyn_dense d = {0.0, 0.0, n, q, coef};
            dyn_sinl_plan plan;
            dyn_sinl_plan_init(&plan, m, S, k, n);
            while (t < t_end) {
                double hn, tnext;
                int last = 0;
                if (t + 1.01 * h >= t_end) {
                    hn = t_end - t;
                    tnext = t_end;
                    last = 1;
                } else {
                    hn = h;
                    tnext = t + h;
                }
                if (max_steps > 0 && res->stats.steps >= max_steps) {
                    res->status = DYN_ERR_MAX_STEPS;
                    snprintf(
                        res->message, sizeof res->message,
                        "reached the limit of %ld steps at t = %.17g (h = %g): raise the limit, "
                        "loosen the tolerances, or use a method for stiff problems",
                        max_steps, t, h);
                    goto finish;
                }
                res->stats.steps++;
                /* the stages (dyn_rk_stages_from): k_0 is f(t, y) already after FSAL */
                const int first = k0_valid && c[0] == 0.0;
#define DYN_SINL_STAGE(I)                                                                          \
    if ((I) < S) {                                                                                 \
        const int I_ = (I) < S ? (I) : 0;                                                          \
        const double *Yi = ycur;                                                                   \
        if (I_ > 0 && dyn_sinl_combine(&plan, I_, n, hn, ycur, Y) > 0)                             \
            Yi = Y;                                                                                \
        if (I_ >= first) {                                                                         \
            const double ti = dyn_sinl_stage_time(t, c[I_], hn, t1);                               \
            rc = f(ti, Yi, k + (size_t)I_ * N, par);                                               \
            if (rc) {                                                                              \
                rhs_calls += I_ + 1 - first;                                                       \
                res->fail_t = ti;                                                                  \
                goto rhs_failed;                                                                   \
            }                                                                                      \
        }                                                                                          \
    }
                DYN_SINL_STAGE(0)
                DYN_SINL_STAGE(1)
                DYN_SINL_STAGE(2)
                DYN_SINL_STAGE(3)
                DYN_SINL_STAGE(4)
                DYN_SINL_STAGE(5)
                DYN_SINL_STAGE(6)
#undef DYN_SINL_STAGE
                rhs_calls += S - first;
                k0_valid = 1;
                dyn_sinl_combine(&plan, S, n, hn, ycur, ynew);
                double finite = 0.0, s5 = 0.0, err;
                for (int i = 0; i < n; i++)
                    finite += ynew[i] - ynew[i];
                if (finite != 0.0) {
                    err = INFINITY;
                } else {
                    for (int i = 0; i < n; i++) {
                        double ei = 0.0;
                        for (int j = 0; j < S; j++)
                            if (e[j] != 0.0)
                                ei += e[j] * k[(size_t)j * N + (size_t)i];
                        const double sk = atol + rtol * fmax(fabs(ycur[i]), fabs(ynew[i]));
                        const double r = ei / sk;
                        s5 += r * r;
                    }
                    err = fabs(hn) * sqrt(s5 / n);
                }
                if (!(err <= 1.0)) {
                    res->stats.rejected++;
                    rejected_before = 1;
                    h = dyn_sinl_ctl_reject(&ctl, hn, err);
                    const double hmin = 16.0 * DBL_EPSILON *
                                        fmax(fabs(t), fmax(DBL_EPSILON * (t_end - t0), DBL_MIN));
                    if (!(h >= hmin) || t + h == t) {
                        int bad = 0;
                        while (bad < n && isfinite(ynew[bad]))
                            bad++;
                        if (bad < n) {
                            res->fail_t = tnext;
                            res->fail_index = bad;
                            res->status = DYN_ERR_NONFINITE;
                            snprintf(res->message, sizeof res->message,
                                     "state %d became not finite at t = %.17g for every step size "
                                     "down to %g",
                                     bad, tnext, hn);
                        } else {
                            res->fail_t = t;
                            res->status = DYN_ERR_STEP_SIZE;
                            snprintf(res->message, sizeof res->message,
                                     "step size underflow at t = %.17g: the error test fails with "
                                     "h = %g (a singularity, a discontinuity, or tolerances below "
                                     "rounding)",
                                     t, hn);
                        }
                        goto finish;
                    }
                    continue;
                }
                res->stats.accepted++;
                const int stiff_due = --stiff_countdown == 0;
                if (stiff_due)
                    stiff_countdown = stiff_every;
                if (stiff_test && (stiff_due || stiff_count > 0)) {
                    const double hl = dyn_sinl_stiffness(m, S, n, hn, k, ycur, ynew, Yj);
                    if (hl > m->stiff_bound) {
                        nonstiff_count = 0;
                        if (++stiff_count == 15 && !res->stiff) {
                            res->stiff = 1;
                            res->stiff_t = t;
                            snprintf(
                                res->stiff_message, sizeof res->stiff_message,
                                "the problem looks stiff from t = %.6g: %s's step size is "
                                "limited by stability (|h lambda| > %g for %d steps in a row), "
                                "not by accuracy",
                                t, m->name, m->stiff_bound, 15);
                        }
                    } else if (hl >= 0.0 && ++nonstiff_count == 6) {
                        stiff_count = 0;
                    }
                }
                if (mode == 2 && next < count && times[next] < tnext) {
                    dyn_sinl_dense(m, S, q, n, hn, k, ycur, ynew, coef);
                    d.t0 = t;
                    d.h = hn;
                }
                while (mode == 2 && next < count && times[next] <= tnext) {
                    const double to = times[next];
                    const double *yo = ynew;
                    if (to != tnext) {
                        dyn_dense_eval(&d, to, yout);
                        yo = yout;
                    }
                    next++;
                    if (output) {
                        res->stats.samples++;
                        if (output(kout++, to, yo, o->output_ctx)) {
                            res->status = DYN_STOPPED;
                            snprintf(res->message, sizeof res->message,
                                     "output stopped the run at t = %g", to);
                            goto finish;
                        }
                    }
                }
                memcpy(k, k + (size_t)(S - 1) * N, N * sizeof *k); /* FSAL */
                memcpy(ycur, ynew, N * sizeof *ycur);
                t = tnext;
                res->h_last = hn;
                if (mode == 0 && output) {
                    res->stats.samples++;
                    if (output(kout++, t, ycur, o->output_ctx)) {
                        res->status = DYN_STOPPED;
                        snprintf(res->message, sizeof res->message,
                                 "output stopped the run at t = %g", t);
                        goto finish;
                    }
                }
                h = fmin(dyn_sinl_ctl_accept(&ctl, hn, err, rejected_before), hmax);
                if (last)
                    h = fmax(h, hn);
                rejected_before = 0;
            }
        }
    } /* a block, so that no goto jumps past an initialisation (C++) */
    goto finish;

rhs_failed:
    res->rhs_status = rc;
    res->status = DYN_ERR_RHS;
    snprintf(res->message, sizeof res->message,
             "the right-hand side failed at t = %.17g (status %d)", res->fail_t, rc);

finish:
    res->t = t;
    res->stats.rhs_calls = rhs_calls;
    if (y && y != ycur)
        memcpy(y, ycur, N * sizeof *y);
    return res->status;
}

/* dyn_solve with the step loop compiled at the call site: same contract, same results bit
 * for bit (see the top of this header for what takes the inline path). */
DYN_SINL int dyn_solve_inline(const dyn_tableau *m, const dyn_system *sys, double t0, double t1,
                              const double *y0, double *y, double *work, const dyn_solve_opts *opts,
                              dyn_result *res)
{
    if (!sys || !m)
        return dyn_solve(m, sys, t0, t1, y0, y, work, opts, res);
    dyn_solve_opts no_opts;
    if (!opts)
        memset(&no_opts, 0, sizeof no_opts);
    const dyn_solve_opts *o = opts ? opts : &no_opts;
    /* read before any call, so that the compiler sees f as the constant it is */
    const dyn_rhs_fn f = sys->f;
    const int n = sys->n;
    void *const par = sys->par;
    const double rtol = o->rtol != 0.0 ? o->rtol : DYN_DEFAULT_RTOL;
    const double atol = o->atol != 0.0 ? o->atol : DYN_DEFAULT_ATOL;
    const int S = m->stages;
    int plain = m->kind == DYN_KIND_EMBEDDED_RK && m->e && !m->e3 && m->fsal && S >= 2 &&
                S <= DYN_SINL_MAX_STAGES && m->dense_stages <= S && f && n > 0 && y0 && work &&
                isfinite(t0) && isfinite(t1) && t1 > t0 && rtol >= DYN_MIN_RTOL && isfinite(rtol) &&
                atol >= 0.0 && isfinite(atol) && !o->rtolv && !o->atolv && o->max_step >= 0.0 &&
                o->initial_step >= 0.0 && !(o->events && o->n_events) && o->n_events >= 0 &&
                !o->step && !o->record && !o->trace && !o->progress && o->out_step == 0.0 &&
                !o->jac_banded;
    if (plain && o->out_times)
        for (long i = 0; i < o->n_out_times; i++)
            if (!(o->out_times[i] >= t0 && o->out_times[i] <= t1) ||
                (i > 0 && o->out_times[i] < o->out_times[i - 1]))
                plain = 0;
    if (plain)
        for (int i = 0; i < n; i++)
            if (!isfinite(y0[i]))
                plain = 0;
    if (!plain)
        return dyn_solve(m, sys, t0, t1, y0, y, work, opts, res);
    dyn_result local;
    if (!res)
        res = &local;
    memset(res, 0, sizeof *res);
    res->t = t0;
    res->fail_t = NAN;
    res->fail_index = -1;
    res->event_index = -1;
    res->stiff_t = NAN;
    /* the stage counts of bs23 (4) and dp45 (7), each compiled once; other FSAL pairs go to
     * dyn_solve (a copy of the solve per stage count would make the caller so large that
     * compilers stop inlining the right-hand side into it) */
    if (S == 4)
        return dyn_sinl_solve(4, m, f, par, n, t0, t1, y0, y, work, o, rtol, atol, res);
    if (S == 7)
        return dyn_sinl_solve(7, m, f, par, n, t0, t1, y0, y, work, o, rtol, atol, res);
    return dyn_solve(m, sys, t0, t1, y0, y, work, opts, res);
}

#undef DYN_SINL
#undef DYN_SINL_COLD
#undef DYN_SINL_SCALAR
#undef DYN_SRESTRICT

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_SOLVE_INLINE_H */
