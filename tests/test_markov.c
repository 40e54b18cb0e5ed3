/* SPDX-License-Identifier: BSD-3-Clause */
/* Stochastic jumps (dynkit/sde.h, src/ode/markov.c): a Markov chain's step takes the
 * states in order against one uniform number, each with the share h * rate of [0, 1)
 * (XPPAUT's rule), and Gillespie's direct method gives the exponential waiting time
 * -log(1 - u1)/R and the reaction whose share of R holds u2 R (numbers chosen so that the
 * sums are exact in binary, so the boundaries are exact); the fixed-step methods for noise
 * call a model's jumps before each step's evaluation, with the step's noise slots written,
 * the same jumps for the same seed and stream; rkmil refuses them. The model-file syntax
 * is checked through the translator's messages. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "dynkit/lang.h"
#include "dynkit/sde.h"

static double step_from(double z, const double *rates, double u)
{
    assert_int_equal(dyn_markov_step(&z, 3, rates, 0.125, u), 0);
    return z;
}

static void test_markov_step_shares(void **state)
{
    (void)state;
    /* from 1: to 0 at rate 2, to 2 at rate 4; over h = 1/8 the shares are [0, 1/4) and
     * [1/4, 3/4); the rest stays; the diagonal (99) and the other rows are not read */
    const double r[9] = {5, -1, 1, 2, 99, 4, NAN, 1, 1};
    assert_true(step_from(1.0, r, 0.0) == 0.0);
    assert_true(step_from(1.0, r, nextafter(0.25, 0.0)) == 0.0);
    assert_true(step_from(1.0, r, 0.25) == 2.0);
    assert_true(step_from(1.0, r, nextafter(0.75, 0.0)) == 2.0);
    assert_true(step_from(1.0, r, 0.75) == 1.0);
    assert_true(step_from(1.0, r, 0.999) == 1.0);
    /* a value within 1e-4 of a state is that state; another value stays as it is */
    assert_true(step_from(1.0 + 5e-5, r, 0.1) == 0.0);
    assert_true(step_from(0.5, r, 0.1) == 0.5);
    assert_true(step_from(7.0, r, 0.1) == 7.0);
    /* a negative or non-finite rate in the row read: -1, the state left as it was */
    double z = 0.0;
    assert_int_equal(dyn_markov_step(&z, 3, r, 0.125, 0.5), -1);
    assert_true(z == 0.0);
    z = 2.0;
    assert_int_equal(dyn_markov_step(&z, 3, r, 0.125, 0.5), -1);
    assert_true(z == 2.0);
}

static void test_gillespie_step(void **state)
{
    (void)state;
    const double rates[3] = {1.0, 0.0, 3.0};
    double out[4];
    assert_int_equal(dyn_gillespie_step(out, 3, rates, 0.5, 0.0), 0);
    assert_true(fabs(out[0] - log(2.0) / 4.0) <= 1e-16);
    assert_true(out[1] == 1.0 && out[2] == 0.0 && out[3] == 0.0);
    /* u2 R = 1 is the end of reaction 0's share; reaction 1 (rate 0) is never chosen */
    assert_int_equal(dyn_gillespie_step(out, 3, rates, 0.5, 0.25), 0);
    assert_true(out[1] == 0.0 && out[2] == 0.0 && out[3] == 1.0);
    assert_int_equal(dyn_gillespie_step(out, 3, rates, 0.5, nextafter(0.25, 0.0)), 0);
    assert_true(out[1] == 1.0 && out[3] == 0.0);
    assert_int_equal(dyn_gillespie_step(out, 3, rates, 0.0, nextafter(1.0, 0.0)), 0);
    assert_true(out[0] == 0.0 && out[3] == 1.0);
    /* every rate 0: no reaction, no time */
    const double none[2] = {0.0, 0.0};
    assert_int_equal(dyn_gillespie_step(out, 2, none, 0.5, 0.5), 0);
    assert_true(out[0] == 0.0 && out[1] == 0.0 && out[2] == 0.0);
    const double bad[2] = {1.0, -1.0};
    assert_int_equal(dyn_gillespie_step(out, 2, bad, 0.5, 0.5), -1);
    assert_true(isnan(out[0]) && isnan(out[2]));
}

