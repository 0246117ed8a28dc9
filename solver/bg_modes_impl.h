/* Private to the modal analysis (bg_modes.c, bg_modes_sparse.c): the result record, the
 * context of one computation and the helpers both methods share. Not installed. */
#ifndef BG_MODES_IMPL_H
#define BG_MODES_IMPL_H

#include <complex.h>

#include "bg_jaceval.h"
#include "bg_modes.h"

#define MODE_TWO_PI 6.283185307179586476925286766559

struct dae_modes {
    const dae_problem *p;     /* during dae_modes_compute only */
    const char *const *names; /* the problem's names (NULL: "y[i]") */
    double *nominal;          /* copy of the problem's nominal magnitudes (NULL: 1) */
    int n, d, method;
    int *dif; /* the d differential unknowns */
    double sigma;
    int nmodes, cap;
    dae_mode *modes;
    double *vre, *vim; /* n per mode */
    int counts[3];
};

typedef struct mctx {
    const dae_problem *p;
    const dae_modes_options *o;
    bg_jaceval J;
    sp_union *u;
    ls_solver *ls;
    dae_modes *M;
    double *w1, *w2; /* n each */
    double normA, normB;
    bg_error *err;
} mctx;

double mode_frob(const sp_csc *A);
int mode_factor_shift(mctx *c, double *sigma);
int mode_add(dae_modes *M, double re, double im, int kind, double rcond, const double *zr,
             const double *zi, double residual);
double mode_pencil_residual(mctx *c, double complex s, const double *zr, const double *zi);
void mode_sort(dae_modes *M);
/* The nominal magnitude of unknown i (1 when the problem has none). */
double mode_nominal(const dae_modes *m, int i);
/* All modes by the reduced dense eigenproblem (bg_modes_dense.c). */
int mode_dense(mctx *c);
/* The lowest or a window of modes of a large model by ARPACK (bg_modes_sparse.c). */
int mode_sparse(mctx *c);
/* bg_jaceval_steadiness's ratio above which a moving state is refused (rounding and the
 * difference's own error are about 1e-7) */
#define MODES_STEADY_TOL 1e-4
/* The fastest unknown of a moving state, largest |yp_i| / (|y_i| + nominal_i), for messages. */
int mode_fastest(const dae_problem *p, const double *y, const double *yp);
/* dae_modes_compute with o->frame (bg_modes_frame.c): the arguments checked already. */
int mode_in_frame(const dae_problem *p, double t, const double *y, const double *yp,
                  const dae_modes_options *o, dae_modes **out, bg_error *err);

#endif
