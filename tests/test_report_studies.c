/* SPDX-License-Identifier: BSD-3-Clause */
/* The report's three studies of many runs (dynkit/report_studies.h, src/studies): K(k) by the
 * AGM against closed forms; the pendulum's period curve against 4 K(k)/w and the
 * small-angle limit; the plane's sweep reproducing the report's Euler and RK4 runs bit for
 * bit from the unperturbed start, and the statistics of the 1,000 starts ordered and
 * containing the report's answer; the cart's map against lambda recomputed along
 * dyn_cart_prescribed (the full motion, with the quadrature of sY) at N samples, the
 * homework's cell equal to 4d's "along the exact prescribed motion", the fraction of the
 * time slipping recounted; the same bits on 1 and 2 threads. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "dynkit/dynkit.h"
#include "dynkit/plane.h"
#include "dynkit/report_studies.h"
#include "dynkit/sweep.h"
#include "test_util.h"

static dyn_homework hw1, hw2; /* studies on 1 and on 2 threads */

static int setup(void **state)
{
    char err[256] = "";
    (void)state;
    if (dyn_homework_compute(&hw1, err, sizeof err) ||
        dyn_homework_studies(&hw1, 1, err, sizeof err) ||
        dyn_homework_compute(&hw2, err, sizeof err) ||
        dyn_homework_studies(&hw2, 2, err, sizeof err)) {
        fprintf(stderr, "studies failed: %s\n", err);
        return -1;
    }
    return 0;
}

static void test_elliptic_k(void **state)
{
    (void)state;
    assert_true(fabs(dyn_elliptic_k(0.0) - DYN_PI / 2.0) < 1e-15);
    /* K(1/sqrt 2) = Gamma(1/4)^2 / (4 sqrt(pi)) (the lemniscatic case) */
    const double g = tgamma(0.25);
    assert_true(fabs(dyn_elliptic_k(sqrt(0.5)) - g * g / (4.0 * sqrt(DYN_PI))) < 1e-14);
    /* the series K = pi/2 (1 + k^2/4 + 9 k^4/64 + 25 k^6/256 + ...) for small k */
    const double k = 1e-2, k2 = k * k;
    assert_true(fabs(dyn_elliptic_k(k) - DYN_PI / 2 * (1 + k2 / 4 + 9 * k2 * k2 / 64)) < 1e-12);
}

static void test_period(void **state)
{
    const dyn_study_period *s = &hw1.studies.period;
    (void)state;
    assert_int_equal(s->n, DYN_STUDY_PERIOD_RUNS);
    assert_int_equal(s->n_failed, 0);
    double worst = 0.0;
    for (int i = 0; i < s->n; i++) {
        worst = fmax(worst, fabs(s->period_s[i] - s->exact_s[i]));
        if (i)
            assert_true(s->period_s[i] > s->period_s[i - 1]); /* grows with the amplitude */
    }
    assert_true(worst < 1e-9);
    assert_true(s->max_difference_s == worst);
    /* small amplitudes: T = 2 pi/w (1 + a^2/16 + ...) */
    const double a = s->amplitude_rad[0];
    assert_true(fabs(s->period_s[0] - 2 * DYN_PI / s->w * (1 + a * a / 16)) < 1e-6);
}

