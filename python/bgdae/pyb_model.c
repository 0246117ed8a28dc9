/* bgdae._core.Model: a model file (mdl_model.h) loaded with its replacements, and its runs
 * (pyb.h). A run is bgsim's (bgsim/bs_run.c: bs_simulate) on the library alone: the file's
 * solver settings with the caller's overrides (mdl_solver_override), the static start when the
 * file asks for it (mdl_static, with its trim), the solver from consistent initial values, then
 * the output times k output_step (k < nout, nout = ceil(t_end / output_step - 1e-9)) and t_end,
 * each reached by single steps (dae_step) and interpolated in the last (dae_solve_to), the
 * declared outputs there (mdl_outputs): the same calls in the same order as bgsim's run loop
 * (runner/rn_loop.c), hence the same numbers. With error_estimate = K the companion run at
 * rtol / K, atol / K of the runner (runner/rn_errest.h) follows in lockstep. The integration
 * runs with the GIL released (nothing in it calls Python).
 *
 * A run or a static solve changes the model (the static start writes its initial values, a
 * trim rebuilds it): used is set, and the package loads the file again before the next one. */
#include "pyb.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bg_status.h"
#include "bgr_analysis.h"
#include "mdl_model.h"
#include "rn_errest.h"

typedef struct {
    PyObject_HEAD
    mdl_model *mm;
    int used;
    int busy; /* a call is working on mm with the GIL released: another one is refused */
} pyb_model;

static int model_init(PyObject *self_, PyObject *args, PyObject *kw)
{
    pyb_model *self = (pyb_model *)self_;
    static char *kwlist[] = {"path", "sets", NULL};
    const char *path;
    PyObject *sets = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "s|O", kwlist, &path, &sets)) return -1;
    if (self->busy) {
        PyErr_SetString(PyExc_RuntimeError, "the model is in use by another thread's call");
        return -1;
    }
    Py_ssize_t ns = sets && sets != Py_None ? PySequence_Length(sets) : 0;
    if (ns < 0) return -1;
    mdl_set *ms = calloc((size_t)ns + 1, sizeof *ms);
    PyObject *items = PyList_New(0);
    int rc = -1;
    if (!ms || !items) goto done;
    for (Py_ssize_t i = 0; i < ns; i++) {
        PyObject *it = PySequence_GetItem(sets, i);
        if (!it || PyList_Append(items, it) < 0) {
            Py_XDECREF(it);
            goto done;
        }
        Py_DECREF(it);
        if (!PyArg_ParseTuple(it, "ss", &ms[i].path, &ms[i].value)) goto done;
    }
    bg_error err = {0};
    mdl_model *mm;
    self->busy = 1;
    Py_BEGIN_ALLOW_THREADS
    mm = mdl_load(path, ms, (int)ns, &err);
    Py_END_ALLOW_THREADS
    self->busy = 0;
    if (!mm) {
        PyErr_SetString(err.status == BG_ERR_IO ? PyExc_OSError : PyExc_ValueError, err.message);
        goto done;
    }
    mdl_free(&self->mm);
    self->mm = mm;
    self->used = 0;
    rc = 0;
done:
    free(ms);
    Py_XDECREF(items);
    return rc;
}

static void model_dealloc(PyObject *self_)
{
    pyb_model *self = (pyb_model *)self_;
    mdl_free(&self->mm);
    Py_TYPE(self_)->tp_free(self_);
}

static int loaded(pyb_model *self)
{
    if (self->busy) {
        PyErr_SetString(PyExc_RuntimeError,
                        "the model is in use by another thread's call (one call at a time)");
        return 0;
    }
    if (self->mm) return 1;
    PyErr_SetString(PyExc_RuntimeError, "the model is not loaded");
    return 0;
}

