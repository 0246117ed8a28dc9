/* Error scales (dae_problem.nominal) and the Newton failure policy, against exact expectations.
 *
 * Nominal magnitudes. The absolute tolerance of unknown i is atol * nominal[i]: a run with
 * nominal magnitudes must be the run with atol_vec[i] = atol * nominal[i], step for step and to
 * the bit; an explicit atol_vec is taken as it is (the nominal magnitudes do not multiply it);
 * a nominal magnitude that is not finite and > 0 is refused with a message that names the
 * unknown. The problem: two decoupled decays of very different size,
 *     p' = -p, p(0) = 2e7 (a pressure in Pa),   x' = -2 x, x(0) = 1 (a position in m),
 * p(t) = 2e7 exp(-t), x(t) = exp(-2 t). With one atol of 1e-6 in SI units the pressure's
 * absolute tolerance is 1e-6 Pa; with nominal 1e7 it is 10 Pa, and once p has decayed to a few
 * Pa the steps are set by x alone: fewer steps, and p within its (scaled) tolerance of exact.
 *
 * Newton policy. A failure of the Newton iteration on a matrix from an earlier step is answered
 * by a fresh Jacobian at the same step (stats.newton_fails_stale), never by a smaller step; only
 * a failure on a matrix evaluated at the step cuts it (stats.newton_fails). The problem
 *     y' = -lambda(t) y,   lambda(t) = 1 + 4999 / (1 + exp(-(t - 1) / 0.01)),
 * stiffens 5000-fold within a few hundredths of a second around t = 1: the matrix of the steps
 * before no longer contracts there. y(t) = exp(-Lambda(t)), Lambda the integral of lambda:
 * Lambda(t) = t + 4999 * 0.01 * log((1 + exp((t - 1) / 0.01)) / (1 + exp(-100))).
 *
 * Newton matrix refresh. On y' = -y + sin(5 t), y(0) = 0, over [0, 10] at rtol 1e-4 and order
 * 1 (a constant Jacobian; the steps double and are cut by error-test failures), the counts of
 * Jacobian evaluations and of factorizations are predicted exactly from the step attempts
 * (cj = 1/h at order 1; an attempt is a run of residual evaluations at one t, rejected attempts
 * included): a Jacobian at the first attempt and whenever cj leaves [0.6, 1/0.6] of the cj it
 * was evaluated at; between, with options.newton_dgmax = 0.3, a refactorization of the saved
 * Jacobian whenever gamma = 1/cj moves more than 30 % from the one the matrix was factored
 * with, and none with newton_dgmax = 0. With options.newton_jac_age = 10 as well, the Jacobian
 * is evaluated at the first attempt and then at the first attempt of each step taken 10 or more
 * steps after the last evaluation, whatever cj does. All runs have the same largest error
 * (within a factor 1.5) against the closed form y = (sin 5t - 5 cos 5t + 5 exp(-t)) / 26.
 * With newton_jac_age the convergence rate carries from step to step: on the same problem at
 * orders 1..5 and rtol 1e-8 (cj changes at most steps) the attempts take 1.04 iterations on
 * average against 1.13 with newton_dgmax alone (each change of cj resets the rate there), and
 * y(10) stays within 5 tolerances.
 *
 * Landing on a stop. A step that would leave less than a quarter of itself to t_stop is replaced
 * by two equal steps, so the last step is at least a quarter of the one before (with a sliver,
 * a ratio of a few percent or less, alpha/h changes as much). Checked over 40 stop times on
 * y' = cos(t) - y. */
#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

#include "bg_dae.h"
#include "bg_sparse.h"
#include "tap.h"

static int res_decay(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user, (void)t;
    F[0] = yp[0] + y[0];
    F[1] = yp[1] + 2 * y[1];
    return 0;
}

typedef struct out {
    int status;
    long steps;
    double y[2];
    char msg[BG_MESSAGE_SIZE];
} out;

