/* SPDX-License-Identifier: BSD-3-Clause */
/* The sweep runner (dynkit/sweep.h): one model over a table of runs, each run reduced to a
 * row of numbers, on OpenMP threads. A plan shared read-only by the threads (the events to
 * locate, the solver's options, the workspace sizes) is made once; each thread's workspace
 * is allocated once before the runs; a run copies the base parameters, sets its row, runs
 * the fixed-step driver (dyn_fixed_solve: fixed-step methods without events) or the general
 * driver (dyn_solve, ode.h / solve.h), and writes its own row and status only. A stiff
 * method takes the model's band or, with dyn_sweep.sparse_open, its sparse pattern, with one
 * sparse solver per thread kept across that thread's runs. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "dynkit/sweep.h"

#define SWEEP_PRAGMA(x) _Pragma(#x)
#ifdef _OPENMP
#define OMP(x) SWEEP_PRAGMA(omp x)
#else
#define OMP(x)
#endif

/* What every run shares, read-only during the runs. */
typedef struct plan {
    const dyn_sweep *s;
    const dyn_model *m;
    const void *par;         /* base parameters */
    int use_solve;           /* dyn_solve (adaptive, or events) rather than dyn_fixed_solve */
    int noise;               /* dyn_sde_solve: the model has noise */
    int need_samples;        /* a reduction over the samples, or the model's bound */
    int samples_outputs;     /* a reduction over the samples reads an output */
    int final_outputs;       /* a final reduction reads an output */
    int n_events;
    dyn_event *events;       /* (n_events) the events located, owned */
    int *event_model;        /* (n_events) their index in model->events, owned */
    dyn_solve_opts solve;    /* template of dyn_solve's options (contexts set per run) */
    int sparse;              /* sparse matrices: each worker's solver (dyn_sweep.sparse_open) */
    int *groups;             /* (n) a pattern without values: its columns' groups, owned */
    dyn_fixed_opts fixed;    /* template of dyn_fixed_solve's options */
    size_t work_size, iwork_size;
    int stop;                /* the sweep is cancelled (read and written atomically) */
} plan;

/* One thread's workspace, allocated once. */
typedef struct worker {
    const plan *p;
    void *par;
    double *y0, *y, *out, *work;
    int *iwork;
    dyn_sparse_solver sparse; /* the thread's sparse LU and its analysis (plan.sparse) */
    int sparse_open;
    double *acc, *aux;       /* (n_reduce) accumulators: value, and time or previous value */
    long samples;
    long run;           /* the run being integrated */
    int outputs_failed; /* the sample callback stopped the run: compute_outputs failed */
    double t_first, t_prev;
    char err[256];
} worker;

static int is_sample_op(dyn_reduce_op op)
{
    return op == DYN_REDUCE_MAX || op == DYN_REDUCE_MIN || op == DYN_REDUCE_MEAN ||
           op == DYN_REDUCE_ARGMAX || op == DYN_REDUCE_ARGMIN;
}

int dyn_sweep_threads(int threads)
{
#ifdef _OPENMP
    return threads > 0 ? threads : omp_get_max_threads();
#else
    (void)threads;
    return 1;
#endif
}

static int stopped(const plan *p)
{
    int v;
    OMP(atomic read)
    v = p->stop;
    return v;
}

static void set_stop(plan *p)
{
    OMP(atomic write)
    p->stop = 1;
}

/* The solvers' progress hook within a run: cancel when the sweep is cancelled. */
static int run_progress(double t, double fraction, void *ctx)
{
    const worker *w = ctx;
    const dyn_sweep *s = w->p->s;
    (void)t;
    (void)fraction;
    return stopped(w->p) || (s->cancel && s->cancel(s->cancel_ctx));
}

