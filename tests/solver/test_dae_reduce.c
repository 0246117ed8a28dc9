/* Index reduction of the constraints (options.index2 = DAE_I2_REDUCE, solver/dae_reduce.c).
 *
 * The example of Brenan, Campbell and Petzold (Numerical Solution of IVPs in DAEs, Section 3.2):
 *   y1 + eta t y2 = sin t,  y1' + eta t y2' + (1 + eta) y2 = 0,
 * exact y2 = -cos t, y1 = sin t + eta t cos t. BDF on this index-2 system, which is not of
 * Hessenberg form, is unstable at every step for eta < -1/2 (BDF1) and eta < -1/4 (BDF2).
 * Asserted, against the closed form at t = 3, for eta = -0.3 and -0.8:
 *   - with the reduction, the global error of both unknowns within 10 tolerances at rtol 1e-4,
 *     1e-6, 1e-8, 1e-10 (atol = rtol / 100), with kinds and patterns given, with an analytic
 *     Jacobian, and from the residual alone (no kinds, no patterns, no Jacobian);
 *   - without it, the run stops and its message names the policy that solves it;
 *   - the pendulum of the collection (Hessenberg) with the reduction: scd against its reference
 *     within 1 digit of the direct index-2 run's at rtol 1e-4 .. 1e-8, one constraint reduced,
 *     the drift before projection below the tolerance scale;
 *   - a step that lands on a breakpoint of a problem with position constraints restarts there
 *     (the projection's status once replaced the landing's, and the next step had h = 0);
 *   - an event function of the problem gets the problem's user pointer and its root (y2 = 0
 *     at pi/2) is found;
 *   - the policy's argument checks: no position constraints of the problem's own, and a
 *     problem without index-2 constraints is refused with a message;
 *   - consistent values given to a reduced pendulum are kept without a warning, and its
 *     multiplier found (closed form). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bg_dae.h"
#include "bg_sparse.h"
#include "problems.h"
#include "tap.h"

static int bcp_res(void *u, double t, const double *y, const double *yp, double *F)
{
    double eta = *(const double *)u;
    F[0] = y[0] + eta * t * y[1] - sin(t);
    F[1] = yp[0] + eta * t * yp[1] + (1 + eta) * y[1];
    return 0;
}

/* dF/dy = [1, eta t; 0, 1 + eta], dF/dy' = [0, 0; 1, eta t] on the full patterns */
static int bcp_jac(void *u, double t, const double *y, const double *yp, sp_csc *Jy, sp_csc *Jyp)
{
    (void)y, (void)yp;
    double eta = *(const double *)u;
    const double vy[4] = {1, 0, eta * t, 1 + eta}, vyp[4] = {0, 1, 0, eta * t};
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            int p = sp_csc_find(Jy, i, j), q = sp_csc_find(Jyp, i, j);
            if (p >= 0) Jy->val[p] = vy[2 * j + i];
            if (q >= 0) Jyp->val[q] = vyp[2 * j + i];
        }
    return 0;
}

enum { GIVEN, ANALYTIC, RESIDUAL_ONLY };

/* The problem with its kinds and patterns (dF/dy full, dF/dy' the second row), *eta its user
 * data; the patterns are the caller's to free. */
static dae_problem bcp_problem(double *eta, sp_csc **jy, sp_csc **jyp)
{
    static const int kind[2] = {DAE_DIFF, DAE_ALG2};
    const double full[4] = {1, 1, 1, 1}, rowtwo[4] = {0, 1, 0, 1};
    *jy = sp_csc_from_dense(2, 2, full, 0.0);
    *jyp = sp_csc_from_dense(2, 2, rowtwo, 0.0);
    dae_problem p = {0};
    p.n = 2;
    p.res = bcp_res;
    p.user = eta;
    p.kind = kind;
    p.jac_y_pattern = *jy;
    p.jac_yp_pattern = *jyp;
    return p;
}

typedef struct outcome {
    int rc;
    double e1, e2, tol1, tol2; /* errors at t = 3 and the tolerances there */
    long steps, reduced;
    char msg[BG_MESSAGE_SIZE];
} outcome;

