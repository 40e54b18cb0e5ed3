/* SPDX-License-Identifier: BSD-3-Clause */
/* The dynkit command line against its contract (the built binary, DYNKIT_CLI).
 *
 * - `run` writes CSV "t,<states>" with %.17g numbers that equal the library's results bit
 *   for bit (--final, full runs, --every, --set, --init, aliases of methods), --output FILE
 *   writes the same bytes as stdout, --outputs adds the pendulum's energy and height
 *   (energy conserved with RK4; the maximum height of homework problem 1a), --trace prints
 *   the stages on stderr and leaves stdout clean.
 * - Bad input exits 2 with a message on stderr that names the input and what is accepted,
 *   and nothing on stdout; a run whose state becomes NaN/Inf exits 1, names the state and
 *   time, and keeps the finite rows computed up to there.
 * - models, methods, info and --help. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "dynkit/io.h"
#include "dynkit/models.h"
#include "test_cli_run.h"
#include "test_util.h"

/* ---- running the binary ---- */

static int setup(void **state)
{
    (void)state;
    return cli_make_tmpdir("cli");
}

static int teardown(void **state)
{
    (void)state;
    static const char *const files[] = {"file.csv", NULL};
    return cli_teardown_files(files);
}

/* ---- CSV ---- */

typedef struct csv {
    char header[256];
    int cols;
    long rows;
    double *v; /* (rows x cols) */
} csv;

/* Parse "header\nrow\n...": every field must be a whole number for strtod. */
static csv parse_csv(const char *text)
{
    csv c = {0};
    const char *nl = strchr(text, '\n');
    CHECK(nl != NULL, "no header line in stdout: '%s'", text);
    size_t hl = (size_t)(nl - text);
    assert_true(hl < sizeof c.header);
    memcpy(c.header, text, hl);
    c.header[hl] = '\0';
    c.cols = 1;
    for (const char *p = c.header; *p; p++)
        c.cols += *p == ',';
    long lines = 0;
    for (const char *p = nl + 1; *p; p++)
        lines += *p == '\n';
    c.v = malloc(((size_t)lines + 1) * (size_t)c.cols * sizeof *c.v);
    assert_non_null(c.v);
    const char *p = nl + 1;
    while (*p) {
        for (int j = 0; j < c.cols; j++) {
            char *end;
            c.v[c.rows * c.cols + j] = strtod(p, &end);
            char want = j + 1 < c.cols ? ',' : '\n';
            CHECK(end != p && *end == want, "row %ld field %d is not a number: '%.40s'", c.rows,
                  j, p);
            p = end + 1;
        }
        c.rows++;
    }
    return c;
}

static double cell(const csv *c, long row, int col) { return c->v[row * c->cols + col]; }

/* ---- the library's answer for the same run ---- */

static sample_log lib;

/* Solve a built-in model with defaults changed by (param, value) and (state, value); the
 * samples go to `lib`, the final state to y. Returns the status; *res gets the details. */
static int lib_run(const char *model_name, const char *method, double t0, double t1, double h,
                   const char *param, double pval, const char *statename, double sval,
                   double *y, dyn_result *res)
{
    const dyn_model *m = dyn_model_find(model_name);
    assert_non_null(m);
    double par[16], y0[TEST_MAX_N], work[TEST_WORK];
    char err[128];
    assert_true(m->par_size <= sizeof par && m->n_states <= TEST_MAX_N);
    assert_int_equal(dyn_model_default_params(m, par, err, sizeof err), 0);
    memcpy(y0, m->y0, (size_t)m->n_states * sizeof *y0);
    if (param)
        dyn_model_set_param(m, par, dyn_model_param_index(m, param), pval);
    if (statename)
        y0[dyn_model_state_index(m, statename)] = sval;
    dyn_system sys = {m->rhs, m->n_states, par};
    dyn_fixed_opts opts = {0};
    opts.output = sample_log_output;
    opts.output_ctx = &lib;
    sample_log_init(&lib, m->n_states);
    return dyn_fixed_solve(dyn_method_find(method), &sys, t0, t1, h, y0, y, work, &opts, res);
}

