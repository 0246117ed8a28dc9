/* Internal to the solver: the solver record and the interfaces between the integrator's parts.
 * Not installed; nothing here is exported from the shared library.
 *
 * The index of the integrator's files, the one place that lists them (each file's own header
 * comment gives its method and references):
 *   bg_dae.h          the public interface: problem, options, statistics, the calls
 *   bg_dae_impl.h     this header: the solver record, the interfaces between the parts
 *   bg_dae.c          the outer loop: dae_init, dae_reinit, dae_set_history, dae_solve_to and
 *                     dae_step over daei_step (stops, roots, restarts, projection), getters
 *   dae_create.c      dae_options_default, checks of the problem and options, dae_create,
 *                     dae_free
 *   dae_step.c        daei_step, one step: coefficients, prediction, the retry loop and its
 *                     failure policy
 *   dae_nls.c         daei_newton, the corrector: Jacobian reuse, the scaled Newton matrix,
 *                     linear solves
 *   dae_err.c         error control: weights and norms, the error test, order and step
 *                     selection, the first step
 *   dae_stab.c        the stability guard (options.stability_guard): the order lowered where a
 *                     lightly damped oscillation holds orders 3..5 at their stability limit
 *   dae_disc.c        discontinuities: restarts at breakpoints and unannounced jumps, the crawl
 *                     stop, the first-correction rule
 *   dae_out.c         output: dae_dense, roots of event functions, drift and projection
 *   dae_eval.c        residual and Jacobian calls, names and notes for messages, dae_stats_line
 *                     and _csv, dae_return_name
 *   dae_struct.c      structure: dae_classify, the maximum matching
 *   dae_ic.c          row classes and consistent initial values (dae_consistent_init)
 *   dae_ic_newton.c   their Newton iteration for y' and the index-2 unknowns
 *   dae_ic_impl.h     the interface between dae_ic.c and dae_ic_newton.c
 *   dae_reduce.c      index reduction of the constraints (DAE_I2_REDUCE)
 *   dae_mebdf.c       the modified extended BDF step (options.method = DAE_MEBDF): two BDF
 *                     stages and Cash's formula with the same Newton matrix
 * The rest of solver/ has interfaces of its own: what the integrator builds on (bg_status,
 * bg_sparse, bg_linsol, bg_fdjac), what builds on its problem form (bg_static, and bg_modes
 * with bg_modes_dense.c, bg_modes_sparse.c, bg_modes_frame.c and bg_modes_impl.h, both through
 * bg_jaceval and, in a co-moving frame, bg_frame), bg_trim (the trim's root finder of model files and the crane's
 * static start), and bg_api.h, the export mark. */
#ifndef BG_DAE_IMPL_H
#define BG_DAE_IMPL_H

#include <float.h>
#include <math.h>
#include <stddef.h>

#include "bg_dae.h"
#include "bg_fdjac.h"

#define MAXORD 7     /* the largest k: MEBDF (order k + 1); BDF stops at BDF_MAXORD */
#define BDF_MAXORD 5
#define STAB_WIN 5 /* error estimates kept by the stability guard (dae_stab.c) */
#define NPHI (MAXORD + 2)
#define MAX_NEF 10 /* error-test failures in one step */
#define MAX_NCF 10 /* Newton failures in one step */
#define MAX_REPROBE 20 /* probes of the residual for missing pattern entries in a run */
#define EPS_NEWT 0.33
#define CJ_LOW 0.6
#define CJ_HIGH (1.0 / 0.6)

/* Loops over the unknowns in pairs, as two-lane vectors: DAEI_VFOR(i, n, body) runs body for i
 * = 0, 2, 4, ... with V a vector of two doubles, then for the odd last unknown with V a vector
 * of one; in body, VAT(p, i) is the V at p + i (no alignment assumed) and a scalar operand
 * stands for a vector of copies of it. GCC at -O2 vectorizes a loop only where it knows the trip
 * count to be a multiple of the vector length (its "very cheap" cost model), which leaves most of
 * the integrator's loops over the unknowns scalar; these are vectors regardless. Each lane does
 * the operations of the scalar loop on its unknown in the same order: the same bits. Not for
 * running sums (their order would change). VABS(x) is |x| (the sign bit cleared, as fabs);
 * VI, VATI: the same for long long; VMASK(x, m) is x where the mask m has all bits set, +0
 * where it is 0. Without GCC's vector extension, the plain loop. */
