/* The CPython extension bgdae._core (private to the package python/bgdae/, prefix pyb_): the C
 * library's solver, static solve and modes for a DAE whose residual (and Jacobian) are Python
 * callables (pyb_dae.c), and the model files (pyb_model.c). The package's Python modules check
 * the arguments and name them; this layer converts them and calls the library.
 *
 * Invariants: a Python exception raised by a callback is kept set (the callback returns the
 * fatal status -1, which stops the library's call) and is what the extension's function raises;
 * a failure of the library is raised as bgdae.SolverError with the library's message, the
 * status's name and code and the time; no function prints. */
#ifndef PYB_H
#define PYB_H

#define PY_SSIZE_T_CLEAN
#include <Python.h>

#define NPY_NO_DEPRECATED_API NPY_1_7_API_VERSION
#define PY_ARRAY_UNIQUE_SYMBOL pyb_ARRAY_API
#ifndef PYB_IMPORT_ARRAY
#define NO_IMPORT_ARRAY
#endif
#include <numpy/arrayobject.h>

#include "bg_dae.h"
#include "bg_modes.h"
#include "bg_static.h"

/* bgdae.SolverError (created by the module) */
extern PyObject *pyb_SolverError;

/* Raises SolverError(message) with attributes status (name), code, t; extra (a dict or NULL)
 * adds more attributes (the values computed before the failure; its key "t", the rows' times,
 * becomes t_out). Returns NULL. */
PyObject *pyb_raise_solver(int code, const char *message, double t, PyObject *extra);

/* PyErr_Format with the C library's formats (%g and all): type(message). Returns NULL. */
PyObject *pyb_error(PyObject *type, const char *fmt, ...);

/* The statistics as a dict. */
PyObject *pyb_stats_dict(const dae_stats *st);
/* The options from a dict of keyword arguments (names of dae_options' fields; index2 and
 * linsol as their integer values; atol may be a sequence: atol_vec). The arrays it makes are
 * kept in *keep (a list, or NULL for none) so that they live as long as the options.
 * 0, or -1 with an exception set. */
int pyb_options_from_dict(PyObject *d, dae_options *o, int n, PyObject **keep);
/* A new 1-D float64 array of n values copied from x. */
PyObject *pyb_vector(const double *x, npy_intp n);
/* A C-contiguous float64 array of n values from obj (a new reference), or NULL with
 * ValueError naming what. n < 0: any length. */
PyArrayObject *pyb_as_vector(PyObject *obj, npy_intp n, const char *what);

/* The dae_problem of a Python residual (pyb_dae.c): module functions. */
PyObject *pyb_dae_solve(PyObject *self, PyObject *args, PyObject *kw);
PyObject *pyb_dae_static(PyObject *self, PyObject *args, PyObject *kw);
PyObject *pyb_dae_modes(PyObject *self, PyObject *args, PyObject *kw);

/* The model type (pyb_model.c). */
extern PyTypeObject pyb_ModelType;
/* The modes as a list of dicts (frequency_hz, damping_ratio, kind, re, im, description,
 * shape_re, shape_im). */
PyObject *pyb_modes_list(const dae_modes *M, int n);

#endif
