/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit.solve_ivp's solver (dyn_ivp_solve, dynkit/ivp.h) for a Python callable or a dynkit
 * Model: SciPy's arguments, events with terminal and direction, the Jacobian, dense output
 * kept in a capsule for OdeSolution. A Python fun runs with the interpreter's lock held (it
 * is Python); a Model's right-hand side runs native with the lock released. An exception
 * raised by fun, jac or an event stops the solve and is raised again, unchanged. */
#include "core.h"
#include "../../common/event_slots.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_EVENTS = DKB_MAX_EVENTS };

typedef struct pyfun {
    PyObject *fun, *args, *jac;
    PyObject *events[MAX_EVENTS];
    int n;
    int failed; /* an exception is pending */
} pyfun;

static PyObject *call(PyObject *f, double t, const double *y, int n, PyObject *args)
{
    npy_intp dim = n;
    PyObject *ya = PyArray_SimpleNew(1, &dim, NPY_DOUBLE);
    if (!ya)
        return NULL;
    memcpy(PyArray_DATA((PyArrayObject *)ya), y, (size_t)n * sizeof *y);
    const Py_ssize_t na = args ? PyTuple_GET_SIZE(args) : 0;
    PyObject *all = PyTuple_New(2 + na);
    if (!all) {
        Py_DECREF(ya);
        return NULL;
    }
    PyTuple_SET_ITEM(all, 0, PyFloat_FromDouble(t));
    PyTuple_SET_ITEM(all, 1, ya);
    for (Py_ssize_t i = 0; i < na; i++) {
        PyObject *a = PyTuple_GET_ITEM(args, i);
        Py_INCREF(a);
        PyTuple_SET_ITEM(all, 2 + i, a);
    }
    PyObject *r = PyObject_Call(f, all, NULL);
    Py_DECREF(all);
    return r;
}

static int rhs(double t, const double *y, double *dydt, void *par)
{
    pyfun *p = par;
    if (p->failed)
        return 1;
    PyObject *r = call(p->fun, t, y, p->n, p->args);
    npy_intp n = p->n;
    PyArrayObject *a = r ? dkpy_vector(r, "the value of fun(t, y)", &n) : NULL;
    Py_XDECREF(r);
    if (!a) {
        p->failed = 1;
        return 1;
    }
    memcpy(dydt, PyArray_DATA(a), (size_t)p->n * sizeof *dydt);
    Py_DECREF(a);
    return 0;
}

static int jacobian(double t, const double *y, double *J, void *par)
{
    pyfun *p = par;
    if (p->failed)
        return 1;
    PyObject *r = call(p->jac, t, y, p->n, p->args);
    PyArrayObject *a = r ? (PyArrayObject *)PyArray_FROMANY(r, NPY_DOUBLE, 2, 2,
                                                              NPY_ARRAY_IN_ARRAY)
                         : NULL;
    Py_XDECREF(r);
    if (a && (PyArray_DIM(a, 0) != p->n || PyArray_DIM(a, 1) != p->n)) {
        PyErr_Format(PyExc_ValueError, "jac(t, y) has shape (%zd, %zd), (%d, %d) expected",
                     (Py_ssize_t)PyArray_DIM(a, 0), (Py_ssize_t)PyArray_DIM(a, 1), p->n, p->n);
        Py_CLEAR(a);
    }
    if (!a) {
        p->failed = 1;
        return 1;
    }
    memcpy(J, PyArray_DATA(a), (size_t)p->n * (size_t)p->n * sizeof *J);
    Py_DECREF(a);
    return 0;
}

static double event(int k, double t, const double *y, void *par)
{
    pyfun *p = par;
    if (p->failed)
        return NAN;
    PyObject *r = call(p->events[k], t, y, p->n, p->args);
    const double v = r ? PyFloat_AsDouble(r) : NAN;
    Py_XDECREF(r);
    if (PyErr_Occurred()) {
        p->failed = 1;
        return NAN;
    }
    return v;
}

/* dyn_event.g has no index: one function per event slot */
DKB_EVENT_SLOTS(event)

static PyObject *array_1d(const double *v, long n)
{
    npy_intp dim = n;
    PyObject *a = PyArray_SimpleNew(1, &dim, NPY_DOUBLE);
    if (a && n > 0)
        memcpy(PyArray_DATA((PyArrayObject *)a), v, (size_t)n * sizeof *v);
    return a;
}

