/* SPDX-License-Identifier: BSD-3-Clause */
/* The adaptive pairs and their driver (dyn_solve), against numerical facts:
 * - the tables: bs23, dp45, DOP853 satisfy the order conditions of their orders (DOP853:
 *   all 200 rooted trees up to order 8) and fail the next ones; the embedded weights have
 *   their stated orders; FSAL rows; the dense corrections vanish for constant f; DOP853's
 *   observed order is 8 on a smooth problem;
 * - tolerance proportionality: with local extrapolation, step h ~ tol^(1/(q+1)) and a
 *   method of order p = q + 1, the global error falls like tol^(p/(q+1)) = tol^1 from
 *   rtol 1e-4 to 1e-10 on exponential decay, the harmonic oscillator and van der Pol
 *   (mu = 1) against a tight DOP853 reference;
 * - counts: dp45 and bs23 reuse their last stage (FSAL), so rhs = s_eff (accepted +
 *   rejected) + 1 (f(t0)) + 1 (the initial-step probe); DOP853 evaluates f(t + h, y1) only
 *   for the next step: rhs = 11 (accepted + rejected) + accepted + 1;
 * - a peer: with a pure I controller the pairs take SciPy's steps (same counts and errors);
 * - the plane of homework problem 3 with the seed's ode45 tolerances agrees with RK4 at
 *   h = 1e-4; fixed-step tables run by dyn_solve equal dyn_fixed_solve bit for bit;
 * - statuses: step-size underflow at a blow-up, too many steps, bad arguments; max_step
 *   and initial_step are obeyed; the DOPRI5 stiffness test fires on van der Pol with
 *   mu = 1000 and stays quiet for mu = 1. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "dynkit/dynkit.h"
#include "test_util.h"

/* ---- problems ---- */

static int decay_rhs(double t, const double *y, double *f, void *par)
{
    (void)t;
    (void)par;
    f[0] = -y[0];
    return 0;
}

static int oscillator_rhs(double t, const double *y, double *f, void *par)
{
    (void)t;
    (void)par;
    f[0] = y[1];
    f[1] = -y[0];
    return 0;
}

/* y' = y cos t, y = exp(sin t): smooth and not autonomous */
static int expsin_rhs(double t, const double *y, double *f, void *par)
{
    (void)par;
    f[0] = y[0] * cos(t);
    return 0;
}

/* y' = y^2, y(0) = 1: y = 1/(1 - t) blows up at t = 1 */
static int blowup_rhs(double t, const double *y, double *f, void *par)
{
    (void)t;
    (void)par;
    f[0] = y[0] * y[0];
    return 0;
}

/* Solve with method name and tolerances; returns the status, y the final state. */
static int solve(const char *method, const dyn_system *sys, double t0, double t1,
                 const double *y0, double rtol, double atol, double *y, dyn_result *res,
                 dyn_solve_opts *extra)
{
    const dyn_tableau *m = dyn_method_find(method);
    assert_non_null(m);
    dyn_solve_opts o = {0};
    if (extra)
        o = *extra;
    o.rtol = rtol;
    o.atol = atol;
    size_t size = dyn_solve_work_size(m, sys->n, &o);
    assert_true(size > 0);
    double *work = malloc(size * sizeof *work);
    assert_non_null(work);
    int rc = dyn_solve(m, sys, t0, t1, y0, y, work, &o, res);
    free(work);
    return rc;
}

static const char *const pairs[] = {"bs23", "dp45", "dop853"};

/* ---- tables ---- */

