/* Compressed-column matrices, the coordinate builder with its slot map, pattern unions,
 * products and the MatrixMarket writer (see bg_sparse.h for the method). */
#include "bg_sparse.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

sp_csc *sp_csc_alloc(int nrow, int ncol, int nnz)
{
    if (nrow < 0 || ncol < 0 || nnz < 0) return NULL;
    sp_csc *A = calloc(1, sizeof *A);
    if (!A) return NULL;
    A->nrow = nrow;
    A->ncol = ncol;
    A->nnz = 0;
    A->colptr = calloc((size_t)ncol + 1, sizeof *A->colptr);
    A->rowind = malloc(((size_t)nnz + 1) * sizeof *A->rowind);
    A->val = malloc(((size_t)nnz + 1) * sizeof *A->val);
    if (!A->colptr || !A->rowind || !A->val) sp_csc_free(&A);
    return A;
}

void sp_csc_free(sp_csc **A)
{
    if (!A || !*A) return;
    free((*A)->colptr);
    free((*A)->rowind);
    free((*A)->val);
    free(*A);
    *A = NULL;
}

sp_csc *sp_csc_copy(const sp_csc *A)
{
    if (!A) return NULL;
    sp_csc *B = sp_csc_alloc(A->nrow, A->ncol, A->nnz);
    if (!B) return NULL;
    memcpy(B->colptr, A->colptr, ((size_t)A->ncol + 1) * sizeof *A->colptr);
    memcpy(B->rowind, A->rowind, (size_t)A->nnz * sizeof *A->rowind);
    memcpy(B->val, A->val, (size_t)A->nnz * sizeof *A->val);
    B->nnz = A->nnz;
    return B;
}

sp_csc *sp_csc_transpose(const sp_csc *A)
{
    if (!A) return NULL;
    sp_csc *T = sp_csc_alloc(A->ncol, A->nrow, A->nnz);
    if (!T) return NULL;
    int *next = calloc((size_t)A->nrow + 1, sizeof *next);
    if (!next) {
        sp_csc_free(&T);
        return NULL;
    }
    for (int p = 0; p < A->nnz; p++)
        T->colptr[A->rowind[p] + 1]++;
    for (int i = 0; i < A->nrow; i++)
        T->colptr[i + 1] += T->colptr[i];
    memcpy(next, T->colptr, (size_t)A->nrow * sizeof *next);
    for (int j = 0; j < A->ncol; j++)
        for (int p = A->colptr[j]; p < A->colptr[j + 1]; p++) {
            int q = next[A->rowind[p]]++;
            T->rowind[q] = j; /* columns visited in order: rows of T ascend */
            T->val[q] = A->val[p];
        }
    T->nnz = A->nnz;
    free(next);
    return T;
}

sp_csc *sp_csc_from_dense(int nrow, int ncol, const double *D, double drop)
{
    if (nrow < 0 || ncol < 0 || (!D && (long)nrow * ncol > 0)) return NULL;
    long nnz = 0;
    for (long k = 0; k < (long)nrow * ncol; k++)
        if (drop < 0 || fabs(D[k]) > drop) nnz++;
    if (nnz > INT_MAX - 1) return NULL;
    sp_csc *A = sp_csc_alloc(nrow, ncol, (int)nnz);
    if (!A) return NULL;
    int p = 0;
    for (int j = 0; j < ncol; j++) {
        for (int i = 0; i < nrow; i++) {
            double v = D[i + (size_t)j * nrow];
            if (drop < 0 || fabs(v) > drop) {
                A->rowind[p] = i;
                A->val[p++] = v;
            }
        }
        A->colptr[j + 1] = p;
    }
    A->nnz = p;
    return A;
}

