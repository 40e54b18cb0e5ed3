/* SPDX-License-Identifier: BSD-3-Clause */
/* The sweep library (dynkit/sweep.h, src/sweep): reductions against exact values (a ramp
 * y = t: final, max, min, mean by the trapezoidal rule, argmax, argmin, an event's time and
 * count), the pendulum's quarter period over amplitudes against K(k)/w (K by the
 * arithmetic-geometric mean), the same bits for 1, 2 and 3 threads, failed runs as rows with
 * their status (a blow-up, the step limit, prepare refusing the parameters), skipped runs
 * left alone, cancellation, terminal events, the names of reductions and their errors. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "dynkit/dynkit.h"
#include "dynkit/sweep.h"
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

/* ---- a test model: y' = a (so y = y0 + a t), output z = 2 y, event y = 1/2;
 * a <= 0 is refused by prepare; a = 1e300 blows up through y' = a y^2 when b = 1 ---- */
typedef struct ramp_par {
    double a, b;
} ramp_par;

static int ramp_rhs(double t, const double *y, double *dydt, void *par)
{
    const ramp_par *p = par;
    (void)t;
    dydt[0] = p->b > 0 ? p->a * y[0] * y[0] : p->a;
    return 0;
}

/* 0: z = 2 y; 1: z is nan once y > 1/2; 2: the outputs fail (status 3) once y > 1/2 */
static int ramp_outputs_mode;

static int ramp_outputs(double t, const double *y, const void *par, double *out)
{
    (void)t;
    (void)par;
    if (ramp_outputs_mode == 2 && y[0] > 0.5)
        return 3;
    out[0] = ramp_outputs_mode == 1 && y[0] > 0.5 ? NAN : 2.0 * y[0];
    return 0;
}

static int ramp_prepare(void *par, char *err, size_t errlen)
{
    return dyn_check_positive("a", ((ramp_par *)par)->a, err, errlen);
}

static double ramp_half(double t, const double *y, void *par)
{
    (void)t;
    (void)par;
    return y[0] - 0.5;
}

static const dyn_var ramp_states[] = {{"y", "1", "the ramp"}};
static const dyn_var ramp_outs[] = {{"z", "1", "twice the ramp"}};
static const double ramp_y0[] = {0.0};
static const dyn_param ramp_params[] = {{"a", "1/s", "slope", offsetof(ramp_par, a), 1.0},
                                        {"b", "1", "1: blow up", offsetof(ramp_par, b), 0.0}};
static const dyn_event ramp_events[] = {{"half", "y = 1/2", ramp_half, 0, 0, NULL}};
static const dyn_model ramp = {
    .name = "ramp",
    .title = "y' = a",
    .n_states = 1,
    .states = ramp_states,
    .y0 = ramp_y0,
    .n_params = 2,
    .params = ramp_params,
    .par_size = sizeof(ramp_par),
    .n_outputs = 1,
    .outputs = ramp_outs,
    .rhs = ramp_rhs,
    .compute_outputs = ramp_outputs,
    .prepare = ramp_prepare,
    .t0 = 0.0,
    .t1 = 1.0,
    .step = 0.125,
    .method = "rk4",
    .n_events = 1,
    .events = ramp_events,
};

