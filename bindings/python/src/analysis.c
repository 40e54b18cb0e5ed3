/* SPDX-License-Identifier: BSD-3-Clause */
/* The analyses of dynkit._core.Model: equilibria in a box (dyn_equilibria_find,
 * dynkit/equilibria.h) with their eigenvalues by LAPACK when the package is built with it,
 * and Lyapunov exponents (dyn_lyapunov, dynkit/lyapunov.h); the interpreter's lock is
 * released while they run. The defaults (the box, the transient) are the command line's and
 * are set by dynkit/_model.py. */
#include "core.h"

#include <stdlib.h>
#include <string.h>

#include "dynkit/equilibria.h"
#include "dynkit/lyapunov.h"
#ifdef DKPY_HAVE_LAPACK
#include "dynkit/lapack.h"
#endif

void *dkpy_model_params(const dyn_model *m, PyObject *params)
{
    char err[512];
    void *par = dkb_model_params(m, err, sizeof err);
    if (!par) {
        PyErr_SetString(dkpy_error, err);
        return NULL;
    }
    PyObject *key, *value;
    Py_ssize_t pos = 0;
    while (params && params != Py_None && PyDict_Next(params, &pos, &key, &value)) {
        const char *name = PyUnicode_AsUTF8(key);
        const int i = name ? dyn_model_param_index(m, name) : -1;
        const double v = PyFloat_AsDouble(value);
        if (i < 0 || PyErr_Occurred()) {
            if (!PyErr_Occurred())
                PyErr_Format(PyExc_KeyError, "model %s has no parameter '%s'", m->name, name);
            free(par);
            return NULL;
        }
        dyn_model_set_param(m, par, i, v);
    }
    if (m->prepare && m->prepare(par, err, sizeof err)) {
        PyErr_SetString(PyExc_ValueError, err);
        free(par);
        return NULL;
    }
    return par;
}

static int is_map(const dyn_model *m)
{
    const dyn_tableau *t = dyn_run_method_find(m->method ? m->method : DYN_MODEL_METHOD);
    return t && dyn_method_is_map(t);
}

PyObject *dkpy_model_equilibria(PyObject *self, PyObject *args, PyObject *kwargs)
{
    const dyn_model *m = ((dkpy_model *)self)->opened.model;
    static char *kw[] = {"lo", "hi", "params", "guess", "starts", "t", NULL};
    PyObject *lo_obj, *hi_obj, *params = Py_None, *guess_obj = Py_None;
    int starts = 0;
    double t = m->t0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OO|OOid", kw, &lo_obj, &hi_obj, &params,
                                     &guess_obj, &starts, &t))
        return NULL;
    npy_intp n = m->n_states, ng = m->n_states;
    PyArrayObject *lo = dkpy_vector(lo_obj, "the box's lower corner", &n);
    PyArrayObject *hi = lo ? dkpy_vector(hi_obj, "the box's upper corner", &n) : NULL;
    PyArrayObject *guess = hi && guess_obj != Py_None ? dkpy_vector(guess_obj, "guess", &ng)
                                                      : NULL;
    void *par = hi && (guess || guess_obj == Py_None) ? dkpy_model_params(m, params) : NULL;
    PyObject *result = NULL;
    if (!par)
        goto done;
    dyn_equilibria_opts o = {0};
    o.lo = PyArray_DATA(lo);
    o.hi = PyArray_DATA(hi);
    o.guess = guess ? PyArray_DATA(guess) : NULL;
    o.starts = starts;
    o.map = is_map(m);
#ifdef DKPY_HAVE_LAPACK
    o.eig = &dyn_eig_solver_lapack;
