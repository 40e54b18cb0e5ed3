/* SPDX-License-Identifier: BSD-3-Clause */
/* Dense output of dyn_solve, against numerical facts:
 * - the order of each interpolant: over one step of size h from an exact state, the error
 *   at mid-step behaves like h^(q+1) (bs23: q = 3, dp45: 4, DOP853: 7; cubic Hermite on a
 *   fixed-step RK4 step: 3);
 * - the interpolant passes through the step's ends (y(t_n) = y_n exactly, y(t_n+1) = y_n+1
 *   to rounding) and its derivative there is f (C1 continuity across steps);
 * - samples at requested times (a grid or a list) equal the recorded dense output at those
 *   times and the exact solution within the tolerance; sample times are t0 + k*h computed;
 * - the caller-owned recorder: exact capacity works, a full recorder without growth stops
 *   with DYN_ERR_CAPACITY keeping what it holds, and a growth callback (the caller's
 *   reallocation between steps) lets the solve finish. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "dynkit/dynkit.h"
#include "test_util.h"

/* y' = y cos t, y = exp(sin t) */
static int expsin_rhs(double t, const double *y, double *f, void *par)
{
    (void)par;
    f[0] = y[0] * cos(t);
    return 0;
}

/* harmonic oscillator, y = (cos t, -sin t) from (1, 0) */
static int oscillator_rhs(double t, const double *y, double *f, void *par)
{
    (void)t;
    (void)par;
    f[0] = y[1];
    f[1] = -y[0];
    return 0;
}

typedef struct one_step {
    dyn_dense d;
    double coef[8 * 2];
    long steps;
} one_step;

static int keep_step(const dyn_dense *d, void *ctx)
{
    one_step *s = ctx;
    s->d = *d;
    memcpy(s->coef, d->coef, (size_t)(d->degree + 1) * (size_t)d->n * sizeof *s->coef);
    s->d.coef = s->coef;
    s->steps++;
    return 0;
}

/* One step of size h from (t0, exp(sin t0)) on y' = y cos t; returns its dense output. */
static void take_one_step(const dyn_tableau *m, double t0, double h, one_step *s)
{
    dyn_system sys = {expsin_rhs, 1, NULL};
    const double y0 = exp(sin(t0));
    double y, work[256];
    dyn_solve_opts o = {0};
    o.step = keep_step;
    o.step_ctx = s;
    if (dyn_method_is_adaptive(m)) {
        o.initial_step = h;
        o.rtol = 1e3; /* accept the step whatever its error */
        o.atol = 1e3;
    } else {
        o.h = h;
    }
    assert_true(dyn_solve_work_size(m, 1, &o) <= sizeof work / sizeof work[0]);
    s->steps = 0;
    dyn_result res;
    assert_int_equal(dyn_solve(m, &sys, t0, t0 + h, &y0, &y, work, &o, &res), DYN_OK);
    assert_int_equal(s->steps, 1);
    assert_true(fabs(s->d.h - h) <= 1e-15 * h && s->d.t0 == t0); /* h = (t0 + h) - t0 */
}

static void test_order_of_dense_output(void **state)
{
    (void)state;
    static const struct {
        const char *name;
        int degree;
        double h0;
    } cases[] = {{"bs23", 3, 0.4}, {"dp45", 4, 0.4}, {"dop853", 7, 0.4}, {"rk4", 3, 0.4}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        const dyn_tableau *m = dyn_method_find(cases[c].name);
        assert_int_equal(dyn_method_dense_degree(m), cases[c].degree);
        const double t0 = 0.3;
        double err[4];
        for (int k = 0; k < 4; k++) {
            const double h = cases[c].h0 / (double)(1 << k);
            one_step s;
            take_one_step(m, t0, h, &s);
            assert_int_equal(s.d.degree, cases[c].degree);
            /* the largest error at interior points, measured against the exact solution
             * minus the step's own error at its end (which is of higher order) */
            err[k] = 0.0;
            for (int j = 1; j < 8; j++) {
                const double t = t0 + h * j / 8.0;
                double y;
                dyn_dense_eval(&s.d, t, &y);
                err[k] = fmax(err[k], fabs(y - exp(sin(t))));
            }
        }
        for (int k = 0; k + 1 < 4; k++) {
            const double order = log2(err[k] / err[k + 1]);
            test_note("%-6s h = %-6g dense error %.3g, then %.3g: h^%.2f", cases[c].name,
                      cases[c].h0 / (1 << k), err[k], err[k + 1], order);
            CHECK(fabs(order - (cases[c].degree + 1)) < 0.5,
                  "%s: dense output error falls like h^%.2f, expected h^%d", cases[c].name, order,
                  cases[c].degree + 1);
        }
    }
}

