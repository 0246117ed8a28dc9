/* Helpers shared by the benchmark programs (bench, ida_compare, klu_bench): CPU time, the median
 * of a set of timings and, where SUNDIALS IDA is built in (BENCH_HAVE_IDA), the adapter that feeds
 * IDA a problem's residual and analytic Jacobian. */
#ifndef BG_BENCH_UTIL_H
#define BG_BENCH_UTIL_H

#ifdef BENCH_HAVE_IDA
#include <ida/ida.h>
#include <nvector/nvector_serial.h>

#include "problems.h"
#endif

/* CPU time of the process in seconds. */
double bench_cpu_now(void);

/* Sorts v[0..n-1] ascending (v[0] is then the minimum) and returns the median; n >= 1. */
double bench_median(double *v, int n);

#ifdef BENCH_HAVE_IDA
/* IDA's user data for bench_ida_res and bench_ida_jac: the problem, its Jacobian matrices on the
 * patterns (jy, jyp) and their union (u), on which dF/dy + cj dF/dy' is combined. */
typedef struct bench_ida_ctx {
    const bp_problem *p;
    sp_csc *jy, *jyp;
    sp_union *u;
} bench_ida_ctx;

/* IDAResFn: the problem's residual. */
int bench_ida_res(realtype t, N_Vector yy, N_Vector yp, N_Vector rr, void *user);

/* IDALsJacFn: the analytic dF/dy + cj dF/dy', into a sparse CSC (KLU) or a dense matrix. */
int bench_ida_jac(realtype t, realtype cj, N_Vector yy, N_Vector yp, N_Vector rr, SUNMatrix J,
                  void *user, N_Vector t1, N_Vector t2, N_Vector t3);
#endif

#endif
