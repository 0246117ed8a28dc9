/* The benchmark harness: error against run time for our solver and SUNDIALS IDA on the problem
 * collection (bench/problems.c), and a stability suite of stiff and extreme cases.
 *
 *   bench [--problems LIST] [--solvers LIST] [--rtols LIST] [--repeat K] [--stability]
 *         [--quick] [--out DIR]
 *
 * writes to DIR (default results/bench): work_precision.csv (one row per problem, solver and
 * tolerance), report.md (tables per problem, the winner at each accuracy, CPU-time ratios of our
 * solver to IDA at equal accuracy interpolated at scd = 4, 6, 8, every failure with its message,
 * machine, commit and build flags), wp_<problem>.png (scd against CPU time and against steps,
 * drawn by gnuplot when it is installed) and, with --stability, stability.csv.
 *
 * Method (IVP Test Set conventions, shared/testset/README.md): every solver starts from the same
 * consistent initial values (computed once by dae_consistent_init: IDA's own initialisation
 * handles index 1 only); CPU time of the integration alone, after a warm-up run, minimum of K
 * repetitions (the median is reported beside it); accuracy as scd (scored components) and mescd,
 * index-2 components apart. IDA runs as its guide recommends for index 2: id vector, algebraic
 * variables suppressed from the error test, fed the same residual and Jacobian code (dense, or
 * sparse CSC for KLU). Problems with breakpoints are integrated segment by segment (IDA is
 * re-initialised at each; its counters are summed). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/utsname.h>
#include <time.h>
#include <unistd.h>

#include "bench_util.h"
#include "problems.h"

#ifdef BENCH_HAVE_IDA
#include <ida/ida.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>
#endif

#include "bench_version.h" /* BENCH_COMMIT, generated at build time */
#ifndef BENCH_BUILD_FLAGS
#define BENCH_BUILD_FLAGS "unknown"
#endif

#define MAXN 64
#define MAXSOLVERS 8
#define MAXRTOL 16
#define MAXPROB 32

typedef struct solver_def {
    const char *name;
    int ida;
    ls_kind ls;
    dae_index2_policy pol;
} solver_def;

static const solver_def SOLVERS[] = {
    {"bgdae-klu", 0, LS_KLU, DAE_I2_EXCLUDE},     {"bgdae-klu-scaleh", 0, LS_KLU, DAE_I2_SCALE_H},
    {"bgdae-dense", 0, LS_DENSE, DAE_I2_EXCLUDE}, {"ida-klu", 1, LS_KLU, DAE_I2_EXCLUDE},
    {"ida-dense", 1, LS_DENSE, DAE_I2_EXCLUDE},
};
#define NSOLVERS ((int)(sizeof SOLVERS / sizeof *SOLVERS))

/* atol = factor * rtol; the components' scales differ too much for atol = rtol in these. */
static double atol_factor(const char *name)
{
    if (!strcmp(name, "robertson")) return 1e-6;
    if (!strcmp(name, "pump")) return 1e-8;
    if (!strcmp(name, "hires")) return 1e-4;
    return 1e-2;
}

typedef struct run_out {
    int status;
    char msg[BG_MESSAGE_SIZE];
    double y[MAXN];
    long steps, rejected, newton, conv_fail, res, jac, fact, solves;
    int max_order;
    double cpu_min, cpu_med;
} run_out;

/* ---------------------------------------------------------------- ours ---- */

static void set_options(dae_options *o, const bp_problem *p, const solver_def *sd, double rtol,
                        double atol)
{
    dae_options_default(o);
    o->rtol = rtol;
    o->atol = atol;
    o->linsol = sd->ls;
    o->index2 = sd->pol;
    o->has_t_stop = 1;
    o->t_stop = p->tend;
    o->breakpoints = p->breakpoints;
    o->nbreakpoints = p->nbreakpoints;
    o->max_steps = 2000000;
}

