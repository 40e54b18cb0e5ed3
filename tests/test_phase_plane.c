/* SPDX-License-Identifier: BSD-3-Clause */
/* test_phase_plane.c — the phase plane (dynkit/phase_plane.h) against closed forms:
 * - FitzHugh–Nagumo's nullclines, the cubic w = v - v^3/3 + I and the line w = (v + a)/b:
 *   every vertex marching squares gives within 1e-12 of its curve, and the curves covered
 *   end to end (segments on the whole cubic across the window); its one equilibrium, the
 *   root of the cubic, with the eigenvalues of the closed-form Jacobian
 *   [[1 - v^2, -1], [eps, -eps b]] (an unstable focus for I = 0.5);
 * - van der Pol in Liénard's form, x' = mu (y - (x^3/3 - x)), y' = -x / mu: the nullclines
 *   y = x^3/3 - x and x = 0, the origin an unstable focus (mu = 1) and an unstable node
 *   (mu = 3, tr^2 > 4 det);
 * - the unforced double-well Duffing x'' + d x' - x + x^3 = 0: a saddle at 0 and two
 *   stable foci at +-1; the harmonic oscillator's centre; a nullcline's vertices from a
 *   Jacobian by differences (a model without one) as from the exact one;
 * - dynkit plot --phase-plane: an SVG with the nullclines, the field, the trajectories and
 *   the equilibria's legend; --html a page with the table; Lorenz's x, y plane at z = 1
 *   (examples/models/lorenz.ode) a saddle at the origin (det = sigma (2 - rho) < 0); bad
 *   input named; the examples of `dynkit plot --help` run;
 * - the maxima of a damped oscillator x'' + 2 zeta x' + x = 0 (run --section max:x): the
 *   ratio of successive ones exp(-2 pi zeta / sqrt(1 - zeta^2)) to 1e-9; plot --return-map
 *   draws one dot per pair of them and the diagonal. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <float.h>
#include <stdio.h>

#include "dynkit/dynkit.h"
#include "dynkit/phase_plane.h"
#include "test_cli_run.h"
#include "test_util.h"

typedef struct fhn_par {
    double i, eps, a, b;
} fhn_par;

static int fhn_rhs(double t, const double *y, double *f, void *par)
{
    (void)t;
    const fhn_par *p = par;
    f[0] = y[0] - y[0] * y[0] * y[0] / 3 - y[1] + p->i;
    f[1] = p->eps * (y[0] + p->a - p->b * y[1]);
    return 0;
}

static int fhn_jac(double t, const double *y, double *J, void *par)
{
    (void)t;
    const fhn_par *p = par;
    J[0] = 1 - y[0] * y[0];
    J[1] = -1;
    J[2] = p->eps;
    J[3] = -p->eps * p->b;
    return 0;
}

static const dyn_var two_states[] = {{"x", "1", ""}, {"y", "1", ""}};
static const double origin[2] = {0, 0};

static dyn_model model_of(dyn_rhs_fn rhs, dyn_jac_fn jac, size_t par_size)
{
    dyn_model m = {0};
    m.name = "test";
    m.n_states = 2;
    m.states = two_states;
    m.y0 = origin;
    m.par_size = par_size;
    m.rhs = rhs;
    m.jacobian = jac;
    return m;
}

/* the segments of one nullcline: their vertices, checked as they come */
typedef struct check {
    int which;
    double (*off)(double x, double y, const void *par); /* distance-like residual of a curve */
    const void *par;
    double worst;
    long count;
    double xmin, xmax;
} check;

static void on_segment(int which, double x0, double y0, double x1, double y1, void *ctx)
{
    check *c = ctx;
    c += which;
    c->count++;
    c->worst = fmax(c->worst, fmax(fabs(c->off(x0, y0, c->par)), fabs(c->off(x1, y1, c->par))));
    c->xmin = fmin(c->xmin, fmin(x0, x1));
    c->xmax = fmax(c->xmax, fmax(x0, x1));
}

static double fhn_cubic(double v, double w, const void *par)
{
    const fhn_par *p = par;
    return w - (v - v * v * v / 3 + p->i);
}

