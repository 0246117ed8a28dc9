/* The stability suite (bench_stab.h). */
#include "bench_stab.h"

#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "bench_case.h"
#include "bench_crane.h"
#include "bench_util.h"

/* ------------------------------------------------------- the BCP problem ---- */

/* Brenan, Campbell and Petzold (1996), sec. 3.2 (a linear time-varying index-2 system of Gear and
 * Petzold): y1 + eta t y2 = g(t), y1' + eta t y2' + (1 + eta) y2 = 0; exact y2 = -g',
 * y1 = g + eta t g'. BDF applied to it directly is unstable at every step for eta < -1/2 (BDF1)
 * and eta < -1/4 (BDF2); with the constraint differentiated (DAE_I2_REDUCE) it is index 1 and
 * solved at both eta. g = sin t here. */
static int bcp_res(void *u, double t, const double *y, const double *yp, double *F)
{
    double eta = *(const double *)u;
    F[0] = y[0] + eta * t * y[1] - sin(t);
    F[1] = yp[0] + eta * t * yp[1] + (1 + eta) * y[1];
    return 0;
}

static const int bcp_kind[2] = {DAE_DIFF, DAE_ALG2}; /* y2 = -g' is index 2 */

/* The BCP problem as a case over [0, 3] (finite-difference Jacobian on dense patterns; consistent
 * values from the exact solution: this system is not semi-explicit, dae_consistent_init does
 * not apply). */
static int bcp_case(bench_case *bc, double *eta, sp_csc **jy, sp_csc **jyp)
{
    static const double full[4] = {1, 1, 1, 1}, rowtwo[4] = {0, 1, 0, 1};
    memset(bc, 0, sizeof *bc);
    *jy = sp_csc_from_dense(2, 2, full, 0.0);
    *jyp = sp_csc_from_dense(2, 2, rowtwo, 0.0); /* y1' and y2' in row 2 */
    bc->n = 2;
    bc->tend = 3.0;
    bc->dp.n = 2;
    bc->dp.res = bcp_res;
    bc->dp.user = eta;
    bc->dp.kind = bcp_kind;
    bc->dp.jac_y_pattern = *jy;
    bc->dp.jac_yp_pattern = *jyp;
    bc->y0 = malloc(2 * sizeof(double));
    bc->yp0 = malloc(2 * sizeof(double));
    bc->ys = malloc(2 * sizeof(double));
    bc->yps = malloc(2 * sizeof(double));
    bc->yref = malloc(2 * sizeof(double));
    if (!*jy || !*jyp || !bc->y0 || !bc->yp0 || !bc->ys || !bc->yps || !bc->yref) return -1;
    bc->ys[1] = bc->y0[1] = -1.0;
    bc->ys[0] = bc->y0[0] = 0.0;
    bc->yps[0] = bc->yp0[0] = 1.0 + *eta;
    bc->yps[1] = bc->yp0[1] = 0.0;
    bc->yref[1] = -cos(bc->tend);
    bc->yref[0] = sin(bc->tend) + *eta * bc->tend * cos(bc->tend);
    bc->atol_factor = 1e-2;
    snprintf(bc->name, sizeof bc->name, "bcp");
    return 0;
}

/* ----------------------------------------------------------------- cases ---- */

enum {
    CR_NONE = 0,
    CR_PAPER, /* the paper scene, settled, built over ten horizons */
    CR_STIFF, /* boom E and G times 1000, geometric start, a fifth of the horizon */
    CR_E512,  /* 512 boom elements, geometric start, 1e-5 of the horizon (a few steps: the
                 factorizations of its 19 000 unknowns cost about a second each) */
    CR_LIGHT, /* load of 1 g, geometric start */
    CR_KINKS, /* the reference's corners inside the horizon, settled */
    CR_STEP,  /* the reference's rate stepped (ramp of 0.1 ms), settled */
    CR_NVARIANTS
};

enum { REF_PROBLEM, REF_TIGHT, REF_IDA, REF_NONE };

enum { START_GIVEN, START_OFF_MANIFOLD, START_SLACK_ROPE };

