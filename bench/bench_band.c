/* SPDX-License-Identifier: BSD-3-Clause */
/* bench_band.c — large stiff systems: how the cost of rodas4 with band matrices grows with
 * the size of the system, against SUNDIALS CVODE (BDF) with its band solver, at equal error,
 * on the Brusselator of Hairer & Wanner, "Solving ODEs II", sec. IV.10 (dynkit/
 * brusselator.h), N = 10 ... 2000 (20 ... 4000 states), t in [0, 10].
 * - Reference: rodas4 at rtol = atol = 1e-12 (band, analytic Jacobian); CVODE at 1e-12 is
 *   printed against it, as a check of the reference.
 * - Work-precision: rodas4 at rtol = atol = 1e-3 ... 1e-9, CVODE to 1e-10 (its errors are
 *   larger at equal tolerance), the error the max norm of
 *   the state at t = 10 against the reference, the time the minimum of --reps runs (each
 *   run includes its allocations). The time at a given error is read off each solver's
 *   curve by linear interpolation of log(time) against log(error) (the usual reading of a
 *   work-precision diagram, HNW II sec. IV.10); the ratio rodas4/CVODE is taken at the
 *   error levels both curves reach, 1e-4 ... 1e-8.
 * - Growth: the slope of log(time) against log(N) at error 1e-6, by least squares over
 *   N >= 50 (1: linear), for both; rodas4 with dense matrices for N <= 100 shows what the
 *   band saves.
 * Both use their analytic Jacobian; rodas4 factors the band with LAPACK's dgbtrf when the
 * backend dynkit_lapack is linked (else its own band LU), as the tool does, and then runs
 * once more with the library's own band LU (the last column) to show what LAPACK buys.
 * Usage: bench_band [--quick] [--reps K] [--svg DIR] [--verbose: every point on stderr]
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "dynkit/brusselator.h"
#include "dynkit/solve.h"
#include "bench_clock.h"
#include "wp_curve.h"
#include "wp_svg.h"
#ifdef DYNKIT_HAVE_CVODE
#include "dynkit/cvode.h"
#endif
#ifdef DYNKIT_HAVE_LAPACK
#include "dynkit/lapack.h"
#endif

#define MAX_SIZES 8
#define MAX_LEVELS 5

static const int sizes_full[] = {10, 20, 50, 100, 200, 500, 1000, 2000};
static const int sizes_quick[] = {10, 20};
/* tolerances rtol = atol; CVODE's errors are larger at the same tolerance, so it goes one
 * further to reach the same errors */
static const double tols[] = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
static const double levels[] = {1e-4, 1e-5, 1e-6, 1e-7, 1e-8};
enum { N_TOL = sizeof tols / sizeof tols[0], N_LEVELS = sizeof levels / sizeof levels[0] };
#define ROD_TOL_MIN 1e-9
#define GROWTH_LEVEL 1e-6
#define DENSE_MAX_N 100

static const dyn_band_solver *band_solver(void)
{
#ifdef DYNKIT_HAVE_LAPACK
    return &dyn_band_solver_lapack;
#else
    return &dyn_band_solver_builtin;
#endif
}

typedef struct problem {
    int N, n;
    dyn_model *m;
    dyn_brusselator_par par;
    double *y0;
} problem;

/* rodas4 from y0 to t = 10 into y; band (1) or dense (0). Returns the steps, or -1. */
static long run_rodas(const problem *p, int band, const dyn_band_solver *solver, double tol,
                      double *y)
{
    const dyn_tableau *meth = dyn_method_find("rodas4");
    dyn_solve_opts o = {0};
    o.rtol = tol;
    o.atol = tol;
    o.jacobian = dyn_brusselator_jac;
    o.jac_banded = band;
    o.jac_lower = o.jac_upper = 2;
    o.jacobian_band = dyn_brusselator_jac_band;
    o.band_solver = solver;
    double *work = malloc(dyn_solve_work_size(meth, p->n, &o) * sizeof *work);
    int *iwork = malloc(dyn_solve_iwork_size(meth, p->n) * sizeof *iwork);
    o.iwork = iwork;
    const dyn_system sys = {dyn_brusselator_rhs, p->n, (void *)&p->par};
    dyn_result res;
    int rc = work && iwork ? dyn_solve(meth, &sys, 0.0, 10.0, p->y0, y, work, &o, &res) : -1;
    free(work);
    free(iwork);
    if (rc != DYN_OK) {
        fprintf(stderr, "bench_band: rodas4 N = %d tol %g: %s\n", p->N, tol,
                rc == -1 ? "out of memory" : res.message);
        return -1;
    }
    return res.stats.accepted + res.stats.rejected;
}

