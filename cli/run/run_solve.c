/* SPDX-License-Identifier: BSD-3-Clause */
/* One run of a model with the method of the run options: the fixed-step driver for
 * fixed-step methods (the homework's loop), the general driver dyn_solve for adaptive
 * methods and for runs with events, the CVODE backend for cvode (when built). A model's
 * events that reset the state are part of its dynamics: every run includes them, asked
 * for with --event or not. A model's output rules (t_trans, bound) are applied to the
 * samples. The workspace is allocated here, outside the library's step loop. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

#ifdef DYNKIT_HAVE_CVODE
#include "dynkit/cvode.h"

/* cvode: the output times from --times or the grid (or every step), the tolerances and the
 * model's Jacobian; the counters come back in res as from dyn_solve. */
static int solve_cvode(const cli_run *run, const dyn_system *sys, dyn_output_fn output,
                       void *output_ctx, double *y, dyn_result *res)
{
    dyn_cvode_opts o = {0};
    o.rtol = run->rtol;
    o.atol = run->atol;
    o.rtolv = run->rtolv;
    o.atolv = run->atolv;
    o.jacobian = run->model->jacobian;
    o.jac_banded = run->model->jac_banded;
    o.jac_lower = run->model->jac_lower;
    o.jac_upper = run->model->jac_upper;
    o.jacobian_band = run->model->jacobian_band;
    cli_linear lin;
    cli_linear_for_run(run, &lin);
    if (lin.kind == CLI_LINEAR_SPARSE) {
        o.jac_sparse = run->model->jac_pattern;
        o.jacobian_sparse = run->model->jacobian_sparse;
    }
    o.max_steps = run->max_steps;
    o.initial_step = run->initial_step;
    o.max_step = run->max_step;
    memset(res, 0, sizeof *res);
    res->t = run->t0;
    if (cli_run_resets(run) > 0) {
        res->status = DYN_ERR_ARG;
        snprintf(res->message, sizeof res->message,
                 "model %s has events that reset the state, and the cvode backend runs "
                 "without events: use --method rodas4 (stiff) or dp45",
                 run->model->name);
        return DYN_ERR_ARG;
    }
    if (run->n_events > 0 || run->trace_steps > 0) {
        res->status = DYN_ERR_ARG;
        snprintf(res->message, sizeof res->message,
                 "cvode runs without events and traces (use rodas4 or dp45 for events)");
        return DYN_ERR_ARG;
    }
    if (cli_run_at_steps(run))
        return dyn_cvode_solve_steps(sys, run->t0, run->t1, run->y0, &o, output, output_ctx, y,
                                     res);
    if (run->times)
        return dyn_cvode_solve(sys, run->t0, run->y0, run->times, run->n_times, &o, output,
                               output_ctx, y, res);
    dyn_grid grid;
    if (dyn_grid_plan(run->t0, run->t1, run->step, run->end, &grid, res->message,
                      sizeof res->message)) {
        res->status = DYN_ERR_ARG;
        return DYN_ERR_ARG;
    }
    if (grid.samples > 100000000L) {
        res->status = DYN_ERR_ARG;
        snprintf(res->message, sizeof res->message,
                 "cvode takes its output times as a list, and --step %g over %g:%g gives %ld of "
                 "them: give a larger --step or --times",
                 run->step, run->t0, run->t1, grid.samples);
        return DYN_ERR_ARG;
    }
    double *tout = malloc((size_t)grid.samples * sizeof *tout);
    if (!tout)
        return -1;
    for (long k = 0; k < grid.samples; k++)
        tout[k] = dyn_grid_time(&grid, k);
    int rc = dyn_cvode_solve(sys, run->t0, run->y0, tout, grid.samples, &o, output, output_ctx,
                             y, res);
    free(tout);
    return rc;
}
#endif

/* The events of a run, in the model's order (the resets of one instant, and a cascade of
 * them, go in that order, as XPPAUT fires its globals): the model's events that are asked
 * for (--event) or reset the state, then asked events the model does not have. asked maps
 * an index of that list to run->events, or -1 for a reset that is not reported. */
typedef struct run_events {
    const cli_run *run;
    dyn_event_fn on_event;
    void *ctx;
    const int *asked;
} run_events;

static int forward_event(int index, double t, const double *y, int direction, void *ctx)
{
    const run_events *re = ctx;
    const int k = re->asked[index];
    if (k < 0 || !re->on_event)
        return 0;
    return re->on_event(k, t, y, direction, re->ctx);
}

