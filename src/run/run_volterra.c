/* SPDX-License-Identifier: BSD-3-Clause */
/* A run of a model with Volterra integrals (dyn_model.volterra, dynkit/volterra.h): XPPAUT's
 * volterra method on the grid of the step, the workspace for the points kept (@ vmaxpts,
 * default 4000) allocated here, a warning when the integrals stop reaching back to t0, and
 * for a model that also reads delay() a history fed with each step (linear between the grid
 * points). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/delay.h"
#include "dynkit/volterra.h"
#include "run_internal.h"

typedef struct volt_delay {
    dyn_history *h;
    double *coef; /* 2 n */
    double t_last;
    double *y_last; /* n */
    int n, have;
} volt_delay;

/* each grid step as a line from the last point to this one */
static int push_step(double t, const double *y, void *ctx)
{
    volt_delay *vd = ctx;
    const int n = vd->n;
    if (vd->have) {
        for (int i = 0; i < n; i++) {
            vd->coef[i] = vd->y_last[i];
            vd->coef[n + i] = y[i] - vd->y_last[i];
        }
        const dyn_dense d = {vd->t_last, t - vd->t_last, n, 1, vd->coef};
        if (dyn_history_push(&d, vd->h))
            return 1;
    }
    memcpy(vd->y_last, y, (size_t)n * sizeof *y);
    vd->t_last = t;
    vd->have = 1;
    return 0;
}

int run_volterra(const run_ctx *rc, dyn_output_fn output, void *output_ctx, double *y,
                 dyn_result *res)
{
    const dyn_model *m = rc->m;
    const dyn_run_opts *ro = rc->o;
    const dyn_volterra_model *vm = m->volterra;
    const int n = m->n_states;
    memset(res, 0, sizeof *res);
    const double h = ro->step, span = ro->t1 - ro->t0;
    const double r = span / h;
    const long steps = lround(r);
    if (!(h > 0.0) || !(r >= 0.5) || fabs(r - (double)steps) > 1e-9 * fmax(1.0, r)) {
        res->status = DYN_ERR_ARG;
        snprintf(res->message, sizeof res->message,
                 "the volterra method steps by --step %g over %g:%g, which is not a whole "
                 "number of steps: give a span that is",
                 h, ro->t0, ro->t1);
        return DYN_ERR_ARG;
    }
    const dyn_grid grid = {ro->t0, ro->t1, h, steps, 0, steps + 1, 1};
    if ((res->status = dyn_grid_check_steps(&grid, ro->max_steps, res->message,
                                            sizeof res->message)) != DYN_OK)
        return res->status;
    const long M = vm->max_points > 0 ? vm->max_points : DYN_VOLTERRA_MAX_POINTS_DEFAULT;
    double *ints = (double *)((char *)rc->par + vm->ints_offset);
    const dyn_volterra v = {n,      vm->is_int,   vm->n_int, vm->mu, vm->conv,
                            m->rhs, vm->integrand, vm->kernel, ints,  rc->par};
    double *work = malloc(dyn_volterra_work_size(n, vm->n_int, M) * sizeof *work);
    volt_delay vd = {0};
    if (!work)
        return -1;
    dyn_volterra_opts o = {0};
    o.max_points = M;
    o.every = ro->every;
    o.output = output;
    o.output_ctx = output_ctx;
    o.progress = ro->progress;
    o.progress_ctx = ro->progress_ctx;
    if (m->delay) {
        vd.n = n;
        vd.h = calloc(1, sizeof *vd.h);
        vd.coef = malloc(3 * (size_t)n * sizeof *vd.coef);
        if (!vd.h || !vd.coef) {
            free(vd.h);
            free(vd.coef);
            free(work);
            return -1;
        }
        vd.y_last = vd.coef + 2 * n;
        vd.h->grow = run_history_grow;
        dyn_history_init(vd.h, n, 1, ro->t0, rc->y0, m->delay->history, rc->par,
                         m->delay->max_delay, NULL, 0);
        m->delay->attach(rc->par, vd.h);
        o.step = push_step;
        o.step_ctx = &vd;
    }
    dyn_volterra_result vr;
    const int status = dyn_volterra_solve(&v, ro->t0, h, steps, rc->y0, y, work, &o, &vr);
    *res = vr.r;
    if (m->delay) {
        m->delay->attach(rc->par, NULL);
        free(vd.h->data);
        free(vd.h);
        free(vd.coef);
    }
    free(work);
    if (!isnan(vr.forgot) && ro->warn) {
        char msg[320];
        snprintf(msg, sizeof msg,
                 "the Volterra integrals keep the last %ld grid points (@ vmaxpts): from t = "
                 "%g on they cover the last %g time units only, not [t0, t], as XPPAUT's do; "
                 "raise vmaxpts in the file for the whole past",
                 M, vr.forgot, (double)M * h);
        ro->warn(msg, ro->warn_ctx);
    }
    return status;
}
