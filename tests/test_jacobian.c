/* SPDX-License-Identifier: BSD-3-Clause */
/* test_jacobian.c — the forward-difference Jacobian and df/dt (src/ode/jacobian.h) against
 * analytic derivatives: the error is about sqrt(eps) relative to the scale of the entries,
 * every column costs one call of f, a state at zero of a stiff system gets a usable
 * increment, states far below one need a typical size of their own (and get it), the state
 * passed in is left alone, and a failing f is passed through; an exact Jacobian whose
 * column is not finite where f is (dyn_jacobian_mend) gets that column by differences: the
 * one-sided limit of the derivative, backward when f is defined on that side only. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <float.h>

#include "dynkit/ode.h"
#include "ode/jacobian.h"
#include "test_util.h"

/* A non-autonomous test system with a dense, nonlinear Jacobian:
 *   f1 = sin(y1) y2 + t^2 y3
 *   f2 = exp(0.5 y2) - y1 y3 + cos(t)
 *   f3 = y1^3 / (1 + y3^2) + 1e3 y2 */
static double last_t; /* time of the last call of f_test */

static int f_test(double t, const double *y, double *f, void *par)
{
    int *calls = par;
    last_t = t;
    if (calls)
        (*calls)++;
    f[0] = sin(y[0]) * y[1] + t * t * y[2];
    f[1] = exp(0.5 * y[1]) - y[0] * y[2] + cos(t);
    f[2] = y[0] * y[0] * y[0] / (1.0 + y[2] * y[2]) + 1e3 * y[1];
    return 0;
}

static void jac_test(double t, const double *y, double *J)
{
    const double q = 1.0 + y[2] * y[2];
    J[0] = cos(y[0]) * y[1];
    J[1] = sin(y[0]);
    J[2] = t * t;
    J[3] = -y[2];
    J[4] = 0.5 * exp(0.5 * y[1]);
    J[5] = -y[0];
    J[6] = 3.0 * y[0] * y[0] / q;
    J[7] = 1e3;
    J[8] = -2.0 * y[2] * y[0] * y[0] * y[0] / (q * q);
}

static void test_difference_jacobian_matches_analytic(void **state)
{
    (void)state;
    int calls = 0;
    dyn_system sys = {f_test, 3, &calls};
    const double pts[][4] = {
        {0.3, 0.7, -1.2, 2.0}, {2.5, -3.0, 0.01, 0.5}, {0.0, 1e-3, 4.0, -7.0}, {10.0, 0, 0, 0}};
    for (size_t p = 0; p < sizeof pts / sizeof pts[0]; p++) {
        const double t = pts[p][0], *y = pts[p] + 1;
        double y_copy[3], f0[3], J[9], Jex[9], work[DYN_FD_JAC_WORK(3)];
        memcpy(y_copy, y, sizeof y_copy);
        f_test(t, y, f0, NULL);
        long rhs = 0;
        calls = 0;
        assert_int_equal(dyn_fd_jacobian(&sys, t, y, f0, NULL, J, work, &rhs), 0);
        assert_int_equal(rhs, 3);
        assert_int_equal(calls, 3);
        assert_memory_equal(y, y_copy, sizeof y_copy);
        jac_test(t, y, Jex);
        double scale = 0.0;
        for (int i = 0; i < 9; i++)
            scale = fmax(scale, fabs(Jex[i]));
        double e = max_abs_diff(J, Jex, 9);
        /* truncation ~ d |f''| and rounding ~ eps |f| / d with d ~ 1.5e-8 max(|y|, 1) */
        CHECK(e < 2e-6 * scale, "point %zu: Jacobian error %.3g (scale %.3g)", p, e, scale);
    }
}

/* Robertson's kinetics: states of sizes 1, 1e-5 and 1. With the default typical size (1)
 * the increment of y2 is 1.5e-8, larger than y2 itself, and the quadratic term 3e7 y2^2
 * puts an error of 3e7 * 1.5e-8 = 0.45 into d f2 / d y2; with a typical size of y2's own
 * order (what a driver passes as atol / rtol) the column is accurate. */
