/* Unit tests of bg_linsol: KLU and dense LU against an independent LAPACK solve, large KLU
 * systems by their residual, several right-hand sides, refactorization statistics, singular
 * matrices, the fallback from a failed refactorization, pattern mismatches, and the CHOLMOD
 * (A A^T + beta I) solver against a dense Cholesky of the explicitly formed product. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bg_linsol.h"
#include "tap.h"
#include "testutil.h"

/* LAPACK (Fortran interface; the trailing size_t is the hidden length of character arguments). */
void dgetrf_(const int *m, const int *n, double *a, const int *lda, int *ipiv, int *info);
void dgetrs_(const char *trans, const int *n, const int *nrhs, const double *a, const int *lda,
             const int *ipiv, double *b, const int *ldb, int *info, size_t ltrans);
void dpotrf_(const char *uplo, const int *n, double *a, const int *lda, int *info, size_t luplo);
void dpotrs_(const char *uplo, const int *n, const int *nrhs, const double *a, const int *lda,
             double *b, const int *ldb, int *info, size_t luplo);

/* ---- helpers ---- */

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

/* A random n x n matrix, strictly diagonally dominant by rows and by columns (so well
 * conditioned). Column j holds the diagonal and about per_col other entries: rows anywhere if
 * band == 0, else within j-band .. j+band plus, with probability longp, one anywhere. */
static sp_csc *gen_dd(tap_rng *r, int n, int per_col, int band, double longp)
{
    int cap = n * (per_col + 2) + 1, nnz = 0, j, k, p;
    int *colptr = malloc(sizeof(int) * (n + 1)), *rowind = malloc(sizeof(int) * cap);
    int *stamp = malloc(sizeof(int) * n);
    double *val = malloc(sizeof(double) * cap);
    double *rabs = calloc(n, sizeof(double)), *cabs = calloc(n, sizeof(double));
    sp_csc *A = NULL;
    for (k = 0; k < n; k++)
        stamp[k] = -1;
    for (j = 0; j < n; j++) {
        int start = nnz;
        colptr[j] = nnz;
        stamp[j] = j;
        rowind[nnz++] = j;
        for (k = 0; k < per_col + 1; k++) {
            int i;
            if (k == per_col) {
                if (!(band > 0 && tap_rng_unif(r) < longp)) continue;
                i = tap_rng_int(r, n);
            } else if (band > 0) {
                i = j - band + tap_rng_int(r, 2 * band + 1);
                if (i < 0 || i >= n) continue;
            } else {
                i = tap_rng_int(r, n);
            }
            if (stamp[i] == j) continue;
            stamp[i] = j;
            rowind[nnz++] = i;
        }
        qsort(rowind + start, (size_t)(nnz - start), sizeof(int), cmp_int);
        for (p = start; p < nnz; p++) {
            int i = rowind[p];
            if (i == j) continue;
            val[p] = tap_rng_range(r, -1.0, 1.0);
            rabs[i] += fabs(val[p]);
            cabs[j] += fabs(val[p]);
        }
    }
    colptr[n] = nnz;
    for (j = 0; j < n; j++)
        for (p = colptr[j]; p < colptr[j + 1]; p++)
            if (rowind[p] == j)
                val[p] = (rabs[j] + cabs[j] + tap_rng_range(r, 0.5, 1.5)) *
                         (tap_rng_unif(r) < 0.5 ? -1.0 : 1.0);
    A = sp_csc_alloc(n, n, nnz);
    if (A) {
        memcpy(A->colptr, colptr, sizeof(int) * (n + 1));
        memcpy(A->rowind, rowind, sizeof(int) * nnz);
        memcpy(A->val, val, sizeof(double) * nnz);
        A->nnz = nnz;
    }
    free(colptr);
    free(rowind);
    free(stamp);
    free(val);
    free(rabs);
    free(cabs);
    return A;
}

static double *my_dense(const sp_csc *A)
{
    double *D = malloc(((size_t)A->nrow * A->ncol + 1) * sizeof(double));
    if (D) tu_dense(A, D);
    return D;
}

/* Solves A X = B (n x nrhs) in place with LAPACK dgetrf/dgetrs; returns info. */
static int lapack_solve(const sp_csc *A, double *B, int nrhs)
{
    int n = A->nrow, info = 0;
    double *D = my_dense(A);
    int *ipiv = malloc(sizeof(int) * n);
    dgetrf_(&n, &n, D, &n, ipiv, &info);
    if (info == 0) dgetrs_("N", &n, &nrhs, D, &n, ipiv, B, &n, &info, 1);
    free(D);
    free(ipiv);
    return info;
}

static double rel_err(const double *x, const double *ref, int n)
{
    double num = 0.0, den = 0.0;
    int i;
    for (i = 0; i < n; i++) {
        num += (x[i] - ref[i]) * (x[i] - ref[i]);
        den += ref[i] * ref[i];
    }
    return sqrt(num) / (sqrt(den) > 0 ? sqrt(den) : 1.0);
}

/* ||A x - b||_inf / (||A||_inf ||x||_inf), computed here. */
static double rel_residual(const sp_csc *A, const double *x, const double *b)
{
    int n = A->nrow, j, p, i;
    double *rr = calloc(n, sizeof(double)), *ra = calloc(n, sizeof(double));
    double rmax = 0.0, amax = 0.0, xmax = 0.0;
    for (j = 0; j < A->ncol; j++) {
        if (fabs(x[j]) > xmax) xmax = fabs(x[j]);
        for (p = A->colptr[j]; p < A->colptr[j + 1]; p++) {
            rr[A->rowind[p]] += A->val[p] * x[j];
            ra[A->rowind[p]] += fabs(A->val[p]);
        }
    }
    for (i = 0; i < n; i++) {
        if (fabs(rr[i] - b[i]) > rmax) rmax = fabs(rr[i] - b[i]);
        if (ra[i] > amax) amax = ra[i];
    }
    free(rr);
    free(ra);
    if (isnan(rmax)) return NAN;
    return rmax / (amax * xmax > 0 ? amax * xmax : 1.0);
}

static const char *kind_name(ls_kind k)
{
    return k == LS_KLU ? "KLU" : "dense";
}

