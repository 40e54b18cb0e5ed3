/* SPDX-License-Identifier: BSD-3-Clause */
/* test_mech_scene.c — the picture of a mechanism (dynkit/mbs.h, dyn_mech_scene_*; the
 * geometry statements of docs/mechanisms.md): the statements read with their numbers and
 * refused at FILE:LINE:COL with what is accepted; the bodies' poses and the shapes' points
 * against the formulas by hand — a pendulum's tip at (L sin q, -L cos q), the top's axis at
 * (sin th sin psi, -sin th cos psi, cos th) of its ZXZ angles, a double pendulum by joints
 * at the sums of its relative angles, joints about and along tilted axes, the rolling disk's contact point under its centre;
 * and the page of `dynkit animate` carrying the double pendulum's poses at every sample,
 * equal to the formulas evaluated at the page's own samples of the coordinates. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>

#include "dynkit/dynkit.h"
#include "dynkit/mbs.h"
#include "test_cli_run.h"
#include "test_util.h"
#include "test_mech_util.h"

#define MECH DYNKIT_SOURCE_DIR "/examples/mechanisms/"

static char cache_dir[512];

static int setup_all(void **state)
{
    (void)state;
    return cli_make_tmpdir_with_cache("mech-scene", cache_dir, sizeof cache_dir);
}

static const char *pendulum =
    "coord q=0.3 [rad]\n"
    "par m=1 [kg], L=0.7 [m], g=9.81 [m/s^2]\n"
    "gravity 0, -g, 0\n"
    "point bob mass=m at (L*sin(q), -L*cos(q), 0)\n"
    "constraint hold [m]: q - 0.3 + 0*t = 0\n"
    "rod arm between ground and bob color grey\n"
    "sphere ball on bob radius L/10 color red\n"
    "box plate on ground at (0, 0.05, 0) size (0.4, 0.02, 2*L)\n"
    "disk face on bob radius 0.05 axis x\n"
    "cylinder hub on bob radius 0.02 length 0.1 at (0, 0, 0.1)\n"
    "frame ground size 0.3\n"
    "ground at (0, -1, 0) size 3\n"
    "trace tip on bob at (0.1, 0, 0) color blue\n"
    "arrow hold on bob along (cos(q), sin(q), 0)\n";

/* every statement read: kinds, bodies, colours, the place, and the numbers */
static void test_statements_read(void **state_)
{
    (void)state_;
    dyn_mech_scene *sc = mech_scene_of(pendulum);
    static const dyn_mech_shape_kind kinds[] = {
        DYN_MECH_ROD,      DYN_MECH_SPHERE, DYN_MECH_BOX,    DYN_MECH_CYLINDER, DYN_MECH_CYLINDER,
        DYN_MECH_FRAME,    DYN_MECH_GROUND, DYN_MECH_TRACE,  DYN_MECH_ARROW};
    const int n = (int)(sizeof kinds / sizeof *kinds);
    CHECK(dyn_mech_scene_n_shapes(sc) == n, "%d shapes", dyn_mech_scene_n_shapes(sc));
    for (int i = 0; i < n; i++) {
        const dyn_mech_shape *s = dyn_mech_scene_shape(sc, i);
        CHECK(s->kind == kinds[i] && s->line == 6 + i && s->col == 1, "shape %d: kind %d at %d:%d",
              i, (int)s->kind, s->line, s->col);
    }
    CHECK(strcmp(dyn_mech_scene_shape(sc, 1)->color, "#d62728") == 0, "red");
    CHECK(dyn_mech_scene_shape(sc, 2)->color == NULL, "no colour: the run's");
    CHECK(dyn_mech_scene_shape(sc, 2)->body == -1 && dyn_mech_scene_shape(sc, 1)->body == 0,
          "bodies");
    CHECK(strcmp(dyn_mech_scene_constraint(sc, dyn_mech_scene_shape(sc, 8)->constraint), "hold") == 0,
          "the arrow's constraint");
    double g[3];
    dyn_mech_scene_gravity(sc, g);
    CHECK(g[0] == 0 && g[1] == -9.81 && g[2] == 0, "gravity %g %g %g", g[0], g[1], g[2]);
    /* the mass of all bodies at the default parameters (the page's weight m g, below 1e-9
     * of which a force is not drawn): 1.5 kg and 2 x 0.25 kg */
    CHECK(dyn_mech_scene_mass(sc) == 1.0, "the pendulum's mass %g", dyn_mech_scene_mass(sc));
    dyn_mech_scene *two = mech_scene_of("par m1=1.5 [kg], m2=0.25 [kg]\ncoord a=0.2 [m]\n"
                                    "point p mass=m1 at (a, 0, 0)\n"
                                    "body b mass=2*m2 inertia=(1, 1, 1) at (0, a, 0)\n");
    CHECK(dyn_mech_scene_mass(two) == 2.0, "two bodies' mass %g", dyn_mech_scene_mass(two));
    dyn_mech_scene_free(two);
    /* at q = 1.1: the tip of the pendulum, the shapes' numbers */
    const double L = 0.7, q = 1.1, y[2] = {q, 0.0}, par[3] = {1, L, 9.81};
    CHECK(dyn_mech_scene_n_params(sc) == 3, "params");
    double pose[12], v[256];
    assert_true(dyn_mech_scene_n_values(sc) <= 256);
    assert_int_equal(dyn_mech_scene_eval(sc, 0.0, y, par, pose, v), 0);
    const double tip[3] = {L * sin(q), -L * cos(q), 0};
    for (int k = 0; k < 3; k++)
        CHECK(fabs(pose[k] - tip[k]) < 1e-15, "x[%d] = %.17g, want %.17g", k, pose[k], tip[k]);
    for (int k = 0; k < 9; k++) /* a point mass: the identity */
        CHECK(pose[3 + k] == (k % 4 == 0), "R[%d] = %g", k, pose[3 + k]);
    const double *rod = v + dyn_mech_scene_shape(sc, 0)->offset;
    CHECK(rod[0] == 0 && rod[1] == 0 && rod[2] == 0 && fabs(rod[3] - tip[0]) < 1e-15 &&
              fabs(rod[4] - tip[1]) < 1e-15, "the rod from the pivot to the bob");
    CHECK(fabs(v[dyn_mech_scene_shape(sc, 1)->offset + 3] - L / 10) < 1e-15, "radius L/10");
    const double *box = v + dyn_mech_scene_shape(sc, 2)->offset;
    CHECK(box[1] == 0.05 && box[3] == 0.2 && box[4] == 0.01 && fabs(box[5] - L) < 1e-15,
          "the box's centre and half sizes");
    const double *disk = v + dyn_mech_scene_shape(sc, 3)->offset;
    CHECK(disk[4] == 0 && disk[5] == 1 && disk[6] == 0 && disk[7] == 0, "a disk along x");
    const double *hub = v + dyn_mech_scene_shape(sc, 4)->offset;
    CHECK(fabs(hub[2] - 0.1) < 1e-15 && hub[4] == 0.05 && hub[7] == 1,
          "the hub 0.1 m along z from the bob (offsets of a point mass in N), half length");
    const double *gr = v + dyn_mech_scene_shape(sc, 6)->offset;
    CHECK(gr[1] == -1 && gr[3] == 0 && gr[4] == 1 && gr[5] == 0 && gr[6] == 1.5,
          "the ground's normal against gravity, half size");
    const double *tr = v + dyn_mech_scene_shape(sc, 7)->offset;
    CHECK(fabs(tr[0] - tip[0] - 0.1) < 1e-15, "the traced point");
    const double *ar = v + dyn_mech_scene_shape(sc, 8)->offset;
    CHECK(fabs(ar[3] - cos(q)) < 1e-15 && fabs(ar[4] - sin(q)) < 1e-15,
          "the arrow's unit direction");
    dyn_mech_scene_free(sc);
}

