/* SPDX-License-Identifier: BSD-3-Clause */
/* Convergence and exactness of the fixed-step methods.
 *
 * - Every method reaches its classical order on problems with exact solutions: exponential
 *   decay, the harmonic oscillator, two linear systems with known matrix exponentials
 *   (rotation with decay; a triangular 3x3 chain) and a non-autonomous equation y' = t y,
 *   which also checks the stage times c_i. The observed order log2(e(h)/e(h/2)) over
 *   h, h/2, h/4, h/8 must be within 0.15 of the method's order.
 * - The homework cases: one Euler step of the pendulum, and van der Pol (mu = 1, y0 = (2, 0),
 *   h = 0.01, 1500 steps), where Euler and modified Euler equal hand-written loops bit for bit
 *   and RK4 and midpoint agree with hand-written loops to rounding.
 * - Counters: rhs_calls == stages * steps, steps == samples - 1.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "dynkit/models.h"
#include "test_util.h"

/* ---- problems with exact solutions ---- */

typedef struct problem {
    const char *name;
    int n;
    dyn_rhs_fn f;
    double t1;              /* span [0, t1] */
    double y0[3];
    void (*exact)(double t, double *y);
} problem;

static int decay_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)t, (void)par;
    dydt[0] = -y[0];
    return 0;
}
static void decay_exact(double t, double *y) { y[0] = exp(-t); }

/* x'' = -w^2 x with w = 2: x = cos(w t), v = -w sin(w t). */
#define OSC_W 2.0
static int oscillator_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)t, (void)par;
    dydt[0] = y[1];
    dydt[1] = -OSC_W * OSC_W * y[0];
    return 0;
}
static void oscillator_exact(double t, double *y)
{
    y[0] = cos(OSC_W * t);
    y[1] = -OSC_W * sin(OSC_W * t);
}

/* y' = A y, A = [-a -w; w -a]: exp(A t) (1, 0) = e^{-a t} (cos w t, sin w t). */
#define ROT_A 0.5
#define ROT_W 3.0
static int rotation_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)t, (void)par;
    dydt[0] = -ROT_A * y[0] - ROT_W * y[1];
    dydt[1] = ROT_W * y[0] - ROT_A * y[1];
    return 0;
}
static void rotation_exact(double t, double *y)
{
    y[0] = exp(-ROT_A * t) * cos(ROT_W * t);
    y[1] = exp(-ROT_A * t) * sin(ROT_W * t);
}

/* Triangular chain y1' = -y1, y2' = y1 - 2 y2, y3' = y2 - 3 y3 from (1, 0, 0). */
static int chain_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)t, (void)par;
    dydt[0] = -y[0];
    dydt[1] = y[0] - 2.0 * y[1];
    dydt[2] = y[1] - 3.0 * y[2];
    return 0;
}
static void chain_exact(double t, double *y)
{
    double e = exp(-t);
    y[0] = e;
    y[1] = e - e * e;
    y[2] = 0.5 * e * (1.0 - e) * (1.0 - e);
}

/* Non-autonomous: y' = t y, y = exp(t^2 / 2). Wrong stage times c_i lose the order. */
static int ty_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)par;
    dydt[0] = t * y[0];
    return 0;
}
static void ty_exact(double t, double *y) { y[0] = exp(0.5 * t * t); }

static const problem problems[] = {
    {"decay y' = -y", 1, decay_rhs, 1.0, {1.0}, decay_exact},
    {"harmonic oscillator", 2, oscillator_rhs, 2.0, {1.0, 0.0}, oscillator_exact},
    {"rotation with decay", 2, rotation_rhs, 1.0, {1.0, 0.0}, rotation_exact},
    {"triangular 3x3 chain", 3, chain_rhs, 2.0, {1.0, 0.0, 0.0}, chain_exact},
    {"non-autonomous y' = t y", 1, ty_rhs, 1.0, {1.0}, ty_exact},
};

/* Error norm at t1 of method m on problem p with N steps. */
static double error_at_end(const dyn_tableau *m, const problem *p, long N)
{
    double work[TEST_WORK], y[3], exact[3];
    dyn_system sys = {p->f, p->n, NULL};
    dyn_result res;
    int rc = dyn_fixed_solve(m, &sys, 0.0, p->t1, p->t1 / (double)N, p->y0, y, work, NULL, &res);
    CHECK(rc == DYN_OK, "%s on %s: status %d (%s)", m->name, p->name, rc, res.message);
    assert_int_equal(res.stats.steps, N);
    p->exact(p->t1, exact);
    return norm_diff(y, exact, p->n);
}

