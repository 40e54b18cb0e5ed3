/* SPDX-License-Identifier: BSD-3-Clause */
/* test_cart.c — the three-wheeled cart of homework problem 4 (dynkit/cart.h), its force
 * tables and the CSV table reader (dynkit/io.h), and the CLI commands around them.
 *
 * Physics and numbers that can fail: the non-holonomic constraint (the seed's initial state
 * satisfies it; RK4 keeps it to rounding, and the drift of Heun shrinks like h^2); inverse
 * dynamics fed back into the forward model reproduces the accelerations; the prescribed
 * motion satisfies the constraint and its sY agrees with an independent quadrature;
 * dsY(0) = pi^2/2; lambda cross-checked with Newton along body y; the constraint force does
 * no work (kinetic energy = work of the force at C); the hold/linear table semantics; the
 * forward run of 4c (second order at a short horizon, the open-loop instability with its
 * predicted growth rate, the homework's run far off the prescribed path but not rounding
 * noise, and convergent for a fixed table); the CLI end to end, bit for bit with the
 * library, and its exit status 2 for bad input.
 */
#define _POSIX_C_SOURCE 200809L /* system, mkdtemp, unlink for the CLI tests */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dynkit/dynkit.h"
#include "test_cli_run.h"

/* Fail with both values when |a - b| > tol. */
#define assert_close(a, b, tol)                                                              \
    do {                                                                                     \
        double a_ = (a), b_ = (b), t_ = (tol);                                               \
        if (!(fabs(a_ - b_) <= t_)) {                                                        \
            print_error("%s = %.17g, %s = %.17g, |diff| = %.3g > %.3g\n", #a, a_, #b, b_,    \
                        fabs(a_ - b_), t_);                                                  \
            fail();                                                                          \
        }                                                                                    \
    } while (0)

/* Fail with a message when cond is false. */
#define CHECK(cond, ...)                                                                     \
    do {                                                                                     \
        if (!(cond)) {                                                                       \
            print_error(__VA_ARGS__);                                                        \
            print_error("\n");                                                               \
            fail();                                                                          \
        }                                                                                    \
    } while (0)

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

/* ---- helpers ---- */

static const double V0 = 20.0, F = 2.0, TS = 0.01;
static const long N_HW = 500;

static void default_par(dyn_cart_par *p)
{
    char err[256];
    assert_int_equal(dyn_model_default_params(&dyn_model_cart, p, err, sizeof err), 0);
}

static double uniform(uint64_t *s, double lo, double hi)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    uint64_t x = *s * 2685821657736338717ULL;
    return lo + (hi - lo) * ((double)(x >> 11) * (1.0 / 9007199254740992.0));
}

/* Fixed-step solve of a 6-state cart (or any n <= 8 system), returning the final state. */
static int solve(const char *method, dyn_rhs_fn f, int n, void *par, double t0, double t1,
                 double h, const double *y0, double *y, const dyn_fixed_opts *opts)
{
    double work[256];
    dyn_system sys = {f, n, par};
    dyn_result res;
    const dyn_tableau *m = dyn_method_find(method);
    assert_non_null(m);
    assert_true(dyn_fixed_work_size(m, n) <= sizeof work / sizeof work[0]);
    return dyn_fixed_solve(m, &sys, t0, t1, h, y0, y, work, opts, &res);
}

/* Largest |constraint residual| over the samples of a run. */
typedef struct residual_watch {
    const dyn_cart_par *p;
    double max_residual;
} residual_watch;

static int watch_residual(long k, double t, const double *y, void *ctx)
{
    residual_watch *w = ctx;
    (void)k;
    (void)t;
    w->max_residual = fmax(w->max_residual, fabs(dyn_cart_constraint_residual(w->p, y)));
    return 0;
}

static double max_residual_of_run(const char *method, double h)
{
    dyn_cart_par p;
    default_par(&p);
    residual_watch w = {&p, 0.0};
    dyn_fixed_opts opts = {0};
    opts.output = watch_residual;
    opts.output_ctx = &w;
    double y[6];
    assert_int_equal(solve(method, dyn_cart_rhs, 6, &p, dyn_model_cart.t0, dyn_model_cart.t1, h,
                           dyn_model_cart.y0, y, &opts),
                     DYN_OK);
    return w.max_residual;
}

/* ---- the model and its constraint ---- */

static void test_model_registered(void **state)
{
    (void)state;
    const dyn_model *m = dyn_model_find("cart");
    assert_ptr_equal(m, &dyn_model_cart);
    static const char *const names[] = {"sX", "sY", "theta", "dsX", "dsY", "omega"};
    assert_int_equal(m->n_states, 6);
    for (int i = 0; i < 6; i++)
        assert_string_equal(m->states[i].name, names[i]);
    assert_int_equal(m->n_inputs, 2);
    assert_string_equal(m->inputs[0].name, "Fx");
    assert_string_equal(m->inputs[1].name, "Fy");
    /* adaptive by default (safe for any span); the homework's heun is asked for by name */
    assert_string_equal(m->method, "dp45");
    assert_true(m->rtol == 1e-8 && m->atol == 1e-10);
    assert_true(m->step == 0.04 && m->t0 == 0.0 && m->t1 == 10.0);
    dyn_cart_par p;
    default_par(&p);
    assert_true(p.m == 20.0 && p.length_cart == 2.0 && p.width_cart == 1.0);
    assert_true(p.Fx == -50.0 && p.Fy == 0.0 && p.mu == 0.7 && p.g == 9.81);
    assert_close(p.Is, 20.0 / 12.0 * 5.0, 1e-14); /* m (l^2 + d^2) / 12 */
    /* Is follows m, l and d */
    p.width_cart = 3.0;
    assert_int_equal(dyn_cart_prepare(&p, NULL, 0), 0);
    assert_close(p.Is, 20.0 / 12.0 * 13.0, 1e-14);
    char err[128];
    p.m = -1.0;
    assert_int_not_equal(dyn_cart_prepare(&p, err, sizeof err), 0);
    assert_non_null(strstr(err, "m must be"));
}

static void test_seed_initial_state_satisfies_constraint(void **state)
{
    (void)state;
    dyn_cart_par p;
    default_par(&p);
    /* 2 cos 0 - 2 sin 0 - (2/2) 2 = 0 exactly; with the OCR's "1/2" it would be 1 */
    assert_true(dyn_cart_constraint_residual(&p, dyn_model_cart.y0) == 0.0);
    assert_true(dyn_cart_constraint_dsY(&p, 0.0, 2.0, 2.0) == 2.0);
}

