/* SPDX-License-Identifier: BSD-3-Clause */
/* dyn_fixed_solve_inline (dynkit/ode_inline.h) keeps dyn_fixed_solve's contract, bit for bit:
 *
 * - the same final state, time and counters for Euler, Heun, the midpoint rule, Ralston and
 *   RK4 (tables from dyn_method_find, and constant copies of Euler, Heun and RK4 that the
 *   compiler folds), on 2 states (the loop with two steps per iteration) and 12 (one step
 *   per iteration), with a partial last step and with every end policy;
 * - the same failures: a state that overflows to Inf (y' = y^2), a NaN from the right-hand
 *   side in one state, a right-hand side that fails: status, time, state index, the last
 *   good state, the counters and the message;
 * - with no_finite_check the run goes on through the non-finite states, as dyn_fixed_solve's;
 * - dyn_fixed_solve itself gives the same whether its steps run as plain steps (no
 *   callbacks: for these shapes, dyn_fixed_solve_inline's step with the right-hand side by
 *   pointer) or each through its general step (an output callback at every step).
 * The library's driver is the reference: tests/test_errors.c and tests/test_conventions.c
 * say what it does.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "dynkit/ode_inline.h"
#include "test_util.h"

/* ---- right-hand sides, defined here so that the inline solver can inline them ---- */

static int vdp(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    (void)par;
    dydt[0] = y[1];
    dydt[1] = (1.0 - y[0] * y[0]) * y[1] - y[0];
    return 0;
}

/* 12 coupled oscillators with a cubic spring: q_i'' = -q_i - 0.1 q_i^3 + 0.5 (q_{i+1} - q_i) */
static int chain12(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    (void)par;
    for (int i = 0; i < 6; i++) {
        const double q = y[i], right = i + 1 < 6 ? y[i + 1] : 0.0;
        dydt[i] = y[6 + i];
        dydt[6 + i] = -q - 0.1 * q * q * q + 0.5 * (right - q);
    }
    return 0;
}

/* y_i' = (i + 1) y_i^2: state n - 1 reaches Inf first (blow-up at t = 1 / (n y0)) */
static int blowup(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    const int n = *(const int *)par;
    for (int i = 0; i < n; i++)
        dydt[i] = (double)(i + 1) * y[i] * y[i];
    return 0;
}

/* van der Pol, but state 1's derivative is NaN from t >= 0.5 on */
static int nan_late(double t, const double *y, double *dydt, void *par)
{
    vdp(t, y, dydt, par);
    if (t >= 0.5)
        dydt[1] = NAN;
    return 0;
}

/* van der Pol, failing with status 7 from t >= 0.3 on */
static int fails_late(double t, const double *y, double *dydt, void *par)
{
    vdp(t, y, dydt, par);
    return t >= 0.3 ? 7 : 0;
}

/* ---- constant copies of three tables (the compiler folds their coefficients) ---- */

static const double euler_a[1] = {0.0}, euler_b[1] = {1.0}, euler_c[1] = {0.0};
static const double heun_a[4] = {0.0, 0.0, 1.0, 0.0}, heun_b[2] = {0.5, 0.5},
                    heun_c[2] = {0.0, 1.0};
static const double rk4_a[16] = {0.0, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0,
                                 0.0, 0.5, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0};
