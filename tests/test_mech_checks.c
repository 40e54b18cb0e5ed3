/* SPDX-License-Identifier: BSD-3-Clause */
/* test_mech_checks.c — a mechanism's inverse dynamics, its initial state against its
 * constraints, and the checks of bad input (docs/mechanisms.md, docs/reliability.md):
 * `dynkit inverse cart.mech` with problem 4a's prescribed motion against the hand-derived
 * `dynkit inverse cart` (1e-8 of the forces); a prescribed pendulum angle's torque
 * m l^2 phi'' + m g l sin(phi) by hand; --project-init's minimal-norm speeds in closed form
 * and a four-bar closed to rounding; states that violate a constraint refused by name;
 * units that do not add up named at their place; a spring's law= that is not a function of
 * two arguments, or with k=/c= beside it, or whose energy= is not its integral (dG/dx
 * against F(x, 0)), or whose law is not in N or energy not in J, refused at its place. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>

#include "test_cli_run.h"
#include "test_util.h"
#include "test_mech_util.h"

#define MECH DYNKIT_SOURCE_DIR "/examples/mechanisms/"

static char cache_dir[512];

static int setup_all(void **state)
{
    (void)state;
    return cli_make_tmpdir_with_cache("mech_checks", cache_dir, sizeof cache_dir);
}

/* the numbers of a CSV text after its header row into v (row-major); rows, *cols set */
static long numbers(const char *text, double *v, long max, int *cols)
{
    const char *line = strchr(text, '\n');
    *cols = 1;
    for (const char *h = text; line && h < line; h++)
        *cols += *h == ',';
    long k = 0;
    for (const char *p = line; p && *p && k < max;) {
        char *end;
        const double x = strtod(p + 1, &end);
        if (end == p + 1)
            break;
        v[k++] = x;
        p = end;
    }
    return k / *cols;
}

/* Problem 4a's prescribed motion sX = -20 t, theta = pi/8 sin(4 pi t) of the cart: the
 * forces Fx, Fy found by `dynkit inverse cart.mech --inputs Fx,Fy` (equations by TMT, the
 * motion integrated by dop853) equal the closed form of `dynkit inverse cart`. */
static void test_inverse_cart_mech_matches_inverse_cart(void **state_)
{
    (void)state_;
    static double a[1 << 14], b[1 << 14];
    cli_result ra = cli("inverse cart --quiet");
    CHECK(ra.status == 0, "%s", ra.err);
    cli_result rb = cli("inverse %scart.mech --prescribe sX=-20*t --prescribe "
                        "'theta=pi/8*sin(4*pi*t)' --inputs Fx,Fy --tspan 0:4.99 --step 0.01 "
                        "--method dop853 --rtol 1e-12 --atol 1e-12", MECH);
    CHECK(rb.status == 0, "%s", rb.err);
    CHECK(strncmp(rb.out, "t,Fx,Fy,lambda\n", 15) == 0, "header: %.40s", rb.out);
    CHECK(strstr(rb.err, "dsX 2 -> -20") && strstr(rb.err, "omega 2 -> 4.934802200544679"),
          "the initial state is moved onto the prescribed motion:\n%s", rb.err);
    int ca, cb;
    const long na = numbers(ra.out, a, 1 << 14, &ca), nb = numbers(rb.out, b, 1 << 14, &cb);
    CHECK(na == 500 && nb == 500 && ca == 3 && cb == 4, "rows %ld %ld cols %d %d", na, nb, ca,
          cb);
    double worst = 0.0, big = 0.0;
    for (long k = 0; k < na; k++) {
        CHECK(a[k * ca] == b[k * cb], "sample times differ at row %ld", k);
        for (int j = 1; j < 3; j++) {
            worst = fmax(worst, fabs(a[k * ca + j] - b[k * cb + j]));
            big = fmax(big, fabs(a[k * ca + j]));
        }
    }
    CHECK(big > 500 && worst < 1e-8 * big, "forces differ by %.3g N (largest %.3g N)", worst,
          big);
    cli_free(&ra);
    cli_free(&rb);
    /* the table in the other formats too */
    rb = cli("inverse %scart.mech --prescribe sX=-20*t --prescribe 'theta=pi/8*sin(4*pi*t)' "
             "--inputs Fx,Fy --tspan 0:0.1 --step 0.05 --quiet -o %s", MECH,
             cli_path("forces.json"));
    CHECK(rb.status == 0, "%s", rb.err);
    char *json = cli_read_file(cli_path("forces.json"), NULL);
    CHECK(strstr(json, "\"columns\": [\"t\", \"Fx\", \"Fy\", \"lambda\"]") ||
              strstr(json, "\"columns\":[\"t\",\"Fx\",\"Fy\",\"lambda\"]"),
          "%s", json);
    free(json);
    cli_free(&rb);
}

