/* SPDX-License-Identifier: BSD-3-Clause */
/* Noise (dynkit/sde.h, src/ode/sde.c): the observed strong and weak orders of
 * Euler–Maruyama and the Runge–Kutta Milstein scheme on geometric Brownian motion
 * dX = mu X dt + sigma X dW (exact: X(T) = X0 exp((mu - sigma^2/2) T + sigma W(T)), with
 * W(T) integrated alongside as the state b' = w, so the exact solution comes from the same
 * path), the mean and variance of an Ornstein–Uhlenbeck process dX = theta (m - X) dt +
 * sigma dW (mean m + (X0 - m) e^{-theta T}, variance sigma^2 (1 - e^{-2 theta T}) / (2 theta)),
 * the Brownian path of the adaptive runs (W(T) ~ N(0, T) however many steps were
 * rejected), and the reproducibility of the noise (seed, run). SRIW1 (strong order 1.5):
 * its coefficients against Rößler's order conditions, its strong order on GBM and on OU
 * (whose exact solution needs the stochastic integral of e^{-theta (T - s)}: built from the
 * same path, see ou_reference), fixed and adaptive, its weak order on the mean and the second
 * moment, and the law of the pair (W, int W) after rejected steps. Fixed seeds; the bounds
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
#include "ode/sde_sri.h"

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

/* ---- SRIW1 ---------------------------------------------------------------------------- */

/* The 25 conditions for strong order 1.5 of an SRI method with scalar or diagonal noise
 * (Rößler 2010, section 5), as DifferentialEquations.jl's checkSRIOrder lists them (e the
 * vector of ones, squares taken entry by entry), and the stage times c0 = A0 e, c1 = A1 e. */
static double dotv(const double *a, const double *b, int s)
{
    double v = 0.0;
    for (int i = 0; i < s; i++)
        v += a[i] * b[i];
    return v;
}

static void matvec(const double M[DYN_SRI_STAGES][DYN_SRI_STAGES], const double *x, int s,
                   double *out)
{
    for (int i = 0; i < s; i++)
        out[i] = dotv(M[i], x, s);
}

static void test_sriw1_order_conditions(void **state)
{
    (void)state;
    const dyn_sri_tableau *T = &dyn_sriw1;
    const int s = T->stages;
    double e[DYN_SRI_STAGES], A0e[DYN_SRI_STAGES], A1e[DYN_SRI_STAGES], B0e[DYN_SRI_STAGES],
        B1e[DYN_SRI_STAGES], B1e2[DYN_SRI_STAGES], B0e2[DYN_SRI_STAGES],
        B1B1e[DYN_SRI_STAGES], A1B0e[DYN_SRI_STAGES];
    for (int i = 0; i < s; i++)
        e[i] = 1.0;
    matvec(T->A0, e, s, A0e);
    matvec(T->A1, e, s, A1e);
    matvec(T->B0, e, s, B0e);
    matvec(T->B1, e, s, B1e);
    matvec(T->B1, B1e, s, B1B1e);
    matvec(T->A1, B0e, s, A1B0e);
    for (int i = 0; i < s; i++) {
        B1e2[i] = B1e[i] * B1e[i];
        B0e2[i] = B0e[i] * B0e[i];
        assert_true(fabs(T->c0[i] - A0e[i]) < 1e-15);
        assert_true(fabs(T->c1[i] - A1e[i]) < 1e-15);
    }
    const double *b1 = T->beta1, *b2 = T->beta2, *b3 = T->beta3, *b4 = T->beta4;
    const double got[25] = {
        dotv(T->alpha, e, s), dotv(b1, e, s), dotv(b2, e, s), dotv(b3, e, s), dotv(b4, e, s),
        dotv(b1, B1e, s), dotv(b2, B1e, s), dotv(b3, B1e, s), dotv(b4, B1e, s),
        dotv(T->alpha, A0e, s), dotv(T->alpha, B0e, s), dotv(T->alpha, B0e2, s),
        dotv(b1, A1e, s), dotv(b2, A1e, s), dotv(b3, A1e, s), dotv(b4, A1e, s),
        dotv(b1, B1e2, s), dotv(b2, B1e2, s), dotv(b3, B1e2, s), dotv(b4, B1e2, s),
        dotv(b1, B1B1e, s), dotv(b2, B1B1e, s), dotv(b3, B1B1e, s), dotv(b4, B1B1e, s),
        0.5 * dotv(b1, A1B0e, s) + dotv(b3, A1B0e, s) / 3.0};
    const double want[25] = {1, 1, 0, 0, 0, 0, 1, 0, 0, 0.5, 1, 1.5, 1,
                             0, -1, 0, 1, 0, -1, 2, 0, 0, 0, 1, 0};
    for (int k = 0; k < 25; k++) {
        if (fabs(got[k] - want[k]) > 1e-14)
            print_error("condition %d: %.17g, not %g\n", k + 1, got[k], want[k]);
        assert_true(fabs(got[k] - want[k]) < 1e-14);
    }
}

