/* SPDX-License-Identifier: BSD-3-Clause */
/* test_mechanisms.c — mechanism files (src/mbs, docs/mechanisms.md) against independent
 * answers: the double pendulum's hand-derived Lagrange equations at random states (1e-12),
 * its energy over 100 s; the plane of examples/mechanisms against the hand-written built-in
 * plane (centre of mass and Euler angles within 1e-8 over 5 s at rtol = atol = 1e-12); the
 * heavy symmetric top's steady precession at the closed-form rates, and its sleeping
 * stability limit and eigenvalues by linearization; the rolling disk's critical speed and
 * eigenvalues, and its energy; the wheel statement on a disk with a free centre against it;
 * the four-bar loop kept closed over 100 s with its energy; the cart against the built-in
 * cart; a prescribed motion's driving torque by hand; and errors at FILE:LINE:COL. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>

#include "dynkit/dynkit.h"
#include "dynkit/jit.h"
#include "dynkit/mbs.h"
#include "test_cli_run.h"
#include "test_util.h"
#include "test_mech_util.h"

#define MECH DYNKIT_SOURCE_DIR "/examples/mechanisms/"

static char cache_dir[512];

static int setup_all(void **state)
{
    (void)state;
    return cli_make_tmpdir_with_cache("mechanisms", cache_dir, sizeof cache_dir);
}

static double compare_runs(const char *a_args, const char *b_args, const char *const *names,
                           int count);

typedef struct loaded {
    dyn_jit_model jm;
    const dyn_model *m;
    double par[4096];
} loaded;

static void load_file(const char *path, loaded *L)
{
    size_t len;
    char *text = cli_read_file(path, &len);
    char *c_src = NULL;
    dyn_lang_diag d;
    char buf[4096];
    const int rc = dyn_mech_to_c(path, text, len, NULL, 0, &c_src, &d, NULL, NULL);
    free(text);
    CHECK(rc == 0, "%s", dyn_lang_diag_format(&d, buf, sizeof buf));
    dyn_jit_opts opts = {0};
    opts.cache_dir = cache_dir;
    char err[4096];
    CHECK(dyn_jit_load_source(c_src, strlen(c_src), path, &opts, &L->jm, err, sizeof err) == 0,
          "%s", err);
    free(c_src);
    L->m = L->jm.model;
    assert_true(L->m->par_size <= sizeof L->par);
    memset(L->par, 0, sizeof L->par);
    char perr[256];
    CHECK(dyn_model_default_params(L->m, L->par, perr, sizeof perr) == 0, "%s", perr);
}

static void set(loaded *L, const char *name, double v)
{
    const int i = dyn_model_param_index(L->m, name);
    CHECK(i >= 0, "no parameter %s", name);
    dyn_model_set_param(L->m, L->par, i, v);
}

static int state(const loaded *L, const char *name)
{
    const int i = dyn_model_state_index(L->m, name);
    CHECK(i >= 0, "no state %s", name);
    return i;
}

static double urand(uint64_t *s, double lo, double hi)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return lo + (hi - lo) * (double)(*s >> 11) / 9007199254740992.0;
}

/* Lagrange's equations of the double pendulum by hand (angles from the downward vertical):
 *   (m1+m2) l1^2 a1 + m2 l1 l2 cos(d) a2 = -m2 l1 l2 w2^2 sin(d) - (m1+m2) g l1 sin(p1)
 *   m2 l1 l2 cos(d) a1 + m2 l2^2 a2      =  m2 l1 l2 w1^2 sin(d) - m2 g l2 sin(p2),
 * d = p1 - p2, solved by Cramer's rule. */
static void test_double_pendulum_matches_hand_derivation(void **state_)
{
    (void)state_;
    loaded L;
    load_file(MECH "double_pendulum.mech", &L);
    const int ip1 = state(&L, "phi1"), ip2 = state(&L, "phi2"), iw1 = state(&L, "dphi1"),
              iw2 = state(&L, "dphi2");
    uint64_t seed = 12345;
    double worst = 0.0;
    for (int trial = 0; trial < 200; trial++) {
        const double m1 = urand(&seed, 0.1, 3), m2 = urand(&seed, 0.1, 3),
                     l1 = urand(&seed, 0.2, 2), l2 = urand(&seed, 0.2, 2),
                     g = urand(&seed, 1, 20);
        set(&L, "m1", m1);
        set(&L, "m2", m2);
        set(&L, "l1", l1);
        set(&L, "l2", l2);
        set(&L, "g", g);
        double y[4], f[4];
        y[ip1] = urand(&seed, -4, 4);
        y[ip2] = urand(&seed, -4, 4);
        y[iw1] = urand(&seed, -5, 5);
        y[iw2] = urand(&seed, -5, 5);
        assert_int_equal(L.m->rhs(0.0, y, f, L.par), 0);
        const double d = y[ip1] - y[ip2], w1 = y[iw1], w2 = y[iw2];
        const double a11 = (m1 + m2) * l1 * l1, a12 = m2 * l1 * l2 * cos(d), a22 = m2 * l2 * l2;
        const double b1 = -m2 * l1 * l2 * w2 * w2 * sin(d) - (m1 + m2) * g * l1 * sin(y[ip1]);
        const double b2 = m2 * l1 * l2 * w1 * w1 * sin(d) - m2 * g * l2 * sin(y[ip2]);
        const double det = a11 * a22 - a12 * a12;
        const double acc1 = (b1 * a22 - a12 * b2) / det, acc2 = (a11 * b2 - a12 * b1) / det;
        const double scale = fabs(acc1) + fabs(acc2) + g / fmin(l1, l2);
        worst = fmax(worst, fmax(fabs(f[iw1] - acc1), fabs(f[iw2] - acc2)) / scale);
        CHECK(f[ip1] == w1 && f[ip2] == w2, "the coordinates' rates are the speeds");
    }
    CHECK(worst < 1e-12, "worst relative difference %.3g", worst);
    dyn_jit_unload(&L.jm);
}

