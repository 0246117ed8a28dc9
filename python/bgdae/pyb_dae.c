/* A DAE whose residual F(t, y, y') and, optionally, Jacobians dF/dy, dF/dy' are Python callables
 * (pyb.h): the library's problem built from the package's checked arguments, the callbacks that
 * call Python, and the three uses: the integration to output times (dae_solve_to), the static
 * equilibrium (dae_static_solve) and the modes (dae_modes_compute).
 *
 * The GIL is held throughout (every residual is a Python call). Each call hands the callable
 * fresh arrays (copies of the solver's y and y'), so that a callable that keeps them keeps valid
 * values. A callable that raises stops the library's call (status -1, fatal) and its exception,
 * with its traceback, is what the extension raises; so is KeyboardInterrupt, the signals being
 * looked at before each residual call. */
#include "pyb.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bg_status.h"

typedef struct pyb_prob {
    PyObject *res, *jac; /* borrowed from the arguments */
    int n;
    dae_problem p;
    sp_csc pat[2]; /* the patterns of dF/dy, dF/dy' (colptr, rowind in keep's arrays) */
    const char **names, **eq_names;
    PyObject *keep; /* the arrays that back the problem */
} pyb_prob;

/* y and y' as fresh arrays. */
static int call_args(pyb_prob *q, double t, const double *y, const double *yp, PyObject **args)
{
    PyObject *ya = pyb_vector(y, q->n), *ypa = pyb_vector(yp, q->n);
    if (!ya || !ypa) {
        Py_XDECREF(ya), Py_XDECREF(ypa);
        return -1;
    }
    *args = Py_BuildValue("(dNN)", t, ya, ypa);
    return *args ? 0 : -1;
}

static int residual(void *user, double t, const double *y, const double *yp, double *F)
{
    pyb_prob *q = user;
    if (PyErr_Occurred() || PyErr_CheckSignals() < 0) return -1; /* Ctrl-C: KeyboardInterrupt */
    PyObject *args, *r;
    if (call_args(q, t, y, yp, &args) < 0) return -1;
    r = PyObject_Call(q->res, args, NULL);
    Py_DECREF(args);
    if (!r) return -1;
    PyArrayObject *a = (PyArrayObject *)PyArray_FROMANY(r, NPY_DOUBLE, 0, 0,
                                                        NPY_ARRAY_IN_ARRAY | NPY_ARRAY_FORCECAST);
    Py_DECREF(r);
    if (!a) {
        PyErr_Clear();
        PyErr_SetString(PyExc_TypeError, "residual: must return an array of floats");
        return -1;
    }
    if (PyArray_NDIM(a) != 1 || PyArray_DIM(a, 0) != q->n) {
        PyErr_Format(PyExc_ValueError, "residual: returned %zd values (%d dimensions), expected %d",
                     (Py_ssize_t)PyArray_SIZE(a), PyArray_NDIM(a), q->n);
        Py_DECREF(a);
        return -1;
    }
    memcpy(F, PyArray_DATA(a), (size_t)q->n * sizeof *F);
    Py_DECREF(a);
    return 0;
}

/* The values of one Jacobian on its pattern from m: a dense (n, n) array or a matrix with
 * tocsc() (scipy.sparse). Entries of m outside the pattern must be zero. */
