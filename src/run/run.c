/* SPDX-License-Identifier: BSD-3-Clause */
/* One run of any model (dynkit/run.h, dyn_run): the solver family the model and the method
 * need — the fixed-step driver for fixed-step methods (the homework's loop), the general
 * driver dyn_solve for adaptive methods and for runs with events, resets or delays, the
 * methods for noise and jumps, XPPAUT's method for Volterra integrals, the CVODE backend.
 * A model's events that reset the state are part of its dynamics: every run includes them,
 * asked for or not. A model's output rules (t_trans, bound) are applied to the samples. The
 * workspace is allocated here, before the first step. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/io.h"
#include "run_internal.h"

/* A model with noise that names no tolerances: rkmil's (strong order 1: 1e-6 would take
 * millions of steps where 1e-3 takes hundreds; docs/solvers.md, "Noise") */
#define RUN_NOISE_RTOL 1e-3
#define RUN_NOISE_ATOL 1e-6

double dyn_run_default_rtol(const dyn_model *m)
{
    return m->rtol > 0.0 ? m->rtol : m->n_noise > 0 ? RUN_NOISE_RTOL : DYN_MODEL_RTOL;
}

double dyn_run_default_atol(const dyn_model *m)
{
    return m->atol > 0.0 ? m->atol : m->n_noise > 0 ? RUN_NOISE_ATOL : DYN_MODEL_ATOL;
}

void dyn_run_tolerances(const dyn_model *m, const dyn_run_opts *o, double *rtol, double *atol)
{
    *rtol = o->rtol > 0.0 ? o->rtol : dyn_run_default_rtol(m);
    *atol = o->atol > 0.0 ? o->atol : dyn_run_default_atol(m);
}

/* What the fixed-step driver and dyn_solve take alike from a run's options (dyn_fixed_opts
 * and dyn_solve_opts name these fields the same): the end policy, the step limit (a fixed
 * grid of more steps is refused at once), the tool's stage trace and its progress report. */
#define RUN_SHARED_OPTS(opts, ro)                                                                  \
    do {                                                                                           \
        (opts).end = (ro)->end;                                                                    \
        (opts).max_steps = (ro)->max_steps;                                                        \
        (opts).trace = (ro)->trace_steps > 0 ? (ro)->trace : NULL;                                 \
        (opts).trace_ctx = (ro)->trace_ctx;                                                        \
        (opts).trace_steps = (ro)->trace_steps;                                                    \
        (opts).progress = (ro)->progress;                                                          \
        (opts).progress_ctx = (ro)->progress_ctx;                                                  \
    } while (0)

/* The events of a run, in the model's order (the resets of one instant, and a cascade of
 * them, go in that order, as XPPAUT fires its globals): the model's events that are asked
 * for or reset the state, then asked events the model does not have. asked maps an index of
 * that list to o->events, or -1 for a reset that is not reported. */
