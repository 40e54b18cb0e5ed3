/* SPDX-License-Identifier: BSD-3-Clause */
/* test_analysis.c — the analysis layer (dynkit/analysis.h): difference Jacobians against
 * analytic ones (Richardson to 1e-12 of a row's or column's size, central differences to
 * 2e-6), the pendulum's eigenvalues at the bottom (+-i sqrt(g/l), marginal) and at the
 * top (+-sqrt(g/l), unstable) from differences, van der Pol at the origin (mu/2 +- i
 * sqrt(1 - mu^2/4)), the stability classes and their tolerance, the reduction P^+ A P to
 * an invariant subspace, equilibria (Lorenz's C+, the pendulum's bottom and top, an
 * ignorable coordinate left alone, none where there is none), the column of a coordinate
 * that f does not depend on exactly zero, a constraint's gradient df/dq and rows dh/dy by
 * dyn_holonomic_gradient against their closed forms, and bad input named. Eigenvalues need
 * the LAPACK backend; those tests are skipped without it. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <float.h>
#include <stdio.h>

#include "dynkit/analysis.h"
#include "dynkit/brusselator.h"
#include "dynkit/dynkit.h"
#include "test_util.h"
#ifdef DYNKIT_HAVE_LAPACK
#include "dynkit/lapack.h"
#endif

#define MAXN 64

/* |a - b| <= tol, both printed when not */
#define assert_close(a, b, tol) assert_close_at((a), (b), (tol), __FILE__, __LINE__)
static void assert_close_at(double a, double b, double tol, const char *file, int line)
{
    if (!(fabs(a - b) <= tol)) {
        print_error("%s:%d: %.17g and %.17g differ by %.3g > %.3g\n", file, line, a, b, fabs(a - b),
                    tol);
        fail();
    }
}

/* A dense, nonlinear, non-autonomous system with its Jacobian:
 *   f1 = sin(y1) y2 + t^2 y3
 *   f2 = exp(0.5 y2) - y1 y3 + cos(t)
 *   f3 = y1^3 / (1 + y3^2) + 1e3 y2 */
static int f_test(double t, const double *y, double *f, void *par)
{
    (void)par;
    f[0] = sin(y[0]) * y[1] + t * t * y[2];
    f[1] = exp(0.5 * y[1]) - y[0] * y[2] + cos(t);
    f[2] = y[0] * y[0] * y[0] / (1.0 + y[2] * y[2]) + 1e3 * y[1];
    return 0;
}

static int jac_test(double t, const double *y, double *J, void *par)
{
    (void)par;
    const double q = 1.0 + y[2] * y[2];
    J[0] = cos(y[0]) * y[1];
    J[1] = sin(y[0]);
    J[2] = t * t;
    J[3] = -y[2];
    J[4] = 0.5 * exp(0.5 * y[1]);
    J[5] = -y[0];
    J[6] = 3.0 * y[0] * y[0] / q;
    J[7] = 1e3;
    J[8] = -2.0 * y[2] * y[0] * y[0] * y[0] / (q * q);
    return 0;
}

static const dyn_var test_states[] = {{"a", "1", ""}, {"b", "1", ""}, {"c", "1", ""}};
static const double test_y0[] = {0, 0, 0};
static const dyn_model test_model = {.name = "test",
                                     .n_states = 3,
                                     .states = test_states,
                                     .y0 = test_y0,
                                     .par_size = sizeof(double),
                                     .rhs = f_test,
                                     .jacobian = jac_test};

/* Largest |D_ij - J_ij| relative to the larger of the max norms of J's row i and column j
 * (what an entry's error is measured against: an eigenvalue moves by a perturbation of
 * the matrix, not of one entry alone). */
static double entry_error(int n, const double *D, const double *J)
{
    double worst = 0.0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double size = 0.0;
            for (int k = 0; k < n; k++)
                size = fmax(size, fmax(fabs(J[i * n + k]), fabs(J[k * n + j])));
            const double e = fabs(D[i * n + j] - J[i * n + j]);
            worst = fmax(worst, size > 0.0 ? e / size : e);
        }
    return worst;
}