/* The numbers of a CSV text (header skipped): returns the rows, columns in *cols. */
static long csv_table(const char *text, double *v, long max, int *cols)
{
    const char *p = strchr(text, '\n');
    long k = 0;
    *cols = 1;
    for (const char *h = text; h < p; h++)
        *cols += *h == ',';
    while (p && *p && k < max) {
        char *end;
        p++;
        const double x = strtod(p, &end);
        if (end == p)
            break;
        v[k++] = x;
        p = end;
    }
    return k / *cols;
}

static double column_spread(const double *v, long rows, int cols, int j, double *first)
{
    double lo = INFINITY, hi = -INFINITY;
    for (long r = 0; r < rows; r++) {
        lo = fmin(lo, v[r * cols + j]);
        hi = fmax(hi, v[r * cols + j]);
    }
    if (first)
        *first = v[j];
    return hi - lo;
}

static void test_double_pendulum_keeps_its_energy(void **state_)
{
    (void)state_;
    static double v[1 << 16];
    cli_result r = cli("run %sdouble_pendulum.mech --outputs --method dop853 --rtol 1e-12 "
                       "--atol 1e-12 --tspan 0:100 --step 1", MECH);
    CHECK(r.status == 0, "%s", r.err);
    int cols;
    const long rows = csv_table(r.out, v, 1 << 16, &cols);
    CHECK(rows == 101 && cols == 8, "rows %ld cols %d", rows, cols);
    double e0;
    const double spread = column_spread(v, rows, cols, 7, &e0);
    CHECK(fabs(e0 + 9.81) < 1e-12, "energy at the start %.17g (potential -m1 g l1 - ...)", e0);
    CHECK(spread < 1e-8 * 9.81, "energy changed by %.3g J over 100 s", spread);
    cli_free(&r);
}

static void test_plane_matches_the_builtin_plane(void **state_)
{
    (void)state_;
    static double a[1 << 16], b[1 << 16];
    const char *opts = "--method dop853 --rtol 1e-12 --atol 1e-12 --tspan 0:5 --step 0.05";
    cli_result ra = cli("run %splane.mech %s", MECH, opts), rb = cli("run plane %s", opts);
    CHECK(ra.status == 0 && rb.status == 0, "%s %s", ra.err, rb.err);
    /* the same column names first: t, sX, sY, sZ, psi, theta, phi */
    CHECK(strncmp(ra.out, "t,sX,sY,sZ,psi,theta,phi,", 25) == 0, "%.60s", ra.out);
    CHECK(strncmp(rb.out, "t,sX,sY,sZ,psi,theta,phi,", 25) == 0, "%.60s", rb.out);
    int ca, cb;
    const long na = csv_table(ra.out, a, 1 << 16, &ca), nb = csv_table(rb.out, b, 1 << 16, &cb);
    CHECK(na == nb && na == 101, "rows %ld %ld", na, nb);
    double worst = 0.0;
    for (long r = 0; r < na; r++)
        for (int j = 0; j < 7; j++)
            worst = fmax(worst, fabs(a[r * ca + j] - b[r * cb + j]));
    CHECK(worst < 1e-8, "largest difference %.3g", worst);
    cli_free(&ra);
    cli_free(&rb);
}

/* The plane with Euler parameters (their norm a constraint; M + D'D, as M is singular along
 * the parameters' radial direction) against the built-in plane-quat. */
static void test_plane_quat_matches_the_builtin_plane_quat(void **state_)
{
    (void)state_;
    static const char *const names[] = {"sX", "sY", "sZ", "qw", "qx", "qy", "qz"};
    char a[1024], b[1024];
    const char *opts = "--method dop853 --rtol 1e-12 --atol 1e-12 --tspan 0:5 --step 0.05";
    snprintf(a, sizeof a, "%splane_quat.mech %s", MECH, opts);
    snprintf(b, sizeof b, "plane-quat %s", opts);
    const double worst = compare_runs(a, b, names, 7);
    CHECK(worst < 1e-8, "largest difference %.3g", worst);
}

/* Steady precession of a heavy symmetric top at nutation theta with spin w3 = dphi + dpsi
 * cos(theta): m g L = Omega (C w3 - A' Omega cos(theta)), A' = A + m L^2 the transverse
 * inertia about the tip (Goldstein, Classical Mechanics, 5.7): both roots. */
static void test_top_precesses_at_the_closed_form_rates(void **state_)
{
    (void)state_;
    loaded L;
    load_file(MECH "top.mech", &L);
    const double m = 1, Lc = 0.1, A = 0.002, C = 0.004, g = 9.81;
    const double Ap = A + m * Lc * Lc;
    for (int k = 0; k < 6; k++) {
        const double th = 0.3 + 0.2 * k, w3 = 60 + 20 * k;
        const double disc = C * C * w3 * w3 - 4 * Ap * cos(th) * m * g * Lc;
        assert_true(disc > 0);
        for (int root = -1; root <= 1; root += 2) {
            const double Om = (C * w3 + root * sqrt(disc)) / (2 * Ap * cos(th));
            double y[6], f[6];
            y[state(&L, "psi")] = 0.7;
            y[state(&L, "theta")] = th;
            y[state(&L, "phi")] = -0.4;
            y[state(&L, "dpsi")] = Om;
            y[state(&L, "dtheta")] = 0;
            y[state(&L, "dphi")] = w3 - Om * cos(th);
            assert_int_equal(L.m->rhs(0.0, y, f, L.par), 0);
            const double scale = m * g * Lc / Ap;
            for (int i = 3; i < 6; i++)
                CHECK(fabs(f[i]) < 1e-12 * scale + 1e-13 * Om * w3, "theta %g w3 %g root %d: "
                      "acceleration %d is %.3g", th, w3, root, i, f[i]);
            /* off the closed-form rate the top nods */
            y[state(&L, "dpsi")] = Om * 1.01;
            y[state(&L, "dphi")] = w3 - 1.01 * Om * cos(th);
            assert_int_equal(L.m->rhs(0.0, y, f, L.par), 0);
            CHECK(fabs(f[state(&L, "dtheta")]) > 1e-4 * scale, "no nodding off steady");
        }
    }
    dyn_jit_unload(&L.jm);
}

