/* SPDX-License-Identifier: BSD-3-Clause */
/* bench_suite: dynkit against the machine's limit and against its peers, in one run.
 *
 * Measures, with every solver integrating the same right-hand sides (bench_systems.h):
 * 1. fixed step (Euler, Heun, RK4) on van der Pol (2 states, the homework's 1500 steps of
 *    0.01) and the model plane (12 states, 500 steps of 0.01): ns per step and time per
 *    solve of a hand-written loop with the right-hand side inlined (the practical limit),
 *    dyn_fixed_solve, dyn_fixed_solve_inline (library table and a constant table) and the
 *    peers; the error at the end against a reference.
 * 2. adaptive work-precision on van der Pol (mu = 1, [0, 15]) and the Arenstorf orbit (one
 *    period), rtol = atol = 1e-1 .. 1e-12: error at t1 against the reference, right-hand-side
 *    calls and time, for bs23, dp45, dop853 (dyn_solve, no output grid), the same three
 *    through dyn_solve_inline (dynkit/solve_inline.h, right-hand side inlined) and the peers'
 *    pairs; calls and time are then compared at equal error (interpolated on the log-log
 *    curve), since equal tolerances are not equal accuracy: dyn_solve against GSL (both
 *    call the right-hand side through a pointer), dyn_solve_inline against Boost.
 * 2b. right-hand-side calls at equal error over families of problems (family.c): the pairs
 *    against the peers' methods of the same order over 24 van der Pol orbits, and each
 *    pair's controller settings over 30 problems.
 * 3. stiff van der Pol (mu = 1000, [0, 3000]): dynkit's stiff methods against CVODE and
 *    GSL's msbdf, at equal error.
 * 4. `dynkit report` end to end (the whole homework), as a separate process: with its
 *    studies of many runs, without them (--no-studies) and on one thread.
 * Then one table of the targets, met or missed. Peers (GSL, Boost.Odeint, SUNDIALS) are
 * compiled in when CMake found them (peer_*.c); timed runs are interleaved, rotating the
 * order, and repeated (medians), every solver created once outside the timing.
 *
 * Checks (exit status 1 when one fails): every fixed-step solver that computes the method
 * itself ends within 1e-12 (relative) of the hand-written loop; every solver gives the same
 * bits when run twice; every adaptive run reaches t1; errors fall with the tolerance.
 *
 * Usage: bench_suite [--quick] [--reps N] [--only LIST] [--peers LIST] [--svg DIR]
 *                    [--csv DIR] [--report-runs N] [--min]
 *   --min          the minimum of the timed samples instead of their median (for a loaded
 *                  machine: the least disturbed sample of each solver)
 *   --quick        one run per solver, few tolerances: checks only, times meaningless (CI)
 *   --reps N       timed repetitions (default 15 for fixed steps, 7 for the adaptive runs)
 *   --only LIST    sections: fixed,adaptive,family,stiff,report (default all)
 *   --peers LIST   gsl,boost,sundials, all (default) or none
 *   --svg DIR      write the work-precision diagrams (wp-*.svg) into DIR
 *   --csv DIR      write the adaptive and stiff measurements (wp-*.csv) into DIR
 *   --report-runs N  runs of `dynkit report` (default 20)
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <spawn.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/utsname.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <dynkit/ode.h>
#include <dynkit/ode_inline.h>
#include <dynkit/problems.h>
#include <dynkit/solve.h>
#include <dynkit/solve_inline.h>

#include "family.h"
#include "hand_loops.h"
#include "suite.h"
#include "bench_util.h"
#include "wp_front.h"
#include "wp_svg.h"

#define MAX_N 12
#define MAX_SOLVERS 24
#define MAX_TOLS 16
#define SAME_RTOL 1e-12
#define CLOBBER() __asm__ __volatile__("" ::: "memory")

/* ------------------------------------------------------------------------------------------
 * The fixed-step tables, as constants (checked equal to the library's in main)
 * ---------------------------------------------------------------------------------------- */
static const double euler_a[1] = {0.0}, euler_b[1] = {1.0}, euler_c[1] = {0.0};
static const double heun_a[4] = {0.0, 0.0, 1.0, 0.0}, heun_b[2] = {0.5, 0.5},
                    heun_c[2] = {0.0, 1.0};
static const double rk4_a[16] = {0.0, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0,
                                 0.0, 0.5, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0};
static const double rk4_b[4] = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};
static const double rk4_c[4] = {0.0, 0.5, 0.5, 1.0};

static const bench_table tables[BENCH_NMETHOD] = {
    {"euler", 1, 1, euler_a, euler_b, euler_c},
    {"heun", 2, 2, heun_a, heun_b, heun_c},
    {"rk4", 4, 4, rk4_a, rk4_b, rk4_c},
};

const bench_table *bench_fixed_table(bench_method m) { return &tables[m]; }

