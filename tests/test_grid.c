/* SPDX-License-Identifier: BSD-3-Clause */
/* The sample grid of fixed-step runs (dyn_grid_plan, dyn_grid_time) and how the driver
 * follows it: sample k is at t0 + k*h computed (never accumulated) and a whole span has
 * exactly round((t1 - t0)/h) + 1 samples ending on t1 itself, even when h is not exact in
 * binary; a span that is not a whole number of steps ends with a shorter step on t1
 * (DYN_END_EXACT) or stops at the last whole step (DYN_END_GRID); bad steps and spans are
 * refused with a message. Through dyn_fixed_solve: the output sees exactly the grid's
 * times and indices, --every K keeps k % K == 0 and the last sample, the right-hand side is
 * never evaluated past t1, and the partial last step has the right size. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "test_util.h"

/* Plan a grid that must be accepted. */
static dyn_grid plan_ok(double t0, double t1, double h, dyn_end_policy end)
{
    dyn_grid g;
    char err[256] = "";
    int rc = dyn_grid_plan(t0, t1, h, end, &g, err, sizeof err);
    CHECK(rc == DYN_OK, "plan %g:%g h=%g refused: %s", t0, t1, h, err);
    return g;
}

/* The shape of a plan: samples, whole steps, a partial last step, ending at t1. */
static void check_plan(const dyn_grid *g, long samples, long whole_steps, int partial,
                       int ends_at_t1)
{
    CHECK(g->samples == samples && g->whole_steps == whole_steps && g->partial == partial &&
              g->ends_at_t1 == ends_at_t1,
          "grid %g:%g h=%g: samples %ld, whole steps %ld, partial %d, ends at t1 %d; expected "
          "%ld, %ld, %d, %d",
          g->t0, g->t1, g->h, g->samples, g->whole_steps, g->partial, g->ends_at_t1, samples,
          whole_steps, partial, ends_at_t1);
}

/* Every sample time is t0 + k*h computed, except a last sample that is t1 by contract. */
static void check_sample_times(const dyn_grid *g)
{
    for (long k = 0; k < g->samples; k++) {
        double t = dyn_grid_time(g, k);
        double expect = (g->ends_at_t1 && k == g->samples - 1) ? g->t1 : (double)k * g->h + g->t0;
        CHECK(same_bits(t, expect), "grid %g:%g h=%g: sample %ld at %.17g, expected %.17g",
              g->t0, g->t1, g->h, k, t, expect);
    }
    /* Times increase strictly and stay within [t0, t1]. */
    assert_true(dyn_grid_time(g, 0) == g->t0);
    for (long k = 1; k < g->samples; k++) {
        assert_true(dyn_grid_time(g, k) > dyn_grid_time(g, k - 1));
        assert_true(dyn_grid_time(g, k) <= g->t1);
    }
}

static void test_homework_span_has_1501_samples(void **state)
{
    (void)state;
    dyn_grid g = plan_ok(0.0, 15.0, 0.01, DYN_END_EXACT);
    check_plan(&g, 1501, 1500, 0, 1);
    assert_true(dyn_grid_time(&g, 1500) == 15.0);
    check_sample_times(&g);
    /* The same with the grid policy: a whole span does not lose its last sample. */
    dyn_grid gg = plan_ok(0.0, 15.0, 0.01, DYN_END_GRID);
    assert_int_equal(gg.samples, 1501);
    assert_true(dyn_grid_time(&gg, 1500) == 15.0);
}

/* 0.1, 0.3, 0.7 are not exact in binary: (t1 - t0)/h is 2.9999999999999996 for 0.3/0.1,
 * but the span is still a whole number of steps. */
static void test_whole_number_detection(void **state)
{
    (void)state;
    static const struct {
        double t0, t1, h;
        long samples;
    } cases[] = {
        {0.0, 1.0, 0.1, 11},  {0.0, 0.3, 0.1, 4},    {0.0, 0.7, 0.1, 8},
        {0.0, 0.2, 0.2, 2},   {2.5, 7.3, 0.001, 4801}, {-1.0, 1.0, 0.1, 21},
        {0.1, 0.7, 0.05, 13}, {0.0, 100.0, 0.01, 10001}, {0.0, 1e4, 1e-4, 100000001},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        for (int end = DYN_END_EXACT; end <= DYN_END_GRID; end++) {
            dyn_grid g = plan_ok(cases[i].t0, cases[i].t1, cases[i].h, (dyn_end_policy)end);
            CHECK(g.samples == cases[i].samples && g.partial == 0 && g.ends_at_t1 == 1,
                  "%g:%g h=%g end=%d: %ld samples (partial %d), expected %ld", cases[i].t0,
                  cases[i].t1, cases[i].h, end, g.samples, g.partial, cases[i].samples);
            assert_true(dyn_grid_time(&g, g.samples - 1) == cases[i].t1);
            if (g.samples < 100000)
                check_sample_times(&g);
        }
    }
    /* The computed time of the 3rd step of 0.1 is not 0.3: the grid reports t1 itself. */
    assert_false(3.0 * 0.1 == 0.3);
}

