/* SPDX-License-Identifier: BSD-3-Clause */
/* How solves fail and stop, and the smaller entry points.
 *
 * - Bad arguments are refused with DYN_ERR_ARG and a message, before f is ever called.
 * - A right-hand side that returns non-zero stops the solve with DYN_ERR_RHS, its value,
 *   the failing time, and the last good state (equal to a run that ends at that time).
 * - A state that becomes NaN or Inf (y' = y^2 blowing up; a NaN from f) stops the solve
 *   with DYN_ERR_NONFINITE, the state index and time; the samples before are all finite.
 *   A non-finite initial state is refused. The drivers' test of the state's bits
 *   (dyn_inl_nonfinite) agrees with isfinite on every kind of double, at every position.
 * - The output callback can stop a solve (DYN_STOPPED), the progress callback can cancel it
 *   (DYN_CANCELLED); both leave the state reached.
 * - dyn_rk_step works in place; dyn_integrate fills tout/yout like the homework's
 *   Integrate_ModifiedEuler. */
#include <float.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "dynkit/models.h"
#include "dynkit/ode_inline.h" /* dyn_inl_nonfinite */
#include "test_util.h"

static sample_log logbuf;

/* y' = -y for every component, counting calls. */
static int decay_rhs(double t, const double *y, double *dydt, void *par)
{
    long *calls = par;
    (void)t;
    if (calls)
        ++*calls;
    dydt[0] = -y[0];
    dydt[1] = -2.0 * y[1];
    return 0;
}

/* ---- bad arguments ---- */

/* dyn_fixed_solve from 0 to t1 with every sample recorded in logbuf (set up by the caller). */
static int solve_logged(const dyn_tableau *m, const dyn_system *sys, double t1, double h,
                        const double *y0, double *y, dyn_result *res)
{
    double work[TEST_WORK];
    dyn_fixed_opts opts = {0};
    opts.output = sample_log_output;
    opts.output_ctx = &logbuf;
    return dyn_fixed_solve(m, sys, 0.0, t1, h, y0, y, work, &opts, res);
}

static void check_arg_refused(int rc, const dyn_result *res, long calls, const char *what)
{
    CHECK(rc == DYN_ERR_ARG && res->status == DYN_ERR_ARG, "%s: status %d, expected %d", what, rc,
          DYN_ERR_ARG);
    CHECK(strlen(res->message) > 0, "%s: empty message", what);
    CHECK(calls == 0, "%s: f called %ld times", what, calls);
    assert_int_equal(logbuf.count, 0);
    assert_int_equal(res->stats.steps, 0);
}