/* A ddq = b holds for the closed-form accelerations (rows of the seed's matrix). */
static void test_accelerations_solve_the_seed_system(void **state)
{
    (void)state;
    dyn_cart_par p;
    default_par(&p);
    uint64_t s = 0x9e3779b97f4a7c15ULL;
    for (int trial = 0; trial < 200; trial++) {
        double th = uniform(&s, -4, 4), dsX = uniform(&s, -20, 20), dsY = uniform(&s, -20, 20);
        double om = uniform(&s, -5, 5), Fx = uniform(&s, -500, 500), Fy = uniform(&s, -500, 500);
        double a[3];
        dyn_cart_accelerations(&p, th, dsX, dsY, om, Fx, Fy, a);
        const double m = p.m, l = p.length_cart, k = 2 * p.Is / l, sn = sin(th), c = cos(th);
        assert_close(m * a[0] - k * sn * a[2], Fx * c - 2 * Fy * sn, 1e-11);
        assert_close(m * a[1] + k * c * a[2], Fx * sn + 2 * Fy * c, 1e-11);
        assert_close(sn * a[0] - c * a[1] + l / 2 * a[2], -dsX * om * c - dsY * om * sn, 1e-11);
    }
}

static void test_rk4_keeps_the_constraint(void **state)
{
    (void)state;
    /* The constraint enters only at acceleration level, so a run keeps it up to the
     * truncation error: RK4 at a small step keeps it to rounding over the default run. */
    double r = max_residual_of_run("rk4", 1e-3);
    print_message("rk4, h = 1e-3, 0..10 s: max |constraint residual| = %.3g m/s\n", r);
    CHECK(r < 1e-9, "rk4 residual %.3g", r);
    /* Heun's drift shrinks like h^2 (ratios 4.9, 3.8, 3.9, 3.9 from h = 0.02 down) */
    double prev = max_residual_of_run("heun", 0.01);
    print_message("heun h = 0.01: max residual %.3g\n", prev);
    for (double h = 0.005; h >= 0.00125; h /= 2) {
        double cur = max_residual_of_run("heun", h);
        print_message("heun h = %g: max residual %.3g (ratio %.2f)\n", h, cur, prev / cur);
        CHECK(prev / cur > 3.5 && prev / cur < 4.5, "h = %g: ratio %.3g", h, prev / cur);
        prev = cur;
    }
}

/* lambda: the output equals Fy - 2 Is domega / l, and Newton along body y gives the same
 * force independently: m a_y = Fy + lambda with a_y = -sin(theta) ddsX + cos(theta) ddsY. */
static void test_lambda_cross_check(void **state)
{
    (void)state;
    dyn_cart_par p;
    default_par(&p);
    const dyn_model *m = &dyn_model_cart;
    const int i_lambda = dyn_model_output_index(m, "lambda");
    const int i_Fy = dyn_model_output_index(m, "Fy");
    const int i_res = dyn_model_output_index(m, "constraint_residual");
    const int i_slip = dyn_model_output_index(m, "slip_margin");
    assert_true(i_lambda >= 0 && i_Fy >= 0 && i_res >= 0 && i_slip >= 0);
    uint64_t s = 12345;
    for (int trial = 0; trial < 200; trial++) {
        p.Fx = uniform(&s, -300, 300);
        p.Fy = uniform(&s, -300, 300);
        double y[6] = {uniform(&s, -5, 5), uniform(&s, -5, 5), uniform(&s, -3, 3),
                       uniform(&s, -20, 20), 0, uniform(&s, -5, 5)};
        y[4] = dyn_cart_constraint_dsY(&p, y[2], y[3], y[5]);
        double out[8], dydt[6];
        assert_int_equal(m->compute_outputs(0.0, y, &p, out), 0);
        assert_int_equal(dyn_cart_rhs(0.0, y, dydt, &p), 0);
        assert_true(out[i_Fy] == p.Fy);
        assert_true(out[i_lambda] == p.Fy - 2 * p.Is * dydt[5] / p.length_cart);
        const double ay = -sin(y[2]) * dydt[3] + cos(y[2]) * dydt[4];
        assert_close(out[i_lambda], p.m * ay - p.Fy, 1e-10);
        /* and Euler about S: Is domega = (l/2) (Fy - lambda) */
        assert_close(p.Is * dydt[5], p.length_cart / 2 * (p.Fy - out[i_lambda]), 1e-10);
        assert_close(out[i_res], 0.0, 1e-13);
        assert_true(out[i_slip] == dyn_cart_friction_limit(&p) - fabs(out[i_lambda]));
        const char *w = m->warn(0.0, y, &p);
        assert_true((w != NULL) == (fabs(out[i_lambda]) > dyn_cart_friction_limit(&p)));
    }
    assert_close(dyn_cart_friction_limit(&p), 0.7 * 2.0 / 3.0 * 20 * 9.81, 1e-12);
}

/* Energy: the constraint force is lateral at the rear axle, whose lateral velocity is zero,
 * so it does no work: KE(t) - KE(0) = integral of F_C . v_C dt. The work is integrated as
 * a seventh state by the same RK4 run. */
static int rhs_with_work(double t, const double *y, double *dydt, void *par)
{
    const dyn_cart_par *p = par;
    double Fx, Fy;
    dyn_cart_rhs(t, y, dydt, (void *)p);
    dyn_cart_forces_at(p, t, &Fx, &Fy);
    const double s = sin(y[2]), c = cos(y[2]);
    const double u = y[3] * c + y[4] * s;                    /* v_S along body x */
    const double v = -y[3] * s + y[4] * c + p->length_cart / 2 * y[5]; /* v_C along body y */
    dydt[6] = Fx * u + Fy * v;
    return 0;
}

static void check_energy_balance(dyn_cart_par *p, const double *y0_6, double t1, double h)
{
    double y0[7], y[7];
    memcpy(y0, y0_6, 6 * sizeof *y0);
    y0[6] = 0.0;
    assert_int_equal(solve("rk4", rhs_with_work, 7, p, 0.0, t1, h, y0, y, NULL), DYN_OK);
    const double dKE = dyn_cart_kinetic_energy(p, y) - dyn_cart_kinetic_energy(p, y0);
    print_message("energy: KE change %.10g J, work of F_C %.10g J, difference %.3g J\n", dKE,
                  y[6], dKE - y[6]);
    assert_close(dKE, y[6], 1e-6);
    CHECK(fabs(dKE) > 1.0, "the test needs a run where the energy changes (%g J)", dKE);
}

