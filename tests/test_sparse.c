/* SPDX-License-Identifier: BSD-3-Clause */
/* test_sparse.c — sparse Jacobians of the stiff methods (docs/stiff.md, "Large systems"):
 * the pattern a model file's exact Jacobian carries is the known structure of its equations
 * (a ring of 40 sites: three entries a row, the ring closing at the corners; a chain with
 * fixed ends: tridiagonal, found as a band without a declaration); its values equal the
 * dense Jacobian's; rodas4 with sparse matrices (a sparse solver of this file over the dense
 * LU, and KLU when built) ends where it ends with dense or band matrices, on the banded
 * chain and on the ring that is not banded; cvode with SUNDIALS' KLU likewise; and without
 * a sparse solver the pattern is not used (the dense run, bit for bit), while a pattern
 * without its diagonal is refused with a message. The tool says which matrices it took
 * (--stats, info) and why (--verbose), and its runs agree whichever they are. A sweep takes
 * the same matrices, one sparse solver per thread, with the same results on 1 and 2
 * threads. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/dynkit.h"
#include "dynkit/jit.h"
#include "dynkit/lang.h"
#include "dynkit/sweep.h"
#include "ode/linalg.h"
#include "test_cli_run.h"
#include "test_util.h"
#include "test_ode_load.h"

#ifdef DYNKIT_HAVE_KLU
#include "dynkit/klu.h"
#endif
#ifdef DYNKIT_HAVE_CVODE
#include "dynkit/cvode.h"
#endif

#define N 40

/* u' = d (second difference) - u^3 on a ring of N sites: row i reads i - 1, i, i + 1 mod N */
static const char ring_ode[] = "par d=50\n"
                               "u0'=d*(u1-2*u0+u39)-u0^3\n"
                               "u[1..38]'=d*(u[j+1]-2*u[j]+u[j-1])-u[j]^3\n"
                               "u39'=d*(u0-2*u39+u38)-u39^3\n"
                               "init u[0..39]=sin(2*pi*[j]/40)+0.5\n"
                               "@ total=1\n"
                               "done\n";
/* the same with fixed ends (u_-1 = u_40 = 0): tridiagonal */
static const char chain_ode[] = "par d=50\n"
                                "u0'=d*(u1-2*u0)-u0^3\n"
                                "u[1..38]'=d*(u[j+1]-2*u[j]+u[j-1])-u[j]^3\n"
                                "u39'=d*(-2*u39+u38)-u39^3\n"
                                "init u[0..39]=sin(2*pi*[j]/40)+0.5\n"
                                "@ total=1\n"
                                "done\n";

static void load(const char *text, loaded *L) { test_ode_load(text, "sparse-jit-cache", L); }

/* A sparse solver over the library's dense LU: the plumbing of the sparse path checked
 * without KLU. */
typedef struct dense_ctx {
    double A[N * N];
    int piv[N];
} dense_ctx;

static int dense_factor(void *ctx, const dyn_sparse_pattern *p, const double *ax)
{
    dense_ctx *d = ctx;
    memset(d->A, 0, sizeof d->A);
    for (int j = 0; j < p->n; j++)
        for (int k = p->colptr[j]; k < p->colptr[j + 1]; k++)
            d->A[p->rowind[k] * p->n + j] = ax[k];
    return dyn_lu_factor(p->n, d->A, d->piv) ? 1 : 0;
}

static void dense_solve(void *ctx, int n, double *b)
{
    dense_ctx *d = ctx;
    dyn_lu_solve(n, d->A, d->piv, b);
}

/* Which matrices a rodas4 run uses. */
enum { DENSE, BAND, SPARSE_OWN, SPARSE_KLU, SPARSE_NO_SOLVER };

/* rodas4 from 0 to 1 at rtol 1e-8 with the matrices of `kind`; the final state into y and
 * the result into res. */