static int f_rober(double t, const double *y, double *f, void *par)
{
    (void)t;
    (void)par;
    f[0] = -0.04 * y[0] + 1e4 * y[1] * y[2];
    f[1] = 0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] * y[1];
    f[2] = 3e7 * y[1] * y[1];
    return 0;
}

static void test_increments_follow_the_size_of_each_state(void **state)
{
    (void)state;
    dyn_system sys = {f_rober, 3, NULL};
    const double y[3] = {0.9, 3.5e-5, 0.1};
    const double Jex[9] = {-0.04, 1e4 * y[2],           1e4 * y[1],
                           0.04,  -1e4 * y[2] - 6e7 * y[1], -1e4 * y[1],
                           0.0,   6e7 * y[1],           0.0};
    double f0[3], J[9], work[6];
    f_rober(0, y, f0, NULL);
    const double typ[3] = {1.0, 1e-5, 1.0};
    assert_int_equal(dyn_fd_jacobian(&sys, 0.0, y, f0, typ, J, work, NULL), 0);
    /* column 2: d^2 f / dy2^2 = 6e7, increment 1.5e-8 * 3.5e-5: error ~ 2e-5 absolute */
    for (int i = 0; i < 9; i++)
        CHECK(fabs(J[i] - Jex[i]) <= 1e-6 * fabs(Jex[i]) + 1e-6, "J[%d] = %.17g, exact %.17g", i,
              J[i], Jex[i]);
    assert_int_equal(dyn_fd_jacobian(&sys, 0.0, y, f0, NULL, J, work, NULL), 0);
    assert_true(fabs(J[4] - Jex[4]) > 0.1 && fabs(J[4] - Jex[4]) < 1.0);
}

/* A stiff right-hand side with a state at zero: f = -1e6 (y - 1) at y = 0. The default
 * increment (1.5e-8) keeps the rounding error eps |f| / d at 1.5e-2 on an entry of 1e6;
 * a floor of 1e-5 (increment 1.5e-13) would make it 1.5e3. */
static int f_stiff(double t, const double *y, double *f, void *par)
{
    (void)t;
    (void)par;
    f[0] = -1e6 * (y[0] - 1.0);
    f[1] = -2e6 * (y[1] - 0.3) + y[0];
    return 0;
}

static void test_zero_state_of_a_stiff_system(void **state)
{
    (void)state;
    dyn_system sys = {f_stiff, 2, NULL};
    const double y[2] = {0.0, 0.0}, Jex[4] = {-1e6, 0.0, 1.0, -2e6};
    double f0[2], J[4], work[4];
    f_stiff(0, y, f0, NULL);
    assert_int_equal(dyn_fd_jacobian(&sys, 0.0, y, f0, NULL, J, work, NULL), 0);
    for (int i = 0; i < 4; i++)
        CHECK(fabs(J[i] - Jex[i]) <= 1e-7 * 2e6, "J[%d] = %.17g, exact %.17g", i, J[i], Jex[i]);
}

