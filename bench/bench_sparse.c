/* SPDX-License-Identifier: BSD-3-Clause */
/* bench_sparse.c — a large stiff system whose Jacobian is sparse but not banded: the complex
 * Ginzburg–Landau equation A_t = A + (1 + i a) A_xx - (1 + i b) |A|^2 A on a ring of N sites
 * (the equations, parameters and initial state of bench/cgl.ode, written by
 * bench/gen_cgl.py: a = 1, b = -0.5, d = 64, states u0, v0, u1, v1, ...), t in [0, 10].
 * rodas4 and SUNDIALS CVODE (BDF), each with dense matrices and with sparse ones (KLU:
 * dynkit_klu for rodas4, SUNDIALS' SUNLinSol_KLU for CVODE), all with the exact Jacobian.
 * - Reference: rodas4 with KLU at rtol = atol = 1e-12; CVODE at 1e-12 against it as a check.
 * - Work-precision: tolerances rtol = atol = 1e-3 ... 1e-9 (CVODE to 1e-10), error the max
 *   norm of the state at t = 10 against the reference, time the minimum over --reps runs of
 *   the process's CPU time (the machine is shared: CPU time does not count the waits for
 *   a core), each run with its allocations and KLU's analysis. Times at equal error are read
 *   off each curve as in bench_band.c (wp_curve.h), at 1e-4 ... 1e-8.
 * - Without the exact Jacobian (as a C model runs): rodas4 with dense differences (n calls
 *   of f a Jacobian) against differences in the pattern's groups of columns (Curtis, Powell
 *   & Reid: dyn_sparse_groups) factored by KLU, at equal error, with the calls of f.
 * - A sweep (dyn_sweep_run, as `dynkit sweep` runs it): 8 runs over b = -0.7 ... -0.3, rodas4
 *   dense and with KLU (one solver a thread, its analysis shared by the thread's runs) at
 *   equal error against the KLU sweep at 1e-12; then the same bits on 1 and 2 threads.
 * Usage: bench_sparse [--quick] [--reps K] [--sites N] [--verbose: every point on stderr]
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/solve.h"
#include "dynkit/sweep.h"
#include "bench_clock.h"
#include "wp_curve.h"
#ifdef DYNKIT_HAVE_CVODE
#include "dynkit/cvode.h"
#endif
#ifdef DYNKIT_HAVE_KLU
#include "dynkit/klu.h"
#endif

static const double tols[] = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
static const double levels[] = {1e-4, 1e-5, 1e-6, 1e-7, 1e-8};
enum { N_TOL = sizeof tols / sizeof tols[0], N_LEVELS = sizeof levels / sizeof levels[0] };
#define ROD_TOL_MIN 1e-9

typedef struct cgl {
    int N;          /* sites; n = 2N states */
    double a, b, d;
    dyn_sparse_pattern pat;
    int *colptr, *rowind;
} cgl;

static int cgl_rhs(double t, const double *y, double *f, void *par)
{
    const cgl *c = par;
    const int N = c->N;
    (void)t;
    for (int j = 0; j < N; j++) {
        const int jp = (j + 1) % N, jm = (j + N - 1) % N;
        const double u = y[2 * j], v = y[2 * j + 1];
        const double lu = y[2 * jp] - 2.0 * u + y[2 * jm];
        const double lv = y[2 * jp + 1] - 2.0 * v + y[2 * jm + 1];
        const double r = u * u + v * v;
        f[2 * j] = u + c->d * lu - c->a * c->d * lv - r * (u - c->b * v);
        f[2 * j + 1] = v + c->d * lv + c->a * c->d * lu - r * (v + c->b * u);
    }
    return 0;
}

/* d f / d y of site j's two equations: the 2 x 2 blocks on the site itself (diag) and on each
 * neighbour (off, the same for both): row-major [du/du du/dv; dv/du dv/dv]. */