static out run_decay(const double *nominal, const double *atol_vec)
{
    out o = {0};
    static const char *const names[2] = {"line/p", "boom/x"};
    dae_problem p = {0};
    p.n = 2;
    p.res = res_decay;
    p.names = names;
    p.nominal = nominal;
    dae_options opt;
    dae_options_default(&opt);
    opt.rtol = 1e-6;
    opt.atol = 1e-6;
    opt.atol_vec = atol_vec;
    bg_error e = {0};
    dae_solver *s = dae_create(&p, &opt, &e);
    if (!s) {
        o.status = e.status;
        snprintf(o.msg, sizeof o.msg, "%s", e.message);
        return o;
    }
    const double y0[2] = {2e7, 1}, yp0[2] = {-2e7, -2};
    double t;
    dae_init(s, 0, y0, yp0);
    o.status = dae_solve_to(s, 20.0, &t, o.y, NULL);
    o.steps = dae_get_stats(s)->steps;
    dae_free(&s);
    return o;
}

#define LAMBDA_JUMP 4999.0
#define LAMBDA_W 0.01

static double Lambda(double t)
{
    double u = (t - 1) / LAMBDA_W;
    double sp = u > 0 ? u + log1p(exp(-u)) : log1p(exp(u)); /* log(1 + exp(u)) */
    return t + LAMBDA_JUMP * LAMBDA_W * (sp - log1p(exp(-1.0 / LAMBDA_W)));
}

static int res_smooth(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user;
    F[0] = yp[0] - cos(t) + y[0];
    return 0;
}

/* The smallest ratio of a last step to the one before, over 40 stop times. */
static double landing_ratio(double *worst_stop)
{
    double worst = INFINITY;
    for (int k = 0; k < 40; k++) {
        double ts = 1.0 + 0.0371 * k;
        dae_problem p = {0};
        p.n = 1;
        p.res = res_smooth;
        dae_options o;
        dae_options_default(&o);
        o.rtol = 1e-6;
        o.atol = 1e-8;
        o.has_t_stop = 1;
        o.t_stop = ts;
        bg_error e = {0};
        dae_solver *s = dae_create(&p, &o, &e);
        const double y0 = 0, yp0 = 1;
        double t = 0, y, hprev = 0, hlast = 0;
        dae_init(s, 0, &y0, &yp0);
        while (t < ts) {
            if (dae_step(s, ts, &t, &y, NULL) < 0) {
                worst = 0;
                break;
            }
            hprev = hlast;
            hlast = dae_get_stats(s)->h_last;
        }
        if (hprev > 0 && hlast / hprev < worst) {
            worst = hlast / hprev;
            *worst_stop = ts;
        }
        dae_free(&s);
    }
    return worst;
}

static int res_stiffen(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user;
    F[0] = yp[0] + (1 + LAMBDA_JUMP / (1 + exp(-(t - 1) / LAMBDA_W))) * y[0];
    return 0;
}

/* What the callbacks of test_refresh record (their user data). */
typedef struct calls {
    long n_jac;
    double *res_t; /* the times of the residual evaluations */
    long n_res, cap_res;
} calls;

#define W_FORCE 5.0

static int res_forced(void *user, double t, const double *y, const double *yp, double *F)
{
    calls *c = user;
    if (c->n_res < c->cap_res) c->res_t[c->n_res] = t;
    c->n_res++;
    F[0] = yp[0] + y[0] - sin(W_FORCE * t);
    return 0;
}

static int jac_forced(void *user, double t, const double *y, const double *yp, sp_csc *Jy,
                      sp_csc *Jyp)
{
    (void)t, (void)y, (void)yp;
    ((calls *)user)->n_jac++;
    Jy->val[0] = 1;
    Jyp->val[0] = 1;
    return 0;
}

/* y' = -y + sin(5 t) with its constant Jacobian, recording into c; the patterns go to *jy, *jyp
 * (the caller frees them). */
