/* SPDX-License-Identifier: BSD-3-Clause */
/* Events of dyn_solve and of the command line, against physical and numerical facts:
 * - the pendulum's first turning point (dphi = 0) from phi = 0 comes at a quarter period
 *   T/4 = K(k)/w, k = sin(phi_max/2), w = sqrt(g/l) (K by the arithmetic-geometric mean),
 *   to 1e-10 with dp45 at rtol 1e-12 and with DOP853; the next passage through the bottom
 *   at T/2; a zero at the start is no event; the state at the event is on the event;
 * - a sign change that returns within one step (two close roots) is found, both roots,
 *   with their directions; direction filters; a terminal event ends the solve with the
 *   state at the event as the last sample;
 * - events with fixed-step methods (cubic Hermite on the step) find the same times to the
 *   accuracy of the method, and leave the samples equal to the fixed-step driver's;
 * - the cart's slip event is where |lambda| reaches mu (2/3) m g;
 * - the command line: --event NAME[:stop], --events-output CSV (header event,t,phi,dphi),
 *   --stats, --times, and the usage errors that name the fix. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "dynkit/dynkit.h"
#include "test_cli_run.h"
#include "test_util.h"

/* Complete elliptic integral of the first kind, K(k) = pi / (2 AGM(1, sqrt(1 - k^2))). */
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

/* The homework's pendulum starts at phi = 0 with dphi = pi/2 and w = 1: its amplitude from
 * energy, 1 - cos(phi_max) = (pi/2)^2 / 2. */
#define HOMEWORK_AMPLITUDE acos(1.0 - 0.125 * DYN_PI * DYN_PI)

/* ---- a recorder of events ---- */

#define MAX_HITS 64
typedef struct hit_log {
    int count;
    int index[MAX_HITS], dir[MAX_HITS];
    double t[MAX_HITS], y[MAX_HITS][12];
    int n;
} hit_log;

static int log_event(int index, double t, const double *y, int direction, void *ctx)
{
    hit_log *h = ctx;
    if (h->count < MAX_HITS) {
        h->index[h->count] = index;
        h->dir[h->count] = direction;
        h->t[h->count] = t;
        memcpy(h->y[h->count], y, (size_t)h->n * sizeof *y);
        h->count++;
    }
    return 0;
}

static int solve_events(const char *method, const dyn_system *sys, double t0, double t1,
                        const double *y0, double tol, double h, const dyn_event *ev, int ne,
                        hit_log *hits, sample_log *samples, double *y, dyn_result *res)
{
    const dyn_tableau *m = dyn_method_find(method);
    assert_non_null(m);
    dyn_solve_opts o = {0};
    o.rtol = tol;
    o.atol = tol;
    o.h = h;
    o.events = ev;
    o.n_events = ne;
    o.on_event = log_event;
    o.event_ctx = hits;
    if (samples) {
        o.output = sample_log_output;
        o.output_ctx = samples;
    }
    hits->count = 0;
    hits->n = sys->n;
    double *work = malloc(dyn_solve_work_size(m, sys->n, &o) * sizeof *work);
    assert_non_null(work);
    int rc = dyn_solve(m, sys, t0, t1, y0, y, work, &o, res);
    free(work);
    return rc;
}

/* the pendulum model with w = 1 (the homework's l = g = 9.81) and amplitude phi_max */
static void pendulum_setup(double phi_max, dyn_pendulum_par *par, double y0[2], double *quarter)
{
    char err[128];
    assert_int_equal(dyn_model_default_params(&dyn_model_pendulum, par, err, sizeof err), 0);
    const double w = sqrt(par->g / par->l), k = sin(0.5 * phi_max);
    y0[0] = 0.0;
    y0[1] = 2.0 * k * w; /* energy: dphi0^2 / 2 = w^2 (1 - cos phi_max) = 2 w^2 k^2 */
    *quarter = ellip_k(k) / w;
}