static void test_bad_arguments_refused(void **state)
{
    (void)state;
    const dyn_tableau *rk4 = dyn_method_find("rk4");
    long calls = 0;
    double work[TEST_WORK], y[2];
    const double y0[2] = {1.0, 1.0};
    dyn_system sys = {decay_rhs, 2, &calls};
    dyn_fixed_opts opts = {0};
    opts.output = sample_log_output;
    opts.output_ctx = &logbuf;
    dyn_result res;
    sample_log_init(&logbuf, 2);

    int rc = dyn_fixed_solve(NULL, &sys, 0, 1, 0.1, y0, y, work, &opts, &res);
    check_arg_refused(rc, &res, calls, "NULL method");
    assert_non_null(strstr(res.message, "method"));

    rc = dyn_fixed_solve(rk4, NULL, 0, 1, 0.1, y0, y, work, &opts, &res);
    check_arg_refused(rc, &res, calls, "NULL system");

    dyn_system nof = {NULL, 2, &calls};
    rc = dyn_fixed_solve(rk4, &nof, 0, 1, 0.1, y0, y, work, &opts, &res);
    check_arg_refused(rc, &res, calls, "NULL f");
    assert_non_null(strstr(res.message, "right-hand side"));

    for (int n = -1; n <= 0; n++) {
        dyn_system bad_n = {decay_rhs, n, &calls};
        rc = dyn_fixed_solve(rk4, &bad_n, 0, 1, 0.1, y0, y, work, &opts, &res);
        check_arg_refused(rc, &res, calls, "n <= 0");
        assert_non_null(strstr(res.message, "states"));
    }

    rc = dyn_fixed_solve(rk4, &sys, 0, 1, 0.1, NULL, y, work, &opts, &res);
    check_arg_refused(rc, &res, calls, "NULL y0");
    rc = dyn_fixed_solve(rk4, &sys, 0, 1, 0.1, y0, y, NULL, &opts, &res);
    check_arg_refused(rc, &res, calls, "NULL work");

    /* A table of another kind is not run by the fixed-step driver. */
    dyn_tableau other = *rk4;
    other.kind = (dyn_method_kind)1;
    rc = dyn_fixed_solve(&other, &sys, 0, 1, 0.1, y0, y, work, &opts, &res);
    check_arg_refused(rc, &res, calls, "kind");

    /* res may be NULL: the status is still returned. */
    assert_int_equal(dyn_fixed_solve(NULL, &sys, 0, 1, 0.1, y0, y, work, NULL, NULL), DYN_ERR_ARG);
    assert_int_equal(dyn_fixed_solve(rk4, &sys, 0, 1, -0.1, y0, y, work, NULL, NULL), DYN_ERR_ARG);
    assert_int_equal(calls, 0);
    /* Workspace size: (stages + 3) * n, and 0 for nonsense. */
    assert_int_equal(dyn_fixed_work_size(rk4, 2), 14);
    assert_int_equal(dyn_fixed_work_size(rk4, 0), 0);
    assert_int_equal(dyn_fixed_work_size(NULL, 2), 0);
}

/* ---- the right-hand side fails ---- */

/* y' = -y, y2' = -2 y2, but f returns 7 at t >= 0.5. */
static int failing_rhs(double t, const double *y, double *dydt, void *par)
{
    long *calls = par;
    ++*calls;
    if (t >= 0.5)
        return 7;
    dydt[0] = -y[0];
    dydt[1] = -2.0 * y[1];
    return 0;
}

static void test_rhs_failure_stops_with_last_good_state(void **state)
{
    (void)state;
    for (int i = 0; i < dyn_method_count(); i++) {
        const dyn_tableau *m = fixed_method_at(i);
        if (!m)
            continue;
        const double h = 0.1, y0[2] = {1.0, 1.0};
        /* Where it must fail: the first step with a stage time t_n + c_i h >= 0.5. */
        dyn_grid g;
        assert_int_equal(dyn_grid_plan(0.0, 1.0, h, DYN_END_EXACT, &g, NULL, 0), DYN_OK);
        long fail_step = -1;
        int fail_stage = -1;
        for (long n = 0; n < g.samples - 1 && fail_step < 0; n++)
            for (int s = 0; s < m->stages && fail_step < 0; s++)
                if (dyn_grid_time(&g, n) + m->c[s] * h >= 0.5)
                    fail_step = n, fail_stage = s;
        const double t_good = dyn_grid_time(&g, fail_step);

        long calls = 0;
        double work[TEST_WORK], y[2];
        dyn_system sys = {failing_rhs, 2, &calls};
        sample_log_init(&logbuf, 2);
        dyn_result res;
        int rc = solve_logged(m, &sys, 1.0, h, y0, y, &res);
        CHECK(rc == DYN_ERR_RHS && res.status == DYN_ERR_RHS, "%s: status %d", m->name, rc);
        assert_int_equal(res.rhs_status, 7);
        CHECK(res.fail_t == dyn_grid_time(&g, fail_step) + m->c[fail_stage] * h,
              "%s: fail_t %.17g", m->name, res.fail_t);
        assert_true(res.fail_t >= 0.5);
        CHECK(res.t == t_good, "%s: res.t = %.17g, expected %.17g", m->name, res.t, t_good);
        assert_int_equal(res.stats.steps, fail_step);
        assert_int_equal(res.stats.rhs_calls, fail_step * m->stages + fail_stage + 1);
        assert_int_equal(calls, res.stats.rhs_calls);
        assert_true(strlen(res.message) > 0);
        assert_non_null(strstr(res.message, "7"));
        /* Samples up to the last good time were all delivered, none after. */
        assert_int_equal(logbuf.count, fail_step + 1);
        assert_true(logbuf.t[logbuf.count - 1] == t_good);

        /* y is the last good state: the same as a run that ends at t_good. */
        double y_ref[2];
        long ref_calls = 0;
        dyn_system ref = {decay_rhs, 2, &ref_calls};
        assert_int_equal(dyn_fixed_solve(m, &ref, 0.0, t_good, h, y0, y_ref, work, NULL, &res),
                         DYN_OK);
        CHECK(same_bits(y[0], y_ref[0]) && same_bits(y[1], y_ref[1]),
              "%s: state after failure (%.17g, %.17g), run to %.17g gives (%.17g, %.17g)",
              m->name, y[0], y[1], t_good, y_ref[0], y_ref[1]);
        assert_memory_equal(y, logbuf.y[logbuf.count - 1], sizeof y);
    }
}