/* The states of a path: X, W (b' = w) and its time integral (c' = b), both integrated exactly
 * by SRIW1 (b gains dW, c gains h W + I_(1,0)), so every step's dW and I_(1,0) can be read
 * from the samples. */
typedef struct path_rec {
    int n;
    double t[4096], y[4096][3];
} path_rec;

static int record(long k, double t, const double *y, void *ctx)
{
    (void)k;
    path_rec *p = ctx;
    if (p->n < 4096) {
        p->t[p->n] = t;
        memcpy(p->y[p->n], y, sizeof p->y[0]);
        p->n++;
    }
    return 0;
}

static int gbm3_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    const gbm_par *p = par;
    dydt[0] = p->mu * y[0] + p->sigma * y[0] * p->w;
    dydt[1] = p->w;
    dydt[2] = y[1];
    return 0;
}

static int ou3_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    const ou_par *p = par;
    dydt[0] = p->theta * (p->m - y[0]) + p->sigma * p->w;
    dydt[1] = p->w;
    dydt[2] = y[1];
    return 0;
}

/* The exact OU solution at the end of a recorded path: over each step of length h,
 * X+ = m + (X - m) e^{-theta h} + sigma J with J = int_0^h e^{-theta (h - s)} dW(s), a Gaussian
 * jointly with the step's dW and I = int_0^h (h - s) dW(s) (kernels 1, h - s, e^{-theta (h - s)};
 * covariances their integrals). J is its conditional mean given (dW, I), plus its conditional
 * spread (variance O(h^5)) drawn from an independent stream: an exact sample of X(T) given
 * every dW and I the solver used. */
static double ou_reference(const path_rec *p, double theta, double m, double sigma,
                           dyn_rng *extra)
{
    double x = p->y[0][0];
    for (int k = 0; k + 1 < p->n; k++) {
        const double h = p->t[k + 1] - p->t[k], th = theta * h;
        const double dW = p->y[k + 1][1] - p->y[k][1];
        const double I = p->y[k + 1][2] - p->y[k][2] - h * p->y[k][1];
        const double c1 = -expm1(-th) / theta;
        const double c2 = (-expm1(-th) - th * exp(-th)) / (theta * theta);
        const double v = -expm1(-2.0 * th) / (2.0 * theta);
        /* C = [[h, h^2/2], [h^2/2, h^3/3]], C^-1 = [[4/h, -6/h^2], [-6/h^2, 12/h^3]] */
        const double k1 = 4.0 / h * c1 - 6.0 / (h * h) * c2;
        const double k2 = -6.0 / (h * h) * c1 + 12.0 / (h * h * h) * c2;
        const double var = fmax(0.0, v - (k1 * c1 + k2 * c2));
        const double J = k1 * dW + k2 * I + sqrt(var) * dyn_rng_normal(extra);
        x = m + (x - m) * exp(-th) + sigma * J;
    }
    return x;
}

static void sri_run(dyn_rhs_fn f, void *par, double *noise, dyn_noise_class cls,
                    const double *y0, dyn_sde_opts o, path_rec *rec, dyn_result *res)
{
    static double work[8192];
    assert_true(dyn_sde_work_size(3, 1, 0) <= 8192);
    dyn_sde sde = {{f, 3, par}, 1, wiener_kind, noise, cls};
    rec->n = 0;
    o.output = record;
    o.output_ctx = rec;
    double y[3];
    assert_int_equal(dyn_sde_solve(DYN_SDE_SRIW1, &sde, 0.0, 1.0, y0, y, work, &o, res),
                     DYN_OK);
}