static void cgl_blocks(const cgl *c, const double *y, int j, double diag[4], double off[4])
{
    const double u = y[2 * j], v = y[2 * j + 1], a = c->a, b = c->b, d = c->d;
    diag[0] = 1.0 - 2.0 * d - (3.0 * u * u + v * v) + 2.0 * b * u * v;
    diag[1] = 2.0 * a * d - (2.0 * u * v - b * (u * u + 3.0 * v * v));
    diag[2] = -2.0 * a * d - (2.0 * u * v + b * (3.0 * u * u + v * v));
    diag[3] = 1.0 - 2.0 * d - (u * u + 3.0 * v * v) - 2.0 * b * u * v;
    off[0] = d;
    off[1] = -a * d;
    off[2] = a * d;
    off[3] = d;
}

static int cgl_jac(double t, const double *y, double *J, void *par)
{
    const cgl *c = par;
    const int N = c->N, n = 2 * N;
    (void)t;
    memset(J, 0, (size_t)n * (size_t)n * sizeof *J);
    for (int j = 0; j < N; j++) {
        double dg[4], of[4];
        cgl_blocks(c, y, j, dg, of);
        const int cols[3] = {j, (j + 1) % N, (j + N - 1) % N};
        for (int q = 0; q < 3; q++)
            for (int r = 0; r < 2; r++)
                for (int s = 0; s < 2; s++)
                    J[(size_t)(2 * j + r) * n + 2 * cols[q] + s] += (q ? of : dg)[2 * r + s];
    }
    return 0;
}

/* The values in the pattern's order: column k = 2 m + s (state s of site m) holds rows of
 * sites m - 1, m, m + 1; the value at (row 2 j + r, column 2 m + s) is block[2 r + s]. */
static int cgl_jac_sparse(double t, const double *y, double *v, void *par)
{
    const cgl *c = par;
    const int N = c->N;
    (void)t;
    for (int col = 0; col < 2 * N; col++) {
        const int m = col / 2, s = col % 2;
        for (int k = c->colptr[col]; k < c->colptr[col + 1]; k++) {
            const int row = c->rowind[k], j = row / 2, r = row % 2;
            double dg[4], of[4];
            cgl_blocks(c, y, j, dg, of);
            v[k] = (j == m ? dg : of)[2 * r + s];
        }
    }
    return 0;
}

/* The pattern: column 2m + s holds the 6 rows of sites m - 1, m, m + 1, sorted. */
static int cgl_init(cgl *c, int N)
{
    const int n = 2 * N;
    c->N = N;
    c->a = 1.0;
    c->b = -0.5;
    c->d = 64.0;
    c->colptr = malloc(((size_t)n + 1) * sizeof *c->colptr);
    c->rowind = malloc((size_t)6 * n * sizeof *c->rowind);
    if (!c->colptr || !c->rowind)
        return 1;
    int k = 0;
    for (int col = 0; col < n; col++) {
        const int m = col / 2;
        int sites[3] = {(m + N - 1) % N, m, (m + 1) % N};
        for (int a = 0; a < 3; a++) /* sorted */
            for (int b = a + 1; b < 3; b++)
                if (sites[b] < sites[a]) {
                    const int tmp = sites[a];
                    sites[a] = sites[b];
                    sites[b] = tmp;
                }
        c->colptr[col] = k;
        for (int a = 0; a < 3; a++) {
            c->rowind[k++] = 2 * sites[a];
            c->rowind[k++] = 2 * sites[a] + 1;
        }
    }
    c->colptr[n] = k;
    c->pat = (dyn_sparse_pattern){n, k, c->colptr, c->rowind};
    return 0;
}

/* bench/gen_cgl.py's initial state: a plane wave of wavenumber 2 and a perturbation of 5. */
static void cgl_y0(const cgl *c, double *y0)
{
    for (int j = 0; j < c->N; j++) {
        const double x = 2.0 * 3.14159265358979323846 * j / c->N;
        y0[2 * j] = 0.9 * cos(2.0 * x) + 0.1 * cos(5.0 * x);
        y0[2 * j + 1] = 0.9 * sin(2.0 * x);
    }
}

