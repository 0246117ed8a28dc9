/* Linear solvers behind one interface: sparse LU by KLU and dense LU by LAPACK.
 *
 * KLU (Davis and Palamadai Natarajan, ACM TOMS 37(3), 2010): the pattern is analysed once
 * (BTF, then COLAMD ordering of the blocks, suited to pivots off the diagonal) at creation. The
 * first ls_factor() is a full numeric factorization; later ones reuse its pivot sequence through
 * klu_refactor, which is much cheaper, then check the cheap reciprocal condition estimate
 * min|U_kk|/max|U_kk| (klu_rcond). If the refactorization hit a zero pivot, or the estimate fell
 * more than a factor 1e-3 below that of the last full factorization (the pivots have gone stale) or
 * below rcond_min (default 0), a full factorization with fresh pivoting is done (counted as a
 * fallback). A matrix that is ill-conditioned by nature keeps its refactorizations: the estimate is
 * relative to what fresh pivots gave. A singular matrix is reported with the column of the original
 * matrix at fault and the numerical rank.
 *
 * Dense: the matrix is expanded into a column-major array and factored by dgetrf (partial
 * pivoting); rcond is estimated by dgecon in the 1-norm. Meant for small systems and as a
 * cross-check of KLU. */
#ifndef BG_LINSOL_H
#define BG_LINSOL_H

#include "bg_api.h"
#include "bg_sparse.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum ls_kind {
    LS_NONE = -1, /* not a solver: what ls_get_kind(NULL) returns */
    LS_KLU = 0,
    LS_DENSE = 1
} ls_kind;

typedef struct ls_stats {
    long symbolic; /* symbolic analyses (KLU: 1 per solver object) */
    long factor;   /* full numeric factorizations (fresh pivoting) */
    long refactor; /* refactorizations reusing the previous pivot sequence */
    long fallback; /* refactorizations that had to be redone as full factorizations */
    long solve;    /* right-hand sides solved */
    double rcond;  /* last reciprocal condition estimate (KLU: min|Ukk|/max|Ukk|) */
} ls_stats;

typedef struct ls_solver ls_solver;

/* A square solver for matrices with this pattern (values ignored). NULL on failure; the
 * reason goes to err if given: BG_ERR_ARGUMENT (pattern NULL or not square, unknown kind),
 * BG_ERR_PATTERN (the pattern's structure is invalid, see sp_csc_check), BG_ERR_MEMORY or
 * BG_ERR_LIBRARY. */
BG_API ls_solver *ls_create(ls_kind kind, const sp_csc *pattern, bg_error *err);
BG_API void ls_free(ls_solver **s);
/* Factor A (same pattern as at creation). Returns BG_OK, BG_ERR_ARGUMENT (s or A NULL),
 * BG_ERR_SINGULAR (see ls_singular_col), BG_ERR_NONFINITE (message names the entry),
 * BG_ERR_PATTERN, BG_ERR_MEMORY or BG_ERR_LIBRARY. */
BG_API int ls_factor(ls_solver *s, const sp_csc *A);
/* Next ls_factor() is a full factorization with fresh pivoting. BG_OK or BG_ERR_ARGUMENT (s
 * NULL). */
BG_API int ls_force_full(ls_solver *s);
/* Solve A x = b in place for nrhs right-hand sides stored one after another. BG_OK,
 * BG_ERR_ARGUMENT (s or b NULL, nrhs < 1), BG_ERR_STATE (no factorization yet, or the last one
 * failed) or BG_ERR_LIBRARY. */
BG_API int ls_solve(ls_solver *s, double *b, int nrhs);
/* Column of the original matrix found singular by the last failed factorization, -1 if none
 * (or s is NULL). */
BG_API int ls_singular_col(const ls_solver *s);
/* A refactorization whose rcond estimate falls below this absolute threshold (default 0: only
 * the relative test above applies) is redone as a full factorization with fresh pivoting. BG_OK, or
 * BG_ERR_ARGUMENT (s NULL, rcond_min negative or NaN; the threshold is then unchanged). */
BG_API int ls_set_rcond_min(ls_solver *s, double rcond_min);
/* Statistics, NULL if s is NULL. */
BG_API const ls_stats *ls_get_stats(const ls_solver *s);
/* The kind, LS_NONE if s is NULL. */
BG_API ls_kind ls_get_kind(const ls_solver *s);
/* The error record with the last message, NULL if s is NULL. */
BG_API bg_error *ls_get_error(ls_solver *s);

/* ---- A*A^T systems by CHOLMOD (constraint projection) ----
 * For an m x n matrix A of full row rank, (A A^T + beta I) x = b by a sparse Cholesky
 * factorization of A A^T (CHOLMOD's unsymmetric mode: the product is never formed by the
 * caller). Pattern analysed once at creation; factor and solve reuse workspace. The factorization
 * is a simplicial LDL^T, so that rows that are numerically dependent (a pivot below 1e-12 times
 * the largest) are reported instead of passing with a tiny positive pivot. */
typedef struct aat_solver aat_solver;

/* NULL on failure with the reason in err (may be NULL): BG_ERR_ARGUMENT (pattern NULL),
 * BG_ERR_PATTERN (invalid structure), BG_ERR_MEMORY or BG_ERR_LIBRARY. */
BG_API aat_solver *aat_create(const sp_csc *pattern, bg_error *err);
BG_API void aat_free(aat_solver **s);
/* BG_OK, BG_ERR_ARGUMENT (s or A NULL, beta negative or not finite), BG_ERR_NOT_POSDEF (A rank
 * deficient: message names the pivot), BG_ERR_PATTERN, BG_ERR_NONFINITE, BG_ERR_LIBRARY. */
BG_API int aat_factor(aat_solver *s, const sp_csc *A, double beta);
/* x = (A A^T + beta I)^-1 b, m values each; x may equal b. BG_OK, BG_ERR_ARGUMENT (a NULL
 * argument), BG_ERR_STATE (no factorization yet, or the last one failed) or BG_ERR_LIBRARY. */
BG_API int aat_solve(aat_solver *s, const double *b, double *x);
/* The error record, NULL if s is NULL. */
BG_API bg_error *aat_get_error(aat_solver *s);
/* Factorizations so far, BG_ERR_ARGUMENT if s is NULL. */
BG_API long aat_factor_count(const aat_solver *s);

#ifdef __cplusplus
}
#endif
#endif
