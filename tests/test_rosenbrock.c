/* SPDX-License-Identifier: BSD-3-Clause */
/* test_rosenbrock.c — the Rosenbrock step (src/ode/rosenbrock.h) and RODAS's coefficients:
 * - the coefficients satisfy the order conditions of Hairer & Wanner II, Table IV.7.1 to
 *   order 4 (the embedded solution to order 3 and not 4), and the stage times and df/dt
 *   coefficients agree with the matrices they come with;
 * - observed order 4 with fixed steps on a stiff linear system, a forced (non-autonomous)
 *   linear system and Kaps's nonlinear stiff problem (exact solutions known), with the
 *   analytic and with the difference Jacobian;
 * - the local error estimate behaves like h^4 and the true local error like h^5; the dense
 *   output has local error h^4 (order 3) and meets y0 and y1 exactly;
 * - L-stability: the stability function tends to 0 like -8.84/z and stays <= 1 on the
 *   imaginary axis; y' = -1e6 (y - cos t) stays accurate with h = 0.1 (h lambda = -1e5),
 *   and an initial layer of size 1 is damped to 9e-5 in one step;
 * - counters, reuse of the factorisation, singular matrices and failing right-hand sides;
 * - the simple adaptive loop meets its tolerance;
 * - through the general driver (dyn_solve, method "rodas4"): van der Pol mu = 1000 and
 *   Robertson to 1e11 against their references, with the analytic and the difference
 *   Jacobian; the dense output at requested times; events; f is never evaluated past t1;
 *   the integer workspace is required. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <float.h>

#include "dynkit/models.h"
#include "dynkit/problems.h"
#include "dynkit/solve.h"
#include "ode/linalg.h"
#include "ode/rosenbrock.h"
#include "test_util.h"

#define NMAX 4

static const dyn_ros_method *M = &dyn_ros_rodas4;

/* ---- order conditions ---------------------------------------------------------------
 * From the transformed form: Gamma^{-1} = I/gamma - C, alpha_ij = (A Gamma)_ij,
 * b = m Gamma, gamma_i = row sums of Gamma, beta_ij = alpha_ij + gamma_ij (j < i). */
typedef struct orig_coef {
    int s;
    double gamma;
    double alpha[6][6], G[6][6], beta[6][6], b[6], bhat[6];
} orig_coef;

static void original_coefficients(const dyn_ros_method *m, orig_coef *o)
{
    const int s = m->stages;
    memset(o, 0, sizeof *o);
    o->s = s;
    o->gamma = m->gamma;
    double Ginv[36], G[36];
    for (int i = 0; i < s; i++)
        for (int j = 0; j < s; j++)
            Ginv[i * s + j] = (i == j ? 1.0 / m->gamma : 0.0) - (j < i ? m->c[i * s + j] : 0.0);
    /* invert the lower triangular Gamma^{-1} column by column */
    for (int j = 0; j < s; j++) {
        double col[6] = {0};
        col[j] = 1.0;
        for (int i = 0; i < s; i++) {
            double v = col[i];
            for (int k = 0; k < i; k++)
                v -= Ginv[i * s + k] * G[k * s + j];
            G[i * s + j] = (i < j) ? 0.0 : v / Ginv[i * s + i];
        }
    }
    for (int i = 0; i < s; i++)
        for (int j = 0; j < s; j++) {
            o->G[i][j] = G[i * s + j];
            double a = 0.0;
            for (int k = 0; k < s; k++)
                a += m->a[i * s + k] * G[k * s + j];
            o->alpha[i][j] = a;
        }
    for (int j = 0; j < s; j++) {
        double b = 0.0, bh = 0.0;
        for (int i = 0; i < s; i++) {
            b += m->m[i] * G[i * s + j];
            bh += (m->m[i] - m->e[i]) * G[i * s + j];
        }
        o->b[j] = b;
        o->bhat[j] = bh;
    }
    for (int i = 0; i < s; i++)
        for (int j = 0; j < i; j++)
            o->beta[i][j] = o->alpha[i][j] + o->G[i][j];
}

/* Residuals of the conditions of order 1..4 (HNW II, Table IV.7.1) for weights w. */
static void order_residuals(const orig_coef *o, const double *w, double res[9])
{
    const int s = o->s;
    const double g = o->gamma;
    double al[6] = {0}, bp[6] = {0}, bb[6] = {0}, ba2[6] = {0}, aabp[6] = {0};
    for (int i = 0; i < s; i++)
        for (int j = 0; j < i; j++) {
            al[i] += o->alpha[i][j];
            bp[i] += o->beta[i][j];
        }
    for (int i = 0; i < s; i++)
        for (int j = 0; j < i; j++) {
            bb[i] += o->beta[i][j] * bp[j];         /* sum_k beta_ik beta_k' */
            ba2[i] += o->beta[i][j] * al[j] * al[j]; /* sum_k beta_ik alpha_k^2 */
            aabp[i] += o->alpha[i][j] * bp[j];       /* sum_k alpha_ik beta_k' */
        }
    double bbb[6] = {0};
    for (int i = 0; i < s; i++)
        for (int j = 0; j < i; j++)
            bbb[i] += o->beta[i][j] * bb[j];
    double r[9] = {0};
    for (int i = 0; i < s; i++) {
        r[0] += w[i];
        r[1] += w[i] * bp[i];
        r[2] += w[i] * al[i] * al[i];
        r[3] += w[i] * bb[i];
        r[4] += w[i] * al[i] * al[i] * al[i];
        r[5] += w[i] * al[i] * aabp[i];
        r[6] += w[i] * ba2[i];
        r[7] += w[i] * bbb[i];
    }
    res[0] = r[0] - 1.0;
    res[1] = r[1] - (0.5 - g);
    res[2] = r[2] - 1.0 / 3.0;
    res[3] = r[3] - (1.0 / 6.0 - g + g * g);
    res[4] = r[4] - 0.25;
    res[5] = r[5] - (1.0 / 8.0 - g / 3.0);
    res[6] = r[6] - (1.0 / 12.0 - g / 3.0);
    res[7] = r[7] - (1.0 / 24.0 - g / 2.0 + 1.5 * g * g - g * g * g);
}

