/* Helpers shared by the benchmark programs (bench, ida_compare, klu_bench): CPU and wall time, the
 * median of a set of timings and, where SUNDIALS IDA is built in (BENCH_HAVE_IDA), the adapter that
 * feeds IDA a dae_problem's residual and analytic Jacobian (the same callbacks our solver gets),
 * optionally timing them and IDA's linear solver. */
#ifndef BG_BENCH_UTIL_H
#define BG_BENCH_UTIL_H

#include <stdio.h>

#include "bg_dae.h"

#ifdef BENCH_HAVE_IDA
#include <ida/ida.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_linearsolver.h>
#endif

/* CPU time of the process in seconds. */
double bench_cpu_now(void);
/* Monotonic wall-clock time in seconds. */
double bench_wall_now(void);

/* Sorts v[0..n-1] ascending (v[0] is then the minimum) and returns the median; n >= 1. */
double bench_median(double *v, int n);

/* The longest path the bench builds: an output folder, '/', a file name of at most
 * BENCH_NAME_MAX characters (wp_<problem>.png the longest), the terminating '\0'. An output
 * folder longer than BENCH_OUT_MAX characters is refused (never cut). */
#define BENCH_PATH_SIZE 4096
#define BENCH_NAME_MAX 120
#define BENCH_OUT_MAX (BENCH_PATH_SIZE - BENCH_NAME_MAX - 2)

/* A file the bench writes, DIR/NAME: opened (created or emptied) by bench_file_open, its text
 * printed into f (a stream in memory), written to the file by bench_file_flush and
 * bench_file_close. Every step is checked (the open, the stream in memory, each write(2), fsync,
 * close): the first failure is said on stderr, "bench: cannot write PATH: ERROR" (the system's
 * error), counted in bench_file_failures, and the file is removed when it is closed: no part of
 * it stays to be taken for a result. */
typedef struct bench_file {
    char path[BENCH_PATH_SIZE];
    char name[BENCH_NAME_MAX + 1];
    FILE *f;     /* where to print; NULL once closed */
    char *buf;   /* the text in memory (open_memstream) */
    size_t len;  /* its length */
    size_t done; /* the part of it in the file */
    int fd, err; /* the file; the first error (errno), 0 while none */
} bench_file;

/* Opens DIR/NAME. 0, or -1 (said and counted; nothing to close). */
int bench_file_open(bench_file *bf, const char *dir, const char *name);
/* Writes what was printed so far into the file. 0, or -1 (said and counted once; the file is
 * removed at bench_file_close). */
int bench_file_flush(bench_file *bf);
/* Marks the file as failed with error err (said and counted unless it had failed already). */
void bench_file_fail(bench_file *bf, int err);
/* Writes the rest, closes and frees. 0, or -1 if any step failed (the file is then removed). */
int bench_file_close(bench_file *bf);
/* Closes and frees without writing the rest, and removes the file (a run given up). */
void bench_file_discard(bench_file *bf);
/* A file written by another program (a gnuplot figure) that failed: says "bench: cannot write
 * DIR/NAME: MSG" and counts it. */
void bench_file_failed(const char *dir, const char *name, const char *msg);
/* The number of files that could not be written, and the i-th of them (its name, *msg the
 * reason); the first 32 are kept. */
int bench_file_failures(void);
const char *bench_file_failure(int i, const char **msg);

#ifdef BENCH_HAVE_IDA
/* IDA's user data for bench_ida_res and bench_ida_jac: the problem (its residual, Jacobian and
 * patterns), the Jacobian matrices on the patterns (jy, jyp, copies of the problem's patterns
 * made by bench_ida_ctx_init) and their union (u), on which dF/dy + cj dF/dy' is combined. With
 * profile set, the wall time spent in the callbacks and (after bench_ida_profile_ls) in IDA's
 * linear solver setup and solve is added up. */
typedef struct bench_ida_ctx {
    const dae_problem *dp;
    sp_csc *jy, *jyp;
    sp_union *u;
    int profile;
    double t_res, t_jac, t_lsetup, t_lsolve;
    long klu_fallback; /* refactorizations redone with fresh pivots (bench_ida_klu) */
    /* Where the Newton corrections' weight sits (bench_ida_klu with newton_diag set and mem the
     * IDA memory): each correction x that the linear solver returns is weighed with IDA's
     * current error weights w (IDAGetErrWeights), as IDA's Newton test weighs it
     * (||x||_WRMS), and its squares are added up by the problem's kinds of unknowns. */
    double klu_tol; /* bench_ida_klu's pivot tolerance; 0: BENCH_IDA_KLU_TOL */
    /* bench_ida_ewt: the tolerances (atolv: n values, or NULL for atol) and ida_mem (mem) */
    double ewt_rtol, ewt_atol;
    const double *ewt_atolv;
    int newton_diag;
    void *mem;
    N_Vector ewt;            /* scratch for the weights */
    long nd_solves;          /* corrections seen */
    long nd_i2_dominant;     /* of which the index-2 unknowns hold more than half the norm^2 */
    long nd_pass_without_i2; /* of which ||x|| >= 0.33 but < 0.33 without the index-2 part */
    double nd_max[3];        /* largest WRMS norm of the part of each kind (DAE_DIFF..ALG2) */
    int nd_argmax;           /* the unknown with the largest |w_i x_i| at the largest norm */
    double nd_norm_max;      /* the largest ||x||_WRMS */
} bench_ida_ctx;