#if defined(__GNUC__)
typedef double daei_v2 __attribute__((vector_size(2 * sizeof(double)), aligned(sizeof(double)),
                                      may_alias));
typedef double daei_v1 __attribute__((vector_size(sizeof(double)), may_alias));
typedef long long daei_v2i __attribute__((vector_size(2 * sizeof(long long)),
                                          aligned(sizeof(long long)), may_alias));
typedef long long daei_v1i __attribute__((vector_size(sizeof(long long)), may_alias));
#define UNUSED_ __attribute__((unused))
#define DAEI_VFOR(i, n, ...)                                                                       \
    do {                                                                                           \
        int i = 0;                                                                                 \
        {                                                                                          \
            typedef daei_v2 V;                                                                     \
            typedef daei_v2i VI UNUSED_;                                                           \
            for (; i + 2 <= (n); i += 2) {                                                         \
                __VA_ARGS__                                                                        \
            }                                                                                      \
        }                                                                                          \
        {                                                                                          \
            typedef daei_v1 V;                                                                     \
            typedef daei_v1i VI UNUSED_;                                                           \
            for (; i < (n); i++) {                                                                 \
                __VA_ARGS__                                                                        \
            }                                                                                      \
        }                                                                                          \
    } while (0)
#define VABS(x) ((V)((VI)(x) & 0x7fffffffffffffffLL))
#define VMASK(x, m) ((V)((VI)(x) & (m)))
#else
#define DAEI_VFOR(i, n, ...)                                                                       \
    do {                                                                                           \
        typedef double V;                                                                          \
        typedef long long VI;                                                                      \
        for (int i = 0; i < (n); i++) {                                                            \
            __VA_ARGS__                                                                            \
        }                                                                                          \
    } while (0)
#define VABS(x) fabs(x)
#define VMASK(x, m) ((m) ? (x) : 0.0)
#endif
#define VAT(p, i) (*(V *)&(p)[i])
#define VATI(p, i) (*(VI *)&(p)[i])
/* a function inlined wherever it is called (constant arguments then specialize it) */
#if defined(__GNUC__)
#define DAEI_INLINE static inline __attribute__((always_inline))
#else
#define DAEI_INLINE static inline
#endif

