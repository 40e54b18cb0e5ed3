/* SPDX-License-Identifier: BSD-3-Clause */
/* test_mech_project.c — --project-init and `dynkit inverse FILE.mech` from guesses that do
 * not hold the constraints (docs/mechanisms.md, "Initial values"): a four-bar driven at its
 * crank (tests/mbs/fourbar_drive.mech) from guesses with its loop open by 0.8 m reaches the
 * loop, and its motor torque at t = 0 equals the closed form by the power balance
 * tau omega = dT/dt + dV/dt on the loop solved by hand (the two circles' intersection, its
 * rates by finite differences); a guess below the line closes the other assembly mode, named
 * by its determinant's sign, and one on the other side of a singular configuration says so;
 * links that cannot close, an impossible constraint (x^2 + y^2 = -R^2) and a coordinate of
 * 1e16 stop with exit 1, naming each constraint and its value, and print no table. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>

#include "test_cli_run.h"
#include "test_util.h"

#define PI 3.14159265358979323846

#define FOURBAR DYNKIT_SOURCE_DIR "/tests/mbs/fourbar_drive.mech"
#define MECH DYNKIT_SOURCE_DIR "/examples/mechanisms/"

static char cache_dir[512];

static int setup_all(void **state)
{
    (void)state;
    return cli_make_tmpdir_with_cache("mech_project", cache_dir, sizeof cache_dir);
}

static const double A = 0.3, B = 0.9, C = 0.6, D = 1.0, RHO = 1.0, G = 9.81;

/* the pose at time t of the four-bar with th = 2 pi t: the mass centres (x, y) of crank,
 * coupler, rocker in p[0..5] and their angles in p[6..8]; up: B above the line AD */
static void pose(double t, int up, double *p)
{
    const double th = 2 * PI * t, ax = A * cos(th), ay = A * sin(th);
    const double dx = D - ax, dy = -ay, r = hypot(dx, dy);
    const double along = (B * B - C * C + r * r) / (2 * r), h = sqrt(B * B - along * along);
    const double sgn = up ? 1.0 : -1.0; /* B to the left of A->D, or to its right */
    const double bx = ax + along * dx / r - sgn * h * dy / r;
    const double by = ay + along * dy / r + sgn * h * dx / r;
    const double ga = atan2(by - ay, bx - ax), be = atan2(by, bx - D);
    p[0] = ax / 2, p[1] = ay / 2;
    p[2] = (ax + bx) / 2, p[3] = (ay + by) / 2;
    p[4] = (D + bx) / 2, p[5] = by / 2;
    p[6] = th, p[7] = ga, p[8] = be;
}

/* the motor torque at t: (dT/dt + dV/dt) / omega, rates by fourth-order differences */
static double motor_torque(double t, int up)
{
    const double hs = 1e-3, w[5] = {1, -8, 0, 8, -1}, w2[5] = {-1, 16, -30, 16, -1};
    double p[5][9], v[9] = {0}, acc[9] = {0};
    for (int k = 0; k < 5; k++)
        pose(t + (k - 2) * hs, up, p[k]);
    for (int i = 0; i < 9; i++) {
        for (int k = 0; k < 5; k++) {
            double x = p[k][i];
            if (i >= 6) /* an angle: unwrapped about the middle one */
                x = p[2][i] + remainder(x - p[2][i], 2 * PI);
            v[i] += w[k] * x / (12 * hs);
            acc[i] += w2[k] * x / (12 * hs * hs);
        }
    }
    const double m[3] = {RHO * A, RHO * B, RHO * C};
    const double len[3] = {A, B, C};
    double power = 0.0;
    for (int j = 0; j < 3; j++) {
        const double I = m[j] * len[j] * len[j] / 12;
        power += m[j] * (v[2 * j] * acc[2 * j] + v[2 * j + 1] * acc[2 * j + 1]) +
                 I * v[6 + j] * acc[6 + j] + m[j] * G * v[2 * j + 1];
    }
    return power / (2 * PI);
}

/* the motor's torque at t = 0 in inverse's table (its first row, second column) */
static double first_torque(const char *out)
{
    const char *row = strchr(out, '\n');
    const char *comma = row ? strchr(row, ',') : NULL;
    return comma ? strtod(comma + 1, NULL) : NAN;
}

/* The file's guess and the others (the loop open by 0.8 m) reach the loop with B
 * above the line: the torque of the closed form, -0.92 N m (it was 1815.96 with the loop
 * left open). */
static void test_poor_guesses_reach_the_loop(void **state_)
{
    (void)state_;
    const double want = motor_torque(0.0, 1);
    CHECK(fabs(want + 0.9197) < 1e-3, "closed form %.17g", want);
    static const char *const guesses[] = {"", "--init ga=0.1 --init be=3.0",
                                          "--init ga=0.3 --init be=3.1"};
    for (int i = 0; i < 3; i++) {
        cli_result r = cli("inverse %s %s --tspan 0:0.1", FOURBAR, guesses[i]);
        const double got = first_torque(r.out);
        CHECK(r.status == 0 && fabs(got - want) < 1e-6, "guess '%s': status %d, torque %.17g, "
              "closed form %.17g\n%s", guesses[i], r.status, got, want, r.err);
        CHECK(strstr(r.err, "assembly mode where det d(lx,ly,motor)/d(th,ga,be) < 0"), "%s",
              r.err);
        cli_free(&r);
    }
}