static void test_order_conditions(void **state)
{
    (void)state;
    orig_coef o;
    original_coefficients(M, &o);
    double res[9];
    order_residuals(&o, o.b, res);
    for (int k = 0; k < 8; k++)
        CHECK(fabs(res[k]) < 1e-12, "rodas4: condition %d residual %.3g", k + 1, res[k]);
    order_residuals(&o, o.bhat, res);
    for (int k = 0; k < 4; k++)
        CHECK(fabs(res[k]) < 1e-12, "embedded: condition %d residual %.3g", k + 1, res[k]);
    double worst4 = 0.0;
    for (int k = 4; k < 8; k++)
        worst4 = fmax(worst4, fabs(res[k]));
    CHECK(worst4 > 1e-3, "embedded solution is of order 4? residual %.3g", worst4);
    /* stage times are the row sums of alpha, df/dt coefficients the row sums of Gamma */
    for (int i = 0; i < o.s; i++) {
        double al = 0.0, gi = 0.0;
        for (int j = 0; j < o.s; j++) {
            al += o.alpha[i][j];
            gi += o.G[i][j];
        }
        CHECK(fabs(al - M->alpha[i]) < 1e-12, "alpha_%d = %.17g, row sum %.17g", i, M->alpha[i],
              al);
        CHECK(fabs(gi - M->gam[i]) < 1e-12, "gamma_%d = %.17g, row sum %.17g", i, M->gam[i], gi);
    }
    /* stiffly accurate: b is the last row of beta plus gamma (y1 is the last stage value) */
    for (int j = 0; j < o.s; j++) {
        double last = (j < o.s - 1 ? o.beta[o.s - 1][j] : 0.0) + (j == o.s - 1 ? o.gamma : 0.0);
        CHECK(fabs(o.b[j] - last) < 1e-12, "b_%d = %.17g, last row %.17g", j, o.b[j], last);
    }
}

/* ---- test problems with exact solutions ---------------------------------------------- */

/* Linear y' = A (y - phi(t)) + phi'(t) with A = V diag(lam) V^{-1}, exact
 * y = phi(t) + V exp(lam t) V^{-1} (y0 - phi(0)). forced = 0: phi = 0 (autonomous). */
typedef struct lin_prob {
    double A[9], V[9], Vinv[9], lam[3];
    int forced;
} lin_prob;

static void phi(const lin_prob *lp, double t, double *p, double *dp)
{
    if (!lp->forced) {
        p[0] = p[1] = p[2] = 0.0;
        dp[0] = dp[1] = dp[2] = 0.0;
        return;
    }
    p[0] = sin(t);
    p[1] = cos(2.0 * t);
    p[2] = exp(-t) + t;
    dp[0] = cos(t);
    dp[1] = -2.0 * sin(2.0 * t);
    dp[2] = -exp(-t) + 1.0;
}

static int lin_f(double t, const double *y, double *f, void *par)
{
    const lin_prob *lp = par;
    double p[3], dp[3], d[3];
    phi(lp, t, p, dp);
    for (int i = 0; i < 3; i++)
        d[i] = y[i] - p[i];
    dyn_mat_vec(3, lp->A, d, f);
    for (int i = 0; i < 3; i++)
        f[i] += dp[i];
    return 0;
}

static int lin_jac(double t, const double *y, double *J, void *par)
{
    (void)t;
    (void)y;
    memcpy(J, ((const lin_prob *)par)->A, 9 * sizeof *J);
    return 0;
}

static void lin_init(lin_prob *lp, double l0, double l1, double l2, int forced)
{
    const double V[9] = {1.0, 0.5, -0.25, 0.25, 1.0, 0.5, -0.5, 0.25, 1.0};
    memcpy(lp->V, V, sizeof V);
    lp->lam[0] = l0;
    lp->lam[1] = l1;
    lp->lam[2] = l2;
    lp->forced = forced;
    double LU[9];
    int piv[3];
    memcpy(LU, V, sizeof V);
    assert_int_equal(dyn_lu_factor(3, LU, piv), 0);
    for (int j = 0; j < 3; j++) {
        double e[3] = {0};
        e[j] = 1.0;
        dyn_lu_solve(3, LU, piv, e);
        for (int i = 0; i < 3; i++)
            lp->Vinv[i * 3 + j] = e[i];
    }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double s = 0.0;
            for (int k = 0; k < 3; k++)
                s += V[i * 3 + k] * lp->lam[k] * lp->Vinv[k * 3 + j];
            lp->A[i * 3 + j] = s;
        }
}

static void lin_exact(const lin_prob *lp, const double *y0, double t, double *y)
{
    double p0[3], dp[3], d[3], w[3];
    phi(lp, 0.0, p0, dp);
    for (int i = 0; i < 3; i++)
        d[i] = y0[i] - p0[i];
    dyn_mat_vec(3, lp->Vinv, d, w);
    for (int i = 0; i < 3; i++)
        w[i] *= exp(lp->lam[i] * t);
    dyn_mat_vec(3, lp->V, w, y);
    double p[3];
    phi(lp, t, p, dp);
    for (int i = 0; i < 3; i++)
        y[i] += p[i];
}

