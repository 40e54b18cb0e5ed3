/* SPDX-License-Identifier: BSD-3-Clause */
/* test_linalg.c — the dense LU of the stiff methods (src/ode/linalg.h): random
 * well-conditioned systems are solved with a backward error at rounding level, pivoting
 * handles zero and tiny leading entries, singular and non-finite matrices are reported
 * with the failing column, and the factorisation reproduces P A = L U. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <float.h>

#include "ode/linalg.h"
#include "test_util.h"

#define NMAX 24

/* Deterministic uniform numbers in [-1, 1) (xorshift64*). */
static double rnd(uint64_t *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return (double)((*s * 2685821657736338717ULL) >> 11) * 0x1.0p-52 - 1.0;
}

static double norm_inf_mat(int n, const double *A)
{
    double best = 0.0;
    for (int i = 0; i < n; i++) {
        double s = 0.0;
        for (int j = 0; j < n; j++)
            s += fabs(A[i * n + j]);
        best = fmax(best, s);
    }
    return best;
}

static double norm_inf(int n, const double *x)
{
    double best = 0.0;
    for (int i = 0; i < n; i++)
        best = fmax(best, fabs(x[i]));
    return best;
}

/* Backward error ||A x - b|| / (||A|| ||x|| + ||b||), which partial pivoting keeps at a
 * small multiple of n eps for these matrices. */
static double backward_error(int n, const double *A, const double *x, const double *b)
{
    double r[NMAX];
    dyn_mat_vec(n, A, x, r);
    for (int i = 0; i < n; i++)
        r[i] -= b[i];
    return norm_inf(n, r) / (norm_inf_mat(n, A) * norm_inf(n, x) + norm_inf(n, b));
}

static void test_random_systems_solve_to_rounding(void **state)
{
    (void)state;
    uint64_t seed = 0x9E3779B97F4A7C15ULL;
    double A[NMAX * NMAX], LU[NMAX * NMAX], x[NMAX], b[NMAX], xs[NMAX];
    int piv[NMAX];
    for (int n = 1; n <= NMAX; n++) {
        for (int trial = 0; trial < 20; trial++) {
            /* random entries plus a diagonal shift: well conditioned, but the largest entry
             * of a column is usually off the diagonal, so pivoting is exercised */
            for (int i = 0; i < n * n; i++)
                A[i] = rnd(&seed);
            for (int i = 0; i < n; i++)
                A[i * n + i] += (trial % 2 ? 0.5 : 2.0) * (rnd(&seed) > 0 ? 1 : -1);
            for (int i = 0; i < n; i++)
                xs[i] = rnd(&seed) * 10.0;
            dyn_mat_vec(n, A, xs, b);
            memcpy(LU, A, sizeof(double) * (size_t)(n * n));
            assert_int_equal(dyn_lu_factor(n, LU, piv), 0);
            memcpy(x, b, sizeof(double) * (size_t)n);
            dyn_lu_solve(n, LU, piv, x);
            double be = backward_error(n, A, x, b);
            CHECK(be < 4.0 * n * DBL_EPSILON, "n = %d trial %d: backward error %.3g", n, trial,
                  be);
            /* and the forward error is small because these matrices are well conditioned */
            double fe = max_abs_diff(x, xs, n) / norm_inf(n, xs);
            CHECK(fe < 1e-11, "n = %d trial %d: forward error %.3g", n, trial, fe);
        }
    }
}

/* P A = L U entry by entry. */
static void test_factors_reproduce_the_matrix(void **state)
{
    (void)state;
    uint64_t seed = 42;
    const int n = 7;
    double A[49], LU[49], PA[49], P_A[49];
    int piv[7];
    for (int i = 0; i < n * n; i++)
        A[i] = rnd(&seed);
    memcpy(LU, A, sizeof A);
    assert_int_equal(dyn_lu_factor(n, LU, piv), 0);
    memcpy(P_A, A, sizeof A);
    for (int k = 0; k < n; k++) {
        assert_true(piv[k] >= k && piv[k] < n);
        for (int j = 0; j < n; j++) {
            double tmp = P_A[k * n + j];
            P_A[k * n + j] = P_A[piv[k] * n + j];
            P_A[piv[k] * n + j] = tmp;
        }
    }
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double s = 0.0;
            for (int k = 0; k <= (i < j ? i : j); k++) {
                double l = k == i ? 1.0 : LU[i * n + k];
                s += l * LU[k * n + j];
            }
            PA[i * n + j] = s;
            /* partial pivoting: every multiplier is at most 1 in magnitude */
            if (j < i)
                assert_true(fabs(LU[i * n + j]) <= 1.0);
        }
    assert_true(max_abs_diff(PA, P_A, n * n) < 8 * DBL_EPSILON);
}