static void test_reduce_ramp(void **state)
{
    (void)state;
    dyn_reduce red[16];
    int nr = 0;
    char err[256];
    assert_int_equal(dyn_reduce_parse(&ramp, "final,max:y,min:z,mean:y,argmax:y,argmin:y,"
                                             "event:half,count:half,final:z,mean:z",
                                      red, 16, &nr, err, sizeof err),
                     0);
    assert_int_equal(nr, 10);
    dyn_sweep_var var;
    assert_int_equal(dyn_sweep_var_find(&ramp, "a", &var, err, sizeof err), 0);
    const double values[] = {1.0, 2.0, 0.25};
    dyn_sweep s = {0};
    s.model = &ramp;
    s.n_vars = 1;
    s.vars = &var;
    s.n_runs = 3;
    s.values = values;
    s.method = dyn_method_find("euler"); /* exact on a line with a step of 1/8 */
    s.t0 = 0.0;
    s.t1 = 1.0;
    s.step = 0.125;
    s.n_reduce = nr;
    s.reduce = red;
    double res[3 * 10];
    int st[3];
    assert_int_equal(dyn_sweep_run(&s, res, st, err, sizeof err), DYN_OK);
    for (int i = 0; i < 3; i++) {
        const double a = values[i], *r = res + i * 10;
        assert_int_equal(st[i], DYN_OK);
        assert_true(r[0] == a);             /* final:y */
        assert_true(r[1] == a);             /* max:y */
        assert_true(r[2] == 0.0);           /* min:z */
        assert_true(r[3] == 0.5 * a);       /* mean:y, trapezoidal: exact for a line */
        assert_true(r[4] == 1.0);           /* argmax:y */
        assert_true(r[5] == 0.0);           /* argmin:y */
        if (a >= 0.5)
            assert_true(fabs(r[6] - 0.5 / a) < 1e-14); /* event:half */
        else
            assert_true(isnan(r[6]));
        assert_true(r[7] == (a >= 0.5 ? 1.0 : 0.0)); /* count:half */
        assert_true(r[8] == 2.0 * a);                /* final:z */
        assert_true(r[9] == a);                      /* mean:z */
    }
    /* a nan sample makes min (max, argmin, argmax) nan from there on, as it makes final
     * and mean (z is nan once y = a t > 1/2) */
    ramp_outputs_mode = 1;
    assert_int_equal(dyn_sweep_run(&s, res, st, err, sizeof err), DYN_OK);
    for (int i = 0; i < 3; i++) {
        const double a = values[i], *r = res + i * 10;
        assert_int_equal(st[i], DYN_OK);
        if (a > 0.5) {
            assert_true(isnan(r[2]) && isnan(r[8]) && isnan(r[9])); /* min, final, mean of z */
            assert_true(r[0] == a && r[1] == a);                   /* the states' untouched */
        } else {
            assert_true(r[2] == 0.0 && r[8] == 2.0 * a);
        }
    }
    /* outputs that fail: every run that meets the failure has the status of a failed
     * right-hand side (not of the model's bound), whichever reduction needed them */
    ramp_outputs_mode = 2;
    assert_int_equal(dyn_sweep_run(&s, res, st, err, sizeof err), DYN_OK);
    for (int i = 0; i < 3; i++)
        assert_int_equal(st[i], values[i] > 0.5 ? DYN_ERR_RHS : DYN_OK);
    ramp_outputs_mode = 0;
    /* the same with an adaptive method, samples on the grid of 0.125 */
    s.method = dyn_method_find("dp45");
    assert_int_equal(dyn_sweep_run(&s, res, st, err, sizeof err), DYN_OK);
    for (int i = 0; i < 3; i++) {
        assert_int_equal(st[i], DYN_OK);
        assert_true(fabs(res[i * 10 + 3] - 0.5 * values[i]) < 1e-14);
        assert_true(res[i * 10 + 4] == 1.0);
    }
}

static void test_names(void **state)
{
    (void)state;
    dyn_reduce red[4];
    int nr;
    char err[256], buf[64];
    const dyn_model *pend = dyn_model_find("pendulum");
    assert_int_equal(dyn_reduce_parse(pend, "final", red, 4, &nr, err, sizeof err), 0);
    assert_int_equal(nr, 2);
    assert_string_equal(dyn_reduce_name(pend, &red[1], buf, sizeof buf), "final_dphi");
    assert_int_equal(dyn_reduce_parse(pend, "max:energy,event:turn", red, 4, &nr, err, sizeof err),
                     0);
    assert_string_equal(dyn_reduce_name(pend, &red[0], buf, sizeof buf), "max_energy");
    assert_int_equal(red[1].source, DYN_SOURCE_EVENT);
    assert_int_equal(dyn_reduce_parse(pend, "max:nothing", red, 4, &nr, err, sizeof err), -1);
    assert_non_null(strstr(err, "states: phi, dphi; outputs: energy, height"));
    assert_int_equal(dyn_reduce_parse(pend, "event:phi", red, 4, &nr, err, sizeof err), -1);
    assert_non_null(strstr(err, "events: turn, bottom"));
    assert_int_equal(dyn_reduce_parse(pend, "median:phi", red, 4, &nr, err, sizeof err), -1);
    assert_non_null(strstr(err, "unknown reduction 'median'"));
    assert_int_equal(dyn_reduce_parse(pend, "max", red, 4, &nr, err, sizeof err), -1);
    assert_int_equal(dyn_reduce_parse(pend, "final,final,final", red, 4, &nr, err, sizeof err),
                     -1);
    dyn_sweep_var v;
    assert_int_equal(dyn_sweep_var_find(pend, "dphi", &v, err, sizeof err), 0);
    assert_int_equal(v.kind, DYN_SWEEP_STATE);
    assert_string_equal(dyn_sweep_var_name(pend, &v), "dphi");
    assert_int_equal(dyn_sweep_var_find(pend, "mass", &v, err, sizeof err), -1);
    assert_non_null(strstr(err, "parameters: m, l, g; states: phi, dphi"));
}

