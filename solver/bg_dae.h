/* The modified-BDF integrator for semi-explicit index-2 DAEs F(t, y, y') = 0.
 *
 * Unknowns are of three kinds: differential (y' appears), index-1 algebraic, and index-2
 * algebraic (constraint efforts such as joint reactions, fixed only through the derivative of a
 * constraint). The method is the variable-order (1..5), variable-step BDF in fixed-leading-
 * coefficient form of DASSL and IDA (Brenan, Campbell and Petzold, "Numerical Solution of
 * Initial-Value Problems in DAEs", SIAM 1996, ch. 5), with what index 2 needs on top:
 *   - the local error test excludes the index-2 variables or scales their error by h (option);
 *   - the Newton convergence norm weighs index-2 corrections in full (or scaled by h, option),
 *     the rate estimate restarts when alpha/h changes, and a step may not grow again until k+1
 *     steps have passed since an error-test failure (this stops the fail/grow cycle that
 *     index-2 variables cause in DASSL-type step control);
 *   - the iteration matrix dF/dy + (alpha/h) dF/dy' is scaled (rows that contain y' by h/alpha,
 *     index-2 columns by alpha/h) so that it stays O(1) as h -> 0;
 *   - consistent initial values replace constraint rows by their time derivative;
 *   - optional projection onto position constraints after each step.
 * Inputs that jump (sources, references) belong in options.breakpoints. One that is not given
 * shows as a step that collapses to round-off with the Newton iteration failing on it: with no
 * error-test failure, or with the last Newton failure within 1000 round-off steps of t (the
 * accepted steps close in on a switch that no step crosses, as the IVP Test Set's charge pump
 * does where a transistor switches off). The solver then restarts once at the end of the last
 * failed step as at a breakpoint (stats.restarts counts them; the first step after it follows
 * the new y', as IDA's first step does) and stops with DAE_STEP_TOO_SMALL if the step
 * collapses there again. A step is never accepted with algebraic unknowns left at
 * the predictor's values across such a jump: the first Newton correction counts as converged on
 * an earlier rate estimate only in proportion to its size, and never when it moves an index-1
 * algebraic unknown by more than half its size, 100 tolerances and five times its change over
 * the last step (another iteration then evaluates the residual where the first one went). A
 * tout that falls between the last step and such a restart gets the values before it. A run
 * that crawls (200 accepted steps in a row within 100 times the round-off limit of t, at a
 * switch no step crosses) stops with DAE_STEP_TOO_SMALL, and its message names the last Newton
 * failure.
 *
 * The Newton iteration stops after max_newton iterations, except that with a Newton matrix
 * evaluated at the step itself it goes on, up to 2 max_newton, while it contracts at a rate of
 * 0.5 or better and that rate says it will converge within them: the alternative, a step cut by
 * 4, costs a new Newton matrix and the steps that grow h back, more than the few further
 * iterations (dae_nls.c, newton_extends).
 * The details and the reasons are in the header comments of the solver's parts (solver/dae_*.c,
 * listed in bg_dae_impl.h).
 *
 * Callbacks return 0 for success, > 0 for a recoverable failure (the step is cut and retried),
 * < 0 for a fatal one (the integration stops with DAE_CALLBACK_FAIL). The residual array is
 * zeroed before each call of the residual function; one that fails may set the rows it could not
 * evaluate to NaN, and the failure message then names the first of those equations.
 *
 * Errors. Every function returns a status (bg_status.h, or the dae_return codes below) and, where
 * it has the solver, leaves a message in dae_get_error(s). Misuse: BG_ERR_ARGUMENT (a NULL
 * solver, array or callback that is needed, a size or option out of range: the message names
 * it), BG_ERR_PATTERN (a Jacobian or constraint pattern of the wrong shape or structure),
 * BG_ERR_STATE (stepping before dae_init, or after a failure without dae_reinit; consistent
 * values after the first step). The failures of the integration (DAE_TOO_MUCH_ACC ..
 * DAE_STEP_TOO_SMALL) name the time and what stopped it by the problem's names: the unknown with
 * the largest weighted local error (error test), with the largest weighted Newton correction
 * (convergence), the unknown of the singular column of the Newton matrix, the equation whose
 * residual is NaN or Inf, or the unknown that limits the step; equations without names (eq_names
 * NULL) are called "equation i (the row of x)", x being the unknown matched to row i in a
 * maximum matching of the Newton matrix's pattern that takes the diagonal first. The library
 * never prints. */