typedef struct stab_case {
    const char *name;
    const char *problem; /* collection problem, "bcp" or "crane" */
    int variant;         /* crane: CR_* */
    double rtol;
    double eta; /* bcp */
    int start;  /* START_*: off the manifold (the reference is then a tight run from the
                   same start, after consistent initialisation) */
    int no_breakpoints;
    double horizon; /* crane: multiple of the configured horizon */
    int ref;        /* REF_* */
    int in_quick;
    int reduce; /* options.index2 = DAE_I2_REDUCE */
} stab_case;

static const stab_case CASES[] = {
    {"pendulum rtol 1e-2", "pendulum2", 0, 1e-2, 0, 0, 0, 0, REF_PROBLEM, 1, 0},
    {"pendulum rtol 1e-12", "pendulum2", 0, 1e-12, 0, 0, 0, 0, REF_PROBLEM, 1, 0},
    {"robertson rtol 1e-2", "robertson", 0, 1e-2, 0, 0, 0, 0, REF_PROBLEM, 1, 0},
    {"robertson rtol 1e-12", "robertson", 0, 1e-12, 0, 0, 0, 0, REF_PROBLEM, 1, 0},
    {"vdp eps 1e-6 rtol 1e-2", "vdp_scaled", 0, 1e-2, 0, 0, 0, 0, REF_PROBLEM, 1, 0},
    {"vdp eps 1e-6 rtol 1e-12", "vdp_scaled", 0, 1e-12, 0, 0, 0, 0, REF_PROBLEM, 1, 0},
    {"hires rtol 1e-12", "hires", 0, 1e-12, 0, 0, 0, 0, REF_PROBLEM, 1, 0},
    {"ap102 rtol 1e-12", "ap102", 0, 1e-12, 0, 0, 0, 0, REF_PROBLEM, 1, 0},
    {"crank rtol 1e-2", "crank", 0, 1e-2, 0, 0, 0, 0, REF_PROBLEM, 1, 0},
    {"crank rtol 1e-12", "crank", 0, 1e-12, 0, 0, 0, 0, REF_PROBLEM, 1, 0},
    {"pump rtol 1e-2", "pump", 0, 1e-2, 0, 0, 0, 0, REF_PROBLEM, 1, 0},
    {"pump without breakpoints", "pump", 0, 1e-6, 0, 0, 1, 0, REF_PROBLEM, 1, 0},
    {"pendulum off the manifold", "pendulum2", 0, 1e-6, 0, START_OFF_MANIFOLD, 0, 0, REF_TIGHT, 1, 0},
    {"kinks without breakpoints", "kinks", 0, 1e-6, 0, 0, 1, 0, REF_PROBLEM, 1, 0},
    {"kinks with breakpoints", "kinks", 0, 1e-6, 0, 0, 0, 0, REF_PROBLEM, 1, 0},
    {"BCP index 2, eta = -0.3, direct (BDF2 unstable)", "bcp", 0, 1e-6, -0.3, 0, 0, 0, REF_PROBLEM,
     1, 0},
    {"BCP index 2, eta = -0.3, reduced", "bcp", 0, 1e-6, -0.3, 0, 0, 0, REF_PROBLEM, 1, 1},
    {"BCP index 2, eta = -0.8, direct (BDF unstable)", "bcp", 0, 1e-6, -0.8, 0, 0, 0, REF_PROBLEM,
     1, 0},
    {"BCP index 2, eta = -0.8, reduced", "bcp", 0, 1e-6, -0.8, 0, 0, 0, REF_PROBLEM, 1, 1},
    {"crane rtol 1e-2", "crane", CR_PAPER, 1e-2, 0, 0, 0, 1, REF_TIGHT, 1, 0},
    {"crane rtol 1e-12", "crane", CR_PAPER, 1e-12, 0, 0, 0, 1, REF_IDA, 1, 0},
    {"crane boom 1000x stiffer", "crane", CR_STIFF, 1e-6, 0, 0, 0, 0.2, REF_TIGHT, 1, 0},
    {"crane 512 boom elements", "crane", CR_E512, 1e-6, 0, 0, 0, 1e-5, REF_NONE, 0, 0},
    {"crane undamped boom, 10x horizon", "crane", CR_PAPER, 1e-6, 0, 0, 0, 10, REF_TIGHT, 1, 0},
    {"crane load of 1 g", "crane", CR_LIGHT, 1e-6, 0, 0, 0, 1, REF_TIGHT, 1, 0},
    {"crane rope going slack", "crane", CR_PAPER, 1e-6, 0, START_SLACK_ROPE, 0, 1, REF_TIGHT, 1, 0},
    {"crane reference kinks with breakpoints", "crane", CR_KINKS, 1e-6, 0, 0, 0, 1, REF_TIGHT, 1, 0},
    {"crane reference kinks without breakpoints", "crane", CR_KINKS, 1e-6, 0, 0, 1, 1, REF_TIGHT,
     1, 0},
    {"crane reference step", "crane", CR_STEP, 1e-6, 0, 0, 0, 1, REF_TIGHT, 1, 0},
    {"crane off the manifold", "crane", CR_PAPER, 1e-6, 0, START_OFF_MANIFOLD, 0, 1, REF_TIGHT, 1, 0},
};
#define NCASES ((int)(sizeof CASES / sizeof *CASES))