/* The sleeping top (upright, spinning at W): linearized, lambda = i (C W +- sqrt(C^2 W^2 -
 * 4 A' m g L)) / (2 A') (Goldstein 5.7), stable above W = 2 sqrt(A' m g L) / C; the spin
 * angle and its rate give two zeros. */
static void test_sleeping_top_is_stable_above_the_closed_form_spin(void **state_)
{
    (void)state_;
    const double m = 1, Lc = 0.1, A = 0.002, C = 0.004, g = 9.81, Ap = A + m * Lc * Lc;
    const double Wc = 2 * sqrt(Ap * m * g * Lc) / C;
    const double W[4] = {0.9 * Wc, 0.99 * Wc, 1.01 * Wc, 1.5 * Wc};
    for (int k = 0; k < 4; k++) {
        cli_result r = cli("linearize %ssleeping_top.mech --init dphi=%.17g -o %s", MECH, W[k],
                           cli_path("eig.csv"));
        CHECK(r.status == 0, "%s", r.err);
        cli_free(&r);
        char *csv = cli_read_file(cli_path("eig.csv"), NULL);
        static double v[64];
        int cols;
        const long rows = csv_table(csv, v, 64, &cols);
        free(csv);
        CHECK(rows == 6 && cols == 2, "rows %ld cols %d", rows, cols);
        const double disc = C * C * W[k] * W[k] - 4 * Ap * m * g * Lc;
        double want_re = 0, want_im[2];
        if (disc < 0) {
            want_re = sqrt(-disc) / (2 * Ap);
            want_im[0] = want_im[1] = C * W[k] / (2 * Ap);
        } else {
            want_im[0] = (C * W[k] + sqrt(disc)) / (2 * Ap);
            want_im[1] = (C * W[k] - sqrt(disc)) / (2 * Ap);
        }
        int zeros = 0, matched = 0;
        for (long i = 0; i < rows; i++) {
            const double re = v[2 * i], im = v[2 * i + 1];
            if (fabs(re) < 1e-9 && fabs(im) < 1e-9) {
                zeros++;
                continue;
            }
            for (int j = 0; j < 2; j++)
                if (fabs(fabs(re) - want_re) < 1e-7 * want_im[0] &&
                    fabs(fabs(im) - want_im[j]) < 1e-7 * want_im[0]) {
                    matched++;
                    break;
                }
        }
        CHECK(zeros == 2 && matched == 4, "W = %g (Wc %g): %d zeros, %d of 4 eigenvalues match",
              W[k], Wc, zeros, matched);
    }
}

/* Eigenvalues of a linearization (-o FILE.csv, columns re,im) into v; returns the count. */
static long eigenvalues(const char *args, double *v, long max)
{
    cli_result r = cli("linearize %s -o %s", args, cli_path("eig.csv"));
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    char *csv = cli_read_file(cli_path("eig.csv"), NULL);
    int cols;
    const long rows = csv_table(csv, v, 2 * max, &cols);
    free(csv);
    CHECK(cols == 2, "columns %d", cols);
    return rows;
}

/* The upright rolling disk (two constraints on the speeds): its lean obeys
 * (A + m r^2) theta'' = (m g r - W^2 C (C + m r^2) / A) theta (Neimark and Fufaev,
 * Dynamics of Nonholonomic Systems), stable above W^2 = m g r A / (C (C + m r^2)), g/(3 r)
 * for a thin disk; the other six eigenvalues of its eight minimal coordinates and speeds
 * (dx and dy eliminated by the rolling constraints) are 0. Its energy is kept while it
 * rolls. */
static void test_rolling_disk_is_stable_above_the_closed_form_speed(void **state_)
{
    (void)state_;
    const double m = 1, r = 0.3, g = 9.81, A = m * r * r / 4, C = m * r * r / 2;
    const double Wc = sqrt(m * g * r * A / (C * (C + m * r * r)));
    const double W[4] = {0.9 * Wc, 0.99 * Wc, 1.01 * Wc, 3 * Wc};
    for (int k = 0; k < 4; k++) {
        static double v[64];
        char args[512];
        snprintf(args, sizeof args, "%srolling_disk.mech --set W=%.17g", MECH, W[k]);
        const long rows = eigenvalues(args, v, 32);
        CHECK(rows == 8, "rows %ld", rows);
        const double l2 = (m * g * r - W[k] * W[k] * C * (C + m * r * r) / A) / (A + m * r * r);
        const double want = sqrt(fabs(l2));
        int zeros = 0, matched = 0;
        for (long i = 0; i < rows; i++) {
            const double re = v[2 * i], im = v[2 * i + 1];
            if (fabs(re) < 1e-9 && fabs(im) < 1e-9)
                zeros++;
            else if (fabs(fabs(l2 > 0 ? re : im) - want) < 1e-7 * want &&
                     fabs(l2 > 0 ? im : re) < 1e-9)
                matched++;
        }
        CHECK(zeros == 6 && matched == 2, "W = %g (Wc %g): %d zeros, %d of 2 match %g", W[k],
              Wc, zeros, matched, want);
    }
    static double v[1 << 14];
    cli_result run = cli("run %srolling_disk.mech --init theta=0.2 --outputs --method dop853 "
                         "--rtol 1e-12 --atol 1e-12 --tspan 0:20 --step 0.5", MECH);
    CHECK(run.status == 0, "%s", run.err);
    int cols;
    const long rows = csv_table(run.out, v, 1 << 14, &cols);
    CHECK(rows == 41, "rows %ld", rows);
    double e0;
    const double spread = column_spread(v, rows, cols, cols - 1, &e0);
    CHECK(spread < 1e-9 * e0, "energy changed by %.3g J of %.3g", spread, e0);
    cli_free(&run);
}

