/* Linearisation and modes of large models: the lowest modes, or those in a window, by ARPACK in
 * shift-invert mode on the sparse LU of the pencil (the method is in bg_modes.h). */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <klu.h>

#ifdef BG_HAVE_ARPACK
#include <arpack.h>
#endif

#include "bg_modes_impl.h"

#ifdef BG_HAVE_ARPACK
/* Entry i of ARPACK's start vector, of the model's scale: the nominal magnitude times a
 * deterministic pattern in [-0.5, 0.5) (runs repeat exactly). */
static double start_entry(const dae_modes *M, int i)
{
    unsigned h = (unsigned)i * 2654435761u;
    return ((double)(h >> 8) / 16777216.0 - 0.5) * mode_nominal(M, i);
}
#endif

/* ------------------------------------------------------------------ sparse ---- */

#ifdef BG_HAVE_ARPACK
/* y = (X A - sigma (X A)^2) x, X = (B + sigma A)^-1 (factored). */
static int apply_op(mctx *c, double sigma, const double *x, double *y)
{
    int n = c->M->n, st;
    double *u = c->w1, *w = c->w2;
    sp_matvec(c->J.Jyp, 1.0, x, 0.0, u);
    if ((st = ls_solve(c->ls, u, 1)) != BG_OK) return st;
    sp_matvec(c->J.Jyp, 1.0, u, 0.0, w);
    if ((st = ls_solve(c->ls, w, 1)) != BG_OK) return st;
    for (int i = 0; i < n; i++)
        y[i] = u[i] - sigma * w[i];
    return BG_OK;
}

/* Rayleigh-quotient iteration on one mode in complex arithmetic (KLU's complex LU of s A + B on
 * the union pattern): the window's eigenvalues come from -s/(sigma - s)^2 through solves with
 * B + sigma A, whose rounding along the model's drift directions (small singular values
 * sigma |A|) limits them to a relative 1e-4 or so on models with many bodies; a solve with the
 * shift at the mode itself does not have that weakness. Two factorizations per mode. */
typedef struct refiner {
    klu_common common;
    klu_symbolic *sym;
    double *Ax, *rhs, *z; /* interleaved complex: 2 nnz, 2 n, 2 n */
} refiner;

static void refiner_free(refiner *R)
{
    if (R->sym) klu_free_symbolic(&R->sym, &R->common);
    free(R->Ax);
    free(R->rhs);
    free(R->z);
    memset(R, 0, sizeof *R);
}

static int refiner_init(mctx *c, refiner *R)
{
    memset(R, 0, sizeof *R);
    const sp_csc *P = c->u->M;
    int n = c->M->n;
    klu_defaults(&R->common);
    R->common.ordering = 1; /* COLAMD, as bg_linsol.c */
    R->sym = klu_analyze(n, P->colptr, P->rowind, &R->common);
    R->Ax = malloc(2 * (size_t)(P->nnz > 0 ? P->nnz : 1) * sizeof *R->Ax);
    R->rhs = malloc(2 * (size_t)n * sizeof *R->rhs);
    R->z = malloc(2 * (size_t)n * sizeof *R->z);
    if (!R->sym || !R->Ax || !R->rhs || !R->z) {
        refiner_free(R);
        return BG_ERR_MEMORY;
    }
    return BG_OK;
}

/* rhs = A z (complex, interleaved) */
static void cplx_matvec(const sp_csc *A, const double *z, double *y)
{
    memset(y, 0, 2 * (size_t)A->nrow * sizeof *y);
    for (int j = 0; j < A->ncol; j++)
        for (int p = A->colptr[j]; p < A->colptr[j + 1]; p++) {
            y[2 * A->rowind[p]] += A->val[p] * z[2 * j];
            y[2 * A->rowind[p] + 1] += A->val[p] * z[2 * j + 1];
        }
}