/* ---- KLU and dense against LAPACK ---- */

static void test_vs_lapack(tap_rng *r, int n, int nrhs, int band)
{
    sp_csc *A = gen_dd(r, n, 4, band, 0.2);
    size_t nb = (size_t)n * nrhs;
    double *b = malloc(sizeof(double) * nb), *xref = malloc(sizeof(double) * nb);
    double *x[2] = {malloc(sizeof(double) * nb), malloc(sizeof(double) * nb)};
    int k, q, got[2] = {0, 0};
    bg_error err;

    if (!A) {
        tap_ok(0, "gen n=%d", n);
        goto out;
    }
    for (k = 0; k < (int)nb; k++)
        b[k] = xref[k] = tap_rng_range(r, -1.0, 1.0);
    if (!tap_ok(lapack_solve(A, xref, nrhs) == 0, "n=%d: LAPACK reference", n)) goto out;
    for (k = 0; k < 2; k++) {
        ls_kind kind = k ? LS_DENSE : LS_KLU;
        ls_solver *s;
        const ls_stats *st;
        int rc;
        bg_error_clear(&err);
        err.handler = NULL;
        s = ls_create(kind, A, &err);
        if (!tap_ok(s != NULL, "%s n=%d: ls_create", kind_name(kind), n)) {
            tap_diag("error: %s", err.message);
            continue;
        }
        tap_ok(ls_get_kind(s) == kind, "%s n=%d: ls_get_kind", kind_name(kind), n);
        memcpy(x[k], b, sizeof(double) * nb);
        tap_ok(ls_solve(s, x[k], nrhs) < 0, "%s n=%d: ls_solve before any factorization fails",
               kind_name(kind), n);
        rc = ls_factor(s, A);
        tap_ok(rc == BG_OK, "%s n=%d: ls_factor returns BG_OK (got %d)", kind_name(kind), n, rc);
        tap_ok(ls_singular_col(s) == -1, "%s n=%d: ls_singular_col == -1 after success",
               kind_name(kind), n);
        memcpy(x[k], b, sizeof(double) * nb);
        rc = ls_solve(s, x[k], nrhs);
        tap_ok(rc == BG_OK, "%s n=%d: ls_solve(nrhs=%d) returns BG_OK", kind_name(kind), n, nrhs);
        for (q = 0; q < nrhs; q++) {
            double e = rel_err(x[k] + (size_t)q * n, xref + (size_t)q * n, n);
            if (!tap_ok(e <= 1e-12,
                        "%s n=%d rhs %d/%d: ||x - x_lapack|| / ||x_lapack|| = %.2e <= 1e-12",
                        kind_name(kind), n, q + 1, nrhs, e))
                tap_diag("x[0] = %.17g, lapack %.17g", x[k][(size_t)q * n], xref[(size_t)q * n]);
            tap_ok(rel_residual(A, x[k] + (size_t)q * n, b + (size_t)q * n) < 1e-14,
                   "%s n=%d rhs %d/%d: relative residual < 1e-14", kind_name(kind), n, q + 1, nrhs);
        }
        st = ls_get_stats(s);
        if (kind == LS_KLU)
            tap_ok(st->symbolic == 1 && st->factor == 1 && st->refactor == 0 && st->fallback == 0,
                   "KLU n=%d: stats symbolic %ld factor %ld refactor %ld fallback %ld == 1 1 0 0",
                   n, st->symbolic, st->factor, st->refactor, st->fallback);
        tap_ok(st->solve == nrhs, "%s n=%d: stats.solve == %d (got %ld)", kind_name(kind), n, nrhs,
               st->solve);
        tap_ok(st->rcond > 0.0 && st->rcond <= 1.0, "%s n=%d: stats.rcond %.3g in (0,1]",
               kind_name(kind), n, st->rcond);
        got[k] = 1;
        ls_free(&s);
        tap_ok(s == NULL, "ls_free sets NULL");
    }
    if (got[0] && got[1])
        for (q = 0; q < nrhs; q++) {
            double e = rel_err(x[0] + (size_t)q * n, x[1] + (size_t)q * n, n);
            tap_ok(e <= 1e-12, "n=%d rhs %d: ||x_klu - x_dense|| / ||x_dense|| = %.2e <= 1e-12", n,
                   q + 1, e);
        }
out:
    sp_csc_free(&A);
    free(b);
    free(xref);
    free(x[0]);
    free(x[1]);
}

/* ---- a large KLU system: residual and known solution ---- */

static void test_klu_large(tap_rng *r, int n)
{
    sp_csc *A = gen_dd(r, n, 5, 40, 0.05);
    int nrhs = 3, k, q, rc;
    size_t nb = (size_t)n * nrhs;
    double *xt = malloc(sizeof(double) * nb), *b = calloc(nb, sizeof(double));
    double *x = malloc(sizeof(double) * nb);
    ls_solver *s = NULL;
    bg_error err;

    if (!A) goto out;
    for (k = 0; k < (int)nb; k++)
        xt[k] = tap_rng_range(r, -1.0, 1.0);
    for (q = 0; q < nrhs; q++) {
        int j, p;
        for (j = 0; j < n; j++)
            for (p = A->colptr[j]; p < A->colptr[j + 1]; p++)
                b[A->rowind[p] + (size_t)q * n] += A->val[p] * xt[j + (size_t)q * n];
    }
    bg_error_clear(&err);
    err.handler = NULL;
    s = ls_create(LS_KLU, A, &err);
    if (!tap_ok(s != NULL, "KLU n=%d (nnz %d): ls_create", n, A->nnz)) goto out;
    rc = ls_factor(s, A);
    tap_ok(rc == BG_OK, "KLU n=%d: ls_factor BG_OK (got %d)", n, rc);
    memcpy(x, b, sizeof(double) * nb);
    rc = ls_solve(s, x, nrhs);
    tap_ok(rc == BG_OK, "KLU n=%d: ls_solve BG_OK", n);
    for (q = 0; q < nrhs; q++) {
        double res = rel_residual(A, x + (size_t)q * n, b + (size_t)q * n);
        double e = rel_err(x + (size_t)q * n, xt + (size_t)q * n, n);
        tap_ok(res < 1e-12, "KLU n=%d rhs %d: ||Ax-b|| / (||A|| ||x||) = %.2e < 1e-12", n, q + 1,
               res);
        tap_ok(e < 1e-10, "KLU n=%d rhs %d: ||x - x_true|| / ||x_true|| = %.2e < 1e-10", n, q + 1,
               e);
    }
    /* Refactor with new values on the same pattern. */
    for (k = 0; k < A->nnz; k++)
        A->val[k] *= (k % 7 == 0) ? 1.25 : 0.9;
    rc = ls_factor(s, A);
    memcpy(x, b, sizeof(double) * (size_t)n);
    if (rc == BG_OK) rc = ls_solve(s, x, 1);
    tap_ok(rc == BG_OK && rel_residual(A, x, b) < 1e-12 && ls_get_stats(s)->refactor == 1,
           "KLU n=%d: refactorization with new values solves (residual %.2e)", n,
           rel_residual(A, x, b));
out:
    ls_free(&s);
    sp_csc_free(&A);
    free(xt);
    free(b);
    free(x);
}