static int fill_jacobian(pyb_prob *q, PyObject *m, sp_csc *J, const char *what)
{
    int n = q->n;
    memset(J->val, 0, (size_t)J->nnz * sizeof *J->val);
    if (PyObject_HasAttrString(m, "tocsc")) {
        PyObject *c = PyObject_CallMethod(m, "tocsc", NULL);
        if (!c) return -1;
        PyObject *ip = PyObject_GetAttrString(c, "indptr"), *ix = PyObject_GetAttrString(c, "indices");
        PyObject *dv = PyObject_GetAttrString(c, "data"), *shape = PyObject_GetAttrString(c, "shape");
        Py_DECREF(c);
        PyArrayObject *aip = NULL, *aix = NULL, *adv = NULL;
        int rc = -1;
        Py_ssize_t r0 = -1, c0 = -1;
        if (!ip || !ix || !dv || !shape || !PyArg_ParseTuple(shape, "nn", &r0, &c0)) goto sparse_done;
        if (r0 != n || c0 != n) {
            PyErr_Format(PyExc_ValueError, "jac: %s has shape (%zd, %zd), expected (%d, %d)", what,
                         r0, c0, n, n);
            goto sparse_done;
        }
        aip = (PyArrayObject *)PyArray_FROMANY(ip, NPY_LONG, 1, 1, NPY_ARRAY_IN_ARRAY | NPY_ARRAY_FORCECAST);
        aix = (PyArrayObject *)PyArray_FROMANY(ix, NPY_LONG, 1, 1, NPY_ARRAY_IN_ARRAY | NPY_ARRAY_FORCECAST);
        adv = (PyArrayObject *)PyArray_FROMANY(dv, NPY_DOUBLE, 1, 1, NPY_ARRAY_IN_ARRAY | NPY_ARRAY_FORCECAST);
        if (!aip || !aix || !adv) goto sparse_done;
        const long *cp = PyArray_DATA(aip), *ri = PyArray_DATA(aix);
        const double *x = PyArray_DATA(adv);
        for (int j = 0; j < n; j++)
            for (long k = cp[j]; k < cp[j + 1]; k++) {
                int lo = J->colptr[j], hi = J->colptr[j + 1] - 1, i = (int)ri[k];
                while (lo <= hi) { /* rowind ascending within a column */
                    int mid = (lo + hi) / 2;
                    if (J->rowind[mid] == i) {
                        lo = mid;
                        break;
                    }
                    if (J->rowind[mid] < i) lo = mid + 1; else hi = mid - 1;
                }
                if (lo < J->colptr[j + 1] && J->rowind[lo] == i)
                    J->val[lo] += x[k];
                else if (x[k] != 0) {
                    pyb_error(PyExc_ValueError,
                                 "jac: %s has the entry (%d, %d) = %g outside its pattern", what, i,
                                 j, x[k]);
                    goto sparse_done;
                }
            }
        rc = 0;
    sparse_done:
        Py_XDECREF(ip), Py_XDECREF(ix), Py_XDECREF(dv), Py_XDECREF(shape);
        Py_XDECREF(aip), Py_XDECREF(aix), Py_XDECREF(adv);
        return rc;
    }
    PyArrayObject *a = (PyArrayObject *)PyArray_FROMANY(m, NPY_DOUBLE, 2, 2,
                                                        NPY_ARRAY_IN_ARRAY | NPY_ARRAY_FORCECAST);
    if (!a) {
        PyErr_Clear();
        PyErr_Format(PyExc_TypeError, "jac: %s must be a 2-D array or a scipy.sparse matrix", what);
        return -1;
    }
    if (PyArray_DIM(a, 0) != n || PyArray_DIM(a, 1) != n) {
        PyErr_Format(PyExc_ValueError, "jac: %s has shape (%zd, %zd), expected (%d, %d)", what,
                     (Py_ssize_t)PyArray_DIM(a, 0), (Py_ssize_t)PyArray_DIM(a, 1), n, n);
        Py_DECREF(a);
        return -1;
    }
    const double *A = PyArray_DATA(a); /* row-major */
    for (int j = 0; j < n; j++) {
        int k = J->colptr[j];
        for (int i = 0; i < n; i++) {
            double v = A[(size_t)i * (size_t)n + (size_t)j];
            if (k < J->colptr[j + 1] && J->rowind[k] == i)
                J->val[k++] = v;
            else if (v != 0) {
                pyb_error(PyExc_ValueError,
                             "jac: %s has the entry (%d, %d) = %g outside its pattern", what, i, j, v);
                Py_DECREF(a);
                return -1;
            }
        }
    }
    Py_DECREF(a);
    return 0;
}

static int jacobian(void *user, double t, const double *y, const double *yp, sp_csc *Jy, sp_csc *Jyp)
{
    pyb_prob *q = user;
    if (PyErr_Occurred()) return -1;
    PyObject *args, *r;
    if (call_args(q, t, y, yp, &args) < 0) return -1;
    r = PyObject_Call(q->jac, args, NULL);
    Py_DECREF(args);
    if (!r) return -1;
    if (!PyTuple_Check(r) || PyTuple_GET_SIZE(r) != 2) {
        Py_DECREF(r);
        PyErr_SetString(PyExc_TypeError, "jac: must return a pair (dF/dy, dF/dyp)");
        return -1;
    }
    int rc = fill_jacobian(q, PyTuple_GET_ITEM(r, 0), Jy, "dF/dy");
    if (rc == 0) rc = fill_jacobian(q, PyTuple_GET_ITEM(r, 1), Jyp, "dF/dyp");
    Py_DECREF(r);
    return rc;
}