static void test_interpolant_meets_the_ends(void **state)
{
    (void)state;
    const char *const names[] = {"bs23", "dp45", "dop853", "heun", "rk4"};
    for (size_t c = 0; c < sizeof names / sizeof names[0]; c++) {
        const dyn_tableau *m = dyn_method_find(names[c]);
        one_step s;
        const double t0 = 0.7;
        take_one_step(m, t0, 0.2, &s);
        const double h = s.d.h;
        double ya, yb, da, db, f0, f1, y0 = exp(sin(t0));
        dyn_dense_eval(&s.d, t0, &ya);
        assert_true(same_bits(ya, y0)); /* theta = 0: the first coefficient */
        dyn_dense_eval(&s.d, t0 + h, &yb);
        /* the step's end state: the solve's result y1; compare through f */
        dyn_dense_deriv(&s.d, t0, &da);
        dyn_dense_deriv(&s.d, t0 + h, &db);
        expsin_rhs(t0, &y0, &f0, NULL);
        expsin_rhs(t0 + h, &yb, &f1, NULL);
        CHECK(fabs(da - f0) < 1e-14 * fabs(f0) + 1e-15, "%s: y'(t0) %.17g != f %.17g", names[c], da,
              f0);
        CHECK(fabs(db - f1) < 1e-12, "%s: y'(t1) %.17g != f(t1, y1) %.17g", names[c], db, f1);
        /* the end value is the step's result to rounding: solve the same step for y1 */
        dyn_system sys = {expsin_rhs, 1, NULL};
        double y1, work[256];
        dyn_solve_opts o = {0};
        if (dyn_method_is_adaptive(m)) {
            o.initial_step = 0.2;
            o.rtol = o.atol = 1e3;
        } else {
            o.h = 0.2;
        }
        dyn_result res;
        assert_int_equal(dyn_solve(m, &sys, t0, t0 + 0.2, &y0, &y1, work, &o, &res), DYN_OK);
        CHECK(fabs(yb - y1) < 4e-16 * fabs(y1), "%s: y(t1) = %.17g, y1 = %.17g", names[c], yb, y1);
    }
}

/* ---- samples, the recorder ---- */

typedef struct grow_ctx {
    long grown;
    size_t block;
} grow_ctx;

/* The caller's growth: doubles the capacity with realloc (outside the library's code). */
static int grow_record(dyn_dense_record *rec, void *ctx)
{
    grow_ctx *g = ctx;
    long cap = rec->capacity ? 2 * rec->capacity : 4;
    double *p = realloc(rec->data, (size_t)cap * g->block * sizeof *p);
    if (!p)
        return 1;
    rec->data = p;
    rec->capacity = cap;
    g->grown++;
    return 0;
}

static void test_samples_equal_dense_output_and_exact(void **state)
{
    (void)state;
    dyn_system sys = {oscillator_rhs, 2, NULL};
    const double y0[2] = {1.0, 0.0};
    const char *const names[] = {"bs23", "dp45", "dop853"};
    static sample_log log;
    for (size_t c = 0; c < 3; c++) {
        const dyn_tableau *m = dyn_method_find(names[c]);
        const int q = dyn_method_dense_degree(m);
        grow_ctx g = {0, dyn_dense_record_block(2, q)};
        dyn_dense_record rec = {0};
        rec.grow = grow_record;
        rec.grow_ctx = &g;
        dyn_dense_record_init(&rec, 2, q, NULL, 0);
        sample_log_init(&log, 2);
        dyn_solve_opts o = {0};
        o.rtol = 1e-9;
        o.atol = 1e-9;
        o.out_step = 0.1;
        o.output = sample_log_output;
        o.output_ctx = &log;
        o.record = &rec;
        double y[2], *work = malloc(dyn_solve_work_size(m, 2, &o) * sizeof *work);
        dyn_result res;
        assert_int_equal(dyn_solve(m, &sys, 0.0, 10.0, y0, y, work, &o, &res), DYN_OK);
        free(work);
        assert_int_equal(log.count, 101);
        assert_true(g.grown > 0);
        assert_int_equal(rec.count, res.stats.accepted);
        for (long k = 0; k < log.count; k++) {
            const double t = log.t[k];
            assert_true(same_bits(t, k == 100 ? 10.0 : 0.0 + (double)k * 0.1)); /* computed */
            double yr[2];
            assert_int_equal(dyn_dense_record_eval(&rec, t, yr), 0);
            /* a sample is the dense output there (the step's end state at a step's end) */
            CHECK(max_abs_diff(yr, log.y[k], 2) < 1e-15, "%s: sample %ld at t = %g differs from the "
                  "recorded dense output by %.3g", names[c], k, t, max_abs_diff(yr, log.y[k], 2));
            const double exact[2] = {cos(t), -sin(t)};
            CHECK(max_abs_diff(log.y[k], exact, 2) < 1e-7, "%s: sample at t = %g off by %.3g",
                  names[c], t, max_abs_diff(log.y[k], exact, 2));
        }
        /* anywhere in the span, not only at samples */
        for (double t = 0.0; t <= 10.0; t += 0.0123) {
            double yr[2];
            assert_int_equal(dyn_dense_record_eval(&rec, t, yr), 0);
            const double exact[2] = {cos(t), -sin(t)};
            CHECK(max_abs_diff(yr, exact, 2) < 1e-7, "%s: dense output at t = %g off by %.3g",
                  names[c], t, max_abs_diff(yr, exact, 2));
        }
        double yr[2];
        assert_int_equal(dyn_dense_record_eval(&rec, 10.5, yr), DYN_ERR_ARG);
        assert_int_equal(dyn_dense_record_eval(&rec, -0.1, yr), DYN_ERR_ARG);
        free(rec.data);
    }
}

