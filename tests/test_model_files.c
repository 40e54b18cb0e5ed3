/* SPDX-License-Identifier: BSD-3-Clause */
/* Model files through the command line: the shipped examples/models (.ode and .c) run like
 * built-in models and give known answers — the homework's pendulum and van der Pol as
 * files reproduce the built-in models, energy is conserved where it should be, a forced
 * Duffing oscillator without its nonlinearity is a harmonic oscillator, the bouncing
 * ball's impacts follow the closed form, the C spring-mass model swings with period
 * 2 pi sqrt(m/k) — and errors in a file are reported at its line and column. */
#define _POSIX_C_SOURCE 200809L
#define _DEFAULT_SOURCE /* wait4: the peak memory of one child */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>
#include <math.h>

#include "test_cli_run.h"
#include "test_util.h"

#define MODELS DYNKIT_SOURCE_DIR "/examples/models/"

static char cache_dir[512];

static int setup_all(void **state)
{
    (void)state;
    return cli_make_tmpdir_with_cache("modelfiles", cache_dir, sizeof cache_dir);
}

/* The numbers of a CSV text (header skipped) into v (at most max); returns the count and
 * the columns per row in *cols. */
static long csv_numbers(const char *text, double *v, long max, int *cols)
{
    const char *p = strchr(text, '\n');
    long k = 0;
    *cols = 1;
    for (const char *h = text; h < p; h++)
        *cols += *h == ',';
    while (p && *p && k < max) {
        char *end;
        p++;
        double x = strtod(p, &end);
        if (end == p)
            break;
        v[k++] = x;
        p = end;
    }
    return k;
}

/* Both runs give the same table to rel (relative to each column's largest value). */
static void check_same_table(const char *file_args, const char *builtin_args, double rel)
{
    enum { MAX = 1 << 16 };
    static double a[MAX], b[MAX];
    cli_result ra = cli("run %s", file_args), rb = cli("run %s", builtin_args);
    CHECK(ra.status == 0 && rb.status == 0, "run %s: %d %s; run %s: %d %s", file_args,
          ra.status, ra.err, builtin_args, rb.status, rb.err);
    int ca, cb;
    const long na = csv_numbers(ra.out, a, MAX, &ca), nb = csv_numbers(rb.out, b, MAX, &cb);
    CHECK(na == nb && ca == cb && na >= 2 * ca, "tables differ in size: %ld/%d vs %ld/%d", na,
          ca, nb, cb);
    for (int j = 0; j < ca; j++) {
        double scale = 0.0, worst = 0.0;
        for (long k = j; k < na; k += ca) {
            scale = fmax(scale, fabs(b[k]));
            worst = fmax(worst, fabs(a[k] - b[k]));
        }
        CHECK(worst <= rel * fmax(scale, 1e-300), "column %d differs by %g (scale %g)", j,
              worst, scale);
    }
    cli_free(&ra);
    cli_free(&rb);
}

/* The homework's pendulum as an .ode file reproduces the built-in model: the same method
 * and step give the same samples and outputs (energy, height) to 1e-12. */
static void test_pendulum_file_is_the_builtin(void **state)
{
    (void)state;
    check_same_table(MODELS "pendulum.ode --method rk4 --step 0.01 --tspan 0:10 --outputs",
                     "pendulum --method rk4 --step 0.01 --tspan 0:10 --outputs", 1e-12);
    /* problem 1e: one Euler step of 0.2 s */
    check_same_table(MODELS "pendulum.ode --method euler --step 0.2 --tspan 0:0.2",
                     "pendulum --method euler --step 0.2 --tspan 0:0.2", 0.0);
    check_same_table(MODELS "pendulum.ode --method dop853 --rtol 1e-10 --atol 1e-12 --tspan 0:5",
                     "pendulum --method dop853 --rtol 1e-10 --atol 1e-12 --tspan 0:5 --step 0.01",
                     1e-12);
}

/* van der Pol as a file: its default run (@ meth=rungekutta, dt=0.01, total=15) is the
 * homework's RK4 run, and its final state is the built-in model's bit for bit. */
static void test_vanderpol_file_default_run(void **state)
{
    (void)state;
    cli_result f = cli("run " MODELS "vanderpol.ode --final");
    cli_result b = cli("run vanderpol --method rk4 --step 0.01 --tspan 0:15 --final");
    CHECK(f.status == 0 && b.status == 0, "%s %s", f.err, b.err);
    CHECK(strcmp(f.out, b.out) == 0, "file:\n%s\nbuilt-in:\n%s", f.out, b.out);
    CHECK(strstr(f.out, "15,0.8304374583632858,-1.3133658561687809") != NULL, "%s", f.out);
    cli_free(&f);
    cli_free(&b);
    check_same_table(MODELS "vanderpol.ode --set mu=3 --method dp45 --rtol 1e-8 --atol 1e-10 "
                            "--tspan 0:10",
                     "vanderpol --set mu=3 --method dp45 --rtol 1e-8 --atol 1e-10 --tspan 0:10",
                     1e-12);
}

/* The largest |energy(t) - energy(0)| of a run with --outputs, energy in column col. */
static double energy_drift(const char *args, int col, double *e0)
{
    enum { MAX = 1 << 17 };
    static double v[MAX];
    cli_result r = cli("run %s --outputs", args);
    CHECK(r.status == 0, "run %s: %s", args, r.err);
    int cols;
    const long n = csv_numbers(r.out, v, MAX, &cols);
    CHECK(n >= 2 * cols && n % cols == 0, "%ld numbers in %d columns", n, cols);
    *e0 = v[col];
    double worst = 0.0;
    for (long k = col; k < n; k += cols)
        worst = fmax(worst, fabs(v[k] - *e0));
    cli_free(&r);
    return worst;
}

/* Frictionless mechanical models conserve their energy: the double and the elastic
 * pendulum (chaotic, so only an invariant can be checked over a long run). */
static void test_conservative_files_keep_energy(void **state)
{
    (void)state;
    double e0;
    double d = energy_drift(MODELS "double_pendulum.ode --method dop853 --rtol 1e-11 "
                                   "--atol 1e-11 --tspan 0:20",
                            7, &e0);
    CHECK(d < 1e-7 * fabs(e0) + 1e-9, "double pendulum energy drift %g of %g", d, e0);
    d = energy_drift(MODELS "elastic_pendulum.ode --method dop853 --rtol 1e-11 --atol 1e-11",
                     7, &e0);
    CHECK(d < 1e-7 * fabs(e0) + 1e-9, "elastic pendulum energy drift %g of %g", d, e0);
    /* the file's own default run (adaptive) keeps it to the default tolerance's level */
    d = energy_drift(MODELS "double_pendulum.ode --tspan 0:5", 7, &e0);
    CHECK(d < 1e-3 * fabs(e0), "double pendulum default run: energy drift %g of %g", d, e0);
}

/* Duffing without damping, forcing and cubic term is x'' = -alpha x: x = cos(t) for
 * alpha = 1, x(0) = 1, v(0) = 0 (known solution, parameters set by name). */
static void test_duffing_reduces_to_harmonic(void **state)
{
    (void)state;
    cli_result r = cli("run " MODELS "duffing.ode --set delta=0 --set gamma=0 --set beta=0 "
                       "--set alpha=1 --method dop853 --rtol 1e-12 --atol 1e-12 --tspan 0:10 "
                       "--final");
    CHECK(r.status == 0, "%s", r.err);
    double t = NAN, x = NAN, v = NAN;
    const char *row = strchr(r.out, '\n');
    CHECK(row && sscanf(row + 1, "%lf,%lf,%lf", &t, &x, &v) == 3, "%s", r.out);
    CHECK(fabs(x - cos(10.0)) < 1e-9 && fabs(v + sin(10.0)) < 1e-9, "x=%.17g v=%.17g", x, v);
    cli_free(&r);
}

