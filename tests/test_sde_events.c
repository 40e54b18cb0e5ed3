/* SPDX-License-Identifier: BSD-3-Clause */
/* Events with noise (dyn_sde_opts.events, src/ode/sde.c):
 * - a noisy perfect integrate-and-fire neuron v' = mu + sigma dW/dt, reset from vth to vr:
 *   its interspike intervals are the first passage times of Brownian motion with drift,
 *   inverse Gaussian with mean (vth - vr)/mu and variance sigma^2 (vth - vr)/mu^3. Checked
 *   with Euler–Maruyama and adaptive rkmil over one fixed seed, within 5 standard errors
 *   plus the discrete scheme's bias (a crossing between two steps that comes back before
 *   the second is missed: the mean passage time is late by about 0.5826 sigma sqrt(h)/mu,
 *   Siegmund's correction for a random walk's overshoot, "Corrected diffusion
 *   approximations in certain random walk problems", Adv. Appl. Prob. 11 (1979));
 * - sigma = 0: the deterministic run. Two neurons whose resets kick each other (cascades,
 *   XPPAUT's rules) with constant drifts, where Euler's steps and the straight line between
 *   them are exact: every method for noise gives dyn_solve's spike times and final state
 *   (rk4, the same model without noise) to 1e-9;
 * - the seed fixes the run: the same spike times twice, other ones with another seed. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "dynkit/sde.h"
#include "dynkit/solve.h"
#include "test_util.h"

#define MAX_SPIKES 40000

typedef struct spikes {
    long count, cascades;
    double t[MAX_SPIKES];
    int index[MAX_SPIKES];
} spikes;

static int on_spike(int index, double t, const double *y, int direction, void *ctx)
{
    (void)y;
    (void)direction;
    spikes *s = ctx;
    if (s->count < MAX_SPIKES) {
        s->t[s->count] = t;
        s->index[s->count] = index;
    }
    s->count++;
    return 0;
}

/* ---- one noisy perfect integrate-and-fire neuron ---- */

typedef struct if_par {
    double mu, sigma, vth, vr, w;
} if_par;

static int if_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    (void)y;
    const if_par *p = par;
    dydt[0] = p->mu + p->sigma * p->w;
    return 0;
}

static double if_g(double t, const double *y, void *par)
{
    (void)t;
    return y[0] - ((const if_par *)par)->vth;
}

static int if_reset(double t, double *y, void *par)
{
    (void)t;
    y[0] = ((const if_par *)par)->vr;
    return 0;
}

static const int wiener_kind[2] = {DYN_NOISE_WIENER, DYN_NOISE_WIENER};

/* Spikes of the neuron from v = vr over [0, T]. */
static void if_run(dyn_sde_method method, int fixed, double h, double T, if_par *par,
                   uint64_t seed, spikes *s)
{
    static const dyn_event ev[1] = {{"spike", "v reaches vth", if_g, 1, 0, if_reset}};
    const size_t size = dyn_sde_work_size(1, 1, 1);
    double *work = malloc(size * sizeof *work);
    assert_non_null(work);
    dyn_sde sde = {{if_rhs, 1, par}, 1, wiener_kind, &par->w, DYN_NOISE_ADDITIVE};
    dyn_sde_opts o = {0};
    o.h = h;
    o.fixed = fixed;
    o.rtol = 1e-3;
    o.atol = 1e-3;
    o.max_step = h;
    o.seed = seed;
    o.events = ev;
    o.n_events = 1;
    o.on_event = on_spike;
    o.event_ctx = s;
    memset(s, 0, sizeof *s);
    const double y0 = par->vr;
    double y;
    dyn_result res;
    const int rc = dyn_sde_solve(method, &sde, 0.0, T, &y0, &y, work, &o, &res);
    CHECK(rc == DYN_OK, "%s", res.message);
    assert_int_equal(res.events, s->count);
    free(work);
}