static dyn_event *all_events(const cli_run *run, int *count, int **asked)
{
    const dyn_model *m = run->model;
    const size_t cap = (size_t)(run->n_events + m->n_events + 1);
    dyn_event *ev = malloc(cap * sizeof *ev);
    int *map = malloc(cap * sizeof *map);
    unsigned char *used = calloc((size_t)run->n_events + 1, 1);
    if (!ev || !map || !used) {
        free(ev);
        free(map);
        free(used);
        return NULL;
    }
    int ne = 0;
    for (int i = 0; i < m->n_events; i++) {
        int k = -1;
        for (int j = 0; j < run->n_events && k < 0; j++)
            if (!used[j] && strcmp(run->events[j].name, m->events[i].name) == 0)
                k = j;
        if (k < 0 && !m->events[i].reset)
            continue;
        if (k >= 0) {
            used[k] = 1;
            ev[ne] = run->events[k];
        } else {
            ev[ne] = m->events[i];
            ev[ne].terminal = 0;
        }
        map[ne++] = k;
    }
    for (int j = 0; j < run->n_events; j++)
        if (!used[j]) {
            ev[ne] = run->events[j];
            map[ne++] = j;
        }
    free(used);
    *count = ne;
    *asked = map;
    return ev;
}

/* A model's output rules (XPPAUT's @ trans and bound, dyn_model.t_trans and bound): no
 * samples before t_trans, and a run stops when a state's magnitude exceeds the bound. */
typedef struct model_output {
    const dyn_model *model;
    dyn_output_fn inner;
    void *ctx;
    double exceeded_t, exceeded_value; /* where the bound was exceeded */
    int exceeded;                      /* index of that state + 1, or 0 */
} model_output;

static int model_output_sample(long k, double t, const double *y, void *ctx)
{
    model_output *mo = ctx;
    const dyn_model *m = mo->model;
    for (int i = 0; m->bound > 0 && i < m->n_states; i++)
        if (fabs(y[i]) > m->bound) {
            mo->exceeded = i + 1;
            mo->exceeded_t = t;
            mo->exceeded_value = y[i];
            return 1;
        }
    if (t < m->t_trans)
        return 0;
    return mo->inner ? mo->inner(k, t, y, mo->ctx) : 0;
}

static int solve_run(const cli_run *run, long every, dyn_output_fn output, void *output_ctx,
                     dyn_event_fn on_event, void *event_ctx, dyn_progress_fn progress,
                     void *progress_ctx, double *y, dyn_result *res);

int cli_run_solve(const cli_run *run, long every, dyn_output_fn output, void *output_ctx,
                  dyn_event_fn on_event, void *event_ctx, dyn_progress_fn progress,
                  void *progress_ctx, double *y, dyn_result *res)
{
    const dyn_model *m = run->model;
    if (!(m->bound > 0) && !(m->t_trans > run->t0))
        return solve_run(run, every, output, output_ctx, on_event, event_ctx, progress,
                         progress_ctx, y, res);
    model_output mo = {m, output, output_ctx, 0.0, 0.0, 0};
    const int rc = solve_run(run, every, model_output_sample, &mo, on_event, event_ctx,
                             progress, progress_ctx, y, res);
    if (mo.exceeded && res->status == DYN_STOPPED) {
        snprintf(res->message, sizeof res->message,
                 "state %s = %g exceeds the model's bound %g at t = %s (the file's @ bound)",
                 m->states[mo.exceeded - 1].name, mo.exceeded_value, m->bound,
                 CLI_NUM(mo.exceeded_t));
        res->fail_t = mo.exceeded_t;
        res->fail_index = mo.exceeded - 1;
    }
    return rc;
}

/* A model with noise (dynkit/sde.h): Euler–Maruyama (euler) on the grid of the step, or
 * rkmil or sriw1 with its samples on the grid (or at every accepted step); the noise of run
 * run->stream under run->seed. */