int sp_csc_to_dense(const sp_csc *A, double *D)
{
    if (!A || !D) return BG_ERR_ARGUMENT;
    memset(D, 0, (size_t)A->nrow * A->ncol * sizeof *D);
    for (int j = 0; j < A->ncol; j++)
        for (int p = A->colptr[j]; p < A->colptr[j + 1]; p++)
            D[A->rowind[p] + (size_t)j * A->nrow] += A->val[p];
    return BG_OK;
}

int sp_csc_find(const sp_csc *A, int i, int j)
{
    if (!A || i < 0 || i >= A->nrow || j < 0 || j >= A->ncol) return -1;
    int lo = A->colptr[j], hi = A->colptr[j + 1] - 1;
    while (lo <= hi) {
        int mid = lo + (hi - lo) / 2;
        if (A->rowind[mid] == i) return mid;
        if (A->rowind[mid] < i)
            lo = mid + 1;
        else
            hi = mid - 1;
    }
    return -1;
}

int sp_csc_check(const sp_csc *A, bg_error *err)
{
    const char *w = "sp_csc_check";
    if (!A) return bg_error_raise(err, BG_ERR_ARGUMENT, w, "matrix is NULL");
    if (A->nrow < 0 || A->ncol < 0)
        return bg_error_raise(err, BG_ERR_PATTERN, w, "negative dimension %d x %d", A->nrow,
                              A->ncol);
    if (A->nnz < 0)
        return bg_error_raise(err, BG_ERR_PATTERN, w, "negative entry count %d", A->nnz);
    if (!A->colptr || (A->nnz > 0 && (!A->rowind || !A->val)))
        return bg_error_raise(err, BG_ERR_PATTERN, w, "the %s array is NULL",
                              !A->colptr   ? "colptr"
                              : !A->rowind ? "rowind"
                                           : "val");
    if (A->colptr[0] != 0)
        return bg_error_raise(err, BG_ERR_PATTERN, w, "colptr[0] = %d, expected 0", A->colptr[0]);
    for (int j = 0; j < A->ncol; j++) {
        if (A->colptr[j + 1] < A->colptr[j])
            return bg_error_raise(err, BG_ERR_PATTERN, w, "colptr decreases at column %d", j);
        if (A->colptr[j + 1] > A->nnz)
            return bg_error_raise(err, BG_ERR_PATTERN, w,
                                  "colptr[%d] = %d exceeds the entry count %d", j + 1,
                                  A->colptr[j + 1], A->nnz);
        for (int p = A->colptr[j]; p < A->colptr[j + 1]; p++) {
            int i = A->rowind[p];
            if (i < 0 || i >= A->nrow)
                return bg_error_raise(err, BG_ERR_PATTERN, w,
                                      "row index %d out of range [0,%d) in column %d", i, A->nrow,
                                      j);
            if (p > A->colptr[j] && A->rowind[p - 1] >= i)
                return bg_error_raise(err, BG_ERR_PATTERN, w,
                                      "rows not strictly ascending in column %d (row %d after %d)",
                                      j, i, A->rowind[p - 1]);
        }
    }
    if (A->colptr[A->ncol] != A->nnz)
        return bg_error_raise(err, BG_ERR_PATTERN, w, "colptr[ncol] = %d but nnz = %d",
                              A->colptr[A->ncol], A->nnz);
    return BG_OK;
}

int sp_csc_same_pattern(const sp_csc *A, const sp_csc *B)
{
    if (!A || !B) return 0;
    if (A == B) return 1;
    if (A->nrow != B->nrow || A->ncol != B->ncol || A->nnz != B->nnz) return 0;
    return memcmp(A->colptr, B->colptr, ((size_t)A->ncol + 1) * sizeof *A->colptr) == 0 &&
           memcmp(A->rowind, B->rowind, (size_t)A->nnz * sizeof *A->rowind) == 0;
}

int sp_csc_zero(sp_csc *A)
{
    if (!A) return BG_ERR_ARGUMENT;
    if (A->nnz > 0) memset(A->val, 0, (size_t)A->nnz * sizeof *A->val);
    return BG_OK;
}

