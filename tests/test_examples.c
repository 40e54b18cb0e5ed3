/* SPDX-License-Identifier: BSD-3-Clause */
/* The C API examples (examples/solve_ivp.c, events.c, double_pendulum.c, linearize.c),
 * built beside the tool, run and their output checked against independent numbers:
 * - solve_ivp: the Lorenz rows at t = 0, 0.25, ..., 2 and the dense-output value at 1.1
 *   against dyn_solve with dp45 at 1e-12;
 * - events: every printed bounce time against the closed form t_{k+1} = t_k + 2 t_1 e^k,
 *   and the terminal event at 9 s;
 * - double_pendulum: the energy column stays at its initial 19.62 J (both rods level, m2 =
 *   0.5 kg), and the drift the example reports is below 1e-7 J;
 * - linearize (when built with LAPACK): the pendulum's bottom and top with +-i sqrt(g/l)
 *   and +-sqrt(g/l). */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "dynkit/dynkit.h"
#include "test_cli_run.h"
#include "test_util.h"

/* Run examples/NAME (built beside the tool) and return its stdout. */
static char *run_example(const char *name, int *status)
{
    char cmd[1024];
    const char *cli = DYNKIT_CLI;
    const char *slash = strrchr(cli, '/');
    const int dir = slash ? (int)(slash - cli) : 0;
    snprintf(cmd, sizeof cmd, "'%.*s/example_%s'", dir, cli, name);
    return cli_capture(cmd, status);
}

typedef struct lorenz_par {
    double sigma, rho, beta;
} lorenz_par;

static int lorenz(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    const lorenz_par *p = par;
    dydt[0] = p->sigma * (y[1] - y[0]);
    dydt[1] = y[0] * (p->rho - y[2]) - y[1];
    dydt[2] = y[0] * y[1] - p->beta * y[2];
    return 0;
}

static int keep(long k, double t, const double *y, void *ctx)
{
    (void)t;
    double *rows = ctx;
    memcpy(rows + 3 * k, y, 3 * sizeof *y);
    return 0;
}

static void test_solve_ivp_example(void **state)
{
    (void)state;
    int status;
    char *out = run_example("solve_ivp", &status);
    assert_int_equal(status, 0);
    /* the reference: dp45 at 1e-12 on the same grid */
    lorenz_par par = {10.0, 28.0, 8.0 / 3.0};
    dyn_system sys = {lorenz, 3, &par};
    const dyn_tableau *m = dyn_method_find("dp45");
    double rows[9 * 3], y[3];
    dyn_solve_opts o = {.rtol = 1e-12, .atol = 1e-12, .out_step = 0.25};
    o.output = keep;
    o.output_ctx = rows;
    dyn_solve_opts to_end = {.rtol = 1e-12, .atol = 1e-12};
    double *work = malloc(dyn_solve_work_size(m, 3, &o) * sizeof *work);
    const double y0[3] = {1.0, 1.0, 1.0};
    dyn_result res;
    assert_int_equal(dyn_solve(m, &sys, 0.0, 2.0, y0, y, work, &o, &res), DYN_OK);
    free(work);
    const char *line = strchr(out, '\n') + 1; /* after the header */
    for (int i = 0; i < 9; i++) {
        double t, x[3];
        assert_int_equal(sscanf(line, "%lf %lf %lf %lf", &t, &x[0], &x[1], &x[2]), 4);
        assert_true(fabs(t - 0.25 * i) < 1e-12);
        for (int j = 0; j < 3; j++)
            if (fabs(x[j] - rows[3 * i + j]) > 1e-6)
                fail_msg("t = %g, state %d: example %.12f, reference %.12f", t, j, x[j],
                         rows[3 * i + j]);
        line = strchr(line, '\n') + 1;
    }
    double x11;
    assert_int_equal(sscanf(line, "x(1.1) = %lf from the dense output", &x11), 1);
    work = malloc(dyn_solve_work_size(m, 3, NULL) * sizeof *work);
    assert_int_equal(dyn_solve(m, &sys, 0.0, 1.1, y0, y, work, &to_end, &res), DYN_OK);
    free(work);
    assert_true(fabs(x11 - y[0]) < 1e-6);
    assert_non_null(strstr(line, "calls of f"));
    free(out);
}

