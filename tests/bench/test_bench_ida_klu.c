/* The benchmark's KLU linear solver for IDA (bench_ida_klu, bench/bench_util.h): a matrix whose
 * entry on the first factorization's pivot is 0 is refactored on fresh pivots. SUNDIALS' own
 * SUNLinSol_KLU refactors on the first matrix's pivot sequence and returns a recoverable failure
 * there (the IDA peer then stopped on the damped crane scene at 0.55 ms); bench_ida_klu solves
 * the system. Truth: the 2 x 2 inverses by hand.
 *   A1 = [4 1; 1 1] (pivots on the diagonal), A2 = [0 1; 1 1]: A2 x = (1, 2) has x = (1, 1);
 *   then A1 again on A2's pivots: A1 x = (5, 2) has x = (1, 1). */
#include <math.h>
#include <stdio.h>

#include "bench_util.h"
#include "tap.h"

#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

/* A := [a00 a01; a10 a11] on the full 2 x 2 pattern (CSC) */
static void set2(SUNMatrix A, double a00, double a01, double a10, double a11)
{
    sunindextype *cp = SUNSparseMatrix_IndexPointers(A), *ri = SUNSparseMatrix_IndexValues(A);
    double *v = SUNSparseMatrix_Data(A);
    cp[0] = 0, cp[1] = 2, cp[2] = 4;
    ri[0] = 0, ri[1] = 1, ri[2] = 0, ri[3] = 1;
    v[0] = a00, v[1] = a10, v[2] = a01, v[3] = a11;
}

/* solves A x = (b0, b1) with LS set up on A; 0 or the solver's flag */
static int solve2(SUNLinearSolver LS, SUNMatrix A, N_Vector x, N_Vector b, double b0, double b1)
{
    NV_Ith_S(b, 0) = b0;
    NV_Ith_S(b, 1) = b1;
    return SUNLinSolSolve(LS, A, x, b, 0.0);
}

int main(void)
{
    SUNContext ctx = NULL;
    if (SUNContext_Create(NULL, &ctx) != 0) {
        tap_ok(0, "SUNContext_Create");
        return tap_done();
    }
    N_Vector x = N_VNew_Serial(2, ctx), b = N_VNew_Serial(2, ctx);
    SUNMatrix A = SUNSparseMatrix(2, 2, 4, CSC_MAT, ctx);

    /* SUNDIALS' own: the failure the benchmark works around */
    SUNLinearSolver plain = SUNLinSol_KLU(x, A, ctx);
    set2(A, 4, 1, 1, 1);
    int r1 = SUNLinSolInitialize(plain), r2 = SUNLinSolSetup(plain, A);
    set2(A, 0, 1, 1, 1);
    int r3 = SUNLinSolSetup(plain, A);
    tap_ok(r1 == 0 && r2 == 0 && r3 == SUNLS_PACKAGE_FAIL_REC,
           "SUNLinSol_KLU: the refactorization on A1's pivots fails on A2 (flag %d, expected "
           "SUNLS_PACKAGE_FAIL_REC %d)",
           r3, SUNLS_PACKAGE_FAIL_REC);
    SUNLinSolFree(plain);

    /* the benchmark's: fresh pivots, counted */
    bench_ida_ctx c = {0};
    SUNLinearSolver LS = bench_ida_klu(x, A, ctx, &c);
    tap_ok(LS != NULL, "bench_ida_klu created");
    if (LS) {
        set2(A, 4, 1, 1, 1);
        int s1 = SUNLinSolInitialize(LS), s2 = SUNLinSolSetup(LS, A);
        int s3 = solve2(LS, A, x, b, 5, 2);
        tap_ok(s1 == 0 && s2 == 0 && s3 == 0 && c.klu_fallback == 0,
               "A1: factored and solved, no fallback (flags %d %d %d, fallbacks %ld)", s1, s2, s3,
               c.klu_fallback);
        tap_close(NV_Ith_S(x, 0), 1.0, 0, 1e-14, "A1 x = (5, 2): x0 = 1");
        tap_close(NV_Ith_S(x, 1), 1.0, 0, 1e-14, "A1 x = (5, 2): x1 = 1");
        set2(A, 0, 1, 1, 1);
        int s4 = SUNLinSolSetup(LS, A);
        tap_ok(s4 == 0 && c.klu_fallback == 1,
               "A2: the failed refactorization redone with fresh pivots (flag %d, fallbacks %ld)",
               s4, c.klu_fallback);
        int s5 = solve2(LS, A, x, b, 1, 2);
        tap_ok(s5 == 0, "A2 solved (flag %d)", s5);
        tap_close(NV_Ith_S(x, 0), 1.0, 0, 1e-14, "A2 x = (1, 2): x0 = 1");
        tap_close(NV_Ith_S(x, 1), 1.0, 0, 1e-14, "A2 x = (1, 2): x1 = 1");
        set2(A, 4, 1, 1, 1);
        int s6 = SUNLinSolSetup(LS, A), s7 = solve2(LS, A, x, b, 5, 2);
        tap_ok(s6 == 0 && s7 == 0 && c.klu_fallback == 1,
               "A1 on A2's pivots: refactored (flags %d %d, fallbacks %ld)", s6, s7,
               c.klu_fallback);
        tap_close(NV_Ith_S(x, 0), 1.0, 0, 1e-14, "A1 again: x0 = 1");
        tap_close(NV_Ith_S(x, 1), 1.0, 0, 1e-14, "A1 again: x1 = 1");
        SUNLinSolFree(LS);
    }
    SUNMatDestroy(A);
    N_VDestroy(x);
    N_VDestroy(b);
    SUNContext_Free(&ctx);
    return tap_done();
}