/* Failing at the very first evaluation: nothing but the initial sample, y = y0. */
static void test_rhs_failure_at_start(void **state)
{
    (void)state;
    long calls = 0;
    double work[TEST_WORK], y[2];
    const double y0[2] = {3.0, 4.0};
    dyn_system sys = {failing_rhs, 2, &calls};
    dyn_result res;
    assert_int_equal(dyn_fixed_solve(dyn_method_find("heun"), &sys, 0.5, 1.0, 0.1, y0, y, work,
                                     NULL, &res),
                     DYN_ERR_RHS);
    assert_true(res.t == 0.5 && res.fail_t == 0.5);
    assert_int_equal(res.stats.steps, 0);
    assert_int_equal(res.stats.rhs_calls, 1);
    assert_true(y[0] == 3.0 && y[1] == 4.0);
}

/* ---- states that become NaN or Inf ---- */

/* y' = y^2: y = 1/(1 - t) blows up at t = 1. */
static int square_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)t, (void)par;
    dydt[0] = y[0] * y[0];
    return 0;
}

static void check_samples_finite(const char *what)
{
    for (long i = 0; i < logbuf.count; i++)
        for (int q = 0; q < logbuf.n; q++)
            CHECK(isfinite(logbuf.y[i][q]), "%s: sample %ld state %d = %g", what, i, q,
                  logbuf.y[i][q]);
}

static void test_blow_up_stops_nonfinite(void **state)
{
    (void)state;
    const double h = 0.01, y0[1] = {1.0};
    double y[1];
    dyn_system sys = {square_rhs, 1, NULL};
    sample_log_init(&logbuf, 1);
    dyn_result res;
    int rc = solve_logged(dyn_method_find("euler"), &sys, 2.0, h, y0, y, &res);
    CHECK(rc == DYN_ERR_NONFINITE, "status %d (%s), y = %g", rc, res.message, y[0]);
    assert_int_equal(res.fail_index, 0);
    /* Euler lags the exact blow-up at t = 1 (its growth y + h y^2 is slower than 1/(1-t)). */
    CHECK(res.fail_t > 1.0 && res.fail_t < 1.5, "fail_t = %.17g", res.fail_t);
    assert_true(isfinite(y[0]) && y[0] > 1e100);
    /* The failing state is at the next grid time, the last good one just before. */
    long k_fail = (long)nearbyint(res.fail_t / h);
    assert_true(same_bits(res.fail_t, (double)k_fail * h));
    assert_true(same_bits(res.t, (double)(k_fail - 1) * h));
    assert_int_equal(logbuf.count, k_fail);
    check_samples_finite("y' = y^2");
    assert_true(same_bits(logbuf.y[logbuf.count - 1][0], y[0]));
    assert_non_null(strstr(res.message, "finite"));
    /* Until the blow-up, Euler stays below the exact solution 1/(1 - t). */
    for (long i = 1; i < logbuf.count && logbuf.t[i] < 0.99; i++)
        assert_true(logbuf.y[i][0] < 1.0 / (1.0 - logbuf.t[i]));
}

