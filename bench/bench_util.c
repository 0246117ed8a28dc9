/* The helpers of bench_util.h. */
#include "bench_util.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "pu_fs.h"

#ifdef BENCH_HAVE_IDA
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>
#include <sunlinsol/sunlinsol_klu.h>
#if defined(SUNDIALS_INT64_T)
typedef SuiteSparse_long KLU_INDEXTYPE; /* as sunlinsol_klu.c: klu_l_* */
#else
typedef int KLU_INDEXTYPE;
#endif
#endif

double bench_cpu_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

double bench_wall_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
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

/* ------------------------------------------------------------ checked files ---- */

#define MAX_FAILED 32
static int n_failed;
static struct {
    char name[BENCH_NAME_MAX + 1];
    char msg[160];
} failed[MAX_FAILED];

static void record_failure(const char *name, const char *msg)
{
    if (n_failed < MAX_FAILED) {
        snprintf(failed[n_failed].name, sizeof failed[n_failed].name, "%s", name);
        snprintf(failed[n_failed].msg, sizeof failed[n_failed].msg, "%s", msg);
    }
    n_failed++;
}

void bench_file_failed(const char *dir, const char *name, const char *msg)
{
    fprintf(stderr, "bench: cannot write %s/%s: %s\n", dir, name, msg);
    record_failure(name, msg);
}

int bench_file_failures(void)
{
    return n_failed;
}

const char *bench_file_failure(int i, const char **msg)
{
    if (i < 0 || i >= n_failed || i >= MAX_FAILED) return NULL;
    *msg = failed[i].msg;
    return failed[i].name;
}

void bench_file_fail(bench_file *bf, int err)
{
    if (bf->err) return;
    bf->err = err ? err : EIO;
    fprintf(stderr, "bench: cannot write %s: %s\n", bf->path, strerror(bf->err));
    record_failure(bf->name, strerror(bf->err));
}

