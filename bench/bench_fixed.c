/* SPDX-License-Identifier: BSD-3-Clause */
/* bench_fixed: the cost of the library's fixed-step driver against a hand-written loop.
 *
 * Times classical RK4 at a fixed step through the library (dyn_fixed_solve with the "rk4"
 * table, the right-hand side called through a dyn_rhs_fn pointer, no output callback)
 * against a hand-written RK4 loop with the same right-hand side inlined, for van der Pol
 * (2 states, the homework's 1500 steps of 0.01) and the 12-state model plane (500 steps of
 * 0.01), see bench_systems.h. Also timed: dyn_fixed_solve_inline (dynkit/ode_inline.h)
 * with the library's rk4 table and with a constant copy of it, and a diagnostic hand loop
 * that calls the right-hand side through a pointer. Each timed sample runs a whole solve
 * `batch` times (batch calibrated so that a sample takes about 10 ms); the variants'
 * samples are interleaved, rotating which goes first, and the medians (and minima) over
 * the repetitions give ns per step and the ratio to the hand-written loop.
 * Checks, so that the benchmark cannot silently time nothing: every variant's final state
 * agrees with the hand-written loop's (relative difference at most 1e-12); the library and
 * the inline solver agree bit for bit (final states here; with --quick also every method,
 * a partial last step, and failing solves, and a table too long for the library's plan).
 *
 * Usage: bench_fixed [--quick] [--reps N] [--system NAME]
 *   --quick        one solve per sample, 3 repetitions: checks that it runs and agrees (CI)
 *   --reps N       repetitions per system (default 31)
 *   --system NAME  only this system (vanderpol or plane), e.g. under a profiler
 * Exit status 0 when every check passes, 1 otherwise, 2 for a usage error.
 */
#define _POSIX_C_SOURCE 199309L /* clock_gettime */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <dynkit/ode.h>
#include <dynkit/ode_inline.h>

#include "bench_systems.h"
#include "bench_util.h"
#include "hand_loops.h"

#define MAX_N 12
#define CHECK_RTOL 1e-12
#define PI 3.14159265358979323846

/* Keep the compiler from merging or hoisting repeated solves. */
#define CLOBBER() __asm__ __volatile__("" ::: "memory")

/* ---- the library's view: plain dyn_rhs_fn functions around the shared inline bodies ---- */
static int vdp_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    bench_vdp_eval(y, dydt, par);
    return 0;
}

static int plane_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    bench_plane_eval(y, dydt, par);
    return 0;
}

/* ---- hand-written RK4 (hand_loops.h): right-hand side inlined, n a constant ---- */
HAND_RK4(hand_rk4_vdp, 2, bench_vdp_par, bench_vdp_eval)
HAND_RK4(hand_rk4_plane, 12, bench_plane_par, bench_plane_eval)

/* ---- diagnostic: the same textbook loop with what a compiled library cannot avoid ----
 * the right-hand side called through a pointer, and n known only at run time. It separates
 * the cost of the call from the cost of the library's generic stage loop. PIN keeps the
 * loops scalar (an empty asm on each value), as the library's small-system loops are: a
 * vector load of two k values written by separate scalar stores of the right-hand side
 * cannot be forwarded from the store buffer and stalls every stage. */
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#define PIN(v) __asm__("" : "+x"(v))
#else
#define PIN(v) ((void)0)
#endif
static void ptr_rk4(dyn_rhs_fn f, void *par, int n, const double *y0, double h, long steps,
                    double *yout)
{
    double y[MAX_N], Y[MAX_N], k1[MAX_N], k2[MAX_N], k3[MAX_N], k4[MAX_N];
    memcpy(y, y0, (size_t)n * sizeof *y);
    const double h2 = 0.5 * h, h6 = h / 6.0;
    for (long step = 0; step < steps; step++) {
        const double t = (double)step * h;
        f(t, y, k1, par);
        for (int q = 0; q < n; q++) {
            double v = y[q] + h2 * k1[q];
            PIN(v);
            Y[q] = v;
        }
        f(t + h2, Y, k2, par);
        for (int q = 0; q < n; q++) {
            double v = y[q] + h2 * k2[q];
            PIN(v);
            Y[q] = v;
        }
        f(t + h2, Y, k3, par);
        for (int q = 0; q < n; q++) {
            double v = y[q] + h * k3[q];
            PIN(v);
            Y[q] = v;
        }
        f(t + h, Y, k4, par);
        for (int q = 0; q < n; q++) {
            double v = y[q] + h6 * (k1[q] + 2.0 * k2[q] + 2.0 * k3[q] + k4[q]);
            PIN(v);
            y[q] = v;
        }
    }
    memcpy(yout, y, (size_t)n * sizeof *y);
}