/* Kaps's problem (HNW II, sec. IV.7): y1' = -(1/eps + 2) y1 + y2^2 / eps,
 * y2' = y1 - y2 - y2^2; exact y1 = exp(-2t), y2 = exp(-t) for every eps. */
static int kaps_f(double t, const double *y, double *f, void *par)
{
    const double eps = *(const double *)par;
    (void)t;
    f[0] = -(1.0 / eps + 2.0) * y[0] + y[1] * y[1] / eps;
    f[1] = y[0] - y[1] - y[1] * y[1];
    return 0;
}

static int kaps_jac(double t, const double *y, double *J, void *par)
{
    const double eps = *(const double *)par;
    (void)t;
    J[0] = -(1.0 / eps + 2.0);
    J[1] = 2.0 * y[1] / eps;
    J[2] = 1.0;
    J[3] = -1.0 - 2.0 * y[1];
    return 0;
}

/* Fixed steps: n_steps steps of (t1 - t0) / n_steps from (t0, y). */
static int ros_fixed(const dyn_ros_problem *p, double t0, double t1, long n_steps, double *y,
                     dyn_ros_stats *st)
{
    const int n = p->sys.n;
    double work[2 * NMAX * NMAX + 12 * NMAX], y1[NMAX];
    int piv[NMAX];
    dyn_ros_ws ws;
    assert_true(dyn_ros_work_size(M, n) <= sizeof work / sizeof work[0]);
    dyn_ros_ws_init(&ws, M, n, work, piv);
    const double h = (t1 - t0) / (double)n_steps;
    for (long k = 0; k < n_steps; k++) {
        const double t = t0 + (double)k * h;
        int rc = dyn_ros_linearize(p, t, h, y, &ws, st);
        if (!rc)
            rc = dyn_ros_step(M, p, t, h, y, &ws, y1, NULL, NULL, st);
        if (rc)
            return rc;
        memcpy(y, y1, (size_t)n * sizeof *y);
    }
    return 0;
}

/* Errors at t1 for 10, 20, 40, 80, 160 steps; checks the observed orders. */
static void check_order(const char *what, const dyn_ros_problem *p, const double *y0,
                        const double *yex, double t1, int levels, double lo, double hi)
{
    const int n = p->sys.n;
    double err[8];
    for (int l = 0; l < levels; l++) {
        double y[NMAX];
        dyn_ros_stats st = {0};
        memcpy(y, y0, (size_t)n * sizeof *y);
        assert_int_equal(ros_fixed(p, 0.0, t1, 10L << l, y, &st), 0);
        err[l] = max_abs_diff(y, yex, n);
    }
    for (int l = 1; l < levels; l++) {
        double order = log2(err[l - 1] / err[l]);
        CHECK(order > lo && order < hi, "%s: observed order %.3f between %ld and %ld steps "
              "(errors %.3g, %.3g)", what, order, 10L << (l - 1), 10L << l, err[l - 1], err[l]);
    }
}

static void test_order_linear_stiff(void **state)
{
    (void)state;
    lin_prob lp;
    lin_init(&lp, -1.0, -2.5, -1e3, 0);
    dyn_ros_problem p = {{lin_f, 3, &lp}, lin_jac, 1, NULL, 0, NULL, NULL, NULL, NULL, NULL, 0};
    const double y0[3] = {1.0, -0.5, 2.0};
    double yex[3];
    lin_exact(&lp, y0, 2.0, yex);
    check_order("linear stiff (-1, -2.5, -1e3)", &p, y0, yex, 2.0, 5, 3.8, 4.4);
    /* forced, non-autonomous: exercises the df/dt terms (a difference df/dt). Non-stiff
     * eigenvalues: with a stiff one this is the Prothero-Robinson problem, on which
     * Rosenbrock methods show their stage order (1) until h |lambda| is small, a known
     * order reduction (HNW II, sec. IV.15) — its accuracy is checked in test_l_stability */
    lin_init(&lp, -1.0, -2.5, -4.0, 1);
    p.autonomous = 0;
    lin_exact(&lp, y0, 2.0, yex);
    check_order("linear forced (df/dt)", &p, y0, yex, 2.0, 4, 3.8, 4.4);
}

/* Kaps's problem in the non-stiff case and in the stiff limit (eps = 1e-9). In between
 * (eps = 1e-3 .. 1e-6 with these steps) the stiff component has the eps-dependent error
 * terms of Rosenbrock methods on singular perturbation problems (HNW II, sec. VI.3) and the
 * observed order drops (to 1 for eps = 1e-6 and h > 1e-2), so those are not order tests. */
static void test_order_nonlinear_kaps(void **state)
{
    (void)state;
    const double y0[2] = {1.0, 1.0}, t1 = 1.0;
    const double yex[2] = {exp(-2.0 * t1), exp(-t1)};
    double eps = 1.0;
    dyn_ros_problem p = {{kaps_f, 2, &eps}, kaps_jac, 1, NULL, 0, NULL, NULL, NULL, NULL, NULL, 0};
    check_order("Kaps eps = 1", &p, y0, yex, t1, 5, 3.9, 4.2);
    eps = 1e-9;
    check_order("Kaps eps = 1e-9", &p, y0, yex, t1, 4, 3.9, 4.4);
    /* difference Jacobian: same orders where its sqrt(eps) error is below the method's */
    p.jac = NULL;
    eps = 1.0;
    check_order("Kaps eps = 1, difference Jacobian", &p, y0, yex, t1, 4, 3.8, 4.3);
}