/* y1' = -y1; y2' = -y2 but NaN from t >= 0.3. */
static int nan_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)par;
    dydt[0] = -y[0];
    dydt[1] = t >= 0.3 ? NAN : -y[1];
    return 0;
}

static void test_nan_from_rhs_stops_nonfinite(void **state)
{
    (void)state;
    const double h = 0.1, y0[2] = {1.0, 1.0};
    double work[TEST_WORK], y[2];
    dyn_system sys = {nan_rhs, 2, NULL};
    dyn_fixed_opts opts = {0};
    opts.output = sample_log_output;
    opts.output_ctx = &logbuf;
    sample_log_init(&logbuf, 2);
    dyn_result res;
    int rc = dyn_fixed_solve(dyn_method_find("euler"), &sys, 0.0, 1.0, h, y0, y, work, &opts, &res);
    assert_int_equal(rc, DYN_ERR_NONFINITE);
    assert_int_equal(res.fail_index, 1);
    /* 3*0.1 = 0.30000000000000004 >= 0.3: the step from there makes y2 NaN at t = 0.4. */
    assert_true(same_bits(res.fail_t, 4.0 * 0.1));
    assert_true(same_bits(res.t, 3.0 * 0.1));
    assert_int_equal(logbuf.count, 4);
    check_samples_finite("NaN from f");
    assert_true(isfinite(y[0]) && isfinite(y[1]));
    assert_true(y[1] == logbuf.y[3][1]);

    /* no_finite_check: the solve runs through and returns the NaN. */
    opts.no_finite_check = 1;
    sample_log_init(&logbuf, 2);
    rc = dyn_fixed_solve(dyn_method_find("euler"), &sys, 0.0, 1.0, h, y0, y, work, &opts, &res);
    assert_int_equal(rc, DYN_OK);
    assert_int_equal(logbuf.count, 11);
    assert_true(isnan(y[1]) && isfinite(y[0]));
}

/* The counters after a failure say how far the solve got, the same way for both kinds of
 * failure: steps counts the steps whose result was kept (res.t is the time of sample
 * `steps`, the output saw steps + 1 samples), rhs_calls every evaluation, including those
 * of the failed step. DYN_ERR_RHS does this; DYN_ERR_NONFINITE must too. */
static void test_counters_after_failure_are_consistent(void **state)
{
    (void)state;
    const double h = 0.1, y0[2] = {1.0, 1.0};
    for (int i = 0; i < dyn_method_count(); i++) {
        const dyn_tableau *m = fixed_method_at(i);
        if (!m)
            continue;
        double work[TEST_WORK], y[2];
        dyn_fixed_opts opts = {0};
        opts.output = sample_log_output;
        opts.output_ctx = &logbuf;
        dyn_result res;
        dyn_grid g;
        assert_int_equal(dyn_grid_plan(0.0, 1.0, h, DYN_END_EXACT, &g, NULL, 0), DYN_OK);

        long calls = 0;
        dyn_system fails = {failing_rhs, 2, &calls};
        sample_log_init(&logbuf, 2);
        assert_int_equal(dyn_fixed_solve(m, &fails, 0.0, 1.0, h, y0, y, work, &opts, &res),
                         DYN_ERR_RHS);
        CHECK(res.stats.steps == logbuf.count - 1 && res.t == dyn_grid_time(&g, res.stats.steps),
              "%s, DYN_ERR_RHS: steps %ld, samples %ld, t %.17g", m->name, res.stats.steps,
              logbuf.count, res.t);

        dyn_system nans = {nan_rhs, 2, NULL};
        sample_log_init(&logbuf, 2);
        assert_int_equal(dyn_fixed_solve(m, &nans, 0.0, 1.0, h, y0, y, work, &opts, &res),
                         DYN_ERR_NONFINITE);
        CHECK(res.stats.steps == logbuf.count - 1 && res.t == dyn_grid_time(&g, res.stats.steps),
              "%s, DYN_ERR_NONFINITE: steps %ld, but %ld samples delivered and the state is at "
              "t = %.17g (sample %ld)",
              m->name, res.stats.steps, logbuf.count, res.t, logbuf.count - 1);
        CHECK(res.stats.rhs_calls == (long)m->stages * (res.stats.steps + 1),
              "%s, DYN_ERR_NONFINITE: %ld rhs calls for %ld kept steps and one failed", m->name,
              res.stats.rhs_calls, res.stats.steps);
    }
}

