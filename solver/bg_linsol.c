/* The linear-solver interface: KLU sparse LU with symbolic reuse and refactorization, dense LU
 * by LAPACK, and the CHOLMOD A*A^T solver (see bg_linsol.h for the method). */
#include "bg_linsol.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cholmod.h>
#include <klu.h>

/* LAPACK, Fortran calling convention with the hidden lengths of character arguments. */
void dgetrf_(const int *m, const int *n, double *a, const int *lda, int *ipiv, int *info);
void dgetrs_(const char *trans, const int *n, const int *nrhs, const double *a, const int *lda,
             const int *ipiv, double *b, const int *ldb, int *info, size_t ltrans);
double dlange_(const char *norm, const int *m, const int *n, const double *a, const int *lda,
               double *work, size_t lnorm);
void dgecon_(const char *norm, const int *n, const double *a, const int *lda, const double *anorm,
             double *rcond, double *work, int *iwork, int *info, size_t lnorm);

struct ls_solver {
    ls_kind kind;
    int n;
    sp_csc *pattern; /* copy, to check the matrices given later */
    ls_stats st;
    double rcond_min;
    double rcond_full; /* KLU: estimate of the last full factorization */
    int singular_col;
    int force_full;
    bg_error err;
    /* KLU */
    klu_common common;
    klu_symbolic *sym;
    klu_numeric *num;
    /* dense */
    double *lu, *work;
    int *ipiv, *iwork;
    int factored;
};

static int finite_values(ls_solver *s, const sp_csc *A, const char *where)
{
    for (int j = 0; j < A->ncol; j++)
        for (int p = A->colptr[j]; p < A->colptr[j + 1]; p++)
            if (!isfinite(A->val[p]))
                return bg_error_raise(&s->err, BG_ERR_NONFINITE, where,
                                      "matrix entry (%d,%d) is %g", A->rowind[p], j, A->val[p]);
    return BG_OK;
}

ls_solver *ls_create(ls_kind kind, const sp_csc *P, bg_error *err)
{
    const char *w = "ls_create";
    if (!P || P->nrow != P->ncol) {
        bg_error_raise(err, BG_ERR_ARGUMENT, w, "matrix must be square (got %d x %d)",
                       P ? P->nrow : -1, P ? P->ncol : -1);
        return NULL;
    }
    if (kind != LS_KLU && kind != LS_DENSE) {
        bg_error_raise(err, BG_ERR_ARGUMENT, w, "unknown linear solver kind %d", (int)kind);
        return NULL;
    }
    bg_error perr = {0};
    if (sp_csc_check(P, &perr) != BG_OK) {
        bg_error_raise(err, BG_ERR_PATTERN, w, "invalid pattern: %s", perr.message);
        return NULL;
    }
    ls_solver *s = calloc(1, sizeof *s);
    if (!s) goto nomem;
    s->kind = kind;
    s->n = P->ncol;
    s->rcond_min = 0.0;
    s->singular_col = -1;
    s->pattern = sp_csc_copy(P);
    if (!s->pattern) goto nomem;
    if (kind == LS_KLU) {
        klu_defaults(&s->common);
        /* COLAMD, not KLU's default AMD: AMD orders A + A^T for diagonal pivots, while Newton
         * matrices of DAEs pivot off the diagonal (equations and unknowns are not paired by
         * value), so at large alpha/h the pivots taken are not the ones AMD planned for and L
         * fills in; COLAMD orders the columns for the Cholesky factor of A^T A, which bounds the
         * fill of LU under any row pivoting (T. A. Davis, J. R. Gilbert, S. I. Larimore and
         * E. G. Ng, ACM TOMS 30 (2004) 353-376) */
        s->common.ordering = 1;
        s->sym = klu_analyze(s->n, s->pattern->colptr, s->pattern->rowind, &s->common);
        if (!s->sym) {
            bg_error_raise(err,
                           s->common.status == KLU_OUT_OF_MEMORY ? BG_ERR_MEMORY : BG_ERR_LIBRARY,
                           w, "klu_analyze failed (KLU status %d) on the %d x %d pattern",
                           s->common.status, s->n, s->n);
            ls_free(&s);
            return NULL;
        }
        s->st.symbolic = 1;
    } else {
        size_t n = (size_t)s->n;
        s->lu = malloc((n * n + 1) * sizeof *s->lu);
        s->work = malloc((4 * n + 1) * sizeof *s->work);
        s->ipiv = malloc((n + 1) * sizeof *s->ipiv);
        s->iwork = malloc((n + 1) * sizeof *s->iwork);
        if (!s->lu || !s->work || !s->ipiv || !s->iwork) goto nomem;
    }
    return s;
nomem:
    ls_free(&s);
    bg_error_raise(err, BG_ERR_MEMORY, w, "out of memory for a %d x %d solver", P->nrow, P->ncol);
    return NULL;
}