/* Without --inputs the drives are the generalized forces: the prescribed pendulum angle
 * phi = A sin(w t) takes m l^2 phi'' + m g l sin(phi). */
static void test_inverse_gives_the_generalized_driving_force(void **state_)
{
    (void)state_;
    static double v[1 << 14];
    cli_result r = cli("inverse %sdriven_pendulum.mech --tspan 0:5 --step 0.01 --rtol 1e-11 "
                       "--atol 1e-12", MECH);
    CHECK(r.status == 0, "%s", r.err);
    CHECK(strncmp(r.out, "t,drive\n", 8) == 0, "header: %.40s", r.out);
    int cols;
    const long rows = numbers(r.out, v, 1 << 14, &cols);
    CHECK(rows == 501 && cols == 2, "rows %ld cols %d", rows, cols);
    const double m = 2, l = 0.5, g = 9.81, A = 0.3, w = 2;
    double worst = 0.0;
    for (long k = 0; k < rows; k++) {
        const double t = v[2 * k], phi = A * sin(w * t);
        const double torque = m * l * l * (-A * w * w * sin(w * t)) + m * g * l * sin(phi);
        worst = fmax(worst, fabs(v[2 * k + 1] - torque));
    }
    CHECK(worst < 1e-8, "driving torque off by %.3g N m", worst);
    cli_free(&r);
}

/* What inverse refuses: no prescribed motion, a bad --prescribe (named as such), inputs
 * that act on a coordinate left free. */
static void test_inverse_refuses_what_it_cannot_do(void **state_)
{
    (void)state_;
    cli_result r = cli("inverse %scart.mech", MECH);
    CHECK(r.status == 2 && strstr(r.err, "prescribes no motion"), "%d %s", r.status, r.err);
    cli_free(&r);
    r = cli("inverse %scart.mech --prescribe 'sX=v0*t'", MECH);
    CHECK(r.status == 2 && strstr(r.err, "--prescribe:1:22: error: unknown name 'v0'"), "%s",
          r.err);
    cli_free(&r);
    r = cli("inverse %scart.mech --prescribe sX=-20*t --inputs Fx --tspan 0:1 --step 0.1",
            MECH);
    CHECK(r.status == 1 && strstr(r.err, "not prescribed"), "%d %s", r.status, r.err);
    cli_free(&r);
    r = cli("inverse %scart.mech --prescribe sX=-20*t --inputs Fx,Fy", MECH);
    CHECK(r.status == 2 && strstr(r.err, "give one for each"), "%d %s", r.status, r.err);
    cli_free(&r);
}

/* The cart's rear axle at theta = 0 says dsY = (length_cart/2) omega = omega: from
 * dsY = 0, omega = 2 the nearest admissible speeds (least squares) are dsY = omega = 1, and
 * dsX, on which the constraint does not depend at theta = 0, stays. Without --project-init
 * the state is refused with the constraint's name and value. */
static void test_project_init_takes_the_nearest_speeds(void **state_)
{
    (void)state_;
    cli_result r = cli("run %scart.mech --init dsY=0 --tspan 0:0.1 --step 0.1", MECH);
    CHECK(r.status == 2 && strstr(r.err, "does not hold constraint 'lambda': its value is -2"),
          "%d %s", r.status, r.err);
    cli_free(&r);
    r = cli("run %scart.mech --init dsY=0 --project-init --tspan 0:0.1 --step 0.1", MECH);
    CHECK(r.status == 0, "%s", r.err);
    CHECK(strstr(r.err, "dsY 0 -> ") && strstr(r.err, "omega 2 -> ") && !strstr(r.err, "dsX"),
          "%s", r.err);
    double v[64];
    int cols;
    CHECK(numbers(r.out, v, 64, &cols) == 2 && cols == 7, "%s", r.out);
    CHECK(fabs(v[5] - 1) < 1e-15 && fabs(v[6] - 1) < 1e-15 && v[4] == 2, "dsX %g dsY %.17g "
          "omega %.17g", v[4], v[5], v[6]);
    cli_free(&r);
    r = cli("run %sdouble_pendulum.mech --project-init --tspan 0:0.1", MECH);
    CHECK(r.status == 0 && strstr(r.err, "has no constraints; nothing changed"), "%s", r.err);
    cli_free(&r);
}