typedef void (*hand_fn)(const void *par, const double *y0, double h, long steps, double *y);

/* ---- dyn_fixed_solve_inline with the right-hand side visible: one solver per system ----
 * RK4_CONST is a constant copy of the library's rk4 table (checked equal in main), so
 * that the compiler can also fold the coefficients. */
static const double rk4_a[16] = {0.0, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0,
                                 0.0, 0.5, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0};
static const double rk4_b[4] = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};
static const double rk4_c[4] = {0.0, 0.5, 0.5, 1.0};
static const dyn_tableau RK4_CONST = {.name = "rk4",
                                      .title = "classical RK4 (constant copy)",
                                      .reference = "bench",
                                      .kind = DYN_KIND_EXPLICIT_RK,
                                      .stages = 4,
                                      .order = 4,
                                      .a = rk4_a,
                                      .b = rk4_b,
                                      .c = rk4_c};

typedef int (*inline_fn)(const dyn_tableau *m, void *par, double t1, double h, const double *y0,
                         double *y, double *work, dyn_result *res);
#define INLINE_SOLVER(NAME, RHS, N, TABLE)                                                         \
    static __attribute__((noinline)) int NAME(const dyn_tableau *m, void *par, double t1,          \
                                              double h, const double *y0, double *y, double *work, \
                                              dyn_result *res)                                     \
    {                                                                                              \
        const dyn_system sys = {RHS, N, par};                                                      \
        (void)m;                                                                                   \
        return dyn_fixed_solve_inline(TABLE, &sys, 0.0, t1, h, y0, y, work, NULL, res);            \
    }
INLINE_SOLVER(inline_vdp, vdp_rhs, 2, m)
INLINE_SOLVER(inline_plane, plane_rhs, 12, m)
INLINE_SOLVER(inline_const_vdp, vdp_rhs, 2, &RK4_CONST)
INLINE_SOLVER(inline_const_plane, plane_rhs, 12, &RK4_CONST)

typedef struct bench_case {
    const char *name;
    int n;
    const double *y0;
    double h;
    long steps;
    dyn_rhs_fn f;
    void *par;
    hand_fn hand;             /* rhs inlined: the reference */
    inline_fn inl, inl_const; /* dyn_fixed_solve_inline, library table / constant table */
} bench_case;

enum { V_HAND, V_LIB, V_INLINE, V_INLINE_CONST, V_PTR, NVARIANT };
static const char *const variant_names[NVARIANT] = {
    "hand-written loop, rhs inlined (reference)", "dyn_fixed_solve (library)",
    "dyn_fixed_solve_inline, library table", "dyn_fixed_solve_inline, constant table",
    "diagnostic: hand loop, rhs by pointer"};

static double now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

/* batch whole solves of variant v; returns elapsed ns, or -1 if a solve failed. */
static double time_variant(const bench_case *bc, int v, const dyn_tableau *m, long batch, double *y,
                           double *work)
{
    const dyn_system sys = {bc->f, bc->n, bc->par};
    const double t1 = (double)bc->steps * bc->h;
    dyn_rhs_fn volatile fv = bc->f; /* read through a volatile: cannot be inlined */
    dyn_result res = {0};
    int rc = DYN_OK;
    double t0 = now_ns();
    for (long r = 0; r < batch && rc == DYN_OK; r++) {
        switch (v) {
        case V_HAND: bc->hand(bc->par, bc->y0, bc->h, bc->steps, y); break;
        case V_LIB:
            rc = dyn_fixed_solve(m, &sys, 0.0, t1, bc->h, bc->y0, y, work, NULL, &res);
            break;
        case V_INLINE: rc = bc->inl(m, bc->par, t1, bc->h, bc->y0, y, work, &res); break;
        case V_INLINE_CONST:
            rc = bc->inl_const(m, bc->par, t1, bc->h, bc->y0, y, work, &res);
            break;
        default: ptr_rk4(fv, bc->par, bc->n, bc->y0, bc->h, bc->steps, y); break;
        }
        CLOBBER();
    }
    double elapsed = now_ns() - t0;
    if (rc != DYN_OK || (v != V_HAND && v != V_PTR && res.stats.steps != bc->steps)) {
        fprintf(stderr, "%s, %s: solve failed: %s (%ld steps)\n", bc->name, variant_names[v],
                res.message, res.stats.steps);
        return -1.0;
    }
    return elapsed;
}

