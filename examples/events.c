/* SPDX-License-Identifier: BSD-3-Clause */
/* Example: dyn_solve with an event that resets the state: a ball dropped from 10 m bounces
 * on the floor, each impact reversing its velocity and scaling it by the restitution e
 * (XPPAUT's `global -1 y {v=-e*v}`). The bounce times are compared with the closed form
 * t_{k+1} = t_k + 2 t_1 e^k, t_1 = sqrt(2 h0 / g); a second event, terminal, ends the run
 * at t = 9 s (the span asked for is 20 s). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <dynkit/dynkit.h>

typedef struct ball {
    double g, e, h0;
} ball;

static int rhs(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    const ball *b = par;
    dydt[0] = y[1]; /* height y, velocity v */
    dydt[1] = -b->g;
    return 0;
}

static double floor_g(double t, const double *y, void *par)
{
    (void)t;
    (void)par;
    return y[0];
}

static int bounce(double t, double *y, void *par)
{
    (void)t;
    const ball *b = par;
    y[1] = -b->e * y[1];
    return 0;
}

static double nine_seconds(double t, const double *y, void *par)
{
    (void)y;
    (void)par;
    return t - 9.0;
}

typedef struct log {
    const ball *b;
    int bounces;
    double t_k, flight; /* the closed form's next bounce time and flight */
    double worst;
} log_t;

static int on_event(int index, double t, const double *y, int direction, void *ctx)
{
    (void)direction;
    log_t *l = ctx;
    if (index == 0) {
        const double err = t - l->t_k;
        l->worst = fmax(l->worst, fabs(err));
        printf("bounce %d at t = %.15f s (closed form %.15f, off %+.1e), v = %8.4f m/s\n",
               ++l->bounces, t, l->t_k, err, y[1]);
        l->t_k += l->flight;
        l->flight *= l->b->e;
    } else {
        printf("stop at t = %.15f s: y = %.6f m, v = %.6f m/s\n", t, y[0], y[1]);
    }
    return 0;
}

int main(void)
{
    ball b = {9.81, 0.8, 10.0};
    const double t1 = sqrt(2.0 * b.h0 / b.g);
    const dyn_event events[2] = {
        {.name = "bounce", .g = floor_g, .direction = -1, .reset = bounce},
        {.name = "nine", .g = nine_seconds, .direction = 1, .terminal = 1}};
    dyn_solve_opts opts = {.rtol = 1e-12, .atol = 1e-12, .events = events, .n_events = 2};
    log_t log = {&b, 0, t1, 2.0 * t1 * b.e, 0.0};
    opts.on_event = on_event;
    opts.event_ctx = &log;
    const dyn_tableau *dp45 = dyn_method_find("dp45");
    dyn_system sys = {rhs, 2, &b};
    double *work = malloc(dyn_solve_work_size(dp45, 2, &opts) * sizeof *work);
    if (!work)
        return 1;
    const double y0[2] = {b.h0, 0.0};
    double y[2];
    dyn_result res;
    int rc = dyn_solve(dp45, &sys, 0.0, 20.0, y0, y, work, &opts, &res);
    free(work);
    if (rc != DYN_OK) {
        fprintf(stderr, "solve failed: %s\n", res.message);
        return 1;
    }
    printf("%d bounces, largest difference to the closed form %.1e s, %ld steps\n",
           log.bounces, log.worst, res.stats.accepted);
    return log.worst < 1e-9 ? 0 : 1;
}
