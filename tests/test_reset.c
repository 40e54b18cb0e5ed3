/* SPDX-License-Identifier: BSD-3-Clause */
/* Events that reset the state (dyn_event.reset, XPPAUT's `global`), against a closed form:
 * a ball dropped from h0 under gravity, y'' = -g, bouncing at y = 0 (falling) with the
 * velocity reversed and scaled by the restitution e. It lands at t_1 = sqrt(2 h0 / g) with
 * speed g t_1, then flies 2 t_1 e^k between bounces k and k + 1, so the bounces come at
 * t_{k+1} = t_k + 2 t_1 e^k and accumulate at t_1 (1 + e) / (1 - e) (Zeno).
 * - bounce times and the states before and after each bounce to ~1e-10 with dp45, dop853
 *   and rodas4 at tight tolerances, and with rk4 fixed steps (exact for this polynomial
 *   solution: to rounding), output on a grid (samples stay on t0 + k*h, from the new
 *   trajectory after each bounce) or at every step (the state after the reset at the event);
 * - an event in both directions gives the same bounces (the ball leaving the floor is no
 *   event); a reset that leaves its event's value unchanged (a counter) fires once; a
 *   crossing later in the step of a reset, on the old trajectory, is dropped;
 * - e = 0.5 over a span past the accumulation time stops with DYN_ERR_ZENO near it;
 * - a reset returning non-zero stops with DYN_ERR_RHS, the state at the event kept;
 * - terminal events still end the solve, also with resets in the same run;
 * - cascades: a reset that carries another event's g across zero fires it at the same
 *   instant, each event once (XPPAUT's globals), a DYN_EVENT_JUMPS event only by resets
 *   and onto zero, a cascade that re-arms itself ever sooner stops with DYN_ERR_ZENO;
 * - the command line: a model file's reset takes part in every run without --event, rows
 *   stay on the --step grid for rk4, --event reports the bounces, cvode refuses the model. */
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

typedef struct ball {
    double g, e;
    int reset_status; /* returned by the reset */
    int resets;       /* calls of the reset */
} ball;

static int ball_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    const ball *b = par;
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
    ball *b = par;
    b->resets++;
    y[1] = -b->e * y[1];
    return b->reset_status;
}

#define H0 10.0
#define G 9.81

/* The closed form: bounce k (k = 0, 1, ...) time, and the state at any t before the
 * accumulation time. */
static double bounce_time(int k, double e)
{
    const double t1 = sqrt(2.0 * H0 / G);
    double t = t1;
    for (int i = 1; i <= k; i++)
        t += 2.0 * t1 * pow(e, i);
    return t;
}

static void ball_exact(double t, double e, double y[2])
{
    const double t1 = sqrt(2.0 * H0 / G), v1 = G * t1;
    if (t < t1) {
        y[0] = H0 - 0.5 * G * t * t;
        y[1] = -G * t;
        return;
    }
    double tk = t1, u = e * v1; /* after bounce k: leaves at tk with speed u */
    while (t >= tk + 2.0 * u / G) {
        tk += 2.0 * u / G;
        u *= e;
    }
    const double s = t - tk;
    y[0] = u * s - 0.5 * G * s * s;
    y[1] = u - G * s;
}

#define MAX_EV 256
typedef struct ev_log {
    int count;
    int index[MAX_EV], dir[MAX_EV];
    double t[MAX_EV], y[MAX_EV][2];
    int stop_at; /* make the event with this count terminal, or -1 */
} ev_log;

static int log_event(int index, double t, const double *y, int direction, void *ctx)
{
    ev_log *l = ctx;
    if (l->count < MAX_EV) {
        l->index[l->count] = index;
        l->dir[l->count] = direction;
        l->t[l->count] = t;
        l->y[l->count][0] = y[0];
        l->y[l->count][1] = y[1];
    }
    return l->count++ == l->stop_at;
}

static sample_log samples; /* large: static */

typedef struct run_opts {
    double tol, h, out_step, t1;
    const dyn_event *events;
    int n_events;
} run_opts;