static const double rk4_b[4] = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};
static const double rk4_c[4] = {0.0, 0.5, 0.5, 1.0};
#define CONST_TABLE(NAME, T, S)                                                                    \
    static const dyn_tableau NAME = {.name = #T,                                                   \
                                     .title = "constant copy",                                     \
                                     .reference = "test",                                          \
                                     .kind = DYN_KIND_EXPLICIT_RK,                                 \
                                     .stages = S,                                                  \
                                     .order = S,                                                   \
                                     .a = T##_a,                                                   \
                                     .b = T##_b,                                                   \
                                     .c = T##_c};
CONST_TABLE(EULER_CONST, euler, 1)
CONST_TABLE(HEUN_CONST, heun, 2)
CONST_TABLE(RK4_CONST, rk4, 4)

/* ---- the comparison ---- */

typedef struct run {
    int rc;
    double y[TEST_MAX_N];
    dyn_result res;
} run;

static int ignore_sample(long k, double t, const double *y, void *ctx)
{
    (void)k;
    (void)t;
    (void)y;
    (void)ctx;
    return 0;
}

/* dyn_fixed_solve with a callback at every step against its plain run: the same state,
 * status and counters */
static void compare_general(const char *what, const dyn_tableau *m, const dyn_system *sys,
                            const double *y0, double t1, double h, const dyn_fixed_opts *opts,
                            const run *plain)
{
    static double work[TEST_WORK];
    dyn_fixed_opts o;
    memset(&o, 0, sizeof o);
    if (opts)
        o = *opts;
    o.output = ignore_sample;
    o.every = 1;
    run gen;
    memset(&gen, 0, sizeof gen);
    gen.rc = dyn_fixed_solve(m, sys, 0.0, t1, h, y0, gen.y, work, &o, &gen.res);
    CHECK(gen.rc == plain->rc, "%s, %s: status %d with a callback, %d without", what, m->name,
          gen.rc, plain->rc);
    for (int i = 0; i < sys->n; i++)
        CHECK(same_bits(gen.y[i], plain->y[i]),
              "%s, %s: y[%d] = %.17g with a callback, %.17g without", what, m->name, i, gen.y[i],
              plain->y[i]);
    CHECK(gen.res.stats.steps == plain->res.stats.steps &&
              gen.res.stats.rhs_calls == plain->res.stats.rhs_calls &&
              gen.res.fail_index == plain->res.fail_index,
          "%s, %s: steps %ld / %ld, calls %ld / %ld", what, m->name, gen.res.stats.steps,
          plain->res.stats.steps, gen.res.stats.rhs_calls, plain->res.stats.rhs_calls);
}

/* Both solvers on the same problem; every field of the results compared. */
static void compare(const char *what, const dyn_tableau *m, dyn_rhs_fn f, void *par, int n,
                    const double *y0, double t1, double h, const dyn_fixed_opts *opts,
                    run *lib_out)
{
    static double work_lib[TEST_WORK], work_inl[TEST_WORK];
    assert_true(dyn_fixed_work_size(m, n) <= TEST_WORK);
    const dyn_system sys = {f, n, par};
    run lib, inl;
    memset(&lib, 0, sizeof lib);
    memset(&inl, 0, sizeof inl);
    lib.rc = dyn_fixed_solve(m, &sys, 0.0, t1, h, y0, lib.y, work_lib, opts, &lib.res);
    inl.rc = dyn_fixed_solve_inline(m, &sys, 0.0, t1, h, y0, inl.y, work_inl, opts, &inl.res);
    CHECK(lib.rc == inl.rc && lib.res.status == inl.res.status,
          "%s, %s: status %d (library) against %d (inline): %s / %s", what, m->name, lib.rc,
          inl.rc, lib.res.message, inl.res.message);
    for (int i = 0; i < n; i++)
        CHECK(same_bits(lib.y[i], inl.y[i]), "%s, %s: y[%d] = %.17g (library), %.17g (inline)",
              what, m->name, i, lib.y[i], inl.y[i]);
    CHECK(same_bits(lib.res.t, inl.res.t) &&
              (same_bits(lib.res.fail_t, inl.res.fail_t) ||
               (isnan(lib.res.fail_t) && isnan(inl.res.fail_t))),
          "%s, %s: t %.17g / %.17g, fail_t %.17g / %.17g", what, m->name, lib.res.t, inl.res.t,
          lib.res.fail_t, inl.res.fail_t);
    CHECK(lib.res.fail_index == inl.res.fail_index && lib.res.rhs_status == inl.res.rhs_status,
          "%s, %s: fail_index %d / %d, rhs_status %d / %d", what, m->name,
          lib.res.fail_index, inl.res.fail_index, lib.res.rhs_status, inl.res.rhs_status);
    CHECK(lib.res.stats.steps == inl.res.stats.steps &&
              lib.res.stats.rhs_calls == inl.res.stats.rhs_calls,
          "%s, %s: steps %ld / %ld, rhs calls %ld / %ld", what, m->name, lib.res.stats.steps,
          inl.res.stats.steps, lib.res.stats.rhs_calls, inl.res.stats.rhs_calls);
    CHECK(strcmp(lib.res.message, inl.res.message) == 0, "%s, %s: message '%s' / '%s'", what,
          m->name, lib.res.message, inl.res.message);
    compare_general(what, m, &sys, y0, t1, h, opts, &lib);
    if (lib_out)
        *lib_out = lib;
}

static const char *const library_tables[] = {"euler", "heun", "midpoint", "ralston", "rk4"};
static const dyn_tableau *const constant_tables[] = {&EULER_CONST, &HEUN_CONST, &RK4_CONST};

static void test_same_results_as_the_library(void **state)
{
    (void)state;
    const double v0[2] = {2.0, 0.0};
    double c0[12];
    for (int i = 0; i < 12; i++)
        c0[i] = i < 6 ? 0.1 * (double)(i + 1) : 0.0;
    const dyn_end_policy ends[] = {DYN_END_EXACT, DYN_END_GRID};
    for (size_t i = 0; i < sizeof library_tables / sizeof *library_tables; i++) {
        const dyn_tableau *m = dyn_method_find(library_tables[i]);
        assert_non_null(m);
        /* 7.005 is not a multiple of 0.01: a partial last step, or the policy's answer */
        for (size_t e = 0; e < sizeof ends / sizeof *ends; e++) {
            const dyn_fixed_opts o = {.end = ends[e]};
            compare("van der Pol", m, vdp, NULL, 2, v0, 7.005, 0.01, &o, NULL);
            compare("12-state chain", m, chain12, NULL, 12, c0, 7.005, 0.01, &o, NULL);
        }
    }
    for (size_t i = 0; i < sizeof constant_tables / sizeof *constant_tables; i++) {
        compare("van der Pol, constant table", constant_tables[i], vdp, NULL, 2, v0, 7.0, 0.01,
                NULL, NULL);
        compare("12-state chain, constant table", constant_tables[i], chain12, NULL, 12, c0, 7.0,
                0.01, NULL, NULL);
    }
}

/* The runs below fail in each of the ways a solve can fail: the library says what happened
 * (checked here as facts), and the inline solver must say the same. */
static void test_same_failures_as_the_library(void **state)
{
    (void)state;
    const double v0[2] = {2.0, 0.0};
    for (size_t i = 0; i < sizeof library_tables / sizeof *library_tables; i++) {
        const dyn_tableau *m = dyn_method_find(library_tables[i]);
        assert_non_null(m);
        for (int n = 2; n <= 12; n += 10) {
            /* y_i(t) = 1 / (1 - (i + 1) t) blows up at t = 1 / (i + 1); the discrete
             * solutions later, but within the span */
            double ones[12];
            for (int q = 0; q < n; q++)
                ones[q] = 1.0;
            run lib;
            compare("blow-up", m, blowup, &n, n, ones, 2.0, 0.01, NULL, &lib);
            CHECK(lib.res.status == DYN_ERR_NONFINITE && lib.res.fail_index >= 0 &&
                      lib.res.fail_index < n && lib.res.fail_t < 2.0,
                  "blow-up, %s, n = %d: status %d, index %d, at t = %g", m->name, n,
                  lib.res.status, lib.res.fail_index, lib.res.fail_t);
            for (int q = 0; q < n; q++)
                assert_true(isfinite(lib.y[q]));
            /* the same run without the check goes on to t1 */
            const dyn_fixed_opts no_check = {.no_finite_check = 1};
            compare("blow-up, no_finite_check", m, blowup, &n, n, ones, 2.0, 0.01, &no_check,
                    &lib);
            CHECK(lib.res.status == DYN_OK && !isfinite(lib.y[n - 1]),
                  "no_finite_check, %s: status %d, y = %g", m->name, lib.res.status,
                  lib.y[n - 1]);
        }
        run lib;
        compare("NaN from the right-hand side", m, nan_late, NULL, 2, v0, 1.0, 0.01, NULL, &lib);
        /* the NaN reaches state 0 too within a step when a later stage reads state 1 */
        CHECK(lib.res.status == DYN_ERR_NONFINITE && lib.res.fail_index >= 0 &&
                  lib.res.fail_index <= 1 && lib.res.fail_t >= 0.5 && lib.res.fail_t <= 0.52,
              "NaN, %s: status %d, index %d, at t = %g", m->name, lib.res.status,
              lib.res.fail_index, lib.res.fail_t);
        compare("failing right-hand side", m, fails_late, NULL, 2, v0, 1.0, 0.01, NULL, &lib);
        CHECK(lib.res.status == DYN_ERR_RHS && lib.res.rhs_status == 7 &&
                  lib.res.fail_t >= 0.3 && lib.res.fail_t <= 0.31,
              "failure, %s: status %d (%d), at t = %g", m->name, lib.res.status,
              lib.res.rhs_status, lib.res.fail_t);
    }
    int n = 12;
    double ones[12];
    for (int q = 0; q < n; q++)
        ones[q] = 1.0;
    for (size_t i = 0; i < sizeof constant_tables / sizeof *constant_tables; i++) {
        compare("blow-up, constant table", constant_tables[i], blowup, &n, n, ones, 2.0, 0.01,
                NULL, NULL);
        compare("NaN, constant table", constant_tables[i], nan_late, NULL, 2, v0, 1.0, 0.01,
                NULL, NULL);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_same_results_as_the_library),
        cmocka_unit_test(test_same_failures_as_the_library),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