/* From ga = -0.7, be = -1.6 the loop closes with B below the line: the other assembly mode,
 * named by the determinant's other sign, with that mode's torque; from ga = 1, be = 0.5 (the
 * lower mode's side) the projection ends in the upper mode and says it went through a
 * singular configuration, under --quiet too. */
static void test_the_assembly_mode_is_named(void **state_)
{
    (void)state_;
    const double want = motor_torque(0.0, 0);
    cli_result r = cli("inverse %s --init ga=-0.7 --init be=-1.6 --tspan 0:0.1", FOURBAR);
    const double got = first_torque(r.out);
    CHECK(r.status == 0 && fabs(got - want) < 1e-6 && fabs(want - motor_torque(0, 1)) > 1,
          "status %d, torque %.17g, closed form %.17g\n%s", r.status, got, want, r.err);
    CHECK(strstr(r.err, "assembly mode where det d(lx,ly,motor)/d(th,ga,be) > 0") &&
          strstr(r.err, "be=-1.618433389419"), "%s", r.err);
    cli_free(&r);
    r = cli("inverse %s --init ga=1 --init be=0.5 --tspan 0:0.1 --quiet", FOURBAR);
    CHECK(r.status == 0 && strstr(r.err, "the start was in the other mode (> 0): the "
          "projection went through a singular configuration"), "%d %s", r.status, r.err);
    cli_free(&r);
}

/* Links that cannot close at t = 0 (c = 0.1: |b - c| = 0.8 > |AD| = 0.7): exit 1 naming
 * each constraint and its value, no table, under --quiet too; as --project-init of run. */
static void test_a_loop_that_cannot_close_stops(void **state_)
{
    (void)state_;
    for (int quiet = 0; quiet < 2; quiet++) {
        cli_result r = cli("inverse %s --set c=0.1 --tspan 0:0.1%s", FOURBAR,
                           quiet ? " --quiet" : "");
        CHECK(r.status == 1 && r.out[0] == '\0', "status %d\n%s", r.status, r.out);
        CHECK(strstr(r.err, "did not bring") && strstr(r.err, "constraint 'lx' is ") &&
              strstr(r.err, "constraint 'ly' is ") && strstr(r.err, "(does not hold)") &&
              strstr(r.err, "give --init values of th, ga, be nearer"), "%s", r.err);
        cli_free(&r);
    }
    cli_result r = cli("run %s --set c=0.1 --project-init --tspan 0:0.1", FOURBAR);
    CHECK(r.status == 1 && r.out[0] == '\0' && strstr(r.err, "constraint 'lx' is "), "%d %s",
          r.status, r.err);
    cli_free(&r);
}

/* x^2 + y^2 = -R^2 holds nowhere; q1 = 1e16 leaves the four-bar's angle no resolution:
 * both stop with exit 1 (they ran on with exit 0). */
static void test_impossible_projections_stop(void **state_)
{
    (void)state_;
    assert_int_equal(cli_write_file("impossible.mech",
                                    "coord x=1 [m], y=0 [m]\n"
                                    "par R=1 [m], m=1 [kg], g=9.81 [m/s^2]\n"
                                    "gravity 0, -g, 0\n"
                                    "point p mass=m at (x, y, 0)\n"
                                    "constraint rod: x^2 + y^2 = -R^2\n"),
                     0);
    cli_result r = cli("run %s --project-init --tspan 0:0.1",
                       cli_path("impossible.mech"));
    CHECK(r.status == 1 && r.out[0] == '\0' && strstr(r.err, "constraint 'rod' is 1 (does "
          "not hold)"), "%d %s", r.status, r.err);
    cli_free(&r);
    r = cli("run %sfourbar.mech --init q1=1e16 --project-init --tspan 0:0.1 --quiet", MECH);
    CHECK(r.status == 1 && r.out[0] == '\0' && strstr(r.err, "constraint 'loop_x' is ") &&
          strstr(r.err, "q1 = 1e16: the doubles near it are 2 apart"), "%d %s", r.status,
          r.err);
    cli_free(&r);
    r = cli("run %sfourbar.mech --init q1=1e16 --tspan 0:0.1", MECH);
    CHECK(r.status == 2 && strstr(r.err, "does not hold constraint 'loop_x'"), "%d %s",
          r.status, r.err);
    cli_free(&r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_poor_guesses_reach_the_loop),
        cmocka_unit_test(test_the_assembly_mode_is_named),
        cmocka_unit_test(test_a_loop_that_cannot_close_stops),
        cmocka_unit_test(test_impossible_projections_stop),
    };
    return cmocka_run_group_tests(tests, setup_all, cli_remove_tmpdir);
}
