/* A collection of DAE and stiff ODE test problems for the modified-BDF solver (bg_dae.h), with
 * analytic Jacobians on declared sparsity patterns, exact solutions where they exist, reference
 * end values from the published test sets, and the accuracy measures of the IVP Test Set.
 *
 * Every problem is written as a residual F(t, y, y') = 0 from the published equations (the
 * sources are named at each problem in problems*.c and in docs/testset.md; the published Fortran
 * and R definitions are the specification, no code is taken from them):
 *   ap102       Ascher and Petzold, Computer Methods for ODEs and DAEs (SIAM 1998), Ex. 10.2:
 *               linear index 2, exact solution x1 = e^t, x2 = e^t/(t-2).
 *   pendulum2   the index-2 pendulum of J. Cash's MEBDFDAE driver (pendul2.f), reference by a
 *               30-digit recomputation.
 *   robertson   Robertson's chemical kinetics to t = 1e11 (IVP Test Set "rober").
 *   vdp_scaled  van der Pol in the scaled form of the IVP Test Set "vdpol", eps = 1e-6, [0, 2].
 *   hires       HIRES plant physiology (IVP Test Set "hires").
 *   lin2        a linear semi-explicit index-2 system with a manufactured smooth solution
 *               (order studies).
 *   smooth_ode  a linear 2x2 ODE with a manufactured smooth solution (order studies).
 *   kinks       y1' = u(t), y2' = y1 with a piecewise-linear forcing u that has kinks at the
 *               problem's breakpoints; exact solution piecewise polynomial.
 * and, in a second table (bp_testset_get), five problems of the IVP Test Set with their published
 * reference values (provenance in docs/testset.md):
 *   crank       flexible slider crank (Simeon), n = 24, index 2 (velocity constraints; 10
 *               index-2 accelerations and multipliers), stiff oscillatory (E = 2e11).
 *   pump        charge pump, n = 9, index 2 (the current y9), charge-oriented MOS model with
 *               a singular mass matrix, 39 breakpoints of the pulsed input.
 *   transamp    transistor amplifier, n = 8, index 1, constant singular mass matrix (all eight
 *               voltages differential; three current balances as algebraic rows).
 *   chemakzo    chemical Akzo Nobel, n = 6, index 1 (semi-explicit).
 *   nand        NAND gate, n = 14, C(y) y' = f with a nonsingular voltage-dependent C, pulsed
 *               inputs with 15 breakpoints.
 * and, in a third table (bp_osc_get), two undamped oscillatory problems of ours:
 *   osc_chain   eight masses on stiff springs (59..626 Hz) driven by a sin^2 ramp through a
 *               velocity constraint, n = 19, index 2, fast modes excited by the start;
 *               closed-form modal reference.
 *   rotating_beam  a flexible beam spun up by its hub (Simo and Vu-Quoc 1986), 2 axial and 3
 *               bending Ritz coordinates, n = 13, index 2 (hub torque), a non-identity mass
 *               matrix; reference by a long-double extrapolation of its ODE.
 *
 * Accuracy (IVP Test Set, Mazzia, Magherini and Iavernaro, Release 2.4):
 *   scd   = -log10(max_i |y_i - yref_i| / |yref_i|) over the scored components with yref_i != 0,
 *   mescd = -log10(max_i |y_i - yref_i| / (atol/rtol + |yref_i|)) over all components,
 * both computed here twice: over the components that are not index-2 algebraic and over the
 * index-2 components alone, so that the error policy for index-2 variables stays visible. */
#ifndef BG_BENCH_PROBLEMS_H
#define BG_BENCH_PROBLEMS_H

