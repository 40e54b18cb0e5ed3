/* SPDX-License-Identifier: BSD-3-Clause */
/* The arithmetic of a Runge–Kutta stage (src/ode/rk_stages.h), as facts about single steps:
 * - fixed-step methods form Y_i = y + h * (sum_j a_ij k_j) left to right (HNW I eq. II.1.8):
 *   RK4's new state is y + h * (b1 k1 + b2 k2 + b3 k3 + b4 k4) bit for bit, Heun's the
 *   homework's y + 0.5 Ts (k1 + k2) (a row of one power of two is summed first);
 * - embedded pairs (bs23, dp45, dop853) add each row's last term apart,
 *   (y + h * (sum_{j<l} a_ij k_j)) + (h a_il) k_l: checked term by term on every row of dp45
 *   and dop853, recomputed here from the tables;
 * - the scan (tables of more stages than a plan holds) and the plan give the same step bit
 *   for bit for the three pairs and RK4 (stage derivatives and new state).
 * System: van der Pol, mu = 1, from (2, 0.5), h = 0.1. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

#include "dynkit/dynkit.h"
#include "ode/rk_stages.h"

#define N 2
#define MAX_S 13

static int vdp(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    (void)par;
    dydt[0] = y[1];
    dydt[1] = (1.0 - y[0] * y[0]) * y[1] - y[0];
    return 0;
}

static const double y0_[N] = {2.0, 0.5};
static const double h_ = 0.1;

/* one step of m through the plan (scan = 0) or the scan (scan = 1): k and ynew */
static void one_step(const dyn_tableau *m, int scan, double *k, double *ynew)
{
    double Y[N], finite = 0.0;
    int fail_stage = -1, rc;
    if (scan) {
        rc = dyn_rk_stages_scan(m, vdp, NULL, N, 0.0, h_, 1.0, y0_, ynew, k, Y, &fail_stage,
                                &finite, NULL, NULL, 0);
    } else {
        dyn_rk_plan plan;
        memset(&plan, 0, sizeof plan);
        assert_int_equal(dyn_rk_plan_init(&plan, m, k, N), 1);
        rc = dyn_rk_stages(m, &plan, vdp, NULL, N, 0.0, h_, 1.0, y0_, ynew, k, Y, &fail_stage,
                           &finite, NULL, NULL, 0);
    }
    assert_int_equal(rc, 0);
    assert_true(finite == 0.0);
}

static void test_rk4_is_the_textbook_sum(void **state)
{
    (void)state;
    const dyn_tableau *m = dyn_method_find("rk4");
    assert_non_null(m);
    double k[4 * N], ynew[N];
    one_step(m, 0, k, ynew);
    const double *b = m->b;
    for (int q = 0; q < N; q++) {
        const double expect = y0_[q] + h_ * (b[0] * k[0 * N + q] + b[1] * k[1 * N + q] +
                                             b[2] * k[2 * N + q] + b[3] * k[3 * N + q]);
        assert_memory_equal(&ynew[q], &expect, sizeof expect);
    }
}

static void test_heun_is_the_homeworks_formula(void **state)
{
    (void)state;
    const dyn_tableau *m = dyn_method_find("heun");
    assert_non_null(m);
    double k[2 * N], ynew[N];
    one_step(m, 0, k, ynew);
    for (int q = 0; q < N; q++) {
        /* Integrate_ModifiedEuler: y + 0.5*Ts*(dytilde + dy), and the table's sum */
        const double homework = y0_[q] + 0.5 * h_ * (k[0 * N + q] + k[1 * N + q]);
        const double table = y0_[q] + h_ * (m->b[0] * k[0 * N + q] + m->b[1] * k[1 * N + q]);
        assert_memory_equal(&ynew[q], &homework, sizeof homework);
        assert_memory_equal(&ynew[q], &table, sizeof table);
    }
}

/* (y + h * (sum of the row's non-zero terms but the last)) + (h a_l) k_l, from the table */
static double apart(const double *row, int len, const double *k, int q)
{
    int l = len - 1;
    while (l >= 0 && row[l] == 0.0)
        l--;
    if (l < 0)
        return y0_[q];
    int terms = 0;
    double sum = 0.0;
    for (int j = 0; j < l; j++)
        if (row[j] != 0.0) {
            sum = terms ? sum + row[j] * k[j * N + q] : row[j] * k[j * N + q];
            terms++;
        }
    const double partial = terms ? y0_[q] + h_ * sum : y0_[q];
    return partial + (h_ * row[l]) * k[l * N + q];
}

static void check_pair_form(const char *name)
{
    const dyn_tableau *m = dyn_method_find(name);
    assert_non_null(m);
    assert_int_equal(m->kind, DYN_KIND_EMBEDDED_RK);
    const int s = m->stages;
    double k[MAX_S * N], ynew[N];
    one_step(m, 0, k, ynew);
    /* each stage derivative is f of the stage state formed apart */
    for (int i = 1; i < s; i++) {
        double Y[N], f[N];
        for (int q = 0; q < N; q++)
            Y[q] = apart(m->a + (size_t)i * (size_t)s, i, k, q);
        vdp(0.0, Y, f, NULL);
        assert_memory_equal(f, k + (size_t)i * N, sizeof f);
    }
    for (int q = 0; q < N; q++) {
        const double expect = apart(m->b, s, k, q);
        assert_memory_equal(&ynew[q], &expect, sizeof expect);
    }
}

static void test_embedded_pairs_add_the_newest_term_apart(void **state)
{
    (void)state;
    check_pair_form("bs23");
    check_pair_form("dp45");
    check_pair_form("dop853");
}

static void test_scan_equals_plan(void **state)
{
    (void)state;
    const char *names[] = {"euler", "heun", "rk4", "bs23", "dp45", "dop853"};
    for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
        const dyn_tableau *m = dyn_method_find(names[i]);
        assert_non_null(m);
        double k1[MAX_S * N], k2[MAX_S * N], y1[N], y2[N];
        memset(k1, 0, sizeof k1);
        memset(k2, 0, sizeof k2);
        one_step(m, 0, k1, y1);
        one_step(m, 1, k2, y2);
        assert_memory_equal(k1, k2, (size_t)m->stages * N * sizeof *k1);
        assert_memory_equal(y1, y2, sizeof y1);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rk4_is_the_textbook_sum),
        cmocka_unit_test(test_heun_is_the_homeworks_formula),
        cmocka_unit_test(test_embedded_pairs_add_the_newest_term_apart),
        cmocka_unit_test(test_scan_equals_plan),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
