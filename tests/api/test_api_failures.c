/* The diagnostics of solver failures: each kind of failure is provoked on a tiny problem and the
 * message (dae_get_error) must name the time and the unknown or the equation at fault, by the
 * problem's names, so that a failing model can be debugged from the message alone.
 *
 * The problems have two unknowns, "a.b.v" (v' = 1, differential) and "a.b.x", whose equation
 * (row 1) is the one that goes wrong:
 *   singular      0 = c(t) (x - 1), c = 0 from t = 0.5 on: the Newton matrix loses the column of
 *                 x (KLU and dense LU);
 *   convergence   0 = x^2 + 1 from t = 0.25 on: no real solution, the Newton corrections of x
 *                 grow;
 *   error test    0 = x - noise(t), noise a hash of t's bits: the local error of x is O(1)
 *                 whatever the step;
 *   step size     x' = -1e4 (x - cos t) from far off, with h_min = 1e-3: the step falls below
 *                 h_min (after error-test failures, or at once from the first-step rule);
 *   tolerance     rtol = 0, atol = 1e-300: below round-off for the largest weighted value, x;
 *   residual      row 1 NaN after t = 0.5 (status 0), marked NaN with a recoverable status,
 *                 a recoverable status without marking, a fatal status with marking;
 *   Jacobian      dF1/dx NaN after t = 0.5;
 *   initial       0 = x^2 + 1 cannot be satisfied by dae_consistent_init.
 * And through a bond graph: a source that turns NaN and a resistor with a vanishing slope, whose
 * messages give the compiler's hierarchical names of the equation and the unknown. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bg_dae.h"
#include "bgr_elements.h"
#include "bgr_model.h"
#include "tap.h"

static const char *const names[2] = {"a.b.v", "a.b.x"};
static const char *const eq_names[2] = {"a.b.v_rate", "a.b.x_balance"};

enum case_id {
    C_SINGULAR,
    C_CONV,
    C_NOISE,
    C_STIFF,
    C_NAN,
    C_MARKED,
    C_UNMARKED,
    C_FATAL,
    C_JACNAN
};

typedef struct prob {
    int kase;
    double t_bad; /* the failure sets in after this time */
} prob;

/* A hash of the bits of t in [-1, 1). */
static double noise(double t)
{
    uint64_t u;
    memcpy(&u, &t, sizeof u);
    u ^= u >> 33;
    u *= 0xff51afd7ed558ccdull;
    u ^= u >> 33;
    u *= 0xc4ceb9fe1a85ec53ull;
    u ^= u >> 33;
    return (double)(u >> 11) / 9007199254740992.0 * 2.0 - 1.0;
}

static int res(void *user, double t, const double *y, const double *yp, double *F)
{
    const prob *p = user;
    int bad = t > p->t_bad;
    F[0] = yp[0] - 1.0;
    switch (p->kase) {
    case C_SINGULAR:
        F[1] = (bad ? 0.0 : 1.0) * (y[1] - 1.0);
        break;
    case C_CONV:
        F[1] = t >= p->t_bad ? y[1] * y[1] + 1.0 : y[1] - 0.7;
        break;
    case C_NOISE:
        F[1] = y[1] - noise(t);
        break;
    case C_STIFF:
        F[1] = yp[1] + 1e4 * (y[1] - cos(t));
        break;
    case C_NAN:
        F[1] = bad ? NAN : y[1] - 1.0;
        break;
    case C_MARKED:
    case C_UNMARKED:
    case C_FATAL:
        F[1] = y[1] - 1.0;
        if (bad) {
            if (p->kase != C_UNMARKED) F[1] = NAN;
            return p->kase == C_FATAL ? -3 : 1;
        }
        break;
    case C_JACNAN:
        F[1] = y[1] - 1.0;
        break;
    }
    return 0;
}