typedef enum {
    ROD_DENSE,
    ROD_SPARSE,
    CV_DENSE,
    CV_SPARSE,
    N_SOLVERS,
    ROD_FD_DENSE = N_SOLVERS, /* without the exact Jacobian: n calls of f a Jacobian */
    ROD_FD_GROUPS,            /* the pattern without values: a call a group, and KLU */
    N_ALL
} solver_id;
static const char *const solver_names[N_ALL] = {
    "rodas4 dense",           "rodas4 KLU", "CVODE dense", "CVODE KLU",
    "rodas4 dense differences", "rodas4 grouped differences KLU"};
static long last_rhs; /* the calls of f of the last run */
static int n_groups;  /* the groups of the ring's pattern (dyn_sparse_groups) */
static int *groups;

/* One run to t = 10 into y; the steps, or -1. */
static long run(cgl *c, solver_id s, double tol, const double *y0, double *y)
{
    const int n = 2 * c->N;
    const dyn_system sys = {cgl_rhs, n, c};
    dyn_result res;
    if (s == CV_DENSE || s == CV_SPARSE) {
#ifdef DYNKIT_HAVE_CVODE
        dyn_cvode_opts o = {0};
        o.rtol = tol;
        o.atol = tol;
        o.jacobian = cgl_jac;
        o.max_steps = 1000000;
        if (s == CV_SPARSE) {
            o.jac_sparse = c->pat;
            o.jacobian_sparse = cgl_jac_sparse;
        }
        const double tout[1] = {10.0};
        if (dyn_cvode_solve(&sys, 0.0, y0, tout, 1, &o, NULL, NULL, y, &res) != DYN_OK) {
            fprintf(stderr, "bench_sparse: %s tol %g: %s\n", solver_names[s], tol, res.message);
            return -1;
        }
        return res.stats.steps;
#else
        return -1;
#endif
    }
    const dyn_tableau *meth = dyn_method_find("rodas4");
    dyn_solve_opts o = {0};
    o.rtol = tol;
    o.atol = tol;
    o.jacobian = s == ROD_FD_DENSE || s == ROD_FD_GROUPS ? NULL : cgl_jac;
    dyn_sparse_solver klu = {0};
#ifdef DYNKIT_HAVE_KLU
    if (s == ROD_SPARSE || s == ROD_FD_GROUPS) {
        if (dyn_klu_init(&klu))
            return -1;
        o.jac_sparse = c->pat;
        o.jacobian_sparse = s == ROD_SPARSE ? cgl_jac_sparse : NULL;
        o.jac_groups = groups;
        o.jac_n_groups = n_groups;
        o.sparse_solver = &klu;
    }
#endif
    double *work = malloc(dyn_solve_work_size(meth, n, &o) * sizeof *work);
    int *iwork = malloc(dyn_solve_iwork_size(meth, n) * sizeof *iwork);
    o.iwork = iwork;
    const int rc = work && iwork ? dyn_solve(meth, &sys, 0.0, 10.0, y0, y, work, &o, &res) : -1;
#ifdef DYNKIT_HAVE_KLU
    dyn_klu_release(&klu);
#endif
    free(work);
    free(iwork);
    if (rc != DYN_OK) {
        fprintf(stderr, "bench_sparse: %s tol %g: %s\n", solver_names[s], tol,
                rc == -1 ? "out of memory" : res.message);
        return -1;
    }
    last_rhs = res.stats.rhs_calls;
    return res.stats.accepted + res.stats.rejected;
}

static int available(solver_id s)
{
#ifndef DYNKIT_HAVE_CVODE
    if (s == CV_DENSE || s == CV_SPARSE)
        return 0;
#else
    if (s == CV_SPARSE && !dyn_cvode_has_klu())
        return 0;
#endif
#ifndef DYNKIT_HAVE_KLU
    if (s == ROD_SPARSE || s == ROD_FD_GROUPS)
        return 0;
#endif
    return 1;
}

/* ---- a sweep of the ring over b: dyn_sweep_run as `dynkit sweep` runs it ---- */

enum { SWEEP_RUNS = 8, SWEEP_TOLS = 6 };
typedef enum { SW_DENSE, SW_KLU, N_SWEEPS } sweep_id;
static const char *const sweep_names[N_SWEEPS] = {"sweep rodas4 dense", "sweep rodas4 KLU"};