/* The differences of m at (t, y) against its analytic Jacobian: the entry errors of the
 * Richardson and central schemes into rich, cent. */
static void compare(const dyn_model *m, double t, const double *y, void *par, double *rich,
                    double *cent)
{
    const int n = m->n_states;
    static double J[MAXN * MAXN], D[MAXN * MAXN], work[MAXN * 32];
    assert_true(n <= MAXN && dyn_linearize_work_size(n) <= MAXN * 32);
    dyn_linearize_info info;
    assert_int_equal(dyn_linearize(m, t, y, par, NULL, J, work, &info), 0);
    assert_int_equal(info.scheme, DYN_JAC_ANALYTIC);
    dyn_linearize_opts o = {DYN_JAC_RICHARDSON, NULL};
    assert_int_equal(dyn_linearize(m, t, y, par, &o, D, work, &info), 0);
    *rich = entry_error(n, D, J);
    /* the estimate is of the same order as the error (never far below it) */
    assert_true(*rich <= fmax(100.0 * info.err_est, 1e-13));
    o.scheme = DYN_JAC_CENTRAL;
    assert_int_equal(dyn_linearize(m, t, y, par, &o, D, work, &info), 0);
    assert_int_equal(info.rhs_calls, 1 + 2 * n);
    *cent = entry_error(n, D, J);
}

static void test_differences_match_analytic(void **state)
{
    (void)state;
    double par = 0.0, worst_r = 0.0, worst_c = 0.0;
    const double pts[][4] = {
        {0.3, 0.7, -1.2, 2.0}, {2.5, -3.0, 0.01, 0.5}, {0.0, 1e-3, 4.0, -7.0}, {10.0, 0, 0, 0}};
    for (size_t p = 0; p < sizeof pts / sizeof pts[0]; p++) {
        double r, c;
        compare(&test_model, pts[p][0], pts[p] + 1, &par, &r, &c);
        worst_r = fmax(worst_r, r);
        worst_c = fmax(worst_c, c);
    }
    /* the built-in models that have analytic Jacobians, at their default states and at a
     * state along a run */
    char berr[256];
    dyn_model *bruss = dyn_brusselator_new(10, berr, sizeof berr); /* 20 states, banded */
    assert_non_null(bruss);
    const dyn_model *models[] = {dyn_model_find("vanderpol"), dyn_model_find("arenstorf"),
                                 dyn_model_find("hires"), dyn_model_find("robertson"), bruss};
    for (size_t k = 0; k < sizeof models / sizeof models[0]; k++) {
        const dyn_model *m = models[k];
        assert_non_null(m);
        assert_non_null(m->jacobian);
        char buf[4096], err[256];
        assert_true(m->par_size <= sizeof buf);
        memset(buf, 0, sizeof buf);
        assert_int_equal(dyn_model_default_params(m, buf, err, sizeof err), 0);
        double y[MAXN];
        assert_true(m->n_states <= MAXN);
        dyn_model_initial_state(m, buf, y);
        double r, c;
        compare(m, m->t0, y, buf, &r, &c);
        worst_r = fmax(worst_r, r);
        worst_c = fmax(worst_c, c);
        for (int i = 0; i < m->n_states; i++) /* off the default, every state moved */
            y[i] = y[i] * 1.1 + 0.05 * (i + 1);
        compare(m, m->t0 + 0.5, y, buf, &r, &c);
        worst_r = fmax(worst_r, r);
        worst_c = fmax(worst_c, c);
    }
    dyn_brusselator_free(bruss);
    print_message("difference Jacobians: Richardson %.2e, central %.2e of a row's or "
                  "column's size\n",
                  worst_r, worst_c);
    /* measured 5.8e-14 and 7.4e-7 (central differences at Arenstorf's start, 0.006 from
     * the Moon's singularity: a truncation error (h/0.006)^2) */
    assert_true(worst_r < 1e-12);
    assert_true(worst_c < 2e-6);
}