static int run_ball(const char *method, ball *b, const run_opts *ro, ev_log *log, double y[2],
                    dyn_result *res)
{
    const dyn_tableau *m = dyn_method_find(method);
    assert_non_null(m);
    dyn_system sys = {ball_rhs, 2, b};
    dyn_solve_opts o = {0};
    o.rtol = ro->tol;
    o.atol = ro->tol;
    o.h = ro->h;
    o.out_step = ro->out_step;
    o.events = ro->events;
    o.n_events = ro->n_events;
    o.on_event = log_event;
    o.event_ctx = log;
    o.output = sample_log_output;
    o.output_ctx = &samples;
    int iwork[4];
    o.iwork = iwork;
    sample_log_init(&samples, 2);
    log->count = 0;
    double *work = malloc(dyn_solve_work_size(m, 2, &o) * sizeof *work);
    assert_non_null(work);
    const double y0[2] = {H0, 0.0};
    int rc = dyn_solve(m, &sys, 0.0, ro->t1, y0, y, work, &o, res);
    free(work);
    return rc;
}

static const dyn_event floor_event = {.name = "bounce",
                                      .g = ball_floor,
                                      .direction = -1,
                                      .reset = ball_bounce};

/* Bounce times and the states at them against the closed form. */
static void check_bounces(const ev_log *log, double e, int expect_min, double bound)
{
    const double v1 = G * sqrt(2.0 * H0 / G);
    assert_true(log->count >= expect_min);
    for (int k = 0; k < log->count && k < MAX_EV; k++) {
        const double tk = bounce_time(k, e);
        if (fabs(log->t[k] - tk) > bound)
            fail_msg("bounce %d at %.17g, closed form %.17g (error %.3g)", k, log->t[k], tk,
                     log->t[k] - tk);
        assert_int_equal(log->dir[k], -1);
        /* the state handed to on_event is the one before the reset: on the floor, falling
         * with the speed the ball left the last bounce with */
        assert_true(fabs(log->y[k][0]) < bound * v1);
        assert_true(fabs(log->y[k][1] + v1 * pow(e, k)) < 10.0 * bound * v1);
    }
}

static void test_bounce_times_adaptive(void **state)
{
    (void)state;
    static const struct {
        const char *method;
        double tol, bound;
    } runs[] = {{"dp45", 1e-12, 1e-10}, {"dop853", 1e-12, 1e-10}, {"rodas4", 1e-12, 1e-9},
                {"bs23", 1e-10, 1e-8}};
    const double e = 0.8; /* accumulation at 12.9 s, after the span */
    for (size_t r = 0; r < sizeof runs / sizeof runs[0]; r++) {
        ball b = {G, e, 0, 0};
        ev_log log = {.stop_at = -1};
        run_opts ro = {.tol = runs[r].tol, .t1 = 10.0, .events = &floor_event, .n_events = 1};
        double y[2];
        dyn_result res;
        int rc = run_ball(runs[r].method, &b, &ro, &log, y, &res);
        if (rc != DYN_OK)
            fail_msg("%s: %s", runs[r].method, res.message);
        /* bounces before t = 10: t_1 = 1.43, then flights of 2.29, 1.83, 1.46, ... */
        int expect = 0;
        while (bounce_time(expect, e) < 10.0)
            expect++;
        assert_int_equal(log.count, expect);
        assert_int_equal(b.resets, expect);
        assert_int_equal(res.events, expect);
        check_bounces(&log, e, expect, runs[r].bound);
        /* every step's end, and the state after each reset at the bounce's time */
        int seen = 0;
        for (long i = 1; i < samples.count; i++) {
            assert_true(samples.t[i] >= samples.t[i - 1]);
            if (seen < log.count && samples.t[i] == log.t[seen]) {
                const double v1 = G * sqrt(2.0 * H0 / G);
                assert_true(fabs(samples.y[i][1] - v1 * pow(e, seen + 1)) <
                            10.0 * runs[r].bound * v1);
                assert_true(samples.y[i][1] > 0.0);
                seen++;
            }
        }
        assert_int_equal(seen, log.count);
        double ye[2];
        ball_exact(10.0, e, ye);
        assert_true(fabs(y[0] - ye[0]) < 1e3 * runs[r].bound);
        assert_true(fabs(y[1] - ye[1]) < 1e3 * runs[r].bound);
        assert_true(res.t == 10.0);
    }
}

