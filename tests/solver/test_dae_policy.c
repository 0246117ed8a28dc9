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
 * Landing on a stop. A step that would leave less than a quarter of itself to t_stop is replaced
 * by two equal steps, so the last step is at least a quarter of the one before (with a sliver,
 * a ratio of a few percent or less, alpha/h changes as much). Checked over 40 stop times on
 * y' = cos(t) - y. */
#include <math.h>
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
    return tap_done();
}
