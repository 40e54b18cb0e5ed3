/* SPDX-License-Identifier: BSD-3-Clause */
/* test_colloc.c — orthogonal collocation (dynkit/colloc.h) against closed forms: the Hopf
 * normal form x' = mu x - y - x r^2, y' = x + mu y - y r^2, whose orbit is the circle of
 * radius sqrt(mu) with period 2 pi and Floquet multipliers 1 and exp(-4 pi mu) (the trace
 * of the linearization integrated over the period); the error at the mesh points of order
 * 2 ncol in 1/ntst (superconvergence, observed for ncol = 2, 3, 4); the branch from its
 * Hopf point (radius sqrt(mu) along it); the Brusselator's branch from its Hopf point
 * b = 1 + a^2, whose period tends to 2 pi/a at onset; a linear boundary-value problem with
 * its closed form; and, with LAPACK's eigenvalues, the Roessler system's first period
 * doubling (a multiplier at -1, the doubled branch starting at twice the period). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dynkit/colloc.h"
#include "dynkit/continuation.h"
#include "test_util.h"
#ifdef DYNKIT_HAVE_LAPACK
#include "dynkit/lapack.h"
#include "roessler_hopf.h"
#endif

#define assert_close(a, b, tol) assert_close_at((a), (b), (tol), __FILE__, __LINE__)
static void assert_close_at(double a, double b, double tol, const char *file, int line)
{
    if (!(fabs(a - b) <= tol)) {
        print_error("%s:%d: %.17g and %.17g differ by %.3g > %.3g\n", file, line, a, b,
                    fabs(a - b), tol);
        fail();
    }
}

/* ---- the Hopf normal form, time scaled by the period par[0] ---- */
static int hopf_f(double t, const double *u, const double *par, double *f, double *fu,
                  void *ctx)
{
    (void)t;
    const double mu = *(const double *)ctx, T = par[0];
    const double x = u[0], y = u[1], r2 = x * x + y * y;
    f[0] = T * (mu * x - y - x * r2);
    f[1] = T * (x + mu * y - y * r2);
    if (fu) {
        fu[0] = T * (mu - r2 - 2 * x * x);
        fu[1] = T * (-1 - 2 * x * y);
        fu[2] = T * (1 - 2 * x * y);
        fu[3] = T * (mu - r2 - 2 * y * y);
    }
    return 0;
}

static int periodic_bc(const double *u0, const double *u1, const double *par, double *g,
                       void *ctx)
{
    (void)par;
    (void)ctx;
    g[0] = u0[0] - u1[0];
    g[1] = u0[1] - u1[1];
    return 0;
}

/* the orbit from a distorted guess; returns the largest error of the mesh points' radius
 * and the period's error */
static void hopf_orbit(int ntst, int ncol, double mu, double *err_r, double *err_T,
                       double *M)
{
    dyn_colloc_problem p = {2, 1, 2, 1, hopf_f, periodic_bc, &mu};
    dyn_colloc_sol x, ref;
    assert_int_equal(dyn_colloc_sol_alloc(&x, 2, ntst, ncol, 1), 0);
    for (long g = 0; g < dyn_colloc_nodes(&x); g++) {
        const double s = 2 * DYN_PI * dyn_colloc_node_time(&x, g);
        x.u[2 * g] = 0.6 * cos(s);
        x.u[2 * g + 1] = 0.4 * sin(s + 0.3);
    }
    x.par[0] = 6.0;
    assert_int_equal(dyn_colloc_sol_copy(&ref, &x), 0);
    dyn_colloc_info inf;
    assert_int_equal(dyn_colloc_solve(&p, &x, &ref, NULL, NULL, &inf), 0);
    double e = 0.0;
    for (int j = 0; j <= ntst; j++) {
        const double *u = x.u + 2 * (size_t)j * ncol;
        e = fmax(e, fabs(hypot(u[0], u[1]) - sqrt(mu)));
    }
    *err_r = e;
    *err_T = fabs(x.par[0] - 2 * DYN_PI);
    if (M)
        assert_int_equal(dyn_colloc_monodromy(&p, &x, M), 0);
    dyn_colloc_sol_free(&x);
    dyn_colloc_sol_free(&ref);
}