static double fhn_line(double v, double w, const void *par)
{
    const fhn_par *p = par;
    return w - (v + p->a) / p->b;
}

static void test_fitzhugh_nagumo(void **state)
{
    (void)state;
    fhn_par par = {0.5, 0.08, 0.7, 0.8};
    const dyn_model m = model_of(fhn_rhs, fhn_jac, sizeof par);
    const double y[2] = {0, 0};
    const dyn_plane p = {&m, &par, 0.0, y, 0, 1, -2.5, 2.5, -1.0, 2.0};
    double work[2 * 2 + 4 + 2 * 101 * 101];
    assert_true(dyn_plane_work_size(2, 100, 100) <= sizeof work / sizeof *work);
    check c[2] = {{0, fhn_cubic, &par, 0, 0, INFINITY, -INFINITY},
                  {1, fhn_line, &par, 0, 0, INFINITY, -INFINITY}};
    char err[128];
    assert_int_equal(dyn_plane_nullclines(&p, 100, 100, work, on_segment, c, err, sizeof err), 0);
    print_message("FitzHugh-Nagumo: %ld segments of the cubic (worst residual %.1e), %ld of "
                  "the line (%.1e)\n", c[0].count, c[0].worst, c[1].count, c[1].worst);
    CHECK(c[0].count > 100 && c[0].worst < 1e-12, "cubic: %ld, %g", c[0].count, c[0].worst);
    CHECK(c[1].count > 50 && c[1].worst < 1e-12, "line: %ld, %g", c[1].count, c[1].worst);
    /* the cubic leaves the window at w = 2 (v = -2.29...) and w = -1 (v = 2.13...): its
     * segments span that range to within a cell */
    CHECK(c[0].xmin < -2.2 && c[0].xmax > 2.08, "cubic over %g .. %g", c[0].xmin, c[0].xmax);
    dyn_plane_point pts[8];
    const int n = dyn_plane_equilibria(&p, 100, 100, work, pts, 8, err, sizeof err);
    CHECK(n == 1, "%d equilibria", n);
    /* the root of v - v^3/3 + I = (v + a)/b by bisection, the eigenvalues in closed form */
    double lo = -2, hi = 0;
    for (int k = 0; k < 200; k++) {
        const double mid = 0.5 * (lo + hi);
        const double g = mid - mid * mid * mid / 3 + par.i - (mid + par.a) / par.b;
        if (g > 0) /* g falls through its root */
            lo = mid;
        else
            hi = mid;
    }
    const double v = 0.5 * (lo + hi), w = (v + par.a) / par.b;
    CHECK(fabs(pts[0].x - v) < 1e-12 && fabs(pts[0].y - w) < 1e-12, "(%.17g, %.17g) vs (%.17g, "
          "%.17g)", pts[0].x, pts[0].y, v, w);
    const double tr = 1 - v * v - par.eps * par.b, det = -(1 - v * v) * par.eps * par.b + par.eps;
    const double re = tr / 2, im = sqrt(det - tr * tr / 4);
    CHECK(fabs(pts[0].re[0] - re) < 1e-12 && fabs(pts[0].im[1] - im) < 1e-12,
          "%g%+gi vs %g%+gi", pts[0].re[0], pts[0].im[1], re, im);
    CHECK(pts[0].type == DYN_PLANE_UNSTABLE_FOCUS, "%s", dyn_plane_point_name(pts[0].type));
}

typedef struct mu_par {
    double mu;
} mu_par;

static int lienard_rhs(double t, const double *y, double *f, void *par)
{
    (void)t;
    const double mu = ((const mu_par *)par)->mu;
    f[0] = mu * (y[1] - (y[0] * y[0] * y[0] / 3 - y[0]));
    f[1] = -y[0] / mu;
    return 0;
}

static double lienard_cubic(double x, double y, const void *par)
{
    (void)par;
    return y - (x * x * x / 3 - x);
}

static double lienard_axis(double x, double y, const void *par)
{
    (void)y;
    (void)par;
    return x;
}