/* The pendulum from phi = 0 with dphi0 in 0.1..1.9: the first turn at K(k)/w,
 * k = dphi0 / (2 w) (energy: sin(phi_max/2) = dphi0 / (2w)). */
static void pendulum_sweep(int threads, int stop, double *res, int *st, long n)
{
    const dyn_model *pend = dyn_model_find("pendulum");
    dyn_sweep_var var = {DYN_SWEEP_STATE, 1};
    double *values = malloc((size_t)n * sizeof *values);
    for (long i = 0; i < n; i++)
        values[i] = 0.1 + (double)i * (1.9 - 0.1) / (double)(n - 1);
    dyn_reduce red[3];
    int nr;
    char err[256];
    assert_int_equal(dyn_reduce_parse(pend, "event:turn,count:bottom,max:height", red, 3, &nr,
                                      err, sizeof err),
                     0);
    const int turn = 0;
    dyn_sweep s = {0};
    s.model = pend;
    s.n_vars = 1;
    s.vars = &var;
    s.n_runs = n;
    s.values = values;
    s.method = dyn_method_find("dop853");
    s.rtol = s.atol = 1e-12;
    s.t0 = 0.0;
    s.t1 = 5.0;
    s.step = 0.01;
    s.n_reduce = nr;
    s.reduce = red;
    s.n_stop = stop;
    s.stop = &turn;
    s.threads = threads;
    assert_int_equal(dyn_sweep_run(&s, res, st, err, sizeof err), DYN_OK);
    free(values);
}

static void test_pendulum_period(void **state)
{
    (void)state;
    enum { N = 50 };
    double res[N * 3];
    int st[N];
    pendulum_sweep(2, 0, res, st, N);
    const double w = 1.0; /* g = l = 9.81 */
    double worst = 0.0;
    for (int i = 0; i < N; i++) {
        const double dphi0 = 0.1 + (double)i * 1.8 / (N - 1);
        assert_int_equal(st[i], DYN_OK);
        const double exact = ellip_k(dphi0 / (2.0 * w)) / w;
        worst = fmax(worst, fabs(res[i * 3] - exact));
        /* the bottom again every half period 2K/w (not at the start) */
        assert_true(res[i * 3 + 1] == floor(5.0 / (2.0 * exact)));
    }
    assert_true(worst < 1e-10);
    /* stopping at the turn: the same turn times, bit for bit; max:height up to there */
    double res2[N * 3];
    int st2[N];
    pendulum_sweep(1, 1, res2, st2, N);
    for (int i = 0; i < N; i++) {
        assert_true(same_bits(res[i * 3], res2[i * 3]));
        assert_true(res2[i * 3 + 1] == 0.0);
    }
}

static void test_threads_same_bits(void **state)
{
    (void)state;
    enum { N = 64 };
    double a[N * 3], b[N * 3], c[N * 3];
    int sa[N], sb[N], sc[N];
    pendulum_sweep(1, 0, a, sa, N);
    pendulum_sweep(2, 0, b, sb, N);
    pendulum_sweep(3, 0, c, sc, N);
    assert_memory_equal(a, b, sizeof a);
    assert_memory_equal(a, c, sizeof a);
    assert_memory_equal(sa, sb, sizeof sa);
    assert_memory_equal(sa, sc, sizeof sa);
    assert_true(dyn_sweep_threads(3) >= 1);
}