static void test_superconvergence_order(void **state)
{
    (void)state;
    for (int ncol = 2; ncol <= 4; ncol++) {
        double e1, t1, e2, t2;
        hopf_orbit(8, ncol, 0.25, &e1, &t1, NULL);
        hopf_orbit(16, ncol, 0.25, &e2, &t2, NULL);
        const double order_r = log2(e1 / e2), order_T = log2(t1 / t2);
        print_message("ncol %d: radius error %.3g -> %.3g (order %.2f), period %.3g -> %.3g "
                      "(order %.2f)\n", ncol, e1, e2, order_r, t1, t2, order_T);
        assert_true(fabs(order_r - 2 * ncol) < 0.3);
        assert_true(fabs(order_T - 2 * ncol) < 0.3);
    }
}

static void test_floquet_multipliers(void **state)
{
    (void)state;
    const double mu = 0.25;
    double e, t, M[4];
    hopf_orbit(32, 4, mu, &e, &t, M);
    assert_true(e < 1e-12);
    assert_true(t < 1e-11);
    /* the multipliers from the trace and determinant of the 2 x 2 monodromy matrix */
    const double tr = M[0] + M[3], det = M[0] * M[3] - M[1] * M[2];
    const double disc = sqrt(fmax(tr * tr / 4 - det, 0.0));
    const double m1 = tr / 2 + disc, m2 = tr / 2 - disc;
    assert_close(m1, 1.0, 1e-8);
    assert_close(m2, exp(-4 * DYN_PI * mu), 1e-8);
}

/* ---- branches: x' = f(x, lambda) ---- */
static int hopf_sys(const double *x, double mu, double *f, double *J, void *ctx)
{
    (void)ctx;
    const double u[2] = {x[0], x[1]}, par[1] = {1.0};
    return hopf_f(0, u, par, f, J, &mu);
}

static void test_branch_from_hopf_normal_form(void **state)
{
    (void)state;
    dyn_po_system sys = {2, hopf_sys, NULL};
    const double x0[2] = {0, 0};
    dyn_po_opts o = {0};
    o.ntst = 20;
    o.ds = 0.05;
    o.nmax = 15;
    dyn_po_branch b;
    assert_int_equal(dyn_po_from_hopf(&sys, x0, 0.0, 1.0, &o, &b), 0);
    assert_int_equal(b.npoints, 15);
    for (int k = 0; k < b.npoints; k++) {
        const dyn_po_point *p = &b.pts[k];
        assert_true(p->par > 0);
        assert_close(p->xmax[0], sqrt(p->par), 2e-6 * (1 + sqrt(p->par)));
        assert_close(p->xmin[1], -sqrt(p->par), 2e-6 * (1 + sqrt(p->par)));
        assert_close(p->period, 2 * DYN_PI, 1e-7);
        assert_int_equal(p->stable, -1); /* no eigenvalue solver given */
    }
    dyn_po_branch_free(&b);
}

static int brusselator(const double *x, double b, double *f, double *J, void *ctx)
{
    const double a = *(const double *)ctx;
    f[0] = a - (b + 1) * x[0] + x[0] * x[0] * x[1];
    f[1] = b * x[0] - x[0] * x[0] * x[1];
    if (J) {
        J[0] = -(b + 1) + 2 * x[0] * x[1];
        J[1] = x[0] * x[0];
        J[2] = b - 2 * x[0] * x[1];
        J[3] = -x[0] * x[0];
    }
    return 0;
}

static void test_brusselator_period_at_onset(void **state)
{
    (void)state;
    double a = 1.5;
    dyn_po_system sys = {2, brusselator, &a};
    const double x0[2] = {a, (1 + a * a) / a};
    dyn_po_opts o = {0};
    o.ntst = 30;
    o.ds = 0.01;
    o.nmax = 20;
    dyn_po_branch b;
    assert_int_equal(dyn_po_from_hopf(&sys, x0, 1 + a * a, a, &o, &b), 0);
    /* T(b) is smooth in b at onset: the first points' periods extrapolated linearly to
     * b = 1 + a^2 give 2 pi / a */
    const dyn_po_point *p0 = &b.pts[0], *p1 = &b.pts[1];
    const double slope = (p1->period - p0->period) / (p1->par - p0->par);
    const double T_onset = p0->period - slope * (p0->par - (1 + a * a));
    print_message("Brusselator a = 1.5: first orbit at b = %.10g, T = %.12g; extrapolated "
                  "T(b_H) = %.12g, 2 pi/a = %.12g\n", p0->par, p0->period, T_onset,
                  2 * DYN_PI / a);
    assert_close(T_onset, 2 * DYN_PI / a, 1e-6);
    assert_true(p0->par > 1 + a * a); /* supercritical: the orbits exist above b_H */
    dyn_po_branch_free(&b);
}