/* Lorenz: two independent methods agree at t = 5 (before chaos separates them). */
static void test_lorenz_methods_agree(void **state)
{
    (void)state;
    cli_result a = cli("run " MODELS "lorenz.ode --method dop853 --rtol 1e-12 --atol 1e-12 "
                       "--tspan 0:5 --final");
    cli_result b = cli("run " MODELS "lorenz.ode --method rk4 --step 1e-4 --tspan 0:5 --final");
    CHECK(a.status == 0 && b.status == 0, "%s %s", a.err, b.err);
    double ya[4] = {NAN, NAN, NAN, NAN}, yb[4] = {NAN, NAN, NAN, NAN};
    CHECK(sscanf(strchr(a.out, '\n') + 1, "%lf,%lf,%lf,%lf", &ya[0], &ya[1], &ya[2], &ya[3]) == 4,
          "%s", a.out);
    CHECK(sscanf(strchr(b.out, '\n') + 1, "%lf,%lf,%lf,%lf", &yb[0], &yb[1], &yb[2], &yb[3]) == 4,
          "%s", b.out);
    CHECK(ya[0] == 5.0 && yb[0] == 5.0, "t %g %g", ya[0], yb[0]);
    CHECK(max_abs_diff(ya + 1, yb + 1, 3) < 1e-6, "dop853 vs rk4: %g",
          max_abs_diff(ya + 1, yb + 1, 3));
    cli_free(&a);
    cli_free(&b);
}

/* The bouncing ball's global event resets the velocity: impact k comes at
 * t_k = t_1 (1 + 2 (e + ... + e^(k-1))), t_1 = sqrt(2 h0 / g), each located to rounding and
 * fired at XPPAUT's instant, a relative 1e-10 of its step after the crossing (each instant
 * moves the impacts after it as much): within 1e-10 of the time elapsed, the ball that far
 * below the floor. */
static void test_bouncing_ball_impacts(void **state)
{
    (void)state;
    const char *events = cli_path("bounces.csv");
    cli_result r = cli("run " MODELS "bouncing_ball.ode --method dop853 --rtol 1e-12 "
                       "--atol 1e-12 --event bounce --events-output '%s' --final",
                       events);
    CHECK(r.status == 0, "%s", r.err);
    char *text = cli_read_file(events, NULL);
    const double g = 9.81, e = 0.8, t1 = sqrt(2.0 * 1.0 / g);
    double expected = t1, speed = sqrt(2.0 * g * 1.0);
    int k = 0;
    for (const char *p = strchr(text, '\n'); p && p[1]; p = strchr(p + 1, '\n')) {
        double t = NAN, y = NAN, v = NAN;
        CHECK(sscanf(p + 1, "bounce,%lf,%lf,%lf", &t, &y, &v) == 3, "row: %.40s", p + 1);
        const double late = 1e-10 * (1.0 + expected);
        CHECK(fabs(t - expected) < late, "impact %d at %.17g, expected %.17g", k + 1, t,
              expected);
        CHECK(fabs(y) < 1e-12 + late * speed && fabs(v + speed) < 1e-9,
              "impact %d: y=%g v=%g (expected %g)", k + 1, y, v, -speed);
        k++;
        speed *= e;
        expected += 2.0 * speed / g;
    }
    CHECK(k == 6, "%d impacts in 3 s, expected 6", k);
    free(text);
    cli_free(&r);
    unlink(events);
}

static void write_file(const char *name, const char *text);

/* An event the file declares terminal (`#: event NAME = ..., stop`) ends the run where it
 * occurs when asked for with --event NAME, in run and in sweep; :continue overrides it.
 * x = cos(2t) + 0.25 sin(2t) turns back (v = 0) first at t = atan(0.25) / 2 (checked to
 * 1e-9, so the run takes tolerances that make its solution that accurate). */
static void test_declared_stop_event_ends_the_run(void **state)
{
    (void)state;
    write_file("osc.ode", "#: event turn = v, falling, stop -- turns back\npar w=2\nx'=v\n"
                          "v'=-w^2*x\ninit x=1, v=0.5\n@ total=10, dt=0.01\ndone\n");
    const double t_turn = atan(0.25) / 2.0;
    cli_result r =
        cli("run '%s' --event turn --final --quiet --rtol 1e-10 --atol 1e-12", cli_path("osc.ode"));
    double t = NAN, x = NAN, v = NAN;
    CHECK(r.status == 0 && sscanf(strchr(r.out, '\n') + 1, "%lf,%lf,%lf", &t, &x, &v) == 3 &&
              fabs(t - t_turn) < 1e-9 && fabs(v) < 1e-9,
          "a declared stop event: exit %d, last row t = %.17g (expected %.17g), v = %g: %s",
          r.status, t, t_turn, v, r.err);
    cli_free(&r);
    r = cli("run '%s' --event turn:continue --final --quiet", cli_path("osc.ode"));
    CHECK(r.status == 0 && sscanf(strchr(r.out, '\n') + 1, "%lf,", &t) == 1 && t == 10.0,
          "--event turn:continue: exit %d, last row %s", r.status, r.out);
    cli_free(&r);
    r = cli("sweep '%s' --vary w=2 --event turn --reduce count:turn,final:x --quiet",
            cli_path("osc.ode"));
    CHECK(r.status == 0 && strstr(r.out, "\n0,2,1,"), "sweep with a declared stop event: %s",
          r.out);
    cli_free(&r);
    unlink(cli_path("osc.ode"));
}

/* A C model whose extra outputs fail (a non-zero status) after t = 5: the rows keep nan
 * there, and the run says so once on stderr. */
static void test_failing_outputs_are_said(void **state)
{
    (void)state;
    write_file("outerr.c",
               "#include <dynkit/model.h>\n"
               "static int rhs(double t, const double *y, double *dydt, void *p)\n"
               "{ (void)t; (void)p; dydt[0] = y[1]; dydt[1] = -y[0]; return 0; }\n"
               "static int outputs(double t, const double *y, const void *p, double *out)\n"
               "{ (void)p; if (t > 5) return 3; out[0] = y[0] * y[0] + y[1] * y[1]; return 0; }\n"
               "static const dyn_var states[] = {{\"x\", \"m\", \"\"}, {\"v\", \"m/s\", \"\"}};\n"
               "static const double init[] = {1.0, 0.0};\n"
               "static const dyn_var outs[] = {{\"r2\", \"m2\", \"\"}};\n"
               "static const dyn_model model = {.name = \"outerr\", .title = \"t\", .n_states = 2,\n"
               "  .states = states, .y0 = init, .n_outputs = 1, .outputs = outs,\n"
               "  .compute_outputs = outputs, .rhs = rhs, .t0 = 0, .t1 = 10, .step = 0.5,\n"
               "  .method = \"rk4\"};\n"
               "const dyn_model *dynkit_model(void) { return &model; }\n");
    cli_result r = cli("run '%s' --outputs", cli_path("outerr.c"));
    CHECK(r.status == 0 && strstr(r.out, "\n5,") && strstr(r.out, "\n5.5,") &&
              strstr(strstr(r.out, "\n5.5,"), ",nan\n") && !strstr(strstr(r.out, "\n5,") + 1, "\n5,") &&
              strstr(r.err, "warning at t = 5.5 s: the model's outputs failed"),
          "failing outputs: exit %d\n%s\n%s", r.status, r.out, r.err);
    const char *w = strstr(r.err, "outputs failed");
    CHECK(w && !strstr(w + 1, "outputs failed"), "the warning is given once: %s", r.err);
    cli_free(&r);
    unlink(cli_path("outerr.c"));
}