/* SWEEP_RUNS runs of rodas4 to t = 10, b from -0.7 to -0.3, every final state into out
 * (SWEEP_RUNS x n), on `threads` threads, dense matrices or KLU (one solver a thread).
 * 0, or 1 with a message. */
static int sweep_ring(cgl *c, sweep_id s, double tol, const double *y0, int threads,
                      double *out)
{
    const int n = 2 * c->N;
    static const dyn_param params[] = {{"a", "1", "linear dispersion", offsetof(cgl, a), 1.0},
                                       {"b", "1", "nonlinear dispersion", offsetof(cgl, b), -0.5},
                                       {"d", "1", "1/dx^2", offsetof(cgl, d), 64.0}};
    dyn_var *states = calloc((size_t)n, sizeof *states);
    dyn_reduce *red = malloc((size_t)n * sizeof *red);
    int status[SWEEP_RUNS], rc = 1;
    if (!states || !red)
        goto done;
    for (int i = 0; i < n; i++) {
        states[i] = (dyn_var){"y", "1", ""};
        red[i] = (dyn_reduce){DYN_REDUCE_FINAL, DYN_SOURCE_STATE, i};
    }
    dyn_model m = {0};
    m.name = "cgl";
    m.n_states = n;
    m.states = states;
    m.n_params = 3;
    m.params = params;
    m.par_size = sizeof *c;
    m.rhs = cgl_rhs;
    m.jacobian = cgl_jac;
    m.jac_pattern = c->pat;
    m.jacobian_sparse = cgl_jac_sparse;
    double values[SWEEP_RUNS];
    for (int k = 0; k < SWEEP_RUNS; k++)
        values[k] = dyn_linspace_at(-0.7, -0.3, SWEEP_RUNS, k);
    const dyn_sweep_var var = {DYN_SWEEP_PARAM, 1};
    dyn_sweep sw = {0};
    sw.model = &m;
    sw.par = c;
    sw.y0 = y0;
    sw.n_vars = 1;
    sw.vars = &var;
    sw.n_runs = SWEEP_RUNS;
    sw.values = values;
    sw.method = dyn_method_find("rodas4");
    sw.t1 = 10.0;
    sw.rtol = sw.atol = tol;
    sw.n_reduce = n;
    sw.reduce = red;
    sw.threads = threads;
#ifdef DYNKIT_HAVE_KLU
    if (s == SW_KLU) {
        sw.sparse_open = dyn_klu_init;
        sw.sparse_close = dyn_klu_release;
    }
#endif
    char err[256];
    if (dyn_sweep_run(&sw, out, status, err, sizeof err) != DYN_OK) {
        fprintf(stderr, "bench_sparse: %s tol %g: %s\n", sweep_names[s], tol, err);
        goto done;
    }
    rc = 0;
    for (int k = 0; k < SWEEP_RUNS; k++)
        if (status[k] != DYN_OK) {
            fprintf(stderr, "bench_sparse: %s tol %g: run %d failed (status %d)\n",
                    sweep_names[s], tol, k, status[k]);
            rc = 1;
        }
done:
    free(states);
    free(red);
    return rc;
}

/* The sweep on one thread at tolerances 1e-3 ... 1e-8 (the error: max over runs and states
 * against ref), dense and with KLU, at equal error; then the same bits on 1 and 2 threads,
 * and KLU against dense at one tolerance. 0, or 1 when a run failed or a check did not hold. */
