/* SPDX-License-Identifier: BSD-3-Clause */
/* bench_sweep: the throughput of sweeps (dynkit/sweep.h, src/sweep) — issue 10's target:
 * 10,000 runs of 1,000 RK4 steps of van der Pol (mu from 0.5 to 2, h = 0.01 over 0:10) on 2
 * threads against one run of 10,000,000 RK4 steps on 1 thread (dyn_fixed_solve, the same
 * step count in one piece): the ratio of the times should be at most 0.75, i.e. the
 * per-run overhead (copying parameters, planning, reductions, scheduling) small against
 * 1,000 steps. Also: the sweep on 1 thread, the thread scaling efficiency T1 / (N TN), and a
 * sweep with a reduction over every sample (max:y1), which calls back at each step.
 * Times are the best of --reps repetitions (default 5) of wall-clock time.
 *   bench_sweep            the measurements
 *   bench_sweep --quick    checks only (untimed; run by CTest): each run of a small sweep
 *                          equals dyn_fixed_solve of that run bit for bit, on 1 and 2 threads */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "dynkit/dynkit.h"
#include "dynkit/sweep.h"
#include "bench_clock.h"

static double last_cpu; /* CPU time of the last measurement */

typedef struct sweep_case {
    long runs, steps;
    double h;
    int threads;
    const char *reduce;
} sweep_case;

/* One sweep of van der Pol: runs values of mu from 0.5 to 2, RK4 with step h over
 * steps steps. Returns the wall time; results (runs x columns) and status filled. */
static double run_sweep(const sweep_case *c, double *results, int *status, int *cols)
{
    const dyn_model *m = dyn_model_find("vanderpol");
    dyn_sweep_var var;
    char err[256];
    if (dyn_sweep_var_find(m, "mu", &var, err, sizeof err))
        abort();
    double *mu = malloc((size_t)c->runs * sizeof *mu);
    for (long i = 0; i < c->runs; i++)
        mu[i] = dyn_linspace_at(0.5, 2.0, c->runs, i);
    dyn_reduce red[8];
    int nr;
    if (dyn_reduce_parse(m, c->reduce, red, 8, &nr, err, sizeof err))
        abort();
    *cols = nr;
    dyn_sweep s = {0};
    s.model = m;
    s.n_vars = 1;
    s.vars = &var;
    s.n_runs = c->runs;
    s.values = mu;
    s.method = dyn_method_find("rk4");
    s.t0 = 0.0;
    s.t1 = (double)c->steps * c->h;
    s.step = c->h;
    s.n_reduce = nr;
    s.reduce = red;
    s.threads = c->threads;
    const double t = bench_wall_seconds(), c0 = bench_process_cpu_seconds();
    int rc = dyn_sweep_run(&s, results, status, err, sizeof err);
    const double elapsed = bench_wall_seconds() - t;
    last_cpu = bench_process_cpu_seconds() - c0;
    free(mu);
    if (rc != DYN_OK) {
        fprintf(stderr, "bench_sweep: %s\n", err);
        exit(1);
    }
    return elapsed;
}

/* One run of steps RK4 steps (mu = 1). */
static double run_one(long steps, double h, double *y)
{
    dyn_vanderpol_par par = {.mu = 1.0};
    const double y0[2] = {2.0, 0.0};
    double work[64];
    dyn_system sys = {dyn_vanderpol_rhs, 2, &par};
    dyn_result res;
    const double t = bench_wall_seconds(), c0 = bench_process_cpu_seconds();
    if (dyn_fixed_solve(dyn_method_find("rk4"), &sys, 0.0, (double)steps * h, h, y0, y, work,
                        NULL, &res) != DYN_OK)
        exit(1);
    last_cpu = bench_process_cpu_seconds() - c0;
    return bench_wall_seconds() - t;
}