/* ---- refactorization reuses the analysis ---- */

static void test_refactor(tap_rng *r, int n)
{
    sp_csc *A = gen_dd(r, n, 4, 0, 0.0), *A2 = NULL, *A3 = NULL;
    double *b = malloc(sizeof(double) * n), *x = malloc(sizeof(double) * n);
    double *xref = malloc(sizeof(double) * n);
    ls_solver *s = NULL;
    const ls_stats *st;
    int k, rc;

    if (!A) goto out;
    A2 = sp_csc_copy(A);
    A3 = sp_csc_copy(A);
    /* New values, same pattern, still diagonally dominant: off-diagonals shrink, the diagonal
     * flips sign in every third column. */
    for (k = 0; k < n; k++) {
        int p;
        for (p = A->colptr[k]; p < A->colptr[k + 1]; p++) {
            if (A->rowind[p] == k) {
                A2->val[p] = (k % 3 == 0) ? -A->val[p] : 1.1 * A->val[p];
                A3->val[p] = 0.8 * A->val[p];
            } else {
                A2->val[p] = tap_rng_range(r, -0.9, 0.9) * fabs(A->val[p]);
                A3->val[p] = -0.5 * A->val[p];
            }
        }
    }
    for (k = 0; k < n; k++)
        b[k] = tap_rng_range(r, -1, 1);
    s = ls_create(LS_KLU, A, NULL);
    if (!tap_ok(s != NULL, "refactor n=%d: ls_create", n)) goto out;
    st = ls_get_stats(s);
    tap_ok(st->symbolic == 1 && st->factor == 0 && st->refactor == 0,
           "refactor n=%d: after create: symbolic 1, factor 0 (got %ld %ld %ld)", n, st->symbolic,
           st->factor, st->refactor);
    tap_ok(ls_factor(s, A) == BG_OK, "refactor n=%d: first factor", n);
    rc = ls_factor(s, A2);
    tap_ok(rc == BG_OK, "refactor n=%d: second factor (new values) BG_OK (got %d)", n, rc);
    st = ls_get_stats(s);
    tap_ok(st->symbolic == 1 && st->factor == 1 && st->refactor == 1 && st->fallback == 0,
           "refactor n=%d: stats symbolic %ld factor %ld refactor %ld fallback %ld == 1 1 1 0", n,
           st->symbolic, st->factor, st->refactor, st->fallback);
    memcpy(x, b, sizeof(double) * n);
    memcpy(xref, b, sizeof(double) * n);
    ls_solve(s, x, 1);
    lapack_solve(A2, xref, 1);
    tap_ok(rel_err(x, xref, n) <= 1e-12, "refactor n=%d: solution after refactor right (%.2e)", n,
           rel_err(x, xref, n));
    /* Forced full factorization. */
    ls_force_full(s);
    rc = ls_factor(s, A3);
    st = ls_get_stats(s);
    tap_ok(rc == BG_OK && st->symbolic == 1 && st->factor == 2 && st->refactor == 1,
           "refactor n=%d: ls_force_full -> factor 2, refactor 1 (got %ld %ld)", n, st->factor,
           st->refactor);
    memcpy(x, b, sizeof(double) * n);
    memcpy(xref, b, sizeof(double) * n);
    ls_solve(s, x, 1);
    lapack_solve(A3, xref, 1);
    tap_ok(rel_err(x, xref, n) <= 1e-12, "refactor n=%d: solution after forced full factor right",
           n);
    /* And back to refactorization. */
    rc = ls_factor(s, A);
    st = ls_get_stats(s);
    tap_ok(rc == BG_OK && st->factor == 2 && st->refactor == 2 && st->symbolic == 1,
           "refactor n=%d: next factor is a refactorization again (factor %ld refactor %ld)", n,
           st->factor, st->refactor);
    memcpy(x, b, sizeof(double) * n);
    memcpy(xref, b, sizeof(double) * n);
    ls_solve(s, x, 1);
    lapack_solve(A, xref, 1);
    tap_ok(rel_err(x, xref, n) <= 1e-12, "refactor n=%d: solution after second refactor right", n);
    ls_free(&s);

    /* The dense solver factors new values too. */
    s = ls_create(LS_DENSE, A, NULL);
    if (tap_ok(s != NULL, "refactor dense n=%d: create", n)) {
        rc = ls_factor(s, A);
        if (rc == BG_OK) rc = ls_factor(s, A2);
        memcpy(x, b, sizeof(double) * n);
        memcpy(xref, b, sizeof(double) * n);
        if (rc == BG_OK) rc = ls_solve(s, x, 1);
        lapack_solve(A2, xref, 1);
        tap_ok(rc == BG_OK && rel_err(x, xref, n) <= 1e-12,
               "refactor dense n=%d: second factorization with new values solves", n);
    }
out:
    ls_free(&s);
    sp_csc_free(&A);
    sp_csc_free(&A2);
    sp_csc_free(&A3);
    free(b);
    free(x);
    free(xref);
}

/* ---- singular matrices ---- */

