/* SPDX-License-Identifier: BSD-3-Clause */
/* test_mech_input.c — what a mechanism file may say about units, inertia and names
 * (docs/mechanisms.md, "Units", "Checks"; docs/reliability.md): a vector with a component in
 * 1 beside components in m, an unknown unit symbol (with the nearest known one), a unit
 * without brackets, units nested 30,000 brackets deep (refused at 200, in info, run and
 * derive), an inertia with a negative principal moment or one above the sum of the other two,
 * a negative mass, a zero-length joint axis, a wheel of radius 0 or without an axis, names
 * that collide with an output, a chain of 190,000 fixed quantities: each refused at its
 * FILE:LINE:COL naming the rule.
 * And `inertia=(...) about (x, y, z)` (or about pivot), moved to the mass centre by the
 * parallel-axis theorem: a rod about its end swings at sqrt(3 g / (2 L)) (linearize), and
 * the heavy top with its inertia about the tip moves as with it about its centre. */
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
    return cli_make_tmpdir_with_cache("mech_input", cache_dir, sizeof cache_dir);
}

static const char *const head = "coord th=0.3 [rad], ph=0.2 [rad], x=1 [m]\n"
                                "par m=1 [kg], l=1 [m], g=9.81 [m/s^2]\n";

static void refused(const char *body, const char *where, const char *what)
{
    char buf[2048];
    snprintf(buf, sizeof buf, "%s%s", head, body);
    mech_refused(buf, where, what);
}

/* A position's components each in m: -cos(th) (in 1, reading th in rad) beside l*... in m
 * is refused; a force likewise; numbers alone (0, 0.5) take the unit they need. */
static void test_vector_components_carry_its_unit(void **state_)
{
    (void)state_;
    refused("point p mass=m at (l*sin(th)*cos(ph), l*sin(th)*sin(ph), -cos(th))\n",
            "bad.mech:3:58:", "component z of the position of 'p' is in 1, beside components "
            "in m");
    refused("point p mass=m at (x, 0, 0)\nforce f on p = (m*g, th, 0)\n", "bad.mech:4:22:",
            "component y of force 'f' is in 1, beside components in N");
    char buf[1024];
    snprintf(buf, sizeof buf, "coord th=0.3 [rad]\npar m=1 [kg], l=1 [m]\n"
             "point p mass=m at (l*sin(th), 0.5, 0)\n");
    assert_int_equal(cli_write_file("good.mech", buf), 0);
    cli_result r = cli("run %s --tspan 0:0.1", cli_path("good.mech"));
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
}

/* [rd] is not a unit: refused at the symbol with the nearest one; a unit without brackets
 * says that units go in brackets; 30,000 nested brackets stop at 200 (info, run, derive). */
static void test_unit_symbols_and_brackets(void **state_)
{
    (void)state_;
    mech_refused("coord th=0.3 [rd]\npar m=1 [kg]\npoint p mass=m at (th, 0, 0)\n",
                 "bad.mech:1:15:", "unknown unit symbol 'rd' (did you mean 'rad'?)");
    mech_refused("coord th=0.3\npar m=1 [kg], l=2 [mm]\npoint p mass=m at (th, 0, 0)\n",
                 "bad.mech:2:20:", "unknown unit symbol 'mm'");
    mech_refused("coord y=0\npar m=1 [kg], g=9.81 m/s^2\ngravity 0, -g, 0\n"
                 "point p mass=m at (0, y, 0)\n",
                 "bad.mech:2:22:", "a unit goes in brackets after the value: [m/s^2]");
    mech_refused("coord y=0 m\npar m=1\npoint p mass=m at (0, y, 0)\n", "bad.mech:1:11:",
                 "a unit goes in brackets after the value: [m]");
    const int depth = 30000;
    char *text = malloc(2 * (size_t)depth + 128);
    assert_non_null(text);
    int k = sprintf(text, "coord q=0.1 [");
    for (int i = 0; i < depth; i++)
        text[k++] = '(';
    text[k++] = 'm';
    for (int i = 0; i < depth; i++)
        text[k++] = ')';
    sprintf(text + k, "]\npar m=1 [kg]\npoint p mass=m at (q, 0, 0)\n");
    assert_int_equal(cli_write_file("deep.mech", text), 0);
    free(text);
    static const char *const commands[] = {"info", "run", "derive"};
    for (int i = 0; i < 3; i++) {
        cli_result r = cli("%s %s", commands[i], cli_path("deep.mech"));
        CHECK(r.status == 2 && strstr(r.err, "deep.mech:1:214:") &&
              strstr(r.err, "parentheses nested deeper than 200 levels in a unit"),
              "%s: status %d\n%.300s", commands[i], r.status, r.err);
        cli_free(&r);
    }
}

