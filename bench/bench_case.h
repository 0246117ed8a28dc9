/* What the benchmark harness runs: a case (a problem of the collection, bench/problems.h, or the
 * crane, bench_crane.h) with its consistent start, tolerances, reference and accuracy measure, and
 * the solvers (ours with each index-2 policy on KLU and on dense LU, SUNDIALS IDA on KLU and on
 * dense LU) that integrate it from the same start with the same residual and Jacobian code.
 *
 * IDA is configured as its guide recommends for index 2: the id vector marks the differential
 * unknowns, the algebraic ones are suppressed from the error test (IDASetSuppressAlg), the
 * analytic Jacobian dF/dy + cj dF/dy' comes from the problem's callbacks, the absolute
 * tolerances are ours (atol times the problem's nominal magnitudes where it declares them,
 * IDASVtolerances), KLU factors with partial pivoting (bench_ida_klu); breakpoints are
 * crossed by stopping there and re-initialising (IDAReInit; the counters are summed). Ours gets
 * the breakpoints as options and, where the case asks (the crane, as crane/crane.c does),
 * exclude_alg: index-1 algebraic unknowns out of the error test, which is what IDA's
 * suppression does. */
#ifndef BG_BENCH_CASE_H
#define BG_BENCH_CASE_H

#include "bg_dae.h"
#include "problems.h"

typedef struct bench_case bench_case;

/* Accuracy of (y, yp) at tend against the case's reference (rtol, atol: the run's tolerances,
 * atol the scalar of mescd). */
typedef void (*bench_score_fn)(const bench_case *bc, const double *y, const double *yp, double rtol,
                               double atol, bp_score *s);
/* Constraint drift of a state (crane: hinge distance), >= 0. */
typedef double (*bench_drift_fn)(const bench_case *bc, double t, const double *y, const double *yp);

struct bench_case {
    char name[64], title[256];
    char ref_source[400]; /* where the reference comes from, for the report */
    int n;
    double t0, tend;
    dae_problem dp;      /* residual, Jacobian, patterns, kinds, names, user */
    double *y0, *yp0;    /* the start as given (owned) */
    double *ys, *yps;    /* the consistent start shared by every solver (bench_case_start) */
    double *breakpoints; /* inside (t0, tend), ascending (owned), nbreakpoints of them */
    int nbreakpoints;
    int exclude_alg;           /* ours: index-1 algebraic unknowns out of the error test too */
    int stability_guard;       /* ours: options.stability_guard (the crane: as its scene says) */
    double newton_dgmax;       /* ours: options.newton_dgmax (the crane: as its scene says) */
    int newton_jac_age;        /* ours: options.newton_jac_age (the crane: as its scene says) */
    int newton_index2_scale_h; /* ours: options.newton_index2_scale_h (likewise) */
    /* tolerances: atol = atol_factor * rtol, or (atol_fn) a scalar and a vector */
    double atol_factor;
    void (*atol_fn)(const bench_case *bc, double rtol, double *atol, double *atolv);
    double *yref, *ypref; /* reference at tend (owned); NULL: none */
    bench_score_fn score;
    bench_drift_fn drift;
    int large;            /* long runs: the profiled first run counts as a timing sample */
    const bp_problem *bp; /* the collection's problem, or NULL */
    bp_instance in;
    void *ext; /* the crane (bench_crane.c) */
    void (*ext_free)(void *ext);
};

/* Wraps a problem of the collection (reference from bp_reference, scoring bp_score_compute;
 * atol = factor * rtol with the factor of the problem, pump: the test set's tolerance vector).
 * 0 or BG_ERR_MEMORY. */
int bench_case_from_problem(bench_case *bc, const bp_problem *p);
void bench_case_free(bench_case *bc);

/* The run's absolute tolerances: *atol the scalar (for mescd and when atolv is not used),
 * atolv (n values) filled when the case has a vector (returns 1), else 0. */
int bench_case_atol(const bench_case *bc, double rtol, double *atol, double *atolv);

/* Consistent start (ys, yps) by dae_consistent_init at rtol, with the case's options. 0, or a
 * negative status with the message in msg (ys, yps are then the given start). */
int bench_case_start(bench_case *bc, double rtol, char *msg, size_t msz);

/* ------------------------------------------------------------------ solvers ---- */

typedef struct solver_def {
    const char *name;
    int ida; /* 0: ours, 1: SUNDIALS IDA */
    ls_kind ls;
    dae_index2_policy pol;
    dae_method method; /* ours: DAE_BDF or DAE_MEBDF */
    int max_order;     /* ours: options.max_order, 0: the default (or run_opts.max_order) */
} solver_def;

extern const solver_def bench_solvers[];
extern const int bench_nsolvers;
const solver_def *bench_solver_find(const char *name);

