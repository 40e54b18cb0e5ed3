/* SPDX-License-Identifier: BSD-3-Clause */
/* test_problems.c — the verification problems (dynkit/problems.h) and their references:
 * - every model's analytic Jacobian (the new ones and van der Pol's) agrees with central
 *   differences of its right-hand side at several states;
 * - Arenstorf's orbit returns to its start after one period with classical RK4 at a small
 *   step, keeps its Jacobi constant, and matches the closing state of the reference;
 * - Robertson conserves y1 + y2 + y3 = 1 (to rounding) with RK4 and with RODAS;
 * - RODAS at tight tolerances reproduces every reference (Robertson to 1e11, HIRES, van der
 *   Pol mu = 1 and mu = 1000) to a small multiple of the tolerance, and the two van der Pol
 *   mu = 1000 references at t = 2000 (Test Set and ours) agree to the Test Set's accuracy;
 * - the reference table is consistent: unique names, known models and parameters, setup
 *   fills parameters and initial states. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <float.h>

#include "dynkit/brusselator.h"
#include "dynkit/models.h"
#include "dynkit/problems.h"
#include "ode/rosenbrock.h"
#include "test_util.h"

#define NMAX 40

/* A parameter struct big enough for every model here. */
typedef union any_par {
    dyn_vanderpol_par vdp;
    dyn_arenstorf_par aren;
    dyn_robertson_par rober;
    dyn_hires_par hires;
    dyn_brusselator_par bruss;
    double pad[16];
} any_par;

/* A built-in model, or one of a chosen size (brusselator:N, built once per name). */
static const dyn_model *model(const char *name)
{
    static struct {
        char name[32];
        dyn_model *m;
    } sized[4];
    const dyn_model *m = dyn_model_find(name);
    for (int i = 0; !m && i < 4; i++) {
        if (!sized[i].m) {
            snprintf(sized[i].name, sizeof sized[i].name, "%s", name);
            sized[i].m = dyn_brusselator_for_name(name);
        }
        if (strcmp(sized[i].name, name) == 0)
            m = sized[i].m;
    }
    assert_non_null(m);
    return m;
}

static void default_par(const dyn_model *m, any_par *par)
{
    char err[128];
    assert_true(m->par_size <= sizeof *par);
    assert_int_equal(dyn_model_default_params(m, par, err, sizeof err), 0);
}

/* ---- Jacobians against central differences ---- */
static void check_jacobian(const dyn_model *m, void *par, double t, const double *y)
{
    const int n = m->n_states;
    double J[NMAX * NMAX], yp[NMAX], ym[NMAX], fp[NMAX], fm[NMAX], f0[NMAX];
    assert_non_null(m->jacobian);
    assert_int_equal(m->jacobian(t, y, J, par), 0);
    assert_int_equal(m->rhs(t, y, f0, par), 0);
    double fscale = 0.0;
    for (int i = 0; i < n * n; i++)
        fscale = fmax(fscale, fabs(J[i]));
    for (int j = 0; j < n; j++) {
        memcpy(yp, y, (size_t)n * sizeof *y);
        memcpy(ym, y, (size_t)n * sizeof *y);
        const double d = 1e-6 * fmax(fabs(y[j]), 1e-3);
        yp[j] += d;
        ym[j] -= d;
        assert_int_equal(m->rhs(t, yp, fp, par), 0);
        assert_int_equal(m->rhs(t, ym, fm, par), 0);
        for (int i = 0; i < n; i++) {
            const double fd = (fp[i] - fm[i]) / (yp[j] - ym[j]);
            const double ex = J[i * n + j];
            CHECK(fabs(fd - ex) <= 1e-6 * fabs(ex) + 1e-8 * fscale,
                  "%s: J[%d][%d] = %.17g, central difference %.17g", m->name, i, j, ex, fd);
        }
    }
}

