/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit._core.Model: a model opened by name or path (bindings/common/model_open.c), its
 * description as a dict (info), and run(): one run through the library's entry dyn_run
 * (dynkit/run.h) — every kind of model (noise, delays, Volterra integrals, resets, CVODE
 * when built) runs as `dynkit run` runs it — with the interpreter's lock released, the
 * samples (and the model's outputs at each) returned as NumPy arrays. */
#include "core.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void model_dealloc(dkpy_model *self)
{
    dkb_model_close(&self->opened);
    Py_TYPE(self)->tp_free((PyObject *)self);
}

static void warn_python(const char *message, void *ctx)
{
    (void)ctx;
    PyErr_WarnEx(PyExc_UserWarning, message, 1);
}

static int model_init(dkpy_model *self, PyObject *args, PyObject *kwargs)
{
    static char *kw[] = {"spec", NULL};
    const char *spec;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "s", kw, &spec))
        return -1;
    dkb_model_close(&self->opened);
    char err[8192];
    if (dkb_model_open(spec, &self->opened, warn_python, NULL, err, sizeof err)) {
        PyErr_SetString(dkpy_error, err);
        return -1;
    }
    return 0;
}

static PyObject *vars(const dyn_var *v, int n)
{
    PyObject *list = PyList_New(n);
    for (int i = 0; list && i < n; i++) {
        PyObject *t = Py_BuildValue("(sss)", v[i].name, v[i].unit ? v[i].unit : "1",
                                    v[i].description ? v[i].description : "");
        if (!t) {
            Py_DECREF(list);
            return NULL;
        }
        PyList_SET_ITEM(list, i, t);
    }
    return list;
}

static PyObject *model_info(dkpy_model *self, PyObject *noargs)
{
    (void)noargs;
    const dyn_model *m = self->opened.model;
    if (!m)
        return PyErr_Format(dkpy_error, "the model is not open");
    char err[512];
    void *par = dkb_model_params(m, err, sizeof err);
    double *y0 = malloc((size_t)(m->n_states > 0 ? m->n_states : 1) * sizeof *y0);
    if (!par || !y0) {
        free(par);
        free(y0);
        return PyErr_Format(dkpy_error, "%s", par ? "out of memory" : err);
    }
    dyn_model_initial_state(m, par, y0);
    PyObject *params = PyList_New(m->n_params), *init = PyList_New(m->n_states);
    PyObject *events = PyList_New(m->n_events);
    for (int i = 0; params && i < m->n_params; i++)
        PyList_SET_ITEM(params, i,
                        Py_BuildValue("(sssd)", m->params[i].name,
                                      m->params[i].unit ? m->params[i].unit : "1",
                                      m->params[i].description ? m->params[i].description : "",
                                      dyn_model_get_param(m, par, i)));
    for (int i = 0; init && i < m->n_states; i++)
        PyList_SET_ITEM(init, i, PyFloat_FromDouble(y0[i]));
    for (int i = 0; events && i < m->n_events; i++)
        PyList_SET_ITEM(events, i, PyUnicode_FromString(m->events[i].name));
    free(par);
    free(y0);
    const dyn_tableau *method = dyn_run_method_find(m->method ? m->method : DYN_MODEL_METHOD);
    const int map = method && dyn_method_is_map(method);
    const char *kind = m->n_noise > 0 ? "noise"
                       : m->delay     ? "delay"
                       : m->volterra  ? "volterra"
                                      : "ode";
    PyObject *info = Py_BuildValue(
        "{s:s,s:s,s:s,s:N,s:N,s:N,s:N,s:N,s:N,s:d,s:d,s:d,s:s,s:d,s:d,s:s,s:s,s:s,s:z,s:z,"
        "s:[dddd],s:O}",
        "name",
        m->name, "title", m->title ? m->title : "", "description",
        m->description ? m->description : "", "states", vars(m->states, m->n_states),
        "parameters", params, "outputs", vars(m->outputs, m->n_outputs), "initial", init,
        "events", events, "inputs", vars(m->inputs, m->n_inputs), "t0", m->t0, "t1", m->t1,
        "step", m->step, "method", m->method ? m->method : DYN_MODEL_METHOD, "rtol",
        dyn_run_default_rtol(m), "atol", dyn_run_default_atol(m), "time_unit",
        m->time_unit && m->time_unit[0] ? m->time_unit : "s", "kind", kind, "source",
        self->opened.path, "phase_x", m->phase_x, "phase_y", m->phase_y, "phase_window",
        m->phase_window[0], m->phase_window[1], m->phase_window[2], m->phase_window[3], "map",
        map ? Py_True : Py_False);
    return info;
}

/* the samples of a run, with the model's outputs at each when asked */
typedef struct run_sink {
    dkb_samples s;
    const dyn_model *m;
    const void *par;
    double *out;
    int failed;
} run_sink;

