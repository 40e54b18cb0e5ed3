/* SPDX-License-Identifier: BSD-3-Clause */
/* test_mech_joints.c — joints and declared generalized speeds of mechanism files (src/mbs,
 * docs/mechanisms.md "Joints", "Generalized speeds") against independent answers: the double
 * pendulum by revolute joints against the one by formulas (1e-10 over 10 s); a slider on a
 * spring with a pendulum (prismatic and revolute joints) against the closed form of its two
 * small-oscillation frequencies; the heavy top with its body-frame angular velocities as
 * speeds against the top by its angles' rates, its axial spin constant (Euler's equations);
 * a free body in zero gravity keeping its angular momentum vector and energy, the
 * torque-free symmetric body's closed-form motion, and the growth rate of the spin about
 * the intermediate axis; joints along tilted axes (a pendulum's frequency, a sled on an
 * incline); a free joint with Euler parameters against plane_quat.mech, and derive's
 * note that M + D'D is solved there; a holonomic
 * constraint with declared speeds against cartesian_pendulum.mech, run, linearized
 * (+-i sqrt(g/l) hanging, +-sqrt(g/l) upright) and projected by --project-init (the
 * closest point of the circle, 1e-10); a chain of 8 revolute
 * joints against its formulas; a spatial chain by its rotations and by its matrices; the
 * picture's poses of prismatic and revolute joints; and the errors of joints and speeds at
 * FILE:LINE:COL. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>

#include "dynkit/lang.h"
#include "dynkit/mbs.h"
#include "test_cli_run.h"
#include "test_util.h"
#include "test_mech_util.h"

#define MECH DYNKIT_SOURCE_DIR "/examples/mechanisms/"
#define TIGHT "--method dop853 --rtol 1e-12 --atol 1e-12"
#define MAXROWS 4096

static char cache_dir[512];

static int setup_all(void **state)
{
    (void)state;
    return cli_make_tmpdir_with_cache("mech_joints", cache_dir, sizeof cache_dir);
}

/* The column NAME of a CSV text into out (at most MAXROWS rows); returns the rows. */
static long column(const char *csv, const char *name, double *out)
{
    const size_t len = strlen(name);
    int want = -1, col = 0;
    for (const char *h = csv; *h && *h != '\n'; col++) {
        if (!strncmp(h, name, len) && (h[len] == ',' || h[len] == '\n'))
            want = col;
        h += strcspn(h, ",\n");
        if (*h == ',')
            h++;
    }
    CHECK(want >= 0, "no column %s", name);
    long rows = 0;
    for (const char *p = strchr(csv, '\n'); p && p[1] && rows < MAXROWS; p = strchr(p + 1, '\n')) {
        const char *f = p + 1;
        for (int k = 0; k < want; k++)
            f = strchr(f, ',') + 1;
        out[rows++] = strtod(f, NULL);
    }
    return rows;
}

static cli_result run_ok(const char *fmt, const char *file, const char *extra)
{
    cli_result r = cli(fmt, file, extra);
    CHECK(r.status == 0, "%s", r.err);
    return r;
}

/* `dynkit linearize ARGS`: its eigenvalues' real and imaginary parts (at most 64) */
static long eigenvalues(const char *args, double *re, double *im)
{
    cli_result r = cli("linearize %s -o %s", args, cli_path("eig.csv"));
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    char *csv = cli_read_file(cli_path("eig.csv"), NULL);
    const long n = column(csv, "re", re);
    CHECK(n <= 64 && column(csv, "im", im) == n, "%ld eigenvalues", n);
    free(csv);
    return n;
}

/* The same chaotic double pendulum, its lower angle measured from the upper rod (phi2) in
 * place of the vertical: phi1 and phi1 + phi2 follow double_pendulum.mech's phi1, phi2. */
static void test_double_pendulum_by_revolute_joints(void **state_)
{
    (void)state_;
    static double a1[MAXROWS], a2[MAXROWS], b1[MAXROWS], b2[MAXROWS];
    const char *fmt = "run %s %s --tspan 0:10 --step 0.1";
    cli_result ra = run_ok(fmt, MECH "double_pendulum_joints.mech", TIGHT);
    cli_result rb = run_ok(fmt, MECH "double_pendulum.mech", TIGHT);
    const long n = column(ra.out, "phi1", a1);
    CHECK(n == 101 && column(ra.out, "phi2", a2) == n && column(rb.out, "phi1", b1) == n &&
              column(rb.out, "phi2", b2) == n,
          "rows %ld", n);
    double worst = 0.0, swing = 0.0;
    for (long i = 0; i < n; i++) {
        worst = fmax(worst, fmax(fabs(a1[i] - b1[i]), fabs(a1[i] + a2[i] - b2[i])));
        swing = fmax(swing, fabs(b2[i]));
    }
    CHECK(worst < 1e-10 && swing > 1.0, "largest difference %.3g rad (swing %.3g)", worst, swing);
    cli_free(&ra);
    cli_free(&rb);
}