static int rodas(const loaded *L, int kind, double *y, dyn_result *res)
{
    const dyn_model *m = L->m;
    double y0[N];
    dyn_model_initial_state(m, L->par, y0);
    dyn_system sys = {m->rhs, N, (void *)L->par};
    dyn_solve_opts o = {0};
    o.rtol = 1e-8;
    o.atol = 1e-10;
    o.jacobian = m->jacobian;
    dense_ctx dc;
    dyn_sparse_solver own = {"dense", &dc, dense_factor, dense_solve, NULL};
    dyn_sparse_solver klu = {0};
    if (kind == BAND) {
        o.jac_banded = 1;
        o.jac_lower = m->jac_lower;
        o.jac_upper = m->jac_upper;
        o.jacobian_band = m->jacobian_band;
    } else if (kind != DENSE) {
        o.jac_sparse = m->jac_pattern;
        o.jacobian_sparse = m->jacobian_sparse;
        o.sparse_solver = kind == SPARSE_OWN ? &own : kind == SPARSE_KLU ? &klu : NULL;
    }
#ifdef DYNKIT_HAVE_KLU
    if (kind == SPARSE_KLU)
        assert_int_equal(dyn_klu_init(&klu), 0);
#endif
    const dyn_tableau *meth = dyn_method_find("rodas4");
    const size_t size = dyn_solve_work_size(meth, N, &o);
    double *work = malloc(size * sizeof *work);
    int iwork[N];
    o.iwork = iwork;
    assert_non_null(work);
    const int rc = dyn_solve(meth, &sys, 0.0, 1.0, y0, y, work, &o, res);
#ifdef DYNKIT_HAVE_KLU
    if (kind == SPARSE_KLU)
        dyn_klu_release(&klu);
#endif
    free(work);
    return rc;
}

/* rodas4 as rodas() does with SPARSE_OWN, the Jacobian by differences in groups. */
static int rodas_grouped(const loaded *L, const dyn_sparse_pattern *p, const int *group,
                         int groups, double *y, dyn_result *res)
{
    const dyn_model *m = L->m;
    double y0[N];
    dyn_model_initial_state(m, L->par, y0);
    dyn_system sys = {m->rhs, N, (void *)L->par};
    dyn_solve_opts o = {0};
    o.rtol = 1e-8;
    o.atol = 1e-10;
    dense_ctx dc;
    dyn_sparse_solver own = {"dense", &dc, dense_factor, dense_solve, NULL};
    o.jac_sparse = *p;
    o.jac_groups = group;
    o.jac_n_groups = groups;
    o.sparse_solver = &own;
    const dyn_tableau *meth = dyn_method_find("rodas4");
    double *work = malloc(dyn_solve_work_size(meth, N, &o) * sizeof *work);
    int iwork[N];
    o.iwork = iwork;
    assert_non_null(work);
    const int rc = dyn_solve(meth, &sys, 0.0, 1.0, y0, y, work, &o, res);
    free(work);
    return rc;
}

static double max_diff(const double *a, const double *b)
{
    double d = 0.0;
    for (int i = 0; i < N; i++)
        d = fmax(d, fabs(a[i] - b[i]));
    return d;
}

/* The ring's pattern is the known one: column j holds rows j - 1, j, j + 1 mod N (sorted),
 * 3N entries; no band is found (the corners); the sparse values equal the dense
 * Jacobian's, including the diagonal's. */
static void test_ring_pattern_is_the_known_one(void **state)
{
    (void)state;
    loaded L;
    load(ring_ode, &L);
    const dyn_sparse_pattern *p = &L.m->jac_pattern;
    assert_int_equal(p->n, N);
    assert_int_equal(p->nnz, 3 * N);
    assert_int_equal(L.m->jac_banded, 0);
    assert_non_null(L.m->jacobian_sparse);
    for (int j = 0; j < N; j++) {
        int want[3] = {(j + N - 1) % N, j, (j + 1) % N}, k0 = p->colptr[j];
        /* sorted */
        for (int a = 0; a < 3; a++)
            for (int b = a + 1; b < 3; b++)
                if (want[b] < want[a]) {
                    const int t = want[a];
                    want[a] = want[b];
                    want[b] = t;
                }
        assert_int_equal(p->colptr[j + 1] - k0, 3);
        for (int a = 0; a < 3; a++)
            CHECK(p->rowind[k0 + a] == want[a], "column %d entry %d: row %d, want %d", j, a,
                  p->rowind[k0 + a], want[a]);
    }
    char err[160];
    assert_int_equal(dyn_sparse_pattern_check(p, N, err, sizeof err), 0);
    int lo, up;
    dyn_sparse_pattern_band(p, &lo, &up);
    assert_int_equal(lo, N - 1);
    assert_int_equal(up, N - 1);
    double y[N], J[N * N], v[3 * N];
    dyn_model_initial_state(L.m, L.par, y);
    assert_int_equal(L.m->jacobian(0.0, y, J, L.par), 0);
    assert_int_equal(L.m->jacobian_sparse(0.0, y, v, L.par), 0);
    int nonzero = 0;
    for (int j = 0; j < N; j++)
        for (int k = p->colptr[j]; k < p->colptr[j + 1]; k++)
            assert_true(v[k] == J[p->rowind[k] * N + j]);
    for (int i = 0; i < N * N; i++)
        nonzero += J[i] != 0.0;
    assert_int_equal(nonzero, 3 * N); /* every entry outside the pattern is zero */
    dyn_jit_unload(&L.jm);
}