#ifdef DYNKIT_HAVE_CVODE
static long run_cvode(const problem *p, double tol, double *y)
{
    dyn_cvode_opts o = {0};
    o.rtol = tol;
    o.atol = tol;
    o.jac_banded = 1;
    o.jac_lower = o.jac_upper = 2;
    o.jacobian_band = dyn_brusselator_jac_band;
    o.max_steps = 1000000;
    const dyn_system sys = {dyn_brusselator_rhs, p->n, (void *)&p->par};
    const double tout[1] = {10.0};
    dyn_result res;
    if (dyn_cvode_solve(&sys, 0.0, p->y0, tout, 1, &o, NULL, NULL, y, &res) != DYN_OK) {
        fprintf(stderr, "bench_band: cvode N = %d tol %g: %s\n", p->N, tol, res.message);
        return -1;
    }
    return res.stats.steps;
}
#endif

typedef enum { ROD_BAND, ROD_BAND_BUILTIN, ROD_DENSE, CVODE_BAND } solver_id;

static int measure(const problem *p, solver_id s, const double *ref, int reps, curve *c)
{
    double *y = malloc((size_t)p->n * sizeof *y);
    c->k = 0;
    for (int t = 0; t < N_TOL; t++) {
        if (s != CVODE_BAND && tols[t] < ROD_TOL_MIN)
            break;
        double best = INFINITY;
        long steps = 0;
        for (int r = 0; r < reps; r++) {
            const double t0 = bench_wall_seconds();
            if (s == CVODE_BAND) {
#ifdef DYNKIT_HAVE_CVODE
                steps = run_cvode(p, tols[t], y);
#endif
            } else {
                steps = run_rodas(p, s != ROD_DENSE,
                                  s == ROD_BAND_BUILTIN ? &dyn_band_solver_builtin : band_solver(),
                                  tols[t], y);
            }
            best = fmin(best, bench_wall_seconds() - t0);
            if (steps < 0) {
                free(y);
                return 1;
            }
        }
        c->err[c->k] = max_err(y, ref, p->n);
        c->time[c->k] = best;
        c->steps[c->k] = steps;
        c->k++;
    }
    free(y);
    return 0;
}

/* The band LU alone, the library's against the backend's: one factorisation and six solves
 * (a rodas4 step) of I/(h gamma) - J for the Brusselator's J at y0, n = 2N; the minimum over
 * `rounds` rounds that alternate the two, each round timing `batch` repetitions. Returns the
 * ratio own/backend (NAN without a backend) and the backend's microseconds per step. */