/* rk4 is exact for this solution (a parabola), and the cubic Hermite interpolant of its
 * steps too: the bounces are located to rounding, and the samples stay on t0 + k*h. */
static void test_bounce_times_fixed_step(void **state)
{
    (void)state;
    const double e = 0.8, h = 0.01;
    ball b = {G, e, 0, 0};
    ev_log log = {.stop_at = -1};
    run_opts ro = {.h = h, .t1 = 10.0, .events = &floor_event, .n_events = 1};
    double y[2];
    dyn_result res;
    assert_int_equal(run_ball("rk4", &b, &ro, &log, y, &res), DYN_OK);
    int expect = 0;
    while (bounce_time(expect, e) < 10.0)
        expect++;
    assert_int_equal(log.count, expect);
    check_bounces(&log, e, expect, 1e-10);
    /* samples: the grid 0, h, 2h, ... 10 (1001 of them), plus the state after each reset at
     * its bounce */
    assert_int_equal(samples.count, 1001 + log.count);
    long k = 0;
    int bounces = 0;
    for (long i = 0; i < samples.count; i++) {
        if (bounces < log.count && samples.t[i] == log.t[bounces]) {
            assert_true(samples.y[i][1] > 0.0); /* after the reset: going up */
            bounces++;
            continue;
        }
        assert_true(same_bits(samples.t[i], k == 1000 ? 10.0 : 0.0 + (double)k * h));
        double ye[2];
        ball_exact(samples.t[i], e, ye);
        if (fabs(samples.y[i][0] - ye[0]) > 1e-9 || fabs(samples.y[i][1] - ye[1]) > 1e-9)
            fail_msg("sample at t = %.17g: (%.17g, %.17g), exact (%.17g, %.17g)",
                     samples.t[i], samples.y[i][0], samples.y[i][1], ye[0], ye[1]);
        k++;
    }
    assert_int_equal(k, 1001);
    assert_int_equal(bounces, log.count);
    assert_true(res.t == 10.0);
}

/* An adaptive run with its samples on a grid: every sample at t0 + k*h, and after each
 * bounce from the new trajectory. */
static void test_grid_after_resets(void **state)
{
    (void)state;
    const double e = 0.8;
    ball b = {G, e, 0, 0};
    ev_log log = {.stop_at = -1};
    run_opts ro = {.tol = 1e-12, .out_step = 0.05, .t1 = 10.0, .events = &floor_event,
                   .n_events = 1};
    double y[2];
    dyn_result res;
    assert_int_equal(run_ball("dp45", &b, &ro, &log, y, &res), DYN_OK);
    assert_int_equal(samples.count, 201);
    for (long i = 0; i < samples.count; i++) {
        assert_true(same_bits(samples.t[i], i == 200 ? 10.0 : (double)i * 0.05));
        double ye[2];
        ball_exact(samples.t[i], e, ye);
        if (fabs(samples.y[i][0] - ye[0]) > 1e-9 || fabs(samples.y[i][1] - ye[1]) > 1e-9)
            fail_msg("sample at t = %.17g: (%.17g, %.17g), exact (%.17g, %.17g)",
                     samples.t[i], samples.y[i][0], samples.y[i][1], ye[0], ye[1]);
    }
}

/* The event in both directions: leaving the floor after a reset is not a crossing (the
 * restart is on the event's zero), so the same bounces come, all falling. */
static void test_both_directions_same_bounces(void **state)
{
    (void)state;
    const double e = 0.8;
    dyn_event both = floor_event;
    both.direction = 0;
    ball b = {G, e, 0, 0};
    ev_log log = {.stop_at = -1};
    run_opts ro = {.tol = 1e-12, .t1 = 10.0, .events = &both, .n_events = 1};
    double y[2];
    dyn_result res;
    assert_int_equal(run_ball("dp45", &b, &ro, &log, y, &res), DYN_OK);
    int expect = 0;
    while (bounce_time(expect, e) < 10.0)
        expect++;
    assert_int_equal(log.count, expect);
    check_bounces(&log, e, expect, 1e-10);
}

/* Zeno: with e = 0.5 the bounces accumulate at 3 t_1 = 4.28 s; a span to 10 s stops there
 * with DYN_ERR_ZENO and a message that says so, after the bounces that could be resolved. */