/* The chain with fixed ends is tridiagonal: its band (1, 1) is found without @ bandlo,
 * bandup, and its analytic band equals the dense Jacobian's. */
static void test_chain_band_is_found(void **state)
{
    (void)state;
    loaded L;
    load(chain_ode, &L);
    assert_int_equal(L.m->jac_banded, 1);
    assert_int_equal(L.m->jac_lower, 1);
    assert_int_equal(L.m->jac_upper, 1);
    assert_int_equal(L.m->jac_pattern.nnz, 3 * N - 2);
    double y[N], J[N * N], B[N * 3];
    dyn_model_initial_state(L.m, L.par, y);
    assert_int_equal(L.m->jacobian(0.0, y, J, L.par), 0);
    assert_int_equal(L.m->jacobian_band(0.0, y, B, L.par), 0);
    for (int i = 0; i < N; i++)
        for (int j = i > 0 ? i - 1 : 0; j <= i + 1 && j < N; j++)
            assert_true(DYN_BAND_AT(B, 1, 1, i, j) == J[i * N + j]);
    dyn_jit_unload(&L.jm);
}

/* rodas4 ends at the same state with dense, band and sparse matrices (the pivots differ, so
 * rounding does: within 1e-12 of states of size 1, far below the tolerance). */
static void test_rodas4_sparse_equals_dense(void **state)
{
    (void)state;
    const char *texts[2] = {chain_ode, ring_ode};
    for (int t = 0; t < 2; t++) {
        loaded L;
        load(texts[t], &L);
        double yd[N], ys[N];
        dyn_result rd, rs;
        assert_int_equal(rodas(&L, DENSE, yd, &rd), DYN_OK);
        int kinds[3] = {SPARSE_OWN, L.m->jac_banded ? BAND : SPARSE_OWN, SPARSE_OWN};
#ifdef DYNKIT_HAVE_KLU
        kinds[2] = SPARSE_KLU;
#endif
        for (int k = 0; k < 3; k++) {
            assert_int_equal(rodas(&L, kinds[k], ys, &rs), DYN_OK);
            CHECK(max_diff(yd, ys) < 1e-12, "%s, kind %d: differs by %g", t ? "ring" : "chain",
                  kinds[k], max_diff(yd, ys));
            assert_int_equal(rs.stats.accepted, rd.stats.accepted);
            assert_int_equal(rs.stats.jac_calls, rd.stats.jac_calls);
        }
        dyn_jit_unload(&L.jm);
    }
}

/* Without a sparse solver the pattern is not used: the dense run, bit for bit. A pattern
 * without a diagonal entry is refused, naming the column. */
static void test_without_a_solver_dense(void **state)
{
    (void)state;
    loaded L;
    load(ring_ode, &L);
    double yd[N], ys[N];
    dyn_result rd, rs;
    assert_int_equal(rodas(&L, DENSE, yd, &rd), DYN_OK);
    assert_int_equal(rodas(&L, SPARSE_NO_SOLVER, ys, &rs), DYN_OK);
    assert_memory_equal(yd, ys, sizeof yd);
    /* column 0 without its diagonal */
    const int colptr[3] = {0, 1, 3}, rowind[3] = {1, 0, 1};
    const dyn_sparse_pattern bad = {2, 3, colptr, rowind};
    char err[160];
    assert_int_equal(dyn_sparse_pattern_check(&bad, 2, err, sizeof err), 1);
    CHECK(strstr(err, "diagonal entry of column 0") != NULL, "%s", err);
    dyn_jit_unload(&L.jm);
}

/* cvode with SUNDIALS' KLU ends where cvode with dense matrices ends (to a few times the
 * tolerance: CVODE's Newton iteration stops at a fraction of it, differently with other
 * rounding), and both near rodas4. */