static PyObject *model_info(PyObject *self_, PyObject *unused)
{
    (void)unused;
    pyb_model *self = (pyb_model *)self_;
    if (!loaded(self)) return NULL;
    mdl_model *mm = self->mm;
    bgr_model *m = mdl_bgr(mm);
    int n = bgr_n(m), no = mdl_noutputs(mm);
    const mdl_solver_settings *s = mdl_solver(mm);
    PyObject *names = PyList_New(n), *outs = PyList_New(no), *eqs = PyList_New(n);
    npy_intp dn = n;
    PyObject *kinds = PyArray_SimpleNew(1, &dn, NPY_INT);
    PyObject *y0 = pyb_vector(bgr_y0(m), n), *yp0 = pyb_vector(bgr_yp0(m), n);
    const double *nom = bgr_nominals(m);
    PyObject *nominal = nom ? pyb_vector(nom, n) : Py_NewRef(Py_None);
    if (!names || !outs || !eqs || !kinds || !y0 || !yp0 || !nominal) goto fail;
    for (int i = 0; i < n; i++) {
        PyObject *a = PyUnicode_FromString(bgr_var_name(m, i));
        PyObject *b = PyUnicode_FromString(bgr_eq_name(m, i) ? bgr_eq_name(m, i) : "");
        if (!a || !b) {
            Py_XDECREF(a), Py_XDECREF(b);
            goto fail;
        }
        PyList_SET_ITEM(names, i, a);
        PyList_SET_ITEM(eqs, i, b);
        ((int *)PyArray_DATA((PyArrayObject *)kinds))[i] = bgr_kinds(m) ? bgr_kinds(m)[i] : 0;
    }
    for (int i = 0; i < no; i++) {
        PyObject *a = PyUnicode_FromString(mdl_output_name(mm, i));
        if (!a) goto fail;
        PyList_SET_ITEM(outs, i, a);
    }
    return Py_BuildValue(
        "{s:s,s:s,s:s,s:N,s:N,s:N,s:N,s:N,s:N,s:N,s:{s:d,s:d,s:d,s:d,s:i,s:i,s:i,s:d,s:i,s:i}}",
        "name", mdl_name(mm), "file", mdl_file(mm), "start",
        mdl_start_kind(mm) == MDL_START_STATIC ? "static" : "given", "unknowns", names,
        "equations", eqs, "outputs", outs, "kinds", kinds, "y0", y0, "yp0", yp0, "nominal",
        nominal, "settings", "t_end", s->t_end, "output_step", s->output_step, "rtol", s->rtol,
        "atol", s->atol, "nominal_scales", s->nominal_scales, "max_order", s->max_order,
        "stability_guard", s->stability_guard, "newton_dgmax", s->newton_dgmax,
        "newton_jac_age", s->newton_jac_age, "newton_index2_scale_h", s->newton_index2_scale_h);
fail:
    Py_XDECREF(names), Py_XDECREF(outs), Py_XDECREF(eqs), Py_XDECREF(kinds);
    Py_XDECREF(y0), Py_XDECREF(yp0), Py_XDECREF(nominal);
    return NULL;
}

static PyObject *model_parameter(PyObject *self_, PyObject *arg)
{
    pyb_model *self = (pyb_model *)self_;
    const char *name = PyUnicode_AsUTF8(arg);
    if (!name || !loaded(self)) return NULL;
    double v;
    if (mdl_parameter(self->mm, name, &v) != BG_OK) {
        PyErr_Format(PyExc_KeyError, "%s: no model parameter of this name in %s", name,
                     mdl_file(self->mm));
        return NULL;
    }
    return PyFloat_FromDouble(v);
}

/* The static start (bgsim's static_start): mdl_static with the default options and the
 * settings put back after a trim. BG_OK or the failure, its message in err. */
static int static_start(pyb_model *self, const mdl_solver_settings *set, mdl_trim_report *rep,
                        bg_error *err)
{
    dae_static_options so;
    dae_static_options_default(&so);
    int st = mdl_static(&self->mm, &so, rep, err);
    if (st == BG_OK && mdl_solver_override(self->mm, set) != BG_OK)
        st = bg_error_raise(err, BG_ERR_ARGUMENT, "run", "the solver settings are out of range");
    return st;
}

static PyObject *report_dict(const mdl_trim_report *t)
{
    const dae_static_result *s = &t->last;
    return Py_BuildValue("{s:d,s:l,s:l,s:l,s:d,s:d,s:i,s:s,s:s,s:d,s:d,s:d,s:i}", "lambda",
                         s->lambda, "steps", s->steps, "rejected", s->rejected, "newton_iters",
                         s->newton_iters, "residual", s->residual, "seconds", s->seconds,
                         "trimmed", t->trimmed, "trim_parameter", t->parameter, "trim_output",
                         t->output, "trim_target", t->target, "trim_value", t->value,
                         "trim_achieved", t->achieved, "trim_solves", t->solves);
}

