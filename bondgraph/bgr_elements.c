/* The standard bond-graph elements (equations in bgr_elements.h). Each class declares its
 * equations and partial derivatives once; residual and Jacobian then only read the unknowns
 * through the variable ids fixed at compilation. */
#include "bgr_elements.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bgr_check.h"

typedef enum law {
    LAW_LINEAR, /* scalar coefficient k */
    LAW_MATRIX, /* d x d matrix */
    LAW_FN,     /* scalar function with derivative */
    LAW_CONST,  /* constant vector */
    LAW_TIME,   /* scalar function of t */
    LAW_SIGNAL  /* another unknown */
} law;

typedef struct par {
    int d;
    law kind;
    double k;
    double *vec; /* LAW_MATRIX: d*d; LAW_CONST: d */
    bgr_fn fn;
    bgr_time_fn tfn;
    void *user;
    bgr_ref ref;
    int refvar; /* resolved at declaration */
    /* variable ids, filled at declaration: ports' e and f, states, own unknowns */
    int *e, *f; /* nports*d each, port-major */
    int *x;     /* states or own unknowns */
    int *s;     /* orientation per port */
    int nports;
} par;

static void par_free(void *p)
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

static par *par_new(int d, law kind, double k)
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
static int bind(bgr_element *el, bgr_model *m)
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
static int declare_eqs(bgr_element *el, bgr_model *m, int neq,
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

#define DEP(k, v, w)                                                                               \
    do {                                                                                           \
        int st_ = bgr_declare_dep(el, m, (k), (v), (w));                                           \
        if (st_ != BG_OK) return st_;                                                              \
    } while (0)

static int add(bgr_model *m, bgr_comp c, const char *name, const bgr_element_class *cls, par *q,
               int nports, int nstates, const char *const *snames, int nalg,
               const char *const *anames)
{
    if (!q)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, "bgr_element_add",
                              "out of memory");
    int *dims = calloc((size_t)nports + 1, sizeof *dims);
    if (!dims) {
        par_free(q);
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
static int check_d(bgr_model *m, bgr_comp c, const char *name, const char *where, int d, int max)
{
    if (d >= 1 && d <= max) return BG_OK;
    if (max < 1000)
        return bgr_refuse(m, c, name, where, "dimension d = %d, expected 1 .. %d", d, max);
    return bgr_refuse(m, c, name, where, "dimension d = %d, expected >= 1", d);
}

/* No limit on the dimension beyond the memory (I and C: 16, the names of their states). */
#define D_ANY 1000000

/* BG_ERR_ARGUMENT with a message if something the element needs is not given (a NULL pointer). */
static int check_given(bgr_model *m, bgr_comp c, const char *name, const char *where, int given,
                       const char *what)
{
    if (given) return BG_OK;
    return bgr_refuse(m, c, name, where, "%s is NULL", what);
}

static void vname2(const bgr_model *m, int v, char *buf, size_t n)
{
    const char *s = bgr_var_name(m, v);
    snprintf(buf, n, "%s", s ? s : "?");
}

/* ------------------------------------------------------------------------- I ---- */

static const char *lab_I(int k, int d, int np)
{
    (void)np;
    return k < d ? "momentum" : "velocity";
}

static int I_declare(bgr_element *el, bgr_model *m)
{
    par *q = el->params;
    int d = q->d, st = bind(el, m);
    if (st || (st = declare_eqs(el, m, 2 * d, lab_I, d))) return st;
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
    vname2(m, q->x[i], a, sizeof a);
    if (k < d) {
        vname2(m, q->e[i], b, sizeof b);
        snprintf(buf, n, "%s' = %s", a, b);
    } else {
        vname2(m, q->f[i], b, sizeof b);
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
                                       .destroy = par_free};

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
        par_free(q);
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "bgr_element_add",
                              "element %s/%s: dimension %d above 16", bgr_component_path(m, c),
                              name ? name : "(null)", d);
    }
    char buf[16][16];
    const char *ptr[16];
    int d = q ? q->d : 1;
    return add(m, c, name, cls, q, 1, d, state_names(d, sname, buf, ptr), 0, NULL);
}

int bgr_I(bgr_model *m, bgr_comp c, const char *name, int d, double mass)
{
    const char *w = "bgr_I";
    if (check_d(m, c, name, w, d, 16) || bgr_check_value(m, c, name, w, "mass", mass, BGR_POSITIVE))
        return BG_ERR_ARGUMENT;
    return add_state_elem(m, c, name, &bgr_class_I, par_new(d, LAW_LINEAR, mass), "p");
}