static void test_singular(tap_rng *r)
{
    enum { N = 20, ZC = 7 };
    double D[N * N], Dz[N * N], Dd[N * N], b[N], x[N], xref[N];
    unsigned char mask[N * N];
    sp_csc *A, *Az, *Ad, *Ae;
    int i, j, k;

    /* A random dense-ish diagonally dominant N x N matrix. */
    memset(D, 0, sizeof D);
    for (j = 0; j < N; j++) {
        for (i = 0; i < N; i++)
            if (i != j && tap_rng_unif(r) < 0.3) D[i + j * N] = tap_rng_range(r, -1, 1);
    }
    for (i = 0; i < N; i++) {
        double s = 0.0;
        for (j = 0; j < N; j++)
            s += fabs(D[i + j * N]) + fabs(D[j + i * N]);
        D[i + i * N] = s + 1.0;
    }
    for (k = 0; k < N * N; k++)
        mask[k] = D[k] != 0.0;
    for (k = 0; k < N; k++)
        mask[k + ZC * N] = 1; /* column 7 full in the pattern */
    A = tu_csc_from_mask(N, N, mask, D);
    /* Same pattern, column 7 numerically zero. */
    memcpy(Dz, D, sizeof D);
    for (i = 0; i < N; i++)
        Dz[i + ZC * N] = 0.0;
    Az = tu_csc_from_mask(N, N, mask, Dz);
    /* Column 7 structurally empty. */
    Ae = tu_csc_from_mask(N, N, NULL, Dz);
    /* Column 7 equal to column 3: rows 3 and 7 and columns 3 and 7 hold only the block
     * [[2, 2], [-4, -4]] (exact arithmetic: the dependent pivot is exactly zero). */
    memcpy(Dd, D, sizeof D);
    for (k = 0; k < N; k++) {
        Dd[3 + k * N] = Dd[7 + k * N] = 0.0;
        Dd[k + 3 * N] = Dd[k + 7 * N] = 0.0;
    }
    Dd[3 + 3 * N] = Dd[3 + 7 * N] = 2.0;
    Dd[7 + 3 * N] = Dd[7 + 7 * N] = -4.0;
    Ad = tu_csc_from_mask(N, N, NULL, Dd);
    for (i = 0; i < N; i++)
        b[i] = tap_rng_range(r, -1, 1);

    if (!A || !Az || !Ad || !Ae) {
        tap_ok(0, "singular: alloc");
        goto out;
    }
    for (k = 0; k < 2; k++) {
        ls_kind kind = k ? LS_DENSE : LS_KLU;
        const char *kn = kind_name(kind);
        ls_solver *s = ls_create(kind, Az, NULL);
        bg_error *e;
        int rc, col;
        if (!tap_ok(s != NULL, "singular %s: create", kn)) continue;
        /* Fresh solver, zero column. */
        rc = ls_factor(s, Az);
        tap_ok(rc == BG_ERR_SINGULAR, "singular %s: zero column 7 -> BG_ERR_SINGULAR (got %d)", kn,
               rc);
        col = ls_singular_col(s);
        tap_ok(col == ZC, "singular %s: ls_singular_col == 7 (got %d)", kn, col);
        e = ls_get_error(s);
        tap_ok(e != NULL && e->message[0] != '\0' && e->status == BG_ERR_SINGULAR,
               "singular %s: error message set (\"%s\")", kn, e ? e->message : "");
        memcpy(x, b, sizeof b);
        tap_ok(ls_solve(s, x, 1) < 0, "singular %s: ls_solve after a singular factorization fails",
               kn);
        /* Recovery: a good matrix of the same pattern. */
        rc = ls_factor(s, A);
        memcpy(x, b, sizeof b);
        memcpy(xref, b, sizeof b);
        if (rc == BG_OK) rc = ls_solve(s, x, 1);
        lapack_solve(A, xref, 1);
        tap_ok(rc == BG_OK && rel_err(x, xref, N) <= 1e-12,
               "singular %s: factor of a good matrix after a singular one solves", kn);
        /* Zero column met by a refactorization. */
        rc = ls_factor(s, Az);
        tap_ok(
            rc == BG_ERR_SINGULAR && ls_singular_col(s) == ZC,
            "singular %s: zero column after a good factor -> BG_ERR_SINGULAR, col 7 (got %d, %d)",
            kn, rc, ls_singular_col(s));
        ls_free(&s);

        /* Column 7 == column 3. */
        s = ls_create(kind, Ad, NULL);
        if (tap_ok(s != NULL, "singular %s: create (equal columns)", kn)) {
            rc = ls_factor(s, Ad);
            col = ls_singular_col(s);
            tap_ok(rc == BG_ERR_SINGULAR,
                   "singular %s: column 7 == column 3 -> BG_ERR_SINGULAR (got %d)", kn, rc);
            tap_ok(col == 3 || col == 7, "singular %s: equal columns: singular col %d is 3 or 7",
                   kn, col);
            e = ls_get_error(s);
            tap_ok(e && e->message[0] != '\0', "singular %s: equal columns: message set", kn);
        }
        ls_free(&s);

        /* Structurally empty column 7: either refused at creation (with a reason) or found
         * singular at column 7. */
        {
            bg_error err;
            bg_error_clear(&err);
            err.handler = NULL;
            s = ls_create(kind, Ae, &err);
            if (s) {
                rc = ls_factor(s, Ae);
                tap_ok(rc == BG_ERR_SINGULAR && ls_singular_col(s) == ZC,
                       "singular %s: empty column 7 -> BG_ERR_SINGULAR at 7 (got %d, %d)", kn, rc,
                       ls_singular_col(s));
            } else {
                tap_ok(err.message[0] != '\0' && err.status < 0,
                       "singular %s: empty column 7 refused by ls_create with a reason", kn);
            }
            ls_free(&s);
        }
    }
out:
    sp_csc_free(&A);
    sp_csc_free(&Az);
    sp_csc_free(&Ad);
    sp_csc_free(&Ae);
}

/* ---- a refactorization that hits a zero pivot falls back to a full factorization ---- */