/* Every row of c equals the library's samples bit for bit (time and states). */
static void check_rows_equal_library(const csv *c, const char *what)
{
    CHECK(c->rows == lib.count, "%s: %ld rows, library %ld samples", what, c->rows, lib.count);
    for (long r = 0; r < c->rows; r++) {
        CHECK(same_bits(cell(c, r, 0), lib.t[r]), "%s: row %ld t = %.17g, library %.17g", what, r,
              cell(c, r, 0), lib.t[r]);
        for (int q = 0; q < lib.n; q++)
            CHECK(same_bits(cell(c, r, q + 1), lib.y[r][q]),
                  "%s: row %ld state %d = %.17g, library %.17g", what, r, q, cell(c, r, q + 1),
                  lib.y[r][q]);
    }
}

/* ---- run: results ---- */

static void test_final_equals_library_bitwise(void **state)
{
    (void)state;
    static const char *const methods[] = {"euler", "heun", "midpoint", "rk4",
                                          "ralston", "rk38", "modified-euler", "rk2"};
    for (size_t i = 0; i < sizeof methods / sizeof methods[0]; i++) {
        cli_result r = cli("run vanderpol --method %s --step 0.01 --tspan 0:15 --final",
                           methods[i]);
        CHECK(r.status == 0, "%s: exit %d, stderr: %s", methods[i], r.status, r.err);
        csv c = parse_csv(r.out);
        assert_string_equal(c.header, "t,y1,y2");
        assert_int_equal(c.rows, 1);
        assert_true(cell(&c, 0, 0) == 15.0);
        double y[2];
        dyn_result res;
        assert_int_equal(lib_run("vanderpol", methods[i], 0, 15, 0.01, NULL, 0, NULL, 0, y, &res),
                         DYN_OK);
        CHECK(same_bits(cell(&c, 0, 1), y[0]) && same_bits(cell(&c, 0, 2), y[1]),
              "%s: CLI (%.17g, %.17g), library (%.17g, %.17g)", methods[i], cell(&c, 0, 1),
              cell(&c, 0, 2), y[0], y[1]);
        /* The exact text: the shortest round-trip strings of the library's numbers. */
        char line[128], a[DYN_DOUBLE_CHARS], b[DYN_DOUBLE_CHARS];
        dyn_format_double(y[0], a);
        dyn_format_double(y[1], b);
        snprintf(line, sizeof line, "t,y1,y2\n15,%s,%s\n", a, b);
        assert_string_equal(r.out, line);
        assert_string_equal(r.err, "");
        free(c.v);
        cli_free(&r);
    }
}

static void test_full_run_and_every(void **state)
{
    (void)state;
    double y[2];
    dyn_result res;
    assert_int_equal(lib_run("vanderpol", "rk4", 0, 15, 0.01, NULL, 0, NULL, 0, y, &res), DYN_OK);
    cli_result r = cli("run vanderpol --method rk4 --step 0.01 --tspan 0:15");
    assert_int_equal(r.status, 0);
    csv c = parse_csv(r.out);
    assert_string_equal(c.header, "t,y1,y2");
    assert_int_equal(c.rows, 1501);
    check_rows_equal_library(&c, "full run");
    assert_true(cell(&c, 1500, 0) == 15.0);
    free(c.v);
    cli_free(&r);

    /* --every 100: samples 0, 100, ..., 1500, i.e. t = 0, 1, ..., 15. */
    r = cli("run vanderpol --method rk4 --step 0.01 --tspan 0:15 --every 100");
    assert_int_equal(r.status, 0);
    c = parse_csv(r.out);
    assert_int_equal(c.rows, 16);
    for (long i = 0; i < 16; i++) {
        assert_true(same_bits(cell(&c, i, 0), lib.t[100 * i]));
        assert_true(same_bits(cell(&c, i, 1), lib.y[100 * i][0]));
        assert_true(same_bits(cell(&c, i, 2), lib.y[100 * i][1]));
        assert_true(fabs(cell(&c, i, 0) - (double)i) < 1e-12);
    }
    free(c.v);
    cli_free(&r);

    /* --every 7: 0, 7, ..., 1498 and the last one, 1500. */
    r = cli("run vanderpol --method rk4 --step 0.01 --tspan 0:15 --every 7");
    assert_int_equal(r.status, 0);
    c = parse_csv(r.out);
    assert_int_equal(c.rows, 1500 / 7 + 2);
    assert_true(same_bits(cell(&c, c.rows - 2, 0), lib.t[1498]));
    assert_true(cell(&c, c.rows - 1, 0) == 15.0);
    free(c.v);
    cli_free(&r);
}