static void test_constraint_force_does_no_work(void **state)
{
    (void)state;
    dyn_cart_par p;
    default_par(&p);
    /* the seed's run: constant Fx = -50 N */
    check_energy_balance(&p, dyn_model_cart.y0, 10.0, 1e-3);
    /* a steering force as well */
    p.Fy = -50.0;
    check_energy_balance(&p, dyn_model_cart.y0, 10.0, 1e-3);
    /* a smooth time-varying force: a table read linearly, sampled finely */
    enum { ROWS = 201 };
    static double tab[ROWS * 3];
    for (int k = 0; k < ROWS; k++) {
        double t = 0.01 * k;
        tab[3 * k] = t;
        tab[3 * k + 1] = 80 * sin(3 * t);
        tab[3 * k + 2] = 40 * cos(2 * t) - 20;
    }
    assert_int_equal(dyn_cart_set_forces(&p, tab, ROWS, DYN_INTERP_LINEAR, NULL, 0), 0);
    check_energy_balance(&p, dyn_model_cart.y0, 2.0, 1e-3);
}

/* ---- inverse dynamics and the prescribed motion (4a, 4b) ---- */

static void test_initial_dsY_is_pi2_over_2(void **state)
{
    (void)state;
    dyn_cart_par p;
    default_par(&p);
    double y[6], a[3];
    assert_int_equal(dyn_cart_prescribed(&p, V0, F, 0.0, y, a), 0);
    /* dsY(0) = (l/2) omega(0) = 1 * (pi/8) (2 pi 2) = pi^2/2 */
    assert_close(y[4], DYN_PI * DYN_PI / 2, 1e-14);
    assert_close(y[5], DYN_PI * DYN_PI / 2, 1e-14);
    assert_true(y[0] == 0.0 && y[1] == 0.0 && y[2] == 0.0 && y[3] == -V0);
    assert_true(!signbit(y[0])); /* +0, so "--init sX=0" reproduces it */
    print_message("4a: dsY(0) = %.17g m/s (pi^2/2 = %.17g)\n", y[4], DYN_PI * DYN_PI / 2);
}

/* Adaptive Simpson: an independent quadrature of dsY for sY. */
typedef struct dsY_fn {
    const dyn_cart_par *p;
} dsY_fn;

static double dsY_at(const dsY_fn *f, double t)
{
    double y[6];
    dyn_cart_prescribed(f->p, V0, F, t, y, NULL);
    return y[4];
}

static double simpson(const dsY_fn *f, double a, double b, double fa, double fm, double fb,
                      double whole, double tol, int depth)
{
    const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
    const double flm = dsY_at(f, lm), frm = dsY_at(f, rm);
    const double left = (m - a) / 6 * (fa + 4 * flm + fm), right = (b - m) / 6 * (fm + 4 * frm + fb);
    if (depth <= 0 || fabs(left + right - whole) <= 15 * tol)
        return left + right + (left + right - whole) / 15;
    return simpson(f, a, m, fa, flm, fm, left, tol / 2, depth - 1) +
           simpson(f, m, b, fm, frm, fb, right, tol / 2, depth - 1);
}

static void test_prescribed_motion(void **state)
{
    (void)state;
    dyn_cart_par p;
    default_par(&p);
    dsY_fn fn = {&p};
    const double te = (double)(N_HW - 1) * TS;
    for (int j = 0; j <= 40; j++) {
        const double t = te * j / 40.0;
        double y[6], a[3];
        assert_int_equal(dyn_cart_prescribed(&p, V0, F, t, y, a), 0);
        /* the constraint holds */
        assert_close(dyn_cart_constraint_residual(&p, y), 0.0, 1e-13);
        /* the prescribed coordinates */
        assert_close(y[0], -V0 * t, 1e-13);
        assert_close(y[2], DYN_PI / 8 * sin(2 * DYN_PI * F * t), 1e-15);
        /* the derivatives by central differences (h = 1e-5: error ~1e-9) */
        const double h = 1e-5;
        double yp[6], ym[6];
        dyn_cart_prescribed(&p, V0, F, t + h, yp, NULL);
        dyn_cart_prescribed(&p, V0, F, t - h, ym, NULL);
        for (int i = 0; i < 3; i++)
            assert_close((yp[i] - ym[i]) / (2 * h), y[i + 3], 2e-8 * (1 + fabs(y[i + 3])));
        for (int i = 0; i < 3; i++)
            assert_close((yp[i + 3] - ym[i + 3]) / (2 * h), a[i], 2e-6 * (1 + fabs(a[i])));
        /* sY against adaptive Simpson of dsY from 0 */
        if (t > 0) {
            const double f0 = dsY_at(&fn, 0), fm = dsY_at(&fn, t / 2), f1 = dsY_at(&fn, t);
            const double ref = simpson(&fn, 0, t, f0, fm, f1, t / 6 * (f0 + 4 * fm + f1), 1e-13,
                                       40);
            assert_close(y[1], ref, 1e-11);
        }
    }
    /* f = 0: straight backwards, sY = 0 */
    double y[6];
    assert_int_equal(dyn_cart_prescribed(&p, V0, 0.0, 3.0, y, NULL), 0);
    assert_true(y[1] == 0.0 && y[2] == 0.0 && y[4] == 0.0);
    assert_int_not_equal(dyn_cart_prescribed(&p, V0, -1.0, 3.0, y, NULL), 0);
    assert_int_not_equal(dyn_cart_prescribed(&p, NAN, F, 3.0, y, NULL), 0);
}

/* Inverse dynamics fed back into the forward model reproduces the accelerations: at the
 * prescribed states, and at random states with accelerations that satisfy the constraint. */
static void test_inverse_then_forward(void **state)
{
    (void)state;
    dyn_cart_par p;
    default_par(&p);
    for (long k = 0; k < N_HW; k++) {
        double y[6], a[3], dydt[6];
        dyn_cart_prescribed(&p, V0, F, (double)k * TS, y, a);
        dyn_cart_inverse_forces(&p, y[2], a[0], a[1], a[2], &p.Fx, &p.Fy);
        dyn_cart_rhs(0.0, y, dydt, &p);
        for (int i = 0; i < 3; i++) {
            assert_true(dydt[i] == y[i + 3]);
            assert_close(dydt[i + 3], a[i], 1e-10);
        }
    }
    uint64_t s = 777;
    for (int trial = 0; trial < 200; trial++) {
        double th = uniform(&s, -1.4, 1.4), dsX = uniform(&s, -20, 20), om = uniform(&s, -5, 5);
        double y[6] = {0, 0, th, dsX, dyn_cart_constraint_dsY(&p, th, dsX, om), om};
        double ddsX = uniform(&s, -50, 50), domega = uniform(&s, -50, 50);
        /* ddsY from the differentiated constraint (third row of A ddq = b) */
        double ddsY = (sin(th) * ddsX + p.length_cart / 2 * domega +
                       om * (dsX * cos(th) + y[4] * sin(th))) / cos(th);
        double dydt[6];
        dyn_cart_inverse_forces(&p, th, ddsX, ddsY, domega, &p.Fx, &p.Fy);
        dyn_cart_rhs(0.0, y, dydt, &p);
        assert_close(dydt[3], ddsX, 1e-10 * (1 + fabs(ddsX)));
        assert_close(dydt[4], ddsY, 1e-10 * (1 + fabs(ddsY)));
        assert_close(dydt[5], domega, 1e-10 * (1 + fabs(domega)));
    }
}

