/* Internal (not installed): the Jacobians dF/dy and dF/dy' of a dae_problem at a point, from the
 * problem's analytic Jacobian on its patterns or, without one, by coloured forward differences
 * (dense patterns when none are declared), and the names of unknowns and equations for messages.
 * Shared by the static solver (bg_static.c) and the modal analysis (bg_modes.c). */
#ifndef BG_JACEVAL_H
#define BG_JACEVAL_H

#include "bg_dae.h"
#include "bg_fdjac.h"

typedef struct bg_jaceval {
    const dae_problem *p;
    int n;
    sp_csc *Jy, *Jyp;       /* values at the last evaluation, on the problem's patterns */
    sp_fdjac *fdy, *fdyp;   /* finite differences (no analytic Jacobian) */
    double *F0, *F1, *ycopy; /* n each: scratch of the differences */
    double t;               /* the point of the differences */
    const double *y, *yp;
    long res_evals, jac_evals;
    int status; /* the residual's last non-zero status inside the differences */
} bg_jaceval;

/* BG_OK, or BG_ERR_ARGUMENT / BG_ERR_PATTERN / BG_ERR_MEMORY with the reason in err (J is then
 * freed). */
int bg_jaceval_init(bg_jaceval *J, const dae_problem *p, bg_error *err);
void bg_jaceval_free(bg_jaceval *J);
/* The residual F(t, y, yp) into F (zeroed first); the callback's status. */
int bg_jaceval_res(bg_jaceval *J, double t, const double *y, const double *yp, double *F);
/* J->Jy, J->Jyp at (t, y, yp); F = F(t, y, yp) may be given (NULL: evaluated when the
 * differences need it). The callback's status, or BG_ERR_MEMORY. */
int bg_jaceval_eval(bg_jaceval *J, double t, const double *y, const double *yp, const double *F);

/* Whether the state (t, y, yp) stays a solution along its own motion, the condition for its
 * linearisation (the pencil dF/dy, dF/dy') to describe small motions about it with constant
 * coefficients and for constant rates yp to be a steady motion: the total derivative
 * dF/dt = dF/dy yp + dF/dt|explicit, by a forward difference along (1, yp) of step h (h = 1e-7
 * over the largest relative rate |yp_i| / (|y_i| + nominal_i)), must vanish against its terms,
 * sum_j |dF/dy_ij yp_j| (J->Jy as evaluated at this state, before the call). A motion along
 * ignorable coordinates (a shaft angle growing under a constant rate, a mass dragged at constant
 * speed through a linear spring) keeps every equation; a structure spinning in the inertial
 * frame does not (its positions move along directions that rotate). The difference of an
 * equation counts beyond its rounding only, 128 DBL_EPSILON times the size of its terms,
 * |F_i| + sum_j |dF/dy_ij y_j| + |dF/dy'_ij yp_j|: an equation the motion leaves all but
 * unchanged would otherwise show that rounding over h as a rate (a stiff element's force,
 * 4e-9 of rounding over h = 6e-9). *ratio receives the largest
 * |dF/dt_i| / sum_j |dF/dy_ij yp_j| over the equations whose terms are above rounding, *row its
 * equation (-1: yp zero, or none). 0, or the residual's status (BG_ERR_MEMORY); scratch: J->F0,
 * J->F1, J->ycopy (J->Jy, J->Jyp are left as they were).
 * With a co-moving frame's generator S (bg_modes.h; NULL: none) the motion is that frame's
 * flow: y moves along yp and yp itself turns along S yp (a state steady in the frame), so the
 * difference is taken along (1, yp, S yp) and the terms include sum_j |dF/dy'_ij (S yp)_j|. */
int bg_jaceval_steadiness(bg_jaceval *J, double t, const double *y, const double *yp,
                          const sp_csc *S, double *ratio, int *row);

/* The name of unknown i / equation i: the problem's, else "y[i]" / "equation i" written into buf. */
const char *bg_var_label(const dae_problem *p, int i, char *buf, size_t size);
const char *bg_eq_label(const dae_problem *p, int i, char *buf, size_t size);

/* The checks of a problem's data shared by the integrator (dae_create), the static solver and
 * the modal analysis, so that the three refuse the same values with the same words.
 * bg_check_nominal: every nominal magnitude (dae_problem.nominal, NULL: none) finite and > 0
 * (they scale the absolute tolerances and the amplitudes: 0, a negative value or NaN gives
 * weights that are not norms). bg_check_state: the n values of v (what: "starting value",
 * "value", "derivative") finite. BG_OK, or status with a message from where that names the
 * unknown (p->names, else y[i]) and the value. */
int bg_check_nominal(const dae_problem *p, const char *where, bg_error *err);
int bg_check_state(const dae_problem *p, const double *v, const char *what, int status,
                   const char *where, bg_error *err);

#endif
