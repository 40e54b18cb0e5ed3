/* SPDX-License-Identifier: BSD-3-Clause */
/* The MEX gateway of dynkit for GNU Octave and MATLAB (mex.h only): the functions of the
 * package folder +dynkit call it with a mode as the first argument.
 *   [tout, yout] = dynkit_mex('integrate', method, odefun, tspan, Ts, y0, par)
 *       the homework's convention (Integrate_Euler, ..._RungeKutta4): dyn_fixed_solve on
 *       tspan(1):Ts:tspan(end), odefun(t, y, par) called with a column y;
 *   [t, y, te, ye, ie, stats] = dynkit_mex('ivp', method, odefun, tspan, y0, options)
 *       ode45's convention on dyn_ivp_solve: every step (Refine points in each) for a
 *       two-element tspan, else the times of tspan; odeset's RelTol, AbsTol, Events,
 *       MaxStep, InitialStep, Refine, Stats;
 *   result = dynkit_mex('run', model, options)
 *       a model by name or path run through dyn_run (dynkit/run.h), as `dynkit run` does.
 * An error raised by odefun or the events function is trapped (mexCallMATLABWithTrap): it
 * stops the solve, the memory is released, and the failed call is made once more, untrapped,
 * which raises the function's own error; bad
 * arguments raise errors with the identifier dynkit:... naming them. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mex.h"

#include "../common/event_slots.h"
#include "../common/model_open.h"
#include "../common/samples.h"
#include "dynkit/dynkit.h"

enum { MAX_EVENTS = DKB_MAX_EVENTS };

/* the Octave/MATLAB function and its state during a solve */
typedef struct mfun {
    const mxArray *fun, *par, *events;
    int n, failed, has_par;
    /* the call that raised: made again once the solver is gone, to raise the same error */
    const mxArray *fail_fn;
    double fail_t, *fail_y;
    int fail_nlhs;
    /* the events function's last values, for its components one by one */
    double ev_t, *ev_y, ev_value[MAX_EVENTS];
    int ev_have, ev_count;
    double ev_terminal[MAX_EVENTS], ev_direction[MAX_EVENTS];
} mfun;

static void fail(const char *id, const char *fmt, const char *what)
{
    mexErrMsgIdAndTxt(id, fmt, what);
}

static mxArray *column(const double *y, int n)
{
    mxArray *a = mxCreateDoubleMatrix((mwSize)n, 1, mxREAL);
    memcpy(mxGetPr(a), y, (size_t)n * sizeof *y);
    return a;
}

/* fn(t, y[, par]) with nlhs outputs into plhs: 0, or 1 when fn raised, its exception kept in
 * f->fail_* (mexCallMATLABWithTrap: the error does not unwind through the solver) */
static int call(mfun *f, const mxArray *fn, double t, const double *y, int nlhs,
                mxArray **plhs)
{
    mxArray *in[4] = {(mxArray *)fn, mxCreateDoubleScalar(t), column(y, f->n),
                      (mxArray *)f->par};
    mxArray *error = mexCallMATLABWithTrap(nlhs, plhs, f->has_par ? 4 : 3, in, "feval");
    mxDestroyArray(in[1]);
    mxDestroyArray(in[2]);
    if (error) {
        mxDestroyArray(error);
        f->failed = 1;
        f->fail_fn = fn;
        f->fail_t = t;
        f->fail_nlhs = nlhs;
        memcpy(f->fail_y, y, (size_t)f->n * sizeof *y);
    }
    return error != NULL;
}

static int rhs(double t, const double *y, double *dydt, void *par)
{
    mfun *f = par;
    mxArray *out = NULL;
    if (f->failed || call(f, f->fun, t, y, 1, &out))
        return 1;
    if (!mxIsDouble(out) || mxIsComplex(out) || (int)mxGetNumberOfElements(out) != f->n) {
        f->failed = 2;
        mxDestroyArray(out);
        return 1;
    }
    memcpy(dydt, mxGetPr(out), (size_t)f->n * sizeof *dydt);
    mxDestroyArray(out);
    return 0;
}

