/* SPDX-License-Identifier: BSD-3-Clause */
/* bench/bench_step.c — the cost of one attempted step of the adaptive pairs (bs23, dp45,
 * dop853) on van der Pol (mu = 1, y0 = (2, 0), t in [0, 15]): dyn_solve_inline
 * (dynkit/solve_inline.h, right-hand side inlined) and dyn_solve (the library, right-hand
 * side through its pointer), at three tolerances. Each cell is the best of R samples of a
 * batch of solves, divided by the attempted steps of one solve; the last column is the
 * pointer path's time over the inlined one of the same pair in the same run (the machines
 * are noisy: compare ratios, and absolute times only within one run).
 *
 * Checked (exit status 1 otherwise): both paths take the same steps and end on the same
 * bits (dyn_solve_inline is dyn_solve bit for bit, see tests/test_solve_inline.c).
 *
 *     bench_step [--reps R] [--batch B] [--quick]
 * --quick: one solve per cell, the checks only (CTest bench_step_quick).
 * The step of these pairs is discussed in docs/performance.md ("The generated kernels",
 * "The controller in logarithms and the newest term apart").
 */
#define _POSIX_C_SOURCE 200809L

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_clock.h"
#include "dynkit/ode.h"
#include "dynkit/solve_inline.h"

DYN_INLINE_RHS int vdp_inline(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    (void)par;
    dydt[0] = y[1];
    dydt[1] = (1.0 - y[0] * y[0]) * y[1] - y[0];
    return 0;
}

static int vdp_pointer(double t, const double *y, double *dydt, void *par)
{
    return vdp_inline(t, y, dydt, par);
}

static const double y0_vdp[2] = {2.0, 0.0};

static __attribute__((noinline)) int solve_inlined(const dyn_tableau *m, double tol, double *y,
                                                   double *work, dyn_result *res)
{
    const dyn_system sys = {vdp_inline, 2, NULL};
    dyn_solve_opts o;
    memset(&o, 0, sizeof o);
    o.rtol = o.atol = tol;
    return dyn_solve_inline(m, &sys, 0.0, 15.0, y0_vdp, y, work, &o, res);
}

static __attribute__((noinline)) int solve_pointer(const dyn_tableau *m, double tol, double *y,
                                                   double *work, dyn_result *res)
{
    const dyn_system sys = {vdp_pointer, 2, NULL};
    dyn_solve_opts o;
    memset(&o, 0, sizeof o);
    o.rtol = o.atol = tol;
    return dyn_solve(m, &sys, 0.0, 15.0, y0_vdp, y, work, &o, res);
}

typedef int (*solve_fn)(const dyn_tableau *, double, double *, double *, dyn_result *);

/* ns per attempted step: the best of reps samples of batch solves; the last solve's state
 * and result are left in y and res */
static double time_per_step(solve_fn solve, const dyn_tableau *m, double tol, int reps,
                            int batch, double *y, double *work, dyn_result *res)
{
    double best = -1.0;
    for (int r = 0; r < reps; r++) {
        const double t0 = bench_wall_seconds();
        for (int b = 0; b < batch; b++)
            solve(m, tol, y, work, res);
        const double dt = (bench_wall_seconds() - t0) / batch;
        if (best < 0.0 || dt < best)
            best = dt;
    }
    return res->stats.steps > 0 ? 1e9 * best / (double)res->stats.steps : 0.0;
}

static int parse_count(const char *opt, const char *text)
{
    char *end;
    const long v = strtol(text, &end, 10);
    if (*text == '\0' || *end != '\0' || v < 1 || v > 1000000) {
        fprintf(stderr, "bench_step: %s takes a whole number from 1 to 1000000, not '%s'\n", opt,
                text);
        exit(2);
    }
    return (int)v;
}

static const char usage[] =
    "usage: bench_step [--reps R] [--batch B] [--quick]\n"
    "  --reps R    samples per cell, the best counts (default 15)\n"
    "  --batch B   solves per sample (default 200)\n"
    "  --quick     one solve per cell: the checks only, the times mean nothing\n";

int main(int argc, char **argv)
{
    int reps = 15, batch = 200, quick = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--quick") == 0)
            quick = 1;
        else if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc)
            reps = parse_count("--reps", argv[++i]);
        else if (strcmp(argv[i], "--batch") == 0 && i + 1 < argc)
            batch = parse_count("--batch", argv[++i]);
        else if (strcmp(argv[i], "--help") == 0) {
            printf("%s", usage);
            return 0;
        } else {
            fprintf(stderr, "bench_step: unknown argument '%s'\n%s", argv[i], usage);
            return 2;
        }
    }
    if (quick)
        reps = batch = 1;
    const char *pairs[] = {"bs23", "dp45", "dop853"};
    const double tols[] = {1e-3, 1e-6, 1e-9};
    static double work[4096];
    int failed = 0;
    printf("## One attempted step of the adaptive pairs (van der Pol, t in [0, 15])\n\n");
    printf("Best of %d samples of %d solves, ns per attempted step.\n\n", reps, batch);
    printf("| pair | tol | attempted steps | dyn_solve_inline (rhs inlined) | dyn_solve (rhs by "
           "pointer) | pointer / inlined |\n|---|---:|---:|---:|---:|---:|\n");
    for (size_t p = 0; p < sizeof pairs / sizeof *pairs; p++) {
        const dyn_tableau *m = dyn_method_find(pairs[p]);
        if (!m || dyn_solve_work_size(m, 2, NULL) > sizeof work / sizeof *work) {
            fprintf(stderr, "bench_step: no method %s, or its workspace is too large\n",
                    pairs[p]);
            return 1;
        }
        for (size_t k = 0; k < sizeof tols / sizeof *tols; k++) {
            double yi[2], yp[2];
            dyn_result ri, rp;
            const double ti = time_per_step(solve_inlined, m, tols[k], reps, batch, yi, work, &ri);
            const double tp = time_per_step(solve_pointer, m, tols[k], reps, batch, yp, work, &rp);
            if (ri.status != DYN_OK || rp.status != DYN_OK || ri.stats.steps != rp.stats.steps ||
                memcmp(yi, yp, sizeof yi) != 0) {
                fprintf(stderr,
                        "bench_step: %s at tol %g: the inlined and the pointer path differ "
                        "(status %d/%d, steps %ld/%ld)\n",
                        pairs[p], tols[k], ri.status, rp.status, ri.stats.steps, rp.stats.steps);
                failed = 1;
            }
            printf("| %s | %.0e | %ld | %.1f | %.1f | %.2f |\n", pairs[p], tols[k],
                   ri.stats.steps, ti, tp, ti > 0.0 ? tp / ti : 0.0);
        }
    }
    if (quick)
        printf("\n(--quick: one solve per cell; the times mean nothing)\n");
    return failed;
}
