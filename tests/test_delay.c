/* SPDX-License-Identifier: BSD-3-Clause */
/* Delay equations (dynkit/delay.h; model files' delay(x, tau)) against closed forms and an
 * independent solver:
 *   - y'(t) = -y(t - 1) with the history 1 is a polynomial of degree k on [k, k + 1]
 *     (the method of steps done exactly: y(1) = 0, y(2) = -1/2, y(3) = -1/6, ...), which
 *     the library's history and every explicit method follow; with the steps landing on
 *     the breaking points dp45, dop853 and rk4 show their orders 5, 8 and 4, and a lag the
 *     tracking cannot see (1 + 0 y) costs orders of magnitude;
 *   - the Mackey-Glass equation against tests/delay/mackey_glass_ref.py (the method of
 *     steps with RK4 at tau/3400, written apart from the library) over t <= 300;
 *   - a state-dependent lag y/4 whose solution is 2 + sin t;
 *   - the breaking points of two lags (Bellen & Zennaro 2003, sec. 3.1), the history's
 *     bound (@ delay=) and the refusals. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <ctype.h>
#include <math.h>

#include "dynkit/delay.h"
#include "dynkit/dynkit.h"
#include "test_cli_run.h"
#include "test_util.h"

static char cache_dir[512];

static int setup_all(void **state)
{
    (void)state;
    if (cli_make_tmpdir_with_cache("delay", cache_dir, sizeof cache_dir))
        return -1;
    /* the documentation's commands name examples/... from the source tree's root */
    return symlink(DYNKIT_SOURCE_DIR "/examples", cli_path("examples"));
}

/* ---- the closed form of y' = -y(t - 1), y = 1 before 0 ----
 * On [k, k + 1], with u = t - k: q_0(u) = 1 - u, and q_{k+1}(u) = q_k(1) - int_0^u q_k(v) dv
 * (y(t - 1) on [k + 1, k + 2] is q_k at the same u). Coefficients of u^j, exact for these
 * small rationals to rounding. */
#define PIECES 24
static double q[PIECES][PIECES + 2];

static void closed_form_init(void)
{
    memset(q, 0, sizeof q);
    q[0][0] = 1.0;
    q[0][1] = -1.0;
    for (int k = 0; k + 1 < PIECES; k++) {
        double end = 0.0;
        for (int j = PIECES; j >= 0; j--)
            end += q[k][j];
        q[k + 1][0] = end;
        for (int j = 0; j <= PIECES; j++)
            q[k + 1][j + 1] = -q[k][j] / (j + 1);
    }
}

static double closed_form(double t)
{
    if (t <= 0.0)
        return 1.0;
    int k = (int)floor(t);
    if (k >= PIECES)
        k = PIECES - 1;
    const double u = t - k;
    double v = 0.0;
    for (int j = PIECES + 1; j >= 0; j--)
        v = v * u + q[k][j];
    return v;
}

/* The closed form gives the values the method of steps gives by hand. */
static void test_closed_form_values(void **state)
{
    (void)state;
    closed_form_init();
    CHECK(fabs(closed_form(1.0)) < 1e-15 && fabs(closed_form(2.0) + 0.5) < 1e-15 &&
              fabs(closed_form(3.0) + 1.0 / 6.0) < 1e-15 &&
              fabs(closed_form(4.0) - 5.0 / 24.0) < 1e-15,
          "%g %g %g %g", closed_form(1.0), closed_form(2.0), closed_form(3.0), closed_form(4.0));
    /* sympy: y(20) = -373609082700793/810967336058880000 */
    CHECK(fabs(closed_form(20.0) - (-373609082700793.0 / 810967336058880000.0)) < 1e-17,
          "%.17g", closed_form(20.0));
}

/* ---- the library alone: y' = -y(t - 1) through a history fed by dyn_solve ---- */

static int lag1_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)y;
    dydt[0] = -dyn_history_value((dyn_history *)par, 0, t, t - 1.0);
    return 0;
}

static int grow_history(dyn_history *h, void *ctx)
{
    long *max_count = ctx;
    if (h->count > *max_count)
        *max_count = h->count;
    const long cap = h->capacity ? 2 * h->capacity : 16;
    double *d = realloc(h->data, (size_t)cap * dyn_dense_record_block(h->n, h->degree) *
                                     sizeof *d);
    if (!d)
        return 1;
    h->data = d;
    h->capacity = cap;
    return 0;
}