static int solve_noise(const cli_run *run, long every, dyn_output_fn output, void *output_ctx,
                       dyn_event_fn on_event, void *event_ctx, dyn_progress_fn progress,
                       void *progress_ctx, double *y, dyn_result *res)
{
    const dyn_model *m = run->model;
    const int n = m->n_states;
    dyn_sde sde = {{m->rhs, n, run->par}, m->n_noise, m->noise_kinds,
                   (double *)((char *)run->par + m->noise_offset), m->noise_class};
    dyn_sde_opts o = {0};
    const dyn_sde_method method = cli_sde_method(run->method);
    const int adaptive = method == DYN_SDE_RKMIL || method == DYN_SDE_SRIW1;
    o.h = adaptive ? run->initial_step : run->step;
    o.rtol = run->rtol;
    o.atol = run->atol;
    o.max_step = run->max_step;
    o.max_steps = run->max_steps;
    o.out_step = adaptive && !cli_run_at_steps(run) ? run->step : 0.0;
    o.end = run->end;
    o.every = every;
    o.seed = run->seed;
    o.stream = run->stream;
    o.jump = m->jump;
    o.output = output;
    o.output_ctx = output_ctx;
    o.progress = progress;
    o.progress_ctx = progress_ctx;
    int n_events = 0, *asked = NULL;
    dyn_event *events = all_events(run, &n_events, &asked);
    if (!events)
        return -1;
    run_events re = {run, on_event, event_ctx, asked};
    o.events = events;
    o.n_events = n_events;
    o.on_event = forward_event;
    o.event_ctx = &re;
    double *work = malloc(dyn_sde_work_size(n, m->n_noise, n_events) * sizeof *work);
    if (!work) {
        free(events);
        free(asked);
        return -1;
    }
    const int rc = dyn_sde_solve(method, &sde, run->t0, run->t1, run->y0, y, work, &o, res);
    free(work);
    free(events);
    free(asked);
    return rc;
}

static int solve_run(const cli_run *run, long every, dyn_output_fn output, void *output_ctx,
                     dyn_event_fn on_event, void *event_ctx, dyn_progress_fn progress,
                     void *progress_ctx, double *y, dyn_result *res)
{
    const dyn_model *m = run->model;
    const int n = m->n_states;
    if (m->n_noise > 0)
        return solve_noise(run, every, output, output_ctx, on_event, event_ctx, progress,
                           progress_ctx, y, res);
    if (m->volterra)
        return cli_solve_volterra(run, every, output, output_ctx, progress, progress_ctx, y,
                                  res);
    dyn_system sys = {m->rhs, n, run->par};
    const int adaptive = dyn_method_is_adaptive(run->method);
    if (cli_method_is_cvode(run->method) && !m->delay) {
#ifdef DYNKIT_HAVE_CVODE
        return solve_cvode(run, &sys, output, output_ctx, y, res);
#else
        memset(res, 0, sizeof *res);
        res->status = DYN_ERR_ARG;
        snprintf(res->message, sizeof res->message, "dynkit was built without SUNDIALS");
        return DYN_ERR_ARG;
#endif
    }
    if (!adaptive && run->n_events == 0 && cli_run_resets(run) == 0 && !m->delay) {
        size_t size = dyn_fixed_work_size(run->method, n);
        double *work = malloc(size * sizeof *work);
        if (!work)
            return -1;
        dyn_fixed_opts opts = {0};
        opts.end = run->end;
        opts.every = every;
        opts.output = output;
        opts.output_ctx = output_ctx;
        opts.trace = run->trace_steps > 0 ? cli_print_trace : NULL;
        opts.trace_ctx = (void *)run;
        opts.trace_steps = run->trace_steps;
        opts.progress = progress;
        opts.progress_ctx = progress_ctx;
        int rc = dyn_fixed_solve(run->method, &sys, run->t0, run->t1, run->step, run->y0, y,
                                 work, &opts, res);
        free(work);
        return rc;
    }
    dyn_solve_opts opts = {0};
    opts.rtol = run->rtol;
    opts.atol = run->atol;
    opts.rtolv = run->rtolv;
    opts.atolv = run->atolv;
    opts.end = run->end;
    if (adaptive) {
        opts.initial_step = run->initial_step;
        opts.max_step = run->max_step;
        opts.max_steps = run->max_steps;
        if (run->times) {
            opts.out_times = run->times;
            opts.n_out_times = run->n_times;
        } else if (!cli_run_at_steps(run)) {
            opts.out_step = run->step;
        } /* else neither: a sample at every accepted step */
    } else {
        opts.h = run->step; /* samples at every step, as the fixed-step driver gives them */
        if (cli_run_resets(run) > 0 || m->delay)
            opts.out_step = run->step; /* the same grid, without a row at each reset */
    }
    opts.output = output;
    opts.output_ctx = output_ctx;
    int n_events = 0, *asked = NULL;
    dyn_event *events = all_events(run, &n_events, &asked);
    if (!events)
        return -1;
    run_events re = {run, on_event, event_ctx, asked};
    opts.events = events;
    opts.n_events = n_events;
    opts.on_event = forward_event;
    opts.event_ctx = &re;
    opts.jacobian = m->jacobian;
    opts.jac_banded = m->jac_banded;
    opts.jac_lower = m->jac_lower;
    opts.jac_upper = m->jac_upper;
    opts.jacobian_band = m->jacobian_band;
    opts.band_solver = cli_band_solver();
    cli_linear lin;
    dyn_sparse_solver sparse = {0};
    int *groups = NULL; /* a pattern without values: differences in groups of columns */
    if (dyn_method_is_stiff(run->method)) {
        cli_linear_choose(m, &lin);
        if (lin.kind == CLI_LINEAR_SPARSE && !m->jacobian_sparse &&
            (groups = malloc((size_t)n * sizeof *groups)) != NULL)
            opts.jac_n_groups = dyn_sparse_groups(&m->jac_pattern, groups);
        if (lin.kind == CLI_LINEAR_SPARSE && (m->jacobian_sparse || opts.jac_n_groups > 0) &&
            !cli_sparse_solver_open(&sparse)) {
            opts.jac_sparse = m->jac_pattern;
            opts.jacobian_sparse = m->jacobian_sparse;
            opts.jac_groups = groups;
            opts.sparse_solver = &sparse;
        }
    }
    opts.trace = run->trace_steps > 0 ? cli_print_trace : NULL;
    opts.trace_ctx = (void *)run;
    opts.trace_steps = run->trace_steps;
    opts.progress = progress;
    opts.progress_ctx = progress_ctx;
    cli_delay cd;
    if (cli_delay_start(run, &cd, &opts, res->message, sizeof res->message)) {
        const char *why = res->message[0] ? res->message : "out of memory";
        char msg[sizeof res->message];
        snprintf(msg, sizeof msg, "%s", why);
        cli_delay_finish(run, &cd, res);
        memset(res, 0, sizeof *res);
        res->status = DYN_ERR_ARG;
        snprintf(res->message, sizeof res->message, "%s", msg);
        cli_sparse_solver_close(&sparse);
        free(groups);
        free(events);
        free(asked);
        return DYN_ERR_ARG;
    }
    const size_t size = dyn_solve_work_size(run->method, n, &opts);
    const size_t isize = dyn_solve_iwork_size(run->method, n);
    double *work = malloc(size * sizeof *work);
    int *iwork = isize ? malloc(isize * sizeof *iwork) : NULL;
    if (!work || (isize && !iwork)) {
        free(work);
        free(iwork);
        free(events);
        free(asked);
        cli_sparse_solver_close(&sparse);
        free(groups);
        cli_delay_finish(run, &cd, res);
        return -1;
    }
    opts.iwork = iwork;
    int rc = dyn_solve(run->method, &sys, run->t0, run->t1, run->y0, y, work, &opts, res);
    cli_delay_finish(run, &cd, res);
    if (res->stopped_by_event && res->event_index >= 0)
        res->event_index = asked[res->event_index];
    cli_sparse_solver_close(&sparse);
    free(groups);
    free(work);
    free(iwork);
    free(events);
    free(asked);
    return rc;
}