static void test_observed_order_matches(void **state)
{
    (void)state;
    for (int i = 0; i < dyn_method_count(); i++) {
        const dyn_tableau *m = fixed_method_at(i);
        if (!m)
            continue;
        /* Coarsest number of steps: errors well above rounding, already asymptotic. */
        const long N0 = m->order == 1 ? 200 : m->order == 2 ? 40 : 20;
        for (size_t q = 0; q < sizeof problems / sizeof problems[0]; q++) {
            const problem *p = &problems[q];
            double e[4];
            for (int r = 0; r < 4; r++)
                e[r] = error_at_end(m, p, N0 << r);
            for (int r = 0; r < 3; r++) {
                double observed = log2(e[r] / e[r + 1]);
                CHECK(fabs(observed - m->order) <= 0.15,
                      "%s on %s: errors %.3g %.3g %.3g %.3g, observed order %.3f between "
                      "N = %ld and %ld, expected %d",
                      m->name, p->name, e[0], e[1], e[2], e[3], observed, N0 << r,
                      N0 << (r + 1), m->order);
            }
        }
    }
}

/* The order is seen through the driver's stage times: with every c_i forced to 0 (a wrong
 * table that still passes the autonomous order conditions on y' = -y), y' = t y loses it. */
static void test_stage_times_matter(void **state)
{
    (void)state;
    const dyn_tableau *rk4 = dyn_method_find("rk4");
    static const double c_zero[4] = {0.0, 0.0, 0.0, 0.0};
    dyn_tableau wrong = *rk4;
    wrong.c = c_zero;
    const problem *decay = &problems[0], *ty = &problems[4];
    double good_decay = log2(error_at_end(&wrong, decay, 20) / error_at_end(&wrong, decay, 40));
    double bad_ty = log2(error_at_end(&wrong, ty, 20) / error_at_end(&wrong, ty, 40));
    assert_true(fabs(good_decay - 4.0) < 0.15);
    assert_true(bad_ty < 1.5);
}

/* ---- the homework cases ---- */

/* Homework problem 1e: one Euler step h = 0.2 of the pendulum from (0, pi/2), l = g = 9.81. */
static void test_pendulum_single_euler_step(void **state)
{
    (void)state;
    const dyn_model *model = &dyn_model_pendulum;
    dyn_pendulum_par par;
    char err[128];
    assert_int_equal(dyn_model_default_params(model, &par, err, sizeof err), 0);
    assert_true(par.l == 9.81 && par.g == 9.81 && par.m == 2.0);
    assert_true(model->y0[0] == 0.0 && model->y0[1] == DYN_PI / 2.0);
    double y[2], work[TEST_WORK];
    dyn_system sys = {dyn_pendulum_rhs, 2, &par};
    dyn_result res;
    assert_int_equal(dyn_fixed_solve(dyn_method_find("euler"), &sys, 0.0, 0.2, 0.2, model->y0, y,
                                     work, NULL, &res),
                     DYN_OK);
    const double h = 0.2, dphi0 = DYN_PI / 2.0;
    const double phi1 = 0.0 + h * dphi0; /* y + h*k, k = (dphi, -(g/l) sin 0) */
    CHECK(same_bits(y[0], phi1), "phi(0.2) = %.17g, expected %.17g", y[0], phi1);
    CHECK(same_bits(y[1], dphi0), "dphi(0.2) = %.17g, expected %.17g", y[1], dphi0);
    char text[32];
    snprintf(text, sizeof text, "%.17g", y[0]);
    assert_string_equal(text, "0.31415926535897931");
    assert_true(res.t == 0.2);
    assert_int_equal(res.stats.steps, 1);
    assert_int_equal(res.stats.rhs_calls, 1);
}

/* van der Pol right-hand side written out here, as in the homework's vanderpoldemo.m. */
static void vdp(const double *y, double mu, double *dy)
{
    dy[0] = y[1];
    dy[1] = mu * (1.0 - y[0] * y[0]) * y[1] - y[0];
}

#define VDP_STEPS 1500
#define VDP_H 0.01

/* Hand-written Integrate_X loops of the homework, on van der Pol (mu = 1, y0 = (2, 0)). */
static void hand_euler(double *y)
{
    double k1[2];
    y[0] = 2.0, y[1] = 0.0;
    for (int n = 0; n < VDP_STEPS; n++) {
        vdp(y, 1.0, k1);
        for (int q = 0; q < 2; q++)
            y[q] = y[q] + VDP_H * k1[q];
    }
}