/* [value, isterminal, direction] = events(t, y): evaluated once per (t, y) */
static int events_at(mfun *f, double t, const double *y)
{
    if (f->ev_have && t == f->ev_t && memcmp(y, f->ev_y, (size_t)f->n * sizeof *y) == 0)
        return 0;
    mxArray *out[3] = {NULL, NULL, NULL};
    if (call(f, f->events, t, y, 3, out))
        return 1;
    const int k = (int)mxGetNumberOfElements(out[0]);
    if (k != f->ev_count || !mxIsDouble(out[0])) {
        f->failed = 3;
        for (int i = 0; i < 3; i++)
            mxDestroyArray(out[i]);
        return 1;
    }
    memcpy(f->ev_value, mxGetPr(out[0]), (size_t)k * sizeof(double));
    for (int i = 0; i < 3; i++)
        mxDestroyArray(out[i]);
    f->ev_t = t;
    memcpy(f->ev_y, y, (size_t)f->n * sizeof *y);
    f->ev_have = 1;
    return 0;
}

static double event(int k, double t, const double *y, void *par)
{
    mfun *f = par;
    if (f->failed || events_at(f, t, y))
        return NAN;
    return f->ev_value[k];
}

DKB_EVENT_SLOTS(event)

/* after a solve that odefun or events stopped: their error again, or what was wrong */
static void raise_callback(mfun *f)
{
    if (f->failed == 2)
        mexErrMsgIdAndTxt("dynkit:odefun", "odefun must return a real column of %d values",
                          f->n);
    if (f->failed == 3)
        mexErrMsgIdAndTxt("dynkit:events", "the events function must return as many values "
                                           "on every call (%d at its first)",
                          f->ev_count);
    /* the trapped exception of Octave names only feval: the failed call once more, untrapped,
     * raises the function's own error (with its identifier and stack) */
    mxArray *out[3] = {NULL, NULL, NULL};
    mxArray *in[4] = {(mxArray *)f->fail_fn, mxCreateDoubleScalar(f->fail_t),
                      column(f->fail_y, f->n), (mxArray *)f->par};
    mexCallMATLAB(f->fail_nlhs, out, f->has_par ? 4 : 3, in, "feval");
    mexErrMsgIdAndTxt("dynkit:odefun", "odefun or the events function failed at t = %g, and "
                                       "not when called again there",
                      f->fail_t);
}

static char *string_arg(const mxArray *a, const char *what)
{
    if (!mxIsChar(a))
        fail("dynkit:argument", "%s must be a string", what);
    return mxArrayToString(a);
}

static const double *vector_arg(const mxArray *a, const char *what, int *n)
{
    if (!mxIsDouble(a) || mxIsComplex(a) || mxIsSparse(a))
        fail("dynkit:argument", "%s must be a real vector of doubles", what);
    *n = (int)mxGetNumberOfElements(a);
    const double *v = mxGetPr(a);
    for (int i = 0; i < *n; i++)
        if (!isfinite(v[i]))
            fail("dynkit:argument", "%s holds a value that is not a finite number", what);
    return v;
}

static double option(const mxArray *opts, const char *name, double dflt)
{
    const mxArray *v = opts && mxIsStruct(opts) ? mxGetField(opts, 0, name) : NULL;
    if (!v || mxIsEmpty(v))
        return dflt;
    if (!mxIsNumeric(v) && !mxIsLogical(v))
        fail("dynkit:option", "option %s must be a number", name);
    return mxGetScalar(v);
}

/* ---- the homework's convention ---- */
typedef struct grid_out {
    double *t, *y;
    long count, cap;
    int n;
} grid_out;

static int keep(long k, double t, const double *y, void *ctx)
{
    (void)k;
    grid_out *g = ctx;
    if (g->count >= g->cap)
        return 1;
    g->t[g->count] = t;
    for (int i = 0; i < g->n; i++) /* yout is column-major: state i of sample k */
        g->y[(size_t)i * (size_t)g->cap + (size_t)g->count] = y[i];
    g->count++;
    return 0;
}