static int sweep_case(cgl *c, const double *y0, int reps, int quick)
{
    const int n = 2 * c->N;
    const size_t size = (size_t)SWEEP_RUNS * (size_t)n;
    double *ref = malloc(size * sizeof *ref), *y = malloc(size * sizeof *y);
    double *y2 = malloc(size * sizeof *y2);
    int failed = !ref || !y || !y2;
    const int have_klu = available(ROD_SPARSE);
    const sweep_id ref_id = have_klu ? SW_KLU : SW_DENSE;
    failed = failed || sweep_ring(c, ref_id, 1e-12, y0, 1, ref);
    curve cv[N_SWEEPS];
    for (int s = 0; s < N_SWEEPS && !failed; s++) {
        cv[s].k = 0;
        for (int t = 0; t < SWEEP_TOLS && !failed && (s == SW_DENSE || have_klu); t++) {
            double best = INFINITY;
            for (int r = 0; r < reps && !failed; r++) {
                const double t0 = bench_process_cpu_seconds();
                failed = sweep_ring(c, (sweep_id)s, tols[t], y0, 1, y);
                best = fmin(best, bench_process_cpu_seconds() - t0);
            }
            cv[s].err[cv[s].k] = max_err(y, ref, (int)size);
            cv[s].time[cv[s].k] = best;
            cv[s].steps[cv[s].k++] = 0;
        }
    }
    if (failed) {
        free(ref);
        free(y);
        free(y2);
        return 1;
    }
    printf("\n## The same ring in a sweep: %d runs over b = -0.7 ... -0.3 (dyn_sweep_run, 1 "
           "thread)\n\n",
           SWEEP_RUNS);
    printf("error: max over the runs' final states against the %s sweep at 1e-12; time: CPU "
           "seconds of the whole sweep, min of %d\n\n",
           have_klu ? "KLU" : "dense", reps);
    printf("| error | sweep rodas4 dense s | sweep rodas4 KLU s | dense / KLU |\n");
    printf("|---:|---:|---:|---:|\n");
    for (int l = 0; l < N_LEVELS; l++) {
        const double td = time_at(&cv[SW_DENSE], levels[l]);
        const double tk = cv[SW_KLU].k ? time_at(&cv[SW_KLU], levels[l]) : NAN;
        printf("| %.0e | %.3g | %.3g | %.1f |\n", levels[l], td, tk, td / tk);
    }
    /* 1 and 2 threads: the same bits; KLU against dense at 1e-6 */
    const double tol = 1e-6;
    for (int s = 0; s < N_SWEEPS; s++) {
        if (s == SW_KLU && !have_klu)
            continue;
        failed |= sweep_ring(c, (sweep_id)s, tol, y0, 1, y);
        failed |= sweep_ring(c, (sweep_id)s, tol, y0, 2, y2);
        const int same = !failed && memcmp(y, y2, size * sizeof *y) == 0;
        printf("\n%s at tol %g: 1 and 2 threads (%d used) give %s", sweep_names[s], tol,
               dyn_sweep_threads(2), same ? "the same bits" : "DIFFERENT results");
        failed |= !same;
        if (s == SW_KLU && !failed) {
            failed |= sweep_ring(c, SW_DENSE, tol, y0, 1, y2);
            const double d = max_err(y, y2, (int)size);
            printf("; KLU against dense: %.2g (the error at this tolerance: %.2g)", d,
                   max_err(y2, ref, (int)size));
            if (quick && !(d < 1e-3 * max_err(y2, ref, (int)size) + 1e-12)) {
                fprintf(stderr, "bench_sparse: the KLU sweep differs from the dense one by %g\n",
                        d);
                failed = 1;
            }
        }
    }
    printf("\n");
    free(ref);
    free(y);
    free(y2);
    return failed;
}

static int measure(cgl *c, solver_id s, const double *y0, const double *ref, int reps,
                   int n_tol, curve *cv)
{
    const int n = 2 * c->N;
    double *y = malloc((size_t)n * sizeof *y);
    cv->k = 0;
    for (int t = 0; t < n_tol && y; t++) {
        if ((s == ROD_DENSE || s == ROD_SPARSE || s >= N_SOLVERS) && tols[t] < ROD_TOL_MIN)
            break;
        double best = INFINITY;
        long steps = 0;
        for (int r = 0; r < reps; r++) {
            const double t0 = bench_process_cpu_seconds();
            steps = run(c, s, tols[t], y0, y);
            best = fmin(best, bench_process_cpu_seconds() - t0);
            if (steps < 0) {
                free(y);
                return 1;
            }
        }
        cv->err[cv->k] = max_err(y, ref, n);
        cv->time[cv->k] = best;
        cv->steps[cv->k] = s >= N_SOLVERS ? last_rhs : steps; /* differences: calls of f */
        cv->k++;
    }
    free(y);
    return y ? 0 : 1;
}

