/* SPDX-License-Identifier: BSD-3-Clause */
/* Butcher tables of the registered methods: each satisfies the order conditions of its
 * stated order to rounding and fails those of the next order (the order is exact, not
 * higher); a is strictly lower triangular with c_i = sum_j a_ij; names, aliases and the
 * set of methods the command line promises are present. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "test_util.h"

static void test_order_conditions_hold_to_stated_order(void **state)
{
    (void)state;
    assert_true(dyn_method_count() >= 6);
    for (int i = 0; i < dyn_method_count(); i++) {
        const dyn_tableau *tab = fixed_method_at(i);
        if (!tab)
            continue;
        assert_true(tab->order >= 1);
        assert_true(tab->order <= tab->stages); /* explicit RK: order <= stages for p <= 4 */
        double r = dyn_tableau_order_residual(tab, tab->order);
        CHECK(r < 1e-15, "%s: order %d, residual %.3g", tab->name, tab->order, r);
    }
}

static void test_order_is_exact_not_higher(void **state)
{
    (void)state;
    for (int i = 0; i < dyn_method_count(); i++) {
        const dyn_tableau *tab = fixed_method_at(i);
        if (!tab || tab->order >= 4)
            continue; /* conditions are only known up to order 4 */
        double r = dyn_tableau_order_residual(tab, tab->order + 1);
        CHECK(r > 1e-3, "%s: residual at order %d is only %.3g", tab->name, tab->order + 1, r);
    }
}

/* The residual must react to a broken table: it is a check, not a constant. */
static void test_residual_detects_a_wrong_coefficient(void **state)
{
    (void)state;
    const dyn_tableau *rk4 = dyn_method_find("rk4");
    assert_non_null(rk4);
    double b[4];
    memcpy(b, rk4->b, sizeof b);
    b[1] += 1e-6;
    b[2] -= 1e-6; /* still sums to one: only the higher conditions see it */
    dyn_tableau broken = *rk4;
    broken.b = b;
    assert_true(dyn_tableau_order_residual(&broken, 1) < 1e-15);
    assert_true(dyn_tableau_order_residual(&broken, 2) < 1e-15); /* c2 == c3 */
    double cbad[4] = {0.0, 0.5, 0.5, 0.9};
    broken.b = rk4->b;
    broken.c = cbad; /* c4 no longer the row sum */
    assert_true(dyn_tableau_order_residual(&broken, 1) > 0.09);
}

static void test_a_strictly_lower_triangular_and_c_row_sums(void **state)
{
    (void)state;
    for (int m = 0; m < dyn_method_count(); m++) {
        const dyn_tableau *tab = fixed_method_at(m);
        if (!tab)
            continue;
        const int s = tab->stages;
        assert_true(s >= 1 && s <= 16);
        assert_true(tab->c[0] == 0.0);
        for (int i = 0; i < s; i++) {
            double row = 0.0;
            for (int j = 0; j < s; j++) {
                if (j >= i)
                    assert_true(tab->a[i * s + j] == 0.0);
                row += tab->a[i * s + j];
            }
            CHECK(fabs(row - tab->c[i]) <= 1e-15, "%s: stage %d, c = %.17g, row sum %.17g",
                  tab->name, i, tab->c[i], row);
            assert_true(tab->c[i] >= 0.0 && tab->c[i] <= 1.0);
        }
    }
}

static void test_descriptions_present(void **state)
{
    (void)state;
    for (int i = 0; i < dyn_method_count(); i++) {
        const dyn_tableau *tab = dyn_method_at(i);
        assert_non_null(tab->name);
        assert_non_null(tab->title);
        assert_non_null(tab->reference);
        assert_true(strlen(tab->title) > 0 && strlen(tab->reference) > 0);
    }
    assert_null(dyn_method_at(-1));
    assert_null(dyn_method_at(dyn_method_count()));
}

static void test_names_and_aliases(void **state)
{
    (void)state;
    const dyn_tableau *heun = dyn_method_find("heun");
    const dyn_tableau *mid = dyn_method_find("midpoint");
    assert_non_null(heun);
    assert_non_null(mid);
    assert_ptr_equal(dyn_method_find("modified-euler"), heun);
    assert_ptr_equal(dyn_method_find("rk2"), mid);
    assert_string_equal(heun->name, "heun");
    assert_string_equal(mid->name, "midpoint");
    assert_null(dyn_method_find("no-such-method"));
    assert_null(dyn_method_find(""));
    assert_null(dyn_method_find(NULL));
    assert_null(dyn_method_find("RK4")); /* case-sensitive */
    assert_null(dyn_method_find("rk")); /* no prefix matching */
    /* Every method is found by its name and its alias, and names are unique. */
    for (int i = 0; i < dyn_method_count(); i++) {
        const dyn_tableau *tab = dyn_method_at(i);
        assert_ptr_equal(dyn_method_find(tab->name), tab);
        if (tab->alias)
            assert_ptr_equal(dyn_method_find(tab->alias), tab);
        for (int j = 0; j < i; j++) {
            const dyn_tableau *other = dyn_method_at(j);
            assert_true(strcmp(other->name, tab->name) != 0);
            if (tab->alias)
                assert_true(strcmp(other->name, tab->alias) != 0);
        }
    }
}

static void test_expected_methods_present(void **state)
{
    (void)state;
    static const struct {
        const char *name;
        int order, stages;
    } expected[] = {
        {"euler", 1, 1}, {"heun", 2, 2}, {"midpoint", 2, 2},
        {"ralston", 2, 2}, {"rk4", 4, 4}, {"rk38", 4, 4},
    };
    for (size_t i = 0; i < sizeof expected / sizeof expected[0]; i++) {
        const dyn_tableau *tab = dyn_method_find(expected[i].name);
        CHECK(tab != NULL, "method %s is not registered", expected[i].name);
        assert_int_equal(tab->kind, DYN_KIND_EXPLICIT_RK);
        assert_int_equal(tab->order, expected[i].order);
        assert_int_equal(tab->stages, expected[i].stages);
    }
}

static void test_method_names_list(void **state)
{
    (void)state;
    char buf[1024];
    assert_ptr_equal(dyn_method_names(buf, sizeof buf), buf);
    for (int i = 0; i < dyn_method_count(); i++) {
        const dyn_tableau *tab = dyn_method_at(i);
        assert_non_null(strstr(buf, tab->name));
        if (tab->alias)
            assert_non_null(strstr(buf, tab->alias));
    }
    /* A small buffer is never overrun and stays a string. */
    char small[8];
    memset(small, 'x', sizeof small);
    dyn_method_names(small, sizeof small);
    assert_true(memchr(small, '\0', sizeof small) != NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_order_conditions_hold_to_stated_order),
        cmocka_unit_test(test_order_is_exact_not_higher),
        cmocka_unit_test(test_residual_detects_a_wrong_coefficient),
        cmocka_unit_test(test_a_strictly_lower_triangular_and_c_row_sums),
        cmocka_unit_test(test_descriptions_present),
        cmocka_unit_test(test_names_and_aliases),
        cmocka_unit_test(test_expected_methods_present),
        cmocka_unit_test(test_method_names_list),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