/* The settings with the overrides (None: the file's). 0, or -1 with ValueError. */
static int settings(pyb_model *self, PyObject *const *ov, mdl_solver_settings *s)
{
    *s = *mdl_solver(self->mm);
    double *f[4] = {&s->t_end, &s->output_step, &s->rtol, &s->atol};
    for (int i = 0; i < 4; i++)
        if (ov[i] && ov[i] != Py_None) {
            *f[i] = PyFloat_AsDouble(ov[i]);
            if (PyErr_Occurred()) return -1;
        }
    if (mdl_solver_override(self->mm, s) != BG_OK) {
        pyb_error(PyExc_ValueError,
                     "the solver settings are out of range (t_end %g, output_step %g, rtol %g, "
                     "atol %g: each finite and > 0)",
                     s->t_end, s->output_step, s->rtol, s->atol);
        return -1;
    }
    return 0;
}

/* The companion's outputs (ctx: the model): the run's, NAN where they cannot be computed (the
 * column then has no values), as bgsim's. */
static void errest_out(void *ctx, double t, const double *y, const double *yp, double *out)
{
    (void)yp;
    mdl_model *mm = ctx;
    if (mdl_outputs(mm, t, y, out, NULL) != BG_OK)
        for (int i = 0; i < mdl_noutputs(mm); i++)
            out[i] = NAN;
}

/* The run loop (rn_loop's calls without its files and signals): rows 0 .. nout into T, OUT.
 * Returns the status: BG_OK, the solver's failure (message in msg), or BG_ERR_CALLBACK for an
 * output; *rows: the rows written. */
static int run_loop(mdl_model *mm, dae_solver *s, rn_errest *e, double t_end, double dt, long nout,
                    double *T, double *OUT, double *y, double *yp, long *rows, double *t_fail,
                    char *msg, size_t size)
{
    int no = mdl_noutputs(mm), rc = BG_OK;
    bg_error err = {0};
    double tret = 0;
    *rows = 0;
    dae_dense(s, 0.0, y, yp);
    for (long k = 0; k <= nout; k++) {
        double tout = k == nout ? t_end : (double)k * dt;
        if (tout > t_end) tout = t_end;
        if (k > 0) {
            while (dae_current_time(s) < tout) {
                rc = dae_step(s, tout, &tret, y, yp);
                if (rc < 0) goto failed;
            }
            rc = dae_solve_to(s, tout, &tret, y, yp);
            if (rc == BG_ERR_ARGUMENT) { /* rn_loop's case of a tout just behind a restart */
                double t0 = dae_current_time(s) - dae_get_stats(s)->h_last;
                if (t0 > tout && t0 - tout <= 1e-9 * fmax(1.0, fabs(tout)) &&
                    dae_dense(s, t0, y, yp) == BG_OK) {
                    tret = t0;
                    rc = DAE_SUCCESS;
                }
            }
            if (rc < 0) goto failed;
        }
        T[k] = tret;
        if (mdl_outputs(mm, tret, y, OUT + k * no, &err) != BG_OK) {
            snprintf(msg, size, "outputs at t = %.9g: %s", tret, err.message);
            *t_fail = tret;
            return BG_ERR_CALLBACK;
        }
        *rows = k + 1;
        if (e && rn_errest_status(e) >= 0) rn_errest_add(e, tret, OUT + k * no);
    }
    return BG_OK;
failed:
    snprintf(msg, size, "%s", dae_get_error(s)->message);
    *t_fail = tret;
    return rc;
}

static PyObject *errest_dict(rn_errest *e, mdl_model *mm)
{
    double rtol, atol, factor;
    rn_errest_tolerances(e, &rtol, &atol, &factor);
    int no = mdl_noutputs(mm);
    npy_intp dn = no;
    PyObject *me = PyArray_SimpleNew(1, &dn, NPY_DOUBLE), *ta = PyArray_SimpleNew(1, &dn, NPY_DOUBLE);
    PyObject *ma = PyArray_SimpleNew(1, &dn, NPY_DOUBLE);
    if (!me || !ta || !ma) {
        Py_XDECREF(me), Py_XDECREF(ta), Py_XDECREF(ma);
        return NULL;
    }
    for (int j = 0; j < no; j++) {
        const rn_errest_col *c = rn_errest_column(e, j);
        ((double *)PyArray_DATA((PyArrayObject *)me))[j] = c->max_err;
        ((double *)PyArray_DATA((PyArrayObject *)ta))[j] = c->t_at;
        ((double *)PyArray_DATA((PyArrayObject *)ma))[j] = c->max_abs;
    }
    return Py_BuildValue("{s:d,s:d,s:d,s:s,s:s,s:l,s:N,s:N,s:N}", "factor", factor, "rtol", rtol,
                         "atol", atol, "status", bg_status_name(rn_errest_status(e)), "message",
                         rn_errest_message(e), "times", rn_errest_count(e), "max_error", me,
                         "t_at", ta, "max_abs", ma);
}