/* a pitchfork of cycles: r' = r (mu - r^2), theta' = 1, z' = (mu - c) z - z^3 (c = 0.5) */
static int cycle_pitchfork(const double *x, double mu, double *f, double *J, void *ctx)
{
    (void)ctx;
    const double c = 0.5, g = mu - x[0] * x[0] - x[1] * x[1];
    f[0] = x[0] * g - x[1];
    f[1] = x[1] * g + x[0];
    f[2] = (mu - c) * x[2] - x[2] * x[2] * x[2];
    if (J) {
        const double j[9] = {g - 2 * x[0] * x[0], -1 - 2 * x[0] * x[1], 0,
                             1 - 2 * x[0] * x[1], g - 2 * x[1] * x[1], 0,
                             0, 0, mu - c - 3 * x[2] * x[2]};
        memcpy(J, j, sizeof j);
    }
    return 0;
}

static int hqr(int n, double *a, double *re, double *im, char *err, size_t errlen)
{
    return dyn_eig_hqr(n, a, re, im, err, errlen);
}

static void test_cycle_pitchfork_switching(void **state)
{
    (void)state;
    static const dyn_eig_solver eig = {"hqr", hqr};
    dyn_po_system sys = {3, cycle_pitchfork, NULL};
    const double x0[3] = {0, 0, 0};
    dyn_po_opts o = {0};
    o.ntst = 20;
    o.ds = 0.02;
    o.dsmax = 0.1;
    o.par_min = -0.5;
    o.par_max = 1.0;
    o.eig = &eig;
    dyn_po_branch b;
    assert_int_equal(dyn_po_from_hopf(&sys, x0, 0.0, 1.0, &o, &b), 0);
    const dyn_po_point *bp = NULL;
    for (int k = 0; k < b.npoints; k++) {
        assert_true(strcmp(b.pts[k].label, "LPC") != 0);
        if (strcmp(b.pts[k].label, "BP") == 0) {
            assert_null(bp);
            bp = &b.pts[k];
        }
    }
    assert_non_null(bp);
    /* the multiplier exp(2 pi (mu - c)) passes through 1 at mu = c */
    assert_close(bp->par, 0.5, 1e-8);
    assert_non_null(bp->tangent.u);
    for (int dir = -1; dir <= 1; dir += 2) {
        dyn_po_branch s;
        assert_int_equal(dyn_po_from_bp(&sys, bp, dir, &o, &s), 0);
        assert_true(s.npoints > 5);
        /* the other family: z^2 = mu - c, r = sqrt(mu), period 2 pi; one z sign each way */
        for (int k = 0; k < s.npoints; k++) {
            const dyn_po_point *p = &s.pts[k];
            const double z = sqrt(fmax(p->par - 0.5, 0.0));
            assert_close(fabs(p->xmax[2]), z, 1e-8);
            assert_close(p->xmax[2], p->xmin[2], 1e-8);
            assert_close(p->xmax[0], sqrt(p->par), 1e-8);
            assert_close(p->period, 2 * DYN_PI, 1e-8);
        }
        assert_true(s.pts[s.npoints - 1].xmax[2] * dir > 0);
        dyn_po_branch_free(&s);
    }
    dyn_po_branch_free(&b);
}