/* A pattern (indptr, indices) of int32 arrays, checked by the package, into J (values zeroed,
 * kept in q->keep). */
static int pattern(pyb_prob *q, PyObject *pair, sp_csc *J)
{
    PyObject *ip, *ix;
    if (!PyArg_ParseTuple(pair, "OO", &ip, &ix)) return -1;
    PyArrayObject *aip = (PyArrayObject *)PyArray_FROMANY(ip, NPY_INT, 1, 1, NPY_ARRAY_IN_ARRAY);
    PyArrayObject *aix = (PyArrayObject *)PyArray_FROMANY(ix, NPY_INT, 1, 1, NPY_ARRAY_IN_ARRAY);
    npy_intp nnz = aix ? PyArray_DIM(aix, 0) : 0;
    PyObject *val = PyArray_ZEROS(1, &nnz, NPY_DOUBLE, 0);
    int rc = aip && aix && val && PyArray_DIM(aip, 0) == q->n + 1 &&
                     PyList_Append(q->keep, (PyObject *)aip) == 0 &&
                     PyList_Append(q->keep, (PyObject *)aix) == 0 && PyList_Append(q->keep, val) == 0
                 ? 0
                 : -1;
    if (rc == 0) {
        J->nrow = J->ncol = q->n;
        J->colptr = PyArray_DATA(aip);
        J->rowind = PyArray_DATA(aix);
        J->val = PyArray_DATA((PyArrayObject *)val);
        J->nnz = (int)nnz;
    } else if (!PyErr_Occurred()) {
        PyErr_SetString(PyExc_ValueError, "pattern: expected (indptr of n + 1, indices)");
    }
    Py_XDECREF(aip), Py_XDECREF(aix), Py_XDECREF(val);
    return rc;
}

static int names_array(pyb_prob *q, PyObject *list, const char ***out)
{
    if (list == Py_None) return 0;
    Py_ssize_t m = PySequence_Length(list);
    if (m != q->n) {
        if (!PyErr_Occurred()) PyErr_Format(PyExc_ValueError, "names: expected %d names", q->n);
        return -1;
    }
    *out = calloc((size_t)q->n, sizeof **out);
    if (!*out) {
        PyErr_NoMemory();
        return -1;
    }
    for (int i = 0; i < q->n; i++) {
        PyObject *s = PySequence_GetItem(list, i);
        if (!s) return -1;
        int bad = PyList_Append(q->keep, s) < 0; /* keeps the UTF-8 buffer alive */
        (*out)[i] = bad ? NULL : PyUnicode_AsUTF8(s);
        Py_DECREF(s);
        if (!(*out)[i]) return -1;
    }
    return 0;
}

static void prob_clear(pyb_prob *q)
{
    free(q->names);
    free(q->eq_names);
    Py_XDECREF(q->keep);
}

/* The problem from the keyword arguments, after a check that those the call needs are there
 * (required: a NULL-terminated list of names). */
