/* Column colouring, coloured finite-difference Jacobians, and a Jacobian checker.
 *
 * Method (Curtis, Powell and Reid, J. Inst. Maths Applics 13 (1974) 117-119): columns that share
 * no row are structurally orthogonal and may be perturbed together, so one extra function
 * evaluation yields every column of a group. Groups come from greedy colouring of the column
 * intersection graph in natural column order: column j takes the smallest group used by none of
 * the columns that share a row with it. On a banded matrix with lower and upper bandwidths p and q
 * this gives exactly p+q+1 groups, which is optimal.
 *
 * The checker does not trust the declared pattern: it differences one column at a time with
 * central differences and compares every row, so an entry missing from the analytic Jacobian is
 * found as well as a wrong value. */
#ifndef BG_FDJAC_H
#define BG_FDJAC_H

#include "bg_api.h"
#include "bg_sparse.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sp_colouring {
    int ncol;
    int ngroups;
    int *group; /* ncol: group of column j, 0..ngroups-1 */
    int *gptr;  /* ngroups+1: columns of group g are gcols[gptr[g] .. gptr[g+1]-1] */
    int *gcols; /* ncol */
} sp_colouring;

/* The greedy colouring of the columns of pattern; NULL if pattern is NULL or on failure. */
BG_API sp_colouring *sp_colour(const sp_csc *pattern);
BG_API void sp_colouring_free(sp_colouring **c);
/* 1 if no two columns of one group share a row of pattern, else 0 (also for NULL arguments). */
BG_API int sp_colouring_valid(const sp_colouring *c, const sp_csc *pattern);

/* f: R^n -> R^m. Returns 0 ok, > 0 recoverable failure, < 0 fatal. */
typedef int (*sp_vecfn)(void *user, const double *x, double *f);

typedef struct sp_fdjac sp_fdjac;

/* For a Jacobian with the given m x n pattern (values ignored). NULL if pattern is NULL or on
 * failure. */
BG_API sp_fdjac *sp_fdjac_create(const sp_csc *pattern);
BG_API void sp_fdjac_free(sp_fdjac **d);
/* Number of column groups (function evaluations per Jacobian), BG_ERR_ARGUMENT if d is NULL. */
BG_API int sp_fdjac_ngroups(const sp_fdjac *d);
/* Forward differences, one evaluation per group: J(:,j) ~ (f(x + h_j e_j) - f0) / h_j with
 * h_j = sqrt(eps) * max(|x_j|, typ_j) (typ may be NULL: 1), sign following x_j. f0 = f(x) must be
 * given. J must have the pattern given at creation; its values are overwritten. No allocation.
 * Returns 0, BG_ERR_ARGUMENT (d, f, x, f0 or J NULL), BG_ERR_PATTERN (J has another pattern), or
 * the callback's non-zero status (J then undefined). */
BG_API int sp_fdjac_eval(sp_fdjac *d, sp_vecfn f, void *user, const double *x, const double *f0,
                         const double *typ, sp_csc *J);
/* Number of calls of f made by sp_fdjac_eval so far; BG_ERR_ARGUMENT if d is NULL. */
BG_API long sp_fdjac_calls(const sp_fdjac *d);

/* One entry of a Jacobian check. */
typedef struct sp_jac_entry {
    int row, col;
    double analytic; /* 0 where (row,col) is outside the analytic pattern */
    double fd;       /* central difference */
    double err;      /* |analytic - fd| / (|fd| + floor) */
} sp_jac_entry;

/* Compares the analytic m x n Jacobian J at x with central differences of f, every row of every
 * column. The nworst largest errors, largest first, go to worst[] (nworst may be 0); *max_err
 * (max_err may be NULL) receives the largest. floor (> 0, e.g. 1e-6 times the Jacobian's scale)
 * keeps tiny entries from dominating. Returns the number of entries with err > tol, or < 0 on
 * failure: BG_ERR_ARGUMENT (J, f or x NULL, m other than J's rows, floor not > 0, nworst < 0,
 * worst NULL with nworst > 0), the callback's status (BG_ERR_CALLBACK for a positive one) or
 * BG_ERR_MEMORY. */
BG_API int sp_jac_check(const sp_csc *J, sp_vecfn f, void *user, int m, const double *x,
                        double floor, double tol, sp_jac_entry *worst, int nworst, double *max_err);

#ifdef __cplusplus
}
#endif
#endif