int sp_matvec(const sp_csc *A, double alpha, const double *x, double beta, double *y)
{
    if (!A || !x || !y) return BG_ERR_ARGUMENT;
    if (beta == 0.0)
        memset(y, 0, (size_t)A->nrow * sizeof *y);
    else if (beta != 1.0)
        for (int i = 0; i < A->nrow; i++)
            y[i] *= beta;
    for (int j = 0; j < A->ncol; j++) {
        double ax = alpha * x[j];
        for (int p = A->colptr[j]; p < A->colptr[j + 1]; p++)
            y[A->rowind[p]] += A->val[p] * ax;
    }
    return BG_OK;
}

int sp_matvec_t(const sp_csc *A, double alpha, const double *x, double beta, double *y)
{
    if (!A || !x || !y) return BG_ERR_ARGUMENT;
    for (int j = 0; j < A->ncol; j++) {
        double s = 0.0;
        for (int p = A->colptr[j]; p < A->colptr[j + 1]; p++)
            s += A->val[p] * x[A->rowind[p]];
        y[j] = (beta == 0.0 ? 0.0 : beta * y[j]) + alpha * s;
    }
    return BG_OK;
}

int sp_write_mm(const sp_csc *A, FILE *f)
{
    if (!A || !f) return BG_ERR_ARGUMENT;
    if (fprintf(f, "%%%%MatrixMarket matrix coordinate real general\n%d %d %d\n", A->nrow, A->ncol,
                A->nnz) < 0)
        return BG_ERR_IO;
    for (int j = 0; j < A->ncol; j++)
        for (int p = A->colptr[j]; p < A->colptr[j + 1]; p++)
            if (fprintf(f, "%d %d %.17g\n", A->rowind[p] + 1, j + 1, A->val[p]) < 0)
                return BG_ERR_IO;
    return ferror(f) ? BG_ERR_IO : BG_OK;
}

int sp_write_mm_file(const sp_csc *A, const char *path, bg_error *err)
{
    if (!A || !path)
        return bg_error_raise(err, BG_ERR_ARGUMENT, "sp_write_mm_file", "%s is NULL",
                              !A ? "the matrix" : "the path");
    FILE *f = fopen(path, "w");
    if (!f) return bg_error_raise(err, BG_ERR_IO, "sp_write_mm_file", "cannot open %s", path);
    int st = sp_write_mm(A, f);
    if (fclose(f) != 0 && st == BG_OK) st = BG_ERR_IO;
    if (st != BG_OK) return bg_error_raise(err, st, "sp_write_mm_file", "cannot write %s", path);
    return BG_OK;
}

/* ---- builder ---- */
struct sp_builder {
    int nrow, ncol;
    int n, cap;
    int *ri, *ci;
    double *v;
    bg_error err;
};

sp_builder *sp_builder_create(int nrow, int ncol, int cap_hint)
{
    if (nrow < 0 || ncol < 0) return NULL;
    sp_builder *b = calloc(1, sizeof *b);
    if (!b) return NULL;
    b->nrow = nrow;
    b->ncol = ncol;
    b->cap = cap_hint > 16 ? cap_hint : 16;
    b->ri = malloc((size_t)b->cap * sizeof *b->ri);
    b->ci = malloc((size_t)b->cap * sizeof *b->ci);
    b->v = malloc((size_t)b->cap * sizeof *b->v);
    if (!b->ri || !b->ci || !b->v) sp_builder_free(&b);
    return b;
}

void sp_builder_free(sp_builder **b)
{
    if (!b || !*b) return;
    free((*b)->ri);
    free((*b)->ci);
    free((*b)->v);
    free(*b);
    *b = NULL;
}

static int grow(void **p, size_t elem, int cap)
{
    void *q = realloc(*p, (size_t)cap * elem);
    if (!q) return 0;
    *p = q;
    return 1;
}