static void test_partial_last_step(void **state)
{
    (void)state;
    dyn_grid e = plan_ok(0.0, 1.0, 0.3, DYN_END_EXACT);
    check_plan(&e, 5, 3, 1, 1);
    const double expect[5] = {0.0, 0.3, 2.0 * 0.3, 3.0 * 0.3, 1.0};
    for (long k = 0; k < 5; k++)
        assert_true(same_bits(dyn_grid_time(&e, k), expect[k]));
    check_sample_times(&e);

    dyn_grid g = plan_ok(0.0, 1.0, 0.3, DYN_END_GRID);
    check_plan(&g, 4, 3, 0, 0);
    for (long k = 0; k < 4; k++)
        assert_true(same_bits(dyn_grid_time(&g, k), expect[k]));
    check_sample_times(&g);

    /* An offset start: 2:7.5 with h = 2 is 2, 4, 6 and then 7.5 (or stops at 6). */
    dyn_grid o = plan_ok(2.0, 7.5, 2.0, DYN_END_EXACT);
    assert_int_equal(o.samples, 4);
    assert_true(dyn_grid_time(&o, 2) == 6.0 && dyn_grid_time(&o, 3) == 7.5);
    dyn_grid og = plan_ok(2.0, 7.5, 2.0, DYN_END_GRID);
    assert_int_equal(og.samples, 3);
    assert_true(dyn_grid_time(&og, 2) == 6.0);
}

static void test_step_larger_than_span(void **state)
{
    (void)state;
    dyn_grid e = plan_ok(0.5, 1.0, 2.0, DYN_END_EXACT);
    assert_int_equal(e.samples, 2);
    assert_int_equal(e.whole_steps, 0);
    assert_int_equal(e.partial, 1);
    assert_true(dyn_grid_time(&e, 0) == 0.5 && dyn_grid_time(&e, 1) == 1.0);
    dyn_grid g = plan_ok(0.5, 1.0, 2.0, DYN_END_GRID);
    assert_int_equal(g.samples, 1);
    assert_true(dyn_grid_time(&g, 0) == 0.5);
}

static void test_empty_span_has_one_sample(void **state)
{
    (void)state;
    for (int end = DYN_END_EXACT; end <= DYN_END_GRID; end++) {
        dyn_grid g = plan_ok(3.0, 3.0, 0.1, (dyn_end_policy)end);
        assert_int_equal(g.samples, 1);
        assert_int_equal(g.whole_steps, 0);
        assert_int_equal(g.partial, 0);
        assert_true(dyn_grid_time(&g, 0) == 3.0);
    }
}

/* A refused plan: DYN_ERR_ARG and a message that mentions what (word). */
static void check_refused(double t0, double t1, double h, int end, const char *word)
{
    dyn_grid g;
    char err[256] = "";
    int rc = dyn_grid_plan(t0, t1, h, (dyn_end_policy)end, &g, err, sizeof err);
    CHECK(rc == DYN_ERR_ARG, "%g:%g h=%g end=%d accepted (rc %d)", t0, t1, h, end, rc);
    CHECK(strlen(err) > 0 && strstr(err, word) != NULL,
          "%g:%g h=%g: message '%s' does not mention '%s'", t0, t1, h, err, word);
    /* err may be NULL: still refused, nothing written. */
    assert_int_equal(dyn_grid_plan(t0, t1, h, (dyn_end_policy)end, &g, NULL, 0), DYN_ERR_ARG);
}

static void test_bad_steps_and_spans_refused(void **state)
{
    (void)state;
    check_refused(0.0, 1.0, 1e-300, DYN_END_EXACT, "step"); /* 1e300 steps */
    check_refused(0.0, 1.0, 1e-300, DYN_END_GRID, "step");
    check_refused(0.0, 1.0, 0.0, DYN_END_EXACT, "step");
    check_refused(0.0, 1.0, -0.0, DYN_END_EXACT, "step");
    check_refused(0.0, 1.0, -0.1, DYN_END_EXACT, "step");
    check_refused(0.0, 1.0, NAN, DYN_END_EXACT, "step");
    check_refused(0.0, 1.0, INFINITY, DYN_END_EXACT, "step");
    check_refused(0.0, 1.0, -INFINITY, DYN_END_EXACT, "step");
    check_refused(1.0, 0.0, 0.1, DYN_END_EXACT, "end time");
    check_refused(NAN, 1.0, 0.1, DYN_END_EXACT, "t0");
    check_refused(0.0, NAN, 0.1, DYN_END_EXACT, "t1");
    check_refused(0.0, INFINITY, 0.1, DYN_END_EXACT, "t1");
    check_refused(-INFINITY, 0.0, 0.1, DYN_END_EXACT, "t0");
    check_refused(0.0, 1.0, 0.1, 7, "end policy");
}