typedef struct dae_reduce dae_reduce;

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
    int *tcols, ntcols; /* the unknowns the error test weighs (werr not always 0), ascending:
                           all but exclude_alg's index-1 ones and DAE_I2_EXCLUDE's index-2 ones */
    long long *wmask;   /* per unknown, all bits set, or 0 where daei_set_weights sets werr to 0
                           (exclude_alg's index-1 unknowns) */
    double cjf;         /* cj the factored matrix was built with */
    long jac_nst;       /* steps taken when the Jacobian was evaluated */
    int *reg_jac;       /* regimes at the last Jacobian evaluation (p.nregimes) */
    int *reg_now;       /* and at the point being checked */
    int reg_valid;      /* reg_jac holds them */
    int reg_failed;     /* the regimes callback failed last (daei_call_regimes) */
    double cjj;         /* cj at the last Jacobian evaluation (cjf without newton_dgmax) */
    int need_refactor;  /* the matrix again from the saved Jacobian at this cj (newton_dgmax) */
    int jac_current;    /* Jacobian evaluated at this step's predictor */
    int need_setup;
    double ss; /* Newton rate factor */
    double dn0,
        dn0_last; /* first Newton correction norm of this step and of the last accepted one */
    /* consistent initialisation (dae_ic.c) */
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
    /* the unknowns the caller reads of the states returned (dae_set_output_unknowns): out_idx[0 ..
     * nout_idx - 1]; nout_idx 0: all */
    int *out_idx, nout_idx;
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
    double *ewt, *werr, *wnewt; /* wnewt is ewt unless o.newton_index2_scale_h */
    double *wdiff; /* Newton weights without the index-2 unknowns */
    int has_alg2;
    double *y, *yp, *ee, *delta, *res, *tmp, *tmp2, *typ;
    double err_k, err_km1;
    double err_next; /* the error estimate of the order chosen for the next step */
    /* stability guard (dae_stab.c) */
    double *stab_e[STAB_WIN]; /* weighted local error estimates of the last steps, newest first,
                                 of the unknowns the error test weighs (tcols) only, packed;
                                 emptied where tcols is made (daei_init_setup) */
    int stab_ns;        /* of them, how many were taken at the current h and order */
    double stab_hs;     /* the step they were taken with */
    int stab_ks;        /* and the order */
    int stab_hits;      /* consecutive fits that found one dominant oscillation */
    double stab_theta;  /* h omega of the last such fit */
    double stab_w;      /* omega of the dominant undamped oscillation, 0: none known */
    int stab_on;        /* the policy of the current phase: 1 lowering, 0 the usual orders */
    long stab_len;      /* the phase's length (accepted steps) */
    long stab_cnt;      /* accepted steps in it so far */
    double stab_tmark;  /* its start: time */
    long stab_amark;    /* and step attempts (accepted, rejected, Newton failures) */
    double stab_pace[2]; /* time per attempt measured in the last phase of each policy, 0: none */
    long stab_win[2];   /* exploitation length of each policy, doubled at each win */
    int stab_probe;     /* the current phase measures a policy (1) or uses the better one (0) */
    int stab_last;      /* the policy the last comparison chose, -1: none yet */
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
    int detect;     /* patterns not given: found from the residual (dae_struct.c) */
    int structured; /* patterns, Newton matrix structure, row classes built */
    int nreprobe;   /* patterns probed again after Newton failures */
    long fact_off[3]; /* factorization counts of the linear solvers of an earlier structure */
    double *yc;       /* y and y' of the last dae_consistent_init (2n), NULL if none */
    int jac_checked;  /* options.check_jacobian done */
    double jac_suspect_rate; /* > 0: the Newton rate on a Jacobian evaluated at its step that
                                calls for the automatic check (dae_nls.c), at jac_suspect_t */
    double jac_suspect_t;
    bg_error warn;    /* the last warning */
    int busy;         /* inside dae_solve_to, dae_step, dae_consistent_init: a callback that
                         calls them again gets BG_ERR_STATE */
    int failed; /* the failure that stopped the integration (< 0), 0 if none */
    /* what the last failed attempt found (names and values), for the final message */
    char note[BG_MESSAGE_SIZE / 2];
    char fail_note[BG_MESSAGE_SIZE / 2]; /* the note of the last Newton failure */
    /* FD context */
    double fd_t;
    const double *fd_y, *fd_yp;
    dae_stats st;
    bg_error err;
    /* consistent initialisation, continued (dae_ic.c, dae_ic_newton.c, dae_ic_impl.h) */
    int ic_a_alg2;  /* stage A takes the ROW_ALG2 rows too: declared kinds leave an index-1
                       unknown that the constraint rows (ROW_ALG1) do not determine */
    double *ic_w;   /* scratch, IC_NWORK vectors of n */
    double *ic_tab; /* the extrapolation tables of the hidden constraints, per ROW_ALG1 row */
    int *ic_rows;   /* the ROW_ALG1 rows, listed (nalg1_rows) */
    int *ic_run;    /* scratch of the extrapolation tables, n */
    double ic_res;  /* the last daei_consistent_init: scaled residual at the values returned */
    double ic_err;  /* and the weighted correction it calls for (1 = the tolerance) */
    dae_reduce *red; /* DAE_I2_REDUCE: the problem as given and the reduction (dae_reduce.c) */
    double *mb;      /* DAE_MEBDF: MB_NVEC vectors of n (dae_mebdf.c) */
    double mb_psik;  /* DAE_MEBDF: psi[k] of the last accepted step, of order mb_k */
    int mb_k;
    int mb_kp1;      /* DAE_MEBDF: the step's error estimate is that of order k + 1 */
};