static int quick(void)
{
    const sweep_case c = {300, 200, 0.01, 1, "final"};
    double *a = malloc(300 * 2 * sizeof *a), *b = malloc(300 * 2 * sizeof *b);
    int *sa = malloc(300 * sizeof *sa), *sb = malloc(300 * sizeof *sb);
    int cols, bad = 0;
    run_sweep(&c, a, sa, &cols);
    sweep_case c2 = c;
    c2.threads = 2;
    run_sweep(&c2, b, sb, &cols);
    bad |= memcmp(a, b, 300 * 2 * sizeof *a) != 0 || memcmp(sa, sb, 300 * sizeof *sa) != 0;
    double work[64];
    for (long i = 0; i < c.runs && !bad; i++) {
        dyn_vanderpol_par par = {.mu = dyn_linspace_at(0.5, 2.0, c.runs, i)};
        const double y0[2] = {2.0, 0.0};
        double y[2];
        dyn_system sys = {dyn_vanderpol_rhs, 2, &par};
        dyn_result res;
        dyn_fixed_solve(dyn_method_find("rk4"), &sys, 0.0, (double)c.steps * c.h, c.h, y0, y,
                        work, NULL, &res);
        bad |= sa[i] != DYN_OK || memcmp(y, a + 2 * i, sizeof y) != 0;
    }
    printf("bench_sweep --quick: %s (300 runs of 200 RK4 steps: the same bits as "
           "dyn_fixed_solve, on 1 and 2 threads)\n",
           bad ? "FAILED" : "ok");
    free(a);
    free(b);
    free(sa);
    free(sb);
    return bad ? 1 : 0;
}

int main(int argc, char **argv)
{
    int reps = 5;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--quick") == 0)
            return quick();
        if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc)
            reps = atoi(argv[++i]);
    }
    const long runs = 10000, steps = 1000;
    const double h = 0.01;
    double *res = malloc((size_t)runs * 8 * sizeof *res);
    int *st = malloc((size_t)runs * sizeof *st);
    int cols;
    double y[2];
    const int nt = dyn_sweep_threads(0);
    /* wall-clock and CPU time, best of reps: [case][0] wall, [case][1] CPU */
    static const char *const names[] = {"final, 1 thread", "final, 2 threads",
                                        "final,max:y1, 1 thread", "final,max:y1, 2 threads"};
    double best[5][2];
    for (int k = 0; k < 5; k++)
        best[k][0] = best[k][1] = 1e300;
    for (int r = 0; r < reps; r++) {
        double w = run_one(runs * steps, h, y);
        best[0][0] = fmin(best[0][0], w);
        best[0][1] = fmin(best[0][1], last_cpu);
        for (int k = 0; k < 4; k++) {
            sweep_case c = {runs, steps, h, k % 2 ? 2 : 1, k < 2 ? "final" : "final,max:y1"};
            w = run_sweep(&c, res, st, &cols);
            best[k + 1][0] = fmin(best[k + 1][0], w);
            best[k + 1][1] = fmin(best[k + 1][1], last_cpu);
        }
    }
    const double nsteps = (double)runs * (double)steps;
    double load[1] = {0};
    FILE *la = fopen("/proc/loadavg", "r");
    if (la) {
        if (fscanf(la, "%lf", &load[0]) != 1)
            load[0] = 0;
        fclose(la);
    }
    printf("bench_sweep: van der Pol, RK4, h = %g; best of %d; OpenMP threads by default: %d; "
           "load average %.1f\n\n",
           h, reps, nt, load[0]);
    printf("| case | wall [s] | vs one run | CPU [s] | CPU ns/step |\n"
           "|---|---:|---:|---:|---:|\n");
    printf("| one run of %.0e steps, 1 thread (dyn_fixed_solve) | %.3f | 1.00 | %.3f | %.1f |\n",
           nsteps, best[0][0], best[0][1], 1e9 * best[0][1] / nsteps);
    for (int k = 0; k < 4; k++)
        printf("| %ld runs x %ld steps, --reduce %s | %.3f | %s%.2f%s | %.3f | %.1f |\n", runs,
               steps, names[k], best[k + 1][0], k == 1 ? "**" : "",
               best[k + 1][0] / best[0][0], k == 1 ? "**" : "", best[k + 1][1],
               1e9 * best[k + 1][1] / nsteps);
    const double ratio = best[2][0] / best[0][0];
    printf("\ntarget: 2 threads at most 0.75 x one run: %.2f (%s)\n", ratio,
           ratio <= 0.75 ? "met" : "NOT met");
    printf("per-run overhead (CPU, 1 thread): %.2f us per run (%.1f%% of a run of %ld steps)\n",
           1e6 * (best[1][1] - best[0][1]) / (double)runs,
           100.0 * (best[1][1] - best[0][1]) / best[0][1], steps);
    printf("thread scaling efficiency T1 / (2 T2) (wall): final %.0f%%, final,max:y1 %.0f%%\n",
           100.0 * best[1][0] / (2.0 * best[2][0]), 100.0 * best[3][0] / (2.0 * best[4][0]));
    (void)y;
    free(res);
    free(st);
    return 0;
}