/* The crane variant's scene. */
static void variant_scene(int v, const stab_config *cfg, crane_scene *s, int *settle, double *tend)
{
    *s = *cfg->scene;
    s->boom_beta = 0; /* undamped boom modes, ties and rope (the paper neglects friction) */
    s->tie_beta = 0;
    s->rope_damping = 0;
    /* and the rest of paper-undamped's reading: massless ties, no lag of the pump, the
     * derivative on a rate filtered over 0.01 s (with the paper scene's derivative on the
     * measured acceleration, an index-2 input of the pump's actuator, rtol 1e-12 misses the IDA
     * reference by 2.5e3 tolerances on the line pressures, a finding for the solver; with the
     * ties' mass alone IDA's reference fails at the start) */
    s->tie_rho = 0;
    s->pump_servo_bw = 0;
    s->kd_filter = 0.01;
    double H = cfg->crane_horizon;
    *settle = 0;
    *tend = H;
    switch (v) {
    case CR_PAPER:
        *settle = s->static_start;
        *tend = 10 * H;
        break;
    case CR_STIFF:
        s->boom_E *= 1000;
        s->boom_G *= 1000;
        s->static_start = 0;
        *tend = 0.2 * H;
        break;
    case CR_E512:
        s->boom_elements = 512;
        s->static_start = 0;
        *tend = 1e-5 * H;
        break;
    case CR_LIGHT:
        s->load_mass = 1e-3;
        s->static_start = 0;
        break;
    case CR_KINKS: /* ramp up, plateau, ramp down inside the horizon */
        *settle = s->static_start;
        s->ref_t1 = 0.25 * H;
        s->ref_t2 = 0.5 * H;
        s->ref_t3 = 0.75 * H;
        break;
    case CR_STEP: /* the rate steps up to 0.5 rad/s within 0.1 ms and down again */
        *settle = s->static_start;
        s->ref_t1 = 1e-4;
        s->ref_t2 = 0.5 * H;
        s->ref_t3 = 0.5 * H + 1e-4;
        break;
    default:
        break;
    }
}

/* ---------------------------------------------------------------- results ---- */

typedef struct stab_result {
    char worst[120]; /* the unknown with the largest error */
    int status;
    long steps, rejected;
    int hi;
    double err, err_tight, drift, t, cpu;
    int tight_div; /* err_tight is the error of the run at rtol / tight_div */
    double bound;  /* "solved" up to this error in tolerances: 1000, 2000 against a reference
                      computed at the case's own tolerance (REF_IDA), whose global error may be
                      as large as the run's: the two may differ by both allowances */
    char msg[BG_MESSAGE_SIZE];
    char ref[200];
} stab_result;