int sp_builder_add(sp_builder *b, int i, int j, double v)
{
    if (!b) return BG_ERR_ARGUMENT;
    if (i < 0 || i >= b->nrow || j < 0 || j >= b->ncol)
        return bg_error_raise(&b->err, BG_ERR_ARGUMENT, "sp_builder_add",
                              "entry (%d,%d) outside the %d x %d matrix", i, j, b->nrow, b->ncol);
    if (b->n == b->cap) {
        if (b->cap > (1 << 29))
            return bg_error_raise(&b->err, BG_ERR_MEMORY, "sp_builder_add", "too many entries");
        int cap = 2 * b->cap;
        if (!grow((void **)&b->ri, sizeof *b->ri, cap) ||
            !grow((void **)&b->ci, sizeof *b->ci, cap) || !grow((void **)&b->v, sizeof *b->v, cap))
            return bg_error_raise(&b->err, BG_ERR_MEMORY, "sp_builder_add",
                                  "cannot grow to %d entries", cap);
        b->cap = cap;
    }
    b->ri[b->n] = i;
    b->ci[b->n] = j;
    b->v[b->n] = v;
    return b->n++;
}

int sp_builder_count(const sp_builder *b)
{
    return b ? b->n : BG_ERR_ARGUMENT;
}

const bg_error *sp_builder_error(const sp_builder *b)
{
    return b ? &b->err : NULL;
}

sp_csc *sp_builder_finish(sp_builder *b, int *slot)
{
    if (!b) return NULL;
    int n = b->n, nc = b->ncol, nr = b->nrow;
    int *cnt = calloc((size_t)(nr > nc ? nr : nc) + 1, sizeof *cnt);
    int *order = malloc(((size_t)n + 1) * sizeof *order);
    int *tmp = malloc(((size_t)n + 1) * sizeof *tmp);
    sp_csc *A = NULL;
    if (!cnt || !order || !tmp) {
        bg_error_raise(&b->err, BG_ERR_MEMORY, "sp_builder_finish", "out of memory");
        goto done;
    }
    /* Two stable counting sorts: by row, then by column, give column-major order with rows
     * ascending and, within one position, entries in order of addition. */
    for (int k = 0; k < n; k++)
        cnt[b->ri[k] + 1]++;
    for (int i = 0; i < nr; i++)
        cnt[i + 1] += cnt[i];
    for (int k = 0; k < n; k++)
        tmp[cnt[b->ri[k]]++] = k;
    memset(cnt, 0, ((size_t)(nr > nc ? nr : nc) + 1) * sizeof *cnt);
    for (int k = 0; k < n; k++)
        cnt[b->ci[k] + 1]++;
    for (int j = 0; j < nc; j++)
        cnt[j + 1] += cnt[j];
    for (int t = 0; t < n; t++) {
        int k = tmp[t];
        order[cnt[b->ci[k]]++] = k;
    }
    /* count distinct positions */
    int nnz = 0;
    for (int t = 0; t < n; t++) {
        int k = order[t];
        if (t == 0 || b->ci[k] != b->ci[order[t - 1]] || b->ri[k] != b->ri[order[t - 1]]) nnz++;
    }
    A = sp_csc_alloc(nr, nc, nnz);
    if (!A) {
        bg_error_raise(&b->err, BG_ERR_MEMORY, "sp_builder_finish", "out of memory");
        goto done;
    }
    int p = -1;
    for (int t = 0; t < n; t++) {
        int k = order[t];
        if (t == 0 || b->ci[k] != b->ci[order[t - 1]] || b->ri[k] != b->ri[order[t - 1]]) {
            p++;
            A->rowind[p] = b->ri[k];
            A->val[p] = 0.0;
            A->colptr[b->ci[k] + 1]++;
        }
        A->val[p] += b->v[k];
        if (slot) slot[k] = p;
    }
    for (int j = 0; j < nc; j++)
        A->colptr[j + 1] += A->colptr[j];
    A->nnz = nnz;
done:
    free(cnt);
    free(order);
    free(tmp);
    return A;
}