/* Mean and variance of the intervals between spikes (the first from t = 0, v = vr). */
static void isi_moments(const spikes *s, double *mean, double *var, long *n)
{
    const long k = s->count < MAX_SPIKES ? s->count : MAX_SPIKES;
    double sum = 0, sum2 = 0;
    for (long i = 0; i < k; i++) {
        const double d = s->t[i] - (i ? s->t[i - 1] : 0.0);
        sum += d;
        sum2 += d * d;
    }
    *n = k;
    *mean = sum / (double)k;
    *var = (sum2 - sum * sum / (double)k) / (double)(k - 1);
}

static void check_isi(const char *what, dyn_sde_method method, int fixed, double h, double T)
{
    static spikes s;
    if_par par = {1.0, 0.3, 1.0, 0.0, 0.0};
    if_run(method, fixed, h, T, &par, 11, &s);
    double mean, var;
    long n;
    isi_moments(&s, &mean, &var, &n);
    const double d = par.vth - par.vr, m = d / par.mu;
    const double v = par.sigma * par.sigma * d / (par.mu * par.mu * par.mu);
    /* inverse Gaussian: lambda = d^2/sigma^2, excess kurtosis 15 m/lambda */
    const double lambda = d * d / (par.sigma * par.sigma), kurt = 3.0 + 15.0 * m / lambda;
    const double se_m = sqrt(v / (double)n), se_v = v * sqrt((kurt - 1.0) / (double)n);
    const double bias = 0.5826 * par.sigma * sqrt(h) / par.mu;
    test_note("%s, h = %g: %ld intervals, mean %.5f (closed form %.5f, se %.5f, bias bound "
              "%.5f), variance %.5f (closed form %.5f, se %.5f)",
              what, h, n, mean, m, se_m, bias, var, v, se_v);
    CHECK(n > 0.9 * T * par.mu / d, "%ld spikes", n);
    CHECK(fabs(mean - m) <= 5 * se_m + bias, "%s: mean interval %.6f, closed form %.6f", what,
          mean, m);
    CHECK(fabs(var - v) <= 5 * se_v + 2 * bias * m, "%s: variance %.6f, closed form %.6f",
          what, var, v);
}

static void test_isi_em(void **state)
{
    (void)state;
    check_isi("Euler-Maruyama", DYN_SDE_EM, 1, 1e-3, 20000.0);
}

static void test_isi_rkmil(void **state)
{
    (void)state;
    check_isi("rkmil, adaptive steps up to", DYN_SDE_RKMIL, 0, 2e-3, 4000.0);
}

/* The seed fixes the run; another seed gives other spikes. */
static void test_seed(void **state)
{
    (void)state;
    static spikes a, b, c;
    if_par par = {1.0, 0.3, 1.0, 0.0, 0.0};
    if_run(DYN_SDE_EM, 1, 1e-2, 200.0, &par, 5, &a);
    if_run(DYN_SDE_EM, 1, 1e-2, 200.0, &par, 5, &b);
    if_run(DYN_SDE_EM, 1, 1e-2, 200.0, &par, 6, &c);
    assert_true(a.count > 100 && a.count == b.count);
    assert_memory_equal(a.t, b.t, (size_t)a.count * sizeof *a.t);
    assert_true(a.t[0] != c.t[0]);
}

/* ---- two neurons whose spikes kick each other ---- */

typedef struct pair_par {
    double mu1, mu2, kick, sigma, w[2];
} pair_par;

static int pair_rhs(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    (void)y;
    const pair_par *p = par;
    dydt[0] = p->mu1 + p->sigma * p->w[0];
    dydt[1] = p->mu2 + p->sigma * p->w[1];
    return 0;
}

static double g1(double t, const double *y, void *par)
{
    (void)t;
    (void)par;
    return y[0] - 1.0;
}

static double g2(double t, const double *y, void *par)
{
    (void)t;
    (void)par;
    return y[1] - 1.0;
}

/* a spike resets its neuron and kicks the other one up */
static int reset1(double t, double *y, void *par)
{
    (void)t;
    y[0] = 0.0;
    y[1] += ((const pair_par *)par)->kick;
    return 0;
}