static void test_pendulum_turn_at_quarter_period(void **state)
{
    (void)state;
    const dyn_model *m = &dyn_model_pendulum;
    assert_int_equal(m->n_events, 2);
    assert_string_equal(m->events[0].name, "turn");
    assert_string_equal(m->events[1].name, "bottom");
    const double amplitudes[] = {0.1, 1.0, HOMEWORK_AMPLITUDE, 3.0};
    static const struct {
        const char *method;
        double tol, bound;
    } runs[] = {{"dp45", 1e-12, 1e-10}, {"dop853", 1e-12, 1e-10}, {"dop853", 1e-10, 1e-8}};
    for (size_t a = 0; a < sizeof amplitudes / sizeof amplitudes[0]; a++) {
        dyn_pendulum_par par;
        double y0[2], T4, y[2];
        pendulum_setup(amplitudes[a], &par, y0, &T4);
        dyn_system sys = {m->rhs, 2, &par};
        for (size_t r = 0; r < sizeof runs / sizeof runs[0]; r++) {
            hit_log hits;
            dyn_result res;
            assert_int_equal(solve_events(runs[r].method, &sys, 0.0, 8.5 * T4, y0, runs[r].tol,
                                          0.0, m->events, 2, &hits, NULL, y, &res),
                             DYN_OK);
            /* turn at T/4 (falling dphi), bottom at T/2 (phi falls through 0), turn at 3T/4,
             * bottom at T, turn at 5T/4 ... the start (phi = 0) is no event */
            assert_int_equal(hits.count, 4 + 4);
            assert_int_equal(res.events, hits.count);
            for (int i = 0; i < hits.count; i++) {
                const double expect = (double)(i + 1) * T4;
                const int idx = i % 2 == 0 ? 0 : 1;
                assert_int_equal(hits.index[i], idx);
                CHECK(fabs(hits.t[i] - expect) < runs[r].bound * (i + 1) * (i + 1), /* phase drift */
                      "%s rtol %g, amplitude %g: event %d at %.17g, expected %.17g (off %.3g)",
                      runs[r].method, runs[r].tol, amplitudes[a], i, hits.t[i], expect,
                      hits.t[i] - expect);
                /* the state there is on the event */
                const double g = m->events[idx].g(hits.t[i], hits.y[i], &par);
                CHECK(fabs(g) < 1e-9, "g = %.3g at the event", g);
                /* directions: turn falling then rising; bottom falling then rising */
                assert_int_equal(hits.dir[i], (i / 2) % 2 == 0 ? -1 : 1);
            }
            if (r == 0 && a == 2)
                test_note("homework pendulum, dp45 rtol 1e-12: turn at %.15f, T/4 = %.15f",
                          hits.t[0], T4);
        }
    }
}

/* g with two roots 1e-3 apart inside one step of a loosely solved smooth problem */
static int slow_rhs(double t, const double *y, double *f, void *par)
{
    (void)t;
    (void)par;
    f[0] = -0.1 * y[0];
    return 0;
}

static double two_roots(double t, const double *y, void *par)
{
    (void)y;
    const double *r = par;
    return (t - r[0]) * (t - r[1]);
}

static double y_dip(double t, const double *y, void *par)
{
    (void)t;
    const double *c = par;
    return y[0] - c[2]; /* y = exp(-0.1 t) passes c[2] once, falling */
}

typedef struct roots_par {
    double r[3];
} roots_par;

static int roots_rhs(double t, const double *y, double *f, void *par)
{
    (void)par; /* the roots of the event functions */
    return slow_rhs(t, y, f, NULL);
}