static void integrate(int nlhs, mxArray *plhs[], int nrhs, const mxArray *prhs[])
{
    if (nrhs < 6 || nrhs > 7)
        fail("dynkit:argument", "%s", "usage: [tout, yout] = dynkit.integrate(method, odefun, "
                                      "tspan, Ts, y0, par)");
    char *name = string_arg(prhs[1], "method");
    const dyn_tableau *m = dyn_method_find(name);
    if (!m || dyn_method_is_adaptive(m))
        fail("dynkit:method", "method '%s': a fixed-step method (euler, heun, rk2, rk4, ...) "
                              "is needed",
             name);
    int nt, one, n;
    const double *tspan = vector_arg(prhs[3], "tspan", &nt);
    const double *h = vector_arg(prhs[4], "Ts", &one);
    const double *y0 = vector_arg(prhs[5], "y0", &n);
    if (nt < 2 || one != 1 || !(h[0] > 0) || !(tspan[nt - 1] > tspan[0]))
        fail("dynkit:argument", "%s", "tspan = [t0 t1] with t1 > t0 and a step Ts > 0");
    /* the seed's grid: tout = (tspan(1):Ts:tspan(end))' */
    const double t0 = tspan[0], t1 = tspan[nt - 1];
    const long steps = (long)floor((t1 - t0) / h[0] * (1.0 + 1e-12));
    const double t_end = t0 + (double)steps * h[0];
    mfun f = {.fun = prhs[2], .par = nrhs == 7 ? prhs[6] : NULL, .n = n, .has_par = nrhs == 7};
    f.fail_y = mxMalloc((size_t)(n > 0 ? n : 1) * sizeof(double));
    const dyn_system sys = {rhs, n, &f};
    grid_out g = {mxMalloc((size_t)(steps + 1) * sizeof(double)),
                  mxMalloc((size_t)(steps + 1) * (size_t)n * sizeof(double)), 0, steps + 1, n};
    double *work = mxMalloc(dyn_fixed_work_size(m, n) * sizeof *work);
    double *y = mxMalloc((size_t)n * sizeof *y);
    dyn_fixed_opts o = {.output = keep, .output_ctx = &g};
    dyn_result res;
    if (steps > 0)
        dyn_fixed_solve(m, &sys, t0, t_end, h[0], y0, y, work, &o, &res);
    else
        keep(0, t0, y0, &g);
    if (f.failed)
        raise_callback(&f);
    plhs[0] = mxCreateDoubleMatrix((mwSize)g.count, 1, mxREAL);
    memcpy(mxGetPr(plhs[0]), g.t, (size_t)g.count * sizeof(double));
    if (nlhs > 1) {
        plhs[1] = mxCreateDoubleMatrix((mwSize)g.count, (mwSize)n, mxREAL);
        for (int i = 0; i < n; i++)
            memcpy(mxGetPr(plhs[1]) + (size_t)i * (size_t)g.count,
                   g.y + (size_t)i * (size_t)g.cap, (size_t)g.count * sizeof(double));
    }
}

/* ---- MATLAB's ode45 convention ---- */
static mxArray *stats_struct(const dyn_ivp_solution *sol)
{
    const char *fields[] = {"nsteps", "nfailed", "nfevals", "njacevals"};
    mxArray *s = mxCreateStructMatrix(1, 1, 4, fields);
    mxSetField(s, 0, "nsteps", mxCreateDoubleScalar((double)sol->stats.accepted));
    mxSetField(s, 0, "nfailed", mxCreateDoubleScalar((double)sol->stats.rejected));
    mxSetField(s, 0, "nfevals", mxCreateDoubleScalar((double)sol->stats.rhs_calls));
    mxSetField(s, 0, "njacevals", mxCreateDoubleScalar((double)sol->stats.jac_calls));
    return s;
}