static void test_jacobians_match_differences(void **state)
{
    (void)state;
    any_par par;
    const dyn_model *vdp = model("vanderpol");
    default_par(vdp, &par);
    const double vs[][2] = {{2.0, 0.0}, {-1.3, 0.7}, {0.2, -3.0}};
    for (int mu = 0; mu < 2; mu++) {
        par.vdp.mu = mu ? 1000.0 : 1.0;
        for (size_t k = 0; k < 3; k++)
            check_jacobian(vdp, &par, 0.0, vs[k]);
    }
    const dyn_model *aren = model("arenstorf");
    default_par(aren, &par);
    const double as[][4] = {{0.994, 0.0, 0.0, -2.0015851063790825},
                            {-0.5, 0.6, 1.2, -0.3},
                            {0.95, -0.05, -0.4, 1.7}};
    for (size_t k = 0; k < 3; k++)
        check_jacobian(aren, &par, 0.0, as[k]);
    const dyn_model *rob = model("robertson");
    default_par(rob, &par);
    const double rs[][3] = {{1.0, 0.0, 0.0}, {0.7, 3.6e-5, 0.3}, {0.02, 1e-9, 0.98}};
    for (size_t k = 0; k < 3; k++)
        check_jacobian(rob, &par, 0.0, rs[k]);
    const dyn_model *hir = model("hires");
    default_par(hir, &par);
    const double hs[][8] = {{1, 0, 0, 0, 0, 0, 0, 0.0057},
                            {0.7e-3, 0.14e-3, 0.6e-4, 1.2e-3, 2.4e-3, 6.2e-3, 2.85e-3, 2.85e-3},
                            {0.3, 0.1, 0.05, 0.2, 0.1, 0.4, 0.002, 0.0037}};
    for (size_t k = 0; k < 3; k++)
        check_jacobian(hir, &par, 0.0, hs[k]);
}

/* ---- Arenstorf ---- */
static void test_arenstorf_returns_after_one_period(void **state)
{
    (void)state;
    const dyn_model *m = model("arenstorf");
    any_par par;
    default_par(m, &par);
    const dyn_tableau *rk4 = dyn_method_find("rk4");
    assert_non_null(rk4);
    dyn_system sys = {m->rhs, 4, &par};
    double work[TEST_WORK], y[4];
    const double T = DYN_ARENSTORF_PERIOD;
    const dyn_reference *ref = dyn_reference_find("arenstorf-period");
    assert_non_null(ref);
    double err[2];
    const long steps[2] = {400000, 800000};
    for (int l = 0; l < 2; l++) {
        dyn_result res;
        assert_int_equal(
            dyn_fixed_solve(rk4, &sys, 0.0, T, T / (double)steps[l], m->y0, y, work, NULL, &res),
            DYN_OK);
        assert_int_equal(res.stats.steps, steps[l]);
        err[l] = max_abs_diff(y, m->y0, 4);
        /* the Jacobi constant is kept to the accuracy of the run */
        const double c0 = dyn_arenstorf_jacobi(&par.aren, m->y0);
        const double c1 = dyn_arenstorf_jacobi(&par.aren, y);
        CHECK(fabs(c1 - c0) < 10.0 * err[l] + 1e-12, "Jacobi constant %.17g -> %.17g", c0, c1);
        /* the reference of the closing state is closer to the run than y0 is when the run
         * error is small: they differ by 1.4e-11 */
        assert_true(max_abs_diff(y, ref->y, 4) < err[l] + 2e-11);
    }
    /* back at the start: RK4 with 8e5 steps of 2.1e-5 closes the orbit to ~1.2e-7;
     * halving the step divides the miss by ~16 */
    CHECK(err[1] < 2e-7, "orbit misses its start by %.3g", err[1]);
    CHECK(err[0] / err[1] > 12.0 && err[0] / err[1] < 20.0, "misses %.3g, %.3g", err[0],
          err[1]);
    /* not a fixed point: half a period away it is far from the start */
    dyn_result res;
    assert_int_equal(dyn_fixed_solve(rk4, &sys, 0.0, T / 2, T / 200000.0, m->y0, y, work, NULL,
                                     &res),
                     DYN_OK);
    assert_true(max_abs_diff(y, m->y0, 4) > 1.0);
}

/* ---- Robertson: y1 + y2 + y3 = 1 ---- */
typedef struct mass_log {
    double worst;
} mass_log;

static int mass_output(long k, double t, const double *y, void *ctx)
{
    mass_log *ml = ctx;
    (void)k;
    (void)t;
    ml->worst = fmax(ml->worst, fabs(y[0] + y[1] + y[2] - 1.0));
    return 0;
}

static int mass_on_step(double t_old, double t_new, const double *y, const double *cont,
                        void *ctx)
{
    (void)t_old;
    (void)cont;
    return mass_output(0, t_new, y, ctx);
}