static void test_van_der_pol_lienard(void **state)
{
    (void)state;
    mu_par par = {1.0};
    const dyn_model m = model_of(lienard_rhs, NULL, sizeof par); /* Jacobian by differences */
    const double y[2] = {0, 0};
    /* a window not symmetric about x = 0, so that the axis is not a grid line */
    const dyn_plane p = {&m, &par, 0.0, y, 0, 1, -2.7, 2.9, -3.1, 3.3};
    double work[2 * 2 + 4 + 2 * 81 * 81];
    check c[2] = {{0, lienard_cubic, NULL, 0, 0, INFINITY, -INFINITY},
                  {1, lienard_axis, NULL, 0, 0, INFINITY, -INFINITY}};
    char err[128];
    assert_int_equal(dyn_plane_nullclines(&p, 80, 80, work, on_segment, c, err, sizeof err), 0);
    print_message("van der Pol (Lienard): y = x^3/3 - x within %.1e (%ld segments), x = 0 "
                  "within %.1e (%ld)\n", c[0].worst, c[0].count, c[1].worst, c[1].count);
    CHECK(c[0].count > 80 && c[0].worst < 1e-12, "%ld %g", c[0].count, c[0].worst);
    CHECK(c[1].count == 80 && c[1].worst < 1e-15, "%ld %g", c[1].count, c[1].worst);
    dyn_plane_point pts[4];
    int n = dyn_plane_equilibria(&p, 80, 80, work, pts, 4, err, sizeof err);
    CHECK(n == 1 && fabs(pts[0].x) < 1e-12 && fabs(pts[0].y) < 1e-12, "%d", n);
    /* J = [[mu, mu], [-1/mu, 0]]: tr = mu, det = 1 */
    CHECK(pts[0].type == DYN_PLANE_UNSTABLE_FOCUS && fabs(pts[0].re[0] - 0.5) < 1e-7 &&
              fabs(pts[0].im[1] - sqrt(0.75)) < 1e-7,
          "%s %g %g", dyn_plane_point_name(pts[0].type), pts[0].re[0], pts[0].im[1]);
    par.mu = 3.0; /* tr^2 = 9 > 4: a node, eigenvalues (3 +- sqrt 5)/2 */
    n = dyn_plane_equilibria(&p, 80, 80, work, pts, 4, err, sizeof err);
    CHECK(n == 1 && pts[0].type == DYN_PLANE_UNSTABLE_NODE &&
              fabs(pts[0].re[0] - (3 - sqrt(5.0)) / 2) < 1e-6 &&
              fabs(pts[0].re[1] - (3 + sqrt(5.0)) / 2) < 1e-6,
          "%d %s %g %g", n, n > 0 ? dyn_plane_point_name(pts[0].type) : "", pts[0].re[0],
          pts[0].re[1]);
}

typedef struct duffing_par {
    double d, k;
} duffing_par;

static int duffing_rhs(double t, const double *y, double *f, void *par)
{
    (void)t;
    const duffing_par *p = par;
    f[0] = y[1];
    f[1] = -p->d * y[1] + p->k * (y[0] - y[0] * y[0] * y[0]) - (1 - p->k) * y[0];
    return 0;
}