static int prob_setup(pyb_prob *q, PyObject *kw, const char *const *required)
{
    memset(q, 0, sizeof *q);
    for (int i = 0; required[i]; i++)
        if (!PyDict_GetItemString(kw, required[i])) {
            PyErr_Format(PyExc_TypeError, "the argument %s is required", required[i]);
            return -1;
        }
    q->keep = PyList_New(0);
    if (!q->keep) return -1;
    PyObject *res = PyDict_GetItemString(kw, "res"), *jac = PyDict_GetItemString(kw, "jac");
    PyObject *n = PyDict_GetItemString(kw, "n");
    if (!res || !jac || !n) {
        PyErr_SetString(PyExc_TypeError, "res, jac and n are required");
        return -1;
    }
    q->res = res;
    q->jac = jac == Py_None ? NULL : jac;
    long nl = PyLong_AsLong(n);
    if (PyErr_Occurred()) return -1;
    if (nl < 1 || nl > 100000000L || !PyCallable_Check(res) || (q->jac && !PyCallable_Check(q->jac))) {
        PyErr_SetString(PyExc_ValueError, "n must be in 1..1e8, res and jac callables");
        return -1;
    }
    q->n = (int)nl;
    dae_problem *p = &q->p;
    p->n = q->n;
    p->res = residual;
    p->jac = q->jac ? jacobian : NULL;
    p->user = q;
    PyObject *v;
    if ((v = PyDict_GetItemString(kw, "jy_pattern")) && v != Py_None) {
        if (pattern(q, v, &q->pat[0]) < 0) return -1;
        p->jac_y_pattern = &q->pat[0];
    }
    if ((v = PyDict_GetItemString(kw, "jyp_pattern")) && v != Py_None) {
        if (pattern(q, v, &q->pat[1]) < 0) return -1;
        p->jac_yp_pattern = &q->pat[1];
    }
    if ((v = PyDict_GetItemString(kw, "kinds")) && v != Py_None) {
        PyArrayObject *a = (PyArrayObject *)PyArray_FROMANY(v, NPY_INT, 1, 1, NPY_ARRAY_IN_ARRAY);
        if (!a || PyArray_DIM(a, 0) != q->n || PyList_Append(q->keep, (PyObject *)a) < 0) {
            Py_XDECREF(a);
            if (!PyErr_Occurred()) PyErr_Format(PyExc_ValueError, "kinds: expected %d values", q->n);
            return -1;
        }
        p->kind = PyArray_DATA(a);
        Py_DECREF(a);
    }
    if ((v = PyDict_GetItemString(kw, "nominal")) && v != Py_None) {
        PyArrayObject *a = pyb_as_vector(v, q->n, "nominal");
        if (!a || PyList_Append(q->keep, (PyObject *)a) < 0) {
            Py_XDECREF(a);
            return -1;
        }
        p->nominal = PyArray_DATA(a);
        Py_DECREF(a);
    }
    if ((v = PyDict_GetItemString(kw, "names")) && names_array(q, v, &q->names) < 0) return -1;
    if ((v = PyDict_GetItemString(kw, "eq_names")) && names_array(q, v, &q->eq_names) < 0) return -1;
    p->names = q->names;
    p->eq_names = q->eq_names;
    return 0;
}

/* A vector argument of kw (a new reference; NULL with the error set). */
static PyArrayObject *kw_vector(PyObject *kw, const char *key, npy_intp n)
{
    PyObject *v = PyDict_GetItemString(kw, key);
    if (!v) {
        PyErr_Format(PyExc_TypeError, "%s is required", key);
        return NULL;
    }
    return pyb_as_vector(v, n, key);
}

/* The rows computed (m of them) as a dict t, y, yp, stats. */
static PyObject *rows_dict(PyArrayObject *T, PyArrayObject *Y, PyArrayObject *YP, npy_intp m,
                           int n, dae_solver *s)
{
    npy_intp d1[1] = {m}, d2[2] = {m, n};
    PyObject *t = PyArray_SimpleNew(1, d1, NPY_DOUBLE), *y = PyArray_SimpleNew(2, d2, NPY_DOUBLE);
    PyObject *yp = PyArray_SimpleNew(2, d2, NPY_DOUBLE), *st = s ? pyb_stats_dict(dae_get_stats(s)) : Py_NewRef(Py_None);
    if (!t || !y || !yp || !st) {
        Py_XDECREF(t), Py_XDECREF(y), Py_XDECREF(yp), Py_XDECREF(st);
        return NULL;
    }
    memcpy(PyArray_DATA((PyArrayObject *)t), PyArray_DATA(T), (size_t)m * sizeof(double));
    memcpy(PyArray_DATA((PyArrayObject *)y), PyArray_DATA(Y), (size_t)(m * n) * sizeof(double));
    memcpy(PyArray_DATA((PyArrayObject *)yp), PyArray_DATA(YP), (size_t)(m * n) * sizeof(double));
    return Py_BuildValue("{s:N,s:N,s:N,s:N}", "t", t, "y", y, "yp", yp, "stats", st);
}