/* Homework problem 1e: one Euler step of the pendulum (also the pendulum's default run). */
static void test_pendulum_euler_step(void **state)
{
    (void)state;
    const char *expected = "t,phi,dphi\n"
                           "0,0,1.5707963267948966\n"
                           "0.2,0.3141592653589793,1.5707963267948966\n";
    cli_result r = cli("run pendulum --method euler --step 0.2 --tspan 0:0.2");
    assert_int_equal(r.status, 0);
    assert_string_equal(r.out, expected);
    cli_free(&r);
    /* the model's default run is adaptive over 0:10 s, not this single Euler step */
    r = cli("run pendulum --final");
    assert_int_equal(r.status, 0);
    assert_true(strncmp(r.out, "t,phi,dphi\n10,", 14) == 0);
    cli_free(&r);
}

static void test_end_policy_option(void **state)
{
    (void)state;
    cli_result r = cli("run vanderpol --method heun --step 0.3 --tspan 0:1");
    assert_int_equal(r.status, 0);
    csv c = parse_csv(r.out);
    assert_int_equal(c.rows, 5);
    assert_true(cell(&c, 4, 0) == 1.0);
    free(c.v);
    cli_free(&r);
    r = cli("run vanderpol --method heun --step 0.3 --tspan 0:1 --end grid");
    assert_int_equal(r.status, 0);
    c = parse_csv(r.out);
    assert_int_equal(c.rows, 4);
    assert_true(same_bits(cell(&c, 3, 0), 3.0 * 0.3));
    free(c.v);
    cli_free(&r);
}

static void test_trace_goes_to_stderr(void **state)
{
    (void)state;
    cli_result plain = cli("run pendulum --method euler --step 0.2 --tspan 0:0.6");
    cli_result traced = cli("run pendulum --method euler --step 0.2 --tspan 0:0.6 --trace 1");
    assert_int_equal(traced.status, 0);
    assert_int_equal(traced.out_len, plain.out_len);
    assert_memory_equal(traced.out, plain.out, plain.out_len); /* stdout: clean CSV */
    assert_string_equal(plain.err, "");
    assert_non_null(strstr(traced.err, "k1"));
    assert_non_null(strstr(traced.err, "y_{n+1}"));
    assert_non_null(strstr(traced.err, "0.3141592653589793")); /* the stepped phi */
    assert_non_null(strstr(traced.err, "step 1"));
    assert_null(strstr(traced.err, "step 2")); /* only the first step */
    cli_free(&plain);
    cli_free(&traced);

    cli_result heun = cli("run pendulum --method heun --step 0.2 --tspan 0:0.2 --trace 1");
    assert_int_equal(heun.status, 0);
    assert_non_null(strstr(heun.err, "predictor"));
    assert_non_null(strstr(heun.err, "corrector"));
    assert_non_null(strstr(heun.err, "k2"));
    csv c = parse_csv(heun.out);
    assert_int_equal(c.rows, 2);
    free(c.v);
    cli_free(&heun);
}

static void test_set_and_init_take_effect(void **state)
{
    (void)state;
    double y[2], y_default[2];
    dyn_result res;
    assert_int_equal(lib_run("vanderpol", "rk4", 0, 15, 0.01, NULL, 0, NULL, 0, y_default, &res),
                     DYN_OK);

    cli_result r = cli("run vanderpol --method rk4 --set mu=2 --final");
    assert_int_equal(r.status, 0);
    csv c = parse_csv(r.out);
    assert_int_equal(lib_run("vanderpol", "rk4", 0, 15, 0.01, "mu", 2.0, NULL, 0, y, &res), DYN_OK);
    assert_true(same_bits(cell(&c, 0, 1), y[0]) && same_bits(cell(&c, 0, 2), y[1]));
    assert_true(fabs(y[0] - y_default[0]) > 1e-3); /* mu matters */
    free(c.v);
    cli_free(&r);

    r = cli("run vanderpol --method rk4 --init y1=1 --final");
    assert_int_equal(r.status, 0);
    c = parse_csv(r.out);
    assert_int_equal(lib_run("vanderpol", "rk4", 0, 15, 0.01, NULL, 0, "y1", 1.0, y, &res), DYN_OK);
    assert_true(same_bits(cell(&c, 0, 1), y[0]) && same_bits(cell(&c, 0, 2), y[1]));
    assert_true(fabs(y[0] - y_default[0]) > 1e-6);
    free(c.v);
    cli_free(&r);

    /* A multiple of pi: exactly DYN_PI / 4. */
    r = cli("run pendulum --method rk4 --step 0.01 --tspan 0:2 --init dphi=pi/4");
    assert_int_equal(r.status, 0);
    c = parse_csv(r.out);
    assert_true(same_bits(cell(&c, 0, 2), DYN_PI / 4.0));
    assert_int_equal(lib_run("pendulum", "rk4", 0, 2, 0.01, NULL, 0, "dphi", DYN_PI / 4.0, y, &res),
                     DYN_OK);
    check_rows_equal_library(&c, "--init dphi=pi/4");
    free(c.v);
    cli_free(&r);
}