static void test_cvode_sparse(void **state)
{
    (void)state;
#if defined(DYNKIT_HAVE_CVODE)
    if (!dyn_cvode_has_klu())
        skip();
    loaded L;
    load(ring_ode, &L);
    double y0[N], yd[N], ys[N], yr[N];
    dyn_model_initial_state(L.m, L.par, y0);
    dyn_system sys = {L.m->rhs, N, L.par};
    dyn_cvode_opts o = {0};
    o.rtol = 1e-10;
    o.atol = 1e-12;
    o.jacobian = L.m->jacobian;
    const double tout[2] = {0.0, 1.0};
    dyn_result rd, rs, rr;
    assert_int_equal(dyn_cvode_solve(&sys, 0.0, y0, tout, 2, &o, NULL, NULL, yd, &rd), DYN_OK);
    o.jac_sparse = L.m->jac_pattern;
    o.jacobian_sparse = L.m->jacobian_sparse;
    assert_int_equal(dyn_cvode_solve(&sys, 0.0, y0, tout, 2, &o, NULL, NULL, ys, &rs), DYN_OK);
    assert_int_equal(rodas(&L, DENSE, yr, &rr), DYN_OK);
    CHECK(max_diff(yd, ys) < 1e-9, "cvode dense and sparse differ by %g", max_diff(yd, ys));
    CHECK(max_diff(yr, ys) < 1e-6, "cvode and rodas4 differ by %g", max_diff(yr, ys));
    dyn_jit_unload(&L.jm);
#else
    skip();
#endif
}

/* Two columns of one group share no row: the groups give a Jacobian in one call of f
 * each. */
static void check_groups(const dyn_sparse_pattern *p, const int *group, int groups)
{
    int owner[N];
    for (int i = 0; i < N; i++)
        owner[i] = -1;
    for (int g = 0; g < groups; g++)
        for (int j = 0; j < p->n; j++)
            if (group[j] == g)
                for (int k = p->colptr[j]; k < p->colptr[j + 1]; k++) {
                    CHECK(owner[p->rowind[k]] != g, "columns %d and another of group %d "
                          "share row %d", j, g, p->rowind[k]);
                    owner[p->rowind[k]] = g;
                }
}

/* Grouped columns (Curtis, Powell & Reid): a tridiagonal pattern takes 3 groups, the ring
 * 4 (its graph of columns sharing a row is a cycle of 40 with the second neighbours joined,
 * which 3 groups cannot colour since 40 is not a multiple of 3); no two columns of a group
 * share a row. Probing the ring's right-hand side finds the exact pattern, and rodas4 with
 * its Jacobian by differences in those 4 groups (4 calls of f a Jacobian instead of 40)
 * ends within 1e-7 of the exact sparse run. */
static void test_groups_and_probe(void **state)
{
    (void)state;
    const char *texts[2] = {chain_ode, ring_ode};
    const int expect[2] = {3, 4};
    for (int t = 0; t < 2; t++) {
        loaded L;
        load(texts[t], &L);
        int group[N];
        const int groups = dyn_sparse_groups(&L.m->jac_pattern, group);
        assert_int_equal(groups, expect[t]);
        check_groups(&L.m->jac_pattern, group, groups);
        double y0[N];
        dyn_model_initial_state(L.m, L.par, y0);
        const dyn_system sys = {L.m->rhs, N, L.par};
        dyn_sparse_pattern probed;
        char err[200];
        assert_int_equal(dyn_sparse_probe(&sys, 0.0, y0, 3, 1, &probed, err, sizeof err), 0);
        assert_int_equal(probed.nnz, L.m->jac_pattern.nnz);
        assert_memory_equal(probed.colptr, L.m->jac_pattern.colptr, (N + 1) * sizeof(int));
        assert_memory_equal(probed.rowind, L.m->jac_pattern.rowind,
                            (size_t)probed.nnz * sizeof(int));
        if (t == 1) {
            double ye[N], yg[N];
            dyn_result re, rg;
            assert_int_equal(rodas(&L, SPARSE_OWN, ye, &re), DYN_OK);
            assert_int_equal(rodas_grouped(&L, &probed, group, groups, yg, &rg), DYN_OK);
            CHECK(max_diff(ye, yg) < 1e-7, "grouped differences: %g", max_diff(ye, yg));
            /* rodas4: 7 calls a step from a new point, 5 after a rejection, 2 more; and
             * one call per group a Jacobian */
            assert_int_equal(rg.stats.rhs_calls, 7 * rg.stats.accepted +
                                                      5 * rg.stats.rejected + 2 +
                                                      groups * rg.stats.jac_calls);
        }
        dyn_sparse_pattern_free(&probed);
        dyn_jit_unload(&L.jm);
    }
}