/* Slider (mass M, spring k along x) with a pendulum (m, l): small oscillations
 * [M+m, m l; m l, m l^2] x'' + [k, 0; 0, m g l] x = 0 give
 * M l w^4 - (k l + (M + m) g) w^2 + k g = 0. */
static void test_slider_pendulum_frequencies(void **state_)
{
    (void)state_;
    const double M = 2, m = 0.5, l = 0.8, k = 30, g = 9.81;
    const double b = k * l + (M + m) * g, disc = sqrt(b * b - 4 * M * l * k * g);
    const double w[2] = {sqrt((b + disc) / (2 * M * l)), sqrt((b - disc) / (2 * M * l))};
    static double re[MAXROWS], im[MAXROWS];
    const long n = eigenvalues(MECH "slider_pendulum.mech --init s=0", re, im);
    CHECK(n == 4, "%ld eigenvalues", n);
    int matched = 0;
    for (long i = 0; i < n; i++)
        for (int j = 0; j < 2; j++)
            matched += fabs(re[i]) < 1e-9 && fabs(fabs(im[i]) - w[j]) < 1e-9 * w[j];
    CHECK(matched == 4, "%d of 4 eigenvalues at +-i %.17g, +-i %.17g", matched, w[0], w[1]);
}

/* The top with w = (w1, w2, w3) in its own frame as speeds: the angles of top.mech, whose
 * speeds are the angles' rates, and w3 constant (C w3' = (A - A) w1 w2 + 0: gravity acts
 * about a transverse axis). */
static void test_top_by_body_angular_velocities(void **state_)
{
    (void)state_;
    static double a[MAXROWS], b[MAXROWS];
    static const char *const names[] = {"psi", "theta", "phi", "energy"};
    const char *fmt = "run %s %s --tspan 0:5 --step 0.05 --outputs";
    cli_result ra = run_ok(fmt, MECH "top_euler.mech", TIGHT);
    cli_result rb = run_ok(fmt, MECH "top.mech", TIGHT);
    double worst = 0.0;
    for (int k = 0; k < 4; k++) {
        const long n = column(ra.out, names[k], a);
        CHECK(n == 101 && column(rb.out, names[k], b) == n, "rows %ld", n);
        for (long i = 0; i < n; i++)
            worst = fmax(worst, fabs(a[i] - b[i]));
    }
    CHECK(worst < 1e-10, "largest difference %.3g", worst);
    const long n = column(ra.out, "w3", a);
    for (long i = 0; i < n; i++)
        CHECK(fabs(a[i] - 100) < 1e-9, "w3 = %.17g at row %ld", a[i], i);
    column(ra.out, "theta", a);
    CHECK(fabs(a[n / 2] - a[0]) > 1e-3, "the top nods");
    cli_free(&ra);
    cli_free(&rb);
}

/* N-components of the angular momentum R' I w, R = Rz(phi) Rx(theta) Rz(psi) (passive) */
static void momentum(double psi, double th, double phi, const double Iw[3], double H[3])
{
    const double c1 = cos(psi), s1 = sin(psi), c2 = cos(th), s2 = sin(th), c3 = cos(phi),
                 s3 = sin(phi);
    const double R[9] = {c3 * c1 - s3 * c2 * s1,
                         c3 * s1 + s3 * c2 * c1,
                         s3 * s2,
                         -s3 * c1 - c3 * c2 * s1,
                         -s3 * s1 + c3 * c2 * c1,
                         c3 * s2,
                         s2 * s1,
                         -s2 * c1,
                         c2};
    for (int j = 0; j < 3; j++)
        H[j] = R[j] * Iw[0] + R[3 + j] * Iw[1] + R[6 + j] * Iw[2];
}