static int on_sample(long k, double t, const double *y, void *ctx)
{
    worker *w = ctx;
    const plan *p = w->p;
    const dyn_model *m = p->m;
    const dyn_sweep *sw = p->s;
    if (sw->series && k % sw->series_every == 0 && k / sw->series_every < sw->n_series)
        memcpy(sw->series + ((size_t)w->run * (size_t)sw->n_series +
                             (size_t)(k / sw->series_every)) * (size_t)m->n_states,
               y, (size_t)m->n_states * sizeof *y);
    if (m->bound > 0)
        for (int i = 0; i < m->n_states; i++)
            if (fabs(y[i]) > m->bound)
                return 1;
    if (t < m->t_trans)
        return 0;
    if (p->samples_outputs && m->compute_outputs(t, y, w->par, w->out)) {
        w->outputs_failed = 1; /* the run's status: the model's functions failed */
        return 1;
    }
    const dyn_sweep *s = p->s;
    const int first = w->samples == 0;
    for (int r = 0; r < s->n_reduce; r++) {
        const dyn_reduce *rd = &s->reduce[r];
        if (!is_sample_op(rd->op))
            continue;
        const double v = rd->source == DYN_SOURCE_STATE ? y[rd->index] : w->out[rd->index];
        switch (rd->op) {
        /* a nan sample makes the extreme nan (from there on), as it does final and mean */
        case DYN_REDUCE_MAX:
        case DYN_REDUCE_ARGMAX:
            if (first || v > w->acc[r] || (isnan(v) && !isnan(w->acc[r]))) {
                w->acc[r] = v;
                w->aux[r] = t;
            }
            break;
        case DYN_REDUCE_MIN:
        case DYN_REDUCE_ARGMIN:
            if (first || v < w->acc[r] || (isnan(v) && !isnan(w->acc[r]))) {
                w->acc[r] = v;
                w->aux[r] = t;
            }
            break;
        case DYN_REDUCE_MEAN:
            if (!first)
                w->acc[r] += (t - w->t_prev) * (0.5 * (w->aux[r] + v));
            w->aux[r] = v;
            break;
        default:
            break;
        }
    }
    if (first)
        w->t_first = t;
    w->t_prev = t;
    w->samples++;
    return 0;
}

static int on_event(int index, double t, const double *y, int direction, void *ctx)
{
    worker *w = ctx;
    const plan *p = w->p;
    const dyn_sweep *s = p->s;
    const int e = p->event_model[index];
    (void)y;
    (void)direction;
    for (int r = 0; r < s->n_reduce; r++) {
        const dyn_reduce *rd = &s->reduce[r];
        if (rd->source != DYN_SOURCE_EVENT || rd->index != e)
            continue;
        if (rd->op == DYN_REDUCE_EVENT && isnan(w->acc[r]))
            w->acc[r] = t;
        else if (rd->op == DYN_REDUCE_COUNT)
            w->acc[r] += 1.0;
    }
    return 0;
}

static void nan_row(double *row, int n)
{
    for (int r = 0; r < n; r++)
        row[r] = NAN;
}