static void hand_modified_euler(double *y)
{
    double k1[2], k2[2], yt[2];
    y[0] = 2.0, y[1] = 0.0;
    for (int n = 0; n < VDP_STEPS; n++) {
        vdp(y, 1.0, k1);
        for (int q = 0; q < 2; q++)
            yt[q] = y[q] + VDP_H * k1[q]; /* predictor */
        vdp(yt, 1.0, k2);
        for (int q = 0; q < 2; q++)
            y[q] = y[q] + 0.5 * VDP_H * (k2[q] + k1[q]); /* corrector */
    }
}

static void hand_midpoint(double *y)
{
    double k1[2], k2[2], ym[2];
    y[0] = 2.0, y[1] = 0.0;
    for (int n = 0; n < VDP_STEPS; n++) {
        vdp(y, 1.0, k1);
        for (int q = 0; q < 2; q++)
            ym[q] = y[q] + VDP_H / 2.0 * k1[q];
        vdp(ym, 1.0, k2);
        for (int q = 0; q < 2; q++)
            y[q] = y[q] + VDP_H * k2[q];
    }
}

static void hand_rk4(double *y)
{
    double k1[2], k2[2], k3[2], k4[2], Y[2];
    const double h = VDP_H;
    y[0] = 2.0, y[1] = 0.0;
    for (int n = 0; n < VDP_STEPS; n++) {
        vdp(y, 1.0, k1);
        for (int q = 0; q < 2; q++)
            Y[q] = y[q] + h / 2.0 * k1[q];
        vdp(Y, 1.0, k2);
        for (int q = 0; q < 2; q++)
            Y[q] = y[q] + h / 2.0 * k2[q];
        vdp(Y, 1.0, k3);
        for (int q = 0; q < 2; q++)
            Y[q] = y[q] + h * k3[q];
        vdp(Y, 1.0, k4);
        for (int q = 0; q < 2; q++)
            y[q] = y[q] + h / 6.0 * (k1[q] + 2.0 * k2[q] + 2.0 * k3[q] + k4[q]);
    }
}

/* Library solve of the homework's van der Pol run; counts the output samples. */
static int count_samples(long k, double t, const double *y, void *ctx)
{
    (void)k, (void)t, (void)y;
    ++*(long *)ctx;
    return 0;
}

static void library_vdp(const char *method, double h, double *y, dyn_result *res)
{
    const dyn_tableau *m = dyn_method_find(method);
    assert_non_null(m);
    dyn_vanderpol_par par = {.mu = 1.0};
    const double y0[2] = {2.0, 0.0};
    double work[TEST_WORK];
    long samples = 0;
    dyn_system sys = {dyn_vanderpol_rhs, 2, &par};
    dyn_fixed_opts opts = {0};
    opts.output = count_samples;
    opts.output_ctx = &samples;
    int rc = dyn_fixed_solve(m, &sys, 0.0, 15.0, h, y0, y, work, &opts, res);
    CHECK(rc == DYN_OK, "%s: %s", method, res->message);
    /* Counters: one sample per grid point, stages calls per step, no step past the end. */
    const long steps = (long)nearbyint(15.0 / h);
    assert_int_equal(res->stats.steps, steps);
    assert_int_equal(res->stats.samples, steps + 1);
    assert_int_equal(samples, steps + 1);
    assert_int_equal(res->stats.steps, res->stats.samples - 1);
    assert_int_equal(res->stats.rhs_calls, (long)m->stages * res->stats.steps);
    assert_true(res->t == 15.0);
}

static void test_vanderpol_euler_bitwise(void **state)
{
    (void)state;
    double lib[2], hand[2];
    dyn_result res;
    library_vdp("euler", VDP_H, lib, &res);
    hand_euler(hand);
    CHECK(same_bits(lib[0], hand[0]) && same_bits(lib[1], hand[1]),
          "euler: library (%.17g, %.17g), hand-written (%.17g, %.17g)", lib[0], lib[1], hand[0],
          hand[1]);
}

static void test_vanderpol_modified_euler_bitwise(void **state)
{
    (void)state;
    double lib[2], alias[2], hand[2];
    dyn_result res;
    library_vdp("heun", VDP_H, lib, &res);
    library_vdp("modified-euler", VDP_H, alias, &res);
    hand_modified_euler(hand);
    CHECK(same_bits(lib[0], hand[0]) && same_bits(lib[1], hand[1]),
          "heun: library (%.17g, %.17g), hand-written (%.17g, %.17g)", lib[0], lib[1], hand[0],
          hand[1]);
    assert_memory_equal(lib, alias, sizeof lib);
}

