/* The benchmark's KLU solver for IDA (bench_ida_klu, bench/bench_util.h) on the Newton matrices of
 * the damped crane scene (crane/scenes/paper.ini, 781 unknowns, 33 of index 2): its pivot
 * tolerance (BENCH_IDA_KLU_TOL, partial pivoting) against KLU's default threshold 0.001.
 * Truth: a manufactured solution. M = dF/dy + cj dF/dy' at the scene's consistent start for the
 * cj = 1/h of the steps where IDA stalled (h = 7e-6 .. 2.8e-5 s), x* = the unknowns' nominal
 * magnitudes, b = M x*; the solve must give x* back to within the matrix's conditioning (the
 * relative error 1e-6 allows cond(M) ~ 1e10). Then IDA-KLU over the first 0.02 s at rtol 1e-5
 * against IDA with dense LU on the same problem (the same method, other linear algebra): the
 * same steps and the same state to within the tolerance. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_case.h"
#include "bench_crane.h"
#include "bench_util.h"
#include "crane_scene.h"
#include "tap.h"

#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

/* max_i |x_i / x*_i - 1| of the solve of M x = M x* (x* = nominal) with bench_ida_klu at pivot
 * tolerance tol (0: the bench's); NAN if a call failed */
static double solve_error(const sp_csc *M, const double *nominal, double tol, SUNContext ctx)
{
    int n = M->ncol;
    SUNMatrix A = SUNSparseMatrix(n, n, M->nnz, CSC_MAT, ctx);
    N_Vector x = N_VNew_Serial(n, ctx), b = N_VNew_Serial(n, ctx);
    double e = NAN;
    if (A && x && b) {
        sunindextype *cp = SUNSparseMatrix_IndexPointers(A), *ri = SUNSparseMatrix_IndexValues(A);
        double *v = SUNSparseMatrix_Data(A);
        for (int j = 0; j <= n; j++)
            cp[j] = M->colptr[j];
        for (int k = 0; k < M->nnz; k++)
            ri[k] = M->rowind[k], v[k] = M->val[k];
        for (int i = 0; i < n; i++)
            NV_Ith_S(b, i) = 0;
        for (int j = 0; j < n; j++)
            for (int k = M->colptr[j]; k < M->colptr[j + 1]; k++)
                NV_Ith_S(b, M->rowind[k]) += M->val[k] * nominal[j];
        bench_ida_ctx c;
        memset(&c, 0, sizeof c);
        c.klu_tol = tol;
        SUNLinearSolver LS = bench_ida_klu(x, A, ctx, &c);
        if (LS && SUNLinSolInitialize(LS) == 0 && SUNLinSolSetup(LS, A) == 0 &&
            SUNLinSolSolve(LS, A, x, b, 0.0) == 0) {
            e = 0;
            for (int i = 0; i < n; i++)
                e = fmax(e, fabs(NV_Ith_S(x, i) / nominal[i] - 1));
        }
        if (LS) SUNLinSolFree(LS);
    }
    if (A) SUNMatDestroy(A);
    if (x) N_VDestroy(x);
    if (b) N_VDestroy(b);
    return e;
}

int main(void)
{
    crane_scene s;
    bg_error err = {0};
    if (crane_scene_load(&s, BENCH_SCENES_DIR "/paper.ini", &err) != BG_OK) {
        tap_ok(0, "paper.ini: %s", err.message);
        return tap_done();
    }
    bench_case bc;
    char msg[BG_MESSAGE_SIZE];
    int r = bench_crane_case(&bc, &s, s.static_start, 0.02, "crane", msg, sizeof msg);
    if (r == 0) r = bench_case_start(&bc, 1e-10, msg, sizeof msg);
    tap_ok(r == 0 && bc.dp.nominal && bc.n == 781, "damped scene built, consistent start, %d "
           "unknowns (%s)", bc.n, r ? msg : "ok");
    if (r != 0 || !bc.dp.nominal) return tap_done();

    SUNContext ctx = NULL;
    SUNContext_Create(NULL, &ctx);
    sp_csc *jy = sp_csc_copy(bc.dp.jac_y_pattern), *jyp = sp_csc_copy(bc.dp.jac_yp_pattern);
    sp_union *u = jy && jyp ? sp_union_create(jy, jyp) : NULL;
    int rj = u ? bc.dp.jac(bc.dp.user, 0.0, bc.ys, bc.yps, jy, jyp) : -1;
    tap_ok(rj == 0, "Jacobian at the start");
    static const double cjs[] = {4.3e4, 1.07e5, 1.44e5};
    for (int k = 0; k < 3 && rj == 0; k++) {
        sp_union_combine(u, jy, 1.0, jyp, cjs[k]);
        double e = solve_error(u->M, bc.dp.nominal, 0.0, ctx);
        double e0 = solve_error(u->M, bc.dp.nominal, 1e-3, ctx);
        tap_ok(e <= 1e-6, "cj = %g: bench_ida_klu gives x* back, relative error %.3g <= 1e-6",
               cjs[k], e);
        tap_ok(!(e0 <= 1e-2), "cj = %g: KLU's default pivot tolerance 0.001 (the bench's "
               "before) does not, relative error %.3g", cjs[k], e0);
    }
    sp_union_free(&u);
    sp_csc_free(&jy);
    sp_csc_free(&jyp);

    /* IDA-KLU against IDA with dense LU over the first 0.02 s */
    run_out ok, od;
    bench_run_alloc(&ok, bc.n);
    bench_run_alloc(&od, bc.n);
    run_opts ro = {0};
    ro.rtol = 1e-5;
    ro.max_steps = 2000;
    ro.ida_consistent_restart = 1;
    ro.ida_max_newton = BENCH_IDA_MAX_NEWTON;
    bench_run(&bc, bench_solver_find("ida-klu"), &ro, &ok);
    bench_run(&bc, bench_solver_find("ida-dense"), &ro, &od);
    tap_ok(ok.status == 0 && od.status == 0, "IDA-KLU and IDA-dense reach 0.02 s (%s%s%s)",
           ok.status ? ok.msg : "ok", od.status ? ", dense: " : "", od.status ? od.msg : "");
    tap_ok(ok.steps == od.steps && ok.steps < 200,
           "IDA-KLU takes the steps of IDA-dense: %ld and %ld (< 200; it was held at h = 3.5e-6 s "
           "with KLU's default pivoting)",
           ok.steps, od.steps);
    double dmax = 0;
    for (int i = 0; i < bc.n && ok.status == 0 && od.status == 0; i++) {
        double d = fabs(ok.y[i] - od.y[i]) / (1e-5 * fabs(od.y[i]) + 1e-5 * bc.dp.nominal[i]);
        if (d > dmax) dmax = d;
    }
    tap_ok(ok.status == 0 && od.status == 0 && dmax < 1e-2,
           "the same state at 0.02 s: largest difference %.3g tolerances (< 0.01)", dmax);
    bench_run_free(&ok);
    bench_run_free(&od);
    SUNContext_Free(&ctx);
    bench_case_free(&bc);
    return tap_done();
}
