/* SPDX-License-Identifier: BSD-3-Clause */
/* The discrete map ("discrete", DYN_KIND_MAP): dyn_fixed_solve iterates
 * y_{k+1} = f(t_k, y_k) on the grid t_k = t0 + k h, as XPPAUT iterates difference equations.
 *
 * - The iterates are f's values bit for bit: halving gives 2^-k exactly, and the logistic
 *   map (chaotic at r = 4 - 1e-9, so one rounding apart would show within a few dozen
 *   steps) equals a plain C loop over 10^4 steps; f sees t_k.
 * - The samples follow dyn_fixed_solve's contract: every K-th and the last, counters.
 * - Failures: a state that becomes Inf (1/x from 0) stops the run at that step's time
 *   with the last good state; a failing f; no_finite_check goes on.
 * - A span that is not a whole number of steps is refused (DYN_END_GRID stops before it);
 *   dyn_solve refuses the map (events and resets need an integrator); dyn_fixed_solve_inline
 *   hands it to dyn_fixed_solve.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "dynkit/ode_inline.h"
#include "dynkit/solve.h"
#include "test_util.h"

static int halve(double t, const double *y, double *next, void *par)
{
    (void)t;
    (void)par;
    next[0] = 0.5 * y[0];
    next[1] = t; /* the time of the step's start */
    return 0;
}

static int logistic(double t, const double *y, double *next, void *par)
{
    (void)t;
    const double r = *(const double *)par;
    next[0] = r * y[0] * (1.0 - y[0]);
    return 0;
}

static int reciprocal(double t, const double *y, double *next, void *par)
{
    (void)t;
    (void)par;
    next[0] = 1.0 / y[0] - 1.0; /* 1 -> 0 -> inf */
    return 0;
}

static int fails_at_3(double t, const double *y, double *next, void *par)
{
    (void)par;
    next[0] = y[0] + 1.0;
    return t >= 3.0 ? 7 : 0;
}

static const dyn_tableau *map_method(void)
{
    const dyn_tableau *m = dyn_method_find("discrete");
    assert_non_null(m);
    assert_ptr_equal(dyn_method_find("map"), m);
    assert_true(dyn_method_is_map(m) && !dyn_method_is_adaptive(m) && !dyn_method_is_stiff(m));
    return m;
}

static void test_iterates_are_the_maps_values(void **state)
{
    (void)state;
    const dyn_tableau *m = map_method();
    double work[TEST_WORK], y[2];
    dyn_system sys = {halve, 2, NULL};
    const double y0[2] = {1.0, -1.0};
    static sample_log log;
    sample_log_init(&log, 2);
    dyn_fixed_opts o = {0};
    o.output = sample_log_output;
    o.output_ctx = &log;
    dyn_result res;
    assert_int_equal(dyn_fixed_solve(m, &sys, 0.0, 60.0, 1.0, y0, y, work, &o, &res), DYN_OK);
    assert_int_equal(log.count, 61);
    for (int k = 0; k <= 60; k++) {
        CHECK(same_bits(log.y[k][0], ldexp(1.0, -k)) && log.t[k] == (double)k &&
                  (k == 0 || log.y[k][1] == (double)(k - 1)),
              "sample %d: t = %g, x = %a, y = %g", k, log.t[k], log.y[k][0], log.y[k][1]);
    }
    assert_int_equal(res.stats.steps, 60);
    assert_int_equal(res.stats.accepted, 60);
    assert_int_equal(res.stats.rhs_calls, 60);
    assert_int_equal(res.stats.samples, 61);
    assert_true(res.t == 60.0 && same_bits(y[0], ldexp(1.0, -60)));

    /* the logistic map against a plain loop, 10^4 steps, with a step of 0.5 */
    double r = 4.0 - 1e-9, x = 0.3;
    const double x0 = x;
    for (int k = 0; k < 10000; k++)
        x = r * x * (1.0 - x);
    dyn_system lsys = {logistic, 1, &r};
    double yl;
    assert_int_equal(dyn_fixed_solve(m, &lsys, 0.0, 5000.0, 0.5, &x0, &yl, work, NULL, &res),
                     DYN_OK);
    CHECK(same_bits(yl, x) && res.stats.steps == 10000 && res.t == 5000.0,
          "logistic map: %a after %ld steps, the plain loop %a", yl, res.stats.steps, x);
}