/* The square of the rolling disk's lean eigenvalue at spin W: the eigenvalue of largest
 * modulus l of its linearization, l^2 = re^2 - im^2 (positive while the lean diverges,
 * negative while it oscillates). */
static double disk_lean_square(double W)
{
    static double v[64];
    char args[512];
    snprintf(args, sizeof args, "%srolling_disk.mech --set W=%.17g", MECH, W);
    const long rows = eigenvalues(args, v, 32);
    long k = 0;
    for (long i = 1; i < rows; i++)
        if (hypot(v[2 * i], v[2 * i + 1]) > hypot(v[2 * k], v[2 * k + 1]))
            k = i;
    return v[2 * k] * v[2 * k] - v[2 * k + 1] * v[2 * k + 1];
}

/* The speed at which the lean's real part reaches zero, found by the secant method on
 * l^2(W^2) from linearizations alone, is the closed form's W^2 = g / (3 r). */
static void test_rolling_disk_critical_speed_by_root_finding(void **state_)
{
    (void)state_;
    const double r = 0.3, g = 9.81, Wc = sqrt(g / (3 * r));
    double a = 0.5 * Wc * Wc, b = 2 * Wc * Wc;
    double fa = disk_lean_square(sqrt(a)), fb = disk_lean_square(sqrt(b));
    CHECK(fa > 0 && fb < 0, "no change of sign: %g %g", fa, fb);
    for (int it = 0; it < 4 && fb != fa; it++) {
        const double c = b - fb * (b - a) / (fb - fa);
        a = b;
        fa = fb;
        b = c;
        fb = disk_lean_square(sqrt(b));
    }
    CHECK(fabs(sqrt(b) - Wc) < 1e-9 * Wc, "critical spin %.17g, closed form %.17g", sqrt(b), Wc);
}

/* Steady turning: the disk leaning by theta, its heading turning at Omega and its spin
 * phi' keep their values when (C + m r^2) Omega w3 cos(theta) - A Omega^2 sin(theta)
 * cos(theta) + m g r sin(theta) = 0, w3 = phi' + Omega sin(theta) the angular velocity
 * along the axle (the moment of momentum about the mass centre, Neimark and Fufaev,
 * Dynamics of Nonholonomic Systems, ch. 1; O'Reilly, Nonlinear Dyn. 10 (1996) 287); the
 * contact point then runs on a circle of radius r |phi'| / Omega. A spin 1% off the
 * relation makes the lean wander by more than 1e-4. */
static void test_rolling_disk_keeps_a_steady_turn(void **state_)
{
    (void)state_;
    const double m = 1, r = 0.3, g = 9.81, A = m * r * r / 4, C = m * r * r / 2;
    const double theta[3] = {0.3, -0.6, 1.0}, Omega[3] = {2, 5, -1.5};
    for (int k = 0; k < 6; k++) {
        const double th = theta[k % 3], Om = Omega[k % 3];
        const double w3 = (A * Om * Om * sin(th) * cos(th) - m * g * r * sin(th)) /
                          ((C + m * r * r) * Om * cos(th));
        const double dphi = (w3 - Om * sin(th)) * (k < 3 ? 1.0 : 1.01);
        static double v[1 << 14];
        cli_result run = cli("run %srolling_disk.mech --init theta=%.17g --init dpsi=%.17g "
                             "--init dphi=%.17g --init dx=%.17g --init dy=0 --method dop853 "
                             "--rtol 1e-12 --atol 1e-12 --tspan 0:10 --step 0.1",
                             MECH, th, Om, dphi, r * dphi);
        CHECK(run.status == 0, "%s", run.err);
        int cols;
        const long rows = csv_table(run.out, v, 1 << 14, &cols);
        cli_free(&run);
        CHECK(rows == 101, "rows %ld", rows);
        const double lean = column_spread(v, rows, cols, 4, NULL);
        double rmax = 0, rmin = 1e300; /* distance of the contact point from the centre */
        const double cx = 0, cy = r * dphi / Om;
        for (long i = 0; i < rows; i++) {
            const double d = hypot(v[i * cols + 1] - cx, v[i * cols + 2] - cy);
            rmax = fmax(rmax, d);
            rmin = fmin(rmin, d);
        }
        if (k < 3)
            CHECK(lean < 1e-10 && rmax - rmin < 1e-9 && fabs(rmax - fabs(r * dphi / Om)) < 1e-9,
                  "theta %g, Omega %g: lean varied by %.3g, radius %.12g to %.12g", th, Om,
                  lean, rmin, rmax);
        else
            CHECK(lean > 1e-4, "theta %g, Omega %g, spin off by 1%%: lean varied by %.3g only",
                  th, Om, lean);
    }
}

/* The wheel statement on a disk whose centre is free (tests/mbs/rolling_disk_centre.mech):
 * it adds the contact's height to the rolling constraints, and the disk in a steady turn
 * moves as the disk of rolling_disk.mech, whose coordinates keep it on the ground (the
 * contact point x = xc - r sin(theta) sin(psi), y = yc + r sin(theta) cos(psi), and the
 * forces of rolling, within 1e-9), while its normal force roll_z carries the weight m g
 * (the centre does not rise or fall). */