void ls_free(ls_solver **sp)
{
    if (!sp || !*sp) return;
    ls_solver *s = *sp;
    if (s->num) klu_free_numeric(&s->num, &s->common);
    if (s->sym) klu_free_symbolic(&s->sym, &s->common);
    sp_csc_free(&s->pattern);
    free(s->lu);
    free(s->work);
    free(s->ipiv);
    free(s->iwork);
    free(s);
    *sp = NULL;
}

static int klu_full(ls_solver *s, const sp_csc *A)
{
    if (s->num) klu_free_numeric(&s->num, &s->common);
    s->num = klu_factor(A->colptr, A->rowind, A->val, s->sym, &s->common);
    s->st.factor++;
    if (!s->num) {
        if (s->common.status == KLU_SINGULAR) {
            s->singular_col = s->common.singular_col;
            return bg_error_raise(&s->err, BG_ERR_SINGULAR, "ls_factor",
                                  "KLU: matrix is singular at column %d (numerical rank %d of %d, "
                                  "structural rank %d)",
                                  s->common.singular_col, s->common.numerical_rank, s->n,
                                  s->common.structural_rank);
        }
        return bg_error_raise(
            &s->err, s->common.status == KLU_OUT_OF_MEMORY ? BG_ERR_MEMORY : BG_ERR_LIBRARY,
            "ls_factor", "klu_factor failed (KLU status %d)", s->common.status);
    }
    klu_rcond(s->sym, s->num, &s->common);
    s->st.rcond = s->rcond_full = s->common.rcond;
    return BG_OK;
}

/* A refactorization whose estimate falls more than this factor below the last full one's is
 * redone with fresh pivots. */
#define LS_REFACTOR_DROP 1e-3

static int klu_fact(ls_solver *s, const sp_csc *A)
{
    if (s->num && !s->force_full) {
        int ok = klu_refactor(A->colptr, A->rowind, A->val, s->sym, s->num, &s->common);
        s->st.refactor++;
        /* stale pivots show as an estimate far below the one the pivots were chosen for; a
         * matrix that is ill-conditioned by nature (index-2 systems, stiff bars: 1e-13 and
         * below) keeps its estimate and its refactorization */
        double rc = ok && klu_rcond(s->sym, s->num, &s->common) ? s->common.rcond : 0.0;
        if (rc > 0 && rc >= s->rcond_min && rc >= LS_REFACTOR_DROP * s->rcond_full) {
            s->st.rcond = s->common.rcond;
            return BG_OK;
        }
        s->st.fallback++; /* stale pivots: zero or tiny pivot met, pivot afresh */
    }
    s->force_full = 0;
    return klu_full(s, A);
}