static outcome bcp_run(double eta, double rtol, int info, int policy)
{
    outcome out = {0};
    sp_csc *jy, *jyp;
    dae_problem p = bcp_problem(&eta, &jy, &jyp);
    if (info == RESIDUAL_ONLY) {
        p.kind = NULL;
        p.jac_y_pattern = p.jac_yp_pattern = NULL;
    }
    if (info == ANALYTIC) p.jac = bcp_jac;
    dae_options o;
    dae_options_default(&o);
    o.rtol = rtol;
    o.atol = 1e-2 * rtol;
    o.max_steps = 200000;
    o.index2 = policy;
    bg_error err = {0};
    dae_solver *s = dae_create(&p, &o, &err);
    double y[2] = {0, -1}, yp[2] = {1 + eta, 0}, t = 0;
    out.rc = s ? dae_init(s, 0, y, yp) : err.status;
    if (out.rc == 0) out.rc = dae_solve_to(s, 3.0, &t, y, yp);
    double y1 = sin(3.0) + eta * 3 * cos(3.0), y2 = -cos(3.0);
    out.e1 = t == 3.0 ? fabs(y[0] - y1) : INFINITY;
    out.e2 = t == 3.0 ? fabs(y[1] - y2) : INFINITY;
    out.tol1 = rtol * fabs(y1) + o.atol;
    out.tol2 = rtol * fabs(y2) + o.atol;
    if (s) {
        out.steps = dae_get_stats(s)->steps;
        out.reduced = dae_get_stats(s)->reduced_rows;
    }
    snprintf(out.msg, sizeof out.msg, "%s", s ? dae_get_error(s)->message : err.message);
    dae_free(&s);
    sp_csc_free(&jy);
    sp_csc_free(&jyp);
    return out;
}

static void test_bcp(void)
{
    const double etas[2] = {-0.3, -0.8}, rtols[4] = {1e-4, 1e-6, 1e-8, 1e-10};
    const char *how[3] = {"kinds and patterns given", "analytic Jacobian", "residual only"};
    for (int e = 0; e < 2; e++) {
        for (int info = 0; info < 3; info++)
            for (int k = 0; k < 4; k++) {
                if (info == ANALYTIC && k != 1) continue;
                outcome o = bcp_run(etas[e], rtols[k], info, DAE_I2_REDUCE);
                tap_ok(o.rc == 0 && o.e1 <= 10 * o.tol1 && o.e2 <= 10 * o.tol2 && o.reduced == 1,
                       "BCP eta %g, rtol %g, %s, reduced: errors %.2g and %.2g at t = 3 "
                       "(tolerances %.2g, %.2g), %ld steps%s%s",
                       etas[e], rtols[k], how[info], o.e1, o.e2, o.tol1, o.tol2, o.steps,
                       o.rc ? ": " : "", o.rc ? o.msg : "");
            }
        for (int info = 0; info < 3; info += 2) {
            outcome o = bcp_run(etas[e], 1e-6, info, DAE_I2_EXCLUDE);
            tap_ok(o.rc < 0 && strstr(o.msg, "DAE_I2_REDUCE"),
                   "BCP eta %g, rtol 1e-6, %s, direct index 2: stops naming the reduction (%s)",
                   etas[e], how[info], o.rc < 0 ? o.msg : "it did not stop");
        }
    }
}

/* The pendulum (bench/problems.c): scd at tend with the policy given, its position constraint
 * dropped for the reduction (which brings its own); breakpoint: one in the middle. */
