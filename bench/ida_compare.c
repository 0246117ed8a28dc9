/* Our modified BDF against SUNDIALS IDA on problems of the collection (bench/problems.h), over a
 * sweep of tolerances: steps, error-test failures, Jacobian evaluations, factorizations,
 * residual evaluations, CPU time (median and minimum of R timed runs after one warm-up), and the
 * accuracy at the end point as scd / mescd, index-2 components apart.
 *
 * IDA is set up as its guide recommends for index 2: the id vector marks the algebraic variables,
 * their error test is suppressed (IDASetSuppressAlg), the stop time is the end point; dense
 * linear algebra with the analytic Jacobian dF/dy + cj dF/dy'. --no-suppress keeps the algebraic
 * variables in IDA's error test (the setting of IDA's own example idaAnalytic_mels).
 *
 * usage: ida_compare [--problem NAME]... [--reps R] [--atol-factor F] [--linsol klu|dense]
 *                    [--no-suppress] [--csv] [--rtol r1,r2,...] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <ida/ida.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "bench_util.h"
#include "bg_dae.h"
#include "problems.h"

typedef struct run_result {
    int status;
    double y[64];
    long steps, rejected, jac, factors, res;
    double tmed, tmin;
} run_result;

/* ---- ours ---- */
static int run_ours(const bp_problem *p, double rtol, double atol, ls_kind ls, double *y,
                    run_result *rr, char *msg, size_t msz)
{
    bp_instance in;
    memset(&in, 0, sizeof in);
    if (bp_instance_init(&in, p) != 0) return -1;
    dae_options o;
    dae_options_default(&o);
    o.rtol = rtol;
    o.atol = atol;
    o.linsol = ls;
    o.has_t_stop = 1;
    o.t_stop = p->tend;
    o.breakpoints = p->breakpoints;
    o.nbreakpoints = p->nbreakpoints;
    bg_error err = {0};
    dae_solver *s = dae_create(&in.dp, &o, &err);
    if (!s) {
        snprintf(msg, msz, "%s", err.message);
        bp_instance_free(&in);
        return -1;
    }
    double t, *yp = malloc((size_t)p->n * sizeof *yp);
    int r = dae_init(s, p->t0, p->y0, p->yp0);
    if (r == 0) r = dae_consistent_init(s);
    if (r == DAE_WARNING) r = 0;
    while (r >= 0 && r != DAE_TSTOP_RETURN && (r = dae_solve_to(s, p->tend, &t, y, yp)) == 0 &&
           t < p->tend)
        ;
    if (r == DAE_TSTOP_RETURN) r = 0;
    if (r < 0) snprintf(msg, msz, "%s", dae_get_error(s)->message);
    const dae_stats *st = dae_get_stats(s);
    rr->steps = st->steps;
    rr->rejected = st->rejected_error;
    rr->jac = st->jac_evals;
    rr->factors = st->factor_full + st->factor_refactor;
    rr->res = st->res_evals + st->res_evals_fd;
    free(yp);
    dae_free(&s);
    bp_instance_free(&in);
    return r;
}