typedef struct run_events {
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

static dyn_event *all_events(const run_ctx *rc, int *count, int **asked)
{
    const dyn_model *m = rc->m;
    const dyn_run_opts *o = rc->o;
    const size_t cap = (size_t)(o->n_events + m->n_events + 1);
    dyn_event *ev = malloc(cap * sizeof *ev);
    int *map = malloc(cap * sizeof *map);
    unsigned char *used = calloc((size_t)o->n_events + 1, 1);
    if (!ev || !map || !used) {
        free(ev);
        free(map);
        free(used);
        return NULL;
    }
    int ne = 0;
    for (int i = 0; i < m->n_events; i++) {
        int k = -1;
        for (int j = 0; j < o->n_events && k < 0; j++)
            if (!used[j] && strcmp(o->events[j].name, m->events[i].name) == 0)
                k = j;
        if (k < 0 && !m->events[i].reset)
            continue;
        if (k >= 0) {
            used[k] = 1;
            ev[ne] = o->events[k];
        } else {
            ev[ne] = m->events[i];
            ev[ne].terminal = 0;
        }
        map[ne++] = k;
    }
    for (int j = 0; j < o->n_events; j++)
        if (!used[j]) {
            ev[ne] = o->events[j];
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

static int fail_arg(dyn_result *res, const char *message)
{
    memset(res, 0, sizeof *res);
    res->status = DYN_ERR_ARG;
    snprintf(res->message, sizeof res->message, "%s", message);
    return DYN_ERR_ARG;
}

/* A model with noise (dynkit/sde.h): Euler–Maruyama (fixed-step methods) on the grid of the
 * step, or rkmil or sriw1 with samples on the grid (or at every accepted step); the noise of
 * stream o->stream under o->seed. */
static int solve_noise(const run_ctx *rc, dyn_output_fn output, void *output_ctx, double *y,
                       dyn_result *res)
{
    const dyn_model *m = rc->m;
    const dyn_run_opts *ro = rc->o;
    const int n = m->n_states;
    dyn_sde sde = {{m->rhs, n, rc->par}, m->n_noise, m->noise_kinds,
                   (double *)((char *)rc->par + m->noise_offset), m->noise_class};
    dyn_sde_opts o = {0};
    const dyn_sde_method method = (dyn_sde_method)dyn_run_sde_method(ro->method);
    const int adaptive = method == DYN_SDE_RKMIL || method == DYN_SDE_SRIW1;
    o.h = adaptive ? ro->initial_step : ro->step;
    dyn_run_tolerances(m, ro, &o.rtol, &o.atol);
    o.max_step = ro->max_step;
    o.max_steps = ro->max_steps;
    o.out_step = adaptive && !ro->at_steps ? ro->step : 0.0;
    o.end = ro->end;
    o.every = ro->every;
    o.seed = ro->seed;
    o.stream = ro->stream;
    o.jump = m->jump;
    o.output = output;
    o.output_ctx = output_ctx;
    o.progress = ro->progress;
    o.progress_ctx = ro->progress_ctx;
    int n_events = 0, *asked = NULL;
    dyn_event *events = all_events(rc, &n_events, &asked);
    if (!events)
        return -1;
    run_events re = {ro->on_event, ro->event_ctx, asked};
    o.events = events;
    o.n_events = n_events;
    o.xppaut_globals = m->xppaut_globals;
    o.on_event = forward_event;
    o.event_ctx = &re;
    double *work = malloc(dyn_sde_work_size(n, m->n_noise, n_events) * sizeof *work);
    if (!work) {
        free(events);
        free(asked);
        return -1;
    }
    const int rc_ = dyn_sde_solve(method, &sde, ro->t0, ro->t1, rc->y0, y, work, &o, res);
    free(work);
    free(events);
    free(asked);
    return rc_;
}

/* A fixed-step method without events, resets or delays: the homework's loop. */
static int solve_fixed(const run_ctx *rc, dyn_output_fn output, void *output_ctx, double *y,
                       dyn_result *res)
{
    const dyn_run_opts *ro = rc->o;
    const dyn_system sys = {rc->m->rhs, rc->m->n_states, rc->par};
    double *work = malloc(dyn_fixed_work_size(ro->method, sys.n) * sizeof *work);
    if (!work)
        return -1;
    dyn_fixed_opts opts = {0};
    RUN_SHARED_OPTS(opts, ro);
    opts.every = ro->every;
    opts.output = output;
    opts.output_ctx = output_ctx;
    const int status = dyn_fixed_solve(ro->method, &sys, ro->t0, ro->t1, ro->step, rc->y0, y,
                                       work, &opts, res);
    free(work);
    return status;
}

/* The linear algebra of a stiff run: the model's Jacobians, the band solver, and a sparse LU
 * opened into sparse when the choice is sparse (groups: the column groups of differences for
 * a pattern without values, owned). */
static void set_linear(const run_ctx *rc, dyn_solve_opts *opts, dyn_sparse_solver *sparse,
                       int **groups, int *sparse_open)
{
    const dyn_model *m = rc->m;
    const dyn_run_backends *b = rc->o->backends;
    opts->jacobian = m->jacobian;
    opts->jac_banded = m->jac_banded;
    opts->jac_lower = m->jac_lower;
    opts->jac_upper = m->jac_upper;
    opts->jacobian_band = m->jacobian_band;
    opts->band_solver = b ? b->band : NULL;
    if (!dyn_method_is_stiff(rc->o->method))
        return;
    dyn_linear_choice lin;
    dyn_run_linear_choose(m, rc->o->method, b, &lin);
    if (lin.kind != DYN_LINEAR_SPARSE)
        return;
    const int n = m->n_states;
    if (!m->jacobian_sparse && (*groups = malloc((size_t)n * sizeof **groups)) != NULL)
        opts->jac_n_groups = dyn_sparse_groups(&m->jac_pattern, *groups);
    if ((m->jacobian_sparse || opts->jac_n_groups > 0) && b->sparse_open(sparse) == 0) {
        *sparse_open = 1;
        opts->jac_sparse = m->jac_pattern;
        opts->jacobian_sparse = m->jacobian_sparse;
        opts->jac_groups = *groups;
        opts->sparse_solver = sparse;
    }
}

/* The general driver: adaptive methods, and fixed-step methods with events, resets or
 * delays (their samples on the grid of the step, without a row at each reset). */
static int solve_general(const run_ctx *rc, dyn_output_fn output, void *output_ctx, double *y,
                         dyn_result *res)
{
    const dyn_model *m = rc->m;
    const dyn_run_opts *ro = rc->o;
    const int n = m->n_states;
    const dyn_system sys = {m->rhs, n, rc->par};
    dyn_solve_opts opts = {0};
    RUN_SHARED_OPTS(opts, ro);
    dyn_run_tolerances(m, ro, &opts.rtol, &opts.atol);
    opts.rtolv = ro->rtolv;
    opts.atolv = ro->atolv;
    if (dyn_method_is_adaptive(ro->method)) {
        opts.initial_step = ro->initial_step;
        opts.max_step = ro->max_step;
        if (ro->times) {
            opts.out_times = ro->times;
            opts.n_out_times = ro->n_times;
        } else if (!ro->at_steps) {
            opts.out_step = ro->step;
        } /* else neither: a sample at every accepted step */
    } else {
        opts.h = ro->step; /* samples at every step, as the fixed-step driver gives them */
        if (dyn_run_resets(m) > 0 || m->delay)
            opts.out_step = ro->step; /* the same grid, without a row at each reset */
    }
    opts.output = output;
    opts.output_ctx = output_ctx;
    int n_events = 0, *asked = NULL;
    dyn_event *events = all_events(rc, &n_events, &asked);
    if (!events)
        return -1;
    run_events re = {ro->on_event, ro->event_ctx, asked};
    opts.events = events;
    opts.n_events = n_events;
    opts.xppaut_globals = m->xppaut_globals;
    opts.on_event = forward_event;
    opts.event_ctx = &re;
    dyn_sparse_solver sparse = {0};
    int *groups = NULL, sparse_open = 0;
    set_linear(rc, &opts, &sparse, &groups, &sparse_open);
    run_delay cd;
    double *work = NULL;
    int *iwork = NULL, status = -1;
    char why[sizeof res->message] = "";
    if (run_delay_start(rc, &cd, &opts, why, sizeof why)) {
        run_delay_finish(rc, &cd, res);
        status = fail_arg(res, why[0] ? why : "out of memory");
        goto done;
    }
    const size_t size = dyn_solve_work_size(ro->method, n, &opts);
    const size_t isize = dyn_solve_iwork_size(ro->method, n);
    work = malloc(size * sizeof *work);
    iwork = isize ? malloc(isize * sizeof *iwork) : NULL;
    if (!work || (isize && !iwork)) {
        run_delay_finish(rc, &cd, res);
        goto done;
    }
    opts.iwork = iwork;
    status = dyn_solve(ro->method, &sys, ro->t0, ro->t1, rc->y0, y, work, &opts, res);
    run_delay_finish(rc, &cd, res);
    if (res->stopped_by_event && res->event_index >= 0)
        res->event_index = asked[res->event_index];
done:
    if (sparse_open)
        rc->o->backends->sparse_close(&sparse);
    free(groups);
    free(work);
    free(iwork);
    free(events);
    free(asked);
    return status;
}

static int solve_cvode(const run_ctx *rc, dyn_output_fn output, void *output_ctx, double *y,
                       dyn_result *res)
{
    const dyn_run_opts *ro = rc->o;
    if (!ro->backends || !ro->backends->cvode)
        return fail_arg(res, "dynkit was built without SUNDIALS");
    if (dyn_run_resets(rc->m) > 0) {
        char msg[sizeof res->message];
        snprintf(msg, sizeof msg,
                 "model %s has events that reset the state, and the cvode backend runs "
                 "without events: use --method rodas4 (stiff) or dp45",
                 rc->m->name);
        return fail_arg(res, msg);
    }
    if (ro->n_events > 0 || ro->trace_steps > 0)
        return fail_arg(res, "cvode runs without events and traces (use rodas4 or dp45 for "
                             "events)");
    return ro->backends->cvode(rc->m, rc->par, rc->y0, ro, output, output_ctx, y, res);
}

static int solve_family(const run_ctx *rc, dyn_output_fn output, void *output_ctx, double *y,
                        dyn_result *res)
{
    const dyn_model *m = rc->m;
    const dyn_run_opts *ro = rc->o;
    if (m->n_noise > 0)
        return solve_noise(rc, output, output_ctx, y, res);
    if (m->volterra)
        return run_volterra(rc, output, output_ctx, y, res);
    if (ro->method == dyn_run_method_cvode()) {
        if (!m->delay)
            return solve_cvode(rc, output, output_ctx, y, res);
        char msg[sizeof res->message];
        snprintf(msg, sizeof msg,
                 "model %s has delays (delay(x, tau)), which the cvode backend cannot read: use "
                 "dp45, dop853, rk4 or rodas4",
                 m->name);
        return fail_arg(res, msg);
    }
    if (!dyn_method_is_adaptive(ro->method) && ro->n_events == 0 && dyn_run_resets(m) == 0 &&
        !m->delay)
        return solve_fixed(rc, output, output_ctx, y, res);
    return solve_general(rc, output, output_ctx, y, res);
}

int dyn_run(const dyn_model *m, void *par, const double *y0, const dyn_run_opts *o, double *y,
            dyn_result *res)
{
    memset(res, 0, sizeof *res);
    if (!m || !o || !o->method || !y0 || !y || (m->par_size > 0 && !par))
        return fail_arg(res, "dyn_run: a model, its parameters, y0, y and options with a "
                             "method are needed");
    const run_ctx rc = {m, par, y0, o};
    if (!(m->bound > 0) && !(m->t_trans > o->t0))
        return solve_family(&rc, o->output, o->output_ctx, y, res);
    model_output mo = {m, o->output, o->output_ctx, 0.0, 0.0, 0};
    const int status = solve_family(&rc, model_output_sample, &mo, y, res);
    if (mo.exceeded && res->status == DYN_STOPPED) {
        snprintf(res->message, sizeof res->message,
                 "state %s = %g exceeds the model's bound %g at t = %s (the file's @ bound)",
                 m->states[mo.exceeded - 1].name, mo.exceeded_value, m->bound,
                 dyn_shortest(mo.exceeded_t).s);
        res->fail_t = mo.exceeded_t;
        res->fail_index = mo.exceeded - 1;
    }
    return status;
}