static void test_no_analytic_jacobian_is_named(void **state)
{
    (void)state;
    const dyn_model *m = dyn_model_find("pendulum");
    assert_null(m->jacobian);
    char par[256], err[256];
    memset(par, 0, sizeof par);
    assert_int_equal(dyn_model_default_params(m, par, err, sizeof err), 0);
    double y[2] = {0, 0}, A[4], work[64];
    dyn_linearize_info info;
    const dyn_linearize_opts o = {DYN_JAC_ANALYTIC, NULL};
    assert_int_equal(dyn_linearize(m, 0.0, y, par, &o, A, work, &info), DYN_ERR_ARG);
    assert_non_null(strstr(info.message, "no analytic Jacobian"));
    const double typ[2] = {1.0, -1.0};
    const dyn_linearize_opts bad = {DYN_JAC_RICHARDSON, typ};
    assert_int_equal(dyn_linearize(m, 0.0, y, par, &bad, A, work, &info), DYN_ERR_ARG);
    assert_non_null(strstr(info.message, "dphi"));
}

static void test_classification(void **state)
{
    (void)state;
    const double stable[] = {-1.0, -2.0, -1e-3}, marg[] = {-1.0, 1e-12, -3.0},
                 unst[] = {-1.0, 1e-6, -3.0};
    assert_int_equal(dyn_classify(3, stable, 1e-8), DYN_STABLE);
    assert_int_equal(dyn_classify(3, marg, 1e-8), DYN_MARGINAL);
    assert_int_equal(dyn_classify(3, unst, 1e-8), DYN_UNSTABLE);
    /* the tolerance is relative to the largest row sum of |A| */
    const double A[] = {1.0, -2.0, 3.0, 0.5};
    assert_close(dyn_stability_tol(2, A, 0.0), 3.5e-8, 1e-22);
    assert_close(dyn_stability_tol(2, A, 1e-6), 3.5e-6, 1e-20);
    /* a pair sits symmetrically after sorting: by im, then re */
    double re[] = {3.0, -1.0, -1.0, 0.5}, im[] = {0.0, 2.0, -2.0, 0.0};
    dyn_eig_sort(4, re, im);
    assert_true(im[0] == -2.0 && im[3] == 2.0 && re[1] == 0.5 && re[2] == 3.0);
    double wn, zeta;
    dyn_eig_mode(-3.0, 4.0, &wn, &zeta); /* s^2 + 6 s + 25: wn 5, zeta 0.6 */
    assert_close(wn, 5.0, 1e-15);
    assert_close(zeta, 0.6, 1e-15);
}

/* A = S B S^-1 with B block upper triangular: span of S's first two columns is invariant
 * and carries B's 2x2 block (eigenvalues +-2i); a mixed basis of it gives that block's
 * trace 0 and determinant 4. */
static void test_reduction_to_invariant_subspace(void **state)
{
    (void)state;
    const double a = 2.0, b = 3.0, c = -1.0;
    const double S[9] = {1, 0, 0, a, 1, 0, b, c, 1};
    const double Si[9] = {1, 0, 0, -a, 1, 0, a * c - b, -c, 1};
    const double B[9] = {0, 1, 7, -4, 0, 3, 0, 0, -5};
    double SB[9], A[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            SB[i * 3 + j] = 0.0;
            for (int k = 0; k < 3; k++)
                SB[i * 3 + j] += S[i * 3 + k] * B[k * 3 + j];
        }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            A[i * 3 + j] = 0.0;
            for (int k = 0; k < 3; k++)
                A[i * 3 + j] += SB[i * 3 + k] * Si[k * 3 + j];
        }
    /* P = S[:, 0:2] M, M = [1 1; 0 2] */
    double P[6];
    for (int i = 0; i < 3; i++) {
        P[i * 2 + 0] = S[i * 3 + 0];
        P[i * 2 + 1] = S[i * 3 + 0] + 2.0 * S[i * 3 + 1];
    }
    double Am[4], work[3 * 2 + 4 + 2];
    assert_int_equal(dyn_linear_reduce(3, 2, A, P, Am, work), 0);
    assert_close(Am[0] + Am[3], 0.0, 1e-13);
    assert_close(Am[0] * Am[3] - Am[1] * Am[2], 4.0, 1e-12);
    /* dependent directions are refused */
    const double Pd[6] = {1, 2, 0, 0, 1, 2};
    assert_int_equal(dyn_linear_reduce(3, 2, A, Pd, Am, work), DYN_ERR_ARG);
}