static void test_library_history(void **state)
{
    (void)state;
    closed_form_init();
    const dyn_tableau *m = dyn_method_find("dop853");
    const double y0[1] = {1.0};
    dyn_history h = {0};
    long grown_at = 0;
    h.grow = grow_history;
    h.grow_ctx = &grown_at;
    dyn_history_init(&h, 1, dyn_method_dense_degree(m), 0.0, y0, NULL, NULL, 2.0, NULL, 0);
    dyn_system sys = {lag1_rhs, 1, &h};
    const double lag = 1.0;
    double stops[64];
    const long ns = dyn_delay_breaks(0.0, 12.0, &lag, 1, m->order + 1, stops, 64);
    CHECK(ns == 9 && stops[0] == 1.0 && stops[8] == 9.0, "%ld stops", ns);
    dyn_solve_opts o = {0};
    o.rtol = 1e-12;
    o.atol = 1e-14;
    o.step = dyn_history_push;
    o.step_ctx = &h;
    o.stops = stops;
    o.n_stops = ns;
    double *work = malloc(dyn_solve_work_size(m, 1, &o) * sizeof *work);
    dyn_result res;
    double y[1];
    for (int k = 1; k <= 12; k++) {
        dyn_history_init(&h, 1, dyn_method_dense_degree(m), 0.0, y0, NULL, NULL, 2.0, h.data,
                         h.capacity);
        assert_int_equal(dyn_solve(m, &sys, 0.0, (double)k, y0, y, work, &o, &res), DYN_OK);
        CHECK(fabs(y[0] - closed_form(k)) < 1e-14, "y(%d) = %.17g, closed form %.17g", k, y[0],
              closed_form(k));
        /* the steps the longest lag (2) can reach are kept, not the whole run */
        double kept_from = h.data[h.first * (long)dyn_dense_record_block(1, h.degree)];
        CHECK(kept_from >= k - 2.0 - 1.0, "t = %d: the steps from %g are kept", k, kept_from);
    }
    assert_int_equal(h.failed, 0);
    /* a lag longer than the bound, or negative, gives NaN and says so */
    CHECK(isnan(dyn_history_value(&h, 0, 12.0, 9.5)), "a lag of 2.5 > 2 is refused");
    char msg[256];
    const char *names[1] = {"y"};
    dyn_history_message(&h, names, msg, sizeof msg);
    CHECK(h.failed == 1 && strstr(msg, "delay(y, ...)") && strstr(msg, "maximal delay 2"), "%s",
          msg);
    CHECK(isnan(dyn_history_value(&h, 0, 12.0, 12.5)) && h.failed == 2, "a negative lag");
    dyn_history_message(&h, names, msg, sizeof msg);
    CHECK(strstr(msg, "asks for a negative lag -0.5, the value at t = 12.5, after the present"),
          "%s", msg);
    /* a NaN lag that the NaN of the refused one made does not hide it; a NaN lag alone says
     * so */
    CHECK(isnan(dyn_history_value(&h, 0, 12.0, NAN)) && h.failed == 2, "%d", h.failed);
    h.failed = 0;
    CHECK(isnan(dyn_history_value(&h, 0, 12.0, NAN)) && h.failed == 3, "%d", h.failed);
    dyn_history_message(&h, names, msg, sizeof msg);
    CHECK(strstr(msg, "asks for a lag that is not a number (NaN)"), "%s", msg);
    CHECK(isnan(dyn_history_value(NULL, 0, 1.0, 0.5)), "no history");
    free(work);
    free(h.data);
}

/* Bellen & Zennaro: the breaking points of lags 1 and 1.5 from 0 are the sums k 1 + l 1.5,
 * here with k + l <= 3, sorted without repeats. */
static void test_breaking_points(void **state)
{
    (void)state;
    const double lags[3] = {1.5, 1.0, 1.5};
    double out[32];
    const long n = dyn_delay_breaks(0.0, 100.0, lags, 3, 3, out, 32);
    const double want[] = {1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0, 4.5};
    assert_int_equal(n, 8);
    for (int i = 0; i < 8; i++)
        CHECK(out[i] == want[i], "break %d = %g, expected %g", i, out[i], want[i]);
    assert_int_equal(dyn_delay_breaks(0.0, 2.2, lags, 3, 3, out, 32), 3); /* 1, 1.5, 2 */
    const double bad = 0.0;
    assert_int_equal(dyn_delay_breaks(0.0, 10.0, &bad, 1, 3, out, 32), 0);
}

