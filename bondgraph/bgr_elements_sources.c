/* The sources Se and Sf: constant, of time, or a signal (bgr_elements.h; shared parts in
 * bgr_elements_impl.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bgr_check.h"
#include "bgr_elements_impl.h"

/* ------------------------------------------------------------------ Se and Sf ---- */

static const char *lab_src(int k, int d, int np)
{
    (void)np;
    (void)k, (void)d;
    return "source";
}

/* Sources: the effort (Se) or the outgoing flow (Sf) equals a value, a function of t or a
 * signal. */
static int src_declare(bgr_element *el, bgr_model *m, int flow)
{
    par *q = el->params;
    int d = q->d, st = bgr_el_bind(el, m);
    if (st || (st = bgr_el_declare_eqs(el, m, d, lab_src, d))) return st;
    for (int i = 0; i < d; i++) {
        DEP(i, flow ? q->f[i] : q->e[i], 0);
        if (q->kind == LAW_SIGNAL) DEP(i, q->refvar, 0);
    }
    /* a constant source's value is the size of what it imposes (nothing for a zero component,
     * a function of time or a signal: no scale among the parameters) */
    for (int i = 0; q->kind == LAW_CONST && q->vec && i < d; i++)
        if (q->vec[i] != 0 && isfinite(q->vec[i]) &&
            (st = bgr_declare_nominal(el, m, flow ? q->f[i] : q->e[i], fabs(q->vec[i]))))
            return st;
    return BG_OK;
}

static double src_value(const par *q, int i, double t, const double *y)
{
    switch (q->kind) {
    case LAW_CONST:
        return q->vec ? q->vec[i] : 0.0;
    case LAW_TIME:
        return q->tfn(q->user, t);
    case LAW_SIGNAL:
        return y[q->refvar];
    default:
        return 0.0;
    }
}

static int Se_declare(bgr_element *el, bgr_model *m)
{
    return src_declare(el, m, 0);
}
static int Sf_declare(bgr_element *el, bgr_model *m)
{
    return src_declare(el, m, 1);
}

static int Se_residual(const bgr_element *el, double t, const double *y, const double *yp,
                       double *F)
{
    (void)yp;
    const par *q = el->params;
    for (int i = 0; i < q->d; i++)
        F[i] = y[q->e[i]] - src_value(q, i, t, y);
    return 0;
}

static int Sf_residual(const bgr_element *el, double t, const double *y, const double *yp,
                       double *F)
{
    (void)yp;
    const par *q = el->params;
    for (int i = 0; i < q->d; i++)
        F[i] = -q->s[0] * y[q->f[i]] - src_value(q, i, t, y);
    return 0;
}

static int Se_jacobian(const bgr_element *el, double t, const double *y, const double *yp,
                       double *v)
{
    (void)t, (void)y, (void)yp;
    const par *q = el->params;
    int n = 0;
    for (int i = 0; i < q->d; i++) {
        v[n++] = 1.0;
        if (q->kind == LAW_SIGNAL) v[n++] = -1.0;
    }
    return 0;
}

static int Sf_jacobian(const bgr_element *el, double t, const double *y, const double *yp,
                       double *v)
{
    (void)t, (void)y, (void)yp;
    const par *q = el->params;
    int n = 0;
    for (int i = 0; i < q->d; i++) {
        v[n++] = -q->s[0];
        if (q->kind == LAW_SIGNAL) v[n++] = -1.0;
    }
    return 0;
}

static void src_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n,
                         int flow)
{
    const par *q = el->params;
    char a[160], b[160] = "";
    bgr_el_vname(m, flow ? q->f[k] : q->e[k], a, sizeof a);
    const char *sg = flow && q->s[0] > 0 ? "-" : "";
    if (q->kind == LAW_CONST)
        snprintf(b, sizeof b, "%g", q->vec ? q->vec[k] : 0.0);
    else if (q->kind == LAW_TIME)
        snprintf(b, sizeof b, "u(t)");
    else
        bgr_el_vname(m, q->refvar, b, sizeof b);
    snprintf(buf, n, "%s%s = %s", sg, a, b);
}