static void test_output_file_same_bytes(void **state)
{
    (void)state;
    char path[512];
    snprintf(path, sizeof path, "%s/file.csv", cli_tmpdir);
    cli_result to_stdout = cli("run vanderpol --method heun --step 0.01 --tspan 0:2");
    cli_result to_file = cli("run vanderpol --method heun --step 0.01 --tspan 0:2 --output '%s'",
                             path);
    assert_int_equal(to_stdout.status, 0);
    assert_int_equal(to_file.status, 0);
    assert_int_equal(to_file.out_len, 0);
    size_t len;
    char *bytes = cli_read_file(path, &len);
    assert_true(len > 0);
    assert_int_equal(len, to_stdout.out_len);
    assert_memory_equal(bytes, to_stdout.out, len);
    free(bytes);
    cli_free(&to_stdout);
    cli_free(&to_file);
}

/* --outputs: energy and height of the pendulum. With RK4 at h = 0.01 the energy is
 * conserved to 1e-8 (relative), and the largest height is that of homework problem 1a,
 * (l dphi0)^2 / (2 g) = 12.10 m for l = g = 9.81, dphi0 = pi/2. */
static void test_pendulum_outputs(void **state)
{
    (void)state;
    cli_result r = cli("run pendulum --method rk4 --step 0.01 --tspan 0:10 --outputs");
    CHECK(r.status == 0, "exit %d: %s", r.status, r.err);
    csv c = parse_csv(r.out);
    assert_string_equal(c.header, "t,phi,dphi,energy,height");
    assert_int_equal(c.rows, 1001);
    const dyn_pendulum_par par = {.m = 2.0, .l = 9.81, .g = 9.81};
    const double e0 = cell(&c, 0, 3);
    double worst = 0.0, hmax = 0.0;
    for (long i = 0; i < c.rows; i++) {
        double y[2] = {cell(&c, i, 1), cell(&c, i, 2)};
        assert_true(same_bits(cell(&c, i, 3), dyn_pendulum_energy(&par, y)));
        assert_true(fabs(cell(&c, i, 4) - par.l * (1.0 - cos(y[0]))) <= 1e-12);
        worst = fmax(worst, fabs(cell(&c, i, 3) - e0) / e0);
        hmax = fmax(hmax, cell(&c, i, 4));
    }
    const double dphi0 = DYN_PI / 2.0;
    CHECK(fabs(e0 - 0.5 * par.m * par.l * par.l * dphi0 * dphi0) < 1e-12 * e0, "E0 = %.17g", e0);
    CHECK(worst < 1e-8, "energy drift %.3g (relative)", worst);
    const double hexact = par.l * par.l * dphi0 * dphi0 / (2.0 * par.g);
    CHECK(fabs(hmax - hexact) < 1e-3, "max height %.6f m, energy says %.6f m", hmax, hexact);
    free(c.v);
    cli_free(&r);
    /* Euler at a coarse step visibly gains energy: the check above can fail. */
    r = cli("run pendulum --method euler --step 0.1 --tspan 0:10 --outputs");
    assert_int_equal(r.status, 0);
    c = parse_csv(r.out);
    assert_true(cell(&c, c.rows - 1, 3) > 1.1 * cell(&c, 0, 3));
    free(c.v);
    cli_free(&r);
}

/* ---- run: errors ---- */

/* Exit 2, nothing on stdout, and stderr mentions every word of `words` (NULL-terminated). */
static void check_usage_error(const char *args, const char *const *words)
{
    cli_result r = cli("%s", args);
    CHECK(r.status == 2, "'%s': exit %d, expected 2 (stderr: %s)", args, r.status, r.err);
    CHECK(r.out_len == 0, "'%s': stdout not empty: '%s'", args, r.out);
    CHECK(strncmp(r.err, "dynkit: error: ", 15) == 0, "'%s': stderr '%s'", args, r.err);
    for (const char *const *w = words; *w; w++)
        CHECK(strstr(r.err, *w) != NULL, "'%s': stderr does not mention '%s': %s", args, *w,
              r.err);
    cli_free(&r);
}

