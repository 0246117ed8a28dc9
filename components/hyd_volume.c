/* Hydraulic volume (equations in hyd_volume.h). */
#include "hyd_volume.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cmp_internal.h"

typedef struct volume {
    double V, beta;
    double p_nom; /* stated nominal pressure (hyd_volume_set_nominal), 0: none */
    int np, p;
    int *e, *f, *s; /* per port */
} volume;

static void volume_free(void *p)
{
    volume *q = p;
    if (!q) return;
    free(q->e);
    free(q->f);
    free(q->s);
    free(q);
}

static int volume_declare(bgr_element *el, bgr_model *m)
{
    volume *q = el->params;
    int np = q->np;
    q->e = malloc((size_t)np * sizeof *q->e);
    q->f = malloc((size_t)np * sizeof *q->f);
    q->s = malloc((size_t)np * sizeof *q->s);
    char **lab = calloc((size_t)np + 1, sizeof *lab);
    char *text = malloc((size_t)np * 16 + 1);
    int st = BG_OK;
    if (!q->e || !q->f || !q->s || !lab || !text)
        st = bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, "bgr_compile", "out of memory");
    if (st == BG_OK) {
        lab[0] = "pressure";
        for (int k = 0; k < np; k++) {
            q->e[k] = bgr_ev(el, m, k, 0);
            q->f[k] = bgr_fv(el, m, k, 0);
            q->s[k] = el->sign[k];
            lab[k + 1] = text + 16 * k;
            snprintf(lab[k + 1], 16, "port%d", k);
        }
        q->p = bgr_sv(el, 0);
        st = bgr_declare_equations(el, m, np + 1, (const char *const *)lab);
    }
    free(lab);
    free(text);
    if (st) return st;
    CMP_DEP(el, m, 0, q->p, 1);
    for (int k = 0; k < np; k++)
        CMP_DEP(el, m, 0, q->f[k], 0);
    for (int k = 0; k < np; k++) {
        CMP_DEP(el, m, k + 1, q->e[k], 0);
        CMP_DEP(el, m, k + 1, q->p, 0);
    }
    /* V and beta give no pressure of their own (the pressure is set by the rest of the circuit):
     * only a stated system pressure scales the volume's pressure and its ports' efforts */
    CMP_NOM(el, m, q->p, q->p_nom);
    for (int k = 0; k < np; k++)
        CMP_NOM(el, m, q->e[k], q->p_nom);
    return BG_OK;
}

static int volume_residual(const bgr_element *el, double t, const double *y, const double *yp,
                           double *F)
{
    (void)t;
    const volume *q = el->params;
    double net = 0;
    for (int k = 0; k < q->np; k++)
        net += q->s[k] * y[q->f[k]];
    F[0] = yp[q->p] - q->beta / q->V * net;
    for (int k = 0; k < q->np; k++)
        F[k + 1] = y[q->e[k]] - y[q->p];
    return 0;
}

static int volume_jacobian(const bgr_element *el, double t, const double *y, const double *yp,
                           double *v)
{
    (void)t, (void)y, (void)yp;
    const volume *q = el->params;
    double c = q->beta / q->V;
    int n = 0;
    v[n++] = 1.0;
    for (int k = 0; k < q->np; k++)
        v[n++] = -c * q->s[k];
    for (int k = 0; k < q->np; k++) {
        v[n++] = 1.0;
        v[n++] = -1.0;
    }
    return 0;
}

static void volume_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n)
{
    const volume *q = el->params;
    const char *p = bgr_var_name(m, q->p);
    if (k == 0)
        snprintf(buf, n, "%s' = %g * (sum of the %d inflows)", p ? p : "p", q->beta / q->V, q->np);
    else {
        const char *e = bgr_var_name(m, q->e[k - 1]);
        snprintf(buf, n, "%s = %s", e ? e : "e", p ? p : "p");
    }
}

const bgr_element_class hyd_class_volume = {.type = "volume",
                                            .declare = volume_declare,
                                            .residual = volume_residual,
                                            .jacobian = volume_jacobian,
                                            .describe = volume_describe,
                                            .destroy = volume_free};

int hyd_volume(bgr_model *m, bgr_comp c, const char *name, int nports, double V, double beta)
{
    const char *w = "hyd_volume";
    if (nports < 1 || nports > 1000)
        return bgr_refuse(m, c, name, w, "nports = %d, expected 1 .. 1000", nports);
    if (bgr_check_value(m, c, name, w, "V", V, BGR_POSITIVE) ||
        bgr_check_value(m, c, name, w, "beta", beta, BGR_POSITIVE))
        return BG_ERR_ARGUMENT;
    if (!isfinite(beta / V))
        return bgr_refuse(m, c, name, w,
                          "beta / V = %g (V = %g, beta = %g), expected a finite number (the "
                          "pressure's rate per unit inflow)",
                          beta / V, V, beta);
    volume *q = calloc(1, sizeof *q);
    int *dims = malloc((size_t)nports * sizeof *dims);
    if (!q || !dims) {
        free(q);
        free(dims);
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, "hyd_volume", "out of memory");
    }
    q->V = V;
    q->beta = beta;
    q->np = nports;
    for (int k = 0; k < nports; k++)
        dims[k] = 1;
    static const char *const sn[1] = {"p"};
    int id = bgr_element_add(m, c, name, &hyd_class_volume, q, nports, dims, 1, sn, 0, NULL);
    free(dims);
    return id;
}

int hyd_volume_set_nominal(bgr_model *m, int id, double pressure)
{
    void *q = NULL;
    int st = cmp_check_scales(m, id, &hyd_class_volume, "a hydraulic volume",
                              "hyd_volume_set_nominal", &pressure, 1, &q);
    if (st != BG_OK) return st;
    ((volume *)q)->p_nom = pressure;
    return BG_OK;
}