static void test_pairs_satisfy_their_order_conditions(void **state)
{
    (void)state;
    for (size_t k = 0; k < sizeof pairs / sizeof pairs[0]; k++) {
        const dyn_tableau *m = dyn_method_find(pairs[k]);
        assert_non_null(m);
        assert_int_equal(m->kind, DYN_KIND_EMBEDDED_RK);
        assert_true(dyn_method_is_adaptive(m));
        double r = dyn_tableau_order_residual(m, m->order);
        CHECK(r < 1e-14, "%s: residual %.3g at its order %d", m->name, r, m->order);
        if (m->order < 8) {
            r = dyn_tableau_order_residual(m, m->order + 1);
            CHECK(r > 1e-5, "%s: order %d holds too (%.3g)", m->name, m->order + 1, r);
        }
        double bhat[16];
        for (int i = 0; i < m->stages; i++)
            bhat[i] = m->b[i] - m->e[i];
        r = dyn_tableau_weights_residual(m, bhat, m->embedded_order);
        CHECK(r < 1e-14, "%s: embedded residual %.3g at order %d", m->name, r, m->embedded_order);
        r = dyn_tableau_weights_residual(m, bhat, m->embedded_order + 1);
        CHECK(r > 1e-5, "%s: embedded order %d holds too (%.3g)", m->name, m->embedded_order + 1,
              r);
        if (m->fsal) { /* last row of a = b, c = 1, b_s = 0 */
            const int s = m->stages;
            assert_true(m->c[s - 1] == 1.0 && m->b[s - 1] == 0.0);
            for (int j = 0; j < s; j++)
                assert_true(m->a[(s - 1) * s + j] == m->b[j]);
        }
        /* dense output: the corrections to the cubic Hermite interpolant vanish when all
         * stages are equal (y' constant): every row of D sums to zero */
        for (int j = 0; j + 3 < m->dense_degree; j++) {
            double sum = 0.0;
            for (int i = 0; i < m->dense_stages; i++)
                sum += m->dense[j * m->dense_stages + i];
            CHECK(fabs(sum) < 1e-12, "%s: dense row %d sums to %.3g", m->name, j, sum);
        }
    }
    /* DOP853: order 8 through all 200 trees; the 3rd-order weights b - e3 */
    const dyn_tableau *d = dyn_method_find("dop853");
    double r8 = dyn_tableau_order_residual(d, 8);
    CHECK(r8 < 1e-13, "dop853 order 8 residual %.3g", r8);
    double b3[12];
    for (int i = 0; i < 12; i++)
        b3[i] = d->b[i] - d->e3[i];
    assert_true(dyn_tableau_weights_residual(d, b3, 3) < 1e-14);
    assert_true(dyn_tableau_weights_residual(d, b3, 4) > 1e-4);
    /* a wrong digit in one weight is seen at order 8 */
    dyn_tableau broken = *d;
    double bb[12];
    memcpy(bb, d->b, sizeof bb);
    bb[7] *= 1.0 + 1e-12;
    bb[0] -= d->b[7] * 1e-12;
    broken.b = bb;
    assert_true(dyn_tableau_order_residual(&broken, 8) > 1e-13);
}

/* DOP853 as a fixed-step method (its 8th-order weights through the stage loop) on
 * y' = y cos t: errors at N and 2N steps differ by 2^8. */
static void test_dop853_observed_order_is_8(void **state)
{
    (void)state;
    const dyn_tableau *m = dyn_method_find("dop853");
    dyn_system sys = {expsin_rhs, 1, NULL};
    const double T = 3.0, exact = exp(sin(T));
    double err[3];
    for (int k = 0; k < 3; k++) {
        const long N = 6L << k;
        const double h = T / (double)N;
        double y = 1.0, work[64];
        for (long i = 0; i < N; i++)
            assert_int_equal(dyn_rk_step(m, &sys, (double)i * h, h, &y, &y, work, NULL), 0);
        err[k] = fabs(y - exact);
    }
    for (int k = 0; k < 2; k++) {
        const double order = log2(err[k] / err[k + 1]);
        CHECK(order > 7.6 && order < 8.6, "observed order %.2f (errors %.3g, %.3g)", order,
              err[k], err[k + 1]);
    }
}

/* ---- accuracy against tolerance ---- */

typedef struct problem {
    const char *name;
    dyn_rhs_fn f;
    int n;
    double t1;
    double y0[2];
    double atol_factor; /* atol = rtol * atol_factor */
} problem;