PyObject *pyb_dae_solve(PyObject *self, PyObject *args, PyObject *kw)
{
    (void)self, (void)args;
    pyb_prob q;
    PyObject *keep = NULL, *out = NULL;
    PyArrayObject *y0 = NULL, *yp0 = NULL, *tout = NULL, *T = NULL, *Y = NULL, *YP = NULL;
    dae_solver *s = NULL;
    if (!kw) {
        PyErr_SetString(PyExc_TypeError, "keyword arguments expected");
        return NULL;
    }
    static const char *const req[] = {"res", "jac", "n", "t0", "y0", "t_out", "consistent", NULL};
    if (prob_setup(&q, kw, req) < 0) goto done;
    int n = q.n;
    dae_options o;
    if (pyb_options_from_dict(PyDict_GetItemString(kw, "options"), &o, n, &keep) < 0) goto done;
    PyObject *v = PyDict_GetItemString(kw, "yp0");
    double t0 = PyFloat_AsDouble(PyDict_GetItemString(kw, "t0"));
    int consistent = PyObject_IsTrue(PyDict_GetItemString(kw, "consistent"));
    if (PyErr_Occurred() || !(y0 = kw_vector(kw, "y0", n)) || !(tout = kw_vector(kw, "t_out", -1)))
        goto done;
    if (v && v != Py_None && !(yp0 = pyb_as_vector(v, n, "yp0"))) goto done;
    npy_intp m = PyArray_DIM(tout, 0), dims[2] = {m, n};
    T = (PyArrayObject *)PyArray_ZEROS(1, dims, NPY_DOUBLE, 0);
    Y = (PyArrayObject *)PyArray_ZEROS(2, dims, NPY_DOUBLE, 0);
    YP = (PyArrayObject *)PyArray_ZEROS(2, dims, NPY_DOUBLE, 0);
    if (!T || !Y || !YP) goto done;
    bg_error err = {0};
    s = dae_create(&q.p, &o, &err);
    if (!s) {
        if (!PyErr_Occurred()) pyb_raise_solver(err.status, err.message, t0, NULL);
        goto done;
    }
    int rc = dae_init(s, t0, PyArray_DATA(y0), yp0 ? PyArray_DATA(yp0) : NULL);
    if (rc == BG_OK && consistent) rc = dae_consistent_init(s);
    const char *warning = rc == DAE_WARNING ? dae_get_warning(s) : "";
    if (rc < 0) {
        if (!PyErr_Occurred()) pyb_raise_solver(rc, dae_get_error(s)->message, t0, NULL);
        goto done;
    }
    const double *tv = PyArray_DATA(tout);
    double *tr = PyArray_DATA(T), *yr = PyArray_DATA(Y), *ypr = PyArray_DATA(YP);
    npy_intp k;
    for (k = 0; k < m; k++) {
        double tret = t0, *yk = yr + k * n, *ypk = ypr + k * n;
        if (tv[k] <= t0) { /* the start (consistent values when found) */
            if (!consistent || dae_get_consistent(s, yk, ypk) != BG_OK) {
                memcpy(yk, PyArray_DATA(y0), (size_t)n * sizeof *yk);
                if (yp0) memcpy(ypk, PyArray_DATA(yp0), (size_t)n * sizeof *ypk);
            }
            tr[k] = t0;
            continue;
        }
        rc = dae_solve_to(s, tv[k], &tret, yk, ypk);
        if (rc < 0) {
            if (PyErr_Occurred()) goto done; /* the callback's exception */
            PyObject *partial = rows_dict(T, Y, YP, k, n, s);
            if (partial) {
                pyb_raise_solver(rc, dae_get_error(s)->message, tret, partial);
                Py_DECREF(partial);
            }
            goto done;
        }
        tr[k] = tret;
        if (rc == DAE_TSTOP_RETURN && tret < tv[k]) {
            k++;
            break;
        }
    }
    out = rows_dict(T, Y, YP, k, n, s);
    if (out) {
        const int *kinds = dae_get_kinds(s);
        npy_intp dn = n;
        PyObject *ka = PyArray_SimpleNew(1, &dn, NPY_INT);
        if (ka && kinds) memcpy(PyArray_DATA((PyArrayObject *)ka), kinds, (size_t)n * sizeof(int));
        PyObject *w = PyUnicode_FromString(warning);
        if (!ka || !w || PyDict_SetItemString(out, "kinds", ka) < 0 ||
            PyDict_SetItemString(out, "warning", w) < 0)
            Py_CLEAR(out);
        Py_XDECREF(ka), Py_XDECREF(w);
    }
done:
    dae_free(&s);
    prob_clear(&q);
    Py_XDECREF(keep), Py_XDECREF(y0), Py_XDECREF(yp0), Py_XDECREF(tout);
    Py_XDECREF(T), Py_XDECREF(Y), Py_XDECREF(YP);
    return out;
}

