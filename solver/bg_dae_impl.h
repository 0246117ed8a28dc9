/* Internal to the solver: the solver record shared by bg_dae.c (stepping) and bg_dae_init.c
 * (structure analysis and consistent initial values). Not installed. */
#ifndef BG_DAE_IMPL_H
#define BG_DAE_IMPL_H

#include <stddef.h>

#include "bg_dae.h"
#include "bg_fdjac.h"

#define MAXORD 5
#define NPHI (MAXORD + 2)
#define MAX_NEF 10 /* error-test failures in one step */
#define MAX_NCF 10 /* Newton failures in one step */
#define EPS_NEWT 0.33
#define RATE_MAX 0.9
#define RATE_EXTEND 0.5 /* the Newton iteration may go past max_newton ... */
#define NEWTON_EXTEND 2 /* ... up to this many times max_newton iterations */
#define CRAWL_FACTOR 100.0
#define CRAWL_STEPS 200
#define JUMP_WINDOW 1000.0  /* a Newton failure this many round-off steps from tn marks a jump */
#define MAX_AUTO_RESTARTS 1 /* restarts at an unannounced jump before a step is accepted */
/* a first correction of an algebraic unknown larger than JUMP_TOLS tolerances, JUMP_CHANGE times
 * its change over the last step and half its size takes another iteration
 * (first_correction_jumps) */
#define JUMP_TOLS 100.0
#define JUMP_CHANGE 5.0
#define CJ_LOW 0.6
#define CJ_HIGH (1.0 / 0.6)

struct dae_solver {
    int n;
    dae_problem p;
    dae_options o;
    int *kind;
    char **names;
    char **enames; /* equation names, NULL if not given */
    int *rowvar;   /* unknown matched to each equation (messages), -1 if none */
    double *atol;  /* n */
    double *bkpt;  /* sorted breakpoints */
    int nbkpt;
    /* Jacobians and the Newton matrix */
    sp_csc *Jy, *Jyp;
    sp_union *U;
    sp_fdjac *fdy, *fdyp;
    ls_solver *ls;
    int *rowkind;       /* ROW_DIFF: contains y'; ROW_ALG1: algebraic, no index-2 unknown
                           (differentiated at initialisation); ROW_ALG2: algebraic with an index-2
                           unknown */
    int *rowscaled;     /* row scaled by h/alpha in the Newton matrix (ROW_DIFF and ROW_ALG2) */
    int *srows, nsrows; /* the scaled rows, listed */
    int *a2cols, na2;   /* the index-2 columns (scaled by alpha/h), listed */
    int *a1cols, na1;   /* the index-1 algebraic unknowns, listed */
    double cjf;         /* cj the factored matrix was built with */
    int jac_current;    /* Jacobian evaluated at this step's predictor */
    int need_setup;
    double ss; /* Newton rate factor */
    double dn0,
        dn0_last; /* first Newton correction norm of this step and of the last accepted one */
    /* consistent initialisation (bg_dae_init.c) */
    sp_csc *K;               /* stage B: Jacobian in (y'_D, y'_A1, y_A2) */
    int *kslot_yp, *kslot_y; /* entry p of Jyp / Jy -> slot in K, -1 if not used */
    ls_solver *kls;
    int nalg_rows, nalg1_rows;
    int not_semi_explicit; /* an index-2 unknown appears differentiated (allowed, but then
                              dae_consistent_init cannot be used) */
    int *arow;             /* row i -> its number among the algebraic rows, -1 */
    sp_csc *kkt;           /* stage A: [D B^T; B 0], B = algebraic rows of Jy, columns scaled */
    int *kkt_diag, *kkt_b, *kkt_bt; /* slots: diagonal j, entry p of Jy in B and in B^T */
    ls_solver *kktls;
    double *kkt_rhs; /* n + nalg_rows */
    /* drift and projection */
    sp_csc *G;
    aat_solver *aat_proj;
    double *gv, *gw;
    /* BDF state */
    double tn, hh, hused, cj, cjold;
    int kk, kused, knew, phase, ns, nst_local, first;
    int since_fail; /* accepted steps since the last error-test failure */
    double psi[MAXORD + 1], alpha[MAXORD + 1], beta[MAXORD + 1], sigma[MAXORD + 1],
        gamma[MAXORD + 1];
    double alphas, alpha0, ck;
    double *phi[NPHI];
    double *ewt, *werr, *wnewt;
    double *wdiff; /* Newton weights without the index-2 unknowns */
    int has_alg2;
    double *y, *yp, *ypred, *yppred, *ee, *delta, *res, *tmp, *tmp2, *typ;
    double err_k, err_km1;
    /* roots */
    double *glo, *ghi, *gmid;
    double tlo;
    int *rfound;
    int root_pending;
    double troot;
    int ibk;             /* next breakpoint index */
    int restart_pending; /* landed on a breakpoint: restart before the next step */
    int nautorestart;    /* restarts at unannounced jumps since the last accepted step */
    int ncrawl;          /* accepted steps in a row within CRAWL_FACTOR of round-off */
    double t_fail;       /* end of the last step whose Newton iteration failed */
    int init_side;       /* consistent init: 0 at t, +1/-1 just after/before t (breakpoints) */
    int initialized;
    int failed; /* the failure that stopped the integration (< 0), 0 if none */
    /* what the last failed attempt found (names and values), for the final message */
    char note[BG_MESSAGE_SIZE / 2];
    char fail_note[BG_MESSAGE_SIZE / 2]; /* the note of the last Newton failure */
    /* FD context */
    double fd_t;
    const double *fd_y, *fd_yp;
    dae_stats st;
    bg_error err;
};

enum { ROW_DIFF = 0, ROW_ALG1 = 1, ROW_ALG2 = 2 };

double daei_seconds(void);
/* daei_seconds, or 0 with options.no_timing (the timed statistics then stay 0) */
static inline double daei_clock(const dae_solver *s)
{
    return s->o.no_timing ? 0.0 : daei_seconds();
}
const char *daei_vname(const dae_solver *s, int i, char *buf, size_t sz);
/* Name of equation i: its eq_name, else "equation i (the row of x)"; buf holds at least 160. */
const char *daei_ename(const dae_solver *s, int i, char *buf, size_t sz);
/* Records what the last failed attempt found (printf format) in s->note. */
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
void daei_note(dae_solver *s, const char *fmt, ...);
/* Residual with timing, counting and NaN detection: 0, > 0 recoverable, < 0 fatal. */
int daei_call_res(dae_solver *s, double t, const double *y, const double *yp, double *F, int fd);
/* Jy, Jyp at (t, y, yp); F = F(t, y, yp) is needed by the finite-difference path. */
int daei_eval_jac(dae_solver *s, double t, const double *y, const double *yp, const double *F);
void daei_set_weights(dae_solver *s, const double *y);
double daei_wrms(const dae_solver *s, const double *v, const double *w);
void daei_sync_stats(dae_solver *s);
/* Row classes, checks of the kinds against the patterns, and the initialisation matrices. */
int daei_init_setup(dae_solver *s, bg_error *err);
void daei_init_free(dae_solver *s);
/* dae_consistent_init without the check of the call order (restarts at breakpoints). */
int daei_consistent_init(dae_solver *s);

#endif