/* Refines s, zr, zi in place; 0 if it improved them, else the inputs are kept. */
static int refine_mode(mctx *c, refiner *R, double complex *s, double *zr, double *zi)
{
    const sp_csc *P = c->u->M;
    const sp_union *u = c->u;
    int n = c->M->n;
    double complex s0 = *s;
    for (int i = 0; i < n; i++)
        R->z[2 * i] = zr[i], R->z[2 * i + 1] = zi[i];
    int improved = 0;
    for (int it = 0; it < 3; it++) {
        memset(R->Ax, 0, 2 * (size_t)P->nnz * sizeof *R->Ax);
        for (int p = 0; p < c->J.Jy->nnz; p++)
            R->Ax[2 * u->map_a[p]] += c->J.Jy->val[p];
        for (int p = 0; p < c->J.Jyp->nnz; p++) {
            R->Ax[2 * u->map_b[p]] += creal(s0) * c->J.Jyp->val[p];
            R->Ax[2 * u->map_b[p] + 1] += cimag(s0) * c->J.Jyp->val[p];
        }
        klu_numeric *num = klu_z_factor(P->colptr, P->rowind, R->Ax, R->sym, &R->common);
        if (!num) break; /* s0 is an eigenvalue to working precision: keep it */
        double complex nu = 0, zz = 0;
        for (int k = 0; k < 2; k++) { /* two steps of inverse iteration at this shift */
            cplx_matvec(c->J.Jyp, R->z, R->rhs);
            if (!klu_z_solve(R->sym, num, n, 1, R->rhs, &R->common)) break;
            /* nu = z^H y / z^H z ~ 1 / (s0 - s) */
            nu = 0, zz = 0;
            double big = 0;
            for (int i = 0; i < n; i++) {
                double complex zi_ = R->z[2 * i] + I * R->z[2 * i + 1];
                double complex yi = R->rhs[2 * i] + I * R->rhs[2 * i + 1];
                nu += conj(zi_) * yi;
                zz += conj(zi_) * zi_;
                big = fmax(big, cabs(yi));
            }
            if (!(big > 0) || !isfinite(big)) break;
            for (int i = 0; i < 2 * n; i++)
                R->z[i] = R->rhs[i] / big;
            nu /= big;
            zz /= big;
        }
        klu_z_free_numeric(&num, &R->common);
        if (!(cabs(nu) > 0) || !isfinite(cabs(nu))) break;
        double complex s1 = s0 - zz / nu;
        double step = cabs(s1 - s0);
        s0 = s1;
        improved = 1;
        if (step <= 1e-13 * cabs(s0)) break;
    }
    if (!improved) return 1;
    double *tr = c->w1, *ti = c->w2;
    /* keep the refined pair only if its residual is smaller */
    double *nr = malloc(2 * (size_t)n * sizeof *nr);
    if (!nr) return 1;
    for (int i = 0; i < n; i++)
        nr[i] = R->z[2 * i], nr[n + i] = R->z[2 * i + 1];
    (void)tr;
    (void)ti;
    double e_old = mode_pencil_residual(c, *s, zr, zi),
           e_new = mode_pencil_residual(c, s0, nr, nr + n);
    int ok = e_new <= e_old || !isfinite(e_old);
    if (ok) {
        *s = s0;
        memcpy(zr, nr, (size_t)n * sizeof *zr);
        memcpy(zi, nr + n, (size_t)n * sizeof *zi);
    }
    free(nr);
    return ok ? 0 : 1;
}

typedef struct found {
    double complex s;
    double res;
    double *zr, *zi;
} found;

/* Whether the mode (s, z) is one already in f (those of f[0..nf) with vectors and use[j] set,
 * or all with vectors when use is NULL):
 * a repeated eigenvalue has as many modes as independent eigenvectors, so two modes are the
 * same only when their eigenvalues agree (relative 1e-6) and the vector lies in the span of the
 * kept vectors of that eigenvalue: the part of z (weighted by the nominal magnitudes) orthogonal
 * to that span, by modified Gram-Schmidt in complex arithmetic, below 1e-3 of |z|. A copy
 * found twice (a window's copies, a mode and its conjugate flipped) passes; the second
 * eigenvector of a symmetric section's bending frequency (another plane) does not. 1 the same,
 * 0 new, < 0 out of memory. */