/* y as SciPy gives it: (n, n_t), state by row */
static PyObject *states_by_row(const double *y, int n, long nt)
{
    npy_intp dims[2] = {n, nt};
    PyObject *a = PyArray_SimpleNew(2, dims, NPY_DOUBLE);
    if (!a)
        return NULL;
    double *d = PyArray_DATA((PyArrayObject *)a);
    for (long k = 0; k < nt; k++)
        for (int i = 0; i < n; i++)
            d[(size_t)i * (size_t)nt + (size_t)k] = y[(size_t)k * (size_t)n + (size_t)i];
    return a;
}

static void free_solution(PyObject *capsule)
{
    dyn_ivp_free(PyCapsule_GetPointer(capsule, "dynkit.ivp_solution"));
}

/* the events found, per event: t_events[k] (m) and y_events[k] (m, n), as SciPy */
static int add_events(PyObject *out, const dyn_ivp_solution *sol, int n_events)
{
    PyObject *te = PyList_New(n_events), *ye = PyList_New(n_events);
    if (!te || !ye)
        goto fail;
    for (int k = 0; k < n_events; k++) {
        long m = 0;
        for (long e = 0; e < sol->n_events; e++)
            m += sol->event_index[e] == k;
        npy_intp d1 = m, d2[2] = {m, sol->n};
        PyObject *t = PyArray_SimpleNew(1, &d1, NPY_DOUBLE);
        PyObject *y = PyArray_SimpleNew(2, d2, NPY_DOUBLE);
        if (!t || !y) {
            Py_XDECREF(t);
            Py_XDECREF(y);
            goto fail;
        }
        long j = 0;
        for (long e = 0; e < sol->n_events; e++)
            if (sol->event_index[e] == k) {
                ((double *)PyArray_DATA((PyArrayObject *)t))[j] = sol->t_events[e];
                memcpy((double *)PyArray_DATA((PyArrayObject *)y) + (size_t)j * (size_t)sol->n,
                       sol->y_events + (size_t)e * (size_t)sol->n,
                       (size_t)sol->n * sizeof(double));
                j++;
            }
        PyList_SET_ITEM(te, k, t);
        PyList_SET_ITEM(ye, k, y);
    }
    const int bad = PyDict_SetItemString(out, "t_events", te) ||
                    PyDict_SetItemString(out, "y_events", ye);
    Py_DECREF(te);
    Py_DECREF(ye);
    return bad;
fail:
    Py_XDECREF(te);
    Py_XDECREF(ye);
    return 1;
}

static int set_number(PyObject *d, const char *key, double v)
{
    PyObject *o = PyFloat_FromDouble(v);
    const int bad = !o || PyDict_SetItemString(d, key, o);
    Py_XDECREF(o);
    return bad;
}

static int set_long(PyObject *d, const char *key, long v)
{
    PyObject *o = PyLong_FromLong(v);
    const int bad = !o || PyDict_SetItemString(d, key, o);
    Py_XDECREF(o);
    return bad;
}

static PyObject *result(dyn_ivp_solution *sol, const dyn_tableau *method, int n_events,
                        int keep_dense)
{
    PyObject *out = PyDict_New();
    if (!out)
        return NULL;
    PyObject *t = array_1d(sol->t, sol->n_t), *y = states_by_row(sol->y, sol->n, sol->n_t);
    PyObject *msg = PyUnicode_FromString(sol->status == DYN_OK ? (sol->terminated
                                                                    ? "A termination event occurred."
                                                                    : "The solver successfully "
                                                                      "reached the end of the "
                                                                      "integration interval.")
                                                              : sol->message);
    int bad = !t || !y || !msg || PyDict_SetItemString(out, "t", t) ||
              PyDict_SetItemString(out, "y", y) || PyDict_SetItemString(out, "message", msg);
    Py_XDECREF(t);
    Py_XDECREF(y);
    Py_XDECREF(msg);
    const int status = sol->status != DYN_OK ? -1 : sol->terminated ? 1 : 0;
    bad = bad || set_long(out, "status", status) ||
          set_long(out, "nfev", sol->stats.rhs_calls) ||
          set_long(out, "njev", sol->stats.jac_calls) ||
          set_long(out, "nlu", dyn_method_is_stiff(method) ? sol->stats.steps : 0) ||
          set_long(out, "naccepted", sol->stats.accepted) ||
          set_long(out, "nrejected", sol->stats.rejected) ||
          set_number(out, "t_reached", sol->result.t) || add_events(out, sol, n_events);
    if (!bad && keep_dense) {
        PyObject *cap = PyCapsule_New(sol, "dynkit.ivp_solution", free_solution);
        if (!cap)
            bad = 1;
        else {
            sol = NULL; /* the capsule owns it */
            bad = PyDict_SetItemString(out, "sol", cap);
            Py_DECREF(cap);
        }
    }
    dyn_ivp_free(sol);
    if (bad) {
        Py_DECREF(out);
        return NULL;
    }
    return out;
}

