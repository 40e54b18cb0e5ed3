/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/ode_inline.h — dyn_fixed_solve compiled into the caller, for speed.
 *
 * dyn_fixed_solve (ode.h) calls the right-hand side through a pointer: every stage stores
 * its state and derivative to memory and calls a function the compiler cannot see. For
 * small systems that is most of the cost of a step (van der Pol, 2 states: about 2.4x the
 * fastest hand-written RK4 loop; see docs/performance.md). dyn_fixed_solve_inline is the same
 * solve as a static inline function: when the right-hand side is defined in the calling
 * translation unit and sys is built there (dyn_system sys = {my_rhs, 2, &par}), the
 * compiler inlines my_rhs into the stage loop, unrolls the stages, and keeps the stage
 * values in registers. When the table itself is a compile-time constant (a static const
 * dyn_tableau with static const coefficients in the same translation unit), the
 * coefficients are folded as well.
 *
 * Contract: exactly dyn_fixed_solve's (arguments, workspace size dyn_fixed_work_size,
 * results bit for bit, counters, failure reports), because it runs the same arithmetic:
 * Y_i = y + h * (sum of the non-zero a_ij k_j, left to right), a single power-of-two
 * coefficient folded into h ((h*a)*k == h*(a*k) exactly) and so is one shared by all the
 * terms of a row (Heun's (h/2)*(k1 + k2) == h*(k1/2 + k2/2) exactly), stage times clamped
 * to t1.
 * It takes the inline path for options without output, trace or progress callbacks (end
 * policy and no_finite_check are honoured) and explicit tables of 1 to 4 stages that are
 * either compile-time constants or, known only at run time (dyn_method_find), of the
 * shape of Euler, Heun, the midpoint rule or the classical RK4 (the same non-zero pattern
 * and power-of-two coefficients; with gcc and clang); it calls dyn_fixed_solve for
 * everything else (other tables, callbacks, bad arguments, a non-finite initial state), so
 * it never behaves differently. The loops it relies on are unrolled by pragmas, so that it
 * is as fast at -O2 as at -O3 (docs/performance.md).
 * Bit for bit needs the same rounding as the library: no contraction of a*b + c into fused
 * multiply-adds in the caller's translation unit. ISO C mode (-std=c11: gcc's default there is
 * -ffp-contract=off) or a target without FMA gives it; GNU C mode with -march=native (gcc's
 * -ffp-contract=fast, clang's on) gives the same method with other rounding in the last bits
 * unless the caller adds -ffp-contract=off.
 * Cost: code size. Each call site gets its own copy of the solver with the right-hand
 * side inlined up to 8 times per table shape (once per stage, twice for systems of at most
 * 4 states; only one shape if the table is a constant). Use it for the hot solve of a
 * program, dyn_fixed_solve elsewhere.
 */
#ifndef DYNKIT_ODE_INLINE_H
#define DYNKIT_ODE_INLINE_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "dynkit/io.h" /* dyn_shortest: numbers in messages */
#include "dynkit/ode.h"

#ifdef __cplusplus
extern "C" {
#endif

#if defined(__GNUC__)
#define DYN_INL static inline __attribute__((always_inline))
#else
#define DYN_INL static inline
#endif
#ifdef __cplusplus
#define DYN_RESTRICT __restrict
#else
#define DYN_RESTRICT restrict
#endif

/* DYN_INL_UNROLL: unroll the loop that follows completely when its trip count is a small
 * constant (the stage count, or n of a small system), at -O2 as well as at -O3: gcc -O2
 * does not unroll or peel loops by itself, and the constant folding of a table's
 * coefficients and the keeping of a small state in registers both rely on it. clang
 * unrolls such loops completely by itself at -O2 and -O3; its own pragma (unroll_count(4))
 * made it keep a loop with an index instead (clang 14: 1.21x the hand-written RK4 loop on
 * van der Pol with it, 0.92x without), so it gets none. */
#if defined(__clang__)
#define DYN_INL_UNROLL
#elif defined(__GNUC__)
#define DYN_INL_UNROLL _Pragma("GCC unroll 4")
#else
#define DYN_INL_UNROLL
#endif

/* DYN_INL_SCALAR(v): an empty asm that keeps v in a register of its own, so that the
 * compiler does not pack two states into one vector register: for small systems the
 * shuffles cost more latency than the vector arithmetic saves (as in the library). */
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#define DYN_INL_SCALAR(v) __asm__("" : "+x"(v))
#elif defined(__GNUC__) && defined(__aarch64__)
#define DYN_INL_SCALAR(v) __asm__("" : "+w"(v))
#else
#define DYN_INL_SCALAR(v) ((void)0)
#endif

/* 1 if a is +-2^e with |e| <= 64 (scaling by it is exact); as in the library. Bit test
 * rather than frexp, so that every compiler folds it for a constant a. */
DYN_INL int dyn_inl_is_pow2(double a)
{
    uint64_t bits;
    memcpy(&bits, &a, sizeof bits);
    const uint64_t biased = (bits >> 52) & 0x7ff;
    return (bits & 0xfffffffffffffULL) == 0 && biased >= 1023 - 64 && biased <= 1023 + 64;
}

/* 1 if some x[q] is NaN or infinite: tested on the bits, the exponent field (masked in
 * place) plus one in its lowest bit reaching bit 63 only for the exponent of NaN and Inf.
 * Integer operations, four per state (load, and, add, or), one state at a time (the empty
 * asm keeps the compiler from loading two states as one vector, which would wait for both
 * scalar stores), so that the test stays off the floating-point units the step is waiting
 * on. The earlier test, the sum of x - x after the step, was a chain of n dependent
 * additions: 15% of an Euler step of the 12-state plane. */
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__aarch64__))
#define DYN_INL_INTEGER(bits) __asm__("" : "+r"(bits))
#else
#define DYN_INL_INTEGER(bits) ((void)0)
#endif
DYN_INL int dyn_inl_nonfinite(int n, const double *x)
{
    const uint64_t exponent = 0x7ff0000000000000ULL, one = 0x0010000000000000ULL;
    uint64_t e = 0;
#define DYN_INL_NONFINITE_TERM(q)                                                                  \
    do {                                                                                           \
        uint64_t bits;                                                                             \
        memcpy(&bits, x + (q), sizeof bits);                                                       \
        DYN_INL_INTEGER(bits);                                                                     \
        e |= (bits & exponent) + one;                                                              \
    } while (0)
#if defined(__GNUC__) && !defined(__clang__)
    if (!__builtin_constant_p(n)) {
        /* n known only at run time (the library): unrolled by two, which takes the loop's
         * own instructions off half the states without the prologue of a wider unrolling
         * (callgrind, Euler: 123 -> 95 instructions per step over the pointer floor's on the
         * 12-state plane, 3 fewer on van der Pol) */
        _Pragma("GCC unroll 2") for (int q = 0; q < n; q++) DYN_INL_NONFINITE_TERM(q);
        return (int)(e >> 63);
    }
#endif
    /* a constant n: the compiler unrolls the loop completely */
    for (int q = 0; q < n; q++)
        DYN_INL_NONFINITE_TERM(q);
#undef DYN_INL_NONFINITE_TERM
    return (int)(e >> 63);
}