#ifndef BG_DAE_H
#define BG_DAE_H

#include <stddef.h>

#include "bg_api.h"
#include "bg_linsol.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum dae_var_kind { DAE_DIFF = 0, DAE_ALG = 1, DAE_ALG2 = 2 } dae_var_kind;

/* F = F(t, y, yp). */
typedef int (*dae_res_fn)(void *user, double t, const double *y, const double *yp, double *F);
/* Values of Jy = dF/dy and Jyp = dF/dy' on the patterns declared in dae_problem (zero them or
 * overwrite every entry). */
typedef int (*dae_jac_fn)(void *user, double t, const double *y, const double *yp, sp_csc *Jy,
                          sp_csc *Jyp);
/* Position-level constraints for projection and drift: g(y) (ncons values) and, if G != NULL,
 * the values of G = dg/dy on cons_pattern. */
typedef int (*dae_cons_fn)(void *user, double t, const double *y, double *g, sp_csc *G);
/* Event functions g(t, y, y') (nroots values): their sign changes are located. Returns 0;
 * any other status, or a value that is not finite, stops dae_init or dae_solve_to with
 * DAE_CALLBACK_FAIL (the message names the event function and the time). */
typedef int (*dae_root_fn)(void *user, double t, const double *y, const double *yp, double *g);
/* Regimes of the problem's switching characteristics at (t, y): nregimes small integers into r
 * (dae_problem.regimes). Returns 0 on success; any other value is fatal: the integration (or
 * dae_consistent_init) stops with DAE_CALLBACK_FAIL and a message that names the regimes
 * callback and the value it returned. A value > 0 is not a request for a smaller step, as it is
 * from the residual: the callback is asked about states the residual has accepted or is about
 * to be evaluated at (the predictor, a converged iterate, the point of a Jacobian), and a
 * classification of the state that fails there fails at a smaller step too. */
typedef int (*dae_regime_fn)(void *user, double t, const double *y, int *r);

typedef struct dae_problem {
    int n;
    dae_res_fn res;
    dae_jac_fn jac;               /* NULL: coloured finite differences on the patterns */
    const sp_csc *jac_y_pattern;  /* n x n pattern of dF/dy; NULL: dense */
    const sp_csc *jac_yp_pattern; /* n x n pattern of dF/dy'; NULL: dense in the differential
                                     columns, i.e. every equation is taken to contain y': give
                                     the patterns for a DAE (the algebraic equations, index-2
                                     unknowns and consistent initialisation are found from
                                     them) */
    const int *kind;              /* n values of dae_var_kind; NULL: found from the patterns by
                                     dae_classify (all differential if no patterns are given).
                                     A DAE_ALG2 variable may appear differentiated (systems that
                                     are not semi-explicit); dae_consistent_init then refuses and
                                     consistent values must be given */
    const char *const *names;     /* n names for messages; NULL: "y[i]" */
    void *user;
    /* optional position constraints (projection, drift) */
    int ncons;
    dae_cons_fn cons;
    const sp_csc *cons_pattern; /* ncons x n pattern of dg/dy */
    /* optional event functions */
    int nroots;
    dae_root_fn roots;
    const char *const *eq_names; /* n names of the equations (rows of F) for messages; NULL (or a
                                    NULL entry): named after the unknown matched to the row */
    const double *nominal;       /* n nominal magnitudes (finite, > 0) in the unknowns' units, or
                                    NULL (all 1): the absolute tolerance of unknown i is
                                    options.atol * nominal[i] (the convention of Modelica tools),
                                    in the error test and in the Newton test alike, so that one
                                    atol means the same for a pressure of 1e7 Pa and an angle of
                                    1 rad. options.atol_vec, when given, is taken as it is */
    /* Optional regimes of sharp but smooth characteristics (a relief valve closed, nearly
       closed, opening or open; a limiter in range or saturated; a rope taut or slack): nregimes integers that
       name the branch each switching element is on at y. The Jacobian is evaluated again
       when they differ from those at its last evaluation: at the predictor of a step, and at
       a converged Newton iterate on a matrix from an earlier step (which then counts as a
       Newton failure on a stale matrix and is redone with a fresh one). Why: across a switch
       a stale matrix can be the stiffer one (the valve's conductance where the valve has
       closed), and a modified Newton iteration on it makes small corrections that the
       convergence test, which sees corrections and not residuals, accepts while the
       switching element's equation is still far from satisfied; the error the iteration
       leaves then acts as a phantom source (a closed valve's residual flow that fills a line
       step after step; the pressure rises smoothly, so the error test does not see it). The
       remedy is the event handling of hybrid DAE solvers reduced to what a smooth model
       needs: at a change of regime the integrator's linearisation is renewed, as Modelica
       tools do at every event (F. E. Cellier and E. Kofman, Continuous System Simulation,
       Springer 2006, ch. 9 on discontinuity handling), without locating the switch or
       restarting the method, since the characteristic is smooth. stats.jac_regime counts the
       Jacobians it caused. */
    int nregimes;
    dae_regime_fn regimes;
} dae_problem;

