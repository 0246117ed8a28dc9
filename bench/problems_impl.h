/* What the files of the problem collection share (private to bench/problems*.c): the pattern
 * helpers and the table macro. */
#ifndef PROBLEMS_IMPL_H
#define PROBLEMS_IMPL_H

#include "problems.h"

/* A pattern from a list of (row, column) pairs, values zero. */
int bpi_pattern_from_pairs(int nrow, int ncol, const int (*ij)[2], int npairs, sp_csc **out);
/* The identity on the first m diagonal entries of an n x n pattern (dF/dy' of y' - f). */
int bpi_pattern_diag(int n, int m, sp_csc **out);
/* Two patterns, or none (on failure both are freed). */
int bpi_patterns_pair(int n, const int (*iy)[2], int ny, const int (*iyp)[2], int nyp, sp_csc **jy,
                      sp_csc **jyp);
/* dF/dy from (row, column) pairs and dF/dy' the identity on the first m diagonal entries (y' - f
 * with m differential rows); on failure jy is freed. */
int bpi_patterns_diag(int n, const int (*iy)[2], int ny, int m, sp_csc **jy, sp_csc **jyp);
/* Dense row-major n x n values D copied onto J's pattern. */
void bpi_fill_from_dense(sp_csc *J, const double *D, int n);
/* J(i,j) = v; entries outside the pattern are a programming error and are ignored. */
void bpi_set(sp_csc *J, int i, int j, double v);

/* The fields every problem names after its prefix: prefix_y0, prefix_yp0, prefix_kind,
 * prefix_names, prefix_res, prefix_jac, prefix_patterns. */
#define BP_PARTS(prefix)                                                                           \
    .y0 = prefix##_y0, .yp0 = prefix##_yp0, .kind = prefix##_kind, .names = prefix##_names,        \
    .res = prefix##_res, .jac = prefix##_jac, .patterns = prefix##_patterns

/* The IVP Test Set's circuits (problems_circuits.c), in the table of problems_testset.c. */
extern const bp_problem bpi_pump, bpi_transamp, bpi_nand;

#endif