/* What the combination of one row of a (or of b) needs besides the row: its number of
 * non-zero coefficients nt, the first one's column j0, fold = the only term has a
 * power-of-two coefficient, and same = two or more terms from j0 on, all with the same
 * power-of-two coefficient. Worked out once per solve; only scalars, so that compilers
 * fold them away when the table is a constant. */
typedef struct dyn_inl_row {
    int nt, j0, fold, same;
} dyn_inl_row;

DYN_INL dyn_inl_row dyn_inl_row_of(const double *row, int len)
{
    dyn_inl_row r = {0, 0, 0, 0};
    DYN_INL_UNROLL
    for (int j = len - 1; j >= 0; j--)
        if (row[j] != 0.0) {
            r.nt++;
            r.j0 = j;
        }
    r.fold = r.nt == 1 && dyn_inl_is_pow2(row[r.j0]);
    r.same = r.nt >= 2 && r.nt == len - r.j0 && dyn_inl_is_pow2(row[r.j0]);
    DYN_INL_UNROLL
    for (int j = r.j0 + 1; j < len; j++)
        if (row[j] != row[r.j0])
            r.same = 0;
    return r;
}

/* The summaries of every row of an S-stage table (1 <= S <= 4): rows[0 .. S - 1] for a,
 * rows[S] for b. Unrolled, so that compilers fold them for a constant table. */