/* Lorenz's system without its Jacobian (differences), sigma 10, rho 28, beta 8/3. */
static int f_lorenz(double t, const double *y, double *f, void *par)
{
    (void)t;
    (void)par;
    f[0] = 10.0 * (y[1] - y[0]);
    f[1] = y[0] * (28.0 - y[2]) - y[1];
    f[2] = y[0] * y[1] - 8.0 / 3.0 * y[2];
    return 0;
}

/* A block sliding with friction, pushed by 1 + x^2 when push is set: x does not enter
 * the equations without it (an ignorable coordinate), and with it x' = v, v' = 1 + x^2 - v
 * has no equilibrium (|f| is least at a point where f is not 0). */
static int f_slide(double t, const double *y, double *f, void *par)
{
    (void)t;
    const int push = *(const int *)par;
    f[0] = push ? 1.0 + y[0] * y[0] : y[1];
    f[1] = -0.7 * y[1];
    return 0;
}

/* A rotor whose damping is written with sin^2 + cos^2 of its angle: the angle does not
 * enter f, but its differences are rounding noise unless told apart from 0. */
static int f_rotor(double t, const double *y, double *f, void *par)
{
    (void)t;
    (void)par;
    const double s = sin(y[0] + 0.3), c = cos(y[0] + 0.3);
    f[0] = y[1];
    f[1] = -0.5 * y[1] * (s * s + c * c) + 1e3 * (s * s + c * c) - 997.0;
    return 0;
}

static const dyn_model rotor_model = {
    .name = "rotor", .n_states = 2, .states = test_states, .y0 = test_y0, .rhs = f_rotor};

static void test_ignorable_column_is_zero(void **state)
{
    (void)state;
    double A[4], work[64];
    const dyn_linearize_opts o = {DYN_JAC_RICHARDSON, NULL};
    for (double x = -2.0; x <= 2.0; x += 0.37) {
        const double y[2] = {x, 6.0};
        assert_int_equal(dyn_linearize(&rotor_model, 0.0, y, NULL, &o, A, work, NULL), 0);
        assert_true(A[0] == 0.0 && A[2] == 0.0); /* the angle's column exactly */
        assert_true(A[1] == 1.0);
        assert_close(A[3], -0.5, 1e-13);
    }
}

static const dyn_model lorenz_model = {
    .name = "lorenz", .n_states = 3, .states = test_states, .y0 = test_y0, .rhs = f_lorenz};
static const dyn_model slide_model = {
    .name = "slide", .n_states = 2, .states = test_states, .y0 = test_y0, .rhs = f_slide};