static void run_ours(const bp_problem *p, const solver_def *sd, double rtol, double atol,
                     const double *y0, const double *yp0, run_out *out)
{
    bp_instance in;
    memset(&in, 0, sizeof in);
    out->status = -1;
    if (bp_instance_init(&in, p) != 0) {
        snprintf(out->msg, sizeof out->msg, "out of memory");
        return;
    }
    dae_options o;
    set_options(&o, p, sd, rtol, atol);
    bg_error err = {0};
    dae_solver *s = dae_create(&in.dp, &o, &err);
    if (!s) {
        snprintf(out->msg, sizeof out->msg, "%s", err.message);
        bp_instance_free(&in);
        return;
    }
    double t, yp[MAXN];
    int r = dae_init(s, p->t0, y0, yp0);
    while (r == 0) {
        r = dae_solve_to(s, p->tend, &t, out->y, yp);
        if (r == DAE_TSTOP_RETURN || (r == 0 && t >= p->tend)) {
            r = 0;
            break;
        }
    }
    if (r < 0) snprintf(out->msg, sizeof out->msg, "%s", dae_get_error(s)->message);
    const dae_stats *st = dae_get_stats(s);
    out->status = r;
    out->steps = st->steps;
    out->rejected = st->rejected_error;
    out->newton = st->newton_iters;
    out->conv_fail = st->newton_fails;
    out->res = st->res_evals + st->res_evals_fd;
    out->jac = st->jac_evals;
    out->fact = st->factor_full + st->factor_refactor;
    out->solves = st->linear_solves;
    out->max_order = 0;
    for (int k = 1; k <= 5; k++)
        if (st->steps_at_order[k]) out->max_order = k;
    dae_free(&s);
    bp_instance_free(&in);
}

/* ----------------------------------------------------------------- IDA ---- */

#ifdef BENCH_HAVE_IDA
static void run_ida(const bp_problem *p, const solver_def *sd, double rtol, double atol,
                    const double *y0, const double *yp0, run_out *out)
{
    int n = p->n;
    SUNContext ctx = NULL;
    out->status = -1;
    if (SUNContext_Create(NULL, &ctx) != 0) {
        snprintf(out->msg, sizeof out->msg, "SUNContext_Create failed");
        return;
    }
    bench_ida_ctx c = {p, NULL, NULL, NULL};
    p->patterns(&c.jy, &c.jyp);
    c.u = c.jy && c.jyp ? sp_union_create(c.jy, c.jyp) : NULL;
    N_Vector yy = N_VNew_Serial(n, ctx), yp = N_VNew_Serial(n, ctx), id = N_VNew_Serial(n, ctx);
    SUNMatrix A = c.u ? (sd->ls == LS_KLU ? SUNSparseMatrix(n, n, c.u->M->nnz, CSC_MAT, ctx)
                                          : SUNDenseMatrix(n, n, ctx))
                      : NULL;
    SUNLinearSolver LS = A ? (sd->ls == LS_KLU ? SUNLinSol_KLU(yy, A, ctx)
                                               : SUNLinSol_Dense(yy, A, ctx))
                           : NULL;
    void *mem = IDACreate(ctx);
    long acc[7] = {0};
    realtype t = p->t0;
    if (!LS || !mem) {
        snprintf(out->msg, sizeof out->msg, "IDA set-up failed (memory)");
        goto done;
    }
    for (int i = 0; i < n; i++) {
        NV_Ith_S(yy, i) = y0[i];
        NV_Ith_S(yp, i) = yp0[i];
        NV_Ith_S(id, i) = p->kind[i] == DAE_DIFF ? 1.0 : 0.0;
    }
    if (IDAInit(mem, bench_ida_res, p->t0, yy, yp) || IDASStolerances(mem, rtol, atol) ||
        IDASetUserData(mem, &c) || IDASetLinearSolver(mem, LS, A) ||
        IDASetJacFn(mem, bench_ida_jac) || IDASetId(mem, id) || IDASetSuppressAlg(mem, SUNTRUE) ||
        IDASetMaxNumSteps(mem, 2000000)) {
        snprintf(out->msg, sizeof out->msg, "IDA set-up failed");
        goto done;
    }
    for (int b = 0; b <= p->nbreakpoints; b++) {
        double tb = b < p->nbreakpoints ? p->breakpoints[b] : p->tend;
        IDASetStopTime(mem, tb);
        int r = IDASolve(mem, tb, &t, yy, yp, IDA_NORMAL);
        long v[7];
        IDAGetNumSteps(mem, &v[0]);
        IDAGetNumErrTestFails(mem, &v[1]);
        IDAGetNumNonlinSolvIters(mem, &v[2]);
        IDAGetNumNonlinSolvConvFails(mem, &v[3]);
        IDAGetNumResEvals(mem, &v[4]);
        IDAGetNumJacEvals(mem, &v[5]);
        IDAGetNumLinSolvSetups(mem, &v[6]);
        for (int k = 0; k < 7; k++) acc[k] += v[k];
        if (r < 0) {
            snprintf(out->msg, sizeof out->msg, "IDASolve returned %d (%s) at t = %.9g", r,
                     IDAGetReturnFlagName(r), t);
            out->status = r;
            goto done;
        }
        if (b < p->nbreakpoints) IDAReInit(mem, t, yy, yp);
    }
    out->status = 0;
done:
    for (int i = 0; i < n && yy; i++) out->y[i] = NV_Ith_S(yy, i);
    out->steps = acc[0];
    out->rejected = acc[1];
    out->newton = acc[2];
    out->conv_fail = acc[3];
    out->res = acc[4];
    out->jac = acc[5];
    out->fact = acc[6];
    out->solves = acc[2];
    out->max_order = 0;
    IDAFree(&mem);
    if (LS) SUNLinSolFree(LS);
    if (A) SUNMatDestroy(A);
    N_VDestroy(yy);
    N_VDestroy(yp);
    N_VDestroy(id);
    sp_union_free(&c.u);
    sp_csc_free(&c.jy);
    sp_csc_free(&c.jyp);
    SUNContext_Free(&ctx);
}
#endif

