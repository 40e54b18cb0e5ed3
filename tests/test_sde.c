/* SPDX-License-Identifier: BSD-3-Clause */
/* Noise (dynkit/sde.h, src/ode/sde.c): the observed strong and weak orders of
 * Euler–Maruyama and the Runge–Kutta Milstein scheme on geometric Brownian motion
 * dX = mu X dt + sigma X dW (exact: X(T) = X0 exp((mu - sigma^2/2) T + sigma W(T)), with
 * W(T) integrated alongside as the state b' = w, so the exact solution comes from the same
 * path), the mean and variance of an Ornstein–Uhlenbeck process dX = theta (m - X) dt +
 * sigma dW (mean m + (X0 - m) e^{-theta T}, variance sigma^2 (1 - e^{-2 theta T}) / (2 theta)),
 * the Brownian path of the adaptive runs (W(T) ~ N(0, T) however many steps were
 * rejected), and the reproducibility of the noise (seed, run). Fixed seeds; the bounds
 * are many standard errors wide. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "dynkit/lang.h"
#include "dynkit/sde.h"

typedef struct gbm_par {
    double mu, sigma, w;
} gbm_par;

static int gbm_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    const gbm_par *p = par;
    dydt[0] = p->mu * y[0] + p->sigma * y[0] * p->w;
    dydt[1] = p->w;
    return 0;
}

typedef struct ou_par {
    double theta, m, sigma, w;
} ou_par;

static int ou_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    const ou_par *p = par;
    dydt[0] = p->theta * (p->m - y[0]) + p->sigma * p->w;
    dydt[1] = p->w;
    return 0;
}

static const int wiener_kind[1] = {DYN_NOISE_WIENER};

/* One run: the final state into y. */
static void run(dyn_sde_method method, dyn_rhs_fn f, void *par, double *noise,
                dyn_noise_class cls, double T, const double *y0, const dyn_sde_opts *o,
                double *y, dyn_result *res)
{
    static double work[4096];
    assert_true(dyn_sde_work_size(2, 1, 0) <= 4096);
    dyn_sde sde = {{f, 2, par}, 1, wiener_kind, noise, cls};
    assert_int_equal(dyn_sde_solve(method, &sde, 0.0, T, y0, y, work, o, res), DYN_OK);
}

/* One path of GBM dX = mu X dt + sigma X dW from X = 1 to t = 1 (options o: step, seed;
 * the stream is set here): X(1) and W(1) into y. */
static void gbm_path(dyn_sde_method method, double mu, double sigma, dyn_sde_opts o,
                     uint64_t stream, double *y, dyn_result *res)
{
    gbm_par par = {mu, sigma, 0.0};
    const double y0[2] = {1.0, 0.0};
    o.stream = stream;
    run(method, gbm_rhs, &par, &par.w, DYN_NOISE_COMMUTATIVE, 1.0, y0, &o, y, res);
}