/* Run i into row; returns its status. */
static int run_one(worker *w, long i, double *row)
{
    const plan *p = w->p;
    const dyn_sweep *s = p->s;
    const dyn_model *m = p->m;
    const int n = m->n_states;
    const double *vals = s->values ? s->values + (size_t)i * (size_t)s->n_vars : NULL;
    memcpy(w->par, p->par, m->par_size);
    for (int v = 0; v < s->n_vars; v++)
        if (s->vars[v].kind == DYN_SWEEP_PARAM)
            dyn_model_set_param(m, w->par, s->vars[v].index, vals[v]);
    if (m->seed_offset) { /* the tables' random numbers: the same in every run */
        double *sd = (double *)((char *)w->par + m->seed_offset);
        sd[0] = (double)(uint32_t)s->seed;
        sd[1] = (double)(uint32_t)(s->seed >> 32);
    }
    if (m->prepare && m->prepare(w->par, w->err, sizeof w->err)) {
        nan_row(row, s->n_reduce);
        return DYN_ERR_ARG;
    }
    if (s->y0)
        memcpy(w->y0, s->y0, (size_t)n * sizeof *w->y0);
    else
        dyn_model_initial_state(m, w->par, w->y0);
    for (int v = 0; v < s->n_vars; v++)
        if (s->vars[v].kind == DYN_SWEEP_STATE)
            w->y0[s->vars[v].index] = vals[v];
    for (int r = 0; r < s->n_reduce; r++) {
        w->acc[r] = s->reduce[r].op == DYN_REDUCE_EVENT ? NAN : 0.0;
        w->aux[r] = 0.0;
    }
    w->samples = 0;
    w->outputs_failed = 0;
    w->t_first = w->t_prev = s->t0;
    const dyn_system sys = {m->rhs, n, w->par};
    dyn_result res;
    int st;
    w->run = i;
    if (p->noise) {
        const dyn_sde sde = {{m->rhs, n, w->par}, m->n_noise, m->noise_kinds,
                             (double *)((char *)w->par + m->noise_offset),
                             (dyn_noise_class)m->noise_class};
        dyn_sde_opts o = {0};
        const int em = s->noise_method != DYN_SDE_RKMIL && s->noise_method != DYN_SDE_SRIW1;
        o.h = em ? s->step : s->initial_step;
        o.rtol = s->rtol;
        o.atol = s->atol;
        o.max_step = s->max_step;
        o.max_steps = s->max_steps;
        o.out_step = em ? 0.0 : s->step;
        o.end = s->end;
        o.seed = s->seed;
        o.stream = (uint64_t)i;
        o.jump = m->jump;
        o.output = p->need_samples ? on_sample : NULL;
        o.output_ctx = w;
        o.progress = run_progress;
        o.progress_ctx = w;
        o.events = p->events;
        o.n_events = p->n_events;
        o.xppaut_globals = m->xppaut_globals;
        o.on_event = p->n_events > 0 ? on_event : NULL;
        o.event_ctx = w;
        st = dyn_sde_solve((dyn_sde_method)s->noise_method, &sde, s->t0, s->t1, w->y0, w->y,
                           w->work, &o, &res);
    } else if (p->use_solve) {
        dyn_solve_opts o = p->solve;
        o.output_ctx = w;
        o.event_ctx = w;
        o.progress_ctx = w;
        o.iwork = w->iwork;
        if (p->sparse)
            o.sparse_solver = &w->sparse;
        st = dyn_solve(s->method, &sys, s->t0, s->t1, w->y0, w->y, w->work, &o, &res);
    } else {
        dyn_fixed_opts o = p->fixed;
        o.output_ctx = w;
        o.progress_ctx = w;
        st = dyn_fixed_solve(s->method, &sys, s->t0, s->t1, s->step, w->y0, w->y, w->work, &o,
                             &res);
    }
    if (st == DYN_CANCELLED) {
        nan_row(row, s->n_reduce);
        return DYN_SWEEP_NOT_RUN;
    }
    if (st != DYN_OK) {
        nan_row(row, s->n_reduce);
        /* stopped by the sample callback: the bound, or the outputs failing */
        return st == DYN_STOPPED && w->outputs_failed ? DYN_ERR_RHS : st;
    }
    if (p->final_outputs && m->compute_outputs(res.t, w->y, w->par, w->out)) {
        nan_row(row, s->n_reduce);
        return DYN_ERR_RHS;
    }
    const double span = w->t_prev - w->t_first;
    for (int r = 0; r < s->n_reduce; r++) {
        const dyn_reduce *rd = &s->reduce[r];
        switch (rd->op) {
        case DYN_REDUCE_FINAL:
            row[r] = rd->source == DYN_SOURCE_STATE ? w->y[rd->index] : w->out[rd->index];
            break;
        case DYN_REDUCE_MAX:
        case DYN_REDUCE_MIN:
            row[r] = w->samples > 0 ? w->acc[r] : NAN;
            break;
        case DYN_REDUCE_ARGMAX:
        case DYN_REDUCE_ARGMIN:
            row[r] = w->samples > 0 ? w->aux[r] : NAN;
            break;
        case DYN_REDUCE_MEAN:
            row[r] = w->samples == 0 ? NAN : span > 0 ? w->acc[r] / span : w->aux[r];
            break;
        case DYN_REDUCE_EVENT:
        case DYN_REDUCE_COUNT:
            row[r] = w->acc[r];
            break;
        }
    }
    return DYN_OK;
}