/* Error in tolerances: max |y - yref| / (rtol |yref| + atol nominal_i) (nominal_i: the problem's
 * nominal magnitudes, dae_problem.nominal, as the solver weighs the unknowns; 1 without them)
 * over the differential unknowns (the
 * crane: its error test has the algebraic ones out) or the unknowns that are not index 2, of a
 * test-set problem those that the test set scores (docs/testset.md: crank's positions
 * y1..y7, whose undamped elastic velocities carry a global error that grows with the number of
 * steps, 5e4 tolerances at rtol 1e-12 in our run and in the convergence of our runs towards the
 * published MEBDFI reference alike). */
static double err_tol(const bench_case *bc, const double *y, const double *yref, double rtol,
                      double atol, int diff_only, char *worst, size_t wsz)
{
    double e = 0;
    int w = -1;
    const unsigned char *scored = bc->bp ? bc->bp->scored : NULL;
    for (int i = 0; i < bc->n; i++) {
        int k = bc->dp.kind ? bc->dp.kind[i] : DAE_DIFF;
        if (diff_only ? k != DAE_DIFF : k == DAE_ALG2) continue;
        if (scored && !scored[i]) continue;
        double a = bc->dp.nominal ? atol * bc->dp.nominal[i] : atol;
        double r = fabs(y[i] - yref[i]) / (rtol * fabs(yref[i]) + a);
        if (!(r <= e)) e = r, w = i;
    }
    if (w >= 0 && bc->dp.names && bc->dp.names[w])
        snprintf(worst, wsz, "%s = %.6g (reference %.6g)", bc->dp.names[w], y[w], yref[w]);
    else if (w >= 0)
        snprintf(worst, wsz, "y[%d] = %.6g (reference %.6g)", w, y[w], yref[w]);
    return e;
}