/* How the index-2 part is integrated. BDF applied to an index-2 system directly is convergent
 * for systems of Hessenberg form (the index-2 unknowns appear only in the differential
 * equations, the constraints contain differential unknowns only; Brenan, Campbell and Petzold,
 * Numerical Solution of Initial-Value Problems in DAEs, SIAM 1996, Theorem 3.2.1): velocity-level
 * multibody models and bond graphs are. It is not in general: on their example
 * y1 + eta t y2 = g(t), y1' + eta t y2' + (1 + eta) y2 = 0 (Section 3.2), where the index-2
 * unknown y2 enters the constraint, BDF1 is unstable for eta < -1/2 and BDF2 for eta < -1/4
 * whatever the step (the recursion (1 + eta) y2_n + eta sum_j j alpha_j y2_{n-j} = ... has a root
 * outside the unit circle), and the run fails with Newton or error-test failures at ever smaller
 * steps. DAE_I2_REDUCE integrates the time derivative of the constraints instead (index 1: BDF of
 * every order converges, Theorem 3.1.1 there) and projects each step back onto them (dae_reduce.c
 * has the method); it costs four more residual evaluations per evaluation and a projection per
 * step, and the derivative of the constraint rows' dF/dy is left out of the Newton matrix. */
typedef enum dae_index2_policy {
    DAE_I2_EXCLUDE = 0, /* index-2 variables take no part in the local error test */
    DAE_I2_SCALE_H = 1, /* their local error estimate is multiplied by h */
    DAE_I2_REDUCE = 2   /* the constraints differentiated once: index 1, projected back onto
                           them after each step (no position constraints of the problem's own:
                           ncons = 0). The kinds, patterns and statistics are then those of the
                           reduced system (the index-2 unknowns become index 1, or differential
                           where the differentiated constraints contain their derivative);
                           stats.reduced_rows counts the constraints, stats.max_drift their
                           largest value before projection */
} dae_index2_policy;

/* The integration method (dae_options.method). */
typedef enum dae_method {
    DAE_BDF = 0,  /* variable-order variable-step BDF (the default; see above) */
    DAE_MEBDF = 1 /* Cash's modified extended BDF (solver/dae_mebdf.c): each step solves BDF of
                     order k at t+h and at t+2h, then a formula of order k+1 at t+h with the same
                     Newton matrix; A-stable up to order 4 (k = 3), stability angles 88.36,
                     83.07, 74.48, 61.98 degrees at orders 5 to 8 (BDF: 73.35 and 51.84 at
                     orders 4 and 5). About three Newton iterations' cost per step for BDF's
                     one. max_order bounds k (up to 7: order 8, as MEBDFI's drivers); order,
                     step and error test: dae_options.mebdf_error */
} dae_method;

/* The error control of DAE_MEBDF (dae_options.mebdf_error; solver/dae_mebdf.c gives the
 * formulas and the measurements). */
