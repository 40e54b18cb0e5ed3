/* SPDX-License-Identifier: BSD-3-Clause */
/* The solve_ivp-like calls (dyn_ivp_solve, dyn_ivp_solve_model, dyn_ivp_eval,
 * dyn_ivp_free) against exact solutions:
 * - exponential decay at every accepted step (the default sampling), defaults with NULL
 *   options, fixed-step methods at every step;
 * - the harmonic oscillator at t_eval (the times exactly as given) and by dense output;
 * - events: the pendulum's first turn at the quarter period K(k)/w (docs/solvers.md), a
 *   terminal event ending the solution there, a model's resets taking part on their own;
 * - failures: a right-hand side that fails keeps the solution up to there, bad arguments
 *   give DYN_ERR_ARG with a message and no samples.
 * Run under AddressSanitizer (DYNKIT_SANITIZE) for the allocations. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "dynkit/dynkit.h"
#include "test_util.h"

static int decay(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    const double *k = par;
    dydt[0] = -k[0] * y[0];
    return 0;
}

static void test_decay_every_step(void **state)
{
    (void)state;
    double k = 0.7;
    const double y0[1] = {2.0};
    dyn_ivp_opts o = {.rtol = 1e-10, .atol = 1e-12};
    dyn_ivp_solution *sol = dyn_ivp_solve(decay, 1, &k, 0.0, 5.0, y0, &o);
    assert_non_null(sol);
    assert_int_equal(sol->status, DYN_OK);
    assert_string_equal(sol->message, "");
    assert_int_equal(sol->n, 1);
    assert_true(sol->n_t > 10);
    assert_int_equal(sol->n_t, sol->stats.accepted + 1); /* t0, then every accepted step */
    assert_int_equal(sol->stats.samples, sol->n_t);
    assert_true(sol->t[0] == 0.0 && sol->y[0] == 2.0);
    assert_true(sol->t[sol->n_t - 1] == 5.0);
    for (long i = 0; i < sol->n_t; i++) {
        if (i > 0)
            assert_true(sol->t[i] > sol->t[i - 1]);
        const double exact = 2.0 * exp(-0.7 * sol->t[i]);
        assert_true(fabs(sol->y[i] - exact) < 1e-9 * exact + 1e-11);
    }
    assert_int_equal(sol->n_events, 0);
    assert_null(sol->t_events);
    assert_int_equal(sol->dense.count, 0);
    double y[1];
    assert_int_equal(dyn_ivp_eval(sol, 1.0, y), DYN_ERR_ARG); /* no dense output kept */
    dyn_ivp_free(sol);

    /* NULL options: dp45 at 1e-3 / 1e-6 */
    sol = dyn_ivp_solve(decay, 1, &k, 0.0, 5.0, y0, NULL);
    assert_non_null(sol);
    assert_int_equal(sol->status, DYN_OK);
    assert_true(fabs(sol->y[sol->n_t - 1] - 2.0 * exp(-3.5)) < 1e-4);
    assert_true(sol->n_t < 30);
    dyn_ivp_free(sol);

    /* a fixed-step method: every step, the fixed-step driver's numbers */
    dyn_ivp_opts f = {.method = "rk4", .h = 0.1};
    sol = dyn_ivp_solve(decay, 1, &k, 0.0, 5.0, y0, &f);
    assert_non_null(sol);
    assert_int_equal(sol->status, DYN_OK);
    assert_int_equal(sol->n_t, 51);
    double yf[1], work[TEST_WORK];
    dyn_system sys = {decay, 1, &k};
    dyn_result res;
    assert_int_equal(dyn_fixed_solve(dyn_method_find("rk4"), &sys, 0.0, 5.0, 0.1, y0, yf, work,
                                     NULL, &res),
                     DYN_OK);
    assert_true(same_bits(sol->y[50], yf[0]));
    assert_true(same_bits(sol->t[50], 5.0));
    dyn_ivp_free(sol);
}

static int oscillator(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    const double *w = par;
    dydt[0] = y[1];
    dydt[1] = -w[0] * w[0] * y[0];
    return 0;
}