/* Warm-up, then K timed runs: CPU minimum and median. */
static void timed(const bp_problem *p, const solver_def *sd, double rtol, double atol,
                  const double *y0, const double *yp0, int K, run_out *out)
{
    double ts[64];
    if (K > 64) K = 64;
    int done = 0;
    for (int k = -1; k < K; k++) {
        double t0 = bench_cpu_now();
#ifdef BENCH_HAVE_IDA
        if (sd->ida)
            run_ida(p, sd, rtol, atol, y0, yp0, out);
        else
#endif
            run_ours(p, sd, rtol, atol, y0, yp0, out);
        double t1 = bench_cpu_now();
        if (k >= 0) ts[done++] = t1 - t0;
        if (out->status < 0) { /* a failure is not timed further */
            if (done == 0) ts[done++] = t1 - t0;
            break;
        }
    }
    out->cpu_med = bench_median(ts, done);
    out->cpu_min = ts[0];
}

/* Consistent start shared by every solver. */
static int consistent_start(const bp_problem *p, double rtol, double *y0, double *yp0,
                            char *msg, size_t msz)
{
    bp_instance in;
    memset(&in, 0, sizeof in);
    if (bp_instance_init(&in, p) != 0) return -1;
    dae_options o;
    dae_options_default(&o);
    o.rtol = rtol;
    o.atol = rtol * atol_factor(p->name);
    bg_error err = {0};
    dae_solver *s = dae_create(&in.dp, &o, &err);
    int r = s ? dae_init(s, p->t0, p->y0, p->yp0) : -1;
    if (r == 0) r = dae_consistent_init(s);
    if (r == 0) r = dae_dense(s, p->t0, y0, yp0);
    if (r != 0) snprintf(msg, msz, "%s", s ? dae_get_error(s)->message : err.message);
    dae_free(&s);
    bp_instance_free(&in);
    return r;
}

/* ------------------------------------------------------------- reporting ---- */

typedef struct row {
    const bp_problem *p;
    const solver_def *sd;
    double rtol, atol;
    run_out r;
    bp_score sc;
} row;

static int split_list(char *s, char **items, int max)
{
    int n = 0;
    for (char *tok = strtok(s, ","); tok && n < max; tok = strtok(NULL, ",")) items[n++] = tok;
    return n;
}

/* scd is +inf where the error is exactly zero: count it as the 16 digits of double precision. */
static double capped(double scd) { return scd > 16 ? 16 : scd; }

/* log10 of CPU time at accuracy target on the curve of (scd, cpu) points: linear interpolation
 * in (scd, log cpu) between neighbours that bracket the target; NAN if none. */
static double cpu_at(const row *rows, int nrows, const bp_problem *p, const char *solver,
                     double target)
{
    double best = NAN;
    for (int a = 0; a < nrows; a++) {
        const row *A = &rows[a];
        double sa = capped(A->sc.scd);
        if (A->p != p || strcmp(A->sd->name, solver) || A->r.status < 0 || isnan(sa)) continue;
        for (int b = 0; b < nrows; b++) {
            const row *B = &rows[b];
            double sb = capped(B->sc.scd);
            if (B->p != p || strcmp(B->sd->name, solver) || B->r.status < 0 || isnan(sb) ||
                !(sa <= target && sb >= target) || sa == sb)
                continue;
            double w = (target - sa) / (sb - sa);
            double lc = (1 - w) * log10(A->r.cpu_min) + w * log10(B->r.cpu_min);
            if (isnan(best) || lc < best) best = lc;
        }
    }
    return best;
}