/* A zero and a tiny leading entry: without pivoting the first fails and the second loses
 * every digit; with it both are exact or nearly so. */
static void test_pivoting_is_needed_and_done(void **state)
{
    (void)state;
    double A[4] = {0.0, 1.0, 1.0, 0.0}, b[2] = {3.0, 5.0};
    int piv[2];
    assert_int_equal(dyn_lu_factor(2, A, piv), 0);
    dyn_lu_solve(2, A, piv, b);
    assert_true(b[0] == 5.0 && b[1] == 3.0);

    double B[4] = {1e-20, 1.0, 1.0, 1.0}, c[2] = {1.0, 2.0};
    assert_int_equal(dyn_lu_factor(2, B, piv), 0);
    dyn_lu_solve(2, B, piv, c);
    /* exact solution x1 = 1/(1 - 1e-20), x2 = (1 - 2e-20)/(1 - 1e-20) */
    assert_true(fabs(c[0] - 1.0) < 4 * DBL_EPSILON && fabs(c[1] - 1.0) < 4 * DBL_EPSILON);
}

static void test_singular_matrices_are_reported(void **state)
{
    (void)state;
    int piv[4];
    /* second row twice the first: elimination leaves an exact zero in column 1 */
    double A[4] = {1.0, 2.0, 2.0, 4.0};
    assert_int_equal(dyn_lu_factor(2, A, piv), 2);
    /* a zero column */
    double B[9] = {1, 0, 3, 4, 0, 6, 7, 0, 9};
    assert_int_equal(dyn_lu_factor(3, B, piv), 2);
    /* all zero */
    double Z[16] = {0};
    assert_int_equal(dyn_lu_factor(4, Z, piv), 1);
    /* rank 2 of 3 with a dependency that stays exact in binary: row3 = row1 / 2 + row2 */
    double C[9] = {4, 1, 2, -2, 3, 1, 0, 3.5, 2};
    assert_int_equal(dyn_lu_factor(3, C, piv), 3);
    /* NaN is reported, not silently factored */
    double D[4] = {1.0, 2.0, NAN, 4.0};
    assert_true(dyn_lu_factor(2, D, piv) > 0);
    double E[4] = {INFINITY, 2.0, 1.0, 4.0};
    assert_true(dyn_lu_factor(2, E, piv) > 0);
}

/* A matrix close to singular relative to its size is still factored: the stiff methods
 * need I/(h gamma) - J for a singular J and large h (Robertson's J is singular). */
static void test_nearly_singular_is_accepted(void **state)
{
    (void)state;
    /* J of Robertson at y = (0.5, 1e-5, 0.5): columns sum to zero, J is singular */
    const double y2 = 1e-5, y3 = 0.5;
    double J[9] = {-0.04, 1e4 * y3, 1e4 * y2, 0.04, -1e4 * y3 - 6e7 * y2, -1e4 * y2,
                   0.0,   6e7 * y2, 0.0};
    const double fac = 1e-10; /* 1/(h gamma) for h = 4e10 */
    double W[9], x[3], b[3] = {1.0, -2.0, 3.0}, r[3];
    for (int i = 0; i < 9; i++)
        W[i] = -J[i];
    for (int i = 0; i < 3; i++)
        W[i * 3 + i] += fac;
    double W0[9];
    memcpy(W0, W, sizeof W);
    int piv[3];
    assert_int_equal(dyn_lu_factor(3, W, piv), 0);
    memcpy(x, b, sizeof b);
    dyn_lu_solve(3, W, piv, x);
    dyn_mat_vec(3, W0, x, r);
    /* the solution is huge (~1/fac) along the null vector; the residual is at rounding
     * relative to |W| |x| */
    for (int i = 0; i < 3; i++)
        r[i] -= b[i];
    assert_true(norm_inf(3, r) < 64 * DBL_EPSILON * norm_inf_mat(3, W0) * norm_inf(3, x));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_systems_solve_to_rounding),
        cmocka_unit_test(test_factors_reproduce_the_matrix),
        cmocka_unit_test(test_pivoting_is_needed_and_done),
        cmocka_unit_test(test_singular_matrices_are_reported),
        cmocka_unit_test(test_nearly_singular_is_accepted),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