static double lu_alone(int N, int rounds, double *us_backend)
{
    *us_backend = NAN;
    if (band_solver() == &dyn_band_solver_builtin)
        return NAN;
    char err[128];
    dyn_model *m = dyn_brusselator_new(N, err, sizeof err);
    dyn_brusselator_par par;
    const int n = 2 * N, kl = 2, ku = 2, ldab = 2 * kl + ku + 1, batch = 20;
    double *y0 = malloc((size_t)n * sizeof *y0), *J = malloc((size_t)n * 5 * sizeof *J);
    double *W0 = calloc((size_t)n * ldab, sizeof *W0), *W = malloc((size_t)n * ldab * sizeof *W);
    double *b = malloc((size_t)n * sizeof *b);
    int *piv = malloc((size_t)n * sizeof *piv);
    if (!m || !y0 || !J || !W0 || !W || !b || !piv ||
        dyn_model_default_params(m, &par, err, sizeof err)) {
        fprintf(stderr, "bench_band: out of memory for the LU alone\n");
        exit(1);
    }
    dyn_model_initial_state(m, &par, y0);
    dyn_brusselator_jac_band(0.0, y0, J, &par);
    for (int j = 0; j < n; j++)
        for (int i = j - ku; i <= j + kl; i++)
            if (i >= 0 && i < n)
                W0[(size_t)j * ldab + (size_t)(kl + ku + i - j)] =
                    (i == j ? 1.0 / (0.01 * 0.25) : 0.0) - DYN_BAND_AT(J, kl, ku, i, j);
    const dyn_band_solver *sv[2] = {&dyn_band_solver_builtin, band_solver()};
    double best[2] = {INFINITY, INFINITY};
    for (int r = 0; r < rounds; r++)
        for (int k = 0; k < 2; k++) {
            const dyn_band_solver *v = sv[(r + k) % 2];
            const double t0 = bench_wall_seconds();
            for (int q = 0; q < batch; q++) {
                memcpy(W, W0, (size_t)n * ldab * sizeof *W);
                v->factor(n, kl, ku, W, ldab, piv);
                for (int st = 0; st < 6; st++) {
                    for (int i = 0; i < n; i++)
                        b[i] = 1.0 + 1e-3 * i;
                    v->solve(n, kl, ku, W, ldab, piv, b);
                }
            }
            const double dt = (bench_wall_seconds() - t0) / batch;
            best[(r + k) % 2] = fmin(best[(r + k) % 2], dt);
        }
    *us_backend = 1e6 * best[1];
    free(y0);
    free(J);
    free(W0);
    free(W);
    free(b);
    free(piv);
    dyn_brusselator_free(m);
    return best[0] / best[1];
}

static double slope(const double *x, const double *y, int n)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int k = 0;
    for (int i = 0; i < n; i++) {
        if (!(y[i] > 0.0) || !isfinite(y[i]))
            continue;
        const double lx = log(x[i]), ly = log(y[i]);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
        k++;
    }
    if (k < 2)
        return NAN;
    return (k * sxy - sx * sy) / (k * sxx - sx * sx);
}

static void loadavg(char *buf, size_t size)
{
    FILE *f = fopen("/proc/loadavg", "r");
    buf[0] = '\0';
    if (f) {
        if (!fgets(buf, (int)size, f))
            buf[0] = '\0';
        fclose(f);
    }
    buf[strcspn(buf, "\n")] = '\0';
}

int main(int argc, char **argv)
{
    int quick = 0, reps = 5, verbose = 0;
    const char *svg_dir = NULL;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--quick") == 0)
            quick = 1;
        else if (strcmp(argv[i], "--verbose") == 0)
            verbose = 1;
        else if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc)
            reps = atoi(argv[++i]);
        else if (strcmp(argv[i], "--svg") == 0 && i + 1 < argc)
            svg_dir = argv[++i];
        else {
            fprintf(stderr, "usage: bench_band [--quick] [--reps K >= 1] [--svg DIR] [--verbose]\n");
            return 2;
        }
    }
    if (reps < 1) {
        fprintf(stderr, "bench_band: --reps must be >= 1\n");
        return 2;
    }
    if (quick)
        reps = 1;
    const int *sizes = quick ? sizes_quick : sizes_full;
    const int n_sizes = quick ? 2 : (int)(sizeof sizes_full / sizeof sizes_full[0]);
    char load0[128], load1[128];
    loadavg(load0, sizeof load0);
    printf("## Large stiff systems: the Brusselator (HNW II, IV.10), rodas4 band vs CVODE band\n\n");
    printf("rodas4's band LU: %s; error: max norm at t = 10 against rodas4 at 1e-12; time: "
           "min of %d runs; load average before: %s\n\n",
           band_solver()->name, reps, load0);
#ifndef DYNKIT_HAVE_CVODE
    printf("(CVODE backend not built: rodas4 only)\n\n");