static void test_fallback(void)
{
    enum { N = 10 };
    double D1[N * N], D2[N * N], b[N], x[N], want[N];
    unsigned char mask[N * N];
    sp_csc *A1, *A2;
    ls_solver *s;
    const ls_stats *st;
    int i, rc;

    memset(D1, 0, sizeof D1);
    memset(mask, 0, sizeof mask);
    for (i = 2; i < N; i++) {
        D1[i + i * N] = 1.0 + i;
        mask[i + i * N] = 1;
    }
    mask[0] = mask[1] = mask[N] = mask[N + 1] = 1;
    memcpy(D2, D1, sizeof D1);
    /* Leading block: [[1, .5], [.5, 1]] is factored with diagonal pivots whatever the column
     * order; [[0, 1], [1, 0]] makes those pivots exactly zero. */
    D1[0] = 1.0;
    D1[1] = 0.5;
    D1[N] = 0.5;
    D1[N + 1] = 1.0;
    D2[0] = 0.0;
    D2[1] = 1.0;
    D2[N] = 1.0;
    D2[N + 1] = 0.0;
    A1 = tu_csc_from_mask(N, N, mask, D1);
    A2 = tu_csc_from_mask(N, N, mask, D2);
    for (i = 0; i < N; i++)
        b[i] = i + 1.0;
    want[0] = b[1];
    want[1] = b[0];
    for (i = 2; i < N; i++)
        want[i] = b[i] / (1.0 + i);

    s = (A1 && A2) ? ls_create(LS_KLU, A1, NULL) : NULL;
    if (!tap_ok(s != NULL, "fallback: create")) goto out;
    rc = ls_factor(s, A1);
    tap_ok(rc == BG_OK, "fallback: first factor BG_OK");
    rc = ls_factor(s, A2);
    st = ls_get_stats(s);
    tap_ok(rc == BG_OK, "fallback: refactor with a zero pivot still returns BG_OK (got %d)", rc);
    tap_ok(st->fallback == 1, "fallback: stats.fallback == 1 (got %ld)", st->fallback);
    tap_ok(st->factor == 2,
           "fallback: the fallback is a full factorization: stats.factor == 2 (got %ld)",
           st->factor);
    tap_ok(st->symbolic == 1, "fallback: no new symbolic analysis (got %ld)", st->symbolic);
    memcpy(x, b, sizeof b);
    rc = ls_solve(s, x, 1);
    tap_ok(rc == BG_OK && rel_err(x, want, N) <= 1e-15, "fallback: solution right (err %.2e)",
           rel_err(x, want, N));
out:
    ls_free(&s);
    sp_csc_free(&A1);
    sp_csc_free(&A2);
}

/* ---- rcond_min triggers a full factorization; rcond estimates ---- */

static void test_rcond(void)
{
    const double dl = 1e-6;
    double D[4] = {1.0, 1.0, 1.0, 1.0 + dl}, b[2] = {1.0, -2.0}, x[2], want[2];
    sp_csc *A = tu_csc_from_mask(2, 2, NULL, D);
    ls_solver *s = A ? ls_create(LS_KLU, A, NULL) : NULL;
    const ls_stats *st;
    int rc;
    double rc_true;

    /* x = A^-1 b with A^-1 = [[1+dl, -1], [-1, 1]] / dl. */
    want[0] = ((1.0 + dl) * b[0] - b[1]) / dl;
    want[1] = (-b[0] + b[1]) / dl;
    if (!tap_ok(s != NULL, "rcond: create")) goto out;
    ls_factor(s, A);
    rc = ls_factor(s, A);
    st = ls_get_stats(s);
    tap_ok(rc == BG_OK && st->refactor == 1 && st->fallback == 0,
           "rcond: min|Ukk|/max|Ukk| ~ 1e-6 above the default rcond_min: no fallback");
    tap_ok(st->rcond > 1e-7 && st->rcond < 1e-5, "rcond: KLU rcond %.3g ~ 1e-6", st->rcond);
    ls_set_rcond_min(s, 1e-3);
    rc = ls_factor(s, A);
    st = ls_get_stats(s);
    tap_ok(rc == BG_OK && st->fallback == 1 && st->factor == 2,
           "rcond: rcond_min 1e-3 turns the refactorization into a fallback (rc %d, fallback %ld, "
           "factor %ld)",
           rc, st->fallback, st->factor);
    memcpy(x, b, sizeof b);
    ls_solve(s, x, 1);
    tap_ok(rel_err(x, want, 2) < 1e-8, "rcond: ill-conditioned 2x2 solved (err %.2e)",
           rel_err(x, want, 2));
    ls_free(&s);

    s = ls_create(LS_DENSE, A, NULL);
    if (tap_ok(s != NULL, "rcond dense: create")) {
        rc = ls_factor(s, A);
        /* 1-norm: ||A|| = 2 + dl, ||A^-1|| = (2 + dl) / dl. */
        rc_true = dl / ((2.0 + dl) * (2.0 + dl));
        tap_ok(rc == BG_OK, "rcond dense: factor BG_OK");
        tap_close(ls_get_stats(s)->rcond, rc_true, 0.5, 0.0, "rcond dense: dgecon estimate ~ %.3g",
                  rc_true);
        memcpy(x, b, sizeof b);
        ls_solve(s, x, 1);
        tap_ok(rel_err(x, want, 2) < 1e-8, "rcond dense: ill-conditioned 2x2 solved");
    }
out:
    ls_free(&s);
    sp_csc_free(&A);
}

/* ---- the fallback is relative to the estimate of the last full factorization ---- */