DYN_INL void dyn_inl_rows_of(const dyn_tableau *m, int S, dyn_inl_row *rows)
{
    DYN_INL_UNROLL
    for (int i = 0; i < S; i++)
        rows[i] = dyn_inl_row_of(m->a + (size_t)i * (size_t)S, i);
    rows[S] = dyn_inl_row_of(m->b, S);
}

/* 1 if the row summaries a[0..count) and b[0..count) are equal. */
DYN_INL int dyn_inl_rows_equal(const dyn_inl_row *a, const dyn_inl_row *b, int count)
{
    for (int i = 0; i < count; i++)
        if (a[i].nt != b[i].nt || a[i].j0 != b[i].j0 || a[i].fold != b[i].fold ||
            a[i].same != b[i].same)
            return 0;
    return 1;
}

/* The row summaries {nt, j0, fold, same} of the common tables: Euler; Heun; Heun's shape
 * with unequal weights (b = (1/4, 3/4) after a21 = 1, say); the midpoint rule; the classical
 * RK4. With these constants the stage loops are fixed at compile time even for a table
 * known only at run time (dyn_method_find): any table of the same shape takes the same
 * loop, its coefficients still read. dyn_fixed_solve_inline below and the library's
 * dyn_fixed_solve (its runs of plain steps, src/ode/fixed_driver.c) use them. */
#if defined(__GNUC__)
#define DYN_INL_UNUSED __attribute__((unused))
#else
#define DYN_INL_UNUSED
#endif
static const dyn_inl_row dyn_inl_euler_rows[2] DYN_INL_UNUSED = {{0, 0, 0, 0}, {1, 0, 1, 0}};
static const dyn_inl_row dyn_inl_heun_rows[3] DYN_INL_UNUSED = {
    {0, 0, 0, 0}, {1, 0, 1, 0}, {2, 0, 0, 1}};
static const dyn_inl_row dyn_inl_heun_shape_rows[3] DYN_INL_UNUSED = {
    {0, 0, 0, 0}, {1, 0, 1, 0}, {2, 0, 0, 0}};
static const dyn_inl_row dyn_inl_midpoint_rows[3] DYN_INL_UNUSED = {
    {0, 0, 0, 0}, {1, 0, 1, 0}, {1, 1, 1, 0}};
static const dyn_inl_row dyn_inl_rk4_rows[5] DYN_INL_UNUSED = {
    {0, 0, 0, 0}, {1, 0, 1, 0}, {1, 1, 1, 0}, {1, 2, 1, 0}, {4, 0, 0, 0}};
#undef DYN_INL_UNUSED

/* out = y + h * (sum_{j<len, row[j] != 0} row[j] k_j, left to right) over n states: the
 * library's arithmetic. Returns the number of terms (0: out is not written). */