static const problem problems[] = {
    {"decay", decay_rhs, 1, 5.0, {1.0, 0.0}, 1e-3},
    {"oscillator", oscillator_rhs, 2, 10.0, {1.0, 0.0}, 1.0},
    {"vanderpol", NULL, 2, 20.0, {2.0, 0.0}, 1.0},
};

static void exact_or_reference(const problem *p, double *yref)
{
    if (p->f == decay_rhs) {
        yref[0] = exp(-p->t1);
    } else if (p->f == oscillator_rhs) {
        yref[0] = cos(p->t1);
        yref[1] = -sin(p->t1);
    } else {
        dyn_vanderpol_par par = {.mu = 1.0};
        dyn_system sys = {dyn_vanderpol_rhs, 2, &par};
        dyn_result res;
        assert_int_equal(solve("dop853", &sys, 0.0, p->t1, p->y0, 1e-14, 1e-14, yref, &res, NULL),
                         DYN_OK);
    }
}

static void test_error_proportional_to_tolerance(void **state)
{
    (void)state;
    for (size_t k = 0; k < sizeof pairs / sizeof pairs[0]; k++) {
        for (size_t q = 0; q < sizeof problems / sizeof problems[0]; q++) {
            const problem *p = &problems[q];
            dyn_vanderpol_par par = {.mu = 1.0};
            dyn_system sys = {p->f ? p->f : dyn_vanderpol_rhs, p->n, &par};
            double yref[2], y[2], lt[7], le[7];
            exact_or_reference(p, yref);
            const double scale = p->f == decay_rhs ? yref[0] : 1.0;
            int count = 0;
            for (int e = 4; e <= 10; e++) {
                const double tol = pow(10.0, -e);
                dyn_result res;
                assert_int_equal(solve(pairs[k], &sys, 0.0, p->t1, p->y0, tol,
                                       tol * p->atol_factor, y, &res, NULL),
                                 DYN_OK);
                const double err = norm_diff(y, yref, p->n) / scale;
                /* the global error stays within a modest factor of the tolerance */
                CHECK(err < 100.0 * tol, "%s on %s at rtol %g: error %.3g", pairs[k], p->name, tol,
                      err);
                lt[count] = log10(tol);
                le[count] = log10(fmax(err, 1e-17));
                count++;
            }
            /* least-squares slope of log(err) against log(tol): ~ p/(q+1) = 1 */
            double mt = 0, me = 0, stt = 0, ste = 0;
            for (int i = 0; i < count; i++) {
                mt += lt[i] / count;
                me += le[i] / count;
            }
            for (int i = 0; i < count; i++) {
                stt += (lt[i] - mt) * (lt[i] - mt);
                ste += (lt[i] - mt) * (le[i] - me);
            }
            const double slope = ste / stt;
            test_note("%-7s %-10s error ~ tol^%.2f (at 1e-4: %.2g, at 1e-10: %.2g)", pairs[k],
                      p->name, slope, pow(10, le[0]), pow(10, le[count - 1]));
            CHECK(slope > 0.8 && slope < 1.4, "%s on %s: error ~ tol^%.2f", pairs[k], p->name,
                  slope);
        }
    }
}

/* ---- counts ---- */