/* No rigid body has a negative principal moment, or one above the sum of the other two
 * (here after a rotation: products make the principal moments); a negative mass is named. */
static void test_inertia_no_body_has(void **state_)
{
    (void)state_;
    refused("body b mass=m inertia=(-0.1, 1, 1) at (x, 0, 0) rot z:th\n", "bad.mech:3:24:",
            "has a negative principal moment");
    refused("body b mass=m inertia=(1, 1, 3) at (x, 0, 0) rot z:th\n", "bad.mech:3:24:",
            "greater than the sum of the other two, 3 > 1 + 1");
    /* the diagonal (1, 1, 1) with the product Ixy = 1: principal moments 0, 1 and 2 */
    refused("body b mass=m inertia=(1, 1, 1, 1, 0, 0) at (x, 0, 0) rot z:th\n",
            "bad.mech:3:24:", "greater than the sum of the other two, 2 >");
    refused("point p mass=-m at (x, 0, 0)\n", "bad.mech:3:14:",
            "the mass of 'p' is -1 at the initial state: a mass is not negative");
}

/* A joint's axis of length 0, a wheel of radius 0 or with an axis of length 0. */
static void test_zero_axes_and_radius(void **state_)
{
    (void)state_;
    refused("point p mass=m revolute ground (0, 0, 0):th pivot (0, l, 0)\n", "bad.mech:3:33:",
            "the axis of the joint of 'p' has length 0");
    const char *disk = "body d mass=m inertia=(1, 1, 2) at (x, 0, l*cos(th)) rot z:ph x:th\n";
    char buf[1024];
    snprintf(buf, sizeof buf, "%swheel w on d radius=0 axis=(0, 0, 1)\n", disk);
    refused(buf, "bad.mech:4:21:", "wheel 'w' has radius 0 at the initial state");
    snprintf(buf, sizeof buf, "%swheel w on d radius=l axis=(0, 0, 0)\n", disk);
    refused(buf, "bad.mech:4:29:", "wheel 'w' has an axis of length 0");
}

/* A constraint or coordinate named as another output. */
static void test_names_that_collide_with_outputs(void **state_)
{
    (void)state_;
    refused("point p mass=m at (x, 0, 0)\nconstraint kinetic: x = l\n", "bad.mech:4:12:",
            "'kinetic' is an output of every mechanism (its kinetic energy)");
    mech_refused("coord x=1 [m], y=0 [m]\npar m=1 [kg]\npoint p mass=m at (x, y, 0)\n"
                 "constraint y: x = 1\n", "bad.mech:4:12:",
                 "constraint 'y' shares its name with a coordinate or speed on line 1");
    mech_refused("coord energy=1 [m]\npar m=1 [kg]\npoint p mass=m at (energy, 0, 0)\n",
                 "bad.mech:1:7:", "'energy' is an output of every mechanism");
}

/* the largest difference between the numbers of two CSV texts (their headers skipped), or
 * INFINITY when they differ in shape */
static double table_difference(const char *a, const char *b)
{
    a = strchr(a, '\n');
    b = strchr(b, '\n');
    double worst = 0.0;
    while (a && b && a[1] && b[1]) {
        char *ea, *eb;
        const double x = strtod(a + 1, &ea), y = strtod(b + 1, &eb);
        if (ea == a + 1 || eb == b + 1)
            return ea == a + 1 && eb == b + 1 ? worst : INFINITY;
        if (*ea != *eb)
            return INFINITY;
        worst = fmax(worst, fabs(x - y));
        a = ea;
        b = eb;
    }
    return a && b && (a[1] != 0) == (b[1] != 0) ? worst : INFINITY;
}

/* inertia=(...) about a point: a uniform rod about its end, (m L^2/3, 0, m L^2/3) about its
 * pivot, swings at sqrt(3 g / (2 L)) for small angles and moves exactly as the rod written
 * about its centre; the heavy top written with its textbook inertia about the tip,
 * A + m L^2, moves as top.mech (A about the centre) within 1e-10 over 2 s. */