static double rel_diff(const double *a, const double *b, int n)
{
    double diff = 0.0, scale = 0.0;
    for (int q = 0; q < n; q++) {
        diff = fmax(diff, fabs(a[q] - b[q]));
        scale = fmax(scale, fabs(b[q]));
    }
    return scale > 0 ? diff / scale : diff;
}

/* Runs one system: prints its rows and checks. Returns 0 if every check passed. */
static int run_case(const bench_case *bc, const dyn_tableau *m, int reps, int quick)
{
    double work[512], yv[NVARIANT][MAX_N];
    if (dyn_fixed_work_size(m, bc->n) > sizeof work / sizeof work[0]) {
        fprintf(stderr, "%s: workspace too small\n", bc->name);
        return 1;
    }
    /* Warm up, and calibrate the batch so that one timed sample takes about 10 ms. */
    for (int v = 0; v < NVARIANT; v++)
        if (time_variant(bc, v, m, 1, yv[v], work) < 0)
            return 1;
    long batch = 1;
    if (!quick) {
        double one = time_variant(bc, V_LIB, m, 4, yv[V_LIB], work) / 4.0;
        batch = (long)ceil(10e6 / fmax(one, 1.0));
    }
    double *samples = malloc((size_t)NVARIANT * (size_t)reps * sizeof *samples);
    if (!samples)
        return 1;
    const double per_step = 1.0 / ((double)batch * (double)bc->steps);
    for (int r = 0; r < reps; r++) {
        for (int i = 0; i < NVARIANT; i++) { /* rotate: no variant always first or last */
            const int v = (r + i) % NVARIANT;
            const double ns = time_variant(bc, v, m, batch, yv[v], work);
            if (ns < 0) {
                free(samples);
                return 1;
            }
            samples[v * reps + r] = ns * per_step;
        }
    }
    double med[NVARIANT], min[NVARIANT];
    for (int v = 0; v < NVARIANT; v++) {
        med[v] = bench_median(samples + v * reps, reps); /* sorts, so [0] is then the minimum */
        min[v] = samples[v * reps];
    }
    free(samples);

    printf("%s: %d states, %ld steps of %g, batch %ld\n", bc->name, bc->n, bc->steps, bc->h, batch);
    int ok = 1;
    for (int v = 0; v < NVARIANT; v++) {
        const double rel = rel_diff(yv[v], yv[V_HAND], bc->n);
        const int agree = rel <= CHECK_RTOL;
        ok &= agree;
        printf("  %-43s %9.2f %9.2f %7.3f %7.3f  %.1e%s\n", variant_names[v], med[v], min[v],
               med[v] / med[V_HAND], min[v] / min[V_HAND], rel, agree ? "" : " FAILED");
    }
    const int same = memcmp(yv[V_LIB], yv[V_INLINE], (size_t)bc->n * sizeof(double)) == 0 &&
                     memcmp(yv[V_LIB], yv[V_INLINE_CONST], (size_t)bc->n * sizeof(double)) == 0;
    ok &= same;
    printf("  check: all final states agree with the hand-written loop to %.0e relative; "
           "library and inline solver bit for bit: %s; y[0] = %.17g\n",
           CHECK_RTOL, same ? "yes" : "NO", yv[V_LIB][0]);
    return ok ? 0 : 1;
}

/* ---- --quick: dyn_fixed_solve_inline agrees with dyn_fixed_solve in every detail ---- */
typedef struct fail_par {
    double mu;
    double t_fail; /* the rhs returns 7 at t >= t_fail */
    int make_nan;  /* ... or writes NaN instead */
} fail_par;

static int fail_rhs(double t, const double *y, double *dydt, void *par)
{
    const fail_par *p = par;
    dydt[0] = y[1];
    dydt[1] = p->mu * (1.0 - y[0] * y[0]) * y[1] - y[0] + 0.1 * t;
    if (t >= p->t_fail) {
        if (!p->make_nan)
            return 7;
        dydt[1] = NAN;
    }
    return 0;
}

