/* SPDX-License-Identifier: BSD-3-Clause */
/* Volterra equations on a grid (dynkit/volterra.h) against closed forms:
 *   - u(t) = 1 - int_0^t u(s) ds is u = e^-t;
 *   - x' = -int_0^t e^-(t-s) x(s) ds, x(0) = 1, is x'' + x' + x = 0, x'(0) = 0:
 *     x = e^(-t/2) (cos wt + sin(wt) / (2w)), w = sqrt(3)/2 (a convolution);
 *   - u(t) = sin t + cos(t)/2 - (t + 1) e^-t / 2 + int_0^t (t-s) e^(s-t) u(s) ds is sin t
 *     (XPPAUT's manual, an integrand that reads t and t');
 *   - Abel's kernel: u(t) = 1 - int_0^t (t-s)^(-1/2) u(s) ds is u = e^(pi t) erfc(sqrt(pi t))
 *     (Laplace: U = 1/(s + sqrt(pi s)); checked with SciPy's quad with the weight
 *     (t-s)^(-1/2): the residual is below 5e-12 at t = 0.3, 1, 2);
 * with the orders the errors show as the step halves (2 for the regular kernels; for mu = 1/2,
 * 1.5 away from t = 0 and 1 at the first steps, where u = 1 - 2 sqrt(t) + O(t)), and the bounded memory: with M points kept, u = 1 - int u over the last M h
 * settles at 1/(1 + M h). */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/volterra.h"

static const unsigned char INT1[1] = {1}, ODE1[1] = {0}, NOCONV[1] = {0}, CONV[1] = {1};
static const double MU0[1] = {0.0}, MUHALF[1] = {0.5};

typedef struct prob {
    double ints[1];
    int kind; /* 0 u = 1 - I, 1 x' = -I, 2 sin t, 3 Abel */
} prob;

static int rhs(double t, const double *y, double *f, void *par)
{
    prob *p = par;
    (void)y;
    switch (p->kind) {
    case 1:
        f[0] = -p->ints[0];
        break;
    case 2:
        f[0] = sin(t) + 0.5 * cos(t) - 0.5 * (t + 1.0) * exp(-t) + p->ints[0];
        break;
    default:
        f[0] = 1.0 - p->ints[0];
    }
    return 0;
}

static int integrand(double t, double tp, const double *yp, const double *ip, double *g,
                     void *par)
{
    prob *p = par;
    (void)ip;
    g[0] = p->kind == 2 ? (t - tp) * exp(tp - t) * yp[0] : yp[0];
    return 0;
}

static int kernel(double lag, double *kv, void *par)
{
    (void)par;
    kv[0] = exp(-lag);
    return 0;
}

static double exact(int kind, double t)
{
    const double w = sqrt(3.0) / 2.0;
    switch (kind) {
    case 1:
        return exp(-t / 2.0) * (cos(w * t) + sin(w * t) / (2.0 * w));
    case 2:
        return sin(t);
    case 3:
        return exp(3.14159265358979323846 * t) * erfc(sqrt(3.14159265358979323846 * t));
    default:
        return exp(-t);
    }
}

/* the largest error over the grid of h on [0, T] */
typedef struct err_ctx {
    int kind;
    double err;
} err_ctx;

static int track(long k, double t, const double *y, void *ctx)
{
    err_ctx *e = ctx;
    (void)k;
    const double d = fabs(y[0] - exact(e->kind, t));
    if (d > e->err)
        e->err = d;
    return 0;
}

static double solve_error(int kind, double h, double T, long max_points, double *last)
{
    prob p = {{0.0}, kind};
    dyn_volterra v = {1,      kind == 1 ? ODE1 : INT1, 1, kind == 3 ? MUHALF : MU0,
                      kind == 1 ? CONV : NOCONV, rhs, integrand, kernel, p.ints, &p};
    const long steps = lround(T / h);
    double *work = malloc(dyn_volterra_work_size(1, 1, max_points) * sizeof *work);
    assert_non_null(work);
    err_ctx e = {kind, 0.0};
    dyn_volterra_opts o = {0};
    o.max_points = max_points;
    o.output = track;
    o.output_ctx = &e;
    dyn_volterra_result res;
    const double y0[1] = {kind == 1 ? 1.0 : 0.0}; /* an integral state's value is computed */
    double y[1];
    assert_int_equal(dyn_volterra_solve(&v, 0.0, h, steps, y0, y, work, &o, &res), DYN_OK);
    assert_int_equal(res.r.stats.steps, steps);
    if (last)
        *last = y[0];
    free(work);
    return e.err;
}

