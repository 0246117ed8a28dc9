/* The power-conserving elements: the transformer TF, the gyrator GY, the 0- and 1-junctions
 * (bgr_elements.h; shared parts in bgr_elements_impl.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bgr_check.h"
#include "bgr_elements_impl.h"

/* ----------------------------------------------------------------- TF and GY ---- */

static const char *lab_TF(int k, int d, int np)
{
    (void)np;
    return k < d ? "effort" : "flow";
}

static int TF_declare(bgr_element *el, bgr_model *m)
{
    par *q = el->params;
    int d = q->d, st = bgr_el_bind(el, m);
    if (st || (st = bgr_el_declare_eqs(el, m, 2 * d, lab_TF, d))) return st;
    for (int i = 0; i < d; i++) {
        DEP(i, q->e[i], 0);
        DEP(i, q->e[d + i], 0);
        if (q->kind == LAW_SIGNAL) DEP(i, q->refvar, 0);
    }
    for (int i = 0; i < d; i++) {
        DEP(d + i, q->f[d + i], 0);
        DEP(d + i, q->f[i], 0);
        if (q->kind == LAW_SIGNAL) DEP(d + i, q->refvar, 0);
    }
    return BG_OK;
}

static int TF_residual(const bgr_element *el, double t, const double *y, const double *yp,
                       double *F)
{
    (void)t, (void)yp;
    const par *q = el->params;
    int d = q->d, s0 = q->s[0], s1 = q->s[1];
    double mod = q->kind == LAW_SIGNAL ? y[q->refvar] : q->k;
    for (int i = 0; i < d; i++) {
        F[i] = y[q->e[i]] - mod * y[q->e[d + i]];
        F[d + i] = -s1 * y[q->f[d + i]] - mod * s0 * y[q->f[i]];
    }
    return 0;
}

static int TF_jacobian(const bgr_element *el, double t, const double *y, const double *yp,
                       double *v)
{
    (void)t, (void)yp;
    const par *q = el->params;
    int d = q->d, s0 = q->s[0], s1 = q->s[1], n = 0, sig = q->kind == LAW_SIGNAL;
    double mod = sig ? y[q->refvar] : q->k;
    for (int i = 0; i < d; i++) {
        v[n++] = 1.0;
        v[n++] = -mod;
        if (sig) v[n++] = -y[q->e[d + i]];
    }
    for (int i = 0; i < d; i++) {
        v[n++] = -s1;
        v[n++] = -mod * s0;
        if (sig) v[n++] = -s0 * y[q->f[i]];
    }
    return 0;
}

static void TF_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n)
{
    const par *q = el->params;
    int d = q->d, i = k % d;
    char a[160], b[160], mo[160];
    if (q->kind == LAW_SIGNAL)
        bgr_el_vname(m, q->refvar, mo, sizeof mo);
    else
        snprintf(mo, sizeof mo, "%g", q->k);
    if (k < d) {
        bgr_el_vname(m, q->e[i], a, sizeof a);
        bgr_el_vname(m, q->e[d + i], b, sizeof b);
        snprintf(buf, n, "%s = %s * %s", a, mo, b);
    } else {
        bgr_el_vname(m, q->f[d + i], a, sizeof a);
        bgr_el_vname(m, q->f[i], b, sizeof b);
        snprintf(buf, n, "%s%s = %s * %s%s", q->s[1] > 0 ? "-" : "", a, mo, q->s[0] > 0 ? "" : "-",
                 b);
    }
}

const bgr_element_class bgr_class_TF = {.type = "TF",
                                        .declare = TF_declare,
                                        .residual = TF_residual,
                                        .jacobian = TF_jacobian,
                                        .describe = TF_describe,
                                        .destroy = bgr_el_par_free};

int bgr_TF(bgr_model *m, bgr_comp c, const char *name, int d, double modulus)
{
    const char *w = "bgr_TF";
    if (bgr_el_check_d(m, c, name, w, d, D_ANY) ||
        bgr_check_value(m, c, name, w, "modulus", modulus, BGR_NONZERO))
        return BG_ERR_ARGUMENT;
    return bgr_el_add(m, c, name, &bgr_class_TF, bgr_el_par_new(d, LAW_LINEAR, modulus), 2, 0, NULL,
                      0, NULL);
}

int bgr_TF_signal(bgr_model *m, bgr_comp c, const char *name, bgr_ref modulus)
{
    return bgr_el_add(m, c, name, &bgr_class_TF, bgr_el_par_signal(modulus), 2, 0, NULL, 0, NULL);
}