static dae_problem forced_problem(calls *c, sp_csc **jy, sp_csc **jyp)
{
    const double one = 1;
    *jy = sp_csc_from_dense(1, 1, &one, 0.0);
    *jyp = sp_csc_from_dense(1, 1, &one, 0.0);
    dae_problem p = {0};
    p.n = 1;
    p.res = res_forced;
    p.jac = jac_forced;
    p.jac_y_pattern = *jy;
    p.jac_yp_pattern = *jyp;
    p.user = c;
    return p;
}

/* Newton iterations per attempt on y' = -y + sin(5 t) over [0, 10] at rtol 1e-8, atol 1e-10,
 * orders 1..5 (cj changes at most steps), with newton_dgmax = dgmax and newton_jac_age = age;
 * *err: the error of y(10) in tolerances. */
static double iterations_per_step(double dgmax, int age, double *err)
{
    calls c = {0, NULL, 0, 0};
    sp_csc *jy, *jyp;
    dae_problem p = forced_problem(&c, &jy, &jyp);
    dae_options o;
    dae_options_default(&o);
    o.rtol = 1e-8;
    o.atol = 1e-10;
    o.newton_dgmax = dgmax;
    o.newton_jac_age = age;
    bg_error e = {0};
    dae_solver *s = dae_create(&p, &o, &e);
    const double y0 = 0, yp0 = 0;
    double t = 0, y = 0;
    int r = dae_init(s, 0, &y0, &yp0);
    if (r >= 0) r = dae_solve_to(s, 10, &t, &y, NULL);
    const dae_stats *st = dae_get_stats(s);
    double per = r >= 0 ? (double)st->newton_iters / (double)(st->steps + st->rejected_error) : NAN;
    double ye = (sin(50.0) - 5 * cos(50.0) + 5 * exp(-10.0)) / 26;
    *err = fabs(y - ye) / (1e-8 * fabs(ye) + 1e-10);
    tap_diag("newton_dgmax %g, newton_jac_age %d: %ld steps, %ld Newton iterations, y(10) off by "
             "%.3g tolerances",
             dgmax, age, st->steps, st->newton_iters, *err);
    dae_free(&s);
    sp_csc_free(&jy);
    sp_csc_free(&jyp);
    return per;
}

/* At order 1, cj = 1/h for every attempt, rejected ones included: each attempt is a run of
 * residual evaluations at one time t (its Newton iterations), its h is t less the last accepted
 * time before it. */