static int reset2(double t, double *y, void *par)
{
    (void)t;
    y[1] = 0.0;
    y[0] += ((const pair_par *)par)->kick;
    return 0;
}

static const dyn_event pair_events[2] = {{"spike1", "", g1, 1, 0, reset1},
                                         {"spike2", "", g2, 1, 0, reset2}};

static void test_deterministic_limit(void **state)
{
    (void)state;
    static spikes ref, got;
    pair_par par = {1.0, 0.9, 0.15, 0.0, {0.0, 0.0}};
    const double y0[2] = {0.0, 0.37}, T = 30.0, h = 0.01;
    /* the deterministic run: rk4 with the same step, events on its dense output */
    double yref[2];
    {
        dyn_system sys = {pair_rhs, 2, &par};
        dyn_solve_opts o = {0};
        o.h = h;
        o.events = pair_events;
        o.n_events = 2;
        o.on_event = on_spike;
        o.event_ctx = &ref;
        const dyn_tableau *rk4 = dyn_method_find("rk4");
        double *work = malloc(dyn_solve_work_size(rk4, 2, &o) * sizeof *work);
        assert_non_null(work);
        dyn_result res;
        assert_int_equal(dyn_solve(rk4, &sys, 0.0, T, y0, yref, work, &o, &res), DYN_OK);
        ref.cascades = res.cascades;
        free(work);
    }
    CHECK(ref.count > 40 && ref.cascades > 0, "%ld spikes, %ld in cascades", ref.count,
          ref.cascades);
    static const struct {
        const char *name;
        dyn_sde_method method;
        int fixed;
    } runs[] = {{"Euler-Maruyama", DYN_SDE_EM, 1},
                {"rkmil, fixed steps", DYN_SDE_RKMIL, 1},
                {"rkmil, adaptive steps", DYN_SDE_RKMIL, 0}};
    for (size_t r = 0; r < sizeof runs / sizeof *runs; r++) {
        const size_t size = dyn_sde_work_size(2, 2, 2);
        double *work = malloc(size * sizeof *work);
        assert_non_null(work);
        dyn_sde sde = {{pair_rhs, 2, &par}, 2, wiener_kind, par.w, DYN_NOISE_ADDITIVE};
        dyn_sde_opts o = {0};
        o.h = h;
        o.fixed = runs[r].fixed;
        o.max_step = 0.1;
        o.seed = 3;
        o.events = pair_events;
        o.n_events = 2;
        o.on_event = on_spike;
        o.event_ctx = &got;
        memset(&got, 0, sizeof got);
        double y[2];
        dyn_result res;
        const int rc = dyn_sde_solve(runs[r].method, &sde, 0.0, T, y0, y, work, &o, &res);
        CHECK(rc == DYN_OK, "%s: %s", runs[r].name, res.message);
        double dt = 0.0;
        CHECK(got.count == ref.count && res.cascades == ref.cascades,
              "%s: %ld spikes (%ld in cascades), deterministic %ld (%ld)", runs[r].name,
              got.count, res.cascades, ref.count, ref.cascades);
        for (long k = 0; k < got.count; k++) {
            assert_int_equal(got.index[k], ref.index[k]);
            dt = fmax(dt, fabs(got.t[k] - ref.t[k]));
        }
        const double dy = fmax(fabs(y[0] - yref[0]), fabs(y[1] - yref[1]));
        test_note("sigma = 0, %s: %ld spikes (%ld in cascades) at dyn_solve's times to %.1e, "
                  "final state to %.1e",
                  runs[r].name, got.count, res.cascades, dt, dy);
        CHECK(dt <= 1e-9 && dy <= 1e-9, "%s: times differ by %g, final state by %g",
              runs[r].name, dt, dy);
        free(work);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_deterministic_limit),
        cmocka_unit_test(test_seed),
        cmocka_unit_test(test_isi_em),
        cmocka_unit_test(test_isi_rkmil),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