int bench_file_open(bench_file *bf, const char *dir, const char *name)
{
    memset(bf, 0, sizeof *bf);
    bf->fd = -1;
    int np = snprintf(bf->name, sizeof bf->name, "%s", name),
        n = snprintf(bf->path, sizeof bf->path, "%s/%s", dir, name);
    if (np < 0 || (size_t)np >= sizeof bf->name || n < 0 || (size_t)n >= sizeof bf->path) {
        /* never cut: say it with the whole name */
        bench_file_failed(dir, name, strerror(ENAMETOOLONG));
        return -1;
    }
    bf->fd = open(bf->path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (bf->fd < 0) {
        bench_file_fail(bf, errno);
        return -1;
    }
    bf->f = open_memstream(&bf->buf, &bf->len);
    if (!bf->f) {
        bench_file_fail(bf, errno);
        close(bf->fd);
        unlink(bf->path);
        return -1;
    }
    return 0;
}

int bench_file_flush(bench_file *bf)
{
    if (!bf->f) return -1;
    /* the stream in memory fails only when memory runs out */
    if (fflush(bf->f) != 0 || ferror(bf->f)) bench_file_fail(bf, ENOMEM);
    if (!bf->err && bf->len > bf->done) {
        if (pu_write_all(bf->fd, bf->buf + bf->done, bf->len - bf->done) != 0)
            bench_file_fail(bf, errno);
        bf->done = bf->len;
    }
    return bf->err ? -1 : 0;
}

int bench_file_close(bench_file *bf)
{
    if (!bf->f) return -1;
    bench_file_flush(bf);
    if (fclose(bf->f) != 0) bench_file_fail(bf, ENOMEM);
    bf->f = NULL;
    free(bf->buf);
    bf->buf = NULL;
    /* fsync: a delayed write's failure shows here (EINVAL: a special file, nothing to sync) */
    if (!bf->err && fsync(bf->fd) != 0 && errno != EINVAL) bench_file_fail(bf, errno);
    if (close(bf->fd) != 0 && !bf->err) bench_file_fail(bf, errno);
    bf->fd = -1;
    if (bf->err) unlink(bf->path);
    return bf->err ? -1 : 0;
}

void bench_file_discard(bench_file *bf)
{
    if (!bf->f) return;
    fclose(bf->f);
    bf->f = NULL;
    free(bf->buf);
    bf->buf = NULL;
    close(bf->fd);
    bf->fd = -1;
    unlink(bf->path);
}

#ifdef BENCH_HAVE_IDA
int bench_ida_ctx_init(bench_ida_ctx *c, const dae_problem *dp)
{
    memset(c, 0, sizeof *c);
    c->dp = dp;
    if (!dp->jac || !dp->jac_y_pattern || !dp->jac_yp_pattern) return BG_ERR_ARGUMENT;
    c->jy = sp_csc_copy(dp->jac_y_pattern);
    c->jyp = sp_csc_copy(dp->jac_yp_pattern);
    c->u = c->jy && c->jyp ? sp_union_create(c->jy, c->jyp) : NULL;
    if (!c->u) {
        bench_ida_ctx_free(c);
        return BG_ERR_MEMORY;
    }
    return 0;
}

void bench_ida_ctx_free(bench_ida_ctx *c)
{
    sp_union_free(&c->u);
    sp_csc_free(&c->jy);
    sp_csc_free(&c->jyp);
}

int bench_ida_res(realtype t, N_Vector yy, N_Vector yp, N_Vector rr, void *user)
{
    bench_ida_ctx *c = user;
    double t0 = c->profile ? bench_wall_now() : 0;
    int r = c->dp->res(c->dp->user, t, N_VGetArrayPointer(yy), N_VGetArrayPointer(yp),
                       N_VGetArrayPointer(rr));
    if (c->profile) c->t_res += bench_wall_now() - t0;
    return r;
}

int bench_ida_ewt(N_Vector y, N_Vector ewt, void *user)
{
    bench_ida_ctx *c = user;
    realtype h = 0;
    if (c->mem) IDAGetCurrentStep(c->mem, &h);
    double hs = h != 0 ? fabs(h) : 1.0;
    const double *yv = N_VGetArrayPointer(y);
    double *w = N_VGetArrayPointer(ewt);
    for (int i = 0; i < c->dp->n; i++) {
        double tol = c->ewt_rtol * fabs(yv[i]) + (c->ewt_atolv ? c->ewt_atolv[i] : c->ewt_atol);
        if (!(tol > 0)) return -1;
        w[i] = 1.0 / tol;
        if (c->dp->kind && c->dp->kind[i] == DAE_ALG2) w[i] *= hs;
        if (!(w[i] > 0) || !isfinite(w[i])) return -1;
    }
    return 0;
}

int bench_ida_jac(realtype t, realtype cj, N_Vector yy, N_Vector yp, N_Vector rr, SUNMatrix J,
                  void *user, N_Vector t1, N_Vector t2, N_Vector t3)
{
    (void)rr, (void)t1, (void)t2, (void)t3;
    bench_ida_ctx *c = user;
    double w0 = c->profile ? bench_wall_now() : 0;
    int r =
        c->dp->jac(c->dp->user, t, N_VGetArrayPointer(yy), N_VGetArrayPointer(yp), c->jy, c->jyp);
    if (r != 0) {
        if (c->profile) c->t_jac += bench_wall_now() - w0;
        return r;
    }
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
    if (c->profile) c->t_jac += bench_wall_now() - w0;
    return 0;
}

/* SUNLinSolSetup_KLU, then a full factorization where its refactorization failed (the content
 * struct and the sun_klu_* names are those of sunlinsol_klu.h; KLU's common.user_data, read by
 * a user ordering only, which SUNLinSol_KLU does not use, holds the context). */
static int klu_setup_pivoting(SUNLinearSolver S, SUNMatrix A)
{
    SUNLinearSolverContent_KLU k = S->content;
    bench_ida_ctx *c = k->common.user_data;
    int r = SUNLinSolSetup_KLU(S, A);
    if (r != SUNLS_PACKAGE_FAIL_REC || !k->symbolic) return r;
    if (k->numeric) sun_klu_free_numeric(&k->numeric, &k->common);
    k->numeric = sun_klu_factor((KLU_INDEXTYPE *)SUNSparseMatrix_IndexPointers(A),
                                (KLU_INDEXTYPE *)SUNSparseMatrix_IndexValues(A),
                                SUNSparseMatrix_Data(A), k->symbolic, &k->common);
    if (c) c->klu_fallback++;
    k->last_flag = k->numeric ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_REC;
    return k->last_flag;
}

/* SUNLinSolSolve_KLU, then (c->newton_diag) the correction's weighted parts by kind. */
static int klu_solve_diag(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b, realtype tol)
{
    int r = SUNLinSolSolve_KLU(S, A, x, b, tol);
    bench_ida_ctx *c = ((SUNLinearSolverContent_KLU)S->content)->common.user_data;
    if (r != SUNLS_SUCCESS || !c || !c->newton_diag || !c->mem || !c->ewt) return r;
    if (IDAGetErrWeights(c->mem, c->ewt) != IDA_SUCCESS) return r;
    const double *xv = N_VGetArrayPointer(x), *w = N_VGetArrayPointer(c->ewt);
    int n = c->dp->n, arg = 0;
    double part[3] = {0, 0, 0}, big = -1;
    for (int i = 0; i < n; i++) {
        double e = w[i] * xv[i];
        int k = c->dp->kind ? c->dp->kind[i] : DAE_DIFF;
        part[k >= 0 && k < 3 ? k : 0] += e * e;
        if (fabs(e) > big) big = fabs(e), arg = i;
    }
    double norm = sqrt((part[0] + part[1] + part[2]) / n);
    c->nd_solves++;
    if (part[2] > 0.5 * (part[0] + part[1] + part[2])) c->nd_i2_dominant++;
    if (norm >= 0.33 && sqrt((part[0] + part[1]) / n) < 0.33) c->nd_pass_without_i2++;
    for (int k = 0; k < 3; k++)
        if (sqrt(part[k] / n) > c->nd_max[k]) c->nd_max[k] = sqrt(part[k] / n);
    if (norm > c->nd_norm_max) c->nd_norm_max = norm, c->nd_argmax = arg;
    return r;
}

SUNLinearSolver bench_ida_klu(N_Vector y, SUNMatrix A, SUNContext ctx, bench_ida_ctx *c)
{
    SUNLinearSolver LS = SUNLinSol_KLU(y, A, ctx);
    if (!LS) return NULL;
    ((SUNLinearSolverContent_KLU)LS->content)->common.user_data = c;
    SUNLinSol_KLUGetCommon(LS)->tol = c && c->klu_tol > 0 ? c->klu_tol : BENCH_IDA_KLU_TOL;
    LS->ops->setup = klu_setup_pivoting;
    LS->ops->solve = klu_solve_diag;
    return LS;
}

/* The wrapped linear solver's original operations and the context that receives the times. */
static bench_ida_ctx *ls_ctx;
static int (*ls_setup0)(SUNLinearSolver, SUNMatrix);
static int (*ls_solve0)(SUNLinearSolver, SUNMatrix, N_Vector, N_Vector, realtype);

static int ls_setup_timed(SUNLinearSolver S, SUNMatrix A)
{
    double t0 = bench_wall_now();
    int r = ls_setup0(S, A);
    ls_ctx->t_lsetup += bench_wall_now() - t0;
    return r;
}

static int ls_solve_timed(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b, realtype tol)
{
    double t0 = bench_wall_now();
    int r = ls_solve0(S, A, x, b, tol);
    ls_ctx->t_lsolve += bench_wall_now() - t0;
    return r;
}

void bench_ida_profile_ls(SUNLinearSolver LS, bench_ida_ctx *c)
{
    ls_ctx = c;
    ls_setup0 = LS->ops->setup;
    ls_solve0 = LS->ops->solve;
    LS->ops->setup = ls_setup_timed;
    LS->ops->solve = ls_solve_timed;
}
#endif

double bench_loglog_slope(const double *x, const double *y, int n)
{
    if (n < 2) return NAN;
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int i = 0; i < n; i++) {
        double lx = log(x[i]), ly = log(y[i]);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
    }
    double d = n * sxx - sx * sx;
    return d != 0 ? (n * sxy - sx * sy) / d : NAN;
}