static void test_refactor_drop(void)
{
    /* A(e) = [[1, 1], [1, 1 + e]]: min|Ukk|/max|Ukk| ~ e with diagonal pivots */
    double D[4] = {1.0, 1.0, 1.0, 1.0 + 1e-14}, b[2] = {1.0, -2.0}, x[2];
    sp_csc *A = tu_csc_from_mask(2, 2, NULL, D);
    ls_solver *s = A ? ls_create(LS_KLU, A, NULL) : NULL;
    if (!tap_ok(s != NULL, "refactor drop: create")) goto out;
    /* ill-conditioned by nature (an index-2 or stiff system): the same matrix again refactors
     * without fresh pivots, even with an estimate of 1e-14 */
    ls_factor(s, A);
    ls_factor(s, A);
    const ls_stats *st = ls_get_stats(s);
    tap_ok(st->factor == 1 && st->refactor == 1 && st->fallback == 0 && st->rcond < 1e-13,
           "refactor drop: a matrix with estimate %.3g refactors without a fallback (factor %ld, "
           "refactor %ld, fallback %ld)",
           st->rcond, st->factor, st->refactor, st->fallback);
    /* well conditioned, then 1e-8 of that with the same pivots: stale, pivot afresh */
    A->val[3] = 3.0; /* [[1, 1], [1, 3]]: pivots 1 and 2, estimate 1/2 */
    ls_force_full(s);
    ls_factor(s, A);
    A->val[3] = 1.0 + 1e-8;
    ls_factor(s, A);
    st = ls_get_stats(s);
    tap_ok(st->fallback == 1 && st->factor == 3,
           "refactor drop: an estimate 1e-8 of the last full factorization's falls back (fallback "
           "%ld, factor %ld)",
           st->fallback, st->factor);
    /* a drop by 1e-2 keeps the refactorization */
    A->val[3] = 1.0 + 1e-6;
    ls_factor(s, A);
    st = ls_get_stats(s);
    tap_ok(st->fallback == 1 && st->refactor == 3,
           "refactor drop: an estimate 1e-2 of the last full one's keeps the refactorization "
           "(fallback %ld, refactor %ld)",
           st->fallback, st->refactor);
    memcpy(x, b, sizeof b);
    ls_solve(s, x, 1);
    /* A^-1 b with e = 1e-6: x1 = ((1 + e) b0 - b1) / e, x2 = (b1 - b0) / e */
    tap_close(x[1], (b[1] - b[0]) / 1e-6, 1e-8, 0, "refactor drop: solution after the refactor");
out:
    ls_free(&s);
    sp_csc_free(&A);
}

/* ---- pattern mismatch ---- */

static void test_pattern(tap_rng *r)
{
    int n = 30, k, p, j;
    sp_csc *A = gen_dd(r, n, 3, 0, 0.0), *Bm = NULL, *C = gen_dd(r, n + 1, 3, 0, 0.0);
    sp_csc *Ex = NULL;
    double *D;
    unsigned char *mask;

    if (!A || !C) goto out0;
    /* Bm: one off-diagonal entry moved to another row (same nnz). */
    Bm = sp_csc_copy(A);
    for (j = 0; j < n; j++) {
        int moved = 0;
        for (p = Bm->colptr[j]; p < Bm->colptr[j + 1]; p++) {
            int nxt = p + 1 < Bm->colptr[j + 1] ? Bm->rowind[p + 1] : n;
            if (Bm->rowind[p] != j && Bm->rowind[p] + 1 < nxt && Bm->rowind[p] + 1 != j) {
                Bm->rowind[p]++;
                moved = 1;
                break;
            }
        }
        if (moved) break;
    }
    /* Ex: A plus one entry. */
    D = my_dense(A);
    mask = calloc((size_t)n * n, 1);
    for (k = 0; k < n * n; k++)
        mask[k] = D[k] != 0.0;
    for (k = 0; k < n * n; k++)
        if (!mask[k]) {
            mask[k] = 1;
            D[k] = 1e-3;
            break;
        }
    Ex = tu_csc_from_mask(n, n, mask, D);
    free(D);
    free(mask);

    for (k = 0; k < 2; k++) {
        ls_kind kind = k ? LS_DENSE : LS_KLU;
        const char *kn = kind_name(kind);
        ls_solver *s = ls_create(kind, A, NULL);
        int rc;
        if (!tap_ok(s != NULL, "pattern %s: create", kn)) continue;
        rc = ls_factor(s, Bm);
        tap_ok(rc == BG_ERR_PATTERN,
               "pattern %s: same nnz, one row moved -> BG_ERR_PATTERN (got %d)", kn, rc);
        tap_ok(ls_get_error(s)->message[0] != '\0', "pattern %s: message set", kn);
        rc = ls_factor(s, Ex);
        tap_ok(rc == BG_ERR_PATTERN, "pattern %s: one extra entry -> BG_ERR_PATTERN (got %d)", kn,
               rc);
        rc = ls_factor(s, C);
        tap_ok(rc == BG_ERR_PATTERN, "pattern %s: %dx%d for %dx%d -> BG_ERR_PATTERN (got %d)", kn,
               n + 1, n + 1, n, n, rc);
        rc = ls_factor(s, A);
        tap_ok(rc == BG_OK, "pattern %s: the right pattern still factors", kn);
        ls_free(&s);
    }
    {
        sp_csc *R = sp_csc_alloc(3, 4, 0);
        bg_error err;
        ls_solver *s;
        bg_error_clear(&err);
        err.handler = NULL;
        s = R ? ls_create(LS_KLU, R, &err) : NULL;
        tap_ok(s == NULL && err.status < 0 && err.message[0] != '\0',
               "ls_create KLU with a 3x4 pattern: NULL and a reason");
        ls_free(&s);
        bg_error_clear(&err);
        s = R ? ls_create(LS_DENSE, R, &err) : NULL;
        tap_ok(s == NULL && err.status < 0 && err.message[0] != '\0',
               "ls_create dense with a 3x4 pattern: NULL and a reason");
        ls_free(&s);
        sp_csc_free(&R);
    }
out0:
    sp_csc_free(&A);
    sp_csc_free(&Bm);
    sp_csc_free(&C);
    sp_csc_free(&Ex);
}

/* ---- NaN or Inf in the matrix ---- */