/* One step from the exact solution of Kaps (eps = 1): the estimate ~ h^4, the true local
 * error ~ h^5, the dense output's error over the step ~ h^4. */
static void test_local_error_and_dense_output(void **state)
{
    (void)state;
    double eps = 1.0;
    dyn_ros_problem p = {{kaps_f, 2, &eps}, kaps_jac, 1, NULL, 0, NULL, NULL, NULL, NULL, NULL, 0};
    double work[64], y1[2], err[2], cont[8], yd[2];
    int piv[2];
    dyn_ros_ws ws;
    dyn_ros_ws_init(&ws, M, 2, work, piv);
    const double t0 = 0.3, y0[2] = {exp(-2 * t0), exp(-t0)};
    double e_est[6], e_loc[6], e_dense[6];
    for (int l = 0; l < 6; l++) {
        const double h = 0.2 / (double)(1 << l);
        dyn_ros_stats st = {0};
        assert_int_equal(dyn_ros_linearize(&p, t0, h, y0, &ws, &st), 0);
        assert_int_equal(dyn_ros_step(M, &p, t0, h, y0, &ws, y1, err, cont, &st), 0);
        const double ex[2] = {exp(-2 * (t0 + h)), exp(-(t0 + h))};
        e_est[l] = fmax(fabs(err[0]), fabs(err[1]));
        e_loc[l] = max_abs_diff(y1, ex, 2);
        e_dense[l] = 0.0;
        for (int k = 0; k <= 20; k++) {
            const double th = k / 20.0, tt = t0 + th * h;
            const double exd[2] = {exp(-2 * tt), exp(-tt)};
            dyn_ros_dense(M, 2, cont, th, yd);
            e_dense[l] = fmax(e_dense[l], max_abs_diff(yd, exd, 2));
        }
        dyn_ros_dense(M, 2, cont, 0.0, yd);
        assert_true(same_bits(yd[0], y0[0]) && same_bits(yd[1], y0[1]));
        dyn_ros_dense(M, 2, cont, 1.0, yd);
        assert_true(same_bits(yd[0], y1[0]) && same_bits(yd[1], y1[1]));
    }
    for (int l = 2; l < 6; l++) { /* skip the largest steps: asymptotics */
        const double o_est = log2(e_est[l - 1] / e_est[l]);
        const double o_loc = log2(e_loc[l - 1] / e_loc[l]);
        const double o_den = log2(e_dense[l - 1] / e_dense[l]);
        CHECK(o_est > 3.7 && o_est < 4.4, "estimate ~ h^%.2f (want 4)", o_est);
        CHECK(o_loc > 4.6 && o_loc < 5.5, "local error ~ h^%.2f (want 5)", o_loc);
        CHECK(o_den > 3.7 && o_den < 4.5, "dense output error ~ h^%.2f (want 4)", o_den);
        /* the estimate is an upper bound of the local error of the order-4 result */
        assert_true(e_est[l] > e_loc[l]);
    }
}

/* y' = -lambda (y - cos t), lambda = 1e6: exact
 * y = (lambda^2 cos t + lambda sin t)/(lambda^2 + 1) + C exp(-lambda t). */
static int pr_f(double t, const double *y, double *f, void *par)
{
    (void)par;
    f[0] = -1e6 * (y[0] - cos(t));
    return 0;
}

static int pr_jac(double t, const double *y, double *J, void *par)
{
    (void)t;
    (void)y;
    (void)par;
    J[0] = -1e6;
    return 0;
}

static double pr_exact(double t, double y0)
{
    const double L = 1e6;
    const double smooth = (L * L * cos(t) + L * sin(t)) / (L * L + 1.0);
    const double c = y0 - L * L / (L * L + 1.0);
    return smooth + c * exp(-L * t);
}

/* y' = A y with A = [[x, -w], [w, x]] (eigenvalues x +- iw): one step of size 1 from (1, 0)
 * gives (Re R(z), Im R(z)) for z = x + iw, R the stability function. */
static int rot_f(double t, const double *y, double *f, void *par)
{
    const double *l = par;
    (void)t;
    f[0] = l[0] * y[0] - l[1] * y[1];
    f[1] = l[1] * y[0] + l[0] * y[1];
    return 0;
}

static double stability_function(double x, double w, double *re)
{
    double l[2] = {x, w}, work[64], y[2] = {1.0, 0.0}, y1[2];
    int piv[2];
    dyn_ros_problem p = {{rot_f, 2, l}, NULL, 1, NULL, 0, NULL, NULL, NULL, NULL, NULL, 0};
    dyn_ros_ws ws;
    dyn_ros_stats st = {0};
    dyn_ros_ws_init(&ws, M, 2, work, piv);
    assert_int_equal(dyn_ros_linearize(&p, 0.0, 1.0, y, &ws, &st), 0);
    assert_int_equal(dyn_ros_step(M, &p, 0.0, 1.0, y, &ws, y1, NULL, NULL, &st), 0);
    if (re)
        *re = y1[0];
    return hypot(y1[0], y1[1]);
}