#endif
    printf("| N | states | ref. check | rodas4 s @1e-6 | CVODE s @1e-6 | ratio @1e-6 | "
           "ratio 1e-4..1e-8 | rodas4 dense s @1e-6 | rodas4 band, own LU s @1e-6 |\n");
    printf("|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    double t_rod[MAX_SIZES], t_cv[MAX_SIZES], t_dense[MAX_SIZES], t_own[MAX_SIZES];
    double xs[MAX_SIZES];
    double worst_ratio = 0.0;
    int failed = 0;
    for (int s = 0; s < n_sizes; s++) {
        problem p;
        char err[128];
        p.N = sizes[s];
        p.n = 2 * p.N;
        p.m = dyn_brusselator_new(p.N, err, sizeof err);
        if (!p.m || dyn_model_default_params(p.m, &p.par, err, sizeof err)) {
            fprintf(stderr, "bench_band: %s\n", err);
            return 1;
        }
        p.y0 = malloc((size_t)p.n * sizeof *p.y0);
        double *ref = malloc((size_t)p.n * sizeof *ref), *chk = malloc((size_t)p.n * sizeof *chk);
        dyn_model_initial_state(p.m, &p.par, p.y0);
        if (run_rodas(&p, 1, band_solver(), 1e-12, ref) < 0)
            return 1;
        double ref_check = NAN;
#ifdef DYNKIT_HAVE_CVODE
        if (run_cvode(&p, 1e-12, chk) >= 0)
            ref_check = max_err(chk, ref, p.n);
#endif
        curve rb, cv = {0}, dn = {0}, ob = {0};
        failed |= measure(&p, ROD_BAND, ref, reps, &rb);
        if (band_solver() != &dyn_band_solver_builtin && !quick)
            failed |= measure(&p, ROD_BAND_BUILTIN, ref, reps, &ob);
#ifdef DYNKIT_HAVE_CVODE
        failed |= measure(&p, CVODE_BAND, ref, reps, &cv);
#endif
        if (p.N <= DENSE_MAX_N && !quick)
            failed |= measure(&p, ROD_DENSE, ref, reps, &dn);
        xs[s] = p.n;
        t_rod[s] = time_at(&rb, GROWTH_LEVEL);
        t_cv[s] = cv.k ? time_at(&cv, GROWTH_LEVEL) : NAN;
        t_dense[s] = dn.k ? time_at(&dn, GROWTH_LEVEL) : NAN;
        t_own[s] = ob.k ? time_at(&ob, GROWTH_LEVEL) : NAN;
        double lo = INFINITY, hi = 0.0;
        for (int l = 0; l < N_LEVELS; l++) {
            const double r = time_at(&rb, levels[l]) / time_at(&cv, levels[l]);
            if (isfinite(r)) {
                lo = fmin(lo, r);
                hi = fmax(hi, r);
            }
        }
        if (hi > 0.0)
            worst_ratio = fmax(worst_ratio, hi);
        if (verbose) {
            const curve *cs[4] = {&rb, &cv, &dn, &ob};
            const char *names[4] = {"rodas4 band", "CVODE band", "rodas4 dense", "rodas4 own"};
            for (int c = 0; c < 4; c++)
                for (int i = 0; i < cs[c]->k; i++)
                    fprintf(stderr, "N %d %-12s tol %.0e err %.3e time %.4g steps %ld\n", p.N,
                            names[c], tols[i], cs[c]->err[i], cs[c]->time[i], cs[c]->steps[i]);
        }
        printf("| %d | %d | %.1e | %.3g | %.3g | %.2f | %.2f–%.2f | %.3g | %.3g |\n", p.N, p.n,
               ref_check, t_rod[s], t_cv[s], t_rod[s] / t_cv[s], lo, hi, t_dense[s], t_own[s]);
        if (quick) {
            /* checks: the errors fall with the tolerance and stay near it */
            for (int i = 0; i + 2 < rb.k; i += 2)
                if (!(rb.err[i + 2] < rb.err[i])) {
                    fprintf(stderr, "bench_band: rodas4 error does not fall with tol (N = %d)\n",
                            p.N);
                    failed = 1;
                }
            for (int i = 0; i < rb.k; i++)
                if (!(rb.err[i] < 100.0 * tols[i])) {
                    fprintf(stderr, "bench_band: rodas4 error %g at tol %g (N = %d)\n",
                            rb.err[i], tols[i], p.N);
                    failed = 1;
                }
            for (int i = 0; i < cv.k; i++)
                if (!(cv.err[i] < 1000.0 * tols[i])) {
                    fprintf(stderr, "bench_band: CVODE error %g at tol %g (N = %d)\n", cv.err[i],
                            tols[i], p.N);
                    failed = 1;
                }
            if (!(ref_check < 1e-8) && !isnan(ref_check)) {
                fprintf(stderr, "bench_band: CVODE and rodas4 at 1e-12 differ by %g\n",
                        ref_check);
                failed = 1;
            }
        }
        free(p.y0);
        free(ref);
        free(chk);
        dyn_brusselator_free(p.m);
    }
    loadavg(load1, sizeof load1);
    /* growth over N >= 50 */
    int first = 0;
    while (first < n_sizes && sizes[first] < 50)
        first++;
    const double s_rod = slope(xs + first, t_rod + first, n_sizes - first);
    const double s_cv = slope(xs + first, t_cv + first, n_sizes - first);
    const double s_dn = slope(xs, t_dense, n_sizes);
    double own_lo = INFINITY, own_hi = 0.0; /* the library's band LU against LAPACK's */
    for (int s = 0; s < n_sizes; s++)
        if (isfinite(t_own[s] / t_rod[s])) {
            own_lo = fmin(own_lo, t_own[s] / t_rod[s]);
            own_hi = fmax(own_hi, t_own[s] / t_rod[s]);
        }
    printf("\nGrowth of the time at error 1e-6 with the number of states (least-squares slope "
           "of log time against log n, N >= 50; 1 is linear): rodas4 band %.2f, CVODE band "
           "%.2f; rodas4 dense (N <= %d) %.2f\n",
           s_rod, s_cv, DENSE_MAX_N, s_dn);
    printf("Worst ratio rodas4/CVODE at equal error over all N and levels: %.2f (target <= 2)\n",
           worst_ratio);
    if (own_hi > 0.0)
        printf("rodas4 with the library's own band LU against LAPACK's dgbtrf: %.2f to %.2f "
               "times the time at error 1e-6\n",
               own_lo, own_hi);
    if (!quick) {
        for (int s = 0; s < n_sizes; s++) {
            if (sizes[s] < 100)
                continue;
            double us;
            const double r = lu_alone(sizes[s], 2 * reps + 1, &us);
            if (isfinite(r))
                printf("band LU alone (factor + 6 solves), n = %d: %s %.1f us, the library's own "
                       "%.2f times that\n",
                       2 * sizes[s], band_solver()->name, us, r);
        }
    }
    printf("Load average after: %s\n", load1);
    if (svg_dir && !quick) {
        char path[1024];
        snprintf(path, sizeof path, "%s/brusselator-growth.svg", svg_dir);
        FILE *f = fopen(path, "w");
        if (!f) {
            fprintf(stderr, "bench_band: cannot write %s\n", path);
            return 1;
        }
        wp_plot pl = {0};
        pl.title = "Brusselator (HNW II IV.10): time at error 1e-6 against the number of states";
        pl.xlabel = "states 2N";
        pl.ylabel = "time [s]";
        pl.n_lines = 3;
        pl.lines[0] = (wp_line){"rodas4, band (LAPACK dgbtrf)", n_sizes, xs, t_rod, 1};
        if (band_solver() == &dyn_band_solver_builtin)
            pl.lines[0].label = "rodas4, band";
        pl.lines[1] = (wp_line){"CVODE BDF, band", n_sizes, xs, t_cv, 0};
        pl.lines[2] = (wp_line){"rodas4, dense LU", n_sizes, xs, t_dense, 0};
        const int bad = wp_svg_write(f, &pl);
        if (fclose(f) || bad) {
            fprintf(stderr, "bench_band: error writing %s\n", path);
            return 1;
        }
        printf("wrote %s\n", path);
    }
    return failed;
}