typedef enum dae_mebdf_error {
    DAE_MEBDF_ERR_BDF = 0,  /* BDF's of order k (dae_err.c) on the MEBDF solution, whose order
                               is k + 1: conservative (the default) */
    DAE_MEBDF_ERR_CASH = 1, /* Cash and Considine's (their code MEBDFI): the order-k estimate
                               in Gear's constants, tested on the first stage, and their order
                               and step rule (h and k held k + 2 steps after a change) */
    DAE_MEBDF_ERR_KP1 = 2   /* the local error of the MEBDF solution itself, of order k + 1:
                               its error constant times y - (the predictor of degree k + 1),
                               step ratios with exponent 1/(k+2), on Cash and Considine's rule:
                               fewer steps and, at tight tolerances, fewer correct digits */
} dae_mebdf_error;

typedef struct dae_options {
    double rtol;              /* default 1e-6; 0 <= rtol < 1 (1e-100 is added to rtol |y| +
                                 atol, so that the weights stay finite when both are 0) */
    double atol;              /* default 1e-8, used when atol_vec is NULL (times the problem's
                                 nominal magnitudes, when it has them) */
    const double *atol_vec;   /* n values or NULL */
    int max_order;            /* the largest k: 0 (default) the method's largest, 5 for BDF
                                 (order 5), 7 for MEBDF (order 8, as MEBDFI's drivers; 5 with
                                 DAE_MEBDF_ERR_KP1); else 1..5 for BDF (its order k), 1..7 for
                                 MEBDF (its order k + 1) */
    double h_init;            /* 0: chosen by the solver */
    double h_min;             /* default 0: limited by round-off only */
    double h_max;             /* 0: no limit */
    long max_steps;           /* per call of dae_solve_to; default 100000 (< 1: default) */
    dae_index2_policy index2; /* default DAE_I2_EXCLUDE */
    int exclude_alg;          /* 1: index-1 algebraic variables take no part in the local error
                                 test either (default 0). Right for models whose algebraic
                                 unknowns are functions of the states, as in bond graphs, where
                                 a stiff element (an axial bar, EA/L = 1e8 N/m) turns a
                                 negligible position error into a large force error */
    ls_kind linsol;           /* default LS_KLU */
    int has_t_stop;           /* never integrate past t_stop */
    double t_stop;
    const double *breakpoints; /* times where the step must land (kinks); dae_create sorts
                                  them, a time given twice counts once */
    int nbreakpoints;
    int projection;            /* project onto cons after each step (needs cons) */
    int max_newton;            /* Newton iterations per step, default 4 (< 1: default); up to
                                  twice as many at a good rate (see above) */
    int fixed_step;            /* 1: constant h_init, order max_order after dae_set_history, no
                                  error-test rejection (for convergence-order studies) */
    int no_timing;             /* 1: stats.t_res, t_jac, t_linalg are not measured (stay 0):
                                  two clock reads fewer per residual, Jacobian and solve, a
                                  quarter of a step's cost on a problem of five unknowns */
    int newton_index2_scale_h; /* 1: index-2 corrections weigh |h| times less in the Newton
                                  convergence test (default 0: full weight, see dae_nls.c) */
    int check_jacobian;        /* 1: the first analytic Jacobian is compared with central
                                  differences of the residual (sp_jac_check, 2n residual
                                  evaluations); a disagreement of more than 1e-3 relative is a
                                  warning (DAE_WARNING to the error handler, dae_get_warning)
                                  that names the equation and the unknown; the run goes on.
                                  0 (default): the same comparison, once, at the first
                                  Jacobian evaluated after the Newton iteration contracted at a
                                  rate above 0.1 on a Jacobian of its own step (with an exact
                                  one the rate is of the order of the corrections, nearly 0 on
                                  a linear problem; Hairer and Wanner's contraction factor
                                  Theta, dae_nls.c), for problems of at most 500 unknowns; the
                                  warning then names that rate too. A wrong entry that does
                                  not slow the iteration down goes unnoticed. -1: never */
    double newton_dgmax;       /* > 0: between Jacobian evaluations the Newton matrix is formed
                                  again from the saved Jacobian and refactored when gamma = 1/cj
                                  has moved by more than this from the gamma it was factored with
                                  (CVODE's rule, 0.3 there; dae_nls.c); fewer Newton failures
                                  on a stale matrix and fewer iterations for one refactorization
                                  more. Default 0: the matrix follows the Jacobian (evaluated
                                  when cj leaves [0.6, 1.67] of its value then, IDA's rule) */
    int newton_jac_age;        /* > 0, with newton_dgmax > 0: the Jacobian is evaluated again
                                  only after a Newton failure on an older one or once this many
                                  steps were taken since it was (CVODE's msbj, 51 there), not
                                  whenever cj leaves [0.6, 1.67] of its value then (the
                                  refactorizations of newton_dgmax keep the matrix at the
                                  current cj); the convergence rate measured at one step then
                                  carries to the next ones until the matrix is formed again
                                  (CVODE's crate) instead of being reset when cj changes.
                                  Default 0: IDA's rule. Fewer Jacobians and Newton iterations,
                                  but a Jacobian kept longer meets more switches of sharp
                                  characteristics: give dae_problem.regimes where there are any
                                  (dae_nls.c: without them the errors of the switches
                                  accumulate at loose tolerances) */
    int stability_guard;       /* 1: where a lightly damped oscillation holds BDF orders 3..5
                                  at their stability limit, the order is lowered to 2, which
                                  damps it (numerical dissipation of the unresolved high
                                  frequencies, for models whose fast modes are not part of the
                                  answer: flexible structures, stiff hydraulic lines); default 0:
                                  the order follows the error estimates alone (dae_stab.c) */
    dae_method method;         /* DAE_BDF (default) or DAE_MEBDF (dae_method above) */
    dae_mebdf_error mebdf_error; /* DAE_MEBDF's error control (dae_mebdf_error above; default
                                    DAE_MEBDF_ERR_BDF) */
} dae_options;