static double test_refresh(double dgmax, int age)
{
    enum { MAXSTEP = 20000 };
    calls c = {0, NULL, 0, 8 * MAXSTEP};
    c.res_t = malloc((size_t)c.cap_res * sizeof *c.res_t);
    sp_csc *jy, *jyp;
    dae_problem p = forced_problem(&c, &jy, &jyp);
    dae_options o;
    dae_options_default(&o);
    o.rtol = 1e-4;
    o.atol = 1e-6;
    o.max_order = 1;
    o.newton_dgmax = dgmax;
    o.newton_jac_age = age;
    bg_error e = {0};
    dae_solver *s = dae_create(&p, &o, &e);
    const double y0 = 0, yp0 = 0, tend = 10, w = W_FORCE;
    double t = 0, y = 0, maxerr = 0;
    double *acc = malloc(MAXSTEP * sizeof *acc);
    long *acc_res = malloc(MAXSTEP * sizeof *acc_res); /* residual evaluations before step i */
    long nacc = 0;
    int r = dae_init(s, 0, &y0, &yp0);
    while (r >= 0 && t < tend && nacc < MAXSTEP) {
        acc_res[nacc] = c.n_res;
        double t0 = t;
        r = dae_step(s, tend, &t, &y, NULL);
        acc[nacc++] = t0; /* the step's start */
        double ye = (sin(w * t) - w * cos(w * t) + w * exp(-t)) / (1 + w * w);
        maxerr = fmax(maxerr, fabs(y - ye) / (1e-4 * fabs(ye) + 1e-6));
    }
    /* the prediction over the attempts */
    long jac_pred = 0, fact_pred = 0, attempts = 0, ia = 0, jac_step = 0;
    double cjj = 0, cjf = 0, tprev = 0;
    for (long q = 0; q < c.n_res && q < c.cap_res; q++) {
        while (ia < nacc && acc_res[ia] <= q) /* the step this evaluation belongs to */
            tprev = acc[ia++];
        if (q > 0 && c.res_t[q] == c.res_t[q - 1]) continue; /* the same attempt */
        if (c.res_t[q] == tprev) continue; /* at the step's start: no attempt */
        double cj = 1.0 / (c.res_t[q] - tprev);
        attempts++;
        long steps = ia - 1; /* accepted before this attempt */
        int old = age > 0 ? steps - jac_step >= age : cj / cjj < 0.6 || cj / cjj > 1 / 0.6;
        if (cjj == 0 || old) {
            jac_pred++;
            fact_pred++;
            cjj = cjf = cj;
            jac_step = steps;
        } else if (dgmax > 0 && fabs(cjf / cj - 1) > dgmax) {
            fact_pred++;
            cjf = cj;
        }
    }
    const dae_stats *st = dae_get_stats(s);
    long fact = st->factor_full + st->factor_refactor;
    tap_ok(r >= 0 && t >= tend && st->newton_fails == 0 && st->newton_fails_stale == 0 &&
               c.n_res <= c.cap_res && st->rejected_error > 0,
           "refresh, newton_dgmax %g, newton_jac_age %d: t = %g reached without Newton failures "
           "(%ld steps, %ld rejected, %ld attempts, %ld and %ld Newton failures)",
           dgmax, age, tend, st->steps, st->rejected_error, attempts, st->newton_fails,
           st->newton_fails_stale);
    tap_ok(c.n_jac == jac_pred && st->jac_evals == jac_pred,
           "refresh, newton_dgmax %g, newton_jac_age %d: %ld Jacobians (%ld counted), as "
           "predicted from the attempts' cj and steps: %ld",
           dgmax, age, c.n_jac, st->jac_evals, jac_pred);
    tap_ok(fact == fact_pred && (dgmax == 0 ? fact == jac_pred : fact > jac_pred + 5),
           "refresh, newton_dgmax %g, newton_jac_age %d: %ld factorizations, as predicted: %ld "
           "(%ld of them of the saved Jacobian, where gamma moved by more than newton_dgmax)",
           dgmax, age, fact, fact_pred, fact - jac_pred);
    tap_diag("refresh, newton_dgmax %g, newton_jac_age %d: y within %.3g tolerances of the closed "
             "form",
             dgmax, age, maxerr);
    dae_free(&s);
    free(acc);
    free(acc_res);
    free(c.res_t);
    sp_csc_free(&jy);
    sp_csc_free(&jyp);
    return maxerr;
}

/* y' = 1 with the regime floor(y) (-1 from the callback past y = 4.5 when fail is set). */
static int res_ramp(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user, (void)t, (void)y;
    F[0] = yp[0] - 1;
    return 0;
}

static int regime_floor(void *user, double t, const double *y, int *r)
{
    (void)t;
    if (user && y[0] > 4.5) return -1;
    r[0] = (int)floor(y[0]);
    return 0;
}

/* The same ramp held by a constraint at index 2: x' = 1 + lambda, 0 = x - t (lambda = 0). */
static int res_ramp2(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user;
    F[0] = yp[0] - 1 - y[1];
    F[1] = y[0] - t;
    return 0;
}

/* Runs y' = 1 from 0 to 5.5 with steps of at most 0.25 (regimes: floor(y) or none; reduce: the
 * constrained ramp with index2 = DAE_I2_REDUCE): the status and the statistics into *st. */