static void ivp(int nlhs, mxArray *plhs[], int nrhs, const mxArray *prhs[])
{
    if (nrhs < 5 || nrhs > 6)
        fail("dynkit:argument", "%s", "usage: [t, y] = dynkit.ode45(odefun, tspan, y0, options)");
    char *name = string_arg(prhs[1], "method");
    const dyn_tableau *m = dyn_method_find(name);
    if (!m || !dyn_method_is_adaptive(m))
        fail("dynkit:method", "method '%s': an adaptive method is needed", name);
    int nt, n;
    const double *tspan = vector_arg(prhs[3], "tspan", &nt);
    const double *y0 = vector_arg(prhs[4], "y0", &n);
    if (nt < 2 || !(tspan[nt - 1] > tspan[0]))
        fail("dynkit:argument", "%s", "tspan must be [t0 t1] with t1 > t0, or increasing times");
    for (int i = 1; i < nt; i++)
        if (!(tspan[i] > tspan[i - 1]))
            fail("dynkit:argument", "%s", "the times of tspan must increase");
    const mxArray *opts = nrhs == 6 ? prhs[5] : NULL;
    if (opts && !mxIsStruct(opts) && !mxIsEmpty(opts))
        fail("dynkit:argument", "%s", "options must be a struct (odeset) or []");
    if (opts && !mxIsStruct(opts))
        opts = NULL; /* [] */
    dyn_ivp_opts o = {0};
    o.method = m->name;
    o.rtol = option(opts, "RelTol", 1e-3);
    o.atol = option(opts, "AbsTol", 1e-6);
    o.max_step = option(opts, "MaxStep", 0.0);
    o.first_step = option(opts, "InitialStep", 0.0);
    const int refine = (int)option(opts, "Refine", 4.0);
    const int stats = opts && mxGetField(opts, 0, "Stats") &&
                      mxIsChar(mxGetField(opts, 0, "Stats")) &&
                      strcmp(mxArrayToString(mxGetField(opts, 0, "Stats")), "on") == 0;
    mfun f = {.fun = prhs[2], .n = n};
    f.ev_y = mxMalloc((size_t)(n > 0 ? n : 1) * sizeof(double));
    f.fail_y = mxMalloc((size_t)(n > 0 ? n : 1) * sizeof(double));
    dyn_event ev[MAX_EVENTS];
    const mxArray *evf = opts ? mxGetField(opts, 0, "Events") : NULL;
    if (evf && !mxIsEmpty(evf)) {
        f.events = evf;
        mxArray *out[3] = {NULL, NULL, NULL};
        const int bad = call(&f, evf, tspan[0], y0, 3, out);
        if (bad)
            raise_callback(&f);
        f.ev_count = (int)mxGetNumberOfElements(out[0]);
        if (f.ev_count > MAX_EVENTS || (int)mxGetNumberOfElements(out[1]) != f.ev_count ||
            (int)mxGetNumberOfElements(out[2]) != f.ev_count)
            fail("dynkit:events", "%s", "the events function must return value, isterminal "
                                        "and direction of the same length (at most 16)");
        for (int k = 0; k < f.ev_count; k++) {
            const double dir = mxGetPr(out[2])[k];
            ev[k] = (dyn_event){.name = "event", .g = dkb_event_slots[k],
                                .direction = dir > 0 ? 1 : dir < 0 ? -1 : 0,
                                .terminal = mxGetPr(out[1])[k] != 0.0};
        }
        o.events = ev;
        o.n_events = f.ev_count;
    }
    /* the output times: tspan's, or every step refined by its dense output */
    o.t_eval = nt > 2 ? tspan : NULL;
    o.n_eval = nt > 2 ? nt : 0;
    o.dense_output = nt == 2 && refine > 1;
    dyn_ivp_solution *sol = dyn_ivp_solve(rhs, n, &f, tspan[0], tspan[nt - 1], y0, &o);
    if (!sol)
        mexErrMsgIdAndTxt("dynkit:memory", "out of memory");
    if (f.failed) {
        dyn_ivp_free(sol);
        raise_callback(&f);
    }
    if (sol->status != DYN_OK && sol->status != DYN_ERR_ARG)
        mexWarnMsgIdAndTxt("dynkit:failed", "%s (the solution up to t = %g is returned)",
                           sol->message, sol->result.t);
    if (sol->status == DYN_ERR_ARG) {
        char msg[256];
        snprintf(msg, sizeof msg, "%s", sol->message);
        dyn_ivp_free(sol);
        fail("dynkit:argument", "%s", msg);
    }
    /* the rows: each sample, and refine - 1 points inside each step before it */
    const int r = o.dense_output ? refine : 1;
    const long rows = sol->n_t > 0 ? 1 + (sol->n_t - 1) * r : 0;
    plhs[0] = mxCreateDoubleMatrix((mwSize)rows, 1, mxREAL);
    mxArray *Y = mxCreateDoubleMatrix((mwSize)rows, (mwSize)n, mxREAL);
    double *T = mxGetPr(plhs[0]), *Yp = mxGetPr(Y), *yk = mxMalloc((size_t)n * sizeof(double));
    long row = 0;
    for (long k = 0; k < sol->n_t; k++) {
        for (int j = 1; k > 0 && j < r; j++) {
            const double t = sol->t[k - 1] + (sol->t[k] - sol->t[k - 1]) * j / r;
            dyn_ivp_eval(sol, t, yk);
            T[row] = t;
            for (int i = 0; i < n; i++)
                Yp[(size_t)i * (size_t)rows + (size_t)row] = yk[i];
            row++;
        }
        T[row] = sol->t[k];
        for (int i = 0; i < n; i++)
            Yp[(size_t)i * (size_t)rows + (size_t)row] = sol->y[(size_t)k * (size_t)n + (size_t)i];
        row++;
    }
    if (nlhs > 1)
        plhs[1] = Y;
    else
        mxDestroyArray(Y);
    if (nlhs > 2) {
        const long ne = sol->n_events;
        plhs[2] = mxCreateDoubleMatrix((mwSize)ne, 1, mxREAL);
        mxArray *ye = mxCreateDoubleMatrix((mwSize)ne, (mwSize)n, mxREAL);
        mxArray *ie = mxCreateDoubleMatrix((mwSize)ne, 1, mxREAL);
        for (long e = 0; e < ne; e++) {
            mxGetPr(plhs[2])[e] = sol->t_events[e];
            mxGetPr(ie)[e] = sol->event_index[e] + 1;
            for (int i = 0; i < n; i++)
                mxGetPr(ye)[(size_t)i * (size_t)ne + (size_t)e] =
                    sol->y_events[(size_t)e * (size_t)n + (size_t)i];
        }
        if (nlhs > 3)
            plhs[3] = ye;
        else
            mxDestroyArray(ye);
        if (nlhs > 4)
            plhs[4] = ie;
        else
            mxDestroyArray(ie);
    }
    if (nlhs > 5)
        plhs[5] = stats_struct(sol);
    if (stats)
        mexPrintf("%ld successful steps\n%ld failed attempts\n%ld function evaluations\n",
                  sol->stats.accepted, sol->stats.rejected, sol->stats.rhs_calls);
    dyn_ivp_free(sol);
}