/* x' = z with a two-state chain z (0 -> 1 at rate a, 1 -> 0 at rate b) jumping at the start
 * of each step from its uniform slot; the jump counts its calls. */
typedef struct tel_par {
    double a, b, u;
    long jumps;
    int map; /* the map x+ = x + z, z+ = z */
} tel_par;

static int tel_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    const tel_par *p = par;
    dydt[0] = p->map ? y[0] + y[1] : y[1];
    dydt[1] = p->map ? y[1] : 0.0;
    return 0;
}

static int tel_jump(double t, double h, double *y, void *par)
{
    (void)t;
    tel_par *p = par;
    const double r[4] = {0.0, p->a, p->b, 0.0};
    p->jumps++;
    return dyn_markov_step(y + 1, 2, r, h, p->u) ? 3 : 0;
}

static const int uniform_kind[1] = {DYN_NOISE_UNIFORM};

static int tel_run(dyn_sde_method method, tel_par *p, double T, double h, uint64_t stream,
                   double *y, dyn_result *res)
{
    static double work[1024];
    assert_true(dyn_sde_work_size(2, 1, 0) <= 1024);
    dyn_sde sde = {{tel_rhs, 2, p}, 1, uniform_kind, &p->u, DYN_NOISE_GENERAL};
    dyn_sde_opts o = {0};
    o.jump = tel_jump;
    o.h = h;
    o.seed = 11;
    o.stream = stream;
    const double y0[2] = {0.0, 0.0};
    return dyn_sde_solve(method, &sde, 0.0, T, y0, y, work, &o, res);
}

static void test_jumps_before_each_step(void **state)
{
    (void)state;
    /* a rate of 1/h jumps at the first step's start: x(h) = h z(h) = h */
    tel_par p = {8.0, 0.0, 0.0, 0, 0};
    double y[2];
    dyn_result res;
    assert_int_equal(tel_run(DYN_SDE_EM, &p, 0.125, 0.125, 0, y, &res), DYN_OK);
    assert_true(y[0] == 0.125 && y[1] == 1.0);
    assert_int_equal(p.jumps, 1);
    /* the same seed and stream, the same jumps; another stream, others */
    tel_par q = {0.5, 1.5, 0.0, 0, 0};
    double y1[2], y2[2], y3[2];
    assert_int_equal(tel_run(DYN_SDE_EM, &q, 200.0, 0.01, 4, y1, &res), DYN_OK);
    assert_int_equal(q.jumps, 20000);
    assert_int_equal(tel_run(DYN_SDE_EM, &q, 200.0, 0.01, 4, y2, &res), DYN_OK);
    assert_int_equal(tel_run(DYN_SDE_EM, &q, 200.0, 0.01, 5, y3, &res), DYN_OK);
    assert_true(y1[0] == y2[0] && y1[1] == y2[1]);
    assert_true(y1[0] != y3[0]);
    /* x(T) is the time spent in 1: mean T a/(a+b) = 50, variance about
     * 2 pi0 pi1 T/(a+b) = 37.5 (pi0 = 3/4, pi1 = 1/4); within 6 standard deviations */
    assert_true(fabs(y1[0] - 50.0) < 6.0 * sqrt(37.5));
    /* a map keeps the value after the jump */
    tel_par m = {1.0, 0.0, 0.0, 0, 1};
    assert_int_equal(tel_run(DYN_SDE_MAP, &m, 1.0, 1.0, 0, y, &res), DYN_OK);
    assert_true(y[0] == 1.0 && y[1] == 1.0);
    /* a jump that fails stops the run where it failed, naming the jumps */
    tel_par bad = {-1.0, 0.0, 0.0, 0, 0};
    assert_int_equal(tel_run(DYN_SDE_EM, &bad, 1.0, 0.125, 0, y, &res), DYN_ERR_RHS);
    assert_int_equal(res.rhs_status, 3);
    assert_non_null(strstr(res.message, "a transition rate of a Markov state is negative or "
                                        "not a number at t = 0 (the jumps returned 3"));
    assert_true(y[1] == 0.0); /* the chain's state before the failed jump, not NaN */
    /* rkmil's adaptive steps cannot take them */
    assert_int_equal(tel_run(DYN_SDE_RKMIL, &q, 1.0, 0.1, 0, y, &res), DYN_ERR_ARG);
    assert_non_null(strstr(res.message, "Markov states jump at the start of each step, with probability rate*h: rkmil"));
}

