/* SPDX-License-Identifier: BSD-3-Clause */
/* The library's one entry for a run of any model (dyn_run, dynkit/run.h), against the
 * drivers it chooses and against exact solutions:
 * - a fixed-step method runs the homework's loop: the same bits as dyn_fixed_solve;
 * - an adaptive method gives the same bits as dyn_solve with the same options, and the
 *   pendulum's first turn at the quarter period K(k)/w when the event is asked for;
 * - a model with a reset (a bouncing decay) runs its reset without being asked, with a
 *   fixed-step method too, and its samples stay on the grid;
 * - a model's output rules: no samples before t_trans, a stop at the bound with the state
 *   named in the message;
 * - a model with noise and a fixed-step method takes Euler–Maruyama: with zero noise
 *   amplitude it is Euler's method;
 * - the method names of every family resolve, cvode without its backend and bad options are
 *   refused with a message. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "dynkit/dynkit.h"
#include "dynkit/models.h"
#include "test_util.h"

typedef struct samples {
    long n;
    double t[4096], y0[4096];
} samples;

static int keep(long k, double t, const double *y, void *ctx)
{
    (void)k;
    samples *s = ctx;
    if (s->n < 4096) {
        s->t[s->n] = t;
        s->y0[s->n] = y[0];
    }
    s->n++;
    return 0;
}

static void pendulum_par(dyn_pendulum_par *p)
{
    char err[128];
    assert_int_equal(dyn_model_default_params(&dyn_model_pendulum, p, err, sizeof err), 0);
}

static void test_fixed_step_is_the_homework_loop(void **state)
{
    (void)state;
    const dyn_model *m = &dyn_model_pendulum;
    dyn_pendulum_par p;
    pendulum_par(&p);
    const double y0[2] = {0.3, 0.0};
    static samples a, b;
    memset(&a, 0, sizeof a);
    memset(&b, 0, sizeof b);
    dyn_run_opts o = {.method = dyn_run_method_find("rk4"), .t0 = 0, .t1 = 2, .step = 0.01};
    o.output = keep;
    o.output_ctx = &a;
    double y[2], yd[2];
    dyn_result res;
    assert_int_equal(dyn_run(m, &p, y0, &o, y, &res), DYN_OK);
    const dyn_system sys = {m->rhs, 2, &p};
    double *work = malloc(dyn_fixed_work_size(o.method, 2) * sizeof *work);
    dyn_fixed_opts fo = {.output = keep, .output_ctx = &b};
    dyn_result rd;
    assert_int_equal(dyn_fixed_solve(o.method, &sys, 0, 2, 0.01, y0, yd, work, &fo, &rd),
                     DYN_OK);
    free(work);
    assert_int_equal(a.n, 201);
    assert_int_equal(a.n, b.n);
    assert_memory_equal(a.y0, b.y0, (size_t)a.n * sizeof a.y0[0]);
    assert_memory_equal(y, yd, sizeof y);
    assert_int_equal(res.stats.rhs_calls, rd.stats.rhs_calls);
}

static int on_turn(int index, double t, const double *y, int direction, void *ctx)
{
    (void)index;
    (void)y;
    (void)direction;
    double *first = ctx;
    if (isnan(*first))
        *first = t;
    return 0;
}

/* the complete elliptic integral of the first kind, K(k) = pi / (2 agm(1, sqrt(1 - k^2))) */
static double ellip_k(double k)
{
    double a = 1.0, g = sqrt(1.0 - k * k);
    for (int i = 0; i < 40; i++) {
        const double an = 0.5 * (a + g);
        g = sqrt(a * g);
        a = an;
    }
    return DYN_PI / (2.0 * a);
}

