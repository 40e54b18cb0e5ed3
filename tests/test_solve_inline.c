/* SPDX-License-Identifier: BSD-3-Clause */
/* The fast path of the embedded pairs (dynkit/solve_inline.h with the generated kernels of
 * dynkit/erk_kernels.h) against the general driver (dyn_solve_general, src/ode/solve.c):
 * dyn_solve_inline (right-hand side inlined) and dyn_solve (the library's fast path, the
 * right-hand side by pointer) must give the general driver's numbers bit for bit — final
 * state, every sample at the requested times (dense output), step, rejection and call
 * counts, h_last, stiffness verdict, messages — for bs23, dp45 and dop853 on van der Pol
 * (mu = 1, [0, 15]) and the Arenstorf orbit (one period; HNW I sec. II.0) at rtol = atol =
 * 1e-3 .. 1e-12, with the automatic and a given first step, a max_step, output at every
 * step, on grids (also one that ends before t1), progress callbacks and cancelling, the
 * stiffness test at every step (on van der Pol with mu = 500), and the failures (too many
 * steps, the right-hand side failing, also in dop853's dense output, a blow-up's step-size
 * underflow); cases it does not take (per-state tolerances) go to the general driver. A sanity fact as well: the error of dp45 on
 * van der Pol falls with the tolerance (the inlined solve is a solve, not a copy of
 * nothing). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "dynkit/dynkit.h"
#include "dynkit/problems.h"
#include "dynkit/solve_inline.h"
#include "ode/solve_general.h"

/* y' = y^2, y(0) = 1: blows up at t = 1; fails (returns 3) once y > 1e3 when asked to */
typedef struct blow_par {
    int fail;
} blow_par;

static int blow_rhs(double t, const double *y, double *f, void *par)
{
    (void)t;
    const blow_par *p = par;
    if (p->fail && y[0] > 1e3)
        return 3;
    f[0] = y[0] * y[0];
    return 0;
}

/* every sample, appended */
typedef struct samples {
    long count;
    double data[4096 * 5];
} samples;

static int keep(long k, double t, const double *y, void *ctx)
{
    samples *s = ctx;
    (void)k;
    if (s->count < 4096) {
        double *row = s->data + s->count * 5;
        row[0] = t;
        for (int i = 0; i < 4; i++)
            row[1 + i] = y[i];
    }
    s->count++;
    return 0;
}

static int keep2(long k, double t, const double *y, void *ctx)
{
    samples *s = ctx;
    (void)k;
    if (s->count < 4096) {
        double *row = s->data + s->count * 5;
        row[0] = t;
        row[1] = y[0];
    }
    s->count++;
    return 0;
}

/* progress: counts its calls, cancels at the call given (0: never) */
typedef struct progress_log {
    long calls, cancel_at;
    double last_t, last_frac;
} progress_log;

static int log_progress(double t, double frac, void *ctx)
{
    progress_log *p = ctx;
    p->calls++;
    p->last_t = t;
    p->last_frac = frac;
    return p->cancel_at > 0 && p->calls == p->cancel_at;
}

static samples sa, sb;

/* Run the general driver and one fast path (fast 0: dyn_solve, 1: dyn_solve_inline) with the
 * same options and compare every number. */
