/* Modes by the reduced dense eigenproblem (bg_modes.h: the method), with the analysis of the
 * zero eigenvalues into rigid motions and constraint modes. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bg_modes.h"
#include "bg_modes_impl.h"

/* LAPACK, Fortran calling convention with the hidden lengths of character arguments. */
void dgeevx_(const char *balanc, const char *jobvl, const char *jobvr, const char *sense,
             const int *n, double *a, const int *lda, double *wr, double *wi, double *vl,
             const int *ldvl, double *vr, const int *ldvr, int *ilo, int *ihi, double *scale,
             double *abnrm, double *rconde, double *rcondv, double *work, const int *lwork,
             int *iwork, int *info, size_t l1, size_t l2, size_t l3, size_t l4);
/* Which zero eigenvalues are defective (Jordan chains: rigid motions) and which semisimple
 * (invariants: constraint modes). The zero eigenvalues of X A are mu0 = 1/sigma; their algebraic
 * multiplicity m is the number of computed eigenvalues there, their geometric multiplicity g the
 * dimension of the null space of C - mu0 I (singular values below 1e-10 of the largest, LAPACK
 * dgesvd on a copy of C), and m - g Jordan chains of length 2 are the rigid motions. Rounding
 * splits a chain into a pair +-delta (or +-i delta) of nearly parallel eigenvectors: the m - g
 * pairs of eigenvectors at the smallest angles are the rigid ones. The reciprocal condition
 * numbers of the eigenvalues tell the same in isolation, but not inside a cluster of dozens of
 * semisimple zeros (the drift of every joint and member), where they fall to 1e-5 and where
 * computed eigenvectors can be nearly parallel too; the multiplicities decide. rigid[j] = 1 for
 * the eigenvalues (of wr, wi) that are rigid. */
void dgesvd_(const char *jobu, const char *jobvt, const int *m, const int *n, double *a,
             const int *lda, double *s, double *u, const int *ldu, double *vt, const int *ldvt,
             double *work, const int *lwork, int *info, size_t l1, size_t l2);

static double col_angle(const double *a, const double *b, int d)
{
    double ab = 0, aa = 0, bb = 0;
    for (int i = 0; i < d; i++)
        ab += a[i] * b[i], aa += a[i] * a[i], bb += b[i] * b[i];
    if (!(aa > 0 && bb > 0)) return 0;
    double c = fabs(ab) / sqrt(aa * bb);
    return c >= 1 ? 0 : sqrt(1 - c * c);
}

static int rigid_analysis(const double *C0, const double *VR, const double *wr, const double *wi,
                          int d, double sigma, double zero_tol, int *rigid)
{
    if (d < 1) return BG_OK;
    int *zero = calloc((size_t)d, sizeof *zero), m = 0;
    if (!zero) return BG_ERR_MEMORY;
    for (int j = 0; j < d; j++) {
        rigid[j] = 0;
        double complex mu = wr[j] + I * wi[j];
        if (cabs(mu) > 0 && cabs(sigma - 1.0 / mu) <= zero_tol * fabs(sigma)) zero[j] = 1, m++;
    }
    /* candidate pairs: complex pairs at zero (real and imaginary parts), and real pairs */
    typedef struct pair {
        int a, b;
        double angle;
    } pair;
    int np = 0, cap = 16;
    pair *P = malloc((size_t)cap * sizeof *P);
    int st = BG_OK;
    for (int j = 0; j < d && P; j++) {
        if (!zero[j] || wi[j] < 0) continue;
        for (int k = j + 1; k < d; k++) {
            if (!(wi[j] > 0 ? k == j + 1 : zero[k] && wi[k] == 0)) continue;
            double ang = col_angle(VR + (size_t)j * d, VR + (size_t)k * d, d);
            if (ang >= 1e-4) continue;
            if (np == cap) {
                pair *q = realloc(P, 2 * (size_t)cap * sizeof *q);
                if (!q) {
                    free(P);
                    P = NULL;
                    break;
                }
                P = q, cap *= 2;
            }
            P[np++] = (pair){j, k, ang};
        }
    }
    if (!P) st = BG_ERR_MEMORY;
    if (st == BG_OK && np > 0) { /* the geometric multiplicity */
        double *A = malloc((size_t)d * d * sizeof *A), *sv = malloc((size_t)d * sizeof *sv), wq;
        int info = 0, lwork = -1, one = 1;
        if (!A || !sv) {
            st = BG_ERR_MEMORY;
        } else {
            memcpy(A, C0, (size_t)d * d * sizeof *A);
            for (int i = 0; i < d; i++)
                A[(size_t)i * d + i] -= 1.0 / sigma;
            dgesvd_("N", "N", &d, &d, A, &d, sv, NULL, &one, NULL, &one, &wq, &lwork, &info, 1, 1);
            lwork = info == 0 ? (int)wq : 5 * d;
            double *work = malloc((size_t)lwork * sizeof *work);
            if (!work) {
                st = BG_ERR_MEMORY;
            } else {
                memcpy(A, C0, (size_t)d * d * sizeof *A);
                for (int i = 0; i < d; i++)
                    A[(size_t)i * d + i] -= 1.0 / sigma;
                dgesvd_("N", "N", &d, &d, A, &d, sv, NULL, &one, NULL, &one, work, &lwork, &info, 1,
                        1);
                free(work);
                int g = 0;
                for (int i = 0; info == 0 && i < d; i++)
                    g += sv[i] <= 1e-10 * sv[0];
                int chains = info == 0 ? m - g : 0;
                /* the pairs at the smallest angles, each eigenvalue once */
                for (int c = 0; c < chains; c++) {
                    int best = -1;
                    for (int q = 0; q < np; q++)
                        if (!rigid[P[q].a] && !rigid[P[q].b] &&
                            (best < 0 || P[q].angle < P[best].angle))
                            best = q;
                    if (best < 0) break;
                    rigid[P[best].a] = rigid[P[best].b] = 1;
                }
            }
        }
        free(A);
        free(sv);
    }
    free(P);
    free(zero);
    return st;
}