static void test_types(void **state)
{
    (void)state;
    duffing_par par = {0.25, 1.0};
    const dyn_model m = model_of(duffing_rhs, NULL, sizeof par);
    const double y[2] = {0, 0};
    const dyn_plane p = {&m, &par, 0.0, y, 0, 1, -1.7, 1.6, -1.1, 1.2};
    double work[2 * 2 + 4 + 2 * 61 * 61];
    char err[128];
    dyn_plane_point pts[8];
    int n = dyn_plane_equilibria(&p, 60, 60, work, pts, 8, err, sizeof err);
    CHECK(n == 3, "%d equilibria", n);
    if (n == 3) {
        CHECK(fabs(pts[0].x + 1) < 1e-12 && pts[0].type == DYN_PLANE_STABLE_FOCUS, "%g %s",
              pts[0].x, dyn_plane_point_name(pts[0].type));
        CHECK(fabs(pts[1].x) < 1e-12 && pts[1].type == DYN_PLANE_SADDLE &&
                  fabs(pts[1].re[1] - (-0.125 + sqrt(0.015625 + 1))) < 1e-7,
              "%g %s %g", pts[1].x, dyn_plane_point_name(pts[1].type), pts[1].re[1]);
        CHECK(fabs(pts[2].x - 1) < 1e-12 && pts[2].type == DYN_PLANE_STABLE_FOCUS, "%g %s",
              pts[2].x, dyn_plane_point_name(pts[2].type));
    }
    /* the harmonic oscillator (k = 0, no damping): a centre */
    par.d = 0.0;
    par.k = 0.0;
    n = dyn_plane_equilibria(&p, 60, 60, work, pts, 8, err, sizeof err);
    CHECK(n == 1 && pts[0].type == DYN_PLANE_CENTER, "%d %s", n,
          n > 0 ? dyn_plane_point_name(pts[0].type) : "");
    /* bad input named */
    const dyn_plane bad = {&m, &par, 0.0, y, 0, 0, -1, 1, -1, 1};
    CHECK(dyn_plane_equilibria(&bad, 10, 10, work, pts, 8, err, sizeof err) < 0 &&
              strstr(err, "two different states"), "%s", err);
    const dyn_plane flat = {&m, &par, 0.0, y, 0, 1, 1, 1, -1, 1};
    CHECK(dyn_plane_nullclines(&flat, 10, 10, work, on_segment, NULL, err, sizeof err) < 0 &&
              strstr(err, "lo < hi"), "%s", err);
}

static void test_cli_phase_plane(void **state)
{
    (void)state;
    cli_write_file("fhn.ode", "v'=v-v^3/3-w+i\nw'=eps*(v+a-b*w)\npar i=0.5,eps=0.08,a=0.7,b=0.8\n"
                          "init v=-1,w=1\n@ total=50,xp=v,yp=w,xlo=-2.5,xhi=2.5,ylo=-1,yhi=2\n"
                          "done\n");
    cli_result r = cli_in_tmpdir("plot fhn.ode --phase-plane --start v=2,w=0 -o fhn.svg");
    CHECK(r.status == 0, "%s", r.err);
    char *svg = cli_read_file(cli_path("fhn.svg"), NULL);
    CHECK(svg && strstr(svg, "<svg") && strstr(svg, "</svg>") && strstr(svg, ">v&#39; = 0<") &&
              strstr(svg, ">w&#39; = 0<") && strstr(svg, ">direction field<") &&
              strstr(svg, ">trajectories (2)<") && strstr(svg, ">unstable focus (1)<"),
          "%.300s", svg ? svg : "(none)");
    free(svg);
    cli_free(&r);
    r = cli_in_tmpdir("plot fhn.ode --phase-plane --html fhn.html");
    CHECK(r.status == 0, "%s", r.err);
    char *page = cli_read_file(cli_path("fhn.html"), NULL);
    CHECK(page && strstr(page, "\"kind\":\"phase\"") && strstr(page, "\"type\":\"unstable focus\"") &&
              strstr(page, "trajectories (10)"),
          "%.300s", page ? page : "(none)");
    free(page);
    cli_free(&r);
    cli_write_file("three.ode", "x'=y\ny'=z\nz'=-x\ndone\n");
    r = cli_in_tmpdir("plot three.ode --phase-plane -o -");
    CHECK(r.status == 2 && strstr(r.err, "name the plane with --x NAME --y NAME"), "%s", r.err);
    cli_free(&r);
    r = cli("plot vanderpol --phase-plane --start y1=abc -o -");
    CHECK(r.status == 2 && strstr(r.err, "give y1=VALUE,y2=VALUE"), "%s", r.err);
    cli_free(&r);
    r = cli("plot " DYNKIT_SOURCE_DIR "/examples/models/lorenz.ode --phase-plane --x x --y y --grid 40 -o -");
    CHECK(r.status == 0 && strstr(r.out, "saddle (1)"), "%s", r.err);
    cli_free(&r);
    unlink(cli_path("fhn.ode"));
    unlink(cli_path("three.ode"));
    unlink(cli_path("fhn.svg"));
    unlink(cli_path("fhn.html"));
}