DYN_INL int dyn_inl_combine(int n, double h, const double *DYN_RESTRICT y,
                            const double *DYN_RESTRICT k, const double *row, int len, dyn_inl_row r,
                            double *DYN_RESTRICT out)
{
    const size_t sn = (size_t)n;
    if (r.nt == 0)
        return 0;
    const double *k0 = k + (size_t)r.j0 * sn;
    if (r.fold) {
        const double hc = h * row[r.j0];
        DYN_INL_UNROLL
        for (int q = 0; q < n; q++) {
            double v = y[q] + hc * k0[q];
            DYN_INL_SCALAR(v);
            out[q] = v;
        }
        return 1;
    }
    if (r.same) {
        /* every coefficient from j0 on is the same power of two c: y + (h c)(k_j0 + ...),
         * equal to y + h (c k_j0 + ...) bit for bit (scaling by c is exact), with one
         * multiplication less after the last stage (Heun: the homework's y + Ts/2 (k1 + k2)) */
        const double hc = h * row[r.j0];
        DYN_INL_UNROLL
        for (int q = 0; q < n; q++) {
            double acc = k0[q];
            DYN_INL_UNROLL
            for (int j = r.j0 + 1; j < len; j++)
                acc += k[(size_t)j * sn + (size_t)q];
            double v = y[q] + hc * acc;
            DYN_INL_SCALAR(v);
            out[q] = v;
        }
        return r.nt;
    }
    if (r.nt == len - r.j0) {
        /* every coefficient from j0 on is non-zero: no tests (the same terms, in order) */
        DYN_INL_UNROLL
        for (int q = 0; q < n; q++) {
            double acc = row[r.j0] * k0[q];
            DYN_INL_UNROLL
            for (int j = r.j0 + 1; j < len; j++)
                acc += row[j] * k[(size_t)j * sn + (size_t)q];
            double v = y[q] + h * acc;
            DYN_INL_SCALAR(v);
            out[q] = v;
        }
        return r.nt;
    }
    DYN_INL_UNROLL
    for (int q = 0; q < n; q++) {
        double acc = row[r.j0] * k0[q];
        DYN_INL_UNROLL
        for (int j = 0; j < len; j++)
            if (j > r.j0 && row[j] != 0.0)
                acc += row[j] * k[(size_t)j * sn + (size_t)q];
        double v = y[q] + h * acc;
        DYN_INL_SCALAR(v);
        out[q] = v;
    }
    return r.nt;
}

/* Stage I of an S-stage table (I < S): Y_I, then k_I = f(t + c_I h, Y_I). Returns f's
 * value. Separate so that the stage loop is unrolled by hand (I constant). */
DYN_INL int dyn_inl_stage(const int S, const int I, const dyn_tableau *m, const dyn_inl_row *rows,
                          dyn_rhs_fn f, void *par, int n, double t, double h, double t1,
                          const double *DYN_RESTRICT y, double *DYN_RESTRICT k,
                          double *DYN_RESTRICT Y)
{
    const double *Yi = y;
    if (I > 0 && dyn_inl_combine(n, h, y, k, m->a + (size_t)I * (size_t)S, I, rows[I], Y) > 0)
        Yi = Y;
    double ti = t + m->c[I] * h;
    if (ti > t1)
        ti = t1;
    return f(ti, Yi, k + (size_t)I * (size_t)n, par);
}

/* One step of an S-stage table from y into ynew (rows[S] is b). Returns f's non-zero
 * value with the stage in *stage, or 0 with *nonfinite set if ynew is not finite. */
DYN_INL int dyn_inl_step(const int S, const dyn_tableau *m, const dyn_inl_row *rows, dyn_rhs_fn f,
                         void *par, int n, double t, double h, double t1,
                         const double *DYN_RESTRICT y, double *DYN_RESTRICT ynew,
                         double *DYN_RESTRICT k, double *DYN_RESTRICT Y, int *stage, int *nonfinite,
                         int check)
{
    int rc;
#define DYN_INL_STAGE(I)                                                                           \
    if ((I) < S &&                                                                                 \
        (rc = dyn_inl_stage(S, (I) < S ? (I) : 0, m, rows, f, par, n, t, h, t1, y, k, Y)) != 0) {  \
        *stage = (I);                                                                              \
        return rc;                                                                                 \
    }
    DYN_INL_STAGE(0)
    DYN_INL_STAGE(1)
    DYN_INL_STAGE(2)
    DYN_INL_STAGE(3)
#undef DYN_INL_STAGE
    if (dyn_inl_combine(n, h, y, k, m->b, S, rows[S], ynew) == 0)
        memcpy(ynew, y, (size_t)n * sizeof *y);
    if (check)
        *nonfinite = dyn_inl_nonfinite(n, ynew);
    return 0;
}

