/* SPDX-License-Identifier: BSD-3-Clause */
/* test_cvode.c — the optional SUNDIALS CVODE backend (dynkit/cvode.h), against RODAS
 * (rodas4 through dyn_solve) and the references of dynkit/problems.h:
 * - Robertson to 1e11 and van der Pol mu = 1000 to 3000: CVODE's BDF with the analytic and
 *   with its difference-quotient Jacobian meets the references to its tolerance, and agrees
 *   with rodas4;
 * - samples at requested times keep Robertson's y1 + y2 + y3 = 1;
 * - counters are filled; a failing right-hand side, too many steps and bad output times
 *   are reported with their statuses; f is never evaluated past the last output time;
 * - every step as a sample (dyn_cvode_solve_steps) with its step limit; per-state relative
 *   tolerances;
 * - the band solver on the Brusselator (N = 20) against SciPy's reference, with the
 *   analytic band and with CVODE's banded difference quotients.
 * Without SUNDIALS (DYNKIT_HAVE_CVODE undefined) every test is skipped. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "dynkit/brusselator.h"
#include "dynkit/models.h"
#include "dynkit/problems.h"
#include "dynkit/solve.h"
#include "test_util.h"

#ifdef DYNKIT_HAVE_CVODE
#include "dynkit/cvode.h"

static double rel_err(const double *y, const double *ref, int n)
{
    double w = 0.0;
    for (int i = 0; i < n; i++)
        w = fmax(w, fabs(y[i] - ref[i]) / fabs(ref[i]));
    return w;
}

/* rodas4 through the general driver, final state only. */
static void rodas(const dyn_model *m, void *par, double t1, double rtol, const double *atolv,
                  double atol, double *y)
{
    const dyn_tableau *meth = dyn_method_find("rodas4");
    assert_non_null(meth);
    dyn_system sys = {m->rhs, m->n_states, par};
    dyn_solve_opts o = {0};
    o.rtol = rtol;
    o.atol = atol;
    o.atolv = atolv;
    o.jacobian = m->jacobian;
    int iwork[8];
    o.iwork = iwork;
    static double work[4096];
    assert_true(dyn_solve_work_size(meth, m->n_states, &o) <= sizeof work / sizeof work[0]);
    dyn_result res;
    int rc = dyn_solve(meth, &sys, m->t0, t1, m->y0, y, work, &o, &res);
    CHECK(rc == DYN_OK, "rodas4: %s", res.message);
}

typedef struct mass_log {
    long count;
    double worst;
} mass_log;

static int mass_out(long k, double t, const double *y, void *ctx)
{
    mass_log *l = ctx;
    (void)t;
    assert_int_equal(k, l->count);
    l->count++;
    l->worst = fmax(l->worst, fabs(y[0] + y[1] + y[2] - 1.0));
    return 0;
}

static void test_robertson(void **state)
{
    (void)state;
    const dyn_model *m = dyn_model_find("robertson");
    const dyn_reference *r = dyn_reference_find("robertson-1e11");
    assert_non_null(m);
    assert_non_null(r);
    dyn_robertson_par par;
    char err[128];
    assert_int_equal(dyn_model_default_params(m, &par, err, sizeof err), 0);
    dyn_system sys = {m->rhs, 3, &par};
    double tout[18];
    long nt = 0;
    tout[nt++] = 0.0;
    for (int k = -5; k <= 11; k++)
        tout[nt++] = pow(10.0, k);
    const double atol[3] = {1e-14, 1e-20, 1e-14};
    double yc[3], yr[3];
    rodas(m, &par, 1e11, 1e-9, atol, 0, yr);
    assert_true(rel_err(yr, r->y, 3) < 1e-6);
    for (int analytic = 1; analytic >= 0; analytic--) {
        dyn_cvode_opts o = {.rtol = 1e-9, .atolv = atol,
                            .jacobian = analytic ? m->jacobian : NULL};
        mass_log log = {0};
        dyn_result res;
        int rc = dyn_cvode_solve(&sys, 0.0, m->y0, tout, nt, &o, mass_out, &log, yc, &res);
        CHECK(rc == DYN_OK, "analytic %d: %s", analytic, res.message);
        assert_int_equal(log.count, nt);
        assert_true(res.t == 1e11);
        CHECK(log.worst < 1e-12, "analytic %d: mass off by %.3g", analytic, log.worst);
        const double e = rel_err(yc, r->y, 3);
        CHECK(e < 1e-5, "analytic %d: CVODE relative error %.3g", analytic, e);
        const double d = rel_err(yc, yr, 3);
        CHECK(d < 1e-5, "analytic %d: CVODE and rodas4 differ by %.3g", analytic, d);
        assert_true(res.stats.accepted > 100 &&
                    res.stats.steps == res.stats.accepted + res.stats.rejected);
        assert_true(res.stats.jac_calls > 0 && res.stats.rhs_calls > res.stats.steps);
        assert_int_equal(res.stats.samples, nt);
    }
}

