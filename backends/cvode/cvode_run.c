/* SPDX-License-Identifier: BSD-3-Clause */
/* dyn_run's CVODE family (dynkit/run.h, dyn_run_backends.cvode): a model's run with
 * dyn_cvode_solve at the output times (the run's list, or its grid) or at every step CVODE
 * takes, with the model's Jacobian: dense, band, or sparse when the model gives its exact
 * sparse values and SUNDIALS' KLU is built (dyn_run_linear_choose). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/cvode.h"
#include "dynkit/run.h"

int dyn_cvode_run(const dyn_model *m, void *par, const double *y0, const dyn_run_opts *ro,
                  dyn_output_fn output, void *output_ctx, double *y, dyn_result *res)
{
    const dyn_system sys = {m->rhs, m->n_states, par};
    dyn_cvode_opts o = {0};
    dyn_run_tolerances(m, ro, &o.rtol, &o.atol);
    o.rtolv = ro->rtolv;
    o.atolv = ro->atolv;
    o.jacobian = m->jacobian;
    o.jac_banded = m->jac_banded;
    o.jac_lower = m->jac_lower;
    o.jac_upper = m->jac_upper;
    o.jacobian_band = m->jacobian_band;
    dyn_linear_choice lin;
    dyn_run_linear_choose(m, ro->method, ro->backends, &lin);
    if (lin.kind == DYN_LINEAR_SPARSE) {
        o.jac_sparse = m->jac_pattern;
        o.jacobian_sparse = m->jacobian_sparse;
    }
    o.max_steps = ro->max_steps;
    o.initial_step = ro->initial_step;
    o.max_step = ro->max_step;
    memset(res, 0, sizeof *res);
    res->t = ro->t0;
    if (ro->at_steps)
        return dyn_cvode_solve_steps(&sys, ro->t0, ro->t1, y0, &o, output, output_ctx, y, res);
    if (ro->times)
        return dyn_cvode_solve(&sys, ro->t0, y0, ro->times, ro->n_times, &o, output,
                               output_ctx, y, res);
    dyn_grid grid;
    if (dyn_grid_plan(ro->t0, ro->t1, ro->step, ro->end, &grid, res->message,
                      sizeof res->message)) {
        res->status = DYN_ERR_ARG;
        return DYN_ERR_ARG;
    }
    if (grid.samples > 100000000L) {
        res->status = DYN_ERR_ARG;
        snprintf(res->message, sizeof res->message,
                 "cvode takes its output times as a list, and --step %g over %g:%g gives %ld of "
                 "them: give a larger --step or --times",
                 ro->step, ro->t0, ro->t1, grid.samples);
        return DYN_ERR_ARG;
    }
    double *tout = malloc((size_t)grid.samples * sizeof *tout);
    if (!tout)
        return -1;
    for (long k = 0; k < grid.samples; k++)
        tout[k] = dyn_grid_time(&grid, k);
    const int rc = dyn_cvode_solve(&sys, ro->t0, y0, tout, grid.samples, &o, output,
                                   output_ctx, y, res);
    free(tout);
    return rc;
}