/* The solve for a table of S stages (1 <= S <= 4) whose rows (S + 1 of them, b last) are
 * summarised in rows: a constant for the common tables (see dyn_fixed_solve_inline), so
 * that the stage loops are fixed at compile time even when the coefficients are not. */
DYN_INL int dyn_inl_solve(const int S, const dyn_tableau *m, const dyn_inl_row *rows, dyn_rhs_fn f,
                          void *par, const int n, const dyn_grid *g, double *y, double *work,
                          int check, dyn_result *res)
{
    double *k = work, *Y = work + (size_t)S * (size_t)n, *ya = Y + n, *yb = ya + n;
    const double t0 = g->t0, t1 = g->t1, h = g->h;
    const long steps = g->samples - 1;
    double *cur = ya;
    long step = 0;
    int rc = 0, stage = 0, nonfinite = 0;
    memcpy(ya, y, (size_t)n * sizeof *y);
    if (n <= 4) {
        /* two steps per iteration, ya -> yb -> ya: the buffers are fixed in the loop body,
         * so the compiler can keep a small state in registers from one step to the next */
        while (step < steps) {
            double tn = t0 + (double)step * h;
            rc = dyn_inl_step(S, m, rows, f, par, n, tn, step < g->whole_steps ? h : t1 - tn, t1,
                              ya, yb, k, Y, &stage, &nonfinite, check);
            if (rc || nonfinite)
                break;
            cur = yb;
            if (++step == steps)
                break;
            tn = t0 + (double)step * h;
            rc = dyn_inl_step(S, m, rows, f, par, n, tn, step < g->whole_steps ? h : t1 - tn, t1,
                              yb, ya, k, Y, &stage, &nonfinite, check);
            if (rc || nonfinite)
                break;
            cur = ya;
            step++;
        }
    } else {
        /* one step per iteration: half the code (the right-hand side is inlined once per
         * stage, not twice), which matters more than registers for larger systems */
        while (step < steps) {
            const double tn = t0 + (double)step * h;
            double *nxt = cur == ya ? yb : ya;
            rc = dyn_inl_step(S, m, rows, f, par, n, tn, step < g->whole_steps ? h : t1 - tn, t1,
                              cur, nxt, k, Y, &stage, &nonfinite, check);
            if (rc || nonfinite)
                break;
            cur = nxt;
            step++;
        }
    }
    /* step is the number of kept steps; cur holds the last good state */
    memcpy(y, cur, (size_t)n * sizeof *y);
    res->stats.steps = step;
    res->t = step == 0 ? t0 : (g->ends_at_t1 && step == steps) ? t1 : t0 + (double)step * h;
    if (rc) {
        const double tn = t0 + (double)step * h;
        const double hn = step < g->whole_steps ? h : t1 - tn;
        double ti = tn + m->c[stage] * hn;
        res->stats.rhs_calls = step * S + stage + 1;
        res->rhs_status = rc;
        res->fail_t = ti > t1 ? t1 : ti;
        res->status = DYN_ERR_RHS;
        snprintf(res->message, sizeof res->message,
                 "the right-hand side failed at t = %s (status %d)", dyn_shortest(res->fail_t).s,
                 rc);
    } else if (nonfinite) {
        const double *bad = cur == ya ? yb : ya;
        int q = 0;
        while (q < n && isfinite(bad[q]))
            q++;
        res->stats.rhs_calls = (step + 1) * S;
        res->fail_t = (g->ends_at_t1 && step + 1 == steps) ? t1 : t0 + (double)(step + 1) * h;
        res->fail_index = q;
        res->status = DYN_ERR_NONFINITE;
        snprintf(res->message, sizeof res->message, "state %d became not finite at t = %s", q,
                 dyn_shortest(res->fail_t).s);
    } else {
        res->stats.rhs_calls = step * S;
    }
    return res->status;
}