static int check(const dyn_sweep *s, char *err, size_t errlen)
{
    const dyn_model *m = s->model;
    if (!m || !s->method) {
        snprintf(err, errlen, "a sweep needs a model and a method");
        return -1;
    }
    if (m->delay) {
        snprintf(err, errlen, "model %s is a delay equation (delay(x, tau)): sweeps run "
                 "ordinary differential equations only (dynkit run runs it, one run a value)",
                 m->name);
        return -1;
    }
    if (m->volterra) {
        snprintf(err, errlen, "model %s has Volterra integrals (int{...}, volt): sweeps run "
                 "ordinary differential equations only (dynkit run runs it, one run a value)",
                 m->name);
        return -1;
    }
    if (s->n_runs < 0 || s->n_vars < 0 || s->n_reduce < 0 || s->n_stop < 0 ||
        (s->n_vars > 0 && s->n_runs > 0 && (!s->vars || !s->values)) ||
        (s->n_reduce > 0 && !s->reduce) || (s->n_stop > 0 && !s->stop)) {
        snprintf(err, errlen, "a sweep's counts must be >= 0, with their arrays");
        return -1;
    }
    if (!(s->t1 > s->t0) || !isfinite(s->t0) || !isfinite(s->t1)) {
        snprintf(err, errlen, "the span %g:%g must be finite with t1 > t0", s->t0, s->t1);
        return -1;
    }
    if (!dyn_method_is_adaptive(s->method) && !(s->step > 0 && isfinite(s->step))) {
        snprintf(err, errlen, "fixed-step method %s needs a step > 0 (got %g)", s->method->name,
                 s->step);
        return -1;
    }
    if (dyn_method_is_adaptive(s->method) && !(s->step >= 0 && isfinite(s->step))) {
        snprintf(err, errlen, "the sample step must be >= 0 (got %g)", s->step);
        return -1;
    }
    for (int v = 0; v < s->n_vars; v++) {
        const dyn_sweep_var *x = &s->vars[v];
        const int lim = x->kind == DYN_SWEEP_PARAM ? m->n_params : m->n_states;
        if ((x->kind != DYN_SWEEP_PARAM && x->kind != DYN_SWEEP_STATE) || x->index < 0 ||
            x->index >= lim) {
            snprintf(err, errlen, "column %d of the run table names no parameter or state", v);
            return -1;
        }
    }
    for (int r = 0; r < s->n_reduce; r++) {
        const dyn_reduce *rd = &s->reduce[r];
        const int ev = rd->op == DYN_REDUCE_EVENT || rd->op == DYN_REDUCE_COUNT;
        const int lim = rd->source == DYN_SOURCE_STATE    ? m->n_states
                        : rd->source == DYN_SOURCE_OUTPUT ? m->n_outputs
                        : rd->source == DYN_SOURCE_EVENT  ? m->n_events
                                                          : 0;
        if (rd->index < 0 || rd->index >= lim || (ev != (rd->source == DYN_SOURCE_EVENT)) ||
            (int)rd->op < 0 || rd->op > DYN_REDUCE_COUNT ||
            (rd->source == DYN_SOURCE_OUTPUT && !m->compute_outputs)) {
            snprintf(err, errlen, "reduction %d names nothing of model %s it can reduce", r,
                     m->name);
            return -1;
        }
    }
    for (int k = 0; k < s->n_stop; k++)
        if (s->stop[k] < 0 || s->stop[k] >= m->n_events) {
            snprintf(err, errlen, "stop event %d is not an event of %s", s->stop[k], m->name);
            return -1;
        }
    if (s->series && (s->n_series < 1 || s->series_every < 1 ||
                      (dyn_method_is_adaptive(s->method) && !(s->step > 0)))) {
        snprintf(err, errlen, "time series of the runs need n_series >= 1, series_every >= 1 "
                              "and, with an adaptive method, a sample step > 0");
        return -1;
    }
    if (m->n_noise > 0 && (s->noise_method < DYN_SDE_EM || s->noise_method > DYN_SDE_SRIW1)) {
        snprintf(err, errlen, "model %s has noise: noise_method must be DYN_SDE_EM, "
                              "DYN_SDE_RKMIL, DYN_SDE_SRIW1 or DYN_SDE_MAP", m->name);
        return -1;
    }
    if (!dyn_method_is_adaptive(s->method)) {
        dyn_grid g;
        if (dyn_grid_plan(s->t0, s->t1, s->step, s->end, &g, err, errlen))
            return -1;
        if (dyn_method_is_map(s->method) && g.partial) {
            snprintf(err, errlen,
                     "a discrete map takes whole steps: [%g, %g] is not a whole number of "
                     "steps of %g",
                     s->t0, s->t1, s->step);
            return -1;
        }
    }
    return 0;
}

/* The events to locate: those reduced, those that stop a run, the model's resets. */
static int plan_events(plan *p)
{
    const dyn_sweep *s = p->s;
    const dyn_model *m = p->m;
    p->events = malloc((size_t)(m->n_events + 1) * sizeof *p->events);
    p->event_model = malloc((size_t)(m->n_events + 1) * sizeof *p->event_model);
    if (!p->events || !p->event_model)
        return -1;
    for (int e = 0; e < m->n_events; e++) {
        int used = m->events[e].reset != NULL, stop = 0;
        for (int r = 0; r < s->n_reduce; r++)
            used |= s->reduce[r].source == DYN_SOURCE_EVENT && s->reduce[r].index == e;
        for (int k = 0; k < s->n_stop; k++)
            stop |= s->stop[k] == e;
        if (!used && !stop)
            continue;
        p->events[p->n_events] = m->events[e];
        p->events[p->n_events].terminal = stop;
        p->event_model[p->n_events++] = e;
    }
    return 0;
}

