/* SPDX-License-Identifier: BSD-3-Clause */
/* dyn_ivp_solve and dyn_ivp_solve_model: the whole solution of an initial value problem in
 * arrays the library allocates, in the manner of SciPy's solve_ivp (its OdeResult) and
 * MATLAB's ode45, on top of dyn_solve. The arrays grow by doubling from dyn_solve's output
 * and event callbacks and the dense-output recorder's grow callback (between steps; the
 * step loop itself does not allocate). Running out of memory there stops the solve and
 * keeps what was stored.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/io.h" /* dyn_shortest: numbers in messages */
#include "dynkit/ivp.h"

typedef struct ivp_ctx {
    dyn_ivp_solution *sol;
    long cap_t, cap_ev;
    int oom;
} ivp_ctx;

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static void set_status(dyn_ivp_solution *sol, int status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(sol->message, sizeof sol->message, fmt, ap);
    va_end(ap);
    sol->status = status;
    sol->result.status = status;
    memcpy(sol->result.message, sol->message, sizeof sol->message);
}

/* *p (cap elements of size bytes) grown to hold at least need; 0 on success. */
static int grow(void **p, long *cap, long need, size_t size)
{
    if (need <= *cap)
        return 0;
    long c = *cap > 0 ? *cap : 64;
    while (c < need)
        c *= 2;
    void *q = realloc(*p, (size_t)c * size);
    if (!q)
        return 1;
    *p = q;
    *cap = c;
    return 0;
}

static int on_output(long k, double t, const double *y, void *ctx)
{
    (void)k;
    ivp_ctx *c = ctx;
    dyn_ivp_solution *s = c->sol;
    const size_t n = (size_t)s->n;
    if (s->n_t >= c->cap_t) {
        long cap = c->cap_t;
        void *tp = s->t;
        if (grow(&tp, &cap, s->n_t + 1, sizeof *s->t)) {
            c->oom = 1;
            return 1;
        }
        s->t = tp;
        long cap_y = c->cap_t;
        void *yp = s->y;
        if (grow(&yp, &cap_y, s->n_t + 1, n * sizeof *s->y)) {
            c->oom = 1;
            return 1;
        }
        s->y = yp;
        c->cap_t = cap < cap_y ? cap : cap_y;
    }
    s->t[s->n_t] = t;
    memcpy(s->y + (size_t)s->n_t * n, y, n * sizeof *y);
    s->n_t++;
    return 0;
}

static int on_event(int index, double t, const double *y, int direction, void *ctx)
{
    ivp_ctx *c = ctx;
    dyn_ivp_solution *s = c->sol;
    const size_t n = (size_t)s->n;
    if (s->n_events >= c->cap_ev) {
        const long need = s->n_events + 1;
        long a = c->cap_ev, b = c->cap_ev, d = c->cap_ev, e = c->cap_ev;
        void *pi = s->event_index, *pd = s->event_direction, *pt = s->t_events,
             *py = s->y_events;
        const int bad = grow(&pi, &a, need, sizeof *s->event_index);
        s->event_index = pi;
        const int bad2 = bad || grow(&pd, &b, need, sizeof *s->event_direction);
        s->event_direction = pd;
        const int bad3 = bad2 || grow(&pt, &d, need, sizeof *s->t_events);
        s->t_events = pt;
        const int bad4 = bad3 || grow(&py, &e, need, n * sizeof *s->y_events);
        s->y_events = py;
        if (bad4) {
            c->oom = 1;
            return 1; /* terminal: the solve stops here, marked out of memory below */
        }
        c->cap_ev = a;
    }
    s->event_index[s->n_events] = index;
    s->event_direction[s->n_events] = direction;
    s->t_events[s->n_events] = t;
    memcpy(s->y_events + (size_t)s->n_events * n, y, n * sizeof *y);
    s->n_events++;
    return 0;
}

static int grow_record(dyn_dense_record *rec, void *ctx)
{
    ivp_ctx *c = ctx;
    long cap = rec->capacity;
    void *p = rec->data;
    if (grow(&p, &cap, rec->count + 1, dyn_dense_record_block(rec->n, rec->degree) *
                                           sizeof *rec->data)) {
        c->oom = 1;
        return 1;
    }
    rec->data = p;
    rec->capacity = cap;
    return 0;
}