static void test_zeno_stops(void **state)
{
    (void)state;
    const double e = 0.5, t_inf = sqrt(2.0 * H0 / G) * (1.0 + e) / (1.0 - e);
    const char *methods[] = {"dp45", "dop853", "rk4"};
    for (size_t r = 0; r < sizeof methods / sizeof methods[0]; r++) {
        ball b = {G, e, 0, 0};
        ev_log log = {.stop_at = -1};
        run_opts ro = {.tol = 1e-12, .h = 0.01, .t1 = 10.0, .events = &floor_event,
                       .n_events = 1};
        double y[2];
        dyn_result res;
        assert_int_equal(run_ball(methods[r], &b, &ro, &log, y, &res), DYN_ERR_ZENO);
        assert_non_null(strstr(res.message, "Zeno"));
        assert_string_equal(dyn_status_name(DYN_ERR_ZENO), "resets accumulate (Zeno)");
        assert_true(fabs(res.t - t_inf) < 1e-8);
        assert_true(log.count > 20 && log.count < 100);
        check_bounces(&log, e, 20, 1e-11);
        assert_true(fabs(y[0]) < 1e-12); /* the state at the last event */
    }
}

/* A reset that fails stops the solve with DYN_ERR_RHS at the event; y is the state there,
 * before the reset. */
static void test_reset_failure(void **state)
{
    (void)state;
    ball b = {G, 0.8, 7, 0};
    ev_log log = {.stop_at = -1};
    run_opts ro = {.tol = 1e-12, .h = 0.01, .t1 = 10.0, .events = &floor_event, .n_events = 1};
    const char *methods[] = {"dp45", "rk4", "rodas4"};
    for (size_t r = 0; r < 3; r++) {
        double y[2];
        dyn_result res;
        b.resets = 0;
        assert_int_equal(run_ball(methods[r], &b, &ro, &log, y, &res), DYN_ERR_RHS);
        assert_int_equal(res.rhs_status, 7);
        assert_int_equal(b.resets, 1);
        assert_true(fabs(res.t - bounce_time(0, 0.8)) < 1e-10);
        assert_true(res.t == res.fail_t);
        assert_non_null(strstr(res.message, "reset of event 0 (bounce)"));
        assert_true(fabs(y[0]) < 1e-9 && y[1] < -10.0); /* falling: before the reset */
    }
}

/* Terminal events: one of their own beside the bounces, or the bounce made terminal by
 * on_event (then it ends the solve without a reset). */
static double at_five(double t, const double *y, void *par)
{
    (void)y;
    (void)par;
    return t - 5.0;
}

static void test_terminal_events_with_resets(void **state)
{
    (void)state;
    const double e = 0.8;
    dyn_event ev[2] = {floor_event, {.name = "five", .g = at_five, .direction = 1,
                                     .terminal = 1}};
    ball b = {G, e, 0, 0};
    ev_log log = {.stop_at = -1};
    run_opts ro = {.tol = 1e-12, .t1 = 10.0, .events = ev, .n_events = 2};
    double y[2], ye[2];
    dyn_result res;
    assert_int_equal(run_ball("dp45", &b, &ro, &log, y, &res), DYN_OK);
    assert_true(res.stopped_by_event);
    assert_int_equal(res.event_index, 1);
    assert_true(fabs(res.t - 5.0) < 1e-12);
    ball_exact(5.0, e, ye);
    assert_true(fabs(y[0] - ye[0]) < 1e-9 && fabs(y[1] - ye[1]) < 1e-9);
    assert_int_equal(log.count, 3); /* bounces at 1.43 and 3.71 s (the next at 5.54 s) */
    assert_int_equal(log.index[2], 1);
    assert_true(samples.t[samples.count - 1] == res.t);

    /* the third bounce made terminal by on_event: no reset, the state before it */
    ev_log stop = {.stop_at = 2};
    b.resets = 0;
    run_opts one = {.tol = 1e-12, .t1 = 10.0, .events = &floor_event, .n_events = 1};
    assert_int_equal(run_ball("dp45", &b, &one, &stop, y, &res), DYN_OK);
    assert_true(res.stopped_by_event);
    assert_int_equal(b.resets, 2);
    assert_true(fabs(res.t - bounce_time(2, e)) < 1e-10);
    assert_true(y[1] < 0.0);
}

