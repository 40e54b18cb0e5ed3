/* SPDX-License-Identifier: BSD-3-Clause */
/* test_equilibria_api.c — the library calls behind dynkit equilibria, lyapunov and steady,
 * without the eigenvalue backend: Halton's points against their radical inverses by hand;
 * the types of hand-made eigenvalue sets (nodes, foci, saddles, saddle-foci, centres,
 * saddle-centres, non-hyperbolic points; multipliers against the unit circle); every
 * equilibrium of f = (x^2 - 1, -y) in a box, sorted, and the fixed points 0 and 1 of the
 * map x -> x^2; a Gram-Schmidt QR whose diagonal multiplies to |det|; the exponents of a
 * diagonal linear system (-1 and -3) with its exact Jacobian and by differences; the
 * circular orbit of a particle in a central field (k = w^2 r^3) by dyn_steady_solve, the
 * angle found cyclic by dyn_steady_cyclic; bad arguments named. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "dynkit/equilibria.h"
#include "dynkit/lyapunov.h"
#include "dynkit/steady.h"

static void test_halton(void **state)
{
    (void)state;
    assert_true(dyn_halton(1, 0) == 0.5);
    assert_true(dyn_halton(2, 0) == 0.25);
    assert_true(dyn_halton(3, 0) == 0.75);
    assert_true(fabs(dyn_halton(1, 1) - 1.0 / 3.0) < 1e-15);
    assert_true(fabs(dyn_halton(5, 1) - 7.0 / 9.0) < 1e-15);              /* 5 = 12 in base 3 */
    assert_true(fabs(dyn_halton(7, 2) - 2.0 / 5.0 - 1.0 / 25.0) < 1e-15); /* 7 = 12_5 */
}

static void test_types(void **state)
{
    (void)state;
    static const struct {
        int k, map;
        double re[4], im[4];
        dyn_eq_type type;
        int dims[3];
    } cases[] = {
        {2, 0, {-1, -2}, {0, 0}, DYN_EQ_STABLE_NODE, {2, 0, 0}},
        {2, 0, {1, 2}, {0, 0}, DYN_EQ_UNSTABLE_NODE, {0, 2, 0}},
        {2, 0, {-1, -1}, {-2, 2}, DYN_EQ_STABLE_FOCUS, {2, 0, 0}},
        {2, 0, {1, 1}, {-2, 2}, DYN_EQ_UNSTABLE_FOCUS, {0, 2, 0}},
        {2, 0, {-1, 1}, {0, 0}, DYN_EQ_SADDLE, {1, 1, 0}},
        {3, 0, {0.1, -13, 0.1}, {-10, 0, 10}, DYN_EQ_SADDLE_FOCUS, {1, 2, 0}},
        {2, 0, {0, 0}, {-1, 1}, DYN_EQ_CENTRE, {0, 0, 2}},
        {4, 0, {-1, 0, 0, 1}, {0, -2, 2, 0}, DYN_EQ_SADDLE_CENTRE, {1, 1, 2}},
        {2, 0, {-1, 0}, {0, 0}, DYN_EQ_NONHYPERBOLIC, {1, 0, 1}},
        {2, 1, {0.5, 3}, {0, 0}, DYN_EQ_SADDLE, {1, 1, 0}},
        {2, 1, {-0.5, -0.5}, {-0.5, 0.5}, DYN_EQ_STABLE_FOCUS, {2, 0, 0}},
        {2, 1, {0.6, 0.6}, {-0.8, 0.8}, DYN_EQ_CENTRE, {0, 0, 2}},
        {1, 1, {-2}, {0}, DYN_EQ_UNSTABLE_NODE, {0, 1, 0}},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        int dims[3];
        const dyn_eq_type t =
            dyn_eq_classify(cases[c].k, cases[c].re, cases[c].im, cases[c].map, 1e-9, dims);
        if (t != cases[c].type || memcmp(dims, cases[c].dims, sizeof dims) != 0) {
            print_error("case %zu: %s (%d %d %d), expected %s\n", c, dyn_eq_type_name(t), dims[0],
                        dims[1], dims[2], dyn_eq_type_name(cases[c].type));
            fail();
        }
    }
    assert_string_equal(dyn_eq_type_name(DYN_EQ_SADDLE_CENTRE), "saddle-centre");
}

/* f = (x^2 - 1, -y): equilibria (-1, 0) and (1, 0) */
static int f_two(double t, const double *y, double *f, void *par)
{
    (void)t;
    (void)par;
    f[0] = y[0] * y[0] - 1.0;
    f[1] = -y[1];
    return 0;
}