static void test_time_derivative(void **state)
{
    (void)state;
    int calls = 0;
    dyn_system sys = {f_test, 3, &calls};
    const double y[3] = {0.3, -0.4, 1.5};
    const double ts[] = {0.0, 1.0, -3.0, 1e3};
    for (size_t k = 0; k < sizeof ts / sizeof ts[0]; k++) {
        const double t = ts[k];
        double f0[3], ft[3], work[3];
        f_test(t, y, f0, NULL);
        long rhs = 0;
        assert_int_equal(dyn_fd_dfdt(&sys, t, y, f0, 0.1, ft, work, &rhs), 0);
        assert_int_equal(rhs, 1);
        const double ex[3] = {2.0 * t * y[2], -sin(t), 0.0};
        const double scale = fmax(1.0, fabs(t));
        for (int i = 0; i < 3; i++)
            CHECK(fabs(ft[i] - ex[i]) < 1e-6 * scale * fmax(1.0, fabs(ex[i])),
                  "t = %g: df%d/dt = %.17g, exact %.17g", t, i, ft[i], ex[i]);
        /* backward: the same to first order, and f is not evaluated after t */
        last_t = -HUGE_VAL;
        assert_int_equal(dyn_fd_dfdt(&sys, t, y, f0, -0.1, ft, work, &rhs), 0);
        assert_true(last_t < t);
        for (int i = 0; i < 3; i++)
            CHECK(fabs(ft[i] - ex[i]) < 1e-6 * scale * fmax(1.0, fabs(ex[i])),
                  "backward, t = %g: df%d/dt = %.17g, exact %.17g", t, i, ft[i], ex[i]);
    }
}

static int f_fails(double t, const double *y, double *f, void *par)
{
    (void)t;
    int *count = par;
    f[0] = y[0];
    f[1] = y[1];
    return ++*count >= 2 ? 7 : 0;
}

static void test_failing_rhs_is_passed_through(void **state)
{
    (void)state;
    int count = 0;
    dyn_system sys = {f_fails, 2, &count};
    double y[2] = {1, 2}, f0[2] = {1, 2}, J[4], work[4], ft[2];
    long rhs = 0;
    assert_int_equal(dyn_fd_jacobian(&sys, 0.0, y, f0, NULL, J, work, &rhs), 7);
    assert_int_equal(rhs, 2);
    assert_true(y[0] == 1.0 && y[1] == 2.0);
    assert_int_equal(dyn_fd_dfdt(&sys, 0.0, y, f0, 1.0, ft, work, &rhs), 7);
}

/* ---- an exact Jacobian mended where it cannot be evaluated (dyn_jacobian_mend) ---- */

/* x' = -x + 1/(1 + kb (1 + 1/p)), p' = -p: at p = 0, 1/p = inf and the fraction is 0, so f
 * is finite; its derivative in p, kb / (p^2 (1 + kb (1 + 1/p))^2), is 0 * inf = NaN there,
 * while the one-sided limit is 1/kb (the fraction is p / (kb + (1 + kb) p)). */
#define KB 0.4

static int f_pole(double t, const double *y, double *f, void *par)
{
    (void)t;
    int *calls = par;
    if (calls)
        (*calls)++;
    f[0] = -y[0] + 1.0 / (1.0 + KB * (1.0 + 1.0 / y[1]));
    f[1] = -y[1];
    return 0;
}

static void jac_pole(const double *y, double *J)
{
    const double q = 1.0 + KB * (1.0 + 1.0 / y[1]);
    J[0] = -1.0;
    J[1] = KB / (y[1] * y[1] * q * q);
    J[2] = 0.0;
    J[3] = -1.0;
}