/* Mean strong errors at T = 1 of SRIW1 on GBM (mu 1.5, sigma 1; exact exp(1 + W(1))) and on
 * OU (theta 2, m 0.5, sigma 0.8, X0 2; ou_reference) over paths, at options o with the
 * stream = the path's index; the mean accepted steps per path into *steps. */
static void sri_errors(dyn_sde_opts o, int paths, double *err_gbm, double *err_ou,
                       double *steps, double *calls)
{
    static path_rec rec;
    double sg = 0, so = 0, ns = 0, nc = 0;
    for (int p = 0; p < paths; p++) {
        dyn_result res;
        o.stream = (uint64_t)p;
        gbm_par g = {1.5, 1.0, 0.0};
        const double yg[3] = {1.0, 0.0, 0.0};
        sri_run(gbm3_rhs, &g, &g.w, DYN_NOISE_COMMUTATIVE, yg, o, &rec, &res);
        const double *yl = rec.y[rec.n - 1];
        sg += fabs(yl[0] - exp(1.0 + yl[1]));
        ns += (double)res.stats.accepted;
        nc += (double)res.stats.rhs_calls;
        ou_par u = {2.0, 0.5, 0.8, 0.0};
        const double yo[3] = {2.0, 0.0, 0.0};
        sri_run(ou3_rhs, &u, &u.w, DYN_NOISE_ADDITIVE, yo, o, &rec, &res);
        dyn_rng extra;
        dyn_rng_init(&extra, 1000 + o.seed, (uint64_t)p);
        so += fabs(rec.y[rec.n - 1][0] - ou_reference(&rec, 2.0, 0.5, 0.8, &extra));
    }
    *err_gbm = sg / paths;
    *err_ou = so / paths;
    if (steps)
        *steps = ns / paths;
    if (calls)
        *calls = nc / paths;
}

/* Fixed steps 2^-5 .. 2^-9: observed strong order 1.5 on GBM; on OU (additive noise, where the
 * terms of the order-1.5 remainder with derivatives of b vanish) above it. */
static void test_strong_order_sriw1(void **state)
{
    (void)state;
    double h[5], eg[5], eo[5];
    for (int k = 0; k < 5; k++) {
        h[k] = ldexp(1.0, -(k + 5));
        const dyn_sde_opts o = {.h = h[k], .fixed = 1, .seed = 11};
        sri_errors(o, 1000, &eg[k], &eo[k], NULL, NULL);
    }
    const double qg = slope(h, eg, 5), qo = slope(h, eo, 5);
    print_message("sriw1 GBM strong errors %.3g %.3g %.3g %.3g %.3g: order %.3f\n", eg[0],
                  eg[1], eg[2], eg[3], eg[4], qg);
    print_message("sriw1 OU strong errors %.3g %.3g %.3g %.3g %.3g: order %.3f\n", eo[0], eo[1],
                  eo[2], eo[3], eo[4], qo);
    assert_true(qg > 1.35 && qg < 1.65);
    assert_true(qo > 1.35 && qo < 2.3);
}

/* Weak order 2 on GBM (mu 1, sigma 0.5, X0 1): E X(1) = e and E X(1)^2 = e^{2 + 1/4}, the
 * errors of the mean and the second moment at h = 1/4 .. 1/32 estimated as the mean of
 * X_h - X and X_h^2 - X^2 with X = exp(0.875 + 0.5 W(1)) the exact solution on the same path
 * (a control variate of known mean: the estimate's spread is the strong error's, not the
 * solution's). */
static void test_weak_order_sriw1(void **state)
{
    (void)state;
    double h[4], e1[4], e2[4];
    const int paths = 40000;
    for (int k = 0; k < 4; k++) {
        h[k] = ldexp(1.0, -(k + 2));
        double s1 = 0, s2 = 0, q1 = 0, q2 = 0;
        const dyn_sde_opts o = {.h = h[k], .fixed = 1, .seed = 8};
        for (int p = 0; p < paths; p++) {
            double y[2];
            dyn_result res;
            gbm_path(DYN_SDE_SRIW1, 1.0, 0.5, o, (uint64_t)p, y, &res);
            const double x = exp(0.875 + 0.5 * y[1]);
            const double d1 = y[0] - x, d2 = y[0] * y[0] - x * x;
            s1 += d1;
            s2 += d2;
            q1 += d1 * d1;
            q2 += d2 * d2;
        }
        e1[k] = fabs(s1 / paths);
        e2[k] = fabs(s2 / paths);
        print_message("sriw1 h %g: mean error %.3g (se %.2g), second moment %.3g (se %.2g)\n",
                      h[k], e1[k], sqrt((q1 / paths - e1[k] * e1[k]) / paths), e2[k],
                      sqrt((q2 / paths - e2[k] * e2[k]) / paths));
    }
    const double q1 = slope(h, e1, 4), q2 = slope(h, e2, 4);
    print_message("sriw1 weak order %.3f (mean), %.3f (second moment)\n", q1, q2);
    assert_true(q1 > 1.7 && q1 < 2.4);
    assert_true(q2 > 1.7 && q2 < 2.4);
}