#define CONST_TABLEAU(NAME, T, S, P)                                                               \
    static const dyn_tableau NAME = {.name = #T,                                                   \
                                     .title = "constant copy",                                     \
                                     .reference = "bench",                                         \
                                     .kind = DYN_KIND_EXPLICIT_RK,                                 \
                                     .stages = S,                                                  \
                                     .order = P,                                                   \
                                     .a = T##_a,                                                   \
                                     .b = T##_b,                                                   \
                                     .c = T##_c};
CONST_TABLEAU(EULER_CONST, euler, 1, 1)
CONST_TABLEAU(HEUN_CONST, heun, 2, 2)
CONST_TABLEAU(RK4_CONST, rk4, 4, 4)

/* ------------------------------------------------------------------------------------------
 * Right-hand sides for dynkit: dyn_rhs_fn around the shared inline bodies
 * ---------------------------------------------------------------------------------------- */
#define DK_RHS_AS(SPEC, NAME, EVAL)                                                                \
    SPEC int NAME(double t, const double *y, double *dydt, void *par)                              \
    {                                                                                              \
        (void)t;                                                                                   \
        EVAL(y, dydt, par);                                                                        \
        return 0;                                                                                  \
    }
#define DK_RHS(NAME, EVAL) DK_RHS_AS(static, NAME, EVAL)
DK_RHS(dk_vdp, bench_vdp_eval)
DK_RHS(dk_plane, bench_plane_eval)
DK_RHS(dk_arenstorf, bench_arenstorf_eval)
DK_RHS(dk_kepler, bench_kepler_eval)
/* the same bodies for dyn_solve_inline, declared as its header asks (DYN_INLINE_RHS) */
DK_RHS_AS(DYN_INLINE_RHS, dk_vdp_inline, bench_vdp_eval)
DK_RHS_AS(DYN_INLINE_RHS, dk_arenstorf_inline, bench_arenstorf_eval)

static int dk_vdp_jac(double t, const double *y, double *J, void *par)
{
    (void)t;
    bench_vdp_jac(y, J, par);
    return 0;
}

static dyn_rhs_fn dk_rhs(const bench_sys *s)
{
    return s->id == BENCH_PLANE       ? dk_plane
           : s->id == BENCH_ARENSTORF ? dk_arenstorf
           : s->id == BENCH_KEPLER    ? dk_kepler
                                      : dk_vdp;
}

/* ------------------------------------------------------------------------------------------
 * Hand-written loops: the textbook formulas, right-hand side inlined, n a constant
 * ---------------------------------------------------------------------------------------- */
#define HAND_HEUN(NAME, N, PAR_T, EVAL)                                                            \
    static __attribute__((noinline)) void NAME(const void *vpar, const double *y0, double h,       \
                                               long steps, double *yout)                           \
    {                                                                                              \
        const PAR_T *par = vpar;                                                                   \
        double y[N], Y[N], k1[N], k2[N];                                                           \
        memcpy(y, y0, sizeof y);                                                                   \
        const double h2 = 0.5 * h;                                                                 \
        for (long step = 0; step < steps; step++) {                                                \
            EVAL(y, k1, par);                                                                      \
            HAND_UNROLL                                                                            \
            for (int q = 0; q < N; q++)                                                            \
                Y[q] = y[q] + h * k1[q];                                                           \
            EVAL(Y, k2, par);                                                                      \
            HAND_UNROLL                                                                            \
            for (int q = 0; q < N; q++)                                                            \
                y[q] += h2 * (k1[q] + k2[q]);                                                      \
        }                                                                                          \
        memcpy(yout, y, sizeof y);                                                                 \
    }
#define HAND_EULER(NAME, N, PAR_T, EVAL)                                                           \
    static __attribute__((noinline)) void NAME(const void *vpar, const double *y0, double h,       \
                                               long steps, double *yout)                           \
    {                                                                                              \
        const PAR_T *par = vpar;                                                                   \
        double y[N], k1[N];                                                                        \
        memcpy(y, y0, sizeof y);                                                                   \
        for (long step = 0; step < steps; step++) {                                                \
            EVAL(y, k1, par);                                                                      \
            HAND_UNROLL                                                                            \
            for (int q = 0; q < N; q++)                                                            \
                y[q] += h * k1[q];                                                                 \
        }                                                                                          \
        memcpy(yout, y, sizeof y);                                                                 \
    }
/* Diagnostic: the same loops with the last combination as a sum of products,
 * y + (h b_1) k_1 + (h b_2) k_2 + ..., the form Boost.Odeint computes: the products of the
 * earlier stages are ready before the last one, so the chain after the last right-hand side
 * is one multiplication and one addition shorter than y + h (b_1 k_1 + ...). */
#define HAND_RK4_SOP(NAME, N, PAR_T, EVAL)                                                         \
    static __attribute__((noinline)) void NAME(const void *vpar, const double *y0, double h,       \
                                               long steps, double *yout)                           \
    {                                                                                              \
        const PAR_T *par = vpar;                                                                   \
        double y[N], Y[N], k1[N], k2[N], k3[N], k4[N];                                             \
        memcpy(y, y0, sizeof y);                                                                   \
        const double h2 = 0.5 * h, h6 = h / 6.0, h3 = h / 3.0;                                     \
        for (long step = 0; step < steps; step++) {                                                \
            EVAL(y, k1, par);                                                                      \
            HAND_UNROLL                                                                            \
            for (int q = 0; q < N; q++)                                                            \
                Y[q] = y[q] + h2 * k1[q];                                                          \
            EVAL(Y, k2, par);                                                                      \
            HAND_UNROLL                                                                            \
            for (int q = 0; q < N; q++)                                                            \
                Y[q] = y[q] + h2 * k2[q];                                                          \
            EVAL(Y, k3, par);                                                                      \
            HAND_UNROLL                                                                            \
            for (int q = 0; q < N; q++)                                                            \
                Y[q] = y[q] + h * k3[q];                                                           \
            EVAL(Y, k4, par);                                                                      \
            HAND_UNROLL                                                                            \
            for (int q = 0; q < N; q++)                                                            \
                y[q] = y[q] + h6 * k1[q] + h3 * k2[q] + h3 * k3[q] + h6 * k4[q];                   \
        }                                                                                          \
        memcpy(yout, y, sizeof y);                                                                 \
    }
#define HAND_HEUN_SOP(NAME, N, PAR_T, EVAL)                                                        \
    static __attribute__((noinline)) void NAME(const void *vpar, const double *y0, double h,       \
                                               long steps, double *yout)                           \
    {                                                                                              \
        const PAR_T *par = vpar;                                                                   \
        double y[N], Y[N], k1[N], k2[N];                                                           \
        memcpy(y, y0, sizeof y);                                                                   \
        const double h2 = 0.5 * h;                                                                 \
        for (long step = 0; step < steps; step++) {                                                \
            EVAL(y, k1, par);                                                                      \
            HAND_UNROLL                                                                            \
            for (int q = 0; q < N; q++)                                                            \
                Y[q] = y[q] + h * k1[q];                                                           \
            EVAL(Y, k2, par);                                                                      \
            HAND_UNROLL                                                                            \
            for (int q = 0; q < N; q++)                                                            \
                y[q] = y[q] + h2 * k1[q] + h2 * k2[q];                                             \
        }                                                                                          \
        memcpy(yout, y, sizeof y);                                                                 \
    }
HAND_HEUN_SOP(sop_heun_vdp, 2, bench_vdp_par, bench_vdp_eval)
HAND_RK4_SOP(sop_rk4_vdp, 2, bench_vdp_par, bench_vdp_eval)
HAND_HEUN_SOP(sop_heun_plane, 12, bench_plane_par, bench_plane_eval)
HAND_RK4_SOP(sop_rk4_plane, 12, bench_plane_par, bench_plane_eval)

HAND_EULER(hand_euler_vdp, 2, bench_vdp_par, bench_vdp_eval)
HAND_HEUN(hand_heun_vdp, 2, bench_vdp_par, bench_vdp_eval)
HAND_RK4(hand_rk4_vdp, 2, bench_vdp_par, bench_vdp_eval)
HAND_EULER(hand_euler_plane, 12, bench_plane_par, bench_plane_eval)
HAND_HEUN(hand_heun_plane, 12, bench_plane_par, bench_plane_eval)
HAND_RK4(hand_rk4_plane, 12, bench_plane_par, bench_plane_eval)

typedef void (*hand_fn)(const void *par, const double *y0, double h, long steps, double *y);

/* Diagnostic: the same textbook loops with what a compiled library cannot avoid, the
 * right-hand side called through a pointer and n known only at run time: the floor of any
 * compiled driver (see bench_fixed.c). PIN keeps the loops scalar, as the library's
 * small-system loops are (a vector load of two values just stored one at a time by the
 * right-hand side stalls on store forwarding). */
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#define PIN(v) __asm__("" : "+x"(v))
#else
#define PIN(v) ((void)0)
#endif
#define PTR_PUT(dst, q, expr)                                                                      \
    do {                                                                                           \
        double v_ = (expr);                                                                        \
        PIN(v_);                                                                                   \
        dst[q] = v_;                                                                               \
    } while (0)
static __attribute__((noinline)) void ptr_loop(bench_method meth, dyn_rhs_fn f, void *par, int n,
                                               const double *y0, double h, long steps, double *yout)
{
    double y[MAX_N], Y[MAX_N], k1[MAX_N], k2[MAX_N], k3[MAX_N], k4[MAX_N];
    memcpy(y, y0, (size_t)n * sizeof *y);
    const double h2 = 0.5 * h, h6 = h / 6.0;
    for (long step = 0; step < steps; step++) {
        const double t = (double)step * h;
        f(t, y, k1, par);
        if (meth == BENCH_EULER) {
            for (int q = 0; q < n; q++)
                PTR_PUT(y, q, y[q] + h * k1[q]);
        } else if (meth == BENCH_HEUN) {
            for (int q = 0; q < n; q++)
                PTR_PUT(Y, q, y[q] + h * k1[q]);
            f(t + h, Y, k2, par);
            for (int q = 0; q < n; q++)
                PTR_PUT(y, q, y[q] + h2 * (k1[q] + k2[q]));
        } else {
            for (int q = 0; q < n; q++)
                PTR_PUT(Y, q, y[q] + h2 * k1[q]);
            f(t + h2, Y, k2, par);
            for (int q = 0; q < n; q++)
                PTR_PUT(Y, q, y[q] + h2 * k2[q]);
            f(t + h2, Y, k3, par);
            for (int q = 0; q < n; q++)
                PTR_PUT(Y, q, y[q] + h * k3[q]);
            f(t + h, Y, k4, par);
            for (int q = 0; q < n; q++)
                PTR_PUT(y, q, y[q] + h6 * (k1[q] + 2.0 * k2[q] + 2.0 * k3[q] + k4[q]));
        }
    }
    memcpy(yout, y, (size_t)n * sizeof *y);
}

/* dyn_fixed_solve_inline with the right-hand side visible: one solver per system and table */
typedef int (*inline_fn)(const dyn_tableau *m, void *par, double t0, double t1, double h,
                         const double *y0, double *y, double *work, dyn_result *res);
static const dyn_fixed_opts NO_CHECK = {.no_finite_check = 1};
#define INLINE_SOLVER(NAME, RHS, N, TABLE, OPTS)                                                   \
    static __attribute__((noinline)) int NAME(const dyn_tableau *m, void *par, double t0,          \
                                              double t1, double h, const double *y0, double *y,    \
                                              double *work, dyn_result *res)                       \
    {                                                                                              \
        const dyn_system sys = {RHS, N, par};                                                      \
        (void)m;                                                                                   \
        return dyn_fixed_solve_inline(TABLE, &sys, t0, t1, h, y0, y, work, OPTS, res);             \
    }
INLINE_SOLVER(inline_vdp, dk_vdp, 2, m, NULL)
INLINE_SOLVER(inline_plane, dk_plane, 12, m, NULL)
INLINE_SOLVER(inline_euler_vdp, dk_vdp, 2, &EULER_CONST, NULL)
INLINE_SOLVER(inline_heun_vdp, dk_vdp, 2, &HEUN_CONST, NULL)
INLINE_SOLVER(inline_rk4_vdp, dk_vdp, 2, &RK4_CONST, NULL)
INLINE_SOLVER(inline_euler_plane, dk_plane, 12, &EULER_CONST, NULL)
INLINE_SOLVER(inline_heun_plane, dk_plane, 12, &HEUN_CONST, NULL)
INLINE_SOLVER(inline_rk4_plane, dk_plane, 12, &RK4_CONST, NULL)
INLINE_SOLVER(nocheck_euler_vdp, dk_vdp, 2, &EULER_CONST, &NO_CHECK)
INLINE_SOLVER(nocheck_heun_vdp, dk_vdp, 2, &HEUN_CONST, &NO_CHECK)
INLINE_SOLVER(nocheck_rk4_vdp, dk_vdp, 2, &RK4_CONST, &NO_CHECK)
INLINE_SOLVER(nocheck_euler_plane, dk_plane, 12, &EULER_CONST, &NO_CHECK)
INLINE_SOLVER(nocheck_heun_plane, dk_plane, 12, &HEUN_CONST, &NO_CHECK)
INLINE_SOLVER(nocheck_rk4_plane, dk_plane, 12, &RK4_CONST, &NO_CHECK)

/* ------------------------------------------------------------------------------------------
 * The local solvers (hand-written loop and dynkit) behind the bench_solver interface
 * ---------------------------------------------------------------------------------------- */
enum {
    DK_HAND,
    DK_PTR,
    DK_FIXED,
    DK_INLINE,
    DK_INLINE_CONST,
    DK_INLINE_NOCHECK,
    DK_SOLVE,
    DK_SOLVE_INLINE
};

/* dyn_solve_inline with the right-hand side visible: one solver per system */
typedef int (*solve_inline_fn)(const dyn_tableau *m, void *par, double t0, double t1,
                               const double *y0, double *y, double *work,
                               const dyn_solve_opts *o, dyn_result *res);
#define SOLVE_INLINE(NAME, RHS, N)                                                                 \
    static __attribute__((noinline)) int NAME(const dyn_tableau *m, void *par, double t0,          \
                                              double t1, const double *y0, double *y,              \
                                              double *work, const dyn_solve_opts *o,               \
                                              dyn_result *res)                                     \
    {                                                                                              \
        const dyn_system sys = {RHS, N, par};                                                      \
        return dyn_solve_inline(m, &sys, t0, t1, y0, y, work, o, res);                             \
    }
SOLVE_INLINE(solve_inline_vdp, dk_vdp_inline, 2)
SOLVE_INLINE(solve_inline_arenstorf, dk_arenstorf_inline, 4)

typedef struct dk_ctx {
    int kind;
    bench_method method;
    const bench_sys *sys;
    const dyn_tableau *m;
    hand_fn hand;
    inline_fn inl;
    solve_inline_fn sinl;
    dyn_system dsys;
    dyn_solve_opts opts;
    double *work;
    int *iwork;
} dk_ctx;

static void dk_destroy(void *vctx)
{
    dk_ctx *x = vctx;
    if (x) {
        free(x->work);
        free(x->iwork);
        free(x);
    }
}

static int dk_fixed_run(void *vctx, double h, long steps, double *y, bench_counts *counts)
{
    dk_ctx *x = vctx;
    const bench_sys *s = x->sys;
    const double t1 = s->t0 + (double)steps * h;
    dyn_result res;
    int rc = DYN_OK;
    res.stats.rhs_calls = steps * x->m->stages;
    switch (x->kind) {
    case DK_HAND: x->hand(s->par, s->y0, h, steps, y); break;
    case DK_PTR: {
        dyn_rhs_fn volatile fv = x->dsys.f; /* read through a volatile: never inlined */
        ptr_loop(x->method, fv, x->dsys.par, s->n, s->y0, h, steps, y);
        break;
    }
    case DK_FIXED:
        rc = dyn_fixed_solve(x->m, &x->dsys, s->t0, t1, h, s->y0, y, x->work, NULL, &res);
        break;
    default: rc = x->inl(x->m, x->dsys.par, s->t0, t1, h, s->y0, y, x->work, &res); break;
    }
    if (counts) {
        counts->rhs = res.stats.rhs_calls;
        counts->jac = 0;
        counts->steps = steps;
    }
    return rc != DYN_OK;
}

static int dk_solve_run(void *vctx, double tol, long steps, double *y, bench_counts *counts)
{
    dk_ctx *x = vctx;
    const bench_sys *s = x->sys;
    dyn_solve_opts o = x->opts;
    dyn_result res;
    (void)steps;
    o.rtol = o.atol = tol;
    const int rc =
        x->kind == DK_SOLVE_INLINE
            ? x->sinl(x->m, x->dsys.par, s->t0, s->t1, s->y0, y, x->work, &o, &res)
            : dyn_solve(x->m, &x->dsys, s->t0, s->t1, s->y0, y, x->work, &o, &res);
    if (counts) {
        counts->rhs = res.stats.rhs_calls;
        counts->jac = res.stats.jac_calls;
        counts->steps = res.stats.accepted;
    }
    return rc != DYN_OK || res.t != s->t1;
}

static int add_dk(bench_solver *out, int *count, int max, dk_ctx *x, const char *peer,
                  const char *label, int flags, int order, double calls_per_step,
                  int (*run)(void *, double, long, double *, bench_counts *))
{
    if (!x)
        return 1;
    if (*count >= max) {
        dk_destroy(x);
        return 1;
    }
    bench_solver *s = &out[(*count)++];
    memset(s, 0, sizeof *s);
    snprintf(s->label, sizeof s->label, "%s", label);
    s->peer = peer;
    s->is_dynkit = strcmp(peer, "dynkit") == 0;
    s->flags = flags;
    s->order = order;
    s->step_factor = 1.0;
    s->calls_per_step = calls_per_step;
    s->ctx = x;
    s->run = run;
    s->destroy = dk_destroy;
    return 0;
}

static dk_ctx *dk_new(int kind, const bench_sys *sys, const dyn_tableau *m)
{
    dk_ctx *x = calloc(1, sizeof *x);
    if (!x)
        return NULL;
    x->kind = kind;
    x->sys = sys;
    x->m = m;
    x->dsys.f = dk_rhs(sys);
    x->dsys.n = sys->n;
    x->dsys.par = (void *)sys->par;
    return x;
}

static const dyn_tableau *const_table(bench_method m)
{
    return m == BENCH_EULER ? &EULER_CONST : m == BENCH_HEUN ? &HEUN_CONST : &RK4_CONST;
}

static int local_fixed(const bench_sys *sys, bench_method m, bench_solver *out, int max)
{
    static const hand_fn hands[2][BENCH_NMETHOD] = {
        {hand_euler_vdp, hand_heun_vdp, hand_rk4_vdp},
        {hand_euler_plane, hand_heun_plane, hand_rk4_plane}};
    static const inline_fn consts[2][BENCH_NMETHOD] = {
        {inline_euler_vdp, inline_heun_vdp, inline_rk4_vdp},
        {inline_euler_plane, inline_heun_plane, inline_rk4_plane}};
    static const inline_fn nochecks[2][BENCH_NMETHOD] = {
        {nocheck_euler_vdp, nocheck_heun_vdp, nocheck_rk4_vdp},
        {nocheck_euler_plane, nocheck_heun_plane, nocheck_rk4_plane}};
    static const hand_fn sops[2][BENCH_NMETHOD] = {{NULL, sop_heun_vdp, sop_rk4_vdp},
                                                   {NULL, sop_heun_plane, sop_rk4_plane}};
    const int p = sys->id == BENCH_PLANE;
    const dyn_tableau *lib = dyn_method_find(tables[m].name);
    const int s = tables[m].s;
    int count = 0;
    dk_ctx *x = dk_new(DK_HAND, sys, const_table(m));
    if (x)
        x->hand = hands[p][m];
    add_dk(out, &count, max, x, "hand", "hand-written loop, rhs inlined, textbook sums", BENCH_SAME,
           0, s, dk_fixed_run);
    const struct {
        int kind;
        const char *label;
    } rows[] = {{DK_FIXED, "dynkit dyn_fixed_solve"},
                {DK_INLINE, "dynkit dyn_fixed_solve_inline, library table"},
                {DK_INLINE_CONST, "dynkit dyn_fixed_solve_inline, constant table"},
                {DK_INLINE_NOCHECK, "dynkit dyn_fixed_solve_inline, constant table, "
                                    "no_finite_check"}};
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        x = dk_new(rows[i].kind, sys, rows[i].kind >= DK_INLINE_CONST ? const_table(m) : lib);
        if (x) {
            x->inl = rows[i].kind == DK_INLINE         ? (p ? inline_plane : inline_vdp)
                     : rows[i].kind == DK_INLINE_CONST ? consts[p][m]
                                                       : nochecks[p][m];
            x->work = malloc(dyn_fixed_work_size(x->m, sys->n) * sizeof(double));
            if (!x->work) {
                dk_destroy(x);
                x = NULL;
            }
        }
        add_dk(out, &count, max, x, "dynkit", rows[i].label, BENCH_SAME, 0, s, dk_fixed_run);
    }
    if (sops[p][m]) {
        x = dk_new(DK_HAND, sys, const_table(m));
        if (x)
            x->hand = sops[p][m];
        add_dk(out, &count, max, x, "hand",
               "hand-written loop, rhs inlined, y + sum (h b_i) k_i (Boost's arithmetic)",
               BENCH_SAME | BENCH_DIAG, 0, s, dk_fixed_run);
    }
    x = dk_new(DK_PTR, sys, const_table(m));
    if (x)
        x->method = m;
    add_dk(out, &count, max, x, "diagnostic",
           "diagnostic: hand-written loop, rhs by pointer (floor of a compiled driver)",
           BENCH_SAME | BENCH_DIAG, 0, s, dk_fixed_run);
    return count;
}