static void test_two_roots_in_one_step(void **state)
{
    (void)state;
    roots_par par = {{3.2, 3.201, exp(-0.1 * 7.5)}};
    dyn_system sys = {roots_rhs, 1, &par};
    const dyn_event ev[] = {{"pair", "", two_roots, 0, 0, NULL}, {"once", "", y_dip, 0, 0, NULL}};
    const double y0 = 1.0;
    const char *const methods[] = {"bs23", "dp45", "dop853"};
    for (int k = 0; k < 3; k++) {
        hit_log hits;
        dyn_result res;
        double y;
        assert_int_equal(solve_events(methods[k], &sys, 0.0, 10.0, &y0, 1e-4, 0.0, ev, 2, &hits,
                                      NULL, &y, &res),
                         DYN_OK);
        /* the steps are long: both roots fall within one step */
        CHECK(res.stats.accepted < 40, "%s: %ld steps", methods[k], res.stats.accepted);
        assert_int_equal(hits.count, 3);
        assert_int_equal(hits.index[0], 0);
        assert_int_equal(hits.dir[0], -1);
        assert_true(fabs(hits.t[0] - 3.2) < 1e-13);
        assert_int_equal(hits.index[1], 0);
        assert_int_equal(hits.dir[1], 1);
        assert_true(fabs(hits.t[1] - 3.201) < 1e-13);
        assert_int_equal(hits.index[2], 1);
        assert_int_equal(hits.dir[2], -1);
        /* the crossing of the computed y (whose error at rtol 1e-4 moves it by ~1e-3) */
        CHECK(fabs(hits.t[2] - 7.5) < 1e-2, "%s: y crosses at %.17g", methods[k], hits.t[2]);
        assert_true(fabs(y_dip(hits.t[2], hits.y[2], &par)) < 1e-14);
    }
    /* the same pair with a fixed-step method and big steps */
    hit_log hits;
    dyn_result res;
    double y;
    assert_int_equal(solve_events("rk4", &sys, 0.0, 10.0, &y0, 0.0, 0.5, ev, 1, &hits, NULL, &y,
                                  &res),
                     DYN_OK);
    assert_int_equal(hits.count, 2);
    assert_true(fabs(hits.t[0] - 3.2) < 1e-13 && fabs(hits.t[1] - 3.201) < 1e-13);
}

/* phi - level for the pendulum (level through the pointer in par's place would change the
 * model's par, so it is a file-scope value) */
static double pendulum_level;
static double phi_minus_level(double t, const double *y, void *par)
{
    (void)t;
    (void)par;
    return y[0] - pendulum_level;
}

static void test_close_crossings_near_a_turning_point(void **state)
{
    (void)state;
    dyn_pendulum_par par;
    double y0[2], T4, y[2];
    pendulum_setup(1.0, &par, y0, &T4);
    dyn_system sys = {dyn_model_pendulum.rhs, 2, &par};
    const dyn_event ev[] = {{"level", "", phi_minus_level, 0, 0, NULL}};
    for (int e = 2; e <= 6; e += 2) {
        const double depth = pow(10.0, -e);
        pendulum_level = 1.0 - depth;
        /* near the top phi ~ 1 - (w t')^2 tan(1)/2 ... the roots: phi(T4 +- d) = level */
        hit_log hits;
        dyn_result res;
        assert_int_equal(solve_events("dop853", &sys, 0.0, 2.0 * T4, y0, 1e-11, 0.0, ev, 1, &hits,
                                      NULL, y, &res),
                         DYN_OK);
        CHECK(hits.count == 2, "depth %g: %d crossings", depth, hits.count);
        assert_int_equal(hits.dir[0], 1);
        assert_int_equal(hits.dir[1], -1);
        /* symmetric about the turning point */
        const double mid = 0.5 * (hits.t[0] + hits.t[1]);
        CHECK(fabs(mid - T4) < 1e-7, "depth %g: crossings %.17g and %.17g, mid %.17g, T/4 %.17g",
              depth, hits.t[0], hits.t[1], mid, T4);
    }
}

static int stop_at_third(int index, double t, const double *y, int direction, void *ctx)
{
    (void)index;
    (void)t;
    (void)y;
    (void)direction;
    return ++*(int *)ctx == 3;
}