enum { ROW_DIFF = 0, ROW_ALG1 = 1, ROW_ALG2 = 2 };

/* ---- dae_eval.c: callbacks, names, notes, statistics ---- */
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
/* First entry of v[0..n) that is not finite, -1 if none. */
int daei_first_nonfinite(const double *v, int n);
/* The unknown with the largest |v_i w_i|, -1 if all are zero. */
int daei_largest_weighted(const dae_solver *s, const double *v, const double *w);
/* Residual with timing, counting and NaN detection: 0, > 0 recoverable, < 0 fatal. */
int daei_call_res(dae_solver *s, double t, const double *y, const double *yp, double *F, int fd);
/* The problem's regimes at (t, y) into r (dae_problem.regimes): 0, or a fatal status (< 0) with
 * s->note naming the regimes callback and s->reg_failed set. The callback's 0 is success and
 * any other value is fatal (bg_dae.h, dae_regime_fn): its own status if < 0, BG_ERR_CALLBACK
 * for one > 0. */
int daei_call_regimes(dae_solver *s, double t, const double *y, int *r);
/* Jy, Jyp at (t, y, yp); F = F(t, y, yp) is needed by the finite-difference path. Then the
 * regimes the Jacobian belongs to (daei_call_regimes). */
int daei_eval_jac(dae_solver *s, double t, const double *y, const double *yp, const double *F);
void daei_sync_stats(dae_solver *s);
/* The time t as messages give it, relative to s->tn: "t = 0", "t = 0 (just after)" (one
 * rounding unit), "t = 0 + 1.2e-06"; s->tn in the shortest of %.15g .. %.17g that reads back as
 * it (dae_eval.c). */
const char *daei_when(const dae_solver *s, double t, char *buf, size_t sz);
/* Records a warning (printf format) in s->warn, counts it and passes it to the error handler
 * with DAE_WARNING. */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
void daei_warn(dae_solver *s, const char *where, const char *fmt, ...);

/* ---- dae_err.c: error control ---- */
void daei_set_weights(dae_solver *s, const double *y);
double daei_wrms(const dae_solver *s, const double *v, const double *w);
/* The local error test of the step just corrected: 0 pass, 1 fail. Sets err_k, err_km1 and
 * knew, the order the estimates favour. */
int daei_error_test(dae_solver *s);
/* Order and step for the next step after an accepted one (kdiff: the order change of the step
 * just taken). */
void daei_choose_next(dae_solver *s, int kdiff);
/* Order and step after the nef-th error-test failure of one step. */
void daei_after_error_fail(dae_solver *s, int nef);
/* Initial step and history from phi[0] = y, phi[1] = y' (unscaled); dir 0: from tout. */
int daei_first_step(dae_solver *s, double tout, double hpref, double dir);

/* ---- dae_step.c: one step ---- */
/* The smallest step t can take here: a few units of round-off of t. */
static inline double daei_roundoff_h(const dae_solver *s)
{
    return 4 * DBL_EPSILON * fabs(s->tn);
}
/* Next time the step must land on (breakpoint or t_stop) beyond tn in direction dir, or NAN. */
double daei_next_stop(const dae_solver *s, double dir, int *is_bkpt);
/* h clipped to the next stop (t_stop or a breakpoint) and to h_max. A step that reaches the
 * stop (or passes it by 0.01 % or less) lands on it. Before t_stop, a step that would leave
 * less than a quarter of itself is replaced by two equal steps, so that no step is followed by
 * a sliver: a last step of a few percent of the one before changes alpha/h as much, and on
 * index-2 problems the Newton iteration of such a step can diverge (its index-2 unknowns are
 * O(1/h)); the last step is at least a quarter of the one before. Not before breakpoints,
 * where the history ends anyway: on the IVP Test Set's charge pump, whose inputs have a
 * breakpoint every few nanoseconds, the split cost digits and, at rtol 2e-8, a collapse after a
 * restart. (Splitting whenever fewer than two steps remain cost accuracy at t_stop: a sliver is
 * a very accurate last step; ap102 lost 0.8 digits.) */