/* A dynkit pair with other controller settings (beta, safety, fac_min, fac_max of ctl), as a
 * diagnostic row of the adaptive section. */
static void add_controller_diagnostic(bench_solver *out, int *count, int max,
                                      const bench_sys *sys, const char *method,
                                      const dyn_solve_opts *ctl, const char *label)
{
    const dyn_tableau *m = dyn_method_find(method);
    dk_ctx *x = m ? dk_new(DK_SOLVE, sys, m) : NULL;
    if (x) {
        x->opts.beta = ctl->beta;
        x->opts.safety = ctl->safety;
        x->opts.fac_min = ctl->fac_min;
        x->opts.fac_max = ctl->fac_max;
        const size_t nw = dyn_solve_work_size(m, sys->n, &x->opts);
        x->work = malloc((nw ? nw : 1) * sizeof(double));
        if (!x->work) {
            dk_destroy(x);
            x = NULL;
        }
    }
    add_dk(out, count, max, x, "diagnostic", label, BENCH_DIAG, m ? m->order : 0, 0.0,
           dk_solve_run);
}

static int local_solve(const bench_sys *sys, bench_task task, bench_solver *out, int max)
{
    int count = 0;
    for (int i = 0; i < dyn_method_count(); i++) {
        const dyn_tableau *m = dyn_method_at(i);
        if (!dyn_method_is_adaptive(m) || dyn_method_is_stiff(m) != (task == BENCH_TASK_STIFF))
            continue;
        for (int fd = 0; fd < (task == BENCH_TASK_STIFF ? 2 : 1); fd++) {
            dk_ctx *x = dk_new(DK_SOLVE, sys, m);
            if (!x)
                continue;
            if (task == BENCH_TASK_STIFF && !fd)
                x->opts.jacobian = dk_vdp_jac;
            const size_t nw = dyn_solve_work_size(m, sys->n, &x->opts);
            const size_t ni = dyn_solve_iwork_size(m, sys->n);
            x->work = malloc((nw ? nw : 1) * sizeof(double));
            x->iwork = malloc((ni ? ni : 1) * sizeof(int));
            x->opts.iwork = ni ? x->iwork : NULL;
            if (!nw || !x->work || !x->iwork) {
                dk_destroy(x);
                continue;
            }
            char label[80];
            if (task == BENCH_TASK_STIFF)
                snprintf(label, sizeof label, "dynkit %s, %s Jacobian", m->name,
                         fd ? "difference" : "analytic");
            else
                snprintf(label, sizeof label, "dynkit %s", m->name);
            add_dk(out, &count, max, x, "dynkit", label, 0, m->order, 0.0, dk_solve_run);
        }
    }
    /* the header-only driver (dynkit/solve_inline.h) for the pairs it takes inline */
    const char *inl_names[] = {"bs23", "dp45", "dop853"};
    for (int i = 0; task == BENCH_TASK_ADAPTIVE && i < 3; i++) {
        const dyn_tableau *mi = dyn_method_find(inl_names[i]);
        solve_inline_fn fn = sys->id == BENCH_VDP         ? solve_inline_vdp
                             : sys->id == BENCH_ARENSTORF ? solve_inline_arenstorf
                                                          : NULL;
        dk_ctx *xi = mi && fn ? dk_new(DK_SOLVE_INLINE, sys, mi) : NULL;
        if (!xi)
            continue;
        xi->sinl = fn;
        const size_t nw = dyn_solve_work_size(mi, sys->n, &xi->opts);
        xi->work = malloc((nw ? nw : 1) * sizeof(double));
        if (!xi->work) {
            dk_destroy(xi);
            continue;
        }
        char label[80];
        snprintf(label, sizeof label, "dynkit %s, dyn_solve_inline (header-only)", mi->name);
        add_dk(out, &count, max, xi, "dynkit inline", label, BENCH_INLINE, mi->order, 0.0,
               dk_solve_run);
    }
    /* diagnostics, to keep the controllers' choices measured (docs/solvers.md; over many
     * problems in section 2b, family.c): dop853 with the default controller of Hairer's
     * dop853.f (pure I: beta = 0, safety 0.9, 0.333 <= h_new/h <= 6) instead of dynkit's
     * (DOPRI5's PI controller), and dop853 and dp45 with the reference codes' safety 0.9
     * instead of their own 0.85 and 0.8 */
    if (task == BENCH_TASK_ADAPTIVE) {
        const dyn_solve_opts i_ctl = {
            .safety = 0.9, .beta = -1.0 /* negative: none */, .fac_min = 0.333, .fac_max = 6.0};
        const dyn_solve_opts safety_09 = {.safety = 0.9};
        add_controller_diagnostic(out, &count, max, sys, "dop853", &i_ctl,
                                  "diagnostic: dynkit dop853, dop853.f's I controller "
                                  "(beta 0, 0.333 .. 6)");
        add_controller_diagnostic(out, &count, max, sys, "dop853", &safety_09,
                                  "diagnostic: dynkit dop853, dop853.f's safety 0.9");
        add_controller_diagnostic(out, &count, max, sys, "dp45", &safety_09,
                                  "diagnostic: dynkit dp45, dopri5.f's safety 0.9");
    }
    return count;
}

