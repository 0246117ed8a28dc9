/* The storage and resistive elements I, C and R (bgr_elements.h; shared parts in
 * bgr_elements_impl.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bgr_check.h"
#include "bgr_elements_impl.h"

/* ------------------------------------------------------------------------- I ---- */

static const char *lab_I(int k, int d, int np)
{
    (void)np;
    return k < d ? "momentum" : "velocity";
}

static int I_declare(bgr_element *el, bgr_model *m)
{
    par *q = el->params;
    int d = q->d, st = bgr_el_bind(el, m);
    if (st || (st = bgr_el_declare_eqs(el, m, 2 * d, lab_I, d))) return st;
    for (int i = 0; i < d; i++) {
        DEP(i, q->x[i], 1);
        DEP(i, q->e[i], 0);
    }
    for (int i = 0; i < d; i++) {
        if (q->kind == LAW_MATRIX)
            for (int j = 0; j < d; j++)
                DEP(d + i, q->f[j], 0);
        else
            DEP(d + i, q->f[i], 0);
        DEP(d + i, q->x[i], 0);
    }
    return BG_OK;
}

static int I_residual(const bgr_element *el, double t, const double *y, const double *yp, double *F)
{
    (void)t;
    const par *q = el->params;
    int d = q->d, s = q->s[0];
    for (int i = 0; i < d; i++)
        F[i] = yp[q->x[i]] - y[q->e[i]];
    for (int i = 0; i < d; i++) {
        double mf;
        if (q->kind == LAW_MATRIX) {
            mf = 0;
            for (int j = 0; j < d; j++)
                mf += q->vec[i + j * d] * s * y[q->f[j]];
            F[d + i] = mf - y[q->x[i]];
        } else if (q->kind == LAW_FN) {
            double dphi;
            F[d + i] = s * y[q->f[i]] - q->fn(q->user, y[q->x[i]], &dphi);
        } else {
            F[d + i] = q->k * s * y[q->f[i]] - y[q->x[i]];
        }
    }
    return 0;
}

static int I_jacobian(const bgr_element *el, double t, const double *y, const double *yp, double *v)
{
    (void)t, (void)yp;
    const par *q = el->params;
    int d = q->d, s = q->s[0], n = 0;
    for (int i = 0; i < d; i++) {
        v[n++] = 1.0;
        v[n++] = -1.0;
    }
    for (int i = 0; i < d; i++) {
        if (q->kind == LAW_MATRIX) {
            for (int j = 0; j < d; j++)
                v[n++] = q->vec[i + j * d] * s;
            v[n++] = -1.0;
        } else if (q->kind == LAW_FN) {
            double dphi;
            q->fn(q->user, y[q->x[i]], &dphi);
            v[n++] = s;
            v[n++] = -dphi;
        } else {
            v[n++] = q->k * s;
            v[n++] = -1.0;
        }
    }
    return 0;
}

static void I_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n)
{
    const par *q = el->params;
    int d = q->d, i = k % d;
    char a[160], b[160];
    bgr_el_vname(m, q->x[i], a, sizeof a);
    if (k < d) {
        bgr_el_vname(m, q->e[i], b, sizeof b);
        snprintf(buf, n, "%s' = %s", a, b);
    } else {
        bgr_el_vname(m, q->f[i], b, sizeof b);
        const char *sg = q->s[0] > 0 ? "" : "-";
        if (q->kind == LAW_MATRIX)
            snprintf(buf, n, "(M %sf)[%d] = %s   (f: %s, ...)", sg, i, a, b);
        else if (q->kind == LAW_FN)
            snprintf(buf, n, "%s%s = phi(%s)", sg, b, a);
        else
            snprintf(buf, n, "%g * %s%s = %s", q->k, sg, b, a);
    }
}

const bgr_element_class bgr_class_I = {.type = "I",
                                       .declare = I_declare,
                                       .residual = I_residual,
                                       .jacobian = I_jacobian,
                                       .describe = I_describe,
                                       .destroy = bgr_el_par_free};

static const char *const *state_names(int d, const char *base, char (*buf)[16], const char **ptr)
{
    for (int i = 0; i < d && i < 16; i++) {
        if (d == 1)
            snprintf(buf[i], 16, "%s", base);
        else
            snprintf(buf[i], 16, "%s%d", base, i);
        ptr[i] = buf[i];
    }
    return ptr;
}