static int dense_fact(ls_solver *s, const sp_csc *A)
{
    int n = s->n, info = 0;
    sp_csc_to_dense(A, s->lu);
    double anorm = dlange_("O", &n, &n, s->lu, &n, s->work, 1);
    dgetrf_(&n, &n, s->lu, &n, s->ipiv, &info);
    s->st.factor++;
    if (info < 0)
        return bg_error_raise(&s->err, BG_ERR_LIBRARY, "ls_factor", "dgetrf: argument %d invalid",
                              -info);
    if (info > 0) {
        s->singular_col = info - 1; /* row pivoting only: columns keep their numbers */
        return bg_error_raise(&s->err, BG_ERR_SINGULAR, "ls_factor",
                              "dense LU: matrix is singular at column %d (zero pivot U(%d,%d))",
                              info - 1, info - 1, info - 1);
    }
    double rc = 0.0;
    dgecon_("1", &n, s->lu, &n, &anorm, &rc, s->work, s->iwork, &info, 1);
    s->st.rcond = rc;
    s->factored = 1;
    return BG_OK;
}

int ls_factor(ls_solver *s, const sp_csc *A)
{
    if (!s) return BG_ERR_ARGUMENT;
    if (!A) {
        s->factored = 0;
        return bg_error_raise(&s->err, BG_ERR_ARGUMENT, "ls_factor", "the matrix is NULL");
    }
    if (!sp_csc_same_pattern(s->pattern, A))
        return bg_error_raise(&s->err, BG_ERR_PATTERN, "ls_factor",
                              "matrix (%d x %d, %d entries) does not have the pattern the solver "
                              "was created with (%d x %d, %d entries)",
                              A->nrow, A->ncol, A->nnz, s->pattern->nrow, s->pattern->ncol,
                              s->pattern->nnz);
    s->singular_col = -1;
    s->factored = 0;
    int st = finite_values(s, A, "ls_factor");
    if (st != BG_OK) return st;
    if (s->kind == LS_KLU) {
        st = klu_fact(s, A);
        s->factored = (st == BG_OK);
        return st;
    }
    return dense_fact(s, A);
}

int ls_force_full(ls_solver *s)
{
    if (!s) return BG_ERR_ARGUMENT;
    s->force_full = 1;
    return BG_OK;
}

int ls_solve(ls_solver *s, double *b, int nrhs)
{
    if (!s) return BG_ERR_ARGUMENT;
    if (!b || nrhs < 1)
        return bg_error_raise(&s->err, BG_ERR_ARGUMENT, "ls_solve",
                              "needs a right-hand side and nrhs >= 1 (b %s, nrhs %d)",
                              b ? "given" : "NULL", nrhs);
    if (!s->factored)
        return bg_error_raise(&s->err, BG_ERR_STATE, "ls_solve",
                              "no valid factorization to solve with (call ls_factor first; the "
                              "last factorization, if any, failed)");
    if (s->n == 0) return BG_OK;
    if (s->kind == LS_KLU) {
        if (!klu_solve(s->sym, s->num, s->n, nrhs, b, &s->common))
            return bg_error_raise(&s->err, BG_ERR_LIBRARY, "ls_solve",
                                  "klu_solve failed (KLU status %d)", s->common.status);
    } else {
        int info = 0;
        dgetrs_("N", &s->n, &nrhs, s->lu, &s->n, s->ipiv, b, &s->n, &info, 1);
        if (info != 0)
            return bg_error_raise(&s->err, BG_ERR_LIBRARY, "ls_solve", "dgetrs: info %d", info);
    }
    s->st.solve += nrhs;
    return BG_OK;
}

int ls_singular_col(const ls_solver *s)
{
    return s ? s->singular_col : -1;
}
int ls_set_rcond_min(ls_solver *s, double r)
{
    if (!s) return BG_ERR_ARGUMENT;
    if (!(r >= 0))
        return bg_error_raise(&s->err, BG_ERR_ARGUMENT, "ls_set_rcond_min",
                              "rcond_min = %g: must be >= 0", r);
    s->rcond_min = r;
    return BG_OK;
}
const ls_stats *ls_get_stats(const ls_solver *s)
{
    return s ? &s->st : NULL;
}
ls_kind ls_get_kind(const ls_solver *s)
{
    return s ? s->kind : LS_NONE;
}
bg_error *ls_get_error(ls_solver *s)
{
    return s ? &s->err : NULL;
}