static void test_samples_every_k_and_the_last(void **state)
{
    (void)state;
    const dyn_tableau *m = map_method();
    double work[TEST_WORK], y[2];
    dyn_system sys = {halve, 2, NULL};
    const double y0[2] = {1.0, 0.0};
    static sample_log log;
    sample_log_init(&log, 2);
    dyn_fixed_opts o = {0};
    o.output = sample_log_output;
    o.output_ctx = &log;
    o.every = 4;
    dyn_result res;
    assert_int_equal(dyn_fixed_solve(m, &sys, 0.0, 10.0, 1.0, y0, y, work, &o, &res), DYN_OK);
    /* 0, 4, 8 and the last, 10 */
    assert_int_equal(log.count, 4);
    assert_true(log.k[1] == 4 && log.k[2] == 8 && log.k[3] == 10 && log.t[3] == 10.0);
    assert_int_equal(res.stats.samples, 4);
    /* the output callback stops the run */
    sample_log_init(&log, 2);
    log.stop_at = 3;
    o.every = 1;
    assert_int_equal(dyn_fixed_solve(m, &sys, 0.0, 10.0, 1.0, y0, y, work, &o, &res),
                     DYN_STOPPED);
    assert_true(res.t == 3.0 && res.stats.steps == 3 && same_bits(y[0], 0.125));
}

static void test_failures_keep_the_last_good_state(void **state)
{
    (void)state;
    const dyn_tableau *m = map_method();
    double work[TEST_WORK], y;
    const double one = 1.0;
    dyn_system sys = {reciprocal, 1, NULL};
    dyn_result res;
    assert_int_equal(dyn_fixed_solve(m, &sys, 0.0, 5.0, 1.0, &one, &y, work, NULL, &res),
                     DYN_ERR_NONFINITE);
    CHECK(res.fail_t == 2.0 && res.fail_index == 0 && y == 0.0 && res.t == 1.0 &&
              res.stats.rhs_calls == 2 && res.stats.steps == 1,
          "fail_t %g index %d y %g t %g calls %ld: %s", res.fail_t, res.fail_index, y, res.t,
          res.stats.rhs_calls, res.message);
    assert_non_null(strstr(res.message, "state 0 became not finite at t = 2"));
    /* no_finite_check: on through inf (1/inf - 1 = -1, then -2, ...) */
    dyn_fixed_opts o = {0};
    o.no_finite_check = 1;
    assert_int_equal(dyn_fixed_solve(m, &sys, 0.0, 5.0, 1.0, &one, &y, work, &o, &res), DYN_OK);
    assert_true(res.t == 5.0 && y == -1.5);
    /* f fails at t = 3: the state of t = 3 is kept */
    const double zero = 0.0;
    sys.f = fails_at_3;
    assert_int_equal(dyn_fixed_solve(m, &sys, 0.0, 5.0, 1.0, &zero, &y, work, NULL, &res),
                     DYN_ERR_RHS);
    CHECK(res.rhs_status == 7 && res.fail_t == 3.0 && y == 3.0 && res.t == 3.0 &&
              res.stats.rhs_calls == 4,
          "status %d fail_t %g y %g t %g calls %ld", res.rhs_status, res.fail_t, y, res.t,
          res.stats.rhs_calls);
}

static void test_what_a_map_refuses(void **state)
{
    (void)state;
    const dyn_tableau *m = map_method();
    double work[TEST_WORK], y[2];
    dyn_system sys = {halve, 2, NULL};
    const double y0[2] = {1.0, 0.0};
    dyn_result res;
    /* 4.5 steps */
    assert_int_equal(dyn_fixed_solve(m, &sys, 0.0, 4.5, 1.0, y0, y, work, NULL, &res),
                     DYN_ERR_ARG);
    assert_non_null(strstr(res.message, "whole steps"));
    dyn_fixed_opts o = {0};
    o.end = DYN_END_GRID; /* stops at t = 4 */
    assert_int_equal(dyn_fixed_solve(m, &sys, 0.0, 4.5, 1.0, y0, y, work, &o, &res), DYN_OK);
    assert_true(res.t == 4.0 && y[0] == 0.0625);
    /* dyn_solve: no events or resets on a map */
    dyn_solve_opts so = {0};
    so.h = 1.0;
    static double swork[4096];
    assert_int_equal(dyn_solve(m, &sys, 0.0, 4.0, y0, y, swork, &so, &res), DYN_ERR_ARG);
    assert_non_null(strstr(res.message, "discrete map"));
    /* the header-only driver hands it to dyn_fixed_solve: the same iterates */
    assert_int_equal(dyn_fixed_solve_inline(m, &sys, 0.0, 4.0, 1.0, y0, y, work, NULL, &res),
                     DYN_OK);
    assert_true(res.t == 4.0 && y[0] == 0.0625 && y[1] == 3.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_iterates_are_the_maps_values),
        cmocka_unit_test(test_samples_every_k_and_the_last),
        cmocka_unit_test(test_failures_keep_the_last_good_state),
        cmocka_unit_test(test_what_a_map_refuses),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