/* dF/dy: (1,1); dF/dy': (0,0) and, for the stiff case, (1,1). */
static int jac(void *user, double t, const double *y, const double *yp, sp_csc *Jy, sp_csc *Jyp)
{
    (void)yp;
    const prob *p = user;
    double d = 1.0;
    if (p->kase == C_SINGULAR && t > p->t_bad) d = 0.0;
    if (p->kase == C_CONV && t >= p->t_bad) d = 2.0 * y[1];
    if (p->kase == C_STIFF) d = 1e4;
    if (p->kase == C_JACNAN && t > p->t_bad) d = NAN;
    Jy->val[0] = d;
    Jyp->val[0] = 1.0;
    if (p->kase == C_STIFF) Jyp->val[1] = 1.0;
    return 0;
}

typedef struct setup {
    sp_csc *Jy, *Jyp;
    dae_problem dp;
    prob pr;
    int kind[2];
} setup;

static void make(setup *S, int kase, double t_bad, int with_eq_names)
{
    memset(S, 0, sizeof *S);
    S->pr.kase = kase;
    S->pr.t_bad = t_bad;
    int stiff = kase == C_STIFF;
    sp_builder *b = sp_builder_create(2, 2, 1);
    sp_builder_add(b, 1, 1, 0.0);
    S->Jy = sp_builder_finish(b, NULL);
    sp_builder_free(&b);
    b = sp_builder_create(2, 2, 2);
    sp_builder_add(b, 0, 0, 0.0);
    if (stiff) sp_builder_add(b, 1, 1, 0.0);
    S->Jyp = sp_builder_finish(b, NULL);
    sp_builder_free(&b);
    S->kind[0] = DAE_DIFF;
    S->kind[1] = stiff ? DAE_DIFF : DAE_ALG;
    S->dp.n = 2;
    S->dp.res = res;
    S->dp.jac = jac;
    S->dp.jac_y_pattern = S->Jy;
    S->dp.jac_yp_pattern = S->Jyp;
    S->dp.kind = S->kind;
    S->dp.names = names;
    S->dp.eq_names = with_eq_names ? eq_names : NULL;
    S->dp.user = &S->pr;
}

static void unmake(setup *S)
{
    sp_csc_free(&S->Jy);
    sp_csc_free(&S->Jyp);
}

/* The first time in msg written "t = <number>"; NaN if none. */
static double time_in(const char *msg)
{
    const char *p = strstr(msg, "t = ");
    return p ? strtod(p + 4, NULL) : NAN;
}

static int has(const char *msg, const char *sub)
{
    return strstr(msg, sub) != NULL;
}

typedef struct outcome {
    int ret;
    double t;
    char msg[BG_MESSAGE_SIZE + 16];
} outcome;

/* Runs the problem from t0 (x0 given, v0 = t0, consistent init if asked) to tend. */
static outcome run(setup *S, const dae_options *o, double t0, double x0, double xp0, int consistent,
                   double tend)
{
    outcome r = {-1000, NAN, ""};
    bg_error e = {0};
    dae_solver *s = dae_create(&S->dp, o, &e);
    if (!s) {
        snprintf(r.msg, sizeof r.msg, "dae_create: %s", e.message);
        return r;
    }
    double y[2] = {t0, x0}, yp[2] = {1.0, xp0};
    r.ret = dae_init(s, t0, y, yp);
    if (r.ret == BG_OK && consistent) r.ret = dae_consistent_init(s);
    if (r.ret == BG_OK) r.ret = dae_solve_to(s, tend, &r.t, y, yp);
    snprintf(r.msg, sizeof r.msg, "%s", dae_get_error(s)->message);
    dae_free(&s);
    return r;
}

