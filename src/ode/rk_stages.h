/* SPDX-License-Identifier: BSD-3-Clause */
/* The one stage loop of every explicit Runge–Kutta method (private to the library).
 *
 * For stage i: Y_i = y_n + h * sum_{j<i} a_ij k_j, k_i = f(t_n + c_i h, Y_i);
 * then y_{n+1} = y_n + h * sum_i b_i k_i (Hairer, Nørsett & Wanner I, eq. II.1.8).
 * Zero coefficients are skipped and each sum starts from its first non-zero term, so the
 * sums are exactly the textbook formulas: Euler is y + h*k1 and Heun y + h*(k1 + k2)/2 bit
 * for bit, as in the homework's MATLAB code. A row whose only coefficient is a power of two
 * (1, 1/2, ...) is computed as y + (h*a)*k: equal to y + h*(a*k) bit for bit, since scaling
 * by a power of two is exact, with one multiplication less on the critical path; so is a
 * row whose coefficients are all the same power of two c: y + (h*c)*(k_a + k_b + ...), equal
 * to y + h*(c*k_a + c*k_b + ...) bit for bit (Heun's b: the homework's y + Ts/2*(k1 + k2)).
 *
 * Embedded pairs (DYN_KIND_EMBEDDED_RK: bs23, dp45, dop853, whose steps are the adaptive
 * drivers') keep the newest term apart: Y_i = (y_n + h * sum_{j<l} a_ij k_j) + (h a_il) k_l,
 * l the last non-zero coefficient of the row (y_n + (h a_il) k_l for a single one). Every
 * other term can be summed while k_l is still being computed, so the chain from k_l to the
 * next stage is one multiplication and one addition instead of four (HNW's form): dop853 20%
 * and dp45 8% less time per step on van der Pol with the right-hand side inlined. The
 * generated kernels of dynkit/erk_kernels.h do the same, term for term.
 *
 * Speed. Before a solve the table is turned into a plan (dyn_rk_plan): for each row of a
 * and for b, its non-zero coefficients and pointers to the k_j they multiply. A stage is
 * then one pass over the states with the row's few terms (1 to 5 terms have their own
 * loops, longer rows unroll their first six), instead of a scan of all j < i testing every
 * coefficient for every state. The plan is derived from the table's data, so every method
 * still runs through this one loop.
 * Tables with more than DYN_RK_PLAN_MAX_STAGES stages use dyn_rk_stages_scan: the same
 * arithmetic with the coefficients scanned on the fly, by the combination code of the
 * public dyn_fixed_solve_inline (dynkit/ode_inline.h).
 * Static inline so that the driver gets a trace-free copy with the trace branch removed.
 */
#ifndef DYNKIT_SRC_ODE_RK_STAGES_H
#define DYNKIT_SRC_ODE_RK_STAGES_H

#include <stddef.h>
#include <string.h>

#include "dynkit/ode.h"
#include "dynkit/ode_inline.h" /* dyn_inl_combine: the reference combination */

/* Workspace layout (doubles): k (stages x n) | Y (n) | two spare states (n each). */
#define DYN_RK_WORK(stages, n) ((size_t)((stages) + 3) * (size_t)(n))

/* Inlined everywhere: the combination loops are only fast when specialised at their call
 * site (vec constant, trace NULL). */
#if defined(__GNUC__)
#define DYN_RK_INLINE static inline __attribute__((always_inline))
#else
#define DYN_RK_INLINE static inline
#endif

/* Largest stage count with a plan (the plan lives on the caller's stack, about 2.5 KB). */
#ifndef DYN_RK_PLAN_MAX_STAGES /* overridable to test the fallback */
#define DYN_RK_PLAN_MAX_STAGES 16
#endif
#define DYN_RK_PLAN_MAX_TERMS (DYN_RK_PLAN_MAX_STAGES * (DYN_RK_PLAN_MAX_STAGES + 1) / 2)

/* Non-zero coefficients of a table by row: rows 0 .. s-1 are the rows of a, row s is b.
 * The terms of row r are coef[t] * kp[t] for first[r] <= t < first[r + 1], where
 * kp[t] = k_j = k + j * n points into the workspace of the solve. */