static int on_sample(long k, double t, const double *y, void *ctx)
{
    (void)k;
    run_sink *r = ctx;
    if (r->s.n_out && r->m->compute_outputs(t, y, r->par, r->out))
        for (int i = 0; i < r->s.n_out; i++)
            r->out[i] = NAN;
    if (dkb_samples_add(&r->s, t, y, r->out)) {
        r->failed = 1;
        return 1;
    }
    return 0;
}

typedef struct found_events {
    long count, cap;
    int *index;
    double *t;
} found_events;

static int on_event(int index, double t, const double *y, int direction, void *ctx)
{
    (void)y;
    (void)direction;
    found_events *f = ctx;
    if (f->count == f->cap) {
        const long cap = f->cap ? 2 * f->cap : 64;
        int *ni = realloc(f->index, (size_t)cap * sizeof *ni);
        if (ni)
            f->index = ni;
        double *nt = realloc(f->t, (size_t)cap * sizeof *nt);
        if (nt)
            f->t = nt;
        if (!ni || !nt)
            return 1;
        f->cap = cap;
    }
    f->index[f->count] = index;
    f->t[f->count++] = t;
    return 0;
}

static PyObject *matrix(const double *v, long rows, int cols)
{
    npy_intp dims[2] = {rows, cols};
    PyObject *a = PyArray_SimpleNew(2, dims, NPY_DOUBLE);
    if (a && rows > 0 && cols > 0)
        memcpy(PyArray_DATA((PyArrayObject *)a), v, (size_t)rows * (size_t)cols * sizeof *v);
    return a;
}

/* the run's options from the keywords; 0, or -1 with an exception */
typedef struct run_args {
    const char *method;
    double t0, t1, step, rtol, atol, max_step, first_step;
    long max_steps, every;
    unsigned long long seed;
    int outputs, step_given;
    PyObject *y0, *params, *times, *events;
} run_args;