static void test_l_stability(void **state)
{
    (void)state;
    /* R(z) -> 0 as z -> -infinity like -8.84 / z, and |R| <= 1 on the imaginary axis */
    for (double z = -1e2; z >= -1e14; z *= 100.0) {
        double re;
        stability_function(z, 0.0, &re);
        CHECK(fabs(re) < 10.0 / fabs(z) && fabs(re) > 5.0 / fabs(z), "R(%g) = %.6g", z, re);
    }
    assert_true(stability_function(-1e200, 0.0, NULL) < 1e-20); /* zero up to rounding */
    for (double w = 0.01; w < 1e8; w *= 1.7)
        CHECK(stability_function(0.0, w, NULL) <= 1.0 + 1e-14, "|R(%g i)| = %.17g", w,
              stability_function(0.0, w, NULL));
    CHECK(fabs(stability_function(-1.0, 0.0, NULL) - exp(-1.0)) < 1e-3, "R(-1) = %.17g",
          stability_function(-1.0, 0.0, NULL));

    /* y' = -1e6 (y - cos t) with h = 0.1 (h lambda = -1e5), analytic and difference
     * Jacobian, difference df/dt */
    for (int use_jac = 0; use_jac < 2; use_jac++) {
        dyn_ros_problem p = {{pr_f, 1, NULL}, use_jac ? pr_jac : NULL, 0, NULL, 0, NULL, NULL, NULL, NULL, NULL, 0};
        double work[32], y1[1];
        int piv[1];
        dyn_ros_ws ws;
        dyn_ros_ws_init(&ws, M, 1, work, piv);
        for (int start = 0; start < 2; start++) {
            /* start = 1: on the smooth solution; start = 0: y0 = 0, an initial layer of
             * size 1 and width 1e-6 */
            const double y0 = start;
            double y = y0, worst = 0.0, first = 0.0;
            const double h = 0.1;
            for (int k = 0; k < 100; k++) {
                const double t = k * h;
                dyn_ros_stats st = {0};
                assert_int_equal(dyn_ros_linearize(&p, t, h, &y, &ws, &st), 0);
                assert_int_equal(dyn_ros_step(M, &p, t, h, &y, &ws, y1, NULL, NULL, &st), 0);
                y = y1[0];
                const double e = fabs(y - pr_exact(t + h, y0));
                if (k == 0)
                    first = e;
                else
                    worst = fmax(worst, e);
            }
            /* the layer is multiplied by R(-1e5) ~ 9e-5 in one step, then again */
            CHECK(first < (start ? 1e-8 : 1e-4), "jac %d start %d: first step error %.3g",
                  use_jac, start, first);
            /* and the smooth solution is followed to ~1e-9 (the O(h^2 / lambda) terms),
             * although h^5 = 1e-5 */
            CHECK(worst < 1e-8, "jac %d start %d: largest error %.3g over 100 steps of 0.1",
                  use_jac, start, worst);
        }
    }
}

static void test_counters_and_factorisation_reuse(void **state)
{
    (void)state;
    double eps = 1e-3;
    double work[64], y1[2], y1b[2];
    int piv[2];
    dyn_ros_ws ws;
    dyn_ros_ws_init(&ws, M, 2, work, piv);
    const double y0[2] = {1.0, 1.0};
    /* analytic Jacobian, autonomous: 1 call for f0, 5 more in the stages */
    dyn_ros_problem p = {{kaps_f, 2, &eps}, kaps_jac, 1, NULL, 0, NULL, NULL, NULL, NULL, NULL, 0};
    dyn_ros_stats st = {0};
    assert_int_equal(dyn_ros_linearize(&p, 0.0, 0.1, y0, &ws, &st), 0);
    assert_int_equal(dyn_ros_step(M, &p, 0.0, 0.1, y0, &ws, y1, NULL, NULL, &st), 0);
    assert_int_equal(st.rhs_calls, 6);
    assert_int_equal(st.jac_evals, 1);
    assert_int_equal(st.jac_rhs_calls, 0);
    assert_int_equal(st.lu_decomps, 1);
    assert_int_equal(st.lin_solves, 6);
    assert_int_equal(st.steps, 1);
    /* the same h again: no new factorisation, same result bit for bit */
    assert_int_equal(dyn_ros_step(M, &p, 0.0, 0.1, y0, &ws, y1b, NULL, NULL, &st), 0);
    assert_int_equal(st.lu_decomps, 1);
    assert_true(same_bits(y1[0], y1b[0]) && same_bits(y1[1], y1b[1]));
    /* another h (a rejected step): refactorised, Jacobian kept */
    assert_int_equal(dyn_ros_step(M, &p, 0.0, 0.05, y0, &ws, y1b, NULL, NULL, &st), 0);
    assert_int_equal(st.lu_decomps, 2);
    assert_int_equal(st.jac_evals, 1);
    /* difference Jacobian, non-autonomous: n calls for J and 1 for df/dt */
    dyn_ros_problem q = {{kaps_f, 2, &eps}, NULL, 0, NULL, 0, NULL, NULL, NULL, NULL, NULL, 0};
    dyn_ros_stats sq = {0};
    assert_int_equal(dyn_ros_linearize(&q, 0.0, 0.1, y0, &ws, &sq), 0);
    assert_int_equal(dyn_ros_step(M, &q, 0.0, 0.1, y0, &ws, y1b, NULL, NULL, &sq), 0);
    assert_int_equal(sq.rhs_calls, 6 + 2 + 1);
    assert_int_equal(sq.jac_rhs_calls, 3);
    assert_int_equal(sq.jac_evals, 1);
    /* close to the analytic-Jacobian step */
    assert_true(max_abs_diff(y1, y1b, 2) < 1e-7);
}

/* y' = lambda y with 1/(h gamma) = lambda: the matrix is exactly zero. */
static int lam_f(double t, const double *y, double *f, void *par)
{
    (void)t;
    f[0] = *(const double *)par * y[0];
    return 0;
}

static int fail_f(double t, const double *y, double *f, void *par)
{
    int *count = par;
    (void)t;
    f[0] = -y[0];
    return ++*count == 3 ? -5 : 0;
}