typedef struct dyn_rk_plan {
    int stages;
    int last_apart; /* an embedded pair: each row's last term added apart (see the top) */
    int first[DYN_RK_PLAN_MAX_STAGES + 2];
    unsigned char same[DYN_RK_PLAN_MAX_STAGES + 1]; /* row r: 2+ terms, one power of two */
    double coef[DYN_RK_PLAN_MAX_TERMS];
    unsigned char pow2[DYN_RK_PLAN_MAX_TERMS]; /* coef is +-2^e, |e| <= 64 (dyn_inl_is_pow2) */
    const double *kp[DYN_RK_PLAN_MAX_TERMS];
} dyn_rk_plan;

/* Build the plan of table m for the stage derivatives k (stages x n).
 * Returns 1, or 0 if m has more stages than a plan holds (then use dyn_rk_stages_scan). */
static inline int dyn_rk_plan_init(dyn_rk_plan *p, const dyn_tableau *m, const double *k,
                                   int n)
{
    const int s = m->stages;
    if (s < 1 || s > DYN_RK_PLAN_MAX_STAGES)
        return 0;
    int t = 0;
    p->stages = s;
    p->last_apart = m->kind == DYN_KIND_EMBEDDED_RK;
    for (int r = 0; r <= s; r++) {
        const double *row = r < s ? m->a + (size_t)r * (size_t)s : m->b;
        const int len = r < s ? r : s; /* a is strictly lower triangular */
        p->first[r] = t;
        for (int j = 0; j < len; j++) {
            if (row[j] != 0.0) {
                p->coef[t] = row[j];
                p->pow2[t] = (unsigned char)dyn_inl_is_pow2(row[j]);
                p->kp[t] = k + (size_t)j * (size_t)n;
                t++;
            }
        }
        /* the rule of dyn_inl_row_of (dynkit/ode_inline.h): contiguous, equal, 2^e */
        const dyn_inl_row ri = dyn_inl_row_of(row, len);
        p->same[r] = (unsigned char)ri.same;
    }
    p->first[s + 1] = t;
    return 1;
}

/* DYN_RK_SCALAR(v): an empty asm statement that pins the double v to a register, so the
 * loop around it stays scalar. The right-hand side writes its k_i one double at a time; a
 * vector load of two of them right after (what vectorised combination loops do) cannot be
 * forwarded from the store buffer and waits for the stores to retire, on the critical path
 * of every stage (measured with gcc 12 -O3: van der Pol, 2 states, 39 -> 66 ns per RK4
 * step; the 12-state plane 309 -> 337 ns). Systems with at least DYN_RK_VECTOR_MIN_N
 * states keep vectorisable loops, where the wide loads pay. No effect on results. */
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#define DYN_RK_SCALAR(v) __asm__("" : "+x"(v))
#elif defined(__GNUC__) && defined(__aarch64__)
#define DYN_RK_SCALAR(v) __asm__("" : "+w"(v))
#else
#define DYN_RK_SCALAR(v) ((void)0)
#endif
#define DYN_RK_VECTOR_MIN_N 32

/* One combination out = base + h * (sum_t coef[t] * kp[t]) over nt terms, summed left to
 * right from the first term (nt == 0: out = base). Returns the sum of out[q] - out[q]: 0
 * when every out[q] is finite, NaN otherwise (the compiler drops it where unused). Fused
 * into the loop that writes out, this measured faster in this loop than the bit test of the
 * inline drivers (dyn_inl_nonfinite) after it: 1.07 against 1.09 times the pointer floor for
 * Euler on the 12-state plane (docs/performance.md). (The plain steps of the common shapes
 * no longer come here: they take dyn_fixed_solve_inline's step, src/ode/fixed_driver.c.)
 * out must not alias base or any kp[t]. vec (a constant at each call) picks the loop kind:
 * scalar, or left to the vectoriser. (Unrolled scalar loops are no better: the compiler
 * pairs their stores into vector stores, and the right-hand side's loads of the upper
 * halves then stall.) */
