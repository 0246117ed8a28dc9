/* Internal to consistent initialisation: the interface between dae_ic.c (set-up, the algebraic
 * constraints, the warning, the entry points) and dae_ic_newton.c (the hidden constraints, the
 * Newton iteration for y' and the index-2 unknowns, the measurement of the values returned, the
 * derivatives of the index-2 unknowns). Not installed. The method is described at the top of
 * dae_ic.c. */
#ifndef BG_DAE_IC_IMPL_H
#define BG_DAE_IC_IMPL_H

#include "bg_dae_impl.h"

#define IC_MAX_ITER 25
#define IC_NLEV 30   /* table entries a constraint row keeps (the hidden constraints) */
#define IC_NLEV_C 14 /* table entries every row keeps (the derivatives of the index-2 ones) */
/* A Newton correction whose largest weighted component (1 = the tolerance: the error weights
 * 1 / (rtol |x| + atol) of each unknown, y' weighted alike) is below this is not applied: the
 * values are consistent to a millionth of the tolerance, and values given consistent stay as
 * they are. */
#define IC_NEGLIGIBLE 1e-6
/* The shortest span of the run (dae_ic.c) taken as the time scale of the differences in t:
 * sqrt(eps) = 1.5e-8 time units; a shorter one counts as not known (scale 1). At t = 0 the
 * scale is the span of the run (t_stop, the first breakpoint), so that a fast circuit's inputs
 * are not differenced across a period; but the differences start at T_FIRST of the scale and
 * the index-2 rates take second differences from there, whose round-off grows as eps |F| / h^2:
 * from a span of 1e-300 every point underflowed and failed (a crane run with --t-end 1e-300),
 * and from sqrt(eps) itself a pendulum's dlam/dt came out at a third of its value. The bound
 * is the forward-difference step h = sqrt(eps) max(|t|, typ t) of Dennis and Schnabel
 * (Numerical Methods for Unconstrained Optimization and Nonlinear Equations, Prentice-Hall
 * 1983, sec. 5.4) with the time unit as typ t (the sqrt(unit roundoff) of IDA's
 * difference-quotient increments): a span below it is not a scale the differences can use,
 * and the scale 1 with hidden_t's shrinking steps (dae_ic_newton.c) finds the smooth step as
 * for a run of unknown length. Runs of 1.5e-8 time units and longer keep their own scale; so
 * does a start time |t| >= 1.5e-8 (below, |t| is no scale either: from t0 = 1e-300 every point
 * failed as well). The scale bounds the steps in t from above only: the derivatives of the
 * index-2 unknowns that the steps within it cannot resolve are taken again at the scale 1
 * (daei_ic_alg2_rates). */
#define IC_TSCALE_MIN 1.4901161193847656e-08 /* sqrt(DBL_EPSILON) = 2^-26 */

/* Scratch vectors of s->ic_w, n values each. */
enum {
    IC_GUESS,  /* the values given (dae_consistent_init), y */
    IC_GUESSP, /* and y' */
    IC_DA1,    /* the first correction of the algebraic constraints (the warning) */
    IC_F1,     /* residuals at the points of the differences */
    IC_F2,
    IC_F3,
    IC_YK,  /* a point of the differences */
    IC_H,   /* the hidden constraints (rows ROW_ALG1) */
    IC_HT,  /* their part in t */
    IC_HTE, /* the error estimates of their part in t */
    IC_HE,  /* the error estimates of their part along y' */
    IC_HA,  /* the earlier estimate in t; the one-sided difference along y' */
    IC_SC,  /* the scales of the hidden constraints */
    IC_TY,  /* per constraint row, the time scale along y' */
    IC_YC,  /* the central difference along y' of the constraint rows */
    IC_EC,  /* and its error estimates */
    IC_SY,  /* y and y' where stage B started */
    IC_SYP,
    IC_R,   /* the residual of the Newton iteration for y' and the index-2 unknowns */
    IC_U,   /* its correction */
    IC_UD,  /* the correction without the residuals within their noise */
    IC_DEN, /* row scales */
    IC_NWORK
};

static inline double *daei_icw(dae_solver *s, int k)
{
    return s->ic_w + (size_t)k * (size_t)s->n;
}

/* The residual at (t, y, yp) through daei_call_res; a failure is described in s->note with
 * the time relative to the initial time s->tn ("t = 0 (just after)", "t = 0 + 1.2e-06"). */
int daei_ic_res(dae_solver *s, double t, const double *y, const double *yp, double *F);
/* F = F(t, y, yp) into s->res and the Jacobians at the point. */
int daei_ic_eval_all(dae_solver *s, double t, const double *y, const double *yp);
/* DAE_INIT_FAIL or DAE_CALLBACK_FAIL (status r < 0) naming what failed and s->note. */
int daei_ic_cb_fail(dae_solver *s, int r, const char *what);
/* den_i = 1 + sum_j |dF_i/dy_j y_j| + |dF_i/dy'_j y'_j| (the Jacobians' current values): the
 * size of row i's terms, against which its residual is scaled. */
void daei_ic_row_scales(dae_solver *s, const double *y, const double *yp, double *den);
/* Factor M with ls and solve M x = rhs in place (timed). */
int daei_ic_factor_solve(dae_solver *s, ls_solver *ls, const sp_csc *M, double *rhs);

/* What the iteration for y' and the index-2 unknowns reached, measured at the values it
 * returns. */
typedef struct ic_outcome {
    int converged; /* the last correction was negligible, or stalled below the tolerance */
    double rnorm;  /* largest scaled residual: rows of F, and the hidden constraints */
    int rworst;    /* its row */
    int rhidden;   /* that row is a hidden constraint */
    double unorm;  /* largest weighted component of the correction the residual calls for */
    double tstep;  /* a step in t (signed) over which the residual was found smooth */
} ic_outcome;

/* Stage B (dae_ic.c has the method): y' of the differential and index-1 unknowns and y of the
 * index-2 ones at t (the equations evaluated at te, one rounding unit past it), y_D and y_A1
 * fixed. side: the direction of the differences in t (+1, or -1 for left-hand values), tscale
 * their time scale. BG_OK with *out filled (a failure to converge is the caller's to judge),
 * or a failure with its message. */
int daei_ic_stage_b(dae_solver *s, double te, double side, double tscale, double *y, double *yp,
                    ic_outcome *out);
/* Whether stage B's outcome is a failure: not converged with a scaled residual above 1e-6, or
 * above 1e-8 at all (the derivatives may stay inconsistent at the level the linear algebra
 * reaches on an ill-conditioned system, stiff bars next to tiny rotary inertias: 1e-7 of the
 * terms; the first steps correct that, so only a gross failure is reported). */
int daei_ic_failed(const ic_outcome *o);
/* The derivatives of the index-2 unknowns at the consistent values (y, yp) found by stage B,
 * into yp (left at 0 where their error estimate, at least the round-off of the differences, is
 * not small); tstep: stage B's smooth step, tscale its time scale. Where tscale < 1 (the span
 * of a short run) left some of them unknown, these are taken again from the smooth step of
 * the time scale 1 (a run of unknown length). BG_OK or a failure of the residual. */
int daei_ic_alg2_rates(dae_solver *s, double te, double tscale, double tstep, const double *y,
                       double *yp);

#endif