PyObject *pyb_dae_static(PyObject *self, PyObject *args, PyObject *kw)
{
    (void)self, (void)args;
    pyb_prob q;
    PyObject *out = NULL, *y = NULL, *yp = NULL;
    PyArrayObject *y0 = NULL;
    if (!kw) {
        PyErr_SetString(PyExc_TypeError, "keyword arguments expected");
        return NULL;
    }
    static const char *const req[] = {"res", "jac", "n", "t0", "y0", NULL};
    if (prob_setup(&q, kw, req) < 0) goto done;
    dae_static_options so;
    dae_static_options_default(&so);
    PyObject *d = PyDict_GetItemString(kw, "options"), *key, *v;
    Py_ssize_t pos = 0;
    while (d && d != Py_None && PyDict_Next(d, &pos, &key, &v)) {
        const char *k = PyUnicode_AsUTF8(key);
        if (!k) goto done;
        double x = PyFloat_AsDouble(v);
        if (x == -1.0 && PyErr_Occurred()) goto done;
        if (!strcmp(k, "rtol")) so.rtol = x;
        else if (!strcmp(k, "atol")) so.atol = x;
        else if (!strcmp(k, "max_newton")) so.max_newton = (int)x;
        else if (!strcmp(k, "max_steps")) so.max_steps = (long)x;
        else if (!strcmp(k, "continuation")) so.continuation = (int)x;
        else if (!strcmp(k, "dlambda")) so.dlambda = x;
        else if (!strcmp(k, "dlambda_min")) so.dlambda_min = x;
        else if (!strcmp(k, "h0")) so.h0 = x;
        else if (!strcmp(k, "h_max")) so.h_max = x;
        else {
            PyErr_Format(PyExc_TypeError, "unknown static option '%s'", k);
            goto done;
        }
    }
    double t = PyFloat_AsDouble(PyDict_GetItemString(kw, "t0"));
    if (PyErr_Occurred() || !(y0 = kw_vector(kw, "y0", q.n))) goto done;
    y = pyb_vector(PyArray_DATA(y0), q.n);
    npy_intp dn = q.n;
    yp = PyArray_ZEROS(1, &dn, NPY_DOUBLE, 0);
    if (!y || !yp) goto done;
    dae_static_result r = {0};
    bg_error err = {0};
    int rc = dae_static_solve(&q.p, &so, t, PyArray_DATA((PyArrayObject *)y),
                              PyArray_DATA((PyArrayObject *)yp), &r, &err);
    if (PyErr_Occurred()) goto done;
    PyObject *info = Py_BuildValue(
        "{s:d,s:d,s:d,s:l,s:l,s:l,s:l,s:l,s:d,s:O,s:O}", "lambda", r.lambda, "residual",
        r.residual, "correction", r.correction, "steps", r.steps, "rejected", r.rejected,
        "newton_iters", r.newton_iters, "res_evals", r.res_evals, "jac_evals", r.jac_evals,
        "seconds", r.seconds, "y", y, "yp", yp);
    if (!info) goto done;
    if (rc != BG_OK) {
        pyb_raise_solver(rc, err.message, t, info);
        Py_DECREF(info);
        goto done;
    }
    out = info;
done:
    prob_clear(&q);
    Py_XDECREF(y0), Py_XDECREF(y), Py_XDECREF(yp);
    return out;
}

PyObject *pyb_dae_modes(PyObject *self, PyObject *args, PyObject *kw)
{
    (void)self, (void)args;
    pyb_prob q;
    PyObject *out = NULL;
    PyArrayObject *y = NULL, *yp = NULL;
    dae_modes *M = NULL;
    if (!kw) {
        PyErr_SetString(PyExc_TypeError, "keyword arguments expected");
        return NULL;
    }
    static const char *const req[] = {"res", "jac", "n", "t0", "y0", NULL};
    if (prob_setup(&q, kw, req) < 0) goto done;
    double t = PyFloat_AsDouble(PyDict_GetItemString(kw, "t0"));
    if (PyErr_Occurred() || !(y = kw_vector(kw, "y0", q.n))) goto done;
    PyObject *v = PyDict_GetItemString(kw, "yp0");
    if (v && v != Py_None && !(yp = pyb_as_vector(v, q.n, "yp0"))) goto done;
    dae_modes_options mo;
    dae_modes_options_default(&mo);
    bg_error err = {0};
    int rc = dae_modes_compute(&q.p, t, PyArray_DATA(y), yp ? PyArray_DATA(yp) : NULL, &mo, &M, &err);
    if (PyErr_Occurred()) goto done;
    if (rc != BG_OK && rc != DAE_CONV_FAIL) {
        pyb_raise_solver(rc, err.message, t, NULL);
        goto done;
    }
    out = pyb_modes_list(M, q.n); /* described while the names are alive */
done:
    dae_modes_free(&M);
    prob_clear(&q);
    Py_XDECREF(y), Py_XDECREF(yp);
    return out;
}