/* The solve behind both entry points; sol is allocated, n set. */
static void run(dyn_ivp_solution *sol, const dyn_tableau *m, dyn_rhs_fn f, void *par,
                double t0, double t1, const double *y0, const dyn_ivp_opts *o)
{
    const int n = sol->n;
    dyn_solve_opts so = {0};
    so.rtol = o->rtol;
    so.atol = o->atol;
    so.rtolv = o->rtolv;
    so.atolv = o->atolv;
    so.h = o->h;
    so.initial_step = o->first_step;
    so.max_step = o->max_step;
    so.max_steps = o->max_steps;
    so.out_times = o->t_eval;
    so.n_out_times = o->t_eval ? o->n_eval : 0;
    so.events = o->events;
    so.n_events = o->events ? o->n_events : 0;
    so.xppaut_globals = o->xppaut_globals;
    so.jacobian = o->jacobian;
    so.jac_banded = o->jac_banded;
    so.jac_lower = o->jac_lower;
    so.jac_upper = o->jac_upper;
    so.jacobian_band = o->jacobian_band;
    ivp_ctx c = {sol, 0, 0, 0};
    so.output = on_output;
    so.output_ctx = &c;
    so.on_event = on_event;
    so.event_ctx = &c;
    if (o->dense_output) {
        sol->dense.grow = grow_record;
        sol->dense.grow_ctx = &c;
        dyn_dense_record_init(&sol->dense, n, dyn_method_dense_degree(m), NULL, 0);
        so.record = &sol->dense;
    }
    if (o->t_eval && o->n_eval > 0) {
        /* the samples are known: one allocation (and one more for a terminal event) */
        void *tp = NULL, *yp = NULL;
        long a = 0, b = 0;
        if (grow(&tp, &a, o->n_eval + 1, sizeof *sol->t) ||
            grow(&yp, &b, o->n_eval + 1, (size_t)n * sizeof *sol->y)) {
            free(tp);
            free(yp);
            set_status(sol, DYN_ERR_CAPACITY, "out of memory for %ld samples", o->n_eval);
            return;
        }
        sol->t = tp;
        sol->y = yp;
        c.cap_t = a < b ? a : b;
    }
    const size_t wsize = dyn_solve_work_size(m, n, &so), isize = dyn_solve_iwork_size(m, n);
    double *work = wsize ? malloc(wsize * sizeof *work) : NULL;
    int *iwork = isize ? malloc(isize * sizeof *iwork) : NULL;
    if (!wsize || !work || (isize && !iwork)) {
        free(work);
        free(iwork);
        if (!wsize)
            set_status(sol, DYN_ERR_ARG, "method %s cannot solve a system of %d states",
                       m->name, n);
        else
            set_status(sol, DYN_ERR_CAPACITY, "out of memory for the workspace");
        return;
    }
    so.iwork = iwork;
    dyn_solve(m, &(dyn_system){f, n, par}, t0, t1, y0, NULL, work, &so, &sol->result);
    free(work);
    free(iwork);
    if (o->dense_output) {
        sol->dense.grow = NULL;
        sol->dense.grow_ctx = NULL;
    }
    sol->stats = sol->result.stats;
    sol->terminated = sol->result.stopped_by_event && !c.oom;
    if (c.oom) {
        set_status(sol, DYN_ERR_CAPACITY,
                   "out of memory after %ld samples and %ld events: the solution up to t = "
                   "%s is kept",
                   sol->n_t, sol->n_events,
                   dyn_shortest(sol->n_t > 0 ? sol->t[sol->n_t - 1] : t0).s);
    } else {
        sol->status = sol->result.status;
        memcpy(sol->message, sol->result.message, sizeof sol->message);
    }
}

static dyn_ivp_solution *new_solution(int n)
{
    dyn_ivp_solution *sol = calloc(1, sizeof *sol);
    if (sol) {
        sol->n = n > 0 ? n : 0;
        sol->result.event_index = -1;
        sol->result.fail_index = -1;
    }
    return sol;
}

static const dyn_tableau *find_method(dyn_ivp_solution *sol, const char *name)
{
    const dyn_tableau *m = dyn_method_find(name);
    if (!m) {
        char names[512];
        set_status(sol, DYN_ERR_ARG, "unknown method '%s' (accepted: %s)", name,
                   dyn_method_names(names, sizeof names));
    }
    return m;
}

static int check_args(dyn_ivp_solution *sol, const dyn_tableau *m, int n, const double *y0,
                      double h)
{
    if (n <= 0)
        set_status(sol, DYN_ERR_ARG, "number of states %d is not accepted: it must be >= 1", n);
    else if (!y0)
        set_status(sol, DYN_ERR_ARG, "no initial state given");
    else if (!dyn_method_is_adaptive(m) && !(h > 0.0))
        set_status(sol, DYN_ERR_ARG,
                   "method %s takes fixed steps: give the step opts.h > 0 (or an adaptive "
                   "method such as dp45)",
                   m->name);
    return sol->status;
}