/* The defaults above; BG_OK, or BG_ERR_ARGUMENT if o is NULL. dae_create checks the options:
 * tolerances as stated, h_init, h_min, h_max finite and >= 0 with h_min <= h_max when h_max > 0,
 * max_order 0 or 1..5 (MEBDF: 0 or 1..7; with DAE_MEBDF_ERR_KP1 0 or 1..5), a known index2 policy and linear
 * solver, a finite t_stop, nbreakpoints >= 0 with finite breakpoints, projection only with constraints, stability_guard 0 or 1,
 * check_jacobian -1, 0 or 1, and absolute tolerances (atol times a nominal magnitude, or
 * atol_vec) that are 0 or normal numbers (not below DBL_MIN = 2.2e-308). */
BG_API int dae_options_default(dae_options *o);

typedef struct dae_stats {
    long steps, rejected_error, newton_iters, newton_fails;
    long res_evals, res_evals_fd, jac_evals;
    long factor_symbolic, factor_full, factor_refactor, linear_solves;
    long steps_at_order[8]; /* by k: BDF 1..5, MEBDF 1..7 (its order k + 1) */
    long projections;
    double h_min_used, h_max_used, h_last;
    int order_last;
    double max_drift;              /* max |g| before projection over the run (needs cons) */
    double init_residual;          /* largest residual of a row or of a hidden constraint, scaled
                                      by the size of its terms, at the values of
                                      dae_consistent_init (see there) */
    double rcond_min;              /* smallest reciprocal condition estimate of the (scaled) Newton
                                      matrix (KLU: min|Ukk|/max|Ukk|; dense: LAPACK dgecon) */
    double t_res, t_jac, t_linalg; /* seconds in residual, Jacobian, linear algebra */
    long restarts;                 /* restarts at unannounced jumps (see dae_solve_to) */
    long stab_lowered;             /* steps whose order the stability guard lowered */
    long pattern_nnz;              /* entries of the patterns found from the residual (dF/dy
                                      and dF/dy' together; 0 when both were given) */
    long pattern_probes;           /* points at which the residual was probed for them */
    long pattern_res_evals;        /* residual evaluations that cost (also in res_evals_fd) */
    double t_pattern;              /* and the seconds */
    long pattern_reprobes;         /* times a Newton failure on a current finite-difference
                                      Jacobian had the residual probed again there and the
                                      patterns grew */
    long pattern_added;            /* entries those probes added */
    long warnings;                 /* warnings issued (dae_get_warning) */
    long newton_fails_stale;       /* Newton failures on a matrix from an earlier step, each
                                      answered by a fresh Jacobian at the same step (not counted
                                      in newton_fails) */
    double t_last_restart;         /* time of the last of them (NAN: none) */
    long reduced_rows;             /* constraint rows differentiated (DAE_I2_REDUCE), else 0 */
    long jac_regime;               /* Jacobians evaluated because a regime changed
                                      (dae_problem.regimes; the ones at a converged iterate
                                      also count in newton_fails_stale) */
    double init_error;             /* the Newton correction that the residuals and the hidden
                                      constraints at the values of dae_consistent_init call for,
                                      largest component in the error weights of y (index-2
                                      unknowns, and y moved by the constraints) and of y' (the
                                      others): <= 1 means consistent to the tolerance */
} dae_stats;