static double pendulum(int policy, double rtol, double breakpoint, long *reduced, double *drift,
                       int *rc)
{
    const bp_problem *bp = bp_find("pendulum2");
    bp_instance in = {0};
    bp_instance_init(&in, bp);
    dae_problem dp = in.dp;
    if (policy == DAE_I2_REDUCE) {
        dp.ncons = 0;
        dp.cons = NULL;
        dp.cons_pattern = NULL;
    }
    dae_options o;
    dae_options_default(&o);
    o.rtol = o.atol = rtol;
    o.index2 = policy;
    o.max_steps = 100000;
    if (breakpoint > 0) {
        o.breakpoints = &breakpoint;
        o.nbreakpoints = 1;
        o.projection = 1;
    }
    bg_error e = {0};
    dae_solver *s = dae_create(&dp, &o, &e);
    double y[16] = {0}, yr[16] = {0}, t;
    *rc = s ? dae_init(s, bp->t0, bp->y0, bp->yp0) : e.status;
    if (*rc == 0) *rc = dae_solve_to(s, bp->tend, &t, y, NULL);
    double scd = NAN;
    if (*rc >= 0) {
        bp_score sc;
        bp_reference(bp, yr);
        bp_score_compute(bp, y, yr, rtol, rtol, &sc);
        scd = sc.scd;
    }
    if (s) {
        *reduced = dae_get_stats(s)->reduced_rows;
        *drift = dae_get_stats(s)->max_drift;
        if (*rc < 0) tap_diag("pendulum: %s", dae_get_error(s)->message);
    }
    dae_free(&s);
    bp_instance_free(&in);
    return scd;
}

static void test_pendulum(void)
{
    const double rtols[3] = {1e-4, 1e-6, 1e-8};
    for (int k = 0; k < 3; k++) {
        long red = 0, red0 = 0;
        double drift = NAN, drift0 = NAN;
        int rc, rc0;
        double sr = pendulum(DAE_I2_REDUCE, rtols[k], 0, &red, &drift, &rc);
        double s0 = pendulum(DAE_I2_EXCLUDE, rtols[k], 0, &red0, &drift0, &rc0);
        tap_ok(rc == 0 && rc0 == 0 && sr >= s0 - 1 && red == 1 && drift < 100 * rtols[k],
               "pendulum rtol %g reduced: scd %.2f (direct index 2: %.2f), %ld row reduced, drift "
               "before projection %.2g",
               rtols[k], sr, s0, red, drift);
    }
    long red;
    double drift;
    int rc;
    double sc = pendulum(DAE_I2_EXCLUDE, 1e-6, 0.5 * bp_find("pendulum2")->tend, &red, &drift, &rc);
    tap_ok(rc == 0 && sc > 3,
           "pendulum with its constraint projected and a breakpoint halfway: "
           "reaches tend (scd %.2f, status %d)",
           sc, rc);
}

/* y2 = -cos t changes sign at pi/2; the user pointer must be the problem's (eta). */
static int bcp_root(void *u, double t, const double *y, const double *yp, double *g)
{
    (void)t, (void)yp;
    if (*(const double *)u != -0.3) return -1;
    g[0] = y[1];
    return 0;
}

static void test_events(void)
{
    double eta = -0.3;
    sp_csc *jy, *jyp;
    dae_problem p = bcp_problem(&eta, &jy, &jyp);
    p.nroots = 1;
    p.roots = bcp_root;
    dae_options o;
    dae_options_default(&o);
    o.rtol = 1e-8;
    o.atol = 1e-10;
    o.index2 = DAE_I2_REDUCE;
    bg_error err = {0};
    dae_solver *s = dae_create(&p, &o, &err);
    double y[2] = {0, -1}, yp[2] = {1 + eta, 0}, t = 0;
    int r = s ? dae_init(s, 0, y, yp) : err.status;
    if (r == 0) r = dae_solve_to(s, 3.0, &t, y, yp);
    tap_ok(r == DAE_ROOT_RETURN && fabs(t - (2 * atan(1.0))) < 1e-6,
           "BCP reduced with an event function (its own user pointer): y2 = 0 found at t = %.10g "
           "(pi/2 = %.10g; status %d%s%s)",
           t, (2 * atan(1.0)), r, r < 0 ? ": " : "", r < 0 && s ? dae_get_error(s)->message : "");
    dae_free(&s);
    sp_csc_free(&jy);
    sp_csc_free(&jyp);
}