/* Work against precision on GBM (mu 1.5, sigma 1, 400 paths, seed 11): the mean strong error
 * at T = 1 and the mean right-hand-side calls per path, for SRIW1 (adaptive and fixed), rkmil
 * (adaptive and fixed) and Euler-Maruyama; at about 2000 calls SRIW1's error is far below the
 * others'. */
static void wp_point(dyn_sde_method method, int fixed, double v, double *err, double *calls)
{
    double se = 0, sc = 0;
    for (int p = 0; p < 400; p++) {
        dyn_sde_opts o = {.seed = 11, .fixed = fixed};
        if (fixed)
            o.h = v;
        else
            o.rtol = o.atol = v;
        double y[2];
        dyn_result res;
        gbm_path(method, 1.5, 1.0, o, (uint64_t)p, y, &res);
        se += fabs(y[0] - exp(1.0 + y[1]));
        sc += (double)res.stats.rhs_calls;
    }
    *err = se / 400;
    *calls = sc / 400;
}

static void test_work_precision(void **state)
{
    (void)state;
    static const struct {
        const char *name;
        dyn_sde_method method;
        int fixed;
        double v[5];
    } rows[] = {
        {"sriw1 rtol=atol", DYN_SDE_SRIW1, 0, {1e-1, 1e-2, 1e-3, 1e-4, 1e-5}},
        {"sriw1 h", DYN_SDE_SRIW1, 1, {0x1p-3, 0x1p-5, 0x1p-7, 0x1p-9, 0x1p-11}},
        {"rkmil rtol=atol", DYN_SDE_RKMIL, 0, {1e-1, 1e-2, 1e-3, 1e-4, 1e-5}},
        {"rkmil h", DYN_SDE_RKMIL, 1, {0x1p-3, 0x1p-5, 0x1p-7, 0x1p-9, 0x1p-11}},
        {"euler h", DYN_SDE_EM, 1, {0x1p-5, 0x1p-7, 0x1p-9, 0x1p-11, 0x1p-13}},
    };
    double at2k[5] = {0};
    for (size_t r = 0; r < sizeof rows / sizeof rows[0]; r++) {
        char line[512];
        int used = snprintf(line, sizeof line, "%-16s", rows[r].name);
        for (int k = 0; k < 5; k++) {
            double e, c;
            wp_point(rows[r].method, rows[r].fixed, rows[r].v[k], &e, &c);
            used += snprintf(line + used, sizeof line - (size_t)used, " | %g: %.3g in %.0f",
                             rows[r].v[k], e, c);
            if (c > 1000 && c < 3000)
                at2k[r] = e;
        }
        print_message("%s\n", line);
    }
    /* about 2000 calls: sriw1 tol 1e-3 (2567) and h 2^-7 (1152), rkmil h 2^-9 (2048), euler
     * h 2^-11 (2048) */
    assert_true(at2k[0] > 0 && at2k[3] > 0 && at2k[4] > 0);
    assert_true(at2k[0] < 0.2 * at2k[3]);
    assert_true(at2k[0] < 0.05 * at2k[4]);
}

/* The path of adaptive SRIW1 runs through many rejected steps is still Brownian motion with
 * its time integral U = int W: at t = 0.5 and 1, Var W = t, Var U = t^3/3, Cov(W, U) = t^2/2
 * (over 20000 paths, within 5 standard errors), and OU's mean and variance at 1 agree with the
 * closed form. */