static void test_force_table(void **state)
{
    (void)state;
    dyn_cart_par p;
    default_par(&p);
    static double tab[500 * 3];
    char err[256];
    assert_int_equal(dyn_cart_force_table(&p, V0, F, N_HW, TS, tab, err, sizeof err), 0);
    for (long k = 0; k < N_HW; k++) {
        double y[6], a[3], Fx, Fy;
        assert_true(tab[3 * k] == (double)k * TS);
        dyn_cart_prescribed(&p, V0, F, tab[3 * k], y, a);
        dyn_cart_inverse_forces(&p, y[2], a[0], a[1], a[2], &Fx, &Fy);
        assert_true(tab[3 * k + 1] == Fx && tab[3 * k + 2] == Fy);
    }
    /* at t = 0 (theta = 0, ddsX = 0): Fx = 0, Fy = (m ddsY)/2 = m omega dsX / 2 */
    assert_close(tab[1], 0.0, 1e-12);
    assert_close(tab[2], p.m * (DYN_PI * DYN_PI / 2) * (-V0) / 2, 1e-10);
    print_message("4b: final forces at te = %.17g s: Fx = %.17g N, Fy = %.17g N\n",
                  tab[3 * (N_HW - 1)], tab[3 * (N_HW - 1) + 1], tab[3 * (N_HW - 1) + 2]);
    assert_int_not_equal(dyn_cart_force_table(&p, V0, F, 0, TS, tab, err, sizeof err), 0);
    assert_non_null(strstr(err, "N"));
    assert_int_not_equal(dyn_cart_force_table(&p, V0, F, 5, -TS, tab, err, sizeof err), 0);
    assert_non_null(strstr(err, "Ts"));
}

/* ---- reading a force table: hold and linear ---- */

static void test_table_hold_and_linear(void **state)
{
    (void)state;
    dyn_cart_par p;
    default_par(&p);
    const double Ts = 0.1;
    double tab[5 * 3];
    for (int k = 0; k < 5; k++) {
        tab[3 * k] = k * Ts;
        tab[3 * k + 1] = 10.0 * (k + 1);
        tab[3 * k + 2] = -100.0 * (k + 1);
    }
    double Fx, Fy;
    /* no table: the constants */
    dyn_cart_forces_at(&p, 0.3, &Fx, &Fy);
    assert_true(Fx == -50.0 && Fy == 0.0);
    assert_int_equal(dyn_cart_set_forces(&p, tab, 5, DYN_INTERP_HOLD, NULL, 0), 0);
    assert_true(p.forces_dt == Ts * 4 / 4);
    /* hold: the nearest sample, the homework's index = round(t/Ts) */
    const double ts[] = {0.0, 0.04, 0.049, 0.051, 0.1, 0.149, 0.151, 0.3499, 0.3501, 0.4};
    for (size_t i = 0; i < sizeof ts / sizeof ts[0]; i++) {
        long k = lround(ts[i] / Ts);
        dyn_cart_forces_at(&p, ts[i], &Fx, &Fy);
        CHECK(Fx == tab[3 * k + 1] && Fy == tab[3 * k + 2], "hold at t = %g: Fx = %g, want %g",
              ts[i], Fx, tab[3 * k + 1]);
    }
    /* a tie goes where round() goes: t/Ts = 2.5 exactly -> 3 */
    dyn_cart_forces_at(&p, 0.25, &Fx, &Fy);
    assert_true(Fx == tab[3 * lround(0.25 / Ts) + 1]);
    /* outside the table the end values are held */
    dyn_cart_forces_at(&p, -1.0, &Fx, &Fy);
    assert_true(Fx == 10.0 && Fy == -100.0);
    dyn_cart_forces_at(&p, 7.0, &Fx, &Fy);
    assert_true(Fx == 50.0 && Fy == -500.0);
    /* linear: exact at the samples, the mean half way, ends held */
    assert_int_equal(dyn_cart_set_forces(&p, tab, 5, DYN_INTERP_LINEAR, NULL, 0), 0);
    for (int k = 0; k < 5; k++) {
        dyn_cart_forces_at(&p, tab[3 * k], &Fx, &Fy);
        assert_true(Fx == tab[3 * k + 1] && Fy == tab[3 * k + 2]);
    }
    dyn_cart_forces_at(&p, 0.15, &Fx, &Fy);
    assert_close(Fx, 25.0, 1e-12);
    assert_close(Fy, -250.0, 1e-11);
    dyn_cart_forces_at(&p, 0.325, &Fx, &Fy);
    assert_close(Fx, 42.5, 1e-12);
    dyn_cart_forces_at(&p, -1.0, &Fx, &Fy);
    assert_true(Fx == 10.0);
    dyn_cart_forces_at(&p, 9.0, &Fx, &Fy);
    assert_true(Fx == 50.0);
    /* non-uniform table: nearest sample by time, ties to the later one */
    double nu[3 * 3] = {0.0, 1.0, 0.0, 0.25, 2.0, 0.0, 0.75, 3.0, 0.0};
    assert_int_equal(dyn_cart_set_forces(&p, nu, 3, DYN_INTERP_HOLD, NULL, 0), 0);
    assert_true(p.forces_dt == 0.0);
    const double t_nu[] = {0.12, 0.13, 0.49, 0.51, 0.5, 0.9};
    const double want[] = {1.0, 2.0, 2.0, 3.0, 3.0, 3.0};
    for (int i = 0; i < 6; i++) {
        dyn_cart_forces_at(&p, t_nu[i], &Fx, &Fy);
        CHECK(Fx == want[i], "non-uniform hold at t = %g: %g, want %g", t_nu[i], Fx, want[i]);
    }
    /* a single row: constant */
    assert_int_equal(dyn_cart_set_forces(&p, tab, 1, DYN_INTERP_LINEAR, NULL, 0), 0);
    dyn_cart_forces_at(&p, 0.3, &Fx, &Fy);
    assert_true(Fx == 10.0);
    /* bad tables are refused and leave the parameters alone */
    char err[256];
    double bad[2 * 3] = {0.0, 1.0, 1.0, 0.0, 2.0, 2.0};
    assert_int_equal(dyn_cart_set_forces(&p, bad, 2, DYN_INTERP_HOLD, err, sizeof err),
                     DYN_ERR_ARG);
    assert_non_null(strstr(err, "row 2"));
    bad[3] = 0.1;
    bad[4] = NAN;
    assert_int_equal(dyn_cart_set_forces(&p, bad, 2, DYN_INTERP_HOLD, err, sizeof err),
                     DYN_ERR_ARG);
    assert_non_null(strstr(err, "not finite"));
    assert_ptr_equal(p.forces, tab);
    /* detach */
    assert_int_equal(dyn_cart_set_forces(&p, NULL, 0, DYN_INTERP_HOLD, NULL, 0), 0);
    dyn_cart_forces_at(&p, 0.3, &Fx, &Fy);
    assert_true(Fx == -50.0);
}