static void test_columns_that_are_not_finite_are_differenced(void **state)
{
    (void)state;
    int calls = 0;
    dyn_system sys = {f_pole, 2, &calls};
    double y[2] = {1.0, 0.0}, f0[2], J[4], work[4];
    f_pole(0.0, y, f0, NULL);
    jac_pole(y, J);
    assert_true(isfinite(f0[0]) && isfinite(f0[1]) && isnan(J[1])); /* the case itself */
    long rhs = 0, columns = 0;
    assert_int_equal(dyn_jacobian_mend(&sys, 0.0, y, f0, NULL, J, work, &rhs, &columns), 0);
    assert_int_equal(columns, 1); /* column p only */
    assert_int_equal(rhs, 1);
    assert_int_equal(calls, 1);
    assert_true(J[0] == -1.0 && J[2] == 0.0); /* the finite column untouched */
    /* the forward difference with d = sqrt(eps): (f1(d) - f1(0))/d = 1/(kb + (1 + kb) d),
     * the limit 1/kb = 2.5 less 1.3e-7, up to the rounding of f1 = -1 + ...: eps |f1| / d */
    const double d = sqrt(DBL_EPSILON), quotient = 1.0 / (KB + (1.0 + KB) * d);
    const double rounding = 2.0 * DBL_EPSILON / d;
    CHECK(fabs(J[1] - quotient) < rounding && fabs(J[1] - 1.0 / KB) < 2e-7,
          "d f1/dp = %.17g, the quotient %.17g", J[1], quotient);
    CHECK(fabs(J[3] + 1.0) < 1e-12, "d f2/dp = %.17g", J[3]);
    assert_true(y[0] == 1.0 && y[1] == 0.0);

    /* a finite Jacobian costs nothing; neither does one where f itself is not finite */
    jac_pole((double[]){1.0, 0.5}, J);
    const double J1 = J[1];
    rhs = columns = 0;
    dyn_jacobian_mend(&sys, 0.0, (double[]){1.0, 0.5}, f0, NULL, J, work, &rhs, &columns);
    assert_true(rhs == 0 && columns == 0 && J[1] == J1);
    double fbad[2] = {NAN, 0.0};
    jac_pole(y, J);
    dyn_jacobian_mend(&sys, 0.0, y, fbad, NULL, J, work, &rhs, &columns);
    assert_true(rhs == 0 && columns == 0 && isnan(J[1]));

    /* the same in band storage (lower = upper = 1: the whole 2 x 2 matrix) */
    double B[6] = {0};
    jac_pole(y, J);
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            DYN_BAND_AT(B, 1, 1, i, j) = J[i * 2 + j];
    rhs = columns = 0;
    assert_int_equal(dyn_jacobian_band_mend(&sys, 0.0, y, f0, NULL, 1, 1, B, work, &rhs,
                                            &columns), 0);
    assert_true(columns == 1 && rhs == 1);
    CHECK(fabs(DYN_BAND_AT(B, 1, 1, 0, 1) - quotient) < rounding, "band: %.17g",
          DYN_BAND_AT(B, 1, 1, 0, 1));
    assert_true(DYN_BAND_AT(B, 1, 1, 0, 0) == -1.0 && DYN_BAND_AT(B, 1, 1, 1, 0) == 0.0);
}

/* f = p + 0 sqrt(-p): defined for p <= 0 only, so the forward difference at p = 0 is NaN
 * and the backward one gives the slope 1; the formula of the derivative, 1 + 0 (-inf), is
 * NaN. */
static int f_left(double t, const double *y, double *f, void *par)
{
    (void)t;
    (void)par;
    f[0] = y[0] + 0.0 * sqrt(-y[0]);
    return 0;
}

static void test_one_sided_formula_is_differenced_backward(void **state)
{
    (void)state;
    dyn_system sys = {f_left, 1, NULL};
    double y[1] = {0.0}, f0[1], J[1] = {NAN}, work[2];
    f_left(0.0, y, f0, NULL);
    long rhs = 0, columns = 0;
    assert_int_equal(dyn_jacobian_mend(&sys, 0.0, y, f0, NULL, J, work, &rhs, &columns), 0);
    assert_true(columns == 1 && rhs == 2); /* forward (NaN), then backward */
    CHECK(fabs(J[0] - 1.0) < 1e-12, "J = %.17g", J[0]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_difference_jacobian_matches_analytic),
        cmocka_unit_test(test_increments_follow_the_size_of_each_state),
        cmocka_unit_test(test_zero_state_of_a_stiff_system),
        cmocka_unit_test(test_time_derivative),
        cmocka_unit_test(test_failing_rhs_is_passed_through),
        cmocka_unit_test(test_columns_that_are_not_finite_are_differenced),
        cmocka_unit_test(test_one_sided_formula_is_differenced_backward),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