/* Crossings later in the step of a reset belong to the old trajectory: with rk4 steps of
 * 1 s the ball's step [1, 2] passes the floor at 1.43 s and, on the old trajectory, 1 m below
 * it at 1.49 s; that second event is dropped, the bounce is kept. */
static double below_floor(double t, const double *y, void *par)
{
    (void)t;
    (void)par;
    return y[0] + 1.0;
}

static void test_old_trajectory_events_dropped(void **state)
{
    (void)state;
    dyn_event ev[2] = {floor_event, {.name = "below", .g = below_floor, .direction = -1}};
    static const struct {
        const char *method;
        double h;
    } runs[] = {{"rk4", 1.0}, {"dp45", 0.0}};
    for (int r = 0; r < 2; r++) {
        ball b = {G, 0.8, 0, 0};
        ev_log log = {.stop_at = -1};
        run_opts ro = {.h = runs[r].h, .tol = 1e-10, .t1 = 3.0, .events = ev, .n_events = 2};
        double y[2];
        dyn_result res;
        assert_int_equal(run_ball(runs[r].method, &b, &ro, &log, y, &res), DYN_OK);
        assert_int_equal(log.count, 1); /* the bounce at 1.43 s only */
        assert_int_equal(log.index[0], 0);
        assert_true(fabs(log.t[0] - bounce_time(0, 0.8)) < 1e-9);
        double ye[2];
        ball_exact(3.0, 0.8, ye);
        assert_true(fabs(y[0] - ye[0]) < 1e-8 && fabs(y[1] - ye[1]) < 1e-8);
    }
}

/* A reset that does not touch its event's value (a counter raised at each crossing): the
 * restart is on the event's zero, so it fires once per crossing, not again and again. */
typedef struct counter {
    int resets;
} counter;

static int line_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    (void)y;
    (void)par;
    dydt[0] = 1.0;
    dydt[1] = 0.0;
    return 0;
}

static double sine_of_x(double t, const double *y, void *par)
{
    (void)t;
    (void)par;
    return sin(DYN_PI * y[0]);
}

static int count_up(double t, double *y, void *par)
{
    (void)t;
    counter *c = par;
    c->resets++;
    y[1] += 1.0;
    return 0;
}

static void test_counter_reset_fires_once_per_crossing(void **state)
{
    (void)state;
    const char *methods[] = {"dp45", "rk4", "rodas4"};
    for (size_t r = 0; r < 3; r++) {
        counter c = {0};
        dyn_system sys = {line_rhs, 2, &c};
        dyn_event ev = {.name = "integer", .g = sine_of_x, .reset = count_up};
        const dyn_tableau *m = dyn_method_find(methods[r]);
        dyn_solve_opts o = {0};
        o.rtol = o.atol = 1e-10;
        o.h = 0.1;
        o.events = &ev;
        o.n_events = 1;
        int iwork[4];
        o.iwork = iwork;
        double *work = malloc(dyn_solve_work_size(m, 2, &o) * sizeof *work);
        const double y0[2] = {0.5, 0.0};
        double y[2];
        dyn_result res;
        assert_int_equal(dyn_solve(m, &sys, 0.0, 10.0, y0, y, work, &o, &res), DYN_OK);
        free(work);
        /* x crosses 1, 2, ..., 10 */
        assert_int_equal(c.resets, 10);
        assert_true(y[1] == 10.0);
        assert_true(fabs(y[0] - 10.5) < 1e-9);
    }
}

/* ---- cascades: a reset that carries another event's g across zero fires it at once ---- */

/* x' = 1, y' = 1/2, z' = 0 (a tally). A: x - 1 rising, x = 0, y += 1, z += 1; B: y - 1
 * rising, y = 0, x += 2, z += 10 (XPPAUT's two globals, tests/xppaut/events/
 * cascade_chain.ode). From y(0) = 0.2: at t = 1 A fires (y = 0.7 -> 1.7), B fires in the
 * same instant (x = 0 -> 2, back across A's zero: A does not fire twice), so x = t + 1 and
 * y = (t - 1)/2 after it, z = 11. Z: a DYN_EVENT_JUMPS event on x - 3.5, which the flow
 * crosses at t = 2.5 (no event) and no reset does. */