static void same_as_general(const dyn_tableau *m, const dyn_system *sys, double t0, double t1,
                            const double *y0, dyn_solve_opts o, int fast)
{
    const int n = sys->n;
    const size_t nw = dyn_solve_work_size(m, n, &o);
    double *wa = calloc(nw, sizeof *wa), *wb = calloc(nw, sizeof *wb);
    double ya[4] = {0}, yb[4] = {0};
    dyn_result ra, rb;
    memset(&sa, 0, sizeof sa);
    memset(&sb, 0, sizeof sb);
    progress_log pa = {0, 0, 0.0, 0.0}, pb = pa;
    if (o.progress_ctx)
        pa.cancel_at = pb.cancel_at = ((const progress_log *)o.progress_ctx)->cancel_at;
    dyn_solve_opts oa = o, ob = o;
    if (o.output) {
        oa.output_ctx = &sa;
        ob.output_ctx = &sb;
    }
    if (o.progress) {
        oa.progress_ctx = &pa;
        ob.progress_ctx = &pb;
    }
    const int sta = dyn_solve_general(m, sys, t0, t1, y0, ya, wa, &oa, &ra);
    const int stb = fast ? dyn_solve_inline(m, sys, t0, t1, y0, yb, wb, &ob, &rb)
                         : dyn_solve(m, sys, t0, t1, y0, yb, wb, &ob, &rb);
    assert_int_equal(sta, stb);
    assert_memory_equal(ya, yb, (size_t)n * sizeof *ya);
    assert_int_equal(ra.stats.steps, rb.stats.steps);
    assert_int_equal(ra.stats.accepted, rb.stats.accepted);
    assert_int_equal(ra.stats.rejected, rb.stats.rejected);
    assert_int_equal(ra.stats.rhs_calls, rb.stats.rhs_calls);
    assert_int_equal(ra.stats.samples, rb.stats.samples);
    assert_memory_equal(&ra.t, &rb.t, sizeof ra.t);
    assert_memory_equal(&ra.h_last, &rb.h_last, sizeof ra.h_last);
    assert_int_equal(ra.stiff, rb.stiff);
    assert_string_equal(ra.message, rb.message);
    assert_int_equal(ra.rhs_status, rb.rhs_status);
    assert_int_equal(sa.count, sb.count);
    const long kept = sa.count < 4096 ? sa.count : 4096;
    assert_memory_equal(sa.data, sb.data, (size_t)kept * 5 * sizeof(double));
    assert_memory_equal(&ra.stiff_t, &rb.stiff_t, sizeof ra.stiff_t);
    assert_string_equal(ra.stiff_message, rb.stiff_message);
    assert_memory_equal(&ra.fail_t, &rb.fail_t, sizeof ra.fail_t);
    assert_int_equal(ra.fail_index, rb.fail_index);
    assert_int_equal(pa.calls, pb.calls);
    assert_memory_equal(&pa.last_t, &pb.last_t, sizeof pa.last_t);
    assert_memory_equal(&pa.last_frac, &pb.last_frac, sizeof pa.last_frac);
    free(wa);
    free(wb);
}

/* both fast paths against the general driver */
static void same(const dyn_tableau *m, const dyn_system *sys, double t0, double t1,
                 const double *y0, dyn_solve_opts o)
{
    same_as_general(m, sys, t0, t1, y0, o, 0);
    same_as_general(m, sys, t0, t1, y0, o, 1);
}

static const dyn_vanderpol_par vdp_par = {1.0};
static const dyn_arenstorf_par aren_par = {0.012277471};

static void run_tols(const char *method, const dyn_system *sys, double t1, const double *y0,
                     long nsamp)
{
    const dyn_tableau *m = dyn_method_find(method);
    assert_non_null(m);
    double times[64];
    for (long i = 0; i < nsamp; i++)
        times[i] = i == nsamp - 1 ? t1 : t1 * (double)i / (double)(nsamp - 1);
    for (int e = 3; e <= 12; e++) {
        dyn_solve_opts o = {0};
        o.rtol = o.atol = pow(10.0, -e);
        o.out_times = times;
        o.n_out_times = nsamp;
        o.output = sys->n == 2 ? keep2 : keep;
        same(m, sys, 0.0, t1, y0, o);
        /* a grid of samples (out_step), ending on t1 and, with DYN_END_GRID, before it */
        dyn_solve_opts g = {0};
        g.rtol = g.atol = pow(10.0, -e);
        g.out_step = t1 / 37.0;
        g.output = o.output;
        same(m, sys, 0.0, t1, y0, g);
        g.out_step = 0.7;
        g.end = DYN_END_GRID;
        same(m, sys, 0.0, t1, y0, g);
        /* no output, a given first step and a max_step */
        dyn_solve_opts p = {0};
        p.rtol = p.atol = pow(10.0, -e);
        same(m, sys, 0.0, t1, y0, p);
        p.initial_step = 1e-3;
        p.max_step = t1 / 50.0;
        same(m, sys, 0.0, t1, y0, p);
    }
}

static void test_vanderpol_bit_for_bit(void **state)
{
    (void)state;
    const dyn_system sys = {dyn_vanderpol_rhs, 2, (void *)&vdp_par};
    const double y0[2] = {2.0, 0.0};
    run_tols("dp45", &sys, 15.0, y0, 31);
    run_tols("bs23", &sys, 15.0, y0, 31);
    run_tols("dop853", &sys, 15.0, y0, 31);
}