static int run_ramp(int regimes, int fail, int reduce, dae_stats *st)
{
    dae_problem p = {0};
    p.n = 1;
    p.res = res_ramp;
    p.user = fail ? (void *)st : NULL;
    const double dy[4] = {0, 1, -1, 0}, dyp[4] = {1, 0, 0, 0}; /* column-major */
    sp_csc *jy = NULL, *jyp = NULL;
    if (reduce) {
        p.n = 2;
        p.res = res_ramp2;
        p.jac_y_pattern = jy = sp_csc_from_dense(2, 2, dy, 0.0);
        p.jac_yp_pattern = jyp = sp_csc_from_dense(2, 2, dyp, 0.0);
    }
    if (regimes) {
        p.nregimes = 1;
        p.regimes = regime_floor;
    }
    dae_options o;
    dae_options_default(&o);
    o.h_max = 0.25;
    if (reduce) o.index2 = DAE_I2_REDUCE;
    bg_error e = {0};
    dae_solver *s = dae_create(&p, &o, &e);
    double y0[2] = {0, 0}, yp0[2] = {1, 0}, t, y[2];
    int r = s ? dae_init(s, 0, y0, yp0) : -100;
    if (r == 0) r = dae_solve_to(s, 5.5, &t, y, NULL);
    if (s) *st = *dae_get_stats(s);
    dae_free(&s);
    sp_csc_free(&jy);
    sp_csc_free(&jyp);
    return r;
}

/* A regimes callback that returns *(int *)user (r = 0), and the ramp's analytic Jacobian
 * (dF/dy = 0, dF/dy' = 1). */
static int regime_status(void *user, double t, const double *y, int *r)
{
    (void)t, (void)y;
    r[0] = 0;
    return *(const int *)user;
}

static int jac_ramp(void *user, double t, const double *y, const double *yp, sp_csc *Jy,
                    sp_csc *Jyp)
{
    (void)user, (void)t, (void)y, (void)yp;
    for (int k = 0; k < Jy->nnz; k++)
        Jy->val[k] = 0;
    Jyp->val[0] = 1;
    return 0;
}

/* y' = 1 with a regimes callback returning status: consistent initialisation (init) or the
 * integration to t = 1, with an analytic Jacobian or differences. The status; the message
 * into msg. */
static int run_regime_status(int status, int with_jac, int init, char *msg, size_t size)
{
    dae_problem p = {0};
    p.n = 1;
    p.res = res_ramp;
    p.user = &status;
    p.nregimes = 1;
    p.regimes = regime_status;
    const double one = 1;
    sp_csc *jy = sp_csc_from_dense(1, 1, &one, 0.0), *jyp = sp_csc_from_dense(1, 1, &one, 0.0);
    if (with_jac) {
        p.jac = jac_ramp;
        p.jac_y_pattern = jy;
        p.jac_yp_pattern = jyp;
    }
    bg_error e = {0};
    dae_solver *s = dae_create(&p, NULL, &e);
    double y0 = 0, yp0 = 1, t, y;
    int r = s ? dae_init(s, 0, &y0, &yp0) : -100;
    if (r == 0) r = init ? dae_consistent_init(s) : dae_solve_to(s, 1, &t, &y, NULL);
    snprintf(msg, size, "%s", s ? dae_get_error(s)->message : e.message);
    dae_free(&s);
    sp_csc_free(&jy);
    sp_csc_free(&jyp);
    return r;
}