#define USAGE(args, ...) check_usage_error(args, (const char *const[]){__VA_ARGS__, NULL})

static void test_bad_input_exits_2(void **state)
{
    (void)state;
    USAGE("run vanderpol --method nosuch", "'nosuch'", "euler", "heun", "rk4", "modified-euler");
    USAGE("run vanderpol --step -0.1", "--step", "-0.1", "> 0");
    USAGE("run vanderpol --step 0", "--step", "'0'", "> 0");
    USAGE("run vanderpol --step abc", "--step", "abc");
    USAGE("run vanderpol --step nan", "--step", "nan");
    USAGE("run vanderpol --step", "--step", "value");
    USAGE("run vanderpol --tspan 5:1", "--tspan", "5:1");
    USAGE("run vanderpol --tspan foo", "--tspan", "foo", "T0:T1");
    USAGE("run vanderpol --tspan 0:inf", "--tspan", "0:inf");
    USAGE("run nosuch", "'nosuch'", "pendulum", "vanderpol");
    USAGE("run", "MODEL", "pendulum");
    USAGE("run vanderpol --bogus", "--bogus");
    USAGE("run vanderpol --set nosuch=1", "nosuch", "mu");
    USAGE("run vanderpol --set mu", "mu", "NAME=VALUE");
    USAGE("run vanderpol --init x=abc", "x=abc");
    USAGE("run pendulum --init phi=abc", "phi=abc");
    USAGE("run pendulum --init x=1", "'x'", "phi", "dphi");
    USAGE("run pendulum --set l=0", "l", "> 0");
    USAGE("run vanderpol --every 0", "--every", "'0'");
    USAGE("run vanderpol --end sometimes", "sometimes", "exact", "grid");
    USAGE("info nosuch", "'nosuch'", "pendulum");
    USAGE("info", "MODEL");
    USAGE("models extra", "extra");
    USAGE("nosuch", "'nosuch'", "run", "models", "methods", "info");
}

/* A step too small for the span is a usage error like a negative one: the grid is refused
 * (2^53 steps at most), so nothing may be written to stdout, not even the header. */
static void test_step_too_small_is_a_clean_usage_error(void **state)
{
    (void)state;
    USAGE("run vanderpol --step 1e-300", "step");
}

/* The state becomes NaN/Inf: exit 1, stderr names the state and the time, stdout holds the
 * rows computed up to there, all finite and equal to the library's. */
static void test_nonfinite_run_exits_1(void **state)
{
    (void)state;
    double y[2];
    dyn_result res;
    int rc = lib_run("vanderpol", "euler", 0, 15, 0.1, "mu", 1e6, NULL, 0, y, &res);
    assert_int_equal(rc, DYN_ERR_NONFINITE);
    assert_true(lib.count >= 2);
    const dyn_model *m = dyn_model_find("vanderpol");
    char when[64];
    dyn_format_double(res.fail_t, when);

    cli_result r = cli("run vanderpol --set mu=1e6 --method euler --step 0.1");
    assert_int_equal(r.status, 1);
    CHECK(strstr(r.err, m->states[res.fail_index].name) != NULL && strstr(r.err, when) != NULL,
          "stderr should name state %s and t = %s: %s", m->states[res.fail_index].name, when,
          r.err);
    CHECK(strstr(r.err, "NaN") || strstr(r.err, "finite"), "stderr does not say what: %s", r.err);
    csv c = parse_csv(r.out);
    assert_string_equal(c.header, "t,y1,y2");
    for (long i = 0; i < c.rows * c.cols; i++)
        assert_true(isfinite(c.v[i]));
    check_rows_equal_library(&c, "non-finite run");
    free(c.v);
    cli_free(&r);

    /* With --final: the last good state. */
    r = cli("run vanderpol --set mu=1e6 --method euler --step 0.1 --final");
    assert_int_equal(r.status, 1);
    c = parse_csv(r.out);
    assert_int_equal(c.rows, 1);
    assert_true(same_bits(cell(&c, 0, 0), res.t));
    assert_true(same_bits(cell(&c, 0, 1), y[0]) && same_bits(cell(&c, 0, 2), y[1]));
    free(c.v);
    cli_free(&r);
}

/* ---- listings and help ---- */