static void test_free_body_keeps_momentum_and_energy(void **state_)
{
    (void)state_;
    static double v[9][MAXROWS];
    static const char *const names[] = {"t",  "psi", "theta",  "phi", "w1",
                                        "w2", "w3",  "energy", "x"};
    /* asymmetric, I = (1, 2, 3): H = (0, 0, 1) and the energy stay */
    cli_result r =
        run_ok("run %s %s --tspan 0:40 --step 0.5 --outputs", MECH "free_body.mech", TIGHT);
    long n = 0;
    for (int k = 0; k < 9; k++)
        n = column(r.out, names[k], v[k]);
    CHECK(n == 81, "rows %ld", n);
    double dH = 0.0, dE = 0.0, dx = 0.0, wobble = 0.0;
    for (long i = 0; i < n; i++) {
        const double Iw[3] = {v[4][i], 2 * v[5][i], 3 * v[6][i]};
        double H[3];
        momentum(v[1][i], v[2][i], v[3][i], Iw, H);
        dH = fmax(dH, fmax(fmax(fabs(H[0]), fabs(H[1])), fabs(H[2] - 1)));
        dE = fmax(dE, fabs(v[7][i] - v[7][0]));
        dx = fmax(dx, fabs(v[8][i] - 0.1 * v[0][i]));
        wobble = fmax(wobble, fabs(v[2][i] - 0.5));
    }
    CHECK(dH < 1e-10 && dE < 1e-12 && dx < 1e-12 && wobble > 0.1,
          "angular momentum off by %.3g, energy by %.3g, x by %.3g (nutation %.3g)", dH, dE, dx,
          wobble);
    cli_free(&r);
    /* symmetric, A = I1 = I2 = 1, C = I3 = 3, H along z: theta stays, psi' = H/A,
     * phi' = H cos(theta) (1/C - 1/A) (Goldstein, Classical Mechanics, 5.6) */
    r = run_ok("run %s %s --tspan 0:40 --step 0.5 --set I2=1", MECH "free_body.mech", TIGHT);
    for (int k = 0; k < 7; k++)
        n = column(r.out, names[k], v[k]);
    double worst = 0.0;
    for (long i = 0; i < n; i++) {
        const double t = v[0][i], phi = cos(0.5) * (1.0 / 3 - 1) * t;
        worst = fmax(worst, fabs(v[1][i] - t));
        worst = fmax(worst, fabs(v[2][i] - 0.5));
        worst = fmax(worst, fabs(v[3][i] - phi));
        worst = fmax(worst, fabs(v[4][i] - sin(0.5) * sin(phi)));
        worst = fmax(worst, fabs(v[5][i] - sin(0.5) * cos(phi)));
    }
    CHECK(worst < 1e-10, "largest difference from the closed form %.3g", worst);
    cli_free(&r);
}

/* Spin W about the intermediate axis (I1 < I2 < I3) grows as exp(lambda t),
 * lambda = W sqrt((I2 - I1)(I3 - I2) / (I1 I3)): linearized Euler's equations. */