static void test_plane(void **state)
{
    const dyn_study_plane *s = &hw1.studies.plane;
    (void)state;
    assert_int_equal(s->n_runs, DYN_STUDY_PLANE_RUNS);
    assert_int_equal(s->n_failed, 0);
    assert_true(s->n_changed >= 1);
    assert_true(s->distance_min <= s->distance_pct[0] && s->distance_pct[4] <= s->distance_max);
    assert_true(s->angle_min <= s->angle_pct[0] && s->angle_pct[4] <= s->angle_max);
    for (int q = 1; q < DYN_STUDY_PERCENTILES; q++)
        assert_true(s->distance_pct[q - 1] <= s->distance_pct[q] &&
                    s->angle_pct[q - 1] <= s->angle_pct[q]);
    assert_true(s->distance_min <= s->distance_mean && s->distance_mean <= s->distance_max);
    assert_true(s->angle_min >= 0.0 && s->angle_max <= DYN_PI + 1e-12);
    /* the report's own answer is one draw of the same distribution: inside its range */
    assert_true(hw1.plane.distance_m >= s->distance_min && hw1.plane.distance_m <= s->distance_max);
    /* the perturbations move the answer (chaos), by far more than 1e-14 */
    assert_true(s->distance_max - s->distance_min > 1e-3);

    /* the sweep's runs are the report's runs: from the unperturbed start, Euler and RK4
     * through dyn_sweep give the report's final states bit for bit */
    const dyn_model *m = &dyn_model_plane;
    dyn_plane_par p;
    double y0[12], fe[12], fr[12];
    int st;
    char err[256];
    assert_int_equal(dyn_model_default_params(m, &p, err, sizeof err), 0);
    dyn_model_initial_state(m, &p, y0);
    dyn_sweep_var var = {DYN_SWEEP_STATE, 0};
    dyn_reduce red[12];
    int nr = 0;
    assert_int_equal(dyn_reduce_parse(m, "final", red, 12, &nr, err, sizeof err), 0);
    dyn_sweep sw = {0};
    sw.model = m, sw.par = &p, sw.y0 = y0;
    sw.n_vars = 1, sw.vars = &var, sw.n_runs = 1, sw.values = &y0[0];
    sw.t0 = 0, sw.t1 = m->t1, sw.step = m->step;
    sw.n_reduce = nr, sw.reduce = red, sw.threads = 1;
    sw.method = dyn_method_find("euler");
    assert_int_equal(dyn_sweep_run(&sw, fe, &st, err, sizeof err), DYN_OK);
    sw.method = dyn_method_find("rk4");
    assert_int_equal(dyn_sweep_run(&sw, fr, &st, err, sizeof err), DYN_OK);
    assert_memory_equal(fe, hw1.plane.final_euler, sizeof fe);
    assert_memory_equal(fr, hw1.plane.final_rk4, sizeof fr);
}

/* |lambda| / limit along dyn_cart_prescribed (the full motion) at time t. */
static double ratio_at(const dyn_cart_par *c, double v0, double f, double t)
{
    double s[6], acc[3], Fx, Fy;
    assert_int_equal(dyn_cart_prescribed(c, v0, f, t, s, acc), 0);
    dyn_cart_inverse_forces(c, s[2], acc[0], acc[1], acc[2], &Fx, &Fy);
    return fabs(dyn_cart_lambda(c, Fy, acc[2])) / dyn_cart_friction_limit(c);
}

