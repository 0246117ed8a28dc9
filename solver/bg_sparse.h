/* Sparse matrices in compressed-column form, the coordinate builder that fixes a pattern once,
 * the union of two patterns, products and a MatrixMarket writer.
 *
 * Method. A pattern is declared once: entries are added to a builder in any order, duplicates
 * allowed; sp_builder_finish() sorts them column by column (counting sort, rows ascending within
 * each column), sums duplicates and returns for every added entry k its slot, the position in
 * val[] where its value lives. Per-step assembly is then a scatter val[slot[k]] += v_k into a
 * pattern that never changes, which is what KLU's refactorization needs. The Newton matrix
 * dF/dy + c dF/dy' is formed on the union of the two patterns through two index maps
 * (sp_union), without allocation.
 *
 * Indices are 0-based C ints (KLU's and CHOLMOD's int interfaces). Matrices own their arrays. */
#ifndef BG_SPARSE_H
#define BG_SPARSE_H

#include <stdio.h>

#include "bg_api.h"
#include "bg_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sp_csc {
    int nrow, ncol;
    int nnz;     /* colptr[ncol] */
    int *colptr; /* ncol+1 */
    int *rowind; /* nnz, ascending within each column, no duplicates */
    double *val; /* nnz */
} sp_csc;

/* A zero matrix with room for nnz entries (colptr zero, rowind/val uninitialised). NULL on
 * failure (a negative size, or no memory). */
BG_API sp_csc *sp_csc_alloc(int nrow, int ncol, int nnz);
/* A copy of A (pattern and values). NULL if A is NULL or on failure. */
BG_API sp_csc *sp_csc_copy(const sp_csc *A);
/* The transpose of A. NULL if A is NULL or on failure. */
BG_API sp_csc *sp_csc_transpose(const sp_csc *A);
/* From a dense column-major array, keeping entries with |a| > drop (drop < 0 keeps all). NULL if
 * D is NULL (with nrow * ncol > 0), a size is negative, or on failure. */
BG_API sp_csc *sp_csc_from_dense(int nrow, int ncol, const double *D, double drop);
/* Frees *A and sets it to NULL; A or *A may be NULL. */
BG_API void sp_csc_free(sp_csc **A);

/* Dense column-major copy: D[i + j*nrow] = A(i,j); D must hold nrow*ncol doubles. BG_OK, or
 * BG_ERR_ARGUMENT if A or D is NULL. */
BG_API int sp_csc_to_dense(const sp_csc *A, double *D);
/* Position of (i,j) in val[], or -1 if not in the pattern, out of range or A is NULL (binary
 * search). */
BG_API int sp_csc_find(const sp_csc *A, int i, int j);
/* Checks the structure: sizes, arrays present, monotone colptr, rows in range and strictly
 * ascending. Returns BG_OK, BG_ERR_ARGUMENT (A is NULL) or BG_ERR_PATTERN, with the first fault
 * in err (may be NULL). */
BG_API int sp_csc_check(const sp_csc *A, bg_error *err);
/* 1 if A and B have the same dimensions and pattern, else 0 (also if either is NULL). */
BG_API int sp_csc_same_pattern(const sp_csc *A, const sp_csc *B);
/* Values set to zero. BG_OK, or BG_ERR_ARGUMENT if A is NULL. */
BG_API int sp_csc_zero(sp_csc *A);

/* y = alpha*A*x + beta*y (beta == 0 ignores y's old content, NaN included). BG_OK, or
 * BG_ERR_ARGUMENT if A, x or y is NULL. */
BG_API int sp_matvec(const sp_csc *A, double alpha, const double *x, double beta, double *y);
/* y = alpha*A^T*x + beta*y. BG_OK, or BG_ERR_ARGUMENT if A, x or y is NULL. */
BG_API int sp_matvec_t(const sp_csc *A, double alpha, const double *x, double beta, double *y);

/* MatrixMarket coordinate real general, 1-based. Returns BG_OK, BG_ERR_ARGUMENT (A or f NULL)
 * or BG_ERR_IO. */
BG_API int sp_write_mm(const sp_csc *A, FILE *f);
/* The same into the file path: BG_OK, BG_ERR_ARGUMENT (A or path NULL) or BG_ERR_IO, with a
 * message in err (may be NULL). */
BG_API int sp_write_mm_file(const sp_csc *A, const char *path, bg_error *err);

/* ---- coordinate builder ---- */
typedef struct sp_builder sp_builder;

/* nrow x ncol, capacity grows as needed (cap_hint may be 0). NULL on failure (a negative
 * dimension, or no memory). */
BG_API sp_builder *sp_builder_create(int nrow, int ncol, int cap_hint);
BG_API void sp_builder_free(sp_builder **b);
/* Adds entry (i,j) with value v. Returns the entry's number k >= 0 (0,1,2,... in order of
 * addition), or BG_ERR_ARGUMENT (b NULL, or an index out of range: message in the builder's
 * error) or BG_ERR_MEMORY. */
BG_API int sp_builder_add(sp_builder *b, int i, int j, double v);
/* Entries added so far, or BG_ERR_ARGUMENT if b is NULL. */
BG_API int sp_builder_count(const sp_builder *b);
/* The compressed matrix with duplicates summed. If slot != NULL it must hold
 * sp_builder_count(b) ints and receives slot[k] = position in val[] of entry k.
 * The builder stays valid (more entries may be added and finish called again). NULL if b is
 * NULL or on failure (message in the builder's error). */
BG_API sp_csc *sp_builder_finish(sp_builder *b, int *slot);
/* The builder's error record, NULL if b is NULL. */
BG_API const bg_error *sp_builder_error(const sp_builder *b);

/* val[slot[k]] += v[k] for k < n. BG_OK, or BG_ERR_ARGUMENT (A, slot or v NULL with n > 0,
 * n < 0, or a slot outside 0..nnz-1; A is then unchanged). */
BG_API int sp_scatter_add(sp_csc *A, const int *slot, const double *v, int n);

/* ---- union of two patterns of the same shape ---- */
typedef struct sp_union {
    sp_csc *M;        /* union pattern, values owned (filled by sp_union_combine) */
    int *map_a;       /* A's entry p lives at M->val[map_a[p]] */
    int *map_b;       /* B's entry p lives at M->val[map_b[p]] */
    int nnz_a, nnz_b; /* entries of A and B at creation */
} sp_union;

/* NULL on failure (A or B NULL, shapes differ, or no memory). */
BG_API sp_union *sp_union_create(const sp_csc *A, const sp_csc *B);
BG_API void sp_union_free(sp_union **u);
/* u->M = ca*A + cb*B; A and B must have the patterns u was created with. BG_OK,
 * BG_ERR_ARGUMENT (a NULL argument) or BG_ERR_PATTERN (a shape or entry count other than at
 * creation; M is then unchanged). */
BG_API int sp_union_combine(sp_union *u, const sp_csc *A, double ca, const sp_csc *B, double cb);

#ifdef __cplusplus
}
#endif
#endif