DYN_RK_INLINE double dyn_rk_combine_kind(int n, double h, const double *restrict base,
                                         const double *const *kp, const double *coef,
                                         const unsigned char *pow2, int nt,
                                         double *restrict out, const int vec)
{
    double z = 0.0;
#define DYN_RK_PUT(q, expr)                                                                  \
    do {                                                                                     \
        double v_ = (expr);                                                                  \
        if (!vec)                                                                            \
            DYN_RK_SCALAR(v_);                                                               \
        out[q] = v_;                                                                         \
        z += v_ - v_;                                                                        \
    } while (0)
#define DYN_RK_LOOP(E)                                                                       \
    do {                                                                                     \
        for (int q = 0; q < n; q++)                                                          \
            DYN_RK_PUT(q, E(q));                                                             \
    } while (0)
    switch (nt) {
    case 0: {
#define E0(q) base[q]
        DYN_RK_LOOP(E0);
        break;
    }
    case 1: {
        const double *restrict k0 = kp[0];
        const double c0 = coef[0];
        if (pow2[0]) {
            /* (h*a)*k == h*(a*k) exactly: one multiplication less on the critical path */
            const double hc = h * c0;
#define E1U(q) (base[q] + hc * k0[q])
            DYN_RK_LOOP(E1U);
        } else {
#define E1(q) (base[q] + h * (c0 * k0[q]))
            DYN_RK_LOOP(E1);
        }
        break;
    }
    case 2: {
        const double *restrict k0 = kp[0], *restrict k1 = kp[1];
        const double c0 = coef[0], c1 = coef[1];
#define E2(q) (base[q] + h * (c0 * k0[q] + c1 * k1[q]))
        DYN_RK_LOOP(E2);
        break;
    }
    case 3: {
        const double *restrict k0 = kp[0], *restrict k1 = kp[1], *restrict k2 = kp[2];
        const double c0 = coef[0], c1 = coef[1], c2 = coef[2];
#define E3(q) (base[q] + h * (c0 * k0[q] + c1 * k1[q] + c2 * k2[q]))
        DYN_RK_LOOP(E3);
        break;
    }
    case 4: {
        const double *restrict k0 = kp[0], *restrict k1 = kp[1], *restrict k2 = kp[2];
        const double *restrict k3 = kp[3];
        const double c0 = coef[0], c1 = coef[1], c2 = coef[2], c3 = coef[3];
#define E4(q) (base[q] + h * (c0 * k0[q] + c1 * k1[q] + c2 * k2[q] + c3 * k3[q]))
        DYN_RK_LOOP(E4);
        break;
    }
    case 5: {
        const double *restrict k0 = kp[0], *restrict k1 = kp[1], *restrict k2 = kp[2];
        const double *restrict k3 = kp[3], *restrict k4 = kp[4];
        const double c0 = coef[0], c1 = coef[1], c2 = coef[2], c3 = coef[3], c4 = coef[4];
#define E5(q) (base[q] + h * (c0 * k0[q] + c1 * k1[q] + c2 * k2[q] + c3 * k3[q] + c4 * k4[q]))
        DYN_RK_LOOP(E5);
        break;
    }
    default: {
        /* 6 or more terms: the first six unrolled (pointers and coefficients in registers),
         * the others added after them in order: the same left-to-right sum */
        const double *restrict k0 = kp[0], *restrict k1 = kp[1], *restrict k2 = kp[2];
        const double *restrict k3 = kp[3], *restrict k4 = kp[4], *restrict k5 = kp[5];
        const double c0 = coef[0], c1 = coef[1], c2 = coef[2], c3 = coef[3], c4 = coef[4];
        const double c5 = coef[5];
        for (int q = 0; q < n; q++) {
            double acc = c0 * k0[q] + c1 * k1[q] + c2 * k2[q] + c3 * k3[q] + c4 * k4[q] +
                         c5 * k5[q];
            for (int t = 6; t < nt; t++)
                acc += coef[t] * kp[t][q];
            DYN_RK_PUT(q, base[q] + h * acc);
        }
        break;
    }
    }
#undef E0
#undef E1U
#undef E1
#undef E2
#undef E3
#undef E4
#undef E5
#undef DYN_RK_LOOP
#undef DYN_RK_PUT
    return z;
}

/* out = base + (h c) k, after out = partial sums (base == out) or from y (base == y). */
DYN_RK_INLINE double dyn_rk_add_apart(int n, double hc, const double *base, const double *kl,
                                      double *out)
{
    double z = 0.0;
    for (int q = 0; q < n; q++) {
        double v = base[q] + hc * kl[q];
        if (n < DYN_RK_VECTOR_MIN_N)
            DYN_RK_SCALAR(v);
        out[q] = v;
        z += v - v;
    }
    return z;
}

/* The plan's terms t0 .. t0 + nt - 1 combined by dyn_rk_combine_kind, in the loop kind
 * that suits n (scalar for small systems). */