/* ---- IDA ---- */
static int run_ida(const bp_problem *p, double rtol, double atol, int suppress, double *y,
                   run_result *rr, char *msg, size_t msz)
{
    int n = p->n, r = -1;
    SUNContext ctx = NULL;
    if (SUNContext_Create(NULL, &ctx) != 0) return -1;
    bp_instance in;
    memset(&in, 0, sizeof in);
    bench_ida_ctx c;
    memset(&c, 0, sizeof c);
    if (bp_instance_init(&in, p) == 0) bench_ida_ctx_init(&c, &in.dp);
    N_Vector yy = N_VNew_Serial(n, ctx), yp = N_VNew_Serial(n, ctx), id = N_VNew_Serial(n, ctx);
    SUNMatrix A = SUNDenseMatrix(n, n, ctx);
    SUNLinearSolver LS = SUNLinSol_Dense(yy, A, ctx);
    void *mem = IDACreate(ctx);
    for (int i = 0; i < n; i++) {
        NV_Ith_S(yy, i) = p->y0[i];
        NV_Ith_S(yp, i) = p->yp0[i];
        NV_Ith_S(id, i) = p->kind[i] == DAE_DIFF ? 1.0 : 0.0;
    }
    if (!c.u || IDAInit(mem, bench_ida_res, p->t0, yy, yp) || IDASStolerances(mem, rtol, atol) ||
        IDASetUserData(mem, &c) || IDASetLinearSolver(mem, LS, A) ||
        IDASetJacFn(mem, bench_ida_jac) || IDASetId(mem, id) ||
        IDASetSuppressAlg(mem, suppress ? SUNTRUE : SUNFALSE) || IDASetStopTime(mem, p->tend) ||
        IDASetMaxNumSteps(mem, 500000)) {
        snprintf(msg, msz, "IDA set-up failed");
        goto done;
    }
    /* IDAReInit at each breakpoint resets IDA's counters: add them up segment by segment */
    realtype t = p->t0;
    memset(rr, 0, sizeof *rr);
    for (int b = 0; b <= p->nbreakpoints; b++) {
        double tb = b < p->nbreakpoints ? p->breakpoints[b] : p->tend;
        IDASetStopTime(mem, tb);
        r = IDASolve(mem, tb, &t, yy, yp, IDA_NORMAL);
        long v;
        IDAGetNumSteps(mem, &v), rr->steps += v;
        IDAGetNumErrTestFails(mem, &v), rr->rejected += v;
        IDAGetNumJacEvals(mem, &v), rr->jac += v;
        IDAGetNumLinSolvSetups(mem, &v), rr->factors += v;
        IDAGetNumResEvals(mem, &v), rr->res += v;
        if (r < 0) {
            snprintf(msg, msz, "IDASolve returned %d at t = %g", r, t);
            goto done;
        }
        if (b < p->nbreakpoints) IDAReInit(mem, t, yy, yp);
    }
    r = 0;
    for (int i = 0; i < n; i++)
        y[i] = NV_Ith_S(yy, i);
done:
    IDAFree(&mem);
    SUNLinSolFree(LS);
    SUNMatDestroy(A);
    N_VDestroy(yy);
    N_VDestroy(yp);
    N_VDestroy(id);
    bench_ida_ctx_free(&c);
    bp_instance_free(&in);
    SUNContext_Free(&ctx);
    return r;
}

static void timed(int which, const bp_problem *p, double rtol, double atol, ls_kind ls,
                  int suppress, int reps, run_result *rr, char *msg, size_t msz)
{
    double *ts = malloc((size_t)reps * sizeof *ts);
    for (int k = -1; k < reps; k++) { /* k = -1: warm-up */
        double t0 = bench_cpu_now();
        rr->status = which ? run_ida(p, rtol, atol, suppress, rr->y, rr, msg, msz)
                           : run_ours(p, rtol, atol, ls, rr->y, rr, msg, msz);
        double t1 = bench_cpu_now();
        if (k >= 0) ts[k] = t1 - t0;
        if (rr->status < 0) {
            reps = k + 1 > 0 ? k + 1 : 1;
            if (k < 0) ts[0] = t1 - t0;
            break;
        }
    }
    rr->tmed = bench_median(ts, reps);
    rr->tmin = ts[0];
    free(ts);
}