static int xyz_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    (void)y;
    (void)par;
    dydt[0] = 1.0;
    dydt[1] = 0.5;
    dydt[2] = 0.0;
    return 0;
}

static double x_minus_1(double t, const double *y, void *par)
{
    (void)t;
    (void)par;
    return y[0] - 1.0;
}

static double y_minus_1(double t, const double *y, void *par)
{
    (void)t;
    (void)par;
    return y[1] - 1.0;
}

static double x_minus_35(double t, const double *y, void *par)
{
    (void)t;
    (void)par;
    return y[0] - 3.5;
}

static int reset_a(double t, double *y, void *par)
{
    (void)t;
    (void)par;
    y[0] = 0.0;
    y[1] += 1.0;
    y[2] += 1.0;
    return 0;
}

static int reset_b(double t, double *y, void *par)
{
    (void)t;
    (void)par;
    y[1] = 0.0;
    y[0] += 2.0;
    y[2] += 10.0;
    return 0;
}

static int reset_z(double t, double *y, void *par)
{
    (void)t;
    (void)par;
    y[2] += 100.0;
    return 0;
}

static int solve_xyz(const char *method, const dyn_event *ev, int ne, double t1, ev_log *log,
                     double y[3], dyn_result *res)
{
    const dyn_tableau *m = dyn_method_find(method);
    assert_non_null(m);
    dyn_system sys = {xyz_rhs, 3, NULL};
    dyn_solve_opts o = {0};
    o.rtol = o.atol = 1e-10;
    o.h = 0.07;
    o.events = ev;
    o.n_events = ne;
    o.on_event = log_event;
    o.event_ctx = log;
    int iwork[4];
    o.iwork = iwork;
    log->count = 0;
    double *work = malloc(dyn_solve_work_size(m, 3, &o) * sizeof *work);
    assert_non_null(work);
    const double y0[3] = {0.0, 0.2, 0.0};
    const int rc = dyn_solve(m, &sys, 0.0, t1, y0, y, work, &o, res);
    free(work);
    return rc;
}

static void test_cascade_fires_at_the_instant(void **state)
{
    (void)state;
    const dyn_event ev[] = {
        {.name = "A", .g = x_minus_1, .direction = 1, .reset = reset_a},
        {.name = "B", .g = y_minus_1, .direction = 1, .reset = reset_b},
        {.name = "Z", .g = x_minus_35, .direction = DYN_EVENT_JUMPS, .reset = reset_z},
    };
    const char *methods[] = {"dp45", "rk4", "rodas4"};
    for (int r = 0; r < 3; r++) {
        ev_log log = {.stop_at = -1};
        double y[3];
        dyn_result res;
        assert_int_equal(solve_xyz(methods[r], ev, 3, 2.8, &log, y, &res), DYN_OK);
        assert_int_equal(log.count, 2);
        assert_int_equal(res.events, 2);
        assert_int_equal(res.cascades, 1);
        assert_int_equal(log.index[0], 0);
        assert_int_equal(log.index[1], 1);
        assert_true(log.t[0] == log.t[1] && fabs(log.t[0] - 1.0) < 1e-9);
        /* B sees the state after A's reset */
        assert_true(fabs(log.y[1][0]) < 1e-15 && fabs(log.y[1][1] - 1.7) < 1e-9);
        assert_true(fabs(y[0] - 3.8) < 1e-8 && fabs(y[1] - 0.9) < 1e-8 && y[2] == 11.0);
        /* on to t = 4.5: y crosses 1 again at t = 3 (B alone, by the flow) */
        assert_int_equal(solve_xyz(methods[r], ev, 3, 4.5, &log, y, &res), DYN_OK);
        assert_int_equal(log.count, 3);
        assert_int_equal(log.index[2], 1);
        assert_true(fabs(log.t[2] - 3.0) < 1e-9);
        assert_true(y[2] == 21.0);
    }
}

/* A DYN_EVENT_JUMPS event fires when a reset takes g onto zero, not when the next one takes
 * it off: y steps 0.5 at each crossing of x = 1 (from y = 0.5: 1, 1.5, 2 at t = 1, 2, 3). */