static PyObject *model_run(dkpy_model *self, PyObject *args, PyObject *kwargs)
{
    const dyn_model *m = self->opened.model;
    if (!m)
        return PyErr_Format(dkpy_error, "the model is not open");
    static char *kw[] = {"method", "t0", "t1", "step", "y0", "params", "rtol", "atol",
                         "times", "max_step", "first_step", "max_steps", "every", "seed",
                         "outputs", "events", NULL};
    run_args a = {.method = NULL, .t0 = m->t0, .t1 = m->t1, .step = NAN, .max_steps = -1,
                  .y0 = Py_None, .params = Py_None, .times = Py_None, .events = Py_None};
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "|zdddOOddOddllKpO", kw, &a.method, &a.t0,
                                     &a.t1, &a.step, &a.y0, &a.params, &a.rtol, &a.atol,
                                     &a.times, &a.max_step, &a.first_step, &a.max_steps,
                                     &a.every, &a.seed, &a.outputs, &a.events))
        return NULL;
    const dyn_tableau *method = dkpy_method(a.method ? a.method
                                            : m->method ? m->method
                                                        : DYN_MODEL_METHOD);
    if (!method)
        return NULL;
    if (method == dyn_run_method_cvode())
        return PyErr_Format(PyExc_ValueError, "method cvode: the Python package runs the "
                                              "library's methods (use rodas4 for stiff models)");
    a.step_given = !isnan(a.step);
    if (!a.step_given)
        a.step = m->step;
    if (!(a.t1 > a.t0) || !(a.step > 0.0) || !isfinite(a.t0) || !isfinite(a.t1))
        return PyErr_Format(PyExc_ValueError,
                            "t0 < t1 and step > 0 are needed (got t0 = %g, t1 = %g, step = %g)",
                            a.t0, a.t1, a.step);
    /* the parameters, then the initial state that may follow them */
    void *par = dkpy_model_params(m, a.params);
    if (!par)
        return NULL;
    PyObject *result = NULL;
    PyArrayObject *y0 = NULL, *times = NULL;
    dyn_event *events = NULL;
    run_sink sink = {.m = m, .par = par};
    found_events found = {0};
    npy_intp n = m->n_states;
    double *y = malloc((size_t)(2 * n + 1) * sizeof *y), *start = y + n;
    if (!y) {
        PyErr_NoMemory();
        goto done;
    }
    if (a.y0 == Py_None)
        dyn_model_initial_state(m, par, start);
    else if ((y0 = dkpy_vector(a.y0, "y0", &n)) != NULL)
        memcpy(start, PyArray_DATA(y0), (size_t)n * sizeof *start);
    else {
        free(y);
        goto done;
    }
    for (npy_intp i = 0; i < n; i++)
        if (!isfinite(start[i])) {
            PyErr_Format(PyExc_ValueError, "y0: state %s is %g, not a finite number",
                         m->states[i].name, start[i]);
            free(y);
            goto done;
        }
    dyn_run_opts o = {0};
    o.method = method;
    o.t0 = a.t0;
    o.t1 = a.t1;
    o.step = a.step;
    o.rtol = a.rtol;
    o.atol = a.atol;
    o.max_step = a.max_step;
    o.initial_step = a.first_step;
    o.max_steps = a.max_steps >= 0 ? a.max_steps
                  : dyn_method_is_adaptive(method) ? 10000000L
                                                   : 0;
    o.every = a.every;
    o.seed = a.seed;
    npy_intp nt = -1;
    if (a.times != Py_None) {
        if (!(times = dkpy_vector(a.times, "times", &nt))) {
            free(y);
            goto done;
        }
        o.times = PyArray_DATA(times);
        o.n_times = (long)nt;
    }
    /* as dynkit run: an adaptive run without times or step writes every step when the model
     * asks for it or its grid would be too long */
    o.at_steps = dyn_method_is_adaptive(method) && !o.times && !a.step_given &&
                 (m->samples == DYN_SAMPLES_STEPS || (a.t1 - a.t0) / a.step + 1.0 > 1e6);
    if (a.events != Py_None) {
        const Py_ssize_t ne = PySequence_Length(a.events);
        events = ne > 0 ? calloc((size_t)ne, sizeof *events) : NULL;
        for (Py_ssize_t k = 0; ne > 0 && events && k < ne; k++) {
            PyObject *e = PySequence_GetItem(a.events, k);
            const char *name = e ? PyUnicode_AsUTF8(e) : NULL;
            int found_k = -1;
            for (int i = 0; name && i < m->n_events; i++)
                if (strcmp(m->events[i].name, name) == 0)
                    found_k = i;
            Py_XDECREF(e);
            if (found_k < 0) {
                if (!PyErr_Occurred())
                    PyErr_Format(PyExc_ValueError, "model %s has no event '%s'", m->name,
                                 name);
                free(y);
                goto done;
            }
            events[k] = m->events[found_k];
            events[k].terminal = 0;
        }
        o.events = events;
        o.n_events = events ? (int)ne : 0;
        o.on_event = on_event;
        o.event_ctx = &found;
    }
    sink.s.n = (int)n;
    sink.s.n_out = a.outputs ? m->n_outputs : 0;
    sink.out = sink.s.n_out ? malloc((size_t)sink.s.n_out * sizeof *sink.out) : NULL;
    o.output = on_sample;
    o.output_ctx = &sink;
    dyn_result res;
    int status;
    Py_BEGIN_ALLOW_THREADS
    status = dyn_run(m, par, start, &o, y, &res);
    Py_END_ALLOW_THREADS
    free(y);
    if (status < 0 || sink.failed) {
        PyErr_NoMemory();
        goto done;
    }
    if (status == DYN_ERR_ARG) {
        PyErr_SetString(PyExc_ValueError, res.message);
        goto done;
    }
    PyObject *ev_t = PyList_New(found.count);
    for (long k = 0; ev_t && k < found.count; k++)
        PyList_SET_ITEM(ev_t, k,
                        Py_BuildValue("(sd)", events[found.index[k]].name, found.t[k]));
    result = Py_BuildValue(
        "{s:N,s:N,s:N,s:i,s:s,s:d,s:{s:l,s:l,s:l,s:l,s:l},s:N}", "t",
        matrix(sink.s.t, sink.s.count, 1), "y", matrix(sink.s.y, sink.s.count, (int)n),
        "outputs",
        sink.s.n_out ? matrix(sink.s.out, sink.s.count, sink.s.n_out) : (Py_INCREF(Py_None), Py_None),
        "status", res.status, "message", res.message, "t_reached", res.t, "stats", "steps",
        res.stats.steps, "accepted", res.stats.accepted, "rejected", res.stats.rejected,
        "rhs_calls", res.stats.rhs_calls, "jac_calls", res.stats.jac_calls, "events", ev_t);
done:
    dkb_samples_free(&sink.s);
    free(sink.out);
    free(found.index);
    free(found.t);
    free(events);
    Py_XDECREF(y0);
    Py_XDECREF(times);
    free(par);
    return result;
}

static PyMethodDef model_methods[] = {
    {"info", (PyCFunction)model_info, METH_NOARGS,
     "The model's name, states, parameters (with their values), outputs, units, defaults."},
    {"run", (PyCFunction)(void (*)(void))model_run, METH_VARARGS | METH_KEYWORDS,
     "One run through dyn_run, the library's entry for every kind of model."},
    {"equilibria", (PyCFunction)(void (*)(void))dkpy_model_equilibria,
     METH_VARARGS | METH_KEYWORDS, "Every equilibrium in the box lo..hi (analysis.c)."},
    {"lyapunov", (PyCFunction)(void (*)(void))dkpy_model_lyapunov,
     METH_VARARGS | METH_KEYWORDS, "The k largest Lyapunov exponents (analysis.c)."},
    {NULL, NULL, 0, NULL},
};

PyTypeObject dkpy_model_type = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "dynkit._core.Model",
    .tp_basicsize = sizeof(dkpy_model),
    .tp_dealloc = (destructor)model_dealloc,
    .tp_flags = Py_TPFLAGS_DEFAULT | Py_TPFLAGS_BASETYPE,
    .tp_doc = "A model opened by name or path (dynkit.Model wraps it).",
    .tp_methods = model_methods,
    .tp_init = (initproc)model_init,
    .tp_new = PyType_GenericNew,
};