static PyObject *model_run(PyObject *self_, PyObject *args, PyObject *kw)
{
    pyb_model *self = (pyb_model *)self_;
    static char *kwlist[] = {"t_end", "output_step", "rtol", "atol", "error_estimate", NULL};
    PyObject *ov[4] = {NULL, NULL, NULL, NULL};
    double factor = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "|OOOOd", kwlist, &ov[0], &ov[1], &ov[2], &ov[3],
                                     &factor) ||
        !loaded(self))
        return NULL;
    if (factor != 0 && !(factor > 1 && factor <= RN_ERREST_MAX_FACTOR)) {
        pyb_error(PyExc_ValueError, "error_estimate: %g is out of range (expected > 1 and <= %g)",
                     factor, RN_ERREST_MAX_FACTOR);
        return NULL;
    }
    mdl_solver_settings set;
    if (settings(self, ov, &set) < 0) return NULL;
    double nout_d = ceil(set.t_end / set.output_step - 1e-9);
    if (!(nout_d >= 1)) nout_d = 1;
    if (!(nout_d <= 1e8)) {
        PyErr_Format(PyExc_ValueError, "t_end / output_step makes %.4g output rows (at most 1e8)",
                     nout_d + 1);
        return NULL;
    }
    long nout = (long)nout_d;
    self->used = 1;
    mdl_trim_report rep = {0};
    bg_error err = {0};
    int static_done = mdl_start_kind(self->mm) == MDL_START_STATIC, st = BG_OK;
    if (static_done) {
        self->busy = 1;
        Py_BEGIN_ALLOW_THREADS
        st = static_start(self, &set, &rep, &err);
        Py_END_ALLOW_THREADS
        self->busy = 0;
        if (st != BG_OK) return pyb_raise_solver(st, err.message, 0.0, NULL);
    }
    mdl_model *mm = self->mm;
    bgr_model *m = mdl_bgr(mm);
    int n = bgr_n(m), no = mdl_noutputs(mm);
    npy_intp d1 = nout + 1, d2[2] = {nout + 1, no};
    PyArrayObject *T = (PyArrayObject *)PyArray_ZEROS(1, &d1, NPY_DOUBLE, 0);
    PyArrayObject *OUT = (PyArrayObject *)PyArray_ZEROS(2, d2, NPY_DOUBLE, 0);
    PyObject *yf = NULL, *ypf = NULL, *result = NULL;
    npy_intp dn = n;
    yf = PyArray_ZEROS(1, &dn, NPY_DOUBLE, 0);
    ypf = PyArray_ZEROS(1, &dn, NPY_DOUBLE, 0);
    dae_options o;
    dae_problem p;
    double *bk = NULL, t_fail = 0;
    dae_solver *s = NULL;
    rn_errest *e = NULL;
    long rows = 0;
    char msg[BG_MESSAGE_SIZE + 128] = "", warning[BG_MESSAGE_SIZE] = "";
    if (!T || !OUT || !yf || !ypf) goto done;
    if (mdl_dae_options(mm, &o, &bk) != BG_OK || mdl_dae_problem(mm, &p) != BG_OK) {
        PyErr_NoMemory();
        goto done;
    }
    int rc;
    self->busy = 1;
    Py_BEGIN_ALLOW_THREADS
    s = dae_create(&p, &o, &err);
    rc = s ? dae_init(s, 0.0, bgr_y0(m), bgr_yp0(m)) : err.status;
    if (rc == BG_OK) rc = dae_consistent_init(s);
    if (rc == DAE_WARNING) {
        snprintf(warning, sizeof warning, "%s", dae_get_warning(s));
        rc = BG_OK;
    }
    if (rc != BG_OK) {
        snprintf(msg, sizeof msg, "consistent initial values: %s",
                 s ? dae_get_error(s)->message : err.message);
    } else {
        if (factor > 0) {
            rn_errest_spec es = {&p, &o, factor, 0.0, bgr_y0(m), bgr_yp0(m), 1, no, errest_out,
                                 mm, NULL};
            e = rn_errest_create(&es, NULL);
        }
        rc = run_loop(mm, s, e, set.t_end, set.output_step, nout, PyArray_DATA(T),
                      PyArray_DATA(OUT), PyArray_DATA((PyArrayObject *)yf),
                      PyArray_DATA((PyArrayObject *)ypf), &rows, &t_fail, msg, sizeof msg);
    }
    Py_END_ALLOW_THREADS
    self->busy = 0;
    PyObject *stats = s ? pyb_stats_dict(dae_get_stats(s)) : Py_NewRef(Py_None);
    PyObject *rep_d = static_done ? report_dict(&rep) : Py_NewRef(Py_None);
    PyObject *est = e ? errest_dict(e, mm) : Py_NewRef(Py_None);
    if (!stats || !rep_d || !est) {
        Py_XDECREF(stats), Py_XDECREF(rep_d), Py_XDECREF(est);
        goto done;
    }
    /* the rows computed (all of them, or those before a failure) */
    PyObject *stop = PyLong_FromLong(rows);
    PyObject *slice = stop ? PySlice_New(NULL, stop, NULL) : NULL;
    Py_XDECREF(stop);
    PyObject *t_rows = slice ? PyObject_GetItem((PyObject *)T, slice) : NULL;
    PyObject *o_rows = slice ? PyObject_GetItem((PyObject *)OUT, slice) : NULL;
    Py_XDECREF(slice);
    result = t_rows && o_rows
                 ? Py_BuildValue("{s:N,s:N,s:N,s:N,s:O,s:O,s:N,s:s,s:d}", "t", t_rows, "outputs",
                                 o_rows, "stats", stats, "static", rep_d, "y", yf, "yp", ypf,
                                 "error_estimate", est, "warning", warning, "t_end", set.t_end)
                 : NULL;
    if (!result) {
        Py_XDECREF(t_rows), Py_XDECREF(o_rows), Py_DECREF(stats), Py_DECREF(rep_d), Py_DECREF(est);
        goto done;
    }
    if (rc != BG_OK) {
        pyb_raise_solver(rc, msg, t_fail, result);
        Py_CLEAR(result);
    }