static void test_oscillator_at_t_eval_and_dense(void **state)
{
    (void)state;
    double w = 2.0;
    const double y0[2] = {1.0, 0.0};
    double te[101];
    for (int i = 0; i <= 100; i++)
        te[i] = 0.1 * i;
    static const char *methods[] = {"dp45", "dop853", "rodas4"};
    for (int r = 0; r < 3; r++) {
        dyn_ivp_opts o = {.method = methods[r], .rtol = 1e-10, .atol = 1e-12, .t_eval = te,
                          .n_eval = 101, .dense_output = 1};
        dyn_ivp_solution *sol = dyn_ivp_solve(oscillator, 2, &w, 0.0, 10.0, y0, &o);
        assert_non_null(sol);
        assert_int_equal(sol->status, DYN_OK);
        assert_int_equal(sol->n_t, 101);
        for (int i = 0; i <= 100; i++) {
            assert_true(same_bits(sol->t[i], te[i]));
            const double x = cos(w * te[i]), v = -w * sin(w * te[i]);
            if (fabs(sol->y[2 * i] - x) > 1e-7 || fabs(sol->y[2 * i + 1] - v) > 1e-7)
                fail_msg("%s at t = %g: (%.17g, %.17g), exact (%.17g, %.17g)", methods[r],
                         te[i], sol->y[2 * i], sol->y[2 * i + 1], x, v);
        }
        /* the dense output anywhere in the span, one block per accepted step */
        assert_int_equal(sol->dense.count, sol->stats.accepted);
        for (double t = 0.0; t <= 10.0; t += 0.0371) {
            double y[2];
            assert_int_equal(dyn_ivp_eval(sol, t, y), 0);
            assert_true(fabs(y[0] - cos(w * t)) < 1e-7);
        }
        double y[2];
        assert_int_equal(dyn_ivp_eval(sol, 10.5, y), DYN_ERR_ARG);
        dyn_ivp_free(sol);
    }
}

/* K(k) by the arithmetic-geometric mean: pi / (2 AGM(1, sqrt(1 - k^2))). */
static double ellip_k(double k)
{
    double a = 1.0, b = sqrt(1.0 - k * k);
    for (int i = 0; i < 60 && fabs(a - b) > 1e-17 * a; i++) {
        const double an = 0.5 * (a + b);
        b = sqrt(a * b);
        a = an;
    }
    return DYN_PI / (a + b);
}

static void test_pendulum_turn_at_quarter_period(void **state)
{
    (void)state;
    const dyn_model *m = &dyn_model_pendulum;
    dyn_pendulum_par par;
    char err[128];
    assert_int_equal(dyn_model_default_params(m, &par, err, sizeof err), 0);
    const double w = sqrt(par.g / par.l), k = sin(0.5 * 1.0); /* amplitude 1 rad */
    const double y0[2] = {0.0, 2.0 * k * w}, T4 = ellip_k(k) / w;
    /* the model's events (turn, bottom), non-terminal: turn, bottom, turn, ... */
    const double tspan[2] = {0.0, 4.5 * T4};
    dyn_ivp_opts o = {.method = "dp45", .rtol = 1e-12, .atol = 1e-12};
    dyn_ivp_solution *sol = dyn_ivp_solve_model(m, &par, y0, tspan, &o);
    assert_non_null(sol);
    assert_int_equal(sol->status, DYN_OK);
    assert_int_equal(sol->n_events, 4);
    for (int i = 0; i < 4; i++) {
        assert_int_equal(sol->event_index[i], i % 2); /* turn, bottom, turn, bottom */
        if (fabs(sol->t_events[i] - (i + 1) * T4) > 1e-9)
            fail_msg("event %d at %.17g, expected %.17g", i, sol->t_events[i], (i + 1) * T4);
        const double g = m->events[sol->event_index[i]].g(sol->t_events[i],
                                                          sol->y_events + 2 * i, &par);
        assert_true(fabs(g) < 1e-9);
    }
    assert_true(fabs(sol->t_events[0] - T4) < 1e-10);
    assert_int_equal(sol->event_direction[0], -1);
    assert_false(sol->terminated);
    dyn_ivp_free(sol);

    /* the turn alone, terminal: the solution ends there */
    dyn_event turn = m->events[0];
    turn.terminal = 1;
    dyn_ivp_opts t = {.rtol = 1e-12, .atol = 1e-12, .events = &turn, .n_events = 1};
    sol = dyn_ivp_solve(m->rhs, 2, &par, 0.0, 10.0, y0, &t);
    assert_non_null(sol);
    assert_int_equal(sol->status, DYN_OK);
    assert_true(sol->terminated);
    assert_int_equal(sol->n_events, 1);
    assert_true(fabs(sol->t_events[0] - T4) < 1e-10);
    assert_true(same_bits(sol->t[sol->n_t - 1], sol->t_events[0]));
    assert_true(same_bits(sol->result.t, sol->t_events[0]));
    dyn_ivp_free(sol);
}