PyObject *dkpy_solve_ivp(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kw[] = {"fun",  "t0",  "t1",         "y0",         "method", "t_eval",
                         "dense_output", "events", "rtol", "atol", "max_step", "first_step",
                         "step", "jac", "args", "params", NULL};
    PyObject *fun, *y0_obj, *t_eval_obj = Py_None, *events = Py_None, *jac = Py_None;
    PyObject *fargs = Py_None, *params = Py_None;
    double t0, t1, rtol = 1e-3, atol = 1e-6, max_step = 0.0, first_step = 0.0, step = 0.0;
    const char *method_name = "RK45";
    int dense = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OddO|sOpOdddddOOO", kw, &fun, &t0, &t1,
                                     &y0_obj, &method_name, &t_eval_obj, &dense, &events, &rtol,
                                     &atol, &max_step, &first_step, &step, &jac, &fargs,
                                     &params))
        return NULL;
    const dyn_tableau *method = dkpy_method(method_name);
    if (!method)
        return NULL;
    const int is_model = PyObject_TypeCheck(fun, &dkpy_model_type);
    if (!is_model && !PyCallable_Check(fun))
        return PyErr_Format(PyExc_TypeError, "fun must be callable or a dynkit.Model");
    const dyn_model *m = is_model ? ((dkpy_model *)fun)->opened.model : NULL;
    npy_intp n = m ? m->n_states : -1;
    PyArrayObject *y0 = dkpy_vector(y0_obj, "y0", &n);
    if (!y0)
        return NULL;
    for (npy_intp i = 0; i < n; i++)
        if (!isfinite(((const double *)PyArray_DATA(y0))[i])) {
            PyErr_Format(PyExc_ValueError, "y0[%zd] is %g: every initial value must be a "
                                           "finite number",
                         (Py_ssize_t)i, ((const double *)PyArray_DATA(y0))[i]);
            Py_DECREF(y0);
            return NULL;
        }
    PyArrayObject *t_eval = NULL;
    npy_intp n_eval = -1;
    if (t_eval_obj != Py_None && !(t_eval = dkpy_vector(t_eval_obj, "t_eval", &n_eval))) {
        Py_DECREF(y0);
        return NULL;
    }
    dyn_ivp_opts o = {0};
    o.method = method->name;
    o.rtol = rtol;
    o.atol = atol;
    o.max_step = max_step;
    o.first_step = first_step;
    o.h = step;
    o.t_eval = t_eval ? PyArray_DATA(t_eval) : NULL;
    o.n_eval = t_eval ? (long)n_eval : 0;
    o.dense_output = dense;
    pyfun p = {.fun = fun, .args = fargs != Py_None ? fargs : NULL, .n = (int)n};
    dyn_event ev[MAX_EVENTS];
    int n_events = 0;
    PyObject *result_dict = NULL;
    dyn_ivp_solution *sol = NULL;
    if (events != Py_None) {
        const Py_ssize_t ne = PySequence_Length(events);
        if (ne < 0 || ne > MAX_EVENTS || is_model) {
            if (!PyErr_Occurred())
                PyErr_Format(PyExc_ValueError,
                             is_model ? "events of a Model are its own, by name: use "
                                        "Model.run(events=[...])"
                                      : "at most %d events", MAX_EVENTS);
            goto done;
        }
        for (Py_ssize_t k = 0; k < ne; k++) {
            PyObject *e = PySequence_GetItem(events, k);
            if (!e || !PyCallable_Check(e)) {
                Py_XDECREF(e);
                PyErr_Format(PyExc_TypeError, "events[%zd] is not callable", k);
                goto done;
            }
            /* SciPy's attributes, each optional */
            PyObject *term = PyObject_GetAttrString(e, "terminal");
            PyErr_Clear();
            PyObject *dir = PyObject_GetAttrString(e, "direction");
            PyErr_Clear();
            ev[k] = (dyn_event){.name = "event", .g = dkb_event_slots[k]};
            ev[k].terminal = term ? PyObject_IsTrue(term) : 0;
            const double d = dir ? PyFloat_AsDouble(dir) : 0.0;
            PyErr_Clear();
            ev[k].direction = d > 0 ? 1 : d < 0 ? -1 : 0;
            Py_XDECREF(term);
            Py_XDECREF(dir);
            p.events[k] = e; /* borrowed from the sequence from here on */
            Py_DECREF(e);
        }
        n_events = (int)ne;
        o.events = ev;
        o.n_events = n_events;
    }
    if (is_model) {
        if (m->delay || m->volterra || m->n_noise > 0) {
            PyErr_Format(PyExc_ValueError,
                         "model %s has %s: run it with Model.run, which takes every kind of "
                         "model", m->name,
                         m->delay ? "delays" : m->volterra ? "Volterra integrals" : "noise");
            goto done;
        }
        void *par = dkpy_model_params(m, params);
        if (!par)
            goto done;
        const double tspan[2] = {t0, t1};
        /* the model's exact Jacobian and band, and its resets, take part (dynkit/ivp.h) */
        Py_BEGIN_ALLOW_THREADS
        sol = dyn_ivp_solve_model(m, par, PyArray_DATA(y0), tspan, &o);
        Py_END_ALLOW_THREADS
        free(par);
    } else {
        if (jac != Py_None) {
            if (!PyCallable_Check(jac)) {
                PyErr_SetString(PyExc_TypeError, "jac must be callable (or None)");
                goto done;
            }
            p.jac = jac;
            o.jacobian = jacobian;
        }
        sol = dyn_ivp_solve(rhs, (int)n, &p, t0, t1, PyArray_DATA(y0), &o);
    }
    if (!sol) {
        PyErr_NoMemory();
        goto done;
    }
    if (p.failed) { /* fun, jac or an event raised: that exception */
        dyn_ivp_free(sol);
        goto done;
    }
    if (sol->status == DYN_ERR_ARG) {
        PyErr_SetString(PyExc_ValueError, sol->message);
        dyn_ivp_free(sol);
        goto done;
    }
    result_dict = result(sol, method, n_events, dense);