static void test_rhs_counts(void **state)
{
    (void)state;
    dyn_vanderpol_par par = {.mu = 1.0};
    dyn_system sys = {dyn_vanderpol_rhs, 2, &par};
    const double y0[2] = {2.0, 0.0};
    double y[2];
    for (int e = 4; e <= 10; e += 2) {
        const double tol = pow(10.0, -e);
        dyn_result res;
        assert_int_equal(solve("dp45", &sys, 0.0, 20.0, y0, tol, tol, y, &res, NULL), DYN_OK);
        const long att = res.stats.accepted + res.stats.rejected;
        assert_int_equal(res.stats.steps, att);
        /* FSAL: 6 new stages per attempt, f(t0), and the initial-step probe */
        assert_int_equal(res.stats.rhs_calls, 6 * att + 2);
        assert_int_equal(solve("bs23", &sys, 0.0, 20.0, y0, tol, tol, y, &res, NULL), DYN_OK);
        assert_int_equal(res.stats.rhs_calls,
                         3 * (res.stats.accepted + res.stats.rejected) + 2);
        assert_int_equal(solve("dop853", &sys, 0.0, 20.0, y0, tol, tol, y, &res, NULL), DYN_OK);
        assert_int_equal(res.stats.rhs_calls,
                         11 * (res.stats.accepted + res.stats.rejected) + res.stats.accepted + 1);
    }
    /* a given first step needs no probe */
    dyn_solve_opts o = {0};
    o.initial_step = 0.01;
    dyn_result res;
    assert_int_equal(solve("dp45", &sys, 0.0, 20.0, y0, 1e-6, 1e-6, y, &res, &o), DYN_OK);
    assert_int_equal(res.stats.rhs_calls, 6 * (res.stats.accepted + res.stats.rejected) + 1);
}

/* A peer: SciPy 1.10's solve_ivp (RK23, RK45, DOP853) uses the same error norm, the same
 * initial step (HNW I II.4) and a pure I controller (safety 0.9, ratio in [0.2, 10]). With
 * beta < 0 (no PI term) and safety 0.9 (dp45's own is 0.8) our pairs take the same steps: van der Pol mu = 1 on [0, 20] from
 * (2, 0), rtol = atol = 1e-6 .. 1e-10; SciPy's nfev and error against a tight reference.
 * (SciPy's DOP853 evaluates f(t + h, y1) also after rejected steps, so only its error is
 * compared.) Counts may differ slightly where the compiler contracts to FMA. */
static void test_same_steps_as_scipy_with_i_controller(void **state)
{
    (void)state;
    static const struct {
        const char *method;
        long nfev[5];
        double err[5];
    } scipy[] = {
        {"bs23", {2837, 6056, 13055, 28139, 60629}, {8.5e-07, 1.1e-07, 1.4e-08, 1.5e-09, 1.6e-10}},
        {"dp45", {1142, 1610, 2198, 3284, 5120}, {2.1e-05, 1.4e-06, 1.1e-07, 8.5e-09, 6.8e-10}},
        {"dop853", {0}, {8.7e-07, 9.4e-08, 2.0e-09, 7.8e-10, 9.5e-11}},
    };
    dyn_vanderpol_par par = {.mu = 1.0};
    dyn_system sys = {dyn_vanderpol_rhs, 2, &par};
    const double y0[2] = {2.0, 0.0};
    double yref[2], y[2];
    exact_or_reference(&problems[2], yref);
    for (size_t k = 0; k < sizeof scipy / sizeof scipy[0]; k++) {
        for (int e = 6; e <= 10; e++) {
            dyn_solve_opts o = {0};
            o.beta = -1.0;
            o.safety = 0.9;
            dyn_result res;
            const double tol = pow(10.0, -e);
            assert_int_equal(solve(scipy[k].method, &sys, 0.0, 20.0, y0, tol, tol, y, &res, &o),
                             DYN_OK);
            const double err = norm_diff(y, yref, 2), ref_err = scipy[k].err[e - 6];
            const long nfev = scipy[k].nfev[e - 6];
            if (nfev)
                CHECK(labs(res.stats.rhs_calls - nfev) <= nfev / 50, "%s rtol %g: %ld calls, SciPy %ld",
                      scipy[k].method, tol, res.stats.rhs_calls, nfev);
            CHECK(err < 1.5 * ref_err && err > ref_err / 1.5, "%s rtol %g: error %.3g, SciPy %.3g",
                  scipy[k].method, tol, err, ref_err);
        }
    }
}

/* ---- the plane with the seed's tolerances ---- */