static void test_vanderpol_rk4_and_midpoint_match_hand_loops(void **state)
{
    (void)state;
    double lib[2], hand[2];
    dyn_result res;
    library_vdp("rk4", VDP_H, lib, &res);
    hand_rk4(hand);
    CHECK(max_abs_diff(lib, hand, 2) <= 1e-13, "rk4: library (%.17g, %.17g), hand (%.17g, %.17g)",
          lib[0], lib[1], hand[0], hand[1]);
    library_vdp("midpoint", VDP_H, lib, &res);
    hand_midpoint(hand);
    CHECK(max_abs_diff(lib, hand, 2) <= 1e-13,
          "midpoint: library (%.17g, %.17g), hand (%.17g, %.17g)", lib[0], lib[1], hand[0],
          hand[1]);
    double alias[2];
    library_vdp("rk2", VDP_H, alias, &res);
    assert_memory_equal(lib, alias, sizeof lib);
}

/* The methods really differ: at h = 0.01, Euler is far from RK4 (first order, 1500 steps),
 * the second-order methods much closer; a sanity check that the runs are not all one. */
static void test_vanderpol_methods_differ_as_their_orders_say(void **state)
{
    (void)state;
    double euler[2], heun[2], rk4[2], ref[2];
    dyn_result res;
    library_vdp("euler", VDP_H, euler, &res);
    library_vdp("heun", VDP_H, heun, &res);
    library_vdp("rk4", VDP_H, rk4, &res);
    library_vdp("rk4", VDP_H / 8.0, ref, &res);
    double e1 = max_abs_diff(euler, ref, 2), e2 = max_abs_diff(heun, ref, 2),
           e4 = max_abs_diff(rk4, ref, 2);
    CHECK(e1 > 1e-3 && e2 < e1 / 20.0 && e4 < e2 / 100.0,
          "errors at h = 0.01: euler %.3g, heun %.3g, rk4 %.3g", e1, e2, e4);
}

/* Two different fourth-order methods agree at a small step. */
static void test_vanderpol_rk4_rk38_cross_check(void **state)
{
    (void)state;
    double a[2], b[2];
    dyn_result res;
    library_vdp("rk4", 0.001, a, &res);
    library_vdp("rk38", 0.001, b, &res);
    double d = max_abs_diff(a, b, 2);
    CHECK(d < 1e-10 && d > 0.0, "rk4 (%.17g, %.17g) vs rk38 (%.17g, %.17g): %.3g", a[0], a[1],
          b[0], b[1], d);
}

/* Counters for every method, also over a span with a partial last step. */
static void test_counters_every_method(void **state)
{
    (void)state;
    for (int i = 0; i < dyn_method_count(); i++) {
        const dyn_tableau *m = fixed_method_at(i);
        if (!m)
            continue;
        double work[TEST_WORK], y[2];
        long samples = 0;
        dyn_system sys = {oscillator_rhs, 2, NULL};
        dyn_fixed_opts opts = {0};
        opts.output = count_samples;
        opts.output_ctx = &samples;
        dyn_result res;
        const double y0[2] = {1.0, 0.0};
        assert_int_equal(dyn_fixed_solve(m, &sys, 0.0, 1.0, 0.3, y0, y, work, &opts, &res),
                         DYN_OK);
        assert_int_equal(res.stats.steps, 4); /* 0, .3, .6, .9, 1 */
        assert_int_equal(res.stats.samples, 5);
        assert_int_equal(samples, 5);
        assert_int_equal(res.stats.rhs_calls, 4L * m->stages);
        /* Without an output callback no samples are counted, but steps still are. */
        assert_int_equal(dyn_fixed_solve(m, &sys, 0.0, 1.0, 0.25, y0, y, work, NULL, &res),
                         DYN_OK);
        assert_int_equal(res.stats.steps, 4);
        assert_int_equal(res.stats.samples, 0);
        assert_int_equal(res.stats.rhs_calls, 4L * m->stages);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_observed_order_matches),
        cmocka_unit_test(test_stage_times_matter),
        cmocka_unit_test(test_pendulum_single_euler_step),
        cmocka_unit_test(test_vanderpol_euler_bitwise),
        cmocka_unit_test(test_vanderpol_modified_euler_bitwise),
        cmocka_unit_test(test_vanderpol_rk4_and_midpoint_match_hand_loops),
        cmocka_unit_test(test_vanderpol_methods_differ_as_their_orders_say),
        cmocka_unit_test(test_vanderpol_rk4_rk38_cross_check),
        cmocka_unit_test(test_counters_every_method),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