static void test_nonfinite(tap_rng *r)
{
    int n = 20, k, t;
    sp_csc *A = gen_dd(r, n, 3, 0, 0.0), *B = NULL;
    if (!A) return;
    for (k = 0; k < 2; k++) {
        ls_kind kind = k ? LS_DENSE : LS_KLU;
        const char *kn = kind_name(kind);
        ls_solver *s = ls_create(kind, A, NULL);
        if (!tap_ok(s != NULL, "nonfinite %s: create", kn)) continue;
        for (t = 0; t < 3; t++) {
            /* t = 0: NaN on a fresh solver; 1: +Inf after a good factorization; 2: -Inf. */
            int j = 11 + t, p, i, rc;
            char si[16], sj[16];
            const char *msg;
            sp_csc_free(&B);
            B = sp_csc_copy(A);
            p = B->colptr[j + 1] - 1; /* last off-diagonal entry of column j if any */
            if (B->rowind[p] == j && p > B->colptr[j]) p--;
            i = B->rowind[p];
            B->val[p] = t == 0 ? NAN : (t == 1 ? INFINITY : -INFINITY);
            if (t == 1) ls_factor(s, A);
            rc = ls_factor(s, B);
            msg = ls_get_error(s)->message;
            tap_ok(rc == BG_ERR_NONFINITE,
                   "nonfinite %s: %s at (%d,%d) -> BG_ERR_NONFINITE (got %d)", kn,
                   t == 0 ? "NaN" : (t == 1 ? "+Inf" : "-Inf"), i, j, rc);
            snprintf(si, sizeof si, "%d", i);
            snprintf(sj, sizeof sj, "%d", j);
            if (!tap_ok(strstr(msg, si) && strstr(msg, sj),
                        "nonfinite %s: message names row %d and column %d", kn, i, j))
                tap_diag("message: \"%s\"", msg);
        }
        tap_ok(ls_factor(s, A) == BG_OK, "nonfinite %s: a finite matrix factors afterwards", kn);
        ls_free(&s);
    }
    sp_csc_free(&A);
    sp_csc_free(&B);
}

/* ---- A A^T + beta I by CHOLMOD ---- */

/* Random m x n (m < n), full row rank: the leading m x m block is strictly diagonally dominant by
 * rows. */
static sp_csc *gen_wide(tap_rng *r, int m, int n, double density)
{
    double *D = calloc((size_t)m * n, sizeof(double));
    sp_csc *A;
    int i, j;
    for (j = 0; j < n; j++)
        for (i = 0; i < m; i++)
            if (i != j && tap_rng_unif(r) < density) D[i + (size_t)j * m] = tap_rng_range(r, -1, 1);
    for (i = 0; i < m; i++) {
        double s = 0.0;
        for (j = 0; j < m; j++)
            s += fabs(D[i + (size_t)j * m]);
        D[i + (size_t)i * m] = (s + tap_rng_range(r, 0.5, 1.5)) * (tap_rng_unif(r) < 0.5 ? -1 : 1);
    }
    A = tu_csc_from_mask(m, n, NULL, D);
    free(D);
    return A;
}

/* x = (A A^T + beta I)^-1 b by LAPACK on the explicitly formed product. Returns info. */
static int dense_aat_solve(const sp_csc *A, double beta, const double *b, double *x)
{
    int m = A->nrow, n = A->ncol, i, j, k, info = 0, one = 1;
    double *D = my_dense(A), *G = calloc((size_t)m * m, sizeof(double));
    for (j = 0; j < m; j++)
        for (i = 0; i < m; i++) {
            double s = 0.0;
            for (k = 0; k < n; k++)
                s += D[i + (size_t)k * m] * D[j + (size_t)k * m];
            G[i + (size_t)j * m] = s + (i == j ? beta : 0.0);
        }
    memcpy(x, b, sizeof(double) * m);
    dpotrf_("L", &m, G, &m, &info, 1);
    if (info == 0) dpotrs_("L", &m, &one, G, &m, x, &m, &info, 1);
    free(D);
    free(G);
    return info;
}

static void test_aat(tap_rng *r, int m, int n, double density)
{
    sp_csc *A = gen_wide(r, m, n, density), *A2 = NULL;
    double *b = malloc(sizeof(double) * m), *x = malloc(sizeof(double) * m);
    double *xref = malloc(sizeof(double) * m), *y = malloc(sizeof(double) * m);
    static const double betas[] = {0.0, 1e-3};
    aat_solver *s = NULL;
    bg_error err;
    int t, k, rc;

    if (!A) goto out;
    bg_error_clear(&err);
    err.handler = NULL;
    s = aat_create(A, &err);
    if (!tap_ok(s != NULL, "aat %dx%d: aat_create", m, n)) {
        tap_diag("error: %s", err.message);
        goto out;
    }
    tap_ok(aat_factor_count(s) == 0, "aat %dx%d: no factorization yet", m, n);
    for (k = 0; k < m; k++)
        b[k] = 1.0;
    tap_ok(aat_solve(s, b, x) < 0, "aat %dx%d: aat_solve before aat_factor fails", m, n);
    for (t = 0; t < 2; t++) {
        double beta = betas[t];
        for (k = 0; k < m; k++)
            b[k] = tap_rng_range(r, -1, 1);
        rc = aat_factor(s, A, beta);
        tap_ok(rc == BG_OK, "aat %dx%d beta=%g: aat_factor BG_OK (got %d)", m, n, beta, rc);
        tap_ok(aat_factor_count(s) == t + 1, "aat %dx%d beta=%g: factor count %ld", m, n, beta,
               aat_factor_count(s));
        rc = aat_solve(s, b, x);
        tap_ok(rc == BG_OK, "aat %dx%d beta=%g: aat_solve BG_OK", m, n, beta);
        if (!tap_ok(dense_aat_solve(A, beta, b, xref) == 0, "aat %dx%d: dense reference", m, n))
            continue;
        tap_ok(rel_err(x, xref, m) <= 1e-10,
               "aat %dx%d beta=%g: ||x - x_dense|| / ||x_dense|| = %.2e <= 1e-10", m, n, beta,
               rel_err(x, xref, m));
        memcpy(y, b, sizeof(double) * m);
        rc = aat_solve(s, y, y);
        tap_ok(rc == BG_OK && rel_err(y, x, m) <= 1e-15, "aat %dx%d beta=%g: in place (x == b) too",
               m, n, beta);
    }
    /* New values, same pattern. */
    A2 = sp_csc_copy(A);
    for (k = 0; k < A2->nnz; k++)
        A2->val[k] *= 1.0 + 0.5 * tap_rng_unif(r);
    for (k = 0; k < m; k++)
        b[k] = tap_rng_range(r, -1, 1);
    rc = aat_factor(s, A2, 1e-3);
    if (rc == BG_OK) rc = aat_solve(s, b, x);
    dense_aat_solve(A2, 1e-3, b, xref);
    tap_ok(rc == BG_OK && rel_err(x, xref, m) <= 1e-10,
           "aat %dx%d: new values on the same pattern (err %.2e)", m, n, rel_err(x, xref, m));
out:
    aat_free(&s);
    tap_ok(s == NULL, "aat_free sets NULL");
    sp_csc_free(&A);
    sp_csc_free(&A2);
    free(b);
    free(x);
    free(xref);
    free(y);
}