static void test_equilibria(void **state)
{
    (void)state;
    double work[512];
    assert_true(dyn_equilibrium_work_size(3) <= 512);
    dyn_equilibrium_info info;
    /* Lorenz's C+ = (sqrt(beta (rho-1)), same, rho - 1) from a guess off it */
    double y[3] = {7.0, 9.5, 25.0};
    assert_int_equal(dyn_equilibrium(&lorenz_model, 0.0, y, NULL, NULL, work, &info), 0);
    const double c = sqrt(8.0 / 3.0 * 27.0);
    assert_close(y[0], c, 1e-12 * c);
    assert_close(y[1], c, 1e-12 * c);
    assert_close(y[2], 27.0, 1e-12 * 27.0);
    assert_true(info.residual <= info.tol && info.iterations <= 10);
    print_message("Lorenz C+: %d iterations, %ld calls of f, |f| = %.1e\n", info.iterations,
                  info.rhs_calls, info.residual);
    /* the pendulum: the bottom from 0.4 rad, the top from 3 rad */
    const dyn_model *pend = dyn_model_find("pendulum");
    char par[256], err[256];
    memset(par, 0, sizeof par);
    assert_int_equal(dyn_model_default_params(pend, par, err, sizeof err), 0);
    double p[2] = {0.4, 0.3};
    assert_int_equal(dyn_equilibrium(pend, 0.0, p, par, NULL, work, &info), 0);
    assert_true(fabs(p[0]) < 1e-12 && fabs(p[1]) < 1e-12);
    p[0] = 3.0;
    p[1] = 0.0;
    assert_int_equal(dyn_equilibrium(pend, 0.0, p, par, NULL, work, &info), 0);
    assert_close(p[0], DYN_PI, 1e-12);
    /* an ignorable coordinate stays where it is, bit for bit */
    int push = 0;
    double s[2] = {3.25, 2.0};
    assert_int_equal(dyn_equilibrium(&slide_model, 0.0, s, &push, NULL, work, &info), 0);
    assert_true(s[0] == 3.25 && fabs(s[1]) <= info.tol);
    /* no equilibrium: refused with the residual named */
    push = 1;
    s[0] = 0.5;
    s[1] = 0.0;
    assert_int_equal(dyn_equilibrium(&slide_model, 0.0, s, &push, NULL, work, &info),
                     DYN_ERR_STEP_SIZE);
    assert_true(fabs(s[0]) < 1e-3 && info.residual >= 1.0 - 1e-6);
    assert_non_null(strstr(info.message, "|f|_inf = 1"));
}

#ifdef DYNKIT_HAVE_LAPACK
/* Eigenvalues of m at y (parameters by name) into re, im (sorted); the stability back. */
static dyn_stability eig_of(const char *model, const char *const *pn, const double *pv, int np,
                            const double *y, double *re, double *im)
{
    const dyn_model *m = dyn_model_find(model);
    char par[4096], err[256];
    memset(par, 0, sizeof par);
    assert_int_equal(dyn_model_default_params(m, par, err, sizeof err), 0);
    for (int k = 0; k < np; k++)
        dyn_model_set_param(m, par, dyn_model_param_index(m, pn[k]), pv[k]);
    assert_true(!m->prepare || m->prepare(par, err, sizeof err) == 0);
    const int n = m->n_states;
    double A[MAXN * MAXN], work[MAXN * 32];
    assert_int_equal(dyn_linearize(m, 0.0, y, par, NULL, A, work, NULL), 0);
    const double tol = dyn_stability_tol(n, A, 0.0);
    assert_int_equal(dyn_eig_solver_lapack.eigenvalues(n, A, re, im, err, sizeof err), 0);
    dyn_eig_sort(n, re, im);
    return dyn_classify(n, re, tol);
}

static void test_pendulum_eigenvalues(void **state)
{
    (void)state;
    const char *pn[] = {"g", "l"};
    const double pv[] = {9.81, 2.0}, w = sqrt(9.81 / 2.0);
    const double bottom[2] = {0.0, 0.0}, top[2] = {DYN_PI, 0.0};
    double re[2], im[2];
    /* the pendulum has no analytic Jacobian: these come from differences */
    assert_int_equal(eig_of("pendulum", pn, pv, 2, bottom, re, im), DYN_MARGINAL);
    assert_close(im[0], -w, 1e-12 * w);
    assert_close(im[1], w, 1e-12 * w);
    assert_true(fabs(re[0]) < 1e-12 && fabs(re[1]) < 1e-12);
    assert_int_equal(eig_of("pendulum", pn, pv, 2, top, re, im), DYN_UNSTABLE);
    assert_close(re[0], -w, 1e-12 * w);
    assert_close(re[1], w, 1e-12 * w);
    assert_true(im[0] == 0.0 && im[1] == 0.0);
}