/* ------------------------------------------------------------------------------------------
 * Options, peers, output
 * ---------------------------------------------------------------------------------------- */
static const bench_peer *const all_peers[] = {
#ifdef BENCH_HAVE_GSL
    &bench_peer_gsl,
#endif
#ifdef BENCH_HAVE_BOOST
    &bench_peer_boost,
#endif
#ifdef BENCH_HAVE_SUNDIALS
    &bench_peer_sundials,
#endif
    NULL};

typedef struct options {
    int quick;
    int reps_fixed, reps_adaptive;
    int sections; /* bits: 1 fixed, 2 adaptive, 4 stiff, 8 report */
    int peers_none;
    char peers[128]; /* comma list, or "" for all */
    const char *svg_dir, *csv_dir;
    int report_runs;
} options;

static int peer_enabled(const options *o, const char *name)
{
    if (o->peers_none)
        return 0;
    if (!o->peers[0])
        return 1;
    char buf[128];
    snprintf(buf, sizeof buf, "%s", o->peers);
    for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save))
        if (strcmp(tok, name) == 0)
            return 1;
    return 0;
}

static int collect(const options *o, const bench_sys *sys, bench_task task, bench_method m,
                   bench_solver *out)
{
    int count = task == BENCH_TASK_FIXED ? local_fixed(sys, m, out, MAX_SOLVERS)
                                         : local_solve(sys, task, out, MAX_SOLVERS);
    for (int i = 0; all_peers[i] && sys->id != BENCH_KEPLER; i++)
        if (peer_enabled(o, all_peers[i]->name))
            count += all_peers[i]->solvers(sys, task, m, out + count, MAX_SOLVERS - count);
    return count;
}

static void release(bench_solver *s, int count)
{
    for (int i = 0; i < count; i++)
        if (s[i].destroy)
            s[i].destroy(s[i].ctx);
}

/* section 2b (family.c): the adaptive section's solvers without its diagnostic and
 * header-only rows, and dynkit's pairs with other controller settings */
static const options *family_options;
static int family_collect(const bench_sys *sys, bench_solver *out, int max)
{
    bench_solver all[MAX_SOLVERS];
    const int n = collect(family_options, sys, BENCH_TASK_ADAPTIVE, BENCH_NMETHOD, all);
    int count = 0;
    for (int i = 0; i < n; i++) {
        if (!(all[i].flags & (BENCH_DIAG | BENCH_INLINE | BENCH_WRONG)) && count < max)
            out[count++] = all[i];
        else if (all[i].destroy)
            all[i].destroy(all[i].ctx);
    }
    return count;
}

static int family_variant(const bench_sys *sys, const char *method, const dyn_solve_opts *ctl,
                          const char *label, bench_solver *out, int max)
{
    int count = 0;
    add_controller_diagnostic(out, &count, max, sys, method, ctl, label);
    return count;
}

/* ------------------------------------------------------------------------------------------
 * Timing
 * ---------------------------------------------------------------------------------------- */
static double now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

typedef struct meas {
    int ok;            /* every run succeeded */
    int deterministic; /* two runs gave the same bits */
    double med, min;   /* ns per run (solve) */
    double y[MAX_N];
    bench_counts counts;
    double err; /* max_i |y_i - ref_i| */
} meas;

static double max_abs_diff(const double *a, const double *b, int n)
{
    double d = 0.0;
    for (int i = 0; i < n; i++)
        d = fmax(d, fabs(a[i] - b[i]));
    return d;
}

static double rel_diff(const double *a, const double *b, int n)
{
    double d = 0.0, scale = 0.0;
    for (int i = 0; i < n; i++) {
        d = fmax(d, fabs(a[i] - b[i]));
        scale = fmax(scale, fabs(b[i]));
    }
    return scale > 0 ? d / scale : d;
}

/* One timed thing: a solver with its argument (h or tol, as the solver runs it) and steps. */
typedef struct item {
    bench_solver *s;
    double arg;
    long steps;
    meas *m;
} item;

/* Runs every item once (results, counts, error against ref) and again (same bits?), then
 * `reps` rounds of timed samples of about target_ns each, every round over all items in an
 * order that rotates from round to round, so that a noisy moment of the machine spreads
 * over all of them instead of falling on one. */
