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
 * failure. */
sp_csc *sp_csc_alloc(int nrow, int ncol, int nnz);
/* A copy of A (pattern and values). */
sp_csc *sp_csc_copy(const sp_csc *A);
/* The transpose of A. */
sp_csc *sp_csc_transpose(const sp_csc *A);
/* From a dense column-major array, keeping entries with |a| > drop (drop < 0 keeps all). */
sp_csc *sp_csc_from_dense(int nrow, int ncol, const double *D, double drop);
void sp_csc_free(sp_csc **A);

/* Dense column-major copy: D[i + j*nrow] = A(i,j); D must hold nrow*ncol doubles. */
void sp_csc_to_dense(const sp_csc *A, double *D);
/* Position of (i,j) in val[], or -1 if not in the pattern (binary search). */
int sp_csc_find(const sp_csc *A, int i, int j);
/* Checks the structure: sizes, monotone colptr, rows in range and strictly ascending. Returns
 * BG_OK or BG_ERR_PATTERN with the first fault in err (may be NULL). */
int sp_csc_check(const sp_csc *A, bg_error *err);
/* 1 if A and B have the same dimensions and pattern, else 0. */
int sp_csc_same_pattern(const sp_csc *A, const sp_csc *B);
void sp_csc_zero(sp_csc *A);

/* y = alpha*A*x + beta*y (beta == 0 ignores y's old content, NaN included). */
void sp_matvec(const sp_csc *A, double alpha, const double *x, double beta, double *y);
/* y = alpha*A^T*x + beta*y. */
void sp_matvec_t(const sp_csc *A, double alpha, const double *x, double beta, double *y);

/* MatrixMarket coordinate real general, 1-based. Returns BG_OK or BG_ERR_IO. */
int sp_write_mm(const sp_csc *A, FILE *f);
int sp_write_mm_file(const sp_csc *A, const char *path, bg_error *err);

/* ---- coordinate builder ---- */
typedef struct sp_builder sp_builder;

/* nrow x ncol, capacity grows as needed (cap_hint may be 0). NULL on failure. */
sp_builder *sp_builder_create(int nrow, int ncol, int cap_hint);
void sp_builder_free(sp_builder **b);
/* Adds entry (i,j) with value v. Returns the entry's number k >= 0 (0,1,2,... in order of
 * addition), or BG_ERR_ARGUMENT (index out of range, message in the builder's error) or
 * BG_ERR_MEMORY. */
int sp_builder_add(sp_builder *b, int i, int j, double v);
int sp_builder_count(const sp_builder *b);
/* The compressed matrix with duplicates summed. If slot != NULL it must hold
 * sp_builder_count(b) ints and receives slot[k] = position in val[] of entry k.
 * The builder stays valid (more entries may be added and finish called again). */
sp_csc *sp_builder_finish(sp_builder *b, int *slot);
const bg_error *sp_builder_error(const sp_builder *b);

/* val[slot[k]] += v[k] for k < n. */
void sp_scatter_add(sp_csc *A, const int *slot, const double *v, int n);

/* ---- union of two patterns of the same shape ---- */
typedef struct sp_union {
    sp_csc *M;  /* union pattern, values owned (filled by sp_union_combine) */
    int *map_a; /* A's entry p lives at M->val[map_a[p]] */
    int *map_b; /* B's entry p lives at M->val[map_b[p]] */
} sp_union;

/* NULL on failure (allocation, or shapes differ). */
sp_union *sp_union_create(const sp_csc *A, const sp_csc *B);
void sp_union_free(sp_union **u);
/* u->M = ca*A + cb*B; A and B must have the patterns u was created with. */
void sp_union_combine(sp_union *u, const sp_csc *A, double ca, const sp_csc *B, double cb);

#ifdef __cplusplus
}
#endif
#endif