static int lin_res(void *u, double t, const double *y, const double *yp, double *F)
{
    (void)u, (void)t;
    F[0] = yp[0] + y[0];
    F[1] = y[1] - 2 * y[0];
    return 0;
}

static void test_arguments(void)
{
    dae_problem p = {0};
    p.n = 2;
    p.res = lin_res;
    dae_options o;
    dae_options_default(&o);
    o.index2 = DAE_I2_REDUCE;
    const double d1[4] = {1, 1, 0, 1}, d2[4] = {1, 0, 0, 0};
    sp_csc *jy = sp_csc_from_dense(2, 2, d1, 0.0), *jyp = sp_csc_from_dense(2, 2, d2, 0.0);
    p.jac_y_pattern = jy;
    p.jac_yp_pattern = jyp;
    bg_error e = {0};
    dae_solver *s = dae_create(&p, &o, &e);
    tap_ok(!s && e.status == BG_ERR_ARGUMENT && strstr(e.message, "no constraint"),
           "an index-1 problem with the reduction is refused: %s", e.message);
    dae_free(&s);
    const bp_problem *bp = bp_find("pendulum2");
    bp_instance in = {0};
    bp_instance_init(&in, bp);
    bg_error e2 = {0};
    s = dae_create(&in.dp, &o, &e2);
    tap_ok(!s && e2.status == BG_ERR_ARGUMENT && strstr(e2.message, "ncons"),
           "the reduction with the problem's own position constraints is refused: %s", e2.message);
    dae_free(&s);
    bp_instance_free(&in);
    sp_csc_free(&jy);
    sp_csc_free(&jyp);
}

/* A pendulum at velocity level (length 1, residual alone) from consistent positions and
 * velocities, the multiplier given as 0 ("not known"): with the reduction, dae_consistent_init
 * returns BG_OK without a warning and lam = v^2 - g y (closed form, unit mass and length).
 * Before, the outer solver compared the values found with the inner solver's unset guesses:
 * DAE_WARNING, "4 unknowns ended far from the values given ... y went from 0 to -0.877583". */
static int vpend_res(void *u, double t, const double *y, const double *yp, double *F)
{
    (void)u, (void)t;
    F[0] = yp[0] - y[2];
    F[1] = yp[1] - y[3];
    F[2] = yp[2] + y[4] * y[0];
    F[3] = yp[3] + y[4] * y[1] + 9.81;
    F[4] = y[0] * y[2] + y[1] * y[3];
    return 0;
}

static void test_consistent_given(void)
{
    static const char *const nm[5] = {"x", "y", "u", "v", "lam"};
    dae_problem p = {0};
    p.n = 5;
    p.res = vpend_res;
    p.names = nm;
    dae_options o;
    dae_options_default(&o);
    o.index2 = DAE_I2_REDUCE;
    bg_error e = {0};
    dae_solver *s = dae_create(&p, &o, &e);
    const double th = 0.5, y0[5] = {sin(th), -cos(th), cos(th), sin(th), 0};
    double y[5] = {0}, yp[5] = {0};
    int r = s ? dae_init(s, 0, y0, NULL) : e.status;
    if (r == 0) r = dae_consistent_init(s);
    if (r >= 0) dae_get_consistent(s, y, yp);
    const double lam = 1.0 + 9.81 * cos(th); /* u^2 + v^2 - g y */
    double dy = 0;
    for (int i = 0; i < 4; i++)
        dy = fmax(dy, fabs(y[i] - y0[i]));
    tap_ok(r == BG_OK && fabs(y[4] - lam) <= 1e-6 * lam && dy <= 1e-12,
           "reduction, consistent values given: BG_OK (%d), no warning (%s), lam %.10g (exact "
           "%.10g), positions and velocities kept (%.2g)",
           r, s ? dae_get_warning(s) : e.message, y[4], lam, dy);
    dae_free(&s);
}

int main(void)
{
    test_bcp();
    test_pendulum();
    test_events();
    test_arguments();
    test_consistent_given();
    return tap_done();
}
