/* LQR design by the ordered Schur form of the Hamiltonian, and the state-feedback element
 * (equations in ctl_lqr.h). */
#include "ctl_lqr.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp_internal.h"

typedef int (*ctl_select_fn)(const double *wr, const double *wi);
extern void dgees_(const char *jobvs, const char *sort, ctl_select_fn select, const int *n,
                   double *a, const int *lda, int *sdim, double *wr, double *wi, double *vs,
                   const int *ldvs, double *work, const int *lwork, int *bwork, int *info);
extern void dgesv_(const int *n, const int *nrhs, double *a, const int *lda, int *ipiv, double *b,
                   const int *ldb, int *info);
extern void dpotrf_(const char *uplo, const int *n, double *a, const int *lda, int *info);
extern void dpotrs_(const char *uplo, const int *n, const int *nrhs, const double *a,
                    const int *lda, double *b, const int *ldb, int *info);

/* the open left half plane: the stable invariant subspace first */
static int stable(const double *wr, const double *wi)
{
    (void)wi;
    return *wr < 0;
}

static int finite_all(int k, const double *a)
{
    for (int i = 0; i < k; i++)
        if (!isfinite(a[i])) return 0;
    return 1;
}

int ctl_lqr(int n, int m, const double *A, const double *B, const double *Q, const double *R,
            double *K, double *P, bg_error *err)
{
    const char *w = "ctl_lqr";
    if (n < 1 || n > CTL_SF_MAX || m < 1 || m > n)
        return bg_error_raise(err, BG_ERR_ARGUMENT, w, "n = %d, m = %d: expected 1 <= m <= n <= %d",
                              n, m, CTL_SF_MAX);
    if (!A || !B || !Q || !R || !K)
        return bg_error_raise(err, BG_ERR_ARGUMENT, w, "a matrix is NULL");
    if (!finite_all(n * n, A) || !finite_all(n * m, B) || !finite_all(n * n, Q) ||
        !finite_all(m * m, R))
        return bg_error_raise(err, BG_ERR_ARGUMENT, w, "a matrix holds a value that is not finite");
    int n2 = 2 * n, st = BG_OK, info = 0;
    size_t need = (size_t)(m * m + n * m + 2 * n2 * n2 + 3 * n2 + n * n + n * n + 64 * n2);
    double *mem = calloc(need, sizeof *mem);
    int *iw = calloc((size_t)(n2 + n), sizeof *iw);
    if (!mem || !iw) {
        free(mem);
        free(iw);
        return bg_error_raise(err, BG_ERR_MEMORY, w, "out of memory");
    }
    double *Rc = mem, *RB = Rc + m * m, *H = RB + n * m, *U = H + n2 * n2, *wr = U + n2 * n2,
           *wi = wr + n2, *X = wi + n2, *Y = X + n * n, *work = Y + n * n;
    int lwork = 64 * n2 - n2; /* what is left of mem */
    (void)need;
    /* R = L L^T; RB = R^-1 B^T (m x n) */
    memcpy(Rc, R, sizeof *Rc * (size_t)(m * m));
    dpotrf_("L", &m, Rc, &m, &info);
    if (info != 0) {
        st = bg_error_raise(err, BG_ERR_ARGUMENT, w, "R is not positive definite (dpotrf %d)",
                            info);
        goto done;
    }
    for (int i = 0; i < m; i++)
        for (int j = 0; j < n; j++) RB[i + j * m] = B[j + i * n];
    dpotrs_("L", &m, &n, Rc, &m, RB, &m, &info);
    /* H = [A, -B R^-1 B^T; -Q, -A^T] */
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double g = 0;
            for (int k = 0; k < m; k++) g += B[i + k * n] * RB[k + j * m];
            H[i + j * n2] = A[i + j * n];
            H[i + (j + n) * n2] = -g;
            H[(i + n) + j * n2] = -0.5 * (Q[i + j * n] + Q[j + i * n]);
            H[(i + n) + (j + n) * n2] = -A[j + i * n];
        }
    int sdim = 0;
    dgees_("V", "S", stable, &n2, H, &n2, &sdim, wr, wi, U, &n2, work, &lwork, iw, &info);
    if (info != 0 && info != n2 + 2) {
        st = info == n2 + 1 ? bg_error_raise(err, BG_ERR_SINGULAR, w,
                                             "the Hamiltonian's eigenvalues could not be "
                                             "reordered (dgees %d)",
                                             info)
                            : bg_error_raise(err, BG_ERR_LIBRARY, w, "LAPACK dgees failed (%d)",
                                             info);
        goto done;
    }
    if (sdim != n) {
        st = bg_error_raise(err, BG_ERR_SINGULAR, w,
                            "%d of the Hamiltonian's %d eigenvalues in the left half plane, "
                            "expected %d: (A, B) not stabilisable or (Q, A) not detectable",
                            sdim, n2, n);
        goto done;
    }
    /* P U11 = U21: U11^T P^T = U21^T */
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            X[i + j * n] = U[j + i * n2];     /* U11^T */
            Y[i + j * n] = U[(j + n) + i * n2]; /* U21^T */
        }
    dgesv_(&n, &n, X, &n, iw, Y, &n, &info);
    if (info != 0) {
        st = bg_error_raise(err, BG_ERR_SINGULAR, w,
                            "U11 of the stable subspace is singular (dgesv %d): no stabilising "
                            "solution",
                            info);
        goto done;
    }
    /* Y = P^T; symmetrise */
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) X[i + j * n] = 0.5 * (Y[i + j * n] + Y[j + i * n]);
    if (P) memcpy(P, X, sizeof *P * (size_t)(n * n));
    /* K = R^-1 B^T P = RB P */
    for (int i = 0; i < m; i++)
        for (int j = 0; j < n; j++) {
            double s = 0;
            for (int k = 0; k < n; k++) s += RB[i + k * m] * X[k + j * n];
            K[i + j * m] = s;
        }
    if (!finite_all(m * n, K))
        st = bg_error_raise(err, BG_ERR_SINGULAR, w, "the gain is not finite");