static void test_robertson_conserves_mass(void **state)
{
    (void)state;
    const dyn_model *m = model("robertson");
    any_par par;
    default_par(m, &par);
    /* RK4 at the model's default run ([0, 40], step 1e-4: 4e5 steps) */
    const dyn_tableau *rk4 = dyn_method_find("rk4");
    dyn_system sys = {m->rhs, 3, &par};
    double work[TEST_WORK], y[3];
    mass_log ml = {0};
    dyn_fixed_opts opts = {.output = mass_output, .output_ctx = &ml};
    dyn_result res;
    assert_int_equal(dyn_fixed_solve(rk4, &sys, m->t0, m->t1, m->step, m->y0, y, work, &opts,
                                     &res),
                     DYN_OK);
    CHECK(ml.worst < 1e-13, "RK4: |y1 + y2 + y3 - 1| up to %.3g", ml.worst);
    /* and RK4 at this step is already close to the t = 40 reference */
    const dyn_reference *r40 = dyn_reference_find("robertson-40");
    assert_non_null(r40);
    for (int i = 0; i < 3; i++)
        CHECK(fabs(y[i] - r40->y[i]) < 1e-9 * fabs(r40->y[i]), "RK4 y%d(40) = %.17g, ref %.17g",
              i + 1, y[i], r40->y[i]);

    /* RODAS over the Test Set's interval [0, 1e11]: linear invariants are kept exactly by
     * Rosenbrock methods too, up to rounding (which grows with the number of steps) */
    const dyn_ros_problem p = {{m->rhs, 3, &par}, m->jacobian, 1, NULL, 0, NULL, NULL, NULL, NULL, NULL, 0};
    double rw[64], y1[3], e[3], cont[12];
    int piv[3];
    dyn_ros_ws ws;
    dyn_ros_ws_init(&ws, &dyn_ros_rodas4, 3, rw, piv);
    ml.worst = 0.0;
    const double atol[3] = {1e-14, 1e-20, 1e-14};
    dyn_ros_opts o = {.rtol = 1e-10, .atolv = atol, .h0 = 1e-8, .on_step = mass_on_step,
                      .ctx = &ml, .cont = cont};
    dyn_ros_stats st = {0};
    char msg[128];
    double yr[3] = {1.0, 0.0, 0.0};
    int rc = dyn_ros_integrate(&dyn_ros_rodas4, &p, 0.0, 1e11, yr, &o, &ws, y1, e, &st, NULL,
                               msg, sizeof msg);
    CHECK(rc == DYN_OK, "%s", msg);
    CHECK(ml.worst < 1e-13, "RODAS: |y1 + y2 + y3 - 1| up to %.3g in %ld steps", ml.worst,
          st.steps);
}

/* ---- RODAS against every reference ---- */
static void test_rodas_reproduces_references(void **state)
{
    (void)state;
    static const struct {
        const char *name;
        double rtol, atol, atol2; /* atol2: absolute tolerance of state 2 (Robertson) */
        double want;              /* largest accepted relative error */
        double floor;             /* error relative to max(|ref_i|, floor) */
    } cases[] = {
        {"robertson-40", 1e-11, 1e-15, 1e-20, 1e-9, 0},
        {"robertson-1e11", 1e-10, 1e-14, 1e-24, 1e-8, 0},
        {"hires-321.8122", 1e-11, 1e-15, 0, 1e-9, 0},
        {"vanderpol-mu1-15", 1e-11, 1e-13, 0, 1e-8, 0},
        {"vanderpol-mu1000-2000", 1e-11, 1e-13, 0, 1e-8, 0},
        {"vanderpol-mu1000-3000", 1e-11, 1e-13, 0, 1e-8, 0},
        /* components near zero (1e-13, 1e-11): measured against the orbit's size */
        {"arenstorf-period", 1e-12, 1e-14, 0, 1e-5, 1.0},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        const dyn_reference *r = dyn_reference_find(cases[c].name);
        assert_non_null(r);
        const dyn_model *m = model(r->model);
        any_par par;
        double y[NMAX], atol[NMAX], y1[NMAX], e[NMAX];
        char msg[128];
        assert_int_equal(dyn_reference_setup(r, &par, y, msg, sizeof msg), 0);
        for (int i = 0; i < r->n; i++)
            atol[i] = (i == 1 && cases[c].atol2 > 0) ? cases[c].atol2 : cases[c].atol;
        const dyn_ros_problem p = {{m->rhs, r->n, &par}, m->jacobian, 1, NULL, 0, NULL, NULL, NULL, NULL, NULL, 0};
        double rw[2 * NMAX * NMAX + 12 * NMAX];
        int piv[NMAX];
        dyn_ros_ws ws;
        dyn_ros_ws_init(&ws, &dyn_ros_rodas4, r->n, rw, piv);
        dyn_ros_opts o = {.rtol = cases[c].rtol, .atolv = atol, .h0 = 1e-6};
        dyn_ros_stats st = {0};
        int rc = dyn_ros_integrate(&dyn_ros_rodas4, &p, r->t0, r->t1, y, &o, &ws, y1, e, &st,
                                   NULL, msg, sizeof msg);
        CHECK(rc == DYN_OK, "%s: %s", r->name, msg);
        double worst = 0.0;
        for (int i = 0; i < r->n; i++) {
            const double rel = fabs(y[i] - r->y[i]) / fmax(fabs(r->y[i]), cases[c].floor);
            worst = fmax(worst, rel);
        }
        CHECK(worst < cases[c].want, "%s: relative error %.3g in %ld steps (%ld rhs calls)",
              r->name, worst, st.steps, st.rhs_calls);
    }
}