#include "bg_dae.h"
#include "bg_sparse.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct bp_problem {
    const char *name;
    const char *title;
    int n;
    double t0, tend;
    const double *y0;         /* n initial values */
    const double *yp0;        /* n initial derivatives (consistent for every problem here) */
    const int *kind;          /* n values of dae_var_kind */
    const char *const *names; /* n variable names */
    dae_res_fn res;
    dae_jac_fn jac; /* analytic Jy, Jyp values on the patterns */
    /* Builds the n x n patterns of dF/dy and dF/dy' (values zero). 0 or BG_ERR_MEMORY. */
    int (*patterns)(sp_csc **jy, sp_csc **jyp);
    /* Exact solution y(t) and, if yp != NULL, y'(t); NULL when none is known. */
    void (*exact)(double t, double *y, double *yp);
    const double *yref;          /* n reference values at tend; NULL: use exact(tend) */
    const char *ref_source;      /* where yref comes from */
    const unsigned char *scored; /* n flags: components that enter scd; NULL: all */
    /* position constraints (projection, drift), ncons = 0 if none */
    int ncons;
    dae_cons_fn cons;
    int (*cons_pattern)(sp_csc **g); /* ncons x n pattern of dg/dy */
    /* breakpoints of the forcing (ascending, inside (t0, tend)), 0 if none */
    int nbreakpoints;
    const double *breakpoints;
    /* The published initial values where y0, yp0 above were made consistent from them (crank:
     * the published set satisfies the algebraic rows only to about 1e-7); NULL otherwise. */
    const double *y0_published;
    const double *yp0_published;
} bp_problem;

/* The table: bp_count() problems, bp_get(i) for i < bp_count(). */
int bp_count(void);
const bp_problem *bp_get(int i);
/* The IVP Test Set problems crank, pump, transamp, chemakzo and nand, in a table of their own:
 * they are larger (n up to 24), have several constraints and index-2 variables (crank: 10),
 * state-dependent or singular mass matrices, and published reference values of limited
 * accuracy, so that properties asserted over the table above do not all hold for them. */
int bp_testset_count(void);
const bp_problem *bp_testset_get(int i);
/* Undamped oscillatory problems (issue "Steps set by accuracy"), in a third table: osc_chain
 * (a chain of masses on stiff springs, 59..626 Hz, driven by a slow ramp through a velocity
 * constraint, index 2; closed-form reference) and rotating_beam (a flexible beam spun up by its
 * hub, Simo and Vu-Quoc 1986, hub rate prescribed, index 2; reference by our solver at rtol
 * 1e-12 checked against IDA). Their mass matrices are not the identity (rotating_beam) and
 * they are checked by tests/bench/test_new_problems.c, not by the solver tests' table loops. */
int bp_osc_count(void);
const bp_problem *bp_osc_get(int i);
/* Lookup by name in the three tables; NULL if unknown. */
const bp_problem *bp_find(const char *name);

/* A dae_problem ready for dae_create, with the patterns it points to. */
typedef struct bp_instance {
    const bp_problem *p;
    dae_problem dp;
    sp_csc *jy, *jyp; /* patterns of dF/dy and dF/dy' */
    sp_csc *g;        /* pattern of dg/dy (NULL without constraints) */
} bp_instance;

/* Fills in (patterns built, residual, Jacobian, kinds, names, constraints; user = NULL; no event
 * functions). Returns 0, or BG_ERR_MEMORY (in is then freed). */
int bp_instance_init(bp_instance *in, const bp_problem *p);
/* Frees the patterns; in may be partly initialised (zeroed first) and is zeroed. */
void bp_instance_free(bp_instance *in);

/* Reference values at tend: yref if given, else exact(tend). Returns 0, or -1 if neither. */
int bp_reference(const bp_problem *p, double *yref);

/* Accuracy against a reference. Each field is +INFINITY when the error is exactly zero and NAN
 * when no component qualifies (e.g. the index-2 fields of an ODE). */
typedef struct bp_score {
    double scd;      /* scored components that are not index 2, yref != 0 */
    double mescd;    /* components that are not index 2 */
    double scd_i2;   /* index-2 scored components with yref != 0 */
    double mescd_i2; /* index-2 components */
    int worst;       /* component (0-based) that limits scd, -1 if none */
} bp_score;

/* y against yref with mescd's atol/rtol (scalar tolerances). */
void bp_score_compute(const bp_problem *p, const double *y, const double *yref, double rtol,
                      double atol, bp_score *s);

/* Checks the analytic Jacobian at (t, y, yp) with central differences (sp_jac_check): dF/dy and
 * dF/dy' separately. The errors are relative to |fd| + floor (see bg_fdjac.h). Returns 0 or the
 * first negative status (callback, memory). */
int bp_check_jacobian(const bp_problem *p, double t, const double *y, const double *yp,
                      double floor, double *max_err_y, double *max_err_yp);

/* Position constraint g(y) of the pendulum (x^2 + y^2 - 1 = 0) and its Jacobian values. */
int bp_pendulum_cons(void *user, double t, const double *y, double *g, sp_csc *G);

#ifdef __cplusplus
}
#endif
#endif