static void test_adaptive_is_dyn_solve_and_finds_the_turn(void **state)
{
    (void)state;
    const dyn_model *m = &dyn_model_pendulum;
    dyn_pendulum_par p;
    pendulum_par(&p);
    const double y0[2] = {1.0, 0.0}; /* released at rest from 1 rad: the first turn is the
                                      * other side, half a period later */
    static samples a, b;
    memset(&a, 0, sizeof a);
    memset(&b, 0, sizeof b);
    dyn_run_opts o = {.method = dyn_run_method_find("dp45"), .t0 = 0, .t1 = 3, .step = 0.01,
                      .rtol = 1e-10, .atol = 1e-12};
    o.output = keep;
    o.output_ctx = &a;
    double y[2], yd[2];
    dyn_result res, rd;
    assert_int_equal(dyn_run(m, &p, y0, &o, y, &res), DYN_OK);
    const dyn_system sys = {m->rhs, 2, &p};
    dyn_solve_opts so = {.rtol = 1e-10, .atol = 1e-12, .out_step = 0.01};
    so.output = keep;
    so.output_ctx = &b;
    double *work = malloc(dyn_solve_work_size(o.method, 2, &so) * sizeof *work);
    assert_int_equal(dyn_solve(o.method, &sys, 0, 3, y0, yd, work, &so, &rd), DYN_OK);
    free(work);
    assert_int_equal(a.n, b.n);
    assert_memory_equal(a.y0, b.y0, (size_t)a.n * sizeof a.y0[0]);
    assert_int_equal(res.stats.rhs_calls, rd.stats.rhs_calls);

    /* the turn, a model event asked for by name */
    const int turn = 0;
    assert_string_equal(m->events[turn].name, "turn");
    dyn_event ev = m->events[turn];
    double first = NAN;
    o.output = NULL;
    o.t1 = 5.0;
    o.events = &ev;
    o.n_events = 1;
    o.on_event = on_turn;
    o.event_ctx = &first;
    assert_int_equal(dyn_run(m, &p, y0, &o, y, &res), DYN_OK);
    const double w = sqrt(p.g / p.l), half = 2.0 * ellip_k(sin(0.5)) / w;
    assert_true(fabs(first - half) < 1e-8);
}

/* x' = -x with a reset x -> 1 when x falls through 0.5 */
static int decay(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    (void)par;
    dydt[0] = -y[0];
    return 0;
}
static double below_half(double t, const double *y, void *par)
{
    (void)t;
    (void)par;
    return y[0] - 0.5;
}
static int back_to_one(double t, double *y, void *par)
{
    (void)t;
    (void)par;
    y[0] = 1.0;
    return 0;
}
static const dyn_var decay_states[] = {{"x", "1", "decaying quantity"}};
static const double decay_y0[] = {1.0};

static dyn_model decay_model(const dyn_event *ev, int n_events)
{
    dyn_model m = {.name = "bounce", .n_states = 1, .states = decay_states, .y0 = decay_y0,
                   .rhs = decay, .t0 = 0, .t1 = 2, .step = 0.1};
    m.events = ev;
    m.n_events = n_events;
    return m;
}

static void test_resets_run_unasked_on_the_grid(void **state)
{
    (void)state;
    const dyn_event ev = {.name = "refill", .g = below_half, .direction = -1,
                          .reset = back_to_one};
    const dyn_model m = decay_model(&ev, 1);
    static samples s;
    memset(&s, 0, sizeof s);
    dyn_run_opts o = {.method = dyn_run_method_find("dp45"), .t0 = 0, .t1 = 2, .step = 0.1,
                      .rtol = 1e-12, .atol = 1e-14, .output = keep, .output_ctx = &s};
    double y[1];
    dyn_result res;
    assert_int_equal(dyn_run(&m, NULL, decay_y0, &o, y, &res), DYN_OK);
    /* the reset comes at ln 2 and again 2 ln 2 later: x(2) = exp(-(2 - 2 ln 2)) */
    assert_true(fabs(y[0] - exp(-(2.0 - 2.0 * log(2.0)))) < 1e-9);
    assert_int_equal(s.n, 21);
    for (long k = 0; k < s.n; k++)
        assert_true(fabs(s.t[k] - 0.1 * (double)k) < 1e-12);
    /* a fixed-step method runs the reset too, on the grid of its step */
    memset(&s, 0, sizeof s);
    o.method = dyn_run_method_find("rk4");
    o.step = 0.001;
    assert_int_equal(dyn_run(&m, NULL, decay_y0, &o, y, &res), DYN_OK);
    assert_int_equal(s.n, 2001);
    assert_true(fabs(y[0] - exp(-(2.0 - 2.0 * log(2.0)))) < 1e-6);
}

