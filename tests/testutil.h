/* Helpers shared by the unit tests: matrices built and read back without the code under test
 * (only sp_csc_alloc), so that they can serve as independent references. */
#ifndef BG_TESTS_TESTUTIL_H
#define BG_TESTS_TESTUTIL_H

#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "bg_sparse.h"
#include "tap.h"

/* CSC from a column-major nrow x ncol array: entries where mask != 0 (mask NULL: where
 * vals != 0), with the values of vals (vals NULL: 1.0). */
static inline sp_csc *tu_csc_from_mask(int nrow, int ncol, const unsigned char *mask,
                                       const double *vals)
{
    int nnz = 0, p = 0;
    for (size_t c = 0; c < (size_t)nrow * ncol; c++)
        nnz += mask ? mask[c] != 0 : vals[c] != 0.0;
    sp_csc *A = sp_csc_alloc(nrow, ncol, nnz);
    if (!A) return NULL;
    for (int j = 0; j < ncol; j++) {
        A->colptr[j] = p;
        for (int i = 0; i < nrow; i++) {
            size_t c = i + (size_t)j * nrow;
            if (mask ? mask[c] != 0 : vals[c] != 0.0) {
                A->rowind[p] = i;
                A->val[p] = vals ? vals[c] : 1.0;
                p++;
            }
        }
    }
    A->colptr[ncol] = p;
    A->nnz = p;
    return A;
}

/* A random nrow x ncol matrix with about density*nrow*ncol entries (tu_csc_from_mask): entry by
 * entry in column-major order, present if a uniform draw is below density, then its value uniform
 * in [lo, hi), then (random_sign) a draw that negates it with probability 1/2. */
static inline sp_csc *tu_random_csc(tap_rng *r, int nrow, int ncol, double density, double lo,
                                    double hi, int random_sign)
{
    size_t n = (size_t)nrow * ncol, k;
    unsigned char *mask = calloc(n + 1, 1);
    double *vals = calloc(n + 1, sizeof(double));
    sp_csc *A;
    for (k = 0; k < n; k++) {
        mask[k] = tap_rng_unif(r) < density;
        vals[k] = tap_rng_range(r, lo, hi);
        if (random_sign && tap_rng_unif(r) < 0.5) vals[k] = -vals[k];
    }
    A = tu_csc_from_mask(nrow, ncol, mask, vals);
    free(mask);
    free(vals);
    return A;
}

/* Dense column-major copy of A (duplicates summed), computed here rather than by
 * sp_csc_to_dense. D holds nrow*ncol doubles. */
static inline void tu_dense(const sp_csc *A, double *D)
{
    memset(D, 0, sizeof(double) * (size_t)A->nrow * (size_t)A->ncol);
    for (int j = 0; j < A->ncol; j++)
        for (int p = A->colptr[j]; p < A->colptr[j + 1]; p++)
            D[A->rowind[p] + (size_t)j * A->nrow] += A->val[p];
}

#endif