int bgr_I_matrix(bgr_model *m, bgr_comp c, const char *name, int d, const double *M)
{
    const char *w = "bgr_I_matrix";
    if (check_d(m, c, name, w, d, 16) || check_given(m, c, name, w, M != NULL, "the mass matrix") ||
        bgr_check_spd(m, c, name, w, "M", M, d))
        return BG_ERR_ARGUMENT;
    par *q = par_new(d, LAW_MATRIX, 0);
    if (q && !(q->vec = malloc((size_t)d * d * sizeof *q->vec))) {
        par_free(q);
        q = NULL;
    }
    if (q) memcpy(q->vec, M, (size_t)d * d * sizeof *M);
    return add_state_elem(m, c, name, &bgr_class_I, q, "p");
}

int bgr_I_fn(bgr_model *m, bgr_comp c, const char *name, bgr_fn phi, void *user)
{
    if (check_given(m, c, name, "bgr_I_fn", phi != NULL, "the function")) return BG_ERR_ARGUMENT;
    par *q = par_new(1, LAW_FN, 0);
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
    int d = q->d, st = bind(el, m);
    if (st || (st = declare_eqs(el, m, 2 * d, lab_C, d))) return st;
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
    vname2(m, q->x[i], a, sizeof a);
    vname2(m, k < d ? q->f[i] : q->e[i], b, sizeof b);
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
                                       .destroy = par_free};

int bgr_C(bgr_model *m, bgr_comp c, const char *name, int d, double stiffness)
{
    const char *w = "bgr_C";
    if (check_d(m, c, name, w, d, 16) ||
        bgr_check_value(m, c, name, w, "stiffness", stiffness, BGR_NONNEGATIVE))
        return BG_ERR_ARGUMENT;
    return add_state_elem(m, c, name, &bgr_class_C, par_new(d, LAW_LINEAR, stiffness), "q");
}

int bgr_C_fn(bgr_model *m, bgr_comp c, const char *name, bgr_fn psi, void *user)
{
    if (check_given(m, c, name, "bgr_C_fn", psi != NULL, "the function")) return BG_ERR_ARGUMENT;
    par *q = par_new(1, LAW_FN, 0);
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
    int d = q->d, st = bind(el, m);
    if (st || (st = declare_eqs(el, m, d, lab_R, d))) return st;
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
    vname2(m, q->e[k], a, sizeof a);
    vname2(m, q->f[k], b, sizeof b);
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
                                       .destroy = par_free};

int bgr_R(bgr_model *m, bgr_comp c, const char *name, int d, double resistance)
{
    const char *w = "bgr_R";
    if (check_d(m, c, name, w, d, D_ANY) ||
        bgr_check_value(m, c, name, w, "resistance", resistance, BGR_NONNEGATIVE))
        return BG_ERR_ARGUMENT;
    return add(m, c, name, &bgr_class_R, par_new(d, LAW_LINEAR, resistance), 1, 0, NULL, 0, NULL);
}

int bgr_R_fn(bgr_model *m, bgr_comp c, const char *name, bgr_fn phi, void *user)
{
    if (check_given(m, c, name, "bgr_R_fn", phi != NULL, "the function")) return BG_ERR_ARGUMENT;
    par *q = par_new(1, LAW_FN, 0);
    if (q) {
        q->fn = phi;
        q->user = user;
    }
    return add(m, c, name, &bgr_class_R, q, 1, 0, NULL, 0, NULL);
}

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
    int d = q->d, st = bind(el, m);
    if (st || (st = declare_eqs(el, m, d, lab_src, d))) return st;
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
    vname2(m, flow ? q->f[k] : q->e[k], a, sizeof a);
    const char *sg = flow && q->s[0] > 0 ? "-" : "";
    if (q->kind == LAW_CONST)
        snprintf(b, sizeof b, "%g", q->vec ? q->vec[k] : 0.0);
    else if (q->kind == LAW_TIME)
        snprintf(b, sizeof b, "u(t)");
    else
        vname2(m, q->refvar, b, sizeof b);
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
                                        .destroy = par_free};
const bgr_element_class bgr_class_Sf = {.type = "Sf",
                                        .declare = Sf_declare,
                                        .residual = Sf_residual,
                                        .jacobian = Sf_jacobian,
                                        .describe = Sf_describe,
                                        .destroy = par_free};

static par *src_const(int d, const double *value)
{
    par *q = par_new(d, LAW_CONST, 0);
    if (q && value) {
        if (!(q->vec = malloc((size_t)d * sizeof *q->vec))) {
            par_free(q);
            return NULL;
        }
        memcpy(q->vec, value, (size_t)d * sizeof *value);
    }
    return q;
}