#ifdef DYNKIT_HAVE_LAPACK
static void test_roessler_period_doubling(void **state)
{
    (void)state;
    /* the equilibrium near the origin and its Hopf point in a (b = 0.2, c = 5.7): found by
     * bisection on the real part of the complex pair (roessler_hopf.h) */
    double a_h, x0[3] = {0}, omega = 0;
    assert_int_equal(roessler_hopf_point(&a_h, x0, &omega), 0);
    dyn_po_system sys = {3, roessler, NULL};
    dyn_po_opts o = {0};
    o.ntst = 50;
    o.ds = 0.01;
    o.dsmax = 0.05;
    o.nmax = 400;
    o.par_min = 0.0;
    o.par_max = 0.13;
    o.eig = &dyn_eig_solver_lapack;
    dyn_po_branch br;
    assert_int_equal(dyn_po_from_hopf(&sys, x0, a_h, omega, &o, &br), 0);
    const dyn_po_point *pd = NULL;
    for (int k = 0; k < br.npoints && !pd; k++)
        if (strcmp(br.pts[k].label, "PD") == 0)
            pd = &br.pts[k];
    assert_non_null(pd);
    print_message("Roessler: PD at a = %.10g, period %.10g\n", pd->par, pd->period);
    /* a multiplier at -1 (AUTO-07p's value of a is checked by tests/analysis/auto_check.py) */
    double nearest = INFINITY;
    for (int i = 1; i < 3; i++)
        nearest = fmin(nearest, hypot(pd->mult_re[i] + 1, pd->mult_im[i]));
    assert_true(nearest < 1e-6);
    assert_close(pd->mult_re[0], 1.0, 1e-7);
    dyn_po_branch b2;
    assert_int_equal(dyn_po_from_pd(&sys, pd, &o, &b2), 0);
    assert_true(b2.npoints > 3);
    assert_close(b2.pts[0].period, 2 * pd->period, 1e-3 * pd->period);
    /* a new branch: the doubled orbit's extremes differ from the original's */
    assert_true(fabs(b2.pts[b2.npoints - 1].xmax[0] - pd->xmax[0]) > 1e-2);
    dyn_po_branch_free(&b2);
    dyn_po_branch_free(&br);
}
#endif

/* y'' = -y with y(0) = 0, y(pi/2) = 1: y = sin t, y' = cos t */
static int harmonic(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    (void)par;
    dydt[0] = y[1];
    dydt[1] = -y[0];
    return 0;
}

static int sine_ends(const double *yl, const double *yr, const void *par, double *g)
{
    (void)par;
    g[0] = yl[0];
    g[1] = yr[0] - 1.0;
    return 0;
}

static void test_linear_bvp_closed_form(void **state)
{
    (void)state;
    static const dyn_var states[] = {{"y", "1", ""}, {"dy", "1", ""}};
    static const double y0[] = {0.0, 0.0};
    const dyn_model m = {.name = "sine", .n_states = 2, .states = states, .y0 = y0,
                         .rhs = harmonic, .n_bdry = 2, .bdry = sine_ends};
    const double h = 0.5 * 3.14159265358979323846;
    dyn_bvp_result r;
    const dyn_bvp_opts o = {.ntst = 20, .ncol = 4};
    assert_int_equal(dyn_bvp_solve(&m, NULL, y0, 0.0, h, &o, &r), 0);
    double err = 0.0, u[2];
    for (int k = 0; k <= 50; k++) {
        const double s = k / 50.0;
        dyn_colloc_eval(&r.sol, s, u);
        err = fmax(err, fmax(fabs(u[0] - sin(h * s)), fabs(u[1] - cos(h * s))));
    }
    print_message("sin t on [0, pi/2] from its ends: max error %.2e, estimate %.2e\n", err,
                  r.err_est);
    assert_true(err < 1e-9);
    assert_true(fabs(r.residuals[0]) < 1e-12 && fabs(r.residuals[1]) < 1e-12);
    dyn_bvp_result_free(&r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_superconvergence_order),
        cmocka_unit_test(test_floquet_multipliers),
        cmocka_unit_test(test_branch_from_hopf_normal_form),
        cmocka_unit_test(test_brusselator_period_at_onset),
        cmocka_unit_test(test_linear_bvp_closed_form),
        cmocka_unit_test(test_cycle_pitchfork_switching),
#ifdef DYNKIT_HAVE_LAPACK
        cmocka_unit_test(test_roessler_period_doubling),
#endif
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