/* Return codes of dae_solve_to / dae_step besides the bg_status codes: DAE_SUCCESS (0),
 * DAE_TSTOP_RETURN, DAE_ROOT_RETURN and the failures DAE_TOO_MUCH_WORK .. DAE_STEP_TOO_SMALL,
 * with their values and meanings in the one table of bg_status.h (BG_DAE_STATUS_TABLE). */

typedef struct dae_solver dae_solver;

/* Structural classification of the unknowns from the patterns of dF/dy and dF/dy'. A variable is
 * differential if some equation contains its derivative. The algebraic ones are split by the
 * Dulmage-Mendelsohn decomposition of the algebraic equations (rows without y') against the
 * algebraic variables (with the differential variables taken as known): a variable in the
 * under-determined part cannot be found from those equations, only through the derivative of a
 * constraint, and is index 2 (a constraint effort, or anything that depends on one); the others
 * are index 1. kind receives n values. Returns the number of index-2 variables, BG_ERR_ARGUMENT
 * (a NULL argument), BG_ERR_PATTERN (the patterns are not both n x n) or BG_ERR_MEMORY. */
BG_API int dae_classify(const sp_csc *Jy, const sp_csc *Jyp, int *kind);
/* The structural rank of the Newton matrix dF/dy + cj dF/dy' from the two patterns (a maximum
 * matching of rows to columns of their union: btf_maxtrans, Duff's MC21): returns how many rows
 * (= columns) a maximum matching leaves unmatched, 0 for a structurally regular system, and
 * writes the first max unmatched rows (equations) into rows and columns (unknowns) into cols
 * (-1 after the last). Which ones are named depends on the matching found; their number does
 * not. < 0: BG_ERR_ARGUMENT (a NULL argument, max < 0), BG_ERR_PATTERN (shapes), BG_ERR_MEMORY. */
BG_API int dae_structure_check(const sp_csc *Jy, const sp_csc *Jyp, int *rows, int *cols, int max);

/* NULL on failure with the reason in err (may be NULL): BG_ERR_ARGUMENT (p NULL, n < 1, no
 * residual, options out of range, kinds that are not dae_var_kind or do not fit the patterns,
 * ncons or nroots < 0, constraints or events declared without their function), BG_ERR_PATTERN
 * (a Jacobian pattern not n x n or not well formed, a constraint pattern not ncons x n, an
 * equation that depends on no unknown), BG_ERR_MEMORY, BG_ERR_LIBRARY. o NULL: the defaults.
 * The problem's arrays, names and patterns are copied. */
BG_API dae_solver *dae_create(const dae_problem *p, const dae_options *o, bg_error *err);
BG_API void dae_free(dae_solver **s);
/* The error record with the last message; NULL if s is NULL. */
BG_API bg_error *dae_get_error(dae_solver *s);

/* Start at t0 from y0, yp0 (yp0 may be NULL: zero). No consistency is assumed or checked.
 * BG_OK, BG_ERR_ARGUMENT (s or y0 NULL, t0 not finite), BG_ERR_NONFINITE (a value not finite:
 * the message names it) or DAE_CALLBACK_FAIL (the event functions). Clears a failure. */