static void test_nonfinite_initial_state_refused(void **state)
{
    (void)state;
    const double bad[][2] = {{1.0, NAN}, {INFINITY, 0.0}, {0.0, -INFINITY}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        long calls = 0;
        double y[2];
        dyn_system sys = {decay_rhs, 2, &calls};
        sample_log_init(&logbuf, 2);
        dyn_result res;
        int rc = solve_logged(dyn_method_find("rk4"), &sys, 1.0, 0.1, bad[i], y, &res);
        CHECK(rc == DYN_ERR_NONFINITE, "initial (%g, %g): status %d", bad[i][0], bad[i][1], rc);
        assert_int_equal(res.fail_index, isfinite(bad[i][0]) ? 1 : 0);
        assert_true(res.fail_t == 0.0);
        assert_true(strlen(res.message) > 0);
        assert_int_equal(calls, 0);
        assert_int_equal(logbuf.count, 0);
    }
}

/* ---- callbacks stop and cancel ---- */

static void test_output_callback_stops(void **state)
{
    (void)state;
    const double h = 0.1, y0[2] = {1.0, 1.0};
    for (long stop_at = 0; stop_at <= 3; stop_at += 3) {
        long calls = 0;
        double y[2];
        dyn_system sys = {decay_rhs, 2, &calls};
        sample_log_init(&logbuf, 2);
        logbuf.stop_at = stop_at;
        dyn_result res;
        int rc = solve_logged(dyn_method_find("rk4"), &sys, 1.0, h, y0, y, &res);
        assert_int_equal(rc, DYN_STOPPED);
        assert_true(strlen(res.message) > 0);
        assert_int_equal(logbuf.count, stop_at + 1);
        assert_int_equal(res.stats.steps, stop_at);
        assert_int_equal(calls, 4 * stop_at); /* no step after the stop */
        assert_true(same_bits(res.t, logbuf.t[stop_at]));
        assert_memory_equal(y, logbuf.y[stop_at], sizeof y);
    }
}

typedef struct progress_log {
    long calls;
    long cancel_at; /* cancel on this call (1-based), 0 = never */
    double t[64], fraction[64];
} progress_log;

static int on_progress(double t, double fraction, void *ctx)
{
    progress_log *p = ctx;
    if (p->calls < 64) {
        p->t[p->calls] = t;
        p->fraction[p->calls] = fraction;
    }
    p->calls++;
    return p->calls == p->cancel_at;
}