static int same_result(const dyn_result *a, const dyn_result *b, const double *ya, const double *yb,
                       int n)
{
    return a->status == b->status && a->rhs_status == b->rhs_status &&
           memcmp(&a->t, &b->t, sizeof a->t) == 0 &&
           (memcmp(&a->fail_t, &b->fail_t, sizeof a->fail_t) == 0 ||
            (isnan(a->fail_t) && isnan(b->fail_t))) &&
           a->fail_index == b->fail_index && a->stats.steps == b->stats.steps &&
           a->stats.rhs_calls == b->stats.rhs_calls && a->stats.samples == b->stats.samples &&
           strcmp(a->message, b->message) == 0 && memcmp(ya, yb, (size_t)n * sizeof *ya) == 0;
}

/* The rhs is visible here, so this is the inlined path (a runtime table). */
static int inline_fail_solve(const dyn_tableau *m, fail_par *p, double t1, double h,
                             dyn_end_policy end, double *y, double *work, dyn_result *res)
{
    const dyn_system sys = {fail_rhs, 2, p};
    const double y0[2] = {2.0, 0.0};
    dyn_fixed_opts opts = {0};
    opts.end = end;
    return dyn_fixed_solve_inline(m, &sys, 0.0, t1, h, y0, y, work, &opts, res);
}

static int check_inline_agrees(void)
{
    int bad = 0, cases = 0;
    const double y0[2] = {2.0, 0.0};
    /* spans: whole steps (odd and even counts), a partial last step; failures at a stage
     * time inside the span, and NaN states */
    const double t1s[] = {15.0, 0.07, 1.234, 0.5};
    const double t_fails[] = {INFINITY, 0.75, 0.3 + 0.005};
    for (int i = 0; i < dyn_method_count(); i++) {
        const dyn_tableau *m = dyn_method_at(i);
        if (m->kind != DYN_KIND_EXPLICIT_RK)
            continue;
        for (size_t a = 0; a < sizeof t1s / sizeof t1s[0]; a++)
            for (size_t b = 0; b < sizeof t_fails / sizeof t_fails[0]; b++)
                for (int nan = 0; nan < 2; nan++)
                    for (int end = DYN_END_EXACT; end <= DYN_END_GRID; end++) {
                        fail_par p = {1.0, t_fails[b], nan};
                        const dyn_system sys = {fail_rhs, 2, &p};
                        double w1[64], w2[64], y1[2], y2[2];
                        dyn_result r1, r2;
                        dyn_fixed_opts opts = {0};
                        opts.end = (dyn_end_policy)end;
                        dyn_fixed_solve(m, &sys, 0.0, t1s[a], 0.01, y0, y1, w1, &opts, &r1);
                        inline_fail_solve(m, &p, t1s[a], 0.01, (dyn_end_policy)end, y2, w2, &r2);
                        cases++;
                        if (!same_result(&r1, &r2, y1, y2, 2)) {
                            bad++;
                            fprintf(stderr,
                                    "inline differs: %s t1 %g t_fail %g nan %d end %d: status "
                                    "%d/%d steps %ld/%ld calls %ld/%ld t %.17g/%.17g '%s'/'%s'\n",
                                    m->name, t1s[a], t_fails[b], nan, end, r1.status, r2.status,
                                    r1.stats.steps, r2.stats.steps, r1.stats.rhs_calls,
                                    r2.stats.rhs_calls, r1.t, r2.t, r1.message, r2.message);
                        }
                    }
    }
    printf("check: dyn_fixed_solve_inline == dyn_fixed_solve in %d solves (every method, "
           "whole and partial spans, rhs failures, NaN states): %s\n",
           cases, bad ? "FAILED" : "ok");
    return bad ? 1 : 0;
}

/* A table of more than 16 stages takes the library's other path (no plan): RK4 padded
 * with 13 stages that contribute nothing must give RK4's results bit for bit. */