/* ---- model files ---- */

static const char lag1_ode[] = "# y' = -y(t-1), history 1\n"
                               "y'=-delay(y,1)\n"
                               "y(0)=1\n"
                               "@ delay=2, total=20, dt=0.125\n"
                               "done\n";
/* the same lag, written through the state: no breaking points are known */
static const char lag1_untracked_ode[] = "y'=-delay(y,1+0*y)\n"
                                         "y(0)=1\n"
                                         "@ delay=2, total=20, dt=0.125\n"
                                         "done\n";

/* The value at the end of a run (the last number printed by --final). */
static double final_value(const char *file, const char *args)
{
    cli_result r = cli("run %s %s --final", cli_path(file), args);
    CHECK(r.status == 0, "run %s %s: %s", file, args, r.err);
    const char *last = strrchr(r.out, ',');
    CHECK(last != NULL, "%s", r.out);
    const double v = strtod(last + 1, NULL);
    cli_free(&r);
    return v;
}

/* dynkit info says a model has delays, with its constant lags and the maximal delay, and
 * that a lag of the state is not tracked. */
static void test_info_delays(void **state)
{
    (void)state;
    assert_int_equal(cli_write_file("lag1.ode", lag1_ode), 0);
    assert_int_equal(cli_write_file("lag1u.ode", lag1_untracked_ode), 0);
    cli_result r = cli("info %s", cli_path("lag1.ode"));
    CHECK(r.status == 0 && strstr(r.out, "Delays: delay(x, tau) reads the past; constant lags: 1 "
                                         "(the steps land on t0 + k*lag)") &&
              strstr(r.out, "maximal delay 2 (@ delay=)"),
          "%s", r.out);
    cli_free(&r);
    r = cli("info %s", cli_path("lag1u.ode"));
    CHECK(r.status == 0 && strstr(r.out, "lags of the states or t only (not tracked)"), "%s",
          r.out);
    cli_free(&r);
    r = cli("info pendulum");
    CHECK(r.status == 0 && !strstr(r.out, "Delays:"), "%s", r.out);
    cli_free(&r);
}

/* Every sample of an adaptive run on [0, 20] follows the closed form: exact values at the
 * breaking points 1 and 2, the piecewise polynomials between. */
static void test_file_closed_form(void **state)
{
    (void)state;
    closed_form_init();
    assert_int_equal(cli_write_file("lag1.ode", lag1_ode), 0);
    const char *methods[] = {"dp45", "dop853"};
    for (int mi = 0; mi < 2; mi++) {
        cli_result r = cli("run %s --method %s --rtol 1e-12 --atol 1e-14", cli_path("lag1.ode"),
                           methods[mi]);
        CHECK(r.status == 0, "%s", r.err);
        const char *p = strchr(r.out, '\n');
        long rows = 0;
        double worst = 0.0;
        while (p && p[1]) {
            char *end;
            const double t = strtod(p + 1, &end);
            const double y = strtod(end + 1, &end);
            worst = fmax(worst, fabs(y - closed_form(t)));
            if (t == 1.0 || t == 2.0)
                CHECK(fabs(y - closed_form(t)) < 1e-15, "%s: y(%g) = %.17g", methods[mi], t, y);
            rows++;
            p = strchr(end, '\n');
        }
        CHECK(rows == 161 && worst < 1e-12, "%s: %ld rows, largest error %g", methods[mi], rows,
              worst);
        cli_free(&r);
    }
}

/* Observed orders at t = 20 with steps h = 1/2, 1/4 (the step limits fix them; tolerances of
 * 1 accept every step): dp45 5, dop853 8, rk4 4 (its own grid). Steps that cross the
 * breaking points (h = 0.3, the lag hidden from the tracking) lose the order. */