/* A sweep's sparse solvers (dynkit/sweep.h): the dense-LU solver of this file, one per
 * thread, counting the threads' solvers and the solves that start (forget). */
typedef struct counted {
    dense_ctx d;
    int forgets;
} counted;
static int opened, closed, forgotten;

static void counted_forget(void *ctx) { ((counted *)ctx)->forgets++; }

static int counted_open(dyn_sparse_solver *s)
{
    counted *c = calloc(1, sizeof *c);
    *s = (dyn_sparse_solver){"counted", c, dense_factor, dense_solve, counted_forget};
    opened++; /* the workers are made on the calling thread, one after the other */
    return c ? 0 : 1;
}

static void counted_close(dyn_sparse_solver *s)
{
    counted *c = s->ctx;
    forgotten += c->forgets;
    closed++;
    free(c);
}

enum { SWEEP_RUNS = 6, SWEEP_COLS = N };

/* rodas4 over d = 30 ... 80 (6 runs) on the ring, every final state, with `threads`
 * threads and the sparse solvers of open/close (NULL: dense matrices). */
static void ring_sweep(const loaded *L, int threads, int (*open)(dyn_sparse_solver *),
                       void (*close)(dyn_sparse_solver *), double *results)
{
    dyn_sweep s = {0};
    const dyn_sweep_var var = {DYN_SWEEP_PARAM, dyn_model_param_index(L->m, "d")};
    double values[SWEEP_RUNS];
    for (int i = 0; i < SWEEP_RUNS; i++)
        values[i] = 30.0 + 10.0 * i;
    dyn_reduce red[SWEEP_COLS];
    int n_red = 0, status[SWEEP_RUNS];
    char err[256];
    assert_int_equal(dyn_reduce_parse(L->m, "final", red, SWEEP_COLS, &n_red, err, sizeof err),
                     0);
    assert_int_equal(n_red, SWEEP_COLS);
    s.model = L->m;
    s.n_vars = 1;
    s.vars = &var;
    s.n_runs = SWEEP_RUNS;
    s.values = values;
    s.method = dyn_method_find("rodas4");
    s.t0 = 0.0;
    s.t1 = 1.0;
    s.rtol = 1e-8;
    s.atol = 1e-10;
    s.n_reduce = n_red;
    s.reduce = red;
    s.threads = threads;
    s.sparse_open = open;
    s.sparse_close = close;
    assert_int_equal(dyn_sweep_run(&s, results, status, err, sizeof err), DYN_OK);
    for (int i = 0; i < SWEEP_RUNS; i++)
        assert_int_equal(status[i], DYN_OK);
}

/* A sweep takes the sparse matrices of a single run: one solver per thread (opened once,
 * closed once, a new solve started in it per run), every run ending within 1e-12 of the
 * dense sweep's, and the same bits on 1 and 2 threads, with this file's solver and with
 * KLU (whose analysis one thread's runs share while each run pivots anew). */
static void test_sweep_sparse(void **state)
{
    (void)state;
    loaded L;
    load(ring_ode, &L);
    const size_t size = (size_t)SWEEP_RUNS * SWEEP_COLS;
    double dense[SWEEP_RUNS * SWEEP_COLS], one[SWEEP_RUNS * SWEEP_COLS];
    double two[SWEEP_RUNS * SWEEP_COLS];
    ring_sweep(&L, 1, NULL, NULL, dense);
    const int threads = dyn_sweep_threads(2); /* 1 without OpenMP */
    for (int t = 1; t <= threads; t++) {
        opened = closed = forgotten = 0;
        ring_sweep(&L, t, counted_open, counted_close, t == 1 ? one : two);
        assert_int_equal(opened, t);
        assert_int_equal(closed, t);
        assert_int_equal(forgotten, SWEEP_RUNS);
    }
    double worst = 0.0;
    for (size_t k = 0; k < size; k++)
        worst = fmax(worst, fabs(one[k] - dense[k]));
    CHECK(worst < 1e-12, "sparse sweep differs from the dense one by %g", worst);
    if (threads > 1)
        assert_memory_equal(one, two, sizeof one);
#ifdef DYNKIT_HAVE_KLU
    ring_sweep(&L, 1, dyn_klu_init, dyn_klu_release, one);
    ring_sweep(&L, threads, dyn_klu_init, dyn_klu_release, two);
    worst = 0.0;
    for (size_t k = 0; k < size; k++)
        worst = fmax(worst, fabs(one[k] - dense[k]));
    CHECK(worst < 1e-12, "KLU sweep differs from the dense one by %g", worst);
    assert_memory_equal(one, two, sizeof one);
#endif
    dyn_jit_unload(&L.jm);
}