static void test_van_der_pol(void **state)
{
    (void)state;
    const dyn_model *m = dyn_model_find("vanderpol");
    const dyn_reference *r = dyn_reference_find("vanderpol-mu1000-3000");
    assert_non_null(m);
    assert_non_null(r);
    dyn_vanderpol_par par = {1000.0};
    dyn_system sys = {m->rhs, 2, &par};
    const double tout[2] = {2000.0, 3000.0};
    double yr[2], yc[2];
    rodas(m, &par, 3000.0, 1e-10, NULL, 1e-12, yr);
    assert_true(rel_err(yr, r->y, 2) < 1e-7);
    for (int analytic = 1; analytic >= 0; analytic--) {
        dyn_cvode_opts o = {.rtol = 1e-10, .atol = 1e-12,
                            .jacobian = analytic ? m->jacobian : NULL};
        dyn_result res;
        int rc = dyn_cvode_solve(&sys, 0.0, m->y0, tout, 2, &o, NULL, NULL, yc, &res);
        CHECK(rc == DYN_OK, "analytic %d: %s", analytic, res.message);
        const double e = rel_err(yc, r->y, 2);
        CHECK(e < 1e-6, "analytic %d: CVODE relative error %.3g in %ld steps", analytic, e,
              res.stats.steps);
        const double d = rel_err(yc, yr, 2);
        CHECK(d < 1e-6, "analytic %d: CVODE and rodas4 differ by %.3g", analytic, d);
        assert_true(res.stats.rejected >= 0 && res.stats.jac_calls > 0);
    }
}

typedef struct step_log {
    long count;
    double t_first, t_last;
    int increasing;
    double worst_mass;
} step_log;

static int step_out(long k, double t, const double *y, void *ctx)
{
    step_log *l = ctx;
    assert_int_equal(k, l->count);
    if (k == 0)
        l->t_first = t;
    else if (!(t > l->t_last))
        l->increasing = 0;
    l->t_last = t;
    l->count++;
    l->worst_mass = fmax(l->worst_mass, fabs(y[0] + y[1] + y[2] - 1.0));
    return 0;
}

/* Every step as a sample (dyn_cvode_solve_steps), its step limit, and per-state relative
 * tolerances (equal ones give the scalar run exactly, a tighter one more steps). */