static void test_file_orders(void **state)
{
    (void)state;
    closed_form_init();
    assert_int_equal(cli_write_file("lag1.ode", lag1_ode), 0);
    assert_int_equal(cli_write_file("lag1u.ode", lag1_untracked_ode), 0);
    const double exact = closed_form(20.0);
    const struct {
        const char *method;
        double order;
    } cases[] = {{"dp45", 5.0}, {"dop853", 8.0}, {"rk4", 4.0}};
    for (int i = 0; i < 3; i++) {
        double e[2];
        for (int k = 0; k < 2; k++) {
            const double h = k ? 0.25 : 0.5;
            char args[256];
            if (strcmp(cases[i].method, "rk4") == 0)
                snprintf(args, sizeof args, "--method rk4 --step %g", h / 2);
            else
                snprintf(args, sizeof args,
                         "--method %s --max-step %g --initial-step %g --rtol 1 --atol 1",
                         cases[i].method, h, h);
            e[k] = fabs(final_value("lag1.ode", args) - exact);
        }
        const double order = log2(e[0] / e[1]);
        print_message("%s: errors %.3g, %.3g: order %.2f\n", cases[i].method, e[0], e[1], order);
        CHECK(fabs(order - cases[i].order) < 0.6, "%s: errors %g %g, order %g", cases[i].method,
              e[0], e[1], order);
    }
    /* dp45 at h = 0.3 (0.1 before each whole number when tracked) */
    for (int k = 0; k < 2; k++) {
        const double h = k ? 0.15 : 0.3;
        char args[256];
        snprintf(args, sizeof args, "--method dp45 --max-step %g --initial-step %g --rtol 1 "
                                    "--atol 1",
                 h, h);
        const double tracked = fabs(final_value("lag1.ode", args) - exact);
        const double blind = fabs(final_value("lag1u.ode", args) - exact);
        print_message("dp45 h = %g: error %.3g tracked, %.3g not\n", h, tracked, blind);
        CHECK(tracked * 100 < blind, "h = %g: tracked %g, not %g", h, tracked, blind);
    }
    /* rk4 at steps 0.3, 0.15, 0.075 that do not divide the lag: a partial step onto each
     * breaking point between grid points keeps the order 4 (stepping over them gave errors
     * 1.2e-6, 1.5e-8, 1.0e-8 at t = 20, orders 6.3 and 0.5) and y(2) = -1/2 exact (it is a
     * polynomial of degree 2 on [1, 2]; stepping over 1 gave -0.500025) */
    double e[3];
    for (int k = 0; k < 3; k++) {
        char args[128];
        snprintf(args, sizeof args, "--method rk4 --step %g", 0.3 / (1 << k));
        e[k] = fabs(final_value("lag1.ode", args) - exact);
    }
    print_message("rk4 h = 0.3, 0.15, 0.075: errors %.3g %.3g %.3g, orders %.2f %.2f\n", e[0],
                  e[1], e[2], log2(e[0] / e[1]), log2(e[1] / e[2]));
    for (int k = 0; k < 2; k++)
        CHECK(fabs(log2(e[k] / e[k + 1]) - 4.0) < 0.3, "rk4 errors %g %g %g", e[0], e[1], e[2]);
    const double y2 = final_value("lag1.ode", "--method rk4 --step 0.3 --tspan 0:2");
    CHECK(fabs(y2 + 0.5) < 1e-14, "rk4 h = 0.3: y(2) = %.17g", y2);
}

/* Mackey-Glass (examples/models/mackey_glass.ode: beta 0.2, gamma 0.1, n 10, tau 17) by
 * dynkit's default run (dop853, rtol 1e-10) and by the independent method of steps: the
 * same values every 50 days up to 300 (before the chaos amplifies the difference). */
static void test_mackey_glass_independent(void **state)
{
    (void)state;
    if (access("/usr/bin/python3", X_OK) != 0) {
        print_message("python3 not found: Mackey-Glass comparison skipped\n");
        skip();
    }
    int status;
    char *ref = cli_capture("/usr/bin/python3 " DYNKIT_SOURCE_DIR
                            "/tests/delay/mackey_glass_ref.py 3400 300 50",
                            &status);
    CHECK(status == 0 && ref, "reference failed");
    cli_result r = cli("run " DYNKIT_SOURCE_DIR "/examples/models/mackey_glass.ode "
                       "--times 0,50,100,150,200,250,300");
    CHECK(r.status == 0, "%s", r.err);
    const char *pr = ref, *pd = strchr(r.out, '\n');
    int rows = 0;
    double worst = 0.0;
    while (*pr && pd && pd[1]) {
        char *end;
        const double tr = strtod(pr, &end), xr = strtod(end, &end);
        pr = end + (*end == '\n');
        const double td = strtod(pd + 1, &end), xd = strtod(end + 1, &end);
        pd = strchr(end, '\n');
        CHECK(tr == td, "times %g %g", tr, td);
        worst = fmax(worst, fabs(xr - xd));
        rows++;
    }
    print_message("Mackey-Glass: %d times, largest difference %.3g\n", rows, worst);
    CHECK(rows == 7 && worst < 1e-8, "%d rows, difference %g", rows, worst);
    free(ref);
    cli_free(&r);
}

