/* Jacobians of a dae_problem at a point, analytic or by coloured differences (bg_jaceval.h). */
#include "bg_jaceval.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A dense n x n pattern. */
static sp_csc *dense_pattern(int n)
{
    sp_csc *A = sp_csc_alloc(n, n, n * n);
    if (!A) return NULL;
    for (int j = 0; j < n; j++) {
        A->colptr[j + 1] = (j + 1) * n;
        for (int i = 0; i < n; i++)
            A->rowind[j * n + i] = i;
    }
    A->nnz = n * n;
    memset(A->val, 0, (size_t)n * (size_t)n * sizeof *A->val);
    return A;
}

int bg_jaceval_init(bg_jaceval *J, const dae_problem *p, bg_error *err)
{
    memset(J, 0, sizeof *J);
    if (!p || p->n < 1 || !p->res)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "dae_linearize",
                              "the problem needs n >= 1 and a residual");
    J->p = p;
    J->n = p->n;
    int n = p->n;
    if (n > 4000 && (!p->jac_y_pattern || !p->jac_yp_pattern)) {
        return bg_error_raise(err, BG_ERR_ARGUMENT, "dae_linearize",
                              "a problem of %d unknowns needs its Jacobian patterns (dense ones "
                              "would take %g MB)",
                              n, 16.0 * n * (double)n / 1e6);
    }
    J->Jy = p->jac_y_pattern ? sp_csc_copy(p->jac_y_pattern) : dense_pattern(n);
    J->Jyp = p->jac_yp_pattern ? sp_csc_copy(p->jac_yp_pattern) : dense_pattern(n);
    J->F0 = malloc((size_t)n * sizeof *J->F0);
    J->F1 = malloc((size_t)n * sizeof *J->F1);
    J->ycopy = malloc((size_t)n * sizeof *J->ycopy);
    if (!J->Jy || !J->Jyp || !J->F0 || !J->F1 || !J->ycopy) goto nomem;
    bg_error perr = {0};
    if (J->Jy->nrow != n || J->Jy->ncol != n || J->Jyp->nrow != n || J->Jyp->ncol != n ||
        sp_csc_check(J->Jy, &perr) != BG_OK || sp_csc_check(J->Jyp, &perr) != BG_OK) {
        bg_jaceval_free(J);
        return bg_error_raise(err, BG_ERR_PATTERN, "dae_linearize",
                              "the Jacobian patterns must be well-formed %d x %d matrices%s%s", n,
                              n, perr.message[0] ? ": " : "", perr.message);
    }
    if (!p->jac) {
        J->fdy = sp_fdjac_create(J->Jy);
        J->fdyp = sp_fdjac_create(J->Jyp);
        if (!J->fdy || !J->fdyp) goto nomem;
    }
    return BG_OK;
nomem:
    bg_jaceval_free(J);
    return bg_error_raise(err, BG_ERR_MEMORY, "dae_linearize", "out of memory");
}

void bg_jaceval_free(bg_jaceval *J)
{
    if (!J) return;
    sp_csc_free(&J->Jy);
    sp_csc_free(&J->Jyp);
    sp_fdjac_free(&J->fdy);
    sp_fdjac_free(&J->fdyp);
    free(J->F0);
    free(J->F1);
    free(J->ycopy);
    memset(J, 0, sizeof *J);
}

int bg_jaceval_res(bg_jaceval *J, double t, const double *y, const double *yp, double *F)
{
    memset(F, 0, (size_t)J->n * sizeof *F);
    J->res_evals++;
    return J->p->res(J->p->user, t, y, yp, F);
}

static int fd_wrt_y(void *user, const double *x, double *f)
{
    bg_jaceval *J = user;
    int st = bg_jaceval_res(J, J->t, x, J->yp, f);
    if (st) J->status = st;
    return st;
}

static int fd_wrt_yp(void *user, const double *x, double *f)
{
    bg_jaceval *J = user;
    int st = bg_jaceval_res(J, J->t, J->y, x, f);
    if (st) J->status = st;
    return st;
}

int bg_jaceval_eval(bg_jaceval *J, double t, const double *y, const double *yp, const double *F)
{
    J->jac_evals++;
    if (J->p->jac) {
        sp_csc_zero(J->Jy);
        sp_csc_zero(J->Jyp);
        return J->p->jac(J->p->user, t, y, yp, J->Jy, J->Jyp);
    }
    int st;
    if (F)
        memcpy(J->F0, F, (size_t)J->n * sizeof *F);
    else if ((st = bg_jaceval_res(J, t, y, yp, J->F0)) != 0)
        return st;
    J->t = t;
    J->y = y;
    J->yp = yp;
    J->status = 0;
    st = sp_fdjac_eval(J->fdy, fd_wrt_y, J, y, J->F0, J->p->nominal, J->Jy);
    if (st == 0) st = sp_fdjac_eval(J->fdyp, fd_wrt_yp, J, yp, J->F0, NULL, J->Jyp);
    return st;
}

const char *bg_var_label(const dae_problem *p, int i, char *buf, size_t size)
{
    if (p && p->names && i >= 0 && i < p->n && p->names[i]) return p->names[i];
    snprintf(buf, size, "y[%d]", i);
    return buf;
}

