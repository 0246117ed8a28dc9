/* The helpers of bench_util.h. */
#include "bench_util.h"

#include <stdlib.h>
#include <time.h>

#ifdef BENCH_HAVE_IDA
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>
#endif

double bench_cpu_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int cmpd(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double bench_median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmpd);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

#ifdef BENCH_HAVE_IDA
int bench_ida_res(realtype t, N_Vector yy, N_Vector yp, N_Vector rr, void *user)
{
    bench_ida_ctx *c = user;
    return c->p->res(NULL, t, N_VGetArrayPointer(yy), N_VGetArrayPointer(yp),
                     N_VGetArrayPointer(rr));
}

int bench_ida_jac(realtype t, realtype cj, N_Vector yy, N_Vector yp, N_Vector rr, SUNMatrix J,
                  void *user, N_Vector t1, N_Vector t2, N_Vector t3)
{
    (void)rr, (void)t1, (void)t2, (void)t3;
    bench_ida_ctx *c = user;
    int r = c->p->jac(NULL, t, N_VGetArrayPointer(yy), N_VGetArrayPointer(yp), c->jy, c->jyp);
    if (r != 0) return r;
    sp_union_combine(c->u, c->jy, 1.0, c->jyp, cj);
    const sp_csc *M = c->u->M;
    if (SUNMatGetID(J) == SUNMATRIX_SPARSE) {
        sunindextype *cp = SM_INDEXPTRS_S(J), *ri = SM_INDEXVALS_S(J);
        realtype *v = SM_DATA_S(J);
        for (int j = 0; j <= M->ncol; j++)
            cp[j] = M->colptr[j];
        for (int k = 0; k < M->nnz; k++) {
            ri[k] = M->rowind[k];
            v[k] = M->val[k];
        }
    } else {
        SUNMatZero(J);
        for (int j = 0; j < M->ncol; j++)
            for (int k = M->colptr[j]; k < M->colptr[j + 1]; k++)
                SM_ELEMENT_D(J, M->rowind[k], j) = M->val[k];
    }
    return 0;
}
#endif