static int GY_declare(bgr_element *el, bgr_model *m)
{
    par *q = el->params;
    int d = q->d, st = bgr_el_bind(el, m);
    if (st || (st = bgr_el_declare_eqs(el, m, 2 * d, lab_TF, d))) return st;
    for (int i = 0; i < d; i++) {
        DEP(i, q->e[i], 0);
        DEP(i, q->f[d + i], 0);
    }
    for (int i = 0; i < d; i++) {
        DEP(d + i, q->e[d + i], 0);
        DEP(d + i, q->f[i], 0);
    }
    return BG_OK;
}

static int GY_residual(const bgr_element *el, double t, const double *y, const double *yp,
                       double *F)
{
    (void)t, (void)yp;
    const par *q = el->params;
    int d = q->d, s0 = q->s[0], s1 = q->s[1];
    for (int i = 0; i < d; i++) {
        F[i] = y[q->e[i]] + q->k * s1 * y[q->f[d + i]];     /* e0 = r f1_out */
        F[d + i] = y[q->e[d + i]] - q->k * s0 * y[q->f[i]]; /* e1 = r f0_in */
    }
    return 0;
}

static int GY_jacobian(const bgr_element *el, double t, const double *y, const double *yp,
                       double *v)
{
    (void)t, (void)y, (void)yp;
    const par *q = el->params;
    int d = q->d, n = 0;
    for (int i = 0; i < d; i++) {
        v[n++] = 1.0;
        v[n++] = q->k * q->s[1];
    }
    for (int i = 0; i < d; i++) {
        v[n++] = 1.0;
        v[n++] = -q->k * q->s[0];
    }
    return 0;
}

static void GY_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n)
{
    const par *q = el->params;
    int d = q->d, i = k % d;
    char a[160], b[160];
    if (k < d) {
        bgr_el_vname(m, q->e[i], a, sizeof a);
        bgr_el_vname(m, q->f[d + i], b, sizeof b);
        snprintf(buf, n, "%s = %g * %s%s", a, q->k, q->s[1] > 0 ? "-" : "", b);
    } else {
        bgr_el_vname(m, q->e[d + i], a, sizeof a);
        bgr_el_vname(m, q->f[i], b, sizeof b);
        snprintf(buf, n, "%s = %g * %s%s", a, q->k, q->s[0] > 0 ? "" : "-", b);
    }
}

const bgr_element_class bgr_class_GY = {.type = "GY",
                                        .declare = GY_declare,
                                        .residual = GY_residual,
                                        .jacobian = GY_jacobian,
                                        .describe = GY_describe,
                                        .destroy = bgr_el_par_free};

int bgr_GY(bgr_model *m, bgr_comp c, const char *name, int d, double modulus)
{
    const char *w = "bgr_GY";
    if (bgr_el_check_d(m, c, name, w, d, D_ANY) ||
        bgr_check_value(m, c, name, w, "modulus", modulus, BGR_NONZERO))
        return BG_ERR_ARGUMENT;
    return bgr_el_add(m, c, name, &bgr_class_GY, bgr_el_par_new(d, LAW_LINEAR, modulus), 2, 0, NULL,
                      0, NULL);
}

/* ------------------------------------------------------------------ junctions ---- */

/* zero = 1: 0-junction (common effort, flows sum); zero = 0: 1-junction. */
static int J_declare(bgr_element *el, bgr_model *m, int zero)
{
    par *q = el->params;
    int d = q->d, np = el->nports, st = bgr_el_bind(el, m);
    if (st) return st;
    /* rows: "equal<k>[_i]" (port k's effort or flow equals port 0's), "sum[<i>]" */
    char(*buf)[32] = calloc((size_t)np * d + 1, sizeof *buf);
    const char **lab = calloc((size_t)np * d + 1, sizeof *lab);
    if (buf && lab) {
        for (int r = 0; r < np * d; r++) {
            int k = r / d + 1, i = r % d;
            if (r < (np - 1) * d)
                snprintf(buf[r], sizeof buf[r], d == 1 ? "equal%d" : "equal%d_%d", k, i);
            else
                snprintf(buf[r], sizeof buf[r], d == 1 ? "sum" : "sum%d", i);
            lab[r] = buf[r];
        }
        st = bgr_declare_equations(el, m, np * d, lab);
    } else {
        st = bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, "bgr_compile", "out of memory");
    }
    free(buf);
    free(lab);
    if (st) return st;
    const int *same = zero ? q->e : q->f, *sum = zero ? q->f : q->e;
    for (int k = 1; k < np; k++)
        for (int i = 0; i < d; i++) {
            DEP((k - 1) * d + i, same[k * d + i], 0);
            DEP((k - 1) * d + i, same[i], 0);
        }
    for (int i = 0; i < d; i++)
        for (int k = 0; k < np; k++)
            DEP((np - 1) * d + i, sum[k * d + i], 0);
    return BG_OK;
}