/* ret == want exactly, every sub in the message, the time in it within [tlo, thi]. */
static void check(const outcome *r, int want, double tlo, double thi, const char *what,
                  const char *sub1, const char *sub2)
{
    double t = time_in(r->msg);
    tap_diag("%s: %s, \"%s\"", what, dae_return_name(r->ret), r->msg);
    tap_ok(r->ret == want, "%s: returns %s (got %s)", what, dae_return_name(want),
           dae_return_name(r->ret));
    tap_ok(has(r->msg, sub1), "%s: the message names \"%s\"", what, sub1);
    if (sub2) tap_ok(has(r->msg, sub2), "%s: the message says \"%s\"", what, sub2);
    tap_ok(t >= tlo && t <= thi, "%s: the message gives the time (%.17g in [%g, %g])", what, t, tlo,
           thi);
}

static void test_singular(void)
{
    for (int k = 0; k < 2; k++) {
        const char *ln = k ? "dense" : "KLU";
        char what[96];
        setup S;
        dae_options o;
        dae_options_default(&o);
        o.linsol = k ? LS_DENSE : LS_KLU;
        /* singular from the start: every retry of the first step meets it */
        make(&S, C_SINGULAR, 0.4, 0);
        outcome r = run(&S, &o, 0.5, 1.0, 0.0, 0, 1.0);
        snprintf(what, sizeof what, "singular (%s) at t0 = 0.5", ln);
        check(&r, DAE_LSETUP_FAIL, 0.5, 0.5, what, "a.b.x", "singular");
        tap_ok(has(r.msg, "nothing determines a.b.x"),
               "%s: the message says that nothing determines a.b.x", what);
        /* singular from t = 0.5 on, met in the middle of the run */
        S.pr.t_bad = 0.5;
        r = run(&S, &o, 0.0, 1.0, 0.0, 0, 1.0);
        snprintf(what, sizeof what, "singular (%s) from t = 0.5", ln);
        tap_diag("%s: %s, \"%s\"", what, dae_return_name(r.ret), r.msg);
        double t = time_in(r.msg);
        tap_ok((r.ret == DAE_LSETUP_FAIL || r.ret == DAE_STEP_TOO_SMALL) &&
                   has(r.msg, "nothing determines a.b.x") && t > 0.45 && t <= 0.5 + 1e-12,
               "%s: %s names a.b.x and the time %.17g (just before 0.5)", what,
               dae_return_name(r.ret), t);
        unmake(&S);
    }
}

static void test_convergence(void)
{
    setup S;
    dae_options o;
    dae_options_default(&o);
    make(&S, C_CONV, 0.25, 0);
    outcome r = run(&S, &o, 0.25, 0.7, 0.0, 0, 1.0);
    check(&r, DAE_CONV_FAIL, 0.25, 0.25, "Newton convergence", "a.b.x",
          "largest weighted correction");
    tap_ok(!has(r.msg, "a.b.v"), "Newton convergence: the well-behaved a.b.v is not blamed");
    unmake(&S);
}

static void test_error_test(void)
{
    setup S;
    dae_options o;
    dae_options_default(&o);
    make(&S, C_NOISE, 0.0, 1);
    outcome r = run(&S, &o, 0.75, noise(0.75), 0.0, 0, 1.0);
    check(&r, DAE_ERR_FAIL, 0.75, 0.75, "error test", "a.b.x", "largest weighted local error");
    tap_ok(has(r.msg, "failed 10 times"), "error test: the message counts the failures");
    unmake(&S);
}

static void test_step_size(void)
{
    setup S;
    dae_options o;
    dae_options_default(&o);
    o.h_min = 1e-3;
    o.h_init = 1e-2;
    make(&S, C_STIFF, 0.0, 0);
    /* x starts at 0, far from cos t: error-test failures cut the step below h_min */
    outcome r = run(&S, &o, 0.125, 0.0, 0.0, 0, 1.0);
    check(&r, DAE_STEP_TOO_SMALL, 0.125, 0.125, "h_min after error-test failures", "a.b.x",
          "below the minimum");
    tap_ok(has(r.msg, "local error"), "h_min after error-test failures: the reason is given");
    /* chosen by the first-step rule, the first step is below h_min at once */
    o.h_init = 0.0;
    r = run(&S, &o, 0.125, 0.0, 1e4 * cos(0.125), 0, 1.0);
    check(&r, DAE_STEP_TOO_SMALL, 0.125, 0.125, "h_min below the first step", "a.b.x",
          "derivative");
    unmake(&S);

    /* a tolerance below round-off: the largest weighted value is x = 5 */
    dae_options_default(&o);
    o.rtol = 0.0;
    o.atol = 1e-300;
    make(&S, C_NAN, 10.0, 0);
    r = run(&S, &o, 0.375, 5.0, 0.0, 0, 1.0);
    check(&r, DAE_TOO_MUCH_ACC, 0.375, 0.375, "tolerance below round-off", "a.b.x", "round-off");
    unmake(&S);
}