static void test_inertia_about_a_point(void **state_)
{
    (void)state_;
    static const char *const rods[] = {
        "inertia=(m*L^2/12, 0, m*L^2/12)",
        "inertia=(m*L^2/3, 0, m*L^2/3) about pivot",
        "inertia=(m*L^2/3, 0, m*L^2/3) about (0, L/2, 0)",
    };
    char *runs[3];
    for (int i = 0; i < 3; i++) {
        char text[512], name[32];
        snprintf(text, sizeof text, "coord th=0.4 [rad]\npar m=2 [kg], L=1.5 [m], "
                 "g=9.81 [m/s^2]\ngravity 0, -g, 0\nbody rod mass=m %s revolute ground z:th "
                 "pivot (0, L/2, 0)\n", rods[i]);
        snprintf(name, sizeof name, "rod%d.mech", i);
        assert_int_equal(cli_write_file(name, text), 0);
        cli_result r = cli("run %s --method dop853 --rtol 1e-12 --atol 1e-12 --tspan 0:3 "
                           "--step 0.1", cli_path(name));
        CHECK(r.status == 0, "%s", r.err);
        runs[i] = strdup(r.out);
        cli_free(&r);
        if (i == 0)
            continue;
        r = cli("linearize %s --init th=0", cli_path(name));
        const char *ev = strstr(r.out, "eigenvalues:");
        const char *row = ev ? strstr(ev, "\n") : NULL;
        row = row ? strstr(row + 1, "\n") : NULL;
        double re = NAN, im = NAN;
        CHECK(r.status == 0 && row && sscanf(row, "%lf %lf", &re, &im) == 2, "%s%s", r.out,
              r.err);
        const double w = sqrt(3 * 9.81 / (2 * 1.5));
        CHECK(fabs(fabs(im) - w) < 1e-9 && fabs(re) < 1e-9, "%.17g %.17g, closed form %.17g",
              re, im, w);
        cli_free(&r);
    }
    for (int i = 1; i < 3; i++)
        CHECK(table_difference(runs[0], runs[i]) < 1e-12, "%s about: %g", rods[i],
              table_difference(runs[0], runs[i]));
    for (int i = 0; i < 3; i++)
        free(runs[i]);
    size_t len;
    char *top = cli_read_file(MECH "top.mech", &len);
    assert_non_null(top);
    const char *centre = "inertia=(A, A, C)";
    char *at = strstr(top, centre), tip[4096];
    assert_non_null(at);
    snprintf(tip, sizeof tip, "%.*sinertia=(A + m*L^2, A + m*L^2, C) about (0, 0, -L)%s",
             (int)(at - top), top, at + strlen(centre));
    free(top);
    assert_int_equal(cli_write_file("top_tip.mech", tip), 0);
    cli_result a = cli("run %stop.mech --method dop853 --rtol 1e-12 --atol 1e-12 --tspan 0:2 "
                       "--outputs", MECH);
    cli_result b = cli("run %s --method dop853 --rtol 1e-12 --atol 1e-12 --tspan 0:2 "
                       "--outputs", cli_path("top_tip.mech"));
    const double diff = table_difference(a.out, b.out);
    CHECK(a.status == 0 && b.status == 0 && diff < 1e-10, "%g\n%s%s", diff, a.err, b.err);
    cli_free(&a);
    cli_free(&b);
    /* about pivot needs a joint */
    refused("body b mass=m inertia=(1, 1, 1) about pivot at (x, 0, 0) rot z:th\n",
            "bad.mech:3:38:", "'about pivot' needs a joint with a pivot");
}

/* A chain of 190,000 fixed quantities (x1 = x0 + q, ...) in a position overflowed the stack
 * where they are inlined; it stops at 1600 levels with FILE:LINE:COL, as derivatives do. */
static void test_deep_chains_are_bounded(void **state_)
{
    (void)state_;
    const int n = 190000;
    FILE *f = fopen(cli_path("chain.mech"), "w");
    assert_non_null(f);
    fprintf(f, "coord q=0.1 [m]\npar m=1 [kg]\nx0=q\n");
    for (int i = 1; i < n; i++)
        fprintf(f, "x%d=x%d+q\n", i, i - 1);
    fprintf(f, "point p mass=m at (x%d, 0, 0)\n", n - 1);
    assert_int_equal(fclose(f), 0);
    cli_result r = cli("info %s", cli_path("chain.mech"));
    CHECK(r.status == 2 && strstr(r.err, "chain.mech:") &&
          strstr(r.err, "nested too deeply through the fixed quantities it reads"),
          "status %d\n%.400s", r.status, r.err);
    cli_free(&r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_vector_components_carry_its_unit),
        cmocka_unit_test(test_unit_symbols_and_brackets),
        cmocka_unit_test(test_inertia_no_body_has),
        cmocka_unit_test(test_zero_axes_and_radius),
        cmocka_unit_test(test_names_that_collide_with_outputs),
        cmocka_unit_test(test_inertia_about_a_point),
        cmocka_unit_test(test_deep_chains_are_bounded),
    };
    return cmocka_run_group_tests(tests, setup_all, cli_remove_tmpdir);
}