static int mode_known(const dae_modes *M, const found *f, int nf, const char *use, double complex s,
                      const double *zr, const double *zi)
{
    const int n = M->n;
    int m = 0;
    for (int j = 0; j < nf; j++)
        if ((!use || use[j]) && f[j].zr && cabs(f[j].s - s) <= 1e-6 * cabs(s)) m++;
    if (m == 0) return 0;
    double complex *Q = malloc((size_t)(m + 1) * (size_t)n * sizeof *Q);
    if (!Q) return -1;
    int q = 0;
    for (int j = 0; j <= nf; j++) { /* the cluster's vectors, then z (j == nf) */
        if (j < nf && ((use && !use[j]) || !f[j].zr || !(cabs(f[j].s - s) <= 1e-6 * cabs(s))))
            continue;
        const double *vr = j < nf ? f[j].zr : zr, *vi = j < nf ? f[j].zi : zi;
        double complex *v = Q + (size_t)q * n;
        double n0 = 0;
        for (int i = 0; i < n; i++) {
            v[i] = (vr[i] + I * (vi ? vi[i] : 0.0)) / mode_nominal(M, i);
            n0 += creal(v[i] * conj(v[i]));
        }
        for (int b = 0; b < q; b++) { /* v -= Q_b (Q_b^H v) */
            const double complex *u = Q + (size_t)b * n;
            double complex h = 0;
            for (int i = 0; i < n; i++)
                h += conj(u[i]) * v[i];
            for (int i = 0; i < n; i++)
                v[i] -= h * u[i];
        }
        double n1 = 0;
        for (int i = 0; i < n; i++)
            n1 += creal(v[i] * conj(v[i]));
        if (j == nf) {
            free(Q);
            return !(n0 > 0) || n1 <= 1e-6 * n0; /* sine of the angle to the span < 1e-3 */
        }
        if (!(n1 > 1e-12 * n0)) continue; /* dependent on the kept ones: adds nothing */
        double r = 1.0 / sqrt(n1);
        for (int i = 0; i < n; i++)
            v[i] *= r;
        q++;
    }
    free(Q);
    return 0;
}

/* One ARPACK run at shift sigma: the elastic modes it finds into f (at most cap, vectors
 * allocated), their count into *nf. BG_OK, DAE_CONV_FAIL (some converged) or an error. */