/* No grid to fill: refused with a message (the message is formatted without reading
 * arguments that are not there; under ASan a mismatched format crashes here). */
static void test_null_grid_refused(void **state)
{
    (void)state;
    char err[64] = "";
    assert_int_equal(dyn_grid_plan(0.0, 1.0, 0.1, DYN_END_EXACT, NULL, err, sizeof err),
                     DYN_ERR_ARG);
    assert_true(strlen(err) > 0);
    assert_non_null(strstr(err, "grid"));
}

/* ---- through the driver ---- */

/* y' = 1 (or y' = t with par != NULL), recording the largest and smallest stage time. */
typedef struct time_probe {
    double tmin, tmax;
    long calls;
    int ramp; /* 1: y' = t instead of y' = 1 */
} time_probe;

static int probe_rhs(double t, const double *y, double *dydt, void *par)
{
    time_probe *p = par;
    (void)y;
    p->tmin = fmin(p->tmin, t);
    p->tmax = fmax(p->tmax, t);
    p->calls++;
    dydt[0] = p->ramp ? t : 1.0;
    return 0;
}

static sample_log logbuf;

/* Solve y' = 1 with an output callback; returns the status. */
static int solve_logged(const char *method, double t0, double t1, double h, dyn_end_policy end,
                        long every, time_probe *probe, double *y, dyn_result *res)
{
    double work[TEST_WORK];
    const double y0[1] = {0.0};
    dyn_system sys = {probe_rhs, 1, probe};
    dyn_fixed_opts opts = {0};
    opts.end = end;
    opts.every = every;
    opts.output = sample_log_output;
    opts.output_ctx = &logbuf;
    sample_log_init(&logbuf, 1);
    probe->tmin = INFINITY;
    probe->tmax = -INFINITY;
    probe->calls = 0;
    return dyn_fixed_solve(dyn_method_find(method), &sys, t0, t1, h, y0, y, work, &opts, res);
}

static const struct span {
    double t0, t1, h;
} spans[] = {
    {0.0, 15.0, 0.01}, {0.0, 1.0, 0.1}, {0.0, 1.0, 0.3},   {0.0, 1.0, 0.7},
    {0.0, 3.0, 0.1},   {0.0, 15.0, 0.05}, {2.5, 7.3, 0.2}, {-1.0, 1.0, 0.1},
    {0.3, 0.6, 0.02},  {0.5, 1.0, 2.0},  {0.0, 5.0, 0.2},  {1.0, 1.0, 0.1},
};

static void test_output_sees_exactly_the_grid(void **state)
{
    (void)state;
    for (size_t i = 0; i < sizeof spans / sizeof spans[0]; i++) {
        for (int end = DYN_END_EXACT; end <= DYN_END_GRID; end++) {
            const struct span *s = &spans[i];
            dyn_grid g = plan_ok(s->t0, s->t1, s->h, (dyn_end_policy)end);
            time_probe probe = {0};
            double y;
            dyn_result res;
            assert_int_equal(solve_logged("rk4", s->t0, s->t1, s->h, (dyn_end_policy)end, 0,
                                          &probe, &y, &res),
                             DYN_OK);
            CHECK(logbuf.count == g.samples, "%g:%g h=%g end=%d: %ld samples, grid has %ld",
                  s->t0, s->t1, s->h, end, logbuf.count, g.samples);
            assert_int_equal(res.stats.samples, g.samples);
            assert_int_equal(res.stats.steps, g.samples - 1);
            assert_int_equal(probe.calls, 4 * (g.samples - 1));
            for (long k = 0; k < logbuf.count; k++) {
                assert_int_equal(logbuf.k[k], k);
                CHECK(same_bits(logbuf.t[k], dyn_grid_time(&g, k)),
                      "%g:%g h=%g: sample %ld at %.17g, grid says %.17g", s->t0, s->t1, s->h, k,
                      logbuf.t[k], dyn_grid_time(&g, k));
            }
            assert_true(res.t == dyn_grid_time(&g, g.samples - 1));
            assert_true(same_bits(y, logbuf.y[logbuf.count - 1][0]));
        }
    }
}