static void test_progress_reports_and_cancels(void **state)
{
    (void)state;
    const double y0[2] = {1.0, 1.0};
    long calls = 0;
    double work[TEST_WORK], y[2];
    dyn_system sys = {decay_rhs, 2, &calls};
    dyn_result res;

    /* 10 steps, progress every 3: at steps 3, 6, 9 with fractions 0.3, 0.6, 0.9. */
    progress_log p = {0};
    dyn_fixed_opts opts = {0};
    opts.progress = on_progress;
    opts.progress_ctx = &p;
    opts.progress_steps = 3;
    assert_int_equal(dyn_fixed_solve(dyn_method_find("heun"), &sys, 0.0, 1.0, 0.1, y0, y, work,
                                     &opts, &res),
                     DYN_OK);
    assert_int_equal(p.calls, 3);
    for (int i = 0; i < 3; i++) {
        assert_true(fabs(p.fraction[i] - 0.3 * (i + 1)) < 1e-15);
        assert_true(same_bits(p.t[i], (double)(3 * (i + 1)) * 0.1));
    }

    /* Cancel on the second report: stopped after 6 steps, y is the state at t(6). */
    progress_log c = {0};
    c.cancel_at = 2;
    opts.progress_ctx = &c;
    opts.output = sample_log_output;
    opts.output_ctx = &logbuf;
    sample_log_init(&logbuf, 2);
    calls = 0;
    assert_int_equal(dyn_fixed_solve(dyn_method_find("heun"), &sys, 0.0, 1.0, 0.1, y0, y, work,
                                     &opts, &res),
                     DYN_CANCELLED);
    assert_true(strlen(res.message) > 0);
    assert_int_equal(res.stats.steps, 6);
    assert_int_equal(calls, 12);
    assert_true(same_bits(res.t, 6.0 * 0.1));
    assert_int_equal(logbuf.count, 7);
    assert_memory_equal(y, logbuf.y[6], sizeof y);

    /* Default interval (65536 steps): a short solve never reports. */
    progress_log d = {0};
    opts.progress_ctx = &d;
    opts.progress_steps = 0;
    opts.output = NULL;
    assert_int_equal(dyn_fixed_solve(dyn_method_find("heun"), &sys, 0.0, 1.0, 0.001, y0, y, work,
                                     &opts, &res),
                     DYN_OK);
    assert_int_equal(d.calls, 0);
}

/* ---- dyn_rk_step ---- */

static void test_rk_step_in_place(void **state)
{
    (void)state;
    for (int i = 0; i < dyn_method_count(); i++) {
        const dyn_tableau *m = fixed_method_at(i);
        if (!m)
            continue;
        dyn_vanderpol_par par = {.mu = 1.0};
        dyn_system sys = {dyn_vanderpol_rhs, 2, &par};
        double work[TEST_WORK], y0[2] = {2.0, 0.0}, y1[2], y[2] = {2.0, 0.0};
        long calls = 0;
        assert_int_equal(dyn_rk_step(m, &sys, 0.0, 0.01, y0, y1, work, &calls), 0);
        assert_int_equal(calls, m->stages);
        assert_int_equal(dyn_rk_step(m, &sys, 0.0, 0.01, y, y, work, &calls), 0);
        assert_int_equal(calls, 2 * m->stages);
        assert_memory_equal(y, y1, sizeof y);
        assert_true(y0[0] == 2.0 && y0[1] == 0.0); /* input untouched */
        assert_int_equal(dyn_rk_step(m, &sys, 0.0, 0.01, y, y, work, NULL), 0);
        /* One step equals one step of the driver. */
        dyn_result res;
        double yd[2];
        assert_int_equal(dyn_fixed_solve(m, &sys, 0.0, 0.01, 0.01, y0, yd, work, NULL, &res),
                         DYN_OK);
        assert_memory_equal(yd, y1, sizeof yd);
    }
    /* A failing f: its status comes back, y1 is left alone, calls count the failing one. */
    long calls = 0, fcalls = 0;
    dyn_system bad = {failing_rhs, 2, &fcalls};
    double work[TEST_WORK], y0[2] = {1.0, 1.0}, y1[2] = {-5.0, -5.0};
    assert_int_equal(dyn_rk_step(dyn_method_find("rk4"), &bad, 0.4, 0.1, y0, y1, work, &calls), 7);
    assert_int_equal(calls, 4); /* stages at 0.4, 0.45, 0.45, then 0.5 fails */
    assert_int_equal(dyn_rk_step(dyn_method_find("rk4"), &bad, 0.45, 0.1, y0, y1, work, &calls),
                     7);
    assert_int_equal(calls, 4 + 2); /* 0.45, then 0.5 fails */
    assert_true(y1[0] == -5.0 && y1[1] == -5.0);
}

/* ---- dyn_integrate: the homework's [tout, yout] = Integrate_X(...) ---- */

#define VDP_SAMPLES 1501
static double tout[VDP_SAMPLES], yout[VDP_SAMPLES * 2];
static double hand_t[VDP_SAMPLES], hand_y[VDP_SAMPLES * 2];