static void test_every_step_and_rtolv(void **state)
{
    (void)state;
    const dyn_model *m = dyn_model_find("robertson");
    const dyn_reference *r = dyn_reference_find("robertson-1e11");
    dyn_robertson_par par;
    char err[128];
    assert_int_equal(dyn_model_default_params(m, &par, err, sizeof err), 0);
    dyn_system sys = {m->rhs, 3, &par};
    const double atol[3] = {1e-14, 1e-20, 1e-14};
    dyn_cvode_opts o = {.rtol = 1e-8, .atolv = atol, .jacobian = m->jacobian};
    step_log log = {0, 0, 0, 1, 0};
    double y[3];
    dyn_result res;
    assert_int_equal(dyn_cvode_solve_steps(&sys, 0.0, 1e11, m->y0, &o, step_out, &log, y, &res),
                     DYN_OK);
    assert_int_equal(log.count, res.stats.accepted + 1);
    assert_int_equal(res.stats.samples, log.count);
    assert_true(log.t_first == 0.0 && log.t_last == 1e11 && log.increasing && res.t == 1e11);
    assert_true(res.stats.steps == res.stats.accepted + res.stats.rejected);
    CHECK(rel_err(y, r->y, 3) < 1e-4, "relative error %.3g", rel_err(y, r->y, 3));
    assert_true(log.worst_mass < 1e-12);
    /* the step limit covers the whole run */
    o.max_steps = 10;
    log = (step_log){0, 0, 0, 1, 0};
    assert_int_equal(dyn_cvode_solve_steps(&sys, 0.0, 1e11, m->y0, &o, step_out, &log, y, &res),
                     DYN_ERR_MAX_STEPS);
    assert_int_equal(log.count, 11);
    assert_true(res.t < 1e11 && res.t == log.t_last);
    o.max_steps = 0;
    /* per-state relative tolerances */
    const double tout = 40.0, rtol_same[3] = {1e-8, 1e-8, 1e-8}, rtol_y2[3] = {1e-8, 1e-11, 1e-8};
    double ys[3], yv[3];
    dyn_result rs, rv;
    assert_int_equal(dyn_cvode_solve(&sys, 0.0, m->y0, &tout, 1, &o, NULL, NULL, ys, &rs), DYN_OK);
    o.rtolv = rtol_same;
    assert_int_equal(dyn_cvode_solve(&sys, 0.0, m->y0, &tout, 1, &o, NULL, NULL, yv, &rv), DYN_OK);
    for (int i = 0; i < 3; i++)
        assert_true(ys[i] == yv[i]);
    assert_int_equal(rs.stats.accepted, rv.stats.accepted);
    o.rtolv = rtol_y2;
    assert_int_equal(dyn_cvode_solve(&sys, 0.0, m->y0, &tout, 1, &o, NULL, NULL, yv, &rv), DYN_OK);
    CHECK(rv.stats.accepted > rs.stats.accepted, "%ld steps, scalar %ld", rv.stats.accepted,
          rs.stats.accepted);
    /* bad spans */
    assert_int_equal(dyn_cvode_solve_steps(&sys, 1.0, 1.0, m->y0, &o, NULL, NULL, y, &res),
                     DYN_ERR_ARG);
}

/* f refuses times past t_max, and fails on request at t_fail. */
typedef struct guard {
    double t_max, t_fail;
    double t_seen;
} guard;

static int guarded(double t, const double *y, double *f, void *par)
{
    guard *g = par;
    g->t_seen = fmax(g->t_seen, t);
    if (t > g->t_max)
        return 42;
    if (t >= g->t_fail)
        return 7;
    f[0] = -50.0 * (y[0] - cos(t));
    return 0;
}

static void test_failures_and_limits(void **state)
{
    (void)state;
    guard g = {2.0, INFINITY, -INFINITY};
    dyn_system sys = {guarded, 1, &g};
    const double y0 = 1.0, tout[3] = {0.0, 1.0, 2.0};
    double y;
    dyn_result res;
    dyn_cvode_opts o = {.rtol = 1e-8, .atol = 1e-10};
    /* never past the last output time */
    assert_int_equal(dyn_cvode_solve(&sys, 0.0, &y0, tout, 3, &o, NULL, NULL, &y, &res), DYN_OK);
    assert_true(g.t_seen <= 2.0);
    const double L = 50.0, ex = (L * L * cos(2.0) + L * sin(2.0)) / (L * L + 1.0);
    CHECK(fabs(y - ex) < 1e-6, "y(2) = %.17g, exact %.17g", y, ex);
    /* a failing right-hand side */
    g.t_fail = 1.5;
    assert_int_equal(dyn_cvode_solve(&sys, 0.0, &y0, tout, 3, &o, NULL, NULL, &y, &res),
                     DYN_ERR_RHS);
    assert_int_equal(res.rhs_status, 7);
    assert_true(res.fail_t >= 1.5 && res.t == 1.0);
    /* too many steps */
    g.t_fail = INFINITY;
    o.max_steps = 5;
    assert_int_equal(dyn_cvode_solve(&sys, 0.0, &y0, tout, 3, &o, NULL, NULL, &y, &res),
                     DYN_ERR_MAX_STEPS);
    assert_true(strlen(res.message) > 0);
    /* bad output times */
    o.max_steps = 0;
    const double bad[2] = {1.0, 0.5};
    assert_int_equal(dyn_cvode_solve(&sys, 0.0, &y0, bad, 2, &o, NULL, NULL, &y, &res),
                     DYN_ERR_ARG);
    assert_non_null(strstr(res.message, "output time"));
    assert_true(strlen(dyn_cvode_version()) >= 5);
}