static const dyn_var two_states[] = {{"x", "1", ""}, {"y", "1", ""}};
static const double two_y0[] = {0.3, 0.2};
static const dyn_model two_model = {.name = "two",
                                    .n_states = 2,
                                    .states = two_states,
                                    .y0 = two_y0,
                                    .par_size = sizeof(double),
                                    .rhs = f_two};

/* the map x -> x^2 (fixed points 0 and 1) */
static int f_square(double t, const double *y, double *f, void *par)
{
    (void)t;
    (void)par;
    f[0] = y[0] * y[0];
    return 0;
}

static const dyn_model square_map = {.name = "square",
                                     .n_states = 1,
                                     .states = two_states,
                                     .y0 = two_y0,
                                     .par_size = sizeof(double),
                                     .rhs = f_square};

static void test_find(void **state)
{
    (void)state;
    double par = 0.0;
    const double lo[] = {-3, -2}, hi[] = {3, 2};
    dyn_equilibria_opts o;
    memset(&o, 0, sizeof o);
    o.lo = lo;
    o.hi = hi;
    o.guess = two_y0;
    dyn_equilibria e;
    assert_int_equal(dyn_equilibria_find(&two_model, 0.0, &par, &o, &e), 0);
    assert_int_equal(e.count, 2);
    assert_int_equal(e.starts, DYN_EQUILIBRIA_STARTS + 1);
    assert_true(fabs(e.y[0] + 1.0) < 1e-14 && fabs(e.y[1]) < 1e-14);
    assert_true(fabs(e.y[2] - 1.0) < 1e-14 && fabs(e.y[3]) < 1e-14);
    assert_int_equal(e.type[0], DYN_EQ_UNCLASSIFIED); /* no solver given */
    dyn_equilibria_free(&e);
    /* a box holding one of them */
    const double lo1[] = {0, -2};
    o.lo = lo1;
    o.starts = 16;
    assert_int_equal(dyn_equilibria_find(&two_model, 0.0, &par, &o, &e), 0);
    assert_int_equal(e.count, 1);
    assert_true(fabs(e.y[0] - 1.0) < 1e-14);
    dyn_equilibria_free(&e);
    /* a map's fixed points */
    const double mlo[] = {-0.5}, mhi[] = {2};
    memset(&o, 0, sizeof o);
    o.lo = mlo;
    o.hi = mhi;
    o.map = 1;
    assert_int_equal(dyn_equilibria_find(&square_map, 0.0, &par, &o, &e), 0);
    assert_int_equal(e.count, 2);
    assert_true(fabs(e.y[0]) < 1e-14 && fabs(e.y[1] - 1.0) < 1e-14);
    dyn_equilibria_free(&e);
    /* a bad box */
    const double bad_hi[] = {-4, 2};
    o.lo = lo;
    o.hi = bad_hi;
    o.map = 0;
    assert_int_equal(dyn_equilibria_find(&two_model, 0.0, &par, &o, &e), DYN_ERR_ARG);
    assert_non_null(strstr(e.message, "the box of x"));
    dyn_equilibria_free(&e);
}

static void test_qr(void **state)
{
    (void)state;
    double Q[] = {3, 1, 4, 2}, logr[2];
    assert_int_equal(dyn_qr_log_diag(2, 2, Q, logr), 0);
    assert_true(fabs(logr[0] - log(5.0)) < 1e-15 && fabs(logr[1] - log(0.4)) < 1e-15);
    assert_true(fabs(Q[0] * Q[1] + Q[2] * Q[3]) < 1e-16); /* orthogonal columns */
    double Z[] = {1, 0, 0, 0};
    assert_int_equal(dyn_qr_log_diag(2, 2, Z, logr), -1); /* a column vanishes */
}

/* x' = -x, y' = -3 y with its Jacobian */
static int f_diag(double t, const double *y, double *f, void *par)
{
    (void)t;
    (void)par;
    f[0] = -y[0];
    f[1] = -3.0 * y[1];
    return 0;
}

static int j_diag(double t, const double *y, double *J, void *par)
{
    (void)t;
    (void)y;
    (void)par;
    J[0] = -1.0;
    J[1] = J[2] = 0.0;
    J[3] = -3.0;
    return 0;
}