BG_API int dae_init(dae_solver *s, double t0, const double *y0, const double *yp0);
/* Consistent initial values at the current time, for semi-explicit systems (y' appears only for
 * differential variables; algebraic variables are fixed by the rows without y', or, index-2
 * ones, through the derivatives of the constraints). First the constraint rows (algebraic rows
 * without index-2 unknowns) are satisfied with the smallest change of the differential
 * variables; then y' of the differential and index-1 variables and the values of the index-2
 * ones follow from the differential rows, the rows with index-2 unknowns and the time
 * derivatives of the constraint rows (the hidden constraints); then y' of the index-2 ones from
 * the same equations differentiated once more (dae_ic.c has the details). The hidden
 * constraints are evaluated from the residual (extrapolated differences in t, and along y' when
 * the Jacobian is by finite differences), so that the values are consistent to the tolerance
 * with finite-difference Jacobians too; values given consistent are returned unchanged (y' of
 * the index-2 unknowns aside, which no equation holds and which are computed). The equations
 * are evaluated one rounding unit after t, so that inputs with a jump at t (a step at t0, a
 * corner of a reference) take their values after it; the solver does the same when it restarts
 * at a breakpoint. Measured at the values returned: stats.init_residual, the largest residual
 * of a row or a hidden constraint scaled by the size of its terms, and stats.init_error, the
 * correction those residuals call for in the error weights (<= 1: consistent to the tolerance).
 * Only between dae_init (or dae_reinit) and the first step: BG_ERR_STATE before dae_init, after
 * dae_set_history or once the integration has stepped. Returns BG_OK, or DAE_WARNING (> 0) when
 * the values were found but unknowns ended far from the values given (dae_get_warning names
 * them: a possible other solution of the algebraic equations or constraints), or a failure:
 * DAE_INIT_FAIL (the message names the equation that cannot be satisfied or the unknown that
 * nothing determines, and the time), DAE_CALLBACK_FAIL. Times in messages are given as t0, "t0
 * (just after)" or t0 + dt. The state set by dae_init is kept on failure. */
BG_API int dae_consistent_init(dae_solver *s);
/* After a discontinuity: new state at time t; order 1, new first step. The statuses of dae_init;
 * clears a failure, keeps the statistics. */
BG_API int dae_reinit(dae_solver *s, double t, const double *y, const double *yp);
/* Fixed-step studies: history y(t0 - i h), i = 0..k, as k+1 consecutive arrays of n values
 * (Y[i*n + j]); the next steps use order k and step h. BG_ERR_ARGUMENT for a NULL argument,
 * k outside 1..5 or h not > 0, BG_ERR_NONFINITE for a value that is not finite, else the
 * statuses of dae_init. */
BG_API int dae_set_history(dae_solver *s, double t0, double h, int k, const double *Y);

/* Integrate to tout and return y, yp there (interpolated; y or yp may be NULL). Returns
 * DAE_SUCCESS, DAE_TSTOP_RETURN, DAE_ROOT_RETURN (then *tret is the root) or an error (< 0), in
 * which case *tret, y and yp hold the last accepted state: BG_ERR_ARGUMENT (s or tret NULL, tout
 * not finite, behind the last step, or too close to start), BG_ERR_STATE (before dae_init, or
 * after a failure: call dae_reinit or dae_init first), DAE_TOO_MUCH_WORK (max_steps taken; the
 * call may be repeated) or a failure DAE_TOO_MUCH_ACC .. DAE_STEP_TOO_SMALL (message: the time
 * and the unknown or equation at fault, see above), after which the solver refuses to step with
 * BG_ERR_STATE until dae_reinit or dae_init. */
BG_API int dae_solve_to(dae_solver *s, double tout, double *tret, double *y, double *yp);
/* One internal step towards tout (not beyond a breakpoint or t_stop); state at *tret (y or yp
 * may be NULL: a loop that interpolates its own output times asks for none). The statuses of
 * dae_solve_to. */