#endif
    dyn_equilibria e;
    int status;
    Py_BEGIN_ALLOW_THREADS
    status = dyn_equilibria_find(m, t, par, &o, &e);
    Py_END_ALLOW_THREADS
    if (status != 0) {
        PyErr_SetString(status == DYN_ERR_ARG ? PyExc_ValueError : dkpy_error, e.message);
        dyn_equilibria_free(&e);
        goto done;
    }
    PyObject *list = PyList_New(e.count);
    for (int q = 0; list && q < e.count; q++) {
        PyObject *state = PyDict_New(), *eig = PyList_New(e.k[q]);
        for (int i = 0; state && i < e.n; i++) {
            PyObject *v = PyFloat_FromDouble(e.y[(size_t)q * (size_t)e.n + (size_t)i]);
            PyDict_SetItemString(state, m->states[i].name, v);
            Py_XDECREF(v);
        }
        for (int i = 0; eig && i < e.k[q]; i++)
            PyList_SET_ITEM(eig, i,
                            Py_BuildValue("[dd]", e.re[(size_t)q * (size_t)e.n + (size_t)i],
                                          e.im[(size_t)q * (size_t)e.n + (size_t)i]));
        PyList_SET_ITEM(list, q,
                        Py_BuildValue("{s:N,s:N,s:s,s:d,s:[iii]}", "state", state,
                                      "eigenvalues", eig, "type", dyn_eq_type_name(e.type[q]),
                                      "residual", e.residual[q], "manifolds",
                                      e.dims[3 * q], e.dims[3 * q + 1], e.dims[3 * q + 2]));
    }
    result = Py_BuildValue("{s:N,s:i,s:i,s:i,s:O}", "equilibria", list, "starts", e.starts,
                           "converged", e.converged, "outside", e.outside, "map",
                           o.map ? Py_True : Py_False);
    dyn_equilibria_free(&e);
done:
    free(par);
    Py_XDECREF(lo);
    Py_XDECREF(hi);
    Py_XDECREF(guess);
    return result;
}

PyObject *dkpy_model_lyapunov(PyObject *self, PyObject *args, PyObject *kwargs)
{
    const dyn_model *m = ((dkpy_model *)self)->opened.model;
    static char *kw[] = {"k", "t0", "y0", "transient", "average", "tau", "rtol", "atol",
                         "params", NULL};
    PyObject *y0_obj, *params = Py_None;
    int k = 1;
    dyn_lyapunov_opts o = {0};
    double t0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "idOddd|ddO", kw, &k, &t0, &y0_obj,
                                     &o.t_trans, &o.t_avg, &o.tau, &o.rtol, &o.atol, &params))
        return NULL;
    npy_intp n = m->n_states;
    if (k < 1 || k > n)
        return PyErr_Format(PyExc_ValueError, "exponents: 1 to %zd (got %d)", (Py_ssize_t)n, k);
    o.k = k;
    o.map = is_map(m);
    PyArrayObject *y0 = dkpy_vector(y0_obj, "y0", &n);
    void *par = y0 ? dkpy_model_params(m, params) : NULL;
    double *ex = par ? malloc(2 * (size_t)k * sizeof *ex) : NULL;
    PyObject *result = NULL;
    if (par && !ex)
        PyErr_NoMemory();
    if (ex) {
        dyn_lyapunov_info info = {0};
        int status;
        Py_BEGIN_ALLOW_THREADS
        status = dyn_lyapunov(m, par, t0, PyArray_DATA(y0), &o, ex, ex + k, &info);
        Py_END_ALLOW_THREADS
        if (status != 0)
            PyErr_SetString(status == DYN_ERR_ARG ? PyExc_ValueError : dkpy_error,
                            info.message);
        else {
            PyObject *e = PyList_New(k), *er = PyList_New(k);
            for (int i = 0; e && er && i < k; i++) {
                PyList_SET_ITEM(e, i, PyFloat_FromDouble(ex[i]));
                PyList_SET_ITEM(er, i, PyFloat_FromDouble(ex[k + i]));
            }
            result = Py_BuildValue("{s:N,s:N,s:O,s:i,s:l}", "exponents", e, "errors", er,
                                   "map", o.map ? Py_True : Py_False, "exact_jacobian",
                                   info.exact_jacobian, "orthonormalizations",
                                   info.orthonormalizations);
        }
    }
    free(ex);
    free(par);
    Py_XDECREF(y0);
    return result;
}