static par *src_time(bgr_time_fn fn, void *user)
{
    par *q = par_new(1, LAW_TIME, 0);
    if (q) {
        q->tfn = fn;
        q->user = user;
    }
    return q;
}

static par *src_signal(bgr_ref r)
{
    par *q = par_new(1, LAW_SIGNAL, 0);
    if (q) q->ref = r;
    return q;
}

int bgr_Se(bgr_model *m, bgr_comp c, const char *name, int d, const double *value)
{
    const char *w = "bgr_Se";
    if (check_d(m, c, name, w, d, D_ANY) ||
        bgr_check_values(m, c, name, w, "value", value, d, BGR_FINITE))
        return BG_ERR_ARGUMENT;
    return add(m, c, name, &bgr_class_Se, src_const(d, value), 1, 0, NULL, 0, NULL);
}

int bgr_Se_fn(bgr_model *m, bgr_comp c, const char *name, bgr_time_fn fn, void *user)
{
    if (check_given(m, c, name, "bgr_Se_fn", fn != NULL, "the function")) return BG_ERR_ARGUMENT;
    return add(m, c, name, &bgr_class_Se, src_time(fn, user), 1, 0, NULL, 0, NULL);
}

int bgr_Se_signal(bgr_model *m, bgr_comp c, const char *name, bgr_ref signal)
{
    return add(m, c, name, &bgr_class_Se, src_signal(signal), 1, 0, NULL, 0, NULL);
}

int bgr_Sf(bgr_model *m, bgr_comp c, const char *name, int d, const double *value)
{
    const char *w = "bgr_Sf";
    if (check_d(m, c, name, w, d, D_ANY) ||
        bgr_check_values(m, c, name, w, "value", value, d, BGR_FINITE))
        return BG_ERR_ARGUMENT;
    return add(m, c, name, &bgr_class_Sf, src_const(d, value), 1, 0, NULL, 0, NULL);
}

int bgr_Sf_fn(bgr_model *m, bgr_comp c, const char *name, bgr_time_fn fn, void *user)
{
    if (check_given(m, c, name, "bgr_Sf_fn", fn != NULL, "the function")) return BG_ERR_ARGUMENT;
    return add(m, c, name, &bgr_class_Sf, src_time(fn, user), 1, 0, NULL, 0, NULL);
}

int bgr_Sf_signal(bgr_model *m, bgr_comp c, const char *name, bgr_ref signal)
{
    return add(m, c, name, &bgr_class_Sf, src_signal(signal), 1, 0, NULL, 0, NULL);
}

/* ----------------------------------------------------------------- TF and GY ---- */

static const char *lab_TF(int k, int d, int np)
{
    (void)np;
    return k < d ? "effort" : "flow";
}

static int TF_declare(bgr_element *el, bgr_model *m)
{
    par *q = el->params;
    int d = q->d, st = bind(el, m);
    if (st || (st = declare_eqs(el, m, 2 * d, lab_TF, d))) return st;
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
        vname2(m, q->refvar, mo, sizeof mo);
    else
        snprintf(mo, sizeof mo, "%g", q->k);
    if (k < d) {
        vname2(m, q->e[i], a, sizeof a);
        vname2(m, q->e[d + i], b, sizeof b);
        snprintf(buf, n, "%s = %s * %s", a, mo, b);
    } else {
        vname2(m, q->f[d + i], a, sizeof a);
        vname2(m, q->f[i], b, sizeof b);
        snprintf(buf, n, "%s%s = %s * %s%s", q->s[1] > 0 ? "-" : "", a, mo, q->s[0] > 0 ? "" : "-",
                 b);
    }
}

const bgr_element_class bgr_class_TF = {.type = "TF",
                                        .declare = TF_declare,
                                        .residual = TF_residual,
                                        .jacobian = TF_jacobian,
                                        .describe = TF_describe,
                                        .destroy = par_free};

int bgr_TF(bgr_model *m, bgr_comp c, const char *name, int d, double modulus)
{
    const char *w = "bgr_TF";
    if (check_d(m, c, name, w, d, D_ANY) ||
        bgr_check_value(m, c, name, w, "modulus", modulus, BGR_NONZERO))
        return BG_ERR_ARGUMENT;
    return add(m, c, name, &bgr_class_TF, par_new(d, LAW_LINEAR, modulus), 2, 0, NULL, 0, NULL);
}

int bgr_TF_signal(bgr_model *m, bgr_comp c, const char *name, bgr_ref modulus)
{
    return add(m, c, name, &bgr_class_TF, src_signal(modulus), 2, 0, NULL, 0, NULL);
}