static void test_arenstorf_bit_for_bit(void **state)
{
    (void)state;
    const dyn_system sys = {dyn_arenstorf_rhs, 4, (void *)&aren_par};
    const double y0[4] = {0.994, 0.0, 0.0, DYN_ARENSTORF_Y2DOT0};
    const double T = DYN_ARENSTORF_PERIOD;
    run_tols("dp45", &sys, T, y0, 41);
    run_tols("bs23", &sys, T, y0, 41);
    run_tols("dop853", &sys, T, y0, 41);
}

/* every step, too many steps, a blow-up, a failing right-hand side, progress and
 * cancelling, for one pair */
static void every_step_and_failures(const char *method)
{
    const dyn_system sys = {dyn_vanderpol_rhs, 2, (void *)&vdp_par};
    const double y0[2] = {2.0, 0.0};
    const dyn_tableau *m = dyn_method_find(method);
    assert_non_null(m);
    dyn_solve_opts o = {0};
    o.rtol = o.atol = 1e-6;
    o.output = keep2; /* a sample at every step */
    same(m, &sys, 0.0, 15.0, y0, o);
    dyn_solve_opts lim = {0};
    lim.rtol = lim.atol = 1e-9;
    lim.max_steps = 100;
    same(m, &sys, 0.0, 15.0, y0, lim);
    /* progress every 7 accepted steps; cancelled at its 5th call */
    progress_log plog = {0, 0, 0.0, 0.0};
    dyn_solve_opts pr = o;
    pr.progress = log_progress;
    pr.progress_ctx = &plog;
    pr.progress_steps = 7;
    same(m, &sys, 0.0, 15.0, y0, pr);
    plog.cancel_at = 5;
    same(m, &sys, 0.0, 15.0, y0, pr);
    /* samples on a grid finer than the steps: dense output at every step */
    dyn_solve_opts fine = o;
    fine.out_step = 0.01;
    same(m, &sys, 0.0, 15.0, y0, fine);
    /* a blow-up: step-size underflow; and the right-hand side failing, also in the
     * stiffness test's f(t + h, y_{n+1}) of dop853 when it runs at every step, and in the
     * dense output's extra stages */
    blow_par bp = {0};
    const dyn_system blow = {blow_rhs, 1, &bp};
    const double b0[1] = {1.0};
    dyn_solve_opts ob = {0};
    ob.rtol = ob.atol = 1e-6;
    same(m, &blow, 0.0, 2.0, b0, ob);
    bp.fail = 1;
    same(m, &blow, 0.0, 2.0, b0, ob);
    ob.stiff_check = 1;
    same(m, &blow, 0.0, 2.0, b0, ob);
    ob.stiff_check = 0;
    ob.out_step = 1e-3;
    ob.output = keep2;
    same(m, &blow, 0.0, 2.0, b0, ob);
    /* stiffness: van der Pol with mu = 500, the test at every accepted step */
    static const dyn_vanderpol_par stiff_par = {500.0};
    const dyn_system stiff = {dyn_vanderpol_rhs, 2, (void *)&stiff_par};
    dyn_solve_opts os = {0};
    os.rtol = os.atol = 1e-5;
    os.stiff_check = 1;
    same(m, &stiff, 0.0, 20.0, y0, os);
    os.stiff_check = 0; /* the default schedule */
    same(m, &stiff, 0.0, 200.0, y0, os);
    /* an extreme controller: the step underflows to 0 and 0/0 makes the next one NaN,
     * which both drivers clamp to the largest step */
    dyn_solve_opts ex = {0};
    ex.safety = 5e-324;
    ex.fac_min = 5e-324;
    ex.fac_max = INFINITY;
    ex.max_steps = 50;
    same(m, &sys, 0.0, 2.0, y0, ex);
    /* a beta that makes the controller's exponent <= 0: refused, by both */
    dyn_solve_opts bb = {0};
    bb.beta = 0.5;
    same(m, &sys, 0.0, 2.0, y0, bb);
    {
        double w[256], yb[2];
        dyn_result rb;
        assert_int_equal(dyn_solve(m, &sys, 0.0, 2.0, y0, yb, w, &bb, &rb), DYN_ERR_ARG);
        assert_non_null(strstr(rb.message, "beta 0.5 is not accepted"));
    }
    /* not taken by the fast path: per-state tolerances; still the general driver's results */
    const double rv[2] = {1e-6, 1e-7};
    dyn_solve_opts pv = {0};
    pv.rtolv = rv;
    same(m, &sys, 0.0, 15.0, y0, pv);
}

static void test_every_step_and_failures(void **state)
{
    (void)state;
    every_step_and_failures("bs23");
    every_step_and_failures("dp45");
    every_step_and_failures("dop853");
}