static void test_singular_and_failures(void **state)
{
    (void)state;
    double lam = 40.0; /* h gamma = 0.1 * 0.25 = 1/40 */
    dyn_ros_problem p = {{lam_f, 1, &lam}, NULL, 1, NULL, 0, NULL, NULL, NULL, NULL, NULL, 0};
    double work[32], y = 1.0, y1[1];
    int piv[1];
    dyn_ros_ws ws;
    dyn_ros_ws_init(&ws, M, 1, work, piv);
    dyn_ros_stats st = {0};
    assert_int_equal(dyn_ros_linearize(&p, 0.0, 0.1, &y, &ws, &st), 0);
    assert_int_equal(dyn_ros_step(M, &p, 0.0, 0.1, &y, &ws, y1, NULL, NULL, &st),
                     DYN_ROS_SINGULAR);
    /* a smaller step is fine */
    assert_int_equal(dyn_ros_step(M, &p, 0.0, 0.05, &y, &ws, y1, NULL, NULL, &st), 0);

    int count = 0;
    dyn_ros_problem q = {{fail_f, 1, &count}, NULL, 1, NULL, 0, NULL, NULL, NULL, NULL, NULL, 0};
    assert_int_equal(dyn_ros_linearize(&q, 0.0, 0.1, &y, &ws, &st), 0); /* calls 1, 2 */
    assert_int_equal(dyn_ros_step(M, &q, 0.0, 0.1, &y, &ws, y1, NULL, NULL, &st),
                     DYN_ROS_RHS_FAIL);
    assert_int_equal(ws.rhs_status, -5);
}

/* The adaptive loop on Kaps (eps = 1e-6, very stiff) and van der Pol (mu = 1000) meets its
 * tolerance to a small factor, and the on_step dense output is continuous. */
typedef struct seen {
    double t_last;
    long steps;
    int gap;
} seen;

static int on_step(double t_old, double t_new, const double *y, const double *cont, void *ctx)
{
    seen *s = ctx;
    (void)y;
    (void)cont;
    if (s->steps > 0 && t_old != s->t_last)
        s->gap = 1;
    s->t_last = t_new;
    s->steps++;
    return 0;
}

static void test_adaptive_loop(void **state)
{
    (void)state;
    double eps = 1e-6;
    dyn_ros_problem p = {{kaps_f, 2, &eps}, kaps_jac, 1, NULL, 0, NULL, NULL, NULL, NULL, NULL, 0};
    double work[64], y1[2], e[2], cont[8];
    int piv[2];
    dyn_ros_ws ws;
    dyn_ros_ws_init(&ws, M, 2, work, piv);
    const double tols[] = {1e-4, 1e-6, 1e-8, 1e-10};
    for (size_t k = 0; k < sizeof tols / sizeof tols[0]; k++) {
        double y[2] = {1.0, 1.0};
        seen s = {0};
        dyn_ros_opts o = {.rtol = tols[k], .atol = tols[k], .on_step = on_step, .ctx = &s,
                          .cont = cont};
        dyn_ros_stats st = {0};
        double t_end = 0.0;
        char msg[128];
        int rc = dyn_ros_integrate(M, &p, 0.0, 2.0, y, &o, &ws, y1, e, &st, &t_end, msg,
                                   sizeof msg);
        CHECK(rc == DYN_OK, "tol %g: %s", tols[k], msg);
        assert_true(t_end == 2.0 && s.t_last == 2.0 && !s.gap);
        const double ex[2] = {exp(-4.0), exp(-2.0)};
        double err = max_abs_diff(y, ex, 2);
        CHECK(err < 20.0 * tols[k], "tol %g: error %.3g in %ld steps", tols[k], err, s.steps);
    }
}

/* ---- through dyn_solve ---- */

static int run_solve(const char *model_name, double mu, double t1, double rtol,
                     const double *atolv, double atol, int analytic, const double *out_times,
                     long n_out, dyn_output_fn out, void *out_ctx, double *y, dyn_result *res)
{
    const dyn_tableau *m = dyn_method_find("rodas4");
    assert_non_null(m);
    assert_true(dyn_method_is_adaptive(m) && dyn_method_is_stiff(m));
    const dyn_model *model = dyn_model_find(model_name);
    assert_non_null(model);
    double par[16];
    char err[128];
    assert_int_equal(dyn_model_default_params(model, par, err, sizeof err), 0);
    if (mu > 0)
        ((dyn_vanderpol_par *)par)->mu = mu;
    dyn_system sys = {model->rhs, model->n_states, par};
    dyn_solve_opts o = {0};
    o.rtol = rtol;
    o.atol = atol;
    o.atolv = atolv;
    o.jacobian = analytic ? model->jacobian : NULL;
    o.out_times = out_times;
    o.n_out_times = n_out;
    o.output = out;
    o.output_ctx = out_ctx;
    int iwork[8];
    assert_int_equal(dyn_solve_iwork_size(m, model->n_states), model->n_states);
    o.iwork = iwork;
    static double work[4096];
    assert_true(dyn_solve_work_size(m, model->n_states, &o) <= sizeof work / sizeof work[0]);
    return dyn_solve(m, &sys, model->t0, t1, model->y0, y, work, &o, res);
}

static double rel_err(const double *y, const double *ref, int n)
{
    double w = 0.0;
    for (int i = 0; i < n; i++)
        w = fmax(w, fabs(y[i] - ref[i]) / fabs(ref[i]));
    return w;
}