/* In the child: the case's run and its reference. */
static void run_case(const stab_case *sc, bench_case *bc, const double *y0, const double *yp0,
                     double crane_ref_rtol, stab_result *res)
{
    const solver_def *ours = bench_solver_find("bgdae-klu");
    run_out o, rr;
    if (bench_run_alloc(&o, bc->n) || bench_run_alloc(&rr, bc->n)) {
        res->status = BG_ERR_MEMORY;
        snprintf(res->msg, sizeof res->msg, "out of memory");
        return;
    }
    run_opts ro = {0};
    ro.rtol = sc->rtol;
    ro.tend = bc->tend;
    ro.y0 = y0;
    ro.yp0 = yp0;
    ro.consistent_init = sc->start != START_GIVEN;
    ro.no_breakpoints = sc->no_breakpoints;
    ro.track_drift = 1;
    ro.max_steps = 3000000;
    ro.reduce = sc->reduce;
    bench_run(bc, ours, &ro, &o);
    res->status = o.status;
    res->steps = o.steps;
    res->rejected = o.rejected;
    res->hi = o.max_order;
    res->drift = o.drift;
    res->t = o.t;
    res->cpu = o.cpu;
    res->err = res->err_tight = NAN;
    res->tight_div = 0;
    res->bound = 1000;
    snprintf(res->msg, sizeof res->msg, "%s", o.status < 0 ? o.msg : "");
    double atol;
    bench_case_atol(bc, sc->rtol, &atol, NULL);
    int crane = !strcmp(sc->problem, "crane");
    if (o.status >= 0) {
        const double *yref = NULL;
        run_opts rt = ro;
        rt.no_breakpoints = 0;
        rt.track_drift = 0;
        if (sc->ref == REF_PROBLEM) {
            yref = bc->yref;
            snprintf(res->ref, sizeof res->ref, "%s", bc->bp ? "published/exact" : "exact");
        } else if (sc->ref == REF_TIGHT || sc->ref == REF_IDA) {
            const solver_def *sd = ours;
            if (sc->ref == REF_TIGHT) {
                rt.rtol = crane ? crane_ref_rtol : 1e-11;
                snprintf(res->ref, sizeof res->ref, "bgdae-klu at rtol %g", rt.rtol);
            } else {
                sd = bench_solver_find("ida-klu");
#ifndef BENCH_HAVE_IDA
                sd = NULL;
#endif
                snprintf(res->ref, sizeof res->ref, "IDA-KLU at rtol %g", rt.rtol);
                if (ro.consistent_init) sd = NULL; /* IDA has no index-2 initialisation */
            }
            if (sd) {
                bench_run(bc, sd, &rt, &rr);
                const solver_def *ida = bench_solver_find("ida-klu");
#ifndef BENCH_HAVE_IDA
                ida = NULL;
#endif
                /* our tight run failed: IDA at the same tolerance, then both ten times looser
                 * (still a hundred times tighter than the case) */
                char m1[120];
                snprintf(m1, sizeof m1, "%.100s", rr.msg);
                for (int tries = 0; rr.status < 0 && sd == ours && tries < 3; tries++) {
                    const solver_def *alt = tries == 1 ? ours : ida;
                    if (tries >= 1) rt.rtol = 10 * (crane ? crane_ref_rtol : 1e-11);
                    if (!alt || rt.rtol > sc->rtol / 100) continue;
                    if (alt == ida && ro.consistent_init) continue; /* no index-2 init in IDA */
                    bench_run(bc, alt, &rt, &rr);
                    if (rr.status >= 0)
                        snprintf(res->ref, sizeof res->ref,
                                 "%s at rtol %g (bgdae-klu at %g failed: %.90s)",
                                 alt == ida ? "IDA-KLU" : "bgdae-klu", rt.rtol,
                                 crane ? crane_ref_rtol : 1e-11, m1);
                }
                if (rr.status < 0)
                    snprintf(res->ref, sizeof res->ref, "reference failed: %.150s", rr.msg);
                else
                    yref = rr.y;
            } else {
                snprintf(res->ref, sizeof res->ref, "none (IDA not built in)");
            }
        } else {
            snprintf(res->ref, sizeof res->ref, "none (too costly)");
        }
        if (yref)
            res->err = err_tol(bc, o.y, yref, sc->rtol, atol, crane, res->worst, sizeof res->worst);
        if (yref && sc->ref == REF_IDA && rt.rtol == sc->rtol) res->bound = 2000;
        /* above 1000 tolerances: is the error at least converging? The same run 100 times
         * tighter, its error in the original tolerances; if that run stops (a tighter
         * tolerance can make the steps crawl at a switch of the model that the looser run
         * stepped over: the crane's kinks without breakpoints at 1e-8), the run 10 times
         * tighter */
        for (int div = 100; yref && res->err > res->bound && sc->rtol >= 1e-11 && div >= 10;
             div /= 10) {
            run_opts r3 = ro;
            r3.rtol = sc->rtol / div;
            r3.track_drift = 0;
            run_out o3;
            int done = 0;
            if (bench_run_alloc(&o3, bc->n) == 0) {
                bench_run(bc, ours, &r3, &o3);
                char w[8];
                if (o3.status >= 0) {
                    res->err_tight = err_tol(bc, o3.y, yref, sc->rtol, atol, crane, w, sizeof w);
                    res->tight_div = div;
                    done = 1;
                }
            }
            bench_run_free(&o3);
            if (done) break;
        }
    }
    bench_run_free(&o);
    bench_run_free(&rr);
}