static int arpack_run(mctx *c, double sigma, int nev_a, found *f, int cap, int *nf, int *iters)
{
    dae_modes *M = c->M;
    const dae_modes_options *o = c->o;
    const int n = M->n;
    *nf = 0;
    if (n < 1) return BG_OK;
    int ncv = o->ncv > 0 ? o->ncv : (2 * nev_a + 1 > nev_a + 20 ? 2 * nev_a + 1 : nev_a + 20);
    if (ncv > n) ncv = n;
    if (nev_a > ncv - 2) nev_a = ncv - 2;
    if (nev_a < 1)
        return bg_error_raise(c->err, BG_ERR_ARGUMENT, "dae_modes_compute",
                              "the model is too small for the sparse method (n = %d)", n);
    int lworkl = 3 * ncv * ncv + 6 * ncv, st = BG_OK;
    double *resid = malloc((size_t)n * sizeof *resid), *V = malloc((size_t)n * ncv * sizeof *V);
    double *workd = malloc(3 * (size_t)n * sizeof *workd);
    double *workl = malloc((size_t)lworkl * sizeof *workl);
    double *dr = malloc((size_t)(nev_a + 1) * sizeof *dr),
           *di = malloc((size_t)(nev_a + 1) * sizeof *di);
    double *Z = malloc((size_t)n * (nev_a + 1) * sizeof *Z);
    double *workev = malloc(3 * (size_t)ncv * sizeof *workev);
    int *select = calloc((size_t)ncv, sizeof *select);
    if (!resid || !V || !workd || !workl || !dr || !di || !Z || !workev || !select) {
        st = bg_error_raise(c->err, BG_ERR_MEMORY, "dae_modes_compute", "out of memory");
        goto done;
    }
    for (int i = 0; i < n; i++)
        resid[i] = start_entry(M, i);
    int ipntr[14] = {0}, iparam[11] = {0}, ido = 0, info = 1;
    iparam[0] = 1;
    iparam[2] = o->maxiter;
    iparam[6] = 1;
    for (;;) {
        dnaupd_c(&ido, "I", n, "LM", nev_a, o->tol, resid, ncv, V, n, iparam, ipntr, workd, workl,
                 lworkl, &info);
        if (ido == -1 || ido == 1) {
            if ((st = apply_op(c, sigma, workd + ipntr[0] - 1, workd + ipntr[1] - 1)) != BG_OK) {
                st = bg_error_raise(c->err, st, "dae_modes_compute", "solve: %s",
                                    ls_get_error(c->ls)->message);
                goto done;
            }
            continue;
        }
        break;
    }
    *iters = iparam[2];
    if (info < 0) {
        st = bg_error_raise(c->err, BG_ERR_LIBRARY, "dae_modes_compute",
                            "ARPACK dnaupd failed (info %d)", info);
        goto done;
    }
    int conv_fail = info == 1;
    int nconv = iparam[4];
    if (nconv < 1) {
        st = bg_error_raise(c->err, DAE_CONV_FAIL, "dae_modes_compute",
                            "ARPACK found no eigenvalue within %d restarts", o->maxiter);
        goto done;
    }
    int rinfo = 0;
    dneupd_c(1, "A", select, dr, di, Z, n, 0.0, 0.0, workev, "I", n, "LM", nev_a, o->tol, resid,
             ncv, V, n, iparam, ipntr, workd, workl, lworkl, &rinfo);
    if (rinfo != 0) {
        st = bg_error_raise(c->err, BG_ERR_LIBRARY, "dae_modes_compute",
                            "ARPACK dneupd failed (info %d)", rinfo);
        goto done;
    }
    nconv = iparam[4];
    double thmax = 0;
    for (int j = 0; j < nconv; j++)
        thmax = fmax(thmax, hypot(dr[j], di[j]));
    double *ti = calloc((size_t)n, sizeof *ti);
    if (!ti) {
        st = bg_error_raise(c->err, BG_ERR_MEMORY, "dae_modes_compute", "out of memory");
        goto done;
    }
    for (int j = 0; j < nconv && *nf < cap; j++) {
        double complex th = dr[j] + I * di[j];
        const double *zr = Z + (size_t)j * n, *zi = NULL;
        int conj_pair = 0;
        if (di[j] != 0) {
            if (j + 1 >= nconv) break;
            zi = Z + (size_t)(j + 1) * n;
            conj_pair = 1;
        }
        if (cabs(th) > 1e-12 * thmax) {
            /* s from theta: theta s^2 - (2 sigma theta - 1) s + theta sigma^2 = 0; the root with
             * the smaller pencil residual on this vector */
            double complex bq = -(2 * sigma * th - 1.0),
                           disc = csqrt(bq * bq - 4 * th * th * sigma * sigma);
            double complex r1 = (-bq + disc) / (2 * th), r2 = (-bq - disc) / (2 * th);
            double e1 = mode_pencil_residual(c, r1, zr, zi ? zi : ti);
            double e2 = mode_pencil_residual(c, r2, zr, zi ? zi : ti);
            double complex s = e1 <= e2 ? r1 : r2;
            double res = fmin(e1, e2);
            int flip = cimag(s) < 0;
            found *fd = &f[*nf];
            fd->zr = malloc((size_t)n * sizeof *fd->zr);
            fd->zi = malloc((size_t)n * sizeof *fd->zi);
            if (!fd->zr || !fd->zi) {
                free(fd->zr);
                free(fd->zi);
                free(ti);
                st = bg_error_raise(c->err, BG_ERR_MEMORY, "dae_modes_compute", "out of memory");
                goto done;
            }
            memcpy(fd->zr, zr, (size_t)n * sizeof *zr);
            for (int i = 0; i < n; i++)
                fd->zi[i] = zi ? (flip ? -zi[i] : zi[i]) : 0.0;
            fd->s = flip ? conj(s) : s;
            fd->res = res;
            (*nf)++;
        }
        if (conj_pair) j++;
    }
    free(ti);
    st = conv_fail ? DAE_CONV_FAIL : BG_OK;
done:
    free(resid);
    free(V);
    free(workd);
    free(workl);
    free(dr);
    free(di);
    free(Z);
    free(workev);
    free(select);
    return st;
}
#endif