static void test_intermediate_axis_is_unstable(void **state_)
{
    (void)state_;
    const double W = 1.5, lam = W * sqrt(1.0 * 1.0 / 3.0);
    char args[512];
    snprintf(args, sizeof args, "%s --init w1=0 --init w2=%.17g --init w3=0", MECH "free_body.mech",
             W);
    static double re[MAXROWS], im[MAXROWS];
    const long n = eigenvalues(args, re, im);
    int up = 0, down = 0;
    for (long i = 0; i < n; i++) {
        up += fabs(im[i]) < 1e-9 && fabs(re[i] - lam) < 1e-8 * lam;
        down += fabs(im[i]) < 1e-9 && fabs(re[i] + lam) < 1e-8 * lam;
    }
    CHECK(n == 12 && up == 1 && down == 1, "%ld eigenvalues, %d at %.17g, %d at its negative", n,
          up, lam, down);
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

/* Joints along axes (ax, ay, az): a pendulum about an axis tilted by beta from the
 * horizontal, its rod square to the axis, swings at sqrt(g cos(beta) / l); a sled on an
 * incline at alpha slides as s = -g sin(alpha) t^2 / 2. */
static void test_tilted_axes(void **state_)
{
    (void)state_;
    char path[512];
    snprintf(path, sizeof path, "%s", cli_path("tilted.mech"));
    write_file(path, "coord phi=0 [rad], s=0 [m]\n"
                     "par l=0.5 [m], beta=0.3, alpha=0.4, g=9.81 [m/s^2]\n"
                     "gravity 0, -g, 0\n"
                     "point bob mass=1 revolute ground (0, sin(beta), cos(beta)):phi "
                     "pivot (0, l*cos(beta), -l*sin(beta))\n"
                     "point sled mass=2 prismatic ground(0, 0, 1) (2*cos(alpha), "
                     "2*sin(alpha), 0):s\n");
    static double re[MAXROWS], im[MAXROWS];
    const long n = eigenvalues(path, re, im);
    const double w = sqrt(9.81 * cos(0.3) / 0.5);
    int matched = 0;
    for (long i = 0; i < n; i++)
        matched += fabs(re[i]) < 1e-9 && fabs(fabs(im[i]) - w) < 1e-9 * w;
    CHECK(n == 4 && matched == 2, "%ld eigenvalues, %d at +-i %.17g", n, matched, w);
    static double t[MAXROWS], sv[MAXROWS];
    cli_result r = run_ok("run %s %s --tspan 0:2 --step 0.5", path, TIGHT);
    const long rows = column(r.out, "t", t);
    column(r.out, "s", sv);
    double worst = 0.0;
    for (long i = 0; i < rows; i++)
        worst = fmax(worst, fabs(sv[i] + 0.5 * 9.81 * sin(0.4) * t[i] * t[i]));
    CHECK(rows == 5 && worst < 1e-12, "sled off by %.3g m", worst);
    cli_free(&r);
}

/* The plane of plane_quat.mech placed by a free joint with Euler parameters: the same run
 * to the last digit (the same formulas). */
static void test_free_joint_with_euler_parameters(void **state_)
{
    (void)state_;
    char path[512];
    snprintf(path, sizeof path, "%s", cli_path("plane_free.mech"));
    char *text = cli_read_file(MECH "plane_quat.mech", NULL);
    const char *from = "at (sX, sY, sZ) rot quat:", *to = "free ground (sX, sY, sZ) quat:";
    char *at = strstr(text, from);
    CHECK(at != NULL, "plane_quat.mech places its body by %s", from);
    char buf[4096];
    snprintf(buf, sizeof buf, "%.*s%s%s", (int)(at - text), text, to, at + strlen(from));
    free(text);
    write_file(path, buf);
    cli_result ra = run_ok("run %s %s --tspan 0:5 --step 0.25", path, TIGHT);
    cli_result rb = run_ok("run %s %s --tspan 0:5 --step 0.25", MECH "plane_quat.mech", TIGHT);
    CHECK(strcmp(ra.out, rb.out) == 0, "the runs differ:\n%.300s\n%.300s", ra.out, rb.out);
    cli_free(&ra);
    cli_free(&rb);
}

/* A pendulum of 8 links by revolute joints, each angle from the link before, against the
 * same pendulum by formulas (each link's absolute angle the sum of the joints' angles):
 * the same motion within 1e-10 rad over 2 s. */
static void test_chain_of_joints_matches_the_formulas(void **state_)
{
    (void)state_;
    enum { LINKS = 8 };
    static char joints[16384], formulas[16384];
    char *j = joints, *f = formulas;
    const char *head = "par g=9.81 [m/s^2], l=0.5 [m]\ngravity 0, -g, 0\ncoord q0=0.3";
    j += sprintf(j, "%s", head);
    f += sprintf(f, "%s", head);
    for (int i = 1; i < LINKS; i++) {
        j += sprintf(j, ", q%d=%.2f", i, 0.1 * (i % 5) - 0.2);
        f += sprintf(f, ", q%d=%.2f", i, 0.1 * (i % 5) - 0.2);
    }
    j += sprintf(j, "\n");
    f += sprintf(f, "\n");
    char sum[1024] = "", x[8192] = "", y[8192] = "";
    for (int i = 0; i < LINKS; i++) {
        char parent[16] = "ground";
        if (i)
            snprintf(parent, sizeof parent, "b%d", i - 1);
        j += sprintf(j, "point b%d mass=1 revolute %s z:q%d pivot (0, l, 0)\n", i, parent, i);
        snprintf(sum + strlen(sum), sizeof sum - strlen(sum), "%sq%d", i ? "+" : "", i);
        snprintf(x + strlen(x), sizeof x - strlen(x), "+l*sin(%s)", sum);
        snprintf(y + strlen(y), sizeof y - strlen(y), "-l*cos(%s)", sum);
        f += sprintf(f, "point b%d mass=1 at (%s, %s, 0)\n", i, x, y);
    }
    CHECK(strstr(joints, "revolute b0 z:q1") && strstr(joints, "revolute ground z:q0"), "%s",
          joints);
    char pj[512], pf[512];
    snprintf(pj, sizeof pj, "%s", cli_path("chain_joints.mech"));
    snprintf(pf, sizeof pf, "%s", cli_path("chain_formulas.mech"));
    write_file(pj, joints);
    write_file(pf, formulas);
    cli_result ra = run_ok("run %s %s --tspan 0:2 --step 0.1", pj, TIGHT);
    cli_result rb = run_ok("run %s %s --tspan 0:2 --step 0.1", pf, TIGHT);
    static double a[MAXROWS], b[MAXROWS];
    double worst = 0.0;
    for (int i = 0; i < LINKS; i++) {
        char name[16];
        snprintf(name, sizeof name, "q%d", i);
        const long n = column(ra.out, name, a);
        CHECK(n == 21 && column(rb.out, name, b) == n, "rows %ld", n);
        for (long k = 0; k < n; k++)
            worst = fmax(worst, fabs(a[k] - b[k]));
    }
    CHECK(worst < 1e-10, "largest difference %.3g rad", worst);
    cli_free(&ra);
    cli_free(&rb);
}

/* A spatial chain (revolute, spherical with two angles, revolute) whose first axis is
 * written z or (0, 0, 1): the first continues the chain of elementary rotations, the
 * second composes each child with its parent's matrix; the same motion within 1e-10 and
 * the energy kept within 1e-10 J over 3 s. */
static void test_spatial_chain_two_ways(void **state_)
{
    (void)state_;
    const char *text = "par g=9.81 [m/s^2]\n"
                       "coord a=0.3 [rad], b=0.2 [rad], c=-0.4 [rad], e=0.5 [rad]\n"
                       "init da=1, de=2\n"
                       "gravity 0, 0, -g\n"
                       "body l1 mass=1 inertia=(0.1, 0.2, 0.3) revolute ground %s:a "
                       "pivot (0.2, 0, 0)\n"
                       "body l2 mass=1 inertia=(0.05, 0.06, 0.01) spherical l1(0.2, 0, 0) "
                       "x:b y:c pivot (0, 0, 0.3)\n"
                       "point tip mass=0.5 revolute l2(0, 0, -0.3) z:e pivot (0, 0.2, 0)\n";
    char buf[1024], pa[512], pb[512];
    snprintf(pa, sizeof pa, "%s", cli_path("chain_z.mech"));
    snprintf(pb, sizeof pb, "%s", cli_path("chain_axis.mech"));
    snprintf(buf, sizeof buf, text, "z");
    write_file(pa, buf);
    snprintf(buf, sizeof buf, text, "(0, 0, 1)");
    write_file(pb, buf);
    const char *opts = TIGHT " --tspan 0:3 --step 0.1 --outputs";
    cli_result ra = run_ok("run %s %s", pa, opts), rb = run_ok("run %s %s", pb, opts);
    static const char *const names[] = {"a", "b", "c", "e", "energy"};
    static double x[MAXROWS], y[MAXROWS];
    double worst = 0.0, energy = 0.0;
    for (int k = 0; k < 5; k++) {
        const long n = column(ra.out, names[k], x);
        CHECK(n == 31 && column(rb.out, names[k], y) == n, "rows %ld", n);
        for (long i = 0; i < n; i++) {
            worst = fmax(worst, fabs(x[i] - y[i]));
            if (k == 4)
                energy = fmax(energy, fabs(x[i] - x[0]));
        }
    }
    CHECK(worst < 1e-10 && energy < 1e-10, "largest difference %.3g, energy changed by %.3g J",
          worst, energy);
    cli_free(&ra);
    cli_free(&rb);
}

/* The pendulum of cartesian_pendulum.mech (x, y held on the rod by a holonomic constraint)
 * with the velocity's radial and tangential components ur, ut as speeds: the same motion
 * and the same rod force (the multiplier of the same constraint), ur kept at 0. */
static void test_constraint_with_declared_speeds(void **state_)
{
    (void)state_;
    char path[512];
    snprintf(path, sizeof path, "%s", cli_path("polar_speeds.mech"));
    write_file(path, "par m=1 [kg], l=2 [m], g=9.81 [m/s^2]\n"
                     "coord x=0 [m], y=-l [m]\n"
                     "speeds ur [m/s], ut=1 [m/s]\n"
                     "rate x' = (ur*x - ut*y)/l, y' = (ur*y + ut*x)/l\n"
                     "gravity 0, -g, 0\n"
                     "point bob mass=m at (x, y, 0)\n"
                     "constraint rod [m]: sqrt(x^2 + y^2) - l = 0\n");
    const char *opts = TIGHT " --tspan 0:10 --step 0.1 --outputs --init dx=1";
    cli_result ra = run_ok("run %s %s", path, TIGHT " --tspan 0:10 --step 0.1 --outputs");
    cli_result rb = run_ok("run %s %s", MECH "cartesian_pendulum.mech", opts);
    static double a[MAXROWS], b[MAXROWS];
    static const char *const names[] = {"x", "y", "rod"};
    double worst[3] = {0, 0, 0};
    for (int k = 0; k < 3; k++) {
        const long n = column(ra.out, names[k], a);
        CHECK(n == 101 && column(rb.out, names[k], b) == n, "rows %ld", n);
        for (long i = 0; i < n; i++)
            worst[k] = fmax(worst[k], fabs(a[i] - b[i]));
    }
    const long n = column(ra.out, "ur", a);
    double ur = 0.0;
    for (long i = 0; i < n; i++)
        ur = fmax(ur, fabs(a[i]));
    CHECK(worst[0] < 1e-10 && worst[1] < 1e-10 && worst[2] < 1e-9 && ur < 1e-10,
          "x off by %.3g m, y by %.3g m, the rod's force by %.3g N; ur up to %.3g m/s", worst[0],
          worst[1], worst[2], ur);
    cli_free(&ra);
    cli_free(&rb);
}

/* cartesian_pendulum.mech with radial and tangential speeds (ur, ut) into path */
static void polar_pendulum(char *path, size_t size)
{
    snprintf(path, size, "%s", cli_path("polar_lin.mech"));
    write_file(path, "par m=1 [kg], l=2 [m], g=9.81 [m/s^2]\n"
                     "coord x=0 [m], y=-l [m]\n"
                     "speeds ur [m/s], ut [m/s]\n"
                     "rate x' = (ur*x - ut*y)/l, y' = (ur*y + ut*x)/l\n"
                     "gravity 0, -g, 0\n"
                     "point bob mass=m at (x, y, 0)\n"
                     "constraint rod [m]: sqrt(x^2 + y^2) - l = 0\n");
}

/* The same pendulum linearized (l = 2 m, g = 9.81 m/s^2): hanging, +-i sqrt(g/l); upright,
 * +-sqrt(g/l); the eigenvalues of cartesian_pendulum.mech's (speeds the rates) at both. The
 * rod's admissible positions are those of f = sqrt(x^2 + y^2) - l, whose gradient in (x, y)
 * is not its rate's row in (ur, ut) (that is df/dq W, with q' = W u). */
static void test_linearize_constraint_with_declared_speeds(void **state_)
{
    (void)state_;
    char path[512];
    polar_pendulum(path, sizeof path);
    const double w = sqrt(9.81 / 2.0);
    static const char *const at[2] = {"", " --init y=2"};
    for (int up = 0; up < 2; up++) {
        char args[1024];
        double re[64], im[64], rc[64], ic[64];
        snprintf(args, sizeof args, "%s%s", path, at[up]);
        const long n = eigenvalues(args, re, im);
        snprintf(args, sizeof args, "%s%s", MECH "cartesian_pendulum.mech", at[up]);
        const long nc = eigenvalues(args, rc, ic);
        CHECK(n == 2 && nc == 2, "%ld and %ld eigenvalues", n, nc);
        double worst = 0.0, apart = 0.0;
        for (long i = 0; i < n; i++) {
            const double s = i == 0 ? -w : w; /* sorted by real, then imaginary part */
            worst = fmax(worst, up ? fabs(re[i] - s) + fabs(im[i]) : fabs(re[i]) + fabs(im[i] - s));
            apart = fmax(apart, fabs(re[i] - rc[i]) + fabs(im[i] - ic[i]));
        }
        CHECK(worst < 1e-8 * w && apart < 1e-8 * w,
              "%s: %.17g%+.17gi, %.17g%+.17gi; off sqrt(g/l) = %.17g by %.3g, off the "
              "rates' by %.3g",
              up ? "upright" : "hanging", re[0], im[0], re[1], im[1], w, worst, apart);
    }
}

/* --project-init moves the coordinates by the minimal-norm step in q whatever the speeds:
 * the pendulum with radial/tangential speeds started off its rod lands, as the Cartesian
 * one does, on the closest point of the circle, (x, y) l / |(x, y)|. */
static void test_project_init_with_declared_speeds(void **state_)
{
    (void)state_;
    static double x[MAXROWS], y[MAXROWS], xc[MAXROWS], yc[MAXROWS];
    char path[512];
    polar_pendulum(path, sizeof path);
    const char *fmt = "run %s%s --init x=1.3 --init y=-0.7 --project-init --tspan 0:0.1 "
                      "--step 0.1";
    cli_result r = run_ok(fmt, path, "");
    cli_result rc = run_ok(fmt, MECH "cartesian_pendulum.mech", "");
    CHECK(column(r.out, "x", x) == 2 && column(r.out, "y", y) == 2 &&
              column(rc.out, "x", xc) == 2 && column(rc.out, "y", yc) == 2,
          "%s%s", r.out, rc.out);
    const double s = 2.0 / hypot(1.3, -0.7);
    const double off = fmax(fabs(x[0] - 1.3 * s), fabs(y[0] + 0.7 * s));
    const double apart = fmax(fabs(x[0] - xc[0]), fabs(y[0] - yc[0]));
    CHECK(off < 1e-10 && apart < 1e-10,
          "(%.17g, %.17g) and Cartesian (%.17g, %.17g): off the closest point by %.3g, "
          "apart by %.3g", x[0], y[0], xc[0], yc[0], off, apart);
    cli_free(&r);
    cli_free(&rc);
}

/* info and derive state the kinematic equations of declared speeds; derive's M and F are
 * by speed (Euler's equations: the top's axial M[w3,w3] = C) */
static void test_info_and_derive_show_the_rates(void **state_)
{
    (void)state_;
    const char *rate = "theta' = w1*cos(phi)-w2*sin(phi)";
    cli_result r = run_ok("info %s%s", MECH "top_euler.mech", "");
    CHECK(strstr(r.out, "speeds w1, w2, w3; kinematic equations psi' = ") && strstr(r.out, rate),
          "%s", r.out);
    cli_free(&r);
    r = run_ok("derive %s%s", MECH "top_euler.mech", "");
    CHECK(strstr(r.out, "M u' = F + D' lambda, q' = W(q) u\n") &&
              strstr(r.out, "\nkinematic equations:\n") && strstr(r.out, rate) &&
              strstr(r.out, "\nM[w3,w3] = C\n") && strstr(r.out, "\nF[w3] = "),
          "%s", r.out);
    cli_free(&r);
}

/* Euler parameters move no mass along q itself (a rotation depends on q / |q| only), so M
 * is singular there and the norm constraint's row 2 q is that direction: derive prints M
 * and D and says that M + D'D is solved, as run does; the four-bar's M is regular. */
static void test_derive_says_when_m_plus_dtd_is_solved(void **state_)
{
    (void)state_;
    const char *note = "M below is singular at the initial state";
    cli_result r = run_ok("derive %s%s", MECH "plane_quat.mech", "");
    CHECK(strstr(r.out, note) && strstr(r.out, "(M + D'D) q'' = F + D' (lambda - b)") &&
              strstr(r.out, "\nD[norm,qw] = 2*qw\n") && strstr(r.out, "\nM[qw,qw] = "),
          "%s", r.out);
    cli_free(&r);
    r = run_ok("derive %s%s", MECH "fourbar.mech", "");
    CHECK(!strstr(r.out, note), "%s", r.out);
    cli_free(&r);
}

/* The picture's poses (dyn_mech_scene_eval) of joints: a slider at (s, 0, 0) by its
 * prismatic joint, along x or along the vector (3, 0, 0), the bob below it at
 * (s + l sin(phi), -l cos(phi), 0) by a revolute joint about z or about (0, 0, 2). */
static void test_picture_follows_the_joints(void **state_)
{
    (void)state_;
    static const char *const axes[2][2] = {{"x", "z"}, {"(3, 0, 0)", "(0, 0, 2)"}};
    const double l = 0.8, par[2] = {l, 9.81};
    double worst = 0.0;
    for (int v = 0; v < 2; v++) {
        char text[1024];
        snprintf(text, sizeof text,
                 "coord s [m], phi [rad]\npar l=0.8 [m], g=9.81 [m/s^2]\n"
                 "gravity 0, -g, 0\npoint slider mass=2 prismatic ground %s:s\n"
                 "point bob mass=1 revolute slider %s:phi pivot (0, l, 0)\n",
                 axes[v][0], axes[v][1]);
        dyn_mech_scene *sc = mech_scene_of(text);
        CHECK(dyn_mech_scene_n_params(sc) == 2, "%d parameters", dyn_mech_scene_n_params(sc));
        for (int k = 0; k < 20; k++) {
            const double sv = 0.3 * k - 2, phi = 0.37 * k - 3;
            const double y[4] = {sv, phi, 0, 0};
            double pose[24], vals[256];
            assert_int_equal(dyn_mech_scene_eval(sc, 0, y, par, pose, vals), 0);
            worst = fmax(worst, fabs(pose[0] - sv) + fabs(pose[1]) + fabs(pose[2]));
            worst = fmax(worst, fabs(pose[12] - sv - l * sin(phi)) + fabs(pose[13] + l * cos(phi)) +
                                    fabs(pose[14]));
        }
        dyn_mech_scene_free(sc);
    }
    CHECK(worst < 1e-14, "largest difference %.3g m", worst);
}

static void test_joint_and_speed_errors(void **state_)
{
    (void)state_;
    const char *head = "coord a=0.1 [rad], b=0 [rad]\n";
    char buf[1024];
    snprintf(buf, sizeof buf, "%spoint p mass=1 revolute arm z:a pivot (0, 1, 0)\n", head);
    mech_refused(buf, "bad.mech:2:25:", "unknown body 'arm'");
    snprintf(buf, sizeof buf, "%spoint p mass=1 revolute p z:a\n", head);
    mech_refused(buf, "bad.mech:2:25:", "'p' cannot be its own parent");
    snprintf(buf, sizeof buf,
             "%spoint p mass=1 revolute ground z:a pivot (0, 1, 0)\n"
             "point q mass=1 revolute p z:a pivot (0, 1, 0)\n",
             head);
    mech_refused(buf, "bad.mech:3:29:", "coordinate 'a' already moves the joint of 'p'");
    snprintf(buf, sizeof buf, "%spoint p mass=1 revolute ground z:2*a\n", head);
    mech_refused(buf, "bad.mech:2:34:",
                 "each angle of the revolute joint of 'p' is a "
                 "coordinate's name");
    snprintf(buf, sizeof buf, "%spoint p mass=1 revolute ground z:a x:b\n", head);
    mech_refused(buf, "bad.mech:2:32:", "a revolute joint has one axis and one coordinate");
    /* a misspelt axis names the joint's own form, not that of 'rot' */
    snprintf(buf, sizeof buf, "%spoint p mass=1 revolute ground w:a\n", head);
    mech_refused(buf, "bad.mech:2:32:", "expected the revolute joint's AXIS:q after its parent");
    snprintf(buf, sizeof buf, "%spoint p mass=1 prismatic ground\n", head);
    mech_refused(buf, "bad.mech:2:32:", "expected the prismatic joint's AXIS:q after its parent");
    snprintf(buf, sizeof buf, "%spoint p mass=1 at (a, b, 0) revolute ground z:a\n", head);
    mech_refused(buf, "bad.mech:2:29:", "placed either by a joint or by at (x, y, z)");
    snprintf(buf, sizeof buf, "%sspeeds u\nrate a' = u\npoint p mass=1 at (a, b, 0)\n", head);
    mech_refused(buf, "bad.mech:2:8:", "1 speeds for 2 coordinates");
    snprintf(buf, sizeof buf, "%sspeeds u, v\nrate a' = u\npoint p mass=1 at (a, b, 0)\n", head);
    mech_refused(buf, "bad.mech:1:20:", "coordinate 'b' has no rate");
    snprintf(buf, sizeof buf, "%sspeeds u, v\nrate a' = u*v, b' = v\npoint p mass=1 at (a, b, 0)\n",
             head);
    mech_refused(buf, "bad.mech:3:6:", "the rate of 'a' is not linear in the speeds");
    snprintf(buf, sizeof buf,
             "%sspeeds u, v\nrate a' = u + 1, b' = v\npoint p mass=1 at (a, b, 0)\n", head);
    mech_refused(buf, "bad.mech:3:6:", "the rate of 'a' is 1 with all speeds 0");
    snprintf(buf, sizeof buf, "%srate a' = da\npoint p mass=1 at (a, b, 0)\n", head);
    mech_refused(buf, "bad.mech:2:6:", "a rate line needs the generalized speeds");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_double_pendulum_by_revolute_joints),
        cmocka_unit_test(test_slider_pendulum_frequencies),
        cmocka_unit_test(test_top_by_body_angular_velocities),
        cmocka_unit_test(test_free_body_keeps_momentum_and_energy),
        cmocka_unit_test(test_intermediate_axis_is_unstable),
        cmocka_unit_test(test_tilted_axes),
        cmocka_unit_test(test_free_joint_with_euler_parameters),
        cmocka_unit_test(test_chain_of_joints_matches_the_formulas),
        cmocka_unit_test(test_spatial_chain_two_ways),
        cmocka_unit_test(test_constraint_with_declared_speeds),
        cmocka_unit_test(test_linearize_constraint_with_declared_speeds),
        cmocka_unit_test(test_project_init_with_declared_speeds),
        cmocka_unit_test(test_info_and_derive_show_the_rates),
        cmocka_unit_test(test_derive_says_when_m_plus_dtd_is_solved),
        cmocka_unit_test(test_picture_follows_the_joints),
        cmocka_unit_test(test_joint_and_speed_errors),
    };
    return cmocka_run_group_tests(tests, setup_all, NULL);
}