/* no geometry: a sphere per point mass, a sphere and the axes per rigid body, the springs */
static void test_default_drawing(void **state_)
{
    (void)state_;
    dyn_mech_scene *sc = mech_scene_of_file(MECH "plane_quat.mech");
    int spheres = 0, frames = 0, springs = 0;
    for (int i = 0; i < dyn_mech_scene_n_shapes(sc); i++) {
        const dyn_mech_shape *s = dyn_mech_scene_shape(sc, i);
        spheres += s->kind == DYN_MECH_SPHERE;
        frames += s->kind == DYN_MECH_FRAME;
        springs += s->kind == DYN_MECH_SPRING;
        CHECK(s->line == 0 || s->kind == DYN_MECH_SPRING, "a default shape has no line");
    }
    CHECK(spheres == 1 && frames == 1 && springs == 1, "%d spheres, %d frames, %d springs",
          spheres, frames, springs);
    dyn_mech_scene_free(sc);
}

static void expect_error(const char *geometry, const char *where, const char *what)
{
    char text[2048];
    snprintf(text, sizeof text,
             "coord q=0.3\npar m=1, L=1\npoint bob mass=m at (L*sin(q), -L*cos(q), 0)\n"
             "constraint c1: q - 0.3 = 0\n%s\n", geometry);
    dyn_mech_scene *sc = NULL;
    dyn_lang_diag d;
    char buf[2048];
    CHECK(dyn_mech_scene_read("bad.mech", text, strlen(text), NULL, 0, &sc, &d) == 2 && !sc,
          "accepted: %s", geometry);
    dyn_lang_diag_format(&d, buf, sizeof buf);
    CHECK(strstr(buf, where) && strstr(buf, what), "expected '%s' and '%s' in:\n%s", where,
          what, buf);
    /* the model refuses it the same way */
    FILE *f = fopen(cli_path("bad.mech"), "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
    cli_result r = cli("info %s", cli_path("bad.mech"));
    CHECK(r.status == 2 && strstr(r.err, where) && strstr(r.err, what),
          "dynkit info: status %d:\n%s", r.status, r.err);
    cli_free(&r);
}

static void test_errors_name_the_place(void **state_)
{
    (void)state_;
    expect_error("box b on bob size (1, 2)", "bad.mech:5:24:", "expected ',' in the size");
    expect_error("box b on bob", "bad.mech:5:1:", "box 'b' has no size: write size (lx, ly, lz)");
    expect_error("sphere s on wall", "bad.mech:5:13:", "unknown body 'wall'");
    expect_error("sphere s on bob color purpel", "bad.mech:5:23:",
                 "unknown colour 'purpel' (did you mean 'purple'?)");
    expect_error("sphere s on bob radius 0.1 width 2", "bad.mech:5:28:",
                 "unknown word 'width' in a sphere: expected radius, at, color");
    expect_error("sphere s on bob radius 0.1*LL", "bad.mech:5:28:", "unknown name 'LL'");
    expect_error("cylinder c on bob radius 1 length 2 axis w", "bad.mech:5:42:",
                 "unknown axis 'w': x, y or z");
    expect_error("disk d on bob axis z", "bad.mech:5:1:", "disk 'd' needs radius R");
    expect_error("rod r between bob or ground", "bad.mech:5:19:",
                 "expected 'and' between the rod's two ends");
    expect_error("arrow c2 on bob along (1, 0, 0)", "bad.mech:5:7:",
                 "unknown constraint 'c2' (did you mean 'c1'?)");
    expect_error("arrow c1 on bob", "bad.mech:5:1:", "arrow 'c1' has no direction");
    expect_error("arrow c1 on bob along (1, 0, 0) in B", "bad.mech:5:1:",
                 "'in B' needs a rigid body");
    expect_error("frame bob size", "bad.mech:5:15:", "expected size");
}

/* the top's axis: ZXZ angles, R = R_z(phi) R_x(theta) R_z(psi), a point (0, 0, s) of B at
 * x + R'(0, 0, s) = (L + s) (sin th sin psi, -sin th cos psi, cos th) */
static void test_rigid_body_points_follow_the_rotation(void **state_)
{
    (void)state_;
    dyn_mech_scene *sc = mech_scene_of_file(MECH "top.mech");
    int tr = -1;
    for (int i = 0; i < dyn_mech_scene_n_shapes(sc); i++)
        if (dyn_mech_scene_shape(sc, i)->kind == DYN_MECH_TRACE)
            tr = i;
    CHECK(tr >= 0, "the top's file traces its axis");
    double par[5] = {1, 0.1, 0.002, 0.004, 9.81}; /* m, L, A, C, g as in the file */
    const double L = par[1];
    srand(7);
    double worst = 0;
    for (int k = 0; k < 100; k++) {
        const double psi = 6.0 * rand() / RAND_MAX - 3, th = 3.0 * rand() / RAND_MAX,
                     phi = 6.0 * rand() / RAND_MAX - 3;
        const double y[6] = {psi, th, phi, 0, 0, 0};
        double pose[12], v[256];
        assert_int_equal(dyn_mech_scene_eval(sc, 0, y, par, pose, v), 0);
        const double e[3] = {sin(th) * sin(psi), -sin(th) * cos(psi), cos(th)};
        const double *p = v + dyn_mech_scene_shape(sc, tr)->offset;
        for (int j = 0; j < 3; j++) {
            worst = fmax(worst, fabs(pose[j] - L * e[j]));
            worst = fmax(worst, fabs(p[j] - 1.5 * L * e[j]));
            worst = fmax(worst, fabs(pose[3 + 6 + j] - e[j])); /* row z of R: B's z in N */
        }
    }
    CHECK(worst < 1e-15, "largest difference %.3g", worst);
    dyn_mech_scene_free(sc);
}

/* joints compose: bob2 at (l1 sin p1 + l2 sin(p1 + p2), -l1 cos p1 - l2 cos(p1 + p2)) */
static void test_joint_poses_compose(void **state_)
{
    (void)state_;
    dyn_mech_scene *sc = mech_scene_of_file(MECH "double_pendulum_joints.mech");
    CHECK(dyn_mech_scene_n_bodies(sc) == 2, "two bodies");
    const double par[5] = {1, 1, 1, 1, 9.81}; /* m1, m2, l1, l2, g */
    double worst = 0;
    srand(11);
    for (int k = 0; k < 100; k++) {
        const double p1 = 6.0 * rand() / RAND_MAX - 3, p2 = 6.0 * rand() / RAND_MAX - 3;
        const double y[4] = {p1, p2, 0, 0};
        double pose[24], v[256];
        assert_int_equal(dyn_mech_scene_eval(sc, 0, y, par, pose, v), 0);
        worst = fmax(worst, fabs(pose[0] - sin(p1)) + fabs(pose[1] + cos(p1)));
        worst = fmax(worst, fabs(pose[12] - sin(p1) - sin(p1 + p2)) +
                                fabs(pose[13] + cos(p1) + cos(p1 + p2)));
    }
    CHECK(worst < 1e-14, "largest difference %.3g", worst);
    dyn_mech_scene_free(sc);
}

/* joints about and along axis vectors: a pendulum about n = (0, sin b, cos b) with its
 * pivot (0, l cos b, -l sin b) square to n swings on (l sin p, -l cos p cos b, l cos p sin b)
 * (Rodrigues: R' pivot = cos p pivot + sin p n x pivot); a sled from (0, 0, 1) along
 * (cos a, sin a, 0) is at (s cos a, s sin a, 1) */
static void test_joint_axis_vectors(void **state_)
{
    (void)state_;
    dyn_mech_scene *sc = mech_scene_of("coord phi=0 [rad], s=0 [m]\n"
                                   "par l=0.5 [m], beta=0.3, alpha=0.4, g=9.81 [m/s^2]\n"
                                   "gravity 0, -g, 0\n"
                                   "point bob mass=1 revolute ground (0, sin(beta), cos(beta)):phi "
                                   "pivot (0, l*cos(beta), -l*sin(beta))\n"
                                   "point sled mass=2 prismatic ground(0, 0, 1) (2*cos(alpha), "
                                   "2*sin(alpha), 0):s\n");
    const double l = 0.5, b = 0.3, a = 0.4, par[4] = {l, b, a, 9.81};
    double worst = 0;
    for (int k = 0; k < 50; k++) {
        const double p = -3 + 0.12 * k, sl = 0.7 * k - 10, y[4] = {p, sl, 0, 0};
        double pose[24], v[64];
        assert_int_equal(dyn_mech_scene_eval(sc, 0, y, par, pose, v), 0);
        const double bob[3] = {l * sin(p), -l * cos(p) * cos(b), l * cos(p) * sin(b)};
        const double sled[3] = {sl * cos(a), sl * sin(a), 1};
        for (int j = 0; j < 3; j++)
            worst = fmax(worst, fmax(fabs(pose[j] - bob[j]), fabs(pose[12 + j] - sled[j])));
    }
    CHECK(worst < 1e-14, "largest difference %.3g m", worst);
    dyn_mech_scene_free(sc);
}

/* the rolling disk's wheel: its disk along the axle, the rolling forces at (x, y, 0) */
static void test_wheel_contact_under_the_disk(void **state_)
{
    (void)state_;
    dyn_mech_scene *sc = mech_scene_of_file(MECH "rolling_disk.mech");
    const double par[4] = {1, 0.3, 9.81, 10};
    const double y[10] = {0.4, -0.2, 0.7, 0.25, 1.3, 0, 0, 0, 0, 0}; /* x y psi theta phi */
    double pose[12], v[256];
    assert_int_equal(dyn_mech_scene_eval(sc, 0, y, par, pose, v), 0);
    int arrows = 0, disks = 0;
    for (int i = 0; i < dyn_mech_scene_n_shapes(sc); i++) {
        const dyn_mech_shape *s = dyn_mech_scene_shape(sc, i);
        const double *p = v + s->offset;
        if (s->kind == DYN_MECH_ARROW) {
            arrows++;
            CHECK(fabs(p[0] - 0.4) < 1e-15 && fabs(p[1] + 0.2) < 1e-15 && fabs(p[2]) < 1e-15,
                  "contact (%.17g, %.17g, %.17g)", p[0], p[1], p[2]);
        }
        if (s->kind == DYN_MECH_CYLINDER) {
            disks++;
            /* the axle: B's y axis, row y of R = R_y(phi) R_x(theta) R_z(psi) */
            const double a[3] = {-cos(0.25) * sin(0.7), cos(0.25) * cos(0.7), sin(0.25)};
            for (int j = 0; j < 3; j++)
                CHECK(fabs(p[5 + j] - a[j]) < 1e-15, "axis[%d] %.17g, want %.17g", j,
                      p[5 + j], a[j]);
            CHECK(fabs(p[3] - 0.3) < 1e-15, "radius r");
        }
    }
    CHECK(arrows == 2 && disks == 1, "%d arrows, %d disks", arrows, disks);
    dyn_mech_scene_free(sc);
}

/* the numbers after key (an array [a,b,...] or one number) into v; returns the count */
static int json_numbers(const char **s, double *v, int cap)
{
    const char *p = *s;
    int n = 0;
    if (*p != '[') {
        v[0] = strtod(p, (char **)s);
        return 1;
    }
    p++;
    while (*p && *p != ']') {
        char *end;
        const double x = strtod(p, &end);
        if (n < cap)
            v[n++] = x;
        p = *end == ',' ? end + 1 : end;
    }
    *s = p + 1;
    return n;
}

/* the page of dynkit animate: the poses it carries are the formulas at its samples */
static void test_page_carries_the_poses(void **state_)
{
    (void)state_;
    cli_result r = cli("animate %sdouble_pendulum.mech --method rk4 --step 0.01 --tspan 0:2 "
                       "--no-ani -o %s", MECH, cli_path("dp.html"));
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    char *html = cli_read_file(cli_path("dp.html"), NULL);
    /* the same run's coordinates to 17 digits */
    r = cli("run %sdouble_pendulum.mech --method rk4 --step 0.01 --tspan 0:2", MECH);
    CHECK(r.status == 0, "%s", r.err);
    static double p1[4000], p2[4000], x2[4000], y2[4000];
    int n = 0;
    for (const char *line = strchr(r.out, '\n'); line && line[1] && n < 4000;
         line = strchr(line + 1, '\n')) {
        double t;
        CHECK(sscanf(line + 1, "%lf,%lf,%lf", &t, &p1[n], &p2[n]) == 3, "a row: %.40s", line);
        n++;
    }
    cli_free(&r);
    CHECK(n == 201, "%d samples", n);
    const char *m = strstr(html, "\"mech\":{");
    CHECK(m, "no mechanism in the page");
    m = strstr(m, "\"poses\":[[");
    assert_non_null(m);
    m += strlen("\"poses\":[");
    /* body 1 (bob1) then body 2: [x, y, z, R...] */
    m = strstr(m + 1, "],[[");
    assert_non_null(m);
    m += 3;
    CHECK(json_numbers(&m, x2, 4000) == n, "x of bob2");
    m++;
    CHECK(json_numbers(&m, y2, 4000) == n, "y of bob2");
    double worst = 0;
    for (int k = 0; k < n; k++) {
        worst = fmax(worst, fabs(x2[k] - (sin(p1[k]) + sin(p2[k]))));
        worst = fmax(worst, fabs(y2[k] + cos(p1[k]) + cos(p2[k])));
    }
    /* written with 9 significant digits on the page */
    CHECK(worst < 5e-9, "bob2 off the formula by %.3g m", worst);
    CHECK(strstr(html, "\"kind\":\"trace\",\"name\":\"tip\""), "the traced tip");
    free(html);
    /* the example of animate --help */
    r = cli("animate %stop.mech --output %s", MECH, cli_path("top.html"));
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    html = cli_read_file(cli_path("top.html"), NULL);
    CHECK(strstr(html, "\"kind\":\"cylinder\",\"name\":\"crown\""), "the top's crown");
    free(html);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_statements_read),
        cmocka_unit_test(test_default_drawing),
        cmocka_unit_test(test_errors_name_the_place),
        cmocka_unit_test(test_rigid_body_points_follow_the_rotation),
        cmocka_unit_test(test_joint_poses_compose),
        cmocka_unit_test(test_joint_axis_vectors),
        cmocka_unit_test(test_wheel_contact_under_the_disk),
        cmocka_unit_test(test_page_carries_the_poses),
    };
    return cmocka_run_group_tests(tests, setup_all, NULL);
}