/* Least-squares slope of log err against log h. */
static double slope(const double *h, const double *err, int n)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int i = 0; i < n; i++) {
        const double x = log(h[i]), yv = log(err[i]);
        sx += x;
        sy += yv;
        sxx += x * x;
        sxy += x * yv;
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

/* Mean |X(T) - exact| over paths at steps 2^-3 .. 2^-7 on GBM (mu 1.5, sigma 1: the
 * multiplicative noise where EM's order 1/2 shows). */
static double strong_order(dyn_sde_method method, int paths)
{
    double h[5], err[5];
    for (int k = 0; k < 5; k++) {
        h[k] = ldexp(1.0, -(k + 3));
        double sum = 0.0;
        const dyn_sde_opts o = {.h = h[k], .fixed = 1, .seed = 11};
        for (int p = 0; p < paths; p++) {
            double y[2];
            dyn_result res;
            gbm_path(method, 1.5, 1.0, o, (uint64_t)p, y, &res);
            sum += fabs(y[0] - exp(1.0 + y[1]));
        }
        err[k] = sum / paths;
    }
    const double q = slope(h, err, 5);
    print_message("strong errors %.3g %.3g %.3g %.3g %.3g: order %.3f\n", err[0], err[1],
                  err[2], err[3], err[4], q);
    return q;
}

static void test_strong_order_em(void **state)
{
    (void)state;
    const double q = strong_order(DYN_SDE_EM, 4000);
    assert_true(q > 0.38 && q < 0.62);
}

static void test_strong_order_rkmil(void **state)
{
    (void)state;
    const double q = strong_order(DYN_SDE_RKMIL, 2000);
    assert_true(q > 0.85 && q < 1.2);
}

/* EM's weak order 1 on GBM (mu 1, sigma 0.5): |E X(T) - e^{mu T}| at steps 1/4 .. 1/32 from
 * 2e5 paths each (standard error 0.003 against errors 0.28 .. 0.04). */
static void test_weak_order_em(void **state)
{
    (void)state;
    double h[4], err[4];
    const int paths = 200000;
    for (int k = 0; k < 4; k++) {
        h[k] = ldexp(1.0, -(k + 2));
        double sum = 0.0;
        const dyn_sde_opts o = {.h = h[k], .seed = 5};
        for (int p = 0; p < paths; p++) {
            double y[2];
            dyn_result res;
            gbm_path(DYN_SDE_EM, 1.0, 0.5, o, (uint64_t)p, y, &res);
            sum += y[0];
        }
        err[k] = fabs(sum / paths - exp(1.0));
    }
    const double q = slope(h, err, 4);
    print_message("weak errors %.3g %.3g %.3g %.3g: order %.3f\n", err[0], err[1], err[2],
                  err[3], q);
    assert_true(q > 0.85 && q < 1.15);
}

/* EM's weak order 1 on OU's mean (theta 2, m 0.5, sigma 0.8, X(0) = 2): the scheme's mean
 * at T = 1 is m + (X0 - m)(1 - theta h)^(1/h), exactly; |E X(1) - (m + 1.5 e^-2)| from 1e5
 * paths at h = 0.2 .. 0.025 (errors 0.085 .. 0.010, standard error 0.0013). */
static void test_weak_order_ou(void **state)
{
    (void)state;
    double h[4], err[4];
    const double y0[2] = {2.0, 0.0};
    const int paths = 100000;
    for (int k = 0; k < 4; k++) {
        h[k] = 0.2 / (1 << k);
        double sum = 0.0;
        for (int p = 0; p < paths; p++) {
            ou_par par = {2.0, 0.5, 0.8, 0.0};
            const dyn_sde_opts o = {.h = h[k], .seed = 21, .stream = (uint64_t)p};
            double y[2];
            dyn_result res;
            run(DYN_SDE_EM, ou_rhs, &par, &par.w, DYN_NOISE_ADDITIVE, 1.0, y0, &o, y, &res);
            sum += y[0];
        }
        err[k] = fabs(sum / paths - (0.5 + 1.5 * exp(-2.0)));
    }
    const double q = slope(h, err, 4);
    print_message("OU mean errors %.3g %.3g %.3g %.3g: weak order %.3f\n", err[0], err[1],
                  err[2], err[3], q);
    assert_true(q > 0.8 && q < 1.2);
}

/* Mean and variance of OU at T = 1 (theta 2, m 0.5, sigma 0.8, X0 2) from 20000 paths,
 * each method within 5 standard errors (plus EM's bias of order h). */
static void ou_moments(dyn_sde_method method, int fixed, double h, double *mean, double *var,
                       double *wvar, long *rejected)
{
    const int paths = 20000;
    const double y0[2] = {2.0, 0.0};
    double s = 0, s2 = 0, w2 = 0;
    *rejected = 0;
    for (int p = 0; p < paths; p++) {
        ou_par par = {2.0, 0.5, 0.8, 0.0};
        dyn_sde_opts o = {0};
        o.h = h;
        o.fixed = fixed;
        o.rtol = 1e-3;
        o.atol = 1e-3;
        o.seed = 99;
        o.stream = (uint64_t)p;
        double y[2];
        dyn_result res;
        run(method, ou_rhs, &par, &par.w, DYN_NOISE_ADDITIVE, 1.0, y0, &o, y, &res);
        s += y[0];
        s2 += y[0] * y[0];
        w2 += y[1] * y[1];
        *rejected += res.stats.rejected;
    }
    *mean = s / paths;
    *var = s2 / paths - *mean * *mean;
    *wvar = w2 / paths;
}

static void test_ou_moments(void **state)
{
    (void)state;
    const double mean = 0.5 + 1.5 * exp(-2.0), var = 0.64 * (1 - exp(-4.0)) / 4.0;
    const double se_mean = sqrt(var / 20000), se_var = var * sqrt(2.0 / 20000);
    double m, v, wv;
    long rej;
    ou_moments(DYN_SDE_EM, 1, 1e-3, &m, &v, &wv, &rej);
    print_message("EM h=1e-3: mean %.5f (exact %.5f) var %.5f (exact %.5f)\n", m, mean, v, var);
    assert_true(fabs(m - mean) < 5 * se_mean + 2e-3);
    assert_true(fabs(v - var) < 5 * se_var + 2e-3);
    ou_moments(DYN_SDE_RKMIL, 0, 0.0, &m, &v, &wv, &rej);
    print_message("rkmil adaptive: mean %.5f var %.5f, Var W(1) %.5f, %ld rejected steps\n", m,
                  v, wv, rej);
    assert_true(rej > 20000); /* the path went through many rejections */
    assert_true(fabs(m - mean) < 5 * se_mean + 5e-3);
    assert_true(fabs(v - var) < 5 * se_var + 5e-3);
    /* W(1) ~ N(0, 1) however the steps were rejected: Var 1 within 5 standard errors */
    assert_true(fabs(wv - 1.0) < 5 * sqrt(2.0 / 20000));
}

/* Adaptive rkmil: a tighter tolerance gives a smaller strong error on GBM. */
static void test_rkmil_tolerance(void **state)
{
    (void)state;
    double err[2];
    long steps[2];
    for (int k = 0; k < 2; k++) {
        double sum = 0;
        steps[k] = 0;
        const double tol = k ? 1e-4 : 1e-2;
        const dyn_sde_opts o = {.rtol = tol, .atol = tol, .seed = 3};
        for (int p = 0; p < 200; p++) {
            double y[2];
            dyn_result res;
            gbm_path(DYN_SDE_RKMIL, 1.5, 1.0, o, (uint64_t)p, y, &res);
            sum += fabs(y[0] - exp(1.0 + y[1]));
            steps[k] += res.stats.accepted;
        }
        err[k] = sum / 200;
    }
    print_message("rkmil rtol 1e-2: error %.3g (%ld steps); 1e-4: %.3g (%ld steps)\n", err[0],
                  steps[0], err[1], steps[1]);
    assert_true(err[1] < 0.25 * err[0]);
}

/* The noise is fixed by (seed, run): the same pair gives the same numbers, another run or
 * seed others; uniform numbers lie in [0, 1) with mean 1/2. */
static void test_rng_streams(void **state)
{
    (void)state;
    dyn_rng a, b, c, d;
    dyn_rng_init(&a, 7, 3);
    dyn_rng_init(&b, 7, 3);
    dyn_rng_init(&c, 7, 4);
    dyn_rng_init(&d, 8, 3);
    int same_c = 0, same_d = 0;
    for (int i = 0; i < 100; i++) {
        const double x = dyn_rng_normal(&a);
        assert_true(x == dyn_rng_normal(&b));
        same_c += x == dyn_rng_normal(&c);
        same_d += x == dyn_rng_normal(&d);
    }
    assert_int_equal(same_c, 0);
    assert_int_equal(same_d, 0);
    double s = 0;
    for (int i = 0; i < 100000; i++) {
        const double u = dyn_rng_uniform(&a);
        assert_true(u >= 0.0 && u < 1.0);
        s += u;
    }
    assert_true(fabs(s / 100000 - 0.5) < 5 * sqrt(1.0 / 12 / 100000));
}

/* The translator's reading of the noise (dyn_model.noise_class in the C text). */
static void expect_class(const char *text, int cls)
{
    char *src = NULL;
    dyn_lang_diag d;
    const int rc = dyn_ode_to_c("n.ode", text, strlen(text), &src, &d, NULL, NULL);
    if (rc)
        print_error("%s: %s\n", text, d.message);
    assert_int_equal(rc, 0);
    char want[64];
    snprintf(want, sizeof want, ".noise_class = %d", cls);
    if (!strstr(src, want))
        print_error("%s: no '%s'\n", text, want);
    assert_non_null(strstr(src, want));
    free(src);
}

static void test_noise_class(void **state)
{
    (void)state;
    expect_class("wiener w\npar s=1\nx'=-x+s*w\n", DYN_NOISE_ADDITIVE);
    expect_class("wiener w\nx'=x*w\n", DYN_NOISE_COMMUTATIVE);
    expect_class("wiener w\nx'=-x+w/(1+y^2)\ny'=x+w\n", DYN_NOISE_COMMUTATIVE);
    expect_class("wiener a,b\nx'=x*a\ny'=y*b\n", DYN_NOISE_COMMUTATIVE);
    /* x's noise a has a coefficient of y, which b moves: Lévy areas needed */
    expect_class("wiener a,b\nx'=y*a\ny'=y*b\n", DYN_NOISE_GENERAL);
    expect_class("wiener w\nx'=w*w\n", DYN_NOISE_GENERAL);
    expect_class("wiener w\nx'=sin(w)\n", DYN_NOISE_GENERAL);
    expect_class("x'=-x+normal(0,1)\n", DYN_NOISE_GENERAL);
    expect_class("x'=ran(2)\n", DYN_NOISE_GENERAL);
    expect_class("wiener w\nv=2*w\nx'=-x+v\n", DYN_NOISE_ADDITIVE);
}

/* What cannot take noise is refused at its place. */
static void expect_refused(const char *text, int line, const char *what)
{
    char *src = NULL;
    dyn_lang_diag d;
    const int rc = dyn_ode_to_c("n.ode", text, strlen(text), &src, &d, NULL, NULL);
    free(src);
    if (rc == 0 || !strstr(d.message, what) || d.line != line)
        print_error("%s: rc %d line %d: %s\n", text, rc, d.line, rc ? d.message : "");
    assert_true(rc != 0 && strstr(d.message, what) && d.line == line);
}

static void test_noise_refused(void **state)
{
    (void)state;
    expect_refused("par a=normal(0,1)\nx'=a\n", 1, "'normal' is not a built-in function");
    expect_refused("x'=1\ninit x=ran(1)\n", 2, "random numbers");
    expect_refused("wiener w\npar k=1\n!d=w\nx'=d\n", 3, "cannot depend on the noise");
    expect_refused("x'=normal(1)\n", 1, "normal takes 2 arguments");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rng_streams),
        cmocka_unit_test(test_noise_class),
        cmocka_unit_test(test_noise_refused),
        cmocka_unit_test(test_strong_order_em),
        cmocka_unit_test(test_strong_order_rkmil),
        cmocka_unit_test(test_weak_order_em),
        cmocka_unit_test(test_weak_order_ou),
        cmocka_unit_test(test_ou_moments),
        cmocka_unit_test(test_rkmil_tolerance),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