static int add_state_elem(bgr_model *m, bgr_comp c, const char *name, const bgr_element_class *cls,
                          par *q, const char *sname)
{
    if (q && q->d > 16) {
        int d = q->d;
        bgr_el_par_free(q);
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "bgr_element_add",
                              "element %s/%s: dimension %d above 16", bgr_component_path(m, c),
                              name ? name : "(null)", d);
    }
    char buf[16][16];
    const char *ptr[16];
    int d = q ? q->d : 1;
    return bgr_el_add(m, c, name, cls, q, 1, d, state_names(d, sname, buf, ptr), 0, NULL);
}

int bgr_I(bgr_model *m, bgr_comp c, const char *name, int d, double mass)
{
    const char *w = "bgr_I";
    if (bgr_el_check_d(m, c, name, w, d, 16) ||
        bgr_check_value(m, c, name, w, "mass", mass, BGR_POSITIVE))
        return BG_ERR_ARGUMENT;
    return add_state_elem(m, c, name, &bgr_class_I, bgr_el_par_new(d, LAW_LINEAR, mass), "p");
}

int bgr_I_matrix(bgr_model *m, bgr_comp c, const char *name, int d, const double *M)
{
    const char *w = "bgr_I_matrix";
    if (bgr_el_check_d(m, c, name, w, d, 16) ||
        bgr_el_check_given(m, c, name, w, M != NULL, "the mass matrix") ||
        bgr_check_spd(m, c, name, w, "M", M, d))
        return BG_ERR_ARGUMENT;
    par *q = bgr_el_par_new(d, LAW_MATRIX, 0);
    if (q && !(q->vec = malloc((size_t)d * d * sizeof *q->vec))) {
        bgr_el_par_free(q);
        q = NULL;
    }
    if (q) memcpy(q->vec, M, (size_t)d * d * sizeof *M);
    return add_state_elem(m, c, name, &bgr_class_I, q, "p");
}

int bgr_I_fn(bgr_model *m, bgr_comp c, const char *name, bgr_fn phi, void *user)
{
    if (bgr_el_check_given(m, c, name, "bgr_I_fn", phi != NULL, "the function"))
        return BG_ERR_ARGUMENT;
    par *q = bgr_el_par_new(1, LAW_FN, 0);
    if (q) {
        q->fn = phi;
        q->user = user;
    }
    return add_state_elem(m, c, name, &bgr_class_I, q, "p");
}

/* ------------------------------------------------------------------------- C ---- */

static const char *lab_C(int k, int d, int np)
{
    (void)np;
    return k < d ? "displacement" : "effort";
}

static int C_declare(bgr_element *el, bgr_model *m)
{
    par *q = el->params;
    int d = q->d, st = bgr_el_bind(el, m);
    if (st || (st = bgr_el_declare_eqs(el, m, 2 * d, lab_C, d))) return st;
    for (int i = 0; i < d; i++) {
        DEP(i, q->x[i], 1);
        DEP(i, q->f[i], 0);
    }
    for (int i = 0; i < d; i++) {
        DEP(d + i, q->e[i], 0);
        DEP(d + i, q->x[i], 0);
    }
    return BG_OK;
}

static int C_residual(const bgr_element *el, double t, const double *y, const double *yp, double *F)
{
    (void)t;
    const par *q = el->params;
    int d = q->d, s = q->s[0];
    for (int i = 0; i < d; i++)
        F[i] = yp[q->x[i]] - s * y[q->f[i]];
    for (int i = 0; i < d; i++) {
        double dpsi;
        F[d + i] = y[q->e[i]] -
                   (q->kind == LAW_FN ? q->fn(q->user, y[q->x[i]], &dpsi) : q->k * y[q->x[i]]);
    }
    return 0;
}

static int C_jacobian(const bgr_element *el, double t, const double *y, const double *yp, double *v)
{
    (void)t, (void)yp;
    const par *q = el->params;
    int d = q->d, s = q->s[0], n = 0;
    for (int i = 0; i < d; i++) {
        v[n++] = 1.0;
        v[n++] = -s;
    }
    for (int i = 0; i < d; i++) {
        double dpsi = q->k;
        if (q->kind == LAW_FN) q->fn(q->user, y[q->x[i]], &dpsi);
        v[n++] = 1.0;
        v[n++] = -dpsi;
    }
    return 0;
}

static void C_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n)
{
    const par *q = el->params;
    int d = q->d, i = k % d;
    char a[160], b[160];
    bgr_el_vname(m, q->x[i], a, sizeof a);
    bgr_el_vname(m, k < d ? q->f[i] : q->e[i], b, sizeof b);
    if (k < d)
        snprintf(buf, n, "%s' = %s%s", a, q->s[0] > 0 ? "" : "-", b);
    else if (q->kind == LAW_FN)
        snprintf(buf, n, "%s = psi(%s)", b, a);
    else
        snprintf(buf, n, "%s = %g * %s", b, q->k, a);
}