static int J0_declare(bgr_element *el, bgr_model *m)
{
    return J_declare(el, m, 1);
}
static int J1_declare(bgr_element *el, bgr_model *m)
{
    return J_declare(el, m, 0);
}

static void J_residual(const bgr_element *el, const double *y, double *F, int zero)
{
    const par *q = el->params;
    int d = q->d, np = el->nports;
    const int *same = zero ? q->e : q->f, *sum = zero ? q->f : q->e;
    for (int k = 1; k < np; k++)
        for (int i = 0; i < d; i++)
            F[(k - 1) * d + i] = y[same[k * d + i]] - y[same[i]];
    for (int i = 0; i < d; i++) {
        double acc = 0;
        for (int k = 0; k < np; k++)
            acc += q->s[k] * y[sum[k * d + i]];
        F[(np - 1) * d + i] = acc;
    }
}

static int J0_residual(const bgr_element *el, double t, const double *y, const double *yp,
                       double *F)
{
    (void)t, (void)yp;
    J_residual(el, y, F, 1);
    return 0;
}

static int J1_residual(const bgr_element *el, double t, const double *y, const double *yp,
                       double *F)
{
    (void)t, (void)yp;
    J_residual(el, y, F, 0);
    return 0;
}

static int J_jacobian(const bgr_element *el, double t, const double *y, const double *yp, double *v)
{
    (void)t, (void)y, (void)yp;
    const par *q = el->params;
    int d = q->d, np = el->nports, n = 0;
    for (int k = 1; k < np; k++)
        for (int i = 0; i < d; i++) {
            v[n++] = 1.0;
            v[n++] = -1.0;
        }
    for (int i = 0; i < d; i++)
        for (int k = 0; k < np; k++)
            v[n++] = q->s[k];
    return 0;
}

static void J_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n,
                       int zero)
{
    const par *q = el->params;
    int d = q->d, np = el->nports;
    const int *same = zero ? q->e : q->f, *sum = zero ? q->f : q->e;
    char a[160], b[160];
    if (k < (np - 1) * d) {
        int port = k / d + 1, i = k % d;
        bgr_el_vname(m, same[port * d + i], a, sizeof a);
        bgr_el_vname(m, same[i], b, sizeof b);
        snprintf(buf, n, "%s = %s", a, b);
    } else {
        int i = k - (np - 1) * d;
        size_t used = 0;
        buf[0] = '\0';
        for (int p = 0; p < np && used + 1 < n; p++) {
            bgr_el_vname(m, sum[p * d + i], a, sizeof a);
            int w =
                snprintf(buf + used, n - used, "%s%s", q->s[p] > 0 ? (p ? " + " : "") : " - ", a);
            if (w < 0) break;
            used += (size_t)w;
        }
        if (used + 1 < n) snprintf(buf + used, n - used, " = 0");
    }
}

static void J0_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n)
{
    J_describe(el, m, k, buf, n, 1);
}

static void J1_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n)
{
    J_describe(el, m, k, buf, n, 0);
}

const bgr_element_class bgr_class_zero = {.type = "0",
                                          .declare = J0_declare,
                                          .residual = J0_residual,
                                          .jacobian = J_jacobian,
                                          .describe = J0_describe,
                                          .destroy = bgr_el_par_free};
const bgr_element_class bgr_class_one = {.type = "1",
                                         .declare = J1_declare,
                                         .residual = J1_residual,
                                         .jacobian = J_jacobian,
                                         .describe = J1_describe,
                                         .destroy = bgr_el_par_free};

static int junction(bgr_model *m, bgr_comp c, const char *name, int nports, int d,
                    const bgr_element_class *cls)
{
    const char *w = cls == &bgr_class_zero ? "bgr_zero" : "bgr_one";
    if (bgr_el_check_d(m, c, name, w, d, D_ANY)) return BG_ERR_ARGUMENT;
    if (nports < 2)
        return bgr_refuse(m, c, name, w, "junction with nports = %d, expected at least 2 ports",
                          nports);
    return bgr_el_add(m, c, name, cls, bgr_el_par_new(d, LAW_LINEAR, 0), nports, 0, NULL, 0, NULL);
}

int bgr_zero(bgr_model *m, bgr_comp c, const char *name, int nports, int d)
{
    return junction(m, c, name, nports, d, &bgr_class_zero);
}

int bgr_one(bgr_model *m, bgr_comp c, const char *name, int nports, int d)
{
    return junction(m, c, name, nports, d, &bgr_class_one);
}