static int GY_declare(bgr_element *el, bgr_model *m)
{
    par *q = el->params;
    int d = q->d, st = bind(el, m);
    if (st || (st = declare_eqs(el, m, 2 * d, lab_TF, d))) return st;
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
        vname2(m, q->e[i], a, sizeof a);
        vname2(m, q->f[d + i], b, sizeof b);
        snprintf(buf, n, "%s = %g * %s%s", a, q->k, q->s[1] > 0 ? "-" : "", b);
    } else {
        vname2(m, q->e[d + i], a, sizeof a);
        vname2(m, q->f[i], b, sizeof b);
        snprintf(buf, n, "%s = %g * %s%s", a, q->k, q->s[0] > 0 ? "" : "-", b);
    }
}

const bgr_element_class bgr_class_GY = {.type = "GY",
                                        .declare = GY_declare,
                                        .residual = GY_residual,
                                        .jacobian = GY_jacobian,
                                        .describe = GY_describe,
                                        .destroy = par_free};

int bgr_GY(bgr_model *m, bgr_comp c, const char *name, int d, double modulus)
{
    const char *w = "bgr_GY";
    if (check_d(m, c, name, w, d, D_ANY) ||
        bgr_check_value(m, c, name, w, "modulus", modulus, BGR_NONZERO))
        return BG_ERR_ARGUMENT;
    return add(m, c, name, &bgr_class_GY, par_new(d, LAW_LINEAR, modulus), 2, 0, NULL, 0, NULL);
}

/* ------------------------------------------------------------------ junctions ---- */

/* zero = 1: 0-junction (common effort, flows sum); zero = 0: 1-junction. */
static int J_declare(bgr_element *el, bgr_model *m, int zero)
{
    par *q = el->params;
    int d = q->d, np = el->nports, st = bind(el, m);
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
        vname2(m, same[port * d + i], a, sizeof a);
        vname2(m, same[i], b, sizeof b);
        snprintf(buf, n, "%s = %s", a, b);
    } else {
        int i = k - (np - 1) * d;
        size_t used = 0;
        buf[0] = '\0';
        for (int p = 0; p < np && used + 1 < n; p++) {
            vname2(m, sum[p * d + i], a, sizeof a);
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
                                          .destroy = par_free};
const bgr_element_class bgr_class_one = {.type = "1",
                                         .declare = J1_declare,
                                         .residual = J1_residual,
                                         .jacobian = J_jacobian,
                                         .describe = J1_describe,
                                         .destroy = par_free};

static int junction(bgr_model *m, bgr_comp c, const char *name, int nports, int d,
                    const bgr_element_class *cls)
{
    const char *w = cls == &bgr_class_zero ? "bgr_zero" : "bgr_one";
    if (check_d(m, c, name, w, d, D_ANY)) return BG_ERR_ARGUMENT;
    if (nports < 2)
        return bgr_refuse(m, c, name, w, "junction with nports = %d, expected at least 2 ports",
                          nports);
    return add(m, c, name, cls, par_new(d, LAW_LINEAR, 0), nports, 0, NULL, 0, NULL);
}

int bgr_zero(bgr_model *m, bgr_comp c, const char *name, int nports, int d)
{
    return junction(m, c, name, nports, d, &bgr_class_zero);
}

int bgr_one(bgr_model *m, bgr_comp c, const char *name, int nports, int d)
{
    return junction(m, c, name, nports, d, &bgr_class_one);
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
    int st = bind(el, m);
    if (st || (st = declare_eqs(el, m, 1, lab_gain, 1))) return st;
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
    vname2(m, q->x[0], a, sizeof a);
    vname2(m, q->refvar, b, sizeof b);
    snprintf(buf, n, "%s = %g * %s", a, q->k, b);
}

const bgr_element_class bgr_class_gain = {.type = "gain",
                                          .declare = gain_declare,
                                          .residual = gain_residual,
                                          .jacobian = gain_jacobian,
                                          .describe = gain_describe,
                                          .destroy = par_free};

int bgr_gain(bgr_model *m, bgr_comp c, const char *name, bgr_ref x, double gain)
{
    if (bgr_check_value(m, c, name, "bgr_gain", "gain", gain, BGR_FINITE)) return BG_ERR_ARGUMENT;
    par *q = par_new(1, LAW_SIGNAL, gain);
    if (q) q->ref = x;
    static const char *const out[1] = {"out"};
    return add(m, c, name, &bgr_class_gain, q, 0, 0, NULL, 1, out);
}