/* ---- the table itself ---- */
static void test_reference_table(void **state)
{
    (void)state;
    assert_true(dyn_reference_count() >= 8);
    assert_null(dyn_reference_at(-1));
    assert_null(dyn_reference_at(dyn_reference_count()));
    assert_null(dyn_reference_find("nosuch"));
    for (int i = 0; i < dyn_reference_count(); i++) {
        const dyn_reference *r = dyn_reference_at(i);
        assert_non_null(r);
        assert_ptr_equal(dyn_reference_find(r->name), r);
        const dyn_model *m = model(r->model);
        assert_int_equal(m->n_states, r->n);
        assert_true(r->t1 > r->t0);
        assert_true(r->error > 0.0 && r->error < 1e-6);
        assert_non_null(r->source);
        assert_non_null(r->method);
        any_par par;
        double y0[NMAX];
        char err[128];
        CHECK(dyn_reference_setup(r, &par, y0, err, sizeof err) == 0, "%s: %s", r->name, err);
        for (int k = 0; k < r->n_set; k++) {
            int pi = dyn_model_param_index(m, r->set[k].name);
            assert_true(pi >= 0);
            assert_true(dyn_model_get_param(m, &par, pi) == r->set[k].value);
        }
        for (int k = 0; k < r->n; k++)
            assert_true(isfinite(r->y[k]) && isfinite(y0[k]));
    }
    /* the two t = 2000 values of van der Pol mu = 1000 agree to the Test Set's accuracy */
    const dyn_reference *a = dyn_reference_find("vanderpol-mu1000-2000");
    const dyn_reference *b = dyn_reference_find("vanderpol-mu1000-2000-testset");
    assert_non_null(a);
    assert_non_null(b);
    for (int k = 0; k < 2; k++)
        assert_true(fabs(a->y[k] - b->y[k]) <= b->error * fabs(b->y[k]));
    /* an unknown parameter is reported */
    dyn_ref_setting bad = {"nosuch", 1.0};
    dyn_reference r = *a;
    r.set = &bad;
    any_par par;
    double y0[2];
    char err[128];
    assert_int_not_equal(dyn_reference_setup(&r, &par, y0, err, sizeof err), 0);
    assert_non_null(strstr(err, "nosuch"));
}

static void test_models_registered(void **state)
{
    (void)state;
    const char *names[] = {"arenstorf", "robertson", "hires"};
    for (size_t k = 0; k < 3; k++) {
        const dyn_model *m = model(names[k]);
        assert_non_null(m->jacobian);
        assert_non_null(dyn_method_find(m->method));
        any_par par;
        default_par(m, &par);
        double f[NMAX], y[NMAX];
        memcpy(y, m->y0, (size_t)m->n_states * sizeof *y);
        assert_int_equal(m->rhs(m->t0, y, f, &par), 0);
        double out[4];
        assert_true(m->n_outputs <= 4);
        assert_int_equal(m->compute_outputs(m->t0, y, &par, out), 0);
    }
    assert_non_null(model("vanderpol")->jacobian);
    /* conserved outputs at the initial states */
    any_par par;
    double out[4];
    const dyn_model *r = model("robertson");
    default_par(r, &par);
    r->compute_outputs(0.0, r->y0, &par, out);
    assert_true(out[0] == 1.0);
    const dyn_model *h = model("hires");
    default_par(h, &par);
    h->compute_outputs(0.0, h->y0, &par, out);
    assert_true(out[0] == 0.0057);
    /* bad parameters are refused */
    const dyn_model *a = model("arenstorf");
    default_par(a, &par);
    char err[128];
    par.aren.mu = 1.5;
    assert_int_not_equal(a->prepare(&par, err, sizeof err), 0);
    par.aren.mu = -1.0;
    assert_int_not_equal(a->prepare(&par, err, sizeof err), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_jacobians_match_differences),
        cmocka_unit_test(test_arenstorf_returns_after_one_period),
        cmocka_unit_test(test_robertson_conserves_mass),
        cmocka_unit_test(test_rodas_reproduces_references),
        cmocka_unit_test(test_reference_table),
        cmocka_unit_test(test_models_registered),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