/* ---- the forward run of 4c ---- */

/* Heun from the exact initial state with the table of N samples at Ts (step Ts), to te;
 * returns sX(te) + v0 te and the heading error, and optionally the max |lambda| of the
 * samples. */
typedef struct lambda_watch {
    const dyn_cart_par *p;
    double max_lambda;
} lambda_watch;

static int watch_lambda(long k, double t, const double *y, void *ctx)
{
    lambda_watch *w = ctx;
    double dydt[6], Fx, Fy;
    (void)k;
    dyn_cart_rhs(t, y, dydt, (void *)w->p);
    dyn_cart_forces_at(w->p, t, &Fx, &Fy);
    w->max_lambda = fmax(w->max_lambda, fabs(dyn_cart_lambda(w->p, Fy, dydt[5])));
    return 0;
}

static double forward_error(const char *method, long N, double Ts, dyn_interp interp,
                            double perturb, double *theta_error, double *max_lambda)
{
    dyn_cart_par p;
    default_par(&p);
    double *tab = malloc((size_t)N * 3 * sizeof *tab);
    assert_non_null(tab);
    assert_int_equal(dyn_cart_force_table(&p, V0, F, N, Ts, tab, NULL, 0), 0);
    assert_int_equal(dyn_cart_set_forces(&p, tab, N, interp, NULL, 0), 0);
    const double te = (double)(N - 1) * Ts;
    double y0[6], y[6], exact[6];
    dyn_cart_prescribed(&p, V0, F, 0.0, y0, NULL);
    y0[5] *= 1.0 + perturb;
    y0[4] = dyn_cart_constraint_dsY(&p, y0[2], y0[3], y0[5]);
    lambda_watch w = {&p, 0.0};
    dyn_fixed_opts opts = {0};
    opts.output = watch_lambda;
    opts.output_ctx = &w;
    assert_int_equal(solve(method, dyn_cart_rhs, 6, &p, 0.0, te, Ts, y0, y, &opts), DYN_OK);
    dyn_cart_prescribed(&p, V0, F, te, exact, NULL);
    if (theta_error)
        *theta_error = fabs(y[2] - exact[2]);
    if (max_lambda)
        *max_lambda = w.max_lambda;
    free(tab);
    return fabs(y[0] + V0 * te);
}

/* sX(te) + v0 te of a run with the homework's table (N = 500, Ts = 0.01) read linearly,
 * with steps of h. */
static double forward_error_h(const char *method, double h)
{
    dyn_cart_par p;
    default_par(&p);
    static double tab[500 * 3];
    assert_int_equal(dyn_cart_force_table(&p, V0, F, N_HW, TS, tab, NULL, 0), 0);
    assert_int_equal(dyn_cart_set_forces(&p, tab, N_HW, DYN_INTERP_LINEAR, NULL, 0), 0);
    const double te = (double)(N_HW - 1) * TS;
    double y0[6], y[6];
    dyn_cart_prescribed(&p, V0, F, 0.0, y0, NULL);
    assert_int_equal(solve(method, dyn_cart_rhs, 6, &p, 0.0, te, h, y0, y, NULL), DYN_OK);
    return fabs(y[0] + V0 * te);
}

/* Over a short horizon (0.25 s, before the instability takes over) the forward run
 * converges at second order when the table and the step are refined together. */
static void test_forward_converges_at_short_horizon(void **state)
{
    (void)state;
    const double T = 0.25;
    double prev = 0;
    for (int r = 0; r < 4; r++) {
        const double Ts = TS / (1 << r);
        const long N = lround(T / Ts) + 1;
        double e_lin = forward_error("heun", N, Ts, DYN_INTERP_LINEAR, 0, NULL, NULL);
        double e_hold = forward_error("heun", N, Ts, DYN_INTERP_HOLD, 0, NULL, NULL);
        print_message("4c at T = %g s, Ts = h = %g: |sX error| linear %.4g m, hold %.4g m\n", T,
                      Ts, e_lin, e_hold);
        /* Heun's stages sit on the samples when h = Ts: hold and linear agree (up to the
         * rounding of the stage time t + h) */
        assert_close(e_lin, e_hold, 1e-9);
        if (r > 0)
            CHECK(prev / e_lin > 3.5 && prev / e_lin < 4.5, "refinement %d: ratio %.3g", r,
                  prev / e_lin);
        prev = e_lin;
    }
}

/* Straight backwards the rear axle leads and the motion is unstable: a small yaw rate
 * grows like exp(sigma t), sigma = m v0 l / (2 Is + m l^2/2) (from domega = (2 Fy - m u
 * omega) / (2 Is/l + m l/2) with u = -v0, Fy = 0); driving forwards it decays at the same
 * rate. For the homework's cart sigma = 14.1 1/s: exp(sigma te) ~ 1e30 over 4.99 s. */
static void test_backward_motion_is_unstable(void **state)
{
    (void)state;
    dyn_cart_par p;
    default_par(&p);
    p.Fx = 0.0;
    p.Fy = 0.0;
    const double l = p.length_cart;
    const double sigma = p.m * V0 * l / (2 * p.Is + p.m * l * l / 2);
    print_message("instability rate sigma = %.6g 1/s, exp(sigma te) = %.3g\n", sigma,
                  exp(sigma * 4.99));
    assert_close(sigma, 14.117647058823529, 1e-12);
    for (int dir = -1; dir <= 1; dir += 2) {
        const double d = 1e-9, T = 0.5;
        double y0[6] = {0, 0, 0, dir * V0, l / 2 * d, d}, y[6];
        assert_int_equal(solve("rk4", dyn_cart_rhs, 6, &p, 0, T, 1e-4, y0, y, NULL), DYN_OK);
        const double growth = y[5] / d, want = exp(-dir * sigma * T);
        print_message("dsX = %+g m/s: omega(%g)/omega(0) = %.10g, exp(%+g t) = %.10g\n",
                      dir * V0, T, growth, -dir * sigma, want);
        assert_close(growth, want, 1e-6 * want);
    }
}