static void test_terminal_event_ends_the_solve(void **state)
{
    (void)state;
    dyn_pendulum_par par;
    double y0[2], T4, y[2];
    pendulum_setup(1.0, &par, y0, &T4);
    dyn_system sys = {dyn_model_pendulum.rhs, 2, &par};
    dyn_event ev[2] = {dyn_model_pendulum.events[0], dyn_model_pendulum.events[1]};
    ev[1].terminal = 1; /* stop at the bottom */
    static sample_log samples;
    sample_log_init(&samples, 2);
    const dyn_tableau *m = dyn_method_find("dp45");
    dyn_solve_opts o = {0};
    o.rtol = o.atol = 1e-10;
    o.out_step = 0.1;
    o.output = sample_log_output;
    o.output_ctx = &samples;
    o.events = ev;
    o.n_events = 2;
    double work[512];
    assert_true(dyn_solve_work_size(m, 2, &o) <= 512);
    dyn_result res;
    assert_int_equal(dyn_solve(m, &sys, 0.0, 100.0, y0, y, work, &o, &res), DYN_OK);
    assert_int_equal(res.stopped_by_event, 1);
    assert_int_equal(res.event_index, 1);
    assert_int_equal(res.events, 2); /* the turn, then the bottom */
    assert_true(fabs(res.t - 2.0 * T4) < 1e-9);
    assert_true(fabs(y[0]) < 1e-9 && y[1] < 0.0); /* the state is at the bottom */
    /* samples on the grid up to the event, then the event as the last sample */
    const long last = samples.count - 1;
    assert_true(same_bits(samples.t[last], res.t));
    assert_true(same_bits(samples.y[last][0], y[0]) && same_bits(samples.y[last][1], y[1]));
    assert_true(samples.t[last - 1] < res.t && samples.t[last - 1] > res.t - 0.1);
    for (long k = 0; k < last; k++)
        assert_true(same_bits(samples.t[k], (double)k * 0.1));
    /* a callback can make an event terminal: the third one */
    ev[1].terminal = 0;
    int seen = 0;
    o.output = NULL;
    o.on_event = stop_at_third;
    o.event_ctx = &seen;
    assert_int_equal(dyn_solve(m, &sys, 0.0, 100.0, y0, y, work, &o, &res), DYN_OK);
    assert_true(res.stopped_by_event && res.event_index == 0 && seen == 3);
    assert_true(fabs(res.t - 3.0 * T4) < 1e-9 && fabs(y[1]) < 1e-9);
    /* and without terminal events the solve runs to the end */
    o.on_event = NULL;
    assert_int_equal(dyn_solve(m, &sys, 0.0, 100.0, y0, y, work, &o, &res), DYN_OK);
    assert_true(!res.stopped_by_event && res.t == 100.0 && res.events > 50);
}

/* direction +1 only: the rising passages of the bottom (phi from < 0 to > 0) */
static void test_direction_filter(void **state)
{
    (void)state;
    dyn_pendulum_par par;
    double y0[2], T4, y[2];
    pendulum_setup(2.0, &par, y0, &T4);
    dyn_system sys = {dyn_model_pendulum.rhs, 2, &par};
    dyn_event ev = dyn_model_pendulum.events[1];
    ev.direction = 1;
    hit_log hits;
    dyn_result res;
    assert_int_equal(
        solve_events("dop853", &sys, 0.0, 16.5 * T4, y0, 1e-12, 0.0, &ev, 1, &hits, NULL, y, &res),
        DYN_OK);
    assert_int_equal(hits.count, 4); /* at T, 2T, 3T, 4T */
    for (int i = 0; i < hits.count; i++) {
        assert_int_equal(hits.dir[i], 1);
        CHECK(fabs(hits.t[i] - 4.0 * (i + 1) * T4) < 1e-9, "rising bottom %d at %.17g", i,
              hits.t[i]);
    }
}