/* ---- a model through dyn_run ---- */
typedef struct run_out {
    dkb_samples s;
    int failed; /* out of memory */
} run_out;

static int on_sample(long k, double t, const double *y, void *ctx)
{
    (void)k;
    run_out *r = ctx;
    r->failed = dkb_samples_add(&r->s, t, y, NULL);
    return r->failed;
}

static void set_values(const dyn_model *m, const mxArray *s, void *par, double *y0, int params)
{
    if (!s || mxIsEmpty(s))
        return;
    if (!mxIsStruct(s))
        fail("dynkit:option", "%s must be a struct of NAME = value", params ? "set" : "init");
    for (int f = 0; f < mxGetNumberOfFields(s); f++) {
        const char *name = mxGetFieldNameByNumber(s, f);
        const mxArray *v = mxGetFieldByNumber(s, 0, f);
        const int i = params ? dyn_model_param_index(m, name) : dyn_model_state_index(m, name);
        if (i < 0)
            mexErrMsgIdAndTxt("dynkit:option", "model %s has no %s '%s'", m->name,
                              params ? "parameter" : "state", name);
        if (!v || !mxIsNumeric(v) || mxGetNumberOfElements(v) != 1 ||
            !isfinite(mxGetScalar(v)))
            mexErrMsgIdAndTxt("dynkit:option", "%s: give a finite number", name);
        if (params)
            dyn_model_set_param(m, par, i, mxGetScalar(v));
        else
            y0[i] = mxGetScalar(v);
    }
}

static mxArray *names_cell(const dyn_var *v, int n, int units, const char *time_unit)
{
    mxArray *c = mxCreateCellMatrix(1, (mwSize)n + 1);
    mxSetCell(c, 0, mxCreateString(units ? time_unit : "t"));
    for (int i = 0; i < n; i++)
        mxSetCell(c, (mwSize)i + 1,
                  mxCreateString(units ? (v[i].unit ? v[i].unit : "1") : v[i].name));
    return c;
}