static void test_wheel_on_a_free_disk_carries_its_weight(void **state_)
{
    (void)state_;
    const double m = 1, r = 0.3, g = 9.81, A = m * r * r / 4, C = m * r * r / 2;
    const double th = 0.3, Om = 2;
    const double w3 = (A * Om * Om * sin(th) * cos(th) - m * g * r * sin(th)) /
                      ((C + m * r * r) * Om * cos(th));
    const double dphi = w3 - Om * sin(th);
    static double a[1 << 14], b[1 << 14];
    cli_result ra = cli("run %srolling_disk.mech --init theta=%.17g --init dpsi=%.17g "
                        "--init dphi=%.17g --init dx=%.17g --init dy=0 --outputs --method dop853 "
                        "--rtol 1e-12 --atol 1e-12 --tspan 0:10 --step 0.5",
                        MECH, th, Om, dphi, r * dphi);
    cli_result rb = cli("run " DYNKIT_SOURCE_DIR "/tests/mbs/rolling_disk_centre.mech "
                        "--init theta=%.17g --init zc=%.17g --init yc=%.17g --init dpsi=%.17g "
                        "--init dphi=%.17g --init dxc=%.17g --outputs --method dop853 "
                        "--rtol 1e-12 --atol 1e-12 --tspan 0:10 --step 0.5",
                        th, r * cos(th), -r * sin(th), Om, dphi, r * dphi + r * sin(th) * Om);
    CHECK(ra.status == 0 && rb.status == 0, "%s\n%s", ra.err, rb.err);
    int ca, cb;
    const long na = csv_table(ra.out, a, 1 << 14, &ca), nb = csv_table(rb.out, b, 1 << 14, &cb);
    cli_free(&ra);
    cli_free(&rb);
    CHECK(na == 21 && nb == 21 && ca == 16 && cb == 19, "rows %ld %ld, columns %d %d", na, nb,
          ca, cb);
    double dx = 0, dforce = 0, dweight = 0;
    for (long i = 0; i < na; i++) {
        const double *p = a + i * ca, *q = b + i * cb;
        const double psi = q[4], lean = q[5];
        dx = fmax(dx, fabs(q[1] - r * sin(lean) * sin(psi) - p[1]));
        dx = fmax(dx, fabs(q[2] + r * sin(lean) * cos(psi) - p[2]));
        dforce = fmax(dforce, fmax(fabs(q[13] - p[11]), fabs(q[14] - p[12])));
        dweight = fmax(dweight, fabs(q[18] - m * g));
    }
    CHECK(dx < 1e-9 && dforce < 1e-9 && dweight < 1e-9,
          "contact point %.3g m, rolling forces %.3g N, normal force - m g %.3g N apart", dx,
          dforce, dweight);
}

/* A pendulum on a freely rolling cart: about phi = 0 it swings at sqrt(g (mc + mb) / (mc l))
 * (the cart's and the bob's motions opposite), the cart's position and speed give two zeros;
 * the common centre of mass stays where it is (no horizontal force). */
static void test_cart_pendulum_frequency_and_centre_of_mass(void **state_)
{
    (void)state_;
    static double v[1 << 14];
    char args[512];
    snprintf(args, sizeof args, "%scart_pendulum.mech --init phi=0", MECH);
    const long n = eigenvalues(args, v, 16);
    CHECK(n == 4, "rows %ld", n);
    const double w = sqrt(9.81 * 2.5 / (2 * 0.8));
    int zeros = 0, matched = 0;
    for (long i = 0; i < n; i++) {
        if (fabs(v[2 * i]) < 1e-9 && fabs(v[2 * i + 1]) < 1e-9)
            zeros++;
        else if (fabs(v[2 * i]) < 1e-9 && fabs(fabs(v[2 * i + 1]) - w) < 1e-9 * w)
            matched++;
    }
    CHECK(zeros == 2 && matched == 2, "%d zeros, %d of 2 at %.17g", zeros, matched, w);
    cli_result r = cli("run %scart_pendulum.mech --outputs --method dop853 --rtol 1e-12 "
                       "--atol 1e-12 --step 0.1", MECH);
    CHECK(r.status == 0, "%s", r.err);
    int cols;
    const long rows = csv_table(r.out, v, 1 << 14, &cols);
    CHECK(rows == 101 && cols == 9, "rows %ld cols %d", rows, cols);
    double x0;
    const double spread = column_spread(v, rows, cols, 5, &x0); /* t x phi dx dphi xcm ... */
    CHECK(fabs(x0 - 0.5 * 0.8 * sin(20 * DYN_PI / 180) / 2.5) < 1e-15 && spread < 1e-10,
          "centre of mass %.17g moved by %.3g m", x0, spread);
    const double swing = column_spread(v, rows, cols, 1, NULL);
    CHECK(swing > 0.05, "the cart moves (%.3g m)", swing);
    cli_free(&r);
}

/* A pendulum in Cartesian coordinates (x, y) held on its rod by a holonomic constraint:
 * linearized in its minimal coordinate and speed (x, dx; y, dy and Baumgarte's two
 * directions removed) its eigenvalues are those of the pendulum, +-i sqrt(g / l). */
static void test_constrained_linearization_keeps_minimal_states(void **state_)
{
    (void)state_;
    const double g = 9.81, l[2] = {2, 0.5};
    for (int k = 0; k < 2; k++) {
        static double v[64];
        char args[512];
        snprintf(args, sizeof args,
                 MECH "cartesian_pendulum.mech --set l=%.17g", l[k]);
        const long rows = eigenvalues(args, v, 32);
        CHECK(rows == 2, "l = %g: %ld eigenvalues, not 2", l[k], rows);
        const double w = sqrt(g / l[k]);
        for (int i = 0; i < 2; i++)
            CHECK(fabs(v[2 * i]) < 1e-12 * w && fabs(fabs(v[2 * i + 1]) - w) < 1e-9 * w,
                  "l = %g: %.17g%+.17gi, want +-%.17gi", l[k], v[2 * i], v[2 * i + 1], w);
    }
    cli_result r = cli("linearize %srolling_disk.mech --set W=3.4", MECH);
    CHECK(r.status == 0, "%s", r.err);
    CHECK(strstr(r.out, "minimal coordinates and speeds (8 of 10, the constraints' directions "
                        "removed): x y psi theta phi dpsi dtheta dphi\n") != NULL,
          "%s", r.out);
    cli_free(&r);
}