/* The last value of the first row after the header of CSV text (the final state's last
 * column). */
static double last_value(const char *out)
{
    const char *row = strchr(out, '\n');
    assert_non_null(row);
    const char *end = strchr(row + 1, '\n');
    const char *p = end ? end : row + strlen(row);
    while (p > row && p[-1] != ',')
        p--;
    return strtod(p, NULL);
}

/* rodas4 over d = 40, 60 in a sweep on 2 threads: its last run's u39(1) is that of the single
 * run with d = 60, to the bit (the options `more` given to both). */
static void sweep_is_run(const char *file, const char *more)
{
    cli_result sw = cli("sweep %s --method rodas4 --vary d=40,60 --reduce final:u39 --threads 2 "
                        "--rtol 1e-9 --atol 1e-12 --quiet%s",
                        cli_path(file), more);
    cli_result one = cli("run %s --method rodas4 --set d=60 --final --rtol 1e-9 --atol 1e-12%s",
                         cli_path(file), more);
    CHECK(sw.status == 0 && one.status == 0, "%s%s", sw.err, one.err);
    const char *last = strrchr(sw.out, ',');
    assert_non_null(last);
    CHECK(strtod(last + 1, NULL) == last_value(one.out), "%s: sweep %s, run %.17g", file,
          last + 1, last_value(one.out));
    cli_free(&sw);
    cli_free(&one);
}

/* dynkit run: the ring with rodas4 and cvode, sparse matrices when built with KLU (else
 * dense, saying why), the chain with the band found in its pattern; u39(1) agrees across
 * them within a few times the tolerance. */
static void test_cli_says_which_matrices(void **state)
{
    (void)state;
    assert_int_equal(cli_write_file("ring.ode", ring_ode), 0);
    assert_int_equal(cli_write_file("chain.ode", chain_ode), 0);
    const int cvode = cli_has_cvode();
    double ref = NAN;
    for (int k = 0; k < 2 + cvode; k++) {
        const char *file = k == 1 ? "chain.ode" : "ring.ode";
        cli_result r = cli("run %s --method %s --final --stats --verbose --rtol 1e-9 "
                           "--atol 1e-12",
                           cli_path(file), k == 2 ? "cvode" : "rodas4");
        CHECK(r.status == 0, "%s: %s", file, r.err);
        if (k == 1) {
            CHECK(strstr(r.err, " linear=band lower=1 upper=1") &&
                      strstr(r.err, "the Jacobian is banded, 1 below and 1 above"),
                  "%s", r.err);
        } else {
#ifdef DYNKIT_HAVE_KLU
            CHECK(strstr(r.err, " linear=sparse nnz=120") &&
                      strstr(r.err, "sparse matrices (KLU): the exact Jacobian has 120 of 1600"),
                  "%s", r.err);
#else
            CHECK(strstr(r.err, " linear=dense") && strstr(r.err, "built without KLU"), "%s",
                  r.err);
#endif
            const double u = last_value(r.out);
            if (k == 0)
                ref = u;
            else
                CHECK(fabs(u - ref) < 1e-8, "cvode %.17g, rodas4 %.17g", u, ref);
        }
        cli_free(&r);
    }
    /* a sweep's run is the single run with the same matrices: the same bits */
    sweep_is_run("ring.ode", "");
    cli_result info = cli("info %s", cli_path("ring.ode"));
    CHECK(info.status == 0 && strstr(info.out, "Jacobian: sparse, 120 of 1600 entries"), "%s%s",
          info.out, info.err);
    cli_free(&info);
    /* a small model keeps dense matrices: 2 states */
    assert_int_equal(cli_write_file("two.ode", "x'=-x+y\ny'=-1000*y\ninit x=1,y=1\ndone\n"), 0);
    cli_result r = cli("run %s --method rodas4 --final --stats --verbose", cli_path("two.ode"));
    CHECK(r.status == 0 && strstr(r.err, " linear=dense") &&
              strstr(r.err, "dense matrices: 2 states"),
          "%s", r.err);
    cli_free(&r);
}