int mode_dense(mctx *c)
{
    dae_modes *M = c->M;
    const dae_modes_options *o = c->o;
    const int n = M->n, d = M->d;
    const sp_csc *A = c->J.Jyp;
    int st;
    if (n < 1 || d < 1) return BG_OK;
    double sigma = o->sigma > 0 ? o->sigma : (o->sigma < 0 ? o->sigma : 1.0);
    if ((st = mode_factor_shift(c, &sigma)) != BG_OK) return st;
    M->sigma = sigma;
    int *pos = malloc((size_t)n * sizeof *pos); /* position among the differential unknowns */
    double *C = malloc((size_t)d * d * sizeof *C), *C0 = malloc((size_t)d * d * sizeof *C0);
    int *rigid = malloc((size_t)d * sizeof *rigid);
    const int nb = 32;
    double *blk = malloc((size_t)n * nb * sizeof *blk);
    double *wr = malloc((size_t)d * sizeof *wr), *wi = malloc((size_t)d * sizeof *wi);
    double *VL = malloc((size_t)d * d * sizeof *VL), *VR = malloc((size_t)d * d * sizeof *VR);
    double *scale = malloc((size_t)d * sizeof *scale), *rce = malloc((size_t)d * sizeof *rce);
    double *rcv = malloc((size_t)d * sizeof *rcv);
    double *zr = malloc((size_t)n * sizeof *zr), *zi = malloc((size_t)n * sizeof *zi);
    double *work = NULL;
    int *iwork = malloc((size_t)(2 * d + 2) * sizeof *iwork);
    if (!pos || !C || !C0 || !rigid || !blk || !wr || !wi || !VL || !VR || !scale || !rce || !rcv ||
        !zr || !zi || !iwork) {
        st = bg_error_raise(c->err, BG_ERR_MEMORY, "dae_modes_compute", "out of memory");
        goto done;
    }
    for (int i = 0; i < n; i++)
        pos[i] = -1;
    for (int j = 0; j < d; j++)
        pos[M->dif[j]] = j;
    /* C = P_d^T (B + sigma A)^-1 A_d, nb columns at a time */
    for (int j0 = 0; j0 < d; j0 += nb) {
        int nc = d - j0 < nb ? d - j0 : nb;
        memset(blk, 0, (size_t)n * nc * sizeof *blk);
        for (int k = 0; k < nc; k++) {
            int col = M->dif[j0 + k];
            for (int p = A->colptr[col]; p < A->colptr[col + 1]; p++)
                blk[(size_t)k * n + A->rowind[p]] = A->val[p];
        }
        if ((st = ls_solve(c->ls, blk, nc)) != BG_OK) {
            st = bg_error_raise(c->err, st, "dae_modes_compute", "solve: %s",
                                ls_get_error(c->ls)->message);
            goto done;
        }
        for (int k = 0; k < nc; k++)
            for (int j = 0; j < d; j++)
                C[(size_t)(j0 + k) * d + j] = blk[(size_t)k * n + M->dif[j]];
    }
    memcpy(C0, C, (size_t)d * d * sizeof *C0); /* dgeevx overwrites C */
    int ilo, ihi, info = 0, lwork = -1;
    double abnrm, wq;
    dgeevx_("B", "V", "V", "E", &d, C, &d, wr, wi, VL, &d, VR, &d, &ilo, &ihi, scale, &abnrm, rce,
            rcv, &wq, &lwork, iwork, &info, 1, 1, 1, 1);
    lwork = info == 0 ? (int)wq : d * (d + 6);
    if (lwork < d * (d + 6)) lwork = d * (d + 6);
    work = malloc((size_t)lwork * sizeof *work);
    if (!work) {
        st = bg_error_raise(c->err, BG_ERR_MEMORY, "dae_modes_compute", "out of memory");
        goto done;
    }
    dgeevx_("B", "V", "V", "E", &d, C, &d, wr, wi, VL, &d, VR, &d, &ilo, &ihi, scale, &abnrm, rce,
            rcv, work, &lwork, iwork, &info, 1, 1, 1, 1);
    if (info != 0) {
        st = bg_error_raise(c->err, BG_ERR_LIBRARY, "dae_modes_compute",
                            "LAPACK dgeevx failed (info %d) on the %d x %d reduced matrix", info, d,
                            d);
        goto done;
    }
    double mumax = 0;
    for (int j = 0; j < d; j++)
        mumax = fmax(mumax, hypot(wr[j], wi[j]));
    if ((st = rigid_analysis(C0, VR, wr, wi, d, sigma, o->zero_tol, rigid)) != BG_OK) {
        st = bg_error_raise(c->err, st, "dae_modes_compute", "out of memory");
        goto done;
    }
    double *ur = blk, *ui = blk + n; /* A_d u, real and imaginary, then z */
    for (int j = 0; j < d; j++) {
        if (wi[j] < 0) continue; /* the conjugate of the previous one */
        double complex mu = wr[j] + I * wi[j];
        const double *vr = VR + (size_t)j * d, *vi = wi[j] > 0 ? VR + (size_t)(j + 1) * d : NULL;
        int kind;
        double complex s;
        if (cabs(mu) <= o->inf_tol * mumax) {
            kind = DAE_MODE_CONSTRAINT;
            s = INFINITY;
        } else {
            s = sigma - 1.0 / mu;
            if (cabs(s) <= o->zero_tol * fabs(sigma))
                kind = rigid[j] ? DAE_MODE_RIGID : DAE_MODE_CONSTRAINT;
            else
                kind = DAE_MODE_ELASTIC;
        }
        /* z = X A_d u */
        memset(ur, 0, 2 * (size_t)n * sizeof *ur);
        for (int k = 0; k < d; k++) {
            int col = M->dif[k];
            for (int p = A->colptr[col]; p < A->colptr[col + 1]; p++) {
                ur[A->rowind[p]] += A->val[p] * vr[k];
                if (vi) ui[A->rowind[p]] += A->val[p] * vi[k];
            }
        }
        if ((st = ls_solve(c->ls, ur, vi ? 2 : 1)) != BG_OK) goto done;
        if (kind == DAE_MODE_CONSTRAINT && isinf(creal(s))) {
            /* at infinity: the differential part of the eigenvector of C itself */
            memset(ur, 0, 2 * (size_t)n * sizeof *ur);
            for (int k = 0; k < d; k++) {
                ur[M->dif[k]] = vr[k];
                if (vi) ui[M->dif[k]] = vi[k];
            }
        }
        memcpy(zr, ur, (size_t)n * sizeof *zr);
        if (vi)
            memcpy(zi, ui, (size_t)n * sizeof *zi);
        else
            memset(zi, 0, (size_t)n * sizeof *zi);
        double res = mode_pencil_residual(c, s, zr, zi);
        double re = creal(s), im = cimag(s);
        if (isinf(re)) re = INFINITY, im = 0;
        if ((st = mode_add(M, re, im, kind, rce[j], zr, zi, res)) != BG_OK) {
            st = bg_error_raise(c->err, st, "dae_modes_compute", "out of memory");
            goto done;
        }
    }
    st = BG_OK;
done:
    free(pos);
    free(C);
    free(C0);
    free(rigid);
    free(blk);
    free(wr);
    free(wi);
    free(VL);
    free(VR);
    free(scale);
    free(rce);
    free(rcv);
    free(zr);
    free(zi);
    free(work);
    free(iwork);
    return st;
}