static void test_fourbar_loop_stays_closed(void **state_)
{
    (void)state_;
    static double v[1 << 17];
    cli_result r = cli("run %sfourbar.mech --outputs --method dop853 --rtol 1e-12 --atol 1e-12 "
                       "--tspan 0:100 --step 0.1", MECH);
    CHECK(r.status == 0, "%s", r.err);
    int cols;
    const long rows = csv_table(r.out, v, 1 << 17, &cols);
    CHECK(rows == 1001 && cols == 13, "rows %ld cols %d", rows, cols);
    /* t q1 q2 q3 dq1 dq2 dq3 loop_x loop_y gap kinetic potential energy */
    double gap0, e0;
    column_spread(v, rows, cols, 9, &gap0);
    double worst = 0.0, turns = 0.0;
    for (long k = 0; k < rows; k++)
        worst = fmax(worst, v[k * cols + 9]);
    turns = column_spread(v, rows, cols, 1, NULL) / (2 * DYN_PI);
    CHECK(worst < 1e-10, "loop open by %.3g m", worst);
    CHECK(turns > 0.5, "the crank swings through most of a turn (%.2f)", turns);
    const double spread = column_spread(v, rows, cols, 12, &e0);
    CHECK(spread < 1e-9 * fabs(e0), "energy changed by %.3g J of %.3g", spread, e0);
    cli_free(&r);
}

/* Columns of the same name in two CSV runs agree within tol; returns the largest
 * difference over the names. */
static double compare_runs(const char *a_args, const char *b_args, const char *const *names,
                           int count)
{
    static double a[1 << 17], b[1 << 17];
    cli_result ra = cli("run %s", a_args), rb = cli("run %s", b_args);
    CHECK(ra.status == 0 && rb.status == 0, "%s\n%s", ra.err, rb.err);
    int ca, cb;
    const long na = csv_table(ra.out, a, 1 << 17, &ca), nb = csv_table(rb.out, b, 1 << 17, &cb);
    CHECK(na == nb && na > 10, "rows %ld %ld", na, nb);
    double worst = 0.0;
    for (int k = 0; k < count; k++) {
        int ja = -1, jb = -1, col = 0;
        const size_t len = strlen(names[k]);
        for (const char *h = ra.out; *h != '\n'; col++) {
            if (!strncmp(h, names[k], len) && (h[len] == ',' || h[len] == '\n'))
                ja = col;
            h += strcspn(h, ",\n");
            if (*h == ',')
                h++;
        }
        col = 0;
        for (const char *h = rb.out; *h != '\n'; col++) {
            if (!strncmp(h, names[k], len) && (h[len] == ',' || h[len] == '\n'))
                jb = col;
            h += strcspn(h, ",\n");
            if (*h == ',')
                h++;
        }
        CHECK(ja >= 0 && jb >= 0, "column %s missing", names[k]);
        for (long r = 0; r < na; r++)
            worst = fmax(worst, fabs(a[r * ca + ja] - b[r * cb + jb]));
    }
    cli_free(&ra);
    cli_free(&rb);
    return worst;
}

/* The cart with its rear axle's constraint on the speeds against the built-in cart (Lagrange
 * with one multiplier, by hand): the homework's forward run of problem 4c (Heun with the
 * force table of the inverse dynamics, zero-order hold) and dop853 with constant forces. */
static void test_cart_matches_the_builtin_cart(void **state_)
{
    (void)state_;
    char table[512], model[512];
    snprintf(table, sizeof table, "%s", cli_path("forces.csv"));
    snprintf(model, sizeof model, "%s", cli_path("cart_model.c"));
    cli_result r = cli("inverse cart --quiet -o %s", table);
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    static const char *const names[] = {"sX", "sY", "theta", "dsX", "dsY", "omega", "lambda"};
    const char *init = "--init sX=0 --init sY=0 --init theta=0 --init dsX=-20 "
                       "--init dsY=4.934802200544679 --init omega=4.934802200544679 "
                       "--tspan 0:4.99 --step 0.01 --outputs";
    char a[2048], b[2048];
    snprintf(a, sizeof a, "%scart.mech --forces %s --method heun %s", MECH, table, init);
    snprintf(b, sizeof b, "cart --forces %s --method heun %s", table, init);
    double worst = compare_runs(a, b, names, 7);
    CHECK(worst < 1e-8, "heun with the force table: largest difference %.3g", worst);
    snprintf(a, sizeof a, "%scart.mech --method dop853 --rtol 1e-12 --atol 1e-12 --tspan 0:10 "
             "--outputs", MECH);
    snprintf(b, sizeof b, "cart --method dop853 --rtol 1e-12 --atol 1e-12 --tspan 0:10 "
             "--outputs");
    worst = compare_runs(a, b, names, 7);
    CHECK(worst < 1e-8, "dop853, constant forces: largest difference %.3g", worst);
    /* the C text of derive --c is the same model */
    r = cli("derive %scart.mech --c %s", MECH, model);
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    snprintf(a, sizeof a, "%s --forces %s --method heun %s", model, table, init);
    snprintf(b, sizeof b, "%scart.mech --forces %s --method heun %s", MECH, table, init);
    worst = compare_runs(a, b, names, 7);
    CHECK(worst == 0.0, "derive --c: largest difference %.3g", worst);
}