static void write_csv(FILE *f, const row *rows, int n)
{
    fprintf(f, "problem,solver,rtol,atol,status,scd,mescd,scd_index2,cpu_s,cpu_median_s,steps,"
               "rejected,newton,conv_fail,res_evals,jac_evals,factorizations,solves\n");
    for (int i = 0; i < n; i++) {
        const row *r = &rows[i];
        fprintf(f, "%s,%s,%g,%g,%d,%.3f,%.3f,%.3f,%.6g,%.6g,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld\n",
                r->p->name, r->sd->name, r->rtol, r->atol, r->r.status, r->sc.scd, r->sc.mescd,
                r->sc.scd_i2, r->r.cpu_min, r->r.cpu_med, r->r.steps, r->r.rejected, r->r.newton,
                r->r.conv_fail, r->r.res, r->r.jac, r->r.fact, r->r.solves);
    }
}

static void plot(const char *dir, const bp_problem *p, const row *rows, int n, const char **sol,
                 int ns)
{
    char dat[512], png[512];
    snprintf(dat, sizeof dat, "%s/wp_%s.dat", dir, p->name);
    snprintf(png, sizeof png, "%s/wp_%s.png", dir, p->name);
    FILE *f = fopen(dat, "w");
    if (!f) return;
    for (int s = 0; s < ns; s++) {
        fprintf(f, "# %s\n", sol[s]);
        for (int i = 0; i < n; i++)
            if (rows[i].p == p && !strcmp(rows[i].sd->name, sol[s]) && rows[i].r.status >= 0)
                fprintf(f, "%.6g %.4f %ld\n", rows[i].r.cpu_min, rows[i].sc.scd, rows[i].r.steps);
        fprintf(f, "\n\n");
    }
    fclose(f);
    char cmd[4096];
    int len = snprintf(cmd, sizeof cmd,
                       "gnuplot -e \"set terminal png size 1000,420; set output '%s'; "
                       "set multiplot layout 1,2 title '%s'; set logscale x; set grid; "
                       "set key bottom right; set xlabel 'CPU time [s]'; set ylabel 'scd'; plot ",
                       png, p->name);
    for (int s = 0; s < ns; s++)
        len += snprintf(cmd + len, sizeof cmd - (size_t)len,
                        "'%s' index %d using 1:2 with linespoints title '%s'%s", dat, s, sol[s],
                        s + 1 < ns ? ", " : "; ");
    len += snprintf(cmd + len, sizeof cmd - (size_t)len,
                    "set xlabel 'steps'; plot ");
    for (int s = 0; s < ns; s++)
        len += snprintf(cmd + len, sizeof cmd - (size_t)len,
                        "'%s' index %d using 3:2 with linespoints title '%s'%s", dat, s, sol[s],
                        s + 1 < ns ? ", " : "; ");
    snprintf(cmd + len, sizeof cmd - (size_t)len, "unset multiplot\" >/dev/null 2>&1");
    if (system(cmd) != 0) remove(png);
}

