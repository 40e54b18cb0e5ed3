/* SPDX-License-Identifier: BSD-3-Clause */
/* What the files of the Python extension dynkit._core share: NumPy's C API (imported once,
 * in module.c), the Model type, and the conversions of options. */
#ifndef DYNKIT_PY_CORE_H
#define DYNKIT_PY_CORE_H

#define PY_SSIZE_T_CLEAN
#include <Python.h>

#define PY_ARRAY_UNIQUE_SYMBOL dynkit_core_ARRAY_API
#define NPY_NO_DEPRECATED_API NPY_1_7_API_VERSION
#ifndef DKPY_IMPORT_ARRAY
#define NO_IMPORT_ARRAY
#endif
#include <numpy/arrayobject.h>

#include "../../common/model_open.h"
#include "../../common/samples.h"
#include "dynkit/dynkit.h"

/* dynkit.DynkitError: every error with a message of dynkit's */
extern PyObject *dkpy_error;

/* A model opened by name or path (model.c). */
typedef struct dkpy_model {
    PyObject_HEAD
    dkb_model opened;
} dkpy_model;
extern PyTypeObject dkpy_model_type;

/* A method by its dynkit name, alias or MATLAB name (ode45, ode15s); NULL with a Python
 * ValueError naming the accepted ones. */
const dyn_tableau *dkpy_method(const char *name);

/* obj as a contiguous 1-D float64 array of n values (n < 0: any length, set into *n); a new
 * reference, or NULL with a ValueError/TypeError naming what. */
PyArrayObject *dkpy_vector(PyObject *obj, const char *what, npy_intp *n);

/* The parameter struct of model m with its defaults, params (a dict NAME: value, or None)
 * set over them, and prepared (malloc'd); NULL with a KeyError, ValueError or DynkitError
 * (analysis.c). */
void *dkpy_model_params(const dyn_model *m, PyObject *params);

/* The functions of the module (ivp.c, model.c, module.c). */
PyObject *dkpy_solve_ivp(PyObject *self, PyObject *args, PyObject *kwargs);
PyObject *dkpy_ivp_eval(PyObject *self, PyObject *args);
PyObject *dkpy_model_equilibria(PyObject *self, PyObject *args, PyObject *kwargs);
PyObject *dkpy_model_lyapunov(PyObject *self, PyObject *args, PyObject *kwargs);

#endif /* DYNKIT_PY_CORE_H */