static int use_min; /* --min: the minimum of the samples instead of their median */
static void measure(item *it, int count, int n, int reps, double target_ns, const double *ref)
{
    long *batch = malloc((size_t)(count > 0 ? count : 1) * sizeof *batch);
    double *samples =
        malloc((size_t)(count > 0 ? count : 1) * (size_t)(reps > 0 ? reps : 1) * sizeof *samples);
    if (!batch || !samples) {
        free(batch);
        free(samples);
        for (int i = 0; i < count; i++)
            memset(it[i].m, 0, sizeof *it[i].m);
        return;
    }
    for (int i = 0; i < count; i++) {
        meas *m = it[i].m;
        double y2[MAX_N];
        memset(m, 0, sizeof *m);
        const double t0 = now_ns();
        m->ok = it[i].s->run(it[i].s->ctx, it[i].arg, it[i].steps, m->y, &m->counts) == 0;
        const double one = now_ns() - t0;
        m->ok &= it[i].s->run(it[i].s->ctx, it[i].arg, it[i].steps, y2, NULL) == 0;
        m->deterministic = memcmp(y2, m->y, (size_t)n * sizeof(double)) == 0;
        m->err = ref ? max_abs_diff(m->y, ref, n) : NAN;
        batch[i] = (long)ceil(target_ns / fmax(one, 1.0));
        if (batch[i] < 1)
            batch[i] = 1;
        m->med = m->min = one;
    }
    for (int r = 0; r < reps; r++)
        for (int k = 0; k < count; k++) {
            const int i = (k + r * (count / reps + 1)) % count;
            double y[MAX_N];
            if (!it[i].m->ok) {
                samples[i * reps + r] = NAN;
                continue;
            }
            const double t0 = now_ns();
            for (long b = 0; b < batch[i]; b++) {
                it[i].s->run(it[i].s->ctx, it[i].arg, it[i].steps, y, NULL);
                CLOBBER();
            }
            samples[i * reps + r] = (now_ns() - t0) / (double)batch[i];
        }
    for (int i = 0; i < count && reps > 0; i++)
        if (it[i].m->ok) {
            it[i].m->med = bench_median(samples + i * reps, reps);
            it[i].m->min = samples[i * reps];
            if (use_min)
                it[i].m->med = it[i].m->min; /* every table and target then uses it */
        }
    free(batch);
    free(samples);
}

/* ------------------------------------------------------------------------------------------
 * Summary of the targets
 * ---------------------------------------------------------------------------------------- */
#define MAX_TARGETS 128
typedef struct target {
    char task[64], what[96], value[96], goal[40];
    int met;
} target;
static target targets[MAX_TARGETS];
static int n_targets;

static void add_target(int met, const char *task, const char *what, const char *goal,
                       const char *fmt, ...) __attribute__((format(printf, 5, 6)));
static void add_target(int met, const char *task, const char *what, const char *goal,
                       const char *fmt, ...)
{
    if (n_targets >= MAX_TARGETS)
        return;
    target *t = &targets[n_targets++];
    snprintf(t->task, sizeof t->task, "%s", task);
    snprintf(t->what, sizeof t->what, "%s", what);
    snprintf(t->goal, sizeof t->goal, "%s", goal);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(t->value, sizeof t->value, fmt, ap);
    va_end(ap);
    t->met = met;
}

static void family_target(int met, const char *task, const char *what, const char *goal,
                          const char *value)
{
    add_target(met, task, what, goal, "%s", value);
}

static int checks_failed;
static void check(int ok, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void check(int ok, const char *fmt, ...)
{
    if (ok)
        return;
    checks_failed++;
    va_list ap;
    va_start(ap, fmt);
    fputs("CHECK FAILED: ", stdout);
    vprintf(fmt, ap);
    fputc('\n', stdout);
    va_end(ap);
}

/* Notes under a table: each distinct one once. */
static void family_check(int ok, const char *message) { check(ok, "%s", message); }

static void print_notes(const bench_solver *s, int count)
{
    for (int i = 0; i < count; i++) {
        if (!s[i].note[0])
            continue;
        int seen = 0;
        for (int j = 0; j < i; j++)
            seen |= strcmp(s[j].note, s[i].note) == 0;
        if (!seen)
            printf("- %s: %s.\n", s[i].label, s[i].note);
    }
}

/* ------------------------------------------------------------------------------------------
 * 1. Fixed steps
 * ---------------------------------------------------------------------------------------- */
static void fixed_section(const options *o, const bench_sys *sys, double h, long steps,
                          const double *ref, const char *ref_text)
{
    static const char *const method_names[BENCH_NMETHOD] = {"Euler", "Heun", "RK4"};
    for (int mi = 0; mi < BENCH_NMETHOD; mi++) {
        bench_solver s[MAX_SOLVERS];
        meas m[MAX_SOLVERS];
        const int count = collect(o, sys, BENCH_TASK_FIXED, (bench_method)mi, s);
        item it[MAX_SOLVERS];
        for (int i = 0; i < count; i++)
            it[i] = (item){&s[i], h * s[i].step_factor, (long)((double)steps / s[i].step_factor),
                           &m[i]};
        measure(it, count, sys->n, o->quick ? 0 : o->reps_fixed, o->quick ? 0 : 5e6, ref);
        printf("\n### Fixed step, %s: %s (%d states), %ld steps of %g\n\n", method_names[mi],
               sys->name, sys->n, steps, h);
        /* the reference: the fastest hand-written loop of this run (textbook sums or Boost's
         * form); the floor of a compiled driver: the hand-written loop calling by pointer */
        double hand_med = INFINITY, floor_med = NAN;
        const char *hand_label = "";
        for (int i = 0; i < count; i++) {
            if (strcmp(s[i].peer, "hand") == 0 && m[i].med < hand_med) {
                hand_med = m[i].med;
                hand_label = s[i].label;
            }
            if (strstr(s[i].label, "rhs by pointer") && strcmp(s[i].peer, "diagnostic") == 0)
                floor_med = m[i].med;
        }
        printf("| solver | ns/step | us/solve | x hand | calls/step | error at t1 | check |\n");
        printf("|---|---:|---:|---:|---:|---:|---|\n");
        double best_peer = INFINITY;
        const char *best_peer_label = "";
        for (int i = 0; i < count; i++) {
            const double own_steps = (double)steps / s[i].step_factor;
            char chk[64] = "";
            const double rel = rel_diff(m[i].y, m[0].y, sys->n);
            if (i == 0)
                snprintf(chk, sizeof chk, "reference");
            else if (s[i].flags & BENCH_WRONG)
                snprintf(chk, sizeof chk, "WRONG (%.1e off)", rel);
            else if (s[i].flags & (BENCH_SAME | BENCH_ACCURACY))
                snprintf(chk, sizeof chk, "= hand to %.0e", fmax(rel, 1e-17));
            /* calls per step as counted where the solver counts them (ARKODE's include its
             * f(t0)), else as the method defines them */
            const double cps =
                m[i].counts.rhs > 0 ? (double)m[i].counts.rhs / own_steps : s[i].calls_per_step;
            printf("| %s | %.1f | %.2f | %.2f | %.3g | %.2e | %s |\n", s[i].label,
                   m[i].med / own_steps, m[i].med / 1e3, m[i].med / hand_med, cps, m[i].err, chk);
            check(m[i].ok, "%s, %s: %s failed", sys->name, method_names[mi], s[i].label);
            check(m[i].deterministic, "%s, %s: %s gives different results when run twice",
                  sys->name, method_names[mi], s[i].label);
            if (i > 0 && (s[i].flags & (BENCH_SAME | BENCH_ACCURACY)))
                check(rel <= SAME_RTOL, "%s, %s: %s differs from the hand-written loop by %.1e",
                      sys->name, method_names[mi], s[i].label, rel);
            if (!s[i].is_dynkit && i > 0 && !(s[i].flags & (BENCH_WRONG | BENCH_DIAG)) &&
                m[i].med < best_peer) {
                best_peer = m[i].med;
                best_peer_label = s[i].label;
            }
        }
        printf("\nx hand: time per solve over the fastest hand-written loop of this run (%s).\n",
               hand_label);
        printf("Error: max |y_i - y_ref_i| at t1, reference %s.\n", ref_text);
        print_notes(s, count);
        /* targets: each dynkit row against the hand-written loop and the fastest peer */
        for (int i = 1; i < count && !o->quick; i++) {
            if (!s[i].is_dynkit || strstr(s[i].label, "library table") ||
                strstr(s[i].label, "no_finite_check"))
                continue;
            char task[64];
            snprintf(task, sizeof task, "fixed %s, %s", method_names[mi], sys->name);
            const double r = m[i].med / hand_med;
            add_target(r <= 1.15, task, s[i].label + 7, "<= 1.15 x hand", "%.2f x hand-written", r);
            if (strstr(s[i].label, "dyn_fixed_solve") && !strstr(s[i].label, "inline") &&
                isfinite(floor_med))
                add_target(m[i].med <= 1.10 * floor_med, task, s[i].label + 7,
                           "<= 1.10 x hand, rhs by pointer", "%.2f x hand, rhs by pointer",
                           m[i].med / floor_med);
            if (isfinite(best_peer)) {
                const double rp = m[i].med / best_peer;
                add_target(rp < 1.0, task, s[i].label + 7, "< 1 x fastest peer", "%.2f x %s", rp,
                           best_peer_label);
            }
        }
        release(s, count);
    }
}

/* ------------------------------------------------------------------------------------------
 * 2, 3. Adaptive work-precision
 * ---------------------------------------------------------------------------------------- */
typedef struct curve {
    int n;
    double tol[MAX_TOLS], err[MAX_TOLS], calls[MAX_TOLS], us[MAX_TOLS], jac[MAX_TOLS];
    int ok[MAX_TOLS];
} curve;

/* Cost at error level e on the solver's work-precision front (wp_front.h). */
static double cost_at(const curve *c, const double *cost, double e)
{
    return wp_front_cost_at(c->n, c->err, cost, c->ok, e);
}

static void write_svg(const options *o, const char *file, const char *title, const char *ylabel,
                      const bench_solver *s, int count, const curve *c, int use_calls)
{
    if (!o->svg_dir)
        return;
    char path[512];
    snprintf(path, sizeof path, "%s/%s", o->svg_dir, file);
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "bench_suite: cannot write %s: %s\n", path, strerror(errno));
        checks_failed++;
        return;
    }
    wp_plot p = {title, "error at the end (max norm)", ylabel, 0, {{0}}};
    static double xs[MAX_SOLVERS][MAX_TOLS], ys[MAX_SOLVERS][MAX_TOLS];
    for (int i = 0; i < count && p.n_lines < WP_SVG_MAX_LINES; i++) {
        if (s[i].flags & BENCH_DIAG)
            continue;
        int k = 0;
        for (int t = 0; t < c[i].n; t++)
            if (c[i].ok[t]) {
                xs[i][k] = c[i].err[t];
                ys[i][k] = use_calls ? c[i].calls[t] : c[i].us[t];
                k++;
            }
        p.lines[p.n_lines++] = (wp_line){s[i].label, k, xs[i], ys[i], s[i].is_dynkit};
    }
    if (wp_svg_write(f, &p) != 0)
        checks_failed++;
    fclose(f);
    printf("\n(wrote %s)\n", path);
}

