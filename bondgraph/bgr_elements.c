/* The standard bond-graph elements (equations in bgr_elements.h): their shared parts
 * (bgr_elements_impl.h: parameters, binding, equations, addition, checks) and the signal gain;
 * the other elements are in bgr_elements_storage.c, bgr_elements_sources.c and
 * bgr_elements_junctions.c. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bgr_check.h"
#include "bgr_elements_impl.h"

void bgr_el_par_free(void *p)
{
    par *q = p;
    if (!q) return;
    free(q->vec);
    free(q->e);
    free(q->f);
    free(q->x);
    free(q->s);
    free(q);
}

par *bgr_el_par_new(int d, law kind, double k)
{
    par *q = calloc(1, sizeof *q);
    if (!q) return NULL;
    q->d = d;
    q->kind = kind;
    q->k = k;
    q->refvar = -1;
    return q;
}

/* Resolves the element's variable ids into its parameters. */
int bgr_el_bind(bgr_element *el, bgr_model *m)
{
    par *q = el->params;
    int d = q->d, np = el->nports, nx = el->nstates + el->nalg;
    q->nports = np;
    q->e = malloc(((size_t)np * d + 1) * sizeof *q->e);
    q->f = malloc(((size_t)np * d + 1) * sizeof *q->f);
    q->x = malloc(((size_t)nx + 1) * sizeof *q->x);
    q->s = malloc(((size_t)np + 1) * sizeof *q->s);
    if (!q->e || !q->f || !q->x || !q->s)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, "bgr_compile",
                              "out of memory");
    for (int k = 0; k < np; k++) {
        q->s[k] = el->sign[k];
        for (int i = 0; i < d; i++) {
            q->e[k * d + i] = bgr_ev(el, m, k, i);
            q->f[k * d + i] = bgr_fv(el, m, k, i);
        }
    }
    for (int i = 0; i < el->nstates; i++)
        q->x[i] = bgr_sv(el, i);
    for (int i = 0; i < el->nalg; i++)
        q->x[el->nstates + i] = bgr_av(el, i);
    if (q->kind == LAW_SIGNAL) {
        q->refvar = bgr_ref_var(m, q->ref);
        if (q->refvar < 0)
            return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "bgr_compile",
                                  "element %s/%s (%s): its signal refers to no unknown",
                                  bgr_component_path(m, el->comp), el->name, el->cls->type);
    }
    return BG_OK;
}

/* Declares neq equations labelled prefix0, prefix1, ... in groups of d (label(k) chooses). */
int bgr_el_declare_eqs(bgr_element *el, bgr_model *m, int neq,
                       const char *(*label)(int k, int d, int np), int d)
{
    char **lab = calloc((size_t)neq + 1, sizeof *lab);
    int st = lab ? BG_OK : BG_ERR_MEMORY;
    for (int k = 0; st == BG_OK && k < neq; k++) {
        char buf[48];
        if (d == 1)
            snprintf(buf, sizeof buf, "%s", label(k, d, el->nports));
        else
            snprintf(buf, sizeof buf, "%s%d", label(k, d, el->nports), k % d);
        if (!(lab[k] = malloc(strlen(buf) + 1)))
            st = BG_ERR_MEMORY;
        else
            strcpy(lab[k], buf);
    }
    if (st == BG_OK) st = bgr_declare_equations(el, m, neq, (const char *const *)lab);
    for (int k = 0; lab && k < neq; k++)
        free(lab[k]);
    free(lab);
    if (st == BG_ERR_MEMORY)
        return bg_error_raise(bgr_model_error_mut(m), st, "bgr_compile", "out of memory");
    return st;
}

int bgr_el_add(bgr_model *m, bgr_comp c, const char *name, const bgr_element_class *cls, par *q,
               int nports, int nstates, const char *const *snames, int nalg,
               const char *const *anames)
{
    if (!q)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, "bgr_element_add",
                              "out of memory");
    int *dims = calloc((size_t)nports + 1, sizeof *dims);
    if (!dims) {
        bgr_el_par_free(q);
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, "bgr_element_add",
                              "out of memory");
    }
    for (int k = 0; k < nports; k++)
        dims[k] = q->d;
    int id = bgr_element_add(m, c, name, cls, q, nports, dims, nstates, snames, nalg, anames);
    free(dims);
    return id;
}

/* BG_ERR_ARGUMENT with a message naming the element unless 1 <= d <= max. */
int bgr_el_check_d(bgr_model *m, bgr_comp c, const char *name, const char *where, int d, int max)
{
    if (d >= 1 && d <= max) return BG_OK;
    if (max < 1000)
        return bgr_refuse(m, c, name, where, "dimension d = %d, expected 1 .. %d", d, max);
    return bgr_refuse(m, c, name, where, "dimension d = %d, expected >= 1", d);
}

/* BG_ERR_ARGUMENT with a message if something the element needs is not given (a NULL pointer). */
int bgr_el_check_given(bgr_model *m, bgr_comp c, const char *name, const char *where, int given,
                       const char *what)
{
    if (given) return BG_OK;
    return bgr_refuse(m, c, name, where, "%s is NULL", what);
}

void bgr_el_vname(const bgr_model *m, int v, char *buf, size_t n)
{
    const char *s = bgr_var_name(m, v);
    snprintf(buf, n, "%s", s ? s : "?");
}

par *bgr_el_par_signal(bgr_ref r)
{
    par *q = bgr_el_par_new(1, LAW_SIGNAL, 0);
    if (q) q->ref = r;
    return q;
}

/* ---------------------------------------------------------------------- gain ---- */

static const char *lab_gain(int k, int d, int np)
{
    (void)np;
    (void)k, (void)d;
    return "signal";
}

static int gain_declare(bgr_element *el, bgr_model *m)
{
    par *q = el->params;
    int st = bgr_el_bind(el, m);
    if (st || (st = bgr_el_declare_eqs(el, m, 1, lab_gain, 1))) return st;
    DEP(0, q->x[0], 0);
    DEP(0, q->refvar, 0);
    return BG_OK;
}

static int gain_residual(const bgr_element *el, double t, const double *y, const double *yp,
                         double *F)
{
    (void)t, (void)yp;
    const par *q = el->params;
    F[0] = y[q->x[0]] - q->k * y[q->refvar];
    return 0;
}

static int gain_jacobian(const bgr_element *el, double t, const double *y, const double *yp,
                         double *v)
{
    (void)t, (void)y, (void)yp;
    const par *q = el->params;
    v[0] = 1.0;
    v[1] = -q->k;
    return 0;
}

static void gain_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n)
{
    (void)k;
    const par *q = el->params;
    char a[160], b[160];
    bgr_el_vname(m, q->x[0], a, sizeof a);
    bgr_el_vname(m, q->refvar, b, sizeof b);
    snprintf(buf, n, "%s = %g * %s", a, q->k, b);
}

const bgr_element_class bgr_class_gain = {.type = "gain",
                                          .declare = gain_declare,
                                          .residual = gain_residual,
                                          .jacobian = gain_jacobian,
                                          .describe = gain_describe,
                                          .destroy = bgr_el_par_free};

int bgr_gain(bgr_model *m, bgr_comp c, const char *name, bgr_ref x, double gain)
{
    if (bgr_check_value(m, c, name, "bgr_gain", "gain", gain, BGR_FINITE)) return BG_ERR_ARGUMENT;
    par *q = bgr_el_par_new(1, LAW_SIGNAL, gain);
    if (q) q->ref = x;
    static const char *const out[1] = {"out"};
    return bgr_el_add(m, c, name, &bgr_class_gain, q, 0, 0, NULL, 1, out);
}