static void test_plane_dp45_agrees_with_rk4(void **state)
{
    (void)state;
    const dyn_model *m = dyn_model_find("plane");
    assert_non_null(m);
    dyn_plane_par par;
    char err[128];
    assert_int_equal(dyn_model_default_params(m, &par, err, sizeof err), 0);
    dyn_system sys = {m->rhs, 12, &par};
    double yr[12], ya[12], work[16 * 12];
    dyn_result res;
    assert_int_equal(dyn_fixed_solve(dyn_method_find("rk4"), &sys, 0.0, 5.0, 1e-4, m->y0, yr,
                                     work, NULL, &res),
                     DYN_OK);
    assert_int_equal(solve("ode45", &sys, 0.0, 5.0, m->y0, 1e-8, 1e-10, ya, &res, NULL), DYN_OK);
    const double d = max_abs_diff(ya, yr, 12);
    test_note("plane at t = 5: dp45 (rtol 1e-8, atol 1e-10) - rk4 (h = 1e-4): %.3g in %ld steps",
              d, res.stats.accepted);
    CHECK(d < 1e-6, "dp45 and RK4 differ by %.3g", d);
    assert_int_equal(solve("dop853", &sys, 0.0, 5.0, m->y0, 1e-12, 1e-12, ya, &res, NULL),
                     DYN_OK);
    CHECK(max_abs_diff(ya, yr, 12) < 1e-6, "dop853 and RK4 differ by %.3g",
          max_abs_diff(ya, yr, 12));
}

/* ---- fixed-step tables through dyn_solve ---- */

static void test_fixed_tables_equal_fixed_driver(void **state)
{
    (void)state;
    dyn_vanderpol_par par = {.mu = 1.0};
    dyn_system sys = {dyn_vanderpol_rhs, 2, &par};
    const double y0[2] = {2.0, 0.0};
    static const double spans[][3] = {{0.0, 15.0, 0.01}, {0.0, 1.0, 0.3}, {0.5, 2.0, 0.25}};
    static sample_log a, b;
    for (int i = 0; i < dyn_method_count(); i++) {
        const dyn_tableau *m = fixed_method_at(i);
        if (!m)
            continue;
        for (size_t s = 0; s < sizeof spans / sizeof spans[0]; s++) {
            for (int end = DYN_END_EXACT; end <= DYN_END_GRID; end++) {
                double ya[2], yb[2], work[TEST_WORK];
                dyn_result ra, rb;
                sample_log_init(&a, 2);
                sample_log_init(&b, 2);
                dyn_fixed_opts fo = {0};
                fo.end = (dyn_end_policy)end;
                fo.output = sample_log_output;
                fo.output_ctx = &a;
                assert_int_equal(dyn_fixed_solve(m, &sys, spans[s][0], spans[s][1], spans[s][2],
                                                 y0, ya, work, &fo, &ra),
                                 DYN_OK);
                dyn_solve_opts so = {0};
                so.h = spans[s][2];
                so.end = (dyn_end_policy)end;
                so.output = sample_log_output;
                so.output_ctx = &b;
                assert_true(dyn_solve_work_size(m, 2, &so) <= TEST_WORK);
                assert_int_equal(dyn_solve(m, &sys, spans[s][0], spans[s][1], y0, yb, work, &so,
                                           &rb),
                                 DYN_OK);
                assert_int_equal(a.count, b.count);
                for (long k = 0; k < a.count; k++) {
                    assert_true(same_bits(a.t[k], b.t[k]));
                    assert_true(same_bits(a.y[k][0], b.y[k][0]) &&
                                same_bits(a.y[k][1], b.y[k][1]));
                }
                assert_true(same_bits(ya[0], yb[0]) && same_bits(ya[1], yb[1]));
                assert_true(same_bits(ra.t, rb.t));
                assert_int_equal(ra.stats.steps, rb.stats.steps);
                assert_int_equal(rb.stats.accepted, rb.stats.steps);
                assert_int_equal(ra.stats.rhs_calls, rb.stats.rhs_calls);
            }
        }
    }
}

/* ---- statuses and options ---- */