static void test_failures(void **state)
{
    (void)state;
    char err[256];
    /* columns a, b: run 1 refused by prepare (a < 0), run 2 blows up (b = 1: y' = a y^2) */
    dyn_sweep_var v2[2] = {{DYN_SWEEP_PARAM, 0}, {DYN_SWEEP_PARAM, 1}};
    const double values[] = {1.0, 0.0, -1.0, 0.0, 1.0, 1.0, 2.0, 0.0};
    dyn_reduce red[2];
    int nr;
    assert_int_equal(dyn_reduce_parse(&ramp, "final,max:z", red, 2, &nr, err, sizeof err), 0);
    const double y0[] = {2.0}; /* y' = y^2 from 2: infinite at t = 1/2 */
    dyn_sweep s = {0};
    s.model = &ramp;
    s.y0 = y0;
    s.n_vars = 2;
    s.vars = v2;
    s.n_runs = 4;
    s.values = values;
    s.method = dyn_method_find("rk4");
    s.t0 = 0.0;
    s.t1 = 1.0;
    s.step = 0.001;
    s.n_reduce = nr;
    s.reduce = red;
    double res[8];
    int st[4];
    for (int threads = 1; threads <= 2; threads++) {
        s.threads = threads;
        assert_int_equal(dyn_sweep_run(&s, res, st, err, sizeof err), DYN_OK);
        assert_int_equal(st[0], DYN_OK);
        assert_true(fabs(res[0] - 3.0) < 1e-12 && fabs(res[1] - 6.0) < 1e-12);
        assert_int_equal(st[1], DYN_ERR_ARG); /* a = -1 refused */
        assert_true(isnan(res[2]) && isnan(res[3]));
        assert_int_equal(st[2], DYN_ERR_NONFINITE);
        assert_true(isnan(res[4]) && isnan(res[5]));
        assert_int_equal(st[3], DYN_OK);
        assert_true(fabs(res[6] - 4.0) < 1e-12);
    }
    /* an adaptive method: the blow-up is a step-size failure or a non-finite state; the
     * step limit */
    s.method = dyn_method_find("dp45");
    s.step = 0;
    s.max_steps = 20;
    assert_int_equal(dyn_sweep_run(&s, res, st, err, sizeof err), DYN_OK);
    assert_int_equal(st[0], DYN_OK);
    assert_true(st[2] == DYN_ERR_MAX_STEPS || st[2] == DYN_ERR_STEP_SIZE ||
                st[2] == DYN_ERR_NONFINITE);
    /* skipped runs keep their rows and statuses */
    const unsigned char skip[] = {1, 0, 1, 0};
    res[0] = 42.0;
    st[0] = 7;
    st[2] = 9;
    s.skip = skip;
    assert_int_equal(dyn_sweep_run(&s, res, st, err, sizeof err), DYN_OK);
    assert_true(res[0] == 42.0);
    assert_int_equal(st[0], 7);
    assert_int_equal(st[2], 9);
    assert_int_equal(st[3], DYN_OK);
    /* bad sweeps */
    s.skip = NULL;
    s.t1 = 0.0;
    assert_int_equal(dyn_sweep_run(&s, res, st, err, sizeof err), DYN_ERR_ARG);
    assert_non_null(strstr(err, "t1 > t0"));
    s.t1 = 1.0;
    s.method = dyn_method_find("rk4");
    s.step = 0.0;
    assert_int_equal(dyn_sweep_run(&s, res, st, err, sizeof err), DYN_ERR_ARG);
    assert_non_null(strstr(err, "needs a step"));
}

typedef struct cancel_ctx {
    long after;
} cancel_ctx;

static int cancel_after(long run, int status, long done, long total, void *ctx)
{
    (void)run;
    (void)status;
    (void)total;
    return done >= ((cancel_ctx *)ctx)->after;
}

static void test_cancel(void **state)
{
    (void)state;
    enum { N = 40 };
    dyn_sweep_var var = {DYN_SWEEP_PARAM, 0};
    double values[N];
    for (int i = 0; i < N; i++)
        values[i] = 1.0 + i;
    dyn_reduce red = {DYN_REDUCE_FINAL, DYN_SOURCE_STATE, 0};
    cancel_ctx cc = {5};
    dyn_sweep s = {0};
    s.model = &ramp;
    s.n_vars = 1;
    s.vars = &var;
    s.n_runs = N;
    s.values = values;
    s.method = dyn_method_find("euler");
    s.t0 = 0.0;
    s.t1 = 1.0;
    s.step = 1e-4;
    s.n_reduce = 1;
    s.reduce = &red;
    s.threads = 2;
    s.progress = cancel_after;
    s.progress_ctx = &cc;
    double res[N];
    int st[N];
    char err[256];
    assert_int_equal(dyn_sweep_run(&s, res, st, err, sizeof err), DYN_CANCELLED);
    int finished = 0;
    for (int i = 0; i < N; i++) {
        if (st[i] == DYN_OK) {
            finished++;
            assert_true(fabs(res[i] - values[i]) < 1e-9);
        } else {
            assert_int_equal(st[i], DYN_SWEEP_NOT_RUN);
            assert_true(isnan(res[i]));
        }
    }
    assert_true(finished >= 5 && finished < N);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_reduce_ramp),     cmocka_unit_test(test_names),
        cmocka_unit_test(test_pendulum_period), cmocka_unit_test(test_threads_same_bits),
        cmocka_unit_test(test_failures),        cmocka_unit_test(test_cancel),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