#ifdef BG_HAVE_ARPACK
/* The window: the nev eigenvalues nearest i wc by complex shift-invert, OP = (B + i wc A)^-1 A
 * (KLU's complex LU, ARPACK znaupd/zneupd): mu = 1 / (i wc - s). Zero modes are at distance wc
 * from the shift, so every mode in the disc |s - i wc| < wc comes before them, and a mode's
 * conjugate is farther than the mode. The found modes go to f as in arpack_run. */
static int arpack_window(mctx *c, refiner *R, double wc, int nev, found *f, int cap, int *nf)
{
    dae_modes *M = c->M;
    const dae_modes_options *o = c->o;
    const sp_csc *P = c->u->M;
    const sp_union *u = c->u;
    const int n = M->n;
    *nf = 0;
    if (n < 1) return BG_OK;
    int ncv = o->ncv > 0 ? o->ncv : (2 * nev + 1 > nev + 20 ? 2 * nev + 1 : nev + 20);
    if (ncv > n) ncv = n;
    if (nev > ncv - 2) nev = ncv - 2;
    if (nev < 1)
        return bg_error_raise(c->err, BG_ERR_ARGUMENT, "dae_modes_compute",
                              "the model is too small for the sparse method (n = %d)", n);
    memset(R->Ax, 0, 2 * (size_t)P->nnz * sizeof *R->Ax);
    for (int p = 0; p < c->J.Jy->nnz; p++)
        R->Ax[2 * u->map_a[p]] += c->J.Jy->val[p];
    for (int p = 0; p < c->J.Jyp->nnz; p++)
        R->Ax[2 * u->map_b[p] + 1] += wc * c->J.Jyp->val[p];
    klu_numeric *num = klu_z_factor(P->colptr, P->rowind, R->Ax, R->sym, &R->common);
    if (!num)
        return bg_error_raise(c->err, BG_ERR_SINGULAR, "dae_modes_compute",
                              "B + i %g A is singular (KLU status %d): an eigenvalue at the "
                              "window's centre; move it",
                              wc, R->common.status);
    int lworkl = 3 * ncv * ncv + 5 * ncv, st = BG_OK;
    double complex *resid = malloc((size_t)n * sizeof *resid);
    double complex *V = malloc((size_t)n * ncv * sizeof *V);
    double complex *workd = malloc(3 * (size_t)n * sizeof *workd);
    double complex *workl = malloc((size_t)lworkl * sizeof *workl);
    double complex *dv = malloc((size_t)(nev + 1) * sizeof *dv);
    double complex *Z = malloc((size_t)n * (nev + 1) * sizeof *Z);
    double complex *workev = malloc(2 * (size_t)ncv * sizeof *workev);
    double *rwork = malloc((size_t)ncv * sizeof *rwork);
    int *select = calloc((size_t)ncv, sizeof *select);
    double *zr = malloc((size_t)n * sizeof *zr), *zi = malloc((size_t)n * sizeof *zi);
    if (!resid || !V || !workd || !workl || !dv || !Z || !workev || !rwork || !select || !zr ||
        !zi) {
        st = bg_error_raise(c->err, BG_ERR_MEMORY, "dae_modes_compute", "out of memory");
        goto done;
    }
    for (int i = 0; i < n; i++)
        resid[i] = start_entry(M, i);
    int ipntr[14] = {0}, iparam[11] = {0}, ido = 0, info = 1;
    iparam[0] = 1;
    iparam[2] = o->maxiter;
    iparam[6] = 1;
    for (;;) {
        znaupd_c(&ido, "I", n, "LM", nev, o->tol, resid, ncv, V, n, iparam, ipntr, workd, workl,
                 lworkl, rwork, &info);
        if (ido != -1 && ido != 1) break;
        const double complex *x = workd + ipntr[0] - 1;
        double complex *y = workd + ipntr[1] - 1;
        cplx_matvec(c->J.Jyp, (const double *)x, (double *)y);
        if (!klu_z_solve(R->sym, num, n, 1, (double *)y, &R->common)) {
            st = bg_error_raise(c->err, BG_ERR_LIBRARY, "dae_modes_compute",
                                "complex solve failed (KLU status %d)", R->common.status);
            goto done;
        }
    }
    if (info < 0) {
        st = bg_error_raise(c->err, BG_ERR_LIBRARY, "dae_modes_compute",
                            "ARPACK znaupd failed (info %d)", info);
        goto done;
    }
    int conv_fail = info == 1;
    if (iparam[4] < 1) {
        st = bg_error_raise(c->err, DAE_CONV_FAIL, "dae_modes_compute",
                            "ARPACK found no eigenvalue within %d restarts", o->maxiter);
        goto done;
    }
    int rinfo = 0;
    zneupd_c(1, "A", select, dv, Z, n, 0.0, workev, "I", n, "LM", nev, o->tol, resid, ncv, V, n,
             iparam, ipntr, workd, workl, lworkl, rwork, &rinfo);
    if (rinfo != 0) {
        st = bg_error_raise(c->err, BG_ERR_LIBRARY, "dae_modes_compute",
                            "ARPACK zneupd failed (info %d)", rinfo);
        goto done;
    }
    int nconv = iparam[4];
    for (int j = 0; j < nconv && *nf < cap; j++) {
        if (!(cabs(dv[j]) * wc > 1e-10)) continue; /* at infinity */
        double complex s = I * wc - 1.0 / dv[j];
        int flip = cimag(s) < 0;
        for (int i = 0; i < n; i++) {
            double complex z = Z[(size_t)j * n + i];
            zr[i] = creal(z);
            zi[i] = flip ? -cimag(z) : cimag(z);
        }
        if (flip) s = conj(s);
        int dup = mode_known(M, f, *nf, NULL, s, zr, zi);
        if (dup < 0) {
            st = bg_error_raise(c->err, BG_ERR_MEMORY, "dae_modes_compute", "out of memory");
            goto done;
        }
        if (dup) continue;
        found *fd = &f[*nf];
        fd->zr = malloc((size_t)n * sizeof *fd->zr);
        fd->zi = malloc((size_t)n * sizeof *fd->zi);
        if (!fd->zr || !fd->zi) {
            free(fd->zr);
            free(fd->zi);
            st = bg_error_raise(c->err, BG_ERR_MEMORY, "dae_modes_compute", "out of memory");
            goto done;
        }
        memcpy(fd->zr, zr, (size_t)n * sizeof *zr);
        memcpy(fd->zi, zi, (size_t)n * sizeof *zi);
        fd->s = s;
        fd->res = mode_pencil_residual(c, s, zr, zi);
        (*nf)++;
    }
    st = conv_fail ? DAE_CONV_FAIL : BG_OK;
done:
    klu_z_free_numeric(&num, &R->common);
    free(resid);
    free(V);
    free(workd);
    free(workl);
    free(dv);
    free(Z);
    free(workev);
    free(rwork);
    free(select);
    free(zr);
    free(zi);
    return st;
}
#endif