static void Se_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n)
{
    src_describe(el, m, k, buf, n, 0);
}

static void Sf_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n)
{
    src_describe(el, m, k, buf, n, 1);
}

const bgr_element_class bgr_class_Se = {.type = "Se",
                                        .declare = Se_declare,
                                        .residual = Se_residual,
                                        .jacobian = Se_jacobian,
                                        .describe = Se_describe,
                                        .destroy = bgr_el_par_free};
const bgr_element_class bgr_class_Sf = {.type = "Sf",
                                        .declare = Sf_declare,
                                        .residual = Sf_residual,
                                        .jacobian = Sf_jacobian,
                                        .describe = Sf_describe,
                                        .destroy = bgr_el_par_free};

static par *src_const(int d, const double *value)
{
    par *q = bgr_el_par_new(d, LAW_CONST, 0);
    if (q && value) {
        if (!(q->vec = malloc((size_t)d * sizeof *q->vec))) {
            bgr_el_par_free(q);
            return NULL;
        }
        memcpy(q->vec, value, (size_t)d * sizeof *value);
    }
    return q;
}

static par *src_time(bgr_time_fn fn, void *user)
{
    par *q = bgr_el_par_new(1, LAW_TIME, 0);
    if (q) {
        q->tfn = fn;
        q->user = user;
    }
    return q;
}

int bgr_Se(bgr_model *m, bgr_comp c, const char *name, int d, const double *value)
{
    const char *w = "bgr_Se";
    if (bgr_el_check_d(m, c, name, w, d, D_ANY) ||
        bgr_check_values(m, c, name, w, "value", value, d, BGR_FINITE))
        return BG_ERR_ARGUMENT;
    return bgr_el_add(m, c, name, &bgr_class_Se, src_const(d, value), 1, 0, NULL, 0, NULL);
}

int bgr_Se_fn(bgr_model *m, bgr_comp c, const char *name, bgr_time_fn fn, void *user)
{
    if (bgr_el_check_given(m, c, name, "bgr_Se_fn", fn != NULL, "the function"))
        return BG_ERR_ARGUMENT;
    return bgr_el_add(m, c, name, &bgr_class_Se, src_time(fn, user), 1, 0, NULL, 0, NULL);
}

int bgr_Se_signal(bgr_model *m, bgr_comp c, const char *name, bgr_ref signal)
{
    return bgr_el_add(m, c, name, &bgr_class_Se, bgr_el_par_signal(signal), 1, 0, NULL, 0, NULL);
}

int bgr_Sf(bgr_model *m, bgr_comp c, const char *name, int d, const double *value)
{
    const char *w = "bgr_Sf";
    if (bgr_el_check_d(m, c, name, w, d, D_ANY) ||
        bgr_check_values(m, c, name, w, "value", value, d, BGR_FINITE))
        return BG_ERR_ARGUMENT;
    return bgr_el_add(m, c, name, &bgr_class_Sf, src_const(d, value), 1, 0, NULL, 0, NULL);
}

int bgr_Sf_fn(bgr_model *m, bgr_comp c, const char *name, bgr_time_fn fn, void *user)
{
    if (bgr_el_check_given(m, c, name, "bgr_Sf_fn", fn != NULL, "the function"))
        return BG_ERR_ARGUMENT;
    return bgr_el_add(m, c, name, &bgr_class_Sf, src_time(fn, user), 1, 0, NULL, 0, NULL);
}

int bgr_Sf_signal(bgr_model *m, bgr_comp c, const char *name, bgr_ref signal)
{
    return bgr_el_add(m, c, name, &bgr_class_Sf, bgr_el_par_signal(signal), 1, 0, NULL, 0, NULL);
}