static int plan_make(plan *p, const dyn_sweep *s)
{
    const dyn_model *m = s->model;
    p->s = s;
    p->m = m;
    for (int r = 0; r < s->n_reduce; r++) {
        const dyn_reduce *rd = &s->reduce[r];
        if (is_sample_op(rd->op)) {
            p->need_samples = 1;
            p->samples_outputs |= rd->source == DYN_SOURCE_OUTPUT;
        } else if (rd->op == DYN_REDUCE_FINAL) {
            p->final_outputs |= rd->source == DYN_SOURCE_OUTPUT;
        }
    }
    p->need_samples |= m->bound > 0 || s->series != NULL;
    if (plan_events(p))
        return -1;
    if (m->n_noise > 0) {
        p->noise = 1;
        p->work_size = dyn_sde_work_size(m->n_states, m->n_noise, p->n_events);
        return 0;
    }
    const int adaptive = dyn_method_is_adaptive(s->method);
    p->use_solve = adaptive || p->n_events > 0;
    const long every = s->progress_steps > 0 ? s->progress_steps : 65536;
    if (p->use_solve) {
        dyn_solve_opts *o = &p->solve;
        o->rtol = s->rtol;
        o->atol = s->atol;
        o->rtolv = s->rtolv;
        o->atolv = s->atolv;
        o->end = s->end;
        o->max_steps = s->max_steps; /* fixed steps: a grid of more is refused at once */
        if (adaptive) {
            o->initial_step = s->initial_step;
            o->max_step = s->max_step;
            if (p->need_samples && s->step > 0)
                o->out_step = s->step;
        } else {
            o->h = s->step;
            int resets = 0;
            for (int e = 0; e < m->n_events; e++)
                resets |= m->events[e].reset != NULL;
            if (resets)
                o->out_step = s->step; /* the grid, without a sample at each reset */
        }
        o->output = p->need_samples ? on_sample : NULL;
        o->events = p->events;
        o->n_events = p->n_events;
        o->xppaut_globals = m->xppaut_globals;
        o->on_event = p->n_events > 0 ? on_event : NULL;
        o->jacobian = m->jacobian;
        o->jac_banded = m->jac_banded;
        o->jac_lower = m->jac_lower;
        o->jac_upper = m->jac_upper;
        o->jacobian_band = m->jacobian_band;
        o->band_solver = s->band_solver;
        /* sparse matrices as dyn_solve takes them; the solver is each worker's */
        p->sparse = dyn_method_is_stiff(s->method) && s->sparse_open && !m->jac_banded &&
                    m->jac_pattern.nnz > 0;
        if (p->sparse && !m->jacobian_sparse) { /* differences in groups of columns */
            p->groups = malloc((size_t)m->n_states * sizeof *p->groups);
            if (!p->groups || (o->jac_n_groups = dyn_sparse_groups(&m->jac_pattern,
                                                                   p->groups)) < 1)
                return -1;
            o->jac_groups = p->groups;
        }
        const dyn_sparse_solver sized = {0};
        if (p->sparse) {
            o->jac_sparse = m->jac_pattern;
            o->jacobian_sparse = m->jacobian_sparse;
            o->sparse_solver = &sized;
        }
        o->progress = run_progress;
        o->progress_steps = every;
        p->work_size = dyn_solve_work_size(s->method, m->n_states, o);
        o->sparse_solver = NULL;
        p->iwork_size = dyn_solve_iwork_size(s->method, m->n_states);
    } else {
        dyn_fixed_opts *o = &p->fixed;
        o->end = s->end;
        o->max_steps = s->max_steps;
        o->output = p->need_samples ? on_sample : NULL;
        o->progress = run_progress;
        o->progress_steps = every;
        p->work_size = dyn_fixed_work_size(s->method, m->n_states);
    }
    return p->work_size == 0 ? -1 : 0;
}

static void worker_free(worker *w)
{
    free(w->par);
    free(w->y0);
    free(w->y);
    free(w->out);
    free(w->work);
    free(w->iwork);
    if (w->sparse_open && w->p->s->sparse_close)
        w->p->s->sparse_close(&w->sparse);
    free(w->acc);
    free(w->aux);
}