/* A C model: the spring-mass example with k = 4 (m = 1) has the period pi: after one
 * period it is back at x0 = 0.1 with v = 0. */
static void test_c_model_with_set(void **state)
{
    (void)state;
    cli_result r = cli("run " MODELS "spring_mass.c --set k=4 --method dop853 --rtol 1e-12 "
                       "--atol 1e-12 --tspan 0:pi --final");
    CHECK(r.status == 0, "%s", r.err);
    double t = NAN, x = NAN, v = NAN;
    CHECK(sscanf(strchr(r.out, '\n') + 1, "%lf,%lf,%lf", &t, &x, &v) == 3, "%s", r.out);
    CHECK(fabs(x - 0.1) < 1e-10 && fabs(v) < 1e-10, "x=%.17g v=%.17g", x, v);
    cli_free(&r);
}

/* info FILE shows the file's title, units and descriptions. */
static void test_info_of_a_file(void **state)
{
    (void)state;
    cli_result r = cli("info " MODELS "double_pendulum.ode");
    CHECK(r.status == 0, "%s", r.err);
    CHECK(strstr(r.out, "double pendulum (two point masses on rigid rods)") != NULL, "%s", r.out);
    CHECK(strstr(r.out, "upper rod length") != NULL, "%s", r.out);
    CHECK(strstr(r.out, "m/s^2") != NULL && strstr(r.out, "rad/s") != NULL, "%s", r.out);
    CHECK(strstr(r.out, "energy") != NULL, "%s", r.out);
    cli_free(&r);
}