static void run(int nlhs, mxArray *plhs[], int nrhs, const mxArray *prhs[])
{
    (void)nlhs;
    if (nrhs < 2 || nrhs > 3)
        fail("dynkit:argument", "%s", "usage: result = dynkit.run(model, options)");
    char *spec = string_arg(prhs[1], "model");
    const mxArray *opts = nrhs == 3 ? prhs[2] : NULL;
    if (opts && !mxIsEmpty(opts) && !mxIsStruct(opts))
        fail("dynkit:argument", "%s", "options must be a struct");
    if (opts && !mxIsStruct(opts))
        opts = NULL;
    static dkb_model opened; /* kept open: its code stays loaded until the next model */
    char err[4096];
    dkb_model_close(&opened);
    if (dkb_model_open(spec, &opened, NULL, NULL, err, sizeof err))
        mexErrMsgIdAndTxt("dynkit:model", "%s", err);
    const dyn_model *m = opened.model;
    const mxArray *mv = opts ? mxGetField(opts, 0, "method") : NULL;
    char *method_name = mv && mxIsChar(mv) ? mxArrayToString(mv) : NULL;
    const dyn_tableau *method = dyn_run_method_find(
        method_name ? method_name : m->method ? m->method : DYN_MODEL_METHOD);
    if (!method || method == dyn_run_method_cvode())
        mexErrMsgIdAndTxt("dynkit:method", "unknown method '%s'", method_name);
    void *par = dkb_model_params(m, err, sizeof err);
    if (!par)
        mexErrMsgIdAndTxt("dynkit:model", "%s", err);
    double *y0 = mxMalloc((size_t)(2 * m->n_states + 1) * sizeof *y0), *y = y0 + m->n_states;
    set_values(m, opts ? mxGetField(opts, 0, "set") : NULL, par, NULL, 1);
    if (m->prepare && m->prepare(par, err, sizeof err)) {
        free(par);
        mexErrMsgIdAndTxt("dynkit:model", "%s", err);
    }
    dyn_model_initial_state(m, par, y0);
    set_values(m, opts ? mxGetField(opts, 0, "init") : NULL, par, y0, 0);
    dyn_run_opts o = {0};
    o.method = method;
    const mxArray *ts = opts ? mxGetField(opts, 0, "tspan") : NULL;
    int nts = 0;
    const double *tspan = ts && !mxIsEmpty(ts) ? vector_arg(ts, "tspan", &nts) : NULL;
    o.t0 = tspan && nts == 2 ? tspan[0] : m->t0;
    o.t1 = tspan && nts == 2 ? tspan[1] : m->t1;
    o.step = option(opts, "step", m->step);
    o.rtol = option(opts, "rtol", 0.0);
    o.atol = option(opts, "atol", 0.0);
    o.max_steps = dyn_method_is_adaptive(method) ? 10000000L : 0;
    const mxArray *step = opts && mxIsStruct(opts) ? mxGetField(opts, 0, "step") : NULL;
    o.at_steps = dyn_method_is_adaptive(method) && (!step || mxIsEmpty(step)) &&
                 m->samples == DYN_SAMPLES_STEPS;
    run_out out = {.s = {.n = m->n_states}};
    dkb_samples *r = &out.s;
    o.output = on_sample;
    o.output_ctx = &out;
    dyn_result res;
    const int status = dyn_run(m, par, y0, &o, y, &res);
    free(par);
    if (status < 0 || out.failed) {
        dkb_samples_free(r);
        mexErrMsgIdAndTxt("dynkit:memory", "out of memory");
    }
    if (status == DYN_ERR_ARG) {
        dkb_samples_free(r);
        mexErrMsgIdAndTxt("dynkit:option", "%s", res.message);
    }
    if (status != DYN_OK)
        mexWarnMsgIdAndTxt("dynkit:failed", "%s", res.message);
    const char *fields[] = {"t", "y", "names", "units", "status", "message"};
    mxArray *s = mxCreateStructMatrix(1, 1, 6, fields);
    mxArray *T = mxCreateDoubleMatrix((mwSize)r->count, 1, mxREAL);
    mxArray *Y = mxCreateDoubleMatrix((mwSize)r->count, (mwSize)r->n, mxREAL);
    memcpy(mxGetPr(T), r->t, (size_t)r->count * sizeof(double));
    for (long k = 0; k < r->count; k++)
        for (int i = 0; i < r->n; i++)
            mxGetPr(Y)[(size_t)i * (size_t)r->count + (size_t)k] = r->y[(size_t)k * (size_t)r->n + (size_t)i];
    dkb_samples_free(r);
    mxSetField(s, 0, "t", T);
    mxSetField(s, 0, "y", Y);
    mxSetField(s, 0, "names", names_cell(m->states, m->n_states, 0, NULL));
    mxSetField(s, 0, "units", names_cell(m->states, m->n_states, 1,
                                            m->time_unit && m->time_unit[0] ? m->time_unit : "s"));
    mxSetField(s, 0, "status", mxCreateDoubleScalar(res.status));
    mxSetField(s, 0, "message", mxCreateString(res.message));
    plhs[0] = s;
}

void mexFunction(int nlhs, mxArray *plhs[], int nrhs, const mxArray *prhs[])
{
    if (nrhs < 1 || !mxIsChar(prhs[0]))
        fail("dynkit:argument", "%s", "dynkit_mex is called by the functions of +dynkit");
    char *mode = mxArrayToString(prhs[0]);
    if (strcmp(mode, "integrate") == 0)
        integrate(nlhs, plhs, nrhs, prhs);
    else if (strcmp(mode, "ivp") == 0)
        ivp(nlhs, plhs, nrhs, prhs);
    else if (strcmp(mode, "run") == 0)
        run(nlhs, plhs, nrhs, prhs);
    else
        fail("dynkit:argument", "unknown mode '%s'", mode);
}