static void test_output_rules(void **state)
{
    (void)state;
    dyn_model m = decay_model(NULL, 0);
    m.t_trans = 1.0;
    static samples s;
    memset(&s, 0, sizeof s);
    dyn_run_opts o = {.method = dyn_run_method_find("rk4"), .t0 = 0, .t1 = 2, .step = 0.1,
                      .output = keep, .output_ctx = &s};
    double y[1];
    dyn_result res;
    assert_int_equal(dyn_run(&m, NULL, decay_y0, &o, y, &res), DYN_OK);
    assert_int_equal(s.n, 11); /* t = 1.0, 1.1, ..., 2.0 */
    assert_true(s.t[0] >= 1.0 - 1e-12);
    /* a start beyond the bound stops the run at its first sample */
    m.t_trans = 0.0;
    m.bound = 0.5;
    const double start[1] = {0.6};
    memset(&s, 0, sizeof s);
    dyn_run(&m, NULL, start, &o, y, &res);
    assert_int_equal(res.status, DYN_STOPPED);
    assert_non_null(strstr(res.message, "state x = 0.6 exceeds the model's bound 0.5"));
    assert_int_equal(res.fail_index, 0);
}

static void test_methods_and_refusals(void **state)
{
    (void)state;
    assert_ptr_equal(dyn_run_method_find("ode45"), dyn_method_find("dp45"));
    assert_ptr_equal(dyn_run_method_find("rkmil"), dyn_run_method_rkmil());
    assert_ptr_equal(dyn_run_method_find("sriw1"), dyn_run_method_sriw1());
    assert_ptr_equal(dyn_run_method_find("volterra"), dyn_run_method_volterra());
    assert_ptr_equal(dyn_run_method_find("cvode"), dyn_run_method_cvode());
    assert_null(dyn_run_method_find("ode113"));
    assert_int_equal(dyn_run_sde_method(dyn_run_method_find("euler")), DYN_SDE_EM);
    assert_int_equal(dyn_run_sde_method(dyn_run_method_rkmil()), DYN_SDE_RKMIL);
    const dyn_model m = decay_model(NULL, 0);
    dyn_run_opts o = {.method = dyn_run_method_cvode(), .t0 = 0, .t1 = 1, .step = 0.1};
    double y[1];
    dyn_result res;
    assert_int_equal(dyn_run(&m, NULL, decay_y0, &o, y, &res), DYN_ERR_ARG);
    assert_string_equal(res.message, "dynkit was built without SUNDIALS");
    o.method = NULL;
    assert_int_equal(dyn_run(&m, NULL, decay_y0, &o, y, &res), DYN_ERR_ARG);
    assert_non_null(strstr(res.message, "with a method"));
    /* the defaults of a model that names no tolerances */
    assert_true(dyn_run_default_rtol(&m) == DYN_MODEL_RTOL);
    assert_true(dyn_run_default_atol(&m) == DYN_MODEL_ATOL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fixed_step_is_the_homework_loop),
        cmocka_unit_test(test_adaptive_is_dyn_solve_and_finds_the_turn),
        cmocka_unit_test(test_resets_run_unasked_on_the_grid),
        cmocka_unit_test(test_output_rules),
        cmocka_unit_test(test_methods_and_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