/* The four-bar from a crank angle off its loop: refused naming loop_x with its value, and
 * with --project-init closed to rounding, the speeds too (the gap output and the loop's
 * rate at t0). */
static void test_project_init_closes_the_fourbar(void **state_)
{
    (void)state_;
    cli_result r = cli("run %sfourbar.mech --init q1=1.1 --tspan 0:0.1", MECH);
    CHECK(r.status == 2 && strstr(r.err, "constraint 'loop_x': its value is -0.0867"), "%s",
          r.err);
    cli_free(&r);
    r = cli("run %sfourbar.mech --init q1=1.1 --init dq1=1 --project-init --outputs "
            "--tspan 0:0.1 --step 0.1", MECH);
    CHECK(r.status == 0, "%s", r.err);
    CHECK(strstr(r.err, "q1 1.1 -> ") && strstr(r.err, "dq1 1 -> "), "%s", r.err);
    double v[64];
    int cols; /* t q1 q2 q3 dq1 dq2 dq3 loop_x loop_y gap kinetic potential energy */
    CHECK(numbers(r.out, v, 64, &cols) == 2 && cols == 13, "%s", r.out);
    const double a = 1, b = 2.5, c = 2;
    const double rate_x = -a * sin(v[1]) * v[4] - b * sin(v[2]) * v[5] + c * sin(v[3]) * v[6];
    const double rate_y = a * cos(v[1]) * v[4] + b * cos(v[2]) * v[5] - c * cos(v[3]) * v[6];
    CHECK(v[9] < 1e-14 && fabs(rate_x) < 1e-14 && fabs(rate_y) < 1e-14,
          "gap %.3g, rates %.3g %.3g", v[9], rate_x, rate_y);
    cli_free(&r);
    /* linearize takes the same state: refused, then projected (the q1 of the run above) */
    r = cli("linearize %sfourbar.mech --init q1=1.1", MECH);
    CHECK(r.status == 2 && strstr(r.err, "constraint 'loop_x'"), "%d %s", r.status, r.err);
    cli_free(&r);
    r = cli("linearize %sfourbar.mech --init q1=1.1 --project-init", MECH);
    CHECK(r.status == 0 && strstr(r.out, "q1    = 1.08723940281"), "%s%s", r.out, r.err);
    cli_free(&r);
}

/* Units that do not add up, at their place with both units: a sum of m and 1/s, sin of a
 * length, a force in kg/s, a mass in kg m, the two sides of a constraint, a constraint
 * against its declared unit, a prescribed motion against its coordinate's. Undeclared
 * units and numbers written in a formula are not checked (l/2 is m). */