static void write_csv(const options *o, const char *file, const bench_solver *s, int count,
                      const curve *c)
{
    if (!o->csv_dir)
        return;
    char path[512];
    snprintf(path, sizeof path, "%s/%s", o->csv_dir, file);
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "bench_suite: cannot write %s: %s\n", path, strerror(errno));
        checks_failed++;
        return;
    }
    fprintf(f, "solver,order,tol,error,rhs_calls,jac_calls,us_median\n");
    for (int i = 0; i < count; i++)
        for (int t = 0; t < c[i].n; t++)
            fprintf(f, "\"%s\",%d,%.0e,%.6e,%.0f,%.0f,%.3f\n", s[i].label, s[i].order, c[i].tol[t],
                    c[i].err[t], c[i].calls[t], c[i].jac[t], c[i].us[t]);
    fclose(f);
}

/* A target row of time at equal error: the fastest dynkit row of the given kind (0:
 * dyn_solve; BENCH_INLINE: dyn_solve_inline; -1: either) against the fastest
 * non-diagnostic row of one peer (NULL: of every peer, dyn_solve_inline not counted as
 * one), at each level; met when the dynkit row is faster (strict) or at most the peer's
 * time. */
static void time_target(const bench_sys *sys, const bench_solver *s, const curve *c, int count,
                        const double *levels, int nl, int kind, const char *peer, int strict,
                        const char *what)
{
    int cmp = 0, met = 0;
    double worst = 0.0;
    char worst_at[96] = "";
    for (int l = 0; l < nl; l++) {
        double best_dk = INFINITY, best_peer = INFINITY;
        const char *peer_label = "";
        for (int i = 0; i < count; i++) {
            const double v = cost_at(&c[i], c[i].us, levels[l]);
            if (!isfinite(v) || (s[i].flags & BENCH_DIAG))
                continue;
            const int dk = kind < 0   ? s[i].is_dynkit || (s[i].flags & BENCH_INLINE)
                           : kind > 0 ? (s[i].flags & kind) != 0
                                      : s[i].is_dynkit;
            if (dk)
                best_dk = fmin(best_dk, v);
            else if ((peer ? strcmp(s[i].peer, peer) == 0 : !(s[i].flags & BENCH_INLINE)) &&
                     v < best_peer) {
                best_peer = v;
                peer_label = s[i].label;
            }
        }
        if (!isfinite(best_dk) || !isfinite(best_peer))
            continue;
        cmp++;
        met += strict ? best_dk < best_peer : best_dk <= best_peer;
        if (best_dk / best_peer > worst) {
            worst = best_dk / best_peer;
            snprintf(worst_at, sizeof worst_at, "%.72s at %.0e", peer_label, levels[l]);
        }
    }
    if (cmp) {
        char task_s[64];
        snprintf(task_s, sizeof task_s, "adaptive, %s", sys->name);
        add_target(met == cmp, task_s, what, strict ? "< 1 at every level" : "<= 1 at every level",
                   "%d/%d; worst %.2f (%s)", met, cmp, worst, worst_at);
    }
}

static void adaptive_section(const options *o, const bench_sys *sys, bench_task task,
                             const double *ref, const char *ref_text, const char *file_stem)
{
    bench_solver s[MAX_SOLVERS];
    static curve c[MAX_SOLVERS];
    const int count = collect(o, sys, task, BENCH_NMETHOD, s);
    double tols[MAX_TOLS];
    int nt = 0;
    if (o->quick) {
        tols[nt++] = 1e-4;
        tols[nt++] = 1e-8;
    } else {
        for (int k = 1; k <= 12; k++)
            tols[nt++] = pow(10.0, -k);
    }
    memset(c, 0, sizeof c);
    static meas m[MAX_TOLS * MAX_SOLVERS];
    static item it[MAX_TOLS * MAX_SOLVERS];
    for (int t = 0; t < nt; t++)
        for (int i = 0; i < count; i++)
            it[t * count + i] = (item){&s[i], tols[t], 0, &m[t * count + i]};
    measure(it, nt * count, sys->n, o->quick ? 0 : o->reps_adaptive, o->quick ? 0 : 2e6, ref);
    for (int t = 0; t < nt; t++)
        for (int i = 0; i < count; i++) {
            const meas *mi = &m[t * count + i];
            curve *ci = &c[i];
            ci->tol[ci->n] = tols[t];
            ci->err[ci->n] = mi->err;
            ci->calls[ci->n] = (double)mi->counts.rhs;
            ci->jac[ci->n] = (double)mi->counts.jac;
            ci->us[ci->n] = mi->med / 1e3;
            ci->ok[ci->n] = mi->ok && isfinite(mi->err);
            ci->n++;
            check(mi->ok, "%s: %s failed at tol %.0e", sys->name, s[i].label, tols[t]);
            check(mi->deterministic, "%s: %s gives different results when run twice", sys->name,
                  s[i].label);
        }
    for (int i = 0; i < count; i++)
        check(c[i].n < 2 || c[i].err[c[i].n - 1] < c[i].err[0],
              "%s: %s: the error does not fall with the tolerance (%.1e at %.0e, %.1e at %.0e)",
              sys->name, s[i].label, c[i].err[0], c[i].tol[0], c[i].err[c[i].n - 1],
              c[i].tol[c[i].n - 1]);

    /* raw measurements */
    printf("\n### %s: %s (%d states, t in [%g, %.10g]), measured\n\n",
           task == BENCH_TASK_STIFF ? "Stiff" : "Adaptive", sys->name, sys->n, sys->t0, sys->t1);
    printf("Error: max |y_i - y_ref_i| at t1 against %s. Cells: error / rhs calls / us per "
           "solve%s.\n\n",
           ref_text, task == BENCH_TASK_STIFF ? " / Jacobians" : "");
    printf("| solver | order |");
    for (int t = 0; t < nt; t++)
        printf(" tol %.0e |", tols[t]);
    printf("\n|---|---:|");
    for (int t = 0; t < nt; t++)
        printf("---|");
    printf("\n");
    for (int i = 0; i < count; i++) {
        printf("| %s | %d |", s[i].label, s[i].order);
        for (int t = 0; t < c[i].n; t++) {
            if (!c[i].ok[t])
                printf(" failed |");
            else if (task == BENCH_TASK_STIFF)
                printf(" %.1e / %.0f / %.0f / %.0f |", c[i].err[t], c[i].calls[t], c[i].us[t],
                       c[i].jac[t]);
            else
                printf(" %.1e / %.0f / %.0f |", c[i].err[t], c[i].calls[t], c[i].us[t]);
        }
        printf("\n");
    }
    print_notes(s, count);

    /* at equal error */
    double levels[16];
    int nl = 0;
    for (int k = 2; k <= 13; k++) {
        const double e = pow(10.0, -k);
        int dk = 0, peer = 0;
        for (int i = 0; i < count; i++) {
            const int has = isfinite(cost_at(&c[i], c[i].us, e));
            dk |= has && s[i].is_dynkit;
            peer |= has && !s[i].is_dynkit && !(s[i].flags & (BENCH_DIAG | BENCH_INLINE));
        }
        if (dk && (peer || o->peers_none || sys->id == BENCH_KEPLER))
            levels[nl++] = e;
    }
    for (int what = 0; what < 2 && nl > 0; what++) {
        printf("\n### %s: %s, %s at equal error\n\n",
               task == BENCH_TASK_STIFF ? "Stiff" : "Adaptive", sys->name,
               what ? "time (us per solve)" : "right-hand-side calls");
        printf("Interpolated in log-log on each solver's curve; - where its runs do not reach "
               "that error.\n\n| solver | order |");
        for (int l = 0; l < nl; l++)
            printf(" err %.0e |", levels[l]);
        printf("\n|---|---:|");
        for (int l = 0; l < nl; l++)
            printf("---:|");
        printf("\n");
        for (int i = 0; i < count; i++) {
            printf("| %s | %d |", s[i].label, s[i].order);
            for (int l = 0; l < nl; l++) {
                const double v = cost_at(&c[i], what ? c[i].us : c[i].calls, levels[l]);
                if (isfinite(v))
                    printf(what ? " %.1f |" : " %.0f |", v);
                else
                    printf(" - |");
            }
            printf("\n");
        }
    }

    /* targets */
    if (!o->quick && task == BENCH_TASK_ADAPTIVE) {
        /* calls: each dynkit pair against the peers' methods of the same order */
        for (int i = 0; i < count; i++) {
            if (!s[i].is_dynkit)
                continue;
            int cmp = 0, met = 0;
            double worst = 0.0;
            char worst_at[96] = "";
            for (int j = 0; j < count; j++) {
                if (s[j].is_dynkit || s[j].order != s[i].order ||
                    (s[j].flags & (BENCH_DIAG | BENCH_INLINE)))
                    continue;
                for (int l = 0; l < nl; l++) {
                    const double a = cost_at(&c[i], c[i].calls, levels[l]);
                    const double b = cost_at(&c[j], c[j].calls, levels[l]);
                    if (!isfinite(a) || !isfinite(b))
                        continue;
                    cmp++;
                    met += a <= b;
                    if (a / b > worst) {
                        worst = a / b;
                        snprintf(worst_at, sizeof worst_at, "%.72s at %.0e", s[j].label, levels[l]);
                    }
                }
            }
            if (cmp) {
                char task_s[64], what[96];
                snprintf(task_s, sizeof task_s, "adaptive, %s", sys->name);
                snprintf(what, sizeof what, "%s: calls vs same-order peers", s[i].label + 7);
                add_target(met == cmp, task_s, what, "<= 1 at every level",
                           "%d/%d; worst %.2f (%s)", met, cmp, worst, worst_at);
            }
        }
        /* time: dynkit's fastest pair, by either path, against the fastest peer of any
         * calling convention, at each level */
        time_target(sys, s, c, count, levels, nl, -1, NULL, 1,
                    "fastest dynkit pair (dyn_solve or dyn_solve_inline) vs fastest peer (time)");
        /* issue 12 item 1: the same calling convention on each side */
        time_target(sys, s, c, count, levels, nl, 0, "GSL", 0,
                    "fastest dyn_solve pair (rhs by pointer) vs fastest GSL pair (time)");
        time_target(sys, s, c, count, levels, nl, BENCH_INLINE, "Boost", 0,
                    "fastest dyn_solve_inline pair vs fastest Boost std::array (time)");
    }
    if (!o->quick && task == BENCH_TASK_STIFF) {
        for (int i = 0; i < count; i++) {
            if (!s[i].is_dynkit)
                continue;
            for (int j = 0; j < count; j++) {
                if (strcmp(s[j].peer, "CVODE") != 0)
                    continue;
                int cmp = 0, met = 0;
                double worst = 0.0, at = 0.0;
                for (int l = 0; l < nl; l++) {
                    const double a = cost_at(&c[i], c[i].us, levels[l]);
                    const double b = cost_at(&c[j], c[j].us, levels[l]);
                    if (!isfinite(a) || !isfinite(b))
                        continue;
                    cmp++;
                    met += a <= 2.0 * b;
                    if (a / b > worst) {
                        worst = a / b;
                        at = levels[l];
                    }
                }
                char what[96];
                snprintf(what, sizeof what, "%.40s vs %.40s (time)", s[i].label + 7, s[j].label);
                if (cmp)
                    add_target(met == cmp, "stiff, van der Pol mu = 1000", what,
                               "<= 2 x at every level", "%d/%d; worst %.2f at %.0e", met, cmp,
                               worst, at);
            }
        }
    }
    char file[96], title[160];
    snprintf(file, sizeof file, "%s.svg", file_stem);
    snprintf(title, sizeof title, "%s: time per solve against error", sys->name);
    write_svg(o, file, title, "time per solve [us]", s, count, c, 0);
    snprintf(file, sizeof file, "%s-calls.svg", file_stem);
    snprintf(title, sizeof title, "%s: right-hand-side calls against error", sys->name);
    write_svg(o, file, title, "right-hand-side calls", s, count, c, 1);
    snprintf(file, sizeof file, "%s.csv", file_stem);
    write_csv(o, file, s, count, c);
    release(s, count);
}