done:
    rn_errest_free(&e);
    dae_free(&s);
    free(bk);
    Py_XDECREF(T), Py_XDECREF(OUT), Py_XDECREF(yf), Py_XDECREF(ypf);
    return result;
}

static PyObject *model_static(PyObject *self_, PyObject *unused)
{
    (void)unused;
    pyb_model *self = (pyb_model *)self_;
    if (!loaded(self)) return NULL;
    mdl_solver_settings set = *mdl_solver(self->mm);
    mdl_trim_report rep = {0};
    bg_error err = {0};
    int st;
    self->used = 1;
    self->busy = 1;
    Py_BEGIN_ALLOW_THREADS
    st = static_start(self, &set, &rep, &err);
    Py_END_ALLOW_THREADS
    self->busy = 0;
    PyObject *rd = report_dict(&rep);
    if (!rd) return NULL;
    if (st != BG_OK) {
        pyb_raise_solver(st, err.message, 0.0, rd);
        Py_DECREF(rd);
        return NULL;
    }
    bgr_model *m = mdl_bgr(self->mm);
    int no = mdl_noutputs(self->mm);
    npy_intp dn = no;
    PyObject *y = pyb_vector(bgr_y0(m), bgr_n(m)), *out = PyArray_ZEROS(1, &dn, NPY_DOUBLE, 0);
    if (!y || !out ||
        mdl_outputs(self->mm, 0.0, bgr_y0(m), PyArray_DATA((PyArrayObject *)out), &err) != BG_OK) {
        if (!PyErr_Occurred()) PyErr_SetString(PyExc_ValueError, err.message);
        Py_XDECREF(y), Py_XDECREF(out), Py_DECREF(rd);
        return NULL;
    }
    return Py_BuildValue("{s:N,s:N,s:N}", "y", y, "outputs", out, "report", rd);
}

/* bgsim --modes T: at T = 0 (or with a static start) the static equilibrium first, at T > 0 the
 * run to T; the modes of the linearisation there (bgr_modes, dense up to 1200 differential
 * unknowns, else the 20 lowest). */