const bgr_element_class bgr_class_C = {.type = "C",
                                       .declare = C_declare,
                                       .residual = C_residual,
                                       .jacobian = C_jacobian,
                                       .describe = C_describe,
                                       .destroy = bgr_el_par_free};

int bgr_C(bgr_model *m, bgr_comp c, const char *name, int d, double stiffness)
{
    const char *w = "bgr_C";
    if (bgr_el_check_d(m, c, name, w, d, 16) ||
        bgr_check_value(m, c, name, w, "stiffness", stiffness, BGR_NONNEGATIVE))
        return BG_ERR_ARGUMENT;
    return add_state_elem(m, c, name, &bgr_class_C, bgr_el_par_new(d, LAW_LINEAR, stiffness), "q");
}

int bgr_C_fn(bgr_model *m, bgr_comp c, const char *name, bgr_fn psi, void *user)
{
    if (bgr_el_check_given(m, c, name, "bgr_C_fn", psi != NULL, "the function"))
        return BG_ERR_ARGUMENT;
    par *q = bgr_el_par_new(1, LAW_FN, 0);
    if (q) {
        q->fn = psi;
        q->user = user;
    }
    return add_state_elem(m, c, name, &bgr_class_C, q, "q");
}

/* ------------------------------------------------------------------------- R ---- */

static const char *lab_R(int k, int d, int np)
{
    (void)np;
    (void)k, (void)d;
    return "resistance";
}

static int R_declare(bgr_element *el, bgr_model *m)
{
    par *q = el->params;
    int d = q->d, st = bgr_el_bind(el, m);
    if (st || (st = bgr_el_declare_eqs(el, m, d, lab_R, d))) return st;
    for (int i = 0; i < d; i++) {
        DEP(i, q->e[i], 0);
        DEP(i, q->f[i], 0);
    }
    return BG_OK;
}

static int R_residual(const bgr_element *el, double t, const double *y, const double *yp, double *F)
{
    (void)t, (void)yp;
    const par *q = el->params;
    int s = q->s[0];
    for (int i = 0; i < q->d; i++) {
        double fin = s * y[q->f[i]], dphi;
        F[i] = y[q->e[i]] - (q->kind == LAW_FN ? q->fn(q->user, fin, &dphi) : q->k * fin);
    }
    return 0;
}

static int R_jacobian(const bgr_element *el, double t, const double *y, const double *yp, double *v)
{
    (void)t, (void)yp;
    const par *q = el->params;
    int s = q->s[0], n = 0;
    for (int i = 0; i < q->d; i++) {
        double dphi = q->k;
        if (q->kind == LAW_FN) q->fn(q->user, s * y[q->f[i]], &dphi);
        v[n++] = 1.0;
        v[n++] = -dphi * s;
    }
    return 0;
}

static void R_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n)
{
    const par *q = el->params;
    char a[160], b[160];
    bgr_el_vname(m, q->e[k], a, sizeof a);
    bgr_el_vname(m, q->f[k], b, sizeof b);
    const char *sg = q->s[0] > 0 ? "" : "-";
    if (q->kind == LAW_FN)
        snprintf(buf, n, "%s = phi(%s%s)", a, sg, b);
    else
        snprintf(buf, n, "%s = %g * %s%s", a, q->k, sg, b);
}

const bgr_element_class bgr_class_R = {.type = "R",
                                       .declare = R_declare,
                                       .residual = R_residual,
                                       .jacobian = R_jacobian,
                                       .describe = R_describe,
                                       .destroy = bgr_el_par_free};

int bgr_R(bgr_model *m, bgr_comp c, const char *name, int d, double resistance)
{
    const char *w = "bgr_R";
    if (bgr_el_check_d(m, c, name, w, d, D_ANY) ||
        bgr_check_value(m, c, name, w, "resistance", resistance, BGR_NONNEGATIVE))
        return BG_ERR_ARGUMENT;
    return bgr_el_add(m, c, name, &bgr_class_R, bgr_el_par_new(d, LAW_LINEAR, resistance), 1, 0,
                      NULL, 0, NULL);
}

int bgr_R_fn(bgr_model *m, bgr_comp c, const char *name, bgr_fn phi, void *user)
{
    if (bgr_el_check_given(m, c, name, "bgr_R_fn", phi != NULL, "the function"))
        return BG_ERR_ARGUMENT;
    par *q = bgr_el_par_new(1, LAW_FN, 0);
    if (q) {
        q->fn = phi;
        q->user = user;
    }
    return bgr_el_add(m, c, name, &bgr_class_R, q, 1, 0, NULL, 0, NULL);
}