static void test_output_times_list(void **state)
{
    (void)state;
    dyn_system sys = {oscillator_rhs, 2, NULL};
    const double y0[2] = {1.0, 0.0};
    const double times[] = {0.0, 0.0, 1e-9, 0.5, 3.0, 3.0, 7.25, 9.999999, 10.0};
    const long nt = sizeof times / sizeof times[0];
    static sample_log log;
    sample_log_init(&log, 2);
    dyn_solve_opts o = {0};
    o.rtol = 1e-10;
    o.atol = 1e-10;
    o.out_times = times;
    o.n_out_times = nt;
    o.output = sample_log_output;
    o.output_ctx = &log;
    double y[2], work[256];
    dyn_result res;
    assert_int_equal(dyn_solve(dyn_method_find("dp45"), &sys, 0.0, 10.0, y0, y, work, &o, &res),
                     DYN_OK);
    assert_int_equal(log.count, nt);
    for (long k = 0; k < nt; k++) {
        assert_true(same_bits(log.t[k], times[k]));
        assert_int_equal(log.k[k], k);
        const double exact[2] = {cos(times[k]), -sin(times[k])};
        assert_true(max_abs_diff(log.y[k], exact, 2) < 1e-9);
    }
    /* the outputs did not shorten the steps: the same steps as without outputs */
    dyn_result res2;
    dyn_solve_opts plain = {0};
    plain.rtol = plain.atol = 1e-10;
    assert_int_equal(
        dyn_solve(dyn_method_find("dp45"), &sys, 0.0, 10.0, y0, y, work, &plain, &res2), DYN_OK);
    assert_int_equal(res.stats.accepted, res2.stats.accepted);
    assert_int_equal(res.stats.rhs_calls, res2.stats.rhs_calls);
}

static void test_recorder_capacity(void **state)
{
    (void)state;
    dyn_system sys = {oscillator_rhs, 2, NULL};
    const double y0[2] = {1.0, 0.0};
    const dyn_tableau *m = dyn_method_find("dp45");
    const int q = dyn_method_dense_degree(m);
    const size_t block = dyn_dense_record_block(2, q);
    assert_int_equal((long)block, 2 + 5 * 2);
    double work[256], y[2];
    dyn_result res;
    /* how many steps the solve takes */
    dyn_solve_opts o = {0};
    o.rtol = o.atol = 1e-8;
    assert_int_equal(dyn_solve(m, &sys, 0.0, 10.0, y0, y, work, &o, &res), DYN_OK);
    const long steps = res.stats.accepted;
    /* exactly enough room */
    double *data = malloc((size_t)steps * block * sizeof *data);
    dyn_dense_record rec = {0};
    dyn_dense_record_init(&rec, 2, q, data, steps);
    o.record = &rec;
    assert_int_equal(dyn_solve(m, &sys, 0.0, 10.0, y0, y, work, &o, &res), DYN_OK);
    assert_int_equal(rec.count, steps);
    dyn_dense last;
    assert_int_equal(dyn_dense_record_step(&rec, steps - 1, &last), 0);
    assert_true(last.t0 + last.h == 10.0);
    /* one step too few, no growth: stops with what it holds */
    dyn_dense_record_init(&rec, 2, q, data, steps - 1);
    assert_int_equal(dyn_solve(m, &sys, 0.0, 10.0, y0, y, work, &o, &res), DYN_ERR_CAPACITY);
    assert_int_equal(rec.count, steps - 1);
    assert_true(res.t < 10.0 && res.t == rec.data[(steps - 2) * (long)block] +
                                             rec.data[(steps - 2) * (long)block + 1]);
    assert_true(fabs(y[0] - cos(res.t)) < 1e-7);
    /* a recorder for another degree is refused */
    dyn_dense_record_init(&rec, 2, 7, data, steps);
    assert_int_equal(dyn_solve(m, &sys, 0.0, 10.0, y0, y, work, &o, &res), DYN_ERR_ARG);
    free(data);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_order_of_dense_output),
        cmocka_unit_test(test_interpolant_meets_the_ends),
        cmocka_unit_test(test_samples_equal_dense_output_and_exact),
        cmocka_unit_test(test_output_times_list),
        cmocka_unit_test(test_recorder_capacity),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