static void test_solve_van_der_pol_stiff(void **state)
{
    (void)state;
    const dyn_reference *r = dyn_reference_find("vanderpol-mu1000-3000");
    assert_non_null(r);
    for (int analytic = 1; analytic >= 0; analytic--) {
        double y[2];
        dyn_result res;
        int rc = run_solve("vanderpol", 1000.0, 3000.0, 1e-9, NULL, 1e-11, analytic, NULL, 0,
                           NULL, NULL, y, &res);
        CHECK(rc == DYN_OK, "%s", res.message);
        const double e = rel_err(y, r->y, 2);
        CHECK(e < 1e-7, "analytic %d: relative error %.3g (%ld steps)", analytic, e,
              res.stats.steps);
        assert_true(res.stats.jac_calls > 0 && res.stats.jac_calls <= res.stats.accepted +
                                                                         res.stats.rejected);
        /* a stiff problem with a stiff method: thousands of steps, not millions */
        CHECK(res.stats.steps < 50000, "%ld steps", res.stats.steps);
        assert_int_equal(res.stiff, 0);
        /* per attempt: 6 stage evaluations (+1 for df/dt, +2 for a difference Jacobian at
         * each new point) */
        const long per = analytic ? 7 : 9;
        assert_true(res.stats.rhs_calls <= per * res.stats.steps + 2);
        /* exactly, as dyn_method_calls_per_step says: each new point f(t, y), df/dt and five
         * stages, a retry after a rejection five stages; f(t0, y0) and the initial-step
         * probe once; one Jacobian per new point */
        const dyn_tableau *m = dyn_method_find("rodas4");
        assert_int_equal(dyn_method_calls_per_step(m), 7);
        assert_int_equal(dyn_method_jac_per_step(m), 1);
        if (analytic) {
            CHECK(res.stats.rhs_calls == dyn_method_calls_per_step(m) * res.stats.accepted +
                                             5 * res.stats.rejected + 2,
                  "rhs %ld, accepted %ld, rejected %ld", res.stats.rhs_calls,
                  res.stats.accepted, res.stats.rejected);
            assert_int_equal(res.stats.jac_calls, res.stats.accepted);
        }
    }
}

typedef struct rober_log {
    long count;
    double worst_mass;
    double t_last;
} rober_log;

static int rober_out(long k, double t, const double *y, void *ctx)
{
    rober_log *l = ctx;
    (void)k;
    l->count++;
    l->t_last = t;
    l->worst_mass = fmax(l->worst_mass, fabs(y[0] + y[1] + y[2] - 1.0));
    return 0;
}

static void test_solve_robertson_to_1e11(void **state)
{
    (void)state;
    const dyn_reference *r = dyn_reference_find("robertson-1e11");
    const dyn_reference *r40 = dyn_reference_find("robertson-40");
    assert_non_null(r);
    assert_non_null(r40);
    /* samples at 40 and at 10^k, k = -5 .. 11: the dense output between steps */
    double times[20];
    long nt = 0;
    times[nt++] = 0.0;
    for (int k = -5; k <= 11; k++) {
        times[nt++] = pow(10.0, k);
        if (k == 1)
            times[nt++] = 40.0;
    }
    const double atol[3] = {1e-14, 1e-20, 1e-14};
    rober_log log = {0};
    double y[3];
    dyn_result res;
    int rc = run_solve("robertson", 0, 1e11, 1e-9, atol, 0, 1, times, nt, rober_out, &log, y,
                       &res);
    CHECK(rc == DYN_OK, "%s", res.message);
    assert_int_equal(log.count, nt);
    assert_true(log.t_last == 1e11);
    CHECK(log.worst_mass < 1e-14, "mass off by %.3g at a sample", log.worst_mass);
    const double e = rel_err(y, r->y, 3);
    CHECK(e < 1e-6, "relative error %.3g at 1e11 in %ld steps", e, res.stats.steps);
    /* with the difference Jacobian (increments from atol / rtol: 1e-11 for y2) */
    rc = run_solve("robertson", 0, 1e11, 1e-9, atol, 0, 0, NULL, 0, NULL, NULL, y, &res);
    CHECK(rc == DYN_OK, "%s", res.message);
    const double e2 = rel_err(y, r->y, 3);
    CHECK(e2 < 1e-6, "difference Jacobian: relative error %.3g", e2);
}

/* The value at t = 40 comes from the dense output of the step that contains 40. */
typedef struct at40 {
    double y[3];
    int seen;
} at40;

static int out40(long k, double t, const double *y, void *ctx)
{
    at40 *a = ctx;
    (void)k;
    if (t == 40.0) {
        memcpy(a->y, y, sizeof a->y);
        a->seen = 1;
    }
    return 0;
}

static void test_solve_dense_output(void **state)
{
    (void)state;
    const dyn_reference *r40 = dyn_reference_find("robertson-40");
    assert_non_null(r40);
    const double times[3] = {0.0, 40.0, 1e3};
    const double atol[3] = {1e-12, 1e-18, 1e-12};
    const double rtols[2] = {1e-6, 1e-9};
    double errs[2];
    for (int k = 0; k < 2; k++) {
        at40 a = {{0}, 0};
        double y[3];
        dyn_result res;
        int rc = run_solve("robertson", 0, 1e3, rtols[k], atol, 0, 1, times, 3, out40, &a, y,
                           &res);
        CHECK(rc == DYN_OK, "%s", res.message);
        assert_true(a.seen);
        errs[k] = rel_err(a.y, r40->y, 3);
    }
    /* the interpolated value follows the tolerance (order 3 interpolant, order 4 steps) */
    CHECK(errs[0] < 1e-4 && errs[1] < 1e-7 && errs[1] < errs[0] / 50.0,
          "errors at 40: %.3g (rtol 1e-6), %.3g (rtol 1e-9)", errs[0], errs[1]);
}