static void test_events_example(void **state)
{
    (void)state;
    int status;
    char *out = run_example("events", &status);
    assert_int_equal(status, 0);
    const double t1 = sqrt(2.0 * 10.0 / 9.81);
    double tk = t1, fly = 2.0 * t1 * 0.8;
    const char *p = out;
    int k = 0;
    while ((p = strstr(p, "bounce ")) != NULL && k < 10) {
        int idx;
        double t;
        if (sscanf(p, "bounce %d at t = %lf", &idx, &t) != 2)
            break;
        assert_int_equal(idx, k + 1);
        if (fabs(t - tk) > 1e-9)
            fail_msg("bounce %d at %.15f, closed form %.15f", idx, t, tk);
        tk += fly;
        fly *= 0.8;
        k++;
        p++;
    }
    assert_int_equal(k, 5); /* 1.43, 3.71, 5.54, 7.00, 8.17 s; then the stop at 9 s */
    assert_non_null(strstr(out, "stop at t = 9.000000000000000 s"));
    assert_non_null(strstr(out, "5 bounces"));
    free(out);
}

static void test_double_pendulum_example(void **state)
{
    (void)state;
    int status;
    char *out = run_example("double_pendulum", &status);
    assert_int_equal(status, 0);
    assert_non_null(strstr(out, "m2  =  0.50 kg"));
    const char *line = strstr(out, "t [s]");
    assert_non_null(line);
    line = strchr(line, '\n') + 1;
    for (int i = 0; i <= 10; i++) {
        double t, th1, th2, x2, y2, e, de;
        assert_int_equal(sscanf(line, "%lf %lf %lf %lf %lf %lf %lf", &t, &th1, &th2, &x2, &y2,
                                &e, &de),
                         7);
        assert_true(t == (double)i);
        assert_true(fabs(e - 19.62) < 1e-6); /* m1 g l1 + m2 g (l1 + l2), both rods level */
        assert_true(fabs(de) < 1e-7);
        /* the lower bob is within reach of the pivot */
        assert_true(hypot(x2, y2) <= 2.0 + 1e-9);
        line = strchr(line, '\n') + 1;
    }
    double drift;
    assert_int_equal(sscanf(line, "energy conserved to %lf J", &drift), 1);
    assert_true(drift < 1e-7);
    free(out);
}

/* linearize (built when dynkit is built with LAPACK): the equilibria found from (0.5, 0.2)
 * and (2.8, 0) are the bottom and the top, with +-i sqrt(g/l) and +-sqrt(g/l) for l = 2 m
 * to 1e-12 (checked by the program itself, which exits 1 otherwise, and here). */
static void test_linearize_example(void **state)
{
    (void)state;
    char path[1024];
    const char *cli = DYNKIT_CLI;
    const char *slash = strrchr(cli, '/');
    snprintf(path, sizeof path, "%.*s/example_linearize", slash ? (int)(slash - cli) : 0, cli);
    FILE *f = fopen(path, "rb");
    if (!f) {
        print_message("SKIP: example_linearize is not built (dynkit without LAPACK)\n");
        skip();
    }
    fclose(f);
    int status;
    char *out = run_example("linearize", &status);
    assert_int_equal(status, 0);
    const double w = sqrt(9.81 / 2.0);
    const char *line = out;
    for (int k = 0; k < 2; k++) {
        double phi, r0, i0, r1, i1;
        int it;
        line = strstr(line, "phi = ");
        assert_non_null(line);
        assert_int_equal(sscanf(line,
                                "phi = %lf rad after %d iterations: eigenvalues %lf %lfi, "
                                "%lf %lfi",
                                &phi, &it, &r0, &i0, &r1, &i1),
                         6);
        assert_true(fabs(phi - (k ? DYN_PI : 0.0)) < 1e-12);
        const double a = k ? r1 : i1, b = k ? i1 : r1; /* the pair, the other part */
        assert_true(fabs(a - w) < 1e-12 * w && fabs(b) < 1e-12 * w);
        line++;
    }
    assert_non_null(strstr(out, ": marginal"));
    assert_non_null(strstr(out, ": unstable"));
    free(out);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_solve_ivp_example),
        cmocka_unit_test(test_events_example),
        cmocka_unit_test(test_double_pendulum_example),
        cmocka_unit_test(test_linearize_example),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
