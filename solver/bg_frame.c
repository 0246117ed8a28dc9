/* A problem in a co-moving frame of the linear kind (bg_frame.h, bg_modes.h). */
#include "bg_frame.h"
#include "bg_jaceval.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void frame_rates(bg_frame *f, const double *z, const double *zp)
{
    int n = f->p->n;
    for (int i = 0; i < n; i++)
        f->yp[i] = f->c[i] + zp[i];
    sp_matvec(f->S, 1.0, z, 1.0, f->yp);
}

static int frame_res(void *user, double t, const double *z, const double *zp, double *G)
{
    bg_frame *f = user;
    frame_rates(f, z, zp);
    return f->p->res(f->p->user, t, z, f->yp, G);
}

static int frame_jac(void *user, double t, const double *z, const double *zp, sp_csc *Gy,
                     sp_csc *Gyp)
{
    bg_frame *f = user;
    frame_rates(f, z, zp);
    sp_csc_zero(f->Jy);
    sp_csc_zero(f->Jyp);
    int st = f->p->jac(f->p->user, t, z, f->yp, f->Jy, f->Jyp);
    if (st != 0) return st;
    memcpy(Gyp->val, f->Jyp->val, (size_t)f->Jyp->nnz * sizeof *Gyp->val);
    memset(Gy->val, 0, (size_t)Gy->nnz * sizeof *Gy->val);
    for (int k = 0; k < f->Jy->nnz; k++)
        Gy->val[f->slot_y[k]] += f->Jy->val[k];
    /* dF/dy' S: column j of S, its entries S(k, j), column k of dF/dy' */
    const sp_csc *S = f->S, *A = f->Jyp;
    long r = 0;
    for (int j = 0; j < S->ncol; j++)
        for (int a = S->colptr[j]; a < S->colptr[j + 1]; a++) {
            int k = S->rowind[a];
            for (int b = A->colptr[k]; b < A->colptr[k + 1]; b++)
                Gy->val[f->slot_prod[r++]] += A->val[b] * S->val[a];
        }
    return 0;
}

void bg_frame_free(bg_frame *f)
{
    if (!f) return;
    free(f->c);
    free(f->yp);
    sp_csc_free(&f->Jy);
    sp_csc_free(&f->Jyp);
    sp_csc_free(&f->pat_y);
    free(f->slot_y);
    free(f->slot_prod);
    memset(f, 0, sizeof *f);
}

int bg_frame_init(bg_frame *f, const dae_problem *p, const sp_csc *S, const double *c,
                  const char *where, bg_error *err)
{
    memset(f, 0, sizeof *f);
    int n = p->n;
    bg_error perr = {0};
    if (S->nrow != n || S->ncol != n || sp_csc_check(S, &perr) != BG_OK)
        return bg_error_raise(err, BG_ERR_ARGUMENT, where,
                              "the frame's generator S must be a well-formed %d x %d matrix "
                              "(the problem's size)%s%s",
                              n, n, perr.message[0] ? ": " : "", perr.message);
    for (int k = 0; k < S->nnz; k++)
        if (!isfinite(S->val[k]))
            return bg_error_raise(err, BG_ERR_ARGUMENT, where,
                                  "the frame's generator S has a value that is not finite (%g)",
                                  S->val[k]);
    f->p = p;
    f->S = S;
    f->c = calloc((size_t)n, sizeof *f->c);
    f->yp = malloc((size_t)n * sizeof *f->yp);
    if (!f->c || !f->yp) goto nomem;
    if (c) memcpy(f->c, c, (size_t)n * sizeof *f->c);
    f->q = *p;
    f->q.res = frame_res;
    f->q.user = f;
    f->q.jac = NULL;
    f->q.nroots = 0;
    f->q.roots = NULL;
    f->q.nregimes = 0;
    f->q.regimes = NULL;
    if (!p->jac_y_pattern || !p->jac_yp_pattern) { /* dense: differences on G */
        f->q.jac_y_pattern = NULL;
        f->q.jac_yp_pattern = NULL;
        return BG_OK;
    }
    /* the pattern of dF/dy + dF/dy' S and the slots of both terms */
    const sp_csc *Py = p->jac_y_pattern, *Pyp = p->jac_yp_pattern;
    if (Py->nrow != n || Py->ncol != n || Pyp->nrow != n || Pyp->ncol != n) {
        bg_frame_free(f);
        return bg_error_raise(err, BG_ERR_PATTERN, where,
                              "the Jacobian patterns must be %d x %d matrices", n, n);
    }
    sp_builder *B = sp_builder_create(n, n, Py->nnz);
    if (!B) goto nomem;
    int ok = 1;
    for (int j = 0; j < n && ok; j++)
        for (int k = Py->colptr[j]; k < Py->colptr[j + 1] && ok; k++)
            ok = sp_builder_add(B, Py->rowind[k], j, 0.0) >= 0;
    long nprod = 0;
    for (int j = 0; j < n && ok; j++)
        for (int a = S->colptr[j]; a < S->colptr[j + 1] && ok; a++) {
            int k = S->rowind[a];
            for (int b = Pyp->colptr[k]; b < Pyp->colptr[k + 1] && ok; b++, nprod++)
                ok = sp_builder_add(B, Pyp->rowind[b], j, 0.0) >= 0;
        }
    int cnt = ok ? sp_builder_count(B) : 0;
    int *slot = ok ? malloc((size_t)(cnt > 0 ? cnt : 1) * sizeof *slot) : NULL;
    f->pat_y = slot ? sp_builder_finish(B, slot) : NULL;
    sp_builder_free(&B);
    f->slot_y = malloc((size_t)(Py->nnz > 0 ? Py->nnz : 1) * sizeof *f->slot_y);
    f->slot_prod = malloc((size_t)(nprod > 0 ? nprod : 1) * sizeof *f->slot_prod);
    f->Jy = sp_csc_copy(Py);
    f->Jyp = sp_csc_copy(Pyp);
    if (!f->pat_y || !f->slot_y || !f->slot_prod || !f->Jy || !f->Jyp) {
        free(slot);
        goto nomem;
    }
    memcpy(f->slot_y, slot, (size_t)Py->nnz * sizeof *slot);
    memcpy(f->slot_prod, slot + Py->nnz, (size_t)nprod * sizeof *slot);
    free(slot);
    f->nprod = nprod;
    f->q.jac_y_pattern = f->pat_y;
    if (p->jac) f->q.jac = frame_jac;
    return BG_OK;
nomem:
    bg_frame_free(f);
    return bg_error_raise(err, BG_ERR_MEMORY, where, "out of memory");
}

int bg_frame_steadiness(const dae_problem *p, const sp_csc *S, double t, const double *y,
                        const double *yp, double *ratio, int *row, const char *where,
                        bg_error *err)
{
    bg_jaceval J;
    memset(&J, 0, sizeof J);
    int st = bg_jaceval_init(&J, p, err);
    if (st != BG_OK) return st;
    st = bg_jaceval_eval(&J, t, y, yp, NULL);
    if (st == 0) st = bg_jaceval_steadiness(&J, t, y, yp, S, ratio, row);
    if (st != 0)
        st = bg_error_raise(err, st == BG_ERR_MEMORY ? st : BG_ERR_CALLBACK, where,
                            "the residual or Jacobian could not be evaluated along the frame's "
                            "motion (status %d)",
                            st);
    bg_jaceval_free(&J);
    return st;
}