static void write_report(FILE *f, const row *rows, int n, const bp_problem **probs, int np,
                         const char **sol, int ns, double wall)
{
    struct utsname u;
    uname(&u);
    fprintf(f, "# Benchmark report\n\n");
    fprintf(f, "- machine: %s %s %s, %ld cores online\n", u.sysname, u.release, u.machine,
            sysconf(_SC_NPROCESSORS_ONLN));
    fprintf(f, "- commit: %s\n- build: %s\n", BENCH_COMMIT, BENCH_BUILD_FLAGS);
    fprintf(f, "- timing: CPU time of the integration alone, after a warm-up run, minimum of the "
               "repetitions (median beside it in work_precision.csv)\n");
    fprintf(f, "- accuracy: scd over the scored components, index-2 components apart (scd2); "
               "atol = factor * rtol per problem\n- wall time of this run: %.1f s\n\n",
            wall);
    for (int q = 0; q < np; q++) {
        const bp_problem *p = probs[q];
        fprintf(f, "## %s (n = %d): %s\n\n", p->name, p->n, p->title ? p->title : "");
        fprintf(f, "| solver | rtol | status | scd | mescd | scd2 | CPU s | steps | rejected | "
                   "Jacobians | factorizations |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
        for (int i = 0; i < n; i++) {
            const row *r = &rows[i];
            if (r->p != p) continue;
            fprintf(f, "| %s | %g | %s | %.2f | %.2f | %.2f | %.4g | %ld | %ld | %ld | %ld |\n",
                    r->sd->name, r->rtol, r->r.status < 0 ? "FAIL" : "ok", r->sc.scd, r->sc.mescd,
                    r->sc.scd_i2, r->r.cpu_min, r->r.steps, r->r.rejected, r->r.jac, r->r.fact);
        }
        fprintf(f, "\nFastest at equal accuracy (interpolated on the scd axis):\n\n| scd |");
        for (int s = 0; s < ns; s++) fprintf(f, " %s |", sol[s]);
        fprintf(f, " winner | bgdae-klu / ida-klu |\n|---|");
        for (int s = 0; s <= ns + 1; s++) fprintf(f, "---|");
        fprintf(f, "\n");
        for (int target = 4; target <= 8; target += 2) {
            fprintf(f, "| %d |", target);
            double bestv = NAN;
            const char *win = "-";
            for (int s = 0; s < ns; s++) {
                double lc = cpu_at(rows, n, p, sol[s], target);
                if (isnan(lc))
                    fprintf(f, " - |");
                else
                    fprintf(f, " %.3g s |", pow(10, lc));
                if (!isnan(lc) && (isnan(bestv) || lc < bestv)) {
                    bestv = lc;
                    win = sol[s];
                }
            }
            double a = cpu_at(rows, n, p, "bgdae-klu", target),
                   b = cpu_at(rows, n, p, "ida-klu", target);
            if (isnan(a) || isnan(b))
                fprintf(f, " %s | - |\n", win);
            else
                fprintf(f, " %s | %.2f |\n", win, pow(10, a - b));
        }
        fprintf(f, "\n![work-precision %s](wp_%s.png)\n\n", p->name, p->name);
    }
    fprintf(f, "## Failures\n\n");
    int nf = 0;
    for (int i = 0; i < n; i++)
        if (rows[i].r.status < 0) {
            fprintf(f, "- %s, %s, rtol %g: status %d: %s\n", rows[i].p->name, rows[i].sd->name,
                    rows[i].rtol, rows[i].r.status, rows[i].r.msg);
            nf++;
        }
    if (!nf) fprintf(f, "none\n");
}

/* -------------------------------------------------------- stability suite ---- */

/* Brenan, Campbell and Petzold (1996), sec. 3.2 (a linear time-varying index-2 system of Gear
 * and Petzold): y1 + eta t y2 = g(t), y1' + eta t y2' + (1 + eta) y2 = 0; exact y2 = -g',
 * y1 = g + eta t g'. BDF is unstable on it for eta < -0.5. g = sin t here. */
static double bcp_eta;
static sp_csc *bcp_jy, *bcp_jyp;
static int bcp_res(void *u, double t, const double *y, const double *yp, double *F)
{
    (void)u;
    F[0] = y[0] + bcp_eta * t * y[1] - sin(t);
    F[1] = yp[0] + bcp_eta * t * yp[1] + (1 + bcp_eta) * y[1];
    return 0;
}

typedef struct stab_case {
    const char *name;
    const char *problem; /* from the collection, or NULL for the local BCP problem */
    double rtol;
    double eta;
    int perturb;        /* start off the constraint manifold: the reference is then a run from
                           the projected start at rtol 1e-11 */
    int no_breakpoints;
} stab_case;

/* Integrates from (y0, yp0), after dae_consistent_init unless given_consistent; y at tend. */
static int stab_run(const dae_problem *dp, const dae_options *o, double t0, double tend,
                    const double *y0, const double *yp0, int given_consistent, double *y,
                    dae_stats *st, char *msg, size_t msz)
{
    bg_error err = {0};
    dae_solver *s = dae_create(dp, o, &err);
    double yp[MAXN], t = t0;
    int r = s ? dae_init(s, t0, y0, yp0) : -1;
    if (r == 0 && !given_consistent) r = dae_consistent_init(s);
    while (r == 0) {
        r = dae_solve_to(s, tend, &t, y, yp);
        if (r == DAE_TSTOP_RETURN || (r == 0 && t >= tend)) {
            r = 0;
            break;
        }
    }
    if (r < 0) snprintf(msg, msz, "%s", s ? dae_get_error(s)->message : err.message);
    if (s) *st = *dae_get_stats(s);
    dae_free(&s);
    return r;
}

static void stability(const char *dir, FILE *rep)
{
    static const stab_case cases[] = {
        {"pendulum rtol 1e-2", "pendulum2", 1e-2, 0, 0, 0},
        {"pendulum rtol 1e-12", "pendulum2", 1e-12, 0, 0, 0},
        {"robertson rtol 1e-2", "robertson", 1e-2, 0, 0, 0},
        {"robertson rtol 1e-12", "robertson", 1e-12, 0, 0, 0},
        {"vdp eps 1e-6 rtol 1e-2", "vdp_scaled", 1e-2, 0, 0, 0},
        {"vdp eps 1e-6 rtol 1e-12", "vdp_scaled", 1e-12, 0, 0, 0},
        {"hires rtol 1e-12", "hires", 1e-12, 0, 0, 0},
        {"ap102 rtol 1e-12", "ap102", 1e-12, 0, 0, 0},
        {"pendulum off the manifold", "pendulum2", 1e-6, 0, 1, 0},
        {"kinks without breakpoints", "kinks", 1e-6, 0, 0, 1},
        {"kinks with breakpoints", "kinks", 1e-6, 0, 0, 0},
        {"BCP index 2, eta = -0.3", NULL, 1e-6, -0.3, 0, 0},
        {"BCP index 2, eta = -0.8 (BDF unstable)", NULL, 1e-6, -0.8, 0, 0},
    };
    char path[512];
    snprintf(path, sizeof path, "%s/stability.csv", dir);
    FILE *f = fopen(path, "w");
    if (!f) return;
    fprintf(f, "case,outcome,status,steps,highest_order,rejected,error_in_tolerances,drift,"
               "message\n");
    fprintf(rep, "## Stability suite\n\n| case | outcome | steps | highest order | rejected | "
                 "error (tolerances) | drift |\n|---|---|---|---|---|---|---|\n");
    for (size_t c = 0; c < sizeof cases / sizeof *cases; c++) {
        const stab_case *sc = &cases[c];
        dae_options o;
        dae_options_default(&o);
        o.rtol = sc->rtol;
        o.max_steps = 2000000;
        bp_instance in;
        memset(&in, 0, sizeof in);
        dae_problem dp = {0};
        double y0[MAXN], yp0[MAXN], yref[MAXN], tend;
        int n;
        const bp_problem *p = sc->problem ? bp_find(sc->problem) : NULL;
        if (p) {
            if (bp_instance_init(&in, p) != 0) continue;
            dp = in.dp;
            n = p->n;
            memcpy(y0, p->y0, (size_t)n * sizeof *y0);
            memcpy(yp0, p->yp0, (size_t)n * sizeof *yp0);
            if (sc->perturb)
                for (int i = 0; i < n && i < 4; i++) y0[i] += 0.01 * (i + 1);
            tend = p->tend;
            bp_reference(p, yref);
            o.atol = sc->rtol * atol_factor(p->name);
            if (!sc->no_breakpoints) {
                o.breakpoints = p->breakpoints;
                o.nbreakpoints = p->nbreakpoints;
            }
        } else {
            bcp_eta = sc->eta;
            n = 2;
            dp.n = 2;
            dp.res = bcp_res; /* finite-difference Jacobian on dense patterns */
            static const int bcp_kind[2] = {DAE_DIFF, DAE_ALG2}; /* y2 = -g' is index 2 */
            static const double full[4] = {1, 1, 1, 1}, rowtwo[4] = {0, 1, 0, 1};
            dp.kind = bcp_kind;
            bcp_jy = sp_csc_from_dense(2, 2, full, 0.0);
            bcp_jyp = sp_csc_from_dense(2, 2, rowtwo, 0.0); /* y1' and y2' in row 2 */
            dp.jac_y_pattern = bcp_jy;
            dp.jac_yp_pattern = bcp_jyp;
            tend = 3.0;
            /* consistent values from the exact solution: y2 = -cos t, y1 = sin t + eta t cos t
             * (this system is not semi-explicit; dae_consistent_init does not apply) */
            y0[1] = -1.0;
            y0[0] = 0.0;
            yp0[0] = 1.0 + bcp_eta;
            yp0[1] = 0.0;
            yref[1] = -cos(tend);
            yref[0] = sin(tend) + bcp_eta * tend * cos(tend);
            o.atol = sc->rtol * 1e-2;
        }
        o.has_t_stop = 1;
        o.t_stop = tend;
        double y[MAXN];
        dae_stats stv = {0};
        char msgb[BG_MESSAGE_SIZE] = "";
        int r = stab_run(&dp, &o, p ? p->t0 : 0.0, tend, y0, yp0, !p, y, &stv, msgb,
                         sizeof msgb);
        if (sc->perturb && r == 0) { /* reference from the projected start, run tight */
            dae_options ot = o;
            ot.rtol = 1e-11;
            ot.atol = 1e-11 * atol_factor(p->name);
            dae_stats sr;
            char m2[BG_MESSAGE_SIZE - 32];
            if (stab_run(&dp, &ot, p->t0, tend, y0, yp0, 0, yref, &sr, m2, sizeof m2) != 0)
                snprintf(msgb, sizeof msgb, "reference run failed: %s", m2);
        }
        double e = 0;
        for (int i = 0; i < n; i++)
            if (!p || p->kind[i] != DAE_ALG2)
                e = fmax(e, fabs(y[i] - yref[i]) / (o.rtol * fabs(yref[i]) + o.atol));
        const dae_stats *st = &stv;
        int hi = 0;
        for (int k = 1; k <= 5; k++)
            if (st->steps_at_order[k]) hi = k;
        /* the global error of a long stiff run may exceed the local tolerance by some hundreds */
        const char *outcome = r < 0 ? "stopped with a diagnostic" : e <= 1000 ? "solved" : "WRONG";
        const char *msg = msgb;
        fprintf(f, "\"%s\",%s,%d,%ld,%d,%ld,%.3g,%.3g,\"%s\"\n", sc->name, outcome, r,
                st->steps, hi, st->rejected_error, e, st->max_drift, msg);
        fprintf(rep, "| %s | %s%s%s | %ld | %d | %ld | %.3g | %.3g |\n", sc->name, outcome,
                r < 0 ? ": " : "", msg, st->steps, hi, st->rejected_error, e, st->max_drift);
        bp_instance_free(&in);
        sp_csc_free(&bcp_jy);
        sp_csc_free(&bcp_jyp);
    }
    fclose(f);
}

/* -------------------------------------------------------------------- main ---- */

static int usage(const char *bad)
{
    fprintf(stderr,
            "bench: %s\nusage: bench [--problems LIST] [--solvers LIST] [--rtols LIST] "
            "[--repeat K] [--stability] [--quick] [--out DIR]\n  solvers:",
            bad);
    for (int s = 0; s < NSOLVERS; s++) fprintf(stderr, " %s", SOLVERS[s].name);
    fprintf(stderr, "\n  problems:");
    for (int i = 0; i < bp_count(); i++) fprintf(stderr, " %s", bp_get(i)->name);
    fprintf(stderr, "\n");
    return 2;
}

static int mkdirs(const char *dir)
{
    char buf[512];
    snprintf(buf, sizeof buf, "%s", dir);
    for (char *q = buf + 1; *q; q++)
        if (*q == '/') {
            *q = '\0';
            if (mkdir(buf, 0755) != 0 && errno != EEXIST) return -1;
            *q = '/';
        }
    return mkdir(buf, 0755) != 0 && errno != EEXIST ? -1 : 0;
}

int main(int argc, char **argv)
{
    char *plist = NULL, *slist = NULL, *rlist = NULL;
    const char *out = "results/bench";
    int K = 3, stab = 0, quick = 0;
    for (int a = 1; a < argc; a++) {
        if (!strcmp(argv[a], "--problems") && a + 1 < argc)
            plist = argv[++a];
        else if (!strcmp(argv[a], "--solvers") && a + 1 < argc)
            slist = argv[++a];
        else if (!strcmp(argv[a], "--rtols") && a + 1 < argc)
            rlist = argv[++a];
        else if (!strcmp(argv[a], "--repeat") && a + 1 < argc)
            K = atoi(argv[++a]);
        else if (!strcmp(argv[a], "--out") && a + 1 < argc)
            out = argv[++a];
        else if (!strcmp(argv[a], "--stability"))
            stab = 1;
        else if (!strcmp(argv[a], "--quick"))
            quick = 1;
        else {
            char m[256];
            snprintf(m, sizeof m, "unknown or incomplete argument '%s'", argv[a]);
            return usage(m);
        }
    }
    if (K < 1 || K > 64) return usage("--repeat takes a number from 1 to 64");
    const bp_problem *probs[MAXPROB];
    int np = 0;
    char *items[MAXPROB];
    if (plist) {
        int k = split_list(plist, items, MAXPROB);
        for (int i = 0; i < k; i++) {
            const bp_problem *p = bp_find(items[i]);
            if (!p) {
                char m[256];
                snprintf(m, sizeof m, "unknown problem '%s'", items[i]);
                return usage(m);
            }
            probs[np++] = p;
        }
    } else
        for (int i = 0; i < bp_count() && np < MAXPROB; i++)
            if (bp_get(i)->yref || bp_get(i)->exact) probs[np++] = bp_get(i);
    const solver_def *sols[MAXSOLVERS];
    const char *solnames[MAXSOLVERS];
    int ns = 0;
    if (slist) {
        int k = split_list(slist, items, MAXSOLVERS);
        for (int i = 0; i < k; i++) {
            int found = -1;
            for (int s = 0; s < NSOLVERS; s++)
                if (!strcmp(items[i], SOLVERS[s].name)) found = s;
            if (found < 0) {
                char m[256];
                snprintf(m, sizeof m, "unknown solver '%s'", items[i]);
                return usage(m);
            }
            sols[ns++] = &SOLVERS[found];
        }
    } else
        for (int s = 0; s < NSOLVERS; s++) sols[ns++] = &SOLVERS[s];
#ifndef BENCH_HAVE_IDA
    for (int s = 0; s < ns; s++)
        if (sols[s]->ida) {
            fprintf(stderr, "bench: built without SUNDIALS IDA; solver '%s' is not available\n",
                    sols[s]->name);
            return 2;
        }
#endif
    for (int s = 0; s < ns; s++) solnames[s] = sols[s]->name;
    double rtols[MAXRTOL];
    int nr = 0;
    if (rlist) {
        int k = split_list(rlist, items, MAXRTOL);
        for (int i = 0; i < k; i++) {
            char *end;
            rtols[nr] = strtod(items[i], &end);
            if (*end || !(rtols[nr] > 0 && rtols[nr] < 1)) {
                char m[256];
                snprintf(m, sizeof m, "--rtols: '%s' is not a number in (0, 1)", items[i]);
                return usage(m);
            }
            nr++;
        }
    } else if (quick) {
        rtols[nr++] = 1e-4;
        rtols[nr++] = 1e-7;
    } else
        for (int e = 4; e <= 10; e++) rtols[nr++] = pow(10.0, -e);
    if (quick && K > 1) K = 1;
    if (mkdirs(out) != 0) {
        fprintf(stderr, "bench: cannot create the output folder '%s': %s\n", out, strerror(errno));
        return 1;
    }
    row *rows = calloc((size_t)np * ns * nr + 1, sizeof *rows);
    if (!rows) return 1;
    int n = 0, failures = 0;
    struct timespec wt0, wt1;
    clock_gettime(CLOCK_MONOTONIC, &wt0);
    for (int q = 0; q < np; q++) {
        const bp_problem *p = probs[q];
        double yref[MAXN];
        bp_reference(p, yref);
        for (int k = 0; k < nr; k++) {
            double y0[MAXN], yp0[MAXN];
            char msg[BG_MESSAGE_SIZE] = "";
            if (consistent_start(p, rtols[k], y0, yp0, msg, sizeof msg) != 0) {
                fprintf(stderr, "bench: %s: no consistent start at rtol %g: %s\n", p->name,
                        rtols[k], msg);
                memcpy(y0, p->y0, (size_t)p->n * sizeof *y0);
                memcpy(yp0, p->yp0, (size_t)p->n * sizeof *yp0);
            }
            for (int s = 0; s < ns; s++) {
                row *r = &rows[n++];
                r->p = p;
                r->sd = sols[s];
                r->rtol = rtols[k];
                r->atol = rtols[k] * atol_factor(p->name);
                timed(p, sols[s], r->rtol, r->atol, y0, yp0, K, &r->r);
                bp_score_compute(p, r->r.y, yref, r->rtol, r->atol, &r->sc);
                if (r->r.status < 0) failures += !sols[s]->ida;
                fprintf(stderr, "%-12s %-17s rtol %-6g %s scd %6.2f  cpu %.4g s  steps %ld\n",
                        p->name, sols[s]->name, r->rtol, r->r.status < 0 ? "FAIL" : "ok  ",
                        r->sc.scd, r->r.cpu_min, r->r.steps);
            }
        }
    }
    char path[512];
    snprintf(path, sizeof path, "%s/work_precision.csv", out);
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "bench: cannot write %s: %s\n", path, strerror(errno));
        free(rows);
        return 1;
    }
    write_csv(f, rows, n);
    fclose(f);
    for (int q = 0; q < np; q++) plot(out, probs[q], rows, n, solnames, ns);
    snprintf(path, sizeof path, "%s/report.md", out);
    f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "bench: cannot write %s: %s\n", path, strerror(errno));
        free(rows);
        return 1;
    }
    clock_gettime(CLOCK_MONOTONIC, &wt1);
    write_report(f, rows, n, probs, np, solnames, ns,
                 (double)(wt1.tv_sec - wt0.tv_sec) + 1e-9 * (double)(wt1.tv_nsec - wt0.tv_nsec));
    if (stab) stability(out, f);
    fclose(f);
    free(rows);
    printf("bench: %d runs, %d failures of our solver; results in %s\n", n, failures, out);
    return failures ? 1 : 0;
}