/* Runs the case in a child under the time limit; the outcome class into *how. */
static void run_isolated(const stab_case *sc, bench_case *bc, const double *y0, const double *yp0,
                         const stab_config *cfg, stab_result *res, const char **how)
{
    double limit = cfg->time_limit;
    memset(res, 0, sizeof *res);
    res->err = res->err_tight = res->drift = NAN;
    int fd[2];
    *how = "CRASHED";
    if (pipe(fd) != 0) {
        res->status = -1;
        snprintf(res->msg, sizeof res->msg, "pipe: %s", strerror(errno));
        return;
    }
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0) {
        close(fd[0]);
        close(fd[1]);
        res->status = -1;
        snprintf(res->msg, sizeof res->msg, "fork: %s", strerror(errno));
        return;
    }
    if (pid == 0) {
        close(fd[0]);
        alarm((unsigned)ceil(limit));
        stab_result r;
        memset(&r, 0, sizeof r);
        run_case(sc, bc, y0, yp0, cfg->quick ? 1e-9 : 1e-10, &r);
        const char *p = (const char *)&r;
        size_t left = sizeof r;
        while (left > 0) {
            ssize_t k = write(fd[1], p, left);
            if (k < 0 && errno == EINTR) continue;
            if (k <= 0) break;
            p += k;
            left -= (size_t)k;
        }
        _exit(0);
    }
    close(fd[1]);
    size_t got = 0;
    char *p = (char *)res;
    while (got < sizeof *res) {
        ssize_t k = read(fd[0], p + got, sizeof *res - got);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) break;
        got += (size_t)k;
    }
    close(fd[0]);
    int wst = 0;
    while (waitpid(pid, &wst, 0) < 0 && errno == EINTR)
        ;
    if (got == sizeof *res && WIFEXITED(wst) && WEXITSTATUS(wst) == 0) {
        *how = res->status < 0 ? "stopped with a diagnostic"
               : isnan(res->err)
                   ? (res->ref[0] == 'n' ? "solved (no reference)" : "solved (reference failed)")
               : res->err <= res->bound ? "solved"
               /* converging, but only from an error that is still a global error: above 1e4
                * tolerances a tighter run being right does not make this one right (a step
                * across an unannounced switch with the algebraic unknowns on its wrong side
                * ends 1e5 tolerances off and converges) */
               : res->err <= 1e4 && res->err_tight <= res->err / 10 ? "solved, converging"
                                                                    : "WRONG";
        return;
    }
    memset(res, 0, sizeof *res);
    res->err = res->err_tight = res->drift = NAN;
    res->status = -1;
    if (WIFSIGNALED(wst) && WTERMSIG(wst) == SIGALRM) {
        *how = "TIME LIMIT";
        snprintf(res->msg, sizeof res->msg, "not finished within %.0f s", limit);
    } else if (WIFSIGNALED(wst)) {
        snprintf(res->msg, sizeof res->msg, "killed by signal %d", WTERMSIG(wst));
    } else {
        snprintf(res->msg, sizeof res->msg, "exit status %d", WEXITSTATUS(wst));
    }
}

/* Velocities (last path component v or w) of the differential unknowns: off the velocity
 * constraints the crane's joints impose (they hold at velocity level). */
static void crane_off_manifold(const bench_case *bc, double *y)
{
    for (int i = 0; i < bc->n; i++) {
        if (bc->dp.kind[i] != DAE_DIFF || !bc->dp.names || !bc->dp.names[i]) continue;
        const char *s = strrchr(bc->dp.names[i], '/');
        s = s ? s + 1 : bc->dp.names[i];
        if ((s[0] == 'v' || s[0] == 'w') && s[1] >= '0' && s[1] <= '9' && s[2] == '\0')
            y[i] += 0.01 * (1 + i % 3);
    }
}

/* The load lifted 2 m above its settled position (the rope's end difference with it): the rope
 * hangs slack until the load has fallen back (its static stretch is about 1 m). */
static int crane_slack(const bench_case *bc, double *y, char *msg, size_t msz)
{
    bgr_model *m = bench_crane_model(bc);
    int xl = bgr_find_var(m, "crane/load/x2"), dr = bgr_find_var(m, "crane/rope/d2");
    if (xl < 0 || dr < 0) {
        snprintf(msg, msz, "no unknowns crane/load/x2 and crane/rope/d2 in the model");
        return -1;
    }
    y[xl] += 2.0;
    y[dr] += 2.0;
    return 0;
}