const char *bg_eq_label(const dae_problem *p, int i, char *buf, size_t size)
{
    if (p && p->eq_names && i >= 0 && i < p->n && p->eq_names[i]) return p->eq_names[i];
    /* without a name: the unknown whose rate the row holds (a differential equation's), from
     * the pattern of dF/dy' */
    const sp_csc *P = p ? p->jac_yp_pattern : NULL;
    int col = -1;
    for (int j = 0; P && i >= 0 && j < P->ncol && col < 0; j++)
        for (int k = P->colptr[j]; k < P->colptr[j + 1]; k++)
            if (P->rowind[k] == i) {
                col = j;
                break;
            }
    if (col >= 0) {
        char nb[64];
        snprintf(buf, size, "equation %d (with the rate of %s)", i,
                 bg_var_label(p, col, nb, sizeof nb));
    } else {
        snprintf(buf, size, "equation %d", i);
    }
    return buf;
}

int bg_check_nominal(const dae_problem *p, const char *where, bg_error *err)
{
    for (int i = 0; p->nominal && i < p->n; i++)
        if (!(p->nominal[i] > 0 && isfinite(p->nominal[i]))) {
            char nb[32];
            return bg_error_raise(err, BG_ERR_ARGUMENT, where,
                                  "the nominal magnitude of %s is %g: it must be finite and > 0",
                                  bg_var_label(p, i, nb, sizeof nb), p->nominal[i]);
        }
    return BG_OK;
}

int bg_check_state(const dae_problem *p, const double *v, const char *what, int status,
                   const char *where, bg_error *err)
{
    for (int i = 0; i < p->n; i++)
        if (!isfinite(v[i])) {
            char nb[32];
            return bg_error_raise(err, status, where, "the %s of %s is %g: it must be finite",
                                  what, bg_var_label(p, i, nb, sizeof nb), v[i]);
        }
    return BG_OK;
}

int bg_jaceval_steadiness(bg_jaceval *J, double t, const double *y, const double *yp,
                          const sp_csc *S, double *ratio, int *row)
{
    const int n = J->n;
    const double *nom = J->p->nominal;
    *ratio = 0;
    *row = -1;
    double rmax = 0;
    for (int i = 0; i < n; i++)
        rmax = fmax(rmax, fabs(yp[i]) / (fabs(y[i]) + (nom ? nom[i] : 1.0)));
    if (!(rmax > 0)) return 0; /* at rest */
    /* the rates' own rate along the frame's flow: y'' = S y' */
    double *acc = NULL, *sz = NULL;
    if (S) {
        acc = calloc((size_t)n, sizeof *acc);
        if (!acc) return BG_ERR_MEMORY;
        sp_matvec(S, 1.0, yp, 0.0, acc);
        for (int i = 0; i < n; i++)
            rmax = fmax(rmax, fabs(acc[i]) / (fabs(yp[i]) + (nom ? nom[i] : 1.0)));
    }
    double h = 1e-7 / rmax, *F0 = J->F0, *F1 = J->F1, *ys = J->ycopy;
    int st = bg_jaceval_res(J, t, y, yp, F0);
    if (st) goto out;
    for (int i = 0; i < n; i++)
        ys[i] = y[i] + h * yp[i];
    if (acc) { /* F1 as the rates' scratch, then the residual over it */
        double *yps = malloc((size_t)n * sizeof *yps);
        if (!yps) {
            st = BG_ERR_MEMORY;
            goto out;
        }
        for (int i = 0; i < n; i++)
            yps[i] = yp[i] + h * acc[i];
        st = bg_jaceval_res(J, t + h, ys, yps, F1);
        free(yps);
    } else {
        st = bg_jaceval_res(J, t + h, ys, yp, F1);
    }
    if (st) goto out;
    /* the terms: sum_j |dF/dy_ij yp_j| (+ sum_j |dF/dy'_ij (S yp)_j|) into ys; the size of
     * the equation's own terms, sum_j |dF/dy_ij y_j| + |dF/dy'_ij yp_j| + |F_i|, into sz */
    sz = malloc((size_t)n * sizeof *sz);
    if (!sz) {
        st = BG_ERR_MEMORY;
        goto out;
    }
    memset(ys, 0, (size_t)n * sizeof *ys);
    const sp_csc *A = J->Jy, *B = J->Jyp;
    double big = 0;
    for (int j = 0; j < n; j++)
        for (int q = A->colptr[j]; q < A->colptr[j + 1]; q++)
            ys[A->rowind[q]] += fabs(A->val[q] * yp[j]);
    if (acc) {
        for (int j = 0; j < n; j++)
            for (int q = B->colptr[j]; q < B->colptr[j + 1]; q++)
                ys[B->rowind[q]] += fabs(B->val[q] * acc[j]);
    }
    for (int i = 0; i < n; i++)
        sz[i] = fabs(F0[i]);
    for (int j = 0; j < n; j++) {
        for (int q = A->colptr[j]; q < A->colptr[j + 1]; q++)
            sz[A->rowind[q]] += fabs(A->val[q] * y[j]);
        for (int q = B->colptr[j]; q < B->colptr[j + 1]; q++)
            sz[B->rowind[q]] += fabs(B->val[q] * yp[j]);
    }
    for (int i = 0; i < n; i++)
        big = fmax(big, ys[i]);
    for (int i = 0; i < n; i++) {
        if (!(ys[i] > 1e-9 * big)) continue; /* nothing moves in this equation */
        /* the change less the rounding of the two residuals (64 units of their terms' size):
         * an equation the motion leaves all but unchanged shows its rounding over h */
        double dF = fmax(fabs(F1[i] - F0[i]) - 128 * DBL_EPSILON * sz[i], 0.0);
        double r = dF / h / ys[i];
        if (!(r <= *ratio)) {
            *ratio = r;
            *row = i;
        }
    }
out:
    free(acc);
    free(sz);
    return st;
}