void daei_clip_to_stop(dae_solver *s);
/* daei_step's results besides a failure (< 0) */
enum { STEP_TAKEN = 0, STEP_ON_BREAKPOINT = 1, STEP_JUMP = 2 };
int daei_step(dae_solver *s);

/* ---- dae_nls.c: the Newton corrector ---- */
enum { NL_OK = 0, NL_RECOVER = 1, NL_RES_RECOVER = 2, NL_SINGULAR = 3, NL_LSFAIL = 4 };
/* Corrects the predicted y, yp at t; ee holds the sum of the corrections. NL_*, or < 0 fatal
 * (a callback's status). A failure is described in s->note. */
int daei_newton(dae_solver *s, double t);

/* ---- dae_mebdf.c: the modified extended BDF step (options.method = DAE_MEBDF) ---- */
#define MB_NVEC 7
/* The corrector of a MEBDF step, after the BDF coefficients and prediction of order k for the
 * step to t (the step's end): the BDF solution at t, the BDF solution at t + h from it, then
 * the MEBDF solution at t with the same Newton matrix. Leaves y, yp and ee = y - ypred as
 * daei_newton does. teval: the time the residual of the first stage sees (a breakpoint's
 * left-hand side); bdf_only: the step ends on (or its second stage would pass) a stop, BDF
 * alone. NL_* or a fatal status, as daei_newton. */
int daei_mebdf_correct(dae_solver *s, double t, double teval, int bdf_only);
/* The error test of a MEBDF step (in place of daei_error_test): 0 pass, 1 fail; sets err_k,
 * err_km1 and knew as daei_error_test does, in Cash and Considine's constants. */
int daei_mebdf_error_test(dae_solver *s);
/* Order and step after an accepted MEBDF step (in place of daei_choose_next). */
void daei_mebdf_choose_next(dae_solver *s, int kdiff);

/* ---- dae_disc.c: discontinuities ---- */
/* Whether the first Newton correction (its weighted RMS norm dn, with the Newton weights) shows
 * a jump the predictor missed (another iteration). */
int daei_first_correction_jumps(const dae_solver *s, double dn);
/* Book-keeping of an accepted step (crawl count, restarts since the last accepted step). */
void daei_disc_accepted(dae_solver *s);
/* DAE_STEP_TOO_SMALL with its message when the run crawls, else BG_OK. */
int daei_crawl_check(dae_solver *s);
/* Whether a step that fell below the step floor marks an unannounced jump at tn. */
int daei_jump_suspected(const dae_solver *s, int nef, int ncf);
/* Restart with consistent values at a breakpoint (dt = 0, jump = 0), or at an unannounced jump
 * at tn + dt (jump = 1). */
int daei_restart(dae_solver *s, double tout, double dt, int jump);
/* The restart after daei_step reported STEP_JUMP: DAE_SUCCESS when tout was reached before
 * the restart point (*tret = tout, y and yp set), 1 to go on stepping, < 0 on failure. */
int daei_restart_at_jump(dae_solver *s, double tout, double dir, int one, double *tret,
                         double *y, double *yp);

/* ---- dae_stab.c: the stability guard ---- */
/* After an accepted step (before the order and step for the next one are chosen): fits the
 * error estimates of the last three steps for a dominant oscillation. */
void daei_stab_observe(dae_solver *s);
/* After the order and step for the next step were chosen: lowers the order where the step lies
 * in the unstable band of BDF orders 3..5 for the dominant oscillation. */
void daei_stab_decide(dae_solver *s);
/* Forget what was learnt (a restart, dae_init). */
void daei_stab_reset(dae_solver *s);

/* ---- dae_out.c: output ---- */
/* The history's interpolating polynomial at t (after a step), without dae_dense's check. */
void daei_interpolate(const dae_solver *s, double t, double *y, double *yp);
/* daei_interpolate at the unknowns idx[0 .. m-1] only (the others untouched): the same values. */
void daei_interpolate_some(const dae_solver *s, double t, const int *idx, int m, double *y,
                           double *yp);