static int reset_step(double t, double *y, void *par)
{
    (void)t;
    (void)par;
    y[0] = 0.0;
    y[1] += 0.5;
    return 0;
}

static double y_minus_1_flat(double t, const double *y, void *par)
{
    (void)t;
    (void)par;
    return y[1] - 1.0;
}

static int tally(double t, double *y, void *par)
{
    (void)t;
    (void)par;
    y[2] += 1.0;
    return 0;
}

static int steps_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    (void)y;
    (void)par;
    dydt[0] = 1.0;
    dydt[1] = dydt[2] = 0.0;
    return 0;
}

/* dp45 at tolerance 1e-10 on steps_rhs from (0, y0) to t1 with the events ev. */
static int solve_steps(const dyn_event *ev, int ne, const double y0[3], double t1, double y[3],
                       dyn_result *res)
{
    const dyn_tableau *m = dyn_method_find("dp45");
    dyn_system sys = {steps_rhs, 3, NULL};
    dyn_solve_opts o = {0};
    o.rtol = o.atol = 1e-10;
    o.events = ev;
    o.n_events = ne;
    double *work = malloc(dyn_solve_work_size(m, 3, &o) * sizeof *work);
    assert_non_null(work);
    const int rc = dyn_solve(m, &sys, 0.0, t1, y0, y, work, &o, res);
    free(work);
    return rc;
}

static void test_jumps_onto_zero_only(void **state)
{
    (void)state;
    const dyn_event ev[] = {
        {.name = "step", .g = x_minus_1, .direction = 1, .reset = reset_step},
        {.name = "onto", .g = y_minus_1_flat, .direction = DYN_EVENT_JUMPS, .reset = tally},
    };
    const double y0[3] = {0.0, 0.5, 0.0};
    double y[3];
    dyn_result res;
    assert_int_equal(solve_steps(ev, 2, y0, 3.5, y, &res), DYN_OK);
    assert_true(y[1] == 2.0);
    assert_true(y[2] == 1.0); /* onto zero at t = 2 only */
    assert_int_equal(res.cascades, 1);
}

/* A cascade that re-arms the event that started it, ever sooner: A (x - 1 rising) raises a
 * flag y, B (y - 1/2 rising) lowers it and sets x just below 1 again. The pair fires at
 * shorter and shorter intervals: DYN_ERR_ZENO near t = 1 rather than a run that hangs. */
static int raise_flag(double t, double *y, void *par)
{
    (void)t;
    (void)par;
    y[1] = 1.0;
    return 0;
}

static double flag_half(double t, const double *y, void *par)
{
    (void)t;
    (void)par;
    return y[1] - 0.5;
}

static int rearm(double t, double *y, void *par)
{
    (void)t;
    (void)par;
    y[1] = 0.0;
    y[0] = 1.0 - 1e-13;
    return 0;
}

static void test_cascade_zeno(void **state)
{
    (void)state;
    const dyn_event ev[] = {
        {.name = "A", .g = x_minus_1, .direction = 1, .reset = raise_flag},
        {.name = "B", .g = flag_half, .direction = 1, .reset = rearm},
    };
    const double y0[3] = {0.0, 0.0, 0.0};
    double y[3];
    dyn_result res;
    assert_int_equal(solve_steps(ev, 2, y0, 3.0, y, &res), DYN_ERR_ZENO);
    assert_true(fabs(res.t - 1.0) < 1e-9);
    assert_true(res.cascades >= DYN_ZENO_RESETS / 2);
}

/* ---- the command line, with the ball as an XPPAUT file ---- */

static const char ball_ode[] = "# a bouncing ball\n"
                               "par g=9.81, e=0.8\n"
                               "init y=10, v=0\n"
                               "y'=v\n"
                               "v'=-g\n"
                               "#: event bounce = y, falling -- the floor\n"
                               "global -1 y {v=-e*v}\n"
                               "@ total=10, dt=0.01\n"
                               "done\n";