/* Events on the stiff van der Pol: y1 = 0 crossings located on RODAS's dense output agree
 * with those of DOP853 at a tight tolerance on the non-stiff mu = 1 (where both are
 * cheap), and one crossing per half period appears for mu = 1000. */
static double g_y1(double t, const double *y, void *par)
{
    (void)t;
    (void)par;
    return y[0];
}

typedef struct ev_log {
    int count;
    double t[16];
} ev_log;

static int on_ev(int index, double t, const double *y, int direction, void *ctx)
{
    ev_log *l = ctx;
    (void)index;
    (void)y;
    (void)direction;
    if (l->count < 16)
        l->t[l->count] = t;
    l->count++;
    return 0;
}

static void events_with(const char *method, double mu, double t1, double rtol, ev_log *log)
{
    const dyn_tableau *m = dyn_method_find(method);
    assert_non_null(m);
    dyn_vanderpol_par par = {mu};
    dyn_system sys = {dyn_vanderpol_rhs, 2, &par};
    dyn_event ev = {"zero", "y1 = 0", g_y1, 0, 0, NULL};
    dyn_solve_opts o = {0};
    o.rtol = rtol;
    o.atol = rtol;
    o.events = &ev;
    o.n_events = 1;
    o.on_event = on_ev;
    o.event_ctx = log;
    o.jacobian = dyn_vanderpol_jac;
    int iwork[2];
    o.iwork = iwork;
    static double work[4096];
    assert_true(dyn_solve_work_size(m, 2, &o) <= sizeof work / sizeof work[0]);
    const double y0[2] = {2.0, 0.0};
    double y[2];
    dyn_result res;
    int rc = dyn_solve(m, &sys, 0.0, t1, y0, y, work, &o, &res);
    CHECK(rc == DYN_OK, "%s: %s", method, res.message);
}

static void test_solve_events(void **state)
{
    (void)state;
    ev_log a = {0}, b = {0};
    events_with("rodas4", 1.0, 15.0, 1e-10, &a);
    events_with("dop853", 1.0, 15.0, 1e-13, &b);
    assert_int_equal(a.count, b.count);
    assert_true(a.count >= 4);
    for (int k = 0; k < a.count && k < 16; k++)
        CHECK(fabs(a.t[k] - b.t[k]) < 1e-7, "crossing %d: rodas4 %.17g, dop853 %.17g", k,
              a.t[k], b.t[k]);
    /* mu = 1000: period T ~ (3 - 2 ln 2) mu = 1614 (HNW I sec. I.16, to O(mu^(-1/3)));
     * from y1 = 2 the slow branch takes half a period, then y1 jumps through zero: crossings
     * near T/2, T and 3T/2 */
    ev_log c = {0};
    events_with("rodas4", 1000.0, 3000.0, 1e-8, &c);
    assert_int_equal(c.count, 3);
    const double T = (3.0 - 2.0 * log(2.0)) * 1000.0;
    for (int k = 0; k < 3; k++)
        CHECK(fabs(c.t[k] - (k + 1) * T / 2) < 0.05 * T, "crossing %d at %.6g", k, c.t[k]);
}

/* A right-hand side that refuses times past the end of the span: the difference df/dt
 * looks backward in the last step. */
static double t_end_allowed;
static int strict_f(double t, const double *y, double *f, void *par)
{
    (void)par;
    if (t > t_end_allowed)
        return 99;
    f[0] = -1e3 * (y[0] - cos(t));
    return 0;
}

static void test_solve_never_past_the_end(void **state)
{
    (void)state;
    const dyn_tableau *m = dyn_method_find("rodas4");
    dyn_system sys = {strict_f, 1, NULL};
    dyn_solve_opts o = {0};
    o.rtol = 1e-8;
    o.atol = 1e-10;
    double work[512];
    const double y0 = 1.0;
    double y;
    dyn_result res;
    /* no iwork: refused with a message */
    assert_int_equal(dyn_solve(m, &sys, 0.0, 2.0, &y0, &y, work, &o, &res), DYN_ERR_ARG);
    assert_non_null(strstr(res.message, "iwork"));
    int iwork[1];
    o.iwork = iwork;
    assert_true(dyn_solve_work_size(m, 1, &o) <= 512);
    t_end_allowed = 2.0;
    int rc = dyn_solve(m, &sys, 0.0, 2.0, &y0, &y, work, &o, &res);
    CHECK(rc == DYN_OK, "%s", res.message);
    const double L = 1e3;
    const double ex = (L * L * cos(2.0) + L * sin(2.0)) / (L * L + 1.0);
    CHECK(fabs(y - ex) < 1e-7, "y(2) = %.17g, exact %.17g", y, ex);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_order_conditions),
        cmocka_unit_test(test_order_linear_stiff),
        cmocka_unit_test(test_order_nonlinear_kaps),
        cmocka_unit_test(test_local_error_and_dense_output),
        cmocka_unit_test(test_l_stability),
        cmocka_unit_test(test_counters_and_factorisation_reuse),
        cmocka_unit_test(test_singular_and_failures),
        cmocka_unit_test(test_adaptive_loop),
        cmocka_unit_test(test_solve_van_der_pol_stiff),
        cmocka_unit_test(test_solve_robertson_to_1e11),
        cmocka_unit_test(test_solve_dense_output),
        cmocka_unit_test(test_solve_events),
        cmocka_unit_test(test_solve_never_past_the_end),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
