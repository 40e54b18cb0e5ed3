/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/solve_inline.h — dyn_solve for the embedded pairs bs23, dp45 and dop853 compiled
 * into the caller.
 *
 * dyn_solve_inline is dyn_solve as a static inline function: when the right-hand side is
 * defined in the calling translation unit and sys is built there, the compiler can inline it
 * into the stage loop. The step of each pair is the generated kernel of dynkit/erk_kernels.h
 * (its coefficients constants, its zero terms gone), compiled once per pair. It follows
 * dyn_solve step for step (HNW I sec. II.4-II.6, IV.2, as dyn_solve does; see
 * src/ode/solve.c): the initial step of HINIT, the stage combinations (y + h * (sum of the
 * non-zero a_ij k_j but the last, left to right)) + (h a_il) k_l (src/ode/rk_stages.h), Hairer's
 * error norm (DOP853's for dop853), the PI controller of DOPRI5 (h_new / h = safety err_old^beta /
 * err^expo, clamped; no growth right after a rejection), the last step shortened to land on t1
 * when t + 1.01 h passes it, DOPRI5's stiffness test every stiff_check accepted steps, output at
 * every step, on a grid or at requested times from the step's end state or the same dense
 * output (dyn_dense_eval), and the progress callback. So the results are dyn_solve's bit for bit:
 * states, samples, counters, messages (tests/test_solve_inline.c checks it against the
 * general driver).
 *
 * The library's dyn_solve runs the same code (src/ode/solve_fast.c, dyn_sinl_try) with the
 * right-hand side behind its pointer for the same cases, and its general driver for the rest.
 *
 * Contract: exactly dyn_solve's (arguments, workspace dyn_solve_work_size). The fast path
 * takes a table whose coefficients are those of bs23, dp45 or dop853, with scalar tolerances
 * (rtol >= DYN_MIN_RTOL), no events, step callback, recorder or trace, and output at every
 * step, on a grid (out_step) or at a list of times (out_times); everything else, including
 * bad arguments, goes to dyn_solve, so it never behaves differently. Bit for bit needs the
 * library's rounding in the caller's translation unit: no contraction of a*b + c into fused
 * multiply-adds (ISO C mode, -ffp-contract=off, or a target without FMA; see
 * dynkit/ode_inline.h).
 * Cost: code size (the right-hand side is inlined once per stage, per pair, per call site).
 */
#ifndef DYNKIT_SOLVE_INLINE_H
#define DYNKIT_SOLVE_INLINE_H

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "dynkit/io.h" /* dyn_shortest: numbers in messages */
#include "dynkit/erk_kernels.h"
#include "dynkit/ode_inline.h" /* dyn_inl_nonfinite */
#include "dynkit/solve.h"