static void test_cli_resets(void **state)
{
    (void)state;
    assert_int_equal(cli_make_tmpdir("reset"), 0);
    FILE *f = fopen(cli_path("ball.ode"), "w");
    assert_non_null(f);
    fputs(ball_ode, f);
    fclose(f);
    const double e = 0.8;
    int expect = 0;
    while (bounce_time(expect, e) < 10.0)
        expect++;

    /* rk4 without --event: the bounces happen, the rows are the grid 0, 0.01, ..., 10 */
    cli_result r = cli("run '%s' --method rk4 --step 0.01 --tspan 0:10", cli_path("ball.ode"));
    if (r.status != 0)
        fail_msg("dynkit run ball.ode: %s", r.err);
    assert_int_equal(csv_rows(r.out), 1001);
    const char *line = strchr(r.out, '\n') + 1;
    for (long k = 0; k <= 1000; k++) {
        double t, y[2], ye[2];
        assert_int_equal(sscanf(line, "%lf,%lf,%lf", &t, &y[0], &y[1]), 3);
        assert_true(same_bits(t, k == 1000 ? 10.0 : (double)k * 0.01));
        ball_exact(t, e, ye);
        if (fabs(y[0] - ye[0]) > 1e-9 || fabs(y[1] - ye[1]) > 1e-9)
            fail_msg("row at t = %.17g: (%.17g, %.17g), exact (%.17g, %.17g)", t, y[0], y[1],
                     ye[0], ye[1]);
        line = strchr(line, '\n') + 1;
    }
    cli_free(&r);

    /* --every keeps the grid's every K-th row */
    r = cli("run '%s' --method rk4 --step 0.01 --tspan 0:10 --every 100", cli_path("ball.ode"));
    assert_int_equal(r.status, 0);
    double t[16];
    assert_int_equal(csv_times(r.out, t, 16), 11);
    for (int k = 0; k <= 10; k++)
        assert_true(t[k] == (double)k);
    cli_free(&r);

    /* dp45 with --event: the bounces reported, at the closed form's times */
    char model[512];
    snprintf(model, sizeof model, "%s", cli_path("ball.ode")); /* cli_path: one buffer */
    r = cli("run '%s' --method dp45 --rtol 1e-12 --atol 1e-12 --tspan 0:10 --final --event "
            "bounce --events-output '%s'",
            model, cli_path("ev.csv"));
    if (r.status != 0)
        fail_msg("dynkit run ball.ode --event bounce: %s", r.err);
    cli_free(&r);
    size_t len;
    char *ev = cli_read_file(cli_path("ev.csv"), &len);
    assert_true(strncmp(ev, "event,t,y,v\n", 12) == 0);
    assert_int_equal(csv_rows(ev), expect);
    line = ev + 12;
    for (int k = 0; k < expect; k++) {
        double te, y, v;
        assert_int_equal(sscanf(line, "bounce,%lf,%lf,%lf", &te, &y, &v), 3);
        /* each instant is XPPAUT's, a relative 1e-10 of its step past the crossing, and
         * moves the bounces after it as much: within 1e-10 of the time elapsed */
        assert_true(fabs(te - bounce_time(k, e)) < 1e-10 * (1.0 + bounce_time(k, e)));
        assert_true(v < 0.0); /* the state before the reset */
        line = strchr(line, '\n') + 1;
    }
    free(ev);

    /* cvode runs without events: refused with the reason */
    r = cli("run '%s' --method cvode", cli_path("ball.ode"));
    assert_int_equal(r.status, 2);
    if (cli_has_cvode())
        assert_non_null(strstr(r.err, "events that reset the state"));
    cli_free(&r);
    const char *files[] = {"ball.ode", "ev.csv", NULL};
    cli_teardown_files(files);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bounce_times_adaptive),
        cmocka_unit_test(test_bounce_times_fixed_step),
        cmocka_unit_test(test_grid_after_resets),
        cmocka_unit_test(test_both_directions_same_bounces),
        cmocka_unit_test(test_zeno_stops),
        cmocka_unit_test(test_reset_failure),
        cmocka_unit_test(test_terminal_events_with_resets),
        cmocka_unit_test(test_old_trajectory_events_dropped),
        cmocka_unit_test(test_counter_reset_fires_once_per_crossing),
        cmocka_unit_test(test_cascade_fires_at_the_instant),
        cmocka_unit_test(test_jumps_onto_zero_only),
        cmocka_unit_test(test_cascade_zeno),
        cmocka_unit_test(test_cli_resets),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