DYN_RK_INLINE double dyn_rk_combine_terms(int n, double h, const double *restrict base,
                                          const dyn_rk_plan *p, int t0, int nt,
                                          double *restrict out)
{
    if (n < DYN_RK_VECTOR_MIN_N)
        return dyn_rk_combine_kind(n, h, base, p->kp + t0, p->coef + t0, p->pow2 + t0, nt, out,
                                   0);
    return dyn_rk_combine_kind(n, h, base, p->kp + t0, p->coef + t0, p->pow2 + t0, nt, out, 1);
}

DYN_RK_INLINE double dyn_rk_combine(int n, double h, const double *restrict base,
                                    const dyn_rk_plan *p, int row, double *restrict out)
{
    const int t0 = p->first[row], nt = p->first[row + 1] - t0;
    if (p->last_apart && nt > 0) {
        const double hc = h * p->coef[t0 + nt - 1];
        const double *kl = p->kp[t0 + nt - 1];
        if (nt == 1)
            return dyn_rk_add_apart(n, hc, base, kl, out);
        dyn_rk_combine_terms(n, h, base, p, t0, nt - 1, out);
        return dyn_rk_add_apart(n, hc, out, kl, out);
    }
    if (p->same[row]) {
        /* y + (h c) (k_a + k_b + ...), the sum left to right (see the top) */
        const double hc = h * p->coef[t0];
        double z = 0.0;
        for (int q = 0; q < n; q++) {
            double acc = p->kp[t0][q];
            for (int t = 1; t < nt; t++)
                acc += p->kp[t0 + t][q];
            double v = base[q] + hc * acc;
            if (n < DYN_RK_VECTOR_MIN_N)
                DYN_RK_SCALAR(v);
            out[q] = v;
            z += v - v;
        }
        return z;
    }
    return dyn_rk_combine_terms(n, h, base, p, t0, nt, out);
}

/* Time of a stage: t + c h, but never past tend (the end of the span: t + h can round
 * above t1 on the last whole step, and a model may be undefined beyond t1). */
static inline double dyn_rk_stage_time(double t, double c, double h, double tend)
{
    const double ti = t + c * h;
    return ti > tend ? tend : ti;
}

/* Report stage i (or the step's result, with k == NULL) to a trace callback. */
static inline void dyn_rk_trace(dyn_trace_fn trace, void *trace_ctx, const dyn_tableau *m,
                                long step_index, int n, double t, double h, double t_stage,
                                int stage, const double *y, const double *Y, const double *k)
{
    dyn_trace_stage ts;
    ts.method = m;
    ts.step = step_index;
    ts.stage = stage;
    ts.t_n = t;
    ts.h = h;
    ts.t_stage = t_stage;
    ts.n = n;
    ts.y_n = y;
    ts.Y = Y;
    ts.k = k;
    trace(&ts, trace_ctx);
}

/* Take one step from (t, y) of size h into ynew with the plan p of m, whose k is the k
 * here (stages x n); stage times are clamped to tend (dyn_rk_stage_time). y, ynew, k and
 * Y are distinct. Stages i < first are not evaluated: k_i is in k already (the adaptive
 * driver's k_0 = f(t, y) after FSAL; f is called directly, without a skipping wrapper).
 * Returns 0, or the non-zero value of f with the failing stage index in *fail_stage. On
 * success *finite is 0 if every ynew[q] is finite, NaN otherwise. */
DYN_RK_INLINE int dyn_rk_stages_from(const dyn_tableau *m, const dyn_rk_plan *p, dyn_rhs_fn f,
                                     void *par, int n, double t, double h, double tend,
                                     const double *restrict y, double *restrict ynew,
                                     double *restrict k, double *restrict Y, int *fail_stage,
                                     double *finite, dyn_trace_fn trace, void *trace_ctx,
                                     long step_index, int first)
{
    const int s = p->stages;
    const double *c = m->c;
    for (int i = 0; i < s; i++) {
        const double *Yi = y;
        if (p->first[i + 1] > p->first[i]) {
            dyn_rk_combine(n, h, y, p, i, Y);
            Yi = Y;
        }
        double *ki = k + (size_t)i * (size_t)n;
        const double ti = dyn_rk_stage_time(t, c[i], h, tend);
        if (i >= first) {
            int rc = f(ti, Yi, ki, par);
            if (rc) {
                *fail_stage = i;
                return rc;
            }
        }
        if (trace)
            dyn_rk_trace(trace, trace_ctx, m, step_index, n, t, h, ti, i, y, Yi, ki);
    }
    *finite = dyn_rk_combine(n, h, y, p, s, ynew);
    if (trace)
        dyn_rk_trace(trace, trace_ctx, m, step_index, n, t, h,
                     dyn_rk_stage_time(t, 1.0, h, tend), s, y, ynew, NULL);
    return 0;
}