/* Two equal rows: A A^T singular. */
static void test_aat_rank_deficient(tap_rng *r)
{
    /* (a) Rows with disjoint supports and perfect-square norms, row 3 == row 1: every step of
     * the Cholesky factorization is exact, and the pivot of the repeated row is exactly 0. */
    enum { M = 6, NC = 15 };
    static const double rows[M][3] = {{1, 2, 2}, {2, 3, 6}, {1, 4, 8},
                                      {2, 3, 6}, {2, 6, 9}, {4, 4, 7}};
    static const int at[M] = {0, 3, 6, 3, 9, 12};
    double D[M * NC];
    sp_csc *A, *R = NULL, *P = NULL;
    aat_solver *s;
    int i, k, rc, m = 20, n = 40;
    double *b = NULL, *x = NULL, *xref = NULL;

    memset(D, 0, sizeof D);
    for (i = 0; i < M; i++)
        for (k = 0; k < 3; k++)
            D[i + (at[i] + k) * M] = rows[i][k];
    A = tu_csc_from_mask(M, NC, NULL, D);
    s = A ? aat_create(A, NULL) : NULL;
    if (tap_ok(s != NULL, "aat rank deficient (exact): create")) {
        rc = aat_factor(s, A, 0.0);
        tap_ok(rc == BG_ERR_NOT_POSDEF,
               "aat rank deficient (exact): beta 0 -> BG_ERR_NOT_POSDEF (got %d)", rc);
        tap_ok(aat_get_error(s)->message[0] != '\0', "aat rank deficient (exact): message \"%s\"",
               aat_get_error(s)->message);
        rc = aat_factor(s, A, 1e-3);
        tap_ok(rc == BG_OK, "aat rank deficient (exact): beta 1e-3 -> BG_OK (got %d)", rc);
    }
    aat_free(&s);

    /* (b) A random A with row 9 equal to row 4. */
    R = gen_wide(r, m, n, 0.15);
    if (!R) goto out;
    {
        double *Dr = my_dense(R);
        for (k = 0; k < n; k++)
            Dr[9 + (size_t)k * m] = Dr[4 + (size_t)k * m];
        P = tu_csc_from_mask(m, n, NULL, Dr);
        free(Dr);
    }
    s = P ? aat_create(P, NULL) : NULL;
    if (tap_ok(s != NULL, "aat rank deficient (random, rows 4 == 9): create")) {
        rc = aat_factor(s, P, 0.0);
        tap_ok(rc == BG_ERR_NOT_POSDEF,
               "aat rank deficient (random, rows 4 == 9): beta 0 -> BG_ERR_NOT_POSDEF (got %d)",
               rc);
        tap_ok(aat_get_error(s)->message[0] != '\0', "aat rank deficient (random): message set");
        /* beta > 0 regularises: the solve matches the dense one. */
        b = malloc(sizeof(double) * m);
        x = malloc(sizeof(double) * m);
        xref = malloc(sizeof(double) * m);
        for (k = 0; k < m; k++)
            b[k] = tap_rng_range(r, -1, 1);
        rc = aat_factor(s, P, 1e-3);
        if (rc == BG_OK) rc = aat_solve(s, b, x);
        dense_aat_solve(P, 1e-3, b, xref);
        tap_ok(rc == BG_OK && rel_err(x, xref, m) <= 1e-10,
               "aat rank deficient (random): beta 1e-3 solves like dense (err %.2e)",
               rc == BG_OK ? rel_err(x, xref, m) : -1.0);
        /* Pattern mismatch. */
        rc = aat_factor(s, R, 1e-3);
        tap_ok(sp_csc_same_pattern(R, P) || rc == BG_ERR_PATTERN,
               "aat: a matrix of another pattern -> BG_ERR_PATTERN (got %d)", rc);
    }
    aat_free(&s);
out:
    sp_csc_free(&A);
    sp_csc_free(&R);
    sp_csc_free(&P);
    free(b);
    free(x);
    free(xref);
}

static void test_aat_pattern(tap_rng *r)
{
    sp_csc *A = gen_wide(r, 10, 25, 0.2), *B = gen_wide(r, 10, 25, 0.2),
           *C = gen_wide(r, 11, 25, 0.2);
    aat_solver *s = A ? aat_create(A, NULL) : NULL;
    if (tap_ok(s != NULL, "aat pattern: create")) {
        int rc = aat_factor(s, B, 0.0);
        tap_ok(sp_csc_same_pattern(A, B) || rc == BG_ERR_PATTERN,
               "aat pattern: another 10x25 pattern -> BG_ERR_PATTERN (got %d)", rc);
        rc = aat_factor(s, C, 0.0);
        tap_ok(rc == BG_ERR_PATTERN, "aat pattern: 11x25 for 10x25 -> BG_ERR_PATTERN (got %d)", rc);
        tap_ok(aat_get_error(s)->message[0] != '\0', "aat pattern: message set");
        rc = aat_factor(s, A, 0.0);
        tap_ok(rc == BG_OK, "aat pattern: the right pattern still factors");
    }
    aat_free(&s);
    sp_csc_free(&A);
    sp_csc_free(&B);
    sp_csc_free(&C);
}

int main(void)
{
    tap_rng r = tap_rng_seed(0x11a50123ull);

    test_vs_lapack(&r, 10, 1, 0);
    test_vs_lapack(&r, 100, 1, 0);
    test_vs_lapack(&r, 100, 3, 0);
    test_vs_lapack(&r, 1000, 1, 0);
    test_vs_lapack(&r, 500, 3, 30);
    test_klu_large(&r, 10000);
    test_refactor(&r, 200);
    test_singular(&r);
    test_fallback();
    test_rcond();
    test_refactor_drop();
    test_pattern(&r);
    test_nonfinite(&r);
    test_aat(&r, 30, 50, 0.1);
    test_aat(&r, 200, 500, 0.02);
    test_aat_rank_deficient(&r);
    test_aat_pattern(&r);
    return tap_done();
}