/* The ring as a C model without a Jacobian (40 states; `declared` adds its pattern,
 * dyn_model.jac_pattern, without values). */
static const char ring_c[] =
    "#include <stddef.h>\n"
    "#include <stdio.h>\n"
    "#include <dynkit/model.h>\n"
    "typedef struct par { double d; } par;\n"
    "static int rhs(double t, const double *u, double *f, void *vp) {\n"
    "    const double d = ((const par *)vp)->d; (void)t;\n"
    "    for (int j = 0; j < 40; j++)\n"
    "        f[j] = d * (u[(j + 1) % 40] - 2 * u[j] + u[(j + 39) % 40]) - u[j] * u[j] * u[j];\n"
    "    return 0; }\n"
    "static char names[40][4]; static dyn_var states[40]; static double init[40];\n"
    "static const dyn_param params[] = {{\"d\", \"1\", \"coupling\", offsetof(par, d), 50}};\n"
    "static int colptr[41], rowind[120];\n"
    "static dyn_model model = {.name = \"ring\", .n_states = 40, .states = states, .y0 = init,\n"
    "    .n_params = 1, .params = params, .par_size = sizeof(par), .rhs = rhs, .t1 = 1,\n"
    "    .step = 0.1};\n"
    "const dyn_model *dynkit_model(void) {\n"
    "    for (int j = 0; j < 40; j++) {\n"
    "        snprintf(names[j], 4, \"u%d\", j);\n"
    "        states[j] = (dyn_var){names[j], \"1\", \"\"};\n"
    "        init[j] = __builtin_sin(2 * 3.14159265358979323846 * j / 40) + 0.5;\n"
    "        int r[3] = {(j + 39) % 40, j, (j + 1) % 40}, k = 3 * j;\n"
    "        if (j == 0) r[0] = 0, r[1] = 1, r[2] = 39;\n"
    "        if (j == 39) r[0] = 0, r[1] = 38, r[2] = 39;\n"
    "        colptr[j] = k; rowind[k] = r[0]; rowind[k + 1] = r[1]; rowind[k + 2] = r[2]; }\n"
    "    colptr[40] = 120;\n"
    "    if (DECLARED) model.jac_pattern = (dyn_sparse_pattern){40, 120, colptr, rowind};\n"
    "    return &model; }\n";

/* --jac-pattern: a C model without a Jacobian runs with dense differences (40 calls of f a
 * Jacobian), with a probed pattern or its declared one in 4 groups (4 calls) and KLU, all
 * ending where the model file's exact run ends (within 1e-7); a sweep with the probed
 * pattern writes the single run's numbers; a declared pattern out of order is refused when
 * the model is loaded; a model with its own pattern refuses probe, none gives dense
 * matrices, and a word outside model|probe|none is refused. */