/* Integrate_ModifiedEuler.m of the homework, line by line (tout = (0:Ts:15)'). */
static void homework_modified_euler(double Ts, const double *y0, double mu)
{
    double y_n[2] = {y0[0], y0[1]}, dy_n[2], ytilde[2], dytilde[2];
    for (int n = 0; n < VDP_SAMPLES; n++) {
        double t_n = (n == VDP_SAMPLES - 1) ? 15.0 : (double)n * Ts;
        hand_t[n] = t_n;
        hand_y[2 * n] = y_n[0];
        hand_y[2 * n + 1] = y_n[1];
        if (n == VDP_SAMPLES - 1)
            break; /* the homework computes one more step and discards it */
        dy_n[0] = y_n[1];
        dy_n[1] = mu * (1.0 - y_n[0] * y_n[0]) * y_n[1] - y_n[0];
        for (int q = 0; q < 2; q++)
            ytilde[q] = y_n[q] + Ts * dy_n[q];
        dytilde[0] = ytilde[1];
        dytilde[1] = mu * (1.0 - ytilde[0] * ytilde[0]) * ytilde[1] - ytilde[0];
        for (int q = 0; q < 2; q++)
            y_n[q] = y_n[q] + .5 * Ts * (dytilde[q] + dy_n[q]);
    }
}

static void test_integrate_like_homework(void **state)
{
    (void)state;
    dyn_vanderpol_par par = {.mu = 1.0};
    const double tspan[2] = {0.0, 15.0}, y0[2] = {2.0, 0.0};
    double work[TEST_WORK];
    dyn_result res;
    int rc = dyn_integrate(dyn_method_find("modified-euler"), dyn_vanderpol_rhs, tspan, 0.01, y0,
                           2, &par, tout, yout, work, &res);
    assert_int_equal(rc, DYN_OK);
    assert_int_equal(res.stats.samples, VDP_SAMPLES);
    homework_modified_euler(0.01, y0, 1.0);
    for (int n = 0; n < VDP_SAMPLES; n++) {
        CHECK(same_bits(tout[n], hand_t[n]), "tout[%d] = %.17g, expected %.17g", n, tout[n],
              hand_t[n]);
        CHECK(same_bits(yout[2 * n], hand_y[2 * n]) && same_bits(yout[2 * n + 1], hand_y[2 * n + 1]),
              "row %d: (%.17g, %.17g), homework loop (%.17g, %.17g)", n, yout[2 * n],
              yout[2 * n + 1], hand_y[2 * n], hand_y[2 * n + 1]);
    }
    assert_true(tout[VDP_SAMPLES - 1] == 15.0);
    /* Answer to homework problem 2 for modified Euler, y(15) = (0.8300, -1.3138). */
    assert_true(fabs(yout[2 * 1500] - 0.8300) < 5e-4);
    assert_true(fabs(yout[2 * 1500 + 1] - (-1.3138)) < 5e-4);

    /* NULL outputs are refused. */
    assert_int_equal(dyn_integrate(dyn_method_find("rk4"), dyn_vanderpol_rhs, tspan, 0.01, y0, 2,
                                   &par, NULL, yout, work, &res),
                     DYN_ERR_ARG);
    assert_true(strlen(res.message) > 0);
    assert_int_equal(dyn_integrate(dyn_method_find("rk4"), dyn_vanderpol_rhs, NULL, 0.01, y0, 2,
                                   &par, tout, yout, work, &res),
                     DYN_ERR_ARG);
    assert_int_equal(dyn_integrate(dyn_method_find("rk4"), dyn_vanderpol_rhs, tspan, 0.01, y0, 0,
                                   &par, tout, yout, work, &res),
                     DYN_ERR_ARG);
}