/* A lag that depends on the state: y' = cos t - y(t - y/4) + sin(t - y/4) + 2 with the
 * history 2 + sin t has the solution y = 2 + sin t (lags from 1/4 to 3/4). */
static void test_state_dependent_lag(void **state)
{
    (void)state;
    assert_int_equal(cli_write_file("sd.ode", "y'=cos(t)-delay(y,y/4)+sin(t-y/4)+2\n"
                                              "y(0)=2+sin(t)\n"
                                              "@ delay=1, total=20, dt=0.5\n"),
                     0);
    const double exact = 2.0 + sin(20.0);
    const double e853 = fabs(final_value("sd.ode", "--method dop853 --rtol 1e-12 --atol 1e-12") -
                             exact);
    const double e45 = fabs(final_value("sd.ode", "--method dp45 --rtol 1e-12 --atol 1e-12") -
                            exact);
    CHECK(e853 < 1e-12 && e45 < 5e-12, "errors dop853 %g, dp45 %g", e853, e45);
    const double r1 = fabs(final_value("sd.ode", "--method rk4 --step 0.05") - exact);
    const double r2 = fabs(final_value("sd.ode", "--method rk4 --step 0.025") - exact);
    print_message("state-dependent lag: dop853 %.3g, dp45 %.3g; rk4 %.3g, %.3g (order %.2f)\n",
                  e853, e45, r1, r2, log2(r1 / r2));
    CHECK(fabs(log2(r1 / r2) - 4.0) < 0.5, "rk4 errors %g %g", r1, r2);
}

/* The history as XPPAUT 6.11 reads it (measured with xppaut -silent): x(0)= gives it (a
 * formula of t, or a number), `init` gives the initial value only, and a state whose value
 * only `init` gives is 0 before t0 (with a warning). x' = x(t - 1) from 0.5: with the
 * history 0, x = 0.5 on [0, 1] and 0.5 + (t - 1)/2 after; with x(0)=1-t and init x=.5,
 * x(1) = 2 and x(2) = 10/3. The jump at t0 is read from the left by the step that ends at
 * t0 + 1 and from the right by the next one, so dp45 has these polynomials exactly. */
static void test_history_as_xppaut(void **state)
{
    (void)state;
    assert_int_equal(cli_write_file("h0.ode", "x'=delay(x,1)\ninit x=0.5\n"
                                              "@ delay=2, total=2, dt=0.25\n"),
                     0);
    assert_int_equal(cli_write_file("h1.ode", "x'=delay(x,1)\nx(0)=1-t\ninit x=0.5\n"
                                              "@ delay=2, total=2, dt=0.25\n"),
                     0);
    cli_result r = cli("run %s --method dp45 --times 1,1.5,2", cli_path("h0.ode"));
    CHECK(r.status == 0 && strstr(r.out, "1,0.5\n1.5,0.75\n2,0.99999999999999") &&
              strstr(r.err, "warning: ") && strstr(r.err, "before t0 it is 0, as in XPPAUT"),
          "%s %s", r.out, r.err);
    cli_free(&r);
    const double x1 = final_value("h1.ode", "--method dp45 --tspan 0:1");
    const double x2 = final_value("h1.ode", "--method dp45");
    CHECK(fabs(x1 - 2.0) < 1e-14 && fabs(x2 - 10.0 / 3.0) < 1e-14, "x(1) = %.17g, x(2) = %.17g",
          x1, x2);
    /* rk4 on its grid (the breaking point 1 is a grid point): the same */
    const double r2 = final_value("h1.ode", "--method rk4");
    CHECK(fabs(r2 - 10.0 / 3.0) < 1e-14, "rk4: x(2) = %.17g", r2);
}