int sp_scatter_add(sp_csc *A, const int *slot, const double *v, int n)
{
    if (!A || n < 0 || (n > 0 && (!slot || !v))) return BG_ERR_ARGUMENT;
    for (int k = 0; k < n; k++)
        if (slot[k] < 0 || slot[k] >= A->nnz) return BG_ERR_ARGUMENT;
    for (int k = 0; k < n; k++)
        A->val[slot[k]] += v[k];
    return BG_OK;
}

/* ---- union ---- */
void sp_union_free(sp_union **u)
{
    if (!u || !*u) return;
    sp_csc_free(&(*u)->M);
    free((*u)->map_a);
    free((*u)->map_b);
    free(*u);
    *u = NULL;
}

sp_union *sp_union_create(const sp_csc *A, const sp_csc *B)
{
    if (!A || !B || A->nrow != B->nrow || A->ncol != B->ncol) return NULL;
    sp_union *u = calloc(1, sizeof *u);
    if (!u) return NULL;
    /* merge of two sorted row lists per column: first count, then fill */
    int nnz = 0;
    for (int j = 0; j < A->ncol; j++) {
        int p = A->colptr[j], q = B->colptr[j];
        int pe = A->colptr[j + 1], qe = B->colptr[j + 1];
        while (p < pe || q < qe) {
            if (q >= qe || (p < pe && A->rowind[p] < B->rowind[q]))
                p++;
            else if (p >= pe || B->rowind[q] < A->rowind[p])
                q++;
            else
                p++, q++;
            nnz++;
        }
    }
    u->M = sp_csc_alloc(A->nrow, A->ncol, nnz);
    u->map_a = malloc(((size_t)A->nnz + 1) * sizeof *u->map_a);
    u->map_b = malloc(((size_t)B->nnz + 1) * sizeof *u->map_b);
    if (!u->M || !u->map_a || !u->map_b) {
        sp_union_free(&u);
        return NULL;
    }
    int r = 0;
    for (int j = 0; j < A->ncol; j++) {
        int p = A->colptr[j], q = B->colptr[j];
        int pe = A->colptr[j + 1], qe = B->colptr[j + 1];
        while (p < pe || q < qe) {
            if (q >= qe || (p < pe && A->rowind[p] < B->rowind[q])) {
                u->M->rowind[r] = A->rowind[p];
                u->map_a[p++] = r;
            } else if (p >= pe || B->rowind[q] < A->rowind[p]) {
                u->M->rowind[r] = B->rowind[q];
                u->map_b[q++] = r;
            } else {
                u->M->rowind[r] = A->rowind[p];
                u->map_a[p++] = r;
                u->map_b[q++] = r;
            }
            u->M->val[r++] = 0.0;
        }
        u->M->colptr[j + 1] = r;
    }
    u->M->nnz = r;
    u->nnz_a = A->nnz;
    u->nnz_b = B->nnz;
    return u;
}

int sp_union_combine(sp_union *u, const sp_csc *A, double ca, const sp_csc *B, double cb)
{
    if (!u || !u->M || !A || !B) return BG_ERR_ARGUMENT;
    if (A->nrow != u->M->nrow || A->ncol != u->M->ncol || B->nrow != u->M->nrow ||
        B->ncol != u->M->ncol || A->nnz != u->nnz_a || B->nnz != u->nnz_b)
        return BG_ERR_PATTERN;
    sp_csc_zero(u->M);
    double *m = u->M->val;
    for (int p = 0; p < A->nnz; p++)
        m[u->map_a[p]] = ca * A->val[p];
    for (int p = 0; p < B->nnz; p++)
        m[u->map_b[p]] += cb * B->val[p];
    return BG_OK;
}