static void test_step_size_underflow_at_blowup(void **state)
{
    (void)state;
    dyn_system sys = {blowup_rhs, 1, NULL};
    const double y0 = 1.0;
    for (size_t k = 0; k < sizeof pairs / sizeof pairs[0]; k++) {
        double y;
        dyn_result res;
        int rc = solve(pairs[k], &sys, 0.0, 2.0, &y0, 1e-8, 1e-8, &y, &res, NULL);
        CHECK(rc == DYN_ERR_STEP_SIZE || rc == DYN_ERR_NONFINITE, "%s: status %d (%s)", pairs[k],
              rc, res.message);
        /* stopped at the blow-up (whose numerical place is within the global error of t = 1),
         * keeping the last good, finite, large state */
        test_note("%s: %s at t = %.17g, y = %.3g after %ld steps", pairs[k], dyn_status_name(rc),
                  res.t, y, res.stats.steps);
        CHECK(fabs(res.t - 1.0) < 1e-6, "%s: stopped at t = %.17g", pairs[k], res.t);
        CHECK(isfinite(y) && y > 1e5, "%s: y = %g at t = %.17g", pairs[k], y, res.t);
        assert_true(strlen(res.message) > 0);
    }
}

static void test_too_many_steps(void **state)
{
    (void)state;
    dyn_system sys = {oscillator_rhs, 2, NULL};
    const double y0[2] = {1.0, 0.0};
    static sample_log log;
    sample_log_init(&log, 2);
    dyn_solve_opts o = {0};
    o.max_steps = 25;
    o.output = sample_log_output;
    o.output_ctx = &log;
    double y[2];
    dyn_result res;
    assert_int_equal(solve("dp45", &sys, 0.0, 100.0, y0, 1e-10, 1e-10, y, &res, &o),
                     DYN_ERR_MAX_STEPS);
    assert_int_equal(res.stats.steps, 25);
    assert_true(res.t > 0.0 && res.t < 100.0);
    /* the solution up to there is kept: the state at res.t is the last sample */
    assert_true(log.count == res.stats.accepted + 1);
    assert_true(same_bits(log.t[log.count - 1], res.t));
    assert_true(fabs(y[0] - cos(res.t)) < 1e-8 && fabs(y[1] + sin(res.t)) < 1e-8);
    assert_non_null(strstr(res.message, "25 steps"));
    assert_string_equal(dyn_status_name(DYN_ERR_MAX_STEPS), "too many steps");
    assert_string_equal(dyn_status_name(DYN_ERR_STEP_SIZE), "step size underflow");
}

static void test_bad_arguments(void **state)
{
    (void)state;
    dyn_system sys = {oscillator_rhs, 2, NULL};
    const double y0[2] = {1.0, 0.0}, bad_atol[2] = {1e-6, -1.0};
    const double times_down[3] = {0.0, 2.0, 1.0}, times_out[2] = {0.0, 11.0};
    double y[2];
    dyn_result res;
    assert_int_equal(solve("dp45", &sys, 0.0, 10.0, y0, -1e-3, 1e-6, y, &res, NULL), DYN_ERR_ARG);
    assert_non_null(strstr(res.message, "rtol"));
    dyn_solve_opts o = {0};
    o.atolv = bad_atol;
    assert_int_equal(solve("dp45", &sys, 0.0, 10.0, y0, 1e-3, 0, y, &res, &o), DYN_ERR_ARG);
    memset(&o, 0, sizeof o);
    o.out_times = times_down;
    o.n_out_times = 3;
    assert_int_equal(solve("dp45", &sys, 0.0, 10.0, y0, 1e-3, 1e-6, y, &res, &o), DYN_ERR_ARG);
    o.out_times = times_out;
    o.n_out_times = 2;
    assert_int_equal(solve("dp45", &sys, 0.0, 10.0, y0, 1e-3, 1e-6, y, &res, &o), DYN_ERR_ARG);
    assert_int_equal(solve("dp45", &sys, 1.0, 1.0, y0, 1e-3, 1e-6, y, &res, NULL), DYN_ERR_ARG);
    /* a fixed-step table needs its step */
    double work[64];
    assert_int_equal(dyn_solve(dyn_method_find("rk4"), &sys, 0.0, 1.0, y0, y, work, NULL, &res),
                     DYN_ERR_ARG);
}