/* The homework's 4c run: Heun at Ts from the table of 500 samples. The instability
 * amplifies the truncation error until the cart swings around (within about half a second);
 * afterwards it drives with its axle trailing, which is stable. So sX(te) is far from
 * -v0 te, and the miss depends on the step, but it is not rounding noise: a relative change
 * of 1e-15 in the initial state changes it by far less than a micrometre. */
static void test_forward_run_of_the_homework(void **state)
{
    (void)state;
    double th_err, max_lambda;
    const double e = forward_error("heun", N_HW, TS, DYN_INTERP_HOLD, 0, &th_err, &max_lambda);
    dyn_cart_par p;
    default_par(&p);
    const double limit = dyn_cart_friction_limit(&p);
    print_message("4c: |sX(te) + v0 te| = %.17g m (heun, hold, Ts = 0.01), heading off by "
                  "%.3g rad\n",
                  e, th_err);
    print_message("4d: max |lambda| over the forward run = %.17g N, friction limit %.17g N\n",
                  max_lambda, limit);
    CHECK(e > 1.0 && th_err > 1.0, "the open-loop run should leave the path: %g m, %g rad", e,
          th_err);
    for (int j = -2; j <= 2; j++) {
        if (j == 0)
            continue;
        double ej = forward_error("heun", N_HW, TS, DYN_INTERP_HOLD, j * 1e-15, NULL, NULL);
        assert_close(ej, e, 1e-6);
    }
    /* the no-slip assumption fails: along the exact motion already */
    double exact_max = 0.0;
    static double tab[500 * 3];
    assert_int_equal(dyn_cart_force_table(&p, V0, F, N_HW, TS, tab, NULL, 0), 0);
    for (long k = 0; k < N_HW; k++) {
        double y[6], a[3];
        dyn_cart_prescribed(&p, V0, F, tab[3 * k], y, a);
        exact_max = fmax(exact_max, fabs(dyn_cart_lambda(&p, tab[3 * k + 2], a[2])));
    }
    print_message("4d: max |lambda| along the exact motion = %.17g N\n", exact_max);
    assert_true(exact_max > limit && max_lambda > limit);
}

/* For a fixed input table the forward run is an ordinary ODE solve and converges: RK4 on
 * the 500-sample table read linearly (steps of Ts/2^k, so each step sees one straight piece
 * of the input) settles at fourth order on one sX(te), and that limit is still tens of
 * metres off the path. The miss of 4c is the instability amplifying the difference between
 * the tabulated and the exact forces (and the integration error), not an integration error
 * that a finer step would remove. */
static void test_forward_run_converges_for_a_fixed_table(void **state)
{
    (void)state;
    double prev = forward_error_h("rk4", TS / 2), prev_diff = 0.0;
    for (int k = 2; k <= 5; k++) {
        const double e = forward_error_h("rk4", TS / (1 << k));
        const double diff = fabs(e - prev);
        print_message("rk4 on the fixed table (linear), h = Ts/%d: |sX(te) + v0 te| = %.15g m, "
                      "change %.3g m\n",
                      1 << k, e, diff);
        if (k > 2)
            CHECK(prev_diff / diff > 12.0, "h = Ts/%d: changes %.3g then %.3g", 1 << k,
                  prev_diff, diff);
        prev = e;
        prev_diff = diff;
    }
    CHECK(prev_diff < 1e-5 && prev > 10.0, "limit %.6g m, last change %.3g m", prev,
          prev_diff);
}

/* ---- the CSV table reader ---- */

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static int read_text_table(const char *text, unsigned flags, dyn_table *t, char *err,
                           size_t errlen)
{
    char path[512];
    snprintf(path, sizeof path, "%s/table.csv", cli_tmpdir);
    write_text(path, text);
    return dyn_table_read_file(path, flags, t, err, errlen);
}

static void test_table_read(void **state)
{
    (void)state;
    dyn_table t;
    char err[512];
    assert_int_equal(read_text_table("# forces\n\"t\", Fx ,Fy\r\n0,1.5,-2\r\n\r\n0.5, 2e3 ,"
                                     "-0.25\r\n1,3,4",
                                     DYN_TABLE_TIME_FIRST, &t, err, sizeof err),
                     DYN_OK);
    assert_int_equal(t.rows, 3);
    assert_int_equal(t.cols, 3);
    assert_string_equal(t.names[0], "t");
    assert_string_equal(t.names[1], "Fx");
    assert_int_equal(dyn_table_column(&t, "Fy"), 2);
    assert_int_equal(dyn_table_column(&t, "Fz"), -1);
    assert_true(t.data[3 * 1 + 1] == 2000.0 && t.data[3 * 1 + 2] == -0.25 &&
                t.data[3 * 2 + 2] == 4.0);
    dyn_table_free(&t);
    dyn_table_free(&t); /* safe twice */
    /* %.17g round trips */
    char text[256];
    const double v = 0.1 + 0.2, w = -1.0 / 3.0;
    snprintf(text, sizeof text, "t,x\n%.17g,%.17g\n", v, w);
    assert_int_equal(read_text_table(text, 0, &t, err, sizeof err), DYN_OK);
    assert_true(same_bits(t.data[0], v) && same_bits(t.data[1], w));
    dyn_table_free(&t);
    /* errors name the line and what is wrong */
    static const struct {
        const char *text, *expect;
        unsigned flags;
    } bad[] = {
        {"", "empty", 0},
        {"\n# only a comment\n", "empty", 0},
        {"t,Fx,Fy\n", "no data rows", 0},
        {"t,Fx,Fy\n0,1,2\n0.1,abc,2\n", ":3: field 2 (Fx) 'abc' is not a number", 0},
        {"t,Fx,Fy\n0,1,2\n0.1,2\n", ":3: 2 fields, but the header has 3 columns", 0},
        {"t,Fx,Fy\n0,1,2,3\n", ":2: 4 fields", 0},
        {"t,Fx,Fy\n0,1,\n", ":2: field 3 (Fy) is empty", 0},
        {"t,Fx,Fy\n0,nan,1\n", "not a finite number", 0},
        {"t,Fx,Fy\n0,1e999,1\n", "not a finite number", 0},
        {"t,Fx,Fy\n0,1,2\n\n0.2,1,2\n0.2,1,2\n", ":5: t = 0.2 does not increase",
         DYN_TABLE_TIME_FIRST},
        {"t,,Fy\n0,1,2\n", ":1: column 2 of the header has no name", 0},
        {"t,Fx,Fx\n0,1,2\n", "'Fx' appears twice", 0},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        int rc = read_text_table(bad[i].text, bad[i].flags, &t, err, sizeof err);
        CHECK(rc == DYN_ERR_ARG && strstr(err, bad[i].expect) && strstr(err, "table.csv"),
              "case %zu: rc %d, message '%s', expected '%s'", i, rc, err, bad[i].expect);
        assert_null(t.data);
        assert_null(t.names);
    }
    /* decreasing time is fine without the flag */
    assert_int_equal(read_text_table("a,b\n1,2\n0,3\n", 0, &t, err, sizeof err), DYN_OK);
    dyn_table_free(&t);
    char path[512];
    snprintf(path, sizeof path, "%s/does-not-exist.csv", cli_tmpdir);
    assert_int_equal(dyn_table_read_file(path, 0, &t, err, sizeof err), DYN_ERR_IO);
    assert_non_null(strstr(err, "cannot open"));
}