static void test_units_that_do_not_add_up_are_named(void **state_)
{
    (void)state_;
    const char *head = "coord x=1 [m], phi=0 [rad]\npar m=1 [kg], l=1 [m], w=2 [1/s], F=1 [N], "
                       "k=3\n";
    char buf[1024];
    snprintf(buf, sizeof buf, "%spoint p mass=m at (x + w, 0, 0)\n", head);
    mech_refused(buf, "bad.mech:3:22:", "the units do not add up: the terms are in m and in 1/s");
    snprintf(buf, sizeof buf, "%spoint p mass=m at (x, sin(x), 0)\n", head);
    mech_refused(buf, "bad.mech:3:27:", "sin of a quantity in m");
    snprintf(buf, sizeof buf, "%spoint p mass=m at (x, 0, 0)\nforce f on p = (F, m*w, 0)\n",
             head);
    mech_refused(buf, "bad.mech:4:20:", "force 'f' is in kg/s, not in N");
    snprintf(buf, sizeof buf, "%sbody b mass=m*l inertia=(1, 1, 1) at (x, 0, 0) rot z:phi\n",
             head);
    mech_refused(buf, "bad.mech:3:13:", "the mass of 'b' is in kg m, not in kg");
    snprintf(buf, sizeof buf, "%spoint p mass=m at (x, l*phi, 0)\nconstraint c [m]: x = dx\n",
             head);
    mech_refused(buf, "bad.mech:4:23:", "the sides of constraint 'c' are in m and in m/s");
    snprintf(buf, sizeof buf, "%spoint p mass=m at (x, l*phi, 0)\nconstraint c [m/s]: x = l\n",
             head);
    mech_refused(buf, "bad.mech:4:21:", "constraint 'c' is in m, not in m/s");
    snprintf(buf, sizeof buf, "%spoint p mass=m at (x, l*phi, 0)\nprescribe d: x = w*t\n",
             head);
    mech_refused(buf, "bad.mech:4:18:", "the sides of prescribe 'd' are in m and in 1");
    /* lenient: k has no unit, numbers take the unit they need */
    snprintf(buf, sizeof buf, "%spoint p mass=m at (x + k + 1, l/2*sin(phi) + 0.5, 0)\n"
             "init x=1\n", head);
    FILE *f = fopen(cli_path("good.mech"), "w");
    assert_non_null(f);
    fputs(buf, f);
    fclose(f);
    cli_result r = cli("run %s --tspan 0:0.1", cli_path("good.mech"));
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
}

/* The directions that move no mass and the combination of dependent constraints, with
 * their coefficients: p at (x + 2 z, y) does not move when dz = 1, dx = -2; c2's row
 * (2, 3) is 2 (1, 0) + 3 (0, 1), the rows of c1 and c3. */
static void test_singular_and_redundant_name_the_combination(void **state_)
{
    (void)state_;
    mech_refused("coord x=1, y=0, z=0\npoint p mass=1 at (x+2*z, y, 0)\n", "bad.mech:1:17:",
            "z moves no mass that the coordinates before it do not (the rates dz = 1, dx = -2 "
            "together move no mass");
    mech_refused("coord x=1, y=0\npoint p mass=1 at (x, y, 0)\nconstraint c1: x-1 = 0\n"
            "constraint c3: y = 0\nconstraint c2: 2*x-2 + 3*y = 0\n", "bad.mech:5:12:",
            "its row depends on those of c1, c3 (D[c2] = 2 D[c1] + 3 D[c3]");
}

/* A spring's law= names a function F(x, v) of the file; energy= a function G(x), F's
 * integral at v = 0 up to a constant: E = 3 x^2/2 + x^4/2 is refused at the stretch x = 1
 * (ground to s = 1, l0 = 0) with E'(1) = 5 against F(1, 0) = 4; G and G + 7 are taken. */