#ifdef __cplusplus
extern "C" {
#endif

#if defined(__GNUC__)
#define DYN_SINL static inline __attribute__((always_inline))
#else
#define DYN_SINL static inline
#endif
/* How to declare a right-hand side for dyn_solve_inline, so that compilers inline it into
 * the stage loop (a plain static function may stay a call: the loop is large):
 *     DYN_INLINE_RHS int my_rhs(double t, const double *y, double *dydt, void *par) ... */
#if defined(__GNUC__)
#define DYN_INLINE_RHS static inline __attribute__((always_inline))
#else
#define DYN_INLINE_RHS static inline
#endif
#ifdef __cplusplus
#define DYN_SRESTRICT __restrict
#else
#define DYN_SRESTRICT restrict
#endif

/* DYN_SINL_STORED(p, n): the n values at p are read from memory here (an empty asm with
 * them as operands), so that the right-hand side's stores of a stage's derivatives stay at
 * that stage. Without it gcc 12 kept the derivatives in registers to the end of the step
 * and stored them there as packed pairs (SLP vectorisation): dp45 took 68 instead of 63 ns
 * per attempted step on van der Pol, dop853 about 3% more (docs/performance.md). clang
 * stores them at the stage anyway and handles the operands badly (20% slower with them),
 * so it gets nothing. */
#if defined(__GNUC__) && !defined(__clang__)
#define DYN_SINL_STORED(p, n)                                                                      \
    do {                                                                                           \
        for (int q_ = 0; q_ < (n); q_++)                                                           \
            __asm__("" : : "m"((p)[q_]));                                                          \
    } while (0)
#else
#define DYN_SINL_STORED(p, n) ((void)0)
#endif

/* The PI controller of DOPRI5 (Gustafsson 1991; HNW I sec. II.4, HNW II sec. IV.2), for
 * both drivers (src/ode/solve.c uses it too):
 *     h_new = h * clamp(safety * err_old^beta / err^(1/(q+1) - 0.75 beta), fac_min, fac_max),
 * with err_old = max(error of the previous accepted step, 1e-4) (1e-4 at the start), no
 * growth right after a rejection, and h * max(fac_min, safety / err^(1/(q+1) - 0.75 beta))
 * (0.9 h when that would not shrink it) after a rejection. This is DOPRI5's
 * h / clamp(err^expo / err_old^beta / safety, 1/fac_max, 1/fac_min), computed in base-2
 * logarithms: 2^(log2 safety + beta log2 err_old - expo log2 err), so that the
 * step-to-step dependency chain holds one log2, one multiply-add and one exp2 instead of a
 * pow and three divisions (the part from err_old is summed off that chain). The step sizes
 * differ from the quotient form in the last bits only. The explicit pairs give the square
 * of the error norm (no square root on that chain either): log2 err = log2(err^2) / 2. */
typedef struct dyn_sinl_ctl {
    double beta;    /* PI term (0.04); 0: the classical I controller */
    double fac_min; /* smallest h_new / h (0.2) */
    double fac_max; /* largest h_new / h (10) */
    double expo;    /* 1/(q + 1) - 0.75 beta, q = the error order */
    double log2_safety, log2_floor; /* log2(safety (the pair's, or 0.9)), log2(1e-4) */
    double log2_scale; /* 1, or 1/2 when the errors given are squared norms */
    double expo_scaled; /* expo log2_scale: the exponent on log2 of the error as given */
    double log2_gain; /* log2(safety) + beta log2(err_old) */
} dyn_sinl_ctl;

/* The controller's exponent 1/(q + 1) - 0.75 beta: dyn_solve refuses a beta that makes it
 * <= 0 (the step would shrink as the error falls). */
DYN_SINL double dyn_sinl_ctl_exponent(int q, double beta)
{
    return 1.0 / (double)((q > 0 ? q : 1) + 1) - 0.75 * beta;
}

/* The safety factor of a solve: the caller's, else the pair's own (0: the default 0.9). */
DYN_SINL double dyn_sinl_ctl_safety(const dyn_tableau *m, double opts_safety)
{
    return opts_safety > 0.0 ? opts_safety : m->safety;
}

/* Set up for error order q (the estimate behaves like h^(q+1)); zeros in safety, fac_min,
 * fac_max mean the defaults, beta < 0 means 0 and beta == 0 the default; squared: the errors
 * passed to accept and reject are squares of the norm (1 <=> 1 all the same). */
DYN_SINL void dyn_sinl_ctl_init(dyn_sinl_ctl *c, int q, double safety, double beta,
                                double fac_min, double fac_max, int squared)
{
    c->log2_scale = squared ? 0.5 : 1.0;
    c->beta = beta < 0.0 ? 0.0 : beta > 0.0 ? beta : 0.04;
    c->fac_min = fac_min > 0.0 ? fac_min : 0.2;
    c->fac_max = fac_max > 0.0 ? fac_max : 10.0;
    c->expo = dyn_sinl_ctl_exponent(q, c->beta);
    c->expo_scaled = c->expo * c->log2_scale;
    c->log2_safety = log2(safety > 0.0 ? safety : 0.9);
    c->log2_floor = log2(1e-4);
    c->log2_gain = c->log2_safety + c->beta * c->log2_floor;
}

/* Next step after an accepted step of size h with error norm err (<= 1); rejected_before
 * keeps the step from growing right after a rejection. */
DYN_SINL double dyn_sinl_ctl_accept(dyn_sinl_ctl *c, double h, double err, int rejected_before)
{
    /* expo_scaled l2 is expo (log2_scale l2) bit for bit (log2_scale is a power of two), one
     * multiplication less on the chain from this step's error to the next step */
    const double l2 = log2(err); /* -inf for 0: the ratio becomes fac_max */
    const double l = c->log2_scale * l2;
    double ratio = exp2(c->log2_gain - c->expo_scaled * l2);
    if (!(ratio <= c->fac_max))
        ratio = c->fac_max;
    if (ratio < c->fac_min)
        ratio = c->fac_min;
    /* log2(max(err, 1e-4)), as log2 is monotonic */
    c->log2_gain = c->log2_safety + c->beta * (l > c->log2_floor ? l : c->log2_floor);
    double hnew = h * ratio;
    if (rejected_before && hnew > h)
        hnew = h;
    return hnew;
}

/* Next try after a rejected step of size h with error norm err (> 1, or NaN/Inf: a quarter). */
DYN_SINL double dyn_sinl_ctl_reject(const dyn_sinl_ctl *c, double h, double err)
{
    if (!isfinite(err))
        return 0.25 * h;
    double ratio = exp2(c->log2_safety - c->expo_scaled * log2(err));
    if (ratio < c->fac_min)
        ratio = c->fac_min;
    if (!(ratio < 1.0))
        ratio = 0.9;
    return h * ratio;
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

/* The pairs with a kernel in dynkit/erk_kernels.h. */
#define DYN_SINL_BS23 0
#define DYN_SINL_DP45 1
#define DYN_SINL_DOP853 2
#define DYN_SINL_DECLINED (-1) /* dyn_sinl_try: not a case of the fast path */

DYN_SINL int dyn_sinl_stages(const int P)
{
    return P == DYN_SINL_BS23 ? 4 : P == DYN_SINL_DP45 ? 7 : 12;
}

/* The stage slots of dyn_solve's workspace (kslots in src/ode/step_erk.c): the stages,
 * f(t + h, ynew) for a pair without FSAL, and the dense output's extra stages. */
DYN_SINL int dyn_sinl_kslots(const int P)
{
    return P == DYN_SINL_BS23 ? 4 : P == DYN_SINL_DP45 ? 7 : 16;
}

DYN_SINL int dyn_sinl_kslots_of(const dyn_tableau *m)
{
    const int k = m->fsal ? m->stages : m->stages + 1;
    return m->dense_stages > k ? m->dense_stages : k;
}

DYN_SINL double dyn_sinl_c(const int P, const int i)
{
    return P == DYN_SINL_BS23 ? dyn_ek_bs23_c[i & 3]
           : P == DYN_SINL_DP45 ? dyn_ek_dp45_c[i < 7 ? i : 0]
                                : dyn_ek_dop853_c[i < 12 ? i : 0];
}

/* Stage r's state (r < S) or y_{n+1} (r == S) of pair P: the generated kernels. */
DYN_SINL int dyn_sinl_row(const int P, const int r, const int n, const double h,
                          const double *DYN_SRESTRICT y, const double *DYN_SRESTRICT k,
                          double *DYN_SRESTRICT out)
{
    if (P == DYN_SINL_BS23)
        return dyn_ek_bs23_row(r, n, h, y, k, out);
    if (P == DYN_SINL_DP45)
        return dyn_ek_dp45_row(r, n, h, y, k, out);
    return dyn_ek_dop853_row(r, n, h, y, k, out);
}

/* The square of the error norm of the step (erk_error in src/ode/step_erk.c): of
 * |h| sqrt(s5 / n), or of DOP853's |h| s5 / sqrt(n (s5 + 0.01 s3)); no square root between
 * the step's error and the next step size (the controller takes log2(err^2) / 2). */
DYN_SINL double dyn_sinl_err(const int P, const int n, const double rtol, const double atol,
                             const double h, const double *y, const double *ynew,
                             const double *k)
{
    double s3 = 0.0, s5;
    if (P == DYN_SINL_BS23)
        s5 = dyn_ek_bs23_err(n, rtol, atol, y, ynew, k, &s3);
    else if (P == DYN_SINL_DP45)
        s5 = dyn_ek_dp45_err(n, rtol, atol, y, ynew, k, &s3);
    else
        s5 = dyn_ek_dop853_err(n, rtol, atol, y, ynew, k, &s3);
    if (P != DYN_SINL_DOP853)
        return h * h * (s5 / n);
    if (s5 == 0.0 && s3 == 0.0)
        return 0.0;
    return h * h * s5 * (s5 / ((s5 + 0.01 * s3) * n));
}

DYN_SINL int dyn_sinl_same(const dyn_tableau *m, int s, int fsal, const double *a,
                           const double *b, const double *c, const double *e, const double *e3)
{
    const size_t S = (size_t)s;
    return m->stages == s && (m->fsal != 0) == fsal && m->a && m->b && m->c && m->e &&
           memcmp(m->a, a, S * S * sizeof *a) == 0 && memcmp(m->b, b, S * sizeof *b) == 0 &&
           memcmp(m->c, c, S * sizeof *c) == 0 && memcmp(m->e, e, S * sizeof *e) == 0 &&
           (e3 ? m->e3 && memcmp(m->e3, e3, S * sizeof *e3) == 0 : !m->e3);
}

/* Which kernel computes table m: one whose coefficients are m's, bit for bit, and whose
 * workspace has the same layout (the library's bs23, dp45 and dop853, or copies of them);
 * DYN_SINL_DECLINED for any other table. */
DYN_SINL int dyn_sinl_pair_of(const dyn_tableau *m)
{
    int P = DYN_SINL_DECLINED;
    if (m->kind != DYN_KIND_EMBEDDED_RK)
        return P;
    if (dyn_sinl_same(m, 4, 1, dyn_ek_bs23_a, dyn_ek_bs23_b, dyn_ek_bs23_c, dyn_ek_bs23_e, NULL))
        P = DYN_SINL_BS23;
    else if (dyn_sinl_same(m, 7, 1, dyn_ek_dp45_a, dyn_ek_dp45_b, dyn_ek_dp45_c, dyn_ek_dp45_e,
                           NULL))
        P = DYN_SINL_DP45;
    else if (dyn_sinl_same(m, 12, 0, dyn_ek_dop853_a, dyn_ek_dop853_b, dyn_ek_dop853_c,
                           dyn_ek_dop853_e, dyn_ek_dop853_e3))
        P = DYN_SINL_DOP853;
    return P != DYN_SINL_DECLINED && dyn_sinl_kslots_of(m) == dyn_sinl_kslots(P)
               ? P
               : DYN_SINL_DECLINED;
}

#if defined(__GNUC__)
#define DYN_SINL_COLD static __attribute__((noinline, cold, unused))
#else
#define DYN_SINL_COLD static
#endif

/* DOPRI5's |h lambda| from stage j (c = 1) and f1 = f(t + h, ynew), also the general
 * driver's (erk_stiffness calls it); out of line (once every stiff_check steps), so that
 * the step loop stays small enough for the right-hand side to be inlined into it. */
DYN_SINL_COLD double dyn_sinl_stiffness(const dyn_tableau *m, int n, double hn, const double *k,
                                        const double *f1, const double *ycur,
                                        const double *ynew, double *Yj)
{
    const size_t N = (size_t)n;
    const int j = m->stiff_stage, S = m->stages;
    const double *kj = k + (size_t)j * N;
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

/* Where output samples go (the general driver's out_plan): every step (mode 0), a grid
 * (mode 1: out_step) or a list of times (mode 2: out_times). */
typedef struct dyn_sinl_out {
    int mode;
    dyn_grid grid;
    const double *times;
    long count;
} dyn_sinl_out;

DYN_SINL double dyn_sinl_out_time(const dyn_sinl_out *out, long i)
{
    return out->mode == 1 ? dyn_grid_time(&out->grid, i) : out->times[i];
}

/* The dense output of the step, also the general driver's (erk_dense in src/ode/step_erk.c
 * calls it): the cubic Hermite part and the table's corrections; for a pair without FSAL
 * first f(t + h, ynew) into slot S (unless the stiffness test computed it: *fnew_valid) and
 * the extra stages of the dense output. Returns 0, or the right-hand side's non-zero status
 * with *fail_t set to the time of the failing evaluation. */
DYN_SINL_COLD int dyn_sinl_dense(const dyn_tableau *m, int q, int n, double t, double hn,
                                 double t1, dyn_rhs_fn f, void *par, double *k, double *Y,
                                 int *fnew_valid, const double *ycur, const double *ynew,
                                 double *coef, long *rhs_calls, double *fail_t)
{
    const size_t N = (size_t)n;
    const int S = m->stages;
    double *f1 = k + (size_t)(m->fsal ? S - 1 : S) * N;
    if (!m->fsal && !*fnew_valid) {
        const double tf = t + hn > t1 ? t1 : t + hn;
        ++*rhs_calls;
        const int rc = f(tf, ynew, f1, par);
        if (rc) {
            *fail_t = tf;
            return rc;
        }
        *fnew_valid = 1;
    }
    const double *f0 = k;
    for (size_t i = 0; i < N; i++) {
        const double dy = ynew[i] - ycur[i];
        coef[i] = ycur[i];
        coef[N + i] = dy;
        coef[2 * N + i] = hn * f0[i] - dy;
        coef[3 * N + i] = 2.0 * dy - hn * (f0[i] + f1[i]);
    }
    const int ds = m->dense_stages;
    if (q <= 3 || !m->dense)
        return 0;
    for (int r = S + 1; r < ds; r++) {
        const double *row = m->dense_a + (size_t)(r - S - 1) * (size_t)ds;
        for (size_t i = 0; i < N; i++) {
            double acc = 0.0;
            for (int j = 0; j < r; j++)
                if (row[j] != 0.0)
                    acc += row[j] * k[(size_t)j * N + i];
            Y[i] = ycur[i] + hn * acc;
        }
        const double tr = dyn_sinl_stage_time(t, m->dense_c[r - S - 1], hn, t1);
        ++*rhs_calls;
        const int rc = f(tr, Y, k + (size_t)r * N, par);
        if (rc) {
            *fail_t = tr;
            return rc;
        }
    }
    for (int jj = 4; jj <= q; jj++) {
        const double *D = m->dense + (size_t)(jj - 4) * (size_t)ds;
        double *cj = coef + (size_t)jj * N;
        for (size_t i = 0; i < N; i++) {
            double acc = 0.0;
            for (int r = 0; r < ds; r++)
                if (D[r] != 0.0)
                    acc += D[r] * k[(size_t)r * N + i];
            cj[i] = hn * acc;
        }
    }
    return 0;
}

/* A message into res (the failure paths, out of line). */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
DYN_SINL_COLD void dyn_sinl_fail(dyn_result *res, int status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(res->message, sizeof res->message, fmt, ap);
    va_end(ap);
    res->status = status;
}

/* The rejected step's new size, and the end of the solve when it is too small (the general
 * driver's test and messages). Returns 1 when the solve ends. */
DYN_SINL_COLD int dyn_sinl_reject(dyn_sinl_ctl ctl, int n, double t, double t0,
                                  double t_end, double tnext, double hn, double err,
                                  const double *ynew, double *h, dyn_result *res)
{
    *h = dyn_sinl_ctl_reject(&ctl, hn, err);
    const double hmin =
        16.0 * DBL_EPSILON * fmax(fabs(t), fmax(DBL_EPSILON * (t_end - t0), DBL_MIN));
    if (*h >= hmin && t + *h != t)
        return 0;
    int bad = 0;
    while (bad < n && isfinite(ynew[bad]))
        bad++;
    if (bad < n) {
        res->fail_t = tnext;
        res->fail_index = bad;
        dyn_sinl_fail(res, DYN_ERR_NONFINITE,
                      "state %d became not finite at t = %s for every step size down to %g",
                      bad, dyn_shortest(tnext).s, hn);
    } else {
        res->fail_t = t;
        dyn_sinl_fail(res, DYN_ERR_STEP_SIZE,
                      "step size underflow at t = %s: the error test fails with h = %g (a "
                      "singularity, a discontinuity, or tolerances below rounding)",
                      dyn_shortest(t).s, hn);
    }
    return 1;
}

/* DOPRI5's stiffness bookkeeping of one test (15 steps in a row above the bound). */
DYN_SINL_COLD void dyn_sinl_stiff_count(const dyn_tableau *m, double hl, double t,
                                        int *stiff_count, int *nonstiff_count, dyn_result *res)
{
    if (hl > m->stiff_bound) {
        *nonstiff_count = 0;
        if (++*stiff_count == 15 && !res->stiff) {
            res->stiff = 1;
            res->stiff_t = t;
            snprintf(res->stiff_message, sizeof res->stiff_message,
                     "the problem looks stiff from t = %.6g: %s's step size is limited by "
                     "stability (|h lambda| > %g for %d steps in a row), not by accuracy",
                     t, m->name, m->stiff_bound, 15);
        }
    } else if (hl >= 0.0 && ++*nonstiff_count == 6) {
        *stiff_count = 0;
    }
}

/* The solve with pair P's kernel. */
DYN_SINL int dyn_sinl_solve(const int P, const dyn_tableau *m, dyn_rhs_fn f, void *par,
                            const int n, double t0, double t1, const double *y0, double *y,
                            double *work, const dyn_solve_opts *o, const dyn_sinl_out *out,
                            double rtol, double atol, dyn_result *res)
{
    const int S = dyn_sinl_stages(P);
    const int fsal = P != DYN_SINL_DOP853;
    const size_t N = (size_t)n;
    const int q = m->dense_degree > 3 && m->dense ? m->dense_degree : 3;
    /* the workspace of dyn_solve: k (slots) | Y | tmp | ycur ynew yout ytmp | coef (q + 1) */
    /* a constant, so that the compiler sees the stage derivatives apart from the states */
    const int kslots = dyn_sinl_kslots(P);
    double *k = work, *Y = k + (size_t)kslots * N, *Yj = Y + N;
    double *ycur = Yj + N, *ynew = ycur + N, *yout = ynew + N, *ytmp = yout + N;
    double *coef = ytmp + N;
    double *const fnew = k + (size_t)(fsal ? S - 1 : S) * N; /* f(t + h, ynew) */
    const int mode = out->mode;
    const long count = out->count;
    long next = 0, kout = 0, rhs_calls = 0;
    const dyn_output_fn output = o->output;
    const dyn_progress_fn progress = o->progress;
    double t = t0, h;
    int rc = 0, k0_valid = 0;
    memmove(ycur, y0, N * sizeof *ycur);
    if (mode == 0 || (count > 0 && dyn_sinl_out_time(out, 0) == t0)) {
        do {
            if (output) {
                res->stats.samples++;
                if (output(kout++, t0, ycur, o->output_ctx)) {
                    dyn_sinl_fail(res, DYN_STOPPED, "output stopped the run at t = %g", t0);
                    goto finish;
                }
            }
            if (mode != 0)
                next++;
        } while (mode != 0 && next < count && dyn_sinl_out_time(out, next) == t0);
    }
    {
        /* the end: t1, or the grid's last sample (DYN_END_GRID may stop before t1) */
        const double t_end = mode == 1 ? dyn_grid_time(&out->grid, count - 1) : t1;
        double hmax = t_end - t0;
        if (o->max_step > 0.0)
            hmax = fmin(hmax, o->max_step);
        dyn_sinl_ctl ctl;
        dyn_sinl_ctl_init(&ctl, m->error_order, dyn_sinl_ctl_safety(m, o->safety), o->beta,
                          o->fac_min, o->fac_max, 1);
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
            const long progress_every = o->progress_steps > 0 ? o->progress_steps : 4096;
            const long max_steps = o->max_steps;
            const int stiff_test = m->stiff_bound > 0.0 && m->stiff_stage >= 0 &&
                                   m->stiff_stage < S && m->c[m->stiff_stage] == 1.0;
            long stiff_countdown = stiff_every, progress_countdown = progress_every;
            int stiff_count = 0, nonstiff_count = 0, rejected_before = 0, fnew_valid = 0;
            dyn_dense d = {0.0, 0.0, n, q, coef};
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
                    dyn_sinl_fail(res, DYN_ERR_MAX_STEPS,
                                  "reached the limit of %ld steps at t = %s (h = %g): raise "
                                  "the limit, loosen the tolerances, or use a method for stiff "
                                  "problems",
                                  max_steps, dyn_shortest(t).s, h);
                    goto finish;
                }
                res->stats.steps++;
                /* the stages (dyn_rk_stages_from): k_0 is f(t, y) already after FSAL, after
                 * a rejection, or when the stiffness test computed f(t + h, ynew) */
                const int first = k0_valid;
#define DYN_SINL_STAGE(I)                                                                          \
    if ((I) < S) {                                                                                 \
        const int I_ = (I) < S ? (I) : 0;                                                          \
        const double *Yi = ycur;                                                                   \
        if (I_ > 0 && dyn_sinl_row(P, I_, n, hn, ycur, k, Y) > 0)                                  \
            Yi = Y;                                                                                \
        if (I_ >= first) {                                                                         \
            const double ti = dyn_sinl_stage_time(t, dyn_sinl_c(P, I_), hn, t1);                   \
            rc = f(ti, Yi, k + (size_t)I_ * N, par);                                               \
            DYN_SINL_STORED(k + (size_t)I_ * N, n);                                                \
            if (rc) {                                                                              \
                rhs_calls += I_ + 1 - first;                                                       \
                k0_valid = I_ > 0;                                                                 \
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
                DYN_SINL_STAGE(7)
                DYN_SINL_STAGE(8)
                DYN_SINL_STAGE(9)
                DYN_SINL_STAGE(10)
                DYN_SINL_STAGE(11)
#undef DYN_SINL_STAGE
                rhs_calls += S - first;
                k0_valid = 1;
                fnew_valid = 0;
                dyn_sinl_row(P, S, n, hn, ycur, k, ynew);
                const double err = dyn_inl_nonfinite(n, ynew)
                                       ? INFINITY
                                       : dyn_sinl_err(P, n, rtol, atol, hn, ycur, ynew, k);
                if (!(err <= 1.0)) {
                    res->stats.rejected++;
                    rejected_before = 1;
                    /* the controller by value and h through a temporary: with their
                     * addresses taken, gcc kept them in memory all along the loop */
                    double h_try;
                    if (dyn_sinl_reject(ctl, n, t, t0, t_end, tnext, hn, err, ynew, &h_try, res))
                        goto finish;
                    h = h_try;
                    continue;
                }
                res->stats.accepted++;
                const int stiff_due = --stiff_countdown == 0;
                if (stiff_due)
                    stiff_countdown = stiff_every;
                if (stiff_test && (stiff_due || stiff_count > 0)) {
                    double hl = -1.0;
                    if (!fsal) {
                        /* f(t + h, ynew) into slot S, kept as the next step's k_0 */
                        rhs_calls++;
                        const double tf = t + hn > t1 ? t1 : t + hn;
                        rc = f(tf, ynew, fnew, par);
                        fnew_valid = rc == 0;
                        /* a failure here is met again as the next step's first stage */
                        rc = 0;
                    }
                    if (fsal || fnew_valid)
                        hl = dyn_sinl_stiffness(m, n, hn, k, fnew, ycur, ynew, Yj);
                    dyn_sinl_stiff_count(m, hl, t, &stiff_count, &nonstiff_count, res);
                }
                if (mode != 0 && next < count && dyn_sinl_out_time(out, next) < tnext) {
                    rc = dyn_sinl_dense(m, q, n, t, hn, t1, f, par, k, Y, &fnew_valid, ycur,
                                        ynew, coef, &rhs_calls, &res->fail_t);
                    if (rc)
                        goto rhs_failed;
                    d.t0 = t;
                    d.h = hn;
                }
                while (mode != 0 && next < count && dyn_sinl_out_time(out, next) <= tnext) {
                    const double to = dyn_sinl_out_time(out, next);
                    const double *yo = ynew;
                    if (to != tnext) {
                        dyn_dense_eval(&d, to, yout);
                        yo = yout;
                    }
                    next++;
                    if (output) {
                        res->stats.samples++;
                        if (output(kout++, to, yo, o->output_ctx)) {
                            dyn_sinl_fail(res, DYN_STOPPED, "output stopped the run at t = %g",
                                          to);
                            goto finish;
                        }
                    }
                }
                if (fsal || fnew_valid)
                    memcpy(k, fnew, N * sizeof *k);
                else
                    k0_valid = 0;
                memcpy(ycur, ynew, N * sizeof *ycur);
                t = tnext;
                res->h_last = hn;
                if (mode == 0 && output) {
                    res->stats.samples++;
                    if (output(kout++, t, ycur, o->output_ctx)) {
                        dyn_sinl_fail(res, DYN_STOPPED, "output stopped the run at t = %g", t);
                        goto finish;
                    }
                }
                if (progress && --progress_countdown == 0) {
                    progress_countdown = progress_every;
                    if (progress(t, (t - t0) / (t_end - t0), o->progress_ctx)) {
                        dyn_sinl_fail(res, DYN_CANCELLED, "cancelled at t = %g", t);
                        goto finish;
                    }
                }
                h = dyn_sinl_ctl_accept(&ctl, hn, err, rejected_before);
                /* fmin(h, hmax): hmax is a number, h may be NaN; in this form one minimum
                 * instruction (minsd), where the test and assignment became a four-instruction
                 * select on the chain to the next step */
                h = h < hmax ? h : hmax;
                if (last)
                    h = fmax(h, hn);
                rejected_before = 0;
            }
        }
    } /* a block, so that no goto jumps past an initialisation (C++) */
    goto finish;

rhs_failed:
    res->rhs_status = rc;
    dyn_sinl_fail(res, DYN_ERR_RHS, "the right-hand side failed at t = %s (status %d)",
                  dyn_shortest(res->fail_t).s, rc);

finish:
    res->t = t;
    res->stats.rhs_calls = rhs_calls;
    if (y && y != ycur)
        memcpy(y, ycur, N * sizeof *y);
    return res->status;
}

/* The solve of dyn_solve by a kernel, when this is a case of the fast path: one of the pairs
 * of dynkit/erk_kernels.h with scalar tolerances (rtol >= DYN_MIN_RTOL), no events, step
 * callback, recorder, trace or band, and output at every step, on a grid (out_step) or at a
 * list of times. Returns DYN_SINL_DECLINED (touching nothing) for every other case, bad
 * arguments included, which dyn_solve's general driver then takes. */
DYN_SINL int dyn_sinl_try(const dyn_tableau *m, const dyn_system *sys, double t0, double t1,
                          const double *y0, double *y, double *work, const dyn_solve_opts *opts,
                          dyn_result *res)
{
    if (!sys || !m)
        return DYN_SINL_DECLINED;
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
    int plain = f && n > 0 && y0 && work && isfinite(t0) && isfinite(t1) && t1 > t0 &&
                rtol >= DYN_MIN_RTOL && isfinite(rtol) && atol >= 0.0 && isfinite(atol) &&
                !o->rtolv && !o->atolv && o->max_step >= 0.0 && o->initial_step >= 0.0 &&
                !(o->events && o->n_events) && o->n_events >= 0 && !o->step && !o->record &&
                !o->trace && !o->jac_banded && !(o->stops && o->n_stops > 0);
    if (!plain)
        return DYN_SINL_DECLINED;
    const int P = dyn_sinl_pair_of(m);
    /* a beta the general driver refuses (the controller's exponent must stay > 0) */
    if (o->beta > 0.0 && !(dyn_sinl_ctl_exponent(m->error_order, o->beta) > 0.0))
        return DYN_SINL_DECLINED;
    if (P == DYN_SINL_DECLINED || (o->out_times && o->out_step != 0.0))
        return DYN_SINL_DECLINED;
    dyn_sinl_out out;
    memset(&out, 0, sizeof out);
    if (o->out_step != 0.0) {
        out.mode = 1;
        if (dyn_grid_plan(t0, t1, o->out_step, o->end, &out.grid, NULL, 0) != DYN_OK)
            return DYN_SINL_DECLINED;
        out.count = out.grid.samples;
    } else if (o->out_times) {
        out.mode = 2;
        out.times = o->out_times;
        out.count = o->n_out_times;
        for (long i = 0; i < o->n_out_times; i++)
            if (!(o->out_times[i] >= t0 && o->out_times[i] <= t1) ||
                (i > 0 && o->out_times[i] < o->out_times[i - 1]))
                return DYN_SINL_DECLINED;
    }
    for (int i = 0; i < n; i++)
        if (!isfinite(y0[i]))
            return DYN_SINL_DECLINED;
    dyn_result local;
    if (!res)
        res = &local;
    memset(res, 0, sizeof *res);
    res->t = t0;
    res->fail_t = NAN;
    res->fail_index = -1;
    res->event_index = -1;
    res->stiff_t = NAN;
    /* each pair compiled once */
    if (P == DYN_SINL_BS23)
        return dyn_sinl_solve(DYN_SINL_BS23, m, f, par, n, t0, t1, y0, y, work, o, &out, rtol,
                              atol, res);
    if (P == DYN_SINL_DP45)
        return dyn_sinl_solve(DYN_SINL_DP45, m, f, par, n, t0, t1, y0, y, work, o, &out, rtol,
                              atol, res);
    return dyn_sinl_solve(DYN_SINL_DOP853, m, f, par, n, t0, t1, y0, y, work, o, &out, rtol,
                          atol, res);
}

/* dyn_solve with the step loop compiled at the call site: same contract, same results bit
 * for bit (see the top of this header for what takes the inline path). */
DYN_SINL int dyn_solve_inline(const dyn_tableau *m, const dyn_system *sys, double t0, double t1,
                              const double *y0, double *y, double *work, const dyn_solve_opts *opts,
                              dyn_result *res)
{
    const int rc = dyn_sinl_try(m, sys, t0, t1, y0, y, work, opts, res);
    return rc != DYN_SINL_DECLINED ? rc : dyn_solve(m, sys, t0, t1, y0, y, work, opts, res);
}

#undef DYN_SINL
#undef DYN_SINL_COLD
#undef DYN_SINL_STORED
#undef DYN_SRESTRICT

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_SOLVE_INLINE_H */