/* The band solver: the Brusselator with N = 20 (band 2 + 2) against SciPy's reference,
 * with the analytic band and with CVODE's banded difference quotients, and the same run with
 * the dense solver giving the same answer to the tolerance. */
static void test_band_brusselator(void **state)
{
    (void)state;
    const dyn_reference *r = dyn_reference_find("brusselator-20-10");
    assert_non_null(r);
    char err[128];
    dyn_model *m = dyn_brusselator_new(20, err, sizeof err);
    assert_non_null(m);
    dyn_brusselator_par par;
    double y0[40], yb[40], yq[40], yd[40];
    assert_int_equal(dyn_model_default_params(m, &par, err, sizeof err), 0);
    dyn_model_initial_state(m, &par, y0);
    const dyn_system sys = {dyn_brusselator_rhs, 40, &par};
    const double tout[1] = {10.0};
    dyn_result res;
    dyn_cvode_opts o = {.rtol = 1e-10, .atol = 1e-10, .jac_banded = 1, .jac_lower = 2,
                        .jac_upper = 2, .jacobian_band = dyn_brusselator_jac_band};
    assert_int_equal(dyn_cvode_solve(&sys, 0.0, y0, tout, 1, &o, NULL, NULL, yb, &res), DYN_OK);
    assert_true(res.stats.jac_calls > 0);
    o.jacobian_band = NULL; /* CVODE's banded difference quotients: 5 calls per Jacobian */
    assert_int_equal(dyn_cvode_solve(&sys, 0.0, y0, tout, 1, &o, NULL, NULL, yq, &res), DYN_OK);
    const long band_dq_calls = res.stats.rhs_calls, band_dq_jacs = res.stats.jac_calls;
    o = (dyn_cvode_opts){.rtol = 1e-10, .atol = 1e-10}; /* dense quotients: 40 per Jacobian */
    assert_int_equal(dyn_cvode_solve(&sys, 0.0, y0, tout, 1, &o, NULL, NULL, yd, &res), DYN_OK);
    test_note("difference Jacobians: band %ld calls of f for %ld, dense %ld for %ld\n",
              band_dq_calls, band_dq_jacs, res.stats.rhs_calls, res.stats.jac_calls);
    assert_true(band_dq_calls < res.stats.rhs_calls);
    o = (dyn_cvode_opts){.rtol = 1e-10, .atol = 1e-10, .jacobian = dyn_brusselator_jac};
    assert_int_equal(dyn_cvode_solve(&sys, 0.0, y0, tout, 1, &o, NULL, NULL, yd, &res), DYN_OK);
    const double eb = max_abs_diff(yb, r->y, 40), eq = max_abs_diff(yq, r->y, 40),
                 ed = max_abs_diff(yd, r->y, 40);
    /* (band and dense LU with partial pivoting do the same arithmetic on the band, so the
     * two runs with the analytic Jacobian may agree to the bit) */
    test_note("Brusselator N = 20 at 1e-10 against SciPy: band %.2e, band differences %.2e, "
              "dense %.2e\n", eb, eq, ed);
    assert_true(eb < 1e-7 && eq < 1e-7 && ed < 1e-7);
    /* a band out of range is refused */
    o = (dyn_cvode_opts){.jac_banded = 1, .jac_lower = 40, .jac_upper = 2};
    assert_int_equal(dyn_cvode_solve(&sys, 0.0, y0, tout, 1, &o, NULL, NULL, yb, &res),
                     DYN_ERR_ARG);
    assert_non_null(strstr(res.message, "band of the Jacobian"));
    dyn_brusselator_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_band_brusselator),
        cmocka_unit_test(test_robertson),
        cmocka_unit_test(test_van_der_pol),
        cmocka_unit_test(test_failures_and_limits),
        cmocka_unit_test(test_every_step_and_rtolv),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

#else /* no SUNDIALS: nothing to test */

static void test_cvode_not_built(void **state)
{
    (void)state;
    skip();
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cvode_not_built),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
#endif