static void test_vanderpol_origin(void **state)
{
    (void)state;
    const char *pn[] = {"mu"};
    const double y[2] = {0.0, 0.0};
    for (double mu = 0.25; mu < 2.0; mu += 0.5) {
        double re[2], im[2];
        assert_int_equal(eig_of("vanderpol", pn, &mu, 1, y, re, im), DYN_UNSTABLE);
        const double w = sqrt(1.0 - mu * mu / 4.0);
        assert_close(re[0], mu / 2.0, 1e-14);
        assert_close(re[1], mu / 2.0, 1e-14);
        assert_close(im[1], w, 1e-14);
        assert_close(im[0], -w, 1e-14);
    }
    for (double mu = 2.5; mu < 6.0; mu += 1.0) { /* two real roots mu/2 +- sqrt(mu^2/4 - 1) */
        double re[2], im[2];
        assert_int_equal(eig_of("vanderpol", pn, &mu, 1, y, re, im), DYN_UNSTABLE);
        const double d = sqrt(mu * mu / 4.0 - 1.0);
        assert_true(im[0] == 0.0 && im[1] == 0.0);
        assert_close(re[0], mu / 2.0 - d, 1e-13);
        assert_close(re[1], mu / 2.0 + d, 1e-13);
    }
}
#endif

/* A point on a rod of length 2 about the origin, f = (x^2 + y^2 - 4)/2 = 0 (its rate
 * h = x dx + y dy), and a constraint on the speeds dx - 3 y dy = 0, as the outputs of
 * dyn_mech_constraints_to_c's model: the gradient df/dq is (x, y), and dh/dy is
 * (dx, dy, x, y) and (0, -3 dy, 1, -3 y): exact for these quadratics but for the rounding
 * of f and h over the step (within 1e-10 of the row's size); without Dh, the same G. */
static const dyn_var rod_states[] = {{"x", "m", ""}, {"y", "m", ""}, {"dx", "m/s", ""},
                                     {"dy", "m/s", ""}};
static const dyn_var rod_outputs[] = {{"rod", "holonomic", ""}, {"slip", "speeds", ""},
                                      {"rod:f", "position", ""}};
static int rod_values(double t, const double *y, const void *par, double *out)
{
    (void)t;
    (void)par;
    out[0] = y[0] * y[2] + y[1] * y[3];
    out[1] = y[2] - 3.0 * y[1] * y[3];
    out[2] = (y[0] * y[0] + y[1] * y[1] - 4.0) / 2.0;
    return 0;
}
static const dyn_model rod_model = {.name = "rod", .n_states = 4, .states = rod_states,
                                    .n_outputs = 3, .outputs = rod_outputs,
                                    .compute_outputs = rod_values};

static void test_holonomic_gradient(void **state)
{
    (void)state;
    const double ys[2][4] = {{1.2, -1.6, 0.8, 0.6}, {-0.3, 1.977, -25.0, 7.0}};
    for (int s = 0; s < 2; s++) {
        const double *y = ys[s];
        double G[3 * 2], Dh[3 * 4];
        assert_int_equal(dyn_holonomic_gradient(&rod_model, NULL, 0.0, y, G, Dh), 2);
        const double want_G[4] = {y[0], y[1], 0.0, 0.0};
        const double want_Dh[8] = {y[2], y[3], y[0], y[1], 0.0, -3.0 * y[3], 1.0, -3.0 * y[1]};
        for (int i = 0; i < 4; i++)
            assert_close(G[i], want_G[i], 1e-10 * 2.0);
        for (int i = 0; i < 8; i++)
            assert_close(Dh[i], want_Dh[i], 1e-10 * 25.0);
        double G2[3 * 2];
        assert_int_equal(dyn_holonomic_gradient(&rod_model, NULL, 0.0, y, G2, NULL), 2);
        for (int i = 0; i < 4; i++)
            assert_true(G2[i] == G[i]);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_differences_match_analytic),
        cmocka_unit_test(test_no_analytic_jacobian_is_named),
        cmocka_unit_test(test_classification),
        cmocka_unit_test(test_reduction_to_invariant_subspace),
        cmocka_unit_test(test_equilibria),
        cmocka_unit_test(test_ignorable_column_is_zero),
        cmocka_unit_test(test_holonomic_gradient),
#ifdef DYNKIT_HAVE_LAPACK
        cmocka_unit_test(test_pendulum_eigenvalues),
        cmocka_unit_test(test_vanderpol_origin),
#endif
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