done:
    Py_DECREF(y0);
    Py_XDECREF(t_eval);
    return result_dict;
}

PyObject *dkpy_ivp_eval(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *cap, *t_obj;
    if (!PyArg_ParseTuple(args, "OO", &cap, &t_obj))
        return NULL;
    const dyn_ivp_solution *sol = PyCapsule_GetPointer(cap, "dynkit.ivp_solution");
    if (!sol)
        return NULL;
    npy_intp nt = -1;
    PyArrayObject *t = dkpy_vector(t_obj, "t", &nt);
    if (!t)
        return NULL;
    npy_intp dims[2] = {sol->n, nt};
    PyObject *out = PyArray_SimpleNew(2, dims, NPY_DOUBLE);
    double *y = malloc((size_t)(sol->n > 0 ? sol->n : 1) * sizeof *y);
    const double *tv = PyArray_DATA(t);
    for (npy_intp k = 0; out && y && k < nt; k++) {
        if (dyn_ivp_eval(sol, tv[k], y)) {
            PyErr_Format(PyExc_ValueError, "t = %g is outside the solved span", tv[k]);
            Py_CLEAR(out);
            break;
        }
        double *d = PyArray_DATA((PyArrayObject *)out);
        for (int i = 0; i < sol->n; i++)
            d[(size_t)i * (size_t)nt + (size_t)k] = y[i];
    }
    free(y);
    Py_DECREF(t);
    if (!y && out) {
        Py_DECREF(out);
        return PyErr_NoMemory();
    }
    return out;
}