static void test_spring_laws_are_checked(void **state_)
{
    (void)state_;
    static const char *const cases[][3] = {
        {"law=H", "bad.mech:6:35:", "the law 'H' is not a function of the file: write "
                                     "H(x, v)=formula"},
        {"law=G", "bad.mech:6:35:", "the law 'G' has 1 argument; it takes 2: the stretch"},
        {"law=k", "bad.mech:6:35:", "the law 'k' is a parameter"},
        {"law=F energy=F", "bad.mech:6:44:", "the energy 'F' has 2 arguments; it takes 1"},
        {"law=F c=1", "bad.mech:6:37:", "spring 'h' has a law=: its tension is the law's alone"},
        {"k=k energy=G", "bad.mech:6:42:", "energy= of spring 'h' goes with a law="},
        {"law=F energy=E", "bad.mech:6:8:", "spring 'h': energy=E is not the integral of "
                                            "law=F: at the stretch x = 1 m, dE/dx = 5 N but "
                                            "F(x, 0) = 4 N"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char buf[512];
        snprintf(buf, sizeof buf, "par k=3\nF(x, v)=k*x + x^3\nG(x)=k*x^2/2 + x^4/4\n"
                 "coord s=1\npoint p mass=1 at (s, 0, 0)\nspring h between ground and p %s\n"
                 "E(x)=k*x^2/2 + x^4/2\n", cases[i][0]);
        mech_refused(buf, cases[i][1], cases[i][2]);
    }
    for (int shift = 0; shift < 2; shift++) {
        FILE *f = fopen(cli_path("good.mech"), "w");
        assert_non_null(f);
        fprintf(f, "par k=3\nF(x, v)=k*x + x^3\nG(x)=k*x^2/2 + x^4/4 + %d\ncoord s=1\n"
                "point p mass=1 at (s, 0, 0)\nspring h between ground and p law=F energy=G\n",
                7 * shift);
        fclose(f);
        cli_result r = cli("run %s --tspan 0:0.1", cli_path("good.mech"));
        CHECK(r.status == 0, "G + %d: %s", 7 * shift, r.err);
        cli_free(&r);
    }
}

/* A spring's law F(x, v) is a force and its energy G(x) an energy, with the stretch x in m
 * and its rate v in m/s: with k [N], k x is in N m; with k [N/m], an energy k x is in N;
 * each refused at its formula's start with both units, and a sum inside a law whose terms
 * differ (k x + c x with c [N s/m]; k x^3 + k x^2 with k [N/m^2]) at its operator. A law
 * of x, v and numbers alone in a file without units is taken, and F = k x + c v with its
 * energy k x^2 / 2 in N/m and N s/m. */
static void test_spring_law_units(void **state_)
{
    (void)state_;
    static const char *const cases[][4] = {
        {"k=3 [N]", "F(x, v)=k*x", "bad.mech:4:9:",
         "the law F(x, v) of spring 'h' is in N m, not in N (x in m, v in m/s)"},
        {"k=3 [N/m]", "F(x, v)=k*x + c*x", "bad.mech:4:13:",
         "the terms are in N and in kg m/s"},
        {"k=3 [N/m]", "F(x, v)=k*x + c*v\nG(x)=k*x", "bad.mech:5:6:",
         "the energy G(x) of spring 'h' is in N, not in J (x in m, v in m/s)"},
        {"k=3 [N/m^2]", "F(x, v)=k*x^2\nG(x)=k*x^3 + k*x^2", "bad.mech:5:12:",
         "the terms are in N m and in N"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char buf[512];
        snprintf(buf, sizeof buf, "par m=2 [kg], %s, c=0.5 [N s/m], L=1 [m]\ncoord s=1.8 [m]\n"
                 "point p mass=m at (s, 0, 0)\n%s\nspring h between ground and p law=F%s l0=L\n",
                 cases[i][0], cases[i][1], strstr(cases[i][1], "G(x)") ? " energy=G" : "");
        mech_refused(buf, cases[i][2], cases[i][3]);
    }
    static const char *const good[] = {
        "par m=2\ncoord s=1.8\npoint p mass=m at (s, 0, 0)\nF(x, v)=3*x + x^3 + v\n"
        "G(x)=3*x^2/2 + x^4/4\nspring h between ground and p law=F energy=G l0=1\n",
        "par m=2 [kg], k=3 [N/m], c=0.5 [N s/m]\ncoord s=1.8 [m]\n"
        "point p mass=m at (s, 0, 0)\nF(x, v)=k*x + c*v\nG(x)=k*x^2/2\n"
        "spring h between ground and p law=F energy=G l0=1\n",
    };
    for (size_t i = 0; i < sizeof good / sizeof *good; i++) {
        FILE *f = fopen(cli_path("good.mech"), "w");
        assert_non_null(f);
        fputs(good[i], f);
        fclose(f);
        cli_result r = cli("run %s --tspan 0:0.1", cli_path("good.mech"));
        CHECK(r.status == 0, "%s", r.err);
        cli_free(&r);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_inverse_cart_mech_matches_inverse_cart),
        cmocka_unit_test(test_inverse_gives_the_generalized_driving_force),
        cmocka_unit_test(test_inverse_refuses_what_it_cannot_do),
        cmocka_unit_test(test_project_init_takes_the_nearest_speeds),
        cmocka_unit_test(test_project_init_closes_the_fourbar),
        cmocka_unit_test(test_units_that_do_not_add_up_are_named),
        cmocka_unit_test(test_singular_and_redundant_name_the_combination),
        cmocka_unit_test(test_spring_laws_are_checked),
        cmocka_unit_test(test_spring_law_units),
    };
    return cmocka_run_group_tests(tests, setup_all, NULL);
}