/* Without the exact Jacobian (a C model): rodas4 with dense differences (n calls of f a
 * Jacobian, dense LU) against the pattern's differences in groups (a call a group) and KLU,
 * at equal error; the calls of f at each tolerance. 0, or 1 when a run failed. */
static int differences_case(cgl *c, const double *y0, const double *ref, int reps, int n_tol,
                            int verbose)
{
    const int n = 2 * c->N;
    groups = malloc((size_t)n * sizeof *groups);
    if (!groups || (n_groups = dyn_sparse_groups(&c->pat, groups)) < 1)
        return 1;
    curve cv[2];
    int failed = 0;
    for (int k = 0; k < 2; k++) {
        const solver_id s = k ? ROD_FD_GROUPS : ROD_FD_DENSE;
        cv[k].k = 0;
        if (available(s))
            failed |= measure(c, s, y0, ref, reps, n_tol, &cv[k]);
        if (verbose)
            for (int i = 0; i < cv[k].k; i++)
                fprintf(stderr, "%-30s tol %.0e err %.3e time %.4g rhs %ld\n", solver_names[s],
                        tols[i], cv[k].err[i], cv[k].time[i], cv[k].steps[i]);
    }
    printf("\n## Without the exact Jacobian: differences, dense or in %d groups of columns\n\n",
           n_groups);
    printf("rodas4 with dense differences (%d calls of f a Jacobian, dense LU) and with the "
           "pattern's differences in %d groups (%d calls, KLU); error and time as above; calls "
           "of f at each tolerance\n\n",
           n, n_groups, n_groups);
    printf("| tol | calls dense | calls groups | error dense | error groups |\n");
    printf("|---:|---:|---:|---:|---:|\n");
    for (int i = 0; i < cv[0].k && i < cv[1].k; i++)
        printf("| %.0e | %ld | %ld | %.2g | %.2g |\n", tols[i], cv[0].steps[i], cv[1].steps[i],
               cv[0].err[i], cv[1].err[i]);
    printf("\n| error | dense differences s | grouped differences KLU s | dense / groups |\n");
    printf("|---:|---:|---:|---:|\n");
    for (int l = 0; l < N_LEVELS; l++) {
        const double td = cv[0].k ? time_at(&cv[0], levels[l]) : NAN;
        const double tg = cv[1].k ? time_at(&cv[1], levels[l]) : NAN;
        printf("| %.0e | %.3g | %.3g | %.1f |\n", levels[l], td, tg, td / tg);
    }
    free(groups);
    groups = NULL;
    return failed;
}

