/* SPDX-License-Identifier: BSD-3-Clause */
/* The Python extension dynkit._core: its functions and the Model type, the error type, the
 * method names (SciPy's and MATLAB's mapped onto dynkit's), the NumPy conversions shared by
 * the other files, and dynkit.report() (the homework's answers as JSON text). Models
 * compiled at run time call the library's functions: the module makes its own symbols
 * global (dlopen RTLD_GLOBAL of itself) so that their shared objects find them. */
#define _GNU_SOURCE
#define DKPY_IMPORT_ARRAY
#include "core.h"

#include <dlfcn.h>

#include "dynkit/lang.h"
#include "dynkit/mbs.h"
#include <stdlib.h>
#include <string.h>
#include <strings.h>

PyObject *dkpy_error;

/* SciPy's and MATLAB's names of methods, and dynkit's method for each */
static const struct {
    const char *name, *method;
} aliases[] = {
    {"RK45", "dp45"},    {"RK23", "bs23"},    {"DOP853", "dop853"}, {"Radau", "rodas4"},
    {"BDF", "rodas4"},   {"LSODA", "rodas4"}, {"ode45", "dp45"},    {"ode23", "bs23"},
    {"ode15s", "rodas4"}, {"ode23s", "rodas4"},
};

const dyn_tableau *dkpy_method(const char *name)
{
    for (size_t i = 0; i < sizeof aliases / sizeof aliases[0]; i++)
        if (strcasecmp(name, aliases[i].name) == 0)
            return dyn_run_method_find(aliases[i].method);
    char low[64];
    size_t k = 0;
    for (; name[k] && k + 1 < sizeof low; k++)
        low[k] = (char)((name[k] >= 'A' && name[k] <= 'Z') ? name[k] - 'A' + 'a' : name[k]);
    low[k] = '\0';
    const dyn_tableau *m = dyn_run_method_find(low);
    if (!m) {
        char names[640];
        dyn_method_names(names, sizeof names);
        PyErr_Format(PyExc_ValueError,
                     "unknown method '%s' (accepted: RK45, RK23, DOP853, Radau, BDF, LSODA, "
                     "%s, rkmil, sriw1, volterra)",
                     name, names);
    }
    return m;
}

PyArrayObject *dkpy_vector(PyObject *obj, const char *what, npy_intp *n)
{
    PyArrayObject *a = (PyArrayObject *)PyArray_FROMANY(obj, NPY_DOUBLE, 0, 1,
                                                         NPY_ARRAY_IN_ARRAY);
    if (!a) {
        PyErr_Clear();
        PyErr_Format(PyExc_TypeError, "%s must be a sequence of real numbers", what);
        return NULL;
    }
    const npy_intp len = PyArray_NDIM(a) == 0 ? 1 : PyArray_DIM(a, 0);
    if (*n >= 0 && len != *n) {
        PyErr_Format(PyExc_ValueError, "%s has %zd values, %zd expected", what, (Py_ssize_t)len,
                     (Py_ssize_t)*n);
        Py_DECREF(a);
        return NULL;
    }
    *n = len;
    return a;
}

/* dynkit.report(): the homework's answers as dynkit report --json writes them */
static PyObject *report_json(PyObject *self, PyObject *args)
{
    (void)self;
    (void)args;
    static dyn_homework hw;
    char err[256] = "";
    int bad;
    Py_BEGIN_ALLOW_THREADS
    bad = dyn_homework_compute(&hw, err, sizeof err);
    Py_END_ALLOW_THREADS
    if (bad) {
        PyErr_SetString(dkpy_error, err);
        return NULL;
    }
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    if (!f)
        return PyErr_NoMemory();
    bad = dyn_homework_write_json(&hw, f);
    fclose(f);
    PyObject *s = bad ? NULL : PyUnicode_FromStringAndSize(text, (Py_ssize_t)len);
    free(text);
    if (bad)
        PyErr_SetString(dkpy_error, "the report could not be written");
    return s;
}

/* the equations a mechanism file derives, as `dynkit derive FILE.mech` (or its C, c = 1) */
static PyObject *mech_text(PyObject *self, PyObject *args)
{
    (void)self;
    const char *path;
    int c = 0;
    if (!PyArg_ParseTuple(args, "s|p", &path, &c))
        return NULL;
    char err[2048];
    size_t len = 0;
    char *text = dkb_read_file(path, &len, err, sizeof err);
    if (!text) {
        PyErr_SetString(dkpy_error, err);
        return NULL;
    }
    char *out = NULL;
    dyn_lang_diag diag;
    const int rc = c ? dyn_mech_to_c(path, text, len, NULL, 0, &out, &diag, NULL, NULL)
                     : dyn_mech_derive_text(path, text, len, &out, &diag);
    free(text);
    if (rc != 0) {
        if (rc == 1)
            return PyErr_NoMemory();
        dyn_lang_diag_format(&diag, err, sizeof err);
        PyErr_SetString(dkpy_error, err);
        return NULL;
    }
    PyObject *r = PyUnicode_FromString(out);
    free(out);
    return r;
}

static PyObject *models(PyObject *self, PyObject *args)
{
    (void)self;
    (void)args;
    PyObject *list = PyList_New(0);
    for (int i = 0; list && i < dyn_model_count(); i++) {
        PyObject *name = PyUnicode_FromString(dyn_model_at(i)->name);
        if (!name || PyList_Append(list, name)) {
            Py_XDECREF(name);
            Py_DECREF(list);
            return NULL;
        }
        Py_DECREF(name);
    }
    return list;
}

static PyMethodDef functions[] = {
    {"solve_ivp", (PyCFunction)(void (*)(void))dkpy_solve_ivp, METH_VARARGS | METH_KEYWORDS,
     "The solver under dynkit.solve_ivp (use that)."},
    {"ivp_eval", dkpy_ivp_eval, METH_VARARGS, "The dense output of a solution at times t."},
    {"report_json", report_json, METH_NOARGS, "The homework's answers as JSON text."},
    {"models", models, METH_NOARGS, "The names of the built-in models."},
    {"mech_text", mech_text, METH_VARARGS,
     "A mechanism file's derived equations (or, c=True, its C), as dynkit derive."},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT, "dynkit._core",
    "dynkit's C library: solvers, models, the one entry that runs them.", -1, functions,
    NULL, NULL, NULL, NULL,
};

PyMODINIT_FUNC PyInit__core(void)
{
    import_array();
    /* the library's symbols global, for the models compiled at run time */
    Dl_info info;
    if (dladdr((void *)PyInit__core, &info) && info.dli_fname)
        dlopen(info.dli_fname, RTLD_NOW | RTLD_GLOBAL | RTLD_NOLOAD);
    PyObject *m = PyModule_Create(&module);
    if (!m)
        return NULL;
    dkpy_error = PyErr_NewExceptionWithDoc("dynkit.DynkitError",
                                           "An error of dynkit's, with its message.",
                                           PyExc_RuntimeError, NULL);
    if (!dkpy_error || PyModule_AddObject(m, "DynkitError", dkpy_error) ||
        PyType_Ready(&dkpy_model_type) < 0) {
        Py_DECREF(m);
        return NULL;
    }
    Py_INCREF(&dkpy_model_type);
    if (PyModule_AddObject(m, "Model", (PyObject *)&dkpy_model_type)) {
        Py_DECREF(m);
        return NULL;
    }
    return m;
}
