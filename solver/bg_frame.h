/* Internal (not installed): a problem F(t, y, y') = 0 seen in a moving frame of the linear
 * kind that bg_modes.h ("Co-moving frames") describes: y = Phi_t(z), the flow of
 * y' = S y + c, so that y' = S y + c + (the frame's own rates z'). At the instant the frame
 * passes the state (y = z) the problem in the frame is
 *     G(t, z, z') = F(t, z, S z + c + z'),
 * with dG/dz = dF/dy + dF/dy' S and dG/dz' = dF/dy'. A state steady in the frame (z' = 0) is a
 * state at rest of G, and the pencil of G there is the co-moving frame's linearisation. The
 * static solver and the modal analysis apply their own methods to G. */
#ifndef BG_FRAME_H
#define BG_FRAME_H

#include "bg_dae.h"

typedef struct bg_frame {
    dae_problem q;        /* G, with p's names, equation names, nominals, kinds and
                             constraints (y = z: the positions' constraints are the same) */
    const dae_problem *p; /* F */
    const sp_csc *S;      /* n x n */
    double *c;            /* n: the affine part (copy; zeros when none is given) */
    double *yp;           /* scratch: S z + c + z' */
    sp_csc *Jy, *Jyp;     /* F's Jacobians (on p's patterns) */
    sp_csc *pat_y;        /* the pattern of dF/dy + dF/dy' S */
    int *slot_y;          /* Jy's entry k at pat_y->val[slot_y[k]] */
    int *slot_prod;       /* the products Jyp(i, k) S(k, j), in the loop order of
                             frame_jac, at pat_y->val[slot_prod[...]] */
    long nprod;
} bg_frame;

/* S n x n (checked: shape, well-formed, finite values); c n values or NULL (zeros). BG_OK, or
 * BG_ERR_ARGUMENT / BG_ERR_MEMORY with a message from where. */
int bg_frame_init(bg_frame *f, const dae_problem *p, const sp_csc *S, const double *c,
                  const char *where, bg_error *err);
void bg_frame_free(bg_frame *f);
/* How far (t, y, yp) is from steady along the flow of y' = S y + c (bg_jaceval_steadiness: the
 * largest relative change of an equation, *ratio, and its row, *row). BG_OK, or BG_ERR_MEMORY /
 * BG_ERR_CALLBACK (the residual or Jacobian failed) with a message from where. */
int bg_frame_steadiness(const dae_problem *p, const sp_csc *S, double t, const double *y,
                        const double *yp, double *ratio, int *row, const char *where,
                        bg_error *err);

#endif