int main(int argc, char **argv)
{
    int quick = 0, reps = 3, verbose = 0, N = 128;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--quick") == 0)
            quick = 1;
        else if (strcmp(argv[i], "--verbose") == 0)
            verbose = 1;
        else if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc)
            reps = atoi(argv[++i]);
        else if (strcmp(argv[i], "--sites") == 0 && i + 1 < argc)
            N = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: bench_sparse [--quick] [--reps K >= 1] [--sites N >= 3] "
                            "[--verbose]\n");
            return 2;
        }
    }
    if (reps < 1 || N < 3) {
        fprintf(stderr, "bench_sparse: --reps must be >= 1 and --sites >= 3\n");
        return 2;
    }
    if (quick) {
        reps = 1;
        N = 32;
    }
    const int n_tol = quick ? 5 : N_TOL;
    cgl c;
    const int n = 2 * N;
    double *y0 = malloc((size_t)n * sizeof *y0), *ref = malloc((size_t)n * sizeof *ref);
    double *chk = malloc((size_t)n * sizeof *chk);
    if (!y0 || !ref || !chk || cgl_init(&c, N)) {
        fprintf(stderr, "bench_sparse: out of memory\n");
        return 1;
    }
    cgl_y0(&c, y0);
    const solver_id ref_solver = available(ROD_SPARSE) ? ROD_SPARSE : ROD_DENSE;
    if (run(&c, ref_solver, 1e-12, y0, ref) < 0)
        return 1;
    double ref_check = NAN;
    if (available(CV_DENSE) && run(&c, CV_DENSE, 1e-12, y0, chk) >= 0)
        ref_check = max_err(chk, ref, n);
    printf("## Sparse, not banded: the complex Ginzburg-Landau ring, %d sites (%d states, %d "
           "entries of the Jacobian)\n\n",
           N, n, c.pat.nnz);
    printf("error: max norm at t = 10 against %s at 1e-12 (CVODE dense at 1e-12 differs by "
           "%.1e); time: CPU seconds, min of %d runs\n\n",
           solver_names[ref_solver], ref_check, reps);
    curve cv[N_SOLVERS];
    int failed = 0;
    for (int s = 0; s < N_SOLVERS; s++) {
        cv[s].k = 0;
        if (available(s))
            failed |= measure(&c, (solver_id)s, y0, ref, reps, n_tol, &cv[s]);
        if (verbose)
            for (int i = 0; i < cv[s].k; i++)
                fprintf(stderr, "%-13s tol %.0e err %.3e time %.4g steps %ld\n",
                        solver_names[s], tols[i], cv[s].err[i], cv[s].time[i], cv[s].steps[i]);
    }
    printf("| error | rodas4 dense s | rodas4 KLU s | CVODE dense s | CVODE KLU s | "
           "rodas4 KLU / CVODE KLU | rodas4 KLU / CVODE dense |\n");
    printf("|---:|---:|---:|---:|---:|---:|---:|\n");
    double worst = 0.0;
    for (int l = 0; l < N_LEVELS; l++) {
        double t[N_SOLVERS];
        for (int s = 0; s < N_SOLVERS; s++)
            t[s] = cv[s].k ? time_at(&cv[s], levels[l]) : NAN;
        const double r = t[ROD_SPARSE] / t[CV_SPARSE];
        if (isfinite(r))
            worst = fmax(worst, r);
        printf("| %.0e | %.3g | %.3g | %.3g | %.3g | %.2f | %.2f |\n", levels[l], t[ROD_DENSE],
               t[ROD_SPARSE], t[CV_DENSE], t[CV_SPARSE], r, t[ROD_SPARSE] / t[CV_DENSE]);
    }
    printf("\nWorst ratio rodas4 KLU / CVODE KLU at equal error: %.2f (target <= 2)\n", worst);
    if (quick) { /* checks, never timings: errors near the tolerance, sparse = dense */
        for (int s = 0; s < N_SOLVERS; s++)
            for (int i = 0; i < cv[s].k; i++)
                if (!(cv[s].err[i] < 1000.0 * tols[i])) {
                    fprintf(stderr, "bench_sparse: %s error %g at tol %g\n", solver_names[s],
                            cv[s].err[i], tols[i]);
                    failed = 1;
                }
        for (int i = 0; i < cv[ROD_SPARSE].k && i < cv[ROD_DENSE].k; i++)
            if (cv[ROD_SPARSE].steps[i] != cv[ROD_DENSE].steps[i] ||
                fabs(cv[ROD_SPARSE].err[i] - cv[ROD_DENSE].err[i]) >
                    1e-3 * cv[ROD_DENSE].err[i] + 1e-9) {
                fprintf(stderr, "bench_sparse: rodas4 KLU and dense differ at tol %g\n", tols[i]);
                failed = 1;
            }
        if (!(ref_check < 1e-8) && !isnan(ref_check)) {
            fprintf(stderr, "bench_sparse: CVODE and rodas4 at 1e-12 differ by %g\n", ref_check);
            failed = 1;
        }
    }
    failed |= differences_case(&c, y0, ref, reps, n_tol, verbose);
    failed |= sweep_case(&c, y0, reps, quick);
    free(y0);
    free(ref);
    free(chk);
    free(c.colptr);
    free(c.rowind);
    return failed;
}