/* A prescribed angle: the multiplier is the driving torque m l^2 phi'' + m g l sin(phi). */
static void test_prescribed_motion_gives_the_driving_torque(void **state_)
{
    (void)state_;
    static double v[1 << 16];
    cli_result r = cli("run %sdriven_pendulum.mech --outputs --rtol 1e-10 --atol 1e-12 "
                       "--step 0.05", MECH);
    CHECK(r.status == 0, "%s", r.err);
    int cols;
    const long rows = csv_table(r.out, v, 1 << 16, &cols);
    CHECK(rows == 201 && cols == 8, "rows %ld cols %d", rows, cols);
    double worst = 0.0, big = 0.0; /* t phi dphi drive exact kinetic potential energy */
    for (long k = 0; k < rows; k++) {
        worst = fmax(worst, fabs(v[k * cols + 3] - v[k * cols + 4]));
        big = fmax(big, fabs(v[k * cols + 4]));
        CHECK(fabs(v[k * cols + 1] - 0.3 * sin(2 * v[k * cols])) < 1e-9, "phi off its path");
    }
    CHECK(worst < 1e-8 * big && big > 1, "torque off by %.3g N m (largest %.3g)", worst, big);
    cli_free(&r);
}

/* The four-bar with its crank driven at a constant rate w (prescribe): by virtual power the
 * drive's torque times w is the rate of the energy (the loop's forces do no work), so its
 * integral over time (Simpson's rule on 1 ms samples) is the energy's change. */
static void test_fourbar_drive_torque_by_virtual_power(void **state_)
{
    (void)state_;
    char *text = cli_read_file(MECH "fourbar.mech", NULL);
    char *at = strstr(text, "coord q1=");
    assert_non_null(at);
    at = strchr(at, '\n') + 1;
    FILE *f = fopen(cli_path("driven.mech"), "w");
    assert_non_null(f);
    fprintf(f, "%.*s", (int)(at - text), text);
    fputs("par w=2 [rad/s]\n!dq20=a*w*sin(q30-q10)/(b*sin(q20-q30))\n"
          "!dq30=a*w*sin(q20-q10)/(c*sin(q20-q30))\ninit dq1=w, dq2=dq20, dq3=dq30\n"
          "prescribe drive: q1 = q10 + w*t\n", f);
    fputs(at, f);
    fclose(f);
    free(text);
    static double v[1 << 16];
    cli_result r = cli("run %s --outputs --method dop853 --rtol 1e-12 --atol 1e-12 --tspan 0:3 "
                       "--step 0.001", cli_path("driven.mech"));
    CHECK(r.status == 0, "%s", r.err);
    int cols;
    const long rows = csv_table(r.out, v, 1 << 16, &cols);
    /* t q1 q2 q3 dq1 dq2 dq3 drive loop_x loop_y gap kinetic potential energy */
    CHECK(rows == 3001 && cols == 14, "rows %ld cols %d", rows, cols);
    double work = 0.0, worst = 0.0, big = 0.0;
    for (long k = 2; k < rows; k += 2) {
        const double *a = v + (k - 2) * cols, *b = v + (k - 1) * cols, *c = v + k * cols;
        work += 0.001 / 3 * 2 * (a[7] + 4 * b[7] + c[7]); /* w = 2 */
        const double dE = c[13] - v[13];
        worst = fmax(worst, fabs(work - dE));
        big = fmax(big, fabs(dE));
        CHECK(fabs(c[1] - 1 - 2 * c[0]) < 1e-9, "the crank follows its motion");
    }
    CHECK(big > 10 && worst < 1e-8 * big, "work of the drive off the energy's change by %.3g J "
          "(largest change %.3g J)", worst, big);
    cli_free(&r);
}

static void test_info_lists_the_mechanism(void **state_)
{
    (void)state_;
    cli_result r = cli("info %sfourbar.mech", MECH);
    CHECK(r.status == 0, "%s", r.err);
    const char *want[] = {"coordinates q1 (speed dq1)", "bodies crank (rigid body)",
                          "constraints loop_x (multiplier loop_x)", "loop_y", "dq3",
                          "kinetic", "energy"};
    for (size_t i = 0; i < sizeof want / sizeof *want; i++)
        CHECK(strstr(r.out, want[i]), "info lacks '%s':\n%s", want[i], r.out);
    CHECK(strstr(r.out, "loop_x") && strstr(strstr(r.out, "Extra outputs"), "loop_x     N "),
          "loop_x's unit is N:\n%s", r.out);
    cli_free(&r);
}

/* A mechanism's C above 64 KiB (the bicycle's is about 158 kB) is compiled by libtcc when
 * DYNKIT_JIT is unset (docs/mechanisms.md, "Speed"); a small one (the four-bar) by cc. */
static void test_large_mechanism_compiles_with_libtcc(void **state_)
{
    (void)state_;
    if (!dyn_jit_backend_available(DYN_JIT_TCC))
        skip();
    unsetenv("DYNKIT_JIT");
    cli_result r = cli("info %sbicycle.mech --verbose", MECH);
    CHECK(r.status == 0, "%s", r.err);
    CHECK(strstr(r.err, "(libtcc, in memory)"), "the bicycle was not compiled by libtcc:\n%s",
          r.err);
    cli_free(&r);
    r = cli("info %sfourbar.mech --verbose", MECH);
    CHECK(r.status == 0, "%s", r.err);
    CHECK(!strstr(r.err, "libtcc"), "the four-bar was compiled by libtcc:\n%s", r.err);
    cli_free(&r);
}

/* animate plays NAME.ani beside NAME.mech (its formulas in the mechanism's names) */
static void test_animate_plays_the_ani_beside(void **state_)
{
    (void)state_;
    char page[512];
    snprintf(page, sizeof page, "%s", cli_path("dp.html"));
    cli_result r = cli("animate %sdouble_pendulum.mech --tspan 0:2 -o %s", MECH, page);
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    char *html = cli_read_file(page, NULL);
    CHECK(strstr(html, "\"ani\":{\"file\":\"double_pendulum.ani\""), "no animation in the page");
    free(html);
}