/* The line of text that starts with prefix (after a newline or at the start), or NULL. */
static const char *line_starting(const char *text, const char *prefix, char *line, size_t size)
{
    size_t n = strlen(prefix);
    for (const char *p = text; p && *p; p = strchr(p, '\n') ? strchr(p, '\n') + 1 : NULL) {
        if (strncmp(p, prefix, n) == 0) {
            const char *end = strchr(p, '\n');
            size_t len = end ? (size_t)(end - p) : strlen(p);
            if (len >= size)
                len = size - 1;
            memcpy(line, p, len);
            line[len] = '\0';
            return line;
        }
    }
    return NULL;
}

static void test_models_methods_info(void **state)
{
    (void)state;
    char line[256];
    cli_result r = cli("models");
    assert_int_equal(r.status, 0);
    for (int i = 0; i < dyn_model_count(); i++)
        CHECK(line_starting(r.out, dyn_model_at(i)->name, line, sizeof line) != NULL,
              "models does not list %s", dyn_model_at(i)->name);
    cli_free(&r);

    r = cli("methods");
    assert_int_equal(r.status, 0);
    for (int i = 0; i < dyn_method_count(); i++) {
        const dyn_tableau *m = dyn_method_at(i);
        char prefix[64];
        snprintf(prefix, sizeof prefix, "%s ", m->name);
        CHECK(line_starting(r.out, prefix, line, sizeof line) != NULL, "methods: no line for %s",
              m->name);
        if (m->alias)
            CHECK(strstr(line, m->alias) != NULL, "methods: alias %s not on the line of %s",
                  m->alias, m->name);
    }
    cli_free(&r);

    /* info pendulum: states, parameters and outputs with their units. */
    r = cli("info pendulum");
    assert_int_equal(r.status, 0);
    static const char *const rows[][2] = {
        {"  m ", "kg"},  {"  l ", " m "},       {"  g ", "m/s^2"},   {"  phi ", "rad"},
        {"  dphi ", "rad/s"}, {"  energy ", " J "}, {"  height ", " m "},
    };
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        CHECK(line_starting(r.out, rows[i][0], line, sizeof line) != NULL,
              "info pendulum: no line for '%s'", rows[i][0]);
        CHECK(strstr(line, rows[i][1]) != NULL, "info pendulum: '%s' lacks unit '%s'", line,
              rows[i][1]);
    }
    assert_non_null(strstr(r.out, "9.81")); /* l and g defaults */
    cli_free(&r);

    r = cli("info vanderpol");
    assert_int_equal(r.status, 0);
    assert_non_null(line_starting(r.out, "  mu ", line, sizeof line));
    assert_non_null(line_starting(r.out, "  y1 ", line, sizeof line));
    cli_free(&r);
}

static void test_help_and_bare_invocation(void **state)
{
    (void)state;
    static const char *const helps[] = {"--help",        "-h",           "run --help",
                                        "run vanderpol --help", "models --help", "methods --help",
                                        "info --help"};
    for (size_t i = 0; i < sizeof helps / sizeof helps[0]; i++) {
        cli_result r = cli("%s", helps[i]);
        CHECK(r.status == 0, "'%s': exit %d", helps[i], r.status);
        CHECK(strstr(r.out, "Usage") != NULL, "'%s': no usage text", helps[i]);
        cli_free(&r);
    }
    cli_result r = cli("run --help");
    assert_non_null(strstr(r.out, "--method"));
    assert_non_null(strstr(r.out, "--tspan"));
    cli_free(&r);

    r = cli("");
    assert_int_equal(r.status, 2);
    CHECK(strstr(r.out, "Usage") || strstr(r.err, "Usage"), "bare dynkit: no usage text");
    cli_free(&r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_final_equals_library_bitwise),
        cmocka_unit_test(test_full_run_and_every),
        cmocka_unit_test(test_pendulum_euler_step),
        cmocka_unit_test(test_end_policy_option),
        cmocka_unit_test(test_trace_goes_to_stderr),
        cmocka_unit_test(test_set_and_init_take_effect),
        cmocka_unit_test(test_output_file_same_bytes),
        cmocka_unit_test(test_pendulum_outputs),
        cmocka_unit_test(test_bad_input_exits_2),
        cmocka_unit_test(test_step_too_small_is_a_clean_usage_error),
        cmocka_unit_test(test_nonfinite_run_exits_1),
        cmocka_unit_test(test_models_methods_info),
        cmocka_unit_test(test_help_and_bare_invocation),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
