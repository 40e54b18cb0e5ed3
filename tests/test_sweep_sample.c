/* SPDX-License-Identifier: BSD-3-Clause */
/* Run tables of sweeps (src/sweep/sample.c): Philox4x32 against Random123's known-answer
 * vectors (tests/kat_vectors of github.com/DEShawResearch/random123: 7 and 10 rounds, the
 * counters and keys of zeros, ones and the digits of pi), evenly spaced values with exact
 * ends, the order of a full grid (last axis fastest), and the moments of the samplers over
 * many runs within statistical bounds (5 standard errors): uniform, normal (Box–Muller),
 * lognormal; any block of runs gives the same values as the whole table. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "dynkit/dynkit.h"
#include "dynkit/sweep.h"

static void test_philox_kat(void **state)
{
    (void)state;
    static const struct {
        int rounds;
        uint32_t ctr[4], key[2], out[4];
    } kat[] = {
        {7, {0, 0, 0, 0}, {0, 0}, {0x5f6fb709, 0x0d893f64, 0x4f121f81, 0x4f730a48}},
        {7,
         {0xffffffff, 0xffffffff, 0xffffffff, 0xffffffff},
         {0xffffffff, 0xffffffff},
         {0x5207ddc2, 0x45165e59, 0x4d8ee751, 0x8c52f662}},
        {7,
         {0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344},
         {0xa4093822, 0x299f31d0},
         {0x4dfccaba, 0x190a87f0, 0xc47362ba, 0xb6b5242a}},
        {10, {0, 0, 0, 0}, {0, 0}, {0x6627e8d5, 0xe169c58d, 0xbc57ac4c, 0x9b00dbd8}},
        {10,
         {0xffffffff, 0xffffffff, 0xffffffff, 0xffffffff},
         {0xffffffff, 0xffffffff},
         {0x408f276d, 0x41c83b0e, 0xa20bc7c6, 0x6d5451fd}},
        {10,
         {0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344},
         {0xa4093822, 0x299f31d0},
         {0xd16cfe09, 0x94fdcceb, 0x5001e420, 0x24126ea1}},
    };
    for (size_t i = 0; i < sizeof kat / sizeof kat[0]; i++) {
        uint32_t out[4];
        dyn_philox4x32(kat[i].ctr, kat[i].key, kat[i].rounds, out);
        for (int j = 0; j < 4; j++)
            assert_int_equal(out[j], kat[i].out[j]);
    }
}

static void test_linspace_grid(void **state)
{
    (void)state;
    assert_true(dyn_linspace_at(0.1, 1.9, 50, 0) == 0.1);
    assert_true(dyn_linspace_at(0.1, 1.9, 50, 49) == 1.9);
    assert_true(dyn_linspace_at(0.1, 1.9, 50, 10) == 0.1 + 10.0 * ((1.9 - 0.1) / 49.0));
    assert_true(dyn_linspace_at(0.0, 1.0, 3, 1) == 0.5);
    assert_true(dyn_linspace_at(2.0, 3.0, 1, 0) == 2.0);
    const double x[] = {1, 2}, y[] = {10, 20, 30};
    const double *axes[] = {x, y};
    const long counts[] = {2, 3};
    double v[12];
    assert_int_equal(dyn_sweep_grid(2, axes, counts, v, 100), 6);
    const double expect[] = {1, 10, 1, 20, 1, 30, 2, 10, 2, 20, 2, 30};
    assert_memory_equal(v, expect, sizeof expect);
    assert_int_equal(dyn_sweep_grid(2, axes, counts, NULL, 5), -1);
    assert_int_equal(dyn_sweep_grid(2, axes, counts, NULL, 6), 6);
}

/* Mean and variance of column col of a table. */
static void moments(const double *v, long n, int cols, int col, double *mean, double *var)
{
    double s = 0.0;
    for (long i = 0; i < n; i++)
        s += v[i * cols + col];
    *mean = s / (double)n;
    double q = 0.0;
    for (long i = 0; i < n; i++) {
        const double d = v[i * cols + col] - *mean;
        q += d * d;
    }
    *var = q / (double)(n - 1);
}

static void test_moments(void **state)
{
    (void)state;
    enum { N = 200000, C = 3 };
    const dyn_dist d[C] = {{DYN_DIST_UNIFORM, 2.0, 5.0},
                           {DYN_DIST_NORMAL, 1.0, 2.0},
                           {DYN_DIST_LOGNORMAL, 0.0, 0.5}};
    double *v = malloc((size_t)N * C * sizeof *v);
    assert_non_null(v);
    dyn_sweep_sample(d, C, 12345, 0, N, v);
    double m, s2;
    /* uniform(2, 5): mean 3.5, variance 9/12, 4th central moment 81/80 */
    moments(v, N, C, 0, &m, &s2);
    assert_true(fabs(m - 3.5) < 5.0 * sqrt(0.75 / N));
    assert_true(fabs(s2 - 0.75) < 5.0 * sqrt((81.0 / 80.0 - 0.75 * 0.75) / N));
    for (long i = 0; i < N; i++)
        assert_true(v[i * C] > 2.0 && v[i * C] < 5.0);
    /* normal(1, 2): mean 1, variance 4 (the variance of s^2 is 2 sigma^4 / n) */
    moments(v, N, C, 1, &m, &s2);
    assert_true(fabs(m - 1.0) < 5.0 * sqrt(4.0 / N));
    assert_true(fabs(s2 - 4.0) < 5.0 * sqrt(2.0 * 16.0 / N));
    /* lognormal(0, 0.5): mean exp(s^2/2), variance (exp(s^2) - 1) exp(s^2) */
    moments(v, N, C, 2, &m, &s2);
    const double lm = exp(0.125), lv = (exp(0.25) - 1.0) * exp(0.25);
    assert_true(fabs(m - lm) < 5.0 * sqrt(lv / N));
    assert_true(fabs(s2 - lv) < 0.02);
    /* columns independent: correlation of 0 and 1 within 5/sqrt(n) */
    double m0, v0, m1, v1, c = 0.0;
    moments(v, N, C, 0, &m0, &v0);
    moments(v, N, C, 1, &m1, &v1);
    for (long i = 0; i < N; i++)
        c += (v[i * C] - m0) * (v[i * C + 1] - m1);
    assert_true(fabs(c / (N - 1) / sqrt(v0 * v1)) < 5.0 / sqrt((double)N));
    /* a block of runs gives the same values as the whole table; another seed others */
    double part[10 * C];
    dyn_sweep_sample(d, C, 12345, 1000, 10, part);
    assert_memory_equal(part, v + 1000 * C, sizeof part);
    dyn_sweep_sample(d, C, 12346, 1000, 10, part);
    assert_true(part[0] != v[1000 * C]);
    /* the value of (seed, run, column) alone */
    assert_true(dyn_dist_value(&d[1], 12345, 77, 1) == v[77 * C + 1]);
    free(v);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_philox_kat),
        cmocka_unit_test(test_linspace_grid),
        cmocka_unit_test(test_moments),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