static PyObject *model_modes(PyObject *self_, PyObject *args)
{
    pyb_model *self = (pyb_model *)self_;
    double T = 0;
    if (!PyArg_ParseTuple(args, "|d", &T) || !loaded(self)) return NULL;
    if (!(T >= 0 && isfinite(T))) {
        pyb_error(PyExc_ValueError, "t: %g is out of range (expected finite and >= 0)", T);
        return NULL;
    }
    mdl_solver_settings set = *mdl_solver(self->mm);
    mdl_trim_report rep = {0};
    bg_error err = {0};
    int st = BG_OK;
    self->used = 1;
    if (T == 0 || mdl_start_kind(self->mm) == MDL_START_STATIC) {
        self->busy = 1;
        Py_BEGIN_ALLOW_THREADS
        st = static_start(self, &set, &rep, &err);
        Py_END_ALLOW_THREADS
        self->busy = 0;
        if (st != BG_OK) return pyb_raise_solver(st, err.message, 0.0, NULL);
    }
    bgr_model *m = mdl_bgr(self->mm);
    int n = bgr_n(m);
    double *y = malloc((size_t)n * sizeof *y), *yp = calloc((size_t)n, sizeof *yp), *bk = NULL;
    if (!y || !yp) {
        free(y), free(yp);
        return PyErr_NoMemory();
    }
    memcpy(y, bgr_y0(m), (size_t)n * sizeof *y);
    dae_modes *M = NULL;
    dae_solver *s = NULL;
    char msg[BG_MESSAGE_SIZE + 64] = "";
    self->busy = 1;
    Py_BEGIN_ALLOW_THREADS
    if (T > 0) {
        dae_options o;
        dae_problem p;
        double tr;
        st = mdl_dae_options(self->mm, &o, &bk);
        if (st == BG_OK) st = mdl_dae_problem(self->mm, &p);
        o.t_stop = fmax(o.t_stop, T);
        if (st == BG_OK) s = dae_create(&p, &o, &err);
        if (st == BG_OK && !s) st = err.status;
        if (s && (st = dae_init(s, 0.0, bgr_y0(m), bgr_yp0(m))) == BG_OK)
            st = dae_consistent_init(s);
        if (st == DAE_WARNING) st = BG_OK;
        if (st == BG_OK && (st = dae_solve_to(s, T, &tr, y, yp)) >= 0) st = BG_OK;
        if (st != BG_OK)
            snprintf(msg, sizeof msg, "the run to t = %g: %s", T,
                     s ? dae_get_error(s)->message : err.message);
    }
    if (st == BG_OK) {
        dae_modes_options mo;
        dae_modes_options_default(&mo);
        mo.dense_max = 1200;
        mo.nev = 20;
        st = bgr_modes(m, T, y, yp, &mo, &M, &err);
        if (st != BG_OK && st != DAE_CONV_FAIL) snprintf(msg, sizeof msg, "%s", err.message);
        else st = BG_OK;
    }
    Py_END_ALLOW_THREADS
    self->busy = 0;
    dae_free(&s);
    free(y), free(yp), free(bk);
    if (st != BG_OK) {
        dae_modes_free(&M);
        return pyb_raise_solver(st, msg, T, NULL);
    }
    PyObject *list = pyb_modes_list(M, n);
    dae_modes_free(&M);
    return list;
}

static PyObject *model_used(PyObject *self_, void *closure)
{
    (void)closure;
    return PyBool_FromLong(((pyb_model *)self_)->used);
}

static PyMethodDef model_methods[] = {
    {"info", model_info, METH_NOARGS,
     "The model's name, file, unknowns, equations, outputs, kinds, start and settings."},
    {"parameter", model_parameter, METH_O, "The value of a model parameter by name."},
    {"run", (PyCFunction)(void (*)(void))model_run, METH_VARARGS | METH_KEYWORDS,
     "run(t_end=None, output_step=None, rtol=None, atol=None, error_estimate=0): bgsim's run."},
    {"static", model_static, METH_NOARGS, "The static equilibrium (with the file's trim)."},
    {"modes", model_modes, METH_VARARGS, "modes(t=0): the modes at time t."},
    {NULL, NULL, 0, NULL}};

static PyObject *model_busy(PyObject *self_, void *closure)
{
    (void)closure;
    return PyBool_FromLong(((pyb_model *)self_)->busy);
}

static PyGetSetDef model_getset[] = {
    {"used", model_used, NULL, "1 once a run or a static solve has changed the model", NULL},
    {"busy", model_busy, NULL, "1 while a call works on the model without the GIL", NULL},
    {NULL, NULL, NULL, NULL, NULL}};

PyTypeObject pyb_ModelType = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "bgdae._core.Model",
    .tp_basicsize = sizeof(pyb_model),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "A model file loaded (mdl_load) with replacements [(path, value), ...].",
    .tp_new = PyType_GenericNew,
    .tp_init = model_init,
    .tp_dealloc = model_dealloc,
    .tp_methods = model_methods,
    .tp_getset = model_getset,
};