static void expect_error(const char *text, int line, int col, const char *what)
{
    char *out = NULL;
    dyn_lang_diag d;
    const int rc = dyn_ode_to_c("t.ode", text, strlen(text), &out, &d, NULL, NULL);
    char buf[2048];
    if (rc != 2 || d.line != line || d.col != col || !strstr(d.message, what))
        fail_msg("%s\nwanted %d:%d '%s', got %d:\n%s", text, line, col, what, rc,
                 dyn_lang_diag_format(&d, buf, sizeof buf));
    free(out);
}

static void test_model_file_syntax(void **state)
{
    (void)state;
    char *out = NULL;
    dyn_lang_diag d;
    /* a chain alone, and gill's NAME{A-B} shorthand in a map */
    const char *ok[] = {"par a=1,b=2\nmarkov z 2\n{0} {a}\n{b} {0}\n",
                        "r1=1\nr2=x\nspecial z=gill(0,r{1-2})\nx(t+1)=x+z(1)-z(2)\n"};
    for (int i = 0; i < 2; i++) {
        char buf[2048];
        if (dyn_ode_to_c("t.ode", ok[i], strlen(ok[i]), &out, &d, NULL, NULL) != 0)
            fail_msg("%s\n%s", ok[i], dyn_lang_diag_format(&d, buf, sizeof buf));
        assert_non_null(strstr(out, i ? "dyn_gillespie_step(" : ".jump = dk_jump"));
        free(out);
    }
    expect_error("x'=-x\nmarkov z 2\n{0} {1}\n", 2, 8, "2 rows of 2 rates in { } must follow");
    expect_error("x'=-x\nmarkov z 2\n{0} {1} {2}\n{1} {0}\n", 3, 9, "unexpected '{' after the row");
    expect_error("x'=-x\nmarkov z 2\n{0} {1}\n{1} 0\n", 4, 5, "rate 1 of row 1");
    expect_error("x'=-x\nmarkov z 51\n", 2, 10, "from 1 to 50");
    expect_error("x'=-x+z\nmarkov z 2\n{0} {q}\n{1} {0}\n", 3, 6, "unknown name 'q'");
    expect_error("x'=-x\nmarkov x 2\n{0} {1}\n{1} {0}\n", 2, 8, "'x' is already declared as a state on line 1");
    expect_error("x'=-x\nmarkov z 2\n{0} {1}\n{1} {0}\nglobal 1 x-1 {x=0}\n", 2, 8,
                 "Markov states together with events or globals (line 5)");
    expect_error("x'=-x\nspecial z=gill(0,x)\n", 2, 9, "draws one reaction per step of a discrete "
                 "map");
    expect_error("x(t+1)=x\nspecial z=gill(2,x)\n", 2, 16, "gill's method");
    expect_error("x(t+1)=x\nspecial z=gill(0,y)\n", 2, 18, "unknown name 'y'");
    expect_error("x(t+1)=x+z(2)\nspecial z=gill(0,x)\n", 1, 12, "from 0 to 1");
    /* an element that is a formula is named so (no stray number after the message) */
    expect_error("x(t+1)=x+z(-1)\nspecial z=gill(0,x)\n", 1, 12,
                 "line); here it is a formula");
    expect_error("x(t+1)=x+z(2)\nspecial z=gill(0,x)\n", 1, 12, "line); here it is 2");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_markov_step_shares),
        cmocka_unit_test(test_gillespie_step),
        cmocka_unit_test(test_jumps_before_each_step),
        cmocka_unit_test(test_model_file_syntax),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