static void test_events_with_fixed_step_methods(void **state)
{
    (void)state;
    dyn_pendulum_par par;
    double y0[2], T4, y[2], yf[2], work[TEST_WORK];
    pendulum_setup(HOMEWORK_AMPLITUDE, &par, y0, &T4);
    dyn_system sys = {dyn_model_pendulum.rhs, 2, &par};
    static sample_log with, without;
    static const struct {
        const char *name;
        double h, tol;
    } cases[] = {{"rk4", 0.01, 1e-8}, {"rk38", 0.01, 1e-8}, {"heun", 0.001, 1e-5},
                 {"euler", 0.0001, 1e-2}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        hit_log hits;
        dyn_result res, rf;
        sample_log_init(&with, 2);
        sample_log_init(&without, 2);
        const double t1 = cases[c].h * 400.0 > 2.2 * T4 ? cases[c].h * 400.0 : 2.2 * T4;
        if (cases[c].h * 4000 < t1)
            continue; /* keep the sample logs small */
        assert_int_equal(solve_events(cases[c].name, &sys, 0.0, t1, y0, 0.0, cases[c].h,
                                      dyn_model_pendulum.events, 2, &hits, &with, y, &res),
                         DYN_OK);
        assert_true(hits.count >= 2);
        CHECK(fabs(hits.t[0] - T4) < cases[c].tol, "%s h = %g: turn at %.17g, T/4 = %.17g",
              cases[c].name, cases[c].h, hits.t[0], T4);
        CHECK(fabs(hits.t[1] - 2.0 * T4) < cases[c].tol, "%s: bottom at %.17g, T/2 = %.17g",
              cases[c].name, hits.t[1], 2.0 * T4);
        /* the samples are the fixed-step driver's, bit for bit */
        dyn_fixed_opts fo = {0};
        fo.output = sample_log_output;
        fo.output_ctx = &without;
        assert_int_equal(dyn_fixed_solve(dyn_method_find(cases[c].name), &sys, 0.0, t1,
                                         cases[c].h, y0, yf, work, &fo, &rf),
                         DYN_OK);
        assert_int_equal(with.count, without.count);
        for (long k = 0; k < with.count; k++)
            assert_true(same_bits(with.y[k][0], without.y[k][0]) &&
                        same_bits(with.y[k][1], without.y[k][1]) &&
                        same_bits(with.t[k], without.t[k]));
    }
}

/* The cart turning hard: the rear wheels reach the friction limit. */
static void test_cart_slip(void **state)
{
    (void)state;
    const dyn_model *m = dyn_model_find("cart");
    assert_non_null(m);
    assert_int_equal(m->n_events, 1);
    assert_string_equal(m->events[0].name, "slip");
    dyn_cart_par par;
    char err[128];
    assert_int_equal(dyn_model_default_params(m, &par, err, sizeof err), 0);
    par.Fy = 150.0; /* a steady side force at the front wheel */
    par.Fx = 0.0;
    assert_int_equal(dyn_cart_prepare(&par, err, sizeof err), 0);
    dyn_system sys = {m->rhs, 6, &par};
    double y0[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0}, y[6];
    /* start slow and below the limit */
    y0[3] = 1.0;
    y0[4] = 0.0;
    hit_log hits;
    dyn_result res;
    assert_true(m->events[0].g(0.0, y0, &par) < 0.0);
    assert_int_equal(solve_events("dp45", &sys, 0.0, 20.0, y0, 1e-10, 0.0, m->events, 1, &hits,
                                  NULL, y, &res),
                     DYN_OK);
    CHECK(hits.count >= 1, "no slip in 20 s");
    double out[6];
    m->compute_outputs(hits.t[0], hits.y[0], &par, out);
    const double limit = dyn_cart_friction_limit(&par);
    CHECK(fabs(fabs(out[2]) - limit) < 1e-8 * limit,
          "|lambda| = %.17g at the event, limit %.17g", fabs(out[2]), limit);
    assert_int_equal(hits.dir[0], 1);
}

/* ---- the command line ---- */

static int setup(void **state)
{
    (void)state;
    return cli_make_tmpdir("events");
}

static int teardown(void **state)
{
    (void)state;
    static const char *const files[] = {"events.csv", "times.txt", NULL};
    return cli_teardown_files(files);
}

static int count_lines(const char *s)
{
    int n = 0;
    for (; *s; s++)
        n += *s == '\n';
    return n;
}