static void test_every_keeps_multiples_and_last(void **state)
{
    (void)state;
    const long everys[] = {0, 1, 2, 3, 5, 7, 10, 11, 1000};
    for (size_t i = 0; i < sizeof spans / sizeof spans[0]; i++) {
        for (size_t e = 0; e < sizeof everys / sizeof everys[0]; e++) {
            const struct span *s = &spans[i];
            const long K = everys[e] > 1 ? everys[e] : 1;
            dyn_grid g = plan_ok(s->t0, s->t1, s->h, DYN_END_EXACT);
            time_probe probe = {0};
            double y;
            dyn_result res;
            assert_int_equal(solve_logged("euler", s->t0, s->t1, s->h, DYN_END_EXACT, everys[e],
                                          &probe, &y, &res),
                             DYN_OK);
            long expected = 0;
            for (long k = 0; k < g.samples; k++) {
                if (k % K != 0 && k != g.samples - 1)
                    continue;
                CHECK(expected < logbuf.count && logbuf.k[expected] == k,
                      "%g:%g h=%g every %ld: sample %ld missing or out of order", s->t0, s->t1,
                      s->h, everys[e], k);
                assert_true(same_bits(logbuf.t[expected], dyn_grid_time(&g, k)));
                expected++;
            }
            CHECK(logbuf.count == expected, "every %ld: %ld samples, expected %ld", everys[e],
                  logbuf.count, expected);
            assert_int_equal(res.stats.samples, expected);
            assert_int_equal(res.stats.steps, g.samples - 1); /* every never skips steps */
        }
    }
    /* The homework span with every 100: 0, 1, ..., 15 s. */
    time_probe probe = {0};
    double y;
    dyn_result res;
    assert_int_equal(solve_logged("rk4", 0.0, 15.0, 0.01, DYN_END_EXACT, 100, &probe, &y, &res),
                     DYN_OK);
    assert_int_equal(logbuf.count, 16);
    for (long i = 0; i < 16; i++)
        assert_true(logbuf.t[i] == (i == 15 ? 15.0 : (double)(100 * i) * 0.01));
}

/* The right-hand side is never evaluated before t0 or past t1 (a model may read a table
 * that ends at t1, or be undefined beyond it). Spans that are a whole number of steps
 * included: 0:3 with h = 0.1, where t0 + 29h + h rounds above 3. */
static void test_rhs_never_evaluated_past_t1(void **state)
{
    (void)state;
    int past = 0;
    for (int m = 0; m < dyn_method_count(); m++) {
        const dyn_tableau *method = fixed_method_at(m);
        if (!method)
            continue;
        for (size_t i = 0; i < sizeof spans / sizeof spans[0]; i++) {
            for (int end = DYN_END_EXACT; end <= DYN_END_GRID; end++) {
                const struct span *s = &spans[i];
                time_probe probe = {0};
                double y;
                dyn_result res;
                assert_int_equal(solve_logged(method->name, s->t0, s->t1, s->h,
                                              (dyn_end_policy)end, 0, &probe, &y, &res),
                                 DYN_OK);
                if (probe.calls == 0)
                    continue;
                assert_true(probe.tmin >= s->t0);
                if (probe.tmax > s->t1) {
                    test_note("%s on %g:%g h=%g end=%d: f evaluated at t = %.17g > t1 (by %.3g)",
                              method->name, s->t0, s->t1, s->h, end, probe.tmax,
                              probe.tmax - s->t1);
                    past++;
                }
            }
        }
    }
    CHECK(past == 0, "%d runs evaluated the right-hand side past t1", past);
}

/* The partial last step has size t1 - (t0 + N h): Euler on y' = 1 sums the step sizes, and
 * RK4 integrates y' = t exactly (Simpson's rule), so both land on the exact values. */