int bench_stability(const char *dir, FILE *rep, const stab_config *cfg, int *crashed)
{
    *crashed = 0;
    /* without its file the suite still runs: its section of the report is written */
    bench_file bf;
    FILE *f = bench_file_open(&bf, dir, "stability.csv") == 0 ? bf.f : NULL;
    if (f)
        fprintf(f, "case,outcome,status,t_reached,steps,highest_order,rejected,error_in_tolerances,"
                   "largest_error_at,error_tighter,tighter_by,drift,reference,cpu_s,message\n");
    fprintf(rep, "## Stability suite\n\n");
    fprintf(rep,
            "bgdae-klu; error = max |y - yref| / (rtol |yref| + atol) over the unknowns that are "
            "not index 2 (the crane: over the differential unknowns; its error test leaves the "
            "algebraic ones out; a test-set problem: over the components the test set scores, "
            "crank's positions y1..y7, as its undamped elastic velocities carry a global error "
            "that grows with the number of steps), against the reference named; drift = "
            "largest constraint "
            "violation seen (pendulum: |g| at position level; crane: the hinge mismatch in m, "
            "its joints hold at velocity level). Outcome: solved (error within 1000 "
            "tolerances); solved, converging (above, up to 1e4 tolerances, and the same run at "
            "rtol / 100, or at rtol / 10 where that one stops, cuts the error tenfold or more: "
            "its error is given in the original tolerances); stopped "
            "with a diagnostic (the solver's message); WRONG; CRASHED; TIME LIMIT. Crane cases: "
            "scene %s read as paper-undamped (no damping, massless ties, no lag of the pump, the "
            "derivative over a 0.01 s filter), horizon %g s unless stated (stiffer boom: a "
            "fifth; 512 elements: 1e-5 of it, no reference), rtol = atol, reference: our run at "
            "rtol %g from the same start (where it fails: IDA-KLU at that tolerance, then both ten "
            "times looser; rtol 1e-12: "
            "IDA-KLU at the same tolerance, whose own global error counts as the run's: solved "
            "up to 2000 tolerances there). Each case "
            "runs in a child process with a %.0f s limit.\n\n",
            cfg->scene->name, cfg->crane_horizon, cfg->quick ? 1e-9 : 1e-10, cfg->time_limit);
    fprintf(rep, "| case | outcome | steps | highest order | rejected | error (tolerances) | drift "
                 "| reference | CPU s |\n|---|---|---|---|---|---|---|---|---|\n");
    bench_case crane_cases[CR_NVARIANTS];
    int built[CR_NVARIANTS] = {0};
    char bmsg[CR_NVARIANTS][BG_MESSAGE_SIZE];
    memset(crane_cases, 0, sizeof crane_cases);
    int bad = 0;
    for (int c = 0; c < NCASES; c++) {
        const stab_case *sc = &CASES[c];
        if (cfg->quick && !sc->in_quick) continue;
        if (cfg->filter && !strstr(sc->name, cfg->filter)) continue;
        bench_case local, *bc = &local;
        double eta = sc->eta;
        sp_csc *jy = NULL, *jyp = NULL;
        char msg[BG_MESSAGE_SIZE] = "";
        int r = 0, is_crane = !strcmp(sc->problem, "crane");
        memset(&local, 0, sizeof local);
        double t0 = bench_wall_now();
        if (is_crane) {
            int v = sc->variant;
            if (!built[v]) {
                crane_scene s;
                int settle;
                double tend;
                variant_scene(v, cfg, &s, &settle, &tend);
                /* The suite's crane cases start from the damped settling run they were defined
                 * with. From the static start (the program's), "reference kinks with
                 * breakpoints" measures 1.16e4 tolerances against its limit of 1e4: its error is
                 * set at the breakpoint restarts (471 without breakpoints), where a change of
                 * 6e-13 in the PID's integral moves it between 8.4e3 and 1.16e4; that, not the
                 * start, is what this case has to show, and it is open. */
                if (settle) settle = BENCH_SETTLE_DAMPED;
                bmsg[v][0] = '\0';
                built[v] = bench_crane_case(&crane_cases[v], &s, settle, tend, "crane", bmsg[v],
                                            sizeof bmsg[v]) == 0
                               ? 1
                               : -1;
                if (built[v] > 0 &&
                    bench_case_start(&crane_cases[v], 1e-10, bmsg[v], sizeof bmsg[v]) != 0)
                    built[v] = -1;
            }
            if (built[v] < 0) {
                r = -1;
                snprintf(msg, sizeof msg, "%s", bmsg[v]);
            } else {
                bc = &crane_cases[v];
            }
        } else if (!strcmp(sc->problem, "bcp")) {
            r = bcp_case(&local, &eta, &jy, &jyp);
            if (r) snprintf(msg, sizeof msg, "out of memory");
        } else {
            const bp_problem *p = bp_find(sc->problem);
            r = p ? bench_case_from_problem(&local, p) : -1;
            if (r) snprintf(msg, sizeof msg, "problem %s: not available", sc->problem);
        }
        stab_result res;
        const char *how = "not run";
        memset(&res, 0, sizeof res);
        res.err = res.err_tight = res.drift = NAN;
        double *y0 = NULL, *yp0 = NULL;
        if (r == 0) {
            y0 = malloc((size_t)bc->n * sizeof *y0);
            yp0 = malloc((size_t)bc->n * sizeof *yp0);
            if (!y0 || !yp0) r = -1;
        }
        if (r == 0) {
            /* the collection's problems start from their consistent values; the crane from its
             * consistent start (computed once per variant) */
            memcpy(y0, is_crane ? bc->ys : bc->y0, (size_t)bc->n * sizeof *y0);
            memcpy(yp0, is_crane ? bc->yps : bc->yp0, (size_t)bc->n * sizeof *yp0);
            if (sc->start == START_OFF_MANIFOLD) {
                if (is_crane)
                    crane_off_manifold(bc, y0);
                else
                    for (int i = 0; i < bc->n && i < 4; i++)
                        y0[i] += 0.01 * (i + 1);
            } else if (sc->start == START_SLACK_ROPE) {
                r = crane_slack(bc, y0, msg, sizeof msg);
            }
        }
        double keep_tend = bc->tend;
        if (r == 0) {
            if (is_crane) bc->tend = sc->horizon * cfg->crane_horizon;
            run_isolated(sc, bc, y0, yp0, cfg, &res, &how);
            bc->tend = keep_tend;
        } else {
            res.status = -1;
            snprintf(res.msg, sizeof res.msg, "set-up failed: %s", msg);
            how = "set-up failed";
        }
        double wall = bench_wall_now() - t0;
        if (!strcmp(how, "WRONG") || !strcmp(how, "CRASHED") || !strcmp(how, "TIME LIMIT") ||
            !strcmp(how, "set-up failed"))
            bad++;
        if (!strcmp(how, "CRASHED")) ++*crashed;
        fprintf(stderr, "stability: %-44s %s%s%s (%.1f s)\n", sc->name, how, res.msg[0] ? ": " : "",
                res.msg, wall);
        if (f)
            fprintf(
                f, "\"%s\",\"%s\",%d,%.9g,%ld,%d,%ld,%.3g,\"%s\",%.3g,%d,%.3g,\"%s\",%.3f,\"%s\"\n",
                sc->name, how, res.status, res.t, res.steps, res.hi, res.rejected, res.err,
                res.worst, res.err_tight, res.tight_div, res.drift, res.ref, res.cpu, res.msg);
        char et[64] = "";
        if (!isnan(res.err_tight))
            snprintf(et, sizeof et, " (%.3g at rtol / %d)", res.err_tight, res.tight_div);
        fprintf(rep, "| %s | %s%s%s | %ld | %d | %ld | %.3g%s | %.3g | %s | %.2f |\n", sc->name,
                how, res.msg[0] ? ": " : "", res.msg, res.steps, res.hi, res.rejected, res.err, et,
                res.drift, res.ref, res.cpu);
        free(y0);
        free(yp0);
        if (bc == &local) bench_case_free(&local);
        sp_csc_free(&jy);
        sp_csc_free(&jyp);
    }
    for (int v = 0; v < CR_NVARIANTS; v++)
        if (built[v] > 0) bench_case_free(&crane_cases[v]);
    fprintf(rep, "\n");
    if (f) bench_file_close(&bf);
    return bad;
}