static void test_cli_events_and_stats(void **state)
{
    (void)state;
    dyn_pendulum_par par;
    double y0[2], T4;
    pendulum_setup(HOMEWORK_AMPLITUDE, &par, y0, &T4); /* the model's default start */
    cli_result r = cli_in_tmpdir(
        "run pendulum --method dp45 --rtol 1e-12 --atol 1e-12 --tspan 0:10 "
        "--event turn --event bottom:stop --events-output events.csv --stats --final");
    CHECK(r.status == 0, "exit %d: %s", r.status, r.err);
    /* --stats: one line of counts */
    long steps, acc, rej, rhs;
    const char *line = strstr(r.err, "steps=");
    assert_non_null(line);
    assert_int_equal(sscanf(line, "steps=%ld accepted=%ld rejected=%ld rhs=%ld", &steps, &acc, &rej,
                            &rhs),
                     4);
    assert_true(steps == acc + rej && rhs == 6 * steps + 2);
    /* the run ended at the bottom: the final row is the event */
    char path[512];
    snprintf(path, sizeof path, "%s/events.csv", cli_tmpdir);
    char *ev = cli_read_file(path, NULL);
    assert_true(strncmp(ev, "event,t,phi,dphi\n", 17) == 0);
    assert_int_equal(count_lines(ev), 3);
    double t_turn, p1, d1, t_bottom, p2, d2;
    assert_int_equal(sscanf(ev + 17, "turn,%lf,%lf,%lf\nbottom,%lf,%lf,%lf", &t_turn, &p1, &d1,
                            &t_bottom, &p2, &d2),
                     6);
    CHECK(fabs(t_turn - T4) < 1e-11, "turn at %.17g, T/4 %.17g", t_turn, T4);
    CHECK(fabs(t_bottom - 2 * T4) < 1e-11, "bottom at %.17g, T/2 %.17g", t_bottom, 2 * T4);
    assert_true(fabs(d1) < 1e-9 && fabs(p2) < 1e-9);
    double tf, pf, df;
    assert_int_equal(sscanf(r.out, "t,phi,dphi\n%lf,%lf,%lf", &tf, &pf, &df), 3);
    assert_true(tf == t_bottom && pf == p2 && df == d2);
    free(ev);
    cli_free(&r);

    /* without --events-output the events go to stderr */
    r = cli_in_tmpdir("run pendulum --method rk4 --step 0.01 --tspan 0:5 --event turn");
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.err, "event turn"));
    assert_int_equal(count_lines(r.out), 1 + 501); /* the samples are unchanged */
    cli_free(&r);
}

static void test_cli_times(void **state)
{
    (void)state;
    cli_result r = cli_in_tmpdir(
        "run pendulum --method dop853 --rtol 1e-12 --atol 1e-12 --times 0,0.25,1,2.5");
    CHECK(r.status == 0, "exit %d: %s", r.status, r.err);
    double t[4], phi, dphi;
    const char *p = strchr(r.out, '\n') + 1;
    for (int i = 0; i < 4; i++) {
        assert_int_equal(sscanf(p, "%lf,%lf,%lf", &t[i], &phi, &dphi), 3);
        p = strchr(p, '\n') + 1;
    }
    assert_true(t[0] == 0 && t[1] == 0.25 && t[2] == 1 && t[3] == 2.5 && *p == '\0');
    cli_free(&r);
    /* @FILE: one time per line */
    char path[512];
    snprintf(path, sizeof path, "%s/times.txt", cli_tmpdir);
    FILE *f = fopen(path, "w");
    fputs("# times\n0.5\n\n1.5\n", f);
    fclose(f);
    r = cli_in_tmpdir("run vanderpol --method dp45 --times @times.txt");
    CHECK(r.status == 0, "exit %d: %s", r.status, r.err);
    assert_int_equal(count_lines(r.out), 3);
    assert_non_null(strstr(r.out, "\n0.5,"));
    assert_non_null(strstr(r.out, "\n1.5,"));
    cli_free(&r);
    /* default output of an adaptive run: the model's step grid, like [0:Ts:endtime] */
    r = cli_in_tmpdir("run vanderpol --method ode45 --rtol 1e-6");
    assert_int_equal(r.status, 0);
    assert_int_equal(count_lines(r.out), 1 + 1501);
    cli_free(&r);
}