/* ---- the command line ---- */

/* Samples of a library run, (t, states) per row. */
static struct {
    long n;
    double rows[600][7];
} collected;

static int collect_sample(long k, double t, const double *y, void *ctx)
{
    (void)ctx;
    (void)k;
    if (collected.n >= 600)
        return 1;
    collected.rows[collected.n][0] = t;
    memcpy(&collected.rows[collected.n][1], y, 6 * sizeof *y);
    collected.n++;
    return 0;
}

/* 4a-4c through the CLI: inverse writes the table and the --init options, run --forces
 * with them reproduces the library's forward run bit for bit. */
static void test_cli_inverse_then_run(void **state)
{
    (void)state;
    cli_result r = cli_in_tmpdir("inverse cart --output forces.csv");
    CHECK(r.status == 0, "inverse: exit %d: %s", r.status, r.err);
    assert_string_equal(r.out, "");
    /* the table equals the library's, bit for bit */
    dyn_cart_par p;
    default_par(&p);
    static double tab[500 * 3];
    assert_int_equal(dyn_cart_force_table(&p, V0, F, N_HW, TS, tab, NULL, 0), 0);
    char path[512], msg[512];
    snprintf(path, sizeof path, "%s/forces.csv", cli_tmpdir);
    dyn_table t;
    assert_int_equal(dyn_table_read_file(path, DYN_TABLE_TIME_FIRST, &t, msg, sizeof msg),
                     DYN_OK);
    assert_int_equal(t.rows, N_HW);
    assert_int_equal(t.cols, 3);
    assert_string_equal(t.names[0], "t");
    assert_string_equal(t.names[1], "Fx");
    assert_string_equal(t.names[2], "Fy");
    for (long i = 0; i < 3 * N_HW; i++)
        assert_true(same_bits(t.data[i], tab[i]));
    dyn_table_free(&t);
    /* the --init options printed on stderr */
    const char *line = strstr(r.err, "  --init ");
    assert_non_null(line);
    char inits[512];
    size_t len = strcspn(line, "\n");
    assert_true(len < sizeof inits);
    memcpy(inits, line, len);
    inits[len] = '\0';
    assert_non_null(strstr(inits, "--init dsX=-20"));
    assert_non_null(strstr(r.err, "Fx = 90.08"));
    cli_free(&r);
    /* forward run: step and span from the table */
    r = cli_in_tmpdir("run cart --forces forces.csv --method heun %s --quiet", inits);
    CHECK(r.status == 0, "run: exit %d: %s", r.status, r.err);
    assert_non_null(strstr(r.err, "rear wheels would slip"));
    snprintf(path, sizeof path, "%s/out", cli_tmpdir);
    assert_int_equal(dyn_table_read_file(path, DYN_TABLE_TIME_FIRST, &t, msg, sizeof msg),
                     DYN_OK);
    cli_free(&r);
    assert_int_equal(t.rows, N_HW);
    assert_int_equal(t.cols, 7);
    /* the library's run, every sample bit for bit */
    assert_int_equal(dyn_cart_set_forces(&p, tab, N_HW, DYN_INTERP_HOLD, NULL, 0), 0);
    double y0[6], y[6];
    dyn_cart_prescribed(&p, V0, F, 0.0, y0, NULL);
    collected.n = 0;
    dyn_fixed_opts opts = {0};
    opts.output = collect_sample;
    opts.output_ctx = &collected;
    const double te = (double)(N_HW - 1) * TS;
    assert_int_equal(solve("heun", dyn_cart_rhs, 6, &p, 0.0, te, TS, y0, y, &opts), DYN_OK);
    assert_int_equal(collected.n, N_HW);
    for (long k = 0; k < N_HW; k++)
        for (int j = 0; j < 7; j++)
            CHECK(same_bits(t.data[7 * k + j], collected.rows[k][j]),
                  "row %ld column %d: CLI %.17g, library %.17g", k, j, t.data[7 * k + j],
                  collected.rows[k][j]);
    print_message("4c through the CLI: sX(te) = %.17g m, error %.17g m\n", y[0], y[0] + V0 * te);
    dyn_table_free(&t);
    /* --final with --interp linear runs too, and --step/--tspan override the table's */
    r = cli_in_tmpdir(
        "run cart --forces forces.csv --interp linear --final --step 0.005 --tspan 0:1 %s", inits);
    static const char head[] = "t,sX,sY,theta,dsX,dsY,omega\n1,";
    CHECK(r.status == 0 && strncmp(r.out, head, strlen(head)) == 0,
          "linear: %d '%s' %s", r.status, r.out, r.err);
    cli_free(&r);
}