BG_API int dae_step(dae_solver *s, double tout, double *tret, double *y, double *yp);
/* The unknowns the caller reads of the states dae_solve_to and dae_step return: idx[0 .. m-1]
 * (copied); the other entries of y and yp are then left as they are, not interpolated. An output
 * that reads a few unknowns of a large system at every output time saves the interpolation of
 * the rest; the values written are those of the whole state. idx NULL or m = 0: all (the
 * default). Ignored while options.projection is on (the projection needs the whole state);
 * dae_dense always writes the whole state. BG_OK, BG_ERR_ARGUMENT (s NULL, m < 0, an index
 * outside 0 .. n-1) or BG_ERR_MEMORY. */
BG_API int dae_set_output_unknowns(dae_solver *s, const int *idx, int m);
/* y and yp at any t in the last step [tn - h_last, tn] (y or yp may be NULL). BG_OK,
 * BG_ERR_ARGUMENT (s NULL, or t outside the last step: y, yp then hold the values at tn) or
 * BG_ERR_STATE (before dae_init). No message (s is const). */
BG_API int dae_dense(const dae_solver *s, double t, double *y, double *yp);
/* After DAE_ROOT_RETURN: found[i] = +1 or -1 (direction) for the functions that changed sign.
 * BG_OK or BG_ERR_ARGUMENT (s or found NULL). */
BG_API int dae_roots_found(const dae_solver *s, int *found);

/* The last warning, "" if none; NULL if s is NULL: the Jacobian check of
 * options.check_jacobian (also the automatic one of its default 0), or dae_consistent_init's
 * unknowns that ended far from the values given (by more than half their size and 100
 * tolerances: algebraic unknowns given a value other than 0, which stands for "not known", and
 * differential ones that the constraints moved along a path that was not straight; a possible
 * other solution of the algebraic equations or of the constraints, such as a mechanism's other
 * assembly), with the values given and found.
 * No such warning where an equation jumps at t0 (the values given are then left-hand values).
 * Warnings never stop the integration and go to the error handler with DAE_WARNING;
 * stats.warnings counts them. */
BG_API const char *dae_get_warning(const dae_solver *s);

/* The kinds of the unknowns the solver works with (dae_var_kind: as given, or classified from
 * the patterns); NULL if s is NULL or the patterns are still to be found (dae_problem without
 * patterns: they are found from the residual in dae_init). */
BG_API const int *dae_get_kinds(const dae_solver *s);
/* The patterns of dF/dy and dF/dy' the solver works with (as given, or found from the residual;
 * their values are scratch). BG_OK, BG_ERR_ARGUMENT (a NULL argument), BG_ERR_STATE (not found
 * yet: before dae_init). */
BG_API int dae_get_patterns(const dae_solver *s, const sp_csc **jy, const sp_csc **jyp);
/* The consistent initial values the last successful dae_consistent_init found (y and y', n
 * values each; either may be NULL). BG_OK, BG_ERR_ARGUMENT (s NULL), BG_ERR_STATE (none). */
BG_API int dae_get_consistent(const dae_solver *s, double *y, double *yp);

/* Time of the last step (or of dae_init); NaN if s is NULL or not initialised. */
BG_API double dae_current_time(const dae_solver *s);
/* Statistics, NULL if s is NULL. */
BG_API const dae_stats *dae_get_stats(const dae_solver *s);
/* One line "steps=... rejected=... ..." / a CSV header and a CSV row: the snprintf count, or
 * BG_ERR_ARGUMENT (st NULL, or buf NULL with size > 0). The line's "orders=" lists the steps at
 * k = 1 .. 5 and on to the highest k taken (MEBDF's 6, 7); the CSV has the columns order1 ..
 * order5 in their places and order6, order7 last. */
BG_API int dae_stats_line(const dae_stats *st, char *buf, size_t size);
BG_API int dae_stats_csv_header(char *buf, size_t size);
BG_API int dae_stats_csv(const dae_stats *st, char *buf, size_t size);
/* bg_status_name: the name of a status code, e.g. "DAE_CONV_FAIL". */
BG_API const char *dae_return_name(int code);

#ifdef __cplusplus
}
#endif
#endif