done:
    free(mem);
    free(iw);
    return st;
}

/* ---- the feedback element ---- */

typedef struct sf {
    ctl_sf_spec sp;
    int x[CTL_SF_MAX], r[CTL_SF_MAX];
    int b, bd, u, rate, w; /* -1 when absent */
} sf;

static int sf_declare(bgr_element *el, bgr_model *m)
{
    static const char *const lab[3] = {"output", "integral", "rate"};
    sf *q = el->params;
    const ctl_sf_spec *s = &q->sp;
    q->u = bgr_av(el, 0);
    q->rate = s->integrate ? bgr_av(el, 1) : -1;
    q->w = s->integrate ? bgr_sv(el, 0) : -1;
    q->b = s->use_bias ? bgr_ref_var(m, s->bias) : -1;
    q->bd = s->use_bias_rate ? bgr_ref_var(m, s->bias_rate) : -1;
    for (int i = 0; i < s->n; i++) {
        q->x[i] = bgr_ref_var(m, s->x[i]);
        q->r[i] = s->use_ref[i] ? bgr_ref_var(m, s->r[i]) : -1;
        if (q->x[i] < 0 || (s->use_ref[i] && q->r[i] < 0))
            return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "bgr_compile",
                                  "state feedback %s: its %s %d refers to no unknown", el->name,
                                  q->x[i] < 0 ? "measurement" : "reference", i + 1);
    }
    if ((s->use_bias && q->b < 0) || (s->use_bias_rate && q->bd < 0))
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_ARGUMENT, "bgr_compile",
                              "state feedback %s: its bias%s refers to no unknown", el->name,
                              s->use_bias && q->b < 0 ? "" : " rate");
    int st = bgr_declare_equations(el, m, s->integrate ? 3 : 1, lab);
    if (st) return st;
    CMP_DEP(el, m, 0, q->u, 0);
    if (q->b >= 0) CMP_DEP(el, m, 0, q->b, 0);
    if (s->integrate) {
        CMP_DEP(el, m, 0, q->w, 0);
        CMP_DEP(el, m, 1, q->w, 1);
        CMP_DEP(el, m, 2, q->rate, 0);
        if (q->bd >= 0) CMP_DEP(el, m, 2, q->bd, 0);
    }
    for (int k = s->integrate ? 1 : 0; k <= (s->integrate ? 2 : 0); k++)
        for (int i = 0; i < s->n; i++) {
            CMP_DEP(el, m, k, q->x[i], 0);
            if (q->r[i] >= 0) CMP_DEP(el, m, k, q->r[i], 0);
        }
    return BG_OK;
}