char *cli_stats_line(const cli_run *run, const dyn_result *res, char *buf, size_t size)
{
    const dyn_stats *s = &res->stats;
    int w = snprintf(buf, size, "steps=%ld accepted=%ld rejected=%ld rhs=%ld", s->steps,
                     s->accepted, s->rejected, s->rhs_calls);
    if (dyn_method_is_stiff(run->method) && w >= 0 && (size_t)w < size)
        w += snprintf(buf + w, size - (size_t)w, " jac=%ld", s->jac_calls);
    /* columns of the exact Jacobian that could not be evaluated (an entry not finite) */
    if (s->jac_fd_columns > 0 && w >= 0 && (size_t)w < size)
        w += snprintf(buf + w, size - (size_t)w, " jac_fd_columns=%ld", s->jac_fd_columns);
    /* the matrices of the linear systems (cli_linear_choose; --verbose says why) */
    if (dyn_method_is_stiff(run->method) && w >= 0 && (size_t)w < size) {
        cli_linear lin;
        cli_linear_for_run(run, &lin);
        if (lin.kind == CLI_LINEAR_BAND)
            snprintf(buf + w, size - (size_t)w, " linear=band lower=%d upper=%d", lin.lower,
                     lin.upper);
        else if (lin.kind == CLI_LINEAR_SPARSE)
            snprintf(buf + w, size - (size_t)w, " linear=sparse nnz=%d", lin.nnz);
        else
            snprintf(buf + w, size - (size_t)w, " linear=dense");
    }
    return buf;
}