/* One integration. */
typedef struct run_opts {
    double rtol;
    double tend;            /* 0: the case's */
    const double *y0, *yp0; /* NULL: the case's consistent start */
    int consistent_init;    /* ours: dae_consistent_init first (a start off the manifold) */
    int no_breakpoints;     /* run over the breakpoints without stopping there */
    int profile;            /* time the residual, Jacobian and linear solver */
    int track_drift;        /* ours: step by step, maximum of bc->drift (or the solver's) */
    long max_steps;         /* 0: 1 000 000 */
    double h_max;           /* ours: 0: none */
    /* IDA: at each breakpoint, the values it restarts from (IDAReInit) made consistent by our
     * dae_consistent_init (as our solver restarts there: the equations one rounding unit after
     * the breakpoint) instead of IDA's own values before it (whose y' belongs to the input
     * before the jump), and its first step there the last one before it (IDASetInitStep); the
     * CPU time includes the consistent values, IDA's counters do not */
    int ida_consistent_restart;
    /* IDA: IDASetMaxNonlinIters, the Newton iterations per attempt (0: IDA's default, 4) */
    int ida_max_newton;
    /* IDA: the scalar atol for every unknown even where the problem declares nominal
       magnitudes (dae_problem.nominal), as the bench gave IDA before; default 0: IDA gets
       ours' absolute tolerances atol * nominal_i (IDASVtolerances) */
    int ida_scalar_atol;
    /* IDA-KLU: where its Newton corrections' weight sits, by kind of unknown (run_out.nd_*) */
    int ida_newton_diag;
    /* IDA-KLU: KLU's pivot tolerance (bench_ida_klu); 0: BENCH_IDA_KLU_TOL (1, true partial
       pivoting); 0.001 is KLU's default, the bench's setting before */
    double ida_klu_tol;
    /* IDA: its index-2 unknowns' weights times |h| (bench_ida_ewt, IDAWFtolerances) */
    int ida_index2_h;
    int max_order; /* ours: options.max_order (0: the default) */
    int guard;     /* ours: 0 the case's stability guard setting, 1 on, -1 off */
    int reduce;    /* ours: options.index2 = DAE_I2_REDUCE (the case's position constraints
                      are then left out: the reduction projects onto its own) */
} run_opts;

typedef struct run_out {
    int status; /* 0, or < 0 (our dae_return / IDA's flag) */
    char msg[BG_MESSAGE_SIZE];
    double t;       /* time reached */
    double *y, *yp; /* n values at t (allocated by bench_run_alloc) */
    long steps, rejected, newton, conv_fail, res, jac, fact, solves;
    long ls_fallback; /* IDA-KLU: refactorizations redone with fresh pivots (bench_ida_klu) */
    /* IDA with run_opts.ida_newton_diag (bench_ida_ctx in bench_util.h): the corrections seen,
     * those whose weighted norm^2 the index-2 unknowns hold more than half of, those that the
     * test ||x|| < 0.33 fails only because of the index-2 part; the largest WRMS norm of the
     * differential, index-1 and index-2 parts and of the whole, and the unknown with the largest
     * weighted entry there; IDA's last step and order */
    long nd_solves, nd_i2_dominant, nd_pass_without_i2;
    double nd_max[3], nd_norm_max, h_last;
    int nd_argmax, order_last;
    int max_order;
    double cpu;                 /* CPU seconds of the integration (creation to end) */
    double wall;                /* wall seconds, same span */
    double t_res, t_jac, t_lin; /* wall seconds in the callbacks and linear algebra (profile) */
    double drift; /* largest constraint drift seen (track_drift), else the solver's max_drift */
} run_out;

int bench_run_alloc(run_out *o, int n);
void bench_run_free(run_out *o);
/* Runs solver sd on the case; status in out. */
void bench_run(const bench_case *bc, const solver_def *sd, const run_opts *ro, run_out *out);

/* Timing: the first run is profiled (callbacks and linear solver timed); it is a warm-up that is
 * not counted unless the case is large (then it counts as the first of K samples). Cases that are
 * not large get up to five profiled runs (while they take less than 0.2 s together), the one with
 * the smallest wall time giving the profile. K timed runs in all: CPU times into cpu[0..K-1]
 * (ascending), count returned. A failing run ends the series. out holds the last run, with the
 * profile (t_res, t_jac, t_lin, wall) of the profiled one. */
/* Timing wrappers of a problem's residual and Jacobian: *out = *in with its callbacks timed
 * (wall clock) into p; out->user is p. */
typedef struct bench_prof {
    const dae_problem *in;
    double t_res, t_jac;
} bench_prof;
void bench_prof_wrap(bench_prof *p, const dae_problem *in, dae_problem *out);

/* A profiled warm-up run (its split into residual, Jacobian and linear algebra kept in out),
 * then K timed runs into cpu[] (a run under 10 ms timed as the mean of a batch of about 20 ms;
 * a large case counts its profiled run as the first, and runs once when that took over 5 s; a
 * failure runs once). Returns the number of times in cpu. */
int bench_run_timed(const bench_case *bc, const solver_def *sd, const run_opts *ro, int K,
                    run_out *out, double *cpu);

#endif