static double sf_law(const sf *q, const double *y)
{
    double s = 0;
    for (int i = 0; i < q->sp.n; i++) s += q->sp.gain[i] * (y[q->x[i]] - (q->r[i] >= 0 ? y[q->r[i]] : 0));
    return s;
}

static int sf_residual(const bgr_element *el, double t, const double *y, const double *yp,
                       double *F)
{
    (void)t;
    const sf *q = el->params;
    double ke = sf_law(q, y), b = q->b >= 0 ? y[q->b] : 0;
    if (!q->sp.integrate) {
        F[0] = y[q->u] - (b - ke);
        return 0;
    }
    F[0] = y[q->u] - (b + y[q->w]);
    F[1] = yp[q->w] + ke;
    F[2] = y[q->rate] - ((q->bd >= 0 ? y[q->bd] : 0) - ke);
    return 0;
}

static int sf_jacobian(const bgr_element *el, double t, const double *y, const double *yp,
                       double *v)
{
    (void)t, (void)y, (void)yp;
    const sf *q = el->params;
    const ctl_sf_spec *s = &q->sp;
    int n = 0;
    v[n++] = 1.0;
    if (q->b >= 0) v[n++] = -1.0;
    if (s->integrate) {
        v[n++] = -1.0;
        v[n++] = 1.0;
        v[n++] = 1.0;
        if (q->bd >= 0) v[n++] = -1.0;
    }
    for (int k = s->integrate ? 1 : 0; k <= (s->integrate ? 2 : 0); k++)
        for (int i = 0; i < s->n; i++) {
            v[n++] = s->gain[i];
            if (q->r[i] >= 0) v[n++] = -s->gain[i];
        }
    return 0;
}

static void sf_describe(const bgr_element *el, const bgr_model *m, int k, char *buf, size_t n)
{
    (void)m;
    const sf *q = el->params;
    static const char *const what[3] = {"u = b + w (integral) or b - sum K_i (x_i - r_i)",
                                        "w' = -sum K_i (x_i - r_i)",
                                        "rate = b' - sum K_i (x_i - r_i)"};
    snprintf(buf, n, "%s (%d gains)", what[k >= 0 && k < 3 ? k : 0], q->sp.n);
}

const bgr_element_class ctl_class_state_feedback = {.type = "state feedback",
                                                    .declare = sf_declare,
                                                    .residual = sf_residual,
                                                    .jacobian = sf_jacobian,
                                                    .describe = sf_describe,
                                                    .destroy = free};

int ctl_state_feedback(bgr_model *m, bgr_comp c, const char *name, const ctl_sf_spec *spec)
{
    const char *w = "ctl_state_feedback";
    if (!spec) return bgr_refuse(m, c, name, w, "no specification (spec is NULL)");
    if (spec->n < 1 || spec->n > CTL_SF_MAX)
        return bgr_refuse(m, c, name, w, "n = %d, expected 1 .. %d", spec->n, CTL_SF_MAX);
    for (int i = 0; i < spec->n; i++)
        if (!isfinite(spec->gain[i]))
            return bgr_refuse(m, c, name, w, "gain[%d] = %g, expected a finite number", i,
                              spec->gain[i]);
    if (spec->use_bias_rate && !spec->integrate)
        return bgr_refuse(m, c, name, w, "a bias rate only in the integral form");
    sf *q = calloc(1, sizeof *q);
    if (!q)
        return bg_error_raise(bgr_model_error_mut(m), BG_ERR_MEMORY, w, "out of memory");
    q->sp = *spec;
    static const char *const sn[1] = {"integral"}, *const an[2] = {"out", "rate"};
    return bgr_element_add(m, c, name, &ctl_class_state_feedback, q, 0, NULL,
                           spec->integrate ? 1 : 0, sn, spec->integrate ? 2 : 1, an);
}