static void test_residual(void)
{
    setup S;
    dae_options o;
    dae_options_default(&o);
    const double lo = 0.4, hi = 0.5 + 1e-9;

    make(&S, C_NAN, 0.5, 0);
    outcome r = run(&S, &o, 0.0, 1.0, 0.0, 0, 1.0);
    check(&r, DAE_RES_FAIL, lo, hi, "NaN residual (no equation names)",
          "equation 1 (the row of a.b.x)", "nan");
    unmake(&S);

    make(&S, C_NAN, 0.5, 1);
    r = run(&S, &o, 0.0, 1.0, 0.0, 0, 1.0);
    check(&r, DAE_RES_FAIL, lo, hi, "NaN residual (equation names)", "a.b.x_balance", "nan");
    tap_ok(!has(r.msg, "a.b.v_rate"), "NaN residual: the finite equation is not blamed");
    unmake(&S);

    make(&S, C_MARKED, 0.5, 1);
    r = run(&S, &o, 0.0, 1.0, 0.0, 0, 1.0);
    check(&r, DAE_RES_FAIL, lo, hi, "recoverable residual, row marked NaN", "a.b.x_balance",
          "recoverable status 1");
    unmake(&S);

    make(&S, C_UNMARKED, 0.5, 1);
    r = run(&S, &o, 0.0, 1.0, 0.0, 0, 1.0);
    check(&r, DAE_RES_FAIL, lo, hi, "recoverable residual, no row marked", "recoverable status 1",
          NULL);
    tap_ok(!has(r.msg, "a.b.x_balance") && !has(r.msg, "a.b.v_rate"),
           "recoverable residual, no row marked: no equation is blamed");
    unmake(&S);

    make(&S, C_FATAL, 0.5, 1);
    r = run(&S, &o, 0.0, 1.0, 0.0, 0, 1.0);
    check(&r, DAE_CALLBACK_FAIL, lo, hi, "fatal residual, row marked NaN", "a.b.x_balance",
          "fatal status -3");
    unmake(&S);

    make(&S, C_JACNAN, 0.5, 1);
    r = run(&S, &o, 0.0, 1.0, 0.0, 0, 1.0);
    check(&r, DAE_RES_FAIL, lo, hi, "NaN Jacobian entry", "d(a.b.x_balance)/d(a.b.x)", "Jacobian");
    unmake(&S);
}

static void test_initial(void)
{
    setup S;
    dae_options o;
    dae_options_default(&o);
    make(&S, C_CONV, 0.0, 1);
    outcome r = run(&S, &o, 0.625, 0.7, 0.0, 1, 1.0);
    tap_diag("consistent init: %s, \"%s\"", dae_return_name(r.ret), r.msg);
    double t = time_in(r.msg);
    tap_ok(r.ret == DAE_INIT_FAIL, "consistent init of 0 = x^2 + 1: DAE_INIT_FAIL (%s)",
           dae_return_name(r.ret));
    tap_ok(has(r.msg, "a.b.x_balance") || has(r.msg, "a.b.x "),
           "consistent init: the message names the equation or the unknown");
    tap_ok(fabs(t - 0.625) < 1e-12, "consistent init: the message gives the time (%.17g)", t);
    unmake(&S);
}

/* ---- through a bond graph: hierarchical names from the compiler ---- */