/* dyn_fixed_solve with the stage loop compiled at the call site: same contract, same
 * results bit for bit (see the top of this header for when it pays). */
DYN_INL int dyn_fixed_solve_inline(const dyn_tableau *m, const dyn_system *sys, double t0,
                                   double t1, double h, const double *y0, double *y, double *work,
                                   const dyn_fixed_opts *opts, dyn_result *res)
{
    if (!sys)
        return dyn_fixed_solve(m, sys, t0, t1, h, y0, y, work, opts, res);
    /* read before any call, so that the compiler sees f as the constant it is */
    const dyn_rhs_fn f = sys->f;
    const int n = sys->n;
    void *const par = sys->par;
    dyn_grid g;
    dyn_result local;
    if (!m || m->kind != DYN_KIND_EXPLICIT_RK || m->stages < 1 || m->stages > 4 || !f || n <= 0 ||
        !y0 || !y || !work || (opts && (opts->output || opts->trace || opts->progress)) ||
        dyn_grid_plan(t0, t1, h, opts ? opts->end : DYN_END_EXACT, &g, NULL, 0) != DYN_OK)
        return dyn_fixed_solve(m, sys, t0, t1, h, y0, y, work, opts, res);
    for (int q = 0; q < n; q++)
        if (!isfinite(y0[q]))
            return dyn_fixed_solve(m, sys, t0, t1, h, y0, y, work, opts, res);
    if (!res)
        res = &local;
    memset(res, 0, sizeof *res);
    res->t = t0;
    res->fail_t = NAN;
    res->fail_index = -1;
    if (y != y0)
        memmove(y, y0, (size_t)n * sizeof *y);
    const int check = !(opts && opts->no_finite_check);
    const int S = m->stages;
    dyn_inl_row rows[5];
    dyn_inl_rows_of(m, S, rows);
    /* the common tables' shapes (dyn_inl_euler_rows ...) with their summaries as constants */
#define DYN_INL_SAME(known, count) (S + 1 == (count) && dyn_inl_rows_equal(rows, known, count))
    if (DYN_INL_SAME(dyn_inl_euler_rows, 2))
        return dyn_inl_solve(1, m, dyn_inl_euler_rows, f, par, n, &g, y, work, check, res);
    if (DYN_INL_SAME(dyn_inl_heun_rows, 3))
        return dyn_inl_solve(2, m, dyn_inl_heun_rows, f, par, n, &g, y, work, check, res);
    if (DYN_INL_SAME(dyn_inl_heun_shape_rows, 3))
        return dyn_inl_solve(2, m, dyn_inl_heun_shape_rows, f, par, n, &g, y, work, check, res);
    if (DYN_INL_SAME(dyn_inl_midpoint_rows, 3))
        return dyn_inl_solve(2, m, dyn_inl_midpoint_rows, f, par, n, &g, y, work, check, res);
    if (DYN_INL_SAME(dyn_inl_rk4_rows, 5))
        return dyn_inl_solve(4, m, dyn_inl_rk4_rows, f, par, n, &g, y, work, check, res);
#undef DYN_INL_SAME
#if defined(__GNUC__)
    /* A table of another shape known only at run time: the library's solve (the same
     * results). Compiling the generic loops for every stage count here as well would make
     * the caller so large that compilers stop inlining the right-hand side into it. */
    if (!__builtin_constant_p(S))
        return dyn_fixed_solve(m, sys, t0, t1, h, y0, y, work, opts, res);
#endif
    switch (S) {
    case 1: return dyn_inl_solve(1, m, rows, f, par, n, &g, y, work, check, res);
    case 2: return dyn_inl_solve(2, m, rows, f, par, n, &g, y, work, check, res);
    case 3: return dyn_inl_solve(3, m, rows, f, par, n, &g, y, work, check, res);
    default: return dyn_inl_solve(4, m, rows, f, par, n, &g, y, work, check, res);
    }
}

#undef DYN_INL
#undef DYN_INL_SCALAR
#undef DYN_INL_UNROLL
#undef DYN_RESTRICT

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_ODE_INLINE_H */