static void test_cli_bad_input(void **state)
{
    (void)state;
    char path[512];
    snprintf(path, sizeof path, "%s/bad.csv", cli_tmpdir);
    write_text(path, "t,Fx,Fy\n0,1,2\n0.01,oops,3\n");
    cli_result r = cli_in_tmpdir("run cart --forces bad.csv");
    CHECK(r.status == 2, "malformed CSV: exit %d", r.status);
    assert_non_null(strstr(r.err, "bad.csv:3"));
    assert_non_null(strstr(r.err, "'oops' is not a number"));
    assert_string_equal(r.out, "");
    cli_free(&r);
    r = cli_in_tmpdir("run cart --forces missing.csv");
    CHECK(r.status == 2 && strstr(r.err, "cannot open missing.csv"), "missing: %d %s", r.status,
          r.err);
    cli_free(&r);
    write_text(path, "t,Fx\n0,1\n0.01,2\n");
    r = cli_in_tmpdir("run cart --forces bad.csv");
    CHECK(r.status == 2 && strstr(r.err, "no column 'Fy'") && strstr(r.err, "t,Fx,Fy"),
          "missing column: %d %s", r.status, r.err);
    cli_free(&r);
    write_text(path, "t,Fx,Fy\n0,1,2\n0.01,2,3\n0.01,2,3\n");
    r = cli_in_tmpdir("run cart --forces bad.csv");
    CHECK(r.status == 2 && strstr(r.err, "bad.csv:4") && strstr(r.err, "does not increase"),
          "time: %d %s", r.status, r.err);
    cli_free(&r);
    write_text(path, "t,Fx,Fy\n0,1,2\n0.01,2,3\n");
    r = cli_in_tmpdir("run pendulum --forces bad.csv");
    CHECK(r.status == 2 && strstr(r.err, "takes no input") && strstr(r.err, "cart"),
          "pendulum: %d %s", r.status, r.err);
    cli_free(&r);
    r = cli_in_tmpdir("run cart --forces bad.csv --interp cubic");
    CHECK(r.status == 2 && strstr(r.err, "'cubic'") && strstr(r.err, "hold, linear"),
          "interp: %d %s", r.status, r.err);
    cli_free(&r);
    r = cli_in_tmpdir("run cart --interp linear");
    CHECK(r.status == 2 && strstr(r.err, "--forces"), "interp alone: %d %s", r.status, r.err);
    cli_free(&r);
    r = cli_in_tmpdir("inverse plane");
    CHECK(r.status == 2 && strstr(r.err, "accepted: cart"), "inverse plane: %d %s", r.status,
          r.err);
    cli_free(&r);
    r = cli_in_tmpdir("inverse cart --set N=0");
    CHECK(r.status == 2 && strstr(r.err, "N=0"), "N=0: %d %s", r.status, r.err);
    cli_free(&r);
    r = cli_in_tmpdir("inverse cart --set speed=3");
    CHECK(r.status == 2 && strstr(r.err, "'speed'") && strstr(r.err, "v0"), "speed: %d %s",
          r.status, r.err);
    cli_free(&r);
}

/* inverse cart --set takes formulas of the cart's parameters as run --set does, the numbers
 * first: the tables equal those of the numbers the formulas make */
static void test_inverse_set_takes_formulas(void **state)
{
    (void)state;
    static const char *const pairs[][2] = {
        {"--set 'v0=2*g' --set g=10 --set N=20", "--set v0=20 --set g=10 --set N=20"},
        {"--set 'Ts=g/200' --set g=10 --set N=20", "--set Ts=0.05 --set g=10 --set N=20"},
    };
    for (size_t i = 0; i < sizeof pairs / sizeof pairs[0]; i++) {
        cli_result a = cli_in_tmpdir("inverse cart %s --quiet", pairs[i][0]);
        cli_result b = cli_in_tmpdir("inverse cart %s --quiet", pairs[i][1]);
        CHECK(a.status == 0 && b.status == 0 && strlen(a.out) > 100 && strcmp(a.out, b.out) == 0,
              "%s: %d %s\nagainst %s: %d", pairs[i][0], a.status, a.err, pairs[i][1], b.status);
        cli_free(&a);
        cli_free(&b);
    }
    cli_result r = cli_in_tmpdir("inverse cart --set 'v0=2*x'");
    CHECK(r.status == 2 && strstr(r.err, "v0=2*x") && strstr(r.err, "'x'") &&
              strstr(r.err, "formula of the cart's parameters") && r.out[0] == '\0',
          "unknown name in a formula: %d %s", r.status, r.err);
    cli_free(&r);
}

static void test_cli_info_and_help(void **state)
{
    (void)state;
    cli_result r = cli_in_tmpdir("info cart");
    CHECK(r.status == 0, "info: %d", r.status);
    static const char *const words[] = {"sX", "omega", "length_cart", "width_cart", "mu",
                                        "lambda", "slip_margin", "constraint_residual", "dp45",
                                        "l/2"};
    for (size_t i = 0; i < sizeof words / sizeof words[0]; i++)
        CHECK(strstr(r.out, words[i]) != NULL, "info cart lacks '%s'", words[i]);
    cli_free(&r);
    r = cli_in_tmpdir("inverse --help");
    CHECK(r.status == 0 && strstr(r.out, "Example") && strstr(r.out, "--forces"),
          "inverse --help: %d", r.status);
    cli_free(&r);
    r = cli_in_tmpdir("run --help");
    CHECK(r.status == 0 && strstr(r.out, "--forces FILE") && strstr(r.out, "--interp"),
          "run --help: %d", r.status);
    cli_free(&r);
}

static int setup(void **state)
{
    (void)state;
    return cli_make_tmpdir("cart");
}

static int teardown(void **state)
{
    (void)state;
    static const char *const files[] = {"forces.csv", "bad.csv", "table.csv", NULL};
    return cli_teardown_files(files);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_model_registered),
        cmocka_unit_test(test_seed_initial_state_satisfies_constraint),
        cmocka_unit_test(test_accelerations_solve_the_seed_system),
        cmocka_unit_test(test_rk4_keeps_the_constraint),
        cmocka_unit_test(test_lambda_cross_check),
        cmocka_unit_test(test_constraint_force_does_no_work),
        cmocka_unit_test(test_initial_dsY_is_pi2_over_2),
        cmocka_unit_test(test_prescribed_motion),
        cmocka_unit_test(test_inverse_then_forward),
        cmocka_unit_test(test_force_table),
        cmocka_unit_test(test_table_hold_and_linear),
        cmocka_unit_test(test_forward_converges_at_short_horizon),
        cmocka_unit_test(test_backward_motion_is_unstable),
        cmocka_unit_test(test_forward_run_of_the_homework),
        cmocka_unit_test(test_forward_run_converges_for_a_fixed_table),
        cmocka_unit_test(test_table_read),
        cmocka_unit_test(test_cli_inverse_then_run),
        cmocka_unit_test(test_cli_bad_input),
        cmocka_unit_test(test_inverse_set_takes_formulas),
        cmocka_unit_test(test_cli_info_and_help),
    };
    return cmocka_run_group_tests_name("cart", tests, setup, teardown);
}