/* dp45 with the stiffness test: it must say stiff on van der Pol with mu = 500 (so that the
 * comparisons above compare a verdict, not two empty ones) */
static void test_stiffness_is_detected(void **state)
{
    (void)state;
    static const dyn_vanderpol_par stiff_par = {500.0};
    const dyn_system stiff = {dyn_vanderpol_rhs, 2, (void *)&stiff_par};
    const double y0[2] = {2.0, 0.0};
    const char *pairs[] = {"dp45", "dop853"};
    for (int i = 0; i < 2; i++) {
        const dyn_tableau *m = dyn_method_find(pairs[i]);
        dyn_solve_opts os = {0};
        os.rtol = os.atol = 1e-5;
        os.stiff_check = 1;
        double *w = calloc(dyn_solve_work_size(m, 2, &os), sizeof *w);
        dyn_result r;
        double y[2];
        assert_int_equal(dyn_solve(m, &stiff, 0.0, 20.0, y0, y, w, &os, &r), DYN_OK);
        assert_int_equal(r.stiff, 1);
        free(w);
    }
}

/* the right-hand side of docs/solvers.md ("Speed"), declared DYN_INLINE_RHS: the library's
 * van der Pol arithmetic, so the inlined solve must give dyn_solve's bits */
DYN_INLINE_RHS int vdp_inline(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    const double mu = *(const double *)par;
    dydt[0] = y[1];
    dydt[1] = mu * (1.0 - y[0] * y[0]) * y[1] - y[0];
    return 0;
}

static void test_inline_rhs_as_documented(void **state)
{
    (void)state;
    double mu = 1.0;
    const dyn_system in = {vdp_inline, 2, &mu};
    const dyn_system lib = {dyn_vanderpol_rhs, 2, (void *)&vdp_par};
    const double y0[2] = {2.0, 0.0};
    const char *pairs[] = {"bs23", "dp45", "dop853"};
    for (int i = 0; i < 3; i++) {
        const dyn_tableau *m = dyn_method_find(pairs[i]);
        dyn_solve_opts o = {0};
        o.rtol = o.atol = 1e-9;
        double *w = calloc(dyn_solve_work_size(m, 2, &o), sizeof *w);
        double ya[2], yb[2];
        dyn_result ra, rb;
        assert_int_equal(dyn_solve_inline(m, &in, 0.0, 15.0, y0, ya, w, &o, &ra), DYN_OK);
        assert_int_equal(dyn_solve(m, &lib, 0.0, 15.0, y0, yb, w, &o, &rb), DYN_OK);
        assert_memory_equal(ya, yb, sizeof ya);
        assert_int_equal(ra.stats.rhs_calls, rb.stats.rhs_calls);
        free(w);
    }
}

/* The error at t = 15 against a tight dop853 solve falls with the tolerance. */
static void test_error_falls(void **state)
{
    (void)state;
    const dyn_system sys = {dyn_vanderpol_rhs, 2, (void *)&vdp_par};
    const double y0[2] = {2.0, 0.0};
    const dyn_tableau *m8 = dyn_method_find("dop853"), *m = dyn_method_find("dp45");
    dyn_solve_opts ro = {0};
    ro.rtol = ro.atol = 1e-13;
    double yref[2], y[2];
    double *w8 = calloc(dyn_solve_work_size(m8, 2, &ro), sizeof *w8);
    assert_int_equal(dyn_solve(m8, &sys, 0.0, 15.0, y0, yref, w8, &ro, NULL), DYN_OK);
    double *w = calloc(dyn_solve_work_size(m, 2, &ro), sizeof *w);
    double prev = INFINITY;
    for (int e = 4; e <= 10; e += 2) {
        dyn_solve_opts o = {0};
        o.rtol = o.atol = pow(10.0, -e);
        assert_int_equal(dyn_solve_inline(m, &sys, 0.0, 15.0, y0, y, w, &o, NULL), DYN_OK);
        const double err = fmax(fabs(y[0] - yref[0]), fabs(y[1] - yref[1]));
        assert_true(err < prev / 10.0);
        prev = err;
    }
    free(w8);
    free(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_vanderpol_bit_for_bit),
        cmocka_unit_test(test_arenstorf_bit_for_bit),
        cmocka_unit_test(test_every_step_and_failures),
        cmocka_unit_test(test_stiffness_is_detected),
        cmocka_unit_test(test_inline_rhs_as_documented),
        cmocka_unit_test(test_error_falls),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
