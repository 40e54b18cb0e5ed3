/* SPDX-License-Identifier: BSD-3-Clause */
/* dyn_integrate: the homework's [tout, yout] = Integrate_X(odefun, tspan, Ts, y0, par)
 * into caller-owned arrays, on top of the streaming fixed-step driver. */
#include <string.h>

#include "dynkit/ode.h"

typedef struct table_sink {
    double *tout, *yout;
    int n;
} table_sink;

static int store_sample(long k, double t, const double *y, void *ctx)
{
    table_sink *sink = ctx;
    sink->tout[k] = t;
    memcpy(sink->yout + (size_t)k * (size_t)sink->n, y, (size_t)sink->n * sizeof *y);
    return 0;
}

int dyn_integrate(const dyn_tableau *m, dyn_rhs_fn f, const double tspan[2], double Ts,
                  const double *y0, int n, void *par, double *tout, double *yout,
                  double *work, dyn_result *res)
{
    dyn_result local;
    if (!res)
        res = &local;
    if (!tspan || !tout || !yout) {
        memset(res, 0, sizeof *res);
        res->status = DYN_ERR_ARG;
        strcpy(res->message, "tspan, tout or yout is NULL");
        return res->status;
    }
    dyn_system sys = {f, n, par};
    table_sink sink = {tout, yout, n};
    dyn_fixed_opts opts = {0};
    opts.output = store_sample;
    opts.output_ctx = &sink;
    return dyn_fixed_solve(m, &sys, tspan[0], tspan[1], Ts, y0, NULL, work, &opts, res);
}
