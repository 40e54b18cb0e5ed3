/* bench_fixed: the cost of the library's fixed-step driver against a hand-written loop.
 *
 * Times classical RK4 at a fixed step through the library (dyn_fixed_solve with the "rk4"
 * table, the right-hand side called through a dyn_rhs_fn pointer, no output callback)
 * against a hand-written RK4 loop with the same right-hand side inlined, for van der Pol
 * (2 states, the homework's 1500 steps of 0.01) and the 12-state model plane (500 steps of
 * 0.01), see bench_systems.h. Each timed sample runs a whole solve `batch` times (batch is
 * calibrated so that a sample takes about 10 ms); library and hand samples are interleaved,
 * alternating which goes first, and the medians (and minima) over the repetitions give
 * ns per step and the ratio library / hand. Both final states are compared (relative
 * difference at most 1e-12) so the benchmark cannot silently time nothing.
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

#include "bench_systems.h"

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

/* ---- hand-written RK4, right-hand side inlined, n a compile-time constant ----
 * Textbook form: k1..k4, then y += h/6 (k1 + 2 k2 + 2 k3 + k4). Both systems are
 * autonomous, so the stage times are not formed. */
#define HAND_RK4(NAME, N, PAR_T, EVAL)                                                       \
    static __attribute__((noinline)) void NAME(const void *vpar, const double *y0, double h, \
                                               long steps, double *yout)                     \
    {                                                                                        \
        const PAR_T *par = vpar;                                                             \
        double y[N], Y[N], k1[N], k2[N], k3[N], k4[N];                                       \
        memcpy(y, y0, sizeof y);                                                             \
        const double h2 = 0.5 * h, h6 = h / 6.0;                                             \
        for (long step = 0; step < steps; step++) {                                          \
            EVAL(y, k1, par);                                                                \
            for (int q = 0; q < N; q++)                                                      \
                Y[q] = y[q] + h2 * k1[q];                                                    \
            EVAL(Y, k2, par);                                                                \
            for (int q = 0; q < N; q++)                                                      \
                Y[q] = y[q] + h2 * k2[q];                                                    \
            EVAL(Y, k3, par);                                                                \
            for (int q = 0; q < N; q++)                                                      \
                Y[q] = y[q] + h * k3[q];                                                     \
            EVAL(Y, k4, par);                                                                \
            for (int q = 0; q < N; q++)                                                      \
                y[q] += h6 * (k1[q] + 2.0 * k2[q] + 2.0 * k3[q] + k4[q]);                    \
        }                                                                                    \
        memcpy(yout, y, sizeof y);                                                           \
    }

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

typedef struct bench_case {
    const char *name;
    int n;
    const double *y0;
    double h;
    long steps;
    dyn_rhs_fn f;
    void *par;
    hand_fn hand; /* rhs inlined: the reference */
    /* the diagnostic loop ptr_rk4 uses f, par and n */
} bench_case;

static double now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

/* batch whole library solves; returns elapsed ns, or -1 if a solve failed. */
static double time_library(const bench_case *bc, const dyn_tableau *m, long batch, double *y,
                           double *work)
{
    const dyn_system sys = {bc->f, bc->n, bc->par};
    const double t1 = (double)bc->steps * bc->h;
    dyn_result res;
    double t0 = now_ns();
    for (long r = 0; r < batch; r++) {
        if (dyn_fixed_solve(m, &sys, 0.0, t1, bc->h, bc->y0, y, work, NULL, &res) != DYN_OK ||
            res.stats.steps != bc->steps) {
            fprintf(stderr, "%s: library solve failed: %s (%ld steps)\n", bc->name, res.message,
                    res.stats.steps);
            return -1.0;
        }
        CLOBBER();
    }
    return now_ns() - t0;
}

static double time_hand(const bench_case *bc, long batch, double *y)
{
    double t0 = now_ns();
    for (long r = 0; r < batch; r++) {
        bc->hand(bc->par, bc->y0, bc->h, bc->steps, y);
        CLOBBER();
    }
    return now_ns() - t0;
}

/* The function pointer is read through a volatile so that it cannot be inlined. */
static double time_ptr(const bench_case *bc, long batch, double *y)
{
    dyn_rhs_fn volatile fv = bc->f;
    double t0 = now_ns();
    for (long r = 0; r < batch; r++) {
        ptr_rk4(fv, bc->par, bc->n, bc->y0, bc->h, bc->steps, y);
        CLOBBER();
    }
    return now_ns() - t0;
}

static int cmp_double(const void *pa, const void *pb)
{
    double a = *(const double *)pa, b = *(const double *)pb;
    return (a > b) - (a < b);
}