static void test_sriw1_path_law(void **state)
{
    (void)state;
    static path_rec rec;
    const int paths = 20000;
    double sw[2] = {0}, su[2] = {0}, swu[2] = {0}, sx = 0, sxx = 0;
    long rejected = 0;
    for (int p = 0; p < paths; p++) {
        ou_par u = {2.0, 0.5, 0.8, 0.0};
        const double y0[3] = {2.0, 0.0, 0.0};
        const dyn_sde_opts o = {.rtol = 1e-3, .atol = 1e-3, .seed = 99, .out_step = 0.5};
        dyn_result res;
        dyn_sde_opts oo = o;
        oo.stream = (uint64_t)p;
        sri_run(ou3_rhs, &u, &u.w, DYN_NOISE_ADDITIVE, y0, oo, &rec, &res);
        assert_int_equal(rec.n, 3);
        for (int k = 0; k < 2; k++) {
            const double w = rec.y[k + 1][1], U = rec.y[k + 1][2];
            sw[k] += w * w;
            su[k] += U * U;
            swu[k] += w * U;
        }
        sx += rec.y[2][0];
        sxx += rec.y[2][0] * rec.y[2][0];
        rejected += res.stats.rejected;
    }
    for (int k = 0; k < 2; k++) {
        const double t = 0.5 * (k + 1);
        const double vw = sw[k] / paths, vu = su[k] / paths, c = swu[k] / paths;
        print_message("t = %g: Var W %.4f (%.4f), Var U %.4f (%.4f), Cov %.4f (%.4f)\n", t, vw,
                      t, vu, t * t * t / 3, c, t * t / 2);
        assert_true(fabs(vw - t) < 5 * t * sqrt(2.0 / paths));
        assert_true(fabs(vu - t * t * t / 3) < 5 * t * t * t / 3 * sqrt(2.0 / paths));
        /* Var(W U) = Var W Var U + Cov^2 for a centred Gaussian pair */
        assert_true(fabs(c - t * t / 2) <
                    5 * sqrt((t * t * t * t / 3 + t * t * t * t / 4) / paths));
    }
    const double mean = 0.5 + 1.5 * exp(-2.0), var = 0.64 * (1 - exp(-4.0)) / 4.0;
    const double m = sx / paths, v = sxx / paths - m * m;
    print_message("sriw1 adaptive OU: mean %.5f (%.5f) var %.5f (%.5f), %ld rejected steps\n",
                  m, mean, v, var, rejected);
    assert_true(rejected > 20000);
    assert_true(fabs(m - mean) < 5 * sqrt(var / paths));
    assert_true(fabs(v - var) < 5 * var * sqrt(2.0 / paths));
}

/* Adaptive steps at tolerances 1e-1 .. 1e-4: the strong error against the mean step 1/steps
 * falls with order about 1.5 as well. */
static void test_strong_order_sriw1_adaptive(void **state)
{
    (void)state;
    double hg[4], eg[4], eo[4], calls[4];
    for (int k = 0; k < 4; k++) {
        const double tol = pow(10.0, -(k + 1));
        const dyn_sde_opts o = {.rtol = tol, .atol = tol, .seed = 5};
        double steps;
        sri_errors(o, 1000, &eg[k], &eo[k], &steps, &calls[k]);
        hg[k] = 1.0 / steps;
        print_message("sriw1 tol %g: %.1f steps, %.1f calls, GBM error %.3g, OU error %.3g\n",
                      tol, steps, calls[k], eg[k], eo[k]);
    }
    const double qg = slope(hg, eg, 4), qo = slope(hg, eo, 4);
    print_message("sriw1 adaptive: order %.3f (GBM), %.3f (OU) against the mean step\n", qg, qo);
    assert_true(eg[3] < 0.05 * eg[0]);
    assert_true(qg > 1.1 && qg < 2.0);
    assert_true(qo > 1.1 && qo < 2.0);
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
        cmocka_unit_test(test_sriw1_order_conditions),
        cmocka_unit_test(test_strong_order_sriw1),
        cmocka_unit_test(test_strong_order_sriw1_adaptive),
        cmocka_unit_test(test_weak_order_sriw1),
        cmocka_unit_test(test_sriw1_path_law),
        cmocka_unit_test(test_work_precision),
        cmocka_unit_test(test_weak_order_em),
        cmocka_unit_test(test_weak_order_ou),
        cmocka_unit_test(test_ou_moments),
        cmocka_unit_test(test_rkmil_tolerance),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