static void write_file(const char *name, const char *text)
{
    FILE *f = fopen(cli_path(name), "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

/* Errors: FILE:LINE:COL, the line and a caret, exit 2; a typo gets the nearest name; an
 * unsupported feature is named with its line; a C file's compiler error names the file
 * and line; a missing file is named. */
static void test_errors_in_model_files(void **state)
{
    (void)state;
    write_file("typo.ode", "par omega=2\nx'=y\ny'=-omgea^2*x\ndone\n");
    cli_result r = cli_in_tmpdir("run typo.ode");
    CHECK(r.status == 2, "status %d", r.status);
    CHECK(strstr(r.err, "typo.ode:3:5:") != NULL, "%s", r.err);
    CHECK(strstr(r.err, "omega") != NULL && strstr(r.err, "y'=-omgea^2*x\n") != NULL, "%s", r.err);
    CHECK(strstr(r.err, "\n      ^") != NULL, "caret under column 5:\n%s", r.err);
    cli_free(&r);

    write_file("markov.ode", "x'=-x\nmarkov z 2\n{0} {1}\n{1}\ndone\n");
    r = cli_in_tmpdir("run markov.ode");
    CHECK(r.status == 2 && strstr(r.err, "markov.ode:4:4:") && strstr(r.err, "row 1 of the Markov "
          "state 'z'"), "%d %s", r.status, r.err);
    cli_free(&r);

    write_file("broken.c", "#include <dynkit/model.h>\n\nconst dyn_model *dynkit_model(void)\n"
                           "{\n    return &undeclared_model;\n}\n");
    r = cli_in_tmpdir("run broken.c");
    CHECK(r.status == 2 && strstr(r.err, "broken.c:5:") && strstr(r.err, "undeclared_model"),
          "%d %s", r.status, r.err);
    cli_free(&r);

    /* a C model with an unknown default method, or with an empty default span, is refused
     * when it is loaded, naming the field (not later as an option never given) */
    static const struct {
        const char *fields, *message;
    } defaults[] = {
        {".t0 = 0, .t1 = 10, .step = 0.1, .method = \"rk5\"", "dyn_model.method = \"rk5\""},
        {".method = \"dp45\"", "bad default run (t0 = 0, t1 = 0, step = 0)"},
    };
    for (size_t i = 0; i < sizeof defaults / sizeof defaults[0]; i++) {
        char text[1024];
        snprintf(text, sizeof text,
                 "#include <dynkit/model.h>\n"
                 "static int rhs(double t, const double *y, double *dydt, void *p)\n"
                 "{ (void)t; (void)p; dydt[0] = -y[0]; return 0; }\n"
                 "static const dyn_var states[] = {{\"x\", \"1\", \"\"}};\n"
                 "static const double init[] = {1.0};\n"
                 "static const dyn_model model = {.name = \"bare\", .n_states = 1,\n"
                 "  .states = states, .y0 = init, .rhs = rhs, %s};\n"
                 "const dyn_model *dynkit_model(void) { return &model; }\n",
                 defaults[i].fields);
        write_file("bare.c", text);
        r = cli_in_tmpdir("run bare.c --final");
        CHECK(r.status == 2 && strstr(r.err, defaults[i].message) && r.out[0] == '\0',
              "%s: exit %d, out '%s': %s", defaults[i].fields, r.status, r.out, r.err);
        cli_free(&r);
    }
    unlink(cli_path("bare.c"));

    r = cli_in_tmpdir("run missing.ode");
    CHECK(r.status == 2 && strstr(r.err, "missing.ode") && strstr(r.err, "No such file"), "%d %s",
          r.status, r.err);
    cli_free(&r);

    r = cli("run pendlum");
    CHECK(r.status == 2 && strstr(r.err, "did you mean 'pendulum'"), "%d %s", r.status, r.err);
    cli_free(&r);
    unlink(cli_path("typo.ode"));
    unlink(cli_path("markov.ode"));
    unlink(cli_path("broken.c"));
}

/* One rule for the default run of every kind of model: a C model that names no method and
 * no tolerances runs dp45 at rtol 1e-6, atol 1e-9 (DYN_MODEL_*), as an .ode file without
 * @ meth does; info and run --verbose say so and where each value came from. The harmonic
 * oscillator x'' = -x from x = 1 ends at cos(50) = 0.96496602849 at t = 50: within 1e-5
 * at these tolerances, 3e-4 off at dyn_solve's rtol 1e-3. */
static void test_model_defaults_one_rule(void **state)
{
    (void)state;
    write_file("osc.c", "#include <dynkit/model.h>\n"
                        "static int rhs(double t, const double *y, double *f, void *p)\n"
                        "{ (void)t; (void)p; f[0] = y[1]; f[1] = -y[0]; return 0; }\n"
                        "static const dyn_var st[] = {{\"x\", \"m\", \"\"}, {\"v\", \"m/s\", \"\"}};\n"
                        "static const double init[] = {1.0, 0.0};\n"
                        "static const dyn_model model = {.name = \"osc\", .n_states = 2,\n"
                        "  .states = st, .y0 = init, .rhs = rhs, .t0 = 0, .t1 = 50, .step = 0.5};\n"
                        "const dyn_model *dynkit_model(void) { return &model; }\n");
    cli_result r = cli_in_tmpdir("info osc.c");
    CHECK(r.status == 0 && strstr(r.out, "Method: dp45 (dynkit's default for models that name none)") &&
              strstr(r.out, "--rtol 1e-6 (dynkit's default") && strstr(r.out, "--atol 1e-9 (dynkit's default"),
          "%d %s %s", r.status, r.out, r.err);
    cli_free(&r);
    r = cli_in_tmpdir("run osc.c --final --verbose");
    CHECK(r.status == 0 && strstr(r.err, "method dp45 (dynkit's default") &&
              strstr(r.err, "rtol 1e-6 (dynkit's default"),
          "%d %s", r.status, r.err);
    double t = 0, x = 0, v = 0;
    const char *row = strchr(r.out, '\n');
    CHECK(row && sscanf(row + 1, "%lf,%lf,%lf", &t, &x, &v) == 3, "%s", r.out);
    CHECK(t == 50.0 && fabs(x - cos(50.0)) < 1e-5, "x(50) = %.12g, cos 50 = %.12g", x, cos(50.0));
    cli_free(&r);
    r = cli_in_tmpdir("run osc.c --final --rtol 1e-3 --atol 1e-6 --verbose");
    row = strchr(r.out, '\n');
    CHECK(r.status == 0 && strstr(r.err, "rtol 0.001 (--rtol)") && row &&
              sscanf(row + 1, "%lf,%lf,%lf", &t, &x, &v) == 3 && fabs(x - cos(50.0)) > 1e-4,
          "%s %s", r.out, r.err);
    cli_free(&r);
    unlink(cli_path("osc.c"));

    /* a model file's @ options are named as such, a built-in model's as its own */
    write_file("decay.ode", "x'=-x\ninit x=1\n@ meth=rk4, total=1\ndone\n");
    r = cli_in_tmpdir("info decay.ode");
    CHECK(r.status == 0 && strstr(r.out, "Method: rk4 (@ meth in decay.ode)") &&
              strstr(r.out, "--rtol 1e-6 (dynkit's default"),
          "%s %s", r.out, r.err);
    cli_free(&r);
    unlink(cli_path("decay.ode"));
    /* a C model's own method and tolerances are named by their field and file */
    r = cli("info " MODELS "spring_mass.c");
    CHECK(r.status == 0 && strstr(r.out, "Method: rk4 (dyn_model.method in spring_mass.c)"),
          "%s %s", r.out, r.err);
    cli_free(&r);
    r = cli("info " MODELS "lorenz.ode"); /* docs/model-files.md */
    CHECK(r.status == 0 &&
              strstr(r.out, "Method: dp45 (dynkit's default for models that name none)\n"
                            "Tolerances of adaptive methods: --rtol 1e-6 (dynkit's default for "
                            "models that name none) --atol 1e-9 (dynkit's default for models "
                            "that name none)\n"),
          "%s", r.out);
    cli_free(&r);
    r = cli("info pendulum");
    CHECK(r.status == 0 && strstr(r.out, "Method: dp45 (the model's)") &&
              strstr(r.out, "--rtol 1e-8 (the model's) --atol 1e-10 (the model's)"),
          "%s", r.out);
    cli_free(&r);
}

/* XPPAUT's options that a run does not use are accepted: AUTO's with a note (--verbose),
 * the others with a warning shown always (XPPAUT's window, what dynkit does not do). */
static void test_ignored_options_noted(void **state)
{
    (void)state;
    write_file("opts.ode",
               "x'=-x\ninit x=1\n@ ntst=20, total=1\n@ axes=2, range=1, fold=x, fold=y\ndone\n");
    cli_result r = cli_in_tmpdir("run opts.ode --final --verbose");
    CHECK(r.status == 0, "%s", r.err);
    CHECK(strstr(r.err, "opts.ode:3: option 'ntst' is AUTO's: dynkit continue reads it") != NULL,
          "%s", r.err);
    CHECK(strstr(r.err, "warning: opts.ode:4: option 'axes=2' sets XPPAUT's window") != NULL,
          "%s", r.err);
    CHECK(strstr(r.err, "warning: opts.ode:4: option 'range=1' is read and ignored") != NULL,
          "%s", r.err);
    /* two options of one name are two warnings, each with its value */
    CHECK(strstr(r.err, "option 'fold=x' is read") && strstr(r.err, "option 'fold=y' is read"),
          "%s", r.err);
    double t = NAN, x = NAN;
    CHECK(sscanf(strchr(r.out, '\n') + 1, "%lf,%lf", &t, &x) == 2 && t == 1.0, "%s", r.out);
    CHECK(fabs(x - exp(-1.0)) < 1e-5, "x(1) = %.17g", x);
    cli_free(&r);
    r = cli_in_tmpdir("run opts.ode --final");
    CHECK(r.status == 0 && strstr(r.err, "ntst") == NULL && strstr(r.err, "'axes=2'") &&
              strstr(r.err, "'range=1'"),
          "notes only with --verbose, warnings always: %s", r.err);
    cli_free(&r);
    unlink(cli_path("opts.ode"));
}

/* A difference equation (x(t+1)=) runs as a discrete map: one row per step of 1 (the
 * file's dt is ignored, as in XPPAUT), the iterates exact (x/2 + t stays exact in binary),
 * nout as --every; sweeps iterate it too. What makes no sense for a map is refused with the
 * reason: an integrator, events, --times, a span of a fractional number of steps. The
 * shipped Henon map runs and reaches its attractor's box. */
static void test_difference_equation_is_a_map(void **state)
{
    (void)state;
    write_file("halves.ode", "par c=1\nx(t+1)=x/2+c*t\ninit x=1\n@ total=6, dt=0.25, nout=2\n"
                             "done\n");
    cli_result r = cli("run '%s'", cli_path("halves.ode"));
    /* x: 1, 0.5, 1.25, 2.625, 4.3125, 6.15625, 8.078125 at t = 0 .. 6; every 2nd row */
    CHECK(r.status == 0 &&
              strcmp(r.out, "t,x\n0,1\n2,1.25\n4,4.3125\n6,8.078125\n") == 0,
          "exit %d:\n%s%s", r.status, r.out, r.err);
    cli_free(&r);
    r = cli("sweep '%s' --vary c=0,1 --reduce final:x --quiet", cli_path("halves.ode"));
    CHECK(r.status == 0 && strstr(r.out, "\n0,0,0.015625\n") && strstr(r.out, "\n1,1,8.078125\n"),
          "sweep of a map: %s%s", r.out, r.err);
    cli_free(&r);
    static const struct {
        const char *args, *says;
    } refused[] = {
        {"--method rk4", "is a discrete map"},
        {"--times 1,2", "states only at its steps"},
        {"--tspan 0:4.5", "whole steps"},
    };
    for (size_t k = 0; k < sizeof refused / sizeof refused[0]; k++) {
        r = cli("run '%s' %s", cli_path("halves.ode"), refused[k].args);
        CHECK(r.status == 2 && strstr(r.err, refused[k].says) && !*r.out,
              "%s: exit %d, out '%s', err %s", refused[k].args, r.status, r.out, r.err);
        cli_free(&r);
    }
    r = cli("plot '%s' --y x --compare rk4 --output '%s'", cli_path("halves.ode"),
            cli_path("halves.svg"));
    CHECK(r.status == 2 && strstr(r.err, "--compare rk4") && strstr(r.err, "discrete map"), "%s",
          r.err);
    cli_free(&r);
    r = cli("run '%s' --step 0.5", cli_path("halves.ode"));
    CHECK(r.status == 2 && strstr(r.err, "steps by 1"), "%s", r.err);
    cli_free(&r);
    r = cli("run vanderpol --method discrete");
    CHECK(r.status == 2 && strstr(r.err, "is a differential equation"), "%s", r.err);
    cli_free(&r);
    r = cli("run '%s/examples/models/henon.ode' --final --stats", DYNKIT_SOURCE_DIR);
    double t = NAN, x = NAN, y = NAN;
    CHECK(r.status == 0 && sscanf(strchr(r.out, '\n') + 1, "%lf,%lf,%lf", &t, &x, &y) == 3 &&
              t == 2000.0 && fabs(x) < 1.3 && fabs(y) < 0.4 &&
              strstr(r.err, "steps=2000 accepted=2000 rejected=0 rhs=2000"),
          "henon: exit %d, %s%s", r.status, r.out, r.err);
    cli_free(&r);
    unlink(cli_path("halves.ode"));
}

/* Lookup tables: a formula table of t with a parameter and a table file beside the model
 * (XPPAUT's format), looked up by linear interpolation and extrapolated by the end segments
 * (as XPPAUT 6.11 does, tests/xppaut); --set re-evaluates the formula table. */
static void test_lookup_tables_in_a_run(void **state)
{
    (void)state;
    write_file("tab_data.tab", "3\n0\n2\n1\n3\n-1\n");
    write_file("tab.ode", "table g % 3 0 2 a*t^2\ntable h tab_data.tab\npar a=1\nx'=0\n"
                          "aux gv=g(t)\naux hv=h(t)\n@ total=3, dt=0.5, meth=euler\ndone\n");
    cli_result r = cli("run '%s' --outputs", cli_path("tab.ode"));
    CHECK(r.status == 0 && strcmp(r.out, "t,x,gv,hv\n0,0,0,1\n0.5,0,0.5,2\n1,0,1,3\n1.5,0,2.5,1\n"
                                         "2,0,4,-1\n2.5,0,5.5,-3\n3,0,7,-5\n") == 0,
          "exit %d:\n%s%s", r.status, r.out, r.err);
    cli_free(&r);
    r = cli("run '%s' --outputs --set a=2 --final", cli_path("tab.ode"));
    CHECK(r.status == 0 && strstr(r.out, "\n3,0,14,-5\n"), "--set a=2: %s%s", r.out, r.err);
    cli_free(&r);
    unlink(cli_path("tab_data.tab"));
    r = cli("run '%s'", cli_path("tab.ode"));
    CHECK(r.status == 2 && strstr(r.err, "cannot read") && strstr(r.err, "tab_data.tab") && !*r.out,
          "missing table file: exit %d, %s", r.status, r.err);
    cli_free(&r);
    unlink(cli_path("tab.ode"));
}

/* Network sums: special k=conv(TYPE,5,2,w,u0) over five states, beyond the ends zero (0),
 * mirrored (even: u(-1) = u(1), u(5) = u(3)) or wrapped (periodic), as XPPAUT 6.11 computes
 * them (measured: tests/xppaut); the sums here are computed again by hand. */
static void test_network_sums(void **state)
{
    (void)state;
    static const char *const types[] = {"0", "even", "periodic"};
    const double u[5] = {10, 20, -30, 40, 50};
    double w[5];
    for (int k = 0; k < 5; k++) {
        const double t = -2.0 + k;
        w[k] = 1 + t + t * t / 3;
    }
    for (int ty = 0; ty < 3; ty++) {
        char text[512];
        snprintf(text, sizeof text,
                 "table w %% 5 -2 2 1+t+t^2/3\nspecial k=conv(%s,5,2,w,u0)\nu[0..4]'=0\n"
                 "init u0=10,u1=20,u2=-30,u3=40,u4=50\naux k[0..4]=k([j])\n"
                 "@ meth=euler, dt=1, total=1\ndone\n",
                 types[ty]);
        write_file("conv.ode", text);
        cli_result r = cli("run '%s' --outputs --final", cli_path("conv.ode"));
        double got[11];
        const char *row = r.status == 0 ? strchr(r.out, '\n') : NULL;
        int n = 0;
        for (const char *q = row ? row + 1 : NULL; q && n < 11; n++) {
            got[n] = strtod(q, NULL);
            q = strchr(q, ',');
            q = q ? q + 1 : NULL;
        }
        CHECK(n == 11, "%s: exit %d, %s%s", types[ty], r.status, r.out, r.err);
        for (int j = 0; j < 5; j++) {
            double want = 0.0;
            for (int i = -2; i <= 2; i++) {
                int q = j + i;
                if (q < 0 || q > 4) {
                    if (ty == 0)
                        continue;
                    q = ty == 1 ? (q < 0 ? -q : 8 - q) : (q + 5) % 5;
                }
                want += w[2 + i] * u[q];
            }
            CHECK(fabs(got[6 + j] - want) <= 1e-13 * fabs(want), "conv(%s): k%d = %.17g, want %.17g",
                  types[ty], j, got[6 + j], want);
        }
        cli_free(&r);
    }
    /* fconv sums w[m+i] f(u(j+i), v(j)): with f(a,b) = a it is conv; with f(a,b) = b it is
     * v(j) times the sum of the weights */
    for (int which = 0; which < 2; which++) {
        char text[512];
        snprintf(text, sizeof text,
                 "g(a,b)=%s\ntable w %% 5 -2 2 1+t+t^2/3\nspecial k=fconv(even,5,2,w,u0,u0,g)\n"
                 "special q=conv(even,5,2,w,u0)\nu[0..4]'=0\n"
                 "init u0=10,u1=20,u2=-30,u3=40,u4=50\naux k[0..4]=k([j])\naux q[0..4]=q([j])\n"
                 "@ meth=euler, dt=1, total=1\ndone\n",
                 which ? "b" : "a");
        write_file("conv.ode", text);
        cli_result r = cli("run '%s' --outputs --final", cli_path("conv.ode"));
        double got[16];
        const char *q = r.status == 0 ? strchr(r.out, '\n') : NULL;
        int n = 0;
        for (q = q ? q + 1 : NULL; q && n < 16; n++) {
            got[n] = strtod(q, NULL);
            q = strchr(q, ',');
            q = q ? q + 1 : NULL;
        }
        const double wsum = w[0] + w[1] + w[2] + w[3] + w[4];
        for (int j = 0; n == 16 && j < 5; j++) {
            const double want = which ? u[j] * wsum : got[11 + j];
            CHECK(fabs(got[6 + j] - want) <= 1e-13 * fabs(want), "fconv with f = %s: k%d = %.17g, "
                  "want %.17g", which ? "b" : "a", j, got[6 + j], want);
        }
        CHECK(n == 16, "fconv: exit %d, %s%s", r.status, r.out, r.err);
        cli_free(&r);
    }
    /* mmult(3,2,w,x0): a(j) = sum_{i<3} w[i+3j] x(i); sparse(2,3,w,l,x0): b(j) =
     * sum_{i<3} w[3j+i] x(l[3j+i]); w = 1..6, l = 1,0,3,2,1,0, x = 1,10,100,1000 (XPPAUT
     * 6.11 gives the same: 321, 654, 3012, 456) */
    write_file("conv.ode", "table w % 6 0 5 t+1\ntable l % 6 0 5 mod(3*t+1,4)\n"
                           "special a=mmult(3,2,w,x0)\nspecial b=sparse(2,3,w,l,x0)\nx[0..3]'=0\n"
                           "init x0=1,x1=10,x2=100,x3=1000\naux a[0..1]=a([j])\naux b[0..1]=b([j])\n"
                           "@ meth=euler, dt=1, total=1\ndone\n");
    cli_result r = cli("run '%s' --outputs --final", cli_path("conv.ode"));
    CHECK(r.status == 0 && strstr(r.out, "\n1,1,10,100,1000,321,654,3012,456\n"), "%s%s", r.out,
          r.err);
    cli_free(&r);
    /* an index of sparse outside the states is refused when the tables are computed */
    write_file("conv.ode", "table w % 2 0 1 1\ntable l % 2 0 1 4*t\nspecial b=sparse(1,2,w,l,x0)\n"
                           "x[0..3]'=b(0)\n");
    r = cli("run '%s'", cli_path("conv.ode"));
    CHECK(r.status == 2 && strstr(r.err, "index 1 of table 'l' is 4, not one of the 4 states"),
          "exit %d: %s", r.status, r.err);
    cli_free(&r);
    /* the sum's table must hold 2m + 1 weights */
    write_file("conv.ode", "table w % 4 -2 2 1\nspecial k=conv(even,5,2,w,u0)\nu[0..4]'=0\n");
    r = cli("run '%s'", cli_path("conv.ode"));
    CHECK(r.status == 2 && strstr(r.err, "2m+1 = 5") && strstr(r.err, "has 4 points"), "%s",
          r.err);
    cli_free(&r);
    unlink(cli_path("conv.ode"));
}

/* The rows of a CSV text with cols columns into v; returns the number of rows. */
static long csv_table(const char *text, double *v, long max_rows, int cols)
{
    int got = 0;
    const long k = csv_numbers(text, v, max_rows * cols, &got);
    return got == cols ? k / cols : -1;
}

/* Differential-algebraic systems (solv and 0=): two linear equations with a closed-form
 * solution, a quintic whose solution satisfies t = 2.75 - ln|y| - 1.5 y^2 - 1.25 y^4 (from
 * x' = y and x = -(y + y^3 + y^5)), and a cubic with a fold at w = 2/(3 sqrt 3), where the
 * branch chosen by the initial guess ends at t = 1 - ln sqrt 3 (an impasse point: the run
 * stops there, the adaptive method's steps shrinking onto it, and says why). Then the
 * branch is followed through long steps, a reset by a global, half turns of an angle and
 * in an aux output alone, and a small variable is solved to its equation's rounding. */
static void test_algebraic_equations(void **state)
{
    (void)state;
    static double v[64 * 4];
    write_file("lin.ode", "x'=-x+a\n0=a+b-x\n0=a-b-sin(t)\nsolv a=0, b=0\ninit x=1\naux av=a\n"
                          "@ total=10, dt=0.5\ndone\n");
    cli_result r = cli("run '%s' --outputs --rtol 1e-10 --atol 1e-12", cli_path("lin.ode"));
    long rows = csv_table(r.out, v, 64, 3);
    double ex = 0.0, ea = 0.0;
    for (long k = 0; k < rows; k++) {
        const double t = v[3 * k], x = v[3 * k + 1], a = v[3 * k + 2];
        ex = fmax(ex, fabs(x - (sin(t) / 5.0 - 2.0 * cos(t) / 5.0 + 1.4 * exp(-t / 2.0))));
        ea = fmax(ea, fabs(a - (x + sin(t)) / 2.0));
    }
    CHECK(r.status == 0 && rows == 21 && ex < 1e-8 && ea < 1e-13,
          "linear DAE: exit %d, %ld rows, error of x %.3g, of a %.3g\n%s", r.status, rows, ex, ea,
          r.err);
    cli_free(&r);
    write_file("quintic.ode", "x'=y\n0=x+y+y^3+y^5\nsolve y=-1\nx(0)=3\naux yy=y\n"
                              "@ total=10, dt=0.5\ndone\n");
    r = cli("run '%s' --outputs --rtol 1e-10 --atol 1e-12", cli_path("quintic.ode"));
    rows = csv_table(r.out, v, 64, 3);
    double et = 0.0, res = 0.0;
    for (long k = 0; k < rows; k++) {
        const double t = v[3 * k], x = v[3 * k + 1], y = v[3 * k + 2];
        et = fmax(et, fabs(2.75 - log(fabs(y)) - 1.5 * y * y - 1.25 * pow(y, 4) - t));
        res = fmax(res, fabs(x + y + pow(y, 3) + pow(y, 5)));
    }
    CHECK(r.status == 0 && rows == 21 && et < 1e-8 && res < 1e-14,
          "quintic DAE: exit %d, %ld rows, error in t(y) %.3g, residual %.3g\n%s", r.status, rows,
          et, res, r.err);
    cli_free(&r);
    write_file("fold.ode", "par g=1\nw'=v_\n0=v_*(1-v_*v_)-w\nsolv v_=g\naux v=v_\n"
                           "@ total=2, dt=0.05\ndone\n");
    const double t_fold = 1.0 - 0.5 * log(3.0), w_fold = 2.0 / (3.0 * sqrt(3.0));
    for (int sign = 1; sign >= -1; sign -= 2) {
        r = cli("run '%s' --final --set g=%d", cli_path("fold.ode"), sign);
        double t = NAN, w = NAN;
        const char *row = strchr(r.out, '\n');
        CHECK(r.status == 1 && row && sscanf(row + 1, "%lf,%lf", &t, &w) == 2 &&
                  fabs(t - t_fold) < 1e-5 && fabs(sign * w - w_fold) < 1e-9 &&
                  strstr(r.err, "algebraic equations (0=...) have no solution near the branch "
                                "followed there"),
              "fold, guess %d: exit %d, %s%s", sign, r.status, r.out, r.err);
        cli_free(&r);
    }
    /* a guess near 0 follows the middle branch, v = w = 0 */
    r = cli("run '%s' --final --outputs --set g=0.1", cli_path("fold.ode"));
    double t2 = NAN, w2 = NAN, v2 = NAN;
    const char *row2 = strchr(r.out, '\n');
    CHECK(r.status == 0 && row2 && sscanf(row2 + 1, "%lf,%lf,%lf", &t2, &w2, &v2) == 3 &&
              t2 == 2.0 && fabs(w2) < 1e-12 && fabs(v2) < 1e-12,
          "fold, the middle branch: exit %d, %s%s", r.status, r.out, r.err);
    cli_free(&r);
    /* w = x while x runs from 0 to 3 in steps as long as dp45 takes them (moves of several
     * times the variable's size in one solve), is reset to 0 by a global and runs to 2 */
    write_file("follow.ode", "x'=1+0*w\n0=w-x\nsolv w=0\nglobal 1 x-3 {x=0}\naux ww=w\n"
                             "@ total=5, dt=0.5\ndone\n");
    r = cli("run '%s' --outputs", cli_path("follow.ode"));
    rows = csv_table(r.out, v, 64, 3);
    double ef = 0.0;
    for (long k = 0; k < rows; k++)
        ef = fmax(ef, fabs(v[3 * k + 2] - v[3 * k + 1]) +
                          fabs(v[3 * k + 1] - (v[3 * k] <= 3.0 ? v[3 * k] : v[3 * k] - 3.0)));
    CHECK(r.status == 0 && rows == 11 && ef < 1e-9, "follow: exit %d, %ld rows, error %.3g\n%s%s",
          r.status, rows, ef, r.out, r.err);
    cli_free(&r);
    /* the upper branch of the cubic read by an aux output alone (v = 1.088 at w = -0.2, 1 at
     * 0, 0.879 at 0.2: XPPAUT's numbers), from the guess -1.5, which picks it at w = -1 */
    write_file("aux_only.ode", "w'=1\n0=v*(1-v^2)-w\nsolv v=-1.5\ninit w=-1\naux vv=v\n"
                               "@ total=1.2, dt=0.2\ndone\n");
    r = cli("run '%s' --outputs", cli_path("aux_only.ode"));
    rows = csv_table(r.out, v, 64, 3);
    double eb = 0.0;
    for (long k = 0; k < rows; k++) { /* v (1 - v^2) = w on the branch v > 1/sqrt 3 */
        const double w = v[3 * k + 1], vv = v[3 * k + 2];
        eb = fmax(eb, fabs(vv * (1.0 - vv * vv) - w) + (vv > 1.0 / sqrt(3.0) ? 0.0 : 1.0));
    }
    CHECK(r.status == 0 && rows == 7 && eb < 1e-12, "aux only: exit %d, %ld rows, %.3g\n%s%s",
          r.status, rows, eb, r.out, r.err);
    cli_free(&r);
    /* an angle run through by half turns between two samples: (c, s) = (cos x, sin x),
     * not its opposite, which solves the same equations */
    write_file("circle.ode", "x'=5\nsolv c=1, s=0\n0=c^2+s^2-1\n0=s*cos(x)-c*sin(x)\n"
                             "aux err=abs(c-cos(x))+abs(s-sin(x))\n@ total=20, dt=0.5\ndone\n");
    r = cli("run '%s' --outputs", cli_path("circle.ode"));
    rows = csv_table(r.out, v, 64, 3);
    double ec = 0.0;
    for (long k = 0; k < rows; k++)
        ec = fmax(ec, v[3 * k + 2]);
    CHECK(r.status == 0 && rows == 41 && ec < 1e-12, "circle: exit %d, %ld rows, %.3g\n%s",
          r.status, rows, ec, r.err);
    cli_free(&r);
    /* w = ln(1 + x) near 1e-9 from exp(w) - 1 - x, whose terms are near 1: solved to the
     * equation's rounding, with an adaptive and a stiff method */
    write_file("floor.ode", "x'=1e-9\ninit x=0\nsolv w\n0=exp(w)-1-x\naux ww=w\n"
                            "@ total=1, dt=0.25\ndone\n");
    for (int stiff = 0; stiff < 2; stiff++) {
        r = cli("run '%s' --outputs --method %s", cli_path("floor.ode"), stiff ? "rodas4" : "dp45");
        rows = csv_table(r.out, v, 64, 3);
        double el = 0.0;
        for (long k = 0; k < rows; k++)
            el = fmax(el, fabs(v[3 * k + 2] - log1p(v[3 * k + 1])));
        CHECK(r.status == 0 && rows == 5 && el < 1e-15, "floor (%s): exit %d, %ld rows, %.3g\n%s",
              stiff ? "rodas4" : "dp45", r.status, rows, el, r.err);
        cli_free(&r);
    }
    /* cancellation inside a user function: w = ln((1/2 + x)/(1/2 - x)) from
     * 1/(1 + exp(-w)) - 1/2 = x while x decays to 2e-10 */
    write_file("sigmoid.ode", "x'=-x\ninit x=0.1\ns(v)=1/(1+exp(-v))-0.5\nsolv w=0\n0=s(w)-x\n"
                              "aux rel=w/ln((0.5+x)/(0.5-x))-1\n@ total=20, dt=1\ndone\n");
    r = cli("run '%s' --outputs", cli_path("sigmoid.ode"));
    rows = csv_table(r.out, v, 64, 3);
    double er = 0.0;
    for (long k = 0; k < rows; k++)
        er = fmax(er, fabs(v[3 * k + 2]));
    CHECK(r.status == 0 && rows == 21 && er < 1e-5, "sigmoid: exit %d, %ld rows, %.3g\n%s",
          r.status, rows, er, r.err);
    cli_free(&r);
    /* a guess where the residual overflows is no solution */
    write_file("overflow.ode", "x'=1\ninit x=2\nsolv w=1000\n0=exp(w)-x\n@ total=1\ndone\n");
    r = cli("run '%s'", cli_path("overflow.ode"));
    CHECK(r.status == 1 && strstr(r.err, "algebraic equations (0=...) have no solution"),
          "overflow: exit %d\n%s%s", r.status, r.out, r.err);
    cli_free(&r);
    unlink(cli_path("sigmoid.ode"));
    unlink(cli_path("overflow.ode"));
    unlink(cli_path("lin.ode"));
    unlink(cli_path("quintic.ode"));
    unlink(cli_path("fold.ode"));
    unlink(cli_path("follow.ode"));
    unlink(cli_path("aux_only.ode"));
    unlink(cli_path("circle.ode"));
    unlink(cli_path("floor.ode"));
}

/* The last value of a one-state run's output (t,x rows). */
static double final_x(const cli_result *r)
{
    double t = NAN, x = NAN;
    const char *row = strchr(r->out, '\n');
    if (!row || sscanf(row + 1, "%lf,%lf", &t, &x) != 2)
        return NAN;
    return x;
}

/* Lines XPPAUT 6.11 reads without a word, each with the meaning it gives them (measured
 * with xppaut -silent: tests/xppaut/lenient/ compares the runs): a ';' after a value in a
 * par, number or init list; a statement word read by its first letter (par1-3 is par); a
 * method read by its first letter; a plot option naming no variable (left out, with a
 * warning shown always); an aux named like a state, a parameter or a function; a global
 * that assigns parameters; a global with sign 0. The answers are closed forms or exact Runge-Kutta
 * polynomials. */
static void test_xppaut_leniency(void **state)
{
    (void)state;
    /* x' = -x c/K4 + a K5/K4 = -x/100 + 1/2: x = 50 - 49 exp(-t/100) */
    write_file("semi.ode", "param K4=200; K5=100;\nparam a=1;b=2\nnumber c=2;\n"
                           "x'=-x*c/K4+a*K5/K4\ninit x=1;\n@ total=2,dt=0.5\ndone\n");
    cli_result r = cli_in_tmpdir("run semi.ode --method rk4 --final --verbose");
    CHECK(r.status == 0 && fabs(final_x(&r) - (50.0 - 49.0 * exp(-0.02))) < 1e-10 &&
              strstr(r.err, "semi.ode:2: 'b=2' after ';' in the par list is not read"),
          "exit %d: %s%s", r.status, r.out, r.err);
    cli_free(&r);
    /* par1-3 is par; meth=runge-kutta is RK4: x' = -2x + 1, four steps of 1/4, each
     * multiplying x - 1/2 by R(-1/2) = 1 - 1/2 + 1/8 - 1/48 + 1/384 */
    write_file("first.ode", "par1-3 vc=2,a=1\nx'=-vc*x+a\ninit x=1\n"
                            "@ meth=runge-kutta, total=1, dt=0.25\ndone\n");
    r = cli_in_tmpdir("run first.ode --final --verbose");
    const double R = 1.0 - 0.5 + 0.125 - 1.0 / 48.0 + 1.0 / 384.0;
    CHECK(r.status == 0 && fabs(final_x(&r) - (0.5 + 0.5 * pow(R, 4))) < 1e-15 &&
              strstr(r.err, "'par1-3' is read as 'par'") &&
              strstr(r.err, "meth=runge-kutta is read by its first letter as 'rungekutta'"),
          "exit %d: %s%s", r.status, r.out, r.err);
    cli_free(&r);
    /* x' = -x, two steps of 1/2: Euler 1/4, the modified Euler method (5/8)^2 */
    static const struct {
        const char *meth;
        double x;
    } by_letter[] = {{"euler-foo", 0.25}, {"modx", 0.390625}};
    for (size_t k = 0; k < 2; k++) {
        char text[128];
        snprintf(text, sizeof text, "x'=-x\ninit x=1\n@ meth=%s, total=1, dt=0.5\ndone\n",
                 by_letter[k].meth);
        write_file("meth.ode", text);
        r = cli_in_tmpdir("run meth.ode --final");
        CHECK(r.status == 0 && final_x(&r) == by_letter[k].x, "meth=%s: exit %d: %s%s",
              by_letter[k].meth, r.status, r.out, r.err);
        cli_free(&r);
    }
    /* a plot option naming no variable: a warning without --verbose, the run unchanged */
    write_file("plotv.ode", "x'=-x\ninit x=1\n@ xp=t, yp=v, total=1, dt=0.5\ndone\n");
    r = cli_in_tmpdir("run plotv.ode --final");
    CHECK(r.status == 0 && fabs(final_x(&r) - exp(-1.0)) < 1e-6 &&
              strstr(r.err, "dynkit: warning: plotv.ode:3: option 'yp': 'v' is not a state"),
          "exit %d: %s%s", r.status, r.out, r.err);
    cli_free(&r);
    /* aux outputs named like a state, a parameter and a function: columns only; the
     * formulas mean the others (x' = -x, y' = x^2 with f(u) = u^2, a = 3) */
    write_file("auxn.ode", "par a=3\naux x=2*x\naux a=a*x\nx'=-x\nf(u)=u^2\ny'=f(x)\n"
                           "aux f=x+1\ninit x=1\n@ total=1,dt=0.5\ndone\n");
    r = cli_in_tmpdir("run auxn.ode --final --outputs --rtol 1e-12 --atol 1e-14");
    double v[6] = {0};
    int cols = 0;
    const long got = csv_numbers(r.out, v, 6, &cols);
    const double e1 = exp(-1.0);
    CHECK(r.status == 0 && got == 6 && strncmp(r.out, "t,x,y,x,a,f\n", 12) == 0 &&
              fabs(v[1] - e1) < 1e-12 && fabs(v[2] - (1.0 - e1 * e1) / 2.0) < 1e-12 &&
              fabs(v[3] - 2.0 * e1) < 1e-12 && fabs(v[4] - 3.0 * e1) < 1e-12 &&
              fabs(v[5] - (e1 + 1.0)) < 1e-12,
          "exit %d: %s%s", r.status, r.out, r.err);
    cli_free(&r);
    unlink(cli_path("auxn.ode"));
    /* a global that counts in a parameter: k = 1 + the crossings of x = 1 (at t = 1, 2, 3),
     * the derived k2 = 2k follows it, n reads k from before the crossing; y' = k2 gives
     * y(3.5) = 2 + 4 + 6 + 4 */
    write_file("count.ode", "par k=1, n=0\n!k2=2*k\nx'=1\ny'=k2\nglobal 1 x-1 {x=0; k=k+1; "
                            "n=k}\naux kk=k\naux nn=n\n@ total=3.5, dt=0.07\ndone\n");
    r = cli_in_tmpdir("run count.ode --final --outputs --rtol 1e-12 --atol 1e-14");
    double w[5] = {0};
    CHECK(r.status == 0 && csv_numbers(r.out, w, 5, &cols) == 5 && fabs(w[1] - 0.5) < 1e-9 &&
              fabs(w[2] - 16.0) < 1e-9 && w[3] == 4.0 && w[4] == 3.0,
          "exit %d: %s%s", r.status, r.out, r.err);
    cli_free(&r);
    /* a picture of it beside two more runs (each series starts from k = 1) */
    r = cli_in_tmpdir("plot count.ode --y y --compare dp45 --compare rk4 --output count.svg");
    CHECK(r.status == 0, "exit %d: %s", r.status, r.err);
    cli_free(&r);
    unlink(cli_path("count.svg"));
    unlink(cli_path("count.ode"));
    /* global 0 is fired by resets only (XPPAUT's sign 0): the flow takes x across 1 at t = 1
     * without firing it, and run says once where XPPAUT differs */
    write_file("zero.ode", "x'=1\nz'=0\nglobal 0 x-1 {z=z+1}\n@ total=2, dt=0.1\ndone\n");
    r = cli_in_tmpdir("run zero.ode --final");
    double u[3] = {0};
    CHECK(r.status == 0 && csv_numbers(r.out, u, 3, &cols) == 3 && u[2] == 0.0 &&
              strstr(r.err, "dynkit: note: event global1 fires only when a reset takes its "
                            "condition onto or across zero"),
          "exit %d: %s%s", r.status, r.out, r.err);
    cli_free(&r);
    r = cli_in_tmpdir("info zero.ode");
    CHECK(r.status == 0 && strstr(r.out, "by resets only"), "%s%s", r.out, r.err);
    cli_free(&r);
    unlink(cli_path("zero.ode"));
    unlink(cli_path("semi.ode"));
    unlink(cli_path("first.ode"));
    unlink(cli_path("meth.ode"));
    unlink(cli_path("plotv.ode"));
}

/* Peak resident memory (KiB) of `dynkit ARGS` run in the temporary directory with its output
 * to /dev/null: wait4's ru_maxrss, which also covers the processes it waited for (the
 * system C compiler when a model is compiled). */
static long peak_kib(const char *args)
{
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "cd '%s' && exec '%s' %s >/dev/null 2>&1", cli_tmpdir, DYNKIT_CLI,
             args);
    pid_t pid = fork();
    if (pid == 0) {
        execl("/bin/sh", "sh", "-c", cmd, (char *)NULL);
        _exit(127);
    }
    int w = 0;
    struct rusage ru;
    if (pid < 0 || wait4(pid, &w, 0, &ru) != pid || !WIFEXITED(w) || WEXITSTATUS(w) != 0)
        return -1;
    return ru.ru_maxrss;
}

/* A streamed run of a model file holds what a built-in model's holds: the rows are written
 * as they come, and the model is a loaded object. The larger peak of a first run (32 MB where
 * a built-in model's run holds 6 MB) is the system C compiler compiling the model, a process
 * of its own that ends before the run starts. */
static void test_streamed_model_file_holds_what_a_builtin_holds(void **state)
{
    (void)state;
#if defined(__SANITIZE_ADDRESS__)
    print_message("SKIP: resident memory under AddressSanitizer (its shadow memory and "
                  "quarantine) says nothing about dynkit's\n");
    return;
#endif
    assert_int_equal(cli_write_file("stream.ode", "x'=v\nv'=-x\ninit x=1, v=0\ndone\n"), 0);
    const long first = peak_kib("run stream.ode --method rk4 --step 0.01 --tspan 0:1");
    const long file = peak_kib("run stream.ode --method rk4 --step 0.0001 --tspan 0:200");
    const long builtin = peak_kib("run vanderpol --method rk4 --step 0.0001 --tspan 0:200");
    print_message("peak resident memory: first run (compiling) %ld KiB, 2e6 rows of the model "
                  "file %ld KiB, of vanderpol %ld KiB\n",
                  first, file, builtin);
    assert_true(first > 0 && file > 0 && builtin > 0);
    CHECK(file <= builtin + 2048, "a streamed run of a model file holds %ld KiB, a built-in "
                                  "model's %ld KiB",
          file, builtin);
    unlink(cli_path("stream.ode"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_streamed_model_file_holds_what_a_builtin_holds),
        cmocka_unit_test(test_network_sums),
        cmocka_unit_test(test_algebraic_equations),
        cmocka_unit_test(test_lookup_tables_in_a_run),
        cmocka_unit_test(test_difference_equation_is_a_map),
        cmocka_unit_test(test_pendulum_file_is_the_builtin),
        cmocka_unit_test(test_vanderpol_file_default_run),
        cmocka_unit_test(test_conservative_files_keep_energy),
        cmocka_unit_test(test_duffing_reduces_to_harmonic),
        cmocka_unit_test(test_lorenz_methods_agree),
        cmocka_unit_test(test_bouncing_ball_impacts),
        cmocka_unit_test(test_declared_stop_event_ends_the_run),
        cmocka_unit_test(test_failing_outputs_are_said),
        cmocka_unit_test(test_c_model_with_set),
        cmocka_unit_test(test_info_of_a_file),
        cmocka_unit_test(test_errors_in_model_files),
        cmocka_unit_test(test_model_defaults_one_rule),
        cmocka_unit_test(test_ignored_options_noted),
        cmocka_unit_test(test_xppaut_leniency),
    };
    return cmocka_run_group_tests(tests, setup_all, cli_remove_tmpdir);
}