/* ------------------------------------------------------------------------------------------
 * 4. dynkit report, end to end
 * ---------------------------------------------------------------------------------------- */
extern char **environ;

#ifdef BENCH_DYNKIT_CLI
/* Median and minimum wall time [ms] of runs of `dynkit report EXTRA...` (stdout to
 * /dev/null); 0, or -1 when a run failed. */
static int time_report(const char *cli, char *const *extra, int runs, double *med, double *min)
{
    double *t = malloc((size_t)runs * sizeof *t);
    int ok = t != NULL;
    for (int r = 0; r < runs && ok; r++) {
        char *argv[8] = {(char *)cli, (char *)"report"};
        for (int k = 0; extra[k] && k < 5; k++)
            argv[2 + k] = extra[k];
        posix_spawn_file_actions_t fa;
        posix_spawn_file_actions_init(&fa);
        posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
        pid_t pid;
        int status = 0;
        const double t0 = now_ns();
        ok = posix_spawn(&pid, cli, &fa, NULL, argv, environ) == 0 &&
             waitpid(pid, &status, 0) == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0;
        t[r] = now_ns() - t0;
        posix_spawn_file_actions_destroy(&fa);
    }
    if (ok) {
        *med = bench_median(t, runs) / 1e6;
        *min = t[0] / 1e6; /* bench_median() sorts */
    }
    free(t);
    return ok ? 0 : -1;
}
#endif

/* The whole report, and without its studies of many runs (--no-studies) and on one thread
 * (--threads 1): what the studies cost. */
static void report_section(const options *o)
{
#ifdef BENCH_DYNKIT_CLI
    const char *cli = BENCH_DYNKIT_CLI;
    const int runs = o->quick ? 1 : o->report_runs;
    static char *const none[] = {NULL};
    static char *const alone[] = {(char *)"--no-studies", NULL};
    static char *const one[] = {(char *)"--threads", (char *)"1", NULL};
    static const struct {
        char *const *extra;
        const char *what;
    } cases[] = {{none, "report"},
                 {alone, "report --no-studies (the homework alone)"},
                 {one, "report --threads 1 (the studies on one thread)"}};
    double med[3], min[3];
    int ok = 1;
    for (int c = 0; c < 3 && ok; c++)
        ok = time_report(cli, cases[c].extra, runs, &med[c], &min[c]) == 0;
    check(ok, "`%s report` failed", cli);
    if (ok) {
        printf("\n### `dynkit report` end to end\n\n%d runs of each, stdout to /dev/null, wall "
               "clock from process start to exit:\n\n| command | median [ms] | minimum [ms] |\n"
               "|---|---:|---:|\n",
               runs);
        for (int c = 0; c < 3; c++)
            printf("| `dynkit %s` | %.1f | %.1f |\n", cases[c].what, med[c], min[c]);
        printf("\nThe studies of many runs cost %.0f ms of the median (%.0f ms on one thread).\n",
               med[0] - med[1], med[2] - med[1]);
        if (!o->quick)
            add_target(med[0] < 1000.0, "dynkit report (the homework and its studies)",
                       "wall clock, median, all cores", "under 1 s", "%.0f ms", med[0]);
    }
#else
    (void)o;
    printf("\n(dynkit report: the path of the command-line tool is not known to this build)\n");
#endif
}

/* ------------------------------------------------------------------------------------------
 * The machine
 * ---------------------------------------------------------------------------------------- */
static void print_machine(const options *o)
{
    char model[256] = "unknown";
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (f) {
        char line[512];
        while (fgets(line, sizeof line, f))
            if (strncmp(line, "model name", 10) == 0) {
                const char *v = strchr(line, ':');
                if (v) {
                    snprintf(model, sizeof model, "%s", v + 2);
                    model[strcspn(model, "\n")] = 0;
                }
                break;
            }
        fclose(f);
    }
    struct utsname u;
    printf("## Machine\n\n- CPU: %s, %ld logical cores\n", model, sysconf(_SC_NPROCESSORS_ONLN));
    if (uname(&u) == 0)
        printf("- %s %s %s\n", u.sysname, u.release, u.machine);
    printf("- C compiler: %s %s, flags `%s`\n",
#if defined(__clang__)
           "clang",
#else
           "gcc",
#endif
           __VERSION__,
#ifdef BENCH_FLAGS
           BENCH_FLAGS
#else
           "?"
#endif
    );
    printf("- peers:");
    int any = 0;
    for (int i = 0; all_peers[i]; i++)
        if (peer_enabled(o, all_peers[i]->name)) {
            printf("%s %s", any ? "," : "", all_peers[i]->version());
            any = 1;
        }
    printf("%s\n", any ? "" : " none");
}

/* ------------------------------------------------------------------------------------------ */
static int parse_int(const char *s, int lo, int hi, int *out)
{
    char *end;
    const long v = strtol(s, &end, 10);
    if (*end || v < lo || v > hi)
        return 1;
    *out = (int)v;
    return 0;
}

static void usage(FILE *out)
{
    fprintf(out,
            "usage: bench_suite [--quick] [--reps N] [--only LIST] [--peers LIST] [--svg DIR]\n"
            "                   [--csv DIR] [--report-runs N] [--min]\n"
            "  --quick          one run per solver, few tolerances: checks only (for CI)\n"
            "  --min            the minimum of the timed samples, not their median (a loaded "
            "machine)\n"
            "  --reps N         timed repetitions (default 15 fixed step, 7 adaptive)\n"
            "  --only LIST      sections, comma-separated: fixed,adaptive,family,stiff,report\n"
            "  --peers LIST     gsl,boost,sundials (those built), all, or none\n"
            "  --svg DIR        write the work-precision diagrams wp-*.svg into DIR\n"
            "  --csv DIR        write the adaptive, family and stiff measurements wp-*.csv into "
            "DIR\n"
            "  --report-runs N  runs of `dynkit report` (default 20)\n");
}