static void test_cart(void **state)
{
    const dyn_study_cart *s = &hw1.studies.cart;
    const dyn_hw_cart *c = &hw1.cart;
    dyn_cart_par p;
    char err[256];
    (void)state;
    assert_int_equal(dyn_model_default_params(&dyn_model_cart, &p, err, sizeof err), 0);
    assert_int_equal(s->n_failed, 0);
    /* the homework's cell is 4d's max |lambda| along the exact prescribed motion */
    assert_true(fabs(s->homework_ratio - c->max_constraint_force_prescribed_N /
                                             c->friction_limit_N) < 1e-12 * s->homework_ratio);
    /* cells recomputed independently over the N samples t = k Ts */
    const int cells[][2] = {{0, 10}, {5, 3}, {20, 20}, {30, 30}, {12, 7}};
    for (size_t q = 0; q < sizeof cells / sizeof *cells; q++) {
        const int i = cells[q][0], j = cells[q][1];
        double worst = 0.0;
        for (long k = 0; k < c->N; k++)
            worst = fmax(worst, ratio_at(&p, s->v0[i], s->f[j], (double)k * c->Ts));
        const double got = s->ratio[i * s->n_f + j];
        assert_true(fabs(got - worst) <= 1e-12 * fmax(1.0, worst));
    }
    /* standing still without steering: no lateral force */
    assert_true(s->ratio[0] == 0.0);
    /* the slip boundary: below it the ratio is under 1, at the next grid point at least 1 */
    for (int i = 0; i < s->n_v0; i++) {
        if (isnan(s->boundary_f[i]))
            continue;
        int j = 0;
        while (s->f[j] < s->boundary_f[i])
            j++;
        assert_true(s->ratio[i * s->n_f + j] >= 1.0);
        if (j > 0)
            assert_true(s->ratio[i * s->n_f + j - 1] < 1.0);
    }
    /* the time slipping at the homework's point: the trapezoidal time average of the
     * indicator ratio >= 1 over the N samples, recounted */
    double sum = 0.0;
    for (long k = 0; k < c->N; k++) {
        const double w = (k == 0 || k == c->N - 1) ? 0.5 : 1.0;
        sum += w * (ratio_at(&p, 20.0, 2.0, (double)k * c->Ts) >= 1.0);
    }
    assert_true(fabs(s->homework_slip_fraction - sum / (double)(c->N - 1)) < 1e-12);
    assert_true(s->homework_slip_fraction > 0.5 && s->homework_slip_fraction <= 1.0);
}

/* the path model's theta integrated by RK4 is the prescribed pi/8 sin(2 pi f t) */
static void test_cart_path_model(void **state)
{
    const dyn_model *m = &dyn_model_cart_path;
    dyn_cart_path_par p;
    char err[256];
    (void)state;
    assert_int_equal(dyn_model_default_params(m, &p, err, sizeof err), 0);
    dyn_reduce red[2];
    int nr = 0;
    assert_int_equal(dyn_reduce_parse(m, "final", red, 2, &nr, err, sizeof err), 0);
    assert_int_equal(nr, 2);
    dyn_sweep_var var;
    assert_int_equal(dyn_sweep_var_find(m, "f", &var, err, sizeof err), 0);
    const double f[2] = {0.5, 2.0};
    double out[4];
    int st[2];
    dyn_sweep sw = {0};
    sw.model = m, sw.n_vars = 1, sw.vars = &var, sw.n_runs = 2, sw.values = f;
    sw.method = dyn_method_find("rk4"), sw.t0 = 0, sw.t1 = m->t1, sw.step = m->step;
    sw.n_reduce = nr, sw.reduce = red;
    assert_int_equal(dyn_sweep_run(&sw, out, st, err, sizeof err), DYN_OK);
    for (int r = 0; r < 2; r++) {
        assert_true(fabs(out[2 * r] + p.v0 * m->t1) < 1e-12);
        assert_true(fabs(out[2 * r + 1] - DYN_PI / 8 * sin(2 * DYN_PI * f[r] * m->t1)) < 1e-8);
    }
    /* a negative frequency is refused by prepare: a failed run, not a crash */
    const double bad = -1.0;
    sw.n_runs = 1, sw.values = &bad;
    assert_int_equal(dyn_sweep_run(&sw, out, st, err, sizeof err), DYN_OK);
    assert_int_equal(st[0], DYN_ERR_ARG);
}

static void test_same_bits_any_threads(void **state)
{
    (void)state;
    assert_int_equal(hw2.studies.threads, dyn_sweep_threads(2));
    assert_memory_equal(&hw1.studies.period, &hw2.studies.period, sizeof hw1.studies.period);
    assert_memory_equal(&hw1.studies.plane, &hw2.studies.plane, sizeof hw1.studies.plane);
    assert_memory_equal(&hw1.studies.cart, &hw2.studies.cart, sizeof hw1.studies.cart);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_elliptic_k),      cmocka_unit_test(test_period),
        cmocka_unit_test(test_plane),           cmocka_unit_test(test_cart),
        cmocka_unit_test(test_cart_path_model), cmocka_unit_test(test_same_bits_any_threads),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