/* A model of its own with an event that resets the state: it takes part without being
 * asked for, also beside other events. */
typedef struct ball_par {
    double g, e;
} ball_par;

static int ball_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    const ball_par *b = par;
    dydt[0] = y[1];
    dydt[1] = -b->g;
    return 0;
}

static double ball_floor(double t, const double *y, void *par)
{
    (void)t;
    (void)par;
    return y[0];
}

static int ball_bounce(double t, double *y, void *par)
{
    (void)t;
    const ball_par *b = par;
    y[1] = -b->e * y[1];
    return 0;
}

static double at_three(double t, const double *y, void *par)
{
    (void)y;
    (void)par;
    return t - 3.0;
}

static const dyn_var ball_states[] = {{"y", "m", "height"}, {"v", "m/s", "velocity"}};
static const double ball_y0[] = {10.0, 0.0};
static const dyn_param ball_params[] = {
    {"g", "m/s^2", "gravity", offsetof(ball_par, g), 9.81},
    {"e", "1", "restitution", offsetof(ball_par, e), 0.8}};
static const dyn_event ball_events[] = {
    {.name = "bounce", .description = "the floor", .g = ball_floor, .direction = -1,
     .reset = ball_bounce}};
static const dyn_model ball_model = {
    .name = "ball", .title = "a bouncing ball", .description = "y'' = -g, bounces at y = 0",
    .n_states = 2, .states = ball_states, .y0 = ball_y0, .n_params = 2,
    .params = ball_params, .par_size = sizeof(ball_par), .rhs = ball_rhs, .t0 = 0.0,
    .t1 = 5.0, .step = 0.01, .method = "dp45", .rtol = 1e-12, .atol = 1e-12, .n_events = 1,
    .events = ball_events};

static void test_model_defaults_and_resets(void **state)
{
    (void)state;
    const double t1 = sqrt(2.0 * 10.0 / 9.81), t2 = t1 * (1.0 + 2.0 * 0.8);
    /* everything from the model: parameters, initial state, span, method, tolerances */
    dyn_ivp_solution *sol = dyn_ivp_solve_model(&ball_model, NULL, NULL, NULL, NULL);
    assert_non_null(sol);
    assert_int_equal(sol->status, DYN_OK);
    assert_true(sol->t[0] == 0.0 && sol->y[0] == 10.0);
    assert_true(sol->t[sol->n_t - 1] == 5.0);
    assert_int_equal(sol->n_events, 2); /* 1.43 and 3.71 s (the next at 5.54 s) */
    assert_true(fabs(sol->t_events[0] - t1) < 1e-10);
    assert_true(fabs(sol->t_events[1] - t2) < 1e-10);
    for (long i = 0; i < sol->n_t; i++)
        assert_true(sol->y[2 * i] > -1e-9); /* never below the floor */
    dyn_ivp_free(sol);

    /* an event of the caller's, terminal at 3 s: the bounce still happens (index 1) */
    dyn_event three = {.name = "three", .g = at_three, .direction = 1, .terminal = 1};
    dyn_ivp_opts o = {.events = &three, .n_events = 1};
    sol = dyn_ivp_solve_model(&ball_model, NULL, NULL, NULL, &o);
    assert_non_null(sol);
    assert_int_equal(sol->status, DYN_OK);
    assert_true(sol->terminated);
    assert_int_equal(sol->n_events, 2);
    assert_int_equal(sol->event_index[0], 1);
    assert_int_equal(sol->event_index[1], 0);
    assert_true(fabs(sol->t_events[1] - 3.0) < 1e-12);
    assert_true(sol->y_events[2] > 1.0); /* at 3 s the ball is in the air after the bounce */
    dyn_ivp_free(sol);

    /* rk4 with the model's step */
    dyn_ivp_opts f = {.method = "rk4"};
    const double span[2] = {0.0, 2.0};
    sol = dyn_ivp_solve_model(&ball_model, NULL, NULL, span, &f);
    assert_non_null(sol);
    assert_int_equal(sol->status, DYN_OK);
    assert_int_equal(sol->n_events, 1);
    assert_int_equal(sol->n_t, 201 + 1); /* the grid and the state after the bounce */
    dyn_ivp_free(sol);
}