static void test_lyapunov_linear(void **state)
{
    (void)state;
    dyn_model m = {.name = "diag",
                   .n_states = 2,
                   .states = two_states,
                   .y0 = two_y0,
                   .par_size = sizeof(double),
                   .rhs = f_diag,
                   .jacobian = j_diag};
    double par = 0.0, ex[2], err[2];
    dyn_lyapunov_opts o;
    memset(&o, 0, sizeof o);
    o.k = 2;
    o.t_trans = 1.0;
    o.t_avg = 20.0;
    o.tau = 0.5;
    dyn_lyapunov_info info;
    for (int exact = 1; exact >= 0; exact--) {
        o.scheme = exact ? DYN_JAC_AUTO : DYN_JAC_CENTRAL;
        assert_int_equal(dyn_lyapunov(&m, &par, 0.0, two_y0, &o, ex, err, &info), 0);
        assert_int_equal(info.exact_jacobian, exact);
        assert_true(fabs(ex[0] + 1.0) < 1e-8 && fabs(ex[1] + 3.0) < 1e-8);
        assert_int_equal(info.orthonormalizations, 40);
    }
    o.k = 3;
    assert_int_equal(dyn_lyapunov(&m, &par, 0.0, two_y0, &o, ex, err, &info), DYN_ERR_ARG);
    assert_non_null(strstr(info.message, "give 1 to 2"));
}

/* a particle in a central field k / r^2 in polar coordinates: r, th, vr, w */
static int f_orbit(double t, const double *y, double *f, void *par)
{
    (void)t;
    const double k = *(const double *)par;
    f[0] = y[2];
    f[1] = y[3];
    f[2] = y[0] * y[3] * y[3] - k / (y[0] * y[0]);
    f[3] = -2.0 * y[2] * y[3] / y[0];
    return 0;
}

static const dyn_var orbit_states[] = {
    {"r", "m", ""}, {"th", "rad", ""}, {"vr", "m/s", ""}, {"w", "rad/s", ""}};
static const dyn_param orbit_params[] = {{"k", "m^3/s^2", "", 0, 1.0}};
static const double orbit_y0[] = {2, 0, 0, 0.5};

static void test_steady_orbit(void **state)
{
    (void)state;
    const dyn_model m = {.name = "orbit",
                         .n_states = 4,
                         .states = orbit_states,
                         .y0 = orbit_y0,
                         .n_params = 1,
                         .params = orbit_params,
                         .par_size = sizeof(double),
                         .rhs = f_orbit};
    /* A at the start, by hand: th's column is zero */
    const double r = 2, w = 0.5, k = 1;
    const double A[16] = {0, 0, 1,         0, 0, 0,          0, 1, w * w + 2 * k / (r * r * r),
                          0, 0, 2 * r * w, 0, 0, -2 * w / r, 0};
    int cyclic[4];
    assert_int_equal(dyn_steady_cyclic(4, 4, NULL, A, 1e-8, cyclic), 1);
    assert_true(cyclic[1] && !cyclic[0] && !cyclic[2] && !cyclic[3]);
    double y[4], par = 1.0;
    memcpy(y, orbit_y0, sizeof y);
    const int eqs[] = {0, 2, 3};
    const dyn_steady_unknown unk[] = {{1, 0}};
    const dyn_steady_opts so = {1, unk, 3, eqs, NULL, NULL, 0.0, 0};
    dyn_steady_info info;
    assert_int_equal(dyn_steady_solve(&m, 0.0, y, &par, &so, &info), 0);
    assert_true(fabs(par - w * w * r * r * r) < 1e-12);
    assert_true(info.residual <= info.tol);
    /* the rate instead */
    par = 1.0;
    y[3] = 0.3;
    const dyn_steady_unknown unk_w[] = {{0, 3}};
    const dyn_steady_opts sw = {1, unk_w, 3, eqs, NULL, NULL, 0.0, 0};
    assert_int_equal(dyn_steady_solve(&m, 0.0, y, &par, &sw, &info), 0);
    assert_true(fabs(y[3] - sqrt(1.0 / 8.0)) < 1e-12);
    /* more unknowns than equations */
    const dyn_steady_opts too_many = {1, unk, 0, eqs, NULL, NULL, 0.0, 0};
    assert_int_equal(dyn_steady_solve(&m, 0.0, y, &par, &too_many, &info), DYN_ERR_ARG);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_halton),
        cmocka_unit_test(test_types),
        cmocka_unit_test(test_find),
        cmocka_unit_test(test_qr),
        cmocka_unit_test(test_lyapunov_linear),
        cmocka_unit_test(test_steady_orbit),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
