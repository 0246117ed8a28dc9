/* bgdae._core: the module, bgdae.SolverError, and the conversions the two halves share (pyb.h):
 * statistics to a dict, keyword options to dae_options, arrays, modes to a list. */
#define PYB_IMPORT_ARRAY
#include "pyb.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "bg_status.h"

PyObject *pyb_SolverError = NULL;

PyObject *pyb_error(PyObject *type, const char *fmt, ...)
{
    char buf[BG_MESSAGE_SIZE + 256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    PyErr_SetString(type, buf);
    return NULL;
}

PyObject *pyb_raise_solver(int code, const char *message, double t, PyObject *extra)
{
    PyObject *exc = PyObject_CallFunction(pyb_SolverError, "s", message);
    if (!exc) return NULL;
    PyObject *v = PyUnicode_FromString(message);
    int bad = !v || PyObject_SetAttrString(exc, "message", v) < 0;
    Py_XDECREF(v);
    v = PyUnicode_FromString(bg_status_name(code));
    bad = bad || !v || PyObject_SetAttrString(exc, "status", v) < 0;
    Py_XDECREF(v);
    v = PyLong_FromLong(code);
    bad = bad || !v || PyObject_SetAttrString(exc, "code", v) < 0;
    Py_XDECREF(v);
    v = PyFloat_FromDouble(t);
    bad = bad || !v || PyObject_SetAttrString(exc, "t", v) < 0;
    Py_XDECREF(v);
    if (!bad && extra) {
        PyObject *key, *val;
        Py_ssize_t pos = 0;
        while (!bad && PyDict_Next(extra, &pos, &key, &val)) /* the rows' times: t_out */
            bad = PyUnicode_Check(key) && !PyUnicode_CompareWithASCIIString(key, "t")
                      ? PyObject_SetAttrString(exc, "t_out", val) < 0
                      : PyObject_SetAttr(exc, key, val) < 0;
    }
    if (!bad) PyErr_SetObject(pyb_SolverError, exc);
    Py_DECREF(exc);
    return NULL;
}

#define SET_ITEM(d, key, expr)                                                                   \
    do {                                                                                         \
        PyObject *v_ = (expr);                                                                   \
        if (!v_ || PyDict_SetItemString(d, key, v_) < 0) {                                       \
            Py_XDECREF(v_);                                                                      \
            Py_DECREF(d);                                                                        \
            return NULL;                                                                         \
        }                                                                                        \
        Py_DECREF(v_);                                                                           \
    } while (0)

PyObject *pyb_stats_dict(const dae_stats *st)
{
    PyObject *d = PyDict_New();
    if (!d) return NULL;
#define L(f) SET_ITEM(d, #f, PyLong_FromLong(st->f))
#define D(f) SET_ITEM(d, #f, PyFloat_FromDouble(st->f))
    L(steps); L(rejected_error); L(newton_iters); L(newton_fails); L(res_evals); L(res_evals_fd);
    L(jac_evals); L(factor_symbolic); L(factor_full); L(factor_refactor); L(linear_solves);
    L(projections); L(order_last); L(restarts); L(stab_lowered); L(pattern_nnz);
    L(pattern_probes); L(pattern_res_evals); L(pattern_reprobes); L(pattern_added); L(warnings);
    L(newton_fails_stale); L(reduced_rows); L(jac_regime);
    D(h_min_used); D(h_max_used); D(h_last); D(max_drift); D(init_residual); D(rcond_min);
    D(t_res); D(t_jac); D(t_linalg); D(t_pattern); D(t_last_restart); D(init_error);
#undef L
#undef D
    SET_ITEM(d, "steps_at_order",
             Py_BuildValue("(llllllll)", st->steps_at_order[0], st->steps_at_order[1],
                           st->steps_at_order[2], st->steps_at_order[3], st->steps_at_order[4],
                           st->steps_at_order[5], st->steps_at_order[6], st->steps_at_order[7]));
    return d;
}

PyObject *pyb_vector(const double *x, npy_intp n)
{
    PyObject *a = PyArray_SimpleNew(1, &n, NPY_DOUBLE);
    if (a && n > 0) memcpy(PyArray_DATA((PyArrayObject *)a), x, (size_t)n * sizeof *x);
    return a;
}

PyArrayObject *pyb_as_vector(PyObject *obj, npy_intp n, const char *what)
{
    PyArrayObject *a = (PyArrayObject *)PyArray_FROMANY(obj, NPY_DOUBLE, 1, 1,
                                                        NPY_ARRAY_IN_ARRAY | NPY_ARRAY_FORCECAST);
    if (!a) {
        PyErr_Format(PyExc_ValueError, "%s: expected a 1-D array of floats", what);
        return NULL;
    }
    if (n >= 0 && PyArray_DIM(a, 0) != n) {
        PyErr_Format(PyExc_ValueError, "%s: expected %zd values, got %zd", what, (Py_ssize_t)n,
                     (Py_ssize_t)PyArray_DIM(a, 0));
        Py_DECREF(a);
        return NULL;
    }
    return a;
}

/* One option: 0 done, 1 not this kind, -1 error. */
static int opt_double(PyObject *v, const char *key, const char *name, double *out)
{
    if (strcmp(key, name)) return 1;
    double x = PyFloat_AsDouble(v);
    if (x == -1.0 && PyErr_Occurred()) return -1;
    *out = x;
    return 0;
}

static int opt_int(PyObject *v, const char *key, const char *name, int *out)
{
    if (strcmp(key, name)) return 1;
    long x = PyLong_AsLong(v);
    if (x == -1 && PyErr_Occurred()) return -1;
    if (x < -2147483647L || x > 2147483647L) {
        PyErr_Format(PyExc_ValueError, "%s: %ld is out of range", name, x);
        return -1;
    }
    *out = (int)x;
    return 0;
}

static int keep_array(PyObject *v, const char *name, npy_intp n, PyObject *keep, const double **out,
                      int *count)
{
    PyArrayObject *a = pyb_as_vector(v, n, name);
    if (!a) return -1;
    int rc = PyList_Append(keep, (PyObject *)a);
    *out = PyArray_DATA(a);
    if (count) *count = (int)PyArray_DIM(a, 0);
    Py_DECREF(a);
    return rc;
}

int pyb_options_from_dict(PyObject *d, dae_options *o, int n, PyObject **keep)
{
    dae_options_default(o);
    *keep = PyList_New(0);
    if (!*keep) return -1;
    if (!d || d == Py_None) return 0;
    PyObject *key, *v;
    Py_ssize_t pos = 0;
    while (PyDict_Next(d, &pos, &key, &v)) {
        const char *k = PyUnicode_AsUTF8(key);
        if (!k) return -1;
        int r = 1, tmp = 0;
        if (!strcmp(k, "atol") && !PyFloat_Check(v) && !PyLong_Check(v)) {
            r = keep_array(v, "atol", n, *keep, &o->atol_vec, NULL);
        } else if (!strcmp(k, "breakpoints")) {
            r = keep_array(v, "breakpoints", -1, *keep, &o->breakpoints, &o->nbreakpoints);
        } else if (!strcmp(k, "t_stop")) {
            r = opt_double(v, k, "t_stop", &o->t_stop);
            o->has_t_stop = 1;
        } else if (!strcmp(k, "max_steps")) {
            long x = PyLong_AsLong(v);
            if (x == -1 && PyErr_Occurred()) return -1;
            o->max_steps = x;
            r = 0;
        } else if (!strcmp(k, "index2") || !strcmp(k, "linsol")) {
            r = opt_int(v, k, k, &tmp);
            if (!strcmp(k, "index2"))
                o->index2 = (dae_index2_policy)tmp;
            else
                o->linsol = (ls_kind)tmp;
        } else {
#define OD(f) if (r == 1) r = opt_double(v, k, #f, &o->f)
#define OI(f) if (r == 1) r = opt_int(v, k, #f, &o->f)
            OD(rtol); OD(atol); OD(h_init); OD(h_min); OD(h_max); OD(newton_dgmax);
            OI(max_order); OI(exclude_alg); OI(max_newton); OI(fixed_step); OI(no_timing);
            OI(newton_index2_scale_h); OI(check_jacobian); OI(newton_jac_age);
            OI(stability_guard); OI(projection);
#undef OD
#undef OI
        }
        if (r < 0) {
            if (PyErr_ExceptionMatches(PyExc_TypeError)) {
                PyErr_Clear();
                PyErr_Format(PyExc_TypeError, "%s: expected a number", k);
            }
            return -1;
        }
        if (r == 1) {
            PyErr_Format(PyExc_TypeError, "unknown solver option '%s'", k);
            return -1;
        }
    }
    return 0;
}

PyObject *pyb_modes_list(const dae_modes *M, int n)
{
    PyObject *list = PyList_New(0);
    if (!list) return NULL;
    for (int k = 0; k < dae_modes_count(M); k++) {
        const dae_mode *md = dae_modes_get(M, k);
        char desc[512];
        dae_modes_describe(M, k, 2, 4, 3, desc, sizeof desc);
        npy_intp dims = n;
        PyObject *re = PyArray_ZEROS(1, &dims, NPY_DOUBLE, 0);
        PyObject *im = PyArray_ZEROS(1, &dims, NPY_DOUBLE, 0);
        if (!re || !im) {
            Py_XDECREF(re), Py_XDECREF(im), Py_DECREF(list);
            return NULL;
        }
        dae_modes_vector(M, k, PyArray_DATA((PyArrayObject *)re),
                         PyArray_DATA((PyArrayObject *)im));
        PyObject *d = Py_BuildValue("{s:d,s:d,s:s,s:d,s:d,s:s,s:N,s:N,s:d}", "frequency_hz",
                                    md->freq_hz, "damping_ratio", md->damping, "kind",
                                    dae_mode_kind_name(md->kind), "re", md->re, "im", md->im,
                                    "description", desc, "shape_re", re, "shape_im", im,
                                    "residual", md->residual);
        if (!d || PyList_Append(list, d) < 0) {
            Py_XDECREF(d), Py_DECREF(list);
            return NULL;
        }
        Py_DECREF(d);
    }
    return list;
}

static PyObject *status_name(PyObject *self, PyObject *arg)
{
    (void)self;
    long c = PyLong_AsLong(arg);
    if (c == -1 && PyErr_Occurred()) return NULL;
    return PyUnicode_FromString(bg_status_name((int)c));
}

static PyObject *default_options(PyObject *self, PyObject *unused)
{
    (void)self, (void)unused;
    dae_options o;
    dae_options_default(&o);
    return Py_BuildValue("{s:d,s:d,s:i,s:d,s:d,s:d,s:l,s:i,s:i,s:i,s:i,s:i,s:i,s:i,s:i,s:d,s:i,s:i}",
                         "rtol", o.rtol, "atol", o.atol, "max_order", o.max_order, "h_init",
                         o.h_init, "h_min", o.h_min, "h_max", o.h_max, "max_steps", o.max_steps,
                         "index2", (int)o.index2, "exclude_alg", o.exclude_alg, "linsol",
                         (int)o.linsol, "max_newton", o.max_newton, "fixed_step", o.fixed_step,
                         "no_timing", o.no_timing, "newton_index2_scale_h",
                         o.newton_index2_scale_h, "check_jacobian", o.check_jacobian,
                         "newton_dgmax", o.newton_dgmax, "newton_jac_age", o.newton_jac_age,
                         "stability_guard", o.stability_guard);
}

static PyMethodDef methods[] = {
    {"default_options", default_options, METH_NOARGS, "The C library's default options."},
    {"dae_solve", (PyCFunction)(void (*)(void))pyb_dae_solve, METH_VARARGS | METH_KEYWORDS,
     "Solve a DAE with a Python residual (bgdae.DAE.solve)."},
    {"dae_static", (PyCFunction)(void (*)(void))pyb_dae_static, METH_VARARGS | METH_KEYWORDS,
     "Static equilibrium of a DAE with a Python residual (bgdae.DAE.static)."},
    {"dae_modes", (PyCFunction)(void (*)(void))pyb_dae_modes, METH_VARARGS | METH_KEYWORDS,
     "Modes of a DAE with a Python residual (bgdae.DAE.modes)."},
    {"status_name", status_name, METH_O, "The name of a status code."},
    {NULL, NULL, 0, NULL}};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "bgdae._core",
                                    "The C library bgdae from Python (see the package bgdae).",
                                    -1, methods, NULL, NULL, NULL, NULL};

PyMODINIT_FUNC PyInit__core(void)
{
    import_array();
    if (PyType_Ready(&pyb_ModelType) < 0) return NULL;
    PyObject *m = PyModule_Create(&module);
    if (!m) return NULL;
    pyb_SolverError = PyErr_NewExceptionWithDoc(
        "bgdae.SolverError",
        "A failure of the solver: message (the library's, naming the unknown or equation and the "
        "time), status (e.g. 'DAE_CONV_FAIL'), code, t, and the values computed before it.",
        PyExc_RuntimeError, NULL);
    if (!pyb_SolverError || PyModule_AddObjectRef(m, "SolverError", pyb_SolverError) < 0 ||
        PyModule_AddObjectRef(m, "Model", (PyObject *)&pyb_ModelType) < 0) {
        Py_DECREF(m);
        return NULL;
    }
    return m;
}