/* f fails after t = 2: the solution up to there is kept */
static int fails_late(double t, const double *y, double *dydt, void *par)
{
    (void)par;
    if (t > 2.0)
        return 42;
    dydt[0] = -y[0];
    return 0;
}

static void test_failures_keep_partial_solution(void **state)
{
    (void)state;
    const double y0[1] = {1.0};
    dyn_ivp_opts o = {.rtol = 1e-8, .atol = 1e-10};
    dyn_ivp_solution *sol = dyn_ivp_solve(fails_late, 1, NULL, 0.0, 5.0, y0, &o);
    assert_non_null(sol);
    assert_int_equal(sol->status, DYN_ERR_RHS);
    assert_int_equal(sol->result.rhs_status, 42);
    assert_non_null(strstr(sol->message, "right-hand side failed"));
    assert_true(sol->n_t > 5);
    assert_true(sol->t[sol->n_t - 1] <= 2.0 && sol->t[sol->n_t - 1] > 1.0);
    for (long i = 0; i < sol->n_t; i++)
        assert_true(fabs(sol->y[i] - exp(-sol->t[i])) < 1e-7);
    dyn_ivp_free(sol);

    /* t_eval: the samples before the failure */
    double te[11];
    for (int i = 0; i <= 10; i++)
        te[i] = 0.5 * i;
    dyn_ivp_opts e = {.rtol = 1e-8, .atol = 1e-10, .t_eval = te, .n_eval = 11};
    sol = dyn_ivp_solve(fails_late, 1, NULL, 0.0, 5.0, y0, &e);
    assert_non_null(sol);
    assert_int_equal(sol->status, DYN_ERR_RHS);
    assert_true(sol->n_t >= 4 && sol->n_t <= 5); /* 0, 0.5, 1, 1.5 (and 2) */
    assert_true(fabs(sol->y[3] - exp(-1.5)) < 1e-7);
    dyn_ivp_free(sol);

    /* bad arguments: a status and a message, no samples */
    dyn_ivp_opts bad = {.method = "rk5"};
    sol = dyn_ivp_solve(fails_late, 1, NULL, 0.0, 5.0, y0, &bad);
    assert_non_null(sol);
    assert_int_equal(sol->status, DYN_ERR_ARG);
    assert_non_null(strstr(sol->message, "unknown method 'rk5'"));
    assert_non_null(strstr(sol->message, "dp45"));
    assert_int_equal(sol->n_t, 0);
    assert_null(sol->t);
    dyn_ivp_free(sol);
    dyn_ivp_opts nostep = {.method = "rk4"};
    sol = dyn_ivp_solve(fails_late, 1, NULL, 0.0, 5.0, y0, &nostep);
    assert_int_equal(sol->status, DYN_ERR_ARG);
    assert_non_null(strstr(sol->message, "opts.h"));
    dyn_ivp_free(sol);
    sol = dyn_ivp_solve(fails_late, 1, NULL, 5.0, 0.0, y0, NULL); /* backwards */
    assert_int_equal(sol->status, DYN_ERR_ARG);
    assert_non_null(strstr(sol->message, "time span"));
    assert_int_equal(sol->n_t, 0);
    dyn_ivp_free(sol);
    const double outside[2] = {1.0, 7.0};
    dyn_ivp_opts out = {.t_eval = outside, .n_eval = 2};
    sol = dyn_ivp_solve(fails_late, 1, NULL, 0.0, 5.0, y0, &out);
    assert_int_equal(sol->status, DYN_ERR_ARG);
    assert_int_equal(sol->n_t, 0);
    dyn_ivp_free(sol);
    dyn_ivp_free(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_decay_every_step),
        cmocka_unit_test(test_oscillator_at_t_eval_and_dense),
        cmocka_unit_test(test_pendulum_turn_at_quarter_period),
        cmocka_unit_test(test_model_defaults_and_resets),
        cmocka_unit_test(test_failures_keep_partial_solution),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