int main(void)
{
    /* nominal magnitudes = the matching atol vector, to the bit */
    const double nom[2] = {1e7, 1}, av[2] = {1e-6 * 1e7, 1e-6 * 1};
    out a = run_decay(nom, NULL), b = run_decay(NULL, av), c = run_decay(NULL, NULL);
    tap_ok(a.status == 0 && b.status == 0 && c.status == 0, "the decays reach t = 20 (%d, %d, %d)",
           a.status, b.status, c.status);
    tap_ok(a.steps == b.steps && a.y[0] == b.y[0] && a.y[1] == b.y[1],
           "nominal (1e7, 1) with atol 1e-6 is atol_vec (10, 1e-6): %ld and %ld steps, p(20) "
           "%.17g and %.17g",
           a.steps, b.steps, a.y[0], b.y[0]);
    tap_ok(a.steps < c.steps,
           "a pressure's tolerance of 10 Pa instead of 1e-6 Pa saves steps: %ld against %ld",
           a.steps, c.steps);
    double pe = 2e7 * exp(-20.0), xe = exp(-40.0);
    tap_ok(fabs(a.y[0] - pe) <= 10 * (1e-6 * fabs(pe) + 10) &&
               fabs(a.y[1] - xe) <= 10 * (1e-6 * fabs(xe) + 1e-6),
           "with nominal magnitudes p(20) = %.6g (exact %.6g, tolerance 10 Pa), x(20) = %.3g",
           a.y[0], pe, a.y[1]);
    /* an explicit atol vector is taken as it is */
    out d = run_decay(nom, av);
    tap_ok(d.status == 0 && d.steps == b.steps && d.y[0] == b.y[0],
           "atol_vec given: the nominal magnitudes do not multiply it (%ld and %ld steps)", d.steps,
           b.steps);
    /* bad nominal magnitudes */
    const double bad[3][2] = {{0, 1}, {1, NAN}, {-1, 1}};
    for (int k = 0; k < 3; k++) {
        out e = run_decay(bad[k], NULL);
        const char *who = k == 1 ? "boom/x" : "line/p";
        tap_ok(e.status == BG_ERR_ARGUMENT && strstr(e.msg, who) && strstr(e.msg, "nominal"),
               "nominal magnitude %g refused, naming %s: %s", k == 1 ? bad[k][1] : bad[k][0], who,
               e.msg);
    }

    /* the Newton policy */
    dae_problem p = {0};
    p.n = 1;
    p.res = res_stiffen;
    dae_options opt;
    dae_options_default(&opt);
    opt.rtol = 1e-6;
    opt.atol = 1e-10;
    bg_error e = {0};
    dae_solver *s = dae_create(&p, &opt, &e);
    const double y0 = 1, yp0 = -1;
    double t, y;
    dae_init(s, 0, &y0, &yp0);
    int r = dae_solve_to(s, 0.95, &t, &y, NULL);
    double ye = exp(-Lambda(0.95));
    tap_ok(r == 0 && fabs(y - ye) <= 10 * (1e-6 * ye + 1e-10),
           "stiffening decay: y(0.95) = %.10g, exact %.10g (status %d)", y, ye, r);
    r = dae_solve_to(s, 1.2, &t, &y, NULL);
    tap_ok(r == 0 && fabs(y) <= 10 * 1e-10, "y(1.2) = %.3g, exact %.3g (status %d)", y,
           exp(-Lambda(1.2)), r);
    const dae_stats *st = dae_get_stats(s);
    double wstop = 0, ratio = landing_ratio(&wstop);
    tap_ok(ratio >= 0.25, "landing on t_stop: the last step at least a quarter of the one before "
                          "(smallest ratio %.3g, t_stop = %g)",
           ratio, wstop);
    tap_ok(st->newton_fails_stale >= 1 && st->newton_fails == 0,
           "a Newton failure on an old matrix is answered by a fresh Jacobian, not a smaller step: "
           "%ld such failures, %ld failures on a current matrix, %ld Jacobians, %ld steps",
           st->newton_fails_stale, st->newton_fails, st->jac_evals, st->steps);
    dae_free(&s);
    double e0 = test_refresh(0, 0), e3 = test_refresh(0.3, 0), ea = test_refresh(0.3, 10);
    tap_ok(e3 <= 1.5 * e0 && e0 <= 1.5 * e3 && ea <= 1.5 * e0 && e0 <= 1.5 * ea,
           "refresh: the same accuracy with and without the refactorizations and the Jacobian's "
           "age rule (largest errors %.3g, %.3g and %.3g tolerances; BDF1's global error at rtol "
           "1e-4)",
           e0, e3, ea);
    double ye0, ye3, p0 = iterations_per_step(0.3, 0, &ye0),
                     p3 = iterations_per_step(0.3, 51, &ye3);
    tap_ok(p3 <= 1.08 && p0 >= 1.1 && ye0 <= 5 && ye3 <= 5,
           "the rate carried from step to step with newton_jac_age: %.3g Newton iterations per "
           "attempt at orders 1..5 (<= 1.08), against %.3g with the rate reset at each new cj "
           "(newton_dgmax alone, >= 1.1); y(10) within %.2g and %.2g tolerances (<= 5)",
           p3, p0, ye3, ye0);
    /* the age rule needs the refactorizations */
    {
        dae_problem q = {0};
        q.n = 1;
        q.res = res_stiffen;
        dae_options oq;
        dae_options_default(&oq);
        oq.newton_jac_age = 10;
        bg_error eq = {0};
        dae_solver *sq = dae_create(&q, &oq, &eq);
        tap_ok(!sq && eq.status == BG_ERR_ARGUMENT && strstr(eq.message, "newton_jac_age") &&
                   strstr(eq.message, "newton_dgmax"),
               "newton_jac_age without newton_dgmax refused: %s", eq.message);
        dae_free(&sq);
    }
    /* regimes: a fresh Jacobian at each change, once; none without them; a failing callback
     * stops the run; nregimes without a function refused */
    {
        dae_stats sa, sb, sc, sd;
        int ra = run_ramp(1, 0, 0, &sa), rb = run_ramp(0, 0, 0, &sb), rc = run_ramp(1, 1, 0, &sc);
        int rd = run_ramp(1, 0, 1, &sd);
        tap_ok(ra == 0 && rb == 0 && sa.jac_regime == 5 && sb.jac_regime == 0 &&
                   sa.jac_evals >= sb.jac_evals + 5,
               "y' = 1 to 5.5 with the regime floor(y): %ld Jacobians for a change of regime (the "
               "5 integers crossed), %ld Jacobians in all against %ld without regimes",
               sa.jac_regime, sa.jac_evals, sb.jac_evals);
        tap_ok(rc == DAE_CALLBACK_FAIL, "a regime callback that fails stops the run (status %d)",
               rc);
        tap_ok(rd == 0 && sd.jac_regime == 5,
               "with index2 = DAE_I2_REDUCE the callback gets the problem's own user pointer: "
               "status %d, %ld Jacobians for a change of regime",
               rd, sd.jac_regime);
        dae_problem q = {0};
        q.n = 1;
        q.res = res_ramp;
        q.nregimes = 2;
        bg_error eq = {0};
        dae_solver *sq = dae_create(&q, NULL, &eq);
        tap_ok(!sq && eq.status == BG_ERR_ARGUMENT && strstr(eq.message, "nregimes"),
               "nregimes without a regime function refused: %s", eq.message);
        dae_free(&sq);
    }
    /* what a regimes callback may return: 0 success, anything else fatal (bg_dae.h), with the
     * regimes callback named, in consistent initialisation and in the integration, with an
     * analytic Jacobian or differences (before: -1 was "the Jacobian function" or "the
     * residual function failed in the finite differences", +1 DAE_INIT_FAIL with no reason) */
    for (int k = 0; k < 8; k++) {
        int status = k & 1 ? 1 : -1, with_jac = (k >> 1) & 1, init = !((k >> 2) & 1);
        char msg[BG_MESSAGE_SIZE], want[64];
        int r = run_regime_status(status, with_jac, init, msg, sizeof msg);
        snprintf(want, sizeof want, "regimes callback (dae_problem.regimes) returned %d", status);
        tap_ok(r == DAE_CALLBACK_FAIL && strstr(msg, want) && !strstr(msg, "Jacobian function") &&
                   !strstr(msg, "residual function"),
               "a regimes callback returning %d stops %s (%s Jacobian) with DAE_CALLBACK_FAIL "
               "naming it: status %d, %s",
               status, init ? "dae_consistent_init" : "the integration",
               with_jac ? "analytic" : "difference", r, msg);
    }
    return tap_done();
}
