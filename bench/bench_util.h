/* Helpers shared by the benchmark programs (bench, ida_compare, klu_bench): CPU and wall time, the
 * median of a set of timings and, where SUNDIALS IDA is built in (BENCH_HAVE_IDA), the adapter that
 * feeds IDA a dae_problem's residual and analytic Jacobian (the same callbacks our solver gets),
 * optionally timing them and IDA's linear solver. */
#ifndef BG_BENCH_UTIL_H
#define BG_BENCH_UTIL_H

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
} bench_ida_ctx;

/* Copies the patterns and builds their union. 0, or BG_ERR_MEMORY / BG_ERR_ARGUMENT (no analytic
 * Jacobian or no patterns). */
int bench_ida_ctx_init(bench_ida_ctx *c, const dae_problem *dp);
void bench_ida_ctx_free(bench_ida_ctx *c);

/* IDAResFn: the problem's residual. */
int bench_ida_res(realtype t, N_Vector yy, N_Vector yp, N_Vector rr, void *user);

/* IDALsJacFn: the analytic dF/dy + cj dF/dy', into a sparse CSC (KLU) or a dense matrix. */
int bench_ida_jac(realtype t, realtype cj, N_Vector yy, N_Vector yp, N_Vector rr, SUNMatrix J,
                  void *user, N_Vector t1, N_Vector t2, N_Vector t3);

/* Times the setup (factorization) and solve operations of LS into c (wraps LS's operation
 * table; one linear solver at a time in the process). */
void bench_ida_profile_ls(SUNLinearSolver LS, bench_ida_ctx *c);
#endif

#endif