static double median(double *v, int count)
{
    qsort(v, (size_t)count, sizeof *v, cmp_double);
    return count % 2 ? v[count / 2] : 0.5 * (v[count / 2 - 1] + v[count / 2]);
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

/* Runs one system; prints its table row and check line. Returns 0 if the check passed. */
static int run_case(const bench_case *bc, const dyn_tableau *m, int reps, int quick)
{
    double work[512], ylib[MAX_N], yhand[MAX_N], yptr[MAX_N];
    if (dyn_fixed_work_size(m, bc->n) > sizeof work / sizeof work[0]) {
        fprintf(stderr, "%s: workspace too small\n", bc->name);
        return 1;
    }
    /* Warm up, and calibrate the batch so that one timed sample takes about 10 ms. */
    double one = time_library(bc, m, 1, ylib, work);
    if (one < 0)
        return 1;
    time_hand(bc, 1, yhand);
    time_ptr(bc, 1, yptr);
    long batch = 1;
    if (!quick) {
        one = time_library(bc, m, 4, ylib, work) / 4.0;
        batch = (long)ceil(10e6 / fmax(one, 1.0));
        if (batch < 1)
            batch = 1;
    }
    /* Samples in ns per step: library, hand (inlined), hand (by pointer). */
    double *tl = malloc(3 * (size_t)reps * sizeof *tl), *th = tl + reps, *tp = th + reps;
    if (!tl)
        return 1;
    const double per_step = 1.0 / ((double)batch * (double)bc->steps);
    for (int r = 0; r < reps; r++) {
        /* Rotate the order so that no variant always runs first or last. */
        for (int v = 0; v < 3; v++) {
            switch ((r + v) % 3) {
            case 0: tl[r] = time_library(bc, m, batch, ylib, work); break;
            case 1: th[r] = time_hand(bc, batch, yhand); break;
            default: tp[r] = time_ptr(bc, batch, yptr); break;
            }
        }
        if (tl[r] < 0) {
            free(tl);
            return 1;
        }
        tl[r] *= per_step;
        th[r] *= per_step;
        tp[r] *= per_step;
    }
    /* median() sorts, so [0] is then the minimum */
    const double lib_med = median(tl, reps), hand_med = median(th, reps);
    const double ptr_med = median(tp, reps);
    const double lib_min = tl[0], hand_min = th[0];
    free(tl);

    const double rel = rel_diff(ylib, yhand, bc->n), rel_ptr = rel_diff(yptr, yhand, bc->n);
    const int ok = rel <= CHECK_RTOL && rel_ptr <= CHECK_RTOL;
    printf("%-10s %3d %6ld %6ld %9.2f %9.2f %9.2f %9.2f %7.3f %7.3f %9.2f %7.3f\n", bc->name,
           bc->n, bc->steps, batch, lib_med, lib_min, hand_med, hand_min, lib_med / hand_med,
           lib_min / hand_min, ptr_med, ptr_med / hand_med);
    printf("  check %s: final states agree to %.2e relative (by pointer %.2e; limit %.0e): %s;"
           " y[0] = %.17g\n",
           bc->name, rel, rel_ptr, CHECK_RTOL, ok ? "ok" : "FAILED", ylib[0]);
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
                fprintf(stderr, "bench_fixed: --system %s is not accepted: give vanderpol or "
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
    if (!rk4) {
        fprintf(stderr, "bench_fixed: method rk4 not found\n");
        return 1;
    }
    static bench_vdp_par vdp = {1.0};
    static const double vdp_y0[2] = {2.0, 0.0};
    static bench_plane_par plane = {1.0, 0.005, 0.005, 0.01, 9.81, 1.0, 20.0, {0.1, 0.0, -0.1}};
    static const double plane_y0[12] = {-0.1, 0.2, 1.0 + 9.81 / 20.0, 0.0, 0.0, 0.0,
                                        2.0,  0.0, 0.0,               0.0, 0.0, PI / 40.0};
    const bench_case cases[] = {
        {"vanderpol", 2, vdp_y0, 0.01, 1500, vdp_rhs, &vdp, hand_rk4_vdp},
        {"plane", 12, plane_y0, 0.01, 500, plane_rhs, &plane, hand_rk4_plane},
    };

    printf("fixed-step rk4: library (dyn_fixed_solve, rhs by pointer, no output) vs "
           "hand-written loop (rhs inlined)\n");
    printf("%d repetitions%s; batch = solves per timed sample; times in ns per step\n", reps,
           quick ? " (quick: checks only, timings meaningless)" : "");
    printf("ratio = lib_med / hand_med, r_min = lib_min / hand_min; ptr = the hand loop with "
           "the rhs by pointer and n at run time (diagnostic), r_ptr = ptr_med / hand_med\n");
    printf("%-10s %3s %6s %6s %9s %9s %9s %9s %7s %7s %9s %7s\n", "system", "n", "steps",
           "batch", "lib_med", "lib_min", "hand_med", "hand_min", "ratio", "r_min", "ptr_med",
           "r_ptr");
    int failed = 0;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        if (!only || strcmp(only, cases[i].name) == 0)
            failed |= run_case(&cases[i], rk4, reps, quick);
    printf("%s\n", failed ? "FAILED" : "all checks passed");
    return failed ? 1 : 0;
}