static int check_unplanned_path(const dyn_tableau *rk4)
{
    enum { S = 17 };
    double a[S * S] = {0}, b[S] = {0}, c[S] = {0};
    for (int i = 0; i < 4; i++) {
        for (int j = 0; j < 4; j++)
            a[i * S + j] = rk4->a[i * 4 + j];
        b[i] = rk4->b[i];
        c[i] = rk4->c[i];
    }
    const dyn_tableau padded = {.name = "rk4-padded", .title = "", .reference = "",
                                .kind = DYN_KIND_EXPLICIT_RK, .stages = S, .order = 4,
                                .a = a, .b = b, .c = c};
    fail_par p = {1.0, INFINITY, 0};
    const dyn_system sys = {fail_rhs, 2, &p};
    const double y0[2] = {2.0, 0.0};
    double w1[64], w2[(S + 3) * 2], y1[2], y2[2];
    dyn_result r1, r2;
    dyn_fixed_solve(rk4, &sys, 0.0, 1.234, 0.01, y0, y1, w1, NULL, &r1);
    dyn_fixed_solve(&padded, &sys, 0.0, 1.234, 0.01, y0, y2, w2, NULL, &r2);
    const int ok = r1.status == DYN_OK && r2.status == DYN_OK && memcmp(y1, y2, sizeof y1) == 0 &&
                   r2.stats.rhs_calls == S * r1.stats.steps;
    printf("check: a 17-stage table (RK4 padded with stages that contribute nothing) gives "
           "RK4's result bit for bit: %s\n",
           ok ? "ok" : "FAILED");
    return ok ? 0 : 1;
}

static void usage(FILE *out)
{
    fprintf(out, "usage: bench_fixed [--quick] [--reps N] [--system NAME]\n"
                 "  --quick        one solve per sample, 3 repetitions (checks only, for CI)\n"
                 "  --reps N       timed repetitions per system, N >= 1 (default 31)\n"
                 "  --system NAME  only this system: vanderpol or plane\n");
}

int main(int argc, char **argv)
{
    int quick = 0, reps = 31, reps_given = 0;
    const char *only = NULL;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--quick") == 0) {
            quick = 1;
        } else if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc) {
            char *end;
            long v = strtol(argv[++i], &end, 10);
            if (*end || v < 1 || v > 100000) {
                fprintf(stderr, "bench_fixed: --reps %s is not accepted: give 1 .. 100000\n",
                        argv[i]);
                return 2;
            }
            reps = (int)v;
            reps_given = 1;
        } else if (strcmp(argv[i], "--system") == 0 && i + 1 < argc) {
            only = argv[++i];
            if (strcmp(only, "vanderpol") != 0 && strcmp(only, "plane") != 0) {
                fprintf(stderr,
                        "bench_fixed: --system %s is not accepted: give vanderpol or "
                        "plane\n",
                        only);
                return 2;
            }
        } else if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            usage(stdout);
            return 0;
        } else {
            fprintf(stderr, "bench_fixed: unknown argument '%s'\n", argv[i]);
            usage(stderr);
            return 2;
        }
    }
    if (quick && !reps_given)
        reps = 3;

    const dyn_tableau *rk4 = dyn_method_find("rk4");
    if (!rk4 || rk4->stages != 4 || memcmp(rk4->a, rk4_a, sizeof rk4_a) != 0 ||
        memcmp(rk4->b, rk4_b, sizeof rk4_b) != 0 || memcmp(rk4->c, rk4_c, sizeof rk4_c) != 0) {
        fprintf(stderr, "bench_fixed: the library's rk4 table is missing or differs from the "
                        "constant copy in this benchmark\n");
        return 1;
    }
    static bench_vdp_par vdp = {1.0};
    static const double vdp_y0[2] = {2.0, 0.0};
    static bench_plane_par plane = {1.0, 0.005, 0.005, 0.01, 9.81, 1.0, 20.0, {0.1, 0.0, -0.1}};
    static const double plane_y0[12] = {-0.1, 0.2, 1.0 + 9.81 / 20.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0,
                                        0.0,  0.0, PI / 40.0};
    const bench_case cases[] = {
        {"vanderpol", 2, vdp_y0, 0.01, 1500, vdp_rhs, &vdp, hand_rk4_vdp, inline_vdp,
         inline_const_vdp},
        {"plane", 12, plane_y0, 0.01, 500, plane_rhs, &plane, hand_rk4_plane, inline_plane,
         inline_const_plane},
    };

    printf("fixed-step rk4, ns per step: median and minimum over %d repetitions%s; ratios to "
           "the hand-written loop; last column: relative difference of the final state\n",
           reps, quick ? " (quick: checks only, timings meaningless)" : "");
    printf("  %-43s %9s %9s %7s %7s  %s\n", "variant", "median", "min", "ratio", "r_min", "diff");
    int failed = 0;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        if (!only || strcmp(only, cases[i].name) == 0)
            failed |= run_case(&cases[i], rk4, reps, quick);
    if (quick) {
        failed |= check_inline_agrees();
        failed |= check_unplanned_path(rk4);
    }
    printf("%s\n", failed ? "FAILED" : "all checks passed");
    return failed ? 1 : 0;
}