int main(int argc, char **argv)
{
    options o = {0, 15, 7, 31, 0, "", NULL, NULL, 20};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        int n;
        if (strcmp(a, "--quick") == 0) {
            o.quick = 1;
        } else if (strcmp(a, "--min") == 0) {
            use_min = 1;
        } else if (strcmp(a, "--reps") == 0 && v && !parse_int(v, 1, 10000, &n)) {
            o.reps_fixed = o.reps_adaptive = n;
            i++;
        } else if (strcmp(a, "--report-runs") == 0 && v && !parse_int(v, 1, 10000, &n)) {
            o.report_runs = n;
            i++;
        } else if (strcmp(a, "--only") == 0 && v) {
            o.sections = (strstr(v, "fixed") ? 1 : 0) | (strstr(v, "adaptive") ? 2 : 0) |
                         (strstr(v, "stiff") ? 4 : 0) | (strstr(v, "report") ? 8 : 0) |
                         (strstr(v, "family") ? 16 : 0);
            if (!o.sections) {
                fprintf(stderr,
                        "bench_suite: --only %s: give fixed, adaptive, family, stiff, report\n", v);
                return 2;
            }
            i++;
        } else if (strcmp(a, "--peers") == 0 && v) {
            o.peers_none = strcmp(v, "none") == 0;
            snprintf(o.peers, sizeof o.peers, "%s", strcmp(v, "all") == 0 ? "" : v);
            i++;
        } else if (strcmp(a, "--svg") == 0 && v) {
            o.svg_dir = v;
            i++;
        } else if (strcmp(a, "--csv") == 0 && v) {
            o.csv_dir = v;
            i++;
        } else if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            usage(stdout);
            return 0;
        } else {
            fprintf(stderr, "bench_suite: bad or incomplete argument '%s'\n", a);
            usage(stderr);
            return 2;
        }
    }
    /* a named peer that is not built is an error, so a CI test cannot silently test nothing */
    if (o.peers[0] && !o.peers_none) {
        char buf[128];
        snprintf(buf, sizeof buf, "%s", o.peers);
        for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok;
             tok = strtok_r(NULL, ",", &save)) {
            int found = 0;
            for (int i = 0; all_peers[i]; i++)
                found |= strcmp(all_peers[i]->name, tok) == 0;
            if (!found) {
                fprintf(stderr, "bench_suite: peer '%s' is not built into this program\n", tok);
                return 2;
            }
        }
    }
    for (int m = 0; m < BENCH_NMETHOD; m++) {
        const dyn_tableau *t = dyn_method_find(tables[m].name);
        const int s = tables[m].s;
        if (!t || t->stages != s || memcmp(t->a, tables[m].a, (size_t)(s * s) * sizeof(double)) ||
            memcmp(t->b, tables[m].b, (size_t)s * sizeof(double)) ||
            memcmp(t->c, tables[m].c, (size_t)s * sizeof(double))) {
            fprintf(stderr, "bench_suite: the library's %s table differs from the copy here\n",
                    tables[m].name);
            return 1;
        }
    }

    /* the systems */
    static bench_vdp_par vdp = {1.0}, vdp_stiff = {1000.0};
    static bench_plane_par plane;
    static bench_arenstorf_par aren = {DYN_ARENSTORF_MU};
    static double plane_y0[12];
    static const double vdp_y0[2] = {2.0, 0.0};
    static const double aren_y0[4] = {0.994, 0.0, 0.0, DYN_ARENSTORF_Y2DOT0};
    bench_plane_defaults(&plane, plane_y0);
    const bench_sys sys_vdp = {BENCH_VDP, "van der Pol", 2, &vdp, vdp_y0, 0.0, 15.0};
    const bench_sys sys_plane = {BENCH_PLANE, "plane", 12, &plane, plane_y0, 0.0, 5.0};
    const bench_sys sys_aren = {BENCH_ARENSTORF,     "Arenstorf", 4, &aren, aren_y0, 0.0,
                                DYN_ARENSTORF_PERIOD};
    double kep_start[4] = {1.0 - BENCH_KEPLER_E, 0.0, 0.0,
                           sqrt((1.0 + BENCH_KEPLER_E) / (1.0 - BENCH_KEPLER_E))};
    const bench_sys sys_kep = {
        BENCH_KEPLER, "Kepler e = 0.9", 4, NULL, kep_start, 0.0, 2.0 * 3.14159265358979323846};
    const bench_sys sys_stiff = {
        BENCH_VDP_STIFF, "van der Pol mu = 1000", 2, &vdp_stiff, vdp_y0, 0.0, 3000.0};

    /* the references */
    const dyn_reference *r_vdp = dyn_reference_find("vanderpol-mu1-15");
    const dyn_reference *r_aren = dyn_reference_find("arenstorf-period");
    const dyn_reference *r_stiff = dyn_reference_find("vanderpol-mu1000-3000");
    if (!r_vdp || !r_aren || !r_stiff) {
        fprintf(stderr, "bench_suite: a reference solution is missing (dynkit/problems.h)\n");
        return 1;
    }
    double plane_ref[12], plane_ref2[12];
    {
        const dyn_system ds = {dk_plane, 12, &plane};
        dyn_solve_opts so = {0};
        dyn_result res;
        so.rtol = so.atol = 1e-13;
        const dyn_tableau *m8 = dyn_method_find("dop853"), *m5 = dyn_method_find("dp45");
        double *w = malloc(dyn_solve_work_size(m8, 12, &so) * sizeof *w);
        double *w5 = malloc(dyn_solve_work_size(m5, 12, &so) * sizeof *w5);
        if (!w || !w5 ||
            dyn_solve(m8, &ds, 0.0, 5.0, plane_y0, plane_ref, w, &so, &res) != DYN_OK ||
            dyn_solve(m5, &ds, 0.0, 5.0, plane_y0, plane_ref2, w5, &so, &res) != DYN_OK) {
            fprintf(stderr, "bench_suite: the plane's reference solve failed\n");
            return 1;
        }
        free(w);
        free(w5);
    }
    char plane_ref_text[160];
    snprintf(plane_ref_text, sizeof plane_ref_text,
             "dop853 at rtol = atol = 1e-13 (dp45 at 1e-13 agrees to %.1e)",
             max_abs_diff(plane_ref, plane_ref2, 12));

    printf("# dynkit benchmark suite%s\n\n",
           o.quick ? " (quick: checks only, the times mean nothing)" : "");
    print_machine(&o);
    if (o.sections & 1) {
        printf("\n## 1. Fixed step\n\nns per step (%s of %d interleaved samples), time per "
               "solve, ratio of the time per solve to the hand-written loop's.\n",
               use_min ? "minimum" : "median", o.reps_fixed);
        fixed_section(&o, &sys_vdp, 0.01, 1500, r_vdp->y, "vanderpol-mu1-15 (dynkit/problems.h)");
        fixed_section(&o, &sys_plane, 0.01, 500, plane_ref, plane_ref_text);
    }
    if (o.sections & 2) {
        printf("\n## 2. Adaptive, work-precision\n\nrtol = atol = tol, %s of %d "
               "interleaved samples per tolerance.\n",
               use_min ? "minima" : "medians", o.reps_adaptive);
        adaptive_section(&o, &sys_vdp, BENCH_TASK_ADAPTIVE, r_vdp->y,
                         "vanderpol-mu1-15 (dynkit/problems.h)", "wp-vanderpol");
        adaptive_section(&o, &sys_aren, BENCH_TASK_ADAPTIVE, r_aren->y,
                         "arenstorf-period (dynkit/problems.h)", "wp-arenstorf");
        adaptive_section(&o, &sys_kep, BENCH_TASK_ADAPTIVE, kep_start,
                         "the initial state (exact after one period, 2 pi)", "wp-kepler");
    }
    if (o.sections & 16) {
        family_options = &o;
        const family_env env = {o.quick,        o.csv_dir,     family_collect,
                                family_variant, family_target, family_check};
        family_section(&env);
    }
    if (o.sections & 4) {
        printf("\n## 3. Stiff\n");
        adaptive_section(&o, &sys_stiff, BENCH_TASK_STIFF, r_stiff->y,
                         "vanderpol-mu1000-3000 (dynkit/problems.h)", "wp-vanderpol-stiff");
    }
    if (o.sections & 8)
        report_section(&o);

    if (n_targets) {
        int met = 0;
        printf("\n## Targets\n\n| task | dynkit | measured | target | met |\n"
               "|---|---|---|---|---|\n");
        for (int i = 0; i < n_targets; i++) {
            printf("| %s | %s | %s | %s | %s |\n", targets[i].task, targets[i].what,
                   targets[i].value, targets[i].goal, targets[i].met ? "yes" : "**no**");
            met += targets[i].met;
        }
        printf("\n%d of %d targets met.\n", met, n_targets);
    }
    printf("\n%s\n", checks_failed ? "CHECKS FAILED" : "all checks passed");
    return checks_failed ? 1 : 0;
}