static void test_partial_step_has_the_right_size(void **state)
{
    (void)state;
    const double eps = 0x1p-52;
    for (size_t i = 0; i < sizeof spans / sizeof spans[0]; i++) {
        const struct span *s = &spans[i];
        for (int end = DYN_END_EXACT; end <= DYN_END_GRID; end++) {
            dyn_grid g = plan_ok(s->t0, s->t1, s->h, (dyn_end_policy)end);
            const double tend = dyn_grid_time(&g, g.samples - 1);
            const double span = tend - s->t0;
            time_probe probe = {0};
            double y;
            dyn_result res;
            assert_int_equal(
                solve_logged("euler", s->t0, s->t1, s->h, (dyn_end_policy)end, 0, &probe, &y, &res),
                DYN_OK);
            /* rounding of the sum and of the times: a few ulps per step */
            double tol = 4.0 * eps * fmax(fabs(s->t0), fabs(s->t1)) * (double)g.samples + 1e-300;
            CHECK(fabs(y - span) <= tol, "euler y'=1 on %g:%g h=%g end=%d: y = %.17g, span %.17g",
                  s->t0, s->t1, s->h, end, y, span);
            probe.ramp = 1;
            double work[TEST_WORK];
            const double y0[1] = {0.0};
            dyn_system sys = {probe_rhs, 1, &probe};
            dyn_fixed_opts opts = {0};
            opts.end = (dyn_end_policy)end;
            assert_int_equal(dyn_fixed_solve(dyn_method_find("rk4"), &sys, s->t0, s->t1, s->h,
                                             y0, &y, work, &opts, &res),
                             DYN_OK);
            double exact = 0.5 * (tend * tend - s->t0 * s->t0);
            tol = 8.0 * eps * fmax(1.0, tend * tend) * (double)g.samples;
            CHECK(fabs(y - exact) <= tol, "rk4 y'=t on %g:%g h=%g end=%d: y = %.17g, exact %.17g",
                  s->t0, s->t1, s->h, end, y, exact);
        }
    }
    /* The plain case of the brief: 0:1 with h = 0.3 ends on exactly 1 (steps .3,.3,.3,.1). */
    time_probe probe = {0};
    double y;
    dyn_result res;
    assert_int_equal(solve_logged("euler", 0.0, 1.0, 0.3, DYN_END_EXACT, 0, &probe, &y, &res),
                     DYN_OK);
    assert_true(fabs(y - 1.0) <= 2.0 * eps);
    assert_true(logbuf.t[4] == 1.0);
    assert_int_equal(solve_logged("euler", 0.0, 1.0, 0.3, DYN_END_GRID, 0, &probe, &y, &res),
                     DYN_OK);
    assert_true(fabs(y - 0.9) <= 2.0 * eps);
    assert_int_equal(logbuf.count, 4);
}

static void test_empty_span_through_driver(void **state)
{
    (void)state;
    time_probe probe = {0};
    double y = 42.0;
    dyn_result res;
    assert_int_equal(solve_logged("rk4", 2.0, 2.0, 0.1, DYN_END_EXACT, 0, &probe, &y, &res),
                     DYN_OK);
    assert_int_equal(logbuf.count, 1);
    assert_int_equal(logbuf.k[0], 0);
    assert_true(logbuf.t[0] == 2.0);
    assert_true(y == 0.0); /* the initial state */
    assert_int_equal(probe.calls, 0);
    assert_int_equal(res.stats.steps, 0);
    assert_true(res.t == 2.0);
}

static void test_driver_refuses_bad_grid_before_any_evaluation(void **state)
{
    (void)state;
    const double bad[][3] = {
        {0.0, 1.0, 1e-300}, {0.0, 1.0, 0.0}, {0.0, 1.0, -0.01}, {0.0, 1.0, NAN},
        {0.0, 1.0, INFINITY}, {1.0, 0.0, 0.1},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        time_probe probe = {0};
        double y;
        dyn_result res;
        int rc = solve_logged("rk4", bad[i][0], bad[i][1], bad[i][2], DYN_END_EXACT, 0, &probe,
                              &y, &res);
        CHECK(rc == DYN_ERR_ARG && res.status == DYN_ERR_ARG,
              "%g:%g h=%g: status %d, expected DYN_ERR_ARG", bad[i][0], bad[i][1], bad[i][2], rc);
        assert_true(strlen(res.message) > 0);
        assert_int_equal(probe.calls, 0);
        assert_int_equal(logbuf.count, 0);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_homework_span_has_1501_samples),
        cmocka_unit_test(test_whole_number_detection),
        cmocka_unit_test(test_partial_last_step),
        cmocka_unit_test(test_step_larger_than_span),
        cmocka_unit_test(test_empty_span_has_one_sample),
        cmocka_unit_test(test_bad_steps_and_spans_refused),
        cmocka_unit_test(test_null_grid_refused),
        cmocka_unit_test(test_output_sees_exactly_the_grid),
        cmocka_unit_test(test_every_keeps_multiples_and_last),
        cmocka_unit_test(test_rhs_never_evaluated_past_t1),
        cmocka_unit_test(test_partial_step_has_the_right_size),
        cmocka_unit_test(test_empty_span_through_driver),
        cmocka_unit_test(test_driver_refuses_bad_grid_before_any_evaluation),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