static void test_errors_name_the_place(void **state_)
{
    (void)state_;
    const char *head = "coord x=1 [m], y=0 [m]\npar m=1 [kg]\n";
    char buf[1024];
    snprintf(buf, sizeof buf, "%spoint p mass=m at (x, yy, 0)\n", head);
    mech_refused(buf, "bad.mech:3:23:", "unknown name 'yy' (did you mean 'y'?)");
    snprintf(buf, sizeof buf, "%sbody b mass=m at (x, y, 0)\n", head);
    mech_refused(buf, "bad.mech:3:1:", "body 'b' has no inertia");
    snprintf(buf, sizeof buf, "%sbody b inertia=(1,1,1) at (x, y, 0)\n", head);
    mech_refused(buf, "bad.mech:3:1:", "body 'b' has no mass");
    snprintf(buf, sizeof buf, "%spoint p mass=m at (x, y, 0)\nconstraint roll: dx*dy = 0\n",
             head);
    mech_refused(buf, "bad.mech:4:12:", "not linear in the speeds");
    snprintf(buf, sizeof buf, "%spoint p mass=m at (x, y, 0)\nspring s between p and wall k=1\n",
             head);
    mech_refused(buf, "bad.mech:4:24:", "unknown body 'wall'");
    snprintf(buf, sizeof buf, "%spoint p mass=m at (x, y, 0)\nforce f on p = (1, 2)\n", head);
    mech_refused(buf, "bad.mech:4:21:", "expected ',' in the force");
    mech_refused("par m=1\npoint p mass=m at (0, 0, 0)\n", "bad.mech", "no coordinates");
    snprintf(buf, sizeof buf, "%sbdy b mass=m inertia=(1,1,1) at (x, y, 0)\n", head);
    mech_refused(buf, "bad.mech:3:1:", "unknown statement 'bdy' (did you mean 'body'?)");
    mech_refused("coord x=1 [m], y=0 [m], z=0 [m]\npoint p mass=1 at (x, y, 0)\n",
                 "bad.mech:1:25:", "no mass or inertia moves with z");
    mech_refused("coord x=1, y=0\npoint p mass=1 at (x+y, x+y, 0)\n", "bad.mech:1:12:",
                 "y moves no mass that the coordinates before it do not");
    mech_refused("coord x=1, y=0\npoint p mass=1 at (x, y, 0)\nconstraint c1: x^2+y^2-2 = 0\n",
                 "bad.mech:3:12:", "constraint 'c1' does not hold at the initial state: its "
                 "value is -1");
    mech_refused("coord x=1, y=0\ninit dx=1\npoint p mass=1 at (x, y, 0)\n"
                 "constraint c1: x^2+y^2-1 = 0\n", "bad.mech:4:12:", "its rate is 2");
    mech_refused("coord x=1, y=0\npoint p mass=1 at (x, y, 0)\nconstraint c1: x-1 = 0\n"
                 "constraint c2: 2*x-2 = 0\n", "bad.mech:4:12:",
                 "constraint 'c2' is redundant at the initial state: its row depends on those "
                 "of c1");
    const char *disk = "coord x=0 [m], y=0 [m], z=1 [m], a=0 [rad]\n"
                       "body d mass=1 inertia=(1,2,1) at (x, y, z) rot z:a\n";
    snprintf(buf, sizeof buf, "%swheel w on d axis=(0, 1, 0)\n", disk);
    mech_refused(buf, "bad.mech:3:1:", "wheel 'w' needs radius=R and axis=(x, y, z)");
    snprintf(buf, sizeof buf, "%swheel w on d radius=1 axle=(0, 1, 0)\n", disk);
    mech_refused(buf, "bad.mech:3:23:", "unknown word 'axle' in a wheel");
    snprintf(buf, sizeof buf, "%swheel w on d radius=2 axis=(0, 1, 0)\n", disk);
    mech_refused(buf, "bad.mech:3:7:", "constraint 'w_z' does not hold at the initial state: "
                 "its value is -1");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_double_pendulum_matches_hand_derivation),
        cmocka_unit_test(test_double_pendulum_keeps_its_energy),
        cmocka_unit_test(test_plane_matches_the_builtin_plane),
        cmocka_unit_test(test_plane_quat_matches_the_builtin_plane_quat),
        cmocka_unit_test(test_top_precesses_at_the_closed_form_rates),
        cmocka_unit_test(test_sleeping_top_is_stable_above_the_closed_form_spin),
        cmocka_unit_test(test_rolling_disk_is_stable_above_the_closed_form_speed),
        cmocka_unit_test(test_rolling_disk_critical_speed_by_root_finding),
        cmocka_unit_test(test_wheel_on_a_free_disk_carries_its_weight),
        cmocka_unit_test(test_rolling_disk_keeps_a_steady_turn),
        cmocka_unit_test(test_cart_pendulum_frequency_and_centre_of_mass),
        cmocka_unit_test(test_constrained_linearization_keeps_minimal_states),
        cmocka_unit_test(test_fourbar_loop_stays_closed),
        cmocka_unit_test(test_cart_matches_the_builtin_cart),
        cmocka_unit_test(test_prescribed_motion_gives_the_driving_torque),
        cmocka_unit_test(test_fourbar_drive_torque_by_virtual_power),
        cmocka_unit_test(test_info_lists_the_mechanism),
        cmocka_unit_test(test_large_mechanism_compiles_with_libtcc),
        cmocka_unit_test(test_animate_plays_the_ani_beside),
        cmocka_unit_test(test_errors_name_the_place),
    };
    return cmocka_run_group_tests(tests, setup_all, cli_remove_tmpdir);
}