/* the errors at h, h/2, h/4 fall by 2^order (within tol), and the finest is below bound */
static void check_order(int kind, double h, double T, double order, double tol, double bound)
{
    double e[3];
    for (int i = 0; i < 3; i++)
        e[i] = solve_error(kind, h / (1 << i), T, 0, NULL);
    for (int i = 0; i < 2; i++) {
        const double p = log2(e[i] / e[i + 1]);
        print_message("kind %d: error %.3e -> %.3e, observed order %.3f\n", kind, e[i],
                      e[i + 1], p);
        assert_true(fabs(p - order) < tol);
    }
    assert_true(e[2] < bound);
}

static void test_exponential(void **state)
{
    (void)state;
    check_order(0, 0.02, 2.0, 2.0, 0.05, 1e-5);
}

static void test_convolution_ode_pair(void **state)
{
    (void)state;
    check_order(1, 0.02, 4.0, 2.0, 0.05, 1e-5);
}

static void test_kernel_of_t_and_tprime(void **state)
{
    (void)state;
    check_order(2, 0.05, 6.0, 2.0, 0.1, 1e-4);
}

static void test_abel_kernel(void **state)
{
    (void)state;
    /* u = 1 - 2 sqrt(t) + O(t) near 0: the largest error, at the first steps, is of order 1 */
    check_order(3, 0.01, 2.0, 1.0, 0.1, 3e-3);
    /* at t = 2, away from it, the rule's order 2 - mu = 1.5 */
    double e[4];
    for (int i = 0; i < 4; i++) {
        double u;
        solve_error(3, 0.01 / (1 << i), 2.0, 0, &u);
        e[i] = fabs(u - exact(3, 2.0));
    }
    for (int i = 0; i < 3; i++) {
        const double p = log2(e[i] / e[i + 1]);
        print_message("Abel at t = 2: error %.3e -> %.3e, observed order %.3f\n", e[i],
                      e[i + 1], p);
        assert_true(fabs(p - 1.5) < 0.06);
    }
    assert_true(e[3] < 3e-7);
}

static void test_bounded_memory(void **state)
{
    (void)state;
    /* M = 200 points of h = 0.01: the integral covers the last 2 time units */
    double u;
    solve_error(0, 0.01, 80.0, 200, &u);
    assert_true(fabs(u - 1.0 / (1.0 + 200 * 0.01)) < 1e-12);
    prob p = {{0.0}, 0};
    dyn_volterra v = {1, INT1, 1, MU0, NOCONV, rhs, integrand, kernel, p.ints, &p};
    double *work = malloc(dyn_volterra_work_size(1, 1, 400) * sizeof *work);
    assert_non_null(work);
    dyn_volterra_opts o = {0};
    o.max_points = 200;
    dyn_volterra_result res;
    const double y0[1] = {0.0};
    assert_int_equal(dyn_volterra_solve(&v, 0.0, 0.01, 300, y0, NULL, work, &o, &res), DYN_OK);
    assert_true(fabs(res.forgot - 2.01) < 1e-12); /* the first step without t = 0 */
    o.max_points = 400;
    assert_int_equal(dyn_volterra_solve(&v, 0.0, 0.01, 300, y0, NULL, work, &o, &res), DYN_OK);
    assert_true(isnan(res.forgot));
    free(work);
}

static void test_refusals(void **state)
{
    (void)state;
    prob p = {{0.0}, 0};
    const double mu1[1] = {1.0};
    dyn_volterra v = {1, INT1, 1, mu1, NOCONV, rhs, integrand, kernel, p.ints, &p};
    double *work = malloc(dyn_volterra_work_size(1, 1, 10) * sizeof *work);
    assert_non_null(work);
    dyn_volterra_opts o = {0};
    o.max_points = 10;
    dyn_volterra_result res;
    const double y0[1] = {0.0};
    assert_int_equal(dyn_volterra_solve(&v, 0.0, 0.1, 3, y0, NULL, work, &o, &res), DYN_ERR_ARG);
    assert_non_null(strstr(res.r.message, "0 <= m < 1"));
    free(work);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_exponential),
        cmocka_unit_test(test_convolution_ode_pair),
        cmocka_unit_test(test_kernel_of_t_and_tprime),
        cmocka_unit_test(test_abel_kernel),
        cmocka_unit_test(test_bounded_memory),
        cmocka_unit_test(test_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