dyn_ivp_solution *dyn_ivp_solve(dyn_rhs_fn f, int n, void *par, double t0, double t1,
                                 const double *y0, const dyn_ivp_opts *opts)
{
    static const dyn_ivp_opts defaults;
    const dyn_ivp_opts *o = opts ? opts : &defaults;
    dyn_ivp_solution *sol = new_solution(n);
    if (!sol)
        return NULL;
    sol->result.t = t0;
    const dyn_tableau *m = find_method(sol, o->method ? o->method : "dp45");
    if (!m || check_args(sol, m, n, y0, o->h))
        return sol;
    run(sol, m, f, par, t0, t1, y0, o);
    return sol;
}

dyn_ivp_solution *dyn_ivp_solve_model(const dyn_model *model, const void *par,
                                       const double *y0, const double *tspan,
                                       const dyn_ivp_opts *opts)
{
    static const dyn_ivp_opts defaults;
    const dyn_ivp_opts *o = opts ? opts : &defaults;
    if (!model) {
        dyn_ivp_solution *sol = new_solution(0);
        if (sol)
            set_status(sol, DYN_ERR_ARG, "no model given");
        return sol;
    }
    const int n = model->n_states;
    dyn_ivp_solution *sol = new_solution(n);
    if (!sol)
        return NULL;
    const double t0 = tspan ? tspan[0] : model->t0, t1 = tspan ? tspan[1] : model->t1;
    sol->result.t = t0;
    const dyn_tableau *m =
        find_method(sol, o->method    ? o->method
                         : model->method ? model->method
                                         : DYN_MODEL_METHOD);
    if (!m)
        return sol;
    /* the parameters: a copy (prepared defaults when par is NULL) */
    void *p = calloc(1, model->par_size > 0 ? model->par_size : 1);
    double *y0m = malloc((size_t)(n > 0 ? n : 1) * sizeof *y0m);
    dyn_event *ev = malloc((size_t)(o->n_events + model->n_events + 1) * sizeof *ev);
    if (!p || !y0m || !ev) {
        free(p);
        free(y0m);
        free(ev);
        set_status(sol, DYN_ERR_CAPACITY, "out of memory for the model's parameters");
        return sol;
    }
    char err[192];
    if (par)
        memcpy(p, par, model->par_size);
    else if (dyn_model_default_params(model, p, err, sizeof err))
        set_status(sol, DYN_ERR_ARG, "model %s: %s", model->name, err);
    if (sol->status == DYN_OK) {
        if (y0)
            memcpy(y0m, y0, (size_t)n * sizeof *y0m);
        else
            dyn_model_initial_state(model, p, y0m);
        dyn_ivp_opts mo = *o;
        if (!(mo.h > 0.0))
            mo.h = model->step;
        if (mo.rtol == 0.0)
            mo.rtol = model->rtol > 0.0 ? model->rtol : DYN_MODEL_RTOL;
        if (mo.atol == 0.0)
            mo.atol = model->atol > 0.0 ? model->atol : DYN_MODEL_ATOL;
        if (!mo.jacobian)
            mo.jacobian = model->jacobian;
        if (!mo.jac_banded && model->jac_banded) {
            mo.jac_banded = 1;
            mo.jac_lower = model->jac_lower;
            mo.jac_upper = model->jac_upper;
            mo.jacobian_band = model->jacobian_band;
        }
        /* events: those asked for, or the model's; then its resets not among them */
        int ne = 0;
        const dyn_event *given = o->events && o->n_events > 0 ? o->events : model->events;
        const int n_given = o->events && o->n_events > 0 ? o->n_events : model->n_events;
        for (int i = 0; given && i < n_given; i++)
            ev[ne++] = given[i];
        for (int i = 0; i < model->n_events; i++) {
            if (!model->events[i].reset)
                continue;
            int in = 0;
            for (int j = 0; j < n_given; j++)
                in |= given == model->events ? 1
                      : given[j].name && model->events[i].name &&
                          strcmp(given[j].name, model->events[i].name) == 0;
            if (!in) {
                ev[ne] = model->events[i];
                ev[ne++].terminal = 0;
            }
        }
        mo.events = ne > 0 ? ev : NULL;
        mo.n_events = ne;
        mo.xppaut_globals = mo.xppaut_globals || model->xppaut_globals;
        if (!check_args(sol, m, n, y0m, mo.h))
            run(sol, m, model->rhs, p, t0, t1, y0m, &mo);
    }
    free(p);
    free(y0m);
    free(ev);
    return sol;
}

int dyn_ivp_eval(const dyn_ivp_solution *sol, double t, double *y)
{
    if (!sol || sol->dense.count < 1)
        return DYN_ERR_ARG;
    return dyn_dense_record_eval(&sol->dense, t, y);
}

void dyn_ivp_free(dyn_ivp_solution *sol)
{
    if (!sol)
        return;
    free(sol->t);
    free(sol->y);
    free(sol->event_index);
    free(sol->event_direction);
    free(sol->t_events);
    free(sol->y_events);
    free(sol->dense.data);
    free(sol);
}