/* Without `@ delay=` XPPAUT 6.11 reads delay(y, 1) as the current y (measured with xppaut
 * -silent: y' = -delay(y,1), y(0)=1 gives y(2) = e^-2 = 0.1353353); dynkit keeps the lag,
 * so y' = -y(t-1) with history 1 gives the closed form y(2) = -1/2, and says once that
 * XPPAUT would differ. With `@ delay=2` the same file runs without that warning. */
static void test_no_max_delay_keeps_the_lag(void **state)
{
    (void)state;
    assert_int_equal(cli_write_file("nomax.ode", "y'=-delay(y,1)\ny(0)=1\ninit y=1\n"
                                                 "@ total=2, dt=0.25\n"),
                     0);
    assert_int_equal(cli_write_file("withmax.ode", "y'=-delay(y,1)\ny(0)=1\ninit y=1\n"
                                                   "@ delay=2, total=2, dt=0.25\n"),
                     0);
    cli_result r = cli("run %s --method dp45 --times 2", cli_path("nomax.ode"));
    const char *w = strstr(r.err, "sets no '@ delay='");
    const char *row = strstr(r.out, "\n2,");
    CHECK(r.status == 0 && row && fabs(strtod(row + 3, NULL) + 0.5) < 1e-14 && w &&
              !strstr(w + 1, "sets no '@ delay='"),
          "%s %s", r.out, r.err);
    cli_free(&r);
    r = cli("run %s --method dp45 --times 2", cli_path("withmax.ode"));
    row = strstr(r.out, "\n2,");
    CHECK(r.status == 0 && row && fabs(strtod(row + 3, NULL) + 0.5) < 1e-14 &&
              !strstr(r.err, "@ delay="),
          "%s %s", r.out, r.err);
    cli_free(&r);
    /* `@ delay=0` is XPPAUT's default written out: the same run, the warning names it; a
     * state-dependent lag that turns negative is named with its value, not as NaN */
    assert_int_equal(cli_write_file("zeromax.ode", "y'=-delay(y,1)\ny(0)=1\ninit y=1\n"
                                                   "@ delay=0, total=2, dt=0.25\n"),
                     0);
    r = cli("run %s --method dp45 --times 2", cli_path("zeromax.ode"));
    row = strstr(r.out, "\n2,");
    CHECK(r.status == 0 && row && fabs(strtod(row + 3, NULL) + 0.5) < 1e-14 &&
              strstr(r.err, "sets '@ delay=0', XPPAUT's default, which keeps no history"),
          "%s %s", r.out, r.err);
    cli_free(&r);
    assert_int_equal(cli_write_file("neglag.ode", "x'=-delay(x,x-5)\nx(0)=1\ninit x=1\n"
                                                  "@ delay=10, total=2\n"),
                     0);
    r = cli("run %s --final", cli_path("neglag.ode"));
    CHECK(r.status != 0 && strstr(r.err, "asks for a negative lag -4") && !strstr(r.err, "nan"),
          "%s", r.err);
    cli_free(&r);
}

/* Whether the line printed matches the line shown: the same text, numbers within 1e-9
 * relative. */
static int same_line(const char *got, size_t gn, const char *want, size_t wn)
{
    size_t i = 0, j = 0;
    while (i < gn && j < wn) {
        char *ge, *we;
        if ((isdigit((unsigned char)want[j]) || want[j] == '-') &&
            (isdigit((unsigned char)got[i]) || got[i] == '-')) {
            const double a = strtod(got + i, &ge), b = strtod(want + j, &we);
            if (ge > got + i && we > want + j) {
                if (fabs(a - b) > 1e-9 * fmax(fabs(b), 1e-300))
                    return 0;
                i = (size_t)(ge - got);
                j = (size_t)(we - want);
                continue;
            }
        }
        if (got[i++] != want[j++])
            return 0;
    }
    return i == gn && j == wn;
}

/* The commands of "Delay equations" in docs/model-files.md print what it shows (standard
 * error, then standard output, as a terminal shows them). */