int main(int argc, char **argv)
{
    const char *names[16];
    int np = 0, reps = 5, suppress = 1, csv = 0;
    double afac = 1e-2;
    ls_kind ls = LS_KLU;
    double rtols[16] = {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
    int nr = 7;
    for (int a = 1; a < argc; a++) {
        if (!strcmp(argv[a], "--problem") && a + 1 < argc && np < 16)
            names[np++] = argv[++a];
        else if (!strcmp(argv[a], "--reps") && a + 1 < argc)
            reps = atoi(argv[++a]);
        else if (!strcmp(argv[a], "--atol-factor") && a + 1 < argc)
            afac = atof(argv[++a]);
        else if (!strcmp(argv[a], "--linsol") && a + 1 < argc) {
            a++;
            if (!strcmp(argv[a], "dense"))
                ls = LS_DENSE;
            else if (strcmp(argv[a], "klu")) {
                fprintf(stderr, "ida_compare: --linsol takes klu or dense, not '%s'\n", argv[a]);
                return 2;
            }
        } else if (!strcmp(argv[a], "--no-suppress"))
            suppress = 0;
        else if (!strcmp(argv[a], "--csv"))
            csv = 1;
        else if (!strcmp(argv[a], "--rtol") && a + 1 < argc) {
            nr = 0;
            for (char *tok = strtok(argv[++a], ","); tok && nr < 16; tok = strtok(NULL, ","))
                rtols[nr++] = atof(tok);
        } else {
            fprintf(stderr,
                    "ida_compare: unknown argument '%s'\nusage: ida_compare [--problem NAME]... "
                    "[--reps R] [--atol-factor F] [--linsol klu|dense] [--no-suppress] [--csv] "
                    "[--rtol r1,r2,...]\n",
                    argv[a]);
            return 2;
        }
    }
    if (reps < 1 || nr < 1) {
        fprintf(stderr, "ida_compare: --reps and --rtol need positive values\n");
        return 2;
    }
    if (np == 0) {
        names[np++] = "ap102";
        names[np++] = "pendulum2";
    }
    if (csv)
        printf("problem,solver,rtol,atol,status,steps,rejected,jac,factors,res,cpu_median_s,"
               "cpu_min_s,scd,mescd,scd_i2,mescd_i2\n");
    int bad = 0;
    for (int q = 0; q < np; q++) {
        const bp_problem *p = bp_find(names[q]);
        if (!p) {
            fprintf(stderr, "ida_compare: unknown problem '%s'\n", names[q]);
            return 2;
        }
        if (p->n > 64) {
            fprintf(stderr, "ida_compare: problem '%s' too large for this program\n", names[q]);
            return 2;
        }
        double yref[64];
        bp_reference(p, yref);
        if (!csv)
            printf("\n%s (n = %d), atol = %g * rtol, IDA %s, medians of %d runs\n"
                   "%-6s %7s | %6s %5s %5s %6s %6s %9s %6s %6s | %6s %5s %5s %6s %6s %9s %6s "
                   "%6s | %6s\n",
                   p->name, p->n, afac,
                   suppress ? "id + suppressed algebraic error" : "no suppression", reps, "",
                   "rtol", "steps", "rej", "jac", "fact", "res", "cpu ms", "scd", "scd2", "steps",
                   "rej", "jac", "fact", "res", "cpu ms", "scd", "scd2", "time");
        for (int k = 0; k < nr; k++) {
            double rtol = rtols[k], atol = afac * rtol;
            run_result a = {0}, b = {0};
            char ma[BG_MESSAGE_SIZE] = "", mb[BG_MESSAGE_SIZE] = "";
            timed(0, p, rtol, atol, ls, suppress, reps, &a, ma, sizeof ma);
            timed(1, p, rtol, atol, ls, suppress, reps, &b, mb, sizeof mb);
            bp_score sa, sb;
            bp_score_compute(p, a.y, yref, rtol, atol, &sa);
            bp_score_compute(p, b.y, yref, rtol, atol, &sb);
            if (a.status < 0) fprintf(stderr, "ours, %s rtol %g: %s\n", p->name, rtol, ma), bad = 1;
            if (b.status < 0) fprintf(stderr, "IDA, %s rtol %g: %s\n", p->name, rtol, mb);
            if (csv) {
                printf("%s,bgdae,%g,%g,%d,%ld,%ld,%ld,%ld,%ld,%.6g,%.6g,%.3f,%.3f,%.3f,%.3f\n",
                       p->name, rtol, atol, a.status, a.steps, a.rejected, a.jac, a.factors, a.res,
                       a.tmed, a.tmin, sa.scd, sa.mescd, sa.scd_i2, sa.mescd_i2);
                printf("%s,ida,%g,%g,%d,%ld,%ld,%ld,%ld,%ld,%.6g,%.6g,%.3f,%.3f,%.3f,%.3f\n",
                       p->name, rtol, atol, b.status, b.steps, b.rejected, b.jac, b.factors, b.res,
                       b.tmed, b.tmin, sb.scd, sb.mescd, sb.scd_i2, sb.mescd_i2);
            } else {
                printf("%-6s %7.0e | %6ld %5ld %5ld %6ld %6ld %9.3f %6.2f %6.2f | %6ld %5ld %5ld "
                       "%6ld %6ld %9.3f %6.2f %6.2f | %6.2f\n",
                       "", rtol, a.steps, a.rejected, a.jac, a.factors, a.res, 1e3 * a.tmed, sa.scd,
                       sa.scd_i2, b.steps, b.rejected, b.jac, b.factors, b.res, 1e3 * b.tmed,
                       sb.scd, sb.scd_i2, b.tmed > 0 ? a.tmed / b.tmed : NAN);
            }
        }
        if (!csv)
            printf("left block: bgdae; right block: IDA; time = bgdae / IDA CPU time (median)\n");
    }
    return bad;
}