static void check_usage(const char *args, const char *const *words)
{
    cli_result r = cli_in_tmpdir("%s", args);
    CHECK(r.status == 2, "'%s': exit %d (stderr %s)", args, r.status, r.err);
    CHECK(r.out[0] == '\0', "'%s': stdout not empty", args);
    for (const char *const *w = words; *w; w++)
        CHECK(strstr(r.err, *w) != NULL, "'%s': stderr does not mention '%s': %s", args, *w, r.err);
    cli_free(&r);
}
#define USAGE(args, ...) check_usage(args, (const char *const[]){__VA_ARGS__, NULL})

static void test_cli_usage_errors(void **state)
{
    (void)state;
    USAGE("run pendulum --method rk4 --rtol 1e-6", "--rtol", "adaptive", "--method dp45");
    USAGE("run pendulum --method euler --atol 1e-6", "--atol", "--method dp45");
    USAGE("run pendulum --method rk4 --max-step 0.1", "--max-step");
    USAGE("run pendulum --method rk4 --times 0,1", "--times", "adaptive");
    USAGE("run pendulum --method dp45 --rtol -1", "--rtol", "-1");
    USAGE("run pendulum --method dp45 --atol 1e-6,1e-6,1e-6", "--atol", "2 values");
    USAGE("run pendulum --method dp45 --times 1,0.5", "--times", "decrease");
    USAGE("run pendulum --method dp45 --times 0,x", "--times", "'x'");
    USAGE("run pendulum --method dp45 --times 0,1 --step 0.1", "--times", "--step");
    USAGE("run pendulum --event top", "'top'", "turn", "bottom");
    USAGE("run vanderpol --event turn", "vanderpol", "no event");
    USAGE("run pendulum --event turn:later", "turn:later", "NAME:stop");
    USAGE("run pendulum --events-output e.csv", "--events-output", "--event");
    USAGE("run pendulum --method dp45 --max-steps 0", "--max-steps");
}

static void test_cli_methods_columns(void **state)
{
    (void)state;
    cli_result r = cli_in_tmpdir("methods");
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.out, "STIFF"));
    const char *dp = strstr(r.out, "\ndp45 ");
    assert_non_null(dp);
    char name[16], alias[16], order[16], kind[16], stiff[8];
    int stages, calls, jac, dense;
    assert_int_equal(sscanf(dp + 1, "%15s %15s %15s %d %d %d %d %15s %7s", name, alias, order,
                            &stages, &calls, &jac, &dense, kind, stiff),
                     9);
    assert_string_equal(alias, "ode45");
    assert_string_equal(order, "5(4)");
    assert_true(stages == 7 && calls == 6 && jac == 0 && dense == 4);
    assert_string_equal(kind, "adaptive");
    assert_string_equal(stiff, "no");
    assert_non_null(strstr(r.out, "\nbs23 "));
    assert_non_null(strstr(r.out, "\ndop853 "));
    /* rodas4: f(t, y), five more stages and df/dt, one Jacobian per step */
    const char *ro = strstr(r.out, "\nrodas4 ");
    assert_non_null(ro);
    assert_int_equal(sscanf(ro + 1, "%15s %15s %15s %d %d %d %d %15s %7s", name, alias, order,
                            &stages, &calls, &jac, &dense, kind, stiff),
                     9);
    assert_true(stages == 6 && calls == 7 && jac == 1 && dense == 3);
    assert_string_equal(stiff, "yes");
    cli_free(&r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pendulum_turn_at_quarter_period),
        cmocka_unit_test(test_two_roots_in_one_step),
        cmocka_unit_test(test_close_crossings_near_a_turning_point),
        cmocka_unit_test(test_terminal_event_ends_the_solve),
        cmocka_unit_test(test_direction_filter),
        cmocka_unit_test(test_events_with_fixed_step_methods),
        cmocka_unit_test(test_cart_slip),
        cmocka_unit_test(test_cli_events_and_stats),
        cmocka_unit_test(test_cli_times),
        cmocka_unit_test(test_cli_usage_errors),
        cmocka_unit_test(test_cli_methods_columns),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