/* Interpolated output at t (projected with options.projection), or the last step's values. */
void daei_output_state(dae_solver *s, double t, double *tret, double *y, double *yp);
/* Earliest sign change of the event functions in (tlo, tn]: 1 found, 0 none, < 0 failure. */
int daei_find_root(dae_solver *s);
/* The event functions at (t, y, yp) into g: BG_OK, or DAE_CALLBACK_FAIL raised (from where)
 * for a status other than 0 or a value that is not finite (its index named). */
int daei_call_roots(dae_solver *s, const char *where, double t, const double *y,
                    const double *yp, double *g);
/* Minimum-norm correction of y onto g(t, y) = 0. */
int daei_project_vec(dae_solver *s, double t, double *y);
/* Drift after an accepted step, and projection of y_n if asked. */
int daei_project_step(dae_solver *s);

/* ---- dae_create.c: creation ---- */
/* The structure from s->Jy, s->Jyp: kinds (classified when not given), the Newton matrix's
 * pattern, the matching, finite differences, the linear solver, row classes and the matrices
 * of consistent initialisation. */
int daei_setup_structure(dae_solver *s, bg_error *err);
void daei_free_structure(dae_solver *s);

/* ---- dae_struct.c: structure ---- */
/* The patterns of dF/dy and dF/dy' from the residual alone: each unknown and each derivative is
 * perturbed in turn at npts points (the first at (t, y, yp), the others around it) and the rows
 * whose residual changes are its entries; the union with s->Jy, s->Jyp where they exist
 * replaces them. *added: entries that were not in them. BG_OK, BG_ERR_MEMORY, BG_ERR_ARGUMENT
 * (more entries than an int counts), or DAE_RES_FAIL / DAE_CALLBACK_FAIL when the residual fails
 * at (t, y, yp) itself; the message is in s->err. */
int daei_probe_patterns(dae_solver *s, double t, const double *y, const double *yp, int npts,
                        long *added);
/* Maximum matching of the rows and columns of A restricted to the rows with rowmask[i] != 0
 * and the columns with colmask[j] != 0 (NULL: all), by BTF's maxtrans with each column's
 * diagonal entry tried first: rowvar[i] = the column matched to row i, -1 if none. Returns the
 * number matched, or BG_ERR_MEMORY. */
int daei_match(const sp_csc *A, const int *rowmask, const int *colmask, int *rowvar);

/* ---- dae_ic.c: row classes and consistent initial values ---- */
/* Row classes, checks of the kinds against the patterns, and the initialisation matrices. */
int daei_init_setup(dae_solver *s, bg_error *err);
void daei_init_free(dae_solver *s);
/* dae_consistent_init without the check of the call order (restarts at breakpoints). */
int daei_consistent_init(dae_solver *s);

/* ---- dae_reduce.c: index reduction (DAE_I2_REDUCE) ---- */
/* At dae_create: the inner solver on the problem p as given; when its patterns are known, the
 * reduced problem replaces s->p and the structure is built; else s->detect is set. */
int daei_red_create(dae_solver *s, const dae_problem *p, const dae_options *o, bg_error *err);
/* At dae_init without patterns: the inner solver finds them, then the reduced structure. */
int daei_red_detect(dae_solver *s, double t0, const double *y0, const double *yp0);
/* Consistent values by the inner solver (the system as given, its hidden constraints). */
int daei_red_consistent_init(dae_solver *s);
void daei_red_free(dae_solver *s);
/* Whether the Jacobian as given is by finite differences (patterns may be probed again). */
int daei_red_by_fd(const dae_solver *s);
/* The problem as given probed for pattern entries at (t, y, yp) (daei_probe_patterns); when
 * it finds some (*added > 0), the inner and the reduced structures are built again. */
int daei_red_probe(dae_solver *s, double t, const double *y, const double *yp, long *added);
/* A new run (dae_init): the scales of the time differences start again. */
void daei_red_reset(dae_solver *s);

#endif