int mode_sparse(mctx *c)
{
#ifndef BG_HAVE_ARPACK
    return bg_error_raise(c->err, BG_ERR_LIBRARY, "dae_modes_compute",
                          "the sparse method needs ARPACK, and the library was built without it "
                          "(Debian: libarpack2-dev); use DAE_MODES_DENSE (%d differential "
                          "unknowns)",
                          c->M->d);
#else
    dae_modes *M = c->M;
    const dae_modes_options *o = c->o;
    int nev = o->nev, auto_sigma = !(o->sigma > 0), st = BG_OK;
    double sigma = auto_sigma ? 1.0 : o->sigma;
    int cap = 2 * nev + 2;
    found *f = calloc((size_t)cap, sizeof *f);
    if (!f) return bg_error_raise(c->err, BG_ERR_MEMORY, "dae_modes_compute", "out of memory");
    int nf = 0;
    refiner R;
    if (refiner_init(c, &R) != BG_OK) {
        free(f);
        return bg_error_raise(c->err, BG_ERR_MEMORY, "dae_modes_compute", "out of memory");
    }
    if (!auto_sigma) { /* a window around the frequency sigma (complex shift) */
        st = arpack_window(c, &R, sigma, nev, f, cap, &nf);
        nev = nf;
    }
    for (int round = 0; auto_sigma && round < 6; round++) {
        for (int k = 0; k < nf; k++)
            free(f[k].zr), free(f[k].zi);
        nf = 0;
        if ((st = mode_factor_shift(c, &sigma)) != BG_OK) break;
        int iters = 0;
        st = arpack_run(c, sigma, 2 * nev, f, cap, &nf, &iters);
        if (st != BG_OK && st != DAE_CONV_FAIL) break;
        if (!auto_sigma || nf == 0) break;
        /* the lowest nev: sigma^2 <= |s_1| |s_nev| */
        double lo = INFINITY, w[256];
        int nw = 0;
        for (int k = 0; k < nf && nw < 256; k++)
            w[nw++] = cabs(f[k].s);
        for (int a = 1; a < nw; a++) /* sort */
            for (int b = a; b > 0 && w[b - 1] > w[b]; b--) {
                double t = w[b];
                w[b] = w[b - 1];
                w[b - 1] = t;
            }
        lo = w[0];
        double hi = w[(nw < nev ? nw : nev) - 1];
        if (sigma * sigma <= 0.9 * lo * hi) break;
        sigma = 0.5 * sqrt(lo * hi);
    }
    M->sigma = sigma;
    int keep = st == BG_OK || st == DAE_CONV_FAIL;
    if (keep && nf > 0) { /* accurate eigenvalues: Rayleigh-quotient iteration per mode */
        {
            for (int k = 0; k < nf; k++) {
                double complex sk = f[k].s;
                if (refine_mode(c, &R, &sk, f[k].zr, f[k].zi) == 0) {
                    if (cimag(sk) < 0) { /* the conjugate, with its vector */
                        sk = conj(sk);
                        for (int i = 0; i < M->n; i++)
                            f[k].zi[i] = -f[k].zi[i];
                    }
                    f[k].s = sk;
                    f[k].res = mode_pencil_residual(c, sk, f[k].zr, f[k].zi);
                }
            }
        }
    }
    refiner_free(&R);
    /* the same mode found twice (copies converge to one eigenvalue and vector when refined):
     * visited by increasing residual, a mode already among the kept ones goes; the independent
     * eigenvectors of a repeated eigenvalue all stay (mode_known) */
    char *kept = calloc((size_t)(nf > 0 ? nf : 1), 1);
    if (!kept) st = bg_error_raise(c->err, BG_ERR_MEMORY, "dae_modes_compute", "out of memory");
    for (int pass = 0; kept && pass < nf; pass++) {
        int k = -1;
        for (int j = 0; j < nf; j++)
            if (f[j].zr && !kept[j] && (k < 0 || f[j].res < f[k].res || isnan(f[k].res))) k = j;
        if (k < 0) break;
        int dup = mode_known(M, f, nf, kept, f[k].s, f[k].zr, f[k].zi);
        if (dup < 0) {
            st = bg_error_raise(c->err, BG_ERR_MEMORY, "dae_modes_compute", "out of memory");
            break;
        }
        if (dup) {
            free(f[k].zr), free(f[k].zi);
            f[k].zr = f[k].zi = NULL;
            f[k].s = INFINITY;
        } else {
            kept[k] = 1;
        }
    }
    free(kept);
    keep = keep && (st == BG_OK || st == DAE_CONV_FAIL);
    /* keep the nev lowest (auto) or all found (window) */
    for (int k = 0; keep && k < nf; k++) {
        if (!f[k].zr) continue;
        int rank = 0;
        for (int j = 0; j < nf; j++)
            if (cabs(f[j].s) < cabs(f[k].s) || (cabs(f[j].s) == cabs(f[k].s) && j < k)) rank++;
        if (auto_sigma && rank >= nev) continue;
        int e = mode_add(M, creal(f[k].s), cimag(f[k].s), DAE_MODE_ELASTIC, NAN, f[k].zr, f[k].zi,
                         f[k].res);
        if (e != BG_OK) {
            st = bg_error_raise(c->err, e, "dae_modes_compute", "out of memory");
            break;
        }
    }
    if (st == DAE_CONV_FAIL)
        bg_error_raise(c->err, st, "dae_modes_compute",
                       "ARPACK did not converge within %d restarts: %d modes returned", o->maxiter,
                       M->nmodes);
    for (int k = 0; k < nf; k++)
        free(f[k].zr), free(f[k].zi);
    free(f);
    return st;
#endif
}