/* ---- CHOLMOD: (A A^T + beta I) x = b ---- */
#define AAT_PIVOT_TOL 1e-12 /* relative pivot below which rows count as dependent */
struct aat_solver {
    int m, n;
    sp_csc *pattern;
    cholmod_common c;
    cholmod_factor *L;
    cholmod_dense *X, *Y, *E;
    long nfactor;
    int factored;
    bg_error err;
};

static void wrap_sparse(cholmod_sparse *W, const sp_csc *A)
{
    memset(W, 0, sizeof *W);
    W->nrow = (size_t)A->nrow;
    W->ncol = (size_t)A->ncol;
    W->nzmax = (size_t)(A->nnz > 0 ? A->nnz : 1);
    W->p = A->colptr;
    W->i = A->rowind;
    W->x = A->val;
    W->stype = 0; /* unsymmetric: CHOLMOD factors A*A' */
    W->itype = CHOLMOD_INT;
    W->xtype = CHOLMOD_REAL;
    W->dtype = CHOLMOD_DOUBLE;
    W->sorted = 1;
    W->packed = 1;
}

aat_solver *aat_create(const sp_csc *P, bg_error *err)
{
    if (!P) {
        bg_error_raise(err, BG_ERR_ARGUMENT, "aat_create", "pattern is NULL");
        return NULL;
    }
    bg_error perr = {0};
    if (sp_csc_check(P, &perr) != BG_OK) {
        bg_error_raise(err, BG_ERR_PATTERN, "aat_create", "invalid pattern: %s", perr.message);
        return NULL;
    }
    aat_solver *s = calloc(1, sizeof *s);
    if (!s) {
        bg_error_raise(err, BG_ERR_MEMORY, "aat_create", "out of memory");
        return NULL;
    }
    cholmod_start(&s->c);
    s->c.print = 0; /* the library never prints */
    /* simplicial LDL^T: D is at hand to detect numerically dependent rows, which a Cholesky
     * factorization in floating point passes with tiny positive pivots */
    s->c.supernodal = CHOLMOD_SIMPLICIAL;
    s->c.final_ll = 0;
    s->m = P->nrow;
    s->n = P->ncol;
    s->pattern = sp_csc_copy(P);
    if (!s->pattern) {
        bg_error_raise(err, BG_ERR_MEMORY, "aat_create", "out of memory");
        aat_free(&s);
        return NULL;
    }
    cholmod_sparse W;
    wrap_sparse(&W, s->pattern);
    s->L = cholmod_analyze(&W, &s->c);
    if (!s->L) {
        bg_error_raise(err, BG_ERR_LIBRARY, "aat_create",
                       "cholmod_analyze failed (CHOLMOD status %d) on the %d x %d pattern",
                       s->c.status, s->m, s->n);
        aat_free(&s);
        return NULL;
    }
    return s;
}

void aat_free(aat_solver **sp)
{
    if (!sp || !*sp) return;
    aat_solver *s = *sp;
    if (s->L) cholmod_free_factor(&s->L, &s->c);
    if (s->X) cholmod_free_dense(&s->X, &s->c);
    if (s->Y) cholmod_free_dense(&s->Y, &s->c);
    if (s->E) cholmod_free_dense(&s->E, &s->c);
    cholmod_finish(&s->c);
    sp_csc_free(&s->pattern);
    free(s);
    *sp = NULL;
}