/* The phase-plane and section examples of `dynkit plot --help` run (examples/ from the
 * source tree). */
static void test_help_examples(void **state)
{
    (void)state;
    cli_result h = cli("plot --help");
    CHECK(h.status == 0 && strstr(h.out, "--phase-plane"), "%s", h.err);
    int ran = 0;
    for (char *line = h.out; line && *line;) {
        char *end = strchr(line, '\n');
        if (end)
            *end = '\0';
        const char *cmd = strstr(line, "dynkit plot examples/");
        if (cmd && (strstr(cmd, "--phase-plane") || strstr(cmd, "--section"))) {
            char args[1024];
            const char *rest = cmd + strlen("dynkit plot ");
            snprintf(args, sizeof args, "plot %s/%s", DYNKIT_SOURCE_DIR, rest);
            cli_result r = cli_in_tmpdir("%s", args);
            CHECK(r.status == 0, "%s: %s", args, r.err);
            cli_free(&r);
            ran++;
        }
        line = end ? end + 1 : NULL;
    }
    CHECK(ran == 4, "%d examples", ran);
    cli_free(&h);
}

static void test_return_map(void **state)
{
    (void)state;
    const double zeta = 0.05;
    cli_write_file("damped.ode", "x'=v\nv'=-2*zeta*v-x\npar zeta=0.05\ninit x=1,v=0\n"
                                 "@ total=100\ndone\n");
    cli_result r = cli_in_tmpdir("run damped.ode --section max:x --rtol 1e-12 --atol 1e-14");
    CHECK(r.status == 0, "%s", r.err);
    double x[64];
    int n = 0;
    for (char *line = strchr(r.out, '\n'); line && n < 64; line = strchr(line + 1, '\n')) {
        double t, xv, vv;
        if (sscanf(line + 1, "%lf,%lf,%lf", &t, &xv, &vv) == 3)
            x[n++] = xv;
    }
    const double ratio = exp(-2 * DYN_PI * zeta / sqrt(1 - zeta * zeta));
    double worst = 0;
    for (int k = 0; k + 1 < n; k++)
        worst = fmax(worst, fabs(x[k + 1] / x[k] - ratio));
    print_message("damped oscillator: %d maxima, successive ratios within %.1e of %.12f\n", n,
                  worst, ratio);
    CHECK(n == 15 && worst < 1e-9, "%d maxima, %g", n, worst);
    cli_free(&r);
    r = cli_in_tmpdir("plot damped.ode --section max:x --y x --return-map -o map.svg");
    CHECK(r.status == 0, "%s", r.err);
    char *svg = cli_read_file(cli_path("map.svg"), NULL);
    long dots = 0;
    for (const char *p = svg; p && (p = strstr(p, "h0")) != NULL; p += 2)
        dots++;
    /* the dots of the crossings' pairs and three in the legend's sample */
    CHECK(svg && strstr(svg, ">crossings<") && strstr(svg, ">diagonal<") &&
              strstr(svg, ">x_n+1<") && dots == (n - 1) + 3,
          "%ld dots for %d maxima", dots, n);
    free(svg);
    cli_free(&r);
    r = cli_in_tmpdir("plot damped.ode --y x --return-map -o map.svg");
    CHECK(r.status == 2 && strstr(r.err, "give --section SPEC"), "%s", r.err);
    cli_free(&r);
    unlink(cli_path("damped.ode"));
    unlink(cli_path("map.svg"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fitzhugh_nagumo),
        cmocka_unit_test(test_van_der_pol_lienard),
        cmocka_unit_test(test_types),
        cmocka_unit_test(test_cli_phase_plane),
        cmocka_unit_test(test_help_examples),
        cmocka_unit_test(test_return_map),
    };
    return cmocka_run_group_tests(tests, cli_setup, cli_remove_tmpdir);
}