static void test_cli_jac_pattern(void **state)
{
    (void)state;
    char text[sizeof ring_c + 64];
    for (int declared = 0; declared < 2; declared++) {
        snprintf(text, sizeof text, "#define DECLARED %d\n%s", declared, ring_c);
        assert_int_equal(cli_write_file(declared ? "ring_declared.c" : "ring_probe.c", text),
                         0);
    }
    assert_int_equal(cli_write_file("ring.ode", ring_ode), 0);
    const char *tol = "--method rodas4 --final --stats --verbose --rtol 1e-9 --atol 1e-12";
    cli_result exact = cli("run %s %s", cli_path("ring.ode"), tol);
    CHECK(exact.status == 0, "%s", exact.err);
    const double ref = last_value(exact.out);
    cli_free(&exact);
    struct {
        const char *file, *how, *linear, *note;
    } runs[] = {
        {"ring_probe.c", "model", " linear=dense", "gives no sparse pattern"},
        {"ring_probe.c", "probe", " linear=sparse nnz=120", "120 of 1600 entries of the "
                                                           "Jacobian are not zero at 3 points"},
        {"ring_declared.c", "model", " linear=sparse nnz=120", "differences in 4 groups of "
                                                               "columns, 4 calls of f"},
        {"ring_declared.c", "none", " linear=dense", "gives no sparse pattern"},
    };
    for (size_t k = 0; k < sizeof runs / sizeof *runs; k++) {
        cli_result r = cli("run %s %s --jac-pattern %s", cli_path(runs[k].file), tol,
                           runs[k].how);
        CHECK(r.status == 0, "%s %s: %s", runs[k].file, runs[k].how, r.err);
#ifdef DYNKIT_HAVE_KLU
        CHECK(strstr(r.err, runs[k].linear) && strstr(r.err, runs[k].note), "%s %s: %s",
              runs[k].file, runs[k].how, r.err);
#endif
        CHECK(fabs(last_value(r.out) - ref) < 1e-7, "%s %s: u39 %.17g, exact %.17g",
              runs[k].file, runs[k].how, last_value(r.out), ref);
        cli_free(&r);
    }
    /* a sweep takes the probed pattern too: the single run's numbers */
    sweep_is_run("ring_probe.c", " --jac-pattern probe");
    /* the command of docs/stiff.md: the 256-state ring as a C model, 10 groups */
    cli_result big = cli("run %s/bench/cgl_ring.c --method rodas4 --final --stats "
                         "--jac-pattern probe --verbose",
                         DYNKIT_SOURCE_DIR);
    CHECK(big.status == 0, "%s", big.err);
#ifdef DYNKIT_HAVE_KLU
    CHECK(strstr(big.err, "linear=sparse nnz=1536") && strstr(big.err, "in 10 groups"), "%s",
          big.err);
#endif
    cli_free(&big);
    cli_result info = cli("info %s", cli_path("ring_declared.c"));
    CHECK(info.status == 0 && strstr(info.out, "Jacobian: sparse, 120 of 1600 entries (the "
                                               "pattern the model declares"),
          "%s%s", info.out, info.err);
    cli_free(&info);
    /* a model file above 400 states has no exact Jacobian: the probe finds its band */
    char chain[256];
    snprintf(chain, sizeof chain,
             "par d=50\nu0'=d*(u1-2*u0)-u0^3\nu[1..399]'=d*(u[j+1]-2*u[j]+u[j-1])-u[j]^3\n"
             "u400'=d*(-2*u400+u399)-u400^3\ninit u[0..400]=0.5\n@ total=1\ndone\n");
    assert_int_equal(cli_write_file("chain401.ode", chain), 0);
    cli_result band = cli("run %s --method rodas4 --final --stats --verbose --jac-pattern probe",
                          cli_path("chain401.ode"));
    CHECK(band.status == 0 && strstr(band.err, " linear=band lower=1 upper=1") &&
              strstr(band.err, "1201 of 160801 entries") &&
              strstr(band.err, "1 below and 1 above the diagonal (of 401 states), as its "
                               "pattern shows"),
          "%s", band.err);
    cli_free(&band);
    /* a declared pattern the loader refuses: column 0's rows out of order */
    snprintf(text, sizeof text, "#define DECLARED 1\n%s", ring_c);
    char *swap = strstr(text, "r[0] = 0, r[1] = 1");
    assert_non_null(swap);
    swap[7] = '1';
    swap[16] = '0';
    assert_int_equal(cli_write_file("ring_bad.c", text), 0);
    cli_result refused = cli("run %s --method rodas4", cli_path("ring_bad.c"));
    CHECK(refused.status == 2 && strstr(refused.err, "declares a pattern of its Jacobian") &&
              strstr(refused.err, "rows in column 0 must increase"),
          "%s", refused.err);
    cli_free(&refused);
    cli_result own = cli("run %s --method rodas4 --jac-pattern probe", cli_path("ring.ode"));
    CHECK(own.status == 2 && strstr(own.err, "has its own pattern"), "%s", own.err);
    cli_free(&own);
    cli_result none = cli("run %s %s --jac-pattern none", cli_path("ring.ode"), tol);
    CHECK(none.status == 0 && strstr(none.err, " linear=dense"), "%s", none.err);
    cli_free(&none);
    cli_result bad = cli("run %s --jac-pattern guess", cli_path("ring.ode"));
    CHECK(bad.status == 2 && strstr(bad.err, "accepted: model"), "%s", bad.err);
    cli_free(&bad);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ring_pattern_is_the_known_one),
        cmocka_unit_test(test_chain_band_is_found),
        cmocka_unit_test(test_rodas4_sparse_equals_dense),
        cmocka_unit_test(test_without_a_solver_dense),
        cmocka_unit_test(test_cvode_sparse),
        cmocka_unit_test(test_sweep_sparse),
        cmocka_unit_test(test_groups_and_probe),
        cmocka_unit_test(test_cli_jac_pattern),
        cmocka_unit_test(test_cli_says_which_matrices),
    };
    return cmocka_run_group_tests(tests, cli_setup, cli_remove_tmpdir);
}