typedef struct step_spy {
    long steps;
    double first_h, max_h;
} step_spy;

static int spy_step(const dyn_dense *d, void *ctx)
{
    step_spy *s = ctx;
    if (s->steps++ == 0)
        s->first_h = d->h;
    s->max_h = fmax(s->max_h, d->h);
    return 0;
}

static void test_max_and_initial_step(void **state)
{
    (void)state;
    dyn_system sys = {decay_rhs, 1, NULL};
    const double y0 = 1.0;
    double y;
    dyn_result res;
    step_spy spy = {0};
    dyn_solve_opts o = {0};
    o.step = spy_step;
    o.step_ctx = &spy;
    o.initial_step = 1e-3;
    o.max_step = 0.05;
    assert_int_equal(solve("dp45", &sys, 0.0, 5.0, &y0, 1e-3, 1e-6, &y, &res, &o), DYN_OK);
    assert_true(spy.first_h == 1e-3);
    assert_true(spy.max_h <= 0.05);
    assert_true(res.stats.accepted >= 100); /* 5 / 0.05 */
    assert_int_equal(spy.steps, res.stats.accepted);
    /* without limits the loose tolerance takes big steps */
    memset(&spy, 0, sizeof spy);
    o.initial_step = o.max_step = 0.0;
    assert_int_equal(solve("dp45", &sys, 0.0, 5.0, &y0, 1e-3, 1e-6, &y, &res, &o), DYN_OK);
    assert_true(spy.max_h > 0.3 && res.stats.accepted < 30);
    assert_true(fabs(y - exp(-5.0)) < 1e-4);
}

static void test_stiffness_detection(void **state)
{
    (void)state;
    const double y0[2] = {2.0, 0.0};
    double y[2];
    dyn_result res;
    const char *const detectors[] = {"dp45", "dop853"};
    for (int k = 0; k < 2; k++) {
        dyn_vanderpol_par stiff = {.mu = 1000.0};
        dyn_system sys = {dyn_vanderpol_rhs, 2, &stiff};
        assert_int_equal(solve(detectors[k], &sys, 0.0, 20.0, y0, 1e-6, 1e-6, y, &res, NULL),
                         DYN_OK);
        CHECK(res.stiff == 1, "%s: no stiffness seen on van der Pol mu = 1000", detectors[k]);
        assert_true(res.stiff_t > 0.0 && res.stiff_t < 20.0);
        assert_non_null(strstr(res.stiff_message, "stiff"));
        dyn_vanderpol_par mild = {.mu = 1.0};
        sys.par = &mild;
        assert_int_equal(solve(detectors[k], &sys, 0.0, 20.0, y0, 1e-6, 1e-6, y, &res, NULL),
                         DYN_OK);
        CHECK(res.stiff == 0, "%s: stiffness reported for mu = 1 at t = %g", detectors[k],
              res.stiff_t);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pairs_satisfy_their_order_conditions),
        cmocka_unit_test(test_dop853_observed_order_is_8),
        cmocka_unit_test(test_error_proportional_to_tolerance),
        cmocka_unit_test(test_rhs_counts),
        cmocka_unit_test(test_same_steps_as_scipy_with_i_controller),
        cmocka_unit_test(test_plane_dp45_agrees_with_rk4),
        cmocka_unit_test(test_fixed_tables_equal_fixed_driver),
        cmocka_unit_test(test_step_size_underflow_at_blowup),
        cmocka_unit_test(test_too_many_steps),
        cmocka_unit_test(test_bad_arguments),
        cmocka_unit_test(test_max_and_initial_step),
        cmocka_unit_test(test_stiffness_detection),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