/* Copies the patterns and builds their union. 0, or BG_ERR_MEMORY / BG_ERR_ARGUMENT (no analytic
 * Jacobian or no patterns). */
int bench_ida_ctx_init(bench_ida_ctx *c, const dae_problem *dp);
void bench_ida_ctx_free(bench_ida_ctx *c);

/* IDAResFn: the problem's residual. */
int bench_ida_res(realtype t, N_Vector yy, N_Vector yp, N_Vector rr, void *user);

/* IDAEwtFn (IDAWFtolerances; user data the context, c->mem IDA's memory): IDA's weights
 * W_i = 1 / (rtol |y_i| + atol_i), those of the index-2 unknowns (dae_problem.kind DAE_ALG2)
 * times |h|, h IDA's current step (1 before the first): our newton_index2_scale_h (bg_dae.h).
 * With the index-2 unknowns out of the error test (IDASetSuppressAlg) the weights act on IDA's
 * Newton test alone, where a correction of an index-2 unknown scales as 1/h (its BDF Jacobian's
 * blocks: cj dF/dy' against dF/dlambda). 0, or -1 for a weight that is not finite and > 0. */
int bench_ida_ewt(N_Vector y, N_Vector ewt, void *user);

/* IDALsJacFn: the analytic dF/dy + cj dF/dy', into a sparse CSC (KLU) or a dense matrix. */
int bench_ida_jac(realtype t, realtype cj, N_Vector yy, N_Vector yp, N_Vector rr, SUNMatrix J,
                  void *user, N_Vector t1, N_Vector t2, N_Vector t3);

/* SUNDIALS' KLU linear solver (SUNLinSol_KLU) with the fallback of ours (solver/bg_linsol.h):
 * a refactorization that meets a zero pivot is redone as a full factorization with fresh
 * pivoting on the same symbolic analysis, counted in c->klu_fallback. SUNLinSol_KLU (SUNDIALS
 * 6.4, sunlinsol_klu.c) refactors every matrix after the first on that first matrix's pivot
 * sequence and pivots afresh only when the condition estimate exceeds 1/eps^(2/3); a zero pivot
 * of klu_refactor is returned to IDA as a recoverable failure (SUNLS_PACKAGE_FAIL_REC) with the
 * stale factorization kept, and every retry at a smaller step refactors on the same pivots: on
 * the damped crane scene IDA stopped so at t = 0.55 ms with h = 3.8e-10 at every tolerance
 * ("the corrector convergence failed repeatedly"). NULL when out of memory. */
/* Its factorizations pivot by true partial pivoting: KLU's pivot tolerance (klu_common.tol,
 * set through SUNLinSol_KLUGetCommon) is BENCH_IDA_KLU_TOL = 1, not KLU's default 0.001, with
 * which a diagonal pivot is kept while it is at least 0.001 of the largest entry of its column
 * (T. A. Davis and E. Palamadai Natarajan, "Algorithm 907: KLU", ACM TOMS 37 (2010) 36: the
 * tolerance of threshold partial pivoting), each such pivot allowing a growth of up to 1000.
 * Measured on the damped crane scene (781 unknowns) at rtol 1e-5: with 0.001 and SUNLinSol_KLU's
 * default COLAMD ordering IDA's first Newton correction at h = 6.95e-6 s was 1e9 to 1e10
 * weighted tolerances (3.6e11 N in a boom force) where dense LU on the same matrix and residual
 * gives 0.03 of the force's nominal magnitude; the iteration diverged, IDA cut h by 4, doubled it
 * back twice, diverged again: 20 000 steps, 10 001 convergence failures and no error-test
 * failure by t = 0.052 s. With 1 (or AMD or the natural ordering) IDA-KLU takes the steps of
 * IDA with dense LU (59 steps to 0.02 s, order 3). c->klu_tol > 0 sets another tolerance. */
#define BENCH_IDA_KLU_TOL 1.0
SUNLinearSolver bench_ida_klu(N_Vector y, SUNMatrix A, SUNContext ctx, bench_ida_ctx *c);

/* Times the setup (factorization) and solve operations of LS into c (wraps LS's operation
 * table; one linear solver at a time in the process). */
void bench_ida_profile_ls(SUNLinearSolver LS, bench_ida_ctx *c);
#endif

/* Least-squares slope of log y against log x over n points (NAN for fewer than 2). */
double bench_loglog_slope(const double *x, const double *y, int n);

#endif