static void test_doc_commands(void **state)
{
    (void)state;
    char *doc = cli_read_file(DYNKIT_SOURCE_DIR "/docs/model-files.md", NULL);
    const char *sec = strstr(doc, "### Delay equations");
    CHECK(sec != NULL, "no section");
    const char *blk = strstr(sec, "```console\n"), *end = blk ? strstr(blk + 11, "```") : NULL;
    CHECK(blk && end, "no console block");
    const char *p = blk + 11;
    int commands = 0;
    while (p < end) {
        CHECK(strncmp(p, "$ dynkit ", 9) == 0, "not a command: %.40s", p);
        const char *eol = strchr(p, '\n');
        char args[512];
        snprintf(args, sizeof args, "%.*s", (int)(eol - p - 9), p + 9);
        char *comment = strstr(args, " #"); /* '# exit 2': the status the doc shows */
        if (comment)
            *comment = '\0';
        cli_result r = cli_in_tmpdir("%s", args);
        /* the lines shown, up to the next command */
        const char *lines = eol + 1;
        const char *next = lines;
        while (next < end && strncmp(next, "$ ", 2) != 0)
            next = strchr(next, '\n') + 1;
        size_t elen = strlen(r.err), olen = strlen(r.out);
        char *shown = malloc(elen + olen + 1);
        memcpy(shown, r.err, elen);
        memcpy(shown + elen, r.out, olen + 1);
        const char *g = shown;
        for (const char *w = lines; w < next;) {
            const char *we = strchr(w, '\n'), *ge = strchr(g, '\n');
            CHECK(ge && same_line(g, (size_t)(ge - g), w, (size_t)(we - w)),
                  "%s: printed\n%s\nshown\n%.*s", args, shown, (int)(next - lines), lines);
            g = ge + 1;
            w = we + 1;
        }
        CHECK(*g == '\0', "%s printed more: %s", args, g);
        CHECK(r.status == (strstr(lines, "error:") && strstr(lines, "error:") < next ? 2 : 0),
              "%s: exit %d", args, r.status);
        free(shown);
        cli_free(&r);
        commands++;
        p = next;
    }
    assert_int_equal(commands, 3);
    free(doc);
}

/* What is refused, and where. */
static void test_refusals(void **state)
{
    (void)state;
    assert_int_equal(cli_write_file("far.ode", "y'=-delay(y,1+t)\ny(0)=1\n@ delay=3, total=5\n"),
                     0);
    cli_result r = cli("run %s --final", cli_path("far.ode"));
    CHECK(r.status == 1 && strstr(r.err, "delay(y, ...) at t = 2") &&
              strstr(r.err, "longer than the maximal delay 3"),
          "%d %s", r.status, r.err);
    cli_free(&r);
    r = cli("run " DYNKIT_SOURCE_DIR "/examples/models/mackey_glass.ode --set tau=20 --final");
    CHECK(r.status == 2 && strstr(r.err, "delay(x, ...) on line 11: the lag is 20 with these "
                                         "parameters") && r.out[0] == '\0',
          "%d %s", r.status, r.err);
    cli_free(&r);
    assert_int_equal(cli_write_file("notstate.ode", "par a=1\ny'=-delay(a,1)\n"), 0);
    r = cli("run %s --final", cli_path("notstate.ode"));
    CHECK(r.status == 2 && strstr(r.err, "notstate.ode:2:5: error: delay(a, ...): 'a' is a "
                                         "parameter"),
          "%d %s", r.status, r.err);
    cli_free(&r);
    assert_int_equal(cli_write_file("inpar.ode", "par a=1\n!b=delay(y,1)\ny'=-b\n"), 0);
    r = cli("run %s --final", cli_path("inpar.ode"));
    CHECK(r.status == 2 && strstr(r.err, "cannot use delay(y, ...)"), "%d %s", r.status, r.err);
    cli_free(&r);
    if (cli_has_cvode()) {
        r = cli("run " DYNKIT_SOURCE_DIR "/examples/models/mackey_glass.ode --method cvode");
        CHECK(r.status == 2 && strstr(r.err, "cvode backend cannot read"), "%d %s", r.status,
              r.err);
        cli_free(&r);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_closed_form_values),
        cmocka_unit_test(test_library_history),
        cmocka_unit_test(test_breaking_points),
        cmocka_unit_test(test_info_delays),
        cmocka_unit_test(test_file_closed_form),
        cmocka_unit_test(test_file_orders),
        cmocka_unit_test(test_mackey_glass_independent),
        cmocka_unit_test(test_state_dependent_lag),
        cmocka_unit_test(test_history_as_xppaut),
        cmocka_unit_test(test_no_max_delay_keeps_the_lag),
        cmocka_unit_test(test_doc_commands),
        cmocka_unit_test(test_refusals),
    };
    return cmocka_run_group_tests(tests, setup_all, cli_remove_tmpdir);
}