static double source_turns_nan(void *user, double t)
{
    (void)user;
    return t > 0.5 ? NAN : 1.0;
}

static double cubic(void *user, double f, double *dfdx)
{
    (void)user;
    *dfdx = 3.0 * f * f;
    return f * f * f;
}

/* circuit/drive: source S -> 1-junction J -> inductor L and resistor R (R linear, or cubic). */
static bgr_model *circuit(int cubic_r)
{
    bgr_model *m = bgr_model_create("circuit");
    bgr_comp c = bgr_component(m, 0, "drive");
    int S = bgr_Se_fn(m, c, "S", source_turns_nan, NULL);
    int J = bgr_one(m, c, "J", cubic_r ? 2 : 3, 1);
    int R = cubic_r ? bgr_R_fn(m, c, "R", cubic, NULL) : bgr_R(m, c, "R", 1, 1.0);
    bgr_bond(m, c, "b0", 1, bgr_port_of(m, S, 0), bgr_port_of(m, J, 0), NULL, NULL);
    bgr_bond(m, c, "b1", 1, bgr_port_of(m, J, 1), bgr_port_of(m, R, 0), NULL, NULL);
    if (!cubic_r) {
        int L = bgr_I(m, c, "L", 1, 1.0);
        bgr_bond(m, c, "b2", 1, bgr_port_of(m, J, 2), bgr_port_of(m, L, 0), NULL, NULL);
    }
    return m;
}

static void test_bondgraph(void)
{
    for (int k = 0; k < 2; k++) {
        bgr_model *m = circuit(k);
        int rc = bgr_compile(m);
        dae_problem p;
        if (rc == BG_OK) rc = bgr_dae_problem(m, &p);
        if (rc != BG_OK) {
            tap_ok(0, "bond graph %d: compiles (%s)", k, bgr_model_error(m)->message);
            bgr_model_free(&m);
            continue;
        }
        dae_options o;
        dae_options_default(&o);
        bg_error e = {0};
        dae_solver *s = dae_create(&p, &o, &e);
        double *y = bgr_y0(m), *yp = bgr_yp0(m), t = 0;
        rc = s ? dae_init(s, 0.0, y, yp) : -1000;
        if (k == 0) { /* the source turns NaN after t = 0.5 */
            if (rc == BG_OK) rc = dae_consistent_init(s);
            if (rc == BG_OK) rc = dae_solve_to(s, 1.0, &t, y, yp);
            const char *msg = s ? dae_get_error(s)->message : e.message;
            double tm = time_in(msg);
            tap_diag("bond graph, NaN source: %s, \"%s\"", dae_return_name(rc), msg);
            tap_ok(rc == DAE_RES_FAIL && has(msg, "circuit/drive/S/source") && tm > 0.4 &&
                       tm <= 0.5 + 1e-9,
                   "bond graph, NaN source: DAE_RES_FAIL names circuit/drive/S/source and the "
                   "time (%s, t = %.17g)",
                   dae_return_name(rc), tm);
        } else { /* e = f^3 with e = 1 at the start: the flow's column vanishes at f = 0 */
            if (rc == BG_OK) rc = dae_solve_to(s, 1.0, &t, y, yp);
            const char *msg = s ? dae_get_error(s)->message : e.message;
            tap_diag("bond graph, cubic resistor from f = 0: %s, \"%s\"", dae_return_name(rc), msg);
            tap_ok(rc == DAE_LSETUP_FAIL && has(msg, "circuit/drive/b1/f") && time_in(msg) == 0.0,
                   "bond graph, singular: DAE_LSETUP_FAIL names the unknown circuit/drive/b1/f "
                   "and t = 0 (%s)",
                   dae_return_name(rc));
        }
        dae_free(&s);
        bgr_model_free(&m);
    }
}

int main(void)
{
    test_singular();
    test_convergence();
    test_error_test();
    test_step_size();
    test_residual();
    test_initial();
    test_bondgraph();
    return tap_done();
}