static int worker_make(worker *w, const plan *p)
{
    const dyn_model *m = p->m;
    const size_t nr = (size_t)p->s->n_reduce + 1;
    memset(w, 0, sizeof *w);
    w->p = p;
    w->par = calloc(1, m->par_size ? m->par_size : 1);
    w->y0 = calloc((size_t)m->n_states, sizeof *w->y0);
    w->y = calloc((size_t)m->n_states, sizeof *w->y);
    w->out = calloc((size_t)m->n_outputs + 1, sizeof *w->out);
    w->work = calloc(p->work_size, sizeof *w->work);
    w->iwork = p->iwork_size ? calloc(p->iwork_size, sizeof *w->iwork) : NULL;
    w->acc = calloc(nr, sizeof *w->acc);
    w->aux = calloc(nr, sizeof *w->aux);
    if (!w->par || !w->y0 || !w->y || !w->out || !w->work || (p->iwork_size && !w->iwork) ||
        !w->acc || !w->aux)
        return -1;
    if (p->sparse) {
        if (p->s->sparse_open(&w->sparse))
            return -1;
        w->sparse_open = 1;
    }
    return 0;
}

int dyn_sweep_run(const dyn_sweep *s, double *results, int *status, char *err, size_t errlen)
{
    char dummy[8];
    if (!err) {
        err = dummy;
        errlen = sizeof dummy;
    }
    err[0] = '\0';
    if (!s || (s->n_runs > 0 && ((s->n_reduce > 0 && !results) || !status))) {
        snprintf(err, errlen, "a sweep needs its description, results and status arrays");
        return DYN_ERR_ARG;
    }
    if (check(s, err, errlen))
        return DYN_ERR_ARG;
    const dyn_model *m = s->model;
    long todo = 0;
    for (long i = 0; i < s->n_runs; i++)
        todo += !(s->skip && s->skip[i]);
    plan p;
    memset(&p, 0, sizeof p);
    void *base = NULL;
    if (!s->par) {
        base = calloc(1, m->par_size ? m->par_size : 1);
        if (!base) {
            snprintf(err, errlen, "out of memory");
            return DYN_ERR_CAPACITY;
        }
        if (dyn_model_default_params(m, base, err, errlen)) {
            free(base);
            return DYN_ERR_ARG;
        }
    }
    p.par = s->par ? s->par : base;
    int nt = dyn_sweep_threads(s->threads);
    if (nt > todo)
        nt = todo > 0 ? (int)todo : 1;
    worker *ws = calloc((size_t)nt, sizeof *ws);
    int rc = DYN_OK;
    if (!ws || plan_make(&p, s)) {
        snprintf(err, errlen, "out of memory");
        rc = DYN_ERR_CAPACITY;
    }
    for (int t = 0; t < nt && rc == DYN_OK; t++)
        if (worker_make(&ws[t], &p)) {
            snprintf(err, errlen, "out of memory");
            rc = DYN_ERR_CAPACITY;
        }
    if (rc == DYN_OK && todo > 0) {
        long done = 0;
        const long n_runs = s->n_runs;
        OMP(parallel num_threads(nt))
        {
#ifdef _OPENMP
            worker *w = &ws[omp_get_thread_num()];
#else
            worker *w = &ws[0];
#endif
            OMP(for schedule(dynamic, 1))
            for (long i = 0; i < n_runs; i++) {
                if (s->skip && s->skip[i])
                    continue;
                double *row = results ? results + (size_t)i * (size_t)s->n_reduce : NULL;
                int st = DYN_SWEEP_NOT_RUN;
                if (!stopped(&p) && s->cancel && s->cancel(s->cancel_ctx))
                    set_stop(&p);
                if (stopped(&p))
                    nan_row(row, s->n_reduce);
                else
                    st = run_one(w, i, row);
                status[i] = st;
                if (st == DYN_SWEEP_NOT_RUN) {
                    set_stop(&p);
                    continue;
                }
                if (s->progress) {
                    OMP(critical(dyn_sweep_progress))
                    {
                        done++;
                        if (s->progress(i, st, done, todo, s->progress_ctx))
                            set_stop(&p);
                    }
                }
            }
        }
        if (p.stop) {
            rc = DYN_CANCELLED;
            snprintf(err, errlen, "the sweep was cancelled");
        }
    }
    if (ws)
        for (int t = 0; t < nt; t++)
            worker_free(&ws[t]);
    free(ws);
    free(p.events);
    free(p.event_model);
    free(p.groups);
    free(base);
    return rc;
}