/* On failure the rows up to the last good sample are filled, the rest untouched. */
static void test_integrate_partial_rows_on_failure(void **state)
{
    (void)state;
    const double tspan[2] = {0.0, 1.0}, y0[2] = {1.0, 1.0};
    double t[11], Y[22], work[TEST_WORK];
    for (int i = 0; i < 11; i++)
        t[i] = Y[2 * i] = Y[2 * i + 1] = -99.0;
    dyn_result res;
    int rc = dyn_integrate(dyn_method_find("euler"), nan_rhs, tspan, 0.1, y0, 2, NULL, t, Y, work,
                           &res);
    assert_int_equal(rc, DYN_ERR_NONFINITE);
    for (int i = 0; i < 11; i++) {
        if (i <= 3) {
            assert_true(same_bits(t[i], (double)i * 0.1));
            assert_true(isfinite(Y[2 * i]) && isfinite(Y[2 * i + 1]) && Y[2 * i] > 0.0);
        } else {
            assert_true(t[i] == -99.0 && Y[2 * i] == -99.0 && Y[2 * i + 1] == -99.0);
        }
    }
}

static void test_status_names(void **state)
{
    (void)state;
    const int all[] = {DYN_OK,        DYN_ERR_ARG, DYN_ERR_RHS,  DYN_ERR_NONFINITE,
                       DYN_STOPPED,   DYN_ERR_IO,  DYN_CANCELLED};
    const int count = (int)(sizeof all / sizeof all[0]);
    for (int i = 0; i < count; i++) {
        const char *name = dyn_status_name(all[i]);
        assert_non_null(name);
        assert_true(strlen(name) > 0);
        for (int j = 0; j < i; j++)
            assert_string_not_equal(name, dyn_status_name(all[j]));
    }
    assert_string_equal(dyn_status_name(DYN_OK), "ok");
    assert_non_null(dyn_status_name(12345));
    assert_non_null(dyn_status_name(-1));
}

/* dyn_inl_nonfinite, the drivers' test of each new state, against isfinite: every kind of
 * double (zeros, subnormals, the extremes, infinities, NaNs of either sign and payload) at
 * every position of vectors of 1 to 13 otherwise finite states. */
static void test_nonfinite_bits_agree_with_isfinite(void **state)
{
    (void)state;
    const uint64_t nan_bits[] = {0x7ff8000000000000ULL, 0xfff8000000000000ULL,
                                 0x7ff0000000000001ULL, 0x7fffffffffffffffULL};
    double kinds[16] = {0.0, -0.0, 1.0, -2.5, DBL_MIN, DBL_MIN / 8.0, -4.9e-324, DBL_MAX,
                        -DBL_MAX, 1e308, INFINITY, -INFINITY};
    int nk = 12;
    for (size_t i = 0; i < sizeof nan_bits / sizeof nan_bits[0]; i++)
        memcpy(&kinds[nk++], &nan_bits[i], sizeof(double));
    for (int n = 1; n <= 13; n++)
        for (int pos = 0; pos < n; pos++)
            for (int kind = 0; kind < nk; kind++) {
                double x[13];
                for (int q = 0; q < n; q++)
                    x[q] = (q % 2 ? -1.0 : 1.0) * DBL_MAX / (double)(q + 1);
                x[pos] = kinds[kind];
                CHECK(dyn_inl_nonfinite(n, x) == !isfinite(kinds[kind]),
                      "n = %d, position %d, value %g: %d", n, pos, kinds[kind],
                      dyn_inl_nonfinite(n, x));
            }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_arguments_refused),
        cmocka_unit_test(test_rhs_failure_stops_with_last_good_state),
        cmocka_unit_test(test_rhs_failure_at_start),
        cmocka_unit_test(test_blow_up_stops_nonfinite),
        cmocka_unit_test(test_nan_from_rhs_stops_nonfinite),
        cmocka_unit_test(test_counters_after_failure_are_consistent),
        cmocka_unit_test(test_nonfinite_initial_state_refused),
        cmocka_unit_test(test_nonfinite_bits_agree_with_isfinite),
        cmocka_unit_test(test_output_callback_stops),
        cmocka_unit_test(test_progress_reports_and_cancels),
        cmocka_unit_test(test_rk_step_in_place),
        cmocka_unit_test(test_integrate_like_homework),
        cmocka_unit_test(test_integrate_partial_rows_on_failure),
        cmocka_unit_test(test_status_names),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