DYN_RK_INLINE int dyn_rk_stages(const dyn_tableau *m, const dyn_rk_plan *p, dyn_rhs_fn f,
                                void *par, int n, double t, double h, double tend,
                                const double *restrict y, double *restrict ynew,
                                double *restrict k, double *restrict Y, int *fail_stage,
                                double *finite, dyn_trace_fn trace, void *trace_ctx,
                                long step_index)
{
    return dyn_rk_stages_from(m, p, f, par, n, t, h, tend, y, ynew, k, Y, fail_stage, finite,
                              trace, trace_ctx, step_index, 0);
}

/* One row of the scan: dyn_inl_combine, or for an embedded pair (apart) the same with the
 * row's last term added apart as in dyn_rk_combine. Returns the number of terms (0: out is
 * not written). */
static inline int dyn_rk_scan_combine(int apart, int n, double h, const double *restrict y,
                                      const double *k, const double *row, int len,
                                      double *restrict out)
{
    int l = len - 1;
    while (apart && l >= 0 && row[l] == 0.0)
        l--;
    if (!apart || l < 0)
        return dyn_inl_combine(n, h, y, k, row, len, dyn_inl_row_of(row, len), out);
    const int nt = dyn_inl_combine(n, h, y, k, row, l, dyn_inl_row_of(row, l), out);
    dyn_rk_add_apart(n, h * row[l], nt > 0 ? out : y, k + (size_t)l * (size_t)n, out);
    return nt + 1;
}

/* The same step for any stage count without a plan: the combinations of the public
 * dyn_fixed_solve_inline (dynkit/ode_inline.h), whose row summaries are worked out here
 * for every row of every step. Same arithmetic as dyn_rk_stages, term for term, and the
 * same contract; used for tables of more than DYN_RK_PLAN_MAX_STAGES stages. */
static inline int dyn_rk_stages_scan_from(const dyn_tableau *m, dyn_rhs_fn f, void *par, int n,
                                          double t, double h, double tend,
                                          const double *restrict y, double *restrict ynew,
                                          double *restrict k, double *restrict Y,
                                          int *fail_stage, double *finite, dyn_trace_fn trace,
                                          void *trace_ctx, long step_index, int first)
{
    const int s = m->stages, apart = m->kind == DYN_KIND_EMBEDDED_RK;
    for (int i = 0; i < s; i++) {
        const double *row = m->a + (size_t)i * (size_t)s; /* strictly lower: i entries */
        const double *Yi = y;
        if (dyn_rk_scan_combine(apart, n, h, y, k, row, i, Y) > 0)
            Yi = Y;
        double *ki = k + (size_t)i * (size_t)n;
        const double ti = dyn_rk_stage_time(t, m->c[i], h, tend);
        if (i >= first) {
            int rc = f(ti, Yi, ki, par);
            if (rc) {
                *fail_stage = i;
                return rc;
            }
        }
        if (trace)
            dyn_rk_trace(trace, trace_ctx, m, step_index, n, t, h, ti, i, y, Yi, ki);
    }
    if (dyn_rk_scan_combine(apart, n, h, y, k, m->b, s, ynew) == 0)
        memcpy(ynew, y, (size_t)n * sizeof *y);
    double z = 0.0;
    for (int q = 0; q < n; q++)
        z += ynew[q] - ynew[q];
    *finite = z;
    if (trace)
        dyn_rk_trace(trace, trace_ctx, m, step_index, n, t, h,
                     dyn_rk_stage_time(t, 1.0, h, tend), s, y, ynew, NULL);
    return 0;
}

static inline int dyn_rk_stages_scan(const dyn_tableau *m, dyn_rhs_fn f, void *par, int n,
                                     double t, double h, double tend, const double *restrict y,
                                     double *restrict ynew, double *restrict k,
                                     double *restrict Y, int *fail_stage, double *finite,
                                     dyn_trace_fn trace, void *trace_ctx, long step_index)
{
    return dyn_rk_stages_scan_from(m, f, par, n, t, h, tend, y, ynew, k, Y, fail_stage, finite,
                                   trace, trace_ctx, step_index, 0);
}

#endif