int aat_factor(aat_solver *s, const sp_csc *A, double beta)
{
    if (!s) return BG_ERR_ARGUMENT;
    s->factored = 0;
    if (!A) return bg_error_raise(&s->err, BG_ERR_ARGUMENT, "aat_factor", "the matrix is NULL");
    if (!(beta >= 0) || !isfinite(beta))
        return bg_error_raise(&s->err, BG_ERR_ARGUMENT, "aat_factor",
                              "beta = %g: must be finite and >= 0", beta);
    if (!sp_csc_same_pattern(s->pattern, A))
        return bg_error_raise(&s->err, BG_ERR_PATTERN, "aat_factor",
                              "matrix does not have the pattern the solver was created with");
    for (int p = 0; p < A->nnz; p++)
        if (!isfinite(A->val[p]))
            return bg_error_raise(&s->err, BG_ERR_NONFINITE, "aat_factor",
                                  "entry %d of the constraint matrix is %g", p, A->val[p]);
    cholmod_sparse W;
    wrap_sparse(&W, A);
    double b2[2] = {beta, 0.0};
    int ok = cholmod_factorize_p(&W, b2, NULL, 0, s->L, &s->c);
    s->nfactor++;
    if (s->c.status == CHOLMOD_NOT_POSDEF)
        return bg_error_raise(&s->err, BG_ERR_NOT_POSDEF, "aat_factor",
                              "A*A^T + %g I is not positive definite: pivot %d of %d fails (the "
                              "constraint rows are linearly dependent)",
                              beta, (int)s->L->minor, s->m);
    if (!ok || s->c.status < 0)
        return bg_error_raise(&s->err, BG_ERR_LIBRARY, "aat_factor",
                              "cholmod_factorize failed (CHOLMOD status %d)", s->c.status);
    if (!s->L->is_ll && !s->L->is_super && s->m > 0) {
        const int *Lp = s->L->p, *perm = s->L->Perm;
        const double *Lx = s->L->x;
        double dmax = 0;
        for (int j = 0; j < s->m; j++)
            dmax = fmax(dmax, fabs(Lx[Lp[j]]));
        for (int j = 0; j < s->m; j++)
            if (!(Lx[Lp[j]] > AAT_PIVOT_TOL * dmax))
                return bg_error_raise(&s->err, BG_ERR_NOT_POSDEF, "aat_factor",
                                      "A*A^T + %g I is numerically singular: pivot %d (row %d of "
                                      "A) is %.3g against a largest pivot of %.3g (the constraint "
                                      "rows are linearly dependent)",
                                      beta, j, perm ? perm[j] : j, Lx[Lp[j]], dmax);
    }
    s->factored = 1;
    return BG_OK;
}

int aat_solve(aat_solver *s, const double *b, double *x)
{
    if (!s) return BG_ERR_ARGUMENT;
    if (!b || !x)
        return bg_error_raise(&s->err, BG_ERR_ARGUMENT, "aat_solve", "%s is NULL",
                              !b ? "the right-hand side" : "the solution array");
    if (!s->factored)
        return bg_error_raise(&s->err, BG_ERR_STATE, "aat_solve",
                              "no valid factorization to solve with (call aat_factor first; the "
                              "last factorization, if any, failed)");
    if (s->m == 0) return BG_OK;
    cholmod_dense B;
    memset(&B, 0, sizeof B);
    B.nrow = (size_t)s->m;
    B.ncol = 1;
    B.nzmax = (size_t)s->m;
    B.d = (size_t)s->m;
    B.x = (void *)(uintptr_t)b; /* read only: cholmod_solve2 does not write B */
    B.xtype = CHOLMOD_REAL;
    B.dtype = CHOLMOD_DOUBLE;
    if (!cholmod_solve2(CHOLMOD_A, s->L, &B, NULL, &s->X, NULL, &s->Y, &s->E, &s->c))
        return bg_error_raise(&s->err, BG_ERR_LIBRARY, "aat_solve",
                              "cholmod_solve2 failed (CHOLMOD status %d)", s->c.status);
    memcpy(x, s->X->x, (size_t)s->m * sizeof *x);
    return BG_OK;
}

bg_error *aat_get_error(aat_solver *s)
{
    return s ? &s->err : NULL;
}
long aat_factor_count(const aat_solver *s)
{
    return s ? s->nfactor : BG_ERR_ARGUMENT;
}
